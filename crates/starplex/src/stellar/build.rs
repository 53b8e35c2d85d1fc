//! Building a Stellar tree: decomposition, vertex reindexing, top-cell reindexing by region
//! tuples, SRE-compressed leaf lists. The result does not depend on the number of threads.
use crate::limits::TooLarge;
use std::sync::atomic::Ordering::Relaxed;
use std::time::Instant;

use rayon::prelude::*;

use super::sre::{self, RUN_FLAG};
use super::{
    default_kv, kind_code, BuildTimings, CellStore, Decomposition, SplitMode, StellarError,
    StellarOptions, StellarTree, TreeNode,
};
use crate::complex::IndexedComplex;

/// The input's top cells, read without a block search when the complex is one block.
pub(super) struct InputCells<'a> {
    k: &'a IndexedComplex,
    /// (kind, vertices, stride) of the only block.
    one: Option<(crate::cell::CellKind, &'a [u32], usize)>,
}

impl<'a> InputCells<'a> {
    fn new(k: &'a IndexedComplex) -> Self {
        let one = match k.blocks() {
            [b] => Some((b.kind, &b.vertices[..], b.kind.n_vertices())),
            _ => None,
        };
        InputCells { k, one }
    }

    /// Number of top cells.
    pub(super) fn len(&self) -> usize {
        self.k.n_cells()
    }

    #[inline]
    pub(super) fn get(&self, c: u32) -> (crate::cell::CellKind, &'a [u32]) {
        match self.one {
            Some((kind, vs, st)) => {
                let i = c as usize * st;
                (kind, &vs[i..i + st])
            }
            None => {
                let r = self.k.cell(crate::ids::CellId(c));
                (r.kind, r.vertices)
            }
        }
    }
}

/// A subtree while splitting.
pub(super) enum T {
    Leaf(u32, u32),
    Inner(u32, u32, Vec<T>),
}

impl T {
    fn range(&self) -> (u32, u32) {
        match self {
            T::Leaf(a, b) | T::Inner(a, b, _) => (*a, *b),
        }
    }
}

struct Ctx<'a> {
    coords: &'a [f64],
    n: usize,
    kv: usize,
    regular: bool,
    max_depth: u32,
}

const PAR_MIN: usize = 32_768;

/// The checks and parameters of a build: the context of the split, the split mode and k_V.
fn setup<'a>(
    k: &'a IndexedComplex,
    opts: &StellarOptions,
) -> Result<(Ctx<'a>, SplitMode, u32), StellarError> {
    let nc = k.n_cells();
    if nc as u64 >= RUN_FLAG as u64 {
        return Err(StellarError::TooManyCells(nc as u64));
    }
    if k.n_refs() >= u32::MAX as usize {
        return Err(StellarError::TooLarge(TooLarge::ids(
            "vertex references",
            k.n_refs() as u128,
        )));
    }
    let n = k.ambient_dim();
    let split = match opts.split {
        SplitMode::Auto if n <= 3 => SplitMode::Regular,
        SplitMode::Auto => SplitMode::Kd,
        SplitMode::Regular if n > 8 => {
            return Err(StellarError::RegularTooWide(n, 1u128 << n.min(127)))
        }
        s => s,
    };
    let kv = opts.kv.unwrap_or_else(|| default_kv(k));
    let graph = opts.decomposition == Decomposition::Graph;
    let max_depth = opts.max_depth.unwrap_or(match split {
        _ if graph => 64,
        SplitMode::Regular => 64,
        _ => (64 * n as u32).min(2048),
    });
    let ctx = Ctx {
        coords: k.coords(),
        n,
        kv: kv as usize,
        regular: split == SplitMode::Regular,
        max_depth,
    };
    Ok((ctx, split, kv))
}

/// The vertex half of [`build`]: the input vertices in tree order and the first tree vertex of
/// every leaf (then the vertex count), exactly as the tree built with `opts` has them
/// (`vertex_to_input` and the leaves' vertex ranges), without filing the cells.
pub(super) fn vertex_order(
    k: &IndexedComplex,
    opts: &StellarOptions,
) -> Result<(Vec<u32>, Vec<u32>), StellarError> {
    let (ctx, _, _) = setup(k, opts)?;
    let graph = opts.decomposition == Decomposition::Graph;
    let input = InputCells::new(k);
    let d = decompose(&ctx, k.n_vertices(), graph.then_some(&input));
    let v = reindex_vertices(d.idx, &d.leaf_vstart);
    Ok((v.v_orig, d.leaf_vstart))
}

pub(super) fn build(
    k: &IndexedComplex,
    opts: &StellarOptions,
) -> Result<StellarTree, StellarError> {
    let (ctx, split, kv) = setup(k, opts)?;
    let n = ctx.n;
    let graph = opts.decomposition == Decomposition::Graph;
    let mut timings = BuildTimings::default();

    let t0 = Instant::now();
    let input = InputCells::new(k);
    let d = decompose(&ctx, k.n_vertices(), graph.then_some(&input));
    timings.decomposition_s = t0.elapsed().as_secs_f64();

    let t1 = Instant::now();
    let mut v = reindex_vertices(d.idx, &d.leaf_vstart);
    timings.vertex_reindex_s = t1.elapsed().as_secs_f64();

    let t2 = Instant::now();
    let c = reindex_cells(k, &mut v, &d.leaf_vstart);
    timings.cell_reindex_s = t2.elapsed().as_secs_f64();

    // SRE-compressed leaf lists from the runs of equal leaf tuples
    let t3 = Instant::now();
    let (leaf_toff, leaf_tops) = leaf_lists(&c.groups, d.leaf_vstart.len() - 1);
    drop(c.groups);
    timings.leaf_lists_s = t3.elapsed().as_secs_f64();

    let attrs = if k.attributes().is_empty() {
        crate::attr::Attributes::default()
    } else {
        k.attributes()
            .gather_vertices(&v.v_orig)
            .gather_cells(&c.c_orig)
    };
    Ok(StellarTree {
        attrs,
        coords: None,
        ambient_dim: n as u32,
        kv,
        split,
        decomposition: opts.decomposition,
        bbox: d.bbox,
        nodes: d.nodes,
        leaf_vstart: d.leaf_vstart,
        leaf_toff,
        leaf_tops,
        cells: c.cells,
        v_orig: v.v_orig,
        v_new: v.v_new,
        c_orig: c.c_orig,
        c_new: c.c_new,
        timings,
    })
}

