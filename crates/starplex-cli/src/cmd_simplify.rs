//! `starplex simplify IN OUT [--mode homology|qem] [--ratio R | --faces N | --vertices N |
//! --max-error E] [--lock-boundary] [--keep-labels NAME | --ignore-labels] [--keep-vertices FILE]
//! [--keep-vertex-attribute NAME] [--json]`: edge contraction that keeps the topology, with
//! a before/after report (f-vector, Euler characteristic, Betti numbers, non-manifold simplices,
//! boundary faces, a sampled Hausdorff estimate, the labels kept). Vertex and cell attributes
//! are carried to the output (the surviving vertices' and cells' own values). Nothing is
//! written when the input or the target is bad.
use std::path::PathBuf;
use std::sync::Arc;
use std::time::Instant;

use serde_json::{json, Value};
use starplex::algo::simplify::hausdorff::{hausdorff_estimate, HausdorffEstimate};
use starplex::algo::simplify::{
    default_label_attribute, simplify, summary, Mode, SimplifyError, SimplifyOptions,
    SimplifyReport, Target, TopologySummary,
};
use starplex::attr::AttrTarget;
use starplex::complex::IndexedComplex;
use starplex::io;

use starplex_cli::report::{print_topology_change, topology_json, topology_kept};

use crate::common::{self, CliError, Ctx, InputArgs};

#[derive(clap::Args, Debug)]
pub struct SimplifyArgs {
    #[command(flatten)]
    pub input: InputArgs,
    /// Output file (format from its extension unless --to is given).
    pub output: PathBuf,
    /// Output format (see `convert --help`).
    #[arg(long)]
    pub to: Option<String>,
    /// homology (link-condition contraction, any simplicial complex) or qem (quadric error,
    /// triangle and tetrahedral meshes; the default for them).
    #[arg(long)]
    pub mode: Option<String>,
    /// Keep this fraction of the top cells (0 to 1).
    #[arg(long, allow_hyphen_values = true)]
    pub ratio: Option<f64>,
    /// Stop at this many top cells.
    #[arg(long)]
    pub faces: Option<usize>,
    /// Stop at this many vertices.
    #[arg(long)]
    pub vertices: Option<usize>,
    /// qem: stop before a contraction whose quadric error exceeds this.
    #[arg(long, allow_hyphen_values = true)]
    pub max_error: Option<f64>,
    /// qem: boundary vertices neither move nor disappear.
    #[arg(long)]
    pub lock_boundary: bool,
    /// homology: also keep a manifold a manifold of its dimension (the extended link
    /// condition); qem always does.
    #[arg(long)]
    pub keep_manifold: bool,
    /// Keep the regions of this cell attribute (a label): vertices on the interface between
    /// two labels neither move nor disappear, so every region keeps its topology and the
    /// interfaces stay where they are. Default: gmsh:physical or medit:ref when the input has
    /// one (the report says which); --ignore-labels turns that off.
    #[arg(long, value_name = "NAME")]
    pub keep_labels: Option<String>,
    /// Do not keep the default label attribute's regions.
    #[arg(long, conflicts_with = "keep_labels")]
    pub ignore_labels: bool,
    /// Vertices (ids from 0, separated by white space or commas; `-` for standard input)
    /// that are never removed nor moved.
    #[arg(long, value_name = "FILE")]
    pub keep_vertices: Option<PathBuf>,
    /// Vertices whose value of this vertex attribute is not 0 are never removed nor moved.
    #[arg(long, value_name = "NAME")]
    pub keep_vertex_attribute: Option<String>,
    /// Skip the before/after topology (Betti numbers, validation): faster on big meshes.
    #[arg(long)]
    pub no_report: bool,
    /// Print one JSON object.
    #[arg(long)]
    pub json: bool,
    /// Worker threads: homology mode contracts blocks of the mesh in parallel rounds, and the
    /// before/after report runs on them (quadric-error contraction itself is sequential); the
    /// answer is the same for any number.
    #[arg(long)]
    pub threads: Option<usize>,
}

pub fn run(ctx: &Ctx, a: &SimplifyArgs) -> Result<(), CliError> {
    let mode = match a.mode.as_deref() {
        None => None,
        Some(m) => Some(Mode::parse(m).ok_or_else(|| {
            CliError::Input(
                format!("--mode {m}: unknown mode"),
                Some("use --mode homology or --mode qem".into()),
            )
        })?),
    };
    let threads = match a.threads {
        Some(0) => return Err(CliError::Input("--threads must be at least 1".into(), None)),
        Some(t) => t,
        None => rayon::current_num_threads(),
    };
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| CliError::Other(e.to_string()))?;
    pool.install(|| run_in_pool(ctx, a, mode))
}

