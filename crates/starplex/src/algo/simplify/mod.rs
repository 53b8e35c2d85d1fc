//! Simplification by edge contraction that keeps the topology: one engine, two modes.
//!
//! * [`Mode::Homology`] ([`contract`]): contract edges that pass the link condition
//!   ([`link_condition`]), in rounds, on any simplicial complex of any dimension, pure or not,
//!   manifold or not; faces left without a top become new lower-dimensional tops.
//! * [`Mode::Qem`] ([`qem`]): Garland–Heckbert quadric error on triangle and tetrahedral meshes,
//!   each contraction checked by the extended link condition and by geometry.
//!
//! Both edit the same working structure, [`TopSimplices`] (the complex by its top simplices),
//! built from any structure through the `topo` traits, with the check-then-mutate pair
//! [`TopSimplices::can_contract`] / [`TopSimplices::contract`].
//!
//! ```
//! use starplex::algo::simplify::{simplify, SimplifyOptions, Mode, Target, summary};
//! use starplex::generate::kuhn_grid;
//! let ball = kuhn_grid(&[3, 3, 3]).unwrap(); // 162 tetrahedra filling a cube
//! let opts = SimplifyOptions { mode: Some(Mode::Homology), ..Default::default() };
//! let (point, report) = simplify(&ball, &opts).unwrap();
//! assert_eq!((point.n_vertices(), point.n_cells()), (1, 0)); // contractible: one vertex
//! let opts = SimplifyOptions { keep_manifold: true, ..opts };
//! let (small, _) = simplify(&ball, &opts).unwrap(); // still a 3-ball
//! assert!(small.n_cells() < 10);
//! assert_eq!(summary(&small).betti, Some(vec![1, 0, 0, 0]));
//! assert_eq!(report.mode, Mode::Homology);
//! ```
pub mod blocks;
pub mod contract;
pub mod hausdorff;
pub mod link_condition;
pub mod qem;
mod rows;
pub mod tops;

use std::sync::Arc;
use std::time::Instant;

pub use blocks::Blocks;
pub use tops::TopSimplices;

use crate::complex::{ComplexError, IndexedComplex};
use crate::topo::naive::VtIndex;

/// A progress callback: called with the number of contractions just made.
pub type Progress = dyn Fn(u64) + Send + Sync;

