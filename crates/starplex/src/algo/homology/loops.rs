//! Short H_1 generators as closed edge paths, for complexes whose edges each lie in at most
//! two 2-cells (surfaces with or without boundary, orientable or not, graphs, and surfaces
//! with dangling edges or isolated pieces): the tree–cotree construction with the greedy
//! choice of Erickson and Whittlesey ("Greedy optimal homotopy and homology generators",
//! SODA 2005).
//!
//! 1. A shortest-path forest `T` (Dijkstra from the smallest vertex of every component, edge
//!    lengths from the coordinates, else one per edge). Every edge `e = ab` outside `T` closes
//!    the loop `σ(e)` = path(a) + e + path(b) (the common part of the two tree paths cancels).
//! 2. The loops `σ(e)` span the cycles, and H_1 is their span modulo the boundaries of the
//!    2-cells. Projected on the non-tree edges, the boundary of a 2-cell touches each edge in
//!    at most one place, and an edge lies in at most two 2-cells, so the relations are the
//!    incidences of the dual graph (a boundary edge joined to one extra node). Kruskal over
//!    the non-tree edges, *longest loop first*, keeps a spanning forest of that graph (the
//!    cotree); the edges it leaves are exactly the pivots left over by a column reduction with
//!    the longest edges as pivots, i.e. the greedy basis: the loops taken, shortest first, are
//!    independent in homology and as many as β_1.
//!
//! Over Z/p (p odd) the incidences carry signs; they are a graph's only when the 2-cells can
//! be oriented coherently, so a non-orientable input over Z/p returns `None` (the caller keeps
//! the Morse generators), as does any edge in three or more 2-cells or any cell above
//! dimension 2.
use std::cmp::Ordering;
use std::collections::BinaryHeap;

use super::Generator;
use crate::algo::unionfind::UnionFind;
use crate::cell::CellKind;
use crate::ids::{CellId, VertexId};
use crate::topo::TopCells;

const NONE: u32 = u32::MAX;

/// An edge `a < b` and the (at most two) 2-cells around it, with the sign in which each
/// crosses it (+1 when the cell's boundary runs from `a` to `b`).
struct Edge {
    a: u32,
    b: u32,
    faces: [(u32, i8); 2],
    n_faces: u8,
}

/// Dijkstra's priority: the smallest distance first, ties by vertex id.
#[derive(PartialEq)]
struct Entry(f64, u32);

impl Eq for Entry {}

impl PartialOrd for Entry {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}

impl Ord for Entry {
    fn cmp(&self, o: &Self) -> Ordering {
        o.0.total_cmp(&self.0).then(o.1.cmp(&self.1))
    }
}

