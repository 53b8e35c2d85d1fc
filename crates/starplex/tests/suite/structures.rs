//! ONE test suite over every structure (VtIndex baseline, IA*, simplex tree with and without
//! label lists, incidence graph, IS, the CASC Hasse diagram, the Stellar tree for several k_V):
//! every relation is compared with a brute-force model
//! (all simplices enumerated from the tops) on named fixtures and on seeded random complexes,
//! and with the dataset oracles (vertex queries, f-vector, Euler characteristic). CP complexes
//! (quads, hexahedra, prisms, pyramids, mixed) run the structures that hold them (incidence
//! graph, IA*) against a model of cells from the face tables.
use crate::common_data;

use std::collections::BTreeSet;

use proptest::prelude::*;
use starplex::algo::components::components;
use starplex::algo::manifold::{singularities, Convention::Local, Manifoldness};
use starplex::cell::CellKind;
use starplex::complex::{BuildOptions, ComplexBuilder, IndexedComplex};
use starplex::hasse::HasseQueries;
use starplex::ids::{CellId, VertexId};
use starplex::limits::Limits;
use starplex::stellar::{StellarOptions, StellarTree};
use starplex::tds::iastar::IaStar;
use starplex::tds::ig::IncidenceGraph;
use starplex::tds::is::Is;
use starplex::tds::simplex_tree::{BuildError, SimplexTree, SimplexTreeOptions};
use starplex::topo::{
    generic, naive::VtIndex, FacetAdjacency, Queries, QueryError, Storage, VertexAdjacency,
    VertexStar,
};
/// The default budgets with `n` stored simplices.
fn stored(n: u128) -> Limits {
    Limits {
        stored_simplices: n,
        ..Limits::default()
    }
}

// ------------------------------------------------------------------------------------------
// the brute-force model

struct Model {
    nv: usize,
    tops: Vec<Vec<u32>>, // sorted, by cell id
    all: BTreeSet<Vec<u32>>,
}

impl Model {
    fn new(k: &IndexedComplex) -> Model {
        let tops: Vec<Vec<u32>> = k
            .cells()
            .map(|c| {
                let mut t = c.vertices.to_vec();
                t.sort_unstable();
                t
            })
            .collect();
        let mut all = BTreeSet::new();
        for v in 0..k.n_vertices() as u32 {
            all.insert(vec![v]);
        }
        for t in &tops {
            for mask in 1u64..(1u64 << t.len()) {
                all.insert(
                    (0..t.len())
                        .filter(|i| mask >> i & 1 == 1)
                        .map(|i| t[i])
                        .collect(),
                );
            }
        }
        Model {
            nv: k.n_vertices(),
            tops,
            all,
        }
    }
    fn contains(a: &[u32], b: &[u32]) -> bool {
        a.iter().all(|x| b.contains(x))
    }
    fn star(&self, s: &[u32]) -> Vec<Vec<u32>> {
        self.all
            .iter()
            .filter(|t| Self::contains(s, t))
            .cloned()
            .collect()
    }
    fn top_star(&self, s: &[u32]) -> Vec<u32> {
        (0..self.tops.len() as u32)
            .filter(|&c| Self::contains(s, &self.tops[c as usize]))
            .collect()
    }
    fn f_vector(&self) -> Vec<u64> {
        let mut f = Vec::new();
        for s in &self.all {
            if f.len() < s.len() {
                f.resize(s.len(), 0);
            }
            f[s.len() - 1] += 1;
        }
        f
    }
}

fn vs(x: &[u32]) -> Vec<VertexId> {
    x.iter().map(|&v| VertexId(v)).collect()
}
fn flat(list: &[Vec<u32>]) -> Vec<VertexId> {
    let mut l: Vec<Vec<u32>> = list.to_vec();
    l.sort();
    l.into_iter().flatten().map(VertexId).collect()
}

/// Every relation of `s` equals the model's, for every simplex.
fn check_structure<S: Queries + ?Sized>(name: &str, s: &S, m: &Model, sorted_tops: bool) {
    assert_eq!(s.n_vertices(), m.nv, "{name}");
    assert_eq!(s.n_top_cells(), m.tops.len(), "{name}");
    let mut buf = Vec::new();
    for (c, t) in m.tops.iter().enumerate() {
        buf.clear();
        s.top_cell_vertices(CellId(c as u32), &mut buf);
        let mut got: Vec<u32> = buf.iter().map(|v| v.0).collect();
        if !sorted_tops {
            got.sort_unstable();
        }
        assert_eq!(&got, t, "{name}: vertices of top {c}");
        assert_eq!(
            s.top_cell_kind(CellId(c as u32)),
            CellKind::Simplex(t.len() as u8 - 1)
        );
    }
    assert_eq!(s.f_vector().unwrap(), m.f_vector(), "{name}: f-vector");
    let f = m.f_vector();
    let chi: i64 = f
        .iter()
        .enumerate()
        .map(|(p, &x)| if p % 2 == 0 { x as i64 } else { -(x as i64) })
        .sum();
    assert_eq!(generic::euler_characteristic(s).unwrap(), chi, "{name}");
    for p in 0..f.len() {
        let mut got = Vec::new();
        s.for_each_simplex(p, &mut |t| got.extend_from_slice(t))
            .unwrap();
        let want: Vec<Vec<u32>> = m.all.iter().filter(|t| t.len() == p + 1).cloned().collect();
        assert_eq!(got, flat(&want), "{name}: level {p}");
        // the flat listing (in parallel for some structures) in the same order
        let flat_got: Vec<u32> = s.faces_flat(p).unwrap();
        let got: Vec<u32> = got.iter().map(|v| v.0).collect();
        assert_eq!(flat_got, got, "{name}: faces_flat({p})");
    }
    let (mut cells, mut vv, mut out) = (Vec::new(), Vec::new(), Vec::new());
    // the rows of every vertex at once, where the structure gives them
    let (vt_rows, vv_rows) = (s.vertex_top_rows(), s.vertex_neighbour_rows());
    for v in 0..m.nv as u32 {
        s.vertex_top_cells(VertexId(v), &mut cells);
        let want: Vec<CellId> = m.top_star(&[v]).into_iter().map(CellId).collect();
        assert_eq!(cells, want, "{name}: VT({v})");
        if let Some(r) = &vt_rows {
            let want: Vec<u32> = want.iter().map(|c| c.0).collect();
            assert_eq!(r.row(v as usize), &want[..], "{name}: vertex_top_rows({v})");
        }
        if let Some(r) = &vv_rows {
            s.vertex_neighbours(VertexId(v), &mut vv);
            let want: Vec<u32> = vv.iter().map(|w| w.0).collect();
            assert_eq!(
                r.row(v as usize),
                &want[..],
                "{name}: vertex_neighbour_rows({v})"
            );
        }
        s.vertex_neighbours(VertexId(v), &mut vv);
        let want: Vec<VertexId> = m
            .all
            .iter()
            .filter(|t| t.len() == 2 && t.contains(&v))
            .map(|t| VertexId(if t[0] == v { t[1] } else { t[0] }))
            .collect();
        assert_eq!(vv, want, "{name}: VV({v})");
    }
    for sigma in &m.all {
        let p = sigma.len() - 1;
        let sv = vs(sigma);
        // top star
        s.top_star(&sv, &mut cells).unwrap();
        let want: Vec<CellId> = m.top_star(sigma).into_iter().map(CellId).collect();
        assert_eq!(cells, want, "{name}: St_T({sigma:?})");
        // star, link, closure
        let star = s.star(&sv).unwrap();
        let want_star = m.star(sigma);
        let got: Vec<Vec<u32>> = star
            .iter()
            .map(|t| t.iter().map(|v| v.0).collect())
            .collect();
        let mut want_sorted = want_star.clone();
        want_sorted.sort_by(|a, b| a.len().cmp(&b.len()).then(a.cmp(b)));
        assert_eq!(got, want_sorted, "{name}: St({sigma:?})");
        let link = generic::link(s, &sv).unwrap();
        // the bulk answers' link, straight from the top cells, is the same set
        let direct = starplex::topo::from_tops::link(s, &sv, u128::MAX).unwrap();
        assert_eq!(direct, link, "{name}: Lk({sigma:?}) from the top cells");
        let want_link: BTreeSet<Vec<u32>> = want_star
            .iter()
            .filter(|t| t.len() > sigma.len())
            .map(|t| t.iter().copied().filter(|x| !sigma.contains(x)).collect())
            .collect();
        assert_eq!(link.len(), want_link.len(), "{name}: Lk({sigma:?})");
        for t in &want_link {
            assert!(link.contains(&vs(t)), "{name}: Lk({sigma:?}) misses {t:?}");
        }
        let cl = generic::closure(s, &sv).unwrap();
        assert_eq!(
            cl.len(),
            (1usize << sigma.len()) - 1,
            "{name}: Cl({sigma:?})"
        );
        // boundary and co-boundary for every q
        for q in 0..f.len() {
            s.boundary(&sv, q, &mut out).unwrap();
            let want: Vec<Vec<u32>> = m
                .all
                .iter()
                .filter(|t| t.len() == q + 1 && q < p && Model::contains(t, sigma))
                .cloned()
                .collect();
            assert_eq!(out, flat(&want), "{name}: R_{p},{q}({sigma:?})");
            s.coboundary(&sv, q, &mut out).unwrap();
            let want: Vec<Vec<u32>> = want_star
                .iter()
                .filter(|t| t.len() == q + 1 && q > p)
                .cloned()
                .collect();
            assert_eq!(out, flat(&want), "{name}: R_{p},{q}({sigma:?})");
        }
        // adjacency
        s.adjacent(&sv, &mut out).unwrap();
        let want: Vec<Vec<u32>> = if p == 0 {
            vv_of(m, sigma[0]).into_iter().map(|w| vec![w]).collect()
        } else {
            m.all
                .iter()
                .filter(|t| {
                    t.len() == p + 1
                        && *t != sigma
                        && t.iter().filter(|x| sigma.contains(x)).count() == p
                })
                .cloned()
                .collect()
        };
        assert_eq!(out, flat(&want), "{name}: R_{p},{p}({sigma:?})");
    }
    // a non-simplex is refused with a typed error
    if m.nv >= 2 {
        let missing = (0..m.nv as u32)
            .flat_map(|a| (a + 1..m.nv as u32).map(move |b| vec![a, b]))
            .find(|e| !m.all.contains(e));
        if let Some(e) = missing {
            assert!(matches!(s.star(&vs(&e)), Err(QueryError::NotInComplex(_))));
            assert!(s.top_star(&vs(&e), &mut cells).is_err());
            assert!(
                matches!(
                    s.boundary(&vs(&e), 0, &mut out),
                    Err(QueryError::NotInComplex(_))
                ),
                "{name}: boundary of the non-simplex {e:?}"
            );
        }
    }
    assert!(s.star(&[VertexId(m.nv as u32 + 5)]).is_err());
    assert!(generic::closure(s, &[VertexId(m.nv as u32 + 5)]).is_err());
    assert!(generic::link(s, &[VertexId(0), VertexId(0)]).is_err());
    assert!(s.refs() > 0 || m.tops.is_empty());
    assert!(s.bytes() > 0 || m.tops.is_empty());
}

