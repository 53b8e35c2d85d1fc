//! Manifoldness of vertices and edges: **one definition**, used by every structure through the
//! query traits ([`singularities`]) and by the Stellar tree's leaf-parallel validation
//! ([`StellarTree::validate`](crate::stellar::StellarTree::validate), `starplex validate`), which
//! call the same star tests ([`StarTester`]) and so give the same answer.
//!
//! **Definition.** A simplex or cell σ is *manifold* when every top cell containing σ has the
//! same dimension k and the link Lk(σ) is a (k − dim σ − 1)-sphere or ball. The empty link is
//! the (−1)-sphere. Two conventions fix k, both available by name ([`Convention`]):
//!
//! * [`Convention::Global`]: k = d, the dimension of the complex (what `starplex validate`
//!   reports). A vertex or edge of a lower-dimensional top cell is non-manifold, and so is an
//!   isolated vertex when d > 0.
//! * [`Convention::Local`]: k = the dimension of σ's own star, which must be uniform. A dangling
//!   top edge is a 1-manifold piece and an isolated vertex is a 0-manifold; only where
//!   dimensions meet (a dangling edge touching a surface) is non-manifold.
//!
//! **Decision procedure** (the same for both conventions, on the cells of σ's star with the cell
//! kinds' face tables, so quads, hexahedra, prisms and pyramids are tested like simplices):
//! * k ≤ 3: exact. k = 1: a vertex is in at most two edges. k = 2: every edge at the vertex is
//!   in at most two faces and the faces around the vertex are connected through those edges.
//!   k = 3: every face at the vertex is in at most two cells, the cells around every edge at
//!   the vertex are connected through the faces at that edge, the cells around the vertex are
//!   connected, and the link is a sphere (χ = 2, closed) or a disk (χ = 1, one boundary cycle).
//! * k ≥ 4 (simplices): the decidable necessary conditions — uniform dimension, every facet at
//!   the vertex in at most two top cells, the top cells around the vertex (and around each edge
//!   at it) connected through facets — prove non-manifoldness; when they all pass the answer is
//!   [`Manifoldness::Unknown`] (sphere recognition is impractical in dimension 3 and
//!   undecidable from dimension 5).
//!
//! ```
//! use starplex::complex::{ComplexBuilder, BuildOptions};
//! use starplex::cell::CellKind;
//! use starplex::ids::VertexId;
//! use starplex::topo::naive::VtIndex;
//! use starplex::algo::manifold::{singularities, vertex_manifoldness, Convention, Manifoldness};
//! // bow-tie: two triangles sharing vertex 0, and a dangling edge 1-5
//! let mut b = ComplexBuilder::new(2).unwrap();
//! for _ in 0..6 { b.push_vertex(&[0.0, 0.0]).unwrap(); }
//! b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
//! b.push_cell(CellKind::Simplex(2), &[0, 3, 4]).unwrap();
//! b.push_cell(CellKind::Simplex(1), &[1, 5]).unwrap();
//! let k = b.build(&BuildOptions::default()).unwrap().0;
//! let idx = VtIndex::new(&k);
//! let nm = |c| vertex_manifoldness(&idx, VertexId(0), c).unwrap();
//! assert_eq!(nm(Convention::Global), Manifoldness::NonManifold);
//! let r = singularities(&idx, Convention::Global).unwrap();
//! assert_eq!(r.non_manifold_vertices, [VertexId(0), VertexId(1), VertexId(5)]);
//! assert_eq!(r.non_manifold_edges, [[VertexId(1), VertexId(5)]]);
//! // locally the dangling edge is a 1-manifold piece; only its attachment point 1 is not
//! let r = singularities(&idx, Convention::Local).unwrap();
//! assert_eq!(r.non_manifold_vertices, [VertexId(0), VertexId(1)]);
//! assert!(r.non_manifold_edges.is_empty());
//! ```
use crate::cell::CellKind;
use crate::ids::{CellId, VertexId};
use crate::topo::{LocalStar, PartStar, QueryError, TopCells, VertexStar};

