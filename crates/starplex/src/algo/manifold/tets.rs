//! Manifold tests of a vertex whose star is made of tetrahedra, and of the edges at it, on the
//! vertex's link (a triangle set) with link-local vertex ids from a small open-addressing hash
//! table: no sorting, no allocation once the scratch buffers have grown.
//!
//! With `v` the vertex, every tetrahedron of its star gives a link triangle (its other three
//! vertices); link edges are the triangles containing `v` and link vertices the edges at `v`.
//! The answers are those of the generic test in [`star`](super::star):
//!
//! * edge `vw` is manifold iff no link edge at `w` lies in three or more link triangles and the
//!   link triangles at `w` are connected through link edges at `w` (a union-find over the
//!   triangles' corners answers this for every `w` at once);
//! * `v` is manifold iff every link edge lies in at most two triangles, every edge at `v` is
//!   manifold, the triangles are connected through link edges, and the link's Euler
//!   characteristic V - E + F is 2 (no boundary) or 1 with a boundary made of one cycle.
use super::{Manifoldness, StarCells};
use crate::algo::unionfind::{find_in as find, union_min_in as union};

const EMPTY: u32 = u32::MAX;
const EMPTY2: u64 = u64::MAX;

/// Local vertex flags.
const OVER: u8 = 1;
const BOUNDARY: u8 = 2;
const FAN: u8 = 4;

/// Reusable buffers of [`star_tests_tets`].
#[derive(Default)]
pub(crate) struct TetScratch {
    /// Vertex hash: slot -> tree vertex (or EMPTY), slot -> local id.
    vkeys: Vec<u32>,
    vvals: Vec<u32>,
    /// Local id -> tree vertex, local id -> its slot (to empty the table afterwards).
    lv: Vec<u32>,
    lslot: Vec<u32>,
    /// Link triangle of every star tetrahedron (local ids, increasing).
    tri: Vec<[u32; 3]>,
    /// Edge hash: slot -> (a << 32 | b) (or EMPTY2), slot -> edge index.
    ekeys: Vec<u64>,
    evals: Vec<u32>,
    eslot: Vec<u32>,
    /// Links of at most [`DENSE`] vertices: edge index at `a * DENSE + b` (or EMPTY), in
    /// place of the edge hash.
    edense: Vec<u32>,
    /// The link edges.
    edges: Vec<LinkEdge>,
    /// Per local vertex: flags, root of its first corner.
    flags: Vec<u8>,
    root: Vec<u32>,
    /// Union-finds over triangles, corners (3 per triangle), local vertices.
    tuf: Vec<u32>,
    cuf: Vec<u32>,
    vuf: Vec<u32>,
}

/// A link edge: its endpoints (local ids, a < b), its number of triangles and the first two
/// (one record, written once when the edge is first met).
#[derive(Clone, Copy, Debug)]
struct LinkEdge {
    a: u32,
    b: u32,
    cnt: u32,
    tri: [u32; 2],
}

/// Most link vertices for which the link edges are indexed directly (a 16 KB table).
const DENSE: usize = 64;

/// Triangle `i` meets link edge `e` again: one more, and the second one kept.
#[inline(always)]
fn edge_again(e: &mut LinkEdge, i: u32) {
    if e.cnt == 1 {
        e.tri[1] = i;
    }
    e.cnt += 1;
}

/// A link edge `ab` first met by triangle `i`: its index.
#[inline(always)]
fn edge_new(edges: &mut Vec<LinkEdge>, (a, b): (u32, u32), i: u32) -> u32 {
    edges.push(LinkEdge {
        a,
        b,
        cnt: 1,
        tri: [i, EMPTY],
    });
    edges.len() as u32 - 1
}

#[inline]
fn hash1(x: u32, shift: u32) -> usize {
    (x.wrapping_mul(0x9E37_79B1) >> shift) as usize
}

#[inline]
fn hash2(a: u32, b: u32, shift: u32) -> usize {
    ((a.wrapping_mul(0x9E37_79B1) ^ b).wrapping_mul(0x85EB_CA6B) >> shift) as usize
}

/// Corner of triangle `t` at local vertex `x` (which must be one of its vertices).
#[inline]
fn corner(tri: &[[u32; 3]], t: u32, x: u32) -> u32 {
    let tr = &tri[t as usize];
    3 * t
        + if tr[0] == x {
            0
        } else if tr[1] == x {
            1
        } else {
            2
        }
}

