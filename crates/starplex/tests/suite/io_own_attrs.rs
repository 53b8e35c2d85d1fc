//! Attributes in starplex's own formats (issue 11, "Attributes travel"): `.spx` version 2 and
//! `.spb` version 2 round trips (int and float, vertex and cell, several components, NaN, -0.0,
//! infinities, extreme integers, odd names), version-1 files still read, the reader's drops
//! carrying the attributes along, corrupted attribute tables giving typed errors at a byte
//! offset, a seeded loop over random attribute sets; and the gmsh 2.2 binary writer.
use std::path::{Path, PathBuf};

use starplex::attr::{AttrTarget, AttrValues, Attribute, Attributes};
use starplex::buf::Buf;
use starplex::cell::CellKind;
use starplex::complex::{BuildOptions, IndexedComplex};
use starplex::io::{self, binary, gmsh, spx, Format, IoError, Location, ReadOptions};
use starplex::testkit::XorShift;

fn tmp(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("starplex-own-attrs-{}-{name}", std::process::id()))
}

/// Two tets sharing a face, a triangle and an edge hanging off them.
fn mixed(vertex: Vec<Attribute>, cell: Vec<Attribute>) -> IndexedComplex {
    let coords = vec![
        0., 0., 0., 1., 0., 0., 0., 1., 0., 0., 0., 1., 1., 1., 1., 2., 0., 0., 3., 3., 3.,
    ];
    let blocks = vec![
        (
            CellKind::Simplex(3),
            Buf::from(vec![0, 1, 2, 3, 1, 2, 3, 4]),
        ),
        (CellKind::Simplex(2), Buf::from(vec![0, 1, 5])),
        (CellKind::Simplex(1), Buf::from(vec![4, 6])),
    ];
    let mut k = IndexedComplex::from_parts(3, coords.into(), blocks).unwrap();
    k.set_attributes(Attributes { vertex, cell }).unwrap();
    k
}

fn rich() -> IndexedComplex {
    mixed(
        vec![
            Attribute::float(
                "velocity",
                3,
                (0..21)
                    .map(|i| match i {
                        0 => f64::NAN,
                        1 => -0.0,
                        2 => f64::INFINITY,
                        3 => f64::NEG_INFINITY,
                        4 => 1e-300,
                        5 => f64::MIN_POSITIVE / 4.0, // subnormal
                        6 => 0.1,
                        _ => i as f64 * 1.5 - 7.0,
                    })
                    .collect(),
            ),
            Attribute::int("", 1, vec![i64::MIN, i64::MAX, 0, -1, 1, 7, 8]),
        ],
        vec![
            Attribute::int("gmsh:physical", 1, vec![10, 10, 20, 30]),
            Attribute::int(
                "a name # with % odd\tbytes é",
                2,
                vec![1, 2, 3, 4, 5, 6, 7, 8],
            ),
            Attribute::float(
                "stress",
                2,
                vec![0.5, -1.0, 1e300, 2.0, 3.25, -0.0, 7.0, 8.0],
            ),
        ],
    )
}

/// Equal complexes, attribute values compared bit for bit (NaN equal to NaN).
fn assert_same(a: &IndexedComplex, b: &IndexedComplex) {
    assert_eq!(a.ambient_dim(), b.ambient_dim());
    assert_eq!(a.coords(), b.coords());
    assert_eq!(a.blocks().len(), b.blocks().len());
    for (x, y) in a.blocks().iter().zip(b.blocks()) {
        assert_eq!((x.kind, &x.vertices[..]), (y.kind, &y.vertices[..]));
    }
    assert_same_attrs(a.attributes(), b.attributes());
}

fn assert_same_attrs(a: &Attributes, b: &Attributes) {
    for (x, y) in [(&a.vertex, &b.vertex), (&a.cell, &b.cell)] {
        assert_eq!(x.len(), y.len());
        for (p, q) in x.iter().zip(y.iter()) {
            assert_eq!((&p.name, p.components), (&q.name, q.components));
            match (&p.values, &q.values) {
                (AttrValues::Int(u), AttrValues::Int(v)) => assert_eq!(u, v, "{}", p.name),
                (AttrValues::Float(u), AttrValues::Float(v)) => {
                    let bits = |w: &[f64]| w.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                    assert_eq!(bits(u), bits(v), "{}", p.name);
                }
                _ => panic!("{}: type changed", p.name),
            }
        }
    }
}

