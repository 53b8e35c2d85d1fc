//! Cell kinds: simplices of any dimension (0..=[`MAX_SIMPLEX_DIM`]) and the CP cells quad,
//! pyramid, prism (VTK wedge) and hexahedron, in VTK vertex order.
//!
//! For every kind: its faces of every dimension as lists of local vertex positions, a canonical
//! key for a face (its sorted global vertex ids: a face shared by two cells gets the same key from
//! both, whatever the cells' vertex orders), and the induced (outward) orientation of its facets.
//!
//! ```
//! use starplex::cell::CellKind;
//! let hex = CellKind::Hex;
//! assert_eq!(hex.n_vertices(), 8);
//! assert_eq!(hex.n_faces(1), 12);       // edges
//! assert_eq!(hex.n_faces(2), 6);        // quads
//! let tet = CellKind::simplex(3).unwrap();
//! assert_eq!(tet.type_name(), "tet");
//! assert_eq!(tet.n_faces(1), 6);
//! let mut n = 0;
//! tet.for_each_face(2, |f| { assert_eq!(f.len(), 3); n += 1; });
//! assert_eq!(n, 4);
//! ```
use std::fmt;

/// Largest simplex dimension a cell may have (a 64-simplex has 65 vertices).
///
/// ```
/// use starplex::cell::{CellKind, MAX_SIMPLEX_DIM};
/// assert_eq!(CellKind::simplex(MAX_SIMPLEX_DIM).unwrap().n_vertices(), 65);
/// assert!(CellKind::simplex(MAX_SIMPLEX_DIM + 1).is_none());
/// ```
pub const MAX_SIMPLEX_DIM: usize = 64;

/// The kind of a top cell.
///
/// ```
/// use starplex::cell::CellKind;
/// let prism = CellKind::Prism;
/// assert_eq!((prism.dim(), prism.n_vertices()), (3, 6));
/// assert_eq!(prism.n_faces(2), 5); // 2 triangles + 3 quads
/// assert!(CellKind::Simplex(2) < CellKind::Quad);
/// ```
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug, PartialOrd, Ord)]
pub enum CellKind {
    /// A simplex of the given dimension (0 = vertex, 1 = edge, 2 = triangle, 3 = tetrahedron ...).
    Simplex(u8),
    /// A quadrilateral, vertices cyclic 0-1-2-3.
    Quad,
    /// A pyramid: base quad 0-1-2-3 (cyclic), apex 4.
    Pyramid,
    /// A prism (VTK wedge): triangles 0-1-2 and 3-4-5, lateral edges 0-3, 1-4, 2-5.
    Prism,
    /// A hexahedron: bottom 0-1-2-3, top 4-5-6-7, vertical edges 0-4, 1-5, 2-6, 3-7.
    Hex,
}

/// Why a cell kind could not be made.
///
/// ```
/// use starplex::cell::{CellKind, CellKindError};
/// assert_eq!(CellKind::from_spx("cube", 8), Err(CellKindError::UnknownType("cube".into())));
/// let err = CellKind::from_spx("tri", 4).unwrap_err();
/// assert_eq!(err.to_string(), "a tri has 3 vertices, not 4");
/// ```
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum CellKindError {
    /// Simplex dimension above [`MAX_SIMPLEX_DIM`].
    #[error("simplex dimension {0} is above the supported maximum {MAX_SIMPLEX_DIM}")]
    DimensionTooHigh(usize),
    /// A type name that is not known.
    #[error(
        "unknown cell type '{0}' (expected line, tri, quad, tet, pyramid, prism, hex or simplex)"
    )]
    UnknownType(String),
    /// A type name with a vertex count that does not fit it.
    #[error("a {kind} has {expected} vertices, not {got}")]
    WrongCount {
        /// The type.
        kind: String,
        /// Its vertex count.
        expected: usize,
        /// The count given.
        got: usize,
    },
}

