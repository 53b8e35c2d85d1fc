//! The processing paradigm: visit the leaves one by one (or in parallel), each expanded into
//! an [`ExpandedLeaf`] — its decoded top-cell list and the local vertex → top cells relation —
//! read through a [`LeafView`]. An LRU cache ([`LeafCache`]) keeps recently expanded leaves
//! for algorithms that look into neighbouring leaves.
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
//! let t = StellarTree::build(&k, &StellarOptions { kv: Some(2), ..Default::default() }).unwrap();
//! // sum of |VT(v)| over all vertices, one leaf at a time, in parallel
//! use starplex::topo::LocalStar;
//! let per_leaf: Vec<usize> = t.par_map_leaves(|leaf| {
//!     leaf.owned_vertices().map(|v| leaf.local_star(v).len()).sum()
//! });
//! assert_eq!(per_leaf.iter().sum::<usize>(), 6);
//! ```
use std::sync::Arc;

use rayon::prelude::*;

use super::sre;
use super::StellarTree;
use crate::cell::CellKind;
use crate::ids::{CellId, LeafId, TreeCellId, TreeVertexId, VertexId};
use crate::topo::LocalStar;

/// A leaf expanded for processing: its cells and its local VT relation, in tree numbering.
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
/// use starplex::ids::{TreeCellId, TreeVertexId, VertexId};
/// let e = t.expand_leaf(t.leaf_of_vertex(VertexId(1)).unwrap());
/// let v: TreeVertexId = t.vertex_from_input()[1];
/// assert_eq!(e.vertices().collect::<Vec<_>>(), [v]); // k_V = 1
/// assert_eq!(e.cells(), [TreeCellId(0), TreeCellId(1)]); // vertex 1 is in both triangles
/// assert_eq!(e.vt(v), [TreeCellId(0), TreeCellId(1)]);
/// assert_eq!(e.n_vt_refs(), 2);
/// ```
#[derive(Clone, Debug, Default)]
pub struct ExpandedLeaf {
    /// The leaf.
    pub leaf: LeafId,
    /// First tree vertex of the leaf (raw; typed: [`ExpandedLeaf::vertices`]).
    pub(crate) v_start: u32,
    /// One past the last tree vertex.
    pub(crate) v_end: u32,
    /// Top cells of the leaf (tree ids, increasing; typed: [`ExpandedLeaf::cells`]).
    pub(crate) cells: Vec<u32>,
    /// `vt_off[i]..vt_off[i+1]` in `vt` are the cells of vertex `v_start + i`.
    pub(crate) vt_off: Vec<u32>,
    /// Tree cell ids, increasing within each vertex (typed: [`ExpandedLeaf::vt`]).
    pub(crate) vt: Vec<u32>,
    /// Scratch of the expansion (rows of a fixed capacity and their lengths); not part of
    /// the value.
    scratch: (Vec<u32>, Vec<u32>),
}

/// The most references the fixed-capacity rows of one leaf may take (4 MiB).
const FIXED_ROWS_MAX: usize = 1 << 20;

impl PartialEq for ExpandedLeaf {
    fn eq(&self, o: &Self) -> bool {
        (self.leaf, self.v_start, self.v_end) == (o.leaf, o.v_start, o.v_end)
            && (&self.cells, &self.vt_off, &self.vt) == (&o.cells, &o.vt_off, &o.vt)
    }
}

impl Eq for ExpandedLeaf {}

impl ExpandedLeaf {
    /// The leaf's vertices (tree numbering, consecutive).
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
    /// let e = t.expand_leaf(LeafId(0));
    /// assert_eq!(e.vertices().count(), 1); // k_V = 1
    /// assert!(e.vertices().all(|v| e.owns(v)));
    /// ```
    pub fn vertices(&self) -> impl ExactSizeIterator<Item = TreeVertexId> {
        (self.v_start..self.v_end).map(TreeVertexId)
    }

