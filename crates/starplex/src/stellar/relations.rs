//! Relations extracted leaf by leaf, answered in the input's numbering: VT (R_{0,top}), VV,
//! vertex links, boundary p-faces of every dimension (simplices and CP cells), and top-cell
//! adjacency across (d-1)-faces; plus the [`topo`](crate::topo) traits.
//!
//! Every face is handled in exactly one leaf: the leaf owning its smallest vertex (tree
//! numbering), which lists every top cell containing the face, so multiplicities are exact.
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
use crate::cell::{faces_of, listed_sign, oriented_facets_of, CellKind};
use crate::csr::Csr;
use crate::ids::{CellId, LeafId, TreeVertexId, VertexId};
use crate::topo::link::{LinkError, VertexLink};
use crate::topo::naive::edge_neighbours;
use crate::topo::{TopCells, VertexAdjacency, VertexStar};

/// Default budget of (cell, face) pairs for face extraction.
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
/// use starplex::stellar::relations::FACE_BUDGET;
/// // `p_faces` uses this budget
/// assert_eq!(t.p_faces_with_budget(1, FACE_BUDGET).unwrap(), t.p_faces(1).unwrap());
/// assert!(t.p_faces_with_budget(1, 1).is_err());
/// ```
pub const FACE_BUDGET: u128 = 2_000_000_000;

/// Faces of one dimension: vertex lists (input ids, sorted) and how many top cells contain
/// each face.
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
/// let edges = t.p_faces(1).unwrap();
/// assert_eq!(edges.len(), 5);
/// // the diagonal {1,2} is in both triangles, the other edges in one
/// let i = (0..edges.len()).find(|&i| edges.faces.row(i) == [1, 2]).unwrap();
/// assert_eq!(edges.n_cofaces[i], 2);
/// assert_eq!(edges.n_cofaces.iter().sum::<u32>(), 6);
/// ```
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct FaceList {
    /// Face `i` is `faces.row(i)`.
    pub faces: Csr,
    /// Number of top cells (of any dimension) that contain face `i`.
    pub n_cofaces: Vec<u32>,
}

impl FaceList {
    /// Number of faces.
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
    /// assert_eq!(t.p_faces(0).unwrap().len(), 4);
    /// assert_eq!(t.p_faces(2).unwrap().len(), 2);
    /// ```
    pub fn len(&self) -> usize {
        self.n_cofaces.len()
    }
    /// True without faces.
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
    /// use starplex::stellar::FaceList;
    /// assert!(FaceList::default().is_empty());
    /// assert!(!t.p_faces(1).unwrap().is_empty());
    /// ```
    pub fn is_empty(&self) -> bool {
        self.n_cofaces.is_empty()
    }
}

/// Sorted face keys with payloads, grouped by key. Keys up to 4 vertices are packed in a
/// `u128`; longer ones are sorted as slices.
#[derive(Default)]
pub(crate) struct FaceKeys {
    w: usize,
    flat: Vec<u32>,
    payload: Vec<u64>,
    small: Vec<(u128, u64)>,
    /// Keys of three vertices with buckets: (first vertex, the other two, payload).
    mid: Vec<(u32, u64, u64)>,
    mid_tmp: Vec<(u64, u64)>,
    /// Unordered grouping: hash table (key, group + 1), group of each record, group sizes
    /// (then cursors), first record of each group, table slot of each group.
    ukeys: Vec<u64>,
    uvals: Vec<u32>,
    ugid: Vec<u32>,
    ucount: Vec<u32>,
    ufirst: Vec<u32>,
    uslot: Vec<u32>,
    tiny: Vec<(u64, u64)>,
    tiny_tmp: Vec<(u64, u64)>,
    small_tmp: Vec<(u128, u64)>,
    counts: Vec<u32>,
    buckets: Option<(u32, u32)>,
    prefix: Option<u32>,
    order: Vec<u32>,
    key: Vec<u32>,
    pays: Vec<u64>,
}

const PAD: u32 = u32::MAX;