// ---- VTK-order face tables of the CP cells (facets oriented outward for a positive cell).
const QUAD_EDGES: &[&[u8]] = &[&[0, 1], &[1, 2], &[2, 3], &[3, 0]];
const PYRAMID_EDGES: &[&[u8]] = &[
    &[0, 1],
    &[1, 2],
    &[2, 3],
    &[3, 0],
    &[0, 4],
    &[1, 4],
    &[2, 4],
    &[3, 4],
];
const PYRAMID_FACES: &[&[u8]] = &[
    &[0, 3, 2, 1],
    &[0, 1, 4],
    &[1, 2, 4],
    &[2, 3, 4],
    &[3, 0, 4],
];
const PRISM_EDGES: &[&[u8]] = &[
    &[0, 1],
    &[1, 2],
    &[2, 0],
    &[3, 4],
    &[4, 5],
    &[5, 3],
    &[0, 3],
    &[1, 4],
    &[2, 5],
];
const PRISM_FACES: &[&[u8]] = &[
    &[0, 1, 2],
    &[3, 5, 4],
    &[0, 3, 4, 1],
    &[1, 4, 5, 2],
    &[2, 5, 3, 0],
];
const HEX_EDGES: &[&[u8]] = &[
    &[0, 1],
    &[1, 2],
    &[2, 3],
    &[3, 0],
    &[4, 5],
    &[5, 6],
    &[6, 7],
    &[7, 4],
    &[0, 4],
    &[1, 5],
    &[2, 6],
    &[3, 7],
];
const HEX_FACES: &[&[u8]] = &[
    &[0, 3, 2, 1],
    &[4, 5, 6, 7],
    &[0, 1, 5, 4],
    &[1, 2, 6, 5],
    &[2, 3, 7, 6],
    &[3, 0, 4, 7],
];
const VERTS: [&[u8]; 8] = [&[0], &[1], &[2], &[3], &[4], &[5], &[6], &[7]];
const ALL: [u8; 8] = [0, 1, 2, 3, 4, 5, 6, 7];

impl CellKind {
    /// A simplex of dimension `dim`, or `None` above [`MAX_SIMPLEX_DIM`].
    ///
    /// ```
    /// use starplex::cell::CellKind;
    /// assert_eq!(CellKind::simplex(3), Some(CellKind::Simplex(3)));
    /// assert_eq!(CellKind::simplex(65), None);
    /// ```
    pub fn simplex(dim: usize) -> Option<CellKind> {
        (dim <= MAX_SIMPLEX_DIM).then_some(CellKind::Simplex(dim as u8))
    }

    /// The kind named by a `.spx` type and vertex count (`line 2`, `tri 3`, `simplex 6`, ...).
    ///
    /// ```
    /// use starplex::cell::{CellKind, CellKindError};
    /// assert_eq!(CellKind::from_spx("tet", 4), Ok(CellKind::Simplex(3)));
    /// assert_eq!(CellKind::from_spx("simplex", 6), Ok(CellKind::Simplex(5)));
    /// assert_eq!(CellKind::from_spx("simplex", 70), Err(CellKindError::DimensionTooHigh(69)));
    /// assert!(CellKind::from_spx("hex", 6).is_err());
    /// ```
    ///
    /// # Errors
    /// Unknown names, counts that do not fit the name, simplices above the maximum dimension.
    pub fn from_spx(name: &str, k: usize) -> Result<CellKind, CellKindError> {
        let fixed = |kind: CellKind| {
            if kind.n_vertices() == k {
                Ok(kind)
            } else {
                Err(CellKindError::WrongCount {
                    kind: name.to_string(),
                    expected: kind.n_vertices(),
                    got: k,
                })
            }
        };
        match name {
            "line" => fixed(CellKind::Simplex(1)),
            "tri" => fixed(CellKind::Simplex(2)),
            "tet" => fixed(CellKind::Simplex(3)),
            "quad" => fixed(CellKind::Quad),
            "pyramid" => fixed(CellKind::Pyramid),
            "prism" => fixed(CellKind::Prism),
            "hex" => fixed(CellKind::Hex),
            "simplex" | "vertex" | "point" => {
                if k == 0 {
                    return Err(CellKindError::WrongCount {
                        kind: name.to_string(),
                        expected: 1,
                        got: 0,
                    });
                }
                CellKind::simplex(k - 1).ok_or(CellKindError::DimensionTooHigh(k - 1))
            }
            _ => Err(CellKindError::UnknownType(name.to_string())),
        }
    }

