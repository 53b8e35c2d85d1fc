//! `mpirun -np P starplex-mpi VERB FILE --json` equals `starplex VERB FILE --json` (timings
//! aside) on every small dataset, for P = 1, 2, 3, 4 (`STARPLEX_MPI_RANKS` to change), and bad
//! input ends every rank with status 2 and no hang.
//!
//! Needs `mpirun` (Debian `openmpi-bin`) and the `starplex` binary built in the same target
//! directory (`crates/starplex-mpi/ci.sh` builds both); datasets from `$STARPLEX_DATA/small/*/`
//! or `shared/datasets/small/`. Without them the tests skip, except under `CI=true`.
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

fn required() -> bool {
    std::env::var("CI").is_ok_and(|v| v == "true")
}

fn skip_or_fail(why: &str) {
    assert!(!required(), "{why} (required under CI=true)");
    eprintln!("skipped: {why}");
}

fn mpirun() -> Option<PathBuf> {
    let out = Command::new("sh")
        .args(["-c", "command -v mpirun"])
        .output()
        .ok()?;
    let p = String::from_utf8_lossy(&out.stdout).trim().to_string();
    (!p.is_empty()).then(|| PathBuf::from(p))
}

fn mpi_bin() -> PathBuf {
    PathBuf::from(env!("CARGO_BIN_EXE_starplex-mpi"))
}

fn cli_bin() -> Option<PathBuf> {
    if let Ok(p) = std::env::var("STARPLEX_BIN") {
        return Some(PathBuf::from(p));
    }
    let p = mpi_bin().with_file_name("starplex");
    p.is_file().then_some(p)
}

fn small_datasets() -> Vec<PathBuf> {
    let mut dirs = Vec::new();
    if let Ok(d) = std::env::var("STARPLEX_DATA")
        && let Ok(rd) = std::fs::read_dir(Path::new(&d).join("small"))
    {
        dirs.extend(rd.flatten().map(|e| e.path()));
    }
    let here = Path::new(env!("CARGO_MANIFEST_DIR"));
    if let Some(d) = here
        .ancestors()
        .map(|a| a.join("shared/datasets/small"))
        .find(|d| d.is_dir())
    {
        dirs.push(d);
    }
    let mut found = std::collections::BTreeMap::new();
    for d in dirs {
        for e in std::fs::read_dir(&d).into_iter().flatten().flatten() {
            let p = e.path();
            if p.extension().is_some_and(|x| x == "spx") {
                let name = p.file_stem().unwrap().to_string_lossy().into_owned();
                found.entry(name).or_insert(p);
            }
        }
    }
    found.into_values().collect()
}

