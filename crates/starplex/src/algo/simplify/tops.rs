//! The editable working structure of simplification: a simplicial complex stored by its top
//! (maximal) simplices, with the vertex → top relation kept up to date by every contraction.
//!
//! It is built once from any structure through [`TopCells`] (plus coordinates), edited by
//! [`TopSimplices::contract`], and written back with [`TopSimplices::to_complex`]. Top simplices
//! keep the vertex order they were given (a contraction replaces a vertex in place), so the
//! orientation of the cells survives simplification.
//!
//! ```
//! use starplex::algo::simplify::TopSimplices;
//! use starplex::topo::naive::VtIndex;
//! # use starplex::complex::{ComplexBuilder, BuildOptions};
//! # use starplex::cell::CellKind;
//! let mut b = ComplexBuilder::new(2).unwrap();
//! for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
//! b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
//! b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
//! let k = b.build(&BuildOptions::default()).unwrap().0;
//! let w = TopSimplices::from_structure(&VtIndex::new(&k), k.coords(), 2).unwrap();
//! assert_eq!((w.n_alive_vertices(), w.n_alive_tops()), (4, 2));
//! assert_eq!(w.neighbours(1), vec![0, 2, 3]);
//! ```
use std::sync::Arc;

use fixedbitset::FixedBitSet;
use smallvec::SmallVec;

use super::rows::Rows;
use super::SimplifyError;
use crate::cell::CellKind;
use crate::complex::{BuildOptions, ComplexBuilder, IndexedComplex};
use crate::ids::{CellId, VertexId};
use crate::topo::TopCells;

/// One top simplex: its vertices in the given order (inline up to a tetrahedron).
pub type Top = SmallVec<[u32; 4]>;

/// A simplicial complex stored by its top simplices, editable by edge contraction.
///
/// Vertex ids are those of the input for the whole life of the structure (a contracted vertex
/// is marked dead, never renumbered); a contraction edits the tops through the removed vertex in
/// place (a top keeps its id, and its origin, for its whole life; removed tops leave empty slots).
///
/// ```
/// use starplex::algo::simplify::TopSimplices;
/// // [1, 2] is a face of [0, 1, 2]: tops must be maximal
/// assert!(TopSimplices::from_tops(3, &[vec![0, 1, 2], vec![1, 2]]).is_err());
/// let w = TopSimplices::from_tops(3, &[vec![0, 1, 2]]).unwrap();
/// assert_eq!(w.top(0), &[0, 1, 2]);
/// ```
#[derive(Clone, Debug)]
pub struct TopSimplices {
    /// The tops, flat ([`FlatTops`]: no allocation or inline header per top).
    tops: FlatTops,
    /// Per top of a part cut out of a structure ([`cut`](Self::cut)): its id there; empty
    /// for a whole structure, whose tops keep their ids.
    whole_id: Vec<u32>,
    /// The tops of the whole structure below this id are the input's, in order: a top is the
    /// image of the input top of its (whole) id; the others are vertex tops added for
    /// isolated vertices.
    n_input_tops: usize,
    /// Per vertex: the tops through it.
    vt: Rows,
    alive_v: Vec<bool>,
    locked: Vec<bool>,
    /// Per input top (by origin): its label, when labels are kept (empty otherwise); shared
    /// with the parts cut out for a parallel sweep ([`cut`](Self::cut)).
    labels: Arc<Vec<u32>>,
    n_alive_tops: usize,
    n_alive_v: usize,
    /// Coordinates, `stride` numbers a vertex (empty when there are none).
    pub coords: Vec<f64>,
    /// Numbers per vertex in `coords`.
    pub stride: usize,
    /// Reused buffers of [`contract`](Self::contract).
    scratch: ContractScratch,
}

/// The top simplices stored flat: every top has a slot in one array, of `width` numbers when
/// `starts` is empty (a pure complex: a triangle mesh takes 12 bytes and 1 length byte a
/// triangle instead of a 24-byte inline vector), else of its input length at `starts[t]`.
/// A top never grows (a contraction replaces or removes a vertex), so it never leaves its slot;
/// a removed top has length 0.
#[derive(Clone, Debug, Default)]
struct FlatTops {
    verts: Vec<u32>,
    lens: Vec<u8>,
    starts: Vec<usize>,
    width: usize,
}

impl FlatTops {
    /// From the tops written one after the other (`verts`, lengths `lens`): equal slots of the
    /// largest length when the padding costs less than an offset per top.
    fn new(mut verts: Vec<u32>, lens: Vec<u8>) -> FlatTops {
        let n = lens.len();
        let width = lens.iter().copied().max().unwrap_or(0) as usize;
        let total = verts.len();
        let mut starts = Vec::new();
        if (n * width).saturating_sub(total) * 4 <= n * 8 {
            if total != n * width {
                // spread the tops to their slots, from the last (a slot starts at or after the
                // top's packed position)
                verts.resize(n * width, 0);
                let mut end = total;
                for t in (0..n).rev() {
                    let l = lens[t] as usize;
                    end -= l;
                    verts.copy_within(end..end + l, t * width);
                }
            }
        } else {
            starts.reserve_exact(n);
            let mut at = 0;
            for &l in &lens {
                starts.push(at);
                at += l as usize;
            }
        }
        FlatTops {
            verts,
            lens,
            starts,
            width,
        }
    }
    fn len(&self) -> usize {
        self.lens.len()
    }
    /// The vertex rows: per vertex `0..n`, the tops through it in increasing id order
    /// (small structures, a block's part, on one thread).
    fn rows(&self, n: usize) -> Rows {
        Rows::from_tops(n, self.len(), |t| self.get(t), self.verts.len() >= 1 << 16)
    }
    #[inline]
    fn slot(&self, t: usize) -> usize {
        if self.starts.is_empty() {
            t * self.width
        } else {
            self.starts[t]
        }
    }
    #[inline]
    fn get(&self, t: usize) -> &[u32] {
        let s = self.slot(t);
        &self.verts[s..s + self.lens[t] as usize]
    }
    #[inline]
    fn get_mut(&mut self, t: usize) -> &mut [u32] {
        let s = self.slot(t);
        &mut self.verts[s..s + self.lens[t] as usize]
    }
    /// Top `t` after the contraction of `b` into `a` (edited in place): `b` dropped when the
    /// top also holds `a` (returns true), else replaced by `a`.
    fn contract_in(&mut self, t: usize, a: u32, b: u32) -> bool {
        let top = self.get_mut(t);
        let had_a = top.contains(&a);
        if let Some(i) = top.iter().position(|&v| v == b) {
            if had_a {
                top.copy_within(i + 1.., i);
                self.lens[t] -= 1;
            } else {
                top[i] = a;
            }
        }
        had_a
    }
}

/// Reused buffers of [`TopSimplices::contract`] (no allocation per contraction).
#[derive(Clone, Debug, Default)]
struct ContractScratch {
    /// The tops through the removed vertex (edited in place into their images).
    ids: Vec<u32>,
    /// Per image: its top also held the surviving vertex.
    had_a: Vec<bool>,
    /// Per image: not a face of another top.
    keep: Vec<bool>,
    /// Tops through the survivor that became a face of an image.
    swallowed: Vec<u32>,
    /// Triangle case: the sorted triples of the other tops through the survivor, and of the
    /// images (an edge image `ax` as `[x, x, x]`).
    other_keys: Vec<[u32; 3]>,
    image_keys: Vec<[u32; 3]>,
    /// General case: the tops through the survivor that were not through the removed vertex.
    others: Vec<u32>,
    /// Uniform case: per top slot, `epoch` when it holds the survivor (made on first use).
    through_a: Vec<u32>,
    epoch: u32,
}

