//! One answer: `starplex validate` (the Stellar tree's leaf-parallel validation) and
//! `algo::validate` over the query traits agree on named fixtures, on 200 random non-pure,
//! non-manifold complexes (simplices of dimension 0-5 and CP cells) and on every small dataset.
//! The manifold lists also equal `algo::manifold::singularities` under the global convention,
//! and the local convention is checked against a brute-force reading of its definition.
use crate::common_data;

use proptest::prelude::*;
use starplex::algo::manifold::{singularities, sphere_or_ball, Convention, Manifoldness};
use starplex::algo::validate::{check, errors, is_valid, validate, ValidationReport};
use starplex::cell::CellKind;
use starplex::complex::{BuildOptions, ComplexBuilder, IndexedComplex};
use starplex::ids::VertexId;
use starplex::stellar::{StellarOptions, StellarTree};
use starplex::tds::iastar::IaStar;
use starplex::topo::naive::VtIndex;

fn complex(nv: usize, cells: &[(CellKind, Vec<u32>)]) -> Option<IndexedComplex> {
    let mut b = ComplexBuilder::new(3).unwrap();
    for i in 0..nv {
        let x = i as f64;
        b.push_vertex(&[x.sin(), (2.0 * x).cos(), (0.5 * x).sin()])
            .unwrap();
    }
    for (k, v) in cells {
        b.push_cell(*k, v).ok()?;
    }
    let opts = BuildOptions {
        drop_duplicates: true,
        drop_face_cells: true,
        ..Default::default()
    };
    b.build(&opts).ok().map(|x| x.0)
}

/// The Stellar tree's report for several bucket sizes equals the generic one, and the generic
/// one is the same on every structure that holds the complex.
fn agree(name: &str, k: &IndexedComplex) -> ValidationReport {
    let r = validate(&VtIndex::new(k));
    for kv in [1, 4, 0] {
        let opts = StellarOptions {
            kv: (kv > 0).then_some(kv),
            ..Default::default()
        };
        let t = StellarTree::build(k, &opts).unwrap();
        assert_eq!(t.validate(), r, "{name}: Stellar tree (kv {kv}) vs algo");
        assert_eq!(validate(&t), r, "{name}: algo on the Stellar tree");
    }
    if let Ok(ia) = IaStar::new(k) {
        assert_eq!(validate(&ia), r, "{name}: algo on IA*");
    }
    let s = singularities(&VtIndex::new(k), Convention::Global).unwrap();
    assert_eq!(s.non_manifold_vertices, r.non_manifold_vertices, "{name}");
    assert_eq!(s.non_manifold_edges, r.non_manifold_edges, "{name}");
    assert_eq!(s.unknown_vertices, r.unknown_vertices, "{name}");
    assert_eq!(is_valid(&VtIndex::new(k)), r.is_valid_manifold(), "{name}");
    assert_eq!(errors(&VtIndex::new(k)).is_empty(), r.is_valid_manifold());
    assert_eq!(check(&VtIndex::new(k)).is_ok(), r.is_valid_manifold());
    r
}

const TRI: CellKind = CellKind::Simplex(2);
const TET: CellKind = CellKind::Simplex(3);

fn strip(n: u32, twist: bool) -> Vec<(CellKind, Vec<u32>)> {
    // a band of 2n triangles around a cycle; with `twist` the last square is glued reversed
    let mut c = Vec::new();
    for i in 0..n {
        let (a, b) = (2 * i, 2 * i + 1);
        let (mut na, mut nb) = (2 * ((i + 1) % n), 2 * ((i + 1) % n) + 1);
        if twist && i == n - 1 {
            std::mem::swap(&mut na, &mut nb);
        }
        c.push((TRI, vec![a, b, na]));
        c.push((TRI, vec![b, nb, na]));
    }
    c
}

