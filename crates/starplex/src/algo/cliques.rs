//! Maximal cliques of a graph, the maximal simplices of its flag (clique) complex: Bron–Kerbosch
//! with pivoting, started once per vertex of an ordering (Eppstein, Löffler and Strash,
//! "Listing all maximal cliques in sparse graphs in near-optimal time", 2010, with their
//! degeneracy ordering, or the cheaper order by degree when it keeps every start's candidates
//! within one 64-bit word: see `start_rank`), in parallel over the vertices. Each start works
//! on its vertex's neighbourhood as a small bit matrix, so the inner loop is word-wise AND and
//! popcount.
//!
//! The output is canonical: every clique's vertices ascending, cliques grouped by size
//! (ascending) and sorted lexicographically within a size. It is therefore the same for any
//! number of threads, and it is the order of the `vr_*` datasets (networkx cliques sorted by
//! `(len, vertices)`). Cliques of one vertex are not listed: in the complex they are isolated
//! vertices.
//!
//! With [`CliqueOptions::max_dim`] = `K`, the answer is the K-skeleton of the flag complex
//! stored by its maximal simplices: the maximal cliques of at most `K` vertices plus every clique
//! of exactly `K + 1` vertices (a `(K+1)`-clique is either maximal or inside a larger maximal
//! clique, whose `(K+1)`-subsets are exactly these). The `(K+1)`-cliques are listed directly
//! from the graph, each once, from its smallest vertex over its higher neighbours (bit sets over
//! that neighbourhood, depth-limited at K + 1), candidates in increasing order: each start
//! vertex's run is already in lexicographic order and the runs of vertices 0, 1, ... concatenate,
//! so the (large) block of `(K+1)`-cliques is neither sorted nor deduplicated. A counting pass
//! sizes the output (and refuses it over the budget) before a parallel pass writes every run in
//! its place.
//!
//! ```
//! use starplex::algo::cliques::{maximal_cliques, CliqueOptions, Graph};
//! // two triangles sharing the edge {1, 2}, plus a pendant edge {3, 4} and a lone vertex 5
//! let g = Graph::from_edges(6, &[(0, 1), (0, 2), (1, 2), (1, 3), (2, 3), (3, 4)]).unwrap();
//! let c = maximal_cliques(&g, &CliqueOptions::default()).unwrap();
//! assert_eq!(c.to_vecs(), vec![vec![3, 4], vec![0, 1, 2], vec![1, 2, 3]]);
//! // the 1-skeleton: every edge
//! let e = maximal_cliques(&g, &CliqueOptions { max_dim: Some(1), ..Default::default() }).unwrap();
//! assert_eq!(e.count(), 6);
//! ```
use std::sync::atomic::{AtomicBool, AtomicU64, AtomicUsize, Ordering};

use rayon::prelude::*;

use crate::csr::Csr;
use crate::limits::Limits;

/// What is wrong with a graph's input, or why an enumeration was refused.
///
/// ```
/// use starplex::algo::cliques::{Graph, GraphError};
/// assert_eq!(Graph::from_edges(3, &[(0, 0)]).unwrap_err(), GraphError::SelfLoop { edge: 0, vertex: 0 });
/// ```
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum GraphError {
    /// An edge joins a vertex to itself.
    #[error("edge {edge}: self-loop at vertex {vertex}")]
    SelfLoop {
        /// Edge position in the input.
        edge: u64,
        /// The vertex.
        vertex: u32,
    },
    /// An edge names a vertex that does not exist.
    #[error("edge {edge}: vertex {vertex} out of range (the graph has {n_vertices} vertices)")]
    VertexOutOfRange {
        /// Edge position in the input.
        edge: u64,
        /// The id given.
        vertex: u64,
        /// Number of vertices.
        n_vertices: u64,
    },
    /// More vertices or adjacency entries than 32-bit ids address.
    #[error(transparent)]
    TooLarge(#[from] crate::limits::TooLarge),
    /// The output would exceed the memory budget.
    #[error(
        "the output would exceed the memory budget of {budget_bytes} bytes: {found} simplices \
         ({found_refs} vertex references) after {done} of {total} start vertices, about \
         {estimate} simplices and {estimate_bytes} bytes extrapolated"
    )]
    OverBudget {
        /// Simplices found before stopping.
        found: u64,
        /// Their vertex references.
        found_refs: u64,
        /// Start vertices finished.
        done: u64,
        /// Start vertices in all.
        total: u64,
        /// Extrapolated number of simplices (a lower bound when few vertices were done).
        estimate: u64,
        /// Extrapolated bytes of the output (4 per vertex reference).
        estimate_bytes: u64,
        /// The budget.
        budget_bytes: u64,
    },
}

/// A simple undirected graph: sorted adjacency rows without self-loops or repeats.
///
/// ```
/// use starplex::algo::cliques::Graph;
/// let g = Graph::from_edges(4, &[(2, 0), (0, 2), (1, 2)]).unwrap(); // repeats are merged
/// assert_eq!((g.n_vertices(), g.n_edges()), (4, 2));
/// assert_eq!(g.neighbours(2), &[0, 1]);
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Graph {
    adj: Csr,
}

impl Graph {
    /// The graph on `n` vertices with these edges (either direction, repeats merged).
    ///
    /// ```
    /// use starplex::algo::cliques::{Graph, GraphError};
    /// let e = Graph::from_edges(2, &[(0, 5)]).unwrap_err();
    /// assert!(matches!(e, GraphError::VertexOutOfRange { edge: 0, vertex: 5, .. }));
    /// ```
    ///
    /// # Errors
    /// Self-loops, ids out of range (each naming the edge's position), more than 2^32 - 2
    /// vertices or adjacency entries.
    pub fn from_edges(n: usize, edges: &[(u32, u32)]) -> Result<Graph, GraphError> {
        if n >= u32::MAX as usize {
            return Err(GraphError::TooLarge(crate::limits::TooLarge::ids(
                "vertices",
                (n as u64) as u128,
            )));
        }
        for (i, &(a, b)) in edges.iter().enumerate() {
            for v in [a, b] {
                if v as usize >= n {
                    return Err(GraphError::VertexOutOfRange {
                        edge: i as u64,
                        vertex: v as u64,
                        n_vertices: n as u64,
                    });
                }
            }
            if a == b {
                return Err(GraphError::SelfLoop {
                    edge: i as u64,
                    vertex: a,
                });
            }
        }
        if 2 * edges.len() as u64 >= u32::MAX as u64 {
            return Err(GraphError::TooLarge(crate::limits::TooLarge::ids(
                "adjacency entries",
                (2 * edges.len() as u64) as u128,
            )));
        }
        let mut adj = Csr::from_fn(n, |push| {
            for &(a, b) in edges {
                push(a, b);
                push(b, a);
            }
        });
        adj.sort_dedup_rows();
        Ok(Graph { adj })
    }

    /// A graph from rows already symmetric, sorted and free of self-loops and repeats
    /// (checked in debug builds).
    ///
    /// ```
    /// use starplex::algo::cliques::Graph;
    /// use starplex::csr::Csr;
    /// let g = Graph::from_sorted_rows(Csr { offsets: vec![0, 1, 2], targets: vec![1, 0] });
    /// assert_eq!(g.n_edges(), 1);
    /// ```
    pub fn from_sorted_rows(adj: Csr) -> Graph {
        debug_assert!((0..adj.n_rows()).all(|v| {
            let r = adj.row(v);
            r.windows(2).all(|w| w[0] < w[1])
                && r.iter().all(|&u| {
                    u as usize != v && adj.row(u as usize).binary_search(&(v as u32)).is_ok()
                })
        }));
        Graph { adj }
    }

    /// Number of vertices.
    ///
    /// ```
    /// # use starplex::algo::cliques::Graph;
    /// assert_eq!(Graph::from_edges(7, &[]).unwrap().n_vertices(), 7);
    /// ```
    pub fn n_vertices(&self) -> usize {
        self.adj.n_rows()
    }

    /// Number of edges.
    ///
    /// ```
    /// # use starplex::algo::cliques::Graph;
    /// assert_eq!(Graph::from_edges(3, &[(0, 1), (1, 2)]).unwrap().n_edges(), 2);
    /// ```
    pub fn n_edges(&self) -> usize {
        self.adj.n_refs() / 2
    }

    /// The neighbours of `v`, ascending.
    ///
    /// ```
    /// # use starplex::algo::cliques::Graph;
    /// let g = Graph::from_edges(3, &[(0, 1), (1, 2)]).unwrap();
    /// assert_eq!(g.neighbours(1), &[0, 2]);
    /// ```
    pub fn neighbours(&self, v: u32) -> &[u32] {
        self.adj.row(v as usize)
    }

