//! Algorithms written once against the complex and the query traits.

pub mod components;
pub mod info;
pub mod nonmanifold;
pub mod surface;
pub mod unionfind;
