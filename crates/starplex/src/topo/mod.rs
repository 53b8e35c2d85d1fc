//! The shared query vocabulary (the Mangrove interface): small capability traits, one question
//! each, in the style of petgraph's `visit`. Every data structure implements the ones it answers
//! efficiently; algorithms are written once against them.
//!
//! Answers are always in the *input* numbering of the [`IndexedComplex`](crate::complex::IndexedComplex)
//! the structure was built from (a structure that renumbers internally maps back), simplices are
//! sorted vertex tuples, and lists are sorted, so different structures can be compared with `==`.
//! A list of p-simplices is a flat `Vec<VertexId>` with stride p+1, sorted lexicographically and
//! without repeats; a mixed set is a [`SimplexSet`] (one such list per dimension).
//!
//! | trait | question |
//! |---|---|
//! | [`TopCells`] | counts, the vertices and kind of a top cell |
//! | [`VertexStar`] | R_{0,top}: the top cells incident to a vertex (VT) |
//! | [`VertexAdjacency`] | R_{0,0}: the vertices joined to a vertex by an edge (VV) |
//! | [`TopStar`] | St_T(σ): the top cells containing any simplex σ |
//! | [`Counts`] | the f-vector: number of simplices per dimension |
//! | [`SimplexVertices`] | vertices of an explicitly stored simplex, and its id from its vertices |
//! | [`Boundary`] | R_{p,q}, q < p: the q-faces of σ |
//! | [`Coboundary`] | R_{p,q}, q > p: the q-simplices having σ as a face |
//! | [`Adjacency`] | R_{p,p}: p-simplices sharing a (p-1)-face with σ (p = 0: an edge) |
//! | [`Star`] | St(σ): every simplex containing σ |
//! | [`Levels`] | iteration over the p-simplices, level by level |
//! | [`Storage`] | size in references and bytes |
//! | [`LocalStar`] | a part (a Stellar leaf, an MPI rank, the whole complex) holding the whole star of each vertex it owns |
//!
//! Generic algorithms written once against them: [`generic`] (closure, link, skeleton,
//! Euler characteristic), [`link::vertex_link`], [`crate::algo::components`],
//! [`crate::algo::manifold`], [`crate::algo::validate`], [`crate::algo::orientation`].
//!
//! Which structure implements which trait (✓ native, g = through the generic top-star helpers
//! of [`from_tops`], – = not implemented). Structures that store every simplex (simplex tree,
//! incidence graph, IS, Hasse) refuse to build, with an estimate, when the complex has more simplices
//! than their limit (a 40-simplex has 2^41 - 1 faces); the others answer top-cell queries in
//! any dimension and refuse face enumerations over [`DEFAULT_BUDGET`] with
//! [`QueryError::TooLarge`]. The simplex tree, incidence graph, IS and Hasse keep no orientation:
//! their [`TopCells::top_cell_vertices`] are sorted.
//!
//! | structure | TopCells | VertexStar | VertexAdjacency | TopStar | Counts | SimplexVertices | Boundary | Coboundary | Adjacency | Star | Levels | Storage |
//! |---|---|---|---|---|---|---|---|---|---|---|---|---|
//! | [`naive::VtIndex`] (baseline) | ✓ | ✓ | ✓ | g | g | – | g | g | g | g | g | ✓ |
//! | [`IaStar`](crate::tds::iastar::IaStar) | ✓ | ✓ | ✓ | g | g | – | g | g | g | g | g | ✓ |
//! | [`SimplexTree`](crate::tds::simplex_tree::SimplexTree) | ✓ | ✓ | ✓ | ✓ | ✓ | ✓ | ✓ | ✓ | ✓ | ✓ | ✓ | ✓ |
//! | [`IncidenceGraph`](crate::tds::ig::IncidenceGraph) | ✓ | ✓ | ✓ | ✓ | ✓ | ✓ | ✓ | ✓ | ✓ | ✓ | ✓ | ✓ |
//! | [`Is`](crate::tds::is::Is) | ✓ | ✓ | ✓ | ✓ | ✓ | ✓ | ✓ | ✓ | ✓ | ✓ | ✓ | ✓ |
//! | [`HasseQueries`](crate::hasse::HasseQueries) (CASC) | ✓ | ✓ | ✓ | ✓ | ✓ | ✓ | ✓ | ✓ | ✓ | ✓ | ✓ | ✓ |
//! | [`StellarTree`](crate::stellar::StellarTree) | ✓ | ✓ | ✓ | g | g | – | g | g | g | g | g | ✓ |
//!
//! **CP complexes** (quads, pyramids, prisms, hexahedra, mixed with simplices): the simplex
//! tree, IS and the Hasse diagram refuse to build. The others hold them, with the cells of the
//! kinds' face tables (a quad's diagonal is not an edge), and name a cell by its canonical key,
//! its sorted vertices (so a list of p-cells may mix sizes: triangles and quads). VtIndex, IA*
//! and the Stellar tree answer [`TopCells`], [`VertexStar`], [`VertexAdjacency`] and
//! [`TopStar`]; their generic (g) face enumerations refuse a star holding a CP cell with
//! [`QueryError::NotSimplicial`] (IA*'s ghosts answer boundary, co-boundary and adjacency on CP
//! cells). The incidence graph stores every cell and answers every trait: [`Counts`] counts
//! cells per dimension, [`SimplexVertices`] takes and gives keys of any length, and the
//! relations written as flat (p+1)-vertex tuples ([`Boundary`], [`Coboundary`], [`Adjacency`],
//! [`Star`], [`Levels`]) answer when the cells listed are simplices and refuse with
//! [`QueryError::NotSimplicial`], naming the quad or 3-cell, otherwise; its id-based
//! `cell_faces`, `cell_cofaces` and `cell_adjacent` answer all of them.
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
use crate::ids::{CellId, SimplexId, VertexId};

