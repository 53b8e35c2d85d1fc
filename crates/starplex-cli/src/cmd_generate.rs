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
    /// Probabilistic Sierpinski filtering of the standard d-simplex, as the datasets' generator
    /// (same numpy PCG64 stream: the same parameters give the same file).
    Sierpinski {
        /// Dimension of the simplex.
        #[arg(long)]
        dim: usize,
        /// Probability of keeping each corner child.
        #[arg(long, default_value_t = 0.35)]
        p: f64,
        /// numpy seed (`default_rng(seed)`).
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// Subdivide until at least this many simplices remain.
        #[arg(long)]
        target: usize,
        /// Stop after this many levels in any case.
        #[arg(long, default_value_t = 60)]
        max_levels: usize,
        /// Output file (format from its extension unless --to is given; `.off` is written as
        /// off-simplices).
        #[arg(short, long)]
        out: PathBuf,
        /// Output format.
        #[arg(long)]
        to: Option<String>,
    },
    /// Each triangle of a triangle mesh -> 3 quads (edge midpoints and centroid), as the
    /// datasets' generator.
    Quads {
        #[command(flatten)]
        input: common::InputArgs,
        /// Output file.
        #[arg(short, long)]
        out: PathBuf,
        /// Output format.
        #[arg(long)]
        to: Option<String>,
    },
    /// Midpoint 1-to-4 subdivision of a triangle mesh, as the datasets' generator.
    Subdivide {
        #[command(flatten)]
        input: common::InputArgs,
        /// Number of subdivision levels.
        #[arg(long, default_value_t = 1)]
        levels: usize,
        /// Output file.
        #[arg(short, long)]
        out: PathBuf,
        /// Output format.
        #[arg(long)]
        to: Option<String>,
    },
    /// Each tetrahedron of a tetrahedral mesh -> 4 hexahedra (edge midpoints, face centroids,
    /// centroid), as the datasets' generator.
    Hexes {
        #[command(flatten)]
        input: common::InputArgs,
        /// Output file.
        #[arg(short, long)]
        out: PathBuf,
        /// Output format.
        #[arg(long)]
        to: Option<String>,
    },
}

pub fn run(ctx: &Ctx, a: &GenerateArgs) -> Result<(), CliError> {
    let (cubes, out, to) = match &a.what {
        GenerateWhat::Grid { cubes, out, to } => (cubes, out, to),
        GenerateWhat::Sierpinski {
            dim,
            p,
            seed,
            target,
            max_levels,
            out,
            to,
        } => {
            if !(0.0..=1.0).contains(p) {
                return Err(CliError::Input(
                    format!("--p {p}: a probability must be in [0, 1]"),
                    None,
                ));
            }
            let mut to = common::output_format_for(to.as_deref(), out)?;
            if to.is_none() && io::Format::from_path(out) == Some(io::Format::Off) {
                to = Some(io::Format::OffSimplices);
            }
            let o = starplex::generate::sierpinski::SierpinskiOptions {
                dim: *dim,
                p: *p,
                seed: *seed,
                target: *target,
                max_levels: *max_levels,
            };
            let s = common::with_spinner(ctx, "generating", || {
                starplex::generate::sierpinski::sierpinski(&o)
            })
            .map_err(|e| CliError::Input(format!("generate sierpinski: {e}"), None))?;
            common::with_spinner(ctx, "writing", || io::write(out, &s.complex, to))?;
            if !ctx.quiet {
                eprintln!(
                    "wrote {} ({} vertices, {} {dim}-simplices, {} levels)",
                    common::shown(out),
                    s.complex.n_vertices(),
                    s.complex.n_cells(),
                    s.levels
                );
            }
            return Ok(());
        }
        GenerateWhat::Subdivide {
            input,
            levels,
            out,
            to,
        } => {
            let to = common::output_format_for(to.as_deref(), out)?;
            let r = common::load(ctx, input)?;
            let k = common::with_spinner(ctx, "subdividing", || {
                starplex::generate::refine::subdivide_triangles(&r.complex, *levels)
            })
            .map_err(|e| CliError::Input(format!("{}: {e}", input.file.display()), None))?;
            common::with_spinner(ctx, "writing", || io::write(out, &k, to))?;
            if !ctx.quiet {
                eprintln!(
                    "wrote {} ({} vertices, {} triangles)",
                    common::shown(out),
                    k.n_vertices(),
                    k.n_cells()
                );
            }
            return Ok(());
        }
        GenerateWhat::Quads { input, out, to } | GenerateWhat::Hexes { input, out, to } => {
            let quads = matches!(a.what, GenerateWhat::Quads { .. });
            let to = common::output_format_for(to.as_deref(), out)?;
            let r = common::load(ctx, input)?;
            let k = common::with_spinner(ctx, "refining", || {
                if quads {
                    starplex::generate::refine::triangles_to_quads(&r.complex)
                } else {
                    starplex::generate::refine::tets_to_hexes(&r.complex)
                }
            })
            .map_err(|e| CliError::Input(format!("{}: {e}", input.file.display()), None))?;
            common::with_spinner(ctx, "writing", || io::write(out, &k, to))?;
            if !ctx.quiet {
                eprintln!(
                    "wrote {} ({} vertices, {} {})",
                    common::shown(out),
                    k.n_vertices(),
                    k.n_cells(),
                    if quads { "quads" } else { "hexahedra" }
                );
            }
            return Ok(());
        }
    };
    let to = common::output_format_for(to.as_deref(), out)?;
    let k = common::with_spinner(ctx, "generating", || starplex::generate::kuhn_grid(cubes))
        .map_err(|e| {
            CliError::Input(
                format!("generate grid {cubes:?}: {e}"),
                Some("use fewer cubes: cells and vertices are numbered with 32 bits".into()),
            )
        })?;
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
