//! PLY (Stanford polygon file), ascii and binary, read through the `ply-rs-bw` parser.
//!
//! Reading: the `vertex` element's `x`, `y` (and `z` when present; without it the complex is 2D)
//! of any scalar type become the coordinates, other vertex properties are ignored; the `face`
//! element's `vertex_indices` (or `vertex_index`) list of any integer type becomes the cells,
//! following [`PolygonMode`]: with `Polygons` a face of 3 vertices is a triangle, 4 a quad, more
//! are fan-triangulated (counted in [`ReadResult::notes`]); with `Simplices` a face of `k`
//! vertices is a `(k-1)`-simplex. Other elements (`edge`, `material`, ...) are read past and noted.
//!
//! Before the payload is parsed, the counts declared in the header are compared with the bytes
//! that follow it (every record needs a minimum number of bytes), so a header declaring 10^12
//! vertices is an error, not an allocation. Errors carry the line (ascii, header) or byte offset
//! (binary payload). Cell ids in index errors are the face's position in the file.
//!
//! Writing: triangles and quads only (`binary_little_endian` by default, `ascii` with
//! [`write_with`]); coordinates as `double` so a round trip is exact.
//!
//! ```
//! use starplex::io::{ply, ReadOptions};
//! let text = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n\
//!             property float z\nelement face 1\nproperty list uchar int vertex_indices\n\
//!             end_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n";
//! let r = ply::read_from(text.as_bytes(), text.len() as u64, "mem.ply".as_ref(),
//!                        &ReadOptions::default()).unwrap();
//! assert_eq!(r.complex.n_vertices(), 4);
//! assert_eq!(r.complex.blocks()[0].kind, starplex::cell::CellKind::Quad);
//! let mut out = Vec::new();
//! ply::write_with(&mut out, &r.complex, ply::PlyEncoding::Ascii).unwrap();
//! assert!(String::from_utf8(out).unwrap().ends_with("4 0 1 2 3\n"));
//! ```
use std::io::{BufRead, Read, Write};
use std::path::Path;

use ply_rs_bw::parser::{ParseError, Parser, Reader};
use ply_rs_bw::ply::{
    BeginList, ElementDef, Encoding, PropertyAccess, PropertyAccessResult, PropertyType, ScalarType,
};

use super::text::write_f64;
use super::{Format, IoError, IoErrorKind, Location, PolygonMode, ReadOptions, ReadResult};
use crate::cell::CellKind;
use crate::complex::{check_cell, ComplexBuilder, IndexedComplex};

/// PLY data encodings starplex writes.
///
/// ```
/// assert_eq!(starplex::io::ply::PlyEncoding::default(),
///            starplex::io::ply::PlyEncoding::BinaryLittleEndian);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum PlyEncoding {
    /// `format ascii 1.0`: readable, larger.
    Ascii,
    /// `format binary_little_endian 1.0`: compact (the default).
    #[default]
    BinaryLittleEndian,
}

/// A `BufRead` that counts the bytes and newlines consumed (for error locations).
struct Counting<R> {
    inner: R,
    pos: u64,
    newlines: u64,
}

impl<R: BufRead> Read for Counting<R> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let n = self.inner.read(buf)?;
        self.pos += n as u64;
        self.newlines += memchr::memchr_iter(b'\n', &buf[..n]).count() as u64;
        Ok(n)
    }
}

impl<R: BufRead> BufRead for Counting<R> {
    fn fill_buf(&mut self) -> std::io::Result<&[u8]> {
        self.inner.fill_buf()
    }
    fn consume(&mut self, amt: usize) {
        if let Ok(b) = self.inner.fill_buf() {
            let n = amt.min(b.len());
            self.newlines += memchr::memchr_iter(b'\n', &b[..n]).count() as u64;
        }
        self.pos += amt as u64;
        self.inner.consume(amt);
    }
}

/// One vertex record: the coordinates found so far.
struct VertexRec {
    p: [f64; 3],
}

