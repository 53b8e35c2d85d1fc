//! `starplex`: the command-line tool. One subcommand per verb; human-readable output by default,
//! `--json` for scripts; exit status 2 on bad input, 1 on other failures.
use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};

mod cmd_bench_hasse;
mod cmd_convert;
mod cmd_info;
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
    /// TEMPORARY (to be nested as `bench hasse`): benchmark the CASC Hasse complex on FILE.
    BenchHasse(cmd_bench_hasse::BenchHasseArgs),
    /// The main job on the bundled sample (what `cargo run --release` does without arguments).
    Demo {
        /// A file to use instead of the bundled sample.
        file: Option<PathBuf>,
    },
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let ctx = common::Ctx { quiet: cli.quiet };
    let result = match cli.command {
        None => common::demo(&ctx, None),
        Some(Command::Demo { file }) => common::demo(&ctx, file),
        Some(Command::Info(a)) => cmd_info::run(&ctx, &a),
        Some(Command::Convert(a)) => cmd_convert::run(&ctx, &a),
        Some(Command::BenchHasse(a)) => cmd_bench_hasse::run(&ctx, &a),
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
