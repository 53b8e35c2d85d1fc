//! Bulk construction from a list of simplices (dimension at most 3): instead of inserting cells
//! one by one (random access into the vertex lookup and the up lists), every level is built
//! from the one above by one sort of its facets. Nodes come out in lexicographic order and
//! every up list in one exactly-sized block, laid out in node order.
use super::complex::Hasse;
use super::levels::Levels;

/// A sorted tuple of at most 4 labels packed in two words, first label most significant (so
/// keys compare like the tuples; 8-byte alignment keeps a record at 24 bytes).
type Key = (u64, u64);

#[inline]
fn pack(vs: &[u32]) -> Key {
    let mut w = [0u32; 4];
    w[..vs.len()].copy_from_slice(vs);
    (
        ((w[0] as u64) << 32) | w[1] as u64,
        ((w[2] as u64) << 32) | w[3] as u64,
    )
}

#[inline]
fn unpack(k: Key, n: usize, out: &mut [u32; 4]) {
    let w = [
        (k.0 >> 32) as u32,
        k.0 as u32,
        (k.1 >> 32) as u32,
        k.1 as u32,
    ];
    out[..n].copy_from_slice(&w[..n]);
}

const NO_PARENT: u32 = u32::MAX;

type Rec = (Key, u32, u32);

/// Label `i` of a packed key.
#[inline]
fn label(k: Key, i: usize) -> u32 {
    match i {
        0 => (k.0 >> 32) as u32,
        1 => k.0 as u32,
        2 => (k.1 >> 32) as u32,
        _ => k.1 as u32,
    }
}

/// Sorts records by key: a least-significant-label-first counting sort (one pass per label)
/// when labels are small, a comparison sort otherwise. Stable order is not needed.
fn sort_recs(recs: &mut Vec<Rec>, k: usize, max_label: u32, tmp: &mut Vec<Rec>) {
    let buckets = max_label as usize + 1;
    if buckets > 4 * recs.len() + 4096 {
        recs.sort_unstable_by_key(|r| r.0);
        return;
    }
    let mut count = vec![0u32; buckets + 1];
    tmp.clear();
    tmp.resize(recs.len(), ((0, 0), 0, 0));
    for pos in (0..k).rev() {
        count.iter_mut().for_each(|c| *c = 0);
        for r in recs.iter() {
            count[label(r.0, pos) as usize + 1] += 1;
        }
        for b in 1..count.len() {
            count[b] += count[b - 1];
        }
        for r in recs.iter() {
            let b = label(r.0, pos) as usize;
            tmp[count[b] as usize] = *r;
            count[b] += 1;
        }
        std::mem::swap(recs, tmp);
    }
}

impl<L: Levels> Hasse<L> {
    /// Builds an empty complex's levels from sorted, non-degenerate simplices given per
    /// dimension (flat arrays, `k + 1` labels per `k`-simplex, `k <= 3`).
    pub(crate) fn bulk_build(&mut self, cells: &[Vec<u32>]) {
        debug_assert!(self.is_empty() && cells.len() <= 4);
        let Some(d) = (0..cells.len()).rev().find(|&k| !cells[k].is_empty()) else {
            return;
        };
        self.ensure_level(d);
        // top level: unique tuples
        let mut keys: Vec<Key> = cells[d].chunks_exact(d + 1).map(pack).collect();
        keys.sort_unstable();
        keys.dedup();
        let mut buf = [0u32; 4];
        {
            let l = &mut self.levels[d];
            l.verts.reserve_exact(keys.len() * (d + 1));
            for &k in &keys {
                unpack(k, d + 1, &mut buf);
                l.verts.extend_from_slice(&buf[..d + 1]);
            }
            if d > 0 {
                l.down = vec![0; l.verts.len()];
            }
            l.up.hdr.reserve_exact(keys.len());
            for _ in 0..keys.len() {
                l.up.push_node(0);
            }
            for _ in 0..keys.len() {
                L::push_default(&mut self.data, d);
            }
        }
        drop(keys);
        let max_label = cells
            .iter()
            .flat_map(|c| c.iter())
            .copied()
            .max()
            .unwrap_or(0);
        let mut recs: Vec<Rec> = Vec::new();
        let mut tmp: Vec<Rec> = Vec::new();
        let mut ups: Vec<[u32; 2]> = Vec::new();
        for k in (1..=d).rev() {
            // facets of level k, plus the input cells of dimension k - 1
            recs.clear();
            let n = self.levels[k].slots();
            recs.reserve(n * (k + 1) + cells[k - 1].len() / k);
            {
                let l = &self.levels[k];
                let mut f = [0u32; 4];
                for i in 0..n as u32 {
                    let vs = l.verts(i);
                    for j in 0..=k {
                        let mut m = 0;
                        for (t, &x) in vs.iter().enumerate() {
                            if t != j {
                                f[m] = x;
                                m += 1;
                            }
                        }
                        recs.push((pack(&f[..k]), i, j as u32));
                    }
                }
            }
            for c in cells[k - 1].chunks_exact(k) {
                recs.push((pack(c), NO_PARENT, 0));
            }
            sort_recs(&mut recs, k, max_label, &mut tmp);
            // groups become the nodes of level k - 1
            let (lo, hi) = self.levels.split_at_mut(k);
            let below = &mut lo[k - 1];
            let above = &mut hi[0];
            // count the groups and the arena slots their up lists need (power-of-two blocks)
            let (mut groups, mut slots, mut run) = (0usize, 0usize, 0u32);
            for (i, r) in recs.iter().enumerate() {
                if r.1 != NO_PARENT {
                    run += 1;
                }
                if i + 1 == recs.len() || recs[i + 1].0 != r.0 {
                    groups += 1;
                    if run > 0 {
                        slots += run.next_power_of_two().max(2) as usize;
                    }
                    run = 0;
                }
            }
            below.verts.reserve_exact(groups * k);
            if k > 1 {
                below.down.reserve_exact(groups * k);
            }
            below.up.hdr.reserve_exact(groups);
            below.up.reserve_slots(slots);
            L::reserve(&mut self.data, k - 1, groups);
            let mut g = 0;
            while g < recs.len() {
                let key = recs[g].0;
                let mut e = g;
                ups.clear();
                while e < recs.len() && recs[e].0 == key {
                    let (_, p, pos) = recs[e];
                    if p != NO_PARENT {
                        let w = above.verts[p as usize * (k + 1) + pos as usize];
                        ups.push([w, p]);
                    }
                    e += 1;
                }
                let id = below.slots() as u32;
                unpack(key, k, &mut buf);
                for &x in &buf[..k] {
                    below.verts.push(x);
                }
                if k > 1 {
                    for _ in 0..k {
                        below.down.push(0);
                    }
                }
                ups.sort_unstable();
                below.up.push_node_with(&ups);
                for r in &recs[g..e] {
                    if r.1 != NO_PARENT {
                        above.down[r.1 as usize * (k + 1) + r.2 as usize] = id;
                    }
                }
                L::push_default(&mut self.data, k - 1);
                g = e;
            }
        }
        // a little headroom in every arena, so the first local edits after a bulk build do not
        // reallocate (and copy) a whole arena
        for l in &mut self.levels {
            l.up.reserve_headroom();
        }
        let l0 = &self.levels[0];
        self.root.reserve_dense(
            l0.verts
                .last()
                .map_or(0, |&m| m as usize + 1)
                .min(2 * l0.verts.len() + 4096),
        );
        for (i, &lab) in l0.verts.iter().enumerate() {
            self.root.insert(lab, i as u32);
        }
        self.max_label = l0.verts.last().copied();
    }
}
