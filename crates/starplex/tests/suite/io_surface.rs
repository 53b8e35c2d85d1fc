//! PLY, OBJ and STL: round trips, hand-written fixtures, an independent reader (tobj) and a
//! table of broken inputs (each an error naming the file and the problem, never a panic).
use std::path::PathBuf;

use proptest::prelude::*;
use starplex::cell::CellKind;
use starplex::complex::{BuildOptions, ComplexBuilder, IndexedComplex};
use starplex::io::{self, obj, ply, Format, IoErrorKind, PolygonMode, ReadOptions};

fn tmp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("starplex-io-surface-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d.join(name)
}

/// A 3x3 grid of quads with two quads split into triangles, plus two isolated vertices.
fn surface(ambient: usize) -> IndexedComplex {
    let mut b = ComplexBuilder::new(ambient).unwrap();
    for j in 0..4 {
        for i in 0..4 {
            let p = [i as f64 * 0.1, j as f64 / 3.0, (i * j) as f64 * 1e-7];
            b.push_vertex(&p[..ambient]).unwrap();
        }
    }
    b.push_vertex(&[-1.5e300, 7.0, 0.1 + 0.2][..ambient])
        .unwrap();
    b.push_vertex(&[5e-324, -0.0, 123456789.125][..ambient])
        .unwrap();
    let v = |i: u32, j: u32| j * 4 + i;
    for j in 0..3 {
        for i in 0..3 {
            let q = [v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j + 1)];
            if (i + j) % 4 == 1 {
                b.push_cell(CellKind::Simplex(2), &[q[0], q[1], q[2]])
                    .unwrap();
                b.push_cell(CellKind::Simplex(2), &[q[0], q[2], q[3]])
                    .unwrap();
            } else {
                b.push_cell(CellKind::Quad, &q).unwrap();
            }
        }
    }
    b.build(&BuildOptions::default()).unwrap().0
}

fn read(path: &std::path::Path) -> Result<io::ReadResult, io::IoError> {
    io::read(path, &ReadOptions::default())
}

fn write_file(name: &str, bytes: &[u8]) -> PathBuf {
    let p = tmp(name);
    std::fs::write(&p, bytes).unwrap();
    p
}

#[test]
fn ply_round_trips_ascii_and_binary() {
    for ambient in [2, 3] {
        let k = surface(ambient);
        assert!(k.blocks().len() > 2);
        for enc in [
            ply::PlyEncoding::Ascii,
            ply::PlyEncoding::BinaryLittleEndian,
        ] {
            let mut bytes = Vec::new();
            ply::write_with(&mut bytes, &k, enc).unwrap();
            let p = write_file(&format!("rt{ambient}{enc:?}.ply"), &bytes);
            let r = read(&p).unwrap();
            assert_eq!(r.complex, k, "{enc:?} {ambient}D");
            assert!(r.notes.is_empty(), "{:?}", r.notes);
        }
        // io::write picks binary.
        let p = tmp(&format!("default{ambient}.ply"));
        io::write(&p, &k, None).unwrap();
        let head = std::fs::read(&p).unwrap();
        assert!(head.starts_with(b"ply\nformat binary_little_endian 1.0\n"));
        assert_eq!(read(&p).unwrap().complex, k);
    }
}

#[test]
fn obj_round_trips() {
    let k = surface(3);
    let p = tmp("rt.obj");
    io::write(&p, &k, None).unwrap();
    let r = read(&p).unwrap();
    assert_eq!(r.format, Format::Obj);
    assert_eq!(r.complex, k);
    // 2D complexes are written with z = 0 and read back as 3D.
    let k2 = surface(2);
    io::write(&p, &k2, None).unwrap();
    let back = read(&p).unwrap().complex;
    assert_eq!(back.ambient_dim(), 3);
    for (a, b) in back.coords().chunks(3).zip(k2.coords().chunks(2)) {
        assert_eq!((a[0], a[1], a[2]), (b[0], b[1], 0.0));
    }
    assert_eq!(back.cells().count(), k2.cells().count());
}

