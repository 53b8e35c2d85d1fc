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
            // SIGTERM first: mpirun forwards it and ends its ranks, which a SIGKILL of
            // mpirun alone would leave running (and slowing every test after)
            // SAFETY: kill(2) on the child's own pid, which has not been reaped yet.
            unsafe { libc::kill(child.id() as i32, libc::SIGTERM) };
            let t1 = Instant::now();
            while t1.elapsed() < Duration::from_secs(10) && matches!(child.try_wait(), Ok(None)) {
                std::thread::sleep(Duration::from_millis(50));
            }
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

/// The CLI, the small datasets and a fresh temporary directory `TAG-PID`; `None` (the test
/// skips) without mpirun, the CLI or datasets.
fn setup(tag: &str) -> Option<(PathBuf, Vec<PathBuf>, PathBuf)> {
    let cli = ready()?;
    let data = small_datasets();
    if data.is_empty() {
        skip_or_fail("no small datasets (set STARPLEX_DATA)");
        return None;
    }
    let tmp = std::env::temp_dir().join(format!("{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&tmp).unwrap();
    Some((cli, data, tmp))
}

/// Names of the files in `dir` that `keep` does not expect (temporary files left behind).
fn leftovers(dir: &Path, keep: impl Fn(&str) -> bool) -> Vec<String> {
    std::fs::read_dir(dir)
        .unwrap()
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| !keep(n))
        .collect()
}

/// The 6-vertex real projective plane (10 triangles; H_1 over Z is Z/2).
fn rp2() -> starplex::complex::IndexedComplex {
    use starplex::cell::CellKind;
    use starplex::complex::{BuildOptions, ComplexBuilder};
    let mut b = ComplexBuilder::new(3).unwrap();
    for i in 0..6 {
        let a = i as f64;
        b.push_vertex(&[a.cos(), a.sin(), a * 0.1]).unwrap();
    }
    for t in [
        [0, 1, 2],
        [0, 2, 3],
        [0, 3, 4],
        [0, 4, 5],
        [0, 5, 1],
        [1, 2, 4],
        [2, 3, 5],
        [3, 4, 1],
        [4, 5, 2],
        [5, 1, 3],
    ] {
        b.push_cell(CellKind::Simplex(2), &t).unwrap();
    }
    b.build(&BuildOptions::default()).unwrap().0
}

/// The keys compared: everything for `info` and `validate`; for `homology` the answer (field,
/// Betti numbers, Euler characteristic), not the size of the reduced complex, which depends on
/// how it was reduced.
fn comparable(verb: &str, v: serde_json::Value) -> serde_json::Value {
    if verb != "homology" {
        return v;
    }
    let keys = [
        "field",
        "betti",
        "betti_z2",
        "euler_characteristic",
        "torsion",
    ];
    serde_json::Value::Object(
        keys.iter()
            .map(|k| (k.to_string(), v[*k].clone()))
            .collect(),
    )
}

/// Converts `src` to `DIR/NAME.spb` with the CLI.
fn to_spb(cli: &Path, src: &Path, dir: &Path) -> String {
    let name = src.file_stem().unwrap().to_string_lossy().into_owned();
    let spb = dir.join(format!("{name}.spb"));
    let (code, _, err) = run(
        Command::new(cli)
            .arg("--quiet")
            .arg("convert")
            .arg(src)
            .arg(&spb),
        Duration::from_secs(120),
    );
    assert_eq!(code, Some(0), "convert {name}: {err}");
    spb.to_string_lossy().into_owned()
}

#[test]
fn info_validate_and_homology_equal_the_single_process_cli() {
    let Some((cli, data, tmp)) = setup("starplex-mpi-test") else {
        return;
    };
    let limit = Duration::from_secs(600); // single-process homology of hex_knot1 took 70 s under load 14
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
        for verb in ["info", "validate", "homology"] {
            let (code, out, err) = run(
                Command::new(&cli).args(["--quiet", verb, &spb_s, "--json"]),
                limit,
            );
            assert_eq!(code, Some(0), "starplex {verb} {name}: {err}");
            let want = comparable(
                verb,
                without_timings(&out, &format!("starplex {verb} {name}")),
            );
            for np in ranks() {
                let t0 = Instant::now();
                let (code, out, err) = run(&mut mpi(np, &[verb, &spb_s, "--json"]), limit);
                let what = format!("-np {np} starplex-mpi {verb} {name}");
                if code != Some(0) {
                    failures.push(format!("{what}: status {code:?}: {err}"));
                    continue;
                }
                let got = comparable(verb, without_timings(&out, &what));
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

/// `stellar`: with one rank the statistics equal `starplex stellar --json` exactly (the
/// ownership rule then counts every leaf and every cell as the single process does); with 2-4
/// ranks the global counts agree, every cell is counted at least once (chi >= 1), and the VT and
/// VV answers of every vertex, each given by its owner's local tree, equal the single-process
/// tree's.
#[test]
fn stellar_counts_and_vt_vv_of_owned_vertices_equal_the_single_process() {
    use starplex::ids::VertexId;
    use starplex::stellar::{StellarOptions, StellarTree};
    let Some((cli, data, tmp)) = setup("starplex-mpi-stellar") else {
        return;
    };
    let limit = Duration::from_secs(120);
    let mut failures = Vec::new();
    for src in &data {
        let name = src.file_stem().unwrap().to_string_lossy().into_owned();
        let spb_s = to_spb(&cli, src, &tmp);
        let (code, out, err) = run(
            Command::new(&cli).args(["--quiet", "stellar", &spb_s, "--json"]),
            limit,
        );
        assert_eq!(code, Some(0), "starplex stellar {name}: {err}");
        let want = without_timings(&out, &format!("starplex stellar {name}"));
        let k = starplex::io::read(Path::new(&spb_s), &Default::default())
            .unwrap()
            .complex;
        let t = StellarTree::build(&k, &StellarOptions::default()).unwrap();
        let all: Vec<VertexId> = (0..k.n_vertices() as u32).map(VertexId).collect();
        let vt = t.vt_of(&all).unwrap();
        let vv = t.vv_of(&all).unwrap();
        for np in ranks() {
            let what = format!("-np {np} starplex-mpi stellar {name}");
            let prefix = tmp.join(format!("{name}-{np}"));
            let prefix_s = prefix.to_string_lossy().into_owned();
            let (code, out, err) = run(
                &mut mpi(np, &["stellar", &spb_s, "--json", "--vt-vv-out", &prefix_s]),
                limit,
            );
            if code != Some(0) {
                failures.push(format!("{what}: status {code:?}: {err}"));
                continue;
            }
            let mut got = without_timings(&out, &what);
            let dist = got.as_object_mut().unwrap().remove("distributed");
            assert!(dist.is_some(), "{what}: no 'distributed' key");
            if np == 1 {
                if got != want {
                    failures.push(format!("{what}: differs\n got {got}\nwant {want}"));
                }
            } else {
                for key in ["n_vertices", "n_top_cells", "kv"] {
                    if got[key] != want[key] {
                        failures.push(format!("{what}: {key} {} != {}", got[key], want[key]));
                    }
                }
                if got["storage"]["base_complex"] != want["storage"]["base_complex"] {
                    failures.push(format!("{what}: base complex storage differs"));
                }
                let nt = want["n_top_cells"].as_u64().unwrap();
                if nt > 0 && got["chi"].as_f64().unwrap() < 1.0 {
                    failures.push(format!("{what}: chi {} < 1", got["chi"]));
                }
            }
            // VT / VV of every vertex, from the rank that owns it
            let mut seen = vec![false; k.n_vertices()];
            for r in 0..np {
                let path = format!("{prefix_s}.rank{r}.txt");
                let text = std::fs::read_to_string(&path)
                    .unwrap_or_else(|e| panic!("{what}: {path}: {e}"));
                for line in text.lines() {
                    let parts: Vec<&str> = line.split('|').collect();
                    let nums = |s: &str| -> Vec<u32> {
                        s.split_whitespace().map(|x| x.parse().unwrap()).collect()
                    };
                    let v: usize = parts[0].parse().unwrap();
                    assert!(!seen[v], "{what}: vertex {v} answered by two ranks");
                    seen[v] = true;
                    let want_vt: Vec<u32> = vt[v].iter().map(|c| c.0).collect();
                    let want_vv: Vec<u32> = vv[v].iter().map(|w| w.0).collect();
                    if nums(parts[1]) != want_vt || nums(parts[2]) != want_vv {
                        failures.push(format!(
                            "{what}: vertex {v}: VT {} VV {} != VT {want_vt:?} VV {want_vv:?}",
                            parts[1], parts[2]
                        ));
                    }
                }
            }
            if let Some(v) = seen.iter().position(|&s| !s) {
                failures.push(format!("{what}: vertex {v} answered by no rank"));
            }
        }
    }
    std::fs::remove_dir_all(&tmp).ok();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The owned top cells of the ranks are balanced: on every small dataset with at least 2,000
/// cells, the largest rank owns at most 10 % above the mean (the splitters are quantiles of a
/// sample of the cells' smallest vertices; all cells are sampled below 4,096 a rank).
#[test]
fn owned_top_cells_are_balanced() {
    let Some((cli, data, tmp)) = setup("starplex-mpi-balance") else {
        return;
    };
    let mut failures = Vec::new();
    for src in &data {
        let name = src.file_stem().unwrap().to_string_lossy().into_owned();
        let spb_s = to_spb(&cli, src, &tmp);
        for np in ranks().into_iter().filter(|&p| p > 1) {
            let what = format!("-np {np} starplex-mpi info {name} --stats");
            let (code, _, err) = run(
                &mut mpi(np, &["info", &spb_s, "--json", "--stats"]),
                Duration::from_secs(120),
            );
            assert_eq!(code, Some(0), "{what}: {err}");
            let line = err
                .lines()
                .find(|l| l.starts_with("owned top cells per rank"))
                .unwrap_or_else(|| panic!("{what}: no balance line in {err}"));
            let inner = &line[line.find('[').unwrap() + 1..line.find(']').unwrap()];
            let owned: Vec<u64> = inner.split(", ").map(|x| x.parse().unwrap()).collect();
            assert_eq!(owned.len(), np, "{what}: {line}");
            let total: u64 = owned.iter().sum();
            let max = *owned.iter().max().unwrap();
            eprintln!("{what}: {owned:?}");
            if total >= 2000 && max as f64 > 1.10 * total as f64 / np as f64 {
                failures.push(format!("{what}: unbalanced {owned:?}"));
            }
        }
    }
    std::fs::remove_dir_all(&tmp).ok();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// `homology --field 2|q|z` of the 6-vertex real projective plane (H_1 = Z/2: Betti [1,1,1]
/// over Z/2, [1,0,0] over Q and Z with torsion [[], [2], []]) on 1-3 ranks: the Morse and the
/// contraction methods keep the torsion.
#[test]
fn homology_of_the_projective_plane_keeps_the_torsion() {
    if ready().is_none() {
        return;
    }
    let tmp = std::env::temp_dir().join(format!("starplex-mpi-rp2-{}", std::process::id()));
    std::fs::create_dir_all(&tmp).unwrap();
    let k = rp2();
    let spb = tmp.join("rp2.spb");
    let mut bytes = Vec::new();
    starplex::io::binary::write(&mut bytes, &k).unwrap();
    std::fs::write(&spb, &bytes).unwrap();
    let spb = spb.to_string_lossy().into_owned();
    let want = [
        ("2", serde_json::json!([1, 1, 1]), serde_json::Value::Null),
        ("q", serde_json::json!([1, 0, 0]), serde_json::Value::Null),
        (
            "z",
            serde_json::json!([1, 0, 0]),
            serde_json::json!([[], ["2"], []]),
        ),
    ];
    for np in [1, 2, 3] {
        for (field, betti, torsion) in &want {
            for method in ["morse", "contract"] {
                let (code, out, err) = run(
                    &mut mpi(
                        np,
                        &[
                            "homology", &spb, "--json", "--field", field, "--method", method,
                        ],
                    ),
                    Duration::from_secs(60),
                );
                let what = format!("-np {np} --field {field} --method {method}");
                assert_eq!(code, Some(0), "{what}: {err}");
                let v = without_timings(&out, "rp2");
                assert_eq!(&v["betti"], betti, "{what}: {v}");
                assert_eq!(&v["torsion"], torsion, "{what}: {v}");
            }
        }
    }
    let left = leftovers(&tmp, |n| n == "rp2.spb");
    assert!(left.is_empty(), "temporary files left: {left:?}");
    std::fs::remove_dir_all(&tmp).ok();
}

/// `validate` of non-orientable surfaces (the projective plane, a Möbius strip, a Klein
/// bottle made of a grid): every rank count equals `starplex validate`'s, `orientable` is
/// false, and the conflicting pair named is two top cells that share an edge (the single
/// process names the first pair its sequential walk meets; the distributed run another one).
#[test]
fn validate_names_a_conflict_on_non_orientable_surfaces() {
    use starplex::cell::CellKind;
    use starplex::complex::{BuildOptions, ComplexBuilder};
    let Some(cli) = ready() else { return };
    let tmp = std::env::temp_dir().join(format!("starplex-mpi-nonorient-{}", std::process::id()));
    std::fs::create_dir_all(&tmp).unwrap();
    // an n x m grid of squares, two triangles each, glued: the last column to the first
    // with a flip (Möbius strip), and for the Klein bottle the last row to the first as well
    let surface = |n: u32, m: u32, klein: bool| {
        let rows = if klein { m } else { m + 1 };
        let id = |i: u32, j: u32| {
            let (i, j) = if i == n { (0, m - j) } else { (i, j) };
            let j = if klein { j % m } else { j };
            i * rows + j
        };
        let mut b = ComplexBuilder::new(3).unwrap();
        for i in 0..n {
            for j in 0..rows {
                let (a, t) = (i as f64 / n as f64 * std::f64::consts::TAU, j as f64);
                b.push_vertex(&[a.cos() * (3.0 + t), a.sin() * (3.0 + t), t * 0.7 + a])
                    .unwrap();
            }
        }
        for i in 0..n {
            for j in 0..m {
                let (p, q, r, s) = (id(i, j), id(i + 1, j), id(i, j + 1), id(i + 1, j + 1));
                b.push_cell(CellKind::Simplex(2), &[p, q, s]).unwrap();
                b.push_cell(CellKind::Simplex(2), &[p, s, r]).unwrap();
            }
        }
        b.build(&BuildOptions::default()).unwrap().0
    };
    let cases = [
        ("rp2", rp2()),
        ("moebius", surface(24, 3, false)),
        ("klein", surface(30, 6, true)),
    ];
    let mut failures = Vec::new();
    for (name, k) in &cases {
        let spb = tmp.join(format!("{name}.spb"));
        let mut bytes = Vec::new();
        starplex::io::binary::write(&mut bytes, k).unwrap();
        std::fs::write(&spb, &bytes).unwrap();
        let spb = spb.to_string_lossy().into_owned();
        let (code, out, err) = run(
            Command::new(&cli).args(["--quiet", "validate", &spb, "--json"]),
            Duration::from_secs(60),
        );
        assert_eq!(code, Some(0), "starplex validate {name}: {err}");
        let mut want = without_timings(&out, name);
        assert_eq!(
            want["orientable"], false,
            "{name} should not be orientable: {want}"
        );
        want.as_object_mut().unwrap().remove("orientation_conflict");
        for np in [1, 2, 3, 4] {
            let what = format!("-np {np} validate {name}");
            let (code, out, err) = run(
                &mut mpi(np, &["validate", &spb, "--json"]),
                Duration::from_secs(60),
            );
            if code != Some(0) {
                failures.push(format!("{what}: status {code:?}: {err}"));
                continue;
            }
            let mut got = without_timings(&out, &what);
            let pair = got
                .as_object_mut()
                .unwrap()
                .remove("orientation_conflict")
                .unwrap_or_default();
            if got != want {
                failures.push(format!("{what}: differs\n got {got}\nwant {want}"));
            }
            let ab: Vec<usize> = pair
                .as_array()
                .map(|a| {
                    a.iter()
                        .filter_map(|x| x.as_u64())
                        .map(|x| x as usize)
                        .collect()
                })
                .unwrap_or_default();
            let shares_an_edge = ab.len() == 2 && ab[0] != ab[1] && {
                let ca = k.cell(starplex::ids::CellId(ab[0] as u32)).vertices;
                let cb = k.cell(starplex::ids::CellId(ab[1] as u32)).vertices;
                ca.iter().filter(|v| cb.contains(v)).count() == 2
            };
            if !shares_an_edge {
                failures.push(format!(
                    "{what}: conflict {pair} is not two triangles sharing an edge"
                ));
            }
        }
    }
    std::fs::remove_dir_all(&tmp).ok();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// `homology` on random complexes (seeded): tetrahedra, triangles and edges over few vertices,
/// non-manifold and with holes, so that interfaces between ranks carry every kind of face;
/// the Betti numbers (and torsion) equal the single process's for 2-4 ranks, over Z/2, Z/3, Q
/// and Z by the Morse reduction, over Z/2, Q and Z by contraction, over Z/2 by the algebraic
/// reduction.
#[test]
fn homology_of_random_complexes_equals_the_single_process() {
    use starplex::cell::CellKind;
    use starplex::complex::{BuildOptions, ComplexBuilder};
    use starplex::testkit::XorShift;
    let Some(cli) = ready() else { return };
    let tmp = std::env::temp_dir().join(format!("starplex-mpi-homrand-{}", std::process::id()));
    std::fs::create_dir_all(&tmp).unwrap();
    let mut rng = XorShift::new(17);
    let mut failures = Vec::new();
    for case in 0..24 {
        let nv = 8 + (rng.next_u64() % 10) as u32;
        let mut cells: Vec<Vec<u32>> = Vec::new();
        let n_cells = 4 + rng.next_u64() % 14;
        for _ in 0..n_cells {
            let size = 2 + (rng.next_u64() % 3) as usize;
            let mut c: Vec<u32> = Vec::new();
            while c.len() < size {
                let v = (rng.next_u64() % nv as u64) as u32;
                if !c.contains(&v) {
                    c.push(v);
                }
            }
            c.sort_unstable();
            cells.push(c);
        }
        cells.sort();
        cells.dedup();
        // keep the maximal ones
        let keep: Vec<Vec<u32>> = cells
            .iter()
            .filter(|c| {
                !cells
                    .iter()
                    .any(|d| d.len() > c.len() && c.iter().all(|x| d.contains(x)))
            })
            .cloned()
            .collect();
        let mut b = ComplexBuilder::new(3).unwrap();
        for _ in 0..nv {
            let p = [0, 1, 2].map(|_| (rng.next_u64() % 1000) as f64 / 100.0);
            b.push_vertex(&p).unwrap();
        }
        for c in &keep {
            b.push_cell(CellKind::Simplex(c.len() as u8 - 1), c)
                .unwrap();
        }
        let k = b.build(&BuildOptions::default()).unwrap().0;
        let spb = tmp.join(format!("r{case}.spb"));
        let mut bytes = Vec::new();
        starplex::io::binary::write(&mut bytes, &k).unwrap();
        std::fs::write(&spb, &bytes).unwrap();
        let spb_s = spb.to_string_lossy().into_owned();
        // every field by the rank-local Morse reduction (the default) and by contraction, Z/2
        // by the algebraic reduction
        let methods: [(&str, &[&str]); 8] = [
            ("2", &[]),
            ("2", &["--method", "algebraic"]),
            ("z", &[]),
            ("q", &[]),
            ("3", &[]),
            ("z", &["--method", "contract"]),
            ("2", &["--method", "contract"]),
            ("q", &["--method", "contract"]),
        ];
        let (field, extra) = methods[case % methods.len()];
        let (code, out, err) = run(
            Command::new(&cli).args(["--quiet", "homology", &spb_s, "--json", "--field", field]),
            Duration::from_secs(60),
        );
        assert_eq!(code, Some(0), "starplex homology case {case}: {err}");
        let want = comparable("homology", without_timings(&out, "single"));
        for np in [2, 3, 4] {
            let what =
                format!("-np {np} homology --field {field} {extra:?} case {case} ({keep:?})");
            let mut args = vec!["homology", spb_s.as_str(), "--json", "--field", field];
            args.extend_from_slice(extra);
            let (code, out, err) = run(&mut mpi(np, &args), Duration::from_secs(60));
            if code != Some(0) {
                failures.push(format!("{what}: status {code:?}: {err}"));
                continue;
            }
            let got = comparable("homology", without_timings(&out, &what));
            if got != want {
                failures.push(format!("{what}: got {got} want {want}"));
            }
        }
    }
    std::fs::remove_dir_all(&tmp).ok();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// A `.spb` truncated while the ranks read it through their memory maps (SIGBUS) ends the run
/// with a clear error and status 2, not a crash report or a hang.
#[test]
fn a_file_truncated_during_the_read_ends_with_status_2() {
    use starplex::cell::CellKind;
    use starplex::complex::{BuildOptions, ComplexBuilder};
    if ready().is_none() {
        return;
    }
    let tmp = std::env::temp_dir().join(format!("starplex-mpi-sigbus-{}", std::process::id()));
    std::fs::create_dir_all(&tmp).unwrap();
    // a grid of triangles large enough to span many pages
    let n = 300u32;
    let mut b = ComplexBuilder::new(2).unwrap();
    for i in 0..n {
        for j in 0..n {
            b.push_vertex(&[i as f64, j as f64]).unwrap();
        }
    }
    for i in 0..n - 1 {
        for j in 0..n - 1 {
            let v = i * n + j;
            b.push_cell(CellKind::Simplex(2), &[v, v + 1, v + n])
                .unwrap();
            b.push_cell(CellKind::Simplex(2), &[v + 1, v + n + 1, v + n])
                .unwrap();
        }
    }
    let k = b.build(&BuildOptions::default()).unwrap().0;
    let spb = tmp.join("grid.spb");
    let mut bytes = Vec::new();
    starplex::io::binary::write(&mut bytes, &k).unwrap();
    std::fs::write(&spb, &bytes).unwrap();
    let f = spb.to_string_lossy().into_owned();
    let mut cmd = mpi(2, &["info", &f, "--json"]);
    cmd.env("STARPLEX_MPI_PAUSE_AFTER_OPEN_MS", "4000");
    let path = spb.clone();
    let cutter = std::thread::spawn(move || {
        std::thread::sleep(Duration::from_millis(2500));
        let file = std::fs::OpenOptions::new().write(true).open(&path).unwrap();
        file.set_len(4096).unwrap();
    });
    let (code, _, err) = run(&mut cmd, Duration::from_secs(60));
    cutter.join().unwrap();
    assert_eq!(code, Some(2), "{err}");
    assert!(err.contains("changed"), "{err}");
    std::fs::remove_dir_all(&tmp).ok();
}

/// The complex of a `.spb` as (coordinates, sorted list of cells): equality up to the order of
/// the cells.
fn cells_of(path: &str) -> (Vec<f64>, Vec<(String, Vec<u32>)>) {
    let k = starplex::io::read(Path::new(path), &Default::default())
        .unwrap_or_else(|e| panic!("{path}: {e}"))
        .complex;
    let mut cells: Vec<(String, Vec<u32>)> = k
        .cells()
        .map(|c| (c.kind.type_name(), c.vertices.to_vec()))
        .collect();
    cells.sort();
    (k.coords().to_vec(), cells)
}

/// `starplex homology --json` and `validate --json` of a file: (Betti numbers over Z/2,
/// non-manifold vertices, non-manifold edges).
fn topology(cli: &Path, spb: &str) -> (serde_json::Value, u64, u64) {
    let limit = Duration::from_secs(300);
    let (code, out, err) = run(
        Command::new(cli).args(["--quiet", "homology", spb, "--json"]),
        limit,
    );
    assert_eq!(code, Some(0), "homology {spb}: {err}");
    let h = without_timings(&out, spb);
    let (code, out, err) = run(
        Command::new(cli).args(["--quiet", "validate", spb, "--json"]),
        limit,
    );
    assert_eq!(code, Some(0), "validate {spb}: {err}");
    let v = without_timings(&out, spb);
    let n = |k: &str| {
        v[k].as_u64()
            .unwrap_or_else(|| panic!("{spb}: no {k} in {v}"))
    };
    (
        h["betti_z2"].clone(),
        n("n_non_manifold_vertices"),
        n("n_non_manifold_edges"),
    )
}

/// The (ranks, `--gather-below`) pairs the `simplify` tests run: 1-4 ranks, with the last round
/// on rank 0 (the default) and, with several ranks, without it (`0`: every round distributed).
fn simplify_configs() -> Vec<(usize, &'static str)> {
    ranks()
        .into_iter()
        .flat_map(|np| [(np, "2000000"), (np, "0")])
        .filter(|&(np, g)| np > 1 || g != "0")
        .collect()
}

/// `mpirun -np NP starplex-mpi simplify SPB -o OUT --json --gather-below GATHER ARGS...`: its
/// report, or `None` with the failure recorded.
fn run_simplify(
    np: usize,
    gather: &str,
    spb: &str,
    out: &str,
    args: &[&str],
    what: &str,
    failures: &mut Vec<String>,
) -> Option<serde_json::Value> {
    let mut all = vec![
        "simplify",
        spb,
        "-o",
        out,
        "--json",
        "--gather-below",
        gather,
    ];
    all.extend_from_slice(args);
    let (code, stdout, err) = run(&mut mpi(np, &all), Duration::from_secs(600));
    if code != Some(0) {
        failures.push(format!("{what}: status {code:?}: {err}"));
        return None;
    }
    Some(without_timings(&stdout, what))
}

/// Betti numbers without their trailing zeros (a simplified complex can lose dimensions).
fn trimmed(b: &serde_json::Value) -> Vec<u64> {
    trim_zeros(
        b.as_array()
            .map(|a| a.iter().filter_map(|x| x.as_u64()).collect())
            .unwrap_or_default(),
    )
}

/// `v` without its trailing zeros.
fn trim_zeros(mut v: Vec<u64>) -> Vec<u64> {
    while v.last() == Some(&0) {
        v.pop();
    }
    v
}

/// `simplify` on every small simplicial dataset: with one rank the result is the single-process
/// `starplex simplify` result (the same complex, up to the order of the cells); with 2-4 ranks,
/// with and without the last round on rank 0 (`--gather-below 0` keeps every round
/// distributed, every rank locking what is not interior to it), the Betti numbers are kept and
/// the complex shrinks. Homology mode everywhere; on the triangle and tetrahedral meshes also
/// QEM at ratio 0.3 and homology mode with `--keep-manifold`, where no non-manifold vertex or
/// edge may appear either. The report's topology before and after (f-vector, Euler
/// characteristic, Betti numbers, non-manifold vertices and edges, boundary faces) is the
/// single process's `summary` of the input and of the output file.
#[test]
fn simplify_keeps_the_topology_and_one_rank_equals_the_single_process() {
    use starplex::algo::simplify::summary;
    use starplex_cli::report::{topology_json, topology_kept};
    let Some((cli, data, tmp)) = setup("starplex-mpi-simplify") else {
        return;
    };
    let limit = Duration::from_secs(600);
    let mut failures = Vec::new();
    let mut checked = 0;
    for src in &data {
        let name = src.file_stem().unwrap().to_string_lossy().into_owned();
        let spb = to_spb(&cli, src, &tmp);
        let k = starplex::io::read(Path::new(&spb), &Default::default())
            .unwrap()
            .complex;
        if !k.is_simplicial() {
            continue;
        }
        let qem = starplex::algo::simplify::default_mode(&k) == starplex::algo::simplify::Mode::Qem;
        let before = topology(&cli, &spb);
        // (options, whether no non-manifold vertex or edge may appear: homology mode keeps
        // the Betti numbers only, unless --keep-manifold)
        // a few vertices to keep: every 7th, at most 60 (they must survive every rank count,
        // at their input coordinates)
        let keep: Vec<u32> = (0..k.n_vertices() as u32).step_by(7).take(60).collect();
        let keep_file = tmp.join(format!("{name}.keep.txt"));
        let keep_text: Vec<String> = keep.iter().map(u32::to_string).collect();
        std::fs::write(&keep_file, keep_text.join("\n")).unwrap();
        let keep_file = keep_file.to_string_lossy().into_owned();
        let kept_points: Vec<Vec<u64>> = keep
            .iter()
            .map(|&v| {
                k.point(starplex::ids::VertexId(v))
                    .iter()
                    .map(|x| x.to_bits())
                    .collect()
            })
            .collect();
        // a vertex target: 60 % of the vertices
        let half = (k.n_vertices() * 3 / 5).to_string();
        let mut modes = vec![
            (vec!["--mode", "homology"], false),
            (
                vec!["--mode", "homology", "--keep-vertices", &keep_file],
                false,
            ),
            (vec!["--mode", "homology", "--vertices", &half], false),
        ];
        if qem {
            modes.push((vec!["--mode", "qem", "--ratio", "0.3"], true));
            modes.push((vec!["--mode", "homology", "--keep-manifold"], true));
        }
        for (m, manifold) in &modes {
            let one = tmp
                .join(format!("{name}.one.spb"))
                .to_string_lossy()
                .into_owned();
            let mut args = vec!["--quiet", "simplify", &spb, &one, "--no-report"];
            args.extend(m.iter().copied());
            let (code, _, err) = run(Command::new(&cli).args(&args), limit);
            assert_eq!(code, Some(0), "starplex simplify {name} {m:?}: {err}");
            // a vertex target the single process reaches, the ranks reach too
            let goal_v: Option<usize> = m
                .iter()
                .position(|&x| x == "--vertices")
                .map(|i| m[i + 1].parse().unwrap());
            let single_v = cells_of(&one).0.len() / k.ambient_dim();
            for (np, gather) in simplify_configs() {
                let out = tmp
                    .join(format!("{name}.p{np}.spb"))
                    .to_string_lossy()
                    .into_owned();
                let what = format!("-np {np} simplify {name} {m:?} --gather-below {gather}");
                let Some(v) = run_simplify(np, gather, &spb, &out, m, &what, &mut failures) else {
                    continue;
                };
                checked += 1;
                // the report: the single process's topology summaries of input and output
                let k_out = starplex::io::read(Path::new(&out), &Default::default())
                    .unwrap()
                    .complex;
                let (b, a) = (summary(&k), summary(&k_out));
                if v["before"] != topology_json(&b)
                    || v["after"] != topology_json(&a)
                    || v["topology_kept"] != topology_kept(&b, &a)
                {
                    failures.push(format!(
                        "{what}: the report {} {} {}, the single process's {} {}",
                        v["before"],
                        v["after"],
                        v["topology_kept"],
                        topology_json(&b),
                        topology_json(&a)
                    ));
                }
                if (v["mode"] == "qem") != v["max_error"].is_f64() {
                    failures.push(format!("{what}: quadric errors reported: {v}"));
                }
                if np == 1 && cells_of(&out) != cells_of(&one) {
                    failures.push(format!("{what}: differs from the single process"));
                }
                if m.contains(&"--keep-vertices") {
                    let (coords, _) = cells_of(&out);
                    let d = k.ambient_dim();
                    let have: std::collections::BTreeSet<Vec<u64>> = coords
                        .chunks_exact(d)
                        .map(|p| p.iter().map(|x| x.to_bits()).collect())
                        .collect();
                    if let Some(p) = kept_points.iter().find(|p| !have.contains(*p)) {
                        failures.push(format!("{what}: a kept vertex is gone: {p:?}"));
                    }
                    if v["per_round"][0]["kept_vertices"].as_u64() != Some(keep.len() as u64) {
                        failures.push(format!("{what}: the report's kept vertices: {v}"));
                    }
                }
                let after = topology(&cli, &out);
                if trimmed(&after.0) != trimmed(&before.0)
                    || (*manifold && (after.1 > before.1 || after.2 > before.2))
                {
                    failures.push(format!(
                        "{what}: topology (betti, nm vertices, nm edges) {after:?}, was {before:?}"
                    ));
                }
                let cells = &v["cells"];
                if cells[1].as_u64() >= cells[0].as_u64() || v["n_contractions"].as_u64() == Some(0)
                {
                    failures.push(format!("{what}: nothing contracted: {v}"));
                }
                if let Some(g) = goal_v.filter(|&g| single_v <= g) {
                    let got = cells_of(&out).0.len() / k.ambient_dim();
                    if got > g || v["target_vertices"].as_u64() != Some(g as u64) {
                        failures.push(format!(
                                "{what}: {got} vertices for a target of {g} (single process {single_v}): {v}"
                            ));
                    }
                }
                if cells[1].as_u64() != Some(cells_of(&out).1.len() as u64) {
                    failures.push(format!(
                        "{what}: the report's cell count is not the file's: {v}"
                    ));
                }
            }
        }
    }
    std::fs::remove_dir_all(&tmp).ok();
    assert!(checked > 0, "no simplicial dataset found");
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The values of an integer column, or of a float column as bit patterns.
fn column(
    k: &starplex::complex::IndexedComplex,
    t: starplex::attr::AttrTarget,
    name: &str,
) -> Vec<i64> {
    use starplex::attr::AttrValues;
    match k.attributes().get(t, name).map(|c| &c.values) {
        Some(AttrValues::Int(v)) => v.clone(),
        Some(AttrValues::Float(v)) => v.iter().map(|x| x.to_bits() as i64).collect(),
        None => panic!("no {t:?} attribute {name}"),
    }
}

/// Betti numbers over Z/2 (trailing zeros dropped) of the cells of `k` whose label is `l`, as
/// a complex of its own (its vertices only).
fn region_betti(k: &starplex::complex::IndexedComplex, labels: &[i64], l: i64) -> Vec<u64> {
    use starplex::buf::Buf;
    let mut at = std::collections::BTreeMap::new();
    let mut blocks: Vec<(starplex::cell::CellKind, Vec<u32>)> = Vec::new();
    for (c, _) in k.cells().zip(labels).filter(|(_, m)| **m == l) {
        let i = match blocks.iter().position(|(x, _)| *x == c.kind) {
            Some(i) => i,
            None => {
                blocks.push((c.kind, Vec::new()));
                blocks.len() - 1
            }
        };
        for &v in c.vertices {
            let n = at.len() as u32;
            blocks[i].1.push(*at.entry(v).or_insert(n));
        }
    }
    let mut coords = vec![0.0; at.len() * k.ambient_dim()];
    for (&v, &i) in &at {
        let d = k.ambient_dim();
        coords[i as usize * d..(i as usize + 1) * d]
            .copy_from_slice(k.point(starplex::ids::VertexId(v)));
    }
    let blocks = blocks
        .into_iter()
        .map(|(x, v)| (x, Buf::Owned(v)))
        .collect();
    let r =
        starplex::complex::IndexedComplex::from_parts(k.ambient_dim(), Buf::Owned(coords), blocks)
            .expect("a region is a complex");
    trim_zeros(starplex::algo::homology::betti_z2(&r).expect("homology of a region"))
}

/// `simplify` carries the input's attribute columns: on the triangle and tetrahedral elephants
/// with a vertex column of input ids (`orig`) and one of input coordinates (`pos`, 3 floats),
/// a cell column of input cell ids (`cid`) and a label (`medit:ref`, by the side of the median
/// x of the cell's centroid; kept by default, as `starplex simplify` does), the output of 1-4
/// ranks, in homology mode and QEM, with and without the last round on rank 0, every ninth
/// vertex kept by a vertex column (`--keep-vertex-attribute pin`): every vertex
/// has its own input id and input position (and, in homology mode, that position), pinned
/// vertices survive where they were; every cell
/// is the image of the input cell it names (the surviving vertices of that cell are among its
/// vertices) and has that cell's label; each label region keeps its Betti numbers; one rank
/// gives the single process's cells with their values.
#[test]
fn simplify_carries_attributes_and_keeps_label_regions() {
    use starplex::attr::{AttrTarget as T, Attribute, Attributes};
    use std::collections::{BTreeMap, BTreeSet};
    let Some((cli, data, tmp)) = setup("starplex-mpi-simplify-attrs") else {
        return;
    };
    let limit = Duration::from_secs(600);
    let mut failures = Vec::new();
    let mut checked = 0;
    for src in data.iter().filter(|p| {
        let n = p.file_stem().unwrap().to_string_lossy();
        n == "tri_elephant" || n == "tet_elephant"
    }) {
        let name = src.file_stem().unwrap().to_string_lossy().into_owned();
        let mut k = starplex::io::read(src, &Default::default())
            .unwrap()
            .complex;
        let d = k.ambient_dim();
        let cx: Vec<f64> = k
            .cells()
            .map(|c| {
                c.vertices
                    .iter()
                    .map(|&v| k.point(starplex::ids::VertexId(v))[0])
                    .sum::<f64>()
                    / c.vertices.len() as f64
            })
            .collect();
        let mut sorted = cx.clone();
        sorted.sort_by(f64::total_cmp);
        let median = sorted[sorted.len() / 2];
        let labels_in: Vec<i64> = cx.iter().map(|&x| 1 + i64::from(x > median)).collect();
        let n = k.n_vertices();
        k.set_attributes(Attributes {
            vertex: vec![
                Attribute::int("orig", 1, (0..n as i64).collect()),
                Attribute::float("pos", d, k.coords().to_vec()),
                Attribute::int("pin", 1, (0..n).map(|v| i64::from(v % 9 == 0)).collect()),
            ],
            cell: vec![
                Attribute::int("medit:ref", 1, labels_in.clone()),
                Attribute::int("cid", 1, (0..k.n_cells() as i64).collect()),
            ],
        })
        .unwrap();
        let pinned: Vec<u32> = (0..n as u32).filter(|v| v % 9 == 0).collect();
        let spb = tmp.join(format!("{name}.spb"));
        starplex::io::write(&spb, &k, None).unwrap();
        let spb = spb.to_string_lossy().into_owned();
        let cells_in: Vec<Vec<u32>> = k.cells().map(|c| c.vertices.to_vec()).collect();
        let regions_in: BTreeMap<i64, Vec<u64>> = [1, 2]
            .iter()
            .map(|&l| (l, region_betti(&k, &labels_in, l)))
            .collect();
        // each output cell with its values, sorted: equality up to the order of the cells
        let listed = |o: &starplex::complex::IndexedComplex| {
            let (lab, cid) = (column(o, T::Cell, "medit:ref"), column(o, T::Cell, "cid"));
            let orig = column(o, T::Vertex, "orig");
            let mut v: Vec<(Vec<i64>, i64, i64)> = o
                .cells()
                .zip(lab.iter().zip(&cid))
                .map(|(c, (&l, &i))| {
                    let mut vs: Vec<i64> = c.vertices.iter().map(|&u| orig[u as usize]).collect();
                    vs.sort_unstable();
                    (vs, l, i)
                })
                .collect();
            v.sort();
            v
        };
        for mode in ["homology", "qem"] {
            let one = tmp
                .join(format!("{name}.{mode}.one.spb"))
                .to_string_lossy()
                .into_owned();
            // the options both binaries get
            let opts = [
                "--no-report",
                "--mode",
                mode,
                "--ratio",
                "0.3",
                "--keep-vertex-attribute",
                "pin",
            ];
            let args = [&["--quiet", "simplify", &spb, &one][..], &opts, &["--json"]].concat();
            let (code, stdout, err) = run(Command::new(&cli).args(args), limit);
            assert_eq!(code, Some(0), "starplex simplify {name} {mode}: {err}");
            let cli_report = without_timings(&stdout, "starplex simplify");
            let single = starplex::io::read(Path::new(&one), &Default::default())
                .unwrap()
                .complex;
            for (np, gather) in simplify_configs() {
                let what =
                    format!("-np {np} simplify {name} --mode {mode} --gather-below {gather}");
                let out = tmp
                    .join(format!("{name}.p{np}.spb"))
                    .to_string_lossy()
                    .into_owned();
                let Some(v) = run_simplify(np, gather, &spb, &out, &opts, &what, &mut failures)
                else {
                    continue;
                };
                checked += 1;
                if v["labels_kept"] != "medit:ref"
                    || v["labels_available"] != serde_json::json!(["medit:ref", "cid"])
                    || v["per_round"][0]["kept_vertices"].as_u64() != Some(pinned.len() as u64)
                    || v["locked_vertices"] != cli_report["locked_vertices"]
                    || v["attributes"] != cli_report["attributes"]
                {
                    failures.push(format!("{what}: the labels reported: {v}"));
                }
                let o = starplex::io::read(Path::new(&out), &Default::default())
                    .unwrap()
                    .complex;
                let names = |t| -> Vec<&str> {
                    o.attributes()
                        .of(t)
                        .iter()
                        .map(|c| c.name.as_str())
                        .collect()
                };
                if names(T::Vertex) != ["orig", "pos", "pin"]
                    || names(T::Cell) != ["medit:ref", "cid"]
                {
                    failures.push(format!(
                        "{what}: columns {:?} {:?}",
                        names(T::Vertex),
                        names(T::Cell)
                    ));
                    continue;
                }
                if np == 1 && listed(&o) != listed(&single) {
                    failures.push(format!("{what}: differs from the single process"));
                }
                // vertices: their own input id and position
                let (orig, pos) = (column(&o, T::Vertex, "orig"), column(&o, T::Vertex, "pos"));
                let survivors: BTreeSet<i64> = orig.iter().copied().collect();
                if survivors.len() != orig.len() || orig.iter().any(|&x| x < 0 || x >= n as i64) {
                    failures.push(format!("{what}: vertex ids repeated or out of range"));
                    continue;
                }
                let bad_vertex = (0..o.n_vertices()).find(|&i| {
                    let p_in = k.point(starplex::ids::VertexId(orig[i] as u32));
                    let own: Vec<i64> = p_in.iter().map(|x| x.to_bits() as i64).collect();
                    pos[i * d..(i + 1) * d] != own[..]
                        || (mode == "homology"
                            && o.point(starplex::ids::VertexId(i as u32)) != p_in)
                });
                // pinned vertices survive, unmoved
                let at: BTreeMap<i64, usize> =
                    orig.iter().enumerate().map(|(i, &x)| (x, i)).collect();
                if let Some(v) = pinned.iter().find(|&&v| {
                    at.get(&(v as i64)).is_none_or(|&i| {
                        o.point(starplex::ids::VertexId(i as u32))
                            != k.point(starplex::ids::VertexId(v))
                    })
                }) {
                    failures.push(format!("{what}: pinned vertex {v} removed or moved"));
                }
                if let Some(i) = bad_vertex {
                    failures.push(format!(
                        "{what}: vertex {i} (input {}) has another position",
                        orig[i]
                    ));
                }
                // cells: images of the input cells they name, with their labels
                let (lab, cid) = (column(&o, T::Cell, "medit:ref"), column(&o, T::Cell, "cid"));
                let distinct: BTreeSet<i64> = cid.iter().copied().collect();
                if distinct.len() != cid.len() {
                    failures.push(format!("{what}: two cells name one input cell"));
                }
                let bad_cell = o.cells().enumerate().find(|(j, c)| {
                    let Some(g) = usize::try_from(cid[*j])
                        .ok()
                        .filter(|&g| g < cells_in.len())
                    else {
                        return true;
                    };
                    let here: BTreeSet<i64> =
                        c.vertices.iter().map(|&u| orig[u as usize]).collect();
                    lab[*j] != labels_in[g]
                        || cells_in[g].iter().any(|&v| {
                            survivors.contains(&(v as i64)) && !here.contains(&(v as i64))
                        })
                });
                if let Some((j, c)) = bad_cell {
                    failures.push(format!(
                        "{what}: cell {j} {:?} is not the image of input cell {} (label {})",
                        c.vertices, cid[j], lab[j]
                    ));
                }
                for (&l, b) in &regions_in {
                    let after = region_betti(&o, &lab, l);
                    if &after != b {
                        failures.push(format!(
                            "{what}: region {l} has Betti numbers {after:?}, was {b:?}"
                        ));
                    }
                }
            }
        }
    }
    std::fs::remove_dir_all(&tmp).ok();
    assert_eq!(
        checked,
        2 * 2 * (2 * ranks().len() - usize::from(ranks().contains(&1))),
        "datasets missing"
    );
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// `simplify`'s refusals: CP cells (with the command that triangulates), no output named, an
/// output that is a stream, a ratio out of range, attributes the input does not have; each
/// ends every rank with status 2 and leaves no file behind.
#[test]
fn simplify_refuses_what_it_cannot_do() {
    use starplex::cell::CellKind;
    use starplex::complex::{BuildOptions, ComplexBuilder};
    if ready().is_none() {
        return;
    }
    let tmp =
        std::env::temp_dir().join(format!("starplex-mpi-simplify-bad-{}", std::process::id()));
    std::fs::create_dir_all(&tmp).unwrap();
    let write = |name: &str, kind: CellKind, cells: &[&[u32]]| {
        let mut b = ComplexBuilder::new(2).unwrap();
        for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] {
            b.push_vertex(&p).unwrap();
        }
        for c in cells {
            b.push_cell(kind, c).unwrap();
        }
        let k = b.build(&BuildOptions::default()).unwrap().0;
        let mut bytes = Vec::new();
        starplex::io::binary::write(&mut bytes, &k).unwrap();
        let p = tmp.join(name);
        std::fs::write(&p, &bytes).unwrap();
        p.to_string_lossy().into_owned()
    };
    let quad = write("q.spb", CellKind::Quad, &[&[0, 1, 3, 2]]);
    let tri = write("t.spb", CellKind::Simplex(2), &[&[0, 1, 2], &[1, 3, 2]]);
    let out = tmp.join("out.spb").to_string_lossy().into_owned();
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (vec!["simplify", &quad, "-o", &out], "triangulate"),
        (vec!["simplify", &tri], "-o OUT.spb"),
        (vec!["simplify", &tri, "-o", "/dev/stdout"], "regular file"),
        (
            vec!["simplify", &tri, "-o", &out, "--ratio", "1.5"],
            "between 0 and 1",
        ),
        (
            vec![
                "simplify",
                &tri,
                "-o",
                &out,
                "--mode",
                "homology",
                "--max-error",
                "1",
            ],
            "qem",
        ),
        (
            vec!["simplify", &tri, "-o", &out, "--keep-labels", "nope"],
            "--keep-labels nope: no cell attribute of that name (the input has no cell attribute)",
        ),
        (
            vec!["simplify", &tri, "-o", &out, "--keep-vertex-attribute", "w"],
            "--keep-vertex-attribute w: no vertex attribute",
        ),
        (
            vec![
                "simplify",
                &tri,
                "-o",
                &out,
                "--keep-labels",
                "x",
                "--ignore-labels",
            ],
            "exclude each other",
        ),
    ];
    for np in [1, 2] {
        for (args, want) in &cases {
            let (code, _, err) = run(&mut mpi(np, args), Duration::from_secs(60));
            assert_eq!(code, Some(2), "-np {np} {args:?}: {err}");
            assert!(err.contains(want), "-np {np} {args:?}: {err}");
            assert!(!Path::new(&out).exists(), "-np {np} {args:?} wrote {out}");
        }
    }
    let left = leftovers(&tmp, |n| !n.contains("starplex-mpi"));
    assert!(left.is_empty(), "temporary files left: {left:?}");
    std::fs::remove_dir_all(&tmp).ok();
}

/// `query --relation R --all --out`: the merged `.jsonl`, `.csv` and `.npz` of 1-4 ranks are the bytes
/// `starplex query FILE --structure S --relation R --all --out` writes, for every small dataset
/// and every relation the single process answers on it (vertex relations from the owners'
/// stars; top-cell relations after the ghost layer is widened; p-faces by the owner of each
/// simplex's smallest vertex); `--per-rank` files hold every
/// item once.
#[test]
fn query_all_out_equals_the_single_process_bytes() {
    let Some((cli, data, tmp)) = setup("starplex-mpi-query") else {
        return;
    };
    let limit = Duration::from_secs(300);
    let mut failures = Vec::new();
    let mut checked = 0;
    for (d, src) in data.iter().enumerate() {
        let name = src.file_stem().unwrap().to_string_lossy().into_owned();
        let spb = to_spb(&cli, src, &tmp);
        for (i, rel) in ["vt", "vv", "link", "star", "adj", "ia-star", "pfaces"]
            .iter()
            .enumerate()
        {
            // csv or npz for some, jsonl for all; ranks 1-4 spread over the cases
            let exts: &[&str] = match (d + i) % 3 {
                0 => &["jsonl", "csv"],
                1 => &["jsonl", "npz"],
                _ => &["jsonl"],
            };
            for ext in exts {
                let one = tmp
                    .join(format!("{name}.{rel}.one.{ext}"))
                    .to_string_lossy()
                    .into_owned();
                let (code, _, _) = run(
                    Command::new(&cli).args([
                        "--quiet",
                        "query",
                        &spb,
                        "--structure",
                        "stellar",
                        "--relation",
                        rel,
                        "--all",
                        "--out",
                        &one,
                    ]),
                    limit,
                );
                if code != Some(0) {
                    continue; // not answered on this complex (a link of CP cells)
                }
                let want = std::fs::read(&one).unwrap();
                for np in [1 + (d + i) % 4, 1 + (d + i + 2) % 4] {
                    let out = tmp
                        .join(format!("{name}.{rel}.p{np}.{ext}"))
                        .to_string_lossy()
                        .into_owned();
                    let what = format!("-np {np} query {name} --relation {rel} --out .{ext}");
                    let (code, _, err) = run(
                        &mut mpi(
                            np,
                            &["query", &spb, "--relation", rel, "--all", "--out", &out],
                        ),
                        limit,
                    );
                    checked += 1;
                    if code != Some(0) {
                        failures.push(format!("{what}: status {code:?}: {err}"));
                    } else if std::fs::read(&out).unwrap() != want {
                        failures.push(format!("{what}: differs from the single process"));
                    }
                }
            }
        }
        // one file per rank: every line of the single process in exactly one of them
        if d % 4 == 0 {
            let one = tmp.join(format!("{name}.vt.one.jsonl"));
            let mut want: Vec<String> = std::fs::read_to_string(&one)
                .unwrap()
                .lines()
                .map(String::from)
                .collect();
            want.sort();
            let out = tmp
                .join(format!("{name}.pr.jsonl"))
                .to_string_lossy()
                .into_owned();
            let (code, _, err) = run(
                &mut mpi(
                    3,
                    &[
                        "query",
                        &spb,
                        "--relation",
                        "vt",
                        "--all",
                        "--out",
                        &out,
                        "--per-rank",
                    ],
                ),
                limit,
            );
            assert_eq!(code, Some(0), "--per-rank {name}: {err}");
            let mut got = Vec::new();
            for r in 0..3 {
                let p = tmp.join(format!("{name}.pr.rank{r}.jsonl"));
                got.extend(
                    std::fs::read_to_string(&p)
                        .unwrap()
                        .lines()
                        .map(String::from),
                );
            }
            got.sort();
            if got != want {
                failures.push(format!(
                    "--per-rank {name}: the parts are not the single process's lines"
                ));
            }
        }
    }
    let left = leftovers(&tmp, |n| !n.contains("starplex-mpi"));
    std::fs::remove_dir_all(&tmp).ok();
    assert!(left.is_empty(), "parts left behind: {left:?}");
    assert!(checked > 50, "only {checked} runs");
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// `validate --check`, `--fail-on` and `--max-list`: every small dataset gives the exit status
/// and the JSON of `starplex validate` with the same options (1 when a defect asked about is
/// found, 0 otherwise; lists cut to `--max-list` while each rank sends only its first
/// entries), with the same list of defects in the message, on 1-4 ranks.
#[test]
fn validate_check_and_fail_on_exit_as_the_single_process() {
    let Some((cli, data, tmp)) = setup("starplex-mpi-check") else {
        return;
    };
    let limit = Duration::from_secs(300);
    let found = |err: &str| {
        err.split_once("validation failed: ")
            .map(|(_, r)| r.lines().next().unwrap_or("").trim().to_string())
    };
    let mut failures = Vec::new();
    let mut statuses = std::collections::BTreeSet::new();
    for (d, src) in data.iter().enumerate() {
        let name = src.file_stem().unwrap().to_string_lossy().into_owned();
        let spb = to_spb(&cli, src, &tmp);
        for opts in [
            vec!["--check"],
            vec!["--fail-on", "boundary,disconnected"],
            vec!["--max-list", "7"],
        ] {
            let mut args = vec!["--quiet", "validate", spb.as_str(), "--json"];
            args.extend(opts.iter().copied());
            let (want_code, want_out, want_err) = run(Command::new(&cli).args(&args), limit);
            statuses.insert(want_code);
            let np = 1 + d % 4;
            let mut margs = vec!["validate", spb.as_str(), "--json"];
            margs.extend(opts.iter().copied());
            let (code, out, err) = run(&mut mpi(np, &margs), limit);
            let what = format!("-np {np} validate {name} {opts:?}");
            // the JSON too: lists cut to --max-list on every rank, counts complete
            if want_code == Some(0) || want_code == Some(1) {
                let (a, b) = (
                    without_timings(&want_out, &what),
                    without_timings(&out, &what),
                );
                if a != b {
                    failures.push(format!("{what}: JSON differs\n got {b}\nwant {a}"));
                }
            }
            if code != want_code || found(&err) != found(&want_err) {
                failures.push(format!(
                    "{what}: status {code:?} ({err}), the single process {want_code:?} ({want_err})"
                ));
            }
        }
    }
    std::fs::remove_dir_all(&tmp).ok();
    assert!(
        statuses.contains(&Some(0)) && statuses.contains(&Some(1)),
        "the datasets should give both statuses: {statuses:?}"
    );
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Eleven 11-simplices along a line (vertices `i..i+12`), split over two ranks: each cell
/// that spans them has up to 2^12 interface faces. Over `--max-faces` the Morse method ends
/// every rank with status 2 and says what to do; `--method contract` (no such bound) answers,
/// and so does a budget that fits.
#[test]
fn homology_refuses_an_interface_over_the_face_budget() {
    if ready().is_none() {
        return;
    }
    let tmp = std::env::temp_dir().join(format!("starplex-mpi-budget-{}", std::process::id()));
    std::fs::create_dir_all(&tmp).unwrap();
    let spb = line_of_simplices(&tmp.join("line.spb"), 11, 12);
    let limit = Duration::from_secs(60);
    let (code, _, err) = run(
        &mut mpi(2, &["homology", &spb, "--json", "--max-faces", "1000"]),
        limit,
    );
    assert_eq!(code, Some(2), "{err}");
    assert!(
        err.contains("interface faces") && err.contains("--method contract"),
        "{err}"
    );
    for extra in [
        vec!["--max-faces", "1000", "--method", "contract"],
        vec!["--max-faces", "10000000"],
    ] {
        let mut args = vec!["homology", spb.as_str(), "--json"];
        args.extend(extra.iter().copied());
        let (code, out, err) = run(&mut mpi(2, &args), limit);
        assert_eq!(code, Some(0), "{extra:?}: {err}");
        let v = without_timings(&out, "line");
        assert_eq!(v["betti"][0], 1, "{extra:?}: {v}");
        assert_eq!(v["euler_characteristic"], 1, "{extra:?}: {v}");
    }
    std::fs::remove_dir_all(&tmp).ok();
}

/// The cell shuffle in many small rounds (`STARPLEX_MPI_ROUND_VALUES=64`: a few cells per
/// round) builds the same local complexes: `info` and `validate` of every small dataset equal
/// the single process's on 2 and 3 ranks.
#[test]
fn the_cell_shuffle_in_small_rounds_changes_nothing() {
    let Some((cli, data, tmp)) = setup("starplex-mpi-rounds") else {
        return;
    };
    let limit = Duration::from_secs(300);
    let mut failures = Vec::new();
    for src in &data {
        let name = src.file_stem().unwrap().to_string_lossy().into_owned();
        let spb_s = to_spb(&cli, src, &tmp);
        for verb in ["info", "validate"] {
            let (code, out, err) = run(
                Command::new(&cli).args(["--quiet", verb, &spb_s, "--json"]),
                limit,
            );
            assert_eq!(code, Some(0), "starplex {verb} {name}: {err}");
            let want = without_timings(&out, &format!("starplex {verb} {name}"));
            for np in [2, 3] {
                let mut c = mpi(np, &[verb, &spb_s, "--json"]);
                c.env("STARPLEX_MPI_ROUND_VALUES", "64");
                let (code, out, err) = run(&mut c, limit);
                let what = format!("-np {np} {verb} {name} in rounds of 64 values");
                if code != Some(0) {
                    failures.push(format!("{what}: status {code:?}: {err}"));
                    continue;
                }
                if without_timings(&out, &what) != want {
                    failures.push(format!("{what}: differs"));
                }
            }
        }
    }
    std::fs::remove_dir_all(&tmp).ok();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// `n` simplices of `arity` vertices along a line (cell `i` has the vertices `i..i + arity`, on
/// `n + arity - 1` vertices in 3D), written as `.spb` at `path` (returned).
fn line_of_simplices(path: &Path, n: u32, arity: u32) -> String {
    use starplex::cell::CellKind;
    use starplex::complex::{BuildOptions, ComplexBuilder};
    let mut b = ComplexBuilder::new(3).unwrap();
    for i in 0..n + arity - 1 {
        b.push_vertex(&[i as f64, (i * i % 7) as f64, 0.0]).unwrap();
    }
    for i in 0..n {
        b.push_cell(
            CellKind::Simplex((arity - 1) as u8),
            &(i..i + arity).collect::<Vec<u32>>(),
        )
        .unwrap();
    }
    let k = b.build(&BuildOptions::default()).unwrap().0;
    let mut bytes = Vec::new();
    starplex::io::binary::write(&mut bytes, &k).unwrap();
    std::fs::write(path, &bytes).unwrap();
    path.to_string_lossy().into_owned()
}

/// Fifteen 29-simplices along a line, split over 2-3 ranks: the cells that span ranks have
/// ~2^30 interface faces, so `homology` without `--method` contracts instead of listing them
/// (and says so); the Betti numbers are those of the single process.
#[test]
fn homology_of_high_dimensional_cells_falls_back_to_contraction() {
    let Some(cli) = ready() else { return };
    let tmp = std::env::temp_dir().join(format!("starplex-mpi-auto-{}", std::process::id()));
    std::fs::create_dir_all(&tmp).unwrap();
    let spb = line_of_simplices(&tmp.join("line30.spb"), 15, 30);
    let limit = Duration::from_secs(120);
    let (code, out, err) = run(
        Command::new(&cli).args(["--quiet", "homology", &spb, "--json"]),
        limit,
    );
    assert_eq!(code, Some(0), "{err}");
    let want = without_timings(&out, "single");
    for np in [2, 3] {
        let (code, out, err) = run(&mut mpi(np, &["homology", &spb, "--json"]), limit);
        assert_eq!(code, Some(0), "-np {np}: {err}");
        let v = without_timings(&out, "line30");
        assert_eq!(v["betti"], want["betti"], "-np {np}: {v}");
        let scheme = v["distributed"]["scheme"].as_str().unwrap_or("");
        assert!(scheme.contains("contract"), "-np {np}: {v}");
    }
    std::fs::remove_dir_all(&tmp).ok();
}
