//! Consistent orientation of the top cells, written once: every structure (and the Stellar tree's
//! leaf-parallel validation) supplies the pairs of top cells that share a facet with the product
//! of the orientations they induce on it, and [`orient_tops`] propagates.
//!
//! The answer is canonical, whatever order the pairs come in: each component of top cells
//! (connected through shared facets) keeps the orientation of its smallest cell id (which fixes
//! every sign of an orientable component), and when a conflict exists the one reported is the
//! first met by a depth-first walk from those cells with every cell's neighbours in increasing
//! id order.
//!
//! ```
//! use starplex::algo::orientation::{orient_tops, Orientation};
//! use starplex::ids::CellId;
//! // a strip of three triangles; cell 1 induces the same orientation as its neighbours on the
//! // shared edges (+1), so it must be flipped
//! let pairs = [(0, 1, 1), (1, 2, 1)];
//! let o = orient_tops(3, |_| true, &pairs);
//! assert_eq!(o, Orientation::Orientable { flips: vec![CellId(1)] });
//! // a Möbius-like cycle: the signs cannot agree
//! let pairs = [(0, 1, -1), (1, 2, -1), (0, 2, 1)];
//! assert!(matches!(orient_tops(3, |_| true, &pairs), Orientation::NonOrientable { .. }));
//! ```
use crate::algo::unionfind::UnionFind;
use crate::csr::Csr;
use crate::ids::CellId;

/// The result of [`orient_tops`].
///
/// ```
/// use starplex::algo::orientation::{orient_tops, Orientation};
/// assert_eq!(orient_tops(2, |_| true, &[]), Orientation::Orientable { flips: vec![] });
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Orientation {
    /// The top cells to reverse (sorted) for a consistent orientation.
    Orientable {
        /// Cells to flip.
        flips: Vec<CellId>,
    },
    /// Two adjacent cells (smaller id first) whose orientations cannot agree.
    NonOrientable {
        /// The pair where the walk found the conflict.
        conflict: (CellId, CellId),
    },
}

/// The full result of an orientation walk: a sign per cell (0 for cells that are not tops),
/// the first conflict met, and the number of components walked.
///
/// ```
/// use starplex::algo::orientation::orient_walk;
/// let w = orient_walk(3, |_| true, &[(0, 1, 1)], |_| 1);
/// assert_eq!(w.signs, [1, -1, 1]);
/// assert_eq!((w.conflict, w.n_components), (None, 2));
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Walk {
    /// +1 or -1 per top cell, relative to the cell's listed orientation; 0 for other cells.
    pub signs: Vec<i8>,
    /// The first pair whose orientations could not agree (smaller id first).
    pub conflict: Option<(CellId, CellId)>,
    /// Components of top cells through the pairs.
    pub n_components: usize,
}

/// The walk behind [`orient_tops`], for callers that want every sign even when the complex is
/// not orientable: each component starts from its smallest cell `s` with sign `seed(s)` (+1
/// when `seed` returns 0) and the walk goes on past a conflict.
///
/// ```
/// use starplex::algo::orientation::orient_walk;
/// // start the component from -1: every sign flips with it
/// let w = orient_walk(2, |_| true, &[(0, 1, -1)], |_| -1);
/// assert_eq!(w.signs, [-1, -1]);
/// ```
pub fn orient_walk(
    n_cells: usize,
    is_top: impl Fn(u32) -> bool,
    pairs: &[(u32, u32, i8)],
    seed: impl Fn(u32) -> i8,
) -> Walk {
    let keep = |&&(a, b, _): &&(u32, u32, i8)| is_top(a) && is_top(b);
    let mut adj = Csr::from_fn(n_cells, |emit| {
        for (i, p) in pairs.iter().enumerate() {
            if keep(&p) {
                emit(p.0, i as u32);
                emit(p.1, i as u32);
            }
        }
    });
    let other = |a: u32, i: u32| {
        let (x, y, rel) = pairs[i as usize];
        (if x == a { y } else { x }, rel)
    };
    let mut w = walk(n_cells, &is_top, &adj, &other, &seed);
    if w.conflict.is_some() {
        // The signs of an orientable component do not depend on the walk order (its smallest
        // cell keeps its seed), but which conflict is met first does: walk again with every
        // row in increasing neighbour order, so the answer does not depend on the order the
        // pairs were found in.
        for a in 0..n_cells {
            let (lo, hi) = (adj.offsets[a] as usize, adj.offsets[a + 1] as usize);
            adj.targets[lo..hi].sort_unstable_by_key(|&i| other(a as u32, i));
        }
        w = walk(n_cells, &is_top, &adj, &other, &seed);
    }
    w
}

