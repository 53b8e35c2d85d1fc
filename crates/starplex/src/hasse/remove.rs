//! Removal from a [`Hasse`] complex: a simplex with its star, sets closed under cofaces, and
//! [`compact`](Hasse::compact), the dense renumbering after edits.
use super::arena::UpArena;
use super::complex::Hasse;
use super::levels::LevelTypes;
use super::storage::{VertexIndex, NONE};
use super::{HasseError, Node};
use crate::ids::VertexId;

impl<L: LevelTypes> Hasse<L> {
    /// Removes one node that has no cofaces: detaches it from its faces and frees its slot.
    pub(crate) fn remove_leaf_node(&mut self, k: usize, n: u32) {
        debug_assert!(self.levels[k].up.get(n).is_empty());
        if k == 0 {
            let lab = self.levels[0].verts(n)[0];
            self.root.remove(lab);
        } else {
            let (lo, hi) = self.levels.split_at_mut(k);
            let l = &hi[0];
            let vs = l.verts(n);
            let ds = l.downs(n);
            for i in 0..=k {
                lo[k - 1].up.remove(ds[i], vs[i]);
            }
        }
        let l = &mut self.levels[k];
        l.up.kill(n);
        l.free.push(n);
        L::reset(&mut self.data, k, n as usize);
    }

    /// Renumbers every level densely (ids `0..n_simplices(k)` in the old order), dropping freed
    /// slots; data columns, incidences and the vertex lookup follow. Invalidates held ids.
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse<(u32,)> = starplex::hasse::Hasse::new();
    /// h.insert(&[0.into(), 1.into(), 2.into()]).unwrap();
    /// *h.data_mut::<0>(h.vertex(2.into()).unwrap().id) = 9;
    /// h.remove_vertices(&[0.into()]).unwrap();
    /// h.compact();
    /// assert_eq!(h.n_slots(0), 2);
    /// assert_eq!(*h.data::<0>(h.vertex(2.into()).unwrap().id), 9);
    /// assert!(h.is_valid());
    /// ```
    pub fn compact(&mut self) {
        let nl = self.levels.len();
        let mut maps: Vec<Vec<u32>> = Vec::with_capacity(nl);
        for k in 0..nl {
            let l = &self.levels[k];
            let keep: Vec<bool> = (0..l.slots() as u32).map(|i| !l.up.is_dead(i)).collect();
            let mut map = vec![NONE; keep.len()];
            let mut next = 0u32;
            for (i, &kp) in keep.iter().enumerate() {
                if kp {
                    map[i] = next;
                    next += 1;
                }
            }
            let k1 = k + 1;
            let mut verts = Vec::with_capacity(next as usize * k1);
            let mut down = Vec::with_capacity(if k > 0 { next as usize * k1 } else { 0 });
            for (i, &kp) in keep.iter().enumerate() {
                if kp {
                    verts.extend_from_slice(&l.verts[i * k1..(i + 1) * k1]);
                    if k > 0 {
                        down.extend(
                            l.down[i * k1..(i + 1) * k1]
                                .iter()
                                .map(|&f| maps[k - 1][f as usize]),
                        );
                    }
                }
            }
            L::retain(&mut self.data, k, &keep);
            let l = &mut self.levels[k];
            l.verts = verts;
            l.down = down;
            l.free = Vec::new();
            maps.push(map);
        }
        // rebuild the up lists with exact capacities
        for k in 0..nl {
            let n = self.levels[k].verts.len() / (k + 1);
            let mut deg = vec![0u32; n];
            if k + 1 < nl {
                for &f in &self.levels[k + 1].down {
                    deg[f as usize] += 1;
                }
            }
            let mut up = UpArena::default();
            for d in deg {
                up.push_node(d);
            }
            self.levels[k].up = up;
        }
        for k in 1..nl {
            let (lo, hi) = self.levels.split_at_mut(k);
            let l = &hi[0];
            for i in 0..l.verts.len() / (k + 1) {
                for j in 0..=k {
                    lo[k - 1].up.insert(
                        l.down[i * (k + 1) + j],
                        l.verts[i * (k + 1) + j],
                        i as u32,
                    );
                }
            }
        }
        let mut root = VertexIndex::default();
        if let Some(l) = self.levels.first() {
            root.reserve_dense(
                self.max_label
                    .map_or(0, |m| m as usize + 1)
                    .min(2 * l.verts.len() + 4096),
            );
            for (i, &lab) in l.verts.iter().enumerate() {
                root.insert(lab, i as u32);
            }
        }
        self.root = root;
    }

