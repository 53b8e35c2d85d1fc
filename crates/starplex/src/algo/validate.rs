//! Topological validation, written once: connected components, purity, (d-1)-connectedness,
//! pseudo-manifoldness, boundary (d-1)-faces, faces in more than two top cells, non-manifold
//! vertices and edges ([`crate::algo::manifold`], global convention), orientability with a
//! consistent orientation ([`crate::algo::orientation`]). Every problem carries its ids (input
//! numbering).
//!
//! [`validate`] runs on any structure answering [`TopCells`] + [`VertexStar`];
//! [`StellarTree::validate`](crate::stellar::StellarTree::validate) computes the same
//! [`ValidationReport`] leaf by leaf in parallel, with the same star tests and the same
//! orientation walk, and a test holds the two equal. One visitor, three entry points:
//! [`is_valid`] (a valid manifold?), [`check`] (the first [`Problem`]) and [`errors`] (every
//! problem), also on a report already computed ([`ValidationReport::problems`]).
//!
//! ```
//! use starplex::complex::{ComplexBuilder, BuildOptions};
//! use starplex::cell::CellKind;
//! use starplex::ids::VertexId;
//! use starplex::topo::naive::VtIndex;
//! use starplex::algo::validate::{validate, check, is_valid, Problem};
//! // a bow tie: two triangles sharing vertex 0
//! let mut b = ComplexBuilder::new(2).unwrap();
//! for p in [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [-1.0, 0.0], [-1.0, -1.0]] { b.push_vertex(&p).unwrap(); }
//! b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
//! b.push_cell(CellKind::Simplex(2), &[0, 3, 4]).unwrap();
//! let k = b.build(&BuildOptions::default()).unwrap().0;
//! let idx = VtIndex::new(&k);
//! let r = validate(&idx);
//! assert_eq!(r.non_manifold_vertices, vec![VertexId(0)]);
//! assert_eq!(r.boundary_faces.len(), 6);
//! assert!(!is_valid(&idx));
//! assert_eq!(check(&idx), Err(Problem::NotFacetConnected { n_classes: 2 }));
//! ```
use crate::algo::components::components;
use crate::algo::manifold::{complex_dim, singularities_in_dim, Convention};
use crate::algo::orientation::{
    apply_joins, facet_union_find, joined_components, orient_parts_joined, orient_walk,
    Orientation, PairParts,
};
use crate::cell::{listed_sign, oriented_facets_of, CellKind};
use crate::ids::{CellId, VertexId};
use crate::topo::{TopCells, VertexStar};
use rayon::prelude::*;

