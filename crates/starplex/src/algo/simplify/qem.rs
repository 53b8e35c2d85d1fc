//! Quadric-error simplification (`--mode qem`) of triangle and tetrahedral meshes
//! (Garland–Heckbert), that never changes the topology.
//!
//! Each vertex carries the sum of the (area-weighted) plane quadrics of its surface triangles
//! (the boundary triangles of a tetrahedral mesh), plus, on a surface's boundary edges, planes
//! through the edge perpendicular to the triangle (weight [`BOUNDARY_WEIGHT`]), plus a tiny
//! point quadric that makes every system solvable. Edges are contracted cheapest first to the
//! point minimising the summed quadric, in two phases:
//! * passes: every edge's cost, sorted; the cheapest edges no two of which share a vertex (so
//!   that their costs hold during the pass), as many as the target still needs and at most 1.5
//!   times the cost of the last needed, contracted in the order of the vertices. The mesh is
//!   numbered along a Z-order curve for the run (and back at the end), so that a pass reads
//!   the memory in order instead of hopping across it as the cost order does;
//! * once a pass selects few edges or sees a quarter of them refused, the greedy order: a
//!   radix heap of edges (an entry is current when its key equals the recomputed cost), the
//!   survivor's edges queued again after each contraction.
//!
//! Every contraction is checked first by
//! * the extended link condition ([`LinkMode::Manifold`]): the Betti numbers are kept, no
//!   non-manifold vertex or edge appears, the boundary stays a manifold with the same loops;
//! * geometry: no triangle whose normal turns by more than ~78° (cos < 0.2) or becomes
//!   degenerate; no tetrahedron whose orientation (the exact `orient3d` of the `robust` crate)
//!   changes sign or becomes zero.
//!
//! When the heap empties before the target, the refused edges are queued again (a new round)
//! as long as the previous round contracted something. The passes and the rounds are the
//! report's `rounds`.
//!
//! ```
//! use starplex::algo::simplify::{TopSimplices, Target, qem::simplify_qem};
//! # use starplex::complex::{ComplexBuilder, BuildOptions};
//! # use starplex::cell::CellKind;
//! // a flat 4x4 grid of squares split into triangles
//! let mut b = ComplexBuilder::new(3).unwrap();
//! for j in 0..5 { for i in 0..5 { b.push_vertex(&[i as f64, j as f64, 0.0]).unwrap(); } }
//! for j in 0..4u32 { for i in 0..4u32 {
//!     let v = j * 5 + i;
//!     b.push_cell(CellKind::Simplex(2), &[v, v + 1, v + 6]).unwrap();
//!     b.push_cell(CellKind::Simplex(2), &[v, v + 6, v + 5]).unwrap();
//! } }
//! let k = b.build(&BuildOptions::default()).unwrap().0;
//! let mut w = TopSimplices::from_complex(&k).unwrap();
//! let s = simplify_qem(&mut w, &Target { faces: Some(8), ..Default::default() }, false, None).unwrap();
//! assert!(w.n_alive_tops() <= 8);
//! assert_eq!(s.n_contractions as usize, 25 - w.n_alive_vertices());
//! assert!(s.mean_error >= 0.0);
//! ```

use super::link_condition::{link_condition, region_condition, LinkMode, LinkScratch};
use super::tops::TopSimplices;
use super::{Progress, SimplifyError, Target};

/// Weight of a boundary edge's perpendicular plane, per squared edge length.
pub const BOUNDARY_WEIGHT: f64 = 100.0;
/// Smallest cosine allowed between a triangle's normal before and after a contraction.
pub const MIN_NORMAL_COS: f64 = 0.2;

/// What [`simplify_qem`] did.
///
/// ```
/// let s = starplex::algo::simplify::qem::QemStats::default();
/// assert_eq!(s.n_contractions, 0);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct QemStats {
    /// Edges contracted.
    pub n_contractions: u64,
    /// Passes over every edge, then rounds of the greedy queue.
    pub rounds: u64,
    /// Largest quadric error of an accepted contraction.
    pub max_error: f64,
    /// Mean quadric error of the accepted contractions.
    pub mean_error: f64,
    /// Contractions refused by the link condition.
    pub refused_link: u64,
    /// Contractions refused by geometry (flip, degenerate or inverted cell).
    pub refused_geometry: u64,
}

/// A symmetric 4x4 quadric: a², ab, ac, ad, b², bc, bd, c², cd, d².
#[derive(Clone, Copy, Debug, Default)]
struct Quadric([f64; 10]);