/// Phase 1: the decomposition.
struct Decomposed {
    /// Bounding box (lower, upper corner).
    bbox: (Vec<f64>, Vec<f64>),
    /// Nodes in brood (BFS) order.
    nodes: Vec<TreeNode>,
    /// First tree vertex of each leaf (leaves in DFS order), then the vertex count.
    leaf_vstart: Vec<u32>,
    /// Input vertex ids, grouped by leaf.
    idx: Vec<u32>,
}

/// Splits the vertices (kD or regular, or with `graph` by connectivity, see [`graph_split`])
/// until every leaf has at most k_V of them; flattens the tree: leaves in DFS order, nodes in
/// brood order.
///
/// [`graph_split`]: super::graph_split
fn decompose(ctx: &Ctx, nv: usize, graph: Option<&InputCells<'_>>) -> Decomposed {
    let n = ctx.n;
    let empty = || (vec![f64::INFINITY; n], vec![f64::NEG_INFINITY; n]);
    let (mut lo, mut hi) = ctx
        .coords
        .par_chunks(n.max(1) << 14)
        .map(|ch| {
            let (mut lo, mut hi) = empty();
            for p in ch.chunks_exact(n) {
                for i in 0..n {
                    lo[i] = lo[i].min(p[i]);
                    hi[i] = hi[i].max(p[i]);
                }
            }
            (lo, hi)
        })
        .reduce(empty, |(mut lo, mut hi), (l, h)| {
            for i in 0..n {
                lo[i] = lo[i].min(l[i]);
                hi[i] = hi[i].max(h[i]);
            }
            (lo, hi)
        });
    if nv == 0 {
        lo.iter_mut().for_each(|x| *x = 0.0);
        hi.iter_mut().for_each(|x| *x = 0.0);
    }
    let mut idx: Vec<u32> = (0..nv as u32).collect();
    let root = if ctx.kv == 0 || nv <= ctx.kv {
        T::Leaf(0, nv as u32)
    } else if let Some(cells) = graph {
        super::graph_split::graph_split(cells, &mut idx, ctx.kv, ctx.max_depth)
    } else {
        split_rec(ctx, &mut idx, 0, lo.clone(), hi.clone(), 0)
    };
    let mut leaf_vstart: Vec<u32> = Vec::new();
    collect_leaves(&root, &mut leaf_vstart);
    leaf_vstart.push(nv as u32);
    let nodes = brood_order(&root, &leaf_vstart);
    Decomposed {
        bbox: (lo, hi),
        nodes,
        leaf_vstart,
        idx,
    }
}

/// The nodes of `root` in brood (BFS) order; a leaf node's `first` is its leaf index.
fn brood_order(root: &T, leaf_vstart: &[u32]) -> Vec<TreeNode> {
    let node = |t: &T| {
        let (a, b) = t.range();
        TreeNode {
            v_start: a,
            v_end: b,
            first: 0,
            n_children: 0,
        }
    };
    let mut nodes = vec![node(root)];
    let mut queue: std::collections::VecDeque<(usize, &T)> = Default::default();
    queue.push_back((0, root));
    while let Some((id, t)) = queue.pop_front() {
        match t {
            T::Leaf(a, _) => {
                let l = leaf_vstart.partition_point(|&s| s < *a);
                nodes[id].first = l as u32;
            }
            T::Inner(_, _, ch) => {
                nodes[id].first = nodes.len() as u32;
                nodes[id].n_children = ch.len() as u32;
                for c in ch {
                    queue.push_back((nodes.len(), c));
                    nodes.push(node(c));
                }
            }
        }
    }
    nodes
}

/// Phase 2: the tree's vertex numbering.
struct VertexNumbering {
    /// Tree vertex → input vertex.
    v_orig: Vec<u32>,
    /// Input vertex → tree vertex.
    v_new: Vec<u32>,
    /// Input vertex → its leaf (dropped by [`reindex_cells`] once the cells are sorted).
    leaf_in: Vec<u32>,
}

/// Sorts each leaf's vertices by input id (deterministic, local) and numbers them in leaf order.
fn reindex_vertices(mut idx: Vec<u32>, leaf_vstart: &[u32]) -> VertexNumbering {
    let n_leaves = leaf_vstart.len() - 1;
    split_by(&mut idx, leaf_vstart)
        .into_par_iter()
        .for_each(|p| p.sort_unstable());
    let v_orig = idx;
    let nv = v_orig.len();
    let v_new = crate::buf::invert(&v_orig);
    let mut leaf_in = vec![0u32; nv];
    let out = crate::buf::atomic_view(&mut leaf_in);
    (0..n_leaves)
        .into_par_iter()
        .with_min_len(64)
        .for_each(|l| {
            for t in leaf_vstart[l]..leaf_vstart[l + 1] {
                out[v_orig[t as usize] as usize].store(l as u32, Relaxed);
            }
        });
    VertexNumbering {
        v_orig,
        v_new,
        leaf_in,
    }
}

/// `v` cut into consecutive parts at the offsets `bounds` (`bounds[0] == 0`, last = `v.len()`).
fn split_by<'a>(v: &'a mut [u32], bounds: &[u32]) -> Vec<&'a mut [u32]> {
    split_by_stride(v, bounds, 1)
}

