//! Simplex sets typed per level with set algebra, simplex maps, star / closure / link,
//! neighbours (Alg. 3), k-rings and breadth-first visitors.
use std::collections::{BTreeMap, VecDeque};

use super::complex::Hasse;
use super::levels::LevelTypes;
use super::Node;
use crate::ids::{SimplexId, VertexId};

/// A set of simplices of one complex, kept per dimension as sorted id lists (like CASC's
/// `NodeSet`, one set per level). Ids are those of the complex when the set was made:
/// ids stay valid while the complex is edited, except that the slot of a removed simplex is
/// reused by a later insertion and [`Hasse::compact`] renumbers everything.
///
/// ```
/// use starplex::hasse::{Hasse, NodeSet};
/// let mut h: Hasse = Hasse::new();
/// h.insert(&[0.into(), 1.into(), 2.into()]).unwrap();
/// let a = h.star(h.vertex(0.into()).unwrap());
/// let b = h.star(h.vertex(1.into()).unwrap());
/// let both = a.intersection(&b);
/// assert_eq!(h.set_to_vertex_lists(&both), vec![vec![0, 1], vec![0, 1, 2]]);
/// assert_eq!(a.union(&b).len(), 6);
/// assert_eq!(a.difference(&b).len(), 2);
/// ```
#[derive(Clone, Debug, Default, PartialEq, Eq, Hash)]
pub struct NodeSet {
    levels: Vec<Vec<SimplexId>>,
}

impl NodeSet {
    /// The empty set.
    ///
    /// ```
    /// assert!(starplex::hasse::NodeSet::new().is_empty());
    /// ```
    pub fn new() -> Self {
        Self::default()
    }

    /// From unsorted ids per level (sorted and deduplicated here).
    pub(crate) fn from_levels(mut levels: Vec<Vec<SimplexId>>) -> Self {
        for l in &mut levels {
            l.sort_unstable();
            l.dedup();
        }
        let mut s = NodeSet { levels };
        s.trim();
        s
    }

    fn trim(&mut self) {
        while self.levels.last().is_some_and(|l| l.is_empty()) {
            self.levels.pop();
        }
    }

    /// Adds a simplex; returns whether it was new.
    ///
    /// ```
    /// use starplex::hasse::{Node, NodeSet};
    /// let mut s = NodeSet::new();
    /// assert!(s.insert(Node::new(1, 4.into())));
    /// assert!(!s.insert(Node::new(1, 4.into())));
    /// assert!(s.contains(Node::new(1, 4.into())));
    /// ```
    pub fn insert(&mut self, n: Node) -> bool {
        let k = n.dim as usize;
        if self.levels.len() <= k {
            self.levels.resize(k + 1, Vec::new());
        }
        let l = &mut self.levels[k];
        match l.binary_search(&n.id) {
            Ok(_) => false,
            Err(p) => {
                l.insert(p, n.id);
                true
            }
        }
    }

    /// Removes a simplex; returns whether it was there.
    ///
    /// ```
    /// use starplex::hasse::{Node, NodeSet};
    /// let mut s = NodeSet::new();
    /// s.insert(Node::new(0, 1.into()));
    /// assert!(s.remove(Node::new(0, 1.into())));
    /// assert!(s.is_empty());
    /// ```
    pub fn remove(&mut self, n: Node) -> bool {
        let Some(l) = self.levels.get_mut(n.dim as usize) else {
            return false;
        };
        match l.binary_search(&n.id) {
            Ok(p) => {
                l.remove(p);
                self.trim();
                true
            }
            Err(_) => false,
        }
    }

    /// Membership.
    ///
    /// ```
    /// assert!(!starplex::hasse::NodeSet::new().contains(starplex::hasse::Node::new(0, 0.into())));
    /// ```
    pub fn contains(&self, n: Node) -> bool {
        self.levels
            .get(n.dim as usize)
            .is_some_and(|l| l.binary_search(&n.id).is_ok())
    }

    /// Number of simplices.
    ///
    /// ```
    /// assert_eq!(starplex::hasse::NodeSet::new().len(), 0);
    /// ```
    pub fn len(&self) -> usize {
        self.levels.iter().map(|l| l.len()).sum()
    }

