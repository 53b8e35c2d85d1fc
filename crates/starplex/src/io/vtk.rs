//! Legacy VTK `.vtk`, `DATASET UNSTRUCTURED_GRID` and `DATASET POLYDATA`, ascii and binary.
//!
//! `POLYDATA` (written by [`write_polydata`]): `POINTS`, then `VERTICES`, `LINES`, `POLYGONS` and `TRIANGLE_STRIPS`
//! sections in either cell layout (classic `n size` lists, or `OFFSETS`/`CONNECTIVITY` in 5.x),
//! read as poly-vertex, poly-line, polygon and triangle-strip cells (below); its cells are
//! numbered section by section in that order, whatever the order in the file, as VTK does, and
//! `CELL_DATA` follows that numbering.
//!
//! Binary files (`BINARY`, big-endian as the format says) are read in both layouts: classic
//! `CELLS` of `int`s (version up to 4.2) and `OFFSETS`/`CONNECTIVITY` of `vtktypeint64` or
//! `vtktypeint32` (version 5.x, meshio's default); `POINTS` of `float` or `double`; the
//! `POINT_DATA` and `CELL_DATA` sections too.
//! Errors in a binary file name the byte offset instead of the line.
//!
//! Read: the classic layout (`CELLS n size` followed by `k v_0 .. v_{k-1}` per cell) and the
//! layout of version 5.x (`CELLS n_offsets n_connectivity`, `OFFSETS type`, `CONNECTIVITY type`),
//! with the linear cell types 1 to 14 (one table shared with `.vtu`): vertex and poly-vertex
//! cells are dropped with a note (their points stay), poly-lines become edges, triangle strips
//! triangles, polygons triangles, quads or fans of triangles, pixels and voxels quads and
//! hexahedra in starplex's corner order; any other type is an error naming it. The arrays of `POINT_DATA` and `CELL_DATA` (`SCALARS`, `VECTORS`, `NORMALS`, `TENSORS`, `FIELD` arrays, ...) become vertex and cell [attributes](crate::attr); dataset-level `FIELD` data and `METADATA` are skipped. VTK's
//! vertex order is starplex's, so cells are kept as written. Points always have 3 coordinates,
//! so the complex read has ambient dimension 3.
//!
//! Write: `# vtk DataFile Version 4.2`, classic layout (read by every VTK version, ParaView and
//! meshio); points of ambient dimension 1 or 2 are padded with zeros. [`write()`] writes an
//! `UNSTRUCTURED_GRID`, [`write_polydata`] (format name `vtk-polydata`) a `POLYDATA` of lines
//! and polygons.
//!
//! ```
//! use starplex::io::{vtk, ReadOptions};
//! let text = "# vtk DataFile Version 4.2\ntwo triangles\nASCII\nDATASET UNSTRUCTURED_GRID\n\
//!             POINTS 4 double\n0 0 0 1 0 0 0 1 0 1 1 0\nCELLS 2 8\n3 0 1 2\n3 1 3 2\n\
//!             CELL_TYPES 2\n5\n5\n";
//! let r = vtk::read_from(text.as_bytes(), "mem.vtk".as_ref(), &ReadOptions::default()).unwrap();
//! assert_eq!(r.complex.n_cells(), 2);
//! let mut out = Vec::new();
//! vtk::write(&mut out, &r.complex).unwrap();
//! let back = vtk::read_from(&out[..], "mem.vtk".as_ref(), &ReadOptions::default()).unwrap();
//! assert_eq!(back.complex, r.complex);
//! ```
use std::io::{BufRead, Write};
use std::path::Path;

use super::faces::push_build_notes;
use super::raw::{
    get_i32, get_i64, get_u32, push_f32s, push_f64s, read_records, read_records_in,
    reserve_declared, Endian, CHUNK,
};
use super::text::write_f64;
use super::words::Words;
use super::{Format, IoError, IoErrorKind, Location, ReadOptions, ReadResult};
use crate::attr::{AttrValues, Attribute, Attributes};
use crate::cell::CellKind;
use crate::complex::{BuildOptions, ComplexBuilder, ComplexError, IndexedComplex};

/// The VTK cell type of a kind (`None` for kinds legacy VTK has no linear cell for).
///
/// ```
/// use starplex::{cell::CellKind, io::vtk};
/// assert_eq!(vtk::vtk_type(CellKind::Prism), Some(13));
/// assert_eq!(vtk::vtk_type(CellKind::Simplex(4)), None);
/// ```
pub fn vtk_type(kind: CellKind) -> Option<u8> {
    Some(match kind {
        CellKind::Simplex(0) => 1,
        CellKind::Simplex(1) => 3,
        CellKind::Simplex(2) => 5,
        CellKind::Simplex(3) => 10,
        CellKind::Quad => 9,
        CellKind::Hex => 12,
        CellKind::Prism => 13,
        CellKind::Pyramid => 14,
        CellKind::Simplex(_) => return None,
    })
}

/// The kind of a VTK cell type starplex reads (`Simplex(0)` for VTK_VERTEX).
///
/// ```
/// use starplex::{cell::CellKind, io::vtk};
/// assert_eq!(vtk::kind_of_vtk_type(14), Some(CellKind::Pyramid));
/// assert_eq!(vtk::kind_of_vtk_type(7), None); // polygon
/// ```
pub fn kind_of_vtk_type(t: u64) -> Option<CellKind> {
    Some(match t {
        1 => CellKind::Simplex(0),
        3 => CellKind::Simplex(1),
        5 => CellKind::Simplex(2),
        9 => CellKind::Quad,
        10 => CellKind::Simplex(3),
        12 => CellKind::Hex,
        13 => CellKind::Prism,
        14 => CellKind::Pyramid,
        _ => return None,
    })
}

fn vtk_type_name(t: u64) -> &'static str {
    match t {
        1 => "vertex",
        2 => "poly_vertex",
        3 => "line",
        4 => "poly_line",
        5 => "triangle",
        6 => "triangle_strip",
        7 => "polygon",
        8 => "pixel",
        9 => "quad",
        10 => "tetra",
        11 => "voxel",
        12 => "hexahedron",
        13 => "wedge",
        14 => "pyramid",
        15 => "pentagonal_prism",
        16 => "hexagonal_prism",
        21..=35 | 37 => "a quadratic or higher-order cell",
        36 => "quadratic_polygon",
        68 => "lagrange_curve",
        69 => "lagrange_triangle",
        70 => "lagrange_quadrilateral",
        71 => "lagrange_tetrahedron",
        72 => "lagrange_hexahedron",
        73 => "lagrange_wedge",
        74 => "lagrange_pyramid",
        75 => "bezier_curve",
        76 => "bezier_triangle",
        77 => "bezier_quadrilateral",
        78 => "bezier_tetrahedron",
        79 => "bezier_hexahedron",
        80 => "bezier_wedge",
        81 => "bezier_pyramid",
        42 => "polyhedron",
        _ => "an unknown type",
    }
}

/// Why a cell of VTK type `ty` cannot list `n` points (`None`: it can): the one table of the cell
/// types starplex reads, for legacy and XML VTK.
pub(crate) fn arity_error(ty: u64, n: u64) -> Option<String> {
    let name = vtk_type_name(ty);
    let need = |k: u64| {
        (n != k)
            .then(|| format!("VTK cell type {ty} ({name}) needs {k} points, the cell lists {n}"))
    };
    let at_least = |k: u64| {
        (n < k).then(|| {
            format!("VTK cell type {ty} ({name}) needs at least {k} points, the cell lists {n}")
        })
    };
    match ty {
        1 => need(1),
        2 => at_least(1),
        3 => need(2),
        4 => at_least(2),
        5 => need(3),
        6 | 7 => at_least(3),
        8..=10 => need(4),
        11 | 12 => need(8),
        13 => need(6),
        14 => need(5),
        36 if n < 6 || n % 2 == 1 => Some(format!(
            "VTK cell type 36 ({name}) needs an even number of points, at least 6 (its corners, \
             then one point on each side), the cell lists {n}"
        )),
        36 => None,
        74 | 81 => Some(format!(
            "VTK cell type {ty} ({name}) is not supported: VTK itself defines no arbitrary-order \
             pyramid cell, so the order of its points is unknown"
        )),
        _ => match (higher_order_vtk_type(ty), arbitrary_order_vtk_type(ty)) {
            (Some((_, k)), _) => need(k as u64),
            (None, Some(kind)) => (!arbitrary_order_count_ok(kind, n)).then(|| {
                format!(
                    "VTK cell type {ty} ({name}) cannot have {n} points: no order of this cell \
                     has that many ({})",
                    arbitrary_order_counts(kind)
                )
            }),
            (None, None) => Some(format!(
                "VTK cell type {ty} ({name}) is not supported (starplex reads the linear types 1 \
                 to 14, the quadratic ones 21-37 and the Lagrange and Bezier ones 68-73 and 75-80 \
                 as their linear cells)"
            )),
        },
    }
}

/// The linear kind and point count of VTK's quadratic and bi/tri-quadratic cell types (21-35,
/// 37): their first points are the corners, in the linear cell's order, so starplex reads them
/// as that linear cell; the other points stay, as vertices in no cell. The quadratic polygon (36:
/// `2n` points) is read as the polygon of its first `n`, and the arbitrary-order types as
/// [`arbitrary_order_vtk_type`] says.
///
/// ```
/// use starplex::{cell::CellKind, io::vtk};
/// assert_eq!(vtk::higher_order_vtk_type(24), Some((CellKind::Simplex(3), 10))); // quadratic tetra
/// assert_eq!(vtk::higher_order_vtk_type(29), Some((CellKind::Hex, 27)));
/// assert_eq!(vtk::higher_order_vtk_type(10), None); // linear: `kind_of_vtk_type`
/// ```
pub fn higher_order_vtk_type(t: u64) -> Option<(CellKind, usize)> {
    let (line, tri) = (CellKind::Simplex(1), CellKind::Simplex(2));
    Some(match t {
        21 => (line, 3),
        35 => (line, 4),
        22 => (tri, 6),
        34 => (tri, 7),
        23 => (CellKind::Quad, 8),
        28 => (CellKind::Quad, 9),
        30 => (CellKind::Quad, 6),
        24 => (CellKind::Simplex(3), 10),
        25 => (CellKind::Hex, 20),
        29 => (CellKind::Hex, 27),
        33 => (CellKind::Hex, 24),
        26 => (CellKind::Prism, 15),
        31 => (CellKind::Prism, 12),
        32 => (CellKind::Prism, 18),
        27 => (CellKind::Pyramid, 13),
        37 => (CellKind::Pyramid, 19),
        _ => return None,
    })
}

/// The linear kind of VTK's arbitrary-order Lagrange (68-73) and Bezier (75-80) cell types:
/// their first points are the corners, in the linear cell's order, so starplex reads them as that
/// linear cell (the other points stay, as vertices in no cell), whatever their order. VTK defines
/// no arbitrary-order pyramid (74, 81): those are refused.
///
/// ```
/// use starplex::{cell::CellKind, io::vtk};
/// assert_eq!(vtk::arbitrary_order_vtk_type(71), Some(CellKind::Simplex(3))); // Lagrange tetra
/// assert_eq!(vtk::arbitrary_order_vtk_type(79), Some(CellKind::Hex)); // Bezier hexahedron
/// assert_eq!(vtk::arbitrary_order_vtk_type(74), None);
/// ```
pub fn arbitrary_order_vtk_type(t: u64) -> Option<CellKind> {
    Some(match t {
        68 | 75 => CellKind::Simplex(1),
        69 | 76 => CellKind::Simplex(2),
        70 | 77 => CellKind::Quad,
        71 | 78 => CellKind::Simplex(3),
        72 | 79 => CellKind::Hex,
        73 | 80 => CellKind::Prism,
        _ => return None,
    })
}

