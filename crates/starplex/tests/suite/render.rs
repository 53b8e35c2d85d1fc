//! `render` on pixels: covered area, depth order, defect markers where the defect projects,
//! one colour per Stellar leaf, SVG with one path per visible face, clipping, refused sizes.
use starplex::attr::{Attribute, Attributes};
use starplex::cell::CellKind;
use starplex::complex::{BuildOptions, ComplexBuilder, IndexedComplex};
use starplex::render::{
    render, render_svg, render_with, Clip, ColorMode, Eye, Given, RenderError, RenderOptions, View,
};

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

/// Two unit squares side by side: x in [0, 1] (holding vertex 0) and x in [1, 2].
fn two_quads() -> IndexedComplex {
    complex(
        2,
        &[
            &[0.0, 0.0],
            &[1.0, 0.0],
            &[2.0, 0.0],
            &[0.0, 1.0],
            &[1.0, 1.0],
            &[2.0, 1.0],
        ],
        &[
            (CellKind::Quad, &[0, 1, 4, 3]),
            (CellKind::Quad, &[1, 2, 5, 4]),
        ],
    )
}

fn close(a: u32, b: u32, tol: i64) -> bool {
    (0..3).all(|k| {
        let s = 8 * k;
        (((a >> s) & 0xFF) as i64 - ((b >> s) & 0xFF) as i64).abs() <= tol
    })
}

#[test]
fn two_labels_show_two_colours_where_their_cells_are() {
    let mut k = two_quads();
    let region: Vec<i64> = k
        .cells()
        .map(|c| if c.vertices.contains(&0) { 5 } else { 9 })
        .collect();
    k.set_attributes(Attributes {
        vertex: vec![],
        cell: vec![Attribute::int("region", 1, region)],
    })
    .unwrap();
    let mut o = bare(400, 300, View::Top);
    o.colour = ColorMode::Label;
    o.attribute = Some("region".into());
    o.legend = true;
    let pic = render(&k, &o).unwrap();
    let at = |x: f64, y: f64| {
        let (px, py) = pic.project(&[x, y]);
        pic.pixel(px as usize, py as usize)
    };
    let (left, right) = (at(0.5, 0.5), at(1.5, 0.5));
    assert_ne!(left, right);
    assert!(left != WHITE && right != WHITE);
    // each square is its label's colour all over (no shading)
    assert_eq!((at(0.1, 0.9), at(0.9, 0.1)), (left, left));
    assert_eq!((at(1.1, 0.9), at(1.9, 0.1)), (right, right));
    // the legend lists both, with the colours drawn
    let swatch = |text: &str| {
        pic.summary
            .legend
            .iter()
            .find(|l| l.1 == text)
            .unwrap_or_else(|| panic!("no '{text}' in {:?}", pic.summary.legend))
            .0
    };
    assert_eq!(swatch("region = 5: 1 cells"), Some(left));
    assert_eq!(swatch("region = 9: 1 cells"), Some(right));
    assert_eq!(pic.summary.n_colours, 2);
    // the swatches are in the picture
    assert!(pic.pixels.iter().filter(|&&p| p == left).count() > 1000);
    // a name that is not there
    o.attribute = Some("material".into());
    let e = render(&k, &o).unwrap_err().to_string();
    assert!(
        e.contains("no cell attribute 'material'") && e.contains("region"),
        "{e}"
    );
}

