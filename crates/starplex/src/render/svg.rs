//! The SVG writer: visible faces back to front as paths, then lines, dots, markers, caption.
use std::fmt::Write;

use super::camera::Camera;
use super::colour::{self, hex};
use super::{font, Marker, Prepared, RenderOptions};

/// Area in pixels of a polygon's projection.
pub(crate) fn projected_area(vs: &[u32], pos: &[[f64; 3]], cam: &Camera) -> f64 {
    let p: Vec<[f64; 3]> = vs.iter().map(|&v| cam.project(pos[v as usize])).collect();
    let mut a = 0.0;
    for i in 0..p.len() {
        let (u, w) = (p[i], p[(i + 1) % p.len()]);
        a += u[0] * w[1] - w[0] * u[1];
    }
    0.5 * a.abs()
}

fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// The document: `visible` faces (back to front) in their shaded colours `cols`.
pub(crate) fn document(p: &Prepared, o: &RenderOptions, visible: &[u32], cols: &[u32]) -> String {
    let (w, h) = (o.width, o.height);
    let mut s = String::new();
    let _ = writeln!(s, r#"<?xml version="1.0" encoding="UTF-8"?>"#);
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}">"#
    );
    let _ = writeln!(
        s,
        r#"<rect width="{w}" height="{h}" fill="{}"/>"#,
        hex(colour::BACKGROUND)
    );
    faces(&mut s, p, o, visible, cols);
    let unit = (f64::from(w.min(h)) / 600.0).max(1.0);
    lines_and_points(&mut s, p, unit);
    markers(&mut s, p, unit, (f64::from(w.min(h)) / 120.0).max(5.0));
    if o.legend {
        caption(&mut s, p, (0.02 * f64::from(w.min(h))).max(2.0));
    }
    let _ = writeln!(s, "</svg>");
    s
}

/// The screen position of vertex `v`.
fn screen(p: &Prepared, v: u32) -> (f64, f64) {
    let s = p.cam.project(p.scene.pos[v as usize]);
    (s[0], s[1])
}

