//! Statistics of a Stellar tree: spanning number chi, reference number mu, leaf sizes, and the
//! storage of the EXPLICIT, VERTEX-COMPRESSED and COMPRESSED encodings next to the base complex.
//!
//! Storage model (the paper's §5.2 and the spec's table): references are 32-bit ids; the
//! hierarchy costs 7 references per node in the paper's model and 48 bytes per node in the
//! reference implementation's byte model. EXPLICIT = 7|H| + |V| + Σ|T(leaf)|; VERTEX-COMPRESSED
//! = 7|H| + 2|H_L| + Σ|T(leaf)|; COMPRESSED = 7|H| + 2|H_L| + Σ|SRE(T(leaf))|.
//!
//! ```
//! # use starplex::complex::{ComplexBuilder, BuildOptions};
//! # use starplex::cell::CellKind;
//! use starplex::stellar::{StellarTree, StellarOptions};
//! # let mut b = ComplexBuilder::new(2).unwrap();
//! # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
//! # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
//! # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
//! # let k = b.build(&BuildOptions::default()).unwrap().0;
//! let t = StellarTree::build(&k, &StellarOptions { kv: Some(0), ..Default::default() }).unwrap();
//! let s = t.stats();
//! assert_eq!(s.n_leaves, 1);
//! assert_eq!(s.chi, 1.0);
//! assert_eq!(s.mu, 1.0); // one run of 2 ids is stored as 2 ids
//! ```
use rayon::prelude::*;

use super::sre;
use super::StellarTree;
use crate::ids::LeafId;

/// Storage of one encoding.
///
/// ```
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// # use starplex::stellar::{StellarTree, StellarOptions};
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// # let t = StellarTree::build(&k, &StellarOptions { kv: Some(1), ..Default::default() }).unwrap();
/// // 5 nodes, 4 leaves, 6 cell references in the leaf lists (no runs)
/// let c = &t.stats().storage.compressed;
/// assert_eq!(c.refs, 7 * 5 + 2 * 4 + 6);
/// assert_eq!(c.bytes, 48 * 5 + 4 * (2 * 4 + 6));
/// ```
#[derive(Clone, Debug, Default, PartialEq)]
pub struct EncodingStorage {
    /// References (32-bit ids), hierarchy at 7 per node.
    pub refs: u64,
    /// Bytes: 4 per list reference plus 48 per node (the reference implementation's model).
    pub bytes: u64,
}

/// Storage of the tree's encodings and of the base complex.
///
/// ```
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// # use starplex::stellar::{StellarTree, StellarOptions};
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// # let t = StellarTree::build(&k, &StellarOptions { kv: Some(1), ..Default::default() }).unwrap();
/// let s = t.stats().storage;
/// assert_eq!(s.base_refs, 6); // two triangles
/// assert_eq!(s.base_bytes, 8 * 4 * 2 + 4 * 6); // 4 points in 2D + 6 references
/// assert_eq!(s.explicit.refs, 7 * 5 + 4 + 6);
/// assert!(s.in_memory_bytes > 0);
/// ```
#[derive(Clone, Debug, Default, PartialEq)]
pub struct StorageStats {
    /// Base indexed complex: references of the top cells.
    pub base_refs: u64,
    /// Base indexed complex bytes: 8 per coordinate plus 4 per reference.
    pub base_bytes: u64,
    /// EXPLICIT encoding (excluding the base complex).
    pub explicit: EncodingStorage,
    /// VERTEX-COMPRESSED encoding.
    pub vertex_compressed: EncodingStorage,
    /// COMPRESSED encoding (what starplex stores).
    pub compressed: EncodingStorage,
    /// Bytes this tree actually uses in memory (nodes, leaf arrays, reindexed cells,
    /// permutations).
    pub in_memory_bytes: u64,
}

/// Statistics of a tree.
///
/// ```
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// # use starplex::stellar::{StellarTree, StellarOptions};
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// # let t = StellarTree::build(&k, &StellarOptions { kv: Some(1), ..Default::default() }).unwrap();
/// let s = t.stats();
/// assert_eq!((s.n_nodes, s.n_leaves, s.max_depth), (5, 4, 1));
/// assert_eq!((s.leaf_max_vertices, s.leaf_max_cells), (1, 2));
/// assert_eq!(s.chi, 3.0); // 6 leaf references for 2 triangles
/// assert_eq!(s.leaf_mean_cells, 1.5);
/// ```
#[derive(Clone, Debug, Default, PartialEq)]
pub struct StellarStats {
    /// Nodes (internal + leaves).
    pub n_nodes: u64,
    /// Leaves.
    pub n_leaves: u64,
    /// Bucketing threshold.
    pub kv: u32,
    /// Vertices.
    pub n_vertices: u64,
    /// Top cells.
    pub n_top_cells: u64,
    /// Depth of the deepest leaf (root = 0).
    pub max_depth: u32,
    /// Average spanning number: Σ|T(leaf)| / |T|.
    pub chi: f64,
    /// Average reference number: Σ|SRE(T(leaf))| / |T|.
    pub mu: f64,
    /// Most vertices in a leaf.
    pub leaf_max_vertices: u64,
    /// Mean vertices per leaf.
    pub leaf_mean_vertices: f64,
    /// Most top cells in a leaf.
    pub leaf_max_cells: u64,
    /// Mean top cells per leaf.
    pub leaf_mean_cells: f64,
    /// Storage.
    pub storage: StorageStats,
}

