//! Feeds arbitrary bytes to the OFF reader (the first byte picks polygon or simplex mode and
//! the build options): it must return Ok or Err, never panic, hang or exhaust memory. A file
//! that reads must also write and read back to the same complex.
#![no_main]
use libfuzzer_sys::fuzz_target;
use starplex::io::{off, PolygonMode, ReadOptions};

fuzz_target!(|data: &[u8]| {
    let Some((&mode, text)) = data.split_first() else {
        return;
    };
    let mut opts = ReadOptions::default();
    if mode & 1 == 1 {
        opts.polygons = PolygonMode::Simplices;
    }
    opts.build.drop_duplicates = mode & 2 == 2;
    opts.build.drop_face_cells = mode & 4 == 4;
    if let Ok(r) = off::read_from(text, "fuzz.off".as_ref(), &opts) {
        let mut out = Vec::new();
        // Polygon mode makes only edges, triangles and quads, simplex mode only simplices:
        // both are written and read back by the same mode.
        if off::write(&mut out, &r.complex).is_ok() {
            let back = off::read_from(&out[..], "back.off".as_ref(), &opts)
                .expect("a written OFF file must read back");
            assert!(
                back.complex == r.complex,
                "OFF round trip changed the complex"
            );
        }
    }
});
