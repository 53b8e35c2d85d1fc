//! The Hasse diagram itself: levels of flat arrays, insertion (Alg. 1), removal, search and
//! up/down traversal (Alg. 2), level iteration, validation.
use rustc_hash::FxHashMap;
use smallvec::SmallVec;

use super::arena::UpArena;
use super::levels::{At, LevelTypes};
use super::{HasseError, Node};
use crate::ids::{SimplexId, VertexId};

/// Largest number of vertices of a simplex the complex inserts with all its faces (2^24 nodes);
/// larger ones are refused with an estimate.
///
/// ```
/// use starplex::hasse::{Hasse, HasseError, MAX_INSERT_VERTICES};
/// use starplex::ids::VertexId;
/// let mut h: Hasse = Hasse::new();
/// let big: Vec<VertexId> = (0..MAX_INSERT_VERTICES as u32 + 1).map(VertexId).collect();
/// let e = h.insert(&big).unwrap_err();
/// assert!(matches!(e, HasseError::TooLarge(t) if t.estimate == (1 << 25) - 1));
/// assert!(h.insert(&big[..3]).is_ok()); // small simplices are inserted with their faces
/// ```
pub const MAX_INSERT_VERTICES: usize = 24;

pub(crate) type Verts = SmallVec<[u32; 8]>;

/// The refusal to insert a simplex of `n` vertices with all its faces.
pub(crate) fn too_many_faces(n: usize) -> HasseError {
    HasseError::TooLarge(crate::limits::TooLarge::new(
        format!("inserting a simplex of {n} vertices with all its faces"),
        (1u128 << n.min(127)) - 1,
        (1u128 << MAX_INSERT_VERTICES) - 1,
        crate::limits::Unit::Simplices,
    ))
}

/// The nodes of one dimension `k`: `k + 1` sorted vertex labels and `k + 1` face ids per node
/// (face `i` is the simplex without vertex `i`), and the up lists in an arena.
#[derive(Clone, Debug, Default)]
pub(crate) struct Level {
    pub(crate) k1: usize,
    pub(crate) verts: Vec<u32>,
    pub(crate) down: Vec<u32>,
    pub(crate) up: UpArena,
    /// Slots of removed nodes, reused by the next insertions.
    pub(crate) free: Vec<u32>,
}

impl Level {
    /// Number of slots (live and removed).
    #[inline]
    pub(crate) fn slots(&self) -> usize {
        self.up.hdr.len()
    }
    /// Number of live nodes.
    #[inline]
    pub(crate) fn len(&self) -> usize {
        self.up.hdr.len() - self.free.len()
    }
    #[inline]
    pub(crate) fn alive(&self, i: u32) -> bool {
        (i as usize) < self.slots() && !self.up.is_dead(i)
    }
    #[inline]
    pub(crate) fn verts(&self, i: u32) -> &[u32] {
        let i = i as usize;
        &self.verts[i * self.k1..(i + 1) * self.k1]
    }
    #[inline]
    pub(crate) fn downs(&self, i: u32) -> &[u32] {
        if self.k1 == 1 {
            return &[];
        }
        let i = i as usize;
        &self.down[i * self.k1..(i + 1) * self.k1]
    }
    fn bytes(&self) -> usize {
        self.verts.capacity() * 4
            + self.down.capacity() * 4
            + self.up.bytes()
            + self.free.capacity() * 4
    }
}

const NONE: u32 = u32::MAX;

/// Vertex label → vertex node: a dense table for labels up to a few times the number of
/// vertices, a hash map for the rest (so a huge label costs no memory).
#[derive(Clone, Debug, Default)]
pub(crate) struct VertexIndex {
    dense: Vec<u32>,
    sparse: FxHashMap<u32, u32>,
    len: usize,
}

