//! The Stellar decomposition by connectivity ([`Decomposition::Graph`]): on every small dataset
//! and on flag complexes of random graphs (whose only coordinates are their ids), every relation
//! of a graph-decomposed tree equals the spatial tree's (VT, VV, links, p-faces with coface
//! counts, top adjacency, validation, the IA* facet adjacency and vertex references), its leaves
//! partition the vertices in blocks of at most k_V, every leaf list is the explicit list, and
//! the tree is the same for any thread count and after a save and load.
use crate::common_data;

use std::collections::BTreeMap;

use starplex::algo::rips::flag_complex;
use starplex::complex::IndexedComplex;
use starplex::ids::{CellId, LeafId, TreeCellId, VertexId};
use starplex::io::{self, ReadOptions};
use starplex::stellar::sre::SreIter;
use starplex::stellar::{Decomposition, StellarOptions, StellarTree};
use starplex::testkit::XorShift;
use starplex::topo::{Adjacent, FacetAdjacency};

fn build(k: &IndexedComplex, kv: u32, d: Decomposition, threads: usize) -> StellarTree {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap()
        .install(|| {
            StellarTree::build(
                k,
                &StellarOptions {
                    kv: Some(kv),
                    decomposition: d,
                    ..Default::default()
                },
            )
            .unwrap()
        })
}

/// p-faces as a map face -> number of cofaces (the order of a tree's list is its own).
fn faces(t: &StellarTree, p: usize) -> BTreeMap<Vec<u32>, u32> {
    let f = t.p_faces(p).unwrap();
    (0..f.len())
        .map(|i| (f.faces.row(i).to_vec(), f.n_cofaces[i]))
        .collect()
}

/// The IA* facet adjacency with non-manifold facets named by their cells and vertices (their
/// ids are the structure's own), and the vertex references.
fn iastar(t: &StellarTree) -> (Vec<Vec<String>>, Vec<Vec<CellId>>) {
    let ia = t.iastar();
    let adj = (0..t.n_top_cells() as u32)
        .map(|c| {
            (0..ia.n_facet_slots(CellId(c)))
                .map(|j| match ia.facet_adjacent(CellId(c), j) {
                    Adjacent::NmFace(f) => {
                        let mut cs = ia.nm_face_cells(f);
                        cs.sort();
                        let mut vs = ia.nm_face_vertices(f);
                        vs.sort();
                        format!("nm {cs:?} {vs:?}")
                    }
                    a => format!("{a:?}"),
                })
                .collect()
        })
        .collect();
    let refs = (0..t.n_vertices() as u32)
        .map(|v| ia.vertex_references(VertexId(v)))
        .collect();
    (adj, refs)
}

/// The graph tree's own invariants: leaves partition the vertices in blocks of at most k_V,
/// every compressed leaf list expands to the explicit list.
fn check_leaves(t: &StellarTree, kv: u32) {
    let mut covered = 0u32;
    for l in 0..t.n_leaves() {
        let r = t.leaf_vertices(LeafId(l as u32));
        assert_eq!(r.start, covered);
        assert!(kv == 0 || r.len() <= kv as usize, "leaf {l}: {}", r.len());
        covered = r.end;
        let got: Vec<u32> = SreIter::new(t.leaf_encoded_cells(LeafId(l as u32))).collect();
        let want: Vec<u32> = (0..t.n_top_cells() as u32)
            .filter(|&c| t.tree_cell(TreeCellId(c)).1.iter().any(|v| r.contains(v)))
            .collect();
        assert_eq!(got, want, "leaf {l}");
    }
    assert_eq!(covered as usize, t.n_vertices());
}

/// Every relation of the graph tree equals the spatial tree's.
fn same_relations(name: &str, k: &IndexedComplex, kv: u32, faces_up_to: usize) {
    let s = build(k, kv, Decomposition::Spatial, 2);
    let g = build(k, kv, Decomposition::Graph, 2);
    assert_eq!(g.decomposition(), Decomposition::Graph);
    check_leaves(&g, kv);
    assert_eq!(g.vt_all(), s.vt_all(), "{name}: VT");
    assert_eq!(g.vv_all(), s.vv_all(), "{name}: VV");
    let all: Vec<VertexId> = (0..k.n_vertices() as u32).map(VertexId).collect();
    assert_eq!(
        g.links_of(&all).unwrap(),
        s.links_of(&all).unwrap(),
        "{name}: links"
    );
    for p in 0..=k.dim().unwrap_or(0).min(faces_up_to) {
        assert_eq!(faces(&g, p), faces(&s, p), "{name}: {p}-faces");
    }
    assert_eq!(g.top_adjacency(), s.top_adjacency(), "{name}: adjacency");
    assert_eq!(g.validate(), s.validate(), "{name}: validation");
    assert_eq!(iastar(&g), iastar(&s), "{name}: IA*");
    // the same tree for any thread count
    let g1 = build(k, kv, Decomposition::Graph, 1);
    // (everything but the build timings)
    assert_eq!(g1.nodes(), g.nodes(), "{name}: threads, nodes");
    assert_eq!(
        g1.vertex_to_input(),
        g.vertex_to_input(),
        "{name}: threads, vertices"
    );
    assert_eq!(
        g1.cell_to_input(),
        g.cell_to_input(),
        "{name}: threads, cells"
    );
    for l in 0..g.n_leaves() as u32 {
        let l = starplex::ids::LeafId(l);
        assert_eq!(
            g1.leaf_encoded_cells(l),
            g.leaf_encoded_cells(l),
            "{name}: threads, leaf {l:?}"
        );
    }
}