impl TopSimplices {
    /// Builds the structure from the top cells of any structure and its coordinates (`stride`
    /// numbers a vertex; pass an empty slice for none). A vertex in no top cell becomes a
    /// 0-dimensional top.
    ///
    /// ```
    /// use starplex::algo::simplify::TopSimplices;
    /// use starplex::tds::simplex_tree::{SimplexTree, SimplexTreeOptions};
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// # let mut b = ComplexBuilder::new(1).unwrap();
    /// # for x in 0..4 { b.push_vertex(&[x as f64]).unwrap(); }
    /// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// let st = SimplexTree::new(&k, &SimplexTreeOptions::default()).unwrap();
    /// let w = TopSimplices::from_structure(&st, &[], 0).unwrap();
    /// assert_eq!(w.n_alive_tops(), 2); // the triangle and the isolated vertex 3
    /// ```
    ///
    /// # Errors
    /// [`SimplifyError::NotSimplicial`] for a CP cell (quad, hexahedron, ...);
    /// [`SimplifyError::Empty`] when there is no vertex.
    pub fn from_structure<S: TopCells + ?Sized>(
        s: &S,
        coords: &[f64],
        stride: usize,
    ) -> Result<TopSimplices, SimplifyError> {
        let n = s.n_vertices();
        if n == 0 {
            return Err(SimplifyError::Empty);
        }
        let mut verts = Vec::new();
        let mut lens = Vec::with_capacity(s.n_top_cells() + 1);
        let mut buf = Vec::new();
        let mut used = vec![false; n];
        for c in 0..s.n_top_cells() {
            let c = CellId(c as u32);
            let kind = s.top_cell_kind(c);
            if !kind.is_simplex() {
                return Err(SimplifyError::not_simplicial(c.0, kind));
            }
            buf.clear();
            s.top_cell_vertices(c, &mut buf);
            if c.0 == 0 {
                verts.reserve_exact(s.n_top_cells() * buf.len());
            }
            for &v in &buf {
                used[v.0 as usize] = true;
            }
            verts.extend(buf.iter().map(|v| v.0));
            lens.push(buf.len() as u8); // at most MAX_SIMPLEX_DIM + 1 = 65 vertices
        }
        let n_input_tops = lens.len();
        for (v, &u) in used.iter().enumerate() {
            if !u {
                verts.push(v as u32);
                lens.push(1);
            }
        }
        let coords = if stride == 0 {
            Vec::new()
        } else {
            coords.to_vec()
        };
        Ok(Self::assemble(
            n,
            FlatTops::new(verts, lens),
            n_input_tops,
            coords,
            stride,
        ))
    }

    /// Builds the structure from an indexed complex (its coordinates included).
    ///
    /// ```
    /// use starplex::algo::simplify::TopSimplices;
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// # let mut b = ComplexBuilder::new(2).unwrap();
    /// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]] { b.push_vertex(&p).unwrap(); }
    /// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// let w = TopSimplices::from_complex(&k).unwrap();
    /// assert_eq!(w.point(2), &[0.0, 1.0]);
    /// ```
    ///
    /// # Errors
    /// As [`from_structure`](Self::from_structure).
    pub fn from_complex(k: &IndexedComplex) -> Result<TopSimplices, SimplifyError> {
        Self::from_complex_points(k, true)
    }

    /// [`from_complex`](Self::from_complex) without a copy of the coordinates, for work that
    /// never reads or moves a vertex (homology mode); write it back with
    /// [`to_complex_with_points`](Self::to_complex_with_points).
    ///
    /// ```
    /// # use starplex::algo::simplify::TopSimplices;
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// # let mut b = ComplexBuilder::new(2).unwrap();
    /// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]] { b.push_vertex(&p).unwrap(); }
    /// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// let w = TopSimplices::from_complex_without_points(&k).unwrap();
    /// assert!(w.point(1).is_empty());
    /// let (k2, _) = w.to_complex_with_points(k.coords(), k.ambient_dim()).unwrap();
    /// assert_eq!(k2, k);
    /// ```
    ///
    /// # Errors
    /// As [`from_complex`](Self::from_complex).
    pub fn from_complex_without_points(k: &IndexedComplex) -> Result<TopSimplices, SimplifyError> {
        Self::from_complex_points(k, false)
    }

    fn from_complex_points(
        k: &IndexedComplex,
        points: bool,
    ) -> Result<TopSimplices, SimplifyError> {
        let n = k.n_vertices();
        if n == 0 {
            return Err(SimplifyError::Empty);
        }
        if let Some(b) = k.blocks().iter().find(|b| !b.kind.is_simplex()) {
            return Err(SimplifyError::not_simplicial(b.first, b.kind));
        }
        // the tops are the cells, block by block (what `from_structure` makes, in id order);
        // the rows are made from them by `assemble` (no vertex -> cells index in between)
        let mut verts = Vec::with_capacity(k.n_refs());
        let mut lens = Vec::with_capacity(k.n_cells() + 1);
        let mut used = FixedBitSet::with_capacity(n);
        for b in k.blocks() {
            verts.extend_from_slice(&b.vertices);
            lens.resize(lens.len() + b.len(), b.kind.n_vertices() as u8);
            for &v in b.vertices.iter() {
                used.insert(v as usize);
            }
        }
        // a vertex in no cell is a 0-dimensional top
        for v in used.zeroes() {
            verts.push(v as u32);
            lens.push(1);
        }
        let (coords, stride) = if points {
            (k.coords().to_vec(), k.ambient_dim())
        } else {
            (Vec::new(), 0)
        };
        Ok(Self::assemble(
            n,
            FlatTops::new(verts, lens),
            k.n_cells(),
            coords,
            stride,
        ))
    }

    /// Builds the structure from lists of vertices (no coordinates), checking that they are
    /// simplices (no repeated vertex, in range) and maximal.
    ///
    /// ```
    /// use starplex::algo::simplify::TopSimplices;
    /// let w = TopSimplices::from_tops(4, &[vec![0, 1, 2], vec![2, 3]]).unwrap();
    /// assert_eq!(w.n_alive_tops(), 2);
    /// assert!(TopSimplices::from_tops(3, &[vec![0, 0]]).is_err());
    /// ```
    ///
    /// # Errors
    /// [`SimplifyError::BadTop`] naming the list.
    pub fn from_tops(n_vertices: usize, tops: &[Vec<u32>]) -> Result<TopSimplices, SimplifyError> {
        let mut used = vec![false; n_vertices];
        let mut out: Vec<Top> = Vec::with_capacity(tops.len());
        for (i, t) in tops.iter().enumerate() {
            let bad = |reason: &str| SimplifyError::BadTop {
                top: i,
                reason: reason.into(),
            };
            if t.is_empty() {
                return Err(bad("no vertex"));
            }
            if t.len() > crate::cell::MAX_SIMPLEX_DIM + 1 {
                return Err(bad("dimension too high"));
            }
            for (j, &v) in t.iter().enumerate() {
                if v as usize >= n_vertices {
                    return Err(bad("vertex out of range"));
                }
                if t[..j].contains(&v) {
                    return Err(bad("repeated vertex"));
                }
                used[v as usize] = true;
            }
            for (j, u) in tops.iter().enumerate() {
                if j != i && is_subset(t, u) && (t.len() < u.len() || j < i) {
                    return Err(bad("not maximal (a face of another top, or a duplicate)"));
                }
            }
            out.push(t.iter().copied().collect());
        }
        let n_input_tops = out.len();
        for (v, &u) in used.iter().enumerate() {
            if !u {
                out.push(SmallVec::from_slice(&[v as u32]));
            }
        }
        let lens = out.iter().map(|t| t.len() as u8).collect();
        let verts = out.into_iter().flatten().collect();
        Ok(Self::assemble(
            n_vertices,
            FlatTops::new(verts, lens),
            n_input_tops,
            Vec::new(),
            0,
        ))
    }

