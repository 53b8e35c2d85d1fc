//! Binary gmsh (2.2, 4.1; little- and big-endian), binary legacy VTK (4.2 classic cells, 5.1
//! offsets/connectivity) and VTK XML `.vtu` (ascii, inline base64, appended raw and base64, zlib,
//! UInt32/UInt64 headers, both byte orders) against the reference mesh of `scripts/make_io_corpus.py` (written by
//! meshio, or by hand where meshio does not write the variant): the same points and the same
//! cells of each kind. Truncated or corrupted files are errors with a byte offset, never a
//! panic.
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use starplex::attr::{AttrTarget, AttrValues};
use starplex::cell::CellKind;
use starplex::complex::IndexedComplex;
use starplex::io::{self, gmsh, vtk, vtu, Format, Location, ReadOptions};

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/io")
        .join(name)
}

type Cells = BTreeMap<String, Vec<Vec<[f64; 3]>>>;

fn meshio_name(k: CellKind) -> &'static str {
    match k {
        CellKind::Simplex(1) => "line",
        CellKind::Simplex(2) => "triangle",
        CellKind::Quad => "quad",
        CellKind::Simplex(3) => "tetra",
        CellKind::Hex => "hexahedron",
        CellKind::Prism => "wedge",
        CellKind::Pyramid => "pyramid",
        _ => "other",
    }
}

/// Cells by kind, each as its corners' coordinates (vertex numbering may differ by format).
fn cells_of(k: &IndexedComplex) -> Cells {
    let mut m = Cells::new();
    for c in k.cells() {
        let pts = c
            .vertices
            .iter()
            .map(|&v| {
                let p = k.point(starplex::ids::VertexId(v));
                [p[0], p[1], p[2]]
            })
            .collect();
        m.entry(meshio_name(c.kind).to_string())
            .or_default()
            .push(pts);
    }
    m
}

fn reference() -> (Vec<[f64; 3]>, Cells) {
    let text = std::fs::read_to_string(data("mixed.json")).unwrap();
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    let pts: Vec<[f64; 3]> = v["points"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| {
            let a = p.as_array().unwrap();
            [0, 1, 2].map(|i| a[i].as_f64().unwrap())
        })
        .collect();
    let mut cells = Cells::new();
    for b in v["cells"].as_array().unwrap() {
        let name = b[0].as_str().unwrap().to_string();
        for c in b[1].as_array().unwrap() {
            let corners = c
                .as_array()
                .unwrap()
                .iter()
                .map(|i| pts[i.as_u64().unwrap() as usize])
                .collect();
            cells.entry(name.clone()).or_default().push(corners);
        }
    }
    (pts, cells)
}

const BINARY: [&str; 6] = [
    "mixed_22_bin.msh",
    "mixed_41_bin.msh",
    "mixed_22_be.msh",
    "mixed_41_be.msh",
    "mixed_42_bin.vtk",
    "mixed_51_bin.vtk",
];
const ASCII: [&str; 4] = [
    "mixed_22_ascii.msh",
    "mixed_41_ascii.msh",
    "mixed_42_ascii.vtk",
    "mixed_51_ascii.vtk",
];
/// VTK XML files: meshio's (ascii, inline base64, zlib), VTK-style appended data written by the
/// script, and VTK's own writer's (appended raw with and without zlib, inline binary, ascii).
const VTU: [&str; 12] = [
    "mixed_ascii.vtu",
    "mixed_b64.vtu",
    "mixed_b64_zlib.vtu",
    "mixed_b64_zlib64.vtu",
    "mixed_app_raw.vtu",
    "mixed_app_raw_zlib.vtu",
    "mixed_app_raw_be.vtu",
    "mixed_app_base64.vtu",
    "mixed_app_base64_zlib_be.vtu",
    "vtk_appended_zlib.vtu",
    "vtk_appended_raw.vtu",
    "vtk_binary.vtu",
];

