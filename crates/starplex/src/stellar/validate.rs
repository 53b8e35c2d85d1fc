//! Topological validation on a Stellar tree, leaf by leaf: connected components, (d-1)-
//! connectedness, purity, pseudo-manifoldness, boundary (d-1)-faces, non-manifold vertices and
//! edges, orientability with a consistent orientation. Every problem comes with its ids (input
//! numbering).
//!
//! Manifoldness uses the global convention (d = dimension of the complex): a vertex is manifold
//! iff its link is a (d-1)-sphere or ball. For d <= 3 the answer is exact (link tests: a path or
//! cycle for d = 2, a connected surface with the Euler characteristic of a sphere or a disk for
//! d = 3). For d >= 4 sphere recognition is impractical or undecidable: the combinatorial tests
//! (mixed dimensions in the star, a facet in three or more d-cells, two or more clusters of
//! d-cells around the simplex, a non-manifold incident edge) prove non-manifoldness, otherwise
//! the answer is [`Manifoldness::Unknown`].
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
use super::tetlink::TetScratch;
use super::{LeafView, StellarTree};
use crate::algo::unionfind::UnionFind;
use crate::ids::{CellId, VertexId};
use crate::topo::naive::edge_neighbours;

/// Tri-state answer of a manifold test.
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
/// use starplex::stellar::Manifoldness;
/// // the report lists the vertices of every class but `Manifold`
/// let class = |v| {
///     if r.non_manifold_vertices.contains(&v) { Manifoldness::NonManifold }
///     else if r.unknown_vertices.contains(&v) { Manifoldness::Unknown }
///     else { Manifoldness::Manifold }
/// };
/// assert_eq!(class(VertexId(0)), Manifoldness::NonManifold);
/// assert_eq!(class(VertexId(1)), Manifoldness::Manifold);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Manifoldness {
    /// The link is a sphere or a ball of the right dimension.
    Manifold,
    /// Proven non-manifold.
    NonManifold,
    /// Not decided (dimension >= 4 and no combinatorial obstruction found).
    Unknown,
}

/// The result of [`StellarTree::validate`].
///
/// ```
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// # use starplex::stellar::{StellarTree, StellarOptions};
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// # let t = StellarTree::build(&k, &StellarOptions { kv: Some(1), ..Default::default() }).unwrap();
/// // two triangles forming a square: a disk
/// let r = t.validate();
/// assert_eq!((r.dim, r.n_connected_components, r.n_facet_components), (2, 1, 1));
/// assert!(r.pure && r.facet_connected && r.pseudo_manifold);
/// assert!(r.faces_in_more_than_two_cells.is_empty() && r.non_manifold_edges.is_empty());
/// assert_eq!(r.orientable, Some(true));
/// assert_eq!(r.cells_to_flip, Some(vec![])); // already consistently oriented
/// ```
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ValidationReport {
    /// Dimension of the complex (-1 when empty).
    pub dim: i64,
    /// Connected components of the 1-skeleton, isolated vertices included.
    pub n_connected_components: u64,
    /// Vertices in no top cell.
    pub isolated_vertices: Vec<VertexId>,
    /// Top cells of dimension below `dim`.
    pub lower_dimensional_cells: Vec<CellId>,
    /// All top cells of dimension `dim` and no isolated vertex.
    pub pure: bool,
    /// Classes of top `dim`-cells connected through shared (d-1)-faces.
    pub n_facet_components: u64,
    /// Exactly one such class (and at least one top cell).
    pub facet_connected: bool,
    /// Pure, every (d-1)-face in at most two d-cells, and (d-1)-connected.
    pub pseudo_manifold: bool,
    /// (d-1)-faces in exactly one top d-cell (sorted input vertex ids).
    pub boundary_faces: Vec<Vec<VertexId>>,
    /// (d-1)-faces in three or more top d-cells.
    pub faces_in_more_than_two_cells: Vec<Vec<VertexId>>,
    /// Non-manifold vertices, sorted.
    pub non_manifold_vertices: Vec<VertexId>,
    /// Vertices whose manifoldness is unknown (d >= 4), sorted.
    pub unknown_vertices: Vec<VertexId>,
    /// Non-manifold edges (endpoints sorted), sorted.
    pub non_manifold_edges: Vec<[VertexId; 2]>,
    /// Edges whose manifoldness is unknown (d >= 4).
    pub unknown_edges: Vec<[VertexId; 2]>,
    /// `Some(orientable)` when every (d-1)-face is in at most two d-cells, else `None`.
    pub orientable: Option<bool>,
    /// When orientable: the top cells to reverse for a consistent orientation (sorted).
    pub cells_to_flip: Option<Vec<CellId>>,
    /// When not orientable: two adjacent cells whose orientations cannot agree.
    pub orientation_conflict: Option<(CellId, CellId)>,
}