pub mod batch;
mod facets;
pub mod from_tops;
pub mod generic;
pub mod link;
mod local;
pub mod naive;
pub(crate) mod sortnet;

pub use facets::{Adjacent, FacetAdjacency};
pub(crate) use local::PartStar;
pub use local::{LocalId, LocalStar};

/// Default budget of simplices a query may enumerate before refusing with an estimate.
///
/// ```
/// use starplex::topo::{naive::VtIndex, QueryError, Star, DEFAULT_BUDGET};
/// use starplex::ids::VertexId;
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// // One 30-simplex: the star of a vertex has 2^30 simplices, refused before enumerating any.
/// let mut b = ComplexBuilder::new(1).unwrap();
/// for x in 0..31 { b.push_vertex(&[x as f64]).unwrap(); }
/// b.push_cell(CellKind::Simplex(30), &(0..31).collect::<Vec<u32>>()).unwrap();
/// let k = b.build(&BuildOptions::default()).unwrap().0;
/// let err = VtIndex::new(&k).star(&[VertexId(0)]).unwrap_err();
/// assert!(matches!(err, QueryError::TooLarge(t) if t.budget as u128 == DEFAULT_BUDGET));
/// ```
pub const DEFAULT_BUDGET: u128 = crate::limits::QUERY_SIMPLICES;

