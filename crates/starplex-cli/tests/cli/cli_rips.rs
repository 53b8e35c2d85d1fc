//! `starplex rips`, `starplex flag` and `generate sierpinski|quads|hexes`: outputs other commands
//! read, JSON summaries, and bad input refused with exit status 2 and nothing written.
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn dir(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("starplex-cli-rips-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn run(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_starplex"))
        .arg("--quiet")
        .args(args)
        .output()
        .unwrap()
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// Exit status 2, the message contains `needle`, and `out` does not exist.
fn refused(o: &Output, needle: &str, out: &Path) {
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains(needle), "expected '{needle}' in: {err}");
    assert!(!out.exists(), "{} was written", out.display());
}

#[test]
fn rips_writes_a_complex_that_info_reads() {
    let d = dir("ok");
    let pts = d.join("square.xyz");
    // a unit square (with normals after the coordinates, as CGAL's .xyz) and a far point
    std::fs::write(
        &pts,
        "0 0 0 0 0 1\n1 0 0 0 0 1\n1 1 0 0 0 1\n0 1 0 0 0 1\n9 9 9 0 0 1\n",
    )
    .unwrap();
    let out = d.join("sq.spx");
    let o = run(&["rips", s(&pts), "--eps", "1", "-o", s(&out), "--json"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let j: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(j["n_points"], 5);
    assert_eq!(j["n_edges"], 4);
    assert_eq!(j["n_maximal_simplices"], 4);
    assert_eq!(j["maximal_simplices_by_dim"]["1"], 4);
    assert_eq!(j["n_isolated_vertices"], 1);
    let i = run(&["info", s(&out), "--json"]);
    assert!(i.status.success());
    let info: serde_json::Value = serde_json::from_slice(&i.stdout).unwrap();
    assert_eq!(info["euler_characteristic"], 1); // a circle and a point
                                                 // --eps-nn: the median nearest-neighbour distance is 1, so 1.5 x joins the diagonals
    let off = d.join("sq.off");
    let o = run(&["rips", s(&pts), "--eps-nn", "1.5", "-o", s(&off), "--json"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let j: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(j["median_nn_distance"], 1.0);
    assert_eq!(j["maximal_simplices_by_dim"]["3"], 1);
    // .off is written as off-simplices
    let i = run(&["info", s(&off), "--simplices", "--json"]);
    assert!(i.status.success());
    let info: serde_json::Value = serde_json::from_slice(&i.stdout).unwrap();
    assert_eq!(info["dim"], 3);
    // the 1-skeleton of the same
    let o = run(&[
        "rips",
        s(&pts),
        "--eps-nn",
        "1.5",
        "--max-dim",
        "1",
        "-o",
        s(&out),
        "--json",
    ]);
    let j: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(j["maximal_simplices_by_dim"]["1"], 6);
}

#[test]
fn rips_refuses_bad_input() {
    let d = dir("bad");
    let pts = d.join("p.txt");
    std::fs::write(&pts, "0 0\n1 0\n0 1\n").unwrap();
    let out = d.join("never.spx");
    for eps in ["0", "-1", "NaN", "inf"] {
        let o = run(&["rips", s(&pts), "--eps", eps, "-o", s(&out)]);
        refused(&o, "positive finite", &out);
    }
    let o = run(&["rips", s(&pts), "--eps-nn", "0", "-o", s(&out)]);
    refused(&o, "positive finite", &out);
    let ragged = d.join("r.txt");
    std::fs::write(&ragged, "0 0\n1 0\n0 1 2\n").unwrap();
    let o = run(&["rips", s(&ragged), "--eps", "1", "-o", s(&out)]);
    refused(&o, "r.txt:3: 3 columns, but the first row has 2", &out);
    let csv = d.join("c.csv");
    std::fs::write(&csv, "x,y\n0,0\n1,oops\n").unwrap();
    let o = run(&["rips", s(&csv), "--eps", "1", "-o", s(&out)]);
    refused(&o, "c.csv:3: coordinate 2: 'oops' is not a number", &out);
    // a dense cloud over a tiny budget: refused with an estimate
    let dense = d.join("dense.txt");
    let text: String = (0..300)
        .map(|i| format!("{} {}\n", i % 17, i / 17))
        .collect();
    std::fs::write(&dense, text).unwrap();
    let o = run(&[
        "rips",
        s(&dense),
        "--eps",
        "100",
        "--max-memory",
        "1e-6",
        "-o",
        s(&out),
    ]);
    refused(&o, "memory budget", &out);
    assert!(String::from_utf8_lossy(&o.stderr).contains("about"));
}

#[test]
fn flag_reads_edge_lists_and_refuses_bad_lines() {
    let d = dir("flag");
    let edges = d.join("g.csv");
    std::fs::write(
        &edges,
        "source,target,weight\n0,1,0.5\n1,2,1\n2,0,1\n2,3,1\n",
    )
    .unwrap();
    let out = d.join("g.spx");
    let o = run(&[
        "flag",
        s(&edges),
        "-o",
        s(&out),
        "--n-vertices",
        "5",
        "--json",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let j: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(j["maximal_simplices_by_dim"]["2"], 1);
    assert_eq!(j["maximal_simplices_by_dim"]["1"], 1);
    assert_eq!(j["n_isolated_vertices"], 1);
    let h = run(&["homology", s(&out), "--json"]);
    assert!(h.status.success(), "{}", String::from_utf8_lossy(&h.stderr));
    let bad = d.join("bad.txt");
    let never = d.join("never.spx");
    std::fs::write(&bad, "# comment\n0 1\n2 2\n").unwrap();
    let o = run(&["flag", s(&bad), "-o", s(&never)]);
    refused(&o, "bad.txt:3: self-loop at vertex 2", &never);
    std::fs::write(&bad, "0 1\n1 9\n").unwrap();
    let o = run(&["flag", s(&bad), "--n-vertices", "4", "-o", s(&never)]);
    refused(&o, "bad.txt:2: vertex id 9 out of range", &never);
    std::fs::write(&bad, "0 1\n7\n").unwrap();
    let o = run(&["flag", s(&bad), "-o", s(&never)]);
    refused(&o, "bad.txt:2: expected two vertex ids", &never);
    std::fs::write(&bad, "0 1\n-1 2\n").unwrap();
    let o = run(&["flag", s(&bad), "-o", s(&never)]);
    refused(&o, "bad.txt:2: '-1' is not a vertex id", &never);
}

#[test]
fn generators_write_complexes() {
    let d = dir("gen");
    let sier = d.join("s.off");
    let o = run(&[
        "generate",
        "sierpinski",
        "--dim",
        "3",
        "--target",
        "40",
        "--seed",
        "2",
        "-o",
        s(&sier),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let i = run(&["info", s(&sier), "--simplices", "--json"]);
    let info: serde_json::Value = serde_json::from_slice(&i.stdout).unwrap();
    assert_eq!(info["dim"], 3);
    assert!(info["n_top_cells"].as_u64().unwrap() >= 40);
    let o = run(&[
        "generate",
        "sierpinski",
        "--dim",
        "3",
        "--target",
        "4",
        "--p",
        "2",
        "-o",
        s(&d.join("x.spx")),
    ]);
    assert_eq!(o.status.code(), Some(2));
    // a tetrahedral grid -> hexahedra, a triangle grid -> quads
    let tets = d.join("t.spx");
    assert!(run(&["generate", "grid", "2", "1", "1", "-o", s(&tets)])
        .status
        .success());
    let hex = d.join("h.vtk");
    let o = run(&["generate", "hexes", s(&tets), "-o", s(&hex)]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let i = run(&["info", s(&hex), "--json"]);
    let info: serde_json::Value = serde_json::from_slice(&i.stdout).unwrap();
    assert_eq!(info["n_top_cells"], 48);
    assert_eq!(info["euler_characteristic"], 1);
    let tris = d.join("t2.spx");
    assert!(run(&["generate", "grid", "2", "2", "-o", s(&tris)])
        .status
        .success());
    let q = d.join("q.off");
    assert!(run(&["generate", "quads", s(&tris), "-o", s(&q)])
        .status
        .success());
    let o = run(&["generate", "quads", s(&tets), "-o", s(&d.join("never.off"))]);
    refused(&o, "not one of the triangles", &d.join("never.off"));
}

/// A format-1.0 `.npy` of float64, C order.
fn npy_f8(rows: usize, cols: usize, v: &[f64]) -> Vec<u8> {
    let mut h = format!("{{'descr': '<f8', 'fortran_order': False, 'shape': ({rows}, {cols}), }}");
    while (10 + h.len() + 1) % 64 != 0 {
        h.push(' ');
    }
    h.push('\n');
    let mut b = b"\x93NUMPY\x01\x00".to_vec();
    b.extend((h.len() as u16).to_le_bytes());
    b.extend(h.as_bytes());
    for x in v {
        b.extend(x.to_le_bytes());
    }
    b
}

#[test]
fn rips_metrics_and_precomputed_distances() {
    let d = dir("metric");
    let pts = d.join("square.txt");
    std::fs::write(&pts, "0 0\n1 0\n1 1\n0 1\n").unwrap();
    let out = d.join("m.spx");
    let by_dim = |metric: &str, eps: &str| {
        let o = run(&[
            "rips",
            s(&pts),
            "--eps",
            eps,
            "--metric",
            metric,
            "-o",
            s(&out),
            "--json",
        ]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let j: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
        assert_eq!(j["metric"], metric);
        j["maximal_simplices_by_dim"].clone()
    };
    // diagonals: L2 √2, L1 2, L∞ 1
    assert_eq!(by_dim("euclidean", "1.5")["3"], 1);
    assert_eq!(by_dim("manhattan", "1.5")["1"], 4);
    assert_eq!(by_dim("chebyshev", "1")["3"], 1);
    // the same square's L1 matrix, as CSV with a header and as .npy
    let m = [
        0.0, 1.0, 2.0, 1.0, 1.0, 0.0, 1.0, 2.0, 2.0, 1.0, 0.0, 1.0, 1.0, 2.0, 1.0, 0.0,
    ];
    let csv = d.join("d.csv");
    let rows: Vec<String> = m
        .chunks(4)
        .map(|r| format!("{},{},{},{}", r[0], r[1], r[2], r[3]))
        .collect();
    std::fs::write(&csv, format!("a,b,c,d\n{}\n", rows.join("\n"))).unwrap();
    let npy = d.join("d.npy");
    std::fs::write(&npy, npy_f8(4, 4, &m)).unwrap();
    for f in [&csv, &npy] {
        let o = run(&[
            "rips",
            s(f),
            "--eps-nn",
            "1.5",
            "--metric",
            "precomputed",
            "-o",
            s(&out),
            "--json",
        ]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let j: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
        assert_eq!(j["median_nn_distance"], 1.0);
        assert_eq!(j["n_points"], 4);
        assert_eq!(j["maximal_simplices_by_dim"]["1"], 4);
    }
    // not a distance matrix: exit 2, the row and column named, nothing written
    let bad_out = d.join("bad.spx");
    let cases = [
        ("0,1,2\n1,0,2\n", "must be square"),
        (
            "0 1 2\n1 0 3\n2 3.5 0\n",
            "row 1 column 2 is 3 but row 2 column 1 is 3.5",
        ),
        ("0 1\n1 0.25\n", "row 1 column 1: the diagonal must be 0"),
        (
            "0 -1\n-1 0\n",
            "row 0 column 1: -1 is not a finite non-negative distance",
        ),
        ("0 1\n1 0 4\n", "ragged rows"),
    ];
    for (i, (text, needle)) in cases.iter().enumerate() {
        let f = d.join(format!("bad{i}.txt"));
        std::fs::write(&f, text).unwrap();
        let o = run(&[
            "rips",
            s(&f),
            "--eps",
            "1",
            "--metric",
            "precomputed",
            "-o",
            s(&bad_out),
        ]);
        refused(&o, needle, &bad_out);
    }
}

/// `stellar --decomposition graph` on a flag complex (no meaningful coordinates): the same
/// counts and VT answers as the spatial tree, the JSON says which, a saved graph tree reloads
/// as one; a bad value is refused with exit status 2.
#[test]
fn stellar_graph_decomposition_of_a_flag_complex() {
    let d = dir("graph");
    let edges = d.join("g.txt");
    // two 4-cliques joined by a path, and a triangle apart; ids shuffled
    let mut text = String::new();
    for (a, b) in [
        (0, 5),
        (0, 9),
        (0, 2),
        (5, 9),
        (5, 2),
        (9, 2),
        (2, 7),
        (7, 11),
        (11, 1),
        (1, 3),
        (1, 8),
        (1, 10),
        (3, 8),
        (3, 10),
        (8, 10),
        (4, 6),
        (6, 12),
        (12, 4),
    ] {
        text.push_str(&format!("{a} {b}\n"));
    }
    std::fs::write(&edges, text).unwrap();
    let out = d.join("g.spx");
    let o = run(&["flag", s(&edges), "-o", s(&out)]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let stats = |extra: &[&str]| -> serde_json::Value {
        let mut a = vec!["stellar", s(&out), "--kv", "3", "--json", "--bench"];
        a.extend_from_slice(extra);
        let o = run(&a);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        serde_json::from_slice(&o.stdout).unwrap()
    };
    let sp = stats(&[]);
    let gr = stats(&["--decomposition", "graph"]);
    assert_eq!(sp["decomposition"], "spatial");
    assert_eq!(gr["decomposition"], "graph");
    for key in ["n_vertices", "n_top_cells"] {
        assert_eq!(sp[key], gr[key], "{key}");
    }
    assert!(gr["leaf_max_vertices"].as_u64().unwrap() <= 3);
    // a saved graph tree reloads as one, and answers VT, VV and links like the mesh
    let saved = d.join("g.stl");
    let o = run(&[
        "stellar",
        s(&out),
        "--kv",
        "3",
        "--decomposition",
        "graph",
        "--save",
        s(&saved),
        "--json",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let o = run(&["stellar", s(&saved), "--json"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let j: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(j["decomposition"], "graph");
    assert_eq!(j["chi"], gr["chi"]);
    for rel in ["vt", "vv", "link"] {
        let answers = |file: &Path, tag: &str| {
            let f = d.join(format!("{tag}-{rel}.jsonl"));
            let o = run(&[
                "query",
                s(file),
                "--structure",
                "stellar",
                "--relation",
                rel,
                "--all",
                "--out",
                s(&f),
            ]);
            assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
            std::fs::read_to_string(&f).unwrap()
        };
        let (a, b) = (answers(&out, "mesh"), answers(&saved, "tree"));
        assert!(a.lines().count() >= 13, "{rel}: {a}");
        assert_eq!(a, b, "{rel}");
    }
    // a bad value: exit 2, naming the choices
    let o = run(&["stellar", s(&out), "--decomposition", "spectral"]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("spectral") && err.contains("spatial or graph"),
        "{err}"
    );
}
