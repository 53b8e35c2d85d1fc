//! The vertex → top rows of [`TopSimplices`](super::TopSimplices), all in one array.
//!
//! Each vertex owns a *chunk* `[owner, capacity, length, entries…]` of the array. A row that
//! outgrows its chunk moves to a new chunk at the end, half as large again; the chunk left
//! behind is a hole, and so is the chunk of a vertex contracted away. When the holes are an
//! eighth of the array and it must grow, the live chunks slide down over them in one pass
//! (the owner in each chunk says whose it is). A row costs its entries, its position and three
//! numbers (16 bytes; 20 past 2^32 numbers), and the slack of its last move, and no allocation
//! of its own; a `SmallVec<[u32; 8]>` holding a tetrahedral vertex's ~20 tops spilled them to
//! the heap, at ~60 bytes beyond the entries.
//!
//! Contraction only shrinks the sum of the rows (a removed top leaves every row, an image
//! takes the place of its top), so the array never needs much more than its first size.

use rayon::prelude::*;

/// Numbers before a chunk's entries: owner, capacity, length.
const HEAD: usize = 3;
/// The owner of a hole.
const DEAD: u32 = u32::MAX;
/// A vertex without a chunk (an empty row of no capacity).
const NONE: usize = usize::MAX;

/// Vertex rows in one array (see the [module](self)).
#[derive(Clone, Debug, Default)]
pub(super) struct Rows {
    /// Per vertex: the position of its chunk's header (`NONE` for none).
    at: At,
    /// The chunks, one after the other.
    arena: Vec<u32>,
    /// Numbers of the array in holes.
    holes: usize,
}

impl Rows {
    /// The rows of `n` vertices made from tops `0..n_tops` (`top(t)` its vertices, all below
    /// `n`): per vertex, the tops through it in increasing id order, in chunks of exactly
    /// their size. The vertices are split in ranges, one per thread, each counted and filled
    /// in scans of the tops; `parallel` false keeps one range.
    pub(super) fn from_tops<'a, F>(n: usize, n_tops: usize, top: F, parallel: bool) -> Rows
    where
        F: Fn(usize) -> &'a [u32] + Sync,
    {
        let threads = if parallel {
            rayon::current_num_threads().max(1)
        } else {
            1
        };
        let span = n.div_ceil(threads).max(1);
        // the counts of each range's vertices, then the chunks' positions
        let mut count = vec![0u32; n];
        count
            .par_chunks_mut(span)
            .enumerate()
            .for_each(|(c, count)| {
                let lo = c * span;
                for t in 0..n_tops {
                    for &v in top(t) {
                        if let Some(k) = (v as usize).checked_sub(lo).and_then(|i| count.get_mut(i))
                        {
                            *k += 1;
                        }
                    }
                }
            });
        let pos = count.iter().map(|&c| HEAD + c as usize).sum::<usize>();
        let at = At::positions(count, pos);
        let mut arena = vec![0u32; pos];
        // each range fills its own stretch of the array
        let mut pieces: Vec<(usize, &mut [u32])> = Vec::with_capacity(threads);
        let mut rest: &mut [u32] = &mut arena;
        let mut base = 0;
        for c in 0..n.div_ceil(span) {
            let end = if (c + 1) * span < n {
                at.get((c + 1) * span)
            } else {
                pos
            };
            let (piece, tail) = rest.split_at_mut(end - base);
            pieces.push((c * span, piece));
            rest = tail;
            base = end;
        }
        pieces.into_par_iter().for_each(|(lo, piece)| {
            let hi = (lo + span).min(n);
            let base = at.get(lo);
            for v in lo..hi {
                let (a, next) = (at.get(v), if v + 1 < n { at.get(v + 1) } else { pos });
                let h = a - base;
                piece[h] = v as u32;
                piece[h + 1] = (next - a - HEAD) as u32;
            }
            for t in 0..n_tops {
                for &v in top(t) {
                    let v = v as usize;
                    if (lo..hi).contains(&v) {
                        let h = at.get(v) - base;
                        let len = piece[h + 2] as usize;
                        piece[h + HEAD + len] = t as u32;
                        piece[h + 2] += 1;
                    }
                }
            }
        });
        Rows {
            at,
            arena,
            holes: 0,
        }
    }

    /// The row of `v` (empty beyond the vertices).
    #[inline]
    pub(super) fn row(&self, v: usize) -> &[u32] {
        if v >= self.at.len() {
            return &[];
        }
        match self.at.get(v) {
            NONE => &[],
            a => {
                let len = self.arena[a + 2] as usize;
                &self.arena[a + HEAD..a + HEAD + len]
            }
        }
    }

    /// The length of the row of `v`.
    #[inline]
    pub(super) fn len(&self, v: usize) -> usize {
        match self.at.get(v) {
            NONE => 0,
            a => self.arena[a + 2] as usize,
        }
    }

    /// Appends `t` to the row of `v`.
    pub(super) fn push(&mut self, v: usize, t: u32) {
        self.extend(v, &[t]);
    }

