//! The Stellar tree: a compressed spatial index over a complex, processed leaf by leaf.
//!
//! Built from an [`IndexedComplex`] with a bucketing threshold k_V: a nested spatial
//! decomposition of the vertices (2^n regular split for ambient dimension <= 3, kD bisection
//! cycling the axes above), vertices reindexed so each leaf owns a contiguous range, top cells
//! reindexed by the tuple of leaves they touch, and every leaf's list of top cells compressed
//! with Sequential Range Encoding ([`sre`]). Every query answers in the input's numbering.
//!
//! ```
//! use starplex::complex::{ComplexBuilder, BuildOptions};
//! use starplex::cell::CellKind;
//! use starplex::ids::{VertexId, CellId};
//! use starplex::stellar::{StellarTree, StellarOptions};
//! use starplex::topo::VertexStar;
//! let mut b = ComplexBuilder::new(2).unwrap();
//! for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
//! b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
//! b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
//! let k = b.build(&BuildOptions::default()).unwrap().0;
//! let t = StellarTree::build(&k, &StellarOptions { kv: Some(1), ..Default::default() }).unwrap();
//! assert_eq!(t.n_leaves(), 4);
//! let mut cells = Vec::new();
//! t.vertex_top_cells(VertexId(1), &mut cells);
//! assert_eq!(cells, vec![CellId(0), CellId(1)]);
//! ```
use crate::cell::CellKind;
use crate::complex::IndexedComplex;
use crate::ids::{CellId, LeafId, NodeId, TreeCellId, TreeVertexId, VertexId};

mod build;
mod graph_split;
pub mod iastar;
pub mod queries;
pub mod relations;
mod save;
mod save_attrs;
pub mod sre;
pub mod stats;
pub mod validate;
pub mod visit;

pub use relations::FaceList;
pub use save::{is_saved_tree, SAVED_TREE_MAGIC};
pub use stats::StellarStats;
pub use visit::{ExpandedLeaf, LeafCache, LeafView};

/// How blocks are split.
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
/// use starplex::stellar::SplitMode;
/// assert_eq!(SplitMode::default(), SplitMode::Auto);
/// // `Auto` resolves to a regular split in 2D
/// assert_eq!(t.split(), SplitMode::Regular);
/// let opts = StellarOptions { kv: Some(1), split: SplitMode::Kd, ..Default::default() };
/// assert_eq!(StellarTree::build(&k, &opts).unwrap().split(), SplitMode::Kd);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum SplitMode {
    /// Regular 2^n split for ambient dimension <= 3, kD bisection above.
    #[default]
    Auto,
    /// Regular 2^n split (quadtree, octree); only allowed up to ambient dimension 8.
    Regular,
    /// Bisection at the block's midpoint, cycling the axes (kD tree).
    Kd,
}

/// How the vertices are split into blocks.
///
/// `Spatial` splits by the vertices' coordinates ([`SplitMode`]); `Graph` by connectivity
/// alone, for complexes whose coordinates mean nothing (flag complexes of graphs, abstract
/// complexes): recursive bisection of the vertex graph of the top cells, each block ordered by
/// breadth-first search from a pseudo-peripheral vertex and cut in half, until a block has at
/// most k_V vertices. The leaves, their encoding and every query are the same either way.
///
/// ```
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// use starplex::stellar::{Decomposition, StellarOptions, StellarTree};
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// assert_eq!(Decomposition::default(), Decomposition::Spatial);
/// let o = StellarOptions { kv: Some(1), decomposition: Decomposition::Graph, ..Default::default() };
/// let g = StellarTree::build(&k, &o).unwrap();
/// let s = StellarTree::build(&k, &StellarOptions { kv: Some(1), ..Default::default() }).unwrap();
/// assert_eq!((g.decomposition(), g.n_leaves()), (Decomposition::Graph, 4));
/// assert_eq!(g.vt_all(), s.vt_all()); // the same answers
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Decomposition {
    /// By coordinates: the split rule of [`StellarOptions::split`].
    #[default]
    Spatial,
    /// By connectivity alone (recursive graph bisection).
    Graph,
}

