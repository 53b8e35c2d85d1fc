//! Every relation from the top-cell queries: a structure that answers [`TopCells`] and
//! [`VertexStar`] (top cells and VT, like [`VtIndex`](super::naive::VtIndex) or IA*) gets
//! [`TopStar`](super::TopStar), [`Boundary`](super::Boundary), [`Coboundary`](super::Coboundary),
//! [`Adjacency`](super::Adjacency), [`Star`](super::Star), [`Levels`](super::Levels) and
//! [`Counts`](super::Counts) through these functions (the spec's §2.3 algorithms: filter the
//! vertex star, then enumerate faces of the tops, each face emitted once).
//!
//! Faces are enumerated for simplicial tops only; a CP cell in the star gives
//! [`QueryError::NotSimplicial`]. Every enumeration checks an estimate against a budget first.
//!
//! ```
//! use starplex::complex::{ComplexBuilder, BuildOptions};
//! use starplex::cell::CellKind;
//! use starplex::ids::VertexId;
//! use starplex::topo::{naive::VtIndex, from_tops};
//! let mut b = ComplexBuilder::new(1).unwrap();
//! for x in 0..4 { b.push_vertex(&[x as f64]).unwrap(); }
//! b.push_cell(CellKind::Simplex(3), &[0, 1, 2, 3]).unwrap();
//! let k = b.build(&BuildOptions::default()).unwrap().0;
//! let idx = VtIndex::new(&k);
//! let st = from_tops::star(&idx, &[VertexId(0), VertexId(1)], 1000).unwrap();
//! assert_eq!(st.f_vector(), vec![0, 1, 2, 1]);
//! ```
use super::{sort_flat, sorted_simplex, QueryError, SimplexSet, TopCells, VertexStar};
use crate::cell::binomial;
use crate::ids::{CellId, VertexId};
use crate::limits::{TooLarge, Unit};

fn not_in(s: &[VertexId]) -> QueryError {
    QueryError::NotInComplex(s.iter().map(|v| v.0).collect())
}

/// True when sorted `small` ⊆ `big` (any order).
#[inline]
fn subset(small: &[VertexId], big: &[VertexId]) -> bool {
    small.iter().all(|v| big.contains(v))
}

/// St_T(s): the top cells containing `s`, sorted; for a vertex, its VT (possibly empty for an
/// isolated vertex).
///
/// ```
/// use starplex::topo::{naive::VtIndex, from_tops};
/// use starplex::ids::{CellId, VertexId};
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// // k: the triangles 0-1-2 and 1-3-2, sharing the edge 1-2
/// let idx = VtIndex::new(&k);
/// let mut cells = Vec::new();
/// from_tops::top_star(&idx, &[VertexId(3)], &mut cells).unwrap();
/// assert_eq!(cells, [CellId(1)]);
/// assert!(from_tops::top_star(&idx, &[VertexId(0), VertexId(3)], &mut cells).is_err());
/// ```
///
/// # Errors
/// `s` is not a simplex of the complex.
pub fn top_star<S: TopCells + VertexStar + ?Sized>(
    st: &S,
    s: &[VertexId],
    out: &mut Vec<CellId>,
) -> Result<(), QueryError> {
    let s = sorted_simplex(s)?;
    if s.iter().any(|v| v.index() >= st.n_vertices()) {
        return Err(not_in(&s));
    }
    st.vertex_top_cells(s[0], out);
    if s.len() == 1 {
        return Ok(());
    }
    let mut buf = Vec::new();
    let raw: Vec<u32> = s.iter().map(|v| v.0).collect();
    out.retain(|&c| {
        buf.clear();
        st.top_cell_vertices(c, &mut buf);
        let kind = st.top_cell_kind(c);
        if kind.is_simplex() {
            subset(&s, &buf)
        } else {
            let cv: Vec<u32> = buf.iter().map(|v| v.0).collect();
            kind.has_face(&cv, &raw)
        }
    });
    if out.is_empty() {
        return Err(not_in(&s));
    }
    Ok(())
}

