//! Validation on small named fixtures whose answers are known by construction (3D link tests,
//! d >= 4 tri-state, orientability).
use starplex::algo::manifold::Manifoldness;
use starplex::cell::CellKind;
use starplex::complex::{BuildOptions, ComplexBuilder, IndexedComplex};
use starplex::ids::{CellId, VertexId};
use starplex::stellar::{StellarOptions, StellarTree};

fn complex(nv: usize, cells: &[(CellKind, Vec<u32>)]) -> IndexedComplex {
    let mut b = ComplexBuilder::new(3).unwrap();
    for i in 0..nv {
        let x = i as f64;
        b.push_vertex(&[x.sin(), (2.0 * x).cos(), (0.5 * x).sin()])
            .unwrap();
    }
    for (k, v) in cells {
        b.push_cell(*k, v).unwrap();
    }
    b.build(&BuildOptions::default()).unwrap().0
}

fn tree(k: &IndexedComplex, kv: u32) -> StellarTree {
    StellarTree::build(
        k,
        &StellarOptions {
            kv: Some(kv),
            ..Default::default()
        },
    )
    .unwrap()
}

const TET: CellKind = CellKind::Simplex(3);
const TRI: CellKind = CellKind::Simplex(2);

fn vs(x: &[u32]) -> Vec<VertexId> {
    x.iter().map(|&v| VertexId(v)).collect()
}

#[test]
fn tetrahedra() {
    for kv in [1, 3, 0] {
        let one = complex(4, &[(TET, vec![0, 1, 2, 3])]);
        let r = tree(&one, kv).validate();
        assert!(r.is_valid_manifold(), "{r:?}");
        assert_eq!(r.n_boundary_faces(), 4);

        // two tets sharing edge 01
        let k = complex(6, &[(TET, vec![0, 1, 2, 3]), (TET, vec![0, 1, 4, 5])]);
        let r = tree(&k, kv).validate();
        assert_eq!(r.non_manifold_edges, vec![[VertexId(0), VertexId(1)]]);
        assert_eq!(r.non_manifold_vertices, vs(&[0, 1]));
        assert!(!r.pseudo_manifold);
        assert_eq!(r.n_facet_components, 2);

        // two tets sharing vertex 0
        let k = complex(7, &[(TET, vec![0, 1, 2, 3]), (TET, vec![0, 4, 5, 6])]);
        let r = tree(&k, kv).validate();
        assert!(r.non_manifold_edges.is_empty());
        assert_eq!(r.non_manifold_vertices, vs(&[0]));

        // octahedron split into 8 tets around the centre 6: every vertex manifold
        let mut cells = Vec::new();
        for (a, b) in [(0, 2), (2, 1), (1, 3), (3, 0)] {
            cells.push((TET, vec![6, a, b, 4]));
            cells.push((TET, vec![6, b, a, 5]));
        }
        let k = complex(7, &cells);
        let r = tree(&k, kv).validate();
        assert!(r.non_manifold_vertices.is_empty(), "{r:?}");
        assert!(r.non_manifold_edges.is_empty());
        assert_eq!(r.n_boundary_faces(), 8);
        assert!(r.pseudo_manifold);
        assert_eq!(r.orientable, Some(true));

        // cone over a 3x3 torus: the apex's link is a torus (chi = 0), everything else fine
        let mut cells = Vec::new();
        let id = |i: u32, j: u32| (i % 3) * 3 + (j % 3);
        for i in 0..3 {
            for j in 0..3 {
                cells.push((TET, vec![9, id(i, j), id(i + 1, j), id(i + 1, j + 1)]));
                cells.push((TET, vec![9, id(i, j), id(i + 1, j + 1), id(i, j + 1)]));
            }
        }
        let k = complex(10, &cells);
        let r = tree(&k, kv).validate();
        assert_eq!(r.non_manifold_vertices, vs(&[9]));
        assert!(r.non_manifold_edges.is_empty());
        assert_eq!(r.n_boundary_faces(), 18);
    }
}

