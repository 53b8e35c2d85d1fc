//! Sorting networks for the many short rows the relations sort (a vertex's few cells, a
//! dozen edge records): straight-line compare-exchanges, no branches to mispredict, where
//! an insertion sort of the same rows spends its time in mispredicted branches.

/// Compare-exchanges in straight-line code (each pair: smaller first), without branches.
macro_rules! network {
    ($a:ident; $(($i:literal, $j:literal)),* $(,)?) => {
        $({
            let (x, y) = ($a[$i], $a[$j]);
            $a[$i] = x.min(y);
            $a[$j] = x.max(y);
        })*
    };
}

/// An optimal sorting network on 8 inputs (19 comparators).
#[inline(always)]
pub(crate) fn net8<T: Ord + Copy>(a: &mut [T; 8]) {
    network!(a; (0, 2), (1, 3), (4, 6), (5, 7), (0, 4), (1, 5), (2, 6), (3, 7), (0, 1),
        (2, 3), (4, 5), (6, 7), (2, 4), (3, 5), (1, 4), (3, 6), (1, 2), (3, 4), (5, 6));
}

/// Batcher's odd-even merge sorting network on 16 inputs (63 comparators).
#[inline(always)]
pub(crate) fn net16<T: Ord + Copy>(a: &mut [T; 16]) {
    network!(a; (0, 1), (2, 3), (4, 5), (6, 7), (8, 9), (10, 11), (12, 13), (14, 15),
        (0, 2), (1, 3), (4, 6), (5, 7), (8, 10), (9, 11), (12, 14), (13, 15), (1, 2), (5, 6),
        (9, 10), (13, 14), (0, 4), (1, 5), (2, 6), (3, 7), (8, 12), (9, 13), (10, 14), (11, 15),
        (2, 4), (3, 5), (10, 12), (11, 13), (1, 2), (3, 4), (5, 6), (9, 10), (11, 12), (13, 14),
        (0, 8), (1, 9), (2, 10), (3, 11), (4, 12), (5, 13), (6, 14), (7, 15), (4, 8), (5, 9),
        (6, 10), (7, 11), (2, 4), (3, 5), (6, 8), (7, 9), (10, 12), (11, 13), (1, 2), (3, 4),
        (5, 6), (7, 8), (9, 10), (11, 12), (13, 14));
}

/// Sorts the first `n` of `row` (`N` long) without branches: the rest is set to `pad` (a
/// value no smaller than any of the `n`), then the sorting network `net` runs.
#[inline(always)]
pub(crate) fn sort_padded<T: Ord + Copy, const N: usize>(
    row: &mut [T],
    n: usize,
    pad: T,
    net: impl Fn(&mut [T; N]),
) {
    let mut a = [pad; N];
    for (k, x) in a.iter_mut().enumerate() {
        *x = if k < n { row[k] } else { pad };
    }
    net(&mut a);
    row[..N].copy_from_slice(&a);
}

/// Sorts the first `n` values of `row`, whose length is a capacity of at least 16: up to 16
/// of them by a network padded in place with `pad` (no smaller than any of them; the padding
/// is left there), more by the standard sort.
#[inline(always)]
pub(crate) fn sort_in_capacity<T: Ord + Copy>(row: &mut [T], n: usize, pad: T) {
    match n {
        0..=8 => sort_padded::<T, 8>(&mut row[..8], n, pad, net8),
        9..=16 => sort_padded::<T, 16>(&mut row[..16], n, pad, net16),
        _ => row[..n].sort_unstable(),
    }
}

/// Sorts `v`: up to 16 values by a network on a copy padded with `pad` (no smaller than any
/// of them), longer ones by the standard sort.
#[inline]
pub(crate) fn sort_short<T: Ord + Copy>(v: &mut [T], pad: T) {
    fn via<T: Ord + Copy, const N: usize>(v: &mut [T], pad: T, net: impl Fn(&mut [T; N])) {
        let mut a = [pad; N];
        for (k, x) in a.iter_mut().enumerate() {
            *x = v.get(k).copied().unwrap_or(pad);
        }
        net(&mut a);
        v.copy_from_slice(&a[..v.len()]);
    }
    match v.len() {
        0 | 1 => {}
        2..=8 => via::<T, 8>(v, pad, net8),
        9..=16 => via::<T, 16>(v, pad, net16),
        _ => v.sort_unstable(),
    }
}

#[cfg(test)]
mod tests {
    /// The networks sort every 0-1 input (so every input, by the 0-1 principle), and the
    /// in-capacity and short sorts sort every length.
    #[test]
    fn sorting_networks_sort() {
        for m in 0u32..1 << 16 {
            let mut a: [u32; 16] = std::array::from_fn(|t| (m >> t) & 1);
            let mut want = a;
            want.sort_unstable();
            super::net16(&mut a);
            assert_eq!(a, want, "16: {m:b}");
            if m < 1 << 8 {
                let mut b: [u32; 8] = std::array::from_fn(|t| (m >> t) & 1);
                let mut want = b;
                want.sort_unstable();
                super::net8(&mut b);
                assert_eq!(b, want, "8: {m:b}");
            }
        }
        let mut rng = crate::testkit::XorShift::new(7);
        for n in 0..=40 {
            let mut row: Vec<u32> = (0..40).map(|_| rng.below(50) as u32).collect();
            let mut want = row[..n].to_vec();
            want.sort_unstable();
            let mut short: Vec<u64> = row[..n].iter().map(|&x| (x as u64) << 33).collect();
            super::sort_short(&mut short, u64::MAX);
            let back: Vec<u32> = short.iter().map(|&x| (x >> 33) as u32).collect();
            assert_eq!(back, want, "short, n = {n}");
            super::sort_in_capacity(&mut row, n, u32::MAX);
            assert_eq!(&row[..n], want.as_slice(), "in capacity, n = {n}");
        }
    }
}