/// The result of a validation: [`validate`] on any structure, or
/// [`StellarTree::validate`](crate::stellar::StellarTree::validate) leaf by leaf (equal answers).
///
/// ```
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// # use starplex::stellar::{StellarTree, StellarOptions};
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// # let t = StellarTree::build(&k, &StellarOptions { kv: Some(1), ..Default::default() }).unwrap();
/// // two triangles forming a square: a disk
/// let r = t.validate();
/// assert_eq!((r.dim, r.n_connected_components, r.n_facet_components), (2, 1, 1));
/// assert!(r.pure && r.facet_connected && r.pseudo_manifold);
/// assert!(r.faces_in_more_than_two_cells.is_empty() && r.non_manifold_edges.is_empty());
/// assert_eq!(r.orientable, Some(true));
/// assert_eq!(r.cells_to_flip, Some(vec![])); // already consistently oriented
/// ```
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ValidationReport {
    /// Dimension of the complex (-1 when empty).
    pub dim: i64,
    /// Connected components of the 1-skeleton, isolated vertices included.
    pub n_connected_components: u64,
    /// Vertices in no top cell.
    pub isolated_vertices: Vec<VertexId>,
    /// Top cells of dimension below `dim`.
    pub lower_dimensional_cells: Vec<CellId>,
    /// All top cells of dimension `dim` and no isolated vertex.
    pub pure: bool,
    /// Classes of top `dim`-cells connected through shared (d-1)-faces.
    pub n_facet_components: u64,
    /// Exactly one such class (and at least one top cell).
    pub facet_connected: bool,
    /// Pure, every (d-1)-face in at most two d-cells, and (d-1)-connected.
    pub pseudo_manifold: bool,
    /// (d-1)-faces in exactly one top d-cell (sorted input vertex ids).
    pub boundary_faces: Vec<Vec<VertexId>>,
    /// (d-1)-faces in three or more top d-cells.
    pub faces_in_more_than_two_cells: Vec<Vec<VertexId>>,
    /// Non-manifold vertices, sorted.
    pub non_manifold_vertices: Vec<VertexId>,
    /// Vertices whose manifoldness is unknown (d >= 4), sorted.
    pub unknown_vertices: Vec<VertexId>,
    /// Non-manifold edges (endpoints sorted), sorted.
    pub non_manifold_edges: Vec<[VertexId; 2]>,
    /// Edges whose manifoldness is unknown (d >= 4).
    pub unknown_edges: Vec<[VertexId; 2]>,
    /// `Some(orientable)` when every (d-1)-face is in at most two d-cells, else `None`.
    pub orientable: Option<bool>,
    /// When orientable: the top cells to reverse for a consistent orientation (sorted).
    pub cells_to_flip: Option<Vec<CellId>>,
    /// When not orientable: two adjacent cells whose orientations cannot agree.
    pub orientation_conflict: Option<(CellId, CellId)>,
}

impl ValidationReport {
    /// Number of boundary (d-1)-faces.
    ///
    /// ```
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// # use starplex::stellar::{StellarTree, StellarOptions};
    /// # let mut b = ComplexBuilder::new(2).unwrap();
    /// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
    /// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
    /// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// # let t = StellarTree::build(&k, &StellarOptions { kv: Some(1), ..Default::default() }).unwrap();
    /// let r = t.validate();
    /// assert_eq!(r.n_boundary_faces(), 4); // the sides of the square
    /// ```
    pub fn n_boundary_faces(&self) -> usize {
        self.boundary_faces.len()
    }
    /// True when no problem was found.
    ///
    /// ```
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// # use starplex::stellar::{StellarTree, StellarOptions};
    /// # let mut b = ComplexBuilder::new(2).unwrap();
    /// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
    /// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
    /// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// # let t = StellarTree::build(&k, &StellarOptions { kv: Some(1), ..Default::default() }).unwrap();
    /// assert!(t.validate().is_valid_manifold()); // a disk
    /// ```
    pub fn is_valid_manifold(&self) -> bool {
        self.pseudo_manifold
            && self.non_manifold_vertices.is_empty()
            && self.non_manifold_edges.is_empty()
            && self.unknown_vertices.is_empty()
            && self.orientable == Some(true)
    }
}

/// One problem found by validation, with the ids that show it.
///
/// ```
/// use starplex::algo::validate::Problem;
/// use starplex::ids::VertexId;
/// let p = Problem::NonManifoldVertex(VertexId(3));
/// assert_eq!(p.to_string(), "vertex 3 is non-manifold");
/// ```
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum Problem {
    /// No top cell at all (an empty complex or a point set).
    #[error("the complex has no top cells")]
    NoTopCells,
    /// A vertex in no top cell (of a complex with top cells).
    #[error("vertex {0} is in no top cell")]
    IsolatedVertex(VertexId),
    /// A top cell of lower dimension than the complex.
    #[error("top cell {0} has a lower dimension than the complex")]
    LowerDimensionalCell(CellId),
    /// The top cells fall in several classes connected through (d-1)-faces.
    #[error("the top cells form {n_classes} classes through shared (d-1)-faces")]
    NotFacetConnected {
        /// Number of classes.
        n_classes: u64,
    },
    /// A (d-1)-face in three or more top cells.
    #[error("face {0:?} is in more than two top cells")]
    FaceInMoreThanTwoCells(Vec<VertexId>),
    /// A non-manifold vertex.
    #[error("vertex {0} is non-manifold")]
    NonManifoldVertex(VertexId),
    /// A non-manifold edge.
    #[error("edge {}-{} is non-manifold", .0[0], .0[1])]
    NonManifoldEdge([VertexId; 2]),
    /// A vertex whose manifoldness could not be decided (d >= 4).
    #[error("vertex {0} could not be decided (dimension >= 4)")]
    UndecidedVertex(VertexId),
    /// Two adjacent top cells whose orientations cannot agree.
    #[error("top cells {0} and {1} cannot be oriented consistently")]
    OrientationConflict(CellId, CellId),
}

