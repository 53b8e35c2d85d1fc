//! Typed user data per level (CASC's "colouring").
//!
//! A level list is a plain tuple of user types, one per dimension starting at the vertices:
//! `([f64; 3], (), u8)` stores a position on every vertex, nothing on edges and a byte on every
//! triangle. Dimensions past the end of the tuple store nothing. The unit type `()` stores
//! nothing (a `Vec<()>` never allocates).
//!
//! * Typed access, resolved at compile time: [`At<K>`] gives the column of level `K`, so
//!   `h.data::<0>(id)` is a slice index, with no downcast and no runtime type check.
//! * Structural edits (insert, remove, renumber) that only know the dimension at run time go
//!   through the [`LevelTypes`] trait, whose tuple implementations `match` on the dimension once per
//!   edit, never per data access.
//! * Decimation carries data through a user callback: implement [`Merge<K, T>`] for each level
//!   (one generic impl covers all `()` levels), or use [`KeepFirst`] / [`DefaultData`].
//!
//! The only bound on a user type is `Default` (a face created implicitly by an insertion gets
//! `T::default()`); `Clone` is needed only to clone the complex.
//!
//! ```
//! use starplex::hasse::{Hasse, At};
//! use starplex::ids::VertexId;
//! let mut h: Hasse<([f64; 3], (), i8)> = Hasse::new();
//! let t = h.insert(&[VertexId(0), VertexId(1), VertexId(2)]).unwrap();
//! *h.data_mut::<2>(t.id) = -1;
//! let v = h.find(&[VertexId(1)]).unwrap();
//! h.data_mut::<0>(v.id)[0] = 2.5;
//! assert_eq!(h.data::<2>(t.id), &-1);
//! assert_eq!(h.data::<0>(v.id), &[2.5, 0.0, 0.0]);
//! ```
use super::Node;
use crate::ids::VertexId;

/// Column storage of a level list: moves data along with the structural edits of the complex.
/// Implemented for `()` (no data anywhere) and for tuples of 1 to 12 user types.
///
/// ```
/// use starplex::hasse::LevelTypes;
/// assert_eq!(<(u8, (), f32) as LevelTypes>::N_LEVELS, 3);
/// assert_eq!(<() as LevelTypes>::N_LEVELS, 0);
/// ```
pub trait LevelTypes: Sized + 'static {
    /// The columns: a tuple of `Vec`s.
    type Columns: Default;
    /// Number of levels with a declared type (levels past it store nothing).
    const N_LEVELS: usize;
    /// Appends a default value at level `dim`.
    fn push_default(cols: &mut Self::Columns, dim: usize);
    /// Resets the value at `i` of level `dim` to the default (a removed or reused slot).
    fn reset(cols: &mut Self::Columns, dim: usize, i: usize);
    /// Keeps the values of level `dim` whose `keep` flag is set, in order (compaction).
    fn retain(cols: &mut Self::Columns, dim: usize, keep: &[bool]);
    /// Reserves room for `n` more values at level `dim`.
    fn reserve(cols: &mut Self::Columns, dim: usize, n: usize);
    /// Bytes used by level `dim`'s column (capacity).
    fn bytes(cols: &Self::Columns, dim: usize) -> usize;
    /// Reverses every staged column (staged values are then popped in order).
    fn reverse_all(cols: &mut Self::Columns);
    /// Moves the last staged value of level `dim` into `cols` at `i`.
    fn commit_pop(cols: &mut Self::Columns, staged: &mut Self::Columns, dim: usize, i: usize);
}

/// Typed access to the column of level `K` of a level list.
///
/// ```
/// use starplex::hasse::{At, LevelTypes};
/// let mut cols = <(u8, f32) as LevelTypes>::Columns::default();
/// <(u8, f32) as LevelTypes>::push_default(&mut cols, 1);
/// <(u8, f32) as At<1>>::column_mut(&mut cols)[0] = 2.0;
/// assert_eq!(<(u8, f32) as At<1>>::column(&cols), &[2.0]);
/// ```
pub trait At<const K: usize>: LevelTypes {
    /// The user type stored at level `K`.
    type Data;
    /// The column of level `K`.
    fn column(cols: &Self::Columns) -> &Vec<Self::Data>;
    /// The column of level `K`, mutable.
    fn column_mut(cols: &mut Self::Columns) -> &mut Vec<Self::Data>;
}