#[test]
fn graph_tree_answers_like_the_spatial_tree_on_the_small_datasets() {
    let files = common_data::spx_files("small");
    if files.is_empty() {
        assert!(!common_data::data_required(), "no small datasets");
        eprintln!("skipped: no small datasets (set STARPLEX_DATA)");
        return;
    }
    for (name, path) in files {
        let k = io::read(&path, &ReadOptions::default()).unwrap().complex;
        // the Sierpinski sets of dimension 7 have huge face counts: faces up to 3 there
        let up_to = if k.dim().unwrap_or(0) > 5 {
            3
        } else {
            usize::MAX
        };
        for kv in [k.n_vertices().div_ceil(40).max(8) as u32, 0] {
            eprintln!("{name}: k_V {kv}");
            same_relations(&name, &k, kv, up_to);
        }
    }
}

fn random_graph(n: usize, m: usize, seed: u64) -> Vec<(u32, u32)> {
    let mut r = XorShift::new(seed);
    let mut e = Vec::new();
    while e.len() < m {
        let a = (r.next_u64() % n as u64) as u32;
        // mostly local edges (clustered, many triangles), some long ones
        let b = if r.next_u64().is_multiple_of(4) {
            (r.next_u64() % n as u64) as u32
        } else {
            ((a as u64 + 1 + r.next_u64() % 12) % n as u64) as u32
        };
        if a != b {
            e.push((a, b));
        }
    }
    e
}

#[test]
fn graph_tree_of_flag_complexes() {
    for (seed, n, m, kv) in [
        (1u64, 300usize, 1200usize, 16u32),
        (2, 2000, 6000, 50),
        (3, 60, 90, 1),
    ] {
        let f = flag_complex(n, &random_graph(n, m, seed), &Default::default()).unwrap();
        same_relations(&format!("flag {seed}"), &f.complex, kv, usize::MAX);
        // saved and loaded: still a graph tree, the same tree
        let g = build(&f.complex, kv, Decomposition::Graph, 2);
        let p =
            std::env::temp_dir().join(format!("starplex-graph-{seed}-{}.stl", std::process::id()));
        g.save(&p).unwrap();
        let back = StellarTree::load(&p).unwrap();
        std::fs::remove_file(&p).ok();
        assert_eq!(back.decomposition(), Decomposition::Graph);
        assert_eq!(back.vt_all(), g.vt_all());
        assert_eq!(back.nodes(), g.nodes());
        assert_eq!(back.stats(), g.stats());
    }
}

/// On a path numbered out of order, the graph leaves are runs of the path (chi at most
/// 1 + (leaves - 1) / edges), while the spatial tree over the ids scatters them.
#[test]
fn graph_leaves_follow_connectivity() {
    let n = 1000u32;
    // position i along the path holds vertex (i * 7919) % n (7919 is prime to 1000)
    let along: Vec<u32> = (0..n).map(|i| i * 7919 % n).collect();
    let edges: Vec<(u32, u32)> = along.windows(2).map(|w| (w[0], w[1])).collect();
    let f = flag_complex(n as usize, &edges, &Default::default()).unwrap();
    let g = build(&f.complex, 10, Decomposition::Graph, 2);
    let s = build(&f.complex, 10, Decomposition::Spatial, 2);
    let (gs, ss) = (g.stats(), s.stats());
    let bound = 1.0 + (g.n_leaves() as f64 - 1.0) / (n as f64 - 1.0);
    assert!(gs.chi <= bound + 1e-9, "graph chi {} > {bound}", gs.chi);
    assert!(ss.chi > 1.5, "spatial chi {}", ss.chi);
    check_leaves(&g, 10);
}
