//! The incidence graph (Edelsbrunner): every simplex explicit, with its immediate boundary
//! R_{p,p-1} and its full immediate co-boundary R_{p,p+1}. Storage 2·Σ_{p≥1}(p+1)n_p references
//! (spec §6). Simplex ids: p-simplices are numbered level by level in lexicographic order of
//! their sorted vertices; the sorted vertex tuples are kept as an auxiliary index (lookups by
//! vertices), reported apart from the references ([`IncidenceGraph::aux_bytes`]).
//!
//! ```
//! use starplex::complex::{ComplexBuilder, BuildOptions};
//! use starplex::cell::CellKind;
//! use starplex::ids::VertexId;
//! use starplex::tds::ig::IncidenceGraph;
//! use starplex::topo::{Coboundary, Storage};
//! let mut b = ComplexBuilder::new(1).unwrap();
//! for x in 0..4 { b.push_vertex(&[x as f64]).unwrap(); }
//! b.push_cell(CellKind::Simplex(3), &[0, 1, 2, 3]).unwrap();
//! let k = b.build(&BuildOptions::default()).unwrap().0;
//! let ig = IncidenceGraph::new(&k, &Default::default()).unwrap();
//! assert_eq!(ig.refs(), 56); // the spec's worked anchor
//! let mut e = Vec::new();
//! ig.coboundary(&[VertexId(0)], 1, &mut e).unwrap();
//! assert_eq!(e.len() / 2, 3);
//! ```
use crate::cell::CellKind;
use crate::complex::IndexedComplex;
use crate::csr::Csr;
use crate::ids::{CellId, SimplexId, VertexId};
use crate::limits::{Limits, TooLarge, Unit};
use crate::tds::simplex_tree::{all_simplices, child_starts, BuildError, Levels0};
use crate::topo::{
    sort_flat, sorted_simplex, Adjacency, Boundary, Coboundary, Counts, Levels, QueryError,
    SimplexSet, SimplexVertices, Star, Storage, TopCells, TopStar, VertexAdjacency, VertexStar,
    DEFAULT_BUDGET,
};

mod cells;

/// All simplices with their boundaries: the part shared by the incidence graph and IS.
#[derive(Clone, Debug)]
pub(crate) struct Explicit {
    pub(crate) n_vertices: u32,
    /// `verts[p]`: sorted tuples of the p-simplices, flat (stride p+1), lexicographic.
    pub(crate) verts: Vec<Vec<u32>>,
    /// `bnd[p]`: for each p-simplex (p ≥ 1), its p+1 facets (index at level p-1); facet j
    /// omits the j-th vertex. `bnd[0]` is empty.
    pub(crate) bnd: Vec<Vec<u32>>,
    pub(crate) level_offset: Vec<u32>,
    pub(crate) cell_node: Vec<u32>,
    pub(crate) blocks: Vec<(u32, u8)>,
    pub(crate) top_at: Vec<Vec<(u32, u32)>>,
}

impl Explicit {
    /// Builds every simplex and its boundary.
    ///
    /// # Errors
    /// A CP cell; more than `limit` simplices.
    pub(crate) fn new(k: &IndexedComplex, limit: u128) -> Result<Explicit, BuildError> {
        let l = all_simplices(k, limit.min(u32::MAX as u128))?;
        let nv = k.n_vertices();
        let Levels0 {
            labels,
            parent,
            cell_node,
        } = l;
        let depth = labels.len();
        let mut verts: Vec<Vec<u32>> = Vec::with_capacity(depth);
        verts.push((0..nv as u32).collect());
        for p in 1..depth {
            let mut v = Vec::with_capacity(labels[p].len() * (p + 1));
            for (i, &lab) in labels[p].iter().enumerate() {
                let par = parent[p][i] as usize;
                let start = v.len();
                let pv = &verts[p - 1][par * p..(par + 1) * p];
                v.extend_from_slice(pv);
                v.push(lab);
                debug_assert!(v[start..].windows(2).all(|w| w[0] < w[1]));
            }
            verts.push(v);
        }
        // a temporary trie to find facets
        let mut cs: Vec<Vec<u32>> = Vec::with_capacity(depth);
        for p in 0..depth.saturating_sub(1) {
            let n_p = verts[p].len() / (p + 1);
            cs.push(child_starts(&parent[p + 1], n_p));
        }
        let find = |s: &[u32]| -> u32 {
            let mut i = s[0];
            for (d, &x) in s.iter().enumerate().skip(1) {
                let (lo, hi) = (
                    cs[d - 1][i as usize] as usize,
                    cs[d - 1][i as usize + 1] as usize,
                );
                let r = labels[d][lo..hi]
                    .binary_search(&x)
                    .expect("faces of a simplex are in the complex");
                i = (lo + r) as u32;
            }
            i
        };
        let mut bnd: Vec<Vec<u32>> = vec![Vec::new()];
        let mut f = Vec::with_capacity(depth);
        for p in 1..depth {
            let n = p + 1;
            let mut b = Vec::with_capacity(verts[p].len());
            for (i, t) in verts[p].chunks_exact(n).enumerate() {
                for j in 0..n {
                    if j == n - 1 {
                        b.push(parent[p][i]); // the facet without the last vertex
                        continue;
                    }
                    f.clear();
                    f.extend(
                        t.iter()
                            .enumerate()
                            .filter(|&(x, _)| x != j)
                            .map(|(_, &v)| v),
                    );
                    b.push(find(&f));
                }
            }
            bnd.push(b);
        }
        let mut level_offset = Vec::with_capacity(depth + 1);
        let mut acc = 0u32;
        for (p, v) in verts.iter().enumerate() {
            level_offset.push(acc);
            acc += (v.len() / (p + 1)) as u32;
        }
        level_offset.push(acc);
        let mut top_at = vec![Vec::new(); depth];
        for c in k.cells() {
            top_at[c.vertices.len() - 1].push((cell_node[c.id.index()], c.id.0));
        }
        for t in &mut top_at {
            t.sort_unstable();
        }
        Ok(Explicit {
            n_vertices: nv as u32,
            verts,
            bnd,
            level_offset,
            cell_node,
            blocks: k
                .blocks()
                .iter()
                .map(|b| (b.first, b.kind.dim() as u8))
                .collect(),
            top_at,
        })
    }

