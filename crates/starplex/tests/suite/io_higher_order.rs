//! Higher-order gmsh elements (gmsh's own files, `scripts/make_higher_order_corpus.py`): each
//! is read as its first-order cell, so every higher-order file of a mesh reads as the order-1
//! file does (same points, cells, tags), in all four encodings, with a note saying so; and VTK's
//! quadratic, Lagrange and Bezier cells (meshio's and VTK's own files) as their linear cells.
use starplex::io::{self, ReadOptions};
use std::path::PathBuf;

fn data(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/io")
        .join(name)
}

#[test]
fn higher_order_files_read_as_their_first_order_mesh() {
    let families = [
        ("ho_tet", &["o2", "o3"][..], 24),
        ("ho_hex", &["o2", "o2s"][..], 8),
        ("ho_prism", &["o2", "o2s"][..], 8),
    ];
    let mut checked = 0;
    for (name, orders, n_cells) in families {
        let o1 = io::read(&data(&format!("{name}_o1.msh")), &ReadOptions::default()).unwrap();
        assert_eq!(o1.complex.n_cells(), n_cells, "{name}");
        assert!(
            !o1.notes.iter().any(|n| n.contains("higher-order")),
            "{name}: {:?}",
            o1.notes
        );
        for order in orders {
            for enc in ["41_ascii", "41_bin", "22_ascii", "22_bin"] {
                let f = format!("{name}_{order}_{enc}.msh");
                let r = io::read(&data(&f), &ReadOptions::default())
                    .unwrap_or_else(|e| panic!("{f}: {e}"));
                assert_eq!(r.complex.n_vertices(), o1.complex.n_vertices(), "{f}");
                assert_eq!(r.complex.coords(), o1.complex.coords(), "{f}: points");
                let cells = |k: &starplex::complex::IndexedComplex| {
                    k.cells()
                        .map(|c| (c.kind, c.vertices.to_vec()))
                        .collect::<Vec<_>>()
                };
                assert_eq!(cells(&r.complex), cells(&o1.complex), "{f}: cells");
                assert_eq!(r.complex.attributes(), o1.complex.attributes(), "{f}: tags");
                assert!(
                    r.notes
                        .iter()
                        .any(|n| n.contains("higher-order elements as their first-order cells")),
                    "{f}: {:?}",
                    r.notes
                );
                checked += 1;
            }
        }
    }
    assert_eq!(checked, 24);
}

