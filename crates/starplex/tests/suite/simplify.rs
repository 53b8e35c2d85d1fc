//! `algo::simplify` against brute force: the link condition (top-based test, definition,
//! the Hasse complex's test) decides the same, every accepted contraction keeps the Z/2 Betti
//! numbers (a GF(2) rank computed here), constructed refusals would have changed them; known
//! answers (sphere → tetrahedron boundary, tetrahedral ball, the bundled genus-3 elephant).
use std::collections::BTreeSet;
use std::path::Path;

use proptest::prelude::*;
use proptest::test_runner::{Config as ProptestConfig, RngSeed};
use starplex::algo::simplify::contract::{contract_homology, contract_homology_blocks};
use starplex::algo::simplify::link_condition::{
    link_condition, link_condition_full, LinkMode, LinkScratch,
};
use starplex::algo::simplify::{
    simplify, summary, Blocks, Mode, SimplifyError, SimplifyOptions, Target, TopSimplices,
};
use starplex::cell::CellKind;
use starplex::complex::{BuildOptions, ComplexBuilder, IndexedComplex};
use starplex::generate::kuhn_grid;
use starplex::hasse::Hasse;
use starplex::ids::VertexId;

/// Z/2 Betti numbers by brute force: every face enumerated, boundary ranks over GF(2).
fn betti_brute(tops: &[Vec<u32>]) -> Vec<usize> {
    let mut faces: Vec<BTreeSet<Vec<u32>>> = Vec::new();
    for t in tops {
        let mut t = t.clone();
        t.sort_unstable();
        for mask in 1u64..(1 << t.len()) {
            let f: Vec<u32> = (0..t.len())
                .filter(|i| mask >> i & 1 == 1)
                .map(|i| t[i])
                .collect();
            if faces.len() < f.len() {
                faces.resize(f.len(), BTreeSet::new());
            }
            faces[f.len() - 1].insert(f);
        }
    }
    let index: Vec<Vec<Vec<u32>>> = faces.iter().map(|s| s.iter().cloned().collect()).collect();
    // rank of the boundary map from dimension k to k-1
    let rank = |k: usize| -> usize {
        if k == 0 || k >= index.len() {
            return 0;
        }
        let lower = &index[k - 1];
        let words = lower.len().div_ceil(64);
        let mut rows: Vec<Vec<u64>> = index[k]
            .iter()
            .map(|f| {
                let mut r = vec![0u64; words];
                for skip in 0..f.len() {
                    let g: Vec<u32> = f
                        .iter()
                        .enumerate()
                        .filter(|(i, _)| *i != skip)
                        .map(|(_, &v)| v)
                        .collect();
                    let j = lower.binary_search(&g).unwrap();
                    r[j / 64] ^= 1 << (j % 64);
                }
                r
            })
            .collect();
        let mut rank = 0;
        for col in 0..lower.len() {
            let (w, b) = (col / 64, 1u64 << (col % 64));
            if let Some(p) = (rank..rows.len()).find(|&i| rows[i][w] & b != 0) {
                rows.swap(rank, p);
                let pivot = rows[rank].clone();
                for (i, r) in rows.iter_mut().enumerate() {
                    if i != rank && r[w] & b != 0 {
                        for (x, y) in r.iter_mut().zip(&pivot) {
                            *x ^= y;
                        }
                    }
                }
                rank += 1;
            }
        }
        rank
    };
    let mut b: Vec<usize> = (0..index.len())
        .map(|k| index[k].len() - rank(k) - rank(k + 1))
        .collect();
    while b.len() > 1 && b.last() == Some(&0) {
        b.pop();
    }
    b
}

fn hasse_of(tops: &[Vec<u32>]) -> Hasse {
    let mut h: Hasse = Hasse::new();
    for t in tops {
        let vs: Vec<VertexId> = t.iter().map(|&v| VertexId(v)).collect();
        h.insert(&vs).unwrap();
    }
    h
}