impl Quadric {
    fn plane(n: [f64; 3], d: f64, w: f64) -> Quadric {
        let [a, b, c] = n;
        Quadric([
            w * a * a,
            w * a * b,
            w * a * c,
            w * a * d,
            w * b * b,
            w * b * c,
            w * b * d,
            w * c * c,
            w * c * d,
            w * d * d,
        ])
    }
    fn point(p: [f64; 3], w: f64) -> Quadric {
        Quadric([
            w,
            0.0,
            0.0,
            -w * p[0],
            w,
            0.0,
            -w * p[1],
            w,
            -w * p[2],
            w * dot(p, p),
        ])
    }
    fn add(&mut self, o: &Quadric) {
        for (x, y) in self.0.iter_mut().zip(o.0) {
            *x += y;
        }
    }
    fn sum(&self, o: &Quadric) -> Quadric {
        let mut q = *self;
        q.add(o);
        q
    }
    fn eval(&self, p: [f64; 3]) -> f64 {
        let q = &self.0;
        let [x, y, z] = p;
        q[0] * x * x
            + 2.0 * q[1] * x * y
            + 2.0 * q[2] * x * z
            + 2.0 * q[3] * x
            + q[4] * y * y
            + 2.0 * q[5] * y * z
            + 2.0 * q[6] * y
            + q[7] * z * z
            + 2.0 * q[8] * z
            + q[9]
    }
    /// The minimiser, when the 3x3 system is well conditioned: the symmetric system solved by
    /// its cofactors (the adjugate of a symmetric matrix is symmetric: six cofactors, one
    /// determinant test, no copy of the matrix).
    fn optimum(&self) -> Option<[f64; 3]> {
        let [a, b, c, d, e, f, g, h, i, _] = self.0;
        // | a b c |       | -d |
        // | b e f | x  =  | -g |
        // | c f h |       | -i |
        let c00 = e * h - f * f;
        let c01 = c * f - b * h;
        let c02 = b * f - c * e;
        let det = a * c00 + b * c01 + c * c02;
        let scale = a.abs() + e.abs() + h.abs();
        if !det.is_finite() || det.abs() <= 1e-12 * scale * scale * scale {
            return None;
        }
        let c11 = a * h - c * c;
        let c12 = b * c - a * f;
        let c22 = a * e - b * b;
        let inv = 1.0 / det;
        let (r0, r1, r2) = (-d, -g, -i);
        let x = [
            (c00 * r0 + c01 * r1 + c02 * r2) * inv,
            (c01 * r0 + c11 * r1 + c12 * r2) * inv,
            (c02 * r0 + c12 * r1 + c22 * r2) * inv,
        ];
        x.iter().all(|v| v.is_finite()).then_some(x)
    }
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn normal(p: [[f64; 3]; 3]) -> [f64; 3] {
    cross(sub(p[1], p[0]), sub(p[2], p[0]))
}

/// An edge of a pass in 12 bytes: its cost's 24 key bits ([`cost_bits`]) and its two
/// vertices.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
struct Edge {
    key: u32,
    a: u32,
    b: u32,
}

/// The 24 key bits of a cost: its f32 bits without the sign and the 7 lowest mantissa bits
/// (monotonic for non-negative costs, 2^-16 relative precision; NaN last, negatives as 0).
fn cost_bits(cost: f64) -> u32 {
    let c = cost as f32;
    let bits = if c.is_nan() {
        f32::MAX.to_bits()
    } else {
        c.max(0.0).to_bits()
    };
    bits >> 7
}

/// The cost that [`cost_bits`] maps to `key` (the smallest of its bin).
fn key_cost(key: u32) -> f64 {
    f32::from_bits(key << 7) as f64
}

/// Calls `f(a, b, cost)` for every contractible edge `a < b` of the live vertices, in vertex
/// order, with its current cost: the sweep of a pass and of a greedy round.
fn each_edge_cost(
    w: &TopSimplices,
    nb: &mut Vec<u32>,
    run: &Run,
    mut f: impl FnMut(u32, u32, f64),
) {
    for a in 0..w.n_vertices() as u32 {
        if !w.is_alive(a) {
            continue;
        }
        w.neighbours_above_into(a, nb);
        for &b in nb.iter() {
            if let Some((cost, _)) = run.candidate(a, b) {
                f(a, b, cost);
            }
        }
    }
}

/// Sorts the edges by key, ties in vertex order (`a`, then `b`), in place: the edges moved
/// into buckets of their key's upper 16 bits by swaps (American flag sort), a bucket of more
/// than 32 the same way on the lower 8, then each run of one key by its vertices. On edges
/// listed in vertex order (each once), this is a stable sort by key.
fn sort_in_place(edges: &mut [Edge]) {
    let by_vertices = |run: &mut [Edge]| run.sort_unstable_by_key(|e| (e.a, e.b));
    let (mut starts, mut inner, mut next) = (Vec::new(), Vec::new(), Vec::new());
    flag_pass(edges, 16, |e| (e.key >> 8) as usize, &mut starts, &mut next);
    for b in starts.windows(2) {
        let bucket = &mut edges[b[0]..b[1]];
        if bucket.len() <= 32 {
            bucket.sort_unstable_by_key(|e| (e.key, e.a, e.b));
            continue;
        }
        flag_pass(
            bucket,
            8,
            |e| (e.key & 0xff) as usize,
            &mut inner,
            &mut next,
        );
        for r in inner.windows(2).filter(|r| r[1] - r[0] > 1) {
            by_vertices(&mut bucket[r[0]..r[1]]);
        }
    }
}

/// One in-place bucket pass of [`sort_in_place`] on a digit of `bits` bits: `starts` receives
/// the `2^bits + 1` bucket boundaries; `next` is scratch.
fn flag_pass(
    edges: &mut [Edge],
    bits: u32,
    digit: impl Fn(&Edge) -> usize,
    starts: &mut Vec<usize>,
    next: &mut Vec<usize>,
) {
    let n = 1usize << bits;
    next.clear();
    next.resize(n, 0);
    for e in edges.iter() {
        next[digit(e)] += 1;
    }
    starts.clear();
    starts.push(0);
    for &c in next.iter() {
        starts.push(starts[starts.len() - 1] + c);
    }
    // the next unsorted place of every bucket; an edge out of place is carried along its
    // cycle (each edge written once) until one of bucket `b` comes back
    next.copy_from_slice(&starts[..n]);
    for b in 0..n {
        let end = starts[b + 1];
        while next[b] < end {
            let mut e = edges[next[b]];
            let mut d = digit(&e);
            while d != b {
                std::mem::swap(&mut e, &mut edges[next[d]]);
                next[d] += 1;
                d = digit(&e);
            }
            edges[next[b]] = e;
            next[b] += 1;
        }
    }
}

/// A pass's edges: every contractible edge of the live vertices with its current cost, then
/// those a pass may select ([`pass_limit`]: of key at most the limit, which `max_key` caps) by
/// increasing cost, ties in vertex order, sorted in place (no spare). Returns the largest key
/// and how many edges the pass selects at most.
fn pass_edges(
    w: &TopSimplices,
    target: &Target,
    nb: &mut Vec<u32>,
    run: &Run,
    tops_per_contraction: f64,
    max_key: u32,
    edges: &mut Vec<Edge>,
) -> (u32, usize) {
    edges.clear();
    each_edge_cost(w, nb, run, |a, b, cost| {
        edges.push(Edge {
            key: cost_bits(cost),
            a,
            b,
        })
    });
    let (limit, cap) = pass_limit(w, target, edges, tops_per_contraction);
    let limit = limit.min(max_key);
    edges.retain(|e| e.key <= limit);
    sort_in_place(edges);
    (limit, cap)
}

/// The `k`-th smallest key of the edges (from 0), `None` when there are no more than `k`:
/// the key's upper 12 bits by a count over all, then its lower 12 over those that share them.
fn nth_key(edges: &[Edge], k: usize) -> Option<u32> {
    if k >= edges.len() {
        return None;
    }
    const BITS: u32 = 12;
    const MASK: u32 = (1 << BITS) - 1;
    // the bucket of digit values holding rank `k` (counts of `digit` over the edges `keep`)
    let rank = |keep: &dyn Fn(u32) -> bool, digit: &dyn Fn(u32) -> usize, k: usize| {
        let mut count = [0usize; 1 << BITS];
        for e in edges.iter().filter(|e| keep(e.key)) {
            count[digit(e.key)] += 1;
        }
        let mut below = 0;
        for (d, &c) in count.iter().enumerate() {
            if k < below + c {
                return (d as u32, k - below);
            }
            below += c;
        }
        unreachable!("rank {k} is below the number of edges")
    };
    let (hi, k) = rank(&|_| true, &|key| (key >> BITS) as usize, k);
    let (lo, _) = rank(&|key| key >> BITS == hi, &|key| (key & MASK) as usize, k);
    Some((hi << BITS) | lo)
}

/// How far a pass goes: the largest key it contracts, and how many edges it selects. Both
/// follow the contractions still needed to reach the target (`tops_per_contraction` top
/// cells go with each): at most that many edges, of cost at most 1.5 times that of the edge
/// at that position in cost order, so that a pass stays near the cheapest edges and ends where
/// the greedy order would (without a count target, as if a quarter of the vertices were to
/// go). `edges` in any order.
fn pass_limit(
    w: &TopSimplices,
    target: &Target,
    edges: &[Edge],
    tops_per_contraction: f64,
) -> (u32, usize) {
    let by_faces = target
        .faces
        .map(|f| w.n_alive_tops().saturating_sub(f) as f64 / tops_per_contraction);
    let by_vertices = target
        .vertices
        .map(|v| w.n_alive_vertices().saturating_sub(v) as f64);
    let needed = match by_faces.into_iter().chain(by_vertices).reduce(f64::min) {
        Some(x) => (x.ceil() as usize).max(1),
        // no count target: a quarter of the vertices a pass
        None => (w.n_alive_vertices() / 4).max(1),
    };
    match nth_key(edges, needed) {
        Some(key) => (cost_bits(key_cost(key) * 1.5).max(key), needed),
        None => (u32::MAX, needed),
    }
}

/// A queued edge in 12 bytes: a 32-bit key and the two vertices. The key's upper 24 bits are
/// the cost (its f32 bits without the sign and the 7 lowest mantissa bits: monotonic for
/// non-negative costs, 2^-16 relative precision), its lower 8 bits 4 bits of each vertex's
/// stamp (bumped when the vertex survives a contraction). An entry is current when the stamps
/// match and its cost bits equal those of the edge's cost recomputed when it is popped: every
/// contraction queues again each edge of the survivor with its new cost and no other edge's
/// cost changes, so each live edge always has a current entry. The stamps reject most older
/// entries without recomputing a cost; one that slips through (a stamp wrapped) fails the cost
/// test, or carries the right cost anyway.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Entry {
    key: u32,
    a: u32,
    b: u32,
}

