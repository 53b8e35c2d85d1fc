//! OFF and the Stellar reference formats against the `.spx` of the same dataset (identical
//! complexes: same coordinates, same cells in the same order), and OFF write/read round trips
//! (seeded property tests against the complex itself as the model).
//!
//! Files under `../shared/datasets/small/` are used when present; files that only exist under
//! `$STARPLEX_DATA/small/<name>/` are used when `STARPLEX_DATA` is set and skipped (with a printed
//! reason) otherwise.
use crate::common_data;
use std::path::{Path, PathBuf};

use proptest::prelude::*;
use proptest::test_runner::{Config as ProptestConfig, RngSeed};
use starplex::cell::CellKind;
use starplex::complex::{BuildOptions, ComplexBuilder, IndexedComplex};
use starplex::io::{self, off, Format, PolygonMode, ReadOptions};

/// The dataset file `file` (e.g. `tri_elephant.off`), from the shared datasets or
/// `$STARPLEX_DATA/small/<stem>/`. `None` (with a printed reason) when it cannot be used here; a
/// failure when `STARPLEX_DATA` is set (the generated copies hold every format).
fn dataset(file: &str) -> Option<PathBuf> {
    let p = common_data::dataset_file("small", file);
    if p.is_none() {
        assert!(
            std::env::var_os("STARPLEX_DATA").is_none(),
            "STARPLEX_DATA is set but has no {file}"
        );
        println!("SKIPPED: {file} not found (set STARPLEX_DATA=/work/data)");
    }
    p
}

fn read(p: &Path, simplices: bool) -> IndexedComplex {
    let opts = ReadOptions {
        polygons: if simplices {
            PolygonMode::Simplices
        } else {
            PolygonMode::Polygons
        },
        ..Default::default()
    };
    match io::read(p, &opts) {
        Ok(r) => r.complex,
        Err(e) => panic!("{e}"),
    }
}

/// `file` read (with simplex mode if asked) equals `<stem>.spx` exactly.
fn same_as_spx(file: &str, simplices: bool) {
    let Some(p) = dataset(file) else { return };
    let stem = file.split('.').next().unwrap();
    let Some(spx) = dataset(&format!("{stem}.spx")) else {
        return;
    };
    let a = read(&p, simplices);
    let b = read(&spx, false);
    assert_eq!(a.n_vertices(), b.n_vertices(), "{file}");
    assert_eq!(a.n_cells(), b.n_cells(), "{file}");
    assert!(a == b, "{file}: the complex differs from {stem}.spx");
    println!(
        "{file}: {} vertices, {} cells, identical to {stem}.spx",
        a.n_vertices(),
        a.n_cells()
    );
}

#[test]
fn off_tri_elephant_equals_spx() {
    same_as_spx("tri_elephant.off", false);
}

#[test]
fn off_vr_kitten_as_simplices_equals_spx() {
    same_as_spx("vr_kitten_s.off", true);
}

#[test]
fn off_sierp5_as_simplices_equals_spx() {
    same_as_spx("sierp5_xs.off", true);
}

#[test]
fn off_quad_elephant_equals_spx() {
    same_as_spx("quad_elephant.off", false);
}

#[test]
fn tri_equals_spx() {
    same_as_spx("tri_elephant.tri", false);
}

#[test]
fn ts_equals_spx() {
    same_as_spx("tet_elephant.ts", false);
}

#[test]
fn sierp_equals_spx() {
    same_as_spx("sierp5_xs.sierp", false);
}

#[test]
fn hex_equals_spx() {
    same_as_spx("hex_knot1.hex", false);
}

/// Writes `k` as OFF into memory and reads it back.
fn off_round_trip(k: &IndexedComplex, mode: PolygonMode) -> IndexedComplex {
    let mut buf = Vec::new();
    match mode {
        PolygonMode::Polygons => off::write(&mut buf, k).unwrap(),
        PolygonMode::Simplices => off::write_simplices(&mut buf, k).unwrap(),
    }
    let opts = ReadOptions {
        polygons: mode,
        ..Default::default()
    };
    match off::read_from(&buf[..], "mem.off".as_ref(), &opts) {
        Ok(r) => r.complex,
        Err(e) => panic!("{e}\n{}", String::from_utf8_lossy(&buf)),
    }
}

