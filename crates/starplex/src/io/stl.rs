//! STL (ascii and binary): reader through `stl_io`, writers of starplex's own.
//!
//! Writing ([`write()`] ascii, [`write_binary`] binary; formats `stl` and `stl-binary`): one facet
//! per triangle with its unit normal (right-hand rule, zero for a degenerate facet), coordinates
//! as `f32` (STL has no other type). What a reader gets back is the same triangles in the same
//! order on vertices numbered by first use; [`check`] refuses what would come back different:
//! cells other than triangles, isolated vertices, two vertices that become one point in `f32`, an
//! ambient dimension other than 2 or 3 (2D points get `z = 0`).
//!
//! STL stores every facet with its own three corners; the reader merges corners with equal
//! coordinates into one vertex (equal as `f32` bit patterns after mapping `-0.0` to `0.0`, with a
//! hash map), so neighbouring facets share vertices and edges. Vertex ids follow first appearance.
//!
//! A facet that is degenerate after merging (two equal corners) is an error naming the facet
//! (0-based) unless `opts.build.drop_degenerate` (or, as before it existed,
//! `opts.build.drop_duplicates`) is set, in which case such facets are dropped and counted in
//! [`ReadResult::notes`] (`drop_duplicates` also drops repeated facets). Non-finite
//! coordinates are errors naming the facet.
//!
//! Binary detection: a file whose length is exactly `84 + 50 * n` where `n` is the facet count
//! stored at byte 80 is binary even when its 80-byte header starts with `solid` (many exporters
//! write that); anything else starting with `solid` is ascii.
//!
//! ```
//! use starplex::io::{stl, ReadOptions};
//! let text = "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n\
//!             endloop\nendfacet\nfacet normal 0 0 1\nouter loop\nvertex 1 0 0\nvertex 1 1 0\n\
//!             vertex 0 1 0\nendloop\nendfacet\nendsolid t\n";
//! let dir = std::env::temp_dir().join(format!("starplex-doc-stl-{}", std::process::id()));
//! std::fs::create_dir_all(&dir).unwrap();
//! let p = dir.join("two.stl");
//! std::fs::write(&p, text).unwrap();
//! let r = stl::read(&p, &ReadOptions::default()).unwrap();
//! assert_eq!(r.complex.n_vertices(), 4); // 6 corners, 2 shared
//! assert_eq!(r.complex.n_cells(), 2);
//! ```
use std::io::{Read, Seek, SeekFrom, Write};
use std::path::Path;

use rustc_hash::FxHashMap;

use super::{Format, IoError, IoErrorKind, ReadOptions, ReadResult};
use crate::cell::CellKind;
use crate::complex::{ComplexBuilder, IndexedComplex};

/// A file seen through a replaced prefix: the bytes of `prefix`, then the file from `skip` on.
/// Lets `stl_io` read binary files whose header starts with `solid` and ascii files whose first
/// line is a bare `solid`.
struct Patched {
    prefix: Vec<u8>,
    file: std::io::BufReader<std::fs::File>,
    skip: u64,
    pos: u64,
}

impl Read for Patched {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let p = self.prefix.len() as u64;
        if self.pos < p {
            let from = &self.prefix[self.pos as usize..];
            let n = from.len().min(buf.len());
            buf[..n].copy_from_slice(&from[..n]);
            self.pos += n as u64;
            if self.pos == p {
                self.file.seek(SeekFrom::Start(self.skip))?;
            }
            return Ok(n);
        }
        let n = self.file.read(buf)?;
        self.pos += n as u64;
        Ok(n)
    }
}

impl Seek for Patched {
    fn seek(&mut self, to: SeekFrom) -> std::io::Result<u64> {
        match to {
            SeekFrom::Start(0) => {
                self.pos = 0;
                if self.prefix.is_empty() {
                    self.file.seek(SeekFrom::Start(self.skip))?;
                }
                Ok(0)
            }
            _ => Err(std::io::Error::other(
                "only rewinding is supported on this reader",
            )),
        }
    }
}

