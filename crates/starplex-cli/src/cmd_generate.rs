//! `starplex generate grid N [N ...] OUT`: the Freudenthal triangulation of a grid of unit cubes
//! (one N per axis), written in any format; `.spb` for the large ones (`generate grid 203 203
//! 203 big.spb` is 50.2 million tetrahedra in 1 GB).
use std::path::PathBuf;

use starplex::io;

use crate::common::{self, CliError, Ctx};

#[derive(clap::Args, Debug)]
pub struct GenerateArgs {
    #[command(subcommand)]
    pub what: GenerateWhat,
}

#[derive(clap::Subcommand, Debug)]
pub enum GenerateWhat {
    /// Freudenthal (Kuhn) triangulation of an N1 x N2 x ... grid of unit cubes: d! simplices per
    /// cube, a pure manifold d-ball.
    Grid {
        /// Cubes along each axis (1 to 8 axes).
        #[arg(required = true, num_args = 1..=8)]
        cubes: Vec<usize>,
        /// Output file (format from its extension unless --to is given; `-` is standard output).
        #[arg(short, long)]
        out: PathBuf,
        /// Output format.
        #[arg(long)]
        to: Option<String>,
    },
}

pub fn run(ctx: &Ctx, a: &GenerateArgs) -> Result<(), CliError> {
    let GenerateWhat::Grid { cubes, out, to } = &a.what;
    let to = common::output_format_for(to.as_deref(), out)?;
    let k = common::with_spinner(ctx, "generating", || starplex::gen::kuhn_grid(cubes)).map_err(
        |e| {
            CliError::Input(
                format!("generate grid {cubes:?}: {e}"),
                Some("use fewer cubes: cells and vertices are numbered with 32 bits".into()),
            )
        },
    )?;
    common::with_spinner(ctx, "writing", || io::write(out, &k, to))?;
    if !ctx.quiet {
        eprintln!(
            "wrote {} ({} vertices, {} cells)",
            common::shown(out),
            k.n_vertices(),
            k.n_cells()
        );
    }
    Ok(())
}