/// `(p + 1)(p + 2)/2` for some order `p >= 1`: the points of an order-p triangle.
fn is_triangle_count(n: u64) -> bool {
    (1..)
        .map(|p: u64| (p + 1) * (p + 2) / 2)
        .take_while(|&t| t <= n)
        .any(|t| t == n)
}

/// `n = a * rest` for some `a >= 2` with `rest` accepted by `more`.
fn splits(n: u64, more: impl Fn(u64) -> bool) -> bool {
    (2..=n / 2).any(|a| n.is_multiple_of(a) && more(n / a))
}

/// Whether an arbitrary-order cell of linear kind `kind` can have `n` points: a curve any number
/// from 2, a triangle or a tetrahedron those of one order, a quadrilateral, hexahedron or wedge
/// those of one order per direction (VTK's `HigherOrderDegrees` lets them differ).
fn arbitrary_order_count_ok(kind: CellKind, n: u64) -> bool {
    match kind {
        CellKind::Simplex(1) => n >= 2,
        CellKind::Simplex(2) => is_triangle_count(n),
        CellKind::Simplex(3) => (1..)
            .map(|p: u64| (p + 1) * (p + 2) * (p + 3) / 6)
            .take_while(|&t| t <= n)
            .any(|t| t == n),
        CellKind::Quad => splits(n, |r| r >= 2),
        CellKind::Hex => splits(n, |r| splits(r, |s| s >= 2)),
        // a triangle's points times those along the axis; 21 is VTK's order-2 wedge with
        // face and body points
        CellKind::Prism => n == 21 || splits(n, is_triangle_count),
        _ => false,
    }
}

/// The point counts of the first orders, for messages.
fn arbitrary_order_counts(kind: CellKind) -> &'static str {
    match kind {
        CellKind::Simplex(1) => "at least 2",
        CellKind::Simplex(2) => "3, 6, 10, 15, ...",
        CellKind::Simplex(3) => "4, 10, 20, 35, ...",
        CellKind::Quad => "(p+1)(q+1): 4, 6, 9, 16, ...",
        CellKind::Hex => "(p+1)(q+1)(r+1): 8, 12, 27, 64, ...",
        _ => "(p+1)(p+2)/2 times (q+1): 6, 18, 21, 40, ...",
    }
}

/// Why a VTK cell could not be pushed.
#[derive(Debug)]
pub(crate) enum PushError {
    /// The type or its point count.
    Cell(String),
    /// The builder refused the cell (repeated or out-of-range vertex, too many cells).
    Complex(ComplexError),
}

impl std::fmt::Display for PushError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            PushError::Cell(m) => f.write_str(m),
            PushError::Complex(e) => write!(f, "{e}"),
        }
    }
}

/// Counts of VTK cells changed on the way in.
#[derive(Default)]
pub(crate) struct CellStats {
    vertex_cells: u64,
    fanned: u64,
    fan_tris: u64,
    strips: u64,
    strip_tris: u64,
    polylines: u64,
    polyline_edges: u64,
    higher_order: u64,
}

impl CellStats {
    /// The notes saying what changed.
    pub(crate) fn notes(&self, notes: &mut Vec<String>) {
        if self.vertex_cells > 0 {
            notes.push(format!(
                "dropped {} VTK vertex cells (types 1, 2); their points stay as vertices",
                self.vertex_cells
            ));
        }
        if self.fanned > 0 {
            notes.push(format!(
                "fan-triangulated {} polygons with more than 4 vertices into {} triangles",
                self.fanned, self.fan_tris
            ));
        }
        if self.strips > 0 {
            notes.push(format!(
                "split {} triangle strips into {} triangles",
                self.strips, self.strip_tris
            ));
        }
        if self.polylines > 0 {
            notes.push(format!(
                "split {} poly-lines into {} edges",
                self.polylines, self.polyline_edges
            ));
        }
        if self.higher_order > 0 {
            notes.push(format!(
                "read {} higher-order cells (types 21-37, 68-80) as their linear cells; their \
                 points that are not corners stay, as vertices in no cell",
                self.higher_order
            ));
        }
    }
}

/// Pushes the cell of VTK type `ty` on `v` (reordering pixels and voxels, splitting poly-lines,
/// strips and polygons of more than 4 points, dropping vertex cells), or says why not.
pub(crate) fn push_cell(
    b: &mut ComplexBuilder,
    st: &mut CellStats,
    ty: u64,
    v: &[u32],
) -> Result<(), PushError> {
    let n = v.len();
    if let Some(m) = arity_error(ty, n as u64) {
        return Err(PushError::Cell(m));
    }
    let mut push =
        |kind: CellKind, v: &[u32]| b.push_cell(kind, v).map(|_| ()).map_err(PushError::Complex);
    match ty {
        1 | 2 => {
            st.vertex_cells += 1;
            Ok(())
        }
        4 if n > 2 => {
            st.polylines += 1;
            st.polyline_edges += n as u64 - 1;
            v.windows(2).try_for_each(|w| push(CellKind::Simplex(1), w))
        }
        3 | 4 => push(CellKind::Simplex(1), v),
        6 => {
            if n > 3 {
                st.strips += 1;
                st.strip_tris += n as u64 - 2;
            }
            (0..n - 2).try_for_each(|i| {
                // keep the strip's orientation: every other triangle is flipped back
                let t = if i % 2 == 0 {
                    [v[i], v[i + 1], v[i + 2]]
                } else {
                    [v[i + 1], v[i], v[i + 2]]
                };
                push(CellKind::Simplex(2), &t)
            })
        }
        7 if n == 4 => push(CellKind::Quad, v),
        7 if n > 4 => {
            st.fanned += 1;
            st.fan_tris += n as u64 - 2;
            (1..n - 1).try_for_each(|j| push(CellKind::Simplex(2), &[v[0], v[j], v[j + 1]]))
        }
        5 | 7 => push(CellKind::Simplex(2), v),
        8 => push(CellKind::Quad, &[v[0], v[1], v[3], v[2]]),
        11 => push(
            CellKind::Hex,
            &[v[0], v[1], v[3], v[2], v[4], v[5], v[7], v[6]],
        ),
        36 => {
            // its corners, then one point on each side: the linear polygon of the corners
            st.higher_order += 1;
            push_cell(b, st, 7, &v[..n / 2])
        }
        _ => {
            let linear = kind_of_vtk_type(ty);
            let higher = higher_order_vtk_type(ty)
                .map(|(kind, _)| kind)
                .or_else(|| arbitrary_order_vtk_type(ty));
            match (linear, higher) {
                (Some(kind), _) => push(kind, v),
                (None, Some(kind)) => {
                    st.higher_order += 1;
                    push(kind, &v[..kind.n_vertices()])
                }
                (None, None) => Err(PushError::Cell(format!(
                    "VTK cell type {ty} is not supported"
                ))),
            }
        }
    }
}

/// The run of cells `i..j` of one linear VTK type other than a vertex, each listing exactly its
/// type's point count, from cell `i` (whose points start at `start` in the connectivity; `ends`
/// are the cells' ends, none past `max_end`): the run's kind and `j`, or `None` when cell `i`
/// is not such a cell. Readers push such runs whole ([`ComplexBuilder::push_cells`]).
pub(crate) fn linear_run<T: Copy + Into<u64>>(
    types: &[T],
    ends: &[u64],
    start: u64,
    i: usize,
    max_end: u64,
) -> Option<(CellKind, usize)> {
    let ty: u64 = (*types.get(i)?).into();
    let kind = kind_of_vtk_type(ty).filter(|&k| k != CellKind::Simplex(0))?;
    let k = kind.n_vertices() as u64;
    let (mut j, mut prev) = (i, start);
    while j < types.len().min(ends.len())
        && types[j].into() == ty
        && ends[j] == prev + k
        && ends[j] <= max_end
    {
        prev = ends[j];
        j += 1;
    }
    (j > i).then_some((kind, j))
}

/// Reads a `.vtk` file.
///
/// ```
/// use starplex::io::{vtk, ReadOptions};
/// let path = std::env::temp_dir().join(format!("starplex-doc-vtk-read-{}.vtk", std::process::id()));
/// std::fs::write(&path, "# vtk DataFile Version 4.2\nan edge\nASCII\nDATASET UNSTRUCTURED_GRID\n\
///                        POINTS 2 float\n0 0 0 1 0 0\nCELLS 1 3\n2 0 1\nCELL_TYPES 1\n3\n").unwrap();
/// let r = vtk::read(&path, &ReadOptions::default()).unwrap();
/// std::fs::remove_file(&path).unwrap();
/// assert_eq!(r.complex.ambient_dim(), 3); // VTK points always have 3 coordinates
/// assert_eq!(r.complex.n_cells(), 1);
/// ```
///
/// # Errors
/// See [`read_from`].
pub fn read(path: &Path, opts: &ReadOptions) -> Result<ReadResult, IoError> {
    let f = std::fs::File::open(path).map_err(|e| IoError::new(path, e))?;
    read_from(std::io::BufReader::with_capacity(1 << 20, f), path, opts)
}

fn lossy(w: &[u8]) -> String {
    String::from_utf8_lossy(&w[..w.len().min(60)]).into_owned()
}

fn count(w: &mut Words<'_, impl BufRead>, what: &str) -> Result<usize, IoError> {
    let n = w.u64(what)?;
    if n >= u32::MAX as u64 {
        return Err(w.err(format!(
            "{what} {n} exceeds the 32-bit id limit of starplex"
        )));
    }
    Ok(n as usize)
}

/// Skips `n` words (data values of a skipped block), failing at the end of the file.
fn skip_values(w: &mut Words<'_, impl BufRead>, n: u64, what: &str) -> Result<(), IoError> {
    for _ in 0..n {
        w.expect(what)?;
    }
    Ok(())
}

/// Skips a `METADATA` block if one comes next (it ends at an empty line).
fn skip_metadata(w: &mut Words<'_, impl BufRead>) -> Result<(), IoError> {
    match w.next_word()? {
        Some(k) if k.eq_ignore_ascii_case(b"METADATA") => {
            w.rest_of_line()?;
            loop {
                let l = w.rest_of_line()?;
                if l.iter().all(|b| b.is_ascii_whitespace()) {
                    return Ok(());
                }
            }
        }
        Some(_) => {
            w.unread();
            Ok(())
        }
        None => {
            w.unread();
            Ok(())
        }
    }
}

