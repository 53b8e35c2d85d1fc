//! In-process timings of the Stellar tree's leaf-parallel phases, split finer than
//! `starplex stellar --bench` (p-faces per dimension; IA* as facet grouping and the whole),
//! medians of `REPS` runs on the current rayon pool (`RAYON_NUM_THREADS=1` for one thread).
//!
//! `cargo run --release --example stellar_phases -- FILE KV [REPS]`; with `ONLY=iastar`
//! (or `pfaces1`, `pfaces2`, `vt`, `vtall`, `validate`, `build`) it runs that phase REPS times and prints
//! nothing, for `perf record`.
use starplex::io::{self, ReadOptions};
use starplex::stellar::{StellarOptions, StellarTree};
use starplex::topo::Storage;

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() {
    let a: Vec<String> = std::env::args().collect();
    let path = std::path::Path::new(&a[1]);
    let kv: u32 = a[2].parse().expect("KV");
    let reps: usize = a.get(3).map_or(5, |s| s.parse().expect("REPS"));
    let r = io::read(path, &ReadOptions::default()).unwrap_or_else(|e| panic!("{e}"));
    let opts = StellarOptions {
        kv: Some(kv),
        ..Default::default()
    };
    let t = StellarTree::build(&r.complex, &opts).unwrap_or_else(|e| panic!("{e}"));
    let time = |name: &str, f: &mut dyn FnMut()| {
        let mut v = Vec::new();
        for _ in 0..reps {
            let t0 = std::time::Instant::now();
            f();
            v.push(t0.elapsed().as_secs_f64());
        }
        println!("{name:<24} {:>9.2} ms", 1e3 * median(v));
    };
    if let Ok(only) = std::env::var("ONLY") {
        for _ in 0..reps {
            match only.as_str() {
                "iastar" => {
                    std::hint::black_box(t.iastar().refs());
                }
                "pfaces1" => {
                    std::hint::black_box(t.count_p_faces(1).ok());
                }
                "pfaces2" => {
                    std::hint::black_box(t.count_p_faces(2).ok());
                }
                "vt" => {
                    std::hint::black_box(t.vt_all());
                }
                "vtall" => {
                    t.par_for_each_vt(|_, c| {
                        std::hint::black_box(c);
                    });
                }
                "validate" => {
                    std::hint::black_box(t.validate());
                }
                "build" => {
                    std::hint::black_box(StellarTree::build(&r.complex, &opts).expect("build"));
                }
                _ => panic!("ONLY"),
            }
        }
        return;
    }
    time("build", &mut || {
        std::hint::black_box(StellarTree::build(&r.complex, &opts).expect("build"));
    });
    time("vt_local", &mut || {
        std::hint::black_box(t.par_map_leaves(|l| l.e.n_vt_refs()));
    });
    time("vt_all (par_for_each)", &mut || {
        let s = std::sync::atomic::AtomicU64::new(0);
        t.par_for_each_vt(|_, c| {
            s.fetch_add(c.len() as u64, std::sync::atomic::Ordering::Relaxed);
        });
        std::hint::black_box(s);
    });
    time("vt_all (black_box)", &mut || {
        t.par_for_each_vt(|_, c| {
            std::hint::black_box(c);
        });
    });
    let d = t.dim().unwrap_or(0);
    let counts: Vec<u64> = (1..d).map(|p| t.count_p_faces(p).unwrap_or(0)).collect();
    println!("p-faces (p = 1..{d}): {counts:?}");
    for p in 1..d {
        time(&format!("count_p_faces({p})"), &mut || {
            std::hint::black_box(t.count_p_faces(p).ok());
        });
    }
    time("iastar", &mut || {
        std::hint::black_box(t.iastar().refs());
    });
    time("validate", &mut || {
        std::hint::black_box(t.validate());
    });
}
