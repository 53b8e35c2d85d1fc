//! CP input (hexahedra, a prism, a quad) through `query` and `compare`: the structures that
//! hold CP cells answer, the simplicial-only ones are refused with a hint (query) or listed as
//! skipped with the reason (compare).
use std::process::Command;

/// Two hexahedra sharing a quad and a prism on the first one's side quad.
const MESH: &str = "SPX 1
3 14 3
0 0 0
1 0 0
1 1 0
0 1 0
0 0 1
1 0 1
1 1 1
0 1 1
2 0 0
2 1 0
2 0 1
2 1 1
1 2 0
1 2 1
hex 8 0 1 2 3 4 5 6 7
hex 8 1 8 9 2 5 10 11 6
prism 6 2 12 3 6 13 7
";

fn run(args: &[&str], file: &std::path::Path) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_starplex"))
        .arg("--quiet")
        .arg(args[0])
        .arg(file)
        .args(&args[1..])
        .output()
        .unwrap()
}

#[test]
fn query_and_compare_on_a_cp_complex() {
    let dir = std::env::temp_dir().join(format!("starplex-cli-cp-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mesh = dir.join("cp.spx");
    std::fs::write(&mesh, MESH).unwrap();
    for s in ["ig", "ia-star", "stellar", "vt"] {
        let o = run(
            &[
                "query",
                "--structure",
                s,
                "--relation",
                "vt",
                "vv",
                "link",
                "--json",
                "--vertex",
                "2",
                "0",
            ],
            &mesh,
        );
        assert!(
            o.status.success(),
            "{s}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
        let got: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
        assert_eq!(
            got[0]["incident_top_cells"],
            serde_json::json!([0, 1, 2]),
            "{s}"
        );
        assert_eq!(got[0]["vv"], serde_json::json!([1, 3, 6, 9, 12]), "{s}");
        assert_eq!(
            got[1]["vv"],
            serde_json::json!([1, 3, 4]),
            "{s}: no diagonal"
        );
        assert!(got[0]["link_f_vector"].is_null(), "{s}");
    }
    for s in ["simplex-tree", "is", "hasse"] {
        let o = run(&["query", "--structure", s, "--vertex", "0"], &mesh);
        assert_eq!(o.status.code(), Some(2), "{s}");
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(err.contains("--structure ig, ia-star"), "{s}: {err}");
    }
    let o = run(&["compare", "--json", "--threads", "1"], &mesh);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let lines: Vec<serde_json::Value> = String::from_utf8_lossy(&o.stdout)
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(lines.len(), 7);
    for l in &lines {
        let name = l["structure"].as_str().unwrap();
        if ["simplex-tree", "is", "hasse"].contains(&name) {
            assert!(l["skipped"].is_string(), "{name}: {l}");
        } else {
            assert!(l["refs_abs"].as_u64().unwrap() > 0, "{name}: {l}");
            assert!(
                l["vt_s"].as_f64().is_some() && l["vv_s"].as_f64().is_some(),
                "{name}"
            );
        }
    }
    std::fs::remove_dir_all(&dir).ok();
}
