//! The vertex order that drives the lower-star matching. Input numberings are often far from
//! a good Morse function (a subdivided mesh numbers its old vertices first, so every one of
//! them is a local minimum), which leaves many critical cells. When the input order has many
//! local minima the vertices are renumbered (first appearance in the cells, else breadth-first,
//! where only the roots are local minima), the top cells are materialised once in the new
//! numbering ([`Flat`]), the algorithm runs on that and its answers are mapped back.
use std::collections::VecDeque;

use rayon::prelude::*;

use crate::cell::CellKind;
use crate::ids::{CellId, VertexId};
use crate::topo::{TopCells, VertexStar};

/// The cells of an indexed complex as vertex slices, in cell id order (the kind's vertex
/// order: what [`TopCells::top_cell_vertices`] gives, without the copies).
pub(crate) fn complex_cells(
    k: &crate::complex::IndexedComplex,
) -> impl Iterator<Item = &[u32]> + '_ {
    k.blocks()
        .iter()
        .flat_map(|b| b.vertices.chunks_exact(b.kind.n_vertices()))
}

/// [`count_minima`] of the cells given as vertex slices (the same count).
pub(crate) fn count_minima_slices<'a>(
    n: usize,
    cells: impl Iterator<Item = &'a [u32]>,
    to_new: Option<&[u32]>,
) -> usize {
    let mut not_min = vec![false; n];
    let mut mark = |c: &[u32], key: &dyn Fn(u32) -> u32| {
        let Some(mn) = c.iter().map(|&x| key(x)).min() else {
            return;
        };
        for &x in c {
            if key(x) != mn {
                not_min[x as usize] = true;
            }
        }
    };
    match to_new {
        None => cells.for_each(|c| mark(c, &|x| x)),
        Some(t) => cells.for_each(|c| mark(c, &|x| t[x as usize])),
    }
    not_min.iter().filter(|&&b| !b).count()
}

