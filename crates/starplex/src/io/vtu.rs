//! VTK XML: `.vtu` (unstructured grid) and `.vtp` (poly data), read and written.
//!
//! The reader takes what VTK, ParaView and meshio write: `ascii`, inline `binary` (base64) and
//! `appended` data (`raw` or `base64`), with or without zlib compression, `UInt32` or `UInt64`
//! headers, either byte order, several `Piece`s (concatenated, their point ids shifted). Cells:
//! - unstructured grids: VTK cell types 1–14 (vertex and poly-vertex cells are dropped, their points
//!   stay as vertices; poly-lines become edges, triangle strips triangles, polygons triangles or
//!   quads like OFF faces, pixels and voxels quads and hexahedra in starplex's corner order);
//! - poly data: `Verts` (dropped as above), `Lines`, `Strips` and `Polys`.
//!
//! Point and cell data arrays become vertex and cell [attributes](crate::attr) (integers stay
//! integers; the cells a file cell was split into share its values).
//! Whatever changed is said in the notes. The parser is `quick-xml` on the XML part of the file;
//! raw appended data (not XML) is addressed by its offsets.
//!
//! The writer writes `.vtu` (every cell kind VTK has: simplices up to tetrahedra, quads, hexahedra,
//! prisms, pyramids) and `.vtp` (points, edges, triangles, quads), with little-endian raw appended
//! data and `UInt64` headers: compact, exact (coordinates as `Float64`) and read by VTK, ParaView
//! and meshio.
//!
//! ```
//! use starplex::cell::CellKind;
//! use starplex::complex::IndexedComplex;
//! use starplex::io::{vtu, ReadOptions};
//! let tet = IndexedComplex::from_parts(3, vec![0., 0., 0., 1., 0., 0., 0., 1., 0., 0., 0., 1.].into(),
//!     vec![(CellKind::Simplex(3), vec![0, 1, 2, 3].into())]).unwrap();
//! let mut out = Vec::new();
//! vtu::write_vtu(&mut out, &tet).unwrap();
//! let back = vtu::read_bytes(&out, "t.vtu".as_ref(), &ReadOptions::default()).unwrap();
//! assert_eq!(back.complex, tet);
//! // an ascii file as another tool writes it
//! let xml = r#"<?xml version="1.0"?>
//! <VTKFile type="PolyData" version="0.1" byte_order="LittleEndian">
//!  <PolyData><Piece NumberOfPoints="4" NumberOfPolys="1">
//!   <Points><DataArray type="Float32" NumberOfComponents="3" format="ascii">
//!     0 0 0  1 0 0  1 1 0  0 1 0 </DataArray></Points>
//!   <Polys><DataArray type="Int32" Name="connectivity" format="ascii">0 1 2 3</DataArray>
//!          <DataArray type="Int32" Name="offsets" format="ascii">4</DataArray></Polys>
//!  </Piece></PolyData></VTKFile>"#;
//! let r = vtu::read_bytes(xml.as_bytes(), "q.vtp".as_ref(), &ReadOptions::default()).unwrap();
//! assert_eq!(r.complex.blocks()[0].kind, CellKind::Quad);
//! ```
use std::borrow::Cow;
use std::io::{Read, Write};
use std::path::Path;

use base64::Engine as _;
use quick_xml::events::{BytesStart, Event};

use super::faces::push_build_notes;
use super::vtk::{linear_run, push_cell, vtk_type, CellStats};
use super::{Format, IoError, IoErrorKind, Location, ReadOptions, ReadResult};
use crate::attr::{AttrValues, Attribute, Attributes};
use crate::cell::CellKind;
use crate::complex::{ComplexBuilder, IndexedComplex};

/// Reads a `.vtu` or `.vtp` file (the whole file is read into memory first).
///
/// ```
/// use starplex::io::{vtu, ReadOptions};
/// let e = vtu::read("/no/such/mesh.vtu".as_ref(), &ReadOptions::default()).unwrap_err();
/// assert!(e.to_string().starts_with("/no/such/mesh.vtu"));
/// ```
///
/// # Errors
/// OS errors, and every error of [`read_bytes`].
pub fn read(path: &Path, opts: &ReadOptions) -> Result<ReadResult, IoError> {
    let f = std::fs::File::open(path).map_err(|e| IoError::new(path, e))?;
    // SAFETY: the map is read only and lives for this call; a file truncated by another
    // process meanwhile is the documented risk of every memory-mapped reader (SIGBUS), the same
    // as for `.spb`.
    match unsafe { memmap2::Mmap::map(&f) } {
        Ok(m) => read_bytes(&m, path, opts),
        // (not mappable: a pipe, /proc, an empty file)
        Err(_) => read_from(f, path, opts),
    }
}

/// Reads a `.vtu` or `.vtp` file from a stream (standard input, a gzip decoder).
///
/// ```
/// use starplex::io::{vtu, ReadOptions};
/// let e = vtu::read_from(&b"<VTKFile type=\"ImageData\"></VTKFile>"[..], "x.vtu".as_ref(),
///                        &ReadOptions::default()).unwrap_err();
/// assert!(e.to_string().contains("ImageData"), "{e}");
/// ```
///
/// # Errors
/// OS errors, and every error of [`read_bytes`].
pub fn read_from(mut r: impl Read, path: &Path, opts: &ReadOptions) -> Result<ReadResult, IoError> {
    let mut data = Vec::new();
    r.read_to_end(&mut data)
        .map_err(|e| IoError::new(path, e))?;
    read_bytes(&data, path, opts)
}

/// A parse error at byte `pos`.
fn perr(path: &Path, pos: usize, msg: impl Into<String>) -> IoError {
    IoError::parse(path, Some(Location::Byte(pos as u64)), msg)
}

/// One `<DataArray>` of the file.
#[derive(Clone, Debug)]
struct ArraySpec<'a> {
    /// The section holding it (`Points`, `Cells`, `Polys`, `PointData`, ...).
    section: String,
    /// Its `Name` attribute (empty when absent).
    name: String,
    /// Its `type` (`Float32`, `Int64`, ...).
    ty: String,
    /// `NumberOfComponents` (1 when absent).
    n_comp: usize,
    /// `ascii`, `binary` or `appended`.
    format: String,
    /// `offset` into the appended data.
    offset: Option<usize>,
    /// The element's text (ascii numbers or base64).
    text: Cow<'a, str>,
    /// Byte position of the element in the file (for errors).
    pos: usize,
}

/// One `<Piece>`: its counts and arrays.
#[derive(Debug, Default)]
struct Piece<'a> {
    n_points: usize,
    arrays: Vec<ArraySpec<'a>>,
    pos: usize,
}

/// What the `<VTKFile>` element says.
#[derive(Debug)]
struct Header {
    poly: bool,
    big_endian: bool,
    header_u64: bool,
    zlib: bool,
}

/// The appended data block: where it starts and how it is encoded.
struct Appended<'a> {
    data: &'a [u8],
    start: usize,
    base64: bool,
}

