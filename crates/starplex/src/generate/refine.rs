//! The Stellar paper's CP refinements, as the datasets' generator builds them
//! (`shared/datasets/gen.py`, `tri_to_quads` and `tet_to_hexes`), vertex order and coordinates
//! included: each triangle becomes 3 quads (edge midpoints and its centroid), each tetrahedron 4
//! hexahedra (edge midpoints, face centroids and its centroid, VTK hexahedron order).
//!
//! New vertices follow the input's: edge midpoints in the order of their sorted endpoint pairs,
//! then (tetrahedra) face centroids in the order of their sorted vertex triples, then one
//! centroid per cell in cell order.
//!
//! ```
//! use starplex::cell::CellKind;
//! use starplex::complex::IndexedComplex;
//! use starplex::generate::refine::{tets_to_hexes, triangles_to_quads};
//! let tri = IndexedComplex::from_parts(2, vec![0., 0., 1., 0., 0., 1.].into(),
//!                                      vec![(CellKind::Simplex(2), vec![0, 1, 2].into())]).unwrap();
//! let q = triangles_to_quads(&tri).unwrap();
//! assert_eq!((q.n_vertices(), q.n_cells()), (7, 3));
//! let tet = IndexedComplex::from_parts(3, vec![0., 0., 0., 1., 0., 0., 0., 1., 0., 0., 0., 1.].into(),
//!                                      vec![(CellKind::Simplex(3), vec![0, 1, 2, 3].into())]).unwrap();
//! let h = tets_to_hexes(&tet).unwrap();
//! assert_eq!((h.n_vertices(), h.n_cells()), (15, 4));
//! ```
use crate::cell::CellKind;
use crate::complex::{ComplexError, IndexedComplex};

