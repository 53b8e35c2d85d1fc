//! [`IndexedComplex`]: vertices with coordinates in any ambient dimension plus top cells of mixed
//! kinds and dimensions, the representation every reader produces and every structure is built
//! from.
//!
//! Cells are stored in blocks: maximal runs of one [`CellKind`] in input order, each a flat
//! `u32` array. A cell's id is its position in the input's cell list across blocks.
//!
//! ```
//! use starplex::complex::{ComplexBuilder, BuildOptions};
//! use starplex::cell::CellKind;
//! let mut b = ComplexBuilder::new(2).unwrap();
//! for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] {
//!     b.push_vertex(&p).unwrap();
//! }
//! b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
//! b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
//! let (k, report) = b.build(&BuildOptions::default()).unwrap();
//! assert_eq!(k.n_vertices(), 4);
//! assert_eq!(k.n_cells(), 2);
//! assert_eq!(k.cell(starplex::ids::CellId(1)).vertices, &[1, 3, 2]);
//! assert_eq!(report.dropped_face_cells, 0);
//!
//! // A degenerate triangle is refused with the offending ids.
//! let mut b = ComplexBuilder::new(2).unwrap();
//! b.push_vertex(&[0.0, 0.0]).unwrap();
//! b.push_vertex(&[1.0, 0.0]).unwrap();
//! b.push_cell(CellKind::Simplex(2), &[0, 1, 1]).unwrap();
//! let err = b.build(&BuildOptions::default()).unwrap_err();
//! assert_eq!(err.to_string(), "cell 0: vertex 1 appears more than once (degenerate cell; drop such cells with the drop-degenerate option)");
//! ```
use crate::attr::{AttrError, Attributes};
use crate::buf::Buf;
use crate::cell::{CellKind, CellKindError};
use crate::csr::Csr;
use crate::ids::{CellId, VertexId};

/// Largest supported ambient dimension.
///
/// ```
/// use starplex::complex::{ComplexBuilder, ComplexError, MAX_AMBIENT_DIM};
/// assert!(ComplexBuilder::new(MAX_AMBIENT_DIM).is_ok());
/// assert_eq!(
///     ComplexBuilder::new(MAX_AMBIENT_DIM + 1).unwrap_err(),
///     ComplexError::BadAmbientDim(65)
/// );
/// ```
pub const MAX_AMBIENT_DIM: usize = 64;

/// What is wrong with a complex's input. Every variant names the offending ids.
///
/// ```
/// use starplex::complex::{ComplexBuilder, ComplexError, BuildOptions};
/// use starplex::cell::CellKind;
/// let mut b = ComplexBuilder::new(2).unwrap();
/// b.push_vertex(&[0.0, 0.0]).unwrap();
/// b.push_vertex(&[1.0, 0.0]).unwrap();
/// b.push_cell(CellKind::Simplex(1), &[0, 5]).unwrap();
/// let err = b.build(&BuildOptions::default()).unwrap_err();
/// assert_eq!(err, ComplexError::VertexOutOfRange { cell: 0, vertex: 5, n_vertices: 2 });
/// ```
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ComplexError {
    /// A cell refers to a vertex that does not exist.
    #[error(
        "cell {cell}: vertex index {vertex} out of range (the complex has {n_vertices} vertices)"
    )]
    VertexOutOfRange {
        /// Cell id.
        cell: u64,
        /// The index given.
        vertex: u64,
        /// Number of vertices.
        n_vertices: u64,
    },
    /// A vertex appears twice in one cell.
    #[error("cell {cell}: vertex {vertex} appears more than once (degenerate cell; drop such cells with the drop-degenerate option)")]
    RepeatedVertex {
        /// Cell id.
        cell: u64,
        /// The repeated vertex.
        vertex: u64,
    },
    /// A coordinate is NaN or infinite.
    #[error("vertex {vertex}: coordinate {axis} is not finite ({value})")]
    NonFiniteCoordinate {
        /// Vertex id.
        vertex: u64,
        /// Axis (0-based).
        axis: usize,
        /// The value.
        value: f64,
    },
    /// A vertex with the wrong number of coordinates.
    #[error("vertex {vertex}: expected {expected} coordinates, got {got}")]
    WrongCoordinateCount {
        /// Vertex id.
        vertex: u64,
        /// The ambient dimension.
        expected: usize,
        /// Coordinates given.
        got: usize,
    },
    /// A cell with the wrong number of vertices for its kind.
    #[error("cell {cell}: a {kind} needs {expected} vertices, got {got}")]
    WrongVertexCount {
        /// Cell id.
        cell: u64,
        /// Kind name.
        kind: String,
        /// Vertices the kind has.
        expected: usize,
        /// Vertices given.
        got: usize,
    },
    /// Two top cells with the same vertex set.
    #[error("cell {cell} has the same vertices as cell {first} (duplicate top cell; drop it with the duplicate option)")]
    DuplicateCell {
        /// The later cell.
        cell: u64,
        /// The earlier cell.
        first: u64,
    },
    /// A top cell that is a face of another top cell.
    #[error("cell {cell} ({kind}) is a face of cell {other} ({other_kind}); top cells must be maximal (drop such cells with the drop-faces option)")]
    CellIsFaceOf {
        /// The cell that is a face.
        cell: u64,
        /// Its kind.
        kind: String,
        /// The cell it is a face of.
        other: u64,
        /// That cell's kind.
        other_kind: String,
    },
    /// Ambient dimension outside 1..=64.
    #[error("ambient dimension {0} is outside 1..={MAX_AMBIENT_DIM}")]
    BadAmbientDim(usize),
    /// More vertices or cells than 32-bit ids can address.
    #[error(transparent)]
    TooLarge(#[from] crate::limits::TooLarge),
    /// A bad cell kind.
    #[error("cell {cell}: {source}")]
    Kind {
        /// Cell id.
        cell: u64,
        /// What is wrong.
        source: CellKindError,
    },
    /// An attribute column that does not fit the complex.
    #[error(transparent)]
    Attribute(#[from] AttrError),
}

/// A run of cells of one kind, in input order.
///
/// ```
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// use starplex::cell::CellKind;
/// let mut b = ComplexBuilder::new(2).unwrap();
/// for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0], [2.0, 0.0], [2.0, 1.0]] {
///     b.push_vertex(&p).unwrap();
/// }
/// b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
/// b.push_cell(CellKind::Quad, &[1, 4, 5, 3]).unwrap();
/// let (k, _) = b.build(&BuildOptions::default()).unwrap();
/// let blocks = k.blocks();
/// assert_eq!(blocks.len(), 2); // two triangles, then one quad
/// assert_eq!((blocks[1].kind, blocks[1].first), (CellKind::Quad, 2));
/// assert_eq!(&blocks[0].vertices[..], &[0, 1, 2, 1, 3, 2]);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct CellBlock {
    /// Kind of every cell in the block.
    pub kind: CellKind,
    /// Id of the block's first cell.
    pub first: u32,
    /// Vertex ids, `kind.n_vertices()` per cell.
    pub vertices: Buf<u32>,
}

impl CellBlock {
    /// Number of cells in the block.
    ///
    /// ```
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// # let mut b = ComplexBuilder::new(1).unwrap();
    /// # for x in [0.0, 1.0, 2.0] { b.push_vertex(&[x]).unwrap(); }
    /// b.push_cell(CellKind::Simplex(1), &[0, 1]).unwrap();
    /// b.push_cell(CellKind::Simplex(1), &[1, 2]).unwrap();
    /// let (k, _) = b.build(&BuildOptions::default()).unwrap();
    /// assert_eq!(k.blocks()[0].len(), 2);
    /// ```
    pub fn len(&self) -> usize {
        self.vertices.len() / self.kind.n_vertices()
    }
    /// True when the block has no cells.
    ///
    /// ```
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// # let mut b = ComplexBuilder::new(1).unwrap();
    /// # for x in [0.0, 1.0] { b.push_vertex(&[x]).unwrap(); }
    /// b.push_cell(CellKind::Simplex(1), &[0, 1]).unwrap();
    /// let (k, _) = b.build(&BuildOptions::default()).unwrap();
    /// // Blocks of a complex are never empty.
    /// assert!(k.blocks().iter().all(|b| !b.is_empty()));
    /// ```
    pub fn is_empty(&self) -> bool {
        self.vertices.is_empty()
    }
    /// Vertices of the `i`-th cell of the block.
    ///
    /// ```
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// # let mut b = ComplexBuilder::new(1).unwrap();
    /// # for x in [0.0, 1.0, 2.0] { b.push_vertex(&[x]).unwrap(); }
    /// b.push_cell(CellKind::Simplex(1), &[0, 1]).unwrap();
    /// b.push_cell(CellKind::Simplex(1), &[2, 1]).unwrap();
    /// let (k, _) = b.build(&BuildOptions::default()).unwrap();
    /// assert_eq!(k.blocks()[0].cell(1), &[2, 1]);
    /// ```
    #[inline]
    pub fn cell(&self, i: usize) -> &[u32] {
        let n = self.kind.n_vertices();
        &self.vertices[i * n..(i + 1) * n]
    }
}

/// One top cell, borrowed from a complex.
///
/// ```
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// use starplex::{cell::CellKind, ids::CellId};
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// b.push_cell(CellKind::Quad, &[0, 1, 3, 2]).unwrap();
/// let (k, _) = b.build(&BuildOptions::default()).unwrap();
/// let c = k.cell(CellId(0));
/// assert_eq!((c.id, c.kind, c.vertices), (CellId(0), CellKind::Quad, &[0u32, 1, 3, 2][..]));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CellRef<'a> {
    /// Its id.
    pub id: CellId,
    /// Its kind.
    pub kind: CellKind,
    /// Its vertex ids in the kind's (VTK) order.
    pub vertices: &'a [u32],
}

