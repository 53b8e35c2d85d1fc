//! The CASC complex behind the shared query interface: see [`HasseQueries`].
use super::{Hasse, HasseError, LevelTypes, Node};
use crate::cell::CellKind;
use crate::complex::IndexedComplex;
use crate::ids::{CellId, SimplexId, VertexId};
use crate::limits::{Limits, TooLarge, Unit};
use crate::tds::simplex_tree::{simplex_estimate, BuildError};
use crate::topo::from_tops::boundary_of_sorted;
use crate::topo::{
    sort_flat, sorted_simplex, Adjacency, Boundary, Coboundary, Counts, Levels, QueryError,
    SimplexSet, SimplexVertices, Star, Storage, TopCells, TopStar, VertexAdjacency, VertexStar,
    DEFAULT_BUDGET,
};

/// Marks a node that is not a top cell in [`HasseQueries`]'s node → cell table.
const NOT_TOP: u32 = u32::MAX;

/// The CASC complex behind the shared query interface ([`crate::topo`]): [`HasseQueries`] wraps a
/// [`Hasse`] built from an [`IndexedComplex`] and remembers which node is which top cell, so the
/// Hasse diagram answers every relation of the Mangrove suite, natively, by walking its up and
/// down incidences:
///
/// * VT and St_T(σ): a breadth-first walk up from σ, keeping the nodes without cofaces;
/// * VV: the up list of a vertex is keyed by the vertex added, so it *is* the neighbour list;
/// * boundary R_{p,q}: down steps from the node; co-boundary R_{p,q} and the star: up steps;
/// * adjacency R_{p,p}: down to each facet, then up to its other cofaces (Alg. 3 of CASC);
/// * counts and levels: the per-dimension arrays.
///
/// Like the other structures that store every simplex, it refuses to build (with an estimate)
/// when the complex has more simplices than a limit, and holds simplices only. Top cells come
/// back with sorted vertices (the Hasse diagram stores labels sorted, not the input's order).
///
/// ```
/// use starplex::cell::CellKind;
/// use starplex::complex::{BuildOptions, ComplexBuilder};
/// use starplex::hasse::HasseQueries;
/// use starplex::ids::{CellId, VertexId};
/// use starplex::topo::{Adjacency, VertexAdjacency, VertexStar};
/// let mut b = ComplexBuilder::new(2).unwrap();
/// for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0], [5.0, 5.0]] {
///     b.push_vertex(&p).unwrap();
/// }
/// b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
/// let k = b.build(&BuildOptions::default()).unwrap().0;
/// let h = HasseQueries::new(&k, &Default::default()).unwrap();
/// let mut vt = Vec::new();
/// h.vertex_top_cells(VertexId(2), &mut vt);
/// assert_eq!(vt, vec![CellId(0), CellId(1)]);
/// let mut vv = Vec::new();
/// h.vertex_neighbours(VertexId(4), &mut vv); // isolated vertex
/// assert!(vv.is_empty());
/// let mut adj = Vec::new();
/// h.adjacent(&[VertexId(0), VertexId(1), VertexId(2)], &mut adj).unwrap();
/// assert_eq!(adj, vec![VertexId(1), VertexId(2), VertexId(3)]);
/// ```
#[derive(Clone, Debug)]
pub struct HasseQueries {
    h: Hasse,
    n_vertices: u32,
    /// Node of every top cell of the input.
    cell_node: Vec<Node>,
    /// Per dimension, node slot → top cell id (or [`NOT_TOP`]).
    top_of: Vec<Vec<u32>>,
    /// Global simplex id of the first slot of each dimension.
    offset: Vec<u32>,
    /// Per dimension: whether the level's slots are in lexicographic order of their vertices
    /// (true for the level-by-level build of dimension <= 3 without isolated vertices).
    lex_sorted: Vec<bool>,
}

