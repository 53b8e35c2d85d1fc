//! Search and up/down traversal of a [`Hasse`] complex (Alg. 2 of the CASC paper): vertex
//! lookup, `find` by vertex labels, one step up or down by a key, keyed iteration of cofaces
//! and faces.
use super::complex::Hasse;
use super::insert::sorted_checked;
use super::levels::LevelTypes;
use super::Node;
use crate::ids::{SimplexId, VertexId};

impl<L: LevelTypes> Hasse<L> {
    /// The vertex node of a label.
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse = starplex::hasse::Hasse::new();
    /// h.insert(&[5.into()]).unwrap();
    /// assert!(h.vertex(5.into()).is_some());
    /// assert!(h.vertex(6.into()).is_none());
    /// ```
    #[inline]
    pub fn vertex(&self, v: VertexId) -> Option<Node> {
        self.root.get(v.0).map(|i| Node::new(0, SimplexId(i)))
    }

    #[inline]
    pub(crate) fn find_sorted(&self, vs: &[u32]) -> Option<u32> {
        let mut cur = self.root.get(*vs.first()?)?;
        for (j, &v) in vs[1..].iter().enumerate() {
            cur = self.levels[j].up.find(cur, v)?;
        }
        Some(cur)
    }

    /// The simplex with these vertices (any order), `None` when absent or degenerate.
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse = starplex::hasse::Hasse::new();
    /// h.insert(&[0.into(), 1.into(), 2.into()]).unwrap();
    /// assert_eq!(h.find(&[2.into(), 0.into()]).unwrap().dim, 1);
    /// assert!(h.find(&[0.into(), 3.into()]).is_none());
    /// ```
    pub fn find(&self, vs: &[VertexId]) -> Option<Node> {
        let s = sorted_checked(vs).ok()?;
        self.find_sorted(&s)
            .map(|i| Node::new((s.len() - 1) as u32, SimplexId(i)))
    }

    /// One step up: the coface `s ∪ {v}`.
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse = starplex::hasse::Hasse::new();
    /// h.insert(&[0.into(), 1.into(), 2.into()]).unwrap();
    /// let e = h.find(&[0.into(), 1.into()]).unwrap();
    /// let t = h.up_by(e, 2.into()).unwrap();
    /// assert_eq!(t.dim, 2);
    /// ```
    #[inline]
    pub fn up_by(&self, s: Node, v: VertexId) -> Option<Node> {
        self.levels[s.dim as usize]
            .up
            .find(s.id.0, v.0)
            .map(|i| Node::new(s.dim + 1, SimplexId(i)))
    }

    /// One step down: the face `s \ {v}` (`None` for a vertex or when `v ∉ s`).
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse = starplex::hasse::Hasse::new();
    /// let t = h.insert(&[0.into(), 1.into(), 2.into()]).unwrap();
    /// let e = h.down_by(t, 1.into()).unwrap();
    /// assert_eq!(h.vertices(e), &[0.into(), 2.into()]);
    /// ```
    #[inline]
    pub fn down_by(&self, s: Node, v: VertexId) -> Option<Node> {
        if s.dim == 0 {
            return None;
        }
        let l = &self.levels[s.dim as usize];
        let pos = l.verts(s.id.0).iter().position(|&x| x == v.0)?;
        Some(Node::new(s.dim - 1, SimplexId(l.downs(s.id.0)[pos])))
    }

    /// Alg. 2: follows the keys up (vertices added) from `s`; `None` when a step is missing.
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse = starplex::hasse::Hasse::new();
    /// h.insert(&[0.into(), 1.into(), 2.into()]).unwrap();
    /// let v = h.vertex(1.into()).unwrap();
    /// let t = h.get_up(v, &[2.into(), 0.into()]).unwrap();
    /// assert_eq!(t.dim, 2);
    /// ```
    pub fn get_up(&self, s: Node, keys: &[VertexId]) -> Option<Node> {
        keys.iter().try_fold(s, |cur, &k| self.up_by(cur, k))
    }

