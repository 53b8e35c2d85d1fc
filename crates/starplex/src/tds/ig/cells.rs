//! The incidence graph of a CP complex (quads, pyramids, prisms, hexahedra, mixed with
//! simplices): every cell of every dimension from the kinds' face tables, with its immediate
//! boundary and co-boundary. A cell is named by its canonical key, its sorted vertices
//! ([`crate::cell::canonical_key`]): a quad shared by two hexahedra is one node, and a level may
//! hold cells of different sizes (triangles and quads at level 2). Cells are numbered level by
//! level in lexicographic order of their keys, as for simplices.
use crate::cell::{binomial, CellKind};
use crate::complex::IndexedComplex;
use crate::csr::Csr;
use crate::ids::{CellId, SimplexId, VertexId};
use crate::limits::{TooLarge, Unit};
use crate::tds::simplex_tree::BuildError;
use crate::topo::{
    sort_flat, sorted_simplex, Adjacency, Boundary, Coboundary, Counts, Levels, QueryError,
    SimplexSet, SimplexVertices, Star, Storage, TopCells, TopStar, VertexAdjacency, VertexStar,
    DEFAULT_BUDGET,
};

/// The faces of one kind: per level p, the local vertex positions of each p-face (in the
/// kind's enumeration order) and, for p ≥ 1, the indices of its facets among the (p-1)-faces.
struct KindFaces {
    faces: Vec<Vec<Vec<u8>>>,
    facets: Vec<Vec<Vec<u32>>>,
}

impl KindFaces {
    fn new(kind: CellKind) -> KindFaces {
        let dim = kind.dim();
        let mut faces: Vec<Vec<Vec<u8>>> = Vec::with_capacity(dim + 1);
        for p in 0..=dim {
            let mut l = Vec::new();
            kind.for_each_face(p, |f| {
                let mut f = f.to_vec();
                f.sort_unstable();
                l.push(f)
            });
            faces.push(l);
        }
        let mut facets = vec![Vec::new()];
        for p in 1..=dim {
            let below: rustc_hash::FxHashMap<&[u8], u32> = faces[p - 1]
                .iter()
                .enumerate()
                .map(|(i, f)| (f.as_slice(), i as u32))
                .collect();
            let mut level = Vec::with_capacity(faces[p].len());
            for f in &faces[p] {
                let fs: Vec<u32> = if kind.is_simplex() {
                    // omit one position
                    (0..f.len())
                        .map(|j| {
                            let g: Vec<u8> = f
                                .iter()
                                .enumerate()
                                .filter(|&(x, _)| x != j)
                                .map(|(_, &l)| l)
                                .collect();
                            below[g.as_slice()]
                        })
                        .collect()
                } else {
                    // the (p-1)-faces of the table inside f (faces of a convex cell)
                    faces[p - 1]
                        .iter()
                        .enumerate()
                        .filter(|(_, g)| g.iter().all(|l| f.contains(l)))
                        .map(|(i, _)| i as u32)
                        .collect()
                };
                level.push(fs);
            }
            facets.push(level);
        }
        KindFaces { faces, facets }
    }
}

/// Packs a key padded with zeros to four entries; `u128` order is then the lexicographic
/// order of the tuples (entries after the first of a sorted tuple are positive).
#[inline]
fn pack4(key: &[u32]) -> u128 {
    let mut x = 0u128;
    for i in 0..4 {
        x = (x << 32) | key.get(i).copied().unwrap_or(0) as u128;
    }
    x
}

/// Real length of a zero-padded sorted key.
#[inline]
fn key_len(key: &[u32]) -> usize {
    1 + key[1..].iter().filter(|&&x| x != 0).count()
}

