//! Homology of any complex: Betti numbers over Z/2, Z/p, Q and Z (with torsion), per connected
//! component, a one-line summary of surface components, and representative cycles.
//!
//! Written once against [`TopCells`] + [`VertexStar`], so it runs on every structure that can
//! give the top cells around a vertex. **Reduce first, then linear algebra on what is left:**
//! 1. `morse` builds a discrete gradient (an acyclic matching) independently in the lower
//!    star of every vertex, generating faces on the fly from the top cells around the vertex
//!    (nothing is stored per face). Lower stars whose lower link is a cone are matched without
//!    enumerating them, so a single 40-simplex is answered at once; the few cells left
//!    unmatched are the *critical cells*.
//! 2. The boundary of each critical cell in the Morse complex is found by following gradient
//!    paths (cells merged in a front ordered by largest vertex, so each is visited once).
//! 3. Over a field the small boundary matrices are reduced by sparse column reduction with
//!    clearing (top dimension first; a cleared column is never even computed); over Z and Q by
//!    sparse unit-pivot elimination and a checked Smith normal form of what is left.
//!
//! Simplicial cells are oriented by their sorted vertices; the facets of CP cells come from
//! the cell kinds' VTK tables with their induced orientations (see [`crate::cell`]). Parallel
//! over vertices and over critical cells; the answer does not depend on the thread count.
//!
//! ```
//! use starplex::complex::{ComplexBuilder, BuildOptions};
//! use starplex::cell::CellKind;
//! use starplex::topo::naive::VtIndex;
//! use starplex::algo::homology::{homology, Field, HomologyOptions};
//! // the boundary of a tetrahedron: a 2-sphere
//! let mut b = ComplexBuilder::new(3).unwrap();
//! for p in [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]] { b.push_vertex(&p).unwrap(); }
//! for t in [[0, 1, 2], [0, 1, 3], [0, 2, 3], [1, 2, 3]] { b.push_cell(CellKind::Simplex(2), &t).unwrap(); }
//! let k = b.build(&BuildOptions::default()).unwrap().0;
//! let h = homology(&VtIndex::new(&k), &HomologyOptions::default()).unwrap();
//! assert_eq!(h.betti, vec![1, 0, 1]);
//! let hz = homology(&VtIndex::new(&k), &HomologyOptions { field: Field::Z, ..Default::default() }).unwrap();
//! assert_eq!((hz.betti, hz.torsion), (vec![1, 0, 1], vec![vec![], vec![], vec![]]));
//! ```
use crate::limits::{Limits, TooLarge, Unit};
use std::collections::BTreeMap;
use std::io::Write;
use std::sync::Arc;

use rayon::prelude::*;

use crate::algo::components::components;
use crate::complex::IndexedComplex;
use crate::ids::{CellId, VertexId};
use crate::topo::{naive::VtIndex, QueryError, TopCells, VertexStar};

mod cells;
mod chain;
mod loops;
mod morse;
mod order;
mod reduce;
mod smith;
mod surface;

use cells::{Cell, Key};
pub use chain::{chain_complex_homology, MorseComplex};
use morse::{Gradient, Scratch, ALONE, EXPLICIT};

/// Coefficients.
///
/// ```
/// use starplex::algo::homology::Field;
/// assert_eq!(Field::parse("2").unwrap(), Field::Z2);
/// assert_eq!(Field::parse("3").unwrap(), Field::Zp(3));
/// assert_eq!(Field::parse("q").unwrap(), Field::Q);
/// assert_eq!(Field::parse("Z").unwrap(), Field::Z);
/// assert!(Field::parse("4").is_err()); // not a prime
/// assert!(Field::parse("r").is_err());
/// assert_eq!(Field::Zp(5).to_string(), "Z/5");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Field {
    /// Z/2 (the default; what the dataset oracles call `betti_z2`).
    #[default]
    Z2,
    /// Z/p for a prime p (3 ≤ p < 2^31).
    Zp(u32),
    /// The rationals.
    Q,
    /// The integers: ranks and torsion coefficients.
    Z,
}

impl Field {
    /// Parses `2`, a prime `p`, `q` or `z` (case-insensitive).
    ///
    /// ```
    /// use starplex::algo::homology::{Field, HomologyError};
    /// assert_eq!(Field::parse("7"), Ok(Field::Zp(7)));
    /// assert_eq!(Field::parse("9"), Err(HomologyError::NotPrime(9)));
    /// ```
    ///
    /// # Errors
    /// [`HomologyError::UnknownField`] for anything else, [`HomologyError::NotPrime`] for a
    /// number that is not a prime below 2^31.
    pub fn parse(s: &str) -> Result<Field, HomologyError> {
        match s.to_ascii_lowercase().as_str() {
            "2" | "z2" | "z/2" => Ok(Field::Z2),
            "q" => Ok(Field::Q),
            "z" => Ok(Field::Z),
            t => {
                let t = t.strip_prefix("z/").unwrap_or(t);
                let p: u64 = t
                    .parse()
                    .map_err(|_| HomologyError::UnknownField(s.to_string()))?;
                if p >= 1 << 31 || !is_prime(p) {
                    return Err(HomologyError::NotPrime(p));
                }
                Ok(if p == 2 {
                    Field::Z2
                } else {
                    Field::Zp(p as u32)
                })
            }
        }
    }

    /// The modulus of the coefficient arithmetic (0 for Q and Z).
    ///
    /// ```
    /// use starplex::algo::homology::Field;
    /// assert_eq!((Field::Z2.modulus(), Field::Zp(5).modulus(), Field::Z.modulus()), (2, 5, 0));
    /// ```
    pub fn modulus(self) -> i64 {
        match self {
            Field::Z2 => 2,
            Field::Zp(p) => p as i64,
            Field::Q | Field::Z => 0,
        }
    }
}

impl std::fmt::Display for Field {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Field::Z2 => f.write_str("Z/2"),
            Field::Zp(p) => write!(f, "Z/{p}"),
            Field::Q => f.write_str("Q"),
            Field::Z => f.write_str("Z"),
        }
    }
}

fn is_prime(p: u64) -> bool {
    if p < 2 {
        return false;
    }
    let mut d = 2;
    while d * d <= p {
        if p.is_multiple_of(d) {
            return false;
        }
        d += 1;
    }
    true
}