    /// Number of levels (dimension + 1).
    pub(crate) fn depth(&self) -> usize {
        self.verts.len()
    }

    /// Number of p-simplices.
    pub(crate) fn n_at(&self, p: usize) -> usize {
        self.verts.get(p).map_or(0, |v| v.len() / (p + 1))
    }

    /// Sorted vertices of (p, i).
    pub(crate) fn tuple(&self, p: usize, i: u32) -> &[u32] {
        &self.verts[p][i as usize * (p + 1)..(i as usize + 1) * (p + 1)]
    }

    /// The facets (indices at level p-1) of (p, i).
    pub(crate) fn facets(&self, p: usize, i: u32) -> &[u32] {
        if p == 0 {
            return &[];
        }
        &self.bnd[p][i as usize * (p + 1)..(i as usize + 1) * (p + 1)]
    }

    /// Index at level |s|-1 of the sorted simplex `s`.
    pub(crate) fn find(&self, s: &[u32]) -> Option<u32> {
        let p = s.len().checked_sub(1)?;
        if p >= self.verts.len() {
            return None;
        }
        let l = &self.verts[p];
        let n = p + 1;
        let (mut lo, mut hi) = (0usize, l.len() / n);
        while lo < hi {
            let mid = (lo + hi) / 2;
            match l[mid * n..(mid + 1) * n].cmp(s) {
                std::cmp::Ordering::Less => lo = mid + 1,
                std::cmp::Ordering::Greater => hi = mid,
                std::cmp::Ordering::Equal => return Some(mid as u32),
            }
        }
        None
    }

    /// Sorted, validated simplex and its index.
    pub(crate) fn locate(&self, s: &[VertexId]) -> Result<(Vec<u32>, u32), QueryError> {
        let s = sorted_simplex(s)?;
        let raw: Vec<u32> = s.iter().map(|v| v.0).collect();
        match self.find(&raw) {
            Some(i) => Ok((raw, i)),
            None => Err(QueryError::NotInComplex(raw)),
        }
    }

    /// The inverse of the boundary: for each level p < dim, the full co-boundary (CSR of
    /// (p+1)-simplices) and, for each entry, the position of the p-simplex in the coface.
    pub(crate) fn coboundaries(&self) -> Vec<(Csr, Vec<u8>)> {
        let mut out = Vec::with_capacity(self.depth());
        for p in 0..self.depth().saturating_sub(1) {
            let n_p = self.n_at(p);
            let b = &self.bnd[p + 1];
            let n = p + 2;
            let csr = Csr::from_fn(n_p, |emit| {
                for (x, &f) in b.iter().enumerate() {
                    emit(f, (x / n) as u32);
                }
            });
            let mut pos = vec![0u8; csr.targets.len()];
            let mut fill = csr.offsets.clone();
            for (x, &f) in b.iter().enumerate() {
                pos[fill[f as usize] as usize] = (x % n) as u8;
                fill[f as usize] += 1;
            }
            out.push((csr, pos));
        }
        out
    }

    /// Boundary references Σ_{p≥1}(p+1)n_p.
    pub(crate) fn boundary_refs(&self) -> u64 {
        self.bnd.iter().map(|b| b.len() as u64).sum()
    }