/// Reads a `.vtu` or `.vtp` file held in memory.
///
/// ```
/// use starplex::io::{vtu, ReadOptions};
/// let bad = br#"<VTKFile type="UnstructuredGrid"><UnstructuredGrid><Piece NumberOfPoints="1" NumberOfCells="0">
///   <Points><DataArray type="Float64" NumberOfComponents="3" format="ascii">0 0</DataArray></Points>
///   </Piece></UnstructuredGrid></VTKFile>"#;
/// let e = vtu::read_bytes(bad, "p.vtu".as_ref(), &ReadOptions::default()).unwrap_err();
/// assert!(e.to_string().contains("holds 2 values, expected 3"), "{e}");
/// ```
///
/// # Errors
/// Malformed XML, a dataset other than an unstructured grid or poly data, arrays that are missing,
/// of the wrong length or type, undecodable base64 or zlib data, unsupported compressors or cell
/// types, and the checks of [`ComplexBuilder::build`], each with the byte position in the file.
pub fn read_bytes(data: &[u8], path: &Path, opts: &ReadOptions) -> Result<ReadResult, IoError> {
    if data.iter().all(|b| b.is_ascii_whitespace()) {
        return Err(perr(path, 0, "the file is empty"));
    }
    // The XML part ends where raw appended data may begin.
    let tag = memchr::memmem::find(data, b"<AppendedData");
    let xml_end = tag.map_or(data.len(), |t| {
        memchr::memchr(b'>', &data[t..]).map_or(data.len(), |g| t + g + 1)
    });
    let xml = match std::str::from_utf8(&data[..xml_end]) {
        Ok(s) => s,
        Err(e) => {
            return Err(perr(
                path,
                e.valid_up_to(),
                "not a VTK XML file: the XML part is not text (UTF-8)",
            ))
        }
    };
    let (header, pieces, appended_encoding) = parse_xml(xml, path)?;
    let appended = appended_block(data, xml_end, appended_encoding, path)?;
    if pieces.is_empty() {
        return Err(perr(path, 0, "the file has no <Piece>"));
    }
    let mut asm = Assembly {
        b: ComplexBuilder::new(3).map_err(|e| IoError::new(path, e))?,
        stats: CellStats::default(),
        origin: Vec::new(),
        n_file_cells: 0,
    };
    let mut point_data = DataColumns::default();
    let mut cell_data = DataColumns::default();
    let src = Source {
        header: &header,
        appended: appended.as_ref(),
        path,
    };
    for (pi, piece) in pieces.iter().enumerate() {
        let base = asm.b.n_vertices() as u64;
        asm.points(piece, &src)?;
        let sections: &[&str] = if header.poly {
            &["Verts", "Lines", "Strips", "Polys"]
        } else {
            &["Cells"]
        };
        for &sec in sections {
            asm.cells(piece, sec, base, &src)?;
        }
        for a in &piece.arrays {
            let cols = match a.section.as_str() {
                "PointData" => &mut point_data,
                "CellData" => &mut cell_data,
                _ => continue,
            };
            let values = decode_attr(a, &header, appended.as_ref(), path)?;
            cols.push(pi, a, values);
        }
    }
    let Assembly {
        mut b,
        stats,
        origin,
        n_file_cells,
    } = asm;
    let mut notes = Vec::new();
    stats.notes(&mut notes);
    let vertex = point_data.finish("PointData", pieces.len(), b.n_vertices(), &mut notes);
    let file_cells = cell_data.finish("CellData", pieces.len(), n_file_cells as usize, &mut notes);
    let cell = file_cells.iter().map(|a| a.gather(&origin)).collect();
    b.set_attributes(Attributes { vertex, cell });
    let (complex, report) = b.build(&opts.build).map_err(|e| IoError::new(path, e))?;
    push_build_notes(&mut notes, &report);
    Ok(ReadResult {
        complex,
        format: if header.poly {
            Format::Vtp
        } else {
            Format::Vtu
        },
        notes,
    })
}

/// The elements of the XML part: the `<VTKFile>` header, the pieces with their array specs,
/// and the encoding of the `<AppendedData>` block if there is one (where parsing stops).
#[allow(clippy::type_complexity)]
fn parse_xml<'a>(
    xml: &'a str,
    path: &Path,
) -> Result<(Header, Vec<Piece<'a>>, Option<String>), IoError> {
    let mut reader = quick_xml::Reader::from_str(xml);
    let mut header: Option<Header> = None;
    let mut pieces: Vec<Piece<'_>> = Vec::new();
    let mut stack: Vec<String> = Vec::new();
    let mut current: Option<ArraySpec<'_>> = None;
    let mut appended_encoding: Option<String> = None;
    loop {
        let pos = reader.buffer_position() as usize;
        let ev = reader.read_event().map_err(|e| {
            perr(
                path,
                reader.error_position() as usize,
                format!("malformed XML: {e}"),
            )
        })?;
        match ev {
            Event::Start(e) | Event::Empty(e) if e.local_name().as_ref() == "AppendedData" => {
                appended_encoding =
                    Some(attr(&e, "encoding", path, pos)?.unwrap_or_else(|| "raw".into()));
                break;
            }
            Event::Start(ref e) | Event::Empty(ref e) => {
                let name = e.local_name().as_ref().to_string();
                open(
                    e,
                    &name,
                    pos,
                    path,
                    &stack,
                    &mut header,
                    &mut pieces,
                    &mut current,
                )?;
                if matches!(ev, Event::Start(_)) {
                    stack.push(name);
                } else {
                    // <X/> opens and closes
                    close(&name, &mut pieces, &mut current);
                }
            }
            Event::End(e) => {
                let name = e.local_name().as_ref().to_string();
                if stack.pop().as_deref() != Some(name.as_str()) {
                    return Err(perr(path, pos, format!("unexpected closing tag </{name}>")));
                }
                close(&name, &mut pieces, &mut current);
            }
            // (text directly inside a DataArray: not in its InformationKey children)
            Event::Text(t) if stack.last().is_some_and(|n| n == "DataArray") => {
                if let Some(a) = current.as_mut() {
                    let s = t.into_inner();
                    if a.text.is_empty() {
                        a.text = s;
                    } else {
                        a.text.to_mut().push_str(&s);
                    }
                }
            }
            Event::CData(t) if stack.last().is_some_and(|n| n == "DataArray") => {
                if let Some(a) = current.as_mut() {
                    let s = t.into_inner();
                    a.text.to_mut().push_str(&s);
                }
            }
            Event::GeneralRef(_) if current.is_some() => {
                return Err(perr(path, pos, "an XML entity inside a data array"));
            }
            Event::Eof => break,
            _ => {}
        }
    }
    let Some(header) = header else {
        return Err(perr(
            path,
            0,
            "not a VTK XML file: it has no <VTKFile> element",
        ));
    };
    Ok((header, pieces, appended_encoding))
}

/// The appended data block after the XML part (`xml_end`), if the XML announced one.
fn appended_block<'a>(
    data: &'a [u8],
    xml_end: usize,
    encoding: Option<String>,
    path: &Path,
) -> Result<Option<Appended<'a>>, IoError> {
    Ok(match encoding {
        None => None,
        Some(enc) => {
            let base64 = match enc.as_str() {
                "raw" => false,
                "base64" => true,
                other => {
                    return Err(perr(
                        path,
                        xml_end,
                        format!("unknown AppendedData encoding '{other}' (expected raw or base64)"),
                    ))
                }
            };
            let Some(u) = memchr::memchr(b'_', &data[xml_end..]) else {
                return Err(perr(path, xml_end, "the AppendedData has no '_' marker"));
            };
            Some(Appended {
                data,
                start: xml_end + u + 1,
                base64,
            })
        }
    })
}

