//! `starplex stellar FILE [--kv N] [--threads T] [--save OUT] [--json]`: build a Stellar tree,
//! print its statistics and the time of each build phase.
use std::path::PathBuf;
use std::time::Instant;

use serde_json::{json, Value};
use starplex::measure;
use starplex::stellar::{Decomposition, SplitMode, StellarOptions, StellarTree};

use crate::common::{self, CliError, Ctx, InputArgs};

#[derive(clap::Args, Debug)]
pub struct StellarArgs {
    #[command(flatten)]
    pub input: InputArgs,
    /// Bucketing threshold: most vertices per leaf (0 = a single leaf; default 100 for
    /// surfaces, 400 for volumes and above).
    #[arg(long)]
    pub kv: Option<u32>,
    /// Split rule: auto (2^n regular up to 3 ambient dimensions, kD above), regular, kd.
    #[arg(long, default_value = "auto")]
    pub split: String,
    /// How vertices are split into blocks: spatial (by coordinates, with --split) or graph (by
    /// connectivity alone: recursive bisection of the vertex graph of the top cells, for
    /// complexes without meaningful coordinates such as flag complexes of graphs).
    #[arg(long, default_value = "spatial")]
    pub decomposition: String,
    /// Worker threads (default: all cores).
    #[arg(long)]
    pub threads: Option<usize>,
    /// Save the tree to this file (binary, memory-mappable).
    #[arg(long)]
    pub save: Option<PathBuf>,
    /// Also time the batched queries (VT, p-faces, validation) after the build.
    #[arg(long)]
    pub bench: bool,
    /// Print one JSON object.
    #[arg(long)]
    pub json: bool,
    /// Also write a picture of the tree's leaf blocks (OUT.png or OUT.svg; `render --color blocks`).
    #[arg(long, value_name = "OUT")]
    pub render: Option<PathBuf>,
}

pub fn split_mode(s: &str) -> Result<SplitMode, CliError> {
    match s {
        "auto" => Ok(SplitMode::Auto),
        "regular" => Ok(SplitMode::Regular),
        "kd" => Ok(SplitMode::Kd),
        _ => Err(CliError::Input(
            format!("unknown split rule '{s}'"),
            Some("use auto, regular or kd".into()),
        )),
    }
}

pub fn decomposition(s: &str) -> Result<Decomposition, CliError> {
    match s {
        "spatial" => Ok(Decomposition::Spatial),
        "graph" => Ok(Decomposition::Graph),
        _ => Err(CliError::Input(
            format!("unknown decomposition '{s}'"),
            Some("use spatial or graph".into()),
        )),
    }
}

/// Runs `f` on a pool of `threads` threads (or the global pool).
pub fn with_threads<T: Send>(
    threads: Option<usize>,
    f: impl FnOnce() -> T + Send,
) -> Result<T, CliError> {
    match threads {
        None => Ok(f()),
        Some(0) => Err(CliError::Input("--threads must be at least 1".into(), None)),
        Some(t) => {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(t)
                .build()
                .map_err(|e| CliError::Other(e.to_string()))?;
            Ok(pool.install(f))
        }
    }
}

pub fn build_tree(
    ctx: &Ctx,
    k: &starplex::complex::IndexedComplex,
    kv: Option<u32>,
    split: &str,
    decomp: &str,
) -> Result<StellarTree, CliError> {
    let opts = StellarOptions {
        kv,
        split: split_mode(split)?,
        decomposition: decomposition(decomp)?,
        ..Default::default()
    };
    common::with_spinner(ctx, "building the Stellar tree", || {
        StellarTree::build(k, &opts)
    })
    .map_err(|e| CliError::Input(e.to_string(), None))
}

pub use starplex_cli::report::{
    print_stellar_stats as print_stats, stellar_stats_json as stats_json,
};

/// Loads a saved tree (memory-mapped), mapping its error to an input error.
pub fn load_saved_tree(ctx: &Ctx, path: &std::path::Path) -> Result<StellarTree, CliError> {
    common::with_spinner(ctx, "loading the saved Stellar tree", || {
        StellarTree::load(path)
    })
    .map_err(|e| {
        CliError::Input(
            e.to_string(),
            Some("rebuild it with `starplex stellar MESH --save OUT`".into()),
        )
    })
}