/// The cells that are no face of another (of two equal cells, the first).
fn maximal(cells: &[Vec<u32>]) -> Vec<Vec<u32>> {
    let dominated = |i: usize, c: &Vec<u32>| {
        cells
            .iter()
            .enumerate()
            .any(|(j, d)| j != i && c.iter().all(|v| d.contains(v)) && (c.len() < d.len() || j < i))
    };
    cells
        .iter()
        .enumerate()
        .filter(|&(i, c)| !dominated(i, c))
        .map(|(_, c)| c.clone())
        .collect()
}

/// Random maximal simplices on `n` vertices: dimensions up to `dim`, not pure, not manifold.
fn random_tops() -> impl Strategy<Value = (usize, Vec<Vec<u32>>)> {
    (4usize..=9, 1usize..=6).prop_flat_map(|(n, dim)| {
        let cell = proptest::collection::btree_set(0..n as u32, 2..=(dim + 1).min(n));
        (Just(n), proptest::collection::vec(cell, 1..=9)).prop_map(|(n, cells)| {
            let cells: Vec<Vec<u32>> = cells.into_iter().map(|c| c.into_iter().collect()).collect();
            (n, maximal(&cells))
        })
    })
}

fn edges(w: &TopSimplices) -> Vec<(u32, u32)> {
    let mut out = Vec::new();
    for a in 0..w.n_vertices() as u32 {
        if w.is_alive(a) {
            for b in w.neighbours(a) {
                if a < b {
                    out.push((a, b));
                }
            }
        }
    }
    out
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 300,
        rng_seed: RngSeed::Fixed(0x51_3f),
        failure_persistence: None,
        ..ProptestConfig::default()
    })]

    /// On 300 random complexes: the top-based test, the definition and the Hasse complex's
    /// test agree on every edge (and the two extended forms agree); every accepted
    /// contraction keeps the brute-force Z/2 Betti numbers; contracting greedily to the end
    /// keeps them too.
    #[test]
    fn link_condition_keeps_betti((n, tops) in random_tops()) {
        let w = TopSimplices::from_tops(n, &tops).unwrap();
        let h = hasse_of(&w.sorted_tops());
        let before = betti_brute(&w.sorted_tops());
        let mut scratch = LinkScratch::default();
        for (a, b) in edges(&w) {
            let top = link_condition(&w, a, b, LinkMode::Homology, &mut scratch);
            let full = link_condition_full(&w, a, b, LinkMode::Homology, 1 << 24).unwrap();
            prop_assert_eq!(top, full, "edge {}-{} of {:?}", a, b, tops);
            prop_assert_eq!(top, link_condition(&w, b, a, LinkMode::Homology, &mut scratch));
            let e = h.find(&[VertexId(a), VertexId(b)]).unwrap();
            let hasse = h.link_condition_violations(e).unwrap().is_empty();
            prop_assert_eq!(top, hasse, "edge {}-{} of {:?}", a, b, tops);
            let ext = link_condition(&w, a, b, LinkMode::Manifold, &mut scratch);
            let ext_full = link_condition_full(&w, a, b, LinkMode::Manifold, 1 << 24).unwrap();
            prop_assert_eq!(ext, ext_full, "extended, edge {}-{} of {:?}", a, b, tops);
            prop_assert!(!ext || top, "the extended condition implies the plain one");
            if top {
                for (s, t) in [(a, b), (b, a)] {
                    let mut c = w.clone();
                    prop_assert!(c.can_contract(s, t).is_ok());
                    prop_assert!(c.contract(s, t));
                    prop_assert_eq!(&betti_brute(&c.sorted_tops()), &before, "contracting {}-{} of {:?}", s, t, tops);
                    // the result is a complex given by maximal simplices
                    let st = c.sorted_tops();
                    prop_assert!(TopSimplices::from_tops(n, &st).is_ok(), "{:?}", st);
                }
            } else {
                prop_assert!(w.can_contract(a, b).is_err());
            }
        }
        let mut c = w.clone();
        contract_homology(&mut c, &Target::default(), LinkMode::Homology, None);
        prop_assert_eq!(betti_brute(&c.sorted_tops()), before);
        // no edge left passes
        for (a, b) in edges(&c) {
            prop_assert!(c.can_contract(a, b).is_err());
        }
    }
}