/// Where the arrays' bytes are and how to decode them.
struct Source<'s, 'a> {
    header: &'s Header,
    appended: Option<&'s Appended<'a>>,
    path: &'s Path,
}

impl Piece<'_> {
    /// The array of `section` named `name` (any name when `None`).
    fn array(&self, section: &str, name: Option<&str>) -> Option<&ArraySpec<'_>> {
        self.arrays
            .iter()
            .find(|a| a.section == section && name.is_none_or(|n| a.name == n))
    }
}

/// The complex being assembled from the pieces: the builder, the cell statistics, and the
/// file cell of every cell pushed (to place the cell data).
struct Assembly {
    b: ComplexBuilder,
    stats: CellStats,
    origin: Vec<u32>,
    n_file_cells: u64,
}

impl Assembly {
    /// The points of a piece.
    fn points(&mut self, piece: &Piece<'_>, src: &Source<'_, '_>) -> Result<(), IoError> {
        let (header, appended, path) = (src.header, src.appended, src.path);
        let b = &mut self.b;
        let find = |section: &str, name: Option<&str>| piece.array(section, name);
        if piece.n_points > 0 {
            let Some(p) = find("Points", None) else {
                return Err(perr(
                    path,
                    piece.pos,
                    "the piece has points but no <Points> array",
                ));
            };
            if p.n_comp != 3 {
                return Err(perr(
                    path,
                    p.pos,
                    format!("points have {} components, VTK points have 3", p.n_comp),
                ));
            }
            let xs = decode_f64(p, header, appended, path)?;
            if xs.len() != 3 * piece.n_points {
                return Err(perr(
                path,
                p.pos,
                format!(
                    "the Points array holds {} values, expected {} (3 per point, NumberOfPoints=\"{}\")",
                    xs.len(),
                    3 * piece.n_points,
                    piece.n_points
                ),
            ));
            }
            b.push_vertices(xs).map_err(|e| IoError::new(path, e))?;
        }
        Ok(())
    }

    /// The cells of section `sec` of a piece whose first point is `base`.
    fn cells(
        &mut self,
        piece: &Piece<'_>,
        sec: &str,
        base: u64,
        src: &Source<'_, '_>,
    ) -> Result<(), IoError> {
        let (header, appended, path) = (src.header, src.appended, src.path);
        let find = |section: &str, name: Option<&str>| piece.array(section, name);
        let nv = piece.n_points as u64;
        let Some(conn) = find(sec, Some("connectivity")) else {
            return Ok(());
        };
        let Some(offs) = find(sec, Some("offsets")) else {
            return Err(perr(
                path,
                conn.pos,
                format!("<{sec}> has connectivity but no offsets"),
            ));
        };
        // the point ids of the whole complex (nv below the 32-bit limit the builder checks)
        let global = |v: u64| (v + base) as u32;
        let mut conn_v = match fast_index(conn, header, appended, path, nv, global) {
            Some(v) => v,
            None => {
                let v = decode_index(conn, header, appended, path, nv)?;
                v.into_iter().map(global).collect()
            }
        };
        let index = |a: &ArraySpec<'_>| match fast_index(a, header, appended, path, u64::MAX, |v| v)
        {
            Some(v) => Ok(v),
            None => decode_index(a, header, appended, path, u64::MAX),
        };
        let offs_v = index(offs)?;
        let types_v = if sec == "Cells" {
            let Some(t) = find(sec, Some("types")) else {
                return Err(perr(path, conn.pos, "<Cells> has no types array"));
            };
            let v = index(t)?;
            if v.len() != offs_v.len() {
                return Err(perr(
                    path,
                    t.pos,
                    format!(
                        "{} cell types for {} cells (offsets)",
                        v.len(),
                        offs_v.len()
                    ),
                ));
            }
            Some(v)
        } else {
            None
        };
        let mut start = 0u64;
        let mut i = 0usize;
        while i < offs_v.len() {
            // a run of cells of one linear type is pushed whole
            let max_end = conn_v.len() as u64;
            if let Some((kind, j)) = types_v
                .as_deref()
                .and_then(|t| linear_run(t, &offs_v, start, i, max_end))
            {
                let end = offs_v[j - 1];
                let verts = if start == 0 && end == max_end && j == offs_v.len() {
                    std::mem::take(&mut conn_v)
                } else {
                    conn_v[start as usize..end as usize].to_vec()
                };
                self.b
                    .push_cells(kind, verts)
                    .map_err(|e| perr(path, conn.pos, format!("<{sec}> cell {i}: {e}")))?;
                let first = self.n_file_cells;
                self.n_file_cells += (j - i) as u64;
                if self.n_file_cells > u32::MAX as u64 {
                    return Err(perr(path, conn.pos, "more than 2^32 cells in one file"));
                }
                self.origin.extend(first as u32..self.n_file_cells as u32);
                (start, i) = (end, j);
                continue;
            }
            let end = offs_v[i];
            if end < start || end > conn_v.len() as u64 {
                return Err(perr(
                    path,
                    offs.pos,
                    format!(
                        "<{sec}> offset {i} is {end}: offsets must grow and stay within the {} connectivity entries",
                        conn_v.len()
                    ),
                ));
            }
            let verts = &conn_v[start as usize..end as usize];
            start = end;
            let ty = match (&types_v, sec) {
                (Some(t), _) => t[i],
                (None, "Verts") => 2,
                (None, "Lines") => 4,
                (None, "Strips") => 6,
                _ => 7,
            };
            let before = self.b.n_cells();
            push_cell(&mut self.b, &mut self.stats, ty, verts)
                .map_err(|e| perr(path, conn.pos, format!("<{sec}> cell {i}: {e}")))?;
            let file_cell = u32::try_from(self.n_file_cells)
                .map_err(|_| perr(path, conn.pos, "more than 2^32 cells in one file"))?;
            self.origin
                .extend((before..self.b.n_cells()).map(|_| file_cell));
            self.n_file_cells += 1;
            i += 1;
        }
        Ok(())
    }
}

/// The point or cell data arrays of every piece, concatenated by name.
#[derive(Default)]
struct DataColumns {
    /// Name, components, values, pieces seen, byte position of the first.
    cols: Vec<(String, usize, AttrValues, usize, usize)>,
    /// Arrays not kept, with the reason.
    dropped: Vec<String>,
}

impl DataColumns {
    /// Adds piece `pi`'s array `a`.
    fn push(&mut self, pi: usize, a: &ArraySpec<'_>, values: AttrValues) {
        let name = if a.name.is_empty() {
            format!("array{}", self.cols.len())
        } else {
            a.name.clone()
        };
        match self.cols.iter_mut().find(|c| c.0 == name) {
            None if pi == 0 => self.cols.push((name, a.n_comp, values, 1, a.pos)),
            None => self.dropped.push(format!("'{name}' (not in every piece)")),
            Some(c) if c.3 != pi || c.1 != a.n_comp => {
                self.dropped.push(format!("'{name}' (pieces disagree)"));
                c.3 = usize::MAX;
            }
            Some(c) => {
                c.3 += 1;
                match (&mut c.2, values) {
                    (AttrValues::Int(x), AttrValues::Int(y)) => x.extend(y),
                    (AttrValues::Float(x), AttrValues::Float(y)) => x.extend(y),
                    (AttrValues::Float(x), AttrValues::Int(y)) => {
                        x.extend(y.into_iter().map(|v| v as f64))
                    }
                    (x @ AttrValues::Int(_), AttrValues::Float(y)) => {
                        let AttrValues::Int(xi) = x else {
                            unreachable!()
                        };
                        let mut f: Vec<f64> = xi.iter().map(|&v| v as f64).collect();
                        f.extend(y);
                        *x = AttrValues::Float(f);
                    }
                }
            }
        }
    }