    /// Appends `ts` to the row of `v`, moving it to a larger chunk when it does not fit.
    pub(super) fn extend(&mut self, v: usize, ts: &[u32]) {
        if ts.is_empty() {
            return;
        }
        let (len, cap) = match self.at.get(v) {
            NONE => (0, 0),
            a => (self.arena[a + 2] as usize, self.arena[a + 1] as usize),
        };
        if len + ts.len() > cap {
            self.grow(v, len + ts.len());
        }
        let a = self.at.get(v);
        self.arena[a + HEAD + len..a + HEAD + len + ts.len()].copy_from_slice(ts);
        self.arena[a + 2] = (len + ts.len()) as u32;
    }

    /// Removes one `t` from the row of `v` (the last entry takes its place); nothing when
    /// it is not there.
    pub(super) fn remove(&mut self, v: usize, t: u32) {
        let a = self.at.get(v);
        if a == NONE {
            return;
        }
        let len = self.arena[a + 2] as usize;
        let row = &mut self.arena[a + HEAD..a + HEAD + len];
        if let Some(i) = row.iter().position(|&x| x == t) {
            row[i] = row[len - 1];
            self.arena[a + 2] -= 1;
        }
    }

    /// Keeps the entries of the row of `v` that `keep` accepts, in order.
    pub(super) fn retain(&mut self, v: usize, mut keep: impl FnMut(u32) -> bool) {
        let a = self.at.get(v);
        if a == NONE {
            return;
        }
        let len = self.arena[a + 2] as usize;
        let mut out = 0;
        for i in 0..len {
            let t = self.arena[a + HEAD + i];
            if keep(t) {
                self.arena[a + HEAD + out] = t;
                out += 1;
            }
        }
        self.arena[a + 2] = out as u32;
    }

    /// Empties the row of `v`, keeping its chunk.
    pub(super) fn clear(&mut self, v: usize) {
        let a = self.at.get(v);
        if a != NONE {
            self.arena[a + 2] = 0;
        }
    }

    /// Empties the row of `v` and gives its chunk up (a vertex contracted away).
    pub(super) fn free(&mut self, v: usize) {
        let a = self.at.get(v);
        self.at.set(v, NONE);
        if a != NONE {
            self.arena[a] = DEAD;
            self.holes += HEAD + self.arena[a + 1] as usize;
        }
    }

    /// Moves the row of `v` to a new chunk at the end for at least `need` entries (half as
    /// large again as its length); first slides the chunks over the holes when they are an
    /// eighth of the array and it would have to grow.
    fn grow(&mut self, v: usize, need: usize) {
        let len = self.len(v);
        let cap = need.max(len + len / 2).max(4);
        if self.arena.len() + HEAD + cap > self.arena.capacity() {
            if self.holes * 8 >= self.arena.len() {
                self.compact();
            }
            let more = HEAD + cap;
            if self.arena.len() + more > self.arena.capacity() {
                // grow by an eighth, not double: the array is most of the structure
                let extra = more.max(self.arena.len() / 8);
                self.arena.reserve_exact(extra);
            }
        }
        let start = self.arena.len();
        self.arena
            .extend_from_slice(&[v as u32, cap as u32, len as u32]);
        match self.at.get(v) {
            NONE => {}
            a => {
                self.arena.extend_from_within(a + HEAD..a + HEAD + len);
                self.arena[a] = DEAD;
                self.holes += HEAD + self.arena[a + 1] as usize;
            }
        }
        self.arena.resize(start + HEAD + cap, 0);
        self.at.set(v, start);
    }

    /// Slides every live chunk down over the holes, in one pass.
    fn compact(&mut self) {
        let mut out = 0;
        let mut pos = 0;
        while pos < self.arena.len() {
            let owner = self.arena[pos];
            let size = HEAD + self.arena[pos + 1] as usize;
            if owner != DEAD {
                self.arena.copy_within(pos..pos + size, out);
                self.at.set(owner as usize, out);
                out += size;
            }
            pos += size;
        }
        self.arena.truncate(out);
        self.holes = 0;
    }

    /// Bytes held (the array's capacity and the positions).
    #[cfg(test)]
    pub(super) fn bytes(&self) -> usize {
        self.arena.capacity() * 4 + self.at.bytes()
    }
}

/// The chunks' positions: 4 bytes a vertex while the array holds fewer than 2^32 - 1 numbers,
/// 8 beyond (widened the first time a chunk lands past that).
#[derive(Clone, Debug)]
enum At {
    /// Positions below `u32::MAX`; `u32::MAX` for none.
    Narrow(Vec<u32>),
    /// Any position; `NONE` for none.
    Wide(Vec<usize>),
}

impl Default for At {
    fn default() -> Self {
        At::Narrow(Vec::new())
    }
}

impl At {
    /// The positions of chunks laid one after the other, of `HEAD` plus each count (their sum
    /// `total`), made in place of the counts when they fit in 32 bits.
    fn positions(mut count: Vec<u32>, total: usize) -> At {
        if total < u32::MAX as usize {
            let mut pos = 0u32;
            for c in count.iter_mut() {
                let len = *c;
                *c = pos;
                pos += HEAD as u32 + len;
            }
            At::Narrow(count)
        } else {
            let mut pos = 0usize;
            At::Wide(
                count
                    .iter()
                    .map(|&c| {
                        let p = pos;
                        pos += HEAD + c as usize;
                        p
                    })
                    .collect(),
            )
        }
    }