mod star;
mod tets;
mod tris;

pub(crate) use tets::TetScratch;
pub(crate) use tris::link_test as triangle_link_test;

/// The star tests of a vertex whose non-empty star holds tetrahedra only, in a complex of
/// dimension 3, with the triangles it owns: as [`StarTester`]'s global test (same answer,
/// `edges_out` sorted by `w`), then `owned(tri, cells)` for every triangle `v a b` with
/// `v < a < b` (star indices of its tetrahedra, increasing; triangles in no particular
/// order). `None` (nothing pushed) for a cell with a repeated vertex, which only a damaged
/// tree file holds: the caller then takes the general path.
pub(crate) fn tet_star_tests_and_triangles<S: StarCells + ?Sized>(
    v: u32,
    star: &S,
    s: &mut TetScratch,
    buf: &mut Vec<u32>,
    edges_out: &mut Vec<(u32, Manifoldness)>,
    owned: impl FnMut([u32; 2], &[u32]),
) -> Option<Manifoldness> {
    let start = edges_out.len();
    let m = tets::star_tests_tets(v, star, s, edges_out)?;
    let new = &mut edges_out[start..];
    if !new.is_sorted_by_key(|e| e.0) {
        new.sort_unstable_by_key(|e| e.0);
    }
    s.owned_triangles(v, buf, owned);
    Some(m)
}

/// The answer of a manifold test.
///
/// ```
/// use starplex::algo::manifold::{sphere_or_ball, Manifoldness};
/// assert_eq!(sphere_or_ball(&[vec![0, 1], vec![1, 2]], 1), Manifoldness::Manifold); // a path
/// // A 3-sphere link is not recognised: every necessary test passes, the answer is Unknown.
/// let bd4: Vec<Vec<u32>> = (0..5u32).map(|i| (0..5).filter(|&j| j != i).collect()).collect();
/// assert_eq!(sphere_or_ball(&bd4, 3), Manifoldness::Unknown);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Manifoldness {
    /// The link is a sphere or a ball of the right dimension.
    Manifold,
    /// A certificate of non-manifoldness was found.
    NonManifold,
    /// Every decidable test passed but sphere recognition is not done in this dimension.
    Unknown,
}

/// Which dimension a simplex's link is measured against (see the [module docs](self)).
///
/// ```
/// use starplex::algo::manifold::Convention;
/// assert_eq!(Convention::default(), Convention::Global); // what `starplex validate` reports
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Convention {
    /// k = the dimension of the complex.
    #[default]
    Global,
    /// k = the dimension of the simplex's own star.
    Local,
}

/// The cells of one star, as the star tests read them: kind and vertices of local cell `i`
/// (any numbering of the vertices, as long as it is the one the tested vertex is given in).
///
/// ```
/// use starplex::algo::manifold::{StarCells, OwnedStar};
/// use starplex::cell::CellKind;
/// let mut s = OwnedStar::default();
/// s.push(CellKind::Simplex(2), &[0, 1, 2]);
/// assert_eq!(s.len(), 1);
/// assert_eq!(s.cell(0), (CellKind::Simplex(2), &[0u32, 1, 2][..]));
/// ```
pub trait StarCells {
    /// Number of cells.
    fn len(&self) -> usize;
    /// Kind and vertices of cell `i`.
    fn cell(&self, i: usize) -> (CellKind, &[u32]);
    /// True when there is no cell.
    fn is_empty(&self) -> bool {
        self.len() == 0
    }
    /// True when every cell is of kind `kind` (a structure may know it without looking).
    ///
    /// ```
    /// use starplex::algo::manifold::{StarCells, OwnedStar};
    /// use starplex::cell::CellKind;
    /// let mut s = OwnedStar::default();
    /// s.push(CellKind::Simplex(2), &[0, 1, 2]);
    /// assert!(s.all_of(CellKind::Simplex(2)));
    /// s.push(CellKind::Quad, &[0, 2, 3, 4]);
    /// assert!(!s.all_of(CellKind::Simplex(2)));
    /// ```
    fn all_of(&self, kind: CellKind) -> bool {
        (0..self.len()).all(|i| self.cell(i).0 == kind)
    }
}

