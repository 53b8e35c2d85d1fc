//! Outputs never clobber or lie: symbolic links, FIFOs, standard output, permissions, failed
//! writes; every refused (lossy) write; the explicit conversions (boundary, triangulate); the STL
//! writers read back by the STL reader.
use std::path::{Path, PathBuf};

use starplex::algo::surface;
use starplex::cell::CellKind;
use starplex::complex::{BuildOptions, ComplexBuilder, IndexedComplex};
use starplex::io::{self, output, Format, IoErrorKind, ReadOptions};

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("starplex-io-output-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

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

const CUBE: [&[f64]; 8] = [
    &[0.0, 0.0, 0.0],
    &[1.0, 0.0, 0.0],
    &[1.0, 1.0, 0.0],
    &[0.0, 1.0, 0.0],
    &[0.0, 0.0, 1.0],
    &[1.0, 0.0, 1.0],
    &[1.0, 1.0, 1.0],
    &[0.0, 1.0, 1.0],
];

fn tri() -> IndexedComplex {
    complex(
        3,
        &[&[0.0, 0.0, 0.0], &[1.0, 0.0, 0.0], &[0.0, 1.0, 0.0]],
        &[(CellKind::Simplex(2), &[0, 1, 2])],
    )
}

fn hex() -> IndexedComplex {
    complex(3, &CUBE, &[(CellKind::Hex, &[0, 1, 2, 3, 4, 5, 6, 7])])
}

/// Two positively oriented tetrahedra sharing a face.
fn two_tets() -> IndexedComplex {
    let pts: [&[f64]; 5] = [
        &[0.0, 0.0, 0.0],
        &[1.0, 0.0, 0.0],
        &[0.0, 1.0, 0.0],
        &[0.0, 0.0, 1.0],
        &[1.0, 1.0, 1.0],
    ];
    complex(
        3,
        &pts,
        &[
            (CellKind::Simplex(3), &[0, 1, 2, 3]),
            (CellKind::Simplex(3), &[1, 4, 2, 3]),
        ],
    )
}

fn read(p: &Path) -> IndexedComplex {
    io::read(p, &ReadOptions::default())
        .unwrap_or_else(|e| panic!("{e}"))
        .complex
}

#[cfg(unix)]
#[test]
fn a_symlink_is_followed_and_stays_a_link() {
    use std::os::unix::fs::PermissionsExt;
    let d = dir("symlink");
    let real = d.join("real.off");
    std::fs::write(&real, "old").unwrap();
    std::fs::set_permissions(&real, std::fs::Permissions::from_mode(0o640)).unwrap();
    let link = d.join("link.off");
    std::os::unix::fs::symlink("real.off", &link).unwrap();
    // a chain of two links, one absolute
    let link2 = d.join("link2.off");
    std::os::unix::fs::symlink(&link, &link2).unwrap();
    io::write(&link2, &tri(), None).unwrap();
    assert!(std::fs::symlink_metadata(&link)
        .unwrap()
        .file_type()
        .is_symlink());
    assert!(std::fs::symlink_metadata(&link2)
        .unwrap()
        .file_type()
        .is_symlink());
    assert_eq!(read(&real), tri());
    let mode = std::fs::metadata(&real).unwrap().permissions().mode() & 0o777;
    assert_eq!(mode, 0o640, "the replaced file keeps its permissions");
    // a dangling link creates its target
    let dangling = d.join("dangling.off");
    std::os::unix::fs::symlink("new.off", &dangling).unwrap();
    io::write(&dangling, &tri(), None).unwrap();
    assert_eq!(read(&d.join("new.off")), tri());
    // no temporary file is left anywhere
    let names: Vec<String> = std::fs::read_dir(&d)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert!(names.iter().all(|n| !n.ends_with(".tmp")), "{names:?}");
    std::fs::remove_dir_all(&d).ok();
}

#[cfg(unix)]
#[test]
fn a_fifo_is_written_through() {
    let d = dir("fifo");
    let fifo = d.join("pipe.off");
    let st = std::process::Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .unwrap();
    assert!(st.success());
    assert_eq!(
        output::resolve(&fifo).unwrap(),
        output::OutputTarget::Stream(fifo.clone())
    );
    let f2 = fifo.clone();
    let reader = std::thread::spawn(move || std::fs::read(&f2).unwrap());
    io::write(&fifo, &tri(), None).unwrap();
    let bytes = reader.join().unwrap();
    let back = io::read_stream(
        &bytes[..],
        "pipe".as_ref(),
        Format::Off,
        &ReadOptions::default(),
    )
    .unwrap();
    assert_eq!(back.complex, tri());
    // still a FIFO, not replaced by a regular file
    use std::os::unix::fs::FileTypeExt;
    assert!(std::fs::symlink_metadata(&fifo)
        .unwrap()
        .file_type()
        .is_fifo());
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn standard_streams_and_devices_resolve_to_streams() {
    use output::OutputTarget;
    for p in ["-", "/dev/stdout", "/dev/fd/1", "/proc/self/fd/1"] {
        assert_eq!(
            output::resolve(Path::new(p)).unwrap(),
            OutputTarget::Stdout,
            "{p}"
        );
    }
    assert_eq!(
        output::resolve(Path::new("/dev/stderr")).unwrap(),
        OutputTarget::Stderr
    );
    assert_eq!(
        output::resolve(Path::new("/dev/null")).unwrap(),
        OutputTarget::Stream("/dev/null".into())
    );
    // writing to /dev/null works and leaves /dev/null a device
    io::write(Path::new("/dev/null"), &tri(), Some(Format::Off)).unwrap();
    // a directory is an error, not a rename over it
    let d = dir("isdir");
    let sub = d.join("sub.off");
    std::fs::create_dir(&sub).unwrap();
    assert!(io::write(&sub, &tri(), None).is_err());
    assert!(sub.is_dir());
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn standard_output_needs_a_format() {
    let e = io::write(Path::new("-"), &tri(), None).unwrap_err();
    assert!(
        matches!(e.kind, IoErrorKind::NeedsFormat { output: true, .. }),
        "{e}"
    );
    let e = io::read(Path::new("-"), &ReadOptions::default()).unwrap_err();
    assert!(
        matches!(e.kind, IoErrorKind::NeedsFormat { output: false, .. }),
        "{e}"
    );
    assert_eq!(e.path, Path::new(io::STDIN_NAME));
}

#[test]
fn a_failed_write_leaves_the_old_file_and_no_temporary() {
    let d = dir("failed");
    let target = d.join("keep.stl");
    std::fs::write(&target, "precious").unwrap();
    // refused before anything is opened
    let e = io::write(&target, &hex(), None).unwrap_err();
    assert!(matches!(
        e.kind,
        IoErrorKind::CannotWrite {
            format: Format::Stl,
            ..
        }
    ));
    // failing in the middle of writing
    let e = output::write_with(&target, |w| {
        w.write_all(b"half a mesh")?;
        Err(IoErrorKind::Parse("disk on fire".into()))
    })
    .unwrap_err();
    assert_eq!(e.to_string(), format!("{}: disk on fire", target.display()));
    assert_eq!(std::fs::read(&target).unwrap(), b"precious");
    assert_eq!(std::fs::read_dir(&d).unwrap().count(), 1);
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn every_lossy_write_is_refused_with_a_typed_error() {
    let tet = complex(3, &CUBE[..4], &[(CellKind::Simplex(3), &[0, 1, 2, 3])]);
    let quad = complex(3, &CUBE[..4], &[(CellKind::Quad, &[0, 1, 2, 3])]);
    let s4 = complex(
        3,
        &[
            &[0.0, 0.0, 0.0],
            &[1.0, 0.0, 0.0],
            &[0.0, 1.0, 0.0],
            &[0.0, 0.0, 1.0],
            &[1.0, 1.0, 1.0],
        ],
        &[(CellKind::Simplex(4), &[0, 1, 2, 3, 4])],
    );
    let point = complex(3, &CUBE[..1], &[(CellKind::Simplex(0), &[0])]);
    let isolated = complex(3, &CUBE[..4], &[(CellKind::Simplex(2), &[0, 1, 2])]);
    let twin = complex(
        3,
        &[
            &[0.0, 0.0, 0.0],
            &[1.0, 0.0, 0.0],
            &[0.0, 1.0, 0.0],
            &[1.0 + 1e-12, 0.0, 0.0],
            &[0.0, 0.0, 1.0],
        ],
        &[
            (CellKind::Simplex(2), &[0, 1, 2]),
            (CellKind::Simplex(2), &[3, 2, 4]),
        ],
    );
    let p4: [&[f64]; 2] = [&[0.0, 0.0, 0.0, 0.0], &[1.0, 0.0, 0.0, 0.0]];
    let ambient4 = complex(4, &p4, &[(CellKind::Simplex(1), &[0, 1])]);
    let hexa = hex();
    let refused: Vec<(&str, &IndexedComplex, Vec<Format>)> = vec![
        (
            "tet",
            &tet,
            vec![
                Format::Off,
                Format::Ply,
                Format::Obj,
                Format::Stl,
                Format::StlBinary,
            ],
        ),
        (
            "quad",
            &quad,
            vec![Format::OffSimplices, Format::Stl, Format::StlBinary],
        ),
        (
            "hex",
            &hexa,
            vec![
                Format::Off,
                Format::OffSimplices,
                Format::Ply,
                Format::Obj,
                Format::Stl,
            ],
        ),
        (
            "4-simplex",
            &s4,
            vec![
                Format::Off,
                Format::Ply,
                Format::Obj,
                Format::Stl,
                Format::Medit,
                Format::Vtk,
                Format::Gmsh,
                Format::Gmsh22,
            ],
        ),
        (
            "point cell",
            &point,
            vec![
                Format::Off,
                Format::Ply,
                Format::Obj,
                Format::Stl,
                Format::Medit,
            ],
        ),
        (
            "isolated vertex",
            &isolated,
            vec![Format::Stl, Format::StlBinary],
        ),
        ("f32 twins", &twin, vec![Format::Stl, Format::StlBinary]),
        (
            "ambient 4",
            &ambient4,
            vec![
                Format::Ply,
                Format::Obj,
                Format::Stl,
                Format::Medit,
                Format::Vtk,
                Format::Gmsh,
            ],
        ),
    ];
    let d = dir("refused");
    for (name, k, formats) in refused {
        for f in formats {
            let target = d.join(format!("out.{}", f.extension()));
            let Err(e) = io::write(&target, k, Some(f)) else {
                panic!("{name} to {f}: written")
            };
            match &e.kind {
                IoErrorKind::CannotWrite { format, reason } => {
                    assert_eq!(*format, f, "{name}");
                    assert!(!reason.is_empty());
                }
                other => panic!("{name} to {f}: expected CannotWrite, got {other:?}"),
            }
            assert!(
                e.to_string().starts_with(&target.display().to_string()),
                "{e}"
            );
            assert!(
                !target.exists(),
                "{name} to {f}: a refused write created a file"
            );
        }
    }
    // and what each format can hold is written
    for (k, f) in [
        (&tet, Format::OffSimplices),
        (&quad, Format::Off),
        (&tet, Format::Vtk),
        (&tri(), Format::Stl),
    ] {
        assert!(io::check_writable(k, f).is_ok(), "{f}");
    }
    // the read-only formats say which ones are writable
    let e = io::check_writable(&tet, Format::Ts).unwrap_err();
    assert!(e.to_string().contains("spx spb off"), "{e}");
    std::fs::remove_dir_all(&d).ok();
}

/// Six times the signed volume enclosed by an oriented closed triangle surface.
fn signed_volume6(k: &IndexedComplex) -> f64 {
    let mut v = 0.0;
    for c in k.cells() {
        assert_eq!(c.kind, CellKind::Simplex(2));
        let p: Vec<&[f64]> = c
            .vertices
            .iter()
            .map(|&i| k.point(starplex::ids::VertexId(i)))
            .collect();
        v += p[0][0] * (p[1][1] * p[2][2] - p[1][2] * p[2][1])
            - p[0][1] * (p[1][0] * p[2][2] - p[1][2] * p[2][0])
            + p[0][2] * (p[1][0] * p[2][1] - p[1][1] * p[2][0]);
    }
    v
}

#[test]
fn boundary_is_the_outward_surface() {
    // a hexahedron: 6 quads, outward (volume 1 after triangulation)
    let (b, r) = surface::boundary(&hex()).unwrap();
    assert_eq!((b.n_cells(), r.ignored_lower_cells), (6, 0));
    assert!(b.blocks().iter().all(|bl| bl.kind == CellKind::Quad));
    let t = surface::triangulate(&b).unwrap();
    assert_eq!(t.n_cells(), 12);
    assert!(
        (signed_volume6(&t) - 6.0).abs() < 1e-12,
        "{}",
        signed_volume6(&t)
    );
    // two tets: the shared face is not boundary; 6 outward triangles
    let (b, _) = surface::boundary(&two_tets()).unwrap();
    assert_eq!((b.n_vertices(), b.n_cells()), (5, 6));
    let vol6: f64 = 1.0 + 2.0; // |det| of the two tets
    assert!(
        (signed_volume6(&b) - vol6).abs() < 1e-12,
        "{}",
        signed_volume6(&b)
    );
    // a mixed mesh: a prism on a hex, and a dangling edge (ignored, counted)
    let mut pts: Vec<&[f64]> = CUBE.to_vec();
    pts.extend_from_slice(&[
        &[0.5, 0.0, 2.0],
        &[0.5, 1.0, 2.0],
        &[3.0, 3.0, 3.0],
        &[4.0, 3.0, 3.0],
    ]);
    let k = complex(
        3,
        &pts,
        &[
            (CellKind::Hex, &[0, 1, 2, 3, 4, 5, 6, 7]),
            (CellKind::Prism, &[4, 5, 8, 7, 6, 9]),
            (CellKind::Simplex(1), &[10, 11]),
        ],
    );
    let (b, r) = surface::boundary(&k).unwrap();
    assert_eq!(r.ignored_lower_cells, 1);
    assert_eq!(b.n_vertices(), 10);
    let t = surface::triangulate(&b).unwrap();
    assert!(
        (signed_volume6(&t) - 9.0).abs() < 1e-12,
        "{}",
        signed_volume6(&t)
    ); // 1 + 0.5
       // a surface's boundary is its border (a single triangle: 3 edges)
    let (b, _) = surface::boundary(&tri()).unwrap();
    assert_eq!(b.n_cells(), 3);
}

#[test]
fn triangulate_splits_quads_and_refuses_volumes() {
    let quad = complex(3, &CUBE[..4], &[(CellKind::Quad, &[0, 1, 2, 3])]);
    let t = surface::triangulate(&quad).unwrap();
    let cells: Vec<Vec<u32>> = t.cells().map(|c| c.vertices.to_vec()).collect();
    assert_eq!(cells, [vec![0, 1, 2], vec![0, 2, 3]]);
    assert!(matches!(
        surface::triangulate(&hex()),
        Err(surface::SurfaceError::VolumeCell {
            cell: 0,
            kind: CellKind::Hex
        })
    ));
}

#[test]
fn stl_writers_read_back_by_the_stl_reader() {
    let d = dir("stl");
    let (surf, _) = surface::boundary(&two_tets()).unwrap();
    let quads = surface::boundary(&hex()).unwrap().0;
    let tris = surface::triangulate(&quads).unwrap();
    for k in [&tri(), &surf, &tris] {
        for f in [Format::Stl, Format::StlBinary] {
            let p = d.join("t.stl");
            io::write(&p, k, Some(f)).unwrap();
            let bytes = std::fs::read(&p).unwrap();
            assert_eq!(bytes.starts_with(b"solid"), f == Format::Stl);
            let back = read(&p);
            // same triangles in the same order; vertices numbered by first use
            assert_eq!(back.n_cells(), k.n_cells());
            assert_eq!(back.n_vertices(), k.n_vertices());
            for (a, b) in k.cells().zip(back.cells()) {
                let pa: Vec<&[f64]> = a
                    .vertices
                    .iter()
                    .map(|&v| k.point(starplex::ids::VertexId(v)))
                    .collect();
                let pb: Vec<&[f64]> = b
                    .vertices
                    .iter()
                    .map(|&v| back.point(starplex::ids::VertexId(v)))
                    .collect();
                assert_eq!(pa, pb, "{f}");
            }
        }
    }
    // 2D triangles get z = 0
    let flat = complex(
        2,
        &[&[0.0, 0.0], &[1.0, 0.0], &[0.0, 1.0]],
        &[(CellKind::Simplex(2), &[0, 1, 2])],
    );
    let p = d.join("flat.stl");
    io::write(&p, &flat, Some(Format::StlBinary)).unwrap();
    assert_eq!(read(&p).coords(), &[0., 0., 0., 1., 0., 0., 0., 1., 0.]);
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn gzip_inputs_are_recognised_by_content_and_unknown_extensions_by_magic() {
    use std::io::Write;
    let d = dir("gzip");
    let text = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    let gz = |bytes: &[u8]| {
        let mut e = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::fast());
        e.write_all(bytes).unwrap();
        e.finish().unwrap()
    };
    // .off.gz, a gzipped file named .off, and two gzip members (as `cat a.gz b.gz` makes)
    let half = text.len() / 2;
    let mut two = gz(&text.as_bytes()[..half]);
    two.extend(gz(&text.as_bytes()[half..]));
    for (name, bytes) in [
        ("t.off.gz", gz(text.as_bytes())),
        ("t.off", gz(text.as_bytes())),
        ("two.off.gz", two),
        ("noext.gz", gz(text.as_bytes())),
    ] {
        let p = d.join(name);
        std::fs::write(&p, bytes).unwrap();
        let r = io::read(&p, &ReadOptions::default()).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(r.complex, tri(), "{name}");
        assert_eq!(r.format, Format::Off);
        assert!(
            r.notes.contains(&"decompressed gzip input".to_string()),
            "{name}"
        );
    }
    // an unknown extension: the first bytes name the format
    for (name, k) in [
        ("mesh.dat", Format::Vtk),
        ("mesh.txt", Format::Gmsh),
        ("mesh", Format::Spx),
    ] {
        let p = d.join(name);
        io::write(&p, &tri(), Some(k)).unwrap();
        let r = io::read(&p, &ReadOptions::default()).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(r.format, k);
        assert_eq!(r.complex.n_cells(), 1);
    }
    // truncated gzip is an error, not a short mesh
    let p = d.join("cut.off.gz");
    let g = gz(text.as_bytes());
    std::fs::write(&p, &g[..g.len() - 12]).unwrap();
    assert!(io::read(&p, &ReadOptions::default()).is_err());
    // nothing recognisable: the unknown-format error
    let p = d.join("notes.txt");
    std::fs::write(&p, "hello").unwrap();
    let e = io::read(&p, &ReadOptions::default()).unwrap_err();
    assert!(matches!(e.kind, IoErrorKind::UnknownFormat(_)), "{e}");
    std::fs::remove_dir_all(&d).ok();
}