/// The tops of St_T(s) as sorted vertex lists (simplicial tops only).
fn star_tops<S: TopCells + VertexStar + ?Sized>(
    st: &S,
    s: &[VertexId],
    what: &str,
) -> Result<Vec<Vec<VertexId>>, QueryError> {
    let mut cells = Vec::new();
    top_star(st, s, &mut cells)?;
    let mut tops = Vec::with_capacity(cells.len());
    for c in cells {
        if !st.top_cell_kind(c).is_simplex() {
            return Err(QueryError::NotSimplicial(what.to_string()));
        }
        let mut t = Vec::new();
        st.top_cell_vertices(c, &mut t);
        t.sort_unstable();
        tops.push(t);
    }
    Ok(tops)
}

/// `s` sorted and the top cells around it (sorted), refused when its star's faces (`Σ 2^(|t| -
/// |s|)`) exceed `budget`: what [`star`] and [`link`] start from.
fn star_tops_within<S: TopCells + VertexStar + ?Sized>(
    st: &S,
    s: &[VertexId],
    budget: u128,
) -> Result<(Vec<VertexId>, Vec<Vec<VertexId>>), QueryError> {
    let s = sorted_simplex(s)?;
    let tops = star_tops(st, &s, "star")?;
    let est: u128 = tops
        .iter()
        .map(|t| 1u128 << (t.len() - s.len()).min(120))
        .fold(1, |a, x| a.saturating_add(x));
    if est > budget {
        return Err(too_large(format!("star of {s:?}"), est, budget));
    }
    Ok((s, tops))
}

/// Calls `f` with every `k`-subset of `items` (in lexicographic order of positions).
///
/// ```
/// use starplex::topo::from_tops::for_each_subset;
/// let mut pairs = Vec::new();
/// for_each_subset(&['a', 'b', 'c'], 2, &mut Vec::new(), &mut |s| pairs.push(s.to_vec()));
/// assert_eq!(pairs, [['a', 'b'], ['a', 'c'], ['b', 'c']]);
/// let mut n = 0;
/// for_each_subset(&[1, 2], 3, &mut Vec::new(), &mut |_| n += 1);
/// assert_eq!(n, 0);
/// ```
pub fn for_each_subset<T: Copy>(items: &[T], k: usize, buf: &mut Vec<T>, f: &mut dyn FnMut(&[T])) {
    let n = items.len();
    if k > n {
        return;
    }
    if k == n {
        buf.clear();
        buf.extend_from_slice(items);
        f(buf);
        return;
    }
    let mut small = [0usize; 72];
    let mut large: Vec<usize>;
    let idx: &mut [usize] = if k <= small.len() {
        &mut small[..k]
    } else {
        large = vec![0; k];
        &mut large[..]
    };
    for (i, x) in idx.iter_mut().enumerate() {
        *x = i;
    }
    loop {
        buf.clear();
        buf.extend(idx.iter().map(|&i| items[i]));
        f(buf);
        let mut i = k as isize - 1;
        while i >= 0 && idx[i as usize] == n - k + i as usize {
            i -= 1;
        }
        if i < 0 {
            return;
        }
        let i = i as usize;
        idx[i] += 1;
        for j in i + 1..k {
            idx[j] = idx[j - 1] + 1;
        }
    }
}

fn too_large(what: String, estimate: u128, budget: u128) -> QueryError {
    QueryError::TooLarge(TooLarge::new(what, estimate, budget, Unit::Simplices))
}

/// St(s): every simplex containing `s`.
///
/// ```
/// use starplex::topo::{naive::VtIndex, from_tops};
/// use starplex::ids::VertexId;
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// // k: the triangles 0-1-2 and 1-3-2, sharing the edge 1-2
/// let idx = VtIndex::new(&k);
/// let st = from_tops::star(&idx, &[VertexId(1), VertexId(2)], 1000).unwrap();
/// assert_eq!(st.f_vector(), vec![0, 1, 2]); // the edge and its two triangles
/// assert!(from_tops::star(&idx, &[VertexId(1)], 2).is_err()); // over a budget of 2
/// ```
///
/// # Errors
/// `s` not in the complex, a CP cell in the star, more than `budget` simplices.
pub fn star<S: TopCells + VertexStar + ?Sized>(
    st: &S,
    s: &[VertexId],
    budget: u128,
) -> Result<SimplexSet, QueryError> {
    let (s, tops) = star_tops_within(st, s, budget)?;
    let mut set = SimplexSet::default();
    set.insert(&s);
    let mut face = Vec::new();
    for_each_rest_subset(&s, &tops, |sub| {
        face.clear();
        face.extend_from_slice(&s);
        face.extend_from_slice(sub);
        set.insert(&face);
    });
    set.normalize();
    Ok(set)
}

