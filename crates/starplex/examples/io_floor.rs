//! The floor under any reader of a binary mesh file on this machine: what reading the file's
//! bytes costs (in 8 MiB reads into one reused buffer, summing every 8-byte word so nothing is
//! skipped) and what writing a result of `OUT_BYTES` into fresh memory costs on every core
//! (the page faults of the arrays a reader returns). Best of 5 each.
//!
//! ```sh
//! cargo run --release --example io_floor -- /tmp/g100.msh 121000000
//! ```
use rayon::prelude::*;
use std::io::Read;
use std::time::Instant;

fn best(mut f: impl FnMut() -> u64) -> (f64, u64) {
    let mut t_best = f64::INFINITY;
    let mut x = 0;
    for _ in 0..5 {
        let t = Instant::now();
        x ^= f();
        t_best = t_best.min(t.elapsed().as_secs_f64());
    }
    (t_best, x)
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let (Some(path), Some(out)) = (
        args.first(),
        args.get(1).and_then(|s| s.parse::<usize>().ok()),
    ) else {
        eprintln!("usage: io_floor FILE OUT_BYTES");
        std::process::exit(2);
    };
    let len = std::fs::metadata(path).map(|m| m.len()).unwrap_or(0) as f64;
    let (t, x) = best(|| {
        let mut f = std::fs::File::open(path).expect("open");
        let mut buf = vec![0u8; 8 << 20];
        let mut sum = 0u64;
        loop {
            let n = f.read(&mut buf).expect("read");
            if n == 0 {
                break;
            }
            sum = buf[..n].chunks_exact(8).fold(sum, |s, c| {
                s.wrapping_add(u64::from_ne_bytes(c.try_into().expect("8 bytes")))
            });
        }
        sum
    });
    println!(
        "read {path}: {:.1} ms ({:.2} GB/s) [{}]",
        t * 1e3,
        len / t / 1e9,
        x & 1
    );
    let (t, x) = best(|| {
        let mut v: Vec<u64> = Vec::with_capacity(out / 8);
        v.par_extend((0..out / 8).into_par_iter().map(|i| i as u64));
        v[v.len() / 3]
    });
    println!(
        "fresh {} MB written on {} threads: {:.1} ms ({:.2} GB/s) [{}]",
        out / 1_000_000,
        rayon::current_num_threads(),
        t * 1e3,
        out as f64 / t / 1e9,
        x & 1
    );
}
