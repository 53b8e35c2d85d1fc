//! The bulk paths of the binary readers (gmsh element blocks decoded in parallel, legacy VTK
//! cell lists checked and compacted at once, `.vtu` index arrays decoded in one loop, runs of
//! one cell type pushed whole) read exactly what the record-by-record text readers read: the
//! same complex and the same attributes, on seeded random meshes of every kind, with tags that
//! vary inside a block (the gmsh 2.2 path then falls back chunk by chunk), element tags that
//! do not follow the usual numbering, degenerate elements and mixed cell sizes. And a problem
//! the bulk path finds is named as the checked path names it: by byte.
use starplex::attr::{AttrTarget, AttrValues, Attribute, Attributes};
use starplex::cell::CellKind;
use starplex::complex::{BuildOptions, ComplexBuilder, IndexedComplex};
use starplex::io::{gmsh, vtk, vtu, Location, ReadOptions, ReadResult};
use starplex::testkit::XorShift;

const KINDS: [CellKind; 7] = [
    CellKind::Simplex(1),
    CellKind::Simplex(2),
    CellKind::Quad,
    CellKind::Simplex(3),
    CellKind::Hex,
    CellKind::Prism,
    CellKind::Pyramid,
];

/// How the gmsh tag columns of [`random_mesh`] vary.
#[derive(Clone, Copy, PartialEq)]
enum Tags {
    Constant,
    /// Both vary inside runs of one kind.
    Varying,
    /// Only the physical tags vary.
    PhysicalVaries,
}

/// A random mesh of `n` cells in runs of one kind (from `kinds`), every vertex used, with the
/// gmsh tag columns.
fn random_mesh(seed: u64, n: usize, kinds: &[CellKind], tags: Tags) -> IndexedComplex {
    let mut r = XorShift::new(seed);
    let pool = (n as u64 * 3).max(16);
    let mut cells: Vec<(CellKind, Vec<u32>)> = Vec::new();
    while cells.len() < n {
        let kind = kinds[r.below(kinds.len() as u64) as usize];
        for _ in 0..1 + r.below(200) {
            let mut v: Vec<u32> = Vec::new();
            while v.len() < kind.n_vertices() {
                let x = r.below(pool) as u32;
                if !v.contains(&x) {
                    v.push(x);
                }
            }
            cells.push((kind, v));
        }
    }
    cells.truncate(n);
    // every vertex used, numbered by first use
    let mut id = vec![u32::MAX; pool as usize];
    let mut next = 0u32;
    for (_, v) in &mut cells {
        for x in v.iter_mut() {
            if id[*x as usize] == u32::MAX {
                id[*x as usize] = next;
                next += 1;
            }
            *x = id[*x as usize];
        }
    }
    let mut b = ComplexBuilder::new(3).unwrap();
    for i in 0..next {
        let p = [
            r.below(1000) as f64 / 7.0,
            r.below(1000) as f64 / 3.0,
            i as f64 * 0.5,
        ];
        b.push_vertex(&p).unwrap();
    }
    for (kind, v) in &cells {
        b.push_cell(*kind, v).unwrap();
    }
    let opts = BuildOptions {
        drop_face_cells: true,
        drop_duplicates: true,
        ..Default::default()
    };
    let (mut k, _) = b.build(&opts).unwrap();
    let m = k.n_cells();
    let tag = |i: usize, period: usize, values: i64, varies: bool| {
        if varies {
            1 + ((i / period) as i64 + i.is_multiple_of(5) as i64) % values
        } else {
            7
        }
    };
    let (p, g) = (tags != Tags::Constant, tags == Tags::Varying);
    let attrs = Attributes {
        vertex: vec![],
        cell: vec![
            Attribute::int(
                "gmsh:physical",
                1,
                (0..m).map(|i| tag(i, 37, 3, p)).collect(),
            ),
            Attribute::int(
                "gmsh:geometrical",
                1,
                (0..m).map(|i| tag(i, 50, 4, g)).collect(),
            ),
        ],
    };
    k.set_attributes(attrs).unwrap();
    k
}

fn write(
    f: fn(&mut dyn std::io::Write, &IndexedComplex) -> Result<(), starplex::io::IoErrorKind>,
    k: &IndexedComplex,
) -> Vec<u8> {
    let mut out = Vec::new();
    f(&mut out, k).unwrap();
    out
}

fn msh(bytes: &[u8]) -> ReadResult {
    gmsh::read_from(bytes, "m.msh".as_ref(), &ReadOptions::default()).unwrap()
}