impl VertexRec {
    #[inline]
    fn set(&mut self, name: &str, v: f64) -> PropertyAccessResult {
        let axis = match name {
            "x" => 0,
            "y" => 1,
            "z" => 2,
            _ => return PropertyAccessResult::Ignored,
        };
        self.p[axis] = v;
        PropertyAccessResult::Set
    }
}

impl PropertyAccess for VertexRec {
    fn new() -> Self {
        VertexRec { p: [0.0; 3] }
    }
    fn set_char(&mut self, n: &str, v: i8) -> PropertyAccessResult {
        self.set(n, v as f64)
    }
    fn set_uchar(&mut self, n: &str, v: u8) -> PropertyAccessResult {
        self.set(n, v as f64)
    }
    fn set_short(&mut self, n: &str, v: i16) -> PropertyAccessResult {
        self.set(n, v as f64)
    }
    fn set_ushort(&mut self, n: &str, v: u16) -> PropertyAccessResult {
        self.set(n, v as f64)
    }
    fn set_int(&mut self, n: &str, v: i32) -> PropertyAccessResult {
        self.set(n, v as f64)
    }
    fn set_uint(&mut self, n: &str, v: u32) -> PropertyAccessResult {
        self.set(n, v as f64)
    }
    fn set_float(&mut self, n: &str, v: f32) -> PropertyAccessResult {
        self.set(n, v as f64)
    }
    fn set_double(&mut self, n: &str, v: f64) -> PropertyAccessResult {
        self.set(n, v)
    }
}

/// One face record: its vertex index list, in whichever integer type the file declares.
#[derive(Default)]
struct FaceRec {
    i8s: Vec<i8>,
    u8s: Vec<u8>,
    i16s: Vec<i16>,
    u16s: Vec<u16>,
    i32s: Vec<i32>,
    u32s: Vec<u32>,
}

#[inline]
fn is_index_name(n: &str) -> bool {
    n == "vertex_indices" || n == "vertex_index"
}

impl FaceRec {
    /// The indices as `u32`, or the first value that is negative.
    fn indices(&self, out: &mut Vec<u32>) -> Result<(), i64> {
        out.clear();
        fn conv<T: Copy + Into<i64>>(v: &[T], out: &mut Vec<u32>) -> Result<(), i64> {
            for &x in v {
                let x: i64 = x.into();
                out.push(u32::try_from(x).map_err(|_| x)?);
            }
            Ok(())
        }
        conv(&self.i8s, out)?;
        conv(&self.u8s, out)?;
        conv(&self.i16s, out)?;
        conv(&self.u16s, out)?;
        conv(&self.i32s, out)?;
        conv(&self.u32s, out)
    }
}

macro_rules! fill {
    ($name:ident, $field:ident, $t:ty) => {
        fn $name(&mut self, n: &str, _len: usize) -> BeginList<'_, $t> {
            if is_index_name(n) {
                BeginList::Fill(&mut self.$field)
            } else {
                BeginList::UseSetter
            }
        }
    };
}

impl PropertyAccess for FaceRec {
    fn new() -> Self {
        FaceRec::default()
    }
    fill!(begin_list_char, i8s, i8);
    fill!(begin_list_uchar, u8s, u8);
    fill!(begin_list_short, i16s, i16);
    fill!(begin_list_ushort, u16s, u16);
    fill!(begin_list_int, i32s, i32);
    fill!(begin_list_uint, u32s, u32);
}

/// Records of elements starplex does not use.
struct Skip;
impl PropertyAccess for Skip {
    fn new() -> Self {
        Skip
    }
}

fn scalar_size(t: &ScalarType) -> u64 {
    match t {
        ScalarType::Char | ScalarType::UChar => 1,
        ScalarType::Short | ScalarType::UShort => 2,
        ScalarType::Int | ScalarType::UInt | ScalarType::Float => 4,
        ScalarType::Double => 8,
    }
}

