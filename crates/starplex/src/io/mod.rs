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
pub mod gmsh;
pub mod medit;
pub mod obj;
pub mod off;
pub mod ply;
pub mod spx;
pub mod stellar_ref;
pub mod stl;
pub mod text;
pub mod vtk;
pub mod words;

/// A file format starplex reads or writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Format {
    /// `.spx`, the starplex text format (FORMATS.md).
    Spx,
    /// `.spb`, the starplex binary format (memory-mapped).
    Binary,
    /// `.off` (OFF, COFF, NOFF, nOFF).
    Off,
    /// `.ply` (ascii and binary).
    Ply,
    /// `.obj` (Wavefront).
    Obj,
    /// `.stl` (ascii and binary).
    Stl,
    /// `.mesh` (Medit).
    Medit,
    /// `.vtk` (legacy unstructured grid, ascii).
    Vtk,
    /// `.msh` (gmsh 2.2 and 4.1 ascii; written as 4.1).
    Gmsh,
    /// `.msh` written as gmsh 2.2 ascii (named `msh22` or `gmsh22`; reads as [`Format::Gmsh`]).
    Gmsh22,
    /// `.tri` (Stellar reference: triangles).
    Tri,
    /// `.ts` (Stellar reference: tetrahedra).
    Ts,
    /// `.sierp` (Stellar reference: simplices of one dimension).
    Sierp,
    /// `.hex` (Stellar reference: hexahedra, 1-based, its own corner order).
    Hex,
}

impl Format {
    /// Every format.
    pub const ALL: [Format; 14] = [
        Format::Spx,
        Format::Binary,
        Format::Off,
        Format::Ply,
        Format::Obj,
        Format::Stl,
        Format::Medit,
        Format::Vtk,
        Format::Gmsh,
        Format::Gmsh22,
        Format::Tri,
        Format::Ts,
        Format::Sierp,
        Format::Hex,
    ];

    /// The format named by a file's extension (case-insensitive).
    pub fn from_path(path: &Path) -> Option<Format> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        Format::from_name(&ext)
    }

    /// The format named `name` (an extension or a name such as `gmsh`, `medit`, `binary`).
    pub fn from_name(name: &str) -> Option<Format> {
        Some(match name.to_ascii_lowercase().as_str() {
            "spx" => Format::Spx,
            "spb" | "binary" | "bin" => Format::Binary,
            "off" | "coff" | "noff" => Format::Off,
            "ply" => Format::Ply,
            "obj" => Format::Obj,
            "stl" => Format::Stl,
            "mesh" | "medit" => Format::Medit,
            "vtk" => Format::Vtk,
            "msh" | "gmsh" | "msh4" | "msh41" | "gmsh4" | "gmsh41" => Format::Gmsh,
            "msh2" | "msh22" | "gmsh2" | "gmsh22" => Format::Gmsh22,
            "tri" => Format::Tri,
            "ts" => Format::Ts,
            "sierp" => Format::Sierp,
            "hex" => Format::Hex,
            _ => return None,
        })
    }

    /// The usual extension.
    pub fn extension(self) -> &'static str {
        match self {
            Format::Spx => "spx",
            Format::Binary => "spb",
            Format::Off => "off",
            Format::Ply => "ply",
            Format::Obj => "obj",
            Format::Stl => "stl",
            Format::Medit => "mesh",
            Format::Vtk => "vtk",
            Format::Gmsh | Format::Gmsh22 => "msh",
            Format::Tri => "tri",
            Format::Ts => "ts",
            Format::Sierp => "sierp",
            Format::Hex => "hex",
        }
    }

    /// Whether starplex can write this format.
    pub fn can_write(self) -> bool {
        !matches!(
            self,
            Format::Stl | Format::Tri | Format::Ts | Format::Sierp | Format::Hex
        )
    }
}

impl fmt::Display for Format {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Format::Gmsh22 => f.write_str("msh22"),
            _ => f.write_str(self.extension()),
        }
    }
}

/// Where in a file a problem is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Location {
    /// 1-based line number (text formats).
    Line(u64),
    /// 0-based byte offset (binary formats).
    Byte(u64),
}