#[test]
fn binary_files_read_the_reference_mesh() {
    let (pts, cells) = reference();
    let mut sorted_ref = pts.clone();
    sorted_ref.sort_by(|a, b| a.partial_cmp(b).unwrap());
    for name in BINARY.iter().chain(ASCII.iter()).chain(VTU.iter()) {
        let r = io::read(&data(name), &ReadOptions::default())
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        let k = &r.complex;
        assert_eq!(k.n_vertices(), pts.len(), "{name}");
        let mut got: Vec<[f64; 3]> = k
            .coords()
            .chunks_exact(3)
            .map(|p| [p[0], p[1], p[2]])
            .collect();
        got.sort_by(|a, b| a.partial_cmp(b).unwrap());
        assert_eq!(got, sorted_ref, "{name}: points");
        assert_eq!(cells_of(k), cells, "{name}: cells by kind");
    }
    // binary and ascii of one format read to the same complex, numbering included
    for (b, a) in [
        ("mixed_22_bin.msh", "mixed_22_ascii.msh"),
        ("mixed_41_bin.msh", "mixed_41_ascii.msh"),
        ("mixed_42_bin.vtk", "mixed_42_ascii.vtk"),
        ("mixed_51_bin.vtk", "mixed_51_ascii.vtk"),
        ("mixed_22_be.msh", "mixed_42_bin.vtk"),
        ("mixed_ascii.vtu", "mixed_42_bin.vtk"),
        ("mixed_app_raw.vtu", "mixed_b64_zlib.vtu"),
        ("mixed_app_base64_zlib_be.vtu", "mixed_b64.vtu"),
        ("vtk_appended_zlib.vtu", "mixed_b64.vtu"),
        ("vtk_surface.vtp", "surface.vtp"),
    ] {
        // (the geometry and cells: attributes are compared in io_attributes.rs)
        let mut kb = io::read(&data(b), &ReadOptions::default()).unwrap().complex;
        let mut ka = io::read(&data(a), &ReadOptions::default()).unwrap().complex;
        kb.take_attributes();
        ka.take_attributes();
        assert_eq!(kb, ka, "{b} vs {a}");
    }
    // VTK's ascii writer keeps 6 digits (and puts InformationKey elements in data arrays): the
    // same cells, points within its precision
    let ka = io::read(&data("vtk_ascii.vtu"), &ReadOptions::default())
        .unwrap()
        .complex;
    let kb = io::read(&data("mixed_b64.vtu"), &ReadOptions::default())
        .unwrap()
        .complex;
    assert_eq!(ka.blocks().len(), kb.blocks().len());
    for (x, y) in ka.blocks().iter().zip(kb.blocks()) {
        assert_eq!((x.kind, &x.vertices[..]), (y.kind, &y.vertices[..]));
    }
    for (x, y) in ka.coords().iter().zip(kb.coords()) {
        assert!((x - y).abs() < 1e-5, "{x} {y}");
    }
}

#[test]
fn binary_vtk_reads_its_point_data() {
    let r = io::read(&data("mixed_51_bin.vtk"), &ReadOptions::default()).unwrap();
    assert!(r.notes.is_empty(), "{:?}", r.notes);
    let k = &r.complex;
    let h = k.attributes().get(AttrTarget::Vertex, "height").unwrap();
    let z: Vec<f64> = k.coords().chunks_exact(3).map(|p| p[2]).collect();
    assert_eq!(h.values, AttrValues::Float(z));
}

fn read_bytes(name: &str, b: &[u8]) -> Result<io::ReadResult, io::IoError> {
    let o = ReadOptions::default();
    if name.ends_with(".msh") {
        gmsh::read_from(b, name.as_ref(), &o)
    } else if name.ends_with(".vtu") {
        vtu::read_bytes(b, name.as_ref(), &o)
    } else {
        vtk::read_from(b, name.as_ref(), &o)
    }
}

#[test]
fn every_truncation_is_an_error_never_a_panic() {
    for name in BINARY.iter().chain(VTU.iter().skip(1)) {
        let bytes = std::fs::read(data(name)).unwrap();
        for cut in 0..bytes.len() {
            let r = read_bytes(name, &bytes[..cut]);
            // a cut inside the trailing "$End..." or after the cells can still read; anything
            // else must be an error
            if let Err(e) = r {
                assert!(e.to_string().starts_with(name), "{e}");
            }
        }
        // cutting the mesh data itself must fail
        assert!(
            read_bytes(name, &bytes[..bytes.len() / 2]).is_err(),
            "{name}"
        );
    }
}