/// Options of [`StellarTree::build`].
///
/// ```
/// let o = starplex::stellar::StellarOptions::default();
/// assert_eq!(o.kv, None);
/// ```
#[derive(Clone, Debug, Default)]
pub struct StellarOptions {
    /// Bucketing threshold: at most this many vertices per leaf (except at the depth limit).
    /// `Some(0)` makes a single leaf; `None` picks [`default_kv`].
    pub kv: Option<u32>,
    /// Split rule.
    pub split: SplitMode,
    /// Deepest level of the tree (`None`: 64 for regular splits and graph decompositions, 64
    /// x ambient dimension, at most 2048, for kD bisection). Leaves at this depth may hold more
    /// than k_V vertices (coincident points).
    pub max_depth: Option<u32>,
    /// Split by coordinates or by connectivity.
    pub decomposition: Decomposition,
}

/// The default bucketing threshold for a complex: 100 for dimension <= 2 (the paper's k_S for
/// triangles and quads), 400 above.
///
/// ```
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// let k = ComplexBuilder::new(3).unwrap().build(&BuildOptions::default()).unwrap().0;
/// assert_eq!(starplex::stellar::default_kv(&k), 100);
/// ```
pub fn default_kv(k: &IndexedComplex) -> u32 {
    match k.dim() {
        Some(d) if d >= 3 => 400,
        _ => 100,
    }
}

/// Why a Stellar tree could not be built or queried.
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
/// use starplex::ids::VertexId;
/// use starplex::stellar::StellarError;
/// let e = t.leaf_of_vertex(VertexId(9)).unwrap_err();
/// assert_eq!(e, StellarError::NoSuchVertex(9, 4));
/// assert_eq!(e.to_string(), "vertex 9 out of range (4 vertices)");
/// ```
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum StellarError {
    /// More top cells than the SRE encoding addresses.
    #[error("{0} top cells: the Stellar tree's compressed lists address at most 2^31 - 1")]
    TooManyCells(u64),
    /// Regular split asked in too high a dimension.
    #[error("a regular 2^n split in ambient dimension {0} would make {1} children per node; use the kD split")]
    RegularTooWide(usize, u128),
    /// An operation whose output would be too large.
    #[error(transparent)]
    TooLarge(#[from] crate::limits::TooLarge),
    /// A vertex id out of range.
    #[error("vertex {0} out of range ({1} vertices)")]
    NoSuchVertex(u32, usize),
    /// The complex asked of a tree that holds no coordinates.
    #[error(
        "the Stellar tree holds no coordinates: it was built in memory, or saved by a starplex \
         that did not save them"
    )]
    NoCoordinates,
    /// The complex of a loaded tree failed the complex's checks.
    #[error("rebuilding the complex of the Stellar tree: {0}")]
    Rebuild(String),
    /// A bad or truncated tree file.
    #[error("stellar tree file {path}: {reason}")]
    File {
        /// The file.
        path: String,
        /// What is wrong.
        reason: String,
    },
}

/// A node of the hierarchy. Children of a node are contiguous (brood encoding); a leaf has
/// no children and [`TreeNode::leaf`] gives its [`LeafId`]. Ids are typed: tree vertices are
/// [`TreeVertexId`]s, children [`NodeId`]s.
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
/// use starplex::ids::{NodeId, TreeVertexId};
/// let root = t.nodes()[0];
/// assert_eq!((root.v_start(), root.v_end()), (TreeVertexId(0), TreeVertexId(4)));
/// assert_eq!(root.n_children(), 4); // quadtree split, one vertex per leaf
/// assert_eq!(root.leaf(), None);
/// let first: NodeId = root.children().next().unwrap();
/// let leaf = t.nodes()[first.index()];
/// assert!(leaf.leaf().is_some() && leaf.children().next().is_none());
/// assert_eq!(leaf.n_vertices(), 1);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, bytemuck::Pod, bytemuck::Zeroable)]
#[repr(C)]
pub struct TreeNode {
    /// First vertex (tree numbering) of the block.
    pub(crate) v_start: u32,
    /// One past the last vertex of the block.
    pub(crate) v_end: u32,
    /// First child node, or the leaf id for a leaf.
    pub(crate) first: u32,
    /// Number of children (0 for a leaf).
    pub(crate) n_children: u32,
}

