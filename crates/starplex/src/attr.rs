//! Attributes: named, typed data columns on the vertices and on the top cells of an
//! [`IndexedComplex`](crate::complex::IndexedComplex) — VTK point and cell data, gmsh physical and
//! elementary tags, Medit references.
//!
//! A column holds `components` values per item (1 for a scalar, 3 for a vector), stored flat,
//! either as integers ([`AttrValues::Int`]) or as floats ([`AttrValues::Float`]; NaN is data
//! here, not an error). Readers fill them, every renumbering of vertices or cells carries them
//! along ([`Attributes::gather_cells`], [`Attributes::gather_vertices`]), `info` lists them and
//! the writers whose format can hold them write them.
//!
//! ```
//! use starplex::attr::{Attribute, Attributes};
//! let mut a = Attributes::default();
//! a.cell.push(Attribute::int("gmsh:physical", 1, vec![7, 7, 9]));
//! a.vertex.push(Attribute::float("velocity", 3, vec![0.0; 12]));
//! assert!(a.check(4, 3).is_ok());
//! // keep cells 2 and 0, in that order
//! let b = a.gather_cells(&[2, 0]);
//! assert_eq!(b.cell[0], Attribute::int("gmsh:physical", 1, vec![9, 7]));
//! ```

/// The values of one column, flat (`components` values per item).
///
/// ```
/// use starplex::attr::AttrValues;
/// let v = AttrValues::Int(vec![1, 2, 3]);
/// assert_eq!((v.len(), v.type_name()), (3, "int"));
/// ```
#[derive(Clone, Debug, PartialEq)]
pub enum AttrValues {
    /// Integer values (every integer type of a file: tags, ids, labels, colours).
    Int(Vec<i64>),
    /// Floating-point values (`Float32` ones widened exactly).
    Float(Vec<f64>),
}

impl AttrValues {
    /// Number of values (items × components).
    ///
    /// ```
    /// use starplex::attr::AttrValues;
    /// assert_eq!(AttrValues::Float(vec![0.5; 6]).len(), 6);
    /// ```
    pub fn len(&self) -> usize {
        match self {
            AttrValues::Int(v) => v.len(),
            AttrValues::Float(v) => v.len(),
        }
    }

    /// True when there are no values.
    ///
    /// ```
    /// use starplex::attr::AttrValues;
    /// assert!(AttrValues::Int(vec![]).is_empty());
    /// ```
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// `"int"` or `"float"`.
    ///
    /// ```
    /// use starplex::attr::AttrValues;
    /// assert_eq!(AttrValues::Float(vec![]).type_name(), "float");
    /// ```
    pub fn type_name(&self) -> &'static str {
        match self {
            AttrValues::Int(_) => "int",
            AttrValues::Float(_) => "float",
        }
    }

    /// Value `i` as a float (integers converted).
    ///
    /// ```
    /// use starplex::attr::AttrValues;
    /// assert_eq!(AttrValues::Int(vec![4, 5]).get_f64(1), 5.0);
    /// ```
    pub fn get_f64(&self, i: usize) -> f64 {
        match self {
            AttrValues::Int(v) => v[i] as f64,
            AttrValues::Float(v) => v[i],
        }
    }
}

/// One named column.
///
/// ```
/// use starplex::attr::Attribute;
/// let a = Attribute::float("normal", 3, vec![0.0, 0.0, 1.0, 0.0, 1.0, 0.0]);
/// assert_eq!(a.n_items(), 2);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Attribute {
    /// Its name, as in the file (`gmsh:physical`, `medit:ref` for the formats' own tags).
    pub name: String,
    /// Values per item (1 for scalars).
    pub components: usize,
    /// The values, item after item.
    pub values: AttrValues,
}

impl Attribute {
    /// An integer column.
    ///
    /// ```
    /// use starplex::attr::{Attribute, AttrValues};
    /// let a = Attribute::int("label", 1, vec![3, 1]);
    /// assert_eq!(a.values, AttrValues::Int(vec![3, 1]));
    /// ```
    pub fn int(name: impl Into<String>, components: usize, values: Vec<i64>) -> Attribute {
        Attribute {
            name: name.into(),
            components,
            values: AttrValues::Int(values),
        }
    }

    /// A float column.
    ///
    /// ```
    /// use starplex::attr::Attribute;
    /// assert_eq!(Attribute::float("t", 1, vec![0.5]).n_items(), 1);
    /// ```
    pub fn float(name: impl Into<String>, components: usize, values: Vec<f64>) -> Attribute {
        Attribute {
            name: name.into(),
            components,
            values: AttrValues::Float(values),
        }
    }