/// Reads an STL file (ascii or binary).
///
/// ```
/// use starplex::io::{stl, ReadOptions};
/// // a binary STL with two facets sharing an edge
/// let mut b = vec![0u8; 80];
/// b.extend_from_slice(&2u32.to_le_bytes());
/// for t in [[[0f32, 0., 0.], [1., 0., 0.], [0., 1., 0.]], [[1., 0., 0.], [1., 1., 0.], [0., 1., 0.]]] {
///     b.extend_from_slice(&[0u8; 12]);
///     for v in t { for x in v { b.extend_from_slice(&x.to_le_bytes()); } }
///     b.extend_from_slice(&[0u8; 2]);
/// }
/// let p = std::env::temp_dir().join(format!("starplex-doc-stlb-{}.stl", std::process::id()));
/// std::fs::write(&p, &b).unwrap();
/// let k = stl::read(&p, &ReadOptions::default()).unwrap().complex;
/// assert_eq!((k.n_vertices(), k.n_cells()), (4, 2));
/// std::fs::remove_file(&p).ok();
/// ```
///
/// # Errors
/// OS errors; a binary file shorter than its facet count says; malformed ascii (with the facet
/// index); non-finite coordinates; degenerate facets (unless dropped, see the module docs);
/// duplicate facets (unless `opts.build.drop_duplicates`).
pub fn read(path: &Path, opts: &ReadOptions) -> Result<ReadResult, IoError> {
    let mut f = std::fs::File::open(path).map_err(|e| IoError::new(path, e))?;
    let len = f.metadata().map_err(|e| IoError::new(path, e))?.len();
    let mut head = Vec::with_capacity(84);
    (&mut f)
        .take(84)
        .read_to_end(&mut head)
        .map_err(|e| IoError::new(path, e))?;
    f.seek(SeekFrom::Start(0))
        .map_err(|e| IoError::new(path, e))?;
    let err = |at: u64, msg: String| IoError::parse(path, Some(super::Location::Byte(at)), msg);
    let starts_solid = head.starts_with(b"solid");
    let declared = (head.len() == 84)
        .then(|| u32::from_le_bytes(head[80..84].try_into().expect("4 bytes")) as u64);
    let binary_exact = declared.is_some_and(|n| 84 + 50 * n == len);
    let mut notes = Vec::new();
    let (prefix, skip) = if starts_solid && !binary_exact {
        // ascii; stl_io wants "solid <name>" on the first line.
        let first_line_end = head.iter().position(|&b| b == b'\n');
        match first_line_end {
            Some(e) if head[..e].trim_ascii() == b"solid" => {
                (b"solid unnamed\n".to_vec(), e as u64 + 1)
            }
            _ => (Vec::new(), 0),
        }
    } else {
        if len < 84 {
            return Err(err(
                0,
                format!("not an STL file: {len} bytes, shorter than a binary STL header (84 bytes), and it does not start with 'solid'"),
            ));
        }
        let n = declared.unwrap_or(0);
        let need = 84 + 50 * n;
        if need > len {
            return Err(err(
                80,
                format!("binary STL declares {n} facets ({need} bytes) but the file has {len} bytes: truncated or not an STL file"),
            ));
        }
        if need < len {
            notes.push(format!("ignored {} bytes after the {n} facets", len - need));
        }
        if starts_solid {
            let mut p = head.clone();
            p[0] = b'S'; // so stl_io does not take it for ascii; header text is ignored
            (p, 84)
        } else {
            (Vec::new(), 0)
        }
    };
    let mut src = Patched {
        prefix,
        file: std::io::BufReader::with_capacity(1 << 20, f),
        skip,
        pos: 0,
    };
    let iter = stl_io::create_stl_reader(&mut src)
        .map_err(|e| IoError::parse(path, None, format!("not a readable STL file: {e}")))?;
    let mut b = ComplexBuilder::new(3).map_err(|e| IoError::new(path, e))?;
    let mut ids: FxHashMap<[u32; 3], u32> = FxHashMap::default();
    let mut dropped_degenerate = 0u64;
    let mut first_degenerate: Option<u64> = None;
    for (i, t) in iter.enumerate() {
        let i = i as u64;
        let t = t.map_err(|e| IoError::parse(path, None, format!("facet {i}: {e}")))?;
        let mut tri = [0u32; 3];
        for (c, v) in t.vertices.iter().enumerate() {
            let p = v.0;
            if let Some(a) = p.iter().position(|x| !x.is_finite()) {
                return Err(IoError::parse(
                    path,
                    None,
                    format!(
                        "facet {i}: corner {c} has a non-finite coordinate {} on axis {a}",
                        p[a]
                    ),
                ));
            }
            // -0.0 and 0.0 are the same point
            let key = p.map(|x| if x == 0.0 { 0 } else { x.to_bits() });
            let next = b.n_vertices() as u32;
            let id = *ids.entry(key).or_insert(next);
            if id == next {
                b.push_vertex(&p.map(|x| x as f64))
                    .map_err(|e| IoError::new(path, e))?;
            }
            tri[c] = id;
        }
        if tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2] {
            if !(opts.build.drop_degenerate || opts.build.drop_duplicates) {
                return Err(IoError::parse(
                    path,
                    None,
                    format!(
                        "facet {i} is degenerate: two of its corners are the same point ({:?}); drop such facets with the drop-degenerate option",
                        t.vertices.iter().map(|v| v.0).collect::<Vec<_>>()
                    ),
                ));
            }
            dropped_degenerate += 1;
            first_degenerate.get_or_insert(i);
            continue;
        }
        b.push_cell(CellKind::Simplex(2), &tri)
            .map_err(|e| IoError::new(path, e))?;
    }
    if dropped_degenerate > 0 {
        notes.push(format!(
            "dropped {dropped_degenerate} degenerate facets (first: facet {})",
            first_degenerate.unwrap_or(0)
        ));
    }
    let (complex, report) = b.build(&opts.build).map_err(|e| IoError::new(path, e))?;
    if report.dropped_duplicates > 0 {
        notes.push(format!(
            "dropped {} duplicate facets",
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
        format: Format::Stl,
        notes,
    })
}

