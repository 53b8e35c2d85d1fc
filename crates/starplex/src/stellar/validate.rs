//! Topological validation on a Stellar tree, leaf by leaf: connected components, (d-1)-
//! connectedness, purity, pseudo-manifoldness, boundary (d-1)-faces, non-manifold vertices and
//! edges, orientability with a consistent orientation. Every problem comes with its ids (input
//! numbering).
//!
//! Manifoldness is the one definition of [`crate::algo::manifold`] under its global convention
//! (d = dimension of the complex): each leaf is a [`LocalStar`](crate::topo::LocalStar) part and
//! runs [`crate::algo::manifold::local_singularities`], whose star tests are those
//! [`crate::algo::manifold::singularities`] uses on any structure, so the two give the same
//! answer (a test holds them equal). Exact for d <= 3; for d >= 4 undecided
//! simplices are reported as unknown.
//!
//! ```
//! # use starplex::complex::{ComplexBuilder, BuildOptions};
//! # use starplex::cell::CellKind;
//! use starplex::stellar::{StellarTree, StellarOptions};
//! use starplex::ids::VertexId;
//! // a bow tie: two triangles sharing vertex 0
//! let mut b = ComplexBuilder::new(2).unwrap();
//! for p in [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [-1.0, 0.0], [-1.0, -1.0]] { b.push_vertex(&p).unwrap(); }
//! b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
//! b.push_cell(CellKind::Simplex(2), &[0, 3, 4]).unwrap();
//! let k = b.build(&BuildOptions::default()).unwrap().0;
//! let t = StellarTree::build(&k, &StellarOptions::default()).unwrap();
//! let r = t.validate();
//! assert_eq!(r.n_connected_components, 1);
//! assert_eq!(r.non_manifold_vertices, vec![VertexId(0)]);
//! assert_eq!(r.boundary_faces.len(), 6);
//! assert!(r.pure);
//! assert!(!r.pseudo_manifold); // not connected through edges
//! assert_eq!(r.orientable, Some(true));
//! ```
use super::relations::unpack;
use super::{LeafView, StellarTree};
use crate::algo::manifold::{local_singularities_global, Singularities};
use crate::algo::orientation::PairParts;
use crate::algo::unionfind::UnionFind;
use crate::algo::validate::{finish_report, finish_report_tops, Faces, ValidationReport};
use crate::cell::{simplex_facet_sign, CellKind};
use crate::ids::{CellId, LeafId, TreeVertexId, VertexId};
use rayon::prelude::*;

/// Pairs of top cells sharing a facet, with the product of the orientations they induce on it.
type FacetPairs = Vec<(u32, u32, i8)>;

/// Cells per part of the orientation's parallel union-find ([`StellarTree::pair_parts`]).
const PART_CELLS: u32 = 1 << 16;

struct LeafOut {
    boundary: Faces,
    over2: Faces,
    pairs: Vec<(u32, u32, i8)>,
    sing: Singularities<TreeVertexId>,
    /// Pairs of cells to join for the vertex components: at every vertex whose star is not
    /// one cluster through facets, its first cell with each other (passes for one cell kind).
    joins: Vec<(u32, u32)>,
    /// Vertices in no cell (tree ids; passes for one cell kind).
    isolated: Vec<u32>,
}

