//! IA*: the generalized indexed data structure with adjacencies (Canino, De Floriani, Weiss
//! 2011) for non-manifold simplicial complexes of any dimension and mixed dimensions, as
//! specified in `shared/specs/ia-star-is-ghosts.md` §2, and for CP cell complexes (below).
//!
//! Stored (all ids are input ids):
//! * R_{k,0}: the vertices of every top k-simplex (input order; facet j = the top without its
//!   j-th vertex);
//! * R_{k,k}, k ≥ 2: one slot per facet — none (boundary), the other top k-simplex
//!   (manifold adjacency), or a non-manifold (k-1)-face record when ≥ 3 top k-simplices share
//!   the facet;
//! * R_{k-1,k} of every non-manifold (k-1)-face: the list of its top k-simplices;
//! * per vertex: every top edge at it, and one top k-simplex per k-cluster (k ≥ 2).
//!
//! On a pure pseudo-manifold there are no non-manifold faces nor top edges and it is IA
//! (one reference per cluster per vertex). Storage follows the spec's formula exactly
//! ([`IaStar::refs`]); ghost simplices ([`Ghost`]) name faces that are not stored.
//!
//! **CP complexes** (quads, pyramids, prisms, hexahedra, mixed with simplices) are held the
//! same way, with the kinds' face tables ([`CellKind::cp_faces`], VTK order): a top stores its
//! vertices in input (VTK) order and one adjacency slot per facet of its table — a hexahedron
//! 6 (quads), a prism 5 (triangles 0-1-2 and 3-5-4, then 3 quads), a pyramid 5 (the base quad,
//! then 4 triangles), a quad 4 (edges). Facets are matched across kinds by their canonical
//! key (sorted vertices): a tetrahedron and a prism sharing a triangle are adjacent, a quad in
//! three hexahedra is a non-manifold facet. Clusters, VT and VV walk the facets (and edges)
//! of the tables, so a quad's diagonal is not an edge. A ghost in a CP top is "face `i` of the
//! kind's p-face table"; ghosts on simplices keep the colex rank. Complexes with a CP cell
//! are built by the general path, never the fast path for dimension ≤ 3 (which stays
//! simplicial). The generic relations ([`crate::topo::from_tops`]) answer top stars on CP
//! cells and refuse face enumerations with [`QueryError::NotSimplicial`]; the ghost relations
//! ([`IaStar::ghost_boundary`], [`IaStar::ghost_coboundary`], [`IaStar::ghost_adjacent`])
//! answer them for CP cells too.
//!
//! ```
//! use starplex::complex::{ComplexBuilder, BuildOptions};
//! use starplex::cell::CellKind;
//! use starplex::ids::{CellId, VertexId};
//! use starplex::tds::iastar::IaStar;
//! use starplex::topo::{Adjacent, FacetAdjacency, VertexAdjacency, VertexStar};
//! // two hexahedra sharing the quad 1-2-6-5, and a prism on the quad 2-3-7-6
//! let mut b = ComplexBuilder::new(3).unwrap();
//! for z in [0.0, 1.0] {
//!     for (x, y) in [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)] {
//!         b.push_vertex(&[x, y, z]).unwrap();
//!     }
//! }
//! for (x, y, z) in [(2.0, 0.0, 0.0), (2.0, 1.0, 0.0), (2.0, 0.0, 1.0), (2.0, 1.0, 1.0),
//!                   (1.0, 2.0, 0.0), (1.0, 2.0, 1.0)] {
//!     b.push_vertex(&[x, y, z]).unwrap();
//! }
//! b.push_cell(CellKind::Hex, &[0, 1, 2, 3, 4, 5, 6, 7]).unwrap();
//! b.push_cell(CellKind::Hex, &[1, 8, 9, 2, 5, 10, 11, 6]).unwrap();
//! b.push_cell(CellKind::Prism, &[2, 12, 3, 6, 13, 7]).unwrap();
//! let k = b.build(&BuildOptions::default()).unwrap().0;
//! let ia = IaStar::new(&k).unwrap();
//! // hexahedron 0's facet 3 is the quad 1-2-6-5, facet 4 the quad 2-3-7-6
//! assert_eq!(ia.facet_adjacent(CellId(0), 3), Adjacent::Top(CellId(1)));
//! assert_eq!(ia.facet_adjacent(CellId(0), 4), Adjacent::Top(CellId(2)));
//! assert_eq!(ia.n_facet_slots(CellId(2)), 5); // 2 triangles + 3 quads
//! let mut vt = Vec::new();
//! ia.vertex_top_cells(VertexId(2), &mut vt);
//! assert_eq!(vt, [CellId(0), CellId(1), CellId(2)]);
//! let mut vv = Vec::new();
//! ia.vertex_neighbours(VertexId(0), &mut vv);
//! assert_eq!(vv, [VertexId(1), VertexId(3), VertexId(4)]); // no diagonal
//! ```
//!
//! ```
//! use starplex::complex::{ComplexBuilder, BuildOptions};
//! use starplex::cell::CellKind;
//! use starplex::ids::{CellId, VertexId};
//! use starplex::tds::iastar::IaStar;
//! use starplex::topo::{FacetAdjacency, VertexStar, Storage};
//! // the book: three triangles sharing edge {0,1}
//! let mut b = ComplexBuilder::new(2).unwrap();
//! for _ in 0..5 { b.push_vertex(&[0.0, 0.0]).unwrap(); }
//! for c in [[0, 1, 2], [0, 1, 3], [0, 1, 4]] { b.push_cell(CellKind::Simplex(2), &c).unwrap(); }
//! let k = b.build(&BuildOptions::default()).unwrap().0;
//! let ia = IaStar::new(&k).unwrap();
//! assert_eq!(ia.refs(), 26); // 9 + 9 + 3 + 5, the spec's worked anchor
//! let mut vt = Vec::new();
//! ia.vertex_top_cells(VertexId(0), &mut vt);
//! assert_eq!(vt, vec![CellId(0), CellId(1), CellId(2)]);
//! assert_eq!(ia.n_nm_faces(), 1);
//! assert_eq!(ia.nm_face_vertices(0), vec![VertexId(0), VertexId(1)]);
//! ```
use rustc_hash::{FxHashMap, FxHashSet};

use crate::cell::{binomial, CellKind};
use crate::complex::IndexedComplex;
use crate::csr::Csr;
use crate::ids::{CellId, VertexId};
use crate::topo::{
    sorted_simplex, Adjacent, FacetAdjacency, QueryError, Storage, TopCells, VertexAdjacency,
    VertexStar,
};

/// Why an IA* could not be built.
///
/// ```
/// use starplex::tds::iastar::IaStarError;
/// let e = IaStarError::TooManyCells(1 << 31);
/// assert_eq!(e.to_string(), "2147483648 top cells: IA* adjacency slots address at most 2^31 - 1");
/// ```
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum IaStarError {
    /// Too many top cells for the 31-bit adjacency encoding.
    #[error("{0} top cells: IA* adjacency slots address at most 2^31 - 1")]
    TooManyCells(usize),
}

/// One adjacency slot, decoded (the non-manifold id is per dimension, as stored).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Slot {
    None,
    Top(CellId),
    NmFace(u32),
}

const NONE: u32 = u32::MAX;
const NM_BIT: u32 = 0x8000_0000;

#[inline]
fn decode(x: u32) -> Slot {
    if x == NONE {
        Slot::None
    } else if x & NM_BIT != 0 {
        Slot::NmFace(x & !NM_BIT)
    } else {
        Slot::Top(CellId(x))
    }
}

/// The tops of one block of the input (one kind).
#[derive(Clone, Debug)]
struct Block {
    dim: usize,
    /// The kind of the block's tops.
    kind: CellKind,
    /// Vertices per top (dim + 1 for a simplex).
    nv: u32,
    /// Adjacency slots per top: one per facet for dimension ≥ 2 (dim + 1 for a simplex, the
    /// facet table's length for a CP cell), none below.
    ns: u32,
    first: u32,
    /// Index of the block's first top among the tops of its dimension.
    dim_offset: u32,
    /// Number of tops in the block.
    len: u32,
    /// Per top: its `nv` vertices, then its `ns` adjacency slots — one cache line per
    /// tetrahedron.
    data: Vec<u32>,
}

impl Block {
    fn new(kind: CellKind, first: u32, dim_offset: u32, len: u32) -> Block {
        let dim = kind.dim();
        Block {
            dim,
            kind,
            nv: kind.n_vertices() as u32,
            ns: if dim >= 2 {
                kind.n_faces(dim - 1) as u32
            } else {
                0
            },
            first,
            dim_offset,
            len,
            data: Vec::new(),
        }
    }
    #[inline]
    fn stride(&self) -> usize {
        (self.nv + self.ns) as usize
    }
    fn n_verts(&self) -> usize {
        self.len as usize * self.nv as usize
    }
    fn n_slots(&self) -> usize {
        self.len as usize * self.ns as usize
    }
}