pub fn run(ctx: &Ctx, a: &StellarArgs) -> Result<(), CliError> {
    // bad option values fail before any reading
    split_mode(&a.split)?;
    decomposition(&a.decomposition)?;
    let t0 = Instant::now();
    let saved = starplex::stellar::is_saved_tree(&a.input.file);
    let k = if saved {
        None
    } else {
        Some(common::load(ctx, &a.input)?.complex)
    };
    let read_s = t0.elapsed().as_secs_f64();
    let rss_loaded = measure::memory().map(|m| m.resident);
    let peak_reset = measure::reset_peak();
    let c0 = measure::process_cpu_seconds();
    let (t, build_s) = with_threads(a.threads, || {
        let t1 = Instant::now();
        let t = match &k {
            Some(k) => build_tree(ctx, k, a.kv, &a.split, &a.decomposition),
            None => load_saved_tree(ctx, &a.input.file),
        };
        (t, t1.elapsed().as_secs_f64())
    })?;
    let build_cpu = c0.and_then(|c| Some(measure::process_cpu_seconds()? - c));
    let t = t?;
    // what the memory ratios are measured against: the indexed complex (or, for a loaded
    // tree, its base complex)
    let complex_bytes = k
        .as_ref()
        .map_or(t.stats().storage.base_bytes, |k| k.bytes() as u64);
    let s = t.stats();
    let bt = t.timings();
    let mut timings = json!({
        "read_s": read_s,
        "build_s": if saved { 0.0 } else { build_s },
        "load_s": if saved { Some(build_s) } else { None },
        "decomposition_s": bt.decomposition_s,
        "vertex_reindex_s": bt.vertex_reindex_s,
        "cell_reindex_s": bt.cell_reindex_s,
        "leaf_lists_s": bt.leaf_lists_s,
        "build_cpu_s": build_cpu,
    });
    if a.bench {
        bench_phases(
            &t,
            a.threads,
            &mut timings,
            (peak_reset, rss_loaded),
            complex_bytes,
        )?;
    }
    if let Some(out) = &a.save {
        let t1 = Instant::now();
        // with the mesh's coordinates, so that the saved tree also reads as the mesh
        match &k {
            Some(k) => t.save_with_coords(out, k.coords()),
            None => t.save(out),
        }
        .map_err(|e| CliError::Other(e.to_string()))?;
        timings["save_s"] = json!(t1.elapsed().as_secs_f64());
    }
    if a.json {
        let mut v = stats_json(&s);
        v["split"] = json!(format!("{:?}", t.split()).to_lowercase());
        v["decomposition"] = json!(format!("{:?}", t.decomposition()).to_lowercase());
        v["timings"] = timings;
        if !t.attributes().is_empty() {
            // in the input's order (a saved tree stores them in tree order)
            v["attributes"] = crate::cmd_info::attributes_json(&t.input_attributes());
        }
        println!(
            "{}",
            serde_json::to_string_pretty(&v).map_err(|e| CliError::Other(e.to_string()))?
        );
    } else {
        print_human(a, &t, &s, &timings, saved, (build_s, build_cpu));
    }
    if let Some(out) = &a.render {
        crate::cmd_render::shortcut(
            ctx,
            k.as_ref(),
            &a.input.file,
            out,
            starplex::render::ColorMode::Blocks,
            a.kv,
            starplex::render::Given {
                tree: Some(&t),
                ..Default::default()
            },
        )?;
    }
    Ok(())
}