/// Why simplification could not run.
///
/// ```
/// use starplex::algo::simplify::SimplifyError;
/// use starplex::cell::CellKind;
/// let e = SimplifyError::not_simplicial(3, CellKind::Quad);
/// assert!(e.to_string().contains("convert --triangulate"));
/// ```
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SimplifyError {
    /// The complex has no vertex or no cell.
    #[error("the complex is empty: nothing to simplify")]
    Empty,
    /// A CP cell (quad, hexahedron, prism, pyramid).
    #[error(transparent)]
    NotSimplicial(#[from] crate::limits::NotSimplicial),
    /// A list given as a top simplex is not one.
    #[error("top {top}: {reason}")]
    BadTop {
        /// Its position.
        top: usize,
        /// What is wrong.
        reason: String,
    },
    /// QEM needs a pure triangle mesh (2D/3D) or a pure tetrahedral mesh (3D).
    #[error("quadric simplification needs a pure triangle mesh (2 or 3 coordinates) or a pure tetrahedral mesh (3 coordinates); use the homology mode for other complexes")]
    NotAMesh,
    /// The target cannot be met or makes no sense.
    #[error("bad target: {0}")]
    BadTarget(String),
    /// An enumeration over the budget.
    #[error(transparent)]
    TooLarge(#[from] crate::limits::TooLarge),
    /// The simplified complex could not be assembled.
    #[error("building the simplified complex: {0}")]
    Complex(ComplexError),
    /// `keep_labels` names no cell attribute of the complex.
    #[error("labels to keep, '{name}': the complex has no cell attribute of that name (it has: {available})")]
    UnknownLabel {
        /// The name asked.
        name: String,
        /// The cell attributes present, comma-separated (or "none").
        available: String,
    },
    /// A vertex of `keep_vertices` out of range.
    #[error("kept vertex {vertex}: the complex has {n_vertices} vertices (ids from 0)")]
    BadVertex {
        /// The id given.
        vertex: u64,
        /// Vertices of the complex.
        n_vertices: usize,
    },
}

impl SimplifyError {
    /// Cell `cell` of kind `kind` is not a simplex.
    ///
    /// ```
    /// use starplex::algo::simplify::SimplifyError;
    /// use starplex::cell::CellKind;
    /// let e = SimplifyError::not_simplicial(0, CellKind::Hex);
    /// assert!(e.to_string().starts_with("cell 0 is a hex: simplification works"));
    /// ```
    pub fn not_simplicial(cell: u32, kind: crate::cell::CellKind) -> SimplifyError {
        crate::limits::NotSimplicial::new(cell as u64, kind, "simplification").into()
    }
}

/// The two modes.
///
/// ```
/// use starplex::algo::simplify::Mode;
/// assert_eq!(Mode::parse("qem"), Some(Mode::Qem));
/// assert_eq!(Mode::Homology.name(), "homology");
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Mode {
    /// Link-condition contraction on any simplicial complex.
    #[default]
    Homology,
    /// Quadric error on triangle / tetrahedral meshes, topology kept.
    Qem,
}

impl Mode {
    /// Parses `homology` or `qem`.
    ///
    /// ```
    /// assert_eq!(starplex::algo::simplify::Mode::parse("x"), None);
    /// ```
    pub fn parse(s: &str) -> Option<Mode> {
        match s {
            "homology" => Some(Mode::Homology),
            "qem" => Some(Mode::Qem),
            _ => None,
        }
    }
    /// The name on the command line.
    ///
    /// ```
    /// assert_eq!(starplex::algo::simplify::Mode::Qem.name(), "qem");
    /// ```
    pub fn name(self) -> &'static str {
        match self {
            Mode::Homology => "homology",
            Mode::Qem => "qem",
        }
    }
}

/// When to stop: the first bound reached ends the run; none set means "as far as possible".
///
/// ```
/// use starplex::algo::simplify::{Target, TopSimplices};
/// let w = TopSimplices::from_tops(3, &[vec![0, 1, 2]]).unwrap();
/// assert!(Target { faces: Some(1), ..Default::default() }.reached(&w));
/// assert!(!Target::default().reached(&w));
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Target {
    /// Stop at this many top cells (or fewer).
    pub faces: Option<usize>,
    /// Stop at this many vertices (or fewer).
    pub vertices: Option<usize>,
    /// Keep this fraction of the top cells (0..=1); resolved into `faces` by [`simplify`].
    pub ratio: Option<f64>,
    /// QEM: stop before a contraction whose quadric error exceeds this.
    pub max_error: Option<f64>,
}

impl Target {
    /// True when a count bound is met.
    ///
    /// ```
    /// use starplex::algo::simplify::{Target, TopSimplices};
    /// let w = TopSimplices::from_tops(3, &[vec![0, 1, 2]]).unwrap();
    /// assert!(Target { vertices: Some(3), ..Default::default() }.reached(&w));
    /// ```
    pub fn reached(&self, w: &TopSimplices) -> bool {
        self.faces.is_some_and(|f| w.n_alive_tops() <= f)
            || self.vertices.is_some_and(|v| w.n_alive_vertices() <= v)
    }
}

/// Options of [`simplify`].
///
/// ```
/// let o = starplex::algo::simplify::SimplifyOptions::default();
/// assert!(o.mode.is_none() && !o.lock_boundary);
/// ```
#[derive(Clone, Default)]
pub struct SimplifyOptions {
    /// The mode (`None`: QEM for triangle and tetrahedral meshes, homology otherwise).
    pub mode: Option<Mode>,
    /// When to stop.
    pub target: Target,
    /// QEM: boundary vertices neither move nor disappear.
    pub lock_boundary: bool,
    /// Homology mode: test the extended link condition (the complex closed by a cone over its
    /// boundary), so a manifold stays a manifold of its dimension (a ball ends as a few
    /// top simplices instead of a point). QEM always does.
    pub keep_manifold: bool,
    /// Called with the number of contractions just made.
    pub progress: Option<Arc<Progress>>,
    /// Keep the regions of this cell attribute (a label such as `gmsh:physical` or
    /// `medit:ref`; see [`default_label_attribute`]): every vertex whose star holds cells of two
    /// different values (the label interface, which is a boundary in its own right) is locked
    /// like the boundary under `lock_boundary` — it neither moves nor disappears — so every
    /// contraction stays inside one region, and every contraction also passes the extended
    /// link condition within its region. This keeps the topology of each region and of the
    /// interfaces (see [`label_interface_vertices`]).
    pub keep_labels: Option<String>,
    /// Vertices (input ids) never removed nor moved.
    pub keep_vertices: Vec<u32>,
}

/// What [`simplify`] did.
///
/// ```
/// let r = starplex::algo::simplify::SimplifyReport::default();
/// assert_eq!(r.n_contractions, 0);
/// ```
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SimplifyReport {
    /// The mode that ran.
    pub mode: Mode,
    /// Edges contracted.
    pub n_contractions: u64,
    /// Rounds.
    pub rounds: u64,
    /// The resolved target of top cells, if any.
    pub target_faces: Option<usize>,
    /// QEM: largest and mean quadric error of the accepted contractions.
    pub max_error: Option<f64>,
    /// QEM: mean quadric error.
    pub mean_error: Option<f64>,
    /// Seconds spent simplifying (building the working structure and writing it back
    /// included).
    pub time_s: f64,
    /// The cell attribute whose regions were kept (`keep_labels`), if any.
    pub kept_labels: Option<String>,
    /// Vertices locked by the label interfaces and `keep_vertices` (not the boundary).
    pub locked_vertices: usize,
}

/// The mode [`simplify`] picks when none is given: QEM for a pure triangle mesh or a pure
/// tetrahedral mesh in 3D, homology otherwise.
///
/// ```
/// use starplex::algo::simplify::{default_mode, Mode};
/// assert_eq!(default_mode(&starplex::generate::kuhn_grid(&[1, 1, 1]).unwrap()), Mode::Qem);
/// assert_eq!(default_mode(&starplex::generate::kuhn_grid(&[1, 1, 1, 1]).unwrap()), Mode::Homology);
/// ```
pub fn default_mode(k: &IndexedComplex) -> Mode {
    let d = k.dim();
    let pure = k.cells().all(|c| Some(c.kind.dim()) == d);
    let simplicial = k.is_simplicial();
    match (d, k.ambient_dim()) {
        (Some(2), 2 | 3) | (Some(3), 3) if pure && simplicial => Mode::Qem,
        _ => Mode::Homology,
    }
}

/// Simplifies `k` (see the module docs) and returns the result with a report.
///
/// ```
/// use starplex::algo::simplify::{simplify, SimplifyOptions, Target};
/// use starplex::generate::kuhn_grid;
/// let sq = kuhn_grid(&[4, 4]).unwrap(); // 32 triangles in a square
/// let opts = SimplifyOptions { target: Target { ratio: Some(0.25), ..Default::default() }, ..Default::default() };
/// let (k, r) = simplify(&sq, &opts).unwrap();
/// assert_eq!(r.target_faces, Some(8));
/// assert!(k.n_cells() <= 8);
/// ```
///
/// # Errors
/// [`SimplifyError::Empty`], [`SimplifyError::NotSimplicial`] (CP cells: triangulate first),
/// [`SimplifyError::BadTarget`] (a count above the complex's, a ratio outside 0..=1, a negative
/// error, an error bound in homology mode), [`SimplifyError::NotAMesh`] (QEM asked on something
/// else than a triangle or tetrahedral mesh).
pub fn simplify(
    k: &IndexedComplex,
    opts: &SimplifyOptions,
) -> Result<(IndexedComplex, SimplifyReport), SimplifyError> {
    let t0 = Instant::now();
    if k.n_vertices() == 0 || k.n_cells() == 0 {
        return Err(SimplifyError::Empty);
    }
    if let Some(c) = k.cells().find(|c| !c.kind.is_simplex()) {
        return Err(SimplifyError::not_simplicial(c.id.0, c.kind));
    }
    let mode = opts.mode.unwrap_or_else(|| default_mode(k));
    let mut target = opts.target;
    let n_tops = k.n_cells() + k.n_isolated_vertices();
    if let Some(f) = target.faces
        && f > n_tops
    {
        return Err(SimplifyError::BadTarget(format!(
            "{f} faces asked, the complex has {n_tops} top cells"
        )));
    }
    if let Some(v) = target.vertices
        && v > k.n_vertices()
    {
        return Err(SimplifyError::BadTarget(format!(
            "{v} vertices asked, the complex has {}",
            k.n_vertices()
        )));
    }
    if let Some(r) = target.ratio {
        if !(0.0..=1.0).contains(&r) {
            return Err(SimplifyError::BadTarget(format!(
                "ratio {r}: it must be between 0 and 1"
            )));
        }
        let f = (r * n_tops as f64).round() as usize;
        target.faces = Some(target.faces.map_or(f, |x| x.max(f)));
    }
    if let Some(e) = target.max_error {
        if !(e >= 0.0 && e.is_finite()) {
            return Err(SimplifyError::BadTarget(format!(
                "max error {e}: it must be a finite number >= 0"
            )));
        }
        if mode == Mode::Homology {
            return Err(SimplifyError::BadTarget(
                "a maximum error is a quadric error: it needs the qem mode".into(),
            ));
        }
    }
    // the working structure and homology mode's blocks both read only `k`: built side by
    // side; homology mode never reads or moves a vertex, so its structure has no coordinates
    let (w, blocks) = rayon::join(
        || match mode {
            Mode::Homology => TopSimplices::from_complex_without_points(k),
            Mode::Qem => TopSimplices::from_complex(k),
        },
        || (mode == Mode::Homology).then(|| homology_blocks(k)),
    );
    let mut w = w?;
    for &v in &opts.keep_vertices {
        if v as usize >= k.n_vertices() {
            return Err(SimplifyError::BadVertex {
                vertex: v as u64,
                n_vertices: k.n_vertices(),
            });
        }
        w.set_locked(v, true);
    }
    if let Some(name) = &opts.keep_labels {
        let (labels, interface) = label_regions(k, name)?;
        for v in interface {
            w.set_locked(v, true);
        }
        // one region (every label id 0): the region test is the whole complex's
        if labels.iter().any(|&l| l != 0) {
            w.set_cell_labels(labels);
        }
    }
    let locked_vertices = w.n_locked();
    let progress = opts.progress.as_deref();
    let mut report = SimplifyReport {
        mode,
        target_faces: target.faces,
        kept_labels: opts.keep_labels.clone(),
        locked_vertices,
        ..Default::default()
    };
    match mode {
        Mode::Homology => {
            let lm = if opts.keep_manifold {
                link_condition::LinkMode::Manifold
            } else {
                link_condition::LinkMode::Homology
            };
            let blocks = blocks.unwrap_or_else(|| homology_blocks(k));
            let s = contract::contract_homology_owned_blocks(&mut w, &target, lm, progress, blocks);
            report.n_contractions = s.n_contractions;
            report.rounds = s.rounds;
        }
        Mode::Qem => {
            let s = qem::simplify_qem(&mut w, &target, opts.lock_boundary, progress)?;
            report.n_contractions = s.n_contractions;
            report.rounds = s.rounds;
            report.max_error = Some(s.max_error);
            report.mean_error = Some(s.mean_error);
        }
    }
    let (mut out, map) = match mode {
        // the survivors are where they were in the input
        Mode::Homology => w.to_complex_with_points(k.coords(), k.ambient_dim())?,
        Mode::Qem => w.to_complex()?,
    };
    let attrs = k.attributes();
    if !attrs.is_empty() {
        // vertex columns: the surviving vertices' own values; cell columns: each output cell
        // has the values of the input cell it is the image of
        let vertices: Vec<u32> = (0..map.len() as u32)
            .filter(|&v| map[v as usize].is_some())
            .collect();
        let cells: Vec<u32> = w
            .cell_origins()
            .into_iter()
            .map(|o| o.unwrap_or(0))
            .collect();
        let carried = crate::attr::Attributes {
            vertex: attrs.gather_vertices(&vertices).vertex,
            cell: attrs.gather_cells(&cells).cell,
        };
        out.set_attributes(carried)
            .map_err(SimplifyError::Complex)?;
    }
    report.time_s = t0.elapsed().as_secs_f64();
    Ok((out, report))
}

/// The blocks of the parallel rounds of homology mode: the leaves of a Stellar tree of `k` (by
/// coordinates; by connectivity when the coordinates do not separate the vertices) grouped by
/// [`blocks::BLOCK_VERTICES`]; one block for a small complex. Only the tree's vertex
/// decomposition is made ([`StellarTree::vertex_order`](crate::stellar::StellarTree::vertex_order)).
/// The blocks depend on the complex alone, so the result is the same for any number of threads.
///
/// ```
/// use starplex::algo::simplify::homology_blocks;
/// use starplex::generate::kuhn_grid;
/// assert_eq!(homology_blocks(&kuhn_grid(&[4, 4]).unwrap()).len(), 1);
/// assert!(homology_blocks(&kuhn_grid(&[300, 300]).unwrap()).len() > 1);
/// ```
pub fn homology_blocks(k: &IndexedComplex) -> Blocks {
    use crate::stellar::{Decomposition, StellarOptions, StellarTree};
    let n = k.n_vertices();
    if n < 2 * blocks::BLOCK_VERTICES {
        return Blocks::single(n);
    }
    for decomposition in [Decomposition::Spatial, Decomposition::Graph] {
        let opts = StellarOptions {
            decomposition,
            ..Default::default()
        };
        // the tree's vertex decomposition is all the blocks need: its cells are not filed
        if let Ok((order, starts)) = StellarTree::vertex_order(k, &opts) {
            let b = Blocks::from_leaves(order, &starts, blocks::BLOCK_VERTICES);
            if b.len() > 1 {
                return b;
            }
        }
    }
    Blocks::single(n)
}

/// The label attributes [`default_label_attribute`] looks for, in order.
pub const LABEL_ATTRIBUTES: [&str; 2] = ["gmsh:physical", "medit:ref"];

/// The cell attribute that labels regions, when the complex has one: the first of
/// [`LABEL_ATTRIBUTES`] (`gmsh:physical`, `medit:ref`) present as a cell attribute.
///
/// ```
/// use starplex::algo::simplify::default_label_attribute;
/// use starplex::attr::{Attribute, Attributes};
/// let mut a = Attributes::default();
/// assert_eq!(default_label_attribute(&a), None);
/// a.cell.push(Attribute::int("medit:ref", 1, vec![1, 2]));
/// assert_eq!(default_label_attribute(&a), Some("medit:ref"));
/// ```
pub fn default_label_attribute(attrs: &crate::attr::Attributes) -> Option<&'static str> {
    LABEL_ATTRIBUTES
        .into_iter()
        .find(|n| attrs.get(crate::attr::AttrTarget::Cell, n).is_some())
}

