//! IA* generated from the Stellar tree (global and local) against a brute-force model on
//! random complexes, and the spec's storage anchors.
use crate::common_data;

use std::collections::BTreeSet;

use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed, TestRunner};
use starplex::cell::CellKind;
use starplex::complex::{BuildOptions, ComplexBuilder, IndexedComplex};
use starplex::ids::{CellId, LeafId, VertexId};
use starplex::stellar::{StellarOptions, StellarTree};
use starplex::topo::{Adjacent, FacetAdjacency, Storage, VertexStar};

const KINDS: [CellKind; 9] = [
    CellKind::Simplex(1),
    CellKind::Simplex(2),
    CellKind::Simplex(2),
    CellKind::Simplex(3),
    CellKind::Simplex(4),
    CellKind::Quad,
    CellKind::Pyramid,
    CellKind::Prism,
    CellKind::Hex,
];

fn make(ambient: usize, points: &[Vec<i32>], cells: &[(u8, Vec<u32>)]) -> IndexedComplex {
    let mut b = ComplexBuilder::new(ambient).unwrap();
    for p in points {
        b.push_vertex(&p.iter().map(|&x| x as f64).collect::<Vec<_>>())
            .unwrap();
    }
    for (k, vs) in cells {
        let kind = KINDS[*k as usize % KINDS.len()];
        let mut d: Vec<u32> = Vec::new();
        for &v in vs {
            if !d.contains(&v) {
                d.push(v);
            }
        }
        if d.len() >= kind.n_vertices() {
            b.push_cell(kind, &d[..kind.n_vertices()]).unwrap();
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

fn facet_sets(kind: CellKind, vs: &[u32]) -> Vec<Vec<u32>> {
    let mut out = Vec::new();
    kind.for_each_oriented_facet(|l, _| {
        let mut f: Vec<u32> = l.iter().map(|&i| vs[i as usize]).collect();
        f.sort();
        out.push(f);
    });
    out
}

fn check(k: &IndexedComplex, kv: u32) {
    let t = StellarTree::build(
        k,
        &StellarOptions {
            kv: Some(kv),
            ..Default::default()
        },
    )
    .unwrap();
    let ia = t.iastar();
    brute_force(k, &ia);
    if kv == 1 {
        brute_force(k, &starplex::tds::iastar::IaStar::new(k).unwrap());
    }
    local_agrees(&t);
}

/// Any IA* ([`FacetAdjacency`]) against the definitions: slots, non-manifold facets,
/// representatives and stars.
fn brute_force<A: FacetAdjacency + VertexStar>(k: &IndexedComplex, ia: &A) {
    let cells: Vec<_> = k.cells().collect();
    let facets: Vec<Vec<Vec<u32>>> = cells
        .iter()
        .map(|c| {
            if c.kind.dim() >= 2 {
                facet_sets(c.kind, c.vertices)
            } else {
                vec![]
            }
        })
        .collect();
    for c in &cells {
        let i = c.id.index();
        assert_eq!(ia.n_facet_slots(c.id), facets[i].len());
        for (j, f) in facets[i].iter().enumerate() {
            let others: Vec<u32> = cells
                .iter()
                .filter(|o| o.id != c.id && o.kind.dim() == c.kind.dim())
                .filter(|o| facets[o.id.index()].contains(f))
                .map(|o| o.id.0)
                .collect();
            match (others.len(), ia.facet_adjacent(c.id, j)) {
                (0, Adjacent::None) => {}
                (1, Adjacent::Top(u)) => assert_eq!(u.0, others[0]),
                (n, Adjacent::NmFace(nf)) if n >= 2 => {
                    let mut all = others.clone();
                    all.push(c.id.0);
                    all.sort();
                    let ids = |v: Vec<CellId>| -> Vec<u32> { v.iter().map(|c| c.0).collect() };
                    assert_eq!(ids(ia.nm_face_cells(nf)), all);
                    let vs: Vec<u32> = ia.nm_face_vertices(nf).iter().map(|v| v.0).collect();
                    assert_eq!(&vs, f);
                }
                (n, a) => panic!("cell {i} facet {j}: {n} others, got {a:?}"),
            }
        }
    }
    // representatives: all top edges, one per k-cluster (its smallest id)
    for v in 0..k.n_vertices() as u32 {
        let star: Vec<_> = cells.iter().filter(|c| c.vertices.contains(&v)).collect();
        let want: Vec<u32> = star
            .iter()
            .filter(|c| c.kind.dim() == 1)
            .map(|c| c.id.0)
            .collect();
        // clusters by plain flooding
        let mut clusters: Vec<Vec<u32>> = Vec::new();
        let mut seen = BTreeSet::new();
        for s in star.iter().filter(|c| c.kind.dim() >= 2) {
            if seen.contains(&s.id.0) {
                continue;
            }
            let mut cluster = vec![s.id.0];
            seen.insert(s.id.0);
            let mut st = vec![s.id.index()];
            while let Some(a) = st.pop() {
                for o in star.iter().filter(|o| o.kind.dim() == cells[a].kind.dim()) {
                    if seen.contains(&o.id.0) {
                        continue;
                    }
                    let shared = facets[a]
                        .iter()
                        .any(|f| f.contains(&v) && facets[o.id.index()].contains(f));
                    if shared {
                        seen.insert(o.id.0);
                        cluster.push(o.id.0);
                        st.push(o.id.index());
                    }
                }
            }
            clusters.push(cluster);
        }
        // all top edges, and exactly one representative in each cluster
        let got: Vec<u32> = ia
            .vertex_references(VertexId(v))
            .iter()
            .map(|c| c.0)
            .collect();
        assert_eq!(got.len(), want.len() + clusters.len(), "reps of {v}");
        for e in &want {
            assert!(got.contains(e));
        }
        for cl in &clusters {
            assert_eq!(
                cl.iter().filter(|c| got.contains(c)).count(),
                1,
                "reps of {v}"
            );
        }
        let vt: Vec<CellId> = star.iter().map(|c| c.id).collect();
        let mut got = Vec::new();
        ia.vertex_top_cells(VertexId(v), &mut got);
        assert_eq!(got, vt, "IA* star of {v}");
    }
}

/// Local IA*: stars of the leaf's own vertices, and the slots it computed, agree with the
/// global IA*.
fn local_agrees(t: &StellarTree) {
    let ia = t.iastar();
    for l in 0..t.n_leaves() {
        let loc = t.local_iastar(LeafId(l as u32));
        for v in loc.vertices() {
            assert_eq!(loc.star(VertexId(v)), ia.star(VertexId(v)));
            assert_eq!(
                loc.vertex_references(VertexId(v)).len(),
                ia.vertex_references(VertexId(v)).len()
            );
        }
        for c in loc.cells() {
            for j in 0..loc.n_facet_slots(CellId(c)) {
                match (
                    loc.facet_adjacent(CellId(c), j),
                    ia.facet_adjacent(CellId(c), j),
                ) {
                    (Adjacent::NotComputed, _) => {}
                    (Adjacent::NmFace(a), Adjacent::NmFace(b)) => {
                        assert_eq!(loc.nm_face_cells(a), ia.nm_face_cells(b))
                    }
                    (a, b) => assert_eq!(a, b),
                }
            }
        }
    }
}

/// Runs `check(k, kv)` for k_V in {1, 5, 0} on seeded random complexes in 1 to 3 ambient
/// dimensions whose cells have kinds drawn by `kinds` (indices into [`KINDS`]).
fn on_random_complexes(
    kinds: BoxedStrategy<u8>,
    cases: u32,
    seed: u64,
    check: impl Fn(&IndexedComplex, u32),
) {
    let strat = (1usize..=3, 1usize..30).prop_flat_map(move |(amb, nv)| {
        (
            Just(amb),
            proptest::collection::vec(proptest::collection::vec(0i32..4, amb), nv),
            proptest::collection::vec(
                (kinds.clone(), proptest::collection::vec(0u32..nv as u32, 8)),
                0..25,
            ),
        )
    });
    let mut runner = TestRunner::new(Config {
        cases,
        rng_seed: RngSeed::Fixed(seed),
        failure_persistence: None,
        ..Config::default()
    });
    runner
        .run(&strat, |(amb, pts, cells)| {
            let k = make(amb, &pts, &cells);
            for kv in [1, 5, 0] {
                check(&k, kv);
            }
            Ok(())
        })
        .unwrap();
}

#[test]
fn iastar_equals_brute_force() {
    on_random_complexes((0u8..9).boxed(), 64, 7, check);
}

#[test]
fn storage_anchors_of_the_spec() {
    let pts: Vec<Vec<i32>> = (0..7).map(|i| vec![i, i * i % 5, i % 3]).collect();
    let anchor = |cells: &[(u8, Vec<u32>)], want: u64| {
        let k = make(3, &pts, cells);
        let t = StellarTree::build(&k, &StellarOptions::default()).unwrap();
        assert_eq!(t.iastar().refs(), want, "{cells:?}");
        let direct = starplex::tds::iastar::IaStar::new(&k).unwrap();
        assert_eq!(direct.refs(), want, "{cells:?}");
    };
    let (tri, tet, edge) = (1u8, 3u8, 0u8);
    anchor(&[(tet, vec![0, 1, 2, 3])], 12);
    anchor(&[(tri, vec![0, 1, 2]), (tri, vec![0, 3, 4])], 18);
    anchor(
        &[
            (tri, vec![0, 1, 2]),
            (tri, vec![0, 1, 3]),
            (tri, vec![0, 1, 4]),
        ],
        26,
    );
    anchor(&[(tet, vec![0, 1, 2, 3]), (tet, vec![0, 1, 4, 5])], 24);
    anchor(&[(tri, vec![0, 1, 2]), (edge, vec![2, 3])], 13);
}

/// The IA* generated from the tree and the IA* built directly (`tds::iastar`) are the same
/// structure: the same slot per facet (none, the same neighbour, or a non-manifold facet with
/// the same cells and vertices), the same non-manifold facets, the same representatives (all
/// top edges and the smallest input id of each cluster) and the same reference count.
fn same_as_direct(k: &IndexedComplex, kv: u32) {
    let t = StellarTree::build(
        k,
        &StellarOptions {
            kv: Some(kv),
            ..Default::default()
        },
    )
    .unwrap();
    same_iastar(
        k,
        &t.iastar(),
        &starplex::tds::iastar::IaStar::new(k).unwrap(),
    );
}

/// Two IA*s answer every IA* relation identically (non-manifold facets are compared by their
/// cells and vertices: their ids may be numbered differently).
fn same_iastar<A, B>(k: &IndexedComplex, a: &A, b: &B)
where
    A: FacetAdjacency + Storage,
    B: FacetAdjacency + Storage,
{
    for c in k.cells() {
        assert_eq!(
            a.n_facet_slots(c.id),
            b.n_facet_slots(c.id),
            "cell {}",
            c.id.0
        );
        for j in 0..a.n_facet_slots(c.id) {
            match (a.facet_adjacent(c.id, j), b.facet_adjacent(c.id, j)) {
                (Adjacent::NmFace(x), Adjacent::NmFace(y)) => {
                    assert_eq!(a.nm_face_cells(x), b.nm_face_cells(y));
                    assert_eq!(a.nm_face_vertices(x), b.nm_face_vertices(y));
                }
                (x, y) => assert_eq!(x, y, "cell {} facet {j}", c.id.0),
            }
        }
        assert_eq!(a.top_adjacent(c.id), b.top_adjacent(c.id));
    }
    assert_eq!(a.n_nm_faces(), b.n_nm_faces());
    for v in 0..k.n_vertices() as u32 {
        assert_eq!(
            a.vertex_references(VertexId(v)),
            b.vertex_references(VertexId(v)),
            "representatives of {v}"
        );
    }
    assert_eq!(a.refs(), b.refs(), "references");
}

#[test]
fn tree_iastar_is_the_direct_iastar() {
    let simplices = prop_oneof![Just(0u8), Just(1), Just(3), Just(4)].boxed();
    on_random_complexes(simplices, 96, 11, same_as_direct);
    // CP cells, alone and mixed with simplices
    on_random_complexes((0u8..9).boxed(), 96, 12, same_as_direct);
    on_random_complexes((5u8..9).boxed(), 64, 13, same_as_direct);
}

/// Triangles only: facets paired in a hashed table per leaf (as for tetrahedra); on so few
/// vertices non-manifold edges and vertices are common.
#[test]
fn tree_iastar_of_triangles_is_the_direct_iastar() {
    on_random_complexes(Just(1u8).boxed(), 128, 14, same_as_direct);
    on_random_complexes(Just(2u8).boxed(), 64, 15, check);
}

/// Tetrahedra only: facets paired in a hashed table per leaf, representatives by a flood
/// over the slots.
#[test]
fn tree_iastar_of_tetrahedra_is_the_direct_iastar() {
    on_random_complexes(Just(3u8).boxed(), 128, 16, same_as_direct);
    on_random_complexes(Just(3u8).boxed(), 64, 17, check);
}

#[test]
fn tree_iastar_is_the_direct_iastar_on_the_small_datasets() {
    let mut n = 0;
    for (name, path, _) in common_data::small_datasets() {
        let k = starplex::io::read(&path, &Default::default())
            .unwrap()
            .complex;
        if k.n_cells() > 40_000 {
            continue;
        }
        eprintln!("{name}");
        same_as_direct(&k, starplex::stellar::default_kv(&k));
        n += 1;
    }
    if n == 0 && !common_data::data_required() {
        eprintln!("SKIPPED: no small datasets found (see tests/suite/common_data.rs)");
        return;
    }
    assert!(n >= 7, "only {n} datasets");
}