/// Why a query could not be answered.
///
/// ```
/// use starplex::topo::{naive::VtIndex, QueryError, TopStar};
/// use starplex::ids::VertexId;
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// // k: the triangles 0-1-2 and 1-3-2, sharing the edge 1-2
/// let mut cells = Vec::new();
/// let err = VtIndex::new(&k).top_star(&[VertexId(0), VertexId(3)], &mut cells).unwrap_err();
/// assert_eq!(err, QueryError::NotInComplex(vec![0, 3]));
/// assert_eq!(err.to_string(), "[0, 3] is not a simplex of the complex");
/// ```
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum QueryError {
    /// The simplex is not in the complex (or has a vertex out of range, or a repeated vertex).
    #[error("{0:?} is not a simplex of the complex")]
    NotInComplex(Vec<u32>),
    /// The answer would exceed the budget.
    #[error(transparent)]
    TooLarge(#[from] crate::limits::TooLarge),
    /// The question is answered for simplicial complexes only.
    #[error("{0}: the complex holds non-simplicial cells; this query needs simplices")]
    NotSimplicial(String),
}

/// Counts and top-cell access.
///
/// ```
/// use starplex::topo::{naive::VtIndex, TopCells};
/// use starplex::ids::{CellId, VertexId};
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// // k: the triangles 0-1-2 and 1-3-2, sharing the edge 1-2
/// let idx = VtIndex::new(&k);
/// assert_eq!((idx.n_vertices(), idx.n_top_cells()), (4, 2));
/// assert_eq!(idx.top_cell_kind(CellId(1)), starplex::cell::CellKind::Simplex(2));
/// let mut vs = Vec::new();
/// idx.top_cell_vertices(CellId(1), &mut vs);
/// assert_eq!(vs, [VertexId(1), VertexId(3), VertexId(2)]); // input order
/// ```
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
///
/// ```
/// use starplex::topo::{naive::VtIndex, VertexStar};
/// use starplex::ids::{CellId, VertexId};
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// // k: the triangles 0-1-2 and 1-3-2, sharing the edge 1-2
/// let idx = VtIndex::new(&k);
/// let mut cells = Vec::new();
/// idx.vertex_top_cells(VertexId(2), &mut cells);
/// assert_eq!(cells, [CellId(0), CellId(1)]);
/// idx.vertex_top_cells(VertexId(3), &mut cells);
/// assert_eq!(cells, [CellId(1)]);
/// assert_eq!(idx.star_has_top_containing(&[VertexId(0), VertexId(3)]), Some(false));
/// ```
pub trait VertexStar {
    /// Replaces `out` with the top cells incident to `v`, sorted by id.
    fn vertex_top_cells(&self, v: VertexId, out: &mut Vec<CellId>);

    /// [`vertex_top_cells`](Self::vertex_top_cells) of every vertex at once (row `v`), when the
    /// structure makes them faster all together than one at a time (the Stellar tree decodes
    /// each leaf once); `None` (the default) otherwise. Bulk answers use it.
    ///
    /// ```
    /// use starplex::topo::{naive::VtIndex, VertexStar};
    /// use starplex::stellar::{StellarTree, StellarOptions};
    /// use starplex::ids::VertexId;
    /// let k = starplex::generate::kuhn_grid(&[2, 2]).unwrap();
    /// assert!(VtIndex::new(&k).vertex_top_rows().is_none());
    /// let t = StellarTree::build(&k, &StellarOptions::default()).unwrap();
    /// let (rows, mut cells) = (t.vertex_top_rows().unwrap(), Vec::new());
    /// t.vertex_top_cells(VertexId(4), &mut cells);
    /// assert_eq!(rows.row(4), cells.iter().map(|c| c.0).collect::<Vec<u32>>());
    /// ```
    fn vertex_top_rows(&self) -> Option<crate::csr::Csr> {
        None
    }

    /// A fast membership answer: `Some(true)` when some top cell incident to `s[0]` contains
    /// the sorted simplex `s` (at least two vertices), `Some(false)` when none does, `None`
    /// when the structure has no faster way than scanning VT(`s[0]`) (the default).
    fn star_has_top_containing(&self, s: &[VertexId]) -> Option<bool> {
        let _ = s;
        None
    }
}

/// R_{0,0}: vertices joined to a vertex by an edge (an edge of a top cell's face table; the
/// diagonal of a quad is not an edge).
///
/// ```
/// use starplex::topo::{naive::VtIndex, VertexAdjacency};
/// use starplex::{cell::CellKind, ids::VertexId};
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// let mut b = ComplexBuilder::new(2).unwrap();
/// for p in [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// b.push_cell(CellKind::Quad, &[0, 1, 2, 3]).unwrap();
/// let k = b.build(&BuildOptions::default()).unwrap().0;
/// let mut vv = Vec::new();
/// VtIndex::new(&k).vertex_neighbours(VertexId(0), &mut vv);
/// assert_eq!(vv, [VertexId(1), VertexId(3)]); // not 2: the diagonal is not an edge
/// ```
pub trait VertexAdjacency {
    /// Replaces `out` with the neighbours of `v`, sorted.
    fn vertex_neighbours(&self, v: VertexId, out: &mut Vec<VertexId>);

    /// [`vertex_neighbours`](Self::vertex_neighbours) of every vertex at once (row `v`), when
    /// the structure makes them faster all together; `None` (the default) otherwise.
    ///
    /// ```
    /// use starplex::topo::{naive::VtIndex, VertexAdjacency};
    /// use starplex::stellar::{StellarTree, StellarOptions};
    /// use starplex::ids::VertexId;
    /// let k = starplex::generate::kuhn_grid(&[2, 2]).unwrap();
    /// assert!(VtIndex::new(&k).vertex_neighbour_rows().is_none());
    /// let t = StellarTree::build(&k, &StellarOptions::default()).unwrap();
    /// let (rows, mut vv) = (t.vertex_neighbour_rows().unwrap(), Vec::new());
    /// t.vertex_neighbours(VertexId(4), &mut vv);
    /// assert_eq!(rows.row(4), vv.iter().map(|v| v.0).collect::<Vec<u32>>());
    /// assert_eq!(vv.len(), 6); // the centre of the grid
    /// ```
    fn vertex_neighbour_rows(&self) -> Option<crate::csr::Csr> {
        None
    }
}

/// St_T(σ): the top cells containing a simplex (any dimension).
///
/// ```
/// use starplex::topo::{naive::VtIndex, TopStar};
/// use starplex::ids::{CellId, VertexId};
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// // k: the triangles 0-1-2 and 1-3-2, sharing the edge 1-2
/// let mut cells = Vec::new();
/// VtIndex::new(&k).top_star(&[VertexId(2), VertexId(1)], &mut cells).unwrap();
/// assert_eq!(cells, [CellId(0), CellId(1)]);
/// ```
pub trait TopStar {
    /// Replaces `out` with the top cells containing `s` (vertices in any order), sorted by id.
    ///
    /// # Errors
    /// [`QueryError::NotInComplex`] when `s` is not a simplex of the complex.
    fn top_star(&self, s: &[VertexId], out: &mut Vec<CellId>) -> Result<(), QueryError>;
}

/// The f-vector.
///
/// ```
/// use starplex::topo::{naive::VtIndex, Counts};
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// // k: the triangles 0-1-2 and 1-3-2, sharing the edge 1-2
/// assert_eq!(VtIndex::new(&k).f_vector().unwrap(), vec![4, 5, 2]);
/// ```
pub trait Counts {
    /// Number of p-simplices for p = 0..=dim (vertices include isolated ones).
    ///
    /// # Errors
    /// [`QueryError::TooLarge`] when counting would enumerate too many faces.
    fn f_vector(&self) -> Result<Vec<u64>, QueryError>;
}

/// Explicitly stored simplices: id ↔ vertices.
///
/// ```
/// use starplex::topo::SimplexVertices;
/// use starplex::tds::simplex_tree::{SimplexTree, SimplexTreeOptions};
/// use starplex::ids::VertexId;
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// // k: the triangles 0-1-2 and 1-3-2, sharing the edge 1-2
/// let st = SimplexTree::new(&k, &SimplexTreeOptions::default()).unwrap();
/// assert_eq!(st.n_simplices(), 4 + 5 + 2);
/// let id = st.find_simplex(&[VertexId(2), VertexId(1)]).unwrap();
/// let mut vs = Vec::new();
/// st.simplex_vertices(id, &mut vs);
/// assert_eq!(vs, [VertexId(1), VertexId(2)]);
/// assert_eq!(st.find_simplex(&[VertexId(0), VertexId(3)]), None);
/// ```
pub trait SimplexVertices {
    /// Number of stored simplices.
    fn n_simplices(&self) -> usize;
    /// Replaces `out` with the sorted vertices of simplex `s`.
    fn simplex_vertices(&self, s: SimplexId, out: &mut Vec<VertexId>);
    /// The id of the simplex with these vertices (any order), if stored.
    fn find_simplex(&self, verts: &[VertexId]) -> Option<SimplexId>;
}

/// R_{p,q}, q < p: the q-faces of a p-simplex.
///
/// ```
/// use starplex::topo::{naive::VtIndex, Boundary};
/// use starplex::ids::VertexId;
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// // k: the triangles 0-1-2 and 1-3-2, sharing the edge 1-2
/// # let v = |x: &[u32]| x.iter().map(|&i| VertexId(i)).collect::<Vec<_>>();
/// let mut out = Vec::new();
/// VtIndex::new(&k).boundary(&v(&[2, 1, 0]), 1, &mut out).unwrap();
/// assert_eq!(out, v(&[0, 1, 0, 2, 1, 2])); // three edges, stride 2
/// ```
pub trait Boundary {
    /// Replaces `out` with the q-faces of `s` (flat, stride q+1, sorted).
    ///
    /// # Errors
    /// `s` not in the complex; `q >= dim s`; an answer over the budget.
    fn boundary(&self, s: &[VertexId], q: usize, out: &mut Vec<VertexId>)
        -> Result<(), QueryError>;
}

/// R_{p,q}, q > p: the q-simplices having a p-simplex as a face.
///
/// ```
/// use starplex::topo::{naive::VtIndex, Coboundary};
/// use starplex::ids::VertexId;
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// // k: the triangles 0-1-2 and 1-3-2, sharing the edge 1-2
/// # let v = |x: &[u32]| x.iter().map(|&i| VertexId(i)).collect::<Vec<_>>();
/// let idx = VtIndex::new(&k);
/// let mut out = Vec::new();
/// idx.coboundary(&v(&[1]), 1, &mut out).unwrap();
/// assert_eq!(out, v(&[0, 1, 1, 2, 1, 3])); // edges at vertex 1
/// idx.coboundary(&v(&[1, 2]), 2, &mut out).unwrap();
/// assert_eq!(out, v(&[0, 1, 2, 1, 2, 3])); // triangles on edge 1-2
/// ```
pub trait Coboundary {
    /// Replaces `out` with the q-cofaces of `s` (flat, stride q+1, sorted).
    ///
    /// # Errors
    /// `s` not in the complex; an answer over the budget.
    fn coboundary(
        &self,
        s: &[VertexId],
        q: usize,
        out: &mut Vec<VertexId>,
    ) -> Result<(), QueryError>;
}

/// R_{p,p}: for p ≥ 1 the p-simplices sharing a (p-1)-face with σ; for p = 0 the vertices
/// sharing an edge with σ.
///
/// ```
/// use starplex::topo::{naive::VtIndex, Adjacency};
/// use starplex::ids::VertexId;
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// // k: the triangles 0-1-2 and 1-3-2, sharing the edge 1-2
/// # let v = |x: &[u32]| x.iter().map(|&i| VertexId(i)).collect::<Vec<_>>();
/// let idx = VtIndex::new(&k);
/// let mut out = Vec::new();
/// idx.adjacent(&v(&[0, 1, 2]), &mut out).unwrap();
/// assert_eq!(out, v(&[1, 2, 3])); // shares the edge 1-2
/// idx.adjacent(&v(&[0]), &mut out).unwrap();
/// assert_eq!(out, v(&[1, 2]));
/// ```
pub trait Adjacency {
    /// Replaces `out` with the simplices adjacent to `s` (flat, stride p+1, sorted).
    ///
    /// # Errors
    /// `s` not in the complex; an answer over the budget.
    fn adjacent(&self, s: &[VertexId], out: &mut Vec<VertexId>) -> Result<(), QueryError>;
}

/// St(σ): every simplex containing σ (σ included).
///
/// ```
/// use starplex::topo::{naive::VtIndex, Star};
/// use starplex::ids::VertexId;
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// // k: the triangles 0-1-2 and 1-3-2, sharing the edge 1-2
/// # let v = |x: &[u32]| x.iter().map(|&i| VertexId(i)).collect::<Vec<_>>();
/// let st = VtIndex::new(&k).star(&v(&[0])).unwrap();
/// assert_eq!(st.f_vector(), vec![1, 2, 1]); // 0, 0-1, 0-2, 0-1-2
/// assert!(st.contains(&v(&[0, 1, 2])));
/// ```
pub trait Star {
    /// The star of `s`.
    ///
    /// # Errors
    /// `s` not in the complex; a star over the budget.
    fn star(&self, s: &[VertexId]) -> Result<SimplexSet, QueryError>;
}

/// Iteration by level.
///
/// ```
/// use starplex::topo::{naive::VtIndex, Levels};
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// // k: the triangles 0-1-2 and 1-3-2, sharing the edge 1-2
/// let mut edges = Vec::new();
/// VtIndex::new(&k).for_each_simplex(1, &mut |e| edges.push([e[0].0, e[1].0])).unwrap();
/// edges.sort();
/// assert_eq!(edges, [[0, 1], [0, 2], [1, 2], [1, 3], [2, 3]]);
/// ```
pub trait Levels {
    /// Calls `f` once per p-simplex (sorted vertices), in an order fixed by the structure.
    ///
    /// # Errors
    /// [`QueryError::TooLarge`] when the level would enumerate more than the budget.
    fn for_each_simplex(&self, p: usize, f: &mut dyn FnMut(&[VertexId])) -> Result<(), QueryError>;

    /// Every p-simplex, flat (`p + 1` vertex ids each), in
    /// [`for_each_simplex`](Self::for_each_simplex)'s order; the structures built from their
    /// top cells list the vertices' ranges in parallel.
    ///
    /// ```
    /// use starplex::topo::{naive::VtIndex, Levels};
    /// let k = starplex::generate::kuhn_grid(&[1, 1]).unwrap(); // two triangles
    /// assert_eq!(VtIndex::new(&k).faces_flat(2).unwrap().len(), 2 * 3);
    /// ```
    ///
    /// # Errors
    /// As [`for_each_simplex`](Self::for_each_simplex).
    fn faces_flat(&self, p: usize) -> Result<Vec<u32>, QueryError> {
        let mut out = Vec::new();
        self.for_each_simplex(p, &mut |x| out.extend(x.iter().map(|v| v.0)))?;
        Ok(out)
    }
}

/// Size of a structure.
///
/// ```
/// use starplex::topo::{naive::VtIndex, Storage};
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// // k: the triangles 0-1-2 and 1-3-2, sharing the edge 1-2
/// let idx = VtIndex::new(&k);
/// // 6 vertex references in the triangles, 6 (vertex, triangle) pairs in VT.
/// assert_eq!(idx.refs(), 12);
/// assert!(idx.bytes() >= 4 * idx.refs());
/// ```
pub trait Storage {
    /// Topological references stored (the papers' unit; coordinates and auxiliary indexes are
    /// not counted).
    fn refs(&self) -> u64;
    /// Bytes actually allocated for the topology (everything the structure owns but
    /// coordinates).
    fn bytes(&self) -> u64;
}

/// Every query of the interface: what the CLI needs of a structure.
///
/// ```
/// use starplex::topo::{naive::VtIndex, Queries};
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// // k: the triangles 0-1-2 and 1-3-2, sharing the edge 1-2
/// fn summary<Q: Queries>(q: &Q) -> (usize, Vec<u64>) {
///     (q.n_top_cells(), q.f_vector().unwrap())
/// }
/// assert_eq!(summary(&VtIndex::new(&k)), (2, vec![4, 5, 2]));
/// ```
pub trait Queries:
    TopCells
    + VertexStar
    + VertexAdjacency
    + TopStar
    + Counts
    + Boundary
    + Coboundary
    + Adjacency
    + Star
    + Levels
    + Storage
{
}
impl<T> Queries for T where
    T: TopCells
        + VertexStar
        + VertexAdjacency
        + TopStar
        + Counts
        + Boundary
        + Coboundary
        + Adjacency
        + Star
        + Levels
        + Storage
{
}

/// A set of simplices of mixed dimensions: `levels[p]` is a flat list of p-simplices (stride
/// p+1), sorted and without repeats; no trailing empty level.
///
/// ```
/// use starplex::topo::SimplexSet;
/// use starplex::ids::VertexId;
/// let v = |x: &[u32]| x.iter().map(|&i| VertexId(i)).collect::<Vec<_>>();
/// let mut s = SimplexSet::default();
/// s.insert(&v(&[2, 1]));
/// s.insert(&v(&[0]));
/// s.insert(&v(&[1, 2]));
/// s.normalize();
/// assert_eq!(s.len(), 2);
/// assert_eq!(s.level(1), &v(&[1, 2])[..]);
/// ```
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct SimplexSet {
    /// Flat lists per dimension.
    pub levels: Vec<Vec<VertexId>>,
}

impl SimplexSet {
    /// Adds a simplex (sorted on insertion; call [`normalize`](Self::normalize) before comparing).
    ///
    /// ```
    /// use starplex::topo::SimplexSet;
    /// use starplex::ids::VertexId;
    /// # let v = |x: &[u32]| x.iter().map(|&i| VertexId(i)).collect::<Vec<_>>();
    /// let mut s = SimplexSet::default();
    /// s.insert(&v(&[3, 1]));
    /// assert_eq!(s.level(1), &v(&[1, 3])[..]); // stored sorted
    /// s.insert(&[]); // the empty simplex is ignored
    /// assert_eq!(s.len(), 1);
    /// ```
    pub fn insert(&mut self, s: &[VertexId]) {
        if s.is_empty() {
            return;
        }
        let p = s.len() - 1;
        if self.levels.len() <= p {
            self.levels.resize(p + 1, Vec::new());
        }
        let start = self.levels[p].len();
        self.levels[p].extend_from_slice(s);
        // sorting networks for the small keys (most of a link's or star's faces), and no sort
        // at all for a key given sorted
        let t = &mut self.levels[p][start..];
        match t.len() {
            1 => {}
            2 => {
                if t[0] > t[1] {
                    t.swap(0, 1);
                }
            }
            3 => t.copy_from_slice(&sort3([t[0], t[1], t[2]])),
            4 => t.copy_from_slice(&sort4([t[0], t[1], t[2], t[3]])),
            _ => {
                if !t.is_sorted() {
                    t.sort_unstable();
                }
            }
        }
    }
    /// Sorts and deduplicates every level, drops trailing empty levels.
    ///
    /// ```
    /// use starplex::topo::SimplexSet;
    /// use starplex::ids::VertexId;
    /// # let v = |x: &[u32]| x.iter().map(|&i| VertexId(i)).collect::<Vec<_>>();
    /// let mut s = SimplexSet::default();
    /// s.insert(&v(&[2, 3]));
    /// s.insert(&v(&[1, 2]));
    /// s.insert(&v(&[3, 2]));
    /// s.normalize();
    /// assert_eq!(s.level(1), &v(&[1, 2, 2, 3])[..]);
    /// ```
    pub fn normalize(&mut self) {
        for (p, l) in self.levels.iter_mut().enumerate() {
            sort_flat(l, p + 1);
        }
        while self.levels.last().is_some_and(|l| l.is_empty()) {
            self.levels.pop();
        }
    }
    /// The flat list of p-simplices.
    ///
    /// ```
    /// use starplex::topo::SimplexSet;
    /// use starplex::ids::VertexId;
    /// # let v = |x: &[u32]| x.iter().map(|&i| VertexId(i)).collect::<Vec<_>>();
    /// let mut s = SimplexSet::default();
    /// s.insert(&v(&[0, 1, 2]));
    /// assert_eq!(s.level(2), &v(&[0, 1, 2])[..]);
    /// assert!(s.level(1).is_empty());
    /// assert!(s.level(7).is_empty());
    /// ```
    pub fn level(&self, p: usize) -> &[VertexId] {
        self.levels.get(p).map_or(&[], |l| l.as_slice())
    }
    /// Number of simplices.
    ///
    /// ```
    /// use starplex::topo::SimplexSet;
    /// use starplex::ids::VertexId;
    /// # let v = |x: &[u32]| x.iter().map(|&i| VertexId(i)).collect::<Vec<_>>();
    /// let mut s = SimplexSet::default();
    /// s.insert(&v(&[0, 1, 2]));
    /// s.insert(&v(&[4]));
    /// assert_eq!(s.len(), 2);
    /// ```
    pub fn len(&self) -> usize {
        self.levels
            .iter()
            .enumerate()
            .map(|(p, l)| l.len() / (p + 1))
            .sum()
    }
    /// True when empty.
    ///
    /// ```
    /// use starplex::topo::SimplexSet;
    /// use starplex::ids::VertexId;
    /// let mut s = SimplexSet::default();
    /// assert!(s.is_empty());
    /// s.insert(&[VertexId(4)]);
    /// assert!(!s.is_empty());
    /// ```
    pub fn is_empty(&self) -> bool {
        self.levels.iter().all(|l| l.is_empty())
    }
    /// Number of simplices per dimension.
    ///
    /// ```
    /// use starplex::topo::SimplexSet;
    /// use starplex::ids::VertexId;
    /// # let v = |x: &[u32]| x.iter().map(|&i| VertexId(i)).collect::<Vec<_>>();
    /// let mut s = SimplexSet::default();
    /// for t in [&[0, 1][..], &[1, 2], &[0, 1, 2]] {
    ///     s.insert(&v(t));
    /// }
    /// assert_eq!(s.f_vector(), vec![0, 2, 1]);
    /// ```
    pub fn f_vector(&self) -> Vec<u64> {
        self.levels
            .iter()
            .enumerate()
            .map(|(p, l)| (l.len() / (p + 1)) as u64)
            .collect()
    }
    /// Iterates over the simplices, by dimension then lexicographically.
    ///
    /// ```
    /// use starplex::topo::SimplexSet;
    /// use starplex::ids::VertexId;
    /// # let v = |x: &[u32]| x.iter().map(|&i| VertexId(i)).collect::<Vec<_>>();
    /// let mut s = SimplexSet::default();
    /// s.insert(&v(&[1, 2]));
    /// s.insert(&v(&[5]));
    /// s.insert(&v(&[0, 1]));
    /// s.normalize();
    /// let all: Vec<Vec<u32>> = s.iter().map(|t| t.iter().map(|x| x.0).collect()).collect();
    /// assert_eq!(all, [vec![5], vec![0, 1], vec![1, 2]]);
    /// ```
    pub fn iter(&self) -> impl Iterator<Item = &[VertexId]> + '_ {
        self.levels
            .iter()
            .enumerate()
            .flat_map(|(p, l)| l.chunks_exact(p + 1))
    }
    /// Whether the (sorted) simplex is in the set (the set must be normalized).
    ///
    /// ```
    /// use starplex::topo::SimplexSet;
    /// use starplex::ids::VertexId;
    /// # let v = |x: &[u32]| x.iter().map(|&i| VertexId(i)).collect::<Vec<_>>();
    /// let mut s = SimplexSet::default();
    /// s.insert(&v(&[0, 1]));
    /// s.insert(&v(&[1, 2]));
    /// s.normalize();
    /// assert!(s.contains(&v(&[1, 2])));
    /// assert!(!s.contains(&v(&[0, 2])));
    /// assert!(!s.contains(&[]));
    /// ```
    pub fn contains(&self, s: &[VertexId]) -> bool {
        if s.is_empty() {
            return false;
        }
        let l = self.level(s.len() - 1);
        let n = s.len();
        let (mut lo, mut hi) = (0usize, l.len() / n);
        while lo < hi {
            let mid = (lo + hi) / 2;
            match l[mid * n..(mid + 1) * n].cmp(s) {
                std::cmp::Ordering::Less => lo = mid + 1,
                std::cmp::Ordering::Greater => hi = mid,
                std::cmp::Ordering::Equal => return true,
            }
        }
        false
    }
}