#[test]
fn datasets_round_trip_through_off_files() {
    let dir = std::env::temp_dir().join(format!("starplex-io-off-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (file, simplices) in [
        ("tri_elephant.spx", false),
        ("vr_kitten_s.spx", true),
        ("tet_elephant.spx", true),
        ("quad_elephant.spx", false),
        ("sierp5_xs.spx", true),
    ] {
        let Some(p) = dataset(file) else { continue };
        let k = read(&p, false);
        let out = dir.join(file.replace(".spx", ".off"));
        let format = simplices.then_some(io::Format::OffSimplices);
        io::write(&out, &k, format).unwrap();
        let back = read(&out, simplices);
        assert!(back == k, "{file}: OFF round trip changed the complex");
        if simplices && k.dim().is_some_and(|d| d >= 3) {
            // plain OFF refuses what would read back as polygons, and writes nothing
            let e = io::write(&out.with_extension("plain.off"), &k, None).unwrap_err();
            assert!(e.to_string().contains("off-simplices"), "{e}");
            assert!(!out.with_extension("plain.off").exists());
        }
    }
    // 3D cells cannot be written, with a clear reason.
    if let Some(p) = dataset("hexvox_skull.spx") {
        let k = read(&p, false);
        let e = io::write(&dir.join("h.off"), &k, None).unwrap_err();
        assert!(
            e.to_string().contains("off cannot hold this complex") && e.to_string().contains("hex"),
            "{e}"
        );
        assert!(!dir.join("h.off").exists());
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// A random complex: simplices of dimension min_dim..=max_dim on `nv` vertices in `ambient`
/// dimensions, made valid by dropping duplicates and faces of other cells.
fn arb_simplicial(min_dim: usize, max_dim: usize) -> impl Strategy<Value = IndexedComplex> {
    (1usize..=7, (min_dim + 1)..=24).prop_flat_map(move |(ambient, nv)| {
        let cell =
            proptest::collection::btree_set(0..nv as u32, (min_dim + 1)..=(max_dim + 1).min(nv))
                .prop_map(|s| s.into_iter().collect::<Vec<u32>>())
                .prop_shuffle();
        (
            proptest::collection::vec(-1e6f64..1e6, ambient * nv),
            proptest::collection::vec(cell, 0..30),
        )
            .prop_map(move |(coords, cells)| {
                let mut b = ComplexBuilder::new(ambient).unwrap();
                for p in coords.chunks(ambient) {
                    b.push_vertex(p).unwrap();
                }
                for c in cells {
                    b.push_cell(CellKind::Simplex((c.len() - 1) as u8), &c)
                        .unwrap();
                }
                let opts = BuildOptions {
                    drop_face_cells: true,
                    drop_duplicates: true,
                    ..Default::default()
                };
                b.build(&opts).unwrap().0
            })
    })
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 200,
        rng_seed: RngSeed::Fixed(0x0ff),
        failure_persistence: None,
        ..ProptestConfig::default()
    })]

    /// Simplicial complexes of any dimension and ambient dimension survive write + read in
    /// simplex mode exactly (coordinates, cells, vertex orders, cell ids).
    #[test]
    fn simplicial_round_trip(k in arb_simplicial(0, 6)) {
        let back = off_round_trip(&k, PolygonMode::Simplices);
        prop_assert!(back == k);
    }

    /// Edges and triangles also survive polygon mode (the default; 0-simplices would be dropped
    /// there with a note, so the model has none).
    #[test]
    fn surface_round_trip_in_polygon_mode(k in arb_simplicial(1, 2)) {
        let back = off_round_trip(&k, PolygonMode::Polygons);
        prop_assert!(back == k);
    }
}