impl FaceKeys {
    pub(crate) fn clear(&mut self, w: usize) {
        self.w = w;
        self.prefix = None;
        self.buckets = None;
        self.flat.clear();
        self.payload.clear();
        self.small.clear();
        self.mid.clear();
        self.tiny.clear();
    }
    /// Every key pushed shares this leading entry, which is not stored but is reported by
    /// [`for_each_group`](Self::for_each_group).
    pub(crate) fn set_prefix(&mut self, p: Option<u32>) {
        self.prefix = p;
    }
    /// Every stored key starts with a vertex in `lo..hi` (the leaf's own range): grouping
    /// then buckets by that vertex before sorting each small bucket (same order as a sort).
    pub(crate) fn set_buckets(&mut self, r: Option<(u32, u32)>) {
        self.buckets = r;
    }
    /// Pushes a sorted key (at most `w` ids).
    #[inline]
    pub(crate) fn push(&mut self, key: &[u32], payload: u64) {
        debug_assert!(key.len() <= self.w);
        if self.w <= 2 {
            let a = key.first().copied().unwrap_or(PAD) as u64;
            let b = key.get(1).copied().unwrap_or(PAD) as u64;
            self.tiny.push(((a << 32) | b, payload));
        } else if self.w == 3 && self.buckets.is_some() {
            let a = key.first().copied().unwrap_or(PAD);
            let b = key.get(1).copied().unwrap_or(PAD) as u64;
            let c = key.get(2).copied().unwrap_or(PAD) as u64;
            self.mid.push((a, (b << 32) | c, payload));
        } else if self.w <= 4 {
            let mut x: u128 = 0;
            for i in 0..4 {
                x = (x << 32) | key.get(i).copied().unwrap_or(PAD) as u128;
            }
            self.small.push((x, payload));
        } else {
            self.flat.extend_from_slice(key);
            self.flat
                .extend(std::iter::repeat_n(PAD, self.w - key.len()));
            self.payload.push(payload);
        }
    }
    /// Calls `f(key, payloads)` for every distinct key, in key order.
    pub(crate) fn for_each_group(&mut self, mut f: impl FnMut(&[u32], &[u64])) {
        if self.w <= 2 {
            match self.buckets {
                Some((lo, hi)) => bucket_sort(
                    &mut self.tiny,
                    &mut self.tiny_tmp,
                    &mut self.counts,
                    lo,
                    hi,
                    |x| (x.0 >> 32) as u32,
                ),
                None => self.tiny.sort_unstable(),
            }
            let mut i = 0;
            while i < self.tiny.len() {
                let k = self.tiny[i].0;
                let mut j = i;
                self.pays.clear();
                while j < self.tiny.len() && self.tiny[j].0 == k {
                    self.pays.push(self.tiny[j].1);
                    j += 1;
                }
                self.key.clear();
                self.key.extend(self.prefix);
                for x in [(k >> 32) as u32, k as u32] {
                    if x != PAD {
                        self.key.push(x);
                    }
                }
                f(&self.key, &self.pays);
                i = j;
            }
        } else if self.w == 3 && self.buckets.is_some() {
            self.mid_groups(&mut f);
        } else if self.w <= 4 {
            match self.buckets {
                Some((lo, hi)) => bucket_sort(
                    &mut self.small,
                    &mut self.small_tmp,
                    &mut self.counts,
                    lo,
                    hi,
                    |x| (x.0 >> 96) as u32,
                ),
                None => self.small.sort_unstable(),
            }
            let mut i = 0;
            while i < self.small.len() {
                let k = self.small[i].0;
                let mut j = i;
                self.pays.clear();
                while j < self.small.len() && self.small[j].0 == k {
                    self.pays.push(self.small[j].1);
                    j += 1;
                }
                self.key.clear();
                self.key.extend(self.prefix);
                for s in (0..4).rev() {
                    let x = (k >> (32 * s)) as u32;
                    if x != PAD {
                        self.key.push(x);
                    }
                }
                f(&self.key, &self.pays);
                i = j;
            }
        } else {
            let w = self.w;
            let n = self.payload.len();
            self.order.clear();
            self.order.extend(0..n as u32);
            let flat = &self.flat;
            let payload = &self.payload;
            self.order.sort_unstable_by(|&a, &b| {
                flat[a as usize * w..a as usize * w + w]
                    .cmp(&flat[b as usize * w..b as usize * w + w])
                    .then(payload[a as usize].cmp(&payload[b as usize]))
            });
            let mut i = 0;
            while i < n {
                let a = self.order[i] as usize;
                let ka = &flat[a * w..a * w + w];
                let mut j = i;
                self.pays.clear();
                while j < n {
                    let b = self.order[j] as usize;
                    if &flat[b * w..b * w + w] != ka {
                        break;
                    }
                    self.pays.push(payload[b]);
                    j += 1;
                }
                self.key.clear();
                self.key.extend(self.prefix);
                self.key.extend(ka.iter().copied().filter(|&x| x != PAD));
                f(&self.key, &self.pays);
                i = j;
            }
        }
    }
}

