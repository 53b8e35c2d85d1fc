//! Complexes from data: the Vietoris–Rips complex of a point cloud and the flag complex of a
//! graph, each stored by its maximal simplices (the maximal cliques of the graph, see
//! [`crate::algo::cliques`]) as an ordinary [`IndexedComplex`], so every reader of a complex
//! (`info`, `stellar`, `query`, `homology`, ...) works on it.
//!
//! The neighbourhood graph of a point cloud joins two points at distance ≤ ε: Euclidean by
//! default, or L1 / L∞ ([`Metric`], [`rips_complex_with`]), or read from a validated
//! [`DistanceMatrix`] ([`rips_from_distances`]). Points are searched
//! with a kd-tree (kiddo, which has L2², L1 and L∞ range queries) for ambient dimensions 1 to
//! 8, and by a sweep along the axis of largest extent above (kd-trees lose their edge there).
//! Either way every candidate pair is decided by the same exact test in `f64`: `Σ (a_i - b_i)²
//! ≤ ε²` (scipy's `cKDTree.query_pairs` test), `Σ |a_i - b_i| ≤ ε` or `max |a_i - b_i| ≤ ε`, so
//! the graph does not depend on the search structure.
//!
//! ```
//! use starplex::algo::rips::{rips_complex, RipsOptions};
//! // four corners of a unit square: at ε = 1 the 4-cycle, at ε = 1.5 the full tetrahedron
//! let pts = [0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 1.0];
//! let r = rips_complex(&pts, 2, 1.0, &RipsOptions::default()).unwrap();
//! assert_eq!((r.complex.n_cells(), r.n_edges), (4, 4));
//! let r = rips_complex(&pts, 2, 1.5, &RipsOptions::default()).unwrap();
//! assert_eq!(r.complex.dim(), Some(3));
//! ```
use kiddo::{Chebyshev, ImmutableKdTree, Manhattan, SquaredEuclidean};
use rayon::prelude::*;

use crate::algo::cliques::{maximal_cliques, CliqueOptions, Cliques, Graph, GraphError};
use crate::cell::{CellKind, MAX_SIMPLEX_DIM};
use crate::complex::{ComplexError, IndexedComplex, MAX_AMBIENT_DIM};
use crate::csr::Csr;
use crate::limits::Limits;

/// Why a Rips or flag complex could not be built.
///
/// ```
/// use starplex::algo::rips::{rips_complex, RipsError, RipsOptions};
/// let e = rips_complex(&[0.0, 1.0], 1, f64::NAN, &RipsOptions::default()).unwrap_err();
/// assert!(matches!(e, RipsError::BadScale(_)));
/// ```
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum RipsError {
    /// The scale is not a positive finite number.
    #[error("the scale must be a positive finite distance, got {0}")]
    BadScale(f64),
    /// Points with a non-finite coordinate, a wrong array length, or a bad dimension.
    #[error(transparent)]
    Complex(#[from] ComplexError),
    /// The graph or the enumeration (over budget, too many ids).
    #[error(transparent)]
    Graph(#[from] GraphError),
    /// A maximal simplex larger than starplex cells can be.
    #[error(
        "a maximal simplex has {vertices} vertices, above the supported simplex dimension \
         {MAX_SIMPLEX_DIM}; keep a skeleton with max_dim"
    )]
    CliqueTooLarge {
        /// Its vertex count.
        vertices: usize,
    },
    /// The neighbourhood graph alone would exceed the memory budget.
    #[error(
        "the neighbourhood graph would exceed the memory budget of {budget_bytes} bytes: about \
         {estimate_edges} edges ({estimate_bytes} bytes), extrapolated from {sampled} sampled \
         points; use a smaller scale"
    )]
    GraphOverBudget {
        /// Extrapolated edge count.
        estimate_edges: u64,
        /// Extrapolated bytes (12 per edge while building).
        estimate_bytes: u64,
        /// Points sampled.
        sampled: u64,
        /// The budget.
        budget_bytes: u64,
    },
    /// Too few points to define a nearest-neighbour scale.
    #[error("the nearest-neighbour scale needs at least two points, got {0}")]
    TooFewPoints(usize),
    /// A precomputed distance matrix that is not one (see [`DistanceMatrix::new`]).
    #[error(transparent)]
    DistanceMatrix(#[from] DistanceMatrixError),
}

/// The distance of [`rips_complex_with`]: two points are joined when it is at most ε.
///
/// ```
/// use starplex::algo::rips::Metric;
/// let (a, b) = ([0.0, 0.0], [3.0, 4.0]);
/// assert_eq!(Metric::Euclidean.distance(&a, &b), 5.0);
/// assert_eq!(Metric::Manhattan.distance(&a, &b), 7.0);
/// assert_eq!(Metric::Chebyshev.distance(&a, &b), 4.0);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Metric {
    /// L2, `sqrt(Σ (a_i - b_i)²)`; decided exactly as `Σ (a_i - b_i)² ≤ ε²`.
    #[default]
    Euclidean,
    /// L1, `Σ |a_i - b_i|`.
    Manhattan,
    /// L∞, `max |a_i - b_i|`.
    Chebyshev,
}

impl Metric {
    /// The distance between two points.
    ///
    /// ```
    /// use starplex::algo::rips::Metric;
    /// assert_eq!(Metric::Chebyshev.distance(&[1.0, 5.0], &[2.0, 3.0]), 2.0);
    /// ```
    pub fn distance(self, a: &[f64], b: &[f64]) -> f64 {
        match self {
            Metric::Euclidean => dist2(a, b).sqrt(),
            _ => self.key(a, b),
        }
    }

    /// The compared value: the squared distance for Euclidean, the distance otherwise.
    #[inline]
    fn key(self, a: &[f64], b: &[f64]) -> f64 {
        match self {
            Metric::Euclidean => dist2(a, b),
            Metric::Manhattan => a.iter().zip(b).map(|(x, y)| (x - y).abs()).sum(),
            Metric::Chebyshev => a
                .iter()
                .zip(b)
                .map(|(x, y)| (x - y).abs())
                .fold(0.0, f64::max),
        }
    }

