//! Connected components of any structure, written once against [`TopCells`]: union of the
//! vertices of each top cell (isolated vertices are components).
//!
//! ```
//! use starplex::complex::{ComplexBuilder, BuildOptions};
//! use starplex::cell::CellKind;
//! use starplex::topo::naive::VtIndex;
//! use starplex::algo::components::components;
//! let mut b = ComplexBuilder::new(1).unwrap();
//! for x in 0..5 { b.push_vertex(&[x as f64]).unwrap(); }
//! b.push_cell(CellKind::Simplex(1), &[0, 1]).unwrap();
//! b.push_cell(CellKind::Simplex(1), &[2, 3]).unwrap();
//! let k = b.build(&BuildOptions::default()).unwrap().0;
//! let c = components(&VtIndex::new(&k));
//! assert_eq!(c.n_components, 3);
//! assert_eq!(c.label[0], c.label[1]);
//! ```
use crate::algo::unionfind::UnionFind;
use crate::ids::{CellId, VertexId};
use crate::topo::TopCells;

/// The components: a label per vertex (0-based, numbered by smallest vertex).
///
/// ```
/// use starplex::algo::components::{components, Components};
/// use starplex::topo::naive::VtIndex;
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// // k: the triangles 0-1-2 and 1-3-2, sharing the edge 1-2
/// let c = components(&VtIndex::new(&k));
/// assert_eq!(c, Components { n_components: 1, label: vec![0, 0, 0, 0] });
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Components {
    /// Number of components.
    pub n_components: usize,
    /// Component of each vertex.
    pub label: Vec<u32>,
}

/// Connected components through the top cells.
///
/// ```
/// use starplex::algo::components::components;
/// use starplex::topo::naive::VtIndex;
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// let mut b = ComplexBuilder::new(1).unwrap();
/// for x in 0..4 { b.push_vertex(&[x as f64]).unwrap(); }
/// b.push_cell(CellKind::Simplex(1), &[3, 1]).unwrap();
/// let k = b.build(&BuildOptions::default()).unwrap().0;
/// let c = components(&VtIndex::new(&k));
/// assert_eq!(c.n_components, 3); // {0}, {1, 3}, {2}
/// assert_eq!(c.label, vec![0, 1, 2, 1]); // numbered by smallest vertex
/// ```
pub fn components<S: TopCells + ?Sized>(s: &S) -> Components {
    let n = s.n_vertices();
    let mut uf = UnionFind::new(n);
    let mut buf: Vec<VertexId> = Vec::new();
    for c in 0..s.n_top_cells() {
        buf.clear();
        s.top_cell_vertices(CellId(c as u32), &mut buf);
        for w in &buf[1..] {
            uf.union(buf[0].0, w.0);
        }
    }
    let mut label = vec![u32::MAX; n];
    let mut root_label = vec![u32::MAX; n];
    let mut next = 0u32;
    for (v, l) in label.iter_mut().enumerate() {
        let r = uf.find(v as u32) as usize;
        if root_label[r] == u32::MAX {
            root_label[r] = next;
            next += 1;
        }
        *l = root_label[r];
    }
    Components {
        n_components: next as usize,
        label,
    }
}