fn walk(
    n_cells: usize,
    is_top: &impl Fn(u32) -> bool,
    adj: &Csr,
    other: &impl Fn(u32, u32) -> (u32, i8),
    seed: &impl Fn(u32) -> i8,
) -> Walk {
    let mut w = Walk {
        signs: vec![0i8; n_cells],
        conflict: None,
        n_components: 0,
    };
    let o = &mut w.signs;
    let mut stack = Vec::new();
    for s in 0..n_cells as u32 {
        if o[s as usize] != 0 || !is_top(s) {
            continue;
        }
        w.n_components += 1;
        o[s as usize] = if seed(s) < 0 { -1 } else { 1 };
        stack.push(s);
        while let Some(a) = stack.pop() {
            for &pi in adj.row(a as usize) {
                let (b, rel) = other(a, pi);
                let want = -o[a as usize] * rel;
                if o[b as usize] == 0 {
                    o[b as usize] = want;
                    stack.push(b);
                } else if o[b as usize] != want && w.conflict.is_none() {
                    w.conflict = Some((CellId(a.min(b)), CellId(a.max(b))));
                }
            }
        }
    }
    w
}

/// Orients the cells `c < n_cells` with `is_top(c)` given `pairs` `(a, b, rel)`: `a` and `b`
/// share a facet and `rel` is the product of the orientations they induce on it (+1: they
/// induce the same one, so as they stand they are inconsistently oriented). Pairs whose cells
/// are not tops are ignored.
///
/// ```
/// use starplex::algo::orientation::{orient_tops, Orientation};
/// use starplex::ids::CellId;
/// // two components: {0, 1} consistent, {2, 3} not; cell 4 is not a top
/// let o = orient_tops(5, |c| c < 4, &[(1, 0, -1), (3, 2, 1), (3, 4, 1)]);
/// assert_eq!(o, Orientation::Orientable { flips: vec![CellId(3)] });
/// ```
pub fn orient_tops(
    n_cells: usize,
    is_top: impl Fn(u32) -> bool,
    pairs: &[(u32, u32, i8)],
) -> Orientation {
    orient_walk(n_cells, is_top, pairs, |_| 1).orientation()
}

/// [`orient_tops`] for pairs numbered in a working order other than the answer's: `to_out`
/// maps each working id to its answer id (a permutation of `0..n_cells`), and `is_top` and
/// `pairs` use working ids. Returns the answer [`orient_tops`] gives on the pairs renumbered
/// by `to_out`, and the number of components of top cells through the pairs.
///
/// Why: the depth-first walk reads each cell's neighbours at random. In an order where
/// neighbours are near each other (the Stellar tree's, leaf by leaf) the work stays in cache;
/// in input order it may miss on every step (95 ms of 360 on an 832,000-triangle mesh). Here
/// the signs are found by a union-find whose links carry the parity between a cell and its
/// parent, reading the pairs once in the working order (no adjacency built, no walk); then
/// each component takes the sign of its smallest answer id, which gives the same signs as
/// the walk in answer ids. When a conflict is met, which conflict is reported depends on the
/// order, so the pairs are renumbered and walked again by [`orient_walk`].
///
/// ```
/// use starplex::algo::orientation::{orient_tops, orient_tops_renumbered};
/// // a strip of three triangles, numbered backwards in the working order
/// let to_out = [2, 1, 0];
/// let pairs = [(2, 1, 1), (1, 0, 1)];
/// let out: Vec<_> = pairs.iter().map(|&(a, b, r)| (to_out[a as usize], to_out[b as usize], r)).collect();
/// let (o, n_components) = orient_tops_renumbered(3, |_| true, &pairs, &to_out);
/// assert_eq!(o, orient_tops(3, |_| true, &out));
/// assert_eq!(n_components, 1);
/// ```
pub fn orient_tops_renumbered(
    n_cells: usize,
    is_top: impl Fn(u32) -> bool + Sync,
    pairs: &[(u32, u32, i8)],
    to_out: &[u32],
) -> (Orientation, usize) {
    let (o, n, _) = orient_renumbered_joined(n_cells, is_top, pairs, to_out, &[]);
    (o, n)
}