/// Vertices with coordinates plus top cells: the input of every structure in starplex.
///
/// ```
/// use starplex::complex::{ComplexBuilder, BuildOptions};
/// use starplex::cell::CellKind;
/// let mut b = ComplexBuilder::new(3).unwrap();
/// for p in [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]] {
///     b.push_vertex(&p).unwrap();
/// }
/// b.push_cell(CellKind::Simplex(3), &[0, 1, 2, 3]).unwrap();
/// let (k, _) = b.build(&BuildOptions::default()).unwrap();
/// assert_eq!((k.ambient_dim(), k.n_vertices(), k.n_cells(), k.dim()), (3, 4, 1, Some(3)));
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct IndexedComplex {
    ambient_dim: usize,
    coords: Buf<f64>,
    blocks: Vec<CellBlock>,
    n_cells: u32,
    attrs: Attributes,
}

/// Options of [`ComplexBuilder::build`].
///
/// ```
/// use starplex::complex::{ComplexBuilder, BuildOptions};
/// use starplex::cell::CellKind;
/// let mut b = ComplexBuilder::new(1).unwrap();
/// for x in [0.0, 1.0, 2.0] { b.push_vertex(&[x]).unwrap(); }
/// b.push_cell(CellKind::Simplex(1), &[0, 1]).unwrap();
/// b.push_cell(CellKind::Simplex(0), &[1]).unwrap(); // a face of the edge
/// assert!(b.clone().build(&BuildOptions::default()).is_err());
/// let opts = BuildOptions { drop_face_cells: true, ..Default::default() };
/// let (k, report) = b.build(&opts).unwrap();
/// assert_eq!((k.n_cells(), report.dropped_face_cells), (1, 1));
/// ```
#[derive(Clone, Debug, Default)]
pub struct BuildOptions {
    /// Drop top cells that are faces of other top cells instead of failing (the dropped count is
    /// in the [`BuildReport`]).
    pub drop_face_cells: bool,
    /// Drop later copies of duplicate top cells instead of failing.
    pub drop_duplicates: bool,
    /// Skip the maximality and duplicate checks (for inputs known to be clean, e.g. the binary
    /// format written by starplex; index and coordinate checks always run).
    pub trust_maximality: bool,
    /// Drop cells with a repeated vertex (degenerate cells, e.g. a triangle `0 1 1`) instead of
    /// failing; the dropped count is in the [`BuildReport`]. Out-of-range indices still fail.
    pub drop_degenerate: bool,
}

impl BuildOptions {
    /// [`check_cell`] as these options ask: with [`drop_degenerate`](Self::drop_degenerate)
    /// only the index range is checked (a repeated vertex is left for
    /// [`ComplexBuilder::build`] to drop). Readers call this to report a bad index with its line.
    ///
    /// ```
    /// use starplex::complex::{BuildOptions, ComplexError};
    /// let strict = BuildOptions::default();
    /// assert_eq!(strict.check_cell(4, &[0, 1, 1], 3),
    ///            Err(ComplexError::RepeatedVertex { cell: 4, vertex: 1 }));
    /// let lax = BuildOptions { drop_degenerate: true, ..Default::default() };
    /// assert!(lax.check_cell(4, &[0, 1, 1], 3).is_ok());
    /// assert!(matches!(lax.check_cell(4, &[0, 1, 3], 3),
    ///                  Err(ComplexError::VertexOutOfRange { vertex: 3, .. })));
    /// ```
    ///
    /// # Errors
    /// As [`check_cell`], without [`ComplexError::RepeatedVertex`] when degenerate cells are
    /// dropped.
    pub fn check_cell(
        &self,
        cell: u64,
        vertices: &[u32],
        n_vertices: usize,
    ) -> Result<(), ComplexError> {
        if !self.drop_degenerate {
            return check_cell(cell, vertices, n_vertices);
        }
        check_range(cell, vertices, n_vertices)
    }
}

/// The first index of `vertices` that is not below `n_vertices`, as an error.
fn check_range(cell: u64, vertices: &[u32], n_vertices: usize) -> Result<(), ComplexError> {
    match vertices.iter().find(|&&v| v as usize >= n_vertices) {
        Some(&v) => Err(ComplexError::VertexOutOfRange {
            cell,
            vertex: v as u64,
            n_vertices: n_vertices as u64,
        }),
        None => Ok(()),
    }
}

/// What [`ComplexBuilder::build`] changed.
///
/// ```
/// use starplex::complex::{ComplexBuilder, BuildOptions, BuildReport};
/// use starplex::cell::CellKind;
/// let mut b = ComplexBuilder::new(1).unwrap();
/// for x in [0.0, 1.0] { b.push_vertex(&[x]).unwrap(); }
/// b.push_cell(CellKind::Simplex(1), &[0, 1]).unwrap();
/// b.push_cell(CellKind::Simplex(1), &[1, 0]).unwrap(); // the same edge again
/// let opts = BuildOptions { drop_duplicates: true, ..Default::default() };
/// let (k, report) = b.build(&opts).unwrap();
/// assert_eq!(report, BuildReport { dropped_duplicates: 1, ..Default::default() });
/// assert_eq!(k.n_cells(), 1);
/// ```
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct BuildReport {
    /// Cells dropped for being a face of another cell.
    pub dropped_face_cells: usize,
    /// Cells dropped as duplicates.
    pub dropped_duplicates: usize,
    /// Cells dropped for having a repeated vertex ([`BuildOptions::drop_degenerate`]).
    pub dropped_degenerate: usize,
}

/// Accumulates vertices and cells, then checks them into an [`IndexedComplex`].
///
/// ```
/// use starplex::complex::{ComplexBuilder, BuildOptions};
/// use starplex::cell::CellKind;
/// let mut b = ComplexBuilder::new(2).unwrap();
/// let v: Vec<u32> = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]
///     .iter()
///     .map(|p| b.push_vertex(p).unwrap().0)
///     .collect();
/// b.push_cell(CellKind::Simplex(2), &v).unwrap();
/// let (k, _) = b.build(&BuildOptions::default()).unwrap();
/// assert_eq!((k.n_vertices(), k.n_cells()), (3, 1));
/// ```
#[derive(Clone, Debug)]
pub struct ComplexBuilder {
    ambient_dim: usize,
    coords: Vec<f64>,
    blocks: Vec<(CellKind, Vec<u32>)>,
    n_cells: u64,
    attrs: Attributes,
}

impl ComplexBuilder {
    /// A builder for points of `ambient_dim` coordinates.
    ///
    /// ```
    /// use starplex::complex::{ComplexBuilder, ComplexError};
    /// assert_eq!(ComplexBuilder::new(3).unwrap().ambient_dim(), 3);
    /// assert_eq!(ComplexBuilder::new(0).unwrap_err(), ComplexError::BadAmbientDim(0));
    /// ```
    ///
    /// # Errors
    /// `ambient_dim` outside 1..=64.
    pub fn new(ambient_dim: usize) -> Result<ComplexBuilder, ComplexError> {
        if ambient_dim == 0 || ambient_dim > MAX_AMBIENT_DIM {
            return Err(ComplexError::BadAmbientDim(ambient_dim));
        }
        Ok(ComplexBuilder {
            ambient_dim,
            coords: Vec::new(),
            blocks: Vec::new(),
            n_cells: 0,
            attrs: Attributes::default(),
        })
    }

    /// The ambient dimension.
    ///
    /// ```
    /// use starplex::complex::ComplexBuilder;
    /// let b = ComplexBuilder::new(2).unwrap();
    /// assert_eq!(b.ambient_dim(), 2);
    /// ```
    pub fn ambient_dim(&self) -> usize {
        self.ambient_dim
    }

    /// Vertices pushed so far.
    ///
    /// ```
    /// use starplex::complex::ComplexBuilder;
    /// let mut b = ComplexBuilder::new(2).unwrap();
    /// assert_eq!(b.n_vertices(), 0);
    /// b.push_vertex(&[0.5, 0.5]).unwrap();
    /// assert_eq!(b.n_vertices(), 1);
    /// ```
    pub fn n_vertices(&self) -> usize {
        self.coords.len() / self.ambient_dim
    }

    /// Cells pushed so far.
    ///
    /// ```
    /// use starplex::{complex::ComplexBuilder, cell::CellKind};
    /// let mut b = ComplexBuilder::new(2).unwrap();
    /// b.push_cell(CellKind::Simplex(1), &[0, 1]).unwrap();
    /// b.push_cell(CellKind::Quad, &[0, 1, 2, 3]).unwrap();
    /// assert_eq!(b.n_cells(), 2);
    /// ```
    pub fn n_cells(&self) -> u64 {
        self.n_cells
    }

    /// Adds a vertex and returns its id.
    ///
    /// ```
    /// use starplex::complex::{ComplexBuilder, ComplexError};
    /// use starplex::ids::VertexId;
    /// let mut b = ComplexBuilder::new(2).unwrap();
    /// assert_eq!(b.push_vertex(&[0.0, 0.0]), Ok(VertexId(0)));
    /// assert_eq!(b.push_vertex(&[1.0, 2.0]), Ok(VertexId(1)));
    /// assert!(matches!(b.push_vertex(&[1.0]), Err(ComplexError::WrongCoordinateCount { .. })));
    /// assert!(matches!(b.push_vertex(&[f64::NAN, 0.0]), Err(ComplexError::NonFiniteCoordinate { .. })));
    /// ```
    ///
    /// # Errors
    /// Wrong coordinate count, a non-finite coordinate, more than `u32::MAX` vertices.
    pub fn push_vertex(&mut self, p: &[f64]) -> Result<VertexId, ComplexError> {
        let id = self.n_vertices() as u64;
        if p.len() != self.ambient_dim {
            return Err(ComplexError::WrongCoordinateCount {
                vertex: id,
                expected: self.ambient_dim,
                got: p.len(),
            });
        }
        if let Some(axis) = p.iter().position(|x| !x.is_finite()) {
            return Err(ComplexError::NonFiniteCoordinate {
                vertex: id,
                axis,
                value: p[axis],
            });
        }
        if id >= u32::MAX as u64 {
            return Err(ComplexError::TooLarge(crate::limits::TooLarge::ids(
                "vertices",
                (id + 1) as u128,
            )));
        }
        self.coords.extend_from_slice(p);
        Ok(VertexId(id as u32))
    }

