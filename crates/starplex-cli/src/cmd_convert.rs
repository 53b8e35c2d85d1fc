//! `starplex convert IN OUT`.
use std::path::PathBuf;

use starplex::io::{self, Format};

use crate::common::{self, CliError, Ctx, InputArgs};

#[derive(clap::Args, Debug)]
pub struct ConvertArgs {
    #[command(flatten)]
    pub input: InputArgs,
    /// Output file (format from its extension unless --to is given).
    pub output: PathBuf,
    /// Output format.
    #[arg(long)]
    pub to: Option<String>,
}

pub fn run(ctx: &Ctx, a: &ConvertArgs) -> Result<(), CliError> {
    let r = common::load(ctx, &a.input)?;
    let to = match &a.to {
        None => None,
        Some(n) => Some(
            Format::from_name(n)
                .ok_or_else(|| CliError::Input(format!("unknown output format '{n}'"), None))?,
        ),
    };
    common::with_spinner(ctx, "writing", || io::write(&a.output, &r.complex, to))?;
    if !ctx.quiet {
        eprintln!(
            "wrote {} ({} vertices, {} cells)",
            a.output.display(),
            r.complex.n_vertices(),
            r.complex.n_cells()
        );
    }
    Ok(())
}