    /// Memory held by the adjacency (bytes).
    ///
    /// ```
    /// # use starplex::algo::cliques::Graph;
    /// assert_eq!(Graph::from_edges(2, &[(0, 1)]).unwrap().bytes(), 4 * (3 + 2));
    /// ```
    pub fn bytes(&self) -> usize {
        self.adj.bytes()
    }
}

/// A degeneracy ordering (smallest-last, Matula–Beck): `order[i]` is the i-th vertex; each
/// vertex has at most `degeneracy` neighbours later in the order. Ties are broken by the
/// bucket structure only, so the order depends on the graph alone.
///
/// ```
/// use starplex::algo::cliques::{degeneracy_order, Graph};
/// let g = Graph::from_edges(4, &[(0, 1), (0, 2), (1, 2), (2, 3)]).unwrap();
/// let (order, d) = degeneracy_order(&g);
/// assert_eq!(d, 2); // a triangle
/// assert_eq!(order[0], 3); // the pendant vertex goes first
/// ```
pub fn degeneracy_order(g: &Graph) -> (Vec<u32>, usize) {
    // Batagelj–Zaversnik bucket sort by current degree.
    let n = g.n_vertices();
    let mut deg: Vec<u32> = (0..n).map(|v| g.adj.degree(v) as u32).collect();
    let md = deg.iter().copied().max().unwrap_or(0) as usize;
    let mut bin = vec![0u32; md + 2];
    for &d in &deg {
        bin[d as usize] += 1;
    }
    let mut start = 0u32;
    for b in bin.iter_mut() {
        let c = *b;
        *b = start;
        start += c;
    }
    let mut pos = vec![0u32; n];
    let mut vert = vec![0u32; n];
    for v in 0..n {
        let d = deg[v] as usize;
        pos[v] = bin[d];
        vert[bin[d] as usize] = v as u32;
        bin[d] += 1;
    }
    for d in (1..=md).rev() {
        bin[d] = bin[d - 1];
    }
    bin[0] = 0;
    let mut degeneracy = 0usize;
    for i in 0..n {
        let v = vert[i] as usize;
        degeneracy = degeneracy.max(deg[v] as usize);
        for &u in g.adj.row(v) {
            let u = u as usize;
            if deg[u] > deg[v] {
                let du = deg[u] as usize;
                let pu = pos[u];
                let pw = bin[du];
                let w = vert[pw as usize] as usize;
                if u != w {
                    pos[u] = pw;
                    vert[pu as usize] = w as u32;
                    pos[w] = pu;
                    vert[pw as usize] = u as u32;
                }
                bin[du] += 1;
                deg[u] -= 1;
            }
        }
    }
    (vert, degeneracy)
}

/// Options of [`maximal_cliques`].
///
/// ```
/// use starplex::algo::cliques::CliqueOptions;
/// let o = CliqueOptions { max_dim: Some(3), ..Default::default() };
/// assert_eq!(o.limits.memory_bytes, u64::MAX); // no memory budget unless asked
/// ```
#[derive(Clone, Copy)]
pub struct CliqueOptions<'a> {
    /// Keep the K-skeleton: cliques of more than K + 1 vertices are replaced by their
    /// (K+1)-subsets (each listed once). `None`: every maximal clique.
    pub max_dim: Option<usize>,
    /// `limits.memory_bytes`: refuse (with an estimate) when the output's vertex references
    /// would take more bytes (default: `u64::MAX`, no memory budget).
    pub limits: Limits,
    /// Called with the number of start vertices finished since the last call (progress bars).
    pub progress: Option<&'a (dyn Fn(u64) + Sync)>,
}

impl Default for CliqueOptions<'_> {
    fn default() -> Self {
        CliqueOptions {
            max_dim: None,
            limits: Limits::with_memory(u64::MAX),
            progress: None,
        }
    }
}

/// Cliques grouped by size, each block a flat array of `size`-vertex rows, ascending within a
/// row and lexicographically sorted across rows.
///
/// ```
/// use starplex::algo::cliques::{maximal_cliques, CliqueOptions, Graph};
/// let g = Graph::from_edges(3, &[(0, 1), (1, 2), (0, 2)]).unwrap();
/// let c = maximal_cliques(&g, &CliqueOptions::default()).unwrap();
/// assert_eq!(c.blocks, vec![(3, vec![0, 1, 2])]);
/// assert_eq!(c.count_by_size(), vec![(3, 1)]);
/// ```
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Cliques {
    /// `(size, rows)` with size ascending, sizes ≥ 2 only.
    pub blocks: Vec<(usize, Vec<u32>)>,
}

impl Cliques {
    /// Number of cliques.
    ///
    /// ```
    /// # use starplex::algo::cliques::Cliques;
    /// assert_eq!(Cliques { blocks: vec![(2, vec![0, 1, 1, 2])] }.count(), 2);
    /// ```
    pub fn count(&self) -> usize {
        self.blocks.iter().map(|(s, v)| v.len() / s).sum()
    }

    /// `(size, count)` per block.
    ///
    /// ```
    /// # use starplex::algo::cliques::Cliques;
    /// assert_eq!(Cliques { blocks: vec![(2, vec![0, 1, 1, 2])] }.count_by_size(), vec![(2, 2)]);
    /// ```
    pub fn count_by_size(&self) -> Vec<(usize, usize)> {
        self.blocks.iter().map(|(s, v)| (*s, v.len() / s)).collect()
    }

    /// Every clique as its own vector, in the canonical order (for tests and small outputs).
    ///
    /// ```
    /// # use starplex::algo::cliques::Cliques;
    /// assert_eq!(Cliques { blocks: vec![(2, vec![0, 1])] }.to_vecs(), vec![vec![0, 1]]);
    /// ```
    pub fn to_vecs(&self) -> Vec<Vec<u32>> {
        self.blocks
            .iter()
            .flat_map(|(s, v)| v.chunks_exact(*s).map(|c| c.to_vec()))
            .collect()
    }
}

type Bits = Vec<u64>;

#[inline]
fn bit_set(b: &mut [u64], i: usize) {
    b[i >> 6] |= 1 << (i & 63);
}

#[inline]
fn bit_clear(b: &mut [u64], i: usize) {
    b[i >> 6] &= !(1 << (i & 63));
}

fn ones(b: &[u64]) -> impl Iterator<Item = usize> + '_ {
    b.iter().enumerate().flat_map(|(w, &word)| {
        let mut x = word;
        std::iter::from_fn(move || {
            if x == 0 {
                return None;
            }
            let t = x.trailing_zeros() as usize;
            x &= x - 1;
            Some(w * 64 + t)
        })
    })
}

/// Shared state of one enumeration: output budget and abort flag.
struct Budget {
    refs: AtomicU64,
    found: AtomicU64,
    max_refs: u64,
    stop: AtomicBool,
}

impl Budget {
    /// `count` cliques of `size` vertices at once (one pair of atomic updates).
    fn take_n(&self, count: usize, size: usize) -> bool {
        self.take_refs(count, count * size)
    }

    /// `count` cliques of `refs` vertex references in all.
    fn take_refs(&self, count: usize, refs: usize) -> bool {
        self.found.fetch_add(count as u64, Ordering::Relaxed);
        let add = refs as u64;
        let r = self.refs.fetch_add(add, Ordering::Relaxed) + add;
        if r > self.max_refs {
            self.stop.store(true, Ordering::Relaxed);
            return false;
        }
        true
    }
}

/// One chunk's output: one flat array per clique size, and the cliques found since the last
/// report to the shared budget (reported in batches, so that threads do not write one shared
/// cache line per clique).
#[derive(Default)]
struct Sink {
    by_size: Vec<Vec<u32>>,
    unflushed: usize,
    unflushed_refs: usize,
}

/// Cliques a [`Sink`] holds back from the budget at most (vertex references).
const SINK_BATCH: usize = 1 << 12;

impl Sink {
    /// Appends `clique`, sorted in place in the flat array (no vector per clique); reports to
    /// the budget every [`SINK_BATCH`] references (which sets its `stop` flag once exceeded).
    fn push(&mut self, clique: &[u32], budget: &Budget) {
        let s = clique.len();
        if self.by_size.len() <= s {
            self.by_size.resize_with(s + 1, Vec::new);
        }
        let v = &mut self.by_size[s];
        let at = v.len();
        v.extend_from_slice(clique);
        v[at..].sort_unstable();
        self.unflushed += 1;
        self.unflushed_refs += s;
        if self.unflushed_refs >= SINK_BATCH {
            self.flush(budget);
        }
    }

