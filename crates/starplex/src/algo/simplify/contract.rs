//! Homology-preserving edge contraction (`--mode homology`): in rounds, every vertex (in id
//! order) not yet touched this round absorbs, one after the other, each of its neighbours (as
//! they were when the round reached it, in id order) that is not touched either and whose edge
//! passes the link condition; both ends become touched. A survivor grows by one ring per round,
//! so a round spreads the work over the complex instead of growing one star without bound, yet
//! clusters around survivors like the reference's queue of edges per leaf (absorbing only the
//! first neighbour stopped a tetrahedral ball at 6.4x more vertices, and took 1.6x longer).
//! Rounds repeat until nothing contracts or the target is reached. Any dimension, pure or not,
//! manifold or not; the result is deterministic.
//!
//! ```
//! use starplex::algo::simplify::{TopSimplices, Target, contract::contract_homology};
//! use starplex::algo::simplify::link_condition::LinkMode;
//! // the boundary of an octahedron (a 2-sphere) ends as the boundary of a tetrahedron
//! let oct = [[0, 2, 4], [2, 1, 4], [1, 3, 4], [3, 0, 4], [2, 0, 5], [1, 2, 5], [3, 1, 5], [0, 3, 5]];
//! let tops: Vec<Vec<u32>> = oct.iter().map(|t| t.to_vec()).collect();
//! let mut w = TopSimplices::from_tops(6, &tops).unwrap();
//! let stats = contract_homology(&mut w, &Target::default(), LinkMode::Homology, None);
//! assert_eq!((w.n_alive_vertices(), w.n_alive_tops()), (4, 4));
//! assert_eq!(stats.n_contractions, 2);
//! ```
use fixedbitset::FixedBitSet;

use super::blocks::Blocks;
use super::link_condition::{link_condition, region_condition, LinkMode, LinkScratch};
use super::tops::TopSimplices;
use super::{Progress, Target};

/// Why an edge may not be contracted.
///
/// ```
/// use starplex::algo::simplify::{TopSimplices, contract::ContractError};
/// let w = TopSimplices::from_tops(3, &[vec![0, 1], vec![1, 2], vec![0, 2]]).unwrap();
/// assert_eq!(w.can_contract(0, 1), Err(ContractError::LinkCondition { a: 0, b: 1 }));
/// assert_eq!(w.can_contract(0, 7), Err(ContractError::NotAnEdge { a: 0, b: 7 }));
/// ```
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum ContractError {
    /// `ab` is not an edge of the complex (or a vertex was contracted away).
    #[error("{a}-{b} is not an edge of the complex")]
    NotAnEdge {
        /// First vertex.
        a: u32,
        /// Second vertex.
        b: u32,
    },
    /// The link condition fails: contracting would change the topology.
    #[error("the edge {a}-{b} fails the link condition (Lk(a) ∩ Lk(b) ≠ Lk(ab))")]
    LinkCondition {
        /// First vertex.
        a: u32,
        /// Second vertex.
        b: u32,
    },
}

impl TopSimplices {
    /// Checks that contracting `ab` keeps the homology (the link condition).
    ///
    /// ```
    /// use starplex::algo::simplify::TopSimplices;
    /// let mut w = TopSimplices::from_tops(3, &[vec![0, 1, 2]]).unwrap();
    /// if w.can_contract(0, 1).is_ok() {
    ///     w.contract(0, 1);
    /// }
    /// assert_eq!(w.sorted_tops(), vec![vec![0, 2]]);
    /// ```
    ///
    /// # Errors
    /// [`ContractError::NotAnEdge`], [`ContractError::LinkCondition`].
    pub fn can_contract(&self, a: u32, b: u32) -> Result<(), ContractError> {
        self.can_contract_in(a, b, LinkMode::Homology, &mut LinkScratch::default())
    }