    fn len(&self) -> usize {
        match self {
            At::Narrow(a) => a.len(),
            At::Wide(a) => a.len(),
        }
    }

    #[inline]
    fn get(&self, v: usize) -> usize {
        match self {
            At::Narrow(a) => match a[v] {
                u32::MAX => NONE,
                p => p as usize,
            },
            At::Wide(a) => a[v],
        }
    }

    #[inline]
    fn set(&mut self, v: usize, p: usize) {
        match self {
            At::Narrow(a) if p == NONE => a[v] = u32::MAX,
            At::Narrow(a) if p < u32::MAX as usize => a[v] = p as u32,
            At::Narrow(a) => {
                let wide = a
                    .iter()
                    .map(|&x| if x == u32::MAX { NONE } else { x as usize })
                    .collect();
                *self = At::Wide(wide);
                self.set(v, p);
            }
            At::Wide(a) => a[v] = p,
        }
    }

    #[cfg(test)]
    fn bytes(&self) -> usize {
        match self {
            At::Narrow(a) => a.capacity() * 4,
            At::Wide(a) => a.capacity() * 8,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testkit::XorShift;

    /// Positions stay 4 bytes a vertex until one does not fit, then all widen, keeping the
    /// others and the empty ones; counts whose chunks would pass 2^32 numbers start wide.
    #[test]
    fn positions_widen() {
        let mut at = At::positions(vec![2, 0, 5], 3 * HEAD + 7);
        assert_eq!((0..3).map(|v| at.get(v)).collect::<Vec<_>>(), [0, 5, 8]);
        assert_eq!(at.bytes(), 12);
        at.set(1, NONE);
        at.set(2, u32::MAX as usize - 1);
        assert!(matches!(at, At::Narrow(_)));
        at.set(0, u32::MAX as usize + 7);
        assert!(matches!(at, At::Wide(_)));
        let got: Vec<usize> = (0..3).map(|v| at.get(v)).collect();
        assert_eq!(got, [u32::MAX as usize + 7, NONE, u32::MAX as usize - 1]);
        assert_eq!(at.len(), 3);
        let big = At::positions(vec![1, 2], u32::MAX as usize);
        assert!(matches!(big, At::Wide(_)));
        assert_eq!((big.get(0), big.get(1)), (0, HEAD + 1));
    }

    /// Random pushes, removals, retains, clears and frees against a vector per vertex; the
    /// array compacts along the way and stays within a bound of what the rows hold.
    #[test]
    fn rows_are_vectors() {
        let mut r = XorShift::new(0x0505);
        let n = 300;
        let tops: Vec<Vec<u32>> = (0..900)
            .map(|_| (0..3).map(|_| r.below(n as u64) as u32).collect())
            .collect();
        for parallel in [false, true] {
            let mut rows = Rows::from_tops(n, tops.len(), |t| &tops[t], parallel);
            let mut model: Vec<Vec<u32>> = vec![Vec::new(); n];
            for (t, top) in tops.iter().enumerate() {
                for &v in top {
                    model[v as usize].push(t as u32);
                }
            }
            let mut compactions = 0;
            for step in 0..20_000u32 {
                let v = r.below(n as u64) as usize;
                match r.below(10) {
                    0..=4 => {
                        let k = 1 + r.below(6) as usize;
                        let ts: Vec<u32> = (0..k).map(|i| step * 8 + i as u32).collect();
                        let before = rows.holes;
                        rows.extend(v, &ts);
                        compactions += usize::from(rows.holes < before);
                        model[v].extend(&ts);
                    }
                    5..=6 => {
                        if let Some(&t) = model[v].get(r.below(4) as usize) {
                            rows.remove(v, t);
                            let i = model[v].iter().position(|&x| x == t).unwrap();
                            model[v].swap_remove(i);
                        }
                    }
                    7 => {
                        rows.retain(v, |t| t % 3 != 0);
                        model[v].retain(|t| t % 3 != 0);
                    }
                    8 => {
                        rows.clear(v);
                        model[v].clear();
                    }
                    _ => {
                        rows.free(v);
                        rows.extend(v, &[]); // nothing to add to a row without a chunk
                        model[v].clear();
                    }
                }
                if step % 97 == 0 {
                    for (u, m) in model.iter().enumerate() {
                        assert_eq!(rows.row(u), &m[..], "vertex {u} at step {step}");
                        assert_eq!(rows.len(u), m.len());
                    }
                }
            }
            for (u, m) in model.iter().enumerate() {
                assert_eq!(rows.row(u), &m[..]);
            }
            assert!(compactions > 3, "{compactions}");
            let live: usize = model.iter().map(|m| m.len()).sum();
            // entries, headers, a half of slack and a quarter of holes, and the growth step
            assert!(
                rows.arena.len() <= 2 * (live + HEAD * n) + 64,
                "{}",
                rows.arena.len()
            );
            assert!(rows.bytes() >= rows.arena.len() * 4);
        }
    }
}
