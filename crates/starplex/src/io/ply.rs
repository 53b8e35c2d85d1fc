//! PLY (Stanford polygon file), ascii and binary, read through the `ply-rs-bw` parser.
//!
//! Reading: the `vertex` element's `x`, `y` (and `z` when present; without it the complex is 2D)
//! of any scalar type become the coordinates; the `face` element's `vertex_indices` (or
//! `vertex_index`) list of any integer type becomes the cells, following [`PolygonMode`](super::PolygonMode): with
//! `Polygons` a face of 3 vertices is a triangle, 4 a quad, more are fan-triangulated (counted in
//! [`ReadResult::notes`]); with `Simplices` a face of `k` vertices is a `(k-1)`-simplex. An `edge`
//! element with integer `vertex1` and `vertex2` properties gives edges (1-simplices), as OBJ `l`
//! lines do. Other elements (`material`, ...) are read past and noted.
//!
//! Attributes: every other scalar property of the `vertex` element (`nx`, `red`, `quality`, ...)
//! is a vertex [attribute](crate::attr) of that name, every other scalar property of the `face`
//! and `edge` elements a cell attribute (one item per cell; the triangles of a fanned polygon
//! share its values); integer types give [`AttrValues::Int`], `float`/`double` give
//! [`AttrValues::Float`]. One rule groups properties: a run of consecutive properties
//! `{base}_0`, `{base}_1`, ..., `{base}_{k-1}` (k >= 2, one type, `base` not itself a property)
//! is one column `base` of `k` components (what the writer writes for a vector column); `nx ny
//! nz` or `red green blue` stay separate columns, as in the file. A property of the `face`
//! element that the `edge` element lacks (or the reverse) is 0 (integer) or NaN (float) on the
//! other element's cells, with a note. List properties other than the indices are ignored
//! (noted).
//!
//! Before the payload is parsed, the counts declared in the header are compared with the bytes
//! that follow it (every record needs a minimum number of bytes), so a header declaring 10^12
//! vertices is an error, not an allocation. Errors carry the line (ascii, header) or byte offset
//! (binary payload). Cell ids in index errors are the face's position in the file.
//!
//! Writing: triangles and quads as `face`s, edges as `edge`s (`binary_little_endian` by
//! default, `ascii` with [`write_with`]); coordinates as `double` so a round trip is exact.
//! Vertex attributes are written as extra `vertex` properties and cell attributes as extra
//! properties of both `face` (after `vertex_indices`) and `edge` (after `vertex1 vertex2`): integers as `uchar` when every value is in 0..=255 (so `red green blue`
//! stay colours for other tools), else `int` or `uint`, floats as `double`; a column of `k > 1`
//! components as `{name}_0` .. `{name}_{k-1}`. Columns PLY cannot hold are left out ([`dropped`]
//! names them): integers beyond 32 bits, NaN or infinite floats in ascii, names that are not one
//! word or that clash (`x`, `vertex_indices`, `vertex1`, another column's property).
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
    BeginList, ElementDef, Encoding, Header, PropertyAccess, PropertyAccessResult, PropertyType,
    ScalarType,
};

use super::faces::{push_build_notes, FaceError, Faces};
use super::text::write_f64;
use super::{Format, IoError, IoErrorKind, Location, ReadOptions, ReadResult};
use crate::attr::{AttrTarget, AttrValues, Attribute, Attributes};
use crate::cell::CellKind;
use crate::complex::{ComplexBuilder, IndexedComplex};

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

/// Extra scalar values of one record (every PLY scalar type is exact as `f64`), in header order.
type Extras = smallvec::SmallVec<[f64; 8]>;

/// One vertex record: the coordinates found so far and the other scalar properties, in header
/// order.
struct VertexRec {
    p: [f64; 3],
    extra: Extras,
}

impl VertexRec {
    #[inline]
    fn set(&mut self, name: &str, v: f64) -> PropertyAccessResult {
        let axis = match name {
            "x" => 0,
            "y" => 1,
            "z" => 2,
            _ => {
                self.extra.push(v);
                return PropertyAccessResult::Set;
            }
        };
        self.p[axis] = v;
        PropertyAccessResult::Set
    }
}