fn vv_of(m: &Model, v: u32) -> Vec<u32> {
    m.all
        .iter()
        .filter(|t| t.len() == 2 && t.contains(&v))
        .map(|t| if t[0] == v { t[1] } else { t[0] })
        .collect()
}

/// Runs the suite on every structure.
fn check_all(name: &str, k: &IndexedComplex) {
    let m = Model::new(k);
    check_structure(&format!("{name}/vt"), &VtIndex::new(k), &m, false);
    check_structure(&format!("{name}/ia*"), &IaStar::new(k).unwrap(), &m, false);
    for ll in [false, true] {
        let st = SimplexTree::new(
            k,
            &SimplexTreeOptions {
                label_lists: ll,
                ..Default::default()
            },
        )
        .unwrap();
        check_structure(&format!("{name}/simplex-tree(ll={ll})"), &st, &m, true);
    }
    check_structure(
        &format!("{name}/ig"),
        &IncidenceGraph::new(k, &stored(1 << 30)).unwrap(),
        &m,
        true,
    );
    check_structure(
        &format!("{name}/is"),
        &Is::new(k, &stored(1 << 30)).unwrap(),
        &m,
        true,
    );
    check_structure(
        &format!("{name}/hasse"),
        &HasseQueries::new(k, &stored(1 << 30)).unwrap(),
        &m,
        true,
    );
    for kv in [Some(1), Some(10), Some(0)] {
        let t = StellarTree::build(
            k,
            &StellarOptions {
                kv,
                ..Default::default()
            },
        )
        .unwrap();
        check_structure(&format!("{name}/stellar(kv={kv:?})"), &t, &m, false);
        check_structure(
            &format!("{name}/stellar-ia*(kv={kv:?})"),
            &t.iastar(),
            &m,
            false,
        );
        same_cells(&format!("{name}/stellar(kv={kv:?})"), k, &t);
        same_cells(&format!("{name}/stellar-ia*(kv={kv:?})"), k, &t.iastar());
    }
    same_cells(&format!("{name}/vt"), k, &VtIndex::new(k));
    same_cells(&format!("{name}/ia*"), k, &IaStar::new(k).unwrap());
}

/// A structure that keeps the input's vertex order writes the same complex back.
fn same_cells<S: starplex::topo::TopCells>(name: &str, k: &IndexedComplex, s: &S) {
    let back = generic::to_complex(s, k.ambient_dim(), k.coords().to_vec()).unwrap();
    assert_eq!(back.n_cells(), k.n_cells(), "{name}");
    for (a, b) in back.cells().zip(k.cells()) {
        assert_eq!(
            (a.kind, a.vertices),
            (b.kind, b.vertices),
            "{name}: cell {}",
            b.id.0
        );
    }
}

fn complex(nv: usize, cells: &[&[u32]]) -> IndexedComplex {
    let mut b = ComplexBuilder::new(1).unwrap();
    for i in 0..nv {
        b.push_vertex(&[i as f64]).unwrap();
    }
    for c in cells {
        b.push_cell(CellKind::Simplex(c.len() as u8 - 1), c)
            .unwrap();
    }
    b.build(&BuildOptions::default()).unwrap().0
}

fn fixtures() -> Vec<(&'static str, IndexedComplex)> {
    vec![
        ("tetrahedron", complex(4, &[&[0, 1, 2, 3]])),
        ("two-tets-face", complex(5, &[&[0, 1, 2, 3], &[1, 2, 3, 4]])),
        (
            "octahedron",
            complex(
                6,
                &[
                    &[0, 2, 4],
                    &[2, 1, 4],
                    &[1, 3, 4],
                    &[3, 0, 4],
                    &[2, 0, 5],
                    &[1, 2, 5],
                    &[3, 1, 5],
                    &[0, 3, 5],
                ],
            ),
        ),
        ("bow-tie", complex(5, &[&[0, 1, 2], &[0, 3, 4]])),
        ("dangling-edge", complex(4, &[&[0, 1, 2], &[2, 3]])),
        ("isolated-vertex", complex(4, &[&[0, 1, 2]])),
        ("book", complex(5, &[&[0, 1, 2], &[0, 1, 3], &[0, 1, 4]])),
        ("two-tets-edge", complex(6, &[&[0, 1, 2, 3], &[0, 1, 4, 5]])),
        (
            "mixed",
            complex(7, &[&[0, 1, 2, 3], &[3, 4, 5], &[5, 6], &[0, 4]]),
        ),
    ]
}

#[test]
fn every_structure_answers_every_relation_on_the_fixtures() {
    for (name, k) in fixtures() {
        check_all(name, &k);
    }
}

