//! Relations extracted leaf by leaf, answered in the input's numbering: VT (R_{0,top}), VV,
//! vertex links, boundary p-faces of every dimension (simplices and CP cells), and top-cell
//! adjacency across (d-1)-faces; plus the [`topo`](crate::topo) traits.
//!
//! Every face is handled in exactly one leaf: the leaf owning its smallest vertex (tree
//! numbering), which lists every top cell containing the face, so multiplicities are exact.
//!
//! Files: this one holds the vertex relations (VT, VV, links) and the `topo` traits;
//! `face_keys.rs` sorts and groups the faces met in a leaf; `faces.rs` extracts p-faces and
//! top adjacency from those groups.
//!
//! ```
//! # use starplex::complex::{ComplexBuilder, BuildOptions};
//! # use starplex::cell::CellKind;
//! use starplex::stellar::{StellarTree, StellarOptions};
//! # let mut b = ComplexBuilder::new(2).unwrap();
//! # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
//! # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
//! # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
//! # let k = b.build(&BuildOptions::default()).unwrap().0;
//! let t = StellarTree::build(&k, &StellarOptions { kv: Some(1), ..Default::default() }).unwrap();
//! assert_eq!(t.vt_all().row(1), &[0, 1]);
//! assert_eq!(t.vv_all().row(0), &[1, 2]);
//! let edges = t.p_faces(1).unwrap();
//! assert_eq!(edges.len(), 5);
//! assert_eq!(t.top_adjacency().row(0), &[1]);
//! ```
use rayon::prelude::*;

use super::{LeafView, StellarError, StellarTree};
use crate::cell::CellKind;
use crate::csr::Csr;
use crate::ids::{CellId, LeafId, TreeVertexId, VertexId};
use crate::limits::Limits;
use crate::topo::link::{LinkError, VertexLink};
use crate::topo::naive::edge_neighbours;
use crate::topo::sortnet::sort_in_capacity;
use crate::topo::{TopCells, VertexAdjacency, VertexStar};

mod face_keys;
mod faces;

pub(crate) use face_keys::{face_width, FaceKeys};
pub(crate) use faces::{pack, unpack, unpack_facet};
pub use faces::{FaceList, FACE_BUDGET};

/// Reusable buffers of [`StellarTree::leaf_vt_rows`].
#[derive(Default)]
struct VtRows {
    cells: Vec<u32>,
    off: Vec<u32>,
    rows: Vec<u32>,
}

impl StellarTree {
    /// Distinct kinds of the top cells.
    pub(crate) fn kinds(&self) -> Vec<CellKind> {
        if let Some(kind) = self.cells.uniform {
            return if self.cells.n > 0 { vec![kind] } else { vec![] };
        }
        let mut seen = [false; 256];
        for &c in &self.cells.kinds {
            seen[c as usize] = true;
        }
        (0..=255u8)
            .filter(|&c| seen[c as usize])
            .map(crate::stellar::code_kind)
            .collect()
    }

    /// Rows of per-leaf results (rows of the leaf's vertices in tree order) reassembled into a
    /// [`Csr`] keyed by input vertex. The rows are first laid end to end in tree order, then
    /// read in input order: the answer is written front to back and the random accesses are
    /// reads, which overlap, not stores, which miss the cache one by one (see `csr::scatter`).
    /// A small gain on the whole of `vt_all` (medians 39 → 37 ms on tri_armadillo_x16, 41 → 40
    /// ms on tet_armadillo_m, one thread, at load 4): the leaf rows, not this, dominate it.
    fn gather_vertex_rows(&self, per_leaf: Vec<(Vec<u32>, Vec<u32>)>) -> Csr {
        let nv = self.n_vertices();
        let total: usize = per_leaf.iter().map(|(_, data)| data.len()).sum();
        let mut start = Vec::with_capacity(nv + 1);
        let mut rows = Vec::with_capacity(total);
        for (lens, data) in per_leaf {
            let mut at = rows.len() as u32;
            for len in lens {
                start.push(at);
                at += len;
            }
            rows.extend_from_slice(&data);
        }
        start.push(rows.len() as u32);
        let mut offsets = Vec::with_capacity(nv + 1);
        offsets.push(0u32);
        let mut targets = Vec::with_capacity(total);
        for &tv in &self.v_new {
            let tv = tv as usize;
            targets.extend_from_slice(&rows[start[tv] as usize..start[tv + 1] as usize]);
            offsets.push(targets.len() as u32);
        }
        Csr { offsets, targets }
    }

