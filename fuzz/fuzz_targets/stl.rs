//! Feeds arbitrary bytes to the STL reader (ascii or binary, decided by the reader as for a real
//! file; the first byte picks the build options): it must return Ok or Err, never panic, hang or
//! exhaust memory. The STL reader reads a path (it needs the file length to tell binary from
//! ascii), so each input goes through a per-process temporary file.
#![no_main]
use libfuzzer_sys::fuzz_target;
use starplex::io::stl;
use starplex_fuzz::options;

fuzz_target!(|data: &[u8]| {
    let Some((&mode, bytes)) = data.split_first() else {
        return;
    };
    let opts = options(mode, false);
    let path = std::env::temp_dir().join(format!("starplex-fuzz-{}.stl", std::process::id()));
    std::fs::write(&path, bytes).expect("temporary file");
    let _ = stl::read(&path, &opts);
});