fn is_int(t: &ScalarType) -> bool {
    !matches!(t, ScalarType::Float | ScalarType::Double)
}

/// The fewest bytes one record of `def` can take.
fn min_record_bytes(def: &ElementDef, enc: Encoding) -> u64 {
    match enc {
        Encoding::Ascii => (2 * def.properties.len() as u64).max(1),
        _ => def
            .properties
            .values()
            .map(|p| match &p.data_type {
                PropertyType::Scalar(t) => scalar_size(t),
                PropertyType::List(i, _) => scalar_size(i),
            })
            .sum(),
    }
}

fn ply_err(path: &Path, e: ParseError, fallback: Location) -> IoError {
    let loc = match e.line() {
        Some(l) if matches!(fallback, Location::Line(_)) => Location::Line(l as u64),
        _ => fallback,
    };
    let msg = e.to_string();
    // ply-rs-bw prefixes "Line N: " itself; the location already says it.
    let msg = match msg.split_once(": ") {
        Some((head, rest)) if head.starts_with("Line ") => rest.to_string(),
        _ => msg,
    };
    // Drop the grammar's debug dump ("Error: ParseError { location: LineCol { line: 1, column:
    // 10, ... }, expected: ... }"), keeping the column.
    let msg = match msg.find("Error: ParseError") {
        Some(i) => {
            let col = msg[i..]
                .split_once("column: ")
                .and_then(|(_, r)| r.split(|c: char| !c.is_ascii_digit()).next())
                .unwrap_or("?");
            format!("{} (column {col})", msg[..i].trim_end())
        }
        None => msg,
    };
    IoError::parse(path, Some(loc), msg.replace(['\n', '\t'], " "))
}

/// Reads a PLY file.
///
/// ```
/// use starplex::io::{ply, ReadOptions};
/// let p = std::env::temp_dir().join(format!("starplex-doc-ply-{}.ply", std::process::id()));
/// std::fs::write(&p, "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n\
///                     property float y\nelement face 1\nproperty list uchar int vertex_indices\n\
///                     end_header\n0 0\n1 0\n0 1\n3 0 1 2\n").unwrap();
/// let r = ply::read(&p, &ReadOptions::default()).unwrap();
/// assert_eq!((r.complex.ambient_dim(), r.complex.n_cells()), (2, 1));
/// std::fs::remove_file(&p).ok();
/// ```
///
/// # Errors
/// See [`read_from`].
pub fn read(path: &Path, opts: &ReadOptions) -> Result<ReadResult, IoError> {
    let f = std::fs::File::open(path).map_err(|e| IoError::new(path, e))?;
    let len = f.metadata().map_err(|e| IoError::new(path, e))?.len();
    read_from(
        std::io::BufReader::with_capacity(1 << 20, f),
        len,
        path,
        opts,
    )
}