/// [`orient_tops_renumbered`], and also the number of components of the top cells once the
/// cells of each of `joins` (working ids, both tops) are joined too: with the cells at every
/// vertex whose star is not connected through facets joined, these are the components of the
/// vertices through the cells (the validation's), found without a union-find over the
/// vertices.
pub(crate) fn orient_renumbered_joined(
    n_cells: usize,
    is_top: impl Fn(u32) -> bool + Sync,
    pairs: &[(u32, u32, i8)],
    to_out: &[u32],
    joins: &[(u32, u32)],
) -> (Orientation, usize, usize) {
    orient_parts_joined(n_cells, is_top, &PairParts::one(pairs), to_out, joins)
}

/// Facet pairs `(a, b, rel)` in pieces (a Stellar tree's: one per leaf, as its leaves found
/// them, not copied into one array), the pieces grouped into consecutive *parts*, each with a
/// range of cells: part `j` is pieces `parts[j].0..parts[j + 1].0` (the last to the end) and
/// cells `parts[j].1..parts[j + 1].1` (the last to `n_cells`). The answers never depend on
/// the grouping; a part's pairs whose two cells lie in its range are united on their own,
/// on all threads, so a grouping where most pairs do is faster.
pub(crate) struct PairParts<'a> {
    pub(crate) pieces: Vec<&'a [(u32, u32, i8)]>,
    pub(crate) parts: Vec<(usize, u32)>,
}

impl<'a> PairParts<'a> {
    /// All pairs in one piece and one part.
    pub(crate) fn one(pairs: &'a [(u32, u32, i8)]) -> PairParts<'a> {
        PairParts {
            pieces: vec![pairs],
            parts: vec![(0, 0)],
        }
    }

    /// Every pair, piece after piece.
    pub(crate) fn iter(&self) -> impl Iterator<Item = &(u32, u32, i8)> + '_ {
        self.pieces.iter().flat_map(|p| p.iter())
    }

    /// The pairs in one slice (borrowed when there is one piece).
    pub(crate) fn flat(&self) -> std::borrow::Cow<'a, [(u32, u32, i8)]> {
        match self.pieces[..] {
            [p] => std::borrow::Cow::Borrowed(p),
            _ => std::borrow::Cow::Owned(self.iter().copied().collect()),
        }
    }
}

/// Links `a` and `b` with parity `want` between them in a parity union-find by rank; false
/// on a conflict (they are linked already, with the other parity).
#[inline(always)]
fn unite_parity(link: &mut [u32], rank: &mut [u8], a: u32, b: u32, want: u32) -> bool {
    let ((ra, pa), (rb, pb)) = (parity_find(link, a), parity_find(link, b));
    let p = pa ^ pb ^ want;
    if ra == rb {
        return p == 0;
    }
    let (hi, lo) = if rank[ra as usize] < rank[rb as usize] {
        (rb, ra)
    } else {
        (ra, rb)
    };
    link[lo as usize] = (hi << 1) | p;
    if rank[ra as usize] == rank[rb as usize] {
        rank[hi as usize] += 1;
    }
    true
}

