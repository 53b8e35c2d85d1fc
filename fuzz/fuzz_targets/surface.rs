//! Feeds arbitrary bytes to the spx reader, then to the explicit conversions of `convert`
//! (`--boundary`, `--triangulate`) and the STL writers: none may panic, and an STL that
//! `check_writable` accepts is written and reads back with the same number of triangles.
#![no_main]
use libfuzzer_sys::fuzz_target;
use starplex::algo::surface;
use starplex::io::{self, spx, stl, Format};
use starplex_fuzz::options;

fuzz_target!(|data: &[u8]| {
    let Some((&mode, text)) = data.split_first() else {
        return;
    };
    let opts = options(mode, false);
    let Ok(r) = spx::read_from(text, "fuzz.spx".as_ref(), &opts) else {
        return;
    };
    let Ok((b, _)) = surface::boundary(&r.complex) else {
        return;
    };
    let t = match surface::triangulate(&b) {
        Ok(t) => t,
        Err(_) => return,
    };
    if io::check_writable(&t, Format::StlBinary).is_err() {
        return;
    }
    let mut out = Vec::new();
    stl::write_binary(&mut out, &t).expect("check_writable accepted it");
    let path = std::env::temp_dir().join(format!("starplex-fuzz-surface-{}.stl", std::process::id()));
    std::fs::write(&path, &out).expect("temporary file");
    let back = stl::read(&path, &Default::default()).expect("a written STL reads back");
    assert_eq!(back.complex.n_cells(), t.n_cells());
});