impl StellarTree {
    /// Validates the complex (see the [module docs](self)).
    ///
    /// ```
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// # use starplex::stellar::{StellarTree, StellarOptions};
    /// use starplex::ids::VertexId;
    /// // a bow tie: two triangles sharing vertex 0
    /// # let mut b = ComplexBuilder::new(2).unwrap();
    /// # for p in [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [-1.0, 0.0], [-1.0, -1.0]] { b.push_vertex(&p).unwrap(); }
    /// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
    /// # b.push_cell(CellKind::Simplex(2), &[0, 3, 4]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// let r = StellarTree::build(&k, &StellarOptions::default()).unwrap().validate();
    /// assert!(r.pure);
    /// assert_eq!(r.non_manifold_vertices, vec![VertexId(0)]);
    /// assert!(!r.is_valid_manifold());
    /// ```
    pub fn validate(&self) -> ValidationReport {
        let d = self.dim();
        let dim = d.map_or(-1, |d| d as i64);
        let mut r = ValidationReport {
            dim,
            ..Default::default()
        };
        // triangles and tetrahedra: the leaf pass finds the vertices whose star is not one
        // cluster, and the vertex components follow from the facet components; otherwise the
        // components (a sequential union-find) run beside the parallel leaf pass: with two
        // threads one of them takes the union-find while the other works through the leaves
        let one_kind = matches!(
            self.cells.uniform,
            Some(CellKind::Simplex(2) | CellKind::Simplex(3))
        ) && d.is_some_and(|d| d >= 2);
        let (components, (outs, joined)) = if one_kind {
            (
                None,
                d.map_or_else(|| (Vec::new(), false), |d| self.leaf_outputs(d)),
            )
        } else {
            let (c, o) = rayon::join(
                || self.vertex_components(),
                || d.map_or_else(|| (Vec::new(), false), |d| self.leaf_outputs(d)),
            );
            (Some(c), o)
        };
        // a damaged tree file sends tetrahedra to the general pass, without the joins
        let components = match components {
            None if !joined => Some(self.vertex_components()),
            c => c,
        };
        let from_cells = components.is_none();
        if let Some((n_components, isolated)) = components {
            r.n_connected_components = n_components;
            r.isolated_vertices = isolated;
        }
        let Some(d) = d else {
            if self.n_vertices() > 0 {
                r.dim = 0;
            }
            r.pure = r.isolated_vertices.is_empty();
            return r;
        };
        r.lower_dimensional_cells = (0..self.cells.n)
            .filter(|&c| self.cells.get(c).0.dim() < d)
            .map(|c| CellId(self.c_orig[c as usize]))
            .collect();
        r.lower_dimensional_cells.sort_unstable();
        let (pairs, joins) = self.merge_leaf_outputs(&mut r, outs, from_cells);
        r.pure = r.lower_dimensional_cells.is_empty() && r.isolated_vertices.is_empty();
        // the walk in tree ids, where the neighbours of a cell are near it; answers in input ids
        let is_top = |c: u32| self.cells.get(c).0.dim() == d;
        let (nc, parts) = (self.n_top_cells(), self.pair_parts(&pairs));
        let n_joined = if self.cells.uniform.is_some_and(|k| k.dim() == d) {
            // one kind of cell, all tops: no mask to make or read
            finish_report_tops(&mut r, nc, |_| true, &parts, Some(&self.c_orig), &joins)
        } else {
            finish_report(&mut r, nc, is_top, &parts, Some(&self.c_orig), &joins)
        };
        if from_cells {
            // every cell is a top: the vertices' components are the cells' joined ones, and
            // each vertex in no cell is one more
            r.n_connected_components = n_joined + r.isolated_vertices.len() as u64;
        }
        r
    }

    /// Connected components of the vertices through the cells (union-find on tree vertices),
    /// and the isolated vertices (in no cell), input ids, sorted.
    fn vertex_components(&self) -> (u64, Vec<VertexId>) {
        let nv = self.n_vertices();
        let mut uf = UnionFind::new(nv);
        let mut used = vec![false; nv];
        for c in 0..self.cells.n {
            let vs = self.cells.verts(c);
            let Some((&a, rest)) = vs.split_first() else {
                continue;
            };
            used[a as usize] = true;
            for &v in rest {
                used[v as usize] = true;
                uf.union(a, v);
            }
        }
        let n = uf.n_sets() as u64;
        drop(uf);
        let mut isolated: Vec<VertexId> = (0..nv)
            .filter(|&v| !used[v])
            .map(|v| VertexId(self.v_orig[v]))
            .collect();
        isolated.sort_unstable();
        (n, isolated)
    }

