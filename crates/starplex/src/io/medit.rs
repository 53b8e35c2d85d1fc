//! Reader and writer for this format (in progress).
use std::path::Path;

use super::{IoError, IoErrorKind, ReadOptions, ReadResult};
use crate::complex::IndexedComplex;

/// Reads a file of this format.
///
/// # Errors
/// Not implemented yet.
pub fn read(path: &Path, _opts: &ReadOptions) -> Result<ReadResult, IoError> {
    Err(IoError::parse(
        path,
        None,
        "this format is not supported yet",
    ))
}

/// Writes this format.
///
/// # Errors
/// Not implemented yet.
pub fn write(_w: &mut dyn std::io::Write, _k: &IndexedComplex) -> Result<(), IoErrorKind> {
    Err(IoErrorKind::Parse(
        "this format is not supported yet".into(),
    ))
}