    /// Calls `f(v, cells)` for every tree vertex `v` of leaf `l`, cells = VT(v) in input ids,
    /// sorted. The rows are bucketed straight in input ids (`buf` holds the decoded cells and
    /// the rows), in one pass into rows of a fixed capacity when they fit, else by the
    /// counting sort; each is made of a few increasing runs (cells are reindexed by leaf
    /// tuple, input order inside), sorted then.
    fn leaf_vt_rows(&self, l: LeafId, buf: &mut VtRows, mut f: impl FnMut(u32, &[u32])) {
        let r = self.leaf_vertices(l);
        buf.cells.clear();
        crate::stellar::sre::decode(self.leaf_encoded_cells(l), &mut buf.cells);
        let c_orig = &self.c_orig;
        let nloc = r.len();
        if let Some(shift) = self.fixed_row_shift(nloc, buf.cells.len())
            && self.bucket_refs_fixed(
                r.clone(),
                &buf.cells,
                |c| c_orig[c as usize],
                shift,
                &mut buf.off,
                &mut buf.rows,
            )
        {
            for (i, v) in r.enumerate() {
                let (at, n) = (i << shift, buf.off[i] as usize);
                // the row's capacity (at least 16) holds the padding of the short sorts
                sort_in_capacity(&mut buf.rows[at..(i + 1) << shift], n, u32::MAX);
                f(v, &buf.rows[at..at + n]);
            }
            return;
        }
        self.bucket_refs(
            r.start,
            r.end,
            &buf.cells,
            |c| c_orig[c as usize],
            &mut buf.off,
            &mut buf.rows,
        );
        for (i, v) in r.enumerate() {
            let row = &mut buf.rows[buf.off[i] as usize..buf.off[i + 1] as usize];
            // a few increasing runs, a few to a few dozen cells: the library's small-sort
            // network beats an insertion sort (16.0 vs 18.7 ms for tet_armadillo_m's rows)
            row.sort_unstable();
            f(v, row);
        }
    }

    /// R_{0,top} of every vertex: row `v` (input id) holds the input ids of the top cells
    /// incident to `v`, sorted. Computed leaf by leaf in parallel.
    ///
    /// ```
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// # use starplex::ids::{CellId, VertexId};
    /// # use starplex::stellar::{StellarTree, StellarOptions};
    /// # let mut b = ComplexBuilder::new(2).unwrap();
    /// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
    /// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
    /// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// # let t = StellarTree::build(&k, &StellarOptions { kv: Some(1), ..Default::default() }).unwrap();
    /// assert_eq!(t.vt_all().row(2), &[0, 1]);
    /// ```
    pub fn vt_all(&self) -> Csr {
        let per_leaf: Vec<(Vec<u32>, Vec<u32>)> = (0..self.n_leaves() as u32)
            .into_par_iter()
            .map_init(VtRows::default, |buf, l| {
                let mut lens = Vec::with_capacity(self.leaf_vertices(LeafId(l)).len());
                let mut data = Vec::new();
                self.leaf_vt_rows(LeafId(l), buf, |_, row| {
                    lens.push(row.len() as u32);
                    data.extend_from_slice(row);
                });
                (lens, data)
            })
            .collect();
        self.gather_vertex_rows(per_leaf)
    }

