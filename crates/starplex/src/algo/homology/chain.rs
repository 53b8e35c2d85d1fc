//! The Morse complex of a simplicial complex as a value, and the homology of any finite chain
//! complex given by its boundary matrices: the two halves of a homology computation that a
//! caller splits, e.g. ranks that each reduce their own region ([`MorseComplex`]) and one that
//! ranks what is left ([`chain_complex_homology`]).
//!
//! The [`MorseComplex`] is the same gradient as [`super::homology`] builds (same vertex order
//! choice, same lower-star matching), kept with the complex so that any chain of the complex can
//! be pushed onto the critical cells afterwards: [`MorseComplex::project`] is the chain map
//! `π: C(K) → M(K)` (a critical cell gives itself; every other cell follows the gradient paths
//! down), and [`MorseComplex::boundaries`] the Morse boundary `π ∘ ∂` of the critical cells. A
//! complex `K ⊂ L` reduced this way can be glued back: `M(K) ⊕ C(L \ K)`, with `∂' = π ∘ ∂` on
//! the cells of `L \ K`, has the homology of `L` (the gradient of `K` is an acyclic matching of
//! `L` whose paths stay in `K`).
use std::borrow::Cow;

use rayon::prelude::*;

use super::cells::{self, Cell};
use super::morse::{Gradient, Scratch};
use super::{
    finish_order, flow_err, morse_gradient, order, pick_order, reduce, smith, Field, HomologyError,
    HomologyOptions,
};
use crate::complex::IndexedComplex;
use crate::limits::{TooLarge, Unit};
use crate::topo::{QueryError, TopCells};

/// A simplicial complex with its discrete gradient: the critical cells per dimension, their
/// Morse boundaries, and the projection of chains onto them.
///
/// ```
/// use starplex::algo::homology::{chain_complex_homology, Field, HomologyOptions, MorseComplex};
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// // a hollow triangle (a circle) and, glued on later, the triangle that fills it
/// let mut b = ComplexBuilder::new(2).unwrap();
/// for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// for e in [[0, 1], [1, 2], [0, 2]] { b.push_cell(CellKind::Simplex(1), &e).unwrap(); }
/// let k = b.build(&BuildOptions::default()).unwrap().0;
/// let m = MorseComplex::new(&k, &HomologyOptions::default()).unwrap();
/// assert_eq!(m.n_critical(), vec![1, 1]); // a vertex and an edge
/// // the boundary of the triangle [0, 1, 2] is [1,2] - [0,2] + [0,1]; pushed onto M(K):
/// let pi = m.project(&[1, 2, 0, 2, 0, 1], 2).unwrap();
/// let mut col: Vec<(u32, i64)> = Vec::new();
/// for (x, s) in pi.into_iter().zip([1i64, -1, 1]) {
///     col.extend(x.into_iter().map(|(i, c)| (i, c * s)));
/// }
/// // M(K) ⊕ {the triangle}: 1 vertex, 1 edge, 1 triangle whose boundary is ± the edge
/// let d1 = m.boundaries(1).unwrap();
/// let h = chain_complex_homology(&[1, 1, 1], vec![vec![], d1, vec![col]], Field::Z, u64::MAX).unwrap();
/// assert_eq!(h.0, vec![1, 0, 0]); // a disc
/// ```
pub struct MorseComplex {
    flat: order::Flat,
    apex: Vec<u32>,
    crit: Vec<Vec<Cell>>,
    /// The gradient's vertex numbering (`to_new[input]`), `None` when it is the input's.
    to_new: Option<Vec<u32>>,
    /// The modulus of the coefficients (0: integers).
    m: i64,
}