#[test]
fn an_unknown_element_type_is_still_refused() {
    let dir = std::env::temp_dir().join(format!("starplex-ho-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join("t32.msh");
    std::fs::write(
        &p,
        "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n1\n1 0 0 0\n$EndNodes\n\
         $Elements\n1\n1 32 0 1\n$EndElements\n",
    )
    .unwrap();
    let e = io::read(&p, &ReadOptions::default())
        .unwrap_err()
        .to_string();
    assert!(e.contains("gmsh element type 32 is not supported"), "{e}");
    // a higher-order element whose extra node is not a node of the file
    std::fs::write(
        &p,
        "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n2\n1 0 0 0\n2 1 0 0\n$EndNodes\n\
         $Elements\n1\n1 8 0 1 2 9\n$EndElements\n",
    )
    .unwrap();
    let e = io::read(&p, &ReadOptions::default())
        .unwrap_err()
        .to_string();
    assert!(e.contains("node tag 9 is not a node"), "{e}");
    std::fs::remove_dir_all(&dir).unwrap();
}

type Key = (starplex::cell::CellKind, Vec<[u64; 3]>);

/// The cells of `k` by their corners' coordinates (sorted), sorted.
fn by_coords(k: &starplex::complex::IndexedComplex) -> Vec<Key> {
    let mut cells: Vec<Key> = k
        .cells()
        .map(|c| {
            let mut p: Vec<[u64; 3]> = c
                .vertices
                .iter()
                .map(|&v| {
                    let x = k.point(starplex::ids::VertexId(v));
                    [x[0].to_bits(), x[1].to_bits(), x[2].to_bits()]
                })
                .collect();
            p.sort_unstable();
            (c.kind, p)
        })
        .collect();
    cells.sort_unstable();
    cells
}

/// The same order-2 meshes written by meshio as legacy VTK and `.vtu` (quadratic cell types):
/// the cells are gmsh's order-1 cells (compared by their corners' coordinates, since VTK keeps
/// every point and numbers them as the file does), the other points are vertices in no cell.
#[test]
fn quadratic_vtk_cells_read_as_their_linear_cells() {
    let mut opts = ReadOptions::default();
    opts.build.drop_face_cells = true; // meshio writes the boundary elements too
    for (name, o1) in [
        ("ho_tet_o2", "ho_tet_o1"),
        ("ho_hex_o2", "ho_hex_o1"),
        ("ho_hex_o2s", "ho_hex_o1"),
        ("ho_prism_o2", "ho_prism_o1"),
    ] {
        let want = io::read(&data(&format!("{o1}.msh")), &ReadOptions::default()).unwrap();
        for ext in ["vtk", "vtu"] {
            let f = format!("{name}.{ext}");
            let r = io::read(&data(&f), &opts).unwrap_or_else(|e| panic!("{f}: {e}"));
            assert_eq!(by_coords(&r.complex), by_coords(&want.complex), "{f}");
            assert_eq!(
                r.complex.n_vertices() - r.complex.n_isolated_vertices(),
                want.complex.n_vertices(),
                "{f}: corner points"
            );
            assert!(r.complex.n_isolated_vertices() > 0, "{f}");
            assert!(
                r.notes
                    .iter()
                    .any(|n| n.contains("higher-order cells (types 21-37, 68-80) as their linear")),
                "{f}: {:?}",
                r.notes
            );
        }
    }
}

/// VTK's own arbitrary-order cells (`scripts/make_lagrange_corpus.py`, VTK's `vtkCellTypeSource`):
/// the Lagrange (68-73) and Bezier (75-80) types at orders 2 and 3, legacy binary and `.vtu`
/// appended raw, each read as the linear cells `vtkCellTypeSource` makes at order 1 on the same
/// block (compared by corner coordinates); the quadratic polygon (36) as its linear polygon.
#[test]
fn lagrange_and_bezier_cells_read_as_their_linear_cells() {
    let linear = [
        (68, "line"),
        (69, "tri"),
        (70, "quad"),
        (71, "tet"),
        (72, "hex"),
        (73, "wedge"),
    ];
    let mut checked = 0;
    for (lagrange, name) in linear {
        let want = io::read(&data(&format!("lg_{name}_o1.vtu")), &ReadOptions::default())
            .unwrap_or_else(|e| panic!("lg_{name}_o1.vtu: {e}"));
        assert!(want.complex.n_cells() >= 2, "{name}");
        for ty in [lagrange, lagrange + 7] {
            for order in [2, 3] {
                for ext in ["vtk", "vtu"] {
                    let f = format!("lg_{ty}_o{order}.{ext}");
                    let r = io::read(&data(&f), &ReadOptions::default())
                        .unwrap_or_else(|e| panic!("{f}: {e}"));
                    assert_eq!(by_coords(&r.complex), by_coords(&want.complex), "{f}");
                    assert!(r.complex.n_isolated_vertices() > 0, "{f}");
                    assert!(
                        r.notes.iter().any(|n| n.contains("higher-order cells")),
                        "{f}: {:?}",
                        r.notes
                    );
                    checked += 1;
                }
            }
        }
    }
    assert_eq!(checked, 48);
    let want = io::read(&data("lg_polygon_o1.vtu"), &ReadOptions::default()).unwrap();
    for ext in ["vtk", "vtu"] {
        let f = format!("lg_36_o2.{ext}");
        let r = io::read(&data(&f), &ReadOptions::default()).unwrap_or_else(|e| panic!("{f}: {e}"));
        assert_eq!(by_coords(&r.complex), by_coords(&want.complex), "{f}");
        assert_eq!(
            r.complex.n_isolated_vertices(),
            9,
            "{f}: one point per side"
        );
    }
}

/// Point counts no order of the cell has, the quadratic polygon's odd counts, and the
/// arbitrary-order pyramids VTK does not define: errors naming the type and the count.
#[test]
fn impossible_arbitrary_order_cells_are_refused() {
    let dir = std::env::temp_dir().join(format!("starplex-lg-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join("bad.vtk");
    let points: String = (0..30).map(|i| format!("{i} 0 {} ", i * i)).collect();
    let cases: [(u32, usize, &str); 6] = [
        (71, 11, "cannot have 11 points"),      // tetra: 4, 10, 20, ...
        (69, 7, "cannot have 7 points"),        // triangle: 3, 6, 10, ...
        (72, 26, "cannot have 26 points"),      // hexahedron: a product of three factors >= 2
        (36, 7, "even number of points"),       // quadratic polygon
        (74, 14, "no arbitrary-order pyramid"), // Lagrange pyramid
        (81, 5, "no arbitrary-order pyramid"),  // Bezier pyramid
    ];
    for (ty, n, want) in cases {
        let ids: String = (0..n).map(|i| format!(" {i}")).collect();
        std::fs::write(
            &p,
            format!(
                "# vtk DataFile Version 4.2\nbad\nASCII\nDATASET UNSTRUCTURED_GRID\n\
                 POINTS 30 double\n{points}\nCELLS 1 {}\n{n}{ids}\nCELL_TYPES 1\n{ty}\n",
                n + 1
            ),
        )
        .unwrap();
        let e = io::read(&p, &ReadOptions::default())
            .unwrap_err()
            .to_string();
        assert!(e.contains(want), "type {ty}, {n} points: {e}");
        assert!(e.contains(&format!("type {ty}")), "{e}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
