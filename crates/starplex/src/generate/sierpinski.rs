//! Probabilistic Sierpinski filtering of the standard d-simplex, as the datasets' generator
//! (`shared/datasets/gen.py`, `sierpinski`) builds it, random stream included: numpy's
//! `default_rng(seed)` (SeedSequence → PCG64, XSL-RR 128/64), `random()` doubles
//! (`(next_u64 >> 11) · 2^-53`) and, when a level would keep no child, `integers(n)` (Lemire's
//! bounded method on the 32-bit half-words of PCG64). The same parameters give the same
//! vertices, coordinates and cells, in the same order.
//!
//! Each level replaces every d-simplex by its d+1 corner children (corner i keeps vertex i and
//! takes the midpoints of the edges at i), keeps each child with probability p, and renumbers the
//! used vertices in increasing order of their previous ids (midpoints appended in the order of
//! their sorted endpoint pairs), until at least `target` simplices remain.
//!
//! ```
//! use starplex::generate::sierpinski::{sierpinski, SierpinskiOptions};
//! let s = sierpinski(&SierpinskiOptions { dim: 2, p: 0.35, seed: 1, target: 10, max_levels: 60 }).unwrap();
//! assert!(s.complex.n_cells() >= 10);
//! assert_eq!(s.complex.ambient_dim(), 2);
//! ```
use crate::cell::CellKind;
use crate::complex::{ComplexError, IndexedComplex};

/// numpy's `SeedSequence(seed).generate_state(4, uint64)` for a non-negative integer seed.
fn seed_sequence_state(seed: u64) -> [u64; 4] {
    const INIT_A: u32 = 0x43b0_d7e5;
    const MULT_A: u32 = 0x931e_8875;
    const INIT_B: u32 = 0x8b51_f9dd;
    const MULT_B: u32 = 0x58f3_8ded;
    const MIX_MULT_L: u32 = 0xca01_f9dd;
    const MIX_MULT_R: u32 = 0x4973_f715;
    // the seed as little-endian 32-bit words (at least one)
    let mut entropy = vec![seed as u32];
    if seed >> 32 != 0 {
        entropy.push((seed >> 32) as u32);
    }
    let mut hc = INIT_A;
    let mut hashmix = |v: u32| -> u32 {
        let mut v = v ^ hc;
        hc = hc.wrapping_mul(MULT_A);
        v = v.wrapping_mul(hc);
        v ^ (v >> 16)
    };
    let mix = |x: u32, y: u32| -> u32 {
        let r = MIX_MULT_L
            .wrapping_mul(x)
            .wrapping_sub(MIX_MULT_R.wrapping_mul(y));
        r ^ (r >> 16)
    };
    let mut pool = [0u32; 4];
    for (i, p) in pool.iter_mut().enumerate() {
        *p = hashmix(entropy.get(i).copied().unwrap_or(0));
    }
    for src in 0..4 {
        for dst in 0..4 {
            if src != dst {
                let h = hashmix(pool[src]);
                pool[dst] = mix(pool[dst], h);
            }
        }
    }
    for &e in entropy.iter().skip(4) {
        for slot in pool.iter_mut() {
            let h = hashmix(e);
            *slot = mix(*slot, h);
        }
    }
    let mut hb = INIT_B;
    let mut words = [0u32; 8];
    for (i, w) in words.iter_mut().enumerate() {
        let mut v = pool[i % 4] ^ hb;
        hb = hb.wrapping_mul(MULT_B);
        v = v.wrapping_mul(hb);
        *w = v ^ (v >> 16);
    }
    let mut out = [0u64; 4];
    for i in 0..4 {
        out[i] = words[2 * i] as u64 | (words[2 * i + 1] as u64) << 32;
    }
    out
}

/// numpy's `PCG64` bit generator (with its 32-bit half-word buffer).
///
/// ```
/// use starplex::generate::sierpinski::NumpyPcg64;
/// let mut r = NumpyPcg64::new(1);
/// let x = r.random();
/// assert!((0.0..1.0).contains(&x));
/// ```
#[derive(Clone, Debug)]
pub struct NumpyPcg64 {
    state: u128,
    inc: u128,
    half: Option<u32>,
}

const PCG_MULT: u128 = (2549297995355413924u128 << 64) + 4865540595714422341u128;

impl NumpyPcg64 {
    /// `numpy.random.default_rng(seed)`'s generator.
    ///
    /// ```
    /// # use starplex::generate::sierpinski::NumpyPcg64;
    /// assert_eq!(NumpyPcg64::new(5).next_u64(), NumpyPcg64::new(5).next_u64());
    /// ```
    pub fn new(seed: u64) -> NumpyPcg64 {
        let s = seed_sequence_state(seed);
        let initstate = (s[0] as u128) << 64 | s[1] as u128;
        let initseq = (s[2] as u128) << 64 | s[3] as u128;
        let mut r = NumpyPcg64 {
            state: 0,
            inc: (initseq << 1) | 1,
            half: None,
        };
        r.step();
        r.state = r.state.wrapping_add(initstate);
        r.step();
        r
    }