/// A decimation callback for level `K` holding `T`: given the new simplex and the simplices
/// that merge into it (with their data), returns the new simplex's data.
///
/// ```
/// use starplex::hasse::Merge;
/// use starplex::ids::VertexId;
/// struct Average;
/// impl Merge<0, f64> for Average {
///     fn merge(&mut self, _new: &[VertexId], old: &[(&[VertexId], &f64)]) -> f64 {
///         old.iter().map(|(_, x)| **x).sum::<f64>() / old.len() as f64
///     }
/// }
/// // one impl covers every level without data
/// impl<const K: usize> Merge<K, ()> for Average {
///     fn merge(&mut self, _: &[VertexId], _: &[(&[VertexId], &())]) {}
/// }
/// let v = [VertexId(0)];
/// assert_eq!(Merge::<0, f64>::merge(&mut Average, &[VertexId(9)], &[(&v, &1.0), (&v, &3.0)]), 2.0);
/// ```
pub trait Merge<const K: usize, T> {
    /// The data of `new`, from the simplices in `old` (never empty) that map to it.
    fn merge(&mut self, new: &[VertexId], old: &[(&[VertexId], &T)]) -> T;
}

/// Keeps the data of the first merged simplex (the one with the smallest vertex tuple).
///
/// ```
/// use starplex::hasse::{KeepFirst, Merge};
/// use starplex::ids::VertexId;
/// let v = [VertexId(0)];
/// assert_eq!(Merge::<0, i32>::merge(&mut KeepFirst, &v, &[(&v, &7), (&v, &8)]), 7);
/// ```
#[derive(Clone, Copy, Debug, Default)]
pub struct KeepFirst;

impl<const K: usize, T: Clone> Merge<K, T> for KeepFirst {
    fn merge(&mut self, _new: &[VertexId], old: &[(&[VertexId], &T)]) -> T {
        old[0].1.clone()
    }
}

/// Gives every new simplex `T::default()`.
///
/// ```
/// use starplex::hasse::{DefaultData, Merge};
/// use starplex::ids::VertexId;
/// let v = [VertexId(0)];
/// assert_eq!(Merge::<0, i32>::merge(&mut DefaultData, &v, &[(&v, &7)]), 0);
/// ```
#[derive(Clone, Copy, Debug, Default)]
pub struct DefaultData;

impl<const K: usize, T: Default> Merge<K, T> for DefaultData {
    fn merge(&mut self, _new: &[VertexId], _old: &[(&[VertexId], &T)]) -> T {
        T::default()
    }
}

/// A callback that merges data on every level of `L` (blanket-implemented for any type that
/// implements [`Merge<K, T>`] for each level `K` of `L`). Runs one level's merge, chosen at run
/// time, and stages the result.
///
/// ```
/// use starplex::hasse::{KeepFirst, LevelTypes, MergeAll};
/// use starplex::ids::VertexId;
/// let mut cols = <(i32,) as LevelTypes>::Columns::default();
/// <(i32,) as LevelTypes>::push_default(&mut cols, 0);
/// cols.0[0] = 5;
/// let mut staged = <(i32,) as LevelTypes>::Columns::default();
/// let v = [VertexId(3)];
/// MergeAll::<(i32,)>::stage(&mut KeepFirst, &cols, &mut staged, 0, &v, &[(&v, 0)]);
/// assert_eq!(staged.0, vec![5]);
/// ```
pub trait MergeAll<L: LevelTypes> {
    /// Calls the level-`dim` merge on the data of `old` (vertex tuples and ids in `cols`) and
    /// pushes the result onto `staged`.
    fn stage(
        &mut self,
        cols: &L::Columns,
        staged: &mut L::Columns,
        dim: usize,
        new: &[VertexId],
        old: &[(&[VertexId], u32)],
    );
}

