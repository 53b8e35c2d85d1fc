//! Feeds arbitrary bytes to `io::read`, the entry point the CLI opens a file with, on a file whose
//! format is named by no extension (so it is sniffed from the content) or by the one before
//! `.gz`. The first byte picks: bits 0-2 the build options and polygon mode (as for `off`), bit 3
//! gzip-compresses the rest (a valid stream, so every reader runs behind the decompressor; without
//! it a mangled gzip stream exercises the decompressor's errors), bit 4 splits the compressed
//! stream into two gzip members, bits 5-7 the inner extension (none, off, ply, obj, msh, vtk, vtu,
//! mesh). `io::read` must return Ok or Err, never panic, hang or exhaust memory. Each input goes
//! through a per-process temporary file.
#![no_main]
use std::io::Write;

use flate2::{write::GzEncoder, Compression};
use libfuzzer_sys::fuzz_target;
use starplex::io;
use starplex_fuzz::options;

const INNER: [&str; 8] = ["", ".off", ".ply", ".obj", ".msh", ".vtk", ".vtu", ".mesh"];

fn gzip(bytes: &[u8]) -> Vec<u8> {
    let mut e = GzEncoder::new(Vec::new(), Compression::fast());
    e.write_all(bytes).expect("in memory");
    e.finish().expect("in memory")
}

fuzz_target!(|data: &[u8]| {
    let Some((&mode, bytes)) = data.split_first() else {
        return;
    };
    let opts = options(mode, true);
    let inner = INNER[(mode >> 5) as usize];
    let compress = mode & 8 == 8;
    let content = match (compress, mode & 16 == 16) {
        (false, _) => bytes.to_vec(),
        (true, false) => gzip(bytes),
        (true, true) => {
            let (a, b) = bytes.split_at(bytes.len() / 2);
            let mut c = gzip(a);
            c.extend_from_slice(&gzip(b));
            c
        }
    };
    // the raw bytes with an inner extension name that format; without, the content decides
    let name = format!("starplex-fuzz-gzip-{}{inner}.gz", std::process::id());
    let path = std::env::temp_dir().join(name);
    std::fs::write(&path, &content).expect("temporary file");
    let _ = io::read(&path, &opts);
});
