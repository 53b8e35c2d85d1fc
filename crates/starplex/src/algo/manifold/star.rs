//! The star tests behind [`StarTester`](super::StarTester): one vertex and the edges at it,
//! for a complex of dimension `d` (the global convention; the local one calls these with the
//! dimension of the star). Exact up to d = 3 (links of dimension at most 2), necessary
//! conditions above.
use super::{Manifoldness, Scratch, StarCells};
use crate::algo::unionfind::{find_in as find, UnionFind};
use crate::cell::CellKind;
use crate::topo::naive::edge_neighbours;

/// Tests vertex `v` with star `star` and every edge `vw` with `w > v`; `fast`
/// allows the tetrahedral and triangular short cuts.
#[allow(clippy::too_many_arguments)]
pub(super) fn star_tests<S: StarCells + ?Sized>(
    v: u32,
    star: &S,
    d: usize,
    fast: bool,
    s: &mut Scratch,
    edge_groups: &mut Vec<(u32, usize, usize)>,
    edges_out: &mut Vec<(u32, Manifoldness)>,
) -> Manifoldness {
    use Manifoldness::*;
    if star.is_empty() {
        return if d == 0 { Manifold } else { NonManifold };
    }
    if fast
        && d == 3
        && star.all_of(CellKind::Simplex(3))
        && let Some(r) = super::tets::star_tests_tets(v, star, &mut s.tet, edges_out)
    {
        return r;
    }
    if fast && d == 2 && star.all_of(CellKind::Simplex(2)) {
        return super::tris::star_tests_tris(v, star, &mut s.recs, &mut s.parent, edges_out);
    }
    // edges at v: (w, local cell index)
    s.ew.clear();
    for i in 0..star.len() {
        let (kind, vs) = star.cell(i);
        edge_neighbours(kind, vs, v, |w| s.ew.push((w, i as u32)));
    }
    s.ew.sort_unstable();
    s.ew.dedup();
    let v_mixed = (0..star.len()).any(|i| star.cell(i).0.dim() != d);
    // per edge: cells containing it
    let mut i = 0;
    edge_groups.clear();
    while i < s.ew.len() {
        let w = s.ew[i].0;
        let mut j = i;
        while j < s.ew.len() && s.ew[j].0 == w {
            j += 1;
        }
        edge_groups.push((w, i, j));
        i = j;
    }
    let edge_mixed = |s: &Scratch, a: usize, b: usize| {
        s.ew[a..b]
            .iter()
            .any(|&(_, ci)| star.cell(ci as usize).0.dim() != d)
    };
    match d {
        0 => Manifold,
        1 => {
            for &(w, a, b) in edge_groups.iter() {
                if w > v {
                    // an edge of a 1-complex: a top edge, manifold (its link is empty)
                    let st = if edge_mixed(s, a, b) {
                        NonManifold
                    } else {
                        Manifold
                    };
                    edges_out.push((w, st));
                }
            }
            let ok = !v_mixed && star.len() <= 2;
            if ok {
                Manifold
            } else {
                NonManifold
            }
        }
        2 => {
            s.parent.clear();
            s.parent.extend(0..star.len() as u32);
            let mut sets = star.len();
            let mut bad = v_mixed;
            for &(w, a, b) in edge_groups.iter() {
                let n2 = s.ew[a..b]
                    .iter()
                    .filter(|&&(_, ci)| star.cell(ci as usize).0.dim() == 2)
                    .count();
                let e_bad = n2 > 2 || edge_mixed(s, a, b);
                bad |= e_bad;
                for k in a + 1..b {
                    let x = find(&mut s.parent, s.ew[a].1);
                    let y = find(&mut s.parent, s.ew[k].1);
                    if x != y {
                        s.parent[x as usize] = y;
                        sets -= 1;
                    }
                }
                if w > v {
                    edges_out.push((w, if e_bad { NonManifold } else { Manifold }));
                }
            }
            let ok = !bad && sets == 1;
            if ok {
                Manifold
            } else {
                NonManifold
            }
        }
        3 => star_tests_3(v, star, edge_groups, v_mixed, s, edges_out),
        _ => star_tests_high(v, star, d, edge_groups, v_mixed, s, edges_out),
    }
}

#[allow(clippy::too_many_arguments)]
fn star_tests_3<S: StarCells + ?Sized>(
    v: u32,
    star: &S,
    edge_groups: &[(u32, usize, usize)],
    v_mixed: bool,
    s: &mut Scratch,
    edges_out: &mut Vec<(u32, Manifoldness)>,
) -> Manifoldness {
    use Manifoldness::*;
    // 2-faces containing v of the 3-cells: (sorted key, cell index, e1, e2)
    faces_around(v, star, s);
    s.faces.sort_unstable();
    // group faces
    let (faces_bad, sets, n_faces) = group_faces(star, s);
    s.wpairs.sort_unstable();
    s.face_bad_w.sort_unstable();
    // per edge vw: cells containing it form one cluster through faces containing vw
    let edges_bad = edge_clusters(v, star, edge_groups, s, edges_out);
    if v_mixed || faces_bad || edges_bad || sets != 1 {
        return NonManifold;
    }
    // Euler characteristic of the link: E - F + C
    let chi = edge_groups.len() as i64 - n_faces + star.len() as i64;
    let ok = if s.bedges.is_empty() {
        chi == 2
    } else {
        // boundary of the link is a single cycle
        chi == 1 && one_cycle(&s.bedges)
    };
    if ok {
        Manifold
    } else {
        NonManifold
    }
}