/// Value type of a legacy VTK data array: bytes per value and kind (`None`: `bit` or unknown).
fn data_type(ty: &[u8]) -> Option<(usize, NumKind)> {
    let t = ty.to_ascii_lowercase();
    Some(match t.as_slice() {
        b"float" | b"vtktypefloat32" => (4, NumKind::Float),
        b"double" | b"vtktypefloat64" => (8, NumKind::Float),
        b"char" | b"signed_char" | b"vtktypeint8" => (1, NumKind::Int),
        b"unsigned_char" | b"vtktypeuint8" => (1, NumKind::UInt),
        b"short" | b"vtktypeint16" => (2, NumKind::Int),
        b"unsigned_short" | b"vtktypeuint16" => (2, NumKind::UInt),
        b"int" | b"vtktypeint32" => (4, NumKind::Int),
        b"unsigned_int" | b"vtktypeuint32" => (4, NumKind::UInt),
        b"long" | b"vtkidtype" | b"vtktypeint64" => (8, NumKind::Int),
        b"unsigned_long" | b"vtktypeuint64" => (8, NumKind::UInt),
        _ => return None,
    })
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum NumKind {
    Int,
    UInt,
    Float,
}

/// Reads `n` values of type `ty` (the header line already read up to the type; ascii words or,
/// in a binary file, big-endian bytes after the end of the header line).
fn read_values(
    w: &mut Words<'_, impl BufRead>,
    n: u64,
    ty: &[u8],
    binary: bool,
    what: &str,
) -> Result<AttrValues, IoError> {
    let Some((width, kind)) = data_type(ty) else {
        return Err(w.err(format!(
            "data type '{}' of {what} is not read (char, short, int, long and their unsigned forms, float, double)",
            lossy(ty)
        )));
    };
    if !binary {
        // values are words; floats may be NaN or infinite here (data, not coordinates)
        let cap = n.min(1 << 20) as usize;
        if kind == NumKind::Float {
            let mut v = Vec::with_capacity(cap);
            for _ in 0..n {
                let t = w.expect(what)?;
                match super::text::parse_f64(t) {
                    Some(x) => v.push(x),
                    None => {
                        let m = format!("{what}: '{}' is not a number", lossy(t));
                        return Err(w.err(m));
                    }
                }
            }
            return Ok(AttrValues::Float(v));
        }
        let mut v = Vec::with_capacity(cap);
        for _ in 0..n {
            v.push(w.i64(what)?);
        }
        return Ok(AttrValues::Int(v));
    }
    w.rest_of_line()?;
    let mut ints: Vec<i64> = Vec::new();
    let mut floats: Vec<f64> = Vec::new();
    read_records(w, n, width, what, |w, c, _| {
        match (kind, width) {
            (NumKind::Float, 4) => push_f32s(c, Endian::Big, &mut floats),
            (NumKind::Float, _) => push_f64s(c, Endian::Big, &mut floats),
            (NumKind::Int, 1) => ints.extend(c.iter().map(|&b| b as i8 as i64)),
            (NumKind::UInt, 1) => ints.extend(c.iter().map(|&b| b as i64)),
            (NumKind::Int, 2) => ints.extend(
                c.chunks_exact(2)
                    .map(|x| i16::from_be_bytes([x[0], x[1]]) as i64),
            ),
            (NumKind::UInt, 2) => ints.extend(
                c.chunks_exact(2)
                    .map(|x| u16::from_be_bytes([x[0], x[1]]) as i64),
            ),
            (NumKind::Int, 4) => {
                ints.extend(c.chunks_exact(4).map(|x| get_i32(x, Endian::Big) as i64))
            }
            (NumKind::UInt, 4) => ints.extend(
                c.chunks_exact(4)
                    .map(|x| get_i32(x, Endian::Big) as u32 as i64),
            ),
            (NumKind::Int, _) => ints.extend(c.chunks_exact(8).map(|x| get_i64(x, Endian::Big))),
            (NumKind::UInt, _) => {
                for x in c.chunks_exact(8) {
                    let u = get_i64(x, Endian::Big) as u64;
                    ints.push(i64::try_from(u).map_err(|_| {
                        w.err(format!("{what}: {u} does not fit a 64-bit signed integer"))
                    })?);
                }
            }
        }
        Ok(())
    })?;
    Ok(if kind == NumKind::Float {
        AttrValues::Float(floats)
    } else {
        AttrValues::Int(ints)
    })
}

/// Reads a `FIELD name n_arrays` block (the `FIELD` word already read): its arrays of `n`
/// tuples become columns (`n` is `None` for dataset-level field data, which is read and dropped).
fn read_field(
    w: &mut Words<'_, impl BufRead>,
    n: Option<u64>,
    binary: bool,
    cols: &mut Vec<Attribute>,
    skipped: &mut Vec<String>,
) -> Result<(), IoError> {
    w.expect("the field name")?;
    let arrays = w.u64("the number of field arrays")?;
    for _ in 0..arrays {
        let name = w.expect("a field array name")?.to_vec();
        let comps = w.u64("the number of components")?;
        let tuples = w.u64("the number of tuples")?;
        let ty = w.expect("the data type")?.to_vec();
        let total = comps
            .checked_mul(tuples)
            .ok_or_else(|| w.err(format!("field array size {comps} x {tuples} overflows")))?;
        let values = read_values(w, total, &ty, binary, "a field value")?;
        skip_metadata(w)?;
        match n {
            Some(n) if tuples == n && (1..=1024).contains(&comps) => cols.push(Attribute {
                name: String::from_utf8_lossy(&name).into_owned(),
                components: comps as usize,
                values,
            }),
            Some(n) => skipped.push(format!(
                "FIELD array '{}' ({tuples} tuples of {comps}, the section has {n} items)",
                lossy(&name)
            )),
            None => {}
        }
    }
    Ok(())
}

/// Reads the arrays of a `POINT_DATA n` / `CELL_DATA n` section up to the next section keyword
/// (left unread) or the end of the file: `SCALARS`, `VECTORS`, `NORMALS`, `TENSORS`,
/// `TEXTURE_COORDINATES`, `GLOBAL_IDS`, `PEDIGREE_IDS` and the arrays of a `FIELD` become
/// columns of `n` items; `COLOR_SCALARS` and `LOOKUP_TABLE`s are skipped (named in `skipped`).
fn read_data_section(
    w: &mut Words<'_, impl BufRead>,
    n: u64,
    binary: bool,
    cols: &mut Vec<Attribute>,
    skipped: &mut Vec<String>,
) -> Result<(), IoError> {
    let add = |cols: &mut Vec<Attribute>, name: Vec<u8>, comps: u64, values: AttrValues| {
        cols.push(Attribute {
            name: String::from_utf8_lossy(&name).into_owned(),
            components: comps as usize,
            values,
        });
    };
    while let Some(word) = w.next_word()?.map(|t| t.to_vec()) {
        let kw = word.to_ascii_uppercase();
        match kw.as_slice() {
            b"POINT_DATA" | b"CELL_DATA" | b"POINTS" | b"CELLS" | b"CELL_TYPES" => {
                w.unread();
                return Ok(());
            }
            b"SCALARS" => {
                let name = w.expect("the scalars' name")?.to_vec();
                let ty = w.expect("the scalars' type")?.to_vec();
                // an optional component count, then LOOKUP_TABLE name (required)
                let mut comps = 1;
                match w.next_word()?.map(|t| t.to_vec()) {
                    Some(t) if t.eq_ignore_ascii_case(b"LOOKUP_TABLE") => {
                        w.expect("the lookup table name")?;
                    }
                    Some(t) => {
                        comps = super::text::parse_u64(&t).filter(|&c| (1..=64).contains(&c)).ok_or_else(|| {
                            w.err(format!(
                                "expected the number of components (1 to 64) or LOOKUP_TABLE, found '{}'",
                                lossy(&t)
                            ))
                        })?;
                        w.keyword("LOOKUP_TABLE")?;
                        w.expect("the lookup table name")?;
                    }
                    None => return Err(w.err("unexpected end of file: expected LOOKUP_TABLE")),
                }
                let v = read_values(w, n.saturating_mul(comps), &ty, binary, "a scalar value")?;
                add(cols, name, comps, v);
            }
            b"VECTORS" | b"NORMALS" | b"TENSORS" | b"TENSORS9" | b"TENSORS6" | b"GLOBAL_IDS"
            | b"PEDIGREE_IDS" => {
                let comps: u64 = match kw.as_slice() {
                    b"VECTORS" | b"NORMALS" => 3,
                    b"TENSORS" | b"TENSORS9" => 9,
                    b"TENSORS6" => 6,
                    _ => 1,
                };
                let name = w.expect("the array name")?.to_vec();
                let ty = w.expect("the array type")?.to_vec();
                let v = read_values(w, n.saturating_mul(comps), &ty, binary, "a data value")?;
                add(cols, name, comps, v);
            }
            b"TEXTURE_COORDINATES" => {
                let name = w.expect("the array name")?.to_vec();
                let d = w.u64("the texture dimension")?;
                if !(1..=3).contains(&d) {
                    return Err(w.err(format!("texture dimension {d} is not 1, 2 or 3")));
                }
                let ty = w.expect("the array type")?.to_vec();
                let v = read_values(w, n.saturating_mul(d), &ty, binary, "a texture coordinate")?;
                add(cols, name, d, v);
            }
            b"COLOR_SCALARS" => {
                let name = w.expect("the array name")?.to_vec();
                let c = w.u64("the number of color values")?;
                if binary {
                    // unsigned chars
                    w.rest_of_line()?;
                    read_records(w, n.saturating_mul(c), 1, "the colour values", |_, _, _| {
                        Ok(())
                    })?;
                } else {
                    skip_values(w, n.saturating_mul(c), "a colour value")?;
                }
                skipped.push(format!("COLOR_SCALARS '{}'", lossy(&name)));
            }
            b"LOOKUP_TABLE" => {
                w.expect("the lookup table name")?;
                let size = w.u64("the lookup table size")?;
                if binary {
                    w.rest_of_line()?;
                    read_records(
                        w,
                        size.saturating_mul(4),
                        1,
                        "the lookup table",
                        |_, _, _| Ok(()),
                    )?;
                } else {
                    skip_values(w, size.saturating_mul(4), "a lookup table value")?;
                }
            }
            b"FIELD" => {
                read_field(w, Some(n), binary, cols, skipped)?;
                continue;
            }
            b"METADATA" => {
                w.unread();
                skip_metadata(w)?;
                continue;
            }
            _ => {
                return Err(w.err(format!(
                    "unknown keyword '{}' in a POINT_DATA/CELL_DATA section",
                    lossy(&word)
                )))
            }
        };
        skip_metadata(w)?;
    }
    Ok(())
}

/// Reads legacy VTK text from any buffered reader; `path` names it in errors.
///
/// ```
/// use starplex::io::{vtk, ReadOptions};
/// // Cell type 42 (a polyhedron) is not read: the error names the line.
/// let text = "# vtk DataFile Version 4.2\np\nASCII\nDATASET UNSTRUCTURED_GRID\n\
///             POINTS 3 double\n0 0 0 1 0 0 0 1 0\nCELLS 1 4\n3 0 1 2\nCELL_TYPES 1\n42\n";
/// let e = vtk::read_from(text.as_bytes(), "m.vtk".as_ref(), &ReadOptions::default()).unwrap_err();
/// assert!(e.to_string().starts_with("m.vtk:10:"), "{e}");
/// // a triangle, and a polygon of 3 points, are triangles
/// for t in ["5", "7"] {
///     let tri = text.replace("CELL_TYPES 1\n42", &format!("CELL_TYPES 1\n{t}"));
///     let r = vtk::read_from(tri.as_bytes(), "m.vtk".as_ref(), &ReadOptions::default()).unwrap();
///     assert_eq!(r.complex.n_cells(), 1);
/// }
/// ```
///
/// # Errors
/// A missing or malformed header, a dataset other than `UNSTRUCTURED_GRID` and `POLYDATA`,
/// malformed or non-finite numbers, counts that do not match the data, unsupported cell types,
/// vertex counts that do not fit the cell type, out-of-range or repeated vertex indices, and the
/// checks of [`ComplexBuilder::build`](crate::complex::ComplexBuilder::build) under
/// `opts.build`; each with the line.
pub fn read_from(r: impl BufRead, path: &Path, opts: &ReadOptions) -> Result<ReadResult, IoError> {
    let mut w = Words::new(r, path, None);
    let h = read_header(&mut w)?;
    let mut s = Sections {
        build: opts.build.clone(),
        ..Sections::default()
    };
    if h.binary {
        w.set_binary();
    }
    while let Some(word) = w.next_word()?.map(|t| t.to_vec()) {
        let kw = word.to_ascii_uppercase();
        match kw.as_slice() {
            b"POINTS" => s.points(&mut w, path, h.binary)?,
            b"VERTICES" | b"LINES" | b"POLYGONS" | b"TRIANGLE_STRIPS" if h.poly => {
                s.poly_cells(&mut w, &h, &kw)?;
            }
            b"CELLS" if !h.poly => s.cells(&mut w, &h)?,
            b"CELL_TYPES" if !h.poly => s.cell_types(&mut w, h.binary)?,
            b"POINT_DATA" | b"CELL_DATA" => s.data(&mut w, &h, &word, kw == b"POINT_DATA")?,
            // dataset-level field data (time values, ...): not per vertex or cell
            b"FIELD" => read_field(&mut w, None, h.binary, &mut Vec::new(), &mut Vec::new())?,
            b"METADATA" => {
                w.unread();
                skip_metadata(&mut w)?;
            }
            _ if word
                .first()
                .is_some_and(|c| c.is_ascii_digit() || b"-+.".contains(c)) =>
            {
                return Err(w.err(format!(
                    "found the number '{}' where a keyword was expected (a section holds more values than its count says)",
                    lossy(&word)
                )))
            }
            _ => {
                return Err(w.err(format!(
                    "unknown keyword '{}' in a {} dataset",
                    lossy(&word),
                    h.dataset_name()
                )))
            }
        }
    }
    s.finish(&w, path, &h, opts)
}

/// What the first lines of a legacy VTK file say.
struct Header {
    /// The major file version (5 and later: cells as OFFSETS and CONNECTIVITY).
    major: u32,
    binary: bool,
    /// POLYDATA (else UNSTRUCTURED_GRID).
    poly: bool,
}

impl Header {
    fn dataset_name(&self) -> &'static str {
        if self.poly {
            "POLYDATA"
        } else {
            "UNSTRUCTURED_GRID"
        }
    }
}

