//! Integer homology of the (small) Morse complex: sparse elimination of unit pivots, then a
//! dense Smith normal form of what is left, with checked `i128` arithmetic (an overflow is
//! reported, never wrapped).
use rustc_hash::FxHashMap;

use super::morse::Overflow;

/// Invariant factors of an integer matrix given by sparse columns: `(rank, torsion)` where
/// `torsion` lists the invariant factors greater than 1 (each dividing the next), plus the
/// component of every eliminated or diagonal entry when `col_comp` is given: per-component
/// ranks and torsion are returned in the maps.
pub(crate) struct IntRank {
    /// Rank per component (index = component label).
    pub rank: Vec<usize>,
    /// Torsion coefficients per component.
    pub torsion: Vec<Vec<i128>>,
}

/// Computes ranks and torsion of the matrix with columns `cols` (rows < n_rows) per component
/// (`col_comp[j]`, `row_comp[r]` in 0..n_comp). Refuses (Err) when a dense remainder would have
/// more than `max_dense` entries or on overflow.
pub(crate) fn int_rank(
    cols: &[Vec<(u32, i64)>],
    n_rows: usize,
    col_comp: &[u32],
    row_comp: &[u32],
    n_comp: usize,
    max_dense: usize,
) -> Result<IntRank, IntError> {
    let mut rank = vec![0usize; n_comp];
    let mut torsion = vec![Vec::new(); n_comp];
    // sparse columns as maps, plus row -> columns
    let mut c: Vec<FxHashMap<u32, i128>> = cols
        .iter()
        .map(|col| col.iter().map(|&(r, x)| (r, x as i128)).collect())
        .collect();
    let mut rows: Vec<Vec<u32>> = vec![Vec::new(); n_rows];
    for (j, col) in cols.iter().enumerate() {
        for &(r, _) in col {
            rows[r as usize].push(j as u32);
        }
    }
    let mut col_alive = vec![true; c.len()];
    let mut row_alive = vec![true; n_rows];
    // unit-pivot elimination, columns in order, the unit entry in the sparsest row
    for j in 0..c.len() {
        let mut best: Option<(usize, u32)> = None;
        for (&r, &x) in &c[j] {
            if (x == 1 || x == -1) && row_alive[r as usize] {
                let len = rows[r as usize].len();
                if best.is_none_or(|(l, br)| (len, r) < (l, br)) {
                    best = Some((len, r));
                }
            }
        }
        let Some((_, r)) = best else { continue };
        let u = c[j][&r]; // ±1, its own inverse
        let pivot_col = std::mem::take(&mut c[j]);
        let others = std::mem::take(&mut rows[r as usize]);
        for &k in &others {
            let k = k as usize;
            if k == j || !col_alive[k] {
                continue;
            }
            let Some(&a) = c[k].get(&r) else { continue };
            let f = a.checked_mul(u).ok_or(IntError::Overflow)?;
            for (&rr, &y) in &pivot_col {
                let delta = f.checked_mul(y).ok_or(IntError::Overflow)?;
                let e = c[k].entry(rr).or_insert(0);
                let was_zero = *e == 0;
                *e = e.checked_sub(delta).ok_or(IntError::Overflow)?;
                if *e == 0 {
                    c[k].remove(&rr);
                } else if was_zero && rr != r {
                    rows[rr as usize].push(k as u32);
                }
            }
            c[k].remove(&r);
        }
        col_alive[j] = false;
        row_alive[r as usize] = false;
        rank[col_comp[j] as usize] += 1;
        for &rr in pivot_col.keys() {
            rows[rr as usize].retain(|&x| x as usize != j);
        }
    }
    // dense remainder per component
    let mut by_comp_cols: Vec<Vec<usize>> = vec![Vec::new(); n_comp];
    for j in 0..c.len() {
        if col_alive[j] && !c[j].is_empty() {
            by_comp_cols[col_comp[j] as usize].push(j);
        }
    }
    for (comp, js) in by_comp_cols.iter().enumerate() {
        if js.is_empty() {
            continue;
        }
        let mut rset: Vec<u32> = js.iter().flat_map(|&j| c[j].keys().copied()).collect();
        rset.sort_unstable();
        rset.dedup();
        debug_assert!(rset.iter().all(|&r| row_comp[r as usize] as usize == comp));
        if rset.len().saturating_mul(js.len()) > max_dense {
            return Err(IntError::TooLarge(rset.len() as u128 * js.len() as u128));
        }
        let mut a = vec![vec![0i128; js.len()]; rset.len()];
        for (jj, &j) in js.iter().enumerate() {
            for (&r, &x) in &c[j] {
                let i = rset.binary_search(&r).unwrap_or(0);
                a[i][jj] = x;
            }
        }
        let d = diagonalize(&mut a)?;
        rank[comp] += d.len();
        torsion[comp] = invariant_factors(d)?;
    }
    Ok(IntRank { rank, torsion })
}