fn spx_round_trip(k: &IndexedComplex) -> IndexedComplex {
    let mut out = Vec::new();
    spx::write(&mut out, k).unwrap();
    spx::read_from(&out[..], "t.spx".as_ref(), &ReadOptions::default())
        .unwrap_or_else(|e| panic!("{e}\n{}", String::from_utf8_lossy(&out)))
        .complex
}

fn spb_round_trip(k: &IndexedComplex, name: &str) -> IndexedComplex {
    let p = tmp(name);
    io::write(&p, k, Some(Format::Binary)).unwrap();
    let back = io::read(&p, &ReadOptions::default()).unwrap().complex;
    std::fs::remove_file(&p).ok();
    back
}

#[test]
fn spx_round_trips_every_kind_of_attribute() {
    let k = rich();
    let mut out = Vec::new();
    spx::write(&mut out, &k).unwrap();
    let text = String::from_utf8(out).unwrap();
    assert!(text.starts_with("SPX 2\n"), "{text}");
    assert!(
        text.contains("attribute vertex float 3 velocity\nNaN -0.0 inf\n"),
        "{text}"
    );
    assert!(
        text.contains("attribute vertex int 1 %\n-9223372036854775808\n"),
        "{text}"
    );
    assert!(
        text.contains("attribute cell int 2 a%20name%20%23%20with%20%25%20odd%09bytes%20%C3%A9\n")
    );
    assert_same(&spx_round_trip(&k), &k);
    // no attributes: version 1, as before
    let mut plain = k.clone();
    plain.take_attributes();
    let mut out = Vec::new();
    spx::write(&mut out, &plain).unwrap();
    assert!(out.starts_with(b"SPX 1\n"));
    assert_eq!(spx_round_trip(&plain), plain);
}

#[test]
fn spb_round_trips_every_kind_of_attribute() {
    let k = rich();
    let back = spb_round_trip(&k, "rich.spb");
    assert_same(&back, &k);
    assert!(back.coords_buf().is_mapped(), "the arrays stay mapped");
    let mut bytes = Vec::new();
    binary::write(&mut bytes, &k).unwrap();
    let h = binary::read_header(&bytes, "r.spb".as_ref()).unwrap();
    assert_eq!(h.version, 2);
    assert_eq!(h.attrs.len(), 5);
    assert_eq!(bytes.len() % 8, 0);
    for a in &h.attrs {
        assert_eq!(a.offset % 8, 0);
    }
    // the attribute arrays come after the cell arrays
    let last_block = h.blocks.iter().map(|b| b.2).max().unwrap();
    assert!(h.attrs.iter().all(|a| a.offset > last_block));
    assert!(h.coords_offset < last_block);
}

#[test]
fn files_without_attributes_are_version_1_and_byte_identical_to_before() {
    let mut k = rich();
    k.take_attributes();
    let mut bytes = Vec::new();
    binary::write(&mut bytes, &k).unwrap();
    assert_eq!(u32::from_le_bytes(bytes[8..12].try_into().unwrap()), 1);
    let h = binary::read_header(&bytes, "p.spb".as_ref()).unwrap();
    assert_eq!((h.version, h.attrs.len()), (1, 0));
    // the layout of version 1: the coordinates right after the block table
    assert_eq!(h.coords_offset, 64 + 3 * 32);
    assert_eq!(spb_round_trip(&k, "plain.spb"), k);
}