    /// ε as a key.
    fn key_of(self, eps: f64) -> f64 {
        match self {
            Metric::Euclidean => eps * eps,
            _ => eps,
        }
    }

    /// A key as a distance.
    fn distance_of(self, key: f64) -> f64 {
        match self {
            Metric::Euclidean => key.sqrt(),
            _ => key,
        }
    }
}

/// Why an array is not a distance matrix. Every variant names the offending row and column.
///
/// ```
/// use starplex::algo::rips::{DistanceMatrix, DistanceMatrixError};
/// let e = DistanceMatrix::new(2, 2, vec![0.0, 1.0, 2.0, 0.0]).unwrap_err();
/// assert_eq!(e, DistanceMatrixError::NotSymmetric { row: 0, col: 1, value: 1.0, transposed: 2.0 });
/// ```
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum DistanceMatrixError {
    /// Not n × n.
    #[error("a distance matrix must be square, got {rows} rows and {cols} columns")]
    NotSquare {
        /// Rows.
        rows: usize,
        /// Columns.
        cols: usize,
    },
    /// The values do not fill the shape.
    #[error("{got} values for a {rows} x {cols} matrix")]
    WrongLength {
        /// Rows.
        rows: usize,
        /// Columns.
        cols: usize,
        /// Values given.
        got: usize,
    },
    /// NaN, infinite or negative.
    #[error("row {row} column {col}: {value} is not a finite non-negative distance")]
    BadEntry {
        /// Row.
        row: usize,
        /// Column.
        col: usize,
        /// The value.
        value: f64,
    },
    /// A point at a non-zero distance from itself.
    #[error("row {row} column {row}: the diagonal must be 0, got {value}")]
    NonZeroDiagonal {
        /// Row (and column).
        row: usize,
        /// The value.
        value: f64,
    },
    /// `d[row][col] != d[col][row]`.
    #[error(
        "row {row} column {col} is {value} but row {col} column {row} is {transposed}: the matrix \
         is not symmetric (symmetrize it, e.g. (D + D.T) / 2)"
    )]
    NotSymmetric {
        /// Row.
        row: usize,
        /// Column.
        col: usize,
        /// `d[row][col]`.
        value: f64,
        /// `d[col][row]`.
        transposed: f64,
    },
    /// More points than 32-bit ids.
    #[error(transparent)]
    TooLarge(#[from] crate::limits::TooLarge),
}

/// A validated distance matrix: n × n, finite, non-negative, zero diagonal, exactly symmetric
/// (row-major).
///
/// ```
/// use starplex::algo::rips::DistanceMatrix;
/// let d = DistanceMatrix::new(2, 2, vec![0.0, 3.0, 3.0, 0.0]).unwrap();
/// assert_eq!((d.len(), d.get(0, 1)), (2, 3.0));
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct DistanceMatrix {
    n: usize,
    d: Vec<f64>,
}

impl DistanceMatrix {
    /// Checks a `rows × cols` row-major array.
    ///
    /// ```
    /// use starplex::algo::rips::{DistanceMatrix, DistanceMatrixError};
    /// let e = DistanceMatrix::new(2, 2, vec![0.0, 1.0, 1.0, 0.5]).unwrap_err();
    /// assert_eq!(e, DistanceMatrixError::NonZeroDiagonal { row: 1, value: 0.5 });
    /// ```
    ///
    /// # Errors
    /// [`DistanceMatrixError`], naming the first bad row and column (row-major).
    pub fn new(rows: usize, cols: usize, d: Vec<f64>) -> Result<Self, DistanceMatrixError> {
        if rows != cols {
            return Err(DistanceMatrixError::NotSquare { rows, cols });
        }
        if rows.checked_mul(cols) != Some(d.len()) {
            return Err(DistanceMatrixError::WrongLength {
                rows,
                cols,
                got: d.len(),
            });
        }
        let n = rows;
        if n >= u32::MAX as usize {
            return Err(crate::limits::TooLarge::ids("points", n as u128).into());
        }
        for i in 0..n {
            for j in 0..n {
                let v = d[i * n + j];
                if !(v.is_finite() && v >= 0.0) {
                    return Err(DistanceMatrixError::BadEntry {
                        row: i,
                        col: j,
                        value: v,
                    });
                }
                if i == j && v != 0.0 {
                    return Err(DistanceMatrixError::NonZeroDiagonal { row: i, value: v });
                }
                let t = d[j * n + i];
                if j > i && v != t && t.is_finite() && t >= 0.0 {
                    return Err(DistanceMatrixError::NotSymmetric {
                        row: i,
                        col: j,
                        value: v,
                        transposed: t,
                    });
                }
            }
        }
        Ok(DistanceMatrix { n, d })
    }

    /// The distance matrix of points under a metric.
    ///
    /// ```
    /// use starplex::algo::rips::{DistanceMatrix, Metric};
    /// let d = DistanceMatrix::of_points(&[0.0, 0.0, 3.0, 4.0], 2, Metric::Manhattan);
    /// assert_eq!(d.get(1, 0), 7.0);
    /// ```
    pub fn of_points(coords: &[f64], dim: usize, metric: Metric) -> Self {
        let n = coords.len() / dim.max(1);
        let p = |i: usize| &coords[i * dim..(i + 1) * dim];
        let d = (0..n * n)
            .map(|k| metric.distance(p(k / n), p(k % n)))
            .collect();
        DistanceMatrix { n, d }
    }

    /// Number of points.
    ///
    /// ```
    /// # use starplex::algo::rips::DistanceMatrix;
    /// assert!(DistanceMatrix::new(0, 0, vec![]).unwrap().is_empty());
    /// ```
    pub fn len(&self) -> usize {
        self.n
    }

    /// True without points.
    ///
    /// ```
    /// # use starplex::algo::rips::DistanceMatrix;
    /// assert_eq!(DistanceMatrix::new(1, 1, vec![0.0]).unwrap().len(), 1);
    /// ```
    pub fn is_empty(&self) -> bool {
        self.n == 0
    }

    /// The distance from `i` to `j`.
    ///
    /// ```
    /// # use starplex::algo::rips::DistanceMatrix;
    /// assert_eq!(DistanceMatrix::new(1, 1, vec![0.0]).unwrap().get(0, 0), 0.0);
    /// ```
    pub fn get(&self, i: usize, j: usize) -> f64 {
        self.d[i * self.n + j]
    }

