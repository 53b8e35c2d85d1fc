//! `starplex simplify` with labels and kept vertices: a Medit surface whose triangles carry
//! references 1 and 2 keeps them by default (the report says so), the interface vertices stay;
//! `--ignore-labels`, `--keep-vertices FILE`, the Hausdorff estimate in the JSON and human
//! reports, exit 2 on an unknown label or an out-of-range kept vertex.
use std::fmt::Write;
use std::path::PathBuf;
use std::process::Command;

use starplex::attr::{AttrTarget, AttrValues};

fn starplex(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_starplex"))
        .args(args)
        .output()
        .unwrap()
}

fn tmpdir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!(
        "starplex-cli-simplify-labels-{name}-{}",
        std::process::id()
    ));
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// A flat n×n square in triangles, reference 2 on x < n/2 and 1 elsewhere, as Medit text.
fn medit_square(n: u32) -> String {
    let mut s = String::from("MeshVersionFormatted 2\nDimension 3\nVertices\n");
    writeln!(s, "{}", (n + 1) * (n + 1)).unwrap();
    for j in 0..=n {
        for i in 0..=n {
            writeln!(s, "{i} {j} 0 0").unwrap();
        }
    }
    writeln!(s, "Triangles\n{}", 2 * n * n).unwrap();
    for j in 0..n {
        for i in 0..n {
            let v = j * (n + 1) + i + 1; // 1-based
            let r = if i < n / 2 { 2 } else { 1 };
            writeln!(s, "{} {} {} {r}", v, v + 1, v + n + 2).unwrap();
            writeln!(s, "{} {} {} {r}", v, v + n + 2, v + n + 1).unwrap();
        }
    }
    s.push_str("End\n");
    s
}

fn json(o: &std::process::Output) -> serde_json::Value {
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    serde_json::from_slice(&o.stdout).unwrap()
}

#[test]
fn medit_references_are_kept_by_default() {
    let d = tmpdir("medit");
    let input = d.join("square.mesh");
    std::fs::write(&input, medit_square(16)).unwrap();
    let out = d.join("out.mesh");
    let (i, o) = (input.to_str().unwrap(), out.to_str().unwrap());
    let v = json(&starplex(&["simplify", i, o, "--ratio", "0.1", "--json"]));
    assert_eq!(v["labels_kept"], "medit:ref");
    assert_eq!(v["locked_vertices"], 17); // the line x = 8
    assert_eq!(v["attributes"]["cell"], serde_json::json!(["medit:ref"]));
    let diag = v["hausdorff"]["input_diagonal"].as_f64().unwrap();
    assert!(v["hausdorff"]["max"].as_f64().unwrap() < 1e-6 * diag);
    assert_eq!(v["topology_kept"], true);
    // the output has both references, and the vertices of x = 8 are all there
    let k = starplex::io::read(&out, &Default::default())
        .unwrap()
        .complex;
    let Some(AttrValues::Int(refs)) = k
        .attributes()
        .get(AttrTarget::Cell, "medit:ref")
        .map(|a| a.values.clone())
    else {
        panic!("no medit:ref in the output");
    };
    assert!(refs.contains(&1) && refs.contains(&2));
    let on_line = (0..k.n_vertices() as u32)
        .filter(|&u| k.point(starplex::ids::VertexId(u))[0] == 8.0)
        .count();
    assert_eq!(on_line, 17);
    // every triangle of reference 2 lies left of the line, of 1 right of it
    for (c, r) in k.cells().zip(&refs) {
        for &u in c.vertices {
            let x = k.point(starplex::ids::VertexId(u))[0];
            assert!(
                if *r == 2 { x <= 8.0 } else { x >= 8.0 },
                "ref {r} at x = {x}"
            );
        }
    }
    // the human report says it too
    let h = starplex(&["simplify", i, o, "--ratio", "0.1"]);
    let text = String::from_utf8_lossy(&h.stdout);
    assert!(text.contains("medit:ref kept"), "{text}");
    assert!(text.contains("Hausdorff (est.)"), "{text}");
    // --ignore-labels: not kept, and the report says which labels there were
    let h = starplex(&["simplify", i, o, "--ratio", "0.1", "--ignore-labels"]);
    let text = String::from_utf8_lossy(&h.stdout);
    assert!(
        text.contains("not kept (cell attributes: medit:ref)"),
        "{text}"
    );
    let v = json(&starplex(&[
        "simplify",
        i,
        o,
        "--ratio",
        "0.1",
        "--ignore-labels",
        "--json",
    ]));
    assert_eq!(v["labels_kept"], serde_json::Value::Null);
    assert_eq!(v["locked_vertices"], 0);
}

#[test]
fn kept_vertices_from_a_file() {
    let d = tmpdir("keep");
    let input = d.join("square.mesh");
    std::fs::write(&input, medit_square(12)).unwrap();
    let ids = d.join("keep.txt");
    // the vertices (3, 3), (5, 9), (10, 2): ids j * 13 + i
    std::fs::write(&ids, "42, 122\n36\n").unwrap();
    let out = d.join("out.off");
    let (i, o, f) = (
        input.to_str().unwrap(),
        out.to_str().unwrap(),
        ids.to_str().unwrap(),
    );
    let v = json(&starplex(&[
        "simplify",
        i,
        o,
        "--ratio",
        "0.02",
        "--ignore-labels",
        "--keep-vertices",
        f,
        "--json",
    ]));
    assert_eq!(v["locked_vertices"], 3);
    let k = starplex::io::read(&out, &Default::default())
        .unwrap()
        .complex;
    for p in [[3.0, 3.0], [5.0, 9.0], [10.0, 2.0]] {
        assert!(
            (0..k.n_vertices() as u32).any(|u| k.point(starplex::ids::VertexId(u))[..2] == p),
            "{p:?} removed"
        );
    }
    // bad input: exit 2, nothing written
    std::fs::write(&ids, "1000000\n").unwrap();
    let out2 = d.join("out2.off");
    let o2 = out2.to_str().unwrap();
    for args in [
        vec!["--keep-vertices", f],
        vec!["--keep-labels", "nope"],
        vec!["--keep-vertex-attribute", "nope"],
    ] {
        let mut a = vec!["simplify", i, o2];
        a.extend(args.iter().copied());
        let r = starplex(&a);
        assert_eq!(
            r.status.code(),
            Some(2),
            "{args:?}: {}",
            String::from_utf8_lossy(&r.stderr)
        );
        assert!(!out2.exists());
    }
}