/// The IA* data structure. See the [module docs](self).
///
/// ```
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// use starplex::ids::{CellId, VertexId};
/// use starplex::tds::iastar::IaStar;
/// use starplex::topo::FacetAdjacency;
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for _ in 0..4 { b.push_vertex(&[0.0, 0.0]).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// let ia = IaStar::new(&k).unwrap(); // triangles [0, 1, 2] and [1, 3, 2]
/// assert_eq!(ia.n_tops(2), 2);
/// assert_eq!(ia.top_adjacent(CellId(0)), vec![CellId(1)]);
/// assert_eq!(ia.n_nm_faces(), 0);
/// ```
#[derive(Clone, Debug)]
pub struct IaStar {
    n_vertices: u32,
    n_cells: u32,
    blocks: Vec<Block>,
    /// `nm[k]`: non-manifold (k-1)-faces of the top k-simplices, row = face, targets = tops.
    nm: Vec<Csr>,
    /// Per vertex: top edges and one top per k-cluster, sorted by cell id.
    vrefs: Csr,
    /// Number of tops per dimension.
    t: Vec<u64>,
    /// Every top is a simplex (else the CP paths of [`cp`] answer).
    simplicial: bool,
}

impl IaStar {
    /// Builds IA* from an indexed complex, simplicial or CP (top cells assumed maximal, as the
    /// complex's checked builder guarantees).
    ///
    /// # Errors
    /// More than 2^31 - 1 top cells.
    ///
    /// ```
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// use starplex::ids::{CellId, VertexId};
    /// use starplex::tds::iastar::IaStar;
    /// # let mut b = ComplexBuilder::new(2).unwrap();
    /// # for _ in 0..4 { b.push_vertex(&[0.0, 0.0]).unwrap(); }
    /// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
    /// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// let ia = IaStar::new(&k).unwrap(); // triangles [0, 1, 2] and [1, 3, 2]
    /// assert_eq!(ia.n_tops(2), 2);
    /// // one cluster per vertex: each vertex stores one triangle
    /// use starplex::topo::FacetAdjacency;
    /// assert_eq!(ia.vertex_references(VertexId(3)), vec![CellId(1)]);
    /// ```
    pub fn new(k: &IndexedComplex) -> Result<IaStar, IaStarError> {
        Self::build(k, Some(low_dim::Tuning::DEFAULT))
    }

    /// Builds IA*: by the construction for dimension ≤ 3 with `tuning` where it applies, else
    /// (and always when `tuning` is `None`) by the path for any dimension. Tests compare them.
    fn build(k: &IndexedComplex, tuning: Option<low_dim::Tuning>) -> Result<IaStar, IaStarError> {
        if k.n_cells() >= NM_BIT as usize {
            return Err(IaStarError::TooManyCells(k.n_cells()));
        }
        let mut blocks = Vec::with_capacity(k.blocks().len());
        let dmax = k.dim().unwrap_or(0);
        let mut t = vec![0u64; dmax + 1];
        let mut simplicial = true;
        for b in k.blocks() {
            let dim = b.kind.dim();
            simplicial &= b.kind.is_simplex();
            blocks.push(Block::new(b.kind, b.first, t[dim] as u32, b.len() as u32));
            t[dim] += b.len() as u64;
        }
        let nv = k.n_vertices();
        let incidences: u64 = blocks.iter().map(|b| b.n_verts() as u64).sum();
        // CP cells take the general path
        let fast = simplicial && dmax <= 3 && incidences + incidences / 2 < u32::MAX as u64;
        if let Some((nm, vrefs)) = tuning
            .filter(|_| fast)
            .and_then(|tu| low_dim::build(k, &mut blocks, &t, nv, tu))
        {
            return Ok(IaStar {
                n_vertices: nv as u32,
                n_cells: k.n_cells() as u32,
                blocks,
                nm,
                vrefs,
                t,
                simplicial,
            });
        }
        Ok(Self::build_general(k, blocks, t, simplicial))
    }

    /// The construction for any dimension and any cell kinds (grouping facet records); kept out
    /// of line so that the fast path's code is laid out as before CP cells existed.
    #[inline(never)]
    fn build_general(
        k: &IndexedComplex,
        mut blocks: Vec<Block>,
        t: Vec<u64>,
        simplicial: bool,
    ) -> IaStar {
        let dmax = k.dim().unwrap_or(0);
        let nv = k.n_vertices();
        for (blk, b) in blocks.iter_mut().zip(k.blocks()) {
            let (n, st) = (blk.nv as usize, blk.stride());
            blk.data = if blk.ns > 0 {
                let mut d = vec![NONE; blk.len as usize * st];
                for (rec, c) in d.chunks_exact_mut(st).zip(b.vertices.chunks_exact(n)) {
                    rec[..n].copy_from_slice(c);
                }
                d
            } else {
                b.vertices.to_vec()
            };
        }
        let mut nm: Vec<Csr> = vec![Csr::default(); dmax + 1];
        for d in 2..=dmax {
            if t[d] == 0 {
                continue;
            }
            nm[d] = if blocks.iter().any(|b| b.dim == d && !b.kind.is_simplex()) {
                cp::build_adjacency(&mut blocks, d)
            } else {
                build_adjacency(&mut blocks, d, nv)
            };
        }
        let mut ia = IaStar {
            n_vertices: nv as u32,
            n_cells: k.n_cells() as u32,
            blocks,
            nm,
            vrefs: Csr::default(),
            t,
            simplicial,
        };
        let vt = k.vertex_cells();
        ia.vrefs = if simplicial {
            ia.cluster_representatives(&vt)
        } else {
            cp::cluster_representatives(&ia, &vt)
        };
        ia
    }

    #[inline]
    fn block_of(&self, c: u32) -> &Block {
        if self.blocks.len() == 1 {
            return &self.blocks[0];
        }
        let i = self.blocks.partition_point(|b| b.first <= c) - 1;
        &self.blocks[i]
    }

    /// Vertices (input order) and adjacency slots of top `c`.
    #[inline]
    fn top(&self, c: u32) -> (usize, &[u32], &[u32]) {
        Self::record(self.block_of(c), c)
    }

    /// Vertices (input order) and adjacency slots of top `c` of block `b`.
    #[inline]
    fn record(b: &Block, c: u32) -> (usize, &[u32], &[u32]) {
        let n = b.nv as usize;
        let st = b.stride();
        let i = (c - b.first) as usize;
        let rec = &b.data[i * st..(i + 1) * st];
        (b.dim, &rec[..n], &rec[n..])
    }

    /// Calls `f` with every top reached from `c` through a facet containing `v`.
    #[inline]
    fn for_each_neighbour_at(&self, c: u32, v: u32, mut f: impl FnMut(u32)) {
        let b = self.block_of(c);
        let (dim, verts, adj) = Self::record(b, c);
        if !b.kind.is_simplex() {
            return cp::for_each_neighbour_at(self, b.kind, c, v, verts, adj, f);
        }
        for j in 0..adj.len() {
            if verts[j] == v {
                continue;
            }
            match decode(adj[j]) {
                Slot::None => {}
                Slot::Top(u) => f(u.0),
                Slot::NmFace(fid) => {
                    for &u in self.nm[dim].row(fid as usize) {
                        if u != c {
                            f(u)
                        }
                    }
                }
            }
        }
    }

    fn cluster_representatives(&self, vt: &Csr) -> Csr {
        let nv = self.n_vertices as usize;
        let mut offsets = Vec::with_capacity(nv + 1);
        let mut targets = Vec::with_capacity(nv + 2 * self.n_tops(1) as usize);
        let mut queue: Vec<u32> = Vec::new();
        // per row: visited marks, and a local copy of the records (the copy loop issues
        // independent loads, so their cache misses overlap; the search then runs in cache)
        let mut mark: Vec<bool> = Vec::new();
        let mut loc: Vec<u32> = Vec::new();
        let mut start: Vec<u32> = Vec::new();
        let mut dims: Vec<u8> = Vec::new();
        offsets.push(0u32);
        for v in 0..nv as u32 {
            let row = vt.row(v as usize);
            mark.clear();
            mark.resize(row.len(), false);
            loc.clear();
            start.clear();
            dims.clear();
            for &c in row {
                let (dim, verts, adj) = self.top(c);
                start.push(loc.len() as u32);
                dims.push(dim as u8);
                if dim >= 2 {
                    for &x in verts.iter().chain(adj) {
                        loc.push(x);
                    }
                }
            }
            for (ri, &c) in row.iter().enumerate() {
                if dims[ri] <= 1 {
                    targets.push(c);
                    continue;
                }
                if mark[ri] {
                    continue;
                }
                targets.push(c);
                mark[ri] = true;
                queue.clear();
                queue.push(ri as u32);
                while let Some(x) = queue.pop() {
                    let n = dims[x as usize] as usize + 1;
                    let s0 = start[x as usize] as usize;
                    let (verts, adj) = (&loc[s0..s0 + n], &loc[s0 + n..s0 + 2 * n]);
                    let mut visit = |u: u32| {
                        let ui = row
                            .binary_search(&u)
                            .expect("a neighbour through a facet at v contains v");
                        if !mark[ui] {
                            mark[ui] = true;
                            queue.push(ui as u32);
                        }
                    };
                    for j in 0..n {
                        if verts[j] == v {
                            continue;
                        }
                        match decode(adj[j]) {
                            Slot::None => {}
                            Slot::Top(u) => visit(u.0),
                            Slot::NmFace(f) => {
                                for &u in self.nm[n - 1].row(f as usize) {
                                    if u != row[x as usize] {
                                        visit(u);
                                    }
                                }
                            }
                        }
                    }
                }
            }
            offsets.push(targets.len() as u32);
        }
        Csr { offsets, targets }
    }

    /// The ids of the non-manifold facets of the top k-cells (the (k-1)-faces shared by three
    /// or more top k-cells), a range of [`FacetAdjacency::nm_face_cells`] ids.
    ///
    /// ```
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// use starplex::ids::{CellId, VertexId};
    /// use starplex::tds::iastar::IaStar;
    /// use starplex::topo::FacetAdjacency;
    /// # let mut b = ComplexBuilder::new(2).unwrap();
    /// # for _ in 0..5 { b.push_vertex(&[0.0, 0.0]).unwrap(); }
    /// # for c in [[0, 1, 2], [0, 1, 3], [0, 1, 4]] { b.push_cell(CellKind::Simplex(2), &c).unwrap(); }
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// let ia = IaStar::new(&k).unwrap(); // the book: three triangles on edge {0,1}
    /// assert_eq!(ia.nm_faces_of_dim(2), 0..1); // edge {0,1}
    /// assert_eq!(ia.nm_faces_of_dim(3), 1..1);
    /// assert_eq!(ia.nm_face_cells(0), vec![CellId(0), CellId(1), CellId(2)]);
    /// ```
    pub fn nm_faces_of_dim(&self, k: usize) -> std::ops::Range<u32> {
        let base = self.nm_base(k.min(self.nm.len()));
        base..base + self.nm.get(k).map_or(0, |c| c.n_rows() as u32)
    }

    /// The global id of the first non-manifold facet of dimension k - 1.
    fn nm_base(&self, k: usize) -> u32 {
        self.nm[..k].iter().map(|c| c.n_rows() as u32).sum()
    }

    /// The dimension k and per-dimension index of global non-manifold facet `f`.
    fn nm_local(&self, f: u32) -> Option<(usize, u32)> {
        let mut f = f;
        for (k, c) in self.nm.iter().enumerate() {
            let n = c.n_rows() as u32;
            if f < n {
                return Some((k, f));
            }
            f -= n;
        }
        None
    }

    /// Number of k-clusters at `v` (k ≥ 2), or of top edges for k = 1.
    ///
    /// ```
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// use starplex::ids::{CellId, VertexId};
    /// use starplex::tds::iastar::IaStar;
    /// // a bowtie: two triangles meeting at vertex 0 only
    /// let mut b = ComplexBuilder::new(2).unwrap();
    /// for _ in 0..5 { b.push_vertex(&[0.0, 0.0]).unwrap(); }
    /// b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
    /// b.push_cell(CellKind::Simplex(2), &[0, 3, 4]).unwrap();
    /// let ia = IaStar::new(&b.build(&BuildOptions::default()).unwrap().0).unwrap();
    /// assert_eq!(ia.n_clusters(VertexId(0), 2), 2);
    /// assert_eq!(ia.n_clusters(VertexId(1), 2), 1);
    /// assert_eq!(ia.n_clusters(VertexId(0), 1), 0); // no top edges
    /// ```
    pub fn n_clusters(&self, v: VertexId, k: usize) -> usize {
        self.vrefs
            .row(v.index())
            .iter()
            .filter(|&&c| self.top(c).0 == k)
            .count()
    }

    /// Number of top k-simplices.
    ///
    /// ```
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// use starplex::ids::{CellId, VertexId};
    /// use starplex::tds::iastar::IaStar;
    /// # let mut b = ComplexBuilder::new(2).unwrap();
    /// # for _ in 0..4 { b.push_vertex(&[0.0, 0.0]).unwrap(); }
    /// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
    /// # b.push_cell(CellKind::Simplex(1), &[2, 3]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// let ia = IaStar::new(&k).unwrap(); // triangle 0 = [0, 1, 2] and top edge 1 = [2, 3]
    /// assert_eq!((ia.n_tops(0), ia.n_tops(1), ia.n_tops(2), ia.n_tops(3)), (0, 1, 1, 0));
    /// ```
    pub fn n_tops(&self, k: usize) -> u64 {
        self.t.get(k).copied().unwrap_or(0)
    }

    /// References with the Stellar-code variant (adjacency slots also for top edges: +2 t_1).
    ///
    /// ```
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// use starplex::ids::{CellId, VertexId};
    /// use starplex::tds::iastar::IaStar;
    /// # let mut b = ComplexBuilder::new(2).unwrap();
    /// # for _ in 0..4 { b.push_vertex(&[0.0, 0.0]).unwrap(); }
    /// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
    /// # b.push_cell(CellKind::Simplex(1), &[2, 3]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// let ia = IaStar::new(&k).unwrap(); // triangle 0 = [0, 1, 2] and top edge 1 = [2, 3]
    /// use starplex::topo::Storage;
    /// assert_eq!(ia.refs_stellar_variant(), ia.refs() + 2); // one top edge
    /// ```
    pub fn refs_stellar_variant(&self) -> u64 {
        self.refs() + 2 * self.n_tops(1)
    }

    /// The index of top `c` among the top simplices of its dimension, and that dimension.
    ///
    /// ```
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// use starplex::ids::{CellId, VertexId};
    /// use starplex::tds::iastar::IaStar;
    /// # let mut b = ComplexBuilder::new(2).unwrap();
    /// # for _ in 0..4 { b.push_vertex(&[0.0, 0.0]).unwrap(); }
    /// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
    /// # b.push_cell(CellKind::Simplex(1), &[2, 3]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// let ia = IaStar::new(&k).unwrap(); // triangle 0 = [0, 1, 2] and top edge 1 = [2, 3]
    /// assert_eq!(ia.dim_index(CellId(0)), (2, 0));
    /// assert_eq!(ia.dim_index(CellId(1)), (1, 0));
    /// ```
    pub fn dim_index(&self, c: CellId) -> (usize, u32) {
        let b = self.block_of(c.0);
        (b.dim, b.dim_offset + (c.0 - b.first))
    }

    /// The input id of the `i`-th top m-simplex.
    ///
    /// ```
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// use starplex::ids::{CellId, VertexId};
    /// use starplex::tds::iastar::IaStar;
    /// # let mut b = ComplexBuilder::new(2).unwrap();
    /// # for _ in 0..4 { b.push_vertex(&[0.0, 0.0]).unwrap(); }
    /// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
    /// # b.push_cell(CellKind::Simplex(1), &[2, 3]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// let ia = IaStar::new(&k).unwrap(); // triangle 0 = [0, 1, 2] and top edge 1 = [2, 3]
    /// assert_eq!(ia.cell_of(2, 0), Some(CellId(0)));
    /// assert_eq!(ia.cell_of(1, 0), Some(CellId(1)));
    /// assert_eq!(ia.cell_of(2, 1), None);
    /// ```
    pub fn cell_of(&self, m: usize, i: u32) -> Option<CellId> {
        let b = self
            .blocks
            .iter()
            .rev()
            .find(|b| b.dim == m && b.dim_offset <= i)?;
        let local = i - b.dim_offset;
        (local < b.len).then(|| CellId(b.first + local))
    }

    fn vt_into(&self, v: u32, out: &mut Vec<CellId>) {
        // breadth-first over each cluster, using `out` itself as the queue
        out.clear();
        let mut seen: FxHashSet<u32> = FxHashSet::default();
        for &r in self.vrefs.row(v as usize) {
            if self.top(r).0 <= 1 {
                out.push(CellId(r));
                continue;
            }
            let start = out.len();
            out.push(CellId(r));
            let mut head = start;
            while head < out.len() {
                let x = out[head].0;
                head += 1;
                self.for_each_neighbour_at(x, v, |u| {
                    let found = if out.len() - start <= 48 {
                        out[start..].contains(&CellId(u))
                    } else {
                        if seen.is_empty() {
                            seen.extend(out[start..].iter().map(|c| c.0));
                        }
                        !seen.insert(u)
                    };
                    if !found {
                        out.push(CellId(u));
                        if !seen.is_empty() {
                            seen.insert(u);
                        }
                    }
                });
            }
            seen.clear();
        }
        out.sort_unstable();
    }
}

mod cp;

/// Construction for complexes of dimension at most 3, in a few passes over flat arrays. The
/// tops of real meshes come in no spatial order and the build is bound by memory traffic, so
/// every pass reads its input in order, scattered writes go to a few hundred "coarse" buckets
/// at once (vertices grouped by their high bits) or to small arrays, and a facet is one packed
/// word:
///
/// 1. vertex degrees, and per vertex the number of facets whose smallest vertex it is;
/// 2. the vertex → tops relation (VT, rows sorted by id) by counting sort, and every facet as
///    one word (its vertices, its top, the omitted vertex's position, and its top's place in
///    the VT row of each of its vertices) in the coarse bucket of its smallest vertex;
/// 3. per coarse bucket (in cache): a counting sort by smallest vertex, then a small sort
///    groups equal facets; their adjacency slots are written, and for each vertex w of the
///    facet a *link* (two places in the VT row of w) joins the two tops in the star of w (the
///    chain of tops for a non-manifold facet);
/// 4. per coarse bucket of vertices, once its links are all known: a union-find over their VT
///    rows; the roots (the smallest id of each cluster, top edges and top vertices alone) are
///    the vertices' references;
/// 5. the top records, in order.
///
/// On large inputs the passes run in parallel (rayon), with the same result for any number of
/// workers: passes 1 and 2 over consecutive parts of a one-block complex (each part writes its
/// own VT rows, with places counted from the earlier parts, and its own facet words; the rows
/// are then joined part after part), pass 3 over ranges of coarse buckets holding about the
/// same number of facet words (adjacency slots are relaxed atomic stores, each slot written by
/// its one facet; non-manifold facets are numbered range after range), and pass 4 over ranges
/// holding about the same number of places and links.
mod low_dim {
    use super::{Block, Csr, IndexedComplex, NM_BIT, NONE};

    // adjacency slots are kept complemented while they are built: zero is `NONE`
    const _: () = assert!(!NONE == 0);
    use crate::algo::unionfind::union_min_in as union;
    use crate::buf::{large_with, large_zeroed};
    use rayon::prelude::*;
    use std::sync::atomic::{AtomicU32, Ordering::Relaxed};

    /// Settings of the construction (tests vary them to reach every code path on small
    /// complexes).
    #[derive(Clone, Copy, Debug)]
    pub(super) struct Tuning {
        /// The number of coarse buckets is at most `1 << coarse_bits`.
        pub coarse_bits: u32,
        /// Use 128-bit facet words even when 64 bits would do.
        pub wide: bool,
        /// Pack a link into one word in buckets with fewer than 2^16 places.
        pub pack_links: bool,
        /// Number of parallel parts: of the input in passes 1 and 2 (only when the complex is
        /// one block of triangles or tetrahedra), of the coarse buckets in passes 3 and 4 (any
        /// complex). 0: one per worker thread (at most 4) for 2^17 tops or more, else 1. The
        /// result is the same for any number.
        pub parts: usize,
    }

    impl Tuning {
        pub const DEFAULT: Tuning = Tuning {
            coarse_bits: 10,
            wide: false,
            pack_links: true,
            parts: 0,
        };
    }

    /// The facet words of one part of the input, by coarse bucket: bucket `c` is
    /// `recs[start[c]..start[c + 1]]`.
    struct Part<W> {
        recs: Vec<W>,
        start: Vec<u32>,
    }

    /// The counts of pass 1 for one part of a one-block complex.
    struct PartCounts {
        /// The part's tops (indices in the block).
        range: std::ops::Range<usize>,
        /// Per vertex, the part's tops at it.
        deg: Vec<u32>,
        /// Per vertex `v`, at `v + 1`: the part's facets whose smallest vertex is `v`.
        fc: Vec<u32>,
    }

    /// The number of parallel parts for `n` tops.
    fn n_parts(n: usize, tuning: Tuning) -> usize {
        match tuning.parts {
            0 if n >= 1 << 17 => rayon::current_num_threads().clamp(1, 4),
            0 => 1,
            p => p.min(n.max(1)),
        }
    }

    /// The parts of pass 1 and 2 (empty: one sequential pass over every block).
    fn part_ranges(k: &IndexedComplex, tuning: Tuning) -> Vec<std::ops::Range<usize>> {
        let [b] = k.blocks() else {
            return Vec::new();
        };
        let n = b.len();
        let p = n_parts(n, tuning);
        if p <= 1 || !matches!(b.kind.dim(), 2 | 3) {
            return Vec::new();
        }
        (0..p).map(|i| i * n / p..(i + 1) * n / p).collect()
    }

    /// Pass 1 over the tops `verts` of dimension `d` ≥ 2: degrees, facet incidences (if
    /// asked: in a one-dimension complex they are `d` times the degrees), and facets by
    /// smallest vertex (at `v + 1`).
    fn count_tops(
        verts: &[u32],
        d: usize,
        deg: &mut [u32],
        mut finc: Option<&mut [u32]>,
        fc: &mut [u32],
    ) {
        for c in verts.chunks_exact(d + 1) {
            let (mut m0, mut m1) = (u32::MAX, u32::MAX);
            for &v in c {
                deg[v as usize] += 1;
                if let Some(f) = finc.as_deref_mut() {
                    f[v as usize] += d as u32;
                }
                if v < m0 {
                    m1 = m0;
                    m0 = v;
                } else if v < m1 {
                    m1 = v;
                }
            }
            fc[m0 as usize + 1] += d as u32;
            fc[m1 as usize + 1] += 1;
        }
    }

    /// A facet word: from the most significant end, the low bits of the facet's smallest vertex
    /// (`low`), its other vertices (`vb` bits each), the input position of the vertex the facet
    /// omits (2 bits) and the top's place in the VT row of each of the facet's vertices (`pb`
    /// bits each; the place in the smallest vertex's row names the top).
    /// All arithmetic on facet words is done in the word's own width (64-bit words are the
    /// common case, and 128-bit shifts cost several instructions each).
    pub(super) trait Word:
        bytemuck::Pod
        + Ord
        + Default
        + Send
        + Sync
        + std::ops::Shl<u32, Output = Self>
        + std::ops::Shr<u32, Output = Self>
        + std::ops::BitOr<Output = Self>
    {
        fn of(x: u32) -> Self;
        /// The low 32 bits.
        fn low32(self) -> u32;
        /// The low 64 bits.
        fn low64(self) -> u64;
    }
    impl Word for u64 {
        #[inline]
        fn of(x: u32) -> Self {
            x as u64
        }
        #[inline]
        fn low32(self) -> u32 {
            self as u32
        }
        #[inline]
        fn low64(self) -> u64 {
            self
        }
    }
    impl Word for u128 {
        #[inline]
        fn of(x: u32) -> Self {
            x as u128
        }
        #[inline]
        fn low32(self) -> u32 {
            self as u32
        }
        #[inline]
        fn low64(self) -> u64 {
            self as u64
        }
    }

    /// The mask of the low `b` bits (`b` ≤ 32).
    #[inline]
    fn mask(b: u32) -> u32 {
        ((1u64 << b) - 1) as u32
    }

    fn bits(x: u64) -> u32 {
        (64 - x.leading_zeros()).max(1)
    }

    /// Bit layout of the facet words.
    #[derive(Clone, Copy)]
    struct Layout {
        vb: u32,
        low: u32,
        pb: u32,
    }

    impl Layout {
        /// Bits of a facet word of a top `D`-simplex.
        fn total(&self, d: u32) -> u32 {
            self.low + (d - 1) * self.vb + 2 + d * self.pb
        }
        /// Shift of the omitted vertex's position.
        #[inline]
        fn tsh(&self, d: usize) -> u32 {
            d as u32 * self.pb
        }
        /// Shift of the facet's vertices after the smallest.
        #[inline]
        fn ksh(&self, d: usize) -> u32 {
            self.tsh(d) + 2
        }
        /// Shift of the smallest vertex's low bits.
        #[inline]
        fn msh(&self, d: usize) -> u32 {
            self.ksh(d) + (d as u32 - 1) * self.vb
        }
    }

    /// The counts of pass 1.
    struct Counts {
        /// VT row offsets.
        vt_off: Vec<u32>,
        /// Per vertex, facet incidences (facets of tops of dimension ≥ 2 at it).
        finc: Vec<u32>,
        /// Facet bucket offsets (by smallest vertex), dimensions 2 and 3.
        fcnt: [Vec<u32>; 2],
        /// Per part, when passes 1 and 2 run in parallel.
        parts: Vec<PartCounts>,
    }

    /// Builds the adjacency slots, the top records, the non-manifold face lists and the
    /// per-vertex references; `None` when a facet does not pack into 128 bits (then the
    /// general construction is used).
    pub(super) fn build(
        k: &IndexedComplex,
        blocks: &mut [Block],
        t: &[u64],
        nv: usize,
        tuning: Tuning,
    ) -> Option<(Vec<Csr>, Csr)> {
        let dmax = t.len() - 1;
        // 1. degrees and facet bucket sizes
        let mut deg = vec![0u32; nv];
        let mut finc = vec![0u32; nv];
        let mut fcnt: [Vec<u32>; 2] = [Vec::new(), Vec::new()];
        for d in 2..=dmax.min(3) {
            if t[d] > 0 {
                fcnt[d - 2] = vec![0u32; nv + 1];
            }
        }
        let ranges = part_ranges(k, tuning);
        let mut parts = Vec::new();
        if ranges.is_empty() {
            for b in k.blocks() {
                let d = b.kind.dim();
                if d < 2 {
                    for &v in b.vertices.iter() {
                        deg[v as usize] += 1;
                    }
                    continue;
                }
                count_tops(&b.vertices, d, &mut deg, Some(&mut finc), &mut fcnt[d - 2]);
            }
        } else {
            let b = &k.blocks()[0];
            let d = b.kind.dim();
            let counted: Vec<PartCounts> = ranges
                .into_par_iter()
                .map(|r| {
                    let (mut deg, mut fc) = (vec![0u32; nv], vec![0u32; nv + 1]);
                    let verts = &b.vertices[r.start * (d + 1)..r.end * (d + 1)];
                    count_tops(verts, d, &mut deg, None, &mut fc);
                    PartCounts { range: r, deg, fc }
                })
                .collect();
            for pc in counted {
                for (x, y) in deg.iter_mut().zip(&pc.deg) {
                    *x += y;
                }
                for (x, y) in fcnt[d - 2].iter_mut().zip(&pc.fc) {
                    *x += y;
                }
                parts.push(pc);
            }
            for (f, &x) in finc.iter_mut().zip(&deg) {
                *f = d as u32 * x;
            }
        }
        let maxdeg = deg.iter().copied().max().unwrap_or(0);
        let mut vt_off = Vec::with_capacity(nv + 1);
        vt_off.push(0u32);
        let mut a = 0u32;
        for &x in &deg {
            a += x;
            vt_off.push(a);
        }
        drop(deg);
        for f in fcnt.iter_mut().filter(|f| !f.is_empty()) {
            for i in 0..nv {
                f[i + 1] += f[i];
            }
        }
        let t3 = t.get(3).copied().unwrap_or(0);
        let vb = bits(nv.saturating_sub(1) as u64);
        let lay = Layout {
            vb,
            low: vb.saturating_sub(tuning.coarse_bits),
            pb: bits(maxdeg.saturating_sub(1) as u64),
        };
        let bits = lay.total(if t3 > 0 { 3 } else { 2 });
        let counts = Counts {
            vt_off,
            finc,
            fcnt,
            parts,
        };
        if bits <= 64 && !tuning.wide {
            Some(run::<u64>(k, blocks, t, nv, lay, counts, tuning))
        } else if bits <= 128 {
            Some(run::<u128>(k, blocks, t, nv, lay, counts, tuning))
        } else {
            None
        }
    }

    /// Dimension-local indices of the tops of one dimension: (first id, first dimension-local
    /// index) per block of that dimension.
    #[derive(Clone)]
    struct DimIds(Vec<(u32, u32)>);

    impl DimIds {
        fn new(blocks: &[Block], d: usize) -> DimIds {
            DimIds(
                blocks
                    .iter()
                    .filter(|b| b.dim == d)
                    .map(|b| (b.first, b.dim_offset))
                    .collect(),
            )
        }
        /// The dimension-local index of top `c` (of this dimension).
        #[inline]
        fn local(&self, c: u32) -> usize {
            let i = if self.0.len() == 1 {
                0
            } else {
                self.0.partition_point(|a| a.0 <= c) - 1
            };
            let (f, o) = self.0[i];
            (o + (c - f)) as usize
        }
    }

    /// Links waiting for the coarse bucket of their vertex: pairs of places in the bucket's
    /// VT rows. A bucket's area has room for half the facet incidences at its vertices, enough
    /// for the links of facets shared by two tops (two incidences each); those of non-manifold
    /// facets go to `over`. In a *narrow* bucket (fewer than 2^16 places) a link is one word
    /// (`x << 16 | y`), else two.
    struct Links {
        area: Vec<u32>,
        start: Vec<usize>,
        end: Vec<usize>,
        narrow: Vec<bool>,
        over: Vec<Vec<[u32; 2]>>,
    }

    /// What grouping a range of coarse buckets leaves: its links into buckets from its start
    /// on, and per dimension 2 and 3 its non-manifold facets (offsets, tops, and the slots to
    /// write).
    struct Grouped {
        links: Links,
        nm: [NmFound; 2],
    }

    /// Non-manifold facets found by one range: CSR offsets and tops, and (slot, index) pairs.
    type NmFound = (Vec<u32>, Vec<u32>, Vec<(usize, u32)>);

    /// `n` consecutive ranges of `0..nc` of about the same total `weight`.
    fn balanced(nc: usize, n: usize, weight: impl Fn(usize) -> u64) -> Vec<std::ops::Range<usize>> {
        let w: Vec<u64> = (0..nc).map(weight).collect();
        let total: u64 = w.iter().sum();
        let mut out = Vec::with_capacity(n);
        let (mut start, mut acc) = (0usize, 0u64);
        for (c, &x) in w.iter().enumerate() {
            acc += x;
            // close range i once the running total passes (i + 1) / n of the whole
            if out.len() + 1 < n && acc * n as u64 >= total * (out.len() as u64 + 1) {
                out.push(start..c + 1);
                start = c + 1;
            }
        }
        out.push(start..nc);
        while out.len() < n {
            out.push(nc..nc);
        }
        out
    }

    /// Splits `a` into the pieces of the bucket ranges `br` (`at(c)`: where bucket `c`
    /// starts in `a`).
    fn split_by<'a, T>(
        a: &'a mut [T],
        br: &[std::ops::Range<usize>],
        at: impl Fn(usize) -> usize,
    ) -> Vec<&'a mut [T]> {
        let mut rest = a;
        let mut pieces = Vec::with_capacity(br.len());
        for r in br {
            let (piece, tail) = std::mem::take(&mut rest).split_at_mut(at(r.end) - at(r.start));
            pieces.push(piece);
            rest = tail;
        }
        pieces
    }

    impl Links {
        /// Leaves a link joining places `x` and `y` of the VT row of `w` for the bucket of `w`
        /// (`nm`: a link of a non-manifold facet).
        #[inline(always)]
        fn push(&mut self, vt_off: &[u32], low: u32, w: u32, x: u32, y: u32, nm: bool) {
            let cw = (w >> low) as usize;
            let base = vt_off[w as usize] - vt_off[cw << low];
            let (x, y) = (base + x, base + y);
            if nm {
                self.over[cw].push([x, y]);
            } else {
                let e = &mut self.end[cw];
                if self.narrow[cw] {
                    self.area[*e] = x << 16 | y;
                    *e += 1;
                } else {
                    self.area[*e] = x;
                    self.area[*e + 1] = y;
                    *e += 2;
                }
            }
        }
    }

    /// The VT relation: row offsets and targets (rows sorted by id).
    struct Vt<'a> {
        off: &'a [u32],
        targets: &'a [u32],
    }

    /// Scratch of one dimension's facet grouping.
    struct Group<'a> {
        lay: Layout,
        ids: DimIds,
        /// Adjacency slot values, complemented (so that a zeroed array is all `NONE`),
        /// dimension-local slot `li * (d + 1) + j`. Shared by the workers: each slot is
        /// written by the one facet it holds (relaxed stores, plain moves on common targets).
        adj: &'a [AtomicU32],
        nm_tops: Vec<u32>,
        nm_offsets: Vec<u32>,
        /// The slots of the non-manifold facets found here, with the facet's index among
        /// them; their values are written once all workers have numbered their facets.
        nm_slots: Vec<(usize, u32)>,
    }

    fn run<W: Word>(
        k: &IndexedComplex,
        blocks: &mut [Block],
        t: &[u64],
        nv: usize,
        lay: Layout,
        counts: Counts,
        tuning: Tuning,
    ) -> (Vec<Csr>, Csr) {
        let Counts {
            vt_off,
            finc,
            fcnt,
            parts,
        } = counts;
        let dmax = t.len() - 1;
        let low = lay.low;
        let nc = if nv == 0 { 0 } else { ((nv - 1) >> low) + 1 };
        let narrow: Vec<bool> = (0..nc)
            .map(|c| {
                let (v0, v1) = (c << low, ((c + 1) << low).min(nv));
                tuning.pack_links && vt_off[v1] - vt_off[v0] <= 1 << 16
            })
            .collect();
        // room for the links into each bucket (see `Links`)
        let mut room = Vec::with_capacity(nc);
        let mut l = 0usize;
        for (v, &x) in finc.iter().enumerate() {
            l += if narrow[v >> low] {
                x as usize / 2
            } else {
                x as usize / 2 * 2
            };
            if v & ((1 << low) - 1) == (1 << low) - 1 || v + 1 == nv {
                room.push(l);
                l = 0;
            }
        }
        drop(finc);
        // 2. VT by counting sort; facet words into coarse buckets
        let n_ranges = n_parts(k.n_cells(), tuning);
        let total = *vt_off.last().unwrap_or(&0) as usize;
        let (mut targets, recs) = if parts.is_empty() {
            scatter_blocks::<W>(k, blocks, t, &vt_off, &fcnt, lay)
        } else {
            scatter_parts::<W>(k, blocks, &vt_off, parts, lay)
        };
        debug_assert_eq!(targets.len(), total);
        // 3. per coarse bucket, in ranges of buckets run in parallel: group equal facets,
        //    write the adjacency slots, join places of the bucket's own rows at once and
        //    leave links for later buckets
        let adj: [Vec<AtomicU32>; 2] = std::array::from_fn(|d| {
            let len = (d + 3) * t.get(d + 2).map_or(0, |&x| x as usize);
            large_with(len, || AtomicU32::new(0))
        });
        let ids = [DimIds::new(blocks, 2), DimIds::new(blocks, 3)];
        let vlo = |c: usize| vt_off[(c << low).min(nv)] as usize;
        // ranges with about the same number of facet words (buckets of small vertices hold
        // more of them: a facet is filed under its smallest vertex)
        let branges = balanced(nc, n_ranges, |c| {
            let (v0, v1) = (c << low, ((c + 1) << low).min(nv));
            fcnt.iter()
                .filter(|f| !f.is_empty())
                .map(|f| (f[v1] - f[v0]) as u64)
                .sum()
        });
        let vt = Vt {
            off: &vt_off,
            targets: &targets,
        };
        let grouped: Vec<Grouped> = branges
            .par_iter()
            .map(|br| {
                // links into the buckets from this range's start on
                let mut start = vec![0usize; nc + 1];
                for c in br.start..nc {
                    start[c + 1] = start[c] + room[c];
                }
                let mut links = Links {
                    area: large_zeroed(start[nc]),
                    end: start[..nc].to_vec(),
                    start,
                    narrow: narrow.clone(),
                    over: vec![Vec::new(); nc],
                };
                let mut groups = [
                    Group::new(lay, ids[0].clone(), &adj[0]),
                    Group::new(lay, ids[1].clone(), &adj[1]),
                ];
                let mut tmp: Vec<W> = Vec::new();
                for c in br.clone() {
                    for (d, g) in groups.iter_mut().enumerate() {
                        if !fcnt[d].is_empty() {
                            g.chunk(d + 2, &recs[d], &fcnt[d], &vt, c, &mut tmp, &mut links);
                        }
                    }
                }
                let [g2, g3] = groups;
                Grouped {
                    links,
                    nm: [
                        (g2.nm_offsets, g2.nm_tops, g2.nm_slots),
                        (g3.nm_offsets, g3.nm_tops, g3.nm_slots),
                    ],
                }
            })
            .collect();
        drop((recs, fcnt));
        // the non-manifold facets, numbered range after range (the sequential order)
        let mut nm: Vec<Csr> = vec![Csr::default(); dmax + 1];
        for d in 0..2 {
            if t.get(d + 2).is_none_or(|&x| x == 0) {
                continue;
            }
            let mut offsets = vec![0u32];
            let mut tops = Vec::new();
            for gr in &grouped {
                let (o, ts, slots) = &gr.nm[d];
                let first = (offsets.len() - 1) as u32;
                for &(slot, f) in slots {
                    adj[d][slot].store(!(NM_BIT | (first + f)), Relaxed);
                }
                let base = tops.len() as u32;
                offsets.extend(o[1..].iter().map(|&x| base + x));
                tops.extend_from_slice(ts);
            }
            nm[d + 2] = Csr {
                offsets,
                targets: tops,
            };
        }
        // 4. per coarse bucket, in parallel ranges: the links into it from every range, then
        //    the clusters of its vertices (roots kept at the front of the range's VT); ranges
        //    of about the same number of places and links
        let branges = balanced(nc, n_ranges, |c| {
            let links: usize = grouped
                .iter()
                .map(|g| g.links.end[c] - g.links.start[c] + g.links.over[c].len())
                .sum();
            (vlo(c + 1) - vlo(c) + links) as u64
        });
        let t_pieces = split_by(&mut targets, &branges, vlo);
        let kept: Vec<(usize, Vec<u32>)> = branges
            .par_iter()
            .zip(t_pieces)
            .map(|(br, tg)| {
                let mut par: Vec<u32> = Vec::new();
                let base = vlo(br.start);
                let mut out = 0usize;
                let mut offs =
                    Vec::with_capacity((br.end << low).min(nv) - (br.start << low).min(nv));
                for c in br.clone() {
                    let (lo, hi) = (vlo(c) - base, vlo(c + 1) - base);
                    par.clear();
                    par.extend(0..(hi - lo) as u32);
                    let bpar = &mut par[..];
                    let mut joined = false;
                    for gr in &grouped {
                        let lk = &gr.links;
                        let ls = &lk.area[lk.start[c]..lk.end[c]];
                        joined |= !ls.is_empty() || !lk.over[c].is_empty();
                        if lk.narrow[c] {
                            for &p in ls {
                                union(bpar, p >> 16, p & 0xffff);
                            }
                        } else {
                            for p in ls.chunks_exact(2) {
                                union(bpar, p[0], p[1]);
                            }
                        }
                        for &[x, y] in &lk.over[c] {
                            union(bpar, x, y);
                        }
                    }
                    let (v0, v1) = (c << low, ((c + 1) << low).min(nv));
                    if !joined {
                        tg.copy_within(lo..hi, out);
                        for v in v0..v1 {
                            offs.push((out + (vt_off[v + 1] as usize - base - lo)) as u32);
                        }
                        out += hi - lo;
                        continue;
                    }
                    let mut i = 0usize;
                    for v in v0..v1 {
                        let e = vt_off[v + 1] as usize - base - lo;
                        while i < e {
                            if bpar[i] == i as u32 {
                                tg[out] = tg[lo + i];
                                out += 1;
                            }
                            i += 1;
                        }
                        offs.push(out as u32);
                    }
                }
                (out, offs)
            })
            .collect();
        drop(grouped);
        // the ranges' kept references, packed
        let mut offsets = Vec::with_capacity(nv + 1);
        offsets.push(0u32);
        let mut out = 0usize;
        for (br, (n_kept, offs)) in branges.iter().zip(kept) {
            let base = vlo(br.start);
            targets.copy_within(base..base + n_kept, out);
            offsets.extend(offs.iter().map(|&x| x + out as u32));
            out += n_kept;
        }
        targets.truncate(out);
        targets.shrink_to_fit();
        // 5. the top records: vertices (input order), then the adjacency slots
        for (blk, b) in blocks.iter_mut().zip(k.blocks()) {
            let d = blk.dim;
            if d < 2 {
                blk.data = b.vertices.to_vec();
                continue;
            }
            let n = d + 1;
            let a = &adj[d - 2][blk.dim_offset as usize * n..];
            let mut data = Vec::with_capacity(2 * b.vertices.len());
            for (c, s) in b.vertices.chunks_exact(n).zip(a.chunks_exact(n)) {
                data.extend_from_slice(c);
                data.extend(s.iter().map(|x| !x.load(Relaxed)));
            }
            blk.data = data;
        }
        (nm, Csr { offsets, targets })
    }

    /// Pass 2 over the tops `verts` of dimension `d` ≥ 2 (ids from `first`): their VT entries
    /// (`pos[v]`: the next slot of `targets` for `v`, and the number of tops at `v` before it)
    /// and their facet words, into the coarse buckets (`cpos`: the next slot of each).
    #[allow(clippy::too_many_arguments)]
    fn scatter_tops<W: Word>(
        d: usize,
        verts: &[u32],
        first: u32,
        pos: &mut [[u32; 2]],
        targets: &mut [u32],
        recs: &mut [W],
        cpos: &mut [u32],
        lay: Layout,
    ) {
        let n = d + 1;
        for (i, c) in verts.chunks_exact(n).enumerate() {
            let id = first + i as u32;
            // sorted vertices, their input positions and the top's places in their rows
            let (sv, pm) = sort_top(c);
            let mut vp = [0u32; 4];
            for s in 0..n {
                let p = &mut pos[sv[s] as usize];
                vp[s] = p[1];
                targets[p[0] as usize] = id;
                *p = [p[0] + 1, p[1] + 1];
            }
            if d == 2 {
                emit::<W, 2>(&sv, &pm, &vp, lay, recs, cpos);
            } else {
                emit::<W, 3>(&sv, &pm, &vp, lay, recs, cpos);
            }
        }
    }

    /// Pass 2, sequentially over every block: the VT targets and, per dimension 2 and 3, the
    /// facet words as one part.
    fn scatter_blocks<W: Word>(
        k: &IndexedComplex,
        blocks: &[Block],
        t: &[u64],
        vt_off: &[u32],
        fcnt: &[Vec<u32>; 2],
        lay: Layout,
    ) -> (Vec<u32>, [Vec<Part<W>>; 2]) {
        let nv = vt_off.len() - 1;
        let low = lay.low;
        let nc = if nv == 0 { 0 } else { ((nv - 1) >> low) + 1 };
        let mut pos: Vec<[u32; 2]> = vt_off[..nv].iter().map(|&o| [o, 0]).collect();
        let mut targets: Vec<u32> = large_zeroed(*vt_off.last().unwrap_or(&0) as usize);
        let mut recs: [Vec<Part<W>>; 2] = [Vec::new(), Vec::new()];
        let mut cpos: [Vec<u32>; 2] = [Vec::new(), Vec::new()];
        for d in 0..2 {
            if !fcnt[d].is_empty() {
                let start: Vec<u32> = (0..=nc).map(|c| fcnt[d][(c << low).min(nv)]).collect();
                cpos[d] = start[..nc].to_vec();
                let len = (d + 3) * t.get(d + 2).map_or(0, |&x| x as usize);
                recs[d].push(Part {
                    recs: large_zeroed(len),
                    start,
                });
            }
        }
        for (blk, b) in blocks.iter().zip(k.blocks()) {
            let d = blk.dim;
            if d < 2 {
                for (i, c) in b.vertices.chunks_exact(d + 1).enumerate() {
                    let id = blk.first + i as u32;
                    for &v in c {
                        let p = &mut pos[v as usize];
                        targets[p[0] as usize] = id;
                        *p = [p[0] + 1, p[1] + 1];
                    }
                }
                continue;
            }
            let r = &mut recs[d - 2][0].recs;
            let verts = &b.vertices[..];
            scatter_tops(
                d,
                verts,
                blk.first,
                &mut pos,
                &mut targets,
                r,
                &mut cpos[d - 2],
                lay,
            );
        }
        (targets, recs)
    }

    /// Pass 2 in parallel over the parts of a one-block complex: each part writes its own VT
    /// (rows laid out by its own degrees, places counted from the tops of the earlier parts)
    /// and its own facet words; the VT rows are then joined part after part, so the result is
    /// the sequential one.
    fn scatter_parts<W: Word>(
        k: &IndexedComplex,
        blocks: &[Block],
        vt_off: &[u32],
        parts: Vec<PartCounts>,
        lay: Layout,
    ) -> (Vec<u32>, [Vec<Part<W>>; 2]) {
        let nv = vt_off.len() - 1;
        let low = lay.low;
        let nc = if nv == 0 { 0 } else { ((nv - 1) >> low) + 1 };
        let (blk, b) = (&blocks[0], &k.blocks()[0]);
        let d = blk.dim;
        // per part: its VT row offsets, and where each vertex's places start
        let mut before = vec![0u32; nv];
        let mut jobs = Vec::with_capacity(parts.len());
        for pc in parts {
            let mut off = Vec::with_capacity(nv + 1);
            let mut a = 0u32;
            let pos: Vec<[u32; 2]> = (0..nv)
                .map(|v| {
                    off.push(a);
                    let p = [a, before[v]];
                    a += pc.deg[v];
                    before[v] += pc.deg[v];
                    p
                })
                .collect();
            off.push(a);
            let mut start = Vec::with_capacity(nc + 1);
            let mut f = 0u32;
            for (v, &x) in pc.fc[1..].iter().enumerate() {
                if v & ((1 << low) - 1) == 0 {
                    start.push(f);
                }
                f += x;
            }
            start.push(f);
            jobs.push((pc.range, off, pos, start));
        }
        drop(before);
        let done: Vec<(Vec<u32>, Vec<u32>, Part<W>)> = jobs
            .into_par_iter()
            .map(|(range, off, mut pos, start)| {
                let mut targets = vec![0u32; off[nv] as usize];
                let mut recs = large_zeroed(start[nc] as usize);
                let mut cpos = start[..nc].to_vec();
                let verts = &b.vertices[range.start * (d + 1)..range.end * (d + 1)];
                let first = blk.first + range.start as u32;
                scatter_tops(
                    d,
                    verts,
                    first,
                    &mut pos,
                    &mut targets,
                    &mut recs,
                    &mut cpos,
                    lay,
                );
                (off, targets, Part { recs, start })
            })
            .collect();
        // join the VT rows, in parallel over vertex ranges
        let mut targets: Vec<u32> = large_zeroed(vt_off[nv] as usize);
        let n_ranges = done.len();
        let mut pieces = Vec::with_capacity(n_ranges);
        let mut rest = &mut targets[..];
        let mut at = 0usize;
        for i in 0..n_ranges {
            let (v0, v1) = (i * nv / n_ranges, (i + 1) * nv / n_ranges);
            let (piece, r) = rest.split_at_mut(vt_off[v1] as usize - at);
            at = vt_off[v1] as usize;
            rest = r;
            pieces.push((v0..v1, piece));
        }
        pieces.into_par_iter().for_each(|(vs, piece)| {
            let mut o = 0usize;
            for v in vs {
                for (off, t, _) in &done {
                    let row = &t[off[v] as usize..off[v + 1] as usize];
                    piece[o..o + row.len()].copy_from_slice(row);
                    o += row.len();
                }
            }
        });
        let mut recs: [Vec<Part<W>>; 2] = [Vec::new(), Vec::new()];
        recs[d - 2] = done.into_iter().map(|(_, _, p)| p).collect();
        (targets, recs)
    }

    /// The vertices of a triangle or tetrahedron sorted, with their input positions, by a
    /// branch-free sorting network on (vertex, position) keys.
    #[inline]
    fn sort_top(c: &[u32]) -> ([u32; 4], [u8; 4]) {
        let mut k = [u64::MAX; 4];
        for (j, (x, &v)) in k.iter_mut().zip(c).enumerate() {
            *x = (v as u64) << 2 | j as u64;
        }
        let mut cx = |a: usize, b: usize| {
            let (x, y) = (k[a], k[b]);
            k[a] = x.min(y);
            k[b] = x.max(y);
        };
        // optimal network for 4 keys (an absent fourth key is u64::MAX and stays last)
        cx(0, 1);
        cx(2, 3);
        cx(0, 2);
        cx(1, 3);
        cx(1, 2);
        let mut sv = [0u32; 4];
        let mut pm = [0u8; 4];
        for s in 0..c.len() {
            sv[s] = (k[s] >> 2) as u32;
            pm[s] = (k[s] & 3) as u8;
        }
        (sv, pm)
    }

    /// The `D + 1` facet words of a top, into the coarse buckets of their smallest vertices.
    #[inline]
    fn emit<W: Word, const D: usize>(
        sv: &[u32; 4],
        pm: &[u8; 4],
        vp: &[u32; 4],
        lay: Layout,
        recs: &mut [W],
        cpos: &mut [u32],
    ) {
        let lowmask = mask(lay.low);
        for (jj, &omitted) in pm[..=D].iter().enumerate() {
            // the facet's q-th vertex is sorted vertex o(q)
            let o = |q: usize| q + usize::from(q >= jj);
            let mut key = W::of(sv[o(0)] & lowmask);
            let mut places = W::of(vp[o(0)]);
            for q in 1..D {
                key = (key << lay.vb) | W::of(sv[o(q)]);
                places = (places << lay.pb) | W::of(vp[o(q)]);
            }
            let w = (((key << 2) | W::of(omitted as u32)) << lay.tsh(D)) | places;
            let m = sv[o(0)];
            let slot = &mut cpos[(m >> lay.low) as usize];
            recs[*slot as usize] = w;
            *slot += 1;
        }
    }

    impl<'a> Group<'a> {
        fn new(lay: Layout, ids: DimIds, adj: &'a [AtomicU32]) -> Self {
            Group {
                lay,
                ids,
                adj,
                nm_tops: Vec::new(),
                nm_offsets: vec![0],
                nm_slots: Vec::new(),
            }
        }

        /// Coarse bucket `c` of the facets of the top `d`-simplices: a counting sort by
        /// smallest vertex into `tmp`, then each vertex's facets sorted and grouped.
        #[allow(clippy::too_many_arguments)]
        fn chunk<W: Word>(
            &mut self,
            d: usize,
            parts: &[Part<W>],
            fcnt: &[u32],
            vt: &Vt,
            c: usize,
            tmp: &mut Vec<W>,
            links: &mut Links,
        ) {
            let nv = fcnt.len() - 1;
            let low = self.lay.low;
            let lowmask = mask(low);
            let msh = self.lay.msh(d);
            let (v0, v1) = (c << low, ((c + 1) << low).min(nv));
            let (s, e) = (fcnt[v0] as usize, fcnt[v1] as usize);
            if e - s < 2 {
                return;
            }
            let srcs = parts
                .iter()
                .map(|p| &p.recs[p.start[c] as usize..p.start[c + 1] as usize]);
            // grown, never cleared: every place below `e - s` is written before it is read
            if tmp.len() < e - s {
                tmp.resize(e - s, W::default());
            }
            let tmp = &mut tmp[..e - s];
            if low == 0 {
                // one vertex per bucket (and `msh` may be the word's full width)
                let mut o = 0;
                for src in srcs {
                    tmp[o..o + src.len()].copy_from_slice(src);
                    o += src.len();
                }
            } else {
                let mut fpos: Vec<u32> = fcnt[v0..v1].iter().map(|&x| x - s as u32).collect();
                for &r in srcs.flatten() {
                    let m = ((r >> msh).low32() & lowmask) as usize;
                    tmp[fpos[m] as usize] = r;
                    fpos[m] += 1;
                }
            }
            for v in v0..v1 {
                let (a, b) = (fcnt[v] as usize - s, fcnt[v + 1] as usize - s);
                if b - a >= 2 {
                    if d == 2 {
                        self.bucket::<W, 2>(v as u32, &mut tmp[a..b], vt, links);
                    } else {
                        self.bucket::<W, 3>(v as u32, &mut tmp[a..b], vt, links);
                    }
                }
            }
        }

        /// The facets whose smallest vertex is `m`.
        fn bucket<W: Word, const D: usize>(
            &mut self,
            m: u32,
            bucket: &mut [W],
            vt: &Vt,
            links: &mut Links,
        ) {
            let lay = self.lay;
            let (tsh, ksh) = (lay.tsh(D), lay.ksh(D));
            let n = D + 1;
            let (vmask, pmask) = (mask(lay.vb), mask(lay.pb));
            let place = |x: W, q: usize| (x >> ((D - 1 - q) as u32 * lay.pb)).low32() & pmask;
            // a facet's top: its id (its place in the VT row of m) and the input position of
            // the vertex the facet omits
            let row = &vt.targets[vt.off[m as usize] as usize..];
            let top = |x: W| (row[place(x, 0) as usize], ((x >> tsh).low32() & 3) as usize);
            if bucket.len() == 2 {
                // the common case: skip the sort
                if bucket[1] < bucket[0] {
                    bucket.swap(0, 1);
                }
            } else if std::mem::size_of::<W>() > 8 && lay.msh(D) - tsh <= 64 {
                // the smallest vertex is shared and the facet's other vertices fit in 64
                // bits: sort by them (the order inside a group does not change the result)
                bucket.sort_unstable_by_key(|&w| (w >> tsh).low64());
            } else {
                bucket.sort_unstable();
            }
            let mut i = 0;
            while i < bucket.len() {
                let rest = bucket[i] >> ksh;
                let mut j = i + 1;
                while j < bucket.len() && bucket[j] >> ksh == rest {
                    j += 1;
                }
                if j - i >= 2 {
                    // the facet's vertices
                    let mut f = [0u32; D];
                    f[0] = m;
                    let mut r = rest;
                    for x in f[1..].iter_mut().rev() {
                        *x = r.low32() & vmask;
                        r = r >> lay.vb;
                    }
                    let g = &bucket[i..j];
                    if g.len() == 2 {
                        let ((ca, ja), (cb, jb)) = (top(g[0]), top(g[1]));
                        self.adj[self.ids.local(ca) * n + ja].store(!cb, Relaxed);
                        self.adj[self.ids.local(cb) * n + jb].store(!ca, Relaxed);
                        for (q, &w) in f.iter().enumerate() {
                            let (x, y) = (place(g[0], q), place(g[1], q));
                            links.push(vt.off, lay.low, w, x, y, false);
                        }
                    } else {
                        let fid = (self.nm_offsets.len() - 1) as u32;
                        let s0 = self.nm_tops.len();
                        for &r in g {
                            let (c, jr) = top(r);
                            self.nm_tops.push(c);
                            self.nm_slots.push((self.ids.local(c) * n + jr, fid));
                        }
                        self.nm_tops[s0..].sort_unstable();
                        self.nm_offsets.push(self.nm_tops.len() as u32);
                        for p in g.windows(2) {
                            for (q, &w) in f.iter().enumerate() {
                                let (x, y) = (place(p[0], q), place(p[1], q));
                                links.push(vt.off, lay.low, w, x, y, true);
                            }
                        }
                    }
                }
                i = j;
            }
        }
    }
}

