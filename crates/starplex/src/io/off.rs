//! OFF (Object File Format): `OFF`, `COFF`, `NOFF`, `nOFF`, `4OFF`, `STOFF` and their
//! combinations (`CNOFF`, `NCOFF`, ...), plus the Stellar reference's OFF for complexes of any
//! dimension.
//!
//! ```text
//! OFF                         # header keyword; the counts may follow on the same line
//! <n_vertices> <n_faces> [<n_edges>]
//! x y z [extras]              (n_vertices lines)
//! k i_0 ... i_{k-1} [colour]  (n_faces lines)
//! ```
//!
//! * `C`, `N`, `ST` prefixes: vertex lines carry normal (`N`), colour (`C`) and texture (`ST`)
//!   values after the position, in that order. Normals (as many values as coordinates) become
//!   the float vertex attribute [`NORMAL`]; the colour (the rest of the line: 1 to 4 values,
//!   e.g. `r g b a`) the vertex attribute [`COLOR`]; texture values are ignored.
//! * Face colours: the values after a face's indices (1 to 4: a colour-map index, `r g b` or
//!   `r g b a`) become the cell attribute [`COLOR`] (the triangles of a fanned polygon share
//!   it). Colours are integers when every value is written as one (`255`), else floats
//!   (`1.0`, `0.5`). A colour column is kept only when every line has the same number of
//!   values (0 on every face line: no column); otherwise it is dropped with a note naming the
//!   first line that differs.
//! * `n` prefix: a line with the dimension `n` follows the keyword; vertices have `n` coordinates.
//! * `4` prefix: homogeneous coordinates (one more value per vertex, the position is divided by it).
//! * Plain `OFF` whose vertex lines do not have 3 values (the Stellar reference's convention for
//!   5D/7D Sierpinski and Vietoris-Rips complexes): the ambient dimension is the number of values
//!   on the first vertex line, and every vertex line must have as many.
//! * `#` starts a comment; blank lines, tabs and CRLF line ends are accepted; a file without the
//!   header keyword (counts first) is read as plain `OFF`.
//!
//! Faces become cells according to [`ReadOptions::polygons`]: with [`PolygonMode::Polygons`] (the
//! default) 3 -> triangle, 4 -> quad cell, more -> fan of triangles (noted), 2 -> edge, 1 ->
//! dropped (noted); with [`PolygonMode::Simplices`] a face of `k` vertices is a `(k-1)`-simplex.
//!
//! ```
//! use starplex::io::{off, PolygonMode, ReadOptions};
//! use starplex::cell::CellKind;
//! let text = "OFF 5 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n2 2 2\n4 0 1 2 3\n3 2 3 4\n";
//! let r = off::read_from(text.as_bytes(), "mem.off".as_ref(), &ReadOptions::default()).unwrap();
//! assert_eq!(r.complex.n_cells(), 2);
//! assert_eq!(r.complex.blocks()[0].kind, CellKind::Quad);
//! let mut out = Vec::new();
//! off::write(&mut out, &r.complex).unwrap();
//! assert_eq!(String::from_utf8(out).unwrap(), text.replacen("OFF 5 2 0", "OFF\n5 2 0", 1));
//!
//! // The same faces read as simplices: a 3-simplex and a triangle.
//! let opts = ReadOptions { polygons: PolygonMode::Simplices, ..Default::default() };
//! let r = off::read_from(text.as_bytes(), "mem.off".as_ref(), &opts).unwrap();
//! assert_eq!(r.complex.blocks()[0].kind, CellKind::Simplex(3));
//! ```
use std::io::{BufRead, Write};
use std::path::Path;

use super::faces::push_build_notes;
use super::text::{parse_f64, parse_u64, write_f64, LineReader, Tokens};
use super::{Format, IoError, IoErrorKind, Location, PolygonMode, ReadOptions, ReadResult};
use crate::attr::{AttrTarget, AttrValues, Attribute, Attributes};
use crate::cell::{CellKind, MAX_SIMPLEX_DIM};
use crate::complex::{check_cell, ComplexBuilder, ComplexError, IndexedComplex, MAX_AMBIENT_DIM};

/// Reads an OFF file.
///
/// ```
/// use starplex::io::{off, IoErrorKind, ReadOptions};
/// let path = std::env::temp_dir().join(format!("starplex-doc-off-read-{}.off", std::process::id()));
/// std::fs::write(&path, "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n3 1 3 2\n").unwrap();
/// let r = off::read(&path, &ReadOptions::default()).unwrap();
/// std::fs::remove_file(&path).unwrap();
/// assert_eq!((r.complex.n_vertices(), r.complex.n_cells()), (4, 2));
/// let e = off::read(&path, &ReadOptions::default()).unwrap_err(); // now missing
/// assert!(matches!(e.kind, IoErrorKind::Os(_)));
/// ```
///
/// # Errors
/// See [`read_from`].
pub fn read(path: &Path, opts: &ReadOptions) -> Result<ReadResult, IoError> {
    let f = std::fs::File::open(path).map_err(|e| IoError::new(path, e))?;
    read_from(std::io::BufReader::with_capacity(1 << 20, f), path, opts)
}

/// What the header keyword says about the vertex lines.
#[derive(Clone, Copy, Debug, Default)]
struct Header {
    /// `C`: colours after the position.
    colour: bool,
    /// `N`: normals after the position.
    normal: bool,
    /// `ST`: texture coordinates after the position.
    texture: bool,
    /// `4`: homogeneous coordinates.
    homogeneous: bool,
    /// `n`: the dimension follows the keyword.
    ndim: bool,
}

impl Header {
    /// Parses `[ST][C][N][4][n]OFF` (prefixes in any order, each at most once).
    fn parse(word: &[u8]) -> Option<Header> {
        let mut rest = word.strip_suffix(b"OFF")?;
        let mut h = Header::default();
        while !rest.is_empty() {
            if let Some(r) = rest.strip_prefix(b"ST") {
                if h.texture {
                    return None;
                }
                h.texture = true;
                rest = r;
                continue;
            }
            let flag = match rest[0] {
                b'C' => &mut h.colour,
                b'N' => &mut h.normal,
                b'4' => &mut h.homogeneous,
                b'n' => &mut h.ndim,
                _ => return None,
            };
            if *flag {
                return None;
            }
            *flag = true;
            rest = &rest[1..];
        }
        Some(h)
    }

    /// Plain OFF: the number of values on a vertex line is the dimension.
    fn is_plain(&self) -> bool {
        !(self.colour || self.normal || self.texture || self.homogeneous || self.ndim)
    }
}