    /// Facets, pairs, vertex and edge tests: one parallel pass over the leaves; true when
    /// the outputs hold the joins and the isolated vertices (the passes for triangles and
    /// tetrahedra).
    fn leaf_outputs(&self, d: usize) -> (Vec<LeafOut>, bool) {
        if d == 0 {
            return (Vec::new(), false);
        }
        if self.cells.uniform == Some(CellKind::Simplex(2)) {
            return (self.leaf_outputs_tris(), true);
        }
        if self.cells.uniform == Some(CellKind::Simplex(3))
            && let Some(outs) = self.leaf_outputs_tets()
        {
            return (outs, true);
        }
        let facet_part = self.par_facet_groups(|_, keys| {
            let mut o = (Faces::default(), Faces::default(), Vec::new());
            keys.for_each_group(|key, pays| {
                if key[0] as usize != d {
                    return;
                }
                match pays.len() {
                    1 => o.0.push(&key[1..]),
                    2 => {}
                    _ => o.1.push(&key[1..]),
                }
                for i in 0..pays.len() {
                    for j in i + 1..pays.len() {
                        let (a, sa) = unpack(pays[i]);
                        let (b, sb) = unpack(pays[j]);
                        o.2.push((a, b, sa * sb));
                    }
                }
            });
            o
        });
        let vertex_part = self.par_map_leaves(|view| self.leaf_manifold(view, d, true));
        let outs = facet_part
            .into_iter()
            .zip(vertex_part)
            .map(|((boundary, over2, pairs), sing)| LeafOut {
                boundary,
                over2,
                pairs,
                sing,
                joins: Vec::new(),
                isolated: Vec::new(),
            })
            .collect();
        (outs, false)
    }

    /// [`leaf_outputs`](Self::leaf_outputs) for a complex of triangles, in one pass over the
    /// leaves instead of two (facet groups, then star tests): for each vertex `v` the edges
    /// through `v` of its star's triangles, as 8-byte records (other vertex `w`, star index,
    /// slot, sign), are sorted (a dozen) and grouped by `w`. Every group is a link vertex of
    /// `v` (the test of `algo::manifold::tris`: `v` is manifold iff no group holds more than
    /// two triangles and the groups join the triangles into one cluster); the groups with
    /// `w > v` are the edges `v` owns: boundary (one triangle), in more than two, their
    /// non-manifold flag, and the pairs with the product of their induced orientations. The
    /// same findings in the same order as the general pass (a test compares the reports).
    fn leaf_outputs_tris(&self) -> Vec<LeafOut> {
        use crate::algo::manifold::{triangle_link_test, Manifoldness};
        let verts = &self.cells.verts;
        (0..self.n_leaves() as u32)
            .into_par_iter()
            .map_init(
                || {
                    (
                        super::ExpandedLeaf::default(),
                        Vec::<u64>::new(),
                        Vec::<u32>::new(),
                    )
                },
                |(e, recs, parent), l| {
                    self.expand_leaf_into(LeafId(l), e);
                    let mut o = LeafOut {
                        boundary: Faces::default(),
                        over2: Faces::default(),
                        pairs: Vec::new(),
                        sing: Singularities::default(),
                        joins: Vec::new(),
                        isolated: Vec::new(),
                    };
                    for (iv, v) in (e.v_start..e.v_end).enumerate() {
                        let star = &e.vt[e.vt_off[iv] as usize..e.vt_off[iv + 1] as usize];
                        if star.is_empty() {
                            // as the star tests say of a vertex of no cell in a 2-complex
                            o.sing.non_manifold_vertices.push(TreeVertexId(v));
                            o.isolated.push(v);
                            continue;
                        }
                        // record: w << 32 | star index << 3 | slot << 1 | negative (the edge
                        // omits the triangle's vertex `slot`; its induced orientation)
                        recs.clear();
                        for (i, &c) in star.iter().enumerate() {
                            let vs = &verts[c as usize * 3..c as usize * 3 + 3];
                            let pv = vs.iter().position(|&w| w == v).expect("v in its star");
                            for j in 0..3 {
                                if j == pv {
                                    continue;
                                }
                                let w = vs[3 - pv - j];
                                let neg = simplex_facet_sign(vs, j) < 0;
                                recs.push(
                                    ((w as u64) << 32)
                                        | ((i as u64) << 3)
                                        | ((j as u64) << 1)
                                        | neg as u64,
                                );
                            }
                        }
                        crate::topo::sortnet::sort_short(recs, u64::MAX);
                        let cell = |r: u64| star[(r as u32 >> 3) as usize];
                        let sign = |r: u64| if r & 1 == 1 { -1i8 } else { 1 };
                        let m = triangle_link_test(star.len(), recs, parent, |w, g| {
                            if w <= v {
                                return;
                            }
                            if g.len() > 2 {
                                o.sing
                                    .non_manifold_edges
                                    .push([TreeVertexId(v), TreeVertexId(w)]);
                            }
                            match g.len() {
                                1 => o.boundary.push(&[v, w]),
                                2 => {}
                                _ => o.over2.push(&[v, w]),
                            }
                            for (x, &rx) in g.iter().enumerate() {
                                for &ry in &g[x + 1..] {
                                    o.pairs.push((cell(rx), cell(ry), sign(rx) * sign(ry)));
                                }
                            }
                        });
                        if m == Manifoldness::NonManifold {
                            o.sing.non_manifold_vertices.push(TreeVertexId(v));
                            // its star may span several facet components
                            o.joins.extend(star[1..].iter().map(|&c| (star[0], c)));
                        }
                    }
                    o
                },
            )
            .collect()
    }

