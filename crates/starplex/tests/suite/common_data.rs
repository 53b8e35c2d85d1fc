//! Locating the shared datasets and their oracles (used by several test files).
#![allow(dead_code)]
use std::path::{Path, PathBuf};

/// The shared datasets: `$STARPLEX_SHARED/datasets` when set, else `shared/datasets` beside the
/// repository or any of its ancestors (a checkout beside `shared/`, as CI has it, or a git
/// worktree deeper down).
pub fn datasets_dir() -> PathBuf {
    if let Ok(s) = std::env::var("STARPLEX_SHARED") {
        return Path::new(&s).join("datasets");
    }
    let here = Path::new(env!("CARGO_MANIFEST_DIR"));
    for a in here.ancestors() {
        let d = a.join("shared/datasets");
        if d.join("oracle").is_dir() {
            return d;
        }
    }
    here.join("../../../shared/datasets")
}

/// True under CI (`CI=true`), where the shared datasets are always beside the checkout and their
/// absence is a failure; elsewhere tests that need them skip with a printed reason.
pub fn data_required() -> bool {
    std::env::var("CI").is_ok_and(|v| v == "true")
}

/// The folders that may hold datasets of `size` (`"small"`, `"medium"`, ...): the shared
/// `datasets/<size>/` and, when `STARPLEX_DATA` is set, every `$STARPLEX_DATA/<size>/<name>/`.
pub fn data_dirs(size: &str) -> Vec<PathBuf> {
    let mut dirs = vec![datasets_dir().join(size)];
    if let Ok(d) = std::env::var("STARPLEX_DATA")
        && let Ok(rd) = std::fs::read_dir(Path::new(&d).join(size))
    {
        let mut more: Vec<PathBuf> = rd.flatten().map(|e| e.path()).collect();
        more.sort();
        dirs.extend(more);
    }
    dirs
}

/// The dataset file `file` (e.g. `tri_elephant.off`) of `size`: from the shared datasets, else
/// from `$STARPLEX_DATA/<size>/<stem>/`. `None` when neither has it.
pub fn dataset_file(size: &str, file: &str) -> Option<PathBuf> {
    let stem = file.split('.').next().unwrap_or(file);
    let shared = datasets_dir().join(size).join(file);
    if shared.is_file() {
        return Some(shared);
    }
    let d = std::env::var("STARPLEX_DATA").ok()?;
    let p = Path::new(&d).join(size).join(stem).join(file);
    p.is_file().then_some(p)
}

/// `(name, path)` of every `.spx` dataset of `size` we can find, sorted by name, first found
/// kept (no oracle needed).
pub fn spx_files(size: &str) -> Vec<(String, PathBuf)> {
    let mut found: std::collections::BTreeMap<String, PathBuf> = Default::default();
    for d in data_dirs(size) {
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
    found.into_iter().collect()
}

/// The `.spx` datasets of `size` that have an oracle: `(name, path to .spx, oracle JSON)`.
pub fn datasets_with_oracle(size: &str) -> Vec<(String, PathBuf, serde_json::Value)> {
    spx_files(size)
        .into_iter()
        .filter_map(|(name, p)| {
            let o = datasets_dir().join("oracle").join(format!("{name}.json"));
            let text = std::fs::read_to_string(o).ok()?;
            Some((name, p, serde_json::from_str(&text).ok()?))
        })
        .collect()
}

/// Every small dataset we can find: `(name, path to .spx, oracle JSON)`. Looks in
/// `../shared/datasets/small/` and, when `STARPLEX_DATA` is set, in `$STARPLEX_DATA/small/*/`.
pub fn small_datasets() -> Vec<(String, PathBuf, serde_json::Value)> {
    datasets_with_oracle("small")
}

/// Every medium dataset with an oracle (medium data is built by `get medium`; CI has none).
pub fn medium_datasets() -> Vec<(String, PathBuf, serde_json::Value)> {
    datasets_with_oracle("medium")
}
