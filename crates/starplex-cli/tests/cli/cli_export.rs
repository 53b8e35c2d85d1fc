//! `query --out`: every answer written as .jsonl, .npz and .csv, read back and compared with the
//! per-vertex JSON answers; `--vertex-file` (and standard input); `--relation` filtering.
use std::io::{Read, Write};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

use serde_json::Value;

/// A 3x3 grid of squares split into triangles (16 vertices, 18 triangles) with a dangling edge
/// to a 17th vertex (not pure).
fn mesh(dir: &Path) -> PathBuf {
    let mut s = String::from("SPX 1\n3 17 19\n");
    for y in 0..4 {
        for x in 0..4 {
            s += &format!("{x} {y} 0\n");
        }
    }
    s += "5 5 5\n";
    let mut tris = Vec::new();
    for y in 0..3 {
        for x in 0..3 {
            let a = y * 4 + x;
            tris.push([a, a + 1, a + 5]);
            tris.push([a, a + 5, a + 4]);
        }
    }
    for t in &tris {
        s += &format!("tri 3 {} {} {}\n", t[0], t[1], t[2]);
    }
    s += "line 2 15 16\n";
    let p = dir.join("grid.spx");
    std::fs::write(&p, s).unwrap();
    p
}

fn run(args: &[&str], stdin: Option<&str>) -> (Option<i32>, String, String) {
    let mut c = Command::new(env!("CARGO_BIN_EXE_starplex"))
        .arg("--quiet")
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    if let Some(s) = stdin {
        c.stdin.take().unwrap().write_all(s.as_bytes()).unwrap();
    }
    drop(c.stdin.take());
    let o = c.wait_with_output().unwrap();
    (
        o.status.code(),
        String::from_utf8_lossy(&o.stdout).into_owned(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

/// The arrays of an .npz: name -> (shape, values as u64 / i64 widened to i128).
fn read_npz(p: &Path) -> std::collections::BTreeMap<String, (Vec<u64>, Vec<i128>)> {
    let f = std::fs::File::open(p).unwrap();
    let mut z = zip::ZipArchive::new(f).unwrap();
    let mut out = std::collections::BTreeMap::new();
    for i in 0..z.len() {
        let mut e = z.by_index(i).unwrap();
        let name = e.name().unwrap().trim_end_matches(".npy").to_string();
        let mut bytes = Vec::new();
        e.read_to_end(&mut bytes).unwrap();
        let npy = npyz::NpyFile::new(&bytes[..]).unwrap();
        let shape = npy.shape().to_vec();
        let vals: Vec<i128> = match npy.dtype() {
            npyz::DType::Plain(t) if t.type_char() == npyz::TypeChar::Uint => npy
                .into_vec::<u32>()
                .unwrap()
                .into_iter()
                .map(i128::from)
                .collect(),
            _ => npy
                .into_vec::<i64>()
                .unwrap()
                .into_iter()
                .map(i128::from)
                .collect(),
        };
        out.insert(name, (shape, vals));
    }
    out
}

#[test]
fn export_reads_back_in_every_format() {
    let dir = std::env::temp_dir().join(format!("starplex-cli-export-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let m = mesh(&dir);
    let m = m.to_str().unwrap();
    let ids: Vec<String> = (0..17).map(|i| i.to_string()).collect();
    let mut q = vec![
        "query",
        m,
        "--structure",
        "ia-star",
        "--relation",
        "vt",
        "vv",
        "link",
        "--json",
        "--vertex",
    ];
    q.extend(ids.iter().map(|s| s.as_str()));
    let (code, out, err) = run(&q, None);
    assert_eq!(code, Some(0), "{err}");
    let want: Vec<Value> = serde_json::from_str(&out).unwrap();
    assert_eq!(want.len(), 17);
    // --relation filters the objects
    let keys: Vec<&String> = want[0].as_object().unwrap().keys().collect();
    assert_eq!(
        keys,
        [
            "incident_top_cells",
            "link_f_vector",
            "link_maximal_simplices",
            "vertex",
            "vv"
        ]
    );
    let (_, out1, _) = run(
        &["query", m, "--relation", "vv", "--json", "--vertex", "5"],
        None,
    );
    let one: Value = serde_json::from_str(&out1).unwrap();
    assert_eq!(one[0].as_object().unwrap().len(), 2, "{one}");

    for s in ["ia-star", "stellar", "ig", "simplex-tree", "vt"] {
        for (rel, key) in [("vt", "incident_top_cells"), ("vv", "vv")] {
            // .npz
            let npz = dir.join(format!("{s}-{rel}.npz"));
            let (code, _, err) = run(
                &[
                    "query",
                    m,
                    "--structure",
                    s,
                    "--relation",
                    rel,
                    "--all",
                    "--out",
                    npz.to_str().unwrap(),
                ],
                None,
            );
            assert_eq!(code, Some(0), "{s} {rel}: {err}");
            let a = read_npz(&npz);
            let (_, off) = &a["offsets"];
            let (_, val) = &a["values"];
            assert_eq!(a["ids"].1.len(), 17);
            for (v, w) in want.iter().enumerate() {
                let got: Vec<i128> = val[off[v] as usize..off[v + 1] as usize].to_vec();
                let exp: Vec<i128> = w[key]
                    .as_array()
                    .unwrap()
                    .iter()
                    .map(|x| x.as_i64().unwrap() as i128)
                    .collect();
                assert_eq!(got, exp, "{s} {rel} npz vertex {v}");
            }
            // .jsonl
            let jl = dir.join(format!("{s}-{rel}.jsonl"));
            let (code, _, err) = run(
                &[
                    "query",
                    m,
                    "--structure",
                    s,
                    "--relation",
                    rel,
                    "--all",
                    "--out",
                    jl.to_str().unwrap(),
                ],
                None,
            );
            assert_eq!(code, Some(0), "{s} {rel}: {err}");
            let text = std::fs::read_to_string(&jl).unwrap();
            let lines: Vec<Value> = text
                .lines()
                .map(|l| serde_json::from_str(l).unwrap())
                .collect();
            assert_eq!(lines.len(), 17);
            for (l, w) in lines.iter().zip(&want) {
                assert_eq!(l["vertex"], w["vertex"]);
                assert_eq!(l[key], w[key], "{s} {rel} jsonl");
            }
            // .csv
            let csv = dir.join(format!("{s}-{rel}.csv"));
            let (code, _, err) = run(
                &[
                    "query",
                    m,
                    "--structure",
                    s,
                    "--relation",
                    rel,
                    "--all",
                    "--out",
                    csv.to_str().unwrap(),
                ],
                None,
            );
            assert_eq!(code, Some(0), "{s} {rel}: {err}");
            let text = std::fs::read_to_string(&csv).unwrap();
            let mut rows = vec![Vec::<i64>::new(); 17];
            for l in text.lines().skip(1) {
                let (a, b) = l.split_once(',').unwrap();
                rows[a.parse::<usize>().unwrap()].push(b.parse().unwrap());
            }
            for (r, w) in rows.iter().zip(&want) {
                let exp: Vec<i64> = w[key]
                    .as_array()
                    .unwrap()
                    .iter()
                    .map(|x| x.as_i64().unwrap())
                    .collect();
                assert_eq!(r, &exp, "{s} {rel} csv");
            }
        }
    }
    // link: per-level arrays whose sizes are the link f-vectors
    let npz = dir.join("link.npz");
    let (code, _, err) = run(
        &[
            "query",
            m,
            "--relation",
            "link",
            "--all",
            "--out",
            npz.to_str().unwrap(),
        ],
        None,
    );
    assert_eq!(code, Some(0), "{err}");
    let a = read_npz(&npz);
    for (v, w) in want.iter().enumerate() {
        let f: Vec<i128> = (0..2)
            .map(|p| {
                let off = &a[&format!("offsets_{p}")].1;
                off[v + 1] - off[v]
            })
            .collect();
        let exp = &w["link_f_vector"];
        for (p, n) in f.iter().enumerate() {
            assert_eq!(
                *n,
                exp.get(p).and_then(Value::as_i64).unwrap_or(0) as i128,
                "link of {v}"
            );
        }
    }
    assert_eq!(a["values_1"].0[1], 2, "link edges are (n, 2)");
    let jl = dir.join("link.jsonl");
    let (code, _, _) = run(
        &[
            "query",
            m,
            "--relation",
            "link",
            "--all",
            "--out",
            jl.to_str().unwrap(),
        ],
        None,
    );
    assert_eq!(code, Some(0));
    let text = std::fs::read_to_string(&jl).unwrap();
    for (l, w) in text.lines().zip(&want) {
        let l: Value = serde_json::from_str(l).unwrap();
        let sizes: Vec<usize> = l["link"]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_array().unwrap().len())
            .collect();
        let exp: Vec<usize> = w["link_f_vector"]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_u64().unwrap() as usize)
            .collect();
        assert_eq!(sizes, exp);
    }
    // pfaces: every simplex of every level, as many as the f-vector says
    let npz = dir.join("faces.npz");
    let (code, _, err) = run(
        &[
            "query",
            m,
            "--relation",
            "pfaces",
            "--all",
            "--out",
            npz.to_str().unwrap(),
        ],
        None,
    );
    assert_eq!(code, Some(0), "{err}");
    let a = read_npz(&npz);
    assert_eq!(a["faces_0"].0, [17, 1]);
    assert_eq!(a["faces_1"].0, [34, 2]); // 12 + 12 + 9 grid edges and the dangling one
    assert_eq!(a["faces_2"].0, [18, 3]);
    // adj --all: per top cell, the adjacent simplices; ia-star: adjacent top ids
    let jl = dir.join("tt.jsonl");
    let (code, _, err) = run(
        &[
            "query",
            m,
            "--relation",
            "ia-star",
            "--all",
            "--out",
            jl.to_str().unwrap(),
        ],
        None,
    );
    assert_eq!(code, Some(0), "{err}");
    let first: Value = serde_json::from_str(
        std::fs::read_to_string(&jl)
            .unwrap()
            .lines()
            .next()
            .unwrap(),
    )
    .unwrap();
    assert_eq!(
        first,
        serde_json::json!({"cell": 0, "adjacent_top_cells": [1, 3]})
    );
    // --vertex-file and standard input
    let f = dir.join("ids.txt");
    std::fs::write(&f, "3, 5\n7\n").unwrap();
    let (code, out, err) = run(
        &["query", m, "--json", "--vertex-file", f.to_str().unwrap()],
        None,
    );
    assert_eq!(code, Some(0), "{err}");
    let got: Vec<Value> = serde_json::from_str(&out).unwrap();
    assert_eq!(
        got.iter()
            .map(|o| o["vertex"].as_u64().unwrap())
            .collect::<Vec<_>>(),
        [3, 5, 7]
    );
    let jl = dir.join("some.jsonl");
    let (code, _, err) = run(
        &[
            "query",
            m,
            "--relation",
            "vv",
            "--vertex-file",
            "-",
            "--out",
            jl.to_str().unwrap(),
        ],
        Some("16 0"),
    );
    assert_eq!(code, Some(0), "{err}");
    let text = std::fs::read_to_string(&jl).unwrap();
    assert_eq!(text.lines().count(), 2);
    assert!(text.starts_with("{\"vertex\":16,\"vv\":[15]}"), "{text}");
    // errors: exit 2, nothing written
    for (args, msg) in [
        (
            vec!["--all", "--out", "x.txt"],
            "writes .jsonl, .npz or .csv",
        ),
        (
            vec!["--vertex", "99", "--out", "x.jsonl"],
            "vertex 99 out of range",
        ),
        (
            vec!["--vertex-file", "/nonexistent/ids"],
            "/nonexistent/ids",
        ),
    ] {
        let mut a = vec!["query", m];
        let owned: Vec<String> = args
            .iter()
            .map(|s| {
                if s.starts_with("x.") {
                    dir.join(s).to_str().unwrap().to_string()
                } else {
                    s.to_string()
                }
            })
            .collect();
        a.extend(owned.iter().map(|s| s.as_str()));
        let (code, _, err) = run(&a, None);
        assert_eq!(code, Some(2), "{args:?}: {err}");
        assert!(err.contains(msg), "{args:?}: {err}");
    }
    assert!(!dir.join("x.jsonl").exists());
    std::fs::write(&f, "3 x\n").unwrap();
    let (code, _, err) = run(&["query", m, "--vertex-file", f.to_str().unwrap()], None);
    assert_eq!(code, Some(2));
    assert!(err.contains("ids.txt:1: 'x' is not a vertex id"), "{err}");
    std::fs::remove_dir_all(&dir).ok();
}

/// `adj --all` of a pure simplicial complex of at least 1024 cells reads every cell's facet
/// neighbours at once (`batch::facet_neighbours_all`): each line equals the one-cell answer (a
/// coboundary per facet), on random tetrahedra over 40 vertices (facets in many cells), for the
/// VT index and the Stellar tree.
#[test]
fn adjacent_tops_in_bulk_equal_one_cell_at_a_time() {
    use starplex::cell::CellKind;
    use starplex::complex::{BuildOptions, ComplexBuilder};
    use starplex::structures::Structure;
    use starplex_cli::export::{write_mapped, RelationKind};
    let mut b = ComplexBuilder::new(3).unwrap();
    for i in 0..40u32 {
        b.push_vertex(&[i as f64, (i * i % 7) as f64, (i % 5) as f64])
            .unwrap();
    }
    let (mut x, mut seen) = (12345u64, std::collections::BTreeSet::new());
    while seen.len() < 2500 {
        let mut c = Vec::new();
        while c.len() < 4 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let v = (x % 40) as u32;
            if !c.contains(&v) {
                c.push(v);
            }
        }
        let mut key = c.clone();
        key.sort_unstable();
        if seen.insert(key) {
            b.push_cell(CellKind::Simplex(3), &c).unwrap();
        }
    }
    let k = b.build(&BuildOptions::default()).unwrap().0;
    let dir = std::env::temp_dir().join(format!("starplex-adj-bulk-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for st in [Structure::Vt, Structure::Stellar] {
        let s = st.build(&k, &Default::default()).unwrap();
        let all = dir.join("all.jsonl");
        write_mapped(s.as_ref(), RelationKind::Adj, None, true, &all, None).unwrap();
        let lines: Vec<String> = std::fs::read_to_string(&all)
            .unwrap()
            .lines()
            .map(String::from)
            .collect();
        assert_eq!(lines.len(), 2500);
        let one = dir.join("one.jsonl");
        for c in (0..2500u32).step_by(7) {
            write_mapped(s.as_ref(), RelationKind::Adj, Some(&[c]), true, &one, None).unwrap();
            let want = std::fs::read_to_string(&one).unwrap();
            assert_eq!(lines[c as usize], want.trim_end(), "{st:?}: cell {c}");
        }
    }
    std::fs::remove_dir_all(&dir).ok();
}
