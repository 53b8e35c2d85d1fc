//! Construction for complexes of dimension at most 3, in a few passes over flat arrays. The
//! tops of real meshes come in no spatial order and the build is bound by memory traffic, so
//! every pass reads its input in order, scattered writes go to a few hundred "coarse" buckets
//! at once (vertices grouped by their high bits) or to small arrays, and a facet is one packed
//! word:
//!
//! 1. vertex degrees, and per vertex the number of facets whose smallest vertex it is;
//! 2. the vertex → tops relation (VT, rows sorted by id) by counting sort, and every facet as
//!    one word (its vertices, its top, the omitted vertex's position, and its top's place in
//!    the VT row of each of its vertices) in the coarse bucket of its smallest vertex;
//! 3. per coarse bucket (in cache): a counting sort by smallest vertex, then a small sort
//!    groups equal facets; their adjacency slots are written, and for each vertex w of the
//!    facet a *link* (two places in the VT row of w) joins the two tops in the star of w (the
//!    chain of tops for a non-manifold facet);
//! 4. per coarse bucket of vertices, once its links are all known: a union-find over their VT
//!    rows; the roots (the smallest id of each cluster, top edges and top vertices alone) are
//!    the vertices' references;
//! 5. the top records, in order.
//!
//! On large inputs the passes run in parallel (rayon), with the same result for any number of
//! workers: passes 1 and 2 over consecutive parts of a one-block complex (each part writes its
//! own VT rows, with places counted from the earlier parts, and its own facet words; the rows
//! are then joined part after part), pass 3 over ranges of coarse buckets holding about the
//! same number of facet words (adjacency slots are relaxed atomic stores, each slot written by
//! its one facet; non-manifold facets are numbered range after range), and pass 4 over ranges
//! holding about the same number of places and links.
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
    let n_ranges = n_parts(k.n_cells(), tuning);
    let (narrow, room) = link_room(&vt_off, &finc, nv, lay.low, tuning);
    drop(finc);
    // 2. VT by counting sort; facet words into coarse buckets
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
    let vt = Vt {
        off: &vt_off,
        targets: &targets,
    };
    let buckets = Buckets {
        nv,
        low: lay.low,
        n_ranges,
        vt_off: &vt_off,
    };
    let grouped = group_facets(
        &buckets, blocks, lay, &adj, &recs, &fcnt, &vt, &narrow, &room,
    );
    drop((recs, fcnt));
    let nm = number_non_manifold(&grouped, &adj, t, dmax);
    // 4. the clusters of every bucket's vertices
    let offsets = join_clusters(&buckets, &mut targets, &grouped);
    drop(grouped);
    // 5. the top records
    top_records(k, blocks, &adj);
    (nm, Csr { offsets, targets })
}

/// The coarse buckets of vertices (`1 << low` vertices each) and the VT row offsets, as the
/// phases of [`run`] share them.
struct Buckets<'a> {
    nv: usize,
    low: u32,
    n_ranges: usize,
    vt_off: &'a [u32],
}

impl Buckets<'_> {
    /// Number of coarse buckets.
    fn len(&self) -> usize {
        if self.nv == 0 {
            0
        } else {
            ((self.nv - 1) >> self.low) + 1
        }
    }
    /// The vertices of bucket `c`.
    fn vertices(&self, c: usize) -> (usize, usize) {
        (c << self.low, ((c + 1) << self.low).min(self.nv))
    }
    /// The first VT place of bucket `c` (the end of the VT for `c == len()`).
    fn vlo(&self, c: usize) -> usize {
        self.vt_off[(c << self.low).min(self.nv)] as usize
    }
}

/// Per coarse bucket, whether its links are packed in one word (narrow), and the room for
/// the links into it (see [`Links`]).
fn link_room(
    vt_off: &[u32],
    finc: &[u32],
    nv: usize,
    low: u32,
    tuning: Tuning,
) -> (Vec<bool>, Vec<usize>) {
    let nc = if nv == 0 { 0 } else { ((nv - 1) >> low) + 1 };
    let narrow: Vec<bool> = (0..nc)
        .map(|c| {
            let (v0, v1) = (c << low, ((c + 1) << low).min(nv));
            tuning.pack_links && vt_off[v1] - vt_off[v0] <= 1 << 16
        })
        .collect();
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
    (narrow, room)
}

