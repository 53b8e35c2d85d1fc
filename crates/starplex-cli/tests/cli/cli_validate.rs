//! `starplex validate --json` gives the answer of `starplex::algo::validate` (the trait-level
//! validation, run here on the naive VT index) on every small dataset: counts, id lists,
//! orientation.
use std::path::Path;
use std::process::Command;

use starplex::algo::validate::validate;
use starplex::topo::naive::VtIndex;

fn shared() -> std::path::PathBuf {
    if let Ok(s) = std::env::var("STARPLEX_SHARED") {
        return Path::new(&s).join("datasets");
    }
    let here = Path::new(env!("CARGO_MANIFEST_DIR"));
    here.ancestors()
        .map(|a| a.join("shared/datasets"))
        .find(|d| d.join("oracle").is_dir())
        .unwrap_or_else(|| here.join("../../../shared/datasets"))
}

#[test]
fn validate_json_equals_algo_on_the_small_datasets() {
    let Ok(rd) = std::fs::read_dir(shared().join("small")) else {
        assert!(
            std::env::var("CI").map_or(true, |v| v != "true"),
            "no datasets under CI"
        );
        println!("SKIPPED: no datasets");
        return;
    };
    let mut files: Vec<_> = rd
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|x| x == "spx"))
        .collect();
    files.sort();
    assert!(!files.is_empty());
    for f in &files {
        let out = Command::new(env!("CARGO_BIN_EXE_starplex"))
            .args(["validate", "--json", "--quiet", "--max-list", "100000000"])
            .arg(f)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let j: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        let k = starplex::io::read(f, &Default::default()).unwrap().complex;
        let r = validate(&VtIndex::new(&k));
        let name = f.display();
        let ids = |v: &serde_json::Value| -> Vec<u64> {
            v.as_array()
                .unwrap()
                .iter()
                .map(|x| x.as_u64().unwrap())
                .collect()
        };
        assert_eq!(j["dim"], r.dim, "{name}");
        assert_eq!(
            j["n_connected_components"], r.n_connected_components,
            "{name}"
        );
        assert_eq!(j["n_boundary_faces"], r.boundary_faces.len(), "{name}");
        assert_eq!(
            j["n_faces_shared_by_more_than_2_top_cells"],
            r.faces_in_more_than_two_cells.len(),
            "{name}"
        );
        assert_eq!(j["n_facet_components"], r.n_facet_components, "{name}");
        assert_eq!(j["pure"], r.pure, "{name}");
        assert_eq!(j["pseudo_manifold"], r.pseudo_manifold, "{name}");
        assert_eq!(
            j["orientable"],
            serde_json::to_value(r.orientable).unwrap(),
            "{name}"
        );
        assert_eq!(
            j["n_cells_to_flip"],
            serde_json::to_value(r.cells_to_flip.as_ref().map(|c| c.len())).unwrap(),
            "{name}"
        );
        let nmv: Vec<u64> = r.non_manifold_vertices.iter().map(|v| v.0 as u64).collect();
        assert_eq!(ids(&j["non_manifold_vertices"]), nmv, "{name}");
        let unk: Vec<u64> = r.unknown_vertices.iter().map(|v| v.0 as u64).collect();
        assert_eq!(ids(&j["unknown_vertices"]), unk, "{name}");
        let nme: Vec<[u64; 2]> = r
            .non_manifold_edges
            .iter()
            .map(|e| [e[0].0 as u64, e[1].0 as u64])
            .collect();
        let got: Vec<[u64; 2]> = j["non_manifold_edges"]
            .as_array()
            .unwrap()
            .iter()
            .map(|e| [e[0].as_u64().unwrap(), e[1].as_u64().unwrap()])
            .collect();
        assert_eq!(got, nme, "{name}");
        // the graph decomposition (connectivity alone) gives the same report
        let graph = Command::new(env!("CARGO_BIN_EXE_starplex"))
            .args(["validate", "--json", "--quiet", "--max-list", "100000000"])
            .args(["--decomposition", "graph"])
            .arg(f)
            .output()
            .unwrap();
        assert!(graph.status.success(), "{name}");
        let mut g: serde_json::Value = serde_json::from_slice(&graph.stdout).unwrap();
        let mut j = j;
        g["timings"] = serde_json::Value::Null;
        j["timings"] = serde_json::Value::Null;
        assert_eq!(g, j, "{name}: --decomposition graph");
    }
}

