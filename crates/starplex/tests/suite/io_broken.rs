//! A corpus of broken files, generated here, for every text reader: each must give `Err` (never a
//! panic), and the message must name the file, the line and the problem.
//!
//! The corpus is a table: one row per format, a small valid file with markers
//! (`@NV@` vertex count, `@NC@` cell count, `@X@` one coordinate, `@I@` one vertex index), and the
//! values that break it. Every breakage (truncated, counts that lie, bad number, NaN, index out
//! of range, repeated vertex, binary garbage, empty, a declared count of 10^12, wrong header) is
//! derived from the row, so a new format is one more line in [`FORMATS`].
use std::path::{Path, PathBuf};

use starplex::io::{self, ReadOptions};

/// One format of the corpus.
struct Row {
    /// File extension (the reader is chosen by it).
    ext: &'static str,
    /// A valid file with markers; the last line is a cell line.
    template: &'static str,
    /// Values of `@NV@`, `@NC@`, `@X@`, `@I@` in the valid file.
    nv: u64,
    nc: u64,
    x: &'static str,
    i: &'static str,
    /// An index value out of range, and one that repeats another index of the same cell.
    out_of_range: &'static str,
    repeated: &'static str,
}

#[rustfmt::skip]
const FORMATS: &[Row] = &[
    Row { ext: "spx", template: "SPX 1\n# c\n3 @NV@ @NC@\n0 0 0\n1 @X@ 0\n0 1 0\n0 0 1\ntri 3 0 1 2\ntri 3 0 @I@ 3\n", nv: 4, nc: 2, x: "0.5", i: "2", out_of_range: "4", repeated: "3" },
    Row { ext: "off", template: "OFF\n# c\n@NV@ @NC@ 0\n0 0 0\n1 @X@ 0\n0 1 0\n0 0 1\n3 0 1 2\n3 0 @I@ 3\n", nv: 4, nc: 2, x: "0.5", i: "2", out_of_range: "4", repeated: "3" },
    Row { ext: "off", template: "COFF @NV@ @NC@ 0\n0 0 0 1 0 0\n1 @X@ 0 1 0 0\n0 1 0 1 0 0\n0 0 1 1 0 0\n4 0 1 2 3 7 7 7\n3 1 @I@ 3\n", nv: 4, nc: 2, x: "0.5", i: "2", out_of_range: "4", repeated: "1" },
    Row { ext: "off", template: "OFF\n@NV@ @NC@ 0\n0 0 0 0 0\n1 @X@ 0 0 0\n0 1 0 0 0\n0 0 1 0 0\n0 0 0 1 0\n1 1 1 1 1\n5 0 1 2 3 4\n2 @I@ 5\n", nv: 6, nc: 2, x: "0.5", i: "4", out_of_range: "6", repeated: "5" },
    Row { ext: "tri", template: "@NV@\n0 0 0\n1 @X@ 0\n0 1 0\n0 0 1\n@NC@\n0 1 2\n0 @I@ 3\n", nv: 4, nc: 2, x: "0.5", i: "2", out_of_range: "4", repeated: "0" },
    Row { ext: "ts", template: "@NV@ @NC@\n0 0 0 0\n1 @X@ 0 0\n0 1 0 0\n0 0 1 1\n1 1 1 1\n0 1 2 3\n1 @I@ 3 4\n", nv: 5, nc: 2, x: "0.5", i: "2", out_of_range: "5", repeated: "4" },
    Row { ext: "sierp", template: "2 @NV@ @NC@\n0 0\n1 @X@\n0 1\n1 1\n3 0 1 2\n3 1 @I@ 3\n", nv: 4, nc: 2, x: "0.5", i: "2", out_of_range: "4", repeated: "3" },
    Row { ext: "hex", template: "v 0 0 0\nv 1 @X@ 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n# 1 hexahedra\nh 1 2 8 4 6 5 @I@ 7\n", nv: 8, nc: 1, x: "0", i: "3", out_of_range: "9", repeated: "2" },
];

/// What a broken file must produce.
struct Expect {
    /// The error must be at one of these lines (empty: at some line).
    lines: Vec<u64>,
    /// The message must contain one of these (empty: no check beyond file and line).
    any_of: Vec<&'static str>,
}