/// Why homology could not be computed.
///
/// ```
/// use starplex::algo::homology::HomologyError;
/// assert_eq!(HomologyError::NotPrime(6).to_string(), "6 is not a prime (use 2, a prime p, q or z)");
/// ```
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum HomologyError {
    /// The work would explode (faces of huge non-cone lower stars).
    #[error(transparent)]
    TooLarge(TooLarge),
    /// A relation of the complex could not be read (a CP cell where simplices are needed, ...).
    #[error(transparent)]
    Query(QueryError),
    /// Integer coefficients overflowed (Z or Q).
    #[error("integer coefficients overflow in {0}; try a prime field")]
    Overflow(String),
    /// A field name that is not known.
    #[error("unknown field '{0}' (use 2, a prime p, q or z)")]
    UnknownField(String),
    /// A modulus that is not a prime.
    #[error("{0} is not a prime (use 2, a prime p, q or z)")]
    NotPrime(u64),
}

impl From<QueryError> for HomologyError {
    fn from(e: QueryError) -> HomologyError {
        match e {
            QueryError::TooLarge(t) => HomologyError::TooLarge(t),
            e => HomologyError::Query(e),
        }
    }
}

/// The vertex order that drives the lower-star matching (the answer never depends on it; the
/// number of critical cells, hence the time, does).
///
/// ```
/// use starplex::algo::homology::VertexOrder;
/// assert_eq!(VertexOrder::default(), VertexOrder::Auto);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum VertexOrder {
    /// The input order, unless it has many local minima (more than 64 + n/1000); then the
    /// order of first appearance in the cells, unless that has many too; then breadth-first.
    #[default]
    Auto,
    /// The input numbering.
    Input,
    /// First appearance in the top cells.
    FirstAppearance,
    /// Breadth-first from the first vertex (in first-appearance order) of each component, two
    /// vertices being neighbours when a top cell holds both (a quad's diagonal included).
    BreadthFirst,
}

/// Options of [`homology`].
///
/// ```
/// use starplex::algo::homology::{Field, HomologyOptions};
/// let o = HomologyOptions { field: Field::Q, per_component: true, ..Default::default() };
/// assert!(!o.generators);
/// assert_eq!(o.limits.homology_cells, 4_000_000_000);
/// ```
#[derive(Clone)]
pub struct HomologyOptions {
    /// Coefficients.
    pub field: Field,
    /// Also compute Betti numbers (and surface summaries) per connected component.
    pub per_component: bool,
    /// Also compute representative cycles (over Z/2 or Z/p; not for Q or Z).
    pub generators: bool,
    /// The budgets: `homology_cells`, the lower-star cells to enumerate in all before refusing
    /// with an estimate; `lower_star_simplices`, the simplices of one lower star;
    /// `dense_entries`, the entries of the dense remainder of the integer elimination.
    pub limits: Limits,
    /// The vertex order of the matching.
    pub order: VertexOrder,
    /// Called with the number of vertices just processed (for progress bars; one pass).
    pub progress: Option<Arc<dyn Fn(u64) + Send + Sync>>,
}

impl Default for HomologyOptions {
    fn default() -> Self {
        HomologyOptions {
            field: Field::Z2,
            per_component: false,
            generators: false,
            limits: Limits::default(),
            order: VertexOrder::Auto,
            progress: None,
        }
    }
}

impl std::fmt::Debug for HomologyOptions {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("HomologyOptions")
            .field("field", &self.field)
            .field("per_component", &self.per_component)
            .field("generators", &self.generators)
            .field("limits", &self.limits)
            .field("order", &self.order)
            .finish()
    }
}

/// A surface component: orientability, genus, boundary loops and Euler characteristic.
///
/// ```
/// use starplex::algo::homology::Surface;
/// let s = Surface { orientable: true, genus: 1, boundary_loops: 0, euler_characteristic: 0 };
/// assert_eq!(s.to_string(), "orientable surface, genus 1, 0 boundary loops, Euler characteristic 0");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Surface {
    /// Orientable.
    pub orientable: bool,
    /// Genus (orientable: handles; non-orientable: cross-caps).
    pub genus: u64,
    /// Boundary loops.
    pub boundary_loops: u64,
    /// Euler characteristic.
    pub euler_characteristic: i64,
}

impl std::fmt::Display for Surface {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} surface, genus {}, {} boundary loop{}, Euler characteristic {}",
            if self.orientable {
                "orientable"
            } else {
                "non-orientable"
            },
            self.genus,
            self.boundary_loops,
            if self.boundary_loops == 1 { "" } else { "s" },
            self.euler_characteristic
        )
    }
}

/// The homology of one connected component.
///
/// ```
/// use starplex::algo::homology::ComponentHomology;
/// let c = ComponentHomology { first_vertex: 0, betti: vec![1, 0], torsion: vec![vec![], vec![]], surface: None };
/// assert_eq!(c.betti[0], 1);
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ComponentHomology {
    /// Its smallest vertex (components are listed by it).
    pub first_vertex: u32,
    /// Betti numbers (ranks for Z).
    pub betti: Vec<u64>,
    /// Torsion coefficients per dimension (Z only; empty otherwise).
    pub torsion: Vec<Vec<u128>>,
    /// The surface summary when the component is a surface.
    pub surface: Option<Surface>,
}

/// A representative cycle: cells (sorted vertex lists) with coefficients.
///
/// ```
/// use starplex::algo::homology::Generator;
/// let g = Generator { dim: 0, cells: vec![(vec![0], 1)] };
/// assert_eq!(g.cells.len(), 1);
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Generator {
    /// Dimension of the class.
    pub dim: usize,
    /// The cells of the cycle (sorted vertex ids; a quad lists its 4 vertices in cyclic
    /// order) and their coefficients (1 over Z/2).
    pub cells: Vec<(Vec<u32>, i64)>,
}

