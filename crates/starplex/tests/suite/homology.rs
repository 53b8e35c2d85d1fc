//! Homology: named fixtures built in code (spheres, torus, Klein bottle, RP², RP³, non-manifold
//! gluings, a 40-simplex, wedges of spheres, CP complexes), property tests against a dense
//! Z/2 rank computation over all faces written here, and the `betti_z2` of every dataset
//! oracle (computed by GUDHI).
use crate::common_data;

use std::collections::BTreeSet;

use proptest::prelude::*;
use starplex::algo::homology::{
    chain_complex_homology, homology, homology_indexed, homology_owned, Field, Generator, Homology,
    HomologyError, HomologyOptions, MorseComplex, VertexOrder,
};
use starplex::buf::Buf;
use starplex::cell::CellKind;
use starplex::complex::{BuildOptions, ComplexBuilder, IndexedComplex};
use starplex::io::{self, ReadOptions};
use starplex::topo::naive::VtIndex;

fn complex(cells: &[(CellKind, Vec<u32>)]) -> IndexedComplex {
    let nv = cells
        .iter()
        .flat_map(|(_, c)| c.iter().copied())
        .max()
        .map_or(0, |m| m + 1);
    complex_n(nv as usize, cells)
}

fn complex_n(nv: usize, cells: &[(CellKind, Vec<u32>)]) -> IndexedComplex {
    let mut b = ComplexBuilder::new(1).unwrap();
    for i in 0..nv {
        b.push_vertex(&[i as f64]).unwrap();
    }
    for (k, c) in cells {
        b.push_cell(*k, c).unwrap();
    }
    b.build(&BuildOptions::default()).unwrap().0
}

fn simplices(cells: &[Vec<u32>]) -> IndexedComplex {
    let v: Vec<(CellKind, Vec<u32>)> = cells
        .iter()
        .map(|c| (CellKind::Simplex((c.len() - 1) as u8), c.clone()))
        .collect();
    complex(&v)
}

fn run(k: &IndexedComplex, field: Field) -> Homology {
    homology(
        &VtIndex::new(k),
        &HomologyOptions {
            field,
            ..Default::default()
        },
    )
    .unwrap()
}

fn betti(k: &IndexedComplex, field: Field) -> Vec<u64> {
    run(k, field).betti
}

/// Dense Z/2 Betti numbers over every face (the brute-force model).
fn brute_betti_z2(nv: usize, cells: &[Vec<u32>]) -> Vec<u64> {
    let mut faces: Vec<BTreeSet<Vec<u32>>> = Vec::new();
    let mut used = vec![false; nv];
    for c in cells {
        let n = c.len();
        for mask in 1u32..(1 << n) {
            let mut f: Vec<u32> = (0..n)
                .filter(|i| mask >> i & 1 == 1)
                .map(|i| c[i])
                .collect();
            f.sort_unstable();
            let d = f.len() - 1;
            if faces.len() <= d {
                faces.resize(d + 1, BTreeSet::new());
            }
            faces[d].insert(f);
        }
        for &v in c {
            used[v as usize] = true;
        }
    }
    if faces.is_empty() {
        faces.push(BTreeSet::new());
    }
    for (v, u) in used.iter().enumerate() {
        if !u {
            faces[0].insert(vec![v as u32]);
        }
    }
    let lists: Vec<Vec<Vec<u32>>> = faces.iter().map(|s| s.iter().cloned().collect()).collect();
    let rank = |d: usize| -> usize {
        // boundary d -> d-1 as bit rows
        if d == 0 || d >= lists.len() {
            return 0;
        }
        let rows = lists[d - 1].len();
        let words = rows.div_ceil(64);
        let mut m: Vec<Vec<u64>> = lists[d]
            .iter()
            .map(|s| {
                let mut col = vec![0u64; words];
                for i in 0..s.len() {
                    let mut f = s.clone();
                    f.remove(i);
                    let r = lists[d - 1].binary_search(&f).unwrap();
                    col[r / 64] ^= 1 << (r % 64);
                }
                col
            })
            .collect();
        let mut rank = 0;
        for bit in 0..rows {
            let Some(p) = (rank..m.len()).find(|&j| m[j][bit / 64] >> (bit % 64) & 1 == 1) else {
                continue;
            };
            m.swap(rank, p);
            for j in 0..m.len() {
                if j != rank && m[j][bit / 64] >> (bit % 64) & 1 == 1 {
                    let pr = m[rank].clone();
                    for (a, b) in m[j].iter_mut().zip(&pr) {
                        *a ^= b;
                    }
                }
            }
            rank += 1;
        }
        rank
    };
    let ranks: Vec<usize> = (0..=lists.len()).map(rank).collect();
    (0..lists.len())
        .map(|d| (lists[d].len() - ranks[d] - ranks[d + 1]) as u64)
        .collect()
}

fn tetra_boundary(off: u32) -> Vec<Vec<u32>> {
    let v = [off, off + 1, off + 2, off + 3];
    vec![
        vec![v[0], v[1], v[2]],
        vec![v[0], v[1], v[3]],
        vec![v[0], v[2], v[3]],
        vec![v[1], v[2], v[3]],
    ]
}

/// Boundary of the (d+1)-simplex on `vs` (d+2 vertices): a d-sphere.
fn sphere(vs: &[u32]) -> Vec<Vec<u32>> {
    (0..vs.len())
        .map(|i| {
            let mut f = vs.to_vec();
            f.remove(i);
            f
        })
        .collect()
}

/// A triangulated n x m grid with wrap-around; `flip` glues the last column to the first with
/// the rows reversed (a Klein bottle).
fn grid_surface(n: u32, m: u32, flip: bool) -> Vec<Vec<u32>> {
    let v = |i: u32, j: u32| -> u32 {
        let j = j % m;
        if i == n {
            if flip {
                (m - j) % m
            } else {
                j
            }
        } else {
            i * m + j
        }
    };
    let mut t = Vec::new();
    for i in 0..n {
        for j in 0..m {
            let (a, b, c, d) = (v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j + 1));
            t.push(vec![a, b, c]);
            t.push(vec![a, c, d]);
        }
    }
    t
}

const RP2: [[u32; 3]; 10] = [
    [0, 1, 2],
    [0, 2, 3],
    [0, 3, 4],
    [0, 4, 5],
    [0, 5, 1],
    [1, 2, 4],
    [2, 3, 5],
    [3, 4, 1],
    [4, 5, 2],
    [5, 1, 3],
];

