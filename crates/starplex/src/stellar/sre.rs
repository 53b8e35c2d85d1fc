//! Sequential Range Encoding (SRE) of sorted `u32` id lists.
//!
//! A run of at least three consecutive ids `a, a+1, .., a+r` is stored as two words:
//! `a | RUN_FLAG` (the "negated start" of the paper, here the high bit) followed by `r`, the
//! number of remaining elements. Every other id is stored as itself. Ids must be below
//! [`RUN_FLAG`] (2^31).
//!
//! ```
//! use starplex::stellar::sre::{encode, decode, RUN_FLAG};
//! let ids = [1, 2, 3, 4, 7, 9, 10];
//! let mut enc = Vec::new();
//! encode(&ids, &mut enc);
//! assert_eq!(enc, vec![1 | RUN_FLAG, 3, 7, 9, 10]);
//! let mut back = Vec::new();
//! decode(&enc, &mut back);
//! assert_eq!(back, ids);
//! ```

/// High bit marking the start of a run.
///
/// ```
/// use starplex::stellar::sre::{encode, RUN_FLAG};
/// let mut enc = Vec::new();
/// encode(&[5, 6, 7, 8], &mut enc);
/// assert_eq!(enc, vec![5 | RUN_FLAG, 3]); // flagged start, then 3 more ids
/// assert_eq!(enc[0] & !RUN_FLAG, 5);
/// ```
pub const RUN_FLAG: u32 = 1 << 31;

/// Shortest run that is encoded as a pair.
///
/// ```
/// use starplex::stellar::sre::{encode, MIN_RUN, RUN_FLAG};
/// assert_eq!(MIN_RUN, 3);
/// let mut enc = Vec::new();
/// encode(&[1, 2, 10, 11, 12], &mut enc); // a pair stays plain, a triple is a run
/// assert_eq!(enc, vec![1, 2, 10 | RUN_FLAG, 2]);
/// ```
pub const MIN_RUN: u32 = 3;

/// Appends the SRE encoding of the strictly increasing list `sorted` to `out`.
///
/// ```
/// use starplex::stellar::sre::{encode, RUN_FLAG};
/// let mut enc = vec![42]; // appends
/// encode(&[0, 1, 2, 3, 4, 9], &mut enc);
/// assert_eq!(enc, vec![42, RUN_FLAG, 4, 9]);
/// ```
pub fn encode(sorted: &[u32], out: &mut Vec<u32>) {
    let mut i = 0;
    while i < sorted.len() {
        let start = sorted[i];
        let mut j = i + 1;
        while j < sorted.len() && sorted[j] == sorted[j - 1] + 1 {
            j += 1;
        }
        push_run(start, (j - i) as u32, out);
        i = j;
    }
}

/// Appends a run of `len >= 1` consecutive ids starting at `start`.
///
/// ```
/// use starplex::stellar::sre::{push_run, decode, RUN_FLAG};
/// let mut enc = Vec::new();
/// push_run(3, 2, &mut enc); // short: stored as ids
/// push_run(7, 4, &mut enc); // 7..=10: stored as a pair
/// assert_eq!(enc, vec![3, 4, 7 | RUN_FLAG, 3]);
/// let mut ids = Vec::new();
/// decode(&enc, &mut ids);
/// assert_eq!(ids, vec![3, 4, 7, 8, 9, 10]);
/// ```
#[inline]
pub fn push_run(start: u32, len: u32, out: &mut Vec<u32>) {
    debug_assert!(start < RUN_FLAG && len >= 1);
    if len >= MIN_RUN {
        out.push(start | RUN_FLAG);
        out.push(len - 1);
    } else {
        out.extend(start..start + len);
    }
}

/// Number of words a run of `len` ids takes.
///
/// ```
/// use starplex::stellar::sre::{push_run, run_cost};
/// assert_eq!((run_cost(1), run_cost(2), run_cost(3), run_cost(1000)), (1, 2, 2, 2));
/// let mut enc = Vec::new();
/// push_run(0, 1000, &mut enc);
/// assert_eq!(enc.len() as u32, run_cost(1000));
/// ```
#[inline]
pub fn run_cost(len: u32) -> u32 {
    if len >= MIN_RUN {
        2
    } else {
        len
    }
}

