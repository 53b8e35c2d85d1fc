//! Load time of a mesh file, best of 3 (warm page cache): with the full checks of the build
//! (duplicate and face cells) and, for readers that honour it, with `trust_maximality` (parse +
//! index checks only).
//!
//! `cargo run --release --example read_speed -- FILE...`
use starplex::complex::BuildOptions;
use starplex::io::{self, ReadOptions};

fn main() {
    for f in std::env::args().skip(1) {
        let p = std::path::Path::new(&f);
        let mb = std::fs::metadata(p).map(|m| m.len()).unwrap_or(0) as f64 / 1e6;
        for (what, build) in [
            ("checked", BuildOptions::default()),
            (
                "trusted",
                BuildOptions {
                    trust_maximality: true,
                    ..Default::default()
                },
            ),
        ] {
            let opts = ReadOptions {
                build,
                ..Default::default()
            };
            let mut best = f64::INFINITY;
            for _ in 0..3 {
                let t = std::time::Instant::now();
                let r = io::read(p, &opts).unwrap_or_else(|e| panic!("{e}"));
                best = best.min(t.elapsed().as_secs_f64());
                assert!(r.complex.n_cells() > 0);
            }
            println!(
                "{f}\t{what}\t{mb:.0} MB\t{best:.3} s\t{:.0} MB/s",
                mb / best
            );
        }
    }
}