    /// True when tree vertex `v` belongs to the leaf.
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
    /// let e = t.expand_leaf(LeafId(0));
    /// assert!(e.owns(TreeVertexId(0)) && !e.owns(TreeVertexId(1)));
    /// ```
    #[inline]
    pub fn owns(&self, v: TreeVertexId) -> bool {
        v.0 >= self.v_start && v.0 < self.v_end
    }

    /// The top cells of the leaf: every top cell incident to one of its vertices (tree ids,
    /// increasing).
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
    /// let e = t.expand_leaf(t.leaf_of_vertex(VertexId(0)).unwrap());
    /// assert_eq!(e.cells().len(), 1); // vertex 0 is in one triangle
    /// ```
    #[inline]
    pub fn cells(&self) -> &[TreeCellId] {
        bytemuck::cast_slice(&self.cells)
    }

    /// The top cells (tree ids, increasing) incident to vertex `v` of the leaf; empty when the
    /// leaf does not own `v`.
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
    /// let v = t.vertex_from_input()[2];
    /// let e = t.expand_leaf(t.leaf_of_vertex(VertexId(2)).unwrap());
    /// assert_eq!(e.vt(v).len(), 2); // vertex 2 is in both triangles
    /// assert!(e.vt(t.vertex_from_input()[0]).is_empty()); // not this leaf's
    /// ```
    #[inline]
    pub fn vt(&self, v: TreeVertexId) -> &[TreeCellId] {
        if !self.owns(v) {
            return &[];
        }
        let i = (v.0 - self.v_start) as usize;
        bytemuck::cast_slice(&self.vt[self.vt_off[i] as usize..self.vt_off[i + 1] as usize])
    }

    /// (vertex, top cell) references of the local VT relation: the sum of `vt(v).len()` over the
    /// leaf's vertices.
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
    /// let n: usize = t.par_map_leaves(|l| l.e.n_vt_refs()).iter().sum();
    /// assert_eq!(n, 6); // 3 + 3 vertex-triangle incidences
    /// ```
    #[inline]
    pub fn n_vt_refs(&self) -> usize {
        self.vt.len()
    }

    /// Bytes used.
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
    /// use starplex::stellar::ExpandedLeaf;
    /// assert_eq!(ExpandedLeaf::default().bytes(), 0);
    /// let e = t.expand_leaf(t.leaf_of_vertex(VertexId(1)).unwrap());
    /// assert_eq!(e.bytes(), 4 * (2 + 2 + 2)); // cells, vt_off, vt
    /// ```
    pub fn bytes(&self) -> usize {
        4 * (self.cells.len() + self.vt_off.len() + self.vt.len())
    }
}

impl StellarTree {
    /// Expands leaf `l` into `out` (reusing its buffers). For one cell kind the references
    /// go in one pass into rows of a fixed capacity, then are packed (10-15 % faster than
    /// the counting sort on tri_armadillo_x16 and tet_armadillo_m); a row that overflows
    /// falls back to the counting sort.
    ///
    /// ```
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// use starplex::stellar::{StellarTree, StellarOptions, ExpandedLeaf};
    /// use starplex::ids::LeafId;
    /// # let mut b = ComplexBuilder::new(1).unwrap();
    /// # for x in 0..3 { b.push_vertex(&[x as f64]).unwrap(); }
    /// # b.push_cell(CellKind::Simplex(1), &[0, 1]).unwrap();
    /// # b.push_cell(CellKind::Simplex(1), &[1, 2]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// let t = StellarTree::build(&k, &StellarOptions { kv: Some(0), ..Default::default() }).unwrap();
    /// let mut e = ExpandedLeaf::default();
    /// t.expand_leaf_into(LeafId(0), &mut e);
    /// assert_eq!(e.cells().len(), 2);
    /// assert_eq!(e.vertices().len(), 3);
    /// ```
    pub fn expand_leaf_into(&self, l: LeafId, out: &mut ExpandedLeaf) {
        let r = self.leaf_vertices(l);
        out.leaf = l;
        out.v_start = r.start;
        out.v_end = r.end;
        out.cells.clear();
        sre::decode(self.leaf_encoded_cells(l), &mut out.cells);
        let cells = &out.cells;
        let nloc = r.len();
        let (counts, rows) = &mut out.scratch;
        if let Some(shift) = self.fixed_row_shift(nloc, cells.len())
            && self.bucket_refs_fixed(r.clone(), cells, |c| c, shift, counts, rows)
        {
            // pack the rows, by copies of 8 references (the buffer has 8 of slack)
            let total: usize = counts[..nloc].iter().map(|&n| n as usize).sum();
            let (off, vt) = (&mut out.vt_off, &mut out.vt);
            off.clear();
            off.reserve(nloc + 1);
            vt.clear();
            vt.resize(total + 8, 0);
            let mut o = 0usize;
            off.push(0);
            for (i, &n) in counts[..nloc].iter().enumerate() {
                let src = &rows[i << shift..(i + 1) << shift];
                let n = n as usize;
                let mut j = 0;
                while j < n {
                    vt[o + j..o + j + 8].copy_from_slice(&src[j..j + 8]);
                    j += 8;
                }
                o += n;
                off.push(o as u32);
            }
            vt.truncate(total);
            return;
        }
        self.bucket_refs(r.start, r.end, cells, |c| c, &mut out.vt_off, &mut out.vt);
    }

