//! Medit `.mesh` (ascii, the format of INRIA's Medit/libMeshb, MMG, TetGen, meshio).
//!
//! ```text
//! MeshVersionFormatted 2
//! Dimension 3
//! Vertices
//! <n>
//! x y z ref                 (n entries)
//! Tetrahedra                (or Edges, Triangles, Quadrilaterals, Pyramids, Prisms, Hexahedra)
//! <m>
//! v_1 ... v_k ref           (m entries, 1-based vertex indices)
//! End
//! ```
//!
//! The format is free-form: words separated by any whitespace, `#` comments. Keywords are
//! case-insensitive. References (`ref`) are read as the vertex and cell attribute `medit:ref` (when one is not 0) and
//! written from it (0 without it). Sections whose
//! layout is known but that carry no cells (`Corners`, `Ridges`, `Required*`, `Normals`,
//! `Tangents`, `NormalAt*`, `TangentAt*`) are skipped with a note; any other keyword is an error
//! naming it.
//!
//! Vertex order: Medit's element numbering is VTK's for every kind read here (tetrahedra, pyramids
//! with base 1-2-3-4 and apex 5, prisms with triangles 1-2-3 / 4-5-6 where 1-2-3 is oriented
//! outward, hexahedra 1-2-3-4 / 5-6-7-8), as in MMG's prism face table and SALOME's Medit driver;
//! cells are kept as written. (meshio writes its prisms, which follow gmsh's orientation, to
//! Medit unchanged, so prisms in meshio-written files come out mirrored.)
//!
//! ```
//! use starplex::io::{medit, ReadOptions};
//! let text = "MeshVersionFormatted 2\nDimension 3\nVertices\n4\n0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\n\
//!             Tetrahedra\n1\n1 2 3 4 7\nEnd\n";
//! let r = medit::read_from(text.as_bytes(), "mem.mesh".as_ref(), &ReadOptions::default()).unwrap();
//! assert_eq!(r.complex.n_cells(), 1);
//! assert_eq!(r.complex.cells().next().unwrap().vertices, &[0, 1, 2, 3]);
//! let mut out = Vec::new();
//! medit::write(&mut out, &r.complex).unwrap();
//! let back = medit::read_from(&out[..], "mem.mesh".as_ref(), &ReadOptions::default()).unwrap();
//! assert_eq!(back.complex, r.complex);
//! ```
use std::io::{BufRead, Write};
use std::path::Path;

use super::faces::push_build_notes;
use super::text::write_f64;
use super::words::Words;
use super::{Format, IoError, IoErrorKind, Location, ReadOptions, ReadResult};
use crate::attr::{AttrTarget, AttrValues, Attribute, Attributes};
use crate::cell::CellKind;
use crate::complex::{ComplexBuilder, IndexedComplex};

/// The Medit keyword of each cell kind the format holds.
const CELL_KEYWORDS: [(&str, CellKind); 7] = [
    ("Edges", CellKind::Simplex(1)),
    ("Triangles", CellKind::Simplex(2)),
    ("Quadrilaterals", CellKind::Quad),
    ("Tetrahedra", CellKind::Simplex(3)),
    ("Pyramids", CellKind::Pyramid),
    ("Prisms", CellKind::Prism),
    ("Hexahedra", CellKind::Hex),
];

/// Sections without cells whose layout is known: `(keyword, integers per entry, reals per entry
/// per coordinate)`.
const SKIPPABLE: [(&str, usize, usize); 13] = [
    ("Corners", 1, 0),
    ("Ridges", 1, 0),
    ("RequiredVertices", 1, 0),
    ("RequiredEdges", 1, 0),
    ("RequiredTriangles", 1, 0),
    ("RequiredQuadrilaterals", 1, 0),
    ("Normals", 0, 1),
    ("Tangents", 0, 1),
    ("NormalAtVertices", 2, 0),
    ("TangentAtVertices", 2, 0),
    ("NormalAtTriangleVertices", 3, 0),
    ("NormalAtQuadrilateralVertices", 3, 0),
    ("TangentAtEdgeVertices", 3, 0),
];