/// Random pure complexes of simplices of `k` vertices on `n` vertices (boundaries, non-manifold
/// faces and vertices, several components): with `k` 3 (triangles) or 4 (tetrahedra), the stars
/// the specialised link tests handle.
fn random_simplices(k: usize) -> impl Strategy<Value = (usize, Vec<Vec<u32>>)> {
    (k + 1..=8).prop_flat_map(move |n| {
        let tri = proptest::collection::btree_set(0..n as u32, k..=k);
        (Just(n), proptest::collection::btree_set(tri, 1..=14)).prop_map(|(n, tris)| {
            (
                n,
                tris.into_iter().map(|t| t.into_iter().collect()).collect(),
            )
        })
    })
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 300,
        rng_seed: RngSeed::Fixed(0x7a1),
        failure_persistence: None,
        ..ProptestConfig::default()
    })]

    /// On 300 random pure triangle complexes, where the top-based test takes its triangle-star
    /// path: it decides as the definition on every edge, in both modes and both directions,
    /// also after contractions (the in-place edit of the tops); contracting greedily with the
    /// extended condition keeps the brute-force Betti numbers.
    #[test]
    fn triangle_link_condition_is_the_definition((n, tops) in random_simplices(3)) {
        fast_test_is_the_definition(n, &tops)?;
    }

    /// The same on 300 random pure tetrahedral complexes (boundaries, non-manifold edges and
    /// vertices), where the test takes its tetrahedral-star path until a contraction leaves a
    /// triangle as a top.
    #[test]
    fn tetrahedral_link_condition_is_the_definition((n, tops) in random_simplices(4)) {
        fast_test_is_the_definition(n, &tops)?;
    }
}

/// A slab one cube thick (a 3x3x1 Freudenthal grid): its inner edges join its two faces, so
/// in the complex closed by a cone over the boundary the two links of such an edge share the
/// apex ω and nothing else outside `Lk(ab)`, a case the random complexes rarely build.
#[test]
fn slab_link_condition_is_the_definition() {
    let slab = kuhn_grid(&[3, 3, 1]).unwrap();
    let tops: Vec<Vec<u32>> = slab.cells().map(|c| c.vertices.to_vec()).collect();
    fast_test_is_the_definition(slab.n_vertices(), &tops).unwrap();
}

/// The body of the tests above.
fn fast_test_is_the_definition(n: usize, tops: &[Vec<u32>]) -> Result<(), TestCaseError> {
    let mut w = TopSimplices::from_tops(n, tops).unwrap();
    let before = betti_brute(&w.sorted_tops());
    let mut scratch = LinkScratch::default();
    loop {
        let mut next = None;
        for (a, b) in edges(&w) {
            for mode in [LinkMode::Homology, LinkMode::Manifold] {
                let full = link_condition_full(&w, a, b, mode, 1 << 24).unwrap();
                for (s, t) in [(a, b), (b, a)] {
                    let fast = link_condition(&w, s, t, mode, &mut scratch);
                    prop_assert_eq!(
                        fast,
                        full,
                        "{:?} {}-{} of {:?}",
                        mode,
                        s,
                        t,
                        w.sorted_tops()
                    );
                }
                if full && mode == LinkMode::Manifold && next.is_none() {
                    next = Some((a, b));
                }
            }
        }
        let Some((a, b)) = next else { break };
        prop_assert!(w.contract(a, b));
        prop_assert_eq!(&betti_brute(&w.sorted_tops()), &before, "after {}-{}", a, b);
        let st = w.sorted_tops();
        prop_assert!(TopSimplices::from_tops(n, &st).is_ok(), "{:?}", st);
    }
    Ok(())
}

