//! `.spx`, the starplex text format (see `FORMATS.md`):
//!
//! ```text
//! SPX 1                            (SPX 2 when attribute sections follow the cells)
//! # comments anywhere
//! <ambient_dim> <n_vertices> <n_cells>
//! x_1 ... x_ambient_dim            (n_vertices lines)
//! <type> <k> v_0 ... v_{k-1}       (n_cells lines; type line|tri|quad|tet|pyramid|prism|hex|simplex)
//! attribute <vertex|cell> <int|float> <components> <name>   (version 2 only, any number of
//! a_1 ... a_components                  sections: one value line per vertex or per cell)
//! ```
//!
//! The writer writes version 1 for a complex without attributes (so older starplex reads it) and
//! version 2 otherwise; the reader takes both. Names are percent-encoded into one token (`%20`
//! for a space, `%` alone for the empty name); floats are written in their shortest round-trip
//! form (`NaN`, `inf` included), so values come back exactly.
//!
//! ```
//! use starplex::attr::{Attribute, Attributes};
//! use starplex::io::{spx, ReadOptions};
//! let text = "SPX 2\n1 2 1\n0\n1\nline 2 0 1\nattribute vertex float 2 my%20speed\n0.5 NaN\n-1 1e300\n";
//! let r = spx::read_from(text.as_bytes(), "a.spx".as_ref(), &ReadOptions::default()).unwrap();
//! assert_eq!(r.complex.attributes().vertex[0].name, "my speed");
//! let mut out = Vec::new();
//! spx::write(&mut out, &r.complex).unwrap();
//! assert!(String::from_utf8(out).unwrap().starts_with("SPX 2\n"));
//! ```
//!
//! ```
//! use starplex::io::{spx, ReadOptions};
//! let text = "SPX 1\n2 3 1\n0 0\n1 0\n0 1\ntri 3 0 1 2\n";
//! let r = spx::read_from(text.as_bytes(), "mem.spx".as_ref(), &ReadOptions::default()).unwrap();
//! assert_eq!(r.complex.n_cells(), 1);
//! let mut out = Vec::new();
//! spx::write(&mut out, &r.complex).unwrap();
//! assert!(String::from_utf8(out).unwrap().ends_with("tri 3 0 1 2\n"));
//! ```
use std::io::{BufRead, Write};
use std::path::Path;

use super::faces::push_build_notes;
use super::text::{write_f64, LineReader};
use super::{Format, IoError, IoErrorKind, Location, ReadOptions, ReadResult};
use crate::cell::CellKind;
use crate::complex::{ComplexBuilder, IndexedComplex};

/// Reads a `.spx` file.
///
/// ```
/// use starplex::io::{spx, ReadOptions};
/// use starplex::cell::CellKind;
/// let path = std::env::temp_dir().join(format!("starplex-doc-spx-read-{}.spx", std::process::id()));
/// std::fs::write(&path, "SPX 1\n# a lone edge\n1 2 1\n0\n1\nline 2 0 1\n").unwrap();
/// let r = spx::read(&path, &ReadOptions::default()).unwrap();
/// std::fs::remove_file(&path).unwrap();
/// assert_eq!(r.complex.blocks()[0].kind, CellKind::Simplex(1));
/// ```
///
/// # Errors
/// See [`read_from`].
pub fn read(path: &Path, opts: &ReadOptions) -> Result<ReadResult, IoError> {
    let f = std::fs::File::open(path).map_err(|e| IoError::new(path, e))?;
    read_from(std::io::BufReader::with_capacity(1 << 20, f), path, opts)
}