/// A star held in flat arrays, for callers that gather one from any structure.
///
/// ```
/// use starplex::algo::manifold::{StarCells, OwnedStar};
/// use starplex::cell::CellKind;
/// let mut s = OwnedStar::default();
/// s.push(CellKind::Quad, &[0, 1, 2, 3]);
/// s.push(CellKind::Simplex(2), &[0, 3, 4]);
/// assert_eq!(s.cell(1).1, &[0, 3, 4]);
/// s.clear();
/// assert!(s.is_empty());
/// ```
#[derive(Clone, Debug, Default)]
pub struct OwnedStar {
    kinds: Vec<CellKind>,
    offsets: Vec<usize>,
    verts: Vec<u32>,
}

impl OwnedStar {
    /// Appends a cell.
    ///
    /// ```
    /// # use starplex::algo::manifold::{StarCells, OwnedStar};
    /// # use starplex::cell::CellKind;
    /// let mut s = OwnedStar::default();
    /// s.push(CellKind::Simplex(1), &[4, 7]);
    /// assert_eq!(s.cell(0).0, CellKind::Simplex(1));
    /// ```
    pub fn push(&mut self, kind: CellKind, verts: &[u32]) {
        if self.offsets.is_empty() {
            self.offsets.push(0);
        }
        self.kinds.push(kind);
        self.verts.extend_from_slice(verts);
        self.offsets.push(self.verts.len());
    }
    /// Removes every cell.
    ///
    /// ```
    /// # use starplex::algo::manifold::{StarCells, OwnedStar};
    /// # use starplex::cell::CellKind;
    /// let mut s = OwnedStar::default();
    /// s.push(CellKind::Simplex(1), &[4, 7]);
    /// s.clear();
    /// assert_eq!(s.len(), 0);
    /// ```
    pub fn clear(&mut self) {
        self.kinds.clear();
        self.offsets.clear();
        self.verts.clear();
    }
}

impl StarCells for OwnedStar {
    #[inline]
    fn len(&self) -> usize {
        self.kinds.len()
    }
    #[inline]
    fn cell(&self, i: usize) -> (CellKind, &[u32]) {
        (
            self.kinds[i],
            &self.verts[self.offsets[i]..self.offsets[i + 1]],
        )
    }
}

/// The cells of a star that have one dimension (the local convention on a mixed star).
struct SubStar<'a, S: ?Sized> {
    star: &'a S,
    idx: &'a [usize],
}

impl<S: StarCells + ?Sized> StarCells for SubStar<'_, S> {
    fn len(&self) -> usize {
        self.idx.len()
    }
    fn cell(&self, i: usize) -> (CellKind, &[u32]) {
        self.star.cell(self.idx[i])
    }
}

#[derive(Default)]
pub(crate) struct Scratch {
    tet: tets::TetScratch,
    ew: Vec<(u32, u32)>,
    /// Edge records of the triangles' test (`tris`).
    recs: Vec<u64>,
    faces: Vec<(u128, u32, u32, u32)>,
    wpairs: Vec<(u32, u32, u32)>,
    bedges: Vec<(u32, u32)>,
    parent: Vec<u32>,
    local_uf: Vec<u32>,
    face_bad_w: Vec<u32>,
}