    /// Reports the held-back cliques to the budget; false once it is exceeded.
    fn flush(&mut self, budget: &Budget) -> bool {
        let (n, refs) = (self.unflushed, self.unflushed_refs);
        (self.unflushed, self.unflushed_refs) = (0, 0);
        n == 0 || budget.take_refs(n, refs)
    }

    /// The sinks' arrays concatenated size by size (one allocation per size).
    fn concat(sinks: Vec<Sink>) -> Vec<Vec<u32>> {
        let sizes = sinks.iter().map(|k| k.by_size.len()).max().unwrap_or(0);
        (0..sizes)
            .map(|s| {
                let len = sinks
                    .iter()
                    .map(|k| k.by_size.get(s).map_or(0, Vec::len))
                    .sum();
                let mut out = Vec::with_capacity(len);
                for k in &sinks {
                    if let Some(v) = k.by_size.get(s) {
                        out.extend_from_slice(v);
                    }
                }
                out
            })
            .collect()
    }
}

/// The maximal cliques of `g` (of at least two vertices), or with `max_dim` the maximal
/// simplices of the K-skeleton of its flag complex; canonical order (see the module docs).
///
/// ```
/// use starplex::algo::cliques::{maximal_cliques, CliqueOptions, Graph};
/// // K4: one maximal clique; its 1-skeleton is its 6 edges, its 2-skeleton its 4 triangles
/// let k4 = Graph::from_edges(4, &[(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)]).unwrap();
/// assert_eq!(maximal_cliques(&k4, &CliqueOptions::default()).unwrap().to_vecs(), vec![vec![0, 1, 2, 3]]);
/// let o = CliqueOptions { max_dim: Some(2), ..Default::default() };
/// assert_eq!(maximal_cliques(&k4, &o).unwrap().count_by_size(), vec![(3, 4)]);
/// ```
///
/// # Errors
/// [`GraphError::OverBudget`] when the output would need more than `opts.limits.memory_bytes`.
pub fn maximal_cliques(g: &Graph, opts: &CliqueOptions) -> Result<Cliques, GraphError> {
    let n = g.n_vertices();
    let max_bytes = opts.limits.memory_bytes;
    let budget = Budget {
        refs: AtomicU64::new(0),
        found: AtomicU64::new(0),
        max_refs: max_bytes / 4,
        stop: AtomicBool::new(false),
    };
    let over = |done: usize| {
        let found = budget.found.load(Ordering::Relaxed);
        let refs = budget.refs.load(Ordering::Relaxed);
        let scale = (n as f64 / done.max(1) as f64).max(1.0);
        GraphError::OverBudget {
            found,
            found_refs: refs,
            done: done as u64,
            total: n as u64,
            estimate: (found as f64 * scale) as u64,
            estimate_bytes: (refs as f64 * 4.0 * scale) as u64,
            budget_bytes: max_bytes,
        }
    };
    let k = opts.max_dim;
    if k == Some(0) {
        return Ok(Cliques::default());
    }
    // The maximal cliques (of at most k vertices with a skeleton; none are listed below 2).
    let limit = k.unwrap_or(usize::MAX);
    let mut blocks = Vec::new();
    if limit >= 2 {
        let progress = if k.is_none() { opts.progress } else { None };
        let (by_size, done) = maximal_from_starts(g, limit, &budget, progress);
        if budget.stop.load(Ordering::Relaxed) {
            return Err(over(done));
        }
        // each size sorted on its own, in parallel (the collect keeps the size order)
        blocks = by_size
            .into_par_iter()
            .enumerate()
            .filter(|(s, flat)| *s >= 2 && !flat.is_empty())
            .map(|(s, flat)| (s, sort_rows(flat, s, n)))
            .collect();
    }
    // The skeleton's other maximal simplices: every clique of k + 1 vertices, listed in order.
    if let Some(k) = k {
        match cliques_of_size(g, k + 1, &budget, opts.progress) {
            Ok(flat) if flat.is_empty() => {}
            Ok(flat) => blocks.push((k + 1, flat)),
            Err(Refused::Budget(done)) => return Err(over(done)),
            Err(Refused::Alloc(bytes)) => {
                return Err(GraphError::TooLarge(crate::limits::TooLarge::new(
                    format!("the cliques of {} vertices", k + 1),
                    bytes as u128,
                    max_bytes as u128,
                    crate::limits::Unit::Bytes,
                )))
            }
        }
    }
    Ok(Cliques { blocks })
}

/// Bron–Kerbosch from every start vertex of the order of `start_rank`, in parallel: the maximal
/// cliques of at most `limit` vertices, unsorted, and the number of start vertices finished.
fn maximal_from_starts(
    g: &Graph,
    limit: usize,
    budget: &Budget,
    progress: Option<&(dyn Fn(u64) + Sync)>,
) -> (Vec<Vec<u32>>, usize) {
    let n = g.n_vertices();
    let rank = start_rank(g);
    let ids: Vec<u32> = (0..n as u32).collect();
    let done = AtomicUsize::new(0);
    // Work per vertex is very uneven; small chunks keep both cores busy, and the result does
    // not depend on how the vertices are split. Shared counters are updated once per chunk.
    // The starts go in id order (the ranks only decide each start's P and X): neighbouring ids
    // are usually neighbouring points, whose rows are then read while still in cache.
    // one sink per rayon job (not per chunk: a sink's arrays grow by reallocation)
    let sinks: Vec<Sink> = ids
        .par_chunks(64)
        .fold(Sink::default, |mut sink, chunk| {
            for &v in chunk {
                if budget.stop.load(Ordering::Relaxed) {
                    return sink;
                }
                from_vertex(g, &rank, v, limit, budget, &mut sink);
            }
            if sink.flush(budget) && !budget.stop.load(Ordering::Relaxed) {
                done.fetch_add(chunk.len(), Ordering::Relaxed);
                if let Some(p) = progress {
                    p(chunk.len() as u64);
                }
            }
            sink
        })
        .collect();
    (Sink::concat(sinks), done.load(Ordering::Relaxed))
}

/// The rank of each vertex in the order of the starts. Any total order lists every maximal
/// clique exactly once (from its earliest vertex); the order decides the size of each start's
/// candidate set P (its later neighbours). The degeneracy order keeps every P within the
/// degeneracy d, but peeling the graph is sequential (5 ms of vr_building_m's 30). The order by
/// degree (ties by id) is a counting sort, and on point clouds and power-law graphs its
/// largest P is 1-2 times d with less work in all (BENCHMARKS, issue 14). It is used when its
/// largest P fits one 64-bit word (so d, which is at most that, does too); otherwise the
/// degeneracy order is.
fn start_rank(g: &Graph) -> Vec<u32> {
    const MAX_P: usize = 64;
    let rank = degree_rank(g);
    let n = g.n_vertices();
    let widest = (0..n)
        .into_par_iter()
        .with_min_len(4096)
        .map(|v| {
            let rv = rank[v];
            let nb = g.neighbours(v as u32);
            nb.iter().filter(|&&u| rank[u as usize] > rv).count()
        })
        .max()
        .unwrap_or(0);
    if widest <= MAX_P {
        return rank;
    }
    let (order, _) = degeneracy_order(g);
    let mut rank = rank;
    for (i, &v) in order.iter().enumerate() {
        rank[v as usize] = i as u32;
    }
    rank
}

/// Each vertex's rank in the order by degree, ties by id (a counting sort).
fn degree_rank(g: &Graph) -> Vec<u32> {
    let n = g.n_vertices();
    let deg = |v: usize| g.adj.degree(v);
    let md = (0..n).map(deg).max().unwrap_or(0);
    let mut at = vec![0u32; md + 1];
    for v in 0..n {
        at[deg(v)] += 1;
    }
    let mut sum = 0u32;
    for a in at.iter_mut() {
        (*a, sum) = (sum, sum + *a);
    }
    let mut rank = vec![0u32; n];
    for (v, r) in rank.iter_mut().enumerate() {
        let d = deg(v);
        *r = at[d];
        at[d] += 1;
    }
    rank
}