/// The answer of [`homology`].
///
/// ```
/// use starplex::algo::homology::{homology, HomologyOptions};
/// use starplex::topo::naive::VtIndex;
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// let mut b = ComplexBuilder::new(1).unwrap();
/// for x in 0..3 { b.push_vertex(&[x as f64]).unwrap(); }
/// for e in [[0, 1], [1, 2], [0, 2]] { b.push_cell(CellKind::Simplex(1), &e).unwrap(); }
/// let k = b.build(&BuildOptions::default()).unwrap().0;
/// let h = homology(&VtIndex::new(&k), &HomologyOptions::default()).unwrap();
/// assert_eq!(h.betti, vec![1, 1]); // a circle
/// assert_eq!(h.euler_characteristic(), 0);
/// assert!(h.critical.iter().sum::<u64>() <= 3);
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Homology {
    /// The coefficients.
    pub field: Field,
    /// Betti numbers for dimensions 0..=dim (ranks of the free part for Z).
    pub betti: Vec<u64>,
    /// Torsion coefficients of H_k (Z only; empty lists otherwise).
    pub torsion: Vec<Vec<u128>>,
    /// Critical cells per dimension (the size of the Morse complex).
    pub critical: Vec<u64>,
    /// Per component (when asked), ordered by smallest vertex.
    pub components: Option<Vec<ComponentHomology>>,
    /// Representative cycles (when asked): for each dimension, one per Betti number.
    pub generators: Vec<Generator>,
}

impl Homology {
    /// The alternating sum of the Betti numbers.
    ///
    /// ```
    /// # use starplex::algo::homology::{Homology, Field};
    /// let h = Homology { field: Field::Z2, betti: vec![1, 2, 1], torsion: vec![], critical: vec![], components: None, generators: vec![] };
    /// assert_eq!(h.euler_characteristic(), 0);
    /// ```
    pub fn euler_characteristic(&self) -> i64 {
        alt_sum(&self.betti)
    }
}

fn alt_sum(b: &[u64]) -> i64 {
    b.iter()
        .enumerate()
        .map(|(i, &x)| if i % 2 == 0 { x as i64 } else { -(x as i64) })
        .sum()
}

/// Betti numbers over Z/2 of an indexed complex (the oracles' `betti_z2`).
///
/// ```
/// use starplex::algo::homology::betti_z2;
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// let mut b = ComplexBuilder::new(2).unwrap();
/// for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// let k = b.build(&BuildOptions::default()).unwrap().0;
/// assert_eq!(betti_z2(&k).unwrap(), vec![1, 0, 0]);
/// ```
///
/// # Errors
/// [`HomologyError::TooLarge`] when the lower stars to enumerate exceed the default budget.
pub fn betti_z2(k: &IndexedComplex) -> Result<Vec<u64>, HomologyError> {
    Ok(homology_indexed(k, &HomologyOptions::default())?.betti)
}

const CHUNK: usize = 4096;

/// Computes the homology of the complex given by `s`.
///
/// ```
/// use starplex::algo::homology::{homology, Field, HomologyOptions};
/// use starplex::topo::naive::VtIndex;
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// // One 40-simplex: contractible, answered without enumerating its 2^41 faces.
/// let mut b = ComplexBuilder::new(1).unwrap();
/// for x in 0..41 { b.push_vertex(&[x as f64]).unwrap(); }
/// b.push_cell(CellKind::Simplex(40), &(0..41).collect::<Vec<u32>>()).unwrap();
/// let k = b.build(&BuildOptions::default()).unwrap().0;
/// let h = homology(&VtIndex::new(&k), &HomologyOptions { field: Field::Z, ..Default::default() }).unwrap();
/// assert_eq!(h.betti[0], 1);
/// assert!(h.betti[1..].iter().all(|&x| x == 0));
/// assert_eq!(h.critical[0], 1);
/// ```
///
/// # Errors
/// [`HomologyError::TooLarge`] (with an estimate) when the lower stars that must be enumerated
/// exceed `opts.limits.homology_cells` cells or one of them exceeds
/// `opts.limits.lower_star_simplices` (2^26 by default);
/// [`HomologyError::Overflow`] when integer coefficients (Z, Q) overflow.
pub fn homology<S: TopCells + VertexStar + Sync + ?Sized>(
    s: &S,
    opts: &HomologyOptions,
) -> Result<Homology, HomologyError> {
    let mut h = match choose_order(s, opts.order) {
        None => homology_ordered(s, None, opts, None),
        Some((f, to_old)) => homology_ordered(&f, f.fast_star(), opts, Some(&to_old)),
    }?;
    if opts.generators {
        short_h1(s, &mut h, &|_, _| 1.0);
    }
    Ok(h)
}

/// Replaces the H_1 generators by short closed edge paths where the tree–cotree construction
/// applies (edges in at most two 2-cells; over Z/p, orientable), else keeps the Morse ones.
fn short_h1<S: TopCells + ?Sized>(s: &S, h: &mut Homology, length: &dyn Fn(u32, u32) -> f64) {
    let m = match h.field {
        Field::Z2 => 2,
        Field::Zp(p) => p as i64,
        Field::Q | Field::Z => return,
    };
    let b1 = h.betti.get(1).copied().unwrap_or(0);
    if b1 == 0 {
        return;
    }
    if let Some(l) = loops::short_loops(s, m, b1, length) {
        let at = h.generators.iter().take_while(|g| g.dim == 0).count();
        h.generators.retain(|g| g.dim != 1);
        h.generators.splice(at..at, l);
    }
}

/// [`homology`] of an indexed complex, building the vertex → cells relation only when the
/// input order is kept (a new order is materialised from the cells alone): less memory than
/// `homology(&VtIndex::new(k), opts)`, the same answer.
///
/// ```
/// use starplex::algo::homology::{homology_indexed, HomologyOptions};
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// let mut b = ComplexBuilder::new(2).unwrap();
/// for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// for t in [[0, 1, 2], [1, 3, 2]] { b.push_cell(CellKind::Simplex(2), &t).unwrap(); }
/// let k = b.build(&BuildOptions::default()).unwrap().0;
/// assert_eq!(homology_indexed(&k, &HomologyOptions::default()).unwrap().betti, vec![1, 0, 0]);
/// ```
///
/// # Errors
/// As [`homology`].
pub fn homology_indexed(
    k: &IndexedComplex,
    opts: &HomologyOptions,
) -> Result<Homology, HomologyError> {
    let mut h = match pick_order(k, opts.order, None, Some(k)) {
        None => input_order(k, opts),
        Some(fa) => {
            let t = std::time::Instant::now();
            match order::Flat::new(k, &fa) {
                Some(f) => {
                    debug_time("first-appearance order", t);
                    let (f, to_old) = finish_order(f, fa, opts.order);
                    homology_ordered(&f, f.fast_star(), opts, Some(&to_old))
                }
                None => input_order(k, opts),
            }
        }
    }?;
    if opts.generators {
        let length = |a: u32, b: u32| {
            let (p, q) = (k.point(VertexId(a)), k.point(VertexId(b)));
            p.iter()
                .zip(q)
                .map(|(x, y)| (x - y) * (x - y))
                .sum::<f64>()
                .sqrt()
        };
        short_h1(k, &mut h, &length);
    }
    Ok(h)
}

