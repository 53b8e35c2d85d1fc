//! ONE test suite over every structure (VtIndex baseline, IA*, simplex tree with and without
//! label lists, incidence graph, IS, the CASC Hasse diagram, the Stellar tree for several k_V):
//! every relation is compared with a brute-force model
//! (all simplices enumerated from the tops) on named fixtures and on seeded random complexes,
//! and with the dataset oracles (vertex queries, f-vector, Euler characteristic).
mod common_data;

use std::collections::BTreeSet;

use proptest::prelude::*;
use starplex::algo::components::components;
use starplex::algo::manifold::{singularities, Convention::Local, Manifoldness};
use starplex::cell::CellKind;
use starplex::complex::{BuildOptions, ComplexBuilder, IndexedComplex};
use starplex::hasse::HasseQueries;
use starplex::ids::{CellId, VertexId};
use starplex::stellar::{StellarOptions, StellarTree};
use starplex::tds::iastar::IaStar;
use starplex::tds::ig::IncidenceGraph;
use starplex::tds::is::Is;
use starplex::tds::simplex_tree::{BuildError, SimplexTree, SimplexTreeOptions};
use starplex::topo::{
    generic, naive::VtIndex, Queries, QueryError, Storage, VertexAdjacency, VertexStar,
};

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
    }
    let (mut cells, mut vv, mut out) = (Vec::new(), Vec::new(), Vec::new());
    for v in 0..m.nv as u32 {
        s.vertex_top_cells(VertexId(v), &mut cells);
        let want: Vec<CellId> = m.top_star(&[v]).into_iter().map(CellId).collect();
        assert_eq!(cells, want, "{name}: VT({v})");
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
        &IncidenceGraph::new(k, 1 << 30).unwrap(),
        &m,
        true,
    );
    check_structure(
        &format!("{name}/is"),
        &Is::new(k, 1 << 30).unwrap(),
        &m,
        true,
    );
    check_structure(
        &format!("{name}/hasse"),
        &HasseQueries::new(k, 1 << 30).unwrap(),
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
            Err(QueryError::TooLarge { estimate, .. }) => assert!(estimate >= 1 << 40),
            other => panic!("{name}: expected a refusal, got {other:?}"),
        }
        assert!(matches!(s.f_vector(), Err(QueryError::TooLarge { .. })));
    };
    check_tops("vt", &VtIndex::new(&k));
    let ia = IaStar::new(&k).unwrap();
    check_tops("ia*", &ia);
    assert_eq!(ia.refs(), 41 + 41 + 41);
    let too_large = |r: Result<(), BuildError>| match r {
        Err(BuildError::TooLarge { estimate, .. }) => assert!(estimate >= 1 << 41),
        other => panic!("expected a refusal, got {other:?}"),
    };
    too_large(SimplexTree::new(&k, &SimplexTreeOptions::default()).map(|_| ()));
    too_large(IncidenceGraph::new(&k, u32::MAX as u128).map(|_| ()));
    too_large(Is::new(&k, u32::MAX as u128).map(|_| ()));
    assert!(matches!(
        HasseQueries::new(&k, u32::MAX as u128),
        Err(starplex::hasse::HasseError::TooManyFaces { estimate, .. }) if estimate >= 1 << 41
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
        assert_eq!(Is::new(&k, 1 << 20).unwrap().refs(), is, "{cells:?}");
        assert_eq!(
            IncidenceGraph::new(&k, 1 << 20).unwrap().refs(),
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
            Is::new(&k, 1 << 20).unwrap().refs(),
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
            IncidenceGraph::new(&k, 1 << 20).unwrap().refs(),
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
        let is = Is::new(&k, 1 << 20).unwrap();
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
            prop_assert_eq!(Is::new(&k, 1 << 20).unwrap().refs(), is_formula(&m));
            // components agree across structures
            let c0 = components(&VtIndex::new(&k));
            prop_assert_eq!(components(&IaStar::new(&k).unwrap()), c0.clone());
            prop_assert_eq!(components(&Is::new(&k, 1 << 20).unwrap()), c0.clone());
            prop_assert_eq!(components(&HasseQueries::new(&k, 1 << 20).unwrap()), c0);
            // non-manifold detection agrees across structures
            let r0 = singularities(&VtIndex::new(&k), Local).unwrap();
            prop_assert_eq!(singularities(&IaStar::new(&k).unwrap(), Local).unwrap(), r0.clone());
            prop_assert_eq!(
                singularities(&SimplexTree::new(&k, &SimplexTreeOptions::default()).unwrap(), Local).unwrap(),
                r0.clone()
            );
            prop_assert_eq!(singularities(&HasseQueries::new(&k, 1 << 20).unwrap(), Local).unwrap(), r0);
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
            assert!(IaStar::new(&k).is_err(), "{name}: IA* refuses CP cells");
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
        check_oracle(&name, "ig", &IncidenceGraph::new(&k, 1 << 30).unwrap(), &o);
        let is = Is::new(&k, 1 << 30).unwrap();
        check_oracle(&name, "is", &is, &o);
        check_oracle(&name, "hasse", &HasseQueries::new(&k, 1 << 30).unwrap(), &o);
        let stellar = StellarTree::build(&k, &StellarOptions::default()).unwrap();
        check_oracle(&name, "stellar", &stellar, &o);
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
