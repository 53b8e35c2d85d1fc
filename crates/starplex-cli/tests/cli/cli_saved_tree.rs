//! A tree saved by `starplex stellar --save` is used directly by `stellar`, `validate` and
//! `query --structure stellar` (memory-mapped, no rebuild), with the same answers as the mesh;
//! the verbs that need the mesh's coordinates (`info`, `convert`, ...) say so.
use std::path::Path;
use std::process::Command;

fn run(args: &[&str], file: &Path) -> (Option<i32>, serde_json::Value, String) {
    let mut c = Command::new(env!("CARGO_BIN_EXE_starplex"));
    c.arg("--quiet").arg(args[0]).arg(file).args(&args[1..]);
    let o = c.output().unwrap();
    let v = serde_json::from_slice(&o.stdout).unwrap_or(serde_json::Value::Null);
    (
        o.status.code(),
        v,
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

fn without_timings(mut v: serde_json::Value) -> serde_json::Value {
    if let Some(o) = v.as_object_mut() {
        o.remove("timings");
    }
    v
}

#[test]
fn a_saved_tree_answers_like_the_mesh() {
    let dir = std::env::temp_dir().join(format!("starplex-cli-saved-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mesh = dir.join("g.spx");
    let tree = dir.join("g.tree");
    let st = Command::new(env!("CARGO_BIN_EXE_starplex"))
        .args(["--quiet", "generate", "grid", "4", "3", "2", "-o"])
        .arg(&mesh)
        .status()
        .unwrap();
    assert!(st.success());
    let (code, built, err) = run(
        &[
            "stellar",
            "--kv",
            "5",
            "--json",
            "--save",
            tree.to_str().unwrap(),
        ],
        &mesh,
    );
    assert_eq!(code, Some(0), "{err}");
    let (code, loaded, err) = run(&["stellar", "--json"], &tree);
    assert_eq!(code, Some(0), "{err}");
    assert!(loaded["timings"]["load_s"].as_f64().is_some());
    assert_eq!(without_timings(built), without_timings(loaded));
    for rel in ["vt", "vv", "link", "star", "adj"] {
        let q = [
            "query",
            "--structure",
            "stellar",
            "--relation",
            rel,
            "--json",
            "--vertex",
            "0",
            "7",
            "20",
            "59",
        ];
        let (c1, a, e1) = run(&q, &mesh);
        let (c2, b, e2) = run(&q, &tree);
        assert_eq!((c1, c2), (Some(0), Some(0)), "{e1} {e2}");
        assert_eq!(a, b, "{rel}");
    }
    let (c1, a, _) = run(&["validate", "--json"], &mesh);
    let (c2, b, _) = run(&["validate", "--json"], &tree);
    assert_eq!((c1, c2), (Some(0), Some(0)));
    assert_eq!(without_timings(a), without_timings(b));
    // other structures need the mesh
    let (code, _, err) = run(
        &[
            "query",
            "--structure",
            "ia-star",
            "--relation",
            "vt",
            "--vertex",
            "0",
        ],
        &tree,
    );
    assert_eq!(code, Some(2));
    assert!(err.contains("--structure stellar"), "{err}");
    // the verbs that need a mesh recognise a saved tree and say what reads it
    for verb in [&["info"][..], &["convert", "/dev/null", "--to", "off"][..]] {
        let (code, _, err) = run(verb, &tree);
        assert_eq!(code, Some(2), "{verb:?}: {err}");
        assert!(err.contains("is a saved Stellar tree"), "{verb:?}: {err}");
        assert!(
            err.contains("hint: pass the mesh it was built from"),
            "{err}"
        );
    }
    // a damaged tree is an input error, not a panic
    let bytes = std::fs::read(&tree).unwrap();
    let cut = dir.join("cut.tree");
    std::fs::write(&cut, &bytes[..bytes.len() / 2]).unwrap();
    let (code, _, err) = run(&["validate"], &cut);
    assert_eq!(code, Some(2), "{err}");
    assert!(err.contains("hint:"), "{err}");
    std::fs::remove_dir_all(&dir).ok();
}
