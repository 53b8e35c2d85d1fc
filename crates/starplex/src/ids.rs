//! Typed index newtypes. Every id is a `u32` inside: 4 bytes per reference, and no bare `usize`
//! in public APIs, so a vertex id can never be passed where a cell id is expected.
//!
//! ```
//! use starplex::ids::{VertexId, CellId};
//! let v = VertexId::new(3);
//! assert_eq!(v.index(), 3);
//! assert_eq!(CellId::from_usize(7), Some(CellId::new(7)));
//! assert_eq!(CellId::from_usize(usize::MAX), None);
//! ```

macro_rules! id_type {
    ($(#[$meta:meta])* $name:ident) => {
        $(#[$meta])*
        #[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Debug, Default)]
        #[derive(bytemuck::Pod, bytemuck::Zeroable)]
        #[repr(transparent)]
        pub struct $name(pub u32);

        impl $name {
            /// Wraps a raw index.
            ///
            /// ```
            #[doc = concat!("use starplex::ids::", stringify!($name), ";")]
            #[doc = concat!("let id = ", stringify!($name), "::new(5);")]
            /// assert_eq!(id.0, 5);
            /// assert_eq!(u32::from(id), 5);
            /// ```
            #[inline]
            pub const fn new(i: u32) -> Self {
                Self(i)
            }
            /// The index as `usize`, for indexing arrays.
            ///
            /// ```
            #[doc = concat!("use starplex::ids::", stringify!($name), ";")]
            /// let names = ["a", "b", "c"];
            #[doc = concat!("assert_eq!(names[", stringify!($name), "(2).index()], \"c\");")]
            /// ```
            #[inline]
            pub const fn index(self) -> usize {
                self.0 as usize
            }
            /// Converts a `usize`, or `None` when it does not fit in 32 bits.
            ///
            /// ```
            #[doc = concat!("use starplex::ids::", stringify!($name), ";")]
            #[doc = concat!("assert_eq!(", stringify!($name), "::from_usize(7), Some(", stringify!($name), "(7)));")]
            #[doc = concat!("assert_eq!(", stringify!($name), "::from_usize(1 << 32), None);")]
            /// ```
            #[inline]
            pub fn from_usize(i: usize) -> Option<Self> {
                u32::try_from(i).ok().map(Self)
            }
        }

        impl From<u32> for $name {
            #[inline]
            fn from(i: u32) -> Self {
                Self(i)
            }
        }

        impl From<$name> for u32 {
            #[inline]
            fn from(i: $name) -> u32 {
                i.0
            }
        }

        impl std::fmt::Display for $name {
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                self.0.fmt(f)
            }
        }
    };
}

id_type!(
    /// A vertex of a complex (0-based position in the input file unless said otherwise).
    VertexId
);
id_type!(
    /// A top cell of an [`IndexedComplex`](crate::complex::IndexedComplex) (0-based position in
    /// the input's cell list, across blocks).
    CellId
);
id_type!(
    /// A simplex stored explicitly by a data structure (incidence graph, IS, Hasse complex, ...).
    SimplexId
);
id_type!(
    /// A node of a spatial hierarchy (Stellar tree).
    NodeId
);
id_type!(
    /// A leaf of a Stellar tree.
    LeafId
);
id_type!(
    /// A vertex in a Stellar tree's own numbering (vertices renumbered so that each leaf holds
    /// a contiguous range), as opposed to the input's [`VertexId`]; the tree's
    /// `vertex_to_input` / `vertex_from_input` convert.
    TreeVertexId
);
id_type!(
    /// A top cell in a Stellar tree's own numbering (cells sorted by their leaves), as opposed to
    /// the input's [`CellId`]; the tree's `cell_to_input` / `cell_from_input` convert.
    TreeCellId
);