/// A typed visitor for level `K` holding `T` (see [`Hasse::visit_typed_bfs_up`]): receives each
/// visited `K`-simplex with its data; returns `false` to stop expanding from it.
///
/// [`Hasse::visit_typed_bfs_up`]: super::Hasse::visit_typed_bfs_up
///
/// ```
/// use starplex::hasse::{Node, Visit};
/// struct Sum(f64);
/// impl Visit<0, f64> for Sum {
///     fn visit(&mut self, _: Node, x: &f64) -> bool { self.0 += x; true }
/// }
/// let mut s = Sum(0.0);
/// assert!(Visit::<0, f64>::visit(&mut s, Node::new(0, 0.into()), &2.0));
/// assert_eq!(s.0, 2.0);
/// ```
pub trait Visit<const K: usize, T> {
    /// Called on a `K`-simplex and its data.
    fn visit(&mut self, s: Node, data: &T) -> bool;
}

/// A visitor for every level of `L` (blanket-implemented for types implementing
/// [`Visit<K, T>`] for each level): the dimension of a node selects, by one `match`, the
/// statically typed method; nodes of dimensions without a declared type are passed over (and
/// expanded).
///
/// ```
/// use starplex::hasse::{LevelTypes, Node, Visit, VisitAll};
/// struct Count(usize);
/// impl Visit<0, u8> for Count {
///     fn visit(&mut self, _: Node, _: &u8) -> bool { self.0 += 1; true }
/// }
/// let mut cols = <(u8,) as LevelTypes>::Columns::default();
/// <(u8,) as LevelTypes>::push_default(&mut cols, 0);
/// let mut c = Count(0);
/// assert!(VisitAll::<(u8,)>::visit_node(&mut c, &cols, Node::new(0, 0.into())));
/// assert!(VisitAll::<(u8,)>::visit_node(&mut c, &cols, Node::new(1, 0.into())));
/// assert_eq!(c.0, 1);
/// ```
pub trait VisitAll<L: LevelTypes> {
    /// Dispatches `s` to the visitor of its level.
    fn visit_node(&mut self, cols: &L::Columns, s: Node) -> bool;
}

impl<V> VisitAll<()> for V {
    fn visit_node(&mut self, _: &(), _: Node) -> bool {
        true
    }
}

impl LevelTypes for () {
    type Columns = ();
    const N_LEVELS: usize = 0;
    #[inline]
    fn push_default(_: &mut (), _: usize) {}
    #[inline]
    fn reset(_: &mut (), _: usize, _: usize) {}
    fn retain(_: &mut (), _: usize, _: &[bool]) {}
    #[inline]
    fn reserve(_: &mut (), _: usize, _: usize) {}
    fn bytes(_: &(), _: usize) -> usize {
        0
    }
    fn reverse_all(_: &mut ()) {}
    fn commit_pop(_: &mut (), _: &mut (), _: usize, _: usize) {}
}

impl<M> MergeAll<()> for M {
    fn stage(&mut self, _: &(), _: &mut (), _: usize, _: &[VertexId], _: &[(&[VertexId], u32)]) {}
}

