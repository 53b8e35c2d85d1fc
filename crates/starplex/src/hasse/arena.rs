//! Compact storage of the up (coface) lists of one level: every node owns a block of
//! `(key, coface)` pairs in a shared arena, sorted by key (the vertex added). Block capacities
//! are powers of two (at least 2), a function of the length, so a node's header is only
//! `(start, len)`: 8 bytes. Freed blocks are reused per size class.

/// One coface reference: the vertex added and the coface's id in the next level.
pub(crate) type UpPair = [u32; 2];

#[inline]
fn cap_of(len: u32) -> u32 {
    if len == 0 {
        0
    } else {
        len.next_power_of_two().max(2)
    }
}

#[inline]
fn class_of(cap: u32) -> usize {
    cap.trailing_zeros() as usize
}

/// The arena of one level.
#[derive(Clone, Debug, Default)]
pub(crate) struct UpArena {
    /// Per node: start of its block and its length.
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
        self.hdr.iter().map(|h| h[1] as usize).sum()
    }

    pub(crate) fn push_node(&mut self) {
        self.hdr.push([0, 0]);
    }

    #[inline]
    pub(crate) fn get(&self, node: u32) -> &[UpPair] {
        let [s, l] = self.hdr[node as usize];
        &self.slots[s as usize..(s + l) as usize]
    }

    #[inline]
    fn get_mut(&mut self, node: u32) -> &mut [UpPair] {
        let [s, l] = self.hdr[node as usize];
        &mut self.slots[s as usize..(s + l) as usize]
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
        let c = class_of(cap);
        if let Some(s) = self.free.get_mut(c).and_then(|f| f.pop()) {
            return s;
        }
        let s = self.slots.len() as u32;
        self.slots.resize(self.slots.len() + cap as usize, [0, 0]);
        s
    }

    fn release(&mut self, start: u32, cap: u32) {
        if cap == 0 {
            return;
        }
        let c = class_of(cap);
        if self.free.len() <= c {
            self.free.resize(c + 1, Vec::new());
        }
        self.free[c].push(start);
    }

    /// Inserts `(key, id)` keeping the block sorted; the key must be absent.
    pub(crate) fn insert(&mut self, node: u32, key: u32, id: u32) {
        let [s, l] = self.hdr[node as usize];
        let (oc, nc) = (cap_of(l), cap_of(l + 1));
        let mut s = s;
        if oc != nc {
            let ns = self.alloc(nc);
            self.slots
                .copy_within(s as usize..(s + l) as usize, ns as usize);
            self.release(s, oc);
            s = ns;
        }
        let block = &mut self.slots[s as usize..(s + l + 1) as usize];
        let pos = block[..l as usize].partition_point(|p| p[0] < key);
        debug_assert!(pos == l as usize || block[pos][0] != key);
        block.copy_within(pos..l as usize, pos + 1);
        block[pos] = [key, id];
        self.hdr[node as usize] = [s, l + 1];
    }

    /// Removes the pair with `key`; returns whether it was there.
    pub(crate) fn remove(&mut self, node: u32, key: u32) -> bool {
        let [s, l] = self.hdr[node as usize];
        let block = &mut self.slots[s as usize..(s + l) as usize];
        let Some(pos) = block.iter().position(|p| p[0] == key) else {
            return false;
        };
        block.copy_within(pos + 1.., pos);
        let (oc, nc) = (cap_of(l), cap_of(l - 1));
        if oc != nc {
            if nc == 0 {
                self.release(s, oc);
                self.hdr[node as usize] = [0, 0];
                return true;
            }
            let ns = self.alloc(nc);
            self.slots
                .copy_within(s as usize..(s + l - 1) as usize, ns as usize);
            self.release(s, oc);
            self.hdr[node as usize] = [ns, l - 1];
        } else {
            self.hdr[node as usize] = [s, l - 1];
        }
        true
    }

    /// Re-points the pair with `key` to `id`.
    pub(crate) fn set(&mut self, node: u32, key: u32, id: u32) {
        if let Some(p) = self.get_mut(node).iter_mut().find(|p| p[0] == key) {
            p[1] = id;
        } else {
            debug_assert!(false, "up pair {key} missing at node {node}");
        }
    }

    /// Frees the block of `node` and moves the last node's header into its place.
    pub(crate) fn swap_remove_node(&mut self, node: u32) {
        let [s, l] = self.hdr[node as usize];
        self.release(s, cap_of(l));
        self.hdr.swap_remove(node as usize);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn insert_remove_keeps_sorted_blocks() {
        let mut a = UpArena::default();
        for _ in 0..3 {
            a.push_node();
        }
        let mut model: Vec<Vec<[u32; 2]>> = vec![vec![]; 3];
        let mut x = 12345u64;
        for step in 0..3000u32 {
            x = x.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
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