#[test]
fn fixtures_agree() {
    let s4: Vec<(CellKind, Vec<u32>)> = (0..5u32)
        .map(|j| (TET, (0..5).filter(|&x| x != j).collect()))
        .collect();
    let bd5: Vec<(CellKind, Vec<u32>)> = (0..6u32)
        .map(|j| (CellKind::Simplex(4), (0..6).filter(|&x| x != j).collect()))
        .collect();
    type Cells = Vec<(CellKind, Vec<u32>)>;
    let cases: Vec<(&str, usize, Cells)> = vec![
        ("empty", 0, vec![]),
        ("points", 3, vec![]),
        ("vertex cells", 3, vec![(CellKind::Simplex(0), vec![1])]),
        ("triangle", 3, vec![(TRI, vec![0, 1, 2])]),
        (
            "bow tie",
            5,
            vec![(TRI, vec![0, 1, 2]), (TRI, vec![0, 3, 4])],
        ),
        ("book", 5, (2..5).map(|c| (TRI, vec![0, 1, c])).collect()),
        (
            "dangling edge",
            4,
            vec![(TRI, vec![0, 1, 2]), (CellKind::Simplex(1), vec![2, 3])],
        ),
        ("isolated vertex", 4, vec![(TRI, vec![0, 1, 2])]),
        ("annulus", 8, strip(4, false)),
        ("Möbius", 8, strip(4, true)),
        ("tet", 4, vec![(TET, vec![0, 1, 2, 3])]),
        ("3-sphere", 5, s4),
        ("4-sphere", 6, bd5),
        (
            "5-simplex",
            6,
            vec![(CellKind::Simplex(5), (0..6).collect())],
        ),
        (
            "two tets on an edge",
            6,
            vec![(TET, vec![0, 1, 2, 3]), (TET, vec![0, 1, 4, 5])],
        ),
        (
            "two hexes",
            12,
            vec![
                (CellKind::Hex, vec![0, 1, 2, 3, 4, 5, 6, 7]),
                (CellKind::Hex, vec![1, 8, 9, 2, 5, 10, 11, 6]),
            ],
        ),
        (
            "hex and pyramid",
            9,
            vec![
                (CellKind::Hex, vec![0, 1, 2, 3, 4, 5, 6, 7]),
                (CellKind::Pyramid, vec![7, 6, 5, 4, 8]),
            ],
        ),
        (
            "quads and a triangle",
            7,
            vec![
                (CellKind::Quad, vec![0, 1, 2, 3]),
                (CellKind::Quad, vec![1, 4, 5, 2]),
                (TRI, vec![2, 5, 6]),
            ],
        ),
        (
            "prism on a tet",
            7,
            vec![
                (CellKind::Prism, vec![0, 1, 2, 3, 4, 5]),
                (TET, vec![3, 4, 5, 6]),
            ],
        ),
    ];
    for (name, nv, cells) in cases {
        let k = complex(nv, &cells).unwrap();
        agree(name, &k);
    }
    // the definitions, by name
    let mob = agree("Möbius", &complex(8, &strip(4, true)).unwrap());
    assert_eq!(mob.orientable, Some(false));
    let ann = agree("annulus", &complex(8, &strip(4, false)).unwrap());
    assert_eq!(ann.orientable, Some(true));
    let sph = agree(
        "4-sphere",
        &complex(6, &{
            (0..6u32)
                .map(|j| (CellKind::Simplex(4), (0..6).filter(|&x| x != j).collect()))
                .collect::<Vec<_>>()
        })
        .unwrap(),
    );
    assert_eq!(sph.unknown_vertices.len(), 6);
}