    /// Number of items (values / components; 0 for a column of 0 components).
    ///
    /// ```
    /// use starplex::attr::Attribute;
    /// assert_eq!(Attribute::int("rgb", 3, vec![0; 9]).n_items(), 3);
    /// ```
    pub fn n_items(&self) -> usize {
        self.values.len().checked_div(self.components).unwrap_or(0)
    }

    /// The column restricted to and reordered by `items` (old item index per new item).
    ///
    /// ```
    /// use starplex::attr::Attribute;
    /// let a = Attribute::int("xy", 2, vec![0, 1, 10, 11, 20, 21]);
    /// assert_eq!(a.gather(&[2, 0]).values, Attribute::int("xy", 2, vec![20, 21, 0, 1]).values);
    /// ```
    pub fn gather(&self, items: &[u32]) -> Attribute {
        let c = self.components;
        fn pick<T: Copy>(v: &[T], c: usize, items: &[u32]) -> Vec<T> {
            let mut out = Vec::with_capacity(items.len() * c);
            for &i in items {
                out.extend_from_slice(&v[i as usize * c..(i as usize + 1) * c]);
            }
            out
        }
        let values = match &self.values {
            AttrValues::Int(v) => AttrValues::Int(pick(v, c, items)),
            AttrValues::Float(v) => AttrValues::Float(pick(v, c, items)),
        };
        Attribute {
            name: self.name.clone(),
            components: c,
            values,
        }
    }

    /// Smallest and largest value over every component (NaN skipped), `None` when there is no
    /// value that is not NaN.
    ///
    /// ```
    /// use starplex::attr::Attribute;
    /// assert_eq!(Attribute::float("f", 1, vec![2.0, f64::NAN, -1.0]).range(), Some((-1.0, 2.0)));
    /// assert_eq!(Attribute::int("i", 1, vec![]).range(), None);
    /// ```
    pub fn range(&self) -> Option<(f64, f64)> {
        let mut r: Option<(f64, f64)> = None;
        for i in 0..self.values.len() {
            let x = self.values.get_f64(i);
            if x.is_nan() {
                continue;
            }
            r = Some(match r {
                None => (x, x),
                Some((a, b)) => (a.min(x), b.max(x)),
            });
        }
        r
    }
}

/// Where a column lives.
///
/// ```
/// use starplex::attr::AttrTarget;
/// assert_eq!(AttrTarget::Cell.to_string(), "cell");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AttrTarget {
    /// One item per vertex.
    Vertex,
    /// One item per top cell.
    Cell,
}

impl std::fmt::Display for AttrTarget {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            AttrTarget::Vertex => "vertex",
            AttrTarget::Cell => "cell",
        })
    }
}

/// A column that does not fit its complex.
///
/// ```
/// use starplex::attr::{Attribute, Attributes, AttrError, AttrTarget};
/// let mut a = Attributes::default();
/// a.vertex.push(Attribute::int("id", 1, vec![1, 2]));
/// assert_eq!(
///     a.check(3, 0).unwrap_err(),
///     AttrError::WrongLength { target: AttrTarget::Vertex, name: "id".into(), expected: 3, got: 2 }
/// );
/// ```
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum AttrError {
    /// The column has not one item per vertex or cell.
    #[error("{target} attribute '{name}' has {got} values, expected {expected} (one per {target} times its components)")]
    WrongLength {
        /// Vertices or cells.
        target: AttrTarget,
        /// The column.
        name: String,
        /// Items × components.
        expected: usize,
        /// Values present.
        got: usize,
    },
    /// A column of zero components.
    #[error("{target} attribute '{name}' has 0 components")]
    NoComponents {
        /// Vertices or cells.
        target: AttrTarget,
        /// The column.
        name: String,
    },
    /// Two columns of one target with one name.
    #[error("two {target} attributes are named '{name}'")]
    DuplicateName {
        /// Vertices or cells.
        target: AttrTarget,
        /// The name.
        name: String,
    },
}

/// Every column of a complex: per vertex and per top cell.
///
/// ```
/// use starplex::attr::{Attribute, Attributes, AttrTarget};
/// let mut a = Attributes::default();
/// assert!(a.is_empty());
/// a.cell.push(Attribute::int("medit:ref", 1, vec![1]));
/// assert_eq!(a.get(AttrTarget::Cell, "medit:ref").unwrap().n_items(), 1);
/// ```
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Attributes {
    /// Columns with one item per vertex.
    pub vertex: Vec<Attribute>,
    /// Columns with one item per top cell.
    pub cell: Vec<Attribute>,
}

