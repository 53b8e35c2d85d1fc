//! The storage of a [`Hasse`](super::Hasse) complex: one [`Level`] of flat arrays per
//! dimension and the vertex-label lookup [`VertexIndex`].
use rustc_hash::FxHashMap;
use smallvec::SmallVec;

use super::arena::UpArena;

/// A sorted vertex tuple, on the stack up to 8 vertices.
pub(crate) type Verts = SmallVec<[u32; 8]>;

/// The nodes of one dimension `k`: `k + 1` sorted vertex labels and `k + 1` face ids per node
/// (face `i` is the simplex without vertex `i`), and the up lists in an arena.
#[derive(Clone, Debug, Default)]
pub(crate) struct Level {
    pub(crate) k1: usize,
    pub(crate) verts: Vec<u32>,
    pub(crate) down: Vec<u32>,
    pub(crate) up: UpArena,
    /// Slots of removed nodes, reused by the next insertions.
    pub(crate) free: Vec<u32>,
}

impl Level {
    /// Number of slots (live and removed).
    #[inline]
    pub(crate) fn slots(&self) -> usize {
        self.up.hdr.len()
    }
    /// Number of live nodes.
    #[inline]
    pub(crate) fn len(&self) -> usize {
        self.up.hdr.len() - self.free.len()
    }
    #[inline]
    pub(crate) fn alive(&self, i: u32) -> bool {
        (i as usize) < self.slots() && !self.up.is_dead(i)
    }
    #[inline]
    pub(crate) fn verts(&self, i: u32) -> &[u32] {
        let i = i as usize;
        &self.verts[i * self.k1..(i + 1) * self.k1]
    }
    #[inline]
    pub(crate) fn downs(&self, i: u32) -> &[u32] {
        if self.k1 == 1 {
            return &[];
        }
        let i = i as usize;
        &self.down[i * self.k1..(i + 1) * self.k1]
    }
    pub(crate) fn bytes(&self) -> usize {
        self.verts.capacity() * 4
            + self.down.capacity() * 4
            + self.up.bytes()
            + self.free.capacity() * 4
    }
}

pub(crate) const NONE: u32 = u32::MAX;

/// Vertex label → vertex node: a dense table for labels up to a few times the number of
/// vertices, a hash map for the rest (so a huge label costs no memory).
#[derive(Clone, Debug, Default)]
pub(crate) struct VertexIndex {
    dense: Vec<u32>,
    sparse: FxHashMap<u32, u32>,
    len: usize,
}

impl VertexIndex {
    #[inline]
    pub(crate) fn get(&self, label: u32) -> Option<u32> {
        match self.dense.get(label as usize) {
            Some(&x) => (x != NONE).then_some(x),
            None => self.sparse.get(&label).copied(),
        }
    }
    pub(crate) fn insert(&mut self, label: u32, id: u32) {
        let l = label as usize;
        if l >= self.dense.len() && l < 2 * self.len + 4096 {
            // absorb sparse entries that now fall inside the dense table
            let new_len = (l + 1).max(self.dense.len() * 3 / 2);
            self.dense.resize(new_len, NONE);
            let moved: Vec<(u32, u32)> = self
                .sparse
                .iter()
                .filter(|&(&k, _)| (k as usize) < new_len)
                .map(|(&k, &v)| (k, v))
                .collect();
            for (k, v) in moved {
                self.sparse.remove(&k);
                self.dense[k as usize] = v;
            }
        }
        let old = if l < self.dense.len() {
            std::mem::replace(&mut self.dense[l], id)
        } else {
            self.sparse.insert(label, id).unwrap_or(NONE)
        };
        if old == NONE {
            self.len += 1;
        }
    }
    pub(crate) fn remove(&mut self, label: u32) {
        let l = label as usize;
        let old = if l < self.dense.len() {
            std::mem::replace(&mut self.dense[l], NONE)
        } else {
            self.sparse.remove(&label).unwrap_or(NONE)
        };
        if old != NONE {
            self.len -= 1;
        }
    }
    #[inline]
    pub(crate) fn contains(&self, label: u32) -> bool {
        self.get(label).is_some()
    }
    pub(crate) fn len(&self) -> usize {
        self.len
    }
    /// Makes room for labels `0..n` in the dense table.
    pub(crate) fn reserve_dense(&mut self, n: usize) {
        if self.dense.len() < n {
            self.dense.resize(n, NONE);
        }
    }
    pub(crate) fn bytes(&self) -> usize {
        self.dense.capacity() * 4 + self.sparse.capacity() * 9
    }
    pub(crate) fn shrink_to_fit(&mut self) {
        self.dense.shrink_to_fit();
        self.sparse.shrink_to_fit();
    }
}
