//! What is drawn: polygons (triangles and quads: 2-cells, the boundary of the kept 3-cells, the
//! 2-skeleton of higher simplices), lines (1-cells), dots (0-cells and isolated vertices), each
//! with the top cell it comes from.
use rustc_hash::FxHashSet;

use super::Clip;
use crate::algo::surface::boundary_facets;
use crate::cell::CellKind;
use crate::complex::IndexedComplex;
use crate::ids::CellId;

/// Not from a top cell (an isolated vertex).
pub(crate) const NO_CELL: u32 = u32::MAX;

/// Triangles of the 2-skeleton of higher simplices shown at most.
const MAX_SKELETON_TRIANGLES: usize = 20_000_000;

/// A drawn polygon.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Face {
    /// The top cell it comes from.
    pub cell: u32,
    /// 3 or 4.
    pub n: u8,
    /// Its vertices (input ids); the first `n` are used.
    pub v: [u32; 4],
    /// A face opened by the clipping plane (not on the boundary of the whole mesh).
    pub exposed: bool,
}

impl Face {
    pub(crate) fn verts(&self) -> &[u32] {
        &self.v[..self.n as usize]
    }
}

/// Everything drawn, with the positions of all input vertices (first three coordinates, turned
/// so that the chosen up axis is z).
pub(crate) struct Scene {
    pub pos: Vec<[f64; 3]>,
    pub faces: Vec<Face>,
    pub lines: Vec<(u32, [u32; 2])>,
    pub points: Vec<(u32, u32)>,
    pub notes: Vec<String>,
    /// Top cells removed by the clipping plane.
    pub clipped_cells: usize,
}

impl Scene {
    /// Vertices used by a drawn primitive, once each.
    pub(crate) fn used(&self) -> Vec<u32> {
        let mut seen = vec![false; self.pos.len()];
        let mut out = Vec::new();
        let mut mark = |v: u32| {
            if !std::mem::replace(&mut seen[v as usize], true) {
                out.push(v);
            }
        };
        self.faces
            .iter()
            .for_each(|f| f.verts().iter().for_each(|&v| mark(v)));
        self.lines
            .iter()
            .for_each(|(_, e)| e.iter().for_each(|&v| mark(v)));
        self.points.iter().for_each(|&(_, v)| mark(v));
        out
    }
}

/// The order of the input axes that makes axis `up` the third: up = 2: (x, y, z); up = 1:
/// (z, x, y); up = 0: (y, z, x) (cyclic: right-handed).
pub(crate) fn axis_order(up: usize) -> [usize; 3] {
    match up {
        0 => [1, 2, 0],
        1 => [2, 0, 1],
        _ => [0, 1, 2],
    }
}

/// A point in input coordinates, cycled like [`positions`].
pub(crate) fn turn(p: [f64; 3], up: usize) -> [f64; 3] {
    axis_order(up).map(|a| p[a])
}

/// Input coordinates (first three, zero-padded) of every vertex, cycled so that axis `up` is
/// the third.
pub(crate) fn positions(k: &IndexedComplex, up: usize) -> Vec<[f64; 3]> {
    let amb = k.ambient_dim();
    let c = k.coords();
    let get = |v: usize, a: usize| if a < amb { c[v * amb + a] } else { 0.0 };
    let order = axis_order(up);
    (0..k.n_vertices())
        .map(|v| order.map(|a| get(v, a)))
        .collect()
}

/// The centroid coordinate `axis` (input axes) of a cell.
fn centroid(k: &IndexedComplex, vs: &[u32], axis: usize) -> f64 {
    let amb = k.ambient_dim();
    if axis >= amb {
        return 0.0;
    }
    let c = k.coords();
    vs.iter().map(|&v| c[v as usize * amb + axis]).sum::<f64>() / vs.len() as f64
}

fn push_polygon(faces: &mut Vec<Face>, cell: u32, vs: &[u32], exposed: bool) {
    let mut v = [0u32; 4];
    v[..vs.len()].copy_from_slice(vs);
    faces.push(Face {
        cell,
        n: vs.len() as u8,
        v,
        exposed,
    });
}

