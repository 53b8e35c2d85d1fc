//! The writers added for issue 11 (third pass): gmsh 4.1 with physical and geometrical tags as
//! geometric entities (ascii and binary), PLY `edge` elements with their attributes, legacy VTK
//! `POLYDATA`; each written, read back and compared, attributes included. Their output for
//! meshio (`scripts/check_writers_more.py`) is written by `own_outputs_for_meshio`.
use std::path::PathBuf;

use starplex::attr::{AttrTarget, AttrValues, Attribute, Attributes};
use starplex::buf::Buf;
use starplex::cell::CellKind;
use starplex::complex::IndexedComplex;
use starplex::io::{self, gmsh, ply, vtk, Format, IoErrorKind, ReadOptions};

fn data(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/io")
        .join(name)
}

fn complex(
    coords: Vec<f64>,
    blocks: &[(CellKind, &[u32])],
    vertex: Vec<Attribute>,
    cell: Vec<Attribute>,
) -> IndexedComplex {
    let blocks = blocks
        .iter()
        .map(|(k, v)| (*k, Buf::from(v.to_vec())))
        .collect();
    let mut k = IndexedComplex::from_parts(3, coords.into(), blocks).unwrap();
    k.set_attributes(Attributes { vertex, cell }).unwrap();
    k
}

/// Two tetrahedra sharing a face, a triangle hanging off one of them, and a dangling edge
/// (every vertex in some cell, no cell a face of another).
fn volume(phys: Vec<i64>, geom: Option<Vec<i64>>) -> IndexedComplex {
    let coords = vec![
        0., 0., 0., 1., 0., 0., 0., 1., 0., 0., 0., 1., 1., 1., 1., 2., 0., 0., 3., 3., 3.,
    ];
    let mut cell = vec![Attribute::int("gmsh:physical", 1, phys)];
    if let Some(g) = geom {
        cell.push(Attribute::int("gmsh:geometrical", 1, g));
    }
    cell.push(Attribute::float(
        "stress",
        2,
        vec![0.5, -1.0, 1e-300, 2.0, 3.25, -0.0, 7.0, 8.0],
    ));
    let n = 7;
    complex(
        coords,
        &[
            (CellKind::Simplex(3), &[0, 1, 2, 3, 1, 2, 3, 4]),
            (CellKind::Simplex(2), &[0, 1, 5]),
            (CellKind::Simplex(1), &[4, 6]),
        ],
        vec![Attribute::float(
            "T",
            1,
            (0..n).map(|i| i as f64 * 0.1).collect(),
        )],
        cell,
    )
}

fn read_msh(bytes: &[u8]) -> IndexedComplex {
    gmsh::read_from(bytes, "t.msh".as_ref(), &ReadOptions::default())
        .unwrap_or_else(|e| panic!("{e}"))
        .complex
}

fn write_both(k: &IndexedComplex) -> [IndexedComplex; 2] {
    let mut a = Vec::new();
    gmsh::write(&mut a, k).unwrap();
    let mut b = Vec::new();
    gmsh::write_binary(&mut b, k).unwrap();
    assert!(b.starts_with(b"$MeshFormat\n4.1 1 8\n\x01\0\0\0\n$EndMeshFormat\n"));
    [read_msh(&a), read_msh(&b)]
}

fn without_attributes(k: &IndexedComplex) -> IndexedComplex {
    let mut k = k.clone();
    k.take_attributes();
    k
}