#[test]
fn a_40_simplex_answers_top_cell_queries_and_refuses_the_rest() {
    let verts: Vec<u32> = (0..41).collect();
    let k = complex(41, &[&verts]);
    let check_tops = |name: &str, s: &dyn Queries| {
        let mut cells = Vec::new();
        s.vertex_top_cells(VertexId(7), &mut cells);
        assert_eq!(cells, vec![CellId(0)], "{name}");
        let mut vv = Vec::new();
        s.vertex_neighbours(VertexId(0), &mut vv);
        assert_eq!(vv.len(), 40, "{name}");
        s.top_star(&[VertexId(3), VertexId(30)], &mut cells)
            .unwrap();
        assert_eq!(cells, vec![CellId(0)], "{name}");
        match s.star(&[VertexId(0)]) {
            Err(QueryError::TooLarge(t)) => assert!(t.estimate >= 1 << 40),
            other => panic!("{name}: expected a refusal, got {other:?}"),
        }
        assert!(matches!(s.f_vector(), Err(QueryError::TooLarge { .. })));
    };
    check_tops("vt", &VtIndex::new(&k));
    let ia = IaStar::new(&k).unwrap();
    check_tops("ia*", &ia);
    assert_eq!(ia.refs(), 41 + 41 + 41);
    let too_large = |r: Result<(), BuildError>| match r {
        Err(BuildError::TooLarge(t)) => assert!(t.estimate >= 1 << 41),
        other => panic!("expected a refusal, got {other:?}"),
    };
    too_large(SimplexTree::new(&k, &SimplexTreeOptions::default()).map(|_| ()));
    too_large(IncidenceGraph::new(&k, &stored(u32::MAX as u128)).map(|_| ()));
    too_large(Is::new(&k, &stored(u32::MAX as u128)).map(|_| ()));
    assert!(matches!(
        HasseQueries::new(&k, &stored(u32::MAX as u128)),
        Err(starplex::hasse::HasseError::TooLarge(t)) if t.estimate >= 1 << 41
    ));
    let t = StellarTree::build(&k, &StellarOptions::default()).unwrap();
    check_tops("stellar", &t);
}

// ------------------------------------------------------------------------------------------
// storage formulas

/// IA* references by brute force from the definitions (spec §2.5).
fn iastar_formula(m: &Model) -> u64 {
    let mut refs = 0u64;
    let mut t1 = 0u64;
    for t in &m.tops {
        let k = t.len() - 1;
        refs += t.len() as u64;
        if k >= 2 {
            refs += t.len() as u64;
        }
        if k == 1 {
            t1 += 1;
        }
    }
    // NM face lists
    let mut facets: std::collections::BTreeMap<Vec<u32>, u64> = Default::default();
    for t in m.tops.iter().filter(|t| t.len() >= 3) {
        for j in 0..t.len() {
            let f: Vec<u32> = t
                .iter()
                .enumerate()
                .filter(|&(i, _)| i != j)
                .map(|(_, &v)| v)
                .collect();
            *facets.entry(f).or_insert(0) += 1;
        }
    }
    refs += facets.values().filter(|&&c| c >= 3).sum::<u64>();
    refs += 2 * t1;
    // clusters: tops of dimension k at v, joined when sharing a facet containing v
    for v in 0..m.nv as u32 {
        let at: Vec<&Vec<u32>> = m
            .tops
            .iter()
            .filter(|t| t.contains(&v) && t.len() >= 3)
            .collect();
        let mut uf = starplex::algo::unionfind::UnionFind::new(at.len());
        for a in 0..at.len() {
            for b in a + 1..at.len() {
                let shared = at[a].iter().filter(|x| at[b].contains(x)).count();
                if at[a].len() == at[b].len() && shared == at[a].len() - 1 {
                    uf.union(a as u32, b as u32);
                }
            }
        }
        refs += uf.n_sets() as u64;
    }
    refs
}

/// IS references: boundary + Σ c(σ), c from link components computed by brute force.
fn is_formula(m: &Model) -> u64 {
    let mut refs = 0u64;
    for s in &m.all {
        if s.len() >= 2 {
            refs += s.len() as u64;
        }
        // link vertices and edges
        let star = m.star(s);
        let lv: Vec<u32> = star
            .iter()
            .filter(|t| t.len() == s.len() + 1)
            .map(|t| *t.iter().find(|x| !s.contains(x)).unwrap())
            .collect();
        let mut uf = starplex::algo::unionfind::UnionFind::new(lv.len());
        for t in star.iter().filter(|t| t.len() == s.len() + 2) {
            let r: Vec<u32> = t.iter().copied().filter(|x| !s.contains(x)).collect();
            let a = lv.iter().position(|&x| x == r[0]).unwrap();
            let b = lv.iter().position(|&x| x == r[1]).unwrap();
            uf.union(a as u32, b as u32);
        }
        refs += uf.n_sets() as u64;
    }
    refs
}

