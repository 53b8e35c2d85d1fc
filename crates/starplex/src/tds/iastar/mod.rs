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
//! cells and refuse face enumerations with [`QueryError::NotSimplicial`](crate::topo::QueryError::NotSimplicial); the ghost relations
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
use rustc_hash::FxHashSet;

use crate::cell::CellKind;
use crate::complex::IndexedComplex;
use crate::csr::Csr;
use crate::ids::{CellId, VertexId};
use crate::topo::{Adjacent, FacetAdjacency, Storage, TopCells, VertexAdjacency, VertexStar};

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

mod low_dim;

/// Groups the facets of the top d-simplices and fills their adjacency slots; returns the
/// non-manifold face lists.
fn build_adjacency(blocks: &mut [Block], d: usize, nv: usize) -> Csr {
    let n = d + 1;
    let tops = SortedTops::new(blocks, d);
    let packed = d <= 3;
    let (counts, mut order, mut recs) = bucket_slots(&tops, d, nv, packed);
    let mut g = Grouper::new(blocks, &tops);
    let mut gbuf: Vec<u32> = Vec::new();
    let mut ka = vec![0u32; n];
    let mut kb = vec![0u32; n];
    for v in 0..nv {
        if counts[v + 1] - counts[v] < 2 {
            continue;
        }
        let r = counts[v] as usize..counts[v + 1] as usize;
        if packed {
            let keyed = &mut recs[r];
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
                    g.group(blocks, &gbuf);
                }
                i = j;
            }
        } else {
            let bucket = &mut order[r];
            bucket.sort_unstable_by(|&a, &b| {
                tops.facet(a, &mut ka[..d]);
                tops.facet(b, &mut kb[..d]);
                ka[..d].cmp(&kb[..d])
            });
            let mut i = 0;
            while i < bucket.len() {
                tops.facet(bucket[i], &mut ka[..d]);
                let mut j = i + 1;
                while j < bucket.len() {
                    tops.facet(bucket[j], &mut kb[..d]);
                    if ka[..d] != kb[..d] {
                        break;
                    }
                    j += 1;
                }
                if j - i >= 2 {
                    gbuf.clear();
                    gbuf.extend_from_slice(&bucket[i..j]);
                    g.group(blocks, &gbuf);
                }
                i = j;
            }
        }
    }
    Csr {
        offsets: g.nm_offsets,
        targets: g.nm_tops,
    }
}

/// The top d-simplices with sorted vertices, in dimension order: slot `li * n + j` is the facet
/// of top `li` without its `j`-th smallest vertex.
struct SortedTops {
    /// Vertices per top (d + 1).
    n: usize,
    /// Number of tops.
    nt: usize,
    /// Every top's vertices, sorted.
    sorted: Vec<u32>,
    /// The input position of each sorted entry.
    perm: Vec<u8>,
    /// Where each block's tops start: (first dimension-local index, block index).
    where_: Vec<(u32, u32)>,
}

impl SortedTops {
    /// Sorted copies of the tops of dimension `d` of `blocks`.
    fn new(blocks: &[Block], d: usize) -> SortedTops {
        let n = d + 1;
        let nt: usize = blocks
            .iter()
            .filter(|b| b.dim == d)
            .map(|b| b.len as usize)
            .sum();
        let mut sorted: Vec<u32> = Vec::with_capacity(nt * n);
        let mut perm: Vec<u8> = Vec::with_capacity(nt * n);
        let mut where_: Vec<(u32, u32)> = Vec::new();
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
        SortedTops {
            n,
            nt,
            sorted,
            perm,
            where_,
        }
    }

    /// The facet of `slot` without its smallest vertex, into `out` (`n - 1` entries).
    #[inline]
    fn facet(&self, slot: u32, out: &mut [u32]) {
        let n = self.n;
        let (li, jj) = (slot as usize / n, slot as usize % n);
        let t = &self.sorted[li * n..(li + 1) * n];
        let mut w = 0;
        for (i, &x) in t.iter().enumerate() {
            if i != jj {
                out[w] = x;
                w += 1;
            }
        }
    }
}

/// Buckets the slots of `tops` by the facet's smallest vertex: returns the bucket offsets per
/// vertex and, when `packed` (d ≤ 3: the rest of the facet packs into a u64 key, computed in
/// one sequential pass), (key, slot) records, else the slots.
#[allow(clippy::type_complexity)]
fn bucket_slots(
    tops: &SortedTops,
    d: usize,
    nv: usize,
    packed: bool,
) -> (Vec<u32>, Vec<u32>, Vec<(u64, u32)>) {
    let (n, nt, sorted) = (tops.n, tops.nt, &tops.sorted);
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
    (counts, order, recs)
}

/// Fills the adjacency slots of one group of slots sharing a facet: two tops see each other;
/// three or more make a non-manifold face (its tops listed, the slots pointing to it).
struct Grouper<'a> {
    tops: &'a SortedTops,
    /// The cell id of every top (dimension-local index).
    ids: Vec<u32>,
    nm_tops: Vec<u32>,
    nm_offsets: Vec<u32>,
}

impl<'a> Grouper<'a> {
    fn new(blocks: &[Block], tops: &'a SortedTops) -> Grouper<'a> {
        let mut g = Grouper {
            tops,
            ids: Vec::new(),
            nm_tops: Vec::new(),
            nm_offsets: vec![0],
        };
        g.ids = (0..tops.nt)
            .map(|li| {
                let (bi, local) = g.locate(li);
                blocks[bi].first + local as u32
            })
            .collect();
        g
    }

    /// (block index, index in the block) of dimension-local top `li`.
    #[inline]
    fn locate(&self, li: usize) -> (usize, usize) {
        let w = &self.tops.where_;
        if w.len() == 1 {
            return (w[0].1 as usize, li);
        }
        let k = w.partition_point(|w| w.0 as usize <= li) - 1;
        (w[k].1 as usize, li - w[k].0 as usize)
    }

    #[inline]
    fn set_slot(&self, blocks: &mut [Block], slot: u32, val: u32) {
        let n = self.tops.n;
        let li = slot as usize / n;
        let j = self.tops.perm[slot as usize] as usize;
        let (bi, local) = self.locate(li);
        blocks[bi].data[local * 2 * n + n + j] = val;
    }

    #[inline]
    fn group(&mut self, blocks: &mut [Block], g: &[u32]) {
        let n = self.tops.n;
        match g.len() {
            1 => {}
            2 => {
                let (c1, c2) = (self.ids[g[0] as usize / n], self.ids[g[1] as usize / n]);
                self.set_slot(blocks, g[0], c2);
                self.set_slot(blocks, g[1], c1);
            }
            _ => {
                let f = (self.nm_offsets.len() - 1) as u32;
                let start = self.nm_tops.len();
                for &s in g {
                    self.nm_tops.push(self.ids[s as usize / n]);
                    self.set_slot(blocks, s, NM_BIT | f);
                }
                self.nm_tops[start..].sort_unstable();
                self.nm_offsets.push(self.nm_tops.len() as u32);
            }
        }
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

mod ghosts;
pub use ghosts::{Ghost, GhostAttributes};

#[cfg(test)]
mod tests;
