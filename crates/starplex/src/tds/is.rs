//! IS, the Incidence Simplicial data structure (De Floriani, Hui, Panozzo, Canino 2010), per
//! spec §1: every simplex explicit, its full immediate boundary R_{p,p-1}, and a *partial*
//! immediate co-boundary R*_{p,p+1}: one (p+1)-coface per connected component of the link of
//! σ (a "(p+1)-cluster"). Storage Σ_{p≥1}(p+1)n_p + Σ_σ c(σ) references, about half the
//! incidence graph. Stars and co-boundaries come from the spec's star expansion (up through
//! the partial co-boundary, down through facets that still contain σ), linear in the star.
//!
//! ```
//! use starplex::complex::{ComplexBuilder, BuildOptions};
//! use starplex::cell::CellKind;
//! use starplex::ids::VertexId;
//! use starplex::tds::is::Is;
//! use starplex::topo::{Star, Storage};
//! // two tets sharing only edge {0,1}
//! let mut b = ComplexBuilder::new(1).unwrap();
//! for x in 0..6 { b.push_vertex(&[x as f64]).unwrap(); }
//! b.push_cell(CellKind::Simplex(3), &[0, 1, 2, 3]).unwrap();
//! b.push_cell(CellKind::Simplex(3), &[0, 1, 4, 5]).unwrap();
//! let k = b.build(&BuildOptions::default()).unwrap().0;
//! let is = Is::new(&k, &Default::default()).unwrap();
//! assert_eq!(is.refs(), 80); // the spec's worked anchor
//! assert_eq!(is.n_clusters(&[VertexId(0), VertexId(1)]).unwrap(), 2);
//! assert_eq!(is.star(&[VertexId(0)]).unwrap().len(), 1 + 5 + 6 + 2);
//! ```
use crate::limits::{Limits, TooLarge, Unit};
use rustc_hash::FxHashSet;

use crate::algo::unionfind::UnionFind;
use crate::cell::CellKind;
use crate::complex::IndexedComplex;
use crate::csr::Csr;
use crate::ids::{CellId, SimplexId, VertexId};
use crate::tds::ig::{impl_explicit_common, Explicit};
use crate::tds::simplex_tree::BuildError;
use crate::topo::{
    Adjacency, Boundary, Coboundary, Counts, Levels, QueryError, SimplexSet, SimplexVertices, Star,
    Storage, TopCells, TopStar, VertexAdjacency, VertexStar, DEFAULT_BUDGET,
};

/// The IS data structure. See the [module docs](self).
///
/// ```
/// use starplex::tds::is::Is;
/// use starplex::topo::{Counts, Star};
/// use starplex::ids::VertexId;
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// // k: the triangles 0-1-2 and 1-3-2, sharing the edge 1-2
/// let is = Is::new(&k, &Default::default()).unwrap();
/// assert_eq!(is.f_vector().unwrap(), vec![4, 5, 2]);
/// assert_eq!(is.star(&[VertexId(1)]).unwrap().f_vector(), vec![1, 3, 2]);
/// ```
#[derive(Clone, Debug)]
pub struct Is {
    x: Explicit,
    /// Partial co-boundary per level p < dim: one (p+1)-coface (index) per cluster.
    pcob: Vec<Csr>,
}

