//! Seeded mutation fuzzing of every reader, in the normal test suite (the cargo-fuzz targets in
//! fuzz/ need a nightly-flag build that CI does not run): the small files of `fuzz/seeds/*` and
//! `tests/data/io` (and a gzip-compressed copy of some), with random byte flips, overwritten
//! 32-bit words (huge counts, negative sizes), inserted tokens, deletions and truncations, read
//! from a file through `io::read` with the format given. Every read must return `Ok` or an
//! `IoError` naming the file, never panic.
use std::io::Write as _;
use std::path::{Path, PathBuf};

use starplex::io::{self, Format, PolygonMode, ReadOptions};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The entries of `dir`, sorted (none when it cannot be read).
fn sorted_entries(dir: &Path) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .map(|d| d.flatten().map(|e| e.path()).collect())
        .unwrap_or_default();
    v.sort();
    v
}

/// `(file, format)` of every corpus file of at most `max_len` bytes.
fn corpus(max_len: u64) -> Vec<(PathBuf, Format)> {
    let mut out = Vec::new();
    let seeds = root().join("../../fuzz/seeds");
    for dir in sorted_entries(&seeds) {
        let name = dir.file_name().unwrap().to_string_lossy().into_owned();
        if name == "gzip" {
            // compressed files of the other formats (or bytes the target compresses): mutating
            // them mostly breaks the gzip stream; the `gzip` fuzz target covers them
            continue;
        }
        for f in sorted_entries(&dir) {
            let stem = f.file_name().unwrap().to_string_lossy().into_owned();
            let format = match name.as_str() {
                "spb" => Format::Binary,
                "medit" => Format::Medit,
                "stellar_ref" => Format::from_name(&stem).unwrap(),
                "surface" => Format::Spx,
                n => Format::from_name(n).unwrap(),
            };
            out.push((f, format));
        }
    }
    for f in sorted_entries(&root().join("tests/data/io")) {
        if let Some(format) = Format::from_path(&f) {
            out.push((f, format));
        }
    }
    out.retain(|(f, _)| std::fs::metadata(f).is_ok_and(|m| m.len() <= max_len));
    out
}

struct Rng(starplex::testkit::XorShift);

impl Rng {
    fn below(&mut self, n: usize) -> usize {
        self.0.below(n.max(1) as u64) as usize
    }
}

const TOKENS: &[&[u8]] = &[
    b" ",
    b"\n",
    b"\r\n",
    b"#",
    b"0",
    b"-1",
    b"nan",
    b"1e309",
    b"4294967295",
    b"18446744073709551616",
    b"1000000000000",
    b"$EndNodes\n",
    b"$Elements\n",
    b"end_header\n",
    b"\"",
    b"<",
    b"/>",
    b"\xff",
    b"\x00",
];

const WORDS: [u32; 6] = [0, 1, 0x7fff_ffff, 0x8000_0000, 0xffff_ffff, 0x0100_0000];

fn mutate(b: &mut Vec<u8>, rng: &mut Rng) {
    for _ in 0..1 + rng.below(3) {
        match rng.below(6) {
            0 if !b.is_empty() => {
                let i = rng.below(b.len());
                b[i] ^= 1 << rng.below(8);
            }
            1 if b.len() >= 4 => {
                let i = rng.below(b.len() - 3);
                let w = WORDS[rng.below(WORDS.len())];
                let bytes = if rng.below(2) == 0 {
                    w.to_le_bytes()
                } else {
                    w.to_be_bytes()
                };
                b[i..i + 4].copy_from_slice(&bytes);
            }
            2 => {
                let i = rng.below(b.len() + 1);
                let t = TOKENS[rng.below(TOKENS.len())];
                b.splice(i..i, t.iter().copied());
            }
            3 if !b.is_empty() => {
                let i = rng.below(b.len());
                let j = (i + 1 + rng.below(16)).min(b.len());
                b.drain(i..j);
            }
            4 if !b.is_empty() => {
                // repeat a chunk (a section or a record twice)
                let i = rng.below(b.len());
                let j = (i + 1 + rng.below(64)).min(b.len());
                let chunk = b[i..j].to_vec();
                b.splice(j..j, chunk);
            }
            _ => {
                let n = rng.below(b.len() + 1);
                b.truncate(n);
            }
        }
    }
}