impl ValidationReport {
    /// Every problem of the report, in a fixed order: isolated vertices, lower-dimensional
    /// cells (or no top cell at all), facet-connectedness, faces in more than two cells, non-manifold vertices and
    /// edges, undecided vertices, the orientation conflict. Empty exactly when
    /// [`ValidationReport::is_valid_manifold`] holds.
    ///
    /// ```
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// use starplex::algo::validate::{validate, Problem};
    /// use starplex::topo::naive::VtIndex;
    /// use starplex::ids::{CellId, VertexId};
    /// // a triangle and a dangling edge at its vertex 2
    /// let mut b = ComplexBuilder::new(2).unwrap();
    /// for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
    /// b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
    /// b.push_cell(CellKind::Simplex(1), &[2, 3]).unwrap();
    /// let k = b.build(&BuildOptions::default()).unwrap().0;
    /// let p = validate(&VtIndex::new(&k)).problems();
    /// assert_eq!(p[0], Problem::LowerDimensionalCell(CellId(1)));
    /// assert!(p.contains(&Problem::NonManifoldVertex(VertexId(2))));
    /// ```
    pub fn problems(&self) -> Vec<Problem> {
        let mut p = Vec::new();
        self.visit(|x| {
            p.push(x);
            true
        });
        p
    }

    /// Calls `f` on each problem in [`ValidationReport::problems`] order while it returns true.
    fn visit(&self, mut f: impl FnMut(Problem) -> bool) {
        let mut go = true;
        let mut emit = |x: Problem| {
            if go {
                go = f(x);
            }
        };
        if self.n_facet_components == 0 {
            emit(Problem::NoTopCells);
        } else {
            self.isolated_vertices
                .iter()
                .for_each(|&v| emit(Problem::IsolatedVertex(v)));
        }
        self.lower_dimensional_cells
            .iter()
            .for_each(|&c| emit(Problem::LowerDimensionalCell(c)));
        if self.n_facet_components > 1 {
            emit(Problem::NotFacetConnected {
                n_classes: self.n_facet_components,
            });
        }
        self.faces_in_more_than_two_cells
            .iter()
            .for_each(|f| emit(Problem::FaceInMoreThanTwoCells(f.clone())));
        self.non_manifold_vertices
            .iter()
            .for_each(|&v| emit(Problem::NonManifoldVertex(v)));
        self.non_manifold_edges
            .iter()
            .for_each(|&e| emit(Problem::NonManifoldEdge(e)));
        self.unknown_vertices
            .iter()
            .for_each(|&v| emit(Problem::UndecidedVertex(v)));
        if let Some((a, b)) = self.orientation_conflict {
            emit(Problem::OrientationConflict(a, b));
        }
    }
}