/// Walkup's minimal RP³ (11 vertices, f = (11, 51, 80, 40)) as listed by Lutz (vertices 1..11).
const RP3: [[u32; 4]; 40] = [
    [1, 2, 3, 7],
    [1, 4, 7, 9],
    [2, 3, 4, 8],
    [2, 5, 8, 10],
    [3, 6, 7, 10],
    [1, 2, 3, 11],
    [1, 4, 7, 10],
    [2, 3, 4, 11],
    [2, 5, 9, 10],
    [3, 6, 8, 9],
    [1, 2, 6, 9],
    [1, 4, 8, 9],
    [2, 3, 7, 8],
    [2, 6, 9, 10],
    [3, 6, 9, 10],
    [1, 2, 6, 11],
    [1, 4, 8, 10],
    [2, 4, 6, 10],
    [3, 4, 5, 9],
    [4, 5, 6, 7],
    [1, 2, 7, 9],
    [1, 5, 6, 8],
    [2, 4, 6, 11],
    [3, 4, 5, 11],
    [4, 5, 6, 11],
    [1, 3, 5, 10],
    [1, 5, 6, 11],
    [2, 4, 8, 10],
    [3, 4, 8, 9],
    [4, 5, 7, 9],
    [1, 3, 5, 11],
    [1, 5, 8, 10],
    [2, 5, 7, 8],
    [3, 5, 9, 10],
    [4, 6, 7, 10],
    [1, 3, 7, 10],
    [1, 6, 8, 9],
    [2, 5, 7, 9],
    [3, 6, 7, 8],
    [5, 6, 7, 8],
];

fn f_vector(cells: &[Vec<u32>]) -> Vec<usize> {
    let mut faces: Vec<BTreeSet<Vec<u32>>> = Vec::new();
    for c in cells {
        for mask in 1u32..(1 << c.len()) {
            let f: Vec<u32> = (0..c.len())
                .filter(|i| mask >> i & 1 == 1)
                .map(|i| c[i])
                .collect();
            if faces.len() < f.len() {
                faces.resize(f.len(), BTreeSet::new());
            }
            let mut f = f;
            f.sort_unstable();
            faces[f.len() - 1].insert(f);
        }
    }
    faces.iter().map(|s| s.len()).collect()
}

#[test]
fn point_and_spheres() {
    let k = complex_n(1, &[]);
    assert_eq!(betti(&k, Field::Z2), vec![1]);
    let t = tetra_boundary(0);
    assert_eq!(betti(&simplices(&t), Field::Z2), vec![1, 0, 1]);
    let mut oct = Vec::new();
    for a in [0, 1] {
        for b in [2, 3] {
            for c in [4, 5] {
                oct.push(vec![a, b, c]);
            }
        }
    }
    let k = simplices(&oct);
    for f in [Field::Z2, Field::Zp(3), Field::Q, Field::Z] {
        assert_eq!(betti(&k, f), vec![1, 0, 1], "{f}");
    }
}

#[test]
fn torus_and_klein_bottle() {
    let t = grid_surface(3, 3, false);
    assert_eq!(brute_betti_z2(9, &t), vec![1, 2, 1]);
    let k = simplices(&t);
    for f in [Field::Z2, Field::Zp(5), Field::Q, Field::Z] {
        let h = run(&k, f);
        assert_eq!(h.betti, vec![1, 2, 1], "{f}");
        assert!(h.torsion.iter().all(|t| t.is_empty()));
    }
    let kb = grid_surface(4, 4, true);
    assert_eq!(brute_betti_z2(16, &kb), vec![1, 2, 1]);
    let k = simplices(&kb);
    assert_eq!(betti(&k, Field::Z2), vec![1, 2, 1]);
    assert_eq!(betti(&k, Field::Zp(3)), vec![1, 1, 0]);
    assert_eq!(betti(&k, Field::Q), vec![1, 1, 0]);
    let hz = run(&k, Field::Z);
    assert_eq!(hz.betti, vec![1, 1, 0]);
    assert_eq!(hz.torsion, vec![vec![], vec![2], vec![]]); // H_1 = Z + Z/2
}

#[test]
fn projective_plane_and_space() {
    let rp2: Vec<Vec<u32>> = RP2.iter().map(|t| t.to_vec()).collect();
    assert_eq!(f_vector(&rp2), vec![6, 15, 10]); // Euler characteristic 1
    let k = simplices(&rp2);
    assert_eq!(betti(&k, Field::Z2), vec![1, 1, 1]);
    assert_eq!(betti(&k, Field::Q), vec![1, 0, 0]);
    assert_eq!(betti(&k, Field::Zp(3)), vec![1, 0, 0]);
    let hz = run(&k, Field::Z);
    assert_eq!(
        (hz.betti, hz.torsion),
        (vec![1, 0, 0], vec![vec![], vec![2], vec![]])
    );

    let rp3: Vec<Vec<u32>> = RP3
        .iter()
        .map(|t| t.iter().map(|x| x - 1).collect())
        .collect();
    assert_eq!(f_vector(&rp3), vec![11, 51, 80, 40]); // Euler characteristic 0
    assert_eq!(brute_betti_z2(11, &rp3), vec![1, 1, 1, 1]);
    let k = simplices(&rp3);
    assert_eq!(betti(&k, Field::Z2), vec![1, 1, 1, 1]);
    assert_eq!(betti(&k, Field::Q), vec![1, 0, 0, 1]);
    let hz = run(&k, Field::Z);
    assert_eq!(hz.betti, vec![1, 0, 0, 1]);
    assert_eq!(hz.torsion, vec![vec![], vec![2], vec![], vec![]]); // H_1 = Z/2, H_3 = Z
}

#[test]
fn non_manifold_gluings() {
    // bow-tie: two triangles sharing a vertex
    let k = simplices(&[vec![0, 1, 2], vec![0, 3, 4]]);
    assert_eq!(betti(&k, Field::Z2), vec![1, 0, 0]);
    // two hollow tetrahedra sharing a vertex, and sharing an edge
    let mut a = tetra_boundary(0);
    a.extend(tetra_boundary(3));
    assert_eq!(betti(&simplices(&a), Field::Z), vec![1, 0, 2]);
    let mut b = tetra_boundary(0);
    b.extend(tetra_boundary(2));
    assert_eq!(betti(&simplices(&b), Field::Z2), vec![1, 0, 2]);
    // three triangles on one edge (a book), with a dangling edge and an isolated vertex
    let cells = vec![
        (CellKind::Simplex(2), vec![0, 1, 2]),
        (CellKind::Simplex(2), vec![0, 1, 3]),
        (CellKind::Simplex(2), vec![0, 1, 4]),
        (CellKind::Simplex(1), vec![4, 5]),
    ];
    assert_eq!(betti(&complex_n(7, &cells), Field::Z2), vec![2, 0, 0]);
    // a circle of edges and a hollow triangle pinched to a filled one (non-pure)
    let cells = vec![
        (CellKind::Simplex(1), vec![0, 1]),
        (CellKind::Simplex(1), vec![1, 2]),
        (CellKind::Simplex(1), vec![0, 2]),
        (CellKind::Simplex(2), vec![2, 3, 4]),
        (CellKind::Simplex(1), vec![4, 5]),
        (CellKind::Simplex(1), vec![5, 3]),
    ];
    assert_eq!(betti(&complex(&cells), Field::Q), vec![1, 2, 0]);
}

