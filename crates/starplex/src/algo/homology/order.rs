//! The vertex order that drives the lower-star matching. Input numberings are often far from
//! a good Morse function (a subdivided mesh numbers its old vertices first, so every one of
//! them is a local minimum), which leaves many critical cells. When the input order has many
//! local minima the vertices are renumbered in breadth-first order (from the smallest vertex of
//! each component), where only the roots are local minima; the algorithm then runs on a
//! relabeled view and maps its answers back.
use std::collections::VecDeque;

use rayon::prelude::*;

use crate::cell::CellKind;
use crate::ids::{CellId, VertexId};
use crate::topo::{TopCells, VertexStar};

/// Vertices with no neighbour of smaller id (local minima of the input order).
pub(crate) fn local_minima<S: TopCells + VertexStar + Sync + ?Sized>(s: &S) -> usize {
    (0..s.n_vertices() as u32)
        .into_par_iter()
        .with_min_len(4096)
        .map_init(
            || (Vec::new(), Vec::new()),
            |(cells, verts), v| {
                s.vertex_top_cells(VertexId(v), cells);
                for &c in cells.iter() {
                    verts.clear();
                    s.top_cell_vertices(c, verts);
                    if verts.iter().any(|x| x.0 < v) {
                        return 0usize;
                    }
                }
                1
            },
        )
        .sum()
}

/// Appends the edge neighbours of `v` in top cell `c` (all other vertices for a simplex).
fn neighbours(kind: CellKind, verts: &[VertexId], v: VertexId, out: &mut Vec<u32>) {
    match kind.cp_faces(1) {
        None => out.extend(verts.iter().filter(|&&x| x != v).map(|x| x.0)),
        Some(edges) => {
            for e in edges {
                let (a, b) = (verts[e[0] as usize], verts[e[1] as usize]);
                if a == v {
                    out.push(b.0);
                } else if b == v {
                    out.push(a.0);
                }
            }
        }
    }
}

/// Breadth-first numbering: `to_new[old]`.
pub(crate) fn bfs_order<S: TopCells + VertexStar + ?Sized>(s: &S) -> Vec<u32> {
    let n = s.n_vertices();
    let mut to_new = vec![u32::MAX; n];
    let mut next = 0u32;
    let mut q = VecDeque::new();
    let (mut cells, mut verts, mut nb) = (Vec::new(), Vec::new(), Vec::new());
    for root in 0..n {
        if to_new[root] != u32::MAX {
            continue;
        }
        to_new[root] = next;
        next += 1;
        q.push_back(root as u32);
        while let Some(v) = q.pop_front() {
            s.vertex_top_cells(VertexId(v), &mut cells);
            nb.clear();
            for &c in &cells {
                verts.clear();
                s.top_cell_vertices(c, &mut verts);
                neighbours(s.top_cell_kind(c), &verts, VertexId(v), &mut nb);
            }
            // new neighbours in the order met (marked as numbered when met: no sort needed)
            for &w in &nb {
                if to_new[w as usize] == u32::MAX {
                    to_new[w as usize] = next;
                    next += 1;
                    q.push_back(w);
                }
            }
        }
    }
    to_new
}

/// A structure seen through a vertex renumbering.
pub(crate) struct Relabeled<'a, S: ?Sized> {
    pub s: &'a S,
    pub to_new: Vec<u32>,
    pub to_old: Vec<u32>,
}

impl<'a, S: ?Sized> Relabeled<'a, S> {
    pub fn new(s: &'a S, to_new: Vec<u32>) -> Self {
        let mut to_old = vec![0u32; to_new.len()];
        for (old, &new) in to_new.iter().enumerate() {
            to_old[new as usize] = old as u32;
        }
        Relabeled { s, to_new, to_old }
    }
}

impl<S: TopCells + ?Sized> TopCells for Relabeled<'_, S> {
    fn n_vertices(&self) -> usize {
        self.s.n_vertices()
    }
    fn n_top_cells(&self) -> usize {
        self.s.n_top_cells()
    }
    fn top_cell_kind(&self, c: CellId) -> CellKind {
        self.s.top_cell_kind(c)
    }
    fn top_cell_vertices(&self, c: CellId, out: &mut Vec<VertexId>) {
        let start = out.len();
        self.s.top_cell_vertices(c, out);
        for v in &mut out[start..] {
            *v = VertexId(self.to_new[v.0 as usize]);
        }
    }
}

impl<S: VertexStar + ?Sized> VertexStar for Relabeled<'_, S> {
    fn vertex_top_cells(&self, v: VertexId, out: &mut Vec<CellId>) {
        self.s
            .vertex_top_cells(VertexId(self.to_old[v.0 as usize]), out);
    }
}

/// Numbering by first appearance in the top cells (a streaming pass): in a mesh whose cells
/// are listed coherently, a vertex first seen in a cell with older vertices is not a local
/// minimum. `to_new[old]`; isolated vertices come last.
pub(crate) fn first_appearance_order<S: TopCells + ?Sized>(s: &S) -> Vec<u32> {
    let n = s.n_vertices();
    let mut to_new = vec![u32::MAX; n];
    let mut next = 0u32;
    let mut verts = Vec::new();
    for c in 0..s.n_top_cells() {
        verts.clear();
        s.top_cell_vertices(CellId(c as u32), &mut verts);
        for v in &verts {
            if to_new[v.0 as usize] == u32::MAX {
                to_new[v.0 as usize] = next;
                next += 1;
            }
        }
    }
    for x in &mut to_new {
        if *x == u32::MAX {
            *x = next;
            next += 1;
        }
    }
    to_new
}