    fn assemble(
        n: usize,
        tops: FlatTops,
        n_input_tops: usize,
        coords: Vec<f64>,
        stride: usize,
    ) -> TopSimplices {
        let vt = tops.rows(n);
        debug_assert!(
            (0..tops.len()).all(|i| tops
                .get(i)
                .iter()
                .all(|&v| vt.row(v as usize).contains(&(i as u32)))),
            "every top is in the rows of its vertices"
        );
        TopSimplices {
            n_alive_tops: tops.len(),
            tops,
            whole_id: Vec::new(),
            n_input_tops,
            vt,
            alive_v: vec![true; n],
            locked: vec![false; n],
            labels: Arc::default(),
            n_alive_v: n,
            coords,
            stride,
            scratch: ContractScratch::default(),
        }
    }

    /// Number of vertex ids (dead ones included).
    ///
    /// ```
    /// # use starplex::algo::simplify::TopSimplices;
    /// let w = TopSimplices::from_tops(3, &[vec![0, 1]]).unwrap();
    /// assert_eq!(w.n_vertices(), 3);
    /// ```
    pub fn n_vertices(&self) -> usize {
        self.alive_v.len()
    }

    /// Number of vertices not contracted away.
    ///
    /// ```
    /// # use starplex::algo::simplify::TopSimplices;
    /// let mut w = TopSimplices::from_tops(3, &[vec![0, 1], vec![1, 2]]).unwrap();
    /// w.contract(0, 1);
    /// assert_eq!(w.n_alive_vertices(), 2);
    /// ```
    pub fn n_alive_vertices(&self) -> usize {
        self.n_alive_v
    }

    /// Number of top simplices (0-dimensional tops, isolated vertices, included).
    ///
    /// ```
    /// # use starplex::algo::simplify::TopSimplices;
    /// let w = TopSimplices::from_tops(3, &[vec![0, 1]]).unwrap();
    /// assert_eq!(w.n_alive_tops(), 2); // the edge and the vertex 2
    /// ```
    pub fn n_alive_tops(&self) -> usize {
        self.n_alive_tops
    }

    /// True when vertex `v` has not been contracted away.
    ///
    /// ```
    /// # use starplex::algo::simplify::TopSimplices;
    /// let mut w = TopSimplices::from_tops(2, &[vec![0, 1]]).unwrap();
    /// w.contract(1, 0);
    /// assert!(w.is_alive(1) && !w.is_alive(0));
    /// ```
    pub fn is_alive(&self, v: u32) -> bool {
        self.alive_v.get(v as usize).copied().unwrap_or(false)
    }

    /// Locks vertex `v` (or unlocks it): the simplifiers ([`contract_homology`] and
    /// [`simplify_qem`]) never remove a locked vertex nor move it, and never contract an edge
    /// between two locked vertices. [`contract`](Self::contract) itself does not look at locks.
    ///
    /// [`contract_homology`]: super::contract::contract_homology
    /// [`simplify_qem`]: super::qem::simplify_qem
    ///
    /// ```
    /// # use starplex::algo::simplify::TopSimplices;
    /// let mut w = TopSimplices::from_tops(2, &[vec![0, 1]]).unwrap();
    /// w.set_locked(1, true);
    /// assert!(w.is_locked(1) && !w.is_locked(0));
    /// assert!(!w.is_locked(9)); // out of range: not locked
    /// ```
    pub fn set_locked(&mut self, v: u32, locked: bool) {
        if let Some(x) = self.locked.get_mut(v as usize) {
            *x = locked;
        }
    }

    /// True when vertex `v` is locked ([`set_locked`](Self::set_locked)).
    ///
    /// ```
    /// # use starplex::algo::simplify::TopSimplices;
    /// let w = TopSimplices::from_tops(2, &[vec![0, 1]]).unwrap();
    /// assert!(!w.is_locked(0));
    /// ```
    pub fn is_locked(&self, v: u32) -> bool {
        self.locked.get(v as usize).copied().unwrap_or(false)
    }

    /// Labels the input tops (one value per input top, by its [`origin`](Self::origin)), so
    /// that the simplifiers keep the regions of each label
    /// ([`link_condition_in`](super::link_condition::link_condition_in)); an empty vector
    /// removes the labels. Lock the vertices on the interfaces too
    /// ([`set_locked`](Self::set_locked)) to keep the interfaces in place.
    ///
    /// ```
    /// # use starplex::algo::simplify::TopSimplices;
    /// let mut w = TopSimplices::from_tops(4, &[vec![0, 1, 2], vec![1, 2, 3]]).unwrap();
    /// w.set_cell_labels(vec![5, 6]);
    /// assert_eq!((w.label(0), w.label(1)), (Some(5), Some(6)));
    /// assert!(w.has_labels());
    /// ```
    pub fn set_cell_labels(&mut self, labels: Vec<u32>) {
        self.labels = Arc::new(labels);
    }

    /// True when the tops are labelled ([`set_cell_labels`](Self::set_cell_labels)).
    ///
    /// ```
    /// # use starplex::algo::simplify::TopSimplices;
    /// assert!(!TopSimplices::from_tops(2, &[vec![0, 1]]).unwrap().has_labels());
    /// ```
    pub fn has_labels(&self) -> bool {
        !self.labels.is_empty()
    }

    /// The label of top `t`: that of the input top it is the image of (`None` without labels,
    /// for a vertex top added for an isolated vertex, or past the labels given).
    ///
    /// ```
    /// # use starplex::algo::simplify::TopSimplices;
    /// let mut w = TopSimplices::from_tops(3, &[vec![0, 1], vec![1, 2]]).unwrap();
    /// w.set_cell_labels(vec![1, 2]);
    /// w.contract(1, 0); // the edge 1-2 is unchanged, 0-1 became the vertex 1, dominated
    /// assert_eq!(w.tops().count(), 1);
    /// assert_eq!(w.label(1), Some(2));
    /// ```
    pub fn label(&self, t: u32) -> Option<u32> {
        self.origin(t)
            .and_then(|o| self.labels.get(o as usize).copied())
    }

    /// Number of locked vertices.
    ///
    /// ```
    /// # use starplex::algo::simplify::TopSimplices;
    /// let mut w = TopSimplices::from_tops(3, &[vec![0, 1, 2]]).unwrap();
    /// w.set_locked(2, true);
    /// assert_eq!(w.n_locked(), 1);
    /// ```
    pub fn n_locked(&self) -> usize {
        self.locked.iter().filter(|&&l| l).count()
    }

