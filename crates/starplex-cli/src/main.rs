//! `starplex`: the command-line tool. One subcommand per verb; human-readable output by default,
//! `--json` for scripts; exit status 2 on bad input, 1 on other failures.
use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};

mod cmd_bench;
mod cmd_bench_hasse;
mod cmd_compare;
mod cmd_convert;
mod cmd_demo;
mod cmd_generate;
mod cmd_homology;
mod cmd_info;
mod cmd_query;
mod cmd_render;
mod cmd_rips;
mod cmd_simplify;
mod cmd_stellar;
mod cmd_validate;
mod common;

/// Topology of meshes and complexes.
#[derive(Parser, Debug)]
#[command(name = "starplex", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
    /// Hide progress bars.
    #[arg(long, global = true)]
    quiet: bool,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Summary of a complex: counts, f-vector, Euler characteristic, boundary, components.
    Info(cmd_info::InfoArgs),
    /// Convert between formats (by extension, or --format / --to).
    Convert(cmd_convert::ConvertArgs),
    /// Build a Stellar tree: statistics and build-phase timings (optionally save it).
    Stellar(cmd_stellar::StellarArgs),
    /// Topological validation: components, purity, pseudo-manifoldness, boundary,
    /// non-manifold vertices and edges, orientability.
    Validate(cmd_validate::ValidateArgs),
    /// Query one data structure through the shared interface (VT, VV, link, star, ...).
    Query(cmd_query::QueryArgs),
    /// Generate a complex (the Freudenthal triangulation of a grid) for tests and scale runs.
    Generate(cmd_generate::GenerateArgs),
    /// Homology: Betti numbers over Z/2, Z/p, Q or Z (torsion), per component, generators.
    Homology(cmd_homology::HomologyArgs),
    /// Simplify by edge contraction keeping the topology (homology or quadric-error mode).
    Simplify(cmd_simplify::SimplifyArgs),
    /// Build every data structure and compare storage and query times.
    Compare(cmd_compare::CompareArgs),
    /// Timings of one data structure (single thread): `bench simplex-tree FILE`.
    Bench(cmd_bench::BenchArgs),
    /// Vietoris–Rips complex of a point cloud, stored by its maximal simplices.
    Rips(cmd_rips::RipsArgs),
    /// Flag (clique) complex of a graph given as an edge list, stored by its maximal simplices.
    Flag(cmd_rips::FlagArgs),
    /// A picture (PNG or SVG) of the complex: plain, Stellar blocks, components, defects,
    /// boundary; clipping plane, wireframe, side-by-side comparison.
    Render(cmd_render::RenderArgs),
    /// The main job on the bundled sample (what `cargo run --release` does without arguments).
    Demo {
        /// A file to use instead of the bundled sample.
        file: Option<PathBuf>,
    },
}

/// Restores the default SIGPIPE action, so `starplex info big.off | head` ends quietly when the
/// reader closes the pipe, as other Unix tools do (Rust ignores SIGPIPE by default, which turns a
/// closed pipe into a panic inside `println!`).
fn default_sigpipe() {
    #[cfg(unix)]
    // SAFETY: called once at the start of `main`, before any other thread exists; SIG_DFL is a
    // valid action for SIGPIPE.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
}

fn main() -> ExitCode {
    default_sigpipe();
    starplex_cli::alloc::tune();
    let cli = Cli::parse();
    let ctx = common::Ctx { quiet: cli.quiet };
    let result = match cli.command {
        None => cmd_demo::run(&ctx, None),
        Some(Command::Demo { file }) => cmd_demo::run(&ctx, file),
        Some(Command::Info(a)) => cmd_info::run(&ctx, &a),
        Some(Command::Convert(a)) => cmd_convert::run(&ctx, &a),
        Some(Command::Stellar(a)) => cmd_stellar::run(&ctx, &a),
        Some(Command::Validate(a)) => cmd_validate::run(&ctx, &a),
        Some(Command::Bench(a)) => cmd_bench::run(&ctx, &a),
        Some(Command::Query(a)) => cmd_query::run(&ctx, &a),
        Some(Command::Compare(a)) => cmd_compare::run(&ctx, &a),
        Some(Command::Generate(a)) => cmd_generate::run(&ctx, &a),
        Some(Command::Homology(a)) => cmd_homology::run(&ctx, &a),
        Some(Command::Simplify(a)) => cmd_simplify::run(&ctx, &a),
        Some(Command::Rips(a)) => cmd_rips::run_rips(&ctx, &a),
        Some(Command::Flag(a)) => cmd_rips::run_flag(&ctx, &a),
        Some(Command::Render(a)) => cmd_render::run(&ctx, &a),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("starplex: error: {e}");
            if let Some(hint) = e.hint() {
                eprintln!("hint: {hint}");
            }
            ExitCode::from(e.status())
        }
    }
}
