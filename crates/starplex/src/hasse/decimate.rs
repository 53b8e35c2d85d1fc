//! Generalized decimation (CASC Def. 4.1, Alg. 4): collapse any simplex `s` into a new vertex
//! `p`, mapping every `f` of `St(Cl(s))` to `φ(f) = p ∪ (f \ s)`, merging the data of the
//! simplices that map to the same new simplex with a user callback. Theorem 4.2: the result is
//! always a simplicial complex.
use smallvec::SmallVec;

use super::complex::Hasse;
use super::levels::{LevelTypes, MergeAll};
use super::remove::StarBufs;
use super::storage::Verts;
use super::{HasseError, Node, NodeSet};
use crate::ids::{SimplexId, VertexId};

/// The simplices that merge into one new simplex.
///
/// ```
/// use starplex::hasse::DecimationGroup;
/// let g = DecimationGroup { new: vec![6.into()], old: vec![vec![3.into()], vec![3.into(), 4.into()]] };
/// assert_eq!(g.old.len(), 2);
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DecimationGroup {
    /// The new simplex `φ(f)` (sorted vertices).
    pub new: Vec<VertexId>,
    /// Every simplex `f` with that image, by dimension then vertices.
    pub old: Vec<Vec<VertexId>>,
}

/// What a decimation will do, computed without changing the complex
/// ([`Hasse::plan_decimate`]).
///
/// ```
/// let mut h: starplex::hasse::Hasse = starplex::hasse::Hasse::new();
/// h.insert(&[0.into(), 1.into(), 2.into()]).unwrap();
/// let e = h.find(&[0.into(), 1.into()]).unwrap();
/// let plan = h.plan_decimate(e, None).unwrap();
/// assert_eq!(plan.new_vertex.0, 3);
/// assert_eq!(plan.groups.len(), 2); // {3} <- {0},{1},{0,1} and {2,3} <- {0,2},{1,2},{0,1,2}
/// assert_eq!(plan.groups[0].new, vec![3.into()]);
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DecimationPlan {
    /// The simplex decimated.
    pub simplex: Vec<VertexId>,
    /// The vertex it becomes.
    pub new_vertex: VertexId,
    /// The groups, by dimension of the new simplex then its vertices.
    pub groups: Vec<DecimationGroup>,
}

impl std::fmt::Display for DecimationPlan {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let fmt = |v: &[VertexId]| {
            let s: Vec<String> = v.iter().map(|x| x.0.to_string()).collect();
            format!("{{{}}}", s.join(","))
        };
        for g in &self.groups {
            let olds: Vec<String> = g.old.iter().map(|o| fmt(o)).collect();
            writeln!(f, "{} -> {}", olds.join(" "), fmt(&g.new))?;
        }
        Ok(())
    }
}

/// One group with node ids (internal form of a plan).
struct RawGroup {
    new: Verts,
    /// (dimension, id) of every old simplex, sorted by dimension then vertices.
    old: SmallVec<[(usize, u32); 4]>,
}

impl<L: LevelTypes> Hasse<L> {
    /// `St(Cl(s))` as sorted, distinct `(dimension, id)` pairs.
    pub(crate) fn neighbourhood_ids(&self, s: Node) -> Vec<(usize, u32)> {
        // Cl(s): breadth-first down, deduplicated per level
        let mut cl: Vec<(usize, u32)> = vec![(s.dim as usize, s.id.0)];
        let mut lo = 0;
        while lo < cl.len() {
            let hi = cl.len();
            let k = cl[lo].0;
            if k == 0 {
                break;
            }
            for j in lo..hi {
                let (k, i) = cl[j];
                for &f in self.levels[k].downs(i) {
                    cl.push((k - 1, f));
                }
            }
            cl[hi..].sort_unstable();
            let mut w = hi;
            for r in hi..cl.len() {
                if w == hi || cl[w - 1] != cl[r] {
                    cl[w] = cl[r];
                    w += 1;
                }
            }
            cl.truncate(w);
            lo = hi;
        }
        // St of each face: cofaces reached only from their canonical parent (no duplicates
        // within one star)
        let mut out: Vec<(usize, u32)> = Vec::new();
        let mut bufs = StarBufs::default();
        for &(k, i) in &cl {
            self.for_each_star_level(k, i, &mut bufs, |j, level| {
                out.extend(level.iter().map(|x| (j, x.0)));
            });
        }
        out.sort_unstable();
        out.dedup();
        out
    }