/// Reads the version line, the title, the encoding and the dataset type.
fn read_header(w: &mut Words<'_, impl BufRead>) -> Result<Header, IoError> {
    let head = w.rest_of_line()?;
    let head_s = String::from_utf8_lossy(&head).into_owned();
    let lower = head_s.to_ascii_lowercase();
    let Some(ver) = lower.trim().strip_prefix("# vtk datafile version") else {
        return Err(w.err_at(
            1,
            format!(
                "not a legacy VTK file: the first line is '{}', expected '# vtk DataFile Version x.y'",
                head_s.chars().take(60).collect::<String>()
            ),
        ));
    };
    let major: u32 = ver
        .trim()
        .split('.')
        .next()
        .and_then(|s| s.parse().ok())
        .ok_or_else(|| w.err_at(1, format!("unreadable VTK version '{}'", ver.trim())))?;
    w.rest_of_line()?; // title
    let enc = w.expect("ASCII or BINARY")?.to_vec();
    let binary = enc.eq_ignore_ascii_case(b"BINARY");
    if !binary && !enc.eq_ignore_ascii_case(b"ASCII") {
        return Err(w.err(format!("expected ASCII or BINARY, found '{}'", lossy(&enc))));
    }
    w.keyword("DATASET")?;
    let ds = w.expect("the dataset type")?.to_vec();
    let poly = ds.eq_ignore_ascii_case(b"POLYDATA");
    if !poly && !ds.eq_ignore_ascii_case(b"UNSTRUCTURED_GRID") {
        return Err(w.err(format!(
            "dataset type '{}' is not supported (starplex reads UNSTRUCTURED_GRID and POLYDATA)",
            lossy(&ds)
        )));
    }
    Ok(Header {
        major,
        binary,
        poly,
    })
}

/// The sections of a legacy VTK file read so far.
#[derive(Default)]
struct Sections {
    builder: Option<ComplexBuilder>,
    nv: usize,
    /// POLYDATA: the cells of VERTICES, LINES, POLYGONS and TRIANGLE_STRIPS (flat vertex
    /// lists and ends), in that order: VTK numbers the cells (and their CELL_DATA) section
    /// by section.
    sections: [Option<(Vec<u32>, Vec<u64>)>; 4],
    /// UNSTRUCTURED_GRID cells: vertex lists flat, with the end of each cell.
    conn: Vec<u32>,
    ends: Vec<u64>,
    /// Every cell of CELLS has this many points (read by the uniform fast path): `ends` is
    /// left empty until a check needs it ([`Sections::cell_ends`]).
    uniform: Option<u64>,
    /// The line of the CELLS section (for the error of a missing CELL_TYPES).
    cells_line: u64,
    have_cells: bool,
    /// The cell types, checked (every type read is below 256).
    types: Option<Vec<u8>>,
    point_data: Vec<Attribute>,
    cell_data: Vec<Attribute>,
    skipped: Vec<String>,
    /// The build options (a repeated point fails at once, or is left for the build to drop).
    build: BuildOptions,
}

impl Sections {
    /// POINTS, in either encoding.
    fn points(
        &mut self,
        w: &mut Words<'_, impl BufRead>,
        path: &Path,
        binary: bool,
    ) -> Result<(), IoError> {
        if self.builder.is_some() {
            return Err(w.err("a second POINTS section"));
        }
        let n = count(w, "the point count")?;
        let mut b = ComplexBuilder::new(3).map_err(|e| IoError::new(path, e))?;
        if binary {
            read_points_bin(w, n, &mut b)?;
        } else {
            w.expect("the point data type")?;
            let mut p = [0.0f64; 3];
            for _ in 0..n {
                for x in p.iter_mut() {
                    *x = w.f64("a point coordinate")?;
                }
                b.push_vertex(&p)
                    .map_err(|e| IoError::new(path, e).at(Location::Line(w.line())))?;
            }
            skip_metadata(w)?;
        }
        self.nv = n;
        self.builder = Some(b);
        Ok(())
    }

    /// One of the POLYDATA cell sections (`kw`).
    fn poly_cells(
        &mut self,
        w: &mut Words<'_, impl BufRead>,
        h: &Header,
        kw: &[u8],
    ) -> Result<(), IoError> {
        let i = POLY_SECTIONS
            .iter()
            .position(|(n, _)| n.as_bytes() == kw)
            .unwrap_or(0);
        let name = POLY_SECTIONS[i].0;
        if self.builder.is_none() {
            return Err(w.err(format!("{name} before POINTS")));
        }
        if self.sections[i].is_some() {
            return Err(w.err(format!("a second {name} section")));
        }
        let (mut c, mut e) = (Vec::new(), Vec::new());
        if let Some(k) = cell_lists(w, h, name, self.nv, &self.build, &mut c, &mut e)? {
            e = uniform_ends(k, c.len());
        }
        self.sections[i] = Some((c, e));
        Ok(())
    }

    /// The CELLS section of an UNSTRUCTURED_GRID.
    fn cells(&mut self, w: &mut Words<'_, impl BufRead>, h: &Header) -> Result<(), IoError> {
        if self.builder.is_none() {
            return Err(w.err("CELLS before POINTS"));
        }
        if self.have_cells {
            return Err(w.err("a second CELLS section"));
        }
        self.have_cells = true;
        if !h.binary {
            self.cells_line = w.line();
        }
        let build = &self.build;
        self.uniform = cell_lists(
            w,
            h,
            "CELLS",
            self.nv,
            build,
            &mut self.conn,
            &mut self.ends,
        )?;
        Ok(())
    }

    /// The number of UNSTRUCTURED_GRID cells read.
    fn n_cells(&self) -> usize {
        match self.uniform {
            Some(k) => self.conn.len() / k as usize,
            None => self.ends.len(),
        }
    }

    /// The cells' ends, made from the uniform size if the fast path left them out.
    fn cell_ends(&mut self) -> &[u64] {
        if let Some(k) = self.uniform.take() {
            self.ends = uniform_ends(k, self.conn.len());
        }
        &self.ends
    }

    /// The CELL_TYPES section of an UNSTRUCTURED_GRID, in either encoding.
    fn cell_types(&mut self, w: &mut Words<'_, impl BufRead>, binary: bool) -> Result<(), IoError> {
        if self.types.is_some() {
            return Err(w.err("a second CELL_TYPES section"));
        }
        let n = w.u64("the cell type count")?;
        if !self.have_cells {
            return Err(w.err("CELL_TYPES before CELLS"));
        }
        if n != self.n_cells() as u64 {
            return Err(w.err(format!(
                "CELL_TYPES counts {n} cells but CELLS has {}",
                self.n_cells()
            )));
        }
        let kinds = if binary {
            w.rest_of_line()?;
            read_types_bin(w, n, self.uniform, &self.ends, CHUNK)?
        } else {
            self.cell_ends();
            let (mut kinds, mut start) = (Vec::with_capacity(self.ends.len()), 0u64);
            for (i, &end) in self.ends.iter().enumerate() {
                let ty = w.u64("a cell type")?;
                let kind = cell_type(i, ty, end - start).map_err(|m| w.err(m))?;
                start = end;
                kinds.push(kind);
            }
            kinds
        };
        self.types = Some(kinds);
        Ok(())
    }

    /// A POINT_DATA (`points`) or CELL_DATA section, whose keyword is `word`.
    fn data(
        &mut self,
        w: &mut Words<'_, impl BufRead>,
        h: &Header,
        word: &[u8],
        points: bool,
    ) -> Result<(), IoError> {
        let n = w.u64("the data count")?;
        let n_cells = if h.poly {
            self.sections
                .iter()
                .flatten()
                .map(|(_, e)| e.len() as u64)
                .sum()
        } else {
            self.n_cells() as u64
        };
        let (cols, n_want) = if points {
            (&mut self.point_data, self.nv as u64)
        } else {
            (&mut self.cell_data, n_cells)
        };
        if n != n_want {
            return Err(w.err(format!(
                "{} counts {n} items, the file has {n_want}",
                lossy(word)
            )));
        }
        read_data_section(w, n, h.binary, cols, &mut self.skipped)
    }

