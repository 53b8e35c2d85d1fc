//! Attributes of PLY (extra vertex, face and edge properties), OFF/COFF colours and gmsh
//! `$NodeData`/`$ElementData`, read from files written by independent tools
//! (`scripts/make_attr_corpus.py`, reference columns in `more_attrs.json`), written back by
//! starplex's writers, and never a panic on truncated or corrupted input.
use std::path::PathBuf;

use starplex::attr::{AttrTarget, AttrValues, Attribute, Attributes};
use starplex::cell::CellKind;
use starplex::complex::IndexedComplex;
use starplex::io::{self, ply, Format, ReadOptions};

fn data(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/io")
        .join(name)
}

fn reference() -> serde_json::Value {
    let text = std::fs::read_to_string(data("more_attrs.json")).unwrap();
    serde_json::from_str(&text).unwrap()
}

/// Checks every column the reference gives for `file` against `k` (and that `k` has no other).
fn check(k: &IndexedComplex, file: &str, what: &str) {
    let r = &reference()[file];
    assert!(r.is_object(), "{file} is not in more_attrs.json");
    for (target, key) in [(AttrTarget::Vertex, "vertex"), (AttrTarget::Cell, "cell")] {
        let cols = r[key].as_object().unwrap();
        let names: Vec<&str> = k
            .attributes()
            .of(target)
            .iter()
            .map(|a| a.name.as_str())
            .collect();
        assert_eq!(names.len(), cols.len(), "{what}: {key} columns {names:?}");
        for (name, rows) in cols {
            let a = k
                .attributes()
                .get(target, name)
                .unwrap_or_else(|| panic!("{what}: no {key} attribute '{name}' in {names:?}"));
            let rows = rows.as_array().unwrap();
            assert_eq!(a.n_items(), rows.len(), "{what}: {name}");
            let comps = rows[0].as_array().unwrap().len();
            assert_eq!(a.components, comps, "{what}: {name}");
            let want: Vec<f64> = rows
                .iter()
                .flat_map(|r| {
                    r.as_array()
                        .unwrap()
                        .iter()
                        .map(|x| x.as_f64().unwrap_or(f64::NAN))
                })
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
                            (g.is_nan() && w.is_nan()) || (g - w).abs() <= 1e-6 * w.abs().max(1.0),
                            "{what}: {name}: {g} vs {w}"
                        );
                    }
                }
            }
        }
    }
}

fn files_with(ext: &str) -> Vec<String> {
    let mut v: Vec<String> = reference()
        .as_object()
        .unwrap()
        .keys()
        .filter(|k| k.ends_with(ext))
        .cloned()
        .collect();
    v.sort();
    assert!(!v.is_empty(), "no {ext} file in more_attrs.json");
    v
}

// ---------------------------------------------------------------- PLY

#[test]
fn ply_properties_written_by_trimesh_and_meshio_are_attributes() {
    for f in files_with(".ply") {
        let r = io::read(&data(&f), &ReadOptions::default()).unwrap_or_else(|e| panic!("{f}: {e}"));
        check(&r.complex, &f, &f);
    }
}

#[test]
fn ply_edge_elements_are_edges_with_their_properties() {
    let r = io::read(&data("hand_be.ply"), &ReadOptions::default()).unwrap();
    let k = &r.complex;
    let kinds: Vec<CellKind> = k.cells().map(|c| c.kind).collect();
    assert_eq!(
        kinds,
        [
            CellKind::Simplex(2),
            CellKind::Simplex(2),
            CellKind::Simplex(1)
        ]
    );
    assert!(r.notes.iter().any(|n| n.contains("NaN")), "{:?}", r.notes);
}

#[test]
fn ply_attributes_survive_both_encodings() {
    for f in ["trimesh_ascii.ply", "trimesh_binary.ply", "meshio_bin.ply"] {
        let k = io::read(&data(f), &ReadOptions::default()).unwrap().complex;
        assert!(Format::Ply.dropped_attributes(k.attributes()).is_empty());
        for enc in [
            ply::PlyEncoding::Ascii,
            ply::PlyEncoding::BinaryLittleEndian,
        ] {
            let mut out = Vec::new();
            ply::write_with(&mut out, &k, enc).unwrap();
            let back = ply::read_from(
                &out[..],
                out.len() as u64,
                "b.ply".as_ref(),
                &ReadOptions::default(),
            )
            .unwrap();
            assert_eq!(back.complex, k, "{f} {enc:?}");
            assert_eq!(back.complex.attributes(), k.attributes(), "{f} {enc:?}");
            check(&back.complex, f, &format!("{f} written {enc:?}"));
        }
    }
}

