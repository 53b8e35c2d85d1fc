//! `starplex query`: every structure gives the oracle's answers for the oracle's vertices, in the
//! oracle's JSON names, on the small datasets shipped in ../shared/datasets/small.
use std::path::Path;
use std::process::Command;

/// `$STARPLEX_SHARED/datasets`, else `shared/datasets` beside the checkout or an ancestor.
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
fn every_structure_answers_the_oracle_vertex_queries() {
    let mut checked = 0;
    for name in [
        "tri_elephant",
        "tet_elephant",
        "vr_kitten_s",
        "sierp5_xs",
        "quad_elephant",
    ] {
        let spx = shared().join("small").join(format!("{name}.spx"));
        let oracle = shared().join("oracle").join(format!("{name}.json"));
        let (Ok(o), true) = (std::fs::read_to_string(&oracle), spx.exists()) else {
            continue;
        };
        let o: serde_json::Value = serde_json::from_str(&o).unwrap();
        let queries = o["vertex_queries"].as_array().unwrap();
        let simplicial = queries[0].get("link_f_vector").is_some();
        let structures: &[&str] = if simplicial {
            &[
                "vt",
                "ia-star",
                "simplex-tree",
                "ig",
                "is",
                "hasse",
                "stellar",
                "stellar:graph",
            ]
        } else {
            // the structures that hold CP cells
            &["vt", "ia-star", "ig", "stellar", "stellar:graph"]
        };
        for s in structures {
            let mut cmd = Command::new(env!("CARGO_BIN_EXE_starplex"));
            cmd.args(["--quiet", "query"]).arg(&spx);
            // `stellar:graph`: the Stellar tree on the decomposition by connectivity alone
            let (s, decomposition) = s.split_once(':').unwrap_or((s, "spatial"));
            if s == "stellar" {
                cmd.args(["--decomposition", decomposition]);
            }
            cmd.args([
                "--structure",
                s,
                "--relation",
                "vt",
                "vv",
                if simplicial { "link" } else { "vv" },
                "--json",
            ]);
            cmd.arg("--vertex");
            for q in queries {
                cmd.arg(q["vertex"].to_string());
            }
            let out = cmd.output().unwrap();
            assert!(
                out.status.success(),
                "{name} {s}: {}",
                String::from_utf8_lossy(&out.stderr)
            );
            let got: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
            let got = got.as_array().unwrap();
            assert_eq!(got.len(), queries.len(), "{name} {s}");
            for (g, q) in got.iter().zip(queries) {
                let mut keys = vec!["vertex", "incident_top_cells", "vv"];
                if simplicial {
                    keys.extend(["link_f_vector", "link_maximal_simplices"]);
                }
                for key in keys {
                    assert_eq!(
                        sorted(&g[key]),
                        sorted(&q[key]),
                        "{name} {s} vertex {} {key}",
                        q["vertex"]
                    );
                }
            }
            checked += 1;
        }
    }
    if checked == 0 && std::env::var("CI").map_or(true, |v| v != "true") {
        eprintln!("SKIPPED: no small datasets at {}", shared().display());
        return;
    }
    // 8 structures on 4 simplicial sets, 5 on the quad mesh
    assert!(
        checked == 37,
        "expected the small datasets in ../shared/datasets/small"
    );
}

/// A JSON list of lists with each inner list and the outer list sorted (the oracle lists link
/// simplices in top-cell order, starplex sorts them); other values unchanged.
fn sorted(v: &serde_json::Value) -> serde_json::Value {
    let Some(items) = v.as_array() else {
        return v.clone();
    };
    if !items.iter().all(|x| x.is_array()) {
        return v.clone();
    }
    let mut lists: Vec<Vec<u64>> = items
        .iter()
        .map(|x| {
            let mut l: Vec<u64> = x
                .as_array()
                .unwrap()
                .iter()
                .map(|n| n.as_u64().unwrap())
                .collect();
            l.sort_unstable();
            l
        })
        .collect();
    lists.sort();
    serde_json::json!(lists)
}

/// `query --all` of `ia-star` and `adj` counts the tops across every facet of every top cell
/// (in bulk, from the VT rows): on the Freudenthal grid of 6³ cubes (1296 tetrahedra, 432
/// boundary triangles) 4 × 1296 − 432 = 4752; on its 5184 hexahedra (4 per tetrahedron, 3
/// boundary quads per boundary triangle) 6 × 5184 − 1296 = 29808, for every structure holding
/// them. `adj` of a hexahedron is a simplex's question: an input error with what to do.
#[test]
fn all_facet_neighbours_count_the_interior_facets_twice() {
    let dir = std::env::temp_dir().join(format!("starplex-query-all-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (grid, hexes) = (dir.join("g.spx"), dir.join("h.spx"));
    let sp = |args: &[&str]| {
        Command::new(env!("CARGO_BIN_EXE_starplex"))
            .arg("--quiet")
            .args(args)
            .output()
            .unwrap()
    };
    let g = grid.to_str().unwrap();
    let h = hexes.to_str().unwrap();
    assert!(sp(&["generate", "grid", "6", "6", "6", "-o", g])
        .status
        .success());
    assert!(sp(&["generate", "hexes", g, "-o", h]).status.success());
    let cases = [
        (g, "ia-star", 4752),
        (g, "adj", 4752),
        (h, "ia-star", 29808),
    ];
    for (file, rel, want) in cases {
        for st in ["vt", "ia-star", "stellar", "ig"] {
            let o = sp(&[
                "query",
                file,
                "--structure",
                st,
                "--relation",
                rel,
                "--all",
                "--json",
            ]);
            let err = String::from_utf8_lossy(&o.stderr);
            assert!(o.status.success(), "{file} {st} {rel}: {err}");
            let j: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
            assert_eq!(j["total_size"], want, "{file} {st} {rel}");
        }
    }
    let o = sp(&[
        "query",
        h,
        "--structure",
        "stellar",
        "--relation",
        "adj",
        "--all",
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("a hex") && err.contains("--triangulate"),
        "{err}"
    );
    std::fs::remove_dir_all(&dir).ok();
}