/// [`orient_renumbered_joined`] on pairs in parts ([`PairParts`]).
pub(crate) fn orient_parts_joined(
    n_cells: usize,
    is_top: impl Fn(u32) -> bool + Sync,
    pairs: &PairParts<'_>,
    to_out: &[u32],
    joins: &[(u32, u32)],
) -> (Orientation, usize, usize) {
    use rayon::prelude::*;
    assert_eq!(to_out.len(), n_cells, "to_out maps every cell");
    let canonical = || {
        let pairs = pairs.flat();
        let out: Vec<(u32, u32, i8)> = pairs
            .iter()
            .map(|&(a, b, r)| (to_out[a as usize], to_out[b as usize], r))
            .collect();
        let mut top = vec![false; n_cells];
        for c in 0..n_cells as u32 {
            top[to_out[c as usize] as usize] = is_top(c);
        }
        let w = orient_walk(n_cells, |c| top[c as usize], &out, |_| 1);
        // the count does not depend on the numbering: in working ids
        let joined = joined_components(n_cells, &is_top, &pairs, joins, w.n_components);
        (w.orientation(), w.n_components, joined)
    };
    if n_cells >= 1 << 31 {
        return canonical();
    }
    // a union-find whose links carry the parity between a cell and its parent (1: opposite
    // signs): the pairs are read once, in the working order, with no adjacency built. Each
    // part first unites the pairs inside its range of cells, in parallel (its links stay in
    // its range); the others follow, in order. Which tree the links make depends on the
    // parts, the components and parities do not.
    let mut link = vec![0u32; n_cells];
    let mut rank = vec![0u8; n_cells];
    // (no part given: one part)
    let n_parts = pairs.parts.len().max(1);
    let bound = |j: usize| match pairs.parts.get(j) {
        Some(&(_, c)) => (c as usize).min(n_cells),
        None => n_cells,
    };
    let piece_end = |j: usize| pairs.parts.get(j).map_or(pairs.pieces.len(), |x| x.0);
    // the ranges, cut out of the link and rank arrays (increasing, clamped)
    let mut ranges = Vec::with_capacity(n_parts);
    let (mut lk, mut rk, mut at) = (&mut link[..], &mut rank[..], 0usize);
    for j in 0..n_parts {
        let end = bound(j + 1).max(at);
        let (l1, l2) = lk.split_at_mut(end - at);
        let (r1, r2) = rk.split_at_mut(end - at);
        ranges.push((j, at as u32, l1, r1));
        (lk, rk, at) = (l2, r2, end);
    }
    let rest: Option<Vec<Vec<(u32, u32, i8)>>> = ranges
        .into_par_iter()
        .map(|(j, base, link, rank)| {
            // in ids from `base` while in the range, then shifted to the whole's
            link.iter_mut().zip(0u32..).for_each(|(l, i)| *l = i << 1);
            let len = link.len() as u32;
            let mut others = Vec::new();
            let first = pairs.parts.get(j).map_or(0, |x| x.0);
            for piece in &pairs.pieces[first.min(piece_end(j + 1))..piece_end(j + 1)] {
                for &(a, b, rel) in piece.iter() {
                    if !(is_top(a) && is_top(b)) {
                        continue;
                    }
                    let (x, y) = (a.wrapping_sub(base), b.wrapping_sub(base));
                    if x < len && y < len {
                        // rel >= 0: as they stand the two induce the same orientation, so
                        // their signs differ
                        if !unite_parity(link, rank, x, y, u32::from(rel >= 0)) {
                            return None;
                        }
                    } else {
                        others.push((a, b, rel));
                    }
                }
            }
            link.iter_mut().for_each(|l| *l += base << 1);
            Some(others)
        })
        .collect();
    let Some(rest) = rest else {
        return canonical();
    };
    for &(a, b, rel) in rest.iter().flatten() {
        if !unite_parity(&mut link, &mut rank, a, b, u32::from(rel >= 0)) {
            return canonical();
        }
    }
    drop((rest, rank));
    // every top linked to its root directly (a root's parity to itself is 0), the roots found
    // on all threads reading the links only
    let roots: Vec<u32> = (0..n_cells as u32)
        .into_par_iter()
        .with_min_len(1 << 14)
        .map(|c| {
            if !is_top(c) {
                return link[c as usize];
            }
            let (mut x, mut par) = (c, 0);
            loop {
                let lx = link[x as usize];
                if lx >> 1 == x {
                    return (x << 1) | par;
                }
                par ^= lx & 1;
                x = lx >> 1;
            }
        })
        .collect();
    drop(link);
    let mut link = roots;
    // each component keeps the sign of its smallest answer id: per root, that id << 1 | its
    // parity to the root
    // (one sequential pass: the roots are known, no find left in it)
    let mut least = vec![u32::MAX; n_cells];
    let mut n_comp = 0usize;
    for (c, &l) in (0u32..).zip(&link) {
        if is_top(c) {
            let r = l >> 1;
            n_comp += usize::from(r == c);
            let x = (to_out[c as usize] << 1) | (l & 1);
            let m = &mut least[r as usize];
            *m = (*m).min(x);
        }
    }
    let mut flips: Vec<CellId> = (0..n_cells)
        .into_par_iter()
        .filter(|&c| is_top(c as u32))
        .filter(|&c| link[c] & 1 != least[(link[c] >> 1) as usize] & 1)
        .map(|c| CellId(to_out[c]))
        .collect();
    flips.par_sort_unstable();
    // the signs are read: the links now serve a plain union-find (their parities unused)
    let mut joined = n_comp;
    for &(a, b) in joins {
        let (ra, rb) = (parity_find(&mut link, a).0, parity_find(&mut link, b).0);
        if ra != rb {
            link[ra as usize] = rb << 1;
            joined -= 1;
        }
    }
    (Orientation::Orientable { flips }, n_comp, joined)
}