/// Calls `f` with every nonempty subset of `t \ s` for each top cell `t` of `tops` (`s`
/// sorted): the faces of the star that miss `s`, which the link is and the star adds `s` to.
fn for_each_rest_subset(s: &[VertexId], tops: &[Vec<VertexId>], mut f: impl FnMut(&[VertexId])) {
    let mut buf = Vec::new();
    let mut rest: Vec<VertexId> = Vec::new();
    for t in tops {
        rest.clear();
        rest.extend(t.iter().copied().filter(|v| s.binary_search(v).is_err()));
        for k in 1..=rest.len() {
            for_each_subset(&rest, k, &mut buf, &mut f);
        }
    }
}

/// The link of `s` from the top cells around it: every nonempty subset of `t \ s` for each top
/// cell `t ⊇ s`, i.e. the faces of the star that miss `s`, without listing the star first. The
/// same answer, budget and errors as [`super::generic::link`] over [`star`].
///
/// ```
/// use starplex::topo::{naive::VtIndex, from_tops, generic};
/// use starplex::ids::VertexId;
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// let vt = VtIndex::new(&k);
/// let l = from_tops::link(&vt, &[VertexId(1)], u128::MAX).unwrap();
/// assert_eq!(l.f_vector(), vec![3, 2]); // the path 0 - 2 - 3
/// assert_eq!(l, generic::link(&vt, &[VertexId(1)]).unwrap());
/// ```
///
/// # Errors
/// [`QueryError::NotSimplicial`] when a top cell around `s` is not a simplex; `TooLarge` when
/// the star's estimate exceeds `budget`; as [`star`] for a bad `s`.
pub fn link<S: TopCells + VertexStar + ?Sized>(
    st: &S,
    s: &[VertexId],
    budget: u128,
) -> Result<SimplexSet, QueryError> {
    let (s, tops) = star_tops_within(st, s, budget)?;
    let mut set = SimplexSet::default();
    for_each_rest_subset(&s, &tops, |sub| set.insert(sub));
    set.normalize();
    Ok(set)
}

/// R_{p,q}, q > p: the q-simplices containing `s` (empty for q ≤ p).
///
/// ```
/// use starplex::topo::{naive::VtIndex, from_tops};
/// use starplex::ids::VertexId;
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// // k: the triangles 0-1-2 and 1-3-2, sharing the edge 1-2
/// let idx = VtIndex::new(&k);
/// let mut out = Vec::new();
/// from_tops::coboundary(&idx, &[VertexId(3)], 2, 1000, &mut out).unwrap();
/// assert_eq!(out, [VertexId(1), VertexId(2), VertexId(3)]);
/// from_tops::coboundary(&idx, &[VertexId(3)], 0, 1000, &mut out).unwrap();
/// assert!(out.is_empty()); // q <= p
/// ```
///
/// # Errors
/// `s` not in the complex, a CP cell in the star, more than `budget` simplices.
pub fn coboundary<S: TopCells + VertexStar + ?Sized>(
    st: &S,
    s: &[VertexId],
    q: usize,
    budget: u128,
    out: &mut Vec<VertexId>,
) -> Result<(), QueryError> {
    let s = sorted_simplex(s)?;
    out.clear();
    let tops = star_tops(st, &s, "co-boundary")?;
    let p = s.len() - 1;
    if q <= p {
        return Ok(());
    }
    let est: u128 = tops
        .iter()
        .map(|t| binomial((t.len() - s.len()) as u64, (q - p) as u64))
        .fold(0, |a, x| a.saturating_add(x));
    if est > budget {
        return Err(too_large(format!("co-boundary R_{p},{q}"), est, budget));
    }
    let mut buf = Vec::new();
    for t in &tops {
        let rest: Vec<VertexId> = t.iter().copied().filter(|v| !s.contains(v)).collect();
        for_each_subset(&rest, q - p, &mut buf, &mut |sub| {
            let start = out.len();
            out.extend_from_slice(&s);
            out.extend_from_slice(sub);
            out[start..].sort_unstable();
        });
    }
    sort_flat(out, q + 1);
    Ok(())
}

