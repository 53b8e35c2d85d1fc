//! Orientation (CASC Alg. 5 and eq. 7-8): signs on incidences by the boundary morphism,
//! consistent orientation of the top simplices per connected component, orientability and
//! pseudo-manifoldness; surface geometry (areas, signed volume, vertex normals and tangents,
//! eq. 9-10) over positions stored on vertices.
use super::complex::Hasse;
use super::edit::Position;
use super::levels::{At, LevelTypes};
use super::Node;
use crate::algo::unionfind::UnionFind;
use crate::complex::IndexedComplex;
use crate::ids::{SimplexId, VertexId};

/// A consistent orientation of the top simplices (dimension `dim`) of a complex.
///
/// `signs[i]` is `+1` when the top simplex `i` is oriented as its sorted vertex order, `-1`
/// when as the opposite order.
///
/// ```
/// let mut h: starplex::hasse::Hasse = starplex::hasse::Hasse::new();
/// h.insert(&[0.into(), 1.into(), 2.into()]).unwrap();
/// h.insert(&[1.into(), 2.into(), 3.into()]).unwrap();
/// let o = h.orient(None);
/// assert!(o.orientable && o.pseudo_manifold);
/// assert_eq!(o.components, 1);
/// // the shared edge {1,2} gets opposite induced orientations
/// assert_eq!(o.signs, vec![1, -1]);
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct HasseOrientation {
    /// Dimension of the simplices oriented.
    pub dim: usize,
    /// One sign per top simplex, by id (0 at freed slots).
    pub signs: Vec<i8>,
    /// True when no conflict was found (every face shared by two top simplices gets opposite
    /// induced orientations).
    pub orientable: bool,
    /// True when the complex is pure and every `(dim-1)`-face has at most two cofaces.
    pub pseudo_manifold: bool,
    /// Connected components of the top simplices through shared `(dim-1)`-faces.
    pub components: usize,
}

/// Areas and volume of an oriented triangulated surface.
///
/// ```
/// use starplex::hasse::SurfaceGeometry;
/// let g = SurfaceGeometry { area: 1.0, signed_volume: 0.0 };
/// assert_eq!(g.area, 1.0);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfaceGeometry {
    /// Total area of the triangles.
    pub area: f64,
    /// Signed volume enclosed (positive when the orientation points outward).
    pub signed_volume: f64,
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Parity of the permutation that sorts `v` (+1 even, -1 odd).
fn parity(v: &[u32]) -> i8 {
    let mut s = 1i8;
    for i in 0..v.len() {
        for j in i + 1..v.len() {
            if v[i] > v[j] {
                s = -s;
            }
        }
    }
    s
}

impl<L: LevelTypes> Hasse<L> {
    /// Alg. 5: the sign of the incidence `a → b` (`b = a ∪ {v}`) by the boundary morphism
    /// (eq. 7): `(-1)^i` where `i` is the position of `v` in `b`'s sorted vertices. `None` when
    /// `a` is not a facet of `b`.
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse = starplex::hasse::Hasse::new();
    /// let t = h.insert(&[0.into(), 1.into(), 2.into()]).unwrap();
    /// let e12 = h.find(&[1.into(), 2.into()]).unwrap();
    /// let e02 = h.find(&[0.into(), 2.into()]).unwrap();
    /// assert_eq!(h.incidence_sign(e12, t), Some(1));
    /// assert_eq!(h.incidence_sign(e02, t), Some(-1));
    /// ```
    pub fn incidence_sign(&self, a: Node, b: Node) -> Option<i8> {
        if b.dim != a.dim + 1 || !self.contains(a) || !self.contains(b) {
            return None;
        }
        let l = &self.levels[b.dim as usize];
        let pos = l.downs(b.id.0).iter().position(|&f| f == a.id.0)?;
        Some(if pos % 2 == 0 { 1 } else { -1 })
    }

    /// The facets of `s` with the orientations induced by `s` carrying `sign` (consistent);
    /// negate them for the opposite orientation.
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse = starplex::hasse::Hasse::new();
    /// let t = h.insert(&[0.into(), 1.into(), 2.into()]).unwrap();
    /// let f = h.oriented_facets(t, -1);
    /// assert_eq!(f.iter().map(|x| x.1).collect::<Vec<_>>(), vec![-1, 1, -1]);
    /// ```
    pub fn oriented_facets(&self, s: Node, sign: i8) -> Vec<(Node, i8)> {
        self.down(s)
            .enumerate()
            .map(|(i, f)| (f, if i % 2 == 0 { sign } else { -sign }))
            .collect()
    }

