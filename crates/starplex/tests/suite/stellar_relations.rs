//! Stellar tree relations against plain brute-force models on random complexes (seeded
//! proptest: mixed dimensions, non-manifold, isolated and coincident vertices, CP cells), for
//! k_V in {1, 10, 100, 0} and 1 and 2 threads.
use std::collections::{BTreeMap, BTreeSet};

use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed, TestRunner};
use starplex::cell::CellKind;
use starplex::complex::{BuildOptions, ComplexBuilder, IndexedComplex};
use starplex::ids::{CellId, LeafId, TreeCellId, VertexId};
use starplex::stellar::sre::SreIter;
use starplex::stellar::{Decomposition, SplitMode, StellarOptions, StellarTree};
use starplex::topo::{
    link::vertex_link, naive::VtIndex, LocalStar, TopCells, VertexAdjacency, VertexStar,
};

#[derive(Clone, Debug)]
struct Spec {
    ambient: usize,
    points: Vec<Vec<i32>>,
    cells: Vec<(u8, Vec<u32>)>,
}

const KINDS: [CellKind; 10] = [
    CellKind::Simplex(0),
    CellKind::Simplex(1),
    CellKind::Simplex(2),
    CellKind::Simplex(3),
    CellKind::Simplex(4),
    CellKind::Quad,
    CellKind::Pyramid,
    CellKind::Prism,
    CellKind::Hex,
    CellKind::Simplex(2),
];

fn spec_strategy() -> impl Strategy<Value = Spec> {
    (1usize..=4, 1usize..40).prop_flat_map(|(ambient, nv)| {
        let pts = proptest::collection::vec(proptest::collection::vec(0i32..4, ambient), nv);
        let cells = proptest::collection::vec(
            (0u8..10, proptest::collection::vec(0u32..nv as u32, 8)),
            0..30,
        );
        (Just(ambient), pts, cells).prop_map(|(ambient, points, cells)| Spec {
            ambient,
            points,
            cells,
        })
    })
}

fn make(spec: &Spec) -> IndexedComplex {
    let mut b = ComplexBuilder::new(spec.ambient).unwrap();
    for p in &spec.points {
        let q: Vec<f64> = p.iter().map(|&x| x as f64 * 0.25).collect();
        b.push_vertex(&q).unwrap();
    }
    for (k, vs) in &spec.cells {
        let kind = KINDS[*k as usize];
        let mut distinct: Vec<u32> = Vec::new();
        for &v in vs {
            if !distinct.contains(&v) {
                distinct.push(v);
            }
        }
        if distinct.len() >= kind.n_vertices() {
            b.push_cell(kind, &distinct[..kind.n_vertices()]).unwrap();
        }
    }
    b.build(&BuildOptions {
        drop_face_cells: true,
        drop_duplicates: true,
        ..Default::default()
    })
    .unwrap()
    .0
}

// ---------------- brute-force models ----------------

fn bf_vt(k: &IndexedComplex, v: u32) -> Vec<u32> {
    k.cells()
        .filter(|c| c.vertices.contains(&v))
        .map(|c| c.id.0)
        .collect()
}

fn cell_edges(kind: CellKind, vs: &[u32]) -> Vec<(u32, u32)> {
    let mut out = Vec::new();
    kind.for_each_face(1, |l| out.push((vs[l[0] as usize], vs[l[1] as usize])));
    out
}

fn bf_vv(k: &IndexedComplex, v: u32) -> Vec<u32> {
    let mut s = BTreeSet::new();
    for c in k.cells() {
        for (a, b) in cell_edges(c.kind, c.vertices) {
            if a == v {
                s.insert(b);
            }
            if b == v {
                s.insert(a);
            }
        }
    }
    s.into_iter().collect()
}

fn bf_faces(k: &IndexedComplex, p: usize) -> BTreeMap<Vec<u32>, u32> {
    let mut m: BTreeMap<Vec<u32>, BTreeSet<u32>> = BTreeMap::new();
    for c in k.cells() {
        c.kind.for_each_face(p, |l| {
            let mut f: Vec<u32> = l.iter().map(|&i| c.vertices[i as usize]).collect();
            f.sort();
            m.entry(f).or_default().insert(c.id.0);
        });
    }
    m.into_iter().map(|(f, s)| (f, s.len() as u32)).collect()
}

fn facets(kind: CellKind, vs: &[u32]) -> Vec<Vec<u32>> {
    let mut out = Vec::new();
    if kind.dim() == 0 {
        return out;
    }
    kind.for_each_face(kind.dim() - 1, |l| {
        let mut f: Vec<u32> = l.iter().map(|&i| vs[i as usize]).collect();
        f.sort();
        out.push(f);
    });
    out
}