/// Phase 3: the tree's cell numbering, the reindexed cell store and the runs of cells with the
/// same leaves.
struct CellNumbering {
    c_orig: Vec<u32>,
    c_new: Vec<u32>,
    cells: CellStore,
    groups: Vec<Groups>,
}

/// Numbers the cells by home leaf (the leaf of their smallest tree vertex), then within a home
/// leaf by (tuple of leaves, kind, input id); the runs of equal tuples make the leaf lists.
fn reindex_cells(
    k: &IndexedComplex,
    v: &mut VertexNumbering,
    leaf_vstart: &[u32],
) -> CellNumbering {
    let n_leaves = leaf_vstart.len() - 1;
    if let [b] = k.blocks()
        && n_leaves < (1 << 31)
        && !b.is_empty()
        && b.kind.n_vertices() <= 4
    {
        return reindex_small_uniform(b.kind, &b.vertices, v, leaf_vstart);
    }
    reindex_cells_general(k, v, n_leaves)
}

/// [`reindex_cells`] for any cells.
fn reindex_cells_general(
    k: &IndexedComplex,
    v: &mut VertexNumbering,
    n_leaves: usize,
) -> CellNumbering {
    let nc = k.n_cells();
    let mixed = k.blocks().len() > 1 && k.blocks().iter().any(|b| b.kind != k.blocks()[0].kind);
    let uniform = if mixed || nc == 0 {
        None
    } else {
        Some(k.blocks()[0].kind)
    };
    let input = InputCells::new(k);
    let in_cell = |c: u32| input.get(c);
    let leaf_in = &v.leaf_in;
    // home leaf of every input cell = leaf of its smallest tree vertex = its smallest leaf
    // (leaves own increasing ranges of tree vertices)
    let home: Vec<u32> = (0..nc as u32)
        .into_par_iter()
        .with_min_len(4096)
        .map(|c| {
            in_cell(c)
                .1
                .iter()
                .map(|&v| leaf_in[v as usize])
                .min()
                .expect("cells have vertices")
        })
        .collect();
    let mut start = vec![0u32; n_leaves + 1];
    for &h in &home {
        start[h as usize + 1] += 1;
    }
    for l in 0..n_leaves {
        start[l + 1] += start[l];
    }
    let mut order = vec![0u32; nc];
    let mut pos = start.clone();
    for (c, &h) in home.iter().enumerate() {
        order[pos[h as usize] as usize] = c as u32;
        pos[h as usize] += 1;
    }
    drop((home, pos));
    let groups: Vec<Groups> = split_by(&mut order, &start)
        .into_par_iter()
        .enumerate()
        .map_init(SortScratch::default, |sc, (home, part)| {
            sort_part(home as u32, part, &in_cell, leaf_in, sc)
        })
        .collect();
    drop(std::mem::take(&mut v.leaf_in)); // not needed by the cell store: keep the peak low
    let c_orig = order;
    let c_new = crate::buf::invert(&c_orig);
    let cells = cell_store(k, &input, uniform, &c_orig, &v.v_new);
    CellNumbering {
        c_orig,
        c_new,
        cells,
        groups,
    }
}

