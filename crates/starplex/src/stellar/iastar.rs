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

use super::relations::{unpack, unpack_facet, FaceKeys};
use super::{ExpandedLeaf, LeafView, StellarTree};
use crate::algo::manifold::triangle_link_test;
use crate::algo::unionfind::find_in;
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

/// Per-leaf pieces of an IA*, in tree numbering.
struct Pieces {
    /// (tree cell, facet, value) with value = tree cell | local nm index | NM.
    slots: Vec<(u32, u32, u32)>,
    nm_cells: Vec<Vec<u32>>,
    nm_verts: Vec<Vec<u32>>,
}

/// [`group_pieces`] from groups in any order: the non-manifold facets are numbered in key
/// order afterwards, so the result is the same.
fn group_pieces_unordered(keys: &mut FaceKeys) -> Pieces {
    let mut p = Pieces {
        slots: Vec::new(),
        nm_cells: Vec::new(),
        nm_verts: Vec::new(),
    };
    let mut nm: Vec<(Vec<u32>, Vec<u64>)> = Vec::new();
    keys.for_each_group_unordered(|key, pays| match pays.len() {
        1 => {}
        2 => {
            let (a, b) = (unpack(pays[0]).0, unpack(pays[1]).0);
            p.slots.push((a, unpack_facet(pays[0]), b));
            p.slots.push((b, unpack_facet(pays[1]), a));
        }
        _ => nm.push((key.to_vec(), pays.to_vec())),
    });
    nm.sort_unstable_by(|a, b| a.0.cmp(&b.0));
    for (key, pays) in nm {
        let id = p.nm_cells.len() as u32 | NM;
        let mut cs: Vec<u32> = pays.iter().map(|&x| unpack(x).0).collect();
        for &x in &pays {
            p.slots.push((unpack(x).0, unpack_facet(x), id));
        }
        cs.sort_unstable();
        cs.dedup();
        p.nm_cells.push(cs);
        p.nm_verts.push(key[1..].to_vec());
    }
    p
}

fn group_pieces(keys: &mut FaceKeys) -> Pieces {
    let mut p = Pieces {
        slots: Vec::new(),
        nm_cells: Vec::new(),
        nm_verts: Vec::new(),
    };
    keys.for_each_group(|key, pays| match pays.len() {
        1 => {}
        2 => {
            let (a, b) = (unpack(pays[0]).0, unpack(pays[1]).0);
            p.slots.push((a, unpack_facet(pays[0]), b));
            p.slots.push((b, unpack_facet(pays[1]), a));
        }
        _ => {
            let id = p.nm_cells.len() as u32 | NM;
            let mut cs: Vec<u32> = pays.iter().map(|&x| unpack(x).0).collect();
            for &x in pays {
                p.slots.push((unpack(x).0, unpack_facet(x), id));
            }
            cs.sort_unstable();
            cs.dedup();
            p.nm_cells.push(cs);
            p.nm_verts.push(key[1..].to_vec());
        }
    });
    p
}

