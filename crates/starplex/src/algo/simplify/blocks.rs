//! Blocks of vertices for the parallel rounds of homology-preserving contraction
//! ([`contract_homology_blocks`](super::contract::contract_homology_blocks)): a partition of
//! the vertices into groups that are close in the complex, taken from the leaves of a Stellar
//! tree ([`Blocks::from_stellar`]: consecutive leaves, in the tree's order, until a block has
//! enough vertices) or given as an order and cut points ([`Blocks::from_order`]).
//!
//! A block's *inner* vertices are those whose every top lies inside the block: an edge between
//! two of them is contracted on a part cut out of the structure ([`TopSimplices::cut`]), without
//! looking at the rest, so the blocks are contracted in parallel, and pasted back in block order.
//!
//! ```
//! use starplex::algo::simplify::Blocks;
//! let b = Blocks::from_order(&[3, 1, 0, 2], &[0, 2, 4]).unwrap();
//! assert_eq!(b.len(), 2);
//! assert_eq!((b.block(0), b.block(1)), (&[1, 3][..], &[0, 2][..])); // each sorted by id
//! assert_eq!(Blocks::single(4).len(), 1);
//! ```
use fixedbitset::FixedBitSet;
use std::sync::RwLock;

use rayon::prelude::*;

use super::contract::{Changes, ContractStats, Sweeper};
use super::tops::TopSimplices;
use super::{SimplifyError, Target};
use crate::stellar::StellarTree;

/// Vertices per block that [`simplify`](super::simplify) aims at: the border of a block (its
/// vertices with a top reaching another block) is then a few percent of it on a mesh.
pub const BLOCK_VERTICES: usize = 16_384;

/// A part runs another round of its own while its last one refused at most this many edges
/// per contraction; past that (the dense end of a volume mesh), the rounds over the whole
/// structure go on, which test fewer edges that are refused again.
const RETRY: u64 = 2;

/// A partition of the vertices into blocks (see the [module](self)).
///
/// ```
/// use starplex::algo::simplify::Blocks;
/// let b = Blocks::from_order(&[0, 1, 2, 3, 4], &[0, 3, 5]).unwrap();
/// assert_eq!(b.block(1), &[3, 4]);
/// ```
#[derive(Clone, Debug, Default)]
pub struct Blocks {
    /// The vertices, block after block, each block in increasing id order.
    verts: Vec<u32>,
    /// Block `x` is `verts[starts[x]..starts[x + 1]]`.
    starts: Vec<usize>,
    /// Per vertex: its position in `verts` (so its block is the one whose range holds it;
    /// `u32::MAX` once contracted away; empty for a single block).
    slot_of: Vec<u32>,
    /// Per block: its number of vertices as made, before [`retain_alive`](Self::retain_alive)
    /// (what a block's share of a count target is proportional to).
    sizes: Vec<usize>,
}

impl Blocks {
    /// All `n` vertices in one block (no parallel sweep).
    ///
    /// ```
    /// assert_eq!(starplex::algo::simplify::Blocks::single(10).len(), 1);
    /// ```
    pub fn single(n: usize) -> Blocks {
        Blocks {
            verts: Vec::new(),
            starts: vec![0, n],
            slot_of: Vec::new(),
            sizes: vec![n],
        }
    }

    /// Blocks `order[cuts[i]..cuts[i + 1]]`: `order` a permutation of the vertices `0..n`,
    /// `cuts` increasing from 0 to `n`.
    ///
    /// ```
    /// use starplex::algo::simplify::Blocks;
    /// assert!(Blocks::from_order(&[0, 0], &[0, 2]).is_err()); // not a permutation
    /// assert!(Blocks::from_order(&[0, 1], &[0, 1]).is_err()); // cuts end before n
    /// ```
    ///
    /// # Errors
    /// [`SimplifyError::BadTarget`] naming what is wrong.
    pub fn from_order(order: &[u32], cuts: &[usize]) -> Result<Blocks, SimplifyError> {
        Self::from_order_owned(order.to_vec(), cuts)
    }

