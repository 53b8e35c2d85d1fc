//! The IA* relations, one vocabulary for every structure that stores them: what lies across
//! each facet of a top cell (R_{k,k}), the non-manifold facets shared by three or more top
//! cells, and the per-vertex references (R_{0,1} and one top cell per k-cluster, R*_{0,k}).
//!
//! Both IA* builders implement [`FacetAdjacency`]: the standalone one
//! ([`crate::tds::iastar::IaStar`]) and the one generated from a Stellar tree, globally or for
//! one leaf ([`crate::stellar::iastar::StellarIaStar`]). They answer identically (held equal by
//! `tests/suite/stellar_iastar.rs`), in input numbering.
//!
//! Slot `j` of a simplex is the facet that omits its `j`-th vertex; a CP cell's slots follow
//! its facet table ([`crate::cell::CellKind::cp_faces`]). Top edges and top vertices have no
//! slots.
//!
//! ```
//! use starplex::complex::{ComplexBuilder, BuildOptions};
//! use starplex::cell::CellKind;
//! use starplex::ids::{CellId, VertexId};
//! use starplex::topo::{Adjacent, FacetAdjacency};
//! use starplex::tds::iastar::IaStar;
//! // the "book": three triangles on edge {0,1}, and a fourth triangle on edge {1,2}
//! let mut b = ComplexBuilder::new(2).unwrap();
//! for _ in 0..6 { b.push_vertex(&[0.0, 0.0]).unwrap(); }
//! for c in [[0, 1, 2], [0, 1, 3], [0, 1, 4], [1, 2, 5]] { b.push_cell(CellKind::Simplex(2), &c).unwrap(); }
//! let k = b.build(&BuildOptions::default()).unwrap().0;
//! fn nm_edges<A: FacetAdjacency>(a: &A) -> Vec<Vec<VertexId>> {
//!     (0..a.n_nm_faces() as u32).map(|f| a.nm_face_vertices(f)).collect()
//! }
//! let ia = IaStar::new(&k).unwrap();
//! assert_eq!(nm_edges(&ia), vec![vec![VertexId(0), VertexId(1)]]);
//! // facet 0 of [0, 1, 2] omits vertex 0: the edge {1,2}, shared with triangle 3
//! assert_eq!(ia.facet_adjacent(CellId(0), 0), Adjacent::Top(CellId(3)));
//! assert_eq!(ia.facet_adjacent(CellId(0), 2), Adjacent::NmFace(0));
//! assert_eq!(ia.top_adjacent(CellId(0)), vec![CellId(1), CellId(2), CellId(3)]);
//! ```
use crate::ids::{CellId, VertexId};

/// What lies across one facet of a top cell.
///
/// ```
/// use starplex::topo::Adjacent;
/// use starplex::ids::CellId;
/// let a = Adjacent::Top(CellId(4));
/// assert_eq!(a.top(), Some(CellId(4)));
/// assert_eq!(Adjacent::NmFace(0).top(), None);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Adjacent {
    /// The facet is in no other top cell of the same dimension.
    None,
    /// The facet is shared with exactly this other top cell.
    Top(CellId),
    /// The facet is shared by three or more top cells: its id among the structure's
    /// non-manifold facets ([`FacetAdjacency::nm_face_cells`]).
    NmFace(u32),
    /// Partial structures only (the IA* of one Stellar leaf): the facet has no vertex in the
    /// part, so it was not examined.
    NotComputed,
}

impl Adjacent {
    /// The one other top cell, for [`Adjacent::Top`].
    ///
    /// ```
    /// use starplex::topo::Adjacent;
    /// assert_eq!(Adjacent::None.top(), None);
    /// ```
    pub fn top(self) -> Option<CellId> {
        match self {
            Adjacent::Top(c) => Some(c),
            _ => None,
        }
    }
}

/// The IA* relations of a structure: facet slots, non-manifold facets, vertex references.
///
/// ```
/// use starplex::complex::{ComplexBuilder, BuildOptions};
/// use starplex::cell::CellKind;
/// use starplex::ids::{CellId, VertexId};
/// use starplex::topo::{Adjacent, FacetAdjacency};
/// use starplex::stellar::{StellarTree, StellarOptions};
/// let mut b = ComplexBuilder::new(2).unwrap();
/// for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
/// let k = b.build(&BuildOptions::default()).unwrap().0;
/// let t = StellarTree::build(&k, &StellarOptions::default()).unwrap();
/// let ia = t.iastar();
/// assert_eq!(ia.n_facet_slots(CellId(0)), 3);
/// assert_eq!(ia.facet_adjacency(CellId(1)), vec![Adjacent::None, Adjacent::Top(CellId(0)), Adjacent::None]);
/// assert_eq!(ia.vertex_references(VertexId(3)), vec![CellId(1)]);
/// assert_eq!(ia.n_nm_faces(), 0);
/// ```
pub trait FacetAdjacency {
    /// Number of facet slots of top cell `c`: its facet count for dimension ≥ 2, 0 below (and
    /// 0 for a cell the structure does not cover or does not have).
    fn n_facet_slots(&self, c: CellId) -> usize;
    /// What lies across facet slot `j` of top cell `c` ([`Adjacent::None`] for a slot or cell
    /// that does not exist).
    fn facet_adjacent(&self, c: CellId, j: usize) -> Adjacent;
    /// Number of non-manifold facets (ids `0..n`, over all dimensions).
    fn n_nm_faces(&self) -> usize;
    /// The top cells of non-manifold facet `f`, sorted (empty for an id out of range).
    fn nm_face_cells(&self, f: u32) -> Vec<CellId>;
    /// The vertices of non-manifold facet `f`, sorted (empty for an id out of range).
    fn nm_face_vertices(&self, f: u32) -> Vec<VertexId>;
    /// The stored references of vertex `v`: every top edge at `v` and one top k-cell per
    /// k-cluster of `v` (k ≥ 2, the cluster's smallest id), sorted.
    fn vertex_references(&self, v: VertexId) -> Vec<CellId>;

    /// Every slot of top cell `c`, in slot order.
    fn facet_adjacency(&self, c: CellId) -> Vec<Adjacent> {
        (0..self.n_facet_slots(c))
            .map(|j| self.facet_adjacent(c, j))
            .collect()
    }
    /// R_{k,k}: the top cells sharing a facet with top cell `c`, sorted, without `c`.
    fn top_adjacent(&self, c: CellId) -> Vec<CellId> {
        let mut out = Vec::new();
        for j in 0..self.n_facet_slots(c) {
            match self.facet_adjacent(c, j) {
                Adjacent::Top(u) => out.push(u),
                Adjacent::NmFace(f) => out.extend(self.nm_face_cells(f)),
                Adjacent::None | Adjacent::NotComputed => {}
            }
        }
        out.retain(|&u| u != c);
        out.sort_unstable();
        out.dedup();
        out
    }
}