    /// The columns with one item per each of `n` points or cells; the others are noted.
    fn finish(
        self,
        section: &str,
        n_pieces: usize,
        n: usize,
        notes: &mut Vec<String>,
    ) -> Vec<Attribute> {
        let mut dropped = self.dropped;
        let mut out = Vec::new();
        for (name, comps, values, seen, _) in self.cols {
            if seen != n_pieces {
                if seen != usize::MAX {
                    dropped.push(format!("'{name}' (not in every piece)"));
                }
                continue;
            }
            if comps == 0 || values.len() != n.saturating_mul(comps) {
                dropped.push(format!(
                    "'{name}' ({} values for {n} items of {comps} components)",
                    values.len()
                ));
                continue;
            }
            out.push(Attribute {
                name,
                components: comps,
                values,
            });
        }
        if !dropped.is_empty() {
            dropped.dedup();
            notes.push(format!(
                "ignored the {section} arrays {}",
                dropped.join(", ")
            ));
        }
        out
    }
}

/// Decodes a point or cell data array: integers as integers, floats as floats.
fn decode_attr(
    a: &ArraySpec<'_>,
    h: &Header,
    app: Option<&Appended<'_>>,
    path: &Path,
) -> Result<AttrValues, IoError> {
    if type_info(&a.ty).is_some_and(|(_, k)| k == Kind::Float) {
        return decode_f64(a, h, app, path).map(AttrValues::Float);
    }
    decode(a, h, app, path, |i, v| match v {
        Val::I(x) => Ok(x),
        Val::U(u) => i64::try_from(u)
            .map_err(|_| format!("value {i} ({u}) does not fit a 64-bit signed integer")),
        Val::F(x) => Ok(x as i64),
    })
    .map(AttrValues::Int)
}

/// The value of attribute `key` of element `e`.
fn attr(e: &BytesStart<'_>, key: &str, path: &Path, pos: usize) -> Result<Option<String>, IoError> {
    for a in e.attributes() {
        let a = a.map_err(|err| perr(path, pos, format!("malformed XML attribute: {err}")))?;
        if a.key.as_ref() == key {
            let v = a
                .normalized_value(quick_xml::XmlVersion::Implicit1_0)
                .map_err(|err| perr(path, pos, format!("malformed XML attribute: {err}")))?;
            return Ok(Some(v.trim().to_string()));
        }
    }
    Ok(None)
}

/// A count attribute (`NumberOfPoints`, ...), 0 when absent.
fn count_attr(e: &BytesStart<'_>, key: &str, path: &Path, pos: usize) -> Result<usize, IoError> {
    match attr(e, key, path, pos)? {
        None => Ok(0),
        Some(v) => v.parse::<u32>().map(|n| n as usize).map_err(|_| {
            perr(
                path,
                pos,
                format!("{key}=\"{v}\" is not a count (a whole number below 2^32)"),
            )
        }),
    }
}

/// Handles an opening tag.
#[allow(clippy::too_many_arguments)]
fn open<'a>(
    e: &BytesStart<'_>,
    name: &str,
    pos: usize,
    path: &Path,
    stack: &[String],
    header: &mut Option<Header>,
    pieces: &mut Vec<Piece<'a>>,
    current: &mut Option<ArraySpec<'a>>,
) -> Result<(), IoError> {
    match name {
        "VTKFile" => {
            let ty = attr(e, "type", path, pos)?.unwrap_or_default();
            let poly = match ty.as_str() {
                "UnstructuredGrid" => false,
                "PolyData" => true,
                other => {
                    return Err(perr(
                        path,
                        pos,
                        format!(
                            "VTK XML dataset type '{other}' is not a mesh starplex reads (UnstructuredGrid .vtu or PolyData .vtp)"
                        ),
                    ))
                }
            };
            let big_endian = match attr(e, "byte_order", path, pos)?.as_deref() {
                None | Some("LittleEndian") => false,
                Some("BigEndian") => true,
                Some(o) => return Err(perr(path, pos, format!("unknown byte_order '{o}'"))),
            };
            let header_u64 = match attr(e, "header_type", path, pos)?.as_deref() {
                None | Some("UInt32") => false,
                Some("UInt64") => true,
                Some(o) => return Err(perr(path, pos, format!("unknown header_type '{o}'"))),
            };
            let zlib = match attr(e, "compressor", path, pos)?.as_deref() {
                None | Some("") => false,
                Some("vtkZLibDataCompressor") => true,
                Some(o) => {
                    return Err(perr(
                        path,
                        pos,
                        format!(
                            "compressor {o} is not supported (starplex reads zlib and uncompressed files): re-save with zlib or no compression"
                        ),
                    ))
                }
            };
            *header = Some(Header {
                poly,
                big_endian,
                header_u64,
                zlib,
            });
        }
        "Piece" => {
            if header.is_none() {
                return Err(perr(path, pos, "<Piece> outside a <VTKFile>"));
            }
            pieces.push(Piece {
                n_points: count_attr(e, "NumberOfPoints", path, pos)?,
                arrays: Vec::new(),
                pos,
            });
        }
        "DataArray" => {
            if pieces.is_empty() || !stack.iter().any(|n| n == "Piece") {
                // dataset-level <FieldData> (time values, names): not part of the mesh
                *current = None;
                return Ok(());
            }
            let section = stack.last().cloned().unwrap_or_default();
            let n_comp = match attr(e, "NumberOfComponents", path, pos)? {
                None => 1,
                Some(v) => match v.parse::<usize>() {
                    Ok(n) if (1..=1024).contains(&n) => n,
                    _ => {
                        return Err(perr(
                            path,
                            pos,
                            format!("NumberOfComponents=\"{v}\" is not a count from 1 to 1024"),
                        ))
                    }
                },
            };
            let offset = match attr(e, "offset", path, pos)? {
                None => None,
                Some(v) => Some(v.parse::<usize>().map_err(|_| {
                    perr(path, pos, format!("offset=\"{v}\" is not a byte offset"))
                })?),
            };
            *current = Some(ArraySpec {
                section,
                name: attr(e, "Name", path, pos)?.unwrap_or_default(),
                ty: attr(e, "type", path, pos)?.unwrap_or_default(),
                n_comp,
                format: attr(e, "format", path, pos)?.unwrap_or_else(|| "ascii".into()),
                offset,
                text: Cow::Borrowed(""),
                pos,
            });
        }
        _ => {}
    }
    Ok(())
}

/// Handles a closing tag.
fn close<'a>(name: &str, pieces: &mut [Piece<'a>], current: &mut Option<ArraySpec<'a>>) {
    if name == "DataArray"
        && let (Some(a), Some(p)) = (current.take(), pieces.last_mut())
    {
        p.arrays.push(a);
    }
}