/// Parses a header count token and appends it to `vals` (the label names it in errors).
fn header_value(
    t: &Tokens<'_>,
    tok: &[u8],
    labels: &[&str],
    vals: &mut Vec<u64>,
) -> Result<(), IoError> {
    let what = labels.get(vals.len()).copied().unwrap_or("the edge count");
    match parse_u64(tok) {
        Some(v) => {
            vals.push(v);
            Ok(())
        }
        None => Err(t.err(format!(
            "expected {what} (an unsigned integer), found '{}'",
            shown(tok, 40)
        ))),
    }
}

/// Reads OFF text from any buffered reader; `path` names it in errors.
///
/// Nothing is allocated from a declared count: vectors grow with the lines actually read, so a
/// file that announces 10^12 faces fails at its end instead of exhausting memory.
///
/// ```
/// use starplex::io::{off, Location, ReadOptions};
/// // 4D points in the Stellar reference's plain OFF: the dimension is read from the first vertex.
/// let text = "OFF\n3 1 0\n0 0 0 0\n1 0 0 0\n0 1 0 0\n3 0 1 2\n";
/// let r = off::read_from(text.as_bytes(), "m.off".as_ref(), &ReadOptions::default()).unwrap();
/// assert_eq!(r.complex.ambient_dim(), 4);
/// let bad = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 5\n";
/// let e = off::read_from(bad.as_bytes(), "m.off".as_ref(), &ReadOptions::default()).unwrap_err();
/// assert_eq!(e.location, Some(Location::Line(6)));
/// ```
///
/// # Errors
/// A missing or unknown header keyword, binary OFF, malformed or non-finite numbers, vertex lines
/// with the wrong number of values, faces with no vertices, out-of-range or repeated vertex
/// indices (with the line), faces of more than 65 vertices in simplex mode, a file shorter or
/// longer than its counts say, and the checks of [`ComplexBuilder::build`].
pub fn read_from(r: impl BufRead, path: &Path, opts: &ReadOptions) -> Result<ReadResult, IoError> {
    let mut lr = LineReader::new(r, path, Some(b'#'));
    let (header, counts) = read_counts(&mut lr, path)?;
    let (mut b, normals, vcolours) = read_vertices(&mut lr, path, &header, &counts)?;
    let (lines, fcolours, faces) = read_faces(&mut lr, path, opts, &counts, &mut b)?;
    let mut notes = Vec::new();
    let mut attrs = Attributes::default();
    if let Some(a) = normals.column(NORMAL, false, &mut notes) {
        attrs.vertex.push(a);
    }
    if let Some(a) = vcolours.column(COLOR, true, &mut notes) {
        attrs.vertex.push(a);
    }
    if let Some(a) = fcolours.column(COLOR, true, &mut notes) {
        attrs.cell.push(a);
    }
    b.set_attributes(attrs);
    let (mut complex, report) = b.build(&opts.build).map_err(|e| lines.error(path, e))?;
    if complex.n_cells() == 0 && !complex.attributes().cell.is_empty() {
        // every coloured face was dropped (one-vertex or degenerate faces): a column of zero
        // items says nothing (and OFF could not write it back)
        let mut a = complex.take_attributes();
        a.cell.clear();
        complex
            .set_attributes(a)
            .map_err(|e| IoError::new(path, e))?;
    }
    if faces.split > 0 {
        notes.push(format!(
            "fan-triangulated {} polygons with more than 4 vertices into {} triangles",
            faces.split,
            faces.split + faces.extra_tris
        ));
    }
    if faces.points > 0 {
        notes.push(format!(
            "dropped {} one-vertex faces (a point is just a vertex; read with simplices \
             to keep them as 0-simplices)",
            faces.points
        ));
    }
    if faces.read != counts.nf {
        notes.push(format!(
            "the header (line {}) announces {} faces but the file has {}: read the {} face \
             lines present (lenient option)",
            counts.line, counts.nf, faces.read, faces.read
        ));
    }
    push_build_notes(&mut notes, &report);
    Ok(ReadResult {
        complex,
        format: Format::Off,
        notes,
    })
}

/// The counts of an OFF header: the declared dimension (nOFF), vertices, faces, and the line
/// that ends them.
struct Counts {
    dim: Option<u64>,
    nv: usize,
    nf: u64,
    line: u64,
}

impl Counts {
    fn err(&self, path: &Path, msg: String) -> IoError {
        IoError::parse(path, Some(Location::Line(self.line)), msg)
    }
}

/// Reads the header keyword and the counts (on the keyword's line or the next ones).
fn read_counts(
    lr: &mut LineReader<'_, impl BufRead>,
    path: &Path,
) -> Result<(Header, Counts), IoError> {
    let mut header = Header::default();
    let mut vals: Vec<u64> = Vec::with_capacity(4);
    let mut labels: Vec<&str> = vec!["the vertex count", "the face count"];
    let counts_line;
    {
        let l = lr.expect_line("the header 'OFF'")?;
        let mut t = l.tokens();
        let first = t.word("the header 'OFF'")?;
        if parse_u64(first).is_some() {
            // No keyword: the counts come first (allowed by the OFF specification).
            header_value(&t, first, &labels, &mut vals)?;
        } else {
            header = Header::parse(first).ok_or_else(|| {
                l.err(format!(
                    "not an OFF file: the first line is '{}', expected a header keyword such as \
                     OFF, COFF, NOFF, nOFF or CNOFF",
                    shown(l.bytes, 60)
                ))
            })?;
            if header.ndim {
                labels.insert(0, "the dimension (nOFF)");
            }
        }
        let mut done_line = None;
        while let Some(tok) = t.next_token() {
            if tok.eq_ignore_ascii_case(b"BINARY") && vals.is_empty() {
                return Err(l.err("binary OFF is not supported (convert it to text OFF)"));
            }
            if vals.len() > labels.len() {
                return Err(t.err(format!(
                    "unexpected extra value '{}' on the header line",
                    shown(tok, 40)
                )));
            }
            header_value(&t, tok, &labels, &mut vals)?;
            if vals.len() >= labels.len() {
                done_line = Some(l.no);
            }
        }
        counts_line = done_line;
    }
    let mut counts_line = counts_line.unwrap_or(0);
    while vals.len() < labels.len() {
        let what = labels[vals.len()];
        let l = lr.expect_line(what)?;
        let mut t = l.tokens();
        while let Some(tok) = t.next_token() {
            if vals.len() > labels.len() {
                return Err(t.err(format!(
                    "unexpected extra value '{}' after the counts",
                    shown(tok, 40)
                )));
            }
            header_value(&t, tok, &labels, &mut vals)?;
        }
        counts_line = l.no;
    }
    let (dim_decl, nv, nf) = if header.ndim {
        (Some(vals[0]), vals[1], vals[2])
    } else {
        (None, vals[0], vals[1])
    };
    let at_counts = |msg: String| IoError::parse(path, Some(Location::Line(counts_line)), msg);
    if nv >= u32::MAX as u64 {
        return Err(at_counts(format!(
            "vertex count {nv} exceeds the 32-bit id limit of starplex"
        )));
    }
    let nv = nv as usize;
    if let Some(d) = dim_decl
        && (d == 0 || d > MAX_AMBIENT_DIM as u64)
    {
        return Err(at_counts(format!(
            "dimension {d} is outside 1..={MAX_AMBIENT_DIM}"
        )));
    }
    Ok((
        header,
        Counts {
            dim: dim_decl,
            nv,
            nf,
            line: counts_line,
        },
    ))
}