/// What went wrong while reading or writing.
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
    /// The extension names no known format.
    #[error("unknown format for '{0}': use one of spx spb off ply obj stl mesh vtk msh tri ts sierp hex, or --format (msh22 writes gmsh 2.2)")]
    UnknownFormat(String),
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
    pub fn parse(path: &Path, location: Option<Location>, msg: impl Into<String>) -> IoError {
        IoError {
            path: path.to_path_buf(),
            location,
            kind: IoErrorKind::Parse(msg.into()),
        }
    }

    /// An error of `kind` with no location.
    pub fn new(path: &Path, kind: impl Into<IoErrorKind>) -> IoError {
        IoError {
            path: path.to_path_buf(),
            location: None,
            kind: kind.into(),
        }
    }

    /// Sets the location.
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
#[derive(Clone, Debug, Default)]
pub struct ReadOptions {
    /// Format to use instead of the extension's.
    pub format: Option<Format>,
    /// How OFF/PLY/OBJ faces become cells.
    pub polygons: PolygonMode,
    /// Checks of the resulting complex (drop duplicates or face cells instead of failing).
    pub build: BuildOptions,
}

/// A complex read from a file, with what the reader had to change.
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

/// Reads a complex, choosing the reader by `opts.format` or the extension.
///
/// # Errors
/// An [`IoError`] naming the file, the line or byte, and the problem.
pub fn read(path: &Path, opts: &ReadOptions) -> Result<ReadResult, IoError> {
    let format = match opts.format.or_else(|| Format::from_path(path)) {
        Some(f) => f,
        None => {
            return Err(IoError::new(
                path,
                IoErrorKind::UnknownFormat(path.display().to_string()),
            ))
        }
    };
    let mut r = match format {
        Format::Spx => spx::read(path, opts),
        Format::Binary => binary::read(path, opts),
        Format::Off => off::read(path, opts),
        Format::Ply => ply::read(path, opts),
        Format::Obj => obj::read(path, opts),
        Format::Stl => stl::read(path, opts),
        Format::Medit => medit::read(path, opts),
        Format::Vtk => vtk::read(path, opts),
        Format::Gmsh | Format::Gmsh22 => gmsh::read(path, opts),
        Format::Tri | Format::Ts | Format::Sierp | Format::Hex => {
            stellar_ref::read(path, format, opts)
        }
    }?;
    r.format = format;
    Ok(r)
}

/// Writes `complex` in `format` (or the extension's). The file appears only when complete.
///
/// # Errors
/// Unknown or read-only formats, a complex the format cannot hold, operating-system errors.
pub fn write(path: &Path, complex: &IndexedComplex, format: Option<Format>) -> Result<(), IoError> {
    let format = match format.or_else(|| Format::from_path(path)) {
        Some(f) => f,
        None => {
            return Err(IoError::new(
                path,
                IoErrorKind::UnknownFormat(path.display().to_string()),
            ))
        }
    };
    match format {
        Format::Spx => atomic_write(path, |w| spx::write(w, complex)),
        Format::Binary => atomic_write(path, |w| binary::write(w, complex)),
        Format::Off => atomic_write(path, |w| off::write(w, complex)),
        Format::Ply => atomic_write(path, |w| ply::write(w, complex)),
        Format::Obj => atomic_write(path, |w| obj::write(w, complex)),
        Format::Medit => atomic_write(path, |w| medit::write(w, complex)),
        Format::Vtk => atomic_write(path, |w| vtk::write(w, complex)),
        Format::Gmsh => atomic_write(path, |w| gmsh::write(w, complex)),
        Format::Gmsh22 => atomic_write(path, |w| gmsh::write_22(w, complex)),
        Format::Stl | Format::Tri | Format::Ts | Format::Sierp | Format::Hex => Err(IoError::new(
            path,
            IoErrorKind::CannotWrite {
                format,
                reason: "starplex reads this format but does not write it".into(),
            },
        )),
    }
}

/// Runs `f` on a buffered writer to a temporary file beside `path`, then renames it over `path`.
/// On any error the temporary file is removed and `path` is untouched.
///
/// # Errors
/// What `f` returns (its path is replaced by `path`), or the OS error of create/flush/rename.
pub fn atomic_write(
    path: &Path,
    f: impl FnOnce(&mut dyn std::io::Write) -> Result<(), IoErrorKind>,
) -> Result<(), IoError> {
    use std::io::Write;
    let dir = path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let tmp = dir.join(format!(".{name}.{}.tmp", std::process::id()));
    let result = (|| -> Result<(), IoErrorKind> {
        let file = std::fs::File::create(&tmp)?;
        let mut w = std::io::BufWriter::with_capacity(1 << 20, file);
        f(&mut w)?;
        w.flush()?;
        w.into_inner().map_err(|e| e.into_error())?.sync_all().ok();
        std::fs::rename(&tmp, path)?;
        Ok(())
    })();
    result.map_err(|kind| {
        let _ = std::fs::remove_file(&tmp);
        IoError::new(path, kind)
    })
}