/// Random cells: simplices of dimension 0-5 over few vertices (many non-manifold gluings,
/// mixed dimensions, isolated vertices), and sometimes hexahedra, prisms, pyramids and quads
/// on a small lattice.
fn random_cells(seed: &[u32], nv: usize, cp: bool) -> Vec<(CellKind, Vec<u32>)> {
    let mut out = Vec::new();
    let mut it = seed.chunks(7);
    if cp {
        // a 3x2x2 lattice of points, cells picked among its unit cubes
        let id = |x: u32, y: u32, z: u32| x + 3 * y + 6 * z;
        for (i, ch) in seed.chunks(3).take(4).enumerate() {
            let (x, y, z) = (ch[0] % 2, 0, 0);
            let kind = ch.get(1).copied().unwrap_or(0) % 4;
            let cube = [
                id(x, y, z),
                id(x + 1, y, z),
                id(x + 1, y + 1, z),
                id(x, y + 1, z),
                id(x, y, z + 1),
                id(x + 1, y, z + 1),
                id(x + 1, y + 1, z + 1),
                id(x, y + 1, z + 1),
            ];
            let _ = i;
            let c = match kind {
                0 => (CellKind::Hex, cube.to_vec()),
                1 => (
                    CellKind::Prism,
                    vec![cube[0], cube[1], cube[3], cube[4], cube[5], cube[7]],
                ),
                2 => (
                    CellKind::Pyramid,
                    vec![cube[0], cube[1], cube[2], cube[3], cube[4]],
                ),
                _ => (CellKind::Quad, vec![cube[4], cube[5], cube[6], cube[7]]),
            };
            out.push(c);
        }
        it = seed[12.min(seed.len())..].chunks(7);
    }
    for ch in it.filter(|ch| ch.len() >= 2) {
        let dim = (ch[0] % 6) as usize;
        let mut vs: Vec<u32> = ch[1..].iter().map(|&x| x % nv as u32).collect();
        vs.sort_unstable();
        vs.dedup();
        vs.truncate(dim + 1);
        let kind = CellKind::simplex(vs.len() - 1).unwrap();
        out.push((kind, vs));
    }
    out
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 200,
        rng_seed: proptest::test_runner::RngSeed::Fixed(20261201),
        failure_persistence: None,
        ..ProptestConfig::default()
    })]
    #[test]
    fn random_non_pure_complexes_agree(
        nv in 4usize..13,
        seed in proptest::collection::vec(0u32..1000, 7..60),
        cp in proptest::bool::weighted(0.25),
    ) {
        let nv = if cp { nv.max(12) } else { nv };
        let cells = random_cells(&seed, nv, cp);
        if let Some(k) = complex(nv, &cells) {
            agree("random", &k);
        }
    }

    /// Triangles only, where the Stellar tree validates in its own single pass: random
    /// triangles on few vertices (non-manifold edges and vertices, isolated vertices), with
    /// a Möbius or a plain strip glued on, so orientable and non-orientable inputs both occur.
    #[test]
    fn random_triangle_complexes_agree(
        nv in 4usize..16,
        seed in proptest::collection::vec(0u32..1000, 3..45),
        strip_len in 0u32..6,
        twist in proptest::bool::ANY,
    ) {
        let mut cells: Vec<(CellKind, Vec<u32>)> = Vec::new();
        for ch in seed.chunks(3).filter(|ch| ch.len() == 3) {
            let vs: Vec<u32> = ch.iter().map(|&x| x % nv as u32).collect();
            if vs[0] != vs[1] && vs[1] != vs[2] && vs[0] != vs[2] {
                cells.push((TRI, vs));
            }
        }
        let base = nv as u32;
        let mut n = nv;
        if strip_len >= 3 {
            cells.extend(strip(strip_len, twist).into_iter().map(|(k, vs)| {
                (k, vs.into_iter().map(|v| v + base).collect())
            }));
            n += 2 * strip_len as usize;
        }
        if let Some(k) = complex(n, &cells) {
            let r = agree("random triangles", &k);
            prop_assert!(r.dim <= 2);
        }
    }

    /// Tetrahedra only, where the Stellar tree validates in its own single pass: random
    /// tetrahedra on few vertices (non-manifold triangles, edges and vertices, isolated
    /// vertices), some with their orientation reversed, and a Kuhn block of cubes with some
    /// tetrahedra removed (manifold with boundary, or pinched).
    #[test]
    fn random_tetrahedra_complexes_agree(
        nv in 5usize..14,
        seed in proptest::collection::vec(0u32..1000, 4..48),
        block in proptest::bool::ANY,
        drop in proptest::collection::vec(0u32..12, 0..6),
    ) {
        let mut cells: Vec<(CellKind, Vec<u32>)> = Vec::new();
        for ch in seed.chunks(4).filter(|ch| ch.len() == 4) {
            let vs: Vec<u32> = ch.iter().map(|&x| x % nv as u32).collect();
            let mut d = vs.clone();
            d.sort_unstable();
            d.dedup();
            if d.len() == 4 {
                cells.push((TET, vs));
            }
        }
        let mut n = nv;
        if block {
            // 2x1x1 cubes of six tetrahedra each, on 12 lattice points after the random ones
            let base = nv as u32;
            let id = |x: u32, y: u32, z: u32| base + x + 3 * y + 6 * z;
            let mut k = 0u32;
            for x in 0..2 {
                for p in [[0, 1, 2], [0, 2, 1], [1, 0, 2], [1, 2, 0], [2, 0, 1], [2, 1, 0]] {
                    k += 1;
                    if drop.contains(&(k % 12)) {
                        continue;
                    }
                    let mut c = [x, 0, 0];
                    let mut t = vec![id(c[0], c[1], c[2])];
                    for axis in p {
                        c[axis] += 1;
                        t.push(id(c[0], c[1], c[2]));
                    }
                    cells.push((TET, t));
                }
            }
            n += 12;
        }
        if let Some(k) = complex(n, &cells) {
            let r = agree("random tetrahedra", &k);
            prop_assert!(r.dim <= 3);
        }
    }

    /// The local convention, by its definition: a simplicial vertex star of one dimension k
    /// is manifold exactly when its link is a (k-1)-sphere or ball, and a star of mixed
    /// dimensions is not.
    #[test]
    fn local_convention_follows_its_definition(
        nv in 4usize..10,
        seed in proptest::collection::vec(0u32..1000, 7..40),
    ) {
        let cells = random_cells(&seed, nv, false);
        let Some(k) = complex(nv, &cells) else { return Ok(()) };
        let s = singularities(&VtIndex::new(&k), Convention::Local).unwrap();
        for v in 0..k.n_vertices() {
            let mut tops: Vec<Vec<u32>> = Vec::new();
            for c in k.cells() {
                if c.vertices.contains(&(v as u32)) {
                    let mut t: Vec<u32> = c.vertices.iter().copied().filter(|&x| x != v as u32).collect();
                    t.sort_unstable();
                    tops.push(t);
                }
            }
            // an isolated vertex, or a vertex that is itself a top cell: the empty link
            let want = if tops.is_empty() || (tops.len() == 1 && tops[0].is_empty()) {
                Manifoldness::Manifold
            } else if tops.iter().any(|t| t.len() != tops[0].len()) {
                Manifoldness::NonManifold
            } else {
                match brute_sphere_or_ball(&tops, tops[0].len() as isize - 1) {
                    Some(true) => Manifoldness::Manifold,
                    Some(false) => Manifoldness::NonManifold,
                    // link dimension >= 3: what sphere_or_ball says, which must not be Manifold
                    // unless it is a single simplex
                    None => {
                        let m = sphere_or_ball(&tops, tops[0].len() as isize - 1);
                        prop_assert!(m != Manifoldness::Manifold || tops.len() == 1);
                        m
                    }
                }
            };
            let got = if s.non_manifold_vertices.contains(&VertexId(v as u32)) {
                Manifoldness::NonManifold
            } else if s.unknown_vertices.contains(&VertexId(v as u32)) {
                Manifoldness::Unknown
            } else {
                Manifoldness::Manifold
            };
            prop_assert_eq!(got, want, "vertex {}", v);
        }
    }
}