/// Writes `text` to a fresh file named `name` and returns its path.
fn temp_file(name: &str, text: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("starplex-cli-validate-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

#[test]
fn check_and_fail_on_set_the_exit_status_for_scripts() {
    // a closed octahedron: no defect, but it is not a ball (no boundary), one component
    let octa = temp_file(
        "octa.off",
        "OFF\n6 8 0\n1 0 0\n-1 0 0\n0 1 0\n0 -1 0\n0 0 1\n0 0 -1\n\
         3 0 2 4\n3 2 1 4\n3 1 3 4\n3 3 0 4\n3 2 0 5\n3 1 2 5\n3 3 1 5\n3 0 3 5\n",
    );
    // two triangles sharing only a vertex (non-manifold vertex 0) and a dangling edge
    let bowtie = temp_file(
        "bowtie.off",
        "OFF\n6 3 0\n0 0 0\n1 0 0\n1 1 0\n-1 0 0\n-1 -1 0\n5 5 0\n3 0 1 2\n3 0 3 4\n2 2 5\n",
    );
    let run = |f: &Path, extra: &[&str]| {
        Command::new(env!("CARGO_BIN_EXE_starplex"))
            .arg("validate")
            .arg(f)
            .args(extra)
            .output()
            .unwrap()
    };
    let ok = run(&octa, &["--check"]);
    assert_eq!(
        ok.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&ok.stderr)
    );
    let b = run(&octa, &["--fail-on", "boundary,disconnected"]);
    assert_eq!(b.status.code(), Some(0));
    let bad = run(&bowtie, &["--check"]);
    assert_eq!(bad.status.code(), Some(1));
    let err = String::from_utf8_lossy(&bad.stderr);
    assert!(err.contains("validation failed"), "{err}");
    // (the global convention: vertex 0, and both ends of the dangling edge, which is itself a
    // non-manifold edge of the 2-complex)
    assert!(
        err.contains("3 non-manifold vertices, 1 non-manifold edges"),
        "{err}"
    );
    assert!(err.contains("1 lower-dimensional top cells"), "{err}");
    // only what was asked for
    let b = run(&bowtie, &["--fail-on", "disconnected"]);
    assert_eq!(b.status.code(), Some(0));
    let b = run(&bowtie, &["--fail-on", "boundary", "--json"]);
    assert_eq!(b.status.code(), Some(1));
    let v: serde_json::Value = serde_json::from_slice(&b.stdout).unwrap();
    assert_eq!(v["n_non_manifold_vertices"], 3);
    // an unknown defect name is a usage error (exit 2) listing the names
    let u = run(&bowtie, &["--fail-on", "holes"]);
    assert_eq!(u.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&u.stderr).contains("non-manifold"));
}

#[test]
fn notes_reach_the_json_and_survive_quiet() {
    // a pentagon is fan-triangulated: the note is in the JSON and on stderr even with --quiet
    let penta = temp_file(
        "penta.off",
        "OFF\n5 1 0\n0 0 0\n1 0 0\n1.5 1 0\n0.5 2 0\n-0.5 1 0\n5 0 1 2 3 4\n",
    );
    let out = Command::new(env!("CARGO_BIN_EXE_starplex"))
        .args(["--quiet", "validate", "--json"])
        .arg(&penta)
        .output()
        .unwrap();
    assert!(out.status.success());
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert!(
        v["notes"][0].as_str().unwrap().contains("fan-triangulated"),
        "{v}"
    );
    assert!(String::from_utf8_lossy(&out.stderr).contains("fan-triangulated"));
}
