//! `starplex simplify`: the JSON report on the bundled elephant (genus kept), and exit status 2
//! with nothing written on bad input (targets, a quad mesh, an empty complex).
use std::path::{Path, PathBuf};
use std::process::Command;

fn starplex(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_starplex"))
        .args(args)
        .output()
        .unwrap()
}

fn tmpdir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!(
        "starplex-cli-simplify-{name}-{}",
        std::process::id()
    ));
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn elephant() -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../data/elephant.off")
        .to_str()
        .unwrap()
        .to_string()
}

#[test]
fn simplify_elephant_report() {
    let d = tmpdir("elephant");
    let out = d.join("out.off");
    for mode in ["qem", "homology"] {
        let o = starplex(&[
            "simplify",
            &elephant(),
            out.to_str().unwrap(),
            "--ratio",
            "0.1",
            "--mode",
            mode,
            "--json",
        ]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
        assert_eq!(v["mode"], mode);
        assert_eq!(v["before"]["euler_characteristic"], -4);
        assert_eq!(v["after"]["euler_characteristic"], -4);
        assert_eq!(v["after"]["betti_z2"], serde_json::json!([1, 6, 1]));
        assert_eq!(v["after"]["non_manifold_edges"], 0);
        assert_eq!(v["topology_kept"], true);
        assert!(v["n_contractions"].as_u64().unwrap() > 2000);
        assert!(v["after"]["n_cells"].as_u64().unwrap() <= 556);
        if mode == "qem" {
            assert!(v["max_error"].as_f64().is_some());
        }
        if cfg!(target_os = "linux") {
            // the simplification's own peak over the loaded input
            let m = &v["memory"];
            let (peak, before) = (
                m["peak_rss"].as_u64().unwrap(),
                m["rss_before"].as_u64().unwrap(),
            );
            assert_eq!(
                m["extra_over_loaded"].as_u64().unwrap(),
                peak.saturating_sub(before)
            );
            assert!(m["complex_bytes"].as_u64().unwrap() > 0);
        }
        assert!(out.exists());
    }
}

#[test]
fn simplify_human_report_reads_as_numbers() {
    let d = tmpdir("human");
    let out = d.join("out.off");
    let o = starplex(&[
        "simplify",
        &elephant(),
        out.to_str().unwrap(),
        "--ratio",
        "0.1",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(!text.contains("Some("), "{text}");
    let line = |key: &str| {
        text.lines()
            .find(|l| l.trim_start().starts_with(key))
            .unwrap_or_else(|| panic!("no {key} line in {text}"))
            .to_string()
    };
    assert!(line("Euler char.").ends_with("-4 -> -4"), "{text}");
    assert!(
        line("Betti (Z/2)").ends_with("[1, 6, 1] -> [1, 6, 1]"),
        "{text}"
    );
}

#[test]
fn simplify_bad_input_exits_2_and_writes_nothing() {
    let d = tmpdir("bad");
    let out = d.join("out.off");
    let el = elephant();
    for args in [
        vec!["--faces", "1000000"],
        vec!["--vertices", "1000000"],
        vec!["--ratio", "-0.5"],
        vec!["--ratio", "2"],
        vec!["--max-error", "-1"],
        vec!["--mode", "nope"],
    ] {
        let mut a = vec!["simplify", el.as_str(), out.to_str().unwrap()];
        a.extend(args.iter().copied());
        let o = starplex(&a);
        assert_eq!(
            o.status.code(),
            Some(2),
            "{args:?}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
        assert!(!out.exists(), "{args:?} wrote the output");
    }
    // a quad: triangulate first
    let q = d.join("quad.spx");
    std::fs::write(&q, "SPX 1\n2 4 1\n0 0\n1 0\n1 1\n0 1\nquad 4 0 1 2 3\n").unwrap();
    let o = starplex(&["simplify", q.to_str().unwrap(), out.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("--triangulate"));
    assert!(!out.exists());
    // empty
    let e = d.join("empty.off");
    std::fs::write(&e, "OFF\n0 0 0\n").unwrap();
    let o = starplex(&["simplify", e.to_str().unwrap(), out.to_str().unwrap()]);
    assert_eq!(
        o.status.code(),
        Some(2),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(!out.exists());
}
