//! Batched answers: one relation asked of many items (vertices, top cells, simplices), gathered
//! into compressed-sparse-row arrays. The one home of "every answer as arrays", used by
//! `starplex query --all --out` and by the Python bindings.
//!
//! Row `i` of an [`Answers`] (CSR) is `values[offsets[i]..offsets[i + 1]]`. Work is split into fixed chunks
//! of items answered in parallel and joined in item order, so the arrays do not depend on the
//! number of threads.
//!
//! ```
//! use starplex::complex::IndexedComplex;
//! use starplex::{buf::Buf, cell::CellKind};
//! use starplex::tds::iastar::IaStar;
//! use starplex::topo::batch::{self, Relation};
//! // two triangles sharing the edge 1-2
//! let coords = Buf::from(vec![0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0, 1.0]);
//! let cells = vec![(CellKind::Simplex(2), Buf::from(vec![0, 1, 2, 1, 3, 2]))];
//! let k = IndexedComplex::from_parts(2, coords, cells).unwrap();
//! let s = IaStar::new(&k).unwrap();
//! let vt = batch::gather(&s, Relation::Vt, &batch::all(4)).unwrap();
//! assert_eq!(vt.offsets, [0, 1, 3, 5, 6]);
//! assert_eq!(vt.values, [0, 0, 1, 0, 1, 1]);
//! ```
use rayon::prelude::*;

use super::{generic, Queries, QueryError, SimplexSet};
use crate::ids::{CellId, VertexId};

/// Items answered per parallel task.
const CHUNK: usize = 2048;

/// A ragged answer in compressed-sparse-row form.
///
/// ```
/// use starplex::topo::batch::Answers;
/// let c = Answers { offsets: vec![0, 2, 2, 3], values: vec![5, 6, 7] };
/// assert_eq!(c.row(0), &[5, 6]);
/// assert_eq!(c.n_rows(), 3);
/// ```
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Answers {
    /// `n_rows + 1` offsets into `values`, starting at 0.
    pub offsets: Vec<u64>,
    /// The rows, concatenated.
    pub values: Vec<u32>,
}

impl Answers {
    /// The number of rows.
    ///
    /// ```
    /// use starplex::topo::batch::Answers;
    /// assert_eq!(Answers { offsets: vec![0], values: vec![] }.n_rows(), 0);
    /// ```
    pub fn n_rows(&self) -> usize {
        self.offsets.len().saturating_sub(1)
    }

    /// Row `i`.
    ///
    /// ```
    /// use starplex::topo::batch::Answers;
    /// let c = Answers { offsets: vec![0, 1], values: vec![9] };
    /// assert_eq!(c.row(0), &[9]);
    /// ```
    pub fn row(&self, i: usize) -> &[u32] {
        &self.values[self.offsets[i] as usize..self.offsets[i + 1] as usize]
    }

    fn append(&mut self, other: Answers) {
        let base = self.values.len() as u64;
        self.offsets
            .extend(other.offsets.iter().skip(1).map(|o| o + base));
        self.values.extend(other.values);
    }
}

/// A relation asked of one item; the item is a vertex id unless said otherwise.
///
/// ```
/// use starplex::topo::batch::Relation;
/// assert_eq!(Relation::Vt.item(), "vertex");
/// assert_eq!(Relation::Tt.item(), "cell");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Relation {
    /// Top cells incident to a vertex (ids).
    Vt,
    /// Vertices adjacent to a vertex (ids).
    Vv,
    /// The vertices of a top cell (the item is a top cell id).
    Tv,
    /// Top cells of the same dimension sharing a facet with a top cell (the item is a top cell
    /// id; the IA* adjacency, non-manifold facets included).
    Tt,
}

