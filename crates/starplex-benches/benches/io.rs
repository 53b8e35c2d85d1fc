//! Read throughput (bytes per second) of the `.spx` text reader, the OFF text reader and the `.spb`
//! memory-mapped binary loader, on the same complex.
//!
//! Input: with `STARPLEX_DATA` set, the first of `medium/tri_armadillo_x16`, `small/tri_polygon_mesh`
//! that exists (its `.spx`, and `.off` beside it); otherwise a generated triangulated grid of about
//! 50 MB of `.spx` text in the temporary directory; `STARPLEX_BENCH_SPX=path.spx` picks a file.
//! The `.spb` is written from the `.spx` complex (once, cached in the temporary directory).
//!
//! ```text
//! cargo bench -p starplex-benches --bench io -- --measurement-time 5
//! ```
use std::hint::black_box;
use std::path::{Path, PathBuf};
use std::time::Duration;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use starplex::cell::CellKind;
use starplex::complex::{BuildOptions, ComplexBuilder, IndexedComplex};
use starplex::io::{self, Format, ReadOptions};

/// A `side` x `side` grid of vertices, two triangles per square, with non-round coordinates.
fn grid(side: u32) -> IndexedComplex {
    let mut b = ComplexBuilder::new(3).unwrap();
    for j in 0..side {
        for i in 0..side {
            let (x, y) = (i as f64 / 7.0, j as f64 / 3.0);
            b.push_vertex(&[x, y, (x * 1.3).sin() * (y * 0.7).cos()])
                .unwrap();
        }
    }
    for j in 0..side - 1 {
        for i in 0..side - 1 {
            let v = j * side + i;
            b.push_cell(CellKind::Simplex(2), &[v, v + 1, v + side + 1])
                .unwrap();
            b.push_cell(CellKind::Simplex(2), &[v, v + side + 1, v + side])
                .unwrap();
        }
    }
    b.build(&BuildOptions {
        trust_maximality: true,
        ..Default::default()
    })
    .unwrap()
    .0
}

/// OFF text of a triangle complex (written here so the bench does not depend on the OFF writer).
fn write_off(path: &Path, k: &IndexedComplex) {
    use std::io::Write;
    let mut w = std::io::BufWriter::new(std::fs::File::create(path).unwrap());
    writeln!(w, "OFF\n{} {} 0", k.n_vertices(), k.n_cells()).unwrap();
    for p in k.coords().chunks_exact(3) {
        writeln!(w, "{} {} {}", p[0], p[1], p[2]).unwrap();
    }
    for c in k.cells() {
        let v = c.vertices;
        writeln!(
            w,
            "{} {}",
            v.len(),
            v.iter()
                .map(|x| x.to_string())
                .collect::<Vec<_>>()
                .join(" ")
        )
        .unwrap();
    }
}

/// (.spx, .off, .spb) paths of the input, creating what is missing.
fn inputs() -> (PathBuf, Option<PathBuf>, PathBuf) {
    let dir = std::env::temp_dir().join("starplex-bench-io");
    std::fs::create_dir_all(&dir).unwrap();
    if let Ok(spx) = std::env::var("STARPLEX_BENCH_SPX") {
        let spx = PathBuf::from(spx);
        let off = spx.with_extension("off");
        let spb = dir.join(format!(
            "{}.spb",
            spx.file_stem().unwrap().to_string_lossy()
        ));
        if !spb.exists() {
            let k = io::read(&spx, &ReadOptions::default()).unwrap().complex;
            io::write(&spb, &k, Some(Format::Binary)).unwrap();
        }
        return (spx, off.exists().then_some(off), spb);
    }
    if let Ok(data) = std::env::var("STARPLEX_DATA") {
        for rel in [
            "medium/tri_armadillo_x16/tri_armadillo_x16",
            "small/tri_polygon_mesh/tri_polygon_mesh",
        ] {
            let spx = Path::new(&data).join(format!("{rel}.spx"));
            if spx.exists() {
                let off = spx.with_extension("off");
                let spb = dir.join(format!(
                    "{}.spb",
                    spx.file_stem().unwrap().to_string_lossy()
                ));
                if !spb.exists() {
                    let k = io::read(&spx, &ReadOptions::default()).unwrap().complex;
                    io::write(&spb, &k, Some(Format::Binary)).unwrap();
                }
                return (spx, off.exists().then_some(off), spb);
            }
        }
        eprintln!("STARPLEX_DATA set but no benchmark dataset found; generating a grid");
    }
    let spx = dir.join("grid.spx");
    let off = dir.join("grid.off");
    let spb = dir.join("grid.spb");
    if !(spx.exists() && off.exists() && spb.exists()) {
        let k = grid(780); // ~608k vertices, ~1.2M triangles, ~50 MB of .spx
        io::write(&spx, &k, None).unwrap();
        write_off(&off, &k);
        io::write(&spb, &k, None).unwrap();
    }
    (spx, Some(off), spb)
}

fn bench_io(c: &mut Criterion) {
    let (spx, off, spb) = inputs();
    let len = |p: &Path| std::fs::metadata(p).unwrap().len();
    let opts = ReadOptions::default();
    let mut g = c.benchmark_group("read");
    g.sample_size(10);
    g.warm_up_time(Duration::from_secs(1));
    eprintln!(
        "inputs: {} ({} B), {} ({} B)",
        spx.display(),
        len(&spx),
        spb.display(),
        len(&spb)
    );
    g.throughput(Throughput::Bytes(len(&spx)));
    g.bench_function("spx_text", |b| {
        b.iter(|| black_box(io::read(&spx, &opts).unwrap().complex.n_cells()))
    });
    match &off {
        Some(off) => match io::read(off, &opts) {
            Ok(_) => {
                g.throughput(Throughput::Bytes(len(off)));
                g.bench_function("off_text", |b| {
                    b.iter(|| black_box(io::read(off, &opts).unwrap().complex.n_cells()))
                });
            }
            Err(e) => eprintln!(
                "off_text skipped: the OFF reader fails on {}: {e}",
                off.display()
            ),
        },
        None => eprintln!("off_text skipped: no .off beside {}", spx.display()),
    }
    g.throughput(Throughput::Bytes(len(&spb)));
    g.bench_function("spb_mmap", |b| {
        b.iter(|| black_box(io::read(&spb, &opts).unwrap().complex.n_cells()))
    });
    g.finish();
}

criterion_group!(benches, bench_io);
criterion_main!(benches);