/// [`first_appearance_order`] of the cells given as vertex slices (the same numbering).
pub(crate) fn first_appearance_slices<'a>(
    n: usize,
    cells: impl Iterator<Item = &'a [u32]>,
) -> Vec<u32> {
    let mut to_new = vec![u32::MAX; n];
    let mut next = 0u32;
    for c in cells {
        for &v in c {
            if to_new[v as usize] == u32::MAX {
                to_new[v as usize] = next;
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

/// [`bfs_order`] of a [`Flat`] (the same numbering), reading its slices directly when its
/// cells are all of one kind (simplices, quads, hexahedra, ...).
pub(crate) fn bfs_order_flat(f: &Flat) -> Vec<u32> {
    if f.uniform.is_none() || f.arity == 0 {
        return bfs_order(f);
    }
    let (verts, vt, a) = (&f.verts[..], &f.vt, f.arity);
    let n = f.n_vertices;
    let mut to_new = vec![u32::MAX; n];
    let mut next = 0u32;
    // the queue is the numbering itself: vertices are dequeued in the order they are numbered
    let mut order: Vec<u32> = Vec::with_capacity(n);
    // a cell met again holds only numbered vertices: each cell is read once (the same
    // numbering, a third of the reads on triangles)
    let mut seen = fixedbitset::FixedBitSet::with_capacity(f.n_cells);
    for root in 0..n {
        if to_new[root] != u32::MAX {
            continue;
        }
        to_new[root] = next;
        next += 1;
        order.push(root as u32);
        let mut head = order.len() - 1;
        while head < order.len() {
            // the queue is known a few steps ahead: its rows and cells are fetched early
            if let Some(&u) = order.get(head + 8) {
                crate::buf::prefetch(&vt.offsets, u as usize);
            }
            if let Some(&u) = order.get(head + 4) {
                let o = &vt.offsets;
                crate::buf::prefetch(&vt.targets, o[u as usize] as usize);
            }
            if let Some(&u) = order.get(head + 2) {
                for &c in vt.row(u as usize) {
                    crate::buf::prefetch(verts, c as usize * a);
                }
            }
            let v = order[head];
            head += 1;
            for &c in vt.row(v as usize) {
                if seen.put(c as usize) {
                    continue;
                }
                for &w in &verts[c as usize * a..(c as usize + 1) * a] {
                    // every other vertex of the cell is a neighbour (across a quad or a
                    // hexahedron too, as in `bfs_order`), met in the stored order
                    if w != v && to_new[w as usize] == u32::MAX {
                        to_new[w as usize] = next;
                        next += 1;
                        order.push(w);
                    }
                }
            }
        }
    }
    to_new
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
                // every other vertex of the cell, also across a quad or a hexahedron: the
                // breadth-first ball then grows by whole cells (numbering the edge
                // neighbours only left 15x more critical cells on quads made from triangles)
                nb.extend(verts.iter().filter(|&&x| x != VertexId(v)).map(|x| x.0));
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

/// Local minima of the order `to_new` (the input order when `None`): vertices with no
/// incident top cell holding a vertex that comes earlier. One streaming pass over the top
/// cells (a vertex is not a minimum as soon as a cell holds it and an earlier vertex); no
/// vertex → cells relation is read.
pub(crate) fn count_minima<S: TopCells + ?Sized>(s: &S, to_new: Option<&[u32]>) -> usize {
    let n = s.n_vertices();
    let mut not_min = vec![false; n];
    let mut verts = Vec::new();
    let key = |x: u32| to_new.map_or(x, |t| t[x as usize]);
    for c in 0..s.n_top_cells() {
        verts.clear();
        s.top_cell_vertices(CellId(c as u32), &mut verts);
        let Some(mn) = verts.iter().map(|x| key(x.0)).min() else {
            continue;
        };
        for x in &verts {
            if key(x.0) != mn {
                not_min[x.0 as usize] = true;
            }
        }
    }
    not_min.iter().filter(|&&b| !b).count()
}

/// The top cells materialised in a new vertex numbering: vertices renumbered (a simplex lists
/// its vertices sorted; a CP cell keeps its kind's order), cells renumbered by their smallest
/// new vertex (a counting sort: the cells around consecutive vertices lie close in memory),
/// and the vertex → cells relation in the new numbering. Built once, instead of mapping every
/// vertex read through a relabeled view and looking every cell up in its block.
pub(crate) struct Flat {
    n_vertices: usize,
    n_cells: usize,
    /// The kind of every cell when they share one.
    uniform: Option<CellKind>,
    /// Per-cell kinds otherwise.
    kinds: Vec<CellKind>,
    /// Vertices per cell when uniform.
    arity: usize,
    /// Cell `c` is `verts[starts[c]..starts[c + 1]]` when not uniform.
    starts: Vec<u32>,
    verts: Vec<u32>,
    vt: crate::csr::Csr,
}

/// Cells per task of the parallel per-cell loops.
const PAR_CELLS: usize = 4096;

/// The vertices of a simplex sorted in place (networks for triangles and tetrahedra).
#[inline]
fn sort_simplex(c: &mut [u32]) {
    match c.len() {
        3 => c.copy_from_slice(&crate::topo::sort3([c[0], c[1], c[2]])),
        4 => c.copy_from_slice(&crate::topo::sort4([c[0], c[1], c[2], c[3]])),
        _ => c.sort_unstable(),
    }
}

/// Renumbers flat cells of `arity` vertices in place (`to_new[old]`), sorting each when they
/// are simplices; in parallel.
fn renumber(verts: &mut [u32], arity: usize, simplices: bool, to_new: &[u32]) {
    verts.par_chunks_mut(arity * PAR_CELLS).for_each(|p| {
        for c in p.chunks_exact_mut(arity) {
            for v in c.iter_mut() {
                *v = to_new[*v as usize];
            }
            if simplices {
                sort_simplex(c);
            }
        }
    });
}

/// The cells of arity `A` (flat) copied into `out` at the slots of a stable counting sort on
/// their smallest vertex; `count[v]`: the first slot of the cells whose smallest vertex is `v`.
fn place<const A: usize>(verts: &[u32], count: &mut [u32], out: &mut [u32]) {
    for c in verts.chunks_exact(A) {
        let c: [u32; A] = c.try_into().unwrap_or([0; A]);
        let mn = c.iter().copied().min().unwrap_or(0) as usize;
        let d = count[mn] as usize;
        count[mn] += 1;
        if let Some(o) = out.get_mut(d * A..(d + 1) * A) {
            o.copy_from_slice(&c);
        }
    }
}

/// [`place`] for any arity.
fn place_any(verts: &[u32], arity: usize, count: &mut [u32], out: &mut [u32]) {
    for c in verts.chunks_exact(arity) {
        let mn = c.iter().copied().min().unwrap_or(0) as usize;
        let d = count[mn] as usize;
        count[mn] += 1;
        out[d * arity..(d + 1) * arity].copy_from_slice(c);
    }
}

/// Places flat cells of `arity` vertices by a stable counting sort on their smallest vertex,
/// out of place (a cycle-by-cycle permutation in place chases one cache miss after another):
/// `count` (n_vertices + 1 entries, any content) and `out` (as long as `verts`, any content)
/// are work buffers; returns the placed cells, in `out`'s buffer, and gives `verts`'s buffer
/// back in `out`, so that no array is allocated.
fn place_by_min(verts: Vec<u32>, arity: usize, count: &mut [u32], out: &mut Vec<u32>) -> Vec<u32> {
    count.fill(0);
    for c in verts.chunks_exact(arity) {
        let mn = c.iter().copied().min().unwrap_or(0);
        count[mn as usize + 1] += 1;
    }
    for i in 1..count.len() {
        count[i] += count[i - 1];
    }
    match arity {
        3 => place::<3>(&verts, count, out),
        4 => place::<4>(&verts, count, out),
        _ => place_any(&verts, arity, count, out),
    }
    std::mem::replace(out, verts)
}

impl Flat {
    /// The top cells of `s` in the numbering `to_new`; `None` when the vertex references do
    /// not fit 32-bit offsets.
    pub(crate) fn new<S: TopCells + ?Sized>(s: &S, to_new: &[u32]) -> Option<Flat> {
        let nv = s.n_vertices();
        let nc = s.n_top_cells();
        let mut verts: Vec<VertexId> = Vec::new();
        // kinds, reference count, and the smallest new vertex of every cell (in `slot`)
        let mut uniform: Option<CellKind> = None;
        let mut mixed = false;
        let mut refs = 0u64;
        let mut count = vec![0u32; nv + 1];
        let mut slot = vec![0u32; nc];
        for (c, sl) in slot.iter_mut().enumerate() {
            let k = s.top_cell_kind(CellId(c as u32));
            match uniform {
                None if c == 0 => uniform = Some(k),
                Some(u) if u != k => mixed = true,
                _ => {}
            }
            verts.clear();
            s.top_cell_vertices(CellId(c as u32), &mut verts);
            refs += verts.len() as u64;
            let mn = verts
                .iter()
                .map(|v| to_new[v.0 as usize])
                .min()
                .unwrap_or(0);
            *sl = mn;
            count[mn as usize + 1] += 1;
        }
        if refs >= u32::MAX as u64 {
            return None;
        }
        if mixed {
            uniform = None;
        }
        for i in 0..nv {
            count[i + 1] += count[i];
        }
        // the slot of each cell: a stable counting sort by smallest new vertex
        for sl in slot.iter_mut() {
            let mn = *sl as usize;
            *sl = count[mn];
            count[mn] += 1;
        }
        drop(count);
        let arity = uniform.map_or(0, |k| k.n_vertices());
        let (mut kinds, mut starts) = (Vec::new(), Vec::new());
        if uniform.is_none() {
            let mut len = vec![0u32; nc + 1];
            kinds = vec![CellKind::Simplex(0); nc];
            for (c, &sl) in slot.iter().enumerate() {
                let k = s.top_cell_kind(CellId(c as u32));
                len[sl as usize + 1] = k.n_vertices() as u32;
                kinds[sl as usize] = k;
            }
            for i in 0..nc {
                len[i + 1] += len[i];
            }
            starts = len;
        }
        let mut flat = vec![0u32; refs as usize];
        for (c, &sl) in slot.iter().enumerate() {
            verts.clear();
            s.top_cell_vertices(CellId(c as u32), &mut verts);
            let a = if uniform.is_some() {
                sl as usize * arity
            } else {
                starts[sl as usize] as usize
            };
            for (d, v) in flat[a..a + verts.len()].iter_mut().zip(&verts) {
                *d = to_new[v.0 as usize];
            }
        }
        drop(slot);
        let mut f = Flat {
            n_vertices: nv,
            n_cells: nc,
            uniform,
            kinds,
            arity,
            starts,
            verts: flat,
            vt: crate::csr::Csr {
                offsets: vec![0u32; nv + 1],
                targets: vec![0u32; refs as usize],
            },
        };
        f.sort_and_index();
        Some(f)
    }

    /// [`Flat::new`] of a complex it consumes: when the complex is one block of owned cells,
    /// they are renumbered in place and then copied to their places (the same layout as
    /// `Flat::new`); the coordinates are freed first, and the input cells before the vertex →
    /// cells relation is built. `None` as for `Flat::new`.
    pub(crate) fn from_complex(k: crate::complex::IndexedComplex, to_new: &[u32]) -> Option<Flat> {
        let nv = k.n_vertices();
        let nc = k.n_cells();
        if k.blocks().len() != 1 || k.n_refs() as u64 >= u32::MAX as u64 {
            return Flat::new(&k, to_new);
        }
        let mut blocks = k.into_blocks();
        let b = blocks.pop()?;
        let kind = b.kind;
        let arity = kind.n_vertices();
        let mut verts = b.vertices.into_vec();
        // renumber (simplices sorted: their smallest vertex comes first), and place the cells
        // by a stable counting sort on their smallest new vertex
        renumber(&mut verts, arity, kind.is_simplex(), to_new);
        // the relation's buffers are the work buffers of the placement
        let mut offsets = vec![0u32; nv + 1];
        let mut targets = vec![0u32; verts.len()];
        let verts = place_by_min(verts, arity, &mut offsets, &mut targets);
        let mut f = Flat {
            n_vertices: nv,
            n_cells: nc,
            uniform: Some(kind),
            kinds: Vec::new(),
            arity,
            starts: Vec::new(),
            verts,
            vt: crate::csr::Csr { offsets, targets },
        };
        // the simplices were sorted by `renumber`
        f.index();
        Some(f)
    }

    /// The cells of a complex it consumes, in the input numbering and order, when they are one
    /// block of simplices (the coordinates are freed first; the vertices of every simplex are
    /// sorted in place).
    /// `None` (nothing consumed) unless [`Flat::takes_over`].
    pub(crate) fn input_order(k: crate::complex::IndexedComplex) -> Option<Flat> {
        if !Flat::takes_over(&k) {
            return None;
        }
        let nv = k.n_vertices();
        let nc = k.n_cells();
        let mut blocks = k.into_blocks();
        let b = blocks.pop()?;
        let verts = b.vertices.into_vec();
        let refs = verts.len();
        let mut f = Flat {
            n_vertices: nv,
            n_cells: nc,
            uniform: Some(b.kind),
            kinds: Vec::new(),
            arity: b.kind.n_vertices(),
            starts: Vec::new(),
            verts,
            vt: crate::csr::Csr {
                offsets: vec![0u32; nv + 1],
                targets: vec![0u32; refs],
            },
        };
        f.sort_and_index();
        Some(f)
    }

    /// The complex is one block of simplices with fewer than 2^32 vertex references.
    pub(crate) fn takes_over(k: &crate::complex::IndexedComplex) -> bool {
        matches!(k.blocks(), [b] if b.kind.is_simplex()) && (k.n_refs() as u64) < u32::MAX as u64
    }

    /// Renumbers the vertices (`to_new[old]`) and rebuilds the vertex → cells relation;
    /// simplices are sorted again. Cells of one kind are also placed again by their smallest
    /// new vertex (as [`Flat::from_complex`] does), so that a vertex's star lies close to its
    /// neighbours' in memory; mixed cells keep their places.
    pub(crate) fn relabel(&mut self, to_new: &[u32]) {
        match self.uniform {
            Some(k) if self.arity > 0 => {
                let a = self.arity;
                renumber(&mut self.verts, a, k.is_simplex(), to_new);
                // the relation is rebuilt below: its buffers are the placement's work buffers
                let verts = std::mem::take(&mut self.verts);
                self.verts = place_by_min(verts, a, &mut self.vt.offsets, &mut self.vt.targets);
                self.index();
            }
            _ => {
                for v in &mut self.verts {
                    *v = to_new[*v as usize];
                }
                self.sort_and_index();
            }
        }
    }

    /// Sorts the vertices of every simplex and builds the vertex → cells relation (cells in
    /// increasing order: rows are sorted).
    fn sort_and_index(&mut self) {
        match self.uniform {
            Some(k) if k.is_simplex() && self.arity > 0 => {
                let a = self.arity;
                self.verts
                    .par_chunks_mut(a * PAR_CELLS)
                    .for_each(|p| p.chunks_exact_mut(a).for_each(sort_simplex));
            }
            Some(_) => {}
            None => {
                for c in 0..self.n_cells {
                    if self.kind(c).is_simplex() {
                        let r = self.range(c);
                        self.verts[r].sort_unstable();
                    }
                }
            }
        }
        self.index();
    }

    /// Builds the vertex → cells relation in its own buffers (cells in increasing order: rows
    /// are sorted).
    fn index(&mut self) {
        let off = &mut self.vt.offsets;
        off.iter_mut().for_each(|x| *x = 0);
        for &v in &self.verts {
            off[v as usize + 1] += 1;
        }
        for i in 0..self.n_vertices {
            off[i + 1] += off[i];
        }
        // `off[v]` is the next free place of row v while filling; shifted back afterwards
        if self.uniform.is_some() && self.arity > 0 {
            for (c, cell) in self.verts.chunks_exact(self.arity).enumerate() {
                for &v in cell {
                    self.vt.targets[off[v as usize] as usize] = c as u32;
                    off[v as usize] += 1;
                }
            }
        } else {
            for c in 0..self.n_cells {
                let r = if self.uniform.is_some() {
                    c * self.arity..(c + 1) * self.arity
                } else {
                    self.starts[c] as usize..self.starts[c + 1] as usize
                };
                for &v in &self.verts[r] {
                    self.vt.targets[off[v as usize] as usize] = c as u32;
                    off[v as usize] += 1;
                }
            }
        }
        // now off[v] = end of row v = start of row v + 1
        for i in (0..self.n_vertices).rev() {
            off[i + 1] = off[i];
        }
        off[0] = 0;
    }

    /// Direct access to the cells when they are simplices of one kind (sorted vertices).
    pub(crate) fn fast_star(&self) -> Option<super::morse::FastStar<'_>> {
        match self.uniform {
            Some(k) if k.is_simplex() => Some(super::morse::FastStar {
                arity: self.arity,
                sorted: true,
                verts: &self.verts,
                vt: &self.vt,
            }),
            _ => None,
        }
    }

    /// The cells as vertex slices, in cell order.
    pub(crate) fn cells(&self) -> impl Iterator<Item = &[u32]> + '_ {
        (0..self.n_cells).map(|c| &self.verts[self.range(c)])
    }

    #[inline]
    fn kind(&self, c: usize) -> CellKind {
        match self.uniform {
            Some(k) => k,
            None => self.kinds[c],
        }
    }

    #[inline]
    fn range(&self, c: usize) -> std::ops::Range<usize> {
        if self.uniform.is_some() {
            c * self.arity..(c + 1) * self.arity
        } else {
            self.starts[c] as usize..self.starts[c + 1] as usize
        }
    }
}

impl TopCells for Flat {
    fn n_vertices(&self) -> usize {
        self.n_vertices
    }
    fn n_top_cells(&self) -> usize {
        self.n_cells
    }
    #[inline]
    fn top_cell_kind(&self, c: CellId) -> CellKind {
        self.kind(c.0 as usize)
    }
    #[inline]
    fn top_cell_vertices(&self, c: CellId, out: &mut Vec<VertexId>) {
        out.extend(
            self.verts[self.range(c.0 as usize)]
                .iter()
                .map(|&v| VertexId(v)),
        );
    }
}

impl VertexStar for Flat {
    #[inline]
    fn vertex_top_cells(&self, v: VertexId, out: &mut Vec<CellId>) {
        out.clear();
        out.extend(self.vt.row(v.index()).iter().map(|&c| CellId(c)));
    }
}