/// [`homology_ordered`] in the input order of `k`, through its vertex → cells relation (read
/// directly when the cells are one block of simplices).
fn input_order(k: &IndexedComplex, opts: &HomologyOptions) -> Result<Homology, HomologyError> {
    let idx = VtIndex::new(k);
    let fast = match k.blocks() {
        [b] if b.kind.is_simplex() => Some(morse::FastStar {
            arity: b.kind.n_vertices(),
            sorted: false,
            verts: &b.vertices,
            vt: &idx.vt,
        }),
        _ => None,
    };
    homology_ordered(&idx, fast, opts, None)
}

/// [`homology_indexed`] consuming the complex: when a new vertex order is chosen, the cells
/// are renumbered in place and the coordinates freed before the work starts, so the input and
/// its renumbered copy never coexist (the least memory; the same answer).
///
/// ```
/// use starplex::algo::homology::{homology_owned, HomologyOptions};
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// let mut b = ComplexBuilder::new(2).unwrap();
/// for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// for e in [[0, 1], [1, 3], [3, 2], [2, 0]] { b.push_cell(CellKind::Simplex(1), &e).unwrap(); }
/// let k = b.build(&BuildOptions::default()).unwrap().0;
/// assert_eq!(homology_owned(k, &HomologyOptions::default()).unwrap().betti, vec![1, 1]);
/// ```
///
/// # Errors
/// As [`homology`].
pub fn homology_owned(
    k: IndexedComplex,
    opts: &HomologyOptions,
) -> Result<Homology, HomologyError> {
    if opts.generators {
        // the loops are measured on the coordinates, which this path frees
        return homology_indexed(&k, opts);
    }
    let Some(fa) = pick_order(&k, opts.order, Some(k.n_refs() as u64), Some(&k)) else {
        // the input order: one block of simplices is taken over (coordinates freed)
        let t = std::time::Instant::now();
        if !order::Flat::takes_over(&k) {
            return input_order(&k, opts);
        }
        return match order::Flat::input_order(k) {
            Some(f) => {
                debug_time("input order (in place)", t);
                homology_ordered(&f, f.fast_star(), opts, None)
            }
            // not reachable: `takes_over` was checked
            None => Err(HomologyError::TooLarge(TooLarge::ids(
                "homology: vertex references",
                u32::MAX as u128,
            ))),
        };
    };
    let t = std::time::Instant::now();
    match order::Flat::from_complex(k, &fa) {
        Some(f) => {
            debug_time("first-appearance order (in place)", t);
            let (f, to_old) = finish_order(f, fa, opts.order);
            homology_ordered(&f, f.fast_star(), opts, Some(&to_old))
        }
        // not reachable: from_complex only refuses what `pick_order` keeps in input order
        None => Err(HomologyError::TooLarge(TooLarge::ids(
            "homology: vertex references",
            u32::MAX as u128,
        ))),
    }
}

/// The vertex order: `None` for the input order, else the complex materialised in the new
/// order and `to_old`. Auto: the input order unless it has many local minima, then the order
/// of first appearance in the cells unless that has many too, then breadth-first (over the
/// first-appearance numbering, whose cells lie close in memory). A complex whose vertex
/// references overflow 32 bits keeps the input order.
fn choose_order<S: TopCells + ?Sized>(s: &S, o: VertexOrder) -> Option<(order::Flat, Vec<u32>)> {
    let fa = pick_order(s, o, None, None)?;
    let t = std::time::Instant::now();
    let f = order::Flat::new(s, &fa)?;
    debug_time("first-appearance order", t);
    Some(finish_order(f, fa, o))
}

/// `None` when the input order is kept (asked, few local minima, or more than 2^32 vertex
/// references: `refs` when known, else counted), else the first-appearance numbering
/// `to_new[old]`. `k`: the same cells as an indexed complex, read directly (faster).
fn pick_order<S: TopCells + ?Sized>(
    s: &S,
    o: VertexOrder,
    refs: Option<u64>,
    k: Option<&IndexedComplex>,
) -> Option<Vec<u32>> {
    let nv = s.n_vertices();
    let few = 64 + nv / 1000;
    let t = std::time::Instant::now();
    match o {
        VertexOrder::Input => return None,
        VertexOrder::Auto => {
            let minima = match k {
                Some(k) => order::count_minima_slices(nv, order::complex_cells(k), None),
                None => order::count_minima(s, None),
            };
            debug_time("local minima", t);
            if minima <= few {
                return None;
            }
        }
        _ => {}
    }
    let refs = refs.unwrap_or_else(|| {
        let mut verts = Vec::new();
        (0..s.n_top_cells())
            .map(|c| {
                verts.clear();
                s.top_cell_vertices(CellId(c as u32), &mut verts);
                verts.len() as u64
            })
            .sum()
    });
    if refs >= u32::MAX as u64 {
        return None;
    }
    Some(match k {
        Some(k) => order::first_appearance_slices(nv, order::complex_cells(k)),
        None => order::first_appearance_order(s),
    })
}

/// Breadth-first over the first-appearance copy `f` when asked (or, for Auto, when it still
/// has many local minima); returns the copy in its final numbering and `to_old`.
fn finish_order(mut f: order::Flat, fa: Vec<u32>, o: VertexOrder) -> (order::Flat, Vec<u32>) {
    let nv = f.n_vertices();
    let few = 64 + nv / 1000;
    let t = std::time::Instant::now();
    let bfs = match o {
        VertexOrder::FirstAppearance => false,
        VertexOrder::BreadthFirst => true,
        _ => order::count_minima_slices(nv, f.cells(), None) > few,
    };
    let mut to_old = fa;
    if bfs {
        let b = order::bfs_order_flat(&f);
        // to_old = (b ∘ fa)^-1, built in the buffer of fa (fa[old] is read before it is
        // overwritten: the composition is written to `b`'s place first)
        let mut composed = b.clone();
        for (old, &x) in to_old.iter().enumerate() {
            composed[x as usize] = old as u32; // composed = fa^-1 (indexed by fa-number)
        }
        // to_old[b[y]] = fa^-1[y]
        for (y, &by) in b.iter().enumerate() {
            to_old[by as usize] = composed[y];
        }
        drop(composed);
        f.relabel(&b);
        debug_time("breadth-first order", t);
    } else {
        let mut inv = vec![0u32; nv];
        for (old, &x) in to_old.iter().enumerate() {
            inv[x as usize] = old as u32;
        }
        to_old = inv;
    }
    (f, to_old)
}