/// The scene of `k`, clipped by `clip` (cells whose centroid lies beyond the plane are
/// removed), with the faces opened by the plane marked when `mark_exposed`.
pub(crate) fn build(
    k: &IndexedComplex,
    clip: Option<Clip>,
    up: usize,
    mark_exposed: bool,
) -> Scene {
    let mut s = Scene {
        pos: positions(k, up),
        faces: Vec::new(),
        lines: Vec::new(),
        points: Vec::new(),
        notes: Vec::new(),
        clipped_cells: 0,
    };
    if k.ambient_dim() > 3 {
        s.notes.push(format!(
            "ambient dimension {}: projected from the first three coordinates",
            k.ambient_dim()
        ));
    }
    let keep = |c: CellId| match clip {
        None => true,
        Some(p) => centroid(k, k.cell(c).vertices, p.axis) <= p.value,
    };
    let mut keep_mask = vec![true; k.n_cells()];
    if clip.is_some() {
        for (c, m) in keep_mask.iter_mut().enumerate() {
            *m = keep(CellId(c as u32));
            s.clipped_cells += usize::from(!*m);
        }
    }
    let kept = |c: CellId| keep_mask[c.0 as usize];
    let has3 = k.blocks().iter().any(|b| b.kind.dim() == 3);
    if has3 {
        let (facets, _) = boundary_facets(k, 3, kept);
        let skin: Option<FxHashSet<Vec<u32>>> = (clip.is_some() && mark_exposed).then(|| {
            boundary_facets(k, 3, |_| true)
                .0
                .into_iter()
                .map(|f| {
                    let mut v = f.vertices.to_vec();
                    v.sort_unstable();
                    v
                })
                .collect()
        });
        for f in facets {
            let exposed = skin.as_ref().is_some_and(|sk| {
                let mut v = f.vertices.to_vec();
                v.sort_unstable();
                !sk.contains(&v)
            });
            push_polygon(&mut s.faces, f.cell.0, &f.vertices, exposed);
        }
    }
    let mut skeleton: FxHashSet<[u32; 3]> = FxHashSet::default();
    let mut high_dim = 0usize;
    let mut truncated = false;
    for b in k.blocks() {
        for i in 0..b.len() {
            let id = b.first + i as u32;
            if !keep_mask[id as usize] {
                continue;
            }
            let c = b.cell(i);
            match b.kind {
                CellKind::Simplex(0) => s.points.push((id, c[0])),
                CellKind::Simplex(1) => s.lines.push((id, [c[0], c[1]])),
                CellKind::Simplex(2) | CellKind::Quad => push_polygon(&mut s.faces, id, c, false),
                CellKind::Simplex(d) if d >= 4 => {
                    high_dim = high_dim.max(d as usize);
                    let n = c.len();
                    'all: for x in 0..n {
                        for y in x + 1..n {
                            for z in y + 1..n {
                                if skeleton.len() >= MAX_SKELETON_TRIANGLES {
                                    truncated = true;
                                    break 'all;
                                }
                                let mut t = [c[x], c[y], c[z]];
                                t.sort_unstable();
                                if skeleton.insert(t) {
                                    push_polygon(&mut s.faces, id, &t, false);
                                }
                            }
                        }
                    }
                }
                _ => {} // 3-cells: their boundary, above
            }
        }
    }
    if high_dim > 0 {
        s.notes.push(format!(
            "cells up to dimension {high_dim}: shown by their 2-skeleton ({} triangles){}",
            skeleton.len(),
            if truncated {
                format!(" (only the first {MAX_SKELETON_TRIANGLES})")
            } else {
                String::new()
            }
        ));
    }
    let used = k.used_vertices();
    for v in 0..k.n_vertices() {
        let v32 = v as u32;
        if !used.contains(v) && clip.is_none_or(|p| centroid(k, &[v32], p.axis) <= p.value) {
            s.points.push((NO_CELL, v32));
        }
    }
    s
}
