//! Readers and writers, one pair per format, dispatching on the file extension.
//!
//! Every reader streams (no whole-file `String`, no allocation sized by a declared count) and
//! reports errors with the file, the line (or byte offset) and the reason. Writers write to a
//! temporary file beside the target and rename it, so a failed write leaves nothing half-written.
//!
//! ```
//! use starplex::io::{self, Format, ReadOptions};
//! let dir = std::env::temp_dir().join(format!("starplex-doc-io-{}", std::process::id()));
//! std::fs::create_dir_all(&dir).unwrap();
//! let spx = dir.join("t.spx");
//! std::fs::write(&spx, "SPX 1\n3 3 1\n0 0 0\n1 0 0\n0 1 0\ntri 3 0 1 2\n").unwrap();
//! let r = io::read(&spx, &ReadOptions::default()).unwrap();
//! assert_eq!(r.complex.n_cells(), 1);
//! let copy = dir.join("copy.spx");
//! io::write(&copy, &r.complex, None).unwrap();
//! let back = io::read(&copy, &ReadOptions::default()).unwrap();
//! assert_eq!(back.complex, r.complex);
//! assert_eq!(Format::from_path(&spx), Some(Format::Spx));
//! // a file the format cannot describe is an error naming the file and the line
//! std::fs::write(&spx, "SPX 1\n3 3 1\n0 0 0\n1 0 0\n0 1 0\ntri 3 0 1 7\n").unwrap();
//! let e = io::read(&spx, &ReadOptions::default()).unwrap_err();
//! assert!(e.to_string().ends_with(":6: cell 0: vertex index 7 is out of range: the file has 3 vertices, numbered from 0"), "{e}");
//! ```
use std::fmt;
use std::path::{Path, PathBuf};

use crate::complex::{BuildOptions, ComplexError, IndexedComplex};

pub mod binary;
mod faces;
pub mod gmsh;
pub mod medit;
pub mod obj;
pub mod off;
pub mod output;
pub mod ply;
pub mod points;
mod raw;
mod spb_attrs;
pub mod spx;
mod spx_attrs;
pub mod stellar_ref;
pub mod stl;
pub mod text;
pub mod vtk;
pub mod vtu;
pub mod words;

/// A file format starplex reads or writes.
///
/// ```
/// use starplex::io::Format;
/// use std::path::Path;
/// assert_eq!(Format::from_path(Path::new("bunny.PLY")), Some(Format::Ply));
/// assert_eq!(Format::from_name("msh22"), Some(Format::Gmsh22));
/// assert_eq!(Format::Gmsh22.to_string(), "msh22");
/// assert!(!Format::Hex.can_write());
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Format {
    /// `.spx`, the starplex text format (FORMATS.md).
    Spx,
    /// `.spb`, the starplex binary format (memory-mapped).
    Binary,
    /// `.off` (OFF, COFF, NOFF, nOFF): faces are polygons (triangles, quads, ...).
    Off,
    /// `.off` whose faces of `k` vertices are `(k-1)`-simplices (the Stellar reference's
    /// convention for simplicial complexes of any dimension; named `off-simplices`). Reads as
    /// OFF with [`PolygonMode::Simplices`]; writes simplices of every dimension.
    OffSimplices,
    /// `.ply` (ascii and binary).
    Ply,
    /// `.obj` (Wavefront).
    Obj,
    /// `.stl` (ascii and binary read; written as ascii).
    Stl,
    /// `.stl` written as binary (named `stl-binary` or `stlb`; reads as [`Format::Stl`]).
    StlBinary,
    /// `.mesh` (Medit).
    Medit,
    /// `.vtk` (legacy unstructured grid, ascii and binary; poly data read).
    Vtk,
    /// `.vtk` written as legacy `POLYDATA` (named `vtk-polydata`: edges as `LINES`, triangles
    /// and quads as `POLYGONS`; reads as [`Format::Vtk`]).
    VtkPolyData,
    /// `.vtu` (VTK XML unstructured grid; the reader also takes poly data).
    Vtu,
    /// `.vtp` (VTK XML poly data: points, lines, polygons; the reader also takes unstructured
    /// grids).
    Vtp,
    /// `.msh` (gmsh 2.2 and 4.1 ascii; written as 4.1).
    Gmsh,
    /// `.msh` written as gmsh 2.2 ascii (named `msh22` or `gmsh22`; reads as [`Format::Gmsh`]).
    Gmsh22,
    /// `.msh` written as gmsh 4.1 binary (named `msh-binary` or `mshb`; reads as
    /// [`Format::Gmsh`]).
    GmshBinary,
    /// `.msh` written as gmsh 2.2 binary (named `msh22-binary` or `msh2b`; reads as
    /// [`Format::Gmsh`]).
    Gmsh22Binary,
    /// `.tri` (Stellar reference: triangles).
    Tri,
    /// `.ts` (Stellar reference: tetrahedra).
    Ts,
    /// `.sierp` (Stellar reference: simplices of one dimension).
    Sierp,
    /// `.hex` (Stellar reference: hexahedra, 1-based, its own corner order).
    Hex,
    /// A Stellar tree saved by `starplex stellar MESH --save OUT` (named `stellar-tree`;
    /// recognised by its magic whatever its name): read as the complex it was built from when
    /// it was saved with the coordinates ([`StellarTree::to_complex`](crate::stellar::StellarTree::to_complex)).
    /// Written by `stellar --save`, not by [`write()`].
    StellarTree,
}