#[test]
fn old_files_still_read() {
    // a version-1 .spb written before attributes existed (the fuzz seed)
    let seed = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fuzz/seeds/spb/cube.spb");
    let bytes = std::fs::read(&seed).unwrap();
    assert_eq!(u32::from_le_bytes(bytes[8..12].try_into().unwrap()), 1);
    let r = io::read(&seed, &ReadOptions::default()).unwrap();
    assert!(r.complex.n_cells() > 0 && r.complex.attributes().is_empty());
    // and writing it back gives the same bytes
    let mut out = Vec::new();
    binary::write(&mut out, &r.complex).unwrap();
    assert_eq!(out, bytes);
    // a version-1 .spx
    let text = "SPX 1\n2 3 1\n0 0\n1 0\n0 1\ntri 3 0 1 2\n";
    let r = spx::read_from(text.as_bytes(), "o.spx".as_ref(), &ReadOptions::default()).unwrap();
    assert!(r.complex.attributes().is_empty());
    // attribute sections need version 2
    let v1 = format!("{text}attribute cell int 1 t\n5\n");
    let e = spx::read_from(v1.as_bytes(), "o.spx".as_ref(), &ReadOptions::default()).unwrap_err();
    assert!(e.to_string().contains("SPX 2"), "{e}");
    let v2 = v1.replacen("SPX 1", "SPX 2", 1);
    let r = spx::read_from(v2.as_bytes(), "o.spx".as_ref(), &ReadOptions::default()).unwrap();
    assert_eq!(
        r.complex.attributes().cell[0],
        Attribute::int("t", 1, vec![5])
    );
    // version 2 without sections is fine too
    let v2 = text.replacen("SPX 1", "SPX 2", 1);
    assert!(spx::read_from(v2.as_bytes(), "o.spx".as_ref(), &ReadOptions::default()).is_ok());
}

#[test]
fn spx_reader_drops_carry_the_attributes() {
    // cell 1 repeats cell 0, cell 2 is a face of cell 0: both dropped, their values too
    let text =
        "SPX 2\n2 4 4\n0 0\n1 0\n0 1\n1 1\ntri 3 0 1 2\ntri 3 2 1 0\nline 2 0 1\ntri 3 1 3 2\n\
                attribute cell int 2 tag\n0 100\n1 101\n2 102\n3 103\n\
                attribute vertex float 1 h\n0.5\n1.5\n2.5\n3.5\n";
    let opts = ReadOptions {
        build: BuildOptions {
            drop_duplicates: true,
            drop_face_cells: true,
            ..Default::default()
        },
        ..Default::default()
    };
    let r = spx::read_from(text.as_bytes(), "d.spx".as_ref(), &opts).unwrap();
    let k = r.complex;
    assert_eq!(k.n_cells(), 2);
    assert_eq!(
        k.attributes().cell[0],
        Attribute::int("tag", 2, vec![0, 100, 3, 103])
    );
    assert_eq!(
        k.attributes().vertex[0].values,
        AttrValues::Float(vec![0.5, 1.5, 2.5, 3.5])
    );
    // and what was read writes and reads back (spx and spb)
    assert_same(&spx_round_trip(&k), &k);
    assert_same(&spb_round_trip(&k, "dropped.spb"), &k);
}

#[test]
fn spx_attribute_errors_name_the_line() {
    let head = "SPX 2\n1 2 1\n0\n1\nline 2 0 1\n";
    for (tail, want_line, want) in [
        (
            "attribute edge int 1 t\n5\n",
            6,
            "neither 'vertex' nor 'cell'",
        ),
        (
            "attribute cell str 1 t\n5\n",
            6,
            "neither 'int' nor 'float'",
        ),
        ("attribute cell int 0 t\n", 6, "0 components"),
        ("attribute cell int 1 t%4\n5\n", 6, "two hex digits"),
        ("attribute cell int 1 t\n5.5\n", 7, "expected an integer"),
        ("attribute cell int 2 t\n5\n", 7, "expected component 1"),
        ("attribute cell float 1 t\nabc\n", 7, "expected a number"),
        (
            "attribute vertex float 1 t\n1\n",
            8,
            "unexpected end of file",
        ),
        (
            "attribute cell int 1 t\n5\n6\n",
            8,
            "expected an attribute section",
        ),
        (
            "attribute cell int 1 t\n5\nattribute cell int 1 t\n6\n",
            8,
            "two cell attributes",
        ),
    ] {
        let text = format!("{head}{tail}");
        let e = spx::read_from(text.as_bytes(), "e.spx".as_ref(), &ReadOptions::default())
            .expect_err(tail);
        assert_eq!(e.location, Some(Location::Line(want_line)), "{tail}: {e}");
        assert!(e.to_string().contains(want), "{tail}: {e}");
    }
}