/// tobj, an independent OBJ reader, sees the same faces (by corner coordinates).
#[test]
fn obj_output_agrees_with_tobj() {
    let mut b = ComplexBuilder::new(3).unwrap();
    // coordinates exact in f32 (tobj stores f32)
    for i in 0..30 {
        b.push_vertex(&[(i % 5) as f64 * 0.5, (i / 5) as f64 * 0.25, (i % 3) as f64])
            .unwrap();
    }
    for j in 0..5 {
        for i in 0..4 {
            let a = j * 5 + i;
            if i % 2 == 0 {
                b.push_cell(CellKind::Quad, &[a, a + 1, a + 6, a + 5])
                    .unwrap();
            } else {
                b.push_cell(CellKind::Simplex(2), &[a, a + 1, a + 6])
                    .unwrap();
                b.push_cell(CellKind::Simplex(2), &[a, a + 6, a + 5])
                    .unwrap();
            }
        }
    }
    let k = b.build(&BuildOptions::default()).unwrap().0;
    let p = tmp("tobj.obj");
    io::write(&p, &k, None).unwrap();
    let (models, _) = tobj::load_obj(
        &p,
        &tobj::LoadOptions {
            single_index: true,
            triangulate: false,
            ..Default::default()
        },
    )
    .unwrap();
    assert_eq!(models.len(), 1);
    let m = &models[0].mesh;
    let mut theirs: Vec<Vec<[u64; 3]>> = Vec::new();
    let mut at = 0usize;
    let arities: Vec<u32> = if m.face_arities.is_empty() {
        vec![3; m.indices.len() / 3]
    } else {
        m.face_arities.clone()
    };
    for n in arities {
        let face = (at..at + n as usize)
            .map(|i| {
                let v = m.indices[i] as usize;
                [0, 1, 2].map(|a| (m.positions[3 * v + a] as f64).to_bits())
            })
            .collect();
        theirs.push(face);
        at += n as usize;
    }
    let ours: Vec<Vec<[u64; 3]>> = read(&p)
        .unwrap()
        .complex
        .cells()
        .map(|c| {
            c.vertices
                .iter()
                .map(|&v| {
                    let q = k.point(starplex::ids::VertexId(v));
                    [q[0].to_bits(), q[1].to_bits(), q[2].to_bits()]
                })
                .collect()
        })
        .collect();
    assert_eq!(ours, theirs);
}

#[test]
fn ply_reads_other_layouts() {
    // float/int/uchar coordinates, extra properties, an edge element, `vertex_index`, uint lists,
    // a pentagon (fan-triangulated), comments and CRLF line ends.
    let text = "ply\r\nformat ascii 1.0\r\ncomment hi\r\nelement vertex 5\r\nproperty float x\r\n\
                property int y\r\nproperty uchar z\r\nproperty float nx\r\nelement edge 1\r\n\
                property int vertex1\r\nproperty int vertex2\r\nelement face 2\r\n\
                property uchar intensity\r\nproperty list uint uint vertex_index\r\nend_header\r\n\
                0.5 0 0 9\r\n1 0 1 9\r\n1 1 2 9\r\n0 1 3 9\r\n-1 2 255 9\r\n2 4\r\n\
                7 3 0 1 4\r\n1 5 0 1 2 3 4\r\n";
    let p = write_file("layouts.ply", text.as_bytes());
    let r = read(&p).unwrap();
    let k = &r.complex;
    assert_eq!(k.n_vertices(), 5);
    assert_eq!(k.point(starplex::ids::VertexId(4)), &[-1.0, 2.0, 255.0]);
    // the edge, the first triangle, then the pentagon as 3 triangles of a fan at vertex 0
    let cells: Vec<&[u32]> = k.cells().map(|c| c.vertices).collect();
    assert_eq!(cells.len(), 5);
    assert_eq!(cells[0], &[2, 4]);
    assert_eq!(cells[1], &[0, 1, 4]);
    assert_eq!(cells[2], &[0, 1, 2]);
    assert_eq!(cells[4], &[0, 3, 4]);
    // the extra properties are attributes (the edge has no intensity: 0)
    let a = k.attributes();
    assert_eq!(
        a.vertex[0],
        starplex::attr::Attribute::float("nx", 1, vec![9.0; 5])
    );
    assert_eq!(
        a.cell[0],
        starplex::attr::Attribute::int("intensity", 1, vec![0, 7, 1, 1, 1])
    );
    let notes = r.notes.join("; ");
    assert!(!notes.contains("ignored element"), "{notes}");
    assert!(notes.contains("fan-triangulated 1 polygons"), "{notes}");
    // the duplicate triangle (0 1 2 twice) is dropped only with the option
    let text2 = text.replace("1 5 0 1 2 3 4", "1 3 4 0 1");
    let p2 = write_file("dup.ply", text2.as_bytes());
    assert!(read(&p2).unwrap_err().to_string().contains("duplicate"));
    let r = io::read(
        &p2,
        &ReadOptions {
            build: BuildOptions {
                drop_duplicates: true,
                ..Default::default()
            },
            ..Default::default()
        },
    )
    .unwrap();
    assert_eq!(r.complex.n_cells(), 2);
    assert!(r.notes.join(" ").contains("dropped 1 duplicate"));
}