    fn row(&self, i: usize) -> &[f64] {
        &self.d[i * self.n..(i + 1) * self.n]
    }

    /// The median over points of the distance to the nearest other point (as
    /// [`median_nn_distance`]).
    ///
    /// ```
    /// # use starplex::algo::rips::DistanceMatrix;
    /// let d = DistanceMatrix::new(3, 3, vec![0.0, 1.0, 4.0, 1.0, 0.0, 2.0, 4.0, 2.0, 0.0]).unwrap();
    /// assert_eq!(d.median_nn_distance().unwrap(), 1.0); // nearest: 1, 1, 2
    /// ```
    ///
    /// # Errors
    /// Fewer than two points.
    pub fn median_nn_distance(&self) -> Result<f64, RipsError> {
        if self.n < 2 {
            return Err(RipsError::TooFewPoints(self.n));
        }
        let mut d: Vec<f64> = (0..self.n)
            .into_par_iter()
            .map(|i| {
                self.row(i)
                    .iter()
                    .enumerate()
                    .filter(|&(j, _)| j != i)
                    .map(|(_, &v)| v)
                    .fold(f64::INFINITY, f64::min)
            })
            .collect();
        Ok(median(&mut d, |x| x))
    }

    /// The graph joining `i` and `j ≠ i` when `d(i, j) ≤ eps`, refused when it would take more
    /// than `limits.memory_bytes`.
    ///
    /// ```
    /// # use starplex::algo::rips::DistanceMatrix;
    /// let d = DistanceMatrix::new(3, 3, vec![0.0, 1.0, 4.0, 1.0, 0.0, 2.0, 4.0, 2.0, 0.0]).unwrap();
    /// assert_eq!(d.graph(2.0, &Default::default()).unwrap().n_edges(), 2);
    /// ```
    ///
    /// # Errors
    /// A bad scale, [`RipsError::GraphOverBudget`] (an exact count, nothing sampled).
    pub fn graph(&self, eps: f64, limits: &Limits) -> Result<Graph, RipsError> {
        let max_bytes = limits.memory_bytes;
        if !(eps.is_finite() && eps > 0.0) {
            return Err(RipsError::BadScale(eps));
        }
        let n = self.n;
        let count: u64 = (0..n)
            .into_par_iter()
            .map(|i| self.row(i)[i + 1..].iter().filter(|&&v| v <= eps).count() as u64)
            .sum();
        let bytes = count.saturating_mul(BYTES_PER_EDGE);
        if bytes > max_bytes {
            return Err(RipsError::GraphOverBudget {
                estimate_edges: count,
                estimate_bytes: bytes,
                sampled: n as u64,
                budget_bytes: max_bytes,
            });
        }
        if 2 * count >= u32::MAX as u64 {
            return Err(GraphError::TooLarge(crate::limits::TooLarge::ids(
                "adjacency entries",
                (2 * count) as u128,
            ))
            .into());
        }
        let adj = Csr::from_fn(n, |push| {
            for i in 0..n {
                for (j, &v) in self.row(i).iter().enumerate() {
                    if j != i && v <= eps {
                        push(i as u32, j as u32);
                    }
                }
            }
        });
        Ok(Graph::from_sorted_rows(adj))
    }
}

/// The Vietoris–Rips complex at scale `eps` of a precomputed distance matrix: `i` and `j` are
/// joined when `d(i, j) ≤ eps`. As a flag complex, each vertex gets one coordinate, its id.
///
/// ```
/// use starplex::algo::rips::{rips_from_distances, DistanceMatrix};
/// let d = DistanceMatrix::new(3, 3, vec![0.0, 1.0, 4.0, 1.0, 0.0, 2.0, 4.0, 2.0, 0.0]).unwrap();
/// assert_eq!(rips_from_distances(&d, 2.0, &Default::default()).unwrap().by_dim, vec![(1, 2)]);
/// ```
///
/// # Errors
/// As [`rips_complex`].
pub fn rips_from_distances(
    d: &DistanceMatrix,
    eps: f64,
    opts: &RipsOptions,
) -> Result<Built, RipsError> {
    let t = std::time::Instant::now();
    let g = d.graph(eps, &opts.cliques.limits)?;
    let graph_s = t.elapsed().as_secs_f64();
    let coords: Vec<f64> = (0..d.n).map(|i| i as f64).collect();
    let mut b = complex_of(coords, 1, &g, opts)?;
    b.phases.graph_s = graph_s;
    Ok(b)
}

/// The median of values (numpy's: the mean of the two middle ones for an even count), after
/// `f` maps each.
fn median(d: &mut [f64], f: impl Fn(f64) -> f64) -> f64 {
    d.par_sort_unstable_by(f64::total_cmp);
    let n = d.len();
    if n % 2 == 1 {
        f(d[n / 2])
    } else {
        0.5 * (f(d[n / 2 - 1]) + f(d[n / 2]))
    }
}

/// Options of [`rips_complex`] and [`flag_complex`].
///
/// ```
/// use starplex::algo::rips::RipsOptions;
/// assert_eq!(RipsOptions::default().max_dim, None);
/// ```
#[derive(Clone, Copy, Default)]
pub struct RipsOptions<'a> {
    /// Options of the clique enumeration (`max_dim`, memory budget, progress).
    pub cliques: CliqueOptions<'a>,
    /// Shortcut for `cliques.max_dim` (either one set is used).
    pub max_dim: Option<usize>,
}

/// A complex built from data, with the numbers a summary reports.
///
/// ```
/// use starplex::algo::rips::flag_complex;
/// let f = flag_complex(3, &[(0, 1), (1, 2), (0, 2)], &Default::default()).unwrap();
/// assert_eq!((f.n_edges, f.complex.n_cells()), (3, 1));
/// ```
#[derive(Clone, Debug)]
pub struct Built {
    /// The complex: vertices are the points (or graph vertices), top cells the maximal simplices
    /// in canonical order (by size, then lexicographically).
    pub complex: IndexedComplex,
    /// Edges of the neighbourhood graph.
    pub n_edges: usize,
    /// `(simplex dimension, count)` of the maximal simplices.
    pub by_dim: Vec<(usize, usize)>,
    /// Vertices in no top cell (isolated points; every vertex with `max_dim` 0), counted from
    /// the graph: the same as `complex.n_isolated_vertices()` without a pass over the cells.
    pub n_isolated: usize,
    /// Wall-clock seconds of each phase.
    pub phases: Phases,
}