fn fnv1a(chunks: &[&[u8]]) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for c in chunks {
        for &b in *c {
            h ^= b as u64;
            h = h.wrapping_mul(0x0000_0100_0000_01b3);
        }
    }
    h
}

/// `bytes` with `patch` applied at `at` and the header checksum recomputed over the header,
/// block table and attribute table (as the writer does), so the field checks themselves run.
fn patched(bytes: &[u8], at: usize, patch: &[u8]) -> Vec<u8> {
    let mut b = bytes.to_vec();
    b[at..at + patch.len()].copy_from_slice(patch);
    // the table's place in the unpatched file
    let nb = u32::from_le_bytes(bytes[20..24].try_into().unwrap()) as usize;
    let t = 64 + 32 * nb;
    let entries = (u64::from_le_bytes(b[t + 8..t + 16].try_into().unwrap()) as usize).min(b.len());
    let end = (t + 16 + entries).min(b.len());
    let sum = fnv1a(&[&b[..56], &b[64..end]]);
    b[56..64].copy_from_slice(&sum.to_le_bytes());
    b
}

fn read_bytes(bytes: &[u8], name: &str) -> Result<IndexedComplex, IoError> {
    let p = tmp(name);
    std::fs::write(&p, bytes).unwrap();
    let r = binary::read(&p, &ReadOptions::default()).map(|r| r.complex);
    std::fs::remove_file(&p).ok();
    r
}

#[test]
fn corrupted_attribute_tables_give_typed_errors_with_the_byte() {
    let k = rich();
    let mut bytes = Vec::new();
    binary::write(&mut bytes, &k).unwrap();
    let t = 64 + 3 * 32; // the attribute table head
    let e0 = t + 16; // the first entry
    let byte_err = |b: &[u8], want: &str, at: usize| {
        let e = read_bytes(b, "bad.spb").expect_err(want);
        assert!(
            matches!(
                e.kind,
                io::IoErrorKind::Parse(_) | io::IoErrorKind::Complex(_)
            ),
            "{e}"
        );
        assert_eq!(e.location, Some(Location::Byte(at as u64)), "{want}: {e}");
        assert!(e.to_string().contains(want), "{want}: {e}");
    };
    byte_err(&patched(&bytes, t + 4, &[1]), "reserved field", t + 4);
    byte_err(&patched(&bytes, t + 8, &[3]), "not a multiple of 8", t + 8);
    byte_err(
        &patched(&bytes, t + 8, &u64::MAX.to_le_bytes()[..7]),
        "not a multiple of 8",
        t + 8,
    );
    byte_err(
        &patched(&bytes, t + 8, &(1u64 << 40).to_le_bytes()),
        "passes the end",
        t + 8,
    );
    byte_err(
        &patched(&bytes, t, &u32::MAX.to_le_bytes()),
        "4294967295 attributes need",
        t,
    );
    byte_err(
        &patched(&bytes, t, &4u32.to_le_bytes()),
        "bytes after its 4 entries",
        e0 + 152,
    );
    byte_err(&patched(&bytes, e0, &[7]), "unknown target code 7", e0);
    byte_err(
        &patched(&bytes, e0 + 1, &[2]),
        "unknown value type code 2",
        e0 + 1,
    );
    byte_err(&patched(&bytes, e0 + 2, &[1]), "reserved field", e0 + 2);
    byte_err(
        &patched(&bytes, e0 + 4, &u32::MAX.to_le_bytes()),
        "passes the end of the attribute table",
        e0 + 4,
    );
    byte_err(
        &patched(&bytes, e0 + 8, &0u64.to_le_bytes()),
        "0 components",
        e0 + 8,
    );
    byte_err(
        &patched(&bytes, e0 + 8, &(1u64 << 60).to_le_bytes()),
        "past the end",
        e0 + 8,
    );
    byte_err(
        &patched(&bytes, e0 + 16, &u64::MAX.to_le_bytes()),
        "past the end",
        e0 + 8,
    );
    byte_err(
        &patched(&bytes, e0 + 16, &8u64.to_le_bytes()),
        "values at offset 8",
        t + 16,
    );
    byte_err(&patched(&bytes, e0 + 24, &[0xff]), "not UTF-8", e0 + 24);
    // the second entry ("", 1 component) renamed "velocity": a duplicate
    let e1 = e0 + 24 + 8;
    let dup = patched(
        &patched(&bytes, e1 + 4, &8u32.to_le_bytes()),
        e1 + 24,
        b"velocity",
    );
    // (the longer name shifts the next entries: an error at a byte, whichever field it hits)
    let shifted = read_bytes(&dup, "dup.spb").unwrap_err();
    assert!(
        matches!(shifted.location, Some(Location::Byte(_))),
        "{shifted}"
    );
    // a changed table without the checksum recomputed
    let mut b = bytes.clone();
    b[e0 + 24] ^= 1;
    byte_err(&b, "checksum mismatch", 56);
    // flipping a table byte to a type change: int <-> float, with checksum: still reads (same bits)
    let flip = patched(&bytes, e0 + 1, &[0]);
    let back = read_bytes(&flip, "flip.spb").unwrap();
    assert!(matches!(
        back.attributes().vertex[0].values,
        AttrValues::Int(_)
    ));
    // every truncation and every single-byte change of the metadata: an error or a complex,
    // never a panic
    for n in 0..bytes.len() {
        assert!(read_bytes(&bytes[..n], "cut.spb").is_err(), "{n}");
    }
    let meta_end = e0 + 200;
    for at in 8..meta_end {
        for v in [0u8, 1, 0x80, 0xff] {
            let _ = read_bytes(&patched(&bytes, at, &[v]), "flip.spb");
            let mut raw = bytes.clone();
            raw[at] = v;
            let _ = binary::read_header(&raw, "x.spb".as_ref());
        }
    }
}