/// The 2-faces containing `v` of the star's 3-cells into `s.faces`: (key of the other
/// vertices, cell index, the face's two neighbours of v).
#[inline]
fn faces_around<S: StarCells + ?Sized>(v: u32, star: &S, s: &mut Scratch) {
    s.faces.clear();
    for i in 0..star.len() {
        let (kind, vs) = star.cell(i);
        if kind.dim() != 3 {
            continue;
        }
        if kind.is_simplex() {
            // a tetrahedron: the faces containing v are v plus two of the other three
            let mut o = [0u32; 3];
            let mut m = 0;
            for &x in vs {
                if x != v {
                    o[m] = x;
                    m += 1;
                }
            }
            o.sort_unstable();
            for (x, y) in [(o[0], o[1]), (o[0], o[2]), (o[1], o[2])] {
                let key = ((x as u128) << 64) | ((y as u128) << 32) | u32::MAX as u128;
                s.faces.push((key, i as u32, x, y));
            }
            continue;
        }
        crate::cell::faces_of(kind, 2, |local| {
            let n = local.len();
            let Some(p) = local.iter().position(|&l| vs[l as usize] == v) else {
                return;
            };
            let e1 = vs[local[(p + 1) % n] as usize];
            let e2 = vs[local[(p + n - 1) % n] as usize];
            // the face's other vertices (it contains v), sorted, packed in a u128
            let mut other = [u32::MAX; 3];
            let mut m = 0;
            for &l in local {
                let x = vs[l as usize];
                if x != v {
                    other[m] = x;
                    m += 1;
                }
            }
            other[..m].sort_unstable();
            let key = ((other[0] as u128) << 64) | ((other[1] as u128) << 32) | other[2] as u128;
            s.faces.push((key, i as u32, e1, e2));
        });
    }
}

/// Groups the sorted faces: one face joins its two cells (union-find in `s.parent`; the link
/// edges through it into `s.wpairs`), one cell makes a boundary edge of the link
/// (`s.bedges`), more makes the face and its edges bad (`s.face_bad_w`). Returns (a bad face,
/// the number of cell clusters, the number of faces).
#[inline]
fn group_faces<S: StarCells + ?Sized>(star: &S, s: &mut Scratch) -> (bool, usize, i64) {
    let mut bad = false;
    s.parent.clear();
    s.parent.extend(0..star.len() as u32);
    let mut sets = star.len();
    let mut n_faces = 0i64;
    // (w, cell a, cell b) for interior faces; boundary link edges (e1, e2)
    s.wpairs.clear();
    s.bedges.clear();
    s.face_bad_w.clear();
    let mut i = 0;
    while i < s.faces.len() {
        let mut j = i;
        while j < s.faces.len() && s.faces[j].0 == s.faces[i].0 {
            j += 1;
        }
        n_faces += 1;
        let (_, _, e1, e2) = s.faces[i];
        match j - i {
            1 => s.bedges.push((e1, e2)),
            2 => {
                let (a, b) = (s.faces[i].1, s.faces[i + 1].1);
                let x = find(&mut s.parent, a);
                let y = find(&mut s.parent, b);
                if x != y {
                    s.parent[x as usize] = y;
                    sets -= 1;
                }
                s.wpairs.push((e1, a, b));
                s.wpairs.push((e2, a, b));
            }
            _ => {
                bad = true;
                s.face_bad_w.push(e1);
                s.face_bad_w.push(e2);
            }
        }
        i = j;
    }
    (bad, sets, n_faces)
}

/// Per edge vw (the groups of `s.ew`): bad when a cell of its star is not a 3-cell, when a
/// bad face contains it, or when its cells are not one cluster through the faces containing
/// it; each edge with w > v goes to `edges_out`. Returns whether one is bad.
#[inline]
fn edge_clusters<S: StarCells + ?Sized>(
    v: u32,
    star: &S,
    edge_groups: &[(u32, usize, usize)],
    s: &mut Scratch,
    edges_out: &mut Vec<(u32, Manifoldness)>,
) -> bool {
    use Manifoldness::*;
    let mut bad = false;
    s.local_uf.clear();
    s.local_uf.resize(star.len(), 0);
    let mut p = 0usize;
    for &(w, a, b) in edge_groups {
        let mut e_bad = s.ew[a..b]
            .iter()
            .any(|&(_, ci)| star.cell(ci as usize).0.dim() != 3)
            || s.face_bad_w.binary_search(&w).is_ok();
        if !e_bad {
            for k in a..b {
                let ci = s.ew[k].1;
                s.local_uf[ci as usize] = ci;
            }
            while p < s.wpairs.len() && s.wpairs[p].0 < w {
                p += 1;
            }
            let mut q = p;
            while q < s.wpairs.len() && s.wpairs[q].0 == w {
                let (x, y) = (s.wpairs[q].1, s.wpairs[q].2);
                let rx = find(&mut s.local_uf, x);
                let ry = find(&mut s.local_uf, y);
                if rx != ry {
                    s.local_uf[rx as usize] = ry;
                }
                q += 1;
            }
            let r0 = find(&mut s.local_uf, s.ew[a].1);
            for k in a + 1..b {
                if find(&mut s.local_uf, s.ew[k].1) != r0 {
                    e_bad = true;
                    break;
                }
            }
        }
        bad |= e_bad;
        if w > v {
            edges_out.push((w, if e_bad { NonManifold } else { Manifold }));
        }
    }
    bad
}