/// The star tests with their reusable buffers: one per thread, no allocation per vertex once
/// the buffers have grown.
///
/// ```
/// use starplex::algo::manifold::{StarTester, OwnedStar, Convention, Manifoldness};
/// use starplex::cell::CellKind;
/// // vertex 0 of two triangles sharing only it (a bow tie), in a 2-complex
/// let mut star = OwnedStar::default();
/// star.push(CellKind::Simplex(2), &[0, 1, 2]);
/// star.push(CellKind::Simplex(2), &[0, 3, 4]);
/// let mut t = StarTester::default();
/// let mut edges = Vec::new();
/// let m = t.test_vertex(0, &star, Convention::Global, 2, &mut edges);
/// assert_eq!(m, Manifoldness::NonManifold);
/// // the edges 0-w (w > 0), each a manifold edge
/// assert_eq!(edges.len(), 4);
/// assert!(edges.iter().all(|&(_, m)| m == Manifoldness::Manifold));
/// ```
#[derive(Default)]
pub struct StarTester {
    s: Scratch,
    groups: Vec<(u32, usize, usize)>,
    idx: Vec<usize>,
    tmp: Vec<(u32, Manifoldness)>,
    by_dim: Vec<(u32, Manifoldness, usize)>,
}

impl StarTester {
    /// Tests vertex `v` whose star (every top cell containing it) is `star`, and every edge
    /// `vw` with `w > v` (pushed to `edges_out` as `(w, answer)`, sorted by `w`), under
    /// `convention`; `complex_dim` is the dimension of the complex (read by
    /// [`Convention::Global`] only).
    ///
    /// ```
    /// use starplex::algo::manifold::{StarTester, OwnedStar, Convention, Manifoldness};
    /// use starplex::cell::CellKind;
    /// // an isolated vertex in a surface
    /// let (star, mut edges) = (OwnedStar::default(), Vec::new());
    /// let mut t = StarTester::default();
    /// assert_eq!(t.test_vertex(7, &star, Convention::Global, 2, &mut edges), Manifoldness::NonManifold);
    /// assert_eq!(t.test_vertex(7, &star, Convention::Local, 2, &mut edges), Manifoldness::Manifold);
    /// ```
    pub fn test_vertex<S: StarCells + ?Sized>(
        &mut self,
        v: u32,
        star: &S,
        convention: Convention,
        complex_dim: usize,
        edges_out: &mut Vec<(u32, Manifoldness)>,
    ) -> Manifoldness {
        match convention {
            Convention::Global => self.test_vertex_global(v, star, complex_dim, true, edges_out),
            Convention::Local => self.test_vertex_local(v, star, edges_out),
        }
    }

    /// The global convention; `fast` allows the tetrahedral and triangular short cuts (equal answers, tested).
    pub(crate) fn test_vertex_global<S: StarCells + ?Sized>(
        &mut self,
        v: u32,
        star: &S,
        d: usize,
        fast: bool,
        edges_out: &mut Vec<(u32, Manifoldness)>,
    ) -> Manifoldness {
        let start = edges_out.len();
        let m = star::star_tests(v, star, d, fast, &mut self.s, &mut self.groups, edges_out);
        let new = &mut edges_out[start..];
        if !new.is_sorted_by_key(|e| e.0) {
            new.sort_unstable_by_key(|e| e.0);
        }
        m
    }

    fn test_vertex_local<S: StarCells + ?Sized>(
        &mut self,
        v: u32,
        star: &S,
        edges_out: &mut Vec<(u32, Manifoldness)>,
    ) -> Manifoldness {
        if star.is_empty() {
            return Manifoldness::Manifold; // a 0-manifold: its link is the empty (-1)-sphere
        }
        let k0 = star.cell(0).0.dim();
        if (1..star.len()).all(|i| star.cell(i).0.dim() == k0) {
            return self.test_vertex_global(v, star, k0, true, edges_out);
        }
        // a mixed star: v is non-manifold; each edge is tested in the cells of its own
        // dimension, and an edge in cells of two dimensions is non-manifold
        let mut dims: Vec<usize> = (0..star.len()).map(|i| star.cell(i).0.dim()).collect();
        dims.sort_unstable();
        dims.dedup();
        self.by_dim.clear();
        for &k in &dims {
            let mut idx = std::mem::take(&mut self.idx);
            idx.clear();
            idx.extend((0..star.len()).filter(|&i| star.cell(i).0.dim() == k));
            let sub = SubStar { star, idx: &idx };
            let mut tmp = std::mem::take(&mut self.tmp);
            tmp.clear();
            star::star_tests(v, &sub, k, true, &mut self.s, &mut self.groups, &mut tmp);
            self.by_dim.extend(tmp.iter().map(|&(w, m)| (w, m, k)));
            self.tmp = tmp;
            self.idx = idx;
        }
        self.by_dim.sort_unstable_by_key(|e| (e.0, e.2));
        let mut i = 0;
        while i < self.by_dim.len() {
            let (w, m, _) = self.by_dim[i];
            let mut j = i + 1;
            while j < self.by_dim.len() && self.by_dim[j].0 == w {
                j += 1;
            }
            edges_out.push((
                w,
                if j - i > 1 {
                    Manifoldness::NonManifold
                } else {
                    m
                },
            ));
            i = j;
        }
        Manifoldness::NonManifold
    }
}