    /// [`from_order`](Self::from_order) on an order it may keep (no copy).
    fn from_order_owned(mut verts: Vec<u32>, cuts: &[usize]) -> Result<Blocks, SimplifyError> {
        let n = verts.len();
        let bad = |what: &str| Err(SimplifyError::BadTarget(format!("blocks: {what}")));
        if cuts.first() != Some(&0) || cuts.last() != Some(&n) {
            return bad("the cuts must run from 0 to the number of vertices");
        }
        if cuts.windows(2).any(|c| c[0] >= c[1]) {
            return bad("the cuts must be increasing");
        }
        let mut slot_of = vec![u32::MAX; n];
        for &v in &verts {
            match slot_of.get_mut(v as usize) {
                Some(b) if *b == u32::MAX => *b = 0,
                _ => return bad("the order must hold every vertex once"),
            }
        }
        for c in cuts.windows(2) {
            verts[c[0]..c[1]].sort_unstable();
        }
        for (p, &v) in verts.iter().enumerate() {
            slot_of[v as usize] = p as u32;
        }
        Ok(Blocks {
            verts,
            starts: cuts.to_vec(),
            slot_of,
            sizes: cuts.windows(2).map(|c| c[1] - c[0]).collect(),
        })
    }

    /// Consecutive leaves of a Stellar tree (in the tree's order) grouped until a block has at
    /// least `min_vertices` vertices; the last block takes what is left. One block when the
    /// tree has fewer than `2 * min_vertices` vertices.
    ///
    /// ```
    /// use starplex::algo::simplify::Blocks;
    /// use starplex::generate::kuhn_grid;
    /// use starplex::stellar::{StellarOptions, StellarTree};
    /// let k = kuhn_grid(&[8, 8]).unwrap(); // 81 vertices
    /// let t = StellarTree::build(&k, &StellarOptions { kv: Some(8), ..Default::default() }).unwrap();
    /// let b = Blocks::from_stellar(&t, 20);
    /// assert!(b.len() >= 2 && (0..b.len()).all(|x| b.block(x).len() >= 20));
    /// assert_eq!((0..b.len()).map(|x| b.block(x).len()).sum::<usize>(), 81);
    /// ```
    pub fn from_stellar(tree: &StellarTree, min_vertices: usize) -> Blocks {
        let order: Vec<u32> = tree.vertex_to_input().iter().map(|v| v.0).collect();
        let mut starts: Vec<u32> = (0..tree.n_leaves())
            .map(|l| tree.leaf_vertices(crate::ids::LeafId(l as u32)).start)
            .collect();
        starts.push(tree.n_vertices() as u32);
        Blocks::from_leaves(order, &starts, min_vertices)
    }

    /// [`from_stellar`](Self::from_stellar) from the vertex decomposition alone
    /// ([`StellarTree::vertex_order`]: the vertices in tree order and the first vertex of
    /// every leaf, then the count).
    ///
    /// ```
    /// use starplex::algo::simplify::Blocks;
    /// use starplex::generate::kuhn_grid;
    /// use starplex::stellar::{StellarOptions, StellarTree};
    /// let k = kuhn_grid(&[8, 8]).unwrap();
    /// let opts = StellarOptions { kv: Some(8), ..Default::default() };
    /// let (order, starts) = StellarTree::vertex_order(&k, &opts).unwrap();
    /// let b = Blocks::from_leaves(order, &starts, 20);
    /// let t = StellarTree::build(&k, &opts).unwrap();
    /// let c = Blocks::from_stellar(&t, 20);
    /// assert!(b.len() >= 2 && (0..b.len()).all(|x| b.block(x) == c.block(x)));
    /// ```
    pub fn from_leaves(order: Vec<u32>, leaf_starts: &[u32], min_vertices: usize) -> Blocks {
        let n = order.len();
        let min_vertices = min_vertices.max(1);
        if n < 2 * min_vertices {
            return Blocks::single(n);
        }
        let mut cuts = vec![0];
        for &end in leaf_starts.iter().skip(1) {
            let end = end as usize;
            if end - cuts[cuts.len() - 1] >= min_vertices && n - end >= min_vertices {
                cuts.push(end);
            }
        }
        if cuts.last() != Some(&n) {
            cuts.push(n);
        }
        Blocks::from_order_owned(order, &cuts).unwrap_or_else(|_| Blocks::single(n))
    }

