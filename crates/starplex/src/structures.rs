//! The registry of data structures: the one place that knows every structure answering the
//! [`Queries`] interface, its name, whether it holds CP cells, and how to build it from an
//! [`IndexedComplex`]. The CLI (`query --structure`, `compare`) and the bindings pick
//! structures through it.
//!
//! ```
//! use starplex::complex::{ComplexBuilder, BuildOptions};
//! use starplex::cell::CellKind;
//! use starplex::structures::{Structure, StructureOptions};
//! let mut b = ComplexBuilder::new(2).unwrap();
//! for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]] { b.push_vertex(&p).unwrap(); }
//! b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
//! b.push_cell(CellKind::Simplex(2), &[1, 3, 2]).unwrap();
//! let k = b.build(&BuildOptions::default()).unwrap().0;
//! for s in Structure::ALL {
//!     let q = s.build(&k, &StructureOptions::default()).unwrap();
//!     assert_eq!(q.f_vector().unwrap(), vec![4, 5, 2], "{}", s.name());
//! }
//! ```
use crate::complex::IndexedComplex;
use crate::hasse::HasseQueries;
use crate::limits::Limits;
use crate::stellar::{StellarOptions, StellarTree};
use crate::tds::iastar::IaStar;
use crate::tds::ig::IncidenceGraph;
use crate::tds::is::Is;
use crate::tds::simplex_tree::{SimplexTree, SimplexTreeOptions};
use crate::topo::{naive::VtIndex, Queries};

/// One data structure of the registry.
///
/// ```
/// use starplex::structures::Structure;
/// assert_eq!(Structure::from_name("ia-star"), Some(Structure::IaStar));
/// assert_eq!(Structure::IaStar.name(), "ia-star");
/// assert!(!Structure::SimplexTree.holds_cp());
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Structure {
    /// The indexed complex with its vertex → top cells relation (the baseline).
    Vt,
    /// IA*: top cells, adjacencies across facets, one top per cluster per vertex.
    IaStar,
    /// Simplex tree (with label lists).
    SimplexTree,
    /// Incidence graph: all cells, full boundary and co-boundary.
    Ig,
    /// IS: all simplices, boundary, one coface per link component.
    Is,
    /// CASC Hasse diagram: every simplex with its up and down incidences.
    Hasse,
    /// Stellar tree: the leaf-by-leaf spatial index.
    Stellar,
}

/// How to build a structure.
///
/// ```
/// use starplex::structures::StructureOptions;
/// use starplex::stellar::Decomposition;
/// let o = StructureOptions { kv: Some(20), ..Default::default() };
/// assert_eq!(o.limits.stored_simplices, 1 << 31);
/// assert_eq!(o.decomposition, Decomposition::Spatial);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct StructureOptions {
    /// The Stellar tree's bucketing threshold k_V (`None`: its default).
    pub kv: Option<u32>,
    /// How the Stellar tree splits the vertices into blocks (by coordinates, or by connectivity
    /// alone for complexes without meaningful coordinates).
    pub decomposition: crate::stellar::Decomposition,
    /// `limits.stored_simplices`: the most simplices the structures that store every simplex
    /// (simplex tree, IG, IS, Hasse) may hold; more is refused with an estimate before anything
    /// is allocated.
    pub limits: Limits,
}

/// Why a structure could not be built.
///
/// ```
/// use starplex::complex::IndexedComplex;
/// use starplex::{buf::Buf, cell::CellKind};
/// use starplex::structures::{Structure, StructureError, StructureOptions};
/// let quad = IndexedComplex::from_parts(2, Buf::from(vec![0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 1.0]),
///     vec![(CellKind::Quad, Buf::from(vec![0, 1, 2, 3]))]).unwrap();
/// let e = Structure::SimplexTree.build(&quad, &StructureOptions::default()).err().unwrap();
/// assert!(matches!(e, StructureError::NotSimplicial { .. }));
/// assert!(e.to_string().starts_with("simplex-tree: cell 0 is a quad"));
/// assert!(Structure::Ig.build(&quad, &StructureOptions::default()).is_ok());
/// ```
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum StructureError {
    /// A simplicial-only structure was asked to hold a complex with CP cells (the reason
    /// names the structures that hold them).
    #[error("{structure}: {reason}")]
    NotSimplicial {
        /// The structure's name.
        structure: &'static str,
        /// The builder's own message.
        reason: String,
    },
    /// Any other refusal (too many cells or simplices for the structure's ids or budget).
    #[error("{structure}: {reason}")]
    Refused {
        /// The structure's name.
        structure: &'static str,
        /// The builder's own message.
        reason: String,
    },
}