/// R_{p,q}, q < p: the q-faces of `s` (empty for q ≥ p).
///
/// ```
/// use starplex::topo::{naive::VtIndex, from_tops};
/// use starplex::ids::VertexId;
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// // k: the triangles 0-1-2 and 1-3-2, sharing the edge 1-2
/// let idx = VtIndex::new(&k);
/// let mut out = Vec::new();
/// from_tops::boundary(&idx, &[VertexId(3), VertexId(1)], 0, 1000, &mut out).unwrap();
/// assert_eq!(out, [VertexId(1), VertexId(3)]);
/// assert!(from_tops::boundary(&idx, &[VertexId(0), VertexId(3)], 0, 1000, &mut out).is_err());
/// ```
///
/// # Errors
/// `s` not in the complex; more than `budget` faces.
pub fn boundary<S: TopCells + VertexStar + ?Sized>(
    st: &S,
    s: &[VertexId],
    q: usize,
    budget: u128,
    out: &mut Vec<VertexId>,
) -> Result<(), QueryError> {
    let s = sorted_simplex(s)?;
    out.clear();
    let simplicial_member = s.len() >= 2
        && s.iter().all(|v| v.index() < st.n_vertices())
        && st.star_has_top_containing(&s) == Some(true);
    if !simplicial_member {
        // vertices, CP cells, and the error for a non-simplex
        let mut cells = Vec::new();
        top_star(st, &s, &mut cells)?;
    }
    boundary_of_sorted(&s, q, budget, out)
}

/// The q-faces of a sorted simplex known to be in the complex.
///
/// ```
/// use starplex::topo::from_tops::boundary_of_sorted;
/// use starplex::ids::VertexId;
/// let tri = [VertexId(4), VertexId(7), VertexId(9)];
/// let mut out = Vec::new();
/// boundary_of_sorted(&tri, 1, 1000, &mut out).unwrap();
/// let edges: Vec<u32> = out.iter().map(|v| v.0).collect();
/// assert_eq!(edges, [4, 7, 4, 9, 7, 9]);
/// ```
///
/// # Errors
/// More than `budget` faces.
pub fn boundary_of_sorted(
    s: &[VertexId],
    q: usize,
    budget: u128,
    out: &mut Vec<VertexId>,
) -> Result<(), QueryError> {
    out.clear();
    if q + 1 >= s.len() {
        return Ok(());
    }
    let est = binomial(s.len() as u64, q as u64 + 1);
    if est > budget {
        return Err(too_large(
            format!("boundary R_{},{q}", s.len() - 1),
            est,
            budget,
        ));
    }
    let mut buf = Vec::new();
    for_each_subset(s, q + 1, &mut buf, &mut |f| out.extend_from_slice(f));
    Ok(())
}

/// R_{p,p}: simplices adjacent to `s` (p ≥ 1: sharing a facet; p = 0: sharing an edge).
///
/// ```
/// use starplex::topo::{naive::VtIndex, from_tops};
/// use starplex::ids::VertexId;
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// // k: the triangles 0-1-2 and 1-3-2, sharing the edge 1-2
/// let idx = VtIndex::new(&k);
/// let mut out = Vec::new();
/// // Edges sharing a vertex with 0-1: p = 1 adjacency.
/// from_tops::adjacent(&idx, &[VertexId(0), VertexId(1)], 1000, &mut out).unwrap();
/// let flat: Vec<u32> = out.iter().map(|v| v.0).collect();
/// assert_eq!(flat, [0, 2, 1, 2, 1, 3]);
/// ```
///
/// # Errors
/// `s` not in the complex, a CP cell in the star, more than `budget` simplices.
pub fn adjacent<S: TopCells + VertexStar + ?Sized>(
    st: &S,
    s: &[VertexId],
    budget: u128,
    out: &mut Vec<VertexId>,
) -> Result<(), QueryError> {
    let s = sorted_simplex(s)?;
    out.clear();
    let p = s.len() - 1;
    if p == 0 {
        let mut e = Vec::new();
        coboundary(st, &s, 1, budget, &mut e)?;
        out.extend(
            e.chunks_exact(2)
                .map(|c| if c[0] == s[0] { c[1] } else { c[0] }),
        );
        out.sort_unstable();
        return Ok(());
    }
    let mut cells = Vec::new();
    top_star(st, &s, &mut cells)?;
    let mut co = Vec::new();
    let mut facet = Vec::with_capacity(p);
    for j in 0..=p {
        facet.clear();
        facet.extend(
            s.iter()
                .enumerate()
                .filter(|&(i, _)| i != j)
                .map(|(_, &v)| v),
        );
        coboundary(st, &facet, p, budget, &mut co)?;
        for c in co.chunks_exact(p + 1) {
            if c != s.as_slice() {
                out.extend_from_slice(c);
            }
        }
    }
    sort_flat(out, p + 1);
    Ok(())
}