macro_rules! impl_levels {
    (@each $all:tt; $($K:tt $T:ident),+) => {
        $( impl_levels!(@one $all $K $T); )+
    };
    (@one [$($All:ident),+] $K:tt $T:ident) => {
        impl<$($All: Default + 'static),+> At<$K> for ($($All,)+) {
            type Data = $T;
            #[inline]
            fn column(cols: &Self::Columns) -> &Vec<$T> {
                &cols.$K
            }
            #[inline]
            fn column_mut(cols: &mut Self::Columns) -> &mut Vec<$T> {
                &mut cols.$K
            }
        }
    };
    ($n:expr; $($K:tt $T:ident),+) => {
        impl<$($T: Default + 'static),+> LevelTypes for ($($T,)+) {
            type Columns = ($(Vec<$T>,)+);
            const N_LEVELS: usize = $n;
            #[inline]
            fn push_default(cols: &mut Self::Columns, dim: usize) {
                match dim {
                    $($K => cols.$K.push($T::default()),)+
                    _ => {}
                }
            }
            #[inline]
            fn reset(cols: &mut Self::Columns, dim: usize, i: usize) {
                match dim {
                    $($K => cols.$K[i] = $T::default(),)+
                    _ => {}
                }
            }
            fn retain(cols: &mut Self::Columns, dim: usize, keep: &[bool]) {
                match dim {
                    $($K => {
                        let mut i = 0;
                        cols.$K.retain(|_| {
                            i += 1;
                            keep[i - 1]
                        });
                    })+
                    _ => {}
                }
            }
            fn reserve(cols: &mut Self::Columns, dim: usize, n: usize) {
                match dim {
                    $($K => cols.$K.reserve(n),)+
                    _ => {}
                }
            }
            fn bytes(cols: &Self::Columns, dim: usize) -> usize {
                match dim {
                    $($K => cols.$K.capacity() * std::mem::size_of::<$T>(),)+
                    _ => 0,
                }
            }
            fn reverse_all(cols: &mut Self::Columns) {
                $(cols.$K.reverse();)+
            }
            fn commit_pop(cols: &mut Self::Columns, staged: &mut Self::Columns, dim: usize, i: usize) {
                match dim {
                    $($K => {
                        if let Some(x) = staged.$K.pop() {
                            cols.$K[i] = x;
                        }
                    })+
                    _ => {}
                }
            }
        }

        impl<CB, $($T: Default + 'static),+> MergeAll<($($T,)+)> for CB
        where
            CB: $(Merge<$K, $T> +)+
        {
            fn stage(
                &mut self,
                cols: &<($($T,)+) as LevelTypes>::Columns,
                staged: &mut <($($T,)+) as LevelTypes>::Columns,
                dim: usize,
                new: &[VertexId],
                old: &[(&[VertexId], u32)],
            ) {
                match dim {
                    $($K => {
                        let v: Vec<(&[VertexId], &$T)> =
                            old.iter().map(|&(s, i)| (s, &cols.$K[i as usize])).collect();
                        let x = <CB as Merge<$K, $T>>::merge(self, new, &v);
                        staged.$K.push(x);
                    })+
                    _ => {}
                }
            }
        }

        impl<VV, $($T: Default + 'static),+> VisitAll<($($T,)+)> for VV
        where
            VV: $(Visit<$K, $T> +)+
        {
            #[inline]
            fn visit_node(&mut self, cols: &<($($T,)+) as LevelTypes>::Columns, s: Node) -> bool {
                match s.dim as usize {
                    $($K => <VV as Visit<$K, $T>>::visit(self, s, &cols.$K[s.id.index()]),)+
                    _ => true,
                }
            }
        }

        impl_levels!(@each [$($T),+]; $($K $T),+);
    };
}

impl_levels!(1; 0 A);
impl_levels!(2; 0 A, 1 B);
impl_levels!(3; 0 A, 1 B, 2 C);
impl_levels!(4; 0 A, 1 B, 2 C, 3 D);
impl_levels!(5; 0 A, 1 B, 2 C, 3 D, 4 E);
impl_levels!(6; 0 A, 1 B, 2 C, 3 D, 4 E, 5 F);
impl_levels!(7; 0 A, 1 B, 2 C, 3 D, 4 E, 5 F, 6 G);
impl_levels!(8; 0 A, 1 B, 2 C, 3 D, 4 E, 5 F, 6 G, 7 H);
impl_levels!(9; 0 A, 1 B, 2 C, 3 D, 4 E, 5 F, 6 G, 7 H, 8 I);
impl_levels!(10; 0 A, 1 B, 2 C, 3 D, 4 E, 5 F, 6 G, 7 H, 8 I, 9 J);
impl_levels!(11; 0 A, 1 B, 2 C, 3 D, 4 E, 5 F, 6 G, 7 H, 8 I, 9 J, 10 L);
impl_levels!(12; 0 A, 1 B, 2 C, 3 D, 4 E, 5 F, 6 G, 7 H, 8 I, 9 J, 10 L, 11 M);