/// Random complexes whose cells are local in the vertex ids (each cell within a window of 6
/// consecutive ids), so that blocks of consecutive ids have inner vertices; with 2 to 4 cuts.
fn random_local_tops() -> impl Strategy<Value = (usize, Vec<Vec<u32>>, Vec<usize>)> {
    (12usize..=40, 1usize..=4).prop_flat_map(|(n, dim)| {
        let cell = (
            0..n as u32 - 1,
            proptest::collection::btree_set(0u32..6, 2..=dim + 1),
        );
        let cuts = proptest::collection::btree_set(1..n, 1..=3);
        (Just(n), proptest::collection::vec(cell, 1..=45), cuts).prop_map(|(n, cells, cuts)| {
            let cells: Vec<Vec<u32>> = cells
                .into_iter()
                .map(|(s, off)| {
                    let c: BTreeSet<u32> =
                        off.into_iter().map(|o| (s + o).min(n as u32 - 1)).collect();
                    c.into_iter().collect()
                })
                .filter(|c: &Vec<u32>| c.len() >= 2)
                .collect();
            let mut tops = maximal(&cells);
            if tops.is_empty() {
                tops.push(vec![0, 1]);
            }
            let mut cuts: Vec<usize> = std::iter::once(0).chain(cuts).collect();
            cuts.push(n);
            (n, tops, cuts)
        })
    })
}

/// The vertex rows of `w` are those of the structure rebuilt from its tops.
fn rows_are_consistent(w: &TopSimplices) -> bool {
    (0..w.n_vertices() as u32).all(|v| {
        let mut row: Vec<Vec<u32>> = w
            .star(v)
            .iter()
            .map(|&t| {
                let mut t = w.top(t).to_vec();
                t.sort_unstable();
                t
            })
            .collect();
        row.sort();
        let want: Vec<Vec<u32>> = w
            .sorted_tops()
            .into_iter()
            .filter(|t| t.contains(&v))
            .collect();
        row == want && (w.is_alive(v) || row.is_empty())
    })
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 300,
        rng_seed: RngSeed::Fixed(0xb10c),
        failure_persistence: None,
        ..ProptestConfig::default()
    })]

    /// Contraction over blocks (parts cut out, contracted in parallel, pasted back) on 300
    /// random complexes of dimension 1–4 cut in 2–4 blocks: the Betti numbers are kept, no edge
    /// left passes the link condition, the vertex rows match the tops, the result is the same
    /// on 1 and 2 threads, and a vertex target is met exactly.
    #[test]
    fn blocks_keep_betti_and_do_not_depend_on_threads((n, tops, cuts) in random_local_tops()) {
        let w = TopSimplices::from_tops(n, &tops).unwrap();
        let before = betti_brute(&w.sorted_tops());
        let order: Vec<u32> = (0..n as u32).collect();
        let blocks = Blocks::from_order(&order, &cuts).unwrap();
        for mode in [LinkMode::Homology, LinkMode::Manifold] {
            let run = |threads: usize, target: Target| {
                let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
                let mut c = w.clone();
                let s = pool.install(|| contract_homology_blocks(&mut c, &target, mode, None, &blocks));
                (c, s)
            };
            let (one, s1) = run(1, Target::default());
            let (two, s2) = run(2, Target::default());
            prop_assert_eq!(one.sorted_tops(), two.sorted_tops());
            prop_assert_eq!(s1, s2);
            prop_assert_eq!(&betti_brute(&one.sorted_tops()), &before, "{:?} {:?} cuts {:?}", mode, tops, cuts);
            prop_assert!(rows_are_consistent(&one), "{:?} {:?} cuts {:?}", mode, tops, cuts);
            if mode == LinkMode::Homology {
                for (a, b) in edges(&one) {
                    prop_assert!(one.can_contract(a, b).is_err(), "{}-{} still contracts", a, b);
                }
            }
            // a vertex target half way: met exactly (each contraction removes one vertex)
            let goal = (w.n_alive_vertices() + one.n_alive_vertices()) / 2;
            let t = Target { vertices: Some(goal), ..Default::default() };
            let (half, _) = run(2, t);
            prop_assert_eq!(half.n_alive_vertices(), goal);
            prop_assert_eq!(half.sorted_tops(), run(1, t).0.sorted_tops());
            prop_assert_eq!(&betti_brute(&half.sorted_tops()), &before);
        }
    }
}

