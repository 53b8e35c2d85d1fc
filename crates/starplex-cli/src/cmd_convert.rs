//! `starplex convert IN OUT [--to FORMAT] [--boundary] [--triangulate]`. `-` is standard input
//! (with `--format`) or standard output (with `--to`).
use std::path::PathBuf;

use starplex::algo::surface;
use starplex::io;

use crate::common::{self, CliError, Ctx, InputArgs};

#[derive(clap::Args, Debug)]
pub struct ConvertArgs {
    #[command(flatten)]
    pub input: InputArgs,
    /// Output file (format from its extension unless --to is given); `-` is standard output.
    /// A symbolic link is followed (its target is replaced), a FIFO or device written through.
    pub output: PathBuf,
    /// Output format: spx spb off off-simplices ply obj stl stl-binary mesh vtk vtk-polydata vtu
    /// vtp msh msh22 msh-binary msh22-binary.
    #[arg(long)]
    pub to: Option<String>,
    /// Write the boundary of the mesh (the faces in exactly one top cell, oriented outward)
    /// instead of the mesh: a tet or hex volume becomes its surface.
    #[arg(long)]
    pub boundary: bool,
    /// Split quads into triangles before writing (after --boundary).
    #[arg(long)]
    pub triangulate: bool,
}

pub fn run(ctx: &Ctx, a: &ConvertArgs) -> Result<(), CliError> {
    let to = common::output_format_for(a.to.as_deref(), &a.output)?;
    let r = common::load(ctx, &a.input)?;
    let mut k = r.complex;
    let convert_err = |e: surface::SurfaceError| {
        let hint = matches!(e, surface::SurfaceError::VolumeCell { .. }).then(|| {
            "pass --boundary as well: the boundary surface is taken first, then triangulated"
                .to_string()
        });
        CliError::Input(format!("{}: {e}", a.input.file.display()), hint)
    };
    let attrs = k.attributes().clone();
    if a.boundary {
        let (b, report) = surface::boundary(&k).map_err(convert_err)?;
        if !ctx.quiet && report.ignored_lower_cells > 0 {
            eprintln!(
                "note: --boundary ignored {} top cells of lower dimension than the mesh",
                report.ignored_lower_cells
            );
        }
        k = b;
    }
    if a.triangulate {
        k = surface::triangulate(&k).map_err(convert_err)?;
    }
    common::with_spinner(ctx, "writing", || io::write(&a.output, &k, to))?;
    if !attrs.is_empty() && !ctx.quiet {
        let names: Vec<&str> = attrs
            .vertex
            .iter()
            .chain(&attrs.cell)
            .map(|c| c.name.as_str())
            .collect();
        let format = to.or_else(|| io::Format::from_path(&a.output));
        if a.boundary || a.triangulate {
            eprintln!(
                "note: the attributes {} are not carried through --boundary/--triangulate",
                names.join(", ")
            );
        } else if let Some(f) = format {
            let dropped = f.dropped_attributes(&attrs);
            if !dropped.is_empty() {
                eprintln!(
                    "note: the attributes {} are not written: {f} cannot hold them (write .vtu, .vtk, .spx or .spb to keep them)",
                    dropped.join(", ")
                );
            }
        }
    }
    if !ctx.quiet {
        eprintln!(
            "wrote {} ({} vertices, {} cells)",
            common::shown(&a.output),
            k.n_vertices(),
            k.n_cells()
        );
    }
    Ok(())
}