    /// The complex of the sections read.
    fn finish(
        mut self,
        w: &Words<'_, impl BufRead>,
        path: &Path,
        h: &Header,
        opts: &ReadOptions,
    ) -> Result<ReadResult, IoError> {
        let Some(mut b) = self.builder.take() else {
            return Err(w.err("the file has no POINTS section"));
        };
        if h.poly {
            self.join_poly_sections(path)?;
        }
        if self.have_cells && self.types.is_none() {
            return Err(w.err_at(
                self.cells_line,
                "the file has CELLS but no CELL_TYPES section (it is truncated)",
            ));
        }
        let mut stats = CellStats::default();
        let mut origin: Vec<u32> = Vec::new();
        let mut one_to_one = true;
        // cells of one size (the uniform fast path) and one linear type: one block
        let one_kind = match (self.uniform, &self.types) {
            (Some(k), Some(kinds)) => kinds
                .first()
                .filter(|&&t| kinds.iter().all(|&u| u == t))
                .and_then(|&t| kind_of_vtk_type(t as u64))
                .filter(|kd| kd.n_vertices() as u64 == k && *kd != CellKind::Simplex(0)),
            _ => None,
        };
        if let Some(kind) = one_kind {
            b.push_cells(kind, std::mem::take(&mut self.conn))
                .map_err(|e| IoError::new(path, e))?;
        } else if self.types.is_some() {
            self.cell_ends();
        }
        if let (None, Some(kinds)) = (one_kind, &self.types) {
            let mut start = 0usize;
            let mut i = 0usize;
            while i < kinds.len() {
                let ty = kinds[i] as u64;
                let before = b.n_cells();
                let max_end = self.conn.len() as u64;
                if let Some((kind, j)) = linear_run(kinds, &self.ends, start as u64, i, max_end) {
                    let end = self.ends[j - 1] as usize;
                    let verts = if start == 0 && end == self.conn.len() {
                        std::mem::take(&mut self.conn)
                    } else {
                        self.conn[start..end].to_vec()
                    };
                    b.push_cells(kind, verts)
                        .map_err(|e| IoError::new(path, e))?;
                    if !self.cell_data.is_empty() {
                        origin.extend(i as u32..j as u32);
                    }
                    (start, i) = (end, j);
                    continue;
                }
                let end = self.ends[i] as usize;
                let verts = &self.conn[start..end];
                push_cell(&mut b, &mut stats, ty, verts).map_err(|e| match e {
                    PushError::Complex(e) => IoError::new(path, e),
                    PushError::Cell(m) => IoError::parse(path, None, format!("cell {i}: {m}")),
                })?;
                one_to_one &= b.n_cells() == before + 1;
                if !self.cell_data.is_empty() {
                    origin.extend((before..b.n_cells()).map(|_| i as u32));
                }
                (start, i) = (end, i + 1);
            }
        }
        let mut notes = Vec::new();
        stats.notes(&mut notes);
        if !self.skipped.is_empty() {
            notes.push(format!(
                "skipped the data arrays {}",
                self.skipped.join(", ")
            ));
        }
        b.set_attributes(Attributes {
            vertex: self.point_data,
            cell: if one_to_one {
                self.cell_data
            } else {
                self.cell_data.iter().map(|a| a.gather(&origin)).collect()
            },
        });
        let (complex, report) = b.build(&opts.build).map_err(|e| IoError::new(path, e))?;
        push_build_notes(&mut notes, &report);
        Ok(ReadResult {
            complex,
            format: Format::Vtk,
            notes,
        })
    }

    /// POLYDATA: the sections in VTK's order, as one cell list with the sections' cell types.
    fn join_poly_sections(&mut self, path: &Path) -> Result<(), IoError> {
        let mut kinds = Vec::new();
        for ((name, ty), sec) in POLY_SECTIONS.iter().zip(std::mem::take(&mut self.sections)) {
            let Some((c, e)) = sec else { continue };
            let base = self.conn.len() as u64;
            let mut start = 0u64;
            for &end in &e {
                let kind = cell_type(self.ends.len(), *ty, end - start)
                    .map_err(|m| IoError::parse(path, None, format!("{m} (in {name})")))?;
                kinds.push(kind);
                self.ends.push(base + end);
                start = end;
            }
            self.conn.extend_from_slice(&c);
        }
        self.types = Some(kinds);
        Ok(())
    }
}

/// The counts line and cell lists of a CELLS or POLYDATA cell section (`name`), in the layout
/// of the file's version and encoding, appended to `conn` and `ends`; or, when both were empty
/// and every cell has the same number k of points, `Some(k)` with the vertices in `conn` and
/// `ends` left empty (see [`uniform_ends`]).
fn cell_lists(
    w: &mut Words<'_, impl BufRead>,
    h: &Header,
    name: &str,
    nv: usize,
    build: &BuildOptions,
    conn: &mut Vec<u32>,
    ends: &mut Vec<u64>,
) -> Result<Option<u64>, IoError> {
    let a = w.u64("the cell count")?;
    let size = w.u64("the cell list size")?;
    if h.binary {
        // the binary data may start with any byte: the layout follows the version
        if h.major >= 5 {
            w.keyword("OFFSETS")?;
            read_offsets_bin(w, a, size, nv, build, conn, ends).map(|()| None)
        } else {
            w.rest_of_line()?;
            read_classic_bin(w, a, size, nv, build, conn, ends)
        }
    } else {
        let next = w.expect("the cells")?;
        if next.eq_ignore_ascii_case(b"OFFSETS") {
            read_offsets_layout(w, a, size, nv, build, conn, ends).map(|()| None)
        } else {
            w.unread();
            if h.major >= 5 {
                return Err(w.err(format!(
                    "this file says VTK version {}, whose {name} section starts with OFFSETS",
                    h.major
                )));
            }
            read_classic_layout(w, a, size, nv, build, conn, ends).map(|()| None)
        }
    }
}

/// The cell sections of a POLYDATA dataset, in VTK's cell order, with the cell type each
/// section's cells have (poly-vertex, poly-line, polygon, triangle strip).
const POLY_SECTIONS: [(&str, u64); 4] = [
    ("VERTICES", 2),
    ("LINES", 4),
    ("POLYGONS", 7),
    ("TRIANGLE_STRIPS", 6),
];

/// VTK type `ty` of cell `i` listing `n` points, or why it cannot be read.
fn cell_type(i: usize, ty: u64, n: u64) -> Result<u8, String> {
    match arity_error(ty, n) {
        Some(m) => Err(format!("cell {i}: {m}")),
        None => {
            u8::try_from(ty).map_err(|_| format!("cell {i}: VTK cell type {ty} is not supported"))
        }
    }
}

/// Bytes of one value of a binary legacy VTK data type (`None`: not an integer or float type
/// starplex reads here).
fn type_width(ty: &[u8]) -> Option<(usize, bool)> {
    let t = ty.to_ascii_lowercase();
    Some(match t.as_slice() {
        b"float" | b"vtktypefloat32" => (4, true),
        b"double" | b"vtktypefloat64" => (8, true),
        b"int" | b"unsigned_int" | b"vtktypeint32" | b"vtktypeuint32" => (4, false),
        b"long" | b"unsigned_long" | b"vtkidtype" | b"vtktypeint64" | b"vtktypeuint64" => {
            (8, false)
        }
        _ => return None,
    })
}

/// Binary `POINTS n type` body (big-endian `float` or `double`), the count already read.
fn read_points_bin(
    w: &mut Words<'_, impl BufRead>,
    n: usize,
    b: &mut ComplexBuilder,
) -> Result<(), IoError> {
    let ty = w.expect("the point data type")?.to_vec();
    let (width, float) = type_width(&ty).unwrap_or((0, false));
    if !float {
        return Err(w.err(format!(
            "binary POINTS of type '{}' are not supported (float or double)",
            lossy(&ty)
        )));
    }
    w.rest_of_line()?;
    if n >= u32::MAX as usize {
        return Err(w.err(format!(
            "point count {n} exceeds the 32-bit id limit of starplex"
        )));
    }
    let (path, at, first) = (w.path(), w.offset(), b.n_vertices());
    // decoded into one array (reserved for them, up to 256 MiB) and moved
    // into the builder at once: no per-buffer array and no second copy
    let mut p: Vec<f64> = Vec::new();
    reserve_declared(&mut p, 3 * n as u64);
    read_records(w, n as u64, 3 * width, "the points", |_, c, _| {
        use rayon::prelude::*;
        if width == 8 {
            p.par_extend(
                c.par_chunks_exact(8)
                    .map(|x| f64::from_be_bytes(x.try_into().expect("8 bytes"))),
            );
        } else {
            p.par_extend(
                c.par_chunks_exact(4)
                    .map(|x| f32::from_be_bytes(x.try_into().expect("4 bytes")) as f64),
            );
        }
        Ok(())
    })?;
    b.push_vertices(p).map_err(|e| {
        let v = match e {
            ComplexError::NonFiniteCoordinate { vertex, .. } => vertex as usize - first,
            _ => 0,
        };
        IoError::new(path, e).at(Location::Byte(at + (3 * width * v) as u64))
    })?;
    Ok(())
}

/// `n` big-endian integers of `width` bytes.
fn read_ints_bin(
    w: &mut Words<'_, impl BufRead>,
    n: u64,
    width: usize,
    what: &str,
) -> Result<Vec<u64>, IoError> {
    let mut out = Vec::new();
    read_records(w, n, width, what, |_, c, _| {
        if width == 4 {
            out.extend(
                c.chunks_exact(4)
                    .map(|x| get_i32(x, Endian::Big) as i64 as u64),
            );
        } else {
            out.extend(c.chunks_exact(8).map(|x| get_i64(x, Endian::Big) as u64));
        }
        Ok(())
    })?;
    Ok(out)
}

/// Binary classic `CELLS n size` body: `size` big-endian `int`s, `k v_0 .. v_{k-1}` per cell.
fn read_classic_bin(
    w: &mut Words<'_, impl BufRead>,
    n: u64,
    size: u64,
    nv: usize,
    build: &BuildOptions,
    conn: &mut Vec<u32>,
    ends: &mut Vec<u64>,
) -> Result<Option<u64>, IoError> {
    if n >= u32::MAX as u64 {
        return Err(w.err(format!(
            "cell count {n} exceeds the 32-bit id limit of starplex"
        )));
    }
    let at = w.offset();
    let mut flat: Vec<u32> = Vec::new();
    if n > 0 && size > 0 && conn.is_empty() && ends.is_empty() {
        let mut head = [0u8; 4];
        w.read_raw(&mut head, "the cell list")?;
        let k = u32::from_be_bytes(head);
        let uniform = match k {
            2 => read_uniform_cells::<2>(w, n, size, nv, build, CHUNK)?,
            3 => read_uniform_cells::<3>(w, n, size, nv, build, CHUNK)?,
            4 => read_uniform_cells::<4>(w, n, size, nv, build, CHUNK)?,
            5 => read_uniform_cells::<5>(w, n, size, nv, build, CHUNK)?,
            6 => read_uniform_cells::<6>(w, n, size, nv, build, CHUNK)?,
            8 => read_uniform_cells::<8>(w, n, size, nv, build, CHUNK)?,
            _ => Uniform::Not,
        };
        match uniform {
            Uniform::Cells(cells) => {
                *conn = cells;
                return Ok(Some(k as u64));
            }
            Uniform::Read(read) => flat = read,
            Uniform::Not => flat.push(k),
        }
    }
    read_records(
        w,
        size - flat.len() as u64,
        4,
        "the cell list",
        |_, c, _| {
            flat.extend(c.chunks_exact(4).map(|x| get_u32(x, Endian::Big)));
            Ok(())
        },
    )?;
    if classic_cells_fast(&mut flat, n, nv, build, ends) {
        if conn.is_empty() {
            *conn = flat;
        } else {
            conn.extend_from_slice(&flat);
        }
        return Ok(None);
    }
    let flat: Vec<u64> = flat.iter().map(|&x| x as i32 as i64 as u64).collect();
    let path = w.path();
    let bad =
        |i: usize, msg: String| IoError::parse(path, Some(Location::Byte(at + 4 * i as u64)), msg);
    let mut i = 0usize;
    for c in 0..n {
        let Some(&k) = flat.get(i) else {
            return Err(bad(
                i,
                format!("CELLS says the cell list has {size} numbers, and cell {c} is past them"),
            ));
        };
        if k == 0 || k > 64 || i + 1 + k as usize > flat.len() {
            return Err(bad(
                i,
                format!(
                    "cell {c} lists {} points (a supported cell has 2 to 8, a vertex 1)",
                    k as i64
                ),
            ));
        }
        let start = conn.len();
        for (j, &v) in flat[i + 1..i + 1 + k as usize].iter().enumerate() {
            if v >= nv as u64 {
                return Err(bad(
                    i + 1 + j,
                    format!(
                        "point index {} is out of range: the file has {nv} points",
                        v as i64
                    ),
                ));
            }
            conn.push(v as u32);
        }
        build
            .check_cell(c, &conn[start..], nv)
            .map_err(|e| IoError::new(path, e).at(Location::Byte(at + 4 * i as u64)))?;
        i += 1 + k as usize;
        ends.push(conn.len() as u64);
    }
    if i != flat.len() {
        return Err(bad(
            i,
            format!("CELLS says the cell list has {size} numbers, the {n} cells hold {i}"),
        ));
    }
    Ok(None)
}