/// Phase 3: per coarse bucket, in ranges of buckets run in parallel, groups equal facets,
/// writes the adjacency slots of manifold facets into `adj`, and leaves the links (and the
/// non-manifold facets) each range found.
#[allow(clippy::too_many_arguments)]
fn group_facets<W: Word>(
    bk: &Buckets<'_>,
    blocks: &[Block],
    lay: Layout,
    adj: &[Vec<AtomicU32>; 2],
    recs: &[Vec<Part<W>>; 2],
    fcnt: &[Vec<u32>; 2],
    vt: &Vt<'_>,
    narrow: &[bool],
    room: &[usize],
) -> Vec<Grouped> {
    let nc = bk.len();
    let ids = [DimIds::new(blocks, 2), DimIds::new(blocks, 3)];
    // ranges with about the same number of facet words (buckets of small vertices hold
    // more of them: a facet is filed under its smallest vertex)
    let branges = balanced(nc, bk.n_ranges, |c| {
        let (v0, v1) = bk.vertices(c);
        fcnt.iter()
            .filter(|f| !f.is_empty())
            .map(|f| (f[v1] - f[v0]) as u64)
            .sum()
    });
    branges
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
                narrow: narrow.to_vec(),
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
                        g.chunk(d + 2, &recs[d], &fcnt[d], vt, c, &mut tmp, &mut links);
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
        .collect()
}

/// The non-manifold facets, numbered range after range (the sequential order), with their
/// adjacency slots written.
fn number_non_manifold(
    grouped: &[Grouped],
    adj: &[Vec<AtomicU32>; 2],
    t: &[u64],
    dmax: usize,
) -> Vec<Csr> {
    let mut nm: Vec<Csr> = vec![Csr::default(); dmax + 1];
    for d in 0..2 {
        if t.get(d + 2).is_none_or(|&x| x == 0) {
            continue;
        }
        let mut offsets = vec![0u32];
        let mut tops = Vec::new();
        for gr in grouped {
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
    nm
}

/// Phase 4: per coarse bucket, in parallel ranges of about the same number of places and
/// links: the links into it from every range, then the clusters of its vertices (roots kept
/// at the front of the range's VT); then the ranges' kept references packed. Returns the
/// offsets of the packed `targets`.
fn join_clusters(bk: &Buckets<'_>, targets: &mut Vec<u32>, grouped: &[Grouped]) -> Vec<u32> {
    let (nv, low, vt_off) = (bk.nv, bk.low, bk.vt_off);
    let branges = balanced(bk.len(), bk.n_ranges, |c| {
        let links: usize = grouped
            .iter()
            .map(|g| g.links.end[c] - g.links.start[c] + g.links.over[c].len())
            .sum();
        (bk.vlo(c + 1) - bk.vlo(c) + links) as u64
    });
    let t_pieces = split_by(targets, &branges, |c| bk.vlo(c));
    let kept: Vec<(usize, Vec<u32>)> = branges
        .par_iter()
        .zip(t_pieces)
        .map(|(br, tg)| {
            let mut par: Vec<u32> = Vec::new();
            let base = bk.vlo(br.start);
            let mut out = 0usize;
            let mut offs = Vec::with_capacity((br.end << low).min(nv) - (br.start << low).min(nv));
            for c in br.clone() {
                let (lo, hi) = (bk.vlo(c) - base, bk.vlo(c + 1) - base);
                par.clear();
                par.extend(0..(hi - lo) as u32);
                let bpar = &mut par[..];
                let mut joined = false;
                for gr in grouped {
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
                let (v0, v1) = bk.vertices(c);
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
    // the ranges' kept references, packed
    let mut offsets = Vec::with_capacity(nv + 1);
    offsets.push(0u32);
    let mut out = 0usize;
    for (br, (n_kept, offs)) in branges.iter().zip(kept) {
        let base = bk.vlo(br.start);
        targets.copy_within(base..base + n_kept, out);
        offsets.extend(offs.iter().map(|&x| x + out as u32));
        out += n_kept;
    }
    targets.truncate(out);
    targets.shrink_to_fit();
    offsets
}

/// Phase 5: the top records: vertices (input order), then the adjacency slots.
fn top_records(k: &IndexedComplex, blocks: &mut [Block], adj: &[Vec<AtomicU32>; 2]) {
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