/// Reads a `.mesh` file.
///
/// ```
/// use starplex::io::{medit, ReadOptions};
/// let path = std::env::temp_dir().join(format!("starplex-doc-medit-read-{}.mesh", std::process::id()));
/// std::fs::write(&path, "MeshVersionFormatted 2\nDimension 2\nVertices\n4\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n\
///                        Quadrilaterals\n1\n1 2 3 4 0\nEnd\n").unwrap();
/// let r = medit::read(&path, &ReadOptions::default()).unwrap();
/// std::fs::remove_file(&path).unwrap();
/// assert_eq!(r.complex.cells().next().unwrap().vertices, &[0, 1, 2, 3]); // 0-based
/// ```
///
/// # Errors
/// See [`read_from`].
pub fn read(path: &Path, opts: &ReadOptions) -> Result<ReadResult, IoError> {
    let f = std::fs::File::open(path).map_err(|e| IoError::new(path, e))?;
    read_from(std::io::BufReader::with_capacity(1 << 20, f), path, opts)
}

fn count_at(w: &mut Words<'_, impl BufRead>, what: &str) -> Result<usize, IoError> {
    let n = w.u64(what)?;
    if n >= u32::MAX as u64 {
        return Err(w.err(format!(
            "{what} {n} exceeds the 32-bit id limit of starplex"
        )));
    }
    Ok(n as usize)
}

