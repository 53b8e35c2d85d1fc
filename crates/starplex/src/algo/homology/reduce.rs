//! Sparse column reduction over Z/p (p prime, 2 included) of the Morse boundary matrices, with
//! clearing: a column whose cell is the pivot row of a reduced column one dimension up is known
//! to reduce to zero and is neither computed nor reduced.
/// A sparse column: (row, coefficient in 1..p), sorted by row.
pub(crate) type Column = Vec<(u32, i64)>;

/// Inverse of `a` modulo the prime `p`.
pub(crate) fn inv_mod(a: i64, p: i64) -> i64 {
    let (mut r, mut b, mut e) = (1i64, a.rem_euclid(p), p - 2);
    while e > 0 {
        if e & 1 == 1 {
            r = r * b % p;
        }
        b = b * b % p;
        e >>= 1;
    }
    r
}

/// `x -= f * y` modulo p on sorted sparse columns.
pub(crate) fn axpy(x: &mut Column, f: i64, y: &Column, p: i64) {
    let mut out = Vec::with_capacity(x.len() + y.len());
    let (mut i, mut j) = (0, 0);
    while i < x.len() || j < y.len() {
        let take_x = j == y.len() || (i < x.len() && x[i].0 < y[j].0);
        let take_y = i == x.len() || (j < y.len() && y[j].0 < x[i].0);
        if take_x {
            out.push(x[i]);
            i += 1;
        } else if take_y {
            out.push((y[j].0, (-f * y[j].1).rem_euclid(p)));
            j += 1;
        } else {
            let c = (x[i].1 - f * y[j].1).rem_euclid(p);
            if c != 0 {
                out.push((x[i].0, c));
            }
            i += 1;
            j += 1;
        }
    }
    *x = out;
}

/// The result of reducing one boundary matrix.
pub(crate) struct Reduction {
    /// Pivot row of each column (None: the column reduced to zero, or was cleared).
    pub low: Vec<Option<u32>>,
    /// For each column, the combination of original columns it became (when tracked).
    pub v: Option<Vec<Column>>,
}

/// Reduces `cols` (None = cleared, treated as zero) modulo the prime `p`.
pub(crate) fn reduce(cols: Vec<Option<Column>>, n_rows: usize, p: i64, track: bool) -> Reduction {
    let n = cols.len();
    let mut pivot_of_row: Vec<u32> = vec![u32::MAX; n_rows];
    let mut low = vec![None; n];
    let mut reduced: Vec<Column> = Vec::with_capacity(n);
    let mut v: Vec<Column> = Vec::new();
    for (j, c) in cols.into_iter().enumerate() {
        let mut col = c.unwrap_or_default();
        let mut vj: Column = if track {
            vec![(j as u32, 1)]
        } else {
            Vec::new()
        };
        while let Some(&(r, a)) = col.last() {
            let i = pivot_of_row[r as usize];
            if i == u32::MAX {
                break;
            }
            let other = &reduced[i as usize];
            let b = other.last().map_or(1, |x| x.1);
            let f = a * inv_mod(b, p) % p;
            axpy(&mut col, f, other, p);
            if track {
                axpy(&mut vj, f, &v[i as usize], p);
            }
        }
        if let Some(&(r, _)) = col.last() {
            pivot_of_row[r as usize] = j as u32;
            low[j] = Some(r);
        }
        reduced.push(col);
        if track {
            v.push(vj);
        }
    }
    Reduction {
        low,
        v: track.then_some(v),
    }
}