impl VertexIndex {
    #[inline]
    pub(crate) fn get(&self, label: u32) -> Option<u32> {
        match self.dense.get(label as usize) {
            Some(&x) => (x != NONE).then_some(x),
            None => self.sparse.get(&label).copied(),
        }
    }
    pub(crate) fn insert(&mut self, label: u32, id: u32) {
        let l = label as usize;
        if l >= self.dense.len() && l < 2 * self.len + 4096 {
            // absorb sparse entries that now fall inside the dense table
            let new_len = (l + 1).max(self.dense.len() * 3 / 2);
            self.dense.resize(new_len, NONE);
            let moved: Vec<(u32, u32)> = self
                .sparse
                .iter()
                .filter(|&(&k, _)| (k as usize) < new_len)
                .map(|(&k, &v)| (k, v))
                .collect();
            for (k, v) in moved {
                self.sparse.remove(&k);
                self.dense[k as usize] = v;
            }
        }
        let old = if l < self.dense.len() {
            std::mem::replace(&mut self.dense[l], id)
        } else {
            self.sparse.insert(label, id).unwrap_or(NONE)
        };
        if old == NONE {
            self.len += 1;
        }
    }
    pub(crate) fn remove(&mut self, label: u32) {
        let l = label as usize;
        let old = if l < self.dense.len() {
            std::mem::replace(&mut self.dense[l], NONE)
        } else {
            self.sparse.remove(&label).unwrap_or(NONE)
        };
        if old != NONE {
            self.len -= 1;
        }
    }
    #[inline]
    pub(crate) fn contains(&self, label: u32) -> bool {
        self.get(label).is_some()
    }
    pub(crate) fn len(&self) -> usize {
        self.len
    }
    /// Makes room for labels `0..n` in the dense table.
    pub(crate) fn reserve_dense(&mut self, n: usize) {
        if self.dense.len() < n {
            self.dense.resize(n, NONE);
        }
    }
    fn bytes(&self) -> usize {
        self.dense.capacity() * 4 + self.sparse.capacity() * 9
    }
    fn shrink_to_fit(&mut self) {
        self.dense.shrink_to_fit();
        self.sparse.shrink_to_fit();
    }
}

/// A simplicial complex stored as its Hasse diagram (CASC), with user data of type
/// `<L as At<K>>::Data` on every `K`-simplex (see [`levels`](super::levels)).
///
/// Vertices are labelled by [`VertexId`] (any `u32`); a simplex is found by its vertex labels.
/// Node ids ([`Node::id`]) are slots per dimension and stay stable while the complex is edited:
/// removing a simplex frees its slot (its data is reset), a later insertion reuses it.
/// [`compact`](Hasse::compact) renumbers densely (data columns follow).
///
/// Methods taking vertex labels check them and never panic. Methods taking a [`Node`] expect a
/// node of this complex (see [`contains`](Hasse::contains)); an id out of range panics, a
/// removed slot gives unspecified (but memory-safe) answers.
///
/// ```
/// use starplex::hasse::Hasse;
/// use starplex::ids::VertexId;
/// let v = |i| VertexId(i);
/// let mut h: Hasse = Hasse::new();
/// h.insert(&[v(0), v(1), v(2)]).unwrap();
/// h.insert(&[v(1), v(2), v(3)]).unwrap();
/// assert_eq!(h.f_vector(), vec![4, 5, 2]);
/// let e = h.find(&[v(2), v(1)]).unwrap();
/// assert_eq!(h.up(e).count(), 2);
/// assert!(h.is_valid());
/// ```
pub struct Hasse<L: LevelTypes = ()> {
    pub(crate) levels: Vec<Level>,
    pub(crate) root: VertexIndex,
    pub(crate) data: L::Columns,
    pub(crate) max_label: Option<u32>,
}

impl<L: LevelTypes> Clone for Hasse<L>
where
    L::Columns: Clone,
{
    fn clone(&self) -> Self {
        Hasse {
            levels: self.levels.clone(),
            root: self.root.clone(),
            data: self.data.clone(),
            max_label: self.max_label,
        }
    }
}

impl<L: LevelTypes> Default for Hasse<L> {
    fn default() -> Self {
        Hasse {
            levels: Vec::new(),
            root: VertexIndex::default(),
            data: L::Columns::default(),
            max_label: None,
        }
    }
}

impl<L: LevelTypes> std::fmt::Debug for Hasse<L> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Hasse")
            .field("f_vector", &self.f_vector())
            .finish()
    }
}