impl HasseQueries {
    /// Builds the Hasse diagram of every simplex of `k` (isolated vertices included as
    /// 0-simplices) and the top-cell tables.
    ///
    /// # Errors
    /// [`HasseError::NotSimplicial`] for a CP cell; [`HasseError::TooLarge`] when `k` may
    /// have more than `limits.stored_simplices` simplices (every face of every top cell,
    /// counted before anything is allocated).
    ///
    /// ```
    /// use starplex::cell::CellKind;
    /// use starplex::complex::{BuildOptions, ComplexBuilder};
    /// let mut b = ComplexBuilder::new(1).unwrap();
    /// for x in 0..41 { b.push_vertex(&[x as f64]).unwrap(); }
    /// b.push_cell(CellKind::Simplex(40), &(0..41).collect::<Vec<u32>>()).unwrap();
    /// let k = b.build(&BuildOptions::default()).unwrap().0;
    /// let limits = starplex::limits::Limits::default(); // 2^31 stored simplices
    /// let e = starplex::hasse::HasseQueries::new(&k, &limits).unwrap_err();
    /// assert!(e.to_string().contains("over the budget of 2147483648"), "{e}");
    /// ```
    pub fn new(k: &IndexedComplex, limits: &Limits) -> Result<HasseQueries, HasseError> {
        let max_simplices = limits.stored_simplices;
        let est = simplex_estimate(k)?;
        if est > max_simplices {
            return Err(BuildError::too_many(est, max_simplices).into());
        }
        let mut h: Hasse = Hasse::from_indexed(k)?;
        let nv = k.n_vertices();
        for v in 0..nv as u32 {
            if h.vertex(VertexId(v)).is_none() {
                h.insert(&[VertexId(v)])?;
            }
        }
        let levels = h.dim().map_or(0, |d| d + 1);
        let mut top_of: Vec<Vec<u32>> = (0..levels).map(|d| vec![NOT_TOP; h.n_slots(d)]).collect();
        let mut cell_node = Vec::with_capacity(k.n_cells());
        let mut buf: Vec<VertexId> = Vec::new();
        for c in k.cells() {
            buf.clear();
            buf.extend(c.vertices.iter().map(|&v| VertexId(v)));
            buf.sort_unstable();
            let n = h
                .find(&buf)
                .ok_or_else(|| HasseError::NotFound(buf.clone()))?;
            top_of[n.dim as usize][n.id.index()] = c.id.0;
            cell_node.push(n);
        }
        let mut offset = Vec::with_capacity(levels + 1);
        let mut acc = 0u32;
        for d in 0..levels {
            offset.push(acc);
            acc += h.n_slots(d) as u32;
        }
        offset.push(acc);
        let lex_sorted = (0..levels)
            .map(|d| {
                let mut prev: Option<&[VertexId]> = None;
                h.level(d).all(|n| {
                    let v = h.vertices(n);
                    let ok = prev.is_none_or(|p| p < v);
                    prev = Some(v);
                    ok
                })
            })
            .collect();
        Ok(HasseQueries {
            h,
            n_vertices: nv as u32,
            cell_node,
            top_of,
            offset,
            lex_sorted,
        })
    }

    /// The Hasse complex inside.
    ///
    /// ```
    /// use starplex::cell::CellKind;
    /// use starplex::complex::{BuildOptions, ComplexBuilder};
    /// let mut b = ComplexBuilder::new(1).unwrap();
    /// for x in 0..2 { b.push_vertex(&[x as f64]).unwrap(); }
    /// b.push_cell(CellKind::Simplex(1), &[0, 1]).unwrap();
    /// let k = b.build(&BuildOptions::default()).unwrap().0;
    /// let q = starplex::hasse::HasseQueries::new(&k, &Default::default()).unwrap();
    /// assert_eq!(q.hasse().f_vector(), vec![2, 1]);
    /// ```
    pub fn hasse(&self) -> &Hasse {
        &self.h
    }