/// Reads the vertex lines: positions (homogeneous ones divided out), normals and colours.
fn read_vertices(
    lr: &mut LineReader<'_, impl BufRead>,
    path: &Path,
    header: &Header,
    counts: &Counts,
) -> Result<(ComplexBuilder, ExtraValues, ExtraValues), IoError> {
    let (dim_decl, nv) = (counts.dim, counts.nv);
    // Values that make up the position on each vertex line (None: plain OFF, set by line 1).
    let mut n_pos: Option<usize> = match (dim_decl, header.homogeneous) {
        (Some(d), h) => Some(d as usize + h as usize),
        (None, true) => Some(4),
        (None, false) if header.is_plain() => None,
        (None, false) => Some(3),
    };
    let mut first_vertex_line = 0u64;
    let mut builder: Option<ComplexBuilder> = None;
    // N: the values after the position; C: the values after those (the texture coordinates
    // of ST, last, are taken as part of the colour only when they make it 4 values or fewer)
    let mut normals = ExtraValues::new("vertex normals");
    let mut vcolours = ExtraValues::new("vertex colours");
    let mut p: Vec<f64> = Vec::with_capacity(8);
    for i in 0..nv {
        let l = lr.expect_line("a vertex line")?;
        let mut t = l.tokens();
        let n = match n_pos {
            Some(n) => n,
            None => {
                let n = t.count_rest();
                if n == 0 || n > MAX_AMBIENT_DIM {
                    return Err(l.err(format!(
                        "the first vertex line has {n} values: the ambient dimension must be in \
                         1..={MAX_AMBIENT_DIM}"
                    )));
                }
                n_pos = Some(n);
                first_vertex_line = l.no;
                n
            }
        };
        let parsed = parse_coords(&mut t, n, i, &mut p);
        if header.is_plain() && (parsed.is_err() || t.next_token().is_some()) {
            let got = l.tokens().count_rest();
            if got != n {
                return Err(l.err(format!(
                    "vertex {i} has {got} values but the first vertex line (line \
                     {first_vertex_line}) has {n}: every vertex line of a plain OFF file must \
                     have the same number of coordinates"
                )));
            }
        }
        parsed?;
        if header.homogeneous {
            let w = p.pop().unwrap_or(1.0);
            if w == 0.0 {
                return Err(l.err(format!(
                    "vertex {i}: homogeneous coordinate is 0 (a point at infinity)"
                )));
            }
            for x in p.iter_mut() {
                *x /= w;
            }
        }
        if header.normal {
            normals.push_line(&mut t, p.len(), l.no);
        }
        if header.colour {
            vcolours.push_line(&mut t, usize::MAX, l.no);
        }
        let b = match &mut builder {
            Some(b) => b,
            None => builder.insert(ComplexBuilder::new(p.len()).map_err(|e| l.err(e.to_string()))?),
        };
        b.push_vertex(&p)
            .map_err(|e| IoError::new(path, e).at(Location::Line(l.no)))?;
    }
    let b = match builder {
        Some(b) => b,
        None => {
            let d = n_pos.map_or(3, |n| n - header.homogeneous as usize);
            ComplexBuilder::new(d).map_err(|e| counts.err(path, e.to_string()))?
        }
    };
    Ok((b, normals, vcolours))
}

/// What reading the faces changed: polygons fan-triangulated (and the triangles they added
/// beyond one each), one-vertex faces dropped.
struct FaceCounts {
    split: u64,
    extra_tris: u64,
    points: u64,
    /// Face lines read (the header's count unless lenient).
    read: u64,
}

/// Reads the face lines into `b` as `opts.polygons` says, with the face colours and the line
/// of each cell.
fn read_faces(
    lr: &mut LineReader<'_, impl BufRead>,
    path: &Path,
    opts: &ReadOptions,
    counts: &Counts,
    b: &mut ComplexBuilder,
) -> Result<(CellLines, ExtraValues, FaceCounts), IoError> {
    let (nv, nf) = (counts.nv, counts.nf);
    let mut verts: Vec<u32> = Vec::with_capacity(16);
    let mut scratch: Vec<u32> = Vec::new();
    let mut split = 0u64;
    let mut extra_tris = 0u64;
    let mut points = 0u64;
    let mut face = 0u64;
    let mut lines = CellLines::default();
    let mut fcolours = ExtraValues::new("face colours");
    // lenient: read face lines until the end of the file, whatever the header's count
    while face < nf || opts.lenient {
        let eof_line = lr.line_no() + 1;
        let Some(l) = lr.next_content_line()? else {
            if opts.lenient {
                break;
            }
            return Err(IoError::new(
                path,
                IoErrorKind::CountMismatch(format!(
                    "unexpected end of file: expected face {face} of the {nf} that the header \
                     (line {}) announces: the file is truncated or the count is wrong (the \
                     lenient option reads the faces that are there)",
                    counts.line
                )),
            )
            .at(Location::Line(eof_line)));
        };
        let mut t = l.tokens();
        let k = t.u64("the face's vertex count")?;
        if k == 0 {
            return Err(l.err(format!("face {face} has no vertices")));
        }
        if opts.polygons == PolygonMode::Simplices && k > MAX_SIMPLEX_DIM as u64 + 1 {
            return Err(l.err(format!(
                "face {face} has {k} vertices: as a simplex it would have dimension {}, above \
                 the supported maximum {MAX_SIMPLEX_DIM}",
                k - 1
            )));
        }
        verts.clear();
        for _ in 0..k {
            verts.push(t.index("face vertex", 0, nv)?);
        }
        // anything after the indices is the face's colour
        fcolours.push_line(&mut t, usize::MAX, l.no);
        if !opts.build.drop_degenerate {
            // (with drop_degenerate the build drops the cells with a repeated vertex: those of
            // a fanned polygon one triangle at a time)
            check_distinct(face, &verts, nv, &mut scratch)
                .map_err(|e| IoError::new(path, e).at(Location::Line(l.no)))?;
        }
        let mut push = |b: &mut ComplexBuilder, kind: CellKind, v: &[u32]| {
            let id = b
                .push_cell(kind, v)
                .map_err(|e| IoError::new(path, e).at(Location::Line(l.no)))?;
            lines.record(id.0 as u64, l.no);
            Ok::<(), IoError>(())
        };
        let cells = match (opts.polygons, verts.len()) {
            (PolygonMode::Simplices, _) | (PolygonMode::Polygons, 2..=4) => 1,
            (PolygonMode::Polygons, 1) => 0,
            (PolygonMode::Polygons, n) => n - 2,
        };
        fcolours.repeat_last(cells);
        match (opts.polygons, verts.len()) {
            (PolygonMode::Simplices, n) => push(b, CellKind::Simplex((n - 1) as u8), &verts)?,
            (PolygonMode::Polygons, 1) => points += 1,
            (PolygonMode::Polygons, 2) => push(b, CellKind::Simplex(1), &verts)?,
            (PolygonMode::Polygons, 3) => push(b, CellKind::Simplex(2), &verts)?,
            (PolygonMode::Polygons, 4) => push(b, CellKind::Quad, &verts)?,
            (PolygonMode::Polygons, n) => {
                split += 1;
                extra_tris += n as u64 - 3;
                for j in 1..n - 1 {
                    push(b, CellKind::Simplex(2), &[verts[0], verts[j], verts[j + 1]])?;
                }
            }
        }
        face += 1;
    }
    if let Some(l) = lr.next_content_line()? {
        return Err(IoError::new(
            path,
            IoErrorKind::CountMismatch(format!(
                "unexpected content after the {nf} faces the header announced: '{}' (if these \
                 are more faces, the header's count is wrong: the lenient option reads them)",
                shown(l.bytes, 60)
            )),
        )
        .at(Location::Line(l.no)));
    }
    Ok((
        lines,
        fcolours,
        FaceCounts {
            split,
            extra_tris,
            points,
            read: face,
        },
    ))
}