    /// The vertices of top `t` (empty for a removed top).
    ///
    /// ```
    /// # use starplex::algo::simplify::TopSimplices;
    /// let w = TopSimplices::from_tops(3, &[vec![2, 0, 1]]).unwrap();
    /// assert_eq!(w.top(0), &[2, 0, 1]);
    /// ```
    pub fn top(&self, t: u32) -> &[u32] {
        if (t as usize) < self.tops.len() {
            self.tops.get(t as usize)
        } else {
            &[]
        }
    }

    /// The ids of the tops containing `v` (in no particular order).
    ///
    /// ```
    /// # use starplex::algo::simplify::TopSimplices;
    /// let w = TopSimplices::from_tops(3, &[vec![0, 1], vec![1, 2]]).unwrap();
    /// assert_eq!(w.star(1).len(), 2);
    /// ```
    pub fn star(&self, v: u32) -> &[u32] {
        self.vt.row(v as usize)
    }

    /// The vertices joined to `v` by an edge, sorted.
    ///
    /// ```
    /// # use starplex::algo::simplify::TopSimplices;
    /// let w = TopSimplices::from_tops(4, &[vec![0, 1, 2], vec![2, 3]]).unwrap();
    /// assert_eq!(w.neighbours(2), vec![0, 1, 3]);
    /// ```
    pub fn neighbours(&self, v: u32) -> Vec<u32> {
        let mut out = Vec::new();
        self.neighbours_into(v, &mut out);
        out
    }

    /// [`neighbours`](Self::neighbours) into a reused buffer.
    ///
    /// ```
    /// # use starplex::algo::simplify::TopSimplices;
    /// let w = TopSimplices::from_tops(3, &[vec![0, 1], vec![0, 2]]).unwrap();
    /// let mut nb = Vec::new();
    /// w.neighbours_into(0, &mut nb);
    /// assert_eq!(nb, [1, 2]);
    /// ```
    pub fn neighbours_into(&self, v: u32, out: &mut Vec<u32>) {
        self.neighbours_where(v, out, |x| x != v);
    }

    /// The neighbours of `v` above it, sorted ([`neighbours_into`](Self::neighbours_into) less
    /// those below `v`, with half the entries to sort): each edge once, from its smaller end.
    ///
    /// ```
    /// # use starplex::algo::simplify::TopSimplices;
    /// let w = TopSimplices::from_tops(5, &[vec![0, 1, 2], vec![1, 3], vec![2, 3, 4]]).unwrap();
    /// let mut nb = Vec::new();
    /// w.neighbours_above_into(1, &mut nb);
    /// assert_eq!(nb, [2, 3]);
    /// w.neighbours_above_into(2, &mut nb);
    /// assert_eq!(nb, [3, 4]);
    /// ```
    pub fn neighbours_above_into(&self, v: u32, out: &mut Vec<u32>) {
        self.neighbours_where(v, out, |x| x > v);
    }

    /// The vertices `x` of the tops through `v` with `keep(x)`, sorted, each once.
    #[inline]
    fn neighbours_where(&self, v: u32, out: &mut Vec<u32>, keep: impl Fn(u32) -> bool) {
        out.clear();
        for &t in self.star(v) {
            out.extend(
                self.tops
                    .get(t as usize)
                    .iter()
                    .copied()
                    .filter(|&x| keep(x)),
            );
        }
        out.sort_unstable();
        out.dedup();
    }

    /// The coordinates of `v` (empty without coordinates).
    ///
    /// ```
    /// # use starplex::algo::simplify::TopSimplices;
    /// let w = TopSimplices::from_tops(2, &[vec![0, 1]]).unwrap();
    /// assert!(w.point(0).is_empty());
    /// ```
    pub fn point(&self, v: u32) -> &[f64] {
        let s = self.stride;
        self.coords
            .get(v as usize * s..(v as usize + 1) * s)
            .unwrap_or(&[])
    }

    /// The highest dimension of a top simplex (`None` when there is none).
    ///
    /// ```
    /// # use starplex::algo::simplify::TopSimplices;
    /// let w = TopSimplices::from_tops(4, &[vec![0, 1, 2], vec![2, 3]]).unwrap();
    /// assert_eq!(w.dim(), Some(2));
    /// ```
    pub fn dim(&self) -> Option<usize> {
        self.tops
            .lens
            .iter()
            .filter(|&&l| l > 0)
            .map(|&l| l as usize - 1)
            .max()
    }