/// A 160,801-vertex grid (several blocks of a Stellar tree): the same result on 1 and 2
/// threads, contractible to one vertex, a disc of few triangles with the manifold condition,
/// and a face target met exactly.
#[test]
fn parallel_rounds_on_a_large_grid() {
    let k = kuhn_grid(&[400, 400]).unwrap();
    assert!(starplex::algo::simplify::homology_blocks(&k).len() > 1);
    let run = |threads: usize, opts: &SimplifyOptions| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| simplify(&k, opts).unwrap())
    };
    let homology = SimplifyOptions {
        mode: Some(Mode::Homology),
        ..Default::default()
    };
    let (p1, r1) = run(1, &homology);
    let (p2, r2) = run(2, &homology);
    assert_eq!((p1.n_vertices(), p1.n_cells()), (1, 0));
    assert_eq!((p2.n_vertices(), r2.n_contractions), (1, r1.n_contractions));
    let manifold = SimplifyOptions {
        keep_manifold: true,
        ..homology.clone()
    };
    let (d1, _) = run(1, &manifold);
    let (d2, _) = run(2, &manifold);
    assert_eq!(
        d1.cells().map(|c| c.vertices.to_vec()).collect::<Vec<_>>(),
        d2.cells().map(|c| c.vertices.to_vec()).collect::<Vec<_>>()
    );
    assert_eq!(summary(&d1).betti, Some(vec![1, 0, 0]));
    assert!(d1.n_cells() < 10, "{} triangles left", d1.n_cells());
    let faces = SimplifyOptions {
        target: Target {
            faces: Some(20_000),
            ..Default::default()
        },
        ..manifold
    };
    let (f1, _) = run(2, &faces);
    assert!(
        f1.n_cells() <= 20_000 && f1.n_cells() >= 19_990,
        "{} triangles",
        f1.n_cells()
    );
    assert_eq!(summary(&f1).betti, Some(vec![1, 0, 0]));
}

/// Refused contractions that would have changed the homology, built to do so.
#[test]
fn refused_contractions_would_change_betti() {
    type Case = (usize, Vec<Vec<u32>>, (u32, u32));
    let cases: Vec<Case> = vec![
        // a hollow triangle (circle): contracting fills the hole
        (3, vec![vec![0, 1], vec![1, 2], vec![0, 2]], (0, 1)),
        // a hollow tetrahedron (2-sphere): contracting an edge kills H2
        (
            4,
            vec![vec![0, 1, 2], vec![0, 1, 3], vec![0, 2, 3], vec![1, 2, 3]],
            (0, 1),
        ),
        // a filled triangle with a second path of length 2 between 0 and 1 (a circle)
        (4, vec![vec![0, 1, 2], vec![0, 3], vec![1, 3]], (0, 1)),
        // the boundary of a 4-simplex (a 3-sphere)
        (
            5,
            (0..5u32)
                .map(|s| (0..5u32).filter(|&v| v != s).collect())
                .collect(),
            (2, 3),
        ),
        // a 6-dimensional sphere: the boundary of a 7-simplex
        (
            8,
            (0..8u32)
                .map(|s| (0..8u32).filter(|&v| v != s).collect())
                .collect(),
            (0, 7),
        ),
        // two triangles glued at two vertices (a circle through them)
        (4, vec![vec![0, 1, 2], vec![0, 1, 3]], (2, 3)),
    ];
    for (n, tops, (a, b)) in cases {
        let w = TopSimplices::from_tops(n, &tops).unwrap();
        let before = betti_brute(&w.sorted_tops());
        let is_edge = w.neighbours(a).contains(&b);
        if !is_edge {
            assert!(w.can_contract(a, b).is_err());
            continue;
        }
        assert!(
            w.can_contract(a, b).is_err(),
            "{tops:?}: {a}-{b} should be refused"
        );
        let mut c = w.clone();
        assert!(c.contract(a, b));
        assert_ne!(betti_brute(&c.sorted_tops()), before, "{tops:?}: {a}-{b}");
    }
}

