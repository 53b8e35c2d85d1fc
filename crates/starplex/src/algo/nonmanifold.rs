//! Non-manifold singularities (vertices and edges), written once against [`TopCells`] +
//! [`VertexStar`], so it runs on every structure (VT, IA*, IS, incidence graph, simplex tree).
//!
//! **Definition used (one for mixed dimensions).** A simplex σ is *manifold* when its
//! top-restricted star St_T(σ) is pure of some dimension k (all tops containing σ have
//! dimension k) and its link Lk(σ) is a (k-dim σ-1)-sphere or ball. So the dimension is
//! *local*: a top edge hanging alone is a 1-manifold piece, a surface is a 2-manifold, but the
//! vertex where a dangling edge meets a surface is non-manifold (its star is not pure); an
//! isolated vertex (k = 0, empty link = the (-1)-sphere) is manifold.
//!
//! Sphere/ball recognition of the link of dimension m = k - dim σ - 1:
//! * m ≤ 1: exact (m = 0: at most 2 points; m = 1: connected, every vertex of degree ≤ 2);
//! * m = 2: exact (every link edge in ≤ 2 triangles, every link vertex's own link a path or a
//!   cycle, connected, χ = 2 without boundary or χ = 1 with boundary — the sphere and the disk);
//! * m ≥ 3: the decidable necessary conditions (connected, every ridge in ≤ 2 facets, the link
//!   of every link vertex passes the test one dimension lower); when they all pass the answer is
//!   [`Manifoldness::Unknown`] (sphere recognition is impractical for m = 3, open for m = 4,
//!   undecidable for m ≥ 5).
//!
//! ```
//! use starplex::complex::{ComplexBuilder, BuildOptions};
//! use starplex::cell::CellKind;
//! use starplex::ids::VertexId;
//! use starplex::topo::naive::VtIndex;
//! use starplex::algo::nonmanifold::{singularities, vertex_manifoldness, Manifoldness};
//! // bow-tie: two triangles sharing vertex 0
//! let mut b = ComplexBuilder::new(2).unwrap();
//! for _ in 0..5 { b.push_vertex(&[0.0, 0.0]).unwrap(); }
//! b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
//! b.push_cell(CellKind::Simplex(2), &[0, 3, 4]).unwrap();
//! let k = b.build(&BuildOptions::default()).unwrap().0;
//! let idx = VtIndex::new(&k);
//! assert_eq!(vertex_manifoldness(&idx, VertexId(0)).unwrap(), Manifoldness::NonManifold);
//! assert_eq!(vertex_manifoldness(&idx, VertexId(1)).unwrap(), Manifoldness::Manifold);
//! let r = singularities(&idx).unwrap();
//! assert_eq!(r.non_manifold_vertices, vec![VertexId(0)]);
//! assert!(r.non_manifold_edges.is_empty());
//! ```
use rustc_hash::FxHashMap;

use crate::ids::{CellId, VertexId};
use crate::topo::{QueryError, TopCells, VertexStar};

/// The answer of a manifold test.
///
/// ```
/// use starplex::algo::nonmanifold::{sphere_or_ball, Manifoldness};
/// assert_eq!(sphere_or_ball(&[vec![0, 1], vec![1, 2]], 1), Manifoldness::Manifold); // a path
/// // A 3-sphere link is not recognised: every necessary test passes, the answer is Unknown.
/// let bd4: Vec<Vec<u32>> = (0..5u32).map(|i| (0..5).filter(|&j| j != i).collect()).collect();
/// assert_eq!(sphere_or_ball(&bd4, 3), Manifoldness::Unknown);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Manifoldness {
    /// The link is a sphere or a ball of the right dimension.
    Manifold,
    /// A certificate of non-manifoldness was found.
    NonManifold,
    /// Every decidable test passed but sphere recognition is not done in this dimension.
    Unknown,
}