/// The singular simplices of a complex, with ids (sorted).
///
/// ```
/// use starplex::algo::manifold::{singularities, Convention, Singularities};
/// use starplex::topo::naive::VtIndex;
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// // k: the triangles 0-1-2 and 1-3-2, sharing the edge 1-2
/// assert_eq!(singularities(&VtIndex::new(&k), Convention::Global).unwrap(), Singularities::default());
/// ```
///
/// `V` is the vertex id of the answer: [`VertexId`] for a whole complex, a part's own id for
/// [`local_singularities`] (a Stellar leaf answers in tree ids).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Singularities<V = VertexId> {
    /// Non-manifold vertices.
    pub non_manifold_vertices: Vec<V>,
    /// Vertices whose manifoldness is undecided (links of dimension ≥ 3).
    pub unknown_vertices: Vec<V>,
    /// Non-manifold edges (endpoints sorted, in the answer's numbering).
    pub non_manifold_edges: Vec<[V; 2]>,
    /// Undecided edges.
    pub unknown_edges: Vec<[V; 2]>,
}

impl<V: Copy + From<u32>> Singularities<V> {
    /// Files the answers of one vertex's star tests: `v` by its answer `m`, and each edge
    /// `[v, w]` of `edges` (`w` in the same numbering) by its own.
    pub(crate) fn record(&mut self, v: V, m: Manifoldness, edges: &[(u32, Manifoldness)]) {
        match m {
            Manifoldness::Manifold => {}
            Manifoldness::NonManifold => self.non_manifold_vertices.push(v),
            Manifoldness::Unknown => self.unknown_vertices.push(v),
        }
        for &(w, st) in edges {
            match st {
                Manifoldness::Manifold => {}
                Manifoldness::NonManifold => self.non_manifold_edges.push([v, V::from(w)]),
                Manifoldness::Unknown => self.unknown_edges.push([v, V::from(w)]),
            }
        }
    }
}

impl<V> Default for Singularities<V> {
    fn default() -> Self {
        Singularities {
            non_manifold_vertices: Vec::new(),
            unknown_vertices: Vec::new(),
            non_manifold_edges: Vec::new(),
            unknown_edges: Vec::new(),
        }
    }
}

