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
/// (pushed to `edges_out` in increasing `w`). `recs` and `parent` are scratch buffers.
pub(super) fn star_tests_tris<S: StarCells + ?Sized>(
    v: u32,
    star: &S,
    recs: &mut Vec<u64>,
    parent: &mut Vec<u32>,
    edges_out: &mut Vec<(u32, Manifoldness)>,
) -> Manifoldness {
    recs.clear();
    for i in 0..star.len() {
        for &x in star.cell(i).1 {
            if x != v {
                recs.push(((x as u64) << 32) | ((i as u64) << 3));
            }
        }
    }
    crate::topo::sortnet::sort_short(recs, u64::MAX);
    link_test(star.len(), recs, parent, |w, group| {
        if w > v {
            let bad = group.len() > 2;
            edges_out.push((
                w,
                if bad {
                    Manifoldness::NonManifold
                } else {
                    Manifoldness::Manifold
                },
            ));
        }
    })
}

/// The test of a vertex `v` whose star holds `n` triangles, on the edges through `v`:
/// `recs` (sorted) holds one record per (triangle, edge through `v`), `w << 32 | star index
/// << 3 | three bits of the caller's`, `w` the edge's other vertex. Calls `group(w, records)`
/// for every `w` in increasing order (the edge `vw` is manifold iff its group holds at most two
/// triangles) and answers whether `v` is manifold: every edge manifold and the triangles
/// joined through the edges into one cluster. `parent` is scratch.
pub(crate) fn link_test(
    n: usize,
    recs: &[u64],
    parent: &mut Vec<u32>,
    mut group: impl FnMut(u32, &[u64]),
) -> Manifoldness {
    use Manifoldness::*;
    parent.clear();
    parent.extend(0..n as u32);
    let mut sets = n;
    let mut bad = false;
    let mut a = 0;
    while a < recs.len() {
        let w = (recs[a] >> 32) as u32;
        let mut b = a + 1;
        while b < recs.len() && (recs[b] >> 32) as u32 == w {
            let x = find(parent, recs[a] as u32 >> 3);
            let y = find(parent, recs[b] as u32 >> 3);
            if x != y {
                parent[x as usize] = y;
                sets -= 1;
            }
            b += 1;
        }
        bad |= b - a > 2;
        group(w, &recs[a..b]);
        a = b;
    }
    if !bad && sets == 1 {
        Manifold
    } else {
        NonManifold
    }
}