    /// [`leaf_outputs`](Self::leaf_outputs) for a complex of tetrahedra, in one pass over
    /// the leaves instead of two: the star test of each vertex (`algo::manifold`'s
    /// tetrahedral one, on the vertex's link) already groups the triangles through the
    /// vertex with their tetrahedra, and those the vertex owns (its other two vertices
    /// larger) are the facets the general pass would group in this leaf: boundary (one
    /// tetrahedron), in more than two, and the pairs with the product of their induced
    /// orientations (in another order: the report sorts the faces, and the orientation's
    /// answer does not depend on the order of the pairs). `None` when a cell has a repeated
    /// vertex (a damaged tree file): the general pass then runs.
    fn leaf_outputs_tets(&self) -> Option<Vec<LeafOut>> {
        use crate::algo::manifold::{tet_star_tests_and_triangles, Manifoldness, TetScratch};
        use crate::topo::{LocalStar, PartStar};
        let verts = &self.cells.verts;
        let sign =
            |c: u32, j: usize| simplex_facet_sign(&verts[c as usize * 4..c as usize * 4 + 4], j);
        let outs: Vec<Option<LeafOut>> = (0..self.n_leaves() as u32)
            .into_par_iter()
            .map_init(
                || {
                    (
                        super::ExpandedLeaf::default(),
                        TetScratch::default(),
                        Vec::<u32>::new(),
                        Vec::<(u32, Manifoldness)>::new(),
                    )
                },
                |(e, ts, buf, edges), l| {
                    self.expand_leaf_into(LeafId(l), e);
                    let view = LeafView { tree: self, e };
                    let mut o = LeafOut {
                        boundary: Faces::default(),
                        over2: Faces::default(),
                        pairs: Vec::new(),
                        sing: Singularities::default(),
                        joins: Vec::new(),
                        isolated: Vec::new(),
                    };
                    for v in view.tree_vertices() {
                        let star = view.local_star(TreeVertexId(v));
                        if star.is_empty() {
                            // as the star tests say of a vertex of no cell in a 3-complex
                            o.sing.non_manifold_vertices.push(TreeVertexId(v));
                            o.isolated.push(v);
                            continue;
                        }
                        let ps = PartStar { part: &view, star };
                        edges.clear();
                        // each triangle `v a b` that `v` owns, with its tetrahedra, as met
                        let m = tet_star_tests_and_triangles(
                            v,
                            &ps,
                            ts,
                            buf,
                            edges,
                            |[a, b], group| {
                                match group.len() {
                                    1 => o.boundary.push(&[v, a, b]),
                                    2 => {}
                                    _ => o.over2.push(&[v, a, b]),
                                }
                                let omit = |c: u32| {
                                    let vs = &verts[c as usize * 4..c as usize * 4 + 4];
                                    vs.iter()
                                        .position(|&u| u != v && u != a && u != b)
                                        .expect("a tetrahedron has a fourth vertex")
                                };
                                for x in 0..group.len() {
                                    for y in x + 1..group.len() {
                                        let (p, q) =
                                            (star[group[x] as usize].0, star[group[y] as usize].0);
                                        o.pairs.push((p, q, sign(p, omit(p)) * sign(q, omit(q))));
                                    }
                                }
                            },
                        )?;
                        o.sing.record(TreeVertexId(v), m, edges);
                        if m != Manifoldness::Manifold {
                            // its star may span several facet components
                            o.joins.extend(star[1..].iter().map(|x| (star[0].0, x.0)));
                        }
                    }
                    Some(o)
                },
            )
            .collect();
        outs.into_iter().collect()
    }

