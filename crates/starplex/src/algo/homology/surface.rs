//! The one-line summary of a surface component: orientable or not, genus, boundary loops.
//! A component is a surface when all its top cells are 2-cells (triangles, quads), every edge
//! is in one or two of them, and the link of every vertex is one path or one cycle.
use super::cells::{top_cell, Cell};
use crate::algo::manifold::{Convention, Manifoldness, OwnedStar, StarTester};
use crate::algo::orientation::orient_walk;
use crate::algo::unionfind::UnionFind;
use crate::ids::{CellId, VertexId};
use crate::topo::{TopCells, VertexStar};

/// Facts of one surface component, before the Euler characteristic is known.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct SurfaceFacts {
    pub is_surface: bool,
    pub orientable: bool,
    pub boundary_loops: u64,
}

/// Surface facts per component (`label[v]` = component of vertex v).
pub(crate) fn surface_facts<S: TopCells + VertexStar + ?Sized>(
    s: &S,
    label: &[u32],
    n_comp: usize,
) -> Vec<SurfaceFacts> {
    let mut facts = vec![
        SurfaceFacts {
            is_surface: true,
            orientable: true,
            boundary_loops: 0
        };
        n_comp
    ];
    let nv = s.n_vertices();
    // components with an isolated vertex or a top cell of dimension != 2 are not surfaces
    let mut has_cell = vec![false; n_comp];
    let mut verts = Vec::new();
    let mut edges: Vec<(u32, u32, u32, i8)> = Vec::new(); // (a, b, cell, sign)
    let mut buf: Vec<(Cell, i8)> = Vec::new();
    for c in 0..s.n_top_cells() {
        verts.clear();
        s.top_cell_vertices(CellId(c as u32), &mut verts);
        let comp = label[verts[0].0 as usize] as usize;
        has_cell[comp] = true;
        let kind = s.top_cell_kind(CellId(c as u32));
        if kind.dim() != 2 {
            facts[comp].is_surface = false;
            continue;
        }
        let g: Vec<u32> = verts.iter().map(|v| v.0).collect();
        let cell = top_cell(kind, &g);
        buf.clear();
        cell.facets(&mut buf);
        for (e, sg) in &buf {
            edges.push((e.key[0], e.key[1], c as u32, *sg));
        }
    }
    for (f, h) in facts.iter_mut().zip(&has_cell) {
        if !h {
            f.is_surface = false;
        }
    }
    edges.sort_unstable();
    // pairs of 2-cells sharing an edge, with the product of their induced signs: the
    // orientation is the shared walk of `algo::orientation`
    let mut pairs: Vec<(u32, u32, i8)> = Vec::new();
    let mut buf_uf = UnionFind::new(nv);
    let mut on_boundary = vec![false; nv];
    let mut i = 0;
    while i < edges.len() {
        let mut j = i;
        while j < edges.len() && (edges[j].0, edges[j].1) == (edges[i].0, edges[i].1) {
            j += 1;
        }
        let comp = label[edges[i].0 as usize] as usize;
        match j - i {
            1 => {
                buf_uf.union(edges[i].0, edges[i].1);
                on_boundary[edges[i].0 as usize] = true;
                on_boundary[edges[i].1 as usize] = true;
            }
            2 => {
                let (a, b) = (edges[i], edges[i + 1]);
                pairs.push((a.2, b.2, a.3 * b.3));
            }
            _ => facts[comp].is_surface = false,
        }
        i = j;
    }
    // a component is orientable when the walk's signs agree on every one of its pairs
    let nc = s.n_top_cells();
    let is2 = |c: u32| s.top_cell_kind(CellId(c)).dim() == 2;
    let walk = orient_walk(nc, is2, &pairs, |_| 1);
    for &(a, b, rel) in &pairs {
        if walk.signs[b as usize] != -walk.signs[a as usize] * rel {
            let mut vs = Vec::new();
            s.top_cell_vertices(CellId(a), &mut vs);
            facts[label[vs[0].0 as usize] as usize].orientable = false;
        }
    }
    // vertex links: one path or one cycle (the shared manifold test, local convention)
    let mut cells = Vec::new();
    let mut star = OwnedStar::default();
    let mut tester = StarTester::default();
    let mut edges_at = Vec::new();
    for v in 0..nv as u32 {
        let comp = label[v as usize] as usize;
        if !facts[comp].is_surface {
            continue;
        }
        s.vertex_top_cells(VertexId(v), &mut cells);
        star.clear();
        for &c in &cells {
            verts.clear();
            s.top_cell_vertices(c, &mut verts);
            let g: Vec<u32> = verts.iter().map(|x| x.0).collect();
            star.push(s.top_cell_kind(c), &g);
        }
        edges_at.clear();
        if tester.test_vertex(v, &star, Convention::Local, 2, &mut edges_at)
            != Manifoldness::Manifold
        {
            facts[comp].is_surface = false;
        }
    }
    // boundary loops
    let mut seen = vec![false; nv];
    for v in 0..nv as u32 {
        if on_boundary[v as usize] {
            let r = buf_uf.find(v) as usize;
            if !seen[r] {
                seen[r] = true;
                facts[label[v as usize] as usize].boundary_loops += 1;
            }
        }
    }
    facts
}