#[test]
fn quads_round_trip_and_tets_are_refused_in_plain_off() {
    let mut b = ComplexBuilder::new(3).unwrap();
    for i in 0..6 {
        b.push_vertex(&[i as f64, (i * i) as f64 * 0.5, -0.25])
            .unwrap();
    }
    b.push_cell(CellKind::Quad, &[0, 1, 2, 3]).unwrap();
    b.push_cell(CellKind::Simplex(2), &[2, 3, 4]).unwrap();
    b.push_cell(CellKind::Quad, &[3, 2, 5, 4]).unwrap();
    let k = b.clone().build(&BuildOptions::default()).unwrap().0;
    assert!(off_round_trip(&k, PolygonMode::Polygons) == k);
    b.push_cell(CellKind::Simplex(3), &[0, 1, 4, 5]).unwrap();
    let k = b.build(&BuildOptions::default()).unwrap().0;
    let e = off::write(&mut Vec::new(), &k).unwrap_err();
    assert!(e.to_string().contains("3-simplex"), "{e}");
    let e = off::write_simplices(&mut Vec::new(), &k).unwrap_err();
    assert!(e.to_string().contains("is a quad"), "{e}");
}

#[test]
fn big_polygons_are_fan_triangulated_with_a_note() {
    let text = "OFF\n6 1 0\n0 0 0\n1 0 0\n2 1 0\n1 2 0\n0 2 0\n-1 1 0\n6 0 1 2 3 4 5\n";
    let r = off::read_from(text.as_bytes(), "m.off".as_ref(), &ReadOptions::default()).unwrap();
    let cells: Vec<Vec<u32>> = r.complex.cells().map(|c| c.vertices.to_vec()).collect();
    assert_eq!(
        cells,
        vec![vec![0, 1, 2], vec![0, 2, 3], vec![0, 3, 4], vec![0, 4, 5]]
    );
    assert_eq!(
        r.notes,
        vec!["fan-triangulated 1 polygons with more than 4 vertices into 4 triangles".to_string()]
    );
    assert_eq!(r.format, Format::Off);
}

/// An OFF file whose header face count disagrees with its face lines (CGAL's `prim.off` says 7
/// and has 8): refused by default (`CountMismatch`, the line, the lenient option named); read with
/// `lenient` (every face line present, a note naming the header line and both counts).
#[test]
fn lenient_reads_a_header_face_count_that_disagrees() {
    const BODY: &str = "OFF\n# a comment\n5 @NF@ 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n2 2 2\n3 0 1 2\n3 0 2 3\n3 2 3 4\n";
    let read = |nf: u64, lenient: bool| {
        let text = BODY.replace("@NF@", &nf.to_string());
        let opts = ReadOptions {
            lenient,
            ..Default::default()
        };
        off::read_from(text.as_bytes(), "h.off".as_ref(), &opts)
    };
    // the header agrees: the same complex and no note either way
    let exact = read(3, false).unwrap();
    assert!(exact.notes.is_empty());
    let exact_lenient = read(3, true).unwrap();
    assert_eq!(exact_lenient.complex, exact.complex);
    assert!(exact_lenient.notes.is_empty(), "{:?}", exact_lenient.notes);
    for nf in [0u64, 1, 2, 4, 5, 1000] {
        let e = read(nf, false).unwrap_err().to_string();
        assert!(e.contains("lenient option"), "{nf}: {e}");
        if nf < 3 {
            // the first face line past the count is named
            let line = 9 + nf;
            assert!(
                e.starts_with(&format!(
                    "h.off:{line}: unexpected content after the {nf} faces"
                )),
                "{nf}: {e}"
            );
        } else {
            // the end of the file (line 12) is named, and the header line with the count
            assert!(
                e.starts_with("h.off:12: unexpected end of file: expected face 3 of the"),
                "{nf}: {e}"
            );
            assert!(e.contains("the header (line 3)"), "{nf}: {e}");
        }
        let r = read(nf, true).unwrap();
        assert_eq!(r.complex, exact.complex, "{nf}");
        assert_eq!(
            r.notes,
            [format!(
                "the header (line 3) announces {nf} faces but the file has 3: read the 3 face lines present (lenient option)"
            )]
        );
    }
    // lenient reads the extra lines as faces: a line that is no face is still an error at its line
    let bad = BODY.replace("@NF@", "2") + "x y z\n";
    let opts = ReadOptions {
        lenient: true,
        ..Default::default()
    };
    let e = off::read_from(bad.as_bytes(), "h.off".as_ref(), &opts).unwrap_err();
    assert!(e.to_string().starts_with("h.off:12:"), "{e}");
    // an announced count that is too large in a file with no face lines at all
    let none = "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n";
    let r = off::read_from(none.as_bytes(), "h.off".as_ref(), &opts).unwrap();
    assert_eq!((r.complex.n_vertices(), r.complex.n_cells()), (3, 0));
    assert!(
        r.notes[0].contains("announces 2 faces but the file has 0"),
        "{:?}",
        r.notes
    );
}