impl Entry {
    fn new(cost: f64, a: u32, b: u32, stamp: &[u8]) -> Entry {
        let st = (stamp[a as usize] as u32 & 15) << 4 | (stamp[b as usize] as u32 & 15);
        Entry {
            key: cost_bits(cost) << 8 | st,
            a,
            b,
        }
    }
    /// The stamps still match the vertices'.
    fn fresh(self, stamp: &[u8]) -> bool {
        let st = (stamp[self.a as usize] as u32 & 15) << 4 | (stamp[self.b as usize] as u32 & 15);
        self.key & 0xff == st
    }
    /// The cost bits are those of `cost`.
    fn current(self, cost: f64) -> bool {
        self.key >> 8 == cost_bits(cost)
    }
}

/// A radix heap over the entries' 32-bit cost keys (Ahuja, Mehlhorn, Orlin, Tarjan): a bucket
/// per highest bit in which a key differs from the last key popped. Pushes are appends, and an
/// entry moves to a lower bucket at most 32 times, so the millions of entries of a big mesh are
/// touched sequentially instead of by the scattered sifts of a binary or 4-ary heap (which took
/// 28% of the time on tri_armadillo_x16). A key below the last one popped (a contraction can
/// make an edge cheaper than the current minimum) goes to bucket 0, the bucket of the keys
/// equal to the last: it is smaller than everything in the other buckets, so it comes out
/// next, keeping its own key (entries of bucket 0 come out last in, first out). A bucket that
/// was emptied by a redistribution gives its memory back when it is large, so the heap's
/// footprint follows the live entries instead of the largest each bucket ever held.
///
/// The entries of a round's start (one per edge, nearly all of a round's entries at once) are
/// not pushed: they are sorted into one exactly sized array ([`fill`](Self::fill)), consumed
/// from its cheap end and merged with the buckets at each pop, so they are never moved between
/// buckets nor held twice while a bucket is redistributed.
struct RadixHeap {
    last: u32,
    len: usize,
    buckets: [Vec<Entry>; 33],
    /// The round's first entries, by decreasing key (the smallest last).
    sorted: Vec<Entry>,
}

impl Default for RadixHeap {
    fn default() -> Self {
        RadixHeap {
            last: 0,
            len: 0,
            buckets: std::array::from_fn(|_| Vec::new()),
            sorted: Vec::new(),
        }
    }
}

impl RadixHeap {
    fn bucket(key: u32, last: u32) -> usize {
        32 - (key ^ last).leading_zeros() as usize
    }
    /// Empties the heap (keeping the buckets' memory) and starts again from key 0.
    fn clear(&mut self) {
        self.last = 0;
        self.len = 0;
        for b in &mut self.buckets {
            b.clear();
        }
        self.sorted = Vec::new();
    }
    /// Adds the round's first entries (the heap is empty), sorted by decreasing key.
    fn fill(&mut self, mut entries: Vec<Entry>) {
        entries.sort_unstable_by_key(|e| std::cmp::Reverse(e.key));
        self.len += entries.len();
        self.sorted = entries;
    }
    fn push(&mut self, e: Entry) {
        let i = if e.key <= self.last {
            0
        } else {
            Self::bucket(e.key, self.last)
        };
        self.buckets[i].push(e);
        self.len += 1;
    }
    /// Drops the entries `keep` refuses (the stale ones), bucket by bucket, in place.
    fn retain(&mut self, mut keep: impl FnMut(Entry) -> bool) {
        for b in &mut self.buckets {
            b.retain(|&e| keep(e));
        }
        self.sorted.retain(|&e| keep(e));
        self.sorted.shrink_to_fit();
        self.len = self.buckets.iter().map(Vec::len).sum::<usize>() + self.sorted.len();
    }
    fn pop(&mut self) -> Option<Entry> {
        let k = self.bucket_min();
        let e = match (self.sorted.last(), k) {
            (Some(s), Some(k)) if s.key <= k => self.sorted.pop(),
            (Some(_), None) => self.sorted.pop(),
            (_, Some(_)) => self.buckets[0].pop(),
            (None, None) => None,
        };
        self.len -= e.is_some() as usize;
        if self.sorted.capacity() > 2 * self.sorted.len() + 65536 {
            self.sorted.shrink_to_fit(); // the consumed end gives its memory back
        }
        e
    }
    /// The key of the next entry of the buckets (bucket 0 filled from the lowest non-empty
    /// bucket if needed).
    fn bucket_min(&mut self) -> Option<u32> {
        if self.buckets[0].is_empty() {
            let i = (1..33).find(|&i| !self.buckets[i].is_empty())?;
            let mut b = std::mem::take(&mut self.buckets[i]);
            let m = b.iter().map(|e| e.key).min().unwrap_or(self.last);
            self.last = m;
            for e in b.drain(..) {
                self.buckets[Self::bucket(e.key, m)].push(e);
            }
            // a large emptied bucket gives its memory back (it refills by pushes)
            if b.capacity() > 4096 {
                b = Vec::new();
            }
            self.buckets[i] = b;
        }
        self.buckets[0].last().map(|e| e.key)
    }
}

/// Is the working structure a mesh QEM handles: every top a triangle, or every top a
/// tetrahedron in 3D, with 2 or 3 coordinates per vertex?
///
/// ```
/// use starplex::algo::simplify::{TopSimplices, qem::qem_dimension};
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// # let mut b = ComplexBuilder::new(3).unwrap();
/// # for p in [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]] { b.push_vertex(&p).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// let w = TopSimplices::from_complex(&k).unwrap();
/// assert_eq!(qem_dimension(&w), Some(2));
/// ```
pub fn qem_dimension(w: &TopSimplices) -> Option<usize> {
    let d = w.dim()?;
    let ok = (d == 2 && (w.stride == 2 || w.stride == 3)) || (d == 3 && w.stride == 3);
    (ok && w.tops().all(|t| t.len() == d + 1)).then_some(d)
}

