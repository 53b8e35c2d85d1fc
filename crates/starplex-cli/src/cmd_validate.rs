//! `starplex validate FILE [--json] [--check | --fail-on DEFECTS]`: topological validation on a
//! Stellar tree; exit status 1 when a defect asked for is found (for scripts and CI).
use std::time::Instant;

use serde_json::{json, Value};
use starplex::algo::validate::ValidationReport;

use crate::cmd_stellar::{build_tree, with_threads};
use crate::common::{self, CliError, Ctx, InputArgs};

#[derive(clap::Args, Debug)]
pub struct ValidateArgs {
    #[command(flatten)]
    pub input: InputArgs,
    /// Bucketing threshold of the Stellar tree used.
    #[arg(long)]
    pub kv: Option<u32>,
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

/// A property `validate --fail-on` can fail on.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum Defect {
    NonManifold,
    NonPure,
    NonOrientable,
    Isolated,
    Boundary,
    Disconnected,
    Undecided,
}

/// The defects of `r` among `wanted`, each with its count, in words.
pub fn defects_found(r: &ValidationReport, wanted: &[Defect]) -> Vec<String> {
    let mut out = Vec::new();
    for &d in wanted {
        let found = match d {
            Defect::NonManifold => {
                let (v, e, f) = (
                    r.non_manifold_vertices.len(),
                    r.non_manifold_edges.len(),
                    r.faces_in_more_than_two_cells.len(),
                );
                (v + e + f > 0).then(|| {
                    format!("{v} non-manifold vertices, {e} non-manifold edges, {f} faces in more than two top cells")
                })
            }
            Defect::NonPure => (!r.lower_dimensional_cells.is_empty()).then(|| {
                format!(
                    "{} lower-dimensional top cells (not pure)",
                    r.lower_dimensional_cells.len()
                )
            }),
            Defect::NonOrientable => {
                (r.orientable == Some(false)).then(|| "not orientable".to_string())
            }
            Defect::Isolated => (!r.isolated_vertices.is_empty())
                .then(|| format!("{} isolated vertices", r.isolated_vertices.len())),
            Defect::Boundary => (!r.boundary_faces.is_empty())
                .then(|| format!("{} boundary faces", r.boundary_faces.len())),
            Defect::Disconnected => (r.n_connected_components > 1)
                .then(|| format!("{} connected components", r.n_connected_components)),
            Defect::Undecided => {
                let (v, e) = (r.unknown_vertices.len(), r.unknown_edges.len());
                (v + e > 0).then(|| format!("{v} vertices and {e} edges not classified"))
            }
        };
        out.extend(found);
    }
    out
}

fn ids<T: Clone>(v: &[T], max: usize) -> Vec<T> {
    v[..v.len().min(max)].to_vec()
}

pub fn to_json(r: &ValidationReport, max: usize) -> Value {
    let vids = |v: &[starplex::ids::VertexId]| ids(v, max).iter().map(|x| x.0).collect::<Vec<_>>();
    let edges = |e: &[[starplex::ids::VertexId; 2]]| {
        ids(e, max)
            .iter()
            .map(|e| [e[0].0, e[1].0])
            .collect::<Vec<_>>()
    };
    let faces = |f: &[Vec<starplex::ids::VertexId>]| {
        ids(f, max)
            .iter()
            .map(|f| f.iter().map(|v| v.0).collect::<Vec<_>>())
            .collect::<Vec<_>>()
    };
    json!({
        "dim": r.dim,
        "n_connected_components": r.n_connected_components,
        "n_boundary_faces": r.boundary_faces.len(),
        "n_faces_shared_by_more_than_2_top_cells": r.faces_in_more_than_two_cells.len(),
        "n_non_manifold_vertices": r.non_manifold_vertices.len(),
        "n_non_manifold_edges": r.non_manifold_edges.len(),
        "n_unknown_vertices": r.unknown_vertices.len(),
        "n_unknown_edges": r.unknown_edges.len(),
        "n_isolated_vertices": r.isolated_vertices.len(),
        "n_lower_dimensional_cells": r.lower_dimensional_cells.len(),
        "n_facet_components": r.n_facet_components,
        "pure": r.pure,
        "facet_connected": r.facet_connected,
        "pseudo_manifold": r.pseudo_manifold,
        "orientable": r.orientable,
        "n_cells_to_flip": r.cells_to_flip.as_ref().map(|c| c.len()),
        "orientation_conflict": r.orientation_conflict.map(|(a, b)| [a.0, b.0]),
        "non_manifold_vertices": vids(&r.non_manifold_vertices),
        "non_manifold_edges": edges(&r.non_manifold_edges),
        "unknown_vertices": vids(&r.unknown_vertices),
        "isolated_vertices": vids(&r.isolated_vertices),
        "lower_dimensional_cells": ids(&r.lower_dimensional_cells, max).iter().map(|c| c.0).collect::<Vec<_>>(),
        "boundary_faces": faces(&r.boundary_faces),
        "faces_shared_by_more_than_2_top_cells": faces(&r.faces_in_more_than_two_cells),
        "lists_truncated_to": max,
    })
}