/// The incidence graph of a CP complex (see the [module docs](self)).
#[derive(Clone, Debug)]
pub(super) struct CellGraph {
    n_vertices: u32,
    /// `keys[p]` (p ≥ 1): the sorted vertices of the p-cells, lexicographic. Level 0 is the
    /// vertices themselves.
    keys: Vec<Csr>,
    /// `bnd[p]` (p ≥ 1): the facets of each p-cell (indices at level p-1), sorted.
    bnd: Vec<Csr>,
    /// `cob[p]` (p < depth - 1): the (p+1)-cells having each p-cell as a facet, sorted.
    cob: Vec<Csr>,
    level_offset: Vec<u32>,
    cell_node: Vec<u32>,
    /// Per block of the input: first top, kind, start of its vertices in `top_verts`.
    blocks: Vec<(u32, CellKind, usize)>,
    /// The tops' vertices in input (VTK) order, block after block: the face tables index them.
    top_verts: Vec<u32>,
    top_at: Vec<Vec<(u32, u32)>>,
}

/// Cells the incidence graph of `k` would hold: its vertices and every face of every top.
fn cell_estimate(k: &IndexedComplex) -> u128 {
    let nv = k.n_vertices();
    let mut est: u128 = nv as u128;
    for b in k.blocks() {
        for p in 1..=b.kind.dim() {
            let f = if b.kind.is_simplex() {
                binomial(b.kind.n_vertices() as u64, p as u64 + 1)
            } else {
                b.kind.n_faces(p)
            };
            est = est.saturating_add(f.saturating_mul(b.len() as u128));
        }
    }
    est
}

/// The face tables of the cell kinds of a complex.
struct FaceTables(Vec<(CellKind, KindFaces)>);

impl FaceTables {
    fn new(k: &IndexedComplex) -> FaceTables {
        let mut kinds: Vec<(CellKind, KindFaces)> = Vec::new();
        for b in k.blocks() {
            if !kinds.iter().any(|x| x.0 == b.kind) {
                kinds.push((b.kind, KindFaces::new(b.kind)));
            }
        }
        FaceTables(kinds)
    }

    /// The table of `kind` (one of the complex's kinds).
    fn get(&self, kind: CellKind) -> &KindFaces {
        &self.0.iter().find(|x| x.0 == kind).expect("listed").1
    }

    /// The number of `p`-faces of a cell of `kind`.
    fn n_faces(&self, kind: CellKind, p: usize) -> usize {
        self.get(kind).faces.get(p).map_or(0, |l| l.len())
    }
}

/// Level `p`'s cells: every (top, p-face) slot keyed by its sorted vertices, the distinct keys
/// in order. Returns the slot base of each block, the keys (one row per cell) and the cell of
/// every slot; `key` is scratch.
fn level_keys(
    k: &IndexedComplex,
    tables: &FaceTables,
    p: usize,
    key: &mut Vec<u32>,
) -> (Vec<usize>, Csr, Vec<u32>) {
    let kf = |kind: CellKind| tables.get(kind);
    let nf = |kind: CellKind, p: usize| tables.n_faces(kind, p);
    let mut base = Vec::new();
    let mut tot = 0usize;
    let mut w = 0usize;
    for b in k.blocks() {
        base.push(tot);
        tot += b.len() * nf(b.kind, p);
        if nf(b.kind, p) > 0 {
            w = w.max(
                kf(b.kind).faces[p]
                    .iter()
                    .map(|f| f.len())
                    .max()
                    .unwrap_or(0),
            );
        }
    }
    // every (cell, face) slot's key, zero-padded to width w
    let mut flat: Vec<u32> = vec![0; tot * w];
    let mut at = 0usize;
    for b in k.blocks() {
        let faces = &kf(b.kind).faces;
        let Some(fl) = faces.get(p) else {
            continue;
        };
        let n = b.kind.n_vertices();
        for c in b.vertices.chunks_exact(n) {
            for f in fl {
                key.clear();
                key.extend(f.iter().map(|&l| c[l as usize]));
                key.sort_unstable();
                flat[at * w..at * w + key.len()].copy_from_slice(key);
                at += 1;
            }
        }
    }
    debug_assert_eq!(at, tot);
    let order: Vec<u32> = if w <= 4 {
        let mut recs: Vec<(u128, u32)> = (0..tot)
            .map(|s| (pack4(&flat[s * w..(s + 1) * w]), s as u32))
            .collect();
        recs.sort_unstable();
        recs.into_iter().map(|x| x.1).collect()
    } else {
        let mut o: Vec<u32> = (0..tot as u32).collect();
        o.sort_unstable_by(|&a, &b| {
            let (a, b) = (a as usize, b as usize);
            flat[a * w..(a + 1) * w]
                .cmp(&flat[b * w..(b + 1) * w])
                .then(a.cmp(&b))
        });
        o
    };
    let mut nodes = vec![0u32; tot];
    let mut kc = Csr {
        offsets: vec![0],
        targets: Vec::new(),
    };
    let mut prev: Option<usize> = None;
    for &s in &order {
        let s = s as usize;
        let cur = &flat[s * w..(s + 1) * w];
        if prev.is_none_or(|q| &flat[q * w..(q + 1) * w] != cur) {
            kc.targets.extend_from_slice(&cur[..key_len(cur)]);
            kc.offsets.push(kc.targets.len() as u32);
        }
        nodes[s] = (kc.offsets.len() - 2) as u32;
        prev = Some(s);
    }
    (base, kc, nodes)
}

