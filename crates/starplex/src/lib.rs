//! # starplex
//!
//! Topology of meshes and complexes: simplicial complexes of any dimension (manifold or not,
//! pure or not) and CP cell complexes (quads, hexahedra, prisms, pyramids, mixed).
//!
//! Data flow: file → [`io`] reader → [`IndexedComplex`](complex::IndexedComplex) → a
//! representation (Stellar tree, IA*, IS, incidence graph, simplex tree, Hasse complex) → queries
//! through the [`topo`] traits → algorithms ([`algo`]) → writers.
//!
//! ```
//! use starplex::io::{self, ReadOptions};
//! use starplex::algo::info::{info, InfoOptions};
//! let dir = std::env::temp_dir().join(format!("starplex-doc-lib-{}", std::process::id()));
//! std::fs::create_dir_all(&dir).unwrap();
//! let path = dir.join("tet.spx");
//! std::fs::write(&path, "SPX 1\n3 4 1\n0 0 0\n1 0 0\n0 1 0\n0 0 1\ntet 4 0 1 2 3\n").unwrap();
//! // load
//! let k = io::read(&path, &ReadOptions::default()).unwrap().complex;
//! // query
//! let s = info(&k, &InfoOptions::default());
//! assert_eq!(s.f_vector.as_deref(), Some(&[4u64, 6, 4, 1][..]));
//! assert_eq!(s.euler_characteristic, Some(1));
//! assert_eq!(s.n_boundary_faces, Some(4));
//! // save
//! io::write(&dir.join("tet.off"), &k, None).ok();
//! ```
#![warn(missing_docs)]

pub mod algo;
pub mod attr;
pub mod buf;
pub mod cell;
pub mod complex;
pub mod csr;
pub mod error;
pub mod generate;
pub mod hasse;
pub mod ids;
pub mod io;
pub mod limits;
pub mod measure;
pub mod render;
pub mod stellar;
pub mod structures;
pub mod tds;
pub mod testkit;
pub mod topo;

pub use error::Error;