/// [`reindex_cells`] for one kind of at most 4 vertices (`flat`: the input cells), in the same
/// order with fewer random reads. The general path reads each cell twice in tree order (its
/// leaves to sort its home leaf, its vertices to renumber them): ~60 % of the build of
/// tri_armadillo_x16, most of it cache misses. Here the cells are read in input order only:
/// once for their home leaf and whether they lie in it alone, once to write them renumbered
/// into their home leaf's range (a counting sort); then each home leaf's range, now contiguous,
/// is put in order in cache: the cells lying in the home leaf alone first, in input order, then
/// the others by (the rest of their tuple of leaves, input id), as [`sort_part`] does.
fn reindex_small_uniform(
    kind: crate::cell::CellKind,
    flat: &[u32],
    v: &mut VertexNumbering,
    leaf_vstart: &[u32],
) -> CellNumbering {
    const MULTI: u32 = 1 << 31;
    let st = kind.n_vertices();
    let nc = flat.len() / st;
    let n_leaves = leaf_vstart.len() - 1;
    let leaf_in = &v.leaf_in;
    // home leaf (the smallest), flagged when the cell has vertices in another leaf too
    let home: Vec<u32> = flat
        .par_chunks_exact(st)
        .with_min_len(4096)
        .map(|c| {
            let (mut lo, mut hi) = (u32::MAX, 0u32);
            for &x in c {
                let l = leaf_in[x as usize];
                lo = lo.min(l);
                hi = hi.max(l);
            }
            if lo == hi {
                lo
            } else {
                lo | MULTI
            }
        })
        .collect();
    // per home leaf: its cells, and those lying in it alone (which come first); counted by
    // chunks on every thread, the chunks' counts added (a chunk at least 8 entries a leaf, so
    // that the per-job counts take at most a byte a cell, whatever the thread count)
    let counts = home
        .par_chunks((1 << 16).max(8 * n_leaves))
        .fold(
            || vec![[0u32; 2]; n_leaves],
            |mut n, ch| {
                for &h in ch {
                    let e = &mut n[(h & !MULTI) as usize];
                    e[0] += 1;
                    e[1] += u32::from(h & MULTI == 0);
                }
                n
            },
        )
        .reduce_with(|mut a, b| {
            a.iter_mut().zip(&b).for_each(|(x, y)| {
                x[0] += y[0];
                x[1] += y[1];
            });
            a
        })
        .unwrap_or_else(|| vec![[0u32; 2]; n_leaves]);
    let mut start = vec![0u32; n_leaves + 1];
    let singles: Vec<u32> = counts.iter().map(|e| e[1]).collect();
    for (l, e) in counts.iter().enumerate() {
        start[l + 1] = start[l] + e[0];
    }
    drop(counts);
    // the counting sort, stable: each home leaf's cells in input order, renumbered, those in
    // the leaf alone before the others
    let mut order = vec![0u32; nc];
    let mut verts = vec![0u32; nc * st];
    let v_new = &v.v_new;
    // On several threads each takes a range of home leaves with about as many cells, scans
    // all cells and writes those of its leaves into its own part of the output (one test per
    // cell more, no shared writes; the same output for any thread count).
    let n_parts = rayon::current_num_threads()
        .clamp(1, 8)
        .min(n_leaves.max(1));
    let mut cuts = vec![0usize];
    for i in 1..n_parts {
        let want = (nc * i / n_parts) as u32;
        cuts.push(
            start
                .partition_point(|&x| x < want)
                .min(n_leaves)
                .max(cuts[i - 1]),
        );
    }
    cuts.push(n_leaves);
    let bounds: Vec<u32> = cuts.iter().map(|&l| start[l]).collect();
    let ranges: Vec<_> = split_by(&mut order, &bounds)
        .into_iter()
        .zip(split_by_stride(&mut verts, &bounds, st))
        .zip(cuts.windows(2))
        .collect();
    ranges.into_par_iter().for_each(|((order, verts), w)| {
        let (lo, hi) = (w[0], w[1]);
        let base = start[lo];
        let mut pos: Vec<[u32; 2]> = (lo..hi)
            .map(|l| [start[l] - base, start[l] + singles[l] - base])
            .collect();
        for (c, (&h, cell)) in home.iter().zip(flat.chunks_exact(st)).enumerate() {
            let l = (h & !MULTI) as usize;
            if !(lo..hi).contains(&l) {
                continue;
            }
            let slot = &mut pos[l - lo][(h >> 31) as usize];
            let p = *slot as usize;
            *slot += 1;
            order[p] = c as u32;
            for (d, &x) in verts[p * st..(p + 1) * st].iter_mut().zip(cell) {
                *d = v_new[x as usize];
            }
        }
    });
    // the leaf of each tree vertex (leaves own increasing ranges of them), in leaf_in's memory
    let mut leaf_of_tree = std::mem::take(&mut v.leaf_in);
    for (l, w) in leaf_vstart.windows(2).enumerate() {
        leaf_of_tree[w[0] as usize..w[1] as usize].fill(l as u32);
    }
    let leaf_t = |t: u32| leaf_of_tree[t as usize];
    let parts: Vec<(&mut [u32], &mut [u32])> = split_by(&mut order, &start)
        .into_iter()
        .zip(split_by_stride(&mut verts, &start, st))
        .collect();
    // one growing run list per rayon job (not one per leaf: thousands of small allocations)
    let groups: Vec<Groups> = parts
        .into_par_iter()
        .enumerate()
        .fold(
            || {
                let g = Groups::default();
                (g, Vec::<u128>::new(), Vec::<u32>::new(), Vec::<u32>::new())
            },
            |(mut g, mut keys, mut rec, mut ids), (h, (part, cells))| {
                let w = singles[h] as usize;
                let h = h as u32;
                // the cells in several leaves, in input order: key = (rest of the tuple, j)
                // for the j-th of them, the same order as by (rest, input id)
                keys.clear();
                rec.clear();
                rec.extend_from_slice(&cells[w * st..]);
                for (j, cell) in rec.chunks_exact(st).enumerate() {
                    keys.push(rest_of_tuple(cell, leaf_t) | j as u128);
                }
                keys.sort_unstable();
                ids.clear();
                ids.extend_from_slice(&part[w..]);
                if w > 0 {
                    g.push(w as u32, &[h]);
                }
                let mut ls = [0u32; 4];
                let mut prev = None;
                for (i, &key) in (w..).zip(keys.iter()) {
                    let j = key as u32 as usize;
                    part[i] = ids[j];
                    cells[i * st..(i + 1) * st].copy_from_slice(&rec[j * st..(j + 1) * st]);
                    let rest = key & !0xffff_ffff;
                    match g.len.last_mut() {
                        Some(n) if prev == Some(rest) => *n += 1,
                        _ => {
                            let m = unpack(h, rest, &mut ls);
                            g.push(1, &ls[..m]);
                        }
                    }
                    prev = Some(rest);
                }
                (g, keys, rec, ids)
            },
        )
        .map(|(g, ..)| g)
        .collect();
    let c_orig = order;
    // the home array's memory (every entry is overwritten: c_orig is a permutation)
    let mut c_new = home;
    crate::buf::invert_into(&c_orig, &mut c_new);
    CellNumbering {
        c_orig,
        c_new,
        cells: CellStore {
            uniform: Some(kind),
            stride: st as u32,
            kinds: Vec::new(),
            offsets: Vec::new(),
            verts,
            n: nc as u32,
        },
        groups,
    }
}

/// The leaves of a cell of 2-4 vertices after its first (smallest) one, distinct and
/// increasing, packed from bit 96 down, 0 after the last ([`unpack`] reads it back). A
/// sorting network, no data-dependent loop.
#[inline]
fn rest_of_tuple(cell: &[u32], leaf_of: impl Fn(u32) -> u32) -> u128 {
    let mut l = [u32::MAX; 4];
    for (d, &x) in l.iter_mut().zip(cell) {
        *d = leaf_of(x);
    }
    let l = crate::topo::sort4(l);
    let (mut key, mut sh, mut prev) = (0u128, 96u32, l[0]);
    for &x in &l[1..] {
        if x != prev && x != u32::MAX {
            key |= (x as u128) << sh;
            sh -= 32;
            prev = x;
        }
    }
    key
}

/// [`split_by`] for records of `st` values: part `i` holds records `bounds[i]..bounds[i + 1]`.
fn split_by_stride<'a>(mut v: &'a mut [u32], bounds: &[u32], st: usize) -> Vec<&'a mut [u32]> {
    let mut parts = Vec::with_capacity(bounds.len().saturating_sub(1));
    for w in bounds.windows(2) {
        let (a, b) = v.split_at_mut((w[1] - w[0]) as usize * st);
        parts.push(a);
        v = b;
    }
    parts
}

