//! Readers of the Stellar-tree reference's own formats (read only), as described in the
//! datasets' `FORMATS.md`:
//!
//! * `.tri` — `nV`, nV vertex lines (the number of values on the first line is the ambient
//!   dimension), `nT`, nT lines `i j k` (0-based triangles).
//! * `.ts` — `nV nT`, nV lines `x y z field` (the field value is ignored), nT lines `a b c d`
//!   (0-based tetrahedra).
//! * `.sierp` — `dim nV nT`, nV coordinate lines, nT lines `k v_0 .. v_dim`: `dim`-simplices; the
//!   first value `k` of a cell line is ignored, as the reference ignores it.
//! * `.hex` — lines `v x y z`, then lines `h i_0 .. i_7` with **1-based** indices in the
//!   reference's corner order, converted here to VTK order (`#` starts a comment).
//!
//! Every reader streams, checks every count against the lines actually present, and reports
//! errors with the file and line.
//!
//! ```
//! use starplex::io::{stellar_ref, Format, ReadOptions};
//! use starplex::cell::CellKind;
//! let tri = "4\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n2\n0 1 2\n0 2 3\n";
//! let r = stellar_ref::read_from(tri.as_bytes(), "m.tri".as_ref(), Format::Tri,
//!                                &ReadOptions::default()).unwrap();
//! assert_eq!(r.complex.n_cells(), 2);
//!
//! // A unit cube as a .hex: the reference's corner order becomes VTK's.
//! let hex = concat!("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n",
//!                   "v 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n",
//!                   "# 1 hexahedra\nh 1 2 8 4 6 5 3 7\n");
//! let r = stellar_ref::read_from(hex.as_bytes(), "m.hex".as_ref(), Format::Hex,
//!                                &ReadOptions::default()).unwrap();
//! let c = r.complex.cells().next().unwrap();
//! assert_eq!(c.kind, CellKind::Hex);
//! assert_eq!(c.vertices, &[0, 1, 2, 3, 4, 5, 6, 7]);
//! ```
use std::io::BufRead;
use std::path::Path;

use super::faces::push_build_notes;
use super::off::{shown, CellLines};
use super::text::{parse_f64, Line, LineReader, Tokens};
use super::{Format, IoError, IoErrorKind, Location, ReadOptions, ReadResult};
use crate::cell::{CellKind, MAX_SIMPLEX_DIM};
use crate::complex::{BuildOptions, ComplexBuilder, IndexedComplex, MAX_AMBIENT_DIM};

/// The reference's `.hex` corner order in terms of VTK corners: reference corner `j` is VTK
/// corner `HEX_REF_TO_VTK[j]`.
///
/// ```
/// use starplex::io::stellar_ref::HEX_REF_TO_VTK;
/// // A cube's corners listed in the reference's order...
/// let reference = [0, 1, 7, 3, 5, 4, 2, 6];
/// let mut vtk = [0; 8];
/// for (j, &v) in reference.iter().enumerate() {
///     vtk[HEX_REF_TO_VTK[j]] = v;
/// }
/// assert_eq!(vtk, [0, 1, 2, 3, 4, 5, 6, 7]); // ...are VTK's bottom 0-1-2-3, top 4-5-6-7
/// ```
pub const HEX_REF_TO_VTK: [usize; 8] = [0, 1, 7, 3, 5, 4, 2, 6];

/// Reads a file of the reference format `format` (one of [`Format::Tri`], [`Format::Ts`],
/// [`Format::Sierp`], [`Format::Hex`]).
///
/// ```
/// use starplex::io::{stellar_ref, Format, ReadOptions};
/// use starplex::cell::CellKind;
/// let path = std::env::temp_dir().join(format!("starplex-doc-ts-read-{}.ts", std::process::id()));
/// // .ts: "nV nT", vertices with a field value, 0-based tetrahedra.
/// std::fs::write(&path, "4 1\n0 0 0 9.5\n1 0 0 9.5\n0 1 0 9.5\n0 0 1 9.5\n0 1 2 3\n").unwrap();
/// let r = stellar_ref::read(&path, Format::Ts, &ReadOptions::default()).unwrap();
/// std::fs::remove_file(&path).unwrap();
/// assert_eq!(r.complex.blocks()[0].kind, CellKind::Simplex(3));
/// assert_eq!(r.complex.ambient_dim(), 3); // the field value is not a coordinate
/// ```
///
/// # Errors
/// See [`read_from`].
pub fn read(path: &Path, format: Format, opts: &ReadOptions) -> Result<ReadResult, IoError> {
    let f = std::fs::File::open(path).map_err(|e| IoError::new(path, e))?;
    read_from(
        std::io::BufReader::with_capacity(1 << 20, f),
        path,
        format,
        opts,
    )
}

