//! `algo::simplify` with attributes: vertex and cell attributes follow the surviving vertices
//! and cells; `keep_labels` keeps the topology of every label region and of every interface
//! (components and Euler characteristic, computed here by brute force from the faces);
//! `keep_vertices` never removes nor moves a listed vertex; the Hausdorff estimate on meshes
//! whose answer is known.
use std::collections::{BTreeMap, BTreeSet};

use starplex::algo::simplify::hausdorff::hausdorff_estimate;
use starplex::algo::simplify::{
    label_interface_vertices, simplify, summary, Mode, SimplifyError, SimplifyOptions, Target,
};
use starplex::attr::{AttrTarget, AttrValues, Attribute, Attributes};
use starplex::cell::CellKind;
use starplex::complex::{BuildOptions, ComplexBuilder, IndexedComplex};
use starplex::generate::kuhn_grid;
use starplex::ids::VertexId;

fn centroid(k: &IndexedComplex, c: &[u32]) -> Vec<f64> {
    let d = k.ambient_dim();
    let mut m = vec![0.0; d];
    for &v in c {
        for (x, y) in m.iter_mut().zip(k.point(VertexId(v))) {
            *x += y / c.len() as f64;
        }
    }
    m
}

/// `k` with a cell attribute "label" from `f(centroid)` and a vertex attribute "id" (the input
/// vertex id, as a float) and "tag2" (2 int components per vertex).
fn labelled(mut k: IndexedComplex, f: impl Fn(&[f64]) -> i64) -> IndexedComplex {
    let labels: Vec<i64> = k.cells().map(|c| f(&centroid(&k, c.vertices))).collect();
    let n = k.n_vertices();
    let attrs = Attributes {
        vertex: vec![
            Attribute::float("id", 1, (0..n).map(|v| v as f64).collect()),
            Attribute::int(
                "tag2",
                2,
                (0..n).flat_map(|v| [v as i64, -(v as i64)]).collect(),
            ),
        ],
        cell: vec![Attribute::int("label", 1, labels)],
    };
    k.set_attributes(attrs).unwrap();
    k
}

fn ints(k: &IndexedComplex, t: AttrTarget, name: &str) -> Vec<i64> {
    match &k.attributes().get(t, name).unwrap().values {
        AttrValues::Int(v) => v.clone(),
        AttrValues::Float(v) => v.iter().map(|&x| x as i64).collect(),
    }
}

/// Every face (sorted vertex list) of the given cells.
fn closure<'a>(cells: impl Iterator<Item = &'a [u32]>) -> BTreeSet<Vec<u32>> {
    let mut out = BTreeSet::new();
    for c in cells {
        let mut c = c.to_vec();
        c.sort_unstable();
        for mask in 1u32..(1 << c.len()) {
            out.insert(
                (0..c.len())
                    .filter(|i| mask >> i & 1 == 1)
                    .map(|i| c[i])
                    .collect(),
            );
        }
    }
    out
}

/// (connected components, Euler characteristic) of a closed set of faces.
fn topo(faces: &BTreeSet<Vec<u32>>) -> (usize, i64) {
    let mut parent: BTreeMap<u32, u32> = BTreeMap::new();
    fn find(p: &mut BTreeMap<u32, u32>, x: u32) -> u32 {
        let mut r = x;
        while p[&r] != r {
            r = p[&r];
        }
        p.insert(x, r);
        r
    }
    for f in faces {
        for &v in f {
            parent.entry(v).or_insert(v);
        }
    }
    for f in faces.iter().filter(|f| f.len() == 2) {
        let (a, b) = (find(&mut parent, f[0]), find(&mut parent, f[1]));
        parent.insert(a, b);
    }
    let verts: Vec<u32> = parent.keys().copied().collect();
    let roots: BTreeSet<u32> = verts.iter().map(|&v| find(&mut parent, v)).collect();
    let chi = faces
        .iter()
        .map(|f| if f.len() % 2 == 1 { 1 } else { -1 })
        .sum();
    (roots.len(), chi)
}

/// Per label: (components, χ) of its region; per pair of labels: (components, χ) of the
/// interface (the faces common to both closures).
type RegionTopology = (
    BTreeMap<i64, (usize, i64)>,
    BTreeMap<(i64, i64), (usize, i64)>,
);

