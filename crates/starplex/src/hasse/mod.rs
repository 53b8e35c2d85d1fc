//! The CASC colored complex: a Hasse diagram with user data typed per dimension.
//!
//! Every simplex is a node; a `k`-simplex is linked down to its `k + 1` faces (keyed by the
//! vertex removed) and up to its cofaces (keyed by the vertex added). On top of that: search
//! and up/down traversal (Alg. 2 of the CASC paper), insertion with all faces (Alg. 1), removal
//! of a star, neighbours by shared face or coface (Alg. 3), k-rings, breadth-first visitors,
//! star / closure / link as [`NodeSet`]s with set algebra, generalized decimation (Def. 4.1,
//! Alg. 4) with a data callback, local edits (bistellar flips, stellar splits, link-checked
//! collapse, Laplacian smoothing), orientation (Alg. 5) and surface geometry.
//!
//! # Design of the typed data (DESIGN.md requirement 1)
//! The data types form a *level list*: a tuple such as `([f64; 3], (), i8)` (vertices, edges,
//! triangles), see [`levels`]. The complex `Hasse<L>` stores one `Vec` per tuple position.
//! Access is `h.data::<K>(id)`: the trait [`At<K>`] resolves the column at compile time, so an
//! access is a plain slice index: no downcast, no `Any`, no runtime type check. `()` levels and
//! dimensions past the tuple store nothing. Structural edits, which know the dimension only at
//! run time, call [`LevelTypes`] methods that `match` on it once per edit (macro-generated for tuples
//! of up to 12 types; any dimension of complex is allowed, data is typed on the first 12).
//! Decimation hands the data of the simplices that merge to a user callback implementing
//! [`Merge<K, T>`] per level (checked at compile time through [`MergeAll`]).
//! We chose this over pmp-style property keys (`PropKey<T>` per level with type-erased columns)
//! because erased columns need either a downcast when a column is borrowed or `unsafe` casts
//! guarded by branded keys; the tuple gives the same flexibility per level with plain generics.
//! Several values per level are a struct (or tuple) as that level's type.
//!
//! Visitors get the same treatment: [`Hasse::visit_typed_bfs_up`] hands each node to the
//! [`Visit<K, T>`] of its level with its typed data (dispatch by one `match` per node).
//!
//! # Memory layout
//! Nodes live per dimension in flat arrays: `k + 1` sorted vertex labels and `k + 1` face ids
//! per `k`-simplex (face `i` = the simplex without vertex `i`, i.e. down keyed by the vertex
//! removed), plus an 8-byte header into a per-level arena of `(vertex added, coface id)` pairs,
//! sorted by key, in power-of-two blocks reused through free lists. The vertex lookup is a dense
//! table (a hash map only for labels far above the vertex count); every other lookup walks up:
//! `find({a,b,c}) = up(up(vertex(a), b), c)`, a scan of a few pairs per step (binary search past
//! 8). No per-node heap allocation. A triangle mesh built from a file costs about 44 bytes per
//! simplex with all up and down incidences (`starplex bench-hasse FILE`).
//!
//! Ids are slots: removing a simplex frees its slot (kept on a free list and reused by the next
//! insertion), so ids of other simplices never change during edits; [`Hasse::compact`]
//! renumbers densely. Complexes of dimension at most 3 read from an
//! [`IndexedComplex`](crate::complex::IndexedComplex) are built level by level by sorting
//! facets (counting sort on the labels), which lays nodes out in lexicographic order.
//!
//! # Errata of the CASC paper found while reproducing it
//! * Section 5.1 prints `Link({3})` without `{0}`; `{0,1}` and `{0,5}` are in the link, so `{0}`
//!   is too (`examples/casc_link.rs`).
//! * Table 1, row 3 maps `{3,4,5} {3,5} {4,5}` to `{5,6}` (printed `{3,6}`); row 7 visits
//!   `{2,4}`, which maps to `{2,6}` (`examples/casc_decimate.rs`).
//!
//! ```
//! use starplex::hasse::{Hasse, KeepFirst};
//! use starplex::ids::VertexId;
//! let v = |i| VertexId(i);
//! // the constructed example of CASC Section 5.1
//! let mut h: Hasse<((), (), ())> = Hasse::new();
//! for t in [[0, 1, 3], [0, 3, 5], [1, 3, 4], [3, 4, 5], [1, 2, 4], [2, 4, 5]] {
//!     h.insert(&t.map(v)).unwrap();
//! }
//! let e = h.find(&[v(3), v(4)]).unwrap();
//! assert!(h.can_collapse(e).is_ok());
//! let lk = h.link(e);
//! assert_eq!(h.set_to_vertex_lists(&lk), vec![vec![1], vec![5]]);
//! let p = h.decimate(e, &mut KeepFirst).unwrap();
//! assert_eq!(p.0, 6);
//! assert_eq!(h.f_vector(), vec![5, 8, 4]);
//! assert!(h.is_valid());
//! ```

