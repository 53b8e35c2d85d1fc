//! Manifold tests of a vertex whose star is made of triangles, and of the edges at it, on the
//! vertex's link (a graph: every triangle of the star gives the link edge of its other two
//! vertices). The answers are those of the generic test in [`star`](super::star):
//!
//! * edge `vw` is manifold iff at most two triangles contain it (`w` has link degree ≤ 2);
//! * `v` is manifold iff every edge at `v` is manifold and the triangles are connected through
//!   the edges at `v` (the link is one path or one cycle).
use super::{Manifoldness, StarCells};
use crate::algo::unionfind::find_in as find;

/// Tests vertex `v` whose star `star` holds triangles only, and every edge `vw` with `w > v`
/// (pushed to `edges_out` in increasing `w`). `ew` and `parent` are scratch buffers.
pub(super) fn star_tests_tris<S: StarCells + ?Sized>(
    v: u32,
    star: &S,
    ew: &mut Vec<(u32, u32)>,
    parent: &mut Vec<u32>,
    edges_out: &mut Vec<(u32, Manifoldness)>,
) -> Manifoldness {
    use Manifoldness::*;
    ew.clear();
    for i in 0..star.len() {
        for &x in star.cell(i).1 {
            if x != v {
                ew.push((x, i as u32));
            }
        }
    }
    ew.sort_unstable();
    parent.clear();
    parent.extend(0..star.len() as u32);
    let mut sets = star.len();
    let mut bad = false;
    let mut a = 0;
    while a < ew.len() {
        let w = ew[a].0;
        let mut b = a + 1;
        while b < ew.len() && ew[b].0 == w {
            let x = find(parent, ew[a].1);
            let y = find(parent, ew[b].1);
            if x != y {
                parent[x as usize] = y;
                sets -= 1;
            }
            b += 1;
        }
        let e_bad = b - a > 2;
        bad |= e_bad;
        if w > v {
            edges_out.push((w, if e_bad { NonManifold } else { Manifold }));
        }
        a = b;
    }
    if !bad && sets == 1 {
        Manifold
    } else {
        NonManifold
    }
}
