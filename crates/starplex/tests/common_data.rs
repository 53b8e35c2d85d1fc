//! Locating the shared datasets and their oracles (used by several test files).
#![allow(dead_code)]
use std::path::{Path, PathBuf};

/// `../shared/datasets` beside the repository.
pub fn datasets_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/datasets")
}

/// Every small dataset we can find: `(name, path to .spx, oracle JSON)`. Looks in
/// `../shared/datasets/small/` and, when `STARPLEX_DATA` is set, in `$STARPLEX_DATA/small/*/`.
pub fn small_datasets() -> Vec<(String, PathBuf, serde_json::Value)> {
    let mut found: std::collections::BTreeMap<String, PathBuf> = Default::default();
    let mut dirs = vec![datasets_dir().join("small")];
    if let Ok(d) = std::env::var("STARPLEX_DATA") {
        if let Ok(rd) = std::fs::read_dir(Path::new(&d).join("small")) {
            for e in rd.flatten() {
                dirs.push(e.path());
            }
        }
    }
    for d in dirs {
        let Ok(rd) = std::fs::read_dir(&d) else {
            continue;
        };
        for e in rd.flatten() {
            let p = e.path();
            if p.extension().is_some_and(|x| x == "spx") {
                let name = p.file_stem().unwrap().to_string_lossy().into_owned();
                found.entry(name).or_insert(p);
            }
        }
    }
    found
        .into_iter()
        .filter_map(|(name, p)| {
            let o = datasets_dir().join("oracle").join(format!("{name}.json"));
            let text = std::fs::read_to_string(o).ok()?;
            Some((name, p, serde_json::from_str(&text).ok()?))
        })
        .collect()
}
