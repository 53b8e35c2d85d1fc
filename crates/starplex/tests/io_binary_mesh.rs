//! Binary gmsh (2.2, 4.1; little- and big-endian) and binary legacy VTK (4.2 classic cells, 5.1
//! offsets/connectivity) against the reference mesh of `scripts/make_io_corpus.py` (written by
//! meshio, or by hand where meshio does not write the variant): the same points and the same
//! cells of each kind. Truncated or corrupted files are errors with a byte offset, never a
//! panic.
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use starplex::cell::CellKind;
use starplex::complex::IndexedComplex;
use starplex::io::{self, gmsh, vtk, Location, ReadOptions};

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

#[test]
fn binary_files_read_the_reference_mesh() {
    let (pts, cells) = reference();
    let mut sorted_ref = pts.clone();
    sorted_ref.sort_by(|a, b| a.partial_cmp(b).unwrap());
    for name in BINARY.iter().chain(ASCII.iter()) {
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
    ] {
        let kb = io::read(&data(b), &ReadOptions::default()).unwrap().complex;
        let ka = io::read(&data(a), &ReadOptions::default()).unwrap().complex;
        assert_eq!(kb, ka, "{b} vs {a}");
    }
}

#[test]
fn binary_vtk_notes_the_attributes_it_skips() {
    let r = io::read(&data("mixed_51_bin.vtk"), &ReadOptions::default()).unwrap();
    assert_eq!(
        r.notes,
        ["binary attribute data (POINT_DATA/CELL_DATA/FIELD) was not read"]
    );
}

fn read_bytes(name: &str, b: &[u8]) -> Result<io::ReadResult, io::IoError> {
    let o = ReadOptions::default();
    if name.ends_with(".msh") {
        gmsh::read_from(b, name.as_ref(), &o)
    } else {
        vtk::read_from(b, name.as_ref(), &o)
    }
}

#[test]
fn every_truncation_is_an_error_never_a_panic() {
    for name in BINARY {
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
    let mut seed = 0x5eed_u64;
    let mut next = || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        seed
    };
    for name in BINARY {
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