    /// Iterates over the alive tops.
    ///
    /// ```
    /// # use starplex::algo::simplify::TopSimplices;
    /// let w = TopSimplices::from_tops(3, &[vec![0, 1], vec![1, 2]]).unwrap();
    /// assert_eq!(w.tops().count(), 2);
    /// ```
    pub fn tops(&self) -> impl Iterator<Item = &[u32]> + '_ {
        (0..self.tops.len())
            .filter(|&t| self.tops.lens[t] > 0)
            .map(|t| self.tops.get(t))
    }

    /// Contracts the edge `ab` into `a` (`b` disappears; `a` keeps its coordinates, set them
    /// with [`set_point`](Self::set_point)). Every top through `b` is replaced by its image
    /// (`b` → `a`); an image that is a face of another top is dropped, and a face left without a
    /// top becomes a new, lower-dimensional top. Does *not* check the link condition (call
    /// [`can_contract`](Self::can_contract) first to keep the homology); returns false (and
    /// changes nothing) when `ab` is not an edge.
    ///
    /// ```
    /// # use starplex::algo::simplify::TopSimplices;
    /// // two triangles sharing the edge 1-2: contracting it folds each into an edge
    /// let mut w = TopSimplices::from_tops(4, &[vec![0, 1, 2], vec![1, 3, 2]]).unwrap();
    /// assert!(w.contract(2, 1));
    /// assert_eq!(w.sorted_tops(), vec![vec![0, 2], vec![2, 3]]); // the triangles became edges
    /// assert!(!w.contract(0, 3)); // not an edge
    /// ```
    pub fn contract(&mut self, a: u32, b: u32) -> bool {
        self.contract_with(a, b, false)
    }

    /// [`contract`](Self::contract) right after [`link_condition`](super::link_condition::link_condition)
    /// held for `ab` (in either mode): then no image of a top through `b` alone is a face of
    /// another top when the stars are of one size, and only the images of the tops through
    /// `ab` are tested (see [`keep_uniform_images`](Self::keep_uniform_images)). Debug builds
    /// check the answers against the general test.
    pub(super) fn contract_linked(&mut self, a: u32, b: u32) -> bool {
        self.contract_with(a, b, true)
    }

    fn contract_with(&mut self, a: u32, b: u32, linked: bool) -> bool {
        if a == b || !self.is_alive(a) || !self.is_alive(b) {
            return false;
        }
        if !self
            .star(b)
            .iter()
            .any(|&t| self.tops.get(t as usize).contains(&a))
        {
            return false;
        }
        // Every top through b is edited in place into its image (b -> a, or b dropped when the
        // top also holds a) and keeps its id and origin; images that are faces of another top
        // are removed afterwards. The buffers are reused from call to call.
        let mut sc = std::mem::take(&mut self.scratch);
        sc.ids.clear();
        sc.had_a.clear();
        sc.keep.clear();
        sc.swallowed.clear();
        sc.ids.extend_from_slice(self.vt.row(b as usize));
        self.vt.free(b as usize);
        // the usual cases: every top through a or b is a triangle (a surface) or has the same
        // size (a tetrahedral mesh)
        let len = sc.ids.first().map_or(0, |&t| self.tops.lens[t as usize]);
        let uniform = sc
            .ids
            .iter()
            .chain(self.vt.row(a as usize))
            .all(|&t| self.tops.lens[t as usize] == len);
        for &t in &sc.ids {
            let had_a = self.tops.contract_in(t as usize, a, b);
            sc.had_a.push(had_a);
        }
        self.alive_v[b as usize] = false;
        self.n_alive_v -= 1;
        match (uniform, len) {
            (true, 3) if !linked => self.keep_triangle_images(a, &mut sc),
            (true, 3..) => {
                self.keep_uniform_images(a, linked, &mut sc);
                #[cfg(debug_assertions)]
                {
                    let mut general = ContractScratch {
                        ids: sc.ids.clone(),
                        had_a: sc.had_a.clone(),
                        ..Default::default()
                    };
                    self.keep_images(a, &mut general);
                    assert_eq!(sc.keep, general.keep, "contracting {b} into {a}");
                    assert!(general.swallowed.is_empty());
                }
            }
            _ => self.keep_images(a, &mut sc),
        }
        for &u in &sc.swallowed {
            self.drop_top(u);
        }
        for ((&t, &keep), &had_a) in sc.ids.iter().zip(&sc.keep).zip(&sc.had_a) {
            if !keep {
                self.drop_top(t);
            } else if !had_a {
                self.vt.push(a as usize, t);
            }
        }
        self.scratch = sc;
        true
    }

    /// [`contract`](Self::contract)'s maximality test: which images (`sc.ids`, edited in
    /// place) are no face of another image or of another top through `a` (`sc.keep`), and
    /// which other tops through `a` became a face of a kept image (`sc.swallowed`).
    fn keep_images(&self, a: u32, sc: &mut ContractScratch) {
        let ContractScratch {
            ids,
            keep,
            swallowed,
            others,
            ..
        } = sc;
        // the tops through a that were not through b, listed once
        others.clear();
        others.extend(
            self.vt
                .row(a as usize)
                .iter()
                .copied()
                .filter(|u| !ids.contains(u)),
        );
        for (i, &ti) in ids.iter().enumerate() {
            let t = self.tops.get(ti as usize);
            let dominated_by_image = ids.iter().enumerate().any(|(j, &u)| {
                let u = self.tops.get(u as usize);
                j != i && is_subset(t, u) && (t.len() < u.len() || j < i)
            });
            let dominated = dominated_by_image
                || others
                    .iter()
                    .any(|&u| is_subset(t, self.tops.get(u as usize)));
            keep.push(!dominated);
        }
        for &u in others.iter() {
            let ut = self.tops.get(u as usize);
            let swallowed_by_image = ids.iter().zip(keep.iter()).any(|(&t, &k)| {
                let t = self.tops.get(t as usize);
                k && ut.len() < t.len() && is_subset(ut, t)
            });
            if swallowed_by_image {
                swallowed.push(u);
            }
        }
    }

    /// [`contract`](Self::contract)'s maximality test when every top through `a` and through
    /// the removed vertex had the same size, at least 3 (a surface or a volume mesh): no top through
    /// `a` can be swallowed (none is smaller than an image), and an image is a face of another
    /// top exactly when a top through one of its vertices `x ≠ a` holds it. So each image
    /// looks only through the row of its vertex with the fewest tops (the survivor's row,
    /// which grows as it absorbs, is never scanned), where every alive top through `x` is
    /// listed, the images included. The same answers as [`keep_images`](Self::keep_images).
    ///
    /// `linked`: the link condition of the edge holds. Then the image `aS` of a top `bS` (`k`
    /// vertices) is kept without a look: were it a face of another top, that top would be
    /// `aS` itself, and `S` a simplex of both `Lk(a)` and `Lk(b)` with `k - 1` vertices, too
    /// many for `Lk(ab)` (whose simplices have at most `k - 2`).
    fn keep_uniform_images(&self, a: u32, linked: bool, sc: &mut ContractScratch) {
        let ContractScratch {
            ids,
            had_a,
            keep,
            through_a,
            epoch,
            ..
        } = sc;
        // the tops through a, marked by id, so a row is scanned without reading its tops;
        // after the link condition, only the few images of the tops through ab look, and
        // read the tops of their rows instead
        let marked = !linked;
        if marked {
            self.mark_through(a, ids, through_a, epoch);
        }
        for (i, &ti) in ids.iter().enumerate() {
            if linked && !had_a[i] {
                keep.push(true);
                continue;
            }
            let t = self.tops.get(ti as usize);
            let x = t
                .iter()
                .copied()
                .filter(|&x| x != a)
                .min_by_key(|&x| self.vt.len(x as usize))
                .expect("an image of a top of 3 or more vertices has a vertex besides a");
            let dominated = self.vt.row(x as usize).iter().any(|&u| {
                u != ti
                    && (!marked || through_a[u as usize] == *epoch)
                    && is_subset(t, self.tops.get(u as usize))
                    // equal sets: another top through a, or an image listed before
                    && (t.len() < self.tops.lens[u as usize] as usize || !ids[i..].contains(&u))
            });
            keep.push(!dominated);
        }
    }

    /// Marks the tops through `a` and the images `ids` with a new `epoch` in `through_a`.
    fn mark_through(&self, a: u32, ids: &[u32], through_a: &mut Vec<u32>, epoch: &mut u32) {
        if through_a.len() < self.tops.len() {
            through_a.resize(self.tops.len(), 0);
        }
        if *epoch == u32::MAX {
            through_a.iter_mut().for_each(|e| *e = 0);
            *epoch = 0;
        }
        *epoch += 1;
        for &u in self.vt.row(a as usize).iter().chain(ids.iter()) {
            through_a[u as usize] = *epoch;
        }
    }

    /// [`contract`](Self::contract)'s maximality test when every top through `a` and through
    /// the removed vertex was a triangle: an image of a triangle through both is an edge `ax`,
    /// a face of another top exactly when one of the other triangles through `a` holds `x`; an
    /// image of another triangle is a triangle, a face of another top exactly when it equals
    /// one (as a set); no other top through `a` can be swallowed (all are triangles). The same
    /// answers as [`keep_images`](Self::keep_images), by comparing sorted triples.
    fn keep_triangle_images(&self, a: u32, sc: &mut ContractScratch) {
        let sorted = |t: &[u32]| {
            let mut k = [t[0], t[1], t[2]];
            k.sort_unstable();
            k
        };
        sc.other_keys.clear();
        for &u in self.vt.row(a as usize) {
            if !sc.ids.contains(&u) {
                sc.other_keys.push(sorted(self.tops.get(u as usize)));
            }
        }
        sc.image_keys.clear();
        for (i, &t) in sc.ids.iter().enumerate() {
            let t = self.tops.get(t as usize);
            sc.image_keys.push(if sc.had_a[i] {
                // the edge a-x, kept as [x, x, x]
                let x = if t[0] == a { t[1] } else { t[0] };
                [x; 3]
            } else {
                sorted(t)
            });
        }
        for (i, (&k, &edge)) in sc.image_keys.iter().zip(&sc.had_a).enumerate() {
            let dominated = if edge {
                let x = k[0];
                sc.other_keys.iter().any(|o| o.contains(&x))
                    || sc.image_keys.iter().enumerate().any(|(j, o)| {
                        if sc.had_a[j] {
                            j < i && o[0] == x
                        } else {
                            o.contains(&x)
                        }
                    })
            } else {
                sc.other_keys.contains(&k)
                    || sc.image_keys[..i]
                        .iter()
                        .zip(&sc.had_a)
                        .any(|(o, &e)| !e && *o == k)
            };
            sc.keep.push(!dominated);
        }
    }

    /// Removes top `t` and its entries in the vertex rows.
    fn drop_top(&mut self, t: u32) {
        let s = self.tops.slot(t as usize);
        let l = std::mem::take(&mut self.tops.lens[t as usize]) as usize;
        self.n_alive_tops -= 1;
        for &v in &self.tops.verts[s..s + l] {
            self.vt.remove(v as usize, t);
        }
    }

    /// Moves vertex `v` (no-op without coordinates).
    ///
    /// ```
    /// # use starplex::algo::simplify::TopSimplices;
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// # let mut b = ComplexBuilder::new(2).unwrap();
    /// # for p in [[0.0, 0.0], [1.0, 0.0]] { b.push_vertex(&p).unwrap(); }
    /// # b.push_cell(CellKind::Simplex(1), &[0, 1]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// let mut w = TopSimplices::from_complex(&k).unwrap();
    /// w.set_point(0, &[0.5, 0.0]);
    /// assert_eq!(w.point(0), &[0.5, 0.0]);
    /// ```
    pub fn set_point(&mut self, v: u32, p: &[f64]) {
        let s = self.stride;
        if let Some(dst) = self.coords.get_mut(v as usize * s..(v as usize + 1) * s) {
            dst.copy_from_slice(&p[..s]);
        }
    }

    /// Writes the structure back as an indexed complex: alive vertices renumbered in id order
    /// (0-dimensional tops become isolated vertices), tops in id order. Also returns the new id
    /// of every old vertex (`None` for a contracted one).
    ///
    /// ```
    /// # use starplex::algo::simplify::TopSimplices;
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// # let mut b = ComplexBuilder::new(1).unwrap();
    /// # for x in 0..3 { b.push_vertex(&[x as f64]).unwrap(); }
    /// # b.push_cell(CellKind::Simplex(1), &[0, 1]).unwrap();
    /// # b.push_cell(CellKind::Simplex(1), &[1, 2]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// let mut w = TopSimplices::from_complex(&k).unwrap();
    /// w.contract(1, 2);
    /// let (k2, map) = w.to_complex().unwrap();
    /// assert_eq!((k2.n_vertices(), k2.n_cells()), (2, 1));
    /// assert_eq!(map, vec![Some(0), Some(1), None]);
    /// ```
    ///
    /// # Errors
    /// [`SimplifyError::Complex`] if the builder refuses (not expected).
    pub fn to_complex(&self) -> Result<(IndexedComplex, Vec<Option<u32>>), SimplifyError> {
        self.to_complex_with_points(&self.coords, self.stride)
    }

    /// [`to_complex`](Self::to_complex) with each surviving vertex at its position in
    /// `coords` (`stride` numbers a vertex, by vertex id): for a structure made by
    /// [`from_complex_without_points`](Self::from_complex_without_points). A vertex beyond
    /// `coords` is put at the origin.
    ///
    /// ```
    /// # use starplex::algo::simplify::TopSimplices;
    /// let mut w = TopSimplices::from_tops(3, &[vec![0, 1], vec![1, 2]]).unwrap();
    /// w.contract(1, 2);
    /// let (k, _) = w.to_complex_with_points(&[0.0, 1.0, 2.0], 1).unwrap();
    /// assert_eq!(k.coords(), &[0.0, 1.0]); // vertices 0 and 1 survive
    /// ```
    ///
    /// # Errors
    /// [`SimplifyError::Complex`] if the builder refuses (not expected).
    pub fn to_complex_with_points(
        &self,
        coords: &[f64],
        stride: usize,
    ) -> Result<(IndexedComplex, Vec<Option<u32>>), SimplifyError> {
        let dim = stride.max(1);
        let mut b = ComplexBuilder::new(dim).map_err(SimplifyError::Complex)?;
        let mut map = vec![None; self.n_vertices()];
        let zero = vec![0.0; dim];
        for (v, slot) in map.iter_mut().enumerate() {
            if self.alive_v[v] {
                let p = if stride == 0 {
                    &zero[..]
                } else {
                    coords
                        .get(v * stride..(v + 1) * stride)
                        .unwrap_or(&zero[..])
                };
                *slot = Some(b.push_vertex(p).map_err(SimplifyError::Complex)?.0);
            }
        }
        let mut cell = Vec::new();
        for t in self.tops() {
            if t.len() < 2 {
                continue;
            }
            cell.clear();
            cell.extend(t.iter().map(|&v| map[v as usize].unwrap_or(u32::MAX)));
            let kind = CellKind::simplex(t.len() - 1).ok_or_else(|| SimplifyError::BadTop {
                top: 0,
                reason: "dimension too high".into(),
            })?;
            b.push_cell(kind, &cell).map_err(SimplifyError::Complex)?;
        }
        let opts = BuildOptions {
            trust_maximality: true,
            ..Default::default()
        };
        let (k, _) = b.build(&opts).map_err(SimplifyError::Complex)?;
        Ok((k, map))
    }

    /// The input top that top `t` is the image of (through any number of contractions): the
    /// cell id of the input for [`from_structure`](Self::from_structure) and
    /// [`from_complex`](Self::from_complex), the list position for
    /// [`from_tops`](Self::from_tops); `None` for a vertex top added for an isolated vertex
    /// or an unknown id. Cell attributes follow their cells this way.
    ///
    /// ```
    /// # use starplex::algo::simplify::TopSimplices;
    /// let mut w = TopSimplices::from_tops(4, &[vec![0, 1, 2], vec![1, 3, 2]]).unwrap();
    /// w.contract(1, 0); // [0, 1, 2] becomes the edge [1, 2], dominated by [1, 3, 2]
    /// let t = (0..8).find(|&t| w.top(t) == [1, 3, 2]).unwrap();
    /// assert_eq!(w.origin(t), Some(1));
    /// ```
    pub fn origin(&self, t: u32) -> Option<u32> {
        if t as usize >= self.tops.len() {
            return None;
        }
        let whole = self.whole_id.get(t as usize).copied().unwrap_or(t);
        ((whole as usize) < self.n_input_tops).then_some(whole)
    }

    /// The origins ([`origin`](Self::origin)) of the cells that
    /// [`to_complex`](Self::to_complex) writes, in its cell order (alive tops of at least two
    /// vertices, in id order): gather the input's cell attributes with them.
    ///
    /// ```
    /// # use starplex::algo::simplify::TopSimplices;
    /// let mut w = TopSimplices::from_tops(4, &[vec![0, 1], vec![1, 2], vec![2, 3]]).unwrap();
    /// w.contract(1, 2);
    /// assert_eq!(w.cell_origins(), vec![Some(0), Some(2)]);
    /// ```
    pub fn cell_origins(&self) -> Vec<Option<u32>> {
        (0..self.tops.len() as u32)
            .filter(|&t| self.tops.lens[t as usize] >= 2)
            .map(|t| self.origin(t))
            .collect()
    }

    /// The alive tops as sorted vertex lists, the list sorted (for comparisons in tests).
    ///
    /// ```
    /// # use starplex::algo::simplify::TopSimplices;
    /// let w = TopSimplices::from_tops(3, &[vec![2, 0, 1]]).unwrap();
    /// assert_eq!(w.sorted_tops(), vec![vec![0, 1, 2]]);
    /// ```
    pub fn sorted_tops(&self) -> Vec<Vec<u32>> {
        let mut out: Vec<Vec<u32>> = self
            .tops()
            .map(|t| {
                let mut t = t.to_vec();
                t.sort_unstable();
                t
            })
            .collect();
        out.sort();
        out
    }

    /// The vertex ids of the alive vertices, as `VertexId`s.
    ///
    /// ```
    /// # use starplex::algo::simplify::TopSimplices;
    /// let mut w = TopSimplices::from_tops(2, &[vec![0, 1]]).unwrap();
    /// w.contract(0, 1);
    /// assert_eq!(w.alive_vertices(), vec![starplex::ids::VertexId(0)]);
    /// ```
    pub fn alive_vertices(&self) -> Vec<VertexId> {
        (0..self.n_vertices() as u32)
            .filter(|&v| self.alive_v[v as usize])
            .map(VertexId)
            .collect()
    }

    /// Renumbers the vertices and moves the tops to other slots, keeping every top's origin:
    /// vertex `v` becomes `to_new[v]`, and slot `i` receives the top of slot `order[i]` (both
    /// permutations). The rows are made again from the tops. [`simplify_qem`] numbers the
    /// vertices and the tops of a mesh along a space-filling curve with it before it starts,
    /// so that a contraction's neighbourhood is a few cache lines instead of scattered over
    /// the arrays, and numbers them back when it is done.
    ///
    /// [`simplify_qem`]: super::qem::simplify_qem
    pub(super) fn permute(&mut self, to_new: &[u32], order: &[u32]) {
        let n = self.n_vertices();
        debug_assert_eq!((to_new.len(), order.len()), (n, self.tops.len()));
        let mut verts = Vec::with_capacity(self.tops.verts.len());
        let mut lens = Vec::with_capacity(order.len());
        let mut whole = Vec::with_capacity(order.len());
        for &o in order {
            let t = self.tops.get(o as usize);
            verts.extend(t.iter().map(|&v| to_new[v as usize]));
            lens.push(t.len() as u8);
            whole.push(self.whole_id.get(o as usize).copied().unwrap_or(o));
        }
        // a whole structure numbered back has its own slots again
        if whole.iter().enumerate().all(|(i, &w)| w as usize == i) {
            whole = Vec::new();
        }
        self.whole_id = whole;
        self.vt = Rows::default();
        self.tops = FlatTops::new(verts, lens);
        self.vt = self.tops.rows(n);
        let moved = |old: &[bool]| {
            let mut new = vec![false; n];
            for (v, &x) in old.iter().enumerate() {
                new[to_new[v] as usize] = x;
            }
            new
        };
        self.alive_v = moved(&self.alive_v);
        self.locked = moved(&self.locked);
        if !self.coords.is_empty() {
            let s = self.stride;
            let mut c = vec![0.0; self.coords.len()];
            for (v, p) in self.coords.chunks_exact(s).enumerate() {
                let at = to_new[v] as usize * s;
                c[at..at + s].copy_from_slice(p);
            }
            self.coords = c;
        }
        self.scratch = ContractScratch::default();
    }
}

