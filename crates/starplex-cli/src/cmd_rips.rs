//! `starplex rips POINTS --eps E | --eps-nn F [--max-dim K] -o OUT` and `starplex flag EDGES -o
//! OUT`: complexes from data, stored by their maximal simplices (maximal cliques of the
//! neighbourhood graph or of the given graph).
use std::path::{Path, PathBuf};
use std::time::Instant;

use serde_json::json;
use starplex::algo::cliques::CliqueOptions;
use starplex::algo::rips::{self, Built, DistanceMatrix, Metric, RipsOptions};
use starplex::io::{self, Format};
use starplex::limits::Limits;

use crate::common::{self, CliError, Ctx};

/// Options shared by `rips` and `flag`.
#[derive(clap::Args, Debug)]
pub struct BuildArgs {
    /// Keep the K-skeleton, stored by its maximal simplices (cliques of more than K + 1 vertices
    /// are replaced by their (K+1)-subsets).
    #[arg(long, value_name = "K")]
    pub max_dim: Option<usize>,
    /// Output file (format from the extension unless --to is given; `.off` is written as
    /// off-simplices; `-` is standard output with --to).
    #[arg(short, long)]
    pub out: PathBuf,
    /// Output format.
    #[arg(long)]
    pub to: Option<String>,
    /// Memory budget for the graph and the output in GiB (default: a third of the available
    /// memory); larger outputs are refused with an estimate.
    #[arg(long, value_name = "GIB")]
    pub max_memory: Option<f64>,
    /// Print a JSON summary on standard output.
    #[arg(long)]
    pub json: bool,
}

#[derive(clap::Args, Debug)]
#[command(group(clap::ArgGroup::new("scale").required(true).args(["eps", "eps_nn"])))]
pub struct RipsArgs {
    /// Point cloud: .xyz (first 3 columns), .txt/.pts (whitespace columns), .csv, .npy, or the
    /// vertices of a mesh (.off, .ply, .obj, .spx, ...).
    pub points: PathBuf,
    /// Scale: two points are joined when their distance is at most E.
    #[arg(long, value_name = "E", allow_negative_numbers = true)]
    pub eps: Option<f64>,
    /// Scale as a multiple F of the median nearest-neighbour distance.
    #[arg(long, value_name = "F", allow_negative_numbers = true)]
    pub eps_nn: Option<f64>,
    /// Distance between points: euclidean (L2), manhattan (L1), chebyshev (L∞), or
    /// precomputed: POINTS is an n x n distance matrix (.npy, .csv, .txt; symmetric, zero
    /// diagonal).
    #[arg(long, value_enum, default_value_t = MetricArg::Euclidean)]
    pub metric: MetricArg,
    #[command(flatten)]
    pub build: BuildArgs,
}

/// `--metric`.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum MetricArg {
    /// L2.
    Euclidean,
    /// L1.
    Manhattan,
    /// L∞.
    Chebyshev,
    /// The input is a distance matrix.
    Precomputed,
}

impl MetricArg {
    fn name(self) -> &'static str {
        match self {
            MetricArg::Euclidean => "euclidean",
            MetricArg::Manhattan => "manhattan",
            MetricArg::Chebyshev => "chebyshev",
            MetricArg::Precomputed => "precomputed",
        }
    }
}

/// An n x n distance matrix from `.npy` (2-D, float64/float32/int64/int32) or text (`.csv`
/// with an optional header line, or whitespace columns), validated: errors name the file and
/// the row and column.
fn read_distance_matrix(path: &Path) -> Result<DistanceMatrix, CliError> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let (rows, cols, vals) = if ext.as_deref() == Some("npy") {
        read_npy_matrix(path)?
    } else {
        read_text_matrix(path)?
    };
    DistanceMatrix::new(rows, cols, vals).map_err(|e| {
        input_error(
            path,
            e,
            Some("--metric precomputed reads a distance matrix"),
        )
    })
}

fn read_npy_matrix(path: &Path) -> Result<(usize, usize, Vec<f64>), CliError> {
    let (shape, vals) = starplex::io::points::read_npy_array(path)
        .map_err(|e| CliError::Input(e.to_string(), None))?;
    let [rows, cols] = shape[..] else {
        return Err(input_error(
            path,
            format!("expected a 2-D distance matrix, got shape {shape:?}"),
            None,
        ));
    };
    Ok((rows, cols, vals))
}