/// Wall-clock seconds of the phases of a build from data (what `rips --json` reports).
///
/// ```
/// use starplex::algo::rips::flag_complex;
/// let f = flag_complex(3, &[(0, 1), (1, 2), (0, 2)], &Default::default()).unwrap();
/// assert!(f.phases.cliques_s >= 0.0 && f.phases.graph_s >= 0.0);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Phases {
    /// The neighbourhood graph (ε-graph of the points, or the edge list's graph).
    pub graph_s: f64,
    /// The clique enumeration (degeneracy order, Bron–Kerbosch, the sorted blocks).
    pub cliques_s: f64,
    /// The complex from the cliques (its checks included).
    pub complex_s: f64,
}

/// The Vietoris–Rips complex at scale `eps` of `coords` (flat, `dim` coordinates per point):
/// its maximal simplices, or with a `max_dim` those of its skeleton.
///
/// ```
/// use starplex::algo::rips::{rips_complex, RipsOptions};
/// // three collinear points 1 apart: two edges at ε = 1, one triangle at ε = 2
/// let pts = [0.0, 1.0, 2.0];
/// assert_eq!(rips_complex(&pts, 1, 1.0, &RipsOptions::default()).unwrap().by_dim, vec![(1, 2)]);
/// assert_eq!(rips_complex(&pts, 1, 2.0, &RipsOptions::default()).unwrap().by_dim, vec![(2, 1)]);
/// ```
///
/// # Errors
/// A scale that is not positive and finite, non-finite coordinates, an output over the budget
/// (with an estimate), a maximal simplex above dimension 64.
pub fn rips_complex(
    coords: &[f64],
    dim: usize,
    eps: f64,
    opts: &RipsOptions,
) -> Result<Built, RipsError> {
    rips_complex_with(coords, dim, eps, Metric::Euclidean, opts)
}

/// [`rips_complex`] under another [`Metric`].
///
/// ```
/// use starplex::algo::rips::{rips_complex_with, Metric};
/// // (0,0) and (1,1): Euclidean √2, Manhattan 2, Chebyshev 1
/// let pts = [0.0, 0.0, 1.0, 1.0];
/// let edges = |m| rips_complex_with(&pts, 2, 1.5, m, &Default::default()).unwrap().n_edges;
/// assert_eq!((edges(Metric::Euclidean), edges(Metric::Manhattan), edges(Metric::Chebyshev)), (1, 0, 1));
/// ```
///
/// # Errors
/// As [`rips_complex`].
pub fn rips_complex_with(
    coords: &[f64],
    dim: usize,
    eps: f64,
    metric: Metric,
    opts: &RipsOptions,
) -> Result<Built, RipsError> {
    check_points(coords, dim)?;
    if !(eps.is_finite() && eps > 0.0) {
        return Err(RipsError::BadScale(eps));
    }
    let t = std::time::Instant::now();
    let g = neighbourhood_graph_metric(coords, dim, eps, metric, &opts.cliques.limits)?;
    let graph_s = t.elapsed().as_secs_f64();
    let mut b = complex_of(coords.to_vec(), dim, &g, opts)?;
    b.phases.graph_s = graph_s;
    Ok(b)
}

/// The flag complex of the graph on `n` vertices with these edges. The vertices have one
/// coordinate, their id (an abstract complex has no geometry; the id line keeps every format
/// and every structure able to hold it).
///
/// ```
/// use starplex::algo::rips::flag_complex;
/// let f = flag_complex(5, &[(0, 1), (1, 2), (2, 0), (3, 2)], &Default::default()).unwrap();
/// assert_eq!(f.by_dim, vec![(1, 1), (2, 1)]);
/// assert_eq!(f.complex.n_isolated_vertices(), 1); // vertex 4
/// assert_eq!(f.n_isolated, 1);
/// ```
///
/// # Errors
/// Self-loops or ids out of range (naming the edge), an output over the budget.
pub fn flag_complex(
    n: usize,
    edges: &[(u32, u32)],
    opts: &RipsOptions,
) -> Result<Built, RipsError> {
    let t = std::time::Instant::now();
    let g = Graph::from_edges(n, edges)?;
    let graph_s = t.elapsed().as_secs_f64();
    let coords: Vec<f64> = (0..n).map(|i| i as f64).collect();
    let mut b = complex_of(coords, 1, &g, opts)?;
    b.phases.graph_s = graph_s;
    Ok(b)
}

/// The complex whose top cells are the cliques of `g` (see [`maximal_cliques`]).
///
/// ```
/// use starplex::algo::cliques::Graph;
/// use starplex::algo::rips::complex_of;
/// let g = Graph::from_edges(2, &[(0, 1)]).unwrap();
/// let b = complex_of(vec![0.0, 1.0], 1, &g, &Default::default()).unwrap();
/// assert_eq!(b.complex.n_cells(), 1);
/// ```
///
/// # Errors
/// As [`rips_complex`].
pub fn complex_of(
    coords: Vec<f64>,
    dim: usize,
    g: &Graph,
    opts: &RipsOptions,
) -> Result<Built, RipsError> {
    let mut co = opts.cliques;
    if opts.max_dim.is_some() {
        co.max_dim = opts.max_dim;
    }
    let t = std::time::Instant::now();
    let cl = maximal_cliques(g, &co)?;
    let cliques_s = t.elapsed().as_secs_f64();
    let n = g.n_vertices();
    let n_isolated = if co.max_dim == Some(0) {
        n
    } else {
        (0..n as u32)
            .filter(|&v| g.neighbours(v).is_empty())
            .count()
    };
    let t = std::time::Instant::now();
    let mut b = complex_from_cliques(coords, dim, g.n_edges(), n_isolated, cl)?;
    b.phases = Phases {
        graph_s: 0.0,
        cliques_s,
        complex_s: t.elapsed().as_secs_f64(),
    };
    Ok(b)
}

