//! The Stellar tree in the shared query interface: every relation of [`crate::topo`] derived
//! from its top cells and VT (decoded leaf by leaf), so `starplex query --structure stellar` and
//! the generic algorithms run on it unchanged.
//!
//! ```
//! use starplex::complex::{ComplexBuilder, BuildOptions};
//! use starplex::cell::CellKind;
//! use starplex::ids::VertexId;
//! use starplex::stellar::{StellarTree, StellarOptions};
//! use starplex::topo::{Counts, Storage, Star};
//! let mut b = ComplexBuilder::new(2).unwrap();
//! for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
//! b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
//! b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
//! let k = b.build(&BuildOptions::default()).unwrap().0;
//! let t = StellarTree::build(&k, &StellarOptions::default()).unwrap();
//! assert_eq!(t.f_vector().unwrap(), vec![4, 5, 2]);
//! assert_eq!(t.star(&[VertexId(1), VertexId(2)]).unwrap().len(), 3); // the edge and 2 triangles
//! assert!(t.refs() > 0);
//! ```
use super::StellarTree;
use crate::topo::Storage;

crate::impl_relations_from_tops!(StellarTree);

impl Storage for StellarTree {
    /// References of the COMPRESSED encoding (leaf lists and hierarchy) plus the base complex's
    /// cell references.
    fn refs(&self) -> u64 {
        let s = self.stats().storage;
        s.compressed.refs + s.base_refs
    }
    /// Bytes the tree really uses in memory (nodes, leaf arrays, reindexed cells, permutations).
    fn bytes(&self) -> u64 {
        self.stats().storage.in_memory_bytes
    }
}