impl Relation {
    /// What the items are: `"vertex"` or `"cell"`.
    ///
    /// ```
    /// use starplex::topo::batch::Relation;
    /// assert_eq!(Relation::Tv.item(), "cell");
    /// ```
    pub fn item(self) -> &'static str {
        match self {
            Relation::Vt | Relation::Vv => "vertex",
            Relation::Tv | Relation::Tt => "cell",
        }
    }

    /// How many items the structure has (vertices or top cells).
    ///
    /// ```
    /// use starplex::complex::IndexedComplex;
    /// use starplex::{buf::Buf, cell::CellKind, topo::naive::VtIndex};
    /// use starplex::topo::batch::Relation;
    /// let k = IndexedComplex::from_parts(1, Buf::from(vec![0.0, 1.0]),
    ///     vec![(CellKind::Simplex(1), Buf::from(vec![0, 1]))]).unwrap();
    /// assert_eq!(Relation::Vt.n_items(&VtIndex::new(&k)), 2);
    /// assert_eq!(Relation::Tt.n_items(&VtIndex::new(&k)), 1);
    /// ```
    pub fn n_items<S: Queries + ?Sized>(self, s: &S) -> usize {
        match self.item() {
            "vertex" => s.n_vertices(),
            _ => s.n_top_cells(),
        }
    }
}

/// Scratch space of one worker.
#[derive(Default)]
struct Scratch {
    cells: Vec<CellId>,
    verts: Vec<VertexId>,
    facet: Vec<VertexId>,
    tops: Vec<CellId>,
    /// A cell's facets, sorted, end to end, with where each ends; a candidate's vertices.
    facets: Vec<u32>,
    ends: Vec<usize>,
    ids: Vec<u32>,
}

/// The items `0..n`.
///
/// ```
/// assert_eq!(starplex::topo::batch::all(3), [0, 1, 2]);
/// ```
pub fn all(n: usize) -> Vec<u32> {
    (0..n as u32).collect()
}

/// Checks that every item is below `n`.
///
/// ```
/// use starplex::topo::batch::check_items;
/// assert!(check_items(&[0, 2], 3, "vertex").is_ok());
/// assert_eq!(check_items(&[0, 3], 3, "vertex").unwrap_err(),
///     "vertex 3 out of range (the complex has 3 vertices)");
/// ```
///
/// # Errors
/// The first item out of range, in the command line's words.
pub fn check_items(items: &[u32], n: usize, what: &str) -> Result<(), String> {
    match items.iter().find(|&&i| i as usize >= n) {
        None => Ok(()),
        Some(i) => Err(format!(
            "{what} {i} out of range (the complex has {n} {})",
            if what == "vertex" {
                "vertices"
            } else {
                "cells"
            }
        )),
    }
}

fn answer<S: Queries + ?Sized>(
    s: &S,
    r: Relation,
    i: u32,
    sc: &mut Scratch,
    out: &mut Vec<u32>,
) -> Result<(), QueryError> {
    match r {
        Relation::Vt => {
            s.vertex_top_cells(VertexId(i), &mut sc.cells);
            out.extend(sc.cells.iter().map(|c| c.0));
        }
        Relation::Vv => {
            s.vertex_neighbours(VertexId(i), &mut sc.verts);
            out.extend(sc.verts.iter().map(|v| v.0));
        }
        Relation::Tv => {
            sc.verts.clear(); // top_cell_vertices appends
            s.top_cell_vertices(CellId(i), &mut sc.verts);
            out.extend(sc.verts.iter().map(|v| v.0));
        }
        Relation::Tt => {
            sc.tops.clear();
            super::generic::facet_neighbours(
                s,
                CellId(i),
                &mut sc.facet,
                &mut sc.cells,
                &mut sc.tops,
            )?;
            let start = out.len();
            out.extend(sc.tops.iter().map(|c| c.0));
            out[start..].sort_unstable();
        }
    }
    Ok(())
}

