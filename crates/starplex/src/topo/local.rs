//! A *part* of a complex that holds the whole star of every vertex it owns: a leaf of a
//! Stellar tree (its vertices and every top cell incident to them), one rank of
//! `starplex-mpi` (owned vertices and their ghost cells), or the whole complex.
//!
//! The processing paradigm of the Stellar paper runs an algorithm part by part; written
//! against [`LocalStar`], the algorithm is the same for a leaf and for a whole complex
//! (e.g. [`crate::algo::manifold::local_singularities`]). A part answers in its own
//! numbering (typed ids: a leaf answers [`TreeVertexId`](crate::ids::TreeVertexId) and
//! [`TreeCellId`](crate::ids::TreeCellId)) and converts to the input numbering on request.
//!
//! ```
//! use starplex::topo::{naive::VtIndex, LocalStar};
//! use starplex::ids::{CellId, VertexId};
//! # use starplex::complex::{ComplexBuilder, BuildOptions};
//! # use starplex::cell::CellKind;
//! # let mut b = ComplexBuilder::new(2).unwrap();
//! # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
//! # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
//! # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
//! # let k = b.build(&BuildOptions::default()).unwrap().0;
//! // k: the triangles 0-1-2 and 1-3-2; the whole complex is one part owning every vertex
//! let idx = VtIndex::new(&k);
//! let degrees: Vec<usize> = idx.owned_vertices().map(|v| idx.local_star(v).len()).collect();
//! assert_eq!(degrees, [1, 2, 2, 1]);
//! assert_eq!(idx.local_cell(CellId(1)).1, [VertexId(1), VertexId(3), VertexId(2)]);
//! ```

use crate::cell::CellKind;
use crate::ids::{CellId, VertexId};

/// An id a part answers in: a `u32` newtype (all the ids of [`crate::ids`]), so that the
/// shared algorithms can read a cell's vertices as plain `u32` without copying.
///
/// ```
/// use starplex::topo::LocalId;
/// use starplex::ids::TreeVertexId;
/// fn raw<I: LocalId>(i: I) -> u32 { i.into() }
/// assert_eq!(raw(TreeVertexId(4)), 4);
/// ```
pub trait LocalId:
    Copy + Ord + std::hash::Hash + std::fmt::Debug + bytemuck::Pod + From<u32> + Into<u32>
{
}

impl<T> LocalId for T where
    T: Copy + Ord + std::hash::Hash + std::fmt::Debug + bytemuck::Pod + From<u32> + Into<u32>
{
}

/// A part of a complex holding the complete star (every incident top cell) of each vertex it
/// owns: a Stellar tree leaf ([`LeafView`](crate::stellar::LeafView), in tree numbering), one
/// rank of `starplex-mpi`, or a whole complex ([`VtIndex`](crate::topo::naive::VtIndex), in
/// input numbering). Algorithms written against it run part by part, e.g.
/// [`local_singularities`](crate::algo::manifold::local_singularities).
///
/// ```
/// use starplex::topo::LocalStar;
/// use starplex::stellar::{StellarTree, StellarOptions};
/// use starplex::ids::VertexId;
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// let t = StellarTree::build(&k, &StellarOptions { kv: Some(1), ..Default::default() }).unwrap();
/// // the sum of |VT(v)| over all vertices, one leaf at a time, in parallel
/// let per_leaf: Vec<usize> =
///     t.par_map_leaves(|leaf| leaf.owned_vertices().map(|v| leaf.local_star(v).len()).sum());
/// assert_eq!(per_leaf.iter().sum::<usize>(), 6);
/// ```
pub trait LocalStar {
    /// The part's vertex ids.
    type Vertex: LocalId;
    /// The part's top-cell ids.
    type Cell: LocalId;

    /// The vertices the part owns, increasing.
    fn owned_vertices(&self) -> impl Iterator<Item = Self::Vertex> + '_;
    /// True when the part owns `v` (its star is complete in the part).
    fn owns(&self, v: Self::Vertex) -> bool;
    /// Every top cell the part holds (each incident to an owned vertex), increasing.
    fn local_top_cells(&self) -> impl Iterator<Item = Self::Cell> + '_;
    /// The top cells incident to the owned vertex `v`, increasing. The answer for a vertex the
    /// part does not own is unspecified (it may panic).
    fn local_star(&self, v: Self::Vertex) -> &[Self::Cell];
    /// Kind and vertices (the kind's vertex order) of a top cell the part holds.
    fn local_cell(&self, c: Self::Cell) -> (CellKind, &[Self::Vertex]);
    /// The kind of every top cell, when the part knows that they all share one (a shortcut
    /// for algorithms; `None` says nothing).
    fn uniform_kind(&self) -> Option<CellKind> {
        None
    }
    /// Input id of a vertex of the part.
    fn input_vertex(&self, v: Self::Vertex) -> VertexId;
    /// Input id of a top cell of the part.
    fn input_cell(&self, c: Self::Cell) -> CellId;
}

/// The star of one owned vertex of a part, as the shared star tests read it (the part's
/// numbering, as plain `u32`).
pub(crate) struct PartStar<'a, P: LocalStar + ?Sized> {
    pub(crate) part: &'a P,
    pub(crate) star: &'a [P::Cell],
}

impl<P: LocalStar + ?Sized> crate::algo::manifold::StarCells for PartStar<'_, P> {
    #[inline(always)]
    fn len(&self) -> usize {
        self.star.len()
    }
    #[inline(always)]
    fn cell(&self, i: usize) -> (CellKind, &[u32]) {
        let (kind, vs) = self.part.local_cell(self.star[i]);
        (kind, bytemuck::cast_slice(vs))
    }
    fn all_of(&self, kind: CellKind) -> bool {
        match self.part.uniform_kind() {
            Some(k) => k == kind,
            None => self.star.iter().all(|&c| self.part.local_cell(c).0 == kind),
        }
    }
}
