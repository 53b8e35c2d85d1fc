//! `info` against a brute-force model: every face of every cell enumerated into sets.
use std::collections::{BTreeMap, BTreeSet};

use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed};
use starplex::algo::info::{info, InfoOptions};
use starplex::cell::{canonical_key, CellKind};
use starplex::complex::{BuildOptions, ComplexBuilder, IndexedComplex};

/// f-vector, boundary and >2-shared counts, components, by plain enumeration.
fn brute(k: &IndexedComplex) -> (Vec<u64>, Option<(u64, u64)>, u64) {
    let dim = k.dim().unwrap();
    let mut faces: Vec<BTreeSet<Vec<u32>>> = vec![BTreeSet::new(); dim + 1];
    let mut key = Vec::new();
    let mut top_count: BTreeMap<Vec<u32>, u64> = BTreeMap::new();
    for c in k.cells() {
        for (fd, set) in faces.iter_mut().enumerate().take(c.kind.dim() + 1) {
            c.kind.for_each_face(fd, |l| {
                canonical_key(c.vertices, l, &mut key);
                set.insert(key.clone());
                if c.kind.dim() == dim && fd + 1 == dim {
                    *top_count.entry(key.clone()).or_default() += 1;
                }
            });
        }
    }
    let mut f: Vec<u64> = faces.iter().map(|s| s.len() as u64).collect();
    f[0] = k.n_vertices() as u64;
    let dims: BTreeSet<usize> = k.cells().map(|c| c.kind.dim()).collect();
    let boundary = (dims.len() == 1 && dim >= 1).then(|| {
        (
            top_count.values().filter(|&&n| n == 1).count() as u64,
            top_count.values().filter(|&&n| n > 2).count() as u64,
        )
    });
    // components by repeated relaxation (plain and slow on purpose)
    let mut label: Vec<u32> = (0..k.n_vertices() as u32).collect();
    loop {
        let mut changed = false;
        for c in k.cells() {
            let m = c.vertices.iter().map(|&v| label[v as usize]).min().unwrap();
            for &v in c.vertices {
                if label[v as usize] != m {
                    label[v as usize] = m;
                    changed = true;
                }
            }
        }
        if !changed {
            break;
        }
    }
    let comps = label
        .iter()
        .enumerate()
        .filter(|&(ref i, &l)| *i as u32 == l)
        .count() as u64;
    (f, boundary, comps)
}

fn random_complex() -> impl Strategy<Value = IndexedComplex> {
    (
        1usize..14,
        prop::collection::vec(prop::collection::btree_set(0u32..14, 1..6), 0..25),
    )
        .prop_map(|(nv, cells)| {
            let mut b = ComplexBuilder::new(2).unwrap();
            for i in 0..nv {
                b.push_vertex(&[i as f64, (i * 7 % 5) as f64]).unwrap();
            }
            for c in cells {
                let v: Vec<u32> = c
                    .into_iter()
                    .map(|x| x % nv as u32)
                    .collect::<BTreeSet<_>>()
                    .into_iter()
                    .collect();
                b.push_cell(CellKind::Simplex((v.len() - 1) as u8), &v)
                    .unwrap();
            }
            b.build(&BuildOptions {
                drop_face_cells: true,
                drop_duplicates: true,
                ..Default::default()
            })
            .unwrap()
            .0
        })
}

proptest! {
    #![proptest_config(Config { cases: 300, rng_seed: RngSeed::Fixed(7), failure_persistence: None, ..Config::default() })]

    #[test]
    fn info_equals_brute_force(k in random_complex()) {
        let s = info(&k, &InfoOptions::default());
        let (f, boundary, comps) = brute(&k);
        prop_assert_eq!(s.f_vector.as_ref(), Some(&f));
        prop_assert_eq!(s.n_connected_components, comps);
        let ours = s.n_boundary_faces.map(|b| (b, s.n_faces_shared_by_more_than_2_top_cells.unwrap()));
        prop_assert_eq!(ours, boundary);
        let euler: i64 = f.iter().enumerate().map(|(i, &x)| if i % 2 == 0 { x as i64 } else { -(x as i64) }).sum();
        prop_assert_eq!(s.euler_characteristic, Some(euler));
    }

    #[test]
    fn thread_count_does_not_change_info(k in random_complex()) {
        let one = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap().install(|| info(&k, &InfoOptions::default()));
        let two = rayon::ThreadPoolBuilder::new().num_threads(2).build().unwrap().install(|| info(&k, &InfoOptions::default()));
        prop_assert_eq!(one, two);
    }
}