/// Relation `r` of every item in `items`, as CSR rows in the order of `items`. Items must be in
/// range (see [`check_items`]). Parallel over chunks of items on the current rayon pool.
///
/// ```
/// use starplex::complex::IndexedComplex;
/// use starplex::{buf::Buf, cell::CellKind, topo::naive::VtIndex};
/// use starplex::topo::batch::{gather, Relation};
/// let k = IndexedComplex::from_parts(2, Buf::from(vec![0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0, 1.0]),
///     vec![(CellKind::Simplex(2), Buf::from(vec![0, 1, 2, 1, 3, 2]))]).unwrap();
/// let tt = gather(&VtIndex::new(&k), Relation::Tt, &[0, 1]).unwrap();
/// assert_eq!((tt.row(0), tt.row(1)), (&[1][..], &[0][..]));
/// ```
///
/// # Errors
/// The structure's own error (e.g. a relation it cannot answer).
pub fn gather<S: Queries + Sync + ?Sized>(
    s: &S,
    r: Relation,
    items: &[u32],
) -> Result<Answers, QueryError> {
    // many vertices: all rows at once where the structure makes them faster so
    if is_bulk(s, r, items.len()) {
        let rows = match r {
            Relation::Vt => s.vertex_top_rows(),
            Relation::Vv => s.vertex_neighbour_rows(),
            _ => None,
        };
        if let Some(rows) = rows {
            return gather_with(items, |i, _, out| {
                out.extend_from_slice(rows.row(i as usize));
                Ok(())
            });
        }
    }
    if r == Relation::Tt
        && is_bulk(s, r, items.len())
        && let Some(a) = facet_neighbours_by_rows(s, items, true)
    {
        return a;
    }
    gather_with(items, |i, sc, out| answer(s, r, i, sc, out))
}

/// True when [`gather`] answers `n` items of relation `r` in bulk: VT, VV or TT of at least
/// 1024 items and a quarter of the vertices (cells for TT), where the rows of every item are
/// made at once (where the structure or the complex allows it). A caller that answers items in
/// blocks should ask for them in one block then, or each block makes every row again.
///
/// ```
/// use starplex::topo::{batch::{self, Relation}, naive::VtIndex};
/// let k = starplex::generate::kuhn_grid(&[40, 40]).unwrap(); // 1681 vertices
/// let s = VtIndex::new(&k);
/// assert!(batch::is_bulk(&s, Relation::Vt, 1681));
/// assert!(!batch::is_bulk(&s, Relation::Vt, 100));
/// assert!(!batch::is_bulk(&s, Relation::Tv, 3200));
/// ```
pub fn is_bulk<S: Queries + ?Sized>(s: &S, r: Relation, n: usize) -> bool {
    let of = match r {
        Relation::Vt | Relation::Vv => s.n_vertices(),
        Relation::Tt => s.n_top_cells(),
        Relation::Tv => return false,
    };
    n >= 1024 && n * 4 >= of
}

/// [`Relation::Tt`] of every top cell (row `c`) by the bulk path of [`gather`], for a complex
/// of simplices; `None` for a complex with a CP cell.
///
/// ```
/// use starplex::topo::{batch, naive::VtIndex};
/// let k = starplex::generate::kuhn_grid(&[1, 1]).unwrap(); // two triangles on a diagonal
/// let tt = batch::facet_neighbours_all(&VtIndex::new(&k)).unwrap().unwrap();
/// assert_eq!((tt.row(0), tt.row(1)), (&[1][..], &[0][..]));
/// ```
///
/// # Errors
/// The structure's own error.
pub fn facet_neighbours_all<S: Queries + Sync + ?Sized>(
    s: &S,
) -> Option<Result<Answers, QueryError>> {
    facet_neighbours_by_rows(s, &all(s.n_top_cells()), false)
}

