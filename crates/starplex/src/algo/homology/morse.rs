//! The discrete gradient: a greedy acyclic matching built independently in the lower star of
//! every vertex (Robins–Wood–Sheppard), with faces generated on the fly from the top cells of
//! the vertex's star, and the Morse boundary of a critical cell by following gradient paths.
//!
//! Every cell belongs to the lower star L(v) of its largest vertex v. Per vertex:
//! * `L(v) = {v}` (no incident cell has a smaller vertex): v is critical;
//! * the lower link is a *cone* (an apex `s` such that every lower simplex `S_c` of an incident
//!   simplicial top cell can be completed by `s` inside some `S_c'`): the perfect matching
//!   `v∪T ↔ v∪T∪{s}` is used without enumerating anything — a single 40-simplex is answered
//!   this way, as is every vertex of a Freudenthal grid;
//! * otherwise the lower star is enumerated and matched by elementary expansions (a pair is
//!   made only when the coface's other facets and the face's own facets are all classified;
//!   when none is possible the lowest-dimensional free cell becomes critical). Expansions keep
//!   the matching acyclic, and the classification time orders gradient paths.
use std::borrow::Cow;
use std::collections::{BTreeMap, BinaryHeap, VecDeque};

use smallvec::SmallVec;

use super::cells::{cp_lower_star_faces, Cell, Key, Shape};
use crate::ids::{CellId, VertexId};
use crate::topo::{TopCells, VertexStar};

/// `apex[v]` when L(v) = {v}.
pub(crate) const ALONE: u32 = u32::MAX;
/// `apex[v]` when L(v) is enumerated.
pub(crate) const EXPLICIT: u32 = u32::MAX - 1;

/// Scratch buffers of one worker (reused from vertex to vertex: no allocation per lower star
/// once they have grown).
#[derive(Default)]
pub(crate) struct Scratch {
    cells: Vec<CellId>,
    verts: Vec<VertexId>,
    /// Lower vertices of each top cell, flat, with offsets.
    lower: Vec<u32>,
    starts: Vec<usize>,
    /// The distinct lower vertices of the star, sorted (bit `i` of a mask is `lv[i]`).
    lv: Vec<u32>,
    /// Lower sets of the top cells as masks over `lv`.
    tops: Vec<u64>,
    /// The cells of L(v) as masks (`v` implied), sorted.
    masks: Vec<u64>,
    /// The cells of L(v) when masks do not apply (CP cells, more than 64 lower vertices).
    general: Vec<Cell>,
    facet_buf: Vec<(Cell, i8)>,
    /// Zero between uses; see [`dense_masks`].
    table: Vec<u32>,
    m: Matching,
    /// Every top cell is known to be a simplex (their kinds need not be read).
    simplicial: bool,
    /// The star last read by [`plan_vertex`] for an explicit lower star: its vertex, and
    /// whether `lv` / `tops` hold its maximal masks (so that [`critical_cells`] right after
    /// does not read the star again).
    planned: Option<(u32, bool)>,
}

impl Scratch {
    /// Scratch for a complex whose top cells are all simplices when `simplicial`.
    pub(crate) fn new(simplicial: bool) -> Scratch {
        Scratch {
            simplicial,
            ..Scratch::default()
        }
    }
}

/// Buffers of the greedy matching of one lower star.
#[derive(Default)]
struct Matching {
    /// Facets inside L(v) of each cell (CSR).
    fstart: Vec<u32>,
    facets: Vec<u32>,
    /// Cofacets inside L(v) (CSR).
    ccount: Vec<u32>,
    cof: Vec<u32>,
    fill: Vec<u32>,
    remaining: Vec<u32>,
    status: Vec<Option<Status>>,
    time: Vec<u32>,
    dims: Vec<u8>,
    pairq: VecDeque<u32>,
    free: BinaryHeap<std::cmp::Reverse<(u8, u32)>>,
}

/// What [`plan_vertex`] found.
pub(crate) struct VertexPlan {
    /// An apex, [`ALONE`] or [`EXPLICIT`].
    pub apex: u32,
    /// Cells of the lower star if enumerated (upper bound).
    pub estimate: u128,
}

fn is_subset(a: &[u32], b: &[u32]) -> bool {
    // both sorted
    let mut j = 0;
    for &x in a {
        while j < b.len() && b[j] < x {
            j += 1;
        }
        if j == b.len() || b[j] != x {
            return false;
        }
        j += 1;
    }
    true
}

/// Direct access to a complex whose top cells are all simplices of one arity, stored flat
/// (cell `c` is `verts[c * arity..(c + 1) * arity]`), with its vertex → cells relation: the
/// star of a vertex is read from the slices, without copying cells through the
/// [`TopCells`] / [`VertexStar`] calls (the same sets in the same order).
#[derive(Clone, Copy)]
pub(crate) struct FastStar<'a> {
    pub arity: usize,
    /// The vertices of every cell are sorted (a lower set is then a prefix).
    pub sorted: bool,
    pub verts: &'a [u32],
    pub vt: &'a crate::csr::Csr,
}

