//! `info`: the summary of a complex (counts, f-vector, Euler characteristic, boundary, components)
//! with the field names of the dataset oracles.
//!
//! Distinct k-faces are counted without a hash set: a face is counted by its *owner*, the
//! smallest-id top cell containing it, found by scanning the id-sorted vertex→cells row of the
//! face's least-used vertex. Memory is the vertex→cells relation only; the work runs in parallel
//! over cells and gives the same result for any thread count.
//!
//! ```
//! use starplex::complex::{ComplexBuilder, BuildOptions};
//! use starplex::cell::CellKind;
//! use starplex::algo::info::{info, InfoOptions};
//! // two triangles sharing an edge, plus an isolated vertex
//! let mut b = ComplexBuilder::new(2).unwrap();
//! for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0], [5.0, 5.0]] { b.push_vertex(&p).unwrap(); }
//! b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
//! b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
//! let k = b.build(&BuildOptions::default()).unwrap().0;
//! let s = info(&k, &InfoOptions::default());
//! assert_eq!(s.f_vector, Some(vec![5, 5, 2]));
//! assert_eq!(s.euler_characteristic, Some(2));
//! assert_eq!(s.n_boundary_faces, Some(4));
//! assert_eq!(s.n_connected_components, 2);
//! assert_eq!(s.n_isolated_vertices, 1);
//! assert!(!s.pure);
//! ```
use std::collections::BTreeMap;
use std::sync::atomic::{AtomicU64, Ordering};

use rayon::prelude::*;

use crate::algo::unionfind::UnionFind;
use crate::complex::IndexedComplex;
use crate::csr::Csr;
use crate::limits::Limits;

/// Options of [`info`].
///
/// ```
/// use starplex::algo::info::{info, InfoOptions};
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// # let mut b = ComplexBuilder::new(1).unwrap();
/// # for x in 0..4 { b.push_vertex(&[x as f64]).unwrap(); }
/// # b.push_cell(CellKind::Simplex(3), &[0, 1, 2, 3]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// // k: the tetrahedron 0-1-2-3
/// // A tiny budget skips the f-vector and reports the estimate instead.
/// let limits = starplex::limits::Limits { info_faces: 5, ..Default::default() };
/// let s = info(&k, &InfoOptions { limits, ..Default::default() });
/// assert_eq!(s.f_vector, None);
/// assert_eq!(s.f_vector_estimate, Some(10)); // 6 edges + 4 triangles
/// assert_eq!(info(&k, &InfoOptions::default()).f_vector, Some(vec![4, 6, 4, 1]));
/// ```
#[derive(Clone, Default)]
pub struct InfoOptions {
    /// `limits.info_faces`: the largest number of (cell, face) pairs the f-vector pass may
    /// visit; above it the f-vector (and Euler characteristic, boundary counts) are skipped and
    /// an estimate is reported.
    pub limits: Limits,
    /// Called with the number of cells just processed (for progress bars).
    pub progress: Option<std::sync::Arc<dyn Fn(u64) + Send + Sync>>,
    /// When set, the face counts (f-vector entries of dimension >= 1, boundary and shared
    /// faces, faces by kind) count only the faces whose smallest vertex is in this set: the
    /// ownership rule of a distributed count (`starplex-mpi`), where each rank holds the full
    /// star of the vertices it owns. `None` (the default) counts every face.
    ///
    /// ```
    /// use std::sync::Arc;
    /// use fixedbitset::FixedBitSet;
    /// use starplex::algo::info::{info, InfoOptions};
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// # let mut b = ComplexBuilder::new(2).unwrap();
    /// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
    /// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
    /// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// // k: the triangles 0-1-2 and 1-3-2; vertex 0 owns 2 edges and 1 triangle, the others the rest
    /// let part = |vs: &[usize]| {
    ///     let mut m = FixedBitSet::with_capacity(4);
    ///     vs.iter().for_each(|&v| m.insert(v));
    ///     info(&k, &InfoOptions { owned_vertices: Some(Arc::new(m)), ..Default::default() })
    /// };
    /// let (a, b) = (part(&[0]), part(&[1, 2, 3]));
    /// assert_eq!((a.f_vector.unwrap(), b.f_vector.unwrap()), (vec![4, 2, 1], vec![4, 3, 1]));
    /// assert_eq!(a.n_boundary_faces.unwrap() + b.n_boundary_faces.unwrap(), 4);
    /// ```
    pub owned_vertices: Option<std::sync::Arc<fixedbitset::FixedBitSet>>,
}

