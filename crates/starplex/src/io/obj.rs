//! Wavefront OBJ: `v` vertices, `f` faces and `l` polylines (reader and writer).
//!
//! The reader is starplex's own streaming line reader, not `tobj`: `tobj` renumbers vertices per
//! object/group in order of first use (so vertex ids change, isolated vertices disappear and a
//! vertex shared by two groups becomes two vertices, which changes the topology), stores `f32`
//! unless a feature is enabled, and reports errors without a line. Here vertex `i` of the file is
//! vertex `i - 1` of the complex, coordinates are `f64`, and every error has its line. (`tobj` is
//! used in the tests as an independent reader to cross-check the faces.)
//!
//! - `v x y z [w | r g b]`: a vertex (a weight `w` or colours after `z` are ignored).
//! - `f i j k ...`: a face; each corner is `v`, `v/vt`, `v//vn` or `v/vt/vn` (only `v` is used),
//!   1-based or negative (relative to the last vertex defined). Vertices must be defined before
//!   they are used. Faces follow [`PolygonMode`](super::PolygonMode) as in PLY/OFF: 3 corners a triangle, 4 a quad,
//!   more fan-triangulated (noted); or a `(k-1)`-simplex with `Simplices`.
//! - `l i j k ...`: a polyline, read as its segments (edges, 1-simplices).
//! - `p ...` (points) is ignored with a note (vertices exist without cells); `vt`, `vn`, `vp`, `o`,
//!   `g`, `s`, `usemtl`, `mtllib` and unknown keywords are ignored.
//!
//! The writer writes `v` lines (a 2D complex gets `z = 0`, so it reads back as 3D) and 1-based
//! `f` lines for triangles and quads; other cells cannot be written.
//!
//! ```
//! use starplex::io::{obj, ReadOptions};
//! let text = "# a square\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1/1 2/2 3/3 4/4\n";
//! let r = obj::read_from(text.as_bytes(), "mem.obj".as_ref(), &ReadOptions::default()).unwrap();
//! assert_eq!(r.complex.n_vertices(), 4);
//! assert_eq!(r.complex.blocks()[0].kind, starplex::cell::CellKind::Quad);
//! let mut out = Vec::new();
//! obj::write(&mut out, &r.complex).unwrap();
//! assert!(String::from_utf8(out).unwrap().ends_with("f 1 2 3 4\n"));
//! ```
use std::io::{BufRead, Write};
use std::path::Path;

use super::faces::{push_build_notes, FaceError, Faces};
use super::text::{parse_u64, write_f64, LineReader};
use super::{Format, IoError, IoErrorKind, Location, ReadOptions, ReadResult};
use crate::cell::CellKind;
use crate::complex::{ComplexBuilder, IndexedComplex};

/// Reads an OBJ file.
///
/// ```
/// use starplex::io::{obj, ReadOptions};
/// let p = std::env::temp_dir().join(format!("starplex-doc-obj-{}.obj", std::process::id()));
/// std::fs::write(&p, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
/// assert_eq!(obj::read(&p, &ReadOptions::default()).unwrap().complex.n_cells(), 1);
/// std::fs::remove_file(&p).ok();
/// ```
///
/// # Errors
/// See [`read_from`].
pub fn read(path: &Path, opts: &ReadOptions) -> Result<ReadResult, IoError> {
    let f = std::fs::File::open(path).map_err(|e| IoError::new(path, e))?;
    read_from(std::io::BufReader::with_capacity(1 << 20, f), path, opts)
}