/// An upper bound of the (top, p-face) pairs of the complex.
///
/// ```
/// use starplex::topo::{naive::VtIndex, from_tops::face_estimate};
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// // k: the triangles 0-1-2 and 1-3-2, sharing the edge 1-2
/// let idx = VtIndex::new(&k);
/// assert_eq!(face_estimate(&idx, 1), 6); // 3 edges per triangle, shared ones counted twice
/// assert_eq!(face_estimate(&idx, 3), 0);
/// ```
pub fn face_estimate<S: TopCells + ?Sized>(st: &S, p: usize) -> u128 {
    let mut est: u128 = 0;
    for c in 0..st.n_top_cells() {
        let kind = st.top_cell_kind(CellId(c as u32));
        est = est.saturating_add(kind.n_faces(p));
    }
    est
}

fn check_simplicial<S: TopCells + ?Sized>(st: &S, what: &str) -> Result<(), QueryError> {
    for c in 0..st.n_top_cells() {
        if !st.top_cell_kind(CellId(c as u32)).is_simplex() {
            return Err(QueryError::NotSimplicial(what.to_string()));
        }
    }
    Ok(())
}

/// Calls `f` once per p-simplex: vertex by vertex, each face emitted from its smallest vertex
/// (sorted within one vertex). p = 0 lists every vertex, isolated ones included.
///
/// ```
/// use starplex::topo::{naive::VtIndex, from_tops};
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// // k: the triangles 0-1-2 and 1-3-2, sharing the edge 1-2
/// let idx = VtIndex::new(&k);
/// let mut tris = Vec::new();
/// from_tops::for_each_simplex(&idx, 2, 1000, &mut |t| tris.push([t[0].0, t[1].0, t[2].0])).unwrap();
/// tris.sort();
/// assert_eq!(tris, [[0, 1, 2], [1, 2, 3]]);
/// ```
///
/// # Errors
/// A CP cell; more than `budget` (top, face) pairs.
pub fn for_each_simplex<S: TopCells + VertexStar + ?Sized>(
    st: &S,
    p: usize,
    budget: u128,
    f: &mut dyn FnMut(&[VertexId]),
) -> Result<(), QueryError> {
    if p == 0 {
        for v in 0..st.n_vertices() {
            f(&[VertexId(v as u32)]);
        }
        return Ok(());
    }
    check_simplicial(st, "level iteration")?;
    let est = face_estimate(st, p);
    if est > budget {
        return Err(too_large(format!("the {p}-simplices"), est, budget));
    }
    let mut sc = FaceScratch::default();
    let vt = |v: VertexId, out: &mut Vec<CellId>| st.vertex_top_cells(v, out);
    for v in 0..st.n_vertices() {
        simplices_from(st, VertexId(v as u32), p, &mut sc, &vt);
        for s in sc.local.chunks_exact(p + 1) {
            f(s);
        }
    }
    Ok(())
}

/// Reused buffers of [`simplices_from`].
#[derive(Default)]
struct FaceScratch {
    cells: Vec<CellId>,
    tv: Vec<VertexId>,
    buf: Vec<VertexId>,
    upper: Vec<VertexId>,
    /// The p-simplices found, flat and sorted.
    local: Vec<VertexId>,
}

/// The p-simplices (p >= 1) whose smallest vertex is `v`, flat and sorted, into `sc.local`;
/// `vt` gives the top cells incident to a vertex.
fn simplices_from<S: TopCells + ?Sized>(
    st: &S,
    v: VertexId,
    p: usize,
    sc: &mut FaceScratch,
    vt: &impl Fn(VertexId, &mut Vec<CellId>),
) {
    vt(v, &mut sc.cells);
    sc.local.clear();
    for &c in &sc.cells {
        sc.tv.clear();
        st.top_cell_vertices(c, &mut sc.tv);
        sc.upper.clear();
        sc.upper.extend(sc.tv.iter().copied().filter(|&w| w > v));
        if sc.upper.len() < p {
            continue;
        }
        sc.upper.sort_unstable();
        let local = &mut sc.local;
        for_each_subset(&sc.upper, p, &mut sc.buf, &mut |sub| {
            local.push(v);
            local.extend_from_slice(sub);
        });
    }
    sort_flat(&mut sc.local, p + 1);
}