    /// Alg. 2 downwards: removes the keys one by one from `s`.
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse = starplex::hasse::Hasse::new();
    /// let t = h.insert(&[0.into(), 1.into(), 2.into()]).unwrap();
    /// let v = h.get_down(t, &[0.into(), 2.into()]).unwrap();
    /// assert_eq!(h.vertices(v), &[1.into()]);
    /// ```
    pub fn get_down(&self, s: Node, keys: &[VertexId]) -> Option<Node> {
        keys.iter().try_fold(s, |cur, &k| self.down_by(cur, k))
    }

    /// The cofaces one dimension up, with the vertex each adds, sorted by that vertex.
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse = starplex::hasse::Hasse::new();
    /// h.insert(&[0.into(), 1.into(), 2.into()]).unwrap();
    /// let v = h.vertex(0.into()).unwrap();
    /// let keys: Vec<_> = h.up_keyed(v).map(|(k, _)| k.0).collect();
    /// assert_eq!(keys, vec![1, 2]);
    /// ```
    pub fn up_keyed(&self, s: Node) -> impl ExactSizeIterator<Item = (VertexId, Node)> + '_ {
        let d = s.dim + 1;
        self.levels[s.dim as usize]
            .up
            .get(s.id.0)
            .iter()
            .map(move |p| (VertexId(p[0]), Node::new(d, SimplexId(p[1]))))
    }

    /// The cofaces one dimension up.
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse = starplex::hasse::Hasse::new();
    /// h.insert(&[0.into(), 1.into(), 2.into()]).unwrap();
    /// assert_eq!(h.up(h.vertex(0.into()).unwrap()).count(), 2);
    /// ```
    pub fn up(&self, s: Node) -> impl ExactSizeIterator<Item = Node> + '_ {
        self.up_keyed(s).map(|(_, n)| n)
    }

    /// The faces one dimension down with the vertex each removes, in vertex order (none for a
    /// vertex: the root is not a node).
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse = starplex::hasse::Hasse::new();
    /// let t = h.insert(&[0.into(), 1.into(), 2.into()]).unwrap();
    /// let (k, e) = h.down_keyed(t).next().unwrap();
    /// assert_eq!(k.0, 0);
    /// assert_eq!(h.vertices(e), &[1.into(), 2.into()]);
    /// ```
    pub fn down_keyed(&self, s: Node) -> impl ExactSizeIterator<Item = (VertexId, Node)> + '_ {
        let l = &self.levels[s.dim as usize];
        let d = s.dim.wrapping_sub(1);
        let vs = l.verts(s.id.0);
        let ds = l.downs(s.id.0);
        let n = ds.len();
        vs[..n]
            .iter()
            .zip(ds)
            .map(move |(&v, &f)| (VertexId(v), Node::new(d, SimplexId(f))))
    }

    /// The faces one dimension down.
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse = starplex::hasse::Hasse::new();
    /// let t = h.insert(&[0.into(), 1.into(), 2.into()]).unwrap();
    /// assert_eq!(h.down(t).count(), 3);
    /// ```
    pub fn down(&self, s: Node) -> impl ExactSizeIterator<Item = Node> + '_ {
        self.down_keyed(s).map(|(_, n)| n)
    }

    /// True when `s` is a node of this complex.
    ///
    /// ```
    /// use starplex::hasse::{Hasse, Node};
    /// let mut h: Hasse = Hasse::new();
    /// let v = h.insert(&[0.into()]).unwrap();
    /// assert!(h.contains(v));
    /// assert!(!h.contains(Node::new(0, 1.into())));
    /// ```
    pub fn contains(&self, s: Node) -> bool {
        self.levels
            .get(s.dim as usize)
            .is_some_and(|l| l.alive(s.id.0))
    }
}