    fn check_label(&self, s: Node, p: Option<VertexId>) -> Result<VertexId, HasseError> {
        match p {
            None => self.fresh_label().ok_or(HasseError::NoFreeLabel),
            Some(p) => {
                if self.root.contains(p.0) && !self.vertices(s).contains(&p) {
                    Err(HasseError::LabelInUse(p))
                } else {
                    Ok(p)
                }
            }
        }
    }

    fn raw_plan(&self, s: Node, p: VertexId) -> Vec<RawGroup> {
        let sv = self.vertices(s).to_vec();
        let nb = self.neighbourhood_ids(s);
        let mut items: Vec<(Verts, usize, u32)> = Vec::with_capacity(nb.len());
        for &(k, i) in &nb {
            {
                let f = self.levels[k].verts(i);
                let mut phi: Verts = f
                    .iter()
                    .copied()
                    .filter(|x| !sv.contains(&VertexId(*x)))
                    .collect();
                let pos = phi.partition_point(|&x| x < p.0);
                phi.insert(pos, p.0);
                items.push((phi, k, i));
            }
        }
        items.sort_by(|a, b| {
            (a.0.len(), &a.0, a.1, self.levels[a.1].verts(a.2)).cmp(&(
                b.0.len(),
                &b.0,
                b.1,
                self.levels[b.1].verts(b.2),
            ))
        });
        let mut groups: Vec<RawGroup> = Vec::new();
        for (phi, k, i) in items {
            match groups.last_mut() {
                Some(g) if g.new == phi => g.old.push((k, i)),
                _ => {
                    let mut old = SmallVec::new();
                    old.push((k, i));
                    groups.push(RawGroup { new: phi, old })
                }
            }
        }
        groups
    }

    /// Plans the decimation of `s` into the vertex `p` (a fresh label when `None`; `p` may also
    /// be a vertex of `s`, which then keeps its label): the groups of simplices that merge, as
    /// Table 1 of the CASC paper lists them. Changes nothing.
    ///
    /// # Errors
    /// [`HasseError::NotANode`], [`HasseError::LabelInUse`] when `p` is a vertex outside `s`.
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse = starplex::hasse::Hasse::new();
    /// h.insert(&[0.into(), 1.into(), 2.into()]).unwrap();
    /// let e = h.find(&[0.into(), 1.into()]).unwrap();
    /// let plan = h.plan_decimate(e, None).unwrap();
    /// assert_eq!(plan.to_string(), "{0} {1} {0,1} -> {3}\n{0,2} {1,2} {0,1,2} -> {2,3}\n");
    /// ```
    pub fn plan_decimate(
        &self,
        s: Node,
        p: Option<VertexId>,
    ) -> Result<DecimationPlan, HasseError> {
        if !self.contains(s) {
            return Err(HasseError::NotANode(s));
        }
        let p = self.check_label(s, p)?;
        let groups = self
            .raw_plan(s, p)
            .into_iter()
            .map(|g| DecimationGroup {
                new: g.new.iter().map(|&x| VertexId(x)).collect(),
                old: g
                    .old
                    .iter()
                    .map(|&(k, i)| self.vertices(Node::new(k as u32, SimplexId(i))).to_vec())
                    .collect(),
            })
            .collect();
        Ok(DecimationPlan {
            simplex: self.vertices(s).to_vec(),
            new_vertex: p,
            groups,
        })
    }