#[test]
fn ply_big_endian_and_simplices_mode() {
    // binary big endian, faces of 2 and 4 vertices read as an edge and a tetrahedron
    let mut b = b"ply\nformat binary_big_endian 1.0\nelement vertex 6\nproperty double x\n\
                  property double y\nproperty double z\nelement face 2\n\
                  property list uchar short vertex_indices\nend_header\n"
        .to_vec();
    for i in 0..6 {
        for a in 0..3 {
            b.extend_from_slice(&((i * 3 + a) as f64 * 0.5).to_be_bytes());
        }
    }
    b.push(4);
    for v in [0i16, 1, 2, 3] {
        b.extend_from_slice(&v.to_be_bytes());
    }
    b.push(2);
    for v in [4i16, 5] {
        b.extend_from_slice(&v.to_be_bytes());
    }
    let p = write_file("be.ply", &b);
    let opts = ReadOptions {
        polygons: PolygonMode::Simplices,
        ..Default::default()
    };
    let k = io::read(&p, &opts).unwrap().complex;
    assert_eq!(k.point(starplex::ids::VertexId(5)), &[7.5, 8.0, 8.5]);
    let cells: Vec<(CellKind, &[u32])> = k.cells().map(|c| (c.kind, c.vertices)).collect();
    assert_eq!(
        cells,
        vec![
            (CellKind::Simplex(3), &[0u32, 1, 2, 3][..]),
            (CellKind::Simplex(1), &[4u32, 5][..])
        ]
    );
    // In polygon mode the same file is a quad and an error for the 2-vertex face.
    let e = read(&p).unwrap_err().to_string();
    assert!(e.contains("face 1 has 2 vertices"), "{e}");
}

#[test]
fn point_cloud_ply_has_isolated_vertices() {
    let text = "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\n\
                property double z\nend_header\n0 0 0\n1 1 1\n2 2 2\n";
    let k = read(&write_file("cloud.ply", text.as_bytes()))
        .unwrap()
        .complex;
    assert_eq!(
        (k.n_vertices(), k.n_cells(), k.n_isolated_vertices()),
        (3, 0, 3)
    );
}

#[test]
fn obj_reads_corners_negative_indices_lines_and_polygons() {
    let text = "mtllib x.mtl\no thing\nv 0 0 0\nv 1 0 0 1.0\nv 1 1 0 0.5 0.5 0.5\nv 0 1 0\n\
                vt 0 0\nvn 0 0 1\ng a\nusemtl m\ns off\nf 1/1/1 2/1/1 3//1\ng b\nf -4 -2 -1\n\
                v 2 0 0\nv 2 1 0\nv 3 0 0\nf 2 5 6 3 7\nl 5 7\np 1\n";
    let p = write_file("misc.obj", text.as_bytes());
    let r = read(&p).unwrap();
    let k = &r.complex;
    assert_eq!(k.n_vertices(), 7);
    let cells: Vec<(CellKind, &[u32])> = k.cells().map(|c| (c.kind, c.vertices)).collect();
    assert_eq!(cells[0], (CellKind::Simplex(2), &[0u32, 1, 2][..]));
    // the triangle of group b shares vertices with group a (tobj would duplicate them)
    assert_eq!(cells[1], (CellKind::Simplex(2), &[0u32, 2, 3][..]));
    assert_eq!(cells[2], (CellKind::Simplex(2), &[1u32, 4, 5][..]));
    assert_eq!(
        cells.last().unwrap(),
        &(CellKind::Simplex(1), &[4u32, 6][..])
    );
    let notes = r.notes.join("; ");
    assert!(notes.contains("fan-triangulated 1 polygons"), "{notes}");
    assert!(notes.contains("1 polylines"), "{notes}");
    assert!(notes.contains("ignored 1 point"), "{notes}");
}