impl TreeNode {
    /// First vertex (tree numbering) of the node's block; see [`TreeNode`] for an example.
    pub fn v_start(&self) -> TreeVertexId {
        TreeVertexId(self.v_start)
    }

    /// One past the last vertex (tree numbering) of the node's block.
    pub fn v_end(&self) -> TreeVertexId {
        TreeVertexId(self.v_end)
    }

    /// Number of vertices in the node's block.
    pub fn n_vertices(&self) -> usize {
        (self.v_end - self.v_start) as usize
    }

    /// The leaf this node is, or `None` for an internal node.
    pub fn leaf(&self) -> Option<LeafId> {
        (self.n_children == 0).then_some(LeafId(self.first))
    }

    /// Number of children (0 for a leaf).
    pub fn n_children(&self) -> usize {
        self.n_children as usize
    }

    /// The children, contiguous in [`StellarTree::nodes`] (none for a leaf).
    pub fn children(&self) -> impl ExactSizeIterator<Item = NodeId> + use<> {
        (self.first..self.first + self.n_children).map(NodeId)
    }
}

/// Seconds spent in each build phase.
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
/// use starplex::stellar::BuildTimings;
/// let tm = t.timings();
/// assert!(tm.decomposition_s >= 0.0 && tm.leaf_lists_s >= 0.0);
/// assert_eq!(BuildTimings::default().cell_reindex_s, 0.0);
/// ```
#[derive(Clone, Debug, Default, PartialEq)]
pub struct BuildTimings {
    /// Spatial decomposition of the vertices.
    pub decomposition_s: f64,
    /// Vertex permutation.
    pub vertex_reindex_s: f64,
    /// Top-cell reindexing by region tuples and the reindexed cell array.
    pub cell_reindex_s: f64,
    /// SRE-compressed leaf cell lists.
    pub leaf_lists_s: f64,
}

/// Kind code of a cell in the flat store.
pub(crate) fn kind_code(k: CellKind) -> u8 {
    match k {
        CellKind::Simplex(d) => d,
        CellKind::Quad => 65,
        CellKind::Pyramid => 66,
        CellKind::Prism => 67,
        CellKind::Hex => 68,
    }
}

pub(crate) fn code_kind(c: u8) -> CellKind {
    match c {
        65 => CellKind::Quad,
        66 => CellKind::Pyramid,
        67 => CellKind::Prism,
        68 => CellKind::Hex,
        d => CellKind::Simplex(d),
    }
}

/// Top cells in tree numbering: one uniform kind with a fixed stride, or per-cell kinds and
/// offsets.
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct CellStore {
    /// The kind of every cell when they all have the same kind (`None`: mixed, see `kinds`).
    pub uniform: Option<CellKind>,
    /// Vertex count of the uniform kind.
    pub stride: u32,
    /// Per-cell kind codes (mixed only).
    pub kinds: Vec<u8>,
    /// Per-cell offsets into `verts`, n+1 entries (mixed only).
    pub offsets: Vec<u32>,
    /// Vertex ids (tree numbering).
    pub verts: Vec<u32>,
    /// Number of cells.
    pub n: u32,
}

impl CellStore {
    #[inline(always)]
    pub(crate) fn get(&self, i: u32) -> (CellKind, &[u32]) {
        if let Some(kind) = self.uniform {
            let s = self.stride as usize;
            let i = i as usize;
            (kind, &self.verts[i * s..(i + 1) * s])
        } else {
            let (a, b) = (
                self.offsets[i as usize] as usize,
                self.offsets[i as usize + 1] as usize,
            );
            (code_kind(self.kinds[i as usize]), &self.verts[a..b])
        }
    }
    #[inline]
    pub(crate) fn verts(&self, i: u32) -> &[u32] {
        self.get(i).1
    }
    pub(crate) fn bytes(&self) -> usize {
        self.kinds.len() + 4 * (self.offsets.len() + self.verts.len())
    }
}