    /// Moves the leaves' findings into the report (input ids, sorted) and returns the facet
    /// pairs in tree cell ids.
    fn merge_leaf_outputs(
        &self,
        r: &mut ValidationReport,
        outs: Vec<LeafOut>,
        isolated: bool,
    ) -> (Vec<FacetPairs>, Vec<(u32, u32)>) {
        let to_in = |v: u32| VertexId(self.v_orig[v as usize]);
        let tv_in = |v: &TreeVertexId| to_in(v.0);
        let edge_in = |e: &[TreeVertexId; 2]| {
            let (a, b) = (to_in(e[0].0), to_in(e[1].0));
            if a < b {
                [a, b]
            } else {
                [b, a]
            }
        };
        // (d-1)-connectedness and orientation: the shared walk, on tree cell ids, over each
        // leaf's pairs where they are (not copied into one array: a serial copy and twice
        // the memory)
        let mut pairs = Vec::with_capacity(outs.len());
        let mut joins = Vec::new();
        let (mut boundary, mut over2) = (Faces::default(), Faces::default());
        for o in outs {
            boundary.append(&o.boundary);
            over2.append(&o.over2);
            r.non_manifold_vertices
                .extend(o.sing.non_manifold_vertices.iter().map(tv_in));
            r.unknown_vertices
                .extend(o.sing.unknown_vertices.iter().map(tv_in));
            r.non_manifold_edges
                .extend(o.sing.non_manifold_edges.iter().map(edge_in));
            r.unknown_edges
                .extend(o.sing.unknown_edges.iter().map(edge_in));
            pairs.push(o.pairs);
            joins.extend_from_slice(&o.joins);
            if isolated {
                r.isolated_vertices
                    .extend(o.isolated.iter().map(|&v| to_in(v)));
            }
        }
        let face_in = |v: u32| self.v_orig[v as usize];
        r.boundary_faces = boundary.into_sorted(face_in);
        r.faces_in_more_than_two_cells = over2.into_sorted(face_in);
        r.non_manifold_vertices.sort_unstable();
        r.unknown_vertices.sort_unstable();
        r.non_manifold_edges.sort_unstable();
        r.unknown_edges.sort_unstable();
        r.isolated_vertices.sort_unstable();
        (pairs, joins)
    }