    /// Bytes of the boundary arrays.
    pub(crate) fn boundary_bytes(&self) -> u64 {
        4 * self.boundary_refs()
    }

    /// Bytes of the auxiliary index (sorted vertex tuples, top-cell map), not counted as
    /// references.
    pub(crate) fn aux_bytes(&self) -> u64 {
        let v: usize = self.verts.iter().map(|v| 4 * v.len()).sum();
        let t: usize = self.top_at.iter().map(|t| 8 * t.len()).sum();
        (v + t + 4 * self.cell_node.len()) as u64
    }

    pub(crate) fn cell_dim(&self, c: u32) -> usize {
        let i = self.blocks.partition_point(|b| b.0 <= c) - 1;
        self.blocks[i].1 as usize
    }

    /// Whether (p, i) is a top, and its cell id.
    pub(crate) fn top_cell(&self, p: usize, i: u32) -> Option<CellId> {
        let t = &self.top_at[p];
        t.binary_search_by_key(&i, |x| x.0)
            .ok()
            .map(|x| CellId(t[x].1))
    }

    /// Global id of (p, i).
    pub(crate) fn global(&self, p: usize, i: u32) -> SimplexId {
        SimplexId(self.level_offset[p] + i)
    }

    /// (p, i) of a global id.
    pub(crate) fn split(&self, s: SimplexId) -> (usize, u32) {
        let p = self.level_offset.partition_point(|&o| o <= s.0) - 1;
        (p, s.0 - self.level_offset[p])
    }