#[test]
fn a_40_simplex_is_answered_at_once() {
    let t0 = std::time::Instant::now();
    let k = simplices(&[(0..41).collect()]);
    let h = run(&k, Field::Z);
    let mut want = vec![0u64; 41];
    want[0] = 1;
    assert_eq!(h.betti, want);
    assert_eq!(h.critical.iter().sum::<u64>(), 1);
    // two 40-simplices sharing 39 vertices: still cones everywhere
    let k = simplices(&[(0..41).collect(), (0..39).chain([41, 42]).collect()]);
    assert_eq!(run(&k, Field::Z2).betti, want);
    assert!(t0.elapsed().as_secs_f64() < 2.0, "{:?}", t0.elapsed());
}

#[test]
fn exploding_work_is_refused_with_an_estimate() {
    // the boundary of a 30-simplex: the lower star of its last vertex has ~2^30 cells
    let k = simplices(&sphere(&(0..31).collect::<Vec<u32>>()));
    let err = homology(&VtIndex::new(&k), &HomologyOptions::default()).unwrap_err();
    match err {
        HomologyError::TooLarge(starplex::limits::TooLarge { estimate, .. }) => {
            assert!(estimate >= 1 << 30, "{estimate}")
        }
        e => panic!("{e:?}"),
    }
}

#[test]
fn wedges_of_spheres_up_to_dimension_8() {
    let mut cells = Vec::new();
    let mut next = 1u32;
    for d in 1..=8u32 {
        let mut vs = vec![0u32];
        vs.extend(next..next + d + 1);
        next += d + 1;
        cells.extend(sphere(&vs));
    }
    let k = simplices(&cells);
    for f in [Field::Z2, Field::Zp(7), Field::Z] {
        assert_eq!(betti(&k, f), vec![1; 9], "{f}");
    }
    // two copies of S^4 and one S^6 at different base points, plus a circle
    let mut cells = sphere(&[0, 1, 2, 3, 4, 5]);
    cells.extend(sphere(&[5, 6, 7, 8, 9, 10]));
    cells.extend(sphere(&[11, 12, 13, 14, 15, 16, 17, 18]));
    cells.extend([vec![18, 19], vec![19, 20], vec![18, 20]]);
    // (two components: S^4 v S^4, and S^6 v S^1)
    let n = 21;
    assert_eq!(brute_betti_z2(n, &cells), vec![2, 1, 0, 0, 2, 0, 1]);
    assert_eq!(
        betti(&simplices(&cells), Field::Z2),
        vec![2, 1, 0, 0, 2, 0, 1]
    );
}

fn quad_grid(n: u32, m: u32, flip: bool) -> Vec<(CellKind, Vec<u32>)> {
    let v = |i: u32, j: u32| -> u32 {
        let j = j % m;
        if i == n {
            if flip {
                (m - j) % m
            } else {
                j
            }
        } else {
            i * m + j
        }
    };
    let mut q = Vec::new();
    for i in 0..n {
        for j in 0..m {
            q.push((
                CellKind::Quad,
                vec![v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j + 1)],
            ));
        }
    }
    q
}

#[test]
fn cp_complexes() {
    let k = complex(&quad_grid(4, 4, false));
    for f in [Field::Z2, Field::Q, Field::Z] {
        assert_eq!(betti(&k, f), vec![1, 2, 1], "{f}");
    }
    let kb = complex(&quad_grid(4, 4, true));
    let hz = run(&kb, Field::Z);
    assert_eq!(
        (hz.betti, hz.torsion),
        (vec![1, 1, 0], vec![vec![], vec![2], vec![]])
    );
    assert_eq!(betti(&kb, Field::Z2), vec![1, 2, 1]);
    // a solid torus of hexahedra: a ring of 4 cubes
    let n = 4u32;
    let v = |i: u32, y: u32, z: u32| (i % n) * 4 + y * 2 + z;
    let mut hexes = Vec::new();
    let mut prisms = Vec::new();
    for i in 0..n {
        hexes.push((
            CellKind::Hex,
            vec![
                v(i, 0, 0),
                v(i + 1, 0, 0),
                v(i + 1, 1, 0),
                v(i, 1, 0),
                v(i, 0, 1),
                v(i + 1, 0, 1),
                v(i + 1, 1, 1),
                v(i, 1, 1),
            ],
        ));
        // the same ring cut into prisms (each cube into two wedges standing on z = 0, so the
        // faces between cubes stay quads and the cells can be mixed with hexahedra)
        prisms.push((
            CellKind::Prism,
            vec![
                v(i, 0, 0),
                v(i + 1, 0, 0),
                v(i + 1, 1, 0),
                v(i, 0, 1),
                v(i + 1, 0, 1),
                v(i + 1, 1, 1),
            ],
        ));
        prisms.push((
            CellKind::Prism,
            vec![
                v(i, 0, 0),
                v(i + 1, 1, 0),
                v(i, 1, 0),
                v(i, 0, 1),
                v(i + 1, 1, 1),
                v(i, 1, 1),
            ],
        ));
    }
    let k = complex(&hexes);
    for f in [Field::Z2, Field::Zp(3), Field::Z] {
        assert_eq!(betti(&k, f), vec![1, 1, 0, 0], "{f}");
    }
    let k = complex(&prisms);
    assert_eq!(betti(&k, Field::Z), vec![1, 1, 0, 0]);
    // mixed: two hexes of the ring, the other two cubes as prisms, plus a pyramid on one face
    let mut mixed: Vec<(CellKind, Vec<u32>)> = hexes[..2].to_vec();
    mixed.extend(prisms[4..].iter().cloned());
    let apex = 16;
    mixed.push((
        CellKind::Pyramid,
        vec![v(0, 0, 0), v(0, 1, 0), v(1, 1, 0), v(1, 0, 0), apex],
    ));
    let k = complex(&mixed);
    assert_eq!(betti(&k, Field::Z), vec![1, 1, 0, 0]);
    assert_eq!(betti(&k, Field::Z2), vec![1, 1, 0, 0]);
}