fn run_in_pool(ctx: &Ctx, a: &SimplifyArgs, mode: Option<Mode>) -> Result<(), CliError> {
    let to = common::output_format_for(a.to.as_deref(), &a.output)?;
    let r = common::load(ctx, &a.input)?;
    let k = &r.complex;
    let name = a.input.file.display().to_string();
    let t_before = Instant::now();
    let before =
        (!a.no_report).then(|| common::with_spinner(ctx, "topology before", || summary(k)));
    let before_s = t_before.elapsed().as_secs_f64();
    let keep_labels = match (&a.keep_labels, a.ignore_labels) {
        (Some(n), _) => Some(n.clone()),
        (None, false) => default_label_attribute(k.attributes()).map(str::to_string),
        (None, true) => None,
    };
    let keep_vertices = keep_vertices(a, k, &name)?;
    let total = (k.n_vertices() as u64).max(1);
    let pb = common::progress_bar(ctx, total, "simplify");
    let pb2 = pb.clone();
    let opts = SimplifyOptions {
        mode,
        target: Target {
            faces: a.faces,
            vertices: a.vertices,
            ratio: a.ratio,
            max_error: a.max_error,
        },
        lock_boundary: a.lock_boundary,
        keep_manifold: a.keep_manifold,
        progress: Some(Arc::new(move |n| pb2.inc(n))),
        keep_labels,
        keep_vertices,
    };
    // the memory of the simplification alone, over what is resident once the input (and the
    // before report) are in memory
    let rss_loaded = starplex::measure::memory().map(|m| m.resident);
    let peak_reset = starplex::measure::reset_peak();
    let res = simplify(k, &opts);
    let memory = match (peak_reset, rss_loaded, starplex::measure::memory()) {
        (true, Some(base), Some(m)) => Some(json!({
            "complex_bytes": k.bytes(),
            "rss_before": base,
            "peak_rss": m.peak,
            "extra_over_loaded": m.peak.saturating_sub(base),
            "extra_ratio_to_complex": m.peak.saturating_sub(base) as f64 / k.bytes().max(1) as f64,
        })),
        _ => None,
    };
    pb.finish_and_clear();
    let (out, report) = res.map_err(|e| simplify_error(e, k, &name))?;
    let t_after = Instant::now();
    let after =
        (!a.no_report).then(|| common::with_spinner(ctx, "topology after", || summary(&out)));
    let hausdorff = if a.no_report {
        None
    } else {
        common::with_spinner(ctx, "Hausdorff estimate", || hausdorff_estimate(k, &out))
    };
    let after_s = t_after.elapsed().as_secs_f64();
    common::with_spinner(ctx, "writing", || io::write(&a.output, &out, to))?;
    let o = Outcome {
        name: &name,
        k,
        out: &out,
        report: &report,
        before,
        after,
        hausdorff,
        report_s: before_s + after_s,
        memory,
        labels_available: k
            .attributes()
            .cell
            .iter()
            .map(|a| a.name.as_str())
            .collect(),
    };
    if a.json {
        print_json(a, &o)
    } else {
        print_human(a, &o);
        Ok(())
    }
}

/// The vertices `--keep-vertices FILE` and `--keep-vertex-attribute NAME` (non-zero values)
/// ask to keep.
fn keep_vertices(a: &SimplifyArgs, k: &IndexedComplex, name: &str) -> Result<Vec<u32>, CliError> {
    let mut keep_vertices = match &a.keep_vertices {
        Some(f) => starplex_cli::export::read_ids(f)?,
        None => Vec::new(),
    };
    if let Some(n) = &a.keep_vertex_attribute {
        let col = k.attributes().get(AttrTarget::Vertex, n).ok_or_else(|| {
            let names: Vec<&str> = k
                .attributes()
                .vertex
                .iter()
                .map(|a| a.name.as_str())
                .collect();
            CliError::Input(
                format!("{name}: --keep-vertex-attribute {n}: no vertex attribute of that name"),
                Some(if names.is_empty() {
                    "the input has no vertex attribute".into()
                } else {
                    format!("its vertex attributes: {}", names.join(", "))
                }),
            )
        })?;
        let c = col.components;
        keep_vertices.extend(
            (0..k.n_vertices())
                .filter(|&v| (v * c..(v + 1) * c).any(|i| col.values.get_f64(i) != 0.0))
                .map(|v| v as u32),
        );
    }
    Ok(keep_vertices)
}

/// The library's refusal as an input error, with a hint per kind.
fn simplify_error(e: SimplifyError, k: &IndexedComplex, name: &str) -> CliError {
    let hint = match &e {
        SimplifyError::NotSimplicial { .. } => Some(format!(
            "starplex convert --triangulate {name} triangulated.off"
        )),
        SimplifyError::BadTarget(_) => Some(format!(
            "the input has {} vertices and {} top cells; --ratio is between 0 and 1",
            k.n_vertices(),
            k.n_cells()
        )),
        SimplifyError::NotAMesh => Some("pass --mode homology".into()),
        SimplifyError::UnknownLabel { .. } => {
            Some("name a cell attribute (`starplex info` lists them)".into())
        }
        _ => None,
    };
    CliError::Input(format!("{name}: {e}"), hint)
}