/// Every p-simplex, flat (`p + 1` vertex ids each), in [`for_each_simplex`]'s order, the
/// vertices split into ranges listed in parallel; from the VT rows of all vertices at once where
/// the structure gives them ([`VertexStar::vertex_top_rows`]).
///
/// ```
/// use starplex::topo::{naive::VtIndex, from_tops};
/// let k = starplex::generate::kuhn_grid(&[2, 2]).unwrap(); // 8 triangles
/// let idx = VtIndex::new(&k);
/// let mut edges = Vec::new();
/// from_tops::for_each_simplex(&idx, 1, 1000, &mut |e| edges.extend([e[0].0, e[1].0])).unwrap();
/// assert_eq!(from_tops::faces_par(&idx, 1, 1000).unwrap(), edges);
/// assert_eq!(edges.len(), 2 * 16);
/// ```
///
/// # Errors
/// As [`for_each_simplex`].
pub fn faces_par<S: TopCells + VertexStar + Sync + ?Sized>(
    st: &S,
    p: usize,
    budget: u128,
) -> Result<Vec<u32>, QueryError> {
    faces_par_with(st, p, budget, || {
        // all rows at once where the structure makes them faster so
        let rows = st.vertex_top_rows();
        move |v: VertexId, out: &mut Vec<CellId>| match &rows {
            Some(r) => {
                out.clear();
                out.extend(r.row(v.index()).iter().map(|&c| CellId(c)));
            }
            None => st.vertex_top_cells(v, out),
        }
    })
}

/// [`faces_par`] with the top cells incident to each vertex given by the function `make_vt`
/// returns (called once the request is checked), for a structure that can list them all at
/// once faster than one vertex at a time.
///
/// ```
/// use starplex::ids::{CellId, VertexId};
/// use starplex::topo::{naive::VtIndex, from_tops, VertexStar};
/// let k = starplex::generate::kuhn_grid(&[2, 2]).unwrap();
/// let idx = VtIndex::new(&k);
/// let rows: Vec<Vec<CellId>> = (0..9).map(|v| {
///     let mut c = Vec::new();
///     idx.vertex_top_cells(VertexId(v), &mut c);
///     c
/// }).collect();
/// let vt = || |v: VertexId, out: &mut Vec<CellId>| out.clone_from(&rows[v.0 as usize]);
/// let got = from_tops::faces_par_with(&idx, 2, 1000, vt).unwrap();
/// assert_eq!(got, from_tops::faces_par(&idx, 2, 1000).unwrap());
/// ```
///
/// # Errors
/// As [`for_each_simplex`].
pub fn faces_par_with<S, F>(
    st: &S,
    p: usize,
    budget: u128,
    make_vt: impl FnOnce() -> F,
) -> Result<Vec<u32>, QueryError>
where
    S: TopCells + Sync + ?Sized,
    F: Fn(VertexId, &mut Vec<CellId>) + Sync,
{
    use rayon::prelude::*;
    let n = st.n_vertices() as u32;
    if p == 0 {
        return Ok((0..n).collect());
    }
    check_simplicial(st, "level iteration")?;
    let est = face_estimate(st, p);
    if est > budget {
        return Err(too_large(format!("the {p}-simplices"), est, budget));
    }
    let vt = make_vt();
    const RANGE: u32 = 2048;
    let parts: Vec<Vec<u32>> = (0..n.div_ceil(RANGE))
        .into_par_iter()
        .map_init(FaceScratch::default, |sc, r| {
            let mut out = Vec::new();
            for v in r * RANGE..((r + 1) * RANGE).min(n) {
                simplices_from(st, VertexId(v), p, sc, &vt);
                out.extend(sc.local.iter().map(|v| v.0));
            }
            out
        })
        .collect();
    Ok(parts.concat())
}