/// The cells' union-find through the `pairs` whose two cells are tops.
pub(crate) fn facet_union_find<'a>(
    n_cells: usize,
    is_top: impl Fn(u32) -> bool,
    pairs: impl IntoIterator<Item = &'a (u32, u32, i8)>,
) -> UnionFind {
    let mut uf = UnionFind::new(n_cells);
    for &(a, b, _) in pairs {
        if is_top(a) && is_top(b) {
            uf.union(a, b);
        }
    }
    uf
}

/// `n_components` (the components of the top cells through `pairs`) less the merges `joins`
/// make in `uf`.
pub(crate) fn apply_joins(uf: &mut UnionFind, joins: &[(u32, u32)], n_components: usize) -> usize {
    joins
        .iter()
        .fold(n_components, |n, &(a, b)| n - usize::from(uf.union(a, b)))
}

/// `n_components` (the components of the top cells through `pairs`) less the merges `joins`
/// make: a union-find over the pairs and joins, only when there are joins.
pub(crate) fn joined_components(
    n_cells: usize,
    is_top: impl Fn(u32) -> bool,
    pairs: &[(u32, u32, i8)],
    joins: &[(u32, u32)],
    n_components: usize,
) -> usize {
    if joins.is_empty() {
        return n_components;
    }
    let mut uf = facet_union_find(n_cells, is_top, pairs);
    apply_joins(&mut uf, joins, n_components)
}

/// The root of `x` in a parity union-find (`link[c] = parent << 1 | parity`) and the parity
/// between `x` and the root, halving the path on the way.
#[inline]
fn parity_find(link: &mut [u32], mut x: u32) -> (u32, u32) {
    let mut par = 0;
    loop {
        let lx = link[x as usize];
        let p = lx >> 1;
        if p == x {
            return (x, par);
        }
        let lp = link[p as usize];
        let g = lp >> 1;
        if g == p {
            return (p, par ^ (lx & 1));
        }
        // x now links to its grandparent
        let nx = (g << 1) | ((lx ^ lp) & 1);
        link[x as usize] = nx;
        par ^= nx & 1;
        x = g;
    }
}

