//! Stellar tree on every small dataset: VT, VV and links of the oracle's vertex queries, and
//! validation (components, boundary faces, non-manifold vertices and edges of surfaces) equal
//! the third-party oracles.
use crate::common_data;

use serde_json::Value;
use starplex::ids::VertexId;
use starplex::io::{self, ReadOptions};
use starplex::stellar::{StellarOptions, StellarTree};

fn u64s(v: &Value) -> Vec<u64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_u64().unwrap())
        .collect()
}

#[test]
fn stellar_matches_the_oracles() {
    let sets = common_data::small_datasets();
    if sets.is_empty() && !common_data::data_required() {
        eprintln!(
            "SKIPPED: no small datasets at {}",
            common_data::datasets_dir().display()
        );
        return;
    }
    assert!(sets.len() >= 9, "small datasets not found ({})", sets.len());
    for (name, path, o) in sets {
        let k = io::read(&path, &ReadOptions::default()).unwrap().complex;
        let kvs: &[Option<u32>] = if k.n_cells() < 15_000 {
            &[None, Some(10)]
        } else {
            &[None]
        };
        for &kv in kvs {
            let t = StellarTree::build(
                &k,
                &StellarOptions {
                    kv,
                    ..Default::default()
                },
            )
            .unwrap();
            let qs: Vec<VertexId> = o["vertex_queries"]
                .as_array()
                .unwrap()
                .iter()
                .map(|q| VertexId(q["vertex"].as_u64().unwrap() as u32))
                .collect();
            let vt = t.vt_of(&qs).unwrap();
            let vv = t.vv_of(&qs).unwrap();
            let links = t.links_of(&qs).unwrap();
            for (i, q) in o["vertex_queries"].as_array().unwrap().iter().enumerate() {
                let got: Vec<u64> = vt[i].iter().map(|c| c.0 as u64).collect();
                assert_eq!(got, u64s(&q["incident_top_cells"]), "{name} vt({})", qs[i]);
                let got: Vec<u64> = vv[i].iter().map(|c| c.0 as u64).collect();
                assert_eq!(got, u64s(&q["vv"]), "{name} vv({})", qs[i]);
                if let Some(lf) = q.get("link_f_vector") {
                    let l = links[i].as_ref().unwrap();
                    assert_eq!(l.f_vector, u64s(lf), "{name} link f-vector({})", qs[i]);
                    let mut want: Vec<Vec<u32>> = q["link_maximal_simplices"]
                        .as_array()
                        .unwrap()
                        .iter()
                        .map(|m| u64s(m).into_iter().map(|x| x as u32).collect())
                        .collect();
                    want.iter_mut().for_each(|m| m.sort_unstable());
                    want.sort();
                    assert_eq!(l.maximal_simplices, want, "{name} link({})", qs[i]);
                }
            }
            let r = t.validate();
            assert_eq!(
                r.n_connected_components,
                o["n_connected_components"].as_u64().unwrap(),
                "{name}"
            );
            if let Some(b) = o["n_boundary_faces"].as_u64() {
                assert_eq!(r.n_boundary_faces() as u64, b, "{name} boundary faces");
            }
            if let Some(x) = o["n_faces_shared_by_more_than_2_top_cells"].as_u64() {
                assert_eq!(r.faces_in_more_than_two_cells.len() as u64, x, "{name}");
            }
            if let Some(x) = o.get("n_non_manifold_vertices").and_then(|x| x.as_u64()) {
                assert_eq!(
                    r.non_manifold_vertices.len() as u64,
                    x,
                    "{name} nm vertices"
                );
            }
            if let Some(x) = o.get("n_non_manifold_edges").and_then(|x| x.as_u64()) {
                assert_eq!(r.non_manifold_edges.len() as u64, x, "{name} nm edges");
            }
            assert_eq!(r.pure, o["pure"].as_bool().unwrap(), "{name} pure");
            // f-vector by the Stellar tree's face extraction (where the budget allows)
            if let Some(f) = o["f_vector"].as_array() {
                for (p, n) in f.iter().enumerate().skip(1) {
                    if t.face_visits(p) < 20_000_000 {
                        assert_eq!(
                            t.count_p_faces(p).unwrap(),
                            n.as_u64().unwrap(),
                            "{name} {p}-faces"
                        );
                    }
                }
            }
        }
    }
}