/// The (cell, facet) pairs of level `p` (`n_p` cells), each cell's facets from the first top
/// met that holds it, sorted per cell.
fn level_facets(
    k: &IndexedComplex,
    tables: &FaceTables,
    p: usize,
    n_p: usize,
    base: &[Vec<usize>],
    slot_node: &[Vec<u32>],
) -> Vec<(u32, u32)> {
    let kf = |kind: CellKind| tables.get(kind);
    let mut seen = vec![false; n_p];
    let mut pairs: Vec<(u32, u32)> = Vec::new();
    for (bi, b) in k.blocks().iter().enumerate() {
        let f = kf(b.kind);
        let Some(fl) = f.faces.get(p) else {
            continue;
        };
        let n = b.kind.n_vertices();
        let (m, mb) = (fl.len(), f.faces[p - 1].len());
        for (i, c) in b.vertices.chunks_exact(n).enumerate() {
            for j in 0..m {
                let node = slot_node[p][base[p][bi] + i * m + j];
                if seen[node as usize] {
                    continue;
                }
                seen[node as usize] = true;
                let start = pairs.len();
                for &g in &f.facets[p][j] {
                    let fnode = if p == 1 {
                        c[f.faces[0][g as usize][0] as usize]
                    } else {
                        slot_node[p - 1][base[p - 1][bi] + i * mb + g as usize]
                    };
                    pairs.push((node, fnode));
                }
                pairs[start..].sort_unstable();
            }
        }
    }
    pairs
}

/// The node of every top cell, and per dimension the (node, top) pairs sorted.
#[allow(clippy::type_complexity)]
fn top_nodes(
    k: &IndexedComplex,
    depth: usize,
    base: &[Vec<usize>],
    slot_node: &[Vec<u32>],
) -> (Vec<u32>, Vec<Vec<(u32, u32)>>) {
    let mut cell_node = vec![0u32; k.n_cells()];
    let mut top_at = vec![Vec::new(); depth];
    for (bi, b) in k.blocks().iter().enumerate() {
        let d = b.kind.dim();
        for i in 0..b.len() {
            let node = if d == 0 {
                b.vertices[i]
            } else {
                slot_node[d][base[d][bi] + i]
            };
            let c = b.first + i as u32;
            cell_node[c as usize] = node;
            top_at[d].push((node, c));
        }
    }
    for t in &mut top_at {
        t.sort_unstable();
    }
    (cell_node, top_at)
}

