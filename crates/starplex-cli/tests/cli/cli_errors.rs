//! The `starplex` binary on broken files: exit status 2, nothing on stdout, and exactly one error
//! line on stderr naming the file, the line and the problem (followed, for problems an option
//! works around, by one `hint:` line naming it).
use std::path::PathBuf;
use std::process::Command;

fn dir() -> PathBuf {
    let d = std::env::temp_dir().join(format!("starplex-cli-errors-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Runs `starplex info FILE` and checks the error contract; returns the error line.
fn info_fails(name: &str, content: &[u8], line: u64, problem: &str) -> String {
    let p = dir().join(name);
    std::fs::write(&p, content).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_starplex"))
        .args(["info", "--quiet"])
        .arg(&p)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(
        out.status.code(),
        Some(2),
        "{name}: status {:?}, stderr {stderr}",
        out.status
    );
    assert!(
        out.stdout.is_empty(),
        "{name}: stdout {:?}",
        String::from_utf8_lossy(&out.stdout)
    );
    let lines: Vec<&str> = stderr.lines().collect();
    let hints = lines
        .iter()
        .skip(1)
        .filter(|l| l.starts_with("hint: "))
        .count();
    assert!(
        lines.len() == 1 || (lines.len() == 2 && hints == 1),
        "{name}: expected one error line (and at most one hint), got {stderr:?}"
    );
    let want = format!("starplex: error: {}:{line}: ", p.display());
    assert!(
        lines[0].starts_with(&want),
        "{name}: '{}' does not start with '{want}'",
        lines[0]
    );
    assert!(
        lines[0].contains(problem),
        "{name}: '{}' does not say '{problem}'",
        lines[0]
    );
    lines[0].to_string()
}

#[test]
fn off_with_an_index_out_of_range() {
    info_fails(
        "oor.off",
        b"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n",
        6,
        "face vertex 7 is out of range",
    );
}

#[test]
fn truncated_tri() {
    info_fails(
        "trunc.tri",
        b"3\n0 0 0\n1 0 0\n0 1 0\n2\n0 1 2\n",
        7,
        "unexpected end of file",
    );
}

#[test]
fn spx_with_nan() {
    info_fails(
        "nan.spx",
        b"SPX 1\n3 3 1\n0 0 0\n1 nan 0\n0 1 0\ntri 3 0 1 2\n",
        4,
        "not finite",
    );
}

#[test]
fn hex_with_a_repeated_vertex() {
    let mut text = String::new();
    for i in 0..8 {
        text.push_str(&format!("v {i} {} 0\n", i % 3));
    }
    text.push_str("# 1 hexahedra\nh 1 2 3 4 5 6 7 7\n");
    info_fails("rep.hex", text.as_bytes(), 10, "appears more than once");
    let p = dir().join("rep.hex");
    let out = Command::new(env!("CARGO_BIN_EXE_starplex"))
        .args(["info", "--quiet"])
        .arg(&p)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.ends_with("hint: pass --drop-degenerate to drop the cells with a repeated vertex\n"),
        "{stderr}"
    );
}

#[test]
fn binary_garbage_as_off() {
    let bytes: Vec<u8> = (0..4000u32)
        .map(|i| (i.wrapping_mul(2654435761) >> 13) as u8)
        .collect();
    info_fails("garbage.off", &bytes, 1, "not an OFF file");
}