/// Sorts the `s`-vertex rows of `flat` (each ascending, vertices below `n`)
/// lexicographically: fewer rows than n / 16 by a comparison sort; otherwise a counting sort by
/// first vertex, then a sort of each (small) run of rows sharing it.
fn sort_rows(flat: Vec<u32>, s: usize, n: usize) -> Vec<u32> {
    let rows = flat.len() / s;
    let row = |i: u32| &flat[i as usize * s..(i as usize + 1) * s];
    if rows < n / 16 {
        // few rows against the vertex count: a comparison sort beats counting over n
        let mut idx: Vec<u32> = (0..rows as u32).collect();
        idx.sort_unstable_by(|&a, &b| row(a).cmp(row(b)));
        let mut out = Vec::with_capacity(flat.len());
        for &i in &idx {
            out.extend_from_slice(row(i));
        }
        return out;
    }
    let by_first = Csr::from_fn(n, |push| {
        for (i, r) in flat.chunks_exact(s).enumerate() {
            push(r[0], i as u32);
        }
    });
    let Csr {
        offsets: start,
        targets: mut idx,
    } = by_first;
    // runs of equal first vertex, sorted in parallel in chunks of whole runs
    let mut runs: Vec<&mut [u32]> = Vec::new();
    let mut rest = &mut idx[..];
    for v in 0..n {
        let len = (start[v + 1] - start[v]) as usize;
        if len > 1 {
            let (a, b) = std::mem::take(&mut rest).split_at_mut(len);
            runs.push(a);
            rest = b;
        } else {
            rest = &mut std::mem::take(&mut rest)[len..];
        }
    }
    runs.par_iter_mut()
        .with_min_len(256)
        .for_each(|r| r.sort_unstable_by(|&a, &b| row(a).cmp(row(b))));
    drop(runs);
    let mut out = Vec::with_capacity(flat.len());
    for &i in &idx {
        out.extend_from_slice(row(i));
    }
    out
}

/// Lists the maximal cliques of at most `limit` vertices whose earliest vertex (in the
/// order of the starts) is `v`.
fn from_vertex(g: &Graph, rank: &[u32], v: u32, limit: usize, budget: &Budget, sink: &mut Sink) {
    let nb = g.neighbours(v);
    if nb.is_empty() {
        return; // an isolated vertex: a clique of one, not listed
    }
    let rv = rank[v as usize];
    if nb.iter().all(|&u| rank[u as usize] < rv) {
        return; // no later neighbour: every clique through v starts at an earlier vertex
    }
    let start = Start {
        g,
        rank,
        v,
        limit,
        budget,
    };
    match nb.len().div_ceil(64) {
        1 => start.fixed::<1>(sink),
        2 => start.fixed::<2>(sink),
        3 | 4 if nb.len() < 255 => start.fixed::<4>(sink),
        _ => start.general(sink),
    }
}

/// One start vertex of the enumeration and what every level of its search reads.
struct Start<'a> {
    g: &'a Graph,
    rank: &'a [u32],
    v: u32,
    limit: usize,
    budget: &'a Budget,
}

/// A later neighbour with more than this many times the start vertex's degree is searched
/// by looking each neighbourhood vertex up in its row, not by scanning the row.
const HUB_RATIO: usize = 16;

thread_local! {
    /// Per-thread scratch of [`Start::fixed`]: the local index of each neighbour of the start
    /// vertex (`u8::MAX` elsewhere, restored after each start), the bit rows and the clique
    /// being grown.
    static SCRATCH: std::cell::RefCell<(Vec<u8>, Vec<u64>, Vec<u32>)> = const {
        std::cell::RefCell::new((Vec::new(), Vec::new(), Vec::new()))
    };
}

impl Start<'_> {
    /// The search for a neighbourhood of at most `64 W` vertices, on fixed-width bit rows: no
    /// allocation below the start. Only the rows of the later neighbours (P) are read from the
    /// graph (by a scan of each one's adjacency against the local index); the rows of the
    /// earlier ones (X) are only ever used against P, and are their transpose.
    fn fixed<const W: usize>(&self, sink: &mut Sink) {
        let nb = self.g.neighbours(self.v);
        let m = nb.len();
        let rv = self.rank[self.v as usize];
        SCRATCH.with(|s| {
            let (pos, rows, r) = &mut *s.borrow_mut();
            if pos.len() < self.g.n_vertices() {
                pos.resize(self.g.n_vertices(), u8::MAX);
            }
            rows.clear();
            rows.resize(m * W, 0);
            let (mut p, mut x) = ([0u64; W], [0u64; W]);
            for (i, &u) in nb.iter().enumerate() {
                pos[u as usize] = i as u8;
                let set = if self.rank[u as usize] > rv {
                    &mut p
                } else {
                    &mut x
                };
                set[i >> 6] |= 1 << (i & 63);
            }
            let pos_s: &[u8] = pos;
            for i in ones(&p) {
                let row: &mut BitRow<W> = (&mut rows[i * W..(i + 1) * W]).try_into().unwrap();
                let nu = self.g.neighbours(nb[i]);
                if nu.len() > HUB_RATIO * m {
                    // a hub: look the few neighbourhood vertices up in its long row instead
                    for (j, w) in nb.iter().enumerate() {
                        if nu.binary_search(w).is_ok() {
                            row[j >> 6] |= 1 << (j & 63);
                        }
                    }
                    continue;
                }
                for &w in nu {
                    // branch-free: a vertex outside the neighbourhood ORs a zero; j < m <= 64 W
                    // and W is a power of two, so the mask only drops the bounds check
                    let j = pos_s[w as usize];
                    row[(j as usize >> 6) & (W - 1)] |= ((j != u8::MAX) as u64) << (j & 63);
                }
            }
            for &u in nb {
                pos[u as usize] = u8::MAX;
            }
            for i in ones(&p) {
                let xs: BitRow<W> = std::array::from_fn(|k| rows[i * W + k] & x[k]);
                for j in ones(&xs) {
                    rows[j * W + (i >> 6)] |= 1 << (i & 63);
                }
            }
            r.clear();
            r.push(self.v);
            self.bk_fixed::<W>(rows, nb, r, p, x, sink);
        });
    }

    /// The start of a Bron–Kerbosch level, both searches' (`np` = |P|, `x` the excluded set):
    /// true when it ends here — stopped by the budget, or P empty (R is reported when X is
    /// empty too and R is within the size limit), or R at the size limit (only larger cliques
    /// below).
    fn ends_here(&self, r: &[u32], np: usize, x: &[u64], sink: &mut Sink) -> bool {
        if self.budget.stop.load(Ordering::Relaxed) {
            return true;
        }
        if np == 0 {
            if x.iter().all(|&q| q == 0) && r.len() <= self.limit {
                sink.push(r, self.budget);
            }
            return true;
        }
        r.len() >= self.limit
    }

    /// Bron–Kerbosch with Tomita's pivot on `W`-word rows (see [`Start::fixed`]). Cliques of
    /// more than `limit` vertices are not reported (nor searched for).
    fn bk_fixed<const W: usize>(
        &self,
        rows: &[u64],
        nb: &[u32],
        r: &mut Vec<u32>,
        mut p: BitRow<W>,
        mut x: BitRow<W>,
        sink: &mut Sink,
    ) {
        let row = |i: usize| -> BitRow<W> { std::array::from_fn(|k| rows[i * W + k]) };
        let np = row_count(&p);
        if self.ends_here(r, np, &x, sink) {
            return;
        }
        // pivot: the vertex of P ∪ X with the most neighbours in P
        let px: BitRow<W> = std::array::from_fn(|k| p[k] | x[k]);
        let (mut best, mut best_n) = (usize::MAX, 0usize);
        for u in ones(&px) {
            let c = row_count(&row_and(&row(u), &p));
            if best == usize::MAX || c > best_n {
                (best, best_n) = (u, c);
                if c == np {
                    break; // no candidate is left outside its neighbourhood
                }
            }
        }
        let pr = row(best);
        let cand: BitRow<W> = std::array::from_fn(|k| p[k] & !pr[k]);
        for w in ones(&cand) {
            let rw = row(w);
            r.push(nb[w]);
            self.bk_fixed::<W>(rows, nb, r, row_and(&p, &rw), row_and(&x, &rw), sink);
            r.pop();
            p[w >> 6] &= !(1 << (w & 63));
            x[w >> 6] |= 1 << (w & 63);
        }
    }

    /// The search for a large neighbourhood (a hub: many earlier neighbours X, few later ones
    /// P: at most 64 in the order by degree, at most the degeneracy otherwise). Local indices
    /// put P first; only P's rows are read from the graph (over all of the neighbourhood), and
    /// X's rows are kept over P only (their transpose), so the matrix is |P| × m bits, not
    /// m × m. The candidate and pivot sets live in P's words, the excluded set in the whole
    /// neighbourhood's.
    fn general(&self, sink: &mut Sink) {
        let nb = self.g.neighbours(self.v);
        let rv = self.rank[self.v as usize];
        let later = |u: &u32| self.rank[*u as usize] > rv;
        let local: Vec<u32> = nb
            .iter()
            .filter(|u| later(u))
            .chain(nb.iter().filter(|u| !later(u)))
            .copied()
            .collect();
        let (m, np) = (local.len(), nb.iter().filter(|u| later(u)).count());
        let (wm, wp) = (m.div_ceil(64), np.div_ceil(64));
        let mut prow = vec![0u64; np * wm];
        let mut xrow = vec![0u64; m * wp];
        WIDE_POS.with(|s| {
            let pos = &mut *s.borrow_mut();
            if pos.len() < self.g.n_vertices() {
                pos.resize(self.g.n_vertices(), u32::MAX);
            }
            for (i, &u) in local.iter().enumerate() {
                pos[u as usize] = i as u32;
            }
            for i in 0..np {
                let row = &mut prow[i * wm..(i + 1) * wm];
                for &w in self.g.neighbours(local[i]) {
                    let j = pos[w as usize];
                    if j != u32::MAX {
                        bit_set(row, j as usize);
                    }
                }
            }
            for &u in &local {
                pos[u as usize] = u32::MAX;
            }
        });
        for i in 0..np {
            for j in ones(&prow[i * wm..(i + 1) * wm]) {
                bit_set(&mut xrow[j * wp..(j + 1) * wp], i);
            }
        }
        let wide = Wide {
            local: &local,
            np,
            wm,
            wp,
            prow: &prow,
            xrow: &xrow,
        };
        let mut p = vec![0u64; wp];
        for i in 0..np {
            bit_set(&mut p, i);
        }
        let mut x = vec![0u64; wm];
        for j in np..m {
            bit_set(&mut x, j);
        }
        let mut r = vec![self.v];
        self.bk_wide(&wide, &mut r, p, x, sink);
    }

    /// Bron–Kerbosch with Tomita's pivot on the rows of [`Start::general`]: `p` over P's
    /// words, `x` over the whole neighbourhood's.
    fn bk_wide(&self, w: &Wide, r: &mut Vec<u32>, mut p: Bits, mut x: Bits, sink: &mut Sink) {
        let np: usize = p.iter().map(|q| q.count_ones() as usize).sum();
        if self.ends_here(r, np, &x, sink) {
            return;
        }
        // pivot: the vertex of P ∪ X with the most neighbours in P
        let (mut best, mut best_n) = (usize::MAX, 0usize);
        for u in ones(&p).chain(ones(&x)) {
            let c = and_count(w.in_p(u), &p);
            if best == usize::MAX || c > best_n {
                (best, best_n) = (u, c);
                if c == np {
                    break;
                }
            }
        }
        let pr = w.in_p(best);
        let cand: Bits = p.iter().zip(pr).map(|(a, b)| a & !b).collect();
        for v in ones(&cand) {
            let row = &w.prow[v * w.wm..(v + 1) * w.wm];
            let p2: Bits = p.iter().zip(row).map(|(a, b)| a & b).collect();
            let x2: Bits = x.iter().zip(row).map(|(a, b)| a & b).collect();
            r.push(w.local[v]);
            self.bk_wide(w, r, p2, x2, sink);
            r.pop();
            bit_clear(&mut p, v);
            bit_set(&mut x, v);
        }
    }
}