#[test]
fn duplicate_names_in_a_spb_are_refused_at_the_table() {
    // write a complex with two distinct names of the same length, rename the second by patching
    let k = mixed(
        vec![],
        vec![
            Attribute::int("aa", 1, vec![1, 2, 3, 4]),
            Attribute::int("ab", 1, vec![5, 6, 7, 8]),
        ],
    );
    let mut bytes = Vec::new();
    binary::write(&mut bytes, &k).unwrap();
    let t = 64 + 3 * 32;
    let e1 = t + 16 + 24 + 8;
    let b = patched(&bytes, e1 + 24 + 1, b"a");
    let e = read_bytes(&b, "dup.spb").unwrap_err();
    assert_eq!(e.location, Some(Location::Byte(t as u64)), "{e}");
    assert!(
        e.to_string().contains("two cell attributes are named 'aa'"),
        "{e}"
    );
}

/// A random complex: `nv` points in 2D, random triangles (duplicates dropped by the builder).
fn random_attrs(rng: &mut XorShift, nv: usize, nc: usize) -> Attributes {
    let mut a = Attributes::default();
    for (target, n) in [(AttrTarget::Vertex, nv), (AttrTarget::Cell, nc)] {
        for j in 0..rng.below(4) {
            let comps = 1 + rng.below(4) as usize;
            let len = n * comps;
            let name: String = (0..rng.below(6))
                .map(|_| [b'a', b' ', b'#', b'%', b'z', b':'][rng.below(6) as usize] as char)
                .collect::<String>()
                + &j.to_string();
            let col = if rng.below(2) == 0 {
                Attribute::int(
                    name,
                    comps,
                    (0..len)
                        .map(|_| rng.next_u64() as i64 >> rng.below(64))
                        .collect(),
                )
            } else {
                Attribute::float(
                    name,
                    comps,
                    (0..len)
                        .map(|_| match rng.below(8) {
                            0 => f64::from_bits(rng.next_u64()), // any bits, NaN included
                            1 => f64::NAN,
                            _ => (rng.next_u64() as i64 as f64) * 1e-10,
                        })
                        .collect(),
                )
            };
            match target {
                AttrTarget::Vertex => a.vertex.push(col),
                AttrTarget::Cell => a.cell.push(col),
            }
        }
    }
    a
}