    /// Number of blocks.
    ///
    /// ```
    /// assert_eq!(starplex::algo::simplify::Blocks::from_order(&[1, 0], &[0, 1, 2]).unwrap().len(), 2);
    /// ```
    pub fn len(&self) -> usize {
        self.starts.len() - 1
    }

    /// True when there is no block (never: a partition has at least one).
    ///
    /// ```
    /// assert!(!starplex::algo::simplify::Blocks::single(0).is_empty());
    /// ```
    pub fn is_empty(&self) -> bool {
        self.starts.len() < 2
    }

    /// The vertices of block `x`, in increasing id order (empty for [`single`](Self::single)).
    ///
    /// ```
    /// let b = starplex::algo::simplify::Blocks::from_order(&[1, 0], &[0, 1, 2]).unwrap();
    /// assert_eq!(b.block(0), &[1]);
    /// ```
    pub fn block(&self, x: usize) -> &[u32] {
        self.verts
            .get(self.starts[x]..self.starts[x + 1])
            .unwrap_or(&[])
    }

    /// Drops the vertices of `w` contracted away from every block (they never come back), so
    /// that the next round's cuts and pastes cost what is alive, not what the blocks held at
    /// first. Positions stay in increasing id order, so the sweeps decide as before.
    ///
    /// ```
    /// use starplex::algo::simplify::{Blocks, TopSimplices};
    /// let mut w = TopSimplices::from_tops(4, &[vec![0, 1], vec![1, 2], vec![2, 3]]).unwrap();
    /// let mut b = Blocks::from_order(&[0, 1, 2, 3], &[0, 2, 4]).unwrap();
    /// w.contract(2, 3);
    /// b.retain_alive(&w);
    /// assert_eq!((b.block(0), b.block(1)), (&[0, 1][..], &[2][..]));
    /// ```
    pub fn retain_alive(&mut self, w: &TopSimplices) {
        if self.slot_of.is_empty() {
            return;
        }
        let mut out = 0;
        for x in 0..self.len() {
            let (from, to) = (self.starts[x], self.starts[x + 1]);
            self.starts[x] = out;
            for i in from..to {
                let v = self.verts[i];
                if w.is_alive(v) {
                    self.slot_of[v as usize] = out as u32;
                    self.verts[out] = v;
                    out += 1;
                } else {
                    self.slot_of[v as usize] = u32::MAX;
                }
            }
        }
        let last = self.starts.len() - 1;
        self.starts[last] = out;
        self.verts.truncate(out);
    }

