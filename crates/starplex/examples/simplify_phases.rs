//! In-process timing of homology-mode simplification (`algo::simplify::simplify`), medians of
//! `REPS` runs on the current rayon pool (`RAYON_NUM_THREADS=1` for one thread), for profiling
//! without the command line's reading, reporting and writing.
//!
//! `cargo run --release --example simplify_phases -- FILE [REPS]`; `MODE=qem` for quadric
//! decimation, `RATIO=0.1` for a target (default: to the end); `QUIET=1` prints nothing, for
//! `perf record`; `VERIFY=1` checks that no edge of the result passes the link condition.
use starplex::algo::simplify::{simplify, Mode, SimplifyOptions, Target, TopSimplices};
use starplex::io::{self, ReadOptions};

fn main() {
    let a: Vec<String> = std::env::args().collect();
    let path = std::path::Path::new(&a[1]);
    let reps: usize = a.get(2).map_or(5, |s| s.parse().expect("REPS"));
    let r = io::read(path, &ReadOptions::default()).unwrap_or_else(|e| panic!("{e}"));
    let mode = match std::env::var("MODE").as_deref() {
        Ok("qem") => Mode::Qem,
        _ => Mode::Homology,
    };
    let ratio = std::env::var("RATIO")
        .ok()
        .map(|s| s.parse().expect("RATIO"));
    let opts = SimplifyOptions {
        mode: Some(mode),
        target: Target {
            ratio,
            ..Default::default()
        },
        ..Default::default()
    };
    let quiet = std::env::var("QUIET").is_ok();
    let mut times = Vec::new();
    let mut n = 0;
    let mut rounds = 0;
    for _ in 0..reps {
        let t0 = std::time::Instant::now();
        let (k, rep) = simplify(&r.complex, &opts).unwrap_or_else(|e| panic!("{e}"));
        times.push(t0.elapsed().as_secs_f64());
        n = rep.n_contractions;
        rounds = rep.rounds;
        if std::env::var("VERIFY").is_ok() {
            let w = TopSimplices::from_complex(&k).unwrap_or_else(|e| panic!("{e}"));
            let mut edges = 0;
            for a in 0..w.n_vertices() as u32 {
                for b in w.neighbours(a).into_iter().filter(|&b| b > a) {
                    edges += 1;
                    assert!(w.can_contract(a, b).is_err(), "{a}-{b} still contracts");
                }
            }
            println!("verified: none of the {edges} edges of the result contracts");
        }
        std::hint::black_box(k);
    }
    times.sort_by(f64::total_cmp);
    if !quiet {
        let m = times[times.len() / 2];
        println!(
            "{} contractions in {} rounds, median {:.1} ms, {:.3} us per contraction (min {:.1} ms)",
            n,
            rounds,
            1e3 * m,
            1e6 * m / n.max(1) as f64,
            1e3 * times[0]
        );
    }
}