    /// The kind named as in the oracle files and `starplex info --json`: `vertex`, `line`, `tri`,
    /// `tet`, `simplex_k` (k = dimension, k >= 4), `quad`, `pyramid`, `prism`, `hex`.
    ///
    /// ```
    /// use starplex::cell::CellKind;
    /// assert_eq!(CellKind::from_type_name("pyramid"), Some(CellKind::Pyramid));
    /// assert_eq!(CellKind::from_type_name("simplex_5"), Some(CellKind::Simplex(5)));
    /// assert_eq!(CellKind::from_type_name("octahedron"), None);
    /// ```
    pub fn from_type_name(name: &str) -> Option<CellKind> {
        Some(match name {
            "vertex" => CellKind::Simplex(0),
            "line" => CellKind::Simplex(1),
            "tri" => CellKind::Simplex(2),
            "tet" => CellKind::Simplex(3),
            "quad" => CellKind::Quad,
            "pyramid" => CellKind::Pyramid,
            "prism" => CellKind::Prism,
            "hex" => CellKind::Hex,
            _ => {
                let d: usize = name.strip_prefix("simplex_")?.parse().ok()?;
                CellKind::simplex(d)?
            }
        })
    }

    /// Name used in JSON output and the oracles (see [`CellKind::from_type_name`]).
    ///
    /// ```
    /// use starplex::cell::CellKind;
    /// assert_eq!(CellKind::Simplex(0).type_name(), "vertex");
    /// assert_eq!(CellKind::Simplex(4).type_name(), "simplex_4");
    /// for k in [CellKind::Simplex(7), CellKind::Hex, CellKind::Simplex(2)] {
    ///     assert_eq!(CellKind::from_type_name(&k.type_name()), Some(k));
    /// }
    /// ```
    pub fn type_name(self) -> String {
        match self {
            CellKind::Simplex(0) => "vertex".into(),
            CellKind::Simplex(1) => "line".into(),
            CellKind::Simplex(2) => "tri".into(),
            CellKind::Simplex(3) => "tet".into(),
            CellKind::Simplex(d) => format!("simplex_{d}"),
            CellKind::Quad => "quad".into(),
            CellKind::Pyramid => "pyramid".into(),
            CellKind::Prism => "prism".into(),
            CellKind::Hex => "hex".into(),
        }
    }