/// Bytes per value of a VTK XML data type, and whether it is a float, signed integer.
fn type_info(ty: &str) -> Option<(usize, Kind)> {
    Some(match ty {
        "Int8" => (1, Kind::Int),
        "UInt8" => (1, Kind::UInt),
        "Int16" => (2, Kind::Int),
        "UInt16" => (2, Kind::UInt),
        "Int32" => (4, Kind::Int),
        "UInt32" => (4, Kind::UInt),
        "Int64" => (8, Kind::Int),
        "UInt64" => (8, Kind::UInt),
        "Float32" => (4, Kind::Float),
        "Float64" => (8, Kind::Float),
        _ => return None,
    })
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum Kind {
    Int,
    UInt,
    Float,
}

/// A decoded value (integer or float).
enum Val {
    I(i64),
    U(u64),
    F(f64),
}

/// The values of array `a`, each converted by `conv(index, value)`.
fn decode<T>(
    a: &ArraySpec<'_>,
    h: &Header,
    app: Option<&Appended<'_>>,
    path: &Path,
    mut conv: impl FnMut(usize, Val) -> Result<T, String>,
) -> Result<Vec<T>, IoError> {
    let mut out: Vec<T> = Vec::new();
    let Some((width, kind)) = type_info(&a.ty) else {
        return Err(perr(
            path,
            a.pos,
            format!(
                "data type '{}' of array '{}' is not a VTK number type (Int8..UInt64, Float32, Float64)",
                a.ty, a.name
            ),
        ));
    };
    let here = |m: String| {
        perr(
            path,
            a.pos,
            format!("array '{}' in <{}>: {m}", a.name, a.section),
        )
    };
    if a.format == "ascii" {
        let mut f = |v: Val| {
            let x = conv(out.len(), v)?;
            out.push(x);
            Ok::<(), String>(())
        };
        for tok in a.text.split_ascii_whitespace() {
            let v = match kind {
                Kind::Float => fast_float2::parse::<f64, _>(tok).ok().map(Val::F),
                Kind::Int => tok.parse::<i64>().ok().map(Val::I),
                Kind::UInt => tok.parse::<u64>().ok().map(Val::U),
            };
            let Some(v) = v else {
                return Err(here(format!("'{}' is not a {} value", shown(tok), a.ty)));
            };
            f(v).map_err(here)?;
        }
        return Ok(out);
    }
    let bytes = array_bytes(a, h, app, path)?;
    if !bytes.len().is_multiple_of(width) {
        return Err(here(format!(
            "{} bytes of data are not whole {} values",
            bytes.len(),
            a.ty
        )));
    }
    out.reserve_exact(bytes.len() / width);
    let mut f = |v: Val| {
        let x = conv(out.len(), v)?;
        out.push(x);
        Ok::<(), String>(())
    };
    let be = h.big_endian;
    // one tight loop per type and byte order
    macro_rules! each {
        ($t:ty, $val:expr) => {{
            const W: usize = std::mem::size_of::<$t>();
            for c in bytes.chunks_exact(W) {
                let mut b = [0u8; W];
                b.copy_from_slice(c);
                let x = if be {
                    <$t>::from_be_bytes(b)
                } else {
                    <$t>::from_le_bytes(b)
                };
                f($val(x)).map_err(here)?;
            }
        }};
    }
    match (kind, width) {
        (Kind::Float, 4) => each!(f32, |x: f32| Val::F(x as f64)),
        (Kind::Float, _) => each!(f64, Val::F),
        (Kind::UInt, 1) => each!(u8, |x: u8| Val::U(x as u64)),
        (Kind::UInt, 2) => each!(u16, |x: u16| Val::U(x as u64)),
        (Kind::UInt, 4) => each!(u32, |x: u32| Val::U(x as u64)),
        (Kind::UInt, _) => each!(u64, Val::U),
        (Kind::Int, 1) => each!(i8, |x: i8| Val::I(x as i64)),
        (Kind::Int, 2) => each!(i16, |x: i16| Val::I(x as i64)),
        (Kind::Int, 4) => each!(i32, |x: i32| Val::I(x as i64)),
        (Kind::Int, _) => each!(i64, Val::I),
    }
    Ok(out)
}

/// The bytes of a binary (base64) or appended array, decoded and inflated.
fn array_bytes<'d>(
    a: &ArraySpec<'_>,
    h: &Header,
    app: Option<&Appended<'d>>,
    path: &Path,
) -> Result<Cow<'d, [u8]>, IoError> {
    let here = |m: String| {
        perr(
            path,
            a.pos,
            format!("array '{}' in <{}>: {m}", a.name, a.section),
        )
    };
    Ok(match a.format.as_str() {
        "binary" => {
            let t: String = a.text.split_ascii_whitespace().collect();
            Cow::Owned(decode_base64_array(t.as_bytes(), h).map_err(here)?)
        }
        "appended" => {
            let Some(app) = app else {
                return Err(here(
                    "format=\"appended\" but the file has no <AppendedData>".into(),
                ));
            };
            let Some(off) = a.offset else {
                return Err(here("format=\"appended\" without an offset".into()));
            };
            let Some(at) = app.start.checked_add(off).filter(|&s| s <= app.data.len()) else {
                return Err(here(format!("offset {off} is past the end of the file")));
            };
            let rest = &app.data[at..];
            if app.base64 {
                Cow::Owned(decode_base64_array(base64_prefix(rest), h).map_err(here)?)
            } else {
                decode_raw_array(rest, h).map_err(here)?
            }
        }
        other => {
            return Err(here(format!(
                "unknown format '{other}' (expected ascii, binary or appended)"
            )))
        }
    })
}

/// A token shortened for an error message.
fn shown(tok: &str) -> String {
    tok.chars().take(40).collect()
}

/// Decodes a float array.
fn decode_f64(
    a: &ArraySpec<'_>,
    h: &Header,
    app: Option<&Appended<'_>>,
    path: &Path,
) -> Result<Vec<f64>, IoError> {
    decode(a, h, app, path, |_, v| {
        Ok(match v {
            Val::F(x) => x,
            Val::I(i) => i as f64,
            Val::U(u) => u as f64,
        })
    })
}

/// Decodes an index array whose values must be below `limit`.
fn decode_index(
    a: &ArraySpec<'_>,
    h: &Header,
    app: Option<&Appended<'_>>,
    path: &Path,
    limit: u64,
) -> Result<Vec<u64>, IoError> {
    decode(a, h, app, path, |i, v| {
        let x = match v {
            Val::U(u) => u,
            Val::I(x) if x >= 0 => x as u64,
            Val::I(x) => return Err(format!("value {i} is {x}, a negative index")),
            Val::F(_) => return Err("indices must be integers, the array holds floats".into()),
        };
        if x >= limit {
            return Err(format!(
                "value {i} is point {x}, out of range: the piece has {limit} points, numbered from 0"
            ));
        }
        Ok(x)
    })
}

