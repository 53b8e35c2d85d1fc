//! Face keys: sorting and grouping the faces met in a leaf by their (sorted) vertices, with
//! a payload per occurrence; the engine of p-faces, adjacency, IA* and validation.
use crate::cell::CellKind;

/// Sorted face keys with payloads, grouped by key. Keys up to 4 vertices are packed in a
/// `u128`; longer ones are sorted as slices.
#[derive(Default)]
pub(crate) struct FaceKeys {
    w: usize,
    flat: Vec<u32>,
    payload: Vec<u64>,
    small: Vec<(u128, u64)>,
    /// Keys of three vertices with buckets: (first vertex, the other two, payload).
    mid: Vec<(u32, u64, u64)>,
    mid_tmp: Vec<(u64, u64)>,
    /// Unordered grouping: hash table (key, group + 1), group of each record, group sizes
    /// (then cursors), first record of each group, table slot of each group.
    ukeys: Vec<u64>,
    uvals: Vec<u32>,
    ugid: Vec<u32>,
    ucount: Vec<u32>,
    ufirst: Vec<u32>,
    uslot: Vec<u32>,
    tiny: Vec<(u64, u64)>,
    tiny_tmp: Vec<(u64, u64)>,
    small_tmp: Vec<(u128, u64)>,
    counts: Vec<u32>,
    buckets: Option<(u32, u32)>,
    prefix: Option<u32>,
    order: Vec<u32>,
    key: Vec<u32>,
    pays: Vec<u64>,
}

const PAD: u32 = u32::MAX;

