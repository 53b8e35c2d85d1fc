//! `starplex info FILE [--json]`.
use std::sync::Arc;
use std::time::Instant;

use serde_json::{json, Value};
use starplex::algo::info::{face_visits, info, InfoOptions};
use starplex::attr::{Attribute, Attributes};

use crate::common::{self, CliError, Ctx, InputArgs};

#[derive(clap::Args, Debug)]
pub struct InfoArgs {
    #[command(flatten)]
    pub input: InputArgs,
    /// Print one JSON object (keys as in the dataset oracles).
    #[arg(long)]
    pub json: bool,
    /// Largest number of (cell, face) pairs to visit for the f-vector (default 4e9); above it the
    /// f-vector is skipped and an estimate printed.
    #[arg(long)]
    pub max_faces: Option<u128>,
    /// Also compute the Betti numbers over Z/2 (`betti_z2`, the oracles' key).
    #[arg(long)]
    pub betti: bool,
}

pub fn run(ctx: &Ctx, a: &InfoArgs) -> Result<(), CliError> {
    let t0 = Instant::now();
    let r = common::load(ctx, &a.input)?;
    let load_s = t0.elapsed().as_secs_f64();
    let k = &r.complex;
    let mut opts = InfoOptions::default();
    if let Some(m) = a.max_faces {
        opts.limits.info_faces = m;
    }
    let pb = if face_visits(k) > 5_000_000 {
        common::progress_bar(ctx, k.n_cells() as u64, "counting faces")
    } else {
        indicatif::ProgressBar::hidden()
    };
    let pb2 = pb.clone();
    opts.progress = Some(Arc::new(move |n| pb2.inc(n)));
    let t1 = Instant::now();
    let s = info(k, &opts);
    pb.finish_and_clear();
    let info_s = t1.elapsed().as_secs_f64();
    let betti = a.betti.then(|| starplex::algo::homology::betti_z2(k));
    if a.json {
        let mut v = to_json(&s);
        v["format"] = json!(r.format.extension());
        v["timings"] = json!({"read_s": load_s, "info_s": info_s});
        match &betti {
            Some(Ok(b)) => v["betti_z2"] = json!(b),
            Some(Err(e)) => v["betti_z2_skipped"] = json!(e.to_string()),
            None => {}
        }
        if !k.attributes().is_empty() {
            v["attributes"] = attributes_json(k.attributes());
        }
        if !r.notes.is_empty() {
            v["notes"] = json!(r.notes);
        }
        println!(
            "{}",
            serde_json::to_string_pretty(&v).map_err(|e| CliError::Other(e.to_string()))?
        );
    } else {
        print_human(
            &s,
            &a.input.file.display().to_string(),
            load_s,
            info_s,
            opts.limits.info_faces,
        );
        match &betti {
            Some(Ok(b)) => println!("  Betti numbers (Z/2) {b:?}"),
            Some(Err(e)) => println!("  Betti numbers (Z/2) skipped: {e}"),
            None => {}
        }
        for (label, cols) in [
            ("vertex attributes", &k.attributes().vertex),
            ("cell attributes", &k.attributes().cell),
        ] {
            if !cols.is_empty() {
                let parts: Vec<String> = cols.iter().map(attribute_label).collect();
                println!("  {label:<19} {}", parts.join(", "));
            }
        }
    }
    Ok(())
}

/// `name (int)`, `velocity (float x3)`, with the value range.
fn attribute_label(a: &Attribute) -> String {
    let comps = if a.components > 1 {
        format!(" x{}", a.components)
    } else {
        String::new()
    };
    let range = match a.range() {
        Some((lo, hi)) => format!(" in [{lo}, {hi}]"),
        None => String::new(),
    };
    format!("{} ({}{comps}{range})", a.name, a.values.type_name())
}

/// The attribute columns as JSON: `{"vertex": [{name, type, components, min, max}], "cell": [..]}`.
pub fn attributes_json(a: &Attributes) -> Value {
    let cols = |cols: &[Attribute]| -> Vec<Value> {
        cols.iter()
            .map(|c| {
                let r = c.range();
                json!({
                    "name": c.name,
                    "type": c.values.type_name(),
                    "components": c.components,
                    "min": r.map(|x| x.0),
                    "max": r.map(|x| x.1),
                })
            })
            .collect()
    };
    json!({"vertex": cols(&a.vertex), "cell": cols(&a.cell)})
}

pub use starplex_cli::report::info_json as to_json;
use starplex_cli::report::print_info as print_human;