/// A Stellar tree over a complex. See the [module docs](self).
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
/// assert_eq!((t.n_vertices(), t.n_top_cells(), t.n_leaves()), (4, 2, 4));
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct StellarTree {
    pub(crate) ambient_dim: u32,
    pub(crate) kv: u32,
    pub(crate) split: SplitMode,
    pub(crate) decomposition: Decomposition,
    pub(crate) bbox: (Vec<f64>, Vec<f64>),
    pub(crate) nodes: Vec<TreeNode>,
    /// `leaf_vstart[l]..leaf_vstart[l+1]` are the vertices of leaf `l` (tree numbering).
    pub(crate) leaf_vstart: Vec<u32>,
    /// `leaf_toff[l]..leaf_toff[l+1]` is leaf `l`'s SRE list in `leaf_tops`.
    pub(crate) leaf_toff: Vec<u32>,
    pub(crate) leaf_tops: Vec<u32>,
    pub(crate) cells: CellStore,
    /// Tree vertex id -> input vertex id.
    pub(crate) v_orig: Vec<u32>,
    /// Input vertex id -> tree vertex id.
    pub(crate) v_new: Vec<u32>,
    /// Tree cell id -> input cell id.
    pub(crate) c_orig: Vec<u32>,
    /// Input cell id -> tree cell id.
    pub(crate) c_new: Vec<u32>,
    pub(crate) timings: BuildTimings,
    /// The input's attributes, in tree order (vertex columns by tree vertex id, cell columns by
    /// tree cell id).
    pub(crate) attrs: crate::attr::Attributes,
    /// The vertices' coordinates in tree order, when the tree was loaded from a file saved with
    /// them ([`StellarTree::save_with_coords`]); a tree built from a complex leaves them there.
    pub(crate) coords: Option<Vec<f64>>,
}

impl StellarTree {
    /// Builds the tree.
    ///
    /// # Errors
    /// More than 2^31 - 1 top cells; a regular split asked above ambient dimension 8.
    ///
    /// ```
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// use starplex::stellar::{StellarTree, StellarOptions};
    /// let mut b = ComplexBuilder::new(1).unwrap();
    /// for x in 0..10 { b.push_vertex(&[x as f64]).unwrap(); }
    /// for x in 0..9 { b.push_cell(CellKind::Simplex(1), &[x, x + 1]).unwrap(); }
    /// let k = b.build(&BuildOptions::default()).unwrap().0;
    /// let t = StellarTree::build(&k, &StellarOptions { kv: Some(3), ..Default::default() }).unwrap();
    /// assert!(t.n_leaves() >= 4);
    /// assert_eq!(t.n_top_cells(), 9);
    /// ```
    pub fn build(k: &IndexedComplex, opts: &StellarOptions) -> Result<StellarTree, StellarError> {
        build::build(k, opts)
    }

    /// The vertex decomposition alone, without filing the top cells: the input vertices in
    /// tree order and the first tree vertex of every leaf, then the vertex count — what
    /// [`vertex_to_input`](Self::vertex_to_input) and [`leaf_vertices`](Self::leaf_vertices)
    /// of the tree [`build`](Self::build) makes with the same options would say.
    ///
    /// ```
    /// use starplex::generate::kuhn_grid;
    /// use starplex::ids::LeafId;
    /// use starplex::stellar::{StellarOptions, StellarTree};
    /// let k = kuhn_grid(&[6, 6]).unwrap();
    /// let opts = StellarOptions { kv: Some(5), ..Default::default() };
    /// let (order, starts) = StellarTree::vertex_order(&k, &opts).unwrap();
    /// let t = StellarTree::build(&k, &opts).unwrap();
    /// assert!(order.iter().zip(t.vertex_to_input()).all(|(&a, b)| a == b.0));
    /// assert_eq!(starts.len(), t.n_leaves() + 1);
    /// assert_eq!(t.leaf_vertices(LeafId(1)), starts[1]..starts[2]);
    /// ```
    ///
    /// # Errors
    /// As [`build`](Self::build).
    pub fn vertex_order(
        k: &IndexedComplex,
        opts: &StellarOptions,
    ) -> Result<(Vec<u32>, Vec<u32>), StellarError> {
        build::vertex_order(k, opts)
    }