pub fn print_human(r: &ValidationReport, max: usize) {
    let yes = |b: bool| if b { "yes" } else { "no" };
    println!("  components          {}", r.n_connected_components);
    println!(
        "  pure                {} ({} isolated vertices, {} lower-dimensional cells)",
        yes(r.pure),
        r.isolated_vertices.len(),
        r.lower_dimensional_cells.len()
    );
    println!(
        "  (d-1)-connected     {} ({} classes of top cells)",
        yes(r.facet_connected),
        r.n_facet_components
    );
    println!("  pseudo-manifold     {}", yes(r.pseudo_manifold));
    println!(
        "  boundary faces      {} ({} faces in more than 2 top cells)",
        r.boundary_faces.len(),
        r.faces_in_more_than_two_cells.len()
    );
    let show = |v: Vec<String>| {
        if v.is_empty() {
            String::new()
        } else {
            format!(
                ": {}{}",
                v.iter()
                    .take(max.min(10))
                    .cloned()
                    .collect::<Vec<_>>()
                    .join(" "),
                if v.len() > 10 { " ..." } else { "" }
            )
        }
    };
    println!(
        "  non-manifold        {} vertices{}",
        r.non_manifold_vertices.len(),
        show(
            r.non_manifold_vertices
                .iter()
                .map(|v| v.to_string())
                .collect()
        )
    );
    println!(
        "                      {} edges{}",
        r.non_manifold_edges.len(),
        show(
            r.non_manifold_edges
                .iter()
                .map(|e| format!("{}-{}", e[0], e[1]))
                .collect()
        )
    );
    if !r.unknown_vertices.is_empty() || !r.unknown_edges.is_empty() {
        println!(
            "  undecided (d >= 4)  {} vertices, {} edges",
            r.unknown_vertices.len(),
            r.unknown_edges.len()
        );
    }
    match (r.orientable, &r.cells_to_flip, r.orientation_conflict) {
        (Some(true), Some(f), _) => println!(
            "  orientable          yes ({} cells to flip for a consistent orientation)",
            f.len()
        ),
        (Some(false), _, Some((a, b))) => {
            println!("  orientable          no (cells {a} and {b} cannot agree)")
        }
        _ => println!("  orientable          undefined (a (d-1)-face in more than two top cells)"),
    }
}

pub fn run(ctx: &Ctx, a: &ValidateArgs) -> Result<(), CliError> {
    let t0 = Instant::now();
    let saved = starplex::stellar::is_saved_tree(&a.input.file);
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
            Some(k) => build_tree(ctx, k, a.kv, "auto")?,
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
    let mut wanted = a.fail_on.clone();
    if a.check {
        for d in [
            Defect::NonManifold,
            Defect::NonPure,
            Defect::NonOrientable,
            Defect::Isolated,
        ] {
            if !wanted.contains(&d) {
                wanted.push(d);
            }
        }
    }
    if let Some(out) = &a.render {
        let k = k.as_ref().ok_or_else(|| {
            CliError::Input(
                "--render needs the mesh file, not a saved tree".into(),
                None,
            )
        })?;
        crate::cmd_render::shortcut(
            ctx,
            k,
            &a.input.file,
            out,
            starplex::render::ColorMode::Defects,
            a.kv,
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