fn read_text_matrix(path: &Path) -> Result<(usize, usize, Vec<f64>), CliError> {
    let text = std::fs::read_to_string(path).map_err(|e| input_error(path, e, None))?;
    let mut vals = Vec::new();
    let (mut rows, mut cols) = (0usize, None);
    for (ln, line) in text.lines().enumerate() {
        let line = line.split('#').next().unwrap_or("").trim();
        if line.is_empty() {
            continue;
        }
        let fields: Vec<&str> = line
            .split(|c: char| c == ',' || c.is_whitespace())
            .filter(|f| !f.is_empty())
            .collect();
        let parsed: Result<Vec<f64>, _> = fields.iter().map(|f| f.parse::<f64>()).collect();
        let row = match parsed {
            Ok(r) => r,
            // a CSV header line
            Err(_) if rows == 0 && cols.is_none() => {
                cols = Some(fields.len());
                continue;
            }
            Err(err) => {
                return Err(CliError::Input(
                    format!("{}:{}: not a number ({err})", path.display(), ln + 1),
                    None,
                ))
            }
        };
        match cols {
            Some(c) if c != row.len() => {
                return Err(CliError::Input(
                    format!(
                        "{}:{}: {} columns, but the first row has {c} (ragged rows)",
                        path.display(),
                        ln + 1,
                        row.len()
                    ),
                    None,
                ))
            }
            _ => cols = Some(row.len()),
        }
        vals.extend(row);
        rows += 1;
    }
    Ok((rows, cols.unwrap_or(0), vals))
}

#[derive(clap::Args, Debug)]
pub struct FlagArgs {
    /// Edge list: two vertex ids per line (further columns ignored), or CSV with a header;
    /// `#` and `%` start comments.
    pub edges: PathBuf,
    /// Number of vertices (ids must be below it); default: the largest id + 1.
    #[arg(long, value_name = "N")]
    pub n_vertices: Option<usize>,
    #[command(flatten)]
    pub build: BuildArgs,
}

fn budget(b: &BuildArgs) -> Result<u64, CliError> {
    match b.max_memory {
        None => Ok(rips::default_max_bytes()),
        Some(g) if g.is_finite() && g > 0.0 => Ok((g * (1u64 << 30) as f64) as u64),
        Some(g) => Err(CliError::Input(
            format!("--max-memory {g}: expected a positive number of GiB"),
            None,
        )),
    }
}

/// The output format: `.off` means off-simplices (the output is simplicial of any dimension).
fn out_format(b: &BuildArgs) -> Result<Option<Format>, CliError> {
    let f = common::output_format_for(b.to.as_deref(), &b.out)?;
    if f.is_none() && Format::from_path(&b.out) == Some(Format::Off) {
        return Ok(Some(Format::OffSimplices));
    }
    Ok(f)
}

fn input_error(what: &Path, e: impl std::fmt::Display, hint: Option<&str>) -> CliError {
    CliError::Input(format!("{}: {e}", what.display()), hint.map(str::to_string))
}

pub fn run_rips(ctx: &Ctx, a: &RipsArgs) -> Result<(), CliError> {
    let t0 = Instant::now();
    let to = out_format(&a.build)?;
    let max_bytes = budget(&a.build)?;
    for (flag, v) in [("--eps", a.eps), ("--eps-nn", a.eps_nn)] {
        if let Some(x) = v
            && !(x.is_finite() && x > 0.0)
        {
            return Err(CliError::Input(
                format!("{flag} {x}: the scale must be a positive finite number"),
                None,
            ));
        }
    }
    let metric = match a.metric {
        MetricArg::Euclidean => Some(Metric::Euclidean),
        MetricArg::Manhattan => Some(Metric::Manhattan),
        MetricArg::Chebyshev => Some(Metric::Chebyshev),
        MetricArg::Precomputed => None,
    };
    // points, or with --metric precomputed a distance matrix
    let (pc, dm) = match metric {
        Some(_) => (
            Some(common::with_spinner(ctx, "reading points", || {
                io::points::read_points(&a.points)
            })?),
            None,
        ),
        None => (
            None,
            Some(common::with_spinner(
                ctx,
                "reading the distance matrix",
                || read_distance_matrix(&a.points),
            )?),
        ),
    };
    let (n_points, ambient) = match (&pc, &dm) {
        (Some(pc), _) => (pc.len(), Some(pc.dim)),
        (None, Some(d)) => (d.len(), None),
        (None, None) => unreachable!("points or a matrix were read"),
    };
    let read_s = t0.elapsed().as_secs_f64();
    let t_nn = Instant::now();
    let (eps, nn) = match (a.eps, a.eps_nn) {
        (Some(e), _) => (e, None),
        (None, Some(f)) => {
            let m = match (&pc, &dm, metric) {
                (Some(pc), _, Some(m)) => rips::median_nn_distance_with(&pc.coords, pc.dim, m),
                (_, Some(d), _) => d.median_nn_distance(),
                _ => unreachable!("points or a matrix were read"),
            }
            .map_err(|e| input_error(&a.points, e, None))?;
            if m <= 0.0 {
                return Err(input_error(
                    &a.points,
                    "the median nearest-neighbour distance is 0 (more than half the points are \
                     duplicates): --eps-nn gives no scale",
                    Some("give the scale with --eps"),
                ));
            }
            (f * m, Some(m))
        }
        (None, None) => unreachable!("clap requires one of --eps, --eps-nn"),
    };
    let nn_s = nn.map(|_| t_nn.elapsed().as_secs_f64());
    let pb = common::progress_bar(ctx, n_points as u64, "maximal cliques");
    let progress = |n: u64| pb.inc(n);
    let opts = RipsOptions {
        cliques: CliqueOptions {
            max_dim: a.build.max_dim,
            limits: Limits::with_memory(max_bytes),
            progress: Some(&progress),
        },
        max_dim: a.build.max_dim,
    };
    let t1 = Instant::now();
    let built = match (&pc, &dm, metric) {
        (Some(pc), _, Some(m)) => rips::rips_complex_with(&pc.coords, pc.dim, eps, m, &opts),
        (_, Some(d), _) => rips::rips_from_distances(d, eps, &opts),
        _ => unreachable!("points or a matrix were read"),
    };
    pb.finish_and_clear();
    let built = built.map_err(|e| {
        input_error(
            &a.points,
            e,
            Some("use a smaller --eps, a --max-dim, or a larger --max-memory"),
        )
    })?;
    let build_s = t1.elapsed().as_secs_f64();
    finish(
        ctx,
        &a.build,
        to,
        built,
        json!({
            "input": a.points.display().to_string(),
            "n_points": n_points,
            "ambient_dim": ambient,
            "metric": a.metric.name(),
            "eps": eps,
            "median_nn_distance": nn,
            "timings": {"nn_s": nn_s},
        }),
        (read_s, build_s),
    )
}