fn same(a: &ReadResult, b: &ReadResult, what: &str) {
    assert_eq!(a.complex, b.complex, "{what}");
    assert_eq!(a.complex.attributes(), b.complex.attributes(), "{what}");
    assert_eq!(a.notes, b.notes, "{what}");
}

#[test]
fn binary_gmsh_reads_what_ascii_gmsh_reads() {
    for seed in 1..=12u64 {
        let kinds: &[CellKind] = if seed % 4 == 0 { &KINDS[3..4] } else { &KINDS };
        let tags = [Tags::Constant, Tags::Varying, Tags::PhysicalVaries][seed as usize % 3];
        let k = random_mesh(seed, 300 + 700 * seed as usize, kinds, tags);
        let a41 = msh(&write(gmsh::write, &k));
        let b41 = msh(&write(gmsh::write_binary, &k));
        same(&a41, &b41, &format!("4.1, seed {seed}"));
        assert_eq!(a41.complex.n_cells(), k.n_cells());
        let a22 = msh(&write(gmsh::write_22, &k));
        let b22 = msh(&write(gmsh::write_22_binary, &k));
        same(&a22, &b22, &format!("2.2, seed {seed}"));
        // the tags come back, in the order the writer grouped the cells
        let sorted = |a: Option<&Attribute>| match a.map(|a| &a.values) {
            Some(AttrValues::Int(v)) => {
                let mut v = v.clone();
                v.sort_unstable();
                v
            }
            other => panic!("no integer column: {other:?}"),
        };
        let phys = |r: &ReadResult| {
            sorted(
                r.complex
                    .attributes()
                    .get(AttrTarget::Cell, "gmsh:physical"),
            )
        };
        let want = sorted(k.attributes().get(AttrTarget::Cell, "gmsh:physical"));
        assert_eq!(phys(&b41), want, "seed {seed}");
        assert_eq!(phys(&b22), want, "seed {seed}");
    }
}

/// The byte range of each element record of a binary 4.1 file written by starplex (one
/// element block per entity; 8-byte sizes; records of tag + node tags).
fn records_41(b: &[u8]) -> Vec<(usize, usize)> {
    let at = b.windows(10).position(|w| w == b"$Elements\n").unwrap() + 10;
    let u = |i: usize| u64::from_le_bytes(b[i..i + 8].try_into().unwrap()) as usize;
    let n_blocks = u(at);
    let mut p = at + 32;
    let mut out = Vec::new();
    for _ in 0..n_blocks {
        let ty = i32::from_le_bytes(b[p + 8..p + 12].try_into().unwrap());
        let n = u(p + 12);
        p += 20;
        let nodes = gmsh::gmsh_type_nodes(ty as u64).unwrap().1;
        for _ in 0..n {
            out.push((p, (1 + nodes) * 8));
            p += (1 + nodes) * 8;
        }
    }
    out
}

#[test]
fn gmsh_bulk_path_hands_unusual_records_to_the_checked_path() {
    let k = random_mesh(99, 3000, &KINDS[3..4], Tags::Constant);
    let clean = write(gmsh::write_binary, &k);
    let recs = records_41(&clean);
    assert_eq!(recs.len(), 3000);
    let plain = msh(&clean);

    // element tags off the usual numbering from the middle on: the same cells
    let mut b = clean.clone();
    for (i, &(at, _)) in recs.iter().enumerate().skip(1500) {
        b[at..at + 8].copy_from_slice(&(10_000 + 3 * i as u64).to_le_bytes());
    }
    same(&plain, &msh(&b), "renumbered element tags");

    // a repeated node in element 2100: an error naming its record, or dropped on request
    let mut b = clean.clone();
    let (at, _) = recs[2100];
    let first_node: [u8; 8] = b[at + 8..at + 16].try_into().unwrap();
    b[at + 16..at + 24].copy_from_slice(&first_node);
    let e = gmsh::read_from(&b[..], "m.msh".as_ref(), &ReadOptions::default()).unwrap_err();
    assert_eq!(e.location, Some(Location::Byte(at as u64)), "{e}");
    assert!(e.to_string().contains("appears more than once"), "{e}");
    let lax = ReadOptions {
        build: BuildOptions {
            drop_degenerate: true,
            ..Default::default()
        },
        ..Default::default()
    };
    let r = gmsh::read_from(&b[..], "m.msh".as_ref(), &lax).unwrap();
    assert_eq!(r.complex.n_cells(), 2999);

    // a node tag that is no node in element 2999: named by its record
    let mut b = clean.clone();
    let (at, _) = recs[2999];
    b[at + 24..at + 32].copy_from_slice(&987_654_321u64.to_le_bytes());
    let e = gmsh::read_from(&b[..], "m.msh".as_ref(), &ReadOptions::default()).unwrap_err();
    assert_eq!(e.location, Some(Location::Byte(at as u64)), "{e}");
    assert!(e.to_string().contains("node tag 987654321"), "{e}");
}

