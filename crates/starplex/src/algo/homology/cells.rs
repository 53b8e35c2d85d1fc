//! Cells of the cellular chain complex, identified by their sorted vertex set, with the
//! boundary operator read from the cell kinds' face tables and induced orientations.
//!
//! Reference orientations: a simplex is oriented by its sorted vertices; a quad by its
//! *canonical cycle* (rotated to start at its smallest vertex, running towards the smaller of
//! that vertex's two neighbours); a pyramid, prism or hexahedron (always a top cell) by the
//! order it was given in, so its facets come from the VTK tables with sign +1 before they are
//! compared with their own reference orientation.
use smallvec::SmallVec;

use crate::cell::CellKind;

/// Sorted vertex ids of a cell.
pub(crate) type Key = SmallVec<[u32; 8]>;

/// How the boundary of a cell is read.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub(crate) enum Shape {
    /// A simplex; `verts` is the sorted key.
    Simplex,
    /// A quad; `verts` is its canonical cycle.
    Quad,
    /// A pyramid, prism or hexahedron; `verts` in the kind's vertex order.
    Solid(CellKind),
}

/// A cell: its sorted key, shape, and oriented vertex list.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Cell {
    pub key: Key,
    pub shape: Shape,
    pub verts: Key,
}

impl Cell {
    /// A simplex from sorted vertices.
    pub fn simplex(key: Key) -> Cell {
        Cell {
            verts: key.clone(),
            key,
            shape: Shape::Simplex,
        }
    }

    /// Dimension.
    pub fn dim(&self) -> usize {
        match self.shape {
            Shape::Simplex => self.key.len() - 1,
            Shape::Quad => 2,
            Shape::Solid(k) => k.dim(),
        }
    }

    /// The largest vertex (the lower star the cell belongs to).
    pub fn max_vertex(&self) -> u32 {
        *self.key.last().expect("cells are not empty")
    }

    /// Appends the facets of the cell with their incidence numbers (+1 or -1).
    pub fn facets(&self, out: &mut Vec<(Cell, i8)>) {
        match self.shape {
            Shape::Simplex => {
                let n = self.key.len();
                if n < 2 {
                    return;
                }
                for i in 0..n {
                    let mut k = self.key.clone();
                    k.remove(i);
                    out.push((Cell::simplex(k), if i % 2 == 0 { 1 } else { -1 }));
                }
            }
            Shape::Quad => {
                for i in 0..4 {
                    let (a, b) = (self.verts[i], self.verts[(i + 1) % 4]);
                    let (k, s) = if a < b { ([a, b], 1) } else { ([b, a], -1) };
                    out.push((Cell::simplex(SmallVec::from_slice(&k)), s));
                }
            }
            Shape::Solid(kind) => {
                let table = kind.cp_faces(2).unwrap_or(&[]);
                for f in table {
                    let g: Key = f.iter().map(|&l| self.verts[l as usize]).collect();
                    out.push(oriented_face(&g));
                }
            }
        }
    }
}

/// A 2-face given by its vertices in cyclic (oriented) order: the cell in reference orientation
/// and the sign relating the two.
pub(crate) fn oriented_face(g: &[u32]) -> (Cell, i8) {
    match g.len() {
        4 => {
            let (c, s) = canonical_quad([g[0], g[1], g[2], g[3]]);
            (c, s)
        }
        _ => {
            let (k, s) = sort_with_sign(g);
            (Cell::simplex(k), s)
        }
    }
}

/// Sorts `g`, returning the sign of the sorting permutation.
pub(crate) fn sort_with_sign(g: &[u32]) -> (Key, i8) {
    let mut k: Key = SmallVec::from_slice(g);
    let mut sign = 1i8;
    // insertion sort counting transpositions (cells are small)
    for i in 1..k.len() {
        let mut j = i;
        while j > 0 && k[j - 1] > k[j] {
            k.swap(j - 1, j);
            sign = -sign;
            j -= 1;
        }
    }
    (k, sign)
}