/// [`Relation::Tt`] of many top cells from the VT rows of every vertex (the structure's own,
/// [`VertexStar::vertex_top_rows`](super::VertexStar::vertex_top_rows), or counted from the top
/// cells), not from one top star per facet. For a simplex `c`, the cells of its dimension
/// sharing exactly `d` of its `d + 1` vertices are those across its facets (two simplices sharing
/// two facets share every vertex). A CP cell may hold a facet's vertices without the facet, so
/// in a complex with one the rows are [`cp_facet_neighbours`], as
/// [`generic::facet_neighbours`](super::generic::facet_neighbours) answers. `None` for a complex
/// without top cells, and for one with a CP cell unless `with_cp`.
fn facet_neighbours_by_rows<S: Queries + Sync + ?Sized>(
    s: &S,
    items: &[u32],
    with_cp: bool,
) -> Option<Result<Answers, QueryError>> {
    let nc = s.n_top_cells();
    if nc == 0 {
        return None;
    }
    let kinds: Vec<crate::cell::CellKind> =
        (0..nc as u32).map(|c| s.top_cell_kind(CellId(c))).collect();
    let simplicial = kinds.iter().all(|k| k.is_simplex());
    if !simplicial && !with_cp {
        return None;
    }
    let vt = s.vertex_top_rows().unwrap_or_else(|| {
        let mut tv = Vec::new();
        crate::csr::Csr::from_fn(s.n_vertices(), |push| {
            for c in 0..nc as u32 {
                tv.clear();
                s.top_cell_vertices(CellId(c), &mut tv);
                tv.iter().for_each(|v| push(v.0, c));
            }
        })
    });
    if !simplicial {
        return Some(gather_with(items, |c, sc, out| {
            cp_facet_neighbours(s, &kinds, &vt, c, sc, out);
            Ok(())
        }));
    }
    Some(gather_with(items, |c, sc, out| {
        let d = kinds[c as usize].dim();
        if d == 0 {
            return Ok(());
        }
        sc.verts.clear();
        s.top_cell_vertices(CellId(c), &mut sc.verts);
        each_cell_through(&vt, &sc.verts, &mut sc.cells, |u, shared| {
            if shared == d && u.0 != c && kinds[u.index()].dim() == d {
                out.push(u.0);
            }
        });
        Ok(())
    }))
}

/// One row of [`facet_neighbours_by_rows`] in a complex with CP cells: for each facet of `c`,
/// the other cells of `c`'s dimension having that facet as a face (a cell across two facets is
/// listed twice), sorted. The candidates are the cells through as many of `c`'s vertices as its
/// smallest facet has, counted from the VT rows of `c`'s vertices; only their vertices are read.
fn cp_facet_neighbours<S: Queries + ?Sized>(
    s: &S,
    kinds: &[crate::cell::CellKind],
    vt: &crate::csr::Csr,
    c: u32,
    sc: &mut Scratch,
    out: &mut Vec<u32>,
) {
    let kind = kinds[c as usize];
    let d = kind.dim();
    if d == 0 {
        return;
    }
    let Scratch {
        verts,
        cells,
        facet: cv,
        facets,
        ends,
        ids: uv,
        ..
    } = sc;
    verts.clear();
    s.top_cell_vertices(CellId(c), verts);
    // c's facets, sorted, end to end
    facets.clear();
    ends.clear();
    kind.for_each_oriented_facet(|l, _| {
        let start = facets.len();
        facets.extend(l.iter().map(|&x| verts[x as usize].0));
        facets[start..].sort_unstable();
        ends.push(facets.len());
    });
    let least = ends
        .iter()
        .scan(0, |prev, &e| Some(e - std::mem::replace(prev, e)))
        .min()
        .unwrap_or(0);
    each_cell_through(vt, verts, cells, |u, shared| {
        let ku = kinds[u.index()];
        if shared >= least && u.0 != c && ku.dim() == d {
            cv.clear();
            s.top_cell_vertices(u, cv);
            uv.clear();
            uv.extend(cv.iter().map(|v| v.0));
            let mut from = 0;
            for &e in ends.iter() {
                if ku.has_face(uv, &facets[from..e]) {
                    out.push(u.0);
                }
                from = e;
            }
        }
    });
}

/// Calls `f(u, k)` for every cell `u` through at least one of `verts`, in increasing id
/// order, with the number `k` of them it goes through (from the VT rows `vt`; `cells` is
/// scratch).
fn each_cell_through(
    vt: &crate::csr::Csr,
    verts: &[VertexId],
    cells: &mut Vec<CellId>,
    mut f: impl FnMut(CellId, usize),
) {
    cells.clear();
    for v in verts {
        cells.extend(vt.row(v.index()).iter().map(|&u| CellId(u)));
    }
    cells.sort_unstable();
    for run in cells.chunk_by(|x, y| x == y) {
        f(run[0], run.len());
    }
}