/// Reads Medit text from any buffered reader; `path` names it in errors.
///
/// ```
/// use starplex::io::{medit, Location, ReadOptions};
/// let text = "MeshVersionFormatted 2\nDimension 2\nVertices\n2\n0 0 0\n1 0 0\nEdges\n1\n1 3 0\nEnd\n";
/// let e = medit::read_from(text.as_bytes(), "m.mesh".as_ref(), &ReadOptions::default()).unwrap_err();
/// assert_eq!(e.location, Some(Location::Line(9))); // vertex 3 of a file with 2
/// let ok = text.replace("1 3 0", "1 2 0");
/// let r = medit::read_from(ok.as_bytes(), "m.mesh".as_ref(), &ReadOptions::default()).unwrap();
/// assert_eq!(r.complex.n_cells(), 1);
/// ```
///
/// # Errors
/// A missing `MeshVersionFormatted` header, a `Dimension` other than 2 or 3, malformed or
/// non-finite numbers, out-of-range or repeated vertex indices, unknown keywords, a file that ends
/// before a section is complete or before `End`, and the checks of
/// [`ComplexBuilder::build`](crate::complex::ComplexBuilder::build) under `opts.build`; each with
/// the line.
pub fn read_from(r: impl BufRead, path: &Path, opts: &ReadOptions) -> Result<ReadResult, IoError> {
    let mut w = Words::new(r, path, Some(b'#'));
    {
        let first = w.expect("'MeshVersionFormatted'")?;
        if !first.eq_ignore_ascii_case(b"MeshVersionFormatted") {
            let shown = String::from_utf8_lossy(&first[..first.len().min(40)]).into_owned();
            return Err(w.err(format!(
                "not a Medit file: expected 'MeshVersionFormatted', found '{shown}'"
            )));
        }
        let v = w.u64("the format version")?;
        if !(1..=4).contains(&v) {
            return Err(w.err(format!(
                "unsupported MeshVersionFormatted {v} (expected 1 to 4)"
            )));
        }
    }
    let mut dim: Option<usize> = None;
    let mut builder: Option<ComplexBuilder> = None;
    let mut nv = 0usize;
    let mut notes = Vec::new();
    let mut verts: Vec<u32> = Vec::with_capacity(8);
    let mut p = [0.0f64; 3];
    let mut n_cells: u64 = 0;
    let mut vrefs: Vec<i64> = Vec::new();
    let mut crefs: Vec<i64> = Vec::new();
    loop {
        let Some(kw) = w.next_word()? else {
            return Err(w.eof("a keyword or 'End'"));
        };
        let kw = String::from_utf8_lossy(&kw[..kw.len().min(60)]).into_owned();
        let kw_line = w.line();
        let lower = kw.to_ascii_lowercase();
        if lower == "end" {
            break;
        }
        if lower == "dimension" {
            let d = w.u64("the dimension")?;
            if d != 2 && d != 3 {
                return Err(w.err(format!("Dimension {d} is not supported (expected 2 or 3)")));
            }
            match dim {
                Some(old) if old != d as usize => {
                    return Err(w.err(format!(
                        "Dimension {d} contradicts the earlier Dimension {old}"
                    )))
                }
                _ => dim = Some(d as usize),
            }
            continue;
        }
        if lower == "vertices" {
            let Some(d) = dim else {
                return Err(w.err_at(kw_line, "'Vertices' before 'Dimension'"));
            };
            if builder.is_some() {
                return Err(w.err_at(kw_line, "a second 'Vertices' section"));
            }
            let n = count_at(&mut w, "the vertex count")?;
            let mut b = ComplexBuilder::new(d).map_err(|e| IoError::new(path, e))?;
            for _ in 0..n {
                for x in p[..d].iter_mut() {
                    *x = w.f64("a vertex coordinate")?;
                }
                vrefs.push(w.i64("the vertex reference")?);
                b.push_vertex(&p[..d])
                    .map_err(|e| IoError::new(path, e).at(Location::Line(w.line())))?;
            }
            nv = n;
            builder = Some(b);
            continue;
        }
        if let Some(&(name, kind)) = CELL_KEYWORDS
            .iter()
            .find(|(name, _)| name.eq_ignore_ascii_case(&kw))
        {
            let Some(b) = builder.as_mut() else {
                return Err(w.err_at(kw_line, format!("'{name}' before 'Vertices'")));
            };
            let n = count_at(&mut w, &format!("the number of {name}"))?;
            let k = kind.n_vertices();
            for _ in 0..n {
                verts.clear();
                for _ in 0..k {
                    verts.push(w.index("vertex index", 1, nv)?);
                }
                let line = w.line();
                crefs.push(w.i64("the element reference")?);
                opts.build
                    .check_cell(n_cells, &verts, nv)
                    .map_err(|e| IoError::new(path, e).at(Location::Line(line)))?;
                b.push_cell(kind, &verts)
                    .map_err(|e| IoError::new(path, e).at(Location::Line(line)))?;
                n_cells += 1;
            }
            continue;
        }
        if let Some(&(name, ints, reals)) = SKIPPABLE
            .iter()
            .find(|(name, _, _)| name.eq_ignore_ascii_case(&kw))
        {
            let n = w.u64(&format!("the number of {name}"))?;
            let per = ints + reals * dim.unwrap_or(3);
            for _ in 0..n {
                for _ in 0..per {
                    w.f64("a value")?;
                }
            }
            notes.push(format!("skipped the Medit section '{name}' ({n} entries)"));
            continue;
        }
        if kw.starts_with(|c: char| c.is_ascii_digit() || c == '-' || c == '+' || c == '.') {
            return Err(w.err_at(
                kw_line,
                format!("found the number '{kw}' where a keyword was expected (a section holds more entries than its count says)"),
            ));
        }
        return Err(w.err_at(
            kw_line,
            format!(
                "unknown Medit keyword '{kw}' (its layout is not known, so it cannot be skipped)"
            ),
        ));
    }
    let Some(mut b) = builder else {
        return Err(w.err("the file has no 'Vertices' section"));
    };
    let mut attrs = Attributes::default();
    if vrefs.iter().any(|&r| r != 0) {
        attrs.vertex.push(Attribute::int(REF, 1, vrefs));
    }
    if crefs.iter().any(|&r| r != 0) {
        attrs.cell.push(Attribute::int(REF, 1, crefs));
    }
    b.set_attributes(attrs);
    let (complex, report) = b.build(&opts.build).map_err(|e| IoError::new(path, e))?;
    push_build_notes(&mut notes, &report);
    Ok(ReadResult {
        complex,
        format: Format::Medit,
        notes,
    })
}