/// [`read_lower_sets`] through a [`FastStar`]: the same `w.cells`, `w.lower`, `w.starts`.
fn read_lower_sets_fast(f: FastStar<'_>, v: u32, w: &mut Scratch) -> (bool, bool, u128) {
    w.planned = None;
    let row = f.vt.row(v as usize);
    w.cells.clear();
    w.cells.extend(row.iter().map(|&c| CellId(c)));
    w.lower.clear();
    w.starts.clear();
    let mut estimate: u128 = 0;
    let a = f.arity;
    for &c in row {
        let cell = &f.verts[c as usize * a..(c as usize + 1) * a];
        let start = w.lower.len();
        w.starts.push(start);
        if f.sorted {
            let n = cell.partition_point(|&x| x < v);
            w.lower.extend_from_slice(&cell[..n]);
        } else {
            w.lower.extend(cell.iter().copied().filter(|&x| x < v));
        }
        let n = w.lower.len() - start;
        let e = if n >= 127 { u128::MAX } else { 1u128 << n };
        estimate = estimate.saturating_add(e);
    }
    w.starts.push(w.lower.len());
    (!w.lower.is_empty(), true, estimate)
}

/// Reads the star of `v`: the lower vertices of every top cell into `w.lower` / `w.starts`
/// (unsorted within a cell). Returns (any lower vertex, all cells simplices, estimate).
fn read_lower_sets<S: TopCells + VertexStar + ?Sized>(
    s: &S,
    v: u32,
    w: &mut Scratch,
) -> (bool, bool, u128) {
    w.planned = None;
    s.vertex_top_cells(VertexId(v), &mut w.cells);
    w.lower.clear();
    w.starts.clear();
    let mut all_simplices = true;
    let mut estimate: u128 = 0;
    for i in 0..w.cells.len() {
        let c = w.cells[i];
        let is_simplex = w.simplicial || s.top_cell_kind(c).is_simplex();
        w.verts.clear();
        s.top_cell_vertices(c, &mut w.verts);
        w.starts.push(w.lower.len());
        let start = w.lower.len();
        w.lower
            .extend(w.verts.iter().map(|x| x.0).filter(|&x| x < v));
        let n = w.lower.len() - start;
        if is_simplex {
            let e = if n >= 127 { u128::MAX } else { 1u128 << n };
            estimate = estimate.saturating_add(e);
        } else {
            all_simplices = false;
            estimate = estimate.saturating_add(27);
        }
    }
    w.starts.push(w.lower.len());
    (!w.lower.is_empty(), all_simplices, estimate)
}

/// After [`read_lower_sets`] on simplices: the distinct lower vertices into `w.lv` and the
/// distinct *maximal* lower sets as masks into `w.tops`. False when there are more than 64
/// lower vertices (masks do not apply).
fn maximal_masks(w: &mut Scratch) -> bool {
    // the distinct lower vertices, sorted, by insertion (a star lists each a few times)
    w.lv.clear();
    for &x in &w.lower {
        if let Err(i) = w.lv.binary_search(&x) {
            if w.lv.len() == 64 {
                return false;
            }
            w.lv.insert(i, x);
        }
    }
    // the maximal masks, kept incrementally (a star has few): a mask inside a kept one is
    // dropped, kept masks inside a new one are removed (the set, not its order, matters)
    w.tops.clear();
    for i in 0..w.starts.len() - 1 {
        let mut m = 0u64;
        for &x in &w.lower[w.starts[i]..w.starts[i + 1]] {
            // lv is small and sorted
            let b = w.lv.partition_point(|&y| y < x);
            m |= 1u64 << b;
        }
        if w.tops.iter().any(|&big| m & !big == 0) {
            continue;
        }
        w.tops.retain(|&small| small & !m != 0);
        w.tops.push(m);
    }
    true
}

/// Classifies the lower star of `v` (see the module docs) without enumerating it.
pub(crate) fn plan_vertex<S: TopCells + VertexStar + ?Sized>(
    s: &S,
    fast: Option<FastStar<'_>>,
    v: u32,
    w: &mut Scratch,
) -> VertexPlan {
    let (any_lower, all_simplices, estimate) = match fast {
        Some(f) => read_lower_sets_fast(f, v, w),
        None => read_lower_sets(s, v, w),
    };
    if !any_lower {
        return VertexPlan {
            apex: ALONE,
            estimate: 1,
        };
    }
    if !all_simplices {
        w.planned = Some((v, false));
        return VertexPlan {
            apex: EXPLICIT,
            estimate,
        };
    }
    if maximal_masks(w) {
        // a cone iff one vertex is in every maximal lower set: the smallest such is the apex
        let common = w.tops.iter().fold(u64::MAX, |a, &m| a & m);
        let apex = if common == 0 {
            w.planned = Some((v, true));
            EXPLICIT
        } else {
            w.lv[common.trailing_zeros() as usize]
        };
        return VertexPlan { apex, estimate };
    }
    // more than 64 lower vertices: compare sorted sets
    for i in 0..w.starts.len() - 1 {
        w.lower[w.starts[i]..w.starts[i + 1]].sort_unstable();
    }
    let m = w.cells.len();
    let set = |i: usize| &w.lower[w.starts[i]..w.starts[i + 1]];
    let best = (0..m)
        .max_by_key(|&i| (set(i).len(), usize::MAX - i))
        .unwrap_or(0);
    let mut with: Vec<usize> = Vec::with_capacity(m);
    let mut work = 0usize;
    'cand: for &cand in set(best) {
        // the cells whose lower set holds the candidate, largest first
        with.clear();
        with.extend((0..m).filter(|&j| set(j).contains(&cand)));
        with.sort_by_key(|&j| std::cmp::Reverse(set(j).len()));
        for i in 0..m {
            let si = set(i);
            if si.contains(&cand) {
                continue;
            }
            let found = with.iter().any(|&j| {
                work += 1;
                let sj = set(j);
                sj.len() > si.len() && is_subset(si, sj)
            });
            if work > 50_000 {
                break 'cand;
            }
            if !found {
                continue 'cand;
            }
        }
        return VertexPlan {
            apex: cand,
            estimate,
        };
    }
    w.planned = Some((v, false));
    VertexPlan {
        apex: EXPLICIT,
        estimate,
    }
}

