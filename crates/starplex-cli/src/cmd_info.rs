//! `starplex info FILE [--json]`.
use std::sync::Arc;
use std::time::Instant;

use serde_json::{json, Value};
use starplex::algo::info::{face_visits, info, Info, InfoOptions};
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
        opts.max_faces = m;
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
            opts.max_faces,
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

pub fn to_json(s: &Info) -> Value {
    json!({
        "n_vertices": s.n_vertices,
        "n_isolated_vertices": s.n_isolated_vertices,
        "ambient_dim": s.ambient_dim,
        "dim": s.dim,
        "pure": s.pure,
        "top_cells": s.top_cells,
        "n_top_cells": s.n_top_cells,
        "bbox": s.bbox.as_ref().map(|(lo, hi)| json!([lo, hi])),
        "f_vector": s.f_vector,
        "f_vector_estimate": s.f_vector_estimate.map(|e| e.to_string()),
        "euler_characteristic": s.euler_characteristic,
        "n_boundary_faces": s.n_boundary_faces,
        "n_faces_shared_by_more_than_2_top_cells": s.n_faces_shared_by_more_than_2_top_cells,
        "faces_by_type": s.faces_by_type,
        "n_connected_components": s.n_connected_components,
    })
}

fn print_human(s: &Info, name: &str, load_s: f64, info_s: f64, budget: u128) {
    println!("{name}");
    let kinds: Vec<String> = s
        .top_cells
        .iter()
        .map(|(k, n)| format!("{n} {k}"))
        .collect();
    println!(
        "  vertices            {} ({} isolated), ambient dimension {}",
        s.n_vertices, s.n_isolated_vertices, s.ambient_dim
    );
    println!(
        "  top cells           {} ({})",
        s.n_top_cells,
        kinds.join(", ")
    );
    println!(
        "  dimension           {}{}",
        s.dim,
        if s.pure { ", pure" } else { ", not pure" }
    );
    if let Some((lo, hi)) = &s.bbox {
        let f = |v: &Vec<f64>| {
            v.iter()
                .map(|x| format!("{x:.6}"))
                .collect::<Vec<_>>()
                .join(" ")
        };
        println!("  bounding box        [{}] .. [{}]", f(lo), f(hi));
    }
    match (&s.f_vector, s.f_vector_estimate) {
        (Some(f), _) => {
            println!("  f-vector            {f:?}");
            if let Some(m) = &s.faces_by_type {
                let parts: Vec<String> = m.iter().map(|(k, n)| format!("{n} {k}")).collect();
                println!("  2-faces by kind     {}", parts.join(", "));
            }
        }
        (None, Some(e)) => println!(
            "  f-vector            skipped: about {e} (cell, face) pairs to visit, over the budget of {budget} (raise it with --max-faces)"
        ),
        _ => {}
    }
    if let Some(x) = s.euler_characteristic {
        println!("  Euler char.         {x}");
    }
    if let Some(b) = s.n_boundary_faces {
        println!("  boundary faces      {b}");
    }
    if let Some(b) = s.n_faces_shared_by_more_than_2_top_cells {
        println!("  faces in >2 cells   {b}");
    }
    println!("  components          {}", s.n_connected_components);
    println!("  time                read {load_s:.3} s, info {info_s:.3} s");
}
