//! Boundary p-faces of every dimension (simplices and CP cells) and top-cell adjacency across
//! (d-1)-faces, each face handled in the leaf owning its smallest vertex.
use crate::limits::{Limits, TooLarge, Unit};
use rayon::prelude::*;

use super::{face_width, FaceKeys};
use crate::cell::{faces_of, listed_sign, oriented_facets_of};
use crate::csr::Csr;
use crate::ids::LeafId;
use crate::stellar::{LeafView, StellarError, StellarTree};

/// Default budget of (cell, face) pairs for face extraction.
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
/// use starplex::stellar::relations::FACE_BUDGET;
/// // `p_faces` uses this budget
/// use starplex::limits::Limits;
/// assert_eq!(t.p_faces_with_limits(1, &Limits::default()).unwrap(), t.p_faces(1).unwrap());
/// assert!(t.p_faces_with_limits(1, &Limits { stellar_faces: 1, ..Limits::default() }).is_err());
/// ```
pub const FACE_BUDGET: u128 = crate::limits::STELLAR_FACES;

/// Faces of one dimension: vertex lists (input ids, sorted) and how many top cells contain
/// each face.
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
/// let edges = t.p_faces(1).unwrap();
/// assert_eq!(edges.len(), 5);
/// // the diagonal {1,2} is in both triangles, the other edges in one
/// let i = (0..edges.len()).find(|&i| edges.faces.row(i) == [1, 2]).unwrap();
/// assert_eq!(edges.n_cofaces[i], 2);
/// assert_eq!(edges.n_cofaces.iter().sum::<u32>(), 6);
/// ```
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct FaceList {
    /// Face `i` is `faces.row(i)`.
    pub faces: Csr,
    /// Number of top cells (of any dimension) that contain face `i`.
    pub n_cofaces: Vec<u32>,
}

impl FaceList {
    /// Number of faces.
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
    /// assert_eq!(t.p_faces(0).unwrap().len(), 4);
    /// assert_eq!(t.p_faces(2).unwrap().len(), 2);
    /// ```
    pub fn len(&self) -> usize {
        self.n_cofaces.len()
    }
    /// True without faces.
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
    /// use starplex::stellar::FaceList;
    /// assert!(FaceList::default().is_empty());
    /// assert!(!t.p_faces(1).unwrap().is_empty());
    /// ```
    pub fn is_empty(&self) -> bool {
        self.n_cofaces.is_empty()
    }
}

impl StellarTree {
    /// Upper bound of (cell, p-face) pairs visited by [`p_faces`](Self::p_faces).
    ///
    /// ```
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// # use starplex::ids::{CellId, VertexId};
    /// # use starplex::stellar::{StellarTree, StellarOptions};
    /// # let mut b = ComplexBuilder::new(2).unwrap();
    /// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
    /// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
    /// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// # let t = StellarTree::build(&k, &StellarOptions { kv: Some(1), ..Default::default() }).unwrap();
    /// assert_eq!(t.face_visits(1), 6);
    /// ```
    pub fn face_visits(&self, p: usize) -> u128 {
        if let Some(kind) = self.cells.uniform {
            return kind.n_faces(p).saturating_mul(self.cells.n as u128);
        }
        self.cells
            .kinds
            .iter()
            .map(|&c| crate::stellar::code_kind(c).n_faces(p))
            .fold(0u128, |a, x| a.saturating_add(x))
    }

    fn check_budget(&self, p: usize, budget: u128) -> Result<(), StellarError> {
        let est = self.face_visits(p);
        if est > budget {
            return Err(StellarError::TooLarge(TooLarge::new(
                format!("{p}-faces"),
                est,
                budget,
                Unit::Simplices,
            )));
        }
        Ok(())
    }

