//! IA* on CP complexes (quads, pyramids, prisms, hexahedra, mixed with simplices): the parts
//! that differ from the simplicial structure. A CP top has one adjacency slot per facet of its
//! kind's facet table ([`CellKind::cp_faces`]`(dim - 1)`, VTK order: a hexahedron's 6 quads, a
//! prism's 2 triangles then 3 quads, a pyramid's base quad then 4 triangles, a quad's 4 edges);
//! facets are matched by their canonical key (sorted vertices), across kinds, so a prism and a
//! tetrahedron sharing a triangle are adjacent, and a quad shared by three hexahedra is a
//! non-manifold facet. Clusters and VT walk only the facets that contain the vertex, read from
//! the table. Complexes with a CP cell are built by the general path (the dimension ≤ 3 fast
//! path is for simplices only).
use super::{decode, Block, Ghost, IaStar, Slot, NM_BIT};
use crate::cell::{binomial, CellKind};
use crate::csr::Csr;
use crate::ids::VertexId;
use crate::limits::{TooLarge, Unit};
use crate::topo::{from_tops, QueryError, DEFAULT_BUDGET};

/// Local vertex positions of facet `j` of a CP cell (empty for a bad slot).
pub(super) fn facet(kind: CellKind, j: usize) -> &'static [u8] {
    kind.cp_faces(kind.dim().saturating_sub(1))
        .and_then(|t| t.get(j).copied())
        .unwrap_or(&[])
}

/// [`IaStar::for_each_neighbour_at`] for a CP top: the slots of the facets holding `v`.
pub(super) fn for_each_neighbour_at(
    ia: &IaStar,
    kind: CellKind,
    c: u32,
    v: u32,
    verts: &[u32],
    adj: &[u32],
    mut f: impl FnMut(u32),
) {
    let Some(p) = verts.iter().position(|&w| w == v) else {
        return;
    };
    for (j, &x) in adj.iter().enumerate() {
        if !facet(kind, j).contains(&(p as u8)) {
            continue;
        }
        match decode(x) {
            Slot::None => {}
            Slot::Top(u) => f(u.0),
            Slot::NmFace(fid) => {
                for &u in ia.nm[kind.dim()].row(fid as usize) {
                    if u != c {
                        f(u)
                    }
                }
            }
        }
    }
}

/// The facet key, sorted and padded with zeros to four vertices, packed so that `u128` order
/// is the lexicographic order of the sorted tuples (a tuple's entries after the first are
/// positive, so a shorter tuple padded with 0 sorts before any longer one it prefixes).
#[inline]
fn pack(key: &mut [u32; 4], m: usize) -> u128 {
    key[..m].sort_unstable();
    key[m..].iter_mut().for_each(|x| *x = 0);
    key.iter().fold(0u128, |a, &x| (a << 32) | x as u128)
}

/// Groups the facets of the top d-cells (d = 2 or 3; simplices and CP cells together) by their
/// canonical key and fills the adjacency slots; returns the non-manifold facets' top lists,
/// numbered in key order.
pub(super) fn build_adjacency(blocks: &mut [Block], d: usize) -> Csr {
    debug_assert!((2..=3).contains(&d));
    // (key, top, slot)
    let mut recs: Vec<(u128, u32, u8)> = Vec::new();
    let mut key = [0u32; 4];
    for b in blocks.iter().filter(|b| b.dim == d) {
        let (n, st) = (b.nv as usize, b.stride());
        recs.reserve(b.len as usize * b.ns as usize);
        for (i, rec) in b.data.chunks_exact(st).enumerate() {
            let c = b.first + i as u32;
            let verts = &rec[..n];
            for j in 0..b.ns as usize {
                let m = if b.kind.is_simplex() {
                    let mut m = 0;
                    for (x, &w) in verts.iter().enumerate() {
                        if x != j {
                            key[m] = w;
                            m += 1;
                        }
                    }
                    m
                } else {
                    let f = facet(b.kind, j);
                    for (x, &l) in f.iter().enumerate() {
                        key[x] = verts[l as usize];
                    }
                    f.len()
                };
                recs.push((pack(&mut key, m), c, j as u8));
            }
        }
    }
    recs.sort_unstable();
    let firsts: Vec<(u32, usize)> = blocks
        .iter()
        .enumerate()
        .map(|(i, b)| (b.first, i))
        .collect();
    let set_slot = |blocks: &mut [Block], c: u32, j: u8, val: u32| {
        let bi = firsts[firsts.partition_point(|x| x.0 <= c) - 1].1;
        let b = &mut blocks[bi];
        let st = b.stride();
        let at = (c - b.first) as usize * st + b.nv as usize + j as usize;
        b.data[at] = val;
    };
    let mut nm = Csr {
        offsets: vec![0],
        targets: Vec::new(),
    };
    let mut i = 0;
    while i < recs.len() {
        let mut e = i + 1;
        while e < recs.len() && recs[e].0 == recs[i].0 {
            e += 1;
        }
        match e - i {
            1 => {}
            2 => {
                let ((_, c1, j1), (_, c2, j2)) = (recs[i], recs[i + 1]);
                set_slot(blocks, c1, j1, c2);
                set_slot(blocks, c2, j2, c1);
            }
            _ => {
                let f = nm.n_rows() as u32;
                for &(_, c, j) in &recs[i..e] {
                    set_slot(blocks, c, j, NM_BIT | f);
                    nm.targets.push(c);
                }
                // records are sorted by (key, top): the list is sorted
                nm.offsets.push(nm.targets.len() as u32);
            }
        }
        i = e;
    }
    nm
}