impl Format {
    /// Every format.
    ///
    /// ```
    /// use starplex::io::Format;
    /// assert_eq!(Format::ALL.len(), 22);
    /// let writable: Vec<String> = Format::ALL.iter().filter(|f| f.can_write()).map(|f| f.to_string()).collect();
    /// assert_eq!(writable, ["spx", "spb", "off", "off-simplices", "ply", "obj", "stl", "stl-binary",
    ///                       "mesh", "vtk", "vtk-polydata", "vtu", "vtp", "msh", "msh22", "msh-binary",
    ///                       "msh22-binary"]);
    /// ```
    pub const ALL: [Format; 22] = [
        Format::Spx,
        Format::Binary,
        Format::Off,
        Format::OffSimplices,
        Format::Ply,
        Format::Obj,
        Format::Stl,
        Format::StlBinary,
        Format::Medit,
        Format::Vtk,
        Format::VtkPolyData,
        Format::Vtu,
        Format::Vtp,
        Format::Gmsh,
        Format::Gmsh22,
        Format::GmshBinary,
        Format::Gmsh22Binary,
        Format::Tri,
        Format::Ts,
        Format::Sierp,
        Format::Hex,
        Format::StellarTree,
    ];

    /// The format named by a file's extension (case-insensitive).
    ///
    /// ```
    /// use starplex::io::Format;
    /// use std::path::Path;
    /// assert_eq!(Format::from_path(Path::new("data/torus.OFF")), Some(Format::Off));
    /// assert_eq!(Format::from_path(Path::new("cube.msh")), Some(Format::Gmsh));
    /// assert_eq!(Format::from_path(Path::new("notes.txt")), None);
    /// assert_eq!(Format::from_path(Path::new("Makefile")), None);
    /// ```
    pub fn from_path(path: &Path) -> Option<Format> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        Format::from_name(&ext)
    }

    /// The format named `name` (an extension or a name such as `gmsh`, `medit`, `binary`).
    ///
    /// ```
    /// use starplex::io::Format;
    /// assert_eq!(Format::from_name("medit"), Some(Format::Medit));
    /// assert_eq!(Format::from_name("COFF"), Some(Format::Off));
    /// assert_eq!(Format::from_name("binary"), Some(Format::Binary));
    /// assert_eq!(Format::from_name("xyz"), None);
    /// ```
    pub fn from_name(name: &str) -> Option<Format> {
        Some(match name.to_ascii_lowercase().as_str() {
            "spx" => Format::Spx,
            "spb" | "binary" | "bin" => Format::Binary,
            "off" | "coff" | "noff" => Format::Off,
            "off-simplices" | "offs" | "soff" => Format::OffSimplices,
            "ply" => Format::Ply,
            "obj" => Format::Obj,
            "stl" | "stl-ascii" => Format::Stl,
            "stl-binary" | "stlb" => Format::StlBinary,
            "mesh" | "medit" => Format::Medit,
            "vtk" => Format::Vtk,
            "vtk-polydata" | "vtkp" | "vtk-poly" => Format::VtkPolyData,
            "vtu" => Format::Vtu,
            "vtp" => Format::Vtp,
            "msh" | "gmsh" | "msh4" | "msh41" | "gmsh4" | "gmsh41" => Format::Gmsh,
            "msh2" | "msh22" | "gmsh2" | "gmsh22" => Format::Gmsh22,
            "msh-binary" | "mshb" | "msh41-binary" | "gmsh-binary" => Format::GmshBinary,
            "msh22-binary" | "msh2b" | "msh2-binary" | "gmsh22-binary" => Format::Gmsh22Binary,
            "tri" => Format::Tri,
            "ts" => Format::Ts,
            "sierp" => Format::Sierp,
            "hex" => Format::Hex,
            "stellar-tree" | "tree" => Format::StellarTree,
            _ => return None,
        })
    }

    /// The format that a file's first bytes show (`None` when they show none): the magic of
    /// `spb`, `SPX`, `ply`, `$MeshFormat`, `# vtk DataFile`, `MeshVersionFormatted`, an OFF
    /// keyword, `solid` (ascii STL). Used for files whose extension names no format.
    ///
    /// ```
    /// use starplex::io::Format;
    /// assert_eq!(Format::sniff(b"$MeshFormat\n4.1 0 8\n"), Some(Format::Gmsh));
    /// assert_eq!(Format::sniff(b"# vtk DataFile Version 5.1\n"), Some(Format::Vtk));
    /// assert_eq!(Format::sniff(b"COFF\n3 1 0\n"), Some(Format::Off));
    /// assert_eq!(Format::sniff(b"ply\nformat ascii 1.0\n"), Some(Format::Ply));
    /// assert_eq!(Format::sniff(b"<?xml version=\"1.0\"?>\n<VTKFile"), Some(Format::Vtu));
    /// assert_eq!(Format::sniff(b"hello"), None);
    /// ```
    pub fn sniff(head: &[u8]) -> Option<Format> {
        let starts = |m: &[u8]| head.len() >= m.len() && head[..m.len()].eq_ignore_ascii_case(m);
        if head.starts_with(&binary::MAGIC) {
            return Some(Format::Binary);
        }
        if starts(b"SPX") {
            return Some(Format::Spx);
        }
        if starts(b"ply\n") || starts(b"ply\r\n") {
            return Some(Format::Ply);
        }
        if starts(b"$MeshFormat") {
            return Some(Format::Gmsh);
        }
        if starts(b"# vtk DataFile") {
            return Some(Format::Vtk);
        }
        if starts(b"<?xml") || starts(b"<VTKFile") {
            // one reader takes both kinds of VTK XML file
            return Some(Format::Vtu);
        }
        if starts(b"MeshVersionFormatted") {
            return Some(Format::Medit);
        }
        if starts(b"solid") {
            return Some(Format::Stl);
        }
        let first = head
            .split(|c| c.is_ascii_whitespace())
            .next()
            .unwrap_or_default();
        let is_off = first
            .strip_suffix(b"OFF")
            .is_some_and(|p| p.iter().all(|c| b"CNST4n".contains(c)))
            && !first.is_empty();
        is_off.then_some(Format::Off)
    }

    /// The usual extension.
    ///
    /// ```
    /// use starplex::io::Format;
    /// assert_eq!(Format::Medit.extension(), "mesh");
    /// assert_eq!(Format::Gmsh22.extension(), "msh");
    /// let variants = [Format::Gmsh22, Format::GmshBinary, Format::Gmsh22Binary, Format::OffSimplices,
    ///                 Format::StlBinary, Format::VtkPolyData];
    /// for f in Format::ALL.into_iter().filter(|f| !variants.contains(f)) {
    ///     assert_eq!(Format::from_name(f.extension()), Some(f));
    /// }
    /// ```
    pub fn extension(self) -> &'static str {
        match self {
            Format::Spx => "spx",
            Format::Binary => "spb",
            Format::Off | Format::OffSimplices => "off",
            Format::Ply => "ply",
            Format::Obj => "obj",
            Format::Stl | Format::StlBinary => "stl",
            Format::Medit => "mesh",
            Format::Vtk | Format::VtkPolyData => "vtk",
            Format::Vtu => "vtu",
            Format::Vtp => "vtp",
            Format::Gmsh | Format::Gmsh22 | Format::GmshBinary | Format::Gmsh22Binary => "msh",
            Format::Tri => "tri",
            Format::Ts => "ts",
            Format::Sierp => "sierp",
            Format::Hex => "hex",
            Format::StellarTree => "tree",
        }
    }

    /// Whether starplex can write this format.
    ///
    /// ```
    /// use starplex::io::Format;
    /// assert!(Format::Vtk.can_write());
    /// assert!(!Format::Hex.can_write()); // the Stellar reference formats are read only
    /// ```
    pub fn can_write(self) -> bool {
        !matches!(
            self,
            Format::Tri | Format::Ts | Format::Sierp | Format::Hex | Format::StellarTree
        )
    }

    /// The attributes of `a` that a file of this format cannot hold (`kind name`, e.g.
    /// `cell material`): none for VTK (`.vtk`, `.vtu`, `.vtp`) and starplex's own `.spx` and
    /// `.spb` (version 2); Medit keeps only its integer
    /// `medit:ref` columns; PLY keeps those [`ply::dropped`] does not name; OFF keeps the
    /// colours ([`off::holds`]); gmsh the data sections and the physical and geometrical tags
    /// ([`gmsh::dropped`]); the other formats keep none.
    ///
    /// ```
    /// use starplex::attr::{Attribute, Attributes};
    /// use starplex::io::Format;
    /// let a = Attributes {
    ///     vertex: vec![Attribute::float("height", 1, vec![0.5])],
    ///     cell: vec![Attribute::int("medit:ref", 1, vec![3])],
    /// };
    /// assert!(Format::Vtu.dropped_attributes(&a).is_empty());
    /// assert!(Format::Spx.dropped_attributes(&a).is_empty());
    /// assert!(Format::Binary.dropped_attributes(&a).is_empty());
    /// assert_eq!(Format::Medit.dropped_attributes(&a), ["vertex height"]);
    /// assert_eq!(Format::Obj.dropped_attributes(&a).len(), 2);
    /// ```
    pub fn dropped_attributes(self, a: &crate::attr::Attributes) -> Vec<String> {
        use crate::attr::{AttrTarget, AttrValues};
        if self == Format::Ply {
            return ply::dropped(a, ply::PlyEncoding::default());
        }
        if matches!(
            self,
            Format::Gmsh | Format::Gmsh22 | Format::GmshBinary | Format::Gmsh22Binary
        ) {
            return gmsh::dropped(self, a);
        }
        let mut out = Vec::new();
        for target in [AttrTarget::Vertex, AttrTarget::Cell] {
            for c in a.of(target) {
                let kept = match self {
                    Format::Vtk | Format::VtkPolyData | Format::Vtu | Format::Vtp => true,
                    Format::Spx | Format::Binary => true,
                    Format::Off | Format::OffSimplices => off::holds(target, c),
                    Format::Medit => {
                        c.name == medit::REF
                            && c.components == 1
                            && matches!(c.values, AttrValues::Int(_))
                    }
                    _ => false,
                };
                if !kept {
                    out.push(format!("{target} {}", c.name));
                }
            }
        }
        out
    }

    /// The names of the formats starplex writes, space-separated (for hints and help).
    ///
    /// ```
    /// use starplex::io::Format;
    /// assert!(Format::writable_names().starts_with("spx spb off"));
    /// assert!(!Format::writable_names().contains("sierp"));
    /// ```
    pub fn writable_names() -> String {
        Format::ALL
            .iter()
            .filter(|f| f.can_write())
            .map(|f| f.to_string())
            .collect::<Vec<_>>()
            .join(" ")
    }
}