/// Every triangle split into 3 quads (corner, edge midpoints, centroid), numbered as the
/// datasets' generator does: the old vertices, then the midpoints, then the centroids.
fn quads_from_triangles(nv: u32, tris: &[Vec<u32>]) -> Vec<(CellKind, Vec<u32>)> {
    let mut mid = std::collections::BTreeMap::new();
    for t in tris {
        for i in 0..3 {
            let (a, b) = (t[i], t[(i + 1) % 3]);
            let n = nv + mid.len() as u32;
            mid.entry((a.min(b), a.max(b))).or_insert(n);
        }
    }
    let first_centroid = nv + mid.len() as u32;
    let mut q = Vec::new();
    for (c, t) in tris.iter().enumerate() {
        let m = |a: u32, b: u32| mid[&(a.min(b), a.max(b))];
        let centre = first_centroid + c as u32;
        for i in 0..3 {
            let (a, b, p) = (t[i], t[(i + 1) % 3], t[(i + 2) % 3]);
            q.push((CellKind::Quad, vec![a, m(a, b), centre, m(p, a)]));
        }
    }
    q
}

#[test]
fn quads_from_triangles_leave_few_critical_cells() {
    // the breadth-first order treats a quad's diagonal as a neighbour: numbering the edge
    // neighbours only left about 15x more critical cells on such meshes
    let (n, m) = (60u32, 60u32);
    // a torus with the diagonals of its squares chosen at random and its vertices shuffled
    let mut seed = 13u64;
    let mut rng = move || {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        seed >> 33
    };
    let mut perm: Vec<u32> = (0..n * m).collect();
    for i in (1..perm.len()).rev() {
        perm.swap(i, rng() as usize % (i + 1));
    }
    let mut tris = Vec::new();
    for t in grid_surface(n, m, false).chunks(2) {
        let (a, b, c, d) = (t[0][0], t[0][1], t[0][2], t[1][2]);
        if rng() % 2 == 0 {
            tris.extend([vec![a, b, c], vec![a, c, d]]);
        } else {
            tris.extend([vec![a, b, d], vec![b, c, d]]);
        }
    }
    for t in &mut tris {
        for x in t.iter_mut() {
            *x = perm[*x as usize];
        }
    }
    let k = complex(&quads_from_triangles(n * m, &tris));
    let o = HomologyOptions {
        order: VertexOrder::BreadthFirst,
        ..Default::default()
    };
    let h = homology_owned(k.clone(), &o).unwrap();
    assert_eq!(h.betti, vec![1, 2, 1]);
    // 176 critical cells of 21,600 quads; numbering edge neighbours only gave 3,204
    assert!(h.critical.iter().sum::<u64>() <= 400, "{:?}", h.critical);
    assert_eq!(homology(&VtIndex::new(&k), &o).unwrap(), h);
}

#[test]
fn per_component_and_surfaces() {
    // a torus, a Klein bottle (quads), a disk, and a point
    let mut cells: Vec<(CellKind, Vec<u32>)> = grid_surface(3, 3, false)
        .into_iter()
        .map(|t| (CellKind::Simplex(2), t))
        .collect();
    cells.extend(
        quad_grid(4, 4, true)
            .into_iter()
            .map(|(k, q)| (k, q.iter().map(|x| x + 9).collect())),
    );
    cells.push((CellKind::Simplex(2), vec![25, 26, 27]));
    let k = complex_n(29, &cells);
    let h = homology(
        &VtIndex::new(&k),
        &HomologyOptions {
            per_component: true,
            ..Default::default()
        },
    )
    .unwrap();
    assert_eq!(h.betti, vec![4, 4, 2]);
    let comps = h.components.unwrap();
    assert_eq!(comps.len(), 4);
    assert_eq!(comps[0].betti, vec![1, 2, 1]);
    let s0 = comps[0].surface.unwrap();
    assert!(s0.orientable);
    assert_eq!(
        (s0.genus, s0.boundary_loops, s0.euler_characteristic),
        (1, 0, 0)
    );
    let s1 = comps[1].surface.unwrap();
    assert!(!s1.orientable);
    assert_eq!((s1.genus, s1.boundary_loops), (2, 0)); // Klein bottle: 2 cross-caps
    let s2 = comps[2].surface.unwrap();
    assert!(s2.orientable);
    assert_eq!((s2.genus, s2.boundary_loops), (0, 1));
    assert_eq!(comps[3].betti, vec![1, 0, 0]);
    assert!(comps[3].surface.is_none());
    // the bow-tie is not a surface
    let k = simplices(&[vec![0, 1, 2], vec![0, 3, 4]]);
    let h = homology(
        &VtIndex::new(&k),
        &HomologyOptions {
            per_component: true,
            ..Default::default()
        },
    )
    .unwrap();
    assert!(h.components.unwrap()[0].surface.is_none());
    // the Moebius strip: non-orientable, one boundary loop
    let m = simplices(&[
        vec![0, 1, 3],
        vec![1, 3, 4],
        vec![1, 2, 4],
        vec![2, 4, 5],
        vec![2, 5, 3], // the twist: 2 meets 3 and 5 meets 0
        vec![5, 3, 0],
    ]);
    let h = homology(
        &VtIndex::new(&m),
        &HomologyOptions {
            per_component: true,
            ..Default::default()
        },
    )
    .unwrap();
    assert_eq!(h.betti, vec![1, 1, 0]);
    let s = h.components.unwrap()[0].surface.unwrap();
    assert!(!s.orientable);
    assert_eq!(
        (s.genus, s.boundary_loops, s.euler_characteristic),
        (1, 1, 0)
    );
    assert_eq!(
        s.to_string(),
        "non-orientable surface, genus 1, 1 boundary loop, Euler characteristic 0"
    );
}

#[test]
fn generators_are_cycles_with_the_right_count() {
    let t = grid_surface(3, 3, false);
    let k = simplices(&t);
    for (field, order) in [
        (Field::Z2, VertexOrder::Input),
        (Field::Zp(3), VertexOrder::Input),
        (Field::Zp(3), VertexOrder::BreadthFirst),
        (Field::Z2, VertexOrder::FirstAppearance),
    ] {
        let h = homology(
            &VtIndex::new(&k),
            &HomologyOptions {
                field,
                order,
                generators: true,
                ..Default::default()
            },
        )
        .unwrap();
        let dims: Vec<usize> = h.generators.iter().map(|g| g.dim).collect();
        assert_eq!(dims, vec![0, 1, 1, 2], "{field}");
        let p = field.modulus();
        for g in &h.generators {
            // boundary of the chain is zero mod p
            let mut bd: std::collections::BTreeMap<Vec<u32>, i64> = Default::default();
            for (c, x) in &g.cells {
                if c.len() < 2 {
                    continue;
                }
                for i in 0..c.len() {
                    let mut f = c.clone();
                    f.remove(i);
                    let s = if i % 2 == 0 { 1 } else { -1 };
                    *bd.entry(f).or_insert(0) += s * x;
                }
            }
            assert!(bd.values().all(|x| x.rem_euclid(p) == 0), "{field} {g:?}");
        }
        // the H_2 generator is the whole torus
        assert_eq!(h.generators[3].cells.len(), 18);
    }
}