/// Status of a cell in its lower star.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Status {
    Critical,
    /// Paired with a coface (index in the lower star).
    Up(u32),
    /// Paired with a face.
    Down(u32),
}

/// An enumerated and matched lower star.
pub(crate) struct LowerStar {
    v: u32,
    /// Distinct lower vertices (mask form), sorted.
    lv: Vec<u32>,
    /// Cells as masks over `lv`, sorted (mask form).
    masks: Vec<u64>,
    /// Cells sorted by key (general form; empty in mask form).
    cells: Vec<Cell>,
    pub status: Vec<Status>,
    pub time: Vec<u32>,
}

impl LowerStar {
    fn is_masks(&self) -> bool {
        self.cells.is_empty()
    }

    pub fn find(&self, key: &[u32]) -> Option<usize> {
        if !self.is_masks() {
            return self
                .cells
                .binary_search_by(|c| c.key.as_slice().cmp(key))
                .ok();
        }
        let (&last, rest) = key.split_last()?;
        if last != self.v {
            return None;
        }
        let mut m = 0u64;
        for x in rest {
            m |= 1u64 << self.lv.binary_search(x).ok()?;
        }
        self.masks.binary_search(&m).ok()
    }

    pub fn cell(&self, i: usize) -> Cell {
        if self.is_masks() {
            mask_cell(&self.lv, self.masks[i], self.v)
        } else {
            self.cells[i].clone()
        }
    }
}

/// The simplex `v ∪ {lv[b] : b in mask}`.
fn mask_cell(lv: &[u32], mask: u64, v: u32) -> Cell {
    let mut key: Key = SmallVec::new();
    let mut m = mask;
    while m != 0 {
        key.push(lv[m.trailing_zeros() as usize]);
        m &= m - 1;
    }
    key.push(v);
    Cell::simplex(key)
}

/// The facet relation of lower-star cells in mask form (`v` implied in every cell) into `m`:
/// `index(f)` is the index of the cell of mask `f` (a facet keeps `v`: the masks less one bit).
fn mask_facets(masks: &[u64], m: &mut Matching, index: impl Fn(u64) -> Option<u32>) {
    for &c in masks {
        m.fstart.push(m.facets.len() as u32);
        m.dims.push(c.count_ones() as u8);
        let mut r = c;
        while r != 0 {
            let f = c & !(r & r.wrapping_neg());
            r &= r - 1;
            match index(f) {
                Some(j) => m.facets.push(j),
                None => debug_assert!(false, "facet of a lower-star cell missing"),
            }
        }
    }
    m.fstart.push(m.facets.len() as u32);
}

/// Lower stars with at most this many distinct lower vertices are enumerated through a table
/// indexed by mask (2^10 entries a worker) instead of a sort and binary searches.
const DENSE_BITS: usize = 10;

/// The mask form of [`enumerate`] through `w.table`: the same `w.masks` (increasing) and the
/// same facet relation. Every subset of a maximal mask is marked, the marks are read in
/// increasing order (numbering the cells), and a facet's index is read from the table.
fn dense_masks(w: &mut Scratch) {
    let size = 1usize << w.lv.len();
    if w.table.len() < size {
        w.table.resize(size, 0);
    }
    let table = &mut w.table[..size];
    for &top in &w.tops {
        let mut sub = top;
        loop {
            table[sub as usize] = 1;
            if sub == 0 {
                break;
            }
            sub = (sub - 1) & top;
        }
    }
    w.masks.clear();
    for (mask, t) in table.iter_mut().enumerate() {
        if *t != 0 {
            w.masks.push(mask as u64);
            *t = w.masks.len() as u32; // index + 1
        }
    }
    mask_facets(&w.masks, &mut w.m, |f| table[f as usize].checked_sub(1));
    for &c in &w.masks {
        table[c as usize] = 0;
    }
}

