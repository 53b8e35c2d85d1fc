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
#[derive(Clone, Debug)]
pub struct UnionFind {
    parent: Vec<u32>,
    size: Vec<u32>,
    sets: usize,
}

impl UnionFind {
    /// `n` singletons.
    pub fn new(n: usize) -> UnionFind {
        UnionFind {
            parent: (0..n as u32).collect(),
            size: vec![1; n],
            sets: n,
        }
    }

    /// The representative of `x`'s set.
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
    pub fn n_sets(&self) -> usize {
        self.sets
    }

    /// Size of `x`'s set.
    pub fn set_size(&mut self, x: u32) -> usize {
        let r = self.find(x);
        self.size[r as usize] as usize
    }
}