    /// [`can_contract`](Self::can_contract) in the given mode, with reused buffers.
    ///
    /// ```
    /// use starplex::algo::simplify::{TopSimplices, link_condition::{LinkMode, LinkScratch}};
    /// let w = TopSimplices::from_tops(4, &[vec![0, 1, 2], vec![1, 3, 2]]).unwrap();
    /// let mut s = LinkScratch::default();
    /// assert!(w.can_contract_in(1, 2, LinkMode::Homology, &mut s).is_ok());
    /// assert!(w.can_contract_in(1, 2, LinkMode::Manifold, &mut s).is_err());
    /// ```
    ///
    /// # Errors
    /// As [`can_contract`](Self::can_contract).
    pub fn can_contract_in(
        &self,
        a: u32,
        b: u32,
        mode: LinkMode,
        scratch: &mut LinkScratch,
    ) -> Result<(), ContractError> {
        let is_edge = a != b
            && self.is_alive(a)
            && self.is_alive(b)
            && self.star(b).iter().any(|&t| self.top(t).contains(&a));
        if !is_edge {
            return Err(ContractError::NotAnEdge { a, b });
        }
        if link_condition(self, a, b, mode, scratch) {
            Ok(())
        } else {
            Err(ContractError::LinkCondition { a, b })
        }
    }
}

/// What a simplification run did.
///
/// ```
/// let s = starplex::algo::simplify::contract::ContractStats::default();
/// assert_eq!((s.n_contractions, s.rounds), (0, 0));
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ContractStats {
    /// Edges contracted.
    pub n_contractions: u64,
    /// Rounds (passes over the vertices) run.
    pub rounds: u64,
    /// Link-condition tests that refused an edge.
    pub n_refused: u64,
}

/// Contracts edges that pass the link condition, in rounds, until nothing contracts or the
/// target (faces = tops, or vertices) is reached. A locked vertex
/// ([`TopSimplices::set_locked`]) is never removed: it absorbs its unlocked neighbours, and an
/// edge between two locked vertices is never contracted. `mode` [`LinkMode::Manifold`] also keeps a
/// manifold (with boundary) a manifold of the same dimension. `progress` is called with the
/// number of contractions made. One thread; [`contract_homology_blocks`] is the same on
/// blocks of vertices contracted in parallel.
///
/// ```
/// use starplex::algo::simplify::{TopSimplices, Target, contract::contract_homology};
/// use starplex::algo::simplify::link_condition::LinkMode;
/// // a path of 5 vertices contracts to one vertex (contractible), a circle to a triangle
/// let mut w = TopSimplices::from_tops(5, &[vec![0, 1], vec![1, 2], vec![2, 3], vec![3, 4]]).unwrap();
/// let s = contract_homology(&mut w, &Target::default(), LinkMode::Homology, None);
/// assert_eq!((w.n_alive_vertices(), s.n_contractions, s.n_refused), (1, 4, 0));
/// let circle: Vec<Vec<u32>> = (0..6).map(|i| vec![i, (i + 1) % 6]).collect();
/// let mut w = TopSimplices::from_tops(6, &circle).unwrap();
/// contract_homology(&mut w, &Target::default(), LinkMode::Homology, None);
/// assert_eq!(w.n_alive_vertices(), 3);
/// ```
pub fn contract_homology(
    w: &mut TopSimplices,
    target: &Target,
    mode: LinkMode,
    progress: Option<&Progress>,
) -> ContractStats {
    let blocks = Blocks::single(w.n_vertices());
    contract_homology_owned_blocks(w, target, mode, progress, blocks)
}

