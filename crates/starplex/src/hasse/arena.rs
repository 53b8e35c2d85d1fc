//! Compact storage of the up (coface) lists of one level: every node owns a block of
//! `(key, coface)` pairs in a shared arena, sorted by key (the vertex added). Block capacities
//! are powers of two (at least 2); a node's header is 8 bytes (start, length and capacity
//! class). Freed blocks are reused per size class.

/// One coface reference: the vertex added and the coface's id in the next level.
pub(crate) type UpPair = [u32; 2];

/// Header start of a removed node (its slot is free for reuse).
pub(crate) const DEAD: u32 = u32::MAX;
const LEN_BITS: u32 = 27;
const LEN_MASK: u32 = (1 << LEN_BITS) - 1;

#[inline]
fn cap_of_class(c: u32) -> u32 {
    if c == 0 {
        0
    } else {
        1 << c
    }
}

/// The arena of one level. A node's header is `[start, len | class << 27]` with capacity
/// `2^class` (class 0: no block). Blocks grow by doubling and shrink by half when a quarter
/// full, so alternating inserts and removals never thrash.
#[derive(Clone, Debug, Default)]
pub(crate) struct UpArena {
    /// Per node: start of its block (or [`DEAD`]) and its length with the capacity class.
    pub(crate) hdr: Vec<[u32; 2]>,
    slots: Vec<UpPair>,
    free: Vec<Vec<u32>>,
}

impl UpArena {
    pub(crate) fn bytes(&self) -> usize {
        self.hdr.capacity() * 8
            + self.slots.capacity() * 8
            + self.free.iter().map(|f| f.capacity() * 4).sum::<usize>()
    }

    /// Slots in use (for statistics).
    #[cfg(test)]
    pub(crate) fn n_pairs(&self) -> usize {
        (0..self.hdr.len() as u32).map(|i| self.get(i).len()).sum()
    }

    #[inline]
    fn parts(&self, node: u32) -> (u32, u32, u32) {
        let [s, x] = self.hdr[node as usize];
        (s, x & LEN_MASK, x >> LEN_BITS)
    }

    /// Appends a node with an empty list and room for `cap` pairs.
    pub(crate) fn push_node(&mut self, cap: u32) {
        self.hdr.push([0, 0]);
        let n = (self.hdr.len() - 1) as u32;
        self.reserve_node(n, cap);
    }

    /// Appends a node whose up list is `pairs` (sorted by key).
    pub(crate) fn push_node_with(&mut self, pairs: &[UpPair]) {
        self.hdr.push([0, 0]);
        let n = (self.hdr.len() - 1) as u32;
        let l = pairs.len() as u32;
        if l == 0 {
            return;
        }
        let c = l.next_power_of_two().max(2);
        let s = self.alloc(c);
        for (d, p) in self.slots[s as usize..(s + l) as usize]
            .iter_mut()
            .zip(pairs)
        {
            *d = *p;
        }
        self.hdr[n as usize] = [s, l | (c.trailing_zeros() << LEN_BITS)];
    }

    /// Replaces every key `x` by `f(x)` (`f` increasing, so blocks stay sorted; unused slots
    /// are mapped too and must be valid arguments of `f`).
    pub(crate) fn map_keys(&mut self, f: impl Fn(u32) -> u32) {
        for p in &mut self.slots {
            p[0] = f(p[0]);
        }
    }

    /// Reserves 1/16 more pairs than in use (at least 64).
    pub(crate) fn reserve_headroom(&mut self) {
        self.slots.reserve_exact(self.slots.len() / 16 + 64);
    }

    /// Reserves room for `n` more pairs.
    pub(crate) fn reserve_slots(&mut self, n: usize) {
        self.slots.reserve_exact(n);
    }

    /// Gives an empty live node room for `cap` pairs (rounded up to a power of two).
    pub(crate) fn reserve_node(&mut self, node: u32, cap: u32) {
        if cap == 0 {
            self.hdr[node as usize] = [0, 0];
            return;
        }
        let c = cap.next_power_of_two().max(2);
        let s = self.alloc(c);
        self.hdr[node as usize] = [s, c.trailing_zeros() << LEN_BITS];
    }

    #[inline]
    pub(crate) fn is_dead(&self, node: u32) -> bool {
        self.hdr[node as usize][0] == DEAD
    }

