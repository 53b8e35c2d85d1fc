//! Compact topological data structures, one file each: [`iastar`] (IA*, with ghost simplices),
//! [`simplex_tree`] (Boissonnat–Maria), [`ig`] (incidence graph), [`is`] (IS). Every one is
//! built from an [`IndexedComplex`](crate::complex::IndexedComplex) and answers the
//! [`topo`](crate::topo) traits in input numbering (see the table there).

pub mod iastar;
pub mod ig;
pub mod is;
pub mod simplex_tree;