/// The STL key of a point: its `f32` bit patterns, `-0.0` as `0.0` (what the reader merges).
fn key32(p: [f32; 3]) -> [u32; 3] {
    p.map(|x| if x == 0.0 { 0 } else { x.to_bits() })
}

fn point32(k: &IndexedComplex, v: u32) -> [f32; 3] {
    let d = k.ambient_dim();
    let p = &k.coords()[v as usize * d..v as usize * d + d];
    let mut q = [0f32; 3];
    for (x, y) in q.iter_mut().zip(p) {
        *x = *y as f32;
    }
    q
}

/// Refuses what STL cannot give back: cells other than triangles, vertices in no triangle,
/// distinct vertices at the same `f32` point (the reader would merge them), coordinates that
/// overflow `f32`, an ambient dimension other than 2 or 3. `format` is [`Format::Stl`] or
/// [`Format::StlBinary`] (named in the error).
///
/// ```
/// use starplex::cell::CellKind;
/// use starplex::complex::IndexedComplex;
/// use starplex::io::{stl, Format};
/// let quad = IndexedComplex::from_parts(3, vec![0., 0., 0., 1., 0., 0., 1., 1., 0., 0., 1., 0.].into(),
///                                       vec![(CellKind::Quad, vec![0, 1, 2, 3].into())]).unwrap();
/// let e = stl::check(&quad, Format::Stl).unwrap_err();
/// assert!(e.to_string().contains("triangulate the quads first"), "{e}");
/// ```
///
/// # Errors
/// [`IoErrorKind::CannotWrite`] with the reason.
pub fn check(k: &IndexedComplex, format: Format) -> Result<(), IoErrorKind> {
    let fail = |reason: String| Err(IoErrorKind::CannotWrite { format, reason });
    let d = k.ambient_dim();
    if d != 2 && d != 3 {
        return fail(format!(
            "STL holds points of 3 coordinates, this complex has {d}: use spx or spb"
        ));
    }
    for b in k.blocks() {
        match b.kind {
            CellKind::Simplex(2) => {}
            CellKind::Quad => {
                return fail(format!(
                    "STL holds triangles only, cell {} is a quad: triangulate the quads first",
                    b.first
                ))
            }
            kind if kind.dim() == 3 => {
                return fail(format!(
                    "STL holds triangles only, cell {} is a {}: write its boundary surface (triangulated, if it has quad faces)",
                    b.first,
                    kind.type_name()
                ))
            }
            kind => {
                return fail(format!(
                    "STL holds triangles only, cell {} is a {}: use vtk, msh, spx or spb",
                    b.first,
                    kind.type_name()
                ))
            }
        }
    }
    if k.n_cells() > u32::MAX as usize {
        return fail(format!(
            "{} facets exceed the 32-bit count of STL",
            k.n_cells()
        ));
    }
    let used = k.used_vertices();
    if let Some(v) = (0..k.n_vertices()).find(|&v| !used.contains(v)) {
        return fail(format!(
            "STL stores facets only, and vertex {v} is in no triangle (it would be lost)"
        ));
    }
    let mut seen: FxHashMap<[u32; 3], u32> = FxHashMap::default();
    seen.reserve(k.n_vertices());
    for v in 0..k.n_vertices() as u32 {
        let p = point32(k, v);
        if p.iter().any(|x| !x.is_finite()) {
            return fail(format!(
                "vertex {v} has a coordinate beyond the range of STL's 32-bit floats"
            ));
        }
        if let Some(u) = seen.insert(key32(p), v) {
            return fail(format!(
                "vertices {u} and {v} are the same point in STL's 32-bit floats ({p:?}), so a \
                 reader would merge them"
            ));
        }
    }
    Ok(())
}