/// Refuses what Medit cannot hold: an ambient dimension other than 2 or 3, vertex cells and
/// simplices of dimension 4 and more.
///
/// ```
/// use starplex::cell::CellKind;
/// use starplex::complex::IndexedComplex;
/// use starplex::io::medit;
/// let pt = IndexedComplex::from_parts(3, vec![0.0; 3].into(),
///                                     vec![(CellKind::Simplex(0), vec![0].into())]).unwrap();
/// assert!(medit::check(&pt).is_err());
/// ```
///
/// # Errors
/// [`IoErrorKind::CannotWrite`] with the reason.
pub fn check(k: &IndexedComplex) -> Result<(), IoErrorKind> {
    let d = k.ambient_dim();
    if d != 2 && d != 3 {
        return Err(IoErrorKind::CannotWrite {
            format: Format::Medit,
            reason: format!("Medit holds 2 or 3 coordinates per vertex, the complex has {d}"),
        });
    }
    for b in k.blocks() {
        if !CELL_KEYWORDS.iter().any(|(_, kind)| *kind == b.kind) {
            return Err(IoErrorKind::CannotWrite {
                format: Format::Medit,
                reason: format!(
                    "Medit has no element for {} cells (it holds edges, triangles, quads, tets, pyramids, prisms and hexahedra)",
                    b.kind
                ),
            });
        }
    }
    Ok(())
}

/// The attribute name of Medit references.
pub const REF: &str = "medit:ref";

/// The integer column `medit:ref` of `target`, if `k` has one.
fn refs(k: &IndexedComplex, target: AttrTarget) -> Option<&[i64]> {
    match k.attributes().get(target, REF) {
        Some(Attribute {
            components: 1,
            values: AttrValues::Int(v),
            ..
        }) => Some(v),
        _ => None,
    }
}

/// Writes `k` as Medit `.mesh` (version 2; references from the `medit:ref` attributes, else 0).
///
/// ```
/// use starplex::io::{medit, IoErrorKind};
/// # use starplex::complex::IndexedComplex;
/// # use starplex::cell::CellKind;
/// let tri = IndexedComplex::from_parts(2, vec![0.0, 0.0, 1.0, 0.0, 0.0, 1.0].into(),
///                                      vec![(CellKind::Simplex(2), vec![0, 1, 2].into())]).unwrap();
/// let mut out = Vec::new();
/// medit::write(&mut out, &tri).unwrap();
/// let text = String::from_utf8(out).unwrap();
/// assert!(text.contains("Triangles\n1\n1 2 3 0\n")); // 1-based, reference 0
/// // Medit has no 4-simplices.
/// let s4 = IndexedComplex::from_parts(3, vec![0.0; 15].into(),
///                                     vec![(CellKind::Simplex(4), vec![0, 1, 2, 3, 4].into())]).unwrap();
/// assert!(matches!(medit::write(&mut Vec::new(), &s4), Err(IoErrorKind::CannotWrite { .. })));
/// ```
///
/// # Errors
/// [`IoErrorKind::CannotWrite`] for an ambient dimension other than 2 or 3, vertex cells (0-simplex
/// top cells) or simplices of dimension 4 and more; OS errors of the writer.
pub fn write(w: &mut dyn Write, k: &IndexedComplex) -> Result<(), IoErrorKind> {
    check(k)?;
    let d = k.ambient_dim();
    writeln!(w, "MeshVersionFormatted 2")?;
    writeln!(w, "# written by starplex {}", env!("CARGO_PKG_VERSION"))?;
    writeln!(w, "Dimension {d}")?;
    writeln!(w, "Vertices")?;
    writeln!(w, "{}", k.n_vertices())?;
    let vref = refs(k, AttrTarget::Vertex);
    for (i, p) in k.coords().chunks_exact(d).enumerate() {
        for &x in p {
            write_f64(w, x)?;
            w.write_all(b" ")?;
        }
        writeln!(w, "{}", vref.map_or(0, |r| r[i]))?;
    }
    let cref = refs(k, AttrTarget::Cell);
    // Medit groups cells by keyword: write each kind's cells in id order.
    let mut line = String::with_capacity(128);
    for (name, kind) in CELL_KEYWORDS {
        let n: usize = k
            .blocks()
            .iter()
            .filter(|b| b.kind == kind)
            .map(|b| b.len())
            .sum();
        if n == 0 {
            continue;
        }
        writeln!(w, "{name}")?;
        writeln!(w, "{n}")?;
        for b in k.blocks().iter().filter(|b| b.kind == kind) {
            for i in 0..b.len() {
                use std::fmt::Write as _;
                line.clear();
                for v in b.cell(i) {
                    let _ = write!(line, "{} ", v + 1);
                }
                let _ = writeln!(line, "{}", cref.map_or(0, |r| r[b.first as usize + i]));
                w.write_all(line.as_bytes())?;
            }
        }
    }
    writeln!(w, "End")?;
    Ok(())
}
