//! Attributes read from files written by meshio (`scripts/make_io_corpus.py --attributes`):
//! point and cell data of `.vtu` (ascii, base64 zlib) and legacy `.vtk` (4.2 and 5.1, ascii and
//! binary) equal the columns meshio was given (`mixed_attrs.json`), and survive starplex's own
//! writers.
use std::path::PathBuf;

use starplex::attr::{AttrTarget, AttrValues, Attribute};
use starplex::complex::IndexedComplex;
use starplex::io::{self, vtk, vtu, ReadOptions};

fn data(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/io")
        .join(name)
}

/// Checks every column of `mixed_attrs.json` against `k`.
fn check_against_reference(k: &IndexedComplex, what: &str) {
    let text = std::fs::read_to_string(data("mixed_attrs.json")).unwrap();
    let r: serde_json::Value = serde_json::from_str(&text).unwrap();
    for (target, key) in [(AttrTarget::Vertex, "vertex"), (AttrTarget::Cell, "cell")] {
        let cols = r[key].as_object().unwrap();
        assert_eq!(
            k.attributes().of(target).len(),
            cols.len(),
            "{what}: {key} columns"
        );
        for (name, rows) in cols {
            let a = k
                .attributes()
                .get(target, name)
                .unwrap_or_else(|| panic!("{what}: no {key} attribute '{name}'"));
            let rows = rows.as_array().unwrap();
            assert_eq!(a.n_items(), rows.len(), "{what}: {name}");
            assert_eq!(
                a.components,
                rows[0].as_array().unwrap().len(),
                "{what}: {name}"
            );
            let want: Vec<f64> = rows
                .iter()
                .flat_map(|r| r.as_array().unwrap().iter().map(|x| x.as_f64().unwrap()))
                .collect();
            let is_int = rows[0][0].is_i64() || rows[0][0].is_u64();
            match &a.values {
                AttrValues::Int(v) => {
                    assert!(is_int, "{what}: {name} read as integers");
                    let got: Vec<f64> = v.iter().map(|&x| x as f64).collect();
                    assert_eq!(got, want, "{what}: {name}");
                }
                AttrValues::Float(v) => {
                    assert!(!is_int, "{what}: {name} read as floats");
                    for (g, w) in v.iter().zip(&want) {
                        assert!(
                            (g - w).abs() <= 1e-12 * w.abs().max(1.0),
                            "{what}: {name}: {g} vs {w}"
                        );
                    }
                }
            }
        }
    }
}

#[test]
fn meshio_point_and_cell_data_are_read() {
    for f in [
        "attrs_ascii.vtu",
        "attrs_b64_zlib.vtu",
        "attrs_42_ascii.vtk",
        "attrs_42_bin.vtk",
        "attrs_51_ascii.vtk",
        "attrs_51_bin.vtk",
    ] {
        let r = io::read(&data(f), &ReadOptions::default()).unwrap_or_else(|e| panic!("{f}: {e}"));
        check_against_reference(&r.complex, f);
        assert!(
            r.notes.iter().all(|n| !n.contains("data arrays")),
            "{f}: {:?}",
            r.notes
        );
    }
}

#[test]
fn attributes_survive_starplex_writers() {
    let k = io::read(&data("attrs_b64_zlib.vtu"), &ReadOptions::default())
        .unwrap()
        .complex;
    let opts = ReadOptions::default();
    let mut out = Vec::new();
    vtu::write_vtu(&mut out, &k).unwrap();
    let back = vtu::read_bytes(&out, "a.vtu".as_ref(), &opts).unwrap();
    assert_eq!(back.complex, k, ".vtu");
    let mut out = Vec::new();
    vtk::write(&mut out, &k).unwrap();
    let back = vtk::read_from(&out[..], "a.vtk".as_ref(), &opts).unwrap();
    check_against_reference(&back.complex, "starplex .vtk");
    assert_eq!(back.complex.attributes(), k.attributes());
}

#[test]
fn poly_data_cell_attributes_follow_the_sections() {
    // an edge then a triangle: .vtp writes the triangle (Polys) after the edge (Lines) but
    // the cell data must stay with its cell
    use starplex::cell::CellKind;
    let mut k = IndexedComplex::from_parts(
        3,
        vec![0., 0., 0., 1., 0., 0., 0., 1., 0., 5., 5., 5., 6., 5., 5.].into(),
        vec![
            (CellKind::Simplex(2), vec![0, 1, 2].into()),
            (CellKind::Simplex(1), vec![3, 4].into()),
        ],
    )
    .unwrap();
    let mut a = starplex::attr::Attributes::default();
    a.cell.push(Attribute::int("id", 1, vec![100, 200]));
    a.vertex.push(Attribute::float(
        "w",
        2,
        (0..10).map(|x| x as f64 * 0.5).collect(),
    ));
    k.set_attributes(a).unwrap();
    let mut out = Vec::new();
    vtu::write_vtp(&mut out, &k).unwrap();
    let back = vtu::read_bytes(&out, "k.vtp".as_ref(), &ReadOptions::default())
        .unwrap()
        .complex;
    // cells come back section by section: the edge first
    let edge = back
        .cells()
        .find(|c| c.kind == CellKind::Simplex(1))
        .unwrap();
    let id = back.attributes().get(AttrTarget::Cell, "id").unwrap();
    assert_eq!(id.values.get_f64(edge.id.index()), 200.0);
    assert_eq!(back.attributes().vertex, k.attributes().vertex);
}