pub fn run_flag(ctx: &Ctx, a: &FlagArgs) -> Result<(), CliError> {
    let t0 = Instant::now();
    let to = out_format(&a.build)?;
    let max_bytes = budget(&a.build)?;
    let el = common::with_spinner(ctx, "reading edges", || {
        io::points::read_edges(&a.edges, a.n_vertices)
    })?;
    let read_s = t0.elapsed().as_secs_f64();
    let pb = common::progress_bar(ctx, el.n_vertices as u64, "maximal cliques");
    let progress = |n: u64| pb.inc(n);
    let opts = RipsOptions {
        cliques: CliqueOptions {
            max_dim: a.build.max_dim,
            limits: Limits::with_memory(max_bytes),
            progress: Some(&progress),
        },
        max_dim: a.build.max_dim,
    };
    let t1 = Instant::now();
    let built = rips::flag_complex(el.n_vertices, &el.edges, &opts);
    pb.finish_and_clear();
    let built = built.map_err(|e| {
        input_error(
            &a.edges,
            e,
            Some("use a --max-dim, or a larger --max-memory"),
        )
    })?;
    let build_s = t1.elapsed().as_secs_f64();
    finish(
        ctx,
        &a.build,
        to,
        built,
        json!({
            "input": a.edges.display().to_string(),
            "n_points": el.n_vertices,
        }),
        (read_s, build_s),
    )
}

fn finish(
    ctx: &Ctx,
    b: &BuildArgs,
    to: Option<Format>,
    built: Built,
    mut summary: serde_json::Value,
    (read_s, build_s): (f64, f64),
) -> Result<(), CliError> {
    let t = Instant::now();
    common::with_spinner(ctx, "writing", || io::write(&b.out, &built.complex, to))?;
    let write_s = t.elapsed().as_secs_f64();
    let n_max: usize = built.by_dim.iter().map(|&(_, c)| c).sum();
    let isolated = built.n_isolated;
    if b.json {
        summary["n_edges"] = json!(built.n_edges);
        summary["n_maximal_simplices"] = json!(n_max);
        summary["n_isolated_vertices"] = json!(isolated);
        summary["maximal_simplices_by_dim"] = json!(built
            .by_dim
            .iter()
            .map(|&(d, c)| (d.to_string(), json!(c)))
            .collect::<serde_json::Map<_, _>>());
        summary["max_dim"] = json!(b.max_dim);
        summary["output"] = json!(common::shown(&b.out));
        let p = built.phases;
        let mut t = json!({
            "read_s": read_s,
            "build_s": build_s,
            "graph_s": p.graph_s,
            "cliques_s": p.cliques_s,
            "complex_s": p.complex_s,
            "write_s": write_s,
        });
        if let Some(nn_s) = summary["timings"]["nn_s"].as_f64() {
            t["nn_s"] = json!(nn_s);
        }
        summary["timings"] = t;
        println!(
            "{}",
            serde_json::to_string_pretty(&summary).unwrap_or_default()
        );
    } else if !ctx.quiet {
        let dims: Vec<String> = built
            .by_dim
            .iter()
            .map(|&(d, c)| format!("{c} of dim {d}"))
            .collect();
        eprintln!(
            "wrote {}: {} vertices ({} isolated), {} edges in the graph, {} maximal simplices ({}); \
             build {:.3} s",
            common::shown(&b.out),
            built.complex.n_vertices(),
            isolated,
            built.n_edges,
            n_max,
            if dims.is_empty() { "none".to_string() } else { dims.join(", ") },
            build_s
        );
    }
    Ok(())
}