/// [`contract_homology`] over blocks of vertices (for instance the leaves of a Stellar tree,
/// [`Blocks::from_stellar`]), both cores at work. Each round first sweeps every block on its
/// own, in parallel: a block contracts only edges whose two stars lie inside it (its *inner*
/// vertices), on a part cut out of the structure, in increasing vertex id order, in sweeps of
/// its own while most of their tests contract; the parts are pasted back in block order.
/// Then one sweep over all the vertices, in id order, takes the edges across blocks (and the
/// vertices left untouched). With a count target, each block gets
/// a share of what is left to remove in proportion to its size and stops before a contraction
/// that could exceed it, so the sequential sweep stops exactly at the target. The result
/// depends on the blocks, never on the number of threads; with one block it is
/// [`contract_homology`]'s.
///
/// ```
/// use starplex::algo::simplify::{TopSimplices, Target, Blocks, contract::{contract_homology_blocks}};
/// use starplex::algo::simplify::link_condition::LinkMode;
/// // a path of 100 vertices in 4 blocks of 25 consecutive ones: contractible, one vertex left
/// let path: Vec<Vec<u32>> = (0..99).map(|i| vec![i, i + 1]).collect();
/// let mut w = TopSimplices::from_tops(100, &path).unwrap();
/// let order: Vec<u32> = (0..100).collect();
/// let blocks = Blocks::from_order(&order, &[0, 25, 50, 75, 100]).unwrap();
/// let s = contract_homology_blocks(&mut w, &Target::default(), LinkMode::Homology, None, &blocks);
/// assert_eq!((w.n_alive_vertices(), s.n_contractions), (1, 99));
/// ```
pub fn contract_homology_blocks(
    w: &mut TopSimplices,
    target: &Target,
    mode: LinkMode,
    progress: Option<&Progress>,
    blocks: &Blocks,
) -> ContractStats {
    contract_homology_owned_blocks(w, target, mode, progress, blocks.clone())
}

/// [`contract_homology_blocks`] on blocks it may consume (the rounds compact them): no copy.
pub(crate) fn contract_homology_owned_blocks(
    w: &mut TopSimplices,
    target: &Target,
    mode: LinkMode,
    progress: Option<&Progress>,
    mut blocks: Blocks,
) -> ContractStats {
    let mut stats = ContractStats::default();
    let n = w.n_vertices();
    let mut sweeper = Sweeper::new(mode, progress);
    let mut touched = FixedBitSet::with_capacity(n);
    // inner vertices whose block sweep ran to its end: their pairs were all tried this round
    let mut tried = FixedBitSet::with_capacity(n);
    let mut in_part = FixedBitSet::with_capacity(w.n_top_slots());
    let mut changes = Changes::all(n);
    while !target.reached(w) {
        stats.rounds += 1;
        touched.clear();
        tried.clear();
        let before = stats.n_contractions;
        if blocks.len() > 1 {
            blocks.sweep_parts(
                w,
                target,
                &sweeper,
                &mut touched,
                &mut tried,
                &mut in_part,
                &mut changes,
                &mut stats,
            );
        }
        if !target.reached(w) {
            let all = 0..n as u32;
            sweeper.sweep(
                w,
                all,
                &mut touched,
                Some(&tried),
                &mut changes,
                &mut stats,
                |_, _, _| true,
                |w| target.reached(w),
            );
        }
        if stats.n_contractions == before {
            break;
        }
        // the vertices contracted away leave the blocks: cuts and pastes cost what is alive
        blocks.retain_alive(w);
        changes.next_round();
    }
    stats
}

/// Per vertex, a flag set in the last round or in this one.
#[derive(Clone)]
struct Window {
    /// Set in the last round.
    prev: FixedBitSet,
    /// Set in this round.
    cur: FixedBitSet,
}

impl Window {
    fn new(n: usize, set: bool) -> Window {
        let mut prev = FixedBitSet::with_capacity(n);
        if set {
            prev.insert_range(..);
        }
        Window {
            prev,
            cur: FixedBitSet::with_capacity(n),
        }
    }

    fn has(&self, v: u32) -> bool {
        self.prev.contains(v as usize) || self.cur.contains(v as usize)
    }

    fn restrict(&self, verts: &[u32]) -> Window {
        let mut w = Window::new(verts.len(), false);
        for (i, &v) in verts.iter().enumerate() {
            w.prev.set(i, self.has(v));
        }
        w
    }

    fn absorb(&mut self, part: &Window, verts: &[u32]) {
        for i in part.cur.ones() {
            self.cur.insert(verts[i] as usize);
        }
    }

