//! `starplex bench-hasse FILE [--json]` (to be nested as `bench hasse`): builds the CASC Hasse
//! complex from FILE and measures insertion, bytes per simplex, star and link of every vertex,
//! and link-checked edge collapses.
use std::time::Instant;

use serde_json::json;
use starplex::hasse::{Hasse, Merge};
use starplex::ids::VertexId;

use crate::common::{self, CliError, Ctx, InputArgs};

#[derive(clap::Args, Debug)]
pub struct BenchHasseArgs {
    #[command(flatten)]
    pub input: InputArgs,
    /// Print one JSON object.
    #[arg(long)]
    pub json: bool,
    /// Number of link-checked edge collapses to time.
    #[arg(long, default_value_t = 1000)]
    pub collapses: usize,
    /// Seed of the random edge choice.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Builds to time (the median is reported; the first build alone with the default 1).
    #[arg(long, default_value_t = 1)]
    pub reps: usize,
}

/// Midpoint of the merged vertices; nothing on other levels.
struct Mid;
impl Merge<0, [f64; 3]> for Mid {
    fn merge(&mut self, _: &[VertexId], old: &[(&[VertexId], &[f64; 3])]) -> [f64; 3] {
        let mut p = [0.0; 3];
        let n = old.len() as f64;
        for (_, x) in old {
            for c in 0..3 {
                p[c] += x[c] / n;
            }
        }
        p
    }
}
impl<const K: usize> Merge<K, ()> for Mid {
    fn merge(&mut self, _: &[VertexId], _: &[(&[VertexId], &())]) {}
}

fn cpu_since(c0: Option<f64>) -> Option<f64> {
    Some(starplex::measure::thread_cpu_seconds()? - c0?)
}

fn hasse_err(e: starplex::hasse::HasseError) -> CliError {
    CliError::Input(e.to_string(), None)
}

pub fn run(ctx: &Ctx, a: &BenchHasseArgs) -> Result<(), CliError> {
    let r = common::load(ctx, &a.input)?;
    let k = &r.complex;

    let mut walls = Vec::new();
    let mut cpus = Vec::new();
    let mut built = None;
    for _ in 0..a.reps.max(1) {
        drop(built.take());
        let c = starplex::measure::thread_cpu_seconds();
        let t = Instant::now();
        let h: Hasse = Hasse::from_indexed(k).map_err(hasse_err)?;
        walls.push(t.elapsed().as_secs_f64());
        cpus.extend(cpu_since(c));
        built = Some(h);
    }
    let h = built.expect("at least one build");
    let med = |mut v: Vec<f64>| {
        v.sort_by(|a, b| a.total_cmp(b));
        v.get(v.len() / 2).copied()
    };
    let insert_s = med(walls).unwrap_or(f64::NAN);
    let insert_cpu_s = med(cpus);
    let n_simplices = h.len();
    let bytes = h.topology_bytes();
    let bytes_per_simplex = bytes as f64 / n_simplices.max(1) as f64;

    let (t, c) = (Instant::now(), starplex::measure::thread_cpu_seconds());
    let mut star_total = 0usize;
    for v in h.level(0) {
        star_total += h.star(v).len();
    }
    let star_all_s = t.elapsed().as_secs_f64();
    let star_all_cpu_s = cpu_since(c);

    let (t, c) = (Instant::now(), starplex::measure::thread_cpu_seconds());
    let mut link_total = 0usize;
    for v in h.level(0) {
        link_total += h.link(v).len();
    }
    let link_all_s = t.elapsed().as_secs_f64();
    let link_all_cpu_s = cpu_since(c);
    let f_vector = h.f_vector();
    drop(h);

    // collapses on a complex carrying positions
    let mut h: Hasse<([f64; 3],)> = Hasse::from_indexed(k).map_err(hasse_err)?;
    h.set_positions_from(k);
    let mut x = a.seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1;
    let mut times = Vec::with_capacity(a.collapses);
    let mut refused = 0usize;
    let mut attempts = 0usize;
    let c = starplex::measure::thread_cpu_seconds();
    while times.len() < a.collapses && h.n_simplices(1) > 0 && attempts < 20 * a.collapses + 100 {
        attempts += 1;
        x = x
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        let Some(e) = h.pick(1, x >> 33) else { break };
        let t = Instant::now();
        if h.can_collapse(e).is_err() {
            refused += 1;
            continue;
        }
        h.collapse(e, &mut Mid)
            .map_err(|e| CliError::Other(e.to_string()))?;
        times.push(t.elapsed().as_secs_f64() * 1e6);
    }
    let collapse_cpu_s = cpu_since(c);
    times.sort_by(|a, b| a.total_cmp(b));
    let median = times.get(times.len() / 2).copied().unwrap_or(f64::NAN);
    let valid = h.is_valid();

    if a.json {
        let v = json!({
            "file": a.input.file.display().to_string(),
            "n_simplices": n_simplices,
            "f_vector": f_vector,
            "insert_s": insert_s,
            "insert_cpu_s": insert_cpu_s,
            "topology_bytes": bytes,
            "bytes_per_simplex": bytes_per_simplex,
            "star_all_s": star_all_s,
            "star_all_cpu_s": star_all_cpu_s,
            "star_total": star_total,
            "link_all_s": link_all_s,
            "link_all_cpu_s": link_all_cpu_s,
            "link_total": link_total,
            "collapses": times.len(),
            "collapses_refused": refused,
            "collapse_us_median": median,
            "collapse_attempt_us_mean_cpu": collapse_cpu_s.map(|c| c * 1e6 / attempts.max(1) as f64),
            "valid_after_collapses": valid,
        });
        println!(
            "{}",
            serde_json::to_string_pretty(&v).map_err(|e| CliError::Other(e.to_string()))?
        );
    } else {
        println!("{}", a.input.file.display());
        println!("  simplices          {n_simplices}");
        println!("  insert all         {:.4} s", insert_s);
        println!("  bytes per simplex  {:.1}", bytes_per_simplex);
        println!(
            "  star of every vertex {:.4} s ({star_total} simplices)",
            star_all_s
        );
        println!(
            "  link of every vertex {:.4} s ({link_total} simplices)",
            link_all_s
        );
        println!(
            "  edge collapse      {:.2} us median over {} ({} refused by the link condition), valid: {}",
            median,
            times.len(),
            refused,
            valid
        );
    }
    Ok(())
}