    /// The leaves' facet pairs (`pairs[l]`: leaf `l`'s) grouped into parts of consecutive
    /// leaves of about [`PART_CELLS`] cells, each with the cells whose home leaf (the leaf of
    /// their smallest vertex, by which the build numbers them) is in it: a facet's two cells
    /// mostly are, so most pairs are united part by part, in parallel.
    fn pair_parts<'a>(&self, pairs: &'a [FacetPairs]) -> PairParts<'a> {
        let nc = self.cells.n;
        let leaf_of = |v: u32| self.leaf_vstart.partition_point(|&s| s <= v) as u32 - 1;
        let home = |c: u32| {
            let vs = self.cells.verts(c);
            vs.iter().min().map_or(u32::MAX, |&v| leaf_of(v))
        };
        // the first cell whose home leaf is at least `l` (cells in home-leaf order; were they
        // not, the parts would only be slower)
        let first_cell = |l: u32| {
            let (mut lo, mut hi) = (0u32, nc);
            while lo < hi {
                let m = lo + (hi - lo) / 2;
                if home(m) < l {
                    lo = m + 1;
                } else {
                    hi = m;
                }
            }
            lo
        };
        // a part ends with the home leaf of its PART_CELLS-th cell: a few binary searches
        let mut parts = vec![(0usize, 0u32)];
        while let Some(&(l0, c0)) = parts.last() {
            let Some(t) = c0.checked_add(PART_CELLS).filter(|&t| t < nc) else {
                break;
            };
            let l = home(t).saturating_add(1);
            let c = first_cell(l);
            if l as usize >= pairs.len() || l as usize <= l0 || c <= c0 {
                break;
            }
            parts.push((l as usize, c));
        }
        PairParts {
            pieces: pairs.iter().map(|p| &p[..]).collect(),
            parts,
        }
    }

    /// Manifold tests for the vertices of a leaf and the edges they own (the edge's smaller
    /// tree endpoint), tree ids: the shared [`local_singularities`](crate::algo::manifold::local_singularities)
    /// on the leaf.
    fn leaf_manifold(
        &self,
        view: &LeafView<'_>,
        d: usize,
        fast: bool,
    ) -> Singularities<TreeVertexId> {
        local_singularities_global(view, d, fast)
    }
}

#[cfg(test)]
mod tests {
    use crate::cell::CellKind;
    use crate::complex::{BuildOptions, ComplexBuilder};
    use crate::stellar::{StellarOptions, StellarTree};

    /// The tetrahedral short cut answers like the generic test, on random (mostly
    /// non-manifold) sets of tetrahedra, grids with holes, and stars mixing tetrahedra and
    /// triangles.
    #[test]
    fn tet_short_cut_equals_generic() {
        let mut rng = crate::testkit::XorShift::new(0x2545_F491_4F6C_DD1D);
        let mut next = |m: u64| rng.below(m);
        // non-manifold vertices, manifold vertices, non-manifold edges met
        let mut seen_kinds = [0usize; 3];
        for case in 0..300 {
            let nv = 5 + next(10) as usize;
            let mut b = ComplexBuilder::new(3).unwrap();
            for i in 0..nv {
                let f = i as f64;
                b.push_vertex(&[f.sin(), (1.7 * f).cos(), (0.3 * f).sin()])
                    .unwrap();
            }
            let mut seen = std::collections::HashSet::new();
            let grid = case % 4 == 3;
            if grid {
                // a 3x3x3 block of cubes, six tetrahedra each (Kuhn), some removed
                b = ComplexBuilder::new(3).unwrap();
                let id = |i: usize, j: usize, k: usize| (i * 16 + j * 4 + k) as u32;
                for i in 0..4 {
                    for j in 0..4 {
                        for k in 0..4 {
                            b.push_vertex(&[i as f64, j as f64, k as f64]).unwrap();
                        }
                    }
                }
                let drop = 1 + next(8);
                for i in 0..3 {
                    for j in 0..3 {
                        for k in 0..3 {
                            for p in [
                                [0, 1, 2],
                                [0, 2, 1],
                                [1, 0, 2],
                                [1, 2, 0],
                                [2, 0, 1],
                                [2, 1, 0],
                            ] {
                                if next(drop + 1) == 0 {
                                    continue;
                                }
                                let mut c = [i, j, k];
                                let mut vs = vec![id(c[0], c[1], c[2])];
                                for &a in &p {
                                    c[a] += 1;
                                    vs.push(id(c[0], c[1], c[2]));
                                }
                                b.push_cell(CellKind::Simplex(3), &vs).unwrap();
                            }
                        }
                    }
                }
            }
            let n_cells = if grid {
                0
            } else {
                1 + next(3 * nv as u64) as usize
            };
            for _ in 0..n_cells {
                let tri = case % 3 == 2 && next(4) == 0;
                let k = if tri { 3 } else { 4 };
                let mut c: Vec<u32> = Vec::new();
                while c.len() < k {
                    let v = next(nv as u64) as u32;
                    if !c.contains(&v) {
                        c.push(v);
                    }
                }
                let mut key = c.clone();
                key.sort_unstable();
                // no duplicates, no triangle inside a tetrahedron
                if !seen.insert(key) {
                    continue;
                }
                let kind = if tri {
                    CellKind::Simplex(2)
                } else {
                    CellKind::Simplex(3)
                };
                b.push_cell(kind, &c).unwrap();
            }
            check_short_cut(b, case, &mut seen_kinds);
        }
        assert!(seen_kinds.iter().all(|&n| n > 100), "{seen_kinds:?}");
    }