    /// Runs `f(view, keys)` for every leaf with the leaf's owned `p`-faces grouped: the
    /// payload of every entry is the tree id of a top cell containing the face.
    fn par_face_groups<R: Send>(
        &self,
        p: usize,
        f: impl Fn(&LeafView<'_>, &mut FaceKeys) -> R + Sync + Send,
    ) -> Vec<R> {
        let w = self
            .kinds()
            .iter()
            .map(|&k| face_width(k, p))
            .max()
            .unwrap_or(1);
        let pool_init = FaceKeys::default;
        (0..self.n_leaves() as u32)
            .into_par_iter()
            .map_init(
                || {
                    (
                        crate::stellar::ExpandedLeaf::default(),
                        pool_init(),
                        Vec::<u32>::new(),
                    )
                },
                |(e, keys, key), l| {
                    self.expand_leaf_cells(LeafId(l), e);
                    keys.clear(w);
                    keys.set_buckets(Some((e.v_start, e.v_end)));
                    let view = LeafView { tree: self, e };
                    for &c in &e.cells {
                        let (kind, vs) = self.cells.get(c);
                        if kind.dim() < p {
                            continue;
                        }
                        faces_of(kind, p, |local| {
                            key.clear();
                            key.extend(local.iter().map(|&i| vs[i as usize]));
                            let m = *key.iter().min().expect("faces have vertices");
                            if view.owns_tree(m) {
                                key.sort_unstable();
                                keys.push(key, c as u64);
                            }
                        });
                    }
                    f(&view, keys)
                },
            )
            .collect()
    }

    /// Expands only the cell list of a leaf (no VT).
    pub(crate) fn expand_leaf_cells(&self, l: LeafId, e: &mut crate::stellar::ExpandedLeaf) {
        let r = self.leaf_vertices(l);
        e.leaf = l;
        e.v_start = r.start;
        e.v_end = r.end;
        e.cells.clear();
        crate::stellar::sre::decode(self.leaf_encoded_cells(l), &mut e.cells);
        e.vt_off.clear();
        e.vt.clear();
    }

    /// Every `p`-face (p >= 0) of the complex once, with its number of top cofaces, budget
    /// [`FACE_BUDGET`] (cell, face) pairs. Faces of CP cells follow their face tables (the
    /// diagonal of a quad is not an edge). Order: by leaf, then by sorted tree ids.
    ///
    /// # Errors
    /// Over the budget (e.g. the 20-faces of 40-simplices).
    ///
    /// ```
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// # use starplex::ids::{CellId, VertexId};
    /// # use starplex::stellar::{StellarTree, StellarOptions};
    /// # let mut b = ComplexBuilder::new(2).unwrap();
    /// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
    /// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
    /// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// # let t = StellarTree::build(&k, &StellarOptions { kv: Some(1), ..Default::default() }).unwrap();
    /// let e = t.p_faces(1).unwrap();
    /// assert_eq!(e.len(), 5);
    /// assert_eq!(e.n_cofaces.iter().filter(|&&n| n == 2).count(), 1);
    /// ```
    pub fn p_faces(&self, p: usize) -> Result<FaceList, StellarError> {
        self.p_faces_within(p, FACE_BUDGET)
    }

    /// [`p_faces`](Self::p_faces) within the budget `limits.stellar_faces` (the faces the
    /// relation may enumerate).
    ///
    /// # Errors
    /// Over the budget.
    ///
    /// ```
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// # use starplex::ids::{CellId, VertexId};
    /// # use starplex::stellar::{StellarTree, StellarOptions};
    /// # let mut b = ComplexBuilder::new(2).unwrap();
    /// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
    /// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
    /// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// # let t = StellarTree::build(&k, &StellarOptions { kv: Some(1), ..Default::default() }).unwrap();
    /// use starplex::limits::Limits;
    /// assert!(t.p_faces_with_limits(1, &Limits { stellar_faces: 3, ..Limits::default() }).is_err());
    /// ```
    pub fn p_faces_with_limits(&self, p: usize, limits: &Limits) -> Result<FaceList, StellarError> {
        self.p_faces_within(p, limits.stellar_faces)
    }

    fn p_faces_within(&self, p: usize, budget: u128) -> Result<FaceList, StellarError> {
        self.check_budget(p, budget)?;
        let per_leaf: Vec<(Vec<u32>, Vec<u32>, Vec<u32>)> = self.par_face_groups(p, |_, keys| {
            let mut lens = Vec::new();
            let mut verts = Vec::new();
            let mut co = Vec::new();
            keys.for_each_group(|k, pays| {
                lens.push(k.len() as u32);
                let s = verts.len();
                verts.extend(k.iter().map(|&v| self.v_orig[v as usize]));
                verts[s..].sort_unstable();
                co.push(pays.len() as u32);
            });
            (lens, verts, co)
        });
        let mut offsets = vec![0u32];
        let mut targets = Vec::new();
        let mut n_cofaces = Vec::new();
        for (lens, verts, co) in per_leaf {
            for l in lens {
                let last = *offsets.last().expect("non-empty");
                offsets.push(last + l);
            }
            targets.extend_from_slice(&verts);
            n_cofaces.extend_from_slice(&co);
        }
        Ok(FaceList {
            faces: Csr { offsets, targets },
            n_cofaces,
        })
    }

    /// Number of distinct `p`-faces, without materialising them.
    ///
    /// # Errors
    /// Over the budget [`FACE_BUDGET`].
    ///
    /// ```
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// # use starplex::ids::{CellId, VertexId};
    /// # use starplex::stellar::{StellarTree, StellarOptions};
    /// # let mut b = ComplexBuilder::new(2).unwrap();
    /// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
    /// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
    /// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// # let t = StellarTree::build(&k, &StellarOptions { kv: Some(1), ..Default::default() }).unwrap();
    /// assert_eq!(t.count_p_faces(2).unwrap(), 2);
    /// ```
    pub fn count_p_faces(&self, p: usize) -> Result<u64, StellarError> {
        self.check_budget(p, FACE_BUDGET)?;
        if p == 1
            && self
                .cells
                .uniform
                .is_some_and(|k| k.is_simplex() && k.dim() >= 1)
        {
            return Ok(self.count_edges_in_leaves());
        }
        if p == 2
            && self
                .cells
                .uniform
                .is_some_and(|k| k.is_simplex() && k.dim() >= 2)
        {
            if self.n_vertices() <= 1 << 21 {
                return Ok(self.count_triangles_in_leaves());
            }
            return Ok(self.count_triangles_by_stars());
        }
        Ok(self
            .par_face_groups(p, |_, keys| {
                let mut n = 0u64;
                keys.for_each_group(|_, _| n += 1);
                n
            })
            .into_iter()
            .sum())
    }

    /// [`count_p_faces`](Self::count_p_faces)`(1)` for a complex of simplices of one kind:
    /// each leaf counts the edges whose smaller vertex it owns, from its cells alone (no
    /// vertex-to-cell expansion), in a small open-addressing table of 8-byte keys sized for
    /// the leaf and emptied through the list of slots it used. One thread: tri_armadillo_x16
    /// 68 ms with the general face keys, 28 ms with a stamp per vertex over the stars, 21 ms
    /// this way; tet_armadillo_m 121, 39 and 25 ms. (The same table with 16-byte keys for
    /// any face size was slower: 41 and 54 ms for edges, and no faster than
    /// [`count_triangles_by_stars`](Self::count_triangles_by_stars) for triangles.)
    /// [`count_p_faces`](Self::count_p_faces)`(2)` for a complex of simplices of one kind
    /// with at most 2^21 vertices (a triangle's three tree ids fit in one 8-byte key): as
    /// [`count_edges_in_leaves`](Self::count_edges_in_leaves), each leaf hashes the triangles
    /// of its cells whose smallest vertex it owns. tet_armadillo_m, one thread: 57 ms over the
    /// stars ([`count_triangles_by_stars`](Self::count_triangles_by_stars), which larger
    /// complexes still take), 29 ms this way.
    fn count_triangles_in_leaves(&self) -> u64 {
        let stride = self.cells.stride as usize;
        let verts = &self.cells.verts;
        let per_cell = stride * (stride - 1) * (stride - 2) / 6;
        (0..self.n_leaves() as u32)
            .into_par_iter()
            .map_init(
                || {
                    (
                        crate::stellar::ExpandedLeaf::default(),
                        Vec::<u64>::new(),
                        Vec::<u32>::new(),
                    )
                },
                |(e, table, used), l| {
                    self.expand_leaf_cells(LeafId(l), e);
                    let (lo, hi) = (e.v_start, e.v_end);
                    let cap = (2 * e.cells.len() * per_cell).next_power_of_two().max(64);
                    if table.len() < cap {
                        table.clear();
                        table.resize(cap, u64::MAX);
                    }
                    let mask = cap - 1;
                    let shift = 64 - cap.trailing_zeros();
                    used.clear();
                    let mut n = 0u64;
                    for &c in &e.cells {
                        let vs = &verts[c as usize * stride..c as usize * stride + stride];
                        for x in 0..stride {
                            for y in x + 1..stride {
                                for z in y + 1..stride {
                                    let mut t = [vs[x], vs[y], vs[z]];
                                    t = crate::topo::sort3(t);
                                    if t[0] < lo || t[0] >= hi {
                                        continue;
                                    }
                                    let key =
                                        ((t[0] as u64) << 42) | ((t[1] as u64) << 21) | t[2] as u64;
                                    let mut h =
                                        (key.wrapping_mul(0x9E37_79B9_7F4A_7C15) >> shift) as usize;
                                    loop {
                                        let k = table[h];
                                        if k == key {
                                            break;
                                        }
                                        if k == u64::MAX {
                                            table[h] = key;
                                            used.push(h as u32);
                                            n += 1;
                                            break;
                                        }
                                        h = (h + 1) & mask;
                                    }
                                }
                            }
                        }
                    }
                    for &h in used.iter() {
                        table[h as usize] = u64::MAX;
                    }
                    n
                },
            )
            .sum()
    }

    fn count_edges_in_leaves(&self) -> u64 {
        let stride = self.cells.stride as usize;
        let verts = &self.cells.verts;
        (0..self.n_leaves() as u32)
            .into_par_iter()
            .map_init(
                || {
                    (
                        crate::stellar::ExpandedLeaf::default(),
                        Vec::<u64>::new(),
                        Vec::<u32>::new(),
                    )
                },
                |(e, table, used), l| {
                    self.expand_leaf_cells(LeafId(l), e);
                    let (lo, hi) = (e.v_start, e.v_end);
                    let cap = (2 * e.cells.len() * stride * (stride - 1) / 2)
                        .next_power_of_two()
                        .max(64);
                    if table.len() < cap {
                        table.clear();
                        table.resize(cap, u64::MAX);
                    }
                    let mask = cap - 1;
                    let shift = 64 - cap.trailing_zeros();
                    used.clear();
                    let mut n = 0u64;
                    for &c in &e.cells {
                        let vs = &verts[c as usize * stride..c as usize * stride + stride];
                        for (x, &a) in vs.iter().enumerate() {
                            for &b in &vs[x + 1..] {
                                let (a, b) = if a < b { (a, b) } else { (b, a) };
                                if a < lo || a >= hi {
                                    continue;
                                }
                                let key = ((a as u64) << 32) | b as u64;
                                let mut h =
                                    (key.wrapping_mul(0x9E37_79B9_7F4A_7C15) >> shift) as usize;
                                loop {
                                    let k = table[h];
                                    if k == key {
                                        break;
                                    }
                                    if k == u64::MAX {
                                        table[h] = key;
                                        used.push(h as u32);
                                        n += 1;
                                        break;
                                    }
                                    h = (h + 1) & mask;
                                }
                            }
                        }
                    }
                    for &h in used.iter() {
                        table[h as usize] = u64::MAX;
                    }
                    n
                },
            )
            .sum()
    }

    /// [`count_p_faces`](Self::count_p_faces)`(2)` for a complex of simplices of one kind:
    /// a triangle belongs to the leaf of its smallest vertex `v`; the pairs of larger
    /// vertices of each cell of the star of `v` are sorted (a few dozen 8-byte keys) and the
    /// distinct ones counted.
    fn count_triangles_by_stars(&self) -> u64 {
        let stride = self.cells.stride as usize;
        let verts = &self.cells.verts;
        (0..self.n_leaves() as u32)
            .into_par_iter()
            .map_init(
                || (crate::stellar::ExpandedLeaf::default(), Vec::<u64>::new()),
                |(e, keys), l| {
                    self.expand_leaf_into(LeafId(l), e);
                    let mut n = 0u64;
                    for (i, v) in (e.v_start..e.v_end).enumerate() {
                        keys.clear();
                        for &c in &e.vt[e.vt_off[i] as usize..e.vt_off[i + 1] as usize] {
                            let vs = &verts[c as usize * stride..c as usize * stride + stride];
                            for (x, &a) in vs.iter().enumerate() {
                                if a <= v {
                                    continue;
                                }
                                for &b in &vs[x + 1..] {
                                    if b > v {
                                        let (lo, hi) = if a < b { (a, b) } else { (b, a) };
                                        keys.push(((lo as u64) << 32) | hi as u64);
                                    }
                                }
                            }
                        }
                        keys.sort_unstable();
                        n += 1 + keys.windows(2).filter(|w| w[0] != w[1]).count() as u64
                            - keys.is_empty() as u64;
                    }
                    n
                },
            )
            .sum()
    }

    /// Adjacency of top cells across (k-1)-faces (R_{k,k}, k = the cell's dimension >= 1):
    /// row `c` (input id) holds the input ids of the other top k-cells sharing a facet with
    /// `c`, sorted; non-manifold facets (in three or more cells) connect all their cells.
    ///
    /// ```
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// # use starplex::ids::{CellId, VertexId};
    /// # use starplex::stellar::{StellarTree, StellarOptions};
    /// # let mut b = ComplexBuilder::new(2).unwrap();
    /// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
    /// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
    /// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// # let t = StellarTree::build(&k, &StellarOptions { kv: Some(1), ..Default::default() }).unwrap();
    /// assert_eq!(t.top_adjacency().row(1), &[0]);
    /// ```
    pub fn top_adjacency(&self) -> Csr {
        let pairs = self.facet_pairs();
        let n = self.n_top_cells();
        let mut csr = Csr::from_fn(n, |emit| {
            for &(a, b, _) in &pairs {
                emit(self.c_orig[a as usize], self.c_orig[b as usize]);
                emit(self.c_orig[b as usize], self.c_orig[a as usize]);
            }
        });
        for i in 0..n {
            let (s, e) = (csr.offsets[i] as usize, csr.offsets[i + 1] as usize);
            csr.targets[s..e].sort_unstable();
        }
        // dedup rows (two cells may share several facets only in degenerate CP configurations)
        let mut out = Csr {
            offsets: vec![0],
            targets: Vec::with_capacity(csr.targets.len()),
        };
        for i in 0..n {
            let row = csr.row(i);
            for (j, &x) in row.iter().enumerate() {
                if j == 0 || row[j - 1] != x {
                    out.targets.push(x);
                }
            }
            out.offsets.push(out.targets.len() as u32);
        }
        out
    }

    /// All pairs (a, b, relative sign) of tree cells of one dimension sharing a facet; the sign
    /// is the product of the two induced facet orientations (+1: the cells induce the same
    /// orientation on the facet, so they are inconsistently oriented).
    pub(crate) fn facet_pairs(&self) -> Vec<(u32, u32, i8)> {
        let per_leaf = self.par_facet_groups(|_, key_groups| {
            let mut out = Vec::new();
            key_groups.for_each_group(|_, pays| {
                for i in 0..pays.len() {
                    for j in i + 1..pays.len() {
                        let (a, sa) = unpack(pays[i]);
                        let (b, sb) = unpack(pays[j]);
                        out.push((a, b, sa * sb));
                    }
                }
            });
            out
        });
        per_leaf.into_iter().flatten().collect()
    }

    /// Like [`par_face_groups`] for facets: each top k-cell (k >= 1) emits its facets with the
    /// cell dimension as an extra leading key entry; payload = tree cell id | sign bit.
    pub(crate) fn par_facet_groups<R: Send>(
        &self,
        f: impl Fn(&LeafView<'_>, &mut FaceKeys) -> R + Sync + Send,
    ) -> Vec<R> {
        self.par_facet_groups_where(1, false, f)
    }

    /// Facet groups of the cells of dimension >= `min_dim`; with `local`, every facet with a
    /// vertex in the leaf (the local IA* rule) instead of the facets the leaf owns.
    pub(crate) fn par_facet_groups_where<R: Send>(
        &self,
        min_dim: usize,
        local_rule: bool,
        f: impl Fn(&LeafView<'_>, &mut FaceKeys) -> R + Sync + Send,
    ) -> Vec<R> {
        let kinds = self.kinds();
        let fw = kinds
            .iter()
            .map(|&k| {
                if k.dim() >= 1 {
                    face_width(k, k.dim() - 1)
                } else {
                    0
                }
            })
            .max()
            .unwrap_or(0);
        // one dimension: the dimension prefix of the keys is implicit
        let dims: std::collections::BTreeSet<usize> = kinds.iter().map(|k| k.dim()).collect();
        let uniform_dim = (dims.len() == 1).then(|| *dims.first().expect("one") as u32);
        let w = if uniform_dim.is_some() { fw } else { fw + 1 };
        (0..self.n_leaves() as u32)
            .into_par_iter()
            .map_init(
                || {
                    (
                        crate::stellar::ExpandedLeaf::default(),
                        FaceKeys::default(),
                        Vec::<u32>::new(),
                    )
                },
                |(e, keys, key), l| {
                    self.expand_leaf_cells(LeafId(l), e);
                    keys.clear(w);
                    keys.set_prefix(uniform_dim);
                    if uniform_dim.is_some() && !local_rule {
                        keys.set_buckets(Some((e.v_start, e.v_end)));
                    }
                    let view = LeafView { tree: self, e };
                    for &c in &e.cells {
                        let (kind, vs) = self.cells.get(c);
                        let d = kind.dim();
                        if d == 0 || d < min_dim {
                            continue;
                        }
                        if uniform_dim.is_some() && kind.is_simplex() && vs.len() <= SIMPLEX_FAST {
                            simplex_facets(vs, local_rule, &view, |key, j, s| {
                                keys.push(key, pack(c, j, s))
                            });
                            continue;
                        }
                        let mut j = 0u64;
                        oriented_facets_of(kind, |local, sign| {
                            j += 1;
                            key.clear();
                            key.extend(local.iter().map(|&i| vs[i as usize]));
                            let keep = if local_rule {
                                key.iter().any(|&v| view.owns_tree(v))
                            } else {
                                view.owns_tree(*key.iter().min().expect("facets have vertices"))
                            };
                            if !keep {
                                return;
                            }
                            let s = sign * listed_sign(key, !kind.is_simplex() && key.len() >= 3);
                            key.sort_unstable();
                            if uniform_dim.is_none() {
                                key.insert(0, d as u32);
                            }
                            keys.push(key, pack(c, j - 1, s));
                        });
                    }
                    f(&view, keys)
                },
            )
            .collect()
    }
}

/// Most vertices of a simplex whose facets take [`simplex_facets`].
const SIMPLEX_FAST: usize = 8;

/// The facets of a simplex kept by [`StellarTree::par_facet_groups_where`]'s rule, each as
/// `f(sorted vertices, facet index, induced sign relative to the sorted order)`: the vertices
/// are sorted once, and the facet omitting the k-th smallest vertex (the j-th listed one) has
/// sign (-1)^k times the parity of the sorting permutation.
#[inline]
fn simplex_facets(
    vs: &[u32],
    local_rule: bool,
    view: &LeafView<'_>,
    mut f: impl FnMut(&[u32], u64, i8),
) {
    let n = vs.len();
    let mut sv = [0u32; SIMPLEX_FAST];
    let mut si = [0u8; SIMPLEX_FAST];
    let mut fk = [0u32; SIMPLEX_FAST];
    if !(2..=SIMPLEX_FAST).contains(&n) {
        return;
    }
    // insertion sort tracking listed positions; the swaps count the inversions
    let mut swaps = 0usize;
    for (i, &x) in vs.iter().enumerate() {
        let mut p = i;
        while p > 0 && sv[p - 1] > x {
            sv[p] = sv[p - 1];
            si[p] = si[p - 1];
            p -= 1;
            swaps += 1;
        }
        sv[p] = x;
        si[p] = i as u8;
    }
    let parity: i8 = if swaps.is_multiple_of(2) { 1 } else { -1 };
    let owned = if local_rule {
        sv[..n].iter().filter(|&&x| view.owns_tree(x)).count()
    } else {
        0
    };
    for k in 0..n {
        let keep = if local_rule {
            owned > view.owns_tree(sv[k]) as usize
        } else {
            view.owns_tree(if k == 0 { sv[1] } else { sv[0] })
        };
        if !keep {
            continue;
        }
        let mut m = 0;
        for (i, &x) in sv[..n].iter().enumerate() {
            if i != k {
                fk[m] = x;
                m += 1;
            }
        }
        let sign = if k % 2 == 0 { parity } else { -parity };
        f(&fk[..n - 1], si[k] as u64, sign);
    }
}

/// Payload of a facet record: tree cell id, facet index in the cell, induced sign.
#[inline]
pub(crate) fn pack(c: u32, j: u64, sign: i8) -> u64 {
    c as u64 | (j << 32) | if sign < 0 { 1 << 63 } else { 0 }
}

/// (tree cell, induced sign) of a facet payload.
#[inline]
pub(crate) fn unpack(x: u64) -> (u32, i8) {
    (x as u32, if x >> 63 == 1 { -1 } else { 1 })
}

/// Facet index of a facet payload.
#[inline]
pub(crate) fn unpack_facet(x: u64) -> u32 {
    ((x >> 32) & 0x7fff_ffff) as u32
}

#[cfg(test)]
mod tests {
    use crate::cell::CellKind;
    use crate::complex::{BuildOptions, ComplexBuilder};
    use crate::stellar::{StellarOptions, StellarTree};

    /// The two counts of triangles of a one-kind simplicial complex (hashed per leaf, which
    /// complexes of up to 2^21 vertices take, and over the stars, which larger ones take)
    /// equal the general face-key count, on random non-manifold complexes of tetrahedra and
    /// of 4-simplices, for several bucket sizes.
    #[test]
    fn triangle_counts_agree() {
        let mut rng = crate::testkit::XorShift::new(0x5EED_2026_1204);
        for case in 0..60 {
            let nv = 6 + rng.below(14) as usize;
            let d = 3 + (case % 2) as u8;
            let mut b = ComplexBuilder::new(3).unwrap();
            for i in 0..nv {
                let f = i as f64;
                b.push_vertex(&[f.sin(), (1.3 * f).cos(), (0.7 * f).sin()])
                    .unwrap();
            }
            for _ in 0..1 + rng.below(25) {
                let mut vs: Vec<u32> = Vec::new();
                while vs.len() < d as usize + 1 {
                    let v = rng.below(nv as u64) as u32;
                    if !vs.contains(&v) {
                        vs.push(v);
                    }
                }
                b.push_cell(CellKind::Simplex(d), &vs).unwrap();
            }
            let opts = BuildOptions {
                drop_duplicates: true,
                drop_face_cells: true,
                ..Default::default()
            };
            let k = b.build(&opts).unwrap().0;
            for kv in [1, 4, 0] {
                let t = StellarTree::build(
                    &k,
                    &StellarOptions {
                        kv: (kv > 0).then_some(kv),
                        ..Default::default()
                    },
                )
                .unwrap();
                let general: u64 = t
                    .par_face_groups(2, |_, keys| {
                        let mut n = 0u64;
                        keys.for_each_group(|_, _| n += 1);
                        n
                    })
                    .into_iter()
                    .sum();
                assert_eq!(
                    t.count_triangles_in_leaves(),
                    general,
                    "case {case} kv {kv}"
                );
                assert_eq!(t.count_triangles_by_stars(), general, "case {case} kv {kv}");
                assert_eq!(
                    t.count_edges_in_leaves(),
                    t.p_faces(1).unwrap().len() as u64
                );
            }
        }
    }
}
