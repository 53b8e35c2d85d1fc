//! A tree saved by `starplex stellar --save` is used directly by `stellar`, `validate` and
//! `query --structure stellar` (memory-mapped, no rebuild), with the same answers as the mesh;
//! the verbs that need the mesh (`info`, `convert`, ...) read the mesh it holds (its
//! coordinates are saved with it), and say what reads a tree saved without them.
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
    // the verbs that need a mesh read a saved tree as the mesh it was built from
    let strip = |mut v: serde_json::Value| {
        for k in ["timings", "format", "notes"] {
            v.as_object_mut().unwrap().remove(k);
        }
        v
    };
    let (c1, a, e1) = run(&["info", "--json"], &mesh);
    let (c2, b, e2) = run(&["info", "--json"], &tree);
    assert_eq!((c1, c2), (Some(0), Some(0)), "{e1} {e2}");
    assert_eq!(b["format"], "tree");
    assert_eq!(strip(a), strip(b));
    let (out1, out2) = (dir.join("from_mesh.spx"), dir.join("from_tree.spx"));
    for (from, to) in [(&mesh, &out1), (&tree, &out2)] {
        let (code, _, err) = run(&["convert", to.to_str().unwrap()], from);
        assert_eq!(code, Some(0), "{err}");
    }
    assert_eq!(std::fs::read(&out1).unwrap(), std::fs::read(&out2).unwrap());
    // re-saving a loaded tree keeps its coordinates
    let again = dir.join("again.tree");
    let (code, _, err) = run(&["stellar", "--save", again.to_str().unwrap()], &tree);
    assert_eq!(code, Some(0), "{err}");
    let (code, c, err) = run(&["info", "--json"], &again);
    assert_eq!(code, Some(0), "{err}");
    assert_eq!(c["f_vector"], serde_json::json!([60, 255, 340, 144]));
    // a tree saved without coordinates (the library's `save` of a tree built in memory) says
    // what reads it
    let k = starplex::io::read(&mesh, &Default::default())
        .unwrap()
        .complex;
    let t = starplex::stellar::StellarTree::build(&k, &Default::default()).unwrap();
    let bare = dir.join("bare.tree");
    t.save(&bare).unwrap();
    for verb in [&["info"][..], &["convert", "/dev/null", "--to", "off"][..]] {
        let (code, _, err) = run(verb, &bare);
        assert_eq!(code, Some(2), "{verb:?}: {err}");
        assert!(err.contains("holds no coordinates"), "{verb:?}: {err}");
        assert!(err.contains("`stellar`, `validate`"), "{err}");
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