#[test]
fn corrupted_bytes_never_panic() {
    let mut rng = starplex::testkit::XorShift::new(0x5eed);
    let mut next = || rng.next_u64();
    for name in BINARY.iter().chain(VTU.iter()) {
        let bytes = std::fs::read(data(name)).unwrap();
        for _ in 0..400 {
            let mut b = bytes.clone();
            for _ in 0..1 + next() % 4 {
                let i = (next() % b.len() as u64) as usize;
                b[i] = next() as u8;
            }
            let _ = read_bytes(name, &b);
        }
    }
}

#[test]
fn binary_errors_name_a_byte() {
    // a wrong byte-order marker
    let mut b = std::fs::read(data("mixed_41_bin.msh")).unwrap();
    let at = b.windows(8).position(|w| w == b"4.1 1 8\n").unwrap() + 8;
    b[at..at + 4].copy_from_slice(&[7, 0, 0, 7]);
    let e = read_bytes("m.msh", &b).unwrap_err();
    assert_eq!(e.location, Some(Location::Byte(at as u64)));
    assert!(e.to_string().contains("expected the integer 1"), "{e}");
    // an element node that is not a node
    let mut b = std::fs::read(data("mixed_22_be.msh")).unwrap();
    let el = b.windows(10).position(|w| w == b"$Elements\n").unwrap();
    let body = el + b[el..].iter().skip(10).position(|&c| c == b'\n').unwrap() + 11;
    // first element: header 12 bytes, then tag, 2 tags, first node (big-endian i32)
    let node = body + 12 + 12;
    b[node..node + 4].copy_from_slice(&999i32.to_be_bytes());
    let e = read_bytes("m.msh", &b).unwrap_err();
    assert!(matches!(e.location, Some(Location::Byte(_))), "{e}");
    assert!(e.to_string().contains("node tag 999 is not a node"), "{e}");
    // binary VTK: a point index out of range
    let mut b = std::fs::read(data("mixed_42_bin.vtk")).unwrap();
    let cells = b.windows(6).position(|w| w == b"CELLS ").unwrap();
    let body = cells + b[cells..].iter().position(|&c| c == b'\n').unwrap() + 1;
    b[body + 4..body + 8].copy_from_slice(&1000i32.to_be_bytes());
    let e = read_bytes("m.vtk", &b).unwrap_err();
    assert_eq!(e.location, Some(Location::Byte(body as u64 + 4)), "{e}");
    assert!(e.to_string().contains("out of range"), "{e}");
}

#[test]
fn vtu_reads_its_point_data_and_vtp_reads_every_section() {
    let r = io::read(&data("mixed_app_raw.vtu"), &ReadOptions::default()).unwrap();
    assert_eq!(r.format, Format::Vtu);
    assert!(r.notes.is_empty(), "{:?}", r.notes);
    let h = r
        .complex
        .attributes()
        .get(AttrTarget::Vertex, "height")
        .unwrap();
    // written as Float32: the heights within single precision
    for (x, p) in (0..h.n_items()).zip(r.complex.coords().chunks_exact(3)) {
        assert!((h.values.get_f64(x) - p[2]).abs() < 1e-6 * p[2].abs().max(1.0));
    }
    // two pieces: a vertex (dropped), a 3-edge poly-line, a 6-point strip (4 triangles), a
    // triangle; a pentagon (3 triangles) and a quad
    let r = io::read(&data("surface.vtp"), &ReadOptions::default()).unwrap();
    assert_eq!(r.format, Format::Vtp);
    let k = &r.complex;
    assert_eq!(k.n_vertices(), 12 + 9);
    let count = |kind| k.cells().filter(|c| c.kind == kind).count();
    assert_eq!(count(CellKind::Simplex(1)), 3);
    assert_eq!(count(CellKind::Simplex(2)), 4 + 1 + 3);
    assert_eq!(count(CellKind::Quad), 1);
    // the second piece's ids are shifted past the first piece's points
    assert!(k
        .cells()
        .any(|c| c.kind == CellKind::Quad && c.vertices == [17, 18, 19, 20]));
    // strips keep one orientation: the triangles of 4 8 5 9 are 4 8 5 and 8 5 9 flipped
    assert!(k.cells().any(|c| c.vertices == [4, 8, 5]));
    assert!(k.cells().any(|c| c.vertices == [5, 8, 9]));
    assert_eq!(r.notes.len(), 4, "{:?}", r.notes);
}

