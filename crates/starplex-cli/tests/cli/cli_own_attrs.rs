//! `convert` to starplex's own formats keeps the attributes (no "not written" note) and `info`
//! shows them read back: a `.vtu` with point and cell data through `.spx`, `.spb`, and gmsh 2.2
//! binary (`--to msh22-binary`, tags only); `stellar --save` keeps them in the saved tree
//! (`stellar SAVED --json` lists them).
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!(
        "starplex-cli-own-attrs-{name}-{}",
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn run(args: &[&str]) -> Output {
    let o = Command::new(env!("CARGO_BIN_EXE_starplex"))
        .args(args)
        .output()
        .unwrap();
    assert!(
        o.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    o
}

fn info_attrs(p: &Path) -> serde_json::Value {
    let o = run(&["info", "--json", p.to_str().unwrap()]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    v["attributes"].clone()
}

#[test]
fn spx_and_spb_keep_attributes_and_info_shows_them() {
    let src =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../starplex/tests/data/io/attrs_ascii.vtu");
    let want = info_attrs(&src);
    let n = want["vertex"].as_array().unwrap().len() + want["cell"].as_array().unwrap().len();
    assert!(n >= 2, "the fixture has attributes: {want}");
    let d = dir("own");
    for name in ["a.spx", "a.spb"] {
        let out = d.join(name);
        let o = run(&["convert", src.to_str().unwrap(), out.to_str().unwrap()]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!err.contains("not written"), "{name}: {err}");
        assert_eq!(info_attrs(&out), want, "{name}");
        // and on to .vtu again: the same attributes
        let back = d.join(format!("{name}.vtu"));
        run(&["convert", out.to_str().unwrap(), back.to_str().unwrap()]);
        assert_eq!(info_attrs(&back), want, "{name} -> vtu");
    }
    let text = std::fs::read_to_string(d.join("a.spx")).unwrap();
    assert!(text.starts_with("SPX 2\n") && text.contains("\nattribute "));
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn msh22_binary_is_a_format_name() {
    let src =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../starplex/tests/data/io/gmsh_22_ascii.msh");
    let d = dir("msh");
    let out = d.join("b.msh");
    run(&[
        "convert",
        src.to_str().unwrap(),
        out.to_str().unwrap(),
        "--to",
        "msh22-binary",
    ]);
    assert!(std::fs::read(&out)
        .unwrap()
        .starts_with(b"$MeshFormat\n2.2 1 8\n\x01\0\0\0\n"));
    assert_eq!(info_attrs(&out), info_attrs(&src));
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn saved_stellar_trees_keep_the_attributes() {
    let src =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../starplex/tests/data/io/attrs_ascii.vtu");
    let want = info_attrs(&src);
    let d = dir("tree");
    let tree = d.join("t.tree");
    let o = run(&[
        "stellar",
        src.to_str().unwrap(),
        "--kv",
        "1",
        "--save",
        tree.to_str().unwrap(),
        "--json",
    ]);
    let built: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(built["attributes"], want);
    let o = run(&["stellar", tree.to_str().unwrap(), "--json"]);
    let loaded: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(loaded["attributes"], want);
    let _ = std::fs::remove_dir_all(&d);
}