/// The name of the colour attributes (vertex colours of `COFF`, face colours).
///
/// ```
/// assert_eq!(starplex::io::off::COLOR, "color");
/// ```
pub const COLOR: &str = "color";

/// The name of the vertex normal attribute (`NOFF`).
///
/// ```
/// assert_eq!(starplex::io::off::NORMAL, "normal");
/// ```
pub const NORMAL: &str = "normal";

/// Values after the fixed part of a run of lines (colours, normals): one row per line, kept as
/// long as every line has the same number of numbers (1 to 4 for colours, the dimension for
/// normals); otherwise the column is dropped with a note.
struct ExtraValues {
    what: &'static str,
    /// Values per line, from the first line.
    n: Option<usize>,
    values: Vec<f64>,
    all_int: bool,
    /// The first line that broke the rule, and why.
    broken: Option<(u64, String)>,
}

impl ExtraValues {
    fn new(what: &'static str) -> Self {
        ExtraValues {
            what,
            n: None,
            values: Vec::new(),
            all_int: true,
            broken: None,
        }
    }

    /// Reads the line's next `want` values (`usize::MAX`: the rest of the line, at most 4).
    #[inline]
    fn push_line(&mut self, t: &mut Tokens<'_>, want: usize, line: u64) {
        if self.broken.is_some() {
            return;
        }
        let start = self.values.len();
        let mut k = 0;
        while k < want {
            let Some(tok) = t.next_token() else { break };
            let Some(x) = parse_f64(tok) else {
                self.broken = Some((line, format!("'{}' is not a number", shown(tok, 20))));
                return;
            };
            self.all_int &= tok
                .iter()
                .enumerate()
                .all(|(i, c)| c.is_ascii_digit() || (i == 0 && (*c == b'-' || *c == b'+')));
            self.values.push(x);
            k += 1;
        }
        let n = self.values.len() - start;
        let limit = if want == usize::MAX { 4 } else { want };
        if n > limit || (want != usize::MAX && n > 0 && n < want) {
            self.broken = Some((line, format!("{n} values")));
            return;
        }
        match self.n {
            None => self.n = Some(n),
            Some(m) if m != n => {
                self.broken = Some((line, format!("{n} values where the first has {m}")));
            }
            _ => {}
        }
    }

    /// Repeats the last row so that it stands for `cells` cells (0: removes it).
    fn repeat_last(&mut self, cells: usize) {
        let Some(n) = self.n.filter(|_| self.broken.is_none()) else {
            return;
        };
        if n == 0 || cells == 1 {
            return;
        }
        let row: smallvec::SmallVec<[f64; 4]> = self.values[self.values.len() - n..].into();
        self.values.truncate(self.values.len() - n);
        for _ in 0..cells {
            self.values.extend_from_slice(&row);
        }
    }

    /// The column, if every line had the same number of values (at least one); integers when
    /// `int_ok` and every value was written as an integer.
    fn column(self, name: &str, int_ok: bool, notes: &mut Vec<String>) -> Option<Attribute> {
        if let Some((line, why)) = self.broken {
            notes.push(format!(
                "ignored the {}: line {line} has {why} (every line needs the same number)",
                self.what
            ));
            return None;
        }
        let n = self.n.filter(|&n| n > 0)?;
        if self.values.is_empty() {
            // every row went with its line's cells (one-vertex faces, dropped): no column
            return None;
        }
        Some(if int_ok && self.all_int {
            Attribute::int(name, n, self.values.iter().map(|&x| x as i64).collect())
        } else {
            Attribute::float(name, n, self.values)
        })
    }
}

/// The line of every cell pushed so far, kept as runs (cell `c` of a run is on line
/// `line + step * (c - first)`), so that an error of [`ComplexBuilder::build`] about a cell can
/// name its line. A file with one cell per line needs one run; gaps (comments, blank lines) and
/// fan-triangulated polygons add runs. Past [`CellLines::MAX_RUNS`] runs recording stops and later
/// cells have no known line.
#[derive(Debug, Default)]
pub(crate) struct CellLines {
    /// `(first cell, its line, step)`; step 2 = not known yet (a run of one cell).
    runs: Vec<(u64, u64, u8)>,
    /// Cells from this id on have no recorded line (recording stopped).
    limit: Option<u64>,
}

impl CellLines {
    /// At most this many runs are kept (24 MiB).
    pub(crate) const MAX_RUNS: usize = 1 << 20;

    /// Records that `cell` (ids increase by one on each call) is on `line`.
    #[inline]
    pub(crate) fn record(&mut self, cell: u64, line: u64) {
        if self.limit.is_some() {
            return;
        }
        if let Some((first, l0, step)) = self.runs.last_mut() {
            let d = cell - *first;
            if *step == 2 && d == 1 && (line == *l0 || line == *l0 + 1) {
                *step = (line - *l0) as u8;
                return;
            }
            if *step != 2 && *l0 + *step as u64 * d == line {
                return;
            }
        }
        if self.runs.len() >= Self::MAX_RUNS {
            self.limit = Some(cell);
            return;
        }
        self.runs.push((cell, line, 2));
    }