impl Is {
    /// Builds IS from an indexed simplicial complex (spec §1.2).
    ///
    /// ```
    /// use starplex::limits::Limits;
    /// use starplex::tds::{is::Is, simplex_tree::BuildError};
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// # let mut b = ComplexBuilder::new(2).unwrap();
    /// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
    /// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
    /// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// // k: the triangles 0-1-2 and 1-3-2, sharing the edge 1-2
    /// assert!(Is::new(&k, &Limits::default()).is_ok());
    /// let tight = Limits { stored_simplices: 5, ..Limits::default() };
    /// assert!(matches!(Is::new(&k, &tight), Err(BuildError::TooLarge(t)) if t.budget == 5));
    /// ```
    ///
    /// # Errors
    /// A CP cell; more than `limits.stored_simplices` simplices (refused before allocating
    /// them).
    pub fn new(k: &IndexedComplex, limits: &Limits) -> Result<Is, BuildError> {
        let x = Explicit::new(k, limits.stored_simplices)?;
        let cobs = x.coboundaries();
        let depth = x.depth();
        let mut pcob = Vec::with_capacity(cobs.len());
        for (p, (csr, pos)) in cobs.iter().enumerate() {
            // incidences of level p: x = τ*(p+2) + j  (σ is facet j of τ at level p+1)
            let n = p + 2;
            let n_inc = x.n_at(p + 1) * n;
            let mut uf = UnionFind::new(n_inc);
            if p + 2 < depth {
                for eta in 0..x.n_at(p + 2) as u32 {
                    let f = x.facets(p + 2, eta);
                    for a in 0..f.len() {
                        for b in a + 1..f.len() {
                            let (t1, t2) = (f[a] as usize, f[b] as usize);
                            uf.union((t1 * n + (b - 1)) as u32, (t2 * n + a) as u32);
                        }
                    }
                }
            }
            let mut roots: Vec<u32> = Vec::new();
            let mut offsets = Vec::with_capacity(csr.n_rows() + 1);
            let mut targets = Vec::new();
            offsets.push(0u32);
            for s in 0..csr.n_rows() {
                roots.clear();
                let lo = csr.offsets[s] as usize;
                for (e, &t) in csr.row(s).iter().enumerate() {
                    let inc = t as usize * n + pos[lo + e] as usize;
                    let r = uf.find(inc as u32);
                    if !roots.contains(&r) {
                        roots.push(r);
                        targets.push(t);
                    }
                }
                offsets.push(targets.len() as u32);
            }
            pcob.push(Csr { offsets, targets });
        }
        Ok(Is { x, pcob })
    }

    /// Bytes of the auxiliary index (sorted vertex tuples, top-cell map), not counted in
    /// [`Storage::bytes`].
    ///
    /// ```
    /// use starplex::tds::is::Is;
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// # let mut b = ComplexBuilder::new(2).unwrap();
    /// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
    /// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
    /// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// // k: the triangles 0-1-2 and 1-3-2, sharing the edge 1-2
    /// let is = Is::new(&k, &Default::default()).unwrap();
    /// // At least the sorted vertex tuples of the 5 edges and 2 triangles.
    /// assert!(is.aux_bytes() >= 4 * (5 * 2 + 2 * 3));
    /// ```
    pub fn aux_bytes(&self) -> u64 {
        self.x.aux_bytes()
    }

    /// c(σ): the number of connected components of the link of `s` (0 for a top).
    ///
    /// ```
    /// use starplex::tds::is::Is;
    /// use starplex::ids::VertexId;
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// // A bow tie: the triangles 0-1-2 and 0-3-4 share only vertex 0.
    /// let mut b = ComplexBuilder::new(1).unwrap();
    /// for x in 0..5 { b.push_vertex(&[x as f64]).unwrap(); }
    /// b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
    /// b.push_cell(CellKind::Simplex(2), &[0, 3, 4]).unwrap();
    /// let k = b.build(&BuildOptions::default()).unwrap().0;
    /// let is = Is::new(&k, &Default::default()).unwrap();
    /// assert_eq!(is.n_clusters(&[VertexId(0)]).unwrap(), 2); // two link components
    /// assert_eq!(is.n_clusters(&[VertexId(1)]).unwrap(), 1);
    /// assert_eq!(is.n_clusters(&[VertexId(0), VertexId(1), VertexId(2)]).unwrap(), 0); // a top
    /// ```
    ///
    /// # Errors
    /// `s` not in the complex.
    pub fn n_clusters(&self, s: &[VertexId]) -> Result<usize, QueryError> {
        let (raw, i) = self.x.locate(s)?;
        let p = raw.len() - 1;
        Ok(self.pcob.get(p).map_or(0, |c| c.degree(i as usize)))
    }