    /// Removes a set of nodes closed under cofaces (a union of stars), given per level.
    pub(crate) fn remove_upward_closed(&mut self, mut per_level: Vec<Vec<u32>>) {
        for k in (0..per_level.len()).rev() {
            let ids = &mut per_level[k];
            ids.sort_unstable();
            ids.dedup();
            for &n in ids.iter() {
                self.remove_leaf_node(k, n);
            }
        }
    }

    /// Removes a simplex and its star (every coface); returns how many simplices went.
    ///
    /// # Errors
    /// [`HasseError::NotANode`] when `s` is not in the complex.
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse = starplex::hasse::Hasse::new();
    /// h.insert(&[0.into(), 1.into(), 2.into()]).unwrap();
    /// let e = h.find(&[0.into(), 1.into()]).unwrap();
    /// assert_eq!(h.remove(e).unwrap(), 2);
    /// assert_eq!(h.f_vector(), vec![3, 2]);
    /// ```
    pub fn remove(&mut self, s: Node) -> Result<usize, HasseError> {
        if !self.contains(s) {
            return Err(HasseError::NotANode(s));
        }
        let st = self.star_ids(s);
        let n = st.iter().map(|v| v.len()).sum();
        self.remove_upward_closed(st);
        Ok(n)
    }

    /// Removes the simplex with these vertices and its star.
    ///
    /// # Errors
    /// [`HasseError::NotFound`] when absent.
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse = starplex::hasse::Hasse::new();
    /// h.insert(&[0.into(), 1.into(), 2.into()]).unwrap();
    /// h.remove_vertices(&[2.into()]).unwrap();
    /// assert_eq!(h.f_vector(), vec![2, 1]);
    /// ```
    pub fn remove_vertices(&mut self, vs: &[VertexId]) -> Result<usize, HasseError> {
        let s = self
            .find(vs)
            .ok_or_else(|| HasseError::NotFound(vs.to_vec()))?;
        self.remove(s)
    }

    /// The star of `s` (all cofaces including `s`) as ids per level, each found exactly once
    /// (see [`for_each_star_level`](Hasse::for_each_star_level)).
    pub(crate) fn star_ids(&self, s: Node) -> Vec<Vec<u32>> {
        let mut out: Vec<Vec<u32>> = vec![Vec::new(); self.levels.len()];
        let mut bufs = StarBufs::default();
        self.for_each_star_level(s.dim as usize, s.id.0, &mut bufs, |j, level| {
            out[j].extend(level.iter().map(|x| x.0));
        });
        out
    }

    /// Walks the star of node `id` of level `k` level by level: calls `f(level, cofaces)`
    /// with the cofaces of that level as (node id, the vertex that led to it) pairs, first
    /// `(k, [(id, 0)])`. Each coface is found exactly once: it is reached only from its parent
    /// without its largest vertex outside the start. `bufs` is scratch space, reusable across
    /// calls.
    pub(crate) fn for_each_star_level(
        &self,
        k: usize,
        id: u32,
        bufs: &mut StarBufs,
        mut f: impl FnMut(usize, &[(u32, u32)]),
    ) {
        let StarBufs { cur, next } = bufs;
        cur.clear();
        cur.push((id, 0));
        f(k, cur);
        let mut first = true;
        let mut j = k;
        while !cur.is_empty() && j + 1 < self.levels.len() {
            next.clear();
            for &(t, m) in cur.iter() {
                for p in self.levels[j].up.get(t) {
                    if first || p[0] > m {
                        next.push((p[1], p[0]));
                    }
                }
            }
            first = false;
            j += 1;
            f(j, next);
            std::mem::swap(cur, next);
        }
    }
}

/// Scratch space of [`Hasse::for_each_star_level`]: the current and the next level of the walk,
/// as (coface id, the vertex that led to it) pairs.
#[derive(Default)]
pub(crate) struct StarBufs {
    cur: Vec<(u32, u32)>,
    next: Vec<(u32, u32)>,
}
