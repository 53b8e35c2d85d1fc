//! `render` on pixels: covered area, depth order, defect markers where the defect projects,
//! one colour per Stellar leaf, SVG with one path per visible face, clipping, refused sizes.
use starplex::cell::CellKind;
use starplex::complex::{BuildOptions, ComplexBuilder, IndexedComplex};
use starplex::render::{render, render_svg, Clip, ColorMode, RenderError, RenderOptions, View};

const WHITE: u32 = 0xFF_FF_FF;

fn complex(amb: usize, pts: &[&[f64]], cells: &[(CellKind, &[u32])]) -> IndexedComplex {
    let mut b = ComplexBuilder::new(amb).unwrap();
    for p in pts {
        b.push_vertex(p).unwrap();
    }
    for (k, c) in cells {
        b.push_cell(*k, c).unwrap();
    }
    b.build(&BuildOptions::default()).unwrap().0
}

fn bare(w: u32, h: u32, view: View) -> RenderOptions {
    RenderOptions {
        width: w,
        height: h,
        view: Some(view),
        legend: false,
        shading: false,
        ..Default::default()
    }
}

#[test]
fn a_triangle_covers_its_projected_area() {
    let k = complex(
        2,
        &[&[0.0, 0.0], &[1.0, 0.2], &[0.3, 0.9]],
        &[(CellKind::Simplex(2), &[0, 1, 2])],
    );
    for (w, h) in [(400, 300), (173, 411)] {
        let pic = render(&k, &bare(w, h, View::Top)).unwrap();
        let covered = pic.pixels.iter().filter(|&&p| p != WHITE).count() as f64;
        let p: Vec<(f64, f64)> = [[0.0, 0.0], [1.0, 0.2], [0.3, 0.9]]
            .iter()
            .map(|q| pic.project(q))
            .collect();
        let area = 0.5
            * ((p[1].0 - p[0].0) * (p[2].1 - p[0].1) - (p[2].0 - p[0].0) * (p[1].1 - p[0].1)).abs();
        assert!(
            (covered - area).abs() <= 0.01 * area,
            "{w}x{h}: {covered} pixels for an area of {area}"
        );
    }
}

#[test]
fn the_near_triangle_hides_the_far_one() {
    // a big triangle at z = 0 and a small one above (z = +1) or below (z = -1) it; components
    // colouring tells them apart (component 0: the big one)
    for (z, near_is_small) in [(1.0, true), (-1.0, false)] {
        let k = complex(
            3,
            &[
                &[0.0, 0.0, 0.0],
                &[4.0, 0.0, 0.0],
                &[0.0, 4.0, 0.0],
                &[0.5, 0.5, z],
                &[1.5, 0.5, z],
                &[0.5, 1.5, z],
            ],
            &[
                (CellKind::Simplex(2), &[0, 1, 2]),
                (CellKind::Simplex(2), &[3, 4, 5]),
            ],
        );
        for view in [
            View::Top,
            View::Angles {
                azimuth: 0.0,
                elevation: 89.0,
            },
        ] {
            let mut o = bare(300, 300, view);
            o.colour = ColorMode::Components;
            let pic = render(&k, &o).unwrap();
            let big = {
                let (x, y) = pic.project(&[3.0, 0.5, 0.0]);
                pic.pixel(x as usize, y as usize)
            };
            let (x, y) = pic.project(&[0.8, 0.8, z]);
            let centre = pic.pixel(x as usize, y as usize);
            assert_ne!(big, WHITE);
            assert_eq!(centre == big, !near_is_small, "z = {z}, {view:?}");
        }
    }
}

fn pixels_near(pic: &starplex::render::Picture, x: f64, y: f64, r: i64) -> Vec<u32> {
    let mut v = Vec::new();
    for dy in -r..=r {
        for dx in -r..=r {
            let (px, py) = (x as i64 + dx, y as i64 + dy);
            if px >= 0 && py >= 0 {
                v.push(pic.pixel(px as usize, py as usize));
            }
        }
    }
    v
}