    /// Adds a top cell (its vertex order is the kind's VTK order) and returns its id. Index
    /// ranges and repeats are checked by [`build`](Self::build), which sees all vertices; a
    /// reader that knows the vertex count can call [`check_cell`] earlier to report a line.
    ///
    /// ```
    /// use starplex::complex::{ComplexBuilder, ComplexError};
    /// use starplex::{cell::CellKind, ids::CellId};
    /// let mut b = ComplexBuilder::new(3).unwrap();
    /// assert_eq!(b.push_cell(CellKind::Simplex(3), &[0, 1, 2, 3]), Ok(CellId(0)));
    /// assert_eq!(b.push_cell(CellKind::Simplex(1), &[3, 4]), Ok(CellId(1)));
    /// let err = b.push_cell(CellKind::Hex, &[0, 1, 2]).unwrap_err();
    /// assert_eq!(err.to_string(), "cell 2: a hex needs 8 vertices, got 3");
    /// ```
    ///
    /// # Errors
    /// A vertex count that does not fit the kind, more than `u32::MAX` cells.
    pub fn push_cell(&mut self, kind: CellKind, vertices: &[u32]) -> Result<CellId, ComplexError> {
        let id = self.n_cells;
        if vertices.len() != kind.n_vertices() {
            return Err(ComplexError::WrongVertexCount {
                cell: id,
                kind: kind.type_name(),
                expected: kind.n_vertices(),
                got: vertices.len(),
            });
        }
        if id >= u32::MAX as u64 {
            return Err(ComplexError::TooLarge(crate::limits::TooLarge::ids(
                "cells",
                (id + 1) as u128,
            )));
        }
        match self.blocks.last_mut() {
            Some((k, v)) if *k == kind => v.extend_from_slice(vertices),
            _ => self.blocks.push((kind, vertices.to_vec())),
        }
        self.n_cells += 1;
        Ok(CellId(id as u32))
    }

    /// Adds a whole block of top cells of one kind (`vertices` holds them one after another,
    /// in the kind's VTK order) and returns the id of its first cell; the array is moved in,
    /// not copied, when it starts a block. Checked like [`push_cell`](Self::push_cell).
    ///
    /// ```
    /// use starplex::complex::{ComplexBuilder, ComplexError};
    /// use starplex::{cell::CellKind, ids::CellId};
    /// let mut b = ComplexBuilder::new(3).unwrap();
    /// assert_eq!(b.push_cells(CellKind::Simplex(2), vec![0, 1, 2, 1, 2, 3]), Ok(CellId(0)));
    /// assert_eq!(b.push_cells(CellKind::Simplex(1), vec![3, 4]), Ok(CellId(2)));
    /// assert_eq!(b.n_cells(), 3);
    /// let err = b.push_cells(CellKind::Quad, vec![0, 1, 2]).unwrap_err();
    /// assert_eq!(err.to_string(), "cell 3: a quad needs 4 vertices, got 3");
    /// ```
    ///
    /// # Errors
    /// A length that is not a whole number of cells, more than `u32::MAX` cells.
    pub fn push_cells(
        &mut self,
        kind: CellKind,
        vertices: Vec<u32>,
    ) -> Result<CellId, ComplexError> {
        let id = self.n_cells;
        let k = kind.n_vertices();
        if !vertices.len().is_multiple_of(k) {
            return Err(ComplexError::WrongVertexCount {
                cell: id + (vertices.len() / k) as u64,
                kind: kind.type_name(),
                expected: k,
                got: vertices.len() % k,
            });
        }
        let n = (vertices.len() / k) as u64;
        if id + n > u32::MAX as u64 {
            return Err(ComplexError::TooLarge(crate::limits::TooLarge::ids(
                "cells",
                (id + n) as u128,
            )));
        }
        match self.blocks.last_mut() {
            Some((last, v)) if *last == kind => v.extend_from_slice(&vertices),
            _ if n > 0 => self.blocks.push((kind, vertices)),
            _ => {}
        }
        self.n_cells += n;
        Ok(CellId(id as u32))
    }

    /// Adds vertices from a flat coordinate array (`ambient_dim` numbers each; moved in, not
    /// copied, when the builder has none yet) and returns the id of the first.
    ///
    /// ```
    /// use starplex::complex::{ComplexBuilder, ComplexError};
    /// use starplex::ids::VertexId;
    /// let mut b = ComplexBuilder::new(2).unwrap();
    /// assert_eq!(b.push_vertices(vec![0.0, 0.0, 1.0, 0.0]), Ok(VertexId(0)));
    /// assert_eq!(b.push_vertices(vec![0.0, 1.0]), Ok(VertexId(2)));
    /// assert!(matches!(b.push_vertices(vec![1.0]), Err(ComplexError::WrongCoordinateCount { .. })));
    /// assert!(matches!(b.push_vertices(vec![0.0, f64::NAN]),
    ///                  Err(ComplexError::NonFiniteCoordinate { vertex: 3, axis: 1, .. })));
    /// assert_eq!(b.n_vertices(), 3);
    /// ```
    ///
    /// # Errors
    /// A length that is not a whole number of points, a non-finite coordinate, more than
    /// `u32::MAX` vertices; nothing is added then.
    pub fn push_vertices(&mut self, coords: Vec<f64>) -> Result<VertexId, ComplexError> {
        let d = self.ambient_dim;
        let id = self.n_vertices() as u64;
        if !coords.len().is_multiple_of(d) {
            return Err(ComplexError::WrongCoordinateCount {
                vertex: id + (coords.len() / d) as u64,
                expected: d,
                got: coords.len() % d,
            });
        }
        if let Some(i) = coords.iter().position(|x| !x.is_finite()) {
            return Err(ComplexError::NonFiniteCoordinate {
                vertex: id + (i / d) as u64,
                axis: i % d,
                value: coords[i],
            });
        }
        let n = (coords.len() / d) as u64;
        if id + n >= u32::MAX as u64 {
            return Err(ComplexError::TooLarge(crate::limits::TooLarge::ids(
                "vertices",
                (id + n) as u128,
            )));
        }
        if self.coords.is_empty() {
            self.coords = coords;
        } else {
            self.coords.extend_from_slice(&coords);
        }
        Ok(VertexId(id as u32))
    }

    /// Sets the attributes of the complex being built (one item per vertex pushed, one per cell
    /// pushed: checked by [`build`](Self::build), which also drops the items of the cells it
    /// drops).
    ///
    /// ```
    /// use starplex::attr::{Attribute, Attributes};
    /// use starplex::complex::{BuildOptions, ComplexBuilder};
    /// use starplex::cell::CellKind;
    /// let mut b = ComplexBuilder::new(1).unwrap();
    /// for x in [0.0, 1.0, 2.0] { b.push_vertex(&[x]).unwrap(); }
    /// b.push_cell(CellKind::Simplex(1), &[0, 1]).unwrap();
    /// b.push_cell(CellKind::Simplex(0), &[1]).unwrap(); // a face: dropped below
    /// b.push_cell(CellKind::Simplex(1), &[1, 2]).unwrap();
    /// b.set_attributes(Attributes { vertex: vec![], cell: vec![Attribute::int("t", 1, vec![10, 11, 12])] });
    /// let opts = BuildOptions { drop_face_cells: true, ..Default::default() };
    /// let (k, _) = b.build(&opts).unwrap();
    /// assert_eq!(k.attributes().cell[0], Attribute::int("t", 1, vec![10, 12]));
    /// ```
    pub fn set_attributes(&mut self, attrs: Attributes) {
        self.attrs = attrs;
    }

    /// Checks everything and returns the complex.
    ///
    /// ```
    /// use starplex::complex::{ComplexBuilder, BuildOptions, ComplexError};
    /// use starplex::cell::CellKind;
    /// let mut b = ComplexBuilder::new(1).unwrap();
    /// for x in [0.0, 1.0, 2.0] { b.push_vertex(&[x]).unwrap(); }
    /// b.push_cell(CellKind::Simplex(1), &[0, 1]).unwrap();
    /// b.push_cell(CellKind::Simplex(1), &[1, 2]).unwrap();
    /// let (k, report) = b.clone().build(&BuildOptions::default()).unwrap();
    /// assert_eq!((k.n_cells(), report.dropped_duplicates), (2, 0));
    /// b.push_cell(CellKind::Simplex(1), &[2, 1]).unwrap();
    /// let err = b.build(&BuildOptions::default()).unwrap_err();
    /// assert_eq!(err, ComplexError::DuplicateCell { cell: 2, first: 1 });
    ///
    /// // a degenerate triangle (vertex 1 twice) fails, or is dropped on request
    /// let mut b = ComplexBuilder::new(1).unwrap();
    /// for x in [0.0, 1.0, 2.0] { b.push_vertex(&[x]).unwrap(); }
    /// b.push_cell(CellKind::Simplex(2), &[0, 1, 1]).unwrap();
    /// b.push_cell(CellKind::Simplex(1), &[1, 2]).unwrap();
    /// assert!(matches!(b.clone().build(&BuildOptions::default()), Err(ComplexError::RepeatedVertex { cell: 0, vertex: 1 })));
    /// let (k, report) = b.build(&BuildOptions { drop_degenerate: true, ..Default::default() }).unwrap();
    /// assert_eq!((k.n_cells(), report.dropped_degenerate), (1, 1));
    /// ```
    ///
    /// # Errors
    /// The first problem found, in cell order: an index out of range, a repeated vertex (unless
    /// [`BuildOptions::drop_degenerate`]: such cells are dropped first, and the cell ids of later
    /// errors count the kept cells), a duplicate top cell, a top cell that is a face of another
    /// (unless the options drop them).
    pub fn build(
        mut self,
        opts: &BuildOptions,
    ) -> Result<(IndexedComplex, BuildReport), ComplexError> {
        let n_vertices = self.n_vertices();
        // the growth slack of the pushes (up to half of each array) is given back: shrinking
        // reallocates in place, so this costs no copy and no extra peak
        self.coords.shrink_to_fit();
        let blocks: Vec<CellBlock> = {
            let mut first = 0u32;
            self.blocks
                .into_iter()
                .map(|(kind, mut v)| {
                    v.shrink_to_fit();
                    let b = CellBlock {
                        kind,
                        first,
                        vertices: Buf::Owned(v),
                    };
                    first += b.len() as u32;
                    b
                })
                .collect()
        };
        let k = IndexedComplex {
            ambient_dim: self.ambient_dim,
            coords: Buf::Owned(self.coords),
            n_cells: self.n_cells as u32,
            blocks,
            attrs: self.attrs,
        };
        let (k, dropped_degenerate) = if opts.drop_degenerate {
            k.attrs.check(n_vertices, k.n_cells())?;
            k.without_degenerate(n_vertices)?
        } else {
            for b in &k.blocks {
                check_block(b.first as u64, &b.vertices, b.kind.n_vertices(), n_vertices)?;
            }
            k.attrs.check(n_vertices, k.n_cells())?;
            (k, 0)
        };
        let (k, mut report) = if opts.trust_maximality {
            (k, BuildReport::default())
        } else {
            k.check_maximality(opts)?
        };
        report.dropped_degenerate = dropped_degenerate;
        Ok((k, report))
    }
}