fn bf_adjacency(k: &IndexedComplex) -> Vec<Vec<u32>> {
    let cells: Vec<_> = k.cells().collect();
    cells
        .iter()
        .map(|a| {
            let fa = facets(a.kind, a.vertices);
            cells
                .iter()
                .filter(|b| b.id != a.id && b.kind.dim() == a.kind.dim() && a.kind.dim() >= 1)
                .filter(|b| facets(b.kind, b.vertices).iter().any(|f| fa.contains(f)))
                .map(|b| b.id.0)
                .collect()
        })
        .collect()
}

fn bf_components(k: &IndexedComplex) -> u64 {
    // plain BFS over the vertex graph
    let n = k.n_vertices();
    let mut adj = vec![Vec::new(); n];
    for c in k.cells() {
        for &a in c.vertices {
            for &b in c.vertices {
                adj[a as usize].push(b as usize);
            }
        }
    }
    let mut seen = vec![false; n];
    let mut comps = 0;
    for s in 0..n {
        if seen[s] {
            continue;
        }
        comps += 1;
        let mut st = vec![s];
        seen[s] = true;
        while let Some(x) = st.pop() {
            for &y in &adj[x] {
                if !seen[y] {
                    seen[y] = true;
                    st.push(y);
                }
            }
        }
    }
    comps
}

/// Boundary facets and facets in > 2 cells, among the top cells of the top dimension.
fn bf_boundary(k: &IndexedComplex) -> (Vec<Vec<u32>>, Vec<Vec<u32>>) {
    let d = k.dim().unwrap_or(0);
    let mut m: BTreeMap<Vec<u32>, usize> = BTreeMap::new();
    if d == 0 {
        return (vec![], vec![]);
    }
    for c in k.cells().filter(|c| c.kind.dim() == d) {
        for f in facets(c.kind, c.vertices) {
            *m.entry(f).or_default() += 1;
        }
    }
    (
        m.iter()
            .filter(|x| *x.1 == 1)
            .map(|x| x.0.clone())
            .collect(),
        m.iter().filter(|x| *x.1 > 2).map(|x| x.0.clone()).collect(),
    )
}

/// Non-manifold vertices of a complex of dimension <= 2 by the definition: the link of v
/// (edges w = link vertices, one link edge per 2-cell joining its two neighbours of v) must be
/// a single path or cycle (d = 2), or at most 2 points (d = 1).
fn bf_nm_vertices_low(k: &IndexedComplex) -> Vec<u32> {
    let d = k.dim().unwrap_or(0);
    let mut out = Vec::new();
    for v in 0..k.n_vertices() as u32 {
        let star: Vec<_> = k.cells().filter(|c| c.vertices.contains(&v)).collect();
        let bad = if star.is_empty() {
            d > 0
        } else if star.iter().any(|c| c.kind.dim() != d) {
            true
        } else if d == 1 {
            star.len() > 2
        } else {
            // link graph
            let mut deg: BTreeMap<u32, usize> = BTreeMap::new();
            let mut link_edges = Vec::new();
            for c in &star {
                let nb: Vec<u32> = cell_edges(c.kind, c.vertices)
                    .into_iter()
                    .filter_map(|(a, b)| {
                        if a == v {
                            Some(b)
                        } else if b == v {
                            Some(a)
                        } else {
                            None
                        }
                    })
                    .collect();
                assert_eq!(nb.len(), 2);
                *deg.entry(nb[0]).or_default() += 1;
                *deg.entry(nb[1]).or_default() += 1;
                link_edges.push((nb[0], nb[1]));
            }
            let maxdeg = deg.values().copied().max().unwrap_or(0);
            // connected?
            let verts: Vec<u32> = deg.keys().copied().collect();
            let mut seen = BTreeSet::new();
            let mut st = vec![verts[0]];
            seen.insert(verts[0]);
            while let Some(x) = st.pop() {
                for &(a, b) in &link_edges {
                    for (p, q) in [(a, b), (b, a)] {
                        if p == x && seen.insert(q) {
                            st.push(q);
                        }
                    }
                }
            }
            maxdeg > 2 || seen.len() != verts.len()
        };
        if bad {
            out.push(v);
        }
    }
    out
}