/// The scalar setters of a record type, all through its `set(name, f64)`.
macro_rules! scalar_setters {
    () => {
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
    };
}

impl PropertyAccess for VertexRec {
    fn new() -> Self {
        VertexRec {
            p: [0.0; 3],
            extra: Extras::new(),
        }
    }
    scalar_setters!();
}

/// One face record: its vertex index list, in whichever integer type the file declares, and
/// its other scalar properties in header order.
#[derive(Default)]
struct FaceRec {
    i8s: Vec<i8>,
    u8s: Vec<u8>,
    i16s: Vec<i16>,
    u16s: Vec<u16>,
    i32s: Vec<i32>,
    u32s: Vec<u32>,
    extra: Extras,
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

    #[inline]
    fn set(&mut self, _name: &str, v: f64) -> PropertyAccessResult {
        self.extra.push(v);
        PropertyAccessResult::Set
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
    scalar_setters!();
}

/// One `edge` record: `vertex1`, `vertex2` and the other scalar properties in header order.
struct EdgeRec {
    v: [f64; 2],
    extra: Extras,
}

impl EdgeRec {
    #[inline]
    fn set(&mut self, name: &str, v: f64) -> PropertyAccessResult {
        match name {
            "vertex1" => self.v[0] = v,
            "vertex2" => self.v[1] = v,
            _ => self.extra.push(v),
        }
        PropertyAccessResult::Set
    }
}

impl PropertyAccess for EdgeRec {
    fn new() -> Self {
        EdgeRec {
            v: [0.0; 2],
            extra: Extras::new(),
        }
    }
    scalar_setters!();
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
    let hdr_err = |msg: String| IoError::parse(path, Some(Location::Line(rd.newlines)), msg);
    let ambient = check_header(&header, len.saturating_sub(rd.pos)).map_err(hdr_err)?;
    let mut notes = Vec::new();
    let mut rec = Records::new(&header, ambient, path, &mut notes)?;
    for def in header.elements.values() {
        rec.read_element(rd, header.encoding, def, opts, &mut notes)?;
    }
    rec.finish(&header, opts, notes)
}

/// The checks of a header before any record is read: the declared counts against the
/// `remaining` bytes, a `vertex` element with scalar `x` and `y` (its count within 32-bit ids),
/// one integer index list on `face`. Returns the ambient dimension (3 when `z` is present);
/// the error is the message.
fn check_header(header: &Header, remaining: u64) -> Result<usize, String> {
    let enc = header.encoding;
    let mut need: u128 = 0;
    for def in header.elements.values() {
        let one = min_record_bytes(def, enc) as u128;
        need += one * def.count as u128;
        if need > remaining as u128 {
            return Err(format!(
                "element '{}' declares {} records, which need at least {} bytes, but only {} bytes follow the header (truncated file or corrupt header)",
                def.name,
                def.count,
                one * def.count as u128,
                remaining
            ));
        }
    }
    let Some(vdef) = header.elements.get("vertex") else {
        return Err("no 'vertex' element in the header".into());
    };
    let mut has_axis = [false; 3];
    for (i, a) in ["x", "y", "z"].iter().enumerate() {
        if let Some(p) = vdef.properties.get(*a) {
            if !matches!(p.data_type, PropertyType::Scalar(_)) {
                return Err(format!(
                    "vertex property '{a}' is a list, expected a number"
                ));
            }
            has_axis[i] = true;
        }
    }
    if !has_axis[0] || !has_axis[1] {
        return Err("the 'vertex' element has no 'x' and 'y' properties".into());
    }
    let ambient = if has_axis[2] { 3 } else { 2 };
    if vdef.count >= u32::MAX as usize {
        return Err(format!(
            "{} vertices exceed the 32-bit id limit of starplex",
            vdef.count
        ));
    }
    if let Some(fdef) = header.elements.get("face") {
        let idx: Vec<_> = fdef
            .properties
            .values()
            .filter(|p| is_index_name(&p.name))
            .collect();
        match idx.as_slice() {
            [] => {
                return Err(
                    "the 'face' element has no 'vertex_indices' (or 'vertex_index') property"
                        .into(),
                );
            }
            [p] => match &p.data_type {
                PropertyType::List(_, t) if is_int(t) => {}
                t => {
                    return Err(format!(
                        "face property '{}' has type {t:?}; expected a list of integers",
                        p.name
                    ));
                }
            },
            _ => {
                return Err(
                    "the 'face' element has both 'vertex_indices' and 'vertex_index'".into(),
                );
            }
        }
    }
    Ok(ambient)
}

/// The attribute columns of a PLY file: one column of values per extra vertex property; the
/// cell columns are the union (by name) of the face and edge properties, `cmaps[m]` placing
/// the extra values of element `m` (0 face, 1 edge) in them.
struct Columns {
    vprops: Vec<(String, bool)>,
    vcols: Vec<Vec<f64>>,
    cprops: Vec<(String, bool)>,
    cmaps: [Vec<usize>; 2],
    ccols: Vec<Vec<f64>>,
}

impl Columns {
    fn new(
        header: &Header,
        vdef: &ElementDef,
        edge_def: Option<&ElementDef>,
        notes: &mut Vec<String>,
    ) -> Columns {
        let vprops = extra_props(vdef, |n| matches!(n, "x" | "y" | "z"), notes);
        let vcols: Vec<Vec<f64>> = vec![Vec::new(); vprops.len()];
        let mut cprops: Vec<(String, bool)> = Vec::new();
        let mut cmaps: [Vec<usize>; 2] = [Vec::new(), Vec::new()];
        for (m, def) in [header.elements.get("face"), edge_def]
            .into_iter()
            .enumerate()
        {
            let Some(def) = def else { continue };
            let props = if m == 0 {
                extra_props(def, is_index_name, notes)
            } else {
                extra_props(def, |n| n == "vertex1" || n == "vertex2", notes)
            };
            for (name, is_int) in props {
                let at = match cprops.iter().position(|(n, _)| *n == name) {
                    Some(at) => {
                        cprops[at].1 &= is_int;
                        at
                    }
                    None => {
                        cprops.push((name, is_int));
                        cprops.len() - 1
                    }
                };
                cmaps[m].push(at);
            }
        }
        let ccols: Vec<Vec<f64>> = vec![Vec::new(); cprops.len()];
        Columns {
            vprops,
            vcols,
            cprops,
            cmaps,
            ccols,
        }
    }

