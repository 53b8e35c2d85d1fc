//! Explicit conversions for writing a complex to a format that cannot hold it as it is:
//! [`boundary`] (the boundary surface of a volume mesh, `convert --boundary`) and
//! [`triangulate`] (quads split into triangles, `convert --triangulate`).
//!
//! ```
//! use starplex::algo::surface;
//! use starplex::cell::CellKind;
//! use starplex::complex::IndexedComplex;
//! let cube = IndexedComplex::from_parts(3,
//!     vec![0., 0., 0., 1., 0., 0., 1., 1., 0., 0., 1., 0., 0., 0., 1., 1., 0., 1., 1., 1., 1., 0., 1., 1.].into(),
//!     vec![(CellKind::Hex, (0..8).collect::<Vec<u32>>().into())]).unwrap();
//! let (skin, report) = surface::boundary(&cube).unwrap();
//! assert_eq!((skin.n_vertices(), skin.n_cells(), report.ignored_lower_cells), (8, 6, 0));
//! let tris = surface::triangulate(&skin).unwrap();
//! assert_eq!(tris.n_cells(), 12);
//! assert!(tris.blocks().iter().all(|b| b.kind == CellKind::Simplex(2)));
//! ```
use rustc_hash::FxHashMap;
use smallvec::SmallVec;

use crate::cell::CellKind;
use crate::complex::{BuildOptions, ComplexBuilder, ComplexError, IndexedComplex};
use crate::ids::CellId;