/// Enumerates L(v) into `w.masks` (mask form, returns true) or `w.general` (sorted by key), and
/// its facet relation into `w.m`.
fn enumerate<S: TopCells + VertexStar + ?Sized>(
    s: &S,
    fast: Option<FastStar<'_>>,
    v: u32,
    w: &mut Scratch,
) -> bool {
    // the star just read by `plan_vertex`, or a fresh read
    let masks = match w.planned.take() {
        Some((pv, masks)) if pv == v => masks,
        _ => {
            let (_, all, _) = match fast {
                Some(f) => read_lower_sets_fast(f, v, w),
                None => read_lower_sets(s, v, w),
            };
            all && maximal_masks(w)
        }
    };
    w.m.fstart.clear();
    w.m.facets.clear();
    w.m.dims.clear();
    if masks && w.lv.len() <= DENSE_BITS {
        dense_masks(w);
        return true;
    }
    if masks {
        let m = &mut w.m;
        w.masks.clear();
        for &top in &w.tops {
            let mut sub = top;
            loop {
                w.masks.push(sub);
                if sub == 0 {
                    break;
                }
                sub = (sub - 1) & top;
            }
        }
        w.masks.sort_unstable();
        w.masks.dedup();
        let masks = &w.masks;
        mask_facets(masks, m, |f| masks.binary_search(&f).ok().map(|j| j as u32));
        return true;
    }
    w.general.clear();
    for i in 0..w.cells.len() {
        let c = w.cells[i];
        let kind = s.top_cell_kind(c);
        w.verts.clear();
        s.top_cell_vertices(c, &mut w.verts);
        if kind.is_simplex() {
            let lower = &mut w.lower[w.starts[i]..w.starts[i + 1]];
            lower.sort_unstable();
            let n = lower.len();
            for mask in 0u64..(1u64 << n) {
                let mut key: Key = SmallVec::new();
                for (b, &x) in lower.iter().enumerate() {
                    if mask >> b & 1 == 1 {
                        key.push(x);
                    }
                }
                key.push(v);
                w.general.push(Cell::simplex(key));
            }
        } else {
            let g: Vec<u32> = w.verts.iter().map(|x| x.0).collect();
            cp_lower_star_faces(kind, &g, v, &mut w.general);
        }
    }
    let cells = &mut w.general;
    cells.sort_unstable_by(|a, b| a.key.cmp(&b.key));
    cells.dedup_by(|a, b| a.key == b.key);
    let m = &mut w.m;
    for c in cells.iter() {
        m.fstart.push(m.facets.len() as u32);
        m.dims.push(c.dim() as u8);
        w.facet_buf.clear();
        c.facets(&mut w.facet_buf);
        for (f, _) in &w.facet_buf {
            if f.key.contains(&v) {
                if let Ok(j) = cells.binary_search_by(|x| x.key.as_slice().cmp(&f.key)) {
                    m.facets.push(j as u32);
                } else {
                    debug_assert!(false, "facet of a lower-star cell missing");
                }
            }
        }
    }
    m.fstart.push(m.facets.len() as u32);
    false
}

impl Matching {
    /// Classifies `x`: updates the counts of its cofaces.
    fn classify(&mut self, x: usize) {
        for k in self.ccount[x] as usize..self.ccount[x + 1] as usize {
            let y = self.cof[k] as usize;
            self.remaining[y] -= 1;
            if self.status[y].is_some() {
                continue;
            }
            if self.remaining[y] == 1 {
                self.pairq.push_back(y as u32);
            } else if self.remaining[y] == 0 {
                self.free.push(std::cmp::Reverse((self.dims[y], y as u32)));
                for &z in &self.cof[self.ccount[y] as usize..self.ccount[y + 1] as usize] {
                    if self.remaining[z as usize] == 1 && self.status[z as usize].is_none() {
                        self.pairq.push_back(z);
                    }
                }
            }
        }
    }

    /// The greedy matching of the `n` cells whose facets are in `fstart` / `facets` and
    /// dimensions in `dims`: into `status` and `time`.
    fn run(&mut self) {
        let n = self.dims.len();
        self.ccount.clear();
        self.ccount.resize(n + 1, 0);
        for &f in &self.facets {
            self.ccount[f as usize + 1] += 1;
        }
        for i in 0..n {
            self.ccount[i + 1] += self.ccount[i];
        }
        self.cof.clear();
        self.cof.resize(self.facets.len(), 0);
        self.fill.clear();
        self.fill.extend_from_slice(&self.ccount);
        for i in 0..n {
            for k in self.fstart[i] as usize..self.fstart[i + 1] as usize {
                let f = self.facets[k] as usize;
                self.cof[self.fill[f] as usize] = i as u32;
                self.fill[f] += 1;
            }
        }
        self.remaining.clear();
        self.remaining
            .extend((0..n).map(|i| self.fstart[i + 1] - self.fstart[i]));
        self.status.clear();
        self.status.resize(n, None);
        self.time.clear();
        self.time.resize(n, 0);
        self.pairq.clear();
        self.free.clear();
        for i in 0..n {
            if self.remaining[i] == 0 {
                self.free.push(std::cmp::Reverse((self.dims[i], i as u32)));
            } else if self.remaining[i] == 1 {
                self.pairq.push_back(i as u32);
            }
        }
        let mut t = 0u32;
        let mut done = 0usize;
        while done < n {
            while let Some(a) = self.pairq.pop_front() {
                let a = a as usize;
                if self.status[a].is_some() || self.remaining[a] != 1 {
                    continue;
                }
                let tau = self.facets[self.fstart[a] as usize..self.fstart[a + 1] as usize]
                    .iter()
                    .map(|&f| f as usize)
                    .find(|&f| self.status[f].is_none());
                let Some(tau) = tau else { continue };
                if self.remaining[tau] != 0 {
                    continue;
                }
                self.status[tau] = Some(Status::Up(a as u32));
                self.status[a] = Some(Status::Down(tau as u32));
                self.time[tau] = t;
                self.time[a] = t;
                t += 1;
                done += 2;
                self.classify(tau);
                self.classify(a);
            }
            if done >= n {
                break;
            }
            // a critical cell: the lowest-dimensional free unclassified cell
            let mut g = None;
            while let Some(std::cmp::Reverse((_, i))) = self.free.pop() {
                if self.status[i as usize].is_none() {
                    g = Some(i as usize);
                    break;
                }
            }
            let Some(g) = g else {
                debug_assert!(false, "no free cell left in a lower star");
                break;
            };
            self.status[g] = Some(Status::Critical);
            self.time[g] = t;
            t += 1;
            done += 1;
            self.classify(g);
            // cofaces of g with one unclassified facet may now pair
            for k in self.ccount[g] as usize..self.ccount[g + 1] as usize {
                let z = self.cof[k];
                if self.remaining[z as usize] == 1 && self.status[z as usize].is_none() {
                    self.pairq.push_back(z);
                }
            }
        }
    }
}

