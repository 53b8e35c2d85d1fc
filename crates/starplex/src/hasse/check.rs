//! Validation of a [`Hasse`] complex: every structural invariant, with the first problem found.
use super::complex::Hasse;
use super::levels::LevelTypes;
use super::storage::Verts;
use super::{HasseError, Node};
use crate::ids::SimplexId;

impl<L: LevelTypes> Hasse<L> {
    /// Checks every invariant: sorted distinct vertices, every face present and the down link
    /// right, up and down incidences symmetric, the vertex lookup exact, no orphans (every
    /// non-vertex node has all its faces; every vertex is in the lookup). Returns the first
    /// problem.
    ///
    /// # Errors
    /// [`HasseError::Invalid`] naming the node and the problem.
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse = starplex::hasse::Hasse::new();
    /// h.insert(&[0.into(), 1.into(), 2.into(), 3.into()]).unwrap();
    /// h.check().unwrap();
    /// ```
    pub fn check(&self) -> Result<(), HasseError> {
        let bad = |s: Node, what: String| Err(HasseError::Invalid { node: s, what });
        for (k, l) in self.levels.iter().enumerate() {
            let mut dead = 0;
            for i in 0..l.slots() as u32 {
                dead += l.up.is_dead(i) as usize;
            }
            if dead != l.free.len() || l.free.iter().any(|&f| l.alive(f)) {
                return bad(
                    Node::new(k as u32, SimplexId(0)),
                    "free list differs from the removed slots".into(),
                );
            }
        }
        if self.root.len() != self.n_simplices(0) {
            return bad(
                Node::new(0, SimplexId(0)),
                "vertex lookup size differs".into(),
            );
        }
        let mut n_up = vec![0usize; self.levels.len()];
        for (k, l) in self.levels.iter().enumerate() {
            if l.verts.len() != l.slots() * (k + 1) || (k > 0 && l.down.len() != l.verts.len()) {
                return bad(Node::new(k as u32, SimplexId(0)), "array lengths".into());
            }
            for i in 0..l.slots() as u32 {
                if l.up.is_dead(i) {
                    continue;
                }
                let s = Node::new(k as u32, SimplexId(i));
                let vs = l.verts(i);
                if vs.windows(2).any(|w| w[0] >= w[1]) {
                    return bad(s, "vertices not sorted and distinct".into());
                }
                if k == 0 {
                    if self.root.get(vs[0]) != Some(i) {
                        return bad(s, "vertex lookup wrong".into());
                    }
                } else {
                    for (pos, &f) in l.downs(i).iter().enumerate() {
                        let fl = &self.levels[k - 1];
                        if !fl.alive(f) {
                            return bad(s, format!("face {pos} out of range"));
                        }
                        let fv = fl.verts(f);
                        let expect: Verts = vs
                            .iter()
                            .enumerate()
                            .filter(|&(j, _)| j != pos)
                            .map(|(_, &x)| x)
                            .collect();
                        if fv != &expect[..] {
                            return bad(s, format!("face {pos} has the wrong vertices"));
                        }
                        if fl.up.find(f, vs[pos]) != Some(i) {
                            return bad(s, format!("face {pos} lacks the up incidence"));
                        }
                    }
                }
                let ups = l.up.get(i);
                n_up[k] += ups.len();
                if ups.windows(2).any(|w| w[0][0] >= w[1][0]) {
                    return bad(s, "up list not sorted".into());
                }
                for p in ups {
                    let Some(al) = self.levels.get(k + 1) else {
                        return bad(s, "up incidence above the top level".into());
                    };
                    if !al.alive(p[1]) {
                        return bad(s, "up incidence out of range".into());
                    }
                    let cv = al.verts(p[1]);
                    let Some(pos) = cv.iter().position(|&x| x == p[0]) else {
                        return bad(s, "up key not in the coface".into());
                    };
                    if al.downs(p[1])[pos] != i {
                        return bad(s, "up incidence without its down incidence".into());
                    }
                }
            }
        }
        for k in 1..self.levels.len() {
            if n_up[k - 1] != self.levels[k].len() * (k + 1) {
                return bad(
                    Node::new(k as u32, SimplexId(0)),
                    "incidence counts differ".into(),
                );
            }
        }
        Ok(())
    }

    /// True when [`check`](Self::check) passes.
    ///
    /// ```
    /// assert!(starplex::hasse::Hasse::<()>::new().is_valid());
    /// ```
    pub fn is_valid(&self) -> bool {
        self.check().is_ok()
    }
}