impl MorseComplex {
    /// Builds the gradient of a simplicial complex (vertex order, budgets and field from
    /// `opts`; `per_component` and `generators` are ignored). Top cells that are faces of
    /// other top cells, or repeated, are accepted: they add no face (the lower stars are sets
    /// of faces), so the gradient is that of the complex they generate.
    ///
    /// ```
    /// use starplex::algo::homology::{HomologyOptions, MorseComplex};
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// let mut b = ComplexBuilder::new(3).unwrap();
    /// for p in [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]] { b.push_vertex(&p).unwrap(); }
    /// b.push_cell(CellKind::Simplex(3), &[0, 1, 2, 3]).unwrap();
    /// let m = MorseComplex::new(&b.build(&BuildOptions::default()).unwrap().0, &HomologyOptions::default()).unwrap();
    /// assert_eq!(m.n_critical(), vec![1, 0, 0, 0]); // a tetrahedron is contractible
    /// ```
    ///
    /// # Errors
    /// [`HomologyError::Query`] when a cell is not a simplex; [`HomologyError::TooLarge`] as
    /// [`super::homology`]; also when the vertex references do not fit 32 bits.
    pub fn new(k: &IndexedComplex, opts: &HomologyOptions) -> Result<MorseComplex, HomologyError> {
        simplicial_only(k)?;
        let nv = k.n_vertices();
        let dmax = k.blocks().iter().map(|b| b.kind.dim()).max().unwrap_or(0);
        let (flat, to_new) = match pick_order(k, opts.order, None, Some(k)) {
            None => {
                let id: Vec<u32> = (0..nv as u32).collect();
                (order::Flat::new(k, &id).ok_or_else(refs_error)?, None)
            }
            Some(fa) => {
                let f = order::Flat::new(k, &fa).ok_or_else(refs_error)?;
                reordered(f, fa, opts.order)
            }
        };
        MorseComplex::build(flat, to_new, nv, dmax, opts)
    }

    /// [`MorseComplex::new`] consuming the complex: its cells are renumbered in place and its
    /// coordinates freed before the gradient is built, so the input and the gradient's copy
    /// never coexist (the least memory; the same answer).
    ///
    /// ```
    /// use starplex::algo::homology::{HomologyOptions, MorseComplex};
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// let mut b = ComplexBuilder::new(2).unwrap();
    /// for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]] { b.push_vertex(&p).unwrap(); }
    /// for e in [[0, 1], [1, 2], [0, 2]] { b.push_cell(CellKind::Simplex(1), &e).unwrap(); }
    /// let k = b.build(&BuildOptions::default()).unwrap().0;
    /// let m = MorseComplex::from_complex(k, &HomologyOptions::default()).unwrap();
    /// assert_eq!(m.n_critical(), vec![1, 1]);
    /// ```
    ///
    /// # Errors
    /// As [`MorseComplex::new`].
    pub fn from_complex(
        k: IndexedComplex,
        opts: &HomologyOptions,
    ) -> Result<MorseComplex, HomologyError> {
        simplicial_only(&k)?;
        let nv = k.n_vertices();
        let dmax = k.blocks().iter().map(|b| b.kind.dim()).max().unwrap_or(0);
        let (flat, to_new) = match pick_order(&k, opts.order, Some(k.n_refs() as u64), Some(&k)) {
            None if order::Flat::takes_over(&k) => {
                (order::Flat::input_order(k).ok_or_else(refs_error)?, None)
            }
            None => {
                let id: Vec<u32> = (0..nv as u32).collect();
                (
                    order::Flat::from_complex(k, &id).ok_or_else(refs_error)?,
                    None,
                )
            }
            Some(fa) => {
                let f = order::Flat::from_complex(k, &fa).ok_or_else(refs_error)?;
                reordered(f, fa, opts.order)
            }
        };
        MorseComplex::build(flat, to_new, nv, dmax, opts)
    }

    /// The gradient over `flat` (in the numbering `to_new`, `None`: the input's).
    fn build(
        flat: order::Flat,
        to_new: Option<Vec<u32>>,
        nv: usize,
        dmax: usize,
        opts: &HomologyOptions,
    ) -> Result<MorseComplex, HomologyError> {
        let (apex, crit) = if flat.n_top_cells() == 0 {
            // isolated vertices only: every vertex is critical
            let mut crit = vec![Vec::new(); dmax + 1];
            crit[0] = (0..nv as u32)
                .map(|v| Cell::simplex(cells::Key::from_slice(&[v])))
                .collect();
            (vec![super::morse::ALONE; nv], crit)
        } else {
            let g = morse_gradient(
                &flat,
                flat.fast_star(),
                opts,
                true,
                dmax,
                std::time::Instant::now(),
            )?;
            (g.apex.into_owned(), g.crit.into_owned())
        };
        Ok(MorseComplex {
            flat,
            apex,
            crit,
            to_new,
            m: opts.field.modulus(),
        })
    }