    fn step(&mut self) {
        self.state = self.state.wrapping_mul(PCG_MULT).wrapping_add(self.inc);
    }

    /// The next 64-bit output.
    ///
    /// ```
    /// # use starplex::generate::sierpinski::NumpyPcg64;
    /// let mut r = NumpyPcg64::new(0);
    /// assert_ne!(r.next_u64(), r.next_u64());
    /// ```
    pub fn next_u64(&mut self) -> u64 {
        self.step();
        let s = self.state;
        let x = ((s >> 64) as u64) ^ (s as u64);
        x.rotate_right((s >> 122) as u32)
    }

    /// The next 32-bit output (low half of a 64-bit one, then its high half).
    ///
    /// ```
    /// # use starplex::generate::sierpinski::NumpyPcg64;
    /// let (mut a, mut b) = (NumpyPcg64::new(2), NumpyPcg64::new(2));
    /// let w = a.next_u64();
    /// assert_eq!((b.next_u32(), b.next_u32()), (w as u32, (w >> 32) as u32));
    /// ```
    pub fn next_u32(&mut self) -> u32 {
        if let Some(h) = self.half.take() {
            return h;
        }
        let w = self.next_u64();
        self.half = Some((w >> 32) as u32);
        w as u32
    }

    /// `Generator.random()`: a double in [0, 1).
    ///
    /// ```
    /// # use starplex::generate::sierpinski::NumpyPcg64;
    /// assert!(NumpyPcg64::new(3).random() < 1.0);
    /// ```
    pub fn random(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / 9007199254740992.0)
    }

    /// `Generator.integers(n)` for `1 <= n <= 2^32` (Lemire's bounded method on 32-bit words).
    ///
    /// ```
    /// # use starplex::generate::sierpinski::NumpyPcg64;
    /// assert!(NumpyPcg64::new(4).integers(6) < 6);
    /// ```
    pub fn integers(&mut self, n: u64) -> u64 {
        debug_assert!((1..=1 << 32).contains(&n));
        let rng = n - 1;
        if rng == 0 {
            return 0;
        }
        if rng == u32::MAX as u64 {
            return self.next_u32() as u64;
        }
        let excl = n;
        let mut m = self.next_u32() as u64 * excl;
        let mut left = m & 0xFFFF_FFFF;
        if left < excl {
            let threshold = (u32::MAX as u64 - rng) % excl;
            while left < threshold {
                m = self.next_u32() as u64 * excl;
                left = m & 0xFFFF_FFFF;
            }
        }
        m >> 32
    }
}

/// Parameters of [`sierpinski`] (the datasets' recipe keys).
///
/// ```
/// use starplex::generate::sierpinski::SierpinskiOptions;
/// let o = SierpinskiOptions::default();
/// assert_eq!((o.p, o.seed, o.max_levels), (0.35, 1, 60));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SierpinskiOptions {
    /// Dimension of the simplex (and of the ambient space).
    pub dim: usize,
    /// Probability of keeping each child.
    pub p: f64,
    /// numpy seed.
    pub seed: u64,
    /// Stop once at least this many simplices remain.
    pub target: usize,
    /// Stop after this many levels in any case.
    pub max_levels: usize,
}

impl Default for SierpinskiOptions {
    fn default() -> Self {
        SierpinskiOptions {
            dim: 3,
            p: 0.35,
            seed: 1,
            target: 1000,
            max_levels: 60,
        }
    }
}

/// The generated complex and the number of levels run.
#[derive(Clone, Debug)]
pub struct Sierpinski {
    /// Vertices and d-simplices, in the generator's order.
    pub complex: IndexedComplex,
    /// Levels of subdivision.
    pub levels: usize,
}