/// The values of a binary or appended integer array when every one is in `0..limit` (else
/// `None`: [`decode_index`] then names the bad value), each mapped by `f`: one tight loop per
/// type, without the per-value checks of the general decoder.
fn fast_index<T: Send>(
    a: &ArraySpec<'_>,
    h: &Header,
    app: Option<&Appended<'_>>,
    path: &Path,
    limit: u64,
    f: impl Fn(u64) -> T + Sync,
) -> Option<Vec<T>> {
    use rayon::prelude::*;
    let (width, kind) = type_info(&a.ty)?;
    if a.format == "ascii" || kind == Kind::Float {
        return None;
    }
    let bytes = array_bytes(a, h, app, path).ok()?;
    if !bytes.len().is_multiple_of(width) {
        return None;
    }
    let be = h.big_endian;
    macro_rules! each {
        ($t:ty) => {{
            const W: usize = std::mem::size_of::<$t>();
            let get = |c: &[u8]| {
                let b: [u8; W] = c.try_into().expect("W bytes");
                if be {
                    <$t>::from_be_bytes(b)
                } else {
                    <$t>::from_le_bytes(b)
                }
            };
            // (negative values of signed types wrap to huge ones: out of range)
            let ok = bytes
                .par_chunks(W << 16)
                .all(|p| p.chunks_exact(W).all(|c| (get(c) as u64) < limit));
            ok.then(|| {
                bytes
                    .par_chunks_exact(W)
                    .map(|c| f(get(c) as u64))
                    .collect()
            })
        }};
    }
    match (kind, width) {
        (Kind::UInt, 1) => each!(u8),
        (Kind::UInt, 2) => each!(u16),
        (Kind::UInt, 4) => each!(u32),
        (Kind::UInt, _) => each!(u64),
        (Kind::Int, 1) => each!(i8),
        (Kind::Int, 2) => each!(i16),
        (Kind::Int, 4) => each!(i32),
        (_, _) => each!(i64),
    }
}

/// The base64 characters at the start of `rest` (until the first byte that is not base64).
fn base64_prefix(rest: &[u8]) -> &[u8] {
    let n = rest
        .iter()
        .position(|&c| !(c.is_ascii_alphanumeric() || c == b'+' || c == b'/' || c == b'='))
        .unwrap_or(rest.len());
    &rest[..n]
}

/// The unsigned integers of a block header of `n` values.
fn header_values(bytes: &[u8], h: &Header, n: usize) -> Option<Vec<u64>> {
    let w: usize = if h.header_u64 { 8 } else { 4 };
    let len = n.checked_mul(w)?;
    if bytes.len() < len {
        return None;
    }
    Some(
        bytes[..len]
            .chunks_exact(w)
            .map(|c| {
                let mut b = [0u8; 8];
                b[..w].copy_from_slice(c);
                if h.big_endian {
                    b[..w].reverse();
                }
                u64::from_le_bytes(b)
            })
            .collect(),
    )
}

/// Base64 characters for `n` bytes encoded on their own (with padding).
fn b64_len(n: usize) -> usize {
    n.div_ceil(3).saturating_mul(4)
}

fn b64(s: &[u8]) -> Result<Vec<u8>, String> {
    base64::engine::general_purpose::STANDARD
        .decode(s)
        .map_err(|e| format!("undecodable base64 data: {e}"))
}

/// Decodes an inline or appended base64 array (header and data encoded together or apart, the
/// way VTK and meshio write them).
fn decode_base64_array(s: &[u8], h: &Header) -> Result<Vec<u8>, String> {
    let w: usize = if h.header_u64 { 8 } else { 4 };
    // The first header value alone: a header encoded apart ends in padding.
    let first_chars = b64_len(w).min(s.len());
    let first = b64(&pad_to_quad(&s[..first_chars]))?;
    let first_v = header_values(&first, h, 1).ok_or("the data header is truncated")?;
    if !h.zlib {
        let n = first_v[0] as usize;
        let apart = s[..first_chars].contains(&b'=');
        let data = if apart {
            let end = first_chars
                .checked_add(b64_len(n))
                .filter(|&e| e <= s.len())
                .ok_or("the data is shorter than its header says")?;
            b64(&s[first_chars..end])?
        } else {
            let end = b64_len(w.saturating_add(n)).min(s.len());
            let all = b64(&s[..end])?;
            all.get(w..).map(<[u8]>::to_vec).unwrap_or_default()
        };
        if data.len() < n {
            return Err(format!(
                "the data holds {} bytes, its header says {n}",
                data.len()
            ));
        }
        let mut data = data;
        data.truncate(n);
        return Ok(data);
    }
    let nb = first_v[0] as usize;
    let hlen = (3usize.checked_add(nb).ok_or("absurd block count")?)
        .checked_mul(w)
        .ok_or("absurd block count")?;
    let hchars = b64_len(hlen);
    if hchars > s.len() {
        return Err(format!(
            "the compressed data header ({nb} blocks) is truncated"
        ));
    }
    let hb = b64(&s[..hchars])?;
    let hv = header_values(&hb, h, 3 + nb).ok_or("the compressed data header is truncated")?;
    // VTK and meshio encode the header apart from the blocks (when its length is a multiple of
    // 3 bytes, encoding them together gives the same characters)
    let comp_total = hv[3..].iter().fold(0u64, |a, &b| a.saturating_add(b));
    let end = hchars + b64_len(comp_total as usize).min(s.len() - hchars);
    let comp = b64(&s[hchars..end])?;
    inflate_blocks(&hv, &comp)
}

/// Pads a base64 prefix to whole quads (so that its first bytes decode).
fn pad_to_quad(s: &[u8]) -> Cow<'_, [u8]> {
    if s.len().is_multiple_of(4) {
        Cow::Borrowed(s)
    } else {
        let mut v = s.to_vec();
        while !v.len().is_multiple_of(4) {
            v.push(b'=');
        }
        Cow::Owned(v)
    }
}

/// Decodes a raw appended array starting at `rest` (uncompressed: borrowed from the file).
fn decode_raw_array<'a>(rest: &'a [u8], h: &Header) -> Result<Cow<'a, [u8]>, String> {
    let w: usize = if h.header_u64 { 8 } else { 4 };
    let first = header_values(rest, h, 1).ok_or("the data header is truncated")?;
    if !h.zlib {
        let n = first[0] as usize;
        return rest
            .get(w..w.saturating_add(n))
            .map(Cow::Borrowed)
            .ok_or_else(|| {
                format!(
                    "the header says {n} bytes, the file holds {}",
                    rest.len() - w
                )
            });
    }
    let nb = first[0] as usize;
    let hn = 3usize.checked_add(nb).ok_or("absurd block count")?;
    let hv = header_values(rest, h, hn).ok_or("the compressed data header is truncated")?;
    let comp_total = hv[3..].iter().fold(0u64, |a, &b| a.saturating_add(b));
    let comp = rest
        .get(hn * w..(hn * w).saturating_add(comp_total as usize))
        .ok_or("the compressed data is truncated")?;
    inflate_blocks(&hv, comp).map(Cow::Owned)
}

/// Inflates zlib blocks described by a VTK compressed header `[nb, block, last, sizes...]`.
fn inflate_blocks(hv: &[u64], comp: &[u8]) -> Result<Vec<u8>, String> {
    let nb = hv[0] as usize;
    let (block, last) = (hv[1] as usize, hv[2] as usize);
    let total = if nb == 0 {
        0
    } else {
        (nb - 1)
            .checked_mul(block)
            .and_then(|t| t.checked_add(if last == 0 { block } else { last }))
            .ok_or("absurd block sizes")?
    };
    // a compressed block inflates at most ~1032x: refuse sizes no data could have
    if total as u128 > (comp.len() as u128 + 64) * 1100 {
        return Err(format!(
            "the header announces {total} bytes from {} compressed bytes",
            comp.len()
        ));
    }
    // (grown by what actually inflates: a header cannot make it allocate)
    let mut out = Vec::with_capacity(total.min(1 << 26));
    let mut at = 0usize;
    for (i, &cs) in hv[3..].iter().enumerate() {
        let cs = cs as usize;
        let src = comp
            .get(at..at.saturating_add(cs))
            .ok_or("the compressed data is truncated")?;
        at += cs;
        let want = if i + 1 == nb && last != 0 {
            last
        } else {
            block
        };
        let before = out.len();
        flate2::read::ZlibDecoder::new(src)
            .take(want as u64)
            .read_to_end(&mut out)
            .map_err(|e| format!("block {i} does not inflate: {e}"))?;
        if out.len() - before != want {
            return Err(format!(
                "block {i} inflates to {} bytes, its header says {want}",
                out.len() - before
            ));
        }
    }
    Ok(out)
}