    /// Name used in `.spx` files (`simplex` for dimension 0 and >= 4).
    ///
    /// ```
    /// use starplex::cell::CellKind;
    /// assert_eq!(CellKind::Simplex(2).spx_name(), "tri");
    /// assert_eq!(CellKind::Simplex(4).spx_name(), "simplex");
    /// let k = CellKind::Simplex(4);
    /// assert_eq!(CellKind::from_spx(k.spx_name(), k.n_vertices()), Ok(k));
    /// ```
    pub fn spx_name(self) -> &'static str {
        match self {
            CellKind::Simplex(1) => "line",
            CellKind::Simplex(2) => "tri",
            CellKind::Simplex(3) => "tet",
            CellKind::Simplex(_) => "simplex",
            CellKind::Quad => "quad",
            CellKind::Pyramid => "pyramid",
            CellKind::Prism => "prism",
            CellKind::Hex => "hex",
        }
    }

    /// Number of vertices.
    ///
    /// ```
    /// use starplex::cell::CellKind;
    /// assert_eq!(CellKind::Simplex(3).n_vertices(), 4);
    /// assert_eq!(CellKind::Pyramid.n_vertices(), 5);
    /// assert_eq!(CellKind::Hex.n_vertices(), 8);
    /// ```
    #[inline]
    pub fn n_vertices(self) -> usize {
        match self {
            CellKind::Simplex(d) => d as usize + 1,
            CellKind::Quad => 4,
            CellKind::Pyramid => 5,
            CellKind::Prism => 6,
            CellKind::Hex => 8,
        }
    }

    /// Dimension of the cell.
    ///
    /// ```
    /// use starplex::cell::CellKind;
    /// assert_eq!(CellKind::Simplex(0).dim(), 0);
    /// assert_eq!(CellKind::Quad.dim(), 2);
    /// assert_eq!(CellKind::Pyramid.dim(), 3);
    /// ```
    #[inline]
    pub fn dim(self) -> usize {
        match self {
            CellKind::Simplex(d) => d as usize,
            CellKind::Quad => 2,
            CellKind::Pyramid | CellKind::Prism | CellKind::Hex => 3,
        }
    }

    /// True for simplices.
    ///
    /// ```
    /// use starplex::cell::CellKind;
    /// assert!(CellKind::Simplex(1).is_simplex());
    /// assert!(!CellKind::Quad.is_simplex());
    /// ```
    #[inline]
    pub fn is_simplex(self) -> bool {
        matches!(self, CellKind::Simplex(_))
    }

    /// The face table of a CP cell for dimension `k` (`None` for simplices, whose faces are all
    /// subsets and are generated, and for `k` above the cell's dimension).
    ///
    /// ```
    /// use starplex::cell::CellKind;
    /// let quads = CellKind::Quad.cp_faces(1).unwrap();
    /// assert_eq!(quads, &[&[0u8, 1][..], &[1, 2], &[2, 3], &[3, 0]][..]);
    /// assert_eq!(CellKind::Hex.cp_faces(2).unwrap().len(), 6);
    /// assert!(CellKind::Simplex(3).cp_faces(1).is_none());
    /// assert!(CellKind::Quad.cp_faces(3).is_none());
    /// ```
    pub fn cp_faces(self, k: usize) -> Option<&'static [&'static [u8]]> {
        let n = self.n_vertices();
        let table: &'static [&'static [u8]] = match (self, k) {
            (CellKind::Simplex(_), _) => return None,
            (_, 0) => &VERTS[..n],
            (CellKind::Quad, 1) => QUAD_EDGES,
            (CellKind::Pyramid, 1) => PYRAMID_EDGES,
            (CellKind::Prism, 1) => PRISM_EDGES,
            (CellKind::Hex, 1) => HEX_EDGES,
            (CellKind::Pyramid, 2) => PYRAMID_FACES,
            (CellKind::Prism, 2) => PRISM_FACES,
            (CellKind::Hex, 2) => HEX_FACES,
            (CellKind::Quad, 2) => &[&[0, 1, 2, 3]],
            (CellKind::Pyramid, 3) => &[&[0, 1, 2, 3, 4]],
            (CellKind::Prism, 3) => &[&[0, 1, 2, 3, 4, 5]],
            (CellKind::Hex, 3) => &[&ALL],
            _ => return None,
        };
        Some(table)
    }

    /// Number of `k`-faces (the cell itself for `k == dim`; 0 above). Saturates at `u128::MAX`
    /// never: a 64-simplex has at most 2^65 faces, which fits.
    ///
    /// ```
    /// use starplex::cell::CellKind;
    /// let tet = CellKind::Simplex(3);
    /// assert_eq!((0..=3).map(|k| tet.n_faces(k)).collect::<Vec<_>>(), [4, 6, 4, 1]);
    /// assert_eq!(tet.n_faces(4), 0);
    /// assert_eq!(CellKind::Pyramid.n_faces(1), 8);
    /// ```
    pub fn n_faces(self, k: usize) -> u128 {
        match self {
            CellKind::Simplex(d) => binomial(d as u64 + 1, k as u64 + 1),
            _ => self.cp_faces(k).map_or(0, |t| t.len() as u128),
        }
    }

    /// Calls `f` with the local vertex positions of every `k`-face, in a fixed order (for
    /// simplices: lexicographic subsets; for CP cells: the VTK tables). Facets of CP cells come
    /// in outward orientation; faces of simplices in increasing local order.
    ///
    /// ```
    /// use starplex::cell::CellKind;
    /// let mut edges = Vec::new();
    /// CellKind::Simplex(2).for_each_face(1, |f| edges.push(f.to_vec()));
    /// assert_eq!(edges, [[0, 1], [0, 2], [1, 2]]);
    /// let mut quads = 0;
    /// CellKind::Prism.for_each_face(2, |f| quads += (f.len() == 4) as usize);
    /// assert_eq!(quads, 3);
    /// ```
    pub fn for_each_face(self, k: usize, f: impl FnMut(&[u8])) {
        faces_of(self, k, f)
    }

    /// The facets ((dim-1)-faces) with their induced orientation: `f(local_vertices, sign)`
    /// where `sign` is +1 or -1 relative to the listed vertex order (for simplices, facet `i`
    /// omits vertex `i` and has sign (-1)^i, the boundary operator; for CP cells the table
    /// order is already outward and the sign is +1).
    ///
    /// ```
    /// use starplex::cell::CellKind;
    /// let mut facets = Vec::new();
    /// CellKind::Simplex(2).for_each_oriented_facet(|f, s| facets.push((f.to_vec(), s)));
    /// assert_eq!(facets, [(vec![1, 2], 1), (vec![0, 2], -1), (vec![0, 1], 1)]);
    /// let mut n = 0;
    /// CellKind::Hex.for_each_oriented_facet(|f, s| { assert_eq!((f.len(), s), (4, 1)); n += 1; });
    /// assert_eq!(n, 6);
    /// ```
    pub fn for_each_oriented_facet(self, f: impl FnMut(&[u8], i8)) {
        oriented_facets_of(self, f)
    }

    /// Whether the sorted global vertex set `face` is a face of a cell of this kind with global
    /// vertices `cell` (any dimension, including the cell itself). For simplices this is the
    /// subset test; for CP cells the vertex set must be one of the table's faces (two diagonal
    /// corners of a quad are not an edge).
    ///
    /// ```
    /// use starplex::cell::CellKind;
    /// let quad = [10, 11, 12, 13];
    /// assert!(CellKind::Quad.has_face(&quad, &[11, 12]));  // an edge
    /// assert!(!CellKind::Quad.has_face(&quad, &[10, 12])); // a diagonal is not
    /// assert!(CellKind::Simplex(2).has_face(&[10, 11, 12], &[10, 12]));
    /// assert!(!CellKind::Quad.has_face(&quad, &[9]));
    /// ```
    pub fn has_face(self, cell: &[u32], face: &[u32]) -> bool {
        debug_assert!(face.windows(2).all(|w| w[0] < w[1]));
        if face.len() > cell.len() || face.is_empty() {
            return false;
        }
        if !face.iter().all(|v| cell.contains(v)) {
            return false;
        }
        if self.is_simplex() || face.len() == 1 || face.len() == cell.len() {
            return true;
        }
        // CP: the set must be a listed face of matching size.
        let k = match face.len() {
            2 => 1,
            3 | 4 => 2,
            _ => return false,
        };
        let Some(t) = self.cp_faces(k) else {
            return false;
        };
        t.iter().any(|lf| {
            lf.len() == face.len()
                && lf
                    .iter()
                    .all(|&l| face.binary_search(&cell[l as usize]).is_ok())
        })
    }
}