thread_local! {
    /// Per-thread scratch of [`Start::general`]: the local index of each neighbour of the
    /// start vertex (`u32::MAX` elsewhere, restored after each start).
    static WIDE_POS: std::cell::RefCell<Vec<u32>> = const { std::cell::RefCell::new(Vec::new()) };
}

/// The rows of a large neighbourhood (see [`Start::general`]).
struct Wide<'a> {
    /// Local index -> vertex: P (the later neighbours) first.
    local: &'a [u32],
    np: usize,
    /// Words of a row over the whole neighbourhood, and over P.
    wm: usize,
    wp: usize,
    /// P's rows, `wm` words each.
    prow: &'a [u64],
    /// Every vertex's neighbours in P, `wp` words each (P's own rows: their first words).
    xrow: &'a [u64],
}

impl Wide<'_> {
    /// The neighbours of local vertex `u` in P, as `wp` words.
    fn in_p(&self, u: usize) -> &[u64] {
        if u < self.np {
            &self.prow[u * self.wm..u * self.wm + self.wp]
        } else {
            &self.xrow[u * self.wp..(u + 1) * self.wp]
        }
    }
}

/// |a ∩ b| of two bit sets of the same width.
fn and_count(a: &[u64], b: &[u64]) -> usize {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x & y).count_ones() as usize)
        .sum()
}

/// Where the (K+1)-cliques go: counted, or written.
trait KOut {
    /// The cliques `prefix + [t]` for the `n` vertices `t` of `tail`; false to abort.
    fn last(&mut self, prefix: &[u32], n: usize, tail: impl Iterator<Item = u32>) -> bool;
}

/// Counts cliques, flushing the count to the shared budget every so often so that a huge
/// output is refused long before it is counted to the end.
struct Counter<'a> {
    n: u64,
    unflushed: u64,
    size: usize,
    budget: &'a Budget,
}

impl Counter<'_> {
    const FLUSH: u64 = 1 << 16;
    fn flush(&mut self) -> bool {
        let u = std::mem::take(&mut self.unflushed);
        u == 0 || self.budget.take_n(u as usize, self.size)
    }
}

impl KOut for Counter<'_> {
    #[inline]
    fn last(&mut self, _: &[u32], n: usize, _: impl Iterator<Item = u32>) -> bool {
        self.n += n as u64;
        self.unflushed += n as u64;
        if self.unflushed >= Self::FLUSH {
            return self.flush() && !self.budget.stop.load(Ordering::Relaxed);
        }
        true
    }
}

/// Writes cliques into a slice sized by the count pass.
struct Writer<'a> {
    out: &'a mut [u32],
    at: usize,
}

impl KOut for Writer<'_> {
    #[inline]
    fn last(&mut self, prefix: &[u32], n: usize, tail: impl Iterator<Item = u32>) -> bool {
        let s = prefix.len() + 1;
        let dst = &mut self.out[self.at..self.at + n * s];
        match s {
            2 => fill_rows::<2>(dst, prefix, tail),
            3 => fill_rows::<3>(dst, prefix, tail),
            4 => fill_rows::<4>(dst, prefix, tail),
            5 => fill_rows::<5>(dst, prefix, tail),
            6 => fill_rows::<6>(dst, prefix, tail),
            7 => fill_rows::<7>(dst, prefix, tail),
            8 => fill_rows::<8>(dst, prefix, tail),
            _ => {
                for (row, t) in dst.chunks_exact_mut(s).zip(tail) {
                    row[..s - 1].copy_from_slice(prefix);
                    row[s - 1] = t;
                }
            }
        }
        self.at += n * s;
        true
    }
}

/// The rows `prefix + [t]` of `S` vertices for the `t` of `tail`, with fixed-size copies
/// (a `memmove` call per row of a few words cost more than the row).
#[inline]
fn fill_rows<const S: usize>(dst: &mut [u32], prefix: &[u32], tail: impl Iterator<Item = u32>) {
    let mut row = [0u32; S];
    row[..S - 1].copy_from_slice(prefix);
    let (rows, _) = dst.as_chunks_mut::<S>();
    for (d, t) in rows.iter_mut().zip(tail) {
        row[S - 1] = t;
        *d = row;
    }
}

/// A fixed-width bit set of `W` words (the higher neighbourhood of a start vertex).
type BitRow<const W: usize> = [u64; W];

#[inline]
fn row_and<const W: usize>(a: &BitRow<W>, b: &BitRow<W>) -> BitRow<W> {
    std::array::from_fn(|i| a[i] & b[i])
}

#[inline]
fn row_count<const W: usize>(a: &BitRow<W>) -> usize {
    a.iter().map(|w| w.count_ones() as usize).sum()
}

/// The set bits of a row, ascending.
#[inline]
fn row_ones<const W: usize>(a: &BitRow<W>) -> impl Iterator<Item = usize> + '_ {
    ones(a)
}

