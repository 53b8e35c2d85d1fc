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
//! This module defines its own layout; the standalone IA* (in `tds`) may differ.
//!
//! ```
//! # use starplex::complex::{ComplexBuilder, BuildOptions};
//! # use starplex::cell::CellKind;
//! use starplex::stellar::{StellarTree, StellarOptions};
//! use starplex::stellar::iastar::Adjacent;
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
//! assert_eq!(ia.adjacent(CellId(0), 2), Adjacent::NmFace(0)); // facet 2 = edge 01
//! assert_eq!(ia.nm_face_cells(0), &[0, 1, 2]);
//! assert_eq!(ia.vertex_representatives(VertexId(0)), &[0]);
//! assert_eq!(ia.storage_refs(), 26); // the spec's anchor for the book
//! ```
use rayon::prelude::*;
use rustc_hash::FxHashSet;

use super::relations::{unpack, unpack_facet, FaceKeys};
use super::{ExpandedLeaf, LeafView, StellarTree};
use crate::cell::CellKind;
use crate::csr::Csr;
use crate::ids::{CellId, LeafId, VertexId};
use crate::topo::{TopCells, VertexStar};

/// Slot value: no adjacent top cell across this facet.
const NONE: u32 = u32::MAX;
/// Slot value (local IA* only): the facet has no vertex in the leaf, not computed.
const NOT_LOCAL: u32 = u32::MAX - 1;
/// Tag of a non-manifold facet reference.
const NM: u32 = 1 << 31;

/// What lies across one facet of a top cell.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Adjacent {
    /// No other top cell of the same dimension.
    None,
    /// Exactly one other top cell (input id).
    Top(CellId),
    /// A non-manifold facet (three or more top cells); its id in [`IaStar::nm_face_cells`].
    NmFace(u32),
    /// Local IA* only: the facet has no vertex in the leaf, so it was not examined.
    NotComputed,
}

fn decode(x: u32) -> Adjacent {
    match x {
        NONE => Adjacent::None,
        NOT_LOCAL => Adjacent::NotComputed,
        x if x & NM != 0 => Adjacent::NmFace(x & !NM),
        x => Adjacent::Top(CellId(x)),
    }
}

/// An IA* data structure (input numbering). For a local IA*, the cells are those of one leaf
/// and the vertex lists those of the leaf's vertices.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct IaStar {
    n_vertices: usize,
    /// Cells covered (input ids, sorted); all cells for the global IA*.
    cells: Vec<u32>,
    kinds: Vec<CellKind>,
    /// R_{k,0}: vertices of cell `cells[i]` in `cell_verts.row(i)`.
    cell_verts: Csr,
    /// R_{k,k} slots of cell `cells[i]` (empty for dimension < 2).
    adj: Csr,
    /// Non-manifold facets: their top cells (input ids, sorted).
    nm_cells: Csr,
    /// Non-manifold facets: their vertices (input ids, sorted).
    nm_verts: Csr,
    /// Vertices covered (input ids, sorted); all vertices for the global IA*.
    vertices: Vec<u32>,
    /// R_{0,1} + R*_{0,k}: top edges and cluster representatives of `vertices[i]`.
    reps: Csr,
    global: bool,
}