/// Why a refinement cannot run.
///
/// ```
/// use starplex::generate::refine::RefineError;
/// assert_eq!(RefineError::WrongKind { want: "triangles", cell: 3 }.to_string(),
///            "cell 3 is not one of the triangles this refinement takes");
/// ```
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum RefineError {
    /// A cell of another kind.
    #[error("cell {cell} is not one of the {want} this refinement takes")]
    WrongKind {
        /// `triangles` or `tetrahedra`.
        want: &'static str,
        /// The first other cell.
        cell: u64,
    },
    /// The output does not fit (32-bit ids) or is invalid.
    #[error(transparent)]
    Complex(#[from] ComplexError),
}

/// The input's cells of `kind` as one flat array, or the first other cell.
fn only(k: &IndexedComplex, kind: CellKind, want: &'static str) -> Result<Vec<u32>, RefineError> {
    let mut out = Vec::with_capacity(k.n_refs());
    for b in k.blocks() {
        if b.kind != kind {
            return Err(RefineError::WrongKind {
                want,
                cell: b.first as u64,
            });
        }
        out.extend_from_slice(&b.vertices);
    }
    Ok(out)
}

/// Sorted distinct keys and, per (cell, local key), the key's rank (numpy's `unique` with
/// `return_inverse`).
fn unique<const N: usize>(keys: Vec<[u32; N]>) -> (Vec<[u32; N]>, Vec<u32>) {
    let mut u = keys.clone();
    u.sort_unstable();
    u.dedup();
    let inv = keys
        .iter()
        .map(|k| u.binary_search(k).expect("listed") as u32)
        .collect();
    (u, inv)
}

fn sorted<const N: usize>(mut a: [u32; N]) -> [u32; N] {
    a.sort_unstable();
    a
}

fn check_size(n: u128, what: &'static str) -> Result<(), ComplexError> {
    if n >= u32::MAX as u128 {
        return Err(ComplexError::TooLarge(crate::limits::TooLarge::ids(
            what, n,
        )));
    }
    Ok(())
}

/// Each triangle `abc` becomes the quads `a m_ab g m_ca`, `b m_bc g m_ab`, `c m_ca g m_bc`
/// (`g` its centroid).
///
/// ```
/// # use starplex::cell::CellKind;
/// # use starplex::complex::IndexedComplex;
/// # use starplex::generate::refine::triangles_to_quads;
/// let two = IndexedComplex::from_parts(2, vec![0., 0., 1., 0., 0., 1., 1., 1.].into(),
///     vec![(CellKind::Simplex(2), vec![0, 1, 2, 1, 3, 2].into())]).unwrap();
/// let q = triangles_to_quads(&two).unwrap();
/// assert_eq!(q.n_vertices(), 4 + 5 + 2); // 5 distinct edges, 2 centroids
/// assert_eq!(q.cell(starplex::ids::CellId(0)).vertices, &[0, 4, 9, 5]);
/// ```
///
/// # Errors
/// A cell that is not a triangle; an output beyond 32-bit ids.
pub fn triangles_to_quads(k: &IndexedComplex) -> Result<IndexedComplex, RefineError> {
    let f = only(k, CellKind::Simplex(2), "triangles")?;
    let d = k.ambient_dim();
    let v = k.coords();
    let n = k.n_vertices();
    let m = f.len() / 3;
    check_size(n as u128 + 4 * m as u128, "vertices")?;
    check_size(3 * m as u128, "cells")?;
    let pairs = [(0, 1), (1, 2), (2, 0)];
    let keys: Vec<[u32; 2]> = f
        .chunks_exact(3)
        .flat_map(|c| pairs.map(|(i, j)| sorted([c[i], c[j]])))
        .collect();
    let (u, inv) = unique(keys);
    let mut coords = v.to_vec();
    for e in &u {
        let (a, b) = (e[0] as usize, e[1] as usize);
        coords.extend((0..d).map(|x| 0.5 * (v[a * d + x] + v[b * d + x])));
    }
    for c in f.chunks_exact(3) {
        let p = |i: usize| &v[c[i] as usize * d..(c[i] as usize + 1) * d];
        coords.extend((0..d).map(|x| (p(0)[x] + p(1)[x] + p(2)[x]) / 3.0));
    }
    let g0 = (n + u.len()) as u32;
    let mut q = Vec::with_capacity(12 * m);
    for (t, c) in f.chunks_exact(3).enumerate() {
        let mm = |i: usize| n as u32 + inv[3 * t + i];
        let (mab, mbc, mca) = (mm(0), mm(1), mm(2));
        let g = g0 + t as u32;
        q.extend_from_slice(&[c[0], mab, g, mca, c[1], mbc, g, mab, c[2], mca, g, mbc]);
    }
    Ok(IndexedComplex::from_parts(
        d,
        coords.into(),
        vec![(CellKind::Quad, q.into())],
    )?)
}

/// Each tetrahedron becomes 4 hexahedra, one per corner `a` (with the others `b < c < d` in
/// local order): `a, m_ab, f_abc, m_ac, m_ad, f_abd, g, f_acd` (VTK order).
///
/// ```
/// # use starplex::cell::CellKind;
/// # use starplex::complex::IndexedComplex;
/// # use starplex::generate::refine::tets_to_hexes;
/// use starplex::algo::info::{info, InfoOptions};
/// let tet = IndexedComplex::from_parts(3, vec![0., 0., 0., 1., 0., 0., 0., 1., 0., 0., 0., 1.].into(),
///                                      vec![(CellKind::Simplex(3), vec![0, 1, 2, 3].into())]).unwrap();
/// let h = tets_to_hexes(&tet).unwrap();
/// assert_eq!(info(&h, &InfoOptions::default()).euler_characteristic, Some(1)); // still a ball
/// ```
///
/// # Errors
/// A cell that is not a tetrahedron; an output beyond 32-bit ids.
pub fn tets_to_hexes(k: &IndexedComplex) -> Result<IndexedComplex, RefineError> {
    let t = only(k, CellKind::Simplex(3), "tetrahedra")?;
    let d = k.ambient_dim();
    let v = k.coords();
    let n = k.n_vertices();
    let m = t.len() / 4;
    check_size(n as u128 + 11 * m as u128, "vertices")?;
    check_size(4 * m as u128, "cells")?;
    let pairs = [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)];
    let triples = [(0, 1, 2), (0, 1, 3), (0, 2, 3), (1, 2, 3)];
    let ekeys: Vec<[u32; 2]> = t
        .chunks_exact(4)
        .flat_map(|c| pairs.map(|(i, j)| sorted([c[i], c[j]])))
        .collect();
    let fkeys: Vec<[u32; 3]> = t
        .chunks_exact(4)
        .flat_map(|c| triples.map(|(i, j, l)| sorted([c[i], c[j], c[l]])))
        .collect();
    let (ue, einv) = unique(ekeys);
    let (uf, finv) = unique(fkeys);
    let mut coords = v.to_vec();
    let p = |i: u32| &v[i as usize * d..(i as usize + 1) * d];
    for e in &ue {
        coords.extend((0..d).map(|x| 0.5 * (p(e[0])[x] + p(e[1])[x])));
    }
    for f in &uf {
        coords.extend((0..d).map(|x| (p(f[0])[x] + p(f[1])[x] + p(f[2])[x]) / 3.0));
    }
    for c in t.chunks_exact(4) {
        coords.extend((0..d).map(|x| (p(c[0])[x] + p(c[1])[x] + p(c[2])[x] + p(c[3])[x]) / 4.0));
    }
    let n1 = (n + ue.len()) as u32;
    let n2 = n1 + uf.len() as u32;
    let eidx = |i: usize, j: usize| {
        pairs
            .iter()
            .position(|&q| q == (i.min(j), i.max(j)))
            .unwrap_or(0)
    };
    let fidx = |mut a: [usize; 3]| {
        a.sort_unstable();
        triples
            .iter()
            .position(|&q| q == (a[0], a[1], a[2]))
            .unwrap_or(0)
    };
    let mut h = Vec::with_capacity(32 * m);
    for (ti, c) in t.chunks_exact(4).enumerate() {
        let e = |i: usize, j: usize| n as u32 + einv[6 * ti + eidx(i, j)];
        let f = |i: usize, j: usize, l: usize| n1 + finv[4 * ti + fidx([i, j, l])];
        let g = n2 + ti as u32;
        for (a, &corner) in c.iter().enumerate() {
            let o: Vec<usize> = (0..4).filter(|&x| x != a).collect();
            let (b, cc, dd) = (o[0], o[1], o[2]);
            h.extend_from_slice(&[
                corner,
                e(a, b),
                f(a, b, cc),
                e(a, cc),
                e(a, dd),
                f(a, b, dd),
                g,
                f(a, cc, dd),
            ]);
        }
    }
    Ok(IndexedComplex::from_parts(
        d,
        coords.into(),
        vec![(CellKind::Hex, h.into())],
    )?)
}