#[test]
fn seeded_random_attribute_sets_round_trip_through_spx_and_spb() {
    let mut rng = XorShift::new(0x5eed_a77e);
    for round in 0..60 {
        let nv = 3 + rng.below(12) as usize;
        let coords: Vec<f64> = (0..nv * 2)
            .map(|i| (i * 7 % 11) as f64 + i as f64)
            .collect();
        // a fan of distinct triangles around vertex 0
        let nc = 1 + rng.below(nv as u64 - 2) as usize;
        let tris: Vec<u32> = (0..nc)
            .flat_map(|i| [0, i as u32 + 1, i as u32 + 2])
            .collect();
        let mut k =
            IndexedComplex::from_parts(2, coords.into(), vec![(CellKind::Simplex(2), tris.into())])
                .unwrap();
        k.set_attributes(random_attrs(&mut rng, nv, nc)).unwrap();
        assert_same(&spx_round_trip(&k), &k);
        let back = spb_round_trip(&k, &format!("rand{round}.spb"));
        assert_same(&back, &k);
        // a .spb written from what was read is the same bytes
        let (mut x, mut y) = (Vec::new(), Vec::new());
        binary::write(&mut x, &k).unwrap();
        binary::write(&mut y, &back).unwrap();
        assert_eq!(x, y, "round {round}");
    }
}

#[test]
fn own_formats_drop_nothing() {
    let k = rich();
    for f in [Format::Spx, Format::Binary] {
        assert!(f.dropped_attributes(k.attributes()).is_empty(), "{f}");
    }
}

fn msh(bytes: &[u8]) -> IndexedComplex {
    gmsh::read_from(bytes, "t.msh".as_ref(), &ReadOptions::default())
        .unwrap_or_else(|e| panic!("{e}"))
        .complex
}