struct Case {
    name: String,
    ext: &'static str,
    bytes: Vec<u8>,
    expect: Expect,
}

fn line_of(text: &str, marker: &str) -> u64 {
    text.lines()
        .position(|l| l.contains(marker))
        .map(|p| p as u64 + 1)
        .unwrap_or_else(|| panic!("marker {marker} not in the template"))
}

fn fill(row: &Row, nv: &str, nc: &str, x: &str, i: &str) -> String {
    row.template
        .replace("@NV@", nv)
        .replace("@NC@", nc)
        .replace("@X@", x)
        .replace("@I@", i)
}

/// Deterministic pseudo-random bytes (xorshift), with a few newlines.
fn garbage(seed: u64, n: usize) -> Vec<u8> {
    let mut rng = starplex::testkit::XorShift::new(seed | 1);
    (0..n).map(|_| (rng.next_u64() >> 24) as u8).collect()
}

/// The broken variants of one row (and the valid file, which must read).
fn cases(k: usize, row: &Row) -> (String, Vec<Case>) {
    let (nv, nc) = (row.nv.to_string(), row.nc.to_string());
    let valid = fill(row, &nv, &nc, row.x, row.i);
    let last = valid.lines().count() as u64;
    let has_counts = row.template.contains("@NC@");
    let mut out = Vec::new();
    let mut add = |name: &str, text: Vec<u8>, lines: Vec<u64>, any_of: Vec<&'static str>| {
        out.push(Case {
            name: format!("{}{k}_{name}", row.ext),
            ext: row.ext,
            bytes: text,
            expect: Expect { lines, any_of },
        })
    };
    // Truncated in the middle of the last line (its last value and the newline are gone).
    let cut = valid.trim_end_matches('\n');
    let cut = &cut[..cut.rfind(' ').unwrap()];
    add(
        "truncated_mid_line",
        cut.into(),
        vec![last],
        vec!["found the end of the line"],
    );
    if has_counts {
        // Truncated at a line boundary: the last cell is missing.
        let cut = &valid[..valid.trim_end_matches('\n').rfind('\n').unwrap() + 1];
        add(
            "truncated_line",
            cut.into(),
            vec![last],
            vec!["unexpected end of file"],
        );
        let more = (row.nc + 1).to_string();
        add(
            "count_says_more",
            fill(row, &nv, &more, row.x, row.i).into(),
            vec![last + 1],
            vec!["unexpected end of file"],
        );
        let fewer = (row.nc - 1).to_string();
        add(
            "count_says_fewer",
            fill(row, &nv, &fewer, row.x, row.i).into(),
            vec![last],
            vec!["unexpected content after"],
        );
        add(
            "count_1e12",
            fill(row, &nv, "1000000000000", row.x, row.i).into(),
            vec![last + 1, line_of(row.template, "@NC@")],
            vec!["unexpected end of file", "32-bit"],
        );
        add(
            "vertex_count_1e12",
            fill(row, "1000000000000", &nc, row.x, row.i).into(),
            vec![line_of(row.template, "@NV@")],
            vec!["32-bit"],
        );
    }
    // The last cell repeated (a duplicate top cell, found when the complex is built). The .spx
    // reader (io/spx.rs) reports build errors without a line, so it is not in this case.
    if row.ext != "spx" {
        let more = (row.nc + 1).to_string();
        let mut dup = fill(row, &nv, &more, row.x, row.i);
        let last_line = dup.lines().last().unwrap().to_string();
        dup.push_str(&last_line);
        dup.push('\n');
        add(
            "duplicate_cell",
            dup.into(),
            vec![last + 1],
            vec!["has the same vertices as"],
        );
    }
    let xl = line_of(row.template, "@X@");
    let il = line_of(row.template, "@I@");
    add(
        "bad_number",
        fill(row, &nv, &nc, "1.2.3", row.i).into(),
        vec![xl],
        vec!["'1.2.3'"],
    );
    add(
        "nan",
        fill(row, &nv, &nc, "nan", row.i).into(),
        vec![xl],
        vec!["not finite"],
    );
    add(
        "inf",
        fill(row, &nv, &nc, "-inf", row.i).into(),
        vec![xl],
        vec!["not finite"],
    );
    add(
        "index_out_of_range",
        fill(row, &nv, &nc, row.x, row.out_of_range).into(),
        vec![il],
        vec!["out of range"],
    );
    add(
        "index_not_a_number",
        fill(row, &nv, &nc, row.x, "-1").into(),
        vec![il],
        vec!["'-1'"],
    );
    add(
        "index_huge",
        fill(row, &nv, &nc, row.x, "99999999999999999999999").into(),
        vec![il],
        vec!["99999999999999999999999"],
    );
    add(
        "repeated_vertex",
        fill(row, &nv, &nc, row.x, row.repeated).into(),
        vec![il],
        vec!["appears more than once"],
    );
    add("empty", Vec::new(), vec![1], vec!["end of file", "empty"]);
    add(
        "only_comments_and_blanks",
        b"\n\n   \n\t\n".to_vec(),
        vec![1, 4, 5],
        vec!["end of file", "empty"],
    );
    let mut wrong = valid.clone();
    let first_end = wrong.find('\n').unwrap();
    wrong.replace_range(..first_end, "solid starplex");
    add("wrong_header", wrong.into(), vec![1], vec!["'solid"]);
    for seed in 1..=4u64 {
        add(
            &format!("binary_garbage_{seed}"),
            garbage(seed * 7919 + k as u64, 3000),
            vec![],
            vec![],
        );
    }
    // Garbage after a valid file.
    let mut tail = valid.clone().into_bytes();
    tail.extend_from_slice(&garbage(99, 200));
    add("garbage_after_the_end", tail, vec![], vec![]);
    (valid, out)
}