const STL_ASCII: &str = "solid tetra
  facet normal 0 0 -1
    outer loop
      vertex 0 0 0
      vertex 0 1 0
      vertex 1 0 0
    endloop
  endfacet
  facet normal 0 -1 0
    outer loop
      vertex 0 0 0
      vertex 1 0 0
      vertex 0 0 1
    endloop
  endfacet
  facet normal -1 0 0
    outer loop
      vertex 0 0 0
      vertex 0 0 1
      vertex 0 1 0
    endloop
  endfacet
  facet normal 1 1 1
    outer loop
      vertex 1 0 0
      vertex 0 1 0
      vertex 0 0 1.5
    endloop
  endfacet
endsolid tetra
";

fn stl_binary(header: &[u8; 80], tris: &[[[f32; 3]; 3]]) -> Vec<u8> {
    let mut b = header.to_vec();
    b.extend_from_slice(&(tris.len() as u32).to_le_bytes());
    for t in tris {
        b.extend_from_slice(&[0u8; 12]);
        for v in t {
            for x in v {
                b.extend_from_slice(&x.to_le_bytes());
            }
        }
        b.extend_from_slice(&[0u8; 2]);
    }
    b
}

#[test]
fn stl_ascii_merges_shared_corners() {
    let r = read(&write_file("tetra.stl", STL_ASCII.as_bytes())).unwrap();
    let k = &r.complex;
    // 12 corners, 5 distinct points: (0,0,1) and (0,0,1.5) differ
    assert_eq!(k.n_vertices(), 5);
    assert_eq!(k.n_cells(), 4);
    assert_eq!(k.cell(starplex::ids::CellId(0)).vertices, &[0, 1, 2]);
    assert_eq!(k.cell(starplex::ids::CellId(3)).vertices, &[2, 1, 4]);
    assert_eq!(k.point(starplex::ids::VertexId(4)), &[0.0, 0.0, 1.5]);
    // bare "solid" first line
    let bare = STL_ASCII.replacen("solid tetra", "solid", 1);
    assert_eq!(
        read(&write_file("bare.stl", bare.as_bytes()))
            .unwrap()
            .complex,
        *k
    );
}

#[test]
fn stl_binary_merges_shared_corners_even_with_a_solid_header() {
    let a = [0.0, 0.0, 0.0];
    let b = [1.0, 0.0, 0.0];
    let c = [1.0, 1.0, 0.0];
    let d = [0.0f32, 1.0, -0.0];
    let d0 = [0.0f32, 1.0, 0.0]; // same point as d with +0.0
    let tris = [
        [a, b, c],
        [a, c, d],
        [c, b, [2.0, 0.5, 0.25]],
        [d0, c, [0.0, 2.0, 0.0]],
    ];
    for header in [[b' '; 80], {
        let mut h = [b' '; 80];
        h[..11].copy_from_slice(b"solid thing");
        h
    }] {
        let bytes = stl_binary(&header, &tris);
        let r = read(&write_file("bin.stl", &bytes)).unwrap();
        let k = &r.complex;
        assert_eq!(k.n_vertices(), 6, "{:?}", &header[..5]);
        let cells: Vec<&[u32]> = k.cells().map(|c| c.vertices).collect();
        assert_eq!(
            cells,
            vec![&[0, 1, 2][..], &[0, 2, 3], &[2, 1, 4], &[3, 2, 5]]
        );
        assert_eq!(k.point(starplex::ids::VertexId(3)), &[0.0, 1.0, 0.0]);
    }
}

#[test]
fn stl_degenerate_facets_fail_or_are_dropped() {
    let a = [0.0, 0.0, 0.0];
    let b = [1.0, 0.0, 0.0];
    let c = [1.0, 1.0, 0.0];
    let bytes = stl_binary(&[0; 80], &[[a, b, c], [a, b, b]]);
    let p = write_file("degen.stl", &bytes);
    let e = read(&p).unwrap_err().to_string();
    assert!(
        e.contains("degen.stl") && e.contains("facet 1 is degenerate"),
        "{e}"
    );
    let r = io::read(
        &p,
        &ReadOptions {
            build: BuildOptions {
                drop_duplicates: true,
                ..Default::default()
            },
            ..Default::default()
        },
    )
    .unwrap();
    assert_eq!(r.complex.n_cells(), 1);
    assert!(r
        .notes
        .join(" ")
        .contains("dropped 1 degenerate facets (first: facet 1)"));
}