/// The canonical cycle of a quad given in cyclic order, and the sign relating the given
/// orientation to the canonical one.
pub(crate) fn canonical_quad(q: [u32; 4]) -> (Cell, i8) {
    let m = (0..4).min_by_key(|&i| q[i]).unwrap_or(0);
    let r = [q[m], q[(m + 1) % 4], q[(m + 2) % 4], q[(m + 3) % 4]];
    let (verts, s) = if r[1] < r[3] {
        (r, 1)
    } else {
        ([r[0], r[3], r[2], r[1]], -1)
    };
    let mut key: Key = SmallVec::from_slice(&verts);
    key.sort_unstable();
    (
        Cell {
            key,
            shape: Shape::Quad,
            verts: SmallVec::from_slice(&verts),
        },
        s,
    )
}

/// The cell of a top cell of `kind` with vertices `verts` (kind order) in reference orientation,
/// with the sign of the given orientation relative to the reference.
pub(crate) fn top_cell(kind: CellKind, verts: &[u32]) -> Cell {
    match kind {
        CellKind::Simplex(_) => {
            let (k, _) = sort_with_sign(verts);
            Cell::simplex(k)
        }
        CellKind::Quad => canonical_quad([verts[0], verts[1], verts[2], verts[3]]).0,
        _ => {
            let mut key: Key = SmallVec::from_slice(verts);
            key.sort_unstable();
            Cell {
                key,
                shape: Shape::Solid(kind),
                verts: SmallVec::from_slice(verts),
            }
        }
    }
}

/// Appends the faces of a top CP cell (not a simplex) that contain `v` and whose largest vertex
/// is `v` (its lower-star faces), all dimensions, itself included.
pub(crate) fn cp_lower_star_faces(kind: CellKind, verts: &[u32], v: u32, out: &mut Vec<Cell>) {
    let d = kind.dim();
    for k in 0..=d {
        let Some(table) = kind.cp_faces(k) else {
            continue;
        };
        for f in table {
            let g: Key = f.iter().map(|&l| verts[l as usize]).collect();
            if !g.contains(&v) || g.iter().any(|&x| x > v) {
                continue;
            }
            let c = if k == d {
                top_cell(kind, verts)
            } else if g.len() == 4 {
                canonical_quad([g[0], g[1], g[2], g[3]]).0
            } else {
                let (key, _) = sort_with_sign(&g);
                Cell::simplex(key)
            };
            out.push(c);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn boundary2(c: &Cell) -> std::collections::BTreeMap<Key, i32> {
        let mut m = std::collections::BTreeMap::new();
        let mut f1 = Vec::new();
        c.facets(&mut f1);
        for (f, s) in f1 {
            let mut f2 = Vec::new();
            f.facets(&mut f2);
            for (g, t) in f2 {
                *m.entry(g.key).or_insert(0) += (s * t) as i32;
            }
        }
        m.retain(|_, v| *v != 0);
        m
    }

    #[test]
    fn boundary_of_boundary_is_zero() {
        let cases = [
            (CellKind::Hex, vec![7u32, 3, 5, 1, 0, 2, 6, 4]),
            (CellKind::Prism, vec![5, 0, 3, 2, 4, 1]),
            (CellKind::Pyramid, vec![4, 2, 0, 3, 1]),
            (CellKind::Quad, vec![3, 1, 0, 2]),
            (CellKind::Simplex(4), vec![0, 1, 2, 3, 4]),
        ];
        for (kind, v) in cases {
            let c = top_cell(kind, &v);
            assert!(boundary2(&c).is_empty(), "{kind}");
        }
    }

    #[test]
    fn quad_canonical() {
        let (a, s) = canonical_quad([5, 2, 9, 7]);
        assert_eq!(&a.verts[..], &[2, 5, 7, 9]);
        assert_eq!(s, -1);
        let (b, t) = canonical_quad([9, 7, 5, 2]); // same cycle, same direction
        assert_eq!((&a, s), (&b, t));
        let (c, u) = canonical_quad([7, 9, 2, 5]); // reversed
        assert_eq!((&a, 1), (&c, u));
    }
}