impl std::fmt::Debug for InfoOptions {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("InfoOptions")
            .field("limits", &self.limits)
            .field(
                "owned_vertices",
                &self.owned_vertices.as_ref().map(|m| m.count_ones(..)),
            )
            .finish()
    }
}

/// The summary of a complex. Field names match the oracle JSON files.
///
/// ```
/// use starplex::algo::info::{info, InfoOptions};
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// # let mut b = ComplexBuilder::new(1).unwrap();
/// # for x in 0..4 { b.push_vertex(&[x as f64]).unwrap(); }
/// # b.push_cell(CellKind::Simplex(3), &[0, 1, 2, 3]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// // k: the tetrahedron 0-1-2-3
/// let s = info(&k, &InfoOptions::default());
/// assert_eq!((s.n_vertices, s.dim, s.n_top_cells), (4, 3, 1));
/// assert_eq!(s.top_cells.get("tet"), Some(&1));
/// assert_eq!(s.bbox, Some((vec![0.0], vec![3.0])));
/// assert!(s.pure);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Info {
    /// Number of vertices.
    pub n_vertices: u64,
    /// Vertices in no top cell.
    pub n_isolated_vertices: u64,
    /// Coordinates per vertex.
    pub ambient_dim: u64,
    /// Largest top-cell dimension (-1 for an empty complex).
    pub dim: i64,
    /// All top cells of one dimension and no isolated vertex.
    pub pure: bool,
    /// Top cells by type name (`tri`, `quad`, `simplex_5`, ...).
    pub top_cells: BTreeMap<String, u64>,
    /// Number of top cells.
    pub n_top_cells: u64,
    /// `[min, max]` corners, `None` without vertices.
    pub bbox: Option<(Vec<f64>, Vec<f64>)>,
    /// Distinct k-cells for k = 0..=dim; `None` when over the budget.
    pub f_vector: Option<Vec<u64>>,
    /// Upper bound of the (cell, face) pairs to visit, when the f-vector was skipped.
    pub f_vector_estimate: Option<u128>,
    /// Alternating sum of the f-vector.
    pub euler_characteristic: Option<i64>,
    /// (d-1)-faces in exactly one top d-cell (`None` when the top cells are not all of one
    /// dimension, or the f-vector was skipped).
    pub n_boundary_faces: Option<u64>,
    /// (d-1)-faces in more than two top d-cells.
    pub n_faces_shared_by_more_than_2_top_cells: Option<u64>,
    /// 2-faces by kind for 3-dimensional CP complexes (`tri`, `quad`).
    pub faces_by_type: Option<BTreeMap<String, u64>>,
    /// Connected components (isolated vertices count).
    pub n_connected_components: u64,
}