/// Reads PLY from a buffered reader of `len` bytes (the size is used to refuse declared counts
/// the data cannot hold); `path` names it in errors.
///
/// ```
/// use starplex::io::{ply, ReadOptions};
/// // a header that declares 10^12 vertices is refused before anything is allocated
/// let text = "ply\nformat ascii 1.0\nelement vertex 1000000000000\nproperty float x\n\
///             property float y\nend_header\n0 0\n";
/// let e = ply::read_from(text.as_bytes(), text.len() as u64, "big.ply".as_ref(),
///                        &ReadOptions::default()).unwrap_err();
/// assert!(e.to_string().starts_with("big.ply:6: element 'vertex' declares 1000000000000 records"));
/// ```
///
/// # Errors
/// A malformed header, a header without a `vertex` element or without `x`/`y`, declared counts
/// larger than the data, truncated or malformed records, faces without an integer
/// `vertex_indices` list, negative, out-of-range or repeated indices, non-finite coordinates, faces
/// of fewer than 3 vertices (polygon mode), and the checks of [`ComplexBuilder::build`].
pub fn read_from(
    r: impl BufRead,
    len: u64,
    path: &Path,
    opts: &ReadOptions,
) -> Result<ReadResult, IoError> {
    let mut reader = Reader::new(Counting {
        inner: r,
        pos: 0,
        newlines: 0,
    });
    let header = Parser::<Skip>::new()
        .read_header(&mut reader)
        .map_err(|e| ply_err(path, e, Location::Line(1)))?;
    let rd = reader.get_mut();
    let header_lines = rd.newlines;
    let hdr_err = |msg: String| IoError::parse(path, Some(Location::Line(header_lines)), msg);
    let enc = header.encoding;

    // Guard: declared counts against the bytes that follow the header.
    let remaining = len.saturating_sub(rd.pos);
    let mut need: u128 = 0;
    for def in header.elements.values() {
        let one = min_record_bytes(def, enc) as u128;
        need += one * def.count as u128;
        if need > remaining as u128 {
            return Err(hdr_err(format!(
                "element '{}' declares {} records, which need at least {} bytes, but only {} bytes follow the header (truncated file or corrupt header)",
                def.name,
                def.count,
                one * def.count as u128,
                remaining
            )));
        }
    }
    let Some(vdef) = header.elements.get("vertex") else {
        return Err(hdr_err("no 'vertex' element in the header".into()));
    };
    let mut has_axis = [false; 3];
    for (i, a) in ["x", "y", "z"].iter().enumerate() {
        if let Some(p) = vdef.properties.get(*a) {
            if !matches!(p.data_type, PropertyType::Scalar(_)) {
                return Err(hdr_err(format!(
                    "vertex property '{a}' is a list, expected a number"
                )));
            }
            has_axis[i] = true;
        }
    }
    if !has_axis[0] || !has_axis[1] {
        return Err(hdr_err(
            "the 'vertex' element has no 'x' and 'y' properties".into(),
        ));
    }
    let ambient = if has_axis[2] { 3 } else { 2 };
    if vdef.count >= u32::MAX as usize {
        return Err(hdr_err(format!(
            "{} vertices exceed the 32-bit id limit of starplex",
            vdef.count
        )));
    }
    if let Some(fdef) = header.elements.get("face") {
        let idx: Vec<_> = fdef
            .properties
            .values()
            .filter(|p| is_index_name(&p.name))
            .collect();
        match idx.as_slice() {
            [] => {
                return Err(hdr_err(
                    "the 'face' element has no 'vertex_indices' (or 'vertex_index') property"
                        .into(),
                ))
            }
            [p] => match &p.data_type {
                PropertyType::List(_, t) if is_int(t) => {}
                t => {
                    return Err(hdr_err(format!(
                        "face property '{}' has type {t:?}; expected a list of integers",
                        p.name
                    )))
                }
            },
            _ => {
                return Err(hdr_err(
                    "the 'face' element has both 'vertex_indices' and 'vertex_index'".into(),
                ))
            }
        }
    }

    let mut b = ComplexBuilder::new(ambient).map_err(|e| IoError::new(path, e))?;
    let mut notes = Vec::new();
    let mut line = Vec::with_capacity(256);
    let mut nv: Option<usize> = None;
    let mut verts: Vec<u32> = Vec::with_capacity(16);
    let (mut n_fanned, mut n_fan_tris) = (0u64, 0u64);
    for def in header.elements.values() {
        let kind = match def.name.as_str() {
            "vertex" => 0,
            "face" => 1,
            _ => {
                notes.push(format!(
                    "ignored element '{}' ({} records)",
                    def.name, def.count
                ));
                2
            }
        };
        if enc != Encoding::Ascii && def.properties.is_empty() {
            continue; // records of no bytes
        }
        for i in 0..def.count {
            let loc = if enc == Encoding::Ascii {
                Location::Line(rd.newlines + 1)
            } else {
                Location::Byte(rd.pos)
            };
            let here = |msg: String| IoError::parse(path, Some(loc), msg);
            match kind {
                0 => {
                    let v: VertexRec = read_record(rd, enc, def, &mut line, i, path, loc)?;
                    b.push_vertex(&v.p[..ambient])
                        .map_err(|e| IoError::new(path, e).at(loc))?;
                }
                1 => {
                    let f: FaceRec = read_record(rd, enc, def, &mut line, i, path, loc)?;
                    f.indices(&mut verts)
                        .map_err(|x| here(format!("face {i}: negative vertex index {x}")))?;
                    let k = verts.len();
                    if let Some(nv) = nv {
                        check_cell(i as u64, &verts, nv)
                            .map_err(|e| IoError::new(path, e).at(loc))?;
                    }
                    let push = |b: &mut ComplexBuilder, kind: CellKind, v: &[u32]| {
                        b.push_cell(kind, v)
                            .map_err(|e| IoError::new(path, e).at(loc))
                    };
                    match opts.polygons {
                        PolygonMode::Polygons => match k {
                            3 => push(&mut b, CellKind::Simplex(2), &verts)?,
                            4 => push(&mut b, CellKind::Quad, &verts)?,
                            k if k > 4 => {
                                for j in 1..k - 1 {
                                    push(&mut b, CellKind::Simplex(2), &[verts[0], verts[j], verts[j + 1]])?;
                                }
                                n_fanned += 1;
                                n_fan_tris += k as u64 - 2;
                                continue;
                            }
                            _ => {
                                return Err(here(format!(
                                    "face {i} has {k} vertices; a polygon needs at least 3 (read in simplices mode for lower-dimensional cells)"
                                )))
                            }
                        },
                        PolygonMode::Simplices => {
                            let kind = k
                                .checked_sub(1)
                                .and_then(CellKind::simplex)
                                .ok_or_else(|| here(format!("face {i} has {k} vertices; a simplex needs 1 to 65")))?;
                            push(&mut b, kind, &verts)?
                        }
                    };
                }
                _ => {
                    let _: Skip = read_record(rd, enc, def, &mut line, i, path, loc)?;
                }
            }
        }
        if kind == 0 {
            nv = Some(b.n_vertices());
        }
    }
    if n_fanned > 0 {
        notes.push(format!(
            "fan-triangulated {n_fanned} polygons of more than 4 vertices into {n_fan_tris} triangles"
        ));
    }
    let (complex, report) = b.build(&opts.build).map_err(|e| IoError::new(path, e))?;
    if report.dropped_duplicates > 0 {
        notes.push(format!(
            "dropped {} duplicate cells",
            report.dropped_duplicates
        ));
    }
    if report.dropped_face_cells > 0 {
        notes.push(format!(
            "dropped {} cells that are faces of other cells",
            report.dropped_face_cells
        ));
    }
    Ok(ReadResult {
        complex,
        format: Format::Ply,
        notes,
    })
}

