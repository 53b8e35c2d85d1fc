//! Feeds arbitrary bytes to the VTK XML reader (`.vtu` / `.vtp`; the first byte picks the build
//! options): it must return Ok or Err, never panic, hang or exhaust memory. A file that reads and
//! that the `.vtu` writer accepts must read back with the same cell count.
#![no_main]
use libfuzzer_sys::fuzz_target;
use starplex::io::vtu;
use starplex_fuzz::{options, round_trip};

fuzz_target!(|data: &[u8]| {
    let Some((&mode, bytes)) = data.split_first() else {
        return;
    };
    let read = |b: &[u8], o: &_| vtu::read_bytes(b, "fuzz.vtu".as_ref(), o);
    if let Some((r, back)) = round_trip(bytes, &options(mode, false), read, vtu::write_vtu) {
        assert_eq!(back.complex.n_cells(), r.complex.n_cells(), "round trip changed the cells");
    }
});