impl CellGraph {
    /// Builds every cell with its boundary and co-boundary.
    ///
    /// # Errors
    /// More than `limit` cells (refused before allocating them).
    pub(super) fn new(k: &IndexedComplex, limit: u128) -> Result<CellGraph, BuildError> {
        let limit = limit.min(u32::MAX as u128);
        let nv = k.n_vertices();
        let est = cell_estimate(k);
        if est > limit {
            return Err(BuildError::too_many(est, limit));
        }
        let depth = k.dim().map_or(1, |d| d + 1);
        let tables = FaceTables::new(k);
        // per level: the slot base of each block, and the node of every (cell, face) slot
        let mut base: Vec<Vec<usize>> = vec![Vec::new(); depth];
        let mut slot_node: Vec<Vec<u32>> = vec![Vec::new(); depth];
        let mut keys: Vec<Csr> = vec![Csr::default(); depth];
        keys[0] = Csr {
            offsets: (0..=nv as u32).collect(),
            targets: (0..nv as u32).collect(),
        };
        let mut key: Vec<u32> = Vec::new();
        for p in 1..depth {
            let (b, kc, nodes) = level_keys(k, &tables, p, &mut key);
            base[p] = b;
            keys[p] = kc;
            slot_node[p] = nodes;
        }
        let n_at = |p: usize| keys[p].n_rows();
        // boundaries: each cell's facets, from the first top met that holds it
        let mut bnd: Vec<Csr> = vec![Csr::default(); depth];
        let mut cob: Vec<Csr> = vec![Csr::default(); depth];
        for p in 1..depth {
            let pairs = level_facets(k, &tables, p, n_at(p), &base, &slot_node);
            let b = Csr::from_pairs(n_at(p), &pairs);
            let mut inv: Vec<(u32, u32)> = Vec::with_capacity(b.n_refs());
            for r in 0..b.n_rows() {
                for &x in b.row(r) {
                    inv.push((x, r as u32));
                }
            }
            cob[p - 1] = Csr::from_pairs(n_at(p - 1), &inv);
            bnd[p] = b;
        }
        cob.truncate(depth.saturating_sub(1));
        let mut level_offset = Vec::with_capacity(depth + 1);
        let mut acc = 0u32;
        for p in 0..depth {
            level_offset.push(acc);
            acc += n_at(p) as u32;
        }
        level_offset.push(acc);
        let (cell_node, top_at) = top_nodes(k, depth, &base, &slot_node);
        let mut blocks = Vec::with_capacity(k.blocks().len());
        let mut top_verts = Vec::with_capacity(k.n_refs());
        for b in k.blocks() {
            blocks.push((b.first, b.kind, top_verts.len()));
            top_verts.extend_from_slice(&b.vertices);
        }
        Ok(CellGraph {
            n_vertices: nv as u32,
            keys,
            bnd,
            cob,
            level_offset,
            cell_node,
            blocks,
            top_verts,
            top_at,
        })
    }

    fn depth(&self) -> usize {
        self.keys.len()
    }

    fn n_at(&self, p: usize) -> usize {
        self.keys.get(p).map_or(0, |k| k.n_rows())
    }

    /// Sorted vertices of (p, i).
    fn key(&self, p: usize, i: u32) -> &[u32] {
        self.keys[p].row(i as usize)
    }

    /// Whether (p, i) is a simplex (p + 1 vertices).
    fn is_simplex(&self, p: usize, i: u32) -> bool {
        self.keys[p].degree(i as usize) == p + 1
    }

    /// (p, i) of the sorted vertex set `s`, at the lowest level holding it.
    fn find(&self, s: &[u32]) -> Option<(usize, u32)> {
        if s.is_empty() {
            return None;
        }
        if s.len() == 1 {
            return (s[0] < self.n_vertices).then_some((0, s[0]));
        }
        for p in 1..self.depth().min(s.len()) {
            let l = &self.keys[p];
            let (mut lo, mut hi) = (0usize, l.n_rows());
            while lo < hi {
                let mid = (lo + hi) / 2;
                match l.row(mid).cmp(s) {
                    std::cmp::Ordering::Less => lo = mid + 1,
                    std::cmp::Ordering::Greater => hi = mid,
                    std::cmp::Ordering::Equal => return Some((p, mid as u32)),
                }
            }
        }
        None
    }

