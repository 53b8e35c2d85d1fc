//! The simplex tree (Boissonnat & Maria 2014; GUDHI's model): a trie of all simplices, each
//! simplex the path of its sorted vertices from the root; a node per simplex.
//!
//! Layout: the nodes of depth d (the d-simplices) are stored level by level in lexicographic
//! order of their vertex tuples, so the children of a node are a contiguous range of the next
//! level and a whole subtree is one contiguous range per level. Per node: its label (last
//! vertex), its parent and the start of its children range — 12 bytes (vertices, depth 0, are
//! implicit). With the *label-linked* option ([`SimplexTreeOptions::label_lists`]) every label
//! also has the list of the nodes carrying it (the paper's per-label lists linking nodes of the
//! same label), which makes stars and co-faces output-sensitive: the star of σ is the union of
//! the subtrees of the nodes labelled max(σ) whose path contains σ. Without the option those
//! nodes are found by scanning the levels.
//!
//! Built bottom-up per vertex: the subtree of v holds the faces of the tops at v whose smallest
//! vertex is v, generated from the tops' "upper" vertex sets with local sorting, so no node is
//! inserted twice and nothing is searched during the build.
//!
//! ```
//! use starplex::complex::{ComplexBuilder, BuildOptions};
//! use starplex::cell::CellKind;
//! use starplex::ids::VertexId;
//! use starplex::tds::simplex_tree::{SimplexTree, SimplexTreeOptions};
//! use starplex::topo::{Counts, Star};
//! let mut b = ComplexBuilder::new(2).unwrap();
//! for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
//! b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
//! b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
//! let k = b.build(&BuildOptions::default()).unwrap().0;
//! let st = SimplexTree::new(&k, &SimplexTreeOptions { label_lists: true, ..Default::default() }).unwrap();
//! assert_eq!(st.f_vector().unwrap(), vec![4, 5, 2]);
//! assert_eq!(st.star(&[VertexId(3)]).unwrap().f_vector(), vec![1, 2, 1]);
//! ```
use crate::cell::CellKind;
use crate::complex::IndexedComplex;
use crate::csr::Csr;
use crate::ids::{CellId, SimplexId, VertexId};
use crate::limits::{Limits, NotSimplicial, TooLarge, Unit};
use crate::topo::from_tops::{boundary_of_sorted, for_each_subset};
use crate::topo::{
    sort_flat, sorted_simplex, Adjacency, Boundary, Coboundary, Counts, Levels, QueryError,
    SimplexSet, SimplexVertices, Star, Storage, TopCells, TopStar, VertexAdjacency, VertexStar,
    DEFAULT_BUDGET,
};

/// Options of [`SimplexTree::new`].
///
/// ```
/// use starplex::tds::simplex_tree::{SimplexTree, SimplexTreeOptions, BuildError};
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// # let mut b = ComplexBuilder::new(1).unwrap();
/// # for x in 0..4 { b.push_vertex(&[x as f64]).unwrap(); }
/// # b.push_cell(CellKind::Simplex(3), &[0, 1, 2, 3]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// // k: the tetrahedron 0-1-2-3
/// let limits = starplex::limits::Limits { stored_simplices: 10, ..Default::default() };
/// let opts = SimplexTreeOptions { limits, ..Default::default() };
/// assert_eq!(SimplexTree::new(&k, &opts).unwrap_err(), BuildError::too_many(19, 10 ));
/// let opts = SimplexTreeOptions { label_lists: true, ..Default::default() };
/// assert!(SimplexTree::new(&k, &opts).unwrap().has_label_lists());
/// ```
#[derive(Clone, Debug, Default)]
pub struct SimplexTreeOptions {
    /// Keep, per label, the list of nodes carrying it (output-sensitive stars and co-faces).
    pub label_lists: bool,
    /// Refuse to build when the complex has more simplices than `limits.stored_simplices`
    /// (estimated from the tops; [`STORED_SIMPLICES`](crate::limits::STORED_SIMPLICES) by
    /// default, as for every structure that stores each simplex: node ids are 32-bit).
    pub limits: Limits,
}