impl fmt::Display for Format {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Format::Gmsh22 => f.write_str("msh22"),
            Format::GmshBinary => f.write_str("msh-binary"),
            Format::Gmsh22Binary => f.write_str("msh22-binary"),
            Format::VtkPolyData => f.write_str("vtk-polydata"),
            Format::OffSimplices => f.write_str("off-simplices"),
            Format::StlBinary => f.write_str("stl-binary"),
            _ => f.write_str(self.extension()),
        }
    }
}

/// Where in a file a problem is.
///
/// ```
/// use starplex::io::{spx, Location, ReadOptions};
/// let text = "SPX 1\n1 2 1\n0\n1\nline 2 0 x\n";
/// let e = spx::read_from(text.as_bytes(), "m.spx".as_ref(), &ReadOptions::default()).unwrap_err();
/// assert_eq!(e.location, Some(Location::Line(5)));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Location {
    /// 1-based line number (text formats).
    Line(u64),
    /// 0-based byte offset (binary formats).
    Byte(u64),
}

/// What went wrong while reading or writing.
///
/// ```
/// use starplex::io::{self, Format, IoErrorKind, ReadOptions};
/// use std::path::Path;
/// let e = io::read(Path::new("mesh.xyz"), &ReadOptions::default()).unwrap_err();
/// assert!(matches!(e.kind, IoErrorKind::UnknownFormat(_)));
/// let e = io::read(Path::new("/no/such/dir/mesh.off"), &ReadOptions::default()).unwrap_err();
/// assert!(matches!(e.kind, IoErrorKind::Os(_)));
/// # let k = starplex::complex::IndexedComplex::from_parts(3, vec![0.0; 3].into(), vec![]).unwrap();
/// let e = io::write(Path::new("out.stl"), &k, None).unwrap_err(); // STL has no isolated vertices
/// assert!(matches!(e.kind, IoErrorKind::CannotWrite { format: Format::Stl, .. }));
/// ```
#[derive(Debug, thiserror::Error)]
pub enum IoErrorKind {
    /// The operating system refused (missing file, permissions, disk full).
    #[error("{0}")]
    Os(#[from] std::io::Error),
    /// The content does not follow the format.
    #[error("{0}")]
    Parse(String),
    /// The content parses but does not make a valid complex.
    #[error("{0}")]
    Complex(#[from] ComplexError),
    /// A count the file declares (an OFF header's face count) disagrees with the content that
    /// follows; [`ReadOptions::lenient`] reads what is there instead. The message says which
    /// count and what was found; front ends add how to pass the option.
    #[error("{0}")]
    CountMismatch(String),
    /// The extension names no known format.
    #[error("unknown format for '{0}': use one of spx spb off ply obj stl mesh vtk vtu vtp msh tri ts sierp hex, or name the format (msh22 writes gmsh 2.2)")]
    UnknownFormat(String),
    /// Standard input or output (`-`) was given without a format: nothing names it.
    /// The format is named by [`ReadOptions::format`] for input and by [`write`]'s `format` for
    /// output; front ends add how to pass it.
    #[error("{what} has no extension to tell its format: name the format")]
    NeedsFormat {
        /// `standard input` or `standard output`.
        what: &'static str,
        /// True for an output, false for an input.
        output: bool,
    },
    /// The format's reader needs a file (it seeks or memory-maps), not a stream.
    #[error("{0} cannot be read from a stream (its reader needs a seekable file): save it to a file first")]
    NeedsFile(Format),
    /// The format cannot hold this complex (e.g. tetrahedra in PLY).
    #[error("{format} cannot hold this complex: {reason}")]
    CannotWrite {
        /// The target format.
        format: Format,
        /// Why.
        reason: String,
    },
}

/// An error with the file and the place in it.
///
/// ```
/// use starplex::io::{spx, IoErrorKind, Location, ReadOptions};
/// let text = "SPX 1\n1 2 1\n0\n1\nline 2 0 7\n";
/// let e = spx::read_from(text.as_bytes(), "m.spx".as_ref(), &ReadOptions::default()).unwrap_err();
/// assert_eq!(e.path, std::path::Path::new("m.spx"));
/// assert_eq!(e.location, Some(Location::Line(5)));
/// assert!(matches!(e.kind, IoErrorKind::Parse(_)));
/// assert_eq!(
///     e.to_string(),
///     "m.spx:5: cell 0: vertex index 7 is out of range: the file has 2 vertices, numbered from 0"
/// );
/// ```
#[derive(Debug)]
pub struct IoError {
    /// The file.
    pub path: PathBuf,
    /// The line or byte, when known.
    pub location: Option<Location>,
    /// What is wrong.
    pub kind: IoErrorKind,
}

impl IoError {
    /// A parse error at `location`.
    ///
    /// ```
    /// use starplex::io::{IoError, IoErrorKind, Location};
    /// use std::path::Path;
    /// let e = IoError::parse(Path::new("m.off"), Some(Location::Line(3)), "expected 3 coordinates");
    /// assert!(matches!(e.kind, IoErrorKind::Parse(_)));
    /// assert_eq!(e.to_string(), "m.off:3: expected 3 coordinates");
    /// ```
    pub fn parse(path: &Path, location: Option<Location>, msg: impl Into<String>) -> IoError {
        IoError {
            path: path.to_path_buf(),
            location,
            kind: IoErrorKind::Parse(msg.into()),
        }
    }

    /// An error of `kind` with no location.
    ///
    /// ```
    /// use starplex::io::{IoError, IoErrorKind};
    /// use starplex::complex::ComplexError;
    /// use std::path::Path;
    /// let e = IoError::new(Path::new("m.spx"), ComplexError::BadAmbientDim(0));
    /// assert!(e.location.is_none());
    /// assert!(matches!(e.kind, IoErrorKind::Complex(ComplexError::BadAmbientDim(0))));
    /// assert_eq!(e.to_string(), "m.spx: ambient dimension 0 is outside 1..=64");
    /// ```
    pub fn new(path: &Path, kind: impl Into<IoErrorKind>) -> IoError {
        IoError {
            path: path.to_path_buf(),
            location: None,
            kind: kind.into(),
        }
    }

    /// Sets the location.
    ///
    /// ```
    /// use starplex::io::{IoError, IoErrorKind, Location};
    /// use std::path::Path;
    /// let e = IoError::new(Path::new("m.spb"), IoErrorKind::Parse("truncated array".into()));
    /// let e = e.at(Location::Byte(128));
    /// assert_eq!(e.to_string(), "m.spb: byte 128: truncated array");
    /// ```
    pub fn at(mut self, location: Location) -> IoError {
        self.location = Some(location);
        self
    }
}

impl fmt::Display for IoError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.path.display())?;
        match self.location {
            Some(Location::Line(l)) => write!(f, ":{l}")?,
            Some(Location::Byte(b)) => write!(f, ": byte {b}")?,
            None => {}
        }
        write!(f, ": {}", self.kind)
    }
}

