//! [`VtIndex`]: the plainest structure — the indexed complex plus its vertex→cells relation. The
//! baseline every other structure is compared with.
//!
//! ```
//! use starplex::topo::{naive::VtIndex, TopCells};
//! # use starplex::complex::{ComplexBuilder, BuildOptions};
//! # use starplex::cell::CellKind;
//! # let mut b = ComplexBuilder::new(1).unwrap();
//! # for x in [0.0, 1.0] { b.push_vertex(&[x]).unwrap(); }
//! # b.push_cell(CellKind::Simplex(1), &[0, 1]).unwrap();
//! # let k = b.build(&BuildOptions::default()).unwrap().0;
//! let idx = VtIndex::new(&k);
//! assert_eq!(idx.n_top_cells(), 1);
//! ```
use super::{LocalStar, Storage, TopCells, VertexAdjacency, VertexStar};
use crate::cell::CellKind;
use crate::complex::IndexedComplex;
use crate::csr::Csr;
use crate::ids::{CellId, VertexId};

/// An indexed complex with its vertex→top-cells relation.
///
/// ```
/// use starplex::topo::naive::VtIndex;
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// // k: the triangles 0-1-2 and 1-3-2, sharing the edge 1-2
/// let idx = VtIndex::new(&k);
/// assert!(std::ptr::eq(idx.complex, &k));
/// assert_eq!(idx.vt.row(2), &[0, 1]); // vertex 2 is in both triangles
/// ```
pub struct VtIndex<'a> {
    /// The complex.
    pub complex: &'a IndexedComplex,
    /// Vertex → incident top cells, sorted.
    pub vt: Csr,
}

impl<'a> VtIndex<'a> {
    /// Builds the relation (one pass over the cells).
    ///
    /// ```
    /// use starplex::topo::{naive::VtIndex, Counts};
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// # let mut b = ComplexBuilder::new(2).unwrap();
    /// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
    /// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
    /// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// // k: the triangles 0-1-2 and 1-3-2, sharing the edge 1-2
    /// let idx = VtIndex::new(&k);
    /// assert_eq!(idx.vt, k.vertex_cells());
    /// assert_eq!(idx.f_vector().unwrap(), vec![4, 5, 2]);
    /// ```
    pub fn new(complex: &'a IndexedComplex) -> Self {
        VtIndex {
            complex,
            vt: complex.vertex_cells(),
        }
    }
}

/// An indexed complex is its list of top cells: it answers [`TopCells`] directly, without a
/// vertex → cells relation (which [`VtIndex`] adds).
///
/// ```
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// use starplex::{cell::CellKind, ids::{CellId, VertexId}, topo::TopCells};
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// let mut vs = Vec::new();
/// TopCells::top_cell_vertices(&k, CellId(1), &mut vs);
/// assert_eq!(vs, [VertexId(1), VertexId(3), VertexId(2)]);
/// assert_eq!(TopCells::n_top_cells(&k), 2);
/// ```
impl TopCells for IndexedComplex {
    fn n_vertices(&self) -> usize {
        IndexedComplex::n_vertices(self)
    }
    fn n_top_cells(&self) -> usize {
        self.n_cells()
    }
    fn top_cell_kind(&self, c: CellId) -> CellKind {
        self.cell(c).kind
    }
    fn top_cell_vertices(&self, c: CellId, out: &mut Vec<VertexId>) {
        out.extend(self.cell(c).vertices.iter().map(|&v| VertexId(v)));
    }
}

impl TopCells for VtIndex<'_> {
    fn n_vertices(&self) -> usize {
        IndexedComplex::n_vertices(self.complex)
    }
    fn n_top_cells(&self) -> usize {
        self.complex.n_cells()
    }
    fn top_cell_kind(&self, c: CellId) -> CellKind {
        self.complex.top_cell_kind(c)
    }
    fn top_cell_vertices(&self, c: CellId, out: &mut Vec<VertexId>) {
        self.complex.top_cell_vertices(c, out)
    }
}