impl Walk {
    /// The answer of [`orient_tops`] from a walk seeded with +1: its conflict, or the cells
    /// whose sign is -1.
    ///
    /// ```
    /// use starplex::algo::orientation::{orient_walk, Orientation};
    /// use starplex::ids::CellId;
    /// let w = orient_walk(3, |_| true, &[(0, 1, 1), (1, 2, 1)], |_| 1);
    /// assert_eq!(w.orientation(), Orientation::Orientable { flips: vec![CellId(1)] });
    /// ```
    pub fn orientation(&self) -> Orientation {
        match self.conflict {
            Some(conflict) => Orientation::NonOrientable { conflict },
            None => Orientation::Orientable {
                flips: (0..self.signs.len())
                    .filter(|&c| self.signs[c] < 0)
                    .map(|c| CellId(c as u32))
                    .collect(),
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{orient_tops, orient_tops_renumbered, orient_walk};
    use crate::algo::unionfind::UnionFind;

    /// The walk in a working order answers like `orient_tops` on the pairs renumbered, on
    /// random graphs (orientable or not, several components, cells that are not tops) under
    /// random permutations.
    #[test]
    fn renumbered_walk_equals_the_walk_in_answer_ids() {
        let mut rng = crate::testkit::XorShift::new(0x0DDB_1A5E_5BAD_5EED);
        let mut conflicts = 0;
        for case in 0..600 {
            // some large enough for deep union-find trees
            let n = 1 + rng.below(if case % 5 == 4 { 3000 } else { 30 }) as usize;
            let top: Vec<bool> = (0..n).map(|_| rng.below(6) != 0).collect();
            // a random spanning-ish tree with consistent signs, plus a few random extra pairs
            let mut pairs: Vec<(u32, u32, i8)> = Vec::new();
            for b in 1..n as u32 {
                if rng.below(4) != 0 {
                    pairs.push((rng.below(b as u64) as u32, b, -1));
                }
            }
            for _ in 0..rng.below(if case % 2 == 0 { 7 } else { 1 }) {
                let a = rng.below(n as u64) as u32;
                let b = rng.below(n as u64) as u32;
                if a != b {
                    pairs.push((a, b, if rng.below(2) == 0 { 1 } else { -1 }));
                }
            }
            // working id w is answer id to_out[w]
            let mut to_out: Vec<u32> = (0..n as u32).collect();
            for i in (1..n).rev() {
                let j = rng.below(i as u64 + 1) as usize;
                to_out.swap(i, j);
            }
            let mut to_work = vec![0u32; n];
            for (w, &o) in to_out.iter().enumerate() {
                to_work[o as usize] = w as u32;
            }
            let work: Vec<(u32, u32, i8)> = pairs
                .iter()
                .map(|&(a, b, r)| (to_work[a as usize], to_work[b as usize], r))
                .collect();
            let want = orient_tops(n, |c| top[c as usize], &pairs);
            let n_want = orient_walk(n, |c| top[c as usize], &pairs, |_| 1).n_components;
            let got =
                orient_tops_renumbered(n, |w| top[to_out[w as usize] as usize], &work, &to_out);
            assert_eq!(got, (want.clone(), n_want), "case {case}");
            conflicts += usize::from(matches!(want, super::Orientation::NonOrientable { .. }));
        }
        assert!(
            conflicts > 50 && conflicts < 550,
            "{conflicts} non-orientable cases"
        );
    }

    /// Pairs in pieces and parts (united part by part on two threads, then the rest) answer
    /// like the walk in answer ids, and the joined count like a union-find over the pairs and
    /// joins: random graphs whose pairs mostly join near ids (inside a part), some far ones,
    /// orientable or not, cells that are not tops, random cuts into pieces and parts.
    #[test]
    fn parts_answer_like_the_walk() {
        let mut rng = crate::testkit::XorShift::new(0x7A27_5EED);
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(2)
            .build()
            .unwrap();
        let (mut conflicts, mut deferred) = (0, 0);
        for case in 0..400 {
            let n = 2 + rng.below(if case % 4 == 3 { 2000 } else { 60 }) as usize;
            let top: Vec<bool> = (0..n).map(|_| rng.below(8) != 0).collect();
            let sign: Vec<bool> = (0..n).map(|_| rng.below(2) == 0).collect();
            let rel = |a: usize, b: usize| if sign[a] != sign[b] { 1 } else { -1 };
            let mut pairs: Vec<(u32, u32, i8)> = Vec::new();
            for b in 1..n {
                let a = if rng.below(8) == 0 {
                    rng.below(b as u64) as usize
                } else {
                    b - 1 - rng.below(b.min(4) as u64) as usize
                };
                if rng.below(5) != 0 {
                    pairs.push((a as u32, b as u32, rel(a, b)));
                }
            }
            for _ in 0..rng.below(if case % 2 == 0 { 6 } else { 1 }) {
                let (a, b) = (rng.below(n as u64) as u32, rng.below(n as u64) as u32);
                if a != b {
                    pairs.push((a, b, if rng.below(2) == 0 { 1 } else { -1 }));
                }
            }
            for i in (1..pairs.len()).rev() {
                if rng.below(3) == 0 {
                    pairs.swap(i, rng.below(i as u64 + 1) as usize);
                }
            }
            let joins: Vec<(u32, u32)> = (0..rng.below(4))
                .map(|_| (rng.below(n as u64) as u32, rng.below(n as u64) as u32))
                .filter(|&(a, b)| top[a as usize] && top[b as usize])
                .collect();
            let mut to_out: Vec<u32> = (0..n as u32).collect();
            for i in (1..n).rev() {
                to_out.swap(i, rng.below(i as u64 + 1) as usize);
            }
            // pieces: random cuts of the pairs; parts: random groups of pieces and cells
            let mut cuts = vec![0usize];
            for i in 1..pairs.len() {
                if rng.below(4) == 0 {
                    cuts.push(i);
                }
            }
            cuts.push(pairs.len());
            let pieces: Vec<&[(u32, u32, i8)]> =
                cuts.windows(2).map(|w| &pairs[w[0]..w[1]]).collect();
            let mut parts = vec![(0usize, 0u32)];
            for (i, _) in pieces.iter().enumerate().skip(1) {
                let last = parts[parts.len() - 1].1 as usize;
                if rng.below(3) == 0 && last < n {
                    parts.push((i, (last + 1 + rng.below((n - last) as u64) as usize) as u32));
                }
            }
            if case % 7 == 6 {
                parts.clear(); // none given: one part
            }
            let is_top = |c: u32| top[c as usize];
            let out: Vec<(u32, u32, i8)> = pairs
                .iter()
                .map(|&(a, b, r)| (to_out[a as usize], to_out[b as usize], r))
                .collect();
            let mut top_out = vec![false; n];
            for c in 0..n {
                top_out[to_out[c] as usize] = top[c];
            }
            let w = orient_walk(n, |c| top_out[c as usize], &out, |_| 1);
            let mut uf = UnionFind::new(n);
            for &(a, b, _) in &pairs {
                if is_top(a) && is_top(b) {
                    uf.union(a, b);
                }
            }
            for &(a, b) in &joins {
                uf.union(a, b);
            }
            let n_joined = (0..n as u32)
                .filter(|&c| is_top(c) && uf.find(c) == c)
                .count();
            let pp = super::PairParts {
                pieces,
                parts: parts.clone(),
            };
            let got = pool.install(|| super::orient_parts_joined(n, is_top, &pp, &to_out, &joins));
            assert_eq!(
                got,
                (w.orientation(), w.n_components, n_joined),
                "case {case}"
            );
            conflicts += usize::from(matches!(got.0, super::Orientation::NonOrientable { .. }));
            deferred += usize::from(parts.len() > 1);
        }
        assert!(
            (20..380).contains(&conflicts),
            "{conflicts} non-orientable cases"
        );
        assert!(deferred > 100, "{deferred} cases of several parts");
    }

    /// Pairs met in the order that builds a binomial union-find tree of depth 6, its deepest
    /// cell numbered first: the signs and the flips still equal the walk's.
    #[test]
    fn deep_union_find_trees_orient_like_the_walk() {
        let mut rng = crate::testkit::XorShift::new(0xDEE9_7EE5);
        let n = 64u32;
        for _ in 0..20 {
            let sign: Vec<bool> = (0..n).map(|_| rng.below(2) == 0).collect();
            let rev = |x: u32| n - 1 - x;
            let mut pairs = Vec::new();
            let mut s = 1;
            while s < n {
                for x in (0..n).step_by(2 * s as usize) {
                    let (a, b) = (rev(x), rev(x + s));
                    pairs.push((
                        a,
                        b,
                        if sign[a as usize] != sign[b as usize] {
                            1
                        } else {
                            -1
                        },
                    ));
                }
                s *= 2;
            }
            let mut to_out: Vec<u32> = (0..n).collect();
            for i in (1..n as usize).rev() {
                to_out.swap(i, rng.below(i as u64 + 1) as usize);
            }
            let out: Vec<(u32, u32, i8)> = pairs
                .iter()
                .map(|&(a, b, r)| (to_out[a as usize], to_out[b as usize], r))
                .collect();
            let want = orient_tops(n as usize, |_| true, &out);
            assert_eq!(
                orient_tops_renumbered(n as usize, |_| true, &pairs, &to_out),
                (want, 1)
            );
        }
    }

    /// The walk's component count is what `finish_report` reports as the facet components when
    /// no facet is in more than two cells: it must equal a union-find over the same pairs of
    /// top cells, on random graphs with cells that are not tops.
    #[test]
    fn walk_components_equal_union_find() {
        let mut rng = crate::testkit::XorShift::new(0x9E37_79B9_7F4A_7C15);
        for _ in 0..500 {
            let n = 1 + rng.below(40) as usize;
            let top: Vec<bool> = (0..n).map(|_| rng.below(5) != 0).collect();
            let m = rng.below(2 * n as u64) as usize;
            let pairs: Vec<(u32, u32, i8)> = (0..m)
                .map(|_| {
                    let a = rng.below(n as u64) as u32;
                    let b = rng.below(n as u64) as u32;
                    (a, b, if rng.below(2) == 0 { 1 } else { -1 })
                })
                .filter(|p| p.0 != p.1)
                .collect();
            let is_top = |c: u32| top[c as usize];
            let mut uf = UnionFind::new(n);
            for &(a, b, _) in &pairs {
                if is_top(a) && is_top(b) {
                    uf.union(a, b);
                }
            }
            let want = (0..n as u32)
                .filter(|&c| is_top(c) && uf.find(c) == c)
                .count();
            assert_eq!(orient_walk(n, is_top, &pairs, |_| 1).n_components, want);
        }
    }
}