/// Manifold tests of vertex `v` whose non-empty star `star` (local cells) holds only
/// tetrahedra in a complex of dimension 3; pushes `(w, answer)` for every edge `vw` with
/// `w > v`. Same answers as the generic test; `None` (nothing pushed) for a cell with a
/// repeated vertex, which only a damaged tree file holds.
pub(crate) fn star_tests_tets<S: StarCells + ?Sized>(
    v: u32,
    star: &S,
    s: &mut TetScratch,
    edges_out: &mut Vec<(u32, Manifoldness)>,
) -> Option<Manifoldness> {
    use Manifoldness::*;
    let n = star.len();
    // at most 3n link vertices and 3n link edges: load factor <= 1/2
    let cap = (6 * n).next_power_of_two().max(16);
    let shift = 32 - cap.trailing_zeros();
    let mask = cap - 1;
    if s.vkeys.len() < cap {
        s.vkeys.resize(cap, EMPTY);
        s.vvals.resize(cap, 0);
        s.ekeys.resize(cap, EMPTY2);
        s.evals.resize(cap, 0);
    }
    // link triangles with local vertex ids
    if s.link_triangles(v, star, shift, mask) {
        return None;
    }
    // link edges with their triangles
    s.link_edges(shift, mask);
    let m = s.lv.len();
    let ne = s.edges.len();
    let (mut bad, sets, n_boundary) = s.classify_edges(n);
    // Euler characteristic of the link: V - E + F
    let chi = m as i64 - ne as i64 + n as i64;
    if !bad && sets == 1 && chi == if n_boundary == 0 { 2 } else { 1 } {
        // Short cut: split every link vertex whose triangles form k > 1 fans into k
        // copies; the result is a connected surface with Euler characteristic
        // chi + sum(k - 1), at most 2 without boundary and 1 with: so every fan is
        // connected, the link is a sphere or a disk, and every edge at v is manifold.
        for &w in s.lv.iter() {
            if w > v {
                edges_out.push((w, Manifold));
            }
        }
        return Some(Manifold);
    }
    // the triangles at each link vertex w form one fan (edge vw manifold)
    s.flag_fans(n);
    for (w, &f) in s.flags.iter().enumerate() {
        let e_bad = f & (OVER | FAN) != 0;
        bad |= e_bad;
        let tw = s.lv[w];
        if tw > v {
            edges_out.push((tw, if e_bad { NonManifold } else { Manifold }));
        }
    }
    if bad || sets != 1 {
        return Some(NonManifold);
    }
    let ok = if n_boundary == 0 {
        chi == 2
    } else {
        // the boundary of the link is a single cycle
        chi == 1 && s.boundary_is_one_cycle()
    };
    Some(if ok { Manifold } else { NonManifold })
}

impl TetScratch {
    /// After [`star_tests_tets`] answered (`Some`) on the star of `v`: calls `f([a, b],
    /// cells)` for every triangle `v a b` with `v < a < b` (the triangles `v` owns), `cells`
    /// the star indices of its tetrahedra, increasing. The triangles come in no particular
    /// order. `buf` is scratch.
    pub(crate) fn owned_triangles(
        &self,
        v: u32,
        buf: &mut Vec<u32>,
        mut f: impl FnMut([u32; 2], &[u32]),
    ) {
        for e in self.edges.iter() {
            let (a, b) = (e.a, e.b);
            let (ta, tb) = (self.lv[a as usize], self.lv[b as usize]);
            if ta < v || tb < v {
                continue;
            }
            buf.clear();
            if e.cnt <= 2 {
                buf.extend(e.tri.iter().copied().filter(|&t| t != EMPTY));
            } else {
                buf.extend((0..self.tri.len() as u32).filter(|&t| {
                    self.tri[t as usize].contains(&a) && self.tri[t as usize].contains(&b)
                }));
            }
            f(if ta < tb { [ta, tb] } else { [tb, ta] }, buf);
        }
    }

    /// The link triangle of every tetrahedron of `star` (its vertices other than `v`, as
    /// local ids from the vertex hash, increasing) into `tri`, the local vertices into `lv`;
    /// empties the hash again. Returns true when a cell has a repeated vertex (only in a
    /// damaged tree file).
    #[inline]
    fn link_triangles<S: StarCells + ?Sized>(
        &mut self,
        v: u32,
        star: &S,
        shift: u32,
        mask: usize,
    ) -> bool {
        let TetScratch {
            vkeys,
            vvals,
            lv,
            lslot,
            tri,
            ..
        } = self;
        lv.clear();
        lslot.clear();
        tri.clear();
        let mut degenerate = false;
        for i in 0..star.len() {
            let mut t = [0u32; 3];
            let mut m = 0;
            for &x in star.cell(i).1 {
                if x == v {
                    continue;
                }
                let mut h = hash1(x, shift);
                let id = loop {
                    let k = vkeys[h];
                    if k == x {
                        break vvals[h];
                    }
                    if k == EMPTY {
                        let id = lv.len() as u32;
                        vkeys[h] = x;
                        vvals[h] = id;
                        lv.push(x);
                        lslot.push(h as u32);
                        break id;
                    }
                    h = (h + 1) & mask;
                };
                if m < 3 {
                    t[m] = id;
                }
                m += 1;
            }
            // a cell with a repeated vertex (only in a damaged tree file)
            degenerate |= m != 3;
            t = crate::topo::sort3(t);
            tri.push(t);
        }
        for &h in lslot.iter() {
            vkeys[h as usize] = EMPTY;
        }
        degenerate
    }