fn complex_from_cliques(
    coords: Vec<f64>,
    dim: usize,
    n_edges: usize,
    n_isolated: usize,
    cl: Cliques,
) -> Result<Built, RipsError> {
    let by_dim = cl
        .count_by_size()
        .iter()
        .map(|&(s, c)| (s - 1, c))
        .collect();
    let mut blocks = Vec::with_capacity(cl.blocks.len());
    for (s, flat) in cl.blocks {
        let kind = CellKind::simplex(s - 1).ok_or(RipsError::CliqueTooLarge { vertices: s })?;
        blocks.push((kind, flat.into()));
    }
    // every clique is ascending with its vertices in range (the graph's ids): no cell check
    let complex = IndexedComplex::from_generated_parts(dim, coords.into(), blocks)?;
    Ok(Built {
        complex,
        n_edges,
        by_dim,
        n_isolated,
        phases: Phases::default(),
    })
}

fn check_points(coords: &[f64], dim: usize) -> Result<(), RipsError> {
    if dim == 0 || dim > MAX_AMBIENT_DIM {
        return Err(ComplexError::BadAmbientDim(dim).into());
    }
    if !coords.len().is_multiple_of(dim) {
        return Err(ComplexError::WrongCoordinateCount {
            vertex: (coords.len() / dim) as u64,
            expected: dim,
            got: coords.len() % dim,
        }
        .into());
    }
    if let Some(i) = coords.iter().position(|x| !x.is_finite()) {
        return Err(ComplexError::NonFiniteCoordinate {
            vertex: (i / dim) as u64,
            axis: i % dim,
            value: coords[i],
        }
        .into());
    }
    if coords.len() / dim >= u32::MAX as usize {
        return Err(GraphError::TooLarge(crate::limits::TooLarge::ids(
            "vertices",
            (coords.len() / dim) as u128,
        ))
        .into());
    }
    Ok(())
}

#[inline]
fn dist2(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y) * (x - y)).sum()
}

/// The ε-neighbourhood graph of the points: `i ~ j` when `Σ (p_i - p_j)² ≤ ε²`.
///
/// ```
/// use starplex::algo::rips::neighbourhood_graph;
/// let g = neighbourhood_graph(&[0.0, 0.0, 3.0, 4.0, 10.0, 0.0], 2, 5.0).unwrap();
/// assert_eq!(g.neighbours(0), &[1]); // at distance exactly 5: joined
/// assert_eq!(g.neighbours(2), &[] as &[u32]);
/// ```
///
/// # Errors
/// Bad coordinates or scale (as [`rips_complex`]), more than 2^32 adjacency entries.
pub fn neighbourhood_graph(coords: &[f64], dim: usize, eps: f64) -> Result<Graph, RipsError> {
    neighbourhood_graph_within(coords, dim, eps, &Limits::with_memory(u64::MAX))
}

/// Bytes per edge while the graph is built (later-neighbour rows, then both directions).
const BYTES_PER_EDGE: u64 = 12;

/// [`neighbourhood_graph`] that first estimates the edge count from a sample of points and
/// refuses when the graph would take more than `limits.memory_bytes`.
///
/// ```
/// use starplex::algo::rips::{neighbourhood_graph_within, RipsError};
/// use starplex::limits::Limits;
/// let pts: Vec<f64> = (0..1000).map(|i| i as f64).collect();
/// let e = neighbourhood_graph_within(&pts, 1, 1e6, &Limits::with_memory(10_000)).unwrap_err();
/// assert!(matches!(e, RipsError::GraphOverBudget { .. }));
/// ```
///
/// # Errors
/// As [`neighbourhood_graph`]; [`RipsError::GraphOverBudget`].
pub fn neighbourhood_graph_within(
    coords: &[f64],
    dim: usize,
    eps: f64,
    limits: &Limits,
) -> Result<Graph, RipsError> {
    neighbourhood_graph_metric(coords, dim, eps, Metric::Euclidean, limits)
}

/// [`neighbourhood_graph_within`] under another [`Metric`]: `i ~ j` when `d(p_i, p_j) ≤ ε`.
///
/// ```
/// use starplex::algo::rips::{neighbourhood_graph_metric, Metric};
/// let limits = starplex::limits::Limits::default();
/// let g = neighbourhood_graph_metric(&[0.0, 0.0, 3.0, 4.0], 2, 4.0, Metric::Chebyshev, &limits).unwrap();
/// assert_eq!(g.n_edges(), 1);
/// ```
///
/// # Errors
/// As [`neighbourhood_graph_within`].
pub fn neighbourhood_graph_metric(
    coords: &[f64],
    dim: usize,
    eps: f64,
    metric: Metric,
    limits: &Limits,
) -> Result<Graph, RipsError> {
    let max_bytes = limits.memory_bytes;
    check_points(coords, dim)?;
    if !(eps.is_finite() && eps > 0.0) {
        return Err(RipsError::BadScale(eps));
    }
    let n = coords.len() / dim;
    // rows of later neighbours, each sorted
    let rows: Vec<Vec<u32>> = match dim {
        1 => later_grid::<1>(coords, eps, metric, max_bytes)?,
        2 => later_grid::<2>(coords, eps, metric, max_bytes)?,
        3 => later_grid::<3>(coords, eps, metric, max_bytes)?,
        4 => later_kd::<4>(coords, eps, metric, max_bytes)?,
        5 => later_kd::<5>(coords, eps, metric, max_bytes)?,
        6 => later_kd::<6>(coords, eps, metric, max_bytes)?,
        7 => later_kd::<7>(coords, eps, metric, max_bytes)?,
        8 => later_kd::<8>(coords, eps, metric, max_bytes)?,
        _ => later_sweep(coords, dim, eps, metric, max_bytes)?,
    };
    let total: u64 = rows.iter().map(|r| 2 * r.len() as u64).sum();
    if total >= u32::MAX as u64 {
        return Err(GraphError::TooLarge(crate::limits::TooLarge::ids(
            "adjacency entries",
            total as u128,
        ))
        .into());
    }
    // Row v receives its earlier neighbours at their own (earlier) iterations, ascending, then
    // its later ones, ascending: every row comes out sorted.
    let adj = Csr::from_fn(n, |push| {
        for (i, r) in rows.iter().enumerate() {
            for &j in r {
                push(i as u32, j);
                push(j, i as u32);
            }
        }
    });
    Ok(Graph::from_sorted_rows(adj))
}

