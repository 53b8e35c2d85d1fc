//! The Hasse diagram itself: the [`Hasse`] type, its counts and statistics, and typed data
//! access. The rest of its methods live by concern: `navigate.rs` (search and up/down
//! traversal, Alg. 2), `insert.rs` (insertion, Alg. 1), `remove.rs` (removal of stars,
//! compaction), `check.rs` (validation); the per-dimension arrays are in `storage.rs`.
use super::levels::{At, LevelTypes};
use super::storage::{Level, VertexIndex};
use super::Node;
use crate::ids::{SimplexId, VertexId};

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
}
