//! Homology-preserving edge contraction (`--mode homology`): in rounds, every vertex (in id
//! order) absorbs the first neighbour (in id order) whose edge passes the link condition; a
//! vertex takes part in at most one contraction per round, so a round spreads the work over the
//! complex instead of growing one star. Rounds repeat until nothing contracts or the target is
//! reached. Any dimension, pure or not, manifold or not; the result is deterministic.
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
/// number of contractions made.
///
/// ```
/// use starplex::algo::simplify::{TopSimplices, Target, contract::contract_homology};
/// use starplex::algo::simplify::link_condition::LinkMode;
/// // a path of 5 vertices contracts to one vertex (contractible), a circle to a triangle
/// let mut w = TopSimplices::from_tops(5, &[vec![0, 1], vec![1, 2], vec![2, 3], vec![3, 4]]).unwrap();
/// contract_homology(&mut w, &Target::default(), LinkMode::Homology, None);
/// assert_eq!(w.n_alive_vertices(), 1);
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
    let mut stats = ContractStats::default();
    let n = w.n_vertices();
    let mut scratch = LinkScratch::default();
    let mut nb = Vec::new();
    let mut touched = FixedBitSet::with_capacity(n);
    while !target.reached(w) {
        stats.rounds += 1;
        touched.clear();
        let before = stats.n_contractions;
        for a in 0..n as u32 {
            if !w.is_alive(a) || touched.contains(a as usize) {
                continue;
            }
            w.neighbours_into(a, &mut nb);
            for &b in &nb {
                if touched.contains(b as usize) {
                    continue;
                }
                // a locked vertex survives; two locked ones are never merged
                let (s, t) = match (w.is_locked(a), w.is_locked(b)) {
                    (true, true) => continue,
                    (false, true) => (b, a),
                    _ => (a, b),
                };
                if link_condition(w, s, t, mode, &mut scratch)
                    && region_condition(w, s, t, &mut scratch)
                {
                    w.contract(s, t);
                    touched.insert(a as usize);
                    touched.insert(b as usize);
                    stats.n_contractions += 1;
                    if let Some(p) = progress {
                        p(1);
                    }
                    break;
                }
                stats.n_refused += 1;
            }
            if target.reached(w) {
                break;
            }
        }
        if stats.n_contractions == before {
            break;
        }
    }
    stats
}