    /// True when empty.
    ///
    /// ```
    /// assert!(starplex::hasse::NodeSet::new().is_empty());
    /// ```
    pub fn is_empty(&self) -> bool {
        self.levels.iter().all(|l| l.is_empty())
    }

    /// The ids of dimension `k`, sorted.
    ///
    /// ```
    /// use starplex::hasse::{Node, NodeSet};
    /// let mut s = NodeSet::new();
    /// s.insert(Node::new(2, 9.into()));
    /// assert_eq!(s.level(2), &[9.into()]);
    /// assert!(s.level(0).is_empty());
    /// ```
    pub fn level(&self, k: usize) -> &[SimplexId] {
        self.levels.get(k).map_or(&[], |l| &l[..])
    }

    /// Every simplex, by dimension then id.
    ///
    /// ```
    /// use starplex::hasse::{Node, NodeSet};
    /// let mut s = NodeSet::new();
    /// s.insert(Node::new(1, 0.into()));
    /// s.insert(Node::new(0, 3.into()));
    /// assert_eq!(s.iter().next(), Some(Node::new(0, 3.into())));
    /// ```
    pub fn iter(&self) -> impl Iterator<Item = Node> + '_ {
        self.levels
            .iter()
            .enumerate()
            .flat_map(|(k, l)| l.iter().map(move |&i| Node::new(k as u32, i)))
    }

    fn merge(&self, o: &Self, keep_a: bool, keep_b: bool, keep_both: bool) -> Self {
        let n = self.levels.len().max(o.levels.len());
        let mut levels = Vec::with_capacity(n);
        for k in 0..n {
            let (a, b) = (self.level(k), o.level(k));
            let mut r = Vec::new();
            let (mut i, mut j) = (0, 0);
            while i < a.len() || j < b.len() {
                if j == b.len() || (i < a.len() && a[i] < b[j]) {
                    if keep_a {
                        r.push(a[i]);
                    }
                    i += 1;
                } else if i == a.len() || b[j] < a[i] {
                    if keep_b {
                        r.push(b[j]);
                    }
                    j += 1;
                } else {
                    if keep_both {
                        r.push(a[i]);
                    }
                    i += 1;
                    j += 1;
                }
            }
            levels.push(r);
        }
        let mut s = NodeSet { levels };
        s.trim();
        s
    }

    /// Set union.
    ///
    /// ```
    /// use starplex::hasse::{Node, NodeSet};
    /// let mut a = NodeSet::new();
    /// a.insert(Node::new(0, 0.into()));
    /// let mut b = NodeSet::new();
    /// b.insert(Node::new(1, 0.into()));
    /// assert_eq!(a.union(&b).len(), 2);
    /// ```
    pub fn union(&self, o: &Self) -> Self {
        self.merge(o, true, true, true)
    }

    /// Set intersection.
    ///
    /// ```
    /// use starplex::hasse::{Node, NodeSet};
    /// let mut a = NodeSet::new();
    /// a.insert(Node::new(0, 0.into()));
    /// assert_eq!(a.intersection(&NodeSet::new()), NodeSet::new());
    /// ```
    pub fn intersection(&self, o: &Self) -> Self {
        self.merge(o, false, false, true)
    }

    /// Set difference `self \ o`.
    ///
    /// ```
    /// use starplex::hasse::{Node, NodeSet};
    /// let mut a = NodeSet::new();
    /// a.insert(Node::new(0, 0.into()));
    /// assert_eq!(a.difference(&a), NodeSet::new());
    /// ```
    pub fn difference(&self, o: &Self) -> Self {
        self.merge(o, true, false, false)
    }

    /// True when every simplex of `self` is in `o`.
    ///
    /// ```
    /// use starplex::hasse::NodeSet;
    /// assert!(NodeSet::new().is_subset(&NodeSet::new()));
    /// ```
    pub fn is_subset(&self, o: &Self) -> bool {
        self.difference(o).is_empty()
    }
}

/// A map from simplices, keyed by their vertex tuples (so it survives renumbering), ordered by
/// dimension then lexicographically. CASC's `NodeMap`; decimation plans use it.
///
/// ```
/// use starplex::hasse::NodeMap;
/// let mut m: NodeMap<&str> = NodeMap::new();
/// m.insert(&[2.into(), 1.into()], "edge");
/// m.insert(&[5.into()], "vertex");
/// assert_eq!(m.get(&[1.into(), 2.into()]), Some(&"edge"));
/// let keys: Vec<_> = m.iter().map(|(k, _)| k.len()).collect();
/// assert_eq!(keys, vec![1, 2]);
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct NodeMap<T> {
    map: BTreeMap<(usize, Vec<VertexId>), T>,
}