/// The binary CELL_TYPES body: `n` big-endian types, each checked against its cell's point
/// count (`k` each when `uniform` is `Some(k)`, else from `ends`), read in chunks of `chunk`
/// bytes. Runs of one type are checked once: after each new type the rest of the buffer is
/// compared with it 64 bytes at a time, and a buffer that repeats it throughout costs that
/// comparison only.
fn read_types_bin(
    w: &mut Words<'_, impl BufRead>,
    n: u64,
    uniform: Option<u64>,
    ends: &[u64],
    chunk: usize,
) -> Result<Vec<u8>, IoError> {
    let (path, at) = (w.path(), w.offset());
    let mut kinds = Vec::new();
    reserve_declared(&mut kinds, n);
    let (mut i, mut start) = (0usize, 0u64);
    // the type and point count of the last cell checked (most cells repeat them)
    let mut last: Option<(u64, u64, u8)> = None;
    let mut fresh = true;
    read_records_in(w, n, 4, chunk, "the cell types", |_, c, _| {
        let mut c = c;
        fresh = true;
        while !c.is_empty() {
            if let (Some(k), Some((t, lk, kind)), true) = (uniform, last, fresh) {
                fresh = false;
                let t: [u8; 64] = std::array::from_fn(|j| (t as u32).to_be_bytes()[j % 4]);
                let whole = c.chunks_exact(64);
                let rest = whole.remainder();
                if lk == k && whole.into_iter().all(|x| x == t) && rest == &t[..rest.len()] {
                    kinds.resize(kinds.len() + c.len() / 4, kind);
                    i += c.len() / 4;
                    start = i as u64 * k;
                    return Ok(());
                }
            }
            let ty = get_u32(c, Endian::Big) as u64;
            let end = match uniform {
                Some(k) => (i as u64 + 1) * k,
                None => ends[i],
            };
            let kind = match last {
                Some((t, k, kind)) if t == ty && k == end - start => kind,
                _ => {
                    let kind = cell_type(i, ty, end - start).map_err(|m| {
                        IoError::parse(path, Some(Location::Byte(at + 4 * i as u64)), m)
                    })?;
                    last = Some((ty, end - start, kind));
                    fresh = true;
                    kind
                }
            };
            start = end;
            kinds.push(kind);
            i += 1;
            c = &c[4..];
        }
        Ok(())
    })?;
    Ok(kinds)
}

/// The ends of the cells of `len` vertex references, `k` each: `k, 2k, ..`.
fn uniform_ends(k: u64, len: usize) -> Vec<u64> {
    (1..=len as u64 / k).map(|c| c * k).collect()
}

/// What [`read_uniform_cells`] found.
enum Uniform {
    /// The list is not `n` cells of one size (nothing more was read).
    Not,
    /// The cells' vertices, every cell checked (sizes, range and, unless degenerate cells are
    /// dropped, distinct vertices).
    Cells(Vec<u32>),
    /// A cell failed a check: the values read so far, the first count included, in file
    /// order (the general path reads the rest and names the problem).
    Read(Vec<u32>),
}

/// A binary classic cell list of `n` cells of `K` points (`size` = n (K + 1) values), its first
/// count already read: the values are decoded, checked and compacted as each buffer (of about
/// `chunk` bytes) arrives, in parallel, straight into the cells' vertex array (one pass over
/// the list instead of a decode, a check and a compaction).
fn read_uniform_cells<const K: usize>(
    w: &mut Words<'_, impl BufRead>,
    n: u64,
    size: u64,
    nv: usize,
    build: &BuildOptions,
    chunk: usize,
) -> Result<Uniform, IoError>
where
    [u32; K]: bytemuck::Pod,
{
    use rayon::prelude::*;
    use std::sync::atomic::{AtomicBool, Ordering};
    if n.checked_mul(K as u64 + 1) != Some(size) {
        return Ok(Uniform::Not);
    }
    let (drop, nvu) = (build.drop_degenerate, nv.min(u32::MAX as usize) as u32);
    // records `v_0 .. v_{K-1} k'`: a cell's vertices and the next cell's count (none after
    // the last cell)
    let rec = 4 * (K + 1);
    let per = (chunk / rec).max(1) as u64;
    let mut cells: Vec<[u32; K]> = Vec::new();
    reserve_declared(&mut cells, n);
    let mut buf = vec![0u8; (n.min(per) as usize) * rec];
    let mut done = 0u64;
    while done < n {
        let m = (n - done).min(per) as usize;
        // the last cell has no count after it
        let len = m * rec - if done + m as u64 == n { 4 } else { 0 };
        let b = &mut buf[..len];
        w.read_raw(b, "the cell list")?;
        let bad = AtomicBool::new(false);
        cells.par_extend(b.par_chunks(rec).map(|r| {
            let mut v = [0u32; K];
            let mut wrong = false;
            for (x, c) in v.iter_mut().zip(r.chunks_exact(4)) {
                *x = u32::from_be_bytes([c[0], c[1], c[2], c[3]]);
                wrong |= *x >= nvu;
            }
            if r.len() == rec {
                wrong |= r[rec - 4..] != (K as u32).to_be_bytes();
            }
            for a in 1..K {
                for c in 0..a {
                    wrong |= v[a] == v[c] && !drop;
                }
            }
            if wrong {
                bad.store(true, Ordering::Relaxed);
            }
            v
        }));
        if bad.into_inner() {
            // hand everything read to the general path, in file order
            let last = cells.len() - m;
            let mut flat = Vec::with_capacity(1 + last * (K + 1) + len / 4);
            flat.push(K as u32);
            for c in &cells[..last] {
                flat.extend_from_slice(c);
                flat.push(K as u32);
            }
            flat.extend(b.chunks_exact(4).map(|x| get_u32(x, Endian::Big)));
            return Ok(Uniform::Read(flat));
        }
        done += m as u64;
    }
    Ok(Uniform::Cells(bytemuck::allocation::cast_vec(cells)))
}

/// The fast path of a classic cell list `k v_0 .. v_{k-1}` (`flat`, `n` cells): when every
/// cell lists 1 to 64 points, all below `nv` and, unless degenerate cells are dropped by the
/// build, pairwise distinct, and the cells fill the list exactly, compacts `flat` in place into
/// the cells' vertices and appends their ends (offset by `ends`' last end) to `ends`.
/// Otherwise returns false with both unchanged: the checked loop then names the problem.
fn classic_cells_fast(
    flat: &mut Vec<u32>,
    n: u64,
    nv: usize,
    build: &BuildOptions,
    ends: &mut Vec<u64>,
) -> bool {
    let e0 = ends.len();
    let base = ends.last().copied().unwrap_or(0);
    // one cell size throughout (a mesh of one kind): checked in parallel, compacted at once
    let uniform = match flat.first() {
        Some(&2) => uniform_cells::<2>(flat, n, nv, build),
        Some(&3) => uniform_cells::<3>(flat, n, nv, build),
        Some(&4) => uniform_cells::<4>(flat, n, nv, build),
        Some(&5) => uniform_cells::<5>(flat, n, nv, build),
        Some(&6) => uniform_cells::<6>(flat, n, nv, build),
        Some(&8) => uniform_cells::<8>(flat, n, nv, build),
        _ => None,
    };
    if let Some(k) = uniform {
        ends.extend((1..=n).map(|c| base + c * k as u64));
        return true;
    }
    ends.reserve(n as usize);
    let (mut i, mut out) = (0usize, 0usize);
    let mut ok = true;
    let mut max = 0u32;
    for _ in 0..n {
        let Some(&k) = flat.get(i) else {
            ok = false;
            break;
        };
        let k = k as usize;
        if !(1..=64).contains(&k) || i + 1 + k > flat.len() {
            ok = false;
            break;
        }
        let c = &flat[i + 1..i + 1 + k];
        for a in 1..k {
            for b in 0..a {
                ok &= build.drop_degenerate || c[a] != c[b];
            }
        }
        max = c.iter().fold(max, |m, &v| m.max(v));
        out += k;
        ends.push(base + out as u64);
        i += 1 + k;
    }
    if !(ok && i == flat.len() && (n == 0 || (max as usize) < nv)) {
        ends.truncate(e0);
        return false;
    }
    // checked: drop each cell's count, in place
    let (mut from, mut to) = (0usize, 0usize);
    for &end in &ends[e0..] {
        let k = (end - base) as usize - to;
        flat.copy_within(from + 1..from + 1 + k, to);
        (from, to) = (from + 1 + k, to + k);
    }
    flat.truncate(out);
    true
}

/// [`classic_cells_fast`] for `n` cells of `K` points each: when `flat` is exactly that and
/// passes the checks, compacts it in place and returns `Some(K)`; otherwise leaves it unchanged.
fn uniform_cells<const K: usize>(
    flat: &mut Vec<u32>,
    n: u64,
    nv: usize,
    build: &BuildOptions,
) -> Option<usize> {
    use rayon::prelude::*;
    if flat.len() as u64 != n * (K as u64 + 1) {
        return None;
    }
    let (drop, nv) = (build.drop_degenerate, nv.min(u32::MAX as usize) as u32);
    let ok = flat.par_chunks(4096 * (K + 1)).all(|part| {
        // branch-free over fixed-size records: one flag per chunk
        let mut bad = 0u32;
        for c in part.chunks_exact(K + 1) {
            let (k, v) = (c[0], &c[1..]);
            let v: &[u32; K] = v.try_into().expect("K + 1 values");
            bad |= k ^ K as u32;
            for a in 0..K {
                bad |= (v[a] >= nv) as u32;
                for b in 0..a {
                    bad |= (v[a] == v[b] && !drop) as u32;
                }
            }
        }
        bad == 0
    });
    if !ok {
        return None;
    }
    for c in 0..n as usize {
        let (from, to) = (c * (K + 1) + 1, c * K);
        for j in 0..K {
            flat[to + j] = flat[from + j];
        }
    }
    flat.truncate(n as usize * K);
    Some(K)
}