/// Tests whether the pure complex with maximal simplices `maxes` (each of m+1 vertices, sorted,
/// distinct) is an m-sphere or an m-ball: the apex of the cone over it is tested as a vertex of
/// an (m+1)-complex, by the same star tests as everything else.
///
/// ```
/// use starplex::algo::manifold::{sphere_or_ball, Manifoldness};
/// let cycle = [vec![0, 1], vec![1, 2], vec![0, 2]];
/// assert_eq!(sphere_or_ball(&cycle, 1), Manifoldness::Manifold);
/// let claw = [vec![0, 1], vec![0, 2], vec![0, 3]]; // vertex 0 of degree 3
/// assert_eq!(sphere_or_ball(&claw, 1), Manifoldness::NonManifold);
/// assert_eq!(sphere_or_ball(&[vec![4], vec![7]], 0), Manifoldness::Manifold); // two points
/// assert_eq!(sphere_or_ball(&[], -1), Manifoldness::Manifold); // the empty (-1)-sphere
/// ```
pub fn sphere_or_ball(maxes: &[Vec<u32>], m: isize) -> Manifoldness {
    if m < 0 {
        return if maxes.is_empty() {
            Manifoldness::Manifold
        } else {
            Manifoldness::NonManifold
        };
    }
    if maxes.is_empty() || maxes.iter().any(|f| f.len() != m as usize + 1) {
        return Manifoldness::NonManifold;
    }
    let Some(apex) = maxes.iter().flatten().max().and_then(|&x| x.checked_add(1)) else {
        return Manifoldness::NonManifold; // u32::MAX in use: no id left for the apex
    };
    let Some(kind) = CellKind::simplex(m as usize + 1) else {
        return Manifoldness::Unknown;
    };
    let mut star = OwnedStar::default();
    let mut cell = Vec::new();
    for f in maxes {
        cell.clear();
        cell.extend_from_slice(f);
        cell.push(apex);
        star.push(kind, &cell);
    }
    let mut edges = Vec::new();
    StarTester::default().test_vertex(apex, &star, Convention::Global, m as usize + 1, &mut edges)
}

/// Dimension of the highest-dimensional top cell, `None` without top cells.
///
/// ```
/// use starplex::algo::manifold::complex_dim;
/// use starplex::topo::naive::VtIndex;
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// assert_eq!(complex_dim(&VtIndex::new(&k)), Some(2));
/// ```
pub fn complex_dim<S: TopCells + ?Sized>(s: &S) -> Option<usize> {
    (0..s.n_top_cells())
        .map(|c| s.top_cell_kind(CellId(c as u32)).dim())
        .max()
}

fn gather_star<S: TopCells + VertexStar + ?Sized>(
    s: &S,
    v: VertexId,
    cells: &mut Vec<CellId>,
    buf: &mut Vec<VertexId>,
    star: &mut OwnedStar,
) {
    s.vertex_top_cells(v, cells);
    star.clear();
    let mut ids = Vec::new();
    for &c in cells.iter() {
        buf.clear();
        s.top_cell_vertices(c, buf);
        ids.clear();
        ids.extend(buf.iter().map(|x| x.0));
        star.push(s.top_cell_kind(c), &ids);
    }
}

/// Manifoldness of a vertex.
///
/// ```
/// use starplex::algo::manifold::{vertex_manifoldness, Convention, Manifoldness};
/// use starplex::{ids::VertexId, topo::naive::VtIndex};
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// // k: the triangles 0-1-2 and 1-3-2, sharing the edge 1-2
/// let idx = VtIndex::new(&k);
/// assert_eq!(vertex_manifoldness(&idx, VertexId(1), Convention::Global).unwrap(), Manifoldness::Manifold);
/// assert!(vertex_manifoldness(&idx, VertexId(9), Convention::Global).is_err());
/// ```
///
/// # Errors
/// [`QueryError::NotInComplex`] for a vertex out of range.
pub fn vertex_manifoldness<S: TopCells + VertexStar + ?Sized>(
    s: &S,
    v: VertexId,
    convention: Convention,
) -> Result<Manifoldness, QueryError> {
    if v.index() >= s.n_vertices() {
        return Err(QueryError::NotInComplex(vec![v.0]));
    }
    let d = complex_dim(s).unwrap_or(0);
    let mut star = OwnedStar::default();
    gather_star(s, v, &mut Vec::new(), &mut Vec::new(), &mut star);
    let mut edges = Vec::new();
    Ok(StarTester::default().test_vertex(v.0, &star, convention, d, &mut edges))
}