    fn gradient(&self) -> Gradient<'_, order::Flat> {
        Gradient {
            s: &self.flat,
            fast: self.flat.fast_star(),
            apex: Cow::Borrowed(&self.apex),
            crit: Cow::Borrowed(&self.crit),
        }
    }

    /// The number of critical cells per dimension (0 to the complex's dimension).
    ///
    /// ```
    /// # use starplex::algo::homology::{HomologyOptions, MorseComplex};
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// let mut b = ComplexBuilder::new(1).unwrap();
    /// for x in 0..3 { b.push_vertex(&[x as f64]).unwrap(); }
    /// let m = MorseComplex::new(&b.build(&BuildOptions::default()).unwrap().0, &HomologyOptions::default()).unwrap();
    /// assert_eq!(m.n_critical(), vec![3]); // three points
    /// ```
    pub fn n_critical(&self) -> Vec<usize> {
        self.crit.iter().map(Vec::len).collect()
    }

    /// The Morse boundaries of the critical `dim`-cells, in their order: columns of
    /// `(critical (dim-1)-cell, coefficient)` sorted by row, coefficients in `1..p` over Z/p and
    /// integers over Q and Z (empty columns for `dim` 0 or beyond the complex).
    ///
    /// ```
    /// # use starplex::algo::homology::{HomologyOptions, MorseComplex};
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// let mut b = ComplexBuilder::new(1).unwrap();
    /// for x in 0..2 { b.push_vertex(&[x as f64]).unwrap(); }
    /// b.push_cell(CellKind::Simplex(1), &[0, 1]).unwrap();
    /// b.push_vertex(&[5.0]).unwrap();
    /// let m = MorseComplex::new(&b.build(&BuildOptions::default()).unwrap().0, &HomologyOptions::default()).unwrap();
    /// assert_eq!(m.n_critical(), vec![2, 0]);
    /// assert!(m.boundaries(1).unwrap().is_empty());
    /// ```
    ///
    /// # Errors
    /// [`HomologyError::Overflow`] when integer coefficients overflow.
    pub fn boundaries(&self, dim: usize) -> Result<Vec<Vec<(u32, i64)>>, HomologyError> {
        let Some(cs) = self.crit.get(dim) else {
            return Ok(Vec::new());
        };
        if dim == 0 || self.crit[dim - 1].is_empty() {
            return Ok(vec![Vec::new(); cs.len()]);
        }
        let g = self.gradient();
        cs.par_iter()
            .map_init(Scratch::default, |w, c| {
                g.flow(&[(c.clone(), 1)], self.m, None, w)
            })
            .collect::<Result<Vec<_>, _>>()
            .map_err(flow_err)
    }

    /// The projections onto the critical cells of the simplices `simplices` (consecutive
    /// runs of `arity` vertex ids of the complex, each run sorted increasingly, every one a face
    /// of the complex), each with coefficient +1: for each, `(critical cell of dimension
    /// arity - 1, coefficient)` sorted by cell, as [`MorseComplex::boundaries`].
    ///
    /// ```
    /// # use starplex::algo::homology::{HomologyOptions, MorseComplex};
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// let mut b = ComplexBuilder::new(1).unwrap();
    /// for x in 0..3 { b.push_vertex(&[x as f64]).unwrap(); }
    /// b.push_cell(CellKind::Simplex(1), &[0, 1]).unwrap();
    /// b.push_cell(CellKind::Simplex(1), &[1, 2]).unwrap();
    /// let m = MorseComplex::new(&b.build(&BuildOptions::default()).unwrap().0, &HomologyOptions::default()).unwrap();
    /// // a path: every vertex is homologous to the one critical vertex
    /// assert_eq!(m.project(&[0, 1, 2], 1).unwrap(), vec![vec![(0, 1)]; 3]);
    /// // and no edge survives
    /// assert_eq!(m.project(&[0, 1, 1, 2], 2).unwrap(), vec![vec![], vec![]]);
    /// ```
    ///
    /// # Errors
    /// [`HomologyError::Query`] for a run that is not sorted, has a vertex out of range or whose
    /// dimension exceeds the complex's; [`HomologyError::Overflow`] when integer coefficients
    /// overflow.
    pub fn project(
        &self,
        simplices: &[u32],
        arity: usize,
    ) -> Result<Vec<Vec<(u32, i64)>>, HomologyError> {
        if arity == 0 || simplices.is_empty() {
            return Ok(Vec::new());
        }
        let nv = self.apex.len();
        if let Some(bad) = simplices.chunks(arity).find(|s| {
            s.len() != arity
                || s.windows(2).any(|w| w[0] >= w[1])
                || s.iter().any(|&v| v as usize >= nv)
                || arity > self.crit.len()
        }) {
            return Err(HomologyError::Query(QueryError::NotInComplex(bad.to_vec())));
        }
        if self.crit[arity - 1].is_empty() {
            // nothing critical in this dimension: every projection is zero
            return Ok(vec![Vec::new(); simplices.len() / arity]);
        }
        let g = self.gradient();
        let cells: Vec<(Cell, i64)> = simplices
            .par_chunks(arity)
            .map(|s| {
                let (key, sign) = match &self.to_new {
                    None => (cells::Key::from_slice(s), 1),
                    Some(t) => {
                        let mapped: cells::Key = s.iter().map(|&v| t[v as usize]).collect();
                        cells::sort_with_sign(&mapped)
                    }
                };
                (Cell::simplex(key), sign as i64)
            })
            .collect();
        // one batch of neighbouring cells per thread: a batch follows each gradient path once
        // (its memo holds at most 2^18 cells, about 25 MB, then starts again: on grid95 over 4
        // ranks, caps of 2^18 to 2^24 took the same time, and 2^20 and more 160 MB more)
        let per = cells.len().div_ceil(rayon::current_num_threads()).max(256);
        let parts: Vec<Vec<Vec<(u32, i64)>>> = cells
            .par_chunks(per)
            .map_init(Scratch::default, |w, batch| {
                let only: Vec<Cell> = batch.iter().map(|(c, _)| c.clone()).collect();
                let mut pi = g.project_batch(&only, self.m, 1 << 18, w)?;
                // the memo changes nothing: each cell followed alone gives the same chain
                #[cfg(debug_assertions)]
                for (c, x) in only.iter().zip(&pi) {
                    debug_assert_eq!(&g.project(&[(c.clone(), 1)], self.m, w)?, x);
                }
                for (col, (_, sign)) in pi.iter_mut().zip(batch) {
                    if *sign != 1 {
                        for x in col.iter_mut() {
                            x.1 = if self.m > 0 {
                                (x.1 * sign).rem_euclid(self.m)
                            } else {
                                x.1 * sign
                            };
                        }
                    }
                }
                Ok(pi)
            })
            .collect::<Result<_, _>>()
            .map_err(flow_err)?;
        Ok(parts.into_iter().flatten().collect())
    }
}