/// Simplifies a triangle or tetrahedral mesh by quadric error until the target (faces = top
/// simplices, vertices, or the error bound) is reached or no edge can be contracted.
/// `lock_boundary` keeps boundary vertices where they are and never removes one; so are the
/// locked vertices ([`TopSimplices::set_locked`]), and an edge between two such vertices is never
/// contracted.
///
/// ```
/// use starplex::algo::simplify::{TopSimplices, Target, qem::simplify_qem};
/// let mut w = TopSimplices::from_tops(3, &[vec![0, 1, 2]]).unwrap();
/// assert!(simplify_qem(&mut w, &Target::default(), false, None).is_err()); // no coordinates
/// ```
///
/// # Errors
/// [`SimplifyError::NotAMesh`] when the structure is not a pure triangle mesh (2D or 3D) or a
/// pure tetrahedral mesh (3D).
pub fn simplify_qem(
    w: &mut TopSimplices,
    target: &Target,
    lock_boundary: bool,
    progress: Option<&Progress>,
) -> Result<QemStats, SimplifyError> {
    run_qem(w, target, lock_boundary, progress, true)
}

/// [`simplify_qem`], with the passes (`with_passes`) or the greedy phase alone (the reference
/// order the tests compare the passes with).
fn run_qem(
    w: &mut TopSimplices,
    target: &Target,
    lock_boundary: bool,
    progress: Option<&Progress>,
    with_passes: bool,
) -> Result<QemStats, SimplifyError> {
    let d = qem_dimension(w).ok_or(SimplifyError::NotAMesh)?;
    // numbered along a space-filling curve for the run, and back at the end
    let (to_new, order) = locality_order(w);
    w.permute(&to_new, &order);
    let n = w.n_vertices();
    let stride = w.stride;
    // the positions as 3D points for the run: the coordinates themselves in 3D (no copy), a
    // padded copy in 2D (written back at the end)
    let mut coords = std::mem::take(&mut w.coords);
    let mut padded: Vec<[f64; 3]> = Vec::new();
    if stride != 3 {
        padded = coords
            .chunks_exact(stride)
            .map(|p| [p[0], p[1], p.get(2).copied().unwrap_or(0.0)])
            .collect();
        coords = Vec::new();
    }
    let pos: &mut [[f64; 3]] = if stride == 3 {
        coords.as_chunks_mut::<3>().0
    } else {
        &mut padded
    };
    let (mut quad, boundary, total_area, n_surface) = surface_quadrics(w, d, pos);
    // vertices that neither move nor disappear: the locked ones, and the boundary if asked
    let locked: Vec<bool> = (0..n as u32)
        .map(|v| w.is_locked(v) || (lock_boundary && boundary[v as usize]))
        .collect();
    let eps = 1e-6 * total_area / n_surface.max(1) as f64;
    let eps = if eps > 0.0 && eps.is_finite() {
        eps
    } else {
        1e-12
    };
    for (q, p) in quad.iter_mut().zip(pos.iter()) {
        q.add(&Quadric::point(*p, eps));
    }

    let mut run = Run {
        d,
        pos,
        quad,
        locked,
        scratch: LinkScratch::default(),
        stats: QemStats::default(),
        sum_err: 0.0,
        unreported: 0,
        progress,
    };
    let mut nb = Vec::new();
    if !with_passes || passes(w, target, &mut run, &mut nb) {
        greedy(w, target, &mut run, &mut nb);
    }
    let (mut stats, sum_err, unreported) = (run.stats, run.sum_err, run.unreported);
    drop(run); // the quadrics go before the numbering back
    if unreported > 0
        && let Some(pr) = progress
    {
        pr(unreported);
    }
    if stats.n_contractions > 0 {
        stats.mean_error = sum_err / stats.n_contractions as f64;
    }
    w.coords = if stride == 3 {
        coords
    } else {
        padded
            .iter()
            .flat_map(|p| p.iter().copied().take(stride))
            .collect()
    };
    w.permute(&crate::buf::invert(&to_new), &crate::buf::invert(&order));
    Ok(stats)
}

/// The run's numbering: the vertices along a Z-order (Morton) curve through their
/// positions (21 bits an axis over the bounding box), and the tops by their first vertex in
/// that order (a stable counting sort; removed tops last). Returns the new id of each vertex
/// and, per new top slot, the slot its top comes from.
fn locality_order(w: &TopSimplices) -> (Vec<u32>, Vec<u32>) {
    let n = w.n_vertices();
    let s = w.stride;
    let point = |v: usize| -> [f64; 3] {
        let p = &w.coords[v * s..(v + 1) * s];
        [p[0], p[1], p.get(2).copied().unwrap_or(0.0)]
    };
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for v in 0..n {
        for (k, x) in point(v).into_iter().enumerate() {
            if x.is_finite() {
                lo[k] = lo[k].min(x);
                hi[k] = hi[k].max(x);
            }
        }
    }
    let scale: [f64; 3] = std::array::from_fn(|k| {
        let e = hi[k] - lo[k];
        if e > 0.0 && e.is_finite() {
            ((1u64 << 21) - 1) as f64 / e
        } else {
            0.0
        }
    });
    let mut keys: Vec<(u64, u32)> = (0..n)
        .map(|v| {
            let p = point(v);
            let key = (0..3).fold(0u64, |key, k| {
                // NaN and out-of-range values clamp (`as` saturates)
                let q = ((p[k] - lo[k]) * scale[k]) as u64;
                key | spread_bits(q.min((1 << 21) - 1)) << k
            });
            (key, v as u32)
        })
        .collect();
    // by key, equal keys in vertex order: the order of sorting the pairs
    radix_sort_by_key(&mut keys);
    let mut to_new = vec![0u32; n];
    for (i, &(_, v)) in keys.iter().enumerate() {
        to_new[v as usize] = i as u32;
    }
    drop(keys);
    // tops by their smallest new vertex (removed tops, with none, after all)
    let n_tops = w.n_top_slots();
    let first: Vec<u32> = (0..n_tops as u32)
        .map(|t| {
            w.top(t)
                .iter()
                .map(|&v| to_new[v as usize])
                .min()
                .unwrap_or(n as u32)
        })
        .collect();
    let mut start = vec![0u32; n + 2];
    for &f in &first {
        start[f as usize + 1] += 1;
    }
    for i in 1..start.len() {
        start[i] += start[i - 1];
    }
    let mut order = vec![0u32; n_tops];
    for (t, &f) in first.iter().enumerate() {
        let at = &mut start[f as usize];
        order[*at as usize] = t as u32;
        *at += 1;
    }
    (to_new, order)
}

/// Sorts the pairs by their key, stably (least significant digit first, 16 bits a pass; a
/// pass whose digit is the same for every pair is skipped).
fn radix_sort_by_key(keys: &mut Vec<(u64, u32)>) {
    let mut spare = vec![(0u64, 0u32); keys.len()];
    let mut count = vec![0usize; 1 << 16];
    for shift in [0, 16, 32, 48] {
        let digit = |k: &(u64, u32)| ((k.0 >> shift) & 0xffff) as usize;
        count.fill(0);
        for k in keys.iter() {
            count[digit(k)] += 1;
        }
        if keys.first().is_none_or(|k| count[digit(k)] == keys.len()) {
            continue;
        }
        let mut at = 0;
        for c in count.iter_mut() {
            let k = *c;
            *c = at;
            at += k;
        }
        for k in keys.iter() {
            let d = digit(k);
            spare[count[d]] = *k;
            count[d] += 1;
        }
        std::mem::swap(keys, &mut spare);
    }
}

