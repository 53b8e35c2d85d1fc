//! Union-find (disjoint sets) with path halving and union by size, on `u32` ids.
//!
//! ```
//! use starplex::algo::unionfind::UnionFind;
//! let mut uf = UnionFind::new(4);
//! uf.union(0, 1);
//! uf.union(2, 3);
//! assert_eq!(uf.n_sets(), 2);
//! assert_eq!(uf.find(1), uf.find(0));
//! assert_ne!(uf.find(1), uf.find(2));
//! ```

/// Disjoint sets over `0..n`.
///
/// ```
/// use starplex::algo::unionfind::UnionFind;
/// let mut uf = UnionFind::new(5);
/// for (a, b) in [(0, 1), (1, 2), (3, 4)] {
///     uf.union(a, b);
/// }
/// assert_eq!(uf.n_sets(), 2);
/// assert_eq!(uf.set_size(2), 3);
/// ```
#[derive(Clone, Debug)]
pub struct UnionFind {
    parent: Vec<u32>,
    size: Vec<u32>,
    sets: usize,
}

impl UnionFind {
    /// `n` singletons.
    ///
    /// ```
    /// use starplex::algo::unionfind::UnionFind;
    /// let mut uf = UnionFind::new(3);
    /// assert_eq!(uf.n_sets(), 3);
    /// assert_eq!((uf.find(0), uf.find(1), uf.find(2)), (0, 1, 2));
    /// ```
    pub fn new(n: usize) -> UnionFind {
        UnionFind {
            parent: (0..n as u32).collect(),
            size: vec![1; n],
            sets: n,
        }
    }

    /// The representative of `x`'s set.
    ///
    /// ```
    /// use starplex::algo::unionfind::UnionFind;
    /// let mut uf = UnionFind::new(3);
    /// uf.union(2, 0);
    /// assert_eq!(uf.find(0), uf.find(2));
    /// assert_ne!(uf.find(1), uf.find(0));
    /// ```
    #[inline]
    pub fn find(&mut self, x: u32) -> u32 {
        find_in(&mut self.parent, x)
    }

    /// Merges the sets of `a` and `b`; true when they were different.
    ///
    /// ```
    /// use starplex::algo::unionfind::UnionFind;
    /// let mut uf = UnionFind::new(3);
    /// assert!(uf.union(0, 1));
    /// assert!(!uf.union(1, 0)); // already in one set
    /// assert_eq!(uf.n_sets(), 2);
    /// ```
    #[inline]
    pub fn union(&mut self, a: u32, b: u32) -> bool {
        let (mut a, mut b) = (self.find(a), self.find(b));
        if a == b {
            return false;
        }
        if self.size[a as usize] < self.size[b as usize] {
            std::mem::swap(&mut a, &mut b);
        }
        self.parent[b as usize] = a;
        self.size[a as usize] += self.size[b as usize];
        self.sets -= 1;
        true
    }

    /// Number of sets.
    ///
    /// ```
    /// use starplex::algo::unionfind::UnionFind;
    /// let mut uf = UnionFind::new(4);
    /// uf.union(0, 1);
    /// uf.union(2, 3);
    /// uf.union(1, 3);
    /// assert_eq!(uf.n_sets(), 1);
    /// ```
    pub fn n_sets(&self) -> usize {
        self.sets
    }

    /// Size of `x`'s set.
    ///
    /// ```
    /// use starplex::algo::unionfind::UnionFind;
    /// let mut uf = UnionFind::new(4);
    /// uf.union(0, 1);
    /// uf.union(0, 2);
    /// assert_eq!(uf.set_size(1), 3);
    /// assert_eq!(uf.set_size(3), 1);
    /// ```
    pub fn set_size(&mut self, x: u32) -> usize {
        let r = self.find(x);
        self.size[r as usize] as usize
    }
}

/// Path-halving find on a bare parent array (`parent[x] == x` at a root), for hot loops that
/// reuse one scratch array across many small problems instead of allocating a [`UnionFind`].
///
/// ```
/// use starplex::algo::unionfind::{find_in, union_min_in};
/// let mut p: Vec<u32> = (0..5).collect();
/// assert!(union_min_in(&mut p, 4, 2));
/// assert!(union_min_in(&mut p, 2, 3));
/// assert!(!union_min_in(&mut p, 3, 4));
/// assert_eq!(find_in(&mut p, 4), 2); // the root is the smallest member
/// assert_eq!(find_in(&mut p, 0), 0);
/// ```
#[inline]
pub fn find_in(parent: &mut [u32], mut x: u32) -> u32 {
    while parent[x as usize] != x {
        let g = parent[parent[x as usize] as usize];
        parent[x as usize] = g;
        x = g;
    }
    x
}

/// Merges the sets of `a` and `b` on a bare parent array, keeping the smaller root (so every
/// root is the smallest member of its set); true when they were different sets.
///
/// ```
/// use starplex::algo::unionfind::{find_in, union_min_in};
/// let mut p: Vec<u32> = (0..3).collect();
/// union_min_in(&mut p, 2, 1);
/// assert_eq!(find_in(&mut p, 2), 1);
/// ```
#[inline]
pub fn union_min_in(parent: &mut [u32], a: u32, b: u32) -> bool {
    let (ra, rb) = (find_in(parent, a), find_in(parent, b));
    if ra < rb {
        parent[rb as usize] = ra;
    } else if rb < ra {
        parent[ra as usize] = rb;
    }
    ra != rb
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Random unions on bare arrays agree with a naive labelling: the same answer from every
    /// union, and every root is the smallest member of its set.
    #[test]
    fn slice_union_find_equals_naive_labels() {
        let mut rng = crate::testkit::XorShift::new(0x9e37_79b9_7f4a_7c15);
        let mut next = |m: u64| rng.below(m);
        for case in 0..200 {
            let n = 1 + next(60) as usize;
            let mut p: Vec<u32> = (0..n as u32).collect();
            let mut label: Vec<usize> = (0..n).collect();
            for _ in 0..next(3 * n as u64) {
                let (a, b) = (next(n as u64) as usize, next(n as u64) as usize);
                let (la, lb) = (label[a], label[b]);
                let merged = union_min_in(&mut p, a as u32, b as u32);
                assert_eq!(merged, la != lb, "case {case}");
                let m = la.min(lb);
                for l in label.iter_mut() {
                    if *l == la || *l == lb {
                        *l = m;
                    }
                }
            }
            for (x, &l) in label.iter().enumerate() {
                assert_eq!(find_in(&mut p, x as u32) as usize, l, "case {case}");
            }
        }
    }
}
