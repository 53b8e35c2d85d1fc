//! Feeds arbitrary bytes to the saved Stellar tree loader (header, arrays, permutations, the
//! coordinate and attribute sections; memory-mapped, so each input goes through a per-process
//! temporary file) and to `io::read`, which reads a saved tree as the complex it was built
//! from: Ok or Err, never a panic or an out-of-bounds read. A tree that loads answers its
//! relations and validation, and its complex (when it holds coordinates) builds the same tree
//! ids back.
#![no_main]
use libfuzzer_sys::fuzz_target;
use starplex::io::{self, ReadOptions};
use starplex::stellar::StellarTree;

fuzz_target!(|data: &[u8]| {
    let path = std::env::temp_dir().join(format!("starplex-fuzz-{}.tree", std::process::id()));
    std::fs::write(&path, data).expect("temporary file");
    if let Ok(t) = StellarTree::load(&path) {
        let _ = t.vt_all();
        let _ = t.validate();
        if let Ok(k) = t.to_complex() {
            assert_eq!(k.n_vertices(), t.n_vertices());
            assert_eq!(k.n_cells(), t.n_top_cells());
        }
    }
    if let Ok(r) = io::read(&path, &ReadOptions::default()) {
        let _ = r.complex.n_cells();
    }
});