/// A binary legacy VTK 4.2 file (classic cell lists, big-endian) written here, independently
/// of starplex's writers.
fn legacy_binary(k: &IndexedComplex) -> Vec<u8> {
    let mut b = format!(
        "# vtk DataFile Version 4.2\nfast paths\nBINARY\nDATASET UNSTRUCTURED_GRID\nPOINTS {} double\n",
        k.n_vertices()
    )
    .into_bytes();
    for x in k.coords() {
        b.extend_from_slice(&x.to_be_bytes());
    }
    b.extend_from_slice(
        format!("\nCELLS {} {}\n", k.n_cells(), k.n_cells() + k.n_refs()).as_bytes(),
    );
    for c in k.cells() {
        b.extend_from_slice(&(c.vertices.len() as i32).to_be_bytes());
        for &v in c.vertices {
            b.extend_from_slice(&(v as i32).to_be_bytes());
        }
    }
    b.extend_from_slice(format!("\nCELL_TYPES {}\n", k.n_cells()).as_bytes());
    for c in k.cells() {
        b.extend_from_slice(&(vtk::vtk_type(c.kind).unwrap() as i32).to_be_bytes());
    }
    b.push(b'\n');
    b
}

fn plain(k: &IndexedComplex) -> IndexedComplex {
    let mut k = k.clone();
    k.take_attributes();
    k
}

#[test]
fn binary_vtk_and_vtu_read_what_ascii_vtk_reads() {
    for seed in 1..=12u64 {
        // tetrahedra only; quads and tetrahedra (one cell size, two types); every kind
        let kinds: &[CellKind] = match seed % 3 {
            0 => &KINDS[3..4],
            1 if seed < 6 => &KINDS[2..4],
            _ => &KINDS,
        };
        let k = plain(&random_mesh(
            seed,
            300 + 700 * seed as usize,
            kinds,
            Tags::Constant,
        ));
        let o = ReadOptions::default();
        let ascii = vtk::read_from(&write(vtk::write, &k)[..], "m.vtk".as_ref(), &o).unwrap();
        assert_eq!(ascii.complex, k, "seed {seed}");
        let bin = vtk::read_from(&legacy_binary(&k)[..], "m.vtk".as_ref(), &o).unwrap();
        same(&ascii, &bin, &format!("legacy binary, seed {seed}"));
        let xml = vtu::read_bytes(&write(vtu::write_vtu, &k), "m.vtu".as_ref(), &o).unwrap();
        assert_eq!(xml.complex, k, "vtu, seed {seed}");
    }
}

#[test]
fn vtk_bulk_path_hands_bad_cells_to_the_checked_path() {
    let k = plain(&random_mesh(7, 2000, &KINDS[3..4], Tags::Constant));
    let clean = legacy_binary(&k);
    let cells = clean.windows(6).position(|w| w == b"CELLS ").unwrap();
    let body = cells + clean[cells..].iter().position(|&c| c == b'\n').unwrap() + 1;
    let o = ReadOptions::default();
    // cell 1500 repeats a vertex: named by its count's byte
    let mut b = clean.clone();
    let rec = body + 1500 * 20;
    let v0: [u8; 4] = b[rec + 4..rec + 8].try_into().unwrap();
    b[rec + 8..rec + 12].copy_from_slice(&v0);
    let e = vtk::read_from(&b[..], "m.vtk".as_ref(), &o).unwrap_err();
    assert_eq!(e.location, Some(Location::Byte(rec as u64)), "{e}");
    assert!(e.to_string().contains("appears more than once"), "{e}");
    // cell 1999 names a point past the last: named by the index's byte
    let mut b = clean.clone();
    let rec = body + 1999 * 20;
    b[rec + 16..rec + 20].copy_from_slice(&(k.n_vertices() as i32).to_be_bytes());
    let e = vtk::read_from(&b[..], "m.vtk".as_ref(), &o).unwrap_err();
    assert_eq!(e.location, Some(Location::Byte(rec as u64 + 16)), "{e}");
    assert!(e.to_string().contains("out of range"), "{e}");
    // cell 10's count says 3: the list no longer adds up
    let mut b = clean.clone();
    let rec = body + 10 * 20;
    b[rec..rec + 4].copy_from_slice(&3i32.to_be_bytes());
    let e = vtk::read_from(&b[..], "m.vtk".as_ref(), &o).unwrap_err();
    assert!(matches!(e.location, Some(Location::Byte(_))), "{e}");
}