    /// Links of up to ~200 vertices (the tetrahedral test indexes the link edges directly up
    /// to 64 link vertices and hashes them beyond): cones from vertex 0 over bipyramids on
    /// rings of 20 to 100 vertices, some tetrahedra removed, sometimes a second cone on the
    /// same apex or on a shared ring edge.
    #[test]
    fn tet_short_cut_equals_generic_on_wide_links() {
        let mut rng = crate::testkit::XorShift::new(0x0005_EED0_FB16_11C5);
        let mut seen_kinds = [0usize; 3];
        for case in 0..60 {
            let mut b = ComplexBuilder::new(3).unwrap();
            let n = 20 + rng.below(81) as u32;
            let second = rng.below(3);
            // apex 0, poles 1 and 2, ring 3..3+n; a second ring (and poles) after it
            let nv = 3 + 2 * n + 2;
            for i in 0..nv {
                let f = i as f64;
                b.push_vertex(&[f.sin(), (1.3 * f).cos(), (0.7 * f).sin()])
                    .unwrap();
            }
            let drop = rng.below(4);
            let mut cone = |b: &mut ComplexBuilder, apex: u32, poles: [u32; 2], ring: &[u32]| {
                for i in 0..ring.len() {
                    let (r0, r1) = (ring[i], ring[(i + 1) % ring.len()]);
                    for p in poles {
                        if drop > 0 && rng.below(40) < drop {
                            continue;
                        }
                        b.push_cell(CellKind::Simplex(3), &[apex, p, r0, r1])
                            .unwrap();
                    }
                }
            };
            let ring: Vec<u32> = (3..3 + n).collect();
            cone(&mut b, 0, [1, 2], &ring);
            if second > 0 {
                let base = 3 + n;
                let mut ring2: Vec<u32> = (base..base + n).collect();
                if second == 2 {
                    // shares the ring edge (3, 4) with the first cone
                    ring2[0] = 3;
                    ring2[1] = 4;
                }
                cone(&mut b, 0, [nv - 2, nv - 1], &ring2);
            }
            check_short_cut(b, case, &mut seen_kinds);
        }
        assert!(seen_kinds.iter().all(|&n| n > 20), "{seen_kinds:?}");
    }

    /// On every leaf of trees with k_V 0, 2 and 5 over `k`, the short cuts answer like the
    /// generic test; counts non-manifold vertices, manifold vertices and non-manifold edges.
    /// The complex is `b` without duplicate cells and cells that are faces of others.
    fn check_short_cut(b: ComplexBuilder, case: usize, seen: &mut [usize; 3]) {
        let opts = BuildOptions {
            drop_duplicates: true,
            drop_face_cells: true,
            ..Default::default()
        };
        let Ok((k, _)) = b.build(&opts) else {
            return;
        };
        for kv in [0, 2, 5] {
            let t = StellarTree::build(
                &k,
                &StellarOptions {
                    kv: Some(kv),
                    ..Default::default()
                },
            )
            .unwrap();
            let Some(d) = t.dim() else { continue };
            let norm = |mut r: Vec<LeafManifold>| {
                for x in &mut r {
                    x.non_manifold_edges.sort_unstable();
                    x.unknown_edges.sort_unstable();
                }
                r
            };
            let fast = norm(t.par_map_leaves(|view| t.leaf_manifold(view, d, true)));
            let slow = norm(t.par_map_leaves(|view| t.leaf_manifold(view, d, false)));
            let nm: usize = slow.iter().map(|x| x.non_manifold_vertices.len()).sum();
            seen[0] += nm;
            seen[1] += t.n_vertices() - nm;
            seen[2] += slow
                .iter()
                .map(|x| x.non_manifold_edges.len())
                .sum::<usize>();
            assert_eq!(fast, slow, "case {case} kv {kv}");
        }
    }

