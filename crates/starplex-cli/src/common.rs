//! Shared pieces of the subcommands: errors with exit codes, loading with a progress spinner,
//! the bundled sample.
use std::path::{Path, PathBuf};

use starplex::io::{self, Format, PolygonMode, ReadOptions, ReadResult};

/// Global options.
pub struct Ctx {
    pub quiet: bool,
}

/// An error of the command line: input problems exit with 2, everything else with 1.
#[derive(Debug)]
pub enum CliError {
    /// Bad input file or arguments.
    Input(String, Option<String>),
    /// Anything else.
    Other(String),
}

impl CliError {
    pub fn status(&self) -> u8 {
        match self {
            CliError::Input(..) => 2,
            CliError::Other(_) => 1,
        }
    }
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
            io::IoErrorKind::UnknownFormat(_) => Some("pass --format NAME (spx, off, ply, obj, stl, mesh, vtk, msh, tri, ts, sierp, hex, spb)".to_string()),
            io::IoErrorKind::Complex(starplex::complex::ComplexError::CellIsFaceOf { .. }) => {
                Some("pass --drop-faces to keep only the maximal cells".to_string())
            }
            io::IoErrorKind::Complex(starplex::complex::ComplexError::DuplicateCell { .. }) => {
                Some("pass --drop-duplicates to keep the first copy".to_string())
            }
            io::IoErrorKind::CannotWrite { .. } => Some("choose a format that holds these cells (spx, spb, vtk, mesh, msh)".to_string()),
            _ => None,
        };
        match e.kind {
            io::IoErrorKind::Os(_) if e.location.is_none() => CliError::Input(e.to_string(), hint),
            _ => CliError::Input(e.to_string(), hint),
        }
    }
}

/// Options shared by every command that reads a complex.
#[derive(clap::Args, Debug, Clone)]
pub struct InputArgs {
    /// Input file (format from the extension unless --format is given).
    pub file: PathBuf,
    /// Input format: spx, spb, off, ply, obj, stl, mesh, vtk, msh, tri, ts, sierp, hex.
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
}

impl InputArgs {
    pub fn read_options(&self) -> Result<ReadOptions, CliError> {
        let format = match &self.format {
            None => None,
            Some(name) => Some(Format::from_name(name).ok_or_else(|| {
                CliError::Input(
                    format!("unknown format '{name}'"),
                    Some("use one of spx spb off ply obj stl mesh vtk msh tri ts sierp hex".into()),
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
    for n in &r.notes {
        if !ctx.quiet {
            eprintln!("note: {name}: {n}");
        }
    }
    Ok(r)
}

/// The bundled sample: `data/elephant.off` of the repository (CGAL's elephant surface).
pub fn bundled_sample() -> PathBuf {
    let p = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/elephant.off");
    p.canonicalize().unwrap_or(p)
}

/// The main job: load the sample, print its summary.
pub fn demo(ctx: &Ctx, file: Option<PathBuf>) -> Result<(), CliError> {
    let file = file.unwrap_or_else(bundled_sample);
    println!(
        "starplex {} — main job on {}",
        env!("CARGO_PKG_VERSION"),
        file.display()
    );
    println!("(run `starplex --help` for every command)\n");
    let input = InputArgs {
        file,
        format: None,
        simplices: false,
        drop_faces: false,
        drop_duplicates: false,
    };
    let args = crate::cmd_info::InfoArgs {
        input: input.clone(),
        json: false,
        max_faces: None,
        betti: false,
    };
    crate::cmd_info::run(ctx, &args)?;
    demo_stellar(ctx, &input)
}

/// The Stellar tree summary and the validation of the sample (part of the main job).
fn demo_stellar(ctx: &Ctx, input: &InputArgs) -> Result<(), CliError> {
    let k = load(ctx, input)?.complex;
    let t0 = std::time::Instant::now();
    let t = crate::cmd_stellar::build_tree(ctx, &k, None, "auto")?;
    let build_s = t0.elapsed().as_secs_f64();
    println!("\nStellar tree");
    crate::cmd_stellar::print_stats(&t.stats());
    println!("  build               {build_s:.3} s");
    let t1 = std::time::Instant::now();
    let r = t.validate();
    println!("\nValidation");
    crate::cmd_validate::print_human(&r, 10);
    println!("  time                {:.3} s", t1.elapsed().as_secs_f64());
    Ok(())
}