/// The facets of the top d-cells, each once: `(sorted vertices, cell, induced sign relative to
/// the sorted order)`, grouped by face; every group is handed to `f`.
fn facet_groups<S: TopCells + VertexStar + ?Sized>(
    s: &S,
    d: usize,
    mut f: impl FnMut(&[VertexId], &[(CellId, i8)]),
) {
    let (mut cells, mut vs) = (Vec::new(), Vec::new());
    let mut recs: Vec<(Vec<VertexId>, CellId, i8)> = Vec::new();
    let mut key: Vec<u32> = Vec::new();
    let mut group: Vec<(CellId, i8)> = Vec::new();
    for v in 0..s.n_vertices() {
        let v = VertexId(v as u32);
        s.vertex_top_cells(v, &mut cells);
        recs.clear();
        for &c in &cells {
            let kind = s.top_cell_kind(c);
            if kind.dim() != d {
                continue;
            }
            vs.clear();
            s.top_cell_vertices(c, &mut vs);
            oriented_facets_of(kind, |local, sign| {
                key.clear();
                key.extend(local.iter().map(|&i| vs[i as usize].0));
                // each facet once: from its smallest vertex
                if key.iter().min() != Some(&v.0) {
                    return;
                }
                let sign = sign * listed_sign(&key, !kind.is_simplex() && key.len() >= 3);
                key.sort_unstable();
                recs.push((key.iter().map(|&x| VertexId(x)).collect(), c, sign));
            });
        }
        recs.sort_unstable();
        let mut i = 0;
        while i < recs.len() {
            let mut j = i + 1;
            while j < recs.len() && recs[j].0 == recs[i].0 {
                j += 1;
            }
            group.clear();
            group.extend(recs[i..j].iter().map(|r| (r.1, r.2)));
            f(&recs[i].0, &group);
            i = j;
        }
    }
}

/// Faces (short vertex lists) one after the other in one array: what a leaf pass finds
/// without an allocation per face, turned into the report's sorted lists once
/// ([`Faces::into_sorted`]).
#[derive(Clone, Debug, Default)]
pub(crate) struct Faces {
    verts: Vec<u32>,
    /// Face `i` is `verts[ends[i - 1]..ends[i]]` (from 0 for the first); `usize`, so that
    /// the faces of a whole report never wrap.
    ends: Vec<usize>,
}

impl Faces {
    /// Appends a face.
    pub(crate) fn push(&mut self, f: &[u32]) {
        self.verts.extend_from_slice(f);
        self.ends.push(self.verts.len());
    }

    /// The faces in order.
    pub(crate) fn iter(&self) -> impl Iterator<Item = &[u32]> + '_ {
        let starts = std::iter::once(0).chain(self.ends.iter().copied());
        starts
            .zip(self.ends.iter().copied())
            .map(|(a, b)| &self.verts[a..b])
    }

    /// Appends all of `other`'s faces.
    pub(crate) fn append(&mut self, other: &Faces) {
        let base = self.verts.len();
        self.verts.extend_from_slice(&other.verts);
        self.ends.extend(other.ends.iter().map(|&e| base + e));
    }

    /// The faces through `map` (each then sorted) in increasing lexicographic order, as the
    /// report lists them: faces of at most four vertices are sorted as fixed-size keys (no
    /// pointer to follow per comparison) and allocated once, in their final order.
    pub(crate) fn into_sorted(self, map: impl Fn(u32) -> u32) -> Vec<Vec<VertexId>> {
        if self.iter().any(|f| f.len() > 4) {
            let mut out: Vec<Vec<VertexId>> = self
                .iter()
                .map(|f| {
                    let mut x: Vec<VertexId> = f.iter().map(|&v| VertexId(map(v))).collect();
                    x.sort_unstable();
                    x
                })
                .collect();
            out.sort_unstable();
            return out;
        }
        // padding with 0 keeps the order of lists (0 is no larger than any vertex; a list
        // that is a prefix of another then ties with it, and the shorter comes first)
        let mut keys: Vec<([u32; 4], u8)> = self
            .iter()
            .map(|f| {
                let mut k = [0u32; 4];
                for (x, &v) in k.iter_mut().zip(f) {
                    *x = map(v);
                }
                k[..f.len()].sort_unstable();
                (k, f.len() as u8)
            })
            .collect();
        keys.sort_unstable();
        keys.iter()
            .map(|(k, n)| k[..*n as usize].iter().map(|&v| VertexId(v)).collect())
            .collect()
    }
}