/// Per vertex: every top edge (and top vertex) at it, and one top per k-cluster (k ≥ 2), the
/// cluster's smallest id, walking the facets that contain the vertex.
pub(super) fn cluster_representatives(ia: &IaStar, vt: &Csr) -> Csr {
    let nv = ia.n_vertices as usize;
    let mut offsets = Vec::with_capacity(nv + 1);
    let mut targets = Vec::with_capacity(nv);
    let mut mark: Vec<bool> = Vec::new();
    let mut queue: Vec<u32> = Vec::new();
    offsets.push(0u32);
    for v in 0..nv as u32 {
        let row = vt.row(v as usize);
        mark.clear();
        mark.resize(row.len(), false);
        for (ri, &c) in row.iter().enumerate() {
            if ia.top(c).0 <= 1 {
                targets.push(c);
                continue;
            }
            if mark[ri] {
                continue;
            }
            // rows are sorted: the first unvisited top of a cluster is its smallest
            targets.push(c);
            mark[ri] = true;
            queue.clear();
            queue.push(c);
            while let Some(x) = queue.pop() {
                ia.for_each_neighbour_at(x, v, |u| {
                    let ui = row
                        .binary_search(&u)
                        .expect("a neighbour through a facet at v contains v");
                    if !mark[ui] {
                        mark[ui] = true;
                        queue.push(u);
                    }
                });
            }
        }
        offsets.push(targets.len() as u32);
    }
    Csr { offsets, targets }
}

/// The (dimension, index in the kind's face table) of the face of a CP top (vertices `verts`)
/// whose vertex set is the sorted `s`.
pub(super) fn face_index(kind: CellKind, verts: &[u32], s: &[VertexId]) -> Option<(usize, usize)> {
    for q in 0..=kind.dim() {
        let table = kind.cp_faces(q)?;
        for (i, f) in table.iter().enumerate() {
            if f.len() == s.len()
                && f.iter()
                    .all(|&l| s.binary_search(&VertexId(verts[l as usize])).is_ok())
            {
                return Some((q, i));
            }
        }
    }
    None
}

/// Sorted vertex sets of the q-faces of a top of `kind` (vertices `verts`) that have the sorted
/// cell `s` as a face (`s` itself excluded unless q is its dimension), appended flat to `out`
/// with their lengths in `lens`. For a CP top a face of the top contained in another face's
/// vertex set is a face of it (the cells are convex polytopes).
fn cofaces_in_top(
    kind: CellKind,
    verts: &[u32],
    s: &[VertexId],
    q: usize,
    out: &mut Vec<VertexId>,
    lens: &mut Vec<usize>,
) {
    let mut key: Vec<VertexId> = Vec::new();
    let holds = |key: &[VertexId]| s.iter().all(|v| key.binary_search(v).is_ok());
    if kind.is_simplex() {
        // the q-subsets of the top containing s: s plus (q + 1 - |s|) other vertices
        if q + 1 < s.len() || q + 1 > verts.len() {
            return;
        }
        let rest: Vec<VertexId> = verts
            .iter()
            .map(|&w| VertexId(w))
            .filter(|w| s.binary_search(w).is_err())
            .collect();
        let mut buf = Vec::new();
        from_tops::for_each_subset(&rest, q + 1 - s.len(), &mut buf, &mut |sub| {
            key.clear();
            key.extend_from_slice(s);
            key.extend_from_slice(sub);
            key.sort_unstable();
            out.extend_from_slice(&key);
            lens.push(key.len());
        });
        return;
    }
    let Some(table) = kind.cp_faces(q) else {
        return;
    };
    for f in table {
        key.clear();
        key.extend(f.iter().map(|&l| VertexId(verts[l as usize])));
        key.sort_unstable();
        if holds(&key) {
            out.extend_from_slice(&key);
            lens.push(key.len());
        }
    }
}

