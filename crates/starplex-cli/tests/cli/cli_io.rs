//! Real files in, real files out: `-` as standard input and output, `/dev/stdout`, symbolic
//! links and FIFOs as outputs, refused (lossy) writes with their hints, `--boundary` and
//! `--triangulate`, STL output.
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("starplex-cli-io-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn starplex(args: &[&str], stdin: Option<&[u8]>) -> Output {
    let mut c = Command::new(env!("CARGO_BIN_EXE_starplex"));
    c.args(args)
        .stdin(if stdin.is_some() {
            Stdio::piped()
        } else {
            Stdio::null()
        })
        .stdout(Stdio::piped())
        .stderr(Stdio::piped());
    let mut child = c.spawn().unwrap();
    if let Some(data) = stdin {
        let mut s = child.stdin.take().unwrap();
        let data = data.to_vec();
        std::thread::spawn(move || {
            let _ = s.write_all(&data);
        });
    }
    child.wait_with_output().unwrap()
}

fn ok(args: &[&str], stdin: Option<&[u8]>) -> Output {
    let o = starplex(args, stdin);
    assert!(
        o.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    o
}

fn fails(args: &[&str], stdin: Option<&[u8]>) -> String {
    let o = starplex(args, stdin);
    assert_eq!(o.status.code(), Some(2), "{args:?}: {o:?}");
    assert!(o.stdout.is_empty(), "{args:?}: wrote to stdout");
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// A 2x2x2 Kuhn grid (48 tetrahedra) in `d`.
fn grid(d: &Path) -> String {
    let p = d.join("g.spx");
    ok(
        &["generate", "grid", "2", "2", "2", "-o", p.to_str().unwrap()],
        None,
    );
    p.to_str().unwrap().to_string()
}

fn info_json(args: &[&str], stdin: Option<&[u8]>) -> serde_json::Value {
    let mut a = vec!["info", "--json"];
    a.extend_from_slice(args);
    let o = ok(&a, stdin);
    serde_json::from_slice(&o.stdout).unwrap()
}

#[test]
fn dash_is_stdin_and_stdout() {
    let d = dir("dash");
    let g = grid(&d);
    // convert to standard output, read back from standard input
    let o = ok(&["convert", &g, "-", "--to", "vtk"], None);
    assert!(o.stdout.starts_with(b"# vtk DataFile Version"));
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(stderr.contains("wrote standard output"), "{stderr}");
    let v = info_json(&["-", "--format", "vtk"], Some(&o.stdout));
    assert_eq!(v["n_top_cells"], 48);
    // generate straight to standard output
    let o = ok(
        &["generate", "grid", "1", "1", "-o", "-", "--to", "off"],
        None,
    );
    assert!(o.stdout.starts_with(b"OFF\n"));
    // /dev/stdout is standard output too (it used to be a silent no-op)
    let o = ok(&["convert", &g, "/dev/stdout", "--to", "msh"], None);
    assert!(o.stdout.starts_with(b"$MeshFormat\n4.1"));
    // stdin -> stdout
    let spx = std::fs::read(&g).unwrap();
    let o = ok(
        &[
            "convert",
            "-",
            "--format",
            "spx",
            "-",
            "--to",
            "off-simplices",
        ],
        Some(&spx),
    );
    let v = info_json(&["-", "--format", "off-simplices"], Some(&o.stdout));
    assert_eq!(v["n_top_cells"], 48);
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn dash_without_a_format_is_a_clear_error() {
    let e = fails(&["info", "-"], Some(b"OFF\n"));
    assert!(
        e.contains("standard input has no extension to tell its format"),
        "{e}"
    );
    assert!(e.contains("hint: pass --format NAME"), "{e}");
    assert!(e.contains("readable formats:"), "{e}");
    let d = dir("dashfmt");
    let g = grid(&d);
    let e = fails(&["convert", &g, "-"], None);
    assert!(e.contains("standard output has no extension"), "{e}");
    assert!(e.contains("hint: pass --to NAME"), "{e}");
    // spb is memory-mapped: not from a pipe
    let e = fails(&["info", "-", "--format", "spb"], Some(b"x"));
    assert!(e.contains("cannot be read from a stream"), "{e}");
    std::fs::remove_dir_all(&d).ok();
}

#[cfg(unix)]
#[test]
fn symlink_and_fifo_outputs() {
    let d = dir("links");
    let g = grid(&d);
    let real = d.join("real.vtk");
    std::fs::write(&real, "old").unwrap();
    let link = d.join("link.vtk");
    std::os::unix::fs::symlink("real.vtk", &link).unwrap();
    ok(&["convert", &g, link.to_str().unwrap()], None);
    assert!(std::fs::symlink_metadata(&link)
        .unwrap()
        .file_type()
        .is_symlink());
    let v = info_json(&[real.to_str().unwrap()], None);
    assert_eq!(v["n_top_cells"], 48);
    // stellar --save through a link
    let tree = d.join("tree.bin");
    std::fs::write(&tree, "old").unwrap();
    let tlink = d.join("tree.link");
    std::os::unix::fs::symlink(&tree, &tlink).unwrap();
    ok(
        &["stellar", &g, "--save", tlink.to_str().unwrap(), "--quiet"],
        None,
    );
    assert!(std::fs::read(&tree).unwrap().starts_with(b"SPXSTEL1"));
    assert!(std::fs::symlink_metadata(&tlink)
        .unwrap()
        .file_type()
        .is_symlink());
    // a FIFO is fed, not replaced
    let fifo = d.join("pipe.vtk");
    assert!(Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .unwrap()
        .success());
    let f2 = fifo.clone();
    let reader = std::thread::spawn(move || std::fs::read(f2).unwrap());
    ok(&["convert", &g, fifo.to_str().unwrap()], None);
    let bytes = reader.join().unwrap();
    let v = info_json(&["-", "--format", "vtk"], Some(&bytes));
    assert_eq!(v["n_top_cells"], 48);
    use std::os::unix::fs::FileTypeExt;
    assert!(std::fs::symlink_metadata(&fifo)
        .unwrap()
        .file_type()
        .is_fifo());
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn lossy_writes_are_refused_with_hints_naming_to() {
    let d = dir("lossy");
    let g = grid(&d);
    for (ext, says) in [
        ("off", "off-simplices"),
        ("stl", "--boundary"),
        ("ply", "tetrahedral mesh"),
        ("obj", "tetrahedral mesh"),
    ] {
        let out = d.join(format!("x.{ext}"));
        let e = fails(&["convert", &g, out.to_str().unwrap()], None);
        assert!(
            e.contains("cannot hold this complex") && e.contains(says),
            "{ext}: {e}"
        );
        let hint = e.lines().find(|l| l.starts_with("hint:")).unwrap();
        assert!(
            hint.contains("--to") && hint.contains("stl-binary"),
            "{hint}"
        );
        assert!(!hint.contains("sierp") && !hint.contains(" tri "), "{hint}");
        assert!(!out.exists(), "{ext}: a refused write left a file");
    }
    let e = fails(&["convert", &g, "x.off", "--to", "ts"], None);
    assert!(e.contains("reads ts but does not write it"), "{e}");
    // an output extension that names no writable format: checked before reading the input
    for out in ["x.txt", "x.sierp"] {
        let e = fails(&["convert", &g, out], None);
        let hint = e.lines().find(|l| l.starts_with("hint:")).unwrap();
        assert!(
            hint.contains("--to") && hint.contains("msh22") && !hint.contains("sierp"),
            "{e}"
        );
    }
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn boundary_and_triangulate_make_a_closed_stl() {
    let d = dir("boundary");
    let g = grid(&d);
    for to in ["stl", "stl-binary"] {
        let out = d.join("skin.stl");
        ok(
            &[
                "convert",
                &g,
                out.to_str().unwrap(),
                "--boundary",
                "--to",
                to,
            ],
            None,
        );
        let v = info_json(&[out.to_str().unwrap()], None);
        // the 2x2x2 cube's surface: 8 squares per face * 6 faces... in triangles: 6 * 8
        assert_eq!(v["n_top_cells"], 48);
        assert_eq!(v["n_boundary_faces"], 0);
        assert_eq!(v["euler_characteristic"], 2);
    }
    // a hex: its quads need --triangulate for STL
    let hex = d.join("hex.spx");
    std::fs::write(
        &hex,
        "SPX 1\n3 8 1\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\nhex 8 0 1 2 3 4 5 6 7\n",
    )
    .unwrap();
    let out = d.join("hex.stl");
    let e = fails(
        &[
            "convert",
            hex.to_str().unwrap(),
            out.to_str().unwrap(),
            "--boundary",
        ],
        None,
    );
    assert!(e.contains("--triangulate"), "{e}");
    ok(
        &[
            "convert",
            hex.to_str().unwrap(),
            out.to_str().unwrap(),
            "--boundary",
            "--triangulate",
        ],
        None,
    );
    let v = info_json(&[out.to_str().unwrap()], None);
    assert_eq!(v["n_top_cells"], 12);
    // --boundary alone to OBJ keeps the quads
    let obj = d.join("hex.obj");
    ok(
        &[
            "convert",
            hex.to_str().unwrap(),
            obj.to_str().unwrap(),
            "--boundary",
        ],
        None,
    );
    let v = info_json(&[obj.to_str().unwrap()], None);
    assert_eq!(v["n_top_cells"], 6);
    // --triangulate on a volume is refused
    let e = fails(
        &[
            "convert",
            hex.to_str().unwrap(),
            "-",
            "--to",
            "vtk",
            "--triangulate",
        ],
        None,
    );
    assert!(e.contains("not 3D cells"), "{e}");
    std::fs::remove_dir_all(&d).ok();
}

/// `--drop-degenerate` and `--lenient` on the verbs that read a mesh: without them the same
/// errors as before, with hints naming them; with them the file reads and `info --json` notes
/// what was done.
#[test]
fn drop_degenerate_and_lenient_options() {
    let d = dir("conventions");
    // a triangle with a repeated vertex beside a good one
    let degen = d.join("degen.off");
    std::fs::write(
        &degen,
        "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n3 1 3 3\n",
    )
    .unwrap();
    let degen = degen.to_str().unwrap();
    let e = fails(&["info", degen], None);
    assert!(
        e.contains("degen.off:8:") && e.contains("appears more than once"),
        "{e}"
    );
    assert!(e.contains("hint: pass --drop-degenerate"), "{e}");
    let v = info_json(&["--drop-degenerate", degen], None);
    assert_eq!(v["n_top_cells"], 1, "{v}");
    let notes = v["notes"].to_string();
    assert!(notes.contains("dropped 1 degenerate cells"), "{notes}");
    // the other verbs take it too
    let out = d.join("out.off");
    ok(
        &["convert", "--drop-degenerate", degen, out.to_str().unwrap()],
        None,
    );
    ok(&["validate", "--drop-degenerate", degen], None);
    // an OFF header that announces one face fewer than the file has (CGAL's prim.off)
    let short = d.join("short.off");
    std::fs::write(
        &short,
        "OFF\n4 1 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n3 1 3 2\n",
    )
    .unwrap();
    let short = short.to_str().unwrap();
    let e = fails(&["info", short], None);
    assert!(
        e.contains("short.off:8: unexpected content after the 1 faces"),
        "{e}"
    );
    assert!(e.contains("--lenient"), "{e}");
    let v = info_json(&["--lenient", short], None);
    assert_eq!(v["n_top_cells"], 2, "{v}");
    assert!(
        v["notes"]
            .to_string()
            .contains("announces 1 faces but the file has 2"),
        "{v}"
    );
    ok(
        &["convert", "--lenient", short, out.to_str().unwrap()],
        None,
    );
    // both at once, on a header that announces more faces than there are
    let long = d.join("long.off");
    std::fs::write(
        &long,
        "OFF\n4 3 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n3 1 3 3\n",
    )
    .unwrap();
    let long = long.to_str().unwrap();
    let e = fails(&["info", "--drop-degenerate", long], None);
    assert!(
        e.contains("long.off:9: unexpected end of file") && e.contains("--lenient"),
        "{e}"
    );
    let v = info_json(&["--lenient", "--drop-degenerate", long], None);
    assert_eq!(v["n_top_cells"], 1, "{v}");
    let help = String::from_utf8(ok(&["info", "--help"], None).stdout).unwrap();
    assert!(
        help.contains("--drop-degenerate") && help.contains("--lenient"),
        "{help}"
    );
}