/// The probabilistic Sierpinski filtering (see the module docs).
///
/// ```
/// use starplex::generate::sierpinski::{sierpinski, SierpinskiOptions};
/// let o = SierpinskiOptions { dim: 3, target: 50, ..Default::default() };
/// let s = sierpinski(&o).unwrap();
/// assert!(s.complex.n_cells() >= 50 && s.levels > 1);
/// assert!(sierpinski(&SierpinskiOptions { dim: 0, ..o }).is_err());
/// ```
///
/// # Errors
/// A dimension outside 1..=64 ([`ComplexError::BadAmbientDim`]); an output over 32-bit ids
/// ([`ComplexError::TooLarge`]).
pub fn sierpinski(o: &SierpinskiOptions) -> Result<Sierpinski, ComplexError> {
    let d = o.dim;
    let kind = CellKind::simplex(d).ok_or(ComplexError::BadAmbientDim(d))?;
    if d == 0 {
        return Err(ComplexError::BadAmbientDim(d));
    }
    let n = d + 1;
    let mut rng = NumpyPcg64::new(o.seed);
    // vertices: the origin and the unit vectors
    let mut v: Vec<f64> = vec![0.0; d];
    for i in 0..d {
        v.extend((0..d).map(|j| if i == j { 1.0 } else { 0.0 }));
    }
    let mut s: Vec<u32> = (0..n as u32).collect();
    let pairs: Vec<(usize, usize)> = (0..n)
        .flat_map(|i| (i + 1..n).map(move |j| (i, j)))
        .collect();
    let pidx = |i: usize, j: usize| -> usize {
        let (a, b) = (i.min(j), i.max(j));
        // position of (a, b) in the row-major list of pairs
        a * n - a * (a + 1) / 2 + (b - a - 1)
    };
    let mut level = 0;
    while s.len() / n < o.target && level < o.max_levels {
        let m = s.len() / n;
        let children = m as u128 * n as u128;
        if children * n as u128 >= u32::MAX as u128 {
            return Err(ComplexError::TooLarge(crate::limits::TooLarge::ids(
                "cells", children,
            )));
        }
        // every (sorted) edge of every simplex, then np.unique's sorted order
        let mut e: Vec<(u32, u32)> = Vec::with_capacity(m * pairs.len());
        for c in s.chunks_exact(n) {
            for &(i, j) in &pairs {
                let (a, b) = (c[i].min(c[j]), c[i].max(c[j]));
                e.push((a, b));
            }
        }
        let mut u = e.clone();
        u.sort_unstable();
        u.dedup();
        let nv = v.len() / d;
        for &(a, b) in &u {
            for k in 0..d {
                let x = 0.5 * (v[a as usize * d + k] + v[b as usize * d + k]);
                v.push(x);
            }
        }
        let mid =
            |k: usize| -> u32 { (nv + u.binary_search(&e[k]).expect("edge is listed")) as u32 };
        let mut kids: Vec<u32> = Vec::with_capacity(m * n * n);
        for (ci, c) in s.chunks_exact(n).enumerate() {
            for (i, &corner) in c.iter().enumerate() {
                for j in 0..n {
                    kids.push(if j == i {
                        corner
                    } else {
                        mid(ci * pairs.len() + pidx(i, j))
                    });
                }
            }
        }
        let nk = m * n;
        let mut keep: Vec<bool> = (0..nk).map(|_| rng.random() < o.p).collect();
        if !keep.iter().any(|&k| k) {
            keep[rng.integers(nk as u64) as usize] = true;
        }
        let mut s2 = Vec::new();
        for (k, c) in kids.chunks_exact(n).enumerate() {
            if keep[k] {
                s2.extend_from_slice(c);
            }
        }
        // renumber the used vertices in increasing order
        let total = v.len() / d;
        let mut used = vec![u32::MAX; total];
        for &x in &s2 {
            used[x as usize] = 0;
        }
        let mut v2 = Vec::new();
        let mut next = 0u32;
        for (i, slot) in used.iter_mut().enumerate() {
            if *slot == 0 {
                *slot = next;
                next += 1;
                v2.extend_from_slice(&v[i * d..(i + 1) * d]);
            }
        }
        for x in &mut s2 {
            *x = used[*x as usize];
        }
        v = v2;
        s = s2;
        level += 1;
    }
    let complex = IndexedComplex::from_parts(d, v.into(), vec![(kind, s.into())])?;
    Ok(Sierpinski {
        complex,
        levels: level,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Values printed by numpy 2.4 (`default_rng(seed).bit_generator.random_raw`, `.random`,
    /// `.integers`).
    #[test]
    fn the_stream_is_numpys() {
        let mut r = NumpyPcg64::new(1);
        let raw: Vec<u64> = (0..3).map(|_| r.next_u64()).collect();
        assert_eq!(
            raw,
            [
                9441442522235856127,
                17532960557476522086,
                2659275481604167885
            ]
        );
        let mut r = NumpyPcg64::new(3);
        assert_eq!(
            (r.random(), r.random()),
            (0.08564916714362436, 0.2368105065960997)
        );
        assert_eq!((r.integers(6), r.integers(1000)), (1, 801));
        assert_eq!(r.random(), 0.5821620360643678);
        assert_eq!(r.integers(7), 0);
        let mut r = NumpyPcg64::new((1 << 40) + 5);
        assert_eq!(
            (r.next_u64(), r.next_u64()),
            (87427594128977387, 6872972437549564694)
        );
    }

    #[test]
    fn probabilities_outside_the_unit_interval_keep_all_or_one() {
        let all = sierpinski(&SierpinskiOptions {
            dim: 2,
            p: 1.0,
            target: 9,
            ..Default::default()
        })
        .unwrap();
        assert_eq!((all.complex.n_cells(), all.levels), (9, 2));
        let one = sierpinski(&SierpinskiOptions {
            dim: 2,
            p: 0.0,
            target: 2,
            max_levels: 5,
            ..Default::default()
        })
        .unwrap();
        assert_eq!((one.complex.n_cells(), one.levels), (1, 5));
    }
}