/// Reads `.spx` text from any buffered reader; `path` names it in errors.
///
/// ```
/// use starplex::io::{spx, ReadOptions};
/// use starplex::cell::CellKind;
/// // A 4-simplex in 4D (type `simplex`, 5 vertices) and an unknown type.
/// let text = "SPX 1\n4 5 1\n0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\n0 0 0 1\nsimplex 5 0 1 2 3 4\n";
/// let r = spx::read_from(text.as_bytes(), "m.spx".as_ref(), &ReadOptions::default()).unwrap();
/// assert_eq!(r.complex.blocks()[0].kind, CellKind::Simplex(4));
/// let bad = text.replace("simplex 5", "cube 5");
/// assert!(spx::read_from(bad.as_bytes(), "m.spx".as_ref(), &ReadOptions::default()).is_err());
/// ```
///
/// # Errors
/// A missing header, malformed or non-finite numbers, wrong token counts, unknown cell types,
/// out-of-range or repeated vertex indices (with the line), a file shorter or longer than its
/// counts say, and the maximality checks of [`ComplexBuilder::build`].
pub fn read_from(r: impl BufRead, path: &Path, opts: &ReadOptions) -> Result<ReadResult, IoError> {
    let mut lr = LineReader::new(r, path, Some(b'#'));
    let version = {
        let l = lr.expect_line("the header 'SPX 1'")?;
        let mut t = l.tokens();
        if t.word("'SPX'")? != b"SPX" {
            return Err(l.err(format!(
                "not an .spx file: the first line is '{}', expected 'SPX 1'",
                l.text()
            )));
        }
        let v = t.u64("the format version")?;
        if v != 1 && v != 2 {
            return Err(l.err(format!(
                "unsupported .spx version {v} (this starplex reads versions 1 and 2)"
            )));
        }
        t.end()?;
        v
    };
    let (ambient, nv, nc) = {
        let l = lr.expect_line("the counts '<ambient_dim> <n_vertices> <n_cells>'")?;
        let mut t = l.tokens();
        let a = t.u64("the ambient dimension")?;
        let nv = t.u64("the vertex count")?;
        let nc = t.u64("the cell count")?;
        t.end()?;
        if a == 0 || a > crate::complex::MAX_AMBIENT_DIM as u64 {
            return Err(l.err(format!("ambient dimension {a} is outside 1..=64")));
        }
        if nv >= u32::MAX as u64 || nc >= u32::MAX as u64 {
            return Err(l.err(format!(
                "counts {nv} vertices / {nc} cells exceed the 32-bit id limit of starplex"
            )));
        }
        (a as usize, nv as usize, nc as usize)
    };
    let mut b = ComplexBuilder::new(ambient).map_err(|e| IoError::new(path, e))?;
    let mut p = vec![0.0f64; ambient];
    for i in 0..nv {
        let l = lr.expect_line(format_args!("vertex {i} of {nv}"))?;
        let mut t = l.tokens();
        for (axis, x) in p.iter_mut().enumerate() {
            *x = t.f64(format_args!("coordinate {axis} of vertex {i}"))?;
        }
        t.end()?;
        b.push_vertex(&p)
            .map_err(|e| IoError::new(path, e).at(Location::Line(l.no)))?;
    }
    let mut verts: Vec<u32> = Vec::with_capacity(8);
    let mut last: Option<(Vec<u8>, usize, CellKind)> = None;
    for i in 0..nc {
        let l = lr.expect_line(format_args!("cell {i} of {nc}"))?;
        let mut t = l.tokens();
        let name = t.word("the cell type")?;
        let k = t.u64("the cell's vertex count")? as usize;
        let kind = match &last {
            Some((n, kk, kind)) if n.as_slice() == name && *kk == k => *kind,
            _ => {
                let s = std::str::from_utf8(name).unwrap_or("?");
                let kind = CellKind::from_spx(s, k).map_err(|e| l.err(e.to_string()))?;
                last = Some((name.to_vec(), k, kind));
                kind
            }
        };
        verts.clear();
        for _ in 0..k {
            verts.push(t.index(format_args!("cell {i}: vertex index"), 0, nv)?);
        }
        t.end()?;
        opts.build
            .check_cell(i as u64, &verts, nv)
            .map_err(|e| IoError::new(path, e).at(Location::Line(l.no)))?;
        b.push_cell(kind, &verts)
            .map_err(|e| IoError::new(path, e).at(Location::Line(l.no)))?;
    }
    if version >= 2 {
        let line = lr.line_no() + 1;
        let attrs = super::spx_attrs::read(&mut lr, nv, nc)?;
        attrs.check(nv, nc).map_err(|e| {
            IoError::new(path, crate::complex::ComplexError::from(e)).at(Location::Line(line))
        })?;
        b.set_attributes(attrs);
    } else if let Some(l) = lr.next_content_line()? {
        let hint = if l.bytes.starts_with(super::spx_attrs::KEYWORD) {
            " (attribute sections need the header 'SPX 2')"
        } else {
            ""
        };
        return Err(l.err(format!(
            "unexpected content after the {nc} cells the header announced: '{}'{hint}",
            String::from_utf8_lossy(&l.bytes[..l.bytes.len().min(60)])
        )));
    }
    let (complex, report) = b.build(&opts.build).map_err(|e| IoError::new(path, e))?;
    let mut notes = Vec::new();
    push_build_notes(&mut notes, &report);
    Ok(ReadResult {
        complex,
        format: Format::Spx,
        notes,
    })
}

/// Writes `k` as `.spx`: version 1 without attributes, version 2 with its attribute sections
/// otherwise.
///
/// ```
/// use starplex::io::spx;
/// # use starplex::complex::IndexedComplex;
/// # use starplex::cell::CellKind;
/// let k = IndexedComplex::from_parts(2, vec![0.0, 0.0, 1.5, 0.0, 0.0, 1.0, 1.5, 1.0].into(),
///                                    vec![(CellKind::Quad, vec![0, 1, 3, 2].into())]).unwrap();
/// let mut out = Vec::new();
/// spx::write(&mut out, &k).unwrap();
/// let text = String::from_utf8(out).unwrap();
/// let lines: Vec<&str> = text.lines().filter(|l| !l.starts_with('#')).collect();
/// assert_eq!(lines, ["SPX 1", "2 4 1", "0 0", "1.5 0", "0 1", "1.5 1", "quad 4 0 1 3 2"]);
/// ```
///
/// # Errors
/// OS errors of the writer.
pub fn write(w: &mut dyn Write, k: &IndexedComplex) -> Result<(), IoErrorKind> {
    let attrs = k.attributes();
    writeln!(w, "SPX {}", if attrs.is_empty() { 1 } else { 2 })?;
    writeln!(w, "# written by starplex {}", env!("CARGO_PKG_VERSION"))?;
    writeln!(w, "{} {} {}", k.ambient_dim(), k.n_vertices(), k.n_cells())?;
    for p in k.coords().chunks_exact(k.ambient_dim()) {
        for (i, &x) in p.iter().enumerate() {
            if i > 0 {
                w.write_all(b" ")?;
            }
            write_f64(w, x)?;
        }
        w.write_all(b"\n")?;
    }
    let mut line = String::with_capacity(128);
    for b in k.blocks() {
        let prefix = format!("{} {}", b.kind.spx_name(), b.kind.n_vertices());
        for i in 0..b.len() {
            use std::fmt::Write as _;
            line.clear();
            line.push_str(&prefix);
            for v in b.cell(i) {
                let _ = write!(line, " {v}");
            }
            line.push('\n');
            w.write_all(line.as_bytes())?;
        }
    }
    super::spx_attrs::write(w, attrs)?;
    Ok(())
}