/// Sorts and checks a vertex tuple.
pub(crate) fn sorted_checked(vs: &[VertexId]) -> Result<Verts, HasseError> {
    if vs.is_empty() {
        return Err(HasseError::Empty);
    }
    let mut s: Verts = vs.iter().map(|v| v.0).collect();
    s.sort_unstable();
    for w in s.windows(2) {
        if w[0] == w[1] {
            return Err(HasseError::Degenerate {
                vertices: vs.to_vec(),
                repeated: VertexId(w[0]),
            });
        }
    }
    Ok(s)
}

impl<L: LevelTypes> Hasse<L> {
    /// An empty complex.
    ///
    /// ```
    /// let h: starplex::hasse::Hasse = starplex::hasse::Hasse::new();
    /// assert_eq!(h.dim(), None);
    /// ```
    pub fn new() -> Self {
        Self::default()
    }

    /// Dimension of the highest non-empty level, `None` when empty.
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse = starplex::hasse::Hasse::new();
    /// h.insert(&[0.into(), 1.into()]).unwrap();
    /// assert_eq!(h.dim(), Some(1));
    /// ```
    pub fn dim(&self) -> Option<usize> {
        (0..self.levels.len())
            .rev()
            .find(|&k| self.levels[k].len() > 0)
    }

    /// Number of `k`-simplices.
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse = starplex::hasse::Hasse::new();
    /// h.insert(&[0.into(), 1.into(), 2.into()]).unwrap();
    /// assert_eq!(h.n_simplices(1), 3);
    /// assert_eq!(h.n_simplices(7), 0);
    /// ```
    pub fn n_simplices(&self, k: usize) -> usize {
        self.levels.get(k).map_or(0, |l| l.len())
    }

    /// Number of slots of dimension `k` (live simplices plus freed slots): ids are below it,
    /// and the data columns have this length.
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse = starplex::hasse::Hasse::new();
    /// h.insert(&[0.into(), 1.into()]).unwrap();
    /// h.remove_vertices(&[0.into()]).unwrap();
    /// assert_eq!((h.n_simplices(0), h.n_slots(0)), (1, 2));
    /// ```
    pub fn n_slots(&self, k: usize) -> usize {
        self.levels.get(k).map_or(0, |l| l.slots())
    }

    /// The first live `k`-simplex at or after slot `r mod n_slots(k)` (wrapping): a cheap way to
    /// sample simplices at random.
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse = starplex::hasse::Hasse::new();
    /// h.insert(&[0.into(), 1.into(), 2.into()]).unwrap();
    /// assert_eq!(h.pick(1, 1_000_001).unwrap().dim, 1);
    /// assert!(h.pick(2, 5).is_some());
    /// assert!(h.pick(3, 0).is_none());
    /// ```
    pub fn pick(&self, k: usize, r: u64) -> Option<Node> {
        let l = self.levels.get(k)?;
        let n = l.slots();
        if l.len() == 0 {
            return None;
        }
        let start = (r % n as u64) as usize;
        (0..n)
            .map(|j| ((start + j) % n) as u32)
            .find(|&i| !l.up.is_dead(i))
            .map(|i| Node::new(k as u32, SimplexId(i)))
    }

    /// Number of simplices of every dimension.
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse = starplex::hasse::Hasse::new();
    /// h.insert(&[0.into(), 1.into(), 2.into()]).unwrap();
    /// assert_eq!(h.len(), 7);
    /// ```
    pub fn len(&self) -> usize {
        self.levels.iter().map(|l| l.len()).sum()
    }

    /// True when the complex has no simplex.
    ///
    /// ```
    /// assert!(starplex::hasse::Hasse::<()>::new().is_empty());
    /// ```
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The f-vector (number of simplices per dimension).
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse = starplex::hasse::Hasse::new();
    /// h.insert(&[0.into(), 1.into(), 2.into(), 3.into()]).unwrap();
    /// assert_eq!(h.f_vector(), vec![4, 6, 4, 1]);
    /// ```
    pub fn f_vector(&self) -> Vec<usize> {
        let d = self.dim().map_or(0, |d| d + 1);
        (0..d).map(|k| self.levels[k].len()).collect()
    }