#[test]
fn storage_matches_the_spec_anchors_and_formulas() {
    // (fixture, IA*, IS, IG) from the spec's table §6.1
    type Anchor<'a> = (&'a [&'a [u32]], usize, u64, u64, u64);
    let anchors: [Anchor; 5] = [
        (&[&[0, 1, 2, 3]], 4, 12, 42, 56),
        (&[&[0, 1, 2], &[0, 3, 4]], 5, 18, 30, 36),
        (&[&[0, 1, 2], &[0, 1, 3], &[0, 1, 4]], 5, 26, 37, 46),
        (&[&[0, 1, 2, 3], &[0, 1, 4, 5]], 6, 24, 80, 108),
        (&[&[0, 1, 2], &[2, 3]], 4, 13, 19, 22),
    ];
    for (cells, nv, ia, is, ig) in anchors {
        let k = complex(nv, cells);
        let iastar = IaStar::new(&k).unwrap();
        assert_eq!(iastar.refs(), ia, "{cells:?}");
        assert_eq!(
            IaStar::refs_stellar_variant(&iastar),
            ia + 2 * iastar.n_tops(1)
        );
        assert_eq!(
            Is::new(&k, &stored(1 << 20)).unwrap().refs(),
            is,
            "{cells:?}"
        );
        assert_eq!(
            IncidenceGraph::new(&k, &stored(1 << 20)).unwrap().refs(),
            ig,
            "{cells:?}"
        );
    }
    for (name, k) in fixtures() {
        let m = Model::new(&k);
        assert_eq!(
            IaStar::new(&k).unwrap().refs(),
            iastar_formula(&m),
            "{name}"
        );
        assert_eq!(
            Is::new(&k, &stored(1 << 20)).unwrap().refs(),
            is_formula(&m),
            "{name}"
        );
        let bnd: u64 = m
            .all
            .iter()
            .filter(|s| s.len() >= 2)
            .map(|s| s.len() as u64)
            .sum();
        assert_eq!(
            IncidenceGraph::new(&k, &stored(1 << 20)).unwrap().refs(),
            2 * bnd,
            "{name}"
        );
        // IA on a pure pseudo-manifold: 2(d+1)t_d + Σ clusters
    }
}

// ------------------------------------------------------------------------------------------
// ghosts and non-manifold singularities

#[test]
fn ghosts_are_canonical_and_answer_relations() {
    for (name, k) in fixtures() {
        let m = Model::new(&k);
        let ia = IaStar::new(&k).unwrap();
        let mut seen = BTreeSet::new();
        for s in &m.all {
            if m.top_star(s).is_empty() {
                // an isolated vertex: no top names it, it is explicit anyway
                assert!(ia.ghost(&vs(s)).is_err());
                continue;
            }
            let g = ia.ghost(&vs(s)).unwrap();
            assert_eq!(ia.ghost_vertices(g).unwrap(), vs(s), "{name} {s:?}");
            assert!(seen.insert(g), "{name}: two simplices share ghost {g:?}");
            // the canonical top is the smallest (m, k) containing s
            let best = m
                .top_star(s)
                .into_iter()
                .map(|c| ia.dim_index(CellId(c)))
                .min()
                .unwrap();
            assert_eq!((g.m as usize, g.k), best, "{name} {s:?}");
            for q in 0..s.len().saturating_sub(1) {
                let gb = ia.ghost_boundary(g, q).unwrap();
                let mut got: Vec<Vec<u32>> = gb
                    .iter()
                    .map(|&h| ia.ghost_vertices(h).unwrap().iter().map(|v| v.0).collect())
                    .collect();
                got.sort();
                let want: Vec<Vec<u32>> = m
                    .all
                    .iter()
                    .filter(|t| t.len() == q + 1 && Model::contains(t, s))
                    .cloned()
                    .collect();
                assert_eq!(got, want, "{name} ghost boundary {s:?} {q}");
            }
            let gc = ia.ghost_coboundary(g, s.len()).unwrap();
            assert_eq!(
                gc.len(),
                m.star(s).iter().filter(|t| t.len() == s.len() + 1).count(),
                "{name} ghost coboundary {s:?}"
            );
        }
        // attributes on ghosts
        let mut attr: starplex::tds::iastar::GhostAttributes<u32> = Default::default();
        let mut n = 0;
        for (i, s) in m.all.iter().enumerate() {
            if let Ok(g) = ia.ghost(&vs(s)) {
                attr.insert(g, i as u32);
                n += 1;
            }
        }
        assert_eq!(attr.len(), n);
    }
}

#[test]
fn non_manifold_singularities_on_the_fixtures() {
    let v = |x: u32| VertexId(x);
    type Case = (&'static str, IndexedComplex, Vec<u32>, Vec<[u32; 2]>);
    let cases: Vec<Case> = vec![
        ("tetrahedron", complex(4, &[&[0, 1, 2, 3]]), vec![], vec![]),
        (
            "bow-tie",
            complex(5, &[&[0, 1, 2], &[0, 3, 4]]),
            vec![0],
            vec![],
        ),
        (
            "book",
            complex(5, &[&[0, 1, 2], &[0, 1, 3], &[0, 1, 4]]),
            vec![0, 1],
            vec![[0, 1]],
        ),
        (
            "two-tets-edge",
            complex(6, &[&[0, 1, 2, 3], &[0, 1, 4, 5]]),
            vec![0, 1],
            vec![[0, 1]],
        ),
        // the vertex where a dangling edge meets a surface is non-manifold; the edge's other
        // end and the edge itself are manifold (local dimension 1)
        (
            "dangling-edge",
            complex(4, &[&[0, 1, 2], &[2, 3]]),
            vec![2],
            vec![],
        ),
        ("isolated-vertex", complex(4, &[&[0, 1, 2]]), vec![], vec![]),
        (
            "two-tets-vertex",
            complex(7, &[&[0, 1, 2, 3], &[0, 4, 5, 6]]),
            vec![0],
            vec![],
        ),
    ];
    for (name, k, nmv, nme) in cases {
        let want_v: Vec<VertexId> = nmv.iter().map(|&x| v(x)).collect();
        let want_e: Vec<[VertexId; 2]> = nme.iter().map(|e| [v(e[0]), v(e[1])]).collect();
        let ia = IaStar::new(&k).unwrap();
        let is = Is::new(&k, &stored(1 << 20)).unwrap();
        for (sname, r) in [
            ("vt", singularities(&VtIndex::new(&k), Local).unwrap()),
            ("ia*", singularities(&ia, Local).unwrap()),
            ("is", singularities(&is, Local).unwrap()),
        ] {
            assert_eq!(r.non_manifold_vertices, want_v, "{name}/{sname}");
            assert_eq!(r.non_manifold_edges, want_e, "{name}/{sname}");
            assert!(r.unknown_vertices.is_empty());
        }
    }
    // a 4-simplex's boundary is a 3-sphere: vertex links are 2-spheres (decided), and a
    // 5-dimensional complex's vertex links are 4-dimensional: Unknown
    let sph: Vec<Vec<u32>> = (0..5u32)
        .map(|j| (0..5).filter(|&x| x != j).collect())
        .collect();
    let refs: Vec<&[u32]> = sph.iter().map(|x| x.as_slice()).collect();
    let k = complex(5, &refs);
    assert!(singularities(&IaStar::new(&k).unwrap(), Local)
        .unwrap()
        .non_manifold_vertices
        .is_empty());
    // the boundary of a 5-simplex: vertex links are 3-spheres, undecided
    let bd5: Vec<Vec<u32>> = (0..6u32)
        .map(|j| (0..6).filter(|&x| x != j).collect())
        .collect();
    let refs: Vec<&[u32]> = bd5.iter().map(|x| x.as_slice()).collect();
    let k = complex(6, &refs);
    let r = singularities(&VtIndex::new(&k), Local).unwrap();
    assert_eq!(r.unknown_vertices.len(), 6);
    assert_eq!(
        starplex::algo::manifold::vertex_manifoldness(&VtIndex::new(&k), VertexId(0), Local)
            .unwrap(),
        Manifoldness::Unknown
    );
    // a single 5-simplex: every link is a simplex, a ball
    let verts: Vec<u32> = (0..6).collect();
    let k = complex(6, &[&verts]);
    let r = singularities(&VtIndex::new(&k), Local).unwrap();
    assert!(r.unknown_vertices.is_empty() && r.non_manifold_vertices.is_empty());
}

// ------------------------------------------------------------------------------------------
// random complexes

fn random_complex(nv: usize, raw: &[Vec<u32>]) -> Option<IndexedComplex> {
    let mut tops: Vec<Vec<u32>> = raw
        .iter()
        .map(|t| {
            let mut t: Vec<u32> = t.iter().map(|&x| x % nv as u32).collect();
            t.sort_unstable();
            t.dedup();
            t
        })
        .filter(|t| t.len() >= 2)
        .collect();
    tops.sort();
    tops.dedup();
    let maximal: Vec<Vec<u32>> = tops
        .iter()
        .filter(|t| {
            !tops
                .iter()
                .any(|u| u.len() > t.len() && t.iter().all(|x| u.contains(x)))
        })
        .cloned()
        .collect();
    if maximal.is_empty() {
        return None;
    }
    let refs: Vec<&[u32]> = maximal.iter().map(|t| t.as_slice()).collect();
    Some(complex(nv, &refs))
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 60,
        rng_seed: proptest::test_runner::RngSeed::Fixed(20261122),
        failure_persistence: None,
        ..ProptestConfig::default()
    })]
    #[test]
    fn every_structure_matches_the_model_on_random_complexes(
        nv in 3usize..9,
        raw in proptest::collection::vec(proptest::collection::vec(0u32..64, 2..6), 1..7),
    ) {
        if let Some(k) = random_complex(nv, &raw) {
            check_all("random", &k);
            let m = Model::new(&k);
            prop_assert_eq!(IaStar::new(&k).unwrap().refs(), iastar_formula(&m));
            prop_assert_eq!(Is::new(&k, &stored(1 << 20)).unwrap().refs(), is_formula(&m));
            // components agree across structures
            let c0 = components(&VtIndex::new(&k));
            prop_assert_eq!(components(&IaStar::new(&k).unwrap()), c0.clone());
            prop_assert_eq!(components(&Is::new(&k, &stored(1 << 20)).unwrap()), c0.clone());
            prop_assert_eq!(components(&HasseQueries::new(&k, &stored(1 << 20)).unwrap()), c0);
            // non-manifold detection agrees across structures
            let r0 = singularities(&VtIndex::new(&k), Local).unwrap();
            prop_assert_eq!(singularities(&IaStar::new(&k).unwrap(), Local).unwrap(), r0.clone());
            prop_assert_eq!(
                singularities(&SimplexTree::new(&k, &SimplexTreeOptions::default()).unwrap(), Local).unwrap(),
                r0.clone()
            );
            prop_assert_eq!(singularities(&HasseQueries::new(&k, &stored(1 << 20)).unwrap(), Local).unwrap(), r0);
        }
    }
}

// ------------------------------------------------------------------------------------------
// the dataset oracles

fn u64s(v: &serde_json::Value) -> Vec<u64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_u64().unwrap())
        .collect()
}