/// Groups the facets of the top d-simplices and fills their adjacency slots; returns the
/// non-manifold face lists.
fn build_adjacency(blocks: &mut [Block], d: usize, nv: usize) -> Csr {
    let n = d + 1;
    // sorted copy of every top's vertices, the input position of each sorted entry, and
    // where each top lives (block, local), in dimension order
    let nt: usize = blocks
        .iter()
        .filter(|b| b.dim == d)
        .map(|b| b.len as usize)
        .sum();
    let mut sorted: Vec<u32> = Vec::with_capacity(nt * n);
    let mut perm: Vec<u8> = Vec::with_capacity(nt * n);
    let mut where_: Vec<(u32, u32)> = Vec::new(); // (first dim-local index, block index)
    let mut pairs: Vec<(u32, u8)> = Vec::with_capacity(n);
    for (bi, b) in blocks.iter().enumerate().filter(|(_, b)| b.dim == d) {
        where_.push(((sorted.len() / n) as u32, bi as u32));
        let st = b.stride();
        for rec in b.data.chunks_exact(st) {
            pairs.clear();
            for (j, &v) in rec[..n].iter().enumerate() {
                pairs.push((v, j as u8));
            }
            // insertion sort: n is small
            for i in 1..pairs.len() {
                let mut j = i;
                while j > 0 && pairs[j - 1].0 > pairs[j].0 {
                    pairs.swap(j - 1, j);
                    j -= 1;
                }
            }
            for p in &pairs {
                sorted.push(p.0);
                perm.push(p.1);
            }
        }
    }
    // bucket the slots (li, jj) by the facet's smallest vertex; for d ≤ 3 the rest of the
    // facet packs into a u64 key, computed in one sequential pass
    let min_of = |slot: usize| -> u32 {
        let (li, jj) = (slot / n, slot % n);
        sorted[li * n + usize::from(jj == 0)]
    };
    let mut counts = vec![0u32; nv + 1];
    for slot in 0..nt * n {
        counts[min_of(slot) as usize + 1] += 1;
    }
    for i in 0..nv {
        counts[i + 1] += counts[i];
    }
    let mut pos = counts.clone();
    let packed = d <= 3;
    let mut order = vec![0u32; if packed { 0 } else { nt * n }];
    let mut recs: Vec<(u64, u32)> = vec![(0, 0); if packed { nt * n } else { 0 }];
    for li in 0..nt {
        let t = &sorted[li * n..(li + 1) * n];
        for jj in 0..n {
            let slot = li * n + jj;
            let m = t[usize::from(jj == 0)] as usize;
            if packed {
                let key = if d == 2 {
                    t[if jj == 2 { 1 } else { 2 }] as u64
                } else {
                    // facet = t without jj; drop its first (min) entry
                    let (a, b) = match jj {
                        0 => (t[2], t[3]),
                        1 => (t[2], t[3]),
                        2 => (t[1], t[3]),
                        _ => (t[1], t[2]),
                    };
                    ((a as u64) << 32) | b as u64
                };
                recs[pos[m] as usize] = (key, slot as u32);
            } else {
                order[pos[m] as usize] = slot as u32;
            }
            pos[m] += 1;
        }
    }
    drop(pos);
    // the facet without its smallest vertex
    let facet = |slot: u32, out: &mut [u32]| {
        let (li, jj) = (slot as usize / n, slot as usize % n);
        let t = &sorted[li * n..(li + 1) * n];
        let mut w = 0;
        for (i, &x) in t.iter().enumerate() {
            if i != jj {
                out[w] = x;
                w += 1;
            }
        }
    };
    let single = where_.len() == 1;
    let locate = |li: usize| -> (usize, usize) {
        if single {
            return (where_[0].1 as usize, li);
        }
        let k = where_.partition_point(|w| w.0 as usize <= li) - 1;
        (where_[k].1 as usize, li - where_[k].0 as usize)
    };
    let ids: Vec<u32> = (0..nt)
        .map(|li| {
            let (bi, local) = locate(li);
            blocks[bi].first + local as u32
        })
        .collect();
    let set_slot = |blocks: &mut [Block], slot: u32, val: u32| {
        let li = slot as usize / n;
        let j = perm[slot as usize] as usize;
        let (bi, local) = locate(li);
        blocks[bi].data[local * 2 * n + n + j] = val;
    };
    let mut nm_tops: Vec<u32> = Vec::new();
    let mut nm_offsets: Vec<u32> = vec![0];
    let mut ka = vec![0u32; n];
    let mut kb = vec![0u32; n];
    let mut group = |blocks: &mut [Block], g: &[u32]| match g.len() {
        1 => {}
        2 => {
            let (c1, c2) = (ids[g[0] as usize / n], ids[g[1] as usize / n]);
            set_slot(blocks, g[0], c2);
            set_slot(blocks, g[1], c1);
        }
        _ => {
            let f = (nm_offsets.len() - 1) as u32;
            let start = nm_tops.len();
            for &s in g {
                nm_tops.push(ids[s as usize / n]);
                set_slot(blocks, s, NM_BIT | f);
            }
            nm_tops[start..].sort_unstable();
            nm_offsets.push(nm_tops.len() as u32);
        }
    };
    let mut gbuf: Vec<u32> = Vec::new();
    for v in 0..nv {
        if counts[v + 1] - counts[v] < 2 {
            continue;
        }
        if packed {
            let keyed = &mut recs[counts[v] as usize..counts[v + 1] as usize];
            keyed.sort_unstable();
            let mut i = 0;
            while i < keyed.len() {
                let mut j = i + 1;
                while j < keyed.len() && keyed[j].0 == keyed[i].0 {
                    j += 1;
                }
                if j - i >= 2 {
                    gbuf.clear();
                    gbuf.extend(keyed[i..j].iter().map(|x| x.1));
                    group(blocks, &gbuf);
                }
                i = j;
            }
        } else {
            let bucket = &mut order[counts[v] as usize..counts[v + 1] as usize];
            bucket.sort_unstable_by(|&a, &b| {
                facet(a, &mut ka[..d]);
                facet(b, &mut kb[..d]);
                ka[..d].cmp(&kb[..d])
            });
            let mut i = 0;
            while i < bucket.len() {
                facet(bucket[i], &mut ka[..d]);
                let mut j = i + 1;
                while j < bucket.len() {
                    facet(bucket[j], &mut kb[..d]);
                    if ka[..d] != kb[..d] {
                        break;
                    }
                    j += 1;
                }
                if j - i >= 2 {
                    gbuf.clear();
                    gbuf.extend_from_slice(&bucket[i..j]);
                    group(blocks, &gbuf);
                }
                i = j;
            }
        }
    }
    Csr {
        offsets: nm_offsets,
        targets: nm_tops,
    }
}

