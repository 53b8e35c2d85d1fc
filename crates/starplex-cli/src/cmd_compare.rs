//! `starplex compare FILE`: builds every structure and reports build time, storage (references
//! and bytes, normalised by the indexed complex) and the time of the batched VT, VV, boundary,
//! co-boundary, link and p-face queries, all through the `topo` traits. Every structure is
//! built and queried on the same number of workers (`--threads`, default all cores; 1 gives
//! single-thread times).
use std::time::Instant;

use rayon::prelude::*;

use starplex::ids::{CellId, VertexId};
use starplex::topo::{Queries, QueryError};

use crate::cmd_query::{self, RelationKind, StructureKind};
use crate::common::{self, CliError, Ctx, InputArgs};

#[derive(clap::Args, Debug)]
pub struct CompareArgs {
    #[command(flatten)]
    pub input: InputArgs,
    /// JSON output (one object per structure).
    #[arg(long)]
    pub json: bool,
    /// Worker threads for every build and query (default: all cores).
    #[arg(long)]
    pub threads: Option<usize>,
}

fn qerr(e: QueryError) -> CliError {
    CliError::Other(e.to_string())
}

/// The seconds of one query over the whole complex, `None` when the structure answers it for
/// simplices only and the complex has CP cells (the reason is kept in `skipped`).
fn measured(
    what: &str,
    r: Result<f64, QueryError>,
    skipped: &mut Vec<String>,
) -> Result<Option<f64>, CliError> {
    match r {
        Ok(t) => Ok(Some(t)),
        Err(e @ QueryError::NotSimplicial(_)) => {
            skipped.push(format!("{what}: {e}"));
            Ok(None)
        }
        Err(e) => Err(qerr(e)),
    }
}

fn timed(f: impl FnOnce() -> Result<u64, QueryError>) -> Result<f64, QueryError> {
    let t = Instant::now();
    f()?;
    Ok(t.elapsed().as_secs_f64())
}

/// R_{k,k-1} of every top cell (in parallel on the current pool).
fn boundary_all(s: &(dyn Queries + Sync)) -> Result<u64, QueryError> {
    (0..s.n_top_cells() as u32)
        .into_par_iter()
        .with_min_len(1024)
        .map_init(
            || (Vec::new(), Vec::new()),
            |(tv, out), c| {
                tv.clear();
                s.top_cell_vertices(CellId(c), tv);
                let d = s.top_cell_kind(CellId(c)).dim();
                if d == 0 {
                    return Ok(0);
                }
                s.boundary(tv, d - 1, out)?;
                Ok((out.len() / d) as u64)
            },
        )
        .try_reduce(|| 0, |a, b| Ok(a + b))
}

/// R_{0,1} of every vertex (in parallel on the current pool).
fn coboundary_all(s: &(dyn Queries + Sync)) -> Result<u64, QueryError> {
    (0..s.n_vertices() as u32)
        .into_par_iter()
        .with_min_len(1024)
        .map_init(Vec::new, |out, v| {
            s.coboundary(&[VertexId(v)], 1, out)?;
            Ok((out.len() / 2) as u64)
        })
        .try_reduce(|| 0, |a, b| Ok(a + b))
}

pub fn run(ctx: &Ctx, a: &CompareArgs) -> Result<(), CliError> {
    let threads = match a.threads {
        Some(0) => return Err(CliError::Input("--threads must be at least 1".into(), None)),
        Some(t) => t,
        None => rayon::current_num_threads(),
    };
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| CliError::Other(e.to_string()))?;
    pool.install(|| compare(ctx, a, threads))
}

