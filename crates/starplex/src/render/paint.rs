//! Colours and markers of a picture, one function per colour mode: Stellar leaves, components,
//! boundary, attribute labels and fields, defects (with inverted cells).

use super::scene::Scene;
use super::{
    colour, short, thousands, ColorMode, ColourBar, Given, Marker, RenderError, RenderOptions,
    Summary,
};
use crate::algo::components::components;
use crate::algo::surface::boundary_facets;
use crate::algo::validate::{validate, ValidationReport};
use crate::cell::CellKind;
use crate::complex::IndexedComplex;
use crate::ids::LeafId;
use crate::stellar::{StellarOptions, StellarTree};
use crate::topo::naive::VtIndex;

/// Labels listed one by one in the legend, at most.
const MAX_LABELS_LISTED: usize = 12;

/// What a colour mode decides: a colour per cell (and per vertex for points and fields),
/// markers drawn on top, and the legend lines.
pub(super) struct Paint {
    pub(super) cell_colour: Vec<u32>,
    pub(super) vertex_colour: Option<Vec<u32>>,
    /// Per-vertex colours the faces are shaded between (field colouring).
    pub(super) vertex_base: Option<Vec<u32>>,
    pub(super) markers: Vec<Marker>,
    pub(super) legend: Vec<(Option<u32>, String)>,
}

/// Colours `k` as `o.colour` says, reusing the results in `given`.
pub(super) fn paint(
    k: &IndexedComplex,
    o: &RenderOptions,
    given: &Given<'_>,
    scene: &Scene,
    summary: &mut Summary,
) -> Result<Paint, RenderError> {
    let mut p = Paint {
        cell_colour: vec![colour::PLAIN; k.n_cells()],
        vertex_colour: None,
        vertex_base: None,
        markers: Vec::new(),
        legend: Vec::new(),
    };
    match o.colour {
        ColorMode::Plain => {}
        ColorMode::Blocks => blocks(k, o, given.tree, &mut p, summary)?,
        ColorMode::Components => by_component(k, &mut p, summary),
        ColorMode::Boundary => boundary(k, o, scene, &mut p),
        ColorMode::Label | ColorMode::Field => attribute(k, o, &mut p, summary)?,
        ColorMode::Defects => defects(k, given.validation, scene, &mut p, summary),
    }
    Ok(p)
}

/// One colour per Stellar tree leaf (the tree given, or one built with `o.kv`).
fn blocks(
    k: &IndexedComplex,
    o: &RenderOptions,
    given: Option<&StellarTree>,
    p: &mut Paint,
    summary: &mut Summary,
) -> Result<(), RenderError> {
    let Paint {
        cell_colour,
        vertex_colour,
        legend,
        ..
    } = p;
    let built;
    let t = match given {
        Some(t) => t,
        None => {
            built = StellarTree::build(
                k,
                &StellarOptions {
                    kv: o.kv,
                    ..Default::default()
                },
            )?;
            &built
        }
    };
    let mut leaf_of = vec![0u32; k.n_vertices()];
    let mut tree_index = vec![0u32; k.n_vertices()];
    let v_in = t.vertex_to_input();
    let mut used = 0;
    for l in 0..t.n_leaves() {
        let r = t.leaf_vertices(LeafId(l as u32));
        used += usize::from(!r.is_empty());
        for tv in r {
            leaf_of[v_in[tv as usize].index()] = l as u32;
            tree_index[v_in[tv as usize].index()] = tv;
        }
    }
    for (c, col) in k.cells().zip(cell_colour.iter_mut()) {
        let first = c
            .vertices
            .iter()
            .copied()
            .min_by_key(|&v| tree_index[v as usize])
            .unwrap_or(0);
        *col = colour::categorical(leaf_of[first as usize]);
    }
    *vertex_colour = Some(leaf_of.iter().map(|&l| colour::categorical(l)).collect());
    summary.n_colours = used;
    legend.push((
        Some(colour::categorical(0)),
        format!(
            "colour: Stellar tree leaf, {} leaves (kv = {})",
            thousands(used),
            t.kv()
        ),
    ));
    Ok(())
}