#[allow(clippy::too_many_arguments)]
fn read_record<E: PropertyAccess, R: BufRead>(
    rd: &mut Counting<R>,
    enc: Encoding,
    def: &ElementDef,
    line: &mut Vec<u8>,
    i: usize,
    path: &Path,
    loc: Location,
) -> Result<E, IoError> {
    let p = Parser::<E>::new();
    let eof = || {
        IoError::parse(
            path,
            Some(loc),
            format!(
                "the file ends in record {i} of element '{}' (the header declares {})",
                def.name, def.count
            ),
        )
    };
    let res = match enc {
        Encoding::Ascii => {
            line.clear();
            let n = rd
                .by_ref()
                .take(64 << 20)
                .read_until(b'\n', line)
                .map_err(|e| IoError::new(path, e).at(loc))?;
            if n == 0 {
                return Err(eof());
            }
            let s = std::str::from_utf8(line).map_err(|_| {
                IoError::parse(
                    path,
                    Some(loc),
                    format!("record {i} of element '{}' is not text", def.name),
                )
            })?;
            p.read_ascii_element(s, def)
        }
        Encoding::BinaryLittleEndian => p.read_little_endian_element(rd, def),
        Encoding::BinaryBigEndian => p.read_big_endian_element(rd, def),
    };
    res.map_err(|e| {
        if e.kind() == std::io::ErrorKind::UnexpectedEof {
            eof()
        } else {
            let inner = ply_err(path, e, loc);
            let msg = match &inner.kind {
                IoErrorKind::Parse(m) => m.clone(),
                k => k.to_string(),
            };
            IoError::parse(
                path,
                Some(loc),
                format!("record {i} of element '{}': {msg}", def.name),
            )
        }
    })
}