impl<T> Default for NodeMap<T> {
    fn default() -> Self {
        NodeMap {
            map: BTreeMap::new(),
        }
    }
}

impl<T> NodeMap<T> {
    /// An empty map.
    ///
    /// ```
    /// assert!(starplex::hasse::NodeMap::<u8>::new().is_empty());
    /// ```
    pub fn new() -> Self {
        Self::default()
    }

    fn key(vs: &[VertexId]) -> (usize, Vec<VertexId>) {
        let mut v = vs.to_vec();
        v.sort_unstable();
        (v.len(), v)
    }

    /// Inserts or replaces; returns the old value.
    ///
    /// ```
    /// let mut m = starplex::hasse::NodeMap::new();
    /// assert_eq!(m.insert(&[1.into()], 1), None);
    /// assert_eq!(m.insert(&[1.into()], 2), Some(1));
    /// ```
    pub fn insert(&mut self, vs: &[VertexId], x: T) -> Option<T> {
        self.map.insert(Self::key(vs), x)
    }

    /// The value at a simplex.
    ///
    /// ```
    /// let m = starplex::hasse::NodeMap::<u8>::new();
    /// assert_eq!(m.get(&[0.into()]), None);
    /// ```
    pub fn get(&self, vs: &[VertexId]) -> Option<&T> {
        self.map.get(&Self::key(vs))
    }

    /// The value at a simplex, inserted with `f` when missing.
    ///
    /// ```
    /// let mut m = starplex::hasse::NodeMap::<Vec<u8>>::new();
    /// m.entry_or_insert_with(&[0.into()], Vec::new).push(3);
    /// assert_eq!(m.get(&[0.into()]), Some(&vec![3]));
    /// ```
    pub fn entry_or_insert_with(&mut self, vs: &[VertexId], f: impl FnOnce() -> T) -> &mut T {
        self.map.entry(Self::key(vs)).or_insert_with(f)
    }

    /// Number of entries.
    ///
    /// ```
    /// assert_eq!(starplex::hasse::NodeMap::<u8>::new().len(), 0);
    /// ```
    pub fn len(&self) -> usize {
        self.map.len()
    }

    /// True when empty.
    ///
    /// ```
    /// assert!(starplex::hasse::NodeMap::<u8>::new().is_empty());
    /// ```
    pub fn is_empty(&self) -> bool {
        self.map.is_empty()
    }

    /// Entries by dimension then vertex tuple.
    ///
    /// ```
    /// let mut m = starplex::hasse::NodeMap::new();
    /// m.insert(&[0.into()], 'a');
    /// assert_eq!(m.iter().count(), 1);
    /// ```
    pub fn iter(&self) -> impl Iterator<Item = (&[VertexId], &T)> + '_ {
        self.map.iter().map(|((_, k), v)| (&k[..], v))
    }
}

/// Two frontiers of a breadth-first walk: (node, largest added vertex).
pub(crate) type Frontier = (Vec<(u32, u32)>, Vec<(u32, u32)>);

impl<L: LevelTypes> Hasse<L> {
    /// The vertex tuples of a set, by dimension then lexicographically.
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse = starplex::hasse::Hasse::new();
    /// h.insert(&[3.into(), 1.into()]).unwrap();
    /// let s = h.closure(h.find(&[1.into(), 3.into()]).unwrap());
    /// assert_eq!(h.set_to_vertex_lists(&s), vec![vec![1], vec![3], vec![1, 3]]);
    /// ```
    pub fn set_to_vertex_lists(&self, s: &NodeSet) -> Vec<Vec<u32>> {
        let mut out: Vec<Vec<u32>> = s
            .iter()
            .map(|n| self.vertices(n).iter().map(|v| v.0).collect())
            .collect();
        out.sort_by(|a, b| (a.len(), a).cmp(&(b.len(), b)));
        out
    }