    /// The stored partial co-boundary R*_{p,p+1}(s) as sorted tuples (flat).
    ///
    /// ```
    /// use starplex::tds::is::Is;
    /// use starplex::topo::Coboundary;
    /// use starplex::ids::VertexId;
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// # let mut b = ComplexBuilder::new(2).unwrap();
    /// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
    /// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
    /// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// // k: the triangles 0-1-2 and 1-3-2, sharing the edge 1-2
    /// let is = Is::new(&k, &Default::default()).unwrap();
    /// let mut part = Vec::new();
    /// is.partial_coboundary(&[VertexId(1)], &mut part).unwrap();
    /// assert_eq!(part.len() / 2, 1); // the link of vertex 1 is connected: one edge kept
    /// let mut full = Vec::new();
    /// is.coboundary(&[VertexId(1)], 1, &mut full).unwrap();
    /// assert_eq!(full.len() / 2, 3);
    /// ```
    ///
    /// # Errors
    /// `s` not in the complex.
    pub fn partial_coboundary(
        &self,
        s: &[VertexId],
        out: &mut Vec<VertexId>,
    ) -> Result<(), QueryError> {
        let (raw, i) = self.x.locate(s)?;
        let p = raw.len() - 1;
        let ids: Vec<u32> = self
            .pcob
            .get(p)
            .map_or(&[][..], |c| c.row(i as usize))
            .to_vec();
        self.x.tuples_of(p + 1, &ids, out);
        Ok(())
    }

    /// St(σ) by star expansion (spec §1.3).
    fn star_ids(&self, p: usize, i: u32) -> Result<Vec<(usize, u32)>, QueryError> {
        let sigma: Vec<u32> = self.x.tuple(p, i).to_vec();
        let key = |d: usize, j: u32| ((d as u64) << 32) | j as u64;
        let mut visited: FxHashSet<u64> = FxHashSet::default();
        visited.insert(key(p, i));
        let mut queue = vec![(p, i)];
        let mut head = 0;
        while head < queue.len() {
            let (d, j) = queue[head];
            head += 1;
            if let Some(c) = self.pcob.get(d) {
                for &t in c.row(j as usize) {
                    if visited.insert(key(d + 1, t)) {
                        queue.push((d + 1, t));
                    }
                }
            }
            if d > p {
                let verts = self.x.tuple(d, j);
                for (pos, &f) in self.x.facets(d, j).iter().enumerate() {
                    if sigma.binary_search(&verts[pos]).is_ok() {
                        continue; // that facet drops a vertex of σ
                    }
                    if visited.insert(key(d - 1, f)) {
                        queue.push((d - 1, f));
                    }
                }
            }
            if queue.len() as u128 > DEFAULT_BUDGET {
                return Err(QueryError::TooLarge(TooLarge::new(
                    "star",
                    queue.len() as u128,
                    DEFAULT_BUDGET,
                    Unit::Simplices,
                )));
            }
        }
        Ok(queue)
    }
}

impl VertexAdjacency for Is {
    fn vertex_neighbours(&self, v: VertexId, out: &mut Vec<VertexId>) {
        out.clear();
        if v.0 >= self.x.n_at(0) as u32 {
            return;
        }
        if let Ok(star) = self.star_ids(0, v.0) {
            for (d, e) in star {
                if d == 1 {
                    let t = self.x.tuple(1, e);
                    out.push(VertexId(if t[0] == v.0 { t[1] } else { t[0] }));
                }
            }
        }
        out.sort_unstable();
    }
}

impl_explicit_common!(Is);

impl Storage for Is {
    /// Σ_{p≥1}(p+1)n_p + Σ_σ c(σ).
    fn refs(&self) -> u64 {
        self.x.boundary_refs() + self.pcob.iter().map(|c| c.n_refs() as u64).sum::<u64>()
    }
    fn bytes(&self) -> u64 {
        self.x.boundary_bytes() + self.pcob.iter().map(|c| c.bytes() as u64).sum::<u64>()
    }
}