    /// Number of vertices.
    ///
    /// ```
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// use starplex::ids::{CellId, LeafId, VertexId};
    /// use starplex::stellar::{StellarTree, StellarOptions, SplitMode};
    /// # let mut b = ComplexBuilder::new(2).unwrap();
    /// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
    /// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
    /// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// let t = StellarTree::build(&k, &StellarOptions { kv: Some(2), ..Default::default() }).unwrap();
    /// assert_eq!((t.n_vertices(), t.n_top_cells(), t.kv()), (4, 2, 2));
    /// assert_eq!(t.split(), SplitMode::Regular);
    /// assert_eq!(t.dim(), Some(2));
    /// assert!(t.n_nodes() > t.n_leaves());
    /// // the permutations are inverse to each other
    /// for v in 0..4 {
    ///     assert_eq!(t.vertex_to_input()[t.vertex_from_input()[v].index()].index(), v);
    /// }
    /// let l = t.leaf_of_vertex(VertexId(3)).unwrap();
    /// assert!(t.leaf_vertices(l).contains(&t.vertex_from_input()[3].0));
    /// let (kind, vs) = t.input_cell(CellId(1));
    /// assert_eq!((kind, vs), (CellKind::Simplex(2), vec![VertexId(1), VertexId(3), VertexId(2)]));
    /// ```
    pub fn n_vertices(&self) -> usize {
        self.v_orig.len()
    }
    /// Number of top cells.
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
    /// assert_eq!(t.n_top_cells(), 2);
    /// ```
    pub fn n_top_cells(&self) -> usize {
        self.c_orig.len()
    }
    /// Number of nodes (internal + leaves).
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
    /// assert_eq!(t.n_nodes(), 5); // the root and its four leaves
    /// assert_eq!(t.n_nodes(), t.nodes().len());
    /// ```
    pub fn n_nodes(&self) -> usize {
        self.nodes.len()
    }
    /// Number of leaves.
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
    /// assert_eq!(t.n_leaves(), 4); // k_V = 1: one vertex per leaf
    /// ```
    pub fn n_leaves(&self) -> usize {
        self.leaf_vstart.len().saturating_sub(1)
    }
    /// The bucketing threshold used.
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
    /// assert_eq!(t.kv(), 1);
    /// ```
    pub fn kv(&self) -> u32 {
        self.kv
    }
    /// The split rule used (`Regular` or `Kd`).
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
    /// assert_eq!(t.split(), starplex::stellar::SplitMode::Regular);
    /// ```
    pub fn split(&self) -> SplitMode {
        self.split
    }
    /// How the vertices were split: by coordinates or by connectivity (then [`split`](Self::split)
    /// was not used).
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
    /// assert_eq!(t.decomposition(), starplex::stellar::Decomposition::Spatial);
    /// ```
    pub fn decomposition(&self) -> Decomposition {
        self.decomposition
    }
    /// Ambient dimension.
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
    /// assert_eq!(t.ambient_dim(), 2);
    /// ```
    pub fn ambient_dim(&self) -> usize {
        self.ambient_dim as usize
    }
    /// The root block `(lo, hi)`.
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
    /// let (lo, hi) = t.bbox();
    /// assert_eq!((lo.len(), hi.len()), (2, 2));
    /// // every point lies in the root block
    /// assert!(lo.iter().all(|&x| x <= 0.0) && hi.iter().all(|&x| x >= 1.0));
    /// ```
    pub fn bbox(&self) -> (&[f64], &[f64]) {
        (&self.bbox.0, &self.bbox.1)
    }
    /// The nodes, root first.
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
    /// let nodes = t.nodes();
    /// assert_eq!(nodes.len(), t.n_nodes());
    /// assert_eq!(nodes[0].n_vertices(), 4); // the root covers every vertex
    /// assert_eq!(nodes.iter().filter(|n| n.leaf().is_some()).count(), t.n_leaves());
    /// ```
    pub fn nodes(&self) -> &[TreeNode] {
        &self.nodes
    }
    /// One node.
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
    /// use starplex::ids::NodeId;
    /// assert_eq!(t.node(NodeId(0)), t.nodes()[0]);
    /// assert_eq!(t.node(NodeId(0)).n_children(), 4);
    /// ```
    pub fn node(&self, n: NodeId) -> TreeNode {
        self.nodes[n.index()]
    }
    /// Time of each build phase.
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
    /// let tm = t.timings();
    /// assert!(tm.decomposition_s >= 0.0 && tm.vertex_reindex_s >= 0.0);
    /// ```
    pub fn timings(&self) -> &BuildTimings {
        &self.timings
    }
    /// Largest top-cell dimension (`None` without cells).
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
    /// assert_eq!(t.dim(), Some(2));
    /// ```
    pub fn dim(&self) -> Option<usize> {
        if let Some(kind) = self.cells.uniform {
            return (self.cells.n > 0).then(|| kind.dim());
        }
        self.cells.kinds.iter().map(|&c| code_kind(c).dim()).max()
    }
    /// Permutation tree vertex id -> input vertex id.
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
    /// use starplex::ids::VertexId;
    /// let mut ids = t.vertex_to_input().to_vec(); // indexed by tree vertex id
    /// ids.sort_unstable();
    /// assert_eq!(ids, (0..4).map(VertexId).collect::<Vec<_>>()); // a permutation of the input ids
    /// ```
    pub fn vertex_to_input(&self) -> &[VertexId] {
        bytemuck::cast_slice(&self.v_orig)
    }
    /// Permutation input vertex id -> tree vertex id.
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
    /// use starplex::ids::VertexId;
    /// for v in (0..4).map(VertexId) {
    ///     let tv = t.vertex_from_input()[v.index()]; // a TreeVertexId
    ///     assert_eq!(t.vertex_to_input()[tv.index()], v);
    /// }
    /// ```
    pub fn vertex_from_input(&self) -> &[TreeVertexId] {
        bytemuck::cast_slice(&self.v_new)
    }
    /// Permutation tree cell id -> input cell id.
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
    /// use starplex::ids::CellId;
    /// let mut ids = t.cell_to_input().to_vec(); // indexed by tree cell id
    /// ids.sort_unstable();
    /// assert_eq!(ids, vec![CellId(0), CellId(1)]);
    /// ```
    pub fn cell_to_input(&self) -> &[CellId] {
        bytemuck::cast_slice(&self.c_orig)
    }