fn complex_of(coords: &[[f64; 3]], tris: &[[u32; 3]]) -> IndexedComplex {
    let mut b = ComplexBuilder::new(3).unwrap();
    for p in coords {
        b.push_vertex(p).unwrap();
    }
    for t in tris {
        b.push_cell(CellKind::Simplex(2), t).unwrap();
    }
    b.build(&BuildOptions::default()).unwrap().0
}

/// A closed genus-0 surface (the boundary of a 4x4x4 cube of tetrahedra, 96 triangles)
/// contracts to the boundary of a tetrahedron.
#[test]
fn sphere_contracts_to_tetrahedron_boundary() {
    let ball = kuhn_grid(&[4, 4, 4]).unwrap();
    let (sphere, _) = starplex::algo::surface::boundary(&ball).unwrap();
    assert_eq!(summary(&sphere).betti, Some(vec![1, 0, 1]));
    let opts = SimplifyOptions {
        mode: Some(Mode::Homology),
        ..Default::default()
    };
    let (k, r) = simplify(&sphere, &opts).unwrap();
    assert_eq!((k.n_vertices(), k.n_cells()), (4, 4));
    assert_eq!(r.n_contractions as usize, sphere.n_vertices() - 4);
    let s = summary(&k);
    assert_eq!(s.betti, Some(vec![1, 0, 1]));
    assert_eq!(s.f_vector, Some(vec![4, 6, 4]));
    // deterministic
    let (k2, _) = simplify(&sphere, &opts).unwrap();
    assert_eq!(
        format!(
            "{:?}",
            k2.cells().map(|c| c.vertices.to_vec()).collect::<Vec<_>>()
        ),
        format!(
            "{:?}",
            k.cells().map(|c| c.vertices.to_vec()).collect::<Vec<_>>()
        )
    );
}

/// A tetrahedral ball (384 tets of a 4x4x4 Freudenthal grid) contracts to a few tetrahedra
/// with the Betti numbers of a point.
#[test]
fn tetrahedral_ball_contracts_to_a_few_tets() {
    let ball = kuhn_grid(&[4, 4, 4]).unwrap();
    let opts = SimplifyOptions {
        mode: Some(Mode::Homology),
        ..Default::default()
    };
    // plain link condition: lower-dimensional tops appear, the ball shrinks to a point
    let (k, _) = simplify(&ball, &opts).unwrap();
    let s = summary(&k);
    println!(
        "tetrahedral ball: 384 tets -> {} top cells, f-vector {:?}",
        k.n_cells(),
        s.f_vector
    );
    assert_eq!(s.betti, Some(vec![1]));
    assert_eq!((k.n_vertices(), k.n_cells()), (1, 0));
    // the extended link condition keeps it a 3-ball: a few tetrahedra
    let opts = SimplifyOptions {
        keep_manifold: true,
        ..opts
    };
    let (k, _) = simplify(&ball, &opts).unwrap();
    let s = summary(&k);
    println!(
        "tetrahedral ball, manifold kept: 384 tets -> {} tets, f-vector {:?}",
        k.n_cells(),
        s.f_vector
    );
    assert_eq!(s.betti, Some(vec![1, 0, 0, 0]));
    assert!(k.n_cells() <= 4, "{} cells left", k.n_cells());
    assert!(k.cells().all(|c| c.kind == CellKind::Simplex(3)));
    // QEM on the same ball keeps it a manifold ball with a manifold boundary
    let opts = SimplifyOptions {
        mode: Some(Mode::Qem),
        target: Target {
            ratio: Some(0.2),
            ..Default::default()
        },
        ..Default::default()
    };
    let (q, _) = simplify(&ball, &opts).unwrap();
    let s = summary(&q);
    assert!(q.n_cells() <= 77, "{}", q.n_cells());
    assert_eq!(s.betti, Some(vec![1, 0, 0, 0]));
    assert_eq!((s.non_manifold_vertices, s.non_manifold_edges), (0, 0));
    let (surf, _) = starplex::algo::surface::boundary(&q).unwrap();
    let b = summary(&surf);
    assert_eq!(b.betti, Some(vec![1, 0, 1]));
    assert_eq!((b.non_manifold_vertices, b.non_manifold_edges), (0, 0));
}