    /// The link edges (`edges`, local ids a < b) with their triangle count and first two
    /// triangles, from the edge hash (emptied again).
    #[inline]
    fn link_edges(&mut self, shift: u32, mask: usize) {
        let TetScratch {
            tri,
            ekeys,
            evals,
            eslot,
            edges,
            ..
        } = self;
        edges.clear();
        eslot.clear();
        if self.lv.len() <= DENSE {
            // local ids index the table directly: no hashing, no probing
            let edense = &mut self.edense;
            if edense.is_empty() {
                edense.resize(DENSE * DENSE, EMPTY);
            }
            for (i, t) in tri.iter().enumerate() {
                for (a, b) in [(t[0], t[1]), (t[0], t[2]), (t[1], t[2])] {
                    let h = a as usize * DENSE + b as usize;
                    let e = edense[h];
                    if e != EMPTY {
                        edge_again(&mut edges[e as usize], i as u32);
                    } else {
                        edense[h] = edge_new(edges, (a, b), i as u32);
                        eslot.push(h as u32);
                    }
                }
            }
            for &h in eslot.iter() {
                edense[h as usize] = EMPTY;
            }
            return;
        }
        for (i, t) in tri.iter().enumerate() {
            for (a, b) in [(t[0], t[1]), (t[0], t[2]), (t[1], t[2])] {
                let key = ((a as u64) << 32) | b as u64;
                let mut h = hash2(a, b, shift);
                loop {
                    let k = ekeys[h];
                    if k == key {
                        edge_again(&mut edges[evals[h] as usize], i as u32);
                        break;
                    }
                    if k == EMPTY2 {
                        ekeys[h] = key;
                        evals[h] = edge_new(edges, (a, b), i as u32);
                        eslot.push(h as u32);
                        break;
                    }
                    h = (h + 1) & mask;
                }
            }
        }
        for &h in eslot.iter() {
            ekeys[h as usize] = EMPTY2;
        }
    }

    /// Classifies the link edges: boundary (one triangle: its ends flagged BOUNDARY), interior
    /// (two: the triangles joined in `tuf`), over-full (more: its ends flagged OVER). Returns
    /// (an over-full edge, the number of triangle clusters, the number of boundary edges).
    #[inline]
    fn classify_edges(&mut self, n: usize) -> (bool, usize, usize) {
        let TetScratch {
            lv,
            edges,
            flags,
            tuf,
            ..
        } = self;
        let m = lv.len();
        flags.clear();
        flags.resize(m, 0);
        tuf.clear();
        tuf.extend(0..n as u32);
        let mut sets = n;
        let mut bad = false;
        let mut n_boundary = 0usize;
        for &LinkEdge { a, b, cnt, tri } in edges.iter() {
            match cnt {
                1 => {
                    flags[a as usize] |= BOUNDARY;
                    flags[b as usize] |= BOUNDARY;
                    n_boundary += 1;
                }
                2 => {
                    let [t0, t1] = tri;
                    if union(tuf, t0, t1) {
                        sets -= 1;
                    }
                }
                _ => {
                    bad = true;
                    flags[a as usize] |= OVER;
                    flags[b as usize] |= OVER;
                }
            }
        }
        (bad, sets, n_boundary)
    }

    /// Flags FAN every link vertex whose triangles are not one fan: corners of triangles
    /// sharing an interior edge are joined, and a vertex whose corners have two roots is
    /// flagged.
    #[inline]
    fn flag_fans(&mut self, n: usize) {
        let TetScratch {
            lv,
            tri,
            edges,
            flags,
            root,
            cuf,
            ..
        } = self;
        let m = lv.len();
        cuf.clear();
        cuf.extend(0..3 * n as u32);
        for e in edges.iter() {
            if e.cnt == 2 {
                let (a, b, [t0, t1]) = (e.a, e.b, e.tri);
                union(cuf, corner(tri, t0, a), corner(tri, t1, a));
                union(cuf, corner(tri, t0, b), corner(tri, t1, b));
            }
        }
        root.clear();
        root.resize(m, EMPTY);
        for (i, t) in tri.iter().enumerate() {
            for (p, &w) in t.iter().enumerate() {
                let r = find(cuf, 3 * i as u32 + p as u32);
                let slot = &mut root[w as usize];
                if *slot == EMPTY {
                    *slot = r;
                } else if *slot != r {
                    flags[w as usize] |= FAN;
                }
            }
        }
    }

    /// True when the link's boundary edges (one triangle each) form one cycle: the boundary
    /// vertices are one set.
    #[inline]
    fn boundary_is_one_cycle(&mut self) -> bool {
        let TetScratch {
            lv,
            edges,
            flags,
            vuf,
            ..
        } = self;
        let m = lv.len();
        vuf.clear();
        vuf.extend(0..m as u32);
        let mut merged = 0usize;
        for e in edges.iter() {
            if e.cnt == 1 {
                merged += union(vuf, e.a, e.b) as usize;
            }
        }
        let nb = flags.iter().filter(|&&f| f & BOUNDARY != 0).count();
        nb - merged == 1
    }
}