fn compare(ctx: &Ctx, a: &CompareArgs, threads: usize) -> Result<(), CliError> {
    let k = common::load(ctx, &a.input)?.complex;
    let base_refs = k.n_refs() as f64;
    let base_bytes = 4.0 * k.n_refs() as f64;
    if !a.json {
        println!(
            "{}: {} vertices, {} top cells; storage normalised by the indexed complex ({} refs); \
             {threads} thread(s)",
            a.input.file.display(),
            k.n_vertices(),
            k.n_cells(),
            k.n_refs()
        );
        println!(
            "{:<13} {:>8} {:>8} {:>8} {:>8} {:>8} {:>8} {:>8} {:>8} {:>8}",
            "structure",
            "build_s",
            "refs",
            "bytes",
            "vt_s",
            "vv_s",
            "bnd_s",
            "cobnd_s",
            "link_s",
            "pfaces_s"
        );
    }
    let cp = !k.is_simplicial();
    for kind in StructureKind::AVAILABLE {
        if cp && !kind.holds_cp() {
            // listed, not failed: the structure holds simplicial complexes only
            let why = match cmd_query::build(&k, kind) {
                Err(e) => match e.hint() {
                    Some(h) => format!("{e} ({h})"),
                    None => e.to_string(),
                },
                Ok(_) => "it holds simplicial complexes only".to_string(),
            };
            if a.json {
                println!(
                    "{}",
                    serde_json::json!({"structure": kind.name(), "skipped": why})
                );
            } else {
                println!("{:<13} skipped: {why}", kind.name());
            }
            continue;
        }
        let t = Instant::now();
        let s = match cmd_query::build(&k, kind) {
            Ok(s) => s,
            Err(e) => {
                if a.json {
                    println!(
                        "{}",
                        serde_json::json!({"structure": kind.name(), "error": e.to_string()})
                    );
                } else {
                    println!("{:<13} not built: {e}", kind.name());
                }
                continue;
            }
        };
        let build_s = t.elapsed().as_secs_f64();
        let s: &(dyn Queries + Sync) = s.as_ref();
        let mut skipped = Vec::new();
        let all = |r| -> Result<Result<f64, QueryError>, CliError> {
            Ok(cmd_query::try_run_all(s, r, threads)?.map(|x| x.2))
        };
        let vt_s = measured("vt", all(RelationKind::Vt)?, &mut skipped)?;
        let vv_s = measured("vv", all(RelationKind::Vv)?, &mut skipped)?;
        let boundary_s = measured("boundary", timed(|| boundary_all(s)), &mut skipped)?;
        let coboundary_s = measured("co-boundary", timed(|| coboundary_all(s)), &mut skipped)?;
        let link_s = measured("link", all(RelationKind::Link)?, &mut skipped)?;
        let pfaces_s = measured("p-faces", all(RelationKind::Pfaces)?, &mut skipped)?;
        let refs = s.refs() as f64 / base_refs;
        let bytes = s.bytes() as f64 / base_bytes;
        if a.json {
            let mut o = serde_json::json!({
                "structure": kind.name(),
                "threads": threads,
                "build_s": build_s,
                "refs": refs,
                "bytes": bytes,
                "refs_abs": s.refs(),
                "bytes_abs": s.bytes(),
                "vt_s": vt_s,
                "vv_s": vv_s,
                "boundary_s": boundary_s,
                "coboundary_s": coboundary_s,
                "link_s": link_s,
                "pfaces_s": pfaces_s,
            });
            if !skipped.is_empty() {
                o["skipped_queries"] = serde_json::json!(skipped);
            }
            println!("{o}");
        } else {
            let col = |x: Option<f64>| x.map_or(format!("{:>8}", "-"), |t| format!("{t:>8.3}"));
            println!(
                "{:<13} {:>8.3} {:>8.2} {:>8.2} {} {} {} {} {} {}",
                kind.name(),
                build_s,
                refs,
                bytes,
                col(vt_s),
                col(vv_s),
                col(boundary_s),
                col(coboundary_s),
                col(link_s),
                col(pfaces_s)
            );
            for why in &skipped {
                println!("{:<13}   - {why}", "");
            }
        }
    }
    Ok(())
}
