//! Feeds arbitrary bytes to the vtk reader (the first byte picks the build options): it must
//! return Ok or Err, never panic, hang or exhaust memory. A file that reads and that the writer
//! accepts must read back with the same cell count, through the unstructured-grid writer and
//! (for edges, triangles and quads) the poly-data writer.
#![no_main]
use libfuzzer_sys::fuzz_target;
use starplex::io::vtk;
use starplex_fuzz::{options, round_trip};

fuzz_target!(|data: &[u8]| {
    let Some((&mode, text)) = data.split_first() else {
        return;
    };
    let opts = options(mode, false);
    let read = |b: &[u8], o: &_| vtk::read_from(b, "fuzz.vtk".as_ref(), o);
    if let Some((r, back)) = round_trip(text, &opts, read, vtk::write) {
        assert_eq!(back.complex.n_cells(), r.complex.n_cells(), "round trip changed the cells");
    }
    if let Some((r, back)) = round_trip(text, &opts, read, vtk::write_polydata) {
        assert_eq!(back.complex.n_cells(), r.complex.n_cells(), "poly data changed the cells");
        assert_eq!(back.complex.attributes().cell.len(), r.complex.attributes().cell.len());
    }
});