/// At most this many grid cells per point (else the kd-tree is used).
const GRID_CELLS_PER_POINT: usize = 16;

/// Later neighbours of every point by a uniform grid of cells of side just over ε, in 1–3
/// dimensions: in each metric a coordinate difference is at most the distance, so every pair
/// within ε lies in the same or adjacent cells, and each point is tested against the points of
/// its 3^K cells. The kd-tree ([`later_kd`]) takes over when the grid would have more than
/// [`GRID_CELLS_PER_POINT`] cells per point (sparse or spread-out points), or when coordinates
/// are so large against ε that rounding could move a point by a cell.
fn later_grid<const K: usize>(
    coords: &[f64],
    eps: f64,
    metric: Metric,
    max_bytes: u64,
) -> Result<Vec<Vec<u32>>, RipsError> {
    let n = coords.len() / K;
    let (mut lo, mut hi) = ([f64::INFINITY; K], [f64::NEG_INFINITY; K]);
    for c in coords.chunks_exact(K) {
        for a in 0..K {
            lo[a] = lo[a].min(c[a]);
            hi[a] = hi[a].max(c[a]);
        }
    }
    let side = eps * (1.0 + 1e-6);
    let mut dims = [0usize; K];
    let mut total = 1usize;
    for a in 0..K {
        let scale = lo[a].abs().max(hi[a].abs());
        let cells = ((hi[a] - lo[a]) / side).floor() + 1.0;
        if !(scale / side < (1u64 << 30) as f64 && cells.is_finite()) {
            return later_kd::<K>(coords, eps, metric, max_bytes);
        }
        dims[a] = cells as usize;
        total = total.saturating_mul(dims[a]);
    }
    if n == 0 || total > GRID_CELLS_PER_POINT.saturating_mul(n) + 1024 {
        return later_kd::<K>(coords, eps, metric, max_bytes);
    }
    let p = |i: usize| -> &[f64] { &coords[i * K..(i + 1) * K] };
    let cell_of = |i: usize| -> [usize; K] {
        std::array::from_fn(|a| (((p(i)[a] - lo[a]) / side) as usize).min(dims[a] - 1))
    };
    // the points by cell (a counting sort): each cell's points ascending
    let keys: Vec<u32> = (0..n)
        .into_par_iter()
        .map(|i| cell_key(&cell_of(i), &dims) as u32)
        .collect();
    let by_cell = Csr::from_fn(total, |push| {
        for (i, &k) in keys.iter().enumerate() {
            push(k, i as u32);
        }
    });
    drop(keys);
    let (start, pts) = (&by_cell.offsets[..], &by_cell.targets[..]);
    let e2 = metric.key_of(eps);
    // coordinates in cell order, read contiguously
    let sorted: Vec<[f64; K]> = pts
        .iter()
        .map(|&j| std::array::from_fn(|a| p(j as usize)[a]))
        .collect();
    let grid = Grid {
        dims,
        start,
        pts,
        sorted: &sorted,
        e2,
    };
    let mine =
        |i: usize| -> ([f64; K], [usize; K]) { (std::array::from_fn(|a| p(i)[a]), cell_of(i)) };
    // one loop per metric, so that the distance is inlined
    match metric {
        Metric::Euclidean => grid.rows(n, max_bytes, mine, |a, b| {
            a.iter().zip(b).map(|(x, y)| (x - y) * (x - y)).sum()
        }),
        Metric::Manhattan => grid.rows(n, max_bytes, mine, |a, b| {
            a.iter().zip(b).map(|(x, y)| (x - y).abs()).sum()
        }),
        Metric::Chebyshev => grid.rows(n, max_bytes, mine, |a, b| {
            a.iter()
                .zip(b)
                .map(|(x, y)| (x - y).abs())
                .fold(0.0, f64::max)
        }),
    }
}

/// The index of grid cell `at` in a grid of `dims` cells (row-major).
fn cell_key<const K: usize>(at: &[usize; K], dims: &[usize; K]) -> usize {
    at.iter().zip(dims).fold(0, |k, (&x, &d)| k * d + x)
}

/// The cells of [`later_grid`]: `pts[start[c]..start[c + 1]]` are cell `c`'s points (ascending),
/// `sorted` their coordinates in the same order.
struct Grid<'a, const K: usize> {
    dims: [usize; K],
    start: &'a [u32],
    pts: &'a [u32],
    sorted: &'a [[f64; K]],
    e2: f64,
}

impl<const K: usize> Grid<'_, K> {
    /// The later neighbours of every point (`mine(i)`: its coordinates and cell), under the
    /// metric key `key`.
    fn rows(
        &self,
        n: usize,
        max_bytes: u64,
        mine: impl Fn(usize) -> ([f64; K], [usize; K]) + Sync,
        key: impl Fn(&[f64; K], &[f64; K]) -> f64 + Sync,
    ) -> Result<Vec<Vec<u32>>, RipsError> {
        let later = |i: usize, out: &mut Vec<u32>| {
            let (q, c) = mine(i);
            let mut at = [0usize; K];
            'cells: for o in 0..3usize.pow(K as u32) {
                let mut r = o;
                for a in 0..K {
                    let x = (c[a] + r % 3).wrapping_sub(1);
                    r /= 3;
                    if x >= self.dims[a] {
                        continue 'cells;
                    }
                    at[a] = x;
                }
                let k = cell_key(&at, &self.dims);
                let (s, e) = (self.start[k] as usize, self.start[k + 1] as usize);
                for (&j, b) in self.pts[s..e].iter().zip(&self.sorted[s..e]) {
                    if j as usize > i && key(&q, b) <= self.e2 {
                        out.push(j);
                    }
                }
            }
            out.sort_unstable();
        };
        check_sample(n, max_bytes, |i| {
            let mut v = Vec::new();
            later(i, &mut v);
            // the later neighbours stand for half of the degree
            2 * v.len()
        })?;
        Ok((0..n)
            .into_par_iter()
            .map(|i| {
                let mut r = Vec::new();
                later(i, &mut r);
                r
            })
            .collect())
    }
}