fn region_topology(k: &IndexedComplex) -> RegionTopology {
    let labels = ints(k, AttrTarget::Cell, "label");
    let cells: Vec<Vec<u32>> = k.cells().map(|c| c.vertices.to_vec()).collect();
    let set: BTreeSet<i64> = labels.iter().copied().collect();
    let closures: BTreeMap<i64, BTreeSet<Vec<u32>>> = set
        .iter()
        .map(|&l| {
            let cl = closure(
                cells
                    .iter()
                    .zip(&labels)
                    .filter(|(_, m)| **m == l)
                    .map(|(c, _)| &c[..]),
            );
            (l, cl)
        })
        .collect();
    let regions = closures.iter().map(|(&l, cl)| (l, topo(cl))).collect();
    let mut interfaces = BTreeMap::new();
    for (&l, a) in &closures {
        for (&m, b) in closures.range(l + 1..) {
            let common: BTreeSet<Vec<u32>> = a.intersection(b).cloned().collect();
            if !common.is_empty() {
                interfaces.insert((l, m), topo(&common));
            }
        }
    }
    (regions, interfaces)
}

/// A closed torus surface in 3D (`n` × `m` squares split in two), bumpy so that QEM has
/// something to choose.
fn torus(n: u32, m: u32) -> IndexedComplex {
    let mut b = ComplexBuilder::new(3).unwrap();
    for i in 0..n {
        for j in 0..m {
            let (u, v) = (
                i as f64 / n as f64 * std::f64::consts::TAU,
                j as f64 / m as f64 * std::f64::consts::TAU,
            );
            let r = 1.0 + 0.02 * ((7.0 * u).sin() * (5.0 * v).cos());
            let x = (3.0 + r * v.cos()) * u.cos();
            let y = (3.0 + r * v.cos()) * u.sin();
            b.push_vertex(&[x, y, r * v.sin()]).unwrap();
        }
    }
    let id = |i: u32, j: u32| (i % n) * m + (j % m);
    for i in 0..n {
        for j in 0..m {
            let (a, bb, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            b.push_cell(CellKind::Simplex(2), &[a, bb, c]).unwrap();
            b.push_cell(CellKind::Simplex(2), &[a, c, d]).unwrap();
        }
    }
    b.build(&BuildOptions::default()).unwrap().0
}

fn scaled(mut k: IndexedComplex, s: f64) -> IndexedComplex {
    k.set_coords(k.coords().iter().map(|x| x * s).collect())
        .unwrap();
    k
}

/// The labelled test meshes: a torus in two bands (two annuli, two circles between them), a
/// flat square with an annulus label (a disk, a frame and an annulus; two interface circles),
/// a cube of tetrahedra with a ball inside.
fn cases() -> Vec<(&'static str, IndexedComplex)> {
    let t = labelled(torus(40, 16), |p| if p[0] > 0.5 { 1 } else { 2 });
    let sq = labelled(scaled(kuhn_grid(&[24, 24]).unwrap(), 1.0 / 24.0), |p| {
        let r = ((p[0] - 0.5).powi(2) + (p[1] - 0.5).powi(2)).sqrt();
        if (0.15..0.35).contains(&r) {
            2
        } else {
            1
        }
    });
    let cube = labelled(scaled(kuhn_grid(&[8, 8, 8]).unwrap(), 1.0 / 8.0), |p| {
        let r = p.iter().map(|x| (x - 0.5).powi(2)).sum::<f64>().sqrt();
        if r < 0.3 {
            2
        } else {
            1
        }
    });
    vec![("torus", t), ("square", sq), ("cube", cube)]
}

fn opts(mode: Mode, ratio: f64, keep: bool) -> SimplifyOptions {
    SimplifyOptions {
        mode: Some(mode),
        target: Target {
            ratio: Some(ratio),
            ..Default::default()
        },
        keep_manifold: true,
        keep_labels: keep.then(|| "label".to_string()),
        ..Default::default()
    }
}

#[test]
fn label_regions_and_interfaces_keep_their_topology() {
    let mut changed_without = 0;
    for (name, k) in cases() {
        let before = region_topology(&k);
        // every case has two regions and at least one interface
        assert_eq!(before.0.len(), 2, "{name}: {before:?}");
        assert!(!before.1.is_empty(), "{name}");
        let interface: BTreeSet<u32> = label_interface_vertices(&k, "label")
            .unwrap()
            .into_iter()
            .collect();
        for mode in [Mode::Qem, Mode::Homology] {
            let (out, report) = simplify(&k, &opts(mode, 0.05, true)).unwrap();
            assert!(
                out.n_cells() < k.n_cells() / 2,
                "{name} {mode:?}: too little done"
            );
            assert_eq!(report.kept_labels.as_deref(), Some("label"));
            assert_eq!(report.locked_vertices, interface.len());
            assert_eq!(region_topology(&out), before, "{name} {mode:?}");
            assert_eq!(summary(&out).betti, summary(&k).betti, "{name} {mode:?}");
            // the interface vertices are all there, where they were
            let ids = ints(&out, AttrTarget::Vertex, "id");
            let kept: BTreeSet<u32> = ids.iter().map(|&v| v as u32).collect();
            assert!(interface.is_subset(&kept), "{name} {mode:?}");
            for (new, &old) in ids.iter().enumerate() {
                if interface.contains(&(old as u32)) {
                    assert_eq!(
                        out.point(VertexId(new as u32)),
                        k.point(VertexId(old as u32))
                    );
                }
            }
            let (unlocked, _) = simplify(&k, &opts(mode, 0.05, false)).unwrap();
            if region_topology(&unlocked) != before {
                changed_without += 1;
            }
        }
    }
    // the test can see a change: without the lock, labels are not kept
    assert!(
        changed_without >= 2,
        "only {changed_without} runs changed without the lock"
    );
}

#[test]
fn attributes_follow_the_surviving_vertices_and_cells() {
    for (name, k) in cases() {
        for mode in [Mode::Qem, Mode::Homology] {
            let (out, _) = simplify(&k, &opts(mode, 0.2, false)).unwrap();
            let a = out.attributes();
            assert!(a.check(out.n_vertices(), out.n_cells()).is_ok());
            assert_eq!(a.vertex.len(), 2);
            assert_eq!(a.cell.len(), 1);
            // vertices: each output vertex has its own input id (increasing: survivors keep
            // their order), and the matching 2-component values
            let ids = ints(&out, AttrTarget::Vertex, "id");
            assert!(ids.windows(2).all(|w| w[0] < w[1]), "{name}");
            let tag2 = ints(&out, AttrTarget::Vertex, "tag2");
            for (i, &id) in ids.iter().enumerate() {
                assert_eq!(&tag2[2 * i..2 * i + 2], &[id, -id]);
                if mode == Mode::Homology {
                    // homology mode moves no vertex
                    assert_eq!(out.point(VertexId(i as u32)), k.point(VertexId(id as u32)));
                }
            }
            // cells: every label value is one of the input's
            let labels_in: BTreeSet<i64> =
                ints(&k, AttrTarget::Cell, "label").into_iter().collect();
            assert!(ints(&out, AttrTarget::Cell, "label")
                .iter()
                .all(|l| labels_in.contains(l)));
        }
    }
    // homology mode on a path: the cell values follow the edges exactly
    let mut b = ComplexBuilder::new(1).unwrap();
    for x in 0..5 {
        b.push_vertex(&[x as f64]).unwrap();
    }
    for i in 0..4u32 {
        b.push_cell(CellKind::Simplex(1), &[i, i + 1]).unwrap();
    }
    b.set_attributes(Attributes {
        vertex: vec![],
        cell: vec![Attribute::int("edge", 1, vec![10, 11, 12, 13])],
    });
    let k = b.build(&BuildOptions::default()).unwrap().0;
    let o = SimplifyOptions {
        target: Target {
            faces: Some(2),
            ..Default::default()
        },
        ..Default::default()
    };
    let (out, _) = simplify(&k, &o).unwrap();
    assert_eq!(out.n_cells(), 2);
    // each output edge [x, y] carries the value of an input edge it is the image of: one of
    // the edges between its end points
    let vals = ints(&out, AttrTarget::Cell, "edge");
    for (c, v) in out.cells().zip(vals) {
        let xs: Vec<f64> = c
            .vertices
            .iter()
            .map(|&u| out.point(VertexId(u))[0])
            .collect();
        let (lo, hi) = (xs[0].min(xs[1]), xs[0].max(xs[1]));
        let e = (v - 10) as f64; // input edge [e, e + 1]
        assert!(lo <= e && e + 1.0 <= hi, "edge {xs:?} has value {v}");
    }
}

#[test]
fn kept_vertices_are_neither_removed_nor_moved() {
    let (_, k) = cases().remove(0); // the torus
    let keep: Vec<u32> = (0..k.n_vertices() as u32).step_by(37).collect();
    for mode in [Mode::Qem, Mode::Homology] {
        let o = SimplifyOptions {
            keep_vertices: keep.clone(),
            ..opts(mode, 0.02, false)
        };
        let (out, report) = simplify(&k, &o).unwrap();
        assert_eq!(report.locked_vertices, keep.len());
        let ids = ints(&out, AttrTarget::Vertex, "id");
        for &v in &keep {
            let i = ids
                .iter()
                .position(|&x| x == v as i64)
                .unwrap_or_else(|| panic!("{mode:?}: vertex {v} removed"));
            assert_eq!(out.point(VertexId(i as u32)), k.point(VertexId(v)));
        }
        assert!(
            out.n_vertices() < keep.len() * 3,
            "{mode:?}: {}",
            out.n_vertices()
        );
    }
    let bad = SimplifyOptions {
        keep_vertices: vec![k.n_vertices() as u32],
        ..opts(Mode::Qem, 0.5, false)
    };
    assert!(matches!(
        simplify(&k, &bad),
        Err(SimplifyError::BadVertex { .. })
    ));
    let bad = SimplifyOptions {
        keep_labels: Some("nope".into()),
        ..opts(Mode::Qem, 0.5, false)
    };
    let e = simplify(&k, &bad).unwrap_err();
    assert!(e.to_string().contains("label"), "{e}"); // names what there is
}

#[test]
fn hausdorff_estimate_known_answers() {
    // a flat square simplified stays on its plane: distance ~0 both ways
    let sq = scaled(kuhn_grid(&[30, 30]).unwrap(), 0.1);
    let mut b = ComplexBuilder::new(3).unwrap();
    for p in sq.coords().chunks_exact(2) {
        b.push_vertex(&[p[0], p[1], 0.0]).unwrap();
    }
    for c in sq.cells() {
        b.push_cell(CellKind::Simplex(2), c.vertices).unwrap();
    }
    let flat = b.build(&BuildOptions::default()).unwrap().0;
    for k in [&sq, &flat] {
        let (out, _) = simplify(k, &opts(Mode::Qem, 0.05, false)).unwrap();
        assert!(out.n_cells() <= 90);
        let h = hausdorff_estimate(k, &out).unwrap();
        // the boundary moves by rounding only (QEM's boundary planes)
        assert!(h.max() < 1e-6 * h.diagonal, "{h:?}");
        assert!((h.diagonal - 18f64.sqrt()).abs() < 1e-12);
    }
    // a tent: the square [0,2]² with its centre raised by 0.3, against the flat square
    let tent = |h: f64| {
        let mut b = ComplexBuilder::new(3).unwrap();
        for p in [
            [0.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [2.0, 2.0, 0.0],
            [0.0, 2.0, 0.0],
            [1.0, 1.0, h],
        ] {
            b.push_vertex(&p).unwrap();
        }
        for c in [[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]] {
            b.push_cell(CellKind::Simplex(2), &c).unwrap();
        }
        b.build(&BuildOptions::default()).unwrap().0
    };
    let h = hausdorff_estimate(&tent(0.3), &tent(0.0)).unwrap();
    assert!((h.a_to_b - 0.3).abs() < 1e-12, "{h:?}");
    // the flat square's vertices (corners, centre) to the tent: corners 0, the centre is
    // under the apex at 0.3 from it, but closer to the faces: 0.3 * cos(atan(0.3))
    let expect = 0.3 / (1.0f64 + 0.09).sqrt();
    assert!((h.b_to_a - expect).abs() < 1e-12, "{h:?}");
    assert_eq!(h.n_samples, [5, 5]);
    assert!((h.mean_a_to_b - 0.3 / 5.0).abs() < 1e-12);
    // not a mesh: no estimate
    assert!(hausdorff_estimate(&kuhn_grid(&[3]).unwrap(), &kuhn_grid(&[3]).unwrap()).is_none());
}