    /// Counting sort of the references of `cells` to the vertices `vs..ve` by vertex: row
    /// `i` of (`off`, `rows`) holds `val(c)` for the cells `c` of `cells` (in their order) that
    /// have vertex `vs + i`. Branch-free: references to other vertices go to a spill row
    /// that is cut off at the end.
    #[inline]
    pub(crate) fn bucket_refs(
        &self,
        vs: u32,
        ve: u32,
        cells: &[u32],
        val: impl Fn(u32) -> u32,
        off: &mut Vec<u32>,
        rows: &mut Vec<u32>,
    ) {
        let nloc = (ve - vs) as usize;
        let spill = nloc as u32;
        let slot = |v: u32| v.wrapping_sub(vs).min(spill) as usize;
        off.clear();
        off.resize(nloc + 2, 0);
        let offs = &mut off[..];
        let st = &self.cells;
        if st.uniform.is_some() {
            let k = st.stride as usize;
            for &c in cells {
                let i = c as usize * k;
                for &v in &st.verts[i..i + k] {
                    offs[slot(v) + 1] += 1;
                }
            }
        } else {
            for &c in cells {
                for &v in st.verts(c) {
                    offs[slot(v) + 1] += 1;
                }
            }
        }
        for i in 0..=nloc {
            offs[i + 1] += offs[i];
        }
        let total = offs[nloc] as usize;
        // every slot below the spill row's end is written once below: no need to zero the
        // part of the buffer that is reused
        let need = offs[nloc + 1] as usize;
        if rows.len() < need {
            rows.resize(need, 0);
        } else {
            rows.truncate(need);
        }
        let out = &mut rows[..];
        // fill using off as cursors (shifted), then restore
        if st.uniform.is_some() {
            let k = st.stride as usize;
            for &c in cells {
                let x = val(c);
                let i = c as usize * k;
                for &v in &st.verts[i..i + k] {
                    let s = slot(v);
                    out[offs[s] as usize] = x;
                    offs[s] += 1;
                }
            }
        } else {
            for &c in cells {
                let x = val(c);
                for &v in st.verts(c) {
                    let s = slot(v);
                    out[offs[s] as usize] = x;
                    offs[s] += 1;
                }
            }
        }
        rows.truncate(total);
        off.truncate(nloc + 1);
        for i in (1..=nloc).rev() {
            off[i] = off[i - 1];
        }
        off[0] = 0;
    }