impl std::error::Error for IoError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        Some(&self.kind)
    }
}

/// How polygon faces (more than 4 corners) of surface formats are read.
///
/// ```
/// use starplex::io::{off, PolygonMode, ReadOptions};
/// use starplex::cell::CellKind;
/// let pentagon = "OFF\n5 1 0\n0 0 0\n1 0 0\n2 1 0\n1 2 0\n0 1 0\n5 0 1 2 3 4\n";
/// let r = off::read_from(pentagon.as_bytes(), "p.off".as_ref(), &ReadOptions::default()).unwrap();
/// assert_eq!(r.complex.n_cells(), 3); // a fan of triangles
/// assert!(r.notes[0].starts_with("fan-triangulated 1 polygons"));
/// let opts = ReadOptions { polygons: PolygonMode::Simplices, ..Default::default() };
/// let r = off::read_from(pentagon.as_bytes(), "p.off".as_ref(), &opts).unwrap();
/// assert_eq!(r.complex.cell(starplex::ids::CellId(0)).kind, CellKind::Simplex(4));
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum PolygonMode {
    /// Triangles stay triangles, quads become quad cells, larger polygons are fan-triangulated
    /// (and the count is reported in [`ReadResult::notes`]).
    #[default]
    Polygons,
    /// Every face of `k` vertices is a (k-1)-simplex on its vertices: the Stellar reference's
    /// convention for simplicial complexes of any dimension in OFF.
    Simplices,
}