    /// The block sweeps of one round: every block's inner edges contracted on its own part, in
    /// rounds of its own while they pay (see [`RETRY`]) and until it meets its share of a count
    /// target, in parallel waves, pasted back in block order (skipping the edges refused
    /// before that no contraction since can have changed, and recording what changed in
    /// `changes`). Marks the vertices contracted (`touched`) and the inner vertices of the
    /// blocks swept to the end (`tried`); `in_part` is a cleared bitset over the top slots.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn sweep_parts(
        &self,
        w: &mut TopSimplices,
        target: &Target,
        sweeper: &Sweeper<'_>,
        touched: &mut FixedBitSet,
        tried: &mut FixedBitSet,
        in_part: &mut FixedBitSet,
        changes: &mut Changes,
        stats: &mut ContractStats,
    ) {
        let n = w.n_vertices() as u128;
        // what a block may remove: its share of what is left before the target
        let left_tops = target
            .faces
            .map(|f| w.n_alive_tops().saturating_sub(f) as u128);
        let left_vertices = target
            .vertices
            .map(|v| w.n_alive_vertices().saturating_sub(v) as u128);
        // Each block is cut, contracted and pasted back on its own, as soon as a thread is
        // free: only the parts being worked on are in memory. A cut reads only its block's
        // vertices and the tops through them, which no other block's paste writes (a part's
        // tops lie inside its block), so the order of the pastes changes nothing.
        let state = RwLock::new(Pasted {
            w,
            changes,
            touched,
            tried,
            in_part,
            stats,
        });
        (0..self.len()).into_par_iter().for_each(|x| {
            let verts = self.block(x);
            let (mut part, mut ch) = {
                let g = state.read().unwrap_or_else(|e| e.into_inner());
                let part = g.w.cut(verts, &self.slot_of, self.starts[x] as u32);
                (part, g.changes.restrict(verts))
            };
            let size = self.sizes[x] as u128;
            let share = |left: u128| (left * size / n.max(1)) as usize;
            let max_tops = left_tops.map(share);
            let max_vertices = left_vertices.map(share);
            let (tops0, verts0) = (part.w.n_alive_tops(), part.w.n_alive_vertices());
            let mut frozen = FixedBitSet::with_capacity(verts.len());
            frozen.insert_range(..);
            frozen.difference_with(&part.inner);
            let mut local = frozen.clone();
            let mut s = sweeper.fork();
            let mut st = ContractStats::default();
            let allow = |p: &TopSimplices, a: u32, b: u32| {
                let bound = tops0 - p.n_alive_tops() + p.star(a).len() + p.star(b).len();
                max_tops.is_none_or(|m| bound <= m)
                    && max_vertices.is_none_or(|m| verts0 - p.n_alive_vertices() < m)
            };
            // rounds on the part while they pay: one cut and one paste for all
            let mut contracted = FixedBitSet::with_capacity(verts.len());
            let mut changed = [
                FixedBitSet::with_capacity(verts.len()),
                FixedBitSet::with_capacity(verts.len()),
            ];
            let complete = loop {
                let (before, refused) = (st.n_contractions, st.n_refused);
                let complete = s.sweep(
                    &mut part.w,
                    0..verts.len() as u32,
                    &mut local,
                    None,
                    &mut ch,
                    &mut st,
                    &allow,
                    |_| false,
                );
                local.difference_with(&frozen);
                contracted.union_with(&local);
                let made = st.n_contractions - before;
                // another round while it pays: most of the tests still contract
                if !complete || made == 0 || st.n_refused - refused > RETRY * made {
                    break complete;
                }
                ch.next_round_into(&mut changed);
                local.clone_from(&frozen);
            };
            ch.add_changed(&changed);
            let mut g = state.write().unwrap_or_else(|e| e.into_inner());
            let g = &mut *g;
            g.w.paste(verts, &part, g.in_part);
            g.changes.absorb(&ch, verts);
            for i in contracted.ones() {
                g.touched.insert(verts[i] as usize);
            }
            if complete {
                for i in part.inner.ones() {
                    g.tried.insert(verts[i] as usize);
                }
            }
            g.stats.n_contractions += st.n_contractions;
            g.stats.n_refused += st.n_refused;
        });
    }
}

/// What the block sweeps of [`Blocks::sweep_parts`] write back, behind one lock.
struct Pasted<'s> {
    w: &'s mut TopSimplices,
    changes: &'s mut Changes,
    touched: &'s mut FixedBitSet,
    tried: &'s mut FixedBitSet,
    in_part: &'s mut FixedBitSet,
    stats: &'s mut ContractStats,
}