/// Manifoldness of the edge {u, w} (an edge of a top cell's face table).
///
/// ```
/// use starplex::algo::manifold::{edge_manifoldness, Convention, Manifoldness};
/// use starplex::{ids::VertexId, topo::naive::VtIndex};
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// let mut b = ComplexBuilder::new(1).unwrap();
/// for x in 0..5 { b.push_vertex(&[x as f64]).unwrap(); }
/// for c in [2, 3, 4] { b.push_cell(CellKind::Simplex(2), &[0, 1, c]).unwrap(); }
/// let k = b.build(&BuildOptions::default()).unwrap().0;
/// let idx = VtIndex::new(&k);
/// let g = Convention::Global;
/// // Three triangles on the edge 0-1: a "book" with three pages.
/// assert_eq!(edge_manifoldness(&idx, VertexId(0), VertexId(1), g).unwrap(), Manifoldness::NonManifold);
/// assert_eq!(edge_manifoldness(&idx, VertexId(0), VertexId(2), g).unwrap(), Manifoldness::Manifold);
/// assert!(edge_manifoldness(&idx, VertexId(2), VertexId(3), g).is_err()); // not an edge
/// ```
///
/// # Errors
/// [`QueryError::NotInComplex`] when {u, w} is not an edge of the complex.
pub fn edge_manifoldness<S: TopCells + VertexStar + ?Sized>(
    s: &S,
    u: VertexId,
    w: VertexId,
    convention: Convention,
) -> Result<Manifoldness, QueryError> {
    if u.index() >= s.n_vertices() || w.index() >= s.n_vertices() || u == w {
        return Err(QueryError::NotInComplex(vec![u.0, w.0]));
    }
    let (a, b) = (u.min(w), u.max(w));
    let d = complex_dim(s).unwrap_or(0);
    let mut star = OwnedStar::default();
    gather_star(s, a, &mut Vec::new(), &mut Vec::new(), &mut star);
    let mut edges = Vec::new();
    StarTester::default().test_vertex(a.0, &star, convention, d, &mut edges);
    edges
        .iter()
        .find(|e| e.0 == b.0)
        .map(|e| e.1)
        .ok_or(QueryError::NotInComplex(vec![u.0, w.0]))
}

/// Every non-manifold (and undecided) vertex and edge under `convention`; each edge is tested
/// once, from its smaller endpoint while that vertex's star is in hand.
///
/// ```
/// use starplex::algo::manifold::{singularities, Convention};
/// use starplex::{ids::VertexId, topo::naive::VtIndex};
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// let mut b = ComplexBuilder::new(1).unwrap();
/// for x in 0..5 { b.push_vertex(&[x as f64]).unwrap(); }
/// for c in [2, 3, 4] { b.push_cell(CellKind::Simplex(2), &[0, 1, c]).unwrap(); }
/// let k = b.build(&BuildOptions::default()).unwrap().0;
/// let r = singularities(&VtIndex::new(&k), Convention::Global).unwrap();
/// assert_eq!(r.non_manifold_edges, vec![[VertexId(0), VertexId(1)]]);
/// assert_eq!(r.non_manifold_vertices, vec![VertexId(0), VertexId(1)]);
/// ```
///
/// # Errors
/// None today (the result type leaves room for structures that refuse a query).
pub fn singularities<S: TopCells + VertexStar + ?Sized>(
    s: &S,
    convention: Convention,
) -> Result<Singularities, QueryError> {
    singularities_in_dim(s, convention, complex_dim(s).unwrap_or(0))
}

