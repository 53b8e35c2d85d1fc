//! Generic algorithms written once against the capability traits: closure, link, skeleton and
//! Euler characteristic of any structure.
//!
//! ```
//! use starplex::complex::{ComplexBuilder, BuildOptions};
//! use starplex::cell::CellKind;
//! use starplex::ids::VertexId;
//! use starplex::topo::{naive::VtIndex, generic};
//! let mut b = ComplexBuilder::new(1).unwrap();
//! for x in 0..4 { b.push_vertex(&[x as f64]).unwrap(); }
//! b.push_cell(CellKind::Simplex(3), &[0, 1, 2, 3]).unwrap();
//! let k = b.build(&BuildOptions::default()).unwrap().0;
//! let idx = VtIndex::new(&k);
//! assert_eq!(generic::euler_characteristic(&idx).unwrap(), 1);
//! let lk = generic::link(&idx, &[VertexId(0)]).unwrap();
//! assert_eq!(lk.f_vector(), vec![3, 3, 1]);
//! let cl = generic::closure(&idx, &[VertexId(1), VertexId(2)]).unwrap();
//! assert_eq!(cl.f_vector(), vec![2, 1]);
//! assert_eq!(generic::skeleton(&idx, 1).unwrap().f_vector(), vec![4, 6]);
//! ```
use super::{
    sorted_simplex, Boundary, Counts, Levels, QueryError, SimplexSet, Star, TopCells, TopStar,
};
use crate::ids::{CellId, VertexId};

/// The closure of `s`: `s` and all its faces.
///
/// ```
/// use starplex::topo::{naive::VtIndex, generic};
/// use starplex::ids::VertexId;
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// // k: the triangles 0-1-2 and 1-3-2, sharing the edge 1-2
/// let cl = generic::closure(&VtIndex::new(&k), &[VertexId(3), VertexId(2), VertexId(1)]).unwrap();
/// assert_eq!(cl.f_vector(), vec![3, 3, 1]);
/// assert!(cl.contains(&[VertexId(2), VertexId(3)]));
/// ```
///
/// # Errors
/// `s` not in the complex; too many faces.
pub fn closure<S: Boundary + ?Sized>(st: &S, s: &[VertexId]) -> Result<SimplexSet, QueryError> {
    let s = sorted_simplex(s)?;
    let mut set = SimplexSet::default();
    let mut out = Vec::new();
    // validates `s` (for a vertex the answer is empty)
    st.boundary(&s, 0, &mut out)?;
    for q in 0..s.len() - 1 {
        st.boundary(&s, q, &mut out)?;
        set.levels.push(out.clone());
    }
    set.insert(&s);
    set.normalize();
    Ok(set)
}

/// The link of `s`: {τ ∖ s : τ ∈ St(s), τ ≠ s}.
///
/// ```
/// use starplex::topo::{naive::VtIndex, generic};
/// use starplex::ids::VertexId;
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// // k: the triangles 0-1-2 and 1-3-2, sharing the edge 1-2
/// let lk = generic::link(&VtIndex::new(&k), &[VertexId(1), VertexId(2)]).unwrap();
/// assert_eq!(lk.level(0), &[VertexId(0), VertexId(3)]); // the opposite corners
/// ```
///
/// # Errors
/// `s` not in the complex; a star over the budget.
pub fn link<S: Star + ?Sized>(st: &S, s: &[VertexId]) -> Result<SimplexSet, QueryError> {
    let s = sorted_simplex(s)?;
    let star = st.star(&s)?;
    let mut set = SimplexSet::default();
    let mut buf = Vec::new();
    for t in star.iter() {
        if t.len() == s.len() {
            continue;
        }
        buf.clear();
        buf.extend(t.iter().copied().filter(|v| s.binary_search(v).is_err()));
        set.insert(&buf);
    }
    set.normalize();
    Ok(set)
}

/// The p-skeleton: every simplex of dimension ≤ p.
///
/// ```
/// use starplex::topo::{naive::VtIndex, generic};
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// // k: the triangles 0-1-2 and 1-3-2, sharing the edge 1-2
/// let sk = generic::skeleton(&VtIndex::new(&k), 1).unwrap();
/// assert_eq!(sk.f_vector(), vec![4, 5]);
/// ```
///
/// # Errors
/// Too many simplices.
pub fn skeleton<S: Levels + ?Sized>(st: &S, p: usize) -> Result<SimplexSet, QueryError> {
    let mut set = SimplexSet::default();
    for q in 0..=p {
        let mut l = Vec::new();
        st.for_each_simplex(q, &mut |s| l.extend_from_slice(s))?;
        set.levels.push(l);
    }
    set.normalize();
    Ok(set)
}

