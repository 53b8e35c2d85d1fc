//! [`Csr`]: a compressed sparse row relation (offsets + flat targets), the layout every batched
//! relation in starplex is returned in (4 bytes per reference plus 4 per row).
//!
//! ```
//! use starplex::csr::Csr;
//! let r = Csr::from_pairs(3, &[(0, 5), (2, 7), (0, 6)]);
//! assert_eq!(r.row(0), &[5, 6]);
//! assert!(r.row(1).is_empty());
//! assert_eq!(r.row(2), &[7]);
//! ```

/// Rows of `u32` targets stored contiguously.
///
/// ```
/// use starplex::csr::Csr;
/// let r = Csr { offsets: vec![0, 2, 2, 3], targets: vec![5, 6, 7] };
/// assert_eq!(r.n_rows(), 3);
/// assert_eq!(r.row(0), &[5, 6]);
/// assert_eq!(r, Csr::from_pairs(3, &[(0, 5), (0, 6), (2, 7)]));
/// ```
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Csr {
    /// `offsets[i]..offsets[i+1]` is row `i` in `targets`; `offsets.len() == n_rows + 1`.
    pub offsets: Vec<u32>,
    /// The targets, row after row.
    pub targets: Vec<u32>,
}

impl Csr {
    /// Builds from (row, target) pairs; within a row, targets keep the order of the pairs.
    ///
    /// ```
    /// use starplex::csr::Csr;
    /// let r = Csr::from_pairs(2, &[(1, 9), (0, 4), (1, 3)]);
    /// assert_eq!(r.offsets, [0, 1, 3]);
    /// assert_eq!(r.row(1), &[9, 3]); // pair order is kept within a row
    /// ```
    ///
    /// # Panics
    /// If a row index is `>= n_rows` or there are more than `u32::MAX` pairs (internal use only:
    /// callers validate their input first).
    pub fn from_pairs(n_rows: usize, pairs: &[(u32, u32)]) -> Csr {
        let mut offsets = vec![0u32; n_rows + 1];
        for &(r, _) in pairs {
            offsets[r as usize + 1] += 1;
        }
        for i in 0..n_rows {
            offsets[i + 1] += offsets[i];
        }
        // monomorphic, unlike `from_fn`'s `dyn` emitter: no indirect call per pair
        let targets = scatter(&offsets, |sink| {
            for &(r, t) in pairs {
                sink.emit(r, t);
            }
        });
        Csr { offsets, targets }
    }

    /// Builds from a count pass and a fill pass over the same items: `each(emit)` must call
    /// `emit(row, target)` identically both times. Avoids materialising the pairs.
    ///
    /// ```
    /// use starplex::csr::Csr;
    /// let edges = [(0u32, 1u32), (1, 2)];
    /// // Vertex -> incident edges, without collecting the pairs.
    /// let r = Csr::from_fn(3, |emit| {
    ///     for (e, &(a, b)) in edges.iter().enumerate() {
    ///         emit(a, e as u32);
    ///         emit(b, e as u32);
    ///     }
    /// });
    /// assert_eq!(r, Csr::from_pairs(3, &[(0, 0), (1, 0), (1, 1), (2, 1)]));
    /// assert_eq!(r.row(1), &[0, 1]);
    /// ```
    pub fn from_fn(n_rows: usize, each: impl FnMut(&mut dyn FnMut(u32, u32))) -> Csr {
        Self::from_fn_with(n_rows, true, each)
    }

    /// [`from_fn`](Self::from_fn) for pairs whose rows come in a cache-friendly order (each
    /// near the rows before it, e.g. cells leaf by leaf in a Stellar tree's numbering): the
    /// targets go straight to their rows, never through the buckets that cost 8 bytes per
    /// reference on top of the answer.
    ///
    /// ```
    /// use starplex::csr::Csr;
    /// let r = Csr::from_fn_local(3, |emit| {
    ///     emit(0, 7);
    ///     emit(1, 8);
    ///     emit(1, 9);
    /// });
    /// assert_eq!(r, Csr::from_pairs(3, &[(0, 7), (1, 8), (1, 9)]));
    /// ```
    pub fn from_fn_local(n_rows: usize, each: impl FnMut(&mut dyn FnMut(u32, u32))) -> Csr {
        Self::from_fn_with(n_rows, false, each)
    }

