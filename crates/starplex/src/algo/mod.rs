//! Algorithms written once against the complex and the query traits.

pub mod cliques;
pub mod components;
pub mod homology;
pub mod info;
pub mod manifold;
pub mod orientation;
pub mod rips;
pub mod simplify;
pub mod surface;
pub mod unionfind;
pub mod validate;