/// `--bench`: times the leaf-parallel phases (local VT, VT of every vertex, p-faces,
/// validation, global IA*) on `threads` threads into `timings` (wall, `cpu`, and the memory
/// over the loaded state when `mem` = (peak reset, RSS after loading) allows it).
fn bench_phases(
    t: &StellarTree,
    threads: Option<usize>,
    timings: &mut Value,
    mem: (bool, Option<u64>),
    complex_bytes: u64,
) -> Result<(), CliError> {
    let (peak_reset, rss_loaded) = mem;
    let mut cpu = serde_json::Map::new();
    let vt_mem: std::sync::Mutex<Option<(u64, u64)>> = std::sync::Mutex::new(None);
    let mut phase = |name: &str, f: &mut dyn FnMut()| -> f64 {
        let c = measure::process_cpu_seconds();
        let t1 = Instant::now();
        f();
        let wall = t1.elapsed().as_secs_f64();
        if let (Some(a), Some(b)) = (c, measure::process_cpu_seconds()) {
            cpu.insert(name.to_string(), json!(b - a));
        }
        wall
    };
    let (vt_local_s, vt_s, faces_s, validate_s, ia_s) = with_threads(threads, || {
        let vt_local_s = phase("vt_local_s", &mut || {
            // the reference's VT: expand every leaf (local VT in tree numbering)
            let n: Vec<usize> = t.par_map_leaves(|l| l.e.n_vt_refs());
            std::hint::black_box(n);
        });
        let vt_s = phase("vt_all_s", &mut || {
            // each row handed to a consumer that keeps it opaque: no shared atomic counter,
            // whose locked add per vertex was an eighth of this phase on one thread
            t.par_for_each_vt(|v, cells| {
                std::hint::black_box((v, cells));
            });
        });
        if let (true, Some(base), Some(measure::Memory { peak: hwm, .. })) =
            (peak_reset, rss_loaded, measure::memory())
        {
            *vt_mem.lock().unwrap_or_else(|e| e.into_inner()) = Some((base, hwm));
        }
        let faces_s = phase("p_faces_s", &mut || {
            for p in 1..t.dim().unwrap_or(0) {
                std::hint::black_box(t.count_p_faces(p).ok());
            }
        });
        let validate_s = phase("validate_s", &mut || {
            std::hint::black_box(t.validate());
        });
        let ia_s = phase("iastar_global_s", &mut || {
            std::hint::black_box(starplex::topo::Storage::refs(&t.iastar()));
        });
        (vt_local_s, vt_s, faces_s, validate_s, ia_s)
    })?;
    timings["vt_local_s"] = json!(vt_local_s);
    if let (true, Some(base), Some(measure::Memory { peak: hwm, .. })) =
        (peak_reset, rss_loaded, measure::memory())
    {
        timings["memory"] = json!({
            "complex_bytes": complex_bytes,
            "rss_after_load": base,
            "peak_rss_build_and_queries": hwm,
            "extra_over_loaded": hwm.saturating_sub(base),
            "extra_ratio_to_complex": hwm.saturating_sub(base) as f64 / complex_bytes.max(1) as f64,
        });
    }
    timings["iastar_global_s"] = json!(ia_s);
    if let Some((base, hwm)) = *vt_mem.lock().unwrap_or_else(|e| e.into_inner()) {
        timings["memory_build_and_vt"] = json!({
            "extra_over_loaded": hwm.saturating_sub(base),
            "extra_ratio_to_complex": hwm.saturating_sub(base) as f64 / complex_bytes.max(1) as f64,
        });
    }
    timings["cpu"] = Value::Object(cpu);
    timings["vt_all_s"] = json!(vt_s);
    timings["p_faces_s"] = json!(faces_s);
    timings["validate_s"] = json!(validate_s);
    Ok(())
}

/// The human-readable report: the tree's statistics, then the build (or load) and each timed
/// phase, per top cell; `build` = (build seconds, build CPU seconds).
fn print_human(
    a: &StellarArgs,
    t: &StellarTree,
    s: &starplex::stellar::StellarStats,
    timings: &Value,
    saved: bool,
    build: (f64, Option<f64>),
) {
    let (build_s, build_cpu) = build;
    let n_cells = t.n_top_cells();
    let bt = t.timings();
    println!("{}", a.input.file.display());
    print_stats(s);
    let per = |x: f64| 1e6 * x / (n_cells.max(1) as f64);
    if saved {
        println!(
            "  loaded              {:.3} s (saved tree, memory-mapped and checked)",
            build_s
        );
    } else {
        println!(
        "  build               {:.3} s ({:.3} us per top cell): decomposition {:.3}, vertex reindex {:.3}, cell reindex {:.3}, leaf lists {:.3}",
        build_s,
        per(build_s),
        bt.decomposition_s,
        bt.vertex_reindex_s,
        bt.cell_reindex_s,
        bt.leaf_lists_s
    );
    }
    if let (false, Some(c)) = (saved, build_cpu) {
        println!(
            "  build cpu           {c:.3} s ({:.3} us per top cell)",
            per(c)
        );
    }
    for key in [
        "vt_local_s",
        "vt_all_s",
        "p_faces_s",
        "validate_s",
        "iastar_global_s",
        "save_s",
    ] {
        if let Some(x) = timings[key].as_f64() {
            let c = timings["cpu"][key].as_f64();
            println!(
                "  {:<19} {:.3} s ({:.3} us per top cell){}",
                key.trim_end_matches("_s"),
                x,
                per(x),
                c.map(|c| format!(", cpu {c:.3} s ({:.3} us)", per(c)))
                    .unwrap_or_default()
            );
        }
    }
}