    /// The row capacity (as a shift) for [`bucket_refs_fixed`](Self::bucket_refs_fixed) on
    /// a leaf of `nloc` vertices and `n_cells` cells of one kind: a power of two of at least
    /// four times the mean references per vertex (spilled ones included), at least 16.
    /// `None` for several kinds, and for a leaf whose rows would take more than
    /// [`FIXED_ROWS_MAX`] references (a huge leaf, say one leaf for the whole complex: the
    /// counting sort's packed rows are smaller and the one pass would not stay in cache).
    #[inline]
    pub(crate) fn fixed_row_shift(&self, nloc: usize, n_cells: usize) -> Option<u32> {
        self.cells.uniform?;
        let mean = (n_cells.checked_mul(self.cells.stride as usize)?).div_ceil(nloc.max(1));
        let shift = mean
            .checked_mul(4)?
            .checked_next_power_of_two()?
            .max(16)
            .trailing_zeros();
        let len = (nloc + 1).checked_mul(1usize.checked_shl(shift)?)?;
        (len <= FIXED_ROWS_MAX).then_some(shift)
    }

    /// [`bucket_refs`](Self::bucket_refs) for one cell kind in one pass: row `i` is
    /// `rows[i << shift..(i << shift) + counts[i]]`, of capacity `1 << shift`. The rows are
    /// not packed, so no counting pass is needed. False when a row overflows (then the
    /// buffers hold nothing useful).
    #[inline]
    pub(crate) fn bucket_refs_fixed(
        &self,
        r: std::ops::Range<u32>,
        cells: &[u32],
        val: impl Fn(u32) -> u32,
        shift: u32,
        counts: &mut Vec<u32>,
        rows: &mut Vec<u32>,
    ) -> bool {
        let st = &self.cells;
        let k = st.stride as usize;
        let (vs, nloc) = (r.start, r.len());
        let spill = nloc as u32;
        let cap = 1usize << shift;
        let last = cap as u32 - 1;
        counts.clear();
        counts.resize(nloc + 1, 0);
        let len = (nloc + 1) << shift;
        if rows.len() < len {
            rows.resize(len, 0);
        }
        let (out, cnt) = (&mut rows[..len], &mut counts[..nloc + 1]);
        // references to other vertices go to the spill row, whose count saturates
        let mut put = |v: u32, x: u32| {
            let s = v.wrapping_sub(vs).min(spill) as usize;
            let n = cnt[s];
            out[(s << shift) | n.min(last) as usize] = x;
            cnt[s] = n + 1;
        };
        // the common strides unrolled
        match k {
            3 => {
                for &c in cells {
                    let i = c as usize * 3;
                    let [a, b, d] = st.verts[i..i + 3] else {
                        unreachable!()
                    };
                    let x = val(c);
                    put(a, x);
                    put(b, x);
                    put(d, x);
                }
            }
            4 => {
                for &c in cells {
                    let i = c as usize * 4;
                    let [a, b, d, e] = st.verts[i..i + 4] else {
                        unreachable!()
                    };
                    let x = val(c);
                    put(a, x);
                    put(b, x);
                    put(d, x);
                    put(e, x);
                }
            }
            _ => {
                for &c in cells {
                    let x = val(c);
                    let i = c as usize * k;
                    for &v in &st.verts[i..i + k] {
                        put(v, x);
                    }
                }
            }
        }
        counts[..nloc].iter().all(|&n| n as usize <= cap)
    }

    /// Expands leaf `l` into a new [`ExpandedLeaf`].
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
    /// use starplex::stellar::ExpandedLeaf;
    /// let e = t.expand_leaf(LeafId(2));
    /// assert_eq!(e.leaf, LeafId(2));
    /// let mut f = ExpandedLeaf::default();
    /// t.expand_leaf_into(LeafId(2), &mut f);
    /// assert_eq!(e, f);
    /// ```
    pub fn expand_leaf(&self, l: LeafId) -> ExpandedLeaf {
        let mut e = ExpandedLeaf::default();
        self.expand_leaf_into(l, &mut e);
        e
    }