/// Refuses complexes that a surface format (PLY, OBJ) cannot hold: anything but triangles and
/// quads, or an ambient dimension other than 2 and 3.
///
/// ```
/// use starplex::cell::CellKind;
/// use starplex::complex::IndexedComplex;
/// use starplex::io::{ply, Format};
/// let tet = IndexedComplex::from_parts(3, vec![0.0; 12].into(),
///                                      vec![(CellKind::Simplex(3), vec![0, 1, 2, 3].into())]).unwrap();
/// let e = ply::check_surface(&tet, Format::Obj).unwrap_err();
/// assert!(e.to_string().contains("a tetrahedral mesh cannot be written to OBJ"), "{e}");
/// ```
///
/// # Errors
/// [`IoErrorKind::CannotWrite`] with the reason and the formats that would hold the complex.
pub fn check_surface(k: &IndexedComplex, format: Format) -> Result<(), IoErrorKind> {
    let name = match format {
        Format::Ply => "PLY",
        Format::Obj => "OBJ",
        _ => "this format",
    };
    let fail = |reason: String| Err(IoErrorKind::CannotWrite { format, reason });
    if k.ambient_dim() < 2 || k.ambient_dim() > 3 {
        return fail(format!(
            "{name} holds points of 2 or 3 coordinates, this complex has {}: use .spx or .spb",
            k.ambient_dim()
        ));
    }
    for b in k.blocks() {
        let what = match b.kind {
            CellKind::Simplex(2) | CellKind::Quad => continue,
            CellKind::Simplex(3) => "a tetrahedral mesh",
            CellKind::Hex => "a hexahedral mesh",
            CellKind::Prism => "a mesh with prisms",
            CellKind::Pyramid => "a mesh with pyramids",
            CellKind::Simplex(1) => "a complex with edges as top cells",
            CellKind::Simplex(0) => "a complex with vertices as top cells",
            CellKind::Simplex(d) => {
                return fail(format!(
                "a complex with {d}-simplices cannot be written to {name}: use .spx, .spb or .off"
            ))
            }
        };
        let alt = if b.kind.dim() == 3 {
            ".mesh, .vtk, .msh, .spx or .spb (or write its surface with --boundary)"
        } else {
            ".spx, .spb, .vtk or .msh"
        };
        return fail(format!("{what} cannot be written to {name}: use {alt}"));
    }
    Ok(())
}

/// Writes `k` as binary little-endian PLY.
///
/// ```
/// use starplex::io::{ply, ReadOptions};
/// use starplex::complex::{ComplexBuilder, BuildOptions};
/// use starplex::cell::CellKind;
/// let mut b = ComplexBuilder::new(3).unwrap();
/// for p in [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.1, 0.7, 0.3]] {
///     b.push_vertex(&p).unwrap();
/// }
/// b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// let (k, _) = b.build(&BuildOptions::default()).unwrap();
/// let mut out = Vec::new();
/// ply::write(&mut out, &k).unwrap();
/// let back = ply::read_from(&out[..], out.len() as u64, "m.ply".as_ref(), &ReadOptions::default());
/// assert_eq!(back.unwrap().complex, k);
/// ```
///
/// # Errors
/// See [`write_with`].
pub fn write(w: &mut dyn Write, k: &IndexedComplex) -> Result<(), IoErrorKind> {
    write_with(w, k, PlyEncoding::BinaryLittleEndian)
}

