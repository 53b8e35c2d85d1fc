//! The Stellar decomposition without coordinates (the paper's section 11, future work): the
//! vertices are split by connectivity alone, by recursive graph bisection. A block is ordered
//! by breadth-first search over the vertex graph of the top cells (two vertices are adjacent
//! when a top cell has both), restricted to the block, from a pseudo-peripheral vertex (George
//! and Liu's search: restart from a vertex of the last level while the eccentricity grows),
//! component after component; the first half of that order and the rest become the two
//! children, until a block has at most k_V vertices. Each half is a "ball" around its end of
//! the block, the graph counterpart of a kD tree's halves, so cells seldom span many leaves.
//!
//! The search reads a cell of at most [`SMALL`] vertices as its other vertices, stored with
//! each vertex (a graph's edges are then a plain adjacency list: no cell is looked up), and a
//! larger cell through the vertex–top-cell incidence, once per search (a clique of s vertices
//! is read once, not s² times). A child block's search starts from the end of the parent's
//! search that lies in it (its first or its last vertex), so only the root looks for a
//! pseudo-peripheral vertex of its components. Every search is deterministic: the order
//! depends on the complex alone, not on the number of threads.
//!
//! ```
//! use starplex::complex::{ComplexBuilder, BuildOptions};
//! use starplex::cell::CellKind;
//! use starplex::stellar::{Decomposition, StellarOptions, StellarTree};
//! // a path of 8 edges on vertices numbered out of order along it: x = 0, 1, ..., 8 is
//! // vertex 0, 5, 1, 6, 2, 7, 3, 8, 4 (all on one line: no geometry is used)
//! let along = [0u32, 5, 1, 6, 2, 7, 3, 8, 4];
//! let mut b = ComplexBuilder::new(1).unwrap();
//! for _ in 0..9 { b.push_vertex(&[0.0]).unwrap(); }
//! for w in along.windows(2) { b.push_cell(CellKind::Simplex(1), w).unwrap(); }
//! let k = b.build(&BuildOptions::default()).unwrap().0;
//! let o = StellarOptions { kv: Some(3), decomposition: Decomposition::Graph, ..Default::default() };
//! let t = StellarTree::build(&k, &o).unwrap();
//! // every leaf is a run of the path: no edge spans more than two leaves
//! assert!(t.stats().chi <= 1.5);
//! assert_eq!(t.decomposition(), Decomposition::Graph);
//! ```
use super::build::{InputCells, T};
use crate::csr::Csr;

/// At most this many searches to find a pseudo-peripheral vertex of a component.
const PERIPHERAL_TRIES: usize = 4;

/// Cells of at most this many vertices are stored as each vertex's co-vertices.
const SMALL: usize = 3;

/// Scratch of the searches: stamps instead of cleared flags.
struct Walk<'a> {
    /// Vertex -> the other vertices of its small top cells (sorted, without repeats).
    near: Csr,
    /// Vertex -> its top cells of more than [`SMALL`] vertices.
    vt: Csr,
    /// The top cells' vertices.
    cells: &'a InputCells<'a>,
    /// Vertex -> the stamp of the block it is in.
    block: Vec<u32>,
    /// Vertex -> the stamp of the last search that reached it.
    seen: Vec<u32>,
    /// Cell -> the stamp of the last search that read it.
    cell_seen: Vec<u32>,
    /// Vertex -> the stamp of the block ordering that placed it.
    placed: Vec<u32>,
    stamp: u32,
    kv: usize,
    max_depth: u32,
}