    /// Calls `f` on every leaf, in order, on one thread.
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
    /// let mut leaves = Vec::new();
    /// let mut refs = 0;
    /// t.for_each_leaf(|leaf| {
    ///     leaves.push(leaf.leaf().0);
    ///     refs += leaf.e.cells().len();
    /// });
    /// assert_eq!(leaves, vec![0, 1, 2, 3]);
    /// assert_eq!(refs, 6); // vertices 1 and 2 are in both triangles
    /// ```
    pub fn for_each_leaf(&self, mut f: impl FnMut(&LeafView<'_>)) {
        let mut e = ExpandedLeaf::default();
        for l in 0..self.n_leaves() {
            self.expand_leaf_into(LeafId(l as u32), &mut e);
            f(&LeafView { tree: self, e: &e });
        }
    }

    /// Maps every leaf in parallel (per-worker expansion buffers); results in leaf order, the
    /// same for any number of threads.
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
    /// let ids = t.par_map_leaves(|leaf| leaf.leaf().0);
    /// assert_eq!(ids, vec![0, 1, 2, 3]); // in leaf order
    /// let n_cells: Vec<usize> = t.par_map_leaves(|leaf| leaf.e.cells().len());
    /// assert_eq!(n_cells.iter().sum::<usize>(), 6);
    /// ```
    pub fn par_map_leaves<R: Send>(&self, f: impl Fn(&LeafView<'_>) -> R + Sync + Send) -> Vec<R> {
        (0..self.n_leaves() as u32)
            .into_par_iter()
            .map_init(ExpandedLeaf::default, |e, l| {
                self.expand_leaf_into(LeafId(l), e);
                f(&LeafView { tree: self, e })
            })
            .collect()
    }

    /// Maps every leaf in parallel with a per-worker LRU cache of `cache_size` expanded leaves:
    /// `f` gets the leaf and the worker's cache, through which it may expand neighbouring
    /// leaves cheaply. Results in leaf order.
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
    /// let n0 = t.expand_leaf(LeafId(0)).cells().len();
    /// // every leaf looks into leaf 0 through the worker's cache
    /// let r = t.par_map_leaves_cached(2, |leaf, cache| (leaf.leaf(), cache.get(leaf.tree, LeafId(0)).cells().len()));
    /// assert_eq!(r.len(), 4);
    /// assert!(r.iter().enumerate().all(|(i, &(l, n))| l == LeafId(i as u32) && n == n0));
    /// ```
    pub fn par_map_leaves_cached<R: Send>(
        &self,
        cache_size: usize,
        f: impl Fn(&LeafView<'_>, &mut LeafCache) -> R + Sync + Send,
    ) -> Vec<R> {
        (0..self.n_leaves() as u32)
            .into_par_iter()
            .map_init(
                || LeafCache::new(cache_size),
                |cache, l| {
                    let e = cache.get(self, LeafId(l));
                    f(&LeafView { tree: self, e: &e }, cache)
                },
            )
            .collect()
    }
}

/// An LRU cache of expanded leaves (capacity 0 disables caching).
///
/// ```
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// use starplex::stellar::{StellarTree, StellarOptions, LeafCache};
/// use starplex::ids::LeafId;
/// # let mut b = ComplexBuilder::new(1).unwrap();
/// # for x in 0..3 { b.push_vertex(&[x as f64]).unwrap(); }
/// # b.push_cell(CellKind::Simplex(1), &[0, 1]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// let t = StellarTree::build(&k, &StellarOptions { kv: Some(1), ..Default::default() }).unwrap();
/// let mut c = LeafCache::new(2);
/// let a = c.get(&t, LeafId(0));
/// let b = c.get(&t, LeafId(0));
/// assert!(std::sync::Arc::ptr_eq(&a, &b));
/// assert_eq!(c.hits(), 1);
/// ```
pub struct LeafCache {
    cache: Option<lru::LruCache<u32, Arc<ExpandedLeaf>>>,
    hits: u64,
    misses: u64,
}

impl LeafCache {
    /// A cache of `capacity` leaves.
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
    /// use starplex::stellar::LeafCache;
    /// let mut c = LeafCache::new(0); // no caching
    /// c.get(&t, LeafId(0));
    /// c.get(&t, LeafId(0));
    /// assert_eq!((c.hits(), c.misses()), (0, 2));
    /// ```
    pub fn new(capacity: usize) -> LeafCache {
        LeafCache {
            cache: std::num::NonZeroUsize::new(capacity).map(lru::LruCache::new),
            hits: 0,
            misses: 0,
        }
    }
    /// The expanded leaf, from the cache or freshly expanded (and cached).
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
    /// use starplex::stellar::LeafCache;
    /// let mut c = LeafCache::new(4);
    /// assert_eq!(*c.get(&t, LeafId(2)), t.expand_leaf(LeafId(2)));
    /// ```
    pub fn get(&mut self, t: &StellarTree, l: LeafId) -> Arc<ExpandedLeaf> {
        if let Some(c) = &mut self.cache
            && let Some(e) = c.get(&l.0)
        {
            self.hits += 1;
            return e.clone();
        }
        self.misses += 1;
        let e = Arc::new(t.expand_leaf(l));
        if let Some(c) = &mut self.cache {
            c.put(l.0, e.clone());
        }
        e
    }
    /// Lookups answered from the cache.
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
    /// use starplex::stellar::LeafCache;
    /// let mut c = LeafCache::new(1);
    /// for l in [0, 0, 1, 0] { c.get(&t, LeafId(l)); }
    /// assert_eq!(c.hits(), 1); // leaf 1 evicted leaf 0
    /// ```
    pub fn hits(&self) -> u64 {
        self.hits
    }
    /// Lookups that expanded a leaf.
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
    /// use starplex::stellar::LeafCache;
    /// let mut c = LeafCache::new(1);
    /// for l in [0, 0, 1, 0] { c.get(&t, LeafId(l)); }
    /// assert_eq!(c.misses(), 3);
    /// ```
    pub fn misses(&self) -> u64 {
        self.misses
    }
}

/// A read-only view of one expanded leaf: its vertices, its top cells and their local
/// relations, with conversions to input numbering.
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
/// # use starplex::ids::{CellId, LeafId, VertexId};
/// use starplex::stellar::LeafView;
/// // the leaf of input vertex 1, which is in both triangles
/// let e = t.expand_leaf(t.leaf_of_vertex(VertexId(1)).unwrap());
/// let leaf = LeafView { tree: &t, e: &e };
/// assert_eq!(leaf.e.cells().len(), 2);
/// assert_eq!(leaf.input_vertices().collect::<Vec<_>>(), vec![VertexId(1)]);
/// ```
#[derive(Clone, Copy)]
pub struct LeafView<'a> {
    /// The tree.
    pub tree: &'a StellarTree,
    /// The expansion.
    pub e: &'a ExpandedLeaf,
}

impl<'a> LeafView<'a> {
    /// The leaf id.
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
    /// # use starplex::ids::{CellId, LeafId, VertexId};
    /// use starplex::stellar::LeafView;
    /// // the leaf of input vertex 1, which is in both triangles
    /// let e = t.expand_leaf(t.leaf_of_vertex(VertexId(1)).unwrap());
    /// let leaf = LeafView { tree: &t, e: &e };
    /// assert_eq!(leaf.leaf(), t.leaf_of_vertex(VertexId(1)).unwrap());
    /// ```
    pub fn leaf(&self) -> LeafId {
        self.e.leaf
    }
    /// Input ids of the leaf's vertices (in tree order).
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
    /// # use starplex::ids::{CellId, LeafId, VertexId};
    /// use starplex::stellar::LeafView;
    /// // the leaf of input vertex 1, which is in both triangles
    /// let e = t.expand_leaf(t.leaf_of_vertex(VertexId(1)).unwrap());
    /// let leaf = LeafView { tree: &t, e: &e };
    /// assert_eq!(leaf.input_vertices().collect::<Vec<_>>(), vec![VertexId(1)]);
    /// ```
    pub fn input_vertices(&self) -> impl Iterator<Item = VertexId> + '_ {
        self.tree_vertices()
            .map(|v| VertexId(self.tree.v_orig[v as usize]))
    }
    /// Tree ids of the leaf's vertices, as raw `u32` (the typed form is
    /// [`LocalStar::owned_vertices`]).
    #[inline]
    pub(crate) fn tree_vertices(&self) -> std::ops::Range<u32> {
        self.e.v_start..self.e.v_end
    }
    /// True when tree vertex `v` belongs to the leaf (raw form of [`LocalStar::owns`]).
    #[inline]
    pub(crate) fn owns_tree(&self, v: u32) -> bool {
        v >= self.e.v_start && v < self.e.v_end
    }
    /// Kind and tree-numbered vertices of a tree cell (raw form of [`LocalStar::local_cell`]).
    #[inline]
    pub(crate) fn cell(&self, c: u32) -> (CellKind, &'a [u32]) {
        self.tree.cells.get(c)
    }
    /// Top cells (tree ids, increasing) incident to tree vertex `v` of this leaf (raw form of
    /// [`LocalStar::local_star`]).
    #[inline]
    pub(crate) fn vt_tree(&self, v: u32) -> &'a [u32] {
        let i = (v - self.e.v_start) as usize;
        &self.e.vt[self.e.vt_off[i] as usize..self.e.vt_off[i + 1] as usize]
    }
}

