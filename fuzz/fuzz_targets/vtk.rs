//! Feeds arbitrary bytes to the vtk reader (the first byte picks the build options): it must
//! return Ok or Err, never panic, hang or exhaust memory. A file that reads and that the writer
//! accepts must read back with the same vertex and cell counts.
#![no_main]
use libfuzzer_sys::fuzz_target;
use starplex::io::{vtk, ReadOptions};

fuzz_target!(|data: &[u8]| {
    let Some((&mode, text)) = data.split_first() else {
        return;
    };
    let mut opts = ReadOptions::default();
    opts.build.drop_duplicates = mode & 2 == 2;
    opts.build.drop_face_cells = mode & 4 == 4;
    if let Ok(r) = vtk::read_from(text, "fuzz.vtk".as_ref(), &opts) {
        let mut out = Vec::new();
        if vtk::write(&mut out, &r.complex).is_ok() {
            let back = vtk::read_from(&out[..], "back.vtk".as_ref(), &opts)
                .expect("a written file must read back");
            assert_eq!(back.complex.n_cells(), r.complex.n_cells(), "round trip changed the cells");
        }
    }
});
