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
    #[inline]
    pub fn n_rows(&self) -> usize {
        self.offsets.len().saturating_sub(1)
    }

    /// The targets of row `i`.
    #[inline]
    pub fn row(&self, i: usize) -> &[u32] {
        &self.targets[self.offsets[i] as usize..self.offsets[i + 1] as usize]
    }

    /// Number of targets in row `i`.
    #[inline]
    pub fn degree(&self, i: usize) -> usize {
        (self.offsets[i + 1] - self.offsets[i]) as usize
    }

    /// Total number of references (targets).
    pub fn n_refs(&self) -> usize {
        self.targets.len()
    }

    /// Bytes used by the two arrays.
    pub fn bytes(&self) -> usize {
        4 * (self.offsets.len() + self.targets.len())
    }
}