/// Writes `k` as PLY with the given encoding: `double` coordinates, one `face` per triangle or
/// quad.
///
/// ```
/// use starplex::io::{ply, IoErrorKind};
/// use starplex::complex::{ComplexBuilder, BuildOptions};
/// use starplex::cell::CellKind;
/// let mut b = ComplexBuilder::new(3).unwrap();
/// for p in [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]] {
///     b.push_vertex(&p).unwrap();
/// }
/// b.push_cell(CellKind::Simplex(3), &[0, 1, 2, 3]).unwrap();
/// let (k, _) = b.build(&BuildOptions::default()).unwrap();
/// let e = ply::write_with(&mut Vec::new(), &k, ply::PlyEncoding::Ascii).unwrap_err();
/// assert!(matches!(e, IoErrorKind::CannotWrite { .. }));
/// assert!(e.to_string().contains("a tetrahedral mesh cannot be written to PLY"));
/// ```
///
/// # Errors
/// [`IoErrorKind::CannotWrite`] for cells other than triangles and quads or an ambient dimension
/// other than 2 or 3; OS errors of the writer.
pub fn write_with(
    w: &mut dyn Write,
    k: &IndexedComplex,
    enc: PlyEncoding,
) -> Result<(), IoErrorKind> {
    check_surface(k, Format::Ply)?;
    let d = k.ambient_dim();
    let idx_t = if k.n_vertices() > i32::MAX as usize {
        "uint"
    } else {
        "int"
    };
    let mut h = String::new();
    h.push_str("ply\n");
    h.push_str(match enc {
        PlyEncoding::Ascii => "format ascii 1.0\n",
        PlyEncoding::BinaryLittleEndian => "format binary_little_endian 1.0\n",
    });
    h.push_str(&format!(
        "comment written by starplex {}\n",
        env!("CARGO_PKG_VERSION")
    ));
    h.push_str(&format!("element vertex {}\n", k.n_vertices()));
    for a in &["x", "y", "z"][..d] {
        h.push_str(&format!("property double {a}\n"));
    }
    h.push_str(&format!("element face {}\n", k.n_cells()));
    h.push_str(&format!(
        "property list uchar {idx_t} vertex_indices\nend_header\n"
    ));
    w.write_all(h.as_bytes())?;
    match enc {
        PlyEncoding::Ascii => {
            for p in k.coords().chunks_exact(d) {
                for (i, &x) in p.iter().enumerate() {
                    if i > 0 {
                        w.write_all(b" ")?;
                    }
                    write_f64(w, x)?;
                }
                w.write_all(b"\n")?;
            }
            let mut s = String::with_capacity(64);
            for b in k.blocks() {
                for i in 0..b.len() {
                    use std::fmt::Write as _;
                    s.clear();
                    let c = b.cell(i);
                    let _ = write!(s, "{}", c.len());
                    for v in c {
                        let _ = write!(s, " {v}");
                    }
                    s.push('\n');
                    w.write_all(s.as_bytes())?;
                }
            }
        }
        PlyEncoding::BinaryLittleEndian => {
            let mut buf: Vec<u8> = Vec::with_capacity(1 << 16);
            for &x in k.coords() {
                buf.extend_from_slice(&x.to_le_bytes());
                if buf.len() >= 1 << 16 {
                    w.write_all(&buf)?;
                    buf.clear();
                }
            }
            for b in k.blocks() {
                for i in 0..b.len() {
                    let c = b.cell(i);
                    buf.push(c.len() as u8);
                    for &v in c {
                        buf.extend_from_slice(&v.to_le_bytes());
                    }
                    if buf.len() >= 1 << 16 {
                        w.write_all(&buf)?;
                        buf.clear();
                    }
                }
            }
            w.write_all(&buf)?;
        }
    }
    Ok(())
}