    /// One row of cell values from the extra values of element `m` (fill values where the
    /// element has no such property).
    fn push_row(&mut self, m: usize, extra: &[f64]) {
        for (c, (_, is_int)) in self.ccols.iter_mut().zip(&self.cprops) {
            c.push(if *is_int { 0.0 } else { f64::NAN });
        }
        for (&c, &v) in self.cmaps[m].iter().zip(extra) {
            if let Some(last) = self.ccols[c].last_mut() {
                *last = v;
            }
        }
    }
}

/// The state of the payload pass: the builder, the polygon splitter, the attribute columns and
/// scratch buffers.
struct Records<'a> {
    path: &'a Path,
    b: ComplexBuilder,
    ambient: usize,
    /// The number of vertices, once the `vertex` element is read (indices are checked then).
    nv: Option<usize>,
    verts: Vec<u32>,
    line: Vec<u8>,
    faces: Faces,
    cols: Columns,
    edge_def: Option<&'a ElementDef>,
    n_edges: u64,
}

impl<'a> Records<'a> {
    fn new(
        header: &'a Header,
        ambient: usize,
        path: &'a Path,
        notes: &mut Vec<String>,
    ) -> Result<Records<'a>, IoError> {
        let b = ComplexBuilder::new(ambient).map_err(|e| IoError::new(path, e))?;
        let edge_def = header
            .elements
            .get("edge")
            .filter(|d| is_edge_def(d) && d.count > 0);
        // checked by check_header
        let vdef = header
            .elements
            .get("vertex")
            .ok_or_else(|| IoError::parse(path, None, "no 'vertex' element in the header"))?;
        let cols = Columns::new(header, vdef, edge_def, notes);
        Ok(Records {
            path,
            b,
            ambient,
            nv: None,
            verts: Vec::with_capacity(16),
            line: Vec::with_capacity(256),
            faces: Faces::default(),
            cols,
            edge_def,
            n_edges: 0,
        })
    }

    /// Reads every record of one element (vertices, faces, edges; others are read past and
    /// noted).
    fn read_element<R: BufRead>(
        &mut self,
        rd: &mut Counting<R>,
        enc: Encoding,
        def: &ElementDef,
        opts: &ReadOptions,
        notes: &mut Vec<String>,
    ) -> Result<(), IoError> {
        let kind = match def.name.as_str() {
            "vertex" => 0,
            "face" => 1,
            "edge" if self.edge_def.is_some() => 3,
            _ => {
                notes.push(format!(
                    "ignored element '{}' ({} records)",
                    def.name, def.count
                ));
                2
            }
        };
        if enc != Encoding::Ascii && def.properties.is_empty() {
            return Ok(()); // records of no bytes
        }
        for i in 0..def.count {
            let loc = if enc == Encoding::Ascii {
                Location::Line(rd.newlines + 1)
            } else {
                Location::Byte(rd.pos)
            };
            match kind {
                0 => {
                    let v: VertexRec =
                        read_record(rd, enc, def, &mut self.line, i, self.path, loc)?;
                    self.vertex(v, loc)?;
                }
                1 => {
                    let f: FaceRec = read_record(rd, enc, def, &mut self.line, i, self.path, loc)?;
                    self.face(f, i, loc, opts)?;
                }
                3 => {
                    let e: EdgeRec = read_record(rd, enc, def, &mut self.line, i, self.path, loc)?;
                    self.edge(e, i, loc, opts)?;
                }
                _ => {
                    let _: Skip = read_record(rd, enc, def, &mut self.line, i, self.path, loc)?;
                }
            }
        }
        if kind == 0 {
            self.nv = Some(self.b.n_vertices());
        }
        Ok(())
    }

    fn vertex(&mut self, v: VertexRec, loc: Location) -> Result<(), IoError> {
        self.b
            .push_vertex(&v.p[..self.ambient])
            .map_err(|e| IoError::new(self.path, e).at(loc))?;
        for (c, &x) in self.cols.vcols.iter_mut().zip(&v.extra) {
            c.push(x);
        }
        Ok(())
    }

    fn face(
        &mut self,
        f: FaceRec,
        i: usize,
        loc: Location,
        opts: &ReadOptions,
    ) -> Result<(), IoError> {
        let path = self.path;
        let here = |msg: String| IoError::parse(path, Some(loc), msg);
        f.indices(&mut self.verts)
            .map_err(|x| here(format!("face {i}: negative vertex index {x}")))?;
        if let Some(nv) = self.nv {
            opts.build
                .check_cell(i as u64, &self.verts, nv)
                .map_err(|e| IoError::new(path, e).at(loc))?;
        }
        let rows = self
            .faces
            .push(&mut self.b, opts.polygons, &self.verts)
            .map_err(|e| match e {
                FaceError::Complex(e) => IoError::new(path, e).at(loc),
                FaceError::TooFew(k) => here(format!(
                    "face {i} has {k} vertices; a polygon needs at least 3 (read in simplices mode for lower-dimensional cells)"
                )),
                FaceError::NotSimplex(k) => {
                    here(format!("face {i} has {k} vertices; a simplex needs 1 to 65"))
                }
            })?;
        if !self.cols.ccols.is_empty() {
            for _ in 0..rows {
                self.cols.push_row(0, &f.extra);
            }
        }
        Ok(())
    }

    fn edge(
        &mut self,
        e: EdgeRec,
        i: usize,
        loc: Location,
        opts: &ReadOptions,
    ) -> Result<(), IoError> {
        let path = self.path;
        self.verts.clear();
        for x in e.v {
            // integer types only (checked by is_edge_def): exact in f64
            if x < 0.0 {
                return Err(IoError::parse(
                    path,
                    Some(loc),
                    format!("edge {i}: negative vertex index {x}"),
                ));
            }
            self.verts.push(x as u32);
        }
        if let Some(nv) = self.nv {
            opts.build
                .check_cell(i as u64, &self.verts, nv)
                .map_err(|e| IoError::new(path, e).at(loc))?;
        }
        self.b
            .push_cell(CellKind::Simplex(1), &self.verts)
            .map_err(|e| IoError::new(path, e).at(loc))?;
        if !self.cols.ccols.is_empty() {
            self.cols.push_row(1, &e.extra);
        }
        self.n_edges += 1;
        Ok(())
    }

    /// The notes of the pass, the attributes, and the build of the complex.
    fn finish(
        mut self,
        header: &Header,
        opts: &ReadOptions,
        mut notes: Vec<String>,
    ) -> Result<ReadResult, IoError> {
        self.faces.note(&mut notes);
        let cols = self.cols;
        let has_faces = header.elements.get("face").is_some_and(|d| d.count > 0);
        if self.n_edges > 0 && has_faces && cols.cmaps.iter().any(|m| m.len() < cols.cprops.len()) {
            notes.push("the 'face' and 'edge' elements do not have the same properties: the values a cell lacks are 0 (integer columns) or NaN (float columns)".into());
        }
        self.b.set_attributes(Attributes {
            vertex: group_columns(&cols.vprops, cols.vcols),
            cell: group_columns(&cols.cprops, cols.ccols),
        });
        let (complex, report) = self
            .b
            .build(&opts.build)
            .map_err(|e| IoError::new(self.path, e))?;
        push_build_notes(&mut notes, &report);
        Ok(ReadResult {
            complex,
            format: Format::Ply,
            notes,
        })
    }
}