/// Options of [`read`].
///
/// ```
/// use starplex::io::{spx, ReadOptions};
/// use starplex::complex::BuildOptions;
/// let text = "SPX 1\n1 2 2\n0\n1\nline 2 0 1\nline 2 1 0\n"; // the same edge twice
/// assert!(spx::read_from(text.as_bytes(), "m.spx".as_ref(), &ReadOptions::default()).is_err());
/// let opts = ReadOptions {
///     build: BuildOptions { drop_duplicates: true, ..Default::default() },
///     ..Default::default()
/// };
/// let r = spx::read_from(text.as_bytes(), "m.spx".as_ref(), &opts).unwrap();
/// assert_eq!(r.complex.n_cells(), 1);
/// assert_eq!(r.notes, ["dropped 1 duplicate cells"]);
/// ```
#[derive(Clone, Debug, Default)]
pub struct ReadOptions {
    /// Format to use instead of the extension's.
    pub format: Option<Format>,
    /// How OFF/PLY/OBJ faces become cells.
    pub polygons: PolygonMode,
    /// Checks of the resulting complex (drop duplicates, face cells or degenerate cells instead
    /// of failing).
    pub build: BuildOptions,
    /// Accept a file whose declared counts disagree with its content where the content is
    /// unambiguous: an OFF file whose header's face count is larger or smaller than the number
    /// of face lines (the face lines present are read, with a note). Other formats ignore it.
    ///
    /// ```
    /// use starplex::io::{off, ReadOptions};
    /// // the header says 1 face, the file has 2 (CGAL's `prim.off` is such a file)
    /// let text = "OFF\n4 1 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n3 1 3 2\n";
    /// let e = off::read_from(text.as_bytes(), "m.off".as_ref(), &ReadOptions::default()).unwrap_err();
    /// assert!(e.to_string().starts_with("m.off:8: unexpected content after the 1 faces"), "{e}");
    /// assert!(matches!(e.kind, starplex::io::IoErrorKind::CountMismatch(_)), "{e}");
    /// assert!(e.to_string().contains("lenient option"), "{e}");
    /// let opts = ReadOptions { lenient: true, ..Default::default() };
    /// let r = off::read_from(text.as_bytes(), "m.off".as_ref(), &opts).unwrap();
    /// assert_eq!(r.complex.n_cells(), 2);
    /// assert!(r.notes[0].starts_with("the header (line 2) announces 1 faces but the file has 2"), "{:?}", r.notes);
    /// ```
    pub lenient: bool,
}

/// A complex read from a file, with what the reader had to change.
///
/// ```
/// use starplex::io::{self, Format, ReadOptions};
/// let path = std::env::temp_dir().join(format!("starplex-doc-readresult-{}.txt", std::process::id()));
/// std::fs::write(&path, "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n").unwrap();
/// // A `.txt` extension names no format: say which one it is.
/// let opts = ReadOptions { format: Some(Format::Off), ..Default::default() };
/// let r = io::read(&path, &opts).unwrap();
/// std::fs::remove_file(&path).unwrap();
/// assert_eq!((r.format, r.complex.n_cells()), (Format::Off, 1));
/// assert!(r.notes.is_empty());
/// ```
#[derive(Clone, Debug)]
pub struct ReadResult {
    /// The complex.
    pub complex: IndexedComplex,
    /// The format that was read.
    pub format: Format,
    /// Human-readable notes on what was changed or dropped (fan-triangulated polygons, boundary
    /// elements of a gmsh file, ...).
    pub notes: Vec<String>,
}