/// The vertices of simplices in `simplices` (flat, `width` ids each) that relation `f` gives, as
/// CSR rows: the common frame of [`boundary`], [`coboundary`] and [`adjacent`].
fn gather_simplices<F>(simplices: &[u32], width: usize, f: F) -> Result<Answers, QueryError>
where
    F: Fn(&[VertexId], &mut Vec<VertexId>) -> Result<(), QueryError> + Sync,
{
    if width == 0 {
        return Ok(Answers {
            offsets: vec![0],
            values: Vec::new(),
        });
    }
    let n = simplices.len() / width;
    let items = all(n);
    gather_with(&items, |i, sc, out| {
        let s = &simplices[i as usize * width..(i as usize + 1) * width];
        sc.facet.clear();
        sc.facet.extend(s.iter().map(|&v| VertexId(v)));
        f(&sc.facet, &mut sc.verts)?;
        out.extend(sc.verts.iter().map(|v| v.0));
        Ok(())
    })
}

/// The q-faces of each simplex (flat, `width` vertex ids each): rows of `q + 1` ids.
///
/// ```
/// use starplex::complex::IndexedComplex;
/// use starplex::{buf::Buf, cell::CellKind, tds::iastar::IaStar};
/// use starplex::topo::batch::boundary;
/// let k = IndexedComplex::from_parts(2, Buf::from(vec![0.0, 0.0, 1.0, 0.0, 0.0, 1.0]),
///     vec![(CellKind::Simplex(2), Buf::from(vec![0, 1, 2]))]).unwrap();
/// let b = boundary(&IaStar::new(&k).unwrap(), &[0, 1, 2], 3, 1).unwrap();
/// assert_eq!(b.row(0).len(), 6); // three edges, two ids each
/// ```
///
/// # Errors
/// A simplex not in the complex, or the structure's own error.
pub fn boundary<S: Queries + Sync + ?Sized>(
    s: &S,
    simplices: &[u32],
    width: usize,
    q: usize,
) -> Result<Answers, QueryError> {
    gather_simplices(simplices, width, |x, out| s.boundary(x, q, out))
}

/// The q-cofaces of each simplex: rows of `q + 1` ids.
///
/// ```
/// use starplex::complex::IndexedComplex;
/// use starplex::{buf::Buf, cell::CellKind, tds::iastar::IaStar};
/// use starplex::topo::batch::coboundary;
/// let k = IndexedComplex::from_parts(2, Buf::from(vec![0.0, 0.0, 1.0, 0.0, 0.0, 1.0]),
///     vec![(CellKind::Simplex(2), Buf::from(vec![0, 1, 2]))]).unwrap();
/// let c = coboundary(&IaStar::new(&k).unwrap(), &[0], 1, 1).unwrap();
/// assert_eq!(c.row(0), &[0, 1, 0, 2]);
/// ```
///
/// # Errors
/// A simplex not in the complex, or the structure's own error.
pub fn coboundary<S: Queries + Sync + ?Sized>(
    s: &S,
    simplices: &[u32],
    width: usize,
    q: usize,
) -> Result<Answers, QueryError> {
    gather_simplices(simplices, width, |x, out| s.coboundary(x, q, out))
}

/// The simplices adjacent to each simplex (same dimension): rows of `width` ids each.
///
/// ```
/// use starplex::complex::IndexedComplex;
/// use starplex::{buf::Buf, cell::CellKind, tds::iastar::IaStar};
/// use starplex::topo::batch::adjacent;
/// let k = IndexedComplex::from_parts(2, Buf::from(vec![0.0, 0.0, 1.0, 0.0, 0.0, 1.0]),
///     vec![(CellKind::Simplex(2), Buf::from(vec![0, 1, 2]))]).unwrap();
/// let a = adjacent(&IaStar::new(&k).unwrap(), &[0], 1).unwrap();
/// assert_eq!(a.row(0), &[1, 2]);
/// ```
///
/// # Errors
/// A simplex not in the complex, or the structure's own error.
pub fn adjacent<S: Queries + Sync + ?Sized>(
    s: &S,
    simplices: &[u32],
    width: usize,
) -> Result<Answers, QueryError> {
    gather_simplices(simplices, width, |x, out| s.adjacent(x, out))
}

