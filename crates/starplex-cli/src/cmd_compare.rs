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

fn timed(f: impl FnOnce() -> Result<u64, QueryError>) -> Result<(f64, u64), CliError> {
    let t = Instant::now();
    let n = f().map_err(qerr)?;
    Ok((t.elapsed().as_secs_f64(), n))
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
                if tv.len() < 2 {
                    return Ok(0);
                }
                s.boundary(tv, tv.len() - 2, out)?;
                Ok((out.len() / (tv.len() - 1)) as u64)
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
    for kind in StructureKind::AVAILABLE {
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
        let (vt_s, _, _) = {
            let (_, n, t) = cmd_query::run_all(s, RelationKind::Vt, threads)?;
            (t, n, ())
        };
        let (_, _, vv_s) = cmd_query::run_all(s, RelationKind::Vv, threads)?;
        let (boundary_s, _) = timed(|| boundary_all(s))?;
        let (coboundary_s, _) = timed(|| coboundary_all(s))?;
        let (_, _, link_s) = cmd_query::run_all(s, RelationKind::Link, threads)?;
        let (_, _, pfaces_s) = cmd_query::run_all(s, RelationKind::Pfaces, threads)?;
        let refs = s.refs() as f64 / base_refs;
        let bytes = s.bytes() as f64 / base_bytes;
        if a.json {
            println!(
                "{}",
                serde_json::json!({
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
                })
            );
        } else {
            println!(
                "{:<13} {:>8.3} {:>8.2} {:>8.2} {:>8.3} {:>8.3} {:>8.3} {:>8.3} {:>8.3} {:>8.3}",
                kind.name(),
                build_s,
                refs,
                bytes,
                vt_s,
                vv_s,
                boundary_s,
                coboundary_s,
                link_s,
                pfaces_s
            );
        }
    }
    Ok(())
}
