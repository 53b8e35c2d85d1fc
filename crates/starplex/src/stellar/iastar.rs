//! IA* generated from a Stellar tree, globally ([`StellarTree::iastar`]) or for one leaf
//! ([`StellarTree::local_iastar`]), following the spec (`ia-star-is-ghosts.md` §2):
//!
//! * R_{k,0} of every top cell (its vertices);
//! * R_{k,k} for every top k-cell with k >= 2: one slot per facet (facet j of a simplex omits its
//!   j-th vertex; CP cells follow their facet tables): no neighbour, the other top k-cell, or a
//!   non-manifold facet (three or more top k-cells) whose full list is stored;
//! * R_{0,1} of every vertex (all its top edges) and R*_{0,k} for k >= 2: one top k-cell per
//!   k-cluster (top k-cells around the vertex connected through facets containing it), the
//!   representative being the cluster's smallest input id.
//!
//! It answers through the one IA* vocabulary, [`FacetAdjacency`] (and [`Storage`]), like the
//! standalone IA* ([`crate::tds::iastar`]); the layout differs but the content is the same: the same slot per facet, the same non-manifold facets, the same representatives and
//! the same reference count (checked by `tests/suite/stellar_iastar.rs` on random complexes and the
//! datasets).
//!
//! ```
//! # use starplex::complex::{ComplexBuilder, BuildOptions};
//! # use starplex::cell::CellKind;
//! use starplex::stellar::{StellarTree, StellarOptions};
//! use starplex::topo::{Adjacent, FacetAdjacency, Storage};
//! use starplex::ids::{CellId, VertexId};
//! // the "book": three triangles on edge 01
//! let mut b = ComplexBuilder::new(3).unwrap();
//! for p in [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [0.0, -1.0, 0.0]] {
//!     b.push_vertex(&p).unwrap();
//! }
//! for c in [[0, 1, 2], [0, 1, 3], [0, 1, 4]] { b.push_cell(CellKind::Simplex(2), &c).unwrap(); }
//! let k = b.build(&BuildOptions::default()).unwrap().0;
//! let t = StellarTree::build(&k, &StellarOptions::default()).unwrap();
//! let ia = t.iastar();
//! assert_eq!(ia.facet_adjacent(CellId(0), 2), Adjacent::NmFace(0)); // facet 2 = edge 01
//! assert_eq!(ia.nm_face_cells(0), vec![CellId(0), CellId(1), CellId(2)]);
//! assert_eq!(ia.vertex_references(VertexId(0)), vec![CellId(0)]);
//! assert_eq!(ia.refs(), 26); // the spec's anchor for the book
//! ```
use rayon::prelude::*;
use rustc_hash::FxHashSet;
use std::sync::atomic::{AtomicU32, Ordering::Relaxed};

use super::relations::{unpack, unpack_facet, FaceKeys};
use super::{ExpandedLeaf, LeafView, StellarTree};
use crate::cell::CellKind;
use crate::csr::Csr;
use crate::ids::{CellId, LeafId, VertexId};
use crate::topo::{Adjacent, FacetAdjacency, Storage, TopCells, VertexAdjacency, VertexStar};

/// Slot value: no adjacent top cell across this facet.
const NONE: u32 = u32::MAX;
/// Slot value (local IA* only): the facet has no vertex in the leaf, not computed.
const NOT_LOCAL: u32 = u32::MAX - 1;
/// Tag of a non-manifold facet reference.
const NM: u32 = 1 << 31;

/// Decodes a stored slot (tree numbering).
fn decode(x: u32) -> Adjacent {
    match x {
        NONE => Adjacent::None,
        NOT_LOCAL => Adjacent::NotComputed,
        x if x & NM != 0 => Adjacent::NmFace(x & !NM),
        x => Adjacent::Top(CellId(x)),
    }
}

/// An IA* data structure over the tree's complex, stored in tree numbering and answering in
/// input numbering. For a local IA*, the cells are those of one leaf and the vertex lists
/// those of the leaf's vertices.
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
/// let ia = t.iastar(); // triangles [0, 1, 2] and [1, 3, 2], one vertex per leaf
/// assert_eq!(ia.cells(), vec![0, 1]);
/// assert_eq!(ia.star(VertexId(2)), vec![CellId(0), CellId(1)]);
/// let local = t.local_iastar(t.leaf_of_vertex(VertexId(3)).unwrap());
/// assert_eq!((local.cells(), local.vertices()), (vec![1], vec![3]));
/// ```
#[derive(Clone, Debug)]
pub struct StellarIaStar<'t> {
    tree: &'t StellarTree,
    /// Covered tree cells (sorted) for a local IA*; `None`: all.
    cells: Option<Vec<u32>>,
    /// R_{k,k} slots of the covered cells, in covered order (tree ids | NM tag | NONE).
    adj_off: Vec<u32>,
    adj: Vec<u32>,
    /// Non-manifold facets: their top cells (tree ids) and vertices (tree ids).
    nm_cells: Csr,
    nm_verts: Csr,
    /// Covered tree vertices.
    v_range: (u32, u32),
    /// R_{0,1} + R*_{0,k} of the covered vertices (tree cell ids), rows in tree order.
    reps: Csr,
}