/// Star or link of many vertices, level by level: entry `p` is a CSR whose row `i` holds the
/// p-simplices (`p + 1` ids each, flat) of item `i`'s answer.
///
/// ```
/// use starplex::complex::IndexedComplex;
/// use starplex::{buf::Buf, cell::CellKind, tds::iastar::IaStar};
/// use starplex::topo::batch::levels;
/// let k = IndexedComplex::from_parts(2, Buf::from(vec![0.0, 0.0, 1.0, 0.0, 0.0, 1.0]),
///     vec![(CellKind::Simplex(2), Buf::from(vec![0, 1, 2]))]).unwrap();
/// let link = levels(&IaStar::new(&k).unwrap(), true, &[0]).unwrap();
/// assert_eq!(link[1].row(0), &[1, 2]); // the link of vertex 0 is the edge 1-2
/// ```
///
/// # Errors
/// The structure's own error (a CP star has no link, a star over the budget, ...).
pub fn levels<S: Queries + Sync + ?Sized>(
    s: &S,
    link: bool,
    items: &[u32],
) -> Result<Vec<Answers>, QueryError> {
    let parts: Vec<Vec<Answers>> = items
        .par_chunks(CHUNK)
        .map(|chunk| {
            let mut lv: Vec<Answers> = Vec::new();
            for (j, &v) in chunk.iter().enumerate() {
                let set: SimplexSet = if link {
                    // from the top cells around the vertex (no star listed first); a CP star
                    // gets the structure's own answer (its error)
                    match super::from_tops::link(s, &[VertexId(v)], super::DEFAULT_BUDGET) {
                        Err(QueryError::NotSimplicial(_)) => generic::link(s, &[VertexId(v)])?,
                        r => r?,
                    }
                } else {
                    s.star(&[VertexId(v)])?
                };
                while lv.len() < set.levels.len() {
                    lv.push(Answers {
                        offsets: vec![0; j + 1],
                        values: Vec::new(),
                    });
                }
                for (p, l) in lv.iter_mut().enumerate() {
                    if let Some(x) = set.levels.get(p) {
                        l.values.extend(x.iter().map(|v| v.0));
                    }
                    l.offsets.push(l.values.len() as u64);
                }
            }
            Ok(lv)
        })
        .collect::<Result<_, QueryError>>()?;
    let mut out: Vec<Answers> = Vec::new();
    let mut done = 0usize;
    for (part, chunk) in parts.into_iter().zip(items.chunks(CHUNK)) {
        while out.len() < part.len() {
            out.push(Answers {
                offsets: vec![0; done + 1],
                values: Vec::new(),
            });
        }
        let mut part = part.into_iter();
        for l in out.iter_mut() {
            match part.next() {
                Some(p) => l.append(p),
                None => {
                    let last = *l.offsets.last().unwrap_or(&0);
                    l.offsets.extend(std::iter::repeat_n(last, chunk.len()));
                }
            }
        }
        done += chunk.len();
    }
    Ok(out)
}

/// Every p-simplex of the complex, flat (`p + 1` ids each), in the structure's order.
///
/// ```
/// use starplex::complex::IndexedComplex;
/// use starplex::{buf::Buf, cell::CellKind, tds::iastar::IaStar};
/// use starplex::topo::batch::faces;
/// let k = IndexedComplex::from_parts(2, Buf::from(vec![0.0, 0.0, 1.0, 0.0, 0.0, 1.0]),
///     vec![(CellKind::Simplex(2), Buf::from(vec![0, 1, 2]))]).unwrap();
/// assert_eq!(faces(&IaStar::new(&k).unwrap(), 1).unwrap().len(), 6);
/// ```
///
/// # Errors
/// The structure's own error (CP cells, over the budget).
pub fn faces<S: Queries + ?Sized>(s: &S, p: usize) -> Result<Vec<u32>, QueryError> {
    s.faces_flat(p)
}