/// Why a conversion cannot be made.
///
/// ```
/// use starplex::algo::surface::{triangulate, SurfaceError};
/// use starplex::cell::CellKind;
/// use starplex::complex::IndexedComplex;
/// let hex = IndexedComplex::from_parts(3, vec![0.0; 24].into(),
///                                      vec![(CellKind::Hex, (0..8).collect::<Vec<u32>>().into())]).unwrap();
/// assert!(matches!(triangulate(&hex), Err(SurfaceError::VolumeCell { cell: 0, .. })));
/// ```
#[derive(Debug, thiserror::Error)]
pub enum SurfaceError {
    /// `triangulate` splits polygons, not 3D cells.
    #[error("cell {cell} is a {kind}: triangulating splits quads into triangles, not 3D cells (take the boundary surface first)")]
    VolumeCell {
        /// The cell id.
        cell: u64,
        /// Its kind.
        kind: CellKind,
    },
    /// The result is not a valid complex (e.g. a triangle of a split quad is also a top cell).
    #[error("{0}")]
    Complex(#[from] ComplexError),
}

/// What [`boundary`] left out.
///
/// ```
/// let r = starplex::algo::surface::BoundaryReport::default();
/// assert_eq!(r.ignored_lower_cells, 0);
/// ```
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct BoundaryReport {
    /// Top cells of lower dimension than the complex (they bound nothing and are not written).
    pub ignored_lower_cells: usize,
}

type Key = SmallVec<[u32; 8]>;

/// One face of [`boundary_facets`]: a (d-1)-face in exactly one kept d-cell.
///
/// ```
/// use starplex::algo::surface::Facet;
/// use starplex::cell::CellKind;
/// use starplex::ids::CellId;
/// let f = Facet { cell: CellId(0), kind: CellKind::Simplex(2), vertices: [0, 1, 2].into_iter().collect() };
/// assert_eq!(f.vertices.len(), 3);
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Facet {
    /// The d-cell it bounds (input numbering).
    pub cell: CellId,
    /// Its kind (a (d-1)-simplex, or a triangle or quad of a CP cell).
    pub kind: CellKind,
    /// Its vertices (input ids), oriented as induced by `cell`.
    pub vertices: SmallVec<[u32; 8]>,
}

/// The (d-1)-faces of the d-dimensional top cells of `k` accepted by `keep` that lie in exactly
/// one accepted d-cell, oriented as induced by that cell, in order of (cell id, facet): with
/// `keep` always true, the boundary of the d-cells ([`boundary`] is this plus a renumbering);
/// with a clipping predicate, the boundary of the kept part (its cut faces included). Top cells
/// of another dimension are counted in the report and ignored.
///
/// ```
/// use starplex::algo::surface::boundary_facets;
/// use starplex::cell::CellKind;
/// use starplex::complex::IndexedComplex;
/// use starplex::ids::CellId;
/// // two tetrahedra sharing the face 1-2-3
/// let k = IndexedComplex::from_parts(3, vec![0., 0., 0., 1., 0., 0., 0., 1., 0., 0., 0., 1., 1., 1., 1.].into(),
///     vec![(CellKind::Simplex(3), vec![0, 1, 2, 3, 4, 3, 2, 1].into())]).unwrap();
/// assert_eq!(boundary_facets(&k, 3, |_| true).0.len(), 6);
/// // keep only the first: its 4 faces, the shared one now exposed
/// let (f, _) = boundary_facets(&k, 3, |c| c == CellId(0));
/// assert_eq!(f.len(), 4);
/// assert!(f.iter().all(|x| x.cell == CellId(0)));
/// ```
pub fn boundary_facets(
    k: &IndexedComplex,
    d: usize,
    keep: impl Fn(CellId) -> bool,
) -> (Vec<Facet>, BoundaryReport) {
    let mut report = BoundaryReport::default();
    let mut counts: FxHashMap<Key, u32> = FxHashMap::default();
    let mut key: Key = SmallVec::new();
    for b in k.blocks() {
        if b.kind.dim() != d {
            report.ignored_lower_cells += b.len();
            continue;
        }
        for i in 0..b.len() {
            if !keep(CellId(b.first + i as u32)) {
                continue;
            }
            let c = b.cell(i);
            b.kind.for_each_oriented_facet(|f, _| {
                key.clear();
                key.extend(f.iter().map(|&l| c[l as usize]));
                key.sort_unstable();
                *counts.entry(key.clone()).or_insert(0) += 1;
            });
        }
    }
    // the boundary facets, oriented, in (cell, facet) order
    let mut faces: Vec<Facet> = Vec::new();
    for b in k.blocks().iter().filter(|b| b.kind.dim() == d) {
        for i in 0..b.len() {
            let cell = CellId(b.first + i as u32);
            if !keep(cell) {
                continue;
            }
            let c = b.cell(i);
            b.kind.for_each_oriented_facet(|f, sign| {
                key.clear();
                key.extend(f.iter().map(|&l| c[l as usize]));
                let mut sorted = key.clone();
                sorted.sort_unstable();
                if counts.get(&sorted) != Some(&1) {
                    return;
                }
                let mut v = key.clone();
                if sign < 0 && v.len() >= 2 {
                    v.swap(0, 1);
                }
                let kind = match (b.kind, v.len()) {
                    (CellKind::Simplex(s), _) => CellKind::Simplex(s - 1),
                    (_, 2) => CellKind::Simplex(1),
                    (_, 3) => CellKind::Simplex(2),
                    _ => CellKind::Quad,
                };
                faces.push(Facet {
                    cell,
                    kind,
                    vertices: v,
                });
            });
        }
    }
    (faces, report)
}

/// The boundary of `k`: the (d-1)-faces of its d-dimensional top cells (d = `k.dim()`) that lie
/// in exactly one of them, oriented as induced by that cell (outward for a positively oriented
/// cell: the VTK facet tables of CP cells, the boundary operator for simplices), in order of
/// (cell id, facet). Vertices are those of the boundary, renumbered in their input order. Faces
/// shared by three or more cells are not boundary. Top cells of lower dimension are ignored and
/// counted in the report.
///
/// ```
/// use starplex::algo::surface::boundary;
/// use starplex::cell::CellKind;
/// use starplex::complex::IndexedComplex;
/// // two tetrahedra sharing the face 1-2-3: 6 boundary triangles on 5 vertices
/// let k = IndexedComplex::from_parts(3, vec![0., 0., 0., 1., 0., 0., 0., 1., 0., 0., 0., 1., 1., 1., 1.].into(),
///     vec![(CellKind::Simplex(3), vec![0, 1, 2, 3, 4, 3, 2, 1].into())]).unwrap();
/// let (b, _) = boundary(&k).unwrap();
/// assert_eq!((b.n_vertices(), b.n_cells()), (5, 6));
/// // the first tetrahedron's facet opposite vertex 0 is shared, the next one, (0,2,3) with sign -1, is not
/// assert_eq!(b.cells().next().unwrap().vertices, &[2, 0, 3]);
/// ```
///
/// # Errors
/// [`SurfaceError::Complex`] if the faces do not make a valid complex (cannot happen for a valid
/// input; kept so no input can panic).
pub fn boundary(k: &IndexedComplex) -> Result<(IndexedComplex, BoundaryReport), SurfaceError> {
    let Some(d) = k.dim() else {
        let b = ComplexBuilder::new(k.ambient_dim())?;
        return Ok((
            b.build(&BuildOptions::default())?.0,
            BoundaryReport::default(),
        ));
    };
    let (facets, report) = boundary_facets(k, d, |_| true);
    let mut faces: Vec<(CellKind, Key)> =
        facets.into_iter().map(|f| (f.kind, f.vertices)).collect();
    let mut new_id = vec![u32::MAX; k.n_vertices()];
    for (_, f) in &faces {
        for &v in f {
            new_id[v as usize] = 0;
        }
    }
    let mut out = ComplexBuilder::new(k.ambient_dim())?;
    let amb = k.ambient_dim();
    for (v, id) in new_id.iter_mut().enumerate() {
        if *id == 0 {
            *id = out.push_vertex(&k.coords()[v * amb..(v + 1) * amb])?.0;
        }
    }
    for (kind, f) in &mut faces {
        for v in f.iter_mut() {
            *v = new_id[*v as usize];
        }
        out.push_cell(*kind, f)?;
    }
    Ok((out.build(&BuildOptions::default())?.0, report))
}

/// `k` with every quad split into the triangles (0, 1, 2) and (0, 2, 3), which keep its
/// orientation; other simplices are kept, vertices and their ids are unchanged.
///
/// ```
/// use starplex::algo::surface::triangulate;
/// use starplex::cell::CellKind;
/// use starplex::complex::IndexedComplex;
/// let q = IndexedComplex::from_parts(2, vec![0., 0., 1., 0., 1., 1., 0., 1.].into(),
///                                    vec![(CellKind::Quad, vec![0, 1, 2, 3].into())]).unwrap();
/// let t = triangulate(&q).unwrap();
/// let cells: Vec<&[u32]> = t.cells().map(|c| c.vertices).collect();
/// assert_eq!(cells, [&[0, 1, 2][..], &[0, 2, 3][..]]);
/// ```
///
/// # Errors
/// [`SurfaceError::VolumeCell`] for hexahedra, prisms and pyramids; [`SurfaceError::Complex`]
/// when a split triangle is already a top cell or a face of one (a non-manifold input).
pub fn triangulate(k: &IndexedComplex) -> Result<IndexedComplex, SurfaceError> {
    let mut out = ComplexBuilder::new(k.ambient_dim())?;
    let amb = k.ambient_dim();
    for p in k.coords().chunks_exact(amb.max(1)) {
        out.push_vertex(p)?;
    }
    for b in k.blocks() {
        match b.kind {
            CellKind::Quad => {
                for i in 0..b.len() {
                    let c = b.cell(i);
                    out.push_cell(CellKind::Simplex(2), &[c[0], c[1], c[2]])?;
                    out.push_cell(CellKind::Simplex(2), &[c[0], c[2], c[3]])?;
                }
            }
            CellKind::Simplex(_) => {
                for i in 0..b.len() {
                    out.push_cell(b.kind, b.cell(i))?;
                }
            }
            kind => {
                return Err(SurfaceError::VolumeCell {
                    cell: b.first as u64,
                    kind,
                })
            }
        }
    }
    Ok(out.build(&BuildOptions::default())?.0)
}