#[test]
fn a_linear_field_shows_the_colour_bar_ends() {
    let mut k = grid(8);
    let x: Vec<f64> = (0..k.n_vertices())
        .map(|v| -2.0 + 0.5 * k.coords()[2 * v]) // -2 at x = 0, 2 at x = 8
        .collect();
    k.set_attributes(Attributes {
        vertex: vec![Attribute::float("temperature", 1, x)],
        cell: vec![],
    })
    .unwrap();
    let mut o = bare(600, 500, View::Top);
    o.colour = ColorMode::Field;
    o.attribute = Some("temperature".into());
    o.legend = true;
    let pic = render(&k, &o).unwrap();
    let bar = pic.summary.colour_bar.clone().expect("a colour bar");
    assert_eq!((bar.lo, bar.hi), (-2.0, 2.0));
    let [x0, y0, x1, y1] = bar.rect.expect("drawn");
    let ym = (y0 + y1) / 2;
    let (bar_lo, bar_hi) = (pic.pixel(x0, ym), pic.pixel(x1 - 1, ym));
    assert!(!close(bar_lo, bar_hi, 60));
    let at = |x: f64, y: f64| {
        let (px, py) = pic.project(&[x, y]);
        pic.pixel(px as usize, py as usize)
    };
    // the mesh's ends are the bar's ends; its middle is the bar's middle
    assert!(
        close(at(0.02, 4.0), bar_lo, 6),
        "{:06x} {bar_lo:06x}",
        at(0.02, 4.0)
    );
    assert!(
        close(at(7.98, 4.0), bar_hi, 6),
        "{:06x} {bar_hi:06x}",
        at(7.98, 4.0)
    );
    let bar_mid = pic.pixel((x0 + x1 - 1) / 2, ym);
    assert!(
        close(at(4.0, 4.0), bar_mid, 8),
        "{:06x} {bar_mid:06x}",
        at(4.0, 4.0)
    );
    // the ends are labelled: dark text pixels left and right of the bar
    let ink = |xs: std::ops::Range<usize>| {
        xs.flat_map(|x| (y0..y1).map(move |y| (x, y)))
            .any(|(x, y)| pic.pixel(x, y) == 0x20_20_20)
    };
    assert!(ink(x0.saturating_sub(60)..x0) && ink(x1..x1 + 60));
    // along a row the colour runs from one end to the other: distinct colours, gradually
    let (ax, ay) = pic.project(&[0.0, 4.0]);
    let (bx, _) = pic.project(&[8.0, 4.0]);
    let row: Vec<u32> = (ax as usize + 1..bx as usize - 1)
        .map(|x| pic.pixel(x, ay as usize))
        .collect();
    assert!(row.windows(2).all(|w| close(w[0], w[1], 8)));
    let mut d = row.clone();
    d.sort_unstable();
    d.dedup();
    assert!(d.len() > 50, "{} colours", d.len());
    // no field of that name
    o.attribute = Some("pressure".into());
    assert!(matches!(
        render(&k, &o),
        Err(RenderError::NoAttribute { .. })
    ));
}

/// A roof: two quads meeting at a ridge along x = 0 at height `h`.
fn roof(h: f64) -> IndexedComplex {
    complex(
        3,
        &[
            &[-1.0, 0.0, 0.0],
            &[-1.0, 1.0, 0.0],
            &[0.0, 0.0, h],
            &[0.0, 1.0, h],
            &[1.0, 0.0, 0.0],
            &[1.0, 1.0, 0.0],
        ],
        &[
            (CellKind::Quad, &[0, 2, 3, 1]),
            (CellKind::Quad, &[2, 4, 5, 3]),
        ],
    )
}

#[test]
fn smooth_shading_hides_a_gentle_crease_flat_shading_shows() {
    // faces 16.7 degrees from the ridge's vertex normal (a dihedral of 33 degrees): smooth
    let k = roof(0.3);
    let mut o = bare(400, 300, View::Top);
    o.shading = true;
    let flat = render(&k, &o).unwrap();
    o.smooth = true;
    let smooth = render(&k, &o).unwrap();
    let at = |pic: &starplex::render::Picture, x: f64| {
        let (px, py) = pic.project(&[x, 0.5, 0.0]);
        pic.pixel(px as usize, py as usize)
    };
    // flat: one colour per face, a jump at the ridge
    assert_eq!(at(&flat, -0.9), at(&flat, -0.1));
    assert_eq!(at(&flat, 0.9), at(&flat, 0.1));
    assert!(!close(at(&flat, -0.02), at(&flat, 0.02), 10));
    // smooth: continuous across the ridge, varying within a face
    assert!(close(at(&smooth, -0.02), at(&smooth, 0.02), 3));
    assert!(!close(at(&smooth, 0.9), at(&smooth, 0.1), 5));
    // at the outer edges smooth and flat agree (the vertex normal is the face's)
    assert!(close(at(&smooth, -0.99), at(&flat, -0.99), 3));
    assert!(close(at(&smooth, 0.99), at(&flat, 0.99), 3));
}