/// The vertices on a label interface: those whose star holds top cells of two different
/// values of the cell attribute `name` (all components compared; floats bit for bit). These are
/// the vertices `keep_labels` locks.
///
/// How `keep_labels` keeps each region's topology: an edge `ab` with `b` unlocked has all of
/// `St(b)` in one region `L`; every other region is untouched, and the contraction must pass,
/// besides the link condition in the whole complex, the extended link condition in `L` alone
/// ([`link_condition::region_condition`]: `L` closed by a cone over its own boundary, which
/// contains the interfaces). The plain link condition in `L` alone is not enough: a triangle
/// of `L` with one side on an interface and one on the mesh boundary would fold onto its
/// interface side, and `L` would lose that side (a test in `tests/suite/simplify_labels.rs` found it).
///
/// ```
/// use starplex::algo::simplify::label_interface_vertices;
/// use starplex::attr::{Attribute, Attributes};
/// use starplex::generate::kuhn_grid;
/// use starplex::ids::VertexId;
/// let mut k = kuhn_grid(&[2, 1]).unwrap(); // 4 triangles over the squares [0,1] and [1,2]
/// // label 1 left of x = 1, 2 right of it
/// let labels: Vec<i64> = k.cells()
///     .map(|c| if c.vertices.iter().all(|&v| k.point(VertexId(v))[0] <= 1.0) { 1 } else { 2 })
///     .collect();
/// k.set_attributes(Attributes { vertex: vec![], cell: vec![Attribute::int("tag", 1, labels)] }).unwrap();
/// assert_eq!(label_interface_vertices(&k, "tag").unwrap().len(), 2); // the middle edge
/// assert!(label_interface_vertices(&k, "nope").is_err());
/// ```
///
/// # Errors
/// [`SimplifyError::UnknownLabel`] when there is no such cell attribute.
pub fn label_interface_vertices(k: &IndexedComplex, name: &str) -> Result<Vec<u32>, SimplifyError> {
    Ok(label_regions(k, name)?.1)
}