    fn locate(&self, s: &[VertexId]) -> Result<(usize, u32), QueryError> {
        let s = sorted_simplex(s)?;
        let raw: Vec<u32> = s.iter().map(|v| v.0).collect();
        self.find(&raw).ok_or(QueryError::NotInComplex(raw))
    }

    pub(super) fn global(&self, p: usize, i: u32) -> SimplexId {
        SimplexId(self.level_offset[p] + i)
    }

    pub(super) fn split(&self, s: SimplexId) -> Option<(usize, u32)> {
        if s.0 >= *self.level_offset.last()? {
            return None;
        }
        let p = self.level_offset.partition_point(|&o| o <= s.0) - 1;
        Some((p, s.0 - self.level_offset[p]))
    }

    fn facets(&self, p: usize, i: u32) -> &[u32] {
        if p == 0 {
            return &[];
        }
        self.bnd[p].row(i as usize)
    }

    /// The q-faces of (p, i), by descending boundary arcs.
    pub(super) fn descend(&self, p: usize, i: u32, q: usize) -> Vec<u32> {
        let mut cur = vec![i];
        let mut level = p;
        while level > q {
            let mut next: Vec<u32> = cur
                .iter()
                .flat_map(|&x| self.facets(level, x).iter().copied())
                .collect();
            next.sort_unstable();
            next.dedup();
            cur = next;
            level -= 1;
        }
        cur
    }

    /// St(σ) as (level, index), by breadth-first ascent through the co-boundaries.
    pub(super) fn star_ids(&self, p: usize, i: u32) -> Result<Vec<(usize, u32)>, QueryError> {
        let mut out = vec![(p, i)];
        let mut cur = vec![i];
        let mut level = p;
        while level + 1 < self.depth() && !cur.is_empty() {
            let mut next: Vec<u32> = cur
                .iter()
                .flat_map(|&x| self.cob[level].row(x as usize).iter().copied())
                .collect();
            next.sort_unstable();
            next.dedup();
            level += 1;
            out.extend(next.iter().map(|&x| (level, x)));
            if out.len() as u128 > DEFAULT_BUDGET {
                return Err(QueryError::TooLarge(TooLarge::new(
                    "star",
                    out.len() as u128,
                    DEFAULT_BUDGET,
                    Unit::Simplices,
                )));
            }
            cur = next;
        }
        Ok(out)
    }

    /// The p-cells sharing a (p-1)-face with (p, i) (p ≥ 1), or the vertices sharing an edge.
    pub(super) fn adjacent_ids(&self, p: usize, i: u32) -> Vec<u32> {
        let mut ids = Vec::new();
        if p == 0 {
            if let Some(c) = self.cob.first() {
                for &e in c.row(i as usize) {
                    let t = self.key(1, e);
                    ids.push(if t[0] == i { t[1] } else { t[0] });
                }
            }
        } else {
            for &f in self.facets(p, i) {
                ids.extend(
                    self.cob[p - 1]
                        .row(f as usize)
                        .iter()
                        .copied()
                        .filter(|&j| j != i),
                );
            }
        }
        ids.sort_unstable();
        ids.dedup();
        ids
    }

    /// The flat sorted tuples of the q-cells `ids`, or a refusal naming the first cell that is
    /// not a simplex (its vertices do not fit a stride of q + 1).
    fn flat(&self, q: usize, ids: &[u32], what: &str) -> Result<Vec<VertexId>, QueryError> {
        let mut out = Vec::with_capacity(ids.len() * (q + 1));
        for &i in ids {
            if !self.is_simplex(q, i) {
                return Err(self.not_simplex(q, i, what));
            }
            out.extend(self.key(q, i).iter().map(|&v| VertexId(v)));
        }
        sort_flat(&mut out, q + 1);
        Ok(out)
    }

