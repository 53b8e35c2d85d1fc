//! Insertion into a [`Hasse`] complex (Alg. 1 of the CASC paper): a simplex with all its
//! missing faces, the checks on a vertex tuple, slots for new nodes.
use smallvec::SmallVec;

use super::complex::Hasse;
use super::levels::{At, LevelTypes};
use super::storage::{Level, Verts};
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

/// The refusal to insert a simplex of `n` vertices with all its faces.
pub(crate) fn too_many_faces(n: usize) -> HasseError {
    HasseError::TooLarge(crate::limits::TooLarge::new(
        format!("inserting a simplex of {n} vertices with all its faces"),
        (1u128 << n.min(127)) - 1,
        (1u128 << MAX_INSERT_VERTICES) - 1,
        crate::limits::Unit::Simplices,
    ))
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
}
