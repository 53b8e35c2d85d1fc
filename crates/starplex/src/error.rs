//! [`Error`]: every module's error in one type, for code that calls several modules and wants
//! one `?`. Each module keeps its own precise error; limits are the shared
//! [`TooLarge`](crate::limits::TooLarge) and [`NotSimplicial`](crate::limits::NotSimplicial)
//! whichever module reports them, and [`Error::too_large`] / [`Error::not_simplicial`] find them.
//!
//! ```
//! use starplex::complex::{BuildOptions, ComplexBuilder};
//! use starplex::cell::CellKind;
//! use starplex::algo::simplify::{simplify, SimplifyOptions};
//!
//! fn run() -> Result<(), starplex::Error> {
//!     let mut b = ComplexBuilder::new(2)?;
//!     for p in [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]] {
//!         b.push_vertex(&p)?;
//!     }
//!     b.push_cell(CellKind::Quad, &[0, 1, 2, 3])?;
//!     let (k, _) = b.build(&BuildOptions::default())?;
//!     simplify(&k, &SimplifyOptions::default())?; // a quad: refused
//!     Ok(())
//! }
//! let e = run().unwrap_err();
//! assert_eq!(e.not_simplicial().map(|n| n.kind.as_str()), Some("quad"));
//! ```

use crate::limits::{NotSimplicial, TooLarge};

/// Any error of the library (see the module documentation).
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// Reading or writing a file.
    #[error(transparent)]
    Io(#[from] crate::io::IoError),
    /// Building an indexed complex.
    #[error(transparent)]
    Complex(#[from] crate::complex::ComplexError),
    /// A cell kind.
    #[error(transparent)]
    CellKind(#[from] crate::cell::CellKindError),
    /// Attributes.
    #[error(transparent)]
    Attr(#[from] crate::attr::AttrError),
    /// A relation query.
    #[error(transparent)]
    Query(#[from] crate::topo::QueryError),
    /// A link.
    #[error(transparent)]
    Link(#[from] crate::topo::link::LinkError),
    /// Building a structure by name.
    #[error(transparent)]
    Structure(#[from] crate::structures::StructureError),
    /// Building the simplex tree, IS or the incidence graph.
    #[error(transparent)]
    Build(#[from] crate::tds::simplex_tree::BuildError),
    /// Building the IA*.
    #[error(transparent)]
    IaStar(#[from] crate::tds::iastar::IaStarError),
    /// The Stellar tree.
    #[error(transparent)]
    Stellar(#[from] crate::stellar::StellarError),
    /// The Hasse complex.
    #[error(transparent)]
    Hasse(#[from] crate::hasse::HasseError),
    /// An edit of the Hasse complex.
    #[error(transparent)]
    Edit(#[from] crate::hasse::EditError),
    /// Simplification.
    #[error(transparent)]
    Simplify(#[from] crate::algo::simplify::SimplifyError),
    /// One contraction.
    #[error(transparent)]
    Contract(#[from] crate::algo::simplify::contract::ContractError),
    /// Homology.
    #[error(transparent)]
    Homology(#[from] crate::algo::homology::HomologyError),
    /// Surface summaries.
    #[error(transparent)]
    Surface(#[from] crate::algo::surface::SurfaceError),
    /// A graph or its cliques.
    #[error(transparent)]
    Graph(#[from] crate::algo::cliques::GraphError),
    /// A Rips complex.
    #[error(transparent)]
    Rips(#[from] crate::algo::rips::RipsError),
    /// A distance matrix.
    #[error(transparent)]
    DistanceMatrix(#[from] crate::algo::rips::DistanceMatrixError),
    /// Refinement generators.
    #[error(transparent)]
    Refine(#[from] crate::generate::refine::RefineError),
    /// Rendering.
    #[error(transparent)]
    Render(#[from] crate::render::RenderError),
    /// A shared limit reported directly.
    #[error(transparent)]
    TooLarge(#[from] TooLarge),
    /// A CP cell reported directly.
    #[error(transparent)]
    NotSimplicial(#[from] NotSimplicial),
}

impl Error {
    /// The limit this error reports, whichever module reported it.
    ///
    /// ```
    /// use starplex::limits::TooLarge;
    /// let e: starplex::Error = starplex::topo::QueryError::TooLarge(TooLarge::ids("cells", 1 << 40)).into();
    /// assert_eq!(e.too_large().unwrap().estimate, 1 << 40);
    /// ```
    pub fn too_large(&self) -> Option<&TooLarge> {
        use crate::topo::QueryError;
        match self {
            Error::TooLarge(t) => Some(t),
            Error::Complex(crate::complex::ComplexError::TooLarge(t))
            | Error::Query(QueryError::TooLarge(t))
            | Error::Link(crate::topo::link::LinkError::TooLarge(t))
            | Error::Build(crate::tds::simplex_tree::BuildError::TooLarge(t))
            | Error::Stellar(crate::stellar::StellarError::TooLarge(t))
            | Error::Hasse(crate::hasse::HasseError::TooLarge(t))
            | Error::Simplify(crate::algo::simplify::SimplifyError::TooLarge(t))
            | Error::Homology(crate::algo::homology::HomologyError::TooLarge(t))
            | Error::Graph(crate::algo::cliques::GraphError::TooLarge(t))
            | Error::DistanceMatrix(crate::algo::rips::DistanceMatrixError::TooLarge(t)) => Some(t),
            Error::Rips(crate::algo::rips::RipsError::Graph(
                crate::algo::cliques::GraphError::TooLarge(t),
            )) => Some(t),
            _ => None,
        }
    }

    /// The CP cell this error reports, whichever module reported it.
    ///
    /// ```
    /// use starplex::cell::CellKind;
    /// use starplex::tds::simplex_tree::BuildError;
    /// let e: starplex::Error = BuildError::cp_cell(2, CellKind::Hex).into();
    /// assert_eq!(e.not_simplicial().unwrap().cell, 2);
    /// ```
    pub fn not_simplicial(&self) -> Option<&NotSimplicial> {
        match self {
            Error::NotSimplicial(n)
            | Error::Build(crate::tds::simplex_tree::BuildError::NotSimplicial(n))
            | Error::Hasse(crate::hasse::HasseError::NotSimplicial(n))
            | Error::Simplify(crate::algo::simplify::SimplifyError::NotSimplicial(n)) => Some(n),
            _ => None,
        }
    }
}