impl FaceKeys {
    /// Like [`for_each_group`](Self::for_each_group), but groups (and the payloads inside a
    /// group) may come in any order that depends only on the pushes: for keys of three
    /// vertices with buckets, each bucket is grouped with a small hash table instead of
    /// sorted.
    pub(crate) fn for_each_group_unordered(&mut self, mut f: impl FnMut(&[u32], &[u64])) {
        if !(self.w == 3 && self.buckets.is_some()) {
            return self.for_each_group(f);
        }
        let (lo, hi) = self.buckets.expect("buckets");
        let n = hi.saturating_sub(lo) as usize;
        if n == 0 || !self.mid.iter().all(|x| x.0 >= lo && x.0 < hi) {
            return self.mid_groups(&mut f);
        }
        self.scatter_mid(lo, n);
        let (counts, tmp) = (&self.counts, &mut self.mid_tmp);
        let (hk, hv, gid, gcount, firsts_slot) = (
            &mut self.ukeys,
            &mut self.uvals,
            &mut self.ugid,
            &mut self.ucount,
            &mut self.uslot,
        );
        let mut start = 0usize;
        for (b, &end) in counts[..n].iter().enumerate() {
            let end = end as usize;
            let bucket = &tmp[start..end];
            start = end;
            let len = bucket.len();
            if len == 0 {
                continue;
            }
            // group ids in first-occurrence order
            let cap = (2 * len).next_power_of_two().max(8);
            let shift = 64 - cap.trailing_zeros();
            let mask = cap - 1;
            if hk.len() < cap {
                hk.resize(cap, 0);
                hv.resize(cap, 0);
            }
            gid.clear();
            gcount.clear();
            firsts_slot.clear();
            for &(r, _) in bucket {
                let mut h = (r.wrapping_mul(0x9E37_79B9_7F4A_7C15) >> shift) as usize;
                let g = loop {
                    if hv[h] == 0 {
                        hk[h] = r;
                        hv[h] = gcount.len() as u32 + 1;
                        gcount.push(0);
                        firsts_slot.push(h as u32);
                        break gcount.len() - 1;
                    }
                    if hk[h] == r {
                        break hv[h] as usize - 1;
                    }
                    h = (h + 1) & mask;
                };
                gcount[g] += 1;
                gid.push(g as u32);
            }
            // empty the table: the first record of each group found its slot
            for &g in firsts_slot.iter() {
                hv[g as usize] = 0;
            }
            // payloads by group (counting sort on the group id)
            let ng = gcount.len();
            let mut acc = 0u32;
            for c in gcount.iter_mut() {
                let x = *c;
                *c = acc;
                acc += x;
            }
            self.pays.clear();
            self.pays.resize(len, 0);
            let mut firsts = std::mem::take(&mut self.ufirst);
            firsts.clear();
            firsts.resize(ng, 0);
            for (i, &(_, pay)) in bucket.iter().enumerate() {
                let g = gid[i] as usize;
                let pos = gcount[g] as usize;
                self.pays[pos] = pay;
                gcount[g] += 1;
                if firsts[g] == 0 {
                    firsts[g] = i as u32 + 1;
                }
            }
            let mut s = 0usize;
            for g in 0..ng {
                let e = gcount[g] as usize;
                let r = bucket[firsts[g] as usize - 1].0;
                self.key.clear();
                self.key.extend(self.prefix);
                for x in [lo + b as u32, (r >> 32) as u32, r as u32] {
                    if x != PAD {
                        self.key.push(x);
                    }
                }
                f(&self.key, &self.pays[s..e]);
                s = e;
            }
            self.ufirst = firsts;
        }
    }

    /// Counting sort of the three-vertex records by first vertex (all in `lo..lo + n`): the
    /// (other two, payload) pairs land in `mid_tmp`, bucket by bucket, and `counts[b]` ends
    /// as the end of bucket `b`.
    fn scatter_mid(&mut self, lo: u32, n: usize) {
        let counts = &mut self.counts;
        counts.clear();
        counts.resize(n + 1, 0);
        for x in &self.mid {
            counts[(x.0 - lo) as usize + 1] += 1;
        }
        for i in 0..n {
            counts[i + 1] += counts[i];
        }
        let tmp = &mut self.mid_tmp;
        tmp.clear();
        tmp.resize(self.mid.len(), (0, 0));
        for x in &self.mid {
            let b = (x.0 - lo) as usize;
            tmp[counts[b] as usize] = (x.1, x.2);
            counts[b] += 1;
        }
    }