/// What one run did, for the reports.
struct Outcome<'a> {
    name: &'a str,
    k: &'a IndexedComplex,
    out: &'a IndexedComplex,
    report: &'a SimplifyReport,
    before: Option<TopologySummary>,
    after: Option<TopologySummary>,
    hausdorff: Option<HausdorffEstimate>,
    /// Seconds of the before/after summaries and the Hausdorff estimate.
    report_s: f64,
    /// The input's cell attributes.
    labels_available: Vec<&'a str>,
    /// Peak memory of the simplification over the loaded state (Linux).
    memory: Option<Value>,
}

/// `--json`: one object with the counts, errors, labels, attributes, Hausdorff estimate and
/// the topology before and after.
fn print_json(a: &SimplifyArgs, o: &Outcome<'_>) -> Result<(), CliError> {
    let Outcome {
        name,
        k,
        out,
        report,
        before,
        after,
        hausdorff,
        report_s,
        labels_available,
        memory,
    } = o;
    let mut v = json!({
        "input": name,
        "output": common::shown(&a.output),
        "mode": report.mode.name(),
        "target_faces": report.target_faces,
        "n_contractions": report.n_contractions,
        "rounds": report.rounds,
        "time_s": report.time_s,
        "report_time_s": report_s,
        "before": before.as_ref().map(topology_json),
        "after": after.as_ref().map(topology_json),
        "vertices": [k.n_vertices(), out.n_vertices()],
        "cells": [k.n_cells(), out.n_cells()],
    });
    if report.mode == Mode::Qem {
        v["max_error"] = json!(report.max_error);
        v["mean_error"] = json!(report.mean_error);
    }
    if let Some(m) = memory {
        v["memory"] = m.clone();
    }
    v["labels_kept"] = json!(report.kept_labels);
    v["labels_available"] = json!(labels_available);
    v["locked_vertices"] = json!(report.locked_vertices);
    v["attributes"] = json!({
        "vertex": out.attributes().vertex.iter().map(|a| &a.name).collect::<Vec<_>>(),
        "cell": out.attributes().cell.iter().map(|a| &a.name).collect::<Vec<_>>(),
    });
    v["hausdorff"] = match &hausdorff {
        None => Value::Null,
        Some(h) => json!({
            "estimate": "sampled: every surface vertex of one mesh to the closest triangle of the other",
            "input_to_output": h.a_to_b,
            "output_to_input": h.b_to_a,
            "max": h.max(),
            "mean_input_to_output": h.mean_a_to_b,
            "mean_output_to_input": h.mean_b_to_a,
            "samples": h.n_samples,
            "input_diagonal": h.diagonal,
        }),
    };
    if let (Some(b), Some(f)) = (&before, &after) {
        v["topology_kept"] = json!(topology_kept(b, f));
    }
    println!(
        "{}",
        serde_json::to_string_pretty(&v).map_err(|e| CliError::Other(e.to_string()))?
    );
    Ok(())
}

/// The human-readable report.
fn print_human(a: &SimplifyArgs, o: &Outcome<'_>) {
    let Outcome {
        name,
        k,
        out,
        report,
        before,
        after,
        hausdorff,
        labels_available,
        ..
    } = o;
    println!("{name} -> {}", common::shown(&a.output));
    println!("  mode                {}", report.mode.name());
    println!(
        "  vertices            {} -> {}",
        k.n_vertices(),
        out.n_vertices()
    );
    println!("  top cells           {} -> {}", k.n_cells(), out.n_cells());
    println!(
        "  contractions        {} in {} round(s), {:.3} s",
        report.n_contractions, report.rounds, report.time_s
    );
    if let (Some(m), Some(e)) = (report.max_error, report.mean_error) {
        println!("  quadric error       max {m:.3e}, mean {e:.3e}");
    }
    if let Some(h) = &hausdorff {
        println!(
            "  Hausdorff (est.)    {:.3e} (input->output {:.3e}, output->input {:.3e}; {:.3}% of the diagonal)",
            h.max(),
            h.a_to_b,
            h.b_to_a,
            100.0 * h.max() / h.diagonal.max(f64::MIN_POSITIVE)
        );
    }
    match (&report.kept_labels, labels_available.is_empty()) {
        (Some(l), _) => println!(
            "  labels              {l} kept ({} interface/kept vertices locked)",
            report.locked_vertices
        ),
        (None, true) => {}
        (None, false) => println!(
            "  labels              not kept (cell attributes: {})",
            labels_available.join(", ")
        ),
    }
    if report.kept_labels.is_none() && report.locked_vertices > 0 {
        println!("  kept vertices       {}", report.locked_vertices);
    }
    if let (Some(b), Some(f)) = (&before, &after) {
        print_topology_change(b, f);
    }
}