    fn node(&self, s: &[VertexId]) -> Result<(Vec<VertexId>, Node), QueryError> {
        node_of(&self.h, s)
    }

    fn star_ids(&self, n: Node) -> Result<Vec<Vec<u32>>, QueryError> {
        star_ids(&self.h, n)
    }
}

/// The node of simplex `s` (sorted), or why not.
fn node_of<L: LevelTypes>(
    h: &Hasse<L>,
    s: &[VertexId],
) -> Result<(Vec<VertexId>, Node), QueryError> {
    let s = sorted_simplex(s)?;
    match h.find(&s) {
        Some(n) => Ok((s, n)),
        None => Err(QueryError::NotInComplex(s.iter().map(|v| v.0).collect())),
    }
}

/// Ids per level of the star of `n`, refused over the budget.
fn star_ids<L: LevelTypes>(h: &Hasse<L>, n: Node) -> Result<Vec<Vec<u32>>, QueryError> {
    let ids = h.star_ids(n);
    let total: u128 = ids.iter().map(|l| l.len() as u128).sum();
    if total > DEFAULT_BUDGET {
        return Err(QueryError::TooLarge(TooLarge::new(
            format!("star of {:?}", h.vertices(n)),
            total,
            DEFAULT_BUDGET,
            Unit::Simplices,
        )));
    }
    Ok(ids)
}

fn push_vertices<L: LevelTypes>(h: &Hasse<L>, d: usize, i: u32, out: &mut Vec<VertexId>) {
    out.extend_from_slice(h.vertices(Node::new(d as u32, SimplexId(i))));
}

impl TopCells for HasseQueries {
    fn n_vertices(&self) -> usize {
        self.n_vertices as usize
    }
    fn n_top_cells(&self) -> usize {
        self.cell_node.len()
    }
    fn top_cell_kind(&self, c: CellId) -> CellKind {
        CellKind::Simplex(self.cell_node[c.index()].dim as u8)
    }
    /// Sorted vertices: the Hasse diagram does not keep the input orientation.
    fn top_cell_vertices(&self, c: CellId, out: &mut Vec<VertexId>) {
        out.extend_from_slice(self.h.vertices(self.cell_node[c.index()]));
    }
}

impl TopStar for HasseQueries {
    fn top_star(&self, s: &[VertexId], out: &mut Vec<CellId>) -> Result<(), QueryError> {
        out.clear();
        let (_, n) = self.node(s)?;
        for (d, l) in self.star_ids(n)?.iter().enumerate() {
            for &i in l {
                let c = self.top_of[d][i as usize];
                if c != NOT_TOP {
                    out.push(CellId(c));
                }
            }
        }
        out.sort_unstable();
        Ok(())
    }
}

impl VertexStar for HasseQueries {
    fn vertex_top_cells(&self, v: VertexId, out: &mut Vec<CellId>) {
        if self.top_star(&[v], out).is_err() {
            out.clear();
        }
    }
}

impl VertexAdjacency for HasseQueries {
    fn vertex_neighbours(&self, v: VertexId, out: &mut Vec<VertexId>) {
        self.h.vertex_neighbours(v, out)
    }
}

impl Counts for HasseQueries {
    fn f_vector(&self) -> Result<Vec<u64>, QueryError> {
        Counts::f_vector(&self.h)
    }
}

impl SimplexVertices for HasseQueries {
    fn n_simplices(&self) -> usize {
        self.h.len()
    }
    fn simplex_vertices(&self, s: SimplexId, out: &mut Vec<VertexId>) {
        out.clear();
        let d = self.offset.partition_point(|&o| o <= s.0) - 1;
        push_vertices(&self.h, d, s.0 - self.offset[d], out);
    }
    fn find_simplex(&self, verts: &[VertexId]) -> Option<SimplexId> {
        let (_, n) = self.node(verts).ok()?;
        Some(SimplexId(self.offset[n.dim as usize] + n.id.0))
    }
}