impl FaceKeys {
    pub(crate) fn clear(&mut self, w: usize) {
        self.w = w;
        self.prefix = None;
        self.buckets = None;
        self.flat.clear();
        self.payload.clear();
        self.small.clear();
        self.mid.clear();
        self.tiny.clear();
    }
    /// Every key pushed shares this leading entry, which is not stored but is reported by
    /// [`for_each_group`](Self::for_each_group).
    pub(crate) fn set_prefix(&mut self, p: Option<u32>) {
        self.prefix = p;
    }
    /// Every stored key starts with a vertex in `lo..hi` (the leaf's own range): grouping
    /// then buckets by that vertex before sorting each small bucket (same order as a sort).
    pub(crate) fn set_buckets(&mut self, r: Option<(u32, u32)>) {
        self.buckets = r;
    }
    /// Pushes a sorted key (at most `w` ids).
    #[inline]
    pub(crate) fn push(&mut self, key: &[u32], payload: u64) {
        debug_assert!(key.len() <= self.w);
        if self.w <= 2 {
            let a = key.first().copied().unwrap_or(PAD) as u64;
            let b = key.get(1).copied().unwrap_or(PAD) as u64;
            self.tiny.push(((a << 32) | b, payload));
        } else if self.w == 3 && self.buckets.is_some() {
            let a = key.first().copied().unwrap_or(PAD);
            let b = key.get(1).copied().unwrap_or(PAD) as u64;
            let c = key.get(2).copied().unwrap_or(PAD) as u64;
            self.mid.push((a, (b << 32) | c, payload));
        } else if self.w <= 4 {
            let mut x: u128 = 0;
            for i in 0..4 {
                x = (x << 32) | key.get(i).copied().unwrap_or(PAD) as u128;
            }
            self.small.push((x, payload));
        } else {
            self.flat.extend_from_slice(key);
            self.flat
                .extend(std::iter::repeat_n(PAD, self.w - key.len()));
            self.payload.push(payload);
        }
    }
    /// Calls `f(key, payloads)` for every distinct key, in key order.
    pub(crate) fn for_each_group(&mut self, mut f: impl FnMut(&[u32], &[u64])) {
        if self.w <= 2 {
            match self.buckets {
                Some((lo, hi)) => bucket_sort(
                    &mut self.tiny,
                    &mut self.tiny_tmp,
                    &mut self.counts,
                    lo,
                    hi,
                    |x| (x.0 >> 32) as u32,
                ),
                None => self.tiny.sort_unstable(),
            }
            let mut i = 0;
            while i < self.tiny.len() {
                let k = self.tiny[i].0;
                let mut j = i;
                self.pays.clear();
                while j < self.tiny.len() && self.tiny[j].0 == k {
                    self.pays.push(self.tiny[j].1);
                    j += 1;
                }
                self.key.clear();
                self.key.extend(self.prefix);
                for x in [(k >> 32) as u32, k as u32] {
                    if x != PAD {
                        self.key.push(x);
                    }
                }
                f(&self.key, &self.pays);
                i = j;
            }
        } else if self.w == 3 && self.buckets.is_some() {
            self.mid_groups(&mut f);
        } else if self.w <= 4 {
            match self.buckets {
                Some((lo, hi)) => bucket_sort(
                    &mut self.small,
                    &mut self.small_tmp,
                    &mut self.counts,
                    lo,
                    hi,
                    |x| (x.0 >> 96) as u32,
                ),
                None => self.small.sort_unstable(),
            }
            let mut i = 0;
            while i < self.small.len() {
                let k = self.small[i].0;
                let mut j = i;
                self.pays.clear();
                while j < self.small.len() && self.small[j].0 == k {
                    self.pays.push(self.small[j].1);
                    j += 1;
                }
                self.key.clear();
                self.key.extend(self.prefix);
                for s in (0..4).rev() {
                    let x = (k >> (32 * s)) as u32;
                    if x != PAD {
                        self.key.push(x);
                    }
                }
                f(&self.key, &self.pays);
                i = j;
            }
        } else {
            let w = self.w;
            let n = self.payload.len();
            self.order.clear();
            self.order.extend(0..n as u32);
            let flat = &self.flat;
            let payload = &self.payload;
            self.order.sort_unstable_by(|&a, &b| {
                flat[a as usize * w..a as usize * w + w]
                    .cmp(&flat[b as usize * w..b as usize * w + w])
                    .then(payload[a as usize].cmp(&payload[b as usize]))
            });
            let mut i = 0;
            while i < n {
                let a = self.order[i] as usize;
                let ka = &flat[a * w..a * w + w];
                let mut j = i;
                self.pays.clear();
                while j < n {
                    let b = self.order[j] as usize;
                    if &flat[b * w..b * w + w] != ka {
                        break;
                    }
                    self.pays.push(payload[b]);
                    j += 1;
                }
                self.key.clear();
                self.key.extend(self.prefix);
                self.key.extend(ka.iter().copied().filter(|&x| x != PAD));
                f(&self.key, &self.pays);
                i = j;
            }
        }
    }
}