impl TopCells for IaStar {
    fn n_vertices(&self) -> usize {
        self.n_vertices as usize
    }
    fn n_top_cells(&self) -> usize {
        self.n_cells as usize
    }
    fn top_cell_kind(&self, c: CellId) -> CellKind {
        self.block_of(c.0).kind
    }
    fn top_cell_vertices(&self, c: CellId, out: &mut Vec<VertexId>) {
        out.extend(self.top(c.0).1.iter().map(|&v| VertexId(v)));
    }
}

impl VertexStar for IaStar {
    fn vertex_top_cells(&self, v: VertexId, out: &mut Vec<CellId>) {
        self.vt_into(v.0, out);
    }

    /// Walks the clusters of `s[0]` and stops at the first top containing `s` (simplicial
    /// complexes; with CP cells, where a vertex subset of a top need not be a face, `None`).
    fn star_has_top_containing(&self, s: &[VertexId]) -> Option<bool> {
        if !self.simplicial {
            return None;
        }
        Some(self.has_top_containing(s))
    }
}

impl IaStar {
    fn has_top_containing(&self, s: &[VertexId]) -> bool {
        let v = s[0].0;
        let has = |c: u32| {
            let verts = self.top(c).1;
            s.iter().all(|x| verts.contains(&x.0))
        };
        let mut cells: Vec<u32> = Vec::new();
        for &r in self.vrefs.row(v as usize) {
            if has(r) {
                return true;
            }
            if self.top(r).0 <= 1 {
                continue;
            }
            cells.clear();
            cells.push(r);
            let mut head = 0;
            let mut found = false;
            while head < cells.len() && !found {
                let x = cells[head];
                head += 1;
                self.for_each_neighbour_at(x, v, |u| {
                    if !found && !cells.contains(&u) {
                        found = has(u);
                        cells.push(u);
                    }
                });
            }
            if found {
                return true;
            }
        }
        false
    }
}

