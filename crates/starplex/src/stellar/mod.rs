//! The Stellar tree: a compressed spatial index over a complex, processed leaf by leaf.