/// The singular simplices of a complex, with ids (sorted).
///
/// ```
/// use starplex::algo::nonmanifold::{singularities, Singularities};
/// use starplex::topo::naive::VtIndex;
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// // k: the triangles 0-1-2 and 1-3-2, sharing the edge 1-2
/// assert_eq!(singularities(&VtIndex::new(&k)).unwrap(), Singularities::default());
/// ```
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Singularities {
    /// Non-manifold vertices.
    pub non_manifold_vertices: Vec<VertexId>,
    /// Vertices whose manifoldness is undecided (links of dimension ≥ 3).
    pub unknown_vertices: Vec<VertexId>,
    /// Non-manifold edges (sorted endpoints).
    pub non_manifold_edges: Vec<[VertexId; 2]>,
    /// Undecided edges.
    pub unknown_edges: Vec<[VertexId; 2]>,
}

fn not_simplicial() -> QueryError {
    QueryError::NotSimplicial("non-manifold detection".into())
}

/// Connected components of a complex given by maximal simplices (vertex sets), by shared
/// vertices.
fn connected(maxes: &[Vec<u32>]) -> bool {
    if maxes.len() <= 1 {
        return true;
    }
    let mut ids: FxHashMap<u32, u32> = FxHashMap::default();
    for m in maxes {
        for &v in m {
            let n = ids.len() as u32;
            ids.entry(v).or_insert(n);
        }
    }
    let mut uf = crate::algo::unionfind::UnionFind::new(ids.len());
    for m in maxes {
        for w in &m[1..] {
            uf.union(ids[&m[0]], ids[w]);
        }
    }
    uf.n_sets() == 1
}

/// Tests whether the pure complex with maximal simplices `maxes` (each of m+1 vertices, sorted,
/// distinct) is an m-sphere or an m-ball.
///
/// ```
/// use starplex::algo::nonmanifold::{sphere_or_ball, Manifoldness};
/// let cycle = [vec![0, 1], vec![1, 2], vec![0, 2]];
/// assert_eq!(sphere_or_ball(&cycle, 1), Manifoldness::Manifold);
/// let claw = [vec![0, 1], vec![0, 2], vec![0, 3]]; // vertex 0 of degree 3
/// assert_eq!(sphere_or_ball(&claw, 1), Manifoldness::NonManifold);
/// assert_eq!(sphere_or_ball(&[vec![4], vec![7]], 0), Manifoldness::Manifold); // two points
/// assert_eq!(sphere_or_ball(&[], -1), Manifoldness::Manifold); // the empty (-1)-sphere
/// ```
pub fn sphere_or_ball(maxes: &[Vec<u32>], m: isize) -> Manifoldness {
    use Manifoldness::*;
    if m < 0 {
        return if maxes.is_empty() {
            Manifold
        } else {
            NonManifold
        };
    }
    if maxes.is_empty() {
        return NonManifold;
    }
    if m == 0 {
        return if maxes.len() <= 2 {
            Manifold
        } else {
            NonManifold
        };
    }
    if !connected(maxes) {
        return NonManifold;
    }
    // ridges in ≤ 2 facets
    let mut ridges: FxHashMap<Vec<u32>, u32> = FxHashMap::default();
    for f in maxes {
        for j in 0..f.len() {
            let r: Vec<u32> = f
                .iter()
                .enumerate()
                .filter(|&(i, _)| i != j)
                .map(|(_, &v)| v)
                .collect();
            *ridges.entry(r).or_insert(0) += 1;
        }
    }
    if ridges.values().any(|&c| c > 2) {
        return NonManifold;
    }
    if m == 1 {
        return Manifold; // connected graph, degrees ≤ 2: path or cycle
    }
    // every vertex's link is an (m-1)-sphere or ball
    let mut by_vertex: FxHashMap<u32, Vec<Vec<u32>>> = FxHashMap::default();
    for f in maxes {
        for &v in f {
            by_vertex
                .entry(v)
                .or_default()
                .push(f.iter().copied().filter(|&w| w != v).collect());
        }
    }
    let mut unknown = false;
    for l in by_vertex.values() {
        match sphere_or_ball(l, m - 1) {
            NonManifold => return NonManifold,
            Unknown => unknown = true,
            Manifold => {}
        }
    }
    if m == 2 {
        if unknown {
            return Unknown;
        }
        // a connected compact surface: the sphere (χ = 2, closed) or the disk (χ = 1, boundary)
        let mut edges: Vec<[u32; 2]> = Vec::new();
        for f in maxes {
            edges.push([f[0], f[1]]);
            edges.push([f[0], f[2]]);
            edges.push([f[1], f[2]]);
        }
        edges.sort_unstable();
        let boundary = ridges.values().any(|&c| c == 1);
        edges.dedup();
        let chi = by_vertex.len() as i64 - edges.len() as i64 + maxes.len() as i64;
        return match (boundary, chi) {
            (false, 2) | (true, 1) => Manifold,
            _ => NonManifold,
        };
    }
    Unknown
}