/// Reads a complex, choosing the reader by `opts.format`, the extension (for `name.off.gz`, the
/// one before `.gz`) or, when neither names a format, the file's first bytes
/// ([`Format::sniff`]). A gzip-compressed file (recognised by its content, whatever its name;
/// several members are read as one stream) is decompressed on the fly, and so is gzip on
/// standard input. `-` is standard input, which needs `opts.format`.
///
/// ```
/// use starplex::io::{self, Format, ReadOptions};
/// let path = std::env::temp_dir().join(format!("starplex-doc-io-read-{}.mesh", std::process::id()));
/// std::fs::write(&path, "MeshVersionFormatted 2\nDimension 2\nVertices\n3\n0 0 0\n1 0 0\n0 1 0\nTriangles\n1\n1 2 3 0\nEnd\n").unwrap();
/// let r = io::read(&path, &ReadOptions::default()).unwrap();
/// std::fs::remove_file(&path).unwrap();
/// assert_eq!(r.format, Format::Medit); // from the extension
/// assert_eq!((r.complex.ambient_dim(), r.complex.n_cells()), (2, 1));
/// ```
///
/// # Errors
/// An [`IoError`] naming the file, the line or byte, and the problem.
pub fn read(path: &Path, opts: &ReadOptions) -> Result<ReadResult, IoError> {
    use std::io::BufRead;
    if path.as_os_str() == "-" {
        let name = Path::new(STDIN_NAME);
        let Some(format) = opts.format else {
            return Err(IoError::new(
                name,
                IoErrorKind::NeedsFormat {
                    what: "standard input",
                    output: false,
                },
            ));
        };
        let stdin = std::io::stdin();
        let mut r = std::io::BufReader::with_capacity(1 << 20, stdin.lock());
        let gz = r
            .fill_buf()
            .map_err(|e| IoError::new(name, e))?
            .starts_with(&GZIP_MAGIC);
        if gz {
            let d =
                std::io::BufReader::with_capacity(1 << 20, flate2::bufread::MultiGzDecoder::new(r));
            return read_stream(d, name, format, opts);
        }
        return read_stream(r, name, format, opts);
    }
    // the extension names the format, unless it is .gz: then the one before it does
    let gz_ext = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("gz"));
    let named = opts.format.or_else(|| {
        if gz_ext {
            path.file_stem()
                .and_then(|s| Format::from_path(Path::new(s)))
        } else {
            Format::from_path(path)
        }
    });
    let unknown = || IoError::new(path, IoErrorKind::UnknownFormat(path.display().to_string()));
    // the first bytes: gzip is recognised by content, and an unnamed format by its magic
    let mut head = [0u8; 64];
    let n_head = match std::fs::File::open(path) {
        Ok(mut f) => read_head(&mut f, &mut head).map_err(|e| IoError::new(path, e))?,
        Err(e) => {
            return Err(match named {
                None => unknown(),
                Some(_) => IoError::new(path, e),
            })
        }
    };
    let head = &head[..n_head];
    if head.starts_with(&GZIP_MAGIC) {
        let f = std::fs::File::open(path).map_err(|e| IoError::new(path, e))?;
        let mut d = std::io::BufReader::with_capacity(
            1 << 20,
            flate2::bufread::MultiGzDecoder::new(std::io::BufReader::with_capacity(1 << 20, f)),
        );
        let format = match named {
            Some(f) => f,
            None => {
                let inner = d.fill_buf().map_err(|e| IoError::new(path, e))?;
                Format::sniff(inner).ok_or_else(unknown)?
            }
        };
        let mut r = read_stream(d, path, format, opts)?;
        r.notes.push("decompressed gzip input".into());
        return Ok(r);
    }
    // a saved Stellar tree whatever its name (`.tree`, `.stl`, ...), unless a format is asked
    let saved_tree = head.starts_with(crate::stellar::SAVED_TREE_MAGIC);
    let format = match opts.format {
        None if saved_tree => Format::StellarTree,
        _ => match named.or_else(|| Format::sniff(head)) {
            Some(f) => f,
            None => return Err(unknown()),
        },
    };
    let mut r = match format {
        Format::Spx => spx::read(path, opts),
        Format::Binary => binary::read(path, opts),
        Format::Off => off::read(path, opts),
        Format::OffSimplices => {
            let o = ReadOptions {
                polygons: PolygonMode::Simplices,
                ..opts.clone()
            };
            off::read(path, &o)
        }
        Format::Ply => ply::read(path, opts),
        Format::Obj => obj::read(path, opts),
        Format::Stl | Format::StlBinary => stl::read(path, opts),
        Format::Medit => medit::read(path, opts),
        Format::Vtk | Format::VtkPolyData => vtk::read(path, opts),
        Format::Vtu | Format::Vtp => vtu::read(path, opts),
        Format::Gmsh | Format::Gmsh22 | Format::GmshBinary | Format::Gmsh22Binary => {
            gmsh::read(path, opts)
        }
        Format::Tri | Format::Ts | Format::Sierp | Format::Hex => {
            stellar_ref::read(path, format, opts)
        }
        Format::StellarTree => read_saved_tree(path),
    }?;
    if !matches!(format, Format::Vtu | Format::Vtp) {
        // (a VTK XML file says itself whether it is an unstructured grid or poly data)
        r.format = format;
    }
    Ok(r)
}