/// Runs `cmd`, killed after `limit`: (status code, stdout, stderr). The pipes are drained by
/// threads while it runs (a JSON report is larger than a pipe buffer).
fn run(cmd: &mut Command, limit: Duration) -> (Option<i32>, String, String) {
    use std::io::Read;
    let mut child = cmd
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("spawn");
    let drain = |mut r: Box<dyn Read + Send>| {
        std::thread::spawn(move || {
            let mut s = String::new();
            r.read_to_string(&mut s).ok();
            s
        })
    };
    let out = drain(Box::new(child.stdout.take().expect("stdout")));
    let err = drain(Box::new(child.stderr.take().expect("stderr")));
    let t0 = Instant::now();
    let status = loop {
        if let Some(st) = child.try_wait().expect("wait") {
            break st;
        }
        if t0.elapsed() > limit {
            child.kill().ok();
            child.wait().ok();
            panic!(
                "{cmd:?} hung (killed after {limit:?}); stderr: {}",
                err.join().unwrap_or_default()
            );
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    (
        status.code(),
        out.join().unwrap_or_default(),
        err.join().unwrap_or_default(),
    )
}

fn mpi(np: usize, args: &[&str]) -> Command {
    let mut c = Command::new(mpirun().expect("mpirun"));
    c.args([
        "--allow-run-as-root",
        "--oversubscribe",
        "-np",
        &np.to_string(),
    ])
    .arg(mpi_bin())
    .args(args)
    .env("OMPI_MCA_btl_vader_single_copy_mechanism", "none")
    .env("OMPI_MCA_rmaps_base_oversubscribe", "1");
    c
}

fn ranks() -> Vec<usize> {
    std::env::var("STARPLEX_MPI_RANKS")
        .unwrap_or_else(|_| "1,2,3,4".into())
        .split(',')
        .filter_map(|x| x.trim().parse().ok())
        .collect()
}

fn without_timings(s: &str, what: &str) -> serde_json::Value {
    let mut v: serde_json::Value =
        serde_json::from_str(s).unwrap_or_else(|e| panic!("{what}: not JSON ({e}): {s}"));
    v.as_object_mut().expect("an object").remove("timings");
    v
}

fn ready() -> Option<PathBuf> {
    if mpirun().is_none() {
        skip_or_fail("mpirun not found (apt-get install openmpi-bin libopenmpi-dev)");
        return None;
    }
    let Some(cli) = cli_bin() else {
        skip_or_fail(
            "the starplex binary is not built beside starplex-mpi (cargo build -p starplex-cli)",
        );
        return None;
    };
    Some(cli)
}

#[test]
fn info_and_validate_equal_the_single_process_cli() {
    let Some(cli) = ready() else { return };
    let data = small_datasets();
    if data.is_empty() {
        skip_or_fail("no small datasets (set STARPLEX_DATA)");
        return;
    }
    let tmp = std::env::temp_dir().join(format!("starplex-mpi-test-{}", std::process::id()));
    std::fs::create_dir_all(&tmp).unwrap();
    let limit = Duration::from_secs(120);
    let mut failures = Vec::new();
    for src in &data {
        let name = src.file_stem().unwrap().to_string_lossy().into_owned();
        let spb = tmp.join(format!("{name}.spb"));
        let (code, _, err) = run(
            Command::new(&cli)
                .arg("--quiet")
                .arg("convert")
                .arg(src)
                .arg(&spb),
            limit,
        );
        assert_eq!(code, Some(0), "convert {name}: {err}");
        let spb_s = spb.to_string_lossy().into_owned();
        for verb in ["info", "validate"] {
            let (code, out, err) = run(
                Command::new(&cli).args(["--quiet", verb, &spb_s, "--json"]),
                limit,
            );
            assert_eq!(code, Some(0), "starplex {verb} {name}: {err}");
            let want = without_timings(&out, &format!("starplex {verb} {name}"));
            for np in ranks() {
                let t0 = Instant::now();
                let (code, out, err) = run(&mut mpi(np, &[verb, &spb_s, "--json"]), limit);
                let what = format!("-np {np} starplex-mpi {verb} {name}");
                if code != Some(0) {
                    failures.push(format!("{what}: status {code:?}: {err}"));
                    continue;
                }
                let got = without_timings(&out, &what);
                if got != want {
                    failures.push(format!("{what}: differs\n got {got}\nwant {want}"));
                }
                eprintln!("{what}: {:.2} s", t0.elapsed().as_secs_f64());
            }
        }
    }
    std::fs::remove_dir_all(&tmp).ok();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn bad_input_ends_every_rank_with_status_2() {
    if ready().is_none() {
        return;
    }
    let tmp = std::env::temp_dir().join(format!("starplex-mpi-bad-{}", std::process::id()));
    std::fs::create_dir_all(&tmp).unwrap();
    let limit = Duration::from_secs(60);
    // a text format
    let off = tmp.join("t.off");
    std::fs::write(&off, "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n").unwrap();
    // a .spb cut short
    let spb = tmp.join("t.spb");
    let mut bytes = Vec::new();
    {
        use starplex::cell::CellKind;
        use starplex::complex::{BuildOptions, ComplexBuilder};
        let mut b = ComplexBuilder::new(2).unwrap();
        for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] {
            b.push_vertex(&p).unwrap();
        }
        b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
        b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
        let k = b.build(&BuildOptions::default()).unwrap().0;
        starplex::io::binary::write(&mut bytes, &k).unwrap();
    }
    std::fs::write(&spb, &bytes[..bytes.len() - 8]).unwrap();
    // a vertex id out of range in the cell array (the header is fine): found by one rank only
    let bad = tmp.join("bad.spb");
    let mut b2 = bytes.clone();
    let n = b2.len();
    b2[n - 8..n - 4].copy_from_slice(&77u32.to_le_bytes());
    std::fs::write(&bad, &b2).unwrap();
    let cases = [
        (off.clone(), "starplex convert"),
        (tmp.join("missing.spb"), "missing.spb"),
        (spb.clone(), "truncated"),
        (bad.clone(), "vertex 77"),
    ];
    for np in [1, 2, 3] {
        for (file, want) in &cases {
            for verb in ["info", "validate"] {
                let f = file.to_string_lossy().into_owned();
                let (code, _, err) = run(&mut mpi(np, &[verb, &f, "--json"]), limit);
                assert_eq!(code, Some(2), "-np {np} {verb} {f}: {err}");
                assert!(err.contains(want), "-np {np} {verb} {f}: {err}");
            }
        }
    }
    std::fs::remove_dir_all(&tmp).ok();
}
