//! Feeds arbitrary bytes to the gmsh reader (the first byte picks the build options): it must
//! return Ok or Err, never panic, hang or exhaust memory. A file that reads and that the writer
//! accepts must read back with the same vertex and cell counts.
#![no_main]
use libfuzzer_sys::fuzz_target;
use starplex::io::{gmsh, ReadOptions};

fuzz_target!(|data: &[u8]| {
    let Some((&mode, text)) = data.split_first() else {
        return;
    };
    let mut opts = ReadOptions::default();
    opts.build.drop_duplicates = mode & 2 == 2;
    opts.build.drop_face_cells = mode & 4 == 4;
    if let Ok(r) = gmsh::read_from(text, "fuzz.msh".as_ref(), &opts) {
        // both writers (4.1 and 2.2) must give files that read back to the same complex
        let mut out = Vec::new();
        if gmsh::write(&mut out, &r.complex).is_ok() {
            let back = gmsh::read_from(&out[..], "back.msh".as_ref(), &opts)
                .expect("a written file must read back");
            assert_eq!(back.complex.n_cells(), r.complex.n_cells(), "round trip changed the cells");
            let mut out22 = Vec::new();
            gmsh::write_22(&mut out22, &r.complex).expect("2.2 accepts what 4.1 accepts");
            let back22 = gmsh::read_from(&out22[..], "back22.msh".as_ref(), &opts)
                .expect("a written 2.2 file must read back");
            assert_eq!(back22.complex, back.complex, "2.2 and 4.1 round trips differ");
        }
    }
});
