//! Where written bytes go: the one write path of every writer (`io::write`, `convert`,
//! `generate -o`, `stellar --save`).
//!
//! - A regular file (or a name that does not exist yet) is written to a temporary file beside it
//!   and renamed over it, so a reader never sees half a file and a failed write leaves the old
//!   file untouched (the temporary file is removed). A replaced file keeps its permissions.
//! - A symbolic link is followed: its final target is written (atomically, as above) and the
//!   link stays a link.
//! - `-`, `/dev/stdout` (and `/dev/fd/1`, `/proc/self/fd/1`) go to the process's standard
//!   output, `/dev/stderr` to standard error; a FIFO, a character device or a socket is opened
//!   and written straight through (a rename would replace it instead of feeding it).
//!
//! ```
//! use starplex::io::output::{self, OutputTarget};
//! use std::path::Path;
//! assert_eq!(output::resolve(Path::new("-")).unwrap(), OutputTarget::Stdout);
//! assert_eq!(output::resolve(Path::new("/dev/stdout")).unwrap(), OutputTarget::Stdout);
//! assert_eq!(output::resolve(Path::new("/dev/null")).unwrap(), OutputTarget::Stream("/dev/null".into()));
//! let dir = std::env::temp_dir().join(format!("starplex-doc-output-{}", std::process::id()));
//! std::fs::create_dir_all(&dir).unwrap();
//! let file = dir.join("a.txt");
//! output::write_with(&file, |w| Ok(w.write_all(b"hello")?)).unwrap();
//! assert_eq!(std::fs::read(&file).unwrap(), b"hello");
//! // a failing writer leaves the old content and no temporary file
//! let e = output::write_with(&file, |w| {
//!     w.write_all(b"half")?;
//!     Err(starplex::io::IoErrorKind::Parse("stopped".into()))
//! });
//! assert!(e.is_err());
//! assert_eq!(std::fs::read(&file).unwrap(), b"hello");
//! assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 1);
//! std::fs::remove_dir_all(&dir).ok();
//! ```
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

use super::{IoError, IoErrorKind};

/// Where [`write_with`] sends the bytes for a given path.
///
/// ```
/// use starplex::io::output::{resolve, OutputTarget};
/// let p = std::env::temp_dir().join(format!("starplex-doc-target-{}.off", std::process::id()));
/// assert_eq!(resolve(&p).unwrap(), OutputTarget::File(p.clone())); // not there yet: a new file
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum OutputTarget {
    /// The process's standard output (`-`, `/dev/stdout`, `/dev/fd/1`, `/proc/self/fd/1`).
    Stdout,
    /// The process's standard error (`/dev/stderr`, `/dev/fd/2`, `/proc/self/fd/2`).
    Stderr,
    /// A FIFO, character device or socket (or a file reached through `/dev/fd/N` or
    /// `/proc/*/fd/N`): opened and written straight through.
    Stream(PathBuf),
    /// A regular file (possibly the target of symbolic links, possibly not existing yet):
    /// written to a temporary file in its directory and renamed over it.
    File(PathBuf),
}

fn std_stream(p: &Path) -> Option<OutputTarget> {
    match p.to_str()? {
        "-" | "/dev/stdout" | "/dev/fd/1" | "/proc/self/fd/1" => Some(OutputTarget::Stdout),
        "/dev/stderr" | "/dev/fd/2" | "/proc/self/fd/2" => Some(OutputTarget::Stderr),
        _ => None,
    }
}

/// A path under `/dev/fd/` or `/proc/<pid>/fd/`: an already-open descriptor, which must be
/// written through (renaming beside its target would bypass whoever holds it).
fn is_fd_path(p: &Path) -> bool {
    let s = p.to_string_lossy();
    s.starts_with("/dev/fd/") || (s.starts_with("/proc/") && s.contains("/fd/"))
}

/// Decides where the bytes for `path` go, following symbolic links (at most 40).
///
/// ```
/// use starplex::io::output::{resolve, OutputTarget};
/// use std::path::Path;
/// assert_eq!(resolve(Path::new("/dev/stderr")).unwrap(), OutputTarget::Stderr);
/// // a directory cannot be written
/// assert!(resolve(&std::env::temp_dir()).is_err());
/// ```
///
/// # Errors
/// A directory, a block device, a symbolic link loop, or an OS error while reading links or
/// metadata (a missing final name is not an error: the file is created).
pub fn resolve(path: &Path) -> Result<OutputTarget, IoError> {
    if let Some(t) = std_stream(path) {
        return Ok(t);
    }
    let mut cur = path.to_path_buf();
    for _ in 0..40 {
        if let Some(t) = std_stream(&cur) {
            return Ok(t);
        }
        if is_fd_path(&cur) {
            return Ok(OutputTarget::Stream(cur));
        }
        let meta = match std::fs::symlink_metadata(&cur) {
            Ok(m) => m,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
                return Ok(OutputTarget::File(cur))
            }
            Err(e) => return Err(IoError::new(path, e)),
        };
        let ft = meta.file_type();
        if ft.is_symlink() {
            let link = std::fs::read_link(&cur).map_err(|e| IoError::new(path, e))?;
            cur = if link.is_absolute() {
                link
            } else {
                cur.parent().unwrap_or(Path::new("")).join(link)
            };
            continue;
        }
        if ft.is_file() {
            return Ok(OutputTarget::File(cur));
        }
        if ft.is_dir() {
            return Err(IoError::new(
                path,
                IoErrorKind::Os(std::io::Error::other("is a directory, not a file")),
            ));
        }
        #[cfg(unix)]
        {
            use std::os::unix::fs::FileTypeExt;
            if ft.is_block_device() {
                return Err(IoError::new(
                    path,
                    IoErrorKind::Os(std::io::Error::other(
                        "is a block device: refusing to write a mesh over it",
                    )),
                ));
            }
        }
        // FIFO, character device, socket
        return Ok(OutputTarget::Stream(cur));
    }
    Err(IoError::new(
        path,
        IoErrorKind::Os(std::io::Error::other("too many levels of symbolic links")),
    ))
}