/// Reads reference-format text from any buffered reader; `path` names it in errors.
///
/// ```
/// use starplex::io::{stellar_ref, Format, ReadOptions};
/// use starplex::cell::CellKind;
/// // .sierp: "dim nV nT", then cells "k v_0 .. v_dim" whose first value is ignored.
/// let text = "1 3 2\n0 0\n1 0\n2 0\n99 0 1\n99 1 2\n";
/// let r = stellar_ref::read_from(text.as_bytes(), "m.sierp".as_ref(), Format::Sierp,
///                                &ReadOptions::default()).unwrap();
/// assert_eq!((r.complex.n_cells(), r.complex.blocks()[0].kind), (2, CellKind::Simplex(1)));
/// let e = stellar_ref::read_from(text.as_bytes(), "m.off".as_ref(), Format::Off, &ReadOptions::default());
/// assert!(e.is_err()); // not one of the four reference formats
/// ```
///
/// # Errors
/// A format that is not one of the four, missing or malformed counts, malformed or non-finite
/// coordinates, vertex lines with the wrong number of values, out-of-range or repeated indices
/// (with the line), a file shorter or longer than its counts say, and the checks of
/// [`ComplexBuilder::build`].
pub fn read_from(
    r: impl BufRead,
    path: &Path,
    format: Format,
    opts: &ReadOptions,
) -> Result<ReadResult, IoError> {
    let mut cx = Cx {
        lines: CellLines::default(),
        build: opts.build.clone(),
    };
    let (b, mut notes) = match format {
        Format::Tri => read_tri(LineReader::new(r, path, None), &mut cx)?,
        Format::Ts => read_ts(LineReader::new(r, path, None), &mut cx)?,
        Format::Sierp => read_sierp(LineReader::new(r, path, None), &mut cx)?,
        Format::Hex => read_hex(LineReader::new(r, path, Some(b'#')), &mut cx)?,
        other => {
            return Err(IoError::parse(
                path,
                None,
                format!("{other} is not a Stellar reference format (tri, ts, sierp, hex)"),
            ))
        }
    };
    let (complex, report) = b.build(&opts.build).map_err(|e| cx.lines.error(path, e))?;
    push_build_notes(&mut notes, &report);
    Ok(ReadResult {
        complex,
        format,
        notes,
    })
}

/// Not supported: the reference formats are read only.
///
/// # Errors
/// Always [`IoErrorKind::CannotWrite`].
///
/// ```
/// let k = starplex::complex::ComplexBuilder::new(3).unwrap()
///     .build(&Default::default()).unwrap().0;
/// assert!(starplex::io::stellar_ref::write(&mut Vec::new(), &k).is_err());
/// ```
pub fn write(_w: &mut dyn std::io::Write, _k: &IndexedComplex) -> Result<(), IoErrorKind> {
    Err(IoErrorKind::CannotWrite {
        format: Format::Tri,
        reason: "starplex reads the Stellar reference formats but does not write them".into(),
    })
}

type Read = Result<(ComplexBuilder, Vec<String>), IoError>;

/// Parses the count tokens of one line (`labels` name them); nothing else may be on the line.
fn counts<R: BufRead, const N: usize>(
    lr: &mut LineReader<'_, R>,
    line: &str,
    labels: [&str; N],
) -> Result<([u64; N], u64), IoError> {
    let l = lr.expect_line(line)?;
    let mut t = l.tokens();
    let mut out = [0u64; N];
    for (o, what) in out.iter_mut().zip(labels) {
        *o = t.u64(what)?;
    }
    t.end()?;
    Ok((out, l.no))
}

fn check_count(n: u64, what: &str, path: &Path, line: u64) -> Result<usize, IoError> {
    if n >= u32::MAX as u64 {
        return Err(IoError::parse(
            path,
            Some(Location::Line(line)),
            format!("{what} {n} exceeds the 32-bit id limit of starplex"),
        ));
    }
    Ok(n as usize)
}