impl Boundary for HasseQueries {
    fn boundary(
        &self,
        s: &[VertexId],
        q: usize,
        out: &mut Vec<VertexId>,
    ) -> Result<(), QueryError> {
        self.h.boundary(s, q, out)
    }
}

impl Coboundary for HasseQueries {
    fn coboundary(
        &self,
        s: &[VertexId],
        q: usize,
        out: &mut Vec<VertexId>,
    ) -> Result<(), QueryError> {
        self.h.coboundary(s, q, out)
    }
}

impl Adjacency for HasseQueries {
    fn adjacent(&self, s: &[VertexId], out: &mut Vec<VertexId>) -> Result<(), QueryError> {
        self.h.adjacent(s, out)
    }
}

impl Star for HasseQueries {
    fn star(&self, s: &[VertexId]) -> Result<SimplexSet, QueryError> {
        Star::star(&self.h, s)
    }
}

impl Levels for HasseQueries {
    /// Lexicographic order, as every structure of the suite (a level built out of order is
    /// sorted on the fly).
    fn for_each_simplex(&self, p: usize, f: &mut dyn FnMut(&[VertexId])) -> Result<(), QueryError> {
        if self.lex_sorted.get(p).copied().unwrap_or(true) {
            for n in self.h.level(p) {
                f(self.h.vertices(n));
            }
            return Ok(());
        }
        let mut all = Vec::with_capacity(self.h.n_simplices(p) * (p + 1));
        for n in self.h.level(p) {
            all.extend_from_slice(self.h.vertices(n));
        }
        sort_flat(&mut all, p + 1);
        for t in all.chunks_exact(p + 1) {
            f(t);
        }
        Ok(())
    }
}

impl Storage for HasseQueries {
    /// Every down incidence (k+1 per k-simplex) and every up incidence (as many in all): the
    /// Hasse diagram's edges counted from both ends.
    fn refs(&self) -> u64 {
        let down: u64 = self
            .h
            .f_vector()
            .iter()
            .enumerate()
            .skip(1)
            .map(|(k, &n)| (k as u64 + 1) * n as u64)
            .sum();
        2 * down
    }
    /// The diagram's topology plus the top-cell tables.
    fn bytes(&self) -> u64 {
        (self.h.topology_bytes()
            + 8 * self.cell_node.len()
            + self.top_of.iter().map(|t| 4 * t.len()).sum::<usize>()
            + 4 * self.offset.len()) as u64
    }
}

// The vertex-list relations, answered by any Hasse complex whatever its level data
// (`HasseQueries` adds the top-cell numbering on top of them).

impl<L: LevelTypes> VertexAdjacency for Hasse<L> {
    /// The keys of the vertex's up list (sorted by construction).
    fn vertex_neighbours(&self, v: VertexId, out: &mut Vec<VertexId>) {
        out.clear();
        if let Some(n) = self.vertex(v) {
            out.extend(self.up_keyed(n).map(|(w, _)| w));
            out.sort_unstable();
        }
    }
}

impl<L: LevelTypes> Counts for Hasse<L> {
    fn f_vector(&self) -> Result<Vec<u64>, QueryError> {
        Ok(Hasse::f_vector(self)
            .into_iter()
            .map(|x| x as u64)
            .collect())
    }
}

impl<L: LevelTypes> Boundary for Hasse<L> {
    /// q = p-1 by one down step; lower q by the combinatorial faces of the node's (stored,
    /// sorted) vertices, which the diagram guarantees are all present.
    fn boundary(
        &self,
        s: &[VertexId],
        q: usize,
        out: &mut Vec<VertexId>,
    ) -> Result<(), QueryError> {
        let (s, n) = node_of(self, s)?;
        out.clear();
        if q + 2 == s.len() {
            for f in Hasse::down(self, n) {
                out.extend_from_slice(self.vertices(f));
            }
            sort_flat(out, q + 1);
            return Ok(());
        }
        boundary_of_sorted(&s, q, DEFAULT_BUDGET, out)
    }
}