#[test]
fn defects_are_drawn_where_they_project() {
    // a bow tie (non-manifold vertex 0) and, apart, three triangles on the edge 5-6
    let k = complex(
        3,
        &[
            &[0.0, 0.0, 0.0],
            &[1.0, 0.0, 0.0],
            &[1.0, 1.0, 0.0],
            &[-1.0, 0.0, 0.0],
            &[-1.0, -1.0, 0.0],
            &[3.0, 0.0, 0.0],
            &[3.0, 1.0, 0.0],
            &[4.0, 0.5, 0.0],
            &[2.0, 0.5, 0.0],
            &[3.0, 0.5, 1.0],
        ],
        &[
            (CellKind::Simplex(2), &[0, 1, 2]),
            (CellKind::Simplex(2), &[0, 3, 4]),
            (CellKind::Simplex(2), &[5, 6, 7]),
            (CellKind::Simplex(2), &[5, 6, 8]),
            (CellKind::Simplex(2), &[5, 6, 9]),
        ],
    );
    let mut o = bare(600, 400, View::Iso);
    o.colour = ColorMode::Defects;
    o.shading = true;
    let pic = render(&k, &o).unwrap();
    let nm_vertex = 0xFF_00_80;
    let (x, y) = pic.project(&[0.0, 0.0, 0.0]);
    assert_eq!(pic.pixel(x as usize, y as usize), nm_vertex);
    // the marker is big enough to see (more than 50 pixels)
    assert!(
        pixels_near(&pic, x, y, 10)
            .iter()
            .filter(|&&p| p == nm_vertex)
            .count()
            > 50
    );
    // the non-manifold edge: its midpoint is red (non-manifold edge) or violet (in 3 faces)
    let (x, y) = pic.project(&[3.0, 0.5, 0.0]);
    let near = pixels_near(&pic, x, y, 1);
    assert!(
        near.iter()
            .filter(|&&p| p == 0xE0_00_00 || p == 0xC0_00_FF)
            .count()
            >= 7,
        "{near:x?}"
    );
    let names: Vec<&str> = pic.summary.defects.iter().map(|d| d.0.as_str()).collect();
    assert!(names.contains(&"non-manifold vertices"));
    assert!(pic
        .summary
        .defects
        .contains(&("non-manifold edges".into(), 1)));
    // nowhere else: the far corner is background
    assert_eq!(pic.pixel(0, 0), WHITE);
}

/// A flat n x n grid of squares split into triangles.
fn grid(n: u32) -> IndexedComplex {
    let mut b = ComplexBuilder::new(2).unwrap();
    for j in 0..=n {
        for i in 0..=n {
            b.push_vertex(&[f64::from(i), f64::from(j)]).unwrap();
        }
    }
    let id = |i: u32, j: u32| j * (n + 1) + i;
    for j in 0..n {
        for i in 0..n {
            b.push_cell(
                CellKind::Simplex(2),
                &[id(i, j), id(i + 1, j), id(i + 1, j + 1)],
            )
            .unwrap();
            b.push_cell(
                CellKind::Simplex(2),
                &[id(i, j), id(i + 1, j + 1), id(i, j + 1)],
            )
            .unwrap();
        }
    }
    b.build(&BuildOptions::default()).unwrap().0
}

#[test]
fn blocks_show_one_colour_per_leaf() {
    let k = grid(48);
    for kv in [16, 64] {
        let mut o = bare(800, 800, View::Top);
        o.colour = ColorMode::Blocks;
        o.kv = Some(kv);
        let pic = render(&k, &o).unwrap();
        let mut colours: Vec<u32> = pic.pixels.iter().copied().filter(|&p| p != WHITE).collect();
        colours.sort_unstable();
        colours.dedup();
        let leaves = pic.summary.n_colours as f64;
        assert!(leaves > 4.0);
        assert!(
            (colours.len() as f64 - leaves).abs() <= 0.05 * leaves,
            "kv {kv}: {} colours for {leaves} leaves",
            colours.len()
        );
    }
}