impl<'t> StellarIaStar<'t> {
    fn cell_pos(&self, c: CellId) -> Option<usize> {
        let t = *self.tree.c_new.get(c.index())?;
        match &self.cells {
            None => Some(t as usize),
            Some(cs) => cs.binary_search(&t).ok(),
        }
    }
    fn tree_cell_pos(&self, t: u32) -> Option<usize> {
        match &self.cells {
            None => Some(t as usize),
            Some(cs) => cs.binary_search(&t).ok(),
        }
    }
    fn vertex_pos(&self, v: VertexId) -> Option<usize> {
        let tv = *self.tree.v_new.get(v.index())?;
        (tv >= self.v_range.0 && tv < self.v_range.1).then(|| (tv - self.v_range.0) as usize)
    }
    fn to_input_sorted(&self, cells: &[u32]) -> Vec<u32> {
        let mut v: Vec<u32> = cells
            .iter()
            .map(|&c| self.tree.c_orig[c as usize])
            .collect();
        v.sort_unstable();
        v
    }
    /// Cells covered (input ids, sorted).
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
    /// let ia = t.iastar(); // triangles [0, 1, 2] and [1, 3, 2], one vertex per leaf
    /// assert_eq!(ia.cells(), vec![0, 1]);
    /// let local = t.local_iastar(t.leaf_of_vertex(VertexId(0)).unwrap());
    /// assert_eq!(local.cells(), vec![0]); // the cells of vertex 0's leaf
    /// ```
    pub fn cells(&self) -> Vec<u32> {
        match &self.cells {
            None => (0..self.tree.n_top_cells() as u32).collect(),
            Some(cs) => self.to_input_sorted(cs),
        }
    }
    /// Vertices covered (input ids, sorted).
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
    /// let ia = t.iastar(); // triangles [0, 1, 2] and [1, 3, 2], one vertex per leaf
    /// assert_eq!(ia.vertices(), vec![0, 1, 2, 3]);
    /// let local = t.local_iastar(t.leaf_of_vertex(VertexId(3)).unwrap());
    /// assert_eq!(local.vertices(), vec![3]);
    /// ```
    pub fn vertices(&self) -> Vec<u32> {
        let mut v: Vec<u32> = (self.v_range.0..self.v_range.1)
            .map(|t| self.tree.v_orig[t as usize])
            .collect();
        v.sort_unstable();
        v
    }
    /// Expands the clusters of `v` through the adjacency slots: the top cells incident to `v`
    /// (needs the cells of the whole star to be covered, true for the global IA* and for the
    /// leaf's own vertices in a local one).
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
    /// let ia = t.iastar(); // triangles [0, 1, 2] and [1, 3, 2], one vertex per leaf
    /// assert_eq!(ia.star(VertexId(1)), vec![CellId(0), CellId(1)]);
    /// assert_eq!(ia.star(VertexId(0)), vec![CellId(0)]);
    /// assert_eq!(ia.star(VertexId(9)), vec![]); // not a vertex
    /// ```
    pub fn star(&self, v: VertexId) -> Vec<CellId> {
        let Some(i) = self.vertex_pos(v) else {
            return Vec::new();
        };
        let tv = self.v_range.0 + i as u32;
        let mut seen: FxHashSet<u32> = FxHashSet::default();
        let mut stack: Vec<u32> = Vec::new();
        for &r in self.reps.row(i) {
            if seen.insert(r) {
                stack.push(r);
            }
        }
        while let Some(c) = stack.pop() {
            let Some(pi) = self.tree_cell_pos(c) else {
                continue;
            };
            let (kind, vs) = self.tree.cells.get(c);
            let Some(p) = vs.iter().position(|&w| w == tv) else {
                continue;
            };
            let row = &self.adj[self.adj_off[pi] as usize..self.adj_off[pi + 1] as usize];
            for (j, &x) in row.iter().enumerate() {
                if !facet_contains(kind, j, p) {
                    continue;
                }
                match decode(x) {
                    Adjacent::Top(u) if seen.insert(u.0) => stack.push(u.0),
                    Adjacent::NmFace(f) => {
                        for &u in self.nm_cells.row(f as usize) {
                            if seen.insert(u) {
                                stack.push(u);
                            }
                        }
                    }
                    _ => {}
                }
            }
        }
        let mut out: Vec<CellId> = seen
            .into_iter()
            .map(|c| CellId(self.tree.c_orig[c as usize]))
            .collect();
        out.sort_unstable();
        out
    }
}

impl TopCells for StellarIaStar<'_> {
    fn n_vertices(&self) -> usize {
        self.tree.n_vertices()
    }
    fn n_top_cells(&self) -> usize {
        self.cells
            .as_ref()
            .map_or(self.tree.n_top_cells(), |c| c.len())
    }
    fn top_cell_kind(&self, c: CellId) -> CellKind {
        self.tree.cells.get(self.tree.c_new[c.index()]).0
    }
    fn top_cell_vertices(&self, c: CellId, out: &mut Vec<VertexId>) {
        if self.cell_pos(c).is_some() {
            let (_, vs) = self.tree.cells.get(self.tree.c_new[c.index()]);
            out.extend(vs.iter().map(|&v| VertexId(self.tree.v_orig[v as usize])));
        }
    }
}

impl VertexStar for StellarIaStar<'_> {
    fn vertex_top_cells(&self, v: VertexId, out: &mut Vec<CellId>) {
        *out = self.star(v);
    }
}

impl FacetAdjacency for StellarIaStar<'_> {
    /// 0 for a cell the IA* does not cover (a local IA* covers its leaf's cells).
    fn n_facet_slots(&self, c: CellId) -> usize {
        self.cell_pos(c)
            .map_or(0, |i| (self.adj_off[i + 1] - self.adj_off[i]) as usize)
    }
    fn facet_adjacent(&self, c: CellId, j: usize) -> Adjacent {
        let Some(i) = self.cell_pos(c) else {
            return Adjacent::None;
        };
        let row = &self.adj[self.adj_off[i] as usize..self.adj_off[i + 1] as usize];
        match row.get(j).map(|&x| decode(x)) {
            Some(Adjacent::Top(u)) => Adjacent::Top(CellId(self.tree.c_orig[u.index()])),
            Some(a) => a,
            None => Adjacent::None,
        }
    }
    fn n_nm_faces(&self) -> usize {
        self.nm_cells.n_rows()
    }
    fn nm_face_cells(&self, f: u32) -> Vec<CellId> {
        if f as usize >= self.nm_cells.n_rows() {
            return Vec::new();
        }
        let cells = self.to_input_sorted(self.nm_cells.row(f as usize));
        cells.into_iter().map(CellId).collect()
    }
    fn nm_face_vertices(&self, f: u32) -> Vec<VertexId> {
        if f as usize >= self.nm_verts.n_rows() {
            return Vec::new();
        }
        let mut v: Vec<VertexId> = self
            .nm_verts
            .row(f as usize)
            .iter()
            .map(|&w| VertexId(self.tree.v_orig[w as usize]))
            .collect();
        v.sort_unstable();
        v
    }
    /// Empty for a vertex outside a local IA*'s leaf.
    fn vertex_references(&self, v: VertexId) -> Vec<CellId> {
        self.vertex_pos(v).map_or(Vec::new(), |i| {
            let cells = self.to_input_sorted(self.reps.row(i));
            cells.into_iter().map(CellId).collect()
        })
    }
}