impl IaStar {
    fn cell_pos(&self, c: CellId) -> Option<usize> {
        if self.global {
            (c.index() < self.cells.len()).then_some(c.index())
        } else {
            self.cells.binary_search(&c.0).ok()
        }
    }
    fn vertex_pos(&self, v: VertexId) -> Option<usize> {
        if self.global {
            (v.index() < self.vertices.len()).then_some(v.index())
        } else {
            self.vertices.binary_search(&v.0).ok()
        }
    }
    /// Cells covered (input ids, sorted).
    pub fn cells(&self) -> &[u32] {
        &self.cells
    }
    /// Vertices covered (input ids, sorted).
    pub fn vertices(&self) -> &[u32] {
        &self.vertices
    }
    /// Number of adjacency slots of a covered cell (its facet count for dimension >= 2).
    pub fn n_slots(&self, c: CellId) -> usize {
        self.cell_pos(c).map_or(0, |i| self.adj.degree(i))
    }
    /// What lies across facet `j` of cell `c` (`None` for an uncovered cell or bad slot).
    pub fn adjacent(&self, c: CellId, j: usize) -> Adjacent {
        match self.cell_pos(c) {
            Some(i) => self
                .adj
                .row(i)
                .get(j)
                .map_or(Adjacent::None, |&x| decode(x)),
            None => Adjacent::None,
        }
    }
    /// Number of non-manifold facets.
    pub fn n_nm_faces(&self) -> usize {
        self.nm_cells.n_rows()
    }
    /// Top cells of non-manifold facet `f` (input ids, sorted).
    pub fn nm_face_cells(&self, f: u32) -> &[u32] {
        self.nm_cells.row(f as usize)
    }
    /// Vertices of non-manifold facet `f` (input ids, sorted).
    pub fn nm_face_vertices(&self, f: u32) -> &[u32] {
        self.nm_verts.row(f as usize)
    }
    /// R_{0,1}(v) plus one top k-cell per k-cluster (k >= 2), sorted input ids.
    pub fn vertex_representatives(&self, v: VertexId) -> &[u32] {
        self.vertex_pos(v).map_or(&[], |i| self.reps.row(i))
    }
    /// References stored (the spec's paper-faithful count): R_{k,0} + R_{k,k} slots + the
    /// non-manifold facet lists + R_{0,1} and cluster representatives.
    pub fn storage_refs(&self) -> u64 {
        (self.cell_verts.n_refs() + self.adj.n_refs() + self.nm_cells.n_refs() + self.reps.n_refs())
            as u64
    }
    /// Bytes of the arrays.
    pub fn bytes(&self) -> usize {
        4 * (self.cells.len() + self.vertices.len())
            + self.cell_verts.bytes()
            + self.adj.bytes()
            + self.nm_cells.bytes()
            + self.nm_verts.bytes()
            + self.reps.bytes()
            + 2 * self.kinds.len()
    }

    /// Expands the clusters of `v` through the adjacency slots: the top cells incident to `v`
    /// (needs the cells of the whole star to be covered, true for the global IA* and for the
    /// leaf's own vertices in a local one).
    pub fn star(&self, v: VertexId) -> Vec<CellId> {
        let mut seen: FxHashSet<u32> = FxHashSet::default();
        let mut stack: Vec<u32> = Vec::new();
        for &r in self.vertex_representatives(v) {
            if seen.insert(r) {
                stack.push(r);
            }
        }
        while let Some(c) = stack.pop() {
            let Some(i) = self.cell_pos(CellId(c)) else {
                continue;
            };
            let kind = self.kinds[i];
            let vs = self.cell_verts.row(i);
            let Some(p) = vs.iter().position(|&w| w == v.0) else {
                continue;
            };
            for (j, &x) in self.adj.row(i).iter().enumerate() {
                if !facet_contains(kind, j, p) {
                    continue;
                }
                match decode(x) {
                    Adjacent::Top(u) if seen.insert(u.0) => stack.push(u.0),
                    Adjacent::NmFace(f) => {
                        for &u in self.nm_face_cells(f) {
                            if seen.insert(u) {
                                stack.push(u);
                            }
                        }
                    }
                    _ => {}
                }
            }
        }
        let mut out: Vec<CellId> = seen.into_iter().map(CellId).collect();
        out.sort_unstable();
        out
    }
}

