//! `starplex generate grid`: the written grid reads back as the ball it is, and absurd sizes
//! are refused with status 2 before anything is allocated or written.
use std::process::Command;

fn starplex() -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_starplex"));
    c.arg("--quiet");
    c
}

#[test]
fn a_generated_grid_is_a_ball() {
    let dir = std::env::temp_dir().join(format!("starplex-cli-gen-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("g.spb");
    let st = starplex()
        .args(["generate", "grid", "3", "2", "4", "-o"])
        .arg(&out)
        .status()
        .unwrap();
    assert!(st.success());
    let o = starplex()
        .arg("info")
        .arg(&out)
        .arg("--json")
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let j: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    // 24 cubes, 6 tetrahedra each; (4 x 3 x 5) grid points
    assert_eq!(j["n_top_cells"], 144);
    assert_eq!(j["n_vertices"], 60);
    assert_eq!(j["euler_characteristic"], 1);
    assert_eq!(j["n_faces_shared_by_more_than_2_top_cells"], 0);
    // the boundary: the box has 2 (3x2 + 3x4 + 2x4) = 52 unit squares, 2 triangles each
    assert_eq!(j["n_boundary_faces"], 104);
    let v = starplex()
        .arg("validate")
        .arg(&out)
        .arg("--json")
        .output()
        .unwrap();
    let j: serde_json::Value = serde_json::from_slice(&v.stdout).unwrap();
    assert_eq!(j["pseudo_manifold"], true);
    assert_eq!(j["n_non_manifold_vertices"], 0);
    assert_eq!(j["orientable"], true);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn absurd_grids_are_refused() {
    let out = std::env::temp_dir().join(format!("starplex-cli-gen-big-{}.spb", std::process::id()));
    let o = starplex()
        .args(["generate", "grid", "100000", "100000", "100000", "-o"])
        .arg(&out)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(e.contains("vertices") && e.contains("hint:"), "{e}");
    assert!(!out.exists());
}