/// Enumerates and matches L(v) in the scratch buffers; true in mask form.
fn match_lower_star<S: TopCells + VertexStar + ?Sized>(
    s: &S,
    fast: Option<FastStar<'_>>,
    v: u32,
    w: &mut Scratch,
) -> bool {
    let masks = enumerate(s, fast, v, w);
    w.m.run();
    masks
}

/// Enumerates and matches L(v).
pub(crate) fn lower_star<S: TopCells + VertexStar + ?Sized>(
    s: &S,
    fast: Option<FastStar<'_>>,
    v: u32,
    w: &mut Scratch,
) -> LowerStar {
    let masks = match_lower_star(s, fast, v, w);
    LowerStar {
        v,
        lv: if masks { w.lv.clone() } else { Vec::new() },
        masks: if masks { w.masks.clone() } else { Vec::new() },
        cells: if masks {
            Vec::new()
        } else {
            std::mem::take(&mut w.general)
        },
        status: w
            .m
            .status
            .iter()
            .map(|s| s.unwrap_or(Status::Critical))
            .collect(),
        time: w.m.time.clone(),
    }
}

/// The critical cells of L(v).
pub(crate) fn critical_cells<S: TopCells + VertexStar + ?Sized>(
    s: &S,
    v: u32,
    apex: u32,
    w: &mut Scratch,
    out: &mut Vec<Cell>,
) {
    match apex {
        ALONE => out.push(Cell::simplex(SmallVec::from_slice(&[v]))),
        EXPLICIT => {
            // the star was just read by `plan_vertex`
            let masks = match_lower_star(s, None, v, w);
            for (i, st) in w.m.status.iter().enumerate() {
                if matches!(st, None | Some(Status::Critical)) {
                    out.push(if masks {
                        mask_cell(&w.lv, w.masks[i], v)
                    } else {
                        w.general[i].clone()
                    });
                }
            }
        }
        _ => {}
    }
}

/// What the gradient says of a cell.
pub(crate) enum Look {
    Critical(u32),
    Down,
    /// Paired with `alpha`, in whose boundary the cell has incidence `sign`; `time` orders paths.
    Up {
        alpha: Cell,
        sign: i8,
        time: u32,
    },
}

/// Arithmetic overflow of integer coefficients.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Overflow;

#[inline]
pub(crate) fn add_c(a: i64, b: i64, m: i64) -> Result<i64, Overflow> {
    if m == 0 {
        a.checked_add(b).ok_or(Overflow)
    } else {
        Ok((a + b).rem_euclid(m))
    }
}

#[inline]
pub(crate) fn mul_c(a: i64, b: i64, m: i64) -> Result<i64, Overflow> {
    if m == 0 {
        a.checked_mul(b).ok_or(Overflow)
    } else {
        Ok((a * b).rem_euclid(m))
    }
}

/// The gradient of a complex: the apex plan per vertex and the sorted critical cells per
/// dimension.
pub(crate) struct Gradient<'a, S: ?Sized> {
    pub s: &'a S,
    /// Direct access to the cells of `s`, when it has it.
    pub fast: Option<FastStar<'a>>,
    pub apex: Cow<'a, [u32]>,
    /// Critical cells per dimension, sorted by key.
    pub crit: Cow<'a, [Vec<Cell>]>,
}

/// A per-flow cache of enumerated lower stars (vertices above the flow's front are dropped).
pub(crate) type Cache = BTreeMap<u32, LowerStar>;