impl StellarTree {
    /// The global IA*, built leaf by leaf in parallel: each facet is examined once, in the leaf
    /// owning its smallest vertex; the cluster representatives of each vertex are found in its
    /// leaf. Same result for any number of threads.
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
        if self.cells.uniform == Some(CellKind::Simplex(2)) {
            return self.iastar_by_stars();
        }
        let nc = self.n_top_cells();
        let pieces: Vec<Pieces> =
            self.par_facet_groups_where(2, false, |_, keys| group_pieces_unordered(keys));
        let (off, adj, nm_cells, nm_verts) = self.scatter_pieces(pieces);
        let stride = if let Some(kind) = self.cells.uniform {
            n_slots(kind)
        } else {
            0
        };
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
                    // per worker: visit stamps over all cells (2 bytes per cell, zeroed
                    // lazily by the allocator)
                    let sc = RepScratch {
                        stamps: vec![0; nc],
                        ..Default::default()
                    };
                    (ExpandedLeaf::default(), sc)
                },
                |(e, sc), l| {
                    self.expand_leaf_into(LeafId(l), e);
                    let view = LeafView { tree: self, e };
                    let mut lens = Vec::with_capacity(view.tree_vertices().len());
                    let mut data = Vec::new();
                    for v in view.tree_vertices() {
                        let s = data.len();
                        self.representatives(&view, v, &slots, &nm_cells, sc, &mut data);
                        lens.push((data.len() - s) as u32);
                    }
                    (lens, data)
                },
            )
            .collect();
        self.global_iastar(off, adj, (nm_cells, nm_verts), per_leaf)
    }

    /// The slot offsets of every cell, the slots filled from the leaves' pieces (leaves in
    /// order: the non-manifold facets are numbered leaf after leaf), and the non-manifold
    /// facets' cells and vertices.
    fn scatter_pieces(&self, pieces: Vec<Pieces>) -> (Vec<u32>, Vec<u32>, Csr, Csr) {
        let nc = self.n_top_cells();
        let mut off = vec![0u32; nc + 1];
        for c in 0..nc {
            off[c + 1] = off[c] + n_slots(self.cells.get(c as u32).0) as u32;
        }
        let mut adj = vec![NONE; off[nc] as usize];
        let mut nm_cells = Csr {
            offsets: vec![0],
            targets: Vec::new(),
        };
        let mut nm_verts = nm_cells.clone();
        for p in pieces {
            let base = nm_cells.n_rows() as u32;
            for (c, j, x) in p.slots {
                let x = if x != NONE && x & NM != 0 {
                    ((x & !NM) + base) | NM
                } else {
                    x
                };
                adj[(off[c as usize] + j) as usize] = x;
            }
            for (cs, vs) in p.nm_cells.iter().zip(&p.nm_verts) {
                nm_cells.targets.extend_from_slice(cs);
                nm_cells.offsets.push(nm_cells.targets.len() as u32);
                nm_verts.targets.extend_from_slice(vs);
                nm_verts.offsets.push(nm_verts.targets.len() as u32);
            }
        }
        (off, adj, nm_cells, nm_verts)
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

    /// [`iastar`](Self::iastar) for a complex of triangles, in one pass over the leaves: for
    /// each vertex `v` of a leaf, the edges through `v` of the triangles of its star are
    /// grouped by their other vertex (a sort of a dozen 8-byte records). Groups of edges whose
    /// smallest vertex is `v` give the adjacency slots (each edge is examined in one leaf, as
    /// in the general path), and every group joins its triangles in the clusters of `v`, so
    /// the representatives come from the same records without walking the slots. The result
    /// is identical to the general path's (`tests/suite/stellar_iastar.rs`). Measured against
    /// the general path, in one process, interleaved: 110-123 ms against 145-158 ms on
    /// tri_armadillo_x16 (one thread); on tetrahedra the same scheme (16-byte records of
    /// two-vertex keys, ~75 per star) was slower than the general path (216-260 ms against
    /// 188-199 ms on tet_armadillo_m), so it is used for triangles only.
    fn iastar_by_stars(&self) -> StellarIaStar<'_> {
        let per_leaf: Vec<(Pieces, LeafRows)> = (0..self.n_leaves() as u32)
            .into_par_iter()
            .map_init(
                || (ExpandedLeaf::default(), StarScratch::default()),
                |(e, sc), l| {
                    self.expand_leaf_into(LeafId(l), e);
                    let view = LeafView { tree: self, e };
                    let mut p = Pieces {
                        slots: Vec::new(),
                        nm_cells: Vec::new(),
                        nm_verts: Vec::new(),
                    };
                    let mut lens = Vec::with_capacity(view.tree_vertices().len());
                    let mut data = Vec::new();
                    for v in view.tree_vertices() {
                        let s = data.len();
                        self.star_edges(v, view.vt_tree(v), sc, &mut p, &mut data);
                        lens.push((data.len() - s) as u32);
                    }
                    (p, (lens, data))
                },
            )
            .collect();
        let (pieces, rows): (Vec<Pieces>, Vec<LeafRows>) = per_leaf.into_iter().unzip();
        let (off, adj, nm_cells, nm_verts) = self.scatter_pieces(pieces);
        self.global_iastar(off, adj, (nm_cells, nm_verts), rows)
    }

    /// One vertex of [`iastar_by_stars`](Self::iastar_by_stars): groups the edges through
    /// tree vertex `v` of the triangles of `star`, appends the slots and non-manifold edges
    /// that `v` owns (its smallest vertex) to `p` and the cluster representatives of `v`
    /// (smallest input id of each cluster, clusters in the order of their first triangle in
    /// `star`, as the general path's flood gives them) to `out`.
    fn star_edges(
        &self,
        v: u32,
        star: &[u32],
        sc: &mut StarScratch,
        p: &mut Pieces,
        out: &mut Vec<u32>,
    ) {
        let StarScratch { recs, uf, best } = sc;
        let verts = &self.cells.verts;
        // record: other vertex << 32 | star index << 3 | slot (the edge omits vertex `slot`);
        // a star of 2^29 triangles would not fit in memory
        recs.clear();
        for (i, &c) in star.iter().enumerate() {
            let vs = &verts[c as usize * 3..c as usize * 3 + 3];
            let pv = vs.iter().position(|&w| w == v).expect("v is in its star");
            for j in 0..3 {
                if j != pv {
                    let w = vs[3 - pv - j] as u64;
                    recs.push((w << 32) | ((i as u64) << 3) | j as u64);
                }
            }
        }
        recs.sort_unstable();
        let at = |r: u64| (((r as u32) >> 3) as usize, r as u32 & 3);
        // the groups join the triangles into the clusters of v (the link test's union-find)
        triangle_link_test(star.len(), recs, uf, |w, group| {
            if w > v && group.len() == 2 {
                let ((ia, ja), (ib, jb)) = (at(group[0]), at(group[1]));
                let (a, b) = (star[ia], star[ib]);
                p.slots.push((a, ja, b));
                p.slots.push((b, jb, a));
            } else if w > v && group.len() > 2 {
                let id = p.nm_cells.len() as u32 | NM;
                let mut cs = Vec::with_capacity(group.len());
                for &r in group {
                    let (i, j) = at(r);
                    p.slots.push((star[i], j, id));
                    cs.push(star[i]);
                }
                cs.sort_unstable();
                cs.dedup();
                p.nm_cells.push(cs);
                p.nm_verts.push(vec![v, w]);
            }
        });
        // each cluster's triangle of smallest input id, in the order of the clusters' first
        // triangles
        best.clear();
        best.resize(star.len(), u32::MAX);
        for (i, &c) in star.iter().enumerate() {
            let r = find_in(uf, i as u32) as usize;
            let b = best[r];
            if b == u32::MAX || self.c_orig[c as usize] < self.c_orig[b as usize] {
                best[r] = c;
            }
        }
        for i in 0..star.len() {
            let r = find_in(uf, i as u32) as usize;
            if best[r] != u32::MAX {
                out.push(best[r]);
                best[r] = u32::MAX;
            }
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
        let RepScratch {
            stack,
            stamps,
            epoch,
            ..
        } = sc;
        *epoch = epoch.wrapping_add(1);
        if *epoch == 0 {
            stamps.iter_mut().for_each(|x| *x = 0);
            *epoch = 1;
        }
        let ep = *epoch;
        self.flood_clusters(v, star, slots_of, nm_cells, stack, out, |c| {
            let fresh = stamps[c as usize] != ep;
            stamps[c as usize] = ep;
            fresh
        });
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
        let p = group_pieces(&mut keys);
        let ncl = e.cells.len();
        let pos = |c: u32| e.cells.binary_search(&c).expect("a leaf cell");
        let mut off = vec![0u32; ncl + 1];
        for (i, &c) in e.cells.iter().enumerate() {
            off[i + 1] = off[i] + n_slots(self.cells.get(c).0) as u32;
        }
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
        for &(c, j, x) in &p.slots {
            adj[(off[pos(c)] + j) as usize] = x;
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

/// Rows of one leaf's vertices, in tree order: their lengths, then their entries end to end.
type LeafRows = (Vec<u32>, Vec<u32>);

/// Scratch of [`StellarTree::star_edges`]: the edge records of one star, a union-find over
/// its triangles and each cluster's best triangle.
#[derive(Default)]
struct StarScratch {
    recs: Vec<u64>,
    uf: Vec<u32>,
    best: Vec<u32>,
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
