//! Ghost simplices: names for the faces IA* does not store ("the i-th p-face of the k-th top
//! m-simplex"), and the relations among them.
use rustc_hash::FxHashMap;

use super::{cp, IaStar};
use crate::cell::binomial;
use crate::ids::VertexId;
use crate::topo::{sorted_simplex, QueryError};

/// A ghost simplex: "the i-th p-face of the k-th top m-simplex" (k counts the top m-simplices in
/// input order; i ranks the face's vertex positions in colex order,
/// rank({s_0<…<s_p}) = Σ_j C(s_j, j+1)). Ghosts returned by [`IaStar`] are canonical: the top
/// is the smallest (m, k) containing the face, so one simplex has one ghost and `==` is
/// simplex equality.
///
/// ```
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// use starplex::ids::{CellId, VertexId};
/// use starplex::tds::iastar::IaStar;
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for _ in 0..4 { b.push_vertex(&[0.0, 0.0]).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// let ia = IaStar::new(&k).unwrap(); // triangles [0, 1, 2] and [1, 3, 2]
/// use starplex::tds::iastar::Ghost;
/// // edge {1,2}: positions {1,2} of top triangle 0, colex rank C(1,1) + C(2,2) = 2
/// let g = ia.ghost(&[VertexId(1), VertexId(2)]).unwrap();
/// assert_eq!(g, Ghost { m: 2, k: 0, p: 1, i: 2 });
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Ghost {
    /// Dimension of the top.
    pub m: u8,
    /// Index of the top among the top m-simplices.
    pub k: u32,
    /// Dimension of the face.
    pub p: u8,
    /// Colex rank of the face's vertex positions in the top.
    pub i: u64,
}

/// Colex rank of sorted positions.
fn colex_rank(pos: &[usize]) -> u64 {
    pos.iter()
        .enumerate()
        .map(|(j, &s)| binomial(s as u64, j as u64 + 1) as u64)
        .sum()
}

/// Positions (sorted) of the colex rank `i` among (p+1)-subsets.
fn colex_unrank(mut i: u64, p: usize) -> Vec<usize> {
    let mut out = vec![0usize; p + 1];
    for j in (0..=p).rev() {
        // largest s with C(s, j+1) <= i
        let mut s = j;
        while binomial(s as u64 + 1, j as u64 + 1) as u64 <= i {
            s += 1;
        }
        out[j] = s;
        i -= binomial(s as u64, j as u64 + 1) as u64;
    }
    out
}

/// Attributes attached to ghost simplices (sparse: a hash map keyed by the canonical ghost).
///
/// ```
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// use starplex::ids::VertexId;
/// use starplex::tds::iastar::{IaStar, GhostAttributes};
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for _ in 0..4 { b.push_vertex(&[0.0, 0.0]).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// let ia = IaStar::new(&k).unwrap();
/// let mut w: GhostAttributes<f64> = GhostAttributes::default();
/// let e = ia.ghost(&[VertexId(2), VertexId(1)]).unwrap();
/// w.insert(e, 0.5);
/// // the same edge named from the other triangle's side is the same canonical ghost
/// let again = ia.ghost(&[VertexId(1), VertexId(2)]).unwrap();
/// assert_eq!(w.get(&again), Some(&0.5));
/// ```
pub type GhostAttributes<T> = FxHashMap<Ghost, T>;

impl IaStar {
    /// The canonical ghost of simplex `s` (vertices in any order).
    ///
    /// # Errors
    /// `s` is not a simplex of the complex.
    ///
    /// ```
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// use starplex::ids::{CellId, VertexId};
    /// use starplex::tds::iastar::IaStar;
    /// # let mut b = ComplexBuilder::new(2).unwrap();
    /// # for _ in 0..4 { b.push_vertex(&[0.0, 0.0]).unwrap(); }
    /// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
    /// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// let ia = IaStar::new(&k).unwrap(); // triangles [0, 1, 2] and [1, 3, 2]
    /// use starplex::tds::iastar::Ghost;
    /// // vertex 3 is position 1 of the second triangle [1, 3, 2]
    /// assert_eq!(ia.ghost(&[VertexId(3)]).unwrap(), Ghost { m: 2, k: 1, p: 0, i: 1 });
    /// // the shared edge has one canonical ghost, from triangle 0
    /// assert_eq!(ia.ghost(&[VertexId(2), VertexId(1)]).unwrap().k, 0);
    /// assert!(ia.ghost(&[VertexId(0), VertexId(3)]).is_err()); // not an edge
    /// ```
    pub fn ghost(&self, s: &[VertexId]) -> Result<Ghost, QueryError> {
        let s = sorted_simplex(s)?;
        let mut cells = Vec::new();
        crate::topo::from_tops::top_star(self, &s, &mut cells)?;
        let best = cells
            .iter()
            .map(|&c| {
                let (m, k) = self.dim_index(c);
                (m, k, c)
            })
            .min()
            .ok_or_else(|| QueryError::NotInComplex(s.iter().map(|v| v.0).collect()))?;
        let (m, k, c) = best;
        let b = self.block_of(c.0);
        let verts = Self::record(b, c.0).1;
        if !b.kind.is_simplex() {
            // a face of a CP top: its index in the kind's face table of its dimension
            let (p, i) = cp::face_index(b.kind, verts, &s)
                .ok_or_else(|| QueryError::NotInComplex(s.iter().map(|v| v.0).collect()))?;
            return Ok(Ghost {
                m: m as u8,
                k,
                p: p as u8,
                i: i as u64,
            });
        }
        let mut pos: Vec<usize> = s
            .iter()
            .map(|v| {
                verts
                    .iter()
                    .position(|&w| w == v.0)
                    .expect("a top of the star contains the simplex")
            })
            .collect();
        pos.sort_unstable();
        Ok(Ghost {
            m: m as u8,
            k,
            p: (s.len() - 1) as u8,
            i: colex_rank(&pos),
        })
    }

    /// The sorted vertices of a ghost.
    ///
    /// # Errors
    /// A ghost that names no face of a top.
    ///
    /// ```
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// use starplex::ids::{CellId, VertexId};
    /// use starplex::tds::iastar::IaStar;
    /// # let mut b = ComplexBuilder::new(2).unwrap();
    /// # for _ in 0..4 { b.push_vertex(&[0.0, 0.0]).unwrap(); }
    /// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
    /// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// let ia = IaStar::new(&k).unwrap(); // triangles [0, 1, 2] and [1, 3, 2]
    /// let g = ia.ghost(&[VertexId(3), VertexId(2)]).unwrap();
    /// assert_eq!(ia.ghost_vertices(g).unwrap(), vec![VertexId(2), VertexId(3)]);
    /// ```
    pub fn ghost_vertices(&self, g: Ghost) -> Result<Vec<VertexId>, QueryError> {
        let bad = || QueryError::NotInComplex(vec![]);
        let c = self.cell_of(g.m as usize, g.k).ok_or_else(bad)?;
        let b = self.block_of(c.0);
        let verts = Self::record(b, c.0).1;
        if !b.kind.is_simplex() {
            let face = b
                .kind
                .cp_faces(g.p as usize)
                .and_then(|t| t.get(usize::try_from(g.i).ok()?))
                .ok_or_else(bad)?;
            let mut out: Vec<VertexId> =
                face.iter().map(|&l| VertexId(verts[l as usize])).collect();
            out.sort_unstable();
            return Ok(out);
        }
        if g.p > g.m || g.i as u128 >= binomial(g.m as u64 + 1, g.p as u64 + 1) {
            return Err(bad());
        }
        let mut out: Vec<VertexId> = colex_unrank(g.i, g.p as usize)
            .into_iter()
            .map(|j| VertexId(verts[j]))
            .collect();
        out.sort_unstable();
        Ok(out)
    }

    /// R_{p,q} on a ghost, q < p: its q-faces as canonical ghosts, sorted.
    ///
    /// # Errors
    /// A bad ghost; too many faces.
    ///
    /// ```
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// use starplex::ids::{CellId, VertexId};
    /// use starplex::tds::iastar::IaStar;
    /// # let mut b = ComplexBuilder::new(2).unwrap();
    /// # for _ in 0..4 { b.push_vertex(&[0.0, 0.0]).unwrap(); }
    /// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
    /// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// let ia = IaStar::new(&k).unwrap(); // triangles [0, 1, 2] and [1, 3, 2]
    /// let e = ia.ghost(&[VertexId(1), VertexId(2)]).unwrap();
    /// let vs: Vec<_> = ia.ghost_boundary(e, 0).unwrap().into_iter()
    ///     .map(|g| ia.ghost_vertices(g).unwrap()).collect();
    /// assert_eq!(vs, vec![vec![VertexId(1)], vec![VertexId(2)]]);
    /// ```
    pub fn ghost_boundary(&self, g: Ghost, q: usize) -> Result<Vec<Ghost>, QueryError> {
        let s = self.ghost_vertices(g)?;
        if s.len() != g.p as usize + 1 {
            // a CP cell (quad, pyramid, prism, hexahedron): the faces in its top's tables
            return cp::ghost_boundary(self, g, &s, q);
        }
        let mut flat = Vec::new();
        crate::topo::from_tops::boundary_of_sorted(&s, q, crate::topo::DEFAULT_BUDGET, &mut flat)?;
        self.ghosts_of_flat(&flat, q)
    }

    /// R_{p,q} on a ghost, q > p: its q-cofaces as canonical ghosts, sorted.
    ///
    /// # Errors
    /// A bad ghost; too many cofaces.
    ///
    /// ```
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// use starplex::ids::{CellId, VertexId};
    /// use starplex::tds::iastar::IaStar;
    /// # let mut b = ComplexBuilder::new(2).unwrap();
    /// # for _ in 0..4 { b.push_vertex(&[0.0, 0.0]).unwrap(); }
    /// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
    /// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// let ia = IaStar::new(&k).unwrap(); // triangles [0, 1, 2] and [1, 3, 2]
    /// let e = ia.ghost(&[VertexId(1), VertexId(2)]).unwrap();
    /// let ts: Vec<_> = ia.ghost_coboundary(e, 2).unwrap().into_iter()
    ///     .map(|g| ia.ghost_vertices(g).unwrap()).collect();
    /// assert_eq!(ts, vec![
    ///     vec![VertexId(0), VertexId(1), VertexId(2)],
    ///     vec![VertexId(1), VertexId(2), VertexId(3)],
    /// ]);
    /// ```
    pub fn ghost_coboundary(&self, g: Ghost, q: usize) -> Result<Vec<Ghost>, QueryError> {
        if !self.simplicial {
            return cp::ghost_coboundary(self, g, q);
        }
        let s = self.ghost_vertices(g)?;
        let mut flat = Vec::new();
        crate::topo::from_tops::coboundary(self, &s, q, crate::topo::DEFAULT_BUDGET, &mut flat)?;
        self.ghosts_of_flat(&flat, q)
    }

    /// R_{p,p} on a ghost: adjacent simplices as canonical ghosts, sorted (p ≥ 1).
    ///
    /// # Errors
    /// A bad ghost; too many simplices.
    ///
    /// ```
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// use starplex::ids::{CellId, VertexId};
    /// use starplex::tds::iastar::IaStar;
    /// # let mut b = ComplexBuilder::new(2).unwrap();
    /// # for _ in 0..4 { b.push_vertex(&[0.0, 0.0]).unwrap(); }
    /// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
    /// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// let ia = IaStar::new(&k).unwrap(); // triangles [0, 1, 2] and [1, 3, 2]
    /// let t0 = ia.ghost(&[VertexId(0), VertexId(1), VertexId(2)]).unwrap();
    /// let adj = ia.ghost_adjacent(t0).unwrap();
    /// assert_eq!(adj.len(), 1);
    /// assert_eq!(ia.ghost_vertices(adj[0]).unwrap(), vec![VertexId(1), VertexId(2), VertexId(3)]);
    /// ```
    pub fn ghost_adjacent(&self, g: Ghost) -> Result<Vec<Ghost>, QueryError> {
        if !self.simplicial {
            return cp::ghost_adjacent(self, g);
        }
        let s = self.ghost_vertices(g)?;
        let mut flat = Vec::new();
        crate::topo::from_tops::adjacent(self, &s, crate::topo::DEFAULT_BUDGET, &mut flat)?;
        if s.len() == 1 {
            return Ok(Vec::new());
        }
        self.ghosts_of_flat(&flat, s.len() - 1)
    }

    fn ghosts_of_flat(&self, flat: &[VertexId], q: usize) -> Result<Vec<Ghost>, QueryError> {
        let mut out = flat
            .chunks_exact(q + 1)
            .map(|f| self.ghost(f))
            .collect::<Result<Vec<_>, _>>()?;
        out.sort_unstable();
        Ok(out)
    }
}