fn cube_surface() -> IndexedComplex {
    let p: Vec<[f64; 3]> = (0..8)
        .map(|i| [f64::from(i & 1), f64::from((i >> 1) & 1), f64::from(i >> 2)])
        .collect();
    let pts: Vec<&[f64]> = p.iter().map(|x| &x[..]).collect();
    complex(
        3,
        &pts,
        &[
            (CellKind::Quad, &[0, 1, 3, 2]),
            (CellKind::Quad, &[4, 5, 7, 6]),
            (CellKind::Quad, &[0, 1, 5, 4]),
            (CellKind::Quad, &[2, 3, 7, 6]),
            (CellKind::Quad, &[0, 2, 6, 4]),
            (CellKind::Quad, &[1, 3, 7, 5]),
        ],
    )
}

/// Number of `<path>` elements inside `<g id="faces">`, and checks the document parses.
fn svg_face_paths(doc: &str) -> usize {
    use quick_xml::events::Event;
    let mut r = quick_xml::Reader::from_str(doc);
    let (mut depth_in_faces, mut n) = (0usize, 0usize);
    loop {
        match r.read_event().expect("the SVG parses as XML") {
            Event::Start(e) => {
                let is_faces = e.name().as_ref() == "g"
                    && e.attributes()
                        .flatten()
                        .any(|a| a.key.as_ref() == "id" && a.value == "faces");
                if depth_in_faces > 0 || is_faces {
                    depth_in_faces += 1;
                }
            }
            Event::End(_) => depth_in_faces = depth_in_faces.saturating_sub(1),
            Event::Empty(e) if depth_in_faces > 0 && e.name().as_ref() == "path" => n += 1,
            Event::Eof => break,
            _ => {}
        }
    }
    n
}

#[test]
fn svg_has_one_path_per_visible_face() {
    let k = cube_surface();
    for (view, visible) in [
        (View::Iso, 3),
        (View::Top, 1),
        (View::Front, 1),
        (
            View::Angles {
                azimuth: 20.0,
                elevation: 0.0,
            },
            2,
        ),
    ] {
        let o = RenderOptions {
            width: 400,
            height: 300,
            view: Some(view),
            ..Default::default()
        };
        let (doc, s) = render_svg(&k, &o).unwrap();
        assert_eq!(s.n_faces, 6);
        assert_eq!(svg_face_paths(&doc), visible, "{view:?}");
    }
    // a flat grid seen from above: every face
    let g = grid(6);
    let (doc, s) = render_svg(
        &g,
        &RenderOptions {
            width: 500,
            height: 500,
            ..Default::default()
        },
    )
    .unwrap();
    assert_eq!(svg_face_paths(&doc), s.n_faces);
    assert_eq!(s.n_faces, 72);
}

/// Two hexahedra side by side along x (unit cubes [0,1] and [1,2]).
fn two_hexes() -> IndexedComplex {
    let mut p = Vec::new();
    for z in 0..2 {
        for y in 0..2 {
            for x in 0..3 {
                p.push([f64::from(x), f64::from(y), f64::from(z)]);
            }
        }
    }
    let id = |x: u32, y: u32, z: u32| z * 6 + y * 3 + x;
    let hex = |x: u32| {
        [
            id(x, 0, 0),
            id(x + 1, 0, 0),
            id(x + 1, 1, 0),
            id(x, 1, 0),
            id(x, 0, 1),
            id(x + 1, 0, 1),
            id(x + 1, 1, 1),
            id(x, 1, 1),
        ]
    };
    let pts: Vec<&[f64]> = p.iter().map(|x| &x[..]).collect();
    complex(
        3,
        &pts,
        &[(CellKind::Hex, &hex(0)), (CellKind::Hex, &hex(1))],
    )
}