/// Refuses what `.vtu` cannot hold (more than 3 coordinates, simplices of dimension 4 and more)
/// or, with `poly`, what `.vtp` cannot hold (3D cells).
///
/// ```
/// use starplex::cell::CellKind;
/// use starplex::complex::IndexedComplex;
/// use starplex::io::vtu;
/// let tet = IndexedComplex::from_parts(3, vec![0.0; 12].into(),
///                                      vec![(CellKind::Simplex(3), vec![0, 1, 2, 3].into())]).unwrap();
/// assert!(vtu::check(&tet, false).is_ok());
/// assert!(vtu::check(&tet, true).unwrap_err().to_string().contains("boundary surface"));
/// ```
///
/// # Errors
/// [`IoErrorKind::CannotWrite`] with the reason.
pub fn check(k: &IndexedComplex, poly: bool) -> Result<(), IoErrorKind> {
    let format = if poly { Format::Vtp } else { Format::Vtu };
    let d = k.ambient_dim();
    if d > 3 {
        return Err(IoErrorKind::CannotWrite {
            format,
            reason: format!("VTK points have 3 coordinates, the complex has {d}"),
        });
    }
    for b in k.blocks() {
        if vtk_type(b.kind).is_none() {
            return Err(IoErrorKind::CannotWrite {
                format,
                reason: format!("VTK has no cell type for {} cells", b.kind),
            });
        }
        if poly && b.kind.dim() > 2 {
            return Err(IoErrorKind::CannotWrite {
                format,
                reason: format!(
                    "VTK poly data holds points, lines and polygons, not {} cells: write .vtu, or its boundary surface",
                    b.kind
                ),
            });
        }
    }
    Ok(())
}

/// Writes `k` as a `.vtu` unstructured grid (raw appended little-endian data, `UInt64` headers).
///
/// ```
/// use starplex::cell::CellKind;
/// use starplex::complex::IndexedComplex;
/// use starplex::io::vtu;
/// let k = IndexedComplex::from_parts(3, vec![0.0; 24].into(),
///     vec![(CellKind::Hex, (0..8).collect::<Vec<u32>>().into())]).unwrap();
/// let mut out = Vec::new();
/// vtu::write_vtu(&mut out, &k).unwrap();
/// assert!(out.starts_with(b"<?xml"));
/// ```
///
/// # Errors
/// [`IoErrorKind::CannotWrite`] (see [`check`]) and OS errors of the writer.
pub fn write_vtu(w: &mut dyn Write, k: &IndexedComplex) -> Result<(), IoErrorKind> {
    check(k, false)?;
    let n_cells = k.n_cells() as u64;
    let conn_bytes = 8 * k.n_refs() as u64;
    let mut sizes = vec![24 * k.n_vertices() as u64, conn_bytes, 8 * n_cells, n_cells];
    let attrs = k.attributes();
    sizes.extend(attrs.vertex.iter().chain(&attrs.cell).map(attr_bytes));
    let offsets = appended_offsets(&sizes);
    writeln!(w, "<?xml version=\"1.0\"?>")?;
    writeln!(
        w,
        "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">"
    )?;
    writeln!(w, "  <UnstructuredGrid>")?;
    writeln!(
        w,
        "    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{n_cells}\">",
        k.n_vertices()
    )?;
    writeln!(w, "      <Points>")?;
    writeln!(w, "        <DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"appended\" offset=\"{}\"/>", offsets[0])?;
    writeln!(w, "      </Points>")?;
    writeln!(w, "      <Cells>")?;
    writeln!(w, "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"appended\" offset=\"{}\"/>", offsets[1])?;
    writeln!(
        w,
        "        <DataArray type=\"Int64\" Name=\"offsets\" format=\"appended\" offset=\"{}\"/>",
        offsets[2]
    )?;
    writeln!(
        w,
        "        <DataArray type=\"UInt8\" Name=\"types\" format=\"appended\" offset=\"{}\"/>",
        offsets[3]
    )?;
    writeln!(w, "      </Cells>")?;
    data_headers(w, k, &offsets[4..])?;
    writeln!(w, "    </Piece>")?;
    writeln!(w, "  </UnstructuredGrid>")?;
    writeln!(w, "  <AppendedData encoding=\"raw\">")?;
    w.write_all(b"   _")?;
    write_points(w, k, sizes[0])?;
    write_cells(w, k, |_| true, conn_bytes, n_cells)?;
    let mut buf: Vec<u8> = Vec::new();
    // types
    w.write_all(&n_cells.to_le_bytes())?;
    for b in k.blocks() {
        let t = vtk_type(b.kind).unwrap_or(0);
        buf.clear();
        buf.resize(b.len(), t);
        w.write_all(&buf)?;
    }
    write_data(w, k, None)?;
    finish_appended(w)
}