/// One colour per connected component.
fn by_component(k: &IndexedComplex, p: &mut Paint, summary: &mut Summary) {
    let Paint {
        cell_colour,
        vertex_colour,
        legend,
        ..
    } = p;
    let comp = components(&VtIndex::new(k));
    for (c, col) in k.cells().zip(cell_colour.iter_mut()) {
        *col = colour::categorical(comp.label[c.vertices[0] as usize]);
    }
    *vertex_colour = Some(comp.label.iter().map(|&l| colour::categorical(l)).collect());
    summary.n_colours = comp.n_components;
    legend.push((
        Some(colour::categorical(0)),
        format!(
            "colour: connected component, {} components",
            thousands(comp.n_components)
        ),
    ));
}

/// Boundary edges of the 2-cells marked; faces cut open by a clip counted.
fn boundary(k: &IndexedComplex, o: &RenderOptions, scene: &Scene, p: &mut Paint) {
    let Paint {
        markers, legend, ..
    } = p;
    if k.dim() == Some(2) || (k.dim() == Some(3) && o.clip.is_none()) {
        let d = k.dim().unwrap_or(2);
        // the boundary edges of the 2-cells (facets of the 2-cells in one 2-cell)
        let edges = boundary_facets(k, 2, |_| true).0;
        let kept = |c: u32| {
            o.clip.is_none_or(|p| {
                let vs = k.cell(crate::ids::CellId(c)).vertices;
                let amb = k.ambient_dim();
                p.axis >= amb
                    || vs
                        .iter()
                        .map(|&v| k.coords()[v as usize * amb + p.axis])
                        .sum::<f64>()
                        / vs.len() as f64
                        <= p.value
            })
        };
        let mut count = 0;
        for e in edges.iter().filter(|e| kept(e.cell.0)) {
            markers.push(Marker::Edge(
                [e.vertices[0], e.vertices[1]],
                colour::BOUNDARY,
                2,
            ));
            count += 1;
        }
        if d == 2 || count > 0 {
            legend.push((
                Some(colour::BOUNDARY),
                format!("boundary edges: {}", thousands(count)),
            ));
        }
    }
    let exposed = scene.faces.iter().filter(|f| f.exposed).count();
    if o.clip.is_some() && k.dim() == Some(3) {
        legend.push((
            Some(colour::PLAIN),
            format!("boundary faces: {}", thousands(scene.faces.len() - exposed)),
        ));
        legend.push((
            Some(colour::EXPOSED),
            format!("faces cut open: {}", thousands(exposed)),
        ));
    }
}