    /// Euler characteristic: the alternating sum of the f-vector.
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse = starplex::hasse::Hasse::new();
    /// h.insert(&[0.into(), 1.into(), 2.into()]).unwrap();
    /// assert_eq!(h.euler_characteristic(), 1);
    /// ```
    pub fn euler_characteristic(&self) -> i64 {
        self.f_vector()
            .iter()
            .enumerate()
            .map(|(k, &n)| if k % 2 == 0 { n as i64 } else { -(n as i64) })
            .sum()
    }

    /// Heap bytes used by the topology (levels, up lists, vertex lookup), without user data.
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse = starplex::hasse::Hasse::new();
    /// h.insert(&[0.into(), 1.into(), 2.into()]).unwrap();
    /// assert!(h.topology_bytes() > 0);
    /// ```
    pub fn topology_bytes(&self) -> usize {
        self.levels.iter().map(|l| l.bytes()).sum::<usize>() + self.root.bytes()
    }

    /// Bytes used by user data (column capacities); zero for levels without data.
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse<((), (), u64)> = starplex::hasse::Hasse::new();
    /// h.insert(&[0.into(), 1.into(), 2.into()]).unwrap();
    /// assert!(h.data_bytes() >= 8);
    /// let mut h: starplex::hasse::Hasse<((), (), ())> = starplex::hasse::Hasse::new();
    /// h.insert(&[0.into(), 1.into(), 2.into()]).unwrap();
    /// assert_eq!(h.data_bytes(), 0);
    /// ```
    pub fn data_bytes(&self) -> usize {
        (0..self.levels.len())
            .map(|k| L::bytes(&self.data, k))
            .sum()
    }

    /// Shrinks every array to its length (after a bulk build).
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse = starplex::hasse::Hasse::new();
    /// h.insert(&[0.into(), 1.into()]).unwrap();
    /// h.shrink_to_fit();
    /// assert!(h.is_valid());
    /// ```
    pub fn shrink_to_fit(&mut self) {
        for l in &mut self.levels {
            l.verts.shrink_to_fit();
            l.down.shrink_to_fit();
            l.up.hdr.shrink_to_fit();
        }
        self.root.shrink_to_fit();
    }

    /// A label not used by any vertex so far (one more than the largest ever inserted).
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse = starplex::hasse::Hasse::new();
    /// h.insert(&[3.into(), 5.into()]).unwrap();
    /// assert_eq!(h.fresh_label().unwrap().0, 6);
    /// ```
    pub fn fresh_label(&self) -> Option<VertexId> {
        match self.max_label {
            None => Some(VertexId(0)),
            Some(m) => m.checked_add(1).map(VertexId),
        }
    }

    // ----- access ---------------------------------------------------------------------------

    /// The sorted vertex labels of a simplex.
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse = starplex::hasse::Hasse::new();
    /// let t = h.insert(&[2.into(), 0.into(), 1.into()]).unwrap();
    /// assert_eq!(h.vertices(t), &[0.into(), 1.into(), 2.into()]);
    /// ```
    #[inline]
    pub fn vertices(&self, s: Node) -> &[VertexId] {
        bytemuck::cast_slice(self.levels[s.dim as usize].verts(s.id.0))
    }