#[test]
fn smooth_shading_keeps_a_hard_edge_sharp() {
    // faces 63 degrees from the ridge's vertex normal (more than CREASE_DEGREES): the ridge
    // stays a sharp edge, each face lit flat as with flat shading
    const { assert!(starplex::render::CREASE_DEGREES < 63.0) };
    let k = roof(2.0);
    let mut o = bare(400, 300, View::Iso);
    o.shading = true;
    let flat = render(&k, &o).unwrap();
    o.smooth = true;
    let smooth = render(&k, &o).unwrap();
    let differ = flat
        .pixels
        .iter()
        .zip(&smooth.pixels)
        .filter(|(a, b)| !close(**a, **b, 2))
        .count();
    assert_eq!(differ, 0, "{differ} pixels differ from flat shading");
}

#[test]
fn a_perspective_camera_looks_at_its_target_and_shrinks_far_things() {
    // two equal squares on the floor, one near the eye, one far, told apart by their label
    let mut k = complex(
        3,
        &[
            &[0.0, 0.0, 0.0],
            &[1.0, 0.0, 0.0],
            &[1.0, 1.0, 0.0],
            &[0.0, 1.0, 0.0],
            &[0.0, 4.0, 0.0],
            &[1.0, 4.0, 0.0],
            &[1.0, 5.0, 0.0],
            &[0.0, 5.0, 0.0],
        ],
        &[
            (CellKind::Quad, &[0, 1, 2, 3]),
            (CellKind::Quad, &[4, 5, 6, 7]),
        ],
    );
    let near: Vec<i64> = k
        .cells()
        .map(|c| i64::from(c.vertices.contains(&0)))
        .collect();
    k.set_attributes(Attributes {
        vertex: vec![],
        cell: vec![Attribute::int("near", 1, near)],
    })
    .unwrap();
    let mut o = bare(400, 400, View::Top);
    o.colour = ColorMode::Label;
    o.attribute = Some("near".into());
    o.camera = Some(Eye {
        eye: [0.5, -3.0, 2.0],
        target: Some([0.5, 2.5, 0.0]),
    });
    let pic = render(&k, &o).unwrap();
    let (tx, ty) = pic.project(&[0.5, 2.5, 0.0]);
    assert!((tx - 200.0).abs() < 1e-6 && (ty - 200.0).abs() < 1e-6);
    let colour_of = |p: [f64; 3]| {
        let (x, y) = pic.project(&p);
        pic.pixel(x as usize, y as usize)
    };
    let (cn, cf) = (colour_of([0.5, 0.5, 0.0]), colour_of([0.5, 4.5, 0.0]));
    assert!(cn != cf && cn != WHITE && cf != WHITE);
    let count = |c: u32| pic.pixels.iter().filter(|&&p| p == c).count();
    assert!(count(cn) > 3 * count(cf), "{} {}", count(cn), count(cf));
    // the far square is nearer the top of the picture, and narrower
    let (n0, n1) = (pic.project(&[0.0, 0.0, 0.0]), pic.project(&[1.0, 0.0, 0.0]));
    let (f0, f1) = (pic.project(&[0.0, 5.0, 0.0]), pic.project(&[1.0, 5.0, 0.0]));
    assert!(f0.1 < n0.1 && (f1.0 - f0.0) < 0.5 * (n1.0 - n0.0));
    // everything in the picture (with the margin)
    for p in [n0, n1, f0, f1] {
        assert!(p.0 >= 0.0 && p.0 <= 400.0 && p.1 >= 0.0 && p.1 <= 400.0);
    }
    // an eye on its target has no direction
    o.camera = Some(Eye {
        eye: [0.5, 2.5, 0.0],
        target: Some([0.5, 2.5, 0.0]),
    });
    assert!(matches!(render(&k, &o), Err(RenderError::EyeIsTarget)));
}