fn elephant() -> IndexedComplex {
    let p = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/elephant.off");
    starplex::io::read(&p, &Default::default()).unwrap().complex
}

/// The bundled genus-3 elephant keeps Euler characteristic -4 (and its Betti numbers, and no
/// non-manifold simplex) at every target, in both modes.
#[test]
fn elephant_keeps_genus_at_every_target() {
    let k = elephant();
    let s0 = summary(&k);
    assert_eq!(s0.euler_characteristic, Some(-4));
    for (mode, ratio) in [
        (Mode::Qem, 0.5),
        (Mode::Qem, 0.1),
        (Mode::Qem, 0.01),
        (Mode::Qem, 0.0),
        (Mode::Homology, 0.3),
        (Mode::Homology, 0.0),
    ] {
        let opts = SimplifyOptions {
            mode: Some(mode),
            target: Target {
                ratio: Some(ratio),
                ..Default::default()
            },
            ..Default::default()
        };
        let (out, r) = simplify(&k, &opts).unwrap();
        let s = summary(&out);
        println!(
            "elephant {mode:?} ratio {ratio}: {} -> {} triangles, {} contractions",
            k.n_cells(),
            out.n_cells(),
            r.n_contractions
        );
        assert_eq!(s.euler_characteristic, Some(-4), "{mode:?} {ratio}");
        assert_eq!(s.betti, s0.betti, "{mode:?} {ratio}");
        assert_eq!(
            (
                s.non_manifold_vertices,
                s.non_manifold_edges,
                s.boundary_faces
            ),
            (0, 0, 0)
        );
        if ratio > 0.0 {
            assert!(out.n_cells() <= (ratio * k.n_cells() as f64).round() as usize + 1);
        }
    }
}

/// QEM on a surface with boundary: the boundary loop survives (locked or not), a flat square
/// stays flat, and locking keeps every boundary vertex in place.
#[test]
fn qem_keeps_boundary_loops() {
    let sq = kuhn_grid(&[8, 8]).unwrap();
    // lift to 3D with a bump so that the quadrics have something to keep
    let mut b = ComplexBuilder::new(3).unwrap();
    for v in 0..sq.n_vertices() as u32 {
        let p = sq.point(VertexId(v));
        let z = ((p[0] - 4.0).powi(2) + (p[1] - 4.0).powi(2)) * 0.05;
        b.push_vertex(&[p[0], p[1], z]).unwrap();
    }
    for c in sq.cells() {
        b.push_cell(c.kind, c.vertices).unwrap();
    }
    let k = b.build(&BuildOptions::default()).unwrap().0;
    for lock in [false, true] {
        let opts = SimplifyOptions {
            target: Target {
                faces: Some(10),
                ..Default::default()
            },
            lock_boundary: lock,
            ..Default::default()
        };
        let (out, r) = simplify(&k, &opts).unwrap();
        assert_eq!(r.mode, Mode::Qem);
        let s = summary(&out);
        assert_eq!(s.betti, Some(vec![1, 0, 0]));
        assert_eq!((s.non_manifold_vertices, s.non_manifold_edges), (0, 0));
        let (loop_, _) = starplex::algo::surface::boundary(&out).unwrap();
        assert_eq!(summary(&loop_).betti, Some(vec![1, 1]), "one boundary loop");
        if lock {
            assert_eq!(s.boundary_faces, 32, "no boundary vertex removed");
        }
    }
}