/// A leaf is a part of the complex that owns its vertices and holds every top cell incident
/// to them, in tree numbering.
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
/// use starplex::ids::{CellId, TreeVertexId, VertexId};
/// use starplex::stellar::LeafView;
/// use starplex::topo::LocalStar;
/// // the leaf of input vertex 1, which is in both triangles
/// let e = t.expand_leaf(t.leaf_of_vertex(VertexId(1)).unwrap());
/// let leaf = LeafView { tree: &t, e: &e };
/// let v: TreeVertexId = t.vertex_from_input()[1];
/// assert_eq!(leaf.owned_vertices().collect::<Vec<_>>(), [v]);
/// assert!(leaf.owns(v) && !leaf.owns(t.vertex_from_input()[0]));
/// assert_eq!(leaf.input_vertex(v), VertexId(1));
/// assert_eq!(leaf.local_star(v).len(), 2); // both triangles
/// let mut input: Vec<CellId> = leaf.local_top_cells().map(|c| leaf.input_cell(c)).collect();
/// input.sort();
/// assert_eq!(input, [CellId(0), CellId(1)]);
/// for c in leaf.local_top_cells() {
///     let (kind, vs) = leaf.local_cell(c);
///     assert_eq!(kind, CellKind::Simplex(2));
///     assert!(vs.contains(&v));
/// }
/// ```
impl LocalStar for LeafView<'_> {
    type Vertex = TreeVertexId;
    type Cell = TreeCellId;

    fn owned_vertices(&self) -> impl Iterator<Item = TreeVertexId> + '_ {
        self.tree_vertices().map(TreeVertexId)
    }
    #[inline]
    fn owns(&self, v: TreeVertexId) -> bool {
        self.owns_tree(v.0)
    }
    fn local_top_cells(&self) -> impl Iterator<Item = TreeCellId> + '_ {
        self.e.cells.iter().map(|&c| TreeCellId(c))
    }
    #[inline]
    fn local_star(&self, v: TreeVertexId) -> &[TreeCellId] {
        bytemuck::cast_slice(self.vt_tree(v.0))
    }
    #[inline]
    fn local_cell(&self, c: TreeCellId) -> (CellKind, &[TreeVertexId]) {
        let (kind, vs) = self.cell(c.0);
        (kind, bytemuck::cast_slice(vs))
    }
    fn uniform_kind(&self) -> Option<CellKind> {
        self.tree.cells.uniform
    }
    fn input_vertex(&self, v: TreeVertexId) -> VertexId {
        VertexId(self.tree.v_orig[v.index()])
    }
    fn input_cell(&self, c: TreeCellId) -> CellId {
        CellId(self.tree.c_orig[c.index()])
    }
}