#[test]
fn hexahedra() {
    // 2x2x2 block of hexes
    let id = |i: u32, j: u32, l: u32| i + 3 * j + 9 * l;
    let mut cells = Vec::new();
    for i in 0..2 {
        for j in 0..2 {
            for l in 0..2 {
                cells.push((
                    CellKind::Hex,
                    vec![
                        id(i, j, l),
                        id(i + 1, j, l),
                        id(i + 1, j + 1, l),
                        id(i, j + 1, l),
                        id(i, j, l + 1),
                        id(i + 1, j, l + 1),
                        id(i + 1, j + 1, l + 1),
                        id(i, j + 1, l + 1),
                    ],
                ));
            }
        }
    }
    let k = complex(27, &cells);
    for kv in [1, 5, 0] {
        let r = tree(&k, kv).validate();
        assert!(r.is_valid_manifold(), "{r:?}");
        assert_eq!(r.n_boundary_faces(), 24);
        assert_eq!(r.cells_to_flip, Some(vec![]));
    }
    // two hexes sharing only an edge
    let k = complex(
        14,
        &[
            (CellKind::Hex, vec![0, 1, 2, 3, 4, 5, 6, 7]),
            (CellKind::Hex, vec![0, 4, 8, 9, 10, 11, 12, 13]),
        ],
    );
    let r = tree(&k, 2).validate();
    assert_eq!(r.non_manifold_edges, vec![[VertexId(0), VertexId(4)]]);
    assert_eq!(r.non_manifold_vertices, vs(&[0, 4]));
}

#[test]
fn high_dimension_is_tri_state() {
    let s4 = CellKind::Simplex(4);
    // one 4-simplex: every link is a simplex, a ball (decided at once)
    let k = complex(5, &[(s4, vec![0, 1, 2, 3, 4])]);
    let r = tree(&k, 1).validate();
    assert!(r.unknown_vertices.is_empty() && r.non_manifold_vertices.is_empty());
    assert!(r.pseudo_manifold && r.is_valid_manifold());
    // the boundary of a 5-simplex: vertex links are 3-spheres, undecided
    let bd5: Vec<(CellKind, Vec<u32>)> = (0..6u32)
        .map(|j| (s4, (0..6).filter(|&x| x != j).collect()))
        .collect();
    let r = tree(&complex(6, &bd5), 1).validate();
    assert_eq!(r.unknown_vertices.len(), 6);
    assert!(r.non_manifold_vertices.is_empty());
    assert!(r.pseudo_manifold);
    // two 4-simplices sharing vertex 0 (and glued into two 4-sphere-like clusters)
    let k = complex(9, &[(s4, vec![0, 1, 2, 3, 4]), (s4, vec![0, 5, 6, 7, 8])]);
    let r = tree(&k, 1).validate();
    assert_eq!(r.non_manifold_vertices, vs(&[0]));
    assert!(r.unknown_vertices.is_empty());
    let _ = Manifoldness::Unknown;
}

fn strip(n: u32, twist: bool) -> Vec<(CellKind, Vec<u32>)> {
    // vertices i (bottom) and n + i (top), i in 0..n, closed into a band
    let mut cells = Vec::new();
    for i in 0..n {
        let j = (i + 1) % n;
        let (b0, t0) = (i, n + i);
        let (mut b1, mut t1) = (j, n + j);
        if twist && j == 0 {
            std::mem::swap(&mut b1, &mut t1);
        }
        cells.push((TRI, vec![b0, b1, t1]));
        cells.push((TRI, vec![b0, t1, t0]));
    }
    cells
}

#[test]
fn orientability() {
    let k = complex(12, &strip(6, false));
    let r = tree(&k, 2).validate();
    assert_eq!(r.orientable, Some(true));
    assert_eq!(r.cells_to_flip, Some(vec![]));
    assert_eq!(r.n_boundary_faces(), 12);
    let k = complex(12, &strip(6, true));
    let r = tree(&k, 2).validate();
    assert_eq!(r.orientable, Some(false));
    assert!(r.orientation_conflict.is_some());
    assert!(r.cells_to_flip.is_none());
    // flip some triangles of the band: the consistent orientation flips them back
    let mut cells = strip(6, false);
    let flipped = [1usize, 4, 5, 9];
    for &f in &flipped {
        cells[f].1.swap(0, 1);
    }
    let k = complex(12, &cells);
    for kv in [1, 3, 0] {
        let r = tree(&k, kv).validate();
        let got = r.cells_to_flip.unwrap();
        let want: Vec<CellId> = flipped.iter().map(|&f| CellId(f as u32)).collect();
        let complement: Vec<CellId> = (0..12u32)
            .map(CellId)
            .filter(|c| !want.contains(c))
            .collect();
        assert!(got == want || got == complement, "{got:?}");
    }
}