static COUNTER: AtomicU64 = AtomicU64::new(0);

/// Runs `f` on a buffered writer to where `path` leads (see the module docs and [`resolve`]):
/// standard output, a stream written straight through, or a temporary file renamed over the
/// (link-resolved) regular file. On any error a temporary file is removed and the old file is
/// untouched; a stream may have received part of the output.
///
/// ```
/// use starplex::io::output;
/// let dir = std::env::temp_dir().join(format!("starplex-doc-write-with-{}", std::process::id()));
/// std::fs::create_dir_all(&dir).unwrap();
/// let real = dir.join("real.txt");
/// std::fs::write(&real, "old").unwrap();
/// # #[cfg(unix)] {
/// let link = dir.join("link.txt");
/// std::os::unix::fs::symlink("real.txt", &link).unwrap();
/// output::write_with(&link, |w| Ok(w.write_all(b"new")?)).unwrap();
/// assert!(std::fs::symlink_metadata(&link).unwrap().file_type().is_symlink()); // still a link
/// assert_eq!(std::fs::read(&real).unwrap(), b"new"); // its target was written
/// # }
/// std::fs::remove_dir_all(&dir).ok();
/// ```
///
/// # Errors
/// What `f` returns (located at `path`), or the OS error of resolving, creating, writing,
/// flushing or renaming.
pub fn write_with(
    path: &Path,
    f: impl FnOnce(&mut dyn Write) -> Result<(), IoErrorKind>,
) -> Result<(), IoError> {
    match resolve(path)? {
        OutputTarget::Stdout => {
            let out = std::io::stdout();
            let mut w = std::io::BufWriter::with_capacity(1 << 20, out.lock());
            let r = f(&mut w).and_then(|()| Ok(w.flush()?));
            r.map_err(|k| IoError::new(path, k))
        }
        OutputTarget::Stderr => {
            let err = std::io::stderr();
            let mut w = std::io::BufWriter::with_capacity(1 << 16, err.lock());
            let r = f(&mut w).and_then(|()| Ok(w.flush()?));
            r.map_err(|k| IoError::new(path, k))
        }
        OutputTarget::Stream(p) => {
            let r = (|| -> Result<(), IoErrorKind> {
                let meta = std::fs::metadata(&p)?;
                let file = std::fs::OpenOptions::new()
                    .write(true)
                    .truncate(meta.is_file())
                    .open(&p)?;
                let mut w = std::io::BufWriter::with_capacity(1 << 20, file);
                f(&mut w)?;
                w.flush()?;
                Ok(())
            })();
            r.map_err(|k| IoError::new(path, k))
        }
        OutputTarget::File(target) => atomic(path, &target, f),
    }
}

/// Writes a temporary file beside `target` and renames it over `target`; errors name `shown`.
fn atomic(
    shown: &Path,
    target: &Path,
    f: impl FnOnce(&mut dyn Write) -> Result<(), IoErrorKind>,
) -> Result<(), IoError> {
    let dir = target
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let name = target
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let old = std::fs::metadata(target).ok();
    let mut tmp = PathBuf::new();
    let result = (|| -> Result<(), IoErrorKind> {
        let file = loop {
            tmp = dir.join(format!(
                ".{name}.{}.{}.tmp",
                std::process::id(),
                COUNTER.fetch_add(1, Ordering::Relaxed)
            ));
            match std::fs::OpenOptions::new()
                .write(true)
                .create_new(true)
                .open(&tmp)
            {
                Ok(f) => break f,
                Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => continue,
                Err(e) => {
                    tmp = PathBuf::new();
                    return Err(e.into());
                }
            }
        };
        if let Some(m) = &old {
            // keep the replaced file's permission bits (best effort: not an error if refused)
            let _ = file.set_permissions(m.permissions());
        }
        let mut w = std::io::BufWriter::with_capacity(1 << 20, file);
        f(&mut w)?;
        w.flush()?;
        w.into_inner().map_err(|e| e.into_error())?.sync_all().ok();
        std::fs::rename(&tmp, target)?;
        Ok(())
    })();
    result.map_err(|kind| {
        if !tmp.as_os_str().is_empty() {
            let _ = std::fs::remove_file(&tmp);
        }
        IoError::new(shown, kind)
    })
}
