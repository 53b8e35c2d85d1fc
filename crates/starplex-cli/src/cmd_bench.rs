//! `starplex bench <structure> FILE`: build and query timings of one structure (single thread).
use std::time::Instant;

use starplex::ids::{SimplexId, VertexId};
use starplex::tds::simplex_tree::{SimplexTree, SimplexTreeOptions};
use starplex::topo::SimplexVertices;

use crate::common::{self, CliError, Ctx, InputArgs};

#[derive(clap::Args, Debug)]
pub struct BenchArgs {
    #[command(subcommand)]
    pub what: BenchWhat,
}

#[derive(clap::Subcommand, Debug)]
pub enum BenchWhat {
    /// Simplex tree: build time, bytes per simplex, star of every vertex (with label lists).
    SimplexTree(SimplexTreeBenchArgs),
    /// IA*: build time per top cell, storage.
    IaStar(SimplexTreeBenchArgs),
    /// CASC Hasse complex: insert, bytes per simplex, star/link of every vertex, 1000 collapses.
    Hasse(crate::cmd_bench_hasse::BenchHasseArgs),
}

#[derive(clap::Args, Debug)]
pub struct SimplexTreeBenchArgs {
    #[command(flatten)]
    pub input: InputArgs,
    /// Build repetitions (the median is reported).
    #[arg(long, default_value_t = 3)]
    pub reps: usize,
    /// JSON output.
    #[arg(long)]
    pub json: bool,
}

pub fn run(ctx: &Ctx, a: &BenchArgs) -> Result<(), CliError> {
    match &a.what {
        BenchWhat::SimplexTree(b) => simplex_tree(ctx, b),
        BenchWhat::IaStar(b) => ia_star(ctx, b),
        BenchWhat::Hasse(b) => crate::cmd_bench_hasse::run(ctx, b),
    }
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(|a, b| a.total_cmp(b));
    v[v.len() / 2]
}

fn simplex_tree(ctx: &Ctx, a: &SimplexTreeBenchArgs) -> Result<(), CliError> {
    let k = common::load(ctx, &a.input)?.complex;
    let mut times = Vec::new();
    let mut times_ll = Vec::new();
    let mut st = None;
    for _ in 0..a.reps.max(1) {
        drop(st.take());
        let t = Instant::now();
        let s = SimplexTree::new(&k, &SimplexTreeOptions::default())
            .map_err(|e| CliError::Input(e.to_string(), None))?;
        times.push(t.elapsed().as_secs_f64());
        drop(s);
        let t = Instant::now();
        let s = SimplexTree::new(
            &k,
            &SimplexTreeOptions {
                label_lists: true,
                ..Default::default()
            },
        )
        .map_err(|e| CliError::Input(e.to_string(), None))?;
        times_ll.push(t.elapsed().as_secs_f64());
        st = Some(s);
    }
    let st = st.expect("at least one build");
    let plain = SimplexTree::new(&k, &SimplexTreeOptions::default())
        .map_err(|e| CliError::Input(e.to_string(), None))?;
    use starplex::topo::Storage;
    let n = st.n_simplices() as f64;
    let t = Instant::now();
    let mut ids: Vec<SimplexId> = Vec::new();
    let mut total = 0u64;
    for v in 0..k.n_vertices() {
        st.star_ids(&[VertexId(v as u32)], &mut ids)
            .map_err(|e| CliError::Other(e.to_string()))?;
        total += ids.len() as u64;
    }
    let star_all_s = t.elapsed().as_secs_f64();
    let insert_s = median(times);
    let insert_ll_s = median(times_ll);
    if a.json {
        println!(
            "{}",
            serde_json::json!({
                "structure": "simplex-tree",
                "input": a.input.file.display().to_string(),
                "num_simplices": st.n_simplices(),
                "insert_s": insert_s,
                "insert_label_lists_s": insert_ll_s,
                "bytes_per_simplex": plain.bytes() as f64 / n,
                "bytes_per_simplex_label_lists": st.bytes() as f64 / n,
                "star_all_s": star_all_s,
                "star_all_total": total,
            })
        );
    } else {
        println!(
            "simplex tree of {} ({} simplices)",
            a.input.file.display(),
            st.n_simplices()
        );
        println!("  insert (build)        {insert_s:.3} s  (with label lists {insert_ll_s:.3} s)");
        println!(
            "  bytes per simplex     {:.1}  (with label lists {:.1})",
            plain.bytes() as f64 / n,
            st.bytes() as f64 / n
        );
        println!("  star of every vertex  {star_all_s:.3} s  ({total} simplices in all stars)");
    }
    Ok(())
}

fn ia_star(ctx: &Ctx, a: &SimplexTreeBenchArgs) -> Result<(), CliError> {
    use starplex::tds::iastar::IaStar;
    use starplex::topo::Storage;
    let k = common::load(ctx, &a.input)?.complex;
    let mut times = Vec::new();
    let mut cpu_times = Vec::new();
    let mut ia = None;
    for _ in 0..a.reps.max(1) {
        drop(ia.take());
        let (t, c) = (Instant::now(), starplex::measure::thread_cpu_seconds());
        let s = IaStar::new(&k).map_err(|e| CliError::Input(e.to_string(), None))?;
        times.push(t.elapsed().as_secs_f64());
        if let (Some(c0), Some(c1)) = (c, starplex::measure::thread_cpu_seconds()) {
            cpu_times.push(c1 - c0);
        }
        ia = Some(s);
    }
    let ia = ia.expect("at least one build");
    let build_s = median(times);
    let us_per_top = 1e6 * build_s / k.n_cells().max(1) as f64;
    // CPU time of the building thread: meaningful on a loaded machine
    let build_cpu_s = (!cpu_times.is_empty()).then(|| median(cpu_times));
    let us_per_top_cpu = build_cpu_s.map(|c| 1e6 * c / k.n_cells().max(1) as f64);
    if a.json {
        println!(
            "{}",
            serde_json::json!({
                "structure": "ia-star",
                "input": a.input.file.display().to_string(),
                "top_cells": k.n_cells(),
                "build_s": build_s,
                "us_per_top": us_per_top,
                "build_cpu_s": build_cpu_s,
                "us_per_top_cpu": us_per_top_cpu,
                "refs": ia.refs(),
                "bytes": ia.bytes(),
            })
        );
    } else {
        println!(
            "IA* of {}: built in {build_s:.3} s ({us_per_top:.3} us per top cell), {} refs, {} bytes",
            a.input.file.display(),
            ia.refs(),
            ia.bytes()
        );
    }
    Ok(())
}