#[test]
fn gmsh_22_binary_reads_back_as_the_ascii_one() {
    let mut k = rich();
    let mut a = k.take_attributes();
    a.cell
        .push(Attribute::int("gmsh:geometrical", 1, vec![1, 2, 3, 4]));
    a.cell[0] = Attribute::int(
        "gmsh:physical",
        1,
        vec![10, -10, i32::MAX as i64, i32::MIN as i64],
    );
    a.vertex.retain(|c| !c.name.is_empty()); // gmsh data is double: no i64::MIN
    k.set_attributes(a).unwrap();
    let (mut asc, mut bin) = (Vec::new(), Vec::new());
    gmsh::write_22(&mut asc, &k).unwrap();
    gmsh::write_22_binary(&mut bin, &k).unwrap();
    assert!(bin.starts_with(b"$MeshFormat\n2.2 1 8\n\x01\0\0\0\n$EndMeshFormat\n"));
    let (x, y) = (msh(&asc), msh(&bin));
    // the ascii writer prints -0.0 as 0: compare values with == (NaN equal to NaN)
    assert_eq!(y.coords(), x.coords());
    assert_eq!(y.blocks(), x.blocks());
    for (p, q) in [
        (&y.attributes().vertex, &x.attributes().vertex),
        (&y.attributes().cell, &x.attributes().cell),
    ] {
        assert_eq!(p.len(), q.len());
        for (c, d) in p.iter().zip(q.iter()) {
            assert_eq!(
                (&c.name, c.components, c.values.len()),
                (&d.name, d.components, d.values.len())
            );
            for i in 0..c.values.len() {
                let (u, v) = (c.values.get_f64(i), d.values.get_f64(i));
                assert!(
                    u == v || (u.is_nan() && v.is_nan()),
                    "{} {i}: {u} {v}",
                    c.name
                );
            }
        }
    }
    // the binary one keeps every bit of the float data
    let vel = |c: &IndexedComplex| match &c
        .attributes()
        .get(AttrTarget::Vertex, "velocity")
        .unwrap()
        .values
    {
        AttrValues::Float(v) => v.iter().map(|x| x.to_bits()).collect::<Vec<_>>(),
        AttrValues::Int(_) => panic!("float data"),
    };
    assert_eq!(vel(&y), vel(&k));
    assert_eq!(y.coords(), k.coords());
    let tags = |c: &IndexedComplex, n: &str| c.attributes().get(AttrTarget::Cell, n).cloned();
    assert_eq!(tags(&y, "gmsh:physical"), tags(&k, "gmsh:physical"));
    assert_eq!(tags(&y, "gmsh:geometrical"), tags(&k, "gmsh:geometrical"));
    // prisms, quads, hexes, a point element and 2D points, without tags: default tags
    let coords: Vec<f64> = (0..17).flat_map(|i| [i as f64, (i * i) as f64]).collect();
    let blocks = vec![
        (CellKind::Prism, Buf::from(vec![0, 1, 2, 3, 4, 5])),
        (CellKind::Quad, Buf::from(vec![14, 15, 1, 0])),
        (CellKind::Hex, Buf::from((6..14).collect::<Vec<u32>>())),
        (CellKind::Simplex(0), Buf::from(vec![16])),
    ];
    let m = IndexedComplex::from_parts(2, coords.into(), blocks).unwrap();
    let (mut asc, mut bin) = (Vec::new(), Vec::new());
    gmsh::write_22(&mut asc, &m).unwrap();
    gmsh::write_22_binary(&mut bin, &m).unwrap();
    let (xm, ym) = (msh(&asc), msh(&bin));
    assert_eq!(xm, ym);
    let mut plain = ym.clone();
    plain.take_attributes();
    // the reader drops gmsh point elements (type 15), as for every gmsh file
    assert_eq!(plain.n_cells(), m.n_cells() - 1);
    for (p, q) in plain.blocks().iter().zip(m.blocks()) {
        assert_eq!((p.kind, &p.vertices[..]), (q.kind, &q.vertices[..]));
    }
    // through io::write and the format name
    assert_eq!(
        Format::from_name("msh22-binary"),
        Some(Format::Gmsh22Binary)
    );
    let p = tmp("b22.msh");
    io::write(&p, &k, Some(Format::Gmsh22Binary)).unwrap();
    let r = io::read(&p, &ReadOptions::default()).unwrap();
    std::fs::remove_file(&p).ok();
    assert_same(&r.complex, &y);
    // tags beyond an int are not held (and named as dropped)
    let mut big = k.clone();
    let mut a = big.take_attributes();
    a.cell[0] = Attribute::int("gmsh:physical", 1, vec![1 << 40, 0, 0, 0]);
    big.set_attributes(a).unwrap();
    assert_eq!(
        Format::Gmsh22Binary.dropped_attributes(big.attributes()),
        ["cell gmsh:physical"]
    );
    assert!(Format::Gmsh22
        .dropped_attributes(big.attributes())
        .is_empty());
}

/// The fuzz seed of the version-2 layout (`fuzz/seeds/spb/attrs.spb`) is what the writer writes
/// for [`rich`]; `STARPLEX_WRITE_SEEDS=1` rewrites it.
#[test]
fn fuzz_seed_of_the_attribute_layout_is_current() {
    let mut bytes = Vec::new();
    binary::write(&mut bytes, &rich()).unwrap();
    let seed = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fuzz/seeds/spb/attrs.spb");
    if std::env::var_os("STARPLEX_WRITE_SEEDS").is_some() {
        std::fs::write(&seed, &bytes).unwrap();
    }
    assert_eq!(
        std::fs::read(&seed).unwrap(),
        bytes,
        "rerun with STARPLEX_WRITE_SEEDS=1"
    );
    assert!(
        bytes.len() <= 4096,
        "scripts/fuzz.sh runs with -max_len=4096"
    );
}