    /// Marks a node removed, releasing its block.
    pub(crate) fn kill(&mut self, node: u32) {
        let (s, _, c) = self.parts(node);
        self.release(s, cap_of_class(c));
        self.hdr[node as usize] = [DEAD, 0];
    }

    #[inline]
    pub(crate) fn get(&self, node: u32) -> &[UpPair] {
        let (s, l, _) = self.parts(node);
        if l == 0 {
            return &[];
        }
        &self.slots[s as usize..(s + l) as usize]
    }

    #[inline]
    pub(crate) fn find(&self, node: u32, key: u32) -> Option<u32> {
        let l = self.get(node);
        if l.len() <= 8 {
            l.iter().find(|p| p[0] == key).map(|p| p[1])
        } else {
            l.binary_search_by_key(&key, |p| p[0]).ok().map(|i| l[i][1])
        }
    }

    fn alloc(&mut self, cap: u32) -> u32 {
        let c = cap.trailing_zeros() as usize;
        if let Some(s) = self.free.get_mut(c).and_then(|f| f.pop()) {
            return s;
        }
        let s = self.slots.len() as u32;
        self.slots.resize(self.slots.len() + cap as usize, [0, 0]);
        s
    }

    fn release(&mut self, start: u32, cap: u32) {
        if cap == 0 || start == DEAD {
            return;
        }
        let c = cap.trailing_zeros() as usize;
        if self.free.len() <= c {
            self.free.resize(c + 1, Vec::new());
        }
        self.free[c].push(start);
    }

    fn move_block(&mut self, node: u32, new_cap: u32) {
        let (s, l, c) = self.parts(node);
        let ns = self.alloc(new_cap);
        self.slots
            .copy_within(s as usize..(s + l) as usize, ns as usize);
        self.release(s, cap_of_class(c));
        self.hdr[node as usize] = [ns, l | (new_cap.trailing_zeros() << LEN_BITS)];
    }

    /// Inserts `(key, id)` keeping the block sorted; the key must be absent.
    pub(crate) fn insert(&mut self, node: u32, key: u32, id: u32) {
        let (_, l, c) = self.parts(node);
        let cap = cap_of_class(c);
        if l == cap {
            self.move_block(node, (cap * 2).max(2));
        }
        let (s, l, c) = self.parts(node);
        let block = &mut self.slots[s as usize..(s + l + 1) as usize];
        let pos = block[..l as usize].partition_point(|p| p[0] < key);
        debug_assert!(pos == l as usize || block[pos][0] != key);
        block.copy_within(pos..l as usize, pos + 1);
        block[pos] = [key, id];
        self.hdr[node as usize] = [s, (l + 1) | (c << LEN_BITS)];
    }

    /// Removes the pair with `key`; returns whether it was there.
    pub(crate) fn remove(&mut self, node: u32, key: u32) -> bool {
        let (s, l, c) = self.parts(node);
        let block = &mut self.slots[s as usize..(s + l) as usize];
        let Some(pos) = block.iter().position(|p| p[0] == key) else {
            return false;
        };
        block.copy_within(pos + 1.., pos);
        let l = l - 1;
        self.hdr[node as usize] = [s, l | (c << LEN_BITS)];
        let cap = cap_of_class(c);
        if l == 0 {
            self.release(s, cap);
            self.hdr[node as usize] = [0, 0];
        } else if cap > 2 && l <= cap / 4 {
            self.move_block(node, cap / 2);
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn insert_remove_keeps_sorted_blocks() {
        let mut a = UpArena::default();
        for i in 0..3 {
            a.push_node(i);
        }
        let mut model: Vec<Vec<[u32; 2]>> = vec![vec![]; 3];
        let mut x = 12345u64;
        for step in 0..3000u32 {
            x = x
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let node = ((x >> 33) % 3) as u32;
            let key = ((x >> 40) % 40) as u32;
            let m = &mut model[node as usize];
            if let Some(p) = m.iter().position(|p| p[0] == key) {
                m.remove(p);
                assert!(a.remove(node, key));
            } else {
                let pos = m.partition_point(|p| p[0] < key);
                m.insert(pos, [key, step]);
                a.insert(node, key, step);
            }
            for n in 0..3 {
                assert_eq!(a.get(n), &model[n as usize][..]);
            }
        }
        assert_eq!(a.n_pairs(), model.iter().map(|m| m.len()).sum::<usize>());
    }
}