    /// [`for_each_group`](Self::for_each_group) for keys of three vertices with buckets: a
    /// counting sort by first vertex, then each bucket's 16-byte (other two, payload) records
    /// sorted. Same order as sorting the whole keys.
    fn mid_groups(&mut self, f: &mut impl FnMut(&[u32], &[u64])) {
        let (lo, hi) = self.buckets.expect("buckets");
        let n = hi.saturating_sub(lo) as usize;
        let in_range = n > 0 && self.mid.iter().all(|x| x.0 >= lo && x.0 < hi);
        let mut emit = |key: &mut Vec<u32>, pays: &[u64], prefix: Option<u32>, a: u32, r: u64| {
            key.clear();
            key.extend(prefix);
            for x in [a, (r >> 32) as u32, r as u32] {
                if x != PAD {
                    key.push(x);
                }
            }
            f(key, pays);
        };
        if !in_range {
            self.mid.sort_unstable();
            let mut i = 0;
            while i < self.mid.len() {
                let (a, r, _) = self.mid[i];
                self.pays.clear();
                let mut j = i;
                while j < self.mid.len() && self.mid[j].0 == a && self.mid[j].1 == r {
                    self.pays.push(self.mid[j].2);
                    j += 1;
                }
                emit(&mut self.key, &self.pays, self.prefix, a, r);
                i = j;
            }
            return;
        }
        self.scatter_mid(lo, n);
        let (counts, tmp) = (&self.counts, &mut self.mid_tmp);
        // counts[b] is now the end of bucket b
        let mut start = 0usize;
        for (b, &end) in counts[..n].iter().enumerate() {
            let end = end as usize;
            let bucket = &mut tmp[start..end];
            if bucket.len() > 1 {
                bucket.sort_unstable();
            }
            let mut i = 0;
            while i < bucket.len() {
                let r = bucket[i].0;
                self.pays.clear();
                let mut j = i;
                while j < bucket.len() && bucket[j].0 == r {
                    self.pays.push(bucket[j].1);
                    j += 1;
                }
                emit(&mut self.key, &self.pays, self.prefix, lo + b as u32, r);
                i = j;
            }
            start = end;
        }
    }
}

/// Sorts `v` by bucketing on `first(x)` (which must lie in `lo..hi`, else it falls back to a
/// plain sort) and sorting each bucket; `T`'s order must start with `first`.
fn bucket_sort<T: Copy + Ord>(
    v: &mut Vec<T>,
    tmp: &mut Vec<T>,
    counts: &mut Vec<u32>,
    lo: u32,
    hi: u32,
    first: impl Fn(&T) -> u32,
) {
    let n = hi.saturating_sub(lo) as usize;
    if v.len() < 64 || n == 0 {
        v.sort_unstable();
        return;
    }
    counts.clear();
    counts.resize(n + 1, 0);
    for x in v.iter() {
        let b = first(x);
        if b < lo || b >= hi {
            v.sort_unstable();
            return;
        }
        counts[(b - lo) as usize + 1] += 1;
    }
    for i in 0..n {
        counts[i + 1] += counts[i];
    }
    tmp.clear();
    tmp.resize(v.len(), v[0]);
    for x in v.iter() {
        let b = (first(x) - lo) as usize;
        tmp[counts[b] as usize] = *x;
        counts[b] += 1;
    }
    // counts[b] is now the end of bucket b
    let mut start = 0usize;
    for &end in &counts[..n] {
        let end = end as usize;
        if end - start > 1 {
            tmp[start..end].sort_unstable();
        }
        start = end;
    }
    std::mem::swap(v, tmp);
}

/// Reusable buffers of [`StellarTree::leaf_vt_rows`].
#[derive(Default)]
struct VtRows {
    cells: Vec<u32>,
    off: Vec<u32>,
    rows: Vec<u32>,
}

/// Sorts a nearly sorted slice: insertion sort (O(n + inversions)) when short, else the
/// library sort.
#[inline]
fn insertion_sort(v: &mut [u32]) {
    if v.len() > 48 {
        v.sort_unstable();
        return;
    }
    for i in 1..v.len() {
        let x = v[i];
        let mut j = i;
        while j > 0 && v[j - 1] > x {
            v[j] = v[j - 1];
            j -= 1;
        }
        v[j] = x;
    }
}