/// Mixed CP fixtures: a hex, a prism on its top face's half, a pyramid on its side, a tet on
/// the pyramid, a quad and a line hanging off.
#[test]
fn cp_fixtures_equal_brute_force() {
    let mut b = ComplexBuilder::new(3).unwrap();
    let pts: Vec<[f64; 3]> = (0..20)
        .map(|i| [i as f64, (i * i % 7) as f64, (i % 3) as f64])
        .collect();
    for p in &pts {
        b.push_vertex(p).unwrap();
    }
    b.push_cell(CellKind::Hex, &[0, 1, 2, 3, 4, 5, 6, 7])
        .unwrap();
    b.push_cell(CellKind::Hex, &[4, 5, 6, 7, 8, 9, 10, 11])
        .unwrap(); // shares the quad 4567
    b.push_cell(CellKind::Prism, &[8, 9, 10, 12, 13, 14])
        .unwrap(); // shares edge 8-9, 9-10
    b.push_cell(CellKind::Pyramid, &[0, 1, 5, 4, 15]).unwrap(); // base = hex side quad 0154
    b.push_cell(CellKind::Simplex(3), &[0, 1, 15, 16]).unwrap(); // shares pyramid triangle 0-1-15
    b.push_cell(CellKind::Quad, &[16, 17, 18, 19]).unwrap();
    b.push_cell(CellKind::Simplex(1), &[19, 2]).unwrap();
    let k = b.build(&BuildOptions::default()).unwrap().0;
    let s = info(&k, &InfoOptions::default());
    let (f, _, comps) = brute(&k);
    assert_eq!(s.f_vector, Some(f));
    assert_eq!(s.n_connected_components, comps);
    assert_eq!(
        s.n_boundary_faces, None,
        "mixed dimensions: no boundary count"
    );
    // a pure CP 3-complex: two hexes and the pyramid and the tet
    let mut b = ComplexBuilder::new(3).unwrap();
    for p in &pts {
        b.push_vertex(p).unwrap();
    }
    b.push_cell(CellKind::Hex, &[0, 1, 2, 3, 4, 5, 6, 7])
        .unwrap();
    b.push_cell(CellKind::Hex, &[4, 5, 6, 7, 8, 9, 10, 11])
        .unwrap();
    b.push_cell(CellKind::Pyramid, &[0, 1, 5, 4, 15]).unwrap();
    b.push_cell(CellKind::Simplex(3), &[0, 1, 15, 16]).unwrap();
    let k = b.build(&BuildOptions::default()).unwrap().0;
    let s = info(&k, &InfoOptions::default());
    let (f, boundary, _) = brute(&k);
    assert_eq!(s.f_vector, Some(f));
    assert_eq!(
        s.n_boundary_faces
            .zip(s.n_faces_shared_by_more_than_2_top_cells),
        boundary
    );
    // 2 hexes: 12 quads, pyramid: 1 quad + 4 tris, minus shared quads 4567 and 0154,
    // tet: 4 tris minus the shared 0-1-15
    assert_eq!(s.faces_by_type.unwrap()["quad"], 12 + 1 - 2);
}

#[test]
fn over_budget_gives_an_estimate_not_an_explosion() {
    let mut b = ComplexBuilder::new(1).unwrap();
    for i in 0..41 {
        b.push_vertex(&[i as f64]).unwrap();
    }
    let all: Vec<u32> = (0..41).collect();
    b.push_cell(CellKind::Simplex(40), &all).unwrap();
    let k = b.build(&BuildOptions::default()).unwrap().0;
    let s = info(&k, &InfoOptions::default());
    assert_eq!(s.f_vector, None);
    // proper faces of dimension 1..=39: all non-empty subsets minus 41 vertices and the cell
    assert_eq!(s.f_vector_estimate, Some((1u128 << 41) - 1 - 41 - 1));
    assert_eq!(s.dim, 40);
    assert_eq!(s.n_connected_components, 1);
}