/// Whether an `edge` element can be read as edges: integer `vertex1` and `vertex2`.
fn is_edge_def(def: &ElementDef) -> bool {
    ["vertex1", "vertex2"].iter().all(|n| {
        def.properties
            .get(*n)
            .is_some_and(|p| matches!(&p.data_type, PropertyType::Scalar(t) if is_int(t)))
    })
}

/// The scalar properties of `def` other than those `used` names, in header order, with whether
/// their type is an integer; list properties other than the used ones are noted as ignored.
fn extra_props(
    def: &ElementDef,
    used: impl Fn(&str) -> bool,
    notes: &mut Vec<String>,
) -> Vec<(String, bool)> {
    let mut out = Vec::new();
    for p in def.properties.values() {
        if used(&p.name) {
            continue;
        }
        match &p.data_type {
            PropertyType::Scalar(t) => out.push((p.name.clone(), is_int(t))),
            PropertyType::List(..) => notes.push(format!(
                "ignored list property '{}' of element '{}'",
                p.name, def.name
            )),
        }
    }
    out
}

/// Where the run of properties `{base}_0`, `{base}_1`, ... starting at `props[i]` ends (the
/// index after it), when it has at least 2 of one type and `base` names no other property.
fn component_run(props: &[(String, bool)], i: usize) -> Option<(&str, usize)> {
    let base = props[i].0.strip_suffix("_0")?;
    if base.is_empty() || props.iter().any(|(n, _)| n == base) {
        return None;
    }
    let mut j = i + 1;
    while j < props.len()
        && props[j].1 == props[i].1
        && props[j]
            .0
            .strip_prefix(base)
            .and_then(|r| r.strip_prefix('_'))
            == Some((j - i).to_string().as_str())
    {
        j += 1;
    }
    (j - i >= 2).then_some((base, j))
}