fn star_test(tops: &[Vec<u32>], sigma: &[u32]) -> Manifoldness {
    if tops.is_empty() {
        // an isolated vertex
        return Manifoldness::Manifold;
    }
    let k = tops[0].len();
    if tops.iter().any(|t| t.len() != k) {
        return Manifoldness::NonManifold;
    }
    let link: Vec<Vec<u32>> = tops
        .iter()
        .map(|t| {
            t.iter()
                .copied()
                .filter(|v| !sigma.contains(v))
                .collect::<Vec<u32>>()
        })
        .filter(|l| !l.is_empty())
        .collect();
    sphere_or_ball(&link, k as isize - sigma.len() as isize - 1)
}

fn sorted_tops<S: TopCells + VertexStar + ?Sized>(
    s: &S,
    cells: &[CellId],
) -> Result<Vec<Vec<u32>>, QueryError> {
    let mut buf = Vec::new();
    let mut out = Vec::with_capacity(cells.len());
    for &c in cells {
        if !s.top_cell_kind(c).is_simplex() {
            return Err(not_simplicial());
        }
        buf.clear();
        s.top_cell_vertices(c, &mut buf);
        let mut t: Vec<u32> = buf.iter().map(|v| v.0).collect();
        t.sort_unstable();
        out.push(t);
    }
    Ok(out)
}

/// Manifoldness of a vertex.
///
/// ```
/// use starplex::algo::nonmanifold::{vertex_manifoldness, Manifoldness};
/// use starplex::{ids::VertexId, topo::naive::VtIndex};
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// // k: the triangles 0-1-2 and 1-3-2, sharing the edge 1-2
/// let idx = VtIndex::new(&k);
/// assert_eq!(vertex_manifoldness(&idx, VertexId(1)).unwrap(), Manifoldness::Manifold);
/// assert!(vertex_manifoldness(&idx, VertexId(9)).is_err());
/// ```
///
/// # Errors
/// A CP cell in its star; a vertex out of range.
pub fn vertex_manifoldness<S: TopCells + VertexStar + ?Sized>(
    s: &S,
    v: VertexId,
) -> Result<Manifoldness, QueryError> {
    if v.index() >= s.n_vertices() {
        return Err(QueryError::NotInComplex(vec![v.0]));
    }
    let mut cells = Vec::new();
    s.vertex_top_cells(v, &mut cells);
    let tops = sorted_tops(s, &cells)?;
    Ok(star_test(&tops, &[v.0]))
}