/// The part of a [`TopSimplices`] cut out for one block of vertices ([`TopSimplices::cut`]):
/// the stars of the block's *inner* vertices (those whose every top lies in the block), in a
/// structure of its own whose vertex `i` is the block's `i`-th vertex.
pub(super) struct Part {
    /// The part: tops in global id order (each top's id in the whole structure is its
    /// `whole_id`), vertices numbered within the block.
    pub(super) w: TopSimplices,
    /// Per block vertex: inner (alive, and every top through it lies in the block).
    pub(super) inner: FixedBitSet,
}

impl TopSimplices {
    /// Cuts out the stars of the inner vertices of a block: `verts` are its vertices in
    /// increasing id order, at positions `first..` of the blocks' order (`slot_of` gives every
    /// alive vertex's position there, so a vertex is in the block when its position less
    /// `first` is below `verts.len()`, and that difference is its number in the part).
    /// A contraction of two inner vertices reads and writes only the part (the tops through
    /// them and the rows of those tops' vertices, all in the block), so disjoint blocks can be
    /// contracted at the same time and pasted back ([`paste`](Self::paste)).
    pub(super) fn cut(&self, verts: &[u32], slot_of: &[u32], first: u32) -> Part {
        let local = |u: u32| slot_of[u as usize].wrapping_sub(first);
        let size = verts.len() as u32;
        let mut inner = FixedBitSet::with_capacity(verts.len());
        for (i, &v) in verts.iter().enumerate() {
            let is_inner = self.is_alive(v)
                && self
                    .star(v)
                    .iter()
                    .all(|&t| self.top(t).iter().all(|&u| local(u) < size));
            inner.set(i, is_inner);
        }
        // the tops of the inner stars, each listed once: by its first inner vertex
        let mut ids: Vec<u32> = Vec::new();
        for i in inner.ones() {
            for &t in self.star(verts[i]) {
                let first = self
                    .top(t)
                    .iter()
                    .map(|&u| local(u) as usize)
                    .filter(|&j| inner.contains(j))
                    .min();
                if first == Some(i) {
                    ids.push(t);
                }
            }
        }
        ids.sort_unstable();
        let mut tverts = Vec::with_capacity(ids.len() * self.tops.width.max(1));
        let mut lens = Vec::with_capacity(ids.len());
        for &t in &ids {
            let top = self.top(t);
            tverts.extend(top.iter().map(|&u| local(u)));
            lens.push(top.len() as u8);
        }
        let mut w = Self::assemble(
            verts.len(),
            FlatTops::new(tverts, lens),
            self.n_input_tops,
            Vec::new(),
            0,
        );
        debug_assert!(
            self.whole_id.is_empty(),
            "a part is cut from a whole structure"
        );
        w.whole_id = ids;
        for (i, &v) in verts.iter().enumerate() {
            w.alive_v[i] = self.is_alive(v);
            w.locked[i] = self.is_locked(v);
        }
        w.n_alive_v = w.alive_v.iter().filter(|&&a| a).count();
        w.labels = Arc::clone(&self.labels);
        Part { w, inner }
    }