/// A quad and a triangle with columns of every kind PLY holds and of kinds it cannot hold.
fn surface_with_columns() -> IndexedComplex {
    let mut k = IndexedComplex::from_parts(
        3,
        vec![0., 0., 0., 1., 0., 0., 1., 1., 0., 0., 1., 0., 2., 0., 0.].into(),
        vec![
            (CellKind::Quad, vec![0, 1, 2, 3].into()),
            (CellKind::Simplex(2), vec![1, 4, 2].into()),
        ],
    )
    .unwrap();
    let a = Attributes {
        vertex: vec![
            Attribute::float("normal", 3, (0..15).map(|i| i as f64 * 0.25).collect()),
            Attribute::int("big", 1, vec![1 << 40, 0, 0, 0, 0]),
            Attribute::int("neg", 1, vec![-5, 3, 70000, 0, 1]),
            Attribute::float("x", 1, vec![0.0; 5]),
            Attribute::float("has space", 1, vec![0.0; 5]),
            Attribute::float("w", 1, vec![f64::NAN, 1.0, 2.0, 3.0, f64::INFINITY]),
            Attribute::int("u", 1, vec![u32::MAX as i64, 0, 1, 2, 3]),
        ],
        cell: vec![
            Attribute::int("rgb", 3, vec![255, 0, 0, 0, 255, 0]),
            Attribute::float("vertex_indices", 1, vec![0.0; 2]),
        ],
    };
    k.set_attributes(a).unwrap();
    k
}

#[test]
fn ply_writes_every_column_it_can_and_says_which_it_drops() {
    let k = surface_with_columns();
    let dropped = Format::Ply.dropped_attributes(k.attributes());
    assert_eq!(
        dropped,
        [
            "vertex big",
            "vertex x",
            "vertex has space",
            "cell vertex_indices"
        ]
    );
    for enc in [
        ply::PlyEncoding::Ascii,
        ply::PlyEncoding::BinaryLittleEndian,
    ] {
        let gone = ply::dropped(k.attributes(), enc);
        let mut out = Vec::new();
        ply::write_with(&mut out, &k, enc).unwrap();
        let back = ply::read_from(
            &out[..],
            out.len() as u64,
            "b.ply".as_ref(),
            &ReadOptions::default(),
        )
        .unwrap()
        .complex;
        for (target, cols) in [
            (AttrTarget::Vertex, &k.attributes().vertex),
            (AttrTarget::Cell, &k.attributes().cell),
        ] {
            for a in cols {
                let got = back.attributes().get(target, &a.name);
                if gone.contains(&format!("{target} {}", a.name)) {
                    assert!(got.is_none(), "{enc:?}: {target} {} written", a.name);
                } else {
                    let got = got.unwrap_or_else(|| panic!("{enc:?}: {target} {} lost", a.name));
                    assert_eq!(got.components, a.components);
                    assert_eq!(got.values.type_name(), a.values.type_name());
                    for i in 0..a.values.len() {
                        let (x, y) = (got.values.get_f64(i), a.values.get_f64(i));
                        assert!(x == y || (x.is_nan() && y.is_nan()), "{} {x} {y}", a.name);
                    }
                }
            }
        }
        let n_kept = back.attributes().vertex.len() + back.attributes().cell.len();
        assert_eq!(n_kept + gone.len(), 9, "{enc:?}");
    }
    // ascii has no NaN or infinity
    assert_eq!(
        ply::dropped(k.attributes(), ply::PlyEncoding::Ascii),
        [
            "vertex big",
            "vertex x",
            "vertex has space",
            "vertex w",
            "cell vertex_indices"
        ]
    );
}

#[test]
fn ply_grouping_rule_is_exact() {
    // a_0 a_1 of one type: one column a; b_0 then b_1 of two types: two columns; c_0 with a
    // property c: not grouped
    let text = "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n\
                property float a_0\nproperty float a_1\nproperty int b_0\nproperty float b_1\n\
                property int c\nproperty int c_0\nproperty int c_1\nend_header\n0 0 1 2 3 4 5 6 7\n";
    let k = ply::read_from(
        text.as_bytes(),
        text.len() as u64,
        "g.ply".as_ref(),
        &ReadOptions::default(),
    )
    .unwrap()
    .complex;
    let names: Vec<(&str, usize)> = k
        .attributes()
        .vertex
        .iter()
        .map(|a| (a.name.as_str(), a.components))
        .collect();
    assert_eq!(
        names,
        [
            ("a", 2),
            ("b_0", 1),
            ("b_1", 1),
            ("c", 1),
            ("c_0", 1),
            ("c_1", 1)
        ]
    );
    assert_eq!(
        k.attributes().vertex[0].values,
        AttrValues::Float(vec![1.0, 2.0])
    );
}