/// Later neighbours of every point by a kd-tree in `K` dimensions.
fn later_kd<const K: usize>(
    coords: &[f64],
    eps: f64,
    metric: Metric,
    max_bytes: u64,
) -> Result<Vec<Vec<u32>>, RipsError> {
    let pts: Vec<[f64; K]> = coords
        .chunks_exact(K)
        .map(|c| {
            let mut a = [0.0; K];
            a.copy_from_slice(c);
            a
        })
        .collect();
    // kiddo pads its stems with f64::MAX, so a coordinate equal to it is left to the sweep
    let tree: ImmutableKdTree<f64, K> = match kd_tree(&pts) {
        Some(t) => t,
        None => return later_sweep(coords, K, eps, metric, max_bytes),
    };
    let e2 = metric.key_of(eps);
    // a slightly larger search radius (kiddo's own metric: L2², L1 or L∞); the exact test
    // below decides
    let search = e2 * (1.0 + 1e-9) + f64::MIN_POSITIVE;
    let within = |p: &[f64; K]| -> Vec<u32> {
        let q = tree.query(p);
        match metric {
            Metric::Euclidean => q
                .within::<SquaredEuclidean<f64>>(search)
                .unsorted()
                .execute()
                .iter()
                .map(|q| q.item)
                .collect(),
            Metric::Manhattan => q
                .within::<Manhattan<f64>>(search)
                .unsorted()
                .execute()
                .iter()
                .map(|q| q.item)
                .collect(),
            Metric::Chebyshev => q
                .within::<Chebyshev<f64>>(search)
                .unsorted()
                .execute()
                .iter()
                .map(|q| q.item)
                .collect(),
        }
    };
    check_sample(pts.len(), max_bytes, |i| {
        within(&pts[i]).len().saturating_sub(1)
    })?;
    Ok(pts
        .par_iter()
        .enumerate()
        .map(|(i, p)| {
            let mut r: Vec<u32> = within(p)
                .into_iter()
                .filter(|&j| j as usize > i && metric.key(p, &pts[j as usize]) <= e2)
                .collect();
            r.sort_unstable();
            r
        })
        .collect())
}

/// Refuses, before the graph is built, when the degrees of a stride sample of points
/// extrapolate to more than `max_bytes` of graph.
fn check_sample(
    n: usize,
    max_bytes: u64,
    degree: impl Fn(usize) -> usize + Sync,
) -> Result<(), RipsError> {
    if max_bytes == u64::MAX || n == 0 {
        return Ok(());
    }
    let s = n.min(1000);
    let step = n / s;
    let sum: u64 = (0..s)
        .into_par_iter()
        .map(|k| degree(k * step) as u64)
        .sum();
    let est_edges = (sum as f64 / s as f64 * n as f64 / 2.0) as u64;
    let est_bytes = est_edges.saturating_mul(BYTES_PER_EDGE);
    if est_bytes > max_bytes {
        return Err(RipsError::GraphOverBudget {
            estimate_edges: est_edges,
            estimate_bytes: est_bytes,
            sampled: s as u64,
            budget_bytes: max_bytes,
        });
    }
    Ok(())
}

/// Later neighbours of every point by a sweep along the axis of largest extent.
fn later_sweep(
    coords: &[f64],
    dim: usize,
    eps: f64,
    metric: Metric,
    max_bytes: u64,
) -> Result<Vec<Vec<u32>>, RipsError> {
    let n = coords.len() / dim;
    let p = |i: usize| &coords[i * dim..(i + 1) * dim];
    let axis = (0..dim)
        .max_by(|&a, &b| {
            let ext = |ax: usize| {
                let (lo, hi) = (0..n).fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), i| {
                    (l.min(p(i)[ax]), h.max(p(i)[ax]))
                });
                hi - lo
            };
            ext(a).total_cmp(&ext(b))
        })
        .unwrap_or(0);
    let mut by: Vec<u32> = (0..n as u32).collect();
    by.sort_by(|&a, &b| p(a as usize)[axis].total_cmp(&p(b as usize)[axis]));
    // every coordinate difference is at most the L1, L2 or L∞ distance
    let e2 = metric.key_of(eps);
    check_sample(n, max_bytes, |i| {
        (0..n)
            .filter(|&j| j != i && metric.key(p(i), p(j)) <= e2)
            .count()
    })?;
    let mut rows: Vec<Vec<u32>> = (0..n).into_par_iter().map(|_| Vec::new()).collect();
    let pairs: Vec<Vec<(u32, u32)>> = (0..n)
        .into_par_iter()
        .map(|s| {
            let i = by[s] as usize;
            let xi = p(i)[axis];
            let mut out = Vec::new();
            for &j in &by[s + 1..] {
                let j = j as usize;
                if p(j)[axis] - xi > eps {
                    break;
                }
                if metric.key(p(i), p(j)) <= e2 {
                    out.push((i.min(j) as u32, i.max(j) as u32));
                }
            }
            out
        })
        .collect();
    for (a, b) in pairs.into_iter().flatten() {
        rows[a as usize].push(b);
    }
    rows.par_iter_mut().for_each(|r| r.sort_unstable());
    Ok(rows)
}

/// The default memory budget (`CliqueOptions::limits.memory_bytes`) for the command line and the
/// Python package: [`crate::limits::default_memory_bytes`], a third of the available memory
/// (Linux `MemAvailable`), else 8 GiB.
///
/// ```
/// assert!(starplex::algo::rips::default_max_bytes() > 0);
/// ```
pub fn default_max_bytes() -> u64 {
    crate::limits::default_memory_bytes()
}