/// Midpoint 1-to-4 subdivision of a triangle mesh, `levels` times (as the datasets'
/// `subdivide_1to4`): triangle `abc` becomes `a m_ab m_ca`, `m_ab b m_bc`, `m_ca m_bc c`,
/// `m_ab m_bc m_ca`, children grouped by kind (all first corners, then all second ones, ...),
/// midpoints appended in the order of their sorted endpoint pairs.
///
/// ```
/// # use starplex::cell::CellKind;
/// # use starplex::complex::IndexedComplex;
/// use starplex::generate::refine::subdivide_triangles;
/// let tri = IndexedComplex::from_parts(2, vec![0., 0., 1., 0., 0., 1.].into(),
///                                      vec![(CellKind::Simplex(2), vec![0, 1, 2].into())]).unwrap();
/// let s = subdivide_triangles(&tri, 2).unwrap();
/// assert_eq!((s.n_vertices(), s.n_cells()), (15, 16));
/// ```
///
/// # Errors
/// A cell that is not a triangle; an output beyond 32-bit ids.
pub fn subdivide_triangles(
    k: &IndexedComplex,
    levels: usize,
) -> Result<IndexedComplex, RefineError> {
    let mut f = only(k, CellKind::Simplex(2), "triangles")?;
    let d = k.ambient_dim();
    let mut coords = k.coords().to_vec();
    for _ in 0..levels {
        let n = coords.len() / d;
        let m = f.len() / 3;
        check_size(n as u128 + 3 * m as u128, "vertices")?;
        check_size(4 * m as u128, "cells")?;
        let pairs = [(0, 1), (1, 2), (2, 0)];
        let keys: Vec<[u32; 2]> = f
            .chunks_exact(3)
            .flat_map(|c| pairs.map(|(i, j)| sorted([c[i], c[j]])))
            .collect();
        let (u, inv) = unique(keys);
        for e in &u {
            let (a, b) = (e[0] as usize, e[1] as usize);
            for x in 0..d {
                let v = 0.5 * (coords[a * d + x] + coords[b * d + x]);
                coords.push(v);
            }
        }
        let mid = |t: usize, i: usize| n as u32 + inv[3 * t + i];
        let mut g = Vec::with_capacity(12 * m);
        for child in 0..4 {
            for (t, c) in f.chunks_exact(3).enumerate() {
                let (mab, mbc, mca) = (mid(t, 0), mid(t, 1), mid(t, 2));
                g.extend_from_slice(&match child {
                    0 => [c[0], mab, mca],
                    1 => [mab, c[1], mbc],
                    2 => [mca, mbc, c[2]],
                    _ => [mab, mbc, mca],
                });
            }
        }
        f = g;
    }
    Ok(IndexedComplex::from_parts(
        d,
        coords.into(),
        vec![(CellKind::Simplex(2), f.into())],
    )?)
}