    /// The q-faces of (p, i) by descending boundary arcs with deduplication, as indices.
    pub(crate) fn descend(&self, p: usize, i: u32, q: usize) -> Vec<u32> {
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

    /// Flat sorted tuples of a list of (p, indices).
    pub(crate) fn tuples_of(&self, p: usize, ids: &[u32], out: &mut Vec<VertexId>) {
        out.clear();
        for &i in ids {
            out.extend(self.tuple(p, i).iter().map(|&v| VertexId(v)));
        }
        sort_flat(out, p + 1);
    }

    pub(crate) fn star_set(&self, star: &[(usize, u32)]) -> SimplexSet {
        let mut set = SimplexSet::default();
        for &(p, i) in star {
            if set.levels.len() <= p {
                set.levels.resize(p + 1, Vec::new());
            }
            set.levels[p].extend(self.tuple(p, i).iter().map(|&v| VertexId(v)));
        }
        set.normalize();
        set
    }
}

macro_rules! impl_explicit_common {
    ($t:ty) => {
        impl TopCells for $t {
            fn n_vertices(&self) -> usize {
                self.x.n_vertices as usize
            }
            fn n_top_cells(&self) -> usize {
                self.x.cell_node.len()
            }
            fn top_cell_kind(&self, c: CellId) -> CellKind {
                CellKind::Simplex(self.x.cell_dim(c.0) as u8)
            }
            /// Sorted vertices (the structure keeps no orientation).
            fn top_cell_vertices(&self, c: CellId, out: &mut Vec<VertexId>) {
                let p = self.x.cell_dim(c.0);
                out.extend(
                    self.x
                        .tuple(p, self.x.cell_node[c.index()])
                        .iter()
                        .map(|&v| VertexId(v)),
                );
            }
        }
        impl TopStar for $t {
            fn top_star(&self, s: &[VertexId], out: &mut Vec<CellId>) -> Result<(), QueryError> {
                let (raw, i) = self.x.locate(s)?;
                out.clear();
                for (p, j) in self.star_ids(raw.len() - 1, i)? {
                    if let Some(c) = self.x.top_cell(p, j) {
                        out.push(c);
                    }
                }
                out.sort_unstable();
                Ok(())
            }
        }
        impl VertexStar for $t {
            fn vertex_top_cells(&self, v: VertexId, out: &mut Vec<CellId>) {
                if self.top_star(&[v], out).is_err() {
                    out.clear();
                }
            }
        }
        impl Counts for $t {
            fn f_vector(&self) -> Result<Vec<u64>, QueryError> {
                if self.x.n_vertices == 0 {
                    return Ok(vec![]);
                }
                Ok((0..self.x.depth()).map(|p| self.x.n_at(p) as u64).collect())
            }
        }
        impl SimplexVertices for $t {
            fn n_simplices(&self) -> usize {
                *self.x.level_offset.last().unwrap_or(&0) as usize
            }
            fn simplex_vertices(&self, s: SimplexId, out: &mut Vec<VertexId>) {
                let (p, i) = self.x.split(s);
                out.clear();
                out.extend(self.x.tuple(p, i).iter().map(|&v| VertexId(v)));
            }
            fn find_simplex(&self, verts: &[VertexId]) -> Option<SimplexId> {
                let (raw, i) = self.x.locate(verts).ok()?;
                Some(self.x.global(raw.len() - 1, i))
            }
        }
        impl Boundary for $t {
            fn boundary(
                &self,
                s: &[VertexId],
                q: usize,
                out: &mut Vec<VertexId>,
            ) -> Result<(), QueryError> {
                let (raw, i) = self.x.locate(s)?;
                out.clear();
                let p = raw.len() - 1;
                if q >= p {
                    return Ok(());
                }
                let est = crate::cell::binomial(raw.len() as u64, q as u64 + 1);
                if est > DEFAULT_BUDGET {
                    return Err(QueryError::TooLarge(TooLarge::new(
                        format!("boundary R_{p},{q}"),
                        est,
                        DEFAULT_BUDGET,
                        Unit::Simplices,
                    )));
                }
                let ids = self.x.descend(p, i, q);
                self.x.tuples_of(q, &ids, out);
                Ok(())
            }
        }
        impl Coboundary for $t {
            fn coboundary(
                &self,
                s: &[VertexId],
                q: usize,
                out: &mut Vec<VertexId>,
            ) -> Result<(), QueryError> {
                let (raw, i) = self.x.locate(s)?;
                out.clear();
                let p = raw.len() - 1;
                if q <= p {
                    return Ok(());
                }
                let ids: Vec<u32> = self
                    .star_ids(p, i)?
                    .into_iter()
                    .filter(|&(d, _)| d == q)
                    .map(|(_, j)| j)
                    .collect();
                self.x.tuples_of(q, &ids, out);
                Ok(())
            }
        }
        impl Adjacency for $t {
            fn adjacent(&self, s: &[VertexId], out: &mut Vec<VertexId>) -> Result<(), QueryError> {
                let (raw, i) = self.x.locate(s)?;
                out.clear();
                let p = raw.len() - 1;
                if p == 0 {
                    self.vertex_neighbours(VertexId(raw[0]), out);
                    return Ok(());
                }
                let mut ids = Vec::new();
                for &f in self.x.facets(p, i) {
                    for (d, j) in self.star_ids(p - 1, f)? {
                        if d == p && j != i {
                            ids.push(j);
                        }
                    }
                }
                self.x.tuples_of(p, &ids, out);
                Ok(())
            }
        }
        impl Star for $t {
            fn star(&self, s: &[VertexId]) -> Result<SimplexSet, QueryError> {
                let (raw, i) = self.x.locate(s)?;
                Ok(self.x.star_set(&self.star_ids(raw.len() - 1, i)?))
            }
        }
        impl Levels for $t {
            fn for_each_simplex(
                &self,
                p: usize,
                f: &mut dyn FnMut(&[VertexId]),
            ) -> Result<(), QueryError> {
                if p >= self.x.depth() {
                    return Ok(());
                }
                let mut buf = Vec::with_capacity(p + 1);
                for t in self.x.verts[p].chunks_exact(p + 1) {
                    buf.clear();
                    buf.extend(t.iter().map(|&v| VertexId(v)));
                    f(&buf);
                }
                Ok(())
            }
        }
    };
}
pub(crate) use impl_explicit_common;

/// The incidence graph of a simplicial complex (its simplices from the simplex-tree levels).
#[derive(Clone, Debug)]
struct SimplicialIg {
    x: Explicit,
    /// Full immediate co-boundaries per level p < dim (indices at level p+1).
    cob: Vec<Csr>,
}

impl SimplicialIg {
    fn descend(&self, p: usize, i: u32, q: usize) -> Vec<u32> {
        self.x.descend(p, i, q)
    }

    fn new(k: &IndexedComplex, limit: u128) -> Result<SimplicialIg, BuildError> {
        let x = Explicit::new(k, limit)?;
        let cob = x.coboundaries().into_iter().map(|(c, _)| c).collect();
        Ok(SimplicialIg { x, cob })
    }