/// The cells in tree order, their vertices in tree ids.
fn cell_store(
    k: &IndexedComplex,
    input: &InputCells<'_>,
    uniform: Option<crate::cell::CellKind>,
    c_orig: &[u32],
    v_new: &[u32],
) -> CellStore {
    let nc = c_orig.len();
    if let Some(kind) = uniform {
        let st = kind.n_vertices();
        let mut verts = vec![0u32; k.n_refs()];
        verts
            .par_chunks_mut(st * 4096)
            .enumerate()
            .for_each(|(ci, ch)| {
                let base = ci * 4096;
                for (i, dst) in ch.chunks_exact_mut(st).enumerate() {
                    for (x, &y) in dst.iter_mut().zip(input.get(c_orig[base + i]).1) {
                        *x = v_new[y as usize];
                    }
                }
            });
        return CellStore {
            uniform,
            stride: st as u32,
            kinds: Vec::new(),
            offsets: Vec::new(),
            verts,
            n: nc as u32,
        };
    }
    let mut kinds = Vec::with_capacity(nc);
    let mut offsets = Vec::with_capacity(nc + 1);
    let mut verts = Vec::with_capacity(k.n_refs());
    offsets.push(0u32);
    for &old in c_orig {
        let (kind, vs) = input.get(old);
        kinds.push(kind_code(kind));
        verts.extend(vs.iter().map(|&v| v_new[v as usize]));
        offsets.push(verts.len() as u32);
    }
    CellStore {
        uniform: None,
        stride: 0,
        kinds,
        offsets,
        verts,
        n: nc as u32,
    }
}

/// Runs of consecutive tree cells with the same distinct leaves, in tree order: `len[i]` cells
/// whose leaves (increasing) are `leaves[off[i]..off[i + 1]]`.
#[derive(Default)]
struct Groups {
    len: Vec<u32>,
    off: Vec<u32>,
    leaves: Vec<u32>,
}

impl Groups {
    /// Appends `len` cells with the distinct leaves `ls` (merged into the last run when equal).
    fn push(&mut self, len: u32, ls: &[u32]) {
        if self.off.is_empty() {
            self.off.push(0);
        }
        if let Some(last) = self.len.last_mut() {
            let s = self.off[self.off.len() - 2] as usize;
            if self.leaves[s..] == *ls {
                *last += len;
                return;
            }
        }
        self.len.push(len);
        self.leaves.extend_from_slice(ls);
        self.off.push(self.leaves.len() as u32);
    }

    fn iter(&self) -> impl Iterator<Item = (u32, &[u32])> + '_ {
        self.len.iter().enumerate().map(|(i, &n)| {
            (
                n,
                &self.leaves[self.off[i] as usize..self.off[i + 1] as usize],
            )
        })
    }
}

/// Per-worker buffers of [`sort_part`].
#[derive(Default)]
struct SortScratch {
    scratch: Vec<u32>,
    keyed: Vec<(u32, u32, u32, u8)>,
    packed: Vec<(u128, u64)>,
}

/// The leaves of a packed tuple: `t0` then the non-zero leaves of `rest` (every leaf after the
/// first is >= 1, so 0 is padding).
#[inline]
fn unpack(t0: u32, rest: u128, out: &mut [u32; 4]) -> usize {
    out[0] = t0;
    let mut m = 1;
    for sh in [96u32, 64, 32] {
        let x = (rest >> sh) as u32;
        if x != 0 {
            out[m] = x;
            m += 1;
        }
    }
    m
}

/// Sorts the cells of one home leaf (`part`, in input order) by (tuple of distinct leaves,
/// kind, input id) and returns the runs of equal tuples.
fn sort_part<'a>(
    home: u32,
    part: &mut [u32],
    in_cell: &impl Fn(u32) -> (crate::cell::CellKind, &'a [u32]),
    leaf_in: &[u32],
    sc: &mut SortScratch,
) -> Groups {
    let mut g = Groups::default();
    let mut ls = [0u32; 4];
    if part.iter().all(|&c| in_cell(c).1.len() <= 4) {
        // the sorted distinct leaves of a cell packed in a u128, padded with 0
        let packed = &mut sc.packed;
        packed.clear();
        for &c in part.iter() {
            let (kind, vs) = in_cell(c);
            let (t, _) = distinct_leaves::<4>(vs, leaf_in);
            let key = ((t[0] as u128) << 96)
                | ((t[1] as u128) << 64)
                | ((t[2] as u128) << 32)
                | t[3] as u128;
            packed.push((key, ((kind_code(kind) as u64) << 32) | c as u64));
        }
        packed.sort_unstable();
        for (dst, k) in part.iter_mut().zip(packed.iter()) {
            *dst = k.1 as u32;
            let m = unpack(home, k.0 << 32, &mut ls);
            g.push(1, &ls[..m]);
        }
        return g;
    }
    let (scratch, keyed) = (&mut sc.scratch, &mut sc.keyed);
    scratch.clear();
    keyed.clear();
    for &c in part.iter() {
        let (kind, vs) = in_cell(c);
        let s = scratch.len();
        scratch.extend(vs.iter().map(|&v| leaf_in[v as usize]));
        scratch[s..].sort_unstable();
        let mut w = s;
        for r in s..scratch.len() {
            if r == s || scratch[r] != scratch[w - 1] {
                scratch[w] = scratch[r];
                w += 1;
            }
        }
        scratch.truncate(w);
        keyed.push((c, s as u32, w as u32, kind_code(kind)));
    }
    keyed.sort_unstable_by(|a, b| {
        scratch[a.1 as usize..a.2 as usize]
            .cmp(&scratch[b.1 as usize..b.2 as usize])
            .then(a.3.cmp(&b.3))
            .then(a.0.cmp(&b.0))
    });
    for (dst, k) in part.iter_mut().zip(keyed.iter()) {
        *dst = k.0;
        g.push(1, &scratch[k.1 as usize..k.2 as usize]);
    }
    g
}