    fn from_fn_with(
        n_rows: usize,
        buckets: bool,
        mut each: impl FnMut(&mut dyn FnMut(u32, u32)),
    ) -> Csr {
        let mut offsets = vec![0u32; n_rows + 1];
        each(&mut |r, _| offsets[r as usize + 1] += 1);
        for i in 0..n_rows {
            offsets[i + 1] += offsets[i];
        }
        let targets = scatter_with(&offsets, buckets, |sink| each(&mut |r, t| sink.emit(r, t)));
        Csr { offsets, targets }
    }

    /// Number of rows.
    ///
    /// ```
    /// use starplex::csr::Csr;
    /// assert_eq!(Csr::from_pairs(4, &[(0, 1)]).n_rows(), 4);
    /// assert_eq!(Csr::default().n_rows(), 0);
    /// ```
    #[inline]
    pub fn n_rows(&self) -> usize {
        self.offsets.len().saturating_sub(1)
    }

    /// The targets of row `i`.
    ///
    /// ```
    /// use starplex::csr::Csr;
    /// let r = Csr::from_pairs(3, &[(2, 8), (2, 9)]);
    /// assert_eq!(r.row(2), &[8, 9]);
    /// assert!(r.row(0).is_empty());
    /// ```
    #[inline]
    pub fn row(&self, i: usize) -> &[u32] {
        &self.targets[self.offsets[i] as usize..self.offsets[i + 1] as usize]
    }

    /// Number of targets in row `i`.
    ///
    /// ```
    /// use starplex::csr::Csr;
    /// let r = Csr::from_pairs(3, &[(2, 8), (2, 9), (0, 1)]);
    /// assert_eq!((r.degree(0), r.degree(1), r.degree(2)), (1, 0, 2));
    /// ```
    #[inline]
    pub fn degree(&self, i: usize) -> usize {
        (self.offsets[i + 1] - self.offsets[i]) as usize
    }

    /// Total number of references (targets).
    ///
    /// ```
    /// use starplex::csr::Csr;
    /// let r = Csr::from_pairs(3, &[(2, 8), (2, 9), (0, 1)]);
    /// assert_eq!(r.n_refs(), 3);
    /// ```
    pub fn n_refs(&self) -> usize {
        self.targets.len()
    }

    /// Bytes used by the two arrays.
    ///
    /// ```
    /// use starplex::csr::Csr;
    /// let r = Csr::from_pairs(3, &[(2, 8), (2, 9), (0, 1)]);
    /// assert_eq!(r.bytes(), 4 * (4 + 3)); // 4 offsets and 3 targets
    /// ```
    pub fn bytes(&self) -> usize {
        4 * (self.offsets.len() + self.targets.len())
    }

    /// Sorts every row and removes repeated targets, in place.
    ///
    /// ```
    /// use starplex::csr::Csr;
    /// let mut r = Csr::from_pairs(2, &[(1, 9), (0, 4), (1, 2), (1, 9)]);
    /// r.sort_dedup_rows();
    /// assert_eq!((r.row(0), r.row(1)), (&[4][..], &[2, 9][..]));
    /// ```
    pub fn sort_dedup_rows(&mut self) {
        let n = self.n_rows();
        let mut w = 0usize;
        let mut start = 0usize;
        for v in 0..n {
            let end = self.offsets[v + 1] as usize;
            self.targets[start..end].sort_unstable();
            let row_start = w;
            for i in start..end {
                let t = self.targets[i];
                if w == row_start || self.targets[w - 1] != t {
                    self.targets[w] = t;
                    w += 1;
                }
            }
            start = end;
            self.offsets[v + 1] = w as u32;
        }
        self.targets.truncate(w);
    }
}

/// Rows per bucket of [`scatter`]'s first pass: a bucket's share of the targets (about
/// 4,096 rows times the mean degree, times 4 bytes) stays in the core's cache while it is filled.
const BUCKET_SHIFT: u32 = 12;

/// Fewer references than this go straight to their rows: the targets fit in cache anyway.
const BUCKETED_FROM: usize = 1 << 19;

/// More references than this go straight to their rows as well: the buckets would take
/// 8 bytes per reference on top of the 4 of the answer (256 MiB at this size). Measured on a
/// 120³ Kuhn grid (10.4M tetrahedra, 41.5M references; `starplex info`, 2 threads): the
/// direct fill gave 2.63-2.75 s and 386 MB against 2.92-3.38 s and 711 MB bucketed (2^27
/// before), and a `starplex-mpi` rank of a 50M-tetrahedron grid (4 ranks) 0.74 GB instead of
/// 0.96 GB.
const BUCKETED_UP_TO: usize = 1 << 25;