/// The H_1 loops of `s` over Z/`m` (`m` = 2 or an odd prime), one per class, shortest first,
/// each edge listed along the loop with coefficient 1 (over Z/2) or ±1 as the loop runs along
/// or against its sorted orientation. `length(a, b)` is the length of edge `ab` (a finite,
/// non-negative number; anything else makes every edge length 1). `None` when the
/// construction does not apply (see the module) or does not find `betti1` loops.
pub(crate) fn short_loops<S: TopCells + ?Sized>(
    s: &S,
    m: i64,
    betti1: u64,
    length: &dyn Fn(u32, u32) -> f64,
) -> Option<Vec<Generator>> {
    let nv = s.n_vertices();
    // the edges of the 2-cells (in boundary order) and the top edges
    let mut inc: Vec<(u32, u32, u32, i8)> = Vec::new();
    let mut verts = Vec::new();
    let mut n_faces = 0u32;
    for c in 0..s.n_top_cells() {
        let kind = s.top_cell_kind(CellId(c as u32));
        verts.clear();
        s.top_cell_vertices(CellId(c as u32), &mut verts);
        let cyc: &[VertexId] = match kind {
            CellKind::Simplex(0) => continue,
            CellKind::Simplex(1) => {
                let (a, b) = (verts[0].0, verts[1].0);
                inc.push((a.min(b), a.max(b), NONE, 0));
                continue;
            }
            CellKind::Simplex(2) | CellKind::Quad => &verts,
            _ => return None,
        };
        let f = n_faces;
        n_faces += 1;
        for i in 0..cyc.len() {
            let (a, b) = (cyc[i].0, cyc[(i + 1) % cyc.len()].0);
            inc.push((a.min(b), a.max(b), f, if a < b { 1 } else { -1 }));
        }
    }
    inc.sort_unstable();
    let mut edges: Vec<Edge> = Vec::new();
    for (a, b, f, sg) in inc {
        match edges.last_mut() {
            Some(e) if (e.a, e.b) == (a, b) => {
                if f == NONE {
                    continue;
                }
                if e.n_faces == 2 {
                    return None;
                }
                e.faces[e.n_faces as usize] = (f, sg);
                e.n_faces += 1;
            }
            _ => edges.push(Edge {
                a,
                b,
                faces: [(f, sg), (NONE, 0)],
                n_faces: u8::from(f != NONE),
            }),
        }
    }
    if m != 2 && !orientable(n_faces as usize, &edges) {
        return None;
    }
    // lengths, and the vertex -> edges relation
    let mut w: Vec<f64> = edges.iter().map(|e| length(e.a, e.b)).collect();
    if w.iter().any(|x| !x.is_finite() || *x < 0.0) {
        w.iter_mut().for_each(|x| *x = 1.0);
    }
    let mut start = vec![0u32; nv + 1];
    for e in &edges {
        start[e.a as usize + 1] += 1;
        start[e.b as usize + 1] += 1;
    }
    for i in 0..nv {
        start[i + 1] += start[i];
    }
    let mut fill = start.clone();
    let mut adj = vec![0u32; 2 * edges.len()];
    for (i, e) in edges.iter().enumerate() {
        for v in [e.a, e.b] {
            adj[fill[v as usize] as usize] = i as u32;
            fill[v as usize] += 1;
        }
    }
    drop(fill);
    // the shortest-path forest
    let mut dist = vec![f64::INFINITY; nv];
    let mut parent = vec![NONE; nv]; // the tree edge towards the root
    let mut depth = vec![0u32; nv];
    let mut done = vec![false; nv];
    let mut heap = BinaryHeap::new();
    for root in 0..nv {
        if done[root] {
            continue;
        }
        dist[root] = 0.0;
        heap.push(Entry(0.0, root as u32));
        while let Some(Entry(d, v)) = heap.pop() {
            if done[v as usize] {
                continue;
            }
            done[v as usize] = true;
            for &ei in &adj[start[v as usize] as usize..start[v as usize + 1] as usize] {
                let e = &edges[ei as usize];
                let u = if e.a == v { e.b } else { e.a };
                let du = d + w[ei as usize];
                if !done[u as usize] && du < dist[u as usize] {
                    dist[u as usize] = du;
                    parent[u as usize] = ei;
                    depth[u as usize] = depth[v as usize] + 1;
                    heap.push(Entry(du, u));
                }
            }
        }
    }
    let mut in_tree = vec![false; edges.len()];
    for &p in &parent {
        if p != NONE {
            in_tree[p as usize] = true;
        }
    }
    // the cotree: Kruskal over the dual graph, longest loop first
    let mut order: Vec<u32> = (0..edges.len() as u32)
        .filter(|&i| !in_tree[i as usize])
        .collect();
    let loop_len = |i: u32| {
        let e = &edges[i as usize];
        dist[e.a as usize] + dist[e.b as usize] + w[i as usize]
    };
    order.sort_unstable_by(|&x, &y| loop_len(y).total_cmp(&loop_len(x)).then(x.cmp(&y)));
    let outer = n_faces;
    let mut uf = UnionFind::new(n_faces as usize + 1);
    let mut chosen: Vec<u32> = Vec::new();
    for &i in &order {
        let e = &edges[i as usize];
        let joined = match e.n_faces {
            0 => false,
            1 => uf.union(e.faces[0].0, outer),
            _ => uf.union(e.faces[0].0, e.faces[1].0),
        };
        if !joined {
            chosen.push(i);
        }
    }
    if chosen.len() as u64 != betti1 {
        debug_assert!(false, "{} loops for betti_1 = {betti1}", chosen.len());
        return None;
    }
    chosen.reverse(); // shortest first
    let other = |ei: u32, v: u32| {
        let e = &edges[ei as usize];
        if e.a == v {
            e.b
        } else {
            e.a
        }
    };
    let mut out = Vec::with_capacity(chosen.len());
    for i in chosen {
        let e = &edges[i as usize];
        // climb from both ends to the common ancestor
        let (mut x, mut y) = (e.a, e.b);
        let (mut up_a, mut up_b) = (vec![e.a], vec![e.b]);
        while x != y {
            if depth[x as usize] >= depth[y as usize] {
                x = other(parent[x as usize], x);
                up_a.push(x);
            } else {
                y = other(parent[y as usize], y);
                up_b.push(y);
            }
        }
        // the loop: a -> ... -> ancestor -> ... -> b -> a
        up_b.pop();
        up_a.extend(up_b.into_iter().rev());
        let n = up_a.len();
        let cells = (0..n)
            .map(|j| {
                let (p, q) = (up_a[j], up_a[(j + 1) % n]);
                let c = if p < q || m == 2 { 1 } else { m - 1 };
                (vec![p.min(q), p.max(q)], c)
            })
            .collect();
        out.push(Generator { dim: 1, cells });
    }
    Some(out)
}

/// Whether the 2-cells can be oriented so that every edge between two of them is crossed in
/// opposite directions (a breadth-first walk over the dual graph).
fn orientable(n_faces: usize, edges: &[Edge]) -> bool {
    let mut nb: Vec<Vec<(u32, bool)>> = vec![Vec::new(); n_faces];
    for e in edges.iter().filter(|e| e.n_faces == 2) {
        let ((f, s), (g, t)) = (e.faces[0], e.faces[1]);
        // same crossing direction: the two cells need opposite orientations
        nb[f as usize].push((g, s == t));
        nb[g as usize].push((f, s == t));
    }
    let mut sign: Vec<Option<bool>> = vec![None; n_faces];
    let mut queue = std::collections::VecDeque::new();
    for root in 0..n_faces {
        if sign[root].is_some() {
            continue;
        }
        sign[root] = Some(false);
        queue.push_back(root as u32);
        while let Some(f) = queue.pop_front() {
            let sf = sign[f as usize].unwrap_or(false);
            for &(g, flip) in &nb[f as usize] {
                let want = sf ^ flip;
                match sign[g as usize] {
                    None => {
                        sign[g as usize] = Some(want);
                        queue.push_back(g);
                    }
                    Some(x) if x != want => return false,
                    _ => {}
                }
            }
        }
    }
    true
}