/// Z/2 rank of sets of edges (dense elimination).
fn z2_rank(rows: &[Vec<usize>], n: usize) -> usize {
    let words = n.div_ceil(64);
    let mut m: Vec<Vec<u64>> = rows
        .iter()
        .map(|r| {
            let mut b = vec![0u64; words];
            for &i in r {
                b[i / 64] ^= 1 << (i % 64);
            }
            b
        })
        .collect();
    let mut rank = 0;
    for bit in 0..n {
        let Some(p) = (rank..m.len()).find(|&j| m[j][bit / 64] >> (bit % 64) & 1 == 1) else {
            continue;
        };
        m.swap(rank, p);
        let pr = m[rank].clone();
        for (j, row) in m.iter_mut().enumerate() {
            if j != rank && row[bit / 64] >> (bit % 64) & 1 == 1 {
                row.iter_mut().zip(&pr).for_each(|(a, b)| *a ^= b);
            }
        }
        rank += 1;
    }
    rank
}

/// Checks that the H_1 generators of `h` are simple closed edge paths of the complex of
/// `cells` (triangles and edges), independent modulo the triangles' boundaries over Z/2;
/// returns their lengths.
fn check_loops(cells: &[Vec<u32>], h: &Homology) -> Vec<usize> {
    let mut edges: BTreeSet<Vec<u32>> = BTreeSet::new();
    for c in cells {
        for i in 0..c.len() {
            for j in i + 1..c.len() {
                edges.insert(vec![c[i].min(c[j]), c[i].max(c[j])]);
            }
        }
    }
    let edges: Vec<Vec<u32>> = edges.into_iter().collect();
    let id = |e: &[u32]| {
        let k = vec![e[0].min(e[1]), e[0].max(e[1])];
        edges.binary_search(&k).expect("an edge of the complex")
    };
    let mut rows: Vec<Vec<usize>> = cells
        .iter()
        .filter(|c| c.len() == 3)
        .map(|t| vec![id(&[t[0], t[1]]), id(&[t[0], t[2]]), id(&[t[1], t[2]])])
        .collect();
    let base = z2_rank(&rows, edges.len());
    let loops: Vec<&Generator> = h.generators.iter().filter(|g| g.dim == 1).collect();
    let mut lens = Vec::new();
    for g in &loops {
        // a simple closed path: every vertex on it has two of its edges, and it is connected
        let mut deg: std::collections::BTreeMap<u32, usize> = Default::default();
        for (e, _) in &g.cells {
            assert_eq!(e.len(), 2);
            *deg.entry(e[0]).or_default() += 1;
            *deg.entry(e[1]).or_default() += 1;
        }
        assert!(deg.values().all(|&d| d == 2), "not a simple loop: {g:?}");
        for w in g.cells.windows(2) {
            assert!(
                w[0].0.iter().any(|v| w[1].0.contains(v)),
                "not listed along the loop"
            );
        }
        rows.push(g.cells.iter().map(|(e, _)| id(e)).collect());
        lens.push(g.cells.len());
    }
    assert_eq!(
        z2_rank(&rows, edges.len()),
        base + loops.len(),
        "dependent loops"
    );
    assert_eq!(loops.len() as u64, h.betti[1]);
    lens
}

#[test]
fn h1_generators_are_short_closed_paths() {
    let gens = |cells: &[Vec<u32>], field: Field| {
        let k = simplices(cells);
        let o = HomologyOptions {
            field,
            generators: true,
            ..Default::default()
        };
        let h = homology(&VtIndex::new(&k), &o).unwrap();
        // the indexed path (lengths from the coordinates) and the consuming path agree
        assert_eq!(
            homology_owned(k.clone(), &o).unwrap(),
            homology_indexed(&k, &o).unwrap()
        );
        h
    };
    // a 12 x 7 torus: the shortest loops go once around each way (7 and 12 edges)
    let torus = grid_surface(12, 7, false);
    for field in [Field::Z2, Field::Zp(3)] {
        let h = gens(&torus, field);
        assert_eq!(check_loops(&torus, &h), vec![7, 12], "{field}");
    }
    // an annulus (the torus cut open along a row): one loop, around it
    let annulus: Vec<Vec<u32>> = torus[..2 * 7 * 11].to_vec();
    assert_eq!(check_loops(&annulus, &gens(&annulus, Field::Z2)), vec![7]);
    // a Klein bottle over Z/2: two loops; over Z/3 (no coherent orientation) the Morse
    // generators are kept, still cycles
    let kb = grid_surface(12, 7, true);
    assert_eq!(check_loops(&kb, &gens(&kb, Field::Z2)).len(), 2);
    let h3 = gens(&kb, Field::Zp(3));
    assert_eq!(h3.betti[1], 1);
    assert_eq!(h3.generators.iter().filter(|g| g.dim == 1).count(), 1);
    // a graph: a triangle and a square sharing a vertex, and a dangling edge
    let graph: Vec<Vec<u32>> = [
        [0, 1],
        [1, 2],
        [0, 2],
        [0, 3],
        [3, 4],
        [4, 5],
        [0, 5],
        [5, 6],
    ]
    .iter()
    .map(|e| e.to_vec())
    .collect();
    assert_eq!(check_loops(&graph, &gens(&graph, Field::Z2)), vec![3, 4]);
    // three triangles on one edge (not a surface): the Morse generators are kept
    let fan: Vec<Vec<u32>> = vec![vec![0, 1, 2], vec![0, 1, 3], vec![0, 1, 4], vec![2, 3, 5]];
    let h = gens(&fan, Field::Z2);
    assert_eq!(h.betti, vec![1, 1, 0]);
    assert_eq!(h.generators.iter().filter(|g| g.dim == 1).count(), 1);
}

/// The maximal ones among drawn vertex sets, vertices below `nv` (sorted, distinct).
fn maximal_cells(nv: usize, raw: Vec<BTreeSet<u32>>) -> Vec<Vec<u32>> {
    let mut cells: Vec<Vec<u32>> = raw
        .into_iter()
        .map(|s| {
            s.into_iter()
                .filter(|&v| (v as usize) < nv)
                .collect::<Vec<u32>>()
        })
        .filter(|s: &Vec<u32>| !s.is_empty())
        .collect();
    cells.sort();
    cells.dedup();
    let all = cells.clone();
    cells.retain(|c| {
        !all.iter()
            .any(|d| d != c && c.iter().all(|x| d.contains(x)))
    });
    cells
}