    fn next_round(&mut self) {
        std::mem::swap(&mut self.prev, &mut self.cur);
        self.cur.clear();
    }
}

/// What the last round and this one changed, so that a sweep skips the edges it tested and
/// refused before that no contraction since can have changed.
///
/// Contracting `t` into `s` replaces the simplices through `t` by their images through `s`.
/// It changes the links of `t` and of its neighbours, `s` among them (*changed*). It changes
/// an element of `Lk(x) ∩ Lk(y)` or of `Lk(xy)` only when `x` and `y` both lie in
/// `{s} ∪ N(s) ∪ N(t)` (*near*): a changed element of `Lk(x)` passes through `s` or `t`, and
/// is one of `Lk(y)` only if `y` is adjacent to `s` or `t`. The same holds in the complex closed
/// by a cone over its boundary ([`LinkMode::Manifold`], and the region test within a label's
/// region), whose apex adds no edge between real vertices.
///
/// So an edge is tested again only when one of its ends changed and both are near, in the last
/// round or in this one. Every edge was tested in the round before, or skipped by this same
/// rule, so skipping changes nothing but the time.
pub(super) struct Changes {
    changed: Window,
    near: Window,
}

impl Changes {
    /// Before the first round: every vertex counts as changed and near.
    pub(super) fn all(n: usize) -> Changes {
        Changes {
            changed: Window::new(n, true),
            near: Window::new(n, true),
        }
    }

    /// The changes of the vertices `verts` (a block's part numbering: vertex `i` is
    /// `verts[i]`), this round's empty.
    pub(super) fn restrict(&self, verts: &[u32]) -> Changes {
        Changes {
            changed: self.changed.restrict(verts),
            near: self.near.restrict(verts),
        }
    }

    /// Adds the changes a part made this round (vertex `i` of the part is `verts[i]`).
    pub(super) fn absorb(&mut self, part: &Changes, verts: &[u32]) {
        self.changed.absorb(&part.changed, verts);
        self.near.absorb(&part.near, verts);
    }

    /// Ends a round of a part's own rounds: this round's changes become the last round's and
    /// are added to `acc` (what the part changed over all its rounds).
    pub(super) fn next_round_into(&mut self, acc: &mut [FixedBitSet; 2]) {
        acc[0].union_with(&self.changed.cur);
        acc[1].union_with(&self.near.cur);
        self.next_round();
    }

    /// Counts the changes `acc` (of [`next_round_into`](Self::next_round_into)) as made in
    /// this round.
    pub(super) fn add_changed(&mut self, acc: &[FixedBitSet; 2]) {
        self.changed.cur.union_with(&acc[0]);
        self.near.cur.union_with(&acc[1]);
    }

    /// Records the contraction of `t` into `s`: `nb_t` and `nb_s` are their neighbours
    /// before it.
    fn record(&mut self, s: u32, t: u32, nb_s: &[u32], nb_t: &[u32]) {
        for &x in nb_t.iter().chain([&t]) {
            self.changed.cur.insert(x as usize);
            self.near.cur.insert(x as usize);
        }
        for &x in nb_s.iter().chain([&s]) {
            self.near.cur.insert(x as usize);
        }
    }

    /// False when no edge `a?` refused before can have changed since (see
    /// [`may_differ`](Self::may_differ)).
    fn may_differ_at(&self, a: u32) -> bool {
        self.near.has(a)
    }

    /// False when the edge `ab`, refused before, cannot have changed since.
    fn may_differ(&self, a: u32, b: u32) -> bool {
        (self.changed.has(a) || self.changed.has(b)) && self.near.has(a) && self.near.has(b)
    }

    fn next_round(&mut self) {
        self.changed.next_round();
        self.near.next_round();
    }
}

/// One sweep of [`contract_homology_blocks`]: its mode, callback and reused buffers.
pub(super) struct Sweeper<'a> {
    mode: LinkMode,
    progress: Option<&'a Progress>,
    scratch: LinkScratch,
    nb: Vec<u32>,
    nb_s: Vec<u32>,
    nb_t: Vec<u32>,
}