impl<S: TopCells + VertexStar + ?Sized> Gradient<'_, S> {
    /// Index of a critical cell.
    pub fn crit_index(&self, c: &Cell) -> Option<u32> {
        self.crit
            .get(c.dim())?
            .binary_search_by(|x| x.key.cmp(&c.key))
            .ok()
            .map(|i| i as u32)
    }

    pub fn look(&self, tau: &Cell, cache: &mut Cache, w: &mut Scratch) -> Look {
        let v = tau.max_vertex();
        match self.apex[v as usize] {
            ALONE => match self.crit_index(tau) {
                Some(i) => Look::Critical(i),
                None => Look::Down,
            },
            EXPLICIT => {
                let ls = cache
                    .entry(v)
                    .or_insert_with(|| lower_star(self.s, self.fast, v, w));
                let Some(i) = ls.find(&tau.key) else {
                    debug_assert!(false, "cell not in its lower star");
                    return Look::Down;
                };
                match ls.status[i] {
                    Status::Critical => match self.crit_index(tau) {
                        Some(i) => Look::Critical(i),
                        None => Look::Down,
                    },
                    Status::Down(_) => Look::Down,
                    Status::Up(a) => {
                        let alpha = ls.cell(a as usize);
                        let sign = if alpha.shape == Shape::Simplex {
                            // alpha = tau plus one vertex, at the first differing position
                            let pos = tau
                                .key
                                .iter()
                                .zip(&alpha.key)
                                .position(|(x, y)| x != y)
                                .unwrap_or(tau.key.len());
                            if pos % 2 == 0 {
                                1
                            } else {
                                -1
                            }
                        } else {
                            let mut buf = Vec::new();
                            alpha.facets(&mut buf);
                            buf.iter()
                                .find(|(f, _)| f.key == tau.key)
                                .map_or(1, |(_, s)| *s)
                        };
                        Look::Up {
                            alpha,
                            sign,
                            time: ls.time[i],
                        }
                    }
                }
            }
            apex => {
                if tau.key.binary_search(&apex).is_ok() {
                    return Look::Down;
                }
                let mut key = tau.key.clone();
                let pos = key.partition_point(|&x| x < apex);
                key.insert(pos, apex);
                Look::Up {
                    alpha: Cell::simplex(key),
                    sign: if pos % 2 == 0 { 1 } else { -1 },
                    time: 0,
                }
            }
        }
    }

    /// Follows the gradient from the boundary of the critical cell (or chain) `start`: returns
    /// the Morse boundary (critical index, coefficient), and when `chain` is given, adds to it
    /// the cells of the gradient paths with their coefficients (the chain of `start` pushed
    /// into the complex, a cycle when `start` is a Morse cycle).
    pub fn flow(
        &self,
        start: &[(Cell, i64)],
        m: i64,
        chain: Option<&mut BTreeMap<Key, (Cell, i64)>>,
        w: &mut Scratch,
    ) -> Result<Vec<(u32, i64)>, Overflow> {
        self.flow_from(start, true, m, chain, w)
    }

    /// The projection of the chain `start` onto the critical cells of its dimension: each cell
    /// followed down the gradient (a critical cell gives itself, the upper cell of a pair
    /// nothing). The chain map from the complex to its Morse complex. (The model that
    /// [`Gradient::project_batch`] is checked against in debug builds.)
    #[cfg(debug_assertions)]
    pub fn project(
        &self,
        start: &[(Cell, i64)],
        m: i64,
        w: &mut Scratch,
    ) -> Result<Vec<(u32, i64)>, Overflow> {
        self.flow_from(start, false, m, None, w)
    }

    /// [`Gradient::project`] of each cell of `cells` (coefficient +1), with one memo of the
    /// projections of every cell met on the way, so gradient paths shared by several cells are
    /// followed once: `π(σ) = σ` for a critical cell, `0` for the upper cell of a pair, and
    /// `π(σ) = -s Σ_{τ ≠ σ} [α : τ] π(τ)` when `σ` is paired with `α` (`s = [α : σ] = ±1`),
    /// evaluated depth first (the gradient is acyclic). The memo and the lower stars are
    /// dropped when they exceed `max_memo` entries (then paths are followed again).
    pub fn project_batch(
        &self,
        cells: &[Cell],
        m: i64,
        max_memo: usize,
        w: &mut Scratch,
    ) -> Result<Vec<Vec<(u32, i64)>>, Overflow> {
        type Chain = Vec<(u32, i64)>;
        struct Frame {
            cell: Cell,
            /// `-s [α : τ]` for the facets `τ ≠ σ` of the pair's upper cell.
            facets: Vec<(Cell, i64)>,
            next: usize,
        }
        let mut memo: rustc_hash::FxHashMap<Key, Chain> = Default::default();
        let mut cache: Cache = BTreeMap::new();
        let mut buf: Vec<(Cell, i8)> = Vec::new();
        let mut out = Vec::with_capacity(cells.len());
        let mut stack: Vec<Frame> = Vec::new();
        for start in cells {
            if memo.len() > max_memo || cache.len() > max_memo / 64 + 1 {
                memo.clear();
                cache.clear();
            }
            if !memo.contains_key(&start.key) {
                stack.push(Frame {
                    cell: start.clone(),
                    facets: Vec::new(),
                    next: usize::MAX,
                });
            }
            while let Some(top) = stack.last_mut() {
                if top.next == usize::MAX {
                    match self.look(&top.cell, &mut cache, w) {
                        Look::Critical(i) => {
                            let f = stack.pop().expect("a frame");
                            memo.insert(f.cell.key, vec![(i, 1)]);
                            continue;
                        }
                        Look::Down => {
                            let f = stack.pop().expect("a frame");
                            memo.insert(f.cell.key, Vec::new());
                            continue;
                        }
                        Look::Up { alpha, sign, .. } => {
                            buf.clear();
                            alpha.facets(&mut buf);
                            top.facets = buf
                                .drain(..)
                                .filter(|(f, _)| f.key != top.cell.key)
                                .map(|(f, c)| (f, -(sign as i64) * c as i64))
                                .collect();
                            top.next = 0;
                        }
                    }
                }
                // the next facet whose projection is not known yet
                while top.next < top.facets.len() && memo.contains_key(&top.facets[top.next].0.key)
                {
                    top.next += 1;
                }
                if top.next < top.facets.len() {
                    let cell = top.facets[top.next].0.clone();
                    stack.push(Frame {
                        cell,
                        facets: Vec::new(),
                        next: usize::MAX,
                    });
                    continue;
                }
                let f = stack.pop().expect("a frame");
                let mut acc: BTreeMap<u32, i64> = BTreeMap::new();
                for (tau, c) in &f.facets {
                    for &(i, x) in &memo[&tau.key] {
                        let e = acc.entry(i).or_insert(0);
                        *e = add_c(*e, mul_c(*c, x, m)?, m)?;
                    }
                }
                memo.insert(
                    f.cell.key,
                    acc.into_iter().filter(|&(_, c)| c != 0).collect(),
                );
            }
            out.push(memo[&start.key].clone());
        }
        Ok(out)
    }

    /// [`Gradient::flow`] (`facets`: the paths start at the facets of `start`) or
    /// [`Gradient::project`] (they start at its cells).
    fn flow_from(
        &self,
        start: &[(Cell, i64)],
        facets: bool,
        m: i64,
        mut chain: Option<&mut BTreeMap<Key, (Cell, i64)>>,
        w: &mut Scratch,
    ) -> Result<Vec<(u32, i64)>, Overflow> {
        type Pending = BTreeMap<(u32, u32, Key), (i64, Cell, Cell, i8)>;
        let mut pending: Pending = BTreeMap::new();
        let mut result: BTreeMap<u32, i64> = BTreeMap::new();
        let mut cache: Cache = BTreeMap::new();
        let mut buf: Vec<(Cell, i8)> = Vec::new();
        let add = |tau: Cell,
                   c: i64,
                   pending: &mut Pending,
                   result: &mut BTreeMap<u32, i64>,
                   cache: &mut Cache,
                   w: &mut Scratch|
         -> Result<(), Overflow> {
            match self.look(&tau, cache, w) {
                Look::Critical(i) => {
                    let e = result.entry(i).or_insert(0);
                    *e = add_c(*e, c, m)?;
                }
                Look::Down => {}
                Look::Up { alpha, sign, time } => {
                    let k = (tau.max_vertex(), time, tau.key.clone());
                    let e = pending.entry(k).or_insert((0, tau, alpha, sign));
                    e.0 = add_c(e.0, c, m)?;
                }
            }
            Ok(())
        };
        for (sigma, c0) in start {
            if !facets {
                let c = add_c(0, *c0, m)?;
                add(sigma.clone(), c, &mut pending, &mut result, &mut cache, w)?;
                continue;
            }
            if let Some(ch) = chain.as_deref_mut() {
                let e = ch.entry(sigma.key.clone()).or_insert((sigma.clone(), 0));
                e.1 = add_c(e.1, *c0, m)?;
            }
            buf.clear();
            sigma.facets(&mut buf);
            for (f, s) in buf.drain(..) {
                add(
                    f,
                    mul_c(*c0, s as i64, m)?,
                    &mut pending,
                    &mut result,
                    &mut cache,
                    w,
                )?;
            }
        }
        while let Some(((v, _, _), (c, tau, alpha, sign))) = pending.pop_last() {
            if cache.last_key_value().is_some_and(|(&k, _)| k > v) {
                let _ = cache.split_off(&(v + 1));
            }
            if c == 0 {
                continue;
            }
            // coefficient of alpha cancelling tau
            let ca = mul_c(-c, sign as i64, m)?;
            if let Some(ch) = chain.as_deref_mut() {
                let e = ch.entry(alpha.key.clone()).or_insert((alpha.clone(), 0));
                e.1 = add_c(e.1, ca, m)?;
            }
            buf.clear();
            alpha.facets(&mut buf);
            let facets = std::mem::take(&mut buf);
            for (f, s) in &facets {
                if f.key == tau.key {
                    continue;
                }
                add(
                    f.clone(),
                    mul_c(ca, *s as i64, m)?,
                    &mut pending,
                    &mut result,
                    &mut cache,
                    w,
                )?;
            }
            buf = facets;
        }
        if let Some(ch) = chain {
            ch.retain(|_, (_, c)| *c != 0);
        }
        Ok(result.into_iter().filter(|&(_, c)| c != 0).collect())
    }
}