/// Manifoldness of the edge {u, w}.
///
/// ```
/// use starplex::algo::nonmanifold::{edge_manifoldness, Manifoldness};
/// use starplex::{ids::VertexId, topo::naive::VtIndex};
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// let mut b = ComplexBuilder::new(1).unwrap();
/// for x in 0..5 { b.push_vertex(&[x as f64]).unwrap(); }
/// for c in [2, 3, 4] { b.push_cell(CellKind::Simplex(2), &[0, 1, c]).unwrap(); }
/// let k = b.build(&BuildOptions::default()).unwrap().0;
/// let idx = VtIndex::new(&k);
/// // Three triangles on the edge 0-1: a "book" with three pages.
/// assert_eq!(edge_manifoldness(&idx, VertexId(0), VertexId(1)).unwrap(), Manifoldness::NonManifold);
/// assert_eq!(edge_manifoldness(&idx, VertexId(0), VertexId(2)).unwrap(), Manifoldness::Manifold);
/// assert!(edge_manifoldness(&idx, VertexId(2), VertexId(3)).is_err()); // not an edge
/// ```
///
/// # Errors
/// Not an edge of the complex; a CP cell in its star.
pub fn edge_manifoldness<S: TopCells + VertexStar + ?Sized>(
    s: &S,
    u: VertexId,
    w: VertexId,
) -> Result<Manifoldness, QueryError> {
    if u.index() >= s.n_vertices() || w.index() >= s.n_vertices() || u == w {
        return Err(QueryError::NotInComplex(vec![u.0, w.0]));
    }
    let mut cells = Vec::new();
    s.vertex_top_cells(u, &mut cells);
    let tops: Vec<Vec<u32>> = sorted_tops(s, &cells)?
        .into_iter()
        .filter(|t| t.binary_search(&w.0).is_ok())
        .collect();
    if tops.is_empty() {
        return Err(QueryError::NotInComplex(vec![u.0, w.0]));
    }
    Ok(star_test(&tops, &[u.0.min(w.0), u.0.max(w.0)]))
}

/// Every non-manifold (and undecided) vertex and edge; each edge handled once from its
/// smaller endpoint while that vertex's star is in hand.
///
/// ```
/// use starplex::algo::nonmanifold::singularities;
/// use starplex::{ids::VertexId, topo::naive::VtIndex};
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// let mut b = ComplexBuilder::new(1).unwrap();
/// for x in 0..5 { b.push_vertex(&[x as f64]).unwrap(); }
/// for c in [2, 3, 4] { b.push_cell(CellKind::Simplex(2), &[0, 1, c]).unwrap(); }
/// let k = b.build(&BuildOptions::default()).unwrap().0;
/// let r = singularities(&VtIndex::new(&k)).unwrap();
/// assert_eq!(r.non_manifold_edges, vec![[VertexId(0), VertexId(1)]]);
/// assert_eq!(r.non_manifold_vertices, vec![VertexId(0), VertexId(1)]);
/// ```
///
/// # Errors
/// A CP cell.
pub fn singularities<S: TopCells + VertexStar + ?Sized>(
    s: &S,
) -> Result<Singularities, QueryError> {
    let mut r = Singularities::default();
    let mut cells = Vec::new();
    let mut by_edge: FxHashMap<u32, Vec<usize>> = FxHashMap::default();
    for v in 0..s.n_vertices() {
        let v = VertexId(v as u32);
        s.vertex_top_cells(v, &mut cells);
        let tops = sorted_tops(s, &cells)?;
        match star_test(&tops, &[v.0]) {
            Manifoldness::NonManifold => r.non_manifold_vertices.push(v),
            Manifoldness::Unknown => r.unknown_vertices.push(v),
            Manifoldness::Manifold => {}
        }
        by_edge.clear();
        for (i, t) in tops.iter().enumerate() {
            for &w in t.iter().filter(|&&w| w > v.0) {
                by_edge.entry(w).or_default().push(i);
            }
        }
        let mut ws: Vec<u32> = by_edge.keys().copied().collect();
        ws.sort_unstable();
        for w in ws {
            let et: Vec<Vec<u32>> = by_edge[&w].iter().map(|&i| tops[i].clone()).collect();
            match star_test(&et, &[v.0, w]) {
                Manifoldness::NonManifold => r.non_manifold_edges.push([v, VertexId(w)]),
                Manifoldness::Unknown => r.unknown_edges.push([v, VertexId(w)]),
                Manifoldness::Manifold => {}
            }
        }
    }
    Ok(r)
}