/// True when the link's boundary edges form one connected set.
fn one_cycle(bedges: &[(u32, u32)]) -> bool {
    let mut ws: Vec<u32> = bedges.iter().flat_map(|&(a, b)| [a, b]).collect();
    ws.sort_unstable();
    ws.dedup();
    let mut buf = UnionFind::new(ws.len());
    for &(a, b) in bedges {
        let ia = ws.binary_search(&a).expect("present") as u32;
        let ib = ws.binary_search(&b).expect("present") as u32;
        buf.union(ia, ib);
    }
    buf.n_sets() == 1
}

/// d >= 4 (the top d-cells are simplices): combinatorial obstructions or Unknown.
#[allow(clippy::too_many_arguments)]
fn star_tests_high<S: StarCells + ?Sized>(
    v: u32,
    star: &S,
    d: usize,
    edge_groups: &[(u32, usize, usize)],
    v_mixed: bool,
    s: &mut Scratch,
    edges_out: &mut Vec<(u32, Manifoldness)>,
) -> Manifoldness {
    use Manifoldness::*;
    if star.len() == 1 && !v_mixed {
        // one d-simplex: every link is a simplex, a ball (a 40-simplex answers at once)
        for &(w, _, _) in edge_groups {
            if w > v {
                edges_out.push((w, Manifold));
            }
        }
        return Manifold;
    }
    // facets containing v of the d-cells: (sorted facet, cell index)
    let mut facets: Vec<(Vec<u32>, u32)> = Vec::new();
    for i in 0..star.len() {
        let (kind, vs) = star.cell(i);
        if kind.dim() != d {
            continue;
        }
        for skip in 0..vs.len() {
            if vs[skip] == v {
                continue;
            }
            let mut f: Vec<u32> = vs
                .iter()
                .enumerate()
                .filter(|&(k, _)| k != skip)
                .map(|(_, &x)| x)
                .collect();
            f.sort_unstable();
            facets.push((f, i as u32));
        }
    }
    facets.sort_unstable();
    let mut over = false;
    let mut groups: Vec<(usize, usize)> = Vec::new();
    let mut i = 0;
    while i < facets.len() {
        let mut j = i;
        while j < facets.len() && facets[j].0 == facets[i].0 {
            j += 1;
        }
        if j - i > 2 {
            over = true;
        }
        groups.push((i, j));
        i = j;
    }
    let clusters = |filter: &dyn Fn(&[u32]) -> bool, members: &[u32]| -> usize {
        // clusters of the given cells through facets passing `filter`
        let mut uf = UnionFind::new(star.len());
        for &(a, b) in &groups {
            if filter(&facets[a].0) {
                for k in a + 1..b {
                    uf.union(facets[a].1, facets[k].1);
                }
            }
        }
        let mut roots: Vec<u32> = members.iter().map(|&m| uf.find(m)).collect();
        roots.sort_unstable();
        roots.dedup();
        roots.len()
    };
    let mut any_bad_edge = false;
    for &(w, a, b) in edge_groups {
        let members: Vec<u32> = s.ew[a..b].iter().map(|&(_, ci)| ci).collect();
        let e_mixed = members
            .iter()
            .any(|&ci| star.cell(ci as usize).0.dim() != d);
        let e_over = groups
            .iter()
            .any(|&(x, y)| y - x > 2 && facets[x].0.binary_search(&w).is_ok());
        let e_bad =
            e_mixed || e_over || clusters(&|f: &[u32]| f.binary_search(&w).is_ok(), &members) > 1;
        any_bad_edge |= e_bad;
        if w > v {
            // an edge of one d-simplex has a simplex for link: a ball
            let m = if e_bad {
                NonManifold
            } else if members.len() == 1 {
                Manifold
            } else {
                Unknown
            };
            edges_out.push((w, m));
        }
    }
    let all: Vec<u32> = (0..star.len() as u32).collect();
    let bad = v_mixed || over || any_bad_edge || clusters(&|_: &[u32]| true, &all) > 1;
    if bad {
        NonManifold
    } else {
        Unknown
    }
}