/// The 21 low bits of `x` spread to every third bit (bit `i` to bit `3i`).
fn spread_bits(x: u64) -> u64 {
    let mut x = x & 0x1f_ffff;
    x = (x | x << 32) & 0x1f_0000_0000_ffff;
    x = (x | x << 16) & 0x1f_0000_ff00_00ff;
    x = (x | x << 8) & 0x100f_00f0_0f00_f00f;
    x = (x | x << 4) & 0x10c3_0c30_c30c_30c3;
    x = (x | x << 2) & 0x1249_2492_4924_9249;
    x
}

/// The state of a run that both of its phases share: the positions, quadrics and locks, and
/// what was done.
struct Run<'a> {
    d: usize,
    pos: &'a mut [[f64; 3]],
    quad: Vec<Quadric>,
    locked: Vec<bool>,
    scratch: LinkScratch,
    stats: QemStats,
    sum_err: f64,
    unreported: u64,
    progress: Option<&'a Progress>,
}

impl Run<'_> {
    /// Contracts edge `a b` to `p` (at quadric error `cost`) when the link condition and the
    /// geometry allow it; returns the survivor (the locked end if there is one, else `a`).
    fn contract(
        &mut self,
        w: &mut TopSimplices,
        a: u32,
        b: u32,
        cost: f64,
        p: [f64; 3],
    ) -> Option<u32> {
        let (s, t) = if self.locked[b as usize] {
            (b, a)
        } else {
            (a, b)
        };
        if !link_condition(w, s, t, LinkMode::Manifold, &mut self.scratch)
            || !region_condition(w, s, t, LinkMode::Manifold, &mut self.scratch)
        {
            self.stats.refused_link += 1;
            return None;
        }
        if !geometry_ok(w, self.d, self.pos, s, t, p) {
            self.stats.refused_geometry += 1;
            return None;
        }
        w.contract_linked(s, t);
        self.pos[s as usize] = p;
        let qs = self.quad[s as usize].sum(&self.quad[t as usize]);
        self.quad[s as usize] = qs;
        self.locked[s as usize] |= self.locked[t as usize];
        self.stats.n_contractions += 1;
        self.stats.max_error = self.stats.max_error.max(cost);
        self.sum_err += cost;
        // the progress callback in batches (a progress bar's update is not free)
        self.unreported += 1;
        if self.unreported == 1024
            && let Some(pr) = self.progress
        {
            pr(self.unreported);
            self.unreported = 0;
        }
        Some(s)
    }
    /// The cost and position of contracting `a b` now ([`candidate`]).
    fn candidate(&self, a: u32, b: u32) -> Option<(f64, [f64; 3])> {
        candidate(a, b, &self.quad, self.pos, &self.locked)
    }
}

/// A pass contracts on after one in which at least this share of the selected edges passed
/// the tests (below, refusals would make the passes drift from the cheapest-first order).
pub const PASS_MIN_SUCCESS: f64 = 0.75;

/// The first phase: passes over every edge while they are productive. A pass computes every
/// edge's cost, sorts them (a radix sort), selects the cheapest ones no two of which share a
/// vertex (their costs cannot change during the pass), up to what the target still needs,
/// and contracts them in the order of the vertices (along the space-filling curve, so that
/// consecutive contractions read neighbouring memory). Returns true when the greedy phase
/// should go on: the target is not reached and the last pass selected few edges or saw more
/// than a quarter refused.
fn passes(w: &mut TopSimplices, target: &Target, run: &mut Run, nb: &mut Vec<u32>) -> bool {
    let n = w.n_vertices();
    let (mut edges, mut selected) = (Vec::new(), Vec::new());
    // per vertex: the other end of its selected edge of this pass (`FREE`: none)
    const FREE: u32 = u32::MAX;
    let mut mate = vec![FREE; n];
    // top cells removed per contraction (measured after each pass)
    let mut tops_per_contraction = if run.d == 2 { 2.0 } else { 4.0 };
    let max_key = target.max_error.map_or(u32::MAX, cost_bits);
    while !target.reached(w) {
        run.stats.rounds += 1;
        let (limit, cap) = pass_edges(
            w,
            target,
            nb,
            run,
            tops_per_contraction,
            max_key,
            &mut edges,
        );
        // the cheapest edges, no two with a common end, in cost order
        let mut n_selected = 0;
        for e in &edges {
            if e.key > limit || n_selected >= cap {
                break;
            }
            let (a, b) = (e.a as usize, e.b as usize);
            if mate[a] == FREE && mate[b] == FREE {
                mate[a] = e.b;
                mate[b] = e.a;
                n_selected += 1;
            }
        }
        // contracted in the order of their vertices (no end of one is an end of another, so
        // each one's cost is still the one it was selected with): read from the mates in
        // vertex order, no sort
        selected.clear();
        for (a, m) in mate.iter_mut().enumerate() {
            if *m != FREE {
                if (a as u32) < *m {
                    selected.push((a as u32, *m));
                }
                *m = FREE;
            }
        }
        let (tops0, contractions0) = (w.n_alive_tops(), run.stats.n_contractions);
        for &(a, b) in &selected {
            if target.reached(w) {
                return false;
            }
            let Some((cost, p)) = run.candidate(a, b) else {
                continue;
            };
            if target.max_error.is_none_or(|m| cost <= m) {
                run.contract(w, a, b, cost, p);
            }
        }
        let made = run.stats.n_contractions - contractions0;
        let live = w.n_alive_vertices();
        if made == 0
            || (made as f64) < PASS_MIN_SUCCESS * selected.len() as f64
            || (selected.len() as u64) < (live / 64) as u64
        {
            break;
        }
        tops_per_contraction =
            (tops0.saturating_sub(w.n_alive_tops()) as f64 / made as f64).clamp(0.5, 64.0);
    }
    !target.reached(w)
}