/// [`singularities`] with the dimension `d` of the complex given: for a part of a larger
/// complex (one rank of `starplex-mpi`) whose own top cells may all be of lower dimension.
///
/// ```
/// use starplex::algo::manifold::{singularities, singularities_in_dim, Convention};
/// use starplex::{ids::VertexId, topo::naive::VtIndex};
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// let mut b = ComplexBuilder::new(1).unwrap();
/// for x in 0..3 { b.push_vertex(&[x as f64]).unwrap(); }
/// b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// let k = b.build(&BuildOptions::default()).unwrap().0;
/// let idx = VtIndex::new(&k);
/// assert_eq!(singularities_in_dim(&idx, Convention::Global, 2).unwrap(), singularities(&idx, Convention::Global).unwrap());
/// ```
///
/// # Errors
/// As [`singularities`].
pub fn singularities_in_dim<S: TopCells + VertexStar + ?Sized>(
    s: &S,
    convention: Convention,
    d: usize,
) -> Result<Singularities, QueryError> {
    let mut r = Singularities::default();
    let (mut cells, mut buf, mut star) = (Vec::new(), Vec::new(), OwnedStar::default());
    let mut t = StarTester::default();
    let mut edges = Vec::new();
    for v in 0..s.n_vertices() {
        let v = VertexId(v as u32);
        gather_star(s, v, &mut cells, &mut buf, &mut star);
        edges.clear();
        match t.test_vertex(v.0, &star, convention, d, &mut edges) {
            Manifoldness::NonManifold => r.non_manifold_vertices.push(v),
            Manifoldness::Unknown => r.unknown_vertices.push(v),
            Manifoldness::Manifold => {}
        }
        for &(w, m) in &edges {
            match m {
                Manifoldness::NonManifold => r.non_manifold_edges.push([v, VertexId(w)]),
                Manifoldness::Unknown => r.unknown_edges.push([v, VertexId(w)]),
                Manifoldness::Manifold => {}
            }
        }
    }
    Ok(r)
}

/// The non-manifold (and undecided) vertices a part owns and the edges it owns (an edge
/// belongs to the part owning its endpoint of smaller id), in the part's own numbering, under
/// `convention`, for a part of a complex of dimension `d`. One definition for every part: a
/// Stellar tree runs it leaf by leaf ([`StellarTree::validate`](crate::stellar::StellarTree::validate)),
/// and on a whole complex it equals [`singularities_in_dim`].
///
/// ```
/// use starplex::algo::manifold::{local_singularities, singularities, Convention};
/// use starplex::topo::naive::VtIndex;
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// let mut b = ComplexBuilder::new(1).unwrap();
/// for x in 0..5 { b.push_vertex(&[x as f64]).unwrap(); }
/// for c in [2, 3, 4] { b.push_cell(CellKind::Simplex(2), &[0, 1, c]).unwrap(); }
/// let k = b.build(&BuildOptions::default()).unwrap().0;
/// let idx = VtIndex::new(&k);
/// let whole = local_singularities(&idx, Convention::Global, 2);
/// assert_eq!(whole, singularities(&idx, Convention::Global).unwrap());
/// ```
pub fn local_singularities<P: LocalStar + ?Sized>(
    part: &P,
    convention: Convention,
    d: usize,
) -> Singularities<P::Vertex> {
    scan_part(part, |t, v, star, edges| {
        t.test_vertex(v, star, convention, d, edges)
    })
}

/// [`local_singularities`] under the global convention, with the tetrahedral and triangular
/// short cuts allowed or not (`fast`; the answers are equal, which the Stellar tests check).
pub(crate) fn local_singularities_global<P: LocalStar + ?Sized>(
    part: &P,
    d: usize,
    fast: bool,
) -> Singularities<P::Vertex> {
    scan_part(part, |t, v, star, edges| {
        t.test_vertex_global(v, star, d, fast, edges)
    })
}

fn scan_part<P: LocalStar + ?Sized>(
    part: &P,
    mut test: impl FnMut(
        &mut StarTester,
        u32,
        &PartStar<'_, P>,
        &mut Vec<(u32, Manifoldness)>,
    ) -> Manifoldness,
) -> Singularities<P::Vertex> {
    let mut r = Singularities::default();
    let mut tester = StarTester::default();
    let mut edges = Vec::new();
    for v in part.owned_vertices() {
        let star = PartStar {
            part,
            star: part.local_star(v),
        };
        edges.clear();
        let m = test(&mut tester, v.into(), &star, &mut edges);
        r.record(v, m, &edges);
    }
    r
}