/// Writes `k` as a `.vtp` poly data file (vertex cells as `Verts`, edges as `Lines`, triangles
/// and quads as `Polys`).
///
/// ```
/// use starplex::cell::CellKind;
/// use starplex::complex::IndexedComplex;
/// use starplex::io::{vtu, ReadOptions};
/// let k = IndexedComplex::from_parts(3, vec![0., 0., 0., 1., 0., 0., 0., 1., 0., 1., 1., 0.].into(),
///     vec![(CellKind::Simplex(2), vec![0, 1, 2].into()), (CellKind::Simplex(1), vec![1, 3].into())]).unwrap();
/// let mut out = Vec::new();
/// vtu::write_vtp(&mut out, &k).unwrap();
/// let back = vtu::read_bytes(&out, "k.vtp".as_ref(), &ReadOptions::default()).unwrap();
/// assert_eq!(back.complex.n_cells(), 2);
/// ```
///
/// # Errors
/// [`IoErrorKind::CannotWrite`] (see [`check`]) and OS errors of the writer.
pub fn write_vtp(w: &mut dyn Write, k: &IndexedComplex) -> Result<(), IoErrorKind> {
    check(k, true)?;
    let groups: [&[CellKind]; 3] = [
        &[CellKind::Simplex(0)],
        &[CellKind::Simplex(1)],
        &[CellKind::Simplex(2), CellKind::Quad],
    ];
    let stats: Vec<(u64, u64)> = groups
        .iter()
        .map(|g| {
            k.blocks()
                .iter()
                .filter(|b| g.contains(&b.kind))
                .fold((0, 0), |(c, r), b| {
                    (c + b.len() as u64, r + b.vertices.len() as u64)
                })
        })
        .collect();
    let mut sizes = vec![24 * k.n_vertices() as u64];
    for &(c, r) in &stats {
        sizes.push(8 * r);
        sizes.push(8 * c);
    }
    let attrs = k.attributes();
    sizes.extend(attrs.vertex.iter().chain(&attrs.cell).map(attr_bytes));
    let offsets = appended_offsets(&sizes);
    writeln!(w, "<?xml version=\"1.0\"?>")?;
    writeln!(
        w,
        "<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">"
    )?;
    writeln!(w, "  <PolyData>")?;
    writeln!(
        w,
        "    <Piece NumberOfPoints=\"{}\" NumberOfVerts=\"{}\" NumberOfLines=\"{}\" NumberOfStrips=\"0\" NumberOfPolys=\"{}\">",
        k.n_vertices(),
        stats[0].0,
        stats[1].0,
        stats[2].0
    )?;
    writeln!(w, "      <Points>")?;
    writeln!(w, "        <DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"appended\" offset=\"{}\"/>", offsets[0])?;
    writeln!(w, "      </Points>")?;
    for (i, sec) in ["Verts", "Lines", "Polys"].iter().enumerate() {
        writeln!(w, "      <{sec}>")?;
        writeln!(w, "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"appended\" offset=\"{}\"/>", offsets[1 + 2 * i])?;
        writeln!(w, "        <DataArray type=\"Int64\" Name=\"offsets\" format=\"appended\" offset=\"{}\"/>", offsets[2 + 2 * i])?;
        writeln!(w, "      </{sec}>")?;
    }
    data_headers(w, k, &offsets[7..])?;
    writeln!(w, "    </Piece>")?;
    writeln!(w, "  </PolyData>")?;
    writeln!(w, "  <AppendedData encoding=\"raw\">")?;
    w.write_all(b"   _")?;
    write_points(w, k, sizes[0])?;
    for (g, &(c, r)) in groups.iter().zip(&stats) {
        write_cells(w, k, |kind| g.contains(&kind), 8 * r, c)?;
    }
    // poly data cells come section by section: their data in that order
    let order: Vec<u32> = groups
        .iter()
        .flat_map(|g| {
            k.blocks()
                .iter()
                .filter(|b| g.contains(&b.kind))
                .flat_map(|b| b.first..b.first + b.len() as u32)
        })
        .collect();
    write_data(w, k, Some(&order))?;
    finish_appended(w)
}

/// Writes the `connectivity` and `offsets` arrays (each after its header) of the blocks of `k`
/// whose kind `keep` accepts: `conn_bytes` bytes of vertex ids, `n_cells` end offsets.
fn write_cells(
    w: &mut dyn Write,
    k: &IndexedComplex,
    keep: impl Fn(CellKind) -> bool,
    conn_bytes: u64,
    n_cells: u64,
) -> Result<(), IoErrorKind> {
    let mut buf: Vec<u8> = Vec::with_capacity(1 << 16);
    w.write_all(&conn_bytes.to_le_bytes())?;
    for b in k.blocks().iter().filter(|b| keep(b.kind)) {
        for &v in b.vertices.iter() {
            buf.extend_from_slice(&(v as i64).to_le_bytes());
            flush_if_full(w, &mut buf)?;
        }
    }
    w.write_all(&buf)?;
    buf.clear();
    w.write_all(&(8 * n_cells).to_le_bytes())?;
    let mut end = 0i64;
    for b in k.blocks().iter().filter(|b| keep(b.kind)) {
        let n = b.kind.n_vertices() as i64;
        for _ in 0..b.len() {
            end += n;
            buf.extend_from_slice(&end.to_le_bytes());
            flush_if_full(w, &mut buf)?;
        }
    }
    w.write_all(&buf)?;
    Ok(())
}

/// Bytes of an attribute's values in the appended data (8 per value).
fn attr_bytes(a: &Attribute) -> u64 {
    8 * a.values.len() as u64
}

/// The `<PointData>` and `<CellData>` elements of `k`'s attributes, at appended `offsets`.
fn data_headers(w: &mut dyn Write, k: &IndexedComplex, offsets: &[u64]) -> Result<(), IoErrorKind> {
    let attrs = k.attributes();
    let mut at = offsets.iter();
    for (sec, cols) in [("PointData", &attrs.vertex), ("CellData", &attrs.cell)] {
        if cols.is_empty() {
            continue;
        }
        writeln!(w, "      <{sec}>")?;
        for a in cols {
            let ty = match a.values {
                AttrValues::Int(_) => "Int64",
                AttrValues::Float(_) => "Float64",
            };
            writeln!(
                w,
                "        <DataArray type=\"{ty}\" Name=\"{}\" NumberOfComponents=\"{}\" format=\"appended\" offset=\"{}\"/>",
                quick_xml::escape::escape(a.name.as_str()),
                a.components,
                at.next().copied().unwrap_or(0)
            )?;
        }
        writeln!(w, "      </{sec}>")?;
    }
    Ok(())
}

/// Writes the attribute arrays (vertex ones, then cell ones in `cell_order` when given), each
/// after its header, little-endian.
fn write_data(
    w: &mut dyn Write,
    k: &IndexedComplex,
    cell_order: Option<&[u32]>,
) -> Result<(), IoErrorKind> {
    let attrs = k.attributes();
    let mut buf: Vec<u8> = Vec::with_capacity(1 << 16);
    let cells: Vec<Attribute>;
    let cell_cols: &[Attribute] = match cell_order {
        Some(o) => {
            cells = attrs.cell.iter().map(|a| a.gather(o)).collect();
            &cells
        }
        None => &attrs.cell,
    };
    for a in attrs.vertex.iter().chain(cell_cols) {
        w.write_all(&attr_bytes(a).to_le_bytes())?;
        match &a.values {
            AttrValues::Int(v) => {
                for x in v {
                    buf.extend_from_slice(&x.to_le_bytes());
                    flush_if_full(w, &mut buf)?;
                }
            }
            AttrValues::Float(v) => {
                for x in v {
                    buf.extend_from_slice(&x.to_le_bytes());
                    flush_if_full(w, &mut buf)?;
                }
            }
        }
        w.write_all(&buf)?;
        buf.clear();
    }
    Ok(())
}

/// Offsets of consecutive arrays of `sizes` bytes, each after its 8-byte header.
fn appended_offsets(sizes: &[u64]) -> Vec<u64> {
    let mut at = 0u64;
    sizes
        .iter()
        .map(|&s| {
            let o = at;
            at += 8 + s;
            o
        })
        .collect()
}

/// Writes the points array (header and coordinates, padded to 3).
fn write_points(w: &mut dyn Write, k: &IndexedComplex, bytes: u64) -> Result<(), IoErrorKind> {
    w.write_all(&bytes.to_le_bytes())?;
    let d = k.ambient_dim();
    let mut buf: Vec<u8> = Vec::with_capacity(1 << 16);
    for p in k.coords().chunks_exact(d) {
        for a in 0..3 {
            let x = p.get(a).copied().unwrap_or(0.0);
            buf.extend_from_slice(&x.to_le_bytes());
        }
        flush_if_full(w, &mut buf)?;
    }
    w.write_all(&buf)?;
    Ok(())
}

fn flush_if_full(w: &mut dyn Write, buf: &mut Vec<u8>) -> std::io::Result<()> {
    if buf.len() >= (1 << 16) - 64 {
        w.write_all(buf)?;
        buf.clear();
    }
    Ok(())
}

fn finish_appended(w: &mut dyn Write) -> Result<(), IoErrorKind> {
    w.write_all(b"\n  </AppendedData>\n</VTKFile>\n")?;
    Ok(())
}