/// A cell label (one colour per value) or a vertex field (a colour ramp and a colour bar).
fn attribute(
    k: &IndexedComplex,
    o: &RenderOptions,
    p: &mut Paint,
    summary: &mut Summary,
) -> Result<(), RenderError> {
    let Paint {
        cell_colour,
        vertex_colour,
        vertex_base,
        legend,
        ..
    } = p;
    use crate::attr::AttrTarget;
    let target = if o.colour == ColorMode::Label {
        AttrTarget::Cell
    } else {
        AttrTarget::Vertex
    };
    let name = o.attribute.clone().unwrap_or_default();
    let Some(a) = k.attributes().get(target, &name) else {
        return Err(RenderError::NoAttribute {
            target,
            name,
            available: k
                .attributes()
                .of(target)
                .iter()
                .map(|a| a.name.clone())
                .collect(),
        });
    };
    // first component, or the length of a vector field
    let value = |i: usize| -> f64 {
        if target == AttrTarget::Vertex && a.components > 1 {
            (0..a.components)
                .map(|c| a.values.get_f64(i * a.components + c).powi(2))
                .sum::<f64>()
                .sqrt()
        } else {
            a.values.get_f64(i * a.components)
        }
    };
    if target == AttrTarget::Cell {
        let mut distinct: Vec<f64> = (0..k.n_cells())
            .map(value)
            .filter(|x| !x.is_nan())
            .collect();
        distinct.sort_by(f64::total_cmp);
        distinct.dedup();
        for (c, col) in cell_colour.iter_mut().enumerate() {
            let x = value(c);
            *col = match distinct.binary_search_by(|d| d.total_cmp(&x)) {
                Ok(i) => colour::categorical(i as u32),
                Err(_) => colour::MUTED,
            };
        }
        summary.n_colours = distinct.len();
        let mut count = vec![0usize; distinct.len()];
        let mut unlabelled = 0;
        for c in 0..k.n_cells() {
            let x = value(c);
            match distinct.binary_search_by(|d| d.total_cmp(&x)) {
                Ok(i) => count[i] += 1,
                Err(_) => unlabelled += 1,
            }
        }
        legend.push((
            None,
            format!(
                "colour: cell label {name}, {} values",
                thousands(distinct.len())
            ),
        ));
        for (i, (x, m)) in distinct.iter().zip(&count).enumerate() {
            if i == MAX_LABELS_LISTED && distinct.len() > MAX_LABELS_LISTED + 1 {
                legend.push((
                    None,
                    format!(
                        "and {} more values ({} cells)",
                        distinct.len() - i,
                        thousands(count[i..].iter().sum())
                    ),
                ));
                break;
            }
            legend.push((
                Some(colour::categorical(i as u32)),
                format!("{name} = {}: {} cells", short(*x), thousands(*m)),
            ));
        }
        if unlabelled > 0 {
            legend.push((
                Some(colour::MUTED),
                format!("no value (NaN): {} cells", thousands(unlabelled)),
            ));
        }
    } else {
        let vals: Vec<f64> = (0..k.n_vertices()).map(value).collect();
        let (lo, hi) = vals
            .iter()
            .filter(|x| x.is_finite())
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
                (a.min(x), b.max(x))
            });
        let span = if hi > lo { hi - lo } else { 1.0 };
        let map = |x: f64| {
            if x.is_finite() {
                colour::ramp(((x - lo) / span).clamp(0.0, 1.0))
            } else {
                colour::MUTED
            }
        };
        for (c, col) in k.cells().zip(cell_colour.iter_mut()) {
            let m =
                c.vertices.iter().map(|&v| vals[v as usize]).sum::<f64>() / c.vertices.len() as f64;
            *col = map(m);
        }
        *vertex_colour = Some(vals.iter().map(|&x| map(x)).collect());
        vertex_base.clone_from(vertex_colour);
        let (lo, hi) = if lo <= hi {
            (lo, hi)
        } else {
            (f64::NAN, f64::NAN)
        };
        legend.push((
            None,
            format!(
                "colour: vertex field {name}{}, from {} to {}",
                if a.components > 1 { " (length)" } else { "" },
                short(lo),
                short(hi)
            ),
        ));
        summary.colour_bar = Some(ColourBar {
            name: name.clone(),
            lo,
            hi,
            rect: None,
        });
    }
    Ok(())
}

/// Every defect of the validation report marked, and inverted or flat cells.
fn defects(
    k: &IndexedComplex,
    given: Option<&ValidationReport>,
    scene: &Scene,
    p: &mut Paint,
    summary: &mut Summary,
) {
    let Paint {
        cell_colour,
        markers,
        legend,
        ..
    } = p;
    cell_colour.fill(colour::MUTED);
    let owned;
    let r = match given {
        Some(r) => r,
        None => {
            owned = validate(&VtIndex::new(k));
            &owned
        }
    };
    let mut push = |name: &str, c: u32, count: usize| {
        summary.defects.push((name.to_string(), count));
        if count > 0 {
            legend.push((Some(c), format!("{name}: {}", thousands(count))));
        }
    };
    if r.dim == 2 {
        for f in &r.boundary_faces {
            if f.len() == 2 {
                markers.push(Marker::Edge([f[0].0, f[1].0], colour::BOUNDARY, 2));
            }
        }
        push("boundary edges", colour::BOUNDARY, r.boundary_faces.len());
    }
    let mut n_nm_faces = 0;
    for f in &r.faces_in_more_than_two_cells {
        n_nm_faces += 1;
        let vs: Vec<u32> = f.iter().map(|v| v.0).collect();
        for i in 0..vs.len() {
            let (a, b) = (vs[i], vs[(i + 1) % vs.len()]);
            if vs.len() == 2 && i == 1 {
                break;
            }
            markers.push(Marker::Edge([a, b], colour::NM_FACE, 4));
        }
    }
    let fname = if r.dim == 2 {
        "edges in more than two faces"
    } else {
        "faces in more than two cells"
    };
    push(fname, colour::NM_FACE, n_nm_faces);
    for e in &r.non_manifold_edges {
        markers.push(Marker::Edge([e[0].0, e[1].0], colour::NM_EDGE, 3));
    }
    push(
        "non-manifold edges",
        colour::NM_EDGE,
        r.non_manifold_edges.len(),
    );
    for v in &r.non_manifold_vertices {
        markers.push(Marker::Vertex(v.0, colour::NM_VERTEX));
    }
    push(
        "non-manifold vertices",
        colour::NM_VERTEX,
        r.non_manifold_vertices.len(),
    );
    // inverted cells: orientation against the majority (or flat)
    if k.ambient_dim() <= 3 {
        let signs: Vec<Option<i8>> = k
            .cells()
            .map(|c| cell_sign(c.kind, c.vertices, &scene.pos))
            .collect();
        let pos = signs.iter().filter(|s| **s == Some(1)).count();
        let neg = signs.iter().filter(|s| **s == Some(-1)).count();
        let good = if pos >= neg { 1 } else { -1 };
        let mut inverted = 0;
        let any = signs.iter().any(Option::is_some);
        for (c, s) in k.cells().zip(&signs) {
            if matches!(s, Some(x) if *x != good) {
                inverted += 1;
                cell_colour[c.id.0 as usize] = colour::INVERTED;
                let m = c.vertices.len() as f64;
                let mut p = [0.0; 3];
                for &v in c.vertices {
                    for (pa, &q) in p.iter_mut().zip(&scene.pos[v as usize]) {
                        *pa += q / m;
                    }
                }
                markers.push(Marker::At(p, colour::INVERTED));
            }
        }
        if any {
            push("inverted or flat cells", colour::INVERTED, inverted);
        }
    }
    if r.is_valid_manifold() && markers.is_empty() {
        legend.push((None, "no defects found".to_string()));
    }
}