    /// Visits R_{0,top} of every vertex, leaf by leaf in parallel: `f(v, cells)` with input
    /// ids, cells sorted. Nothing global is materialised.
    ///
    /// ```
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// # use starplex::ids::{CellId, VertexId};
    /// # use starplex::stellar::{StellarTree, StellarOptions};
    /// # let mut b = ComplexBuilder::new(2).unwrap();
    /// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
    /// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
    /// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// # let t = StellarTree::build(&k, &StellarOptions { kv: Some(1), ..Default::default() }).unwrap();
    /// let total = std::sync::atomic::AtomicUsize::new(0);
    /// t.par_for_each_vt(|_, cells| { total.fetch_add(cells.len(), std::sync::atomic::Ordering::Relaxed); });
    /// assert_eq!(total.into_inner(), 6);
    /// ```
    pub fn par_for_each_vt(&self, f: impl Fn(VertexId, &[CellId]) + Sync + Send) {
        (0..self.n_leaves() as u32)
            .into_par_iter()
            .for_each_init(VtRows::default, |buf, l| {
                self.leaf_vt_rows(LeafId(l), buf, |v, row| {
                    f(VertexId(self.v_orig[v as usize]), bytemuck::cast_slice(row))
                });
            });
    }

    /// R_{0,0} of every vertex: row `v` holds the input ids of the vertices joined to `v` by an
    /// edge (of a top cell's face table), sorted.
    ///
    /// ```
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// # use starplex::ids::{CellId, VertexId};
    /// # use starplex::stellar::{StellarTree, StellarOptions};
    /// # let mut b = ComplexBuilder::new(2).unwrap();
    /// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
    /// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
    /// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// # let t = StellarTree::build(&k, &StellarOptions { kv: Some(1), ..Default::default() }).unwrap();
    /// assert_eq!(t.vv_all().row(1), &[0, 2, 3]);
    /// ```
    pub fn vv_all(&self) -> Csr {
        let per_leaf: Vec<(Vec<u32>, Vec<u32>)> = self.par_map_leaves(|view| {
            let mut lens = Vec::new();
            let mut data = Vec::new();
            let mut row = Vec::new();
            for v in view.tree_vertices() {
                self.vv_row(view, v, &mut row);
                lens.push(row.len() as u32);
                data.extend_from_slice(&row);
            }
            (lens, data)
        });
        self.gather_vertex_rows(per_leaf)
    }

    fn vv_row(&self, view: &LeafView<'_>, v: u32, row: &mut Vec<u32>) {
        row.clear();
        for &c in view.vt_tree(v) {
            let (kind, vs) = view.cell(c);
            edge_neighbours(kind, vs, v, |w| row.push(self.v_orig[w as usize]));
        }
        row.sort_unstable();
        row.dedup();
    }