/// Computes the summary of `k`.
///
/// ```
/// use starplex::algo::info::{info, InfoOptions};
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// // k: the triangles 0-1-2 and 1-3-2, sharing the edge 1-2
/// let s = info(&k, &InfoOptions::default());
/// assert_eq!(s.f_vector, Some(vec![4, 5, 2]));
/// assert_eq!(s.euler_characteristic, Some(1));
/// assert_eq!(s.n_boundary_faces, Some(4));
/// assert_eq!(s.n_faces_shared_by_more_than_2_top_cells, Some(0));
/// ```
pub fn info(k: &IndexedComplex, opts: &InfoOptions) -> Info {
    let nv = k.n_vertices();
    let n_isolated = k.n_isolated_vertices() as u64;
    let dims: std::collections::BTreeSet<usize> = k.blocks().iter().map(|b| b.kind.dim()).collect();
    let dim = k.dim().map_or(-1, |d| d as i64);
    let pure = dims.len() == 1 && n_isolated == 0;
    let mut top_cells = BTreeMap::new();
    for b in k.blocks() {
        *top_cells.entry(b.kind.type_name()).or_insert(0) += b.len() as u64;
    }
    let bbox = (nv > 0).then(|| {
        let d = k.ambient_dim();
        let mut lo = vec![f64::INFINITY; d];
        let mut hi = vec![f64::NEG_INFINITY; d];
        for p in k.coords().chunks_exact(d) {
            for i in 0..d {
                lo[i] = lo[i].min(p[i]);
                hi[i] = hi[i].max(p[i]);
            }
        }
        (lo, hi)
    });
    let n_connected_components = components(k) as u64;

    let mut out = Info {
        n_vertices: nv as u64,
        n_isolated_vertices: n_isolated,
        ambient_dim: k.ambient_dim() as u64,
        dim,
        pure,
        top_cells,
        n_top_cells: k.n_cells() as u64,
        bbox,
        f_vector: None,
        f_vector_estimate: None,
        euler_characteristic: None,
        n_boundary_faces: None,
        n_faces_shared_by_more_than_2_top_cells: None,
        faces_by_type: None,
        n_connected_components,
    };
    if dim < 0 {
        out.f_vector = Some(vec![]);
        out.euler_characteristic = Some(0);
        return out;
    }
    let estimate = face_visits(k);
    if estimate > opts.limits.info_faces {
        out.f_vector_estimate = Some(estimate);
        return out;
    }
    let counts = count_faces(k, opts);
    apply_face_counts(&mut out, &counts, dims.len() == 1, k.is_simplicial());
    out
}

/// Sets what follows from the face counts in `out` (whose `n_vertices` and `dim` are set): the
/// f-vector (`f[0]` is `n_vertices`), the Euler characteristic, the boundary and shared face
/// counts when every top cell has one dimension (`single_dim`), and the 2-faces by kind for a
/// 3-dimensional complex that is not `simplicial`. [`info`] ends with it; `starplex-mpi` calls it
/// with the counts summed over ranks.
///
/// ```
/// use starplex::algo::info::{apply_face_counts, info, FaceCounts, InfoOptions};
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// let mut s = info(&k, &InfoOptions::default());
/// let counts = FaceCounts { per_dim: vec![0, 3, 1], boundary: 3, ..Default::default() };
/// apply_face_counts(&mut s, &counts, true, true);
/// assert_eq!((s.f_vector, s.euler_characteristic), (Some(vec![3, 3, 1]), Some(1)));
/// ```
pub fn apply_face_counts(out: &mut Info, counts: &FaceCounts, single_dim: bool, simplicial: bool) {
    let dim = out.dim;
    let mut f = vec![0u64; dim.max(0) as usize + 1];
    f[0] = out.n_vertices;
    for (i, x) in counts.per_dim.iter().enumerate().skip(1) {
        if i < f.len() {
            f[i] = *x;
        }
    }
    out.euler_characteristic = Some(
        f.iter()
            .enumerate()
            .map(|(i, &x)| if i % 2 == 0 { x as i64 } else { -(x as i64) })
            .sum(),
    );
    if single_dim && dim >= 1 {
        out.n_boundary_faces = Some(counts.boundary);
        out.n_faces_shared_by_more_than_2_top_cells = Some(counts.shared_more_than_2);
    }
    if dim == 3 && !simplicial {
        let mut m = BTreeMap::new();
        m.insert("tri".to_string(), counts.tri_faces);
        m.insert("quad".to_string(), counts.quad_faces);
        out.faces_by_type = Some(m);
    }
    out.f_vector = Some(f);
}

/// Upper bound of (cell, proper face of dimension >= 1) pairs: the work of the f-vector pass.
///
/// ```
/// use starplex::algo::info::face_visits;
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// // k: the triangles 0-1-2 and 1-3-2, sharing the edge 1-2
/// // Each triangle has 3 edges (faces of dimension >= 1 below its own dimension).
/// assert_eq!(face_visits(&k), 2 * 3);
/// ```
pub fn face_visits(k: &IndexedComplex) -> u128 {
    face_visits_of(k.blocks().iter().map(|b| (b.kind, b.len() as u64)))
}