fn bf_nm_edges_2(k: &IndexedComplex) -> Vec<[u32; 2]> {
    let mut m: BTreeMap<(u32, u32), (usize, bool)> = BTreeMap::new();
    for c in k.cells() {
        for (a, b) in cell_edges(c.kind, c.vertices) {
            let e = m.entry((a.min(b), a.max(b))).or_default();
            if c.kind.dim() == 2 {
                e.0 += 1;
            } else {
                e.1 = true;
            }
        }
    }
    m.into_iter()
        .filter(|(_, (n, low))| *n > 2 || *low)
        .map(|((a, b), _)| [a, b])
        .collect()
}

// ---------------- the comparison ----------------

fn check(k: &IndexedComplex, kv: u32, threads: usize, split: SplitMode) {
    check_with(k, kv, threads, split, Decomposition::Spatial)
}

fn check_with(
    k: &IndexedComplex,
    kv: u32,
    threads: usize,
    split: SplitMode,
    decomposition: Decomposition,
) {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| {
        let t = StellarTree::build(
            k,
            &StellarOptions {
                kv: Some(kv),
                split,
                decomposition,
                ..Default::default()
            },
        )
        .unwrap();
        let nv = k.n_vertices();
        assert_eq!(t.n_vertices(), nv);
        assert_eq!(TopCells::n_top_cells(&t), k.n_cells());
        // permutations are inverse bijections; cells keep their vertices
        for v in 0..nv {
            assert_eq!(
                t.vertex_to_input()[t.vertex_from_input()[v].index()].index(),
                v
            );
        }
        for c in k.cells() {
            let (kind, vs) = t.input_cell(c.id);
            assert_eq!(kind, c.kind);
            assert_eq!(vs.iter().map(|v| v.0).collect::<Vec<_>>(), c.vertices);
        }
        // leaves partition the vertices; kV respected unless coincident points / one leaf
        let mut covered = 0u32;
        for l in 0..t.n_leaves() {
            let r = t.leaf_vertices(LeafId(l as u32));
            assert_eq!(r.start, covered);
            covered = r.end;
            // expanding the compressed list gives exactly the explicit list
            let got: Vec<u32> = SreIter::new(t.leaf_encoded_cells(LeafId(l as u32))).collect();
            let want: Vec<u32> = (0..k.n_cells() as u32)
                .filter(|&c| t.tree_cell(TreeCellId(c)).1.iter().any(|v| r.contains(v)))
                .collect();
            assert_eq!(got, want, "leaf {l}");
        }
        assert_eq!(covered as usize, nv);
        // relations
        let vt = t.vt_all();
        let vv = t.vv_all();
        let (mut cells, mut nbrs) = (Vec::new(), Vec::new());
        let all: Vec<VertexId> = (0..nv as u32).map(VertexId).collect();
        let vt_of = t.vt_of(&all).unwrap();
        let vv_of = t.vv_of(&all).unwrap();
        let links = t.links_of(&all).unwrap();
        let idx = VtIndex::new(k);
        for v in 0..nv as u32 {
            let want = bf_vt(k, v);
            assert_eq!(vt.row(v as usize), &want[..], "vt {v}");
            t.vertex_top_cells(VertexId(v), &mut cells);
            assert_eq!(cells.iter().map(|c| c.0).collect::<Vec<_>>(), want);
            assert_eq!(
                vt_of[v as usize].iter().map(|c| c.0).collect::<Vec<_>>(),
                want
            );
            let want = bf_vv(k, v);
            assert_eq!(vv.row(v as usize), &want[..], "vv {v}");
            t.vertex_neighbours(VertexId(v), &mut nbrs);
            assert_eq!(nbrs.iter().map(|c| c.0).collect::<Vec<_>>(), want);
            assert_eq!(
                vv_of[v as usize].iter().map(|c| c.0).collect::<Vec<_>>(),
                want
            );
            assert_eq!(
                links[v as usize],
                vertex_link(&idx, VertexId(v)),
                "link {v}"
            );
        }
        for p in 0..=k.dim().unwrap_or(0) {
            let want = bf_faces(k, p);
            let got = t.p_faces(p).unwrap();
            let mut gotm = BTreeMap::new();
            for i in 0..got.len() {
                assert!(gotm
                    .insert(got.faces.row(i).to_vec(), got.n_cofaces[i])
                    .is_none());
            }
            assert_eq!(gotm, want, "{p}-faces");
            assert_eq!(t.count_p_faces(p).unwrap() as usize, want.len());
        }
        let adj = t.top_adjacency();
        let want = bf_adjacency(k);
        for (c, w) in want.iter().enumerate() {
            assert_eq!(adj.row(c), &w[..], "adjacency of cell {c}");
        }
        // validation
        let r = t.validate();
        assert_eq!(r.n_connected_components, bf_components(k));
        let (bd, over) = bf_boundary(k);
        let conv = |f: &Vec<VertexId>| f.iter().map(|v| v.0).collect::<Vec<u32>>();
        assert_eq!(r.boundary_faces.iter().map(conv).collect::<Vec<_>>(), bd);
        assert_eq!(
            r.faces_in_more_than_two_cells
                .iter()
                .map(conv)
                .collect::<Vec<_>>(),
            over
        );
        let d = k.dim().unwrap_or(0);
        if (1..=2).contains(&d) {
            let nm: Vec<u32> = r.non_manifold_vertices.iter().map(|v| v.0).collect();
            assert_eq!(nm, bf_nm_vertices_low(k), "non-manifold vertices");
            if d == 2 {
                let ne: Vec<[u32; 2]> = r
                    .non_manifold_edges
                    .iter()
                    .map(|e| [e[0].0, e[1].0])
                    .collect();
                assert_eq!(ne, bf_nm_edges_2(k), "non-manifold edges");
            }
        }
        let pure = k.n_isolated_vertices() == 0 && k.cells().all(|c| c.kind.dim() == d);
        assert_eq!(r.pure, pure);
        let _ = CellId(0);
    });
}