fn check_oracle(name: &str, sname: &str, s: &dyn Queries, o: &serde_json::Value) {
    assert_eq!(
        s.f_vector().unwrap(),
        u64s(&o["f_vector"]),
        "{name}/{sname}"
    );
    assert_eq!(
        generic::euler_characteristic(s).unwrap(),
        o["euler_characteristic"].as_i64().unwrap(),
        "{name}/{sname}"
    );
    let (mut cells, mut vv) = (Vec::new(), Vec::new());
    for q in o["vertex_queries"].as_array().unwrap() {
        let v = VertexId(q["vertex"].as_u64().unwrap() as u32);
        s.vertex_top_cells(v, &mut cells);
        let got: Vec<u64> = cells.iter().map(|c| c.0 as u64).collect();
        assert_eq!(
            got,
            u64s(&q["incident_top_cells"]),
            "{name}/{sname} vt({v})"
        );
        s.vertex_neighbours(v, &mut vv);
        let got: Vec<u64> = vv.iter().map(|w| w.0 as u64).collect();
        assert_eq!(got, u64s(&q["vv"]), "{name}/{sname} vv({v})");
        if let Some(lf) = q.get("link_f_vector") {
            let l = generic::link(s, &[v]).unwrap();
            assert_eq!(l.f_vector(), u64s(lf), "{name}/{sname} link f-vector({v})");
        }
    }
}

#[test]
fn every_structure_matches_the_oracles_on_the_small_datasets() {
    let mut sets = common_data::small_datasets();
    if sets.is_empty() {
        // a worktree one level deeper than the repository: STARPLEX_SHARED names shared/
        if let (Ok(shared), Ok(data)) = (
            std::env::var("STARPLEX_SHARED"),
            std::env::var("STARPLEX_DATA"),
        ) {
            for e in std::fs::read_dir(std::path::Path::new(&data).join("small"))
                .into_iter()
                .flatten()
                .flatten()
            {
                let name = e.file_name().to_string_lossy().into_owned();
                let spx = e.path().join(format!("{name}.spx"));
                let oracle = std::path::Path::new(&shared)
                    .join("datasets/oracle")
                    .join(format!("{name}.json"));
                if let (true, Ok(text)) = (spx.exists(), std::fs::read_to_string(oracle)) {
                    sets.push((name, spx, serde_json::from_str(&text).unwrap()));
                }
            }
        }
    }
    if sets.is_empty() {
        eprintln!("SKIPPED: no small datasets with oracles found (set STARPLEX_DATA=/work/data, and STARPLEX_SHARED=/work/shared from a worktree)");
        return;
    }
    let mut n_checked = 0;
    for (name, path, o) in sets {
        let k = starplex::io::read(&path, &Default::default())
            .unwrap()
            .complex;
        let vt = VtIndex::new(&k);
        let (mut cells, mut vv) = (Vec::new(), Vec::new());
        for q in o["vertex_queries"].as_array().unwrap() {
            let v = VertexId(q["vertex"].as_u64().unwrap() as u32);
            vt.vertex_top_cells(v, &mut cells);
            let got: Vec<u64> = cells.iter().map(|c| c.0 as u64).collect();
            assert_eq!(got, u64s(&q["incident_top_cells"]), "{name}/vt");
            vt.vertex_neighbours(v, &mut vv);
            let got: Vec<u64> = vv.iter().map(|w| w.0 as u64).collect();
            assert_eq!(got, u64s(&q["vv"]), "{name}/vt");
        }
        if !k.is_simplicial() {
            // the structures that hold CP cells: VT and VV (tests/suite/cp_oracle_small.rs checks more)
            let ig = IncidenceGraph::new(&k, &stored(1 << 30)).unwrap();
            let ia = IaStar::new(&k).unwrap();
            for (sname, s) in [("ig", &ig as &dyn Queries), ("ia*", &ia)] {
                for q in o["vertex_queries"].as_array().unwrap() {
                    let v = VertexId(q["vertex"].as_u64().unwrap() as u32);
                    s.vertex_top_cells(v, &mut cells);
                    let got: Vec<u64> = cells.iter().map(|c| c.0 as u64).collect();
                    assert_eq!(got, u64s(&q["incident_top_cells"]), "{name}/{sname}");
                    s.vertex_neighbours(v, &mut vv);
                    let got: Vec<u64> = vv.iter().map(|w| w.0 as u64).collect();
                    assert_eq!(got, u64s(&q["vv"]), "{name}/{sname}");
                }
            }
            let f = starplex::topo::Counts::f_vector(&ig).unwrap();
            assert_eq!(f, u64s(&o["f_vector"]), "{name}/ig");
            continue;
        }
        check_oracle(&name, "vt", &vt, &o);
        let ia = IaStar::new(&k).unwrap();
        check_oracle(&name, "ia*", &ia, &o);
        let st = SimplexTree::new(
            &k,
            &SimplexTreeOptions {
                label_lists: true,
                ..Default::default()
            },
        )
        .unwrap();
        check_oracle(&name, "simplex-tree", &st, &o);
        check_oracle(
            &name,
            "ig",
            &IncidenceGraph::new(&k, &stored(1 << 30)).unwrap(),
            &o,
        );
        let is = Is::new(&k, &stored(1 << 30)).unwrap();
        check_oracle(&name, "is", &is, &o);
        check_oracle(
            &name,
            "hasse",
            &HasseQueries::new(&k, &stored(1 << 30)).unwrap(),
            &o,
        );
        let stellar = StellarTree::build(&k, &StellarOptions::default()).unwrap();
        check_oracle(&name, "stellar", &stellar, &o);
        check_oracle(&name, "stellar-ia*", &stellar.iastar(), &o);
        if let Some(nmv) = o.get("n_non_manifold_vertices").and_then(|x| x.as_u64()) {
            for (sname, r) in [
                ("ia*", singularities(&ia, Local).unwrap()),
                ("is", singularities(&is, Local).unwrap()),
            ] {
                assert_eq!(r.non_manifold_vertices.len() as u64, nmv, "{name}/{sname}");
                if let Some(nme) = o.get("n_non_manifold_edges").and_then(|x| x.as_u64()) {
                    assert_eq!(r.non_manifold_edges.len() as u64, nme, "{name}/{sname}");
                }
            }
        }
        n_checked += 1;
    }
    assert!(
        n_checked >= 5,
        "only {n_checked} simplicial datasets checked"
    );
}

// ------------------------------------------------------------------------------------------
// CP complexes: the incidence graph and IA* against a brute-force model of cells

/// Every cell of a CP complex from the kinds' face tables, named by its sorted vertices.
struct CpModel {
    nv: usize,
    kinds: Vec<CellKind>,
    /// Vertices of each top, input order.
    tops: Vec<Vec<u32>>,
    /// Per top: its faces of every dimension (itself included), as (dimension, sorted key).
    faces: Vec<BTreeSet<(usize, Vec<u32>)>>,
    /// Every cell, vertices included.
    cells: BTreeSet<(usize, Vec<u32>)>,
}