impl Storage for StellarIaStar<'_> {
    /// The spec's paper-faithful count: R_{k,0} + R_{k,k} slots + the non-manifold facet lists
    /// + R_{0,1} and cluster representatives.
    fn refs(&self) -> u64 {
        let cell_refs = match &self.cells {
            None => self.tree.cells.verts.len(),
            Some(cs) => cs.iter().map(|&c| self.tree.cells.verts(c).len()).sum(),
        };
        (cell_refs + self.adj.len() + self.nm_cells.n_refs() + self.reps.n_refs()) as u64
    }
    /// The arrays this structure adds to the tree (the tree's own cells are not counted).
    fn bytes(&self) -> u64 {
        let b = 4
            * (self.cells.as_ref().map_or(0, |c| c.len()) + self.adj_off.len() + self.adj.len())
            + self.nm_cells.bytes()
            + self.nm_verts.bytes()
            + self.reps.bytes();
        b as u64
    }
}

impl VertexAdjacency for StellarIaStar<'_> {
    /// The edges of the cells around `v` (a CP cell's face-table edges: a quad's diagonal is
    /// not an edge); needs `v`'s whole star covered, as [`StellarIaStar::star`].
    fn vertex_neighbours(&self, v: VertexId, out: &mut Vec<VertexId>) {
        out.clear();
        let mut vs = Vec::new();
        for c in self.star(v) {
            vs.clear();
            self.top_cell_vertices(c, &mut vs);
            let kind = self.top_cell_kind(c);
            if kind.is_simplex() {
                out.extend(vs.iter().copied().filter(|&w| w != v));
            } else {
                let raw: Vec<u32> = vs.iter().map(|w| w.0).collect();
                crate::topo::naive::edge_neighbours(kind, &raw, v.0, |w| out.push(VertexId(w)));
            }
        }
        out.sort_unstable();
        out.dedup();
    }
}