impl Walk<'_> {
    fn next_stamp(&mut self) -> u32 {
        self.stamp += 1;
        self.stamp
    }

    /// Breadth-first search from `r` inside block `b`, appending the vertices reached to
    /// `out`; returns the start of the last level in `out` and the number of levels.
    fn bfs(&mut self, r: u32, b: u32, out: &mut Vec<u32>) -> (usize, usize) {
        let s = self.next_stamp();
        let base = out.len();
        self.seen[r as usize] = s;
        out.push(r);
        let (mut head, mut level_end, mut last_level, mut levels) = (base, base + 1, base, 1);
        while head < out.len() {
            if head == level_end {
                last_level = head;
                level_end = out.len();
                levels += 1;
            }
            let v = out[head];
            head += 1;
            for &u in self.near.row(v as usize) {
                let ui = u as usize;
                if self.block[ui] == b && self.seen[ui] != s {
                    self.seen[ui] = s;
                    out.push(u);
                }
            }
            for &c in self.vt.row(v as usize) {
                if self.cell_seen[c as usize] == s {
                    continue;
                }
                self.cell_seen[c as usize] = s;
                for &u in self.cells.get(c).1 {
                    let ui = u as usize;
                    if self.block[ui] == b && self.seen[ui] != s {
                        self.seen[ui] = s;
                        out.push(u);
                    }
                }
            }
        }
        (last_level, levels)
    }

    /// A pseudo-peripheral vertex of `r`'s component inside block `b`.
    fn peripheral(&mut self, mut r: u32, b: u32, scratch: &mut Vec<u32>) -> u32 {
        let mut ecc = 0usize;
        for _ in 0..PERIPHERAL_TRIES {
            scratch.clear();
            let (last, levels) = self.bfs(r, b, scratch);
            if levels <= ecc || scratch.len() == 1 {
                break;
            }
            ecc = levels;
            // the vertex of the last level in the fewest top cells (then the smallest id)
            let x = scratch[last..]
                .iter()
                .copied()
                .min_by_key(|&u| (self.near.degree(u as usize) + self.vt.degree(u as usize), u))
                .unwrap_or(r);
            if x == r {
                break;
            }
            r = x;
        }
        r
    }

    /// Orders `idx` (a block) component by component and splits it in two halves, recursively.
    /// `start`, when given, is a vertex of the block at an end of its graph (the parent's
    /// search reached it first or last): its component is searched from it without a search
    /// for a peripheral vertex.
    fn split(&mut self, idx: &mut [u32], offset: u32, depth: u32, start: Option<u32>) -> T {
        let len = idx.len();
        let end = offset + len as u32;
        if len <= self.kv || depth >= self.max_depth {
            return T::Leaf(offset, end);
        }
        // a block uses at most 1 + (PERIPHERAL_TRIES + 1) stamps per vertex: start afresh
        // before they could wrap (no block is being ordered here)
        if self.stamp as u64 + (PERIPHERAL_TRIES as u64 + 2) * len as u64 >= u32::MAX as u64 {
            for a in [
                &mut self.block,
                &mut self.seen,
                &mut self.cell_seen,
                &mut self.placed,
            ] {
                a.iter_mut().for_each(|x| *x = 0);
            }
            self.stamp = 0;
        }
        let b = self.next_stamp();
        for &v in idx.iter() {
            self.block[v as usize] = b;
        }
        let mut order = Vec::with_capacity(len);
        let mut scratch = Vec::new();
        for v in start.into_iter().chain(idx.iter().copied()) {
            if self.placed[v as usize] == b {
                continue;
            }
            let r = if Some(v) == start {
                v
            } else {
                self.peripheral(v, b, &mut scratch)
            };
            let from = order.len();
            self.bfs(r, b, &mut order);
            for &u in &order[from..] {
                self.placed[u as usize] = b;
            }
        }
        debug_assert_eq!(order.len(), len);
        idx.copy_from_slice(&order);
        drop((order, scratch));
        let half = len / 2;
        let (a, c) = idx.split_at_mut(half);
        let (first, last) = (a[0], c[c.len() - 1]);
        let left = self.split(a, offset, depth + 1, Some(first));
        let right = self.split(c, offset + half as u32, depth + 1, Some(last));
        T::Inner(offset, end, vec![left, right])
    }
}

/// Splits the vertices by connectivity: `idx` (the input vertex ids, in any order) is
/// reordered so that every leaf of the returned tree owns a contiguous range of it.
pub(super) fn graph_split(cells: &InputCells<'_>, idx: &mut [u32], kv: usize, max_depth: u32) -> T {
    let nv = idx.len();
    if kv == 0 || nv <= kv {
        return T::Leaf(0, nv as u32);
    }
    let nc = cells.len();
    let vt = Csr::from_fn(nv, |push| {
        for c in 0..nc as u32 {
            let vs = cells.get(c).1;
            if vs.len() > SMALL {
                for &v in vs {
                    push(v, c);
                }
            }
        }
    });
    let mut near = Csr::from_fn(nv, |push| {
        for c in 0..nc as u32 {
            let vs = cells.get(c).1;
            if vs.len() <= SMALL {
                for &v in vs {
                    for &u in vs {
                        if u != v {
                            push(v, u);
                        }
                    }
                }
            }
        }
    });
    near.sort_dedup_rows();
    let mut w = Walk {
        near,
        vt,
        cells,
        block: vec![0; nv],
        seen: vec![0; nv],
        cell_seen: vec![0; nc],
        placed: vec![0; nv],
        stamp: 0,
        kv,
        max_depth,
    };
    w.split(idx, 0, 0, None)
}