/// The second phase: cheapest edge first from a radix heap (an entry is current when its key
/// equals the recomputed cost), each contraction queueing the survivor's edges again with
/// their new costs; when the heap empties before the target, the refused edges are queued
/// again (a new round) as long as the previous round contracted something.
fn greedy(w: &mut TopSimplices, target: &Target, run: &mut Run, nb: &mut Vec<u32>) {
    let n = w.n_vertices();
    let mut stamp = vec![0u8; n];
    let mut heap = RadixHeap::default();
    let mut last_round_contracted = true;
    'rounds: while last_round_contracted && !target.reached(w) {
        run.stats.rounds += 1;
        last_round_contracted = false;
        push_all(&mut heap, w, nb, run, &stamp);
        // the queue holds about one entry per live edge at the start of a round; when older
        // entries make it twice that (the live edges shrink with the vertices), they are
        // dropped, which bounds the queue's memory
        let (edges0, verts0) = (heap.len.max(1), w.n_alive_vertices().max(1));
        let mut compact_at = 2 * edges0 + 4096;
        while let Some(e) = heap.pop() {
            if heap.len > compact_at {
                heap.retain(|e| w.is_alive(e.a) && w.is_alive(e.b) && e.fresh(&stamp));
                let live = edges0 as f64 * w.n_alive_vertices() as f64 / verts0 as f64;
                compact_at = (2 * live as usize).max(heap.len + heap.len / 2) + 4096;
            }
            if target.reached(w) {
                break 'rounds;
            }
            let (a, b) = (e.a, e.b);
            if !w.is_alive(a) || !w.is_alive(b) || !e.fresh(&stamp) {
                continue;
            }
            let Some((cost, p)) = run.candidate(a, b) else {
                continue;
            };
            if !e.current(cost) {
                continue; // an older entry of an edge queued again since
            }
            if target.max_error.is_some_and(|m| cost > m) {
                break 'rounds;
            }
            let Some(s) = run.contract(w, a, b, cost, p) else {
                continue;
            };
            stamp[s as usize] = stamp[s as usize].wrapping_add(1);
            last_round_contracted = true;
            w.neighbours_into(s, nb);
            for &x in nb.iter() {
                if let Some((c, _)) = run.candidate(s, x) {
                    heap.push(Entry::new(c, s.min(x), s.max(x), &stamp));
                }
            }
        }
    }
}

/// The quadrics of the surface planes at every vertex (the triangles, or the boundary faces of
/// the tetrahedra, area-weighted; on a triangle mesh also the boundary-edge constraints), the
/// boundary vertices, the surface area and the number of surface triangles.
fn surface_quadrics(
    w: &TopSimplices,
    d: usize,
    pos: &[[f64; 3]],
) -> (Vec<Quadric>, Vec<bool>, f64, usize) {
    let n = w.n_vertices();
    let mut quad = vec![Quadric::default(); n];
    let mut boundary = vec![false; n];
    // surface triangles: the triangles themselves, or the boundary faces of the tets
    let tet_surface = (d == 3).then(|| boundary_faces(w));
    let mut total_area = 0.0;
    let mut n_surface = 0usize;
    let mut add_plane = |f: [u32; 3], quad: &mut [Quadric]| {
        let p = f.map(|v| pos[v as usize]);
        let nrm = normal(p);
        let len = dot(nrm, nrm).sqrt();
        if len > 0.0 {
            let u = nrm.map(|x| x / len);
            let q = Quadric::plane(u, -dot(u, p[0]), len / 2.0);
            for &v in &f {
                quad[v as usize].add(&q);
            }
        }
        total_area += len / 2.0;
        n_surface += 1;
    };
    match &tet_surface {
        Some(faces) => {
            for &f in faces {
                add_plane(f, &mut quad);
                for v in f {
                    boundary[v as usize] = true;
                }
            }
        }
        None => {
            for t in w.tops() {
                add_plane([t[0], t[1], t[2]], &mut quad);
            }
        }
    }
    drop(tet_surface);
    if d == 2 {
        boundary_edge_quadrics(w, pos, &mut quad, &mut boundary);
    }
    (quad, boundary, total_area, n_surface)
}

/// The boundary edges of a triangle mesh (in exactly one triangle), in (u, v) order, found
/// from each vertex's star (no edge table): marks their vertices in `boundary` and adds to both
/// ends the quadric of the plane through the edge perpendicular to its triangle.
fn boundary_edge_quadrics(
    w: &TopSimplices,
    pos: &[[f64; 3]],
    quad: &mut [Quadric],
    boundary: &mut [bool],
) {
    let n = w.n_vertices();
    // star: no edge table
    let mut around: Vec<(u32, u32)> = Vec::new();
    for u in 0..n as u32 {
        around.clear();
        for &t in w.star(u) {
            around.extend(w.top(t).iter().filter(|&&v| v > u).map(|&v| (v, t)));
        }
        around.sort_unstable();
        let mut i = 0;
        while i < around.len() {
            let (v, t) = around[i];
            let mut j = i + 1;
            while j < around.len() && around[j].0 == v {
                j += 1;
            }
            let single = j - i == 1;
            i = j;
            if !single {
                continue;
            }
            boundary[u as usize] = true;
            boundary[v as usize] = true;
            let tri = w.top(t);
            let p = [0, 1, 2].map(|k| pos[tri[k] as usize]);
            let nrm = normal(p);
            let e = sub(pos[v as usize], pos[u as usize]);
            let m = cross(e, nrm);
            let len = dot(m, m).sqrt();
            if len > 0.0 {
                let m = m.map(|x| x / len);
                let q = Quadric::plane(m, -dot(m, pos[u as usize]), BOUNDARY_WEIGHT * dot(e, e));
                quad[u as usize].add(&q);
                quad[v as usize].add(&q);
            }
        }
    }
}

/// The cost and the position of contracting edge `a b`: a locked end stays, else the
/// quadric's optimum, else the best of the midpoint and the ends; `None` when both are locked.
fn candidate(
    a: u32,
    b: u32,
    quad: &[Quadric],
    pos: &[[f64; 3]],
    locked: &[bool],
) -> Option<(f64, [f64; 3])> {
    let (la, lb) = (locked[a as usize], locked[b as usize]);
    let q = quad[a as usize].sum(&quad[b as usize]);
    let (pa, pb) = (pos[a as usize], pos[b as usize]);
    let p = if la && lb {
        return None;
    } else if la {
        pa
    } else if lb {
        pb
    } else if let Some(x) = q.optimum() {
        x
    } else {
        let mid = [
            (pa[0] + pb[0]) / 2.0,
            (pa[1] + pb[1]) / 2.0,
            (pa[2] + pb[2]) / 2.0,
        ];
        let mut best = (q.eval(mid), mid);
        for c in [pa, pb] {
            let e = q.eval(c);
            if e < best.0 {
                best = (e, c);
            }
        }
        best.1
    };
    Some((q.eval(p).max(0.0), p))
}

/// Fills the queue with one entry per contractible edge of the live vertices.
fn push_all(heap: &mut RadixHeap, w: &TopSimplices, nb: &mut Vec<u32>, run: &Run, stamp: &[u8]) {
    heap.clear();
    // one entry per edge (the capacity beyond is never touched, and is given back)
    let mut entries = Vec::new();
    each_edge_cost(w, nb, run, |a, b, cost| {
        entries.push(Entry::new(cost, a, b, stamp))
    });
    entries.shrink_to_fit();
    heap.fill(entries);
}

/// The boundary triangles of a tetrahedral mesh (in one tetrahedron), oriented outward for a
/// positively oriented tetrahedron, sorted by their sorted vertices. A face is looked up in the
/// star of its smallest vertex: no face table.
fn boundary_faces(w: &TopSimplices) -> Vec<[u32; 3]> {
    let mut faces: Vec<([u32; 3], [u32; 3])> = Vec::new();
    // each tet once: from its smallest vertex
    for v in 0..w.n_vertices() as u32 {
        for &id in w.star(v) {
            let t = w.top(id);
            if t.iter().any(|&x| x < v) {
                continue;
            }
            boundary_faces_of(w, id, t, &mut faces);
        }
    }
    faces.sort_unstable();
    faces.into_iter().map(|(_, f)| f).collect()
}