fn gather_with<F>(items: &[u32], f: F) -> Result<Answers, QueryError>
where
    F: Fn(u32, &mut Scratch, &mut Vec<u32>) -> Result<(), QueryError> + Sync,
{
    let parts: Vec<Answers> = items
        .par_chunks(CHUNK)
        .map_init(Scratch::default, |sc, chunk| {
            let mut c = Answers {
                offsets: Vec::with_capacity(chunk.len() + 1),
                values: Vec::new(),
            };
            c.offsets.push(0);
            for &i in chunk {
                f(i, sc, &mut c.values)?;
                c.offsets.push(c.values.len() as u64);
            }
            Ok(c)
        })
        .collect::<Result<_, QueryError>>()?;
    let mut out = Answers {
        offsets: Vec::with_capacity(items.len() + 1),
        values: Vec::with_capacity(parts.iter().map(|p| p.values.len()).sum()),
    };
    out.offsets.push(0);
    for p in parts {
        out.append(p);
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::buf::Buf;
    use crate::cell::CellKind;
    use crate::complex::IndexedComplex;
    use crate::topo::naive::VtIndex;
    use crate::topo::TopCells;

    fn strip(n: u32) -> IndexedComplex {
        // a strip of 2n triangles over 2(n+1) vertices
        let mut coords = Vec::new();
        for i in 0..=n {
            coords.extend([i as f64, 0.0, i as f64, 1.0]);
        }
        let mut cells = Vec::new();
        for i in 0..n {
            let (a, b, c, d) = (2 * i, 2 * i + 1, 2 * i + 2, 2 * i + 3);
            cells.extend([a, c, b, b, c, d]);
        }
        IndexedComplex::from_parts(
            2,
            Buf::from(coords),
            vec![(CellKind::Simplex(2), Buf::from(cells))],
        )
        .unwrap()
    }

    #[test]
    fn gather_equals_one_by_one_across_chunks() {
        let k = strip(3000);
        let s = VtIndex::new(&k);
        let items = all(s.n_vertices());
        for r in [Relation::Vt, Relation::Vv, Relation::Tv, Relation::Tt] {
            let n = r.n_items(&s);
            let c = gather(&s, r, &items[..n]).unwrap();
            assert_eq!(c.n_rows(), n);
            for i in [0, 1, CHUNK - 1, CHUNK, n - 1] {
                let one = gather(&s, r, &[i as u32]).unwrap();
                assert_eq!(c.row(i), one.row(0), "{r:?} item {i}");
            }
        }
        let lk = levels(&s, true, &items).unwrap();
        assert_eq!(lk.len(), 2);
        for l in &lk {
            assert_eq!(l.n_rows(), items.len());
        }
        for i in [0usize, CHUNK + 5, items.len() - 1] {
            let one = levels(&s, true, &[i as u32]).unwrap();
            for p in 0..2 {
                assert_eq!(lk[p].row(i), one[p].row(0), "link level {p} of {i}");
            }
        }
    }

    /// The bulk TT of a simplicial complex (VT rows, cells sharing d vertices) equals the one
    /// cell at a time answer (a top star per facet) on every cell: random tetrahedra, triangles
    /// and edges over few vertices, so facets are shared by up to several cells (non-manifold)
    /// and dimensions mix; for the VT index and the Stellar tree.
    #[test]
    fn bulk_facet_neighbours_equal_one_by_one() {
        use crate::complex::{BuildOptions, ComplexBuilder};
        use crate::stellar::{StellarOptions, StellarTree};
        let mut rng = crate::testkit::XorShift::new(7);
        let mut b = ComplexBuilder::new(3).unwrap();
        let nv = 60u32;
        for i in 0..nv {
            b.push_vertex(&[i as f64, (i * i % 7) as f64, (i % 5) as f64])
                .unwrap();
        }
        let mut seen = std::collections::BTreeSet::new();
        while seen.len() < 3000 {
            let k = [4, 4, 4, 3, 2][rng.below(5) as usize];
            let mut c: Vec<u32> = Vec::new();
            while c.len() < k {
                let v = rng.below(nv as u64) as u32;
                if !c.contains(&v) {
                    c.push(v);
                }
            }
            let mut key = c.clone();
            key.sort_unstable();
            if seen.insert(key) {
                b.push_cell(CellKind::Simplex(k as u8 - 1), &c).unwrap();
            }
        }
        let opts = BuildOptions {
            drop_face_cells: true,
            ..Default::default()
        };
        let k = b.build(&opts).unwrap().0;
        let t = StellarTree::build(&k, &StellarOptions::default()).unwrap();
        let vt = VtIndex::new(&k);
        let items = all(k.n_cells());
        let structures: [&(dyn Queries + Sync); 2] = [&vt, &t];
        for s in structures {
            let bulk = gather(s, Relation::Tt, &items).unwrap();
            for (i, &c) in items.iter().enumerate() {
                let one = gather(s, Relation::Tt, &[c]).unwrap();
                assert_eq!(bulk.row(i), one.row(0), "cell {c}");
            }
        }
    }

    /// The bulk TT of a complex with CP cells (each facet's candidates from the VT rows, kept
    /// when the facet is one of their faces) equals the one cell at a time answer on every
    /// cell. Each new cell is put on a facet of an earlier one, so quads and triangles are
    /// shared by several hexahedra, prisms, pyramids and tetrahedra (non-manifold), and some
    /// tetrahedra take three corners of a quad, which they hold without the quad being a face;
    /// for the VT index, the IA* and the Stellar tree.
    #[test]
    fn bulk_facet_neighbours_of_cp_cells_equal_one_by_one() {
        use crate::complex::{BuildOptions, ComplexBuilder};
        use crate::stellar::{StellarOptions, StellarTree};
        use crate::tds::iastar::IaStar;
        let mut rng = crate::testkit::XorShift::new(11);
        let nv = 40u32;
        let kinds = [
            CellKind::Hex,
            CellKind::Prism,
            CellKind::Pyramid,
            CellKind::Simplex(3),
        ];
        let mut cells: Vec<(CellKind, Vec<u32>)> = vec![(CellKind::Hex, (0..8).collect())];
        let mut seen = std::collections::BTreeSet::new();
        seen.insert((0..8).collect::<Vec<u32>>());
        let mut tries = 0;
        while cells.len() < 600 && tries < 100_000 {
            tries += 1;
            let (pk, pv) = &cells[rng.below(cells.len() as u64) as usize];
            let mut facets = Vec::new();
            pk.for_each_oriented_facet(|l, _| {
                facets.push(l.iter().map(|&x| pv[x as usize]).collect::<Vec<u32>>())
            });
            let f = &facets[rng.below(facets.len() as u64) as usize];
            let kind = kinds[rng.below(4) as usize];
            let mut v = vec![u32::MAX; kind.n_vertices()];
            if kind == CellKind::Simplex(3) && f.len() == 4 {
                // three corners of a quad and one more vertex
                v[..3].copy_from_slice(&f[..3]);
            } else {
                // the new cell's first facet of the same size is f
                let mut first = None;
                kind.for_each_oriented_facet(|l, _| {
                    if first.is_none() && l.len() == f.len() {
                        first = Some(l.to_vec());
                    }
                });
                let Some(l) = first else { continue };
                for (&x, &w) in l.iter().zip(f) {
                    v[x as usize] = w;
                }
            }
            for i in 0..v.len() {
                while v[i] == u32::MAX {
                    let w = rng.below(nv as u64) as u32;
                    if !v.contains(&w) {
                        v[i] = w;
                    }
                }
            }
            let mut key = v.clone();
            key.sort_unstable();
            if seen.insert(key) {
                cells.push((kind, v));
            }
        }
        assert_eq!(cells.len(), 600);
        let mut b = ComplexBuilder::new(3).unwrap();
        for i in 0..nv {
            b.push_vertex(&[i as f64, (i * i % 7) as f64, (i % 5) as f64])
                .unwrap();
        }
        for (kind, v) in &cells {
            b.push_cell(*kind, v).unwrap();
        }
        let opts = BuildOptions {
            drop_face_cells: true,
            ..Default::default()
        };
        let k = b.build(&opts).unwrap().0;
        let t = StellarTree::build(&k, &StellarOptions::default()).unwrap();
        let ia = IaStar::new(&k).unwrap();
        let vt = VtIndex::new(&k);
        let items = all(k.n_cells());
        let structures: [&(dyn Queries + Sync); 3] = [&vt, &ia, &t];
        let mut shared = 0;
        for s in structures {
            let bulk = facet_neighbours_by_rows(s, &items, true).unwrap().unwrap();
            for (i, &c) in items.iter().enumerate() {
                let one = gather(s, Relation::Tt, &[c]).unwrap();
                assert_eq!(bulk.row(i), one.row(0), "cell {c}");
                shared += usize::from(bulk.row(i).len() > 6);
            }
        }
        // some faces are shared by more than two cells
        assert!(shared > 0);
    }
}