impl StellarTree {
    /// Computes the statistics (one pass over the leaf lists).
    ///
    /// ```
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// # use starplex::stellar::{StellarTree, StellarOptions};
    /// # let mut b = ComplexBuilder::new(2).unwrap();
    /// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
    /// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
    /// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// # let t = StellarTree::build(&k, &StellarOptions { kv: Some(1), ..Default::default() }).unwrap();
    /// let s = t.stats();
    /// assert_eq!((s.n_vertices, s.n_top_cells, s.kv), (4, 2, 1));
    /// assert_eq!(s.mu, 3.0); // no run to compress
    /// ```
    pub fn stats(&self) -> StellarStats {
        let nl = self.n_leaves();
        let sizes: Vec<(u64, u64)> = (0..nl)
            .into_par_iter()
            .map(|l| {
                let enc = self.leaf_encoded_cells(LeafId(l as u32));
                (sre::decoded_len(enc) as u64, enc.len() as u64)
            })
            .collect();
        let sum_t: u64 = sizes.iter().map(|s| s.0).sum();
        let sum_sre: u64 = sizes.iter().map(|s| s.1).sum();
        let nt = self.n_top_cells() as u64;
        let nv = self.n_vertices() as u64;
        let nn = self.n_nodes() as u64;
        let leaf_v: Vec<u64> = (0..nl)
            .map(|l| (self.leaf_vstart[l + 1] - self.leaf_vstart[l]) as u64)
            .collect();
        let hier_refs = 7 * nn;
        let hier_bytes = 48 * nn;
        let base_refs = self.cells.verts.len() as u64;
        let enc = |lists: u64| EncodingStorage {
            refs: hier_refs + lists,
            bytes: hier_bytes + 4 * lists,
        };
        let in_memory_bytes = (std::mem::size_of::<super::TreeNode>() * self.nodes.len()
            + 4 * (self.leaf_vstart.len() + self.leaf_toff.len() + self.leaf_tops.len())
            + self.cells.bytes()
            + 4 * (self.v_orig.len() + self.v_new.len() + self.c_orig.len() + self.c_new.len()))
            as u64;
        StellarStats {
            n_nodes: nn,
            n_leaves: nl as u64,
            kv: self.kv,
            n_vertices: nv,
            n_top_cells: nt,
            max_depth: self.depth(),
            chi: if nt > 0 {
                sum_t as f64 / nt as f64
            } else {
                0.0
            },
            mu: if nt > 0 {
                sum_sre as f64 / nt as f64
            } else {
                0.0
            },
            leaf_max_vertices: leaf_v.iter().copied().max().unwrap_or(0),
            leaf_mean_vertices: if nl > 0 { nv as f64 / nl as f64 } else { 0.0 },
            leaf_max_cells: sizes.iter().map(|s| s.0).max().unwrap_or(0),
            leaf_mean_cells: if nl > 0 {
                sum_t as f64 / nl as f64
            } else {
                0.0
            },
            storage: StorageStats {
                base_refs,
                base_bytes: 8 * nv * self.ambient_dim as u64 + 4 * base_refs,
                explicit: enc(nv + sum_t),
                vertex_compressed: enc(2 * nl as u64 + sum_t),
                compressed: enc(2 * nl as u64 + sum_sre),
                in_memory_bytes,
            },
        }
    }

    /// Depth of the deepest leaf (root = 0).
    ///
    /// ```
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// # use starplex::stellar::{StellarTree, StellarOptions};
    /// # let mut b = ComplexBuilder::new(2).unwrap();
    /// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
    /// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
    /// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// # let t = StellarTree::build(&k, &StellarOptions { kv: Some(1), ..Default::default() }).unwrap();
    /// assert_eq!(t.depth(), 1); // root and four leaves
    /// let one = StellarTree::build(&k, &StellarOptions { kv: Some(0), ..Default::default() }).unwrap();
    /// assert_eq!(one.depth(), 0);
    /// ```
    pub fn depth(&self) -> u32 {
        let mut best = 0;
        let mut stack = vec![(0usize, 0u32)];
        while let Some((n, d)) = stack.pop() {
            let node = self.nodes[n];
            best = best.max(d);
            for c in 0..node.n_children {
                stack.push(((node.first + c) as usize, d + 1));
            }
        }
        best
    }
}