/// Why a simplex tree could not be built.
///
/// ```
/// use starplex::tds::simplex_tree::{SimplexTree, SimplexTreeOptions, BuildError};
/// use starplex::cell::CellKind;
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// let mut b = ComplexBuilder::new(2).unwrap();
/// for p in [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// b.push_cell(CellKind::Quad, &[0, 1, 2, 3]).unwrap();
/// let k = b.build(&BuildOptions::default()).unwrap().0;
/// let err = SimplexTree::new(&k, &SimplexTreeOptions::default()).unwrap_err();
/// assert_eq!(err, BuildError::cp_cell(0, CellKind::Quad));
/// ```
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum BuildError {
    /// A top cell that is not a simplex.
    #[error(transparent)]
    NotSimplicial(#[from] NotSimplicial),
    /// Too many simplices (every face of every top cell, estimated before allocating).
    #[error(transparent)]
    TooLarge(#[from] TooLarge),
}

/// What a simplicial-only structure's [`NotSimplicial`] suggests.
pub const CP_STRUCTURES_HINT: &str =
    "the incidence graph, IA* and the Stellar tree hold CP cells (or triangulate first with \
     `starplex convert --triangulate IN OUT`)";

impl BuildError {
    /// The refusal of CP cell `cell` of kind `kind` by a simplicial-only structure.
    ///
    /// ```
    /// use starplex::cell::CellKind;
    /// use starplex::tds::simplex_tree::BuildError;
    /// let e = BuildError::cp_cell(4, CellKind::Prism);
    /// assert!(e.to_string().starts_with("cell 4 is a prism: this structure works on simplicial"));
    /// ```
    pub fn cp_cell(cell: u32, kind: CellKind) -> BuildError {
        BuildError::NotSimplicial(
            NotSimplicial::new(cell as u64, kind, "this structure").with_hint(CP_STRUCTURES_HINT),
        )
    }

    /// The refusal of `estimate` simplices over `limit`.
    ///
    /// ```
    /// use starplex::tds::simplex_tree::BuildError;
    /// assert!(matches!(BuildError::too_many(10, 5), BuildError::TooLarge(t) if t.budget == 5));
    /// ```
    pub fn too_many(estimate: u128, limit: u128) -> BuildError {
        BuildError::TooLarge(TooLarge::new(
            "the simplices of the complex (every face of every top cell)",
            estimate,
            limit,
            Unit::Simplices,
        ))
    }
}

/// Upper bound of the number of simplices: vertices plus every face of every top.
///
/// ```
/// use starplex::tds::simplex_tree::simplex_estimate;
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// // k: the triangles 0-1-2 and 1-3-2, sharing the edge 1-2
/// // 4 vertices + 7 faces (of any dimension) per triangle; shared faces are counted twice.
/// assert_eq!(simplex_estimate(&k).unwrap(), 4 + 2 * 7);
/// ```
///
/// # Errors
/// A CP cell.
pub fn simplex_estimate(k: &IndexedComplex) -> Result<u128, BuildError> {
    let mut est = k.n_vertices() as u128;
    for b in k.blocks() {
        if !b.kind.is_simplex() {
            return Err(BuildError::cp_cell(b.first, b.kind));
        }
        let per = (1u128 << (b.kind.dim() + 1).min(126)) - 1;
        est = est.saturating_add(per.saturating_mul(b.len() as u128));
    }
    Ok(est)
}

/// Every simplex of the complex, level by level, in lexicographic order: for depth q ≥ 1 the
/// label (last vertex) and parent (index at depth q-1) of each q-simplex. Shared by the
/// simplex tree, the incidence graph and IS.
pub(crate) struct Levels0 {
    pub labels: Vec<Vec<u32>>,
    pub parent: Vec<Vec<u32>>,
    /// Index of every top cell at depth = its dimension.
    pub cell_node: Vec<u32>,
}

pub(crate) fn all_simplices(k: &IndexedComplex, limit: u128) -> Result<Levels0, BuildError> {
    let est = simplex_estimate(k)?;
    if est > limit {
        return Err(BuildError::too_many(est, limit));
    }
    let nv = k.n_vertices();
    let dmax = k.dim().unwrap_or(0);
    let vt = k.vertex_cells();
    let (mut labels, mut parent) = reserved_levels(k, dmax);
    let mut s = Scratch::default();
    let mut cell_node = vec![u32::MAX; k.n_cells()];
    for v in 0..nv as u32 {
        let row = vt.row(v as usize);
        let Some(maxu) = s.upper_sets(k, row, v) else {
            continue;
        };
        let packed = maxu <= 8 && s.w.len() <= 1 << 16;
        s.prev.clear();
        for q in 1..=maxu {
            s.level(q, packed);
            s.emit(&mut labels, &mut parent, q, v);
            s.place_tops(k, row, q, labels[q].len(), &mut cell_node);
            std::mem::swap(&mut s.prev, &mut s.cur);
        }
    }
    // tops of dimension 0 (a vertex cell) are the vertex nodes
    for c in k.cells() {
        if c.vertices.len() == 1 {
            cell_node[c.id.index()] = c.vertices[0];
        }
    }
    while labels.len() > 1 && labels.last().is_some_and(|l| l.is_empty()) {
        labels.pop();
        parent.pop();
    }
    Ok(Levels0 {
        labels,
        parent,
        cell_node,
    })
}

/// Empty label and parent arrays per level `0..=dmax`, with rough reservations from the tops.
fn reserved_levels(k: &IndexedComplex, dmax: usize) -> (Vec<Vec<u32>>, Vec<Vec<u32>>) {
    let mut labels: Vec<Vec<u32>> = vec![Vec::new(); dmax + 1];
    let mut parent: Vec<Vec<u32>> = vec![Vec::new(); dmax + 1];
    for b in k.blocks() {
        for q in 1..=b.kind.dim() {
            let per = crate::cell::binomial(b.kind.dim() as u64 + 1, q as u64 + 1) as usize;
            let add = if q == b.kind.dim() {
                b.len()
            } else {
                per * b.len() / 2
            };
            labels[q].reserve(add.min(1 << 28));
            parent[q].reserve(add.min(1 << 28));
        }
    }
    (labels, parent)
}

/// The per-vertex working state of [`all_simplices`], reused across vertices.
#[derive(Default)]
struct Scratch {
    /// Upper vertices of the current vertex v (sorted, distinct).
    w: Vec<u32>,
    /// Ranks (in `w`) of each top's upper set, flat, each sorted.
    us: Vec<u32>,
    /// Length of each top's upper set.
    ulen: Vec<u8>,
    /// Packed keys of the level being built.
    keys: Vec<u128>,
    /// The level being built: sorted distinct rank tuples of length q, flat.
    cur: Vec<u32>,
    /// The previous level (length q - 1).
    prev: Vec<u32>,
    /// Subset buffer.
    sub: Vec<u32>,
}

impl Scratch {
    /// The upper sets (vertices above `v`) of the tops in `row`, the star of `v`; `None` when
    /// no top has a vertex above `v`, else the largest upper set's size.
    #[inline]
    fn upper_sets(&mut self, k: &IndexedComplex, row: &[u32], v: u32) -> Option<usize> {
        let w = &mut self.w;
        w.clear();
        for &c in row {
            let cell = k.cell(CellId(c));
            w.extend(cell.vertices.iter().copied().filter(|&x| x > v));
        }
        if w.is_empty() {
            return None;
        }
        w.sort_unstable();
        w.dedup();
        let (us, ulen) = (&mut self.us, &mut self.ulen);
        us.clear();
        ulen.clear();
        let mut maxu = 0usize;
        for &c in row {
            let cell = k.cell(CellId(c));
            let start = us.len();
            for &x in cell.vertices.iter().filter(|&&x| x > v) {
                us.push(w.binary_search(&x).expect("upper vertex") as u32);
            }
            us[start..].sort_unstable();
            let n = us.len() - start;
            maxu = maxu.max(n);
            ulen.push(n as u8);
        }
        Some(maxu)
    }

    /// Level `q` into `cur`: every q-subset of every upper set, sorted and distinct (through
    /// packed 16-bit keys when `packed`).
    #[inline]
    fn level(&mut self, q: usize, packed: bool) {
        let Scratch {
            us,
            ulen,
            keys,
            cur,
            sub,
            ..
        } = self;
        cur.clear();
        if packed {
            keys.clear();
            let mut off = 0usize;
            for &n in ulen.iter() {
                let n = n as usize;
                let u = &us[off..off + n];
                off += n;
                if n < q {
                    continue;
                }
                if q == 1 {
                    keys.extend(u.iter().map(|&r| (r as u128) << 112));
                } else {
                    for_each_subset(u, q, sub, &mut |s| {
                        let mut key = 0u128;
                        for (i, &r) in s.iter().enumerate() {
                            key |= (r as u128) << (112 - 16 * i);
                        }
                        keys.push(key);
                    });
                }
            }
            keys.sort_unstable();
            keys.dedup();
            for &key in keys.iter() {
                for i in 0..q {
                    cur.push(((key >> (112 - 16 * i)) & 0xffff) as u32);
                }
            }
        } else {
            let mut off = 0usize;
            for &n in ulen.iter() {
                let n = n as usize;
                let u = &us[off..off + n];
                off += n;
                if n >= q {
                    for_each_subset(u, q, sub, &mut |s| cur.extend_from_slice(s));
                }
            }
            sort_flat(cur, q);
        }
    }

    /// Appends level `q` of `v`'s subtree: labels (the last vertex) and parents (the node of
    /// the tuple without its last vertex, found by a forward scan of the previous level).
    #[inline]
    fn emit(&self, labels: &mut [Vec<u32>], parent: &mut [Vec<u32>], q: usize, v: u32) {
        let (w, cur, prev) = (&self.w, &self.cur, &self.prev);
        let base_prev = if q == 1 {
            0
        } else {
            labels[q - 1].len() - prev.len() / (q - 1)
        };
        let mut ptr = 0usize;
        for t in cur.chunks_exact(q) {
            labels[q].push(w[t[q - 1] as usize]);
            if q == 1 {
                parent[q].push(v);
            } else {
                while prev[ptr * (q - 1)..(ptr + 1) * (q - 1)] != t[..q - 1] {
                    ptr += 1;
                }
                parent[q].push((base_prev + ptr) as u32);
            }
        }
    }

    /// The node of each top of `row` whose smallest vertex is v and whose dimension is q
    /// (binary search of its upper set in level `q`, which ends at `level_len`).
    #[inline]
    fn place_tops(
        &self,
        k: &IndexedComplex,
        row: &[u32],
        q: usize,
        level_len: usize,
        cell_node: &mut [u32],
    ) {
        let (us, ulen, cur) = (&self.us, &self.ulen, &self.cur);
        let base = level_len - cur.len() / q;
        let mut off = 0usize;
        for (ci, &n) in ulen.iter().enumerate() {
            let n = n as usize;
            let u = &us[off..off + n];
            off += n;
            if n != q {
                continue;
            }
            let c = row[ci];
            if k.cell(CellId(c)).vertices.len() != q + 1 {
                continue;
            }
            let (mut lo, mut hi) = (0usize, cur.len() / q);
            while lo < hi {
                let mid = (lo + hi) / 2;
                match cur[mid * q..(mid + 1) * q].cmp(u) {
                    std::cmp::Ordering::Less => lo = mid + 1,
                    std::cmp::Ordering::Greater => hi = mid,
                    std::cmp::Ordering::Equal => {
                        lo = mid;
                        break;
                    }
                }
            }
            cell_node[c as usize] = (base + lo) as u32;
        }
    }
}

/// Children ranges from non-decreasing parent indices.
pub(crate) fn child_starts(parent: &[u32], n_parents: usize) -> Vec<u32> {
    let mut cs = vec![0u32; n_parents + 1];
    for &p in parent {
        cs[p as usize + 1] += 1;
    }
    for i in 0..n_parents {
        cs[i + 1] += cs[i];
    }
    cs
}

/// The simplex tree. See the [module docs](self).
///
/// ```
/// use starplex::tds::simplex_tree::{SimplexTree, SimplexTreeOptions};
/// use starplex::topo::{Coboundary, Counts};
/// use starplex::ids::VertexId;
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// // k: the triangles 0-1-2 and 1-3-2, sharing the edge 1-2
/// let st = SimplexTree::new(&k, &SimplexTreeOptions::default()).unwrap();
/// assert_eq!(st.f_vector().unwrap(), vec![4, 5, 2]);
/// let mut tris = Vec::new();
/// st.coboundary(&[VertexId(2), VertexId(1)], 2, &mut tris).unwrap();
/// assert_eq!(tris.len() / 3, 2);
/// ```
#[derive(Clone, Debug)]
pub struct SimplexTree {
    n_vertices: u32,
    /// `labels[d][i]`: last vertex of node i at depth d (d ≥ 1; `labels[0]` is empty).
    labels: Vec<Vec<u32>>,
    /// `parent[d][i]`: index at depth d-1.
    parent: Vec<Vec<u32>>,
    /// `child_start[d]`: children ranges of depth-d nodes in depth d+1 (n_d + 1 entries).
    child_start: Vec<Vec<u32>>,
    /// Global node id of the first node of each depth.
    level_offset: Vec<u32>,
    /// Optional label → nodes (global ids, depth ≥ 1).
    label_nodes: Option<Csr>,
    /// Node index of every top cell at depth = its dimension.
    cell_node: Vec<u32>,
    /// Dimension of every block of cells: (first cell id, dim).
    blocks: Vec<(u32, u8)>,
    /// Per depth: (node index, cell id) of the tops, sorted.
    top_at: Vec<Vec<(u32, u32)>>,
}

impl SimplexTree {
    /// Builds the tree of every simplex of `k`.
    ///
    /// ```
    /// use starplex::tds::simplex_tree::{SimplexTree, SimplexTreeOptions};
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// # let mut b = ComplexBuilder::new(1).unwrap();
    /// # for x in 0..4 { b.push_vertex(&[x as f64]).unwrap(); }
    /// # b.push_cell(CellKind::Simplex(3), &[0, 1, 2, 3]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// // k: the tetrahedron 0-1-2-3
    /// let st = SimplexTree::new(&k, &SimplexTreeOptions::default()).unwrap();
    /// assert_eq!(st.n_nodes(), 15); // 4 + 6 + 4 + 1
    /// ```
    ///
    /// # Errors
    /// A CP cell; more simplices than `opts.limits.stored_simplices` (refused before
    /// allocating).
    pub fn new(k: &IndexedComplex, opts: &SimplexTreeOptions) -> Result<SimplexTree, BuildError> {
        let l = all_simplices(k, opts.limits.stored_simplices.min(u32::MAX as u128))?;
        Ok(Self::from_levels(k, l, opts.label_lists))
    }

    pub(crate) fn from_levels(k: &IndexedComplex, l: Levels0, label_lists: bool) -> SimplexTree {
        let nv = k.n_vertices();
        let Levels0 {
            labels,
            parent,
            cell_node,
        } = l;
        let depth = labels.len();
        let mut child_start = Vec::with_capacity(depth);
        for d in 0..depth {
            let n_d = if d == 0 { nv } else { labels[d].len() };
            if d + 1 < depth {
                child_start.push(child_starts(&parent[d + 1], n_d));
            } else {
                child_start.push(vec![0u32; n_d + 1]);
            }
        }
        let mut level_offset = Vec::with_capacity(depth + 1);
        let mut acc = 0u32;
        for (d, l) in labels.iter().enumerate() {
            level_offset.push(acc);
            acc += if d == 0 { nv as u32 } else { l.len() as u32 };
        }
        level_offset.push(acc);
        let mut st = SimplexTree {
            n_vertices: nv as u32,
            labels,
            parent,
            child_start,
            level_offset,
            label_nodes: None,
            cell_node,
            blocks: k
                .blocks()
                .iter()
                .map(|b| (b.first, b.kind.dim() as u8))
                .collect(),
            top_at: vec![Vec::new(); depth],
        };
        if label_lists {
            let lv = &st.labels;
            let off = &st.level_offset;
            st.label_nodes = Some(Csr::from_fn(nv, |emit| {
                for (d, l) in lv.iter().enumerate().skip(1) {
                    for (i, &x) in l.iter().enumerate() {
                        emit(x, off[d] + i as u32);
                    }
                }
            }));
        }
        for c in k.cells() {
            let i = st.cell_node[c.id.index()];
            debug_assert!(i != u32::MAX);
            st.top_at[c.vertices.len() - 1].push((i, c.id.0));
        }
        for t in &mut st.top_at {
            t.sort_unstable();
        }
        st
    }

    /// Number of nodes (simplices, isolated vertices included).
    ///
    /// ```
    /// use starplex::tds::simplex_tree::{SimplexTree, SimplexTreeOptions};
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// # let mut b = ComplexBuilder::new(2).unwrap();
    /// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
    /// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
    /// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// // k: the triangles 0-1-2 and 1-3-2, sharing the edge 1-2
    /// let st = SimplexTree::new(&k, &SimplexTreeOptions::default()).unwrap();
    /// assert_eq!(st.n_nodes(), 4 + 5 + 2);
    /// ```
    pub fn n_nodes(&self) -> usize {
        *self.level_offset.last().unwrap_or(&0) as usize
    }

    /// Whether the label lists are kept.
    ///
    /// ```
    /// use starplex::tds::simplex_tree::{SimplexTree, SimplexTreeOptions};
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// # let mut b = ComplexBuilder::new(2).unwrap();
    /// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
    /// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
    /// # b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// // k: the triangles 0-1-2 and 1-3-2, sharing the edge 1-2
    /// let plain = SimplexTree::new(&k, &SimplexTreeOptions::default()).unwrap();
    /// assert!(!plain.has_label_lists());
    /// let opts = SimplexTreeOptions { label_lists: true, ..Default::default() };
    /// assert!(SimplexTree::new(&k, &opts).unwrap().has_label_lists());
    /// ```
    pub fn has_label_lists(&self) -> bool {
        self.label_nodes.is_some()
    }

    fn n_at(&self, d: usize) -> usize {
        if d == 0 {
            self.n_vertices as usize
        } else {
            self.labels[d].len()
        }
    }

    #[inline]
    fn label(&self, d: usize, i: u32) -> u32 {
        if d == 0 {
            i
        } else {
            self.labels[d][i as usize]
        }
    }

    /// Index at depth |s|-1 of the sorted simplex `s`.
    fn find_index(&self, s: &[VertexId]) -> Option<u32> {
        let first = s.first()?.0;
        if first >= self.n_vertices {
            return None;
        }
        let mut i = first;
        for (d, v) in s.iter().enumerate().skip(1) {
            if d >= self.labels.len() {
                return None;
            }
            let cs = &self.child_start[d - 1];
            let (lo, hi) = (cs[i as usize] as usize, cs[i as usize + 1] as usize);
            let r = self.labels[d][lo..hi].binary_search(&v.0).ok()?;
            i = (lo + r) as u32;
        }
        Some(i)
    }

    /// Vertices (sorted) of node i at depth d.
    fn node_vertices(&self, d: usize, mut i: u32, out: &mut Vec<VertexId>) {
        out.clear();
        out.resize(d + 1, VertexId(0));
        for e in (1..=d).rev() {
            out[e] = VertexId(self.labels[e][i as usize]);
            i = self.parent[e][i as usize];
        }
        out[0] = VertexId(i);
    }

    /// Whether node (d, i) contains all of sorted `s` (whose last vertex is the node's label).
    fn path_contains(&self, d: usize, mut i: u32, s: &[VertexId]) -> bool {
        let mut need = s.len();
        let mut e = d;
        loop {
            let lab = self.label(e, i);
            if need == 0 {
                return true;
            }
            let want = s[need - 1].0;
            if lab == want {
                need -= 1;
            } else if lab < want {
                return false;
            }
            if e == 0 {
                return need == 0;
            }
            i = self.parent[e][i as usize];
            e -= 1;
        }
    }

    /// Calls `f(depth, lo, hi)` with the ranges of nodes (per depth) forming the star of sorted
    /// `s`: the union of the subtrees of the nodes labelled max(s) that contain `s`.
    fn for_each_star_range(&self, s: &[VertexId], f: &mut dyn FnMut(usize, u32, u32)) {
        let p = s.len() - 1;
        let m = s[p].0;
        let mut visit = |d: usize, i: u32| {
            let (mut lo, mut hi) = (i, i + 1);
            let mut e = d;
            loop {
                if lo < hi {
                    f(e, lo, hi);
                }
                if e + 1 >= self.labels.len() {
                    break;
                }
                let cs = &self.child_start[e];
                lo = cs[lo as usize];
                hi = cs[hi as usize];
                e += 1;
                if lo >= hi {
                    break;
                }
            }
        };
        if p == 0 {
            visit(0, m);
        }
        match &self.label_nodes {
            Some(ln) => {
                for &g in ln.row(m as usize) {
                    let d = self.level_offset.partition_point(|&o| o <= g) - 1;
                    if d < p {
                        continue;
                    }
                    let i = g - self.level_offset[d];
                    if self.path_contains(d, i, s) {
                        visit(d, i);
                    }
                }
            }
            None => {
                for d in p.max(1)..self.labels.len() {
                    for (i, &lab) in self.labels[d].iter().enumerate() {
                        if lab == m && self.path_contains(d, i as u32, s) {
                            visit(d, i as u32);
                        }
                    }
                }
            }
        }
    }

    /// The star of `s` as simplex ids (global node ids), unsorted; the output-sensitive query
    /// that label lists make fast.
    ///
    /// # Errors
    /// `s` not in the complex.
    ///
    /// ```
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// use starplex::ids::VertexId;
    /// use starplex::tds::simplex_tree::{SimplexTree, SimplexTreeOptions};
    /// # let mut b = ComplexBuilder::new(1).unwrap();
    /// # for x in 0..4 { b.push_vertex(&[x as f64]).unwrap(); }
    /// # b.push_cell(CellKind::Simplex(3), &[0, 1, 2, 3]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// let st = SimplexTree::new(&k, &SimplexTreeOptions { label_lists: true, ..Default::default() }).unwrap();
    /// let mut ids = Vec::new();
    /// st.star_ids(&[VertexId(2)], &mut ids).unwrap();
    /// assert_eq!(ids.len(), 8);
    /// ```
    pub fn star_ids(&self, s: &[VertexId], out: &mut Vec<SimplexId>) -> Result<(), QueryError> {
        out.clear();
        let s = self.check(s)?;
        self.for_each_star_range(&s, &mut |d, lo, hi| {
            let o = self.level_offset[d];
            out.extend((lo..hi).map(|i| SimplexId(o + i)));
        });
        Ok(())
    }

    fn check(&self, s: &[VertexId]) -> Result<Vec<VertexId>, QueryError> {
        let s = sorted_simplex(s)?;
        if self.find_index(&s).is_none() {
            return Err(QueryError::NotInComplex(s.iter().map(|v| v.0).collect()));
        }
        Ok(s)
    }

    fn cell_dim(&self, c: u32) -> usize {
        let i = self.blocks.partition_point(|b| b.0 <= c) - 1;
        self.blocks[i].1 as usize
    }
}

impl TopCells for SimplexTree {
    fn n_vertices(&self) -> usize {
        self.n_vertices as usize
    }
    fn n_top_cells(&self) -> usize {
        self.cell_node.len()
    }
    fn top_cell_kind(&self, c: CellId) -> CellKind {
        CellKind::Simplex(self.cell_dim(c.0) as u8)
    }
    /// Sorted vertices: a simplex tree does not keep the input orientation.
    fn top_cell_vertices(&self, c: CellId, out: &mut Vec<VertexId>) {
        let mut v = Vec::new();
        self.node_vertices(self.cell_dim(c.0), self.cell_node[c.index()], &mut v);
        out.extend(v);
    }
}

impl TopStar for SimplexTree {
    fn top_star(&self, s: &[VertexId], out: &mut Vec<CellId>) -> Result<(), QueryError> {
        out.clear();
        let s = self.check(s)?;
        self.for_each_star_range(&s, &mut |d, lo, hi| {
            let tops = &self.top_at[d];
            let a = tops.partition_point(|t| t.0 < lo);
            for t in &tops[a..] {
                if t.0 >= hi {
                    break;
                }
                out.push(CellId(t.1));
            }
        });
        out.sort_unstable();
        Ok(())
    }
}

impl VertexStar for SimplexTree {
    fn vertex_top_cells(&self, v: VertexId, out: &mut Vec<CellId>) {
        if self.top_star(&[v], out).is_err() {
            out.clear();
        }
    }
}

impl VertexAdjacency for SimplexTree {
    fn vertex_neighbours(&self, v: VertexId, out: &mut Vec<VertexId>) {
        out.clear();
        if v.0 >= self.n_vertices || self.labels.len() < 2 {
            return;
        }
        let cs = &self.child_start[0];
        out.extend(
            self.labels[1][cs[v.index()] as usize..cs[v.index() + 1] as usize]
                .iter()
                .map(|&w| VertexId(w)),
        );
        match &self.label_nodes {
            Some(ln) => {
                for &g in ln.row(v.index()) {
                    if g >= self.level_offset[1] && g < self.level_offset[2] {
                        out.push(VertexId(
                            self.parent[1][(g - self.level_offset[1]) as usize],
                        ));
                    }
                }
            }
            None => {
                for (i, &lab) in self.labels[1].iter().enumerate() {
                    if lab == v.0 {
                        out.push(VertexId(self.parent[1][i]));
                    }
                }
            }
        }
        out.sort_unstable();
    }
}

impl Counts for SimplexTree {
    fn f_vector(&self) -> Result<Vec<u64>, QueryError> {
        if self.n_vertices == 0 {
            return Ok(vec![]);
        }
        Ok((0..self.labels.len())
            .map(|d| self.n_at(d) as u64)
            .collect())
    }
}

impl SimplexVertices for SimplexTree {
    fn n_simplices(&self) -> usize {
        self.n_nodes()
    }
    fn simplex_vertices(&self, s: SimplexId, out: &mut Vec<VertexId>) {
        let d = self.level_offset.partition_point(|&o| o <= s.0) - 1;
        self.node_vertices(d, s.0 - self.level_offset[d], out);
    }
    fn find_simplex(&self, verts: &[VertexId]) -> Option<SimplexId> {
        let s = sorted_simplex(verts).ok()?;
        let i = self.find_index(&s)?;
        Some(SimplexId(self.level_offset[s.len() - 1] + i))
    }
}

impl Boundary for SimplexTree {
    fn boundary(
        &self,
        s: &[VertexId],
        q: usize,
        out: &mut Vec<VertexId>,
    ) -> Result<(), QueryError> {
        let s = self.check(s)?;
        boundary_of_sorted(&s, q, DEFAULT_BUDGET, out)
    }
}

impl SimplexTree {
    fn star_filtered(
        &self,
        s: &[VertexId],
        only: Option<usize>,
        f: &mut dyn FnMut(&[VertexId]),
    ) -> Result<(), QueryError> {
        let s = self.check(s)?;
        let mut est: u128 = 0;
        self.for_each_star_range(&s, &mut |d, lo, hi| {
            if only.is_none_or(|q| q == d) {
                est += (hi - lo) as u128;
            }
        });
        if est > DEFAULT_BUDGET {
            return Err(QueryError::TooLarge(TooLarge::new(
                format!("star of {s:?}"),
                est,
                DEFAULT_BUDGET,
                Unit::Simplices,
            )));
        }
        let mut buf = Vec::new();
        self.for_each_star_range(&s, &mut |d, lo, hi| {
            if only.is_none_or(|q| q == d) {
                for i in lo..hi {
                    self.node_vertices(d, i, &mut buf);
                    f(&buf);
                }
            }
        });
        Ok(())
    }
}

impl Coboundary for SimplexTree {
    fn coboundary(
        &self,
        s: &[VertexId],
        q: usize,
        out: &mut Vec<VertexId>,
    ) -> Result<(), QueryError> {
        out.clear();
        if q < s.len() {
            self.check(s)?;
            return Ok(());
        }
        self.star_filtered(s, Some(q), &mut |t| out.extend_from_slice(t))?;
        sort_flat(out, q + 1);
        Ok(())
    }
}

impl Adjacency for SimplexTree {
    fn adjacent(&self, s: &[VertexId], out: &mut Vec<VertexId>) -> Result<(), QueryError> {
        let s = self.check(s)?;
        out.clear();
        if s.len() == 1 {
            self.vertex_neighbours(s[0], out);
            return Ok(());
        }
        let p = s.len() - 1;
        let mut co = Vec::new();
        let mut facet = Vec::new();
        for j in 0..=p {
            facet.clear();
            facet.extend(
                s.iter()
                    .enumerate()
                    .filter(|&(i, _)| i != j)
                    .map(|(_, &v)| v),
            );
            self.coboundary(&facet, p, &mut co)?;
            for c in co.chunks_exact(p + 1) {
                if c != s.as_slice() {
                    out.extend_from_slice(c);
                }
            }
        }
        sort_flat(out, p + 1);
        Ok(())
    }
}

impl Star for SimplexTree {
    fn star(&self, s: &[VertexId]) -> Result<SimplexSet, QueryError> {
        let mut set = SimplexSet::default();
        self.star_filtered(s, None, &mut |t| set.insert(t))?;
        set.normalize();
        Ok(set)
    }
}

impl Levels for SimplexTree {
    fn for_each_simplex(&self, p: usize, f: &mut dyn FnMut(&[VertexId])) -> Result<(), QueryError> {
        if p >= self.labels.len() {
            return Ok(());
        }
        let mut buf = Vec::new();
        for i in 0..self.n_at(p) {
            self.node_vertices(p, i as u32, &mut buf);
            f(&buf);
        }
        Ok(())
    }
}

impl Storage for SimplexTree {
    /// Three references per node (label, parent, children start; vertices implicit), plus the
    /// label lists (one per node) when kept.
    fn refs(&self) -> u64 {
        let nodes = self.n_nodes() as u64;
        let ll = self.label_nodes.as_ref().map_or(0, |c| c.n_refs() as u64);
        3 * nodes + ll
    }
    fn bytes(&self) -> u64 {
        let v: usize = self.labels.iter().map(|l| 4 * l.len()).sum::<usize>()
            + self.parent.iter().map(|l| 4 * l.len()).sum::<usize>()
            + self.child_start.iter().map(|l| 4 * l.len()).sum::<usize>()
            + 4 * self.level_offset.len()
            + self.label_nodes.as_ref().map_or(0, |c| c.bytes())
            + 4 * self.cell_node.len()
            + self.top_at.iter().map(|t| 8 * t.len()).sum::<usize>()
            + 5 * self.blocks.len();
        v as u64
    }
}