    /// What [`StellarTree::leaf_manifold`] returns for one leaf.
    type LeafManifold = crate::algo::manifold::Singularities<crate::ids::TreeVertexId>;

    /// The triangle short cut answers like the generic test, on random (mostly non-manifold)
    /// sets of triangles, triangulated grids with holes, and stars mixing triangles and edges.
    /// A tree of more tetrahedra than one part of the orientation's union-find holds, some
    /// turned over (cells to flip) and some removed: on two threads, the report equals the
    /// generic validation's.
    #[test]
    fn several_parts_orient_like_the_generic_validation() {
        let g = crate::generate::kuhn_grid(&[30, 30, 30]).unwrap();
        let mut b = ComplexBuilder::new(3).unwrap();
        for p in g.coords().chunks_exact(3) {
            b.push_vertex(p).unwrap();
        }
        let mut rng = crate::testkit::XorShift::new(0x0B5E_55ED);
        for c in g.cells() {
            let mut vs = c.vertices.to_vec();
            match rng.below(40) {
                0 => continue,
                1..=4 => vs.swap(0, 1),
                _ => {}
            }
            b.push_cell(c.kind, &vs).unwrap();
        }
        let k = b.build(&BuildOptions::default()).unwrap().0;
        assert!(k.n_cells() > 2 * super::PART_CELLS as usize);
        let want = crate::algo::validate::validate(&crate::topo::naive::VtIndex::new(&k));
        assert!(want.cells_to_flip.as_ref().is_some_and(|f| f.len() > 1000));
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(2)
            .build()
            .unwrap();
        let t = StellarTree::build(&k, &StellarOptions::default()).unwrap();
        assert_eq!(pool.install(|| t.validate()), want);
    }

    #[test]
    fn tri_short_cut_equals_generic() {
        let mut rng = crate::testkit::XorShift::new(0x9E37_79B9_7F4A_7C15);
        let mut next = |m: u64| rng.below(m);
        let mut seen_kinds = [0usize; 3];
        for case in 0..300 {
            let mut b = ComplexBuilder::new(2).unwrap();
            let mut seen = std::collections::HashSet::new();
            if case % 3 == 2 {
                // a 5x5 grid of squares, two triangles each, some removed
                for i in 0..6 {
                    for j in 0..6 {
                        b.push_vertex(&[i as f64, j as f64]).unwrap();
                    }
                }
                let id = |i: u32, j: u32| i * 6 + j;
                let drop = 1 + next(6);
                for i in 0..5 {
                    for j in 0..5 {
                        for t in [
                            [id(i, j), id(i + 1, j), id(i + 1, j + 1)],
                            [id(i, j), id(i + 1, j + 1), id(i, j + 1)],
                        ] {
                            if next(drop + 1) != 0 {
                                b.push_cell(CellKind::Simplex(2), &t).unwrap();
                            }
                        }
                    }
                }
            } else {
                let nv = 4 + next(10) as usize;
                for i in 0..nv {
                    let f = i as f64;
                    b.push_vertex(&[f.sin(), (1.7 * f).cos()]).unwrap();
                }
                for _ in 0..1 + next(3 * nv as u64) {
                    let edge = case % 3 == 1 && next(4) == 0;
                    let k: u8 = if edge { 2 } else { 3 };
                    let mut c: Vec<u32> = Vec::new();
                    while c.len() < k as usize {
                        let v = next(nv as u64) as u32;
                        if !c.contains(&v) {
                            c.push(v);
                        }
                    }
                    let mut key = c.clone();
                    key.sort_unstable();
                    if seen.insert(key) {
                        b.push_cell(CellKind::Simplex(k - 1), &c).unwrap();
                    }
                }
            }
            check_short_cut(b, case, &mut seen_kinds);
        }
        assert!(seen_kinds.iter().all(|&n| n > 100), "{seen_kinds:?}");
    }
}