/// The attribute columns of properties `props` (name, integer type) whose values are `cols`
/// (one value per item each): one column per property, except that a run of properties
/// `{base}_0`, `{base}_1`, ... `{base}_{k-1}` (k >= 2, consecutive, of one type, `base` not a
/// property itself) is one column `base` of `k` components, as the writer writes them.
fn group_columns(props: &[(String, bool)], cols: Vec<Vec<f64>>) -> Vec<Attribute> {
    let mut out = Vec::new();
    let mut i = 0;
    while i < props.len() {
        let (name, end) = match component_run(props, i) {
            Some((base, end)) => (base.to_string(), end),
            None => (props[i].0.clone(), i + 1),
        };
        let c = end - i;
        let n = cols[i].len();
        let mut flat = Vec::with_capacity(n * c);
        for item in 0..n {
            for col in &cols[i..end] {
                flat.push(col.get(item).copied().unwrap_or(f64::NAN));
            }
        }
        out.push(if props[i].1 {
            Attribute::int(name, c, flat.into_iter().map(|x| x as i64).collect())
        } else {
            Attribute::float(name, c, flat)
        });
        i = end;
    }
    out
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

/// Refuses complexes that a surface format (PLY, OBJ) cannot hold: anything but triangles,
/// quads and (PLY only, as its `edge` element) edges, or an ambient dimension other than 2
/// and 3.
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
            CellKind::Simplex(1) if format == Format::Ply => continue,
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
            ".mesh, .vtk, .msh, .spx or .spb (or write its boundary surface)"
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
/// quad, one `edge` (`vertex1`, `vertex2`) per edge, the cell attributes on both elements. The
/// element of the first cell comes first, so a reader gives back the cells in the same order
/// when `k` lists all its faces before its edges or all its edges before its faces; otherwise
/// the cells come back grouped by element, each in its order in `k`.
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
    let attrs = k.attributes();
    let vcols = plan_columns(&attrs.vertex, &["x", "y", "z"], enc);
    let ccols = plan_columns(&attrs.cell, CELL_RESERVED, enc);
    let is_edge = |b: &&crate::complex::CellBlock| b.kind == CellKind::Simplex(1);
    let n_edges: usize = k.blocks().iter().filter(is_edge).map(|b| b.len()).sum();
    let n_faces = k.n_cells() - n_edges;
    // the element of the first cell first, so that a complex listing its edges before its
    // faces (or only one of them) reads back in the same cell order
    let edges_first = k.blocks().first().is_some_and(|b| is_edge(&b));
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
    let props = |h: &mut String, cols: &[PlyColumn<'_>]| {
        for c in cols {
            for n in &c.names {
                h.push_str(&format!("property {} {n}\n", c.ty.name()));
            }
        }
    };
    props(&mut h, &vcols);
    let elements: &[bool] = match (n_edges > 0, edges_first) {
        (false, _) => &[false],
        (true, true) => &[true, false],
        (true, false) => &[false, true],
    };
    for &edges in elements {
        if edges {
            h.push_str(&format!("element edge {n_edges}\n"));
            h.push_str(&format!(
                "property {idx_t} vertex1\nproperty {idx_t} vertex2\n"
            ));
        } else if n_faces > 0 || n_edges == 0 {
            h.push_str(&format!("element face {n_faces}\n"));
            h.push_str(&format!("property list uchar {idx_t} vertex_indices\n"));
        } else {
            continue;
        }
        props(&mut h, &ccols);
    }
    h.push_str("end_header\n");
    w.write_all(h.as_bytes())?;
    // the cells of each element, in cell order
    let cells_of = |edges: bool| {
        k.blocks()
            .iter()
            .filter(move |b| is_edge(b) == edges)
            .flat_map(|b| (0..b.len()).map(move |i| (b.first as usize + i, b.cell(i))))
    };
    match enc {
        PlyEncoding::Ascii => {
            let mut s = Vec::with_capacity(256);
            for (i, p) in k.coords().chunks_exact(d).enumerate() {
                s.clear();
                for (j, &x) in p.iter().enumerate() {
                    if j > 0 {
                        s.push(b' ');
                    }
                    write_f64(&mut s, x)?;
                }
                ascii_values(&mut s, &vcols, i)?;
                s.push(b'\n');
                w.write_all(&s)?;
            }
            for &edges in elements {
                for (id, c) in cells_of(edges) {
                    use std::io::Write as _;
                    s.clear();
                    if edges {
                        write!(s, "{} {}", c[0], c[1])?;
                    } else {
                        write!(s, "{}", c.len())?;
                        for v in c {
                            write!(s, " {v}")?;
                        }
                    }
                    ascii_values(&mut s, &ccols, id)?;
                    s.push(b'\n');
                    w.write_all(&s)?;
                }
            }
        }
        PlyEncoding::BinaryLittleEndian => {
            let mut buf: Vec<u8> = Vec::with_capacity(1 << 16);
            for (i, p) in k.coords().chunks_exact(d).enumerate() {
                for &x in p {
                    buf.extend_from_slice(&x.to_le_bytes());
                }
                binary_values(&mut buf, &vcols, i);
                if buf.len() >= 1 << 16 {
                    w.write_all(&buf)?;
                    buf.clear();
                }
            }
            for &edges in elements {
                for (id, c) in cells_of(edges) {
                    if !edges {
                        buf.push(c.len() as u8);
                    }
                    for &v in c {
                        buf.extend_from_slice(&v.to_le_bytes());
                    }
                    binary_values(&mut buf, &ccols, id);
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

/// Property names of the `face` and `edge` elements that cell columns cannot take.
const CELL_RESERVED: &[&str] = &["vertex_indices", "vertex_index", "vertex1", "vertex2"];

/// The PLY type an attribute column is written as.
#[derive(Clone, Copy, Debug, PartialEq)]
enum PlyType {
    UChar,
    Int,
    UInt,
    Double,
}

impl PlyType {
    fn name(self) -> &'static str {
        match self {
            PlyType::UChar => "uchar",
            PlyType::Int => "int",
            PlyType::UInt => "uint",
            PlyType::Double => "double",
        }
    }
}

/// How an attribute column is written: its properties and their type.
struct PlyColumn<'a> {
    attr: &'a Attribute,
    names: Vec<String>,
    ty: PlyType,
}

/// The type that holds every value of `a` in `enc` (`None` when none does: integers outside
/// the 32-bit range; NaN or infinite values in ascii, whose number grammar has neither).
fn column_type(a: &Attribute, enc: PlyEncoding) -> Option<PlyType> {
    match &a.values {
        AttrValues::Int(v) => {
            let (lo, hi) = (
                v.iter().copied().min().unwrap_or(0),
                v.iter().copied().max().unwrap_or(0),
            );
            if lo >= 0 && hi <= 255 {
                Some(PlyType::UChar)
            } else if lo >= i32::MIN as i64 && hi <= i32::MAX as i64 {
                Some(PlyType::Int)
            } else if lo >= 0 && hi <= u32::MAX as i64 {
                Some(PlyType::UInt)
            } else {
                None
            }
        }
        AttrValues::Float(v) => (enc == PlyEncoding::BinaryLittleEndian
            || v.iter().all(|x| x.is_finite()))
        .then_some(PlyType::Double),
    }
}

/// The columns of `cols` that PLY holds, with their property names: a scalar column is the
/// property of its name, a column of `k > 1` components the properties `{name}_0` ..
/// `{name}_{k-1}` (which the reader groups back). A column is left out when its name is not
/// one PLY word (empty, blank or non-ASCII characters), one of its property names is `reserved`
/// or taken by an earlier column, its values fit no PLY type ([`column_type`]), or the reader
/// would not group its properties back into it.
fn plan_columns<'a>(
    cols: &'a [Attribute],
    reserved: &[&str],
    enc: PlyEncoding,
) -> Vec<PlyColumn<'a>> {
    let mut out: Vec<PlyColumn<'a>> = Vec::new();
    for a in cols {
        if a.name.is_empty() || !a.name.bytes().all(|c| c.is_ascii_graphic()) || a.components == 0 {
            continue;
        }
        let Some(ty) = column_type(a, enc) else {
            continue;
        };
        let names: Vec<String> = if a.components == 1 {
            vec![a.name.clone()]
        } else {
            (0..a.components)
                .map(|i| format!("{}_{i}", a.name))
                .collect()
        };
        let taken =
            |n: &String| reserved.contains(&n.as_str()) || out.iter().any(|c| c.names.contains(n));
        if names.iter().any(taken) {
            continue;
        }
        out.push(PlyColumn { attr: a, names, ty });
    }
    // keep only the columns the reader's grouping gives back (drop the first that it does not,
    // then look again)
    loop {
        let props: Vec<(String, bool)> = out
            .iter()
            .flat_map(|c| {
                c.names
                    .iter()
                    .map(move |n| (n.clone(), c.ty != PlyType::Double))
            })
            .collect();
        let mut start = 0;
        let mut bad = None;
        for (ci, c) in out.iter().enumerate() {
            let end = component_run(&props, start).map(|(_, e)| e);
            let ok = if c.names.len() == 1 {
                end.is_none()
            } else {
                end == Some(start + c.names.len())
            };
            if !ok {
                bad = Some(ci);
                break;
            }
            start += c.names.len();
        }
        match bad {
            Some(ci) => {
                out.remove(ci);
            }
            None => return out,
        }
    }
}

/// The attributes of `a` that PLY written with `enc` does not hold (`kind name`, as
/// [`Format::dropped_attributes`]); see [`write_with`] for the rules.
///
/// ```
/// use starplex::attr::{Attribute, Attributes};
/// use starplex::io::ply::{dropped, PlyEncoding};
/// let a = Attributes {
///     vertex: vec![Attribute::float("quality", 1, vec![f64::NAN]), Attribute::int("x", 1, vec![1])],
///     cell: vec![Attribute::int("big", 1, vec![1 << 40]), Attribute::float("normal", 3, vec![0.0; 3])],
/// };
/// assert_eq!(dropped(&a, PlyEncoding::BinaryLittleEndian), ["vertex x", "cell big"]);
/// assert_eq!(dropped(&a, PlyEncoding::Ascii), ["vertex quality", "vertex x", "cell big"]);
/// ```
pub fn dropped(a: &Attributes, enc: PlyEncoding) -> Vec<String> {
    let mut out = Vec::new();
    for (target, cols, reserved) in [
        (AttrTarget::Vertex, &a.vertex, &["x", "y", "z"][..]),
        (AttrTarget::Cell, &a.cell, CELL_RESERVED),
    ] {
        let kept = plan_columns(cols, reserved, enc);
        for c in cols {
            if !kept.iter().any(|k| std::ptr::eq(k.attr, c)) {
                out.push(format!("{target} {}", c.name));
            }
        }
    }
    out
}

/// Appends the values of item `i` of every column, as ascii (` v` each).
fn ascii_values(s: &mut Vec<u8>, cols: &[PlyColumn<'_>], i: usize) -> std::io::Result<()> {
    for c in cols {
        let n = c.names.len();
        for j in i * n..(i + 1) * n {
            s.push(b' ');
            match &c.attr.values {
                AttrValues::Int(v) => {
                    use std::io::Write as _;
                    write!(s, "{}", v[j])?
                }
                AttrValues::Float(v) => write_f64(s, v[j])?,
            }
        }
    }
    Ok(())
}

/// Appends the values of item `i` of every column, little-endian in the column's type.
fn binary_values(buf: &mut Vec<u8>, cols: &[PlyColumn<'_>], i: usize) {
    for c in cols {
        let n = c.names.len();
        for j in i * n..(i + 1) * n {
            match (&c.attr.values, c.ty) {
                (AttrValues::Int(v), PlyType::UChar) => buf.push(v[j] as u8),
                (AttrValues::Int(v), PlyType::Int) => {
                    buf.extend_from_slice(&(v[j] as i32).to_le_bytes())
                }
                (AttrValues::Int(v), PlyType::UInt) => {
                    buf.extend_from_slice(&(v[j] as u32).to_le_bytes())
                }
                (AttrValues::Int(v), PlyType::Double) => {
                    buf.extend_from_slice(&(v[j] as f64).to_le_bytes())
                }
                (AttrValues::Float(v), _) => buf.extend_from_slice(&v[j].to_le_bytes()),
            }
        }
    }
}