    /// Formats a set as `{0} {1} {0,1}` (dimension then lexicographic order).
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse = starplex::hasse::Hasse::new();
    /// let e = h.insert(&[0.into(), 1.into()]).unwrap();
    /// assert_eq!(h.format_set(&h.closure(e)), "{0} {1} {0,1}");
    /// ```
    pub fn format_set(&self, s: &NodeSet) -> String {
        self.set_to_vertex_lists(s)
            .iter()
            .map(|v| {
                let inner: Vec<String> = v.iter().map(|x| x.to_string()).collect();
                format!("{{{}}}", inner.join(","))
            })
            .collect::<Vec<_>>()
            .join(" ")
    }

    /// The star of `s`: every simplex having `s` as a face, `s` included.
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse = starplex::hasse::Hasse::new();
    /// h.insert(&[0.into(), 1.into(), 2.into()]).unwrap();
    /// assert_eq!(h.star(h.vertex(0.into()).unwrap()).len(), 4);
    /// ```
    pub fn star(&self, s: Node) -> NodeSet {
        let ids = self.star_ids(s);
        NodeSet::from_levels(
            ids.into_iter()
                .map(|l| l.into_iter().map(SimplexId).collect())
                .collect(),
        )
    }

    /// The closure of `s`: every face of `s`, `s` included.
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse = starplex::hasse::Hasse::new();
    /// let t = h.insert(&[0.into(), 1.into(), 2.into()]).unwrap();
    /// assert_eq!(h.closure(t).len(), 7);
    /// ```
    pub fn closure(&self, s: Node) -> NodeSet {
        let mut set = NodeSet::new();
        set.insert(s);
        self.close_down(&mut set);
        set
    }

    fn close_down(&self, set: &mut NodeSet) {
        for k in (1..set.levels.len()).rev() {
            let mut add: Vec<SimplexId> = Vec::new();
            for &i in &set.levels[k] {
                add.extend(self.levels[k].downs(i.0).iter().map(|&f| SimplexId(f)));
            }
            let l = &mut set.levels[k - 1];
            l.extend(add);
            l.sort_unstable();
            l.dedup();
        }
    }

    /// The link of `s`: `{τ \ s : τ ∈ St(s), τ ≠ s}` (= Cl(St(s)) \ St(Cl(s))).
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse = starplex::hasse::Hasse::new();
    /// h.insert(&[0.into(), 1.into(), 2.into()]).unwrap();
    /// let lk = h.link(h.vertex(0.into()).unwrap());
    /// assert_eq!(h.format_set(&lk), "{1} {2} {1,2}");
    /// ```
    pub fn link(&self, s: Node) -> NodeSet {
        let mut out = Vec::new();
        self.link_ids_into(s, &mut out, &mut Default::default());
        NodeSet::from_levels(out)
    }