mod arena;
mod bulk;
mod check;
mod complex;
mod convert;
mod decimate;
mod edit;
mod geom;
mod insert;
pub mod levels;
mod navigate;
mod orient;
mod queries;
mod remove;
mod sets;
mod storage;

pub use complex::Hasse;
pub use convert::DotOptions;
pub use decimate::{DecimationGroup, DecimationPlan};
pub use edit::{EditError, Position};
pub use insert::MAX_INSERT_VERTICES;
pub use levels::{At, DefaultData, KeepFirst, LevelTypes, Merge, MergeAll, Visit, VisitAll};
pub use orient::{HasseOrientation, SurfaceGeometry};
pub use queries::HasseQueries;
pub use sets::{NodeMap, NodeSet};

use crate::ids::{SimplexId, VertexId};

/// A simplex of a [`Hasse`] complex: its dimension and its id within that dimension.
///
/// ```
/// use starplex::hasse::Node;
/// let n = Node::new(2, 5.into());
/// assert_eq!((n.dim, n.id.0), (2, 5));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Node {
    /// Dimension (number of vertices minus one).
    pub dim: u32,
    /// Position in its dimension's arrays.
    pub id: SimplexId,
}

impl Node {
    /// A node handle.
    ///
    /// ```
    /// assert_eq!(starplex::hasse::Node::new(0, 1.into()).dim, 0);
    /// ```
    pub const fn new(dim: u32, id: SimplexId) -> Node {
        Node { dim, id }
    }
}

fn fmt_verts(v: &[VertexId]) -> String {
    format!("{:?}", v.iter().map(|x| x.0).collect::<Vec<_>>())
}

/// Errors of the Hasse complex.
///
/// ```
/// use starplex::hasse::{Hasse, HasseError};
/// let mut h: Hasse = Hasse::new();
/// let e = h.insert(&[1.into(), 2.into(), 2.into()]).unwrap_err();
/// assert_eq!(e.to_string(), "simplex [1, 2, 2]: vertex 2 appears more than once (degenerate)");
/// ```
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum HasseError {
    /// A simplex with a repeated vertex.
    #[error("simplex {}: vertex {repeated} appears more than once (degenerate)", fmt_verts(.vertices))]
    Degenerate {
        /// The vertices given.
        vertices: Vec<VertexId>,
        /// The repeated one.
        repeated: VertexId,
    },
    /// An empty vertex list.
    #[error("a simplex needs at least one vertex")]
    Empty,
    /// Inserting would create too many faces.
    #[error(transparent)]
    TooLarge(#[from] crate::limits::TooLarge),
    /// The vertex count does not match the level of the data given.
    #[error("data for dimension {expected} given to a simplex of dimension {got}")]
    WrongDimension {
        /// Dimension of the data's level.
        expected: usize,
        /// Dimension of the simplex.
        got: usize,
    },
    /// No simplex with these vertices.
    #[error("no simplex with vertices {}", fmt_verts(.0))]
    NotFound(Vec<VertexId>),
    /// A node handle that is not in the complex.
    #[error("node {0:?} is not in the complex")]
    NotANode(Node),
    /// The label chosen for a new vertex is already used.
    #[error("vertex label {0} is already in use")]
    LabelInUse(VertexId),
    /// No label left for a new vertex.
    #[error("no free vertex label left")]
    NoFreeLabel,
    /// A broken invariant (from [`Hasse::check`]).
    #[error("invalid complex at {node:?}: {what}")]
    Invalid {
        /// The node where it was found.
        node: Node,
        /// What is wrong.
        what: String,
    },
    /// A cell of an input complex that is not a simplex.
    #[error(transparent)]
    NotSimplicial(#[from] crate::limits::NotSimplicial),
    /// Building an indexed complex failed.
    #[error(transparent)]
    Complex(#[from] crate::complex::ComplexError),
}

impl From<crate::tds::simplex_tree::BuildError> for HasseError {
    fn from(e: crate::tds::simplex_tree::BuildError) -> HasseError {
        match e {
            crate::tds::simplex_tree::BuildError::NotSimplicial(e) => HasseError::NotSimplicial(e),
            crate::tds::simplex_tree::BuildError::TooLarge(e) => HasseError::TooLarge(e),
        }
    }
}