#[test]
fn split_cells_share_their_file_cell_values() {
    // a pentagon (fanned into 3 triangles) and a quad, with cell data
    let text = "# vtk DataFile Version 4.2\np\nASCII\nDATASET UNSTRUCTURED_GRID\n\
                POINTS 9 double\n0 0 0 1 0 0 2 1 0 1 2 0 0 1 0 5 0 0 6 0 0 6 1 0 5 1 0\n\
                CELLS 2 11\n5 0 1 2 3 4\n4 5 6 7 8\nCELL_TYPES 2\n7\n9\n\
                CELL_DATA 2\nSCALARS part int 1\nLOOKUP_TABLE default\n7 9\n\
                POINT_DATA 9\nVECTORS n float\n0 0 1 0 0 1 0 0 1 0 0 1 0 0 1 0 0 1 0 0 1 0 0 1 0 0 1\n";
    let r = vtk::read_from(text.as_bytes(), "p.vtk".as_ref(), &ReadOptions::default()).unwrap();
    let k = r.complex;
    assert_eq!(k.n_cells(), 4);
    let part = k.attributes().get(AttrTarget::Cell, "part").unwrap();
    assert_eq!(part.values, AttrValues::Int(vec![7, 7, 7, 9]));
    let n = k.attributes().get(AttrTarget::Vertex, "n").unwrap();
    assert_eq!((n.components, n.n_items()), (3, 9));
}

#[test]
fn bad_attribute_sections_are_errors_with_lines() {
    let head = "# vtk DataFile Version 4.2\np\nASCII\nDATASET UNSTRUCTURED_GRID\n\
                POINTS 3 double\n0 0 0 1 0 0 0 1 0\nCELLS 1 4\n3 0 1 2\nCELL_TYPES 1\n5\n";
    for (tail, want) in [
        (
            "POINT_DATA 4\nSCALARS s float\nLOOKUP_TABLE default\n1 2 3 4\n",
            "counts 4 items, the file has 3",
        ),
        (
            "CELL_DATA 1\nSCALARS s float\nLOOKUP_TABLE default\n",
            "end of file",
        ),
        (
            "CELL_DATA 1\nSCALARS s int\nLOOKUP_TABLE default\n1.5\n",
            "integer",
        ),
        (
            "CELL_DATA 1\nSCALARS s bit\nLOOKUP_TABLE default\n1\n",
            "data type 'bit'",
        ),
    ] {
        let text = format!("{head}{tail}");
        let e = vtk::read_from(text.as_bytes(), "p.vtk".as_ref(), &ReadOptions::default())
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("p.vtk:"), "{e}");
        assert!(e.contains(want), "{tail:?}: {e}");
    }
}

#[test]
fn gmsh_physical_and_elementary_tags_are_cell_attributes() {
    // meshio wrote physical 1 everywhere and elementary tag = block number (1..=7, the two
    // tetrahedra share block 1)
    let geometrical = AttrValues::Int(vec![1, 1, 2, 3, 4, 5, 6, 7]);
    for f in [
        "mixed_22_ascii.msh",
        "mixed_22_bin.msh",
        "mixed_41_ascii.msh",
        "mixed_41_bin.msh",
    ] {
        let r = io::read(&data(f), &ReadOptions::default()).unwrap();
        let a = r.complex.attributes();
        let g = a.get(AttrTarget::Cell, "gmsh:geometrical").unwrap();
        assert_eq!(g.values, geometrical, "{f}");
        let p = a.get(AttrTarget::Cell, "gmsh:physical").unwrap();
        assert_eq!(p.values, AttrValues::Int(vec![1; 8]), "{f}");
    }
}

#[test]
fn medit_references_are_attributes_and_are_written_back() {
    use starplex::io::medit;
    let text =
        "MeshVersionFormatted 2\nDimension 3\nVertices\n4\n0 0 0 1\n1 0 0 1\n0 1 0 2\n0 0 1 0\n\
                Tetrahedra\n1\n1 2 3 4 7\nTriangles\n1\n1 2 3 0\nEnd\n";
    let opts = ReadOptions {
        build: starplex::complex::BuildOptions {
            drop_face_cells: true,
            ..Default::default()
        },
        ..Default::default()
    };
    let k = medit::read_from(text.as_bytes(), "m.mesh".as_ref(), &opts)
        .unwrap()
        .complex;
    // the boundary triangle is dropped with its reference
    assert_eq!(k.n_cells(), 1);
    let a = k.attributes();
    assert_eq!(a.vertex, [Attribute::int("medit:ref", 1, vec![1, 1, 2, 0])]);
    assert_eq!(a.cell, [Attribute::int("medit:ref", 1, vec![7])]);
    let mut out = Vec::new();
    medit::write(&mut out, &k).unwrap();
    let back = medit::read_from(&out[..], "m.mesh".as_ref(), &ReadOptions::default()).unwrap();
    assert_eq!(back.complex, k);
    // no reference other than 0: no attribute
    let zero = text
        .replace(" 1\n1 0 0 1", " 0\n1 0 0 0")
        .replace("0 1 0 2", "0 1 0 0")
        .replace(" 7\n", " 0\n");
    let z = medit::read_from(zero.as_bytes(), "m.mesh".as_ref(), &opts)
        .unwrap()
        .complex;
    assert!(z.attributes().is_empty(), "{:?}", z.attributes());
    assert_eq!(
        io::Format::Medit.dropped_attributes(k.attributes()),
        Vec::<String>::new()
    );
}
