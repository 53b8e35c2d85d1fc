//! `starplex homology` and `info --betti`: answers, JSON keys, generators file, and exit status
//! 2 on bad input.
use std::process::Command;

fn starplex(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_starplex"))
        .args(args)
        .output()
        .unwrap()
}

/// A 3 x 3 triangulated torus as .spx.
fn torus_file(dir: &std::path::Path) -> std::path::PathBuf {
    let n = 3u32;
    let v = |i: u32, j: u32| (i % n) * n + j % n;
    let mut s = format!("SPX 1\n2 {} {}\n", n * n, 2 * n * n);
    for i in 0..n {
        for j in 0..n {
            s += &format!("{i} {j}\n");
        }
    }
    for i in 0..n {
        for j in 0..n {
            s += &format!("tri 3 {} {} {}\n", v(i, j), v(i + 1, j), v(i + 1, j + 1));
            s += &format!("tri 3 {} {} {}\n", v(i, j), v(i + 1, j + 1), v(i, j + 1));
        }
    }
    let p = dir.join("torus.spx");
    std::fs::write(&p, s).unwrap();
    p
}

fn tmpdir(name: &str) -> std::path::PathBuf {
    let d = std::env::temp_dir().join(format!(
        "starplex-cli-homology-{name}-{}",
        std::process::id()
    ));
    std::fs::create_dir_all(&d).unwrap();
    d
}

#[test]
fn homology_of_a_torus() {
    let d = tmpdir("torus");
    let f = torus_file(&d);
    let o = starplex(&["homology", f.to_str().unwrap(), "--json", "--per-component"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["betti_z2"], serde_json::json!([1, 2, 1]));
    let s = &v["components"][0]["surface"];
    assert_eq!(s["orientable"], true);
    assert_eq!(s["genus"], 1);
    let o = starplex(&[
        "homology",
        f.to_str().unwrap(),
        "--field",
        "z",
        "--threads",
        "1",
    ]);
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(text.contains("H0 = Z, H1 = Z^2, H2 = Z"), "{text}");
    // generators as OBJ groups
    let g = d.join("gens.obj");
    let o = starplex(&[
        "homology",
        f.to_str().unwrap(),
        "--generators",
        g.to_str().unwrap(),
    ]);
    assert!(o.status.success());
    let obj = std::fs::read_to_string(&g).unwrap();
    assert!(obj.contains("g h1_0") && obj.contains("g h1_1") && obj.contains("g h2_0"));
    // each H_1 class is one closed polyline, once around the 3 x 3 torus (3 edges)
    for g in ["g h1_0\n", "g h1_1\n"] {
        let after = &obj[obj.find(g).unwrap() + g.len()..];
        let line = after.lines().next().unwrap();
        let ids: Vec<&str> = line.split_whitespace().skip(1).collect();
        assert!(
            line.starts_with("l ") && ids.len() == 4 && ids[0] == ids[3],
            "{line}"
        );
        assert!(
            after.lines().nth(1).unwrap().starts_with("g "),
            "one line per loop"
        );
    }
    // info --betti
    let o = starplex(&["info", f.to_str().unwrap(), "--json", "--betti"]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["betti_z2"], serde_json::json!([1, 2, 1]));
}

#[test]
fn bad_input_exits_with_status_2() {
    let d = tmpdir("bad");
    let f = torus_file(&d);
    let f = f.to_str().unwrap();
    for args in [
        vec!["homology", f, "--field", "r"],
        vec!["homology", f, "--field", "4"],
        vec!["homology", f, "--generators", "/nonexistent-dir/x.obj"],
        vec!["homology", f, "--field", "q", "--generators", "/tmp/x.obj"],
        vec!["homology", f, "--threads", "0"],
        vec!["homology", "/nonexistent.spx"],
    ] {
        let o = starplex(&args);
        assert_eq!(o.status.code(), Some(2), "{args:?}");
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(err.contains("error"), "{args:?}: {err}");
    }
    let o = starplex(&["homology", f, "--field", "4"]);
    assert!(String::from_utf8_lossy(&o.stderr).contains("4 is not a prime"));
}