#[test]
fn clipping_opens_the_volume() {
    let k = two_hexes();
    let mut o = bare(300, 200, View::Iso);
    o.colour = ColorMode::Boundary;
    let whole = render(&k, &o).unwrap();
    assert_eq!(whole.summary.n_faces, 10);
    o.clip = Some(Clip {
        axis: 0,
        value: 1.0,
    });
    let cut = render(&k, &o).unwrap();
    assert_eq!((cut.summary.n_faces, cut.summary.clipped_cells), (6, 1));
    // the face x = 1 is now exposed: its centre shows the cut colour, seen from +x
    o.view = Some(View::Side);
    let side = render(&k, &o).unwrap();
    let (x, y) = side.project(&[1.0, 0.5, 0.5]);
    assert_eq!(side.pixel(x as usize, y as usize), 0xF2_B8_5A);
    assert!(side
        .summary
        .legend
        .iter()
        .any(|l| l.1 == "faces cut open: 1"));
    // everything clipped away
    o.clip = Some(Clip {
        axis: 0,
        value: -1.0,
    });
    assert!(matches!(render(&k, &o), Err(RenderError::NothingLeft(2))));
}

#[test]
fn inverted_hexes_and_tets_are_found() {
    let k = two_hexes();
    // flip the second hex (swap bottom and top)
    let cells: Vec<Vec<u32>> = k.cells().map(|c| c.vertices.to_vec()).collect();
    let mut flipped = cells[1].clone();
    flipped.rotate_left(4);
    let k2 = IndexedComplex::from_parts(
        3,
        k.coords().to_vec().into(),
        vec![(CellKind::Hex, [cells[0].clone(), flipped].concat().into())],
    )
    .unwrap();
    let mut o = bare(200, 200, View::Iso);
    o.colour = ColorMode::Defects;
    // one against one: the majority rule keeps the first as the reference
    let pic = render(&k2, &o).unwrap();
    assert!(pic
        .summary
        .defects
        .contains(&("inverted or flat cells".into(), 1)));
    let pic = render(&k, &o).unwrap();
    assert!(pic
        .summary
        .defects
        .contains(&("inverted or flat cells".into(), 0)));
}

#[test]
fn lines_dots_and_higher_dimensions() {
    // a 4-simplex in R^4, an edge and an isolated vertex
    let k = complex(
        4,
        &[
            &[0.0, 0.0, 0.0, 0.0],
            &[1.0, 0.0, 0.0, 0.0],
            &[0.0, 1.0, 0.0, 0.0],
            &[0.0, 0.0, 1.0, 0.0],
            &[0.0, 0.0, 0.0, 1.0],
            &[2.0, 2.0, 2.0, 0.0],
            &[3.0, 2.0, 2.0, 0.0],
            &[3.0, 3.0, 3.0, 0.0],
        ],
        &[
            (CellKind::Simplex(4), &[0, 1, 2, 3, 4]),
            (CellKind::Simplex(1), &[5, 6]),
        ],
    );
    let pic = render(&k, &bare(200, 200, View::Iso)).unwrap();
    assert_eq!(
        (
            pic.summary.n_faces,
            pic.summary.n_lines,
            pic.summary.n_points
        ),
        (10, 1, 1)
    );
    assert!(pic.summary.notes.iter().any(|n| n.contains("2-skeleton")));
    assert!(pic
        .summary
        .notes
        .iter()
        .any(|n| n.contains("first three coordinates")));
    let (x, y) = pic.project(&[2.5, 2.0, 2.0]);
    assert!(pixels_near(&pic, x, y, 1).iter().any(|&p| p != WHITE));
    let (x, y) = pic.project(&[3.0, 3.0, 3.0]);
    assert!(pixels_near(&pic, x, y, 1).iter().any(|&p| p != WHITE));
}

#[test]
fn bad_sizes_and_empty_complexes_are_refused() {
    let k = cube_surface();
    for (w, h) in [
        (0, 10),
        (10, 0),
        (100_000, 100_000),
        (16_385, 10),
        (10_000, 10_000),
    ] {
        let o = RenderOptions {
            width: w,
            height: h,
            ..Default::default()
        };
        let e = render(&k, &o).unwrap_err();
        assert!(matches!(e, RenderError::Size { .. }), "{w}x{h}");
        assert!(e.to_string().contains("of memory"), "{e}");
    }
    let e = render(&complex(3, &[], &[]), &RenderOptions::default()).unwrap_err();
    assert!(matches!(e, RenderError::Empty));
}