impl VertexStar for VtIndex<'_> {
    fn vertex_top_cells(&self, v: VertexId, out: &mut Vec<CellId>) {
        out.clear();
        out.extend(self.vt.row(v.index()).iter().map(|&c| CellId(c)));
    }

    fn star_has_top_containing(&self, s: &[VertexId]) -> Option<bool> {
        if !self.complex.is_simplicial() {
            return None;
        }
        Some(self.vt.row(s[0].index()).iter().any(|&c| {
            let cell = self.complex.cell(CellId(c));
            s.iter().all(|v| cell.vertices.contains(&v.0))
        }))
    }
}

/// The whole complex as one part: it owns every vertex, in input numbering.
///
/// ```
/// use starplex::topo::{naive::VtIndex, LocalStar};
/// use starplex::ids::{CellId, VertexId};
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// let idx = VtIndex::new(&k);
/// assert!(idx.owns(VertexId(3)));
/// assert_eq!(idx.local_top_cells().count(), 2);
/// assert_eq!(idx.local_star(VertexId(2)), [CellId(0), CellId(1)]);
/// assert_eq!(idx.input_cell(CellId(1)), CellId(1));
/// ```
impl LocalStar for VtIndex<'_> {
    type Vertex = VertexId;
    type Cell = CellId;

    fn owned_vertices(&self) -> impl Iterator<Item = VertexId> + '_ {
        (0..self.complex.n_vertices() as u32).map(VertexId)
    }
    fn owns(&self, v: VertexId) -> bool {
        v.index() < self.complex.n_vertices()
    }
    fn local_top_cells(&self) -> impl Iterator<Item = CellId> + '_ {
        (0..self.complex.n_cells() as u32).map(CellId)
    }
    #[inline]
    fn local_star(&self, v: VertexId) -> &[CellId] {
        bytemuck::cast_slice(self.vt.row(v.index()))
    }
    #[inline]
    fn local_cell(&self, c: CellId) -> (CellKind, &[VertexId]) {
        let cell = self.complex.cell(c);
        (cell.kind, bytemuck::cast_slice(cell.vertices))
    }
    fn input_vertex(&self, v: VertexId) -> VertexId {
        v
    }
    fn input_cell(&self, c: CellId) -> CellId {
        c
    }
}

impl VertexAdjacency for VtIndex<'_> {
    fn vertex_neighbours(&self, v: VertexId, out: &mut Vec<VertexId>) {
        out.clear();
        for &c in self.vt.row(v.index()) {
            let cell = self.complex.cell(CellId(c));
            edge_neighbours(cell.kind, cell.vertices, v.0, |w| out.push(VertexId(w)));
        }
        out.sort_unstable();
        out.dedup();
    }
}

impl Storage for VtIndex<'_> {
    /// The top cells' vertex references plus one reference per (vertex, incident cell) pair.
    fn refs(&self) -> u64 {
        (self.complex.n_refs() + self.vt.n_refs()) as u64
    }
    fn bytes(&self) -> u64 {
        (4 * self.complex.n_refs() + self.vt.bytes()) as u64
    }
}

crate::impl_relations_from_tops!(VtIndex<'_>);

/// Calls `f` with every vertex joined to `v` by an edge of the cell (`vertices` in the kind's
/// order; `v` must be one of them).
///
/// ```
/// use starplex::topo::naive::edge_neighbours;
/// use starplex::cell::CellKind;
/// let mut n = Vec::new();
/// edge_neighbours(CellKind::Quad, &[10, 11, 12, 13], 10, |w| n.push(w));
/// assert_eq!(n, [11, 13]); // 12 is across the diagonal
/// n.clear();
/// edge_neighbours(CellKind::Simplex(2), &[10, 11, 12], 10, |w| n.push(w));
/// assert_eq!(n, [11, 12]);
/// ```
pub fn edge_neighbours(kind: CellKind, vertices: &[u32], v: u32, mut f: impl FnMut(u32)) {
    if kind.is_simplex() {
        vertices.iter().filter(|&&w| w != v).for_each(|&w| f(w));
        return;
    }
    if let Some(edges) = kind.cp_faces(1) {
        for e in edges {
            let (a, b) = (vertices[e[0] as usize], vertices[e[1] as usize]);
            if a == v {
                f(b);
            } else if b == v {
                f(a);
            }
        }
    }
}