impl<L: LevelTypes> Coboundary for Hasse<L> {
    fn coboundary(
        &self,
        s: &[VertexId],
        q: usize,
        out: &mut Vec<VertexId>,
    ) -> Result<(), QueryError> {
        out.clear();
        let (s, n) = node_of(self, s)?;
        if q < s.len() {
            return Ok(());
        }
        if q == s.len() {
            for c in Hasse::up(self, n) {
                out.extend_from_slice(self.vertices(c));
            }
        } else if let Some(l) = star_ids(self, n)?.get(q) {
            for &i in l {
                push_vertices(self, q, i, out);
            }
        }
        sort_flat(out, q + 1);
        Ok(())
    }
}

impl<L: LevelTypes> Adjacency for Hasse<L> {
    /// Alg. 3 of CASC: down to every facet, up to its other cofaces; for a vertex, VV.
    fn adjacent(&self, s: &[VertexId], out: &mut Vec<VertexId>) -> Result<(), QueryError> {
        let (s, n) = node_of(self, s)?;
        out.clear();
        if s.len() == 1 {
            VertexAdjacency::vertex_neighbours(self, s[0], out);
            return Ok(());
        }
        for m in self.neighbours_by_face(n) {
            out.extend_from_slice(self.vertices(m));
        }
        sort_flat(out, s.len());
        Ok(())
    }
}

impl<L: LevelTypes> Star for Hasse<L> {
    fn star(&self, s: &[VertexId]) -> Result<SimplexSet, QueryError> {
        let (_, n) = node_of(self, s)?;
        let mut set = SimplexSet::default();
        for (d, l) in star_ids(self, n)?.iter().enumerate() {
            let mut buf = Vec::new();
            for &i in l {
                buf.clear();
                push_vertices(self, d, i, &mut buf);
                set.insert(&buf);
            }
        }
        set.normalize();
        Ok(set)
    }
}

impl<L: LevelTypes> Levels for Hasse<L> {
    /// Lexicographic order, as every structure of the suite (a level not in that order, after
    /// edits, is sorted on the fly).
    ///
    /// ```
    /// use starplex::hasse::Hasse;
    /// use starplex::ids::VertexId;
    /// use starplex::topo::{generic, Boundary, Levels};
    /// let mut h: Hasse<(f64, (), u8)> = Hasse::new();
    /// h.insert(&[VertexId(0), VertexId(1), VertexId(2)]).unwrap();
    /// // any Hasse complex, whatever its data per level, answers the shared queries
    /// assert_eq!(generic::euler_characteristic(&h).unwrap(), 1);
    /// let mut edges = Vec::new();
    /// h.for_each_simplex(1, &mut |e| edges.push(e.to_vec())).unwrap();
    /// assert_eq!(edges.len(), 3);
    /// let mut out = Vec::new();
    /// h.boundary(&[VertexId(0), VertexId(1), VertexId(2)], 0, &mut out).unwrap();
    /// assert_eq!(out, [VertexId(0), VertexId(1), VertexId(2)]);
    /// ```
    fn for_each_simplex(&self, p: usize, f: &mut dyn FnMut(&[VertexId])) -> Result<(), QueryError> {
        let mut prev: Option<&[VertexId]> = None;
        let sorted = self.level(p).all(|n| {
            let v = self.vertices(n);
            let ok = prev.is_none_or(|q| q < v);
            prev = Some(v);
            ok
        });
        if sorted {
            for n in self.level(p) {
                f(self.vertices(n));
            }
            return Ok(());
        }
        let mut all = Vec::with_capacity(self.n_simplices(p) * (p + 1));
        for n in self.level(p) {
            all.extend_from_slice(self.vertices(n));
        }
        sort_flat(&mut all, p + 1);
        for t in all.chunks_exact(p + 1) {
            f(t);
        }
        Ok(())
    }
}