/// The faces group: one path per visible face, back to front.
fn faces(s: &mut String, p: &Prepared, o: &RenderOptions, visible: &[u32], cols: &[u32]) {
    let pr = |v: u32| screen(p, v);
    let stroke = if o.edges {
        format!(r#" stroke="{}" stroke-width="0.6""#, hex(colour::WIRE))
    } else {
        // a hairline of the face's own colour hides the seams between faces
        String::new()
    };
    let _ = writeln!(s, r#"<g id="faces" stroke-linejoin="round"{stroke}>"#);
    for &i in visible {
        let f = &p.scene.faces[i as usize];
        let mut d = String::new();
        for (j, &v) in f.verts().iter().enumerate() {
            let (x, y) = pr(v);
            let _ = write!(d, "{}{x:.2} {y:.2} ", if j == 0 { "M" } else { "L" });
        }
        d.push('Z');
        let c = hex(cols[i as usize]);
        if o.edges {
            let _ = writeln!(s, r#"<path d="{d}" fill="{c}"/>"#);
        } else {
            let _ = writeln!(
                s,
                r#"<path d="{d}" fill="{c}" stroke="{c}" stroke-width="0.5"/>"#
            );
        }
    }
    let _ = writeln!(s, "</g>");
}

/// The 1D and 0D parts: edges as lines, isolated vertices as dots.
fn lines_and_points(s: &mut String, p: &Prepared, unit: f64) {
    let pr = |v: u32| screen(p, v);
    let _ = writeln!(s, r#"<g id="lines" stroke-width="{unit:.2}" fill="none">"#);
    for (&(_, e), &c) in p.scene.lines.iter().zip(&p.line_colour) {
        let ((x0, y0), (x1, y1)) = (pr(e[0]), pr(e[1]));
        let _ = writeln!(
            s,
            r#"<line x1="{x0:.2}" y1="{y0:.2}" x2="{x1:.2}" y2="{y1:.2}" stroke="{}"/>"#,
            hex(c)
        );
    }
    let _ = writeln!(s, "</g>");
    let _ = writeln!(s, r#"<g id="points">"#);
    for (&(_, v), &c) in p.scene.points.iter().zip(&p.point_colour) {
        let (x, y) = pr(v);
        let _ = writeln!(
            s,
            r#"<circle cx="{x:.2}" cy="{y:.2}" r="{:.2}" fill="{}"/>"#,
            1.5 * unit,
            hex(c)
        );
    }
    let _ = writeln!(s, "</g>");
}

/// The defect markers: edges drawn thick, vertices and points as outlined discs of radius `r`.
fn markers(s: &mut String, p: &Prepared, unit: f64, r: f64) {
    let pr = |v: u32| screen(p, v);
    let _ = writeln!(s, r#"<g id="defects">"#);
    for m in &p.markers {
        if let Marker::Edge(e, c, t) = m {
            let ((x0, y0), (x1, y1)) = (pr(e[0]), pr(e[1]));
            let _ = writeln!(
                s,
                r#"<line x1="{x0:.2}" y1="{y0:.2}" x2="{x1:.2}" y2="{y1:.2}" stroke="{}" stroke-width="{}"/>"#,
                hex(*c),
                *t as f64 * unit
            );
        }
    }
    for m in &p.markers {
        let (x, y, c, rr) = match m {
            Marker::Vertex(v, c) => {
                let (x, y) = pr(*v);
                (x, y, *c, r)
            }
            Marker::At(q, c) => {
                let q = p.cam.project(*q);
                (q[0], q[1], *c, 0.6 * r)
            }
            Marker::Edge(..) => continue,
        };
        let _ = writeln!(
            s,
            r#"<circle cx="{x:.2}" cy="{y:.2}" r="{rr:.2}" fill="{}" stroke="{}" stroke-width="1.5"/>"#,
            hex(c),
            hex(colour::OUTLINE)
        );
    }
    let _ = writeln!(s, "</g>");
}

/// The caption: legend rows with swatches, and the colour bar of a field, `x0` from the corner.
fn caption(s: &mut String, p: &Prepared, x0: f64) {
    let ts = p.text_scale;
    let lh = font::line_height(ts) as f64;
    let _ = writeln!(
        s,
        r#"<g id="caption" font-family="sans-serif" font-size="{:.1}" fill="{}">"#,
        7.0 * ts as f64 * 1.3,
        hex(colour::INK)
    );
    for (k, (sw, text)) in p.summary.legend.iter().take(p.caption_rows).enumerate() {
        let y = x0 + k as f64 * lh;
        let mut x = x0;
        if let Some(c) = sw {
            let sz = 7.0 * ts as f64;
            let _ = writeln!(
                s,
                r#"<rect x="{x:.1}" y="{y:.1}" width="{sz:.1}" height="{sz:.1}" fill="{}" stroke="{}"/>"#,
                hex(*c),
                hex(colour::OUTLINE)
            );
            x += sz + 3.0 * ts as f64;
        }
        let _ = writeln!(
            s,
            r#"<text x="{x:.1}" y="{:.1}">{}</text>"#,
            y + 7.0 * ts as f64,
            esc(text)
        );
    }
    if let Some(super::ColourBar {
        lo,
        hi,
        rect: Some(r),
        ..
    }) = &p.summary.colour_bar
    {
        let [x0, y0, x1, y1] = r.map(|v| v as f64);
        let _ = writeln!(s, r#"<defs><linearGradient id="ramp">"#);
        for i in 0..=8 {
            let t = f64::from(i) / 8.0;
            let _ = writeln!(
                s,
                r#"<stop offset="{t:.3}" stop-color="{}"/>"#,
                hex(colour::ramp(t))
            );
        }
        let _ = writeln!(s, "</linearGradient></defs>");
        let _ = writeln!(
            s,
            r#"<rect x="{x0:.1}" y="{y0:.1}" width="{:.1}" height="{:.1}" fill="url(#ramp)" stroke="{}"/>"#,
            x1 - x0,
            y1 - y0,
            hex(colour::OUTLINE)
        );
        let ty = y0 + 7.0 * ts as f64;
        let _ = writeln!(
            s,
            r#"<text x="{:.1}" y="{ty:.1}" text-anchor="end">{}</text>"#,
            x0 - 6.0 * ts as f64,
            esc(&super::short(*lo))
        );
        let _ = writeln!(
            s,
            r#"<text x="{:.1}" y="{ty:.1}">{}</text>"#,
            x1 + 6.0 * ts as f64,
            esc(&super::short(*hi))
        );
    }
    let _ = writeln!(s, "</g>");
}