/// The fill pass of a counting sort: `each(sink)` calls [`Sink::emit`] for every (row, target)
/// pair, in the same order as the count pass that made `offsets`; targets keep that order
/// within a row.
///
/// Writing each target straight to its row is one random store per reference, and a store that
/// misses the cache is slow (measured: about 28 ns each into a 10 MB answer on this project's
/// 2-core Xeon VM, against 3 ns for the count pass's increments into a 1.6 MB array). Past
/// [`BUCKETED_FROM`] references the pairs first go to buckets of 2^[`BUCKET_SHIFT`] rows, one
/// sequential stream per bucket, and each bucket is then written into its own short,
/// cache-resident stretch of the answer: about 2x faster on meshes of a few million references.
pub(crate) fn scatter(offsets: &[u32], each: impl FnMut(&mut Sink)) -> Vec<u32> {
    scatter_with(offsets, true, each)
}

/// [`scatter`], with the buckets only when `buckets` allows them.
fn scatter_with(offsets: &[u32], buckets: bool, mut each: impl FnMut(&mut Sink)) -> Vec<u32> {
    let n_rows = offsets.len() - 1;
    let total = offsets[n_rows] as usize;
    let bucketed =
        buckets && (BUCKETED_FROM..=BUCKETED_UP_TO).contains(&total) && n_rows >> BUCKET_SHIFT >= 2;
    let mut sink = Sink {
        bucketed,
        targets: vec![0u32; total],
        pos: offsets[..n_rows].to_vec(),
        bucket_pos: Vec::new(),
        pairs: Vec::new(),
    };
    if bucketed {
        sink.bucket_pos = offsets.iter().step_by(1 << BUCKET_SHIFT).copied().collect();
        sink.pairs = vec![0u64; total];
    }
    each(&mut sink);
    let Sink {
        mut targets,
        mut pos,
        pairs,
        ..
    } = sink;
    for x in pairs {
        let p = &mut pos[(x >> 32) as usize];
        targets[*p as usize] = x as u32;
        *p += 1;
    }
    targets
}

/// Where [`scatter`]'s fill pass sends its pairs: straight to the rows, or to the buckets.
pub(crate) struct Sink {
    bucketed: bool,
    targets: Vec<u32>,
    pos: Vec<u32>,
    bucket_pos: Vec<u32>,
    pairs: Vec<u64>,
}

impl Sink {
    /// Sends target `t` to row `r` (the branch is the same for every pair of a fill).
    #[inline(always)]
    pub(crate) fn emit(&mut self, r: u32, t: u32) {
        if self.bucketed {
            let p = &mut self.bucket_pos[(r >> BUCKET_SHIFT) as usize];
            self.pairs[*p as usize] = (u64::from(r) << 32) | u64::from(t);
            *p += 1;
        } else {
            let p = &mut self.pos[r as usize];
            self.targets[*p as usize] = t;
            *p += 1;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testkit::XorShift;

    /// The model: a stable sort of the pairs by row.
    fn model(n_rows: usize, pairs: &[(u32, u32)]) -> Csr {
        let mut sorted = pairs.to_vec();
        sorted.sort_by_key(|&(r, _)| r);
        let mut offsets = vec![0u32; n_rows + 1];
        for &(r, _) in pairs {
            offsets[r as usize + 1] += 1;
        }
        for i in 0..n_rows {
            offsets[i + 1] += offsets[i];
        }
        Csr {
            offsets,
            targets: sorted.into_iter().map(|(_, t)| t).collect(),
        }
    }

    #[test]
    fn both_fills_equal_a_stable_sort_by_row() {
        let mut rng = XorShift::new(0x5ca7);
        // below, at and above the bucketed range's lower end, few and many rows, empty rows,
        // rows past the last full bucket
        for (n_rows, n_pairs) in [
            (0, 0),
            (1, 5),
            (3 << BUCKET_SHIFT, BUCKETED_FROM - 1),
            (3 << BUCKET_SHIFT, BUCKETED_FROM),
            ((5 << BUCKET_SHIFT) + 17, BUCKETED_FROM + 1000),
            (1 << BUCKET_SHIFT, BUCKETED_FROM + 3), // one bucket: the direct fill
            (200_000, BUCKETED_FROM + 77),
        ] {
            let pairs: Vec<(u32, u32)> = (0..n_pairs)
                .map(|_| {
                    let r = rng.below(n_rows.max(1) as u64) as u32;
                    (r, rng.next_u64() as u32)
                })
                .filter(|_| n_rows > 0)
                .collect();
            let want = model(n_rows, &pairs);
            assert_eq!(
                Csr::from_pairs(n_rows, &pairs),
                want,
                "{n_rows} rows, {n_pairs} pairs"
            );
        }
    }
}