/// The faces of dimension `p` of a cell of this kind, as local vertex indices, without a heap
/// allocation (what [`CellKind::for_each_face`] calls).
#[inline]
pub(crate) fn faces_of(kind: CellKind, p: usize, mut f: impl FnMut(&[u8])) {
    match kind {
        CellKind::Simplex(d) => {
            let n = d as usize + 1;
            if p + 1 > n {
                return;
            }
            let mut idx = [0u8; 66];
            for (i, x) in idx.iter_mut().enumerate().take(p + 1) {
                *x = i as u8;
            }
            loop {
                f(&idx[..=p]);
                let mut i = p as isize;
                while i >= 0 && idx[i as usize] as usize == n - (p + 1) + i as usize {
                    i -= 1;
                }
                if i < 0 {
                    return;
                }
                let i = i as usize;
                idx[i] += 1;
                for j in i + 1..=p {
                    idx[j] = idx[j - 1] + 1;
                }
            }
        }
        _ => {
            if let Some(t) = kind.cp_faces(p) {
                t.iter().for_each(|face| f(face));
            }
        }
    }
}

/// The facets with their induced orientation, without a heap allocation (what
/// [`CellKind::for_each_oriented_facet`] calls).
#[inline]
pub(crate) fn oriented_facets_of(kind: CellKind, mut f: impl FnMut(&[u8], i8)) {
    match kind {
        CellKind::Simplex(0) => {}
        CellKind::Simplex(d) => {
            let n = d as usize + 1;
            let mut buf = [0u8; 66];
            for i in 0..n {
                let mut m = 0;
                for j in 0..n {
                    if j != i {
                        buf[m] = j as u8;
                        m += 1;
                    }
                }
                f(&buf[..n - 1], if i % 2 == 0 { 1 } else { -1 });
            }
        }
        _ => {
            if let Some(t) = kind.cp_faces(kind.dim() - 1) {
                t.iter().for_each(|face| f(face, 1));
            }
        }
    }
}