    /// Writes a contracted part back (the inverse of [`cut`](Self::cut) for block `verts`):
    /// the part's tops into their slots (removed ones removed), the inner vertices' rows, the
    /// part's entries of the other block vertices' rows, the vertices contracted away.
    /// `in_part` is a cleared bitset over the tops (left cleared).
    pub(super) fn paste(&mut self, verts: &[u32], part: &Part, in_part: &mut FixedBitSet) {
        let p = &part.w;
        let mut buf = Vec::new();
        for (lt, &g) in p.whole_id.iter().enumerate() {
            in_part.insert(g as usize);
            let g = g as usize;
            let l = p.tops.lens[lt];
            if l == 0 {
                self.tops.lens[g] = 0;
                self.n_alive_tops -= 1;
                continue;
            }
            let s = self.tops.slot(g);
            for (i, &u) in p.tops.get(lt).iter().enumerate() {
                self.tops.verts[s + i] = verts[u as usize];
            }
            self.tops.lens[g] = l;
        }
        // the rows of the vertices contracted away are given up before the survivors' rows
        // grow, so that a row moving to the end finds their room
        for (i, &v) in verts.iter().enumerate() {
            if self.alive_v[v as usize] && !p.alive_v[i] {
                self.alive_v[v as usize] = false;
                self.n_alive_v -= 1;
                self.vt.free(v as usize);
            } else if part.inner.contains(i) {
                self.vt.clear(v as usize);
            } else {
                self.vt
                    .retain(v as usize, |t| !in_part.contains(t as usize));
            }
        }
        for (i, &v) in verts.iter().enumerate() {
            if p.alive_v[i] {
                buf.clear();
                buf.extend(p.vt.row(i).iter().map(|&lt| p.whole_id[lt as usize]));
                self.vt.extend(v as usize, &buf);
            }
        }
        for &g in &p.whole_id {
            in_part.set(g as usize, false);
        }
    }