impl<'a> Sweeper<'a> {
    pub(super) fn new(mode: LinkMode, progress: Option<&'a Progress>) -> Sweeper<'a> {
        Sweeper {
            mode,
            progress,
            scratch: LinkScratch::default(),
            nb: Vec::new(),
            nb_s: Vec::new(),
            nb_t: Vec::new(),
        }
    }

    /// A fresh sweeper with the same mode and callback (one per parallel task).
    pub(super) fn fork(&self) -> Sweeper<'a> {
        Sweeper::new(self.mode, self.progress)
    }

    /// Every vertex `a` of `order` not `touched` absorbs each untouched neighbour (of those it
    /// had when the sweep reached it, in id order) whose edge passes the link condition, both
    /// ends becoming touched; a locked neighbour absorbs `a` instead, which ends its turn.
    /// A pair of two `tried` vertices is skipped (already tried this round), and so is a pair
    /// whose two stars are as when it was refused last round (`changes`, which records the
    /// stars each contraction changes). `allow(w, s, t)`
    /// is asked before contracting `t` into `s` (false ends the sweep), `done(w)` after each
    /// contraction (true ends it). Returns false when a callback ended the sweep.
    ///
    /// Each turn focuses the link tests on `a` ([`LinkScratch::focus`]), again after each of
    /// its contractions; the sweeper's buffers serve no other test, so no focus outlives a turn
    /// that could be misread.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn sweep(
        &mut self,
        w: &mut TopSimplices,
        order: impl Iterator<Item = u32>,
        touched: &mut FixedBitSet,
        tried: Option<&FixedBitSet>,
        changes: &mut Changes,
        stats: &mut ContractStats,
        mut allow: impl FnMut(&TopSimplices, u32, u32) -> bool,
        mut done: impl FnMut(&TopSimplices) -> bool,
    ) -> bool {
        let was_tried = |v: u32| tried.is_some_and(|t| t.contains(v as usize));
        for a in order {
            // an edge of a vertex not near any change since it was refused is refused again
            if !w.is_alive(a) || touched.contains(a as usize) || !changes.may_differ_at(a) {
                continue;
            }
            w.neighbours_into(a, &mut self.nb);
            self.scratch.focus(a);
            let a_tried = was_tried(a);
            for i in 0..self.nb.len() {
                let b = self.nb[i];
                if touched.contains(b as usize)
                    || (a_tried && was_tried(b))
                    || !changes.may_differ(a, b)
                {
                    continue;
                }
                // a locked vertex survives; two locked ones are never merged
                let (s, t) = match (w.is_locked(a), w.is_locked(b)) {
                    (true, true) => continue,
                    (false, true) => (b, a),
                    _ => (a, b),
                };
                if link_condition(w, s, t, self.mode, &mut self.scratch)
                    && region_condition(w, s, t, self.mode, &mut self.scratch)
                {
                    if !allow(w, s, t) {
                        return false;
                    }
                    // what the contraction changes (see `Changes`)
                    w.neighbours_into(t, &mut self.nb_t);
                    // `a`'s neighbours when its turn began: those it gained since are the
                    // neighbours of the vertices it absorbed, already recorded as near
                    let nb_s = if s == a {
                        &self.nb
                    } else {
                        w.neighbours_into(s, &mut self.nb_s);
                        &self.nb_s
                    };
                    changes.record(s, t, nb_s, &self.nb_t);
                    w.contract_linked(s, t);
                    self.scratch.focus(a);
                    touched.insert(a as usize);
                    touched.insert(b as usize);
                    stats.n_contractions += 1;
                    if let Some(p) = self.progress {
                        p(1);
                    }
                    if done(w) {
                        return false;
                    }
                    if s != a {
                        break; // `a` was absorbed
                    }
                    continue;
                }
                stats.n_refused += 1;
            }
        }
        true
    }
}