/// Whether a pure complex of dimension m <= 2 (maximal simplices, sorted) is a sphere or a
/// ball, from the definitions: m = 0 one or two points; m = 1 a path or a cycle; m = 2 every
/// edge in one or two triangles, every vertex link a path or a cycle, connected, and χ = 2
/// without boundary or χ = 1 with a boundary that is one cycle. `None` for m >= 3.
fn brute_sphere_or_ball(maxes: &[Vec<u32>], m: isize) -> Option<bool> {
    use std::collections::{BTreeMap, BTreeSet};
    let verts: BTreeSet<u32> = maxes.iter().flatten().copied().collect();
    let connected = |edges: &[(u32, u32)], verts: &BTreeSet<u32>| {
        let mut seen = BTreeSet::new();
        let mut stack = vec![*verts.iter().next().unwrap()];
        while let Some(x) = stack.pop() {
            if seen.insert(x) {
                for &(a, b) in edges {
                    if a == x {
                        stack.push(b)
                    }
                    if b == x {
                        stack.push(a)
                    }
                }
            }
        }
        seen.len() == verts.len()
    };
    let path_or_cycle = |edges: &[(u32, u32)]| {
        let vs: BTreeSet<u32> = edges.iter().flat_map(|&(a, b)| [a, b]).collect();
        let mut deg: BTreeMap<u32, usize> = BTreeMap::new();
        for &(a, b) in edges {
            *deg.entry(a).or_default() += 1;
            *deg.entry(b).or_default() += 1;
        }
        !vs.is_empty() && deg.values().all(|&d| d <= 2) && connected(edges, &vs)
    };
    match m {
        0 => Some(maxes.len() <= 2),
        1 => Some(path_or_cycle(
            &maxes.iter().map(|e| (e[0], e[1])).collect::<Vec<_>>(),
        )),
        2 => {
            let mut edge_count: BTreeMap<(u32, u32), usize> = BTreeMap::new();
            for t in maxes {
                for (a, b) in [(t[0], t[1]), (t[0], t[2]), (t[1], t[2])] {
                    *edge_count.entry((a, b)).or_default() += 1;
                }
            }
            if edge_count.values().any(|&c| c > 2) {
                return Some(false);
            }
            for &x in &verts {
                let lk: Vec<(u32, u32)> = maxes
                    .iter()
                    .filter(|t| t.contains(&x))
                    .map(|t| {
                        let o: Vec<u32> = t.iter().copied().filter(|&y| y != x).collect();
                        (o[0], o[1])
                    })
                    .collect();
                if !path_or_cycle(&lk) {
                    return Some(false);
                }
            }
            let edges: Vec<(u32, u32)> = edge_count.keys().copied().collect();
            if !connected(&edges, &verts) {
                return Some(false);
            }
            let chi = verts.len() as i64 - edges.len() as i64 + maxes.len() as i64;
            let bd: Vec<(u32, u32)> = edge_count
                .iter()
                .filter(|e| *e.1 == 1)
                .map(|e| *e.0)
                .collect();
            Some(if bd.is_empty() {
                chi == 2
            } else {
                let bv: BTreeSet<u32> = bd.iter().flat_map(|&(a, b)| [a, b]).collect();
                chi == 1 && connected(&bd, &bv)
            })
        }
        _ => None,
    }
}

#[test]
fn small_datasets_agree() {
    let sets = common_data::small_datasets();
    if sets.is_empty() {
        assert!(!common_data::data_required(), "no small datasets found");
        println!("SKIPPED: no datasets");
        return;
    }
    for (name, path, _) in sets {
        let k = starplex::io::read(&path, &Default::default())
            .unwrap()
            .complex;
        let r = validate(&VtIndex::new(&k));
        let t = StellarTree::build(&k, &StellarOptions::default()).unwrap();
        assert_eq!(t.validate(), r, "{name}");
    }
}