impl Attributes {
    /// True when there is no column.
    ///
    /// ```
    /// use starplex::attr::Attributes;
    /// assert!(Attributes::default().is_empty());
    /// ```
    pub fn is_empty(&self) -> bool {
        self.vertex.is_empty() && self.cell.is_empty()
    }

    /// The column named `name` on `target`.
    ///
    /// ```
    /// use starplex::attr::{Attribute, Attributes, AttrTarget};
    /// let a = Attributes { vertex: vec![Attribute::float("h", 1, vec![0.0])], cell: vec![] };
    /// assert!(a.get(AttrTarget::Vertex, "h").is_some());
    /// assert!(a.get(AttrTarget::Cell, "h").is_none());
    /// ```
    pub fn get(&self, target: AttrTarget, name: &str) -> Option<&Attribute> {
        self.of(target).iter().find(|a| a.name == name)
    }

    /// The columns on `target`.
    ///
    /// ```
    /// use starplex::attr::{Attributes, AttrTarget};
    /// assert!(Attributes::default().of(AttrTarget::Cell).is_empty());
    /// ```
    pub fn of(&self, target: AttrTarget) -> &[Attribute] {
        match target {
            AttrTarget::Vertex => &self.vertex,
            AttrTarget::Cell => &self.cell,
        }
    }

    /// Checks that every column has one item per vertex (`n_vertices`) or per cell (`n_cells`),
    /// at least one component, and a name unique on its target.
    ///
    /// ```
    /// use starplex::attr::{Attribute, Attributes};
    /// let a = Attributes { vertex: vec![], cell: vec![Attribute::int("tag", 1, vec![1, 2])] };
    /// assert!(a.check(0, 2).is_ok());
    /// assert!(a.check(0, 3).is_err());
    /// ```
    ///
    /// # Errors
    /// The first column that does not fit, as an [`AttrError`].
    pub fn check(&self, n_vertices: usize, n_cells: usize) -> Result<(), AttrError> {
        for (target, cols, n) in [
            (AttrTarget::Vertex, &self.vertex, n_vertices),
            (AttrTarget::Cell, &self.cell, n_cells),
        ] {
            for (i, a) in cols.iter().enumerate() {
                if a.components == 0 {
                    return Err(AttrError::NoComponents {
                        target,
                        name: a.name.clone(),
                    });
                }
                let expected = n.saturating_mul(a.components);
                if a.values.len() != expected {
                    return Err(AttrError::WrongLength {
                        target,
                        name: a.name.clone(),
                        expected,
                        got: a.values.len(),
                    });
                }
                if cols[..i].iter().any(|b| b.name == a.name) {
                    return Err(AttrError::DuplicateName {
                        target,
                        name: a.name.clone(),
                    });
                }
            }
        }
        Ok(())
    }

    /// The cell columns gathered by `cells` (old cell index per new cell); vertex columns kept.
    ///
    /// ```
    /// use starplex::attr::{Attribute, Attributes};
    /// let a = Attributes { vertex: vec![], cell: vec![Attribute::int("t", 1, vec![5, 6, 7])] };
    /// assert_eq!(a.gather_cells(&[1, 1]).cell[0].values, Attribute::int("t", 1, vec![6, 6]).values);
    /// ```
    pub fn gather_cells(&self, cells: &[u32]) -> Attributes {
        Attributes {
            vertex: self.vertex.clone(),
            cell: self.cell.iter().map(|a| a.gather(cells)).collect(),
        }
    }

    /// The vertex columns gathered by `vertices` (old vertex index per new vertex); cell columns
    /// kept.
    ///
    /// ```
    /// use starplex::attr::{Attribute, Attributes};
    /// let a = Attributes { vertex: vec![Attribute::float("h", 1, vec![0.0, 0.5])], cell: vec![] };
    /// assert_eq!(a.gather_vertices(&[1]).vertex[0].values, Attribute::float("h", 1, vec![0.5]).values);
    /// ```
    pub fn gather_vertices(&self, vertices: &[u32]) -> Attributes {
        Attributes {
            vertex: self.vertex.iter().map(|a| a.gather(vertices)).collect(),
            cell: self.cell.clone(),
        }
    }

    /// Total bytes of the values.
    ///
    /// ```
    /// use starplex::attr::{Attribute, Attributes};
    /// let a = Attributes { vertex: vec![Attribute::float("h", 1, vec![0.0; 4])], cell: vec![] };
    /// assert_eq!(a.bytes(), 32);
    /// ```
    pub fn bytes(&self) -> usize {
        self.vertex
            .iter()
            .chain(&self.cell)
            .map(|a| a.values.len() * 8)
            .sum()
    }
}