/// Maps a cell of a relabeled view back to input numbering (sign of the change of orientation).
fn map_back(c: &Cell, to_old: Option<&[u32]>) -> (Vec<u32>, i64) {
    let Some(t) = to_old else {
        return (c.verts.to_vec(), 1);
    };
    let g: Vec<u32> = c.verts.iter().map(|&v| t[v as usize]).collect();
    match c.shape {
        cells::Shape::Simplex => {
            let (k, sg) = cells::sort_with_sign(&g);
            (k.to_vec(), sg as i64)
        }
        cells::Shape::Quad => {
            let (q, sg) = cells::canonical_quad([g[0], g[1], g[2], g[3]]);
            (q.verts.to_vec(), sg as i64)
        }
        cells::Shape::Solid(_) => (g, 1),
    }
}

/// Phase timings on stderr when `STARPLEX_HOMOLOGY_TIMES` is set.
fn debug_time(what: &str, t: std::time::Instant) {
    if std::env::var_os("STARPLEX_HOMOLOGY_TIMES").is_some() {
        eprintln!("homology: {what}: {:.3} s", t.elapsed().as_secs_f64());
    }
}

fn homology_ordered<S: TopCells + VertexStar + Sync + ?Sized>(
    s: &S,
    fast: Option<morse::FastStar<'_>>,
    opts: &HomologyOptions,
    to_old: Option<&[u32]>,
) -> Result<Homology, HomologyError> {
    let nv = s.n_vertices();
    let (simplicial, dmax) = scan_kinds(s, fast);
    let Some(dmax) = dmax.or(if nv > 0 { Some(0) } else { None }) else {
        return Ok(Homology {
            field: opts.field,
            betti: vec![],
            torsion: vec![],
            critical: vec![],
            components: opts.per_component.then(Vec::new),
            generators: vec![],
        });
    };
    let t0 = std::time::Instant::now();
    let g = morse_gradient(s, fast, opts, simplicial, dmax, t0)?;
    let critical: Vec<u64> = g.crit.iter().map(|l| l.len() as u64).collect();

    // components
    let comps = if opts.per_component {
        components(s)
    } else {
        // one label for everything: totals need no components
        crate::algo::components::Components {
            n_components: 1,
            label: vec![0; nv],
        }
    };
    debug_time("components", t0);
    let n_comp = comps.n_components;
    let comp_of = |c: &Cell| comps.label[c.key[0] as usize];
    let comp_labels: Vec<Vec<u32>> = g
        .crit
        .iter()
        .map(|l| l.iter().map(comp_of).collect())
        .collect();

    let m = opts.field.modulus();
    // per component Betti numbers and torsion
    let mut rank = vec![vec![0u64; n_comp]; dmax + 2]; // rank[k] = rank of ∂_k per component
    let mut tors: Vec<Vec<Vec<u128>>> = vec![vec![Vec::new(); n_comp]; dmax + 1];
    let mut generators = Vec::new();
    if m > 0 {
        let red = field_ranks(&g, m, simplicial, opts.generators, &comp_labels, &mut rank)?;
        if opts.generators {
            generators = field_generators(&g, m, red, to_old)?;
        }
    } else {
        let max_dense = usize::try_from(opts.limits.dense_entries).unwrap_or(usize::MAX);
        integer_ranks(
            &g,
            opts.field,
            max_dense,
            &comp_labels,
            n_comp,
            &mut rank,
            &mut tors,
        )?;
    }
    debug_time("boundaries and ranks", t0);
    let (betti, torsion, per) =
        betti_per_component(s, opts, &comps, &comp_labels, &rank, &tors, to_old);
    for g in &mut generators {
        g.cells.sort();
    }
    Ok(Homology {
        field: opts.field,
        betti,
        torsion,
        critical,
        components: opts.per_component.then_some(per),
        generators,
    })
}

/// Whether every top cell is a simplex, and the largest top-cell dimension (`None` without
/// top cells).
fn scan_kinds<S: TopCells + Sync + ?Sized>(
    s: &S,
    fast: Option<morse::FastStar<'_>>,
) -> (bool, Option<usize>) {
    match fast {
        // simplices of one arity: no scan of the kinds
        Some(f) if s.n_top_cells() > 0 => (true, Some(f.arity - 1)),
        _ => (
            (0..s.n_top_cells())
                .into_par_iter()
                .all(|c| s.top_cell_kind(CellId(c as u32)).is_simplex()),
            (0..s.n_top_cells())
                .into_par_iter()
                .map(|c| s.top_cell_kind(CellId(c as u32)).dim())
                .max(),
        ),
    }
}