    /// The line of `cell`, when recorded.
    pub(crate) fn line(&self, cell: u64) -> Option<u64> {
        if self.limit.is_some_and(|lim| cell >= lim) {
            return None;
        }
        let i = self.runs.partition_point(|r| r.0 <= cell).checked_sub(1)?;
        let (first, l0, step) = self.runs[i];
        Some(l0 + (step % 2) as u64 * (cell - first))
    }

    /// `e` as an [`IoError`] at the line of the cell it names (the later one for duplicates).
    pub(crate) fn error(&self, path: &Path, e: ComplexError) -> IoError {
        let cell = match &e {
            ComplexError::DuplicateCell { cell, .. }
            | ComplexError::CellIsFaceOf { cell, .. }
            | ComplexError::VertexOutOfRange { cell, .. }
            | ComplexError::RepeatedVertex { cell, .. }
            | ComplexError::WrongVertexCount { cell, .. }
            | ComplexError::Kind { cell, .. } => Some(*cell),
            _ => None,
        };
        let line = cell.and_then(|c| self.line(c));
        let err = IoError::new(path, e);
        match line {
            Some(l) => err.at(Location::Line(l)),
            None => err,
        }
    }
}

/// At most `max` bytes of `b` for a message: invalid UTF-8 replaced, control characters escaped
/// (so binary garbage cannot send escape sequences to a terminal), `...` when cut.
pub(crate) fn shown(b: &[u8], max: usize) -> String {
    let mut s = String::new();
    for c in String::from_utf8_lossy(&b[..b.len().min(max)]).chars() {
        if c.is_control() {
            s.extend(c.escape_default());
        } else {
            s.push(c);
        }
    }
    if b.len() > max {
        s.push_str("...");
    }
    s
}

/// Parses the first `n` values of a vertex line into `p` (extras are left unread).
#[inline]
fn parse_coords(t: &mut Tokens<'_>, n: usize, i: usize, p: &mut Vec<f64>) -> Result<(), IoError> {
    p.clear();
    for axis in 0..n {
        let Some(tok) = t.next_token() else {
            return Err(t.err(format!(
                "vertex {i}: expected coordinate {axis} of {n}, found the end of the line"
            )));
        };
        match parse_f64(tok) {
            Some(x) if x.is_finite() => p.push(x),
            Some(x) => {
                return Err(t.err(format!("vertex {i}: coordinate {axis} is not finite ({x})")))
            }
            None => {
                return Err(t.err(format!(
                    "vertex {i}: expected coordinate {axis} (a number), found '{}'",
                    shown(tok, 40)
                )))
            }
        }
    }
    Ok(())
}

/// Indices already checked in range; checks that they are pairwise distinct ([`check_cell`] for
/// small faces, a sort for large polygons so that a huge face is not quadratic).
fn check_distinct(
    face: u64,
    verts: &[u32],
    nv: usize,
    scratch: &mut Vec<u32>,
) -> Result<(), ComplexError> {
    if verts.len() <= 32 {
        return check_cell(face, verts, nv);
    }
    scratch.clear();
    scratch.extend_from_slice(verts);
    scratch.sort_unstable();
    match scratch.windows(2).find(|w| w[0] == w[1]) {
        Some(w) => Err(ComplexError::RepeatedVertex {
            cell: face,
            vertex: w[0] as u64,
        }),
        None => Ok(()),
    }
}

/// Refuses what plain OFF (faces read back as polygons) cannot hold: 0-simplices, simplices of
/// dimension 3 and more (their faces of 4+ vertices read back as quads or fans of triangles:
/// write them with [`write_simplices`], format `off-simplices`) and 3D CP cells.
///
/// ```
/// use starplex::cell::CellKind;
/// use starplex::complex::IndexedComplex;
/// use starplex::io::off;
/// let tet = IndexedComplex::from_parts(3, vec![0.0; 12].into(),
///                                      vec![(CellKind::Simplex(3), vec![0, 1, 2, 3].into())]).unwrap();
/// let e = off::check(&tet).unwrap_err();
/// assert!(e.to_string().contains("off-simplices"), "{e}");
/// assert!(off::check_simplices(&tet).is_ok());
/// ```
///
/// # Errors
/// [`IoErrorKind::CannotWrite`] naming the first cell that cannot be written and the way out.
pub fn check(k: &IndexedComplex) -> Result<(), IoErrorKind> {
    for b in k.blocks() {
        let reason = match b.kind {
            CellKind::Simplex(1) | CellKind::Simplex(2) | CellKind::Quad => continue,
            CellKind::Simplex(0) => format!(
                "cell {} is a vertex (a 0-simplex top cell), which OFF readers drop; write \
                 off-simplices (the Stellar convention, read back as simplices), spx or spb",
                b.first
            ),
            CellKind::Simplex(d) => format!(
                "cell {} is a {d}-simplex, whose {} vertices an OFF reader takes for a polygon \
                 (a tetrahedron comes back as a quad); write off-simplices (the Stellar \
                 convention, read back as simplices), or the boundary surface",
                b.first,
                d + 1
            ),
            kind => format!(
                "OFF holds simplices and polygons, not 3D cells; cell {} is a {} (write its \
                 boundary surface, or use vtk, msh, mesh, spx or spb)",
                b.first,
                kind.type_name()
            ),
        };
        return Err(IoErrorKind::CannotWrite {
            format: Format::Off,
            reason,
        });
    }
    Ok(())
}

/// Refuses what OFF read as simplices (format `off-simplices`) cannot hold: CP cells (a quad's 4
/// vertices would come back as a tetrahedron).
///
/// ```
/// use starplex::cell::CellKind;
/// use starplex::complex::IndexedComplex;
/// use starplex::io::off;
/// let quad = IndexedComplex::from_parts(2, vec![0.0; 8].into(),
///                                       vec![(CellKind::Quad, vec![0, 1, 2, 3].into())]).unwrap();
/// assert!(off::check_simplices(&quad).is_err());
/// assert!(off::check(&quad).is_ok());
/// ```
///
/// # Errors
/// [`IoErrorKind::CannotWrite`] naming the first CP cell.
pub fn check_simplices(k: &IndexedComplex) -> Result<(), IoErrorKind> {
    match k.blocks().iter().find(|b| !b.kind.is_simplex()) {
        None => Ok(()),
        Some(b) => Err(IoErrorKind::CannotWrite {
            format: Format::OffSimplices,
            reason: format!(
                "off-simplices reads every face as a simplex, and cell {} is a {} (write off, \
                 or triangulate first)",
                b.first,
                b.kind.type_name()
            ),
        }),
    }
}