/// Builds every leaf's SRE list from the runs of equal leaf tuples, in tree order.
fn leaf_lists(groups: &[Groups], n_leaves: usize) -> (Vec<u32>, Vec<u32>) {
    const NONE: u32 = u32::MAX;
    // per-leaf open run: (start, len)
    let mut run_start = vec![NONE; n_leaves];
    let mut run_len = vec![0u32; n_leaves];
    let mut cost = vec![0u32; n_leaves + 1];
    let runs = || groups.iter().flat_map(|g| g.iter());
    // pass 1: sizes
    let mut c = 0u32;
    for (len, ls) in runs() {
        for &l in ls {
            let l = l as usize;
            if run_start[l] != NONE && run_start[l] + run_len[l] == c {
                run_len[l] += len;
            } else {
                if run_start[l] != NONE {
                    cost[l + 1] += sre::run_cost(run_len[l]);
                }
                run_start[l] = c;
                run_len[l] = len;
            }
        }
        c += len;
    }
    for l in 0..n_leaves {
        if run_start[l] != NONE {
            cost[l + 1] += sre::run_cost(run_len[l]);
        }
        cost[l + 1] += cost[l];
    }
    let offsets = cost;
    let mut out = vec![0u32; offsets[n_leaves] as usize];
    let mut cursor: Vec<u32> = offsets[..n_leaves].to_vec();
    run_start.iter_mut().for_each(|x| *x = NONE);
    let mut tmp: Vec<u32> = Vec::with_capacity(4);
    let mut flush = |l: usize, s: u32, len: u32, out: &mut Vec<u32>, cursor: &mut Vec<u32>| {
        tmp.clear();
        sre::push_run(s, len, &mut tmp);
        let p = cursor[l] as usize;
        out[p..p + tmp.len()].copy_from_slice(&tmp);
        cursor[l] += tmp.len() as u32;
    };
    let mut c = 0u32;
    for (len, ls) in runs() {
        for &l in ls {
            let l = l as usize;
            if run_start[l] != NONE && run_start[l] + run_len[l] == c {
                run_len[l] += len;
            } else {
                if run_start[l] != NONE {
                    flush(l, run_start[l], run_len[l], &mut out, &mut cursor);
                }
                run_start[l] = c;
                run_len[l] = len;
            }
        }
        c += len;
    }
    for l in 0..n_leaves {
        if run_start[l] != NONE {
            flush(l, run_start[l], run_len[l], &mut out, &mut cursor);
        }
    }
    debug_assert!((0..n_leaves).all(|l| cursor[l] == offsets[l + 1]));
    (offsets, out)
}

/// The distinct leaves of the vertices `vs` (at most `N` of them), increasing, in the prefix of
/// the returned array (rest 0) whose length is returned: insertion into a sorted prefix, no
/// allocation.
#[inline]
fn distinct_leaves<const N: usize>(vs: &[u32], leaf_of: &[u32]) -> ([u32; N], usize) {
    let mut t = [0u32; N];
    let mut m = 0;
    for &v in vs {
        let x = leaf_of[v as usize];
        let mut p = m;
        while p > 0 && t[p - 1] > x {
            p -= 1;
        }
        if p > 0 && t[p - 1] == x {
            continue;
        }
        // a few words: moved one by one (`copy_within` would call memmove)
        let mut j = m;
        while j > p {
            t[j] = t[j - 1];
            j -= 1;
        }
        t[p] = x;
        m += 1;
    }
    (t, m)
}

fn collect_leaves(t: &T, out: &mut Vec<u32>) {
    match t {
        T::Leaf(a, _) => out.push(*a),
        T::Inner(_, _, ch) => ch.iter().for_each(|c| collect_leaves(c, out)),
    }
}

/// True when all points of `idx` are equal.
fn all_equal(ctx: &Ctx, idx: &[u32]) -> bool {
    let n = ctx.n;
    let p0 = &ctx.coords[idx[0] as usize * n..idx[0] as usize * n + n];
    idx.iter()
        .all(|&i| &ctx.coords[i as usize * n..i as usize * n + n] == p0)
}

/// Partitions `idx` in place: points with coordinate `axis` < `mid` first. Returns the split.
fn partition(ctx: &Ctx, idx: &mut [u32], axis: usize, mid: f64) -> usize {
    let n = ctx.n;
    let c = ctx.coords;
    // Lomuto without branches: [0, s) below mid, [s, i) not. A point's side is a coin flip
    // for the branch predictor; the swap is unconditional and only `s` moves by the test.
    // (The order within a side differs from a Hoare partition's; each leaf's vertices are
    // sorted by input id afterwards, so the tree is the same.)
    let mut s = 0usize;
    for i in 0..idx.len() {
        let v = idx[i];
        let below = usize::from(c[v as usize * n + axis] < mid);
        idx[i] = idx[s];
        idx[s] = v;
        s += below;
    }
    s
}

/// A node at least this large is partitioned on all threads ([`partition_par`]) when there
/// are several: the first levels of the split are otherwise serial passes over every vertex.
const PAR_PARTITION: usize = 1 << 18;