    /// The node of every `k`-simplex, in id order.
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse = starplex::hasse::Hasse::new();
    /// h.insert(&[0.into(), 1.into(), 2.into()]).unwrap();
    /// assert_eq!(h.level(1).count(), 3);
    /// ```
    pub fn level(&self, k: usize) -> impl Iterator<Item = Node> + '_ {
        let n = self.n_slots(k) as u32;
        (0..n)
            .filter(move |&i| !self.levels[k].up.is_dead(i))
            .map(move |i| Node::new(k as u32, SimplexId(i)))
    }

    /// Every simplex, by increasing dimension.
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse = starplex::hasse::Hasse::new();
    /// h.insert(&[0.into(), 1.into(), 2.into()]).unwrap();
    /// assert_eq!(h.nodes().count(), 7);
    /// ```
    pub fn nodes(&self) -> impl Iterator<Item = Node> + '_ {
        (0..self.levels.len()).flat_map(move |k| self.level(k))
    }

    /// The data of the `K`-simplex `id` (typed at compile time; a slice index).
    ///
    /// # Panics
    /// When `id` is not a `K`-simplex id of this complex.
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse<(u8, u16)> = starplex::hasse::Hasse::new();
    /// let e = h.insert(&[0.into(), 1.into()]).unwrap();
    /// *h.data_mut::<1>(e.id) = 7;
    /// assert_eq!(*h.data::<1>(e.id), 7u16);
    /// ```
    #[inline]
    pub fn data<const K: usize>(&self, id: SimplexId) -> &<L as At<K>>::Data
    where
        L: At<K>,
    {
        &L::column(&self.data)[id.index()]
    }

    /// Mutable data of the `K`-simplex `id`.
    ///
    /// # Panics
    /// When `id` is not a `K`-simplex id of this complex.
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse<(f32,)> = starplex::hasse::Hasse::new();
    /// let v = h.insert(&[4.into()]).unwrap();
    /// *h.data_mut::<0>(v.id) = 1.5;
    /// assert_eq!(h.level_data::<0>(), &[1.5]);
    /// ```
    #[inline]
    pub fn data_mut<const K: usize>(&mut self, id: SimplexId) -> &mut <L as At<K>>::Data
    where
        L: At<K>,
    {
        &mut L::column_mut(&mut self.data)[id.index()]
    }

    /// All data of level `K`, indexed by simplex id (freed slots hold default values).
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse<((), i32)> = starplex::hasse::Hasse::new();
    /// h.insert(&[0.into(), 1.into(), 2.into()]).unwrap();
    /// assert_eq!(h.level_data::<1>().len(), 3);
    /// ```
    pub fn level_data<const K: usize>(&self) -> &[<L as At<K>>::Data]
    where
        L: At<K>,
    {
        L::column(&self.data)
    }

    /// All data of level `K`, mutable.
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse<(i32,)> = starplex::hasse::Hasse::new();
    /// h.insert(&[0.into(), 1.into()]).unwrap();
    /// for x in h.level_data_mut::<0>() { *x = 3; }
    /// assert_eq!(h.level_data::<0>(), &[3, 3]);
    /// ```
    pub fn level_data_mut<const K: usize>(&mut self) -> &mut [<L as At<K>>::Data]
    where
        L: At<K>,
    {
        L::column_mut(&mut self.data)
    }

    // ----- search and traversal (Alg. 2) ---------------------------------------------------

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

    // ----- insertion (Alg. 1) ---------------------------------------------------------------

    /// Inserts a simplex with all its missing faces (Alg. 1); new simplices get default data.
    /// Returns the simplex's node (existing or new).
    ///
    /// # Errors
    /// [`HasseError::Degenerate`] for a repeated vertex, [`HasseError::Empty`], and
    /// [`HasseError::TooLarge`] above [`MAX_INSERT_VERTICES`] vertices.
    ///
    /// ```
    /// use starplex::hasse::{Hasse, HasseError};
    /// let mut h: Hasse = Hasse::new();
    /// let t = h.insert(&[1.into(), 2.into(), 3.into()]).unwrap();
    /// assert_eq!(t.dim, 2);
    /// let e = h.insert(&[1.into(), 2.into(), 2.into()]).unwrap_err();
    /// assert!(matches!(e, HasseError::Degenerate { .. }));
    /// ```
    pub fn insert(&mut self, vs: &[VertexId]) -> Result<Node, HasseError> {
        let s = sorted_checked(vs)?;
        if s.len() > MAX_INSERT_VERTICES {
            return Err(too_many_faces(s.len()));
        }
        let id = self.insert_sorted(&s);
        Ok(Node::new((s.len() - 1) as u32, SimplexId(id)))
    }

    /// Inserts a simplex and sets its data (level `K` must be the simplex's dimension).
    ///
    /// # Errors
    /// As [`insert`](Self::insert), and [`HasseError::WrongDimension`] when the simplex does not
    /// have `K + 1` vertices.
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse<((), (), &'static str)> = starplex::hasse::Hasse::new();
    /// let t = h.insert_with::<2>(&[0.into(), 1.into(), 2.into()], "face").unwrap();
    /// assert_eq!(*h.data::<2>(t.id), "face");
    /// ```
    pub fn insert_with<const K: usize>(
        &mut self,
        vs: &[VertexId],
        data: <L as At<K>>::Data,
    ) -> Result<Node, HasseError>
    where
        L: At<K>,
    {
        if vs.len() != K + 1 {
            return Err(HasseError::WrongDimension {
                expected: K,
                got: vs.len().wrapping_sub(1),
            });
        }
        let n = self.insert(vs)?;
        *self.data_mut::<K>(n.id) = data;
        Ok(n)
    }

    pub(crate) fn ensure_level(&mut self, k: usize) {
        while self.levels.len() <= k {
            let k1 = self.levels.len() + 1;
            self.levels.push(Level {
                k1,
                ..Level::default()
            });
        }
    }

    /// Inserts a sorted, non-degenerate vertex tuple with its faces; returns the id.
    pub(crate) fn insert_sorted(&mut self, s: &[u32]) -> u32 {
        if let Some(id) = self.find_sorted(s) {
            return id;
        }
        let k = s.len() - 1;
        self.ensure_level(k);
        if k == 0 {
            let id = self.new_slot(0, s, &[], 0);
            self.root.insert(s[0], id);
            self.max_label = Some(self.max_label.map_or(s[0], |m| m.max(s[0])));
            return id;
        }
        let mut downs: SmallVec<[u32; 8]> = SmallVec::with_capacity(k + 1);
        let mut buf: Verts = SmallVec::with_capacity(k);
        for i in 0..=k {
            buf.clear();
            buf.extend(
                s.iter()
                    .enumerate()
                    .filter(|&(j, _)| j != i)
                    .map(|(_, &x)| x),
            );
            downs.push(self.insert_sorted(&buf));
        }
        let id = self.new_slot(k, s, &downs, 0);
        let below = &mut self.levels[k - 1].up;
        for i in 0..=k {
            below.insert(downs[i], s[i], id);
        }
        id
    }

    /// A slot for a new node (a freed one when there is one) with default data.
    pub(crate) fn new_slot(&mut self, k: usize, s: &[u32], downs: &[u32], up_cap: u32) -> u32 {
        let l = &mut self.levels[k];
        if let Some(id) = l.free.pop() {
            let a = id as usize * (k + 1);
            l.verts[a..a + k + 1].copy_from_slice(s);
            if k > 0 {
                l.down[a..a + k + 1].copy_from_slice(downs);
            }
            l.up.reserve_node(id, up_cap);
            L::reset(&mut self.data, k, id as usize);
            id
        } else {
            let id = l.slots() as u32;
            l.verts.extend_from_slice(s);
            l.down.extend_from_slice(downs);
            l.up.push_node(up_cap);
            L::push_default(&mut self.data, k);
            id
        }
    }

    // ----- removal ---------------------------------------------------------------------------

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
            let mut up = super::arena::UpArena::default();
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

    /// The star of `s` (all cofaces including `s`) as ids per level, each found exactly once:
    /// a coface is reached only from its parent without its largest vertex outside `s`.
    pub(crate) fn star_ids(&self, s: Node) -> Vec<Vec<u32>> {
        let k = s.dim as usize;
        let mut out: Vec<Vec<u32>> = vec![Vec::new(); self.levels.len()];
        out[k].push(s.id.0);
        let mut cur: Vec<(u32, u32)> = vec![(s.id.0, 0)];
        let mut first = true;
        let mut j = k;
        while !cur.is_empty() && j + 1 < self.levels.len() {
            let mut next = Vec::new();
            for &(t, m) in &cur {
                for p in self.levels[j].up.get(t) {
                    if first || p[0] > m {
                        next.push((p[1], p[0]));
                    }
                }
            }
            first = false;
            j += 1;
            out[j].extend(next.iter().map(|x| x.0));
            cur = next;
        }
        out
    }

    // ----- validation ------------------------------------------------------------------------

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