/// Induced orientation of facet `j` (the one omitting listed vertex `j`) of the simplex with
/// listed vertices `vs` (at most 8), against the facet's sorted vertices: `(-1)^j` (see
/// [`oriented_facets_of`]) times the parity of the vertices it keeps ([`listed_sign`]).
#[inline]
pub(crate) fn simplex_facet_sign(vs: &[u32], j: usize) -> i8 {
    let mut kept = [0u32; 8];
    let mut m = 0;
    for (x, &w) in vs.iter().enumerate() {
        if x != j {
            kept[m] = w;
            m += 1;
        }
    }
    let s = listed_sign(&kept[..m], false);
    if j.is_multiple_of(2) {
        s
    } else {
        -s
    }
}

/// Orientation of a listed facet relative to its sorted order: the parity of the sorting
/// permutation, or for a polygon (CP facet) the cyclic direction.
pub(crate) fn listed_sign(key: &[u32], polygon: bool) -> i8 {
    let n = key.len();
    if polygon {
        let i = (0..n).min_by_key(|&i| key[i]).expect("non-empty");
        let next = key[(i + 1) % n];
        let prev = key[(i + n - 1) % n];
        return if next < prev { 1 } else { -1 };
    }
    let mut inv = 0usize;
    for i in 0..n {
        for j in i + 1..n {
            if key[i] > key[j] {
                inv += 1;
            }
        }
    }
    if inv.is_multiple_of(2) {
        1
    } else {
        -1
    }
}

impl fmt::Display for CellKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.type_name())
    }
}

/// Writes the canonical key of a face into `out`: the global vertex ids of `local` positions of
/// `cell`, sorted. Two cells sharing a face produce the same key.
///
/// ```
/// use starplex::cell::canonical_key;
/// let (mut a, mut b) = (Vec::new(), Vec::new());
/// canonical_key(&[10, 11, 12, 13], &[1, 2], &mut a);  // edge 11-12 of one quad
/// canonical_key(&[12, 11, 20, 21], &[0, 1], &mut b);  // the same edge, seen from its neighbour
/// assert_eq!(a, b);
/// assert_eq!(a, vec![11, 12]);
/// ```
pub fn canonical_key(cell: &[u32], local: &[u8], out: &mut Vec<u32>) {
    out.clear();
    out.extend(local.iter().map(|&l| cell[l as usize]));
    out.sort_unstable();
}