#[cfg(test)]
mod tests {
    use super::StellarTree;
    use crate::cell::CellKind;
    use crate::complex::{BuildOptions, ComplexBuilder, IndexedComplex};
    use crate::ids::LeafId;
    use crate::stellar::{sre, ExpandedLeaf, StellarOptions};

    /// A fan of `n` triangles around vertex 0 in the plane, then a strip of `m` triangles
    /// beside it.
    fn fan_and_strip(n: usize, m: usize) -> IndexedComplex {
        let mut b = ComplexBuilder::new(2).unwrap();
        b.push_vertex(&[0.0, 0.0]).unwrap();
        for i in 0..n {
            let a = std::f64::consts::TAU * i as f64 / n as f64;
            b.push_vertex(&[a.cos(), a.sin()]).unwrap();
        }
        for i in 0..n as u32 {
            b.push_cell(CellKind::Simplex(2), &[0, 1 + i, 1 + (i + 1) % n as u32])
                .unwrap();
        }
        let s = 1 + n as u32;
        for i in 0..=m / 2 {
            b.push_vertex(&[3.0 + i as f64, 0.0]).unwrap();
            b.push_vertex(&[3.0 + i as f64, 1.0]).unwrap();
        }
        for i in 0..m as u32 {
            let (a, c) = (s + 2 * (i / 2), s + 2 * (i / 2) + 2);
            let t = if i % 2 == 0 {
                [a, c, a + 1]
            } else {
                [a + 1, c, c + 1]
            };
            b.push_cell(CellKind::Simplex(2), &t).unwrap();
        }
        b.build(&BuildOptions::default()).unwrap().0
    }