/// Sorts a flat list of tuples of `stride` lexicographically and removes repeats.
///
/// ```
/// use starplex::topo::sort_flat;
/// let mut v = vec![3u32, 4, 1, 2, 3, 4];
/// sort_flat(&mut v, 2);
/// assert_eq!(v, vec![1, 2, 3, 4]);
/// ```
pub fn sort_flat<T: Ord + Copy>(v: &mut Vec<T>, stride: usize) {
    if stride == 1 {
        v.sort_unstable();
        v.dedup();
        return;
    }
    let n = v.len() / stride;
    if n < 2 {
        return;
    }
    // keys of 2-4 ids (edges, triangles, tetrahedra): sorted as fixed-size arrays, not through
    // an index compared by slices
    match stride {
        2 => return sort_fixed::<T, 2>(v),
        3 => return sort_fixed::<T, 3>(v),
        4 => return sort_fixed::<T, 4>(v),
        _ => {}
    }
    let mut idx: Vec<u32> = (0..n as u32).collect();
    idx.sort_unstable_by(|&a, &b| {
        v[a as usize * stride..(a as usize + 1) * stride]
            .cmp(&v[b as usize * stride..(b as usize + 1) * stride])
    });
    let mut out: Vec<T> = Vec::with_capacity(v.len());
    for &i in &idx {
        let t = &v[i as usize * stride..(i as usize + 1) * stride];
        if out.len() >= stride && &out[out.len() - stride..] == t {
            continue;
        }
        out.extend_from_slice(t);
    }
    *v = out;
}