/// Fills the parts of a report that follow from the facet pairs: (d-1)-connectedness,
/// pseudo-manifoldness and the orientation. `pairs` are `(a, b, rel)` in input cell ids, or, with
/// `to_input`, in a working numbering that `to_input` maps to input ids (`is_top` then takes
/// working ids too; see [`orient_tops_renumbered`](crate::algo::orientation::orient_tops_renumbered)).
/// Returns the number of components of the top cells through the pairs and `joins` (pairs of
/// top cells, in the pairs' numbering, also to be joined).
pub(crate) fn finish_report(
    r: &mut ValidationReport,
    n_cells: usize,
    is_top: impl Fn(u32) -> bool + Sync,
    pairs: &PairParts<'_>,
    to_input: Option<&[u32]>,
    joins: &[(u32, u32)],
) -> u64 {
    // the top mask once: `is_top` may map ids and look up kinds; none when every cell is a
    // top (a pure complex: no test left in the loops over the pairs)
    let top: Vec<bool> = (0..n_cells as u32)
        .into_par_iter()
        .with_min_len(1 << 14)
        .map(&is_top)
        .collect();
    if top.iter().all(|&t| t) {
        drop(top);
        return finish_report_tops(r, n_cells, |_| true, pairs, to_input, joins);
    }
    finish_report_tops(r, n_cells, |c| top[c as usize], pairs, to_input, joins)
}

/// [`finish_report`] once the tops are known (`is_top` a cheap test).
pub(crate) fn finish_report_tops(
    r: &mut ValidationReport,
    n_cells: usize,
    is_top: impl Fn(u32) -> bool + Sync + Copy,
    pairs: &PairParts<'_>,
    to_input: Option<&[u32]>,
    joins: &[(u32, u32)],
) -> u64 {
    let joined = if r.faces_in_more_than_two_cells.is_empty() {
        // the orientation walk counts the components it walks: no separate union-find
        let (o, n_components, joined) = match to_input {
            Some(to_input) => orient_parts_joined(n_cells, is_top, pairs, to_input, joins),
            None => {
                let pairs = pairs.flat();
                let w = orient_walk(n_cells, is_top, &pairs, |_| 1);
                let joined = joined_components(n_cells, is_top, &pairs, joins, w.n_components);
                (w.orientation(), w.n_components, joined)
            }
        };
        r.n_facet_components = n_components as u64;
        match o {
            Orientation::Orientable { flips } => {
                r.orientable = Some(true);
                r.cells_to_flip = Some(flips);
            }
            Orientation::NonOrientable { conflict } => {
                r.orientable = Some(false);
                r.orientation_conflict = Some(conflict);
            }
        }
        joined
    } else {
        // the count does not depend on the numbering
        let mut cuf = facet_union_find(n_cells, is_top, pairs.iter());
        let n = (0..n_cells as u32)
            .filter(|&c| is_top(c) && cuf.find(c) == c)
            .count();
        r.n_facet_components = n as u64;
        apply_joins(&mut cuf, joins, n)
    };
    r.facet_connected = r.n_facet_components == 1;
    r.pseudo_manifold = r.pure && r.faces_in_more_than_two_cells.is_empty() && r.facet_connected;
    joined as u64
}

/// Validates any structure (see the [module docs](self)); the answer equals
/// [`StellarTree::validate`](crate::stellar::StellarTree::validate) on the same complex.
///
/// ```
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// use starplex::algo::validate::validate;
/// use starplex::stellar::{StellarTree, StellarOptions};
/// use starplex::topo::naive::VtIndex;
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # b.push_cell(CellKind::Simplex(2), &[1, 2, 3]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// // two triangles on the edge 1-2, listed so that they induce the same orientation on it
/// let r = validate(&VtIndex::new(&k));
/// assert_eq!(r.cells_to_flip, Some(vec![starplex::ids::CellId(1)]));
/// let t = StellarTree::build(&k, &StellarOptions::default()).unwrap();
/// assert_eq!(t.validate(), r);
/// ```
pub fn validate<S: TopCells + VertexStar + ?Sized>(s: &S) -> ValidationReport {
    let d = complex_dim(s);
    let (mut r, pairs) = validate_parts(s, d);
    if let Some(d) = d {
        let nc = s.n_top_cells();
        let kinds: Vec<CellKind> = (0..nc).map(|c| s.top_cell_kind(CellId(c as u32))).collect();
        finish_report(
            &mut r,
            nc,
            |c| kinds[c as usize].dim() == d,
            &PairParts::one(&pairs),
            None,
            &[],
        );
    }
    r
}