    /// Number of top slots (alive or removed): the range of top ids.
    pub(super) fn n_top_slots(&self) -> usize {
        self.tops.len()
    }
}

/// True when every vertex of `s` is in `t` (both without repetition, any order).
///
/// ```
/// use starplex::algo::simplify::tops::is_subset;
/// assert!(is_subset(&[2, 0], &[0, 1, 2]));
/// assert!(!is_subset(&[3], &[0, 1, 2]));
/// ```
pub fn is_subset(s: &[u32], t: &[u32]) -> bool {
    s.len() <= t.len() && s.iter().all(|v| t.contains(v))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testkit::XorShift;

    /// `from_complex` (the complex's blocks and vertex index, side by side) builds what the
    /// generic `from_structure` builds: the same tops in the same order, the same rows, the
    /// same origins, vertices in no cell as 0-dimensional tops.
    #[test]
    fn from_complex_is_from_structure() {
        let mut r = XorShift::new(7);
        let mut b = ComplexBuilder::new(3).unwrap();
        for i in 0..40 {
            b.push_vertex(&[i as f64, (i * i % 7) as f64, 0.0]).unwrap();
        }
        for _ in 0..60 {
            let k = 2 + r.below(3) as usize;
            let mut c: Vec<u32> = Vec::new();
            while c.len() < k {
                let v = r.below(36) as u32; // 36..40 stay in no cell
                if !c.contains(&v) {
                    c.push(v);
                }
            }
            b.push_cell(CellKind::simplex(k - 1).unwrap(), &c).unwrap();
        }
        let opts = BuildOptions {
            drop_duplicates: true,
            drop_face_cells: true,
            ..Default::default()
        };
        let k = b.build(&opts).unwrap().0;
        let fast = TopSimplices::from_complex(&k).unwrap();
        let slow = TopSimplices::from_structure(&k, k.coords(), k.ambient_dim()).unwrap();
        assert_eq!(fast.n_top_slots(), slow.n_top_slots());
        assert!(fast.n_top_slots() > 4 + k.n_cells() / 2);
        for t in 0..fast.n_top_slots() as u32 {
            assert_eq!(fast.top(t), slow.top(t));
        }
        for v in 0..40 {
            assert_eq!(fast.star(v), slow.star(v), "{v}");
        }
        assert_eq!(fast.cell_origins(), slow.cell_origins());
        assert_eq!(fast.coords, slow.coords);
    }

    /// The triangle maximality test of `contract` decides as the general one, on random pure
    /// triangle complexes (boundaries, non-manifold edges, duplicates excluded) and every edge,
    /// also after contractions.
    #[test]
    fn triangle_keep_is_the_general_keep() {
        fast_keep_is_the_general_keep(3, TopSimplices::keep_triangle_images);
    }

    /// The same for the test of stars of one size (triangles, tetrahedra, 4-simplices).
    #[test]
    fn uniform_keep_is_the_general_keep() {
        let uniform =
            |w: &TopSimplices, a, sc: &mut ContractScratch| w.keep_uniform_images(a, false, sc);
        fast_keep_is_the_general_keep(3, uniform);
        fast_keep_is_the_general_keep(4, uniform);
        fast_keep_is_the_general_keep(5, uniform);
    }

    /// Random pure complexes of `k`-vertex tops; while the stars of an edge are all of that
    /// size, `fast` and the general test judge its images alike.
    fn fast_keep_is_the_general_keep(k: usize, fast: fn(&TopSimplices, u32, &mut ContractScratch)) {
        let mut r = XorShift::new(0x5eed + k as u64);
        let mut compared = 0;
        for _ in 0..400 {
            let n = k as u32 + 1 + r.below(5) as u32;
            let mut tops: Vec<Vec<u32>> = Vec::new();
            for _ in 0..1 + r.below(12) {
                let mut t: Vec<u32> = Vec::new();
                while t.len() < k {
                    let v = r.below(n as u64) as u32;
                    if !t.contains(&v) {
                        t.push(v);
                    }
                }
                let mut key = t.clone();
                key.sort_unstable();
                if !tops.iter().any(|u| {
                    let mut k = u.clone();
                    k.sort_unstable();
                    k == key
                }) {
                    tops.push(t);
                }
            }
            let mut w = TopSimplices::from_tops(n as usize, &tops).unwrap();
            // contract random edges while the stars are all of size k
            for _ in 0..4 {
                let edges: Vec<(u32, u32)> = (0..n)
                    .filter(|&a| w.is_alive(a))
                    .flat_map(|a| w.neighbours(a).into_iter().map(move |b| (a, b)))
                    .collect();
                if edges.is_empty() {
                    break;
                }
                let (a, b) = edges[r.below(edges.len() as u64) as usize];
                let uniform = w
                    .star(a)
                    .iter()
                    .chain(w.star(b))
                    .all(|&t| w.top(t).len() == k);
                if uniform {
                    // the images, edited as contract does, judged both ways
                    let mut c = w.clone();
                    let mut sc = ContractScratch::default();
                    let st_b = c.vt.row(b as usize).to_vec();
                    c.vt.free(b as usize);
                    for &t in &st_b {
                        let had_a = c.tops.contract_in(t as usize, a, b);
                        sc.ids.push(t);
                        sc.had_a.push(had_a);
                    }
                    let mut general = ContractScratch {
                        ids: sc.ids.clone(),
                        had_a: sc.had_a.clone(),
                        ..Default::default()
                    };
                    fast(&c, a, &mut sc);
                    c.keep_images(a, &mut general);
                    assert_eq!(sc.keep, general.keep, "{a}-{b} in {:?}", w.sorted_tops());
                    assert!(general.swallowed.is_empty());
                    compared += 1;
                }
                assert!(w.contract(a, b));
                let st = w.sorted_tops();
                assert!(TopSimplices::from_tops(n as usize, &st).is_ok(), "{st:?}");
            }
        }
        assert!(compared > 200, "{compared}");
    }
}
