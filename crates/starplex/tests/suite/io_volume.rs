//! Medit, legacy VTK and gmsh: round trips on fixtures built in code and on seeded random
//! complexes, a table of broken inputs (each must fail with its line), and, when `STARPLEX_DATA`
//! is set, the dataset files against their `.spx`.
use crate::common_data;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use starplex::cell::CellKind;
use starplex::complex::{BuildOptions, ComplexBuilder, IndexedComplex};
use starplex::io::{self, gmsh, medit, vtk, Format, IoErrorKind, ReadOptions, ReadResult};

const TET: CellKind = CellKind::Simplex(3);
const TRI: CellKind = CellKind::Simplex(2);
const LINE: CellKind = CellKind::Simplex(1);

fn complex(ambient: usize, pts: &[&[f64]], cells: &[(CellKind, &[u32])]) -> IndexedComplex {
    let mut b = ComplexBuilder::new(ambient).unwrap();
    for p in pts {
        b.push_vertex(p).unwrap();
    }
    for (k, c) in cells {
        b.push_cell(*k, c).unwrap();
    }
    b.build(&BuildOptions::default()).unwrap().0
}

fn unit_cube() -> Vec<&'static [f64]> {
    vec![
        &[0.0, 0.0, 0.0],
        &[1.0, 0.0, 0.0],
        &[1.0, 1.0, 0.0],
        &[0.0, 1.0, 0.0],
        &[0.0, 0.0, 1.0],
        &[1.0, 0.0, 1.0],
        &[1.0, 1.0, 1.0],
        &[0.0, 1.0, 1.0],
        // awkward values for the number round trip
        &[0.1, -2.5e17, 1e-300],
        &[1.0 / 3.0, 7.0, -0.0],
        &[2.0, 0.5, 0.5],
        &[0.5, 0.5, 2.0],
    ]
}

/// Named fixtures: `(name, complex, formats that hold it exactly)`.
fn fixtures() -> Vec<(&'static str, IndexedComplex, Vec<Format>)> {
    let all = vec![Format::Medit, Format::Vtk, Format::Gmsh, Format::Gmsh22];
    let c = unit_cube();
    let mut v = vec![
        (
            "tet",
            complex(3, &c[..4], &[(TET, &[0, 1, 3, 2])]),
            all.clone(),
        ),
        (
            "two tets",
            complex(3, &c[..5], &[(TET, &[0, 1, 3, 4]), (TET, &[1, 2, 3, 4])]),
            all.clone(),
        ),
        (
            "hex",
            complex(3, &c[..8], &[(CellKind::Hex, &[0, 1, 2, 3, 4, 5, 6, 7])]),
            all.clone(),
        ),
        (
            "prism",
            complex(3, &c[..6], &[(CellKind::Prism, &[0, 2, 1, 3, 5, 4])]),
            all.clone(),
        ),
        (
            "pyramid",
            complex(3, &c[..12], &[(CellKind::Pyramid, &[4, 5, 6, 7, 11])]).clone(),
            vec![Format::Medit, Format::Vtk],
        ),
        (
            "mixed (Medit's keyword order)",
            complex(
                3,
                &c,
                &[
                    (TET, &[8, 9, 10, 11]),
                    (CellKind::Pyramid, &[4, 5, 6, 7, 11]),
                    (CellKind::Prism, &[1, 2, 5, 8, 9, 10]),
                    (CellKind::Hex, &[0, 1, 2, 3, 4, 5, 6, 7]),
                ],
            ),
            all.clone(),
        ),
        (
            "mixed dimensions, alternating blocks",
            complex(
                3,
                &c,
                &[
                    (TRI, &[8, 9, 10]),
                    (CellKind::Quad, &[0, 1, 2, 3]),
                    (LINE, &[7, 11]),
                    (TRI, &[4, 5, 6]),
                    (TET, &[0, 8, 9, 11]),
                ],
            ),
            vec![Format::Vtk, Format::Gmsh, Format::Gmsh22],
        ),
        (
            "quads in the plane",
            complex(
                2,
                &[
                    &[0.0, 0.0],
                    &[1.0, 0.0],
                    &[1.0, 1.0],
                    &[0.0, 1.0],
                    &[2.0, 0.0],
                    &[2.0, 1.0],
                ],
                &[
                    (CellKind::Quad, &[0, 1, 2, 3]),
                    (CellKind::Quad, &[1, 4, 5, 2]),
                ],
            ),
            vec![Format::Medit],
        ),
        (
            "lines",
            complex(
                3,
                &c[..3],
                &[(LINE, &[0, 1]), (LINE, &[1, 2]), (LINE, &[2, 0])],
            ),
            all.clone(),
        ),
        (
            "isolated vertices",
            complex(3, &c, &[(TET, &[0, 1, 3, 4])]),
            vec![Format::Medit, Format::Vtk],
        ),
        (
            "vertices only",
            complex(3, &c[..3], &[]),
            vec![Format::Medit, Format::Vtk],
        ),
        ("empty", complex(3, &[], &[]), all.clone()),
    ];
    // a pyramid whose apex is used by nothing else also round-trips through gmsh
    v.push((
        "pyramid (all vertices used)",
        complex(
            3,
            &[c[4], c[5], c[6], c[7], c[11]],
            &[(CellKind::Pyramid, &[0, 1, 2, 3, 4])],
        ),
        all,
    ));
    v
}