fn normal(t: [[f32; 3]; 3]) -> [f32; 3] {
    let a = [0, 1, 2].map(|i| t[1][i] as f64 - t[0][i] as f64);
    let b = [0, 1, 2].map(|i| t[2][i] as f64 - t[0][i] as f64);
    let n = [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ];
    let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    if len > 0.0 && len.is_finite() {
        n.map(|x| (x / len) as f32)
    } else {
        [0.0; 3]
    }
}

fn facets(k: &IndexedComplex) -> impl Iterator<Item = [[f32; 3]; 3]> + '_ {
    k.blocks().iter().flat_map(move |b| {
        (0..b.len()).map(move |i| {
            let c = b.cell(i);
            [point32(k, c[0]), point32(k, c[1]), point32(k, c[2])]
        })
    })
}

/// Writes `k` as ascii STL (`solid starplex ... endsolid starplex`).
///
/// ```
/// use starplex::cell::CellKind;
/// use starplex::complex::IndexedComplex;
/// use starplex::io::stl;
/// let t = IndexedComplex::from_parts(3, vec![0., 0., 0., 1., 0., 0., 0., 1., 0.].into(),
///                                    vec![(CellKind::Simplex(2), vec![0, 1, 2].into())]).unwrap();
/// let mut out = Vec::new();
/// stl::write(&mut out, &t).unwrap();
/// let text = String::from_utf8(out).unwrap();
/// assert!(text.starts_with("solid starplex\n  facet normal 0 0 1\n    outer loop\n      vertex 0 0 0\n"));
/// assert!(text.ends_with("endsolid starplex\n"));
/// ```
///
/// # Errors
/// [`IoErrorKind::CannotWrite`] (see [`check`]); OS errors of the writer.
pub fn write(w: &mut dyn Write, k: &IndexedComplex) -> Result<(), IoErrorKind> {
    check(k, Format::Stl)?;
    w.write_all(b"solid starplex\n")?;
    let mut s = String::with_capacity(256);
    for t in facets(k) {
        use std::fmt::Write as _;
        s.clear();
        let n = normal(t);
        let _ = writeln!(s, "  facet normal {} {} {}", n[0], n[1], n[2]);
        s.push_str("    outer loop\n");
        for p in t {
            let _ = writeln!(s, "      vertex {} {} {}", p[0], p[1], p[2]);
        }
        s.push_str("    endloop\n  endfacet\n");
        w.write_all(s.as_bytes())?;
    }
    w.write_all(b"endsolid starplex\n")?;
    Ok(())
}

/// Writes `k` as binary STL (an 80-byte header that does not start with `solid`, the facet
/// count, 50 bytes per facet, little-endian).
///
/// ```
/// use starplex::cell::CellKind;
/// use starplex::complex::IndexedComplex;
/// use starplex::io::stl;
/// let t = IndexedComplex::from_parts(3, vec![0., 0., 0., 1., 0., 0., 0., 1., 0.].into(),
///                                    vec![(CellKind::Simplex(2), vec![0, 1, 2].into())]).unwrap();
/// let mut out = Vec::new();
/// stl::write_binary(&mut out, &t).unwrap();
/// assert_eq!(out.len(), 84 + 50);
/// assert_eq!(&out[80..84], &1u32.to_le_bytes());
/// ```
///
/// # Errors
/// [`IoErrorKind::CannotWrite`] (see [`check`]); OS errors of the writer.
pub fn write_binary(w: &mut dyn Write, k: &IndexedComplex) -> Result<(), IoErrorKind> {
    check(k, Format::StlBinary)?;
    let mut head = [b' '; 80];
    let title = format!(
        "binary STL written by starplex {}",
        env!("CARGO_PKG_VERSION")
    );
    head[..title.len().min(80)].copy_from_slice(&title.as_bytes()[..title.len().min(80)]);
    w.write_all(&head)?;
    w.write_all(&(k.n_cells() as u32).to_le_bytes())?;
    let mut buf: Vec<u8> = Vec::with_capacity(1 << 16);
    for t in facets(k) {
        for x in normal(t).iter().chain(t.iter().flatten()) {
            buf.extend_from_slice(&x.to_le_bytes());
        }
        buf.extend_from_slice(&[0, 0]);
        if buf.len() >= 1 << 16 {
            w.write_all(&buf)?;
            buf.clear();
        }
    }
    w.write_all(&buf)?;
    Ok(())
}
