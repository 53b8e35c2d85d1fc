//! Feeds arbitrary bytes to the `.spb` binary reader (header checks, then the memory-mapped
//! arrays): it must return Ok or Err, never panic or read out of bounds. A file that loads must
//! write back to the same bytes' complex (attributes of version-2 files included). Each input goes through a per-process temporary file,
//! since the reader memory-maps a path.
#![no_main]
use libfuzzer_sys::fuzz_target;
use starplex::io::{binary, ReadOptions};

fuzz_target!(|data: &[u8]| {
    let path = std::env::temp_dir().join(format!("starplex-fuzz-{}.spb", std::process::id()));
    std::fs::write(&path, data).expect("temporary file");
    let _ = binary::read_header(data, "fuzz.spb".as_ref());
    if let Ok(r) = binary::read(&path, &ReadOptions::default()) {
        let k = r.complex.clone();
        drop(r);
        let mut out = Vec::new();
        binary::write(&mut out, &k).expect("a loaded complex writes");
        std::fs::write(&path, &out).expect("temporary file");
        let back = binary::read(&path, &ReadOptions::default()).expect("a written file must load");
        // compared as written bytes: attribute floats may be NaN (NaN != NaN)
        let mut again = Vec::new();
        binary::write(&mut again, &back.complex).expect("a loaded complex writes");
        assert_eq!(again, out, "round trip changed the complex");
    }
});