#[test]
fn relations_equal_brute_force_on_random_complexes() {
    let mut runner = TestRunner::new(Config {
        cases: 64,
        rng_seed: RngSeed::Fixed(20261122),
        failure_persistence: None,
        ..Config::default()
    });
    runner
        .run(&spec_strategy(), |spec| {
            let k = make(&spec);
            for kv in [1u32, 10, 100, 0] {
                for threads in [1usize, 2] {
                    check(&k, kv, threads, SplitMode::Auto);
                }
            }
            check(&k, 2, 2, SplitMode::Kd);
            // by connectivity alone
            for kv in [1u32, 3, 10] {
                check_with(&k, kv, 2, SplitMode::Auto, Decomposition::Graph);
            }
            Ok(())
        })
        .unwrap();
}

/// Complexes whose cells are all simplices of one dimension (1 to 4), where the tree takes
/// its own paths (edges counted over each vertex's star, the triangles' IA*); more cells on
/// fewer vertices, so non-manifold edges and vertices are common.
#[test]
fn simplices_of_one_dimension_equal_brute_force() {
    let mut runner = TestRunner::new(Config {
        cases: 48,
        rng_seed: RngSeed::Fixed(20261204),
        failure_persistence: None,
        ..Config::default()
    });
    let strat = (1u8..=4, spec_strategy()).prop_map(|(kind, mut spec)| {
        for c in &mut spec.cells {
            c.0 = kind;
        }
        spec
    });
    runner
        .run(&strat, |spec| {
            let k = make(&spec);
            for kv in [1u32, 10, 0] {
                check(&k, kv, 2, SplitMode::Auto);
            }
            Ok(())
        })
        .unwrap();
}

#[test]
fn same_tree_for_any_thread_count() {
    let spec = {
        let mut points = Vec::new();
        let mut cells = Vec::new();
        let n = 60u32;
        for i in 0..n {
            for j in 0..n {
                points.push(vec![i as i32, j as i32, ((i * j) % 7) as i32]);
            }
        }
        for i in 0..n - 1 {
            for j in 0..n - 1 {
                let a = i * n + j;
                cells.push((2u8, vec![a, a + 1, a + n]));
                cells.push((2u8, vec![a + 1, a + n + 1, a + n]));
            }
        }
        Spec {
            ambient: 3,
            points,
            cells,
        }
    };
    let k = make(&spec);
    let build = |t: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(t)
            .build()
            .unwrap()
            .install(|| {
                StellarTree::build(
                    &k,
                    &StellarOptions {
                        kv: Some(7),
                        ..Default::default()
                    },
                )
                .unwrap()
            })
    };
    let (a, b) = (build(1), build(2));
    assert_eq!(a.vertex_to_input(), b.vertex_to_input());
    assert_eq!(a.cell_to_input(), b.cell_to_input());
    assert_eq!(a.nodes(), b.nodes());
    assert_eq!(a.stats(), b.stats());
    assert!(a.stats().mu < a.stats().chi);
}