crate::impl_relations_from_tops!(StellarIaStar<'_>);

/// Whether facet `j` of a cell of `kind` contains local vertex position `p`.
fn facet_contains(kind: CellKind, j: usize, p: usize) -> bool {
    if kind.is_simplex() {
        return j != p;
    }
    kind.cp_faces(kind.dim() - 1)
        .and_then(|t| t.get(j))
        .is_some_and(|f| f.contains(&(p as u8)))
}

fn n_slots(kind: CellKind) -> usize {
    if kind.dim() >= 2 {
        kind.n_faces(kind.dim() - 1) as usize
    } else {
        0
    }
}

/// Inserts into `t` the facets of the cells of leaf `e` (simplices of `S` = 3 or 4 vertices,
/// `verts` all cells' vertices) whose smallest vertex the leaf owns, keyed in 8 bytes, pairs
/// written into `adj`.
#[inline(always)]
fn hash_owned_facets<const S: usize>(
    verts: &[u32],
    e: &ExpandedLeaf,
    t: &mut FacetTable,
    adj: &[AtomicU32],
) {
    let (lo, hi) = (e.v_start, e.v_end);
    for &c in &e.cells {
        let vs = &verts[c as usize * S..c as usize * S + S];
        // sorted vertices with their listed positions (a branch-free sorting network on
        // vertex << 8 | position; for triangles the fourth stays last)
        let mut r = [u64::MAX; 4];
        for i in 0..S {
            r[i] = ((vs[i] as u64) << 8) | i as u64;
        }
        let r = crate::topo::sort4(r);
        let sv = r.map(|x| (x >> 8) as u32);
        // the facet omitting the k-th smallest vertex (listed position rk as u8)
        for (k, &rk) in r[..S].iter().enumerate() {
            let min = if k == 0 { sv[1] } else { sv[0] };
            if min < lo || min >= hi {
                continue;
            }
            let key = if S == 3 {
                let (a, b) = match k {
                    0 => (sv[1], sv[2]),
                    1 => (sv[0], sv[2]),
                    _ => (sv[0], sv[1]),
                };
                ((a as u64) << 32) | b as u64
            } else {
                let mut f = [0u64; 3];
                let mut m = 0;
                for (i, &x) in sv.iter().enumerate() {
                    if i != k {
                        f[m] = x as u64;
                        m += 1;
                    }
                }
                (f[0] << 42) | (f[1] << 21) | f[2]
            };
            t.insert(key, c, rk as u8 as u32, S as u32, adj);
        }
    }
}

/// Per-leaf pieces of an IA*, in tree numbering.
struct Pieces {
    /// (slot index, value) with value = tree cell | local nm index | NM (8 bytes a slot: the
    /// grouped pieces of a global IA* hold every slot once before the scatter; the hashed
    /// ones only the slots of non-manifold facets).
    slots: Vec<(u32, u32)>,
    nm_cells: Vec<Vec<u32>>,
    nm_verts: Vec<Vec<u32>>,
}

/// The pieces of one leaf from its grouped facet keys; `slot(c, j)` is the slot index of
/// facet `j` of tree cell `c`. The groups may come in any order that depends only on the
/// pushes: the non-manifold facets are numbered in key order afterwards, so the result is
/// the same.
fn group_pieces(keys: &mut FaceKeys, slot: impl Fn(u32, u32) -> u32) -> Pieces {
    let mut p = Pieces {
        slots: Vec::new(),
        nm_cells: Vec::new(),
        nm_verts: Vec::new(),
    };
    let at = |x: u64| slot(unpack(x).0, unpack_facet(x));
    let mut nm: Vec<(Vec<u32>, Vec<u64>)> = Vec::new();
    keys.for_each_group_unordered(|key, pays| match pays.len() {
        1 => {}
        2 => {
            let (a, b) = (unpack(pays[0]).0, unpack(pays[1]).0);
            p.slots.push((at(pays[0]), b));
            p.slots.push((at(pays[1]), a));
        }
        _ => nm.push((key.to_vec(), pays.to_vec())),
    });
    nm.sort_unstable_by(|a, b| a.0.cmp(&b.0));
    for (key, pays) in nm {
        let id = p.nm_cells.len() as u32 | NM;
        let mut cs: Vec<u32> = pays.iter().map(|&x| unpack(x).0).collect();
        for &x in &pays {
            p.slots.push((at(x), id));
        }
        cs.sort_unstable();
        cs.dedup();
        p.nm_cells.push(cs);
        p.nm_verts.push(key[1..].to_vec());
    }
    p
}

impl StellarTree {
    /// The global IA*, built leaf by leaf in parallel: each facet is examined once, in the leaf
    /// owning its smallest vertex (for triangles and tetrahedra hashed in a leaf-sized table,
    /// otherwise grouped as face keys); the cluster representatives of each vertex are found in
    /// its leaf by a flood over the slots. Same result for any number of threads.
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
    /// let ia = t.iastar(); // triangles [0, 1, 2] and [1, 3, 2], one vertex per leaf
    /// use starplex::topo::{Adjacent, FacetAdjacency, Storage};
    /// assert_eq!(ia.facet_adjacent(CellId(0), 0), Adjacent::Top(CellId(1)));
    /// // the same structure whatever the leaves
    /// let one_leaf = StellarTree::build(&k, &StellarOptions { kv: Some(0), ..Default::default() }).unwrap();
    /// assert_eq!(one_leaf.iastar().refs(), ia.refs());
    /// ```
    pub fn iastar(&self) -> StellarIaStar<'_> {
        let nc = self.n_top_cells();
        let off = self.slot_offsets();
        let (adj, nm_cells, nm_verts) = match self.facet_slots_hashed() {
            Some((adj, pieces)) => self.scatter_pieces(pieces, adj),
            None => {
                let pieces = self.par_facet_groups_where(2, false, |_, keys| {
                    group_pieces(keys, |c, j| off[c as usize] + j)
                });
                self.scatter_pieces(pieces, vec![NONE; off[nc] as usize])
            }
        };
        let stride = if let Some(kind) = self.cells.uniform {
            n_slots(kind)
        } else {
            0
        };
        // one simplex kind of dimension >= 2: the flood reads the slots directly
        let simplex_dim2 = self
            .cells
            .uniform
            .is_some_and(|k| k.is_simplex() && k.dim() >= 2);
        // representatives, leaf by leaf; rows come out in tree vertex order
        let slots = |c: u32| {
            if stride > 0 {
                // one kind: the slots of cell c start at c * stride
                let s = c as usize * stride;
                &adj[s..s + stride]
            } else {
                &adj[off[c as usize] as usize..off[c as usize + 1] as usize]
            }
        };
        let per_leaf: Vec<(Vec<u32>, Vec<u32>)> = (0..self.n_leaves() as u32)
            .into_par_iter()
            .map_init(
                || {
                    // per worker: visit stamps over all cells and one more, the flood's
                    // sink (2 bytes per cell, zeroed lazily by the allocator)
                    let sc = RepScratch {
                        stamps: vec![0; nc + 1],
                        ..Default::default()
                    };
                    (ExpandedLeaf::default(), sc)
                },
                |(e, sc), l| {
                    self.expand_leaf_into(LeafId(l), e);
                    if simplex_dim2 {
                        // the flood reads the leaf's cells in star order, at random: their
                        // slots, vertices and input ids are asked for in id order first
                        let pf = crate::buf::prefetch;
                        for &c in &e.cells {
                            let c = c as usize;
                            pf(&adj, c * stride);
                            pf(&self.cells.verts, c * stride);
                            pf(&self.c_orig, c);
                        }
                    }
                    let view = LeafView { tree: self, e };
                    let mut lens = Vec::with_capacity(view.tree_vertices().len());
                    // about one representative a vertex on a manifold
                    let mut data = Vec::with_capacity(view.tree_vertices().len() + 8);
                    for v in view.tree_vertices() {
                        let s = data.len();
                        if simplex_dim2 {
                            let ep = sc.next_epoch();
                            let (star, nm) = (view.vt_tree(v), &nm_cells);
                            let RepScratch { stack, stamps, .. } = sc;
                            let out = &mut data;
                            // triangles and tetrahedra: the stride a constant, the slot
                            // loop unrolled
                            match stride {
                                3 => self
                                    .flood_simplices(v, star, &adj, 3, nm, stamps, ep, stack, out),
                                4 => self
                                    .flood_simplices(v, star, &adj, 4, nm, stamps, ep, stack, out),
                                _ => self.flood_simplices(
                                    v, star, &adj, stride, nm, stamps, ep, stack, out,
                                ),
                            }
                        } else {
                            self.representatives(&view, v, &slots, &nm_cells, sc, &mut data);
                        }
                        lens.push((data.len() - s) as u32);
                    }
                    (lens, data)
                },
            )
            .collect();
        self.global_iastar(off, adj, (nm_cells, nm_verts), per_leaf)
    }

    /// The slots of a complex of one simplex kind of dimension 2 or 3 whose facet keys fit
    /// in 8 bytes (edges always; triangles with at most 2^21 vertices), with the per-leaf
    /// [`Pieces`] of its non-manifold facets, as
    /// [`par_facet_groups_where`](Self::par_facet_groups_where) with [`group_pieces`] gives
    /// them, without the face records: each leaf hashes the facets of its cells whose
    /// smallest vertex it owns into an open-addressing table sized for the leaf. The second
    /// cell met on a facet pairs the two at once, writing both slots (each slot is written by
    /// the one leaf that owns its facet); a third makes the facet non-manifold, and the
    /// non-manifold facets of the leaf are numbered in key order at the end (their slots,
    /// in the pieces, overwrite the pairs in [`scatter_pieces`](Self::scatter_pieces)).
    /// `None` for other complexes.
    fn facet_slots_hashed(&self) -> Option<(Vec<u32>, Vec<Pieces>)> {
        let kind = self.cells.uniform?;
        let s = self.cells.stride as usize;
        let fits = kind.is_simplex() && (s == 3 || (s == 4 && self.n_vertices() <= 1 << 21));
        if !fits {
            return None;
        }
        let verts = &self.cells.verts;
        let adj: Vec<AtomicU32> =
            crate::buf::large_with(self.n_top_cells() * s, || AtomicU32::new(NONE));
        let pieces = (0..self.n_leaves() as u32)
            .into_par_iter()
            .map_init(
                || (ExpandedLeaf::default(), FacetTable::default()),
                |(e, t), l| {
                    self.expand_leaf_cells(LeafId(l), e);
                    t.reset(e.cells.len() * s);
                    // the non-manifold facets only: empty (no allocation) on a manifold
                    let mut p = Pieces {
                        slots: Vec::new(),
                        nm_cells: Vec::new(),
                        nm_verts: Vec::new(),
                    };
                    // the stride a constant: the facet loop unrolled
                    if s == 3 {
                        hash_owned_facets::<3>(verts, e, t, &adj);
                    } else {
                        hash_owned_facets::<4>(verts, e, t, &adj);
                    }
                    t.finish(s, &mut p);
                    p
                },
            )
            .collect();
        // same size and alignment: collected in place
        let adj = adj.into_iter().map(AtomicU32::into_inner).collect();
        Some((adj, pieces))
    }

    /// The first slot of every tree cell, then the number of slots.
    fn slot_offsets(&self) -> Vec<u32> {
        let nc = self.n_top_cells();
        if let Some(kind) = self.cells.uniform {
            let s = n_slots(kind) as u32;
            return (0..=nc as u32).map(|c| c * s).collect();
        }
        let mut off = vec![0u32; nc + 1];
        for c in 0..nc {
            off[c + 1] = off[c] + n_slots(self.cells.get(c as u32).0) as u32;
        }
        off
    }

    /// The slots `adj` filled from the leaves' pieces (leaves in order: the non-manifold
    /// facets are numbered leaf after leaf), and the non-manifold facets' cells and vertices.
    fn scatter_pieces(&self, pieces: Vec<Pieces>, mut adj: Vec<u32>) -> (Vec<u32>, Csr, Csr) {
        let mut nm_cells = Csr {
            offsets: vec![0],
            targets: Vec::new(),
        };
        let mut nm_verts = nm_cells.clone();
        for p in pieces {
            let base = nm_cells.n_rows() as u32;
            for (i, x) in p.slots {
                let x = if x != NONE && x & NM != 0 {
                    ((x & !NM) + base) | NM
                } else {
                    x
                };
                adj[i as usize] = x;
            }
            for (cs, vs) in p.nm_cells.iter().zip(&p.nm_verts) {
                nm_cells.targets.extend_from_slice(cs);
                nm_cells.offsets.push(nm_cells.targets.len() as u32);
                nm_verts.targets.extend_from_slice(vs);
                nm_verts.offsets.push(nm_verts.targets.len() as u32);
            }
        }
        (adj, nm_cells, nm_verts)
    }

    /// Assembles the global IA* from its slots, non-manifold facets and per-leaf
    /// representative rows (leaves in order).
    fn global_iastar(
        &self,
        adj_off: Vec<u32>,
        adj: Vec<u32>,
        (nm_cells, nm_verts): (Csr, Csr),
        per_leaf: Vec<(Vec<u32>, Vec<u32>)>,
    ) -> StellarIaStar<'_> {
        let mut reps = Csr {
            offsets: Vec::with_capacity(self.n_vertices() + 1),
            targets: Vec::new(),
        };
        reps.offsets.push(0);
        for (lens, data) in per_leaf {
            for l in lens {
                let last = *reps.offsets.last().expect("non-empty");
                reps.offsets.push(last + l);
            }
            reps.targets.extend_from_slice(&data);
        }
        StellarIaStar {
            tree: self,
            cells: None,
            adj_off,
            adj,
            nm_cells,
            nm_verts,
            v_range: (0, self.n_vertices() as u32),
            reps,
        }
    }

    /// Appends the top edges and cluster representatives of tree vertex `v` (tree cell ids;
    /// each cluster represented by its cell of smallest input id).
    fn representatives<'s>(
        &self,
        view: &LeafView<'_>,
        v: u32,
        slots_of: &impl Fn(u32) -> &'s [u32],
        nm_cells: &Csr,
        sc: &mut RepScratch,
        out: &mut Vec<u32>,
    ) {
        let star = view.vt_tree(v);
        if !sc.stamps.is_empty() {
            return self.representatives_stamped(v, star, slots_of, nm_cells, sc, out);
        }
        let RepScratch {
            seen,
            stack,
            keys,
            vals,
            ..
        } = sc;
        // star cell -> index in the star (open addressing; neighbours through facets
        // containing v are in the star)
        let cap = (2 * star.len()).next_power_of_two().max(16);
        let shift = 32 - cap.trailing_zeros();
        let mask = cap - 1;
        if keys.len() < cap {
            keys.resize(cap, NONE);
            vals.resize(cap, 0);
        }
        let hash = |c: u32| (c.wrapping_mul(0x9E37_79B1) >> shift) as usize;
        for (i, &c) in star.iter().enumerate() {
            let mut h = hash(c);
            while keys[h] != NONE {
                h = (h + 1) & mask;
            }
            keys[h] = c;
            vals[h] = i as u32;
        }
        seen.clear();
        seen.resize(star.len(), false);
        // marks `c` seen; true when it is in the star and was not seen before
        let mark = |seen: &mut Vec<bool>, c: u32| -> bool {
            let mut h = hash(c);
            loop {
                let k = keys[h];
                if k == c {
                    let i = vals[h] as usize;
                    if seen[i] {
                        return false;
                    }
                    seen[i] = true;
                    return true;
                }
                if k == NONE {
                    return false;
                }
                h = (h + 1) & mask;
            }
        };
        self.flood_clusters(v, star, slots_of, nm_cells, stack, out, |c| mark(seen, c));
        // empty the table
        for &c in star {
            let mut h = hash(c);
            while keys[h] != c {
                h = (h + 1) & mask;
            }
            keys[h] = NONE;
        }
    }

    /// [`representatives`](Self::representatives) with visit stamps over all cells (every
    /// cell met through a facet containing `v` is in the star of `v`).
    fn representatives_stamped<'s>(
        &self,
        v: u32,
        star: &[u32],
        slots_of: &impl Fn(u32) -> &'s [u32],
        nm_cells: &Csr,
        sc: &mut RepScratch,
        out: &mut Vec<u32>,
    ) {
        let ep = sc.next_epoch();
        let RepScratch { stack, stamps, .. } = sc;
        self.flood_clusters(v, star, slots_of, nm_cells, stack, out, |c| {
            let fresh = stamps[c as usize] != ep;
            stamps[c as usize] = ep;
            fresh
        });
    }

    /// [`flood_clusters`](Self::flood_clusters) with stamps for a complex of one simplex kind
    /// of dimension >= 2, whose slots are `adj[c * s..c * s + s]` (slot j: the facet
    /// omitting vertex j).
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn flood_simplices(
        &self,
        v: u32,
        star: &[u32],
        adj: &[u32],
        s: usize,
        nm_cells: &Csr,
        stamps: &mut [u16],
        ep: u16,
        stack: &mut Vec<u32>,
        out: &mut Vec<u32>,
    ) {
        let verts = &self.cells.verts;
        let orig = &self.c_orig;
        // the last stamp is a sink that always holds the current stamp: slots that lead
        // nowhere (the facet omits v, no neighbour) mark it instead of branching
        let sink = stamps.len() - 1;
        stamps[sink] = ep;
        // every cell of the star is pushed at most once
        stack.clear();
        stack.resize(star.len() + 1, 0);
        for &c in star {
            if stamps[c as usize] == ep {
                continue;
            }
            stamps[c as usize] = ep;
            let (mut best, mut best_orig) = (c, orig[c as usize]);
            stack[0] = c;
            let mut top = 1usize;
            while top > 0 {
                top -= 1;
                let a = stack[top];
                let o = orig[a as usize];
                if o < best_orig {
                    (best, best_orig) = (a, o);
                }
                let a = a as usize;
                let (vs, sl) = (&verts[a * s..a * s + s], &adj[a * s..a * s + s]);
                for (&w, &x) in vs.iter().zip(sl) {
                    // NONE has the NM bit: one test excludes both
                    let nm = x & NM != 0;
                    if nm && x != NONE && w != v {
                        for &u in nm_cells.row((x & !NM) as usize) {
                            if stamps[u as usize] != ep {
                                stamps[u as usize] = ep;
                                stack[top] = u;
                                top += 1;
                            }
                        }
                        continue;
                    }
                    let i = if w != v && !nm { x as usize } else { sink };
                    let fresh = stamps[i] != ep;
                    stamps[i] = ep;
                    stack[top] = x;
                    top += fresh as usize;
                }
            }
            out.push(best);
        }
    }

    /// The flood shared by both marking schemes: every top edge of `star` (the star of tree
    /// vertex `v`), then each k-cluster (k >= 2) found by walking the adjacency slots across
    /// facets containing `v`, represented by its cell of smallest input id. `mark(c)` marks
    /// `c` visited and says whether it was not visited before.
    #[allow(clippy::too_many_arguments)]
    #[inline]
    fn flood_clusters<'s>(
        &self,
        v: u32,
        star: &[u32],
        slots_of: &impl Fn(u32) -> &'s [u32],
        nm_cells: &Csr,
        stack: &mut Vec<u32>,
        out: &mut Vec<u32>,
        mut mark: impl FnMut(u32) -> bool,
    ) {
        stack.clear();
        for &c in star {
            let kind = self.cells.get(c).0;
            if kind.dim() < 2 {
                if kind.dim() == 1 {
                    out.push(c);
                }
                continue;
            }
            if !mark(c) {
                continue;
            }
            // the cluster's representative: its smallest input id, as the direct IA* picks
            let mut best = c;
            stack.push(c);
            while let Some(a) = stack.pop() {
                if self.c_orig[a as usize] < self.c_orig[best as usize] {
                    best = a;
                }
                let (ka, vs) = self.cells.get(a);
                let p = vs.iter().position(|&w| w == v).expect("in the star");
                let simplex = ka.is_simplex();
                for (j, &x) in slots_of(a).iter().enumerate() {
                    if x == NONE
                        || x == NOT_LOCAL
                        || if simplex {
                            j == p
                        } else {
                            !facet_contains(ka, j, p)
                        }
                    {
                        continue;
                    }
                    if x & NM != 0 {
                        for &u in nm_cells.row((x & !NM) as usize) {
                            if mark(u) {
                                stack.push(u);
                            }
                        }
                    } else if mark(x) {
                        stack.push(x);
                    }
                }
            }
            out.push(best);
        }
    }

    /// The local IA* of one leaf: its top cells with the adjacencies across facets that have
    /// a vertex in the leaf (other slots are [`Adjacent::NotComputed`]), the non-manifold
    /// facets among those, and the representatives of the leaf's vertices.
    ///
    /// ```
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// use starplex::stellar::{StellarTree, StellarOptions};
    /// use starplex::ids::{LeafId, VertexId};
    /// use starplex::topo::VertexStar;
    /// # let mut b = ComplexBuilder::new(2).unwrap();
    /// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
    /// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
    /// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// let t = StellarTree::build(&k, &StellarOptions { kv: Some(1), ..Default::default() }).unwrap();
    /// let l = t.leaf_of_vertex(VertexId(1)).unwrap();
    /// let ia = t.local_iastar(l);
    /// assert_eq!(ia.vertices(), vec![1]);
    /// assert_eq!(ia.star(VertexId(1)).len(), 2);
    /// // the leaf of vertex 0 does not examine edge {1,2} (facet 0 of triangle [0, 1, 2])
    /// use starplex::ids::CellId;
    /// use starplex::topo::{Adjacent, FacetAdjacency};
    /// let local = t.local_iastar(t.leaf_of_vertex(VertexId(0)).unwrap());
    /// assert_eq!(local.facet_adjacent(CellId(0), 0), Adjacent::NotComputed);
    /// assert_eq!(local.facet_adjacent(CellId(0), 1), Adjacent::None);
    /// ```
    pub fn local_iastar(&self, l: LeafId) -> StellarIaStar<'_> {
        let mut e = ExpandedLeaf::default();
        self.expand_leaf_into(l, &mut e);
        let view = LeafView { tree: self, e: &e };
        let mut keys = FaceKeys::default();
        let w = 1 + self
            .kinds()
            .iter()
            .map(|&k| {
                if k.dim() >= 1 {
                    super::relations::face_width(k, k.dim() - 1)
                } else {
                    0
                }
            })
            .max()
            .unwrap_or(0);
        keys.clear(w);
        let mut key = Vec::new();
        for &c in &e.cells {
            let (kind, vs) = self.cells.get(c);
            let d = kind.dim();
            if d < 2 {
                continue;
            }
            let mut j = 0u64;
            crate::cell::oriented_facets_of(kind, |local, _| {
                j += 1;
                key.clear();
                key.extend(local.iter().map(|&i| vs[i as usize]));
                if key.iter().any(|&x| view.owns_tree(x)) {
                    key.sort_unstable();
                    key.insert(0, d as u32);
                    keys.push(&key, super::relations::pack(c, j - 1, 1));
                }
            });
        }
        let ncl = e.cells.len();
        let pos = |c: u32| e.cells.binary_search(&c).expect("a leaf cell");
        let mut off = vec![0u32; ncl + 1];
        for (i, &c) in e.cells.iter().enumerate() {
            off[i + 1] = off[i] + n_slots(self.cells.get(c).0) as u32;
        }
        let p = group_pieces(&mut keys, |c, j| off[pos(c)] + j);
        let mut adj = vec![NOT_LOCAL; off[ncl] as usize];
        // facets with a leaf vertex: NONE unless paired below
        for (i, &c) in e.cells.iter().enumerate() {
            let (kind, vs) = self.cells.get(c);
            if kind.dim() < 2 {
                continue;
            }
            let mut j = 0usize;
            crate::cell::oriented_facets_of(kind, |local, _| {
                if local.iter().any(|&x| view.owns_tree(vs[x as usize])) {
                    adj[off[i] as usize + j] = NONE;
                }
                j += 1;
            });
        }
        for &(i, x) in &p.slots {
            adj[i as usize] = x;
        }
        let mut nm_cells = Csr {
            offsets: vec![0],
            targets: Vec::new(),
        };
        let mut nm_verts = nm_cells.clone();
        for (cs, vs) in p.nm_cells.iter().zip(&p.nm_verts) {
            nm_cells.targets.extend_from_slice(cs);
            nm_cells.offsets.push(nm_cells.targets.len() as u32);
            nm_verts.targets.extend_from_slice(vs);
            nm_verts.offsets.push(nm_verts.targets.len() as u32);
        }
        let slots_of = |c: u32| -> &[u32] {
            let i = pos(c);
            &adj[off[i] as usize..off[i + 1] as usize]
        };
        let mut reps = Csr {
            offsets: vec![0],
            targets: Vec::new(),
        };
        let mut sc = RepScratch::default();
        for v in view.tree_vertices() {
            self.representatives(&view, v, &slots_of, &nm_cells, &mut sc, &mut reps.targets);
            reps.offsets.push(reps.targets.len() as u32);
        }
        let cells = std::mem::take(&mut e.cells);
        StellarIaStar {
            tree: self,
            cells: Some(cells),
            adj_off: off,
            adj,
            nm_cells,
            nm_verts,
            v_range: (e.v_start, e.v_end),
            reps,
        }
    }

    /// Builds the local IA* of every leaf in parallel and returns the total of their
    /// reference counts (the local approach: each is discarded after use by `f`).
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
    /// // each leaf's local IA* covers its own vertex and that vertex's triangles
    /// let per_leaf = t.par_local_iastar(|ia| (ia.vertices().len(), ia.cells().len()));
    /// assert_eq!(per_leaf.len(), 4);
    /// assert!(per_leaf.iter().all(|&(nv, _)| nv == 1));
    /// assert_eq!(per_leaf.iter().map(|&(_, nc)| nc).sum::<usize>(), 6);
    /// ```
    pub fn par_local_iastar<R: Send>(
        &self,
        f: impl Fn(&StellarIaStar<'_>) -> R + Sync + Send,
    ) -> Vec<R> {
        (0..self.n_leaves() as u32)
            .into_par_iter()
            .map(|l| f(&self.local_iastar(LeafId(l))))
            .collect()
    }
}