    /// Decimates `s` into a new vertex (a fresh label), in place (Alg. 4). Each new simplex
    /// gets its data from `merge`, called with the merged simplices of the new simplex's own
    /// dimension (there is always at least one). Returns the new vertex's label.
    ///
    /// # Errors
    /// [`HasseError::NotANode`], [`HasseError::NoFreeLabel`].
    ///
    /// ```
    /// use starplex::hasse::{Hasse, Merge};
    /// use starplex::ids::VertexId;
    /// struct Mid;
    /// impl Merge<0, f64> for Mid {
    ///     fn merge(&mut self, _: &[VertexId], old: &[(&[VertexId], &f64)]) -> f64 {
    ///         old.iter().map(|(_, x)| **x).sum::<f64>() / old.len() as f64
    ///     }
    /// }
    /// impl<const K: usize> Merge<K, ()> for Mid {
    ///     fn merge(&mut self, _: &[VertexId], _: &[(&[VertexId], &())]) {}
    /// }
    /// let mut h: Hasse<(f64, ())> = Hasse::new();
    /// h.insert_with::<0>(&[0.into()], 1.0).unwrap();
    /// h.insert_with::<0>(&[1.into()], 3.0).unwrap();
    /// h.insert(&[0.into(), 1.into(), 2.into()]).unwrap();
    /// let e = h.find(&[0.into(), 1.into()]).unwrap();
    /// let p = h.decimate(e, &mut Mid).unwrap();
    /// let v = h.vertex(p).unwrap();
    /// assert_eq!(*h.data::<0>(v.id), 2.0);
    /// assert_eq!(h.f_vector(), vec![2, 1]);
    /// ```
    pub fn decimate<C: MergeAll<L>>(
        &mut self,
        s: Node,
        merge: &mut C,
    ) -> Result<VertexId, HasseError> {
        self.decimate_into(s, None, merge)
    }

    /// Decimates `s` into the vertex `p` (fresh when `None`, or one of `s`'s vertices).
    ///
    /// # Errors
    /// As [`plan_decimate`](Self::plan_decimate).
    ///
    /// ```
    /// use starplex::hasse::{Hasse, KeepFirst};
    /// let mut h: Hasse = Hasse::new();
    /// h.insert(&[0.into(), 1.into(), 2.into()]).unwrap();
    /// let e = h.find(&[0.into(), 1.into()]).unwrap();
    /// h.decimate_into(e, Some(0.into()), &mut KeepFirst).unwrap();
    /// assert!(h.find(&[0.into(), 2.into()]).is_some());
    /// ```
    pub fn decimate_into<C: MergeAll<L>>(
        &mut self,
        s: Node,
        p: Option<VertexId>,
        merge: &mut C,
    ) -> Result<VertexId, HasseError> {
        if !self.contains(s) {
            return Err(HasseError::NotANode(s));
        }
        let p = self.check_label(s, p)?;
        let groups = self.raw_plan(s, p);
        // when p is a vertex of s, a simplex that meets s in p alone is its own image: it stays
        // in place (same id) and only its data is replaced by the merged value
        let kept: Vec<Option<u32>> = groups
            .iter()
            .map(|g| {
                let d = g.new.len() - 1;
                g.old
                    .iter()
                    .find(|&&(k, i)| k == d && self.levels[k].verts(i) == &g.new[..])
                    .map(|&(_, i)| i)
            })
            .collect();
        // stage the merged data, per group, from the old simplices of the new one's dimension
        let mut staged = L::Columns::default();
        let mut old_buf: Vec<(&[VertexId], u32)> = Vec::new();
        for g in &groups {
            let d = g.new.len() - 1;
            if d >= L::N_LEVELS {
                continue;
            }
            old_buf.clear();
            for &(k, i) in &g.old {
                if k == d {
                    old_buf.push((bytemuck::cast_slice(self.levels[k].verts(i)), i));
                }
            }
            debug_assert!(!old_buf.is_empty());
            let newv: &[VertexId] = bytemuck::cast_slice(&g.new[..]);
            merge.stage(&self.data, &mut staged, d, newv, &old_buf);
        }
        drop(old_buf);
        L::reverse_all(&mut staged);
        // remove the neighbourhood
        let mut nb: Vec<Vec<u32>> = vec![Vec::new(); self.levels.len()];
        for (g, kp) in groups.iter().zip(&kept) {
            for &(k, i) in &g.old {
                if Some(i) != *kp || k != g.new.len() - 1 {
                    nb[k].push(i);
                }
            }
        }
        self.remove_upward_closed(nb);
        // insert the images (or update the kept ones)
        for (g, kp) in groups.iter().zip(&kept) {
            let d = g.new.len() - 1;
            let id = match kp {
                Some(i) => *i,
                None => self.insert_sorted(&g.new),
            };
            L::commit_pop(&mut self.data, &mut staged, d, id as usize);
        }
        if self.root.contains(p.0) {
            Ok(p)
        } else {
            // s was isolated from everything: only happens for an empty image, impossible
            Err(HasseError::NotFound(vec![p]))
        }
    }