#[test]
fn degenerate_inputs() {
    // all points equal, k_V = 1: stops at the depth limit with one leaf
    let mut b = ComplexBuilder::new(3).unwrap();
    for _ in 0..50 {
        b.push_vertex(&[1.0, 1.0, 1.0]).unwrap();
    }
    for i in 0..48u32 {
        b.push_cell(CellKind::Simplex(2), &[i, i + 1, i + 2])
            .unwrap();
    }
    let k = b.build(&BuildOptions::default()).unwrap().0;
    let t = StellarTree::build(
        &k,
        &StellarOptions {
            kv: Some(1),
            ..Default::default()
        },
    )
    .unwrap();
    assert_eq!(t.n_leaves(), 1);
    assert_eq!(t.vt_all().row(0), &[0]);
    // huge k_V: one leaf
    let t = StellarTree::build(
        &k,
        &StellarOptions {
            kv: Some(u32::MAX),
            ..Default::default()
        },
    )
    .unwrap();
    assert_eq!(t.n_leaves(), 1);
    // empty complex
    let k = ComplexBuilder::new(2)
        .unwrap()
        .build(&BuildOptions::default())
        .unwrap()
        .0;
    let t = StellarTree::build(&k, &StellarOptions::default()).unwrap();
    assert_eq!(t.n_vertices(), 0);
    assert_eq!(t.vt_all().n_rows(), 0);
    assert_eq!(t.validate().n_connected_components, 0);
    // high ambient dimension: kD split, regular refused above 8
    let mut b = ComplexBuilder::new(12).unwrap();
    for i in 0..30 {
        let p: Vec<f64> = (0..12).map(|a| ((i * 7 + a * 3) % 11) as f64).collect();
        b.push_vertex(&p).unwrap();
    }
    b.push_cell(CellKind::Simplex(5), &[0, 1, 2, 3, 4, 5])
        .unwrap();
    let k = b.build(&BuildOptions::default()).unwrap().0;
    let t = StellarTree::build(
        &k,
        &StellarOptions {
            kv: Some(2),
            ..Default::default()
        },
    )
    .unwrap();
    assert_eq!(t.split(), SplitMode::Kd);
    assert!(t.n_leaves() > 1);
    assert!(StellarTree::build(
        &k,
        &StellarOptions {
            split: SplitMode::Regular,
            ..Default::default()
        }
    )
    .is_err());
    // a 40-simplex: faces refused with an estimate, top queries fine
    let mut b = ComplexBuilder::new(2).unwrap();
    for i in 0..41 {
        b.push_vertex(&[i as f64, (i * i % 13) as f64]).unwrap();
    }
    b.push_cell(CellKind::Simplex(40), &(0..41).collect::<Vec<u32>>())
        .unwrap();
    let k = b.build(&BuildOptions::default()).unwrap().0;
    let t = StellarTree::build(&k, &StellarOptions::default()).unwrap();
    assert!(t.p_faces(20).is_err());
    assert_eq!(t.vt_all().row(3), &[0]);
    assert_eq!(t.p_faces(1).unwrap().len(), 820);
}

#[test]
fn cached_visit_equals_plain_visit() {
    let mut b = ComplexBuilder::new(2).unwrap();
    let n = 30u32;
    for i in 0..n {
        for j in 0..n {
            b.push_vertex(&[i as f64, j as f64]).unwrap();
        }
    }
    for i in 0..n - 1 {
        for j in 0..n - 1 {
            let a = i * n + j;
            b.push_cell(CellKind::Quad, &[a, a + 1, a + n + 1, a + n])
                .unwrap();
        }
    }
    let k = b.build(&BuildOptions::default()).unwrap().0;
    let t = StellarTree::build(
        &k,
        &StellarOptions {
            kv: Some(16),
            ..Default::default()
        },
    )
    .unwrap();
    let plain: Vec<Vec<usize>> =
        t.par_map_leaves(|l| l.owned_vertices().map(|v| l.local_star(v).len()).collect());
    for cap in [0usize, 1, 4] {
        // each leaf also looks at its successor through the cache
        let cached: Vec<(Vec<usize>, usize)> = t.par_map_leaves_cached(cap, |l, cache| {
            let next = (l.leaf().0 + 1) % t.n_leaves() as u32;
            let e = cache.get(&t, LeafId(next));
            (
                l.owned_vertices().map(|v| l.local_star(v).len()).collect(),
                e.cells().len(),
            )
        });
        for (i, (rows, next_cells)) in cached.iter().enumerate() {
            assert_eq!(rows, &plain[i]);
            let next = (i + 1) % t.n_leaves();
            assert_eq!(
                *next_cells,
                t.expand_leaf(LeafId(next as u32)).cells().len()
            );
        }
    }
    let mut cache = starplex::stellar::LeafCache::new(2);
    for l in [0u32, 1, 0, 1, 2, 0] {
        cache.get(&t, LeafId(l));
    }
    assert_eq!((cache.hits(), cache.misses()), (2, 4));
}