/// One cell of each volume kind, positively oriented (VTK), apart from each other; with
/// `mirror`, the cell of that kind reflected in x (so inverted).
fn one_of_each(mirror: Option<CellKind>) -> IndexedComplex {
    let cells: [(CellKind, Vec<[f64; 3]>); 4] = [
        (
            CellKind::Simplex(3),
            vec![[0., 0., 0.], [1., 0., 0.], [0., 1., 0.], [0., 0., 1.]],
        ),
        (
            CellKind::Hex,
            vec![
                [0., 0., 0.],
                [1., 0., 0.],
                [1., 1., 0.],
                [0., 1., 0.],
                [0., 0., 1.],
                [1., 0., 1.],
                [1., 1., 1.],
                [0., 1., 1.],
            ],
        ),
        (
            CellKind::Prism, // VTK wedge: 0 1 2 turns away from 3 4 5
            vec![
                [0., 0., 0.],
                [0., 1., 0.],
                [1., 0., 0.],
                [0., 0., 1.],
                [0., 1., 1.],
                [1., 0., 1.],
            ],
        ),
        (
            CellKind::Pyramid,
            vec![
                [0., 0., 0.],
                [1., 0., 0.],
                [1., 1., 0.],
                [0., 1., 0.],
                [0.5, 0.5, 1.],
            ],
        ),
    ];
    let mut b = ComplexBuilder::new(3).unwrap();
    let mut next = 0u32;
    for (i, (kind, pts)) in cells.iter().enumerate() {
        let ids: Vec<u32> = (next..next + pts.len() as u32).collect();
        next += pts.len() as u32;
        for p in pts {
            let x = if mirror == Some(*kind) { -p[0] } else { p[0] };
            b.push_vertex(&[x + 3.0 * i as f64, p[1], p[2]]).unwrap();
        }
        b.push_cell(*kind, &ids).unwrap();
    }
    b.build(&BuildOptions::default()).unwrap().0
}

#[test]
fn inverted_prisms_and_pyramids_are_found() {
    let mut o = bare(300, 200, View::Iso);
    o.colour = ColorMode::Defects;
    let inverted = |k: &IndexedComplex| {
        render(k, &o)
            .unwrap()
            .summary
            .defects
            .iter()
            .find(|d| d.0 == "inverted or flat cells")
            .map(|d| d.1)
    };
    // the four kinds agree on what is positive
    assert_eq!(inverted(&one_of_each(None)), Some(0));
    for kind in [
        CellKind::Simplex(3),
        CellKind::Hex,
        CellKind::Prism,
        CellKind::Pyramid,
    ] {
        assert_eq!(inverted(&one_of_each(Some(kind))), Some(1), "{kind:?}");
    }
    // a flattened pyramid (apex in the base plane) is flat
    let k = one_of_each(None);
    let mut xyz = k.coords().to_vec();
    let apex = xyz.len() - 1;
    xyz[apex] = 0.0;
    let k2 = IndexedComplex::from_parts(
        3,
        xyz.into(),
        k.blocks()
            .iter()
            .map(|b| {
                (
                    b.kind,
                    (0..b.len())
                        .flat_map(|i| b.cell(i).to_vec())
                        .collect::<Vec<u32>>()
                        .into(),
                )
            })
            .collect(),
    )
    .unwrap();
    assert_eq!(inverted(&k2), Some(1));
}