/// Why integer homology could not be computed.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) enum IntError {
    Overflow,
    TooLarge(u128),
}

impl From<Overflow> for IntError {
    fn from(_: Overflow) -> Self {
        IntError::Overflow
    }
}

#[allow(clippy::needless_range_loop)]
/// Diagonalizes a dense matrix by unimodular row and column operations; returns the nonzero
/// diagonal entries (absolute values).
fn diagonalize(a: &mut [Vec<i128>]) -> Result<Vec<i128>, IntError> {
    let nr = a.len();
    let nc = if nr == 0 { 0 } else { a[0].len() };
    let mut diag = Vec::new();
    let mut t = 0;
    while t < nr.min(nc) {
        // smallest nonzero |entry| in the remaining block
        let mut best: Option<(i128, usize, usize)> = None;
        for (i, row) in a.iter().enumerate().skip(t) {
            for (j, &x) in row.iter().enumerate().skip(t) {
                if x != 0 && best.is_none_or(|(b, _, _)| x.abs() < b) {
                    best = Some((x.abs(), i, j));
                }
            }
        }
        let Some((_, bi, bj)) = best else { break };
        a.swap(t, bi);
        for row in a.iter_mut() {
            row.swap(t, bj);
        }
        loop {
            let p = a[t][t];
            let mut again = false;
            // rows below
            for i in t + 1..nr {
                if a[i][t] != 0 {
                    let q = a[i][t] / p;
                    for j in t..nc {
                        let d = q.checked_mul(a[t][j]).ok_or(IntError::Overflow)?;
                        a[i][j] = a[i][j].checked_sub(d).ok_or(IntError::Overflow)?;
                    }
                    if a[i][t] != 0 {
                        again = true;
                    }
                }
            }
            // columns to the right
            for j in t + 1..nc {
                if a[t][j] != 0 {
                    let q = a[t][j] / p;
                    for row in a.iter_mut().skip(t) {
                        let d = q.checked_mul(row[t]).ok_or(IntError::Overflow)?;
                        row[j] = row[j].checked_sub(d).ok_or(IntError::Overflow)?;
                    }
                    if a[t][j] != 0 {
                        again = true;
                    }
                }
            }
            if !again {
                break;
            }
            // move the smallest nonzero of row t / column t to the pivot
            let mut best = (a[t][t].abs(), t, t);
            for i in t..nr {
                let x = a[i][t];
                if x != 0 && (best.0 == 0 || x.abs() < best.0) {
                    best = (x.abs(), i, t);
                }
            }
            for j in t..nc {
                let x = a[t][j];
                if x != 0 && (best.0 == 0 || x.abs() < best.0) {
                    best = (x.abs(), t, j);
                }
            }
            let (_, bi, bj) = best;
            a.swap(t, bi);
            for row in a.iter_mut() {
                row.swap(t, bj);
            }
        }
        diag.push(a[t][t].abs());
        t += 1;
    }
    Ok(diag)
}

fn gcd(a: i128, b: i128) -> i128 {
    let (mut a, mut b) = (a.abs(), b.abs());
    while b != 0 {
        (a, b) = (b, a % b);
    }
    a
}

/// Turns diagonal entries into invariant factors (each dividing the next), keeping those > 1.
fn invariant_factors(mut d: Vec<i128>) -> Result<Vec<i128>, IntError> {
    d.retain(|&x| x > 1);
    for i in 0..d.len() {
        for j in i + 1..d.len() {
            let g = gcd(d[i], d[j]);
            let l = (d[i] / g).checked_mul(d[j]).ok_or(IntError::Overflow)?;
            d[i] = g;
            d[j] = l;
        }
    }
    d.retain(|&x| x > 1);
    d.sort_unstable();
    Ok(d)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn snf_small() {
        // [[2, 4], [6, 8]] ~ diag(2, 4)
        let mut a = vec![vec![2i128, 4], vec![6, 8]];
        let d = diagonalize(&mut a).unwrap();
        assert_eq!(invariant_factors(d).unwrap(), vec![2, 4]);
        assert_eq!(invariant_factors(vec![2, 3]).unwrap(), vec![6]);
    }

    #[test]
    fn unit_elimination_then_dense() {
        // columns: e0 = r0 - r1, e1 = 2 r1  -> coker Z^2 / <(1,-1), (0,2)> = Z/2
        let cols = vec![vec![(0u32, 1i64), (1, -1)], vec![(1, 2)]];
        let r = int_rank(&cols, 2, &[0, 0], &[0, 0], 1, 100).unwrap();
        assert_eq!(r.rank, vec![2]);
        assert_eq!(r.torsion, vec![vec![2]]);
    }
}