/// Every `need`-vertex extension of `prefix` by vertices of `p` (local indices into `hi`),
/// candidates in increasing order: lexicographic order of the finished cliques. `rows[w]`
/// holds only the neighbours of `w` after it, so `p ∩ rows[w]` are the later candidates.
fn kc_bits<const W: usize, O: KOut>(
    rows: &[BitRow<W>],
    hi: &[u32],
    p: &BitRow<W>,
    prefix: &mut Vec<u32>,
    need: usize,
    out: &mut O,
) -> bool {
    let c = row_count(p);
    if need == 1 {
        return out.last(prefix, c, row_ones(p).map(|j| hi[j]));
    }
    if c < need {
        return true;
    }
    for w in row_ones(p) {
        let p2 = row_and(p, &rows[w]);
        if row_count(&p2) >= need - 1 {
            prefix.push(hi[w]);
            let go = kc_bits(rows, hi, &p2, prefix, need - 1, out);
            prefix.pop();
            if !go {
                return false;
            }
        }
    }
    true
}

/// [`kc_bits`] on sorted candidate lists (global ids), for start vertices with very many
/// higher neighbours (no quadratic bit matrix).
fn kc_lists<O: KOut>(
    g: &Graph,
    cand: &[u32],
    prefix: &mut Vec<u32>,
    need: usize,
    out: &mut O,
) -> bool {
    if need == 1 {
        return out.last(prefix, cand.len(), cand.iter().copied());
    }
    if cand.len() < need {
        return true;
    }
    let mut next = Vec::new();
    for (i, &w) in cand.iter().enumerate() {
        next.clear();
        intersect_sorted(&cand[i + 1..], g.neighbours(w), &mut next);
        if next.len() >= need - 1 {
            prefix.push(w);
            let go = kc_lists(g, &next, prefix, need - 1, out);
            prefix.pop();
            if !go {
                return false;
            }
        }
    }
    true
}

/// `a ∩ b` of two ascending lists, appended to `out`.
fn intersect_sorted(a: &[u32], b: &[u32], out: &mut Vec<u32>) {
    let (mut i, mut j) = (0usize, 0usize);
    while i < a.len() && j < b.len() {
        match a[i].cmp(&b[j]) {
            std::cmp::Ordering::Less => i += 1,
            std::cmp::Ordering::Greater => j += 1,
            std::cmp::Ordering::Equal => {
                out.push(a[i]);
                i += 1;
                j += 1;
            }
        }
    }
}

/// Above this many higher neighbours a start vertex is searched on sorted lists.
const BITS_MAX: usize = 1024;

/// The cliques of `size` vertices whose smallest vertex is `v`, in lexicographic order.
fn kc_from<O: KOut>(g: &Graph, v: u32, size: usize, out: &mut O) -> bool {
    let nb = g.neighbours(v);
    let hi = &nb[nb.partition_point(|&u| u < v)..];
    if hi.len() + 1 < size {
        return true;
    }
    let mut prefix = Vec::with_capacity(size);
    prefix.push(v);
    match hi.len().div_ceil(64) {
        1 => kc_local::<1, O>(g, hi, &mut prefix, size - 1, out),
        2 => kc_local::<2, O>(g, hi, &mut prefix, size - 1, out),
        3 | 4 => kc_local::<4, O>(g, hi, &mut prefix, size - 1, out),
        5..=8 => kc_local::<8, O>(g, hi, &mut prefix, size - 1, out),
        w if w * 64 <= BITS_MAX => kc_local::<16, O>(g, hi, &mut prefix, size - 1, out),
        _ => kc_lists(g, hi, &mut prefix, size - 1, out),
    }
}

/// The upper-triangular bit matrix of the higher neighbourhood `hi` (row i: the j > i with
/// `hi[j]` adjacent to `hi[i]`), then [`kc_bits`].
fn kc_local<const W: usize, O: KOut>(
    g: &Graph,
    hi: &[u32],
    prefix: &mut Vec<u32>,
    need: usize,
    out: &mut O,
) -> bool {
    let m = hi.len();
    let mut all = [0u64; W];
    for i in 0..m {
        all[i >> 6] |= 1 << (i & 63);
    }
    if need == 1 {
        return out.last(prefix, m, hi.iter().copied());
    }
    let mut rows = vec![[0u64; W]; m];
    for i in 0..m {
        let u = hi[i];
        let nu = g.neighbours(u);
        let row = &nu[nu.partition_point(|&x| x <= u)..];
        let (mut a, mut b) = (0usize, i + 1);
        while a < row.len() && b < m {
            match row[a].cmp(&hi[b]) {
                std::cmp::Ordering::Less => a += 1,
                std::cmp::Ordering::Greater => b += 1,
                std::cmp::Ordering::Equal => {
                    rows[i][b >> 6] |= 1 << (b & 63);
                    a += 1;
                    b += 1;
                }
            }
        }
    }
    kc_bits(&rows, hi, &all, prefix, need, out)
}

/// Every clique of exactly `size` (≥ 2) vertices, vertices ascending, lexicographically
/// sorted, as one flat array built without a sort: the cliques whose smallest vertex is `v`
/// come out in lexicographic order from [`kc_from`], and the runs of `v = 0, 1, ...`
/// concatenate. A first pass counts (and stops as soon as the budget is exceeded), a second
/// writes each start vertex's run straight into its place, in parallel.
///
/// `Err(done)`: over budget after counting `done` start vertices.
fn cliques_of_size(
    g: &Graph,
    size: usize,
    budget: &Budget,
    progress: Option<&(dyn Fn(u64) + Sync)>,
) -> Result<Vec<u32>, Refused> {
    let n = g.n_vertices();
    let done = AtomicUsize::new(0);
    let counts: Vec<u64> = (0..n as u32)
        .into_par_iter()
        .with_min_len(64)
        .map(|v| {
            if budget.stop.load(Ordering::Relaxed) {
                return 0;
            }
            let mut c = Counter {
                n: 0,
                unflushed: 0,
                size,
                budget,
            };
            if kc_from(g, v, size, &mut c) && c.flush() {
                done.fetch_add(1, Ordering::Relaxed);
            }
            c.n
        })
        .collect();
    if budget.stop.load(Ordering::Relaxed) {
        return Err(Refused::Budget(done.load(Ordering::Relaxed)));
    }
    let total: u64 = counts.iter().sum::<u64>() * size as u64;
    if total.checked_mul(4).is_none_or(|b| b > isize::MAX as u64) {
        return Err(Refused::Alloc(total.saturating_mul(4)));
    }
    // zeroed pages from the allocator: no pass over the output before the parallel writes,
    // which fault the pages in on both cores. (Huge pages were tried twice: radar's 5-skeleton
    // 0.103-0.112 -> 0.055-0.060 s, but its 6-skeleton 0.30 -> 0.68-0.87 s when run after
    // another large process: the VM reports free 2 MiB blocks to its host
    // (`page_reporting_order` 9), which must fault them in again on first touch, and huge pages
    // come from exactly those blocks. `MADV_POPULATE_WRITE` on both cores: no faster.)
    let mut out: Vec<u32> = vec![0; total as usize];
    // parts of about `target` references, each a run of start vertices and its slice
    let target = (total / (64 * rayon::current_num_threads() as u64)).max(1 << 14);
    let mut parts: Vec<(u32, u32, &mut [u32])> = Vec::new();
    let mut rest = &mut out[..];
    let (mut start, mut acc) = (0usize, 0u64);
    for (v, &count) in counts.iter().enumerate().take(n) {
        acc += count * size as u64;
        if acc >= target || v + 1 == n {
            let (a, b) = std::mem::take(&mut rest).split_at_mut(acc as usize);
            parts.push((start as u32, v as u32 + 1, a));
            rest = b;
            start = v + 1;
            acc = 0;
        }
    }
    parts.into_par_iter().for_each(|(a, b, slice)| {
        let mut w = Writer { out: slice, at: 0 };
        for v in a..b {
            if counts[v as usize] > 0 {
                kc_from(g, v, size, &mut w);
            }
        }
        debug_assert_eq!(w.at, w.out.len());
        if let Some(p) = progress {
            p((b - a) as u64);
        }
    });
    Ok(out)
}

