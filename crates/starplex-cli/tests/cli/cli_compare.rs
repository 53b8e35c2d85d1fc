//! `starplex compare`: one JSON object per structure, with the same storage on any number of
//! threads.
use std::process::Command;

fn compare(file: &std::path::Path, threads: &str) -> Vec<serde_json::Value> {
    let o = Command::new(env!("CARGO_BIN_EXE_starplex"))
        .args(["--quiet", "compare"])
        .arg(file)
        .args(["--json", "--threads", threads])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    String::from_utf8_lossy(&o.stdout)
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect()
}

#[test]
fn compare_reports_every_structure_on_any_thread_count() {
    let dir = std::env::temp_dir().join(format!("starplex-cli-compare-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mesh = dir.join("g.spx");
    let st = Command::new(env!("CARGO_BIN_EXE_starplex"))
        .args(["--quiet", "generate", "grid", "5", "4", "3", "-o"])
        .arg(&mesh)
        .status()
        .unwrap();
    assert!(st.success());
    let one = compare(&mesh, "1");
    let two = compare(&mesh, "2");
    let names: Vec<&str> = one
        .iter()
        .map(|o| o["structure"].as_str().unwrap())
        .collect();
    assert_eq!(
        names,
        [
            "vt",
            "ia-star",
            "simplex-tree",
            "ig",
            "is",
            "hasse",
            "stellar"
        ]
    );
    for (a, b) in one.iter().zip(&two) {
        assert_eq!(a["threads"], 1);
        assert_eq!(b["threads"], 2);
        for key in ["structure", "refs_abs", "bytes_abs", "refs", "bytes"] {
            assert_eq!(a[key], b[key], "{key}");
        }
        for key in [
            "build_s",
            "vt_s",
            "vv_s",
            "boundary_s",
            "coboundary_s",
            "link_s",
            "pfaces_s",
        ] {
            assert!(a[key].as_f64().unwrap() >= 0.0, "{key}");
        }
    }
    // 5 x 4 x 3 cubes of 6 tetrahedra on 6 x 5 x 4 vertices: IA* holds 4 vertices and 4
    // adjacency slots per tetrahedron and one top per vertex (every vertex star is one cluster)
    assert_eq!(one[1]["refs_abs"], 8 * 360 + 120);
    let o = Command::new(env!("CARGO_BIN_EXE_starplex"))
        .args(["--quiet", "compare"])
        .arg(&mesh)
        .args(["--threads", "0"])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2), "--threads 0 is a usage error");
    std::fs::remove_dir_all(&dir).ok();
}
