//! `starplex homology FILE [--field 2|p|q|z] [--per-component] [--generators OUT] [--json]
//! [--threads N]`: Betti numbers (torsion over Z), per component with surface summaries, and
//! representative cycles written as an OBJ file (one group per class).
use std::path::PathBuf;
use std::sync::Arc;
use std::time::Instant;

use serde_json::json;
use starplex::algo::homology::{
    homology_indexed, homology_owned, write_generators_obj, Field, HomologyOptions,
};

use crate::common::{self, CliError, Ctx, InputArgs};

#[derive(clap::Args, Debug)]
pub struct HomologyArgs {
    #[command(flatten)]
    pub input: InputArgs,
    /// Coefficients: 2 (default), a prime p (e.g. 3), q (rationals) or z (integers, with torsion).
    #[arg(long, default_value = "2")]
    pub field: String,
    /// Betti numbers per connected component, with a one-line summary of surface components
    /// (orientability, genus, boundary loops).
    #[arg(long)]
    pub per_component: bool,
    /// Write representative cycles to this OBJ file (one group `hK_i` per class; fields 2 or p).
    #[arg(long, value_name = "OUT")]
    pub generators: Option<PathBuf>,
    /// Print one JSON object.
    #[arg(long)]
    pub json: bool,
    /// Worker threads (default: all cores); the answer is the same for any number.
    #[arg(long)]
    pub threads: Option<usize>,
    /// Largest number of lower-star cells to enumerate (default 4e9); above it the command
    /// refuses with an estimate.
    #[arg(long)]
    pub max_faces: Option<u128>,
}

pub fn run(ctx: &Ctx, a: &HomologyArgs) -> Result<(), CliError> {
    let field = Field::parse(&a.field).map_err(|e| {
        CliError::Input(
            format!("--field: {e}"),
            Some("use --field 2, --field 3 (any prime), --field q or --field z".into()),
        )
    })?;
    if a.generators.is_some() && matches!(field, Field::Q | Field::Z) {
        return Err(CliError::Input(
            format!("--generators is computed over Z/2 or Z/p, not over {field}"),
            Some("drop --field, or pass --field 2 or a prime".into()),
        ));
    }
    let threads = match a.threads {
        Some(0) => return Err(CliError::Input("--threads must be at least 1".into(), None)),
        Some(t) => t,
        None => rayon::current_num_threads(),
    };
    // open the generators file first, so a bad path fails before the work
    let gen_file = match &a.generators {
        Some(p) => Some(std::fs::File::create(p).map_err(|e| {
            CliError::Input(
                format!("{}: cannot write the generators: {e}", p.display()),
                None,
            )
        })?),
        None => None,
    };
    let t0 = Instant::now();
    let r = common::load(ctx, &a.input)?;
    let read_s = t0.elapsed().as_secs_f64();
    let k = r.complex;
    let pb = if k.n_cells() > 200_000 {
        common::progress_bar(ctx, k.n_vertices() as u64, "homology")
    } else {
        indicatif::ProgressBar::hidden()
    };
    let pb2 = pb.clone();
    let mut opts = HomologyOptions {
        field,
        per_component: a.per_component,
        generators: a.generators.is_some(),
        progress: Some(Arc::new(move |n| pb2.inc(n))),
        ..Default::default()
    };
    if let Some(m) = a.max_faces {
        opts.limits.homology_cells = m;
    }
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| CliError::Other(e.to_string()))?;
    let t1 = Instant::now();
    // without generators the complex is not needed afterwards: it is consumed (its cells
    // renumbered in place, its coordinates freed), which lowers the peak memory
    let (h, k) = if a.generators.is_some() {
        (pool.install(|| homology_indexed(&k, &opts)), Some(k))
    } else {
        (pool.install(|| homology_owned(k, &opts)), None)
    };
    pb.finish_and_clear();
    let h = h.map_err(|e| {
        CliError::Input(
            e.to_string(),
            Some("raise --max-faces, or use a prime field when integers overflow".into()),
        )
    })?;
    let homology_s = t1.elapsed().as_secs_f64();
    if let (Some(f), Some(p), Some(k)) = (gen_file, &a.generators, &k) {
        let w = std::io::BufWriter::new(f);
        write_generators_obj(k, &h.generators, w).map_err(|e| {
            CliError::Input(
                format!("{}: cannot write the generators: {e}", p.display()),
                None,
            )
        })?;
    }
    if a.json {
        let mut v = to_json(&h);
        v["timings"] = json!({"read_s": read_s, "homology_s": homology_s});
        v["threads"] = json!(threads);
        if let Some(p) = &a.generators {
            v["generators"] = json!({"file": p.display().to_string(), "count": h.generators.len()});
        }
        println!(
            "{}",
            serde_json::to_string_pretty(&v).map_err(|e| CliError::Other(e.to_string()))?
        );
    } else {
        println!("{}", a.input.file.display());
        println!("  field               {}", h.field);
        println!("  Betti numbers       {:?}", h.betti);
        if h.field == Field::Z {
            println!("  groups              {}", groups(&h.betti, &h.torsion));
        }
        println!("  Euler char.         {}", h.euler_characteristic());
        println!("  critical cells      {:?}", h.critical);
        if let Some(comps) = &h.components {
            println!("  components          {}", comps.len());
            for (i, c) in comps.iter().enumerate() {
                let mut line = format!("    #{i} (vertex {}): Betti {:?}", c.first_vertex, c.betti);
                if h.field == Field::Z && c.torsion.iter().any(|t| !t.is_empty()) {
                    line += &format!(", {}", groups(&c.betti, &c.torsion));
                }
                if let Some(s) = &c.surface {
                    line += &format!("; {s}");
                }
                println!("{line}");
            }
        }
        if let Some(p) = &a.generators {
            println!(
                "  generators          {} written to {}",
                h.generators.len(),
                p.display()
            );
        }
        println!("  time                read {read_s:.3} s, homology {homology_s:.3} s ({threads} thread(s))");
    }
    Ok(())
}

/// `H0 = Z, H1 = Z^2 + Z/2, ...`
fn groups(betti: &[u64], torsion: &[Vec<u128>]) -> String {
    betti
        .iter()
        .enumerate()
        .map(|(k, &b)| {
            let mut parts = Vec::new();
            match b {
                0 => {}
                1 => parts.push("Z".to_string()),
                _ => parts.push(format!("Z^{b}")),
            }
            for t in torsion.get(k).into_iter().flatten() {
                parts.push(format!("Z/{t}"));
            }
            if parts.is_empty() {
                parts.push("0".into());
            }
            format!("H{k} = {}", parts.join(" + "))
        })
        .collect::<Vec<_>>()
        .join(", ")
}

pub use starplex_cli::report::homology_json as to_json;