/// Sign of the volume of a tetrahedron (a b c d).
fn tet_sign(a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3]) -> i8 {
    let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
    let w = [d[0] - a[0], d[1] - a[1], d[2] - a[2]];
    let det = u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0])
        + u[2] * (v[0] * w[1] - v[1] * w[0]);
    if det > 0.0 {
        1
    } else if det < 0.0 {
        -1
    } else {
        0
    }
}

/// The sign shared by the corner tetrahedra `corners` of a cell, 0 when they disagree (a
/// twisted cell) or one is flat.
fn corner_sign(corners: &[[usize; 4]], p: impl Fn(usize) -> [f64; 3]) -> i8 {
    let s0 = tet_sign(
        p(corners[0][0]),
        p(corners[0][1]),
        p(corners[0][2]),
        p(corners[0][3]),
    );
    if corners[1..]
        .iter()
        .all(|q| tet_sign(p(q[0]), p(q[1]), p(q[2]), p(q[3])) == s0)
    {
        s0
    } else {
        0
    }
}

/// Orientation of a 3-cell, +1 for the VTK orientation of its kind (a tetrahedron whose face
/// 0 1 2 turns, right-handed, towards vertex 3; a hexahedron, pyramid or prism whose faces of
/// [`CellKind::faces`] point outwards), -1 reversed, 0 when flat or twisted (its corner
/// tetrahedra disagree: 8 for a hexahedron, 6 for a prism, the 4 base corners of a pyramid);
/// `None` for other kinds.
fn cell_sign(kind: CellKind, c: &[u32], pos: &[[f64; 3]]) -> Option<i8> {
    let p = |i: usize| pos[c[i] as usize];
    match kind {
        CellKind::Simplex(3) => Some(tet_sign(p(0), p(1), p(2), p(3))),
        CellKind::Pyramid => {
            // at each base corner: the next and the previous base vertex, the apex
            const CORNERS: [[usize; 4]; 4] =
                [[0, 1, 3, 4], [1, 2, 0, 4], [2, 3, 1, 4], [3, 0, 2, 4]];
            Some(corner_sign(&CORNERS, p))
        }
        CellKind::Prism => {
            // the VTK wedge's triangle 0 1 2 turns away from 3 4 5
            const CORNERS: [[usize; 4]; 6] = [
                [0, 2, 1, 3],
                [1, 0, 2, 4],
                [2, 1, 0, 5],
                [3, 4, 5, 0],
                [4, 5, 3, 1],
                [5, 3, 4, 2],
            ];
            Some(corner_sign(&CORNERS, p))
        }
        CellKind::Hex => {
            const CORNERS: [[usize; 4]; 8] = [
                [0, 1, 3, 4],
                [1, 2, 0, 5],
                [2, 3, 1, 6],
                [3, 0, 2, 7],
                [4, 7, 5, 0],
                [5, 4, 6, 1],
                [6, 5, 7, 2],
                [7, 6, 4, 3],
            ];
            Some(corner_sign(&CORNERS, p))
        }
        _ => None,
    }
}
