//! Feeds arbitrary bytes to the gmsh reader (the first byte picks the build options): it must
//! return Ok or Err, never panic, hang or exhaust memory. A file that reads and that the writer
//! accepts must read back with the same cell count, and the 2.2 writer must give the same
//! complex as the 4.1 one.
#![no_main]
use libfuzzer_sys::fuzz_target;
use starplex::io::gmsh;
use starplex_fuzz::{options, round_trip};

fuzz_target!(|data: &[u8]| {
    let Some((&mode, text)) = data.split_first() else {
        return;
    };
    let opts = options(mode, false);
    let read = |b: &[u8], o: &_| gmsh::read_from(b, "fuzz.msh".as_ref(), o);
    if let Some((r, back)) = round_trip(text, &opts, read, gmsh::write) {
        assert_eq!(back.complex.n_cells(), r.complex.n_cells(), "round trip changed the cells");
        let mut out22 = Vec::new();
        gmsh::write_22(&mut out22, &r.complex).expect("2.2 accepts what 4.1 accepts");
        let back22 = read(&out22, &opts).expect("a written 2.2 file must read back");
        assert_eq!(back22.complex, back.complex, "2.2 and 4.1 round trips differ");
    }
});