    /// The link as unsorted ids per level into a reused buffer (each link simplex once).
    pub(crate) fn link_ids_into(
        &self,
        s: Node,
        out: &mut Vec<Vec<SimplexId>>,
        scratch: &mut Frontier,
    ) {
        for l in out.iter_mut() {
            l.clear();
        }
        let k = s.dim as usize;
        let sv: smallvec::SmallVec<[u32; 8]> = self.levels[k].verts(s.id.0).into();
        let (cur, next) = scratch;
        cur.clear();
        cur.push((s.id.0, 0));
        let mut j = k;
        let mut first = true;
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
            let ld = j - k - 1;
            if out.len() <= ld {
                out.resize(ld + 1, Vec::new());
            }
            for &(t, _) in next.iter() {
                // go down from t removing the vertices of s
                let mut cur_id = t;
                let mut d = j;
                for &v in &sv {
                    let l = &self.levels[d];
                    let vs = l.verts(cur_id);
                    let pos = vs.iter().position(|&x| x == v).unwrap_or(0);
                    cur_id = l.downs(cur_id)[pos];
                    d -= 1;
                }
                out[ld].push(SimplexId(cur_id));
            }
            std::mem::swap(cur, next);
        }
    }

    /// The star of a set: the union of the stars of its members.
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse = starplex::hasse::Hasse::new();
    /// h.insert(&[0.into(), 1.into(), 2.into()]).unwrap();
    /// let mut s = starplex::hasse::NodeSet::new();
    /// s.insert(h.vertex(0.into()).unwrap());
    /// s.insert(h.vertex(1.into()).unwrap());
    /// assert_eq!(h.star_of(&s).len(), 6);
    /// ```
    pub fn star_of(&self, set: &NodeSet) -> NodeSet {
        let mut levels: Vec<Vec<SimplexId>> = Vec::new();
        for n in set.iter() {
            let st = self.star_ids(n);
            if levels.len() < st.len() {
                levels.resize(st.len(), Vec::new());
            }
            for (k, l) in st.into_iter().enumerate() {
                levels[k].extend(l.into_iter().map(SimplexId));
            }
        }
        NodeSet::from_levels(levels)
    }

    /// The closure of a set: the union of the closures of its members.
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse = starplex::hasse::Hasse::new();
    /// let t = h.insert(&[0.into(), 1.into(), 2.into()]).unwrap();
    /// let mut s = starplex::hasse::NodeSet::new();
    /// s.insert(t);
    /// assert_eq!(h.closure_of(&s).len(), 7);
    /// ```
    pub fn closure_of(&self, set: &NodeSet) -> NodeSet {
        let mut s = set.clone();
        self.close_down(&mut s);
        s
    }

    /// The link of a set: `Cl(St(S)) \ St(Cl(S))`.
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse = starplex::hasse::Hasse::new();
    /// h.insert(&[0.into(), 1.into(), 2.into()]).unwrap();
    /// let mut s = starplex::hasse::NodeSet::new();
    /// s.insert(h.vertex(0.into()).unwrap());
    /// assert_eq!(h.link_of(&s), h.link(h.vertex(0.into()).unwrap()));
    /// ```
    pub fn link_of(&self, set: &NodeSet) -> NodeSet {
        let a = self.closure_of(&self.star_of(set));
        let b = self.star_of(&self.closure_of(set));
        a.difference(&b)
    }

    /// Alg. 3: the simplices of the same dimension sharing a face with `s` (none for a vertex).
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse = starplex::hasse::Hasse::new();
    /// h.insert(&[0.into(), 1.into(), 2.into()]).unwrap();
    /// h.insert(&[1.into(), 2.into(), 3.into()]).unwrap();
    /// let t = h.find(&[0.into(), 1.into(), 2.into()]).unwrap();
    /// assert_eq!(h.neighbours_by_face(t).len(), 1);
    /// ```
    pub fn neighbours_by_face(&self, s: Node) -> Vec<Node> {
        let mut out: Vec<Node> = self
            .down(s)
            .flat_map(|f| self.up(f))
            .filter(|&n| n != s)
            .collect();
        out.sort_unstable();
        out.dedup();
        out
    }

    /// The simplices of the same dimension sharing a coface with `s`.
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse = starplex::hasse::Hasse::new();
    /// h.insert(&[0.into(), 1.into(), 2.into()]).unwrap();
    /// let v = h.vertex(0.into()).unwrap();
    /// assert_eq!(h.neighbours_by_coface(v).len(), 2);
    /// ```
    pub fn neighbours_by_coface(&self, s: Node) -> Vec<Node> {
        let mut out: Vec<Node> = self
            .up(s)
            .flat_map(|c| self.down(c))
            .filter(|&n| n != s)
            .collect();
        out.sort_unstable();
        out.dedup();
        out
    }

    /// The k-ring of `s`: simplices of its dimension at most `k` coface-sharing steps away
    /// (for a vertex: the vertices within `k` edges), `s` included.
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse = starplex::hasse::Hasse::new();
    /// h.insert(&[0.into(), 1.into()]).unwrap();
    /// h.insert(&[1.into(), 2.into()]).unwrap();
    /// let v = h.vertex(0.into()).unwrap();
    /// assert_eq!(h.k_ring(v, 1).len(), 2);
    /// assert_eq!(h.k_ring(v, 2).len(), 3);
    /// ```
    pub fn k_ring(&self, s: Node, k: usize) -> NodeSet {
        let mut set = NodeSet::new();
        set.insert(s);
        let mut frontier = vec![s];
        for _ in 0..k {
            let mut next = Vec::new();
            for &f in &frontier {
                for n in self.neighbours_by_coface(f) {
                    if set.insert(n) {
                        next.push(n);
                    }
                }
            }
            frontier = next;
        }
        set
    }

    /// Breadth-first traversal up from `s` (s included), each coface visited once; the visitor
    /// returns `false` to stop expanding above a node.
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse = starplex::hasse::Hasse::new();
    /// h.insert(&[0.into(), 1.into(), 2.into()]).unwrap();
    /// let mut dims = vec![];
    /// h.visit_bfs_up(h.vertex(0.into()).unwrap(), |n| { dims.push(n.dim); true });
    /// assert_eq!(dims, vec![0, 1, 1, 2]);
    /// ```
    pub fn visit_bfs_up(&self, s: Node, mut visit: impl FnMut(Node) -> bool) {
        let mut seen = NodeSet::new();
        let mut q = VecDeque::from([s]);
        seen.insert(s);
        while let Some(n) = q.pop_front() {
            if visit(n) {
                for c in self.up(n) {
                    if seen.insert(c) {
                        q.push_back(c);
                    }
                }
            }
        }
    }

    /// Breadth-first traversal up from `s` with a typed visitor: each node reaches the
    /// [`Visit<K, T>`](super::Visit) of its level with its data, the level chosen by one `match`
    /// on the dimension, the data typed at compile time.
    ///
    /// ```
    /// use starplex::hasse::{Hasse, Node, Visit};
    /// struct Tally { weight: f64, triangles: Vec<u8> }
    /// impl Visit<0, f64> for Tally {
    ///     fn visit(&mut self, _: Node, w: &f64) -> bool { self.weight += w; true }
    /// }
    /// impl Visit<1, ()> for Tally {
    ///     fn visit(&mut self, _: Node, _: &()) -> bool { true }
    /// }
    /// impl Visit<2, u8> for Tally {
    ///     fn visit(&mut self, _: Node, c: &u8) -> bool { self.triangles.push(*c); true }
    /// }
    /// let mut h: Hasse<(f64, (), u8)> = Hasse::new();
    /// let t = h.insert_with::<2>(&[0.into(), 1.into(), 2.into()], 7).unwrap();
    /// *h.data_mut::<0>(h.vertex(0.into()).unwrap().id) = 1.5;
    /// let mut v = Tally { weight: 0.0, triangles: vec![] };
    /// h.visit_typed_bfs_up(h.vertex(0.into()).unwrap(), &mut v);
    /// assert_eq!((v.weight, v.triangles), (1.5, vec![7]));
    /// let mut v = Tally { weight: 0.0, triangles: vec![] };
    /// h.visit_typed_bfs_down(t, &mut v);
    /// assert_eq!(v.weight, 1.5);
    /// ```
    pub fn visit_typed_bfs_up<V: super::VisitAll<L>>(&self, s: Node, v: &mut V) {
        self.visit_bfs_up(s, |n| v.visit_node(&self.data, n));
    }

    /// Breadth-first traversal down from `s` with a typed visitor (see
    /// [`visit_typed_bfs_up`](Self::visit_typed_bfs_up)).
    ///
    /// ```
    /// use starplex::hasse::{Hasse, Node, Visit};
    /// struct Verts(usize);
    /// impl Visit<0, u32> for Verts {
    ///     fn visit(&mut self, _: Node, _: &u32) -> bool { self.0 += 1; true }
    /// }
    /// let mut h: Hasse<(u32,)> = Hasse::new();
    /// let t = h.insert(&[0.into(), 1.into(), 2.into()]).unwrap();
    /// let mut v = Verts(0);
    /// h.visit_typed_bfs_down(t, &mut v);
    /// assert_eq!(v.0, 3);
    /// ```
    pub fn visit_typed_bfs_down<V: super::VisitAll<L>>(&self, s: Node, v: &mut V) {
        self.visit_bfs_down(s, |n| v.visit_node(&self.data, n));
    }

    /// Breadth-first traversal down from `s` (s included), each face visited once.
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse = starplex::hasse::Hasse::new();
    /// let t = h.insert(&[0.into(), 1.into(), 2.into()]).unwrap();
    /// let mut n = 0;
    /// h.visit_bfs_down(t, |_| { n += 1; true });
    /// assert_eq!(n, 7);
    /// ```
    pub fn visit_bfs_down(&self, s: Node, mut visit: impl FnMut(Node) -> bool) {
        let mut seen = NodeSet::new();
        let mut q = VecDeque::from([s]);
        seen.insert(s);
        while let Some(n) = q.pop_front() {
            if visit(n) {
                for c in self.down(n) {
                    if seen.insert(c) {
                        q.push_back(c);
                    }
                }
            }
        }
    }
}
