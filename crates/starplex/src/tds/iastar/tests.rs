use super::*;
use crate::complex::{BuildOptions, ComplexBuilder};

/// A seeded generator: `next(m)` is in `0..m`.
fn xorshift(seed: u64) -> impl FnMut(u64) -> u64 {
    let mut rng = crate::testkit::XorShift::new(seed);
    move |m| rng.below(m)
}

/// The two builds hold the same structure: references, per-vertex references,
/// non-manifold facets and every top record.
fn assert_same(fast: &IaStar, general: &IaStar, at: &str) {
    assert_eq!(fast.refs(), general.refs(), "{at}");
    assert_eq!(fast.bytes(), general.bytes(), "{at}");
    assert_eq!(fast.vrefs, general.vrefs, "{at}");
    assert_eq!(fast.nm, general.nm, "{at}");
    for (a, b) in fast.blocks.iter().zip(&general.blocks) {
        assert!(a.data == b.data, "{at}");
    }
}

/// The construction for dimension ≤ 3 and the general one give the same structure, on
/// random mixed complexes with non-manifold faces, several blocks per dimension and
/// input orders that are not sorted.
#[test]
fn low_dim_build_equals_general_build() {
    let mut next = xorshift(0x2545_f491_4f6c_dd1d);
    for case in 0..300 {
        let nv = 3 + next(if case < 200 { 8 } else { 40 }) as usize;
        let mut b = ComplexBuilder::new(1).unwrap();
        for _ in 0..nv {
            b.push_vertex(&[0.0]).unwrap();
        }
        let nc = 1 + next(if case < 200 { 12 } else { 120 });
        for _ in 0..nc {
            let len = (1 + next(4) as usize).min(nv);
            let mut c: Vec<u32> = Vec::new();
            while c.len() < len {
                let v = next(nv as u64) as u32;
                if !c.contains(&v) {
                    c.push(v);
                }
            }
            b.push_cell(CellKind::Simplex(len as u8 - 1), &c).unwrap();
        }
        let opts = BuildOptions {
            drop_face_cells: true,
            drop_duplicates: true,
            ..Default::default()
        };
        let k = b.build(&opts).unwrap().0;
        let general = IaStar::build(&k, None).unwrap();
        // the default settings, several vertices per coarse bucket, 128-bit words, and
        // links of two words
        // (passes 1 and 2 run in parts only on one-block complexes; passes 3 and 4 run in
        // ranges of buckets on any)
        for (coarse_bits, wide, pack_links, parts) in [
            (10, false, true, 1),
            (2, false, true, 1),
            (1, true, true, 1),
            (10, true, false, 1),
            (2, false, false, 1),
            (10, false, true, 2),
            (1, false, false, 3),
            (2, true, true, 5),
        ] {
            let tu = low_dim::Tuning {
                coarse_bits,
                wide,
                pack_links,
                parts,
            };
            let fast = IaStar::build(&k, Some(tu)).unwrap();
            assert_same(&fast, &general, &format!("case {case}, {tu:?}"));
        }
    }
}

/// Passes 1 and 2 split into parts (run in parallel) give the general path's IA* on random
/// pure triangle and tetrahedral complexes (one block each), whatever the number of parts.
#[test]
fn low_dim_build_in_parts_equals_general_build() {
    let mut next = xorshift(0x1234_5678_9abc_def1);
    for case in 0..120 {
        let d = 2 + next(2) as usize;
        let nv = d + 1 + next(30) as usize;
        let mut b = ComplexBuilder::new(1).unwrap();
        for _ in 0..nv {
            b.push_vertex(&[0.0]).unwrap();
        }
        for _ in 0..1 + next(80) {
            let mut c: Vec<u32> = Vec::new();
            while c.len() < d + 1 {
                let v = next(nv as u64) as u32;
                if !c.contains(&v) {
                    c.push(v);
                }
            }
            b.push_cell(CellKind::Simplex(d as u8), &c).unwrap();
        }
        let opts = BuildOptions {
            drop_duplicates: true,
            ..Default::default()
        };
        let k = b.build(&opts).unwrap().0;
        assert_eq!(k.blocks().len(), 1);
        let general = IaStar::build(&k, None).unwrap();
        for (parts, coarse_bits, wide) in [(2, 10, false), (3, 2, false), (7, 1, true)] {
            let tu = low_dim::Tuning {
                coarse_bits,
                wide,
                parts,
                ..low_dim::Tuning::DEFAULT
            };
            let fast = IaStar::build(&k, Some(tu)).unwrap();
            assert_same(&fast, &general, &format!("case {case}, {tu:?}"));
        }
    }
}

/// A facet word of exactly 64 bits with one vertex per coarse bucket (the shift to the
/// smallest vertex's low bits is then the full word width): a cone over every triangle of
/// 60 vertices (34,220 tetrahedra at the apex, 16-bit places) and 9 isolated vertices
/// (7-bit vertex ids).
#[test]
fn low_dim_build_with_a_full_64_bit_word() {
    let mut b = ComplexBuilder::new(1).unwrap();
    for _ in 0..70 {
        b.push_vertex(&[0.0]).unwrap();
    }
    for x in 1..=60u32 {
        for y in x + 1..=60 {
            for z in y + 1..=60 {
                b.push_cell(CellKind::Simplex(3), &[0, x, y, z]).unwrap();
            }
        }
    }
    let k = b.build(&BuildOptions::default()).unwrap().0;
    let general = IaStar::build(&k, None).unwrap();
    let fast = IaStar::build(&k, Some(low_dim::Tuning::DEFAULT)).unwrap();
    assert_same(&fast, &general, "cone");
    assert!(!fast.nm_faces_of_dim(3).is_empty());
}

/// The same on the medium meshes of `$STARPLEX_DATA` (slow in a debug build:
/// `cargo test --release -- --ignored`).
#[test]
#[ignore]
fn low_dim_build_equals_general_build_on_medium_meshes() {
    let Ok(dir) = std::env::var("STARPLEX_DATA") else {
        return;
    };
    for name in ["tri_armadillo_x16", "tet_armadillo_m"] {
        let p = std::path::Path::new(&dir).join(format!("medium/{name}/{name}.spx"));
        if !p.exists() {
            continue;
        }
        let k = crate::io::read(&p, &Default::default()).unwrap().complex;
        assert!(k.n_cells() > 500_000, "{name}");
        let general = IaStar::build(&k, None).unwrap();
        for (wide, pack_links, parts) in [(false, true, 1), (false, true, 2), (true, false, 3)] {
            let tu = low_dim::Tuning {
                wide,
                pack_links,
                parts,
                ..low_dim::Tuning::DEFAULT
            };
            let fast = IaStar::build(&k, Some(tu)).unwrap();
            assert_same(&fast, &general, name);
        }
    }
}