#[test]
fn ply_with_attributes_never_panics_when_cut_or_corrupted() {
    let mut files: Vec<(String, Vec<u8>)> =
        ["trimesh_ascii.ply", "trimesh_binary.ply", "hand_be.ply"]
            .iter()
            .map(|f| (f.to_string(), std::fs::read(data(f)).unwrap()))
            .collect();
    let k = surface_with_columns();
    for enc in [
        ply::PlyEncoding::Ascii,
        ply::PlyEncoding::BinaryLittleEndian,
    ] {
        let mut out = Vec::new();
        ply::write_with(&mut out, &k, enc).unwrap();
        files.push((format!("own_{enc:?}.ply"), out));
    }
    let mut rng = starplex::testkit::XorShift::new(0x5eed);
    let mut next = || rng.next_u64();
    let opts = ReadOptions::default();
    for (name, full) in &files {
        let binary = !name.contains("ascii") && !name.contains("Ascii");
        for cut in 0..full.len() {
            let r = ply::read_from(&full[..cut], cut as u64, name.as_ref(), &opts);
            match r {
                Err(e) => assert!(e.to_string().starts_with(name.as_str()), "{e}"),
                Ok(_) => assert!(!binary, "{name} cut at {cut} read fine"),
            }
        }
        for _ in 0..300 {
            let mut b = full.clone();
            for _ in 0..1 + next() % 4 {
                let i = (next() % b.len() as u64) as usize;
                b[i] = next() as u8;
            }
            if let Err(e) = ply::read_from(&b[..], b.len() as u64, name.as_ref(), &opts) {
                assert!(e.to_string().starts_with(name.as_str()), "{e}");
                assert!(
                    e.location.is_some() || matches!(e.kind, io::IoErrorKind::Complex(_)),
                    "{e}"
                );
            }
        }
    }
}

/// starplex's own output of the corpus files, for `scripts/check_attrs_more.py` (meshio and
/// trimesh read them back): written to `$STARPLEX_ATTR_OUT` when set, else to a temporary
/// directory (which checks that every write succeeds).
#[test]
fn own_outputs_for_independent_readers() {
    let dir = match std::env::var_os("STARPLEX_ATTR_OUT") {
        Some(d) => PathBuf::from(d),
        None => std::env::temp_dir().join(format!("starplex-attr-out-{}", std::process::id())),
    };
    std::fs::create_dir_all(&dir).unwrap();
    let k = io::read(&data("trimesh_binary.ply"), &ReadOptions::default())
        .unwrap()
        .complex;
    io::write(&dir.join("out_bin.ply"), &k, None).unwrap();
    let mut out = Vec::new();
    ply::write_with(&mut out, &k, ply::PlyEncoding::Ascii).unwrap();
    std::fs::write(dir.join("out_ascii.ply"), out).unwrap();
    let k = io::read(&data("meshio_22_bin.msh"), &ReadOptions::default())
        .unwrap()
        .complex;
    io::write(&dir.join("out_22.msh"), &k, Some(Format::Gmsh22)).unwrap();
    io::write(&dir.join("out_41.msh"), &k, Some(Format::Gmsh)).unwrap();
    if std::env::var_os("STARPLEX_ATTR_OUT").is_none() {
        std::fs::remove_dir_all(&dir).ok();
    }
}

// ---------------------------------------------------------------- OFF

const COFF: &str = "COFF\n6 3 0\n0 0 0 255 0 0 255\n1 0 0 0 255 0 255\n1 1 0 0 0 255 255\n\
                    0 1 0 9 9 9 0\n2 0 0 1 2 3 4\n2 1 0 5 6 7 8\n\
                    3 1 4 5 0.5 0 0\n5 0 1 2 3 4 0 0.25 1\n2 3 5 1 1 1\n";