/// One label id per cell (equal values, equal ids) and the interface vertices.
fn label_regions(k: &IndexedComplex, name: &str) -> Result<(Vec<u32>, Vec<u32>), SimplifyError> {
    use crate::attr::{AttrTarget, AttrValues};
    let attrs = k.attributes();
    let Some(col) = attrs.get(AttrTarget::Cell, name) else {
        let names: Vec<&str> = attrs.cell.iter().map(|a| a.name.as_str()).collect();
        return Err(SimplifyError::UnknownLabel {
            name: name.into(),
            available: if names.is_empty() {
                "none".into()
            } else {
                names.join(", ")
            },
        });
    };
    // one u32 per cell: equal values, equal ids
    let c = col.components;
    let label: Vec<u32> = match (&col.values, c) {
        (AttrValues::Int(v), 1) => {
            let mut ids = rustc_hash::FxHashMap::default();
            v.iter()
                .map(|x| {
                    let n = ids.len() as u32;
                    *ids.entry(*x).or_insert(n)
                })
                .collect()
        }
        _ => {
            let mut ids: rustc_hash::FxHashMap<Vec<u64>, u32> = Default::default();
            (0..k.n_cells())
                .map(|i| {
                    let key: Vec<u64> = (i * c..(i + 1) * c)
                        .map(|j| match &col.values {
                            AttrValues::Int(v) => v[j] as u64,
                            AttrValues::Float(v) => v[j].to_bits(),
                        })
                        .collect();
                    let n = ids.len() as u32;
                    *ids.entry(key).or_insert(n)
                })
                .collect()
        }
    };
    let mut first = vec![u32::MAX; k.n_vertices()];
    let mut on = vec![false; k.n_vertices()];
    for cell in k.cells() {
        let l = label[cell.id.0 as usize];
        for &v in cell.vertices {
            let f = &mut first[v as usize];
            if *f == u32::MAX {
                *f = l;
            } else if *f != l {
                on[v as usize] = true;
            }
        }
    }
    let interface = (0..k.n_vertices() as u32)
        .filter(|&v| on[v as usize])
        .collect();
    Ok((label, interface))
}