/// The discrete gradient: in one pass, the plan of every lower star, and the critical cells of
/// those enumerated (the enumeration stops as soon as the budget is known to be exceeded; the
/// decision itself depends only on the plans, so it is the same for any thread count).
fn morse_gradient<'a, S: TopCells + VertexStar + Sync + ?Sized>(
    s: &'a S,
    fast: Option<morse::FastStar<'a>>,
    opts: &HomologyOptions,
    simplicial: bool,
    dmax: usize,
    t0: std::time::Instant,
) -> Result<Gradient<'a, S>, HomologyError> {
    let nv = s.n_vertices();
    let progress = |n: usize| {
        if let Some(p) = &opts.progress {
            p(n as u64);
        }
    };
    let spent = std::sync::atomic::AtomicU64::new(0);
    let over = std::sync::atomic::AtomicBool::new(false);
    let budget = u64::try_from(opts.limits.homology_cells).unwrap_or(u64::MAX);
    let max_star = opts.limits.lower_star_simplices;
    type Part = (Vec<u32>, u128, u128, Vec<Cell>);
    let parts: Vec<Part> = (0..nv.div_ceil(CHUNK))
        .into_par_iter()
        .map_init(
            || Scratch::new(simplicial),
            |w, ci| {
                use std::sync::atomic::Ordering::Relaxed;
                let lo = ci * CHUNK;
                let hi = (lo + CHUNK).min(nv);
                let mut apex = Vec::with_capacity(hi - lo);
                let (mut est, mut worst) = (0u128, 0u128);
                let mut out = Vec::new();
                for v in lo..hi {
                    let p = morse::plan_vertex(s, fast, v as u32, w);
                    if p.apex == EXPLICIT {
                        est = est.saturating_add(p.estimate);
                        worst = worst.max(p.estimate);
                        let e = u64::try_from(p.estimate).unwrap_or(u64::MAX);
                        if p.estimate > max_star
                            || spent.fetch_add(e.min(1 << 40), Relaxed).saturating_add(e) > budget
                        {
                            over.store(true, Relaxed);
                        }
                    }
                    if (p.apex == ALONE || p.apex == EXPLICIT) && !over.load(Relaxed) {
                        morse::critical_cells(s, v as u32, p.apex, w, &mut out);
                    }
                    apex.push(p.apex);
                }
                progress(hi - lo);
                (apex, est, worst, out)
            },
        )
        .collect();
    let est = parts.iter().fold(0u128, |a, p| a.saturating_add(p.1));
    let worst = parts.iter().map(|p| p.2).max().unwrap_or(0);
    if est > opts.limits.homology_cells || worst > max_star {
        return Err(HomologyError::TooLarge(TooLarge::new(
            "homology: cells of the lower stars to enumerate",
            est,
            opts.limits.homology_cells.min(if worst > max_star {
                max_star
            } else {
                u128::MAX
            }),
            Unit::Simplices,
        )));
    }
    let mut apex: Vec<u32> = Vec::with_capacity(nv);
    let mut crit_lists = Vec::with_capacity(parts.len());
    for p in parts {
        apex.extend(p.0);
        crit_lists.push(p.3);
    }
    debug_time("plan and critical cells", t0);
    if std::env::var_os("STARPLEX_HOMOLOGY_TIMES").is_some() {
        let explicit = apex.iter().filter(|&&a| a == EXPLICIT).count();
        let alone = apex.iter().filter(|&&a| a == ALONE).count();
        eprintln!("homology: {nv} vertices, {explicit} explicit lower stars, {alone} alone");
    }
    let mut crit: Vec<Vec<Cell>> = vec![Vec::new(); dmax + 1];
    for c in crit_lists.into_iter().flatten() {
        let d = c.dim();
        crit[d].push(c);
    }
    for l in &mut crit {
        l.sort_unstable_by(|a, b| a.key.cmp(&b.key));
    }
    let g = Gradient {
        s,
        fast,
        apex: apex.into(),
        crit: crit.into(),
    };
    debug_time("critical cells", t0);
    Ok(g)
}

fn flow_err(_: morse::Overflow) -> HomologyError {
    HomologyError::Overflow("the Morse boundary".into())
}

/// What the reduction over Z/p keeps for the generators: per dimension, the rows that are
/// pivots (boundaries), the reduction matrix `V` when tracked, and the columns reduced to zero
/// (cycles).
struct FieldReduction {
    essential_rows: Vec<Vec<bool>>,
    vs: Vec<Option<Vec<reduce::Column>>>,
    zero_cols: Vec<Vec<bool>>,
}

/// Ranks of the Morse boundaries over Z/`m` per component (into `rank`), from the top dimension
/// down, with clearing (the pivot rows of ∂_{k+1} are skipped as columns of ∂_k).
fn field_ranks<S: TopCells + VertexStar + Sync + ?Sized>(
    g: &Gradient<'_, S>,
    m: i64,
    simplicial: bool,
    generators: bool,
    comp_labels: &[Vec<u32>],
    rank: &mut [Vec<u64>],
) -> Result<FieldReduction, HomologyError> {
    let dmax = g.crit.len() - 1;
    let mut cleared: Vec<bool> = Vec::new();
    let mut essential_rows: Vec<Vec<bool>> = vec![Vec::new(); dmax + 2];
    let mut vs: Vec<Option<Vec<reduce::Column>>> = vec![None; dmax + 1];
    let mut zero_cols: Vec<Vec<bool>> = vec![Vec::new(); dmax + 1];
    for k in (1..=dmax).rev() {
        let n = g.crit[k].len();
        if cleared.len() != n {
            cleared = vec![false; n];
        }
        let no_rows = g.crit[k - 1].is_empty();
        if k == dmax
            && simplicial
            && !generators
            && !no_rows
            && let Some(next) = coboundary_pairs(g, k, m, &cleared, comp_labels, rank)?
        {
            essential_rows[k - 1] = next.clone();
            cleared = next;
            continue;
        }
        let cols: Vec<Option<reduce::Column>> = (0..n)
            .into_par_iter()
            .map_init(Scratch::default, |w, j| {
                if cleared[j] {
                    return Ok(None);
                }
                if no_rows {
                    // nothing critical below: every Morse boundary is zero
                    return Ok(Some(Vec::new()));
                }
                let col = g.flow(&[(g.crit[k][j].clone(), 1)], m, None, w)?;
                Ok(Some(col))
            })
            .collect::<Result<_, _>>()
            .map_err(flow_err)?;
        let r = reduce::reduce(cols, g.crit[k - 1].len(), m, generators);
        let mut next = vec![false; g.crit[k - 1].len()];
        let mut zc = vec![false; n];
        for (j, l) in r.low.iter().enumerate() {
            match l {
                Some(row) => {
                    next[*row as usize] = true;
                    rank[k][comp_labels[k][j] as usize] += 1;
                }
                None => zc[j] = !cleared[j],
            }
        }
        zero_cols[k] = zc;
        essential_rows[k - 1] = next.clone();
        vs[k] = r.v;
        cleared = next;
    }
    Ok(FieldReduction {
        essential_rows,
        vs,
        zero_cols,
    })
}

/// One cycle per essential class over Z/`m`: every zero column that is not a pivot row, its
/// combination of critical cells flowed back to cells of the complex (input numbering).
fn field_generators<S: TopCells + VertexStar + Sync + ?Sized>(
    g: &Gradient<'_, S>,
    m: i64,
    mut red: FieldReduction,
    to_old: Option<&[u32]>,
) -> Result<Vec<Generator>, HomologyError> {
    let dmax = g.crit.len() - 1;
    let mut generators = Vec::new();
    red.zero_cols[0] = vec![true; g.crit[0].len()];
    for k in 0..=dmax {
        let pivots = &red.essential_rows[k];
        for j in 0..g.crit[k].len() {
            let is_pivot = pivots.get(j).copied().unwrap_or(false);
            if !red.zero_cols[k][j] || is_pivot {
                continue;
            }
            let combo: Vec<(Cell, i64)> = match &red.vs[k] {
                Some(v) => v[j]
                    .iter()
                    .map(|&(i, c)| (g.crit[k][i as usize].clone(), c))
                    .collect(),
                None => vec![(g.crit[k][j].clone(), 1)],
            };
            let mut chain: BTreeMap<Key, (Cell, i64)> = BTreeMap::new();
            let mut w = Scratch::default();
            g.flow(&combo, m, Some(&mut chain), &mut w)
                .map_err(flow_err)?;
            generators.push(Generator {
                dim: k,
                cells: chain
                    .into_values()
                    .map(|(c, x)| {
                        let (v, sg) = map_back(&c, to_old);
                        (v, (x * sg).rem_euclid(m))
                    })
                    .collect(),
            });
        }
    }
    Ok(generators)
}

