//! `starplex validate FILE [--json] [--check | --fail-on DEFECTS]`: topological validation on a
//! Stellar tree; exit status 1 when a defect asked for is found (for scripts and CI).
use std::time::Instant;

use serde_json::json;

use crate::cmd_stellar::{build_tree, with_threads};
use crate::common::{self, CliError, Ctx, InputArgs};

#[derive(clap::Args, Debug)]
pub struct ValidateArgs {
    #[command(flatten)]
    pub input: InputArgs,
    /// Bucketing threshold of the Stellar tree used.
    #[arg(long)]
    pub kv: Option<u32>,
    /// How the Stellar tree splits vertices into blocks: spatial (by coordinates, the default)
    /// or graph (by connectivity alone, for complexes without meaningful coordinates). A saved
    /// tree keeps the one it was built with.
    #[arg(long)]
    pub decomposition: Option<String>,
    /// Worker threads (default: all cores).
    #[arg(long)]
    pub threads: Option<usize>,
    /// Longest list of ids printed per problem (the counts are always complete).
    #[arg(long, default_value_t = 1000)]
    pub max_list: usize,
    /// Print one JSON object.
    #[arg(long)]
    pub json: bool,
    /// Exit with status 1 when the complex has a defect: the same as
    /// `--fail-on non-manifold,non-pure,non-orientable,isolated`.
    #[arg(long)]
    pub check: bool,
    /// Exit with status 1 when the complex has any of these (comma-separated): non-manifold
    /// (vertices or edges, or faces in more than two top cells), non-pure, non-orientable,
    /// isolated (vertices), boundary, disconnected, undecided (links not classified, d >= 4).
    #[arg(long, value_delimiter = ',', value_name = "DEFECTS")]
    pub fail_on: Vec<Defect>,
    /// Also write a picture of the defects (OUT.png or OUT.svg; `render --color defects`).
    #[arg(long, value_name = "OUT")]
    pub render: Option<std::path::PathBuf>,
}

pub use starplex_cli::report::{defects_found, Defect};
pub use starplex_cli::report::{print_validation as print_human, validation_json as to_json};

/// `--decomposition` on a saved tree: it keeps the decomposition it was built with.
pub fn saved_tree_decomposition(file: &std::path::Path) -> CliError {
    CliError::Input(
        format!(
            "{}: a saved Stellar tree keeps the decomposition it was built with",
            file.display()
        ),
        Some("drop --decomposition, or run on the mesh file to build the tree anew".into()),
    )
}

pub fn run(ctx: &Ctx, a: &ValidateArgs) -> Result<(), CliError> {
    let t0 = Instant::now();
    let saved = starplex::stellar::is_saved_tree(&a.input.file);
    let decomp = a.decomposition.as_deref().unwrap_or("spatial");
    crate::cmd_stellar::decomposition(decomp)?;
    if saved && a.decomposition.is_some() {
        return Err(saved_tree_decomposition(&a.input.file));
    }
    let (k, notes) = if saved {
        (None, Vec::new())
    } else {
        let r = common::load(ctx, &a.input)?;
        (Some(r.complex), r.notes)
    };
    let read_s = t0.elapsed().as_secs_f64();
    let (rep, build_s, validate_s) = with_threads(a.threads, || {
        let t1 = Instant::now();
        let t = match &k {
            Some(k) => build_tree(ctx, k, a.kv, "auto", decomp)?,
            None => crate::cmd_stellar::load_saved_tree(ctx, &a.input.file)?,
        };
        let build_s = t1.elapsed().as_secs_f64();
        let t2 = Instant::now();
        let rep = common::with_spinner(ctx, "validating", || t.validate());
        Ok::<_, CliError>((rep, build_s, t2.elapsed().as_secs_f64()))
    })??;
    if a.json {
        let mut v = to_json(&rep, a.max_list);
        v["timings"] = json!({"read_s": read_s, "build_s": build_s, "validate_s": validate_s});
        if !notes.is_empty() {
            v["notes"] = json!(notes);
        }
        println!(
            "{}",
            serde_json::to_string_pretty(&v).map_err(|e| CliError::Other(e.to_string()))?
        );
    } else {
        println!("{}", a.input.file.display());
        print_human(&rep, a.max_list);
        println!("  time                read {read_s:.3} s, Stellar tree {build_s:.3} s, validation {validate_s:.3} s");
    }
    let wanted = Defect::wanted(a.check, &a.fail_on);
    if let Some(out) = &a.render {
        crate::cmd_render::shortcut(
            ctx,
            k.as_ref(),
            &a.input.file,
            out,
            starplex::render::ColorMode::Defects,
            a.kv,
            starplex::render::Given {
                validation: Some(&rep),
                ..Default::default()
            },
        )?;
    }
    let found = defects_found(&rep, &wanted);
    if !found.is_empty() {
        return Err(CliError::Other(format!(
            "{}: validation failed: {}",
            a.input.file.display(),
            found.join("; ")
        )));
    }
    Ok(())
}