/// The topology of a complex, as reported before and after simplification.
///
/// ```
/// let s = starplex::algo::simplify::summary(&starplex::generate::kuhn_grid(&[1, 1]).unwrap());
/// assert_eq!(s.f_vector, Some(vec![4, 5, 2]));
/// assert_eq!((s.euler_characteristic, s.boundary_faces), (Some(1), 4));
/// ```
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct TopologySummary {
    /// Vertices.
    pub n_vertices: usize,
    /// Top cells.
    pub n_cells: usize,
    /// Simplices per dimension (`None` when over the counting budget).
    pub f_vector: Option<Vec<u64>>,
    /// Alternating sum of the f-vector.
    pub euler_characteristic: Option<i64>,
    /// Betti numbers over Z/2 (`None` when over the homology budget).
    pub betti: Option<Vec<u64>>,
    /// Non-manifold vertices.
    pub non_manifold_vertices: usize,
    /// Non-manifold edges.
    pub non_manifold_edges: usize,
    /// (d-1)-faces in exactly one top d-cell.
    pub boundary_faces: usize,
}

/// Computes the [`TopologySummary`] of `k` with `algo::homology` and `algo::validate`.
///
/// ```
/// let s = starplex::algo::simplify::summary(&starplex::generate::kuhn_grid(&[2, 2, 2]).unwrap());
/// assert_eq!(s.betti, Some(vec![1, 0, 0, 0]));
/// assert_eq!(s.non_manifold_vertices, 0);
/// ```
pub fn summary(k: &IndexedComplex) -> TopologySummary {
    let idx = VtIndex::new(k);
    let f_vector = crate::topo::from_tops::f_vector(&idx, 4_000_000_000).ok();
    let euler_characteristic = f_vector.as_ref().map(|f| {
        f.iter()
            .enumerate()
            .map(|(i, &x)| if i % 2 == 0 { x as i64 } else { -(x as i64) })
            .sum()
    });
    let betti = crate::algo::homology::homology(&idx, &Default::default())
        .ok()
        .map(|h| h.betti);
    let v = crate::algo::validate::validate(&idx);
    TopologySummary {
        n_vertices: k.n_vertices(),
        n_cells: k.n_cells(),
        f_vector,
        euler_characteristic,
        betti,
        non_manifold_vertices: v.non_manifold_vertices.len(),
        non_manifold_edges: v.non_manifold_edges.len(),
        boundary_faces: v.boundary_faces.len(),
    }
}