fn corpus_dir() -> PathBuf {
    let d = std::env::temp_dir().join(format!("starplex-io-broken-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// `path:LINE: ...` -> LINE.
fn line_in(msg: &str, path: &Path) -> Option<u64> {
    let rest = msg.strip_prefix(&format!("{}:", path.display()))?;
    let digits: String = rest.chars().take_while(|c| c.is_ascii_digit()).collect();
    if digits.is_empty() || !rest[digits.len()..].starts_with(':') {
        return None;
    }
    digits.parse().ok()
}

#[test]
fn every_broken_file_is_a_clear_error() {
    let dir = corpus_dir();
    let mut failures = Vec::new();
    let mut n = 0;
    for (k, row) in FORMATS.iter().enumerate() {
        let (valid, cases) = cases(k, row);
        // The unbroken file reads: the errors below come from the breakage.
        let vp = dir.join(format!("{}{k}_valid.{}", row.ext, row.ext));
        std::fs::write(&vp, &valid).unwrap();
        if let Err(e) = io::read(&vp, &ReadOptions::default()) {
            failures.push(format!(
                "{}: the valid file does not read: {e}",
                vp.display()
            ));
        }
        for c in cases {
            n += 1;
            let p = dir.join(format!("{}.{}", c.name, c.ext));
            std::fs::write(&p, &c.bytes).unwrap();
            let r = std::panic::catch_unwind(|| io::read(&p, &ReadOptions::default()));
            let msg = match r {
                Err(_) => {
                    failures.push(format!("{}: PANIC", c.name));
                    continue;
                }
                Ok(Ok(_)) => {
                    failures.push(format!("{}: read without error", c.name));
                    continue;
                }
                Ok(Err(e)) => {
                    println!("{}: {e}", c.name);
                    e.to_string()
                }
            };
            let Some(line) = line_in(&msg, &p) else {
                failures.push(format!("{}: no 'file:line:' in '{msg}'", c.name));
                continue;
            };
            if !c.expect.lines.is_empty() && !c.expect.lines.contains(&line) {
                failures.push(format!(
                    "{}: line {line}, expected one of {:?}: '{msg}'",
                    c.name, c.expect.lines
                ));
            }
            if !c.expect.any_of.is_empty() && !c.expect.any_of.iter().any(|w| msg.contains(w)) {
                failures.push(format!(
                    "{}: '{msg}' says none of {:?}",
                    c.name, c.expect.any_of
                ));
            }
        }
    }
    std::fs::remove_dir_all(&dir).ok();
    assert!(
        failures.is_empty(),
        "{} of {n} cases failed:\n{}",
        failures.len(),
        failures.join("\n")
    );
    assert!(n > 100, "the corpus is smaller than expected ({n})");
}

#[test]
fn missing_file_and_unknown_extension_name_the_file() {
    let dir = corpus_dir().join("missing");
    for ext in ["spx", "off", "tri", "ts", "sierp", "hex"] {
        let p = dir.join(format!("nope.{ext}"));
        let e = io::read(&p, &ReadOptions::default()).unwrap_err();
        assert!(e.to_string().starts_with(&p.display().to_string()), "{e}");
    }
    let e = io::read(&dir.join("x.unknown"), &ReadOptions::default()).unwrap_err();
    assert!(e.to_string().contains("unknown format"), "{e}");
}

/// Seeded random mutations of the corpus's valid files (byte flips, insertions of tricky tokens,
/// deletions, truncations), fed to every reader from memory: never a panic, and every error
/// names the file and a line. Complements the cargo-fuzz targets (fuzz/), which CI does not run.
#[test]
fn mutated_files_never_panic() {
    use starplex::io::{off, spx, stellar_ref, Format, PolygonMode};
    const TOKENS: &[&[u8]] = &[
        b" ",
        b"\n",
        b"\r\n",
        b"\t",
        b"#",
        b"0",
        b"-1",
        b"nan",
        b"inf",
        b"1e309",
        b"4294967295",
        b"18446744073709551616",
        b"1000000000000",
        b"65",
        b"66",
        b"OFF",
        b"nOFF",
        b"4",
        b"v",
        b"h",
        b"\xff",
        b"\x00",
    ];
    let mut rng = starplex::testkit::XorShift::new(0x5eed);
    let mut next = move |n: usize| {
        let rng = rng.next_u64();
        (rng % n as u64) as usize
    };
    let mut runs = 0;
    for (k, row) in FORMATS.iter().enumerate() {
        let (valid, _) = cases(k, row);
        for _ in 0..400 {
            let mut b = valid.clone().into_bytes();
            for _ in 0..1 + next(4) {
                match next(4) {
                    0 if !b.is_empty() => {
                        let i = next(b.len());
                        b[i] = next(256) as u8;
                    }
                    1 => {
                        let i = next(b.len() + 1);
                        let t = TOKENS[next(TOKENS.len())];
                        b.splice(i..i, t.iter().copied());
                    }
                    2 if !b.is_empty() => {
                        let i = next(b.len());
                        let j = (i + 1 + next(8)).min(b.len());
                        b.drain(i..j);
                    }
                    _ => b.truncate(next(b.len() + 1)),
                }
            }
            let name = format!("m.{}", row.ext);
            let path: &Path = name.as_ref();
            let mode = next(2);
            let r = std::panic::catch_unwind(|| {
                let mut opts = ReadOptions::default();
                if mode == 1 {
                    opts.polygons = PolygonMode::Simplices;
                }
                match row.ext {
                    "spx" => spx::read_from(&b[..], path, &opts),
                    "off" => off::read_from(&b[..], path, &opts),
                    ext => {
                        let f = Format::from_name(ext).unwrap();
                        stellar_ref::read_from(&b[..], path, f, &opts)
                    }
                }
            });
            runs += 1;
            match r {
                Err(_) => panic!(
                    "reader panicked on {name}: {:?}",
                    String::from_utf8_lossy(&b)
                ),
                Ok(Err(e)) => {
                    let msg = e.to_string();
                    assert!(msg.starts_with(&name), "{msg}");
                    // Build errors (duplicates, faces of other cells) name cell ids, not lines.
                    let is_build = matches!(e.kind, starplex::io::IoErrorKind::Complex(_))
                        && e.location.is_none();
                    assert!(
                        is_build || line_in(&msg, path).is_some(),
                        "no line in '{msg}'"
                    );
                }
                Ok(Ok(_)) => {}
            }
        }
    }
    assert_eq!(runs, FORMATS.len() * 400);
}

/// `drop_degenerate` (`--drop-degenerate`): a cell with a repeated vertex, an error by default
/// (above), is dropped instead, in every reader, with a note counting it; the other cells and
/// their attributes are kept.
#[test]
fn drop_degenerate_drops_cells_with_a_repeated_vertex_in_every_reader() {
    use starplex::complex::BuildOptions;
    let dir = std::env::temp_dir().join(format!("starplex-io-degenerate-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let drop = ReadOptions {
        build: BuildOptions {
            drop_degenerate: true,
            ..Default::default()
        },
        ..Default::default()
    };
    // (name with extension, valid file, the same with one degenerate cell)
    let mut files: Vec<(String, Vec<u8>, Vec<u8>)> = Vec::new();
    for (k, row) in FORMATS.iter().enumerate() {
        let (nv, nc) = (row.nv.to_string(), row.nc.to_string());
        files.push((
            format!("row{k}.{}", row.ext),
            fill(row, &nv, &nc, row.x, row.i).into(),
            fill(row, &nv, &nc, row.x, row.repeated).into(),
        ));
    }
    let pair = |name: &str, valid: &str, from: &str, to: &str| {
        assert!(valid.contains(from), "{name}");
        (
            name.to_string(),
            valid.as_bytes().to_vec(),
            valid.replacen(from, to, 1).into_bytes(),
        )
    };
    files.push(pair(
        "m.mesh",
        "MeshVersionFormatted 2\nDimension 3\nVertices\n4\n0 0 0 0\n1 0 0 0\n0 1 0 0\n1 1 0 0\nTriangles\n2\n1 2 3 10\n2 4 3 20\nEnd\n",
        "2 4 3 20",
        "2 4 4 20",
    ));
    files.push(pair(
        "m.obj",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n",
        "f 2 4 3",
        "f 2 4 4",
    ));
    files.push(pair(
        "m.ply",
        "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n3 1 3 2\n",
        "3 1 3 2",
        "3 1 3 3",
    ));
    files.push(pair(
        "m.stl",
        "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nfacet normal 0 0 1\nouter loop\nvertex 1 0 0\nvertex 1 1 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid t\n",
        "vertex 1 1 0\nvertex 0 1 0",
        "vertex 1 1 0\nvertex 1 1 0",
    ));
    files.push(pair(
        "m.vtk",
        "# vtk DataFile Version 4.2\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 float\n0 0 0 1 0 0 0 1 0 1 1 0\nCELLS 2 8\n3 0 1 2\n3 1 3 2\nCELL_TYPES 2\n5\n5\n",
        "3 1 3 2",
        "3 1 3 3",
    ));
    files.push(pair(
        "m.vtu",
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n<UnstructuredGrid>\n<Piece NumberOfPoints=\"4\" NumberOfCells=\"2\">\n<Points>\n<DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"ascii\">0 0 0 1 0 0 0 1 0 1 1 0</DataArray>\n</Points>\n<Cells>\n<DataArray type=\"Int32\" Name=\"connectivity\" format=\"ascii\">0 1 2 1 3 2</DataArray>\n<DataArray type=\"Int32\" Name=\"offsets\" format=\"ascii\">3 6</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">5 5</DataArray>\n</Cells>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n",
        "1 3 2</DataArray>",
        "1 3 3</DataArray>",
    ));
    files.push(pair(
        "m22.msh",
        "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 1 1 0\n$EndNodes\n$Elements\n2\n1 2 2 7 1 1 2 3\n2 2 2 7 1 2 4 3\n$EndElements\n",
        "2 4 3\n",
        "2 4 4\n",
    ));
    // binary legacy VTK (big-endian), and binary gmsh 4.1 as starplex writes it, patched
    let vtk_bin = |last: i32| {
        let mut b =
            b"# vtk DataFile Version 4.2\nt\nBINARY\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 float\n"
                .to_vec();
        for x in [0f32, 0., 0., 1., 0., 0., 0., 1., 0., 1., 1., 0.] {
            b.extend_from_slice(&x.to_be_bytes());
        }
        b.extend_from_slice(b"\nCELLS 2 8\n");
        for x in [3i32, 0, 1, 2, 3, 1, 3, last] {
            b.extend_from_slice(&x.to_be_bytes());
        }
        b.extend_from_slice(b"\nCELL_TYPES 2\n");
        for x in [5i32, 5] {
            b.extend_from_slice(&x.to_be_bytes());
        }
        b.push(b'\n');
        b
    };
    files.push(("bin.vtk".into(), vtk_bin(2), vtk_bin(3)));
    let two = {
        use starplex::cell::CellKind;
        starplex::complex::IndexedComplex::from_parts(
            3,
            vec![0., 0., 0., 1., 0., 0., 0., 1., 0., 1., 1., 0.].into(),
            vec![(CellKind::Simplex(2), vec![0, 1, 2, 1, 3, 2].into())],
        )
        .unwrap()
    };
    let mut msh = Vec::new();
    io::gmsh::write_binary(&mut msh, &two).unwrap();
    let tags: Vec<u8> = [2u64, 4, 3].iter().flat_map(|x| x.to_le_bytes()).collect();
    let at = msh
        .windows(24)
        .position(|w| w == &tags[..])
        .expect("the second triangle's node tags 2 4 3 in the binary file");
    let mut bad = msh.clone();
    bad[at + 16..at + 24].copy_from_slice(&4u64.to_le_bytes());
    files.push(("bin41.msh".into(), msh, bad));

    let mut failures = Vec::new();
    for (name, valid, degenerate) in &files {
        let vp = dir.join(format!("valid_{name}"));
        let dp = dir.join(format!("degenerate_{name}"));
        std::fs::write(&vp, valid).unwrap();
        std::fs::write(&dp, degenerate).unwrap();
        let v = match io::read(&vp, &ReadOptions::default()) {
            Ok(r) => r,
            Err(e) => {
                failures.push(format!("{name}: the valid file does not read: {e}"));
                continue;
            }
        };
        // the valid file reads the same with the option, without a note about it
        match io::read(&vp, &drop) {
            Ok(r) if r.complex == v.complex && r.notes == v.notes => {}
            Ok(r) => failures.push(format!(
                "{name}: drop_degenerate changed a valid file: {:?}",
                r.notes
            )),
            Err(e) => failures.push(format!("{name}: valid file with drop_degenerate: {e}")),
        }
        match io::read(&dp, &ReadOptions::default()) {
            Ok(_) => failures.push(format!("{name}: the degenerate file reads by default")),
            Err(e) => {
                let e = e.to_string();
                if !(e.contains("degenerate") && e.contains(&dp.display().to_string())) {
                    failures.push(format!(
                        "{name}: default error says nothing of a degenerate cell: {e}"
                    ));
                }
            }
        }
        match io::read(&dp, &drop) {
            Err(e) => failures.push(format!("{name}: drop_degenerate still fails: {e}")),
            Ok(r) => {
                if r.complex.n_cells() + 1 != v.complex.n_cells() {
                    failures.push(format!(
                        "{name}: {} cells, expected {} - 1",
                        r.complex.n_cells(),
                        v.complex.n_cells()
                    ));
                }
                if !r
                    .notes
                    .iter()
                    .any(|n| n.starts_with("dropped 1 degenerate"))
                {
                    failures.push(format!(
                        "{name}: no note on the dropped cell: {:?}",
                        r.notes
                    ));
                }
                // every kept cell is a cell of the valid file
                for c in r.complex.cells() {
                    if !v
                        .complex
                        .cells()
                        .any(|d| d.kind == c.kind && d.vertices == c.vertices)
                    {
                        failures.push(format!(
                            "{name}: cell {:?} is not in the valid file",
                            c.vertices
                        ));
                    }
                }
                if name == "m.mesh" {
                    let refs = &r.complex.attributes().cell;
                    if refs.len() != 1
                        || refs[0] != starplex::attr::Attribute::int("medit:ref", 1, vec![10])
                    {
                        failures.push(format!(
                            "m.mesh: the references did not follow the drop: {refs:?}"
                        ));
                    }
                }
            }
        }
    }
    std::fs::remove_dir_all(&dir).ok();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