/// The f-vector by level iteration.
///
/// ```
/// use starplex::topo::{naive::VtIndex, from_tops};
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// // k: the triangles 0-1-2 and 1-3-2, sharing the edge 1-2
/// let idx = VtIndex::new(&k);
/// assert_eq!(from_tops::f_vector(&idx, 1000).unwrap(), vec![4, 5, 2]);
/// assert!(from_tops::f_vector(&idx, 3).is_err());
/// ```
///
/// # Errors
/// A CP cell; more than `budget` (top, face) pairs in total.
pub fn f_vector<S: TopCells + VertexStar + ?Sized>(
    st: &S,
    budget: u128,
) -> Result<Vec<u64>, QueryError> {
    let mut dim = None;
    for c in 0..st.n_top_cells() {
        let d = st.top_cell_kind(CellId(c as u32)).dim();
        dim = Some(dim.map_or(d, |x: usize| x.max(d)));
    }
    let dim = match dim {
        None if st.n_vertices() == 0 => return Ok(vec![]),
        None => 0,
        Some(d) => d,
    };
    let total: u128 = (1..=dim)
        .map(|p| face_estimate(st, p))
        .fold(0, |a, x| a.saturating_add(x));
    if total > budget {
        return Err(too_large("the f-vector".into(), total, budget));
    }
    let mut f = vec![0u64; dim + 1];
    for (p, x) in f.iter_mut().enumerate() {
        let mut n = 0u64;
        for_each_simplex(st, p, budget, &mut |_| n += 1)?;
        *x = n;
    }
    Ok(f)
}

/// Implements `TopStar`, `Counts`, `Boundary`, `Coboundary`, `Adjacency`, `Star` and `Levels`
/// for a type that implements `TopCells + VertexStar`, through this module's functions with
/// [`DEFAULT_BUDGET`](super::DEFAULT_BUDGET).
#[macro_export]
macro_rules! impl_relations_from_tops {
    ($t:ty) => {
        impl $crate::topo::TopStar for $t {
            fn top_star(
                &self,
                s: &[$crate::ids::VertexId],
                out: &mut Vec<$crate::ids::CellId>,
            ) -> Result<(), $crate::topo::QueryError> {
                $crate::topo::from_tops::top_star(self, s, out)
            }
        }
        impl $crate::topo::Counts for $t {
            fn f_vector(&self) -> Result<Vec<u64>, $crate::topo::QueryError> {
                $crate::topo::from_tops::f_vector(self, $crate::topo::DEFAULT_BUDGET * 100)
            }
        }
        impl $crate::topo::Boundary for $t {
            fn boundary(
                &self,
                s: &[$crate::ids::VertexId],
                q: usize,
                out: &mut Vec<$crate::ids::VertexId>,
            ) -> Result<(), $crate::topo::QueryError> {
                $crate::topo::from_tops::boundary(self, s, q, $crate::topo::DEFAULT_BUDGET, out)
            }
        }
        impl $crate::topo::Coboundary for $t {
            fn coboundary(
                &self,
                s: &[$crate::ids::VertexId],
                q: usize,
                out: &mut Vec<$crate::ids::VertexId>,
            ) -> Result<(), $crate::topo::QueryError> {
                $crate::topo::from_tops::coboundary(self, s, q, $crate::topo::DEFAULT_BUDGET, out)
            }
        }
        impl $crate::topo::Adjacency for $t {
            fn adjacent(
                &self,
                s: &[$crate::ids::VertexId],
                out: &mut Vec<$crate::ids::VertexId>,
            ) -> Result<(), $crate::topo::QueryError> {
                $crate::topo::from_tops::adjacent(self, s, $crate::topo::DEFAULT_BUDGET, out)
            }
        }
        impl $crate::topo::Star for $t {
            fn star(
                &self,
                s: &[$crate::ids::VertexId],
            ) -> Result<$crate::topo::SimplexSet, $crate::topo::QueryError> {
                $crate::topo::from_tops::star(self, s, $crate::topo::DEFAULT_BUDGET)
            }
        }
        impl $crate::topo::Levels for $t {
            fn for_each_simplex(
                &self,
                p: usize,
                f: &mut dyn FnMut(&[$crate::ids::VertexId]),
            ) -> Result<(), $crate::topo::QueryError> {
                $crate::topo::from_tops::for_each_simplex(
                    self,
                    p,
                    $crate::topo::DEFAULT_BUDGET * 100,
                    f,
                )
            }
            fn faces_flat(&self, p: usize) -> Result<Vec<u32>, $crate::topo::QueryError> {
                $crate::topo::from_tops::faces_par(self, p, $crate::topo::DEFAULT_BUDGET * 100)
            }
        }
    };
}