#[test]
fn coff_colours_are_attributes_and_are_written_back() {
    use starplex::io::off;
    let opts = ReadOptions::default();
    let r = off::read_from(COFF.as_bytes(), "c.off".as_ref(), &opts).unwrap();
    let k = &r.complex;
    // the pentagon is 3 triangles sharing its colour
    assert_eq!(k.n_cells(), 5);
    let a = k.attributes();
    assert_eq!(a.vertex[0].name, "color");
    assert_eq!(a.vertex[0].components, 4);
    assert!(matches!(a.vertex[0].values, AttrValues::Int(_)));
    assert_eq!(
        a.cell,
        [Attribute::float(
            "color",
            3,
            vec![0.5, 0., 0., 0., 0.25, 1., 0., 0.25, 1., 0., 0.25, 1., 1., 1., 1.]
        )]
    );
    assert!(Format::Off.dropped_attributes(a).is_empty());
    let mut out = Vec::new();
    off::write(&mut out, k).unwrap();
    let text = String::from_utf8(out.clone()).unwrap();
    assert!(text.starts_with("COFF\n"), "{text}");
    let back = off::read_from(&out[..], "c.off".as_ref(), &opts)
        .unwrap()
        .complex;
    assert_eq!(&back, k);
    assert_eq!(back.attributes(), k.attributes());
    // a 2D complex with vertex colours is written as CnOFF (the dimension in the header)
    let mut flat = IndexedComplex::from_parts(
        2,
        vec![0., 0., 1., 0., 0., 1.].into(),
        vec![(CellKind::Simplex(2), vec![0, 1, 2].into())],
    )
    .unwrap();
    flat.set_attributes(Attributes {
        vertex: vec![Attribute::float("color", 3, vec![1.0; 9])],
        cell: vec![Attribute::int("color", 1, vec![7])],
    })
    .unwrap();
    let mut out = Vec::new();
    off::write(&mut out, &flat).unwrap();
    let back = off::read_from(&out[..], "c.off".as_ref(), &opts)
        .unwrap()
        .complex;
    assert_eq!(back, flat);
    assert_eq!(back.attributes(), flat.attributes());
    // what OFF cannot hold is named, and not written
    let mut odd = flat.clone();
    odd.set_attributes(Attributes {
        vertex: vec![Attribute::float("normal", 2, vec![0.0; 6])],
        cell: vec![Attribute::float("color", 1, vec![f64::NAN])],
    })
    .unwrap();
    assert_eq!(
        Format::Off.dropped_attributes(odd.attributes()),
        ["vertex normal", "cell color"]
    );
    let mut out = Vec::new();
    off::write(&mut out, &odd).unwrap();
    let back = off::read_from(&out[..], "c.off".as_ref(), &opts)
        .unwrap()
        .complex;
    assert!(back.attributes().is_empty());
}

#[test]
fn coff_never_panics_when_cut_or_corrupted() {
    use starplex::io::off;
    let opts = ReadOptions::default();
    let full = COFF.as_bytes();
    for cut in 0..full.len() {
        if let Err(e) = off::read_from(&full[..cut], "c.off".as_ref(), &opts) {
            assert!(e.to_string().starts_with("c.off"), "{e}");
        }
    }
    let mut rng = starplex::testkit::XorShift::new(0x0ff);
    let mut next = || rng.next_u64();
    for _ in 0..2000 {
        let mut b = full.to_vec();
        for _ in 0..1 + next() % 4 {
            let i = (next() % b.len() as u64) as usize;
            b[i] = b"0123456789 .-\nCOFFnan"[(next() % 21) as usize];
        }
        if let Err(e) = off::read_from(&b[..], "c.off".as_ref(), &opts) {
            assert!(e.to_string().starts_with("c.off"), "{e}");
        }
    }
}

/// CGAL's own test meshes with colours (`$STARPLEX_DATA/cgal/data/meshes`), when present.
#[test]
fn cgal_coloured_meshes() {
    let Some(dir) = std::env::var_os("STARPLEX_DATA")
        .map(|d| PathBuf::from(d).join("cgal/data/meshes"))
        .filter(|d| d.join("mesh_with_colors.off").exists())
    else {
        eprintln!("skipped: no $STARPLEX_DATA/cgal/data/meshes");
        return;
    };
    // floats with comments, blank lines and a pentagon
    let r = io::read(&dir.join("mesh_with_colors.off"), &ReadOptions::default()).unwrap();
    let a = r.complex.attributes();
    let v = a.get(AttrTarget::Vertex, "color").unwrap();
    assert_eq!((v.components, v.n_items()), (3, 8));
    assert_eq!(
        &v.values,
        &AttrValues::Float([[0.9, 0., 0.], [0., 0., 0.9]].repeat(4).concat())
    );
    let c = a.get(AttrTarget::Cell, "color").unwrap();
    assert_eq!((c.components, c.n_items()), (3, 6));
    // uchar RGBA on every vertex of a CGAL COFF
    let r = io::read(&dir.join("cactus.off"), &ReadOptions::default()).unwrap();
    let v = r
        .complex
        .attributes()
        .get(AttrTarget::Vertex, "color")
        .unwrap();
    assert_eq!(v.components, 4);
    assert!(matches!(v.values, AttrValues::Int(_)));
    // PLY with normals, colours, ids, face labels and an edge element with confidences (its
    // edges are sides of the faces: dropped with the option, with their values)
    let opts = ReadOptions {
        build: starplex::complex::BuildOptions {
            drop_face_cells: true,
            ..Default::default()
        },
        ..Default::default()
    };
    let r = io::read(&dir.join("colored_tetra.ply"), &opts).unwrap();
    let a = r.complex.attributes();
    let names: Vec<&str> = a.vertex.iter().map(|a| a.name.as_str()).collect();
    assert_eq!(names, ["nx", "ny", "nz", "red", "green", "blue", "id"]);
    let names: Vec<&str> = a.cell.iter().map(|a| a.name.as_str()).collect();
    assert_eq!(names, ["red", "green", "blue", "label", "confidence"]);
    assert_eq!(
        a.get(AttrTarget::Cell, "label").unwrap().values,
        AttrValues::Int(vec![-1, 1, -1, 0])
    );
}