/// What the gradient says of a cell, seen from below (for coboundary flows).
pub(crate) enum CoLook {
    Critical(u32),
    /// Paired with a coface: no coboundary path goes through it.
    Up,
    /// Paired with the facet `beta`, which has incidence `sign` in the cell; `time` orders paths.
    Down {
        beta: Cell,
        sign: i8,
        time: u32,
    },
}

/// The coboundary flows ran over their shared work budget.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum CoflowError {
    Overflow,
    OverBudget,
}

impl From<Overflow> for CoflowError {
    fn from(_: Overflow) -> Self {
        CoflowError::Overflow
    }
}

/// Sign of the facet `small` (one vertex less) in the simplex `big`.
fn facet_sign(small: &[u32], big: &[u32]) -> i8 {
    let pos = small
        .iter()
        .zip(big)
        .position(|(x, y)| x != y)
        .unwrap_or(small.len());
    if pos % 2 == 0 {
        1
    } else {
        -1
    }
}

impl<S: TopCells + VertexStar + ?Sized> Gradient<'_, S> {
    /// [`Gradient::look`] from below: for a simplex `tau`.
    pub fn colook(&self, tau: &Cell, cache: &mut Cache, w: &mut Scratch) -> CoLook {
        let v = tau.max_vertex();
        match self.apex[v as usize] {
            ALONE => match self.crit_index(tau) {
                Some(i) => CoLook::Critical(i),
                None => CoLook::Up,
            },
            EXPLICIT => {
                let ls = cache
                    .entry(v)
                    .or_insert_with(|| lower_star(self.s, self.fast, v, w));
                let Some(i) = ls.find(&tau.key) else {
                    debug_assert!(false, "cell not in its lower star");
                    return CoLook::Up;
                };
                match ls.status[i] {
                    Status::Critical => match self.crit_index(tau) {
                        Some(i) => CoLook::Critical(i),
                        None => CoLook::Up,
                    },
                    Status::Up(_) => CoLook::Up,
                    Status::Down(b) => {
                        let beta = ls.cell(b as usize);
                        let sign = facet_sign(&beta.key, &tau.key);
                        CoLook::Down {
                            beta,
                            sign,
                            time: ls.time[i],
                        }
                    }
                }
            }
            apex => match tau.key.binary_search(&apex) {
                Ok(pos) => {
                    let mut key = tau.key.clone();
                    key.remove(pos);
                    CoLook::Down {
                        beta: Cell::simplex(key),
                        sign: if pos % 2 == 0 { 1 } else { -1 },
                        time: 0,
                    }
                }
                Err(_) => CoLook::Up,
            },
        }
    }

    /// Appends the cofacets of the simplex `sigma` (all top cells simplices) with the
    /// incidence of `sigma` in each.
    fn cofacets(&self, sigma: &Cell, w: &mut Scratch, out: &mut Vec<(Cell, i8)>) {
        let v = sigma.max_vertex();
        self.s.vertex_top_cells(VertexId(v), &mut w.cells);
        w.lower.clear();
        for i in 0..w.cells.len() {
            w.verts.clear();
            self.s.top_cell_vertices(w.cells[i], &mut w.verts);
            if sigma.key.iter().all(|x| w.verts.iter().any(|y| y.0 == *x)) {
                w.lower.extend(
                    w.verts
                        .iter()
                        .map(|y| y.0)
                        .filter(|y| sigma.key.binary_search(y).is_err()),
                );
            }
        }
        w.lower.sort_unstable();
        w.lower.dedup();
        for &x in &w.lower {
            let pos = sigma.key.partition_point(|&y| y < x);
            let mut key = sigma.key.clone();
            key.insert(pos, x);
            out.push((Cell::simplex(key), if pos % 2 == 0 { 1 } else { -1 }));
        }
    }

    /// The Morse coboundary of the critical simplex `sigma` (critical index, coefficient):
    /// gradient paths followed upwards, cells processed in increasing (largest vertex, time)
    /// order. Every processed cell takes one unit of `budget`; when the budget shared by all
    /// flows is exhausted, the flow stops with [`CoflowError::OverBudget`] (the total work
    /// is then known to exceed it, so the outcome does not depend on the thread count).
    pub fn coflow(
        &self,
        sigma: &Cell,
        m: i64,
        budget: &std::sync::atomic::AtomicI64,
        w: &mut Scratch,
    ) -> Result<Vec<(u32, i64)>, CoflowError> {
        use std::sync::atomic::Ordering::Relaxed;
        type Pending = BTreeMap<(u32, u32, Key), (i64, Cell, i8)>;
        let mut pending: Pending = BTreeMap::new();
        let mut result: BTreeMap<u32, i64> = BTreeMap::new();
        let mut cache: Cache = BTreeMap::new();
        let mut buf: Vec<(Cell, i8)> = Vec::new();
        let add = |tau: Cell,
                   c: i64,
                   pending: &mut Pending,
                   result: &mut BTreeMap<u32, i64>,
                   cache: &mut Cache,
                   w: &mut Scratch|
         -> Result<(), Overflow> {
            match self.colook(&tau, cache, w) {
                CoLook::Critical(i) => {
                    let e = result.entry(i).or_insert(0);
                    *e = add_c(*e, c, m)?;
                }
                CoLook::Up => {}
                CoLook::Down { beta, sign, time } => {
                    let k = (tau.max_vertex(), time, tau.key);
                    let e = pending.entry(k).or_insert((0, beta, sign));
                    e.0 = add_c(e.0, c, m)?;
                }
            }
            Ok(())
        };
        self.cofacets(sigma, w, &mut buf);
        for (t, s) in std::mem::take(&mut buf) {
            add(t, s as i64, &mut pending, &mut result, &mut cache, w)?;
        }
        let mut work = 0i64;
        while let Some(((v, _, tau_key), (c, beta, sign))) = pending.pop_first() {
            work += 1;
            if work == 256 {
                if budget.fetch_sub(work, Relaxed) - work < 0 {
                    return Err(CoflowError::OverBudget);
                }
                work = 0;
            }
            if cache.first_key_value().is_some_and(|(&k, _)| k < v) {
                cache = cache.split_off(&v);
            }
            if c == 0 {
                continue;
            }
            // coefficient of beta cancelling tau
            let cb = mul_c(-c, sign as i64, m)?;
            buf.clear();
            self.cofacets(&beta, w, &mut buf);
            let cof = std::mem::take(&mut buf);
            for (t, s) in &cof {
                if t.key == tau_key {
                    continue;
                }
                add(
                    t.clone(),
                    mul_c(cb, *s as i64, m)?,
                    &mut pending,
                    &mut result,
                    &mut cache,
                    w,
                )?;
            }
            buf = cof;
        }
        if budget.fetch_sub(work, Relaxed) - work < 0 {
            return Err(CoflowError::OverBudget);
        }
        Ok(result.into_iter().filter(|&(_, c)| c != 0).collect())
    }
}
