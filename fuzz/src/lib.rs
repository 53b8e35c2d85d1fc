//! What the fuzz targets share: the reader options picked by an input's first byte, and the
//! read → write → read round trip every target with a writer runs.
use std::io::Write;

use starplex::attr::{AttrTarget, AttrValues, Attribute};
use starplex::complex::IndexedComplex;
use starplex::io::{Format, IoError, IoErrorKind, PolygonMode, ReadOptions, ReadResult};

/// Reader options from a target's mode byte: bit 1 drops duplicate cells, bit 2 drops cells
/// that are faces of others, bit 3 degenerate cells, bit 4 reads leniently (OFF face counts;
/// the `gzip` target uses bits 3-4 for its own choices too), and, when `polygon_bit` is set (OFF, PLY), bit 0 reads every
/// face as a simplex.
pub fn options(mode: u8, polygon_bit: bool) -> ReadOptions {
    let mut opts = ReadOptions::default();
    if polygon_bit && mode & 1 == 1 {
        opts.polygons = PolygonMode::Simplices;
    }
    opts.build.drop_duplicates = mode & 2 == 2;
    opts.build.drop_face_cells = mode & 4 == 4;
    opts.build.drop_degenerate = mode & 8 == 8;
    opts.lenient = mode & 16 == 16;
    opts
}

/// Reads `data`; when that succeeds and `write` accepts the complex, reads the written bytes
/// back (which must succeed) and returns both results.
pub fn round_trip(
    data: &[u8],
    opts: &ReadOptions,
    read: impl Fn(&[u8], &ReadOptions) -> Result<ReadResult, IoError>,
    write: impl Fn(&mut dyn Write, &IndexedComplex) -> Result<(), IoErrorKind>,
) -> Option<(ReadResult, ReadResult)> {
    let r = read(data, opts).ok()?;
    let mut out = Vec::new();
    write(&mut out, &r.complex).ok()?;
    let back = read(&out, opts).expect("a written file must read back");
    Some((r, back))
}

/// Whether two complexes are the same, attributes included, with NaN equal to NaN (a reader
/// fills the items a data section does not cover with NaN, and `==` on `f64` says NaN != NaN).
pub fn same(a: &IndexedComplex, b: &IndexedComplex) -> bool {
    let (mut a, mut b) = (a.clone(), b.clone());
    let (aa, ab) = (a.take_attributes(), b.take_attributes());
    let col = |x: &Attribute, y: &Attribute| {
        x.name == y.name
            && x.components == y.components
            && match (&x.values, &y.values) {
                (AttrValues::Int(p), AttrValues::Int(q)) => p == q,
                (AttrValues::Float(p), AttrValues::Float(q)) => {
                    p.len() == q.len()
                        && p.iter().zip(q).all(|(u, v)| u == v || (u.is_nan() && v.is_nan()))
                }
                _ => false,
            }
    };
    let cols = |p: &[Attribute], q: &[Attribute]| {
        p.len() == q.len() && p.iter().zip(q).all(|(x, y)| col(x, y))
    };
    a == b && cols(&aa.vertex, &ab.vertex) && cols(&aa.cell, &ab.cell)
}

/// [`same`] for a round trip through `format`: the attribute columns the format cannot hold
/// (which the writer drops with a note, e.g. NOFF normals in OFF) are left out of `read`.
pub fn same_after_writing(read: &IndexedComplex, back: &IndexedComplex, format: Format) -> bool {
    let dropped = format.dropped_attributes(read.attributes());
    let mut r = read.clone();
    let mut attrs = r.take_attributes();
    attrs
        .vertex
        .retain(|c| !dropped.contains(&format!("{} {}", AttrTarget::Vertex, c.name)));
    attrs
        .cell
        .retain(|c| !dropped.contains(&format!("{} {}", AttrTarget::Cell, c.name)));
    r.set_attributes(attrs).expect("a subset of the columns it had");
    same(&r, back)
}
