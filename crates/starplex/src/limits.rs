//! One vocabulary for limits, shared by every module: the budgets starplex checks *before* large
//! work ([`Limits`]), the error it gives when an input or a request would exceed one
//! ([`TooLarge`]), and the error it gives when an algorithm that needs simplices meets a CP cell
//! ([`NotSimplicial`]).
//!
//! Each module's error enum wraps these two structs in variants of the same names
//! (`QueryError::TooLarge(TooLarge)`, `SimplifyError::NotSimplicial(NotSimplicial)`, ...), so a
//! caller matches one shape everywhere, and [`crate::Error`] gathers every module's error for
//! code that wants one type.
//!
//! ```
//! use starplex::limits::{Limits, TooLarge, Unit};
//! let limits = Limits::default();
//! let need: u128 = 1 << 40;
//! if need > limits.query_simplices {
//!     let e = TooLarge::new("faces of cell 7", need, limits.query_simplices, Unit::Simplices);
//!     assert_eq!(
//!         e.to_string(),
//!         "faces of cell 7: about 1099511627776 simplices, over the budget of 50000000"
//!     );
//! }
//! ```

use crate::cell::CellKind;

/// Simplices one query may enumerate (the faces of a cell, a level of a star, a link) unless
/// the caller passes its own budget.
pub const QUERY_SIMPLICES: u128 = 50_000_000;
/// Faces one Stellar-tree face relation (`p_faces`, p-face adjacency) may enumerate.
pub const STELLAR_FACES: u128 = 2_000_000_000;
/// Cells of all lower stars homology's Morse reduction may enumerate.
pub const HOMOLOGY_CELLS: u128 = 4_000_000_000;
/// Simplices one lower star may hold in homology's Morse reduction.
pub const LOWER_STAR_SIMPLICES: u128 = 1 << 26;
/// Entries of the dense remainder of homology's integer elimination.
pub const DENSE_ENTRIES: u128 = 50_000_000;
/// Simplices a structure that stores every simplex (the simplex tree, the incidence graph, IS,
/// the Hasse diagram) may hold; more is refused with an estimate before anything is allocated.
pub const STORED_SIMPLICES: u128 = 1 << 31;
/// (cell, face) pairs the f-vector pass of [`info`](crate::algo::info::info) may visit; above
/// it the f-vector is skipped and an estimate reported.
pub const INFO_FACES: u128 = 4_000_000_000;
/// Ids are 32-bit (`u32::MAX` is reserved): at most this many vertices or cells in one complex.
pub const MAX_IDS: u128 = u32::MAX as u128 - 1;

/// What a [`TooLarge`] counts, for its message.
///
/// ```
/// use starplex::limits::Unit;
/// assert_eq!(Unit::Bytes.to_string(), "bytes");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Unit {
    /// Simplices or faces to enumerate.
    Simplices,
    /// Generic items (tree nodes, leaf entries, matrix entries).
    Items,
    /// Bytes of memory or output.
    Bytes,
    /// Ids of one kind (vertices, cells, points), against the 32-bit id space.
    Ids,
}

impl std::fmt::Display for Unit {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Unit::Simplices => "simplices",
            Unit::Items => "items",
            Unit::Bytes => "bytes",
            Unit::Ids => "ids",
        })
    }
}

/// A request or an input over a budget, refused before the work or the allocation: what would
/// be too large, the estimate, and the budget it exceeds.
///
/// ```
/// use starplex::limits::{TooLarge, Unit};
/// let e = TooLarge::ids("vertices", 5_000_000_000);
/// assert_eq!(e.estimate, 5_000_000_000);
/// assert!(e.to_string().contains("32-bit"), "{e}");
/// ```
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{}", self.message())]
pub struct TooLarge {
    /// What would be too large ("faces of dimension 3", "the neighbourhood graph", "vertices").
    pub what: String,
    /// How many (a count or an estimate; `u64::MAX` means at least that many).
    pub estimate: u64,
    /// The budget it exceeds.
    pub budget: u64,
    /// What `estimate` and `budget` count.
    pub unit: Unit,
}

impl TooLarge {
    /// `what` would need `estimate` of `unit`, over `budget`.
    ///
    /// ```
    /// use starplex::limits::{TooLarge, Unit};
    /// let e = TooLarge::new("the link of vertex 3", 90, 10, Unit::Simplices);
    /// assert_eq!(e.budget, 10);
    /// // estimates past u64 saturate and say so
    /// let huge = TooLarge::new("faces", 1 << 100, 10, Unit::Simplices);
    /// assert!(huge.to_string().starts_with("faces: more than 18446744073709551615"));
    /// ```
    pub fn new(what: impl Into<String>, estimate: u128, budget: u128, unit: Unit) -> TooLarge {
        // u64 keeps the error small (it travels inside io errors); larger estimates saturate
        let sat = |x: u128| x.min(u64::MAX as u128) as u64;
        TooLarge {
            what: what.into(),
            estimate: sat(estimate),
            budget: sat(budget),
            unit,
        }
    }

    /// `count` ids of `what`, more than 32-bit ids address.
    ///
    /// ```
    /// use starplex::limits::{TooLarge, MAX_IDS};
    /// assert_eq!(TooLarge::ids("cells", 1 << 33).budget as u128, MAX_IDS);
    /// ```
    pub fn ids(what: impl Into<String>, count: u128) -> TooLarge {
        TooLarge::new(what, count, MAX_IDS, Unit::Ids)
    }