/// The per-leaf table of [`StellarTree::facet_pieces_hashed`]: 8-byte facet keys (`EMPTY`
/// when unused) and a state per key: the first cell met on the facet, the index of the pair
/// in the leaf's slots, or non-manifold; the slots used (to empty the table) and the facet
/// records of the non-manifold facets.
#[derive(Default)]
struct FacetTable {
    keys: Vec<u64>,
    vals: Vec<u64>,
    used: Vec<u32>,
    /// The two slots of every pair (a pair's value indexes it).
    paired: Vec<(u32, u32)>,
    shift: u32,
    /// (key, tree cell, facet) of every cell on a non-manifold facet.
    extra: Vec<(u64, u32, u32)>,
}

impl FacetTable {
    const EMPTY: u64 = u64::MAX;
    /// State tags (top two bits of a value).
    const SINGLE: u64 = 1 << 62;
    const PAIRED: u64 = 2 << 62;
    const NONMANIFOLD: u64 = 3 << 62;

    /// Empties the table (through the slots used) and sizes it for `n` insertions at most.
    fn reset(&mut self, n: usize) {
        for &h in &self.used {
            self.keys[h as usize] = Self::EMPTY;
        }
        self.used.clear();
        self.paired.clear();
        self.extra.clear();
        let cap = (2 * n).next_power_of_two().max(64);
        if self.keys.len() < cap {
            self.keys.clear();
            self.keys.resize(cap, Self::EMPTY);
            self.vals.resize(cap, 0);
        }
        // hash into the first `cap` slots; larger tables from earlier leaves stay empty
        self.shift = 64 - cap.trailing_zeros();
    }