// ---------------------------------------------------------------- gmsh

#[test]
fn gmsh_data_sections_written_by_meshio_are_attributes() {
    for f in files_with(".msh") {
        let r = io::read(&data(&f), &ReadOptions::default()).unwrap_or_else(|e| panic!("{f}: {e}"));
        check(&r.complex, &f, &f);
    }
}

/// gmsh's own files: `temperature` = 10 x at the last time step, `flux` = (tag, 0.5, -1), the
/// physical volume 5 (binary 4.1 included).
#[test]
fn gmsh_data_sections_written_by_gmsh_are_attributes() {
    for f in [
        "gmsh_22_ascii.msh",
        "gmsh_22_bin.msh",
        "gmsh_41_ascii.msh",
        "gmsh_41_bin.msh",
    ] {
        let r = io::read(&data(f), &ReadOptions::default()).unwrap_or_else(|e| panic!("{f}: {e}"));
        let k = &r.complex;
        assert!(k.n_cells() > 10, "{f}");
        let a = k.attributes();
        let t = a
            .get(AttrTarget::Vertex, "temperature")
            .unwrap_or_else(|| panic!("{f}: {a:?}"));
        assert_eq!((t.components, t.n_items()), (1, k.n_vertices()), "{f}");
        for v in 0..k.n_vertices() {
            let x = k.point(starplex::ids::VertexId(v as u32))[0];
            assert!(
                (t.values.get_f64(v) - 10.0 * x).abs() < 1e-9,
                "{f}: vertex {v}"
            );
        }
        assert!(
            r.notes.iter().any(|n| n.contains("last time step")),
            "{f}: {:?}",
            r.notes
        );
        let flux = a.get(AttrTarget::Cell, "flux").unwrap();
        assert_eq!((flux.components, flux.n_items()), (3, k.n_cells()), "{f}");
        let mut first: Vec<i64> = (0..k.n_cells())
            .map(|c| {
                assert_eq!(flux.values.get_f64(3 * c + 1), 0.5);
                assert_eq!(flux.values.get_f64(3 * c + 2), -1.0);
                flux.values.get_f64(3 * c) as i64
            })
            .collect();
        first.sort();
        first.dedup();
        assert_eq!(first.len(), k.n_cells(), "{f}: element tags");
        let phys = a
            .get(AttrTarget::Cell, "gmsh:physical")
            .unwrap_or_else(|| panic!("{f}: no physical tags"));
        assert_eq!(phys.values, AttrValues::Int(vec![5; k.n_cells()]), "{f}");
    }
}

