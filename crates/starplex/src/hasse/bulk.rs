//! Bulk construction from a list of simplices (dimension at most 3): instead of inserting cells
//! one by one (random access into the vertex lookup and the up lists), every level is built
//! from the one above by one counting sort of its facets on their first label, then a small
//! sort per label. Nodes come out in lexicographic order and every up list in one
//! exactly-sized block, laid out in node order.
use super::complex::Hasse;
use super::levels::LevelTypes;

const NO_PARENT: u32 = u32::MAX;

/// A facet: its labels after the first (at most two, packed first label most significant),
/// the parent node and the position of the label the facet omits (or [`NO_PARENT`] for an
/// input cell). The first label is the counting-sort bucket.
type Rec = (u64, u32, u32);

/// Labels after the first of a sorted tuple of at most 4 labels, packed 32 bits each, first
/// most significant (so packed tuples compare like the tuples).
#[inline]
fn pack_rest(vs: &[u32]) -> u128 {
    let mut x = 0u128;
    for &v in &vs[1..] {
        x = (x << 32) | v as u128;
    }
    x
}

/// Appends `first` then the `n - 1` labels packed in `rest`.
#[inline]
fn push_unpacked(out: &mut Vec<u32>, first: u32, rest: u128, n: usize) {
    out.push(first);
    for i in (0..n - 1).rev() {
        out.push((rest >> (32 * i)) as u32);
    }
}

/// Counting-sort offsets: `count[l]..count[l + 1]` is bucket `l` once `count[l + 1]` holds the
/// size of bucket `l` (the prefix sums are taken here).
fn prefix(count: &mut [u32]) {
    for b in 1..count.len() {
        count[b] += count[b - 1];
    }
}

