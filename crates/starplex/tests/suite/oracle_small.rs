//! Every small dataset: `info` and the vertex queries equal the third-party oracle
//! (GUDHI, gmsh, pymeshlab, trimesh, numpy — never starplex).
use crate::common_data;

use serde_json::Value;
use starplex::algo::info::{info, InfoOptions};
use starplex::ids::VertexId;
use starplex::io::{self, ReadOptions};
use starplex::topo::{link::vertex_link, naive::VtIndex, VertexAdjacency, VertexStar};

fn u64s(v: &Value) -> Vec<u64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_u64().unwrap())
        .collect()
}

#[test]
fn info_and_vertex_queries_match_the_oracles() {
    let sets = common_data::small_datasets();
    if sets.is_empty() && !common_data::data_required() {
        eprintln!(
            "SKIPPED: no small datasets at {} (set STARPLEX_SHARED to the shared/ directory)",
            common_data::datasets_dir().display()
        );
        return;
    }
    assert!(
        sets.len() >= 9,
        "expected the small datasets in ../shared/datasets/small (found {})",
        sets.len()
    );
    for (name, path, o) in sets {
        let k = io::read(&path, &ReadOptions::default()).unwrap().complex;
        let s = info(&k, &InfoOptions::default());
        assert_eq!(s.n_vertices, o["n_vertices"].as_u64().unwrap(), "{name}");
        assert_eq!(
            s.n_isolated_vertices,
            o["n_isolated_vertices"].as_u64().unwrap(),
            "{name}"
        );
        assert_eq!(s.ambient_dim, o["ambient_dim"].as_u64().unwrap(), "{name}");
        assert_eq!(s.dim, o["dim"].as_i64().unwrap(), "{name}");
        assert_eq!(s.pure, o["pure"].as_bool().unwrap(), "{name}");
        assert_eq!(s.n_top_cells, o["n_top_cells"].as_u64().unwrap(), "{name}");
        for (t, n) in o["top_cells"].as_object().unwrap() {
            assert_eq!(s.top_cells.get(t).copied(), n.as_u64(), "{name} {t}");
        }
        assert_eq!(
            s.top_cells.len(),
            o["top_cells"].as_object().unwrap().len(),
            "{name}"
        );
        assert_eq!(s.f_vector, Some(u64s(&o["f_vector"])), "{name}");
        assert_eq!(
            s.euler_characteristic,
            o["euler_characteristic"].as_i64(),
            "{name}"
        );
        if !o["n_boundary_faces"].is_null() {
            assert_eq!(s.n_boundary_faces, o["n_boundary_faces"].as_u64(), "{name}");
        }
        if !o["n_faces_shared_by_more_than_2_top_cells"].is_null() {
            assert_eq!(
                s.n_faces_shared_by_more_than_2_top_cells,
                o["n_faces_shared_by_more_than_2_top_cells"].as_u64(),
                "{name}"
            );
        }
        assert_eq!(
            s.n_connected_components,
            o["n_connected_components"].as_u64().unwrap(),
            "{name}"
        );
        let (lo, hi) = s.bbox.clone().unwrap();
        for (axis, (a, b)) in lo.iter().zip(hi.iter()).enumerate() {
            assert!(
                (a - o["bbox"][0][axis].as_f64().unwrap()).abs() < 1e-9,
                "{name}"
            );
            assert!(
                (b - o["bbox"][1][axis].as_f64().unwrap()).abs() < 1e-9,
                "{name}"
            );
        }

        let idx = VtIndex::new(&k);
        let (mut cells, mut vv) = (Vec::new(), Vec::new());
        for q in o["vertex_queries"].as_array().unwrap() {
            let v = VertexId(q["vertex"].as_u64().unwrap() as u32);
            idx.vertex_top_cells(v, &mut cells);
            let got: Vec<u64> = cells.iter().map(|c| c.0 as u64).collect();
            assert_eq!(got, u64s(&q["incident_top_cells"]), "{name} vt({v})");
            idx.vertex_neighbours(v, &mut vv);
            let got: Vec<u64> = vv.iter().map(|w| w.0 as u64).collect();
            assert_eq!(got, u64s(&q["vv"]), "{name} vv({v})");
            if let Some(lf) = q.get("link_f_vector") {
                let l = vertex_link(&idx, v).unwrap();
                assert_eq!(l.f_vector, u64s(lf), "{name} link f-vector({v})");
                let want: Vec<Vec<u32>> = q["link_maximal_simplices"]
                    .as_array()
                    .unwrap()
                    .iter()
                    .map(|m| u64s(m).into_iter().map(|x| x as u32).collect())
                    .collect();
                let mut want = want;
                want.iter_mut().for_each(|m| m.sort_unstable());
                want.sort();
                assert_eq!(
                    l.maximal_simplices, want,
                    "{name} link maximal simplices({v})"
                );
            }
        }
    }
}
