//! Exact geometric checks of flips with robust predicates (`orient2d`, `orient3d` of the
//! `robust` crate): a topologically valid flip may still fold a planar triangulation or invert
//! tetrahedra; these tests decide it exactly.
use robust::{orient2d, orient3d, Coord, Coord3D};

use super::complex::Hasse;
use super::edit::{EditError, Position};
use super::levels::{At, LevelTypes};
use super::Node;
use crate::ids::VertexId;

fn c2(p: [f64; 3]) -> Coord<f64> {
    Coord { x: p[0], y: p[1] }
}
fn c3(p: [f64; 3]) -> Coord3D<f64> {
    Coord3D {
        x: p[0],
        y: p[1],
        z: p[2],
    }
}
fn sign(x: f64) -> i8 {
    if x > 0.0 {
        1
    } else if x < 0.0 {
        -1
    } else {
        0
    }
}

impl<L: LevelTypes> Hasse<L>
where
    L: At<0>,
    <L as At<0>>::Data: Position,
{
    fn position_of(&self, v: VertexId) -> [f64; 3] {
        self.vertex(v)
            .map_or([0.0; 3], |n| self.data::<0>(n.id).position())
    }

    /// Checks that the flip of `s` is also geometrically valid, exactly:
    /// * planar triangle meshes (2-2 flip, positions' `x, y`): the quadrilateral around the edge
    ///   is strictly convex, so the new triangles do not overlap;
    /// * tetrahedral meshes (2-3 flip of a face, 3-2 flip of an edge): the segment joining the
    ///   two apexes crosses the triangle's interior, so the new tetrahedra are non-degenerate and
    ///   fill the same volume.
    ///
    /// # Errors
    /// The errors of [`can_flip`](Self::can_flip), and [`EditError::NotFlippable`] when the
    /// flip would fold or degenerate, or for other dimensions.
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse<([f64; 3],)> = starplex::hasse::Hasse::new();
    /// let p = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [2.0, 2.0, 0.0], [0.0, 2.0, 0.0], [3.0, -1.0, 0.0]];
    /// for (i, x) in p.iter().enumerate() { h.insert_with::<0>(&[(i as u32).into()], *x).unwrap(); }
    /// h.insert(&[0.into(), 1.into(), 2.into()]).unwrap();
    /// h.insert(&[0.into(), 2.into(), 3.into()]).unwrap();
    /// let e = h.find(&[0.into(), 2.into()]).unwrap();
    /// h.can_flip_geometric(e).unwrap(); // a convex square: flipping the diagonal is fine
    /// h.insert(&[1.into(), 2.into(), 4.into()]).unwrap();
    /// let e = h.find(&[1.into(), 2.into()]).unwrap();
    /// assert!(h.can_flip(e).is_ok() && h.can_flip_geometric(e).is_err()); // 0,1,4,2 is not convex
    /// ```
    pub fn can_flip_geometric(&self, s: Node) -> Result<(), EditError> {
        let t = self.can_flip(s)?;
        let sv = self.vertices(s).to_vec();
        let refuse = |why: &str| EditError::NotFlippable {
            simplex: sv.clone(),
            why: why.to_string(),
        };
        let d = self.dim().unwrap_or(0);
        let pos = |v: VertexId| self.position_of(v);
        match (d, sv.len(), t.len()) {
            (2, 2, 2) => {
                let (a, b, c, dd) = (pos(sv[0]), pos(sv[1]), pos(t[0]), pos(t[1]));
                let s1 = sign(orient2d(c2(a), c2(b), c2(c)));
                let s2 = sign(orient2d(c2(a), c2(b), c2(dd)));
                let s3 = sign(orient2d(c2(c), c2(dd), c2(a)));
                let s4 = sign(orient2d(c2(c), c2(dd), c2(b)));
                if s1 * s2 == -1 && s3 * s4 == -1 {
                    Ok(())
                } else {
                    Err(refuse(
                        "the quadrilateral around the edge is not strictly convex",
                    ))
                }
            }
            (3, 3, 2) | (3, 2, 3) => {
                let (tri, seg) = if sv.len() == 3 { (&sv, &t) } else { (&t, &sv) };
                let (a, b, c) = (pos(tri[0]), pos(tri[1]), pos(tri[2]));
                let (p, q) = (pos(seg[0]), pos(seg[1]));
                let sp = sign(orient3d(c3(a), c3(b), c3(c), c3(p)));
                let sq = sign(orient3d(c3(a), c3(b), c3(c), c3(q)));
                if sp * sq != -1 {
                    return Err(refuse(
                        "the apexes are not on opposite sides of the triangle",
                    ));
                }
                let o1 = sign(orient3d(c3(p), c3(q), c3(a), c3(b)));
                let o2 = sign(orient3d(c3(p), c3(q), c3(b), c3(c)));
                let o3 = sign(orient3d(c3(p), c3(q), c3(c), c3(a)));
                if o1 != 0 && o1 == o2 && o2 == o3 {
                    Ok(())
                } else {
                    Err(refuse(
                        "the segment between the apexes misses the triangle's interior",
                    ))
                }
            }
            _ => Err(refuse(
                "geometric flip checks exist for planar triangle meshes and tetrahedral meshes",
            )),
        }
    }
}
