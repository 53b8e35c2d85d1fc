//! Local editing, each a check-then-mutate pair, for triangle meshes and, by the same code, for
//! tetrahedral meshes and beyond:
//! * edge collapse with the link condition (`can_collapse` / `collapse`);
//! * bistellar flips (`can_flip` / `flip`): the 2-2 edge flip of a triangle mesh, the 2-3 (face)
//!   and 3-2 (edge) flips of a tetrahedral mesh, and their higher-dimensional forms: a simplex
//!   `s` whose link is the boundary of a missing simplex `t` is replaced by `t` and its joins;
//! * stellar splits (`can_split` / `split`): edge split, face split, cell split;
//! * Laplacian smoothing of vertex positions stored as level-0 data.
//!
//! The flips are topological: they do not look at positions. `can_flip_geometric` adds an exact
//! test (robust `orient2d` / `orient3d`) for planar triangle meshes and tetrahedral meshes.
use super::complex::Hasse;
use super::decimate::{LinkBufs, LINK_BUFS};
use super::levels::{At, LevelTypes, MergeAll};
use super::{HasseError, Node};
use crate::ids::VertexId;

/// Why an edit is refused.
///
/// ```
/// use starplex::hasse::{Hasse, EditError};
/// let mut h: Hasse = Hasse::new();
/// let v = h.insert(&[0.into()]).unwrap();
/// assert!(matches!(h.can_collapse(v), Err(EditError::NotAnEdge(_))));
/// ```
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum EditError {
    /// The node is not an edge.
    #[error("{0:?} is not an edge of the complex")]
    NotAnEdge(Node),
    /// The node is not in the complex.
    #[error("{0:?} is not in the complex")]
    NotANode(Node),
    /// The link condition fails: collapsing would change the topology.
    #[error("edge {edge:?} fails the link condition (Lk(a) ∩ Lk(b) has {extra} simplices not in Lk(ab))")]
    LinkCondition {
        /// The edge's vertices.
        edge: Vec<VertexId>,
        /// How many simplices are in Lk(a) ∩ Lk(b) but not in Lk(ab).
        extra: usize,
    },
    /// The link of the simplex is not the boundary of a missing simplex.
    #[error("simplex {simplex:?} cannot be flipped: {why}")]
    NotFlippable {
        /// The simplex's vertices.
        simplex: Vec<VertexId>,
        /// Why.
        why: String,
    },
    /// A vertex cannot be split.
    #[error("a vertex cannot be split")]
    SplitVertex,
    /// An error of the complex.
    #[error(transparent)]
    Hasse(#[from] HasseError),
}

/// A vertex datum that holds a position in 3D (for smoothing and geometry).
///
/// ```
/// use starplex::hasse::Position;
/// let mut p = [1.0, 2.0, 3.0];
/// p.set_position([0.0; 3]);
/// assert_eq!(p.position(), [0.0; 3]);
/// ```
pub trait Position {
    /// The position.
    fn position(&self) -> [f64; 3];
    /// Moves it.
    fn set_position(&mut self, p: [f64; 3]);
}

impl Position for [f64; 3] {
    fn position(&self) -> [f64; 3] {
        *self
    }
    fn set_position(&mut self, p: [f64; 3]) {
        *self = p;
    }
}

impl<L: LevelTypes> Hasse<L> {
    /// Checks that the edge `e` can be collapsed without changing the topology (the link
    /// condition, Lemma 5.1 of CASC; Dey et al. for manifolds of any dimension).
    ///
    /// # Errors
    /// [`EditError::NotAnEdge`], [`EditError::LinkCondition`].
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse = starplex::hasse::Hasse::new();
    /// h.insert(&[0.into(), 1.into(), 2.into()]).unwrap();
    /// let e = h.find(&[0.into(), 1.into()]).unwrap();
    /// h.can_collapse(e).unwrap();
    /// ```
    pub fn can_collapse(&self, e: Node) -> Result<(), EditError> {
        if e.dim != 1 || !self.contains(e) {
            return Err(EditError::NotAnEdge(e));
        }
        let holds = LINK_BUFS.with(|b| match b.try_borrow_mut() {
            Ok(mut bufs) => self.link_condition_holds(e, &mut bufs),
            Err(_) => self.link_condition_holds(e, &mut LinkBufs::default()),
        });
        if holds {
            Ok(())
        } else {
            let extra = self.link_condition_violations(e).map_or(0, |s| s.len());
            Err(EditError::LinkCondition {
                edge: self.vertices(e).to_vec(),
                extra,
            })
        }
    }

    /// Collapses the edge `ab` into `a` (the smaller label), merging data with `merge`
    /// (see [`decimate`](Self::decimate)). Does not check the link condition: call
    /// [`can_collapse`](Self::can_collapse) first. Returns the surviving vertex.
    ///
    /// # Errors
    /// [`EditError::NotAnEdge`].
    ///
    /// ```
    /// use starplex::hasse::{Hasse, KeepFirst};
    /// let mut h: Hasse = Hasse::new();
    /// h.insert(&[0.into(), 1.into(), 2.into()]).unwrap();
    /// h.insert(&[1.into(), 2.into(), 3.into()]).unwrap();
    /// let e = h.find(&[1.into(), 2.into()]).unwrap();
    /// h.can_collapse(e).unwrap();
    /// assert_eq!(h.collapse(e, &mut KeepFirst).unwrap().0, 1);
    /// assert_eq!(h.f_vector(), vec![3, 2]);
    /// ```
    pub fn collapse<C: MergeAll<L>>(
        &mut self,
        e: Node,
        merge: &mut C,
    ) -> Result<VertexId, EditError> {
        if e.dim != 1 || !self.contains(e) {
            return Err(EditError::NotAnEdge(e));
        }
        let a = self.vertices(e)[0];
        Ok(self.decimate_into(e, Some(a), merge)?)
    }

    /// Checks a bistellar flip of `s`: its link must be the boundary of a simplex `t` that is
    /// not in the complex. Returns `t`'s vertices, sorted.
    ///
    /// # Errors
    /// [`EditError::NotANode`], [`EditError::NotFlippable`].
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse = starplex::hasse::Hasse::new();
    /// h.insert(&[0.into(), 1.into(), 2.into()]).unwrap();
    /// h.insert(&[1.into(), 2.into(), 3.into()]).unwrap();
    /// let e = h.find(&[1.into(), 2.into()]).unwrap();
    /// assert_eq!(h.can_flip(e).unwrap(), vec![0.into(), 3.into()]);
    /// ```
    pub fn can_flip(&self, s: Node) -> Result<Vec<VertexId>, EditError> {
        if !self.contains(s) {
            return Err(EditError::NotANode(s));
        }
        let refuse = |why: String| EditError::NotFlippable {
            simplex: self.vertices(s).to_vec(),
            why,
        };
        let lk = self.link(s);
        let mut t: Vec<VertexId> = lk
            .level(0)
            .iter()
            .map(|&i| self.vertices(Node::new(0, i))[0])
            .collect();
        t.sort_unstable();
        if t.len() < 2 {
            return Err(refuse(format!("its link has {} vertices", t.len())));
        }
        if t.len() > 24 {
            return Err(refuse("its link is too large".into()));
        }
        let want = (1usize << t.len()) - 2;
        if lk.len() != want || !lk.level(t.len() - 1).is_empty() {
            return Err(refuse(format!(
                "its link is not the boundary of the simplex {:?}",
                t.iter().map(|v| v.0).collect::<Vec<_>>()
            )));
        }
        if self.find(&t).is_some() {
            return Err(refuse(format!(
                "the simplex {:?} is already in the complex",
                t.iter().map(|v| v.0).collect::<Vec<_>>()
            )));
        }
        Ok(t)
    }

    /// Performs the bistellar flip checked by [`can_flip`](Self::can_flip): removes the star of
    /// `s` and inserts `(s \ {v}) ∪ t` for every vertex `v` of `s` (new simplices get default
    /// data). Returns the node of `t`.
    ///
    /// # Errors
    /// As [`can_flip`](Self::can_flip).
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse = starplex::hasse::Hasse::new();
    /// h.insert(&[0.into(), 1.into(), 2.into()]).unwrap();
    /// h.insert(&[1.into(), 2.into(), 3.into()]).unwrap();
    /// let e = h.find(&[1.into(), 2.into()]).unwrap();
    /// h.flip(e).unwrap();
    /// assert!(h.find(&[0.into(), 3.into()]).is_some());
    /// assert!(h.find(&[1.into(), 2.into()]).is_none());
    /// assert_eq!(h.f_vector(), vec![4, 5, 2]);
    /// ```
    pub fn flip(&mut self, s: Node) -> Result<Node, EditError> {
        let t = self.can_flip(s)?;
        let sv = self.vertices(s).to_vec();
        self.remove(s)?;
        let mut last = None;
        for (i, _) in sv.iter().enumerate() {
            let mut n: Vec<VertexId> = sv
                .iter()
                .enumerate()
                .filter(|&(j, _)| j != i)
                .map(|(_, &v)| v)
                .collect();
            n.extend_from_slice(&t);
            last = Some(self.insert(&n)?);
        }
        let tn = self.find(&t).or(last).ok_or(EditError::NotANode(s))?;
        Ok(tn)
    }

    /// Checks a stellar split of `s` (edge split, face split, ...).
    ///
    /// # Errors
    /// [`EditError::NotANode`], [`EditError::SplitVertex`].
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse = starplex::hasse::Hasse::new();
    /// let e = h.insert(&[0.into(), 1.into()]).unwrap();
    /// h.can_split(e).unwrap();
    /// ```
    pub fn can_split(&self, s: Node) -> Result<(), EditError> {
        if !self.contains(s) {
            return Err(EditError::NotANode(s));
        }
        if s.dim == 0 {
            return Err(EditError::SplitVertex);
        }
        Ok(())
    }

    /// Stellar split of `s` at a new vertex `p` (a fresh label): every `τ ⊇ s` is replaced by
    /// `p ∪ (τ \ s) ∪ f` for every facet `f` of `s`. An edge split of a triangle mesh turns the
    /// two triangles at the edge into four; a face split turns a triangle into three. New
    /// simplices get default data. Returns `p`.
    ///
    /// # Errors
    /// As [`can_split`](Self::can_split), and [`HasseError::NoFreeLabel`].
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse = starplex::hasse::Hasse::new();
    /// let t = h.insert(&[0.into(), 1.into(), 2.into()]).unwrap();
    /// let p = h.split(t).unwrap();
    /// assert_eq!(p.0, 3);
    /// assert_eq!(h.f_vector(), vec![4, 6, 3]);
    /// ```
    pub fn split(&mut self, s: Node) -> Result<VertexId, EditError> {
        self.can_split(s)?;
        let p = self.fresh_label().ok_or(HasseError::NoFreeLabel)?;
        let sv = self.vertices(s).to_vec();
        // maximal simplices of the star (those without cofaces)
        let st = self.star(s);
        let tops: Vec<Vec<VertexId>> = st
            .iter()
            .filter(|&n| self.up(n).len() == 0)
            .map(|n| self.vertices(n).to_vec())
            .collect();
        self.remove(s)?;
        for tau in tops {
            let rest: Vec<VertexId> = tau.iter().copied().filter(|v| !sv.contains(v)).collect();
            for i in 0..sv.len() {
                let mut n: Vec<VertexId> = rest.clone();
                n.push(p);
                n.extend(
                    sv.iter()
                        .enumerate()
                        .filter(|&(j, _)| j != i)
                        .map(|(_, &v)| v),
                );
                self.insert(&n)?;
            }
        }
        Ok(p)
    }

    /// True when vertex `v` is on the boundary: some `(d-1)`-simplex of its star has exactly one
    /// coface, `d` being the dimension of the complex.
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse = starplex::hasse::Hasse::new();
    /// h.insert(&[0.into(), 1.into(), 2.into()]).unwrap();
    /// assert!(h.is_boundary_vertex(h.vertex(0.into()).unwrap()));
    /// ```
    pub fn is_boundary_vertex(&self, v: Node) -> bool {
        let Some(d) = self.dim() else { return false };
        if d == 0 {
            return false;
        }
        let st = self.star_ids(v);
        st.get(d - 1)
            .is_some_and(|l| l.iter().any(|&i| self.levels[d - 1].up.get(i).len() == 1))
    }

    /// Laplacian smoothing of the positions stored on vertices: each pass moves every vertex by
    /// `lambda` times the offset to the average of its neighbours (by edges). Boundary vertices
    /// stay put when `fix_boundary`.
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse<([f64; 3],)> = starplex::hasse::Hasse::new();
    /// for (i, p) in [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0], [2.0, 2.0, 0.0], [1.5, 1.5, 1.0]].iter().enumerate() {
    ///     h.insert_with::<0>(&[(i as u32).into()], *p).unwrap();
    /// }
    /// for t in [[0, 1, 4], [1, 3, 4], [3, 2, 4], [2, 0, 4]] {
    ///     h.insert(&t.map(starplex::ids::VertexId)).unwrap();
    /// }
    /// h.smooth_laplacian(1.0, 1, true);
    /// let c = h.vertex(4.into()).unwrap();
    /// assert_eq!(*h.data::<0>(c.id), [1.0, 1.0, 0.0]);
    /// ```
    pub fn smooth_laplacian(&mut self, lambda: f64, iterations: usize, fix_boundary: bool)
    where
        L: At<0>,
        <L as At<0>>::Data: Position,
    {
        let n = self.n_slots(0);
        let fixed: Vec<bool> = (0..n)
            .map(|i| {
                let v = Node::new(0, (i as u32).into());
                !self.contains(v) || (fix_boundary && self.is_boundary_vertex(v))
            })
            .collect();
        for _ in 0..iterations {
            let col = self.level_data::<0>();
            let mut new_pos = Vec::with_capacity(n);
            for (i, &fx) in fixed.iter().enumerate() {
                let p = col[i].position();
                if fx {
                    new_pos.push(p);
                    continue;
                }
                let v = Node::new(0, (i as u32).into());
                let mut sum = [0.0; 3];
                let mut cnt = 0usize;
                for e in self.up(v) {
                    for w in self.down(e) {
                        if w != v {
                            let q = col[w.id.index()].position();
                            for c in 0..3 {
                                sum[c] += q[c];
                            }
                            cnt += 1;
                        }
                    }
                }
                if cnt == 0 {
                    new_pos.push(p);
                    continue;
                }
                let mut r = p;
                for c in 0..3 {
                    r[c] = p[c] + lambda * (sum[c] / cnt as f64 - p[c]);
                }
                new_pos.push(r);
            }
            let col = self.level_data_mut::<0>();
            for (d, p) in col.iter_mut().zip(new_pos) {
                d.set_position(p);
            }
        }
    }
}