/// The faces of tet `id` (vertices `t`) in no other tet, as (sorted key, outward face).
fn boundary_faces_of(w: &TopSimplices, id: u32, t: &[u32], faces: &mut Vec<([u32; 3], [u32; 3])>) {
    {
        // facet i omits vertex i, sign (-1)^i
        for (f, flip) in [
            ([1, 2, 3], false),
            ([0, 2, 3], true),
            ([0, 1, 3], false),
            ([0, 1, 2], true),
        ] {
            let mut face = [t[f[0]], t[f[1]], t[f[2]]];
            if flip {
                face.swap(0, 1);
            }
            let mut key = face;
            key.sort_unstable();
            let shared = w.star(key[0]).iter().any(|&u| {
                u != id && {
                    let u = w.top(u);
                    u.contains(&key[1]) && u.contains(&key[2])
                }
            });
            if !shared {
                faces.push((key, face));
            }
        }
    }
}

/// No cell of the star of `s` or `t` (other than those through `st`, which disappear) flips,
/// degenerates or inverts when `s` and `t` move to `p`.
fn geometry_ok(w: &TopSimplices, d: usize, pos: &[[f64; 3]], s: u32, t: u32, p: [f64; 3]) -> bool {
    for v in [s, t] {
        for &c in w.star(v) {
            let top = w.top(c);
            if top.contains(&s) && top.contains(&t) {
                continue;
            }
            if d == 2 {
                let &[x, y, z] = top else {
                    return false;
                };
                let old = [x, y, z].map(|i| pos[i as usize]);
                let moved = |i: u32, q: [f64; 3]| if i == v { p } else { q };
                let new = [moved(x, old[0]), moved(y, old[1]), moved(z, old[2])];
                let (n0, n1) = (normal(old), normal(new));
                let (l0, l1) = (dot(n0, n0), dot(n1, n1));
                if l1 <= 1e-24 * l0 || l1 == 0.0 {
                    return false;
                }
                if dot(n0, n1) < MIN_NORMAL_COS * (l0 * l1).sqrt() {
                    return false;
                }
            } else {
                let &[x, y, z, u] = top else {
                    return false;
                };
                let old = [x, y, z, u].map(|i| pos[i as usize]);
                let moved = |i: u32, q: [f64; 3]| if i == v { p } else { q };
                let new = [
                    moved(x, old[0]),
                    moved(y, old[1]),
                    moved(z, old[2]),
                    moved(u, old[3]),
                ];
                let o = |q: [[f64; 3]; 4]| {
                    let c = |x: [f64; 3]| robust::Coord3D {
                        x: x[0],
                        y: x[1],
                        z: x[2],
                    };
                    robust::orient3d(c(q[0]), c(q[1]), c(q[2]), c(q[3]))
                };
                let (o0, o1) = (o(old), o(new));
                if o1 == 0.0 || (o0 > 0.0) != (o1 > 0.0) {
                    return false;
                }
            }
        }
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cell::CellKind;
    use crate::complex::{BuildOptions, ComplexBuilder, IndexedComplex};

    /// A bumpy torus of `nu x nv` vertices, numbered in a scrambled order.
    fn torus(nu: u32, nv: u32) -> IndexedComplex {
        let n = nu * nv;
        // a bijection of 0..n that scatters neighbours (7919 is prime, coprime with n here)
        let id = |i: u32, j: u32| ((i * nv + j) as u64 * 7919 % n as u64) as u32;
        let mut pts = vec![[0.0; 3]; n as usize];
        for i in 0..nu {
            for j in 0..nv {
                let (u, v) = (
                    i as f64 / nu as f64 * std::f64::consts::TAU,
                    j as f64 / nv as f64 * std::f64::consts::TAU,
                );
                let r = 1.0 + 0.15 * (5.0 * u).sin() * (3.0 * v).cos();
                pts[id(i, j) as usize] = [
                    (3.0 + r * v.cos()) * u.cos(),
                    (3.0 + r * v.cos()) * u.sin(),
                    r * v.sin(),
                ];
            }
        }
        let mut b = ComplexBuilder::new(3).unwrap();
        for p in &pts {
            b.push_vertex(p).unwrap();
        }
        for i in 0..nu {
            for j in 0..nv {
                let (i1, j1) = ((i + 1) % nu, (j + 1) % nv);
                let t = CellKind::Simplex(2);
                b.push_cell(t, &[id(i, j), id(i1, j), id(i1, j1)]).unwrap();
                b.push_cell(t, &[id(i, j), id(i1, j1), id(i, j1)]).unwrap();
            }
        }
        b.build(&BuildOptions::default()).unwrap().0
    }

    /// The passes contract nearly as cheaply as the greedy order: on a bumpy torus to a tenth
    /// of its triangles, the same count, the torus kept, and a mean quadric error within 10%
    /// of the greedy order's.
    #[test]
    fn passes_stay_near_the_greedy_order() {
        let k = torus(120, 60);
        let target = Target {
            faces: Some(1440),
            ..Default::default()
        };
        let mut runs = Vec::new();
        for with_passes in [true, false] {
            let mut w = TopSimplices::from_complex(&k).unwrap();
            let s = run_qem(&mut w, &target, false, None, with_passes).unwrap();
            assert_eq!(w.n_alive_tops(), 1440);
            let (out, _) = w.to_complex().unwrap();
            let euler = out.n_vertices() as i64 - out.n_cells() as i64 / 2; // V - E + F, E = 3F/2
            assert_eq!(euler, 0, "still a torus");
            runs.push(s);
        }
        let (p, g) = (runs[0], runs[1]);
        assert!(p.rounds >= 3 && g.rounds == 1, "{p:?} {g:?}");
        assert!(p.mean_error <= 1.1 * g.mean_error, "{p:?} {g:?}");
    }

    /// A planar annulus (2 coordinates a vertex): the run's numbering, passes and numbering back
    /// keep it an annulus with its two boundary loops' vertices where they were.
    #[test]
    fn planar_annulus_stays_an_annulus() {
        let (rings, sectors) = (12u32, 90u32);
        let mut b = ComplexBuilder::new(2).unwrap();
        for i in 0..rings {
            for j in 0..sectors {
                let (r, a) = (
                    1.0 + i as f64 / 4.0,
                    j as f64 / sectors as f64 * std::f64::consts::TAU,
                );
                b.push_vertex(&[r * a.cos(), r * a.sin()]).unwrap();
            }
        }
        let id = |i: u32, j: u32| i * sectors + j % sectors;
        for i in 0..rings - 1 {
            for j in 0..sectors {
                let t = CellKind::Simplex(2);
                b.push_cell(t, &[id(i, j), id(i + 1, j), id(i + 1, j + 1)])
                    .unwrap();
                b.push_cell(t, &[id(i, j), id(i + 1, j + 1), id(i, j + 1)])
                    .unwrap();
            }
        }
        let k = b.build(&BuildOptions::default()).unwrap().0;
        let mut w = TopSimplices::from_complex(&k).unwrap();
        let target = Target {
            faces: Some(400),
            ..Default::default()
        };
        let s = simplify_qem(&mut w, &target, true, None).unwrap();
        assert!(s.rounds >= 2 && w.n_alive_tops() <= 400, "{s:?}");
        assert_eq!(w.stride, 2);
        // the boundary circles are locked: alive, unmoved
        for j in 0..sectors {
            for v in [id(0, j), id(rings - 1, j)] {
                assert!(w.is_alive(v));
                assert_eq!(w.point(v), k.point(crate::ids::VertexId(v)));
            }
        }
        let (out, _) = w.to_complex().unwrap();
        // E = (3F + B) / 2 with the B = 2 * sectors boundary edges kept
        let f = out.n_cells() as i64;
        let euler = out.n_vertices() as i64 - (3 * f + 2 * sectors as i64) / 2 + f;
        assert_eq!(euler, 0, "still an annulus");
    }

    /// The in-place sort orders edges listed in vertex order as a stable sort by key does:
    /// random keys, buckets of more than 32 edges, and long runs of one key.
    #[test]
    fn sort_in_place_is_a_stable_sort_by_key() {
        let mut r = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            r ^= r << 13;
            r ^= r >> 7;
            r ^= r << 17;
            r
        };
        // edges listed in vertex order, each once; keys with many repeats, some buckets over
        // 32 edges and some runs of one key (small, and one of 600 edges)
        let mut edges = Vec::new();
        for a in 0..2000u32 {
            for b in a + 1..a + 1 + (next() % 6) as u32 {
                let key = match next() % 4 {
                    0 => (next() % (1 << 24)) as u32,
                    1 => (0x7ab << 12) | (next() % 50) as u32,
                    2 => 0x123456,
                    _ => (next() % 3000) as u32 * 4099 % (1 << 24),
                };
                edges.push(Edge { key, a, b });
            }
        }
        assert!(edges.iter().filter(|e| e.key == 0x123456).count() > 600);
        let mut expected = edges.clone();
        expected.sort_by_key(|e| e.key);
        sort_in_place(&mut edges);
        assert_eq!(edges, expected);
    }

    /// The `k`-th smallest key by counts is the sorted keys' `k`-th, for every `k` (keys with
    /// many repeats, some sharing their upper 12 bits, some their lower 12), and none past
    /// the end.
    #[test]
    fn nth_key_is_the_sorted_keys_kth() {
        let mut r = 0x9e37_79b9_7f4a_7c15u64;
        let edges: Vec<Edge> = (0..3000)
            .map(|i| {
                r ^= r << 13;
                r ^= r >> 7;
                r ^= r << 17;
                let key = match r % 3 {
                    0 => (r >> 8) as u32 % (1 << 24),
                    1 => (0x5a5 << 12) | ((r >> 8) as u32 % 64),
                    _ => (((r >> 8) as u32 % 64) << 12) | 0x3c3,
                };
                Edge {
                    key,
                    a: i,
                    b: i + 1,
                }
            })
            .collect();
        let mut sorted: Vec<u32> = edges.iter().map(|e| e.key).collect();
        sorted.sort_unstable();
        for (k, &key) in sorted.iter().enumerate() {
            assert_eq!(nth_key(&edges, k), Some(key), "rank {k}");
        }
        assert_eq!(nth_key(&edges, edges.len()), None);
        assert_eq!(nth_key(&[], 0), None);
    }

    /// The Z-order keys' radix sort orders as sorting the (key, vertex) pairs: keys over all 63
    /// bits with many repeats (ties in vertex order), and keys whose high digits are all equal
    /// (the skipped passes).
    #[test]
    fn radix_sort_by_key_sorts_the_pairs() {
        let mut r = 0x9e37_79b9_7f4a_7c15u64;
        for spread in [u64::MAX >> 1, 0xffff_ffff, 0xff] {
            let mut keys: Vec<(u64, u32)> = (0..20_000)
                .map(|v| {
                    r ^= r << 13;
                    r ^= r >> 7;
                    r ^= r << 17;
                    // a few hundred distinct keys: many ties
                    ((r % 300).wrapping_mul(0x0123_4567_89ab_cdef) & spread, v)
                })
                .collect();
            let mut expected = keys.clone();
            expected.sort_unstable();
            radix_sort_by_key(&mut keys);
            assert_eq!(keys, expected, "keys within {spread:#x}");
        }
    }

    #[test]
    fn spread_bits_puts_bit_i_at_3i() {
        let mut r = 0x9e37_79b9_7f4a_7c15u64;
        for _ in 0..1000 {
            r ^= r << 13;
            r ^= r >> 7;
            r ^= r << 17;
            let x = r & 0x1f_ffff;
            let slow = (0..21).fold(0u64, |acc, i| acc | ((x >> i) & 1) << (3 * i));
            assert_eq!(spread_bits(x), slow, "{x:#x}");
        }
        assert_eq!(spread_bits(u64::MAX), 0x1249_2492_4924_9249);
    }

    /// The run's numbering and back leave the structure as it was (tops, slots, rows,
    /// flags, coordinates, origins), also after contractions.
    #[test]
    fn locality_order_and_back_is_the_identity() {
        let k = crate::generate::kuhn_grid(&[7, 5]).unwrap();
        let mut w = TopSimplices::from_complex(&k).unwrap();
        w.set_locked(3, true);
        assert!(w.contract(8, 9));
        // per vertex: its star (sorted), alive, locked, position
        let vertices = |w: &TopSimplices| {
            (0..w.n_vertices() as u32)
                .map(|v| {
                    let mut star = w.star(v).to_vec();
                    star.sort_unstable();
                    (star, w.is_alive(v), w.is_locked(v), w.point(v).to_vec())
                })
                .collect::<Vec<_>>()
        };
        let before = vertices(&w);
        let tops: Vec<Vec<u32>> = (0..w.n_top_slots() as u32)
            .map(|t| w.top(t).to_vec())
            .collect();
        let origins = w.cell_origins();
        let (to_new, order) = locality_order(&w);
        w.permute(&to_new, &order);
        assert_ne!(to_new, (0..to_new.len() as u32).collect::<Vec<_>>());
        assert_ne!(order, (0..order.len() as u32).collect::<Vec<_>>());
        for (i, &o) in order.iter().enumerate() {
            let moved: Vec<u32> = tops[o as usize]
                .iter()
                .map(|&v| to_new[v as usize])
                .collect();
            assert_eq!(w.top(i as u32), &moved[..]);
            assert_eq!(w.origin(i as u32), Some(o));
        }
        // removed tops last, the others by their first vertex
        let firsts: Vec<u32> = (0..w.n_top_slots() as u32)
            .map(|t| w.top(t).iter().copied().min().unwrap_or(u32::MAX))
            .collect();
        assert!(firsts.windows(2).all(|p| p[0] <= p[1]));
        w.permute(&crate::buf::invert(&to_new), &crate::buf::invert(&order));
        assert_eq!(vertices(&w), before);
        for (t, top) in tops.iter().enumerate() {
            assert_eq!(w.top(t as u32), &top[..]);
        }
        assert!((0..tops.len() as u32).all(|t| w.origin(t) == Some(t)));
        assert_eq!(w.cell_origins(), origins);
    }
}
