//! Critical cells and time of the homology's lower-star matching under each vertex order.
//!
//! `cargo run --release --example homology_orders -- FILE...`
use starplex::algo::homology::{homology_indexed, HomologyOptions, VertexOrder};
use starplex::io::{self, ReadOptions};

fn main() {
    for f in std::env::args().skip(1) {
        let r = io::read(std::path::Path::new(&f), &ReadOptions::default())
            .unwrap_or_else(|e| panic!("{e}"));
        for order in [
            VertexOrder::Auto,
            VertexOrder::Input,
            VertexOrder::FirstAppearance,
            VertexOrder::BreadthFirst,
        ] {
            let t = std::time::Instant::now();
            let h = homology_indexed(
                &r.complex,
                &HomologyOptions {
                    order,
                    ..Default::default()
                },
            )
            .unwrap_or_else(|e| panic!("{e}"));
            println!(
                "{f}\t{order:?}\tbetti {:?}\tcritical {:?}\t{:.3} s",
                h.betti,
                h.critical,
                t.elapsed().as_secs_f64()
            );
        }
    }
}
