//! The shared query vocabulary (the Mangrove interface): small capability traits, one question
//! each, in the style of petgraph's `visit`. Every data structure implements the ones it answers
//! efficiently; algorithms are written once against them.
//!
//! Answers are always in the *input* numbering of the [`IndexedComplex`] the structure was built
//! from (a structure that renumbers internally, like the Stellar tree, maps back), and lists are
//! sorted, so different structures can be compared with `==`.
//!
//! | trait | question |
//! |---|---|
//! | [`TopCells`] | counts, the vertices and kind of a top cell |
//! | [`VertexStar`] | R_{0,top}: the top cells incident to a vertex (VT) |
//! | [`VertexAdjacency`] | R_{0,0}: the vertices joined to a vertex by an edge (VV) |
//!
//! Generic algorithms on top: [`link::vertex_link`].
//!
//! ```
//! use starplex::complex::{ComplexBuilder, BuildOptions};
//! use starplex::cell::CellKind;
//! use starplex::ids::VertexId;
//! use starplex::topo::{VertexStar, VertexAdjacency, naive::VtIndex, link::vertex_link};
//! let mut b = ComplexBuilder::new(2).unwrap();
//! for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
//! b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
//! b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
//! let k = b.build(&BuildOptions::default()).unwrap().0;
//! let idx = VtIndex::new(&k);
//! let mut cells = Vec::new();
//! idx.vertex_top_cells(VertexId(1), &mut cells);
//! assert_eq!(cells.len(), 2);
//! let mut vv = Vec::new();
//! idx.vertex_neighbours(VertexId(1), &mut vv);
//! assert_eq!(vv, vec![VertexId(0), VertexId(2), VertexId(3)]);
//! let l = vertex_link(&idx, VertexId(1)).unwrap();
//! assert_eq!(l.f_vector, vec![3, 2]);
//! ```
use crate::cell::CellKind;
use crate::ids::{CellId, VertexId};

pub mod link;
pub mod naive;

/// Counts and top-cell access.
pub trait TopCells {
    /// Number of vertices.
    fn n_vertices(&self) -> usize;
    /// Number of top cells.
    fn n_top_cells(&self) -> usize;
    /// Kind of top cell `c`.
    fn top_cell_kind(&self, c: CellId) -> CellKind;
    /// Appends the vertices of top cell `c` (input numbering, the kind's vertex order) to `out`.
    fn top_cell_vertices(&self, c: CellId, out: &mut Vec<VertexId>);
}

/// R_{0,top}: top cells incident to a vertex.
pub trait VertexStar {
    /// Replaces `out` with the top cells incident to `v`, sorted by id.
    fn vertex_top_cells(&self, v: VertexId, out: &mut Vec<CellId>);
}

/// R_{0,0}: vertices joined to a vertex by an edge (an edge of a top cell's face table; the
/// diagonal of a quad is not an edge).
pub trait VertexAdjacency {
    /// Replaces `out` with the neighbours of `v`, sorted.
    fn vertex_neighbours(&self, v: VertexId, out: &mut Vec<VertexId>);
}