#[test]
fn volume_and_line_complexes_cannot_be_written_to_surface_formats() {
    let mut b = ComplexBuilder::new(3).unwrap();
    for p in [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
    ] {
        b.push_vertex(&p).unwrap();
    }
    b.push_cell(CellKind::Simplex(3), &[0, 1, 2, 3]).unwrap();
    let tet = b.build(&BuildOptions::default()).unwrap().0;
    let mut b = ComplexBuilder::new(3).unwrap();
    for p in [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]] {
        b.push_vertex(&p).unwrap();
    }
    b.push_cell(CellKind::Simplex(1), &[0, 1]).unwrap();
    let edge = b.build(&BuildOptions::default()).unwrap().0;
    for ext in ["ply", "obj"] {
        let p = tmp(&format!("tet.{ext}"));
        let e = io::write(&p, &tet, None).unwrap_err();
        assert!(matches!(e.kind, IoErrorKind::CannotWrite { .. }));
        let m = e.to_string();
        assert!(m.contains("a tetrahedral mesh cannot be written to"), "{m}");
        assert!(m.contains(".mesh, .vtk, .msh, .spx or .spb"), "{m}");
        assert!(!p.exists(), "nothing is left behind");
        if ext == "ply" {
            // PLY holds edges as an `edge` element
            io::write(&p, &edge, None).unwrap();
            let back = io::read(&p, &ReadOptions::default()).unwrap();
            assert_eq!(back.complex.n_cells(), 1);
        } else {
            let e = io::write(&p, &edge, None).unwrap_err().to_string();
            assert!(e.contains("edges"), "{e}");
        }
    }
    let e = io::write(&tmp("x.stl"), &tet, None).unwrap_err();
    assert!(matches!(e.kind, IoErrorKind::CannotWrite { .. }));
}