/// Ranks (and, over Z, torsion) of the Morse boundaries with integer coefficients per
/// component, by the Smith normal form (into `rank` and `tors`).
fn integer_ranks<S: TopCells + VertexStar + Sync + ?Sized>(
    g: &Gradient<'_, S>,
    field: Field,
    max_dense: usize,
    comp_labels: &[Vec<u32>],
    n_comp: usize,
    rank: &mut [Vec<u64>],
    tors: &mut [Vec<Vec<u128>>],
) -> Result<(), HomologyError> {
    let dmax = g.crit.len() - 1;
    for k in 1..=dmax {
        let n = g.crit[k].len();
        let cols: Vec<Vec<(u32, i64)>> = (0..n)
            .into_par_iter()
            .map_init(Scratch::default, |w, j| {
                if g.crit[k - 1].is_empty() {
                    return Ok(Vec::new());
                }
                g.flow(&[(g.crit[k][j].clone(), 1)], 0, None, w)
            })
            .collect::<Result<_, _>>()
            .map_err(flow_err)?;
        let r = smith::int_rank(
            &cols,
            g.crit[k - 1].len(),
            &comp_labels[k],
            &comp_labels[k - 1],
            n_comp,
            max_dense,
        )
        .map_err(|e| match e {
            smith::IntError::Overflow => HomologyError::Overflow("the Smith normal form".into()),
            smith::IntError::TooLarge(n) => HomologyError::TooLarge(TooLarge::new(
                "homology over Z: dense Smith normal form entries",
                n,
                max_dense as u128,
                Unit::Items,
            )),
        })?;
        for c in 0..n_comp {
            rank[k][c] = r.rank[c] as u64;
            if field == Field::Z {
                tors[k - 1][c] = r.torsion[c].iter().map(|&x| x as u128).collect();
            }
        }
    }
    Ok(())
}

/// Betti numbers and torsion in total and per component (with the surface facts of each
/// component of a 2-complex), from the critical cells and the boundary ranks.
#[allow(clippy::type_complexity)]
fn betti_per_component<S: TopCells + VertexStar + Sync + ?Sized>(
    s: &S,
    opts: &HomologyOptions,
    comps: &crate::algo::components::Components,
    comp_labels: &[Vec<u32>],
    rank: &[Vec<u64>],
    tors: &[Vec<Vec<u128>>],
    to_old: Option<&[u32]>,
) -> (Vec<u64>, Vec<Vec<u128>>, Vec<ComponentHomology>) {
    let dmax = comp_labels.len() - 1;
    let n_comp = comps.n_components;
    let mut crit_per_comp = vec![vec![0u64; n_comp]; dmax + 1];
    for k in 0..=dmax {
        for &l in &comp_labels[k] {
            crit_per_comp[k][l as usize] += 1;
        }
    }
    let betti_of = |c: usize| -> Vec<u64> {
        (0..=dmax)
            .map(|k| crit_per_comp[k][c] - rank[k][c] - rank[k + 1][c])
            .collect()
    };
    let mut betti = vec![0u64; dmax + 1];
    let mut torsion = vec![Vec::new(); dmax + 1];
    let mut per = Vec::new();
    let facts =
        (opts.per_component && dmax == 2).then(|| surface::surface_facts(s, &comps.label, n_comp));
    let mut first_vertex = vec![u32::MAX; n_comp];
    for (v, &l) in comps.label.iter().enumerate() {
        let old = to_old.map_or(v as u32, |t| t[v]);
        first_vertex[l as usize] = first_vertex[l as usize].min(old);
    }
    for c in 0..n_comp {
        let b = betti_of(c);
        for (t, x) in betti.iter_mut().zip(&b) {
            *t += x;
        }
        let tc: Vec<Vec<u128>> = (0..=dmax).map(|k| tors[k][c].clone()).collect();
        for k in 0..=dmax {
            torsion[k].extend(tc[k].iter().copied());
        }
        if opts.per_component {
            let chi = alt_sum(&b);
            let surface = facts.as_ref().and_then(|f| {
                let f = f[c];
                f.is_surface.then(|| {
                    let x = 2 - chi - f.boundary_loops as i64;
                    Surface {
                        orientable: f.orientable,
                        genus: if f.orientable {
                            (x / 2).max(0)
                        } else {
                            x.max(0)
                        } as u64,
                        boundary_loops: f.boundary_loops,
                        euler_characteristic: chi,
                    }
                })
            });
            per.push(ComponentHomology {
                first_vertex: first_vertex[c],
                betti: b,
                torsion: tc,
                surface,
            });
        }
    }
    for t in &mut torsion {
        t.sort_unstable();
    }
    per.sort_by_key(|c: &ComponentHomology| c.first_vertex);
    (betti, torsion, per)
}

