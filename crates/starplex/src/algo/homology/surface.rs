//! The one-line summary of a surface component: orientable or not, genus, boundary loops.
//! A component is a surface when all its top cells are 2-cells (triangles, quads), every edge
//! is in one or two of them, and the link of every vertex is one path or one cycle.
use super::cells::{top_cell, Cell};
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

struct ParityUf {
    parent: Vec<u32>,
    parity: Vec<u8>,
}

impl ParityUf {
    fn find(&mut self, x: u32) -> (u32, u8) {
        let mut root = x;
        let mut par = 0u8;
        while self.parent[root as usize] != root {
            par ^= self.parity[root as usize];
            root = self.parent[root as usize];
        }
        // path compression: every node on the way points at the root with its own parity
        let mut cur = x;
        let mut acc = 0u8;
        while cur != root {
            let next = self.parent[cur as usize];
            let pc = self.parity[cur as usize];
            self.parent[cur as usize] = root;
            self.parity[cur as usize] = par ^ acc;
            acc ^= pc;
            cur = next;
        }
        (root, par)
    }
    /// Requires parity(a) ^ parity(b) == p; false on a contradiction.
    fn union(&mut self, a: u32, b: u32, p: u8) -> bool {
        let (ra, pa) = self.find(a);
        let (rb, pb) = self.find(b);
        if ra == rb {
            return pa ^ pb == p;
        }
        self.parent[ra as usize] = rb;
        self.parity[ra as usize] = pa ^ pb ^ p;
        true
    }
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
    let mut puf = ParityUf {
        parent: (0..s.n_top_cells() as u32).collect(),
        parity: vec![0; s.n_top_cells()],
    };
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
                let p = u8::from(a.3 == b.3);
                if !puf.union(a.2, b.2, p) {
                    facts[comp].orientable = false;
                }
            }
            _ => facts[comp].is_surface = false,
        }
        i = j;
    }
    // vertex links: one path or one cycle
    let mut cells = Vec::new();
    let mut nb: Vec<(u32, u32)> = Vec::new();
    for v in 0..nv as u32 {
        let comp = label[v as usize] as usize;
        if !facts[comp].is_surface {
            continue;
        }
        s.vertex_top_cells(VertexId(v), &mut cells);
        nb.clear();
        for &c in &cells {
            verts.clear();
            s.top_cell_vertices(c, &mut verts);
            let kind = s.top_cell_kind(c);
            let g: Vec<u32> = verts.iter().map(|x| x.0).collect();
            buf.clear();
            top_cell(kind, &g).facets(&mut buf);
            let ends: Vec<u32> = buf
                .iter()
                .filter(|(e, _)| e.key.contains(&v))
                .map(|(e, _)| if e.key[0] == v { e.key[1] } else { e.key[0] })
                .collect();
            if ends.len() == 2 {
                nb.push((ends[0], ends[1]));
            }
        }
        // connectivity of the link graph
        let mut ids: Vec<u32> = nb.iter().flat_map(|&(a, b)| [a, b]).collect();
        ids.sort_unstable();
        ids.dedup();
        let mut uf = UnionFind::new(ids.len());
        for &(a, b) in &nb {
            let (ia, ib) = (
                ids.binary_search(&a).unwrap_or(0) as u32,
                ids.binary_search(&b).unwrap_or(0) as u32,
            );
            uf.union(ia, ib);
        }
        if uf.n_sets() > 1 {
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