/// The part of [`validate`] that is local to vertex stars, for a complex of dimension `d`:
/// the report without the facet classes and orientation (`n_facet_components`,
/// `facet_connected`, `pseudo_manifold`, `orientable`, ... left at their defaults), and the
/// pairs of top `d`-cells sharing a facet, with the product of the orientations they induce on
/// it (what [`orient_tops`](crate::algo::orientation::orient_tops) propagates).
/// `starplex-mpi` runs it on each rank, where the stars of the vertices a rank does not own are
/// empty, and merges the classes across ranks.
///
/// ```
/// use starplex::algo::validate::{validate, validate_parts};
/// use starplex::algo::manifold::complex_dim;
/// use starplex::topo::naive::VtIndex;
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # b.push_cell(CellKind::Simplex(2), &[1, 2, 3]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// // k: the triangles 0-1-2 and 1-2-3, sharing the edge 1-2
/// let idx = VtIndex::new(&k);
/// let (r, pairs) = validate_parts(&idx, complex_dim(&idx));
/// assert_eq!(r.boundary_faces, validate(&idx).boundary_faces);
/// assert_eq!(pairs, vec![(0, 1, 1)]);
/// ```
pub fn validate_parts<S: TopCells + VertexStar + ?Sized>(
    s: &S,
    d: Option<usize>,
) -> (ValidationReport, Vec<(u32, u32, i8)>) {
    let nv = s.n_vertices();
    let nc = s.n_top_cells();
    let mut r = ValidationReport {
        dim: d.map_or(-1, |d| d as i64),
        n_connected_components: components(s).n_components as u64,
        ..Default::default()
    };
    let mut cells = Vec::new();
    for v in 0..nv {
        s.vertex_top_cells(VertexId(v as u32), &mut cells);
        if cells.is_empty() {
            r.isolated_vertices.push(VertexId(v as u32));
        }
    }
    let Some(d) = d else {
        if nv > 0 {
            r.dim = 0;
        }
        r.pure = r.isolated_vertices.is_empty();
        return (r, Vec::new());
    };
    let kinds: Vec<CellKind> = (0..nc).map(|c| s.top_cell_kind(CellId(c as u32))).collect();
    r.lower_dimensional_cells = (0..nc)
        .filter(|&c| kinds[c].dim() < d)
        .map(|c| CellId(c as u32))
        .collect();
    r.pure = r.lower_dimensional_cells.is_empty() && r.isolated_vertices.is_empty();
    let mut pairs = Vec::new();
    let (mut boundary, mut over2) = (Faces::default(), Faces::default());
    if d > 0 {
        facet_groups(s, d, |face, group| {
            match group.len() {
                1 => boundary.push(bytemuck::cast_slice(face)),
                2 => {}
                _ => over2.push(bytemuck::cast_slice(face)),
            }
            for i in 0..group.len() {
                for j in i + 1..group.len() {
                    let ((a, sa), (b, sb)) = (group[i], group[j]);
                    pairs.push((a.0, b.0, sa * sb));
                }
            }
        });
        let sing =
            singularities_in_dim(s, Convention::Global, d).expect("global tests do not refuse");
        r.non_manifold_vertices = sing.non_manifold_vertices;
        r.unknown_vertices = sing.unknown_vertices;
        r.non_manifold_edges = sing.non_manifold_edges;
        r.unknown_edges = sing.unknown_edges;
    }
    r.boundary_faces = boundary.into_sorted(|v| v);
    r.faces_in_more_than_two_cells = over2.into_sorted(|v| v);
    (r, pairs)
}