    /// St(σ) as (level, index) by breadth-first ascent through full co-boundaries.
    fn star_ids(&self, p: usize, i: u32) -> Result<Vec<(usize, u32)>, QueryError> {
        let mut out = vec![(p, i)];
        let mut cur = vec![i];
        let mut level = p;
        while level + 1 < self.x.depth() && !cur.is_empty() {
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
}

impl VertexAdjacency for SimplicialIg {
    fn vertex_neighbours(&self, v: VertexId, out: &mut Vec<VertexId>) {
        out.clear();
        if v.0 >= self.x.n_vertices || self.cob.is_empty() {
            return;
        }
        for &e in self.cob[0].row(v.index()) {
            let t = self.x.tuple(1, e);
            out.push(VertexId(if t[0] == v.0 { t[1] } else { t[0] }));
        }
        out.sort_unstable();
    }
}

impl_explicit_common!(SimplicialIg);

impl Storage for SimplicialIg {
    /// 2·Σ_{p≥1}(p+1)n_p: every boundary arc in both directions.
    fn refs(&self) -> u64 {
        self.x.boundary_refs() + self.cob.iter().map(|c| c.n_refs() as u64).sum::<u64>()
    }
    fn bytes(&self) -> u64 {
        self.x.boundary_bytes() + self.cob.iter().map(|c| c.bytes() as u64).sum::<u64>()
    }
}

/// The incidence graph. See the [module docs](self).
///
/// ```
/// use starplex::tds::ig::IncidenceGraph;
/// use starplex::topo::{Boundary, Storage};
/// use starplex::ids::VertexId;
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// // k: the triangles 0-1-2 and 1-3-2, sharing the edge 1-2
/// let ig = IncidenceGraph::new(&k, &Default::default()).unwrap();
/// // Boundary and co-boundary references: 2 * (2 * 5 edges + 3 * 2 triangles).
/// assert_eq!(ig.refs(), 32);
/// let mut out = Vec::new();
/// ig.boundary(&[VertexId(1), VertexId(3)], 0, &mut out).unwrap();
/// assert_eq!(out, [VertexId(1), VertexId(3)]);
/// ```
///
/// A CP complex (quads, pyramids, prisms, hexahedra, mixed with simplices) is held the same
/// way, its cells taken from the kinds' face tables: edges are the tables' edges (a quad's
/// diagonal is not one), a 2-cell is a triangle or a quad, and a face shared by two cells is
/// one node. A cell is named by its canonical key, its sorted vertices, as the Stellar tree's
/// face lists name CP faces. [`TopCells`], [`VertexStar`], [`VertexAdjacency`], [`TopStar`],
/// [`Counts`] (cells per dimension) and [`SimplexVertices`] (keys of any length) answer for
/// every cell ([`TopCells::top_cell_vertices`] keeps the input order of a CP complex's tops,
/// which the face tables index); the relations whose answer is a flat list of sorted (q+1)-vertex tuples
/// ([`Boundary`], [`Coboundary`], [`Adjacency`], [`Star`], [`Levels`]) answer when the cells
/// listed are simplices and return [`QueryError::NotSimplicial`], naming the first quad or
/// 3-cell, otherwise. The id-based relations ([`IncidenceGraph::cell_faces`],
/// [`IncidenceGraph::cell_cofaces`], [`IncidenceGraph::cell_adjacent`]) answer everything.
///
/// ```
/// use starplex::complex::{ComplexBuilder, BuildOptions};
/// use starplex::cell::CellKind;
/// use starplex::ids::{CellId, VertexId};
/// use starplex::tds::ig::IncidenceGraph;
/// use starplex::topo::{Boundary, Counts, SimplexVertices, VertexAdjacency, VertexStar};
/// // two quads sharing the edge 1-4, and a triangle on the edge 4-5
/// let mut b = ComplexBuilder::new(2).unwrap();
/// for p in [[0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [0.0, 1.0], [1.0, 1.0], [2.0, 1.0], [1.5, 2.0]] {
///     b.push_vertex(&p).unwrap();
/// }
/// b.push_cell(CellKind::Quad, &[0, 1, 4, 3]).unwrap();
/// b.push_cell(CellKind::Quad, &[1, 2, 5, 4]).unwrap();
/// b.push_cell(CellKind::Simplex(2), &[4, 5, 6]).unwrap();
/// let k = b.build(&BuildOptions::default()).unwrap().0;
/// let ig = IncidenceGraph::new(&k, &Default::default()).unwrap();
/// assert_eq!(ig.f_vector().unwrap(), vec![7, 9, 3]); // no diagonals
/// let mut vv = Vec::new();
/// ig.vertex_neighbours(VertexId(4), &mut vv);
/// assert_eq!(vv, [VertexId(1), VertexId(3), VertexId(5), VertexId(6)]);
/// let mut vt = Vec::new();
/// ig.vertex_top_cells(VertexId(5), &mut vt);
/// assert_eq!(vt, [CellId(1), CellId(2)]);
/// // a quad is named by its sorted vertices; its edges are simplices
/// let v = |x: &[u32]| x.iter().map(|&i| VertexId(i)).collect::<Vec<_>>();
/// let mut edges = Vec::new();
/// ig.boundary(&v(&[4, 1, 2, 5]), 1, &mut edges).unwrap();
/// assert_eq!(edges, v(&[1, 2, 1, 4, 2, 5, 4, 5]));
/// // the 2-cells at the edge 4-5, by id: a quad and a triangle
/// let e = ig.find_simplex(&v(&[4, 5])).unwrap();
/// let cells: Vec<Vec<VertexId>> = ig.cell_cofaces(e, 2).unwrap().into_iter().map(|c| {
///     let mut vs = Vec::new();
///     ig.simplex_vertices(c, &mut vs);
///     vs
/// }).collect();
/// assert_eq!(cells, [v(&[1, 2, 4, 5]), v(&[4, 5, 6])]);
/// ```
#[derive(Clone, Debug)]
pub struct IncidenceGraph {
    repr: Repr,
}

#[derive(Clone, Debug)]
enum Repr {
    Simplices(SimplicialIg),
    Cells(cells::CellGraph),
}

/// Runs `$e` with `$g` bound to the representation.
macro_rules! each {
    ($self:expr, $g:ident => $e:expr) => {
        match &$self.repr {
            Repr::Simplices($g) => $e,
            Repr::Cells($g) => $e,
        }
    };
}

impl IncidenceGraph {
    /// Builds every simplex (every cell, for a CP complex) with its boundary and co-boundary.
    ///
    /// ```
    /// use starplex::limits::Limits;
    /// use starplex::tds::{ig::IncidenceGraph, simplex_tree::BuildError};
    /// use starplex::topo::Counts;
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// # let mut b = ComplexBuilder::new(1).unwrap();
    /// # for x in 0..4 { b.push_vertex(&[x as f64]).unwrap(); }
    /// # b.push_cell(CellKind::Simplex(3), &[0, 1, 2, 3]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// // k: the tetrahedron 0-1-2-3
    /// let ig = IncidenceGraph::new(&k, &Limits::default()).unwrap();
    /// assert_eq!(ig.f_vector().unwrap(), vec![4, 6, 4, 1]);
    /// let tight = Limits { stored_simplices: 10, ..Limits::default() };
    /// assert!(matches!(IncidenceGraph::new(&k, &tight), Err(BuildError::TooLarge { .. })));
    /// ```
    ///
    /// # Errors
    /// More than `limits.stored_simplices` simplices or cells (refused before allocating them).
    pub fn new(k: &IndexedComplex, limits: &Limits) -> Result<IncidenceGraph, BuildError> {
        let limit = limits.stored_simplices;
        let repr = if k.is_simplicial() {
            Repr::Simplices(SimplicialIg::new(k, limit)?)
        } else {
            Repr::Cells(cells::CellGraph::new(k, limit)?)
        };
        Ok(IncidenceGraph { repr })
    }

    /// Bytes of the auxiliary index (sorted vertex tuples, top-cell map), not counted in
    /// [`Storage::bytes`].
    ///
    /// ```
    /// use starplex::tds::ig::IncidenceGraph;
    /// use starplex::topo::Storage;
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// # let mut b = ComplexBuilder::new(1).unwrap();
    /// # for x in 0..4 { b.push_vertex(&[x as f64]).unwrap(); }
    /// # b.push_cell(CellKind::Simplex(3), &[0, 1, 2, 3]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// // k: the tetrahedron 0-1-2-3
    /// let ig = IncidenceGraph::new(&k, &Default::default()).unwrap();
    /// assert!(ig.aux_bytes() > 0);
    /// assert!(ig.bytes() >= 4 * ig.refs()); // aux_bytes is not part of bytes
    /// ```
    pub fn aux_bytes(&self) -> u64 {
        match &self.repr {
            Repr::Simplices(g) => g.x.aux_bytes(),
            Repr::Cells(g) => g.aux_bytes(),
        }
    }

    /// The dimension of cell `c` (a [`SimplexVertices`] id), `None` for an id out of range.
    ///
    /// ```
    /// use starplex::tds::ig::IncidenceGraph;
    /// use starplex::topo::SimplexVertices;
    /// use starplex::ids::{SimplexId, VertexId};
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// # let mut b = ComplexBuilder::new(2).unwrap();
    /// # for p in [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]] { b.push_vertex(&p).unwrap(); }
    /// # b.push_cell(CellKind::Quad, &[0, 1, 2, 3]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// // k: the quad 0-1-2-3
    /// let ig = IncidenceGraph::new(&k, &Default::default()).unwrap();
    /// let q = ig.find_simplex(&[VertexId(3), VertexId(2), VertexId(1), VertexId(0)]).unwrap();
    /// assert_eq!(ig.cell_dim(q), Some(2));
    /// assert_eq!(ig.cell_dim(SimplexId(99)), None);
    /// ```
    pub fn cell_dim(&self, c: SimplexId) -> Option<usize> {
        self.split(c).map(|(p, _)| p)
    }

    fn split(&self, c: SimplexId) -> Option<(usize, u32)> {
        match &self.repr {
            Repr::Simplices(g) => (c.0 < *g.x.level_offset.last()?).then(|| g.x.split(c)),
            Repr::Cells(g) => g.split(c),
        }
    }

    fn globals(&self, p: usize, ids: Vec<u32>) -> Vec<SimplexId> {
        ids.into_iter()
            .map(|i| match &self.repr {
                Repr::Simplices(g) => g.x.global(p, i),
                Repr::Cells(g) => g.global(p, i),
            })
            .collect()
    }

    /// R_{p,q}, q < p: the q-faces of cell `c` by id (quads and 3-cells included), sorted;
    /// empty for q ≥ p.
    ///
    /// # Errors
    /// An id out of range.
    ///
    /// ```
    /// use starplex::tds::ig::IncidenceGraph;
    /// use starplex::topo::SimplexVertices;
    /// use starplex::ids::VertexId;
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// # let mut b = ComplexBuilder::new(3).unwrap();
    /// # for i in 0..8 { b.push_vertex(&[(i & 1) as f64, (i >> 1 & 1) as f64, (i >> 2) as f64]).unwrap(); }
    /// # b.push_cell(CellKind::Hex, &[0, 1, 3, 2, 4, 5, 7, 6]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// // k: one hexahedron
    /// let ig = IncidenceGraph::new(&k, &Default::default()).unwrap();
    /// let hex = ig.find_simplex(&(0..8).map(VertexId).collect::<Vec<_>>()).unwrap();
    /// assert_eq!(ig.cell_faces(hex, 2).unwrap().len(), 6);
    /// assert_eq!(ig.cell_faces(hex, 1).unwrap().len(), 12);
    /// ```
    pub fn cell_faces(&self, c: SimplexId, q: usize) -> Result<Vec<SimplexId>, QueryError> {
        let (p, i) = self.split(c).ok_or(QueryError::NotInComplex(vec![]))?;
        if q >= p {
            return Ok(Vec::new());
        }
        let ids = each!(self, g => g.descend(p, i, q));
        Ok(self.globals(q, ids))
    }

    /// R_{p,q}, q > p: the q-cells having cell `c` as a face, by id, sorted; empty for q ≤ p.
    ///
    /// # Errors
    /// An id out of range; a star over the budget.
    ///
    /// ```
    /// use starplex::tds::ig::IncidenceGraph;
    /// use starplex::topo::SimplexVertices;
    /// use starplex::ids::VertexId;
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// # let mut b = ComplexBuilder::new(3).unwrap();
    /// # for i in 0..8 { b.push_vertex(&[(i & 1) as f64, (i >> 1 & 1) as f64, (i >> 2) as f64]).unwrap(); }
    /// # b.push_cell(CellKind::Hex, &[0, 1, 3, 2, 4, 5, 7, 6]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// // k: one hexahedron
    /// let ig = IncidenceGraph::new(&k, &Default::default()).unwrap();
    /// let v0 = ig.find_simplex(&[VertexId(0)]).unwrap();
    /// assert_eq!(ig.cell_cofaces(v0, 2).unwrap().len(), 3); // three quads at a corner
    /// ```
    pub fn cell_cofaces(&self, c: SimplexId, q: usize) -> Result<Vec<SimplexId>, QueryError> {
        let (p, i) = self.split(c).ok_or(QueryError::NotInComplex(vec![]))?;
        if q <= p {
            return Ok(Vec::new());
        }
        let ids: Vec<u32> = each!(self, g => g.star_ids(p, i))?
            .into_iter()
            .filter(|&(d, _)| d == q)
            .map(|(_, j)| j)
            .collect();
        Ok(self.globals(q, ids))
    }

    /// R_{p,p}: the p-cells sharing a (p-1)-face with cell `c` (p ≥ 1), or the vertices
    /// sharing an edge with it (p = 0), by id, sorted.
    ///
    /// # Errors
    /// An id out of range.
    ///
    /// ```
    /// use starplex::tds::ig::IncidenceGraph;
    /// use starplex::topo::SimplexVertices;
    /// use starplex::ids::VertexId;
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// # let mut b = ComplexBuilder::new(3).unwrap();
    /// # for i in 0..8 { b.push_vertex(&[(i & 1) as f64, (i >> 1 & 1) as f64, (i >> 2) as f64]).unwrap(); }
    /// # b.push_cell(CellKind::Hex, &[0, 1, 3, 2, 4, 5, 7, 6]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// // k: one hexahedron
    /// let ig = IncidenceGraph::new(&k, &Default::default()).unwrap();
    /// let bottom = ig.find_simplex(&[VertexId(0), VertexId(1), VertexId(2), VertexId(3)]).unwrap();
    /// assert_eq!(ig.cell_adjacent(bottom).unwrap().len(), 4); // the four side quads
    /// ```
    pub fn cell_adjacent(&self, c: SimplexId) -> Result<Vec<SimplexId>, QueryError> {
        let (p, i) = self.split(c).ok_or(QueryError::NotInComplex(vec![]))?;
        let ids = match &self.repr {
            Repr::Cells(g) => g.adjacent_ids(p, i),
            Repr::Simplices(g) if p == 0 => {
                let mut vv = Vec::new();
                g.vertex_neighbours(VertexId(i), &mut vv);
                vv.into_iter().map(|v| v.0).collect()
            }
            Repr::Simplices(g) => {
                let mut ids: Vec<u32> = Vec::new();
                for &f in g.x.facets(p, i) {
                    for (d, j) in g.star_ids(p - 1, f)? {
                        if d == p && j != i {
                            ids.push(j);
                        }
                    }
                }
                ids.sort_unstable();
                ids.dedup();
                ids
            }
        };
        Ok(self.globals(p, ids))
    }
}

impl TopCells for IncidenceGraph {
    fn n_vertices(&self) -> usize {
        each!(self, g => g.n_vertices())
    }
    fn n_top_cells(&self) -> usize {
        each!(self, g => g.n_top_cells())
    }
    fn top_cell_kind(&self, c: CellId) -> CellKind {
        each!(self, g => g.top_cell_kind(c))
    }
    /// Sorted vertices for a simplicial complex (the structure keeps no orientation); input
    /// (VTK) order for a CP complex, whose face tables index it.
    fn top_cell_vertices(&self, c: CellId, out: &mut Vec<VertexId>) {
        each!(self, g => g.top_cell_vertices(c, out))
    }
}

impl VertexStar for IncidenceGraph {
    fn vertex_top_cells(&self, v: VertexId, out: &mut Vec<CellId>) {
        each!(self, g => g.vertex_top_cells(v, out))
    }
}

impl VertexAdjacency for IncidenceGraph {
    fn vertex_neighbours(&self, v: VertexId, out: &mut Vec<VertexId>) {
        each!(self, g => g.vertex_neighbours(v, out))
    }
}

impl TopStar for IncidenceGraph {
    fn top_star(&self, s: &[VertexId], out: &mut Vec<CellId>) -> Result<(), QueryError> {
        each!(self, g => g.top_star(s, out))
    }
}

impl Counts for IncidenceGraph {
    fn f_vector(&self) -> Result<Vec<u64>, QueryError> {
        each!(self, g => g.f_vector())
    }
}

impl SimplexVertices for IncidenceGraph {
    fn n_simplices(&self) -> usize {
        each!(self, g => g.n_simplices())
    }
    fn simplex_vertices(&self, s: SimplexId, out: &mut Vec<VertexId>) {
        each!(self, g => g.simplex_vertices(s, out))
    }
    fn find_simplex(&self, verts: &[VertexId]) -> Option<SimplexId> {
        each!(self, g => g.find_simplex(verts))
    }
}

impl Boundary for IncidenceGraph {
    fn boundary(
        &self,
        s: &[VertexId],
        q: usize,
        out: &mut Vec<VertexId>,
    ) -> Result<(), QueryError> {
        each!(self, g => g.boundary(s, q, out))
    }
}

impl Coboundary for IncidenceGraph {
    fn coboundary(
        &self,
        s: &[VertexId],
        q: usize,
        out: &mut Vec<VertexId>,
    ) -> Result<(), QueryError> {
        each!(self, g => g.coboundary(s, q, out))
    }
}

impl Adjacency for IncidenceGraph {
    fn adjacent(&self, s: &[VertexId], out: &mut Vec<VertexId>) -> Result<(), QueryError> {
        each!(self, g => g.adjacent(s, out))
    }
}

impl Star for IncidenceGraph {
    fn star(&self, s: &[VertexId]) -> Result<SimplexSet, QueryError> {
        each!(self, g => g.star(s))
    }
}

impl Levels for IncidenceGraph {
    fn for_each_simplex(&self, p: usize, f: &mut dyn FnMut(&[VertexId])) -> Result<(), QueryError> {
        each!(self, g => g.for_each_simplex(p, f))
    }
}

impl Storage for IncidenceGraph {
    /// 2·Σ_{p≥1}(p+1)n_p for a simplicial complex (every boundary arc in both directions);
    /// for a CP complex likewise 2·(the cells' facet counts summed).
    fn refs(&self) -> u64 {
        each!(self, g => g.refs())
    }
    fn bytes(&self) -> u64 {
        each!(self, g => g.bytes())
    }
}