impl ValidationReport {
    /// Number of boundary (d-1)-faces.
    ///
    /// ```
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// # use starplex::stellar::{StellarTree, StellarOptions};
    /// # let mut b = ComplexBuilder::new(2).unwrap();
    /// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
    /// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
    /// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// # let t = StellarTree::build(&k, &StellarOptions { kv: Some(1), ..Default::default() }).unwrap();
    /// let r = t.validate();
    /// assert_eq!(r.n_boundary_faces(), 4); // the sides of the square
    /// ```
    pub fn n_boundary_faces(&self) -> usize {
        self.boundary_faces.len()
    }
    /// True when no problem was found.
    ///
    /// ```
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// # use starplex::stellar::{StellarTree, StellarOptions};
    /// # let mut b = ComplexBuilder::new(2).unwrap();
    /// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
    /// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
    /// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// # let t = StellarTree::build(&k, &StellarOptions { kv: Some(1), ..Default::default() }).unwrap();
    /// assert!(t.validate().is_valid_manifold()); // a disk
    /// ```
    pub fn is_valid_manifold(&self) -> bool {
        self.pseudo_manifold
            && self.non_manifold_vertices.is_empty()
            && self.non_manifold_edges.is_empty()
            && self.unknown_vertices.is_empty()
            && self.orientable == Some(true)
    }
}