impl CpModel {
    fn new(k: &IndexedComplex) -> CpModel {
        let mut m = CpModel {
            nv: k.n_vertices(),
            kinds: Vec::new(),
            tops: Vec::new(),
            faces: Vec::new(),
            cells: (0..k.n_vertices() as u32).map(|v| (0, vec![v])).collect(),
        };
        for c in k.cells() {
            let mut f = BTreeSet::new();
            for p in 0..=c.kind.dim() {
                c.kind.for_each_face(p, |l| {
                    let mut key: Vec<u32> = l.iter().map(|&i| c.vertices[i as usize]).collect();
                    key.sort_unstable();
                    f.insert((p, key));
                });
            }
            m.cells.extend(f.iter().cloned());
            m.kinds.push(c.kind);
            m.tops.push(c.vertices.to_vec());
            m.faces.push(f);
        }
        m
    }
    /// Keys naming a single cell (a key of two levels, e.g. a quad face and a tetrahedron on
    /// the same four vertices, is ambiguous by vertices).
    fn unambiguous(&self, key: &[u32]) -> bool {
        self.cells.iter().filter(|c| c.1 == key).count() == 1
    }
    fn top_star(&self, s: &(usize, Vec<u32>)) -> Vec<u32> {
        (0..self.tops.len() as u32)
            .filter(|&c| self.faces[c as usize].contains(s))
            .collect()
    }
    /// The q-cells having `s` as a face (q > p) or being a face of `s` (q < p).
    fn related(&self, s: &(usize, Vec<u32>), q: usize) -> Vec<Vec<u32>> {
        let mut out = BTreeSet::new();
        for f in self.faces.iter().filter(|f| f.contains(s)) {
            for t in f.iter().filter(|t| t.0 == q) {
                let sub = |a: &[u32], b: &[u32]| a.iter().all(|x| b.contains(x));
                if (q < s.0 && sub(&t.1, &s.1)) || (q > s.0 && sub(&s.1, &t.1)) {
                    out.insert(t.1.clone());
                }
            }
        }
        out.into_iter().collect()
    }
    fn vv(&self, v: u32) -> Vec<u32> {
        self.cells
            .iter()
            .filter(|c| c.0 == 1 && c.1.contains(&v))
            .map(|c| if c.1[0] == v { c.1[1] } else { c.1[0] })
            .collect()
    }
    fn adjacent(&self, s: &(usize, Vec<u32>)) -> Vec<Vec<u32>> {
        if s.0 == 0 {
            return self.vv(s.1[0]).into_iter().map(|w| vec![w]).collect();
        }
        let mine = self.related(s, s.0 - 1);
        self.cells
            .iter()
            .filter(|t| t.0 == s.0 && *t != s)
            .filter(|t| self.related(t, s.0 - 1).iter().any(|f| mine.contains(f)))
            .map(|t| t.1.clone())
            .collect()
    }
    fn f_vector(&self) -> Vec<u64> {
        let mut f = Vec::new();
        for c in &self.cells {
            if f.len() <= c.0 {
                f.resize(c.0 + 1, 0);
            }
            f[c.0] += 1;
        }
        f
    }
    /// Local facets of a top of `kind` (simplex: facet j omits vertex j; CP: the table).
    fn facet_locals(kind: CellKind) -> Vec<Vec<u8>> {
        match kind {
            CellKind::Simplex(d) => (0..=d)
                .map(|j| (0..=d).filter(|&x| x != j).collect())
                .collect(),
            _ => kind
                .cp_faces(kind.dim() - 1)
                .unwrap()
                .iter()
                .map(|f| f.to_vec())
                .collect(),
        }
    }
}

/// The answer of a flat-tuple relation: the model's cells if they are all simplices, else a
/// `NotSimplicial` refusal.
fn flat_or_refusal(
    name: &str,
    got: Result<Vec<VertexId>, QueryError>,
    want: &[Vec<u32>],
    q: usize,
) {
    if want.iter().all(|t| t.len() == q + 1) {
        assert_eq!(got.unwrap(), flat(want), "{name}");
    } else {
        assert!(
            matches!(got, Err(QueryError::NotSimplicial(_))),
            "{name}: {got:?}"
        );
    }
}

fn check_cp_ig(name: &str, ig: &IncidenceGraph, m: &CpModel) {
    use starplex::ids::SimplexId;
    use starplex::topo::{Adjacency, Boundary, Coboundary, Counts, Star, TopStar};
    use starplex::topo::{Levels, SimplexVertices, TopCells};
    assert_eq!(ig.n_vertices(), m.nv, "{name}");
    assert_eq!(ig.n_top_cells(), m.tops.len(), "{name}");
    let mut buf = Vec::new();
    for c in 0..m.tops.len() {
        buf.clear();
        ig.top_cell_vertices(CellId(c as u32), &mut buf);
        // input order with CP cells (the tables index it), sorted for a simplicial complex
        let mut want = m.tops[c].clone();
        if m.kinds.iter().all(|k| k.is_simplex()) {
            want.sort_unstable();
        }
        assert_eq!(buf, vs(&want), "{name}: top {c}");
        assert_eq!(ig.top_cell_kind(CellId(c as u32)), m.kinds[c], "{name}");
    }
    let f = m.f_vector();
    assert_eq!(ig.f_vector().unwrap(), f, "{name}: f-vector");
    let bnd: u64 = m
        .cells
        .iter()
        .filter(|c| c.0 >= 1)
        .map(|c| m.related(c, c.0 - 1).len() as u64)
        .sum();
    assert_eq!(ig.refs(), 2 * bnd, "{name}: references");
    let (mut cells, mut vv, mut out) = (Vec::new(), Vec::new(), Vec::new());
    for v in 0..m.nv as u32 {
        ig.vertex_top_cells(VertexId(v), &mut cells);
        let want: Vec<CellId> = m.top_star(&(0, vec![v])).into_iter().map(CellId).collect();
        assert_eq!(cells, want, "{name}: VT({v})");
        ig.vertex_neighbours(VertexId(v), &mut vv);
        assert_eq!(vv, vs(&m.vv(v)), "{name}: VV({v})");
    }
    for p in 0..f.len() {
        let mut got = Vec::new();
        let r = ig.for_each_simplex(p, &mut |t| got.extend_from_slice(t));
        let want: Vec<Vec<u32>> = m
            .cells
            .iter()
            .filter(|c| c.0 == p)
            .map(|c| c.1.clone())
            .collect();
        flat_or_refusal(&format!("{name}: level {p}"), r.map(|_| got), &want, p);
    }
    let keys = |ids: Vec<SimplexId>| -> Vec<Vec<u32>> {
        let mut l: Vec<Vec<u32>> = ids
            .into_iter()
            .map(|i| {
                let mut b = Vec::new();
                ig.simplex_vertices(i, &mut b);
                b.iter().map(|v| v.0).collect()
            })
            .collect();
        l.sort();
        l
    };
    for sigma in m.cells.iter().filter(|c| m.unambiguous(&c.1)) {
        let (p, key) = (sigma.0, &sigma.1);
        let sv = vs(key);
        let id = ig.find_simplex(&sv).unwrap();
        assert_eq!(ig.cell_dim(id), Some(p), "{name}: {key:?}");
        ig.simplex_vertices(id, &mut buf);
        assert_eq!(buf, sv, "{name}");
        ig.top_star(&sv, &mut cells).unwrap();
        let want: Vec<CellId> = m.top_star(sigma).into_iter().map(CellId).collect();
        assert_eq!(cells, want, "{name}: St_T({key:?})");
        for q in 0..f.len() {
            let want = m.related(sigma, q);
            if q < p {
                assert_eq!(
                    keys(ig.cell_faces(id, q).unwrap()),
                    want,
                    "{name}: {key:?} {q}"
                );
                let r = ig.boundary(&sv, q, &mut out).map(|_| out.clone());
                flat_or_refusal(&format!("{name}: R_{p},{q}({key:?})"), r, &want, q);
            } else if q > p {
                assert_eq!(
                    keys(ig.cell_cofaces(id, q).unwrap()),
                    want,
                    "{name}: {key:?} {q}"
                );
                let r = ig.coboundary(&sv, q, &mut out).map(|_| out.clone());
                flat_or_refusal(&format!("{name}: R_{p},{q}({key:?})"), r, &want, q);
            }
        }
        let want = m.adjacent(sigma);
        assert_eq!(
            keys(ig.cell_adjacent(id).unwrap()),
            want,
            "{name}: adj {key:?}"
        );
        let r = ig.adjacent(&sv, &mut out).map(|_| out.clone());
        flat_or_refusal(&format!("{name}: R_{p},{p}({key:?})"), r, &want, p);
        // the star: every coface, σ included
        let star: Vec<Vec<u32>> = (p..f.len())
            .flat_map(|q| {
                if q == p {
                    vec![key.clone()]
                } else {
                    m.related(sigma, q)
                }
            })
            .collect();
        match ig.star(&sv) {
            Ok(st) => {
                assert!(star.iter().all(|t| t.len() <= p + 1 + (t.len() - p - 1)));
                let got: Vec<Vec<u32>> =
                    st.iter().map(|t| t.iter().map(|v| v.0).collect()).collect();
                let mut want = star.clone();
                want.sort_by(|a, b| a.len().cmp(&b.len()).then(a.cmp(b)));
                assert_eq!(got, want, "{name}: St({key:?})");
            }
            Err(QueryError::NotSimplicial(_)) => {
                let dims: Vec<usize> = (p..f.len()).collect();
                assert!(
                    dims.iter()
                        .any(|&q| m.related(sigma, q).iter().any(|t| t.len() != q + 1))
                        || key.len() != p + 1,
                    "{name}: St({key:?}) refused without a CP cell"
                );
            }
            Err(e) => panic!("{name}: St({key:?}): {e}"),
        }
    }
    assert!(ig.star(&[VertexId(m.nv as u32 + 5)]).is_err());
    assert!(ig.cell_faces(SimplexId(u32::MAX), 0).is_err());
}