/// Checks one cell's vertex indices: in range and pairwise distinct.
///
/// ```
/// use starplex::complex::check_cell;
/// assert!(check_cell(0, &[0, 1, 2], 3).is_ok());
/// assert!(check_cell(0, &[0, 1, 3], 3).is_err());
/// assert!(check_cell(0, &[0, 1, 0], 3).is_err());
/// ```
///
/// # Errors
/// [`ComplexError::VertexOutOfRange`] or [`ComplexError::RepeatedVertex`] naming `cell`.
pub fn check_cell(cell: u64, vertices: &[u32], n_vertices: usize) -> Result<(), ComplexError> {
    for (i, &v) in vertices.iter().enumerate() {
        if v as usize >= n_vertices {
            return Err(ComplexError::VertexOutOfRange {
                cell,
                vertex: v as u64,
                n_vertices: n_vertices as u64,
            });
        }
        if vertices[..i].contains(&v) {
            return Err(ComplexError::RepeatedVertex {
                cell,
                vertex: v as u64,
            });
        }
    }
    Ok(())
}

/// [`check_cell`] over a block of cells of `n` vertices whose first cell is `first`: a fast
/// branch-free check of the whole block, and the per-cell check only to name the first
/// offending cell.
fn check_block(first: u64, verts: &[u32], n: usize, nv: usize) -> Result<(), ComplexError> {
    if !block_is_valid(verts, n, nv) {
        for (i, c) in verts.chunks_exact(n).enumerate() {
            check_cell(first + i as u64, c, nv)?;
        }
    }
    Ok(())
}

/// True when every index of `verts` is below `nv` and the cells of `n` vertices have no
/// repeated vertex (what [`check_cell`] checks, for a whole block, without early exits).
fn block_is_valid(verts: &[u32], n: usize, nv: usize) -> bool {
    // large blocks (complexes built from data) are checked in parallel
    const PAR_REFS: usize = 1 << 20;
    if verts.len() > PAR_REFS {
        use rayon::prelude::*;
        return verts
            .par_chunks(n * (PAR_REFS / 16))
            .all(|c| block_is_valid_serial(c, n, nv));
    }
    block_is_valid_serial(verts, n, nv)
}

fn block_is_valid_serial(verts: &[u32], n: usize, nv: usize) -> bool {
    fn distinct<const N: usize>(verts: &[u32]) -> bool {
        let mut bad = false;
        for c in verts.chunks_exact(N) {
            for i in 1..N {
                for j in 0..i {
                    bad |= c[i] == c[j];
                }
            }
        }
        !bad
    }
    if verts.is_empty() {
        return true;
    }
    let max = verts.iter().fold(0u32, |m, &v| m.max(v));
    if max as usize >= nv {
        return false;
    }
    match n {
        1 => true,
        2 => distinct::<2>(verts),
        3 => distinct::<3>(verts),
        4 => distinct::<4>(verts),
        5 => distinct::<5>(verts),
        6 => distinct::<6>(verts),
        8 => distinct::<8>(verts),
        _ => verts
            .chunks_exact(n)
            .all(|c| (1..n).all(|i| !c[..i].contains(&c[i]))),
    }
}

impl IndexedComplex {
    /// The complex without its cells that have a repeated vertex (their attribute items go with
    /// them; later cells are renumbered), and how many were dropped. Out-of-range indices fail.
    fn without_degenerate(
        self,
        n_vertices: usize,
    ) -> Result<(IndexedComplex, usize), ComplexError> {
        let mut bad: Vec<u32> = Vec::new();
        for c in self.cells() {
            check_range(c.id.0 as u64, c.vertices, n_vertices)?;
            if check_cell(c.id.0 as u64, c.vertices, n_vertices).is_err() {
                bad.push(c.id.0);
            }
        }
        if bad.is_empty() {
            return Ok((self, 0));
        }
        let mut next_bad = bad.iter().peekable();
        let k = self.keep_cells(|c| next_bad.next_if(|&&x| x == c).is_none())?;
        Ok((k, bad.len()))
    }

    /// The complex with the cells `keep` accepts (asked once per cell, in id order; their
    /// attribute items go with them, kept cells renumbered in order), the vertices unchanged.
    fn keep_cells(
        &self,
        mut keep: impl FnMut(u32) -> bool,
    ) -> Result<IndexedComplex, ComplexError> {
        let mut b = ComplexBuilder::new(self.ambient_dim)?;
        b.coords = self.coords.to_vec();
        let mut kept: Vec<u32> = Vec::new();
        for c in self.cells() {
            if keep(c.id.0) {
                b.push_cell(c.kind, c.vertices)?;
                kept.push(c.id.0);
            }
        }
        b.attrs = self.attrs.gather_cells(&kept);
        let (k, _) = b.build(&BuildOptions {
            trust_maximality: true,
            ..BuildOptions::default()
        })?;
        Ok(k)
    }

    /// The cell blocks, consuming the complex (its coordinates and attributes are freed).
    pub(crate) fn into_blocks(self) -> Vec<CellBlock> {
        self.blocks
    }

    /// Assembles a complex from parts already checked elsewhere (the binary reader checks
    /// indices itself); cell ids follow the block order.
    ///
    /// ```
    /// use starplex::complex::{IndexedComplex, ComplexError};
    /// use starplex::{buf::Buf, cell::CellKind};
    /// let coords = Buf::from(vec![0.0, 0.0, 1.0, 0.0, 0.0, 1.0]);
    /// let tri = vec![(CellKind::Simplex(2), Buf::from(vec![0, 1, 2]))];
    /// let k = IndexedComplex::from_parts(2, coords.clone(), tri).unwrap();
    /// assert_eq!((k.n_vertices(), k.n_cells()), (3, 1));
    /// let bad = vec![(CellKind::Simplex(2), Buf::from(vec![0, 1, 3]))];
    /// let err = IndexedComplex::from_parts(2, coords, bad).unwrap_err();
    /// assert_eq!(err, ComplexError::VertexOutOfRange { cell: 0, vertex: 3, n_vertices: 3 });
    /// ```
    ///
    /// # Errors
    /// Wrong coordinate array length, out-of-range or repeated vertex indices, non-finite
    /// coordinates.
    pub fn from_parts(
        ambient_dim: usize,
        coords: Buf<f64>,
        blocks: Vec<(CellKind, Buf<u32>)>,
    ) -> Result<IndexedComplex, ComplexError> {
        IndexedComplex::from_parts_inner(ambient_dim, coords, blocks, false)
    }

    /// [`from_parts`](Self::from_parts) for cells that the crate itself generated with their
    /// indices in range and no vertex repeated (the clique blocks of a Rips complex): the cells
    /// are only checked in debug builds.
    pub(crate) fn from_generated_parts(
        ambient_dim: usize,
        coords: Buf<f64>,
        blocks: Vec<(CellKind, Buf<u32>)>,
    ) -> Result<IndexedComplex, ComplexError> {
        IndexedComplex::from_parts_inner(ambient_dim, coords, blocks, true)
    }

    fn from_parts_inner(
        ambient_dim: usize,
        coords: Buf<f64>,
        blocks: Vec<(CellKind, Buf<u32>)>,
        trusted: bool,
    ) -> Result<IndexedComplex, ComplexError> {
        if ambient_dim == 0 || ambient_dim > MAX_AMBIENT_DIM {
            return Err(ComplexError::BadAmbientDim(ambient_dim));
        }
        if !coords.len().is_multiple_of(ambient_dim) {
            return Err(ComplexError::WrongCoordinateCount {
                vertex: (coords.len() / ambient_dim) as u64,
                expected: ambient_dim,
                got: coords.len() % ambient_dim,
            });
        }
        let nv = coords.len() / ambient_dim;
        if nv >= u32::MAX as usize {
            return Err(ComplexError::TooLarge(crate::limits::TooLarge::ids(
                "vertices", nv as u128,
            )));
        }
        if let Some(i) = coords.iter().position(|x| !x.is_finite()) {
            return Err(ComplexError::NonFiniteCoordinate {
                vertex: (i / ambient_dim) as u64,
                axis: i % ambient_dim,
                value: coords[i],
            });
        }
        let mut first: u64 = 0;
        let mut out = Vec::with_capacity(blocks.len());
        for (kind, v) in blocks {
            let n = kind.n_vertices();
            if v.len() % n != 0 {
                return Err(ComplexError::WrongVertexCount {
                    cell: first + (v.len() / n) as u64,
                    kind: kind.type_name(),
                    expected: n,
                    got: v.len() % n,
                });
            }
            let b = CellBlock {
                kind,
                first: first as u32,
                vertices: v,
            };
            if trusted {
                debug_assert!(check_block(first, &b.vertices, n, nv).is_ok());
            } else {
                check_block(first, &b.vertices, n, nv)?;
            }
            first += b.len() as u64;
            if first >= u32::MAX as u64 {
                return Err(ComplexError::TooLarge(crate::limits::TooLarge::ids(
                    "cells",
                    first as u128,
                )));
            }
            if !b.is_empty() {
                out.push(b);
            }
        }
        Ok(IndexedComplex {
            ambient_dim,
            coords,
            blocks: out,
            n_cells: first as u32,
            attrs: Attributes::default(),
        })
    }