    /// Facet `j` of tree cell `c` (`s` slots a cell) has key `key`: pairs it with the first
    /// cell met on the same facet (writing both slots of `adj`), or records a non-manifold
    /// facet.
    #[inline(always)]
    fn insert(&mut self, key: u64, c: u32, j: u32, s: u32, adj: &[AtomicU32]) {
        let mask = (1usize << (64 - self.shift)) - 1;
        let mut h = (key.wrapping_mul(0x9E37_79B9_7F4A_7C15) >> self.shift) as usize;
        loop {
            let k = self.keys[h];
            if k == Self::EMPTY {
                self.keys[h] = key;
                self.vals[h] = Self::SINGLE | ((j as u64) << 32) | c as u64;
                self.used.push(h as u32);
                return;
            }
            if k == key {
                break;
            }
            h = (h + 1) & mask;
        }
        let x = self.vals[h];
        match x & (3 << 62) {
            Self::SINGLE => {
                let (a, ja) = (x as u32, (x >> 32) as u32 & 0xff);
                self.vals[h] = Self::PAIRED | self.paired.len() as u64;
                let (sa, sc) = (a * s + ja, c * s + j);
                self.paired.push((sa, sc));
                // each slot belongs to the one leaf owning its facet: plain stores
                adj[sa as usize].store(c, Relaxed);
                adj[sc as usize].store(a, Relaxed);
            }
            Self::PAIRED => {
                let (sa, sb) = self.paired[(x & 0xffff_ffff) as usize];
                let (a, b) = (sa / s, sb / s);
                self.extra.push((key, a, sa - a * s));
                self.extra.push((key, b, sb - b * s));
                self.extra.push((key, c, j));
                self.vals[h] = Self::NONMANIFOLD;
            }
            _ => self.extra.push((key, c, j)),
        }
    }