#[test]
fn gmsh_41_writes_physical_and_geometrical_tags_as_entities() {
    // consistent tags: everything comes back, in both encodings
    let k = volume(vec![10, 10, 20, 0], Some(vec![1, 2, 3, 4]));
    assert!(Format::Gmsh.dropped_attributes(k.attributes()).is_empty());
    assert!(Format::GmshBinary
        .dropped_attributes(k.attributes())
        .is_empty());
    for back in write_both(&k) {
        assert_eq!(back, k);
    }
    // one geometrical tag in two physical groups: 4.1 numbers the entities by physical tag
    let k = volume(vec![10, 11, 20, 0], Some(vec![1, 1, 3, 4]));
    assert_eq!(
        Format::Gmsh.dropped_attributes(k.attributes()),
        ["cell gmsh:geometrical"]
    );
    assert!(Format::Gmsh22.dropped_attributes(k.attributes()).is_empty());
    for back in write_both(&k) {
        assert_eq!(without_attributes(&back), without_attributes(&k));
        let a = back.attributes();
        assert_eq!(
            a.get(AttrTarget::Cell, "gmsh:physical"),
            k.attributes().get(AttrTarget::Cell, "gmsh:physical")
        );
        assert_eq!(
            a.get(AttrTarget::Cell, "gmsh:geometrical").unwrap().values,
            AttrValues::Int(vec![1, 2, 1, 1])
        );
        assert_eq!(a.vertex, k.attributes().vertex);
        assert_eq!(
            a.get(AttrTarget::Cell, "stress"),
            k.attributes().get(AttrTarget::Cell, "stress")
        );
    }
    // physical tags only (negative ones too: an int)
    let k = volume(vec![-3, 7, 7, 0], None);
    for back in write_both(&k) {
        assert_eq!(
            back.attributes().get(AttrTarget::Cell, "gmsh:physical"),
            k.attributes().get(AttrTarget::Cell, "gmsh:physical")
        );
        assert_eq!(
            back.attributes()
                .get(AttrTarget::Cell, "gmsh:geometrical")
                .unwrap()
                .values,
            AttrValues::Int(vec![1, 2, 1, 1])
        );
    }
    // tags a 4.1 entity cannot take are named as dropped, and the file still reads
    let k = volume(vec![1 << 40, 1, 1, 1], Some(vec![0, 1, 2, 3]));
    assert_eq!(
        Format::Gmsh.dropped_attributes(k.attributes()),
        ["cell gmsh:physical", "cell gmsh:geometrical"]
    );
    for back in write_both(&k) {
        assert_eq!(without_attributes(&back), without_attributes(&k));
        assert!(back
            .attributes()
            .get(AttrTarget::Cell, "gmsh:physical")
            .is_none());
    }
}

