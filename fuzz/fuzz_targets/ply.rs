//! Feeds arbitrary bytes to the PLY reader (ascii and binary; the first byte picks the build
//! options and polygon mode): it must return Ok or Err, never panic, hang or exhaust memory. A
//! file that reads and that the writer accepts must read back with the same counts.
#![no_main]
use libfuzzer_sys::fuzz_target;
use starplex::io::ply;
use starplex_fuzz::{options, round_trip};

fuzz_target!(|data: &[u8]| {
    let Some((&mode, bytes)) = data.split_first() else {
        return;
    };
    let read = |b: &[u8], o: &_| ply::read_from(b, b.len() as u64, "fuzz.ply".as_ref(), o);
    if let Some((r, back)) = round_trip(bytes, &options(mode, true), read, ply::write) {
        assert_eq!(back.complex.n_cells(), r.complex.n_cells(), "round trip changed the cells");
        assert_eq!(back.complex.n_vertices(), r.complex.n_vertices());
    }
});