/// [`face_visits`] from the cell kinds and counts alone (a `.spb` header's blocks).
///
/// ```
/// use starplex::algo::info::face_visits_of;
/// use starplex::cell::CellKind;
/// // a tetrahedron has 6 edges and 4 triangles
/// assert_eq!(face_visits_of([(CellKind::Simplex(3), 2)]), 20);
/// ```
pub fn face_visits_of(blocks: impl IntoIterator<Item = (crate::cell::CellKind, u64)>) -> u128 {
    blocks
        .into_iter()
        .map(|(kind, n)| {
            let per: u128 = (1..kind.dim())
                .map(|d| kind.n_faces(d))
                .fold(0u128, |a, x| a.saturating_add(x));
            per.saturating_mul(n as u128)
        })
        .fold(0u128, |a, x| a.saturating_add(x))
}

/// Connected components of the 1-skeleton, isolated vertices included.
///
/// ```
/// use starplex::algo::info::components;
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// // k: the triangles 0-1-2 and 1-3-2, sharing the edge 1-2
/// assert_eq!(components(&k), 1);
/// ```
pub fn components(k: &IndexedComplex) -> usize {
    let mut uf = UnionFind::new(k.n_vertices());
    for c in k.cells() {
        let v0 = c.vertices[0];
        for &v in &c.vertices[1..] {
            uf.union(v0, v);
        }
    }
    uf.n_sets()
}

/// The face counts of the f-vector pass (see [`apply_face_counts`] for an example).
///
/// ```
/// let c = starplex::algo::info::FaceCounts::default();
/// assert!(c.per_dim.is_empty() && c.boundary == 0);
/// ```
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct FaceCounts {
    /// Distinct faces by dimension (entry 0 unused).
    pub per_dim: Vec<u64>,
    /// (d-1)-faces in exactly one top d-cell.
    pub boundary: u64,
    /// (d-1)-faces in more than two top d-cells.
    pub shared_more_than_2: u64,
    /// Triangular 2-faces.
    pub tri_faces: u64,
    /// Quadrilateral 2-faces.
    pub quad_faces: u64,
}

fn count_faces(k: &IndexedComplex, opts: &InfoOptions) -> FaceCounts {
    let vt = k.vertex_cells();
    let dmax = k.dim().unwrap_or(0);
    let n = k.n_cells();
    let chunk = 4096usize;
    let n_chunks = n.div_ceil(chunk);
    let done = AtomicU64::new(0);
    let partials: Vec<FaceCounts> = (0..n_chunks)
        .into_par_iter()
        .map(|ci| {
            let mut acc = FaceCounts {
                per_dim: vec![0; dmax + 1],
                ..Default::default()
            };
            let mut key: Vec<u32> = Vec::with_capacity(16);
            let lo = ci * chunk;
            let hi = (lo + chunk).min(n);
            for c in lo..hi {
                count_cell(
                    k,
                    &vt,
                    c as u32,
                    dmax,
                    opts.owned_vertices.as_deref(),
                    &mut key,
                    &mut acc,
                );
            }
            if let Some(p) = &opts.progress {
                p((hi - lo) as u64);
            }
            done.fetch_add((hi - lo) as u64, Ordering::Relaxed);
            acc
        })
        .collect();
    let mut total = FaceCounts {
        per_dim: vec![0; dmax + 1],
        ..Default::default()
    };
    for p in partials {
        for (t, x) in total.per_dim.iter_mut().zip(&p.per_dim) {
            *t += x;
        }
        total.boundary += p.boundary;
        total.shared_more_than_2 += p.shared_more_than_2;
        total.tri_faces += p.tri_faces;
        total.quad_faces += p.quad_faces;
    }
    total
}

/// Records one owned face of dimension `fd` with `n_vertices` vertices, in `in_top` top cells.
#[inline]
fn count_owned(
    acc: &mut FaceCounts,
    fd: usize,
    track_boundary: bool,
    in_top: u32,
    n_vertices: usize,
    d: usize,
    simplex: bool,
) {
    acc.per_dim[fd] += 1;
    if track_boundary {
        if in_top == 1 {
            acc.boundary += 1;
        } else if in_top > 2 {
            acc.shared_more_than_2 += 1;
        }
    }
    if fd == 2 && (d == 3 || !simplex) {
        match n_vertices {
            3 => acc.tri_faces += 1,
            4 => acc.quad_faces += 1,
            _ => {}
        }
    }
}