    /// Numbers the leaf's non-manifold facets in key order and pushes their slots (after the
    /// pairs they replace) and their cells and vertices (tree ids) into `p`; `s` is the
    /// cells' vertex count.
    fn finish(&mut self, s: usize, p: &mut Pieces) {
        if self.extra.is_empty() {
            return;
        }
        self.extra.sort_unstable();
        for g in self.extra.chunk_by(|a, b| a.0 == b.0) {
            let id = p.nm_cells.len() as u32 | NM;
            let mut cs = Vec::with_capacity(g.len());
            for &(_, c, j) in g {
                p.slots.push((c * s as u32 + j, id));
                cs.push(c);
            }
            cs.dedup();
            p.nm_cells.push(cs);
            let key = g[0].0;
            p.nm_verts.push(if s == 3 {
                vec![(key >> 32) as u32, key as u32]
            } else {
                let m = (1u64 << 21) - 1;
                vec![
                    (key >> 42) as u32,
                    ((key >> 21) & m) as u32,
                    (key & m) as u32,
                ]
            });
        }
    }
}

impl RepScratch {
    /// A new visit stamp (the stamps are zeroed when the counter wraps).
    fn next_epoch(&mut self) -> u16 {
        self.epoch = self.epoch.wrapping_add(1);
        if self.epoch == 0 {
            self.stamps.iter_mut().for_each(|x| *x = 0);
            self.epoch = 1;
        }
        self.epoch
    }
}