/// Binomial coefficient C(n, k) in `u128` (exact up to n = 128, saturating beyond).
///
/// ```
/// assert_eq!(starplex::cell::binomial(65, 33), 3609714217008132870);
/// assert_eq!(starplex::cell::binomial(3, 5), 0);
/// ```
pub fn binomial(n: u64, k: u64) -> u128 {
    if k > n {
        return 0;
    }
    let k = k.min(n - k);
    let mut r: u128 = 1;
    for i in 0..k {
        r = match r.checked_mul((n - i) as u128) {
            Some(x) => x / (i as u128 + 1),
            None => return u128::MAX,
        };
    }
    r
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn simplex_faces_are_all_subsets() {
        for d in 0..8usize {
            let kind = CellKind::simplex(d).unwrap();
            for k in 0..=d + 1 {
                let mut seen = std::collections::BTreeSet::new();
                kind.for_each_face(k, |f| {
                    assert_eq!(f.len(), k + 1);
                    assert!(f.windows(2).all(|w| w[0] < w[1]));
                    seen.insert(f.to_vec());
                });
                assert_eq!(seen.len() as u128, kind.n_faces(k), "d={d} k={k}");
            }
        }
    }

    #[test]
    fn cp_tables_are_consistent() {
        // Every edge of a 2-face is an edge of the cell; every vertex appears in some edge;
        // Euler characteristic of the boundary of a 3-cell is 2.
        for kind in [CellKind::Pyramid, CellKind::Prism, CellKind::Hex] {
            let e = kind.cp_faces(1).unwrap();
            let f = kind.cp_faces(2).unwrap();
            let nv = kind.n_vertices() as i64;
            assert_eq!(nv - e.len() as i64 + f.len() as i64, 2, "{kind}");
            for face in f {
                for i in 0..face.len() {
                    let (a, b) = (face[i], face[(i + 1) % face.len()]);
                    assert!(
                        e.iter()
                            .any(|x| (x[0] == a && x[1] == b) || (x[0] == b && x[1] == a)),
                        "{kind}: face edge {a}-{b} missing"
                    );
                }
            }
            // Outward orientation: every edge is used once in each direction by the facets.
            for edge in e {
                let (a, b) = (edge[0], edge[1]);
                let mut fwd = 0;
                let mut bwd = 0;
                for face in f {
                    for i in 0..face.len() {
                        let (x, y) = (face[i], face[(i + 1) % face.len()]);
                        fwd += (x == a && y == b) as i32;
                        bwd += (x == b && y == a) as i32;
                    }
                }
                assert_eq!((fwd, bwd), (1, 1), "{kind} edge {a}-{b}");
            }
        }
    }

    #[test]
    fn has_face_rejects_quad_diagonal() {
        let q = [5, 6, 7, 8];
        assert!(CellKind::Quad.has_face(&q, &[5, 6]));
        assert!(!CellKind::Quad.has_face(&q, &[5, 7]));
        assert!(CellKind::Hex.has_face(&[0, 1, 2, 3, 4, 5, 6, 7], &[0, 1, 4, 5]));
        assert!(!CellKind::Hex.has_face(&[0, 1, 2, 3, 4, 5, 6, 7], &[0, 1, 2, 4]));
        assert!(CellKind::Simplex(3).has_face(&[9, 3, 4, 1], &[1, 3, 9]));
    }

    #[test]
    fn names_round_trip() {
        for kind in [
            CellKind::Simplex(0),
            CellKind::Simplex(1),
            CellKind::Simplex(2),
            CellKind::Simplex(3),
            CellKind::Simplex(40),
            CellKind::Quad,
            CellKind::Pyramid,
            CellKind::Prism,
            CellKind::Hex,
        ] {
            assert_eq!(CellKind::from_type_name(&kind.type_name()), Some(kind));
            assert_eq!(
                CellKind::from_spx(kind.spx_name(), kind.n_vertices()),
                Ok(kind)
            );
        }
        assert!(CellKind::from_spx("hex", 7).is_err());
        assert!(CellKind::from_spx("simplex", 66).is_err());
    }
}