    /// The cofaces of `s`, each oriented so that it induces `sign` on `s` (consistent with
    /// `s`); negate for the opposite.
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse = starplex::hasse::Hasse::new();
    /// h.insert(&[0.into(), 1.into(), 2.into()]).unwrap();
    /// h.insert(&[1.into(), 2.into(), 3.into()]).unwrap();
    /// let e = h.find(&[1.into(), 2.into()]).unwrap();
    /// let c = h.oriented_cofaces(e, 1);
    /// // {1,2} is facet 0 of {0,1,2} and facet 2 of {1,2,3}: both sorted orders induce +1
    /// assert_eq!(c.iter().map(|x| x.1).collect::<Vec<_>>(), vec![1, 1]);
    /// ```
    pub fn oriented_cofaces(&self, s: Node, sign: i8) -> Vec<(Node, i8)> {
        self.up(s)
            .map(|c| (c, sign * self.incidence_sign(s, c).unwrap_or(1)))
            .collect()
    }

    /// The vertices of `s` in an order with orientation `sign` (sorted when `+1`, the first two
    /// swapped when `-1`).
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse = starplex::hasse::Hasse::new();
    /// let t = h.insert(&[0.into(), 1.into(), 2.into()]).unwrap();
    /// assert_eq!(h.oriented_vertices(t, -1), vec![1.into(), 0.into(), 2.into()]);
    /// ```
    pub fn oriented_vertices(&self, s: Node, sign: i8) -> Vec<VertexId> {
        let mut v = self.vertices(s).to_vec();
        if sign < 0 && v.len() >= 2 {
            v.swap(0, 1);
        }
        v
    }

    /// The orientation of each top simplex given by an input complex's vertex order (the
    /// winding of the file): `+1`/`-1` per top simplex, `0` for those not among its cells.
    ///
    /// ```
    /// use starplex::complex::{ComplexBuilder, BuildOptions};
    /// use starplex::cell::CellKind;
    /// let mut b = ComplexBuilder::new(2).unwrap();
    /// for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]] { b.push_vertex(&p).unwrap(); }
    /// b.push_cell(CellKind::Simplex(2), &[1, 0, 2]).unwrap();
    /// let k = b.build(&BuildOptions::default()).unwrap().0;
    /// let h: starplex::hasse::Hasse = starplex::hasse::Hasse::from_indexed(&k).unwrap();
    /// assert_eq!(h.input_signs(&k), vec![-1]);
    /// ```
    pub fn input_signs(&self, k: &IndexedComplex) -> Vec<i8> {
        let Some(d) = self.dim() else {
            return Vec::new();
        };
        let mut s = vec![0i8; self.n_slots(d)];
        for c in k.cells() {
            if c.kind.is_simplex() && c.kind.dim() == d {
                let vs: Vec<VertexId> = c.vertices.iter().map(|&x| VertexId(x)).collect();
                if let Some(n) = self.find(&vs) {
                    s[n.id.index()] = parity(c.vertices);
                }
            }
        }
        s
    }