fn threads<T: Send>(n: usize, f: impl FnOnce() -> T + Send) -> T {
    rayon::ThreadPoolBuilder::new()
        .num_threads(n)
        .build()
        .unwrap()
        .install(f)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 500, rng_algorithm: proptest::test_runner::RngAlgorithm::ChaCha, ..ProptestConfig::default() })]
    #[test]
    fn random_complexes_match_brute_force(
        nv in 1usize..10,
        raw in proptest::collection::vec(proptest::collection::btree_set(0u32..10, 1..6), 0..9),
        perm_seed in 0u64..1000,
    ) {
        let cells = maximal_cells(nv, raw);
        // a vertex relabeling, so lower stars see many orders
        let mut perm: Vec<u32> = (0..nv as u32).collect();
        let mut s = perm_seed;
        for i in (1..nv).rev() {
            s = s.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            perm.swap(i, (s >> 33) as usize % (i + 1));
        }
        let cells: Vec<Vec<u32>> = cells.iter().map(|c| c.iter().map(|&v| perm[v as usize]).collect()).collect();
        let want = brute_betti_z2(nv, &cells);
        let typed: Vec<(CellKind, Vec<u32>)> = cells
            .iter()
            .map(|c| (CellKind::Simplex((c.len() - 1) as u8), c.clone()))
            .collect();
        let k = complex_n(nv, &typed);
        let h1 = threads(1, || run(&k, Field::Z2));
        let h3 = threads(3, || run(&k, Field::Z2));
        prop_assert_eq!(&h1.betti, &want);
        prop_assert_eq!(&h1, &h3);
        // alternating sum = Euler characteristic of the f-vector
        let f = f_vector(&cells);
        let mut chi: i64 = f.iter().enumerate().map(|(i, &x)| if i % 2 == 0 { x as i64 } else { -(x as i64) }).sum();
        let isolated = nv - cells.iter().flatten().collect::<BTreeSet<_>>().len();
        chi += isolated as i64;
        prop_assert_eq!(h1.euler_characteristic(), chi);
        // Q and Z ranks agree with each other; Z/3 has the same Euler characteristic
        let hq = run(&k, Field::Q);
        let hz = run(&k, Field::Z);
        prop_assert_eq!(&hq.betti, &hz.betti);
        prop_assert_eq!(hq.euler_characteristic(), chi);
        prop_assert_eq!(run(&k, Field::Zp(3)).euler_characteristic(), chi);
        // every vertex order gives the same Betti numbers (and torsion over Z)
        for order in [VertexOrder::FirstAppearance, VertexOrder::BreadthFirst] {
            let o = HomologyOptions { order, per_component: true, ..Default::default() };
            let h = homology(&VtIndex::new(&k), &o).unwrap();
            prop_assert_eq!(&h.betti, &want);
            // consuming the complex (cells renumbered in place) changes nothing
            prop_assert_eq!(&homology_owned(k.clone(), &o).unwrap(), &h);
            let comps = h.components.unwrap();
            prop_assert!(comps.windows(2).all(|w| w[0].first_vertex < w[1].first_vertex));
            let oz = HomologyOptions { order, field: Field::Z, ..Default::default() };
            let hz2 = homology(&VtIndex::new(&k), &oz).unwrap();
            prop_assert_eq!(&hz2.betti, &hz.betti);
            prop_assert_eq!(&hz2.torsion, &hz.torsion);
        }
    }
}

#[test]
fn betti_z2_matches_the_oracles() {
    let sets = common_data::small_datasets();
    if sets.is_empty() && !common_data::data_required() {
        eprintln!(
            "SKIPPED: no small datasets at {} (set STARPLEX_SHARED to the shared/ directory)",
            common_data::datasets_dir().display()
        );
        return;
    }
    let mut checked = 0;
    for (name, path, o) in sets.into_iter().chain(common_data::medium_datasets()) {
        let Some(want) = o.get("betti_z2").and_then(|b| b.as_array()) else {
            continue;
        };
        let want: Vec<u64> = want.iter().map(|x| x.as_u64().unwrap()).collect();
        let k = io::read(&path, &ReadOptions::default()).unwrap().complex;
        let got = starplex::algo::homology::betti_z2(&k).unwrap();
        assert_eq!(got, want, "{name}");
        if k.n_cells() < 100_000 {
            // the consumed complex (what the CLI runs) gives the same critical cells
            let o = HomologyOptions::default();
            let h = starplex::algo::homology::homology_indexed(&k, &o).unwrap();
            assert_eq!(homology_owned(k, &o).unwrap(), h, "{name}");
        }
        eprintln!("{name}: betti_z2 {got:?} (oracle)");
        checked += 1;
    }
    assert!(
        checked >= 9 || !common_data::data_required(),
        "checked {checked}"
    );
}

/// Larger surfaces (a torus and a Klein bottle of 6,000 triangles, every vertex order): the
/// same answer, critical cells included, for 1 and 2 threads, over Z/2 and Z/3 (this exercises
/// the coboundary paths of the top dimension on many lower stars).
#[test]
fn larger_surfaces_same_answer_for_1_and_2_threads() {
    for (flip, want2, want3) in [
        (false, vec![1, 2, 1], vec![1, 2, 1]),
        (true, vec![1, 2, 1], vec![1, 1, 0]),
    ] {
        let k = simplices(&grid_surface(60, 50, flip));
        for order in [
            VertexOrder::Input,
            VertexOrder::FirstAppearance,
            VertexOrder::BreadthFirst,
        ] {
            for field in [Field::Z2, Field::Zp(3)] {
                let o = HomologyOptions {
                    order,
                    field,
                    ..Default::default()
                };
                let h1 = threads(1, || homology(&VtIndex::new(&k), &o).unwrap());
                let h2 = threads(2, || homology(&VtIndex::new(&k), &o).unwrap());
                let want = if field == Field::Z2 { &want2 } else { &want3 };
                assert_eq!(&h1.betti, want, "flip {flip} {order:?} {field}");
                assert_eq!(h1, h2, "flip {flip} {order:?} {field}");
                // one block of triangles: the in-place renumbering of a consumed complex
                let ho = threads(2, || homology_owned(k.clone(), &o).unwrap());
                assert_eq!(h1, ho, "owned, flip {flip} {order:?} {field}");
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, rng_algorithm: proptest::test_runner::RngAlgorithm::ChaCha, ..ProptestConfig::default() })]
    /// Pure complexes (one block of simplices, vertices listed in any order): the paths that
    /// read the cells directly (`homology_indexed` in input order, `homology_owned` taking the
    /// block over, the renumbered copies) give exactly what the generic path gives (critical
    /// cells included) for every vertex order and 1 or 2 threads, and the Betti numbers of
    /// the dense computation.
    #[test]
    fn pure_complexes_same_answer_on_every_path(
        nv in 2usize..12,
        d in 1usize..4,
        raw in proptest::collection::vec(proptest::collection::vec(0u32..12, 4), 1..14),
    ) {
        // d-simplices with distinct vertices, kept in the drawn (unsorted) order
        let mut cells: Vec<Vec<u32>> = Vec::new();
        let mut seen: BTreeSet<Vec<u32>> = BTreeSet::new();
        for r in raw {
            let mut c: Vec<u32> = Vec::new();
            for v in r.into_iter().map(|v| v % nv as u32) {
                if !c.contains(&v) && c.len() < d + 1 {
                    c.push(v);
                }
            }
            let mut key = c.clone();
            key.sort_unstable();
            if c.len() == d + 1 && seen.insert(key) {
                cells.push(c);
            }
        }
        prop_assume!(!cells.is_empty());
        let want = brute_betti_z2(nv, &cells);
        let typed: Vec<(CellKind, Vec<u32>)> = cells
            .iter()
            .map(|c| (CellKind::Simplex(d as u8), c.clone()))
            .collect();
        let k = complex_n(nv, &typed);
        for order in [
            VertexOrder::Auto,
            VertexOrder::Input,
            VertexOrder::FirstAppearance,
            VertexOrder::BreadthFirst,
        ] {
            for field in [Field::Z2, Field::Zp(3)] {
                let o = HomologyOptions { order, field, per_component: true, ..Default::default() };
                let h = threads(1, || homology(&VtIndex::new(&k), &o).unwrap());
                if field == Field::Z2 {
                    prop_assert_eq!(&h.betti, &want);
                }
                let hi = threads(2, || starplex::algo::homology::homology_indexed(&k, &o).unwrap());
                prop_assert_eq!(&hi, &h);
                let ho = threads(2, || homology_owned(k.clone(), &o).unwrap());
                prop_assert_eq!(&ho, &h);
            }
        }
    }
}