    /// The leaf's rows by the counting sort.
    fn counted(t: &StellarTree, l: LeafId) -> (Vec<u32>, Vec<u32>) {
        let r = t.leaf_vertices(l);
        let mut cells = Vec::new();
        sre::decode(t.leaf_encoded_cells(l), &mut cells);
        let (mut off, mut rows) = (Vec::new(), Vec::new());
        t.bucket_refs(r.start, r.end, &cells, |c| c, &mut off, &mut rows);
        (off, rows)
    }

    /// The one-pass rows of a fixed capacity, packed or not, equal the counting sort's; a
    /// vertex of many more cells than the mean overflows them and the counting sort is used.
    #[test]
    fn fixed_capacity_rows_equal_counted_rows() {
        // seen: a row overflowed, the rows fitted, the leaf was too big for them
        let mut seen = [false; 3];
        let cases = [
            (6, 40, 4),
            (64, 4, 0),
            (64, 40, 8),
            (5, 200, 0),
            (5, 200_000, 0),
        ];
        for (n, m, kv) in cases {
            let k = fan_and_strip(n, m);
            let opts = StellarOptions {
                kv: Some(kv),
                ..Default::default()
            };
            let t = StellarTree::build(&k, &opts).unwrap();
            let mut e = ExpandedLeaf::default();
            for l in (0..t.n_leaves() as u32).map(LeafId) {
                let (off, rows) = counted(&t, l);
                t.expand_leaf_into(l, &mut e);
                assert_eq!((&e.vt_off, &e.vt), (&off, &rows), "leaf {l:?}");
                // which path expand_leaf_into took
                let r = t.leaf_vertices(l);
                let Some(shift) = t.fixed_row_shift(r.len(), e.cells.len()) else {
                    seen[2] = true; // too big for rows of a fixed capacity
                    continue;
                };
                let (mut cnt, mut fixed) = (Vec::new(), Vec::new());
                let fits =
                    t.bucket_refs_fixed(r.clone(), &e.cells, |c| c, shift, &mut cnt, &mut fixed);
                seen[fits as usize] = true;
                if fits {
                    for i in 0..r.len() {
                        let row = &fixed[i << shift..(i << shift) + cnt[i] as usize];
                        assert_eq!(row, &rows[off[i] as usize..off[i + 1] as usize]);
                    }
                }
            }
            // VT in input ids agrees with the brute force
            let mut want = vec![Vec::new(); k.n_vertices()];
            for c in k.cells() {
                for &v in c.vertices {
                    want[v as usize].push(c.id.0);
                }
            }
            let vt = t.vt_all();
            for (v, w) in want.iter().enumerate() {
                assert_eq!(vt.row(v), w.as_slice(), "vertex {v}");
            }
        }
        assert_eq!(seen, [true; 3], "every path taken");
    }
}