    /// [`from_parts`](Self::from_parts) followed by the checks of [`ComplexBuilder::build`]:
    /// duplicate top cells and top cells that are faces of others are errors, or dropped as
    /// `opts` asks. The path for cell arrays handed over whole (the Python bindings).
    ///
    /// ```
    /// use starplex::complex::{BuildOptions, IndexedComplex};
    /// use starplex::{buf::Buf, cell::CellKind};
    /// let coords = Buf::from(vec![0.0, 0.0, 1.0, 0.0, 0.0, 1.0]);
    /// let twice = vec![(CellKind::Simplex(2), Buf::from(vec![0, 1, 2, 2, 1, 0]))];
    /// let opts = BuildOptions::default();
    /// assert!(IndexedComplex::from_parts_checked(2, coords.clone(), twice.clone(), &opts).is_err());
    /// let opts = BuildOptions { drop_duplicates: true, ..Default::default() };
    /// let (k, report) = IndexedComplex::from_parts_checked(2, coords, twice, &opts).unwrap();
    /// assert_eq!((k.n_cells(), report.dropped_duplicates), (1, 1));
    /// ```
    ///
    /// # Errors
    /// Everything [`from_parts`](Self::from_parts) refuses, then the first duplicate or face
    /// cell not dropped by `opts`.
    pub fn from_parts_checked(
        ambient_dim: usize,
        coords: Buf<f64>,
        blocks: Vec<(CellKind, Buf<u32>)>,
        opts: &BuildOptions,
    ) -> Result<(IndexedComplex, BuildReport), ComplexError> {
        IndexedComplex::from_parts_with_attributes(
            ambient_dim,
            coords,
            blocks,
            Attributes::default(),
            opts,
        )
    }

    /// [`from_parts_checked`](Self::from_parts_checked) with attributes: one item per given
    /// vertex and per given cell; cells dropped by `opts` take their items along.
    ///
    /// ```
    /// use starplex::attr::{Attribute, Attributes};
    /// use starplex::complex::{BuildOptions, IndexedComplex};
    /// use starplex::{buf::Buf, cell::CellKind};
    /// let coords = Buf::from(vec![0.0, 0.0, 1.0, 0.0, 0.0, 1.0]);
    /// let twice = vec![(CellKind::Simplex(2), Buf::from(vec![0, 1, 2, 2, 1, 0]))];
    /// let tags = Attributes { vertex: vec![], cell: vec![Attribute::int("tag", 1, vec![5, 6])] };
    /// let opts = BuildOptions { drop_duplicates: true, ..Default::default() };
    /// let (k, _) = IndexedComplex::from_parts_with_attributes(2, coords, twice, tags, &opts).unwrap();
    /// assert_eq!(k.attributes().cell[0], Attribute::int("tag", 1, vec![5]));
    /// ```
    ///
    /// # Errors
    /// Everything [`from_parts_checked`](Self::from_parts_checked) refuses, and
    /// [`ComplexError::Attribute`] naming the first column that does not fit (checked against
    /// the cells as given, before any is dropped).
    pub fn from_parts_with_attributes(
        ambient_dim: usize,
        coords: Buf<f64>,
        blocks: Vec<(CellKind, Buf<u32>)>,
        attrs: Attributes,
        opts: &BuildOptions,
    ) -> Result<(IndexedComplex, BuildReport), ComplexError> {
        let mut k = IndexedComplex::from_parts(ambient_dim, coords, blocks)?;
        k.set_attributes(attrs)?;
        if opts.trust_maximality {
            return Ok((k, BuildReport::default()));
        }
        k.check_maximality(opts)
    }

    /// The vertex and cell attributes (empty unless a reader or the user set some).
    ///
    /// ```
    /// use starplex::attr::{Attribute, Attributes};
    /// use starplex::complex::IndexedComplex;
    /// use starplex::cell::CellKind;
    /// let mut k = IndexedComplex::from_parts(1, vec![0.0, 1.0].into(),
    ///     vec![(CellKind::Simplex(1), vec![0, 1].into())]).unwrap();
    /// assert!(k.attributes().is_empty());
    /// let a = Attributes { vertex: vec![], cell: vec![Attribute::int("tag", 1, vec![4])] };
    /// k.set_attributes(a).unwrap();
    /// assert_eq!(k.attributes().cell[0].name, "tag");
    /// ```
    pub fn attributes(&self) -> &Attributes {
        &self.attrs
    }

    /// Replaces the attributes, after checking that each column has one item per vertex or per
    /// cell.
    ///
    /// ```
    /// use starplex::attr::{Attribute, Attributes};
    /// use starplex::complex::IndexedComplex;
    /// use starplex::cell::CellKind;
    /// let mut k = IndexedComplex::from_parts(1, vec![0.0, 1.0].into(),
    ///     vec![(CellKind::Simplex(1), vec![0, 1].into())]).unwrap();
    /// let two_cells = Attributes { vertex: vec![], cell: vec![Attribute::int("t", 1, vec![1, 2])] };
    /// assert!(k.set_attributes(two_cells).is_err());
    /// assert!(k.attributes().is_empty()); // unchanged
    /// ```
    ///
    /// # Errors
    /// [`ComplexError::Attribute`] naming the first column that does not fit.
    pub fn set_attributes(&mut self, attrs: Attributes) -> Result<(), ComplexError> {
        attrs.check(self.n_vertices(), self.n_cells())?;
        self.attrs = attrs;
        Ok(())
    }

    /// Removes and returns the attributes.
    ///
    /// ```
    /// use starplex::complex::IndexedComplex;
    /// use starplex::cell::CellKind;
    /// let mut k = IndexedComplex::from_parts(1, vec![0.0, 1.0].into(),
    ///     vec![(CellKind::Simplex(1), vec![0, 1].into())]).unwrap();
    /// assert!(k.take_attributes().is_empty());
    /// ```
    pub fn take_attributes(&mut self) -> Attributes {
        std::mem::take(&mut self.attrs)
    }

    /// Number of coordinates per vertex.
    ///
    /// ```
    /// # use starplex::complex::IndexedComplex;
    /// # use starplex::{buf::Buf, cell::CellKind};
    /// let coords = Buf::from(vec![0.0, 0.0, 0.0, 1.0, 0.0, 0.0]); // two points in 3D
    /// let k = IndexedComplex::from_parts(3, coords, vec![(CellKind::Simplex(1), vec![0, 1].into())]).unwrap();
    /// assert_eq!(k.ambient_dim(), 3);
    /// ```
    #[inline]
    pub fn ambient_dim(&self) -> usize {
        self.ambient_dim
    }

    /// Number of vertices (isolated ones included).
    ///
    /// ```
    /// # use starplex::complex::IndexedComplex;
    /// # use starplex::{buf::Buf, cell::CellKind};
    /// // Three points on a line, the last one in no cell.
    /// let coords = Buf::from(vec![0.0, 1.0, 5.0]);
    /// let k = IndexedComplex::from_parts(1, coords, vec![(CellKind::Simplex(1), vec![0, 1].into())]).unwrap();
    /// assert_eq!(k.n_vertices(), 3);
    /// ```
    #[inline]
    pub fn n_vertices(&self) -> usize {
        self.coords.len() / self.ambient_dim
    }

    /// Number of top cells.
    ///
    /// ```
    /// # use starplex::complex::IndexedComplex;
    /// # use starplex::{buf::Buf, cell::CellKind};
    /// let edges = vec![
    ///     (CellKind::Simplex(1), Buf::from(vec![0, 1, 1, 2])),
    ///     (CellKind::Simplex(0), Buf::from(vec![3])),
    /// ];
    /// let k = IndexedComplex::from_parts(1, vec![0.0, 1.0, 2.0, 5.0].into(), edges).unwrap();
    /// assert_eq!(k.n_cells(), 3);
    /// ```
    #[inline]
    pub fn n_cells(&self) -> usize {
        self.n_cells as usize
    }

    /// Coordinates of vertex `v`.
    ///
    /// ```
    /// # use starplex::complex::IndexedComplex;
    /// # use starplex::{buf::Buf, cell::CellKind, ids::VertexId};
    /// let coords = Buf::from(vec![0.0, 0.0, 1.0, 2.0]);
    /// let k = IndexedComplex::from_parts(2, coords, vec![(CellKind::Simplex(1), vec![0, 1].into())]).unwrap();
    /// assert_eq!(k.point(VertexId(1)), &[1.0, 2.0]);
    /// ```
    #[inline]
    pub fn point(&self, v: VertexId) -> &[f64] {
        let d = self.ambient_dim;
        &self.coords[v.index() * d..(v.index() + 1) * d]
    }