/// CGAL's `meshes/prim.off` (header: 7 faces; the file: 8) reads with `lenient` only.
#[test]
fn lenient_reads_cgal_prim_off() {
    let Some(d) = std::env::var_os("STARPLEX_DATA") else {
        println!("SKIPPED: STARPLEX_DATA not set");
        return;
    };
    let p = Path::new(&d).join("cgal/data/meshes/prim.off");
    if !p.exists() {
        println!("SKIPPED: {} not present", p.display());
        return;
    }
    let e = io::read(&p, &ReadOptions::default())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("unexpected content after the 7 faces") && e.contains("lenient option"),
        "{e}"
    );
    let opts = ReadOptions {
        lenient: true,
        ..Default::default()
    };
    let r = io::read(&p, &opts).unwrap();
    assert_eq!(r.complex.n_cells(), 8);
    assert!(
        r.notes
            .iter()
            .any(|n| n.contains("announces 7 faces but the file has 8")),
        "{:?}",
        r.notes
    );
}

/// Fuzz regression (`off` target, crash-48e956de): when every coloured face is a dropped
/// one-vertex face, no colour column of zero items is left behind (it made the round trip
/// through the OFF writer, which writes no column, differ).
#[test]
fn colours_of_dropped_point_faces_leave_no_empty_column() {
    let text = "# c\x0bCOO\u{b9}FF\n1 1\n1 0 \t\t0 1 1\n1 0 \t\t0\t\t5\n";
    let r = off::read_from(text.as_bytes(), "c.off".as_ref(), &ReadOptions::default()).unwrap();
    assert_eq!((r.complex.n_vertices(), r.complex.n_cells()), (1, 0));
    assert!(
        r.complex.attributes().cell.is_empty(),
        "{:?}",
        r.complex.attributes()
    );
    let mut out = Vec::new();
    off::write(&mut out, &r.complex).unwrap();
    let back = off::read_from(&out[..], "c.off".as_ref(), &ReadOptions::default()).unwrap();
    assert_eq!(back.complex, r.complex);
}

/// Fuzz regression (`off` target, crash-99f92be5, mode 0xfb): a COFF whose only face (an edge
/// `1 1`) is degenerate and dropped (`drop_degenerate`, `lenient` for the header's 2 faces) leaves
/// no cell colour column of zero items.
#[test]
fn colours_of_dropped_degenerate_faces_leave_no_empty_column() {
    let text: &[u8] = b"# c\nCOFF\n5 2 0\n0 0 0 2 1\n1 0 00 111   1\xff\xff\xff\xff\xff0 \n1  1 0\n2 1 0 111   1\n1 2 040 0\n2 1 01 0";
    let opts = ReadOptions {
        polygons: PolygonMode::Simplices,
        build: BuildOptions {
            drop_duplicates: true,
            drop_degenerate: true,
            ..Default::default()
        },
        lenient: true,
        ..Default::default()
    };
    let r = off::read_from(text, "c.off".as_ref(), &opts).unwrap();
    assert_eq!(r.complex.n_cells(), 0);
    assert!(
        r.complex.attributes().cell.is_empty(),
        "{:?}",
        r.complex.attributes()
    );
    let mut out = Vec::new();
    off::write(&mut out, &r.complex).unwrap();
    let back = off::read_from(&out[..], "c.off".as_ref(), &opts).unwrap();
    assert_eq!(back.complex, r.complex);
}
