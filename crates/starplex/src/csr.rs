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
        let mut counts = vec![0u32; n_rows + 1];
        for &(r, _) in pairs {
            counts[r as usize + 1] += 1;
        }
        for i in 0..n_rows {
            counts[i + 1] += counts[i];
        }
        let mut pos = counts.clone();
        let mut targets = vec![0u32; pairs.len()];
        for &(r, t) in pairs {
            targets[pos[r as usize] as usize] = t;
            pos[r as usize] += 1;
        }
        Csr {
            offsets: counts,
            targets,
        }
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
    pub fn from_fn(n_rows: usize, mut each: impl FnMut(&mut dyn FnMut(u32, u32))) -> Csr {
        let mut offsets = vec![0u32; n_rows + 1];
        each(&mut |r, _| offsets[r as usize + 1] += 1);
        for i in 0..n_rows {
            offsets[i + 1] += offsets[i];
        }
        let mut pos = offsets[..n_rows].to_vec();
        let mut targets = vec![0u32; offsets[n_rows] as usize];
        each(&mut |r, t| {
            targets[pos[r as usize] as usize] = t;
            pos[r as usize] += 1;
        });
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
}
