//! Feeds arbitrary bytes to the OFF reader (the first byte picks polygon or simplex mode and
//! the build options): it must return Ok or Err, never panic, hang or exhaust memory. A file
//! that reads must also write and read back to the same complex.
#![no_main]
use libfuzzer_sys::fuzz_target;
use starplex::io::{off, Format};
use starplex_fuzz::{options, round_trip, same_after_writing};

fuzz_target!(|data: &[u8]| {
    let Some((&mode, text)) = data.split_first() else {
        return;
    };
    // Polygon mode makes only edges, triangles and quads, simplex mode only simplices: both
    // are written and read back by the same mode.
    let read = |b: &[u8], o: &_| off::read_from(b, "fuzz.off".as_ref(), o);
    if let Some((r, back)) = round_trip(text, &options(mode, true), read, off::write) {
        // (NaN-aware: a colour may be written as nan; NOFF normals are not written, with a note)
        assert!(
            same_after_writing(&r.complex, &back.complex, Format::Off),
            "OFF round trip changed the complex"
        );
    }
});