/// The median distance from a point to its nearest other point (numpy's median: the mean of
/// the two middle values for an even count), the scale `--eps-nn F` multiplies.
///
/// ```
/// use starplex::algo::rips::median_nn_distance;
/// // points at 0, 1, 3, 7: nearest-neighbour distances 1, 1, 2, 4
/// assert_eq!(median_nn_distance(&[0.0, 1.0, 3.0, 7.0], 1).unwrap(), 1.5);
/// ```
///
/// # Errors
/// Fewer than two points; bad coordinates.
pub fn median_nn_distance(coords: &[f64], dim: usize) -> Result<f64, RipsError> {
    median_nn_distance_with(coords, dim, Metric::Euclidean)
}

/// [`median_nn_distance`] under another [`Metric`].
///
/// ```
/// use starplex::algo::rips::{median_nn_distance_with, Metric};
/// // a unit square's diagonal neighbours do not matter: every nearest distance is 1
/// let sq = [0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 1.0];
/// assert_eq!(median_nn_distance_with(&sq, 2, Metric::Manhattan).unwrap(), 1.0);
/// ```
///
/// # Errors
/// As [`median_nn_distance`].
pub fn median_nn_distance_with(
    coords: &[f64],
    dim: usize,
    metric: Metric,
) -> Result<f64, RipsError> {
    check_points(coords, dim)?;
    let n = coords.len() / dim;
    if n < 2 {
        return Err(RipsError::TooFewPoints(n));
    }
    let mut d: Vec<f64> = match dim {
        1 => nn_kd::<1>(coords, metric),
        2 => nn_kd::<2>(coords, metric),
        3 => nn_kd::<3>(coords, metric),
        4 => nn_kd::<4>(coords, metric),
        5 => nn_kd::<5>(coords, metric),
        6 => nn_kd::<6>(coords, metric),
        7 => nn_kd::<7>(coords, metric),
        8 => nn_kd::<8>(coords, metric),
        _ => nn_brute(coords, dim, metric),
    };
    Ok(median(&mut d, |k| metric.distance_of(k)))
}

/// Squared distance from each point to its nearest other point.
fn nn_kd<const K: usize>(coords: &[f64], metric: Metric) -> Vec<f64> {
    let pts: Vec<[f64; K]> = coords
        .chunks_exact(K)
        .map(|c| {
            let mut a = [0.0; K];
            a.copy_from_slice(c);
            a
        })
        .collect();
    let Some(tree) = kd_tree(&pts) else {
        return nn_brute(coords, K, metric);
    };
    let two = std::num::NonZero::new(2usize).expect("2 is not zero");
    pts.par_iter()
        .enumerate()
        .map(|(i, p)| {
            let q = tree.query(p);
            let r: Vec<u64> = match metric {
                Metric::Euclidean => q
                    .nearest_n::<SquaredEuclidean<f64>>(two)
                    .execute()
                    .iter()
                    .map(|q| q.item as u64)
                    .collect(),
                Metric::Manhattan => q
                    .nearest_n::<Manhattan<f64>>(two)
                    .execute()
                    .iter()
                    .map(|q| q.item as u64)
                    .collect(),
                Metric::Chebyshev => q
                    .nearest_n::<Chebyshev<f64>>(two)
                    .execute()
                    .iter()
                    .map(|q| q.item as u64)
                    .collect(),
            };
            // the point itself is at distance 0 (as is a duplicate): take the other one
            r.iter()
                .find(|&&j| j as usize != i)
                .map(|&j| metric.key(p, &pts[j as usize]))
                .unwrap_or(f64::INFINITY)
        })
        .collect()
}

/// Squared nearest-neighbour distances by comparing every pair (above 8 dimensions).
fn nn_brute(coords: &[f64], dim: usize, metric: Metric) -> Vec<f64> {
    let n = coords.len() / dim;
    (0..n)
        .into_par_iter()
        .map(|i| {
            let a = &coords[i * dim..(i + 1) * dim];
            (0..n)
                .filter(|&j| j != i)
                .map(|j| metric.key(a, &coords[j * dim..(j + 1) * dim]))
                .fold(f64::INFINITY, f64::min)
        })
        .collect()
}

/// A kd-tree of the points, or `None` where kiddo cannot hold them (no point, a coordinate
/// equal to `f64::MAX`, which kiddo uses as padding).
fn kd_tree<const K: usize>(pts: &[[f64; K]]) -> Option<ImmutableKdTree<f64, K>> {
    if pts.is_empty() || pts.iter().any(|p| p.contains(&f64::MAX)) {
        return None;
    }
    ImmutableKdTree::new_from_slice(pts).ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The grid and the kd-tree find the same later neighbours: 1–3 dimensions, every metric,
    /// integer coordinates (many pairs at exactly ε) and jittered ones, dense and spread out
    /// (the spread-out cloud takes the kd-tree inside `later_grid` itself).
    #[test]
    fn grid_rows_equal_kd_rows() {
        let mut rng = crate::testkit::XorShift::new(0x9e37_79b9_7f4a_7c15);
        for k in 1..=3usize {
            for (n, range, jitter) in [
                (3000, 12u64, false),
                (3000, 12, true),
                (500, 1 << 20, false),
            ] {
                let coords: Vec<f64> = (0..n * k)
                    .map(|_| {
                        let x = rng.below(range) as f64;
                        if jitter {
                            x + rng.below(1000) as f64 / 1000.0
                        } else {
                            x
                        }
                    })
                    .collect();
                for metric in [Metric::Euclidean, Metric::Manhattan, Metric::Chebyshev] {
                    for eps in [1.0, 2.0, 2.5] {
                        let (g, t) = match k {
                            1 => (
                                later_grid::<1>(&coords, eps, metric, u64::MAX),
                                later_kd::<1>(&coords, eps, metric, u64::MAX),
                            ),
                            2 => (
                                later_grid::<2>(&coords, eps, metric, u64::MAX),
                                later_kd::<2>(&coords, eps, metric, u64::MAX),
                            ),
                            _ => (
                                later_grid::<3>(&coords, eps, metric, u64::MAX),
                                later_kd::<3>(&coords, eps, metric, u64::MAX),
                            ),
                        };
                        let (g, t) = (g.unwrap(), t.unwrap());
                        assert!(g.iter().map(Vec::len).sum::<usize>() > 0 || range > 1000);
                        assert_eq!(g, t, "dim {k} n {n} jitter {jitter} {metric:?} eps {eps}");
                    }
                }
            }
        }
    }
}