/// The complex of a saved Stellar tree (its vertices, cells and attributes in the numbering of
/// the mesh it was built from).
fn read_saved_tree(path: &Path) -> Result<ReadResult, IoError> {
    let fail = |reason: String, hint: &str| IoError::parse(path, None, format!("{reason}; {hint}"));
    let t = crate::stellar::StellarTree::load(path).map_err(|e| {
        fail(
            e.to_string(),
            "rebuild it with `starplex stellar MESH --save OUT`",
        )
    })?;
    let complex = t.to_complex().map_err(|e| {
        fail(
            e.to_string(),
            "save it again from its mesh (`starplex stellar MESH --save OUT` now saves the \
             coordinates), or use a verb that reads trees (`stellar`, `validate`, `query \
             --structure stellar`)",
        )
    })?;
    Ok(ReadResult {
        complex,
        format: Format::StellarTree,
        notes: vec!["read the complex a saved Stellar tree was built from".into()],
    })
}

/// The first two bytes of a gzip stream.
const GZIP_MAGIC: [u8; 2] = [0x1f, 0x8b];

/// Reads up to `buf.len()` bytes from the start of `f`.
fn read_head(f: &mut std::fs::File, buf: &mut [u8]) -> std::io::Result<usize> {
    use std::io::Read;
    let mut n = 0;
    while n < buf.len() {
        match f.read(&mut buf[n..]) {
            Ok(0) => break,
            Ok(k) => n += k,
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
            Err(e) => return Err(e),
        }
    }
    Ok(n)
}

/// How standard input is named in errors (`-` on the command line).
///
/// ```
/// assert_eq!(starplex::io::STDIN_NAME, "<stdin>");
/// ```
pub const STDIN_NAME: &str = "<stdin>";

/// Reads a complex in `format` from a stream (standard input, a decompressor, memory); `path`
/// names it in errors. Formats whose reader needs a file (`spb`, memory-mapped; STL, which
/// looks at the file length) are refused; PLY is read into memory first (its reader checks
/// declared counts against the length).
///
/// ```
/// use starplex::io::{self, Format, IoErrorKind, ReadOptions};
/// let text = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
/// let r = io::read_stream(text.as_bytes(), "pipe".as_ref(), Format::Off, &ReadOptions::default()).unwrap();
/// assert_eq!((r.format, r.complex.n_cells()), (Format::Off, 1));
/// let e = io::read_stream(&b""[..], "pipe".as_ref(), Format::Binary, &ReadOptions::default()).unwrap_err();
/// assert!(matches!(e.kind, IoErrorKind::NeedsFile(Format::Binary)));
/// ```
///
/// # Errors
/// As the format's `read_from`; [`IoErrorKind::NeedsFile`] for `spb` and STL.
pub fn read_stream(
    mut r: impl std::io::BufRead,
    path: &Path,
    format: Format,
    opts: &ReadOptions,
) -> Result<ReadResult, IoError> {
    let mut res = match format {
        Format::Spx => spx::read_from(r, path, opts),
        Format::Off => off::read_from(r, path, opts),
        Format::OffSimplices => {
            let o = ReadOptions {
                polygons: PolygonMode::Simplices,
                ..opts.clone()
            };
            off::read_from(r, path, &o)
        }
        Format::Ply => {
            let mut buf = Vec::new();
            std::io::Read::read_to_end(&mut r, &mut buf).map_err(|e| IoError::new(path, e))?;
            ply::read_from(&buf[..], buf.len() as u64, path, opts)
        }
        Format::Obj => obj::read_from(r, path, opts),
        Format::Medit => medit::read_from(r, path, opts),
        Format::Vtk | Format::VtkPolyData => vtk::read_from(r, path, opts),
        Format::Vtu | Format::Vtp => vtu::read_from(r, path, opts),
        Format::Gmsh | Format::Gmsh22 | Format::GmshBinary | Format::Gmsh22Binary => {
            gmsh::read_from(r, path, opts)
        }
        Format::Tri | Format::Ts | Format::Sierp | Format::Hex => {
            stellar_ref::read_from(r, path, format, opts)
        }
        Format::Binary | Format::Stl | Format::StlBinary | Format::StellarTree => {
            Err(IoError::new(path, IoErrorKind::NeedsFile(format)))
        }
    }?;
    res.format = format;
    Ok(res)
}