/// Each broken input: (file name, content, part of the expected message).
fn broken_inputs() -> Vec<(&'static str, Vec<u8>, &'static str)> {
    let head = |nv: &str, nf: &str, fmt: &str| {
        format!(
            "ply\nformat {fmt} 1.0\nelement vertex {nv}\nproperty float x\nproperty float y\n\
             property float z\nelement face {nf}\nproperty list uchar int vertex_indices\nend_header\n"
        )
    };
    let ascii =
        |nv: &str, nf: &str, body: &str| format!("{}{body}", head(nv, nf, "ascii")).into_bytes();
    let verts = "0 0 0\n1 0 0\n0 1 0\n";
    let mut bin_trunc = head("3", "1", "binary_little_endian").into_bytes();
    let mut bin_nan = head("3", "0", "binary_little_endian").into_bytes();
    for x in [0.0f32, 0.0, 0.0, 1.0, f32::NAN, 0.0, 0.0, 1.0, 0.0] {
        bin_nan.extend_from_slice(&x.to_le_bytes());
    }
    let mut bin_short = bin_trunc.clone();
    bin_short.extend_from_slice(&[0u8; 30]);
    bin_trunc.extend_from_slice(&[0u8; 36]);
    bin_trunc.push(3);
    bin_trunc.extend_from_slice(&[0u8; 4]);
    vec![
        ("empty.ply", vec![], "magic"),
        ("notply.ply", b"plx\nformat ascii 1.0\nend_header\n".to_vec(), "magic"),
        ("noformat.ply", b"ply\nelement vertex 0\nend_header\n".to_vec(), "format"),
        ("noend.ply", b"ply\nformat ascii 1.0\nelement vertex 1\n".to_vec(), "end_header"),
        ("badprop.ply", b"ply\nformat ascii 1.0\nelement vertex 1\nproperty blob x\nend_header\n".to_vec(), "parse"),
        ("huge.ply", ascii("1000000000000", "0", verts), "1000000000000 records"),
        ("hugefaces.ply", ascii("3", "1000000000000", verts), "element 'face' declares 1000000000000"),
        ("binshort.ply", bin_short, "need at least 36 bytes, but only 30 bytes follow"),
        ("bintrunc.ply", bin_trunc, "the file ends in record 0 of element 'face'"),
        ("asciitrunc.ply", ascii("3", "1", "0 0 0\n1 0 0\n0 1 0\n3 0 1"), "record 0 of element 'face'"),
        ("asciishort.ply", ascii("4", "1", "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"), "the file ends in record 0 of element 'face'"),
        ("range.ply", ascii("3", "1", &format!("{verts}3 0 1 7\n")), "vertex index 7 out of range"),
        ("repeat.ply", ascii("3", "1", &format!("{verts}3 0 1 1\n")), "appears more than once"),
        ("negative.ply", ascii("3", "1", &format!("{verts}3 0 1 -2\n")), "negative vertex index -2"),
        ("nan.ply", bin_nan, "vertex 1: coordinate 1 is not finite"),
        ("word.ply", ascii("3", "1", "0 0 0\n1 x 0\n0 1 0\n3 0 1 2\n"), "record 1 of element 'vertex'"),
        ("twoverts.ply", ascii("3", "1", &format!("{verts}2 0 1\n")), "face 0 has 2 vertices"),
        ("novertex.ply", b"ply\nformat ascii 1.0\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n".to_vec(), "no 'vertex' element"),
        ("noz.ply", b"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n0\n".to_vec(), "no 'x' and 'y'"),
        ("floatlist.ply", b"ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\nelement face 0\nproperty list uchar float vertex_indices\nend_header\n".to_vec(), "expected a list of integers"),
        ("noindices.ply", b"ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\nelement face 0\nproperty int a\nend_header\n".to_vec(), "no 'vertex_indices'"),
        ("badfloat.obj", b"v 0 0 0\nv 1 zero 0\n".to_vec(), ":2: expected the y coordinate (a number), found 'zero'"),
        ("nan.obj", b"v 0 0 0\nv 1 inf 0\n".to_vec(), "not finite"),
        ("short.obj", b"v 0 0\n".to_vec(), "expected the z coordinate"),
        ("zero.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n".to_vec(), ":4: vertex index 0 is out of range"),
        ("range.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n".to_vec(), "vertex index 4 is out of range"),
        ("forward.obj", b"v 0 0 0\nv 1 0 0\nf 1 2 3\nv 0 1 0\n".to_vec(), ":3: vertex index 3 is out of range"),
        ("negrange.obj", b"v 0 0 0\nf -1 -2 -3\n".to_vec(), "vertex index -2 is out of range"),
        ("junk.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n".to_vec(), "found 'x'"),
        ("repeat.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 2\n".to_vec(), "appears more than once"),
        ("twoface.obj", b"v 0 0 0\nv 1 0 0\nf 1 2\n".to_vec(), "at least 3 vertices"),
        ("oneline.obj", b"v 0 0 0\nl 1\n".to_vec(), "at least 2 vertices"),
        ("empty.stl", vec![], "not an STL file"),
        ("tiny.stl", b"hello".to_vec(), "not an STL file"),
        ("trunc.stl", {
            let mut b = stl_binary(&[0; 80], &[[[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]]);
            b[80..84].copy_from_slice(&1_000_000_000u32.to_le_bytes());
            b
        }, "declares 1000000000 facets"),
        ("nan.stl", stl_binary(&[0; 80], &[[[0.0; 3], [1.0, f32::NAN, 0.0], [0.0, 1.0, 0.0]]]), "facet 0: corner 1 has a non-finite"),
        ("noend.stl", STL_ASCII.replace("endsolid tetra\n", "").into_bytes(), "facet 4"),
        ("badvertex.stl", STL_ASCII.replacen("vertex 0 1 0", "vertex 0 one 0", 1).into_bytes(), "facet 0"),
    ]
}

#[test]
fn broken_inputs_are_errors_naming_file_and_problem() {
    for (name, bytes, want) in broken_inputs() {
        let p = write_file(name, &bytes);
        let t = std::time::Instant::now();
        let e = match read(&p) {
            Ok(r) => panic!("{name}: read fine: {} cells", r.complex.n_cells()),
            Err(e) => e.to_string(),
        };
        assert!(
            t.elapsed().as_secs_f64() < 2.0,
            "{name} took {:?}",
            t.elapsed()
        );
        assert!(
            e.contains(name),
            "{name}: the message does not name the file: {e}"
        );
        assert!(e.contains(want), "{name}: expected '{want}' in: {e}");
        println!("{e}");
    }
}

/// Truncating valid files anywhere gives an error or (for text cut at a record boundary) a
/// smaller complex, never a panic.
#[test]
fn truncated_surface_files_never_panic() {
    let k = surface(3);
    // (name, bytes, whether every cut must be an error: binary files, whose sizes are fixed)
    let mut files: Vec<(&str, Vec<u8>, bool)> = Vec::new();
    for enc in [
        ply::PlyEncoding::Ascii,
        ply::PlyEncoding::BinaryLittleEndian,
    ] {
        let mut b = Vec::new();
        ply::write_with(&mut b, &k, enc).unwrap();
        files.push(("cut.ply", b, enc == ply::PlyEncoding::BinaryLittleEndian));
    }
    let mut b = Vec::new();
    obj::write(&mut b, &k).unwrap();
    files.push(("cut.obj", b, false));
    files.push(("cut.stl", STL_ASCII.as_bytes().to_vec(), false));
    let tri = [[0.0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
    files.push((
        "cut.stl",
        stl_binary(&[0; 80], &[tri, tri.map(|p| [p[0], p[1], 1.0])]),
        true,
    ));
    for (name, full, strict) in files {
        let mut errors = 0;
        let opts = ReadOptions::default();
        for cut in 0..full.len() {
            let part = &full[..cut];
            // PLY and OBJ in memory (fast); STL needs a file
            let r = if name.ends_with(".ply") {
                ply::read_from(part, cut as u64, name.as_ref(), &opts).map(|_| ())
            } else if name.ends_with(".obj") {
                obj::read_from(part, name.as_ref(), &opts).map(|_| ())
            } else {
                read(&write_file(name, part)).map(|_| ())
            };
            if strict {
                assert!(r.is_err(), "{name} cut at {cut} of {}", full.len());
            }
            errors += r.is_err() as usize;
        }
        assert!(errors * 2 > full.len(), "{name}: most cuts must fail");
    }
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 64,
        rng_seed: proptest::test_runner::RngSeed::Fixed(0x51ce),
        failure_persistence: None,
        ..ProptestConfig::default()
    })]
    /// Random surfaces with arbitrary finite coordinates survive PLY (both encodings) and OBJ.
    #[test]
    fn random_surfaces_round_trip(
        coords in proptest::collection::vec(
            proptest::num::f64::NORMAL | proptest::num::f64::SUBNORMAL | proptest::num::f64::ZERO,
            12..60),
        faces in proptest::collection::vec((any::<bool>(), any::<u32>()), 1..12),
    ) {
        let nv = coords.len() / 3;
        let mut b = ComplexBuilder::new(3).unwrap();
        for p in coords.chunks_exact(3) {
            b.push_vertex(p).unwrap();
        }
        // distinct vertex sets from a seed: a window of consecutive ids
        for (quad, s) in &faces {
            let n = if *quad { 4 } else { 3 };
            let s = (*s as usize) % (nv - n + 1);
            let v: Vec<u32> = (s..s + n).map(|x| x as u32).collect();
            b.push_cell(if *quad { CellKind::Quad } else { CellKind::Simplex(2) }, &v).unwrap();
        }
        let opts = BuildOptions { drop_duplicates: true, drop_face_cells: true, ..Default::default() };
        let k = b.build(&opts).unwrap().0;
        for enc in [ply::PlyEncoding::Ascii, ply::PlyEncoding::BinaryLittleEndian] {
            let mut bytes = Vec::new();
            ply::write_with(&mut bytes, &k, enc).unwrap();
            let r = ply::read_from(&bytes[..], bytes.len() as u64, "m.ply".as_ref(), &ReadOptions::default()).unwrap();
            prop_assert_eq!(&r.complex, &k);
        }
        let mut bytes = Vec::new();
        obj::write(&mut bytes, &k).unwrap();
        let r = obj::read_from(&bytes[..], "m.obj".as_ref(), &ReadOptions::default()).unwrap();
        prop_assert_eq!(&r.complex, &k);
    }
}