impl FaceKeys {
    /// Like [`for_each_group`](Self::for_each_group), but groups (and the payloads inside a
    /// group) may come in any order that depends only on the pushes: for keys of three
    /// vertices with buckets, each bucket is grouped with a small hash table instead of
    /// sorted.
    pub(crate) fn for_each_group_unordered(&mut self, mut f: impl FnMut(&[u32], &[u64])) {
        if !(self.w == 3 && self.buckets.is_some()) {
            return self.for_each_group(f);
        }
        let (lo, hi) = self.buckets.expect("buckets");
        let n = hi.saturating_sub(lo) as usize;
        if n == 0 || !self.mid.iter().all(|x| x.0 >= lo && x.0 < hi) {
            return self.mid_groups(&mut f);
        }
        self.scatter_mid(lo, n);
        let (counts, tmp) = (&self.counts, &mut self.mid_tmp);
        let (hk, hv, gid, gcount, firsts_slot) = (
            &mut self.ukeys,
            &mut self.uvals,
            &mut self.ugid,
            &mut self.ucount,
            &mut self.uslot,
        );
        let mut start = 0usize;
        for (b, &end) in counts[..n].iter().enumerate() {
            let end = end as usize;
            let bucket = &tmp[start..end];
            start = end;
            let len = bucket.len();
            if len == 0 {
                continue;
            }
            // group ids in first-occurrence order
            let cap = (2 * len).next_power_of_two().max(8);
            let shift = 64 - cap.trailing_zeros();
            let mask = cap - 1;
            if hk.len() < cap {
                hk.resize(cap, 0);
                hv.resize(cap, 0);
            }
            gid.clear();
            gcount.clear();
            firsts_slot.clear();
            for &(r, _) in bucket {
                let mut h = (r.wrapping_mul(0x9E37_79B9_7F4A_7C15) >> shift) as usize;
                let g = loop {
                    if hv[h] == 0 {
                        hk[h] = r;
                        hv[h] = gcount.len() as u32 + 1;
                        gcount.push(0);
                        firsts_slot.push(h as u32);
                        break gcount.len() - 1;
                    }
                    if hk[h] == r {
                        break hv[h] as usize - 1;
                    }
                    h = (h + 1) & mask;
                };
                gcount[g] += 1;
                gid.push(g as u32);
            }
            // empty the table: the first record of each group found its slot
            for &g in firsts_slot.iter() {
                hv[g as usize] = 0;
            }
            // payloads by group (counting sort on the group id)
            let ng = gcount.len();
            let mut acc = 0u32;
            for c in gcount.iter_mut() {
                let x = *c;
                *c = acc;
                acc += x;
            }
            self.pays.clear();
            self.pays.resize(len, 0);
            let mut firsts = std::mem::take(&mut self.ufirst);
            firsts.clear();
            firsts.resize(ng, 0);
            for (i, &(_, pay)) in bucket.iter().enumerate() {
                let g = gid[i] as usize;
                let pos = gcount[g] as usize;
                self.pays[pos] = pay;
                gcount[g] += 1;
                if firsts[g] == 0 {
                    firsts[g] = i as u32 + 1;
                }
            }
            let mut s = 0usize;
            for g in 0..ng {
                let e = gcount[g] as usize;
                let r = bucket[firsts[g] as usize - 1].0;
                self.key.clear();
                self.key.extend(self.prefix);
                for x in [lo + b as u32, (r >> 32) as u32, r as u32] {
                    if x != PAD {
                        self.key.push(x);
                    }
                }
                f(&self.key, &self.pays[s..e]);
                s = e;
            }
            self.ufirst = firsts;
        }
    }

    /// Counting sort of the three-vertex records by first vertex (all in `lo..lo + n`): the
    /// (other two, payload) pairs land in `mid_tmp`, bucket by bucket, and `counts[b]` ends
    /// as the end of bucket `b`.
    fn scatter_mid(&mut self, lo: u32, n: usize) {
        let counts = &mut self.counts;
        counts.clear();
        counts.resize(n + 1, 0);
        for x in &self.mid {
            counts[(x.0 - lo) as usize + 1] += 1;
        }
        for i in 0..n {
            counts[i + 1] += counts[i];
        }
        let tmp = &mut self.mid_tmp;
        tmp.clear();
        tmp.resize(self.mid.len(), (0, 0));
        for x in &self.mid {
            let b = (x.0 - lo) as usize;
            tmp[counts[b] as usize] = (x.1, x.2);
            counts[b] += 1;
        }
    }