/// Writes `k` as plain OFF (`COFF` when it has a vertex [`COLOR`] column, see [`holds`]; face
/// colours after each face's indices): `OFF`, the counts, one line of `ambient_dim` coordinates per vertex
/// (the Stellar reference's convention when the ambient dimension is not 3), then one line
/// `k i_0 .. i_{k-1}` per cell in cell-id order (so cell ids survive a round trip). A complex
/// with no vertex and an ambient dimension other than 3 is written as `nOFF` so that its
/// dimension survives.
///
/// Edges, triangles and quads are written (see [`check`]); [`write_simplices`] writes simplices
/// of every dimension.
///
/// ```
/// use starplex::cell::CellKind;
/// use starplex::complex::{BuildOptions, ComplexBuilder};
/// use starplex::io::{off, IoErrorKind};
/// let mut b = ComplexBuilder::new(3).unwrap();
/// for p in [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0],
///           [0.0, 0.0, 1.0], [1.0, 0.0, 1.0], [1.0, 1.0, 1.0], [0.0, 1.0, 1.0]] {
///     b.push_vertex(&p).unwrap();
/// }
/// b.push_cell(CellKind::Hex, &[0, 1, 2, 3, 4, 5, 6, 7]).unwrap();
/// let (k, _) = b.build(&BuildOptions::default()).unwrap();
/// let err = off::write(&mut Vec::new(), &k).unwrap_err();
/// assert!(matches!(err, IoErrorKind::CannotWrite { .. }));
/// ```
///
/// # Errors
/// [`IoErrorKind::CannotWrite`] (see [`check`]); OS errors of the writer.
pub fn write(w: &mut dyn Write, k: &IndexedComplex) -> Result<(), IoErrorKind> {
    check(k)?;
    write_faces(w, k)
}

/// Writes `k` as OFF whose faces are simplices of any dimension (the Stellar reference's
/// convention, format `off-simplices`): read it back with [`PolygonMode::Simplices`]
/// (`--simplices`, or `--format off-simplices`).
///
/// ```
/// use starplex::cell::CellKind;
/// use starplex::complex::IndexedComplex;
/// use starplex::io::{off, PolygonMode, ReadOptions};
/// let tet = IndexedComplex::from_parts(3, vec![0., 0., 0., 1., 0., 0., 0., 1., 0., 0., 0., 1.].into(),
///                                      vec![(CellKind::Simplex(3), vec![0, 1, 2, 3].into())]).unwrap();
/// let mut out = Vec::new();
/// off::write_simplices(&mut out, &tet).unwrap();
/// let opts = ReadOptions { polygons: PolygonMode::Simplices, ..Default::default() };
/// assert_eq!(off::read_from(&out[..], "t.off".as_ref(), &opts).unwrap().complex, tet);
/// ```
///
/// # Errors
/// [`IoErrorKind::CannotWrite`] for CP cells (see [`check_simplices`]); OS errors of the writer.
pub fn write_simplices(w: &mut dyn Write, k: &IndexedComplex) -> Result<(), IoErrorKind> {
    check_simplices(k)?;
    write_faces(w, k)
}

/// Whether OFF holds the attribute `a` of `target`: the vertex and the cell column named
/// [`COLOR`] of 1 to 4 components (integers up to 2^53 in magnitude, or finite floats). Vertex
/// normals are read, not written.
///
/// ```
/// use starplex::attr::{AttrTarget, Attribute};
/// use starplex::io::off;
/// assert!(off::holds(AttrTarget::Cell, &Attribute::int("color", 3, vec![255, 0, 0])));
/// assert!(!off::holds(AttrTarget::Cell, &Attribute::float("color", 3, vec![f64::NAN, 0.0, 0.0])));
/// assert!(!off::holds(AttrTarget::Vertex, &Attribute::float("normal", 3, vec![0.0, 0.0, 1.0])));
/// ```
pub fn holds(target: AttrTarget, a: &Attribute) -> bool {
    let _ = target;
    a.name == COLOR
        && (1..=4).contains(&a.components)
        && match &a.values {
            AttrValues::Int(v) => v.iter().all(|x| x.unsigned_abs() <= 1 << 53),
            AttrValues::Float(v) => v.iter().all(|x| x.is_finite()),
        }
}

/// The column of `cols` that OFF writes (see [`holds`]).
fn colour_column(target: AttrTarget, cols: &[Attribute]) -> Option<&Attribute> {
    cols.iter().find(|a| holds(target, a))
}

/// Appends the values of item `i` of `a` (` v` each; floats always with a `.` or an exponent,
/// so that they read back as floats).
fn push_values(s: &mut Vec<u8>, a: &Attribute, i: usize) -> std::io::Result<()> {
    let c = a.components;
    for j in i * c..(i + 1) * c {
        s.push(b' ');
        match &a.values {
            AttrValues::Int(v) => {
                use std::io::Write as _;
                write!(s, "{}", v[j])?
            }
            AttrValues::Float(v) => {
                let at = s.len();
                write_f64(s, v[j])?;
                if s[at..].iter().all(|c| c.is_ascii_digit() || *c == b'-') {
                    s.extend_from_slice(b".0");
                }
            }
        }
    }
    Ok(())
}