    /// Orients the top simplices consistently (eq. 8), one walk per component ([`orient_walk`](crate::algo::orientation::orient_walk))
    /// through faces with exactly two cofaces. Each component starts from its first simplex
    /// with the sign given in `initial` (when non-zero) or `+1`, so an input winding that is
    /// already consistent is kept as is.
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse = starplex::hasse::Hasse::new();
    /// // a Möbius strip is not orientable
    /// for t in [[0, 1, 2], [1, 2, 3], [2, 3, 4], [3, 4, 0], [4, 0, 1]] {
    ///     h.insert(&t.map(starplex::ids::VertexId)).unwrap();
    /// }
    /// assert!(!h.orient(None).orientable);
    /// ```
    pub fn orient(&self, initial: Option<&[i8]>) -> HasseOrientation {
        let Some(d) = self.dim() else {
            return HasseOrientation {
                dim: 0,
                signs: Vec::new(),
                orientable: true,
                pseudo_manifold: true,
                components: 0,
            };
        };
        let n = self.n_slots(d);
        // pure: every lower simplex has a coface
        let mut pseudo = (0..d).all(|k| self.level(k).all(|s| self.up(s).len() > 0));
        if d > 0 {
            pseudo &= self.level(d - 1).all(|s| self.up(s).len() <= 2);
        }
        // pairs of top simplices through faces with exactly two cofaces; the sign of facet i
        // of a simplex relative to its sorted order is (-1)^i
        let mut pairs = Vec::new();
        if d > 0 {
            let l = &self.levels[d];
            for f in self.level(d - 1) {
                let ups = self.levels[d - 1].up.get(f.id.0);
                if ups.len() != 2 {
                    continue;
                }
                let (t, u) = (ups[0][1], ups[1][1]);
                let i = l.downs(t).iter().position(|&x| x == f.id.0).unwrap_or(0);
                let j = l.downs(u).iter().position(|&x| x == f.id.0).unwrap_or(0);
                pairs.push((t, u, if (i + j) % 2 == 0 { 1 } else { -1 }));
            }
        }
        let dead = |c: u32| self.levels[d].up.is_dead(c);
        let seed = |c: u32| {
            initial
                .and_then(|x| x.get(c as usize).copied())
                .unwrap_or(1)
        };
        let walk = crate::algo::orientation::orient_walk(n, |c| !dead(c), &pairs, seed);
        let (signs, orientable, components) =
            (walk.signs, walk.conflict.is_none(), walk.n_components);
        HasseOrientation {
            dim: d,
            signs,
            orientable,
            pseudo_manifold: pseudo,
            components,
        }
    }

    /// Connected components of the whole complex (vertices joined by edges; isolated vertices
    /// count).
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse = starplex::hasse::Hasse::new();
    /// h.insert(&[0.into(), 1.into()]).unwrap();
    /// h.insert(&[2.into()]).unwrap();
    /// assert_eq!(h.n_components(), 2);
    /// ```
    pub fn n_components(&self) -> usize {
        let n = self.n_slots(0);
        let mut uf = UnionFind::new(n);
        for e in self.level(1) {
            let d = self.levels[1].downs(e.id.0);
            uf.union(d[0], d[1]);
        }
        uf.n_sets() - (n - self.n_simplices(0))
    }

    fn pos(&self, v: u32) -> [f64; 3]
    where
        L: At<0>,
        <L as At<0>>::Data: Position,
    {
        self.level_data::<0>()[v as usize].position()
    }

    /// Positions of a triangle's vertices in sorted order.
    fn tri_points(&self, t: u32) -> [[f64; 3]; 3]
    where
        L: At<0>,
        <L as At<0>>::Data: Position,
    {
        let vs = self.levels[2].verts(t);
        let r = |x: u32| self.pos(self.root.get(x).unwrap_or(0));
        [r(vs[0]), r(vs[1]), r(vs[2])]
    }

    /// Area of triangle `t` (positions from level-0 data).
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse<([f64; 3],)> = starplex::hasse::Hasse::new();
    /// for (i, p) in [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]].iter().enumerate() {
    ///     h.insert_with::<0>(&[(i as u32).into()], *p).unwrap();
    /// }
    /// let t = h.insert(&[0.into(), 1.into(), 2.into()]).unwrap();
    /// assert_eq!(h.triangle_area(t.id), 0.5);
    /// ```
    pub fn triangle_area(&self, t: SimplexId) -> f64
    where
        L: At<0>,
        <L as At<0>>::Data: Position,
    {
        let [a, b, c] = self.tri_points(t.0);
        let n = cross(sub(b, a), sub(c, a));
        0.5 * dot(n, n).sqrt()
    }

    /// Total area and signed volume of an oriented surface (`o` from [`orient`](Self::orient)
    /// on a complex of dimension 2): `Σ sign · det(p0, p1, p2) / 6`.
    ///
    /// ```
    /// use starplex::hasse::Hasse;
    /// let mut h: Hasse<([f64; 3],)> = Hasse::new();
    /// let p = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    /// for (i, x) in p.iter().enumerate() { h.insert_with::<0>(&[(i as u32).into()], *x).unwrap(); }
    /// // outward winding of the unit corner tetrahedron
    /// let faces = [[0u32, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];
    /// for f in faces { h.insert(&f.map(starplex::ids::VertexId)).unwrap(); }
    /// // {0,1,2} (id 0, the seed) is wound (0,2,1): odd, so -1; the rest follows
    /// let o = h.orient(Some(&[-1, 0, 0, 0]));
    /// assert!(o.orientable);
    /// let g = h.surface_geometry(&o);
    /// assert!((g.signed_volume - 1.0 / 6.0).abs() < 1e-12);
    /// ```
    pub fn surface_geometry(&self, o: &HasseOrientation) -> SurfaceGeometry
    where
        L: At<0>,
        <L as At<0>>::Data: Position,
    {
        let mut area = 0.0;
        let mut vol = 0.0;
        if o.dim == 2 && self.n_slots(2) == o.signs.len() {
            for t in self.level(2).map(|t| t.id.0) {
                let [a, b, c] = self.tri_points(t);
                let n = cross(sub(b, a), sub(c, a));
                area += 0.5 * dot(n, n).sqrt();
                vol += o.signs[t as usize] as f64 * dot(a, cross(b, c)) / 6.0;
            }
        }
        SurfaceGeometry {
            area,
            signed_volume: vol,
        }
    }

