//! Shared pieces of the subcommands: errors with exit codes, loading with a progress spinner,
//! the bundled sample.
use std::path::{Path, PathBuf};

use starplex::io::{self, Format, PolygonMode, ReadOptions, ReadResult};

/// Global options.
pub struct Ctx {
    pub quiet: bool,
}

pub use starplex_cli::error::{CliError, READABLE};

/// The output format named by `--to` (`None`: from the output's extension).
pub fn output_format(to: Option<&str>) -> Result<Option<Format>, CliError> {
    let Some(n) = to else { return Ok(None) };
    match Format::from_name(n) {
        Some(f) if f.can_write() => Ok(Some(f)),
        Some(f) => Err(CliError::Input(
            format!("--to {n}: starplex reads {f} but does not write it"),
            Some(format!("writable formats: {}", Format::writable_names())),
        )),
        None => Err(CliError::Input(
            format!("--to {n}: unknown output format"),
            Some(format!("writable formats: {}", Format::writable_names())),
        )),
    }
}

/// The output format named by `--to`, or else by the output's extension: an output whose
/// extension names no writable format is an error whose hint lists the writable ones.
pub fn output_format_for(to: Option<&str>, out: &Path) -> Result<Option<Format>, CliError> {
    if let Some(f) = output_format(to)? {
        return Ok(Some(f));
    }
    if out.as_os_str() == "-" {
        return Ok(None); // io::write says standard output needs --to
    }
    match Format::from_path(out) {
        Some(f) if f.can_write() => Ok(None),
        Some(f) => Err(CliError::Input(
            format!(
                "{}: starplex reads {f} but does not write it",
                out.display()
            ),
            Some(format!(
                "choose the output format with --to ({})",
                Format::writable_names()
            )),
        )),
        None => Err(CliError::Input(
            format!(
                "{}: the extension names no format starplex writes",
                out.display()
            ),
            Some(format!(
                "choose the output format with --to ({})",
                Format::writable_names()
            )),
        )),
    }
}

/// How an output path is shown in messages (`-` as standard output).
pub fn shown(p: &Path) -> String {
    if p.as_os_str() == "-" {
        "standard output".into()
    } else {
        p.display().to_string()
    }
}

/// Options shared by every command that reads a complex.
#[derive(clap::Args, Debug, Clone)]
pub struct InputArgs {
    /// Input file (format from the extension unless --format is given); `-` is standard input
    /// (--format required).
    pub file: PathBuf,
    /// Input format: spx, spb, off, off-simplices, ply, obj, stl, mesh, vtk, msh, tri, ts,
    /// sierp, hex.
    #[arg(long)]
    pub format: Option<String>,
    /// Read every OFF/PLY/OBJ face of k vertices as a (k-1)-simplex (Stellar-reference convention
    /// for simplicial complexes of any dimension) instead of as a polygon.
    #[arg(long)]
    pub simplices: bool,
    /// Drop top cells that are faces of other top cells instead of failing.
    #[arg(long)]
    pub drop_faces: bool,
    /// Drop duplicate top cells instead of failing.
    #[arg(long)]
    pub drop_duplicates: bool,
    /// Drop degenerate cells (a vertex repeated in a cell, e.g. a triangle `0 1 1`) instead of
    /// failing; the number dropped is noted (and in `info --json` notes).
    #[arg(long)]
    pub drop_degenerate: bool,
    /// Accept an OFF file whose header face count disagrees with the face lines present: read
    /// the faces that are there, with a note.
    #[arg(long)]
    pub lenient: bool,
}

impl InputArgs {
    pub fn read_options(&self) -> Result<ReadOptions, CliError> {
        let format = match &self.format {
            None => None,
            Some(name) => Some(Format::from_name(name).ok_or_else(|| {
                CliError::Input(
                    format!("unknown format '{name}'"),
                    Some(format!("readable formats: {READABLE}")),
                )
            })?),
        };
        let mut o = ReadOptions {
            format,
            ..Default::default()
        };
        if self.simplices {
            o.polygons = PolygonMode::Simplices;
        }
        o.build.drop_face_cells = self.drop_faces;
        o.build.drop_duplicates = self.drop_duplicates;
        o.build.drop_degenerate = self.drop_degenerate;
        o.lenient = self.lenient;
        Ok(o)
    }
}

/// A spinner on stderr while `f` runs (hidden when quiet or not a terminal).
pub fn with_spinner<T>(ctx: &Ctx, msg: &str, f: impl FnOnce() -> T) -> T {
    let pb = progress_spinner(ctx, msg);
    let r = f();
    pb.finish_and_clear();
    r
}

pub fn progress_spinner(ctx: &Ctx, msg: &str) -> indicatif::ProgressBar {
    use std::io::IsTerminal;
    if ctx.quiet || !std::io::stderr().is_terminal() {
        return indicatif::ProgressBar::hidden();
    }
    let pb = indicatif::ProgressBar::new_spinner();
    pb.set_message(msg.to_string());
    pb.enable_steady_tick(std::time::Duration::from_millis(120));
    pb
}

pub fn progress_bar(ctx: &Ctx, len: u64, msg: &str) -> indicatif::ProgressBar {
    use std::io::IsTerminal;
    if ctx.quiet || !std::io::stderr().is_terminal() {
        return indicatif::ProgressBar::hidden();
    }
    let pb = indicatif::ProgressBar::new(len);
    pb.set_style(
        indicatif::ProgressStyle::with_template("{msg} [{bar:30}] {pos}/{len} ({eta})")
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar())
            .progress_chars("=> "),
    );
    pb.set_message(msg.to_string());
    pb
}

/// Reads a complex with a spinner.
pub fn load(ctx: &Ctx, args: &InputArgs) -> Result<ReadResult, CliError> {
    let opts = args.read_options()?;
    let name = args.file.display().to_string();
    let r = with_spinner(ctx, &format!("reading {name}"), || {
        io::read(&args.file, &opts)
    })?;
    // (--quiet hides progress, never what was changed on the way in)
    for n in &r.notes {
        eprintln!("note: {name}: {n}");
    }
    Ok(r)
}
