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
    pub fn find(&mut self, mut x: u32) -> u32 {
        while self.parent[x as usize] != x {
            let p = self.parent[x as usize];
            self.parent[x as usize] = self.parent[p as usize];
            x = self.parent[x as usize];
        }
        x
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