    /// [`for_each_group`](Self::for_each_group) for keys of three vertices with buckets: a
    /// counting sort by first vertex, then each bucket's 16-byte (other two, payload) records
    /// sorted. Same order as sorting the whole keys.
    fn mid_groups(&mut self, f: &mut impl FnMut(&[u32], &[u64])) {
        let (lo, hi) = self.buckets.expect("buckets");
        let n = hi.saturating_sub(lo) as usize;
        let in_range = n > 0 && self.mid.iter().all(|x| x.0 >= lo && x.0 < hi);
        let mut emit = |key: &mut Vec<u32>, pays: &[u64], prefix: Option<u32>, a: u32, r: u64| {
            key.clear();
            key.extend(prefix);
            for x in [a, (r >> 32) as u32, r as u32] {
                if x != PAD {
                    key.push(x);
                }
            }
            f(key, pays);
        };
        if !in_range {
            self.mid.sort_unstable();
            let mut i = 0;
            while i < self.mid.len() {
                let (a, r, _) = self.mid[i];
                self.pays.clear();
                let mut j = i;
                while j < self.mid.len() && self.mid[j].0 == a && self.mid[j].1 == r {
                    self.pays.push(self.mid[j].2);
                    j += 1;
                }
                emit(&mut self.key, &self.pays, self.prefix, a, r);
                i = j;
            }
            return;
        }
        self.scatter_mid(lo, n);
        let (counts, tmp) = (&self.counts, &mut self.mid_tmp);
        // counts[b] is now the end of bucket b
        let mut start = 0usize;
        for (b, &end) in counts[..n].iter().enumerate() {
            let end = end as usize;
            let bucket = &mut tmp[start..end];
            if bucket.len() > 1 {
                bucket.sort_unstable();
            }
            let mut i = 0;
            while i < bucket.len() {
                let r = bucket[i].0;
                self.pays.clear();
                let mut j = i;
                while j < bucket.len() && bucket[j].0 == r {
                    self.pays.push(bucket[j].1);
                    j += 1;
                }
                emit(&mut self.key, &self.pays, self.prefix, lo + b as u32, r);
                i = j;
            }
            start = end;
        }
    }
}

/// Sorts `v` by bucketing on `first(x)` (which must lie in `lo..hi`, else it falls back to a
/// plain sort) and sorting each bucket; `T`'s order must start with `first`.
fn bucket_sort<T: Copy + Ord>(
    v: &mut Vec<T>,
    tmp: &mut Vec<T>,
    counts: &mut Vec<u32>,
    lo: u32,
    hi: u32,
    first: impl Fn(&T) -> u32,
) {
    let n = hi.saturating_sub(lo) as usize;
    if v.len() < 64 || n == 0 {
        v.sort_unstable();
        return;
    }
    counts.clear();
    counts.resize(n + 1, 0);
    for x in v.iter() {
        let b = first(x);
        if b < lo || b >= hi {
            v.sort_unstable();
            return;
        }
        counts[(b - lo) as usize + 1] += 1;
    }
    for i in 0..n {
        counts[i + 1] += counts[i];
    }
    tmp.clear();
    tmp.resize(v.len(), v[0]);
    for x in v.iter() {
        let b = (first(x) - lo) as usize;
        tmp[counts[b] as usize] = *x;
        counts[b] += 1;
    }
    // counts[b] is now the end of bucket b
    let mut start = 0usize;
    for &end in &counts[..n] {
        let end = end as usize;
        if end - start > 1 {
            tmp[start..end].sort_unstable();
        }
        start = end;
    }
    std::mem::swap(v, tmp);
}

/// Largest number of vertices of a `p`-face of `kind`.
pub(crate) fn face_width(kind: CellKind, p: usize) -> usize {
    if kind.is_simplex() {
        p + 1
    } else {
        kind.cp_faces(p)
            .map_or(0, |t| t.iter().map(|f| f.len()).max().unwrap_or(0))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bucket_sort_equals_sort() {
        let mut rng = crate::testkit::XorShift::new(12345);
        let mut next = || rng.next_u64();
        for n in [0usize, 1, 63, 64, 500, 3000] {
            let v: Vec<(u64, u64)> = (0..n)
                .map(|_| {
                    let a = 100 + next() % 50;
                    ((a << 32) | (next() % 7), next() % 5)
                })
                .collect();
            let mut want = v.clone();
            want.sort_unstable();
            let (mut got, mut tmp, mut counts) = (v.clone(), Vec::new(), Vec::new());
            bucket_sort(&mut got, &mut tmp, &mut counts, 100, 150, |x| {
                (x.0 >> 32) as u32
            });
            assert_eq!(got, want);
            // out-of-range keys fall back to a plain sort
            let mut got = v.clone();
            bucket_sort(&mut got, &mut tmp, &mut counts, 120, 130, |x| {
                (x.0 >> 32) as u32
            });
            assert_eq!(got, want);
        }
    }
}
