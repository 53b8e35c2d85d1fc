//! The main job on the bundled sample: what `cargo run --release` (or `starplex demo [FILE]`)
//! prints: the summary, the Stellar tree and the validation.
use std::path::{Path, PathBuf};

use crate::common::{load, CliError, Ctx, InputArgs};

/// The bundled sample: `data/elephant.off` of the repository (CGAL's elephant surface).
pub fn bundled_sample() -> PathBuf {
    let p = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/elephant.off");
    p.canonicalize().unwrap_or(p)
}

/// The main job: load the sample, print its summary.
pub fn run(ctx: &Ctx, file: Option<PathBuf>) -> Result<(), CliError> {
    let file = file.unwrap_or_else(bundled_sample);
    println!(
        "starplex {} — main job on {}",
        env!("CARGO_PKG_VERSION"),
        file.display()
    );
    println!("(run `starplex --help` for every command)\n");
    let input = InputArgs {
        file,
        format: None,
        simplices: false,
        drop_faces: false,
        drop_duplicates: false,
        drop_degenerate: false,
        lenient: false,
    };
    let args = crate::cmd_info::InfoArgs {
        input: input.clone(),
        json: false,
        max_faces: None,
        betti: false,
    };
    crate::cmd_info::run(ctx, &args)?;
    demo_stellar(ctx, &input)
}

/// The Stellar tree summary and the validation of the sample (part of the main job).
fn demo_stellar(ctx: &Ctx, input: &InputArgs) -> Result<(), CliError> {
    let k = load(ctx, input)?.complex;
    let t0 = std::time::Instant::now();
    let t = crate::cmd_stellar::build_tree(ctx, &k, None, "auto", "spatial")?;
    let build_s = t0.elapsed().as_secs_f64();
    println!("\nStellar tree");
    crate::cmd_stellar::print_stats(&t.stats());
    println!("  build               {build_s:.3} s");
    let t1 = std::time::Instant::now();
    let r = t.validate();
    println!("\nValidation");
    crate::cmd_validate::print_human(&r, 10);
    println!("  time                {:.3} s", t1.elapsed().as_secs_f64());
    Ok(())
}