    /// The input complex's attributes, renumbered with the tree (vertex columns indexed by tree
    /// vertex id, cell columns by tree cell id); saved and loaded with the tree.
    ///
    /// ```
    /// use starplex::attr::{Attribute, Attributes};
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// # use starplex::stellar::{StellarTree, StellarOptions};
    /// # let mut b = ComplexBuilder::new(2).unwrap();
    /// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
    /// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
    /// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
    /// # let mut k = b.build(&BuildOptions::default()).unwrap().0;
    /// k.set_attributes(Attributes { vertex: vec![], cell: vec![Attribute::int("tag", 1, vec![5, 6])] }).unwrap();
    /// let t = StellarTree::build(&k, &StellarOptions { kv: Some(1), ..Default::default() }).unwrap();
    /// let tags = &t.attributes().cell[0];
    /// for (tree_id, input) in t.cell_to_input().iter().enumerate() {
    ///     assert_eq!(tags.values.get_f64(tree_id), [5.0, 6.0][input.index()]);
    /// }
    /// assert_eq!(t.input_attributes(), *k.attributes()); // back in the input's order
    /// ```
    pub fn attributes(&self) -> &crate::attr::Attributes {
        &self.attrs
    }

    /// The attributes in the input complex's order (what [`attributes`](Self::attributes) holds,
    /// gathered back through the permutations).
    ///
    /// ```
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// # use starplex::stellar::{StellarTree, StellarOptions};
    /// # let mut b = ComplexBuilder::new(1).unwrap();
    /// # for x in [0.0, 1.0] { b.push_vertex(&[x]).unwrap(); }
    /// # b.push_cell(CellKind::Simplex(1), &[0, 1]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// let t = StellarTree::build(&k, &StellarOptions::default()).unwrap();
    /// assert!(t.input_attributes().is_empty());
    /// ```
    pub fn input_attributes(&self) -> crate::attr::Attributes {
        self.attrs
            .gather_vertices(&self.v_new)
            .gather_cells(&self.c_new)
    }
    /// The complex the tree was built from, in the input's numbering (vertices, cells and
    /// attributes), when the tree holds the coordinates (a tree saved by
    /// [`save_with_coords`](Self::save_with_coords), as `starplex stellar MESH --save OUT`
    /// does, and loaded). The verbs that need a mesh read a saved tree through this.
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
    /// let t = StellarTree::build(&k, &StellarOptions { kv: Some(1), ..Default::default() }).unwrap();
    /// assert!(t.to_complex().is_err()); // built in memory: the complex is the caller's
    /// let path = std::env::temp_dir().join(format!("starplex-doc-tocomplex-{}.tree", std::process::id()));
    /// t.save_with_coords(&path, k.coords()).unwrap();
    /// let u = StellarTree::load(&path).unwrap();
    /// assert_eq!(u.to_complex().unwrap(), k);
    /// # std::fs::remove_file(&path).ok();
    /// ```
    ///
    /// # Errors
    /// [`StellarError::NoCoordinates`] when the tree holds no coordinates.
    pub fn to_complex(&self) -> Result<crate::complex::IndexedComplex, StellarError> {
        let Some(tc) = &self.coords else {
            return Err(StellarError::NoCoordinates);
        };
        let d = self.ambient_dim as usize;
        let mut coords = vec![0.0; tc.len()];
        for (t, p) in tc.chunks_exact(d).enumerate() {
            let v = self.v_orig[t] as usize;
            coords[d * v..d * v + d].copy_from_slice(p);
        }
        let re = |e: crate::complex::ComplexError| StellarError::Rebuild(e.to_string());
        let mut b = crate::complex::ComplexBuilder::new(d).map_err(re)?;
        b.push_vertices(coords).map_err(re)?;
        let mut run: Option<(crate::cell::CellKind, Vec<u32>)> = None;
        for &tcell in &self.c_new {
            let (kind, verts) = self.cells.get(tcell);
            match &mut run {
                Some((k, v)) if *k == kind => {
                    v.extend(verts.iter().map(|&x| self.v_orig[x as usize]))
                }
                _ => {
                    if let Some((k, v)) = run.take() {
                        b.push_cells(k, v).map_err(re)?;
                    }
                    run = Some((
                        kind,
                        verts.iter().map(|&x| self.v_orig[x as usize]).collect(),
                    ));
                }
            }
        }
        if let Some((k, v)) = run {
            b.push_cells(k, v).map_err(re)?;
        }
        b.set_attributes(self.input_attributes());
        let opts = crate::complex::BuildOptions {
            trust_maximality: true,
            ..Default::default()
        };
        Ok(b.build(&opts).map_err(re)?.0)
    }