#[test]
fn gmsh_writers_write_the_data_back() {
    use starplex::io::gmsh;
    let opts = ReadOptions::default();
    for f in ["meshio_22_bin.msh", "gmsh_41_bin.msh"] {
        let k = io::read(&data(f), &opts).unwrap().complex;
        // 2.2: everything (the tags as tags)
        assert!(
            Format::Gmsh22.dropped_attributes(k.attributes()).is_empty(),
            "{f}"
        );
        let mut out = Vec::new();
        gmsh::write_22(&mut out, &k).unwrap();
        let back = gmsh::read_from(&out[..], "o.msh".as_ref(), &opts)
            .unwrap()
            .complex;
        assert_eq!(back, k, "{f}");
        assert_eq!(back.attributes(), k.attributes(), "{f}");
        // 4.1, ascii and binary: the data sections, and the tags as geometric entities; in
        // meshio's file the geometrical entity 1 holds tetrahedra of physical groups 1 and 2,
        // which a 4.1 entity cannot say (its entities are then numbered by physical group)
        let dropped = Format::Gmsh.dropped_attributes(k.attributes());
        let mixed = f == "meshio_22_bin.msh";
        let want: &[&str] = if mixed {
            &["cell gmsh:geometrical"]
        } else {
            &[]
        };
        assert_eq!(dropped, want, "{f}");
        for bin in [false, true] {
            let mut out = Vec::new();
            if bin {
                gmsh::write_binary(&mut out, &k).unwrap();
            } else {
                gmsh::write(&mut out, &k).unwrap();
            }
            let back = gmsh::read_from(&out[..], "o.msh".as_ref(), &opts)
                .unwrap()
                .complex;
            if mixed {
                let (mut b2, mut k2) = (back.clone(), k.clone());
                let (ba, ka) = (b2.take_attributes(), k2.take_attributes());
                assert_eq!(b2, k2, "{f} binary {bin}");
                assert_eq!(ba.vertex, ka.vertex, "{f} binary {bin}");
                for a in &ka.cell {
                    if a.name != "gmsh:geometrical" {
                        assert_eq!(
                            ba.get(AttrTarget::Cell, &a.name),
                            Some(a),
                            "{f} binary {bin}"
                        );
                    }
                }
            } else {
                assert_eq!(back, k, "{f} binary {bin}");
            }
        }
    }
    // integer columns come back as floats (gmsh data is double); NaN survives
    let mut k = io::read(&data("meshio_41_bin.msh"), &opts).unwrap().complex;
    let n = k.n_vertices();
    let mut a = k.take_attributes();
    a.vertex = vec![
        Attribute::int("id", 1, (0..n as i64).collect()),
        Attribute::float("with space", 2, vec![f64::NAN; 2 * n]),
    ];
    k.set_attributes(a).unwrap();
    let mut out = Vec::new();
    gmsh::write(&mut out, &k).unwrap();
    let back = gmsh::read_from(&out[..], "o.msh".as_ref(), &opts)
        .unwrap()
        .complex;
    let id = back.attributes().get(AttrTarget::Vertex, "id").unwrap();
    assert_eq!(
        id.values,
        AttrValues::Float((0..n).map(|x| x as f64).collect())
    );
    let ws = back
        .attributes()
        .get(AttrTarget::Vertex, "with space")
        .unwrap();
    assert!(ws.values.get_f64(0).is_nan() && ws.components == 2);
}

#[test]
fn gmsh_data_section_errors_name_the_line() {
    use starplex::io::gmsh;
    let head = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n3\n1 0 0 0\n2 1 0 0\n3 0 1 0\n\
                $EndNodes\n$Elements\n1\n1 2 2 0 1 1 2 3\n$EndElements\n";
    for (tail, line, want) in [
        (
            "$NodeData\n1\n\"T\"\n0\n2\n0\n1\n$EndNodeData\n",
            17,
            "2 integer tags",
        ),
        ("$NodeData\n1\n\"T\"\n0\n3\n0\n0\n3\n", 17, "0 components"),
        (
            "$NodeData\n1\n\"T\"\n0\n3\n0\n1\n3\n1 0\n2 x\n",
            23,
            "found 'x'",
        ),
        (
            "$NodeData\n1\n\"T\"\n0\n3\n0\n1\n3\n1 0\n2 1\n",
            24,
            "end of file",
        ),
        (
            "$ElementData\n1\n\"T\"\n0\n3\n0\n1\n1\n1 0\n$EndNodeData\n",
            23,
            "$EndElementData",
        ),
    ] {
        let text = format!("{head}{tail}");
        let e = gmsh::read_from(text.as_bytes(), "d.msh".as_ref(), &ReadOptions::default())
            .unwrap_err()
            .to_string();
        assert!(e.contains(want), "{tail:?}: {e}");
        assert!(e.starts_with(&format!("d.msh:{line}:")), "{tail:?}: {e}");
    }
    // a data value for a node that is not in the file is ignored, a node without one is NaN
    let text = format!("{head}$NodeData\n1\n\"T\"\n0\n3\n0\n1\n2\n1 7\n9 8\n$EndNodeData\n");
    let r = gmsh::read_from(text.as_bytes(), "d.msh".as_ref(), &ReadOptions::default()).unwrap();
    let t = r.complex.attributes().get(AttrTarget::Vertex, "T").unwrap();
    assert_eq!(t.values.get_f64(0), 7.0);
    assert!(t.values.get_f64(1).is_nan() && t.values.get_f64(2).is_nan());
    assert!(
        r.notes.iter().any(|n| n.contains("no value")),
        "{:?}",
        r.notes
    );
}