/// Writes `complex` in `format` (or the extension's). The file appears only when complete.
///
/// ```
/// use starplex::io::{self, Format, ReadOptions};
/// # use starplex::complex::IndexedComplex;
/// # use starplex::cell::CellKind;
/// let k = IndexedComplex::from_parts(2, vec![0.0, 0.0, 1.0, 0.0, 0.0, 1.0].into(),
///                                    vec![(CellKind::Simplex(2), vec![0, 1, 2].into())]).unwrap();
/// let path = std::env::temp_dir().join(format!("starplex-doc-io-write-{}.msh", std::process::id()));
/// io::write(&path, &k, Some(Format::Gmsh22)).unwrap(); // gmsh 2.2 instead of 4.1
/// assert!(std::fs::read_to_string(&path).unwrap().starts_with("$MeshFormat\n2.2"));
/// let back = io::read(&path, &ReadOptions::default()).unwrap().complex;
/// std::fs::remove_file(&path).unwrap();
/// assert_eq!(back.n_cells(), 1);
/// ```
///
/// # Errors
/// Unknown or read-only formats, a complex the format cannot hold (checked by
/// [`check_writable`] before anything is opened or written), operating-system errors.
pub fn write(path: &Path, complex: &IndexedComplex, format: Option<Format>) -> Result<(), IoError> {
    let format = match format.or_else(|| Format::from_path(path)) {
        Some(f) => f,
        None if path.as_os_str() == "-" => {
            return Err(IoError::new(
                path,
                IoErrorKind::NeedsFormat {
                    what: "standard output",
                    output: true,
                },
            ))
        }
        None => {
            return Err(IoError::new(
                path,
                IoErrorKind::UnknownFormat(path.display().to_string()),
            ))
        }
    };
    check_writable(complex, format).map_err(|k| IoError::new(path, k))?;
    match format {
        Format::Spx => atomic_write(path, |w| spx::write(w, complex)),
        Format::Binary => atomic_write(path, |w| binary::write(w, complex)),
        Format::Off => atomic_write(path, |w| off::write(w, complex)),
        Format::OffSimplices => atomic_write(path, |w| off::write_simplices(w, complex)),
        Format::Ply => atomic_write(path, |w| ply::write(w, complex)),
        Format::Obj => atomic_write(path, |w| obj::write(w, complex)),
        Format::Stl => atomic_write(path, |w| stl::write(w, complex)),
        Format::StlBinary => atomic_write(path, |w| stl::write_binary(w, complex)),
        Format::Medit => atomic_write(path, |w| medit::write(w, complex)),
        Format::Vtk => atomic_write(path, |w| vtk::write(w, complex)),
        Format::VtkPolyData => atomic_write(path, |w| vtk::write_polydata(w, complex)),
        Format::Vtu => atomic_write(path, |w| vtu::write_vtu(w, complex)),
        Format::Vtp => atomic_write(path, |w| vtu::write_vtp(w, complex)),
        Format::Gmsh => atomic_write(path, |w| gmsh::write(w, complex)),
        Format::Gmsh22 => atomic_write(path, |w| gmsh::write_22(w, complex)),
        Format::GmshBinary => atomic_write(path, |w| gmsh::write_binary(w, complex)),
        Format::Gmsh22Binary => atomic_write(path, |w| gmsh::write_22_binary(w, complex)),
        Format::Tri | Format::Ts | Format::Sierp | Format::Hex | Format::StellarTree => {
            unreachable!("refused by check_writable")
        }
    }
}

/// Whether `format` can hold `complex` exactly: every cell kind, every dimension, every vertex
/// (what a reader of the file gets back is the same complex, up to the zero padding of 1- or
/// 2-dimensional points in formats with 3 coordinates). Every writer runs this check first;
/// [`write()`] runs it before opening the output.
///
/// ```
/// use starplex::cell::CellKind;
/// use starplex::complex::IndexedComplex;
/// use starplex::io::{check_writable, Format, IoErrorKind};
/// let tet = IndexedComplex::from_parts(3, vec![0., 0., 0., 1., 0., 0., 0., 1., 0., 0., 0., 1.].into(),
///                                      vec![(CellKind::Simplex(3), vec![0, 1, 2, 3].into())]).unwrap();
/// for f in [Format::Spx, Format::Binary, Format::Vtk, Format::Gmsh, Format::Medit, Format::OffSimplices] {
///     assert!(check_writable(&tet, f).is_ok(), "{f}");
/// }
/// // OFF faces of 4 vertices read back as quads; PLY, OBJ and STL hold surfaces only
/// for f in [Format::Off, Format::Ply, Format::Obj, Format::Stl, Format::StlBinary] {
///     let e = check_writable(&tet, f).unwrap_err();
///     assert!(matches!(e, IoErrorKind::CannotWrite { format, .. } if format == f), "{f}");
/// }
/// ```
///
/// # Errors
/// [`IoErrorKind::CannotWrite`] with the reason; read-only formats.
pub fn check_writable(complex: &IndexedComplex, format: Format) -> Result<(), IoErrorKind> {
    match format {
        Format::Spx | Format::Binary => Ok(()),
        Format::Off => off::check(complex),
        Format::OffSimplices => off::check_simplices(complex),
        Format::Ply | Format::Obj => ply::check_surface(complex, format),
        Format::Stl | Format::StlBinary => stl::check(complex, format),
        Format::Medit => medit::check(complex),
        Format::Vtk => vtk::check(complex),
        Format::VtkPolyData => vtk::check_polydata(complex),
        Format::Vtu => vtu::check(complex, false),
        Format::Vtp => vtu::check(complex, true),
        Format::Gmsh | Format::Gmsh22 | Format::GmshBinary | Format::Gmsh22Binary => {
            gmsh::check_writable(complex, format)
        }
        Format::Tri | Format::Ts | Format::Sierp | Format::Hex => Err(IoErrorKind::CannotWrite {
            format,
            reason: format!(
                "starplex reads this format but does not write it; it writes {}",
                Format::writable_names()
            ),
        }),
        Format::StellarTree => Err(IoErrorKind::CannotWrite {
            format,
            reason: "`starplex stellar MESH --save OUT` writes saved trees".into(),
        }),
    }
}

/// Runs `f` on a buffered writer to `path` through [`output::write_with`] (atomic for regular
/// files, straight through for standard output, FIFOs and devices, symbolic links followed).
///
/// # Errors
/// What `f` returns (its path is replaced by `path`), or the OS error of create/flush/rename.
pub(crate) fn atomic_write(
    path: &Path,
    f: impl FnOnce(&mut dyn std::io::Write) -> Result<(), IoErrorKind>,
) -> Result<(), IoError> {
    output::write_with(path, f)
}