/// Any IA* (the standalone one or the Stellar tree's) on a CP complex against the model:
/// vertices, VT, VV, every facet slot, the non-manifold facets, the vertex references, the
/// reference count and the top stars.
fn check_cp_ia<A: FacetAdjacency + Queries>(name: &str, ia: &A, m: &CpModel) {
    use starplex::topo::Adjacent as Adj;
    assert_eq!(ia.n_vertices(), m.nv, "{name}");
    assert_eq!(ia.n_top_cells(), m.tops.len(), "{name}");
    let mut buf = Vec::new();
    for c in 0..m.tops.len() {
        buf.clear();
        ia.top_cell_vertices(CellId(c as u32), &mut buf);
        assert_eq!(buf, vs(&m.tops[c]), "{name}: top {c} (input order)");
        assert_eq!(ia.top_cell_kind(CellId(c as u32)), m.kinds[c], "{name}");
    }
    let (mut cells, mut vv) = (Vec::new(), Vec::new());
    for v in 0..m.nv as u32 {
        ia.vertex_top_cells(VertexId(v), &mut cells);
        let want: Vec<CellId> = m.top_star(&(0, vec![v])).into_iter().map(CellId).collect();
        assert_eq!(cells, want, "{name}: VT({v})");
        ia.vertex_neighbours(VertexId(v), &mut vv);
        assert_eq!(vv, vs(&m.vv(v)), "{name}: VV({v})");
    }
    // adjacency slots: none, the other top, or a non-manifold facet with all its tops
    let facet_key = |c: usize, l: &[u8]| -> Vec<u32> {
        let mut k: Vec<u32> = l.iter().map(|&i| m.tops[c][i as usize]).collect();
        k.sort_unstable();
        k
    };
    let mut refs: u64 = m.tops.iter().map(|t| t.len() as u64).sum();
    let mut nm_refs = 0u64;
    let mut nm_seen = BTreeSet::new();
    for c in 0..m.tops.len() {
        let d = m.kinds[c].dim();
        let slots = ia.facet_adjacency(CellId(c as u32));
        if d < 2 {
            assert!(slots.is_empty(), "{name}");
            continue;
        }
        let locals = CpModel::facet_locals(m.kinds[c]);
        assert_eq!(slots.len(), locals.len(), "{name}: slots of {c}");
        refs += slots.len() as u64;
        for (j, l) in locals.iter().enumerate() {
            let key = facet_key(c, l);
            let with: Vec<u32> = (0..m.tops.len() as u32)
                .filter(|&u| m.kinds[u as usize].dim() == d)
                .filter(|&u| m.faces[u as usize].contains(&(d - 1, key.clone())))
                .collect();
            match (with.len(), slots[j]) {
                (1, Adj::None) => {}
                (2, Adj::Top(u)) => {
                    assert_eq!(u.0, with.iter().copied().find(|&x| x != c as u32).unwrap())
                }
                (n, Adj::NmFace(f)) if n >= 3 => {
                    let tops: Vec<u32> = ia.nm_face_cells(f).iter().map(|c| c.0).collect();
                    assert_eq!(tops, with, "{name}");
                    assert_eq!(ia.nm_face_vertices(f), vs(&key), "{name}");
                    if nm_seen.insert(f) {
                        nm_refs += n as u64;
                    }
                }
                (n, a) => panic!("{name}: top {c} facet {j} {key:?}: {n} tops, slot {a:?}"),
            }
        }
    }
    // per vertex: every top of dimension <= 1, and the smallest top of each k-cluster
    for v in 0..m.nv as u32 {
        let star: Vec<usize> = (0..m.tops.len())
            .filter(|&c| m.tops[c].contains(&v))
            .collect();
        let mut reps: Vec<u32> = Vec::new();
        let mut uf = starplex::algo::unionfind::UnionFind::new(star.len());
        for a in 0..star.len() {
            for b in a + 1..star.len() {
                let (ca, cb) = (star[a], star[b]);
                let d = m.kinds[ca].dim();
                if d < 2 || m.kinds[cb].dim() != d {
                    continue;
                }
                let shares = CpModel::facet_locals(m.kinds[ca]).iter().any(|l| {
                    let key = facet_key(ca, l);
                    key.contains(&v) && m.faces[cb].contains(&(d - 1, key))
                });
                if shares {
                    uf.union(a as u32, b as u32);
                }
            }
        }
        for (i, &c) in star.iter().enumerate() {
            if m.kinds[c].dim() <= 1 || (0..i).all(|j| uf.find(j as u32) != uf.find(i as u32)) {
                reps.push(c as u32);
            }
        }
        let got: Vec<u32> = ia
            .vertex_references(VertexId(v))
            .iter()
            .map(|c| c.0)
            .collect();
        assert_eq!(got, reps, "{name}: refs of {v}");
        refs += reps.len() as u64;
    }
    assert_eq!(ia.refs(), refs + nm_refs, "{name}: references");
    for sigma in m.cells.iter().filter(|c| m.unambiguous(&c.1)) {
        let want = m.top_star(sigma);
        if want.is_empty() {
            continue; // an isolated vertex
        }
        ia.top_star(&vs(&sigma.1), &mut cells).unwrap();
        let w: Vec<CellId> = want.iter().copied().map(CellId).collect();
        assert_eq!(cells, w, "{name}: St_T({:?})", sigma.1);
    }
}

/// The standalone IA* on a CP complex: [`check_cp_ia`], and the ghosts of every cell.
fn check_cp_iastar(name: &str, ia: &IaStar, m: &CpModel) {
    check_cp_ia(name, ia, m);
    let mut seen = BTreeSet::new();
    for sigma in m.cells.iter().filter(|c| m.unambiguous(&c.1)) {
        let sv = vs(&sigma.1);
        let want = m.top_star(sigma);
        if want.is_empty() {
            continue; // an isolated vertex
        }
        let g = ia.ghost(&sv).unwrap();
        assert_eq!(g.p as usize, sigma.0, "{name}: ghost {sigma:?}");
        assert_eq!(ia.ghost_vertices(g).unwrap(), sv, "{name}: ghost {sigma:?}");
        assert!(seen.insert(g), "{name}: two cells share ghost {g:?}");
        let best = want.iter().map(|&c| ia.dim_index(CellId(c))).min().unwrap();
        assert_eq!(
            (g.m as usize, g.k),
            best,
            "{name}: canonical top of {sigma:?}"
        );
        let names = |gs: Vec<starplex::tds::iastar::Ghost>| -> Vec<Vec<u32>> {
            let mut l: Vec<Vec<u32>> = gs
                .into_iter()
                .map(|h| ia.ghost_vertices(h).unwrap().iter().map(|v| v.0).collect())
                .collect();
            l.sort();
            l
        };
        for q in 0..sigma.0 {
            assert_eq!(
                names(ia.ghost_boundary(g, q).unwrap()),
                m.related(sigma, q),
                "{name}: ghost boundary {sigma:?} {q}"
            );
        }
        let q = sigma.0 + 1;
        assert_eq!(
            names(ia.ghost_coboundary(g, q).unwrap()),
            m.related(sigma, q),
            "{name}: ghost co-boundary {sigma:?}"
        );
        if sigma.0 >= 1 {
            assert_eq!(
                names(ia.ghost_adjacent(g).unwrap()),
                m.adjacent(sigma),
                "{name}: ghost adjacency {sigma:?}"
            );
        }
    }
}