/// The offset count of a version-5 `CELLS` header: cells + 1, at least 1, ids within 32 bits.
fn check_offset_count(w: &Words<'_, impl BufRead>, n_off: u64) -> Result<(), IoError> {
    if n_off == 0 {
        return Err(w.err("CELLS declares 0 offsets (there must be cells + 1)"));
    }
    if n_off >= u32::MAX as u64 {
        return Err(w.err(format!(
            "cell count {n_off} exceeds the 32-bit id limit of starplex"
        )));
    }
    Ok(())
}

/// Binary version-5 body: `OFFSETS type` then `CONNECTIVITY type` (the word `OFFSETS` already
/// read), big-endian integers.
fn read_offsets_bin(
    w: &mut Words<'_, impl BufRead>,
    n_off: u64,
    n_conn: u64,
    nv: usize,
    build: &BuildOptions,
    conn: &mut Vec<u32>,
    ends: &mut Vec<u64>,
) -> Result<(), IoError> {
    check_offset_count(w, n_off)?;
    let ty = w.expect("the offsets' data type")?.to_vec();
    let Some((width, false)) = type_width(&ty) else {
        return Err(w.err(format!(
            "offsets of type '{}' are not supported",
            lossy(&ty)
        )));
    };
    w.rest_of_line()?;
    let path = w.path();
    let at = w.offset();
    let offs = read_ints_bin(w, n_off, width, "the offsets")?;
    let bad = |at: u64, msg: String| IoError::parse(path, Some(Location::Byte(at)), msg);
    if offs[0] != 0 {
        return Err(bad(
            at,
            format!("the first offset is {}, expected 0", offs[0] as i64),
        ));
    }
    let mut prev = 0u64;
    for (i, &o) in offs.iter().enumerate().skip(1) {
        if o < prev || o - prev > 64 || o > n_conn {
            return Err(bad(at + (i * width) as u64, format!(
                "offset {i} is {} after {prev}: a cell has 1 to 64 points, and CELLS declares {n_conn} connectivity entries",
                o as i64
            )));
        }
        prev = o;
        ends.push(o);
    }
    if prev != n_conn {
        return Err(bad(
            at,
            format!("the last offset is {prev} but CELLS declares {n_conn} connectivity entries"),
        ));
    }
    w.keyword("CONNECTIVITY")?;
    let ty = w.expect("the connectivity's data type")?.to_vec();
    let Some((width, false)) = type_width(&ty) else {
        return Err(w.err(format!(
            "connectivity of type '{}' is not supported",
            lossy(&ty)
        )));
    };
    w.rest_of_line()?;
    let at = w.offset();
    let flat = read_ints_bin(w, n_conn, width, "the connectivity")?;
    if let Some(i) = flat.iter().position(|&v| v >= nv as u64) {
        return Err(bad(
            at + (i * width) as u64,
            format!(
                "point index {} is out of range: the file has {nv} points",
                flat[i] as i64
            ),
        ));
    }
    conn.extend(flat.iter().map(|&v| v as u32));
    let mut start = 0usize;
    for (i, &end) in ends.iter().enumerate() {
        build
            .check_cell(i as u64, &conn[start..end as usize], nv)
            .map_err(|e| IoError::new(path, e).at(Location::Byte(at + (start * width) as u64)))?;
        start = end as usize;
    }
    Ok(())
}

/// Reads the classic `CELLS n size` body: `n` lines `k v_0 .. v_{k-1}`, `size = n + sum k`.
fn read_classic_layout(
    w: &mut Words<'_, impl BufRead>,
    n: u64,
    size: u64,
    nv: usize,
    build: &BuildOptions,
    conn: &mut Vec<u32>,
    ends: &mut Vec<u64>,
) -> Result<(), IoError> {
    if n >= u32::MAX as u64 {
        return Err(w.err(format!(
            "cell count {n} exceeds the 32-bit id limit of starplex"
        )));
    }
    let mut used: u64 = 0;
    for i in 0..n {
        let k = w.u64("a cell's point count")?;
        if k == 0 || k > 64 {
            return Err(w.err(format!(
                "cell {i} lists {k} points (a supported cell has 2 to 8, a vertex 1)"
            )));
        }
        let line = w.line();
        let start = conn.len();
        for _ in 0..k {
            conn.push(w.index("point index", 0, nv)?);
        }
        build
            .check_cell(i, &conn[start..], nv)
            .map_err(|e| IoError::new(w.path(), e).at(Location::Line(line)))?;
        used += k + 1;
        ends.push(conn.len() as u64);
    }
    if used != size {
        return Err(w.err(format!(
            "CELLS says the cell list has {size} numbers, the {n} cells hold {used}"
        )));
    }
    Ok(())
}

/// Reads the version-5 body: `OFFSETS type` with `n_off` offsets, then `CONNECTIVITY type` with
/// `n_conn` point indices (the word `OFFSETS` already read).
fn read_offsets_layout(
    w: &mut Words<'_, impl BufRead>,
    n_off: u64,
    n_conn: u64,
    nv: usize,
    build: &BuildOptions,
    conn: &mut Vec<u32>,
    ends: &mut Vec<u64>,
) -> Result<(), IoError> {
    check_offset_count(w, n_off)?;
    w.expect("the offsets' data type")?;
    let mut prev = w.u64("an offset")?;
    if prev != 0 {
        return Err(w.err(format!("the first offset is {prev}, expected 0")));
    }
    for i in 1..n_off {
        let o = w.u64("an offset")?;
        if o < prev || o - prev > 64 {
            return Err(w.err(format!(
                "offset {i} is {o} after {prev}: a cell has 1 to 64 points"
            )));
        }
        if o > n_conn {
            return Err(w.err(format!(
                "offset {o} is past the {n_conn} connectivity entries CELLS declares"
            )));
        }
        prev = o;
        ends.push(o);
    }
    if prev != n_conn {
        return Err(w.err(format!(
            "the last offset is {prev} but CELLS declares {n_conn} connectivity entries"
        )));
    }
    w.keyword("CONNECTIVITY")?;
    w.expect("the connectivity's data type")?;
    let mut start = 0usize;
    for (i, &end) in ends.iter().enumerate() {
        let mut line = 0;
        while (conn.len() as u64) < end {
            conn.push(w.index("point index", 0, nv)?);
            if line == 0 {
                line = w.line();
            }
        }
        build
            .check_cell(i as u64, &conn[start..], nv)
            .map_err(|e| IoError::new(w.path(), e).at(Location::Line(line.max(1))))?;
        start = conn.len();
    }
    Ok(())
}

/// Refuses what legacy VTK cannot hold: more than 3 coordinates, simplices of dimension 4 and
/// more.
///
/// ```
/// use starplex::cell::CellKind;
/// use starplex::complex::IndexedComplex;
/// use starplex::io::vtk;
/// let s4 = IndexedComplex::from_parts(3, vec![0.0; 15].into(),
///                                     vec![(CellKind::Simplex(4), vec![0, 1, 2, 3, 4].into())]).unwrap();
/// assert!(vtk::check(&s4).unwrap_err().to_string().contains("no cell type for simplex_4"));
/// ```
///
/// # Errors
/// [`IoErrorKind::CannotWrite`] with the reason.
pub fn check(k: &IndexedComplex) -> Result<(), IoErrorKind> {
    let d = k.ambient_dim();
    if d > 3 {
        return Err(IoErrorKind::CannotWrite {
            format: Format::Vtk,
            reason: format!("VTK points have 3 coordinates, the complex has {d}"),
        });
    }
    for b in k.blocks() {
        if vtk_type(b.kind).is_none() {
            return Err(IoErrorKind::CannotWrite {
                format: Format::Vtk,
                reason: format!("VTK has no cell type for {} cells", b.kind),
            });
        }
    }
    Ok(())
}

/// Writes `k` as legacy VTK (version 4.2, ascii, classic layout).
///
/// ```
/// use starplex::io::{vtk, IoErrorKind};
/// # use starplex::complex::IndexedComplex;
/// # use starplex::cell::CellKind;
/// // A 2D edge: points are padded to 3 coordinates.
/// let k = IndexedComplex::from_parts(2, vec![0.0, 0.0, 1.0, 2.0].into(),
///                                    vec![(CellKind::Simplex(1), vec![0, 1].into())]).unwrap();
/// let mut out = Vec::new();
/// vtk::write(&mut out, &k).unwrap();
/// let text = String::from_utf8(out).unwrap();
/// assert!(text.starts_with("# vtk DataFile Version 4.2\n"));
/// assert!(text.contains("1 2 0\n"));
/// let k4 = IndexedComplex::from_parts(4, vec![0.0; 4].into(), vec![]).unwrap();
/// assert!(matches!(vtk::write(&mut Vec::new(), &k4), Err(IoErrorKind::CannotWrite { .. })));
/// ```
///
/// # Errors
/// [`IoErrorKind::CannotWrite`] for an ambient dimension above 3 or simplices of dimension 4 and
/// more; OS errors of the writer.
pub fn write(w: &mut dyn Write, k: &IndexedComplex) -> Result<(), IoErrorKind> {
    check(k)?;
    write_head(w, k, "UNSTRUCTURED_GRID")?;
    writeln!(w, "CELLS {} {}", k.n_cells(), k.n_cells() + k.n_refs())?;
    let mut line = String::with_capacity(128);
    for b in k.blocks() {
        for i in 0..b.len() {
            push_cell_line(&mut line, b.cell(i));
            w.write_all(line.as_bytes())?;
        }
    }
    writeln!(w, "CELL_TYPES {}", k.n_cells())?;
    for b in k.blocks() {
        let t = vtk_type(b.kind).unwrap_or(0);
        for _ in 0..b.len() {
            writeln!(w, "{t}")?;
        }
    }
    write_point_cell_data(w, k, None)
}

/// Refuses what a legacy `POLYDATA` file written by [`write_polydata`] cannot hold: more than 3
/// coordinates, cells other than edges, triangles and quads.
///
/// ```
/// use starplex::cell::CellKind;
/// use starplex::complex::IndexedComplex;
/// use starplex::io::vtk;
/// let tet = IndexedComplex::from_parts(3, vec![0.0; 12].into(),
///                                      vec![(CellKind::Simplex(3), vec![0, 1, 2, 3].into())]).unwrap();
/// let e = vtk::check_polydata(&tet).unwrap_err().to_string();
/// assert!(e.contains("POLYDATA holds edges, triangles and quads"), "{e}");
/// ```
///
/// # Errors
/// [`IoErrorKind::CannotWrite`] with the reason.
pub fn check_polydata(k: &IndexedComplex) -> Result<(), IoErrorKind> {
    let d = k.ambient_dim();
    let fail = |reason: String| {
        Err(IoErrorKind::CannotWrite {
            format: Format::VtkPolyData,
            reason,
        })
    };
    if d > 3 {
        return fail(format!(
            "VTK points have 3 coordinates, the complex has {d}"
        ));
    }
    for b in k.blocks() {
        if !matches!(
            b.kind,
            CellKind::Simplex(1) | CellKind::Simplex(2) | CellKind::Quad
        ) {
            return fail(format!(
                "POLYDATA holds edges, triangles and quads, not {} cells: write the unstructured grid (format vtk)",
                b.kind
            ));
        }
    }
    Ok(())
}