fn write_to_vec(f: Format, k: &IndexedComplex) -> Result<Vec<u8>, IoErrorKind> {
    let mut out = Vec::new();
    match f {
        Format::Medit => medit::write(&mut out, k)?,
        Format::Vtk => vtk::write(&mut out, k)?,
        Format::Gmsh => gmsh::write(&mut out, k)?,
        Format::Gmsh22 => gmsh::write_22(&mut out, k)?,
        _ => unreachable!(),
    }
    Ok(out)
}

fn read_bytes(f: Format, data: &[u8]) -> Result<ReadResult, io::IoError> {
    let o = ReadOptions::default();
    let p = Path::new(match f {
        Format::Medit => "t.mesh",
        Format::Vtk => "t.vtk",
        _ => "t.msh",
    });
    match f {
        Format::Medit => medit::read_from(data, p, &o),
        Format::Vtk => vtk::read_from(data, p, &o),
        Format::Gmsh | Format::Gmsh22 => gmsh::read_from(data, p, &o),
        _ => unreachable!(),
    }
}

fn round_trip(f: Format, k: &IndexedComplex) -> ReadResult {
    let data = write_to_vec(f, k).unwrap_or_else(|e| panic!("{f}: write failed: {e}"));
    let mut r = read_bytes(f, &data).unwrap_or_else(|e| {
        panic!(
            "{f}: reading back failed: {e}\n{}",
            String::from_utf8_lossy(&data)
        )
    });
    if matches!(f, Format::Gmsh | Format::Gmsh22) && k.attributes().is_empty() {
        // every gmsh element belongs to a geometric entity: the reader gives its tag
        // (when it is not 0)
        let a = r.complex.take_attributes();
        assert!(a.vertex.is_empty() && a.cell.len() <= 1, "{f}: {a:?}");
        assert!(
            a.cell.iter().all(|c| c.name == "gmsh:geometrical"),
            "{f}: {a:?}"
        );
    }
    r
}

#[test]
fn fixtures_round_trip_exactly() {
    for (name, k, formats) in fixtures() {
        for f in formats {
            let r = round_trip(f, &k);
            assert_eq!(r.complex, k, "{name} through {f}");
            assert!(r.notes.is_empty(), "{name} through {f}: {:?}", r.notes);
        }
    }
}

#[test]
fn what_each_format_changes_is_what_the_docs_say() {
    let c = unit_cube();
    // VTK and gmsh points have 3 coordinates: a planar complex comes back with z = 0.
    let planar = complex(
        2,
        &[&[0.0, 0.0], &[1.0, 0.0], &[1.0, 1.0], &[0.0, 1.0]],
        &[(CellKind::Quad, &[0, 1, 2, 3])],
    );
    for f in [Format::Vtk, Format::Gmsh, Format::Gmsh22] {
        let r = round_trip(f, &planar);
        assert_eq!(r.complex.ambient_dim(), 3);
        assert_eq!(
            r.complex.coords(),
            &[0., 0., 0., 1., 0., 0., 1., 1., 0., 0., 1., 0.]
        );
        assert_eq!(r.complex.cells().next().unwrap().vertices, &[0, 1, 2, 3]);
    }
    // gmsh drops nodes that no element uses, renumbering the others in order.
    let k = complex(3, &c, &[(TET, &[4, 1, 3, 6])]);
    let r = round_trip(Format::Gmsh, &k);
    assert_eq!(r.complex.n_vertices(), 4);
    assert_eq!(r.complex.cells().next().unwrap().vertices, &[2, 0, 1, 3]);
    assert_eq!(r.complex.point(starplex::ids::VertexId(2)), c[4]);
    assert_eq!(
        r.notes,
        vec!["dropped 8 nodes used by no element (geometry points)"]
    );
    // Medit groups cells by keyword.
    let k = complex(3, &c[..4], &[(TET, &[0, 1, 2, 3])]);
    let mixed = complex(
        3,
        &c,
        &[
            (CellKind::Hex, &[0, 1, 2, 3, 4, 5, 6, 7]),
            (TRI, &[8, 9, 10]),
        ],
    );
    let r = round_trip(Format::Medit, &mixed);
    assert_eq!(by_kind(&r.complex), by_kind(&mixed));
    assert_eq!(r.complex.cells().next().unwrap().kind, TRI);
    assert_eq!(round_trip(Format::Medit, &k).complex, k);
    // VTK vertex cells and gmsh point elements are written, and dropped on reading.
    let with_vertex_cell = complex(
        3,
        &c[..5],
        &[(TET, &[0, 1, 2, 3]), (CellKind::Simplex(0), &[4])],
    );
    let r = round_trip(Format::Vtk, &with_vertex_cell);
    assert_eq!(r.complex.n_cells(), 1);
    assert_eq!(r.complex.n_vertices(), 5);
    assert_eq!(
        r.notes,
        vec!["dropped 1 VTK vertex cells (types 1, 2); their points stay as vertices"]
    );
    let r = round_trip(Format::Gmsh, &with_vertex_cell);
    assert_eq!(r.complex.n_cells(), 1);
    assert_eq!(r.complex.n_vertices(), 4);
}