fn write_faces(w: &mut dyn Write, k: &IndexedComplex) -> Result<(), IoErrorKind> {
    let d = k.ambient_dim();
    let vcol = colour_column(AttrTarget::Vertex, &k.attributes().vertex);
    let fcol = colour_column(AttrTarget::Cell, &k.attributes().cell);
    let c = if vcol.is_some() { "C" } else { "" };
    if (k.n_vertices() == 0 || vcol.is_some()) && d != 3 {
        // No vertex line to carry the dimension, or a COFF whose vertex lines do not: say it
        // in the header.
        writeln!(w, "{c}nOFF\n{d}")?;
    } else {
        writeln!(w, "{c}OFF")?;
    }
    writeln!(w, "{} {} 0", k.n_vertices(), k.n_cells())?;
    let mut line: Vec<u8> = Vec::with_capacity(128);
    for (i, p) in k.coords().chunks_exact(d).enumerate() {
        line.clear();
        for (j, &x) in p.iter().enumerate() {
            if j > 0 {
                line.push(b' ');
            }
            write_f64(&mut line, x)?;
        }
        if let Some(a) = vcol {
            push_values(&mut line, a, i)?;
        }
        line.push(b'\n');
        w.write_all(&line)?;
    }
    let mut id = 0;
    for b in k.blocks() {
        let n = b.kind.n_vertices();
        for i in 0..b.len() {
            use std::io::Write as _;
            line.clear();
            write!(line, "{n}")?;
            for v in b.cell(i) {
                write!(line, " {v}")?;
            }
            if let Some(a) = fcol {
                push_values(&mut line, a, id)?;
            }
            id += 1;
            line.push(b'\n');
            w.write_all(&line)?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::io::IoError;

    fn rd(text: &str) -> Result<ReadResult, IoError> {
        read_from(text.as_bytes(), "t.off".as_ref(), &ReadOptions::default())
    }

    fn rd_simplices(text: &str) -> Result<ReadResult, IoError> {
        let opts = ReadOptions {
            polygons: PolygonMode::Simplices,
            ..Default::default()
        };
        read_from(text.as_bytes(), "t.off".as_ref(), &opts)
    }

    fn err(text: &str) -> String {
        match rd(text) {
            Ok(_) => panic!("expected an error for {text:?}"),
            Err(e) => e.to_string(),
        }
    }

    #[test]
    fn header_keywords() {
        for (kw, ok) in [
            ("OFF", true),
            ("COFF", true),
            ("NOFF", true),
            ("CNOFF", true),
            ("NCOFF", true),
            ("STCNOFF", true),
            ("nOFF", true),
            ("4OFF", true),
            ("CCOFF", false),
            ("OFFX", false),
            ("XOFF", false),
            ("off", false),
        ] {
            assert_eq!(Header::parse(kw.as_bytes()).is_some(), ok, "{kw}");
        }
    }

    #[test]
    fn counts_on_header_line_comments_tabs_crlf() {
        let text = "# a comment\r\nOFF\t3 1 0 # counts here\r\n\r\n0 0 0\r\n1\t0 0\r\n  0 1 0  \r\n# face\r\n3 0 1 2\r\n";
        let r = rd(text).unwrap();
        assert_eq!(r.complex.n_vertices(), 3);
        assert_eq!(r.complex.n_cells(), 1);
        assert_eq!(r.complex.ambient_dim(), 3);
    }

    #[test]
    fn counts_without_edges_and_without_keyword() {
        let r = rd("OFF\n3 1\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n").unwrap();
        assert_eq!(r.complex.n_cells(), 1);
        let r = rd("3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n").unwrap();
        assert_eq!(r.complex.n_cells(), 1);
    }

    #[test]
    fn coff_noff_extras_are_attributes() {
        let text = "COFF\n3 1 0\n0 0 0 255 0 0 255\n1 0 0 0 255 0 255\n0 1 0 0 0 255 255\n3 0 1 2 10 20 30\n";
        let r = rd(text).unwrap();
        assert_eq!(r.complex.ambient_dim(), 3);
        assert_eq!(r.complex.coords(), &[0., 0., 0., 1., 0., 0., 0., 1., 0.]);
        let a = r.complex.attributes();
        assert_eq!(
            a.vertex,
            [Attribute::int(
                COLOR,
                4,
                vec![255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255]
            )]
        );
        assert_eq!(a.cell, [Attribute::int(COLOR, 3, vec![10, 20, 30])]);
        let text =
            "CNOFF\n3 1 0\n0 0 0 0 0 1 1 .5 1\n1 0 0 0 0 1 1 1 1\n0 1 0 0 0 1 1 1 1\n3 0 1 2\n";
        let a = rd(text).unwrap().complex.take_attributes();
        assert_eq!(
            a.vertex[0],
            Attribute::float(NORMAL, 3, [0., 0., 1.].repeat(3))
        );
        assert_eq!(
            a.vertex[1],
            Attribute::float(COLOR, 3, vec![1., 0.5, 1., 1., 1., 1., 1., 1., 1.])
        );
        // lines that disagree: no column, a note
        let text = "COFF\n3 1 0\n0 0 0 1 1 1\n1 0 0 1 1\n0 1 0 1 1 1\n3 0 1 2\n";
        let r = rd(text).unwrap();
        assert!(r.complex.attributes().is_empty());
        assert!(
            r.notes[0].contains("ignored the vertex colours: line 4 has 2 values"),
            "{:?}",
            r.notes
        );
        let text = "NOFF\n3 1 0\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n";
        assert_eq!(rd(text).unwrap().complex.ambient_dim(), 3);
        let text =
            "CNOFF\n3 1 0\n0 0 0 0 0 1 1 1 1\n1 0 0 0 0 1 1 1 1\n0 1 0 0 0 1 1 1 1\n3 0 1 2\n";
        assert_eq!(rd(text).unwrap().complex.ambient_dim(), 3);
    }

    #[test]
    fn noff_dimension_line_and_homogeneous() {
        let text = "nOFF\n4\n3 1 0\n0 0 0 0\n1 0 0 0\n0 1 0 1\n3 0 1 2\n";
        let r = rd(text).unwrap();
        assert_eq!(r.complex.ambient_dim(), 4);
        let r = rd("nOFF 2 3 1 0\n0 0\n1 0\n0 1\n3 0 1 2\n").unwrap();
        assert_eq!(r.complex.ambient_dim(), 2);
        let r = rd("4OFF\n3 1 0\n0 0 0 2\n2 0 0 2\n0 4 0 2\n3 0 1 2\n").unwrap();
        assert_eq!(r.complex.coords(), &[0., 0., 0., 1., 0., 0., 0., 2., 0.]);
        assert!(err("4OFF\n1 0 0\n1 1 1 0\n").contains("homogeneous coordinate is 0"));
        assert!(err("nOFF\n0\n0 0 0\n").contains("dimension 0 is outside"));
    }

    #[test]
    fn plain_off_takes_the_dimension_from_the_first_vertex_line() {
        let text = "OFF\n3 1 0\n0 0 0 0 0\n1 0 0 0 0\n0 1 0 0 0.5\n3 0 1 2\n";
        assert_eq!(rd(text).unwrap().complex.ambient_dim(), 5);
        let e = err("OFF\n3 1 0\n0 0 0 0 0\n1 0 0 0\n0 1 0 0 0.5\n3 0 1 2\n");
        assert!(
            e.starts_with(
                "t.off:4: vertex 1 has 4 values but the first vertex line (line 3) has 5"
            ),
            "{e}"
        );
    }

    #[test]
    fn polygon_mode() {
        let text = "OFF\n7 4 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n-1 1 0\n5 5 5\n6 6 6\n5 0 1 2 3 4\n2 5 6\n1 6\n4 1 0 6 4 9 9 9\n";
        let r = rd(text).unwrap();
        let kinds: Vec<_> = r.complex.cells().map(|c| c.kind).collect();
        assert_eq!(
            kinds,
            vec![
                CellKind::Simplex(2),
                CellKind::Simplex(2),
                CellKind::Simplex(2),
                CellKind::Simplex(1),
                CellKind::Quad
            ]
        );
        assert_eq!(r.complex.cells().next().unwrap().vertices, &[0, 1, 2]);
        assert_eq!(r.notes.len(), 3, "{:?}", r.notes);
        // only the quad has a colour: no face colour column, said so
        assert!(r.notes[0]
            .contains("ignored the face colours: line 13 has 3 values where the first has 0"));
        assert!(r.notes[1].contains("fan-triangulated 1 polygons"));
        assert!(r.notes[2].contains("dropped 1 one-vertex faces"));
    }

    #[test]
    fn simplex_mode_any_size() {
        let nv = 70;
        let text = |faces: &[Vec<u32>]| {
            let mut t = format!("OFF\n{nv} {} 0\n", faces.len());
            for i in 0..nv {
                t.push_str(&format!("{i} 0 0\n"));
            }
            for f in faces {
                let s: Vec<String> = f.iter().map(|i| i.to_string()).collect();
                t.push_str(&format!("{} {}\n", f.len(), s.join(" ")));
            }
            t
        };
        let r = rd_simplices(&text(&[(0..65).collect(), vec![68, 69]])).unwrap();
        let kinds: Vec<_> = r.complex.cells().map(|c| c.kind).collect();
        assert_eq!(kinds, vec![CellKind::Simplex(64), CellKind::Simplex(1)]);
        let e = rd_simplices(&text(&[(0..66).collect()]))
            .unwrap_err()
            .to_string();
        assert!(e.contains(":73: face 0 has 66 vertices"), "{e}");
        // In polygon mode a 66-gon is a fan; the repeat check of large faces sorts.
        let r = rd(&text(&[(0..66).collect()])).unwrap();
        assert_eq!(r.complex.n_cells(), 64);
        let e = err(&text(&[(0..40).chain([3]).collect()]));
        assert!(
            e.contains(":73: cell 0: vertex 3 appears more than once"),
            "{e}"
        );
    }

    #[test]
    fn errors_name_the_line() {
        let ok = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
        let cases: &[(&str, &str)] = &[
            ("", "t.off:1: unexpected end of file"),
            ("PLY\n", "t.off:1: not an OFF file"),
            ("OFF BINARY\n", "binary OFF is not supported"),
            ("OFF\n3 x 0\n", "t.off:2: expected the face count"),
            ("OFF\n3 1 0 7\n", "t.off:2: unexpected extra value '7'"),
            ("OFF\n3 1 0\n0 0 0\n1 0 0\n", "t.off:5: unexpected end of file"),
            ("OFF\n3 1 0\n0 0 0\n1 0 zz\n0 1 0\n3 0 1 2\n", "t.off:4: vertex 1: expected coordinate 2 (a number), found 'zz'"),
            ("OFF\n3 1 0\n0 0 0\n1 0 nan\n0 1 0\n3 0 1 2\n", "t.off:4: vertex 1: coordinate 2 is not finite"),
            ("OFF\n3 1 0\n0 0 0\n1 0 inf\n0 1 0\n3 0 1 2\n", "t.off:4: vertex 1: coordinate 2 is not finite"),
            ("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", "t.off:6: face vertex 3 is out of range"),
            ("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 1\n", "t.off:6: cell 0: vertex 1 appears more than once"),
            ("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1\n", "t.off:6: expected face vertex, found the end of the line"),
            ("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n0\n", "t.off:6: face 0 has no vertices"),
            ("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 2\n", "t.off:7: unexpected content after the 1 faces"),
            ("OFF\n3 1000000000000 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "t.off:7: unexpected end of file"),
            ("OFF\n5000000000 1 0\n", "t.off:2: vertex count 5000000000 exceeds"),
            ("OFF\n1 0 0\n1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 17 18 19 20 21 22 23 24 25 26 27 28 29 30 31 32 33 34 35 36 37 38 39 40 41 42 43 44 45 46 47 48 49 50 51 52 53 54 55 56 57 58 59 60 61 62 63 64 65\n", "t.off:3: the first vertex line has 65 values"),
        ];
        assert!(rd(ok).is_ok());
        for (text, want) in cases {
            let e = err(text);
            assert!(e.contains(want), "{text:?}: got '{e}', want '{want}'");
        }
    }

    #[test]
    fn messages_escape_control_characters() {
        assert_eq!(shown(b"\x1b[31mX\tY", 40), "\\u{1b}[31mX\\tY");
        assert_eq!(shown(b"abcdef", 3), "abc...");
        let e = read_from(
            &b"\x1b[2J\xff\n"[..],
            "t.off".as_ref(),
            &ReadOptions::default(),
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("'\\u{1b}[2J\u{fffd}'"), "{e}");
    }

    #[test]
    fn cell_lines_follow_gaps_and_fans() {
        let mut cl = CellLines::default();
        // cells 0..3 on lines 10..13, a comment, cells 3..5 on 15..17, a fan of 3 on line 18.
        for (c, l) in [
            (0, 10),
            (1, 11),
            (2, 12),
            (3, 15),
            (4, 16),
            (5, 18),
            (6, 18),
            (7, 18),
            (8, 19),
            (9, 20),
        ] {
            cl.record(c, l);
        }
        let got: Vec<_> = (0..10).map(|c| cl.line(c).unwrap()).collect();
        assert_eq!(got, vec![10, 11, 12, 15, 16, 18, 18, 18, 19, 20]);
        assert_eq!(cl.runs.len(), 4);
    }

    #[test]
    fn duplicate_faces_go_to_the_builder() {
        let text = "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n# c\n3 2 1 0\n";
        let e = err(text);
        assert!(
            e.starts_with("t.off:8: cell 1 has the same vertices as cell 0"),
            "{e}"
        );
        let e = err("OFF\n5 2 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n2 2 2\n5 0 1 3 2 4\n2 2 4\n");
        assert!(
            e.starts_with("t.off:9: cell 3 (line) is a face of cell 2"),
            "{e}"
        );
        let mut opts = ReadOptions::default();
        opts.build.drop_duplicates = true;
        let r = read_from(text.as_bytes(), "t.off".as_ref(), &opts).unwrap();
        assert_eq!(r.complex.n_cells(), 1);
        assert!(r.notes.iter().any(|n| n.contains("duplicate")));
    }

    #[test]
    fn empty_complex_and_isolated_vertices() {
        let r = rd("OFF\n0 0 0\n").unwrap();
        assert_eq!(r.complex.n_vertices(), 0);
        assert_eq!(r.complex.ambient_dim(), 3);
        let r = rd("nOFF 5 0 0 0\n").unwrap();
        assert_eq!(r.complex.ambient_dim(), 5);
        let mut out = Vec::new();
        write(&mut out, &r.complex).unwrap();
        assert_eq!(
            rd(std::str::from_utf8(&out).unwrap()).unwrap().complex,
            r.complex
        );
        let r = rd("OFF\n2 0 0\n0 0\n1 1\n").unwrap();
        assert_eq!(r.complex.ambient_dim(), 2);
        assert_eq!(r.complex.n_isolated_vertices(), 2);
    }
}