#[test]
fn gmsh_with_data_never_panics_when_cut_or_corrupted() {
    use starplex::io::gmsh;
    let opts = ReadOptions::default();
    let mut files: Vec<(String, Vec<u8>, usize)> = Vec::new();
    for f in ["meshio_22_bin.msh", "meshio_41_bin.msh"] {
        files.push((f.to_string(), std::fs::read(data(f)).unwrap(), 1));
    }
    for f in ["gmsh_22_bin.msh", "gmsh_41_bin.msh", "gmsh_41_ascii.msh"] {
        files.push((f.to_string(), std::fs::read(data(f)).unwrap(), 211));
    }
    let k = io::read(&data("meshio_22_bin.msh"), &opts).unwrap().complex;
    let mut out = Vec::new();
    gmsh::write_22(&mut out, &k).unwrap();
    files.push(("own_22.msh".into(), out, 1));
    let mut rng = starplex::testkit::XorShift::new(0x95);
    let mut next = || rng.next_u64();
    for (name, full, step) in &files {
        for cut in (0..full.len()).step_by(*step) {
            if let Err(e) = gmsh::read_from(&full[..cut], name.as_ref(), &opts) {
                assert!(e.to_string().starts_with(name.as_str()), "{e}");
                assert!(
                    e.location.is_some() || matches!(e.kind, io::IoErrorKind::Complex(_)),
                    "{e}"
                );
            }
        }
        assert!(gmsh::read_from(&full[..full.len() / 2], name.as_ref(), &opts).is_err());
        for _ in 0..if *step == 1 { 400 } else { 40 } {
            let mut b = full.clone();
            for _ in 0..1 + next() % 4 {
                let i = (next() % b.len() as u64) as usize;
                b[i] = next() as u8;
            }
            if let Err(e) = gmsh::read_from(&b[..], name.as_ref(), &opts) {
                assert!(e.to_string().starts_with(name.as_str()), "{e}");
            }
        }
    }
}

// ---------------------------------------------------------------- legacy VTK POLYDATA

/// Points 0..7; a quad and a pentagon (POLYGONS, before LINES in the file), a poly-line of 3
/// points (LINES), a strip of 4 points (TRIANGLE_STRIPS), a vertex (VERTICES).
fn polydata_ascii(v5: bool) -> String {
    let head = format!(
        "# vtk DataFile Version {}\npoly\nASCII\nDATASET POLYDATA\n\
         POINTS 12 double\n0 0 0 1 0 0 1 1 0 0 1 0 5 0 0 6 0 0 6 1 0 5.5 2 0 5 1 0\n\
         9 9 9 10 9 9 11 9 9\n",
        if v5 { "5.1" } else { "4.2" }
    );
    let sections = if v5 {
        "POLYGONS 3 9\nOFFSETS vtktypeint64\n0 4 9\nCONNECTIVITY vtktypeint64\n0 1 2 3 4 5 6 7 8\n\
         LINES 2 3\nOFFSETS vtktypeint64\n0 3\nCONNECTIVITY vtktypeint64\n9 10 11\n\
         VERTICES 2 1\nOFFSETS vtktypeint64\n0 1\nCONNECTIVITY vtktypeint64\n9\n\
         TRIANGLE_STRIPS 2 4\nOFFSETS vtktypeint64\n0 4\nCONNECTIVITY vtktypeint64\n0 1 3 2\n"
    } else {
        "POLYGONS 2 11\n4 0 1 2 3\n5 4 5 6 7 8\nLINES 1 4\n3 9 10 11\nVERTICES 1 2\n1 9\n\
         TRIANGLE_STRIPS 1 5\n4 0 1 3 2\n"
    };
    // cells in VTK order: vertex, line, quad, pentagon, strip
    let data = "CELL_DATA 5\nSCALARS id int 1\nLOOKUP_TABLE default\n10 20 30 40 50\n\
                POINT_DATA 12\nSCALARS h double 1\nLOOKUP_TABLE default\n0 1 2 3 4 5 6 7 8 9 10 11\n";
    format!("{head}{sections}{data}")
}