    /// Whether the tree holds its vertices' coordinates (see [`to_complex`](Self::to_complex)).
    ///
    /// ```
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// # use starplex::stellar::{StellarTree, StellarOptions};
    /// # let mut b = ComplexBuilder::new(1).unwrap();
    /// # for p in [[0.0], [1.0]] { b.push_vertex(&p).unwrap(); }
    /// # b.push_cell(CellKind::Simplex(1), &[0, 1]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// let t = StellarTree::build(&k, &StellarOptions::default()).unwrap();
    /// assert!(!t.has_coords());
    /// ```
    pub fn has_coords(&self) -> bool {
        self.coords.is_some()
    }

    /// Permutation input cell id -> tree cell id.
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
    /// use starplex::ids::CellId;
    /// for c in [CellId(0), CellId(1)] {
    ///     assert_eq!(t.cell_to_input()[t.cell_from_input()[c.index()].index()], c);
    /// }
    /// ```
    pub fn cell_from_input(&self) -> &[TreeCellId] {
        bytemuck::cast_slice(&self.c_new)
    }
    /// Tree vertex range of a leaf.
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
    /// use starplex::ids::LeafId;
    /// // the leaves split the tree numbering into contiguous ranges
    /// assert_eq!(t.leaf_vertices(LeafId(0)).start, 0);
    /// assert_eq!(t.leaf_vertices(LeafId(3)).end, 4);
    /// assert!((0..4).all(|l| t.leaf_vertices(LeafId(l)).len() == 1));
    /// ```
    pub fn leaf_vertices(&self, l: LeafId) -> std::ops::Range<u32> {
        self.leaf_vstart[l.index()]..self.leaf_vstart[l.index() + 1]
    }
    /// The SRE-encoded top-cell list of a leaf (tree cell ids).
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
    /// use starplex::ids::{LeafId, VertexId};
    /// use starplex::stellar::sre::SreIter;
    /// // vertex 1 is in both triangles
    /// let l = t.leaf_of_vertex(VertexId(1)).unwrap();
    /// let cells: Vec<u32> = SreIter::new(t.leaf_encoded_cells(l)).collect();
    /// assert_eq!(cells, vec![0, 1]);
    /// ```
    pub fn leaf_encoded_cells(&self, l: LeafId) -> &[u32] {
        &self.leaf_tops[self.leaf_toff[l.index()] as usize..self.leaf_toff[l.index() + 1] as usize]
    }
    /// The leaf holding a vertex given in tree numbering.
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
    /// use starplex::ids::{LeafId, TreeVertexId};
    /// for l in 0..4 {
    ///     let r = t.leaf_vertices(LeafId(l));
    ///     assert_eq!(t.leaf_of_tree_vertex(TreeVertexId(r.start)), LeafId(l));
    /// }
    /// ```
    pub fn leaf_of_tree_vertex(&self, v: TreeVertexId) -> LeafId {
        // last l with leaf_vstart[l] <= v
        let l = self.leaf_vstart.partition_point(|&s| s <= v.0) - 1;
        LeafId(l as u32)
    }
    /// The leaf holding an input vertex.
    ///
    /// # Errors
    /// The vertex does not exist.
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
    /// use starplex::ids::VertexId;
    /// let l = t.leaf_of_vertex(VertexId(3)).unwrap();
    /// assert!(t.leaf_vertices(l).contains(&t.vertex_from_input()[3].0));
    /// assert!(t.leaf_of_vertex(VertexId(4)).is_err());
    /// ```
    pub fn leaf_of_vertex(&self, v: VertexId) -> Result<LeafId, StellarError> {
        let tv = self.tree_vertex(v)?;
        Ok(self.leaf_of_tree_vertex(TreeVertexId(tv)))
    }
    pub(crate) fn tree_vertex(&self, v: VertexId) -> Result<u32, StellarError> {
        self.v_new
            .get(v.index())
            .copied()
            .ok_or(StellarError::NoSuchVertex(v.0, self.v_new.len()))
    }
    /// Kind and vertices (tree numbering) of a cell given in tree numbering.
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
    /// let c = t.cell_from_input()[1]; // input triangle [1, 3, 2]
    /// let (kind, vs) = t.tree_cell(c);
    /// assert_eq!(kind, CellKind::Simplex(2));
    /// let input: Vec<u32> = vs.iter().map(|&v| t.vertex_to_input()[v as usize].0).collect();
    /// assert_eq!(input, vec![1, 3, 2]);
    /// ```
    pub fn tree_cell(&self, c: TreeCellId) -> (CellKind, &[u32]) {
        self.cells.get(c.0)
    }
    /// Kind and vertices (input numbering, the kind's vertex order) of an input cell.
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
    /// use starplex::ids::{CellId, VertexId};
    /// let (kind, vs) = t.input_cell(CellId(0));
    /// assert_eq!(kind, CellKind::Simplex(2));
    /// assert_eq!(vs, vec![VertexId(0), VertexId(1), VertexId(2)]);
    /// ```
    pub fn input_cell(&self, c: CellId) -> (CellKind, Vec<VertexId>) {
        let (k, v) = self.cells.get(self.c_new[c.index()]);
        (
            k,
            v.iter()
                .map(|&w| VertexId(self.v_orig[w as usize]))
                .collect(),
        )
    }
}
