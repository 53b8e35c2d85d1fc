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
    }
}