    /// Area-weighted unit normal at vertex `v` of an oriented surface (zero when undefined).
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse<([f64; 3],)> = starplex::hasse::Hasse::new();
    /// for (i, p) in [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]].iter().enumerate() {
    ///     h.insert_with::<0>(&[(i as u32).into()], *p).unwrap();
    /// }
    /// h.insert(&[0.into(), 1.into(), 2.into()]).unwrap();
    /// let o = h.orient(None);
    /// assert_eq!(h.vertex_normal(h.vertex(0.into()).unwrap(), &o), [0.0, 0.0, 1.0]);
    /// ```
    pub fn vertex_normal(&self, v: Node, o: &HasseOrientation) -> [f64; 3]
    where
        L: At<0>,
        <L as At<0>>::Data: Position,
    {
        let t = self.vertex_tangent(v, o);
        // the dual of the bivector: (B_yz, B_zx, B_xy)
        let n = [t[1][2], t[2][0], t[0][1]];
        let len = dot(n, n).sqrt();
        if len == 0.0 {
            [0.0; 3]
        } else {
            [n[0] / len, n[1] / len, n[2] / len]
        }
    }

    /// Eq. 9-10: the tangent bivector at `v`, `1/N Σ Orient(f) (e_j ∧ e_k)` over the `N`
    /// triangles at `v` (with `e_j`, `e_k` the edges from `v` to the other two vertices, in the
    /// triangle's orientation), as the antisymmetric matrix `½(e_j ⊗ e_k − e_k ⊗ e_j)`.
    ///
    /// ```
    /// let mut h: starplex::hasse::Hasse<([f64; 3],)> = starplex::hasse::Hasse::new();
    /// for (i, p) in [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]].iter().enumerate() {
    ///     h.insert_with::<0>(&[(i as u32).into()], *p).unwrap();
    /// }
    /// h.insert(&[0.into(), 1.into(), 2.into()]).unwrap();
    /// let o = h.orient(None);
    /// let b = h.vertex_tangent(h.vertex(0.into()).unwrap(), &o);
    /// assert_eq!((b[0][1], b[1][0]), (0.5, -0.5));
    /// ```
    pub fn vertex_tangent(&self, v: Node, o: &HasseOrientation) -> [[f64; 3]; 3]
    where
        L: At<0>,
        <L as At<0>>::Data: Position,
    {
        let mut b = [[0.0; 3]; 3];
        if o.dim != 2 || v.dim != 0 || !self.contains(v) {
            return b;
        }
        let st = self.star_ids(v);
        let Some(tris) = st.get(2) else { return b };
        let lab = self.levels[0].verts(v.id.0)[0];
        let pv = self.pos(v.id.0);
        for &t in tris {
            let vs = self.levels[2].verts(t);
            let i = vs.iter().position(|&x| x == lab).unwrap_or(0);
            let others: Vec<u32> = vs.iter().copied().filter(|&x| x != lab).collect();
            let sign = o.signs.get(t as usize).copied().unwrap_or(1) as f64
                * if i % 2 == 0 { 1.0 } else { -1.0 };
            let ej = sub(self.pos(self.root.get(others[0]).unwrap_or(0)), pv);
            let ek = sub(self.pos(self.root.get(others[1]).unwrap_or(0)), pv);
            for r in 0..3 {
                for c in 0..3 {
                    b[r][c] += sign * 0.5 * (ej[r] * ek[c] - ek[r] * ej[c]);
                }
            }
        }
        let n = tris.len() as f64;
        for row in &mut b {
            for x in row.iter_mut() {
                *x /= n;
            }
        }
        b
    }
}