#[test]
fn gmsh_binary_writer_gives_what_the_ascii_one_gives() {
    let opts = ReadOptions::default();
    for f in [
        "gmsh_41_bin.msh",
        "gmsh_22_ascii.msh",
        "meshio_22_bin.msh",
        "meshio_41_bin.msh",
        "mixed_41_ascii.msh",
        "mixed_22_be.msh",
    ] {
        let k = io::read(&data(f), &opts).unwrap().complex;
        let [a, b] = write_both(&k);
        assert_eq!(a, b, "{f}");
        // every column that the format is said to hold comes back
        let dropped = Format::GmshBinary.dropped_attributes(k.attributes());
        assert_eq!(without_attributes(&b), without_attributes(&k), "{f}");
        for t in [AttrTarget::Vertex, AttrTarget::Cell] {
            for c in k.attributes().of(t) {
                if dropped.contains(&format!("{t} {}", c.name)) {
                    continue;
                }
                let got = b
                    .attributes()
                    .get(t, &c.name)
                    .unwrap_or_else(|| panic!("{f}: {}", c.name));
                match (&c.values, &got.values) {
                    (AttrValues::Int(x), AttrValues::Float(y)) => {
                        // data sections are double (tags stay integers)
                        assert!(!c.name.starts_with("gmsh:"), "{f}: {}", c.name);
                        assert!(
                            x.iter().zip(y).all(|(a, b)| *a as f64 == *b),
                            "{f}: {}",
                            c.name
                        );
                    }
                    _ => assert_eq!(got, c, "{f}"),
                }
            }
        }
    }
    // through io::write with the format name, and an empty complex
    let dir = std::env::temp_dir().join(format!("starplex-writers-more-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let k = volume(vec![1, 1, 2, 2], None);
    let p = dir.join("v.msh");
    io::write(&p, &k, Format::from_name("msh-binary")).unwrap();
    let back = io::read(&p, &opts).unwrap();
    assert_eq!(without_attributes(&back.complex), without_attributes(&k));
    let empty = IndexedComplex::from_parts(3, Vec::new().into(), vec![]).unwrap();
    let pts = IndexedComplex::from_parts(2, vec![0.0, 1.0, 2.0, 3.0].into(), vec![]).unwrap();
    for e in [&empty, &pts] {
        let mut out = Vec::new();
        gmsh::write_binary(&mut out, e).unwrap();
        let back = read_msh(&out);
        assert_eq!(back.n_cells(), 0);
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// Triangles, a quad and two edges, in the order `order` of block kinds.
fn surface_with_edges(edges_first: bool) -> IndexedComplex {
    let coords = vec![
        0., 0., 0., 1., 0., 0., 1., 1., 0., 0., 1., 0., 2., 0., 0., 2., 1., 0., 5., 5., 5., 6., 5.,
        5.,
    ];
    let faces: [(CellKind, &[u32]); 2] = [
        (CellKind::Simplex(2), &[0, 1, 2, 0, 2, 3]),
        (CellKind::Quad, &[1, 4, 5, 2]),
    ];
    let edges: (CellKind, &[u32]) = (CellKind::Simplex(1), &[6, 7, 5, 6]);
    let blocks: Vec<(CellKind, &[u32])> = if edges_first {
        std::iter::once(edges).chain(faces).collect()
    } else {
        faces.into_iter().chain(std::iter::once(edges)).collect()
    };
    complex(
        coords,
        &blocks,
        vec![
            Attribute::int("red", 1, vec![0, 10, 20, 30, 40, 50, 60, 255]),
            Attribute::float("height", 1, vec![0.5, 1.5, 2.5, 3.5, 4.5, 5.5, 6.5, -7.25]),
        ],
        vec![
            Attribute::int("label", 1, vec![1, -2, 300, 4, 5]),
            Attribute::float("q", 2, (0..10).map(|i| i as f64 / 3.0).collect()),
        ],
    )
}

fn read_ply(bytes: &[u8]) -> IndexedComplex {
    ply::read_from(
        bytes,
        bytes.len() as u64,
        "t.ply".as_ref(),
        &ReadOptions::default(),
    )
    .unwrap_or_else(|e| panic!("{e}"))
    .complex
}

#[test]
fn ply_writes_edges_with_their_attributes() {
    for edges_first in [false, true] {
        let k = surface_with_edges(edges_first);
        assert!(Format::Ply.dropped_attributes(k.attributes()).is_empty());
        for enc in [
            ply::PlyEncoding::Ascii,
            ply::PlyEncoding::BinaryLittleEndian,
        ] {
            let mut out = Vec::new();
            ply::write_with(&mut out, &k, enc).unwrap();
            let head = String::from_utf8_lossy(&out[..400.min(out.len())]).into_owned();
            assert!(
                head.contains("element edge 2\nproperty int vertex1\nproperty int vertex2\nproperty int label"),
                "{head}"
            );
            assert_eq!(read_ply(&out), k, "{enc:?} edges first {edges_first}");
        }
    }
    // edges only: no face element
    let k = complex(
        vec![0., 0., 0., 1., 0., 0., 2., 0., 0.],
        &[(CellKind::Simplex(1), &[0, 1, 1, 2])],
        vec![],
        vec![Attribute::int("id", 1, vec![7, 8])],
    );
    let mut out = Vec::new();
    ply::write(&mut out, &k).unwrap();
    assert!(!String::from_utf8_lossy(&out).contains("element face"));
    assert_eq!(read_ply(&out), k);
    // faces, then edges, then faces again: read back grouped by element, each in order
    let k = complex(
        vec![
            0., 0., 0., 1., 0., 0., 0., 1., 0., 5., 5., 5., 6., 5., 5., 7., 7., 7., 8., 8., 9.,
        ],
        &[
            (CellKind::Simplex(2), &[0, 1, 2]),
            (CellKind::Simplex(1), &[3, 4]),
            (CellKind::Simplex(2), &[4, 5, 6]),
        ],
        vec![],
        vec![Attribute::float("w", 1, vec![1.0, 2.0, 3.0])],
    );
    let mut out = Vec::new();
    ply::write(&mut out, &k).unwrap();
    let back = read_ply(&out);
    let want = complex(
        vec![
            0., 0., 0., 1., 0., 0., 0., 1., 0., 5., 5., 5., 6., 5., 5., 7., 7., 7., 8., 8., 9.,
        ],
        &[
            (CellKind::Simplex(2), &[0, 1, 2, 4, 5, 6]),
            (CellKind::Simplex(1), &[3, 4]),
        ],
        vec![],
        vec![Attribute::float("w", 1, vec![1.0, 3.0, 2.0])],
    );
    assert_eq!(back, want);
    // OBJ still refuses dangling edges; PLY refuses point cells and volumes
    assert!(io::check_writable(&k, Format::Obj).is_err());
    let pt = complex(vec![0.; 3], &[(CellKind::Simplex(0), &[0])], vec![], vec![]);
    assert!(matches!(
        io::check_writable(&pt, Format::Ply),
        Err(IoErrorKind::CannotWrite { .. })
    ));
}

fn read_vtk(bytes: &[u8]) -> IndexedComplex {
    vtk::read_from(bytes, "t.vtk".as_ref(), &ReadOptions::default())
        .unwrap_or_else(|e| panic!("{e}\n{}", String::from_utf8_lossy(bytes)))
        .complex
}

#[test]
fn legacy_vtk_polydata_writer_round_trips() {
    // edges first: VTK's own cell order, so the complex comes back as it is
    let k = surface_with_edges(true);
    let mut out = Vec::new();
    vtk::write_polydata(&mut out, &k).unwrap();
    let text = String::from_utf8(out.clone()).unwrap();
    assert!(text.contains("DATASET POLYDATA\n"), "{text}");
    assert!(
        text.contains("LINES 2 6\n3 6 7\n") || text.contains("LINES 2 6\n2 6 7\n2 5 6\n"),
        "{text}"
    );
    assert!(text.contains("POLYGONS 3 13\n"), "{text}");
    assert_eq!(read_vtk(&out), k);
    // faces first: the edges come back first, with their attributes
    let k = surface_with_edges(false);
    let mut out = Vec::new();
    vtk::write_polydata(&mut out, &k).unwrap();
    let back = read_vtk(&out);
    let want = surface_with_edges(true);
    assert_eq!(without_attributes(&back), without_attributes(&want));
    assert_eq!(back.attributes().vertex, k.attributes().vertex);
    let order = [3usize, 4, 0, 1, 2]; // cell i of the file is cell order[i] of k
    for c in &k.attributes().cell {
        let got = back.attributes().get(AttrTarget::Cell, &c.name).unwrap();
        for (i, &o) in order.iter().enumerate() {
            for j in 0..c.components {
                let a = got.values.get_f64(i * c.components + j);
                let b = c.values.get_f64(o * c.components + j);
                assert_eq!(a, b, "{} cell {i}", c.name);
            }
        }
        assert_eq!(got.values.type_name(), c.values.type_name());
    }
    // through io::write by format name; the unstructured writer is unchanged
    let dir = std::env::temp_dir().join(format!("starplex-polydata-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join("s.vtk");
    io::write(&p, &want, Format::from_name("vtk-polydata")).unwrap();
    assert!(std::fs::read_to_string(&p)
        .unwrap()
        .contains("DATASET POLYDATA"));
    assert_eq!(io::read(&p, &ReadOptions::default()).unwrap().complex, want);
    io::write(&p, &want, None).unwrap();
    assert!(std::fs::read_to_string(&p)
        .unwrap()
        .contains("DATASET UNSTRUCTURED_GRID"));
    std::fs::remove_dir_all(&dir).ok();
    // refused: volumes and point cells
    let tet = volume(vec![1; 4], None);
    let e = io::check_writable(&tet, Format::VtkPolyData).unwrap_err();
    assert!(
        e.to_string()
            .contains("POLYDATA holds edges, triangles and quads"),
        "{e}"
    );
    let pt = complex(vec![0.; 3], &[(CellKind::Simplex(0), &[0])], vec![], vec![]);
    assert!(vtk::check_polydata(&pt).is_err());
}

/// Writes this file's outputs for `scripts/check_writers_more.py` (meshio reads them back) to
/// `$STARPLEX_WRITERS_OUT` when set, else to a temporary directory (which checks every write).
#[test]
fn own_outputs_for_meshio() {
    let dir = match std::env::var_os("STARPLEX_WRITERS_OUT") {
        Some(d) => PathBuf::from(d),
        None => std::env::temp_dir().join(format!("starplex-writers-out-{}", std::process::id())),
    };
    std::fs::create_dir_all(&dir).unwrap();
    let k = volume(vec![10, 10, 20, 30], Some(vec![1, 2, 3, 4]));
    io::write(&dir.join("tags_41.msh"), &k, Some(Format::Gmsh)).unwrap();
    io::write(&dir.join("tags_41_bin.msh"), &k, Some(Format::GmshBinary)).unwrap();
    // gmsh 2.2 binary without the element data: meshio 5.3.5 splits 2.2 `$ElementData` wrongly
    // over several cell blocks (its own ascii 2.2 reading of starplex's msh22 fails the same way)
    let mut k22 = k.clone();
    let mut a22 = k22.take_attributes();
    a22.cell.retain(|c| c.name != "stress");
    k22.set_attributes(a22).unwrap();
    io::write(
        &dir.join("tags_22_bin.msh"),
        &k22,
        Some(Format::Gmsh22Binary),
    )
    .unwrap();
    let gmsh_ref = k.attributes().clone();
    let s = surface_with_edges(true);
    io::write(&dir.join("edges_bin.ply"), &s, None).unwrap();
    let mut out = Vec::new();
    ply::write_with(&mut out, &s, ply::PlyEncoding::Ascii).unwrap();
    std::fs::write(dir.join("edges_ascii.ply"), out).unwrap();
    io::write(&dir.join("poly.vtk"), &s, Some(Format::VtkPolyData)).unwrap();
    // the reference: what starplex holds, as JSON
    let col = |a: &Attribute| {
        let v: Vec<serde_json::Value> = (0..a.values.len())
            .map(|i| {
                let x = a.values.get_f64(i);
                if x.is_nan() {
                    serde_json::Value::Null
                } else {
                    serde_json::json!(x)
                }
            })
            .collect();
        serde_json::json!({"components": a.components, "values": v})
    };
    let cols = |a: &Attributes| {
        let mut m = serde_json::Map::new();
        for (t, list) in [("vertex", &a.vertex), ("cell", &a.cell)] {
            let mut c = serde_json::Map::new();
            for x in list {
                c.insert(x.name.clone(), col(x));
            }
            m.insert(t.into(), c.into());
        }
        serde_json::Value::Object(m)
    };
    let blocks = |k: &IndexedComplex| {
        k.blocks()
            .iter()
            .map(|b| serde_json::json!([b.kind.to_string(), b.vertices.to_vec()]))
            .collect::<Vec<_>>()
    };
    let reference = serde_json::json!({
        "gmsh": {"attrs": cols(&gmsh_ref), "points": k.coords().to_vec(), "blocks": blocks(&k)},
        "surface": {"attrs": cols(s.attributes()), "points": s.coords().to_vec(), "blocks": blocks(&s)},
    });
    std::fs::write(dir.join("reference.json"), reference.to_string()).unwrap();
    if std::env::var_os("STARPLEX_WRITERS_OUT").is_none() {
        std::fs::remove_dir_all(&dir).ok();
    }
}