/// Why [`cliques_of_size`] stopped.
enum Refused {
    /// Over the budget after counting this many start vertices.
    Budget(usize),
    /// The output (bytes) could not be allocated.
    Alloc(u64),
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Naive maximal cliques: every vertex subset that is a clique and has no common neighbour.
    pub(crate) fn brute(n: usize, edges: &[(u32, u32)], max_dim: Option<usize>) -> Vec<Vec<u32>> {
        let mut adj = vec![vec![false; n]; n];
        for &(a, b) in edges {
            adj[a as usize][b as usize] = true;
            adj[b as usize][a as usize] = true;
        }
        let mut out = Vec::new();
        for mask in 1u32..(1 << n) {
            let vs: Vec<u32> = (0..n as u32).filter(|&i| mask >> i & 1 == 1).collect();
            if vs.len() < 2 {
                continue;
            }
            let clique = vs
                .iter()
                .all(|&a| vs.iter().all(|&b| a == b || adj[a as usize][b as usize]));
            if !clique {
                continue;
            }
            let maximal = (0..n as u32)
                .filter(|i| !vs.contains(i))
                .all(|c| !vs.iter().all(|&a| adj[a as usize][c as usize]));
            let keep = match max_dim {
                None => maximal,
                Some(k) => vs.len() == k + 1 || (vs.len() <= k && maximal),
            };
            if keep {
                out.push(vs);
            }
        }
        out.sort_by(|a, b| (a.len(), a).cmp(&(b.len(), b)));
        out
    }

    fn random_graph(n: usize, p: f64, seed: u64) -> Vec<(u32, u32)> {
        let mut s = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        let mut e = Vec::new();
        for a in 0..n as u32 {
            for b in a + 1..n as u32 {
                s = s
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                if ((s >> 33) as f64 / (1u64 << 31) as f64) < p {
                    e.push((b, a));
                }
            }
        }
        e
    }

    #[test]
    fn equals_brute_force_on_random_graphs() {
        for seed in 0..200u64 {
            let n = 1 + (seed % 13) as usize;
            let p = [0.2, 0.5, 0.8, 0.95][(seed % 4) as usize];
            let e = random_graph(n, p, seed);
            let g = Graph::from_edges(n, &e).unwrap();
            for k in [None, Some(0), Some(1), Some(2), Some(3), Some(5)] {
                let o = CliqueOptions {
                    max_dim: k,
                    ..Default::default()
                };
                let got = maximal_cliques(&g, &o).unwrap().to_vecs();
                assert_eq!(got, brute(n, &e, k), "seed {seed} n {n} k {k:?}");
            }
        }
    }

    /// Every clique of `size` vertices by plain recursion on adjacency sets, lexicographic.
    fn reference_k_cliques(n: usize, edges: &[(u32, u32)], size: usize) -> Vec<Vec<u32>> {
        use std::collections::BTreeSet;
        let mut adj = vec![BTreeSet::new(); n];
        for &(a, b) in edges {
            adj[a as usize].insert(b);
            adj[b as usize].insert(a);
        }
        fn grow(
            adj: &[std::collections::BTreeSet<u32>],
            r: &mut Vec<u32>,
            size: usize,
            out: &mut Vec<Vec<u32>>,
        ) {
            if r.len() == size {
                out.push(r.clone());
                return;
            }
            let last = *r.last().unwrap();
            for &c in adj[last as usize].range(last + 1..) {
                if r.iter().all(|&x| adj[x as usize].contains(&c)) {
                    r.push(c);
                    grow(adj, r, size, out);
                    r.pop();
                }
            }
        }
        let mut out = Vec::new();
        for v in 0..n as u32 {
            grow(&adj, &mut vec![v], size, &mut out);
        }
        out
    }

    /// The skeleton on graphs too large for brute force: the (K+1)-block equals the plain
    /// recursion, the smaller blocks the maximal cliques of at most K vertices; start vertices
    /// with 1 to 2000 higher neighbours exercise every bit-set width and the list path.
    #[test]
    fn skeleton_equals_reference_on_larger_graphs() {
        let mut graphs: Vec<(usize, Vec<(u32, u32)>)> = Vec::new();
        // sizes keep the 7-clique reference small: G(90, 0.9) alone has ~8e8 7-cliques
        for (i, (n, p)) in [(120, 0.3), (300, 0.08), (150, 0.5), (30, 0.8)]
            .iter()
            .enumerate()
        {
            graphs.push((*n, random_graph(*n, *p, 11 + i as u64)));
        }
        // hubs: vertex 0 sees everything, vertex 1 sees 100 vertices, vertex 2 sees 700
        let n = 2100usize;
        let mut e = random_graph(n, 0.004, 5);
        e.retain(|&(a, b)| a.min(b) > 2);
        e.extend((1..n as u32).map(|u| (0, u)));
        e.extend((3..103u32).map(|u| (1, u)));
        e.extend(
            (3..703u32)
                .map(|u| (2, u * 3 % n as u32))
                .filter(|&(_, u)| u > 2),
        );
        e.extend((3..20u32).flat_map(|a| (a + 1..20).map(move |b| (a, b))));
        graphs.push((n, e));
        for (n, e) in &graphs {
            let g = Graph::from_edges(*n, e).unwrap();
            let all = maximal_cliques(&g, &CliqueOptions::default()).unwrap();
            // sizes 2-10: every fixed-size row writer and the general one
            for k in 1..=9usize {
                let o = CliqueOptions {
                    max_dim: Some(k),
                    ..Default::default()
                };
                let got = maximal_cliques(&g, &o).unwrap();
                let mut want: Vec<(usize, Vec<u32>)> = all
                    .blocks
                    .iter()
                    .filter(|(s, _)| *s <= k)
                    .cloned()
                    .collect();
                let top: Vec<u32> = reference_k_cliques(*n, e, k + 1).concat();
                if !top.is_empty() {
                    want.push((k + 1, top));
                }
                assert!(got.blocks == want, "n {n} k {k}");
            }
        }
    }