/// Appends the decoded ids of `enc` to `out`.
///
/// ```
/// use starplex::stellar::sre::{decode, RUN_FLAG};
/// let mut ids = vec![0]; // appends
/// decode(&[2, 5 | RUN_FLAG, 2, 9], &mut ids);
/// assert_eq!(ids, vec![0, 2, 5, 6, 7, 9]);
/// ```
pub fn decode(enc: &[u32], out: &mut Vec<u32>) {
    let mut i = 0;
    while i < enc.len() {
        let x = enc[i];
        if x & RUN_FLAG != 0 {
            let s = x & !RUN_FLAG;
            let r = enc[i + 1];
            out.extend(s..=s + r);
            i += 2;
        } else {
            out.push(x);
            i += 1;
        }
    }
}

/// Number of ids `enc` decodes to.
///
/// ```
/// use starplex::stellar::sre::{decoded_len, RUN_FLAG};
/// assert_eq!(decoded_len(&[5 | RUN_FLAG, 9, 20]), 11);
/// ```
pub fn decoded_len(enc: &[u32]) -> usize {
    let mut n = 0usize;
    let mut i = 0;
    while i < enc.len() {
        if enc[i] & RUN_FLAG != 0 {
            n += enc[i + 1] as usize + 1;
            i += 2;
        } else {
            n += 1;
            i += 1;
        }
    }
    n
}

/// Iterator over the ids of an SRE-encoded list.
///
/// ```
/// use starplex::stellar::sre::{SreIter, RUN_FLAG};
/// let v: Vec<u32> = SreIter::new(&[2, 4 | RUN_FLAG, 2]).collect();
/// assert_eq!(v, vec![2, 4, 5, 6]);
/// ```
#[derive(Clone, Debug)]
pub struct SreIter<'a> {
    enc: &'a [u32],
    pos: usize,
    cur: u32,
    left: u32,
}

impl<'a> SreIter<'a> {
    /// Iterates over `enc`.
    ///
    /// ```
    /// use starplex::stellar::sre::{SreIter, RUN_FLAG};
    /// assert_eq!(SreIter::new(&[]).count(), 0);
    /// assert_eq!(SreIter::new(&[RUN_FLAG, 4]).sum::<u32>(), 0 + 1 + 2 + 3 + 4);
    /// ```
    pub fn new(enc: &'a [u32]) -> Self {
        SreIter {
            enc,
            pos: 0,
            cur: 0,
            left: 0,
        }
    }
}

impl Iterator for SreIter<'_> {
    type Item = u32;
    #[inline]
    fn next(&mut self) -> Option<u32> {
        if self.left > 0 {
            self.left -= 1;
            self.cur += 1;
            return Some(self.cur);
        }
        let x = *self.enc.get(self.pos)?;
        if x & RUN_FLAG != 0 {
            self.cur = x & !RUN_FLAG;
            self.left = self.enc[self.pos + 1];
            self.pos += 2;
        } else {
            self.cur = x;
            self.pos += 1;
        }
        Some(self.cur)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trips() {
        let cases: Vec<Vec<u32>> = vec![
            vec![],
            vec![0],
            vec![0, 1],
            vec![0, 1, 2],
            vec![5, 6, 8, 9, 10, 11, 20],
            (100..1000).collect(),
            vec![RUN_FLAG - 3, RUN_FLAG - 2, RUN_FLAG - 1],
        ];
        for c in cases {
            let mut e = Vec::new();
            encode(&c, &mut e);
            let mut d = Vec::new();
            decode(&e, &mut d);
            assert_eq!(d, c);
            assert_eq!(decoded_len(&e), c.len());
            assert_eq!(SreIter::new(&e).collect::<Vec<_>>(), c);
        }
    }
}