fn gzip(b: &[u8]) -> Vec<u8> {
    let mut e = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::fast());
    e.write_all(b).unwrap();
    e.finish().unwrap()
}

/// Reads `bytes` as `format` from `path`; a panic or an error that does not name the file is
/// returned as a failure.
fn check(path: &Path, bytes: &[u8], format: Format, mode: usize) -> Result<(), String> {
    std::fs::write(path, bytes).unwrap();
    let opts = ReadOptions {
        format: Some(format),
        polygons: if mode & 1 == 1 {
            PolygonMode::Simplices
        } else {
            PolygonMode::Polygons
        },
        build: starplex::complex::BuildOptions {
            drop_duplicates: mode & 2 == 2,
            drop_face_cells: mode & 4 == 4,
            ..Default::default()
        },
        ..Default::default()
    };
    match std::panic::catch_unwind(|| io::read(path, &opts)) {
        Err(_) => Err("panicked".into()),
        Ok(Err(e)) if !e.to_string().starts_with(&path.display().to_string()) => {
            Err(format!("error does not name the file: {e}"))
        }
        Ok(_) => Ok(()),
    }
}

#[test]
fn every_reader_survives_mutated_corpus_files() {
    let files = corpus(24 << 10);
    assert!(files.len() >= 40, "corpus too small: {}", files.len());
    let mut formats: Vec<String> = files.iter().map(|(_, f)| f.to_string()).collect();
    formats.sort();
    formats.dedup();
    for f in [
        "spx", "spb", "off", "ply", "obj", "stl", "mesh", "vtk", "vtu", "msh", "tri", "ts",
        "sierp", "hex",
    ] {
        assert!(
            formats.iter().any(|x| x == f),
            "no {f} file in the corpus: {formats:?}"
        );
    }
    let dir = std::env::temp_dir().join(format!("starplex-mutations-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let keep = dir.join("failures");
    let mut failures = Vec::new();
    let mut rng = Rng(starplex::testkit::XorShift::new(0x00c0_ffee_1234_5678));
    let hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {})); // the panics are reported below, with their input
    let t0 = std::time::Instant::now();
    let mut runs = 0;
    for (i, (file, format)) in files.iter().enumerate() {
        let valid = std::fs::read(file).unwrap();
        let path = dir.join(format!("in{i}.{}", format.extension()));
        // a gzip copy of every fourth file: the decompressor's errors too
        let gz = i % 4 == 0;
        let n = if valid.len() > 8 << 10 { 24 } else { 48 };
        for m in 0..n {
            let mut b = valid.clone();
            mutate(&mut b, &mut rng);
            let b = if gz && m % 2 == 0 {
                let mut z = gzip(&b);
                if m % 4 == 0 {
                    mutate(&mut z, &mut rng);
                }
                z
            } else {
                b
            };
            runs += 1;
            if let Err(why) = check(&path, &b, *format, rng.below(8)) {
                std::fs::create_dir_all(&keep).unwrap();
                let saved = keep.join(format!("{i}-{m}.{}", format.extension()));
                std::fs::write(&saved, &b).unwrap();
                failures.push(format!(
                    "{} ({format}) mutation {m}: {why}; input saved as {}",
                    file.display(),
                    saved.display()
                ));
            }
        }
    }
    std::panic::set_hook(hook);
    if failures.is_empty() {
        std::fs::remove_dir_all(&dir).ok();
    }
    assert!(
        failures.is_empty(),
        "{} of {runs} reads failed:\n{}",
        failures.len(),
        failures.join("\n")
    );
    eprintln!("{runs} mutated reads in {:.1?}", t0.elapsed());
}
