//! Feeds arbitrary bytes to the PLY reader (ascii and binary; the first byte picks the build
//! options and polygon mode): it must return Ok or Err, never panic, hang or exhaust memory. A
//! file that reads and that the writer accepts must read back to the same complex.
#![no_main]
use libfuzzer_sys::fuzz_target;
use starplex::io::{ply, PolygonMode, ReadOptions};

fuzz_target!(|data: &[u8]| {
    let Some((&mode, bytes)) = data.split_first() else {
        return;
    };
    let mut opts = ReadOptions::default();
    if mode & 1 == 1 {
        opts.polygons = PolygonMode::Simplices;
    }
    opts.build.drop_duplicates = mode & 2 == 2;
    opts.build.drop_face_cells = mode & 4 == 4;
    if let Ok(r) = ply::read_from(bytes, bytes.len() as u64, "fuzz.ply".as_ref(), &opts) {
        let mut out = Vec::new();
        if ply::write(&mut out, &r.complex).is_ok() {
            let back = ply::read_from(&out[..], out.len() as u64, "back.ply".as_ref(), &opts)
                .expect("a written file must read back");
            assert_eq!(back.complex.n_cells(), r.complex.n_cells(), "round trip changed the cells");
            assert_eq!(back.complex.n_vertices(), r.complex.n_vertices());
        }
    }
});