/// A built structure, answering every query.
pub type BoxedQueries<'a> = Box<dyn Queries + Sync + 'a>;

impl Structure {
    /// Every structure, in the order `compare` lists them.
    pub const ALL: [Structure; 7] = [
        Structure::Vt,
        Structure::IaStar,
        Structure::SimplexTree,
        Structure::Ig,
        Structure::Is,
        Structure::Hasse,
        Structure::Stellar,
    ];

    /// Whether the structure holds CP cells (quads, hexahedra, prisms, pyramids); the others
    /// refuse CP complexes with [`StructureError::NotSimplicial`].
    ///
    /// ```
    /// use starplex::structures::Structure;
    /// assert!(Structure::Stellar.holds_cp());
    /// ```
    pub fn holds_cp(self) -> bool {
        !matches!(
            self,
            Structure::SimplexTree | Structure::Is | Structure::Hasse
        )
    }

    /// The structure's name (what `--structure` takes).
    ///
    /// ```
    /// use starplex::structures::Structure;
    /// assert_eq!(Structure::SimplexTree.name(), "simplex-tree");
    /// ```
    pub fn name(self) -> &'static str {
        match self {
            Structure::Vt => "vt",
            Structure::IaStar => "ia-star",
            Structure::SimplexTree => "simplex-tree",
            Structure::Ig => "ig",
            Structure::Is => "is",
            Structure::Hasse => "hasse",
            Structure::Stellar => "stellar",
        }
    }

    /// The structure of a name (as [`Structure::name`] writes it).
    ///
    /// ```
    /// use starplex::structures::Structure;
    /// assert_eq!(Structure::from_name("hasse"), Some(Structure::Hasse));
    /// assert_eq!(Structure::from_name("btree"), None);
    /// ```
    pub fn from_name(name: &str) -> Option<Structure> {
        Structure::ALL.into_iter().find(|s| s.name() == name)
    }

    /// Builds the structure on `k`.
    ///
    /// # Errors
    /// [`StructureError::NotSimplicial`] for a simplicial-only structure on a complex with CP
    /// cells, [`StructureError::Refused`] when the builder refuses (sizes, budget).
    ///
    /// ```
    /// # use starplex::complex::{ComplexBuilder, BuildOptions};
    /// # use starplex::cell::CellKind;
    /// use starplex::structures::{Structure, StructureOptions};
    /// # let mut b = ComplexBuilder::new(1).unwrap();
    /// # for x in 0..3 { b.push_vertex(&[x as f64]).unwrap(); }
    /// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
    /// # let k = b.build(&BuildOptions::default()).unwrap().0;
    /// use starplex::limits::Limits;
    /// let limits = Limits { stored_simplices: 3, ..Limits::default() };
    /// let tight = StructureOptions { limits, ..Default::default() };
    /// assert!(Structure::Ig.build(&k, &tight).is_err()); // 7 simplices
    /// assert!(Structure::IaStar.build(&k, &tight).is_ok()); // tops only
    /// ```
    pub fn build<'a>(
        self,
        k: &'a IndexedComplex,
        o: &StructureOptions,
    ) -> Result<BoxedQueries<'a>, StructureError> {
        let structure = self.name();
        let err = |reason: String| {
            if !self.holds_cp() && !k.is_simplicial() {
                StructureError::NotSimplicial { structure, reason }
            } else {
                StructureError::Refused { structure, reason }
            }
        };
        Ok(match self {
            Structure::Vt => Box::new(VtIndex::new(k)),
            Structure::IaStar => Box::new(IaStar::new(k).map_err(|e| err(e.to_string()))?),
            Structure::SimplexTree => Box::new(
                SimplexTree::new(
                    k,
                    &SimplexTreeOptions {
                        label_lists: true,
                        limits: o.limits,
                    },
                )
                .map_err(|e| err(e.to_string()))?,
            ),
            Structure::Ig => {
                Box::new(IncidenceGraph::new(k, &o.limits).map_err(|e| err(e.to_string()))?)
            }
            Structure::Is => Box::new(Is::new(k, &o.limits).map_err(|e| err(e.to_string()))?),
            Structure::Hasse => {
                Box::new(HasseQueries::new(k, &o.limits).map_err(|e| err(e.to_string()))?)
            }
            Structure::Stellar => {
                let opts = StellarOptions {
                    kv: o.kv,
                    decomposition: o.decomposition,
                    ..Default::default()
                };
                Box::new(StellarTree::build(k, &opts).map_err(|e| err(e.to_string()))?)
            }
        })
    }
}