impl<L: LevelTypes> Hasse<L> {
    /// Builds an empty complex's levels from sorted, non-degenerate simplices given per
    /// dimension (flat arrays, `k + 1` labels per `k`-simplex, `k <= 3`).
    pub(crate) fn bulk_build(&mut self, cells: &[Vec<u32>]) {
        debug_assert!(self.is_empty() && cells.len() <= 4);
        let Some(d) = (0..cells.len()).rev().find(|&k| !cells[k].is_empty()) else {
            return;
        };
        let total: usize = cells.iter().map(|c| c.len()).sum();
        let max_label = cells
            .iter()
            .flat_map(|c| c.iter())
            .copied()
            .max()
            .unwrap_or(0);
        if max_label as usize > 4 * total + 4096 {
            // sparse labels: build on their ranks (same order), then label the nodes
            let mut labels: Vec<u32> = cells.iter().flatten().copied().collect();
            labels.sort_unstable();
            labels.dedup();
            let ranked: Vec<Vec<u32>> = cells
                .iter()
                .map(|c| {
                    c.iter()
                        .map(|&x| labels.partition_point(|&y| y < x) as u32)
                        .collect()
                })
                .collect();
            self.bulk_build_dense(&ranked, d, labels.len() as u32 - 1);
            for l in &mut self.levels {
                for x in &mut l.verts {
                    *x = labels[*x as usize];
                }
                l.up.map_keys(|x| labels[x as usize]);
            }
        } else {
            self.bulk_build_dense(cells, d, max_label);
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

    /// [`bulk_build`](Self::bulk_build) with labels at most `max_label` (counting sorts over
    /// `max_label + 1` buckets); `d` is the top dimension.
    fn bulk_build_dense(&mut self, cells: &[Vec<u32>], d: usize, max_label: u32) {
        self.ensure_level(d);
        let nb = max_label as usize + 1;
        let mut count = vec![0u32; nb + 1];
        self.bulk_top_level(&cells[d], d, &mut count);
        let mut recs: Vec<Rec> = Vec::new();
        let mut pos: Vec<u32> = Vec::new();
        let mut ups: Vec<[u32; 2]> = Vec::new();
        for k in (1..=d).rev() {
            // facets of level k, plus the input cells of dimension k - 1, bucketed by their
            // first label
            let l = &self.levels[k];
            bucket_facets(&l.verts, &cells[k - 1], k, &mut count, &mut recs, &mut pos);
            debug_assert_eq!(l.slots() * (k + 1) + cells[k - 1].len() / k, recs.len());
            let (groups, slots) = sort_buckets(&mut recs, &count);
            self.bulk_level_below(k, &recs, &count, (groups, slots), &mut ups);
        }
        // a little headroom in every arena, so the first local edits after a bulk build do not
        // reallocate (and copy) a whole arena
        for l in &mut self.levels {
            l.up.reserve_headroom();
        }
    }

    /// The top level `d` from the input cells `top` (`d + 1` labels each): unique tuples,
    /// bucketed by first label, sorted in each bucket; `count` has `max_label + 2` entries.
    #[inline]
    fn bulk_top_level(&mut self, top: &[u32], d: usize, count: &mut [u32]) {
        let nb = count.len() - 1;
        let n = d + 1;
        for c in top.chunks_exact(n) {
            count[c[0] as usize + 1] += 1;
        }
        prefix(count);
        let mut keys = vec![0u128; top.len() / n];
        let mut pos = count.to_vec();
        for c in top.chunks_exact(n) {
            let p = &mut pos[c[0] as usize];
            keys[*p as usize] = pack_rest(c);
            *p += 1;
        }
        drop(pos);
        let mut unique = 0usize;
        for a in 0..nb {
            let b = &mut keys[count[a] as usize..count[a + 1] as usize];
            if b.len() > 1 {
                b.sort_unstable();
            }
            // duplicates are adjacent now
            unique += b.len() - b.windows(2).filter(|w| w[0] == w[1]).count();
        }
        let l = &mut self.levels[d];
        l.verts.reserve_exact(unique * n);
        for a in 0..nb {
            let b = &keys[count[a] as usize..count[a + 1] as usize];
            for (i, &r) in b.iter().enumerate() {
                if i == 0 || b[i - 1] != r {
                    push_unpacked(&mut l.verts, a as u32, r, n);
                }
            }
        }
        if d > 0 {
            l.down = vec![0; l.verts.len()];
        }
        l.up.hdr.reserve_exact(unique);
        for _ in 0..unique {
            l.up.push_node(0);
        }
        for _ in 0..unique {
            L::push_default(&mut self.data, d);
        }
    }

    /// Level `k - 1` from the sorted facet records of level `k`: each group of equal keys
    /// becomes one node (labels, up list sorted, the faces' `down` entries above pointing to
    /// it); `sizes` = (groups, up-arena slots) from [`sort_buckets`].
    #[inline]
    fn bulk_level_below(
        &mut self,
        k: usize,
        recs: &[Rec],
        count: &[u32],
        sizes: (usize, usize),
        ups: &mut Vec<[u32; 2]>,
    ) {
        let nb = count.len() - 1;
        let (groups, slots) = sizes;
        let (lo, hi) = self.levels.split_at_mut(k);
        let below = &mut lo[k - 1];
        let above = &mut hi[0];
        below.verts.reserve_exact(groups * k);
        if k > 1 {
            below.down.reserve_exact(groups * k);
        }
        below.up.hdr.reserve_exact(groups);
        // with the headroom reserved below, so that it costs no copy
        below.up.reserve_slots(slots + slots / 16 + 64);
        L::reserve(&mut self.data, k - 1, groups);
        for a in 0..nb {
            let b = &recs[count[a] as usize..count[a + 1] as usize];
            let mut g = 0;
            while g < b.len() {
                let key = b[g].0;
                let mut e = g;
                ups.clear();
                while e < b.len() && b[e].0 == key {
                    let (_, p, q) = b[e];
                    if p != NO_PARENT {
                        let w = above.verts[p as usize * (k + 1) + q as usize];
                        ups.push([w, p]);
                    }
                    e += 1;
                }
                let id = below.slots() as u32;
                push_unpacked(&mut below.verts, a as u32, key as u128, k);
                if k > 1 {
                    below.down.extend(std::iter::repeat_n(0, k));
                }
                if ups.len() == 2 {
                    if ups[1] < ups[0] {
                        ups.swap(0, 1);
                    }
                } else {
                    ups.sort_unstable();
                }
                below.up.push_node_with(ups);
                for r in &b[g..e] {
                    if r.1 != NO_PARENT {
                        above.down[r.1 as usize * (k + 1) + r.2 as usize] = id;
                    }
                }
                L::push_default(&mut self.data, k - 1);
                g = e;
            }
        }
    }
}

/// Counting sort of the facets of level `k` (`verts`, `k + 1` labels per node) and of the input
/// cells of dimension `k - 1` (`below`) into `recs`, bucketed by first label (`count`: the
/// bucket offsets after the call; `pos` scratch).
#[inline]
fn bucket_facets(
    verts: &[u32],
    below: &[u32],
    k: usize,
    count: &mut [u32],
    recs: &mut Vec<Rec>,
    pos: &mut Vec<u32>,
) {
    let nb = count.len() - 1;
    count.iter_mut().for_each(|c| *c = 0);
    for vs in verts.chunks_exact(k + 1) {
        count[vs[1] as usize + 1] += 1; // the facet without vs[0]
        count[vs[0] as usize + 1] += k as u32;
    }
    for c in below.chunks_exact(k) {
        count[c[0] as usize + 1] += 1;
    }
    prefix(count);
    recs.clear();
    recs.resize(count[nb] as usize, (0, 0, 0));
    pos.clear();
    pos.extend_from_slice(&count[..nb]);
    let mut f = [0u32; 4];
    for (i, vs) in verts.chunks_exact(k + 1).enumerate() {
        for j in 0..=k {
            let mut m = 0;
            for (t, &x) in vs.iter().enumerate() {
                if t != j {
                    f[m] = x;
                    m += 1;
                }
            }
            let p = &mut pos[f[0] as usize];
            recs[*p as usize] = (pack_rest(&f[..k]) as u64, i as u32, j as u32);
            *p += 1;
        }
    }
    for c in below.chunks_exact(k) {
        let p = &mut pos[c[0] as usize];
        recs[*p as usize] = (pack_rest(c) as u64, NO_PARENT, 0);
        *p += 1;
    }
}

/// Sorts every bucket of `recs` by key; returns the number of groups (equal keys: the nodes of
/// the level below) and the arena slots their up lists need (power-of-two blocks).
#[inline]
fn sort_buckets(recs: &mut [Rec], count: &[u32]) -> (usize, usize) {
    let nb = count.len() - 1;
    let (mut groups, mut slots) = (0usize, 0usize);
    for a in 0..nb {
        let b = &mut recs[count[a] as usize..count[a + 1] as usize];
        match b.len() {
            0 => continue,
            1 => {}
            2 => {
                if b[1].0 < b[0].0 {
                    b.swap(0, 1);
                }
            }
            _ => b.sort_unstable_by_key(|r| r.0),
        }
        let mut run = 0u32;
        for (i, r) in b.iter().enumerate() {
            if r.1 != NO_PARENT {
                run += 1;
            }
            if i + 1 == b.len() || b[i + 1].0 != r.0 {
                groups += 1;
                if run > 0 {
                    slots += run.next_power_of_two().max(2) as usize;
                }
                run = 0;
            }
        }
    }
    (groups, slots)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A node by labels: its labels, its faces' labels, its up list (key, coface's labels).
    type NodeByLabels = (Vec<u32>, Vec<Vec<u32>>, Vec<(u32, Vec<u32>)>);

    /// Every node, by labels (independent of node ids), per level.
    fn by_labels(h: &Hasse) -> Vec<Vec<NodeByLabels>> {
        let mut out = Vec::new();
        for k in 0..h.levels.len() {
            let l = &h.levels[k];
            let mut level: Vec<_> = (0..l.slots() as u32)
                .map(|i| {
                    let downs = l
                        .downs(i)
                        .iter()
                        .map(|&f| h.levels[k - 1].verts(f).to_vec())
                        .collect();
                    let ups =
                        l.up.get(i)
                            .iter()
                            .map(|&[w, c]| (w, h.levels[k + 1].verts(c).to_vec()))
                            .collect();
                    (l.verts(i).to_vec(), downs, ups)
                })
                .collect();
            level.sort();
            out.push(level);
        }
        out
    }

    /// The bulk build equals cell-by-cell insertion, with nodes in lexicographic order, on
    /// random mixed complexes of dimension ≤ 3 with dense and sparse labels.
    #[test]
    fn bulk_build_equals_insertion() {
        let mut rng = crate::testkit::XorShift::new(0x9E37_79B9_7F4A_7C15);
        let mut next = |m: u64| rng.below(m);
        for case in 0..300 {
            let nv = 4 + next(30) as u32;
            let scale = if case % 3 == 0 { 100_003 } else { 1 };
            let mut cells: Vec<Vec<u32>> = vec![Vec::new(); 4];
            let mut inc: Hasse = Hasse::new();
            for _ in 0..1 + next(40) {
                let len = 1 + next(4) as usize;
                let mut c: Vec<u32> = Vec::new();
                while c.len() < len {
                    let v = next(nv as u64) as u32 * scale;
                    if !c.contains(&v) {
                        c.push(v);
                    }
                }
                c.sort_unstable();
                inc.insert_sorted(&c);
                cells[len - 1].extend_from_slice(&c);
            }
            let mut bulk: Hasse = Hasse::new();
            bulk.bulk_build(&cells);
            assert_eq!(bulk.check(), Ok(()), "case {case}");
            for l in &bulk.levels {
                let v: Vec<&[u32]> = l.verts.chunks_exact(l.k1).collect();
                assert!(v.windows(2).all(|w| w[0] < w[1]), "case {case}: order");
            }
            assert_eq!(bulk.f_vector(), inc.f_vector(), "case {case}");
            assert_eq!(by_labels(&bulk), by_labels(&inc), "case {case}");
            assert_eq!(bulk.max_label, inc.max_label, "case {case}");
        }
    }
}