#[test]
fn writers_refuse_what_the_format_cannot_hold() {
    let pts: Vec<&[f64]> = vec![
        &[0.0, 0.0, 0.0],
        &[1.0, 0.0, 0.0],
        &[0.0, 1.0, 0.0],
        &[0.0, 0.0, 1.0],
        &[1.0, 1.0, 1.0],
    ];
    let four_simplex = complex(3, &pts, &[(CellKind::Simplex(4), &[0, 1, 2, 3, 4])]);
    let p4: Vec<&[f64]> = vec![&[0.0, 0.0, 0.0, 0.0], &[1.0, 0.0, 0.0, 0.0]];
    let ambient4 = complex(4, &p4, &[(LINE, &[0, 1])]);
    let p1: Vec<&[f64]> = vec![&[0.0], &[1.0]];
    let ambient1 = complex(1, &p1, &[(LINE, &[0, 1])]);
    let vertex_cell = complex(1, &p1, &[(CellKind::Simplex(0), &[0])]);
    for f in [Format::Medit, Format::Vtk, Format::Gmsh, Format::Gmsh22] {
        for k in [&four_simplex, &ambient4] {
            match write_to_vec(f, k) {
                Err(IoErrorKind::CannotWrite { format, .. }) => assert_eq!(format, f),
                other => panic!("{f}: expected CannotWrite, got {:?}", other.map(|_| ())),
            }
        }
    }
    assert!(matches!(
        write_to_vec(Format::Medit, &ambient1),
        Err(IoErrorKind::CannotWrite { .. })
    ));
    assert!(matches!(
        write_to_vec(Format::Medit, &vertex_cell),
        Err(IoErrorKind::CannotWrite { .. })
    ));
    assert!(write_to_vec(Format::Vtk, &ambient1).is_ok());
    // through the dispatcher: the error names the file and nothing is left behind
    let dir = std::env::temp_dir().join(format!("starplex-io-volume-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let target = dir.join("x.msh");
    let e = io::write(&target, &four_simplex, None).unwrap_err();
    assert!(e.to_string().contains("cannot hold"), "{e}");
    assert!(!target.exists());
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn msh22_through_the_dispatcher_writes_version_2_2_and_reads_back() {
    let c = unit_cube();
    let k = complex(3, &c[..8], &[(CellKind::Hex, &[0, 1, 2, 3, 4, 5, 6, 7])]);
    let dir = std::env::temp_dir().join(format!("starplex-msh22-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let target = dir.join("cube.msh");
    io::write(&target, &k, Format::from_name("msh22")).unwrap();
    let text = std::fs::read_to_string(&target).unwrap();
    assert!(text.starts_with("$MeshFormat\n2.2 0 8\n"), "{text}");
    let mut back = io::read(&target, &ReadOptions::default()).unwrap();
    // the hexahedron's elementary tag (its entity, of dimension 3 in gmsh 2.2 as starplex writes it)
    let tags = back.complex.take_attributes();
    assert_eq!(tags.cell[0].name, "gmsh:geometrical");
    assert_eq!(back.complex, k);
    assert_eq!(back.format, Format::Gmsh);
    io::write(&target, &k, None).unwrap();
    assert!(std::fs::read_to_string(&target)
        .unwrap()
        .starts_with("$MeshFormat\n4.1 0 8\n"));
    std::fs::remove_dir_all(&dir).ok();
}

// ---------------------------------------------------------------- seeded random round trips

struct Rng(u64);
impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
}

fn random_complex(seed: u64) -> IndexedComplex {
    let mut r = Rng(seed);
    let nv = 8 + r.below(30);
    let mut b = ComplexBuilder::new(3).unwrap();
    let values = [0.0, 1.0, -1.5, 0.1, 1e-7, 3.25e12, -7.0 / 3.0, 0.3];
    for _ in 0..nv {
        let p: Vec<f64> = (0..3)
            .map(|_| {
                if r.below(2) == 0 {
                    values[r.below(values.len())]
                } else {
                    (r.next() >> 11) as f64 / (1u64 << 53) as f64 * 10.0 - 5.0
                }
            })
            .collect();
        b.push_vertex(&p).unwrap();
    }
    let kinds = [
        LINE,
        TRI,
        CellKind::Quad,
        TET,
        CellKind::Pyramid,
        CellKind::Prism,
        CellKind::Hex,
    ];
    let nc = r.below(25);
    for _ in 0..nc {
        let kind = kinds[r.below(kinds.len())];
        let mut pool: Vec<u32> = (0..nv as u32).collect();
        let mut c = Vec::new();
        for _ in 0..kind.n_vertices() {
            let i = r.below(pool.len());
            c.push(pool.swap_remove(i));
        }
        b.push_cell(kind, &c).unwrap();
    }
    b.build(&BuildOptions {
        drop_face_cells: true,
        drop_duplicates: true,
        ..Default::default()
    })
    .unwrap()
    .0
}

/// Cells grouped by kind, each group in id order.
fn by_kind(k: &IndexedComplex) -> BTreeMap<CellKind, Vec<Vec<u32>>> {
    let mut m: BTreeMap<CellKind, Vec<Vec<u32>>> = BTreeMap::new();
    for c in k.cells() {
        m.entry(c.kind).or_default().push(c.vertices.to_vec());
    }
    m
}

/// The complex without the vertices no cell uses (others renumbered in order).
fn without_unused(k: &IndexedComplex) -> IndexedComplex {
    let used = k.used_vertices();
    let mut id = vec![u32::MAX; k.n_vertices()];
    let mut b = ComplexBuilder::new(k.ambient_dim()).unwrap();
    for (v, slot) in id.iter_mut().enumerate() {
        if used.contains(v) {
            *slot = b
                .push_vertex(k.point(starplex::ids::VertexId(v as u32)))
                .unwrap()
                .0;
        }
    }
    for c in k.cells() {
        let vs: Vec<u32> = c.vertices.iter().map(|&v| id[v as usize]).collect();
        b.push_cell(c.kind, &vs).unwrap();
    }
    b.build(&BuildOptions::default()).unwrap().0
}

#[test]
fn random_complexes_round_trip() {
    for seed in 0..300u64 {
        let k = random_complex(seed);
        let vt = round_trip(Format::Vtk, &k);
        assert_eq!(vt.complex, k, "seed {seed} vtk");
        let g = round_trip(Format::Gmsh, &k);
        assert_eq!(g.complex, without_unused(&k), "seed {seed} gmsh");
        let g2 = round_trip(Format::Gmsh22, &k);
        assert_eq!(g2.complex, g.complex, "seed {seed} gmsh 2.2");
        let m = round_trip(Format::Medit, &k).complex;
        assert_eq!(m.coords(), k.coords(), "seed {seed} medit");
        assert_eq!(by_kind(&m), by_kind(&k), "seed {seed} medit");
    }
}

// ---------------------------------------------------------------- hand-written inputs

#[test]
fn vtk_5_layout_with_data_sections_reads_like_the_classic_one() {
    let v5 = "# vtk DataFile Version 5.1\nmeshio-like\nASCII\nDATASET UNSTRUCTURED_GRID\n\
              POINTS 5 double\n0.0 0.0 0.0 1.0 0.0 0.0 0.0 1.0 0.0 0.0 0.0 1.0 1.0 1.0 1.0\n\
              METADATA\nINFORMATION 1\nNAME L2_NORM_RANGE LOCATION vtkDataArray\nDATA 2 0 1.73\n\n\
              CELLS 4 8\nOFFSETS vtktypeint64\n0\n4\n7\n8\nCONNECTIVITY vtktypeint64\n\
              0\n1\n2\n3\n1\n2\n4\n4\nCELL_TYPES 3\n10\n5\n1\n\
              POINT_DATA 5\nSCALARS h double 1\nLOOKUP_TABLE default\n1 2 3 4 5\n\
              VECTORS vel float\n0 0 0 1 1 1 2 2 2 3 3 3 4 4 4\n\
              CELL_DATA 3\nFIELD FieldData 2\nids 1 3 int\n7 8 9\nw 2 3 double\n1 2 3 4 5 6\n\
              SCALARS q int\nLOOKUP_TABLE default\n1 2 3\n";
    let classic = "# vtk DataFile Version 4.2\nclassic\nASCII\nDATASET UNSTRUCTURED_GRID\n\
                   POINTS 5 float\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n1 1 1\n\
                   CELLS 2 9\n4 0 1 2 3\n3 1 2 4\nCELL_TYPES 2\n10\n5\n";
    let mut a = read_bytes(Format::Vtk, v5.as_bytes()).unwrap();
    let b = read_bytes(Format::Vtk, classic.as_bytes()).unwrap();
    // the data sections are attributes; the vertex cell (type 1) is dropped with its data
    use starplex::attr::{AttrValues, Attribute};
    let attrs = a.complex.take_attributes();
    let names = |c: &[Attribute]| c.iter().map(|a| a.name.clone()).collect::<Vec<_>>();
    assert_eq!(names(&attrs.vertex), ["h", "vel"]);
    assert_eq!(names(&attrs.cell), ["ids", "w", "q"]);
    assert_eq!(attrs.cell[0].values, AttrValues::Int(vec![7, 8]));
    assert_eq!(
        attrs.cell[1].values,
        AttrValues::Float(vec![1.0, 2.0, 3.0, 4.0])
    );
    assert_eq!(attrs.vertex[1].components, 3);
    assert_eq!(a.complex, b.complex);
    assert_eq!(a.complex.n_cells(), 2);
    assert_eq!(a.notes.len(), 1, "{:?}", a.notes);
}

#[test]
fn gmsh_22_and_41_with_sparse_tags_read_alike() {
    // Tags 100, 7, 55, 3000000000 (sparse), listed out of order; a boundary triangle, a point
    // element, a duplicated tetrahedron, a physical-names section.
    let v41 = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n1\n3 1 \"my $Nodes volume\"\n$EndPhysicalNames\n\
               $Entities\n1 0 0 1\n1 0 0 0 0\n1 0 0 0 1 1 1 0 0\n$EndEntities\n\
               $Nodes\n2 5 7 3000000000\n0 1 0 1\n100\n0 0 0\n3 1 0 4\n7\n55\n3000000000\n8\n1 0 0\n0 1 0\n0 0 1\n9 9 9\n$EndNodes\n\
               $Elements\n3 4 1 4\n0 1 15 1\n1 100\n2 1 2 1\n2 100 7 55\n3 1 4 2\n3 100 7 55 3000000000\n4 7 100 55 3000000000\n$EndElements\n";
    let v22 = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n5\n100 0 0 0\n7 1 0 0\n55 0 1 0\n3000000000 0 0 1\n8 9 9 9\n$EndNodes\n\
               $Elements\n5\n1 15 2 0 1 100\n2 2 2 0 1 100 7 55\n3 4 2 1 1 100 7 55 3000000000\n4 4 3 1 1 0 7 100 55 3000000000\n9 2 0 7 55 3000000000\n$EndElements\n";
    let mut a = read_bytes(Format::Gmsh, v41.as_bytes()).unwrap();
    let mut b = read_bytes(Format::Gmsh, v22.as_bytes()).unwrap();
    // the 2.2 file gives physical tag 1 to the tetrahedron, the 4.1 file's volume has none
    let (ta, tb) = (a.complex.take_attributes(), b.complex.take_attributes());
    assert_eq!(ta.cell.len(), 1);
    assert_eq!(
        ta.cell[0],
        starplex::attr::Attribute::int("gmsh:geometrical", 1, vec![1])
    );
    assert_eq!(
        tb.cell[0],
        starplex::attr::Attribute::int("gmsh:physical", 1, vec![1])
    );
    assert_eq!(tb.cell[1], ta.cell[0]);
    assert_eq!(a.complex, b.complex);
    assert_eq!(a.complex.n_cells(), 1);
    assert_eq!(a.complex.n_vertices(), 4);
    assert_eq!(a.complex.cells().next().unwrap().vertices, &[0, 1, 2, 3]);
    for r in [&a, &b] {
        assert!(
            r.notes.iter().any(|n| n.contains("1 duplicate")),
            "{:?}",
            r.notes
        );
        assert!(
            r.notes.iter().any(|n| n.contains("1 point elements")),
            "{:?}",
            r.notes
        );
        assert!(
            r.notes
                .iter()
                .any(|n| n.contains("1 nodes used by no element")),
            "{:?}",
            r.notes
        );
    }
    assert!(a
        .notes
        .iter()
        .any(|n| n.contains("dropped 1 elements that are faces")));
    assert!(b
        .notes
        .iter()
        .any(|n| n.contains("dropped 2 elements that are faces")));
}

/// A large tag seen first (stored sparsely), then enough small tags for the dense table to grow
/// past it: every tag must still be found.
#[test]
fn gmsh_tags_stay_found_when_the_dense_table_grows() {
    let n = 6000u64;
    let mut t = String::from("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n");
    t += &format!("{n}\n5000 0 0 5000\n");
    for i in (1..=n).filter(|&i| i != 5000) {
        t += &format!("{i} 0 0 {i}\n");
    }
    t += "$EndNodes\n$Elements\n1\n1 1 2 0 1 5000 3\n$EndElements\n";
    let r = read_bytes(Format::Gmsh, t.as_bytes()).unwrap();
    assert_eq!(r.complex.n_vertices(), 2);
    assert_eq!(r.complex.coords(), &[0.0, 0.0, 5000.0, 0.0, 0.0, 3.0]);
}

/// gmsh's prism has its triangle 0-1-2 facing the other one; VTK's faces outward. A gmsh prism
/// with positive gmsh volume must come out with positive VTK orientation.
#[test]
fn gmsh_prisms_are_mirrored_into_vtk_order() {
    let text = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 6 1 6\n3 1 0 6\n1\n2\n3\n4\n5\n6\n\
                0 0 0\n1 0 0\n0 1 0\n0 0 1\n1 0 1\n0 1 1\n$EndNodes\n\
                $Elements\n1 1 1 1\n3 1 6 1\n1 1 2 3 4 5 6\n$EndElements\n";
    let r = read_bytes(Format::Gmsh, text.as_bytes()).unwrap();
    let c = r.complex.cells().next().unwrap();
    assert_eq!(c.vertices, &[0, 2, 1, 3, 5, 4]);
    assert!(orientation(&r.complex, c.kind, c.vertices) > 0.0);
    // and the writer puts gmsh's order back
    let out = String::from_utf8(write_to_vec(Format::Gmsh, &r.complex).unwrap()).unwrap();
    assert!(out.contains("\n1 1 2 3 4 5 6\n"), "{out}");
}

#[test]
fn medit_skips_known_sections_and_accepts_free_layout() {
    let text = "  MeshVersionFormatted 1\n # comment\n Dimension\n 3\n Vertices\n 4\n\
                0 0 0 1 1 0 0 1\n0 1 0 1 0 0 1 1\nCorners 2 1 2\nNormals 1 0.5 0.5 0.7\n\
                NormalAtVertices 1 1 1\nTETRAHEDRA 1 1 2 3 4 -3\nEnd\n";
    let r = read_bytes(Format::Medit, text.as_bytes()).unwrap();
    assert_eq!(r.complex.n_cells(), 1);
    assert_eq!(r.notes.len(), 3, "{:?}", r.notes);
}

// ---------------------------------------------------------------- broken inputs

const M_HEAD: &str =
    "MeshVersionFormatted 2\nDimension 3\nVertices\n4\n0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\n";
const V_HEAD: &str =
    "# vtk DataFile Version 4.2\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 double\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n";
const G_HEAD: &str = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 4 1 4\n3 1 0 4\n1\n2\n3\n4\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n$EndNodes\n";

#[test]
fn broken_inputs_fail_with_their_line() {
    let cases: Vec<(Format, String, u64, &str)> = vec![
        // Medit
        (Format::Medit, "Vertices\n1\n".into(), 1, "not a Medit file"),
        (Format::Medit, "MeshVersionFormatted 2\nDimension 4\n".into(), 2, "Dimension 4"),
        (Format::Medit, M_HEAD[..M_HEAD.len() - 8].into(), 8, "unexpected end of file"),
        (Format::Medit, "MeshVersionFormatted 2\nDimension 3\nVertices\n1000000000000\n".into(), 4, "32-bit"),
        (Format::Medit, "MeshVersionFormatted 2\nDimension 3\nVertices\n1000000000\n0 0 0 0\n".into(), 6, "unexpected end of file"),
        (Format::Medit, M_HEAD.replace("1 0 0 0", "1 x 0 0"), 6, "found 'x'"),
        (Format::Medit, M_HEAD.replace("1 0 0 0", "1 nan 0 0"), 6, "not finite"),
        (Format::Medit, format!("{M_HEAD}Tetrahedra\n1\n1 2 3 5 0\nEnd\n"), 11, "out of range"),
        (Format::Medit, format!("{M_HEAD}Tetrahedra\n1\n1 2 2 3 0\nEnd\n"), 11, "more than once"),
        (Format::Medit, format!("{M_HEAD}Tetrahedra\n2\n1 2 3 4 0\nEnd\n"), 12, "found 'End'"),
        (Format::Medit, format!("{M_HEAD}Tetrahedra\n1\n1 2 3 4 0\n4 3 2 1 0\nEnd\n"), 12, "found the number '4' where a keyword"),
        (Format::Medit, format!("{M_HEAD}Blobs\n1\n1 2\nEnd\n"), 9, "unknown Medit keyword 'Blobs'"),
        (Format::Medit, format!("{M_HEAD}Tetrahedra\n1\n1 2 3 4 0\n"), 12, "expected a keyword or 'End'"),
        (Format::Medit, "MeshVersionFormatted 2\nDimension 3\nTriangles\n1\n1 2 3 0\n".into(), 3, "before 'Vertices'"),
        (Format::Medit, format!("{M_HEAD}Triangles\n2\n1 2 3 0\n3 2 1 0\nEnd\n"), 0, "same vertices"),
        // VTK
        (Format::Vtk, "# vtk DataFile Version 4.2\nt\nBINARY\n".into(), 4, "expected 'DATASET'"),
        (Format::Vtk, "solid x\n".into(), 1, "not a legacy VTK file"),
        (Format::Vtk, "# vtk DataFile Version 4.2\nt\nASCII\nDATASET STRUCTURED_POINTS\n".into(), 4, "STRUCTURED_POINTS"),
        (Format::Vtk, V_HEAD[..V_HEAD.len() - 6].into(), 9, "unexpected end of file"),
        (Format::Vtk, V_HEAD.replace("POINTS 4", "POINTS 1000000000000"), 5, "32-bit"),
        (Format::Vtk, V_HEAD.replace("POINTS 4", "POINTS 5000000000"), 5, "32-bit"),
        (Format::Vtk, V_HEAD.replace("POINTS 4", "POINTS 400000000"), 10, "unexpected end of file"),
        (Format::Vtk, V_HEAD.replace("0 1 0\n", "0 inf 0\n"), 8, "not finite"),
        (Format::Vtk, V_HEAD.replace("POINTS 4", "POINTS 3"), 9, "found the number '0' where a keyword"),
        (Format::Vtk, format!("{V_HEAD}CELLS 1 6\n4 0 1 2 3\nCELL_TYPES 1\n10\n"), 11, "6 numbers"),
        (Format::Vtk, format!("{V_HEAD}CELLS 1 5\n4 0 1 2 4\nCELL_TYPES 1\n10\n"), 11, "out of range"),
        (Format::Vtk, format!("{V_HEAD}CELLS 1 5\n4 0 1 1 3\nCELL_TYPES 1\n10\n"), 11, "more than once"),
        (Format::Vtk, format!("{V_HEAD}CELLS 1 5\n4 0 1 2 3\nCELL_TYPES 1\n42\n"), 13, "VTK cell type 42 (polyhedron) is not supported"),
        (Format::Vtk, format!("{V_HEAD}CELLS 1 4\n3 0 1 2\nCELL_TYPES 1\n10\n"), 13, "needs 4 points"),
        (Format::Vtk, format!("{V_HEAD}CELLS 1 5\n4 0 1 2 3\nCELL_TYPES 2\n10\n10\n"), 12, "CELL_TYPES counts 2"),
        (Format::Vtk, format!("{V_HEAD}CELLS 1 5\n4 0 1 2 3\n"), 10, "no CELL_TYPES"),
        (Format::Vtk, format!("{V_HEAD}CELLS 2 4\nOFFSETS int\n1 4\nCONNECTIVITY int\n0 1 2 3\nCELL_TYPES 1\n10\n"), 12, "first offset"),
        (Format::Vtk, format!("{V_HEAD}CELLS 2 5\nOFFSETS int\n0 4\nCONNECTIVITY int\n0 1 2 3\nCELL_TYPES 1\n10\n"), 12, "last offset"),
        (Format::Vtk, format!("{V_HEAD}CELLS 2 4\nOFFSETS int\n0 4\nCONNECTIVITY int\n0 1 2\n"), 15, "unexpected end of file"),
        (Format::Vtk, format!("{V_HEAD}CELLS 1 5\n4 0 1 2 3\nCELL_TYPES 1\n10\nPOINT_DATA 4\nSCALARS s float\nLOOKUP_TABLE default\n1 2 3\n"), 18, "unexpected end of file"),
        (Format::Vtk, format!("{V_HEAD}CELLS 1 5\n4 0 1 2 3\nCELL_TYPES 1\n10\nPOINT_DATA 4\nSCALARS s float 1\n1 2 3 4\n"), 16, "expected 'LOOKUP_TABLE', found '1'"),
        (Format::Vtk, format!("{V_HEAD}CELLS 1 5\n4 0 1 2 3\nCELL_TYPES 1\n10\nPOINT_DATA 4\nBLOB s float\n"), 15, "unknown keyword 'BLOB'"),
        // gmsh
        (Format::Gmsh, "$MeshFormat\n4.1 1 8\n$EndMeshFormat\n".into(), 0, "t.msh: byte 20: expected the integer 1"),
        (Format::Gmsh, "$MeshFormat\n3.0 0 8\n$EndMeshFormat\n".into(), 2, "version 3.0"),
        (Format::Gmsh, "$Nodes\n".into(), 1, "not a gmsh file"),
        (Format::Gmsh, G_HEAD.replace("1 4 1 4\n3 1 0 4", "1 5 1 4\n3 1 0 4"), 5, "declares 5 nodes"),
        (Format::Gmsh, G_HEAD.replace("1 4 1 4\n3 1 0 4", "1 4 1 4\n3 1 0 5"), 15, "found '$EndNodes'"),
        (Format::Gmsh, G_HEAD.replace("\n4\n0 0 0", "\n3\n0 0 0"), 10, "node tag 3 appears twice"),
        (Format::Gmsh, G_HEAD.replace("0 1 0\n", "0 nan 0\n"), 13, "not finite"),
        (Format::Gmsh, "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n1000000000000\n1 0 0 0\n".into(), 7, "unexpected end of file"),
        (Format::Gmsh, format!("{G_HEAD}$Elements\n1 1 1 1\n3 1 4 1\n1 1 2 3 9\n$EndElements\n"), 19, "node tag 9 is not a node"),
        (Format::Gmsh, format!("{G_HEAD}$Elements\n1 1 1 1\n3 1 4 1\n1 1 2 3 3\n$EndElements\n"), 19, "more than once"),
        (Format::Gmsh, format!("{G_HEAD}$Elements\n1 1 1 1\n3 1 32 1\n1 1 2 3 4\n$EndElements\n"), 18, "element type 32 is not supported"),
        // a 10-node tetrahedron (read as its corners) whose mid-edge nodes are not in $Nodes
        (Format::Gmsh, format!("{G_HEAD}$Elements\n1 1 1 1\n3 1 11 1\n1 1 2 3 4 5 6 7 8 9 10\n$EndElements\n"), 19, "node tag 5 is not a node"),
        (Format::Gmsh, format!("{G_HEAD}$Elements\n1 2 1 2\n3 1 4 1\n1 1 2 3 4\n$EndElements\n"), 17, "declares 2 elements"),
        (Format::Gmsh, format!("{G_HEAD}$Elements\n1 1 1 1\n3 1 4 1\n1 1 2 3 4\n"), 20, "'$EndElements'"),
        (Format::Gmsh, format!("{G_HEAD}$Comments\nhello\n"), 18, "'$EndComments'"),
        (Format::Gmsh, "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Elements\n0 0 0 0\n$EndElements\n".into(), 4, "$Elements before $Nodes"),
    ];
    for (i, (f, text, line, want)) in cases.iter().enumerate() {
        let e = match read_bytes(*f, text.as_bytes()) {
            Ok(r) => panic!(
                "case {i} ({f}, expecting '{want}'): read {} cells",
                r.complex.n_cells()
            ),
            Err(e) => e.to_string(),
        };
        assert!(e.contains(want), "case {i} ({f}): '{e}' lacks '{want}'");
        if *line > 0 {
            let at = format!(".{}:{line}: ", f.extension());
            assert!(
                e.contains(&at),
                "case {i} ({f}): '{e}' is not at line {line}"
            );
        }
    }
}

/// Arbitrary bytes never panic any of the three readers.
#[test]
fn garbage_never_panics() {
    let seeds: Vec<Vec<u8>> = vec![
        M_HEAD.as_bytes().to_vec(),
        format!("{V_HEAD}CELLS 1 5\n4 0 1 2 3\nCELL_TYPES 1\n10\n").into_bytes(),
        format!("{G_HEAD}$Elements\n1 1 1 1\n3 1 4 1\n1 1 2 3 4\n$EndElements\n").into_bytes(),
    ];
    let mut r = Rng(7);
    for (si, s) in seeds.iter().enumerate() {
        let f = [Format::Medit, Format::Vtk, Format::Gmsh][si];
        for _ in 0..400 {
            let mut d = s.clone();
            for _ in 0..1 + r.below(4) {
                let i = r.below(d.len());
                match r.below(3) {
                    0 => d[i] = b"0123456789 \n-.eE$x"[r.below(18)],
                    1 => {
                        d.remove(i);
                    }
                    _ => d.truncate(i),
                }
                if d.is_empty() {
                    break;
                }
            }
            let _ = read_bytes(f, &d);
        }
    }
}

// ---------------------------------------------------------------- dataset files

/// Signed orientation in VTK's convention (> 0 when the cell is positively oriented).
fn orientation(k: &IndexedComplex, kind: CellKind, v: &[u32]) -> f64 {
    let p = |i: usize| -> [f64; 3] {
        let q = k.point(starplex::ids::VertexId(v[i]));
        [q[0], q[1], q[2]]
    };
    let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let mean = |ids: &[usize]| {
        let mut m = [0.0; 3];
        for &i in ids {
            let q = p(i);
            for a in 0..3 {
                m[a] += q[a] / ids.len() as f64;
            }
        }
        m
    };
    match kind {
        CellKind::Simplex(3) => dot(cross(sub(p(1), p(0)), sub(p(2), p(0))), sub(p(3), p(0))),
        // the base normal points at the apex / the top face
        CellKind::Pyramid => dot(
            cross(sub(p(2), p(0)), sub(p(3), p(1))),
            sub(p(4), mean(&[0, 1, 2, 3])),
        ),
        CellKind::Hex => dot(
            cross(sub(p(2), p(0)), sub(p(3), p(1))),
            sub(mean(&[4, 5, 6, 7]), mean(&[0, 1, 2, 3])),
        ),
        // VTK's wedge: the normal of 0-1-2 points away from 3-4-5
        CellKind::Prism => -dot(
            cross(sub(p(1), p(0)), sub(p(2), p(0))),
            sub(mean(&[3, 4, 5]), mean(&[0, 1, 2])),
        ),
        _ => 1.0,
    }
}

/// The small dataset file `file` (shared datasets or `$STARPLEX_DATA`), or `None` with a printed
/// reason (medium copies with `.mesh`/`.msh`/`.vtk` live only under `$STARPLEX_DATA`).
fn data_file(file: &str) -> Option<PathBuf> {
    let p = common_data::dataset_file("small", file);
    if p.is_none() {
        println!(
            "skipped: {file} not found (set STARPLEX_DATA=/work/data to compare the dataset files)"
        );
    }
    p
}

fn read_file(p: &Path) -> ReadResult {
    io::read(p, &ReadOptions::default()).unwrap_or_else(|e| panic!("{e}"))
}

fn assert_same_points(a: &IndexedComplex, spx: &IndexedComplex, what: &str) {
    assert_eq!(a.n_vertices(), spx.n_vertices(), "{what}: vertex count");
    assert_eq!(a.ambient_dim(), spx.ambient_dim(), "{what}");
    // the .spx holds 10 significant digits
    for (i, (x, y)) in a.coords().iter().zip(spx.coords()).enumerate() {
        assert!(
            (x - y).abs() <= 1e-9 * x.abs().max(1.0),
            "{what}: coordinate {i}: {x} vs {y}"
        );
    }
}

#[test]
fn dataset_medit_files_match_their_spx() {
    for name in ["mixed_plate_s", "tet_elephant", "hex_knot1", "hexvox_skull"] {
        let Some(mesh) = data_file(&format!("{name}.mesh")) else {
            continue;
        };
        let spx =
            read_file(&common_data::dataset_file("small", &format!("{name}.spx")).unwrap()).complex;
        let r = read_file(&mesh);
        assert!(r.notes.is_empty(), "{name}: {:?}", r.notes);
        assert_same_points(&r.complex, &spx, name);
        // meshio wrote the .mesh from the same cell arrays as the .spx, without reordering
        assert_eq!(by_kind(&r.complex), by_kind(&spx), "{name}");
    }
}

#[test]
fn dataset_mixed_plate_vtk_and_msh_match_the_spx() {
    let Some(msh) = data_file("mixed_plate_s.msh") else {
        return;
    };
    let d = msh.parent().unwrap();
    let spx = read_file(&d.join("mixed_plate_s.spx")).complex;
    // The .spx stores gmsh's prism order (meshio's internal one); in VTK's convention those
    // prisms are mirrored. The expected VTK-order cells: every cell of the .spx, prisms mapped
    // by gmsh's prism-to-VTK permutation when the .spx prism has gmsh's orientation.
    let mut expected = by_kind(&spx);
    let mut mirrored = 0;
    for c in expected.get_mut(&CellKind::Prism).into_iter().flatten() {
        let o = orientation(&spx, CellKind::Prism, c);
        assert!(o != 0.0);
        if o < 0.0 {
            *c = gmsh::PRISM_PERM.iter().map(|&i| c[i]).collect();
            mirrored += 1;
        }
    }
    println!("{mirrored} prisms of mixed_plate_s.spx are in gmsh's (mirrored) order");
    for ext in ["vtk", "msh"] {
        let r = read_file(&d.join(format!("mixed_plate_s.{ext}")));
        assert_same_points(&r.complex, &spx, ext);
        assert_eq!(by_kind(&r.complex), expected, "{ext}");
        for c in r.complex.cells() {
            assert!(
                orientation(&r.complex, c.kind, c.vertices) > 0.0,
                "{ext}: cell {:?} is inverted",
                c
            );
        }
        if ext == "msh" {
            assert!(
                r.notes
                    .contains(&"dropped 1 duplicate elements".to_string()),
                "{:?}",
                r.notes
            );
            assert!(
                r.notes
                    .contains(&"dropped 27 point elements (type 15)".to_string()),
                "{:?}",
                r.notes
            );
            assert!(
                r.notes
                    .contains(&"dropped 3 nodes used by no element (geometry points)".to_string()),
                "{:?}",
                r.notes
            );
        } else {
            assert!(r.notes.is_empty(), "{:?}", r.notes);
        }
    }
}

#[test]
fn legacy_vtk_reads_polygons_pixels_strips_and_poly_lines() {
    // a pentagon (fan of 3 triangles), a pixel (a quad in starplex's corner order), a 5-point
    // strip (3 triangles) and a 3-point poly-line (2 edges), disjoint
    let text =
        "# vtk DataFile Version 4.2\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 17 double\n\
                0 0 0\n1 0 0\n1.5 1 0\n0.5 2 0\n-0.5 1 0\n\
                3 0 0\n4 0 0\n3 1 0\n4 1 0\n\
                6 0 0\n6 1 0\n7 0 0\n7 1 0\n8 0 0\n\
                10 0 0\n11 0 0\n12 0 0\n\
                CELLS 4 21\n5 0 1 2 3 4\n4 5 6 7 8\n5 9 10 11 12 13\n3 14 15 16\n\
                CELL_TYPES 4\n7\n8\n6\n4\n";
    let r = vtk::read_from(text.as_bytes(), "p.vtk".as_ref(), &ReadOptions::default()).unwrap();
    let k = &r.complex;
    let count = |kind| k.cells().filter(|c| c.kind == kind).count();
    assert_eq!(count(CellKind::Simplex(2)), 3 + 3);
    assert_eq!(count(CellKind::Simplex(1)), 2);
    assert!(k
        .cells()
        .any(|c| c.kind == CellKind::Quad && c.vertices == [5, 6, 8, 7]));
    assert_eq!(r.notes.len(), 3, "{:?}", r.notes);
    // a polygon of two points is an error naming the cell
    let bad = text
        .replace("3 14 15 16", "2 14 15")
        .replace("CELLS 4 21", "CELLS 4 20")
        .replace("\n4\n", "\n7\n");
    let e = vtk::read_from(bad.as_bytes(), "p.vtk".as_ref(), &ReadOptions::default()).unwrap_err();
    assert!(
        e.to_string()
            .contains("cell 3: VTK cell type 7 (polygon) needs at least 3 points"),
        "{e}"
    );
}
