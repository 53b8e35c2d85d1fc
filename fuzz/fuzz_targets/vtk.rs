//! Feeds arbitrary bytes to the vtk reader (the first byte picks the build options): it must
//! return Ok or Err, never panic, hang or exhaust memory. A file that reads and that the writer
//! accepts must read back with the same cell count.
#![no_main]
use libfuzzer_sys::fuzz_target;
use starplex::io::vtk;
use starplex_fuzz::{options, round_trip};

fuzz_target!(|data: &[u8]| {
    let Some((&mode, text)) = data.split_first() else {
        return;
    };
    let read = |b: &[u8], o: &_| vtk::read_from(b, "fuzz.vtk".as_ref(), o);
    if let Some((r, back)) = round_trip(text, &options(mode, false), read, vtk::write) {
        assert_eq!(back.complex.n_cells(), r.complex.n_cells(), "round trip changed the cells");
    }
});