/// Homology of `k` through every structure that answers `TopCells` + `VertexStar`: Betti
/// numbers, torsion and the per-component summaries equal those of the vertex → cells index
/// (the critical cells may differ: a structure may number its top cells in its own order,
/// which the vertex orders follow).
fn same_homology_on_every_structure(name: &str, k: &IndexedComplex, fields: &[Field]) {
    use starplex::hasse::HasseQueries;
    use starplex::limits::Limits;
    use starplex::stellar::{StellarOptions, StellarTree};
    use starplex::tds::iastar::IaStar;
    use starplex::tds::ig::IncidenceGraph;
    use starplex::tds::is::Is;
    use starplex::tds::simplex_tree::{SimplexTree, SimplexTreeOptions};
    let lim = Limits {
        stored_simplices: 1 << 24,
        ..Limits::default()
    };
    for &field in fields {
        let o = HomologyOptions {
            field,
            per_component: true,
            ..Default::default()
        };
        let want = homology(&VtIndex::new(k), &o).unwrap();
        let check = |s: &str, h: Homology| {
            assert_eq!(h.betti, want.betti, "{name} {field} {s}");
            assert_eq!(h.torsion, want.torsion, "{name} {field} {s}");
            assert_eq!(h.components, want.components, "{name} {field} {s}");
        };
        check("ia*", homology(&IaStar::new(k).unwrap(), &o).unwrap());
        check(
            "ig",
            homology(&IncidenceGraph::new(k, &lim).unwrap(), &o).unwrap(),
        );
        for kv in [Some(1), Some(0)] {
            let t = StellarTree::build(
                k,
                &StellarOptions {
                    kv,
                    ..Default::default()
                },
            )
            .unwrap();
            check(&format!("stellar kv={kv:?}"), homology(&t, &o).unwrap());
            check(
                &format!("stellar-ia* kv={kv:?}"),
                homology(&t.iastar(), &o).unwrap(),
            );
        }
        // the simplicial-only structures
        if k.blocks().iter().all(|b| b.kind.is_simplex()) {
            check(
                "hasse",
                homology(&HasseQueries::new(k, &lim).unwrap(), &o).unwrap(),
            );
            check("is", homology(&Is::new(k, &lim).unwrap(), &o).unwrap());
            let st = SimplexTree::new(k, &SimplexTreeOptions::default()).unwrap();
            check("simplex tree", homology(&st, &o).unwrap());
        }
    }
}

#[test]
fn every_structure_gives_the_same_homology_on_the_fixtures() {
    let all = [Field::Z2, Field::Zp(3), Field::Z];
    same_homology_on_every_structure("torus", &simplices(&grid_surface(3, 3, false)), &all);
    same_homology_on_every_structure("klein", &simplices(&grid_surface(4, 4, true)), &all);
    let rp2: Vec<Vec<u32>> = RP2.iter().map(|t| t.to_vec()).collect();
    same_homology_on_every_structure("rp2", &simplices(&rp2), &all);
    let mut a = tetra_boundary(0);
    a.extend(tetra_boundary(3));
    same_homology_on_every_structure("two spheres on a vertex", &simplices(&a), &all);
    let book = vec![
        (CellKind::Simplex(2), vec![0, 1, 2]),
        (CellKind::Simplex(2), vec![0, 1, 3]),
        (CellKind::Simplex(2), vec![0, 1, 4]),
        (CellKind::Simplex(1), vec![4, 5]),
    ];
    same_homology_on_every_structure("book", &complex_n(7, &book), &all);
    // CP cells: a quad torus and a quad Klein bottle
    same_homology_on_every_structure("quad torus", &complex(&quad_grid(4, 3, false)), &all);
    same_homology_on_every_structure("quad klein", &complex(&quad_grid(4, 4, true)), &all);
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 100, rng_algorithm: proptest::test_runner::RngAlgorithm::ChaCha, ..ProptestConfig::default() })]
    /// Random simplicial complexes (any dimension, non-pure, isolated vertices): the same
    /// homology from every structure, over Z/2 and Z.
    #[test]
    fn every_structure_gives_the_same_homology_on_random_complexes(
        nv in 1usize..9,
        raw in proptest::collection::vec(proptest::collection::btree_set(0u32..9, 1..5), 1..8),
    ) {
        let cells = maximal_cells(nv, raw);
        prop_assume!(!cells.is_empty());
        let typed: Vec<(CellKind, Vec<u32>)> = cells
            .iter()
            .map(|c| (CellKind::Simplex((c.len() - 1) as u8), c.clone()))
            .collect();
        let k = complex_n(nv, &typed);
        same_homology_on_every_structure("random", &k, &[Field::Z2, Field::Z]);
    }
}

