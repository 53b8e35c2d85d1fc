//! `starplex render`: PNG and SVG written, bad input refused with exit status 2 and nothing
//! written.
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn dir() -> PathBuf {
    let d = std::env::temp_dir().join(format!("starplex-cli-render-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn run(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_starplex"))
        .args(args)
        .output()
        .unwrap()
}

/// The two-tetrahedron input, shared by every test of this file. Tests run in parallel threads
/// of one process, so each writes its own copy and renames it into place: a reader never sees a
/// file another test is in the middle of writing (CI once read an empty `pair.mesh`).
fn tet_pair() -> PathBuf {
    let p = dir().join("pair.mesh");
    let tmp = dir().join(format!("pair.mesh.{:?}", std::thread::current().id()));
    std::fs::write(
        &tmp,
        "MeshVersionFormatted 2\nDimension 3\nVertices\n5\n0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\n1 1 1 0\nTetrahedra\n2\n1 2 3 4 0\n5 4 3 2 0\nEnd\n",
    )
    .unwrap();
    std::fs::rename(&tmp, &p).unwrap();
    p
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

#[test]
fn png_and_svg_are_written() {
    let input = tet_pair();
    let png = dir().join("pair.png");
    let out = run(&[
        "render",
        "--quiet",
        s(&input),
        "-o",
        s(&png),
        "--size",
        "320x240",
        "--color",
        "blocks",
        "--kv",
        "2",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let bytes = std::fs::read(&png).unwrap();
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n");
    let svg = dir().join("pair.svg");
    let out = run(&[
        "render",
        "--quiet",
        s(&input),
        "-o",
        s(&svg),
        "--clip",
        "x=0.6",
        "--edges",
        "--view",
        "front",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let doc = std::fs::read_to_string(&svg).unwrap();
    assert!(doc.starts_with("<?xml") && doc.contains(r#"<g id="faces""#));
    // the shortcuts
    let v = dir().join("validate.png");
    let out = run(&["validate", "--quiet", s(&input), "--render", s(&v)]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(std::fs::read(&v).unwrap().starts_with(b"\x89PNG"));
    let t = dir().join("stellar.png");
    let out = run(&["stellar", "--quiet", s(&input), "--render", s(&t)]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(std::fs::read(&t).unwrap().starts_with(b"\x89PNG"));
}

/// The error contract: status 2, the message, nothing written.
fn refused(args: &[&str], out_file: &Path, says: &str) {
    let out = run(args);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
    assert!(
        err.contains(says),
        "{args:?}: '{err}' does not say '{says}'"
    );
    assert!(!out_file.exists(), "{args:?} wrote {}", out_file.display());
}

#[test]
fn bad_input_is_refused() {
    let input = tet_pair();
    let o = dir().join("never.png");
    let (i, op) = (s(&input), s(&o));
    refused(
        &["render", i, "-o", op, "--color", "rainbow"],
        &o,
        "unknown colour mode",
    );
    refused(
        &["render", i, "-o", op, "--color", "label", "region"],
        &o,
        "there is no cell attribute 'region'",
    );
    refused(
        &["render", i, "-o", op, "--color", "field", "temperature"],
        &o,
        "there is no vertex attribute 'temperature'",
    );
    refused(
        &["render", i, "-o", op, "--color", "label"],
        &o,
        "needs the attribute's name",
    );
    refused(
        &["render", i, "-o", op, "--size", "0x100"],
        &o,
        "at least one pixel",
    );
    refused(
        &["render", i, "-o", op, "--size", "100000x100000"],
        &o,
        "150.0 GB of memory",
    );
    refused(
        &["render", i, "-o", op, "--size", "big"],
        &o,
        "WIDTHxHEIGHT",
    );
    refused(
        &["render", i, "-o", op, "--view", "sideways"],
        &o,
        "unknown view",
    );
    refused(&["render", i, "-o", op, "--clip", "w=1"], &o, "AXIS=VALUE");
    refused(
        &["render", i, "-o", op, "--clip", "x=-5"],
        &o,
        "removed all 2 top cells",
    );
    let jpg = dir().join("never.jpg");
    refused(&["render", i, "-o", s(&jpg)], &jpg, ".png or a .svg");
    let empty = dir().join("empty.off");
    std::fs::write(&empty, "OFF\n0 0 0\n").unwrap();
    refused(&["render", s(&empty), "-o", op], &o, "the complex is empty");
}

#[test]
fn labels_and_fields_colour_by_attributes() {
    // meshio's mixed mesh with cell data `material` and point data `velocity` (a vector)
    let input = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../starplex/tests/data/io/attrs_b64_zlib.vtu");
    for (mode, name) in [
        ("label", "material"),
        ("field", "velocity"),
        ("field", "height"),
    ] {
        let o = dir().join(format!("attr-{mode}-{name}.png"));
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_starplex"))
            .args([
                "render",
                s(&input),
                "-o",
                s(&o),
                "--color",
                mode,
                name,
                "--size",
                "200x150",
            ])
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let png = std::fs::read(&o).unwrap();
        assert!(png.starts_with(b"\x89PNG"), "{mode} {name}");
    }
}

#[test]
fn smooth_shading_and_a_perspective_camera() {
    let input = tet_pair();
    let o = dir().join("camera.png");
    let out = run(&[
        "render",
        "--quiet",
        s(&input),
        "-o",
        s(&o),
        "--size",
        "200x150",
        "--shading",
        "smooth",
        "--camera",
        "3,-4,2,0.5,0.5,0.5",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(std::fs::read(&o).unwrap().starts_with(b"\x89PNG"));
    let never = dir().join("never-camera.png");
    let (i, n) = (s(&input), s(&never));
    refused(
        &["render", i, "-o", n, "--camera", "1,2"],
        &never,
        "EX,EY,EZ",
    );
    refused(
        &["render", i, "-o", n, "--camera", "1,1,1,1,1,1"],
        &never,
        "eye is the point it looks at",
    );
    refused(
        &["render", i, "-o", n, "--camera", "1,1,1", "--view", "top"],
        &never,
        "cannot be used with",
    );
    refused(
        &["render", i, "-o", n, "--shading", "glossy"],
        &never,
        "glossy",
    );
}

#[test]
fn compare_draws_both_complexes_side_by_side() {
    let input = tet_pair();
    let one = dir().join("one.mesh");
    std::fs::write(
        &one,
        "MeshVersionFormatted 2\nDimension 3\nVertices\n4\n0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\nTetrahedra\n1\n1 2 3 4 0\nEnd\n",
    )
    .unwrap();
    let o = dir().join("compare.png");
    let out = run(&[
        "render",
        "--quiet",
        s(&input),
        "-o",
        s(&o),
        "--size",
        "301x200",
        "--compare",
        s(&one),
        "--camera",
        "3,-4,2",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let png = std::fs::read(&o).unwrap();
    let be = |i: usize| u32::from_be_bytes(png[i..i + 4].try_into().unwrap());
    // two halves of 151 pixels and a rule between them
    assert_eq!((be(16), be(20)), (303, 200));
    let never = dir().join("never-compare.svg");
    refused(
        &["render", s(&input), "-o", s(&never), "--compare", s(&one)],
        &never,
        "PNG only",
    );
}