/// Largest number of vertices of a `p`-face of `kind`.
pub(crate) fn face_width(kind: CellKind, p: usize) -> usize {
    if kind.is_simplex() {
        p + 1
    } else {
        kind.cp_faces(p)
            .map_or(0, |t| t.iter().map(|f| f.len()).max().unwrap_or(0))
    }
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
            .map(super::code_kind)
            .collect()
    }

    /// Rows of per-leaf results (rows of the leaf's vertices in tree order) reassembled into a
    /// [`Csr`] keyed by input vertex.
    fn gather_vertex_rows(&self, per_leaf: Vec<(Vec<u32>, Vec<u32>)>) -> Csr {
        let nv = self.n_vertices();
        let mut offsets = vec![0u32; nv + 1];
        let mut tv = 0usize;
        for (lens, _) in &per_leaf {
            for &len in lens {
                offsets[self.v_orig[tv] as usize + 1] = len;
                tv += 1;
            }
        }
        for i in 0..nv {
            offsets[i + 1] += offsets[i];
        }
        let mut targets = vec![0u32; offsets[nv] as usize];
        let mut tv = 0usize;
        for (lens, data) in &per_leaf {
            let mut pos = 0usize;
            for &len in lens {
                let o = offsets[self.v_orig[tv] as usize] as usize;
                let len = len as usize;
                targets[o..o + len].copy_from_slice(&data[pos..pos + len]);
                pos += len;
                tv += 1;
            }
        }
        Csr { offsets, targets }
    }

    /// Calls `f(v, cells)` for every tree vertex `v` of leaf `l`, cells = VT(v) in input ids,
    /// sorted. The rows are bucketed straight in input ids (`buf` holds the decoded cells and
    /// the rows); each is nearly sorted (a few increasing runs: cells are reindexed by leaf
    /// tuple, input order inside), so an insertion sort finishes it.
    fn leaf_vt_rows(&self, l: LeafId, buf: &mut VtRows, mut f: impl FnMut(u32, &[u32])) {
        let r = self.leaf_vertices(l);
        buf.cells.clear();
        super::sre::decode(self.leaf_encoded_cells(l), &mut buf.cells);
        let c_orig = &self.c_orig;
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
            insertion_sort(row);
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
        let mut e = super::ExpandedLeaf::default();
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
    /// f-vector or why it could not be computed.
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
    /// let f = t.link_f_vectors_all(1_000_000);
    /// assert_eq!(f[1].as_ref().unwrap(), &vec![3, 2]);
    /// ```
    pub fn link_f_vectors_all(&self, budget: u128) -> Vec<Result<Vec<u64>, LinkError>> {
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

    /// Upper bound of (cell, p-face) pairs visited by [`p_faces`](Self::p_faces).
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
    /// assert_eq!(t.face_visits(1), 6);
    /// ```
    pub fn face_visits(&self, p: usize) -> u128 {
        if let Some(kind) = self.cells.uniform {
            return kind.n_faces(p).saturating_mul(self.cells.n as u128);
        }
        self.cells
            .kinds
            .iter()
            .map(|&c| super::code_kind(c).n_faces(p))
            .fold(0u128, |a, x| a.saturating_add(x))
    }

    fn check_budget(&self, p: usize, budget: u128) -> Result<(), StellarError> {
        let est = self.face_visits(p);
        if est > budget {
            return Err(StellarError::TooLarge {
                what: format!("{p}-faces"),
                estimate: est,
                budget,
            });
        }
        Ok(())
    }

    /// Runs `f(view, keys)` for every leaf with the leaf's owned `p`-faces grouped: the
    /// payload of every entry is the tree id of a top cell containing the face.
    fn par_face_groups<R: Send>(
        &self,
        p: usize,
        f: impl Fn(&LeafView<'_>, &mut FaceKeys) -> R + Sync + Send,
    ) -> Vec<R> {
        let w = self
            .kinds()
            .iter()
            .map(|&k| face_width(k, p))
            .max()
            .unwrap_or(1);
        let pool_init = FaceKeys::default;
        (0..self.n_leaves() as u32)
            .into_par_iter()
            .map_init(
                || {
                    (
                        super::ExpandedLeaf::default(),
                        pool_init(),
                        Vec::<u32>::new(),
                    )
                },
                |(e, keys, key), l| {
                    self.expand_leaf_cells(LeafId(l), e);
                    keys.clear(w);
                    keys.set_buckets(Some((e.v_start, e.v_end)));
                    let view = LeafView { tree: self, e };
                    for &c in &e.cells {
                        let (kind, vs) = self.cells.get(c);
                        if kind.dim() < p {
                            continue;
                        }
                        faces_of(kind, p, |local| {
                            key.clear();
                            key.extend(local.iter().map(|&i| vs[i as usize]));
                            let m = *key.iter().min().expect("faces have vertices");
                            if view.owns(m) {
                                key.sort_unstable();
                                keys.push(key, c as u64);
                            }
                        });
                    }
                    f(&view, keys)
                },
            )
            .collect()
    }

    /// Expands only the cell list of a leaf (no VT).
    pub(crate) fn expand_leaf_cells(&self, l: LeafId, e: &mut super::ExpandedLeaf) {
        let r = self.leaf_vertices(l);
        e.leaf = l;
        e.v_start = r.start;
        e.v_end = r.end;
        e.cells.clear();
        super::sre::decode(self.leaf_encoded_cells(l), &mut e.cells);
        e.vt_off.clear();
        e.vt.clear();
    }

    /// Every `p`-face (p >= 0) of the complex once, with its number of top cofaces, budget
    /// [`FACE_BUDGET`] (cell, face) pairs. Faces of CP cells follow their face tables (the
    /// diagonal of a quad is not an edge). Order: by leaf, then by sorted tree ids.
    ///
    /// # Errors
    /// Over the budget (e.g. the 20-faces of 40-simplices).
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
    /// let e = t.p_faces(1).unwrap();
    /// assert_eq!(e.len(), 5);
    /// assert_eq!(e.n_cofaces.iter().filter(|&&n| n == 2).count(), 1);
    /// ```
    pub fn p_faces(&self, p: usize) -> Result<FaceList, StellarError> {
        self.p_faces_with_budget(p, FACE_BUDGET)
    }

    /// [`p_faces`](Self::p_faces) with an explicit budget.
    ///
    /// # Errors
    /// Over the budget.
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
    /// assert!(t.p_faces_with_budget(1, 3).is_err());
    /// ```
    pub fn p_faces_with_budget(&self, p: usize, budget: u128) -> Result<FaceList, StellarError> {
        self.check_budget(p, budget)?;
        let per_leaf: Vec<(Vec<u32>, Vec<u32>, Vec<u32>)> = self.par_face_groups(p, |_, keys| {
            let mut lens = Vec::new();
            let mut verts = Vec::new();
            let mut co = Vec::new();
            keys.for_each_group(|k, pays| {
                lens.push(k.len() as u32);
                let s = verts.len();
                verts.extend(k.iter().map(|&v| self.v_orig[v as usize]));
                verts[s..].sort_unstable();
                co.push(pays.len() as u32);
            });
            (lens, verts, co)
        });
        let mut offsets = vec![0u32];
        let mut targets = Vec::new();
        let mut n_cofaces = Vec::new();
        for (lens, verts, co) in per_leaf {
            for l in lens {
                let last = *offsets.last().expect("non-empty");
                offsets.push(last + l);
            }
            targets.extend_from_slice(&verts);
            n_cofaces.extend_from_slice(&co);
        }
        Ok(FaceList {
            faces: Csr { offsets, targets },
            n_cofaces,
        })
    }

    /// Number of distinct `p`-faces, without materialising them.
    ///
    /// # Errors
    /// Over the budget [`FACE_BUDGET`].
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
    /// assert_eq!(t.count_p_faces(2).unwrap(), 2);
    /// ```
    pub fn count_p_faces(&self, p: usize) -> Result<u64, StellarError> {
        self.check_budget(p, FACE_BUDGET)?;
        Ok(self
            .par_face_groups(p, |_, keys| {
                let mut n = 0u64;
                keys.for_each_group(|_, _| n += 1);
                n
            })
            .into_iter()
            .sum())
    }

    /// Adjacency of top cells across (k-1)-faces (R_{k,k}, k = the cell's dimension >= 1):
    /// row `c` (input id) holds the input ids of the other top k-cells sharing a facet with
    /// `c`, sorted; non-manifold facets (in three or more cells) connect all their cells.
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
    /// assert_eq!(t.top_adjacency().row(1), &[0]);
    /// ```
    pub fn top_adjacency(&self) -> Csr {
        let pairs = self.facet_pairs();
        let n = self.n_top_cells();
        let mut csr = Csr::from_fn(n, |emit| {
            for &(a, b, _) in &pairs {
                emit(self.c_orig[a as usize], self.c_orig[b as usize]);
                emit(self.c_orig[b as usize], self.c_orig[a as usize]);
            }
        });
        for i in 0..n {
            let (s, e) = (csr.offsets[i] as usize, csr.offsets[i + 1] as usize);
            csr.targets[s..e].sort_unstable();
        }
        // dedup rows (two cells may share several facets only in degenerate CP configurations)
        let mut out = Csr {
            offsets: vec![0],
            targets: Vec::with_capacity(csr.targets.len()),
        };
        for i in 0..n {
            let row = csr.row(i);
            for (j, &x) in row.iter().enumerate() {
                if j == 0 || row[j - 1] != x {
                    out.targets.push(x);
                }
            }
            out.offsets.push(out.targets.len() as u32);
        }
        out
    }

    /// All pairs (a, b, relative sign) of tree cells of one dimension sharing a facet; the sign
    /// is the product of the two induced facet orientations (+1: the cells induce the same
    /// orientation on the facet, so they are inconsistently oriented).
    pub(crate) fn facet_pairs(&self) -> Vec<(u32, u32, i8)> {
        let per_leaf = self.par_facet_groups(|_, key_groups| {
            let mut out = Vec::new();
            key_groups.for_each_group(|_, pays| {
                for i in 0..pays.len() {
                    for j in i + 1..pays.len() {
                        let (a, sa) = unpack(pays[i]);
                        let (b, sb) = unpack(pays[j]);
                        out.push((a, b, sa * sb));
                    }
                }
            });
            out
        });
        per_leaf.into_iter().flatten().collect()
    }

    /// Like [`par_face_groups`] for facets: each top k-cell (k >= 1) emits its facets with the
    /// cell dimension as an extra leading key entry; payload = tree cell id | sign bit.
    pub(crate) fn par_facet_groups<R: Send>(
        &self,
        f: impl Fn(&LeafView<'_>, &mut FaceKeys) -> R + Sync + Send,
    ) -> Vec<R> {
        self.par_facet_groups_where(1, false, f)
    }

    /// Facet groups of the cells of dimension >= `min_dim`; with `local`, every facet with a
    /// vertex in the leaf (the local IA* rule) instead of the facets the leaf owns.
    pub(crate) fn par_facet_groups_where<R: Send>(
        &self,
        min_dim: usize,
        local_rule: bool,
        f: impl Fn(&LeafView<'_>, &mut FaceKeys) -> R + Sync + Send,
    ) -> Vec<R> {
        let kinds = self.kinds();
        let fw = kinds
            .iter()
            .map(|&k| {
                if k.dim() >= 1 {
                    face_width(k, k.dim() - 1)
                } else {
                    0
                }
            })
            .max()
            .unwrap_or(0);
        // one dimension: the dimension prefix of the keys is implicit
        let dims: std::collections::BTreeSet<usize> = kinds.iter().map(|k| k.dim()).collect();
        let uniform_dim = (dims.len() == 1).then(|| *dims.first().expect("one") as u32);
        let w = if uniform_dim.is_some() { fw } else { fw + 1 };
        (0..self.n_leaves() as u32)
            .into_par_iter()
            .map_init(
                || {
                    (
                        super::ExpandedLeaf::default(),
                        FaceKeys::default(),
                        Vec::<u32>::new(),
                    )
                },
                |(e, keys, key), l| {
                    self.expand_leaf_cells(LeafId(l), e);
                    keys.clear(w);
                    keys.set_prefix(uniform_dim);
                    if uniform_dim.is_some() && !local_rule {
                        keys.set_buckets(Some((e.v_start, e.v_end)));
                    }
                    let view = LeafView { tree: self, e };
                    for &c in &e.cells {
                        let (kind, vs) = self.cells.get(c);
                        let d = kind.dim();
                        if d == 0 || d < min_dim {
                            continue;
                        }
                        if uniform_dim.is_some() && kind.is_simplex() && vs.len() <= SIMPLEX_FAST {
                            simplex_facets(vs, local_rule, &view, |key, j, s| {
                                keys.push(key, pack(c, j, s))
                            });
                            continue;
                        }
                        let mut j = 0u64;
                        oriented_facets_of(kind, |local, sign| {
                            j += 1;
                            key.clear();
                            key.extend(local.iter().map(|&i| vs[i as usize]));
                            let keep = if local_rule {
                                key.iter().any(|&v| view.owns(v))
                            } else {
                                view.owns(*key.iter().min().expect("facets have vertices"))
                            };
                            if !keep {
                                return;
                            }
                            let s = sign * listed_sign(key, !kind.is_simplex() && key.len() >= 3);
                            key.sort_unstable();
                            if uniform_dim.is_none() {
                                key.insert(0, d as u32);
                            }
                            keys.push(key, pack(c, j - 1, s));
                        });
                    }
                    f(&view, keys)
                },
            )
            .collect()
    }
}

/// Most vertices of a simplex whose facets take [`simplex_facets`].
const SIMPLEX_FAST: usize = 8;

/// The facets of a simplex kept by [`StellarTree::par_facet_groups_where`]'s rule, each as
/// `f(sorted vertices, facet index, induced sign relative to the sorted order)`: the vertices
/// are sorted once, and the facet omitting the k-th smallest vertex (the j-th listed one) has
/// sign (-1)^k times the parity of the sorting permutation.
#[inline]
fn simplex_facets(
    vs: &[u32],
    local_rule: bool,
    view: &LeafView<'_>,
    mut f: impl FnMut(&[u32], u64, i8),
) {
    let n = vs.len();
    let mut sv = [0u32; SIMPLEX_FAST];
    let mut si = [0u8; SIMPLEX_FAST];
    let mut fk = [0u32; SIMPLEX_FAST];
    if !(2..=SIMPLEX_FAST).contains(&n) {
        return;
    }
    // insertion sort tracking listed positions; the swaps count the inversions
    let mut swaps = 0usize;
    for (i, &x) in vs.iter().enumerate() {
        let mut p = i;
        while p > 0 && sv[p - 1] > x {
            sv[p] = sv[p - 1];
            si[p] = si[p - 1];
            p -= 1;
            swaps += 1;
        }
        sv[p] = x;
        si[p] = i as u8;
    }
    let parity: i8 = if swaps.is_multiple_of(2) { 1 } else { -1 };
    let owned = if local_rule {
        sv[..n].iter().filter(|&&x| view.owns(x)).count()
    } else {
        0
    };
    for k in 0..n {
        let keep = if local_rule {
            owned > view.owns(sv[k]) as usize
        } else {
            view.owns(if k == 0 { sv[1] } else { sv[0] })
        };
        if !keep {
            continue;
        }
        let mut m = 0;
        for (i, &x) in sv[..n].iter().enumerate() {
            if i != k {
                fk[m] = x;
                m += 1;
            }
        }
        let sign = if k % 2 == 0 { parity } else { -parity };
        f(&fk[..n - 1], si[k] as u64, sign);
    }
}

/// Payload of a facet record: tree cell id, facet index in the cell, induced sign.
#[inline]
pub(crate) fn pack(c: u32, j: u64, sign: i8) -> u64 {
    c as u64 | (j << 32) | if sign < 0 { 1 << 63 } else { 0 }
}

/// (tree cell, induced sign) of a facet payload.
#[inline]
pub(crate) fn unpack(x: u64) -> (u32, i8) {
    (x as u32, if x >> 63 == 1 { -1 } else { 1 })
}

/// Facet index of a facet payload.
#[inline]
pub(crate) fn unpack_facet(x: u64) -> u32 {
    ((x >> 32) & 0x7fff_ffff) as u32
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
        for c in super::sre::SreIter::new(self.leaf_encoded_cells(l)) {
            if self.cells.verts(c).contains(&tv) {
                out.push(CellId(self.c_orig[c as usize]));
            }
        }
        out.sort_unstable();
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
        for c in super::sre::SreIter::new(self.leaf_encoded_cells(l)) {
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
        for c in super::sre::SreIter::new(self.leaf_encoded_cells(l)) {
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
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bucket_sort_equals_sort() {
        let mut x: u64 = 12345;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x
        };
        for n in [0usize, 1, 63, 64, 500, 3000] {
            let v: Vec<(u64, u64)> = (0..n)
                .map(|_| {
                    let a = 100 + next() % 50;
                    ((a << 32) | (next() % 7), next() % 5)
                })
                .collect();
            let mut want = v.clone();
            want.sort_unstable();
            let (mut got, mut tmp, mut counts) = (v.clone(), Vec::new(), Vec::new());
            bucket_sort(&mut got, &mut tmp, &mut counts, 100, 150, |x| {
                (x.0 >> 32) as u32
            });
            assert_eq!(got, want);
            // out-of-range keys fall back to a plain sort
            let mut got = v.clone();
            bucket_sort(&mut got, &mut tmp, &mut counts, 120, 130, |x| {
                (x.0 >> 32) as u32
            });
            assert_eq!(got, want);
        }
    }
}
