//! Attributes follow the Stellar tree's renumbering and are saved and loaded with it (issue 11,
//! "Attributes travel"): tree order matches the permutations, a saved tree loads the same
//! attributes, the input order comes back, trees without attributes are saved as version 1, and
//! a truncated or corrupted attribute section is an error (never a panic).
use starplex::attr::{AttrValues, Attribute, Attributes};
use starplex::complex::IndexedComplex;
use starplex::generate::kuhn_grid;
use starplex::stellar::{StellarOptions, StellarTree};
use starplex::testkit::XorShift;

fn tmp(name: &str) -> std::path::PathBuf {
    std::env::temp_dir().join(format!("starplex-tree-attrs-{}-{name}", std::process::id()))
}

fn with_attrs(seed: u64) -> IndexedComplex {
    let mut k = kuhn_grid(&[4, 3, 3]).unwrap();
    let (nv, nc) = (k.n_vertices(), k.n_cells());
    let mut rng = XorShift::new(seed);
    let a = Attributes {
        vertex: vec![
            Attribute::float(
                "T",
                1,
                (0..nv)
                    .map(|i| if i == 3 { f64::NAN } else { i as f64 * 0.25 })
                    .collect(),
            ),
            Attribute::int("id", 2, (0..2 * nv as i64).collect()),
        ],
        cell: vec![
            Attribute::int(
                "gmsh:physical",
                1,
                (0..nc).map(|_| rng.below(5) as i64).collect(),
            ),
            Attribute::float("grad", 3, (0..3 * nc).map(|i| -(i as f64)).collect()),
        ],
    };
    k.set_attributes(a).unwrap();
    k
}

fn bits(a: &Attributes) -> Vec<(String, usize, Vec<u64>)> {
    a.vertex
        .iter()
        .chain(&a.cell)
        .map(|c| {
            let v = match &c.values {
                AttrValues::Int(v) => v.iter().map(|&x| x as u64).collect(),
                AttrValues::Float(v) => v.iter().map(|x| x.to_bits()).collect(),
            };
            (c.name.clone(), c.components, v)
        })
        .collect()
}

#[test]
fn attributes_follow_the_tree_and_are_saved_with_it() {
    let k = with_attrs(7);
    for kv in [1, 3, 16] {
        let t = StellarTree::build(
            &k,
            &StellarOptions {
                kv: Some(kv),
                ..Default::default()
            },
        )
        .unwrap();
        // tree order: item i of a tree column is item vertex_to_input()[i] of the input's
        let ta = t.attributes();
        let id = &ta.vertex[1];
        for (tv, input) in t.vertex_to_input().iter().enumerate() {
            let want = [2 * input.index() as i64, 2 * input.index() as i64 + 1];
            match &id.values {
                AttrValues::Int(v) => assert_eq!(&v[2 * tv..2 * tv + 2], &want),
                AttrValues::Float(_) => panic!(),
            }
        }
        let grad = &ta.cell[1];
        for (tc, input) in t.cell_to_input().iter().enumerate() {
            assert_eq!(
                grad.values.get_f64(3 * tc + 2),
                -((3 * input.index() + 2) as f64)
            );
        }
        assert!(
            t.vertex_to_input()
                .iter()
                .enumerate()
                .any(|(i, v)| v.index() != i)
                || kv == 16
        );
        assert_eq!(bits(&t.input_attributes()), bits(k.attributes()));
        // saved and loaded
        let p = tmp(&format!("kv{kv}.tree"));
        t.save(&p).unwrap();
        let bytes = std::fs::read(&p).unwrap();
        assert_eq!(u64::from_le_bytes(bytes[8..16].try_into().unwrap()), 2);
        let u = StellarTree::load(&p).unwrap();
        assert_eq!(bits(u.attributes()), bits(t.attributes()));
        assert_eq!(bits(&u.input_attributes()), bits(k.attributes()));
        assert_eq!(u.vertex_to_input(), t.vertex_to_input());
        std::fs::remove_file(&p).ok();
    }
}

#[test]
fn trees_without_attributes_are_saved_as_before() {
    let mut k = with_attrs(1);
    k.take_attributes();
    let t = StellarTree::build(
        &k,
        &StellarOptions {
            kv: Some(4),
            ..Default::default()
        },
    )
    .unwrap();
    let p = tmp("plain.tree");
    t.save(&p).unwrap();
    let bytes = std::fs::read(&p).unwrap();
    assert_eq!(u64::from_le_bytes(bytes[8..16].try_into().unwrap()), 1);
    let u = StellarTree::load(&p).unwrap();
    assert!(u.attributes().is_empty());
    // a version-1 file with trailing bytes still loads, as before
    std::fs::remove_file(&p).ok();
}

#[test]
fn truncated_or_corrupted_attribute_sections_are_errors() {
    let k = with_attrs(3);
    let t = StellarTree::build(
        &k,
        &StellarOptions {
            kv: Some(4),
            ..Default::default()
        },
    )
    .unwrap();
    let p = tmp("cut.tree");
    t.save(&p).unwrap();
    let bytes = std::fs::read(&p).unwrap();
    let mut plain = k.clone();
    plain.take_attributes();
    let q = tmp("plain2.tree");
    StellarTree::build(
        &plain,
        &StellarOptions {
            kv: Some(4),
            ..Default::default()
        },
    )
    .unwrap()
    .save(&q)
    .unwrap();
    let section = std::fs::read(&q).unwrap().len(); // where the attribute section starts
    std::fs::remove_file(&q).ok();
    for n in (section..bytes.len()).step_by(7) {
        std::fs::write(&p, &bytes[..n]).unwrap();
        assert!(StellarTree::load(&p).is_err(), "{n}");
    }
    // trailing bytes after the section
    let mut more = bytes.clone();
    more.extend_from_slice(&[0; 8]);
    std::fs::write(&p, &more).unwrap();
    assert!(StellarTree::load(&p)
        .unwrap_err()
        .to_string()
        .contains("after the attribute section"));
    // every word of the first column's head set to huge or odd values
    for at in (section..section + 40).step_by(8) {
        for v in [u64::MAX, 1 << 62, 7, 0] {
            let mut b = bytes.clone();
            b[at..at + 8].copy_from_slice(&v.to_le_bytes());
            std::fs::write(&p, &b).unwrap();
            let _ = StellarTree::load(&p); // Ok or Err, never a panic
        }
    }
    // a count of columns that the file cannot hold
    let mut b = bytes.clone();
    b[section..section + 8].copy_from_slice(&u64::MAX.to_le_bytes());
    std::fs::write(&p, &b).unwrap();
    assert!(StellarTree::load(&p).is_err());
    std::fs::remove_file(&p).ok();
}