    /// All coordinates, `ambient_dim` per vertex.
    ///
    /// ```
    /// # use starplex::complex::IndexedComplex;
    /// # use starplex::{buf::Buf, cell::CellKind};
    /// let coords = Buf::from(vec![0.0, 0.0, 1.0, 2.0]);
    /// let k = IndexedComplex::from_parts(2, coords, vec![(CellKind::Simplex(1), vec![0, 1].into())]).unwrap();
    /// assert_eq!(k.coords(), &[0.0, 0.0, 1.0, 2.0]);
    /// assert_eq!(k.coords().chunks(k.ambient_dim()).nth(1), Some(&[1.0, 2.0][..]));
    /// ```
    #[inline]
    pub fn coords(&self) -> &[f64] {
        &self.coords
    }

    /// The coordinate buffer (owned or mapped).
    ///
    /// ```
    /// # use starplex::complex::IndexedComplex;
    /// # use starplex::{buf::Buf, cell::CellKind};
    /// let coords = Buf::from(vec![0.0, 0.0, 1.0, 2.0]);
    /// let k = IndexedComplex::from_parts(2, coords, vec![(CellKind::Simplex(1), vec![0, 1].into())]).unwrap();
    /// assert!(!k.coords_buf().is_mapped()); // built in memory, not loaded from a mapped file
    /// assert_eq!(&k.coords_buf()[..], k.coords());
    /// ```
    pub fn coords_buf(&self) -> &Buf<f64> {
        &self.coords
    }

    /// Replaces the coordinates (same vertex count and ambient dimension).
    ///
    /// ```
    /// # use starplex::complex::IndexedComplex;
    /// # use starplex::{buf::Buf, cell::CellKind, ids::VertexId};
    /// let coords = Buf::from(vec![0.0, 0.0, 1.0, 2.0]);
    /// let mut k = IndexedComplex::from_parts(2, coords, vec![(CellKind::Simplex(1), vec![0, 1].into())]).unwrap();
    /// k.set_coords(vec![10.0, 0.0, 11.0, 2.0]).unwrap();
    /// assert_eq!(k.point(VertexId(0)), &[10.0, 0.0]);
    /// assert!(k.set_coords(vec![1.0, 2.0]).is_err());       // wrong length
    /// assert!(k.set_coords(vec![0.0, 0.0, 1.0, f64::INFINITY]).is_err());
    /// ```
    ///
    /// # Errors
    /// A wrong length or a non-finite value.
    pub fn set_coords(&mut self, coords: Vec<f64>) -> Result<(), ComplexError> {
        if coords.len() != self.coords.len() {
            return Err(ComplexError::WrongCoordinateCount {
                vertex: (coords.len() / self.ambient_dim) as u64,
                expected: self.ambient_dim,
                got: coords.len() % self.ambient_dim,
            });
        }
        if let Some(i) = coords.iter().position(|x| !x.is_finite()) {
            return Err(ComplexError::NonFiniteCoordinate {
                vertex: (i / self.ambient_dim) as u64,
                axis: i % self.ambient_dim,
                value: coords[i],
            });
        }
        self.coords = Buf::Owned(coords);
        Ok(())
    }

    /// The blocks (runs of one kind) in cell-id order.
    ///
    /// ```
    /// # use starplex::complex::IndexedComplex;
    /// # use starplex::{buf::Buf, cell::CellKind};
    /// let blocks = vec![
    ///     (CellKind::Simplex(2), Buf::from(vec![0, 1, 2])),
    ///     (CellKind::Quad, Buf::from(vec![1, 4, 5, 3])),
    /// ];
    /// let coords = Buf::from(vec![0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0, 1.0, 2.0, 0.0, 2.0, 1.0]);
    /// let k = IndexedComplex::from_parts(2, coords, blocks).unwrap();
    /// let kinds: Vec<_> = k.blocks().iter().map(|b| (b.kind, b.first)).collect();
    /// assert_eq!(kinds, [(CellKind::Simplex(2), 0), (CellKind::Quad, 1)]);
    /// ```
    #[inline]
    pub fn blocks(&self) -> &[CellBlock] {
        &self.blocks
    }