/// [`sort_flat`] for keys of `K` values.
fn sort_fixed<T: Ord + Copy, const K: usize>(v: &mut Vec<T>) {
    let mut a: Vec<[T; K]> = v
        .chunks_exact(K)
        .map(|c| std::array::from_fn(|i| c[i]))
        .collect();
    a.sort_unstable();
    a.dedup();
    v.clear();
    for x in &a {
        v.extend_from_slice(x);
    }
}

/// Three vertex ids sorted by a three-comparison sorting network, by value (so the ids stay in
/// registers: the triangle keys of the per-leaf and per-star passes, once per triangle on hot
/// paths).
///
/// ```
/// assert_eq!(starplex::topo::sort3([7, 2, 5]), [2, 5, 7]);
/// ```
#[inline]
pub fn sort3<T: Ord + Copy>([a, b, c]: [T; 3]) -> [T; 3] {
    let (a, b) = (a.min(b), a.max(b));
    let (b, c) = (b.min(c), b.max(c));
    let (a, b) = (a.min(b), a.max(b));
    [a, b, c]
}

/// Four vertex ids sorted by a five-comparison sorting network, by value (the tetrahedra of
/// the homology orders, once per tetrahedron and renumbering).
///
/// ```
/// assert_eq!(starplex::topo::sort4([7, 2, 9, 5]), [2, 5, 7, 9]);
/// assert_eq!(starplex::topo::sort4([7u64 << 40, 2, 9, 5]), [2, 5, 9, 7 << 40]);
/// ```
#[inline(always)]
pub fn sort4<T: Ord + Copy>([a, b, c, d]: [T; 4]) -> [T; 4] {
    let (a, b) = (a.min(b), a.max(b));
    let (c, d) = (c.min(d), c.max(d));
    let (a, c) = (a.min(c), a.max(c));
    let (b, d) = (b.min(d), b.max(d));
    let (b, c) = (b.min(c), b.max(c));
    [a, b, c, d]
}

/// Sorts a simplex given in any order and checks it has no repeated vertex.
///
/// # Errors
/// [`QueryError::NotInComplex`] for an empty simplex or a repeated vertex.
///
/// ```
/// use starplex::topo::sorted_simplex;
/// use starplex::ids::VertexId;
/// assert_eq!(sorted_simplex(&[VertexId(2), VertexId(1)]).unwrap(), vec![VertexId(1), VertexId(2)]);
/// assert!(sorted_simplex(&[VertexId(2), VertexId(2)]).is_err());
/// ```
pub fn sorted_simplex(s: &[VertexId]) -> Result<Vec<VertexId>, QueryError> {
    let mut v = s.to_vec();
    v.sort_unstable();
    if v.is_empty() || v.windows(2).any(|w| w[0] == w[1]) {
        return Err(QueryError::NotInComplex(s.iter().map(|x| x.0).collect()));
    }
    Ok(v)
}