/// Counts the faces of cell `c` that `c` owns.
///
/// The cells containing a face are among the common entries of the id-sorted vertex→cells rows
/// of its two least-used vertices, found by a merge; a common entry is then checked with
/// [`CellKind::has_face`](crate::cell::CellKind::has_face) (skipped for edges of simplicial
/// complexes, where sharing both vertices is enough). The first cell containing the face is its
/// owner.
fn count_cell(
    k: &IndexedComplex,
    vt: &Csr,
    c: u32,
    dmax: usize,
    owned: Option<&fixedbitset::FixedBitSet>,
    key: &mut Vec<u32>,
    acc: &mut FaceCounts,
) {
    let cell = k.cell(crate::ids::CellId(c));
    let d = cell.kind.dim();
    // the ownership rule of `InfoOptions::owned_vertices`: a face counts where its smallest
    // vertex is owned (`key` is sorted)
    let counts = |key: &[u32]| owned.is_none_or(|m| m.contains(key[0] as usize));
    let min_v = cell.vertices.iter().copied().min().unwrap_or(0);
    if counts(&[min_v]) {
        acc.per_dim[d] += 1;
    }
    let all_simplices = k.is_simplicial();
    for fd in 1..d {
        let track_boundary = d == dmax && fd + 1 == d;
        cell.kind.for_each_face(fd, |local| {
            crate::cell::canonical_key(cell.vertices, local, key);
            if !counts(key) {
                return;
            }
            // the two least-used vertices of the face (degrees read once)
            let (mut a, mut da, mut b, mut db) = (0u32, u32::MAX, 0u32, u32::MAX);
            for &v in key.iter() {
                let dv = vt.degree(v as usize) as u32;
                if dv < da {
                    (b, db) = (a, da);
                    (a, da) = (v, dv);
                } else if dv < db {
                    (b, db) = (v, dv);
                }
            }
            if da == 1 {
                // only c holds this vertex, hence the face
                count_owned(
                    acc,
                    fd,
                    track_boundary,
                    1,
                    key.len(),
                    d,
                    cell.kind.is_simplex(),
                );
                return;
            }
            let _ = db;
            let need_check = key.len() > 2 || !all_simplices;
            let (ra, rb) = (vt.row(a as usize), vt.row(b as usize));
            let (mut i, mut j) = (0, 0);
            let mut owned = false;
            let mut in_top = 0u32;
            while i < ra.len() && j < rb.len() {
                let (x, y) = (ra[i], rb[j]);
                if x < y {
                    i += 1;
                    continue;
                }
                if y < x {
                    j += 1;
                    continue;
                }
                i += 1;
                j += 1;
                let o = x;
                let other_dim = if o == c {
                    d
                } else {
                    let other = k.cell(crate::ids::CellId(o));
                    if need_check && !other.kind.has_face(other.vertices, key) {
                        continue;
                    }
                    other.kind.dim()
                };
                if !owned {
                    // the first cell containing the face is its owner
                    if o != c {
                        return;
                    }
                    owned = true;
                }
                if !track_boundary {
                    break;
                }
                if other_dim == d {
                    in_top += 1;
                }
            }
            debug_assert!(owned, "a cell contains its own faces");
            count_owned(
                acc,
                fd,
                track_boundary,
                in_top,
                key.len(),
                d,
                cell.kind.is_simplex(),
            );
        });
    }
    // 1-dimensional top cells: their boundary faces are vertices.
    if d == 1 && dmax == 1 {
        for &v in cell.vertices {
            let row = vt.row(v as usize);
            if row.first() == Some(&c) && counts(&[v]) {
                match row.len() {
                    1 => acc.boundary += 1,
                    2 => {}
                    _ => acc.shared_more_than_2 += 1,
                }
            }
        }
    }
}