    /// The top cell with id `c`.
    ///
    /// ```
    /// # use starplex::complex::IndexedComplex;
    /// # use starplex::{buf::Buf, cell::CellKind, ids::CellId};
    /// # let blocks = vec![
    /// #     (CellKind::Simplex(2), Buf::from(vec![0, 1, 2])),
    /// #     (CellKind::Quad, Buf::from(vec![1, 4, 5, 3])),
    /// # ];
    /// # let coords = Buf::from(vec![0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0, 1.0, 2.0, 0.0, 2.0, 1.0]);
    /// // A triangle (cell 0), then a quad (cell 1).
    /// let k = IndexedComplex::from_parts(2, coords, blocks).unwrap();
    /// let c = k.cell(CellId(1));
    /// assert_eq!((c.kind, c.vertices), (CellKind::Quad, &[1u32, 4, 5, 3][..]));
    /// ```
    ///
    /// # Panics
    /// When `c` is out of range; see [`IndexedComplex::try_cell`].
    #[inline]
    pub fn cell(&self, c: CellId) -> CellRef<'_> {
        self.try_cell(c).expect("cell id out of range")
    }

    /// The top cell with id `c`, or `None` when out of range.
    ///
    /// ```
    /// # use starplex::complex::IndexedComplex;
    /// # use starplex::{buf::Buf, cell::CellKind, ids::CellId};
    /// let coords = Buf::from(vec![0.0, 1.0]);
    /// let k = IndexedComplex::from_parts(1, coords, vec![(CellKind::Simplex(1), vec![0, 1].into())]).unwrap();
    /// assert_eq!(k.try_cell(CellId(0)).unwrap().vertices, &[0, 1]);
    /// assert!(k.try_cell(CellId(1)).is_none());
    /// ```
    #[inline]
    pub fn try_cell(&self, c: CellId) -> Option<CellRef<'_>> {
        if c.0 >= self.n_cells {
            return None;
        }
        let bi = match self.blocks.len() {
            1 => 0,
            _ => self.blocks.partition_point(|b| b.first <= c.0) - 1,
        };
        let b = &self.blocks[bi];
        Some(CellRef {
            id: c,
            kind: b.kind,
            vertices: b.cell((c.0 - b.first) as usize),
        })
    }

    /// All top cells in id order.
    ///
    /// ```
    /// # use starplex::complex::IndexedComplex;
    /// # use starplex::{buf::Buf, cell::CellKind};
    /// # let blocks = vec![
    /// #     (CellKind::Simplex(2), Buf::from(vec![0, 1, 2])),
    /// #     (CellKind::Quad, Buf::from(vec![1, 4, 5, 3])),
    /// # ];
    /// # let coords = Buf::from(vec![0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0, 1.0, 2.0, 0.0, 2.0, 1.0]);
    /// // A triangle (cell 0), then a quad (cell 1).
    /// let k = IndexedComplex::from_parts(2, coords, blocks).unwrap();
    /// let sizes: Vec<(u32, usize)> = k.cells().map(|c| (c.id.0, c.vertices.len())).collect();
    /// assert_eq!(sizes, [(0, 3), (1, 4)]);
    /// ```
    pub fn cells(&self) -> impl Iterator<Item = CellRef<'_>> + '_ {
        self.blocks.iter().flat_map(|b| {
            (0..b.len()).map(move |i| CellRef {
                id: CellId(b.first + i as u32),
                kind: b.kind,
                vertices: b.cell(i),
            })
        })
    }

    /// Largest top-cell dimension (`Some(0)` for vertices only, `None` for an empty complex).
    ///
    /// ```
    /// # use starplex::complex::IndexedComplex;
    /// # use starplex::{buf::Buf, cell::CellKind};
    /// let edge = vec![(CellKind::Simplex(1), Buf::from(vec![0, 1]))];
    /// let k = IndexedComplex::from_parts(1, vec![0.0, 1.0].into(), edge).unwrap();
    /// assert_eq!(k.dim(), Some(1));
    /// let points = IndexedComplex::from_parts(1, vec![0.0, 1.0].into(), vec![]).unwrap();
    /// assert_eq!(points.dim(), Some(0));
    /// let empty = IndexedComplex::from_parts(1, Buf::default(), vec![]).unwrap();
    /// assert_eq!(empty.dim(), None);
    /// ```
    pub fn dim(&self) -> Option<usize> {
        let d = self.blocks.iter().map(|b| b.kind.dim()).max();
        match d {
            Some(d) => Some(d),
            None if self.n_vertices() > 0 => Some(0),
            None => None,
        }
    }

    /// Total number of vertex references in the cells.
    ///
    /// ```
    /// # use starplex::complex::IndexedComplex;
    /// # use starplex::{buf::Buf, cell::CellKind};
    /// # let blocks = vec![
    /// #     (CellKind::Simplex(2), Buf::from(vec![0, 1, 2])),
    /// #     (CellKind::Quad, Buf::from(vec![1, 4, 5, 3])),
    /// # ];
    /// # let coords = Buf::from(vec![0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0, 1.0, 2.0, 0.0, 2.0, 1.0]);
    /// // A triangle and a quad.
    /// let k = IndexedComplex::from_parts(2, coords, blocks).unwrap();
    /// assert_eq!(k.n_refs(), 3 + 4);
    /// ```
    pub fn n_refs(&self) -> usize {
        self.blocks.iter().map(|b| b.vertices.len()).sum()
    }

    /// True when every cell is a simplex.
    ///
    /// ```
    /// # use starplex::complex::IndexedComplex;
    /// # use starplex::{buf::Buf, cell::CellKind};
    /// let coords = Buf::from(vec![0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0, 1.0]);
    /// let tri = vec![(CellKind::Simplex(2), Buf::from(vec![0, 1, 2]))];
    /// assert!(IndexedComplex::from_parts(2, coords.clone(), tri).unwrap().is_simplicial());
    /// let quad = vec![(CellKind::Quad, Buf::from(vec![0, 1, 3, 2]))];
    /// assert!(!IndexedComplex::from_parts(2, coords, quad).unwrap().is_simplicial());
    /// ```
    pub fn is_simplicial(&self) -> bool {
        self.blocks.iter().all(|b| b.kind.is_simplex())
    }

    /// Bytes of the complex itself: coordinates, cell vertex arrays and attribute values.
    ///
    /// ```
    /// # use starplex::complex::IndexedComplex;
    /// # use starplex::{buf::Buf, cell::CellKind};
    /// let coords = Buf::from(vec![0.0, 0.0, 1.0, 0.0, 0.0, 1.0]);
    /// let tri = vec![(CellKind::Simplex(2), Buf::from(vec![0, 1, 2]))];
    /// let k = IndexedComplex::from_parts(2, coords, tri).unwrap();
    /// // 6 coordinates of 8 bytes and 3 vertex ids of 4 bytes, plus the block header.
    /// assert!(k.bytes() >= 6 * 8 + 3 * 4);
    /// ```
    pub fn bytes(&self) -> usize {
        8 * self.coords.len()
            + 4 * self.n_refs()
            + std::mem::size_of::<CellBlock>() * self.blocks.len()
            + self.attrs.bytes()
    }

    /// For each vertex, whether any cell uses it.
    ///
    /// ```
    /// # use starplex::complex::IndexedComplex;
    /// # use starplex::{buf::Buf, cell::CellKind};
    /// let coords = Buf::from(vec![0.0, 1.0, 2.0, 9.0]);
    /// let edges = vec![(CellKind::Simplex(1), Buf::from(vec![0, 1, 1, 2]))];
    /// let k = IndexedComplex::from_parts(1, coords, edges).unwrap();
    /// let used = k.used_vertices();
    /// assert_eq!(used.ones().collect::<Vec<_>>(), [0, 1, 2]); // vertex 3 is isolated
    /// ```
    pub fn used_vertices(&self) -> fixedbitset::FixedBitSet {
        let mut used = fixedbitset::FixedBitSet::with_capacity(self.n_vertices());
        for b in &self.blocks {
            for &v in b.vertices.iter() {
                used.insert(v as usize);
            }
        }
        used
    }

    /// Number of vertices in no cell.
    ///
    /// ```
    /// # use starplex::complex::IndexedComplex;
    /// # use starplex::{buf::Buf, cell::CellKind};
    /// let coords = Buf::from(vec![0.0, 1.0, 2.0, 9.0]);
    /// let edges = vec![(CellKind::Simplex(1), Buf::from(vec![0, 1, 1, 2]))];
    /// let k = IndexedComplex::from_parts(1, coords, edges).unwrap();
    /// assert_eq!(k.n_isolated_vertices(), 1);
    /// ```
    pub fn n_isolated_vertices(&self) -> usize {
        self.n_vertices() - self.used_vertices().count_ones(..)
    }

    /// The relation vertex → incident top cells (R_{0,top}), cells sorted by id in each row.
    ///
    /// ```
    /// # use starplex::complex::IndexedComplex;
    /// # use starplex::{buf::Buf, cell::CellKind};
    /// let coords = Buf::from(vec![0.0, 1.0, 2.0, 9.0]);
    /// let edges = vec![(CellKind::Simplex(1), Buf::from(vec![0, 1, 1, 2]))];
    /// let k = IndexedComplex::from_parts(1, coords, edges).unwrap();
    /// let vc = k.vertex_cells();
    /// assert_eq!(vc.n_rows(), 4);
    /// assert_eq!(vc.row(1), &[0, 1]); // vertex 1 is in both edges
    /// assert!(vc.row(3).is_empty());
    /// ```
    pub fn vertex_cells(&self) -> Csr {
        // a count pass, then a fill in cell order (so rows come out sorted) by csr::scatter
        let nv = self.n_vertices();
        let mut offsets = vec![0u32; nv + 1];
        for b in &self.blocks {
            for &v in b.vertices.iter() {
                offsets[v as usize + 1] += 1;
            }
        }
        for i in 0..nv {
            offsets[i + 1] += offsets[i];
        }
        let targets = crate::csr::scatter(&offsets, |sink| {
            for b in &self.blocks {
                let n = b.kind.n_vertices();
                for (i, cell) in b.vertices.chunks_exact(n).enumerate() {
                    let c = b.first + i as u32;
                    for &v in cell {
                        sink.emit(v, c);
                    }
                }
            }
        });
        Csr { offsets, targets }
    }

    /// Duplicate cells (same vertex set) and cells that are faces of other cells.
    ///
    /// Duplicates: sort the cells by a hash of their sorted vertex set and compare equal-hash
    /// runs exactly (O(n log n), cache-friendly). Faces: only cells below the top dimension can
    /// be faces of others; each scans the cells around its least-used vertex.
    fn check_maximality(
        self,
        opts: &BuildOptions,
    ) -> Result<(IndexedComplex, BuildReport), ComplexError> {
        let mut drop: Vec<bool> = Vec::new();
        let mut report = BuildReport::default();
        let n = self.n_cells();
        let dups = self.duplicate_pairs();
        if let Some(&(cell, first)) = dups.iter().min() {
            if !opts.drop_duplicates {
                return Err(ComplexError::DuplicateCell {
                    cell: cell as u64,
                    first: first as u64,
                });
            }
            for &(c, _) in &dups {
                mark(&mut drop, c as usize, n);
            }
            report.dropped_duplicates = dups.len();
        }
        let dmax = self.dim().unwrap_or(0);
        if self.blocks.iter().any(|b| b.kind.dim() < dmax) {
            let vt = self.vertex_cells();
            let mut key: Vec<u32> = Vec::new();
            for b in self.blocks.iter().filter(|b| b.kind.dim() < dmax) {
                for i in 0..b.len() {
                    let c = b.first + i as u32;
                    if !drop.is_empty() && drop[c as usize] {
                        continue;
                    }
                    let verts = b.cell(i);
                    let &v = verts
                        .iter()
                        .min_by_key(|&&v| vt.degree(v as usize))
                        .expect("cells have at least one vertex");
                    key.clear();
                    key.extend_from_slice(verts);
                    key.sort_unstable();
                    for &o in vt.row(v as usize) {
                        let other = self.cell(CellId(o));
                        if other.kind.dim() <= b.kind.dim()
                            || !other.kind.has_face(other.vertices, &key)
                        {
                            continue;
                        }
                        if !opts.drop_face_cells {
                            return Err(ComplexError::CellIsFaceOf {
                                cell: c as u64,
                                kind: b.kind.type_name(),
                                other: o as u64,
                                other_kind: other.kind.type_name(),
                            });
                        }
                        mark(&mut drop, c as usize, n);
                        report.dropped_face_cells += 1;
                        break;
                    }
                }
            }
        }
        if drop.is_empty() {
            return Ok((self, report));
        }
        let k = self.keep_cells(|c| !drop[c as usize])?;
        Ok((k, report))
    }
}

impl IndexedComplex {
    /// Every top cell with the vertex set of an earlier one, as `(later, first)`.
    ///
    /// One u64 per cell, the high 32 bits of its set hash above its id (8 bytes a cell: this is
    /// the peak of reading a large mesh), bucketed by the hash's top bits: each chunk of cells
    /// files its keys by bucket in its own part of one array (in parallel), then each bucket
    /// gathers its keys from every part, sorts them (a few dozen) and compares equal-hash runs
    /// exactly. A counting pass instead of a global sort: 6M tetrahedra in a fraction of the
    /// time of a parallel sort, and the same pairs.
    fn duplicate_pairs(&self) -> Vec<(u32, u32)> {
        use rayon::prelude::*;
        let n = self.n_cells();
        if n < 2 {
            return Vec::new();
        }
        // about 32 keys a bucket, at most 2^16 buckets (256 kB of counts a chunk: a larger
        // table leaves the cache and its counting costs more than sorting larger buckets)
        let bits = ((n / 32).max(1).ilog2()).min(16);
        let nb = 1usize << bits;
        let bucket = |k: u64| {
            if bits == 0 {
                0
            } else {
                (k >> (64 - bits)) as usize
            }
        };
        let chunk = n.div_ceil(rayon::current_num_threads() * 4).max(1 << 16);
        let mut keys = vec![0u64; n];
        // per chunk: where each bucket starts in the chunk's part (nb + 1 entries)
        let starts: Vec<Vec<u32>> = keys
            .par_chunks_mut(chunk)
            .enumerate()
            .map_init(Vec::new, |local: &mut Vec<u64>, (t, part)| {
                let lo = (t * chunk) as u32;
                local.clear();
                self.set_keys(lo, lo + part.len() as u32, local);
                let mut start = vec![0u32; nb + 1];
                for &k in local.iter() {
                    start[bucket(k) + 1] += 1;
                }
                for b in 0..nb {
                    start[b + 1] += start[b];
                }
                let mut at = start.clone();
                for &k in local.iter() {
                    let b = bucket(k);
                    part[at[b] as usize] = k;
                    at[b] += 1;
                }
                start
            })
            .collect();
        let parts: Vec<&[u64]> = keys.chunks(chunk).collect();
        let hash_of = |x: u64| x >> 32;
        let id_of = |x: u64| x as u32;
        let group = (nb / (rayon::current_num_threads() * 16)).max(1);
        (0..nb.div_ceil(group))
            .into_par_iter()
            .flat_map_iter(|g| {
                let mut run: Vec<u64> = Vec::new();
                let mut dups: Vec<(u32, u32)> = Vec::new();
                for b in g * group..((g + 1) * group).min(nb) {
                    run.clear();
                    for (part, start) in parts.iter().zip(&starts) {
                        run.extend_from_slice(&part[start[b] as usize..start[b + 1] as usize]);
                    }
                    run.sort_unstable();
                    let mut i = 0;
                    while i < run.len() {
                        let mut j = i + 1;
                        while j < run.len() && hash_of(run[j]) == hash_of(run[i]) {
                            j += 1;
                        }
                        for b in i + 1..j {
                            let cb = self.cell(CellId(id_of(run[b])));
                            if let Some(a) = (i..b).find(|&a| {
                                let ca = self.cell(CellId(id_of(run[a])));
                                ca.vertices.len() == cb.vertices.len()
                                    && cb.vertices.iter().all(|x| ca.vertices.contains(x))
                            }) {
                                dups.push((id_of(run[b]), id_of(run[a])));
                            }
                        }
                        i = j;
                    }
                }
                dups
            })
            .collect()
    }

