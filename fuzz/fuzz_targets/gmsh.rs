//! Feeds arbitrary bytes to the gmsh reader (the first byte picks the build options): it must
//! return Ok or Err, never panic, hang or exhaust memory. A file that reads and that the writer
//! accepts must read back with the same cell count; the binary 4.1 writer must give the same
//! complex and attributes as the ascii one, and the 2.2 writer the same complex.
#![no_main]
use libfuzzer_sys::fuzz_target;
use starplex::io::gmsh;
use starplex_fuzz::{options, round_trip, same};

fuzz_target!(|data: &[u8]| {
    let Some((&mode, text)) = data.split_first() else {
        return;
    };
    let opts = options(mode, false);
    let read = |b: &[u8], o: &_| gmsh::read_from(b, "fuzz.msh".as_ref(), o);
    if let Some((r, back)) = round_trip(text, &opts, read, gmsh::write) {
        assert_eq!(back.complex.n_cells(), r.complex.n_cells(), "round trip changed the cells");
        let mut out_bin = Vec::new();
        gmsh::write_binary(&mut out_bin, &r.complex).expect("binary accepts what ascii accepts");
        let back_bin = read(&out_bin, &opts).expect("a written binary file must read back");
        // (NaN-aware: items a $NodeData section does not cover are NaN)
        assert!(same(&back_bin.complex, &back.complex), "binary and ascii 4.1 round trips differ");
        let mut out22 = Vec::new();
        gmsh::write_22(&mut out22, &r.complex).expect("2.2 accepts what 4.1 accepts");
        let mut back22 = read(&out22, &opts).expect("a written 2.2 file must read back");
        // (the tags differ where 4.1 renumbers entities: compare the cells)
        let mut back41 = back;
        back22.complex.take_attributes();
        back41.complex.take_attributes();
        assert_eq!(back22.complex, back41.complex, "2.2 and 4.1 round trips differ");
    }
});