/// True when the complex is a valid manifold: pseudo-manifold, no non-manifold or undecided
/// vertex, no non-manifold edge, orientable.
///
/// ```
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// use starplex::algo::validate::is_valid;
/// use starplex::topo::naive::VtIndex;
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// assert!(is_valid(&VtIndex::new(&k))); // a disk
/// ```
pub fn is_valid<S: TopCells + VertexStar + ?Sized>(s: &S) -> bool {
    validate(s).is_valid_manifold()
}

/// The first problem found, in [`ValidationReport::problems`] order.
///
/// ```
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// use starplex::algo::validate::{check, Problem};
/// use starplex::topo::naive::VtIndex;
/// use starplex::ids::VertexId;
/// let mut b = ComplexBuilder::new(1).unwrap();
/// for x in 0..5 { b.push_vertex(&[x as f64]).unwrap(); }
/// for c in [2, 3, 4] { b.push_cell(CellKind::Simplex(2), &[0, 1, c]).unwrap(); }
/// let k = b.build(&BuildOptions::default()).unwrap().0;
/// // a book of three pages on the edge 0-1
/// let e = check(&VtIndex::new(&k)).unwrap_err();
/// assert_eq!(e, Problem::FaceInMoreThanTwoCells(vec![VertexId(0), VertexId(1)]));
/// ```
///
/// # Errors
/// The first [`Problem`].
pub fn check<S: TopCells + VertexStar + ?Sized>(s: &S) -> Result<(), Problem> {
    let mut first = None;
    validate(s).visit(|p| {
        first = Some(p);
        false
    });
    first.map_or(Ok(()), Err)
}

/// Every problem found, in [`ValidationReport::problems`] order.
///
/// ```
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// use starplex::algo::validate::errors;
/// use starplex::topo::naive::VtIndex;
/// let mut b = ComplexBuilder::new(1).unwrap();
/// for x in 0..5 { b.push_vertex(&[x as f64]).unwrap(); }
/// for c in [2, 3, 4] { b.push_cell(CellKind::Simplex(2), &[0, 1, c]).unwrap(); }
/// let k = b.build(&BuildOptions::default()).unwrap().0;
/// let e = errors(&VtIndex::new(&k));
/// assert_eq!(e.len(), 4); // the shared edge, its two vertices, the edge itself non-manifold
/// ```
pub fn errors<S: TopCells + VertexStar + ?Sized>(s: &S) -> Vec<Problem> {
    validate(s).problems()
}

#[cfg(test)]
mod tests {
    use super::Faces;
    use crate::ids::VertexId;

    /// Faces sorted as fixed-size keys come out as the report's lists sorted as vectors:
    /// lengths mixed (prefixes of one another, vertex 0 included, which the padding also is),
    /// and past four vertices by the vectors themselves.
    #[test]
    fn faces_sort_like_vectors() {
        let mut rng = crate::testkit::XorShift::new(11);
        for case in 0..200 {
            let most = if case % 4 == 0 { 6 } else { 4 };
            let mut faces = Faces::default();
            let mut want: Vec<Vec<VertexId>> = Vec::new();
            let map = |v: u32| (v * 7) % 5; // not monotone, and not one to one
            for _ in 0..rng.below(30) {
                let n = 1 + rng.below(most as u64) as usize;
                let f: Vec<u32> = (0..n).map(|_| rng.below(6) as u32).collect();
                faces.push(&f);
                let mut x: Vec<VertexId> = f.iter().map(|&v| VertexId(map(v))).collect();
                x.sort_unstable();
                want.push(x);
            }
            let mut other = Faces::default();
            other.push(&[3, 1]);
            faces.append(&other);
            want.push(vec![VertexId(map(3)), VertexId(map(1))]); // [1, 2]
            want.sort_unstable();
            let got = faces.into_sorted(map);
            let i = (0..want.len()).find(|&i| got.get(i) != want.get(i));
            assert_eq!(
                got,
                want,
                "case {case}: first difference at {i:?}: {:?} {:?}",
                i.map(|i| &got[i]),
                i.map(|i| &want[i])
            );
        }
    }
}