    /// Appends the key of each cell `lo..hi` (the high 32 bits of its set hash above its id),
    /// in id order; the common cell sizes in loops of fixed length.
    fn set_keys(&self, lo: u32, hi: u32, out: &mut Vec<u64>) {
        fn keys<const K: usize>(first: u32, verts: &[u32], out: &mut Vec<u64>) {
            out.extend(verts.chunks_exact(K).zip(first..).map(|(v, c)| {
                let v: &[u32; K] = v.try_into().expect("K vertices");
                (set_hash(v) & !0xFFFF_FFFF) | c as u64
            }));
        }
        for b in &self.blocks {
            let end = b.first + b.len() as u32;
            if end <= lo || b.first >= hi {
                continue;
            }
            let (from, to) = (lo.max(b.first), hi.min(end));
            let k = b.kind.n_vertices();
            let verts = &b.vertices[(from - b.first) as usize * k..(to - b.first) as usize * k];
            match k {
                3 => keys::<3>(from, verts, out),
                4 => keys::<4>(from, verts, out),
                8 => keys::<8>(from, verts, out),
                _ => out.extend(
                    verts
                        .chunks_exact(k)
                        .zip(from..)
                        .map(|(v, c)| (set_hash(v) & !0xFFFF_FFFF) | c as u64),
                ),
            }
        }
    }
}

/// An order-independent 64-bit hash of a vertex set: the sum and the xor of the ids, each
/// spread by one multiply, mixed once by a 64-bit finaliser (one multiply a vertex, not two: it
/// is most of the duplicate check of a large mesh).
#[inline]
fn set_hash(vertices: &[u32]) -> u64 {
    let mut sum: u64 = 0;
    let mut x: u64 = 0;
    for &v in vertices {
        let h = (v as u64 + 1).wrapping_mul(0x9E37_79B9_7F4A_7C15);
        let h = h ^ (h >> 32);
        sum = sum.wrapping_add(h);
        x ^= h;
    }
    let h = (sum ^ x.rotate_left(29)).wrapping_add(vertices.len() as u64);
    let h = (h ^ (h >> 33)).wrapping_mul(0xFF51_AFD7_ED55_8CCD);
    let h = (h ^ (h >> 33)).wrapping_mul(0xC4CE_B9FE_1A85_EC53);
    h ^ (h >> 33)
}

fn mark(drop: &mut Vec<bool>, i: usize, n: usize) {
    if drop.is_empty() {
        drop.resize(n, false);
    }
    drop[i] = true;
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(
        cells: &[(CellKind, &[u32])],
        opts: &BuildOptions,
    ) -> Result<(IndexedComplex, BuildReport), ComplexError> {
        let mut b = ComplexBuilder::new(3).unwrap();
        for i in 0..8 {
            b.push_vertex(&[i as f64, (i * i) as f64, 0.0]).unwrap();
        }
        for (k, v) in cells {
            b.push_cell(*k, v)?;
        }
        b.build(opts)
    }

    #[test]
    fn detects_each_input_problem() {
        let d = BuildOptions::default();
        let tri = CellKind::Simplex(2);
        assert!(matches!(
            square(&[(tri, &[0, 1, 9])], &d),
            Err(ComplexError::VertexOutOfRange {
                cell: 0,
                vertex: 9,
                ..
            })
        ));
        assert!(matches!(
            square(&[(tri, &[0, 1, 1])], &d),
            Err(ComplexError::RepeatedVertex { cell: 0, vertex: 1 })
        ));
        assert!(matches!(
            square(&[(tri, &[0, 1, 2]), (tri, &[2, 0, 1])], &d),
            Err(ComplexError::DuplicateCell { cell: 1, first: 0 })
        ));
        assert!(matches!(
            square(&[(CellKind::Simplex(1), &[0, 1]), (tri, &[2, 0, 1])], &d),
            Err(ComplexError::CellIsFaceOf {
                cell: 0,
                other: 1,
                ..
            })
        ));
        assert!(matches!(
            square(&[(tri, &[0, 1])], &d),
            Err(ComplexError::WrongVertexCount {
                cell: 0,
                expected: 3,
                got: 2,
                ..
            })
        ));
        // A quad's diagonal is not a face of it.
        assert!(square(
            &[
                (CellKind::Quad, &[0, 1, 2, 3]),
                (CellKind::Simplex(1), &[0, 2])
            ],
            &d
        )
        .is_ok());
        let mut b = ComplexBuilder::new(2).unwrap();
        assert!(matches!(
            b.push_vertex(&[0.0, f64::NAN]),
            Err(ComplexError::NonFiniteCoordinate {
                vertex: 0,
                axis: 1,
                ..
            })
        ));
        assert!(ComplexBuilder::new(0).is_err());
        assert!(ComplexBuilder::new(65).is_err());
    }

    #[test]
    fn drop_options_keep_the_maximal_cells() {
        let tri = CellKind::Simplex(2);
        let opts = BuildOptions {
            drop_face_cells: true,
            drop_duplicates: true,
            ..Default::default()
        };
        let (k, r) = square(
            &[
                (CellKind::Simplex(1), &[0, 1]),
                (tri, &[2, 0, 1]),
                (tri, &[1, 2, 0]),
                (tri, &[3, 4, 5]),
            ],
            &opts,
        )
        .unwrap();
        assert_eq!(r.dropped_face_cells, 1);
        assert_eq!(r.dropped_duplicates, 1);
        assert_eq!(k.n_cells(), 2);
        assert_eq!(k.cell(CellId(0)).vertices, &[2, 0, 1]);
        assert_eq!(k.cell(CellId(1)).vertices, &[3, 4, 5]);
        assert_eq!(k.n_isolated_vertices(), 2);
    }

    #[test]
    fn bucketed_duplicates_equal_a_brute_force_search() {
        // enough cells for many buckets and several chunks, in blocks of three kinds, with
        // copies (their vertices shuffled) of earlier cells sprinkled in
        let mut rng = crate::testkit::XorShift::new(0x0dd_ba11);
        let nv = 5000u64;
        let mut blocks: Vec<(CellKind, Vec<u32>)> = Vec::new();
        let mut all: Vec<Vec<u32>> = Vec::new();
        for (kind, n) in [
            (CellKind::Simplex(3), 120_000),
            (CellKind::Simplex(2), 30_000),
            (CellKind::Simplex(3), 60_000),
        ] {
            let mut v: Vec<u32> = Vec::new();
            for _ in 0..n {
                let k = kind.n_vertices();
                let mut c: Vec<u32> = if !all.is_empty() && rng.below(500) == 0 {
                    let o = &all[rng.below(all.len() as u64) as usize];
                    if o.len() != k {
                        continue;
                    }
                    let mut c = o.clone();
                    c.rotate_left(1 + rng.below(k as u64 - 1) as usize);
                    c
                } else {
                    let mut c = Vec::new();
                    while c.len() < k {
                        let x = rng.below(nv) as u32;
                        if !c.contains(&x) {
                            c.push(x);
                        }
                    }
                    c
                };
                v.extend_from_slice(&c);
                c.sort_unstable();
                all.push(c);
            }
            blocks.push((kind, v));
        }
        let coords = Buf::from(vec![0.0; nv as usize]);
        let blocks = blocks.into_iter().map(|(k, v)| (k, Buf::from(v))).collect();
        let k = IndexedComplex::from_parts(1, coords, blocks).unwrap();
        let mut got = k.duplicate_pairs();
        got.sort_unstable();
        let mut first: std::collections::HashMap<&[u32], u32> = Default::default();
        let mut want: Vec<(u32, u32)> = Vec::new();
        for (i, c) in all.iter().enumerate() {
            match first.get(c.as_slice()) {
                Some(&f) => want.push((i as u32, f)),
                None => {
                    first.insert(c, i as u32);
                }
            }
        }
        assert!(want.len() > 100, "{}", want.len());
        assert_eq!(got, want);
    }

    #[test]
    fn block_fast_check_agrees_with_check_cell() {
        let mut rng = crate::testkit::XorShift::new(0x2545_f491_4f6c_dd1d);
        let mut next = |m: u64| rng.below(m);
        for n in 1..=10usize {
            for _ in 0..300 {
                let nv = 1 + next(40) as usize;
                let cells = next(6) as usize;
                let verts: Vec<u32> = (0..n * cells).map(|_| next(nv as u64 + 1) as u32).collect();
                let slow = verts
                    .chunks_exact(n)
                    .enumerate()
                    .all(|(i, c)| check_cell(i as u64, c, nv).is_ok());
                assert_eq!(block_is_valid(&verts, n, nv), slow, "{n} {nv} {verts:?}");
            }
        }
    }

    #[test]
    fn blocks_follow_input_order() {
        let (k, _) = square(
            &[
                (CellKind::Simplex(2), &[0, 1, 2]),
                (CellKind::Quad, &[3, 4, 5, 6]),
                (CellKind::Simplex(2), &[0, 2, 7]),
            ],
            &BuildOptions::default(),
        )
        .unwrap();
        assert_eq!(k.blocks().len(), 3);
        assert_eq!(k.cell(CellId(1)).kind, CellKind::Quad);
        assert_eq!(k.cell(CellId(2)).vertices, &[0, 2, 7]);
        assert!(k.try_cell(CellId(3)).is_none());
        assert_eq!(k.cells().count(), 3);
        let vt = k.vertex_cells();
        assert_eq!(vt.row(0), &[0, 2]);
        assert_eq!(vt.row(3), &[1]);
    }
}