impl VertexAdjacency for IaStar {
    fn vertex_neighbours(&self, v: VertexId, out: &mut Vec<VertexId>) {
        let mut cells = Vec::new();
        self.vt_into(v.0, &mut cells);
        out.clear();
        if !self.simplicial {
            // the edges of the face tables (a quad's diagonal is not an edge)
            for c in cells {
                let b = self.block_of(c.0);
                let verts = Self::record(b, c.0).1;
                crate::topo::naive::edge_neighbours(b.kind, verts, v.0, |w| out.push(VertexId(w)));
            }
            out.sort_unstable();
            out.dedup();
            return;
        }
        for c in cells {
            out.extend(
                self.top(c.0)
                    .1
                    .iter()
                    .filter(|&&w| w != v.0)
                    .map(|&w| VertexId(w)),
            );
        }
        out.sort_unstable();
        out.dedup();
    }
}

impl FacetAdjacency for IaStar {
    fn n_facet_slots(&self, c: CellId) -> usize {
        if c.0 >= self.n_cells {
            return 0;
        }
        self.top(c.0).2.len()
    }
    fn facet_adjacent(&self, c: CellId, j: usize) -> Adjacent {
        if c.0 >= self.n_cells {
            return Adjacent::None;
        }
        let (dim, _, adj) = self.top(c.0);
        match adj.get(j).map(|&x| decode(x)) {
            None | Some(Slot::None) => Adjacent::None,
            Some(Slot::Top(u)) => Adjacent::Top(u),
            Some(Slot::NmFace(f)) => Adjacent::NmFace(self.nm_base(dim) + f),
        }
    }
    fn n_nm_faces(&self) -> usize {
        self.nm.iter().map(|c| c.n_rows()).sum()
    }
    fn nm_face_cells(&self, f: u32) -> Vec<CellId> {
        self.nm_local(f).map_or(Vec::new(), |(k, f)| {
            self.nm[k]
                .row(f as usize)
                .iter()
                .map(|&u| CellId(u))
                .collect()
        })
    }
    fn nm_face_vertices(&self, f: u32) -> Vec<VertexId> {
        let Some((k, f)) = self.nm_local(f) else {
            return Vec::new();
        };
        let tops = self.nm[k].row(f as usize);
        let b = self.block_of(tops[0]);
        let (_, verts, adj) = Self::record(b, tops[0]);
        let Some(j) = adj.iter().position(|&x| x == (NM_BIT | f)) else {
            return Vec::new();
        };
        let mut out: Vec<VertexId> = if b.kind.is_simplex() {
            verts
                .iter()
                .enumerate()
                .filter(|&(i, _)| i != j)
                .map(|(_, &v)| VertexId(v))
                .collect()
        } else {
            cp::facet(b.kind, j)
                .iter()
                .map(|&l| VertexId(verts[l as usize]))
                .collect()
        };
        out.sort_unstable();
        out
    }
    fn vertex_references(&self, v: VertexId) -> Vec<CellId> {
        if v.0 >= self.n_vertices {
            return Vec::new();
        }
        self.vrefs
            .row(v.index())
            .iter()
            .map(|&c| CellId(c))
            .collect()
    }
    /// The slots read directly (no per-facet dispatch).
    fn top_adjacent(&self, c: CellId) -> Vec<CellId> {
        if c.0 >= self.n_cells {
            return Vec::new();
        }
        let (dim, _, adj) = self.top(c.0);
        let mut out = Vec::new();
        for &x in adj {
            match decode(x) {
                Slot::None => {}
                Slot::Top(u) => out.push(u),
                Slot::NmFace(f) => out.extend(
                    self.nm[dim]
                        .row(f as usize)
                        .iter()
                        .filter(|&&u| u != c.0)
                        .map(|&u| CellId(u)),
                ),
            }
        }
        out.sort_unstable();
        out.dedup();
        out
    }
}

