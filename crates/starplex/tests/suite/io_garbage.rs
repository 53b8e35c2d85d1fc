//! An empty file and random bytes are an error in every reader (never an empty complex, never
//! a panic).
use starplex::io::{self, Format, ReadOptions};

fn random(n: usize, seed: u64) -> Vec<u8> {
    let mut rng = starplex::testkit::XorShift::new(seed);
    (0..n).map(|_| rng.next_u64() as u8).collect()
}

#[test]
fn empty_and_random_inputs_are_errors_in_every_reader() {
    let dir = std::env::temp_dir().join(format!("starplex-io-garbage-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let inputs: Vec<(&str, Vec<u8>)> = vec![
        ("empty", Vec::new()),
        ("random", random(4096, 7)),
        (
            "random text",
            random(4096, 9)
                .iter()
                .map(|b| b"abc xyz 019\n#."[*b as usize % 14])
                .collect(),
        ),
    ];
    let mut accepted = Vec::new();
    for f in Format::ALL {
        if matches!(f, Format::Gmsh22 | Format::StlBinary) {
            continue;
        }
        for (name, bytes) in &inputs {
            let p = dir.join(format!("in.{}", f.extension()));
            std::fs::write(&p, bytes).unwrap();
            let opts = ReadOptions {
                format: Some(f),
                ..Default::default()
            };
            if let Ok(r) = io::read(&p, &opts) {
                accepted.push(format!(
                    "{f} accepted {name} ({} vertices, {} cells)",
                    r.complex.n_vertices(),
                    r.complex.n_cells()
                ));
            }
        }
    }
    std::fs::remove_dir_all(&dir).ok();
    assert!(accepted.is_empty(), "{accepted:#?}");
}