    /// Groups input vertices by leaf and calls `f(view, tree vertex, position in vs)` with each
    /// leaf expanded once.
    fn for_given_vertices(
        &self,
        vs: &[VertexId],
        mut f: impl FnMut(&LeafView<'_>, u32, usize),
    ) -> Result<(), StellarError> {
        let mut items: Vec<(u32, u32, usize)> = Vec::with_capacity(vs.len());
        for (i, &v) in vs.iter().enumerate() {
            let tv = self.tree_vertex(v)?;
            items.push((self.leaf_of_tree_vertex(TreeVertexId(tv)).0, tv, i));
        }
        items.sort_unstable();
        let mut e = crate::stellar::ExpandedLeaf::default();
        let mut cur = u32::MAX;
        for (l, tv, i) in items {
            if l != cur {
                self.expand_leaf_into(LeafId(l), &mut e);
                cur = l;
            }
            f(&LeafView { tree: self, e: &e }, tv, i);
        }
        Ok(())
    }

    /// VT of the given input vertices (each leaf expanded once).
    ///
    /// # Errors
    /// A vertex out of range.
    ///
    /// ```
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// # use starplex::ids::{CellId, VertexId};
    /// # use starplex::stellar::{StellarTree, StellarOptions};
    /// # let mut b = ComplexBuilder::new(2).unwrap();
    /// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
    /// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
    /// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// # let t = StellarTree::build(&k, &StellarOptions { kv: Some(1), ..Default::default() }).unwrap();
    /// assert_eq!(t.vt_of(&[VertexId(3)]).unwrap(), vec![vec![CellId(1)]]);
    /// assert!(t.vt_of(&[VertexId(9)]).is_err());
    /// ```
    pub fn vt_of(&self, vs: &[VertexId]) -> Result<Vec<Vec<CellId>>, StellarError> {
        let mut out = vec![Vec::new(); vs.len()];
        self.for_given_vertices(vs, |view, tv, i| {
            let mut r: Vec<CellId> = view
                .vt_tree(tv)
                .iter()
                .map(|&c| CellId(self.c_orig[c as usize]))
                .collect();
            r.sort_unstable();
            out[i] = r;
        })?;
        Ok(out)
    }

    /// VV of the given input vertices.
    ///
    /// # Errors
    /// A vertex out of range.
    ///
    /// ```
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// # use starplex::ids::{CellId, VertexId};
    /// # use starplex::stellar::{StellarTree, StellarOptions};
    /// # let mut b = ComplexBuilder::new(2).unwrap();
    /// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
    /// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
    /// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// # let t = StellarTree::build(&k, &StellarOptions { kv: Some(1), ..Default::default() }).unwrap();
    /// assert_eq!(t.vv_of(&[VertexId(3)]).unwrap(), vec![vec![VertexId(1), VertexId(2)]]);
    /// ```
    pub fn vv_of(&self, vs: &[VertexId]) -> Result<Vec<Vec<VertexId>>, StellarError> {
        let mut out = vec![Vec::new(); vs.len()];
        let mut row = Vec::new();
        self.for_given_vertices(vs, |view, tv, i| {
            self.vv_row(view, tv, &mut row);
            out[i] = row.iter().map(|&w| VertexId(w)).collect();
        })?;
        Ok(out)
    }

    /// Links of the given input vertices (maximal simplices in input ids and f-vector), with a
    /// budget of 50 million link faces per vertex.
    ///
    /// # Errors
    /// A vertex out of range (the outer error); per vertex, a non-simplicial star or a link
    /// over the budget.
    ///
    /// ```
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// # use starplex::ids::{CellId, VertexId};
    /// # use starplex::stellar::{StellarTree, StellarOptions};
    /// # let mut b = ComplexBuilder::new(2).unwrap();
    /// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
    /// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
    /// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// # let t = StellarTree::build(&k, &StellarOptions { kv: Some(1), ..Default::default() }).unwrap();
    /// let l = t.links_of(&[VertexId(0)]).unwrap();
    /// assert_eq!(l[0].as_ref().unwrap().maximal_simplices, vec![vec![1, 2]]);
    /// ```
    pub fn links_of(
        &self,
        vs: &[VertexId],
    ) -> Result<Vec<Result<VertexLink, LinkError>>, StellarError> {
        let mut out: Vec<Option<Result<VertexLink, LinkError>>> = vec![None; vs.len()];
        self.for_given_vertices(vs, |view, tv, i| {
            out[i] = Some(self.link_in_leaf(view, tv, 50_000_000));
        })?;
        Ok(out
            .into_iter()
            .map(|x| x.expect("every vertex visited"))
            .collect())
    }

    /// Link f-vectors of every vertex, leaf by leaf in parallel; entry `v` (input id) is the
    /// f-vector or why it could not be computed (a link over `limits.query_simplices`
    /// simplices is refused).
    ///
    /// ```
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// # use starplex::ids::{CellId, VertexId};
    /// # use starplex::stellar::{StellarTree, StellarOptions};
    /// # let mut b = ComplexBuilder::new(2).unwrap();
    /// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
    /// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
    /// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// # let t = StellarTree::build(&k, &StellarOptions { kv: Some(1), ..Default::default() }).unwrap();
    /// let f = t.link_f_vectors_all(&starplex::limits::Limits::default());
    /// assert_eq!(f[1].as_ref().unwrap(), &vec![3, 2]);
    /// ```
    pub fn link_f_vectors_all(&self, limits: &Limits) -> Vec<Result<Vec<u64>, LinkError>> {
        let budget = limits.query_simplices;
        let per_leaf: Vec<Vec<Result<Vec<u64>, LinkError>>> = self.par_map_leaves(|view| {
            view.tree_vertices()
                .map(|v| self.link_in_leaf(view, v, budget).map(|l| l.f_vector))
                .collect()
        });
        let mut out: Vec<Option<Result<Vec<u64>, LinkError>>> = vec![None; self.n_vertices()];
        let mut tv = 0usize;
        for leaf in per_leaf {
            for r in leaf {
                out[self.v_orig[tv] as usize] = Some(r);
                tv += 1;
            }
        }
        out.into_iter().map(|x| x.expect("all vertices")).collect()
    }

    fn link_in_leaf(
        &self,
        view: &LeafView<'_>,
        tv: u32,
        budget: u128,
    ) -> Result<VertexLink, LinkError> {
        let vin = self.v_orig[tv as usize];
        let mut maximal: Vec<Vec<u32>> = Vec::new();
        for &c in view.vt_tree(tv) {
            let (kind, vs) = view.cell(c);
            if !kind.is_simplex() {
                return Err(LinkError::NotSimplicial(vin));
            }
            let mut m: Vec<u32> = vs
                .iter()
                .filter(|&&w| w != tv)
                .map(|&w| self.v_orig[w as usize])
                .collect();
            m.sort_unstable();
            maximal.push(m);
        }
        crate::topo::link::link_from_maximal(vin, maximal, budget)
    }
}

impl TopCells for StellarTree {
    fn n_vertices(&self) -> usize {
        self.v_orig.len()
    }
    fn n_top_cells(&self) -> usize {
        self.c_orig.len()
    }
    fn top_cell_kind(&self, c: CellId) -> CellKind {
        self.cells.get(self.c_new[c.index()]).0
    }
    fn top_cell_vertices(&self, c: CellId, out: &mut Vec<VertexId>) {
        let (_, vs) = self.cells.get(self.c_new[c.index()]);
        out.extend(vs.iter().map(|&v| VertexId(self.v_orig[v as usize])));
    }
}

impl VertexStar for StellarTree {
    fn vertex_top_cells(&self, v: VertexId, out: &mut Vec<CellId>) {
        out.clear();
        let Ok(tv) = self.tree_vertex(v) else {
            return;
        };
        let l = self.leaf_of_tree_vertex(TreeVertexId(tv));
        for c in crate::stellar::sre::SreIter::new(self.leaf_encoded_cells(l)) {
            if self.cells.verts(c).contains(&tv) {
                out.push(CellId(self.c_orig[c as usize]));
            }
        }
        out.sort_unstable();
    }