/// Reads OBJ text from any buffered reader; `path` names it in errors.
///
/// ```
/// use starplex::io::{obj, ReadOptions};
/// let e = obj::read_from(&b"v 0 0 0\nf 1 2 3\n"[..], "m.obj".as_ref(), &ReadOptions::default())
///     .unwrap_err();
/// assert!(e.to_string().starts_with("m.obj:2: vertex index 2 is out of range"), "{e}");
/// ```
///
/// # Errors
/// Malformed or non-finite coordinates, malformed corner indices, index 0, indices of vertices
/// not defined yet (or before the first one, for negative indices), repeated corners, faces of
/// fewer than 3 corners (polygon mode), polylines of fewer than 2, a line whose keyword is not
/// printable ASCII, a file with no vertex and no element (an empty or non-OBJ file), and the checks of
/// [`ComplexBuilder::build`]. Every error before the final build has its line.
pub fn read_from(r: impl BufRead, path: &Path, opts: &ReadOptions) -> Result<ReadResult, IoError> {
    let mut lr = LineReader::new(r, path, Some(b'#'));
    let mut b = ComplexBuilder::new(3).map_err(|e| IoError::new(path, e))?;
    let mut verts: Vec<u32> = Vec::with_capacity(16);
    let (mut n_polylines, mut n_segments, mut n_points) = (0u64, 0u64, 0u64);
    let mut faces = Faces::default();
    let mut n_faces = 0u64;
    while let Some(l) = lr.next_content_line()? {
        let mut t = l.tokens();
        let Some(key) = t.next_token() else { continue };
        match key {
            b"v" => {
                let mut p = [0.0; 3];
                for (x, what) in
                    p.iter_mut()
                        .zip(["the x coordinate", "the y coordinate", "the z coordinate"])
                {
                    // no format! per token: the line number locates the vertex
                    *x = t.f64(what)?;
                }
                b.push_vertex(&p)
                    .map_err(|e| IoError::new(path, e).at(Location::Line(l.no)))?;
            }
            b"f" | b"l" => {
                let nv = b.n_vertices();
                verts.clear();
                while let Some(tok) = t.next_token() {
                    let v = tok.split(|&c| c == b'/').next().unwrap_or(tok);
                    let (neg, digits) = match v.first() {
                        Some(b'-') => (true, &v[1..]),
                        Some(b'+') => (false, &v[1..]),
                        _ => (false, v),
                    };
                    let Some(i) = parse_u64(digits) else {
                        return Err(l.err(format!(
                            "expected a vertex index (like 7, 7/1, 7//2, -1), found '{}'",
                            String::from_utf8_lossy(&tok[..tok.len().min(40)])
                        )));
                    };
                    let idx = if neg {
                        (nv as u64).checked_sub(i).filter(|_| i > 0)
                    } else {
                        i.checked_sub(1).filter(|&x| x < nv as u64)
                    };
                    let Some(idx) = idx else {
                        let shown = String::from_utf8_lossy(v);
                        return Err(l.err(format!(
                            "vertex index {shown} is out of range: {nv} vertices are defined before this line (OBJ indices are 1-based, negative ones count back from the last vertex)"
                        )));
                    };
                    verts.push(idx as u32);
                }
                let k = verts.len();
                let loc = Location::Line(l.no);
                if key == b"l" {
                    if k < 2 {
                        return Err(l.err(format!(
                            "a polyline needs at least 2 vertices, this one has {k}"
                        )));
                    }
                    for w in verts.windows(2) {
                        opts.build
                            .check_cell(b.n_cells(), w, nv)
                            .map_err(|e| IoError::new(path, e).at(loc))?;
                        b.push_cell(CellKind::Simplex(1), w)
                            .map_err(|e| IoError::new(path, e).at(loc))?;
                    }
                    n_polylines += 1;
                    n_segments += k as u64 - 1;
                    continue;
                }
                opts.build
                    .check_cell(n_faces, &verts, nv)
                    .map_err(|e| IoError::new(path, e).at(loc))?;
                n_faces += 1;
                faces.push(&mut b, opts.polygons, &verts).map_err(|e| match e {
                    FaceError::Complex(e) => IoError::new(path, e).at(loc),
                    FaceError::TooFew(k) => l.err(format!(
                        "a face needs at least 3 vertices, this one has {k} (use 'l' for edges, or read in simplices mode)"
                    )),
                    FaceError::NotSimplex(k) => l.err(format!(
                        "a face of {k} vertices cannot be a simplex (1 to 65 vertices)"
                    )),
                })?;
            }
            b"p" => n_points += 1,
            key => {
                // other OBJ statements (vt, vn, g, usemtl, ...) are words of printable ASCII;
                // anything else is not OBJ text (a binary file, random bytes)
                if !key.iter().all(|c| c.is_ascii_graphic()) {
                    return Err(l.err(format!(
                        "not an OBJ file: a line starts with '{}', which is not an OBJ keyword",
                        String::from_utf8_lossy(&key[..key.len().min(20)]).escape_debug()
                    )));
                }
            }
        }
    }
    if b.n_vertices() == 0 && b.n_cells() == 0 {
        return Err(IoError::parse(
            path,
            Some(Location::Line(lr.line_no().max(1))),
            "not an OBJ file: no vertex ('v') and no face ('f') or polyline ('l') in it",
        ));
    }
    let mut notes = Vec::new();
    faces.note(&mut notes);
    if n_polylines > 0 {
        notes.push(format!(
            "read {n_polylines} polylines ('l') as {n_segments} edges"
        ));
    }
    if n_points > 0 {
        notes.push(format!(
            "ignored {n_points} point elements ('p'): their vertices are kept"
        ));
    }
    let (complex, report) = b.build(&opts.build).map_err(|e| IoError::new(path, e))?;
    push_build_notes(&mut notes, &report);
    Ok(ReadResult {
        complex,
        format: Format::Obj,
        notes,
    })
}

/// Writes `k` as OBJ: `v` lines, then 1-based `f` lines.
///
/// ```
/// use starplex::io::obj;
/// use starplex::complex::{ComplexBuilder, BuildOptions};
/// use starplex::cell::CellKind;
/// let mut b = ComplexBuilder::new(3).unwrap();
/// for p in [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.5, 0.0]] {
///     b.push_vertex(&p).unwrap();
/// }
/// b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// let (k, _) = b.build(&BuildOptions::default()).unwrap();
/// let mut out = Vec::new();
/// obj::write(&mut out, &k).unwrap();
/// assert!(String::from_utf8(out).unwrap().ends_with("v 0 1.5 0\nf 1 2 3\n"));
/// ```
///
/// # Errors
/// [`IoErrorKind::CannotWrite`] for cells other than triangles and quads or an ambient dimension
/// above 3; OS errors of the writer.
pub fn write(w: &mut dyn Write, k: &IndexedComplex) -> Result<(), IoErrorKind> {
    super::ply::check_surface(k, Format::Obj)?;
    writeln!(w, "# written by starplex {}", env!("CARGO_PKG_VERSION"))?;
    writeln!(w, "# {} vertices, {} faces", k.n_vertices(), k.n_cells())?;
    let d = k.ambient_dim();
    for p in k.coords().chunks_exact(d) {
        w.write_all(b"v")?;
        for &x in p {
            w.write_all(b" ")?;
            write_f64(w, x)?;
        }
        if d == 2 {
            w.write_all(b" 0")?;
        }
        w.write_all(b"\n")?;
    }
    let mut s = String::with_capacity(64);
    for b in k.blocks() {
        for i in 0..b.len() {
            use std::fmt::Write as _;
            s.clear();
            s.push('f');
            for v in b.cell(i) {
                let _ = write!(s, " {}", v + 1);
            }
            s.push('\n');
            w.write_all(s.as_bytes())?;
        }
    }
    Ok(())
}