#[test]
fn legacy_vtk_polydata_is_read_with_its_attributes() {
    use starplex::io::vtk;
    let opts = ReadOptions {
        build: starplex::complex::BuildOptions {
            drop_face_cells: true,
            drop_duplicates: true,
            ..Default::default()
        },
        ..Default::default()
    };
    for v5 in [false, true] {
        let text = polydata_ascii(v5);
        let r = vtk::read_from(text.as_bytes(), "p.vtk".as_ref(), &opts)
            .unwrap_or_else(|e| panic!("v5 {v5}: {e}"));
        let k = &r.complex;
        assert_eq!(k.n_vertices(), 12);
        // the vertex is dropped; the poly-line gives 2 edges (id 20), the quad (30), the
        // pentagon 3 triangles (40), the strip 2 triangles (50) that share the quad's vertices
        let id = k.attributes().get(AttrTarget::Cell, "id").unwrap();
        let mut got: Vec<(CellKind, i64)> = k
            .cells()
            .map(|c| (c.kind, id.values.get_f64(c.id.index()) as i64))
            .collect();
        got.sort_by_key(|x| x.1);
        assert_eq!(
            got,
            [
                (CellKind::Simplex(1), 20),
                (CellKind::Simplex(1), 20),
                (CellKind::Quad, 30),
                (CellKind::Simplex(2), 40),
                (CellKind::Simplex(2), 40),
                (CellKind::Simplex(2), 40),
                (CellKind::Simplex(2), 50),
                (CellKind::Simplex(2), 50),
            ],
            "v5 {v5}"
        );
        let h = k.attributes().get(AttrTarget::Vertex, "h").unwrap();
        assert_eq!(
            h.values,
            AttrValues::Float((0..12).map(|x| x as f64).collect())
        );
        assert!(r.notes.iter().any(|n| n.contains("vert")), "{:?}", r.notes);
    }
}

/// The same poly data in binary (4.2 classic layout, big-endian).
fn polydata_binary() -> Vec<u8> {
    let mut b: Vec<u8> =
        b"# vtk DataFile Version 4.2\npoly\nBINARY\nDATASET POLYDATA\nPOINTS 5 float\n".to_vec();
    for p in [
        [0f32, 0., 0.],
        [1., 0., 0.],
        [1., 1., 0.],
        [0., 1., 0.],
        [3., 3., 3.],
    ] {
        for x in p {
            b.extend_from_slice(&x.to_be_bytes());
        }
    }
    b.extend_from_slice(b"\nLINES 1 3\n");
    for x in [2i32, 3, 4] {
        b.extend_from_slice(&x.to_be_bytes());
    }
    b.extend_from_slice(b"\nPOLYGONS 1 5\n");
    for x in [4i32, 0, 1, 2, 3] {
        b.extend_from_slice(&x.to_be_bytes());
    }
    b.extend_from_slice(b"\nCELL_DATA 2\nSCALARS id int 1\nLOOKUP_TABLE default\n");
    for x in [7i32, 8] {
        b.extend_from_slice(&x.to_be_bytes());
    }
    b.push(b'\n');
    b
}

#[test]
fn binary_polydata_and_its_truncations() {
    use starplex::io::vtk;
    let opts = ReadOptions::default();
    let full = polydata_binary();
    let k = vtk::read_from(&full[..], "b.vtk".as_ref(), &opts)
        .unwrap()
        .complex;
    let kinds: Vec<CellKind> = k.cells().map(|c| c.kind).collect();
    assert_eq!(kinds, [CellKind::Simplex(1), CellKind::Quad]);
    assert_eq!(k.attributes().cell[0].values, AttrValues::Int(vec![7, 8]));
    let mut rng = starplex::testkit::XorShift::new(0x77);
    let mut next = || rng.next_u64();
    let ascii: Vec<Vec<u8>> = vec![
        polydata_ascii(false).into_bytes(),
        polydata_ascii(true).into_bytes(),
    ];
    for (name, f) in [("b.vtk", &full), ("a.vtk", &ascii[0]), ("c.vtk", &ascii[1])] {
        for cut in 0..f.len() {
            if let Err(e) = vtk::read_from(&f[..cut], name.as_ref(), &opts) {
                assert!(e.to_string().starts_with(name), "{e}");
            }
        }
        for _ in 0..500 {
            let mut b = f.clone();
            for _ in 0..1 + next() % 4 {
                let i = (next() % b.len() as u64) as usize;
                b[i] = next() as u8;
            }
            if let Err(e) = vtk::read_from(&b[..], name.as_ref(), &opts) {
                assert!(e.to_string().starts_with(name), "{e}");
            }
        }
    }
    // errors name the section
    let bad = polydata_ascii(false).replace("POLYGONS 2 11\n4 0 1 2 3", "POLYGONS 2 9\n2 0 1");
    let e = vtk::read_from(bad.as_bytes(), "p.vtk".as_ref(), &opts)
        .unwrap_err()
        .to_string();
    assert!(e.contains("POLYGONS"), "{e}");
    let bad = polydata_ascii(false).replace("LINES", "CELLS");
    let e = vtk::read_from(bad.as_bytes(), "p.vtk".as_ref(), &opts)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("unknown keyword 'CELLS' in a POLYDATA dataset"),
        "{e}"
    );
}