impl Storage for IaStar {
    /// The spec's formula: Σ_{k≥1}(k+1)t_k + Σ_{k≥2}(k+1)t_k + Σ |NM lists| + 2t_1 + Σ_v Σ_k κ_k(v).
    fn refs(&self) -> u64 {
        let verts: u64 = self.blocks.iter().map(|b| b.n_verts() as u64).sum();
        let adj: u64 = self.blocks.iter().map(|b| b.n_slots() as u64).sum();
        let nm: u64 = self.nm.iter().map(|c| c.n_refs() as u64).sum();
        verts + adj + nm + self.vrefs.n_refs() as u64
    }
    fn bytes(&self) -> u64 {
        let blocks: usize = self
            .blocks
            .iter()
            .map(|b| 4 * b.data.len() + std::mem::size_of::<Block>())
            .sum();
        let nm: usize = self.nm.iter().map(|c| c.bytes()).sum();
        (blocks + nm + self.vrefs.bytes()) as u64
    }
}

crate::impl_relations_from_tops!(IaStar);

// ---------------------------------------------------------------------------------------------
// Ghost simplices

/// A ghost simplex: "the i-th p-face of the k-th top m-simplex" (k counts the top m-simplices in
/// input order; i ranks the face's vertex positions in colex order,
/// rank({s_0<…<s_p}) = Σ_j C(s_j, j+1)). Ghosts returned by [`IaStar`] are canonical: the top
/// is the smallest (m, k) containing the face, so one simplex has one ghost and `==` is
/// simplex equality.
///
/// ```
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// use starplex::ids::{CellId, VertexId};
/// use starplex::tds::iastar::IaStar;
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for _ in 0..4 { b.push_vertex(&[0.0, 0.0]).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// let ia = IaStar::new(&k).unwrap(); // triangles [0, 1, 2] and [1, 3, 2]
/// use starplex::tds::iastar::Ghost;
/// // edge {1,2}: positions {1,2} of top triangle 0, colex rank C(1,1) + C(2,2) = 2
/// let g = ia.ghost(&[VertexId(1), VertexId(2)]).unwrap();
/// assert_eq!(g, Ghost { m: 2, k: 0, p: 1, i: 2 });
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Ghost {
    /// Dimension of the top.
    pub m: u8,
    /// Index of the top among the top m-simplices.
    pub k: u32,
    /// Dimension of the face.
    pub p: u8,
    /// Colex rank of the face's vertex positions in the top.
    pub i: u64,
}

/// Colex rank of sorted positions.
fn colex_rank(pos: &[usize]) -> u64 {
    pos.iter()
        .enumerate()
        .map(|(j, &s)| binomial(s as u64, j as u64 + 1) as u64)
        .sum()
}

/// Positions (sorted) of the colex rank `i` among (p+1)-subsets.
fn colex_unrank(mut i: u64, p: usize) -> Vec<usize> {
    let mut out = vec![0usize; p + 1];
    for j in (0..=p).rev() {
        // largest s with C(s, j+1) <= i
        let mut s = j;
        while binomial(s as u64 + 1, j as u64 + 1) as u64 <= i {
            s += 1;
        }
        out[j] = s;
        i -= binomial(s as u64, j as u64 + 1) as u64;
    }
    out
}

/// Attributes attached to ghost simplices (sparse: a hash map keyed by the canonical ghost).
///
/// ```
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// use starplex::ids::VertexId;
/// use starplex::tds::iastar::{IaStar, GhostAttributes};
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for _ in 0..4 { b.push_vertex(&[0.0, 0.0]).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// let ia = IaStar::new(&k).unwrap();
/// let mut w: GhostAttributes<f64> = GhostAttributes::default();
/// let e = ia.ghost(&[VertexId(2), VertexId(1)]).unwrap();
/// w.insert(e, 0.5);
/// // the same edge named from the other triangle's side is the same canonical ghost
/// let again = ia.ghost(&[VertexId(1), VertexId(2)]).unwrap();
/// assert_eq!(w.get(&again), Some(&0.5));
/// ```
pub type GhostAttributes<T> = FxHashMap<Ghost, T>;

impl IaStar {
    /// The canonical ghost of simplex `s` (vertices in any order).
    ///
    /// # Errors
    /// `s` is not a simplex of the complex.
    ///
    /// ```
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// use starplex::ids::{CellId, VertexId};
    /// use starplex::tds::iastar::IaStar;
    /// # let mut b = ComplexBuilder::new(2).unwrap();
    /// # for _ in 0..4 { b.push_vertex(&[0.0, 0.0]).unwrap(); }
    /// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
    /// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// let ia = IaStar::new(&k).unwrap(); // triangles [0, 1, 2] and [1, 3, 2]
    /// use starplex::tds::iastar::Ghost;
    /// // vertex 3 is position 1 of the second triangle [1, 3, 2]
    /// assert_eq!(ia.ghost(&[VertexId(3)]).unwrap(), Ghost { m: 2, k: 1, p: 0, i: 1 });
    /// // the shared edge has one canonical ghost, from triangle 0
    /// assert_eq!(ia.ghost(&[VertexId(2), VertexId(1)]).unwrap().k, 0);
    /// assert!(ia.ghost(&[VertexId(0), VertexId(3)]).is_err()); // not an edge
    /// ```
    pub fn ghost(&self, s: &[VertexId]) -> Result<Ghost, QueryError> {
        let s = sorted_simplex(s)?;
        let mut cells = Vec::new();
        crate::topo::from_tops::top_star(self, &s, &mut cells)?;
        let best = cells
            .iter()
            .map(|&c| {
                let (m, k) = self.dim_index(c);
                (m, k, c)
            })
            .min()
            .ok_or_else(|| QueryError::NotInComplex(s.iter().map(|v| v.0).collect()))?;
        let (m, k, c) = best;
        let b = self.block_of(c.0);
        let verts = Self::record(b, c.0).1;
        if !b.kind.is_simplex() {
            // a face of a CP top: its index in the kind's face table of its dimension
            let (p, i) = cp::face_index(b.kind, verts, &s)
                .ok_or_else(|| QueryError::NotInComplex(s.iter().map(|v| v.0).collect()))?;
            return Ok(Ghost {
                m: m as u8,
                k,
                p: p as u8,
                i: i as u64,
            });
        }
        let mut pos: Vec<usize> = s
            .iter()
            .map(|v| {
                verts
                    .iter()
                    .position(|&w| w == v.0)
                    .expect("a top of the star contains the simplex")
            })
            .collect();
        pos.sort_unstable();
        Ok(Ghost {
            m: m as u8,
            k,
            p: (s.len() - 1) as u8,
            i: colex_rank(&pos),
        })
    }

    /// The sorted vertices of a ghost.
    ///
    /// # Errors
    /// A ghost that names no face of a top.
    ///
    /// ```
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// use starplex::ids::{CellId, VertexId};
    /// use starplex::tds::iastar::IaStar;
    /// # let mut b = ComplexBuilder::new(2).unwrap();
    /// # for _ in 0..4 { b.push_vertex(&[0.0, 0.0]).unwrap(); }
    /// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
    /// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// let ia = IaStar::new(&k).unwrap(); // triangles [0, 1, 2] and [1, 3, 2]
    /// let g = ia.ghost(&[VertexId(3), VertexId(2)]).unwrap();
    /// assert_eq!(ia.ghost_vertices(g).unwrap(), vec![VertexId(2), VertexId(3)]);
    /// ```
    pub fn ghost_vertices(&self, g: Ghost) -> Result<Vec<VertexId>, QueryError> {
        let bad = || QueryError::NotInComplex(vec![]);
        let c = self.cell_of(g.m as usize, g.k).ok_or_else(bad)?;
        let b = self.block_of(c.0);
        let verts = Self::record(b, c.0).1;
        if !b.kind.is_simplex() {
            let face = b
                .kind
                .cp_faces(g.p as usize)
                .and_then(|t| t.get(usize::try_from(g.i).ok()?))
                .ok_or_else(bad)?;
            let mut out: Vec<VertexId> =
                face.iter().map(|&l| VertexId(verts[l as usize])).collect();
            out.sort_unstable();
            return Ok(out);
        }
        if g.p > g.m || g.i as u128 >= binomial(g.m as u64 + 1, g.p as u64 + 1) {
            return Err(bad());
        }
        let mut out: Vec<VertexId> = colex_unrank(g.i, g.p as usize)
            .into_iter()
            .map(|j| VertexId(verts[j]))
            .collect();
        out.sort_unstable();
        Ok(out)
    }

    /// R_{p,q} on a ghost, q < p: its q-faces as canonical ghosts, sorted.
    ///
    /// # Errors
    /// A bad ghost; too many faces.
    ///
    /// ```
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// use starplex::ids::{CellId, VertexId};
    /// use starplex::tds::iastar::IaStar;
    /// # let mut b = ComplexBuilder::new(2).unwrap();
    /// # for _ in 0..4 { b.push_vertex(&[0.0, 0.0]).unwrap(); }
    /// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
    /// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// let ia = IaStar::new(&k).unwrap(); // triangles [0, 1, 2] and [1, 3, 2]
    /// let e = ia.ghost(&[VertexId(1), VertexId(2)]).unwrap();
    /// let vs: Vec<_> = ia.ghost_boundary(e, 0).unwrap().into_iter()
    ///     .map(|g| ia.ghost_vertices(g).unwrap()).collect();
    /// assert_eq!(vs, vec![vec![VertexId(1)], vec![VertexId(2)]]);
    /// ```
    pub fn ghost_boundary(&self, g: Ghost, q: usize) -> Result<Vec<Ghost>, QueryError> {
        let s = self.ghost_vertices(g)?;
        if s.len() != g.p as usize + 1 {
            // a CP cell (quad, pyramid, prism, hexahedron): the faces in its top's tables
            return cp::ghost_boundary(self, g, &s, q);
        }
        let mut flat = Vec::new();
        crate::topo::from_tops::boundary_of_sorted(&s, q, crate::topo::DEFAULT_BUDGET, &mut flat)?;
        self.ghosts_of_flat(&flat, q)
    }

    /// R_{p,q} on a ghost, q > p: its q-cofaces as canonical ghosts, sorted.
    ///
    /// # Errors
    /// A bad ghost; too many cofaces.
    ///
    /// ```
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// use starplex::ids::{CellId, VertexId};
    /// use starplex::tds::iastar::IaStar;
    /// # let mut b = ComplexBuilder::new(2).unwrap();
    /// # for _ in 0..4 { b.push_vertex(&[0.0, 0.0]).unwrap(); }
    /// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
    /// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// let ia = IaStar::new(&k).unwrap(); // triangles [0, 1, 2] and [1, 3, 2]
    /// let e = ia.ghost(&[VertexId(1), VertexId(2)]).unwrap();
    /// let ts: Vec<_> = ia.ghost_coboundary(e, 2).unwrap().into_iter()
    ///     .map(|g| ia.ghost_vertices(g).unwrap()).collect();
    /// assert_eq!(ts, vec![
    ///     vec![VertexId(0), VertexId(1), VertexId(2)],
    ///     vec![VertexId(1), VertexId(2), VertexId(3)],
    /// ]);
    /// ```
    pub fn ghost_coboundary(&self, g: Ghost, q: usize) -> Result<Vec<Ghost>, QueryError> {
        if !self.simplicial {
            return cp::ghost_coboundary(self, g, q);
        }
        let s = self.ghost_vertices(g)?;
        let mut flat = Vec::new();
        crate::topo::from_tops::coboundary(self, &s, q, crate::topo::DEFAULT_BUDGET, &mut flat)?;
        self.ghosts_of_flat(&flat, q)
    }

    /// R_{p,p} on a ghost: adjacent simplices as canonical ghosts, sorted (p ≥ 1).
    ///
    /// # Errors
    /// A bad ghost; too many simplices.
    ///
    /// ```
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// use starplex::ids::{CellId, VertexId};
    /// use starplex::tds::iastar::IaStar;
    /// # let mut b = ComplexBuilder::new(2).unwrap();
    /// # for _ in 0..4 { b.push_vertex(&[0.0, 0.0]).unwrap(); }
    /// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
    /// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// let ia = IaStar::new(&k).unwrap(); // triangles [0, 1, 2] and [1, 3, 2]
    /// let t0 = ia.ghost(&[VertexId(0), VertexId(1), VertexId(2)]).unwrap();
    /// let adj = ia.ghost_adjacent(t0).unwrap();
    /// assert_eq!(adj.len(), 1);
    /// assert_eq!(ia.ghost_vertices(adj[0]).unwrap(), vec![VertexId(1), VertexId(2), VertexId(3)]);
    /// ```
    pub fn ghost_adjacent(&self, g: Ghost) -> Result<Vec<Ghost>, QueryError> {
        if !self.simplicial {
            return cp::ghost_adjacent(self, g);
        }
        let s = self.ghost_vertices(g)?;
        let mut flat = Vec::new();
        crate::topo::from_tops::adjacent(self, &s, crate::topo::DEFAULT_BUDGET, &mut flat)?;
        if s.len() == 1 {
            return Ok(Vec::new());
        }
        self.ghosts_of_flat(&flat, s.len() - 1)
    }

    fn ghosts_of_flat(&self, flat: &[VertexId], q: usize) -> Result<Vec<Ghost>, QueryError> {
        let mut out = flat
            .chunks_exact(q + 1)
            .map(|f| self.ghost(f))
            .collect::<Result<Vec<_>, _>>()?;
        out.sort_unstable();
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::complex::{BuildOptions, ComplexBuilder};

    /// A seeded xorshift generator: `next(m)` is in `0..m`.
    fn xorshift(mut x: u64) -> impl FnMut(u64) -> u64 {
        move |m| {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x % m
        }
    }

    /// The two builds hold the same structure: references, per-vertex references,
    /// non-manifold facets and every top record.
    fn assert_same(fast: &IaStar, general: &IaStar, at: &str) {
        assert_eq!(fast.refs(), general.refs(), "{at}");
        assert_eq!(fast.bytes(), general.bytes(), "{at}");
        assert_eq!(fast.vrefs, general.vrefs, "{at}");
        assert_eq!(fast.nm, general.nm, "{at}");
        for (a, b) in fast.blocks.iter().zip(&general.blocks) {
            assert!(a.data == b.data, "{at}");
        }
    }

    /// The construction for dimension ≤ 3 and the general one give the same structure, on
    /// random mixed complexes with non-manifold faces, several blocks per dimension and
    /// input orders that are not sorted.
    #[test]
    fn low_dim_build_equals_general_build() {
        let mut next = xorshift(0x2545_f491_4f6c_dd1d);
        for case in 0..300 {
            let nv = 3 + next(if case < 200 { 8 } else { 40 }) as usize;
            let mut b = ComplexBuilder::new(1).unwrap();
            for _ in 0..nv {
                b.push_vertex(&[0.0]).unwrap();
            }
            let nc = 1 + next(if case < 200 { 12 } else { 120 });
            for _ in 0..nc {
                let len = (1 + next(4) as usize).min(nv);
                let mut c: Vec<u32> = Vec::new();
                while c.len() < len {
                    let v = next(nv as u64) as u32;
                    if !c.contains(&v) {
                        c.push(v);
                    }
                }
                b.push_cell(CellKind::Simplex(len as u8 - 1), &c).unwrap();
            }
            let opts = BuildOptions {
                drop_face_cells: true,
                drop_duplicates: true,
                ..Default::default()
            };
            let k = b.build(&opts).unwrap().0;
            let general = IaStar::build(&k, None).unwrap();
            // the default settings, several vertices per coarse bucket, 128-bit words, and
            // links of two words
            // (passes 1 and 2 run in parts only on one-block complexes; passes 3 and 4 run in
            // ranges of buckets on any)
            for (coarse_bits, wide, pack_links, parts) in [
                (10, false, true, 1),
                (2, false, true, 1),
                (1, true, true, 1),
                (10, true, false, 1),
                (2, false, false, 1),
                (10, false, true, 2),
                (1, false, false, 3),
                (2, true, true, 5),
            ] {
                let tu = low_dim::Tuning {
                    coarse_bits,
                    wide,
                    pack_links,
                    parts,
                };
                let fast = IaStar::build(&k, Some(tu)).unwrap();
                assert_same(&fast, &general, &format!("case {case}, {tu:?}"));
            }
        }
    }

    /// Passes 1 and 2 split into parts (run in parallel) give the general path's IA* on random
    /// pure triangle and tetrahedral complexes (one block each), whatever the number of parts.
    #[test]
    fn low_dim_build_in_parts_equals_general_build() {
        let mut next = xorshift(0x1234_5678_9abc_def1);
        for case in 0..120 {
            let d = 2 + next(2) as usize;
            let nv = d + 1 + next(30) as usize;
            let mut b = ComplexBuilder::new(1).unwrap();
            for _ in 0..nv {
                b.push_vertex(&[0.0]).unwrap();
            }
            for _ in 0..1 + next(80) {
                let mut c: Vec<u32> = Vec::new();
                while c.len() < d + 1 {
                    let v = next(nv as u64) as u32;
                    if !c.contains(&v) {
                        c.push(v);
                    }
                }
                b.push_cell(CellKind::Simplex(d as u8), &c).unwrap();
            }
            let opts = BuildOptions {
                drop_duplicates: true,
                ..Default::default()
            };
            let k = b.build(&opts).unwrap().0;
            assert_eq!(k.blocks().len(), 1);
            let general = IaStar::build(&k, None).unwrap();
            for (parts, coarse_bits, wide) in [(2, 10, false), (3, 2, false), (7, 1, true)] {
                let tu = low_dim::Tuning {
                    coarse_bits,
                    wide,
                    parts,
                    ..low_dim::Tuning::DEFAULT
                };
                let fast = IaStar::build(&k, Some(tu)).unwrap();
                assert_same(&fast, &general, &format!("case {case}, {tu:?}"));
            }
        }
    }

    /// A facet word of exactly 64 bits with one vertex per coarse bucket (the shift to the
    /// smallest vertex's low bits is then the full word width): a cone over every triangle of
    /// 60 vertices (34,220 tetrahedra at the apex, 16-bit places) and 9 isolated vertices
    /// (7-bit vertex ids).
    #[test]
    fn low_dim_build_with_a_full_64_bit_word() {
        let mut b = ComplexBuilder::new(1).unwrap();
        for _ in 0..70 {
            b.push_vertex(&[0.0]).unwrap();
        }
        for x in 1..=60u32 {
            for y in x + 1..=60 {
                for z in y + 1..=60 {
                    b.push_cell(CellKind::Simplex(3), &[0, x, y, z]).unwrap();
                }
            }
        }
        let k = b.build(&BuildOptions::default()).unwrap().0;
        let general = IaStar::build(&k, None).unwrap();
        let fast = IaStar::build(&k, Some(low_dim::Tuning::DEFAULT)).unwrap();
        assert_same(&fast, &general, "cone");
        assert!(!fast.nm_faces_of_dim(3).is_empty());
    }

    /// The same on the medium meshes of `$STARPLEX_DATA` (slow in a debug build:
    /// `cargo test --release -- --ignored`).
    #[test]
    #[ignore]
    fn low_dim_build_equals_general_build_on_medium_meshes() {
        let Ok(dir) = std::env::var("STARPLEX_DATA") else {
            return;
        };
        for name in ["tri_armadillo_x16", "tet_armadillo_m"] {
            let p = std::path::Path::new(&dir).join(format!("medium/{name}/{name}.spx"));
            if !p.exists() {
                continue;
            }
            let k = crate::io::read(&p, &Default::default()).unwrap().complex;
            assert!(k.n_cells() > 500_000, "{name}");
            let general = IaStar::build(&k, None).unwrap();
            for (wide, pack_links, parts) in [(false, true, 1), (false, true, 2), (true, false, 3)]
            {
                let tu = low_dim::Tuning {
                    wide,
                    pack_links,
                    parts,
                    ..low_dim::Tuning::DEFAULT
                };
                let fast = IaStar::build(&k, Some(tu)).unwrap();
                assert_same(&fast, &general, name);
            }
        }
    }
}