/// Parses `n` finite coordinates of vertex `i` into `p`.
#[inline]
fn coords(t: &mut Tokens<'_>, n: usize, i: usize, p: &mut Vec<f64>) -> Result<(), IoError> {
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

/// Reads `nv` vertex lines whose values are all coordinates; the first line sets the dimension.
/// Returns the builder (ambient 3 when there are no vertices).
fn vertices_no_field<R: BufRead>(
    lr: &mut LineReader<'_, R>,
    nv: usize,
) -> Result<ComplexBuilder, IoError> {
    let mut builder: Option<ComplexBuilder> = None;
    let mut first = 0u64;
    let mut p = Vec::with_capacity(8);
    for i in 0..nv {
        let l = lr.expect_line("a vertex line")?;
        let mut t = l.tokens();
        let b = match &mut builder {
            Some(b) => b,
            None => {
                let n = t.count_rest();
                if n == 0 || n > MAX_AMBIENT_DIM {
                    return Err(l.err(format!(
                        "the first vertex line has {n} values: the ambient dimension must be in \
                         1..={MAX_AMBIENT_DIM}"
                    )));
                }
                first = l.no;
                builder.insert(ComplexBuilder::new(n).map_err(|e| l.err(e.to_string()))?)
            }
        };
        let n = b.ambient_dim();
        let parsed = coords(&mut t, n, i, &mut p);
        if parsed.is_err() || t.next_token().is_some() {
            let got = l.tokens().count_rest();
            if got != n {
                return Err(l.err(format!(
                    "vertex {i} has {got} values but the first vertex line (line {first}) has \
                     {n}: every vertex line must have the same number of coordinates"
                )));
            }
        }
        parsed?;
        b.push_vertex(&p).map_err(|e| l.err(e.to_string()))?;
    }
    match builder {
        Some(b) => Ok(b),
        None => ComplexBuilder::new(3).map_err(|e| lr.err(e.to_string())),
    }
}

/// Reads `nc` lines of exactly `k` 0-based indices (after `skip` ignored leading integers).
fn cells<R: BufRead>(
    lr: &mut LineReader<'_, R>,
    cx: &mut Cx,
    b: &mut ComplexBuilder,
    kind: CellKind,
    nc: u64,
    skip: usize,
) -> Result<(), IoError> {
    let nv = b.n_vertices();
    let k = kind.n_vertices();
    let mut v: Vec<u32> = Vec::with_capacity(k);
    for i in 0..nc {
        let l = lr.expect_line("a cell line")?;
        let mut t = l.tokens();
        for _ in 0..skip {
            t.u64("the vertex count (ignored)")?;
        }
        v.clear();
        for _ in 0..k {
            v.push(t.index("cell vertex", 0, nv)?);
        }
        t.end()?;
        push_checked(&l, cx, b, i, kind, &v)?;
    }
    Ok(())
}

fn push_checked(
    l: &Line<'_>,
    cx: &mut Cx,
    b: &mut ComplexBuilder,
    i: u64,
    kind: CellKind,
    v: &[u32],
) -> Result<(), IoError> {
    let at = |e| IoError::new(l.path, e).at(Location::Line(l.no));
    cx.build.check_cell(i, v, b.n_vertices()).map_err(at)?;
    let id = b.push_cell(kind, v).map_err(at)?;
    cx.lines.record(id.0 as u64, l.no);
    Ok(())
}

/// What the cell lines are read with: the line of each cell (for errors of the build) and the
/// build options (whether a repeated vertex fails at once or is dropped by the build).
struct Cx {
    lines: CellLines,
    build: BuildOptions,
}

fn no_trailing<R: BufRead>(lr: &mut LineReader<'_, R>, what: &str) -> Result<(), IoError> {
    if let Some(l) = lr.next_content_line()? {
        return Err(l.err(format!(
            "unexpected content after the {what} the file announced: '{}'",
            shown(l.bytes, 60)
        )));
    }
    Ok(())
}

fn read_tri<R: BufRead>(mut lr: LineReader<'_, R>, cx: &mut Cx) -> Read {
    let path = lr.path();
    let ([nv], line) = counts(&mut lr, "the vertex count line 'nV'", ["the vertex count"])?;
    let nv = check_count(nv, "vertex count", path, line)?;
    let mut b = vertices_no_field(&mut lr, nv)?;
    let ([nt], _) = counts(
        &mut lr,
        "the triangle count line 'nT'",
        ["the triangle count"],
    )?;
    cells(&mut lr, cx, &mut b, CellKind::Simplex(2), nt, 0)?;
    no_trailing(&mut lr, &format!("{nt} triangles"))?;
    Ok((b, Vec::new()))
}

fn read_ts<R: BufRead>(mut lr: LineReader<'_, R>, cx: &mut Cx) -> Read {
    let path = lr.path();
    let ([nv, nt], line) = counts(
        &mut lr,
        "the counts line 'nV nT'",
        ["the vertex count", "the tetrahedron count"],
    )?;
    let nv = check_count(nv, "vertex count", path, line)?;
    let mut b = ComplexBuilder::new(3).map_err(|e| IoError::new(path, e))?;
    let mut p = Vec::with_capacity(4);
    for i in 0..nv {
        let l = lr.expect_line("a vertex line 'x y z field'")?;
        let mut t = l.tokens();
        coords(&mut t, 3, i, &mut p)?;
        t.f64("the field value after x y z")?;
        t.end()?;
        b.push_vertex(&p).map_err(|e| l.err(e.to_string()))?;
    }
    cells(&mut lr, cx, &mut b, CellKind::Simplex(3), nt, 0)?;
    no_trailing(&mut lr, &format!("{nt} tetrahedra"))?;
    Ok((b, Vec::new()))
}

fn read_sierp<R: BufRead>(mut lr: LineReader<'_, R>, cx: &mut Cx) -> Read {
    let path = lr.path();
    let ([dim, nv, nt], line) = counts(
        &mut lr,
        "the counts line 'dim nV nT'",
        [
            "the simplex dimension",
            "the vertex count",
            "the simplex count",
        ],
    )?;
    if dim > MAX_SIMPLEX_DIM as u64 {
        return Err(IoError::parse(
            path,
            Some(Location::Line(line)),
            format!("simplex dimension {dim} is above the supported maximum {MAX_SIMPLEX_DIM}"),
        ));
    }
    let nv = check_count(nv, "vertex count", path, line)?;
    let mut b = vertices_no_field(&mut lr, nv)?;
    cells(&mut lr, cx, &mut b, CellKind::Simplex(dim as u8), nt, 1)?;
    no_trailing(&mut lr, &format!("{nt} simplices"))?;
    Ok((b, Vec::new()))
}

fn read_hex<R: BufRead>(mut lr: LineReader<'_, R>, cx: &mut Cx) -> Read {
    let path = lr.path();
    let mut b = ComplexBuilder::new(3).map_err(|e| IoError::new(path, e))?;
    let mut p = Vec::with_capacity(3);
    let mut refv = [0u32; 8];
    let mut vtk = [0u32; 8];
    let mut n_hex = 0u64;
    let mut any_line = false;
    while let Some(l) = lr.next_content_line()? {
        any_line = true;
        let mut t = l.tokens();
        let tag = t.word("'v' or 'h'")?;
        match tag {
            b"v" => {
                if n_hex > 0 {
                    return Err(l.err(
                        "a vertex line 'v' after the first hexahedron: every vertex must come \
                         before the hexahedra",
                    ));
                }
                coords(&mut t, 3, b.n_vertices(), &mut p)?;
                t.end()?;
                b.push_vertex(&p).map_err(|e| l.err(e.to_string()))?;
            }
            b"h" => {
                let nv = b.n_vertices();
                for r in refv.iter_mut() {
                    *r = t.index("cell vertex", 1, nv)?;
                }
                t.end()?;
                for (j, &r) in refv.iter().enumerate() {
                    vtk[HEX_REF_TO_VTK[j]] = r;
                }
                push_checked(&l, cx, &mut b, n_hex, CellKind::Hex, &vtk)?;
                n_hex += 1;
            }
            other => {
                return Err(l.err(format!(
                    "expected a line 'v x y z' or 'h i_0 .. i_7', found '{}'",
                    shown(other, 40)
                )))
            }
        }
    }
    if !any_line {
        return Err(IoError::parse(
            path,
            Some(Location::Line(lr.line_no().max(1))),
            "the file is empty: expected lines 'v x y z' then 'h i_0 .. i_7'",
        ));
    }
    Ok((b, Vec::new()))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rd(text: &str, f: Format) -> Result<ReadResult, IoError> {
        let name = format!("t.{}", f.extension());
        read_from(text.as_bytes(), name.as_ref(), f, &ReadOptions::default())
    }

    fn err(text: &str, f: Format) -> String {
        match rd(text, f) {
            Ok(_) => panic!("expected an error for {text:?}"),
            Err(e) => e.to_string(),
        }
    }

    #[test]
    fn tri_ts_sierp_read() {
        let r = rd("3\n0 0\n1 0\n0 1\n1\n0 1 2\n", Format::Tri).unwrap();
        assert_eq!(r.complex.ambient_dim(), 2);
        assert_eq!(r.complex.n_cells(), 1);
        let r = rd(
            "4 1\n0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 1\n0 1 2 3\n",
            Format::Ts,
        )
        .unwrap();
        assert_eq!(r.complex.cells().next().unwrap().kind, CellKind::Simplex(3));
        assert_eq!(r.complex.point(crate::ids::VertexId(3)), &[0., 0., 1.]);
        let r = rd(
            "4 5 1\n0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\n0 0 0 1\n99 0 1 2 3 4\n",
            Format::Sierp,
        )
        .unwrap();
        assert_eq!(r.complex.cells().next().unwrap().kind, CellKind::Simplex(4));
        assert_eq!(r.complex.ambient_dim(), 4);
    }

    #[test]
    fn hex_permutation_is_inverse_of_writers() {
        // Write a cube in the reference order from VTK order and read it back.
        let vtk: [u32; 8] = [10, 11, 12, 13, 14, 15, 16, 17];
        let mut text = String::new();
        for i in 0..18 {
            text.push_str(&format!("v {i} 0 0\n"));
        }
        text.push_str("# 1 hexahedra\nh");
        for j in 0..8 {
            text.push_str(&format!(" {}", vtk[HEX_REF_TO_VTK[j]] + 1));
        }
        text.push('\n');
        let r = rd(&text, Format::Hex).unwrap();
        assert_eq!(r.complex.cells().next().unwrap().vertices, &vtk);
    }

    #[test]
    fn errors_name_the_line() {
        let cases: &[(&str, Format, &str)] = &[
            ("", Format::Tri, "t.tri:1: unexpected end of file"),
            (
                "3\n0 0 0\n1 0 0\n",
                Format::Tri,
                "t.tri:4: unexpected end of file",
            ),
            (
                "3\n0 0 0\n1 0\n0 1 0\n",
                Format::Tri,
                "t.tri:3: vertex 1 has 2 values but the first vertex line (line 2) has 3",
            ),
            (
                "3\n0 0 0\n1 0 0\n0 1 0\n1\n0 1 3\n",
                Format::Tri,
                "t.tri:6: cell vertex 3 is out of range",
            ),
            (
                "3\n0 0 0\n1 0 0\n0 1 0\n1\n0 1 2 4\n",
                Format::Tri,
                "t.tri:6: unexpected extra value '4'",
            ),
            (
                "3\n0 0 0\n1 0 0\n0 1 0\n1\n0 1 2\n0 1 2\n",
                Format::Tri,
                "t.tri:7: unexpected content after the 1 triangles",
            ),
            (
                "2 0\n0 0 0\n1 0 0\n",
                Format::Ts,
                "t.ts:2: expected the field value after x y z",
            ),
            (
                "1 0\n0 0 NaN 1\n",
                Format::Ts,
                "t.ts:2: vertex 0: coordinate 2 is not finite",
            ),
            (
                "4 1\n0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\n0 1 2 2\n",
                Format::Ts,
                "t.ts:6: cell 0: vertex 2 appears more than once",
            ),
            (
                "65 1 0\n0\n",
                Format::Sierp,
                "t.sierp:1: simplex dimension 65 is above",
            ),
            (
                "2 3 1\n0 0\n1 0\n0 1\n3 0 1\n",
                Format::Sierp,
                "t.sierp:5: expected cell vertex, found the end of the line",
            ),
            (
                "2 3 1\n0 0\n1 0\n0 1\nx 0 1 2\n",
                Format::Sierp,
                "t.sierp:5: expected the vertex count (ignored)",
            ),
            ("", Format::Hex, "t.hex:1: the file is empty"),
            ("# only a comment\n", Format::Hex, "the file is empty"),
            (
                "v 0 0 0\nq 1\n",
                Format::Hex,
                "t.hex:2: expected a line 'v x y z' or 'h i_0 .. i_7', found 'q'",
            ),
            (
                "v 0 0 0\nh 1 1 1 1 1 1 1 0\n",
                Format::Hex,
                "t.hex:2: cell vertex 0 is out of range",
            ),
            (
                "v 0 0 0\nv 1 0 0\nh 1 2 1 2 1 2 1 2\n",
                Format::Hex,
                "t.hex:3: cell 0: vertex",
            ),
            (
                "v 0 0 0\nv 1 0 0 2\n",
                Format::Hex,
                "t.hex:2: unexpected extra value '2'",
            ),
            (
                "3\n0 0 0\n",
                Format::Spx,
                "spx is not a Stellar reference format",
            ),
            (
                "4\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3\n0 1 2\n0 2 3\n2 1 0\n",
                Format::Tri,
                "t.tri:9: cell 2 has the same vertices as cell 0",
            ),
        ];
        for (text, f, want) in cases {
            let e = err(text, *f);
            assert!(e.contains(want), "{text:?}: got '{e}', want '{want}'");
        }
    }
}