    fn not_simplex(&self, q: usize, i: u32, what: &str) -> QueryError {
        let key = self.key(q, i);
        let name = match (q, key.len()) {
            (2, 4) => "quad",
            (3, 5) => "pyramid",
            (3, 6) => "prism",
            (3, 8) => "hexahedron",
            _ => "CP cell",
        };
        QueryError::NotSimplicial(format!(
            "{what} holds the {name} {key:?}, which a list of sorted {}-vertex tuples cannot \
             hold (IncidenceGraph::cell_faces, cell_cofaces and cell_adjacent answer by id)",
            q + 1
        ))
    }

    fn cell_kind(&self, c: u32) -> CellKind {
        let i = self.blocks.partition_point(|b| b.0 <= c) - 1;
        self.blocks[i].1
    }

    /// The vertices of top `c` in input (VTK) order.
    fn top_vertices(&self, c: u32) -> &[u32] {
        let (first, kind, start) = self.blocks[self.blocks.partition_point(|b| b.0 <= c) - 1];
        let n = kind.n_vertices();
        let at = start + (c - first) as usize * n;
        &self.top_verts[at..at + n]
    }

    fn top_cell(&self, p: usize, i: u32) -> Option<CellId> {
        let t = &self.top_at[p];
        t.binary_search_by_key(&i, |x| x.0)
            .ok()
            .map(|x| CellId(t[x].1))
    }

    pub(super) fn refs(&self) -> u64 {
        (self.bnd.iter().map(|b| b.n_refs()).sum::<usize>()
            + self.cob.iter().map(|c| c.n_refs()).sum::<usize>()) as u64
    }

    pub(super) fn bytes(&self) -> u64 {
        (self.bnd.iter().map(|b| b.bytes()).sum::<usize>()
            + self.cob.iter().map(|c| c.bytes()).sum::<usize>()) as u64
    }

    pub(super) fn aux_bytes(&self) -> u64 {
        let k: usize = self.keys.iter().map(|k| k.bytes()).sum();
        let t: usize = self.top_at.iter().map(|t| 8 * t.len()).sum();
        (k + t + 4 * self.cell_node.len() + 4 * self.top_verts.len()) as u64
    }
}

impl TopCells for CellGraph {
    fn n_vertices(&self) -> usize {
        self.n_vertices as usize
    }
    fn n_top_cells(&self) -> usize {
        self.cell_node.len()
    }
    fn top_cell_kind(&self, c: CellId) -> CellKind {
        self.cell_kind(c.0)
    }
    /// Input (VTK) order: the kinds' face tables index it.
    fn top_cell_vertices(&self, c: CellId, out: &mut Vec<VertexId>) {
        out.extend(self.top_vertices(c.0).iter().map(|&v| VertexId(v)));
    }
}

impl TopStar for CellGraph {
    fn top_star(&self, s: &[VertexId], out: &mut Vec<CellId>) -> Result<(), QueryError> {
        let (p, i) = self.locate(s)?;
        out.clear();
        for (q, j) in self.star_ids(p, i)? {
            if let Some(c) = self.top_cell(q, j) {
                out.push(c);
            }
        }
        out.sort_unstable();
        Ok(())
    }
}

impl VertexStar for CellGraph {
    fn vertex_top_cells(&self, v: VertexId, out: &mut Vec<CellId>) {
        if self.top_star(&[v], out).is_err() {
            out.clear();
        }
    }
}

impl VertexAdjacency for CellGraph {
    fn vertex_neighbours(&self, v: VertexId, out: &mut Vec<VertexId>) {
        out.clear();
        if v.0 >= self.n_vertices {
            return;
        }
        out.extend(self.adjacent_ids(0, v.0).into_iter().map(VertexId));
    }
}

impl Counts for CellGraph {
    /// The number of cells per dimension (a CP complex's f-vector).
    fn f_vector(&self) -> Result<Vec<u64>, QueryError> {
        if self.n_vertices == 0 {
            return Ok(vec![]);
        }
        Ok((0..self.depth()).map(|p| self.n_at(p) as u64).collect())
    }
}