    #[test]
    fn skeleton_is_the_same_for_any_thread_count() {
        let e = random_graph(400, 0.15, 9);
        let g = Graph::from_edges(400, &e).unwrap();
        let o = CliqueOptions {
            max_dim: Some(3),
            ..Default::default()
        };
        let run = |t: usize| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(t)
                .build()
                .unwrap()
                .install(|| maximal_cliques(&g, &o).unwrap())
        };
        let one = run(1);
        assert!(one.count() > 1000);
        for t in [2, 3, 7] {
            assert_eq!(run(t), one);
        }
    }

    #[test]
    fn skeleton_over_budget_is_refused_with_an_estimate() {
        // K30: 142,506 cliques of 5 vertices; a budget of 1,000 vertex references
        let e: Vec<(u32, u32)> = (0..30u32)
            .flat_map(|a| (a + 1..30).map(move |b| (a, b)))
            .collect();
        let g = Graph::from_edges(30, &e).unwrap();
        for max_bytes in [4000, 4 * 5 * 142_505] {
            let o = CliqueOptions {
                max_dim: Some(4),
                limits: Limits::with_memory(max_bytes),
                ..Default::default()
            };
            let err = maximal_cliques(&g, &o).unwrap_err();
            let GraphError::OverBudget {
                found,
                budget_bytes,
                estimate,
                ..
            } = err
            else {
                panic!("{err}")
            };
            assert_eq!(budget_bytes, max_bytes);
            assert!(
                estimate >= found && found * 5 * 4 > max_bytes,
                "{found} {estimate}"
            );
        }
        // exactly enough
        let o = CliqueOptions {
            max_dim: Some(4),
            limits: Limits::with_memory(4 * 5 * 142_506),
            ..Default::default()
        };
        assert_eq!(maximal_cliques(&g, &o).unwrap().count(), 142_506);
    }

    /// Maximal cliques (of two or more vertices) by Bron–Kerbosch with Tomita's pivot on
    /// ordered sets: an independent reference, sorted by (size, vertices).
    fn reference_maximal(n: usize, edges: &[(u32, u32)]) -> Vec<Vec<u32>> {
        use std::collections::BTreeSet;
        let mut adj = vec![BTreeSet::new(); n];
        for &(a, b) in edges {
            adj[a as usize].insert(b);
            adj[b as usize].insert(a);
        }
        fn bk(
            adj: &[BTreeSet<u32>],
            r: &mut Vec<u32>,
            mut p: BTreeSet<u32>,
            mut x: BTreeSet<u32>,
            out: &mut Vec<Vec<u32>>,
        ) {
            if p.is_empty() {
                if x.is_empty() && r.len() > 1 {
                    let mut c = r.clone();
                    c.sort_unstable();
                    out.push(c);
                }
                return;
            }
            let pivot = *p
                .union(&x)
                .max_by_key(|&&u| p.intersection(&adj[u as usize]).count())
                .unwrap();
            let cand: Vec<u32> = p.difference(&adj[pivot as usize]).copied().collect();
            for w in cand {
                let nw = &adj[w as usize];
                r.push(w);
                bk(
                    adj,
                    r,
                    p.intersection(nw).copied().collect(),
                    x.intersection(nw).copied().collect(),
                    out,
                );
                r.pop();
                p.remove(&w);
                x.insert(w);
            }
        }
        let mut out = Vec::new();
        bk(
            &adj,
            &mut Vec::new(),
            (0..n as u32).collect(),
            BTreeSet::new(),
            &mut out,
        );
        out.sort_by(|a, b| (a.len(), a).cmp(&(b.len(), b)));
        out
    }

    /// Neighbourhoods of every width (one word, two, four, and the general matrix above 254
    /// vertices), with large cliques inside them, against the set-based reference.
    #[test]
    fn wide_neighbourhoods_equal_the_reference() {
        let n = 2100usize;
        let mut e = random_graph(n, 0.004, 21);
        e.retain(|&(a, b)| a.min(b) > 2);
        // vertex 0 sees everything (general path), 1 sees 200 vertices (4 words), 2 sees 100
        e.extend((3..n as u32).map(|u| (0, u)));
        e.extend(
            (3..203u32)
                .map(|u| (1, u * 7 % n as u32))
                .filter(|&(_, u)| u > 2),
        );
        e.extend(
            (3..103u32)
                .map(|u| (2, u * 11 % n as u32))
                .filter(|&(_, u)| u > 2),
        );
        // a K40 and a K17 that the hubs see in part
        e.extend((500..540u32).flat_map(|a| (a + 1..540).map(move |b| (a, b))));
        e.extend((3..20u32).flat_map(|a| (a + 1..20).map(move |b| (a, b))));
        e.extend((500..530u32).map(|u| (1, u)));
        let g = Graph::from_edges(n, &e).unwrap();
        for v in 0..3 {
            assert!(
                g.neighbours(v).len() > [254, 128, 64][v as usize],
                "hub {v}"
            );
        }
        let got = maximal_cliques(&g, &CliqueOptions::default())
            .unwrap()
            .to_vecs();
        let want = reference_maximal(n, &e);
        assert!(want.len() > 2000 && want.iter().any(|c| c.len() >= 41));
        assert_eq!(got, want);
        // a wide start (vertex 1, 300 neighbours) whose later neighbour 0 is a hub of more
        // than 16 times its degree: the hub's row is searched, not scanned
        let n = 5000usize;
        let mut e = random_graph(n, 0.001, 8);
        e.retain(|&(a, b)| a.min(b) > 1);
        e.extend((2..n as u32).map(|u| (0, u)));
        let ring: Vec<u32> = (2..302u32).map(|u| u * 13 % n as u32).collect();
        e.extend(ring.iter().map(|&u| (1, u)));
        e.push((0, 1));
        e.extend(
            ring[..12]
                .iter()
                .enumerate()
                .flat_map(|(i, &a)| ring[i + 1..12].iter().map(move |&b| (a, b))),
        );
        let g = Graph::from_edges(n, &e).unwrap();
        assert!(g.neighbours(1).len() > 254 && g.neighbours(0).len() > 16 * 301);
        let got = maximal_cliques(&g, &CliqueOptions::default())
            .unwrap()
            .to_vecs();
        let want = reference_maximal(n, &e);
        assert!(want.iter().any(|c| c.len() == 14));
        assert_eq!(got, want);
        // G(150, 0.5): every start has a two-word neighbourhood
        let e = random_graph(150, 0.5, 4);
        let g = Graph::from_edges(150, &e).unwrap();
        let got = maximal_cliques(&g, &CliqueOptions::default())
            .unwrap()
            .to_vecs();
        assert_eq!(got, reference_maximal(150, &e));
    }

    /// The wide search from a start whose 300 neighbours are all later (a rank that puts it
    /// first; one of them a hub adjacent to everything, others forming a K12): every maximal
    /// clique through the start, against the set-based reference.
    #[test]
    fn wide_start_with_every_neighbour_later_equals_the_reference() {
        let n = 3000usize;
        let mut e = random_graph(n, 0.003, 8);
        e.retain(|&(a, b)| a.min(b) > 1);
        e.extend((2..n as u32).map(|u| (0, u)));
        let ring: Vec<u32> = (2..302u32).map(|u| u * 7 % n as u32).collect();
        e.extend(ring.iter().map(|&u| (1, u)));
        e.push((0, 1));
        for (i, &a) in ring[..12].iter().enumerate() {
            e.extend(ring[i + 1..12].iter().map(|&b| (a, b)));
        }
        let g = Graph::from_edges(n, &e).unwrap();
        assert!(g.neighbours(1).len() > 254);
        let mut rank: Vec<u32> = (1..=n as u32).collect();
        rank[1] = 0;
        let budget = Budget {
            refs: AtomicU64::new(0),
            found: AtomicU64::new(0),
            max_refs: u64::MAX,
            stop: AtomicBool::new(false),
        };
        let mut sink = Sink::default();
        let start = Start {
            g: &g,
            rank: &rank,
            v: 1,
            limit: usize::MAX,
            budget: &budget,
        };
        start.general(&mut sink);
        let mut got: Vec<Vec<u32>> = Vec::new();
        for (s, flat) in Sink::concat(vec![sink]).iter().enumerate().skip(1) {
            got.extend(flat.chunks_exact(s).map(|c| c.to_vec()));
        }
        got.sort_by(|a, b| (a.len(), a).cmp(&(b.len(), b)));
        let want: Vec<Vec<u32>> = reference_maximal(n, &e)
            .into_iter()
            .filter(|c| c.contains(&1))
            .collect();
        assert!(want.len() > 250 && want.iter().any(|c| c.len() == 14));
        assert_eq!(got, want);
    }

    #[test]
    fn starts_follow_the_degree_order_unless_a_candidate_set_would_pass_64() {
        // sparse: a random graph of low degree
        let e = random_graph(400, 0.02, 11);
        let g = Graph::from_edges(400, &e).unwrap();
        assert_eq!(start_rank(&g), degree_rank(&g));
        // a K70 (its first vertex in degree order has 69 later neighbours) with pendant paths
        // of growing length: the degeneracy order, and the same cliques as the reference
        let mut e: Vec<(u32, u32)> = Vec::new();
        for a in 0..70 {
            for b in a + 1..70 {
                e.push((a, b));
            }
        }
        let mut next = 70;
        for len in 1..6u32 {
            let mut prev = len * 7;
            for _ in 0..len {
                e.push((prev, next));
                (prev, next) = (next, next + 1);
            }
        }
        let g = Graph::from_edges(next as usize, &e).unwrap();
        let (order, d) = degeneracy_order(&g);
        assert_eq!(d, 69);
        let mut want = vec![0u32; order.len()];
        for (i, &v) in order.iter().enumerate() {
            want[v as usize] = i as u32;
        }
        assert_eq!(start_rank(&g), want);
        let got = maximal_cliques(&g, &CliqueOptions::default()).unwrap();
        assert_eq!(got.to_vecs(), reference_maximal(next as usize, &e));
    }

    #[test]
    fn thread_count_does_not_change_the_output() {
        let e = random_graph(300, 0.1, 7);
        let g = Graph::from_edges(300, &e).unwrap();
        let run = |t: usize| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(t)
                .build()
                .unwrap()
                .install(|| maximal_cliques(&g, &CliqueOptions::default()).unwrap())
        };
        let one = run(1);
        assert!(one.count() > 100);
        for t in [2, 3, 5] {
            assert_eq!(run(t), one);
        }
    }

    #[test]
    fn over_budget_is_refused_with_an_estimate() {
        let e = random_graph(200, 0.3, 3);
        let g = Graph::from_edges(200, &e).unwrap();
        let o = CliqueOptions {
            limits: Limits::with_memory(400),
            ..Default::default()
        };
        let err = maximal_cliques(&g, &o).unwrap_err();
        assert!(
            matches!(
                err,
                GraphError::OverBudget {
                    budget_bytes: 400,
                    ..
                }
            ),
            "{err}"
        );
    }

    #[test]
    fn bad_edges_are_named() {
        assert_eq!(
            Graph::from_edges(3, &[(0, 1), (2, 2)]).unwrap_err(),
            GraphError::SelfLoop { edge: 1, vertex: 2 }
        );
        assert!(matches!(
            Graph::from_edges(3, &[(0, 3)]).unwrap_err(),
            GraphError::VertexOutOfRange {
                edge: 0,
                vertex: 3,
                n_vertices: 3
            }
        ));
    }
}