/// The homology of `cells` (maximal simplices over `nv` vertices, each sorted) computed as the
/// distributed scheme does: the subcomplex `K` induced by the vertices in `inside` reduced to
/// its Morse complex, the faces with a vertex outside glued on with `∂' = π ∘ ∂`.
fn glued_homology(
    nv: usize,
    cells: &[Vec<u32>],
    inside: &[bool],
    field: Field,
    order: VertexOrder,
    raw_parts: bool,
) -> (Vec<u64>, Vec<Vec<u128>>) {
    // K: the inside part of every cell (maximal ones), vertices renumbered in increasing order
    let mut new_id = vec![u32::MAX; nv];
    let mut n_in = 0u32;
    for v in 0..nv {
        if inside[v] {
            new_id[v] = n_in;
            n_in += 1;
        }
    }
    let opts = HomologyOptions {
        field,
        order,
        ..Default::default()
    };
    let raw: Vec<BTreeSet<u32>> = cells
        .iter()
        .map(|c| {
            c.iter()
                .filter(|&&v| inside[v as usize])
                .map(|&v| new_id[v as usize])
                .collect()
        })
        .collect();
    // the inside parts as they come (some are faces of others, some repeat) when `raw_parts`,
    // as the distributed homology hands them over, else the maximal ones
    let k = if raw_parts {
        let mut blocks: Vec<(CellKind, Buf<u32>)> = Vec::new();
        for c in raw.iter().filter(|c| !c.is_empty()) {
            let kind = CellKind::Simplex((c.len() - 1) as u8);
            blocks.push((kind, Buf::Owned(c.iter().copied().collect())));
        }
        IndexedComplex::from_parts(1, Buf::Owned(vec![0.0; n_in as usize]), blocks).unwrap()
    } else {
        let k_cells = maximal_cells(n_in as usize, raw);
        let typed: Vec<(CellKind, Vec<u32>)> = k_cells
            .iter()
            .map(|c| (CellKind::Simplex((c.len() - 1) as u8), c.clone()))
            .collect();
        complex_n(n_in as usize, &typed)
    };
    let m = if raw_parts {
        MorseComplex::from_complex(k, &opts).unwrap()
    } else {
        MorseComplex::new(&k, &opts).unwrap()
    };

    let crit = m.n_critical();
    // J: every face with a vertex outside, by dimension (sorted)
    let mut j: BTreeSet<Vec<u32>> = BTreeSet::new();
    for c in cells {
        for mask in 1u32..(1 << c.len()) {
            let f: Vec<u32> = (0..c.len())
                .filter(|&i| mask >> i & 1 == 1)
                .map(|i| c[i])
                .collect();
            if f.iter().any(|&v| !inside[v as usize]) {
                j.insert(f);
            }
        }
    }
    for v in 0..nv as u32 {
        if !inside[v as usize] {
            j.insert(vec![v]); // isolated vertices included
        }
    }
    let top = cells
        .iter()
        .map(|c| c.len())
        .max()
        .unwrap_or(1)
        .max(crit.len());
    let mut by_dim: Vec<Vec<Vec<u32>>> = vec![Vec::new(); top];
    for f in j {
        by_dim[f.len() - 1].push(f);
    }
    let n: Vec<usize> = (0..top)
        .map(|d| crit.get(d).copied().unwrap_or(0) + by_dim[d].len())
        .collect();
    let mut cols: Vec<Vec<Vec<(u32, i64)>>> = vec![Vec::new(); top];
    for d in 1..top {
        cols[d] = m.boundaries(d).unwrap();
        cols[d].resize(crit.get(d).copied().unwrap_or(0), Vec::new());
        let off = crit.get(d - 1).copied().unwrap_or(0) as u32;
        for f in &by_dim[d] {
            let mut col = Vec::new();
            for i in 0..f.len() {
                let sign = if i % 2 == 0 { 1 } else { -1 };
                let mut g = f.clone();
                g.remove(i);
                if let Ok(at) = by_dim[d - 1].binary_search(&g) {
                    col.push((off + at as u32, sign));
                } else {
                    let local: Vec<u32> = g.iter().map(|&v| new_id[v as usize]).collect();
                    for (r, c) in m.project(&local, local.len()).unwrap().remove(0) {
                        col.push((r, c * sign));
                    }
                }
            }
            cols[d].push(col);
        }
    }
    chain_complex_homology(&n, cols, field, u64::MAX).unwrap()
}

#[test]
fn gluing_a_morse_complex_keeps_the_torsion() {
    // RP^2 with its vertices relabeled (5 - v), so that a new vertex order reorients cells
    let rp2: Vec<Vec<u32>> = RP2
        .iter()
        .map(|t| {
            let mut t: Vec<u32> = t.iter().map(|&v| 5 - v).collect();
            t.sort_unstable();
            t
        })
        .collect();
    for mask in 0u32..64 {
        let inside: Vec<bool> = (0..6).map(|v| mask >> v & 1 == 1).collect();
        for order in [
            VertexOrder::Auto,
            VertexOrder::FirstAppearance,
            VertexOrder::BreadthFirst,
        ] {
            let z = glued_homology(6, &rp2, &inside, Field::Z, order, mask % 2 == 0);
            let want = (vec![1, 0, 0], vec![vec![], vec![2], vec![]]);
            assert_eq!(z, want, "inside {mask:06b} {order:?}");
            let z2 = glued_homology(6, &rp2, &inside, Field::Z2, order, mask % 3 == 0);
            assert_eq!(z2.0, vec![1, 1, 1]);
            let z3 = glued_homology(6, &rp2, &inside, Field::Zp(3), order, true);
            assert_eq!(z3.0, vec![1, 0, 0]);
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, rng_algorithm: proptest::test_runner::RngAlgorithm::ChaCha, ..ProptestConfig::default() })]
    /// `M(K) ⊕ C(L \ K)` with `∂' = π ∘ ∂` has the homology of `L`, for any induced `K`,
    /// field and vertex order (the distributed homology's scheme).
    #[test]
    fn gluing_a_morse_complex_keeps_the_homology(
        nv in 1usize..10,
        raw in proptest::collection::vec(proptest::collection::btree_set(0u32..10, 1..6), 0..9),
        inside_mask in 0u32..1024,
        order in 0usize..3,
        raw_parts in any::<bool>(),
    ) {
        let cells = maximal_cells(nv, raw);
        let inside: Vec<bool> = (0..nv).map(|v| inside_mask >> v & 1 == 1).collect();
        let typed: Vec<(CellKind, Vec<u32>)> = cells
            .iter()
            .map(|c| (CellKind::Simplex((c.len() - 1) as u8), c.clone()))
            .collect();
        let l = complex_n(nv, &typed);
        let order = [VertexOrder::Auto, VertexOrder::FirstAppearance, VertexOrder::BreadthFirst][order];
        for field in [Field::Z2, Field::Zp(3), Field::Q, Field::Z] {
            let want = run(&l, field);
            let (b, t) = glued_homology(nv, &cells, &inside, field, order, raw_parts);
            let mut wb = want.betti.clone();
            wb.resize(b.len().max(wb.len()), 0);
            prop_assert_eq!(&b, &wb, "field {}", field);
            if field == Field::Z {
                let mut wt = want.torsion.clone();
                wt.resize(t.len().max(wt.len()), Vec::new());
                prop_assert_eq!(&t, &wt);
            }
        }
    }
}