/// The top-based test decides like the definition on the elephant's edges (extended form).
#[test]
fn top_test_equals_definition_on_the_elephant() {
    let w = TopSimplices::from_complex(&elephant()).unwrap();
    let mut scratch = LinkScratch::default();
    let mut refused = 0;
    for (a, b) in edges(&w) {
        for mode in [LinkMode::Homology, LinkMode::Manifold] {
            let x = link_condition(&w, a, b, mode, &mut scratch);
            assert_eq!(x, link_condition_full(&w, a, b, mode, 1 << 20).unwrap());
            refused += usize::from(!x);
        }
    }
    println!("elephant: {refused} refusals");
}

#[test]
fn bad_targets_and_inputs_are_errors() {
    let k = elephant();
    let bad = |t: Target, mode| {
        let opts = SimplifyOptions {
            mode,
            target: t,
            ..Default::default()
        };
        simplify(&k, &opts).unwrap_err()
    };
    assert!(matches!(
        bad(
            Target {
                faces: Some(1 << 30),
                ..Default::default()
            },
            None
        ),
        SimplifyError::BadTarget(_)
    ));
    assert!(matches!(
        bad(
            Target {
                vertices: Some(1 << 30),
                ..Default::default()
            },
            None
        ),
        SimplifyError::BadTarget(_)
    ));
    assert!(matches!(
        bad(
            Target {
                ratio: Some(-0.5),
                ..Default::default()
            },
            None
        ),
        SimplifyError::BadTarget(_)
    ));
    assert!(matches!(
        bad(
            Target {
                ratio: Some(1.5),
                ..Default::default()
            },
            None
        ),
        SimplifyError::BadTarget(_)
    ));
    assert!(matches!(
        bad(
            Target {
                max_error: Some(-1.0),
                ..Default::default()
            },
            None
        ),
        SimplifyError::BadTarget(_)
    ));
    assert!(matches!(
        bad(
            Target {
                max_error: Some(1.0),
                ..Default::default()
            },
            Some(Mode::Homology)
        ),
        SimplifyError::BadTarget(_)
    ));
    // a quad
    let mut b = ComplexBuilder::new(2).unwrap();
    for p in [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]] {
        b.push_vertex(&p).unwrap();
    }
    b.push_cell(CellKind::Quad, &[0, 1, 2, 3]).unwrap();
    let q = b.build(&BuildOptions::default()).unwrap().0;
    let e = simplify(&q, &Default::default()).unwrap_err();
    assert!(matches!(e, SimplifyError::NotSimplicial { .. }));
    assert!(e.to_string().contains("--triangulate"));
    // empty
    let e = ComplexBuilder::new(3)
        .unwrap()
        .build(&BuildOptions::default())
        .unwrap()
        .0;
    assert_eq!(
        simplify(&e, &Default::default()).unwrap_err(),
        SimplifyError::Empty
    );
    // QEM on a non-mesh
    let edges_only = complex_of(&[[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], &[[0, 1, 2]]);
    let mut b = ComplexBuilder::new(3).unwrap();
    for v in 0..4u32 {
        b.push_vertex(&[v as f64, 0.0, 0.0]).unwrap();
    }
    b.push_cell(CellKind::Simplex(1), &[0, 1]).unwrap();
    b.push_cell(CellKind::Simplex(1), &[1, 2]).unwrap();
    let path = b.build(&BuildOptions::default()).unwrap().0;
    let opts = SimplifyOptions {
        mode: Some(Mode::Qem),
        ..Default::default()
    };
    assert_eq!(simplify(&path, &opts).unwrap_err(), SimplifyError::NotAMesh);
    assert!(simplify(&edges_only, &opts).is_ok());
}