struct LeafOut {
    boundary: Vec<Vec<u32>>,
    over2: Vec<Vec<u32>>,
    pairs: Vec<(u32, u32, i8)>,
    nm_v: Vec<u32>,
    unk_v: Vec<u32>,
    nm_e: Vec<[u32; 2]>,
    unk_e: Vec<[u32; 2]>,
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
        // components (sequential union-find on tree vertices)
        let nv = self.n_vertices();
        let mut uf = UnionFind::new(nv);
        let mut used = vec![false; nv];
        for c in 0..self.cells.n {
            let vs = self.cells.verts(c);
            for &v in vs {
                used[v as usize] = true;
                uf.union(vs[0], v);
            }
        }
        r.n_connected_components = uf.n_sets() as u64;
        drop(uf);
        r.isolated_vertices = (0..nv)
            .filter(|&v| !used[v])
            .map(|v| VertexId(self.v_orig[v]))
            .collect();
        r.isolated_vertices.sort_unstable();
        drop(used);
        let Some(d) = d else {
            if nv > 0 {
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
        r.pure = r.lower_dimensional_cells.is_empty() && r.isolated_vertices.is_empty();

        // facets, pairs, vertex and edge tests: one parallel pass over the leaves
        let outs: Vec<LeafOut> = if d == 0 {
            Vec::new()
        } else {
            let facet_part = self.par_facet_groups(|_, keys| {
                let mut o = (Vec::new(), Vec::new(), Vec::new());
                keys.for_each_group(|key, pays| {
                    if key[0] as usize != d {
                        return;
                    }
                    match pays.len() {
                        1 => o.0.push(key[1..].to_vec()),
                        2 => {}
                        _ => o.1.push(key[1..].to_vec()),
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
            facet_part
                .into_iter()
                .zip(vertex_part)
                .map(
                    |((boundary, over2, pairs), (nm_v, unk_v, nm_e, unk_e))| LeafOut {
                        boundary,
                        over2,
                        pairs,
                        nm_v,
                        unk_v,
                        nm_e,
                        unk_e,
                    },
                )
                .collect()
        };
        let to_in = |v: u32| VertexId(self.v_orig[v as usize]);
        let face_in = |f: &Vec<u32>| {
            let mut x: Vec<VertexId> = f.iter().map(|&v| to_in(v)).collect();
            x.sort_unstable();
            x
        };
        let edge_in = |e: &[u32; 2]| {
            let (a, b) = (to_in(e[0]), to_in(e[1]));
            if a < b {
                [a, b]
            } else {
                [b, a]
            }
        };
        let mut pairs: Vec<(u32, u32, i8)> = Vec::new();
        for o in &outs {
            r.boundary_faces.extend(o.boundary.iter().map(face_in));
            r.faces_in_more_than_two_cells
                .extend(o.over2.iter().map(face_in));
            r.non_manifold_vertices
                .extend(o.nm_v.iter().map(|&v| to_in(v)));
            r.unknown_vertices.extend(o.unk_v.iter().map(|&v| to_in(v)));
            r.non_manifold_edges.extend(o.nm_e.iter().map(edge_in));
            r.unknown_edges.extend(o.unk_e.iter().map(edge_in));
            pairs.extend_from_slice(&o.pairs);
        }
        drop(outs);
        if d == 0 {
            // isolated points: every vertex is a 0-manifold (a top vertex cell)
        }
        r.boundary_faces.sort_unstable();
        r.faces_in_more_than_two_cells.sort_unstable();
        r.non_manifold_vertices.sort_unstable();
        r.unknown_vertices.sort_unstable();
        r.non_manifold_edges.sort_unstable();
        r.unknown_edges.sort_unstable();

        // (d-1)-connectedness of the top d-cells
        let nc = self.n_top_cells();
        let mut cuf = UnionFind::new(nc);
        for &(a, b, _) in &pairs {
            cuf.union(a, b);
        }
        let is_top = |c: u32| self.cells.get(c).0.dim() == d;
        let mut roots = 0u64;
        for c in 0..nc as u32 {
            if is_top(c) && cuf.find(c) == c {
                roots += 1;
            }
        }
        r.n_facet_components = roots;
        r.facet_connected = roots == 1;
        r.pseudo_manifold =
            r.pure && r.faces_in_more_than_two_cells.is_empty() && r.facet_connected;

        // orientation
        if r.faces_in_more_than_two_cells.is_empty() {
            let adj = crate::csr::Csr::from_fn(nc, |emit| {
                for (i, &(a, b, _)) in pairs.iter().enumerate() {
                    emit(a, i as u32);
                    emit(b, i as u32);
                }
            });
            let mut o = vec![0i8; nc];
            let mut conflict = None;
            let mut queue = Vec::new();
            'outer: for s in 0..nc as u32 {
                if o[s as usize] != 0 || !is_top(s) {
                    continue;
                }
                o[s as usize] = 1;
                queue.push(s);
                while let Some(a) = queue.pop() {
                    for &pi in adj.row(a as usize) {
                        let (x, y, rel) = pairs[pi as usize];
                        let b = if x == a { y } else { x };
                        let want = -o[a as usize] * rel;
                        if o[b as usize] == 0 {
                            o[b as usize] = want;
                            queue.push(b);
                        } else if o[b as usize] != want {
                            conflict = Some((
                                CellId(self.c_orig[a as usize]),
                                CellId(self.c_orig[b as usize]),
                            ));
                            break 'outer;
                        }
                    }
                }
            }
            match conflict {
                Some((a, b)) => {
                    r.orientable = Some(false);
                    let (a, b) = if a < b { (a, b) } else { (b, a) };
                    r.orientation_conflict = Some((a, b));
                }
                None => {
                    r.orientable = Some(true);
                    let mut flips: Vec<CellId> = (0..nc)
                        .filter(|&c| o[c] < 0)
                        .map(|c| CellId(self.c_orig[c]))
                        .collect();
                    flips.sort_unstable();
                    r.cells_to_flip = Some(flips);
                }
            }
        }
        r
    }

    /// Manifold tests for the vertices of a leaf and the edges they own (the edge's smaller
    /// tree endpoint). Returns (non-manifold vertices, unknown vertices, non-manifold edges,
    /// unknown edges), tree ids.
    #[allow(clippy::type_complexity)]
    fn leaf_manifold(
        &self,
        view: &LeafView<'_>,
        d: usize,
        fast: bool,
    ) -> (Vec<u32>, Vec<u32>, Vec<[u32; 2]>, Vec<[u32; 2]>) {
        let mut out = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
        let mut s = Scratch::default();
        let mut edges = Vec::new();
        let mut groups = Vec::new();
        for v in view.tree_vertices() {
            let star = view.vt_tree(v);
            edges.clear();
            let vs = self.star_tests(v, star, d, fast, &mut s, &mut groups, &mut edges);
            match vs {
                Manifoldness::Manifold => {}
                Manifoldness::NonManifold => out.0.push(v),
                Manifoldness::Unknown => out.1.push(v),
            }
            for &(w, st) in &edges {
                match st {
                    Manifoldness::Manifold => {}
                    Manifoldness::NonManifold => out.2.push([v, w]),
                    Manifoldness::Unknown => out.3.push([v, w]),
                }
            }
        }
        out
    }

    /// Tests vertex `v` with star `star` (tree cells) and every edge `vw` with `w > v`; `fast`
    /// allows the tetrahedral short cut.
    #[allow(clippy::too_many_arguments)]
    fn star_tests(
        &self,
        v: u32,
        star: &[u32],
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
        if fast && d == 3 && self.all_tets(star) {
            if let Some(r) = self.star_tests_tets(v, star, &mut s.tet, edges_out) {
                return r;
            }
        }
        // edges at v: (w, local cell index)
        s.ew.clear();
        for (i, &c) in star.iter().enumerate() {
            let (kind, vs) = self.cells.get(c);
            edge_neighbours(kind, vs, v, |w| s.ew.push((w, i as u32)));
        }
        s.ew.sort_unstable();
        s.ew.dedup();
        let v_mixed = star.iter().any(|&c| self.cells.get(c).0.dim() != d);
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
                .any(|&(_, ci)| self.cells.get(star[ci as usize]).0.dim() != d)
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
                        .filter(|&&(_, ci)| self.cells.get(star[ci as usize]).0.dim() == 2)
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
            3 => self.star_tests_3(v, star, edge_groups, v_mixed, s, edges_out),
            _ => self.star_tests_high(v, star, d, edge_groups, v_mixed, s, edges_out),
        }
    }

    #[allow(clippy::too_many_arguments)]
    fn star_tests_3(
        &self,
        v: u32,
        star: &[u32],
        edge_groups: &[(u32, usize, usize)],
        v_mixed: bool,
        s: &mut Scratch,
        edges_out: &mut Vec<(u32, Manifoldness)>,
    ) -> Manifoldness {
        use Manifoldness::*;
        // 2-faces containing v of the 3-cells: (sorted key, cell index, e1, e2)
        s.faces.clear();
        for (i, &c) in star.iter().enumerate() {
            let (kind, vs) = self.cells.get(c);
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
            super::relations::faces_of(kind, 2, |local| {
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
                let key =
                    ((other[0] as u128) << 64) | ((other[1] as u128) << 32) | other[2] as u128;
                s.faces.push((key, i as u32, e1, e2));
            });
        }
        s.faces.sort_unstable();
        // group faces
        let mut bad = v_mixed;
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
        s.wpairs.sort_unstable();
        s.face_bad_w.sort_unstable();
        // per edge vw: cells containing it form one cluster through faces containing vw
        s.local_uf.clear();
        s.local_uf.resize(star.len(), 0);
        let mut p = 0usize;
        let n_edges = edge_groups.len() as i64;
        for &(w, a, b) in edge_groups {
            let mut e_bad = s.ew[a..b]
                .iter()
                .any(|&(_, ci)| self.cells.get(star[ci as usize]).0.dim() != 3)
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
        if bad || sets != 1 {
            return NonManifold;
        }
        // Euler characteristic of the link: E - F + C
        let chi = n_edges - n_faces + star.len() as i64;
        let ok = if s.bedges.is_empty() {
            chi == 2
        } else {
            // boundary of the link is a single cycle
            let mut ws: Vec<u32> = s.bedges.iter().flat_map(|&(a, b)| [a, b]).collect();
            ws.sort_unstable();
            ws.dedup();
            let mut buf = UnionFind::new(ws.len());
            for &(a, b) in &s.bedges {
                let ia = ws.binary_search(&a).expect("present") as u32;
                let ib = ws.binary_search(&b).expect("present") as u32;
                buf.union(ia, ib);
            }
            chi == 1 && buf.n_sets() == 1
        };
        if ok {
            Manifold
        } else {
            NonManifold
        }
    }

    /// d >= 4 (the top d-cells are simplices): combinatorial obstructions or Unknown.
    #[allow(clippy::too_many_arguments)]
    fn star_tests_high(
        &self,
        v: u32,
        star: &[u32],
        d: usize,
        edge_groups: &[(u32, usize, usize)],
        v_mixed: bool,
        s: &mut Scratch,
        edges_out: &mut Vec<(u32, Manifoldness)>,
    ) -> Manifoldness {
        use Manifoldness::*;
        // facets containing v of the d-cells: (sorted facet, cell index)
        let mut facets: Vec<(Vec<u32>, u32)> = Vec::new();
        for (i, &c) in star.iter().enumerate() {
            let (kind, vs) = self.cells.get(c);
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
                .any(|&ci| self.cells.get(star[ci as usize]).0.dim() != d);
            let e_over = groups
                .iter()
                .any(|&(x, y)| y - x > 2 && facets[x].0.binary_search(&w).is_ok());
            let e_bad = e_mixed
                || e_over
                || clusters(&|f: &[u32]| f.binary_search(&w).is_ok(), &members) > 1;
            any_bad_edge |= e_bad;
            if w > v {
                edges_out.push((w, if e_bad { NonManifold } else { Unknown }));
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
}

fn find(p: &mut [u32], mut x: u32) -> u32 {
    while p[x as usize] != x {
        let g = p[p[x as usize] as usize];
        p[x as usize] = g;
        x = g;
    }
    x
}

#[derive(Default)]
struct Scratch {
    tet: TetScratch,
    ew: Vec<(u32, u32)>,
    faces: Vec<(u128, u32, u32, u32)>,
    wpairs: Vec<(u32, u32, u32)>,
    bedges: Vec<(u32, u32)>,
    parent: Vec<u32>,
    local_uf: Vec<u32>,
    face_bad_w: Vec<u32>,
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
        let mut x: u64 = 0x2545_F491_4F6C_DD1D;
        let mut next = |m: u64| {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x % m
        };
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
            let opts = BuildOptions {
                drop_duplicates: true,
                drop_face_cells: true,
                ..Default::default()
            };
            let Ok((k, _)) = b.build(&opts) else {
                continue;
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
                let fast = t.par_map_leaves(|view| t.leaf_manifold(view, d, true));
                let slow = t.par_map_leaves(|view| t.leaf_manifold(view, d, false));
                type Leaf = (Vec<u32>, Vec<u32>, Vec<[u32; 2]>, Vec<[u32; 2]>);
                let norm = |mut r: Vec<Leaf>| {
                    for x in &mut r {
                        x.2.sort_unstable();
                        x.3.sort_unstable();
                    }
                    r
                };
                let slow = norm(slow);
                let nm: usize = slow.iter().map(|x| x.0.len()).sum();
                seen_kinds[0] += nm;
                seen_kinds[1] += t.n_vertices() - nm;
                seen_kinds[2] += slow.iter().map(|x| x.2.len()).sum::<usize>();
                assert_eq!(norm(fast), slow, "case {case} kv {kv}");
            }
        }
        assert!(seen_kinds.iter().all(|&n| n > 100), "{seen_kinds:?}");
    }
}