#[test]
fn vtu_and_vtp_round_trip_every_kind_they_hold() {
    let mixed = io::read(&data("mixed_b64_zlib.vtu"), &ReadOptions::default())
        .unwrap()
        .complex;
    let mut out = Vec::new();
    vtu::write_vtu(&mut out, &mixed).unwrap();
    let back = vtu::read_bytes(&out, "m.vtu".as_ref(), &ReadOptions::default()).unwrap();
    assert_eq!(back.complex, mixed);
    assert!(back.notes.is_empty(), "{:?}", back.notes);
    // poly data refuses volume cells, holds the surface kinds
    let e = vtu::write_vtp(&mut Vec::new(), &mixed).unwrap_err();
    assert!(e.to_string().contains("write .vtu"), "{e}");
    let surf = io::read(&data("surface.vtp"), &ReadOptions::default())
        .unwrap()
        .complex;
    let mut out = Vec::new();
    vtu::write_vtp(&mut out, &surf).unwrap();
    let back = vtu::read_bytes(&out, "s.vtp".as_ref(), &ReadOptions::default()).unwrap();
    assert_eq!(back.complex, surf);
}

#[test]
fn vtu_errors_say_what_and_where() {
    let o = ReadOptions::default();
    let bad = |text: &str| {
        vtu::read_bytes(text.as_bytes(), "b.vtu".as_ref(), &o)
            .unwrap_err()
            .to_string()
    };
    assert!(bad("").contains("empty"));
    assert!(bad("<VTKFile type=\"ImageData\"/>").contains("ImageData"));
    assert!(bad("<a><b></a>").contains("malformed XML"));
    let head = |body: &str| {
        format!(
            "<VTKFile type=\"UnstructuredGrid\"><UnstructuredGrid><Piece NumberOfPoints=\"3\" NumberOfCells=\"1\">\
             <Points><DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"ascii\">0 0 0 1 0 0 0 1 0</DataArray></Points>\
             <Cells>{body}</Cells></Piece></UnstructuredGrid></VTKFile>"
        )
    };
    let da = |name: &str, ty: &str, v: &str| {
        format!("<DataArray type=\"{ty}\" Name=\"{name}\" format=\"ascii\">{v}</DataArray>")
    };
    let cells = |conn: &str, offs: &str, types: &str| {
        head(&format!(
            "{}{}{}",
            da("connectivity", "Int32", conn),
            da("offsets", "Int32", offs),
            da("types", "UInt8", types)
        ))
    };
    assert!(bad(&cells("0 1 7", "3", "5")).contains("point 7, out of range"));
    assert!(bad(&cells("0 1 -2", "3", "5")).contains("negative"));
    assert!(bad(&cells("0 1 2", "4", "5")).contains("offsets must grow"));
    assert!(bad(&cells("0 1 2", "3", "42")).contains("type 42 (polyhedron) is not supported"));
    assert!(bad(&cells("0 1 2", "3", "10")).contains("needs 4 points"));
    assert!(bad(&cells("0 1 x", "3", "5")).contains("'x' is not a Int32 value"));
    assert!(bad(&head(&da("connectivity", "Int32", "0 1 2"))).contains("no offsets"));
    let ok = vtu::read_bytes(cells("0 1 2", "3", "5").as_bytes(), "g.vtu".as_ref(), &o).unwrap();
    assert_eq!(ok.complex.n_cells(), 1);
    // dataset-level field data (ParaView writes the time there) is not part of the mesh
    let with_field = cells("0 1 2", "3", "5").replace(
        "<UnstructuredGrid>",
        "<UnstructuredGrid><FieldData><DataArray type=\"Float64\" Name=\"TimeValue\" \
         NumberOfTuples=\"1\" format=\"ascii\">0.5</DataArray></FieldData>",
    );
    let r = vtu::read_bytes(with_field.as_bytes(), "f.vtu".as_ref(), &o).unwrap();
    assert_eq!(r.complex, ok.complex);
}