/// The children of the box `lo`..`hi` split at its middle on every axis of `axes`, as the
/// serial passes of [`split_rec`] make them (the first axis most significant; the points
/// below the middle first), but with the points of each child in another order (each leaf is
/// sorted by input id afterwards, so the tree is the same): each chunk of `idx` counts its
/// points per child, then writes them to their place in a copy, on all threads.
fn partition_par<'a>(
    ctx: &Ctx,
    idx: &'a mut [u32],
    axes: &[usize],
    lo: Vec<f64>,
    hi: Vec<f64>,
) -> Vec<(&'a mut [u32], Vec<f64>, Vec<f64>)> {
    const CHUNK: usize = 1 << 16;
    let (n, c) = (ctx.n, ctx.coords);
    let mids: Vec<f64> = axes.iter().map(|&a| 0.5 * (lo[a] + hi[a])).collect();
    let n_children = 1usize << axes.len();
    let child = |v: u32| {
        let p = &c[v as usize * n..v as usize * n + n];
        axes.iter()
            .zip(&mids)
            .fold(0usize, |k, (&a, &m)| (k << 1) | (1 - usize::from(p[a] < m)))
    };
    // per chunk, its first place in each child (the children in order, the chunks in order)
    let mut at: Vec<Vec<usize>> = idx
        .par_chunks(CHUNK)
        .map(|ch| {
            let mut k = vec![0usize; n_children];
            ch.iter().for_each(|&v| k[child(v)] += 1);
            k
        })
        .collect();
    let mut sizes = vec![0usize; n_children];
    for k in &mut at {
        for (s, x) in sizes.iter_mut().zip(k.iter_mut()) {
            (*s, *x) = (*s + *x, *s);
        }
    }
    let mut first = 0;
    let child_start: Vec<usize> = sizes
        .iter()
        .map(|&s| {
            first += s;
            first - s
        })
        .collect();
    let mut copy = vec![0u32; idx.len()];
    let out = crate::buf::atomic_view(&mut copy);
    idx.par_chunks(CHUNK).zip(at).for_each(|(ch, mut k)| {
        for (x, s) in k.iter_mut().zip(&child_start) {
            *x += s;
        }
        for &v in ch {
            let j = child(v);
            out[k[j]].store(v, Relaxed);
            k[j] += 1;
        }
    });
    idx.par_chunks_mut(CHUNK)
        .zip(copy.par_chunks(CHUNK))
        .for_each(|(d, s)| d.copy_from_slice(s));
    drop(copy);
    let mut parts = Vec::with_capacity(n_children);
    let mut rest = idx;
    for (j, &size) in sizes.iter().enumerate() {
        let (a, b) = rest.split_at_mut(size);
        rest = b;
        let (mut l, mut h) = (lo.clone(), hi.clone());
        for (i, (&axis, &m)) in axes.iter().zip(&mids).enumerate() {
            if (j >> (axes.len() - 1 - i)) & 1 == 0 {
                h[axis] = m;
            } else {
                l[axis] = m;
            }
        }
        parts.push((a, l, h));
    }
    parts
}

fn split_rec(ctx: &Ctx, idx: &mut [u32], offset: u32, lo: Vec<f64>, hi: Vec<f64>, depth: u32) -> T {
    let len = idx.len();
    let end = offset + len as u32;
    if len <= ctx.kv || depth >= ctx.max_depth || (depth % 16 == 15 && all_equal(ctx, idx)) {
        return T::Leaf(offset, end);
    }
    // children: (slice, lo, hi)
    let axes: Vec<usize> = if ctx.regular {
        (0..ctx.n).collect()
    } else {
        vec![depth as usize % ctx.n]
    };
    if len >= PAR_PARTITION && rayon::current_num_threads() > 1 {
        return split_children(ctx, partition_par(ctx, idx, &axes, lo, hi), offset, depth);
    }
    let mut parts: Vec<(&mut [u32], Vec<f64>, Vec<f64>)> = vec![(idx, lo, hi)];
    for &axis in &axes {
        let mut next = Vec::with_capacity(parts.len() * 2);
        for (s, l, h) in parts {
            let mid = 0.5 * (l[axis] + h[axis]);
            let m = partition(ctx, s, axis, mid);
            let (a, b) = s.split_at_mut(m);
            let mut h1 = h.clone();
            h1[axis] = mid;
            let mut l2 = l.clone();
            l2[axis] = mid;
            next.push((a, l, h1));
            next.push((b, l2, h));
        }
        parts = next;
    }
    split_children(ctx, parts, offset, depth)
}

