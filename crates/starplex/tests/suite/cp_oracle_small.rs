//! The incidence graph and IA* on the small CP datasets (quads, hexahedra, mixed
//! tet/pyramid/prism/hex): the oracle's vertex queries (VT, VV, from numpy and gmsh), the
//! f-vector (gmsh's unique edges and faces), boundary faces and faces in three or more top
//! cells (numpy on the VTK face templates) — never values computed by starplex.
use crate::common_data;

use serde_json::Value;
use starplex::ids::{CellId, VertexId};
use starplex::io::{self, ReadOptions};
use starplex::limits::Limits;
use starplex::tds::iastar::IaStar;
use starplex::tds::ig::IncidenceGraph;
use starplex::topo::{generic, Counts, Queries, TopCells};
use starplex::topo::{Adjacent, FacetAdjacency};
/// The default budgets with `n` stored simplices.
fn stored(n: u128) -> Limits {
    Limits {
        stored_simplices: n,
        ..Limits::default()
    }
}

fn u64s(v: &Value) -> Vec<u64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_u64().unwrap())
        .collect()
}

fn vertex_queries(name: &str, sname: &str, s: &dyn Queries, o: &Value) {
    let (mut cells, mut vv) = (Vec::new(), Vec::new());
    for q in o["vertex_queries"].as_array().unwrap() {
        let v = VertexId(q["vertex"].as_u64().unwrap() as u32);
        s.vertex_top_cells(v, &mut cells);
        let got: Vec<u64> = cells.iter().map(|c| c.0 as u64).collect();
        assert_eq!(
            got,
            u64s(&q["incident_top_cells"]),
            "{name}/{sname} VT({v})"
        );
        s.vertex_neighbours(v, &mut vv);
        let got: Vec<u64> = vv.iter().map(|w| w.0 as u64).collect();
        assert_eq!(got, u64s(&q["vv"]), "{name}/{sname} VV({v})");
    }
}

#[test]
fn ig_and_iastar_match_the_oracles_on_the_small_cp_datasets() {
    let sets: Vec<_> = common_data::small_datasets()
        .into_iter()
        .filter(|(name, ..)| {
            ["quad_", "hex", "mixed_"]
                .iter()
                .any(|p| name.starts_with(p))
        })
        .collect();
    if sets.is_empty() && !common_data::data_required() {
        eprintln!(
            "SKIPPED: no small CP datasets at {} (set STARPLEX_SHARED to the shared/ directory)",
            common_data::datasets_dir().display()
        );
        return;
    }
    let names: Vec<&str> = sets.iter().map(|s| s.0.as_str()).collect();
    for want in ["quad_elephant", "hexvox_skull", "mixed_plate_s"] {
        assert!(names.contains(&want), "{want} missing (found {names:?})");
    }
    for (name, path, o) in &sets {
        let k = io::read(path, &ReadOptions::default()).unwrap().complex;
        assert!(!k.is_simplicial(), "{name}");
        let ig = IncidenceGraph::new(&k, &stored(1 << 31)).unwrap();
        vertex_queries(name, "ig", &ig, o);
        assert_eq!(ig.f_vector().unwrap(), u64s(&o["f_vector"]), "{name}/ig");
        assert_eq!(
            generic::euler_characteristic(&ig).unwrap(),
            o["euler_characteristic"].as_i64().unwrap(),
            "{name}/ig"
        );
        let ia = IaStar::new(&k).unwrap();
        vertex_queries(name, "ia*", &ia, o);
        // pure complexes: a facet slot of a top is empty exactly on the boundary, and the
        // non-manifold facet lists are the facets in three or more tops
        let d = o["dim"].as_u64().unwrap() as usize;
        let mut boundary = 0u64;
        for c in 0..ia.n_top_cells() as u32 {
            assert_eq!(ia.top_cell_kind(CellId(c)).dim(), d, "{name}: pure");
            boundary += ia
                .facet_adjacency(CellId(c))
                .iter()
                .filter(|a| **a == Adjacent::None)
                .count() as u64;
        }
        assert_eq!(
            boundary,
            o["n_boundary_faces"].as_u64().unwrap(),
            "{name}/ia* boundary faces"
        );
        if let Some(n) = o.get("n_faces_shared_by_more_than_2_top_cells") {
            assert_eq!(
                ia.nm_faces_of_dim(d).len() as u64,
                n.as_u64().unwrap(),
                "{name}/ia*"
            );
        }
    }
}