#[test]
fn a_given_validation_is_used_not_recomputed() {
    let k = two_quads();
    let mut fake = starplex::algo::validate::validate(&starplex::topo::naive::VtIndex::new(&k));
    assert!(fake.non_manifold_vertices.is_empty());
    fake.non_manifold_vertices.push(starplex::ids::VertexId(4));
    let mut o = bare(300, 200, View::Top);
    o.colour = ColorMode::Defects;
    let pic = render_with(
        &k,
        &o,
        Given {
            validation: Some(&fake),
            ..Default::default()
        },
    )
    .unwrap();
    assert!(pic
        .summary
        .defects
        .contains(&("non-manifold vertices".into(), 1)));
    let (x, y) = pic.project(&[1.0, 1.0]);
    assert!(pixels_near(&pic, x, y, 2).contains(&0xFF_00_80));
    // and a given tree for blocks
    let t = starplex::stellar::StellarTree::build(
        &k,
        &starplex::stellar::StellarOptions {
            kv: Some(1),
            ..Default::default()
        },
    )
    .unwrap();
    o.colour = ColorMode::Blocks;
    let given = render_with(
        &k,
        &o,
        Given {
            tree: Some(&t),
            ..Default::default()
        },
    )
    .unwrap();
    o.kv = Some(1);
    let built = render(&k, &o).unwrap();
    assert_eq!(given.pixels, built.pixels);
}

/// The squares `x < cols`, `y < rows` of a grid of unit squares in the plane z = 0, two
/// triangles each (only their vertices).
fn grid_part(cols: u32, rows: u32) -> IndexedComplex {
    let m = cols + 1;
    let pts: Vec<Vec<f64>> = (0..m * (rows + 1))
        .map(|i| vec![f64::from(i % m), f64::from(i / m), 0.0])
        .collect();
    let pts: Vec<&[f64]> = pts.iter().map(|p| p.as_slice()).collect();
    let mut tris = Vec::new();
    for y in 0..rows {
        for x in 0..cols {
            let a = y * m + x;
            tris.push([a, a + 1, a + m + 1]);
            tris.push([a, a + m + 1, a + m]);
        }
    }
    let cells: Vec<(CellKind, &[u32])> = tris
        .iter()
        .map(|t| (CellKind::Simplex(2), t.as_slice()))
        .collect();
    complex(3, &pts, &cells)
}

#[test]
fn a_common_frame_puts_two_complexes_on_one_scale() {
    // a quarter of a grid, framed with the whole grid, lands on the whole grid's pixels
    let (whole, left) = (grid_part(10, 10), grid_part(5, 5));
    let frame = starplex::render::frame_around(&[&whole, &left]);
    assert_eq!(frame, Some([[0.0; 3], [10.0, 10.0, 0.0]]));
    for view in [None, Some(View::Iso)] {
        let o = RenderOptions {
            view,
            frame,
            ..bare(240, 200, View::Top)
        };
        let a = render(&whole, &o).unwrap();
        let b = render(&left, &o).unwrap();
        let drawn =
            |p: &starplex::render::Picture| p.pixels.iter().filter(|&&c| c != WHITE).count();
        let inside = a
            .pixels
            .iter()
            .zip(&b.pixels)
            .filter(|&(&pa, &pb)| pb != WHITE && pa != WHITE)
            .count();
        let (na, nb) = (drawn(&a), drawn(&b));
        assert!(
            inside as f64 >= 0.99 * nb as f64,
            "{view:?}: {inside} of {nb} inside"
        );
        let share = nb as f64 / na as f64;
        assert!(
            (0.2..0.3).contains(&share),
            "{view:?}: the quarter covers {share} of the whole"
        );
        // without the frame the quarter fills the picture on its own
        let alone = render(
            &left,
            &RenderOptions {
                frame: None,
                ..o.clone()
            },
        )
        .unwrap();
        assert!(
            drawn(&alone) as f64 > 3.0 * nb as f64,
            "{view:?}: not rescaled alone"
        );
        // the two halves of a comparison picture are the two framed pictures
        let both = a.beside(&b);
        assert_eq!(both.width, 2 * a.width + 1); // a grey rule between
        for y in (0..a.height).step_by(7) {
            for x in (0..a.width).step_by(5) {
                assert_eq!(both.pixel(x, y), a.pixel(x, y));
                assert_eq!(both.pixel(a.width + 1 + x, y), b.pixel(x, y));
            }
        }
    }
}