/// The pairs of the Morse boundary matrix of dimension `k` found from the other side: the
/// Morse *coboundary* of every critical (k-1)-cell (gradient paths followed upwards, which on a
/// manifold's top dimension are single paths, where the boundary flows cover every top cell),
/// reduced as the anti-transposed matrix (same pairs, hence same ranks). Columns of `cleared`
/// cells (known to reduce to zero) are left out. Adds the ranks per component to `rank[k]`
/// and returns the (k-1)-cells that are pivots (to clear in dimension k-1); `None` when the
/// upward paths exceed a work budget of half the top cells (then the boundary flows are
/// cheaper; the outcome is the same for any thread count).
fn coboundary_pairs<S: TopCells + VertexStar + Sync + ?Sized>(
    g: &Gradient<'_, S>,
    k: usize,
    m: i64,
    cleared: &[bool],
    comp_labels: &[Vec<u32>],
    rank: &mut [Vec<u64>],
) -> Result<Option<Vec<bool>>, HomologyError> {
    let n = g.crit[k].len();
    let n_low = g.crit[k - 1].len();
    let budget = std::sync::atomic::AtomicI64::new((g.s.n_top_cells() as i64 / 2).max(10_000));
    let rows: Result<Vec<reduce::Column>, morse::CoflowError> = (0..n_low)
        .into_par_iter()
        .map_init(Scratch::default, |w, j| {
            g.coflow(&g.crit[k - 1][j], m, &budget, w)
        })
        .collect();
    let rows = match rows {
        Ok(r) => r,
        Err(morse::CoflowError::OverBudget) => return Ok(None),
        Err(morse::CoflowError::Overflow) => {
            return Err(HomologyError::Overflow("the Morse coboundary".into()))
        }
    };
    // the anti-transpose: columns are the (k-1)-cells last first, rows the k-cells last first
    let cols: Vec<Option<reduce::Column>> = rows
        .iter()
        .rev()
        .map(|r| {
            Some(
                r.iter()
                    .rev()
                    .filter(|&&(t, _)| !cleared[t as usize])
                    .map(|&(t, c)| (n as u32 - 1 - t, c))
                    .collect(),
            )
        })
        .collect();
    let r = reduce::reduce(cols, n, m, false);
    let mut next = vec![false; n_low];
    for (j, l) in r.low.iter().enumerate() {
        if let Some(row) = l {
            let tau = n - 1 - *row as usize;
            next[n_low - 1 - j] = true;
            rank[k][comp_labels[k][tau] as usize] += 1;
        }
    }
    Ok(Some(next))
}

/// The vertices of a 1-cycle listed as one closed path (each edge sharing its first vertex
/// with the end of the previous one, the last closing on the first), else `None`.
fn closed_path(g: &Generator) -> Option<Vec<u32>> {
    if g.dim != 1 || g.cells.len() < 3 {
        return None;
    }
    let (first, second) = (&g.cells[0].0, &g.cells[1].0);
    // the start: the vertex of the first edge that is not on the second
    let start = *first.iter().find(|v| !second.contains(v))?;
    let mut path = vec![start];
    let mut at = start;
    for (e, _) in &g.cells {
        let [a, b] = e[..] else { return None };
        at = if a == at {
            b
        } else if b == at {
            a
        } else {
            return None;
        };
        path.push(at);
    }
    (path.pop() == Some(start)).then_some(path)
}

/// Writes generators as an OBJ file a viewer can show: every vertex of the complex (`v x y z`,
/// coordinates padded or cut to 3), then one group per generator (`g h1_0`, `g h2_0`, ...)
/// holding its cells: `p` for vertices, `l` for edges, `f` for triangles and quads, and for
/// cells of dimension 3 or more their boundary triangles as `f` lines (a comment line
/// `# cell a b c d` names each such cell). Coefficients other than 1 are written as comments.
/// An H_1 generator whose edges are listed along one closed path (the short loops of surfaces
/// and graphs) is written as a single polyline `l a b c ... a`, its direction giving the signs.
///
/// ```
/// use starplex::algo::homology::{write_generators_obj, Generator};
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// let mut b = ComplexBuilder::new(2).unwrap();
/// for p in [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// for e in [[0, 1], [1, 2], [2, 3], [0, 3]] { b.push_cell(CellKind::Simplex(1), &e).unwrap(); }
/// let k = b.build(&BuildOptions::default()).unwrap().0;
/// let edges = |l: &[[u32; 2]]| l.iter().map(|e| (e.to_vec(), 1)).collect();
/// let g = Generator { dim: 1, cells: edges(&[[0, 1], [1, 2], [2, 3], [0, 3]]) };
/// let mut out = Vec::new();
/// write_generators_obj(&k, &[g], &mut out).unwrap();
/// assert!(String::from_utf8(out).unwrap().contains("g h1_0\nl 1 2 3 4 1\n"));
/// // edges not listed along their path: one line each
/// let g = Generator { dim: 1, cells: edges(&[[0, 1], [0, 3], [1, 2], [2, 3]]) };
/// let mut out = Vec::new();
/// write_generators_obj(&k, &[g], &mut out).unwrap();
/// assert!(String::from_utf8(out).unwrap().contains("g h1_0\nl 1 2\nl 1 4\nl 2 3\nl 3 4\n"));
/// ```
///
/// # Errors
/// Errors of the writer.
pub fn write_generators_obj(
    k: &IndexedComplex,
    gens: &[Generator],
    mut w: impl Write,
) -> std::io::Result<()> {
    writeln!(
        w,
        "# starplex homology generators: one group per class (g hK_i)"
    )?;
    let d = k.ambient_dim();
    for p in k.coords().chunks_exact(d.max(1)) {
        let c = |i: usize| p.get(i).copied().unwrap_or(0.0);
        writeln!(w, "v {} {} {}", c(0), c(1), c(2))?;
    }
    let mut count: BTreeMap<usize, usize> = BTreeMap::new();
    for g in gens {
        let i = count.entry(g.dim).or_insert(0);
        writeln!(w, "g h{}_{}", g.dim, i)?;
        *i += 1;
        if let Some(path) = closed_path(g) {
            let idx: Vec<String> = path.iter().map(|v| (v + 1).to_string()).collect();
            writeln!(w, "l {} {}", idx.join(" "), idx[0])?;
            continue;
        }
        for (cell, coef) in &g.cells {
            if *coef != 1 {
                writeln!(w, "# coefficient {coef}")?;
            }
            let idx: Vec<String> = cell.iter().map(|v| (v + 1).to_string()).collect();
            match cell.len() {
                1 => writeln!(w, "p {}", idx[0])?,
                2 => writeln!(w, "l {}", idx.join(" "))?,
                3 | 4 if g.dim == 2 => writeln!(w, "f {}", idx.join(" "))?,
                _ => {
                    writeln!(w, "# cell {}", idx.join(" "))?;
                    if g.dim >= 3 && cell.len() == g.dim + 1 {
                        // boundary triangles of a simplex
                        let n = cell.len();
                        for a in 0..n {
                            for b in a + 1..n {
                                for c in b + 1..n {
                                    writeln!(w, "f {} {} {}", idx[a], idx[b], idx[c])?;
                                }
                            }
                        }
                    }
                }
            }
        }
    }
    Ok(())
}