    /// [`vt_all`](StellarTree::vt_all): every leaf decoded once.
    fn vertex_top_rows(&self) -> Option<Csr> {
        Some(self.vt_all())
    }

    /// One scan of the leaf of `s[0]` (tree ids, no sort, no mapping back), for complexes of
    /// one simplex kind; `None` otherwise (a CP cell holding the vertices of `s` need not have
    /// `s` as a face).
    fn star_has_top_containing(&self, s: &[VertexId]) -> Option<bool> {
        if !self.cells.uniform.is_some_and(|k| k.is_simplex()) {
            return None;
        }
        let mut tv: smallvec::SmallVec<[u32; 8]> = smallvec::SmallVec::new();
        for &v in s {
            tv.push(self.tree_vertex(v).ok()?);
        }
        let l = self.leaf_of_tree_vertex(TreeVertexId(*tv.first()?));
        for c in crate::stellar::sre::SreIter::new(self.leaf_encoded_cells(l)) {
            let vs = self.cells.verts(c);
            if tv.iter().all(|x| vs.contains(x)) {
                return Some(true);
            }
        }
        Some(false)
    }
}

impl VertexAdjacency for StellarTree {
    fn vertex_neighbours(&self, v: VertexId, out: &mut Vec<VertexId>) {
        out.clear();
        let Ok(tv) = self.tree_vertex(v) else {
            return;
        };
        let l = self.leaf_of_tree_vertex(TreeVertexId(tv));
        for c in crate::stellar::sre::SreIter::new(self.leaf_encoded_cells(l)) {
            let (kind, vs) = self.cells.get(c);
            if vs.contains(&tv) {
                edge_neighbours(kind, vs, tv, |w| {
                    out.push(VertexId(self.v_orig[w as usize]))
                });
            }
        }
        out.sort_unstable();
        out.dedup();
    }

    /// [`vv_all`](StellarTree::vv_all): every leaf decoded once.
    fn vertex_neighbour_rows(&self) -> Option<Csr> {
        Some(self.vv_all())
    }
}