    /// The link condition (Lemma 5.1; Dey et al. for d-manifolds): for an edge `ab`,
    /// `Lk(a) ∩ Lk(b) = Lk(ab)`. Returns the simplices in `Lk(a) ∩ Lk(b)` but not in `Lk(ab)`
    /// (empty when the condition holds), or `None` when `e` is not an edge.
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse = starplex::hasse::Hasse::new();
    /// h.insert(&[0.into(), 1.into(), 2.into()]).unwrap();
    /// h.insert(&[0.into(), 1.into(), 3.into()]).unwrap();
    /// let e = h.find(&[0.into(), 1.into()]).unwrap();
    /// assert!(h.link_condition_violations(e).unwrap().is_empty());
    /// // a hollow triangle: collapsing an edge would pinch it
    /// let mut h: starplex::hasse::Hasse = starplex::hasse::Hasse::new();
    /// for e in [[0, 1], [1, 2], [0, 2]] { h.insert(&e.map(starplex::ids::VertexId)).unwrap(); }
    /// let e = h.find(&[0.into(), 1.into()]).unwrap();
    /// assert_eq!(h.link_condition_violations(e).unwrap().len(), 1);
    /// ```
    pub fn link_condition_violations(&self, e: Node) -> Option<NodeSet> {
        if e.dim != 1 || !self.contains(e) {
            return None;
        }
        let vs = self.vertices(e);
        let (a, b) = (self.vertex(vs[0])?, self.vertex(vs[1])?);
        let la = self.link(a);
        let lb = self.link(b);
        let lab = self.link(e);
        Some(la.intersection(&lb).difference(&lab))
    }

    /// Fast link condition check for an edge (no allocation beyond small buffers): true when
    /// `Lk(a) ∩ Lk(b) = Lk(ab)`.
    pub(crate) fn link_condition_holds(&self, e: Node, bufs: &mut LinkBufs) -> bool {
        let vs = self.vertices(e);
        let (Some(a), Some(b)) = (self.vertex(vs[0]), self.vertex(vs[1])) else {
            return false;
        };
        self.link_ids_into(a, &mut bufs.a, &mut bufs.scratch);
        self.link_ids_into(b, &mut bufs.b, &mut bufs.scratch);
        self.link_ids_into(e, &mut bufs.ab, &mut bufs.scratch);
        let n = bufs.a.len().max(bufs.b.len()).max(bufs.ab.len());
        for k in 0..n {
            let get = |v: &mut Vec<Vec<SimplexId>>| -> SmallVec<[SimplexId; 32]> {
                let mut x: SmallVec<[SimplexId; 32]> =
                    v.get(k).map(|l| l[..].into()).unwrap_or_default();
                x.sort_unstable();
                x
            };
            let (la, lb, lab) = (get(&mut bufs.a), get(&mut bufs.b), get(&mut bufs.ab));
            // Lk(ab) ⊆ Lk(a) ∩ Lk(b) always; compare sizes of the intersection
            let (mut i, mut j, mut common) = (0, 0, 0usize);
            while i < la.len() && j < lb.len() {
                match la[i].cmp(&lb[j]) {
                    std::cmp::Ordering::Less => i += 1,
                    std::cmp::Ordering::Greater => j += 1,
                    std::cmp::Ordering::Equal => {
                        common += 1;
                        i += 1;
                        j += 1;
                    }
                }
            }
            if common != lab.len() {
                return false;
            }
        }
        true
    }
}

/// Reused buffers of the link check.
#[derive(Default)]
pub(crate) struct LinkBufs {
    a: Vec<Vec<SimplexId>>,
    b: Vec<Vec<SimplexId>>,
    ab: Vec<Vec<SimplexId>>,
    scratch: super::sets::Frontier,
}

thread_local! {
    /// Buffers of the link check, reused across calls on one thread.
    pub(crate) static LINK_BUFS: std::cell::RefCell<LinkBufs> = std::cell::RefCell::new(LinkBufs::default());
}