impl TopCells for IaStar {
    fn n_vertices(&self) -> usize {
        self.n_vertices
    }
    fn n_top_cells(&self) -> usize {
        self.cells.len()
    }
    fn top_cell_kind(&self, c: CellId) -> CellKind {
        self.kinds[self.cell_pos(c).expect("a covered cell")]
    }
    fn top_cell_vertices(&self, c: CellId, out: &mut Vec<VertexId>) {
        if let Some(i) = self.cell_pos(c) {
            out.extend(self.cell_verts.row(i).iter().map(|&v| VertexId(v)));
        }
    }
}

impl VertexStar for IaStar {
    fn vertex_top_cells(&self, v: VertexId, out: &mut Vec<CellId>) {
        *out = self.star(v);
    }
}

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
    pub fn iastar(&self) -> IaStar {
        let nc = self.n_top_cells();
        let pieces: Vec<Pieces> =
            self.par_facet_groups_where(2, false, |_, keys| group_pieces(keys));
        // slot offsets in tree numbering
        let mut off = vec![0u32; nc + 1];
        for c in 0..nc {
            off[c + 1] = off[c] + n_slots(self.cells.get(c as u32).0) as u32;
        }
        let mut adj = vec![NONE; off[nc] as usize];
        let mut nm_cells: Vec<Vec<u32>> = Vec::new();
        let mut nm_verts: Vec<Vec<u32>> = Vec::new();
        for p in pieces {
            let base = nm_cells.len() as u32;
            for (c, j, x) in p.slots {
                let x = if x != NONE && x & NM != 0 {
                    ((x & !NM) + base) | NM
                } else {
                    x
                };
                adj[(off[c as usize] + j) as usize] = x;
            }
            nm_cells.extend(p.nm_cells);
            nm_verts.extend(p.nm_verts);
        }
        // representatives, leaf by leaf
        let per_leaf: Vec<Vec<Vec<u32>>> = self.par_map_leaves(|view| {
            view.tree_vertices()
                .map(|v| {
                    self.representatives(
                        view,
                        v,
                        &|c: u32| &adj[off[c as usize] as usize..off[c as usize + 1] as usize],
                        &nm_cells,
                    )
                })
                .collect()
        });
        // convert to input numbering
        let c_orig = &self.c_orig;
        let to_in = |x: u32| -> u32 {
            if x == NONE || x & NM != 0 {
                x
            } else {
                c_orig[x as usize]
            }
        };
        let kinds: Vec<CellKind> = (0..nc).map(|c| self.cells.get(self.c_new[c]).0).collect();
        let cell_verts = Csr::from_fn(nc, |emit| {
            for c in 0..nc {
                for &v in self.cells.verts(self.c_new[c]) {
                    emit(c as u32, self.v_orig[v as usize]);
                }
            }
        });
        let adj_in = Csr::from_fn(nc, |emit| {
            for c in 0..nc {
                let t = self.c_new[c] as usize;
                for &x in &adj[off[t] as usize..off[t + 1] as usize] {
                    emit(c as u32, to_in(x));
                }
            }
        });
        let nm_cells_in = Csr::from_fn(nm_cells.len(), |emit| {
            for (f, cs) in nm_cells.iter().enumerate() {
                let mut v: Vec<u32> = cs.iter().map(|&c| c_orig[c as usize]).collect();
                v.sort_unstable();
                v.into_iter().for_each(|c| emit(f as u32, c));
            }
        });
        let nm_verts_in = Csr::from_fn(nm_verts.len(), |emit| {
            for (f, vs) in nm_verts.iter().enumerate() {
                let mut v: Vec<u32> = vs.iter().map(|&w| self.v_orig[w as usize]).collect();
                v.sort_unstable();
                v.into_iter().for_each(|w| emit(f as u32, w));
            }
        });
        let nv = self.n_vertices();
        let mut rows: Vec<&Vec<u32>> = vec![&EMPTY; nv];
        let mut tv = 0usize;
        for leaf in &per_leaf {
            for r in leaf {
                rows[self.v_orig[tv] as usize] = r;
                tv += 1;
            }
        }
        let reps = Csr::from_fn(nv, |emit| {
            for (v, r) in rows.iter().enumerate() {
                r.iter().for_each(|&c| emit(v as u32, c));
            }
        });
        IaStar {
            n_vertices: nv,
            cells: (0..nc as u32).collect(),
            kinds,
            cell_verts,
            adj: adj_in,
            nm_cells: nm_cells_in,
            nm_verts: nm_verts_in,
            vertices: (0..nv as u32).collect(),
            reps,
            global: true,
        }
    }

    /// Top edges and cluster representatives of tree vertex `v` (input ids, sorted).
    fn representatives<'s>(
        &self,
        view: &LeafView<'_>,
        v: u32,
        slots_of: &dyn Fn(u32) -> &'s [u32],
        nm_cells: &[Vec<u32>],
    ) -> Vec<u32> {
        let star = view.vt_tree(v);
        let mut reps: Vec<u32> = Vec::new();
        // seen[i]: star[i] visited (neighbours through facets containing v are in the star)
        let mut seen = vec![false; star.len()];
        let mark = |seen: &mut Vec<bool>, c: u32| -> bool {
            match star.binary_search(&c) {
                Ok(i) if !seen[i] => {
                    seen[i] = true;
                    true
                }
                _ => false,
            }
        };
        // visit the star in input-id order so the representative is the smallest input id
        let mut order: Vec<u32> = star.to_vec();
        order.sort_unstable_by_key(|&c| self.c_orig[c as usize]);
        let mut stack = Vec::new();
        for &c in &order {
            let kind = self.cells.get(c).0;
            if kind.dim() < 2 {
                if kind.dim() == 1 {
                    reps.push(self.c_orig[c as usize]);
                }
                continue;
            }
            if !mark(&mut seen, c) {
                continue;
            }
            reps.push(self.c_orig[c as usize]);
            stack.push(c);
            while let Some(a) = stack.pop() {
                let (ka, vs) = self.cells.get(a);
                let p = vs.iter().position(|&w| w == v).expect("in the star");
                let slots = slots_of(a);
                for (j, &x) in slots.iter().enumerate() {
                    if x == NONE || x == NOT_LOCAL || !facet_contains(ka, j, p) {
                        continue;
                    }
                    if x & NM != 0 {
                        for &u in &nm_cells[(x & !NM) as usize] {
                            if mark(&mut seen, u) {
                                stack.push(u);
                            }
                        }
                    } else if mark(&mut seen, x) {
                        stack.push(x);
                    }
                }
            }
        }
        reps.sort_unstable();
        reps
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
    /// assert_eq!(ia.vertices(), &[1]);
    /// assert_eq!(ia.star(VertexId(1)).len(), 2);
    /// ```
    pub fn local_iastar(&self, l: LeafId) -> IaStar {
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
            super::relations::oriented_facets_of(kind, |local, _| {
                j += 1;
                key.clear();
                key.extend(local.iter().map(|&i| vs[i as usize]));
                if key.iter().any(|&x| view.owns(x)) {
                    key.sort_unstable();
                    key.insert(0, d as u32);
                    keys.push(&key, super::relations::pack(c, j - 1, 1));
                }
            });
        }
        let p = group_pieces(&mut keys);
        // local cell positions
        let ncl = e.cells.len();
        let pos = |c: u32| e.cells.binary_search(&c).expect("a leaf cell");
        let mut off = vec![0u32; ncl + 1];
        for (i, &c) in e.cells.iter().enumerate() {
            off[i + 1] = off[i] + n_slots(self.cells.get(c).0) as u32;
        }
        let mut adj = vec![NOT_LOCAL; off[ncl] as usize];
        // facets with a leaf vertex and a single cell: NONE
        for (i, &c) in e.cells.iter().enumerate() {
            let (kind, vs) = self.cells.get(c);
            if kind.dim() < 2 {
                continue;
            }
            let mut j = 0usize;
            super::relations::oriented_facets_of(kind, |local, _| {
                if local.iter().any(|&x| view.owns(vs[x as usize])) {
                    adj[off[i] as usize + j] = NONE;
                }
                j += 1;
            });
        }
        for &(c, j, x) in &p.slots {
            adj[(off[pos(c)] + j) as usize] = x;
        }
        // representatives with the local adjacency
        let slots_of = |c: u32| -> &[u32] {
            let i = pos(c);
            &adj[off[i] as usize..off[i + 1] as usize]
        };
        let reps_t: Vec<Vec<u32>> = view
            .tree_vertices()
            .map(|v| self.representatives(&view, v, &slots_of, &p.nm_cells))
            .collect();
        // input numbering, cells sorted by input id
        let mut cells_in: Vec<(u32, usize)> = e
            .cells
            .iter()
            .enumerate()
            .map(|(i, &c)| (self.c_orig[c as usize], i))
            .collect();
        cells_in.sort_unstable();
        let to_in = |x: u32| -> u32 {
            if x == NONE || x == NOT_LOCAL || x & NM != 0 {
                x
            } else {
                self.c_orig[x as usize]
            }
        };
        let kinds = cells_in
            .iter()
            .map(|&(_, i)| self.cells.get(e.cells[i]).0)
            .collect();
        let cell_verts = Csr::from_fn(ncl, |emit| {
            for (r, &(_, i)) in cells_in.iter().enumerate() {
                for &v in self.cells.verts(e.cells[i]) {
                    emit(r as u32, self.v_orig[v as usize]);
                }
            }
        });
        let adj_in = Csr::from_fn(ncl, |emit| {
            for (r, &(_, i)) in cells_in.iter().enumerate() {
                for &x in &adj[off[i] as usize..off[i + 1] as usize] {
                    emit(r as u32, to_in(x));
                }
            }
        });
        let nm_cells_in = Csr::from_fn(p.nm_cells.len(), |emit| {
            for (f, cs) in p.nm_cells.iter().enumerate() {
                let mut v: Vec<u32> = cs.iter().map(|&c| self.c_orig[c as usize]).collect();
                v.sort_unstable();
                v.into_iter().for_each(|c| emit(f as u32, c));
            }
        });
        let nm_verts_in = Csr::from_fn(p.nm_verts.len(), |emit| {
            for (f, vs) in p.nm_verts.iter().enumerate() {
                let mut v: Vec<u32> = vs.iter().map(|&w| self.v_orig[w as usize]).collect();
                v.sort_unstable();
                v.into_iter().for_each(|w| emit(f as u32, w));
            }
        });
        let mut verts_in: Vec<(u32, usize)> = view
            .tree_vertices()
            .enumerate()
            .map(|(i, v)| (self.v_orig[v as usize], i))
            .collect();
        verts_in.sort_unstable();
        let reps = Csr::from_fn(verts_in.len(), |emit| {
            for (r, &(_, i)) in verts_in.iter().enumerate() {
                reps_t[i].iter().for_each(|&c| emit(r as u32, c));
            }
        });
        IaStar {
            n_vertices: self.n_vertices(),
            cells: cells_in.iter().map(|x| x.0).collect(),
            kinds,
            cell_verts,
            adj: adj_in,
            nm_cells: nm_cells_in,
            nm_verts: nm_verts_in,
            vertices: verts_in.iter().map(|x| x.0).collect(),
            reps,
            global: false,
        }
    }

    /// Builds the local IA* of every leaf in parallel and returns the total of their
    /// reference counts (the local approach: each is discarded after use by `f`).
    pub fn par_local_iastar<R: Send>(&self, f: impl Fn(&IaStar) -> R + Sync + Send) -> Vec<R> {
        (0..self.n_leaves() as u32)
            .into_par_iter()
            .map(|l| f(&self.local_iastar(LeafId(l))))
            .collect()
    }
}

static EMPTY: Vec<u32> = Vec::new();