fn cp_complex(nv: usize, cells: &[(CellKind, &[u32])]) -> IndexedComplex {
    let mut b = ComplexBuilder::new(3).unwrap();
    for i in 0..nv {
        b.push_vertex(&[i as f64, (i * i % 7) as f64, (i % 3) as f64])
            .unwrap();
    }
    for (kind, c) in cells {
        b.push_cell(*kind, c).unwrap();
    }
    b.build(&BuildOptions::default()).unwrap().0
}

fn cp_fixtures() -> Vec<(&'static str, IndexedComplex)> {
    use CellKind::{Hex, Prism, Pyramid, Quad, Simplex};
    vec![
        ("quad", cp_complex(4, &[(Quad, &[0, 1, 2, 3])])),
        (
            "quad-strip-and-triangle",
            cp_complex(
                8,
                &[
                    (Quad, &[0, 1, 4, 3]),
                    (Quad, &[1, 2, 5, 4]),
                    (Simplex(2), &[4, 5, 6]),
                    (Simplex(1), &[6, 7]),
                ],
            ),
        ),
        (
            "quad-book",
            cp_complex(
                8,
                &[
                    (Quad, &[0, 1, 2, 3]),
                    (Quad, &[0, 1, 4, 5]),
                    (Quad, &[1, 0, 6, 7]),
                ],
            ),
        ),
        (
            "quad-bow-tie",
            cp_complex(7, &[(Quad, &[0, 1, 2, 3]), (Quad, &[0, 4, 5, 6])]),
        ),
        ("hex", cp_complex(8, &[(Hex, &[0, 1, 2, 3, 4, 5, 6, 7])])),
        (
            "two-hexes",
            cp_complex(
                12,
                &[
                    (Hex, &[0, 1, 2, 3, 4, 5, 6, 7]),
                    (Hex, &[1, 8, 9, 2, 5, 10, 11, 6]),
                ],
            ),
        ),
        (
            "three-hexes-on-a-quad",
            cp_complex(
                20,
                &[
                    (Hex, &[0, 1, 2, 3, 4, 5, 6, 7]),
                    (Hex, &[1, 8, 9, 2, 5, 10, 11, 6]),
                    (Hex, &[1, 12, 13, 2, 5, 14, 15, 6]),
                    (Hex, &[16, 17, 18, 19, 0, 1, 2, 3]),
                ],
            ),
        ),
        (
            "mixed-3d",
            cp_complex(
                15,
                &[
                    (Hex, &[0, 1, 2, 3, 4, 5, 6, 7]),
                    (Prism, &[2, 8, 3, 6, 9, 7]),
                    (Pyramid, &[4, 5, 6, 7, 10]),
                    (Simplex(3), &[5, 6, 10, 11]),
                    (Simplex(3), &[6, 9, 7, 12]),
                    (Simplex(2), &[0, 1, 13]),
                    (Simplex(1), &[13, 14]),
                ],
            ),
        ),
        (
            "hexes-on-a-vertex-and-an-edge",
            cp_complex(
                21,
                &[
                    (Hex, &[0, 1, 2, 3, 4, 5, 6, 7]),
                    (Hex, &[7, 8, 9, 10, 11, 12, 13, 14]),
                    (Hex, &[0, 1, 15, 16, 17, 18, 19, 20]),
                ],
            ),
        ),
    ]
}

#[test]
fn ig_and_iastar_answer_every_relation_on_the_cp_fixtures() {
    for (name, k) in cp_fixtures() {
        let m = CpModel::new(&k);
        check_cp_ig(
            &format!("{name}/ig"),
            &IncidenceGraph::new(&k, &stored(1 << 30)).unwrap(),
            &m,
        );
        check_cp_iastar(&format!("{name}/ia*"), &IaStar::new(&k).unwrap(), &m);
        // VT and VV are the same from every structure that holds CP cells
        let vt = VtIndex::new(&k);
        let t = StellarTree::build(&k, &StellarOptions::default()).unwrap();
        check_cp_ia(&format!("{name}/stellar-ia*"), &t.iastar(), &m);
        let (mut a, mut b) = (Vec::new(), Vec::new());
        for v in 0..k.n_vertices() as u32 {
            vt.vertex_neighbours(VertexId(v), &mut a);
            t.vertex_neighbours(VertexId(v), &mut b);
            assert_eq!(a, b, "{name}: VV({v}) vt/stellar");
            assert_eq!(a, vs(&m.vv(v)), "{name}: VV({v}) model");
        }
    }
}

#[test]
fn simplicial_only_structures_refuse_cp_complexes_naming_one_that_answers() {
    let (_, k) = cp_fixtures().swap_remove(1);
    let st = SimplexTree::new(&k, &SimplexTreeOptions::default()).unwrap_err();
    let is = Is::new(&k, &stored(1 << 20)).unwrap_err();
    for e in [st, is] {
        assert!(matches!(e, BuildError::NotSimplicial(ref n) if n.cell == 0));
        assert!(e
            .to_string()
            .contains("the incidence graph, IA* and the Stellar tree"));
    }
    assert!(HasseQueries::new(&k, &stored(1 << 20)).is_err());
}

/// A random CP complex: cells of random kinds on few vertices (faces of other cells and
/// duplicates dropped).
fn random_cp_complex(nv: usize, raw: &[(u8, Vec<u32>)]) -> Option<IndexedComplex> {
    const KINDS: [CellKind; 9] = [
        CellKind::Simplex(1),
        CellKind::Simplex(2),
        CellKind::Simplex(3),
        CellKind::Quad,
        CellKind::Quad,
        CellKind::Pyramid,
        CellKind::Prism,
        CellKind::Hex,
        CellKind::Hex,
    ];
    let mut b = ComplexBuilder::new(1).unwrap();
    for i in 0..nv {
        b.push_vertex(&[i as f64]).unwrap();
    }
    let mut any = false;
    for (kind, vs) in raw {
        let kind = KINDS[*kind as usize % KINDS.len()];
        let mut d: Vec<u32> = Vec::new();
        for &v in vs {
            let v = v % nv as u32;
            if !d.contains(&v) {
                d.push(v);
            }
        }
        if d.len() >= kind.n_vertices() {
            b.push_cell(kind, &d[..kind.n_vertices()]).unwrap();
            any = true;
        }
    }
    if !any {
        return None;
    }
    let k = b
        .build(&BuildOptions {
            drop_face_cells: true,
            drop_duplicates: true,
            ..Default::default()
        })
        .ok()?
        .0;
    (k.n_cells() > 0).then_some(k)
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 80,
        rng_seed: proptest::test_runner::RngSeed::Fixed(20261201),
        failure_persistence: None,
        ..ProptestConfig::default()
    })]
    #[test]
    fn ig_and_iastar_match_the_model_on_random_cp_complexes(
        nv in 4usize..14,
        raw in proptest::collection::vec((0u8..9, proptest::collection::vec(0u32..64, 8)), 1..7),
    ) {
        if let Some(k) = random_cp_complex(nv, &raw) {
            let m = CpModel::new(&k);
            check_cp_ig("random/ig", &IncidenceGraph::new(&k, &stored(1 << 30)).unwrap(), &m);
            check_cp_iastar("random/ia*", &IaStar::new(&k).unwrap(), &m);
            let c0 = components(&VtIndex::new(&k));
            prop_assert_eq!(components(&IaStar::new(&k).unwrap()), c0.clone());
            prop_assert_eq!(components(&IncidenceGraph::new(&k, &stored(1 << 30)).unwrap()), c0);
        }
    }
}
