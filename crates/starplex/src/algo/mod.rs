//! Algorithms written once against the complex and the query traits.

pub mod info;
pub mod unionfind;