/// The node over `parts` (its children's vertices, in order, with their boxes), each child
/// split further, in parallel when the node is large.
fn split_children(
    ctx: &Ctx,
    parts: Vec<(&mut [u32], Vec<f64>, Vec<f64>)>,
    offset: u32,
    depth: u32,
) -> T {
    let len: usize = parts.iter().map(|p| p.0.len()).sum();
    let end = offset + len as u32;
    let mut jobs = Vec::with_capacity(parts.len());
    let mut off = offset;
    for (s, l, h) in parts {
        let n = s.len() as u32;
        if n > 0 {
            jobs.push((s, off, l, h));
        }
        off += n;
    }
    let children: Vec<T> = if len >= PAR_MIN {
        jobs.into_par_iter()
            .map(|(s, o, l, h)| split_rec(ctx, s, o, l, h, depth + 1))
            .collect()
    } else {
        jobs.into_iter()
            .map(|(s, o, l, h)| split_rec(ctx, s, o, l, h, depth + 1))
            .collect()
    };
    T::Inner(offset, end, children)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cell::CellKind;
    use crate::complex::{BuildOptions, ComplexBuilder};
    use crate::testkit::XorShift;

    /// Jittered grid points; cells of nearby ids (most in one leaf) and some of random ids
    /// (in several leaves), of `k + 1` vertices.
    fn complex(k: usize, n: u32, seed: u64) -> IndexedComplex {
        let mut r = XorShift::new(seed);
        let mut b = ComplexBuilder::new(3).unwrap();
        for i in 0..n {
            let j = |r: &mut XorShift| r.below(1000) as f64 / 4000.0;
            let p = [
                (i % 20) as f64 + j(&mut r),
                (i / 20 % 20) as f64 + j(&mut r),
                (i / 400) as f64 + j(&mut r),
            ];
            b.push_vertex(&p).unwrap();
        }
        for i in 0..n * 2 {
            let mut c: Vec<u32> = Vec::new();
            let local = r.below(10) != 0;
            let base = i % n;
            while c.len() < k + 1 {
                let v = if local {
                    (base + [0, 1, 20, 21, 400][r.below(5) as usize]) % n
                } else {
                    r.below(n as u64) as u32
                };
                if !c.contains(&v) {
                    c.push(v);
                }
            }
            b.push_cell(CellKind::simplex(k).unwrap(), &c).unwrap();
        }
        let opts = BuildOptions {
            drop_duplicates: true,
            drop_face_cells: true,
            ..Default::default()
        };
        b.build(&opts).unwrap().0
    }

    /// The parallel partition of a node makes the children of the serial passes: the same
    /// points in each (as sets: each leaf is sorted afterwards) and the same boxes, for the
    /// regular split (every axis) and the kD split (one), with points on the middles.
    #[test]
    fn parallel_partition_makes_the_serial_children() {
        let mut r = XorShift::new(7);
        let n_pts = 150_000u32; // more than one chunk
        let coords: Vec<f64> = (0..n_pts * 3)
            .map(|i| match r.below(8) {
                0 => 0.5, // on the middle of the unit box
                _ => r.below(1 << 20) as f64 / (1 << 20) as f64 + f64::from(i % 3 == 2),
            })
            .collect();
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(2)
            .build()
            .unwrap();
        for (regular, axes) in [(true, vec![0, 1, 2]), (false, vec![1]), (false, vec![2])] {
            let ctx = Ctx {
                coords: &coords,
                n: 3,
                kv: 10,
                regular,
                max_depth: 64,
            };
            let (lo, hi) = (vec![0.0, 0.0, 1.0], vec![1.0, 1.0, 2.0]);
            // a shuffled start, as a node deeper in the tree has
            let mut start: Vec<u32> = (0..n_pts).collect();
            for i in (1..start.len()).rev() {
                start.swap(i, r.below(i as u64 + 1) as usize);
            }
            let mut serial = start.clone();
            let mut parts = vec![(&mut serial[..], lo.clone(), hi.clone())];
            for &axis in &axes {
                let mut next = Vec::new();
                for (s, l, h) in parts {
                    let mid = 0.5 * (l[axis] + h[axis]);
                    let m = partition(&ctx, s, axis, mid);
                    let (a, b) = s.split_at_mut(m);
                    let (mut h1, mut l2) = (h.clone(), l.clone());
                    (h1[axis], l2[axis]) = (mid, mid);
                    next.push((a, l, h1));
                    next.push((b, l2, h));
                }
                parts = next;
            }
            let want: Vec<(Vec<u32>, Vec<f64>, Vec<f64>)> = parts
                .into_iter()
                .map(|(s, l, h)| {
                    let mut s = s.to_vec();
                    s.sort_unstable();
                    (s, l, h)
                })
                .collect();
            let mut par = start.clone();
            let got: Vec<(Vec<u32>, Vec<f64>, Vec<f64>)> = pool.install(|| {
                partition_par(&ctx, &mut par, &axes, lo.clone(), hi.clone())
                    .into_iter()
                    .map(|(s, l, h)| {
                        let mut s = s.to_vec();
                        s.sort_unstable();
                        (s, l, h)
                    })
                    .collect()
            });
            assert_eq!(got.len(), 1 << axes.len());
            assert!(
                want.iter().all(|w| !w.0.is_empty()),
                "every child has points"
            );
            assert_eq!(got, want, "axes {axes:?}");
        }
    }

    /// The one-kind path of the cell numbering gives what the general path gives: the same
    /// order, cells, and runs of leaf tuples.
    #[test]
    fn small_uniform_cells_are_numbered_as_by_the_general_path() {
        for (k, n, kv, seed) in [
            (1, 300, 8, 1),
            (2, 2000, 16, 2),
            (3, 3000, 40, 3),
            (2, 500, 1, 4),
        ] {
            let cx = complex(k, n, seed);
            assert_eq!(cx.blocks().len(), 1);
            let opts = StellarOptions {
                kv: Some(kv),
                ..Default::default()
            };
            let (ctx, _, _) = setup(&cx, &opts).unwrap();
            let d = decompose(&ctx, cx.n_vertices(), None);
            let n_leaves = d.leaf_vstart.len() - 1;
            assert!(n_leaves > 4, "k {k}: {n_leaves} leaves");
            let mut v2 = reindex_vertices(d.idx.clone(), &d.leaf_vstart);
            let slow = reindex_cells_general(&cx, &mut v2, n_leaves);
            // the one-kind path splits its counting sort by thread count: 1, 3 and 8 parts
            for threads in [1, 3, 8] {
                let pool = rayon::ThreadPoolBuilder::new()
                    .num_threads(threads)
                    .build()
                    .unwrap();
                let mut v1 = reindex_vertices(d.idx.clone(), &d.leaf_vstart);
                let fast = pool.install(|| reindex_cells(&cx, &mut v1, &d.leaf_vstart));
                check(&fast, &slow, k, n_leaves);
            }
        }
    }

    fn check(fast: &CellNumbering, slow: &CellNumbering, k: usize, n_leaves: usize) {
        assert_eq!(fast.c_orig, slow.c_orig, "k {k}");
        assert_eq!(fast.c_new, slow.c_new);
        assert_eq!(fast.cells.verts, slow.cells.verts);
        assert_eq!(fast.cells.uniform, slow.cells.uniform);
        assert_eq!(fast.cells.stride, slow.cells.stride);
        // the runs, in order (the fast path keeps one run list per job, not per leaf)
        let runs = |g: &[Groups]| -> Vec<(u32, Vec<u32>)> {
            g.iter()
                .flat_map(|g| g.iter().map(|(n, l)| (n, l.to_vec())))
                .collect()
        };
        let (a, b) = (runs(&fast.groups), runs(&slow.groups));
        assert!(
            a.len() > n_leaves,
            "k {k}: cells in several leaves are exercised"
        );
        assert_eq!(a, b, "k {k}");
    }
}
