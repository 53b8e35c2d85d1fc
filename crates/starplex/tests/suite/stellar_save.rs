//! Save/load round trip of the Stellar tree, and refusal (never a panic) of damaged files.
use starplex::cell::CellKind;
use starplex::complex::{BuildOptions, ComplexBuilder};
use starplex::stellar::{StellarOptions, StellarTree};

#[test]
fn round_trip_and_damaged_files() {
    let mut b = ComplexBuilder::new(3).unwrap();
    for i in 0..200u32 {
        let x = i as f64;
        b.push_vertex(&[x.sin(), (0.3 * x).cos(), (0.7 * x).sin()])
            .unwrap();
    }
    for i in 0..150u32 {
        b.push_cell(CellKind::Simplex(3), &[i, i + 1, i + 2, i + 3])
            .unwrap();
    }
    b.push_cell(CellKind::Hex, &[190, 191, 192, 193, 194, 195, 196, 197])
        .unwrap();
    b.push_cell(CellKind::Simplex(1), &[198, 199]).unwrap();
    let k = b.build(&BuildOptions::default()).unwrap().0;
    let dir = std::env::temp_dir().join(format!("starplex-stellar-save-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for kv in [1u32, 7, 0] {
        let t = StellarTree::build(
            &k,
            &StellarOptions {
                kv: Some(kv),
                ..Default::default()
            },
        )
        .unwrap();
        let p = dir.join(format!("t{kv}.stl"));
        t.save(&p).unwrap();
        let u = StellarTree::load(&p).unwrap();
        assert_eq!(u.vt_all(), t.vt_all());
        assert_eq!(u.vertex_to_input(), t.vertex_to_input());
        assert_eq!(u.cell_to_input(), t.cell_to_input());
        assert_eq!(u.stats(), t.stats());
        assert_eq!(u.validate(), t.validate());
        // without coordinates the tree is no mesh; saved with them, it reads back as the mesh
        assert!(u.to_complex().is_err());
        let pc = dir.join(format!("c{kv}.stl"));
        t.save_with_coords(&pc, k.coords()).unwrap();
        let uc = StellarTree::load(&pc).unwrap();
        assert_eq!(uc.to_complex().unwrap(), k);
        assert_eq!(uc.vt_all(), t.vt_all());
        uc.save(&p).unwrap(); // re-saved, still with them
        assert_eq!(std::fs::read(&p).unwrap(), std::fs::read(&pc).unwrap());
        t.save(&p).unwrap();
        if kv != 7 {
            continue;
        }
        let bytes = std::fs::read(&pc).unwrap();
        let bad = dir.join("bad.stl");
        for cut in (0..bytes.len()).step_by(31) {
            std::fs::write(&bad, &bytes[..cut]).unwrap();
            assert!(StellarTree::load(&bad).is_err(), "cut at {cut}");
        }
        for i in (0..bytes.len()).step_by(11) {
            let mut b2 = bytes.clone();
            b2[i] ^= 0xA5;
            std::fs::write(&bad, &b2).unwrap();
            if let Ok(t2) = StellarTree::load(&bad) {
                let _ = t2.to_complex();
            }
        }
        // every truncation and a sweep of single-byte corruptions: an error or a tree, no panic
        let bytes = std::fs::read(&p).unwrap();
        let bad = dir.join("bad.stl");
        for cut in (0..bytes.len()).step_by(29) {
            std::fs::write(&bad, &bytes[..cut]).unwrap();
            assert!(StellarTree::load(&bad).is_err(), "cut at {cut}");
        }
        for i in (0..bytes.len()).step_by(13) {
            let mut b2 = bytes.clone();
            b2[i] ^= 0xA5;
            std::fs::write(&bad, &b2).unwrap();
            if let Ok(t2) = StellarTree::load(&bad) {
                // a tree that passed the checks must still answer without panicking
                let _ = t2.vt_all();
                let _ = t2.validate();
            }
        }
    }
    assert!(StellarTree::load(&dir.join("missing.stl")).is_err());
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_saved_cell_that_repeats_a_vertex_is_refused() {
    // found by the `tree` fuzz target: a tetrahedron listing a vertex twice passed the loader's
    // range checks, and validation then looked for a fourth vertex that was not there
    let p = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/stellar/repeated_vertex.tree");
    let e = StellarTree::load(&p).unwrap_err();
    assert!(e.to_string().contains("repeats a vertex"), "{e}");
    let e = starplex::io::read(&p, &Default::default()).unwrap_err();
    assert!(e.to_string().contains("repeats a vertex"), "{e}");
}