#[derive(Default)]
struct RepScratch {
    seen: Vec<bool>,
    stack: Vec<u32>,
    /// Hash table star cell -> star index (slots NONE when unused).
    keys: Vec<u32>,
    vals: Vec<u32>,
    /// Global IA*: a visit stamp per tree cell (empty: use the hash table), current stamp.
    stamps: Vec<u16>,
    epoch: u16,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::complex::{BuildOptions, ComplexBuilder};
    use crate::stellar::StellarOptions;
    use crate::testkit::XorShift;

    /// The hashed facet pairing gives exactly the slots and non-manifold facets (same numbers,
    /// cells and vertices) of the face-key grouping, on random complexes of triangles and of
    /// tetrahedra on few vertices, where non-manifold facets and vertices are common, for
    /// several leaf sizes.
    #[test]
    fn hashed_facets_are_the_grouped_facets() {
        let mut rng = XorShift::new(41);
        let (mut nm_seen, mut cases) = (0usize, 0usize);
        for case in 0..400 {
            let s = 3 + case % 2;
            let nv = 4 + rng.below(14) as usize;
            let mut b = ComplexBuilder::new(3).unwrap();
            for _ in 0..nv {
                let p = [0, 1, 2].map(|_| rng.below(5) as f64);
                b.push_vertex(&p).unwrap();
            }
            for _ in 0..1 + rng.below(30) {
                let mut vs: Vec<u32> = Vec::new();
                while vs.len() < s {
                    let v = rng.below(nv as u64) as u32;
                    if !vs.contains(&v) {
                        vs.push(v);
                    }
                }
                b.push_cell(CellKind::Simplex(s as u8 - 1), &vs).unwrap();
            }
            let opts = BuildOptions {
                drop_duplicates: true,
                ..Default::default()
            };
            let Ok((k, _)) = b.build(&opts) else { continue };
            for kv in [1, 3, 0] {
                let t = StellarTree::build(
                    &k,
                    &StellarOptions {
                        kv: Some(kv),
                        ..Default::default()
                    },
                )
                .unwrap();
                let Some((adj, hashed)) = t.facet_slots_hashed() else {
                    continue; // not one kind (cannot happen here)
                };
                let off = t.slot_offsets();
                let grouped = t.par_facet_groups_where(2, false, |_, keys| {
                    group_pieces(keys, |c, j| off[c as usize] + j)
                });
                let n = *off.last().unwrap() as usize;
                let (a, b) = (
                    t.scatter_pieces(hashed, adj),
                    t.scatter_pieces(grouped, vec![NONE; n]),
                );
                assert_eq!(a.0, b.0, "case {case} kv {kv}");
                assert_eq!(a.1, b.1, "case {case} kv {kv}");
                assert_eq!(a.2, b.2, "case {case} kv {kv}");
                nm_seen += a.1.n_rows();
                cases += 1;
            }
        }
        // the cases exercise both paths' non-manifold facets
        assert!(
            cases > 600 && nm_seen > 100,
            "{cases} cases, {nm_seen} nm facets"
        );
    }
}