fn simplicial_only(k: &IndexedComplex) -> Result<(), HomologyError> {
    match k.blocks().iter().find(|b| !b.kind.is_simplex()) {
        Some(b) => Err(HomologyError::Query(QueryError::NotSimplicial(format!(
            "a {} cell (the Morse complex is built for simplicial complexes)",
            b.kind
        )))),
        None => Ok(()),
    }
}

fn refs_error() -> HomologyError {
    HomologyError::TooLarge(TooLarge::ids(
        "homology: vertex references",
        u32::MAX as u128,
    ))
}

/// The final order after the first-appearance one (`fa`) and `to_new[input]`.
fn reordered(
    f: order::Flat,
    fa: Vec<u32>,
    o: super::VertexOrder,
) -> (order::Flat, Option<Vec<u32>>) {
    let (f, to_old) = finish_order(f, fa, o);
    let mut to_new = vec![0u32; to_old.len()];
    for (new, &old) in to_old.iter().enumerate() {
        to_new[old as usize] = new as u32;
    }
    (f, Some(to_new))
}

/// Betti numbers (and over Z the torsion of each `H_k`) of the chain complex with `n[k]` cells
/// in dimension `k` and boundary matrices `cols[k]` (`cols[k][j]`: the column of the `j`-th
/// `k`-cell, `(row among the (k-1)-cells, integer coefficient)` in any order, repeats summed;
/// `cols[0]` is ignored). Over Z/p by sparse column reduction with clearing, over Q and Z by
/// unit-pivot elimination and a checked Smith normal form of at most `max_dense` dense entries.
///
/// ```
/// use starplex::algo::homology::{chain_complex_homology, Field};
/// // RP^2 as a CW complex: one cell per dimension, ∂_1 = 0, ∂_2 = 2
/// let cols = vec![vec![], vec![vec![]], vec![vec![(0, 2)]]];
/// let z = chain_complex_homology(&[1, 1, 1], cols.clone(), Field::Z, 1 << 20).unwrap();
/// assert_eq!(z, (vec![1, 0, 0], vec![vec![], vec![2], vec![]]));
/// let z2 = chain_complex_homology(&[1, 1, 1], cols, Field::Z2, 1 << 20).unwrap();
/// assert_eq!(z2.0, vec![1, 1, 1]);
/// ```
///
/// # Errors
/// [`HomologyError::Query`] when a row is out of range or `cols` and `n` disagree;
/// [`HomologyError::Overflow`] and [`HomologyError::TooLarge`] over Q and Z.
#[allow(clippy::type_complexity)]
pub fn chain_complex_homology(
    n: &[usize],
    mut cols: Vec<Vec<Vec<(u32, i64)>>>,
    field: Field,
    max_dense: u64,
) -> Result<(Vec<u64>, Vec<Vec<u128>>), HomologyError> {
    let top = n.len();
    cols.resize(top, Vec::new());
    for k in 1..top {
        if cols[k].len() != n[k] {
            return Err(HomologyError::Query(QueryError::NotSimplicial(format!(
                "{} boundary columns for {} cells of dimension {k}",
                cols[k].len(),
                n[k]
            ))));
        }
        if let Some(&(r, _)) = cols[k]
            .iter()
            .flatten()
            .find(|&&(r, _)| r as usize >= n[k - 1])
        {
            return Err(HomologyError::Query(QueryError::NotSimplicial(format!(
                "row {r} of a boundary of dimension {k} (there are {} cells of dimension {})",
                n[k - 1],
                k - 1
            ))));
        }
    }
    let m = field.modulus();
    // normalise: sorted rows, repeats summed, zeros dropped (coefficients mod p over Z/p)
    for col in cols.iter_mut().skip(1).flatten() {
        col.sort_unstable_by_key(|x| x.0);
        let mut out: Vec<(u32, i64)> = Vec::with_capacity(col.len());
        for &(r, c) in col.iter() {
            let c = if m > 0 { c.rem_euclid(m) } else { c };
            match out.last_mut() {
                Some(l) if l.0 == r => {
                    l.1 = if m > 0 {
                        (l.1 + c) % m
                    } else {
                        l.1.checked_add(c).ok_or_else(|| {
                            HomologyError::Overflow("a chain complex boundary".into())
                        })?
                    }
                }
                _ => out.push((r, c)),
            }
        }
        out.retain(|x| x.1 != 0);
        *col = out;
    }
    let mut rank = vec![0u64; top + 1];
    let mut torsion: Vec<Vec<u128>> = vec![Vec::new(); top];
    if m > 0 {
        let mut cleared: Vec<bool> = Vec::new();
        for k in (1..top).rev() {
            let c = std::mem::take(&mut cols[k]);
            let opt: Vec<Option<reduce::Column>> = c
                .into_iter()
                .enumerate()
                .map(|(j, col)| (!cleared.get(j).copied().unwrap_or(false)).then_some(col))
                .collect();
            let r = reduce::reduce(opt, n[k - 1], m, false);
            let mut next = vec![false; n[k - 1]];
            for row in r.low.iter().flatten() {
                next[*row as usize] = true;
                rank[k] += 1;
            }
            cleared = next;
        }
    } else {
        let max_dense = usize::try_from(max_dense).unwrap_or(usize::MAX);
        for k in 1..top {
            let zeros_c = vec![0u32; n[k]];
            let zeros_r = vec![0u32; n[k - 1]];
            let r = smith::int_rank(&cols[k], n[k - 1], &zeros_c, &zeros_r, 1, max_dense).map_err(
                |e| match e {
                    smith::IntError::Overflow => {
                        HomologyError::Overflow("the Smith normal form".into())
                    }
                    smith::IntError::TooLarge(x) => HomologyError::TooLarge(TooLarge::new(
                        "homology over Z: dense Smith normal form entries",
                        x,
                        max_dense as u128,
                        Unit::Items,
                    )),
                },
            )?;
            rank[k] = r.rank[0] as u64;
            if field == Field::Z {
                torsion[k - 1] = r.torsion[0].iter().map(|&x| x as u128).collect();
            }
        }
    }
    let betti = (0..top)
        .map(|k| n[k] as u64 - rank[k] - rank[k + 1])
        .collect();
    Ok((betti, torsion))
}
