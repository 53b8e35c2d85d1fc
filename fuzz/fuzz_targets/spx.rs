//! Feeds arbitrary bytes to the `.spx` reader: it must return Ok or Err, never panic, hang or
//! exhaust memory.
#![no_main]
use libfuzzer_sys::fuzz_target;
use starplex::io::{spx, ReadOptions};

fuzz_target!(|data: &[u8]| {
    let _ = spx::read_from(data, "fuzz.spx".as_ref(), &ReadOptions::default());
});
