//! The command line's error: input problems exit with 2, everything else with 1; an input
//! error carries a hint that says what to do.
use starplex::io::{self, Format};

/// An error of the command line: input problems exit with 2, everything else with 1.
///
/// ```
/// use starplex_cli::error::CliError;
/// let e = CliError::Input("bad.off: empty".into(), Some("check the file".into()));
/// assert_eq!((e.status(), e.hint(), e.to_string().as_str()), (2, Some("check the file"), "bad.off: empty"));
/// assert_eq!(CliError::Other("x".into()).status(), 1);
/// ```
#[derive(Debug)]
pub enum CliError {
    /// Bad input file or arguments.
    Input(String, Option<String>),
    /// Anything else.
    Other(String),
}

impl CliError {
    /// The exit status: 2 for input errors, 1 otherwise.
    pub fn status(&self) -> u8 {
        match self {
            CliError::Input(..) => 2,
            CliError::Other(_) => 1,
        }
    }
    /// What to do about it, when known.
    pub fn hint(&self) -> Option<&str> {
        match self {
            CliError::Input(_, h) => h.as_deref(),
            CliError::Other(_) => None,
        }
    }
}

impl std::fmt::Display for CliError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            CliError::Input(m, _) | CliError::Other(m) => f.write_str(m),
        }
    }
}

impl From<io::IoError> for CliError {
    fn from(e: io::IoError) -> Self {
        let hint = match &e.kind {
            io::IoErrorKind::UnknownFormat(_) => Some(format!(
                "pass --format NAME to read it ({}), or --to NAME to write it ({})",
                READABLE,
                Format::writable_names()
            )),
            io::IoErrorKind::NeedsFormat { output: true, .. } => Some(format!(
                "pass --to NAME, e.g. --to off (writable formats: {})",
                Format::writable_names()
            )),
            io::IoErrorKind::NeedsFormat { output: false, .. } => Some(format!(
                "pass --format NAME, e.g. --format off (readable formats: {READABLE})"
            )),
            io::IoErrorKind::Complex(starplex::complex::ComplexError::CellIsFaceOf { .. }) => {
                Some("pass --drop-faces to keep only the maximal cells".to_string())
            }
            io::IoErrorKind::Complex(starplex::complex::ComplexError::DuplicateCell { .. }) => {
                Some("pass --drop-duplicates to keep the first copy".to_string())
            }
            io::IoErrorKind::CountMismatch(_) => {
                Some("pass --lenient to read what the file holds, with a note".to_string())
            }
            io::IoErrorKind::Complex(starplex::complex::ComplexError::RepeatedVertex { .. }) => {
                Some("pass --drop-degenerate to drop the cells with a repeated vertex".to_string())
            }
            io::IoErrorKind::CannotWrite { .. } => Some(format!(
                "choose another output format with --to ({}), or convert explicitly with --boundary / --triangulate",
                Format::writable_names()
            )),
            _ => None,
        };
        match e.kind {
            io::IoErrorKind::Os(_) if e.location.is_none() => CliError::Input(e.to_string(), hint),
            _ => CliError::Input(e.to_string(), hint),
        }
    }
}

/// The formats starplex reads, for hints.
pub const READABLE: &str =
    "spx spb off off-simplices ply obj stl mesh vtk vtu vtp msh tri ts sierp hex";
