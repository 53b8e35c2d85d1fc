//! In-process timings of the Rips build's phases (median NN distance, ε-graph, degeneracy
//! order, clique enumeration, complex assembly), medians of `REPS` runs on the current rayon
//! pool (`RAYON_NUM_THREADS=1` for one thread).
//!
//! `cargo run --release --example rips_phases -- POINTS EPS_NN|=EPS [MAX_DIM|-] [REPS]`; with
//! `ONLY=cliques` (or `graph`) it runs that phase REPS times and prints nothing, for
//! `perf record`.
use starplex::algo::cliques::{degeneracy_order, maximal_cliques, CliqueOptions};
use starplex::algo::rips::{self, RipsOptions};
use starplex::io::points::read_points;

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() {
    let a: Vec<String> = std::env::args().collect();
    let pc = read_points(std::path::Path::new(&a[1])).unwrap_or_else(|e| panic!("{e}"));
    // EPS_NN: a multiple of the median nearest-neighbour distance, or `=E` for ε itself
    let (f, absolute) = match a[2].strip_prefix('=') {
        Some(e) => (e.parse::<f64>().expect("=EPS"), true),
        None => (a[2].parse::<f64>().expect("EPS_NN"), false),
    };
    let max_dim: Option<usize> = a.get(3).and_then(|s| s.parse().ok());
    let reps: usize = a.get(4).map_or(5, |s| s.parse().expect("REPS"));
    let nn = rips::median_nn_distance(&pc.coords, pc.dim).unwrap();
    let eps = if absolute { f } else { f * nn };
    let g = rips::neighbourhood_graph(&pc.coords, pc.dim, eps).unwrap();
    let co = CliqueOptions {
        max_dim,
        ..Default::default()
    };
    if let Ok(only) = std::env::var("ONLY") {
        for _ in 0..reps {
            match only.as_str() {
                "graph" => {
                    std::hint::black_box(rips::neighbourhood_graph(&pc.coords, pc.dim, eps).ok());
                }
                "cliques" => {
                    std::hint::black_box(maximal_cliques(&g, &co).ok());
                }
                _ => panic!("ONLY"),
            }
        }
        return;
    }
    println!(
        "{} points, dim {}, eps {eps}, {} edges",
        pc.len(),
        pc.dim,
        g.n_edges()
    );
    let time = |name: &str, f: &mut dyn FnMut()| {
        let mut v = Vec::new();
        for _ in 0..reps {
            let t0 = std::time::Instant::now();
            f();
            v.push(t0.elapsed().as_secs_f64());
        }
        println!("{name:<24} {:>9.3} ms", 1e3 * median(v));
    };
    time("median nn", &mut || {
        std::hint::black_box(rips::median_nn_distance(&pc.coords, pc.dim).ok());
    });
    time("graph", &mut || {
        std::hint::black_box(rips::neighbourhood_graph(&pc.coords, pc.dim, eps).ok());
    });
    time("degeneracy order", &mut || {
        std::hint::black_box(degeneracy_order(&g));
    });
    time("cliques", &mut || {
        std::hint::black_box(maximal_cliques(&g, &co).ok());
    });
    let opts = RipsOptions {
        max_dim,
        ..Default::default()
    };
    time("complex (from graph)", &mut || {
        std::hint::black_box(rips::complex_of(pc.coords.clone(), pc.dim, &g, &opts).ok());
    });
    time("whole rips_complex", &mut || {
        std::hint::black_box(rips::rips_complex(&pc.coords, pc.dim, eps, &opts).ok());
    });
}