/// Writes `k` as legacy VTK `DATASET POLYDATA` (version 4.2, ascii, classic layout): edges as
/// `LINES`, triangles and quads as `POLYGONS`, attributes as in [`write()`]. VTK numbers the
/// cells of poly data section by section, so `CELL_DATA` lists the edges' values first, then
/// the polygons'; a reader gives back the edges first, then the polygons, each in their order
/// in `k` (the same cells when `k` lists its edges first).
///
/// ```
/// use starplex::cell::CellKind;
/// use starplex::complex::IndexedComplex;
/// use starplex::io::{vtk, ReadOptions};
/// let k = IndexedComplex::from_parts(3, vec![0., 0., 0., 1., 0., 0., 0., 1., 0., 2., 2., 0.].into(),
///     vec![(CellKind::Simplex(1), vec![2, 3].into()), (CellKind::Simplex(2), vec![0, 1, 2].into())]).unwrap();
/// let mut out = Vec::new();
/// vtk::write_polydata(&mut out, &k).unwrap();
/// let text = String::from_utf8(out).unwrap();
/// assert!(text.contains("DATASET POLYDATA\n") && text.contains("LINES 1 3\n2 2 3\nPOLYGONS 1 4\n3 0 1 2\n"));
/// let back = vtk::read_from(text.as_bytes(), "p.vtk".as_ref(), &ReadOptions::default()).unwrap();
/// assert_eq!(back.complex, k);
/// ```
///
/// # Errors
/// [`IoErrorKind::CannotWrite`] (see [`check_polydata`]); OS errors of the writer.
pub fn write_polydata(w: &mut dyn Write, k: &IndexedComplex) -> Result<(), IoErrorKind> {
    check_polydata(k)?;
    write_head(w, k, "POLYDATA")?;
    // VTK's cell order: the lines, then the polygons
    let mut order: Vec<u32> = Vec::with_capacity(k.n_cells());
    let mut line = String::with_capacity(128);
    for (sec, lines) in [("LINES", true), ("POLYGONS", false)] {
        let blocks = || {
            k.blocks()
                .iter()
                .filter(move |b| (b.kind == CellKind::Simplex(1)) == lines)
        };
        let (n, refs) = blocks().fold((0, 0), |(n, r), b| {
            (n + b.len(), r + b.len() * (1 + b.kind.n_vertices()))
        });
        if n == 0 {
            continue;
        }
        writeln!(w, "{sec} {n} {refs}")?;
        for b in blocks() {
            for i in 0..b.len() {
                order.push(b.first + i as u32);
                push_cell_line(&mut line, b.cell(i));
                w.write_all(line.as_bytes())?;
            }
        }
    }
    write_point_cell_data(w, k, Some(&order))
}

/// The header and `POINTS` section of a legacy file of dataset type `dataset`.
fn write_head(w: &mut dyn Write, k: &IndexedComplex, dataset: &str) -> std::io::Result<()> {
    let d = k.ambient_dim();
    writeln!(w, "# vtk DataFile Version 4.2")?;
    writeln!(w, "written by starplex {}", env!("CARGO_PKG_VERSION"))?;
    writeln!(w, "ASCII")?;
    writeln!(w, "DATASET {dataset}")?;
    writeln!(w, "POINTS {} double", k.n_vertices())?;
    for p in k.coords().chunks_exact(d.max(1)) {
        for (i, &x) in p.iter().enumerate() {
            if i > 0 {
                w.write_all(b" ")?;
            }
            write_f64(w, x)?;
        }
        for _ in d..3 {
            w.write_all(b" 0")?;
        }
        w.write_all(b"\n")?;
    }
    Ok(())
}

/// `line` = `n v_0 .. v_{n-1}` and a line end.
fn push_cell_line(line: &mut String, c: &[u32]) {
    use std::fmt::Write as _;
    line.clear();
    let _ = write!(line, "{}", c.len());
    for v in c {
        let _ = write!(line, " {v}");
    }
    line.push('\n');
}

/// `POINT_DATA` and `CELL_DATA` as `FIELD` arrays; the cells' values in `order` (cell ids) when
/// given, else in cell order.
fn write_point_cell_data(
    w: &mut dyn Write,
    k: &IndexedComplex,
    order: Option<&[u32]>,
) -> Result<(), IoErrorKind> {
    let attrs = k.attributes();
    for (sec, cols, n, order) in [
        ("POINT_DATA", &attrs.vertex, k.n_vertices(), None),
        ("CELL_DATA", &attrs.cell, k.n_cells(), order),
    ] {
        if cols.is_empty() {
            continue;
        }
        writeln!(w, "{sec} {n}")?;
        writeln!(w, "FIELD FieldData {}", cols.len())?;
        for a in cols {
            let ty = match a.values {
                AttrValues::Int(_) => "long", // 64-bit: what meshio and VTK read in version 4.2 files
                AttrValues::Float(_) => "double",
            };
            writeln!(w, "{} {} {n} {ty}", legacy_name(&a.name), a.components)?;
            for pos in 0..n {
                let item = order.map_or(pos, |o| o[pos] as usize);
                for c in 0..a.components {
                    if c > 0 {
                        w.write_all(b" ")?;
                    }
                    let i = item * a.components + c;
                    match &a.values {
                        AttrValues::Int(v) => write!(w, "{}", v[i])?,
                        AttrValues::Float(v) => write_f64(w, v[i])?,
                    }
                }
                w.write_all(b"\n")?;
            }
        }
    }
    Ok(())
}

/// An attribute name as one legacy VTK word (whitespace replaced by `_`, empty named `array`).
fn legacy_name(name: &str) -> String {
    if name.is_empty() {
        return "array".into();
    }
    name.chars()
        .map(|c| if c.is_whitespace() { '_' } else { c })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn be(b: &[u8]) -> Vec<u32> {
        b.chunks_exact(4)
            .map(|x| u32::from_be_bytes(x.try_into().unwrap()))
            .collect()
    }

    /// A classic cell list of tetrahedra `4 a b c d ..`, big-endian.
    fn classic(cells: &[[u32; 4]]) -> Vec<u8> {
        let mut b = Vec::new();
        for c in cells {
            b.extend_from_slice(&4u32.to_be_bytes());
            for v in c {
                b.extend_from_slice(&v.to_be_bytes());
            }
        }
        b
    }

    fn uniform(body: &[u8], n: u64, nv: usize, o: &BuildOptions, chunk: usize) -> (Uniform, u64) {
        // the first count is read by the caller
        let mut w = Words::new(&body[4..], Path::new("m.vtk"), None);
        let u = read_uniform_cells::<4>(&mut w, n, 5 * n, nv, o, chunk).unwrap();
        (u, w.offset())
    }

    #[test]
    fn uniform_cells_are_read_across_buffers_and_hand_over_a_prefix_on_a_fault() {
        let cells: Vec<[u32; 4]> = (0..50).map(|i| [i, i + 3, i + 1, i + 2]).collect();
        let clean = classic(&cells);
        let o = BuildOptions::default();
        // 20 bytes: one record a buffer; 1 MiB: all at once
        let chunks = [20, 40, 60, 100, 220, 1 << 20];
        for chunk in chunks {
            let (u, _) = uniform(&clean, 50, 53, &o, chunk);
            let Uniform::Cells(c) = u else {
                panic!("chunk {chunk}: the clean list is uniform")
            };
            assert_eq!(c, cells.concat(), "chunk {chunk}");
            // a vertex past the last: not uniform-clean
            let (u, _) = uniform(&clean, 50, 52, &o, chunk);
            assert!(matches!(u, Uniform::Read(_)), "chunk {chunk}");
        }
        // (cell, value index within the record `k a b c d`, value): out of range, repeated,
        // a count that is not 4
        let faults = [
            (0, 2, 99),
            (17, 3, 17),
            (33, 0, 3),
            (49, 4, 49),
            (20, 1, 500),
        ];
        for (cell, at, value) in faults {
            let mut b = clean.clone();
            let i = 4 * (5 * cell + at);
            b[i..i + 4].copy_from_slice(&(value as u32).to_be_bytes());
            let all = be(&b);
            for chunk in chunks {
                let (u, read) = uniform(&b, 50, 60, &o, chunk);
                let Uniform::Read(flat) = u else {
                    panic!("cell {cell}, chunk {chunk}: the fault is found")
                };
                // what was read, in file order: the caller reads the rest after it
                assert_eq!(flat[..], all[..flat.len()], "cell {cell}, chunk {chunk}");
                assert_eq!(
                    4 * flat.len() as u64,
                    4 + read,
                    "cell {cell}, chunk {chunk}"
                );
                assert!(flat.len() > 5 * cell + at, "cell {cell}, chunk {chunk}");
            }
        }
        // a repeated vertex is the build's to drop when degenerate cells are dropped
        let mut b = clean.clone();
        b[4 * (5 * 9 + 2)..4 * (5 * 9 + 3)].copy_from_slice(&9u32.to_be_bytes());
        let drop = BuildOptions {
            drop_degenerate: true,
            ..BuildOptions::default()
        };
        let (u, _) = uniform(&b, 50, 53, &drop, 40);
        let Uniform::Cells(c) = u else {
            panic!("repeated vertices pass when they are dropped later")
        };
        assert_eq!(c[36..40], [9, 9, 10, 11]);
    }

    #[test]
    fn cell_types_in_runs_are_checked_across_buffers() {
        // 4-point cells: tetrahedra (10) and quads (9) in runs, read with uniform and listed ends
        let types: Vec<u32> = (0..40)
            .map(|i| if (i / 7) % 3 == 2 { 9 } else { 10 })
            .collect();
        let body: Vec<u8> = types.iter().flat_map(|t| t.to_be_bytes()).collect();
        let ends = uniform_ends(4, 160);
        for chunk in [4, 8, 12, 64, 68, 256, 1 << 20] {
            for (uni, e) in [(Some(4), &[][..]), (None, &ends[..])] {
                let mut w = Words::new(&body[..], Path::new("m.vtk"), None);
                let k = read_types_bin(&mut w, 40, uni, e, chunk).unwrap();
                let want: Vec<u8> = types.iter().map(|&t| t as u8).collect();
                assert_eq!(k, want, "chunk {chunk}, uniform {uni:?}");
            }
            // one triangle type among 4-point cells: named by its byte
            let mut b = body.clone();
            b[4 * 23..4 * 24].copy_from_slice(&5u32.to_be_bytes());
            let mut w = Words::new(&b[..], Path::new("m.vtk"), None);
            let e = read_types_bin(&mut w, 40, Some(4), &[], chunk).unwrap_err();
            assert_eq!(
                e.location,
                Some(Location::Byte(4 * 23)),
                "chunk {chunk}: {e}"
            );
            // the same type throughout, but the wrong one for 3-point cells
            let mut w = Words::new(&body[..], Path::new("m.vtk"), None);
            let e = read_types_bin(&mut w, 40, Some(3), &[], chunk).unwrap_err();
            assert_eq!(e.location, Some(Location::Byte(0)), "chunk {chunk}: {e}");
        }
    }
}