    fn message(&self) -> String {
        if self.estimate == u64::MAX {
            return format!(
                "{}: more than {} {}, over the budget of {}",
                self.what, self.estimate, self.unit, self.budget
            );
        }
        match self.unit {
            Unit::Ids => format!(
                "too many {}: {} (starplex ids are 32-bit, at most {})",
                self.what, self.estimate, self.budget
            ),
            Unit::Bytes => format!(
                "{}: about {} bytes, over the memory budget of {} bytes",
                self.what, self.estimate, self.budget
            ),
            u => format!(
                "{}: about {} {u}, over the budget of {}",
                self.what, self.estimate, self.budget
            ),
        }
    }
}

/// A CP cell (quad, hexahedron, prism, pyramid, polygon) given to an algorithm or a structure
/// that needs simplices, with the way out.
///
/// ```
/// use starplex::cell::CellKind;
/// use starplex::limits::NotSimplicial;
/// let e = NotSimplicial::new(3, CellKind::Quad, "simplification");
/// assert_eq!(
///     e.to_string(),
///     "cell 3 is a quad: simplification works on simplicial complexes; \
///      triangulate first with `starplex convert --triangulate IN OUT`"
/// );
/// ```
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("cell {cell} is a {kind}: {what} works on simplicial complexes; {hint}")]
pub struct NotSimplicial {
    /// The first CP cell found (input id).
    pub cell: u64,
    /// Its kind, as a name ("quad", "hex", ...).
    pub kind: String,
    /// What needs simplices ("simplification", "the simplex tree", ...).
    pub what: String,
    /// What to do instead.
    pub hint: String,
}

/// The default way out of a [`NotSimplicial`].
pub const TRIANGULATE_HINT: &str = "triangulate first with `starplex convert --triangulate IN OUT`";

impl NotSimplicial {
    /// Cell `cell` of kind `kind` met by `what`; the hint says to triangulate.
    ///
    /// ```
    /// use starplex::cell::CellKind;
    /// use starplex::limits::NotSimplicial;
    /// assert_eq!(NotSimplicial::new(0, CellKind::Hex, "IS").kind, "hex");
    /// ```
    pub fn new(cell: u64, kind: CellKind, what: impl Into<String>) -> NotSimplicial {
        NotSimplicial {
            cell,
            kind: kind.to_string(),
            what: what.into(),
            hint: TRIANGULATE_HINT.to_string(),
        }
    }

    /// The same error with another way out.
    ///
    /// ```
    /// use starplex::cell::CellKind;
    /// use starplex::limits::NotSimplicial;
    /// let e = NotSimplicial::new(0, CellKind::Quad, "IS").with_hint("use the IA*");
    /// assert!(e.to_string().ends_with("; use the IA*"));
    /// ```
    pub fn with_hint(mut self, hint: impl Into<String>) -> NotSimplicial {
        self.hint = hint.into();
        self
    }
}

/// The budgets in one value, each defaulting to the constant of this module (and memory to a
/// third of the available memory). Functions that take a budget take one of these fields.
///
/// ```
/// use starplex::limits::{Limits, QUERY_SIMPLICES};
/// let l = Limits::default();
/// assert_eq!(l.query_simplices, QUERY_SIMPLICES);
/// assert!(l.memory_bytes > 0);
/// let tight = Limits { query_simplices: 1_000, ..Limits::default() };
/// assert!(tight.query_simplices < l.query_simplices);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Limits {
    /// Simplices one query may enumerate ([`QUERY_SIMPLICES`]).
    pub query_simplices: u128,
    /// Faces one Stellar face relation may enumerate ([`STELLAR_FACES`]).
    pub stellar_faces: u128,
    /// Cells of all lower stars homology's Morse reduction may enumerate ([`HOMOLOGY_CELLS`]).
    pub homology_cells: u128,
    /// Simplices in one lower star of homology's reduction ([`LOWER_STAR_SIMPLICES`]).
    pub lower_star_simplices: u128,
    /// Entries of homology's dense integer remainder ([`DENSE_ENTRIES`]).
    pub dense_entries: u128,
    /// Simplices a structure storing every simplex may hold ([`STORED_SIMPLICES`]).
    pub stored_simplices: u128,
    /// (cell, face) pairs `info`'s f-vector pass may visit ([`INFO_FACES`]).
    pub info_faces: u128,
    /// Bytes an output built in memory may take (a Rips complex, a neighbourhood graph, the
    /// cliques of a graph): [`default_memory_bytes`].
    pub memory_bytes: u64,
}

impl Default for Limits {
    fn default() -> Limits {
        Limits::with_memory(default_memory_bytes())
    }
}

impl Limits {
    /// The default budgets with this memory budget, without reading the available memory
    /// (`u64::MAX`: no memory budget).
    ///
    /// ```
    /// use starplex::limits::{Limits, STORED_SIMPLICES};
    /// let l = Limits::with_memory(1 << 20);
    /// assert_eq!((l.memory_bytes, l.stored_simplices), (1 << 20, STORED_SIMPLICES));
    /// assert_eq!(Limits { memory_bytes: 1 << 20, ..Limits::default() }, l);
    /// ```
    pub const fn with_memory(memory_bytes: u64) -> Limits {
        Limits {
            query_simplices: QUERY_SIMPLICES,
            stellar_faces: STELLAR_FACES,
            homology_cells: HOMOLOGY_CELLS,
            lower_star_simplices: LOWER_STAR_SIMPLICES,
            dense_entries: DENSE_ENTRIES,
            stored_simplices: STORED_SIMPLICES,
            info_faces: INFO_FACES,
            memory_bytes,
        }
    }
}

/// The default memory budget of an output built in memory: a third of the available memory
/// (`MemAvailable`), or 8 GiB where that cannot be read.
///
/// ```
/// assert!(starplex::limits::default_memory_bytes() > 0);
/// ```
pub fn default_memory_bytes() -> u64 {
    crate::measure::available_memory().map_or(8 << 30, |b| b / 3)
}
