//! Algorithms written once against the complex and the query traits.

pub mod components;
pub mod homology;
pub mod info;
pub mod nonmanifold;
pub mod unionfind;