/// χ = Σ (-1)^p f_p.
///
/// ```
/// use starplex::topo::{naive::VtIndex, generic};
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// // k: the triangles 0-1-2 and 1-3-2, sharing the edge 1-2
/// assert_eq!(generic::euler_characteristic(&VtIndex::new(&k)).unwrap(), 4 - 5 + 2);
/// ```
///
/// # Errors
/// The f-vector is over the budget.
pub fn euler_characteristic<S: Counts + ?Sized>(st: &S) -> Result<i64, QueryError> {
    Ok(st
        .f_vector()?
        .iter()
        .enumerate()
        .map(|(p, &x)| if p % 2 == 0 { x as i64 } else { -(x as i64) })
        .sum())
}

/// R_{k,k} of top cell `c` read from top stars: for each facet of `c` (a simplex's facet j
/// omits vertex j; a CP cell's come from its table), the other top cells of `c`'s dimension
/// containing it, appended to `out` in facet order (a cell sharing two facets appears twice).
/// What an IA* stores, computed from any structure; `facet` and `cells` are scratch.
///
/// ```
/// use starplex::complex::{ComplexBuilder, BuildOptions};
/// use starplex::cell::CellKind;
/// use starplex::ids::CellId;
/// use starplex::topo::{naive::VtIndex, generic};
/// let mut b = ComplexBuilder::new(2).unwrap();
/// for _ in 0..5 { b.push_vertex(&[0.0, 0.0]).unwrap(); }
/// for c in [[0, 1, 2], [0, 1, 3], [1, 2, 4]] { b.push_cell(CellKind::Simplex(2), &c).unwrap(); }
/// let k = b.build(&BuildOptions::default()).unwrap().0;
/// let (mut f, mut cs, mut out) = (Vec::new(), Vec::new(), Vec::new());
/// generic::facet_neighbours(&VtIndex::new(&k), CellId(0), &mut f, &mut cs, &mut out).unwrap();
/// assert_eq!(out, [CellId(2), CellId(1)]); // across {1,2}, then across {0,1}
/// ```
///
/// # Errors
/// The structure's own [`TopStar`] errors.
pub fn facet_neighbours<S: TopStar + TopCells + ?Sized>(
    st: &S,
    c: CellId,
    facet: &mut Vec<VertexId>,
    cells: &mut Vec<CellId>,
    out: &mut Vec<CellId>,
) -> Result<(), QueryError> {
    let kind = st.top_cell_kind(c);
    let d = kind.dim();
    if d == 0 {
        return Ok(());
    }
    let mut tv = Vec::with_capacity(kind.n_vertices());
    st.top_cell_vertices(c, &mut tv);
    let mut err = Ok(());
    kind.for_each_oriented_facet(|l, _| {
        if err.is_err() {
            return;
        }
        facet.clear();
        facet.extend(l.iter().map(|&x| tv[x as usize]));
        match st.top_star(facet, cells) {
            Ok(()) => out.extend(
                cells
                    .iter()
                    .filter(|&&u| u != c && st.top_cell_kind(u).dim() == d),
            ),
            Err(e) => err = Err(e),
        }
    });
    err
}

/// Writes any structure's top cells back to an [`IndexedComplex`](crate::complex::IndexedComplex)
/// (cells in the structure's id order, each with the vertex order the structure keeps), on the
/// given coordinates (`ambient` numbers per vertex, one row per vertex of the structure). The
/// structures store topology only; the coordinates come from where the complex was read.
///
/// ```
/// use starplex::topo::generic;
/// use starplex::tds::iastar::IaStar;
/// let k = starplex::testkit::fixture::book();
/// let back = generic::to_complex(&IaStar::new(&k).unwrap(), 3, k.coords().to_vec()).unwrap();
/// assert_eq!(back.n_cells(), 3);
/// assert_eq!(back.cell(starplex::ids::CellId(2)).vertices, &[0, 1, 4]);
/// ```
///
/// # Errors
/// The checks of [`IndexedComplex::from_parts`](crate::complex::IndexedComplex::from_parts):
/// coordinates that do not fit the vertices, non-finite values, vertex ids out of range.
pub fn to_complex<S: TopCells + ?Sized>(
    st: &S,
    ambient: usize,
    coords: Vec<f64>,
) -> Result<crate::complex::IndexedComplex, crate::complex::ComplexError> {
    let mut blocks: Vec<(crate::cell::CellKind, Vec<u32>)> = Vec::new();
    let mut vs = Vec::new();
    for c in 0..st.n_top_cells() as u32 {
        let kind = st.top_cell_kind(CellId(c));
        vs.clear();
        st.top_cell_vertices(CellId(c), &mut vs);
        match blocks.last_mut() {
            Some((k, b)) if *k == kind => b.extend(vs.iter().map(|v| v.0)),
            _ => blocks.push((kind, vs.iter().map(|v| v.0).collect())),
        }
    }
    crate::complex::IndexedComplex::from_parts(
        ambient,
        crate::buf::Buf::from(coords),
        blocks
            .into_iter()
            .map(|(k, b)| (k, crate::buf::Buf::from(b)))
            .collect(),
    )
}