impl SimplexVertices for CellGraph {
    fn n_simplices(&self) -> usize {
        *self.level_offset.last().unwrap_or(&0) as usize
    }
    fn simplex_vertices(&self, s: SimplexId, out: &mut Vec<VertexId>) {
        out.clear();
        if let Some((p, i)) = self.split(s) {
            out.extend(self.key(p, i).iter().map(|&v| VertexId(v)));
        }
    }
    fn find_simplex(&self, verts: &[VertexId]) -> Option<SimplexId> {
        let (p, i) = self.locate(verts).ok()?;
        Some(self.global(p, i))
    }
}

impl Boundary for CellGraph {
    fn boundary(
        &self,
        s: &[VertexId],
        q: usize,
        out: &mut Vec<VertexId>,
    ) -> Result<(), QueryError> {
        let (p, i) = self.locate(s)?;
        out.clear();
        if q >= p {
            return Ok(());
        }
        let ids = self.descend(p, i, q);
        *out = self.flat(q, &ids, &format!("boundary R_{p},{q}"))?;
        Ok(())
    }
}

impl Coboundary for CellGraph {
    fn coboundary(
        &self,
        s: &[VertexId],
        q: usize,
        out: &mut Vec<VertexId>,
    ) -> Result<(), QueryError> {
        let (p, i) = self.locate(s)?;
        out.clear();
        if q <= p {
            return Ok(());
        }
        let ids: Vec<u32> = self
            .star_ids(p, i)?
            .into_iter()
            .filter(|&(d, _)| d == q)
            .map(|(_, j)| j)
            .collect();
        *out = self.flat(q, &ids, &format!("co-boundary R_{p},{q}"))?;
        Ok(())
    }
}

impl Adjacency for CellGraph {
    fn adjacent(&self, s: &[VertexId], out: &mut Vec<VertexId>) -> Result<(), QueryError> {
        let (p, i) = self.locate(s)?;
        out.clear();
        let ids = self.adjacent_ids(p, i);
        if p == 0 {
            out.extend(ids.into_iter().map(VertexId));
            return Ok(());
        }
        *out = self.flat(p, &ids, &format!("adjacency R_{p},{p}"))?;
        Ok(())
    }
}

impl Star for CellGraph {
    fn star(&self, s: &[VertexId]) -> Result<SimplexSet, QueryError> {
        let (p, i) = self.locate(s)?;
        let mut set = SimplexSet::default();
        for (q, j) in self.star_ids(p, i)? {
            if !self.is_simplex(q, j) {
                return Err(self.not_simplex(q, j, "the star"));
            }
            if set.levels.len() <= q {
                set.levels.resize(q + 1, Vec::new());
            }
            set.levels[q].extend(self.key(q, j).iter().map(|&v| VertexId(v)));
        }
        set.normalize();
        Ok(set)
    }
}

impl Levels for CellGraph {
    /// Refuses a level holding a cell that is not a simplex before calling `f`.
    fn for_each_simplex(&self, p: usize, f: &mut dyn FnMut(&[VertexId])) -> Result<(), QueryError> {
        if p >= self.depth() {
            return Ok(());
        }
        if let Some(i) = (0..self.n_at(p) as u32).find(|&i| !self.is_simplex(p, i)) {
            return Err(self.not_simplex(p, i, &format!("level {p}")));
        }
        let mut buf = Vec::with_capacity(p + 1);
        for i in 0..self.n_at(p) as u32 {
            buf.clear();
            buf.extend(self.key(p, i).iter().map(|&v| VertexId(v)));
            f(&buf);
        }
        Ok(())
    }
}

impl Storage for CellGraph {
    fn refs(&self) -> u64 {
        CellGraph::refs(self)
    }
    fn bytes(&self) -> u64 {
        CellGraph::bytes(self)
    }
}