/// An upper bound of the q-faces of a top of `kind`.
fn face_bound(kind: CellKind, q: usize) -> u128 {
    if kind.is_simplex() {
        binomial(kind.n_vertices() as u64, q as u64 + 1)
    } else {
        kind.n_faces(q)
    }
}

/// Canonical ghosts of a flat list of sorted cells of lengths `lens`, sorted, without repeats.
fn ghosts_of(ia: &IaStar, flat: &[VertexId], lens: &[usize]) -> Result<Vec<Ghost>, QueryError> {
    let mut out = Vec::with_capacity(lens.len());
    let mut at = 0;
    for &n in lens {
        out.push(ia.ghost(&flat[at..at + n])?);
        at += n;
    }
    out.sort_unstable();
    out.dedup();
    Ok(out)
}

/// R_{p,q}, q < p, of a ghost naming a CP cell (sorted vertices `s`): the q-faces of its top's
/// table inside it.
pub(super) fn ghost_boundary(
    ia: &IaStar,
    g: Ghost,
    s: &[VertexId],
    q: usize,
) -> Result<Vec<Ghost>, QueryError> {
    if q >= g.p as usize {
        return Ok(Vec::new());
    }
    let c = ia
        .cell_of(g.m as usize, g.k)
        .ok_or(QueryError::NotInComplex(vec![]))?;
    let b = ia.block_of(c.0);
    let verts = IaStar::record(b, c.0).1;
    let (mut flat, mut lens) = (Vec::new(), Vec::new());
    let mut key: Vec<VertexId> = Vec::new();
    for f in b.kind.cp_faces(q).unwrap_or(&[]) {
        key.clear();
        key.extend(f.iter().map(|&l| VertexId(verts[l as usize])));
        key.sort_unstable();
        if key.iter().all(|v| s.binary_search(v).is_ok()) {
            flat.extend_from_slice(&key);
            lens.push(key.len());
        }
    }
    ghosts_of(ia, &flat, &lens)
}

/// R_{p,q}, q > p, of a ghost in a complex with CP cells: the q-faces of the tops of its star
/// that have it as a face.
pub(super) fn ghost_coboundary(ia: &IaStar, g: Ghost, q: usize) -> Result<Vec<Ghost>, QueryError> {
    let s = ia.ghost_vertices(g)?;
    if q <= g.p as usize {
        return Ok(Vec::new());
    }
    let mut cells = Vec::new();
    from_tops::top_star(ia, &s, &mut cells)?;
    let est = cells
        .iter()
        .map(|&c| face_bound(ia.block_of(c.0).kind, q))
        .fold(0u128, |a, x| a.saturating_add(x));
    if est > DEFAULT_BUDGET {
        return Err(QueryError::TooLarge(TooLarge::new(
            format!("co-boundary R_{},{q}", g.p),
            est,
            DEFAULT_BUDGET,
            Unit::Simplices,
        )));
    }
    let (mut flat, mut lens) = (Vec::new(), Vec::new());
    for c in cells {
        let b = ia.block_of(c.0);
        let verts = IaStar::record(b, c.0).1;
        cofaces_in_top(b.kind, verts, &s, q, &mut flat, &mut lens);
    }
    ghosts_of(ia, &flat, &lens)
}

/// R_{p,p} of a ghost in a complex with CP cells: the p-cells sharing a (p-1)-face with it
/// (none for a vertex, as for simplicial complexes).
pub(super) fn ghost_adjacent(ia: &IaStar, g: Ghost) -> Result<Vec<Ghost>, QueryError> {
    ia.ghost_vertices(g)?;
    if g.p == 0 {
        return Ok(Vec::new());
    }
    let mut out = Vec::new();
    for h in ia.ghost_boundary(g, g.p as usize - 1)? {
        out.extend(
            ghost_coboundary(ia, h, g.p as usize)?
                .into_iter()
                .filter(|&x| x != g),
        );
    }
    out.sort_unstable();
    out.dedup();
    Ok(out)
}
