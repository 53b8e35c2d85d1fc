//! `starplex-mpi`: starplex distributed over MPI ranks.
//!
//! ```text
//! mpirun -np P starplex-mpi info FILE.spb [--json] [--max-faces N] [--stats]
//! mpirun -np P starplex-mpi validate FILE.spb [--json] [--max-list N] [--stats]
//!     [--check | --fail-on DEFECTS]
//! mpirun -np P starplex-mpi stellar FILE.spb [--json] [--kv N] [--vt-vv-out PREFIX] [--stats]
//! mpirun -np P starplex-mpi homology FILE.spb [--json] [--stats] [--field 2|p|q|z]
//!     [--method morse|contract|algebraic] [--tmp-dir DIR]
//! mpirun -np P starplex-mpi query FILE.spb --relation R --all --out OUT.jsonl|csv|npz
//!     [--structure S] [--per-rank]
//! mpirun -np P starplex-mpi simplify FILE.spb -o OUT.spb [--mode homology|qem] [--ratio R]
//!     [--faces N] [--vertices N] [--max-error E] [--keep-manifold] [--lock-boundary] [--keep-vertices FILE]
//!     [--keep-labels NAME | --ignore-labels] [--keep-vertex-attribute NAME] [--no-report]
//!     [--rounds N] [--gather-below N] [--json]
//! ```
//!
//! Rank 0 prints what `starplex info` / `starplex validate` print on the same file (the
//! timings aside); `--stats` adds one line per rank on stderr (vertices and cells owned and held,
//! ghost share, bytes sent, peak RSS). Every error, on any rank, ends every rank with status 2
//! and rank 0 printing it; `validate --check` / `--fail-on` end every rank with status 1 when
//! the complex has one of the defects, as `starplex validate` does. See the crate's DESIGN section "Distributed (MPI)".
use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::Arc;
use std::time::Instant;

use mpi::traits::Communicator;
use serde_json::json;
use starplex::algo::info::{
    apply_face_counts, face_visits_of, info, FaceCounts, Info, InfoOptions,
};
use starplex::algo::orientation::orient_walk;
use starplex::algo::unionfind::UnionFind;
use starplex::algo::validate::{validate_parts, ValidationReport};
use starplex::cell::CellKind;
use starplex::ids::{CellId, VertexId};
use starplex::topo::naive::VtIndex;
use starplex::topo::{TopCells, VertexStar};

mod comm;
mod dist;
mod fault;
mod homology;
mod labels;
mod morse;
mod query;
mod simplify;
mod stellar;
mod summary;
mod write;

use comm::{agree, Failure, World};
use dist::{Local, Spb, Split};

const USAGE: &str = "usage: mpirun -np P starplex-mpi (info | validate | stellar | homology | query | simplify) FILE.spb [--json] [--max-faces N] [--max-list N] [--kv N] [--vt-vv-out PREFIX] [--stats]\n       homology: [--field 2|p|q|z] [--method morse|contract|algebraic] [--tmp-dir DIR]\n       validate: [--check | --fail-on non-manifold,non-pure,non-orientable,isolated,boundary,disconnected,undecided]\n       query: --relation vt|vv|link|star|adj|ia-star|pfaces --all --out OUT.jsonl|csv|npz [--structure stellar|vt|ia-star|ig|is|simplex-tree|hasse] [--per-rank]\n       simplify: -o OUT.spb [--mode homology|qem] [--ratio R] [--faces N] [--vertices N] [--max-error E] [--keep-manifold] [--lock-boundary] [--keep-vertices FILE] [--keep-labels NAME | --ignore-labels] [--keep-vertex-attribute NAME] [--no-report] [--rounds N] [--gather-below N]";
const VERBS: [&str; 6] = [
    "info", "validate", "stellar", "homology", "query", "simplify",
];

#[derive(Debug)]
struct Args {
    verb: String,
    file: PathBuf,
    json: bool,
    stats: bool,
    max_faces: u128,
    max_list: usize,
    kv: Option<u32>,
    vt_vv_out: Option<PathBuf>,
    out: Option<PathBuf>,
    mode: Option<starplex::algo::simplify::Mode>,
    ratio: Option<f64>,
    faces: Option<u64>,
    vertices: Option<u64>,
    max_error: Option<f64>,
    keep_manifold: bool,
    lock_boundary: bool,
    keep_vertices: Option<PathBuf>,
    keep_labels: Option<String>,
    ignore_labels: bool,
    keep_vertex_attribute: Option<String>,
    no_report: bool,
    rounds: u32,
    gather_below: u64,
    relation: Option<starplex_cli::export::RelationKind>,
    structure: starplex::structures::Structure,
    all: bool,
    per_rank: bool,
    check: bool,
    fail_on: Vec<starplex_cli::report::Defect>,
    field: starplex::algo::homology::Field,
    method: Option<Method>,
    tmp_dir: Option<PathBuf>,
}

/// How `homology` is distributed.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Method {
    /// Rank-local Morse reduction, the interface ranked on rank 0 (simplicial; any field).
    Morse,
    /// One round of homology-mode contraction, the rest on rank 0 (simplicial; any field).
    Contract,
    /// Rank-local Z/2 column reduction of every face (any cells; Z/2).
    Algebraic,
}

fn parse_args() -> Result<Args, String> {
    let mut it = std::env::args().skip(1);
    let mut a = Args {
        verb: String::new(),
        file: PathBuf::new(),
        json: false,
        stats: false,
        max_faces: starplex::limits::INFO_FACES,
        max_list: 1000,
        kv: None,
        vt_vv_out: None,
        out: None,
        mode: None,
        ratio: None,
        faces: None,
        vertices: None,
        max_error: None,
        keep_manifold: false,
        lock_boundary: false,
        keep_vertices: None,
        keep_labels: None,
        ignore_labels: false,
        keep_vertex_attribute: None,
        no_report: false,
        rounds: 8,
        gather_below: 2_000_000,
        relation: None,
        structure: starplex::structures::Structure::Stellar,
        all: false,
        per_rank: false,
        check: false,
        fail_on: Vec::new(),
        field: starplex::algo::homology::Field::Z2,
        method: None,
        tmp_dir: None,
    };
    let mut pos = Vec::new();
    while let Some(x) = it.next() {
        let mut num = |name: &str| -> Result<u128, String> {
            let v = it.next().ok_or(format!("{name} needs a value\n{USAGE}"))?;
            v.parse()
                .map_err(|_| format!("{name}: '{v}' is not a number\n{USAGE}"))
        };
        match x.as_str() {
            "--json" => a.json = true,
            "--stats" => a.stats = true,
            "--max-faces" => a.max_faces = num("--max-faces")?,
            "--max-list" => a.max_list = num("--max-list")? as usize,
            "--kv" => {
                a.kv = Some(
                    u32::try_from(num("--kv")?)
                        .map_err(|_| format!("--kv: above 2^32\n{USAGE}"))?,
                )
            }
            "--vt-vv-out" => {
                a.vt_vv_out = Some(PathBuf::from(
                    it.next()
                        .ok_or(format!("--vt-vv-out needs a value\n{USAGE}"))?,
                ))
            }
            "-o" | "--out" => {
                a.out = Some(PathBuf::from(
                    it.next().ok_or(format!("{x} needs a value\n{USAGE}"))?,
                ))
            }
            "--mode" => {
                let m = it.next().ok_or(format!("--mode needs a value\n{USAGE}"))?;
                a.mode = Some(starplex::algo::simplify::Mode::parse(&m).ok_or(format!(
                    "--mode {m}: unknown mode (use --mode homology or --mode qem)"
                ))?)
            }
            "--ratio" | "--max-error" => {
                let v = it.next().ok_or(format!("{x} needs a value\n{USAGE}"))?;
                let f: f64 = v
                    .parse()
                    .map_err(|_| format!("{x}: '{v}' is not a number\n{USAGE}"))?;
                if x == "--ratio" {
                    a.ratio = Some(f)
                } else {
                    a.max_error = Some(f)
                }
            }
            "--faces" => a.faces = Some(num("--faces")? as u64),
            "--vertices" => a.vertices = Some(num("--vertices")? as u64),
            "--gather-below" => a.gather_below = num("--gather-below")? as u64,
            "--rounds" => {
                a.rounds = u32::try_from(num("--rounds")?)
                    .ok()
                    .filter(|&r| r > 0)
                    .ok_or(format!("--rounds: between 1 and 2^32 - 1\n{USAGE}"))?
            }
            "--relation" => {
                use starplex_cli::export::RelationKind as R;
                let r = it
                    .next()
                    .ok_or(format!("--relation needs a value\n{USAGE}"))?;
                a.relation = Some(match r.as_str() {
                    "vt" => R::Vt,
                    "vv" => R::Vv,
                    "link" => R::Link,
                    "star" => R::Star,
                    "pfaces" => R::Pfaces,
                    "adj" => R::Adj,
                    "ia-star" => R::IaStar,
                    _ => {
                        return Err(format!(
                            "--relation {r}: unknown (vt, vv, link, star, adj, ia-star)\n{USAGE}"
                        ))
                    }
                })
            }
            "--structure" => {
                let n = it
                    .next()
                    .ok_or(format!("--structure needs a value\n{USAGE}"))?;
                a.structure = starplex::structures::Structure::from_name(&n)
                    .ok_or(format!("--structure {n}: unknown\n{USAGE}"))?
            }
            "--field" => {
                let v = it.next().ok_or(format!("--field needs a value\n{USAGE}"))?;
                a.field = starplex::algo::homology::Field::parse(&v).map_err(|e| {
                    format!("--field: {e} (use 2, a prime such as 3, q or z)\n{USAGE}")
                })?
            }
            "--method" => {
                let v = it
                    .next()
                    .ok_or(format!("--method needs a value\n{USAGE}"))?;
                a.method = Some(match v.as_str() {
                    "morse" => Method::Morse,
                    "contract" => Method::Contract,
                    "algebraic" => Method::Algebraic,
                    _ => {
                        return Err(format!(
                            "--method {v}: morse, contract or algebraic\n{USAGE}"
                        ))
                    }
                })
            }
            "--tmp-dir" => {
                a.tmp_dir = Some(PathBuf::from(
                    it.next()
                        .ok_or(format!("--tmp-dir needs a value\n{USAGE}"))?,
                ))
            }
            "--check" => a.check = true,
            "--fail-on" => {
                use starplex_cli::report::Defect as D;
                let list = it
                    .next()
                    .ok_or(format!("--fail-on needs a value\n{USAGE}"))?;
                for d in list.split(',').filter(|d| !d.is_empty()) {
                    a.fail_on.push(match d {
                        "non-manifold" => D::NonManifold,
                        "non-pure" => D::NonPure,
                        "non-orientable" => D::NonOrientable,
                        "isolated" => D::Isolated,
                        "boundary" => D::Boundary,
                        "disconnected" => D::Disconnected,
                        "undecided" => D::Undecided,
                        _ => return Err(format!("--fail-on: unknown defect '{d}'\n{USAGE}")),
                    });
                }
            }
            "--all" => a.all = true,
            "--per-rank" => a.per_rank = true,
            "--keep-manifold" => a.keep_manifold = true,
            "--lock-boundary" => a.lock_boundary = true,
            "--keep-vertices" => {
                a.keep_vertices = Some(PathBuf::from(it.next().ok_or(format!(
                    "--keep-vertices needs a file of vertex ids\n{USAGE}"
                ))?))
            }
            "--keep-labels" | "--keep-vertex-attribute" => {
                let n = it
                    .next()
                    .ok_or(format!("{x} needs an attribute name\n{USAGE}"))?;
                if x == "--keep-labels" {
                    a.keep_labels = Some(n)
                } else {
                    a.keep_vertex_attribute = Some(n)
                }
            }
            "--ignore-labels" => a.ignore_labels = true,
            "--no-report" => a.no_report = true,
            "-h" | "--help" => return Err(USAGE.to_string()),
            s if s.starts_with('-') => return Err(format!("unknown option {s}\n{USAGE}")),
            _ => pos.push(x),
        }
    }
    match pos.as_slice() {
        [v, _] if v == "simplify" && a.keep_labels.is_some() && a.ignore_labels => Err(format!(
            "--keep-labels and --ignore-labels exclude each other\n{USAGE}"
        )),
        [v, _] if v == "simplify" && a.out.is_none() => Err(format!(
            "simplify needs the output file: -o OUT.spb\n{USAGE}"
        )),
        [v, _] if v == "query" && (a.relation.is_none() || !a.all || a.out.is_none()) => Err(
            format!(
                "query writes every answer of one relation: --relation R --all --out OUT.jsonl (single items: `starplex query` on one machine)\n{USAGE}"
            ),
        ),
        [v, f] if VERBS.contains(&v.as_str()) => {
            a.verb = v.clone();
            a.file = PathBuf::from(f);
            Ok(a)
        }
        [v, _] => Err(format!(
            "unknown verb '{v}' (this version distributes info, validate, stellar, homology, query and simplify)\n{USAGE}"
        )),
        _ => Err(USAGE.to_string()),
    }
}

fn main() -> ExitCode {
    starplex_cli::alloc::tune();
    let Some(universe) = mpi::initialize() else {
        eprintln!("error: MPI could not be initialized (run under mpirun)");
        return ExitCode::from(2);
    };
    let w = universe.world();
    let r = run(&w);
    let code = match r {
        Ok(code) => code,
        Err(Failure(msg)) => {
            if w.rank() == 0 {
                eprintln!("error: {msg}");
            }
            2
        }
    };
    drop(universe);
    ExitCode::from(code)
}

/// The shared phases: open, agree on the split, distribute.
struct Loaded {
    f: Spb,
    split: Split,
    l: Local,
    read_s: f64,
}

/// Runs the verb; `Ok(1)` when `validate --check` / `--fail-on` found a defect (rank 0 said
/// which).
fn run(w: &World) -> Result<u8, Failure> {
    let a = agree(w, parse_args())?;
    let t0 = Instant::now();
    fault::guard_sigbus(&a.file);
    if a.verb == "simplify" {
        let out = a.out.as_deref().unwrap_or(std::path::Path::new(""));
        let s = simplify::SimplifyArgs {
            out,
            mode: a.mode,
            ratio: a.ratio,
            faces: a.faces,
            vertices: a.vertices,
            max_error: a.max_error,
            keep_manifold: a.keep_manifold,
            lock_boundary: a.lock_boundary,
            keep_vertices: a.keep_vertices.as_deref(),
            keep_labels: a.keep_labels.as_deref(),
            ignore_labels: a.ignore_labels,
            keep_vertex_attribute: a.keep_vertex_attribute.as_deref(),
            attributes: true,
            report: !a.no_report,
            max_rounds: a.rounds,
            gather_below: a.gather_below,
            json: a.json,
        };
        simplify::run(w, &s, &a.file)?;
        if a.stats {
            print_peaks(w)?;
        }
        return Ok(0);
    }
    if a.verb == "homology" {
        // simplicial complexes: by rank-local Morse reduction (or contraction when asked), over
        // any field; else the algebraic reduction (Z/2)
        let f = agree(w, Spb::open(&a.file))?;
        let simplicial = f.h.blocks.iter().all(|&(k, _, _)| k.is_simplex());
        let contractible = f.h.n_cells > 0 && simplicial;
        drop(f);
        let method = a.method.unwrap_or(if simplicial {
            Method::Morse
        } else {
            Method::Algebraic
        });
        if method == Method::Contract && !contractible {
            return Err(Failure(format!(
                "{}: --method contract needs a simplicial complex with cells (use --method algebraic)",
                a.file.display()
            )));
        }
        if method == Method::Contract {
            homology::run_by_contraction(w, a.json, &a.file, a.field, &tmp_dir(&a))?;
            if a.stats {
                print_peaks(w)?;
            }
            return Ok(0);
        }
        if method == Method::Algebraic && a.field != starplex::algo::homology::Field::Z2 {
            return Err(Failure(format!(
                "--field {}: the algebraic method (CP cells, or --method algebraic) computes over Z/2 only",
                a.field
            )));
        }
    }
    let f = agree(w, Spb::open(&a.file))?;
    fault::test_pause();
    let split = dist::split(w, &f, dist::SplitKind::Plain)?;
    let l = dist::distribute(w, &f, &split)?;
    agree(w, f.check_unchanged())?;
    f.release_pages();
    let mut ld = Loaded {
        f,
        split,
        l,
        read_s: t0.elapsed().as_secs_f64(),
    };
    let mut code = 0;
    match a.verb.as_str() {
        "info" => run_info(w, &a, &mut ld)?,
        "stellar" => stellar::run(
            w,
            &stellar::StellarArgs {
                kv: a.kv,
                vt_vv_out: a.vt_vv_out.as_deref(),
                json: a.json,
            },
            &a.file,
            &ld.f,
            &ld.l,
            ld.read_s,
        )?,
        "homology"
            if a.method == Some(Method::Algebraic)
                || !ld.f.h.blocks.iter().all(|&(k, _, _)| k.is_simplex()) =>
        {
            homology::run(w, a.json, &a.file, &ld.f, &ld.l, ld.read_s, a.max_faces)?
        }
        "homology"
            if a.method.is_none() && {
                // the default: Morse, unless the cells that span ranks have too many faces
                // (high-dimensional complexes): then contraction, which has no such bound
                let est = morse::interface_estimate(&ld.l);
                comm::max(w, u64::try_from(est).unwrap_or(u64::MAX)) > morse::AUTO_FACES
            } =>
        {
            ld.l = Local::empty();
            homology::run_by_contraction(w, a.json, &a.file, a.field, &tmp_dir(&a))?
        }
        "homology" => morse::run(
            w,
            a.json,
            &a.file,
            ld.f.dim().unwrap_or(0) + 1,
            &mut ld.l,
            ld.read_s,
            a.field,
            a.max_faces,
        )?,
        "query" => {
            let q = query::QueryArgs {
                relation: a.relation.unwrap_or(starplex_cli::export::RelationKind::Vt),
                structure: a.structure,
                out: a.out.as_deref().unwrap_or(std::path::Path::new("")),
                per_rank: a.per_rank,
                kv: a.kv,
                json: a.json,
            };
            query::run(w, &q, &a.file, &ld.f, &ld.split, &mut ld.l, ld.read_s)?
        }
        _ => code = run_validate(w, &a, &ld)?,
    }
    if a.stats {
        print_stats(w, &ld)?;
    }
    Ok(code)
}

/// Where `homology --method contract` writes its temporary file: `--tmp-dir`, else beside the
/// input.
fn tmp_dir(a: &Args) -> PathBuf {
    a.tmp_dir.clone().unwrap_or_else(|| {
        a.file
            .parent()
            .filter(|p| !p.as_os_str().is_empty())
            .map_or_else(|| PathBuf::from("."), PathBuf::from)
    })
}

/// Connected components of the 1-skeleton (isolated vertices count): local union-find over
/// the held cells, merged across ranks by the labels of the ghost vertices.
fn components(w: &World, l: &Local) -> Result<u64, Failure> {
    let n = l.vertex_gid.len();
    let mut uf = UnionFind::new(n);
    for c in l.k.cells() {
        for &v in &c.vertices[1..] {
            uf.union(c.vertices[0], v);
        }
    }
    let (class, n_classes) = classes(&mut uf, n);
    let e = labels::Elements {
        gid: l.vertex_gid.clone(),
        owner: l.vertex_owner.clone(),
        class,
        n_classes,
        sign: vec![1; n],
        conflict: false,
    };
    Ok(labels::merge(w, &e)?.n_classes)
}

/// Dense class ids `0..n` of the sets of `uf`.
fn classes(uf: &mut UnionFind, n: usize) -> (Vec<u32>, usize) {
    let mut id = vec![u32::MAX; n];
    let mut class = Vec::with_capacity(n);
    let mut next = 0u32;
    for i in 0..n as u32 {
        let r = uf.find(i) as usize;
        if id[r] == u32::MAX {
            id[r] = next;
            next += 1;
        }
        class.push(id[r]);
    }
    (class, next as usize)
}

pub(crate) fn global_dims(f: &Spb) -> std::collections::BTreeSet<usize> {
    f.h.blocks.iter().map(|&(k, _, _)| k.dim()).collect()
}

fn isolated_owned(l: &Local) -> Vec<u32> {
    let used = l.k.used_vertices();
    l.owned
        .ones()
        .filter(|&v| !used.contains(v))
        .map(|v| l.vertex_gid[v])
        .collect()
}

fn run_info(w: &World, a: &Args, ld: &mut Loaded) -> Result<(), Failure> {
    let t1 = Instant::now();
    let (f, l) = (&ld.f, &ld.l);
    let dims = global_dims(f);
    let dim = dims.iter().max().map_or(-1, |&d| d as i64);
    let n_isolated = comm::sum(w, isolated_owned(l).len() as u64);
    let mut top_cells = std::collections::BTreeMap::new();
    for &(k, n, _) in &f.h.blocks {
        *top_cells.entry(k.type_name()).or_insert(0) += n;
    }
    let mut s = Info {
        n_vertices: f.h.n_vertices,
        n_isolated_vertices: n_isolated,
        ambient_dim: f.h.ambient_dim as u64,
        dim,
        pure: dims.len() == 1 && n_isolated == 0,
        top_cells,
        n_top_cells: f.h.n_cells,
        bbox: ld.split.bbox.clone(),
        f_vector: None,
        f_vector_estimate: None,
        euler_characteristic: None,
        n_boundary_faces: None,
        n_faces_shared_by_more_than_2_top_cells: None,
        faces_by_type: None,
        n_connected_components: components(w, l)?,
    };
    let estimate = face_visits_of(f.h.blocks.iter().map(|&(k, n, _)| (k, n)));
    if dim < 0 {
        s.f_vector = Some(vec![]);
        s.euler_characteristic = Some(0);
    } else if estimate > a.max_faces {
        s.f_vector_estimate = Some(estimate);
    } else {
        let counts = owned_face_counts(w, l, dim as usize);
        let simplicial =
            f.h.blocks
                .iter()
                .all(|&(k, _, _)| matches!(k, CellKind::Simplex(_)));
        apply_face_counts(&mut s, &counts, dims.len() == 1, simplicial);
    }
    agree(w, f.check_unchanged())?;
    let info_s = t1.elapsed().as_secs_f64();
    if w.rank() == 0 {
        if a.json {
            let mut v = starplex_cli::report::info_json(&s);
            v["format"] = json!(starplex::io::Format::Binary.extension());
            v["timings"] = json!({"read_s": ld.read_s, "info_s": info_s});
            print_json(&v);
        } else {
            starplex_cli::report::print_info(
                &s,
                &a.file.display().to_string(),
                ld.read_s,
                info_s,
                a.max_faces,
            );
        }
    }
    Ok(())
}

/// The faces of dimension 1 to `d` of the whole complex, each counted by the rank owning its
/// smallest vertex (collective); `per_dim[0]` is left 0.
pub(crate) fn owned_face_counts(w: &World, l: &Local, d: usize) -> FaceCounts {
    let part = info(
        &l.k,
        &InfoOptions {
            limits: starplex::limits::Limits {
                info_faces: u128::MAX,
                ..Default::default()
            },
            owned_vertices: Some(Arc::new(l.owned.clone())),
            ..Default::default()
        },
    );
    // [f_1 .. f_d, boundary, shared by > 2, tri faces, quad faces]
    let mut mine = vec![0u64; d + 4];
    if let Some(fv) = &part.f_vector {
        for (i, &x) in fv.iter().enumerate().skip(1).take(d) {
            mine[i - 1] = x;
        }
    }
    mine[d] = part.n_boundary_faces.unwrap_or(0);
    mine[d + 1] = part.n_faces_shared_by_more_than_2_top_cells.unwrap_or(0);
    if let Some(m) = &part.faces_by_type {
        mine[d + 2] = m.get("tri").copied().unwrap_or(0);
        mine[d + 3] = m.get("quad").copied().unwrap_or(0);
    }
    let all = comm::sums(w, &mine);
    let mut per_dim = vec![0u64];
    per_dim.extend_from_slice(&all[..d]);
    FaceCounts {
        per_dim,
        boundary: all[d],
        shared_more_than_2: all[d + 1],
        tri_faces: all[d + 2],
        quad_faces: all[d + 3],
    }
}

pub(crate) fn print_json(v: &serde_json::Value) {
    println!(
        "{}",
        serde_json::to_string_pretty(v).unwrap_or_else(|e| format!("{{\"error\": \"{e}\"}}"))
    );
}

/// The local complex seen with empty stars at the vertices this rank does not own: a generic
/// algorithm that visits every vertex's star then sees each owned vertex's full star once and
/// nothing else, which is the ownership rule (a face is handled by the owner of its smallest
/// vertex).
pub(crate) struct OwnedStars<'a> {
    pub idx: VtIndex<'a>,
    pub owned: &'a fixedbitset::FixedBitSet,
}

impl TopCells for OwnedStars<'_> {
    fn n_vertices(&self) -> usize {
        self.idx.n_vertices()
    }
    fn n_top_cells(&self) -> usize {
        self.idx.n_top_cells()
    }
    fn top_cell_kind(&self, c: CellId) -> CellKind {
        self.idx.top_cell_kind(c)
    }
    fn top_cell_vertices(&self, c: CellId, out: &mut Vec<VertexId>) {
        self.idx.top_cell_vertices(c, out)
    }
}

impl VertexStar for OwnedStars<'_> {
    fn vertex_top_cells(&self, v: VertexId, out: &mut Vec<CellId>) {
        if self.owned.contains(v.index()) {
            self.idx.vertex_top_cells(v, out)
        } else {
            out.clear()
        }
    }
}

/// Flattens faces as `len, v...` (global ids).
fn flat_faces(l: &Local, faces: &[Vec<VertexId>]) -> Vec<u32> {
    let mut out = Vec::new();
    for f in faces {
        out.push(f.len() as u32);
        out.extend(f.iter().map(|v| l.vertex_gid[v.index()]));
    }
    out
}

fn unflat_faces(x: &[u32]) -> Vec<Vec<VertexId>> {
    let mut out = Vec::new();
    let mut i = 0;
    while i < x.len() {
        let n = x[i] as usize;
        out.push(x[i + 1..i + 1 + n].iter().map(|&v| VertexId(v)).collect());
        i += 1 + n;
    }
    out.sort_unstable();
    out
}

fn vids(x: Vec<u32>) -> Vec<VertexId> {
    let mut v: Vec<VertexId> = x.into_iter().map(VertexId).collect();
    v.sort_unstable();
    v
}

/// Edges by their first vertex, each vertex's edges in the order they came (the single-process
/// order: vertices in increasing id, each vertex's edges as its star test lists them).
fn edges(x: Vec<u32>) -> Vec<[VertexId; 2]> {
    let mut e: Vec<[VertexId; 2]> = x
        .chunks_exact(2)
        .map(|c| [VertexId(c[0]), VertexId(c[1])])
        .collect();
    e.sort_by_key(|e| e[0]);
    e
}

/// A witness that the complex cannot be oriented: the smallest pair `(a, b)` (global ids,
/// `a < b`, packed as `a << 32 | b`; `u64::MAX` when none here) among this rank's facet pairs
/// whose final signs contradict their induced orientations (`signs[x] * signs[y] == s`, where
/// a consistent pair has `-s`). The single process names the first conflict its sequential
/// walk meets, which a distributed run cannot reproduce: this is another such pair.
fn conflict_witness(l: &Local, d: usize, pairs: &[(u32, u32, i8)], signs: &[i8]) -> u64 {
    // element index of each top cell (the order `facet_classes` lists them in)
    let mut elem = vec![u32::MAX; l.k.n_cells()];
    let mut next = 0u32;
    for (c, e) in elem.iter_mut().enumerate() {
        if l.k.cell(CellId(c as u32)).kind.dim() == d {
            *e = next;
            next += 1;
        }
    }
    let mut best = u64::MAX;
    for &(x, y, s) in pairs {
        let (ex, ey) = (elem[x as usize], elem[y as usize]);
        if ex == u32::MAX || ey == u32::MAX {
            continue;
        }
        if signs[ex as usize] * signs[ey as usize] == s {
            let (a, b) = (l.cell_gid[x as usize], l.cell_gid[y as usize]);
            let (a, b) = (a.min(b), a.max(b));
            best = best.min((u64::from(a) << 32) | u64::from(b));
        }
    }
    best
}

/// The facet-connected classes of the top cells and their orientation signs: the local walk over
/// the facet `pairs`, then the merge across ranks.
fn facet_classes(
    w: &World,
    l: &Local,
    d: usize,
    pairs: &[(u32, u32, i8)],
) -> Result<labels::Merged, Failure> {
    let nc = l.k.n_cells();
    let is_top = |c: u32| l.k.cell(CellId(c)).kind.dim() == d;
    let walk = orient_walk(nc, is_top, pairs, |_| 1);
    let mut uf = UnionFind::new(nc);
    for &(x, y, _) in pairs {
        uf.union(x, y);
    }
    let tops: Vec<usize> = (0..nc).filter(|&c| is_top(c as u32)).collect();
    let (class_all, _) = classes(&mut uf, nc);
    // classes renumbered over the top cells
    let mut remap = rustc_hash::FxHashMap::default();
    let class: Vec<u32> = tops
        .iter()
        .map(|&c| {
            let n = remap.len() as u32;
            *remap.entry(class_all[c]).or_insert(n)
        })
        .collect();
    let e = labels::Elements {
        gid: tops.iter().map(|&c| l.cell_gid[c]).collect(),
        owner: tops
            .iter()
            .map(|&c| {
                let cell = l.k.cell(CellId(c as u32));
                let m = cell.vertices.iter().copied().min().unwrap_or(0);
                l.vertex_owner[m as usize]
            })
            .collect(),
        class,
        n_classes: remap.len(),
        sign: tops.iter().map(|&c| walk.signs[c]).collect(),
        conflict: walk.conflict.is_some(),
    };
    labels::merge(w, &e)
}

/// `validate`; returns the exit status (1: a defect `--check` / `--fail-on` asked about).
fn run_validate(w: &World, a: &Args, ld: &Loaded) -> Result<u8, Failure> {
    let (f, l) = (&ld.f, &ld.l);
    let t1 = Instant::now();
    let view = OwnedStars {
        idx: VtIndex::new(&l.k),
        owned: &l.owned,
    };
    let build_s = t1.elapsed().as_secs_f64();
    let t2 = Instant::now();
    let d = global_dims(f).into_iter().max();
    let (r, pairs) = validate_parts(&view, d);
    let OwnedLists {
        lower,
        nm_v,
        un_v,
        nm_e,
        un_e,
        bnd,
        more,
    } = owned_lists(l, &r);
    let isolated = isolated_owned(l);
    let n_components = components(w, l)?;
    // facet classes and orientation: local walk, then the merge across ranks
    let mut rep = ValidationReport {
        dim: d.map_or(if f.h.n_vertices > 0 { 0 } else { -1 }, |d| d as i64),
        n_connected_components: n_components,
        ..Default::default()
    };
    let (mut negative, mut conflict) = (Vec::new(), false);
    let mut witness = u64::MAX;
    if let Some(d) = d {
        let m = facet_classes(w, l, d, &pairs)?;
        if m.conflict {
            witness = conflict_witness(l, d, &pairs, &m.signs);
        }
        rep.n_facet_components = m.n_classes;
        rep.facet_connected = m.n_classes == 1;
        negative = m.negative;
        conflict = m.conflict;
    }
    let validate_s = t2.elapsed().as_secs_f64();
    // complete counts, and only the first --max-list entries of each rank's lists (rank 0
    // keeps the first --max-list of their union: O(ranks x max-list), not O(boundary))
    let counts = comm::sums(
        w,
        &[
            bnd_len(&bnd) as u64,
            bnd_len(&more) as u64,
            nm_v.len() as u64,
            (nm_e.len() / 2) as u64,
            un_v.len() as u64,
            (un_e.len() / 2) as u64,
            isolated.len() as u64,
            lower.len() as u64,
            negative.len() as u64,
        ],
    );
    let max = a.max_list;
    let gathered = [
        comm::gather(w, &first_ids(isolated, max))?,
        comm::gather(w, &first_ids(lower, max))?,
        comm::gather(w, &first_ids(nm_v, max))?,
        comm::gather(w, &first_ids(un_v, max))?,
        comm::gather(w, &first_edges(nm_e, max))?,
        comm::gather(w, &first_edges(un_e, max))?,
        comm::gather(w, &first_faces(&bnd, max))?,
        comm::gather(w, &first_faces(&more, max))?,
    ];
    let c = starplex_cli::report::ListCounts {
        boundary_faces: counts[0] as usize,
        faces_in_more_than_two_cells: counts[1] as usize,
        non_manifold_vertices: counts[2] as usize,
        non_manifold_edges: counts[3] as usize,
        unknown_vertices: counts[4] as usize,
        unknown_edges: counts[5] as usize,
        isolated_vertices: counts[6] as usize,
        lower_dimensional_cells: counts[7] as usize,
        cells_to_flip: (d.is_some() && counts[1] == 0 && !conflict).then_some(counts[8] as usize),
    };
    // non-orientable: the smallest pair (global ids) whose signs contradict, over all ranks
    let witness = comm::min(w, witness);
    let conflict_pair =
        (conflict && witness != u64::MAX).then_some(((witness >> 32) as u32, witness as u32));
    agree(w, f.check_unchanged())?;
    let report = if w.rank() == 0 {
        Some(validation_report(rep, d, &c, max, conflict_pair, gathered))
    } else {
        None
    };
    let wanted = starplex_cli::report::Defect::wanted(a.check, &a.fail_on);
    let found = report
        .as_ref()
        .map(|r| starplex_cli::report::defects_found_counted(r, &c, &wanted))
        .unwrap_or_default();
    let failed = comm::max(w, u64::from(!found.is_empty())) > 0;
    if let Some(rep) = report {
        if a.json {
            let mut v = starplex_cli::report::validation_json_counted(&rep, &c, a.max_list);
            v["timings"] =
                json!({"read_s": ld.read_s, "build_s": build_s, "validate_s": validate_s});
            print_json(&v);
        } else {
            println!("{}", a.file.display());
            starplex_cli::report::print_validation_counted(&rep, &c, a.max_list);
            println!(
                "  time                read {:.3} s, Stellar tree {build_s:.3} s, validation {validate_s:.3} s",
                ld.read_s
            );
        }
        if failed {
            eprintln!(
                "error: {}: validation failed: {}",
                a.file.display(),
                found.join("; ")
            );
        }
    }
    Ok(u8::from(failed))
}

/// This rank's share of the lists of a validation of its local complex (the owner's items),
/// in global ids: edges as pairs, faces as [`flat_faces`].
pub(crate) struct OwnedLists {
    pub lower: Vec<u32>,
    pub nm_v: Vec<u32>,
    pub un_v: Vec<u32>,
    pub nm_e: Vec<u32>,
    pub un_e: Vec<u32>,
    pub bnd: Vec<u32>,
    pub more: Vec<u32>,
}

/// The owned items of `r` (a validation of the owned stars of `l`).
pub(crate) fn owned_lists(l: &Local, r: &ValidationReport) -> OwnedLists {
    let gv = |v: &VertexId| l.vertex_gid[v.index()];
    let owned_v = |v: &VertexId| l.owned.contains(v.index());
    let vertices =
        |vs: &[VertexId]| -> Vec<u32> { vs.iter().filter(|v| owned_v(v)).map(gv).collect() };
    let edge_list = |es: &[[VertexId; 2]]| -> Vec<u32> {
        es.iter()
            .filter(|e| owned_v(&e[0]))
            .flat_map(|e| [gv(&e[0]), gv(&e[1])])
            .collect()
    };
    OwnedLists {
        lower: r
            .lower_dimensional_cells
            .iter()
            .filter(|c| l.owns_cell(c.index()))
            .map(|c| l.cell_gid[c.index()])
            .collect(),
        nm_v: vertices(&r.non_manifold_vertices),
        un_v: vertices(&r.unknown_vertices),
        nm_e: edge_list(&r.non_manifold_edges),
        un_e: edge_list(&r.unknown_edges),
        bnd: flat_faces(l, &r.boundary_faces),
        more: flat_faces(l, &r.faces_in_more_than_two_cells),
    }
}

/// Rank 0's report from the gathered first entries of the lists (global ids, sorted as the
/// single process sorts them, cut to `max`) and the complete counts `c`.
fn validation_report(
    mut rep: ValidationReport,
    d: Option<usize>,
    c: &starplex_cli::report::ListCounts,
    max: usize,
    conflict: Option<(u32, u32)>,
    gathered: [Option<Vec<u32>>; 8],
) -> ValidationReport {
    let [Some(iso), Some(low), Some(nmv), Some(unv), Some(nme), Some(une), Some(bnd), Some(more)] =
        gathered
    else {
        unreachable!("rank 0 holds every gathered list");
    };
    let cut = |mut v: Vec<VertexId>| {
        v.truncate(max);
        v
    };
    rep.isolated_vertices = cut(vids(iso));
    let mut low = low;
    low.sort_unstable();
    low.truncate(max);
    rep.lower_dimensional_cells = low.into_iter().map(CellId).collect();
    rep.non_manifold_vertices = cut(vids(nmv));
    rep.unknown_vertices = cut(vids(unv));
    rep.non_manifold_edges = edges(nme);
    rep.non_manifold_edges.truncate(max);
    rep.unknown_edges = edges(une);
    rep.unknown_edges.truncate(max);
    rep.boundary_faces = unflat_faces(&bnd);
    rep.boundary_faces.truncate(max);
    rep.faces_in_more_than_two_cells = unflat_faces(&more);
    rep.faces_in_more_than_two_cells.truncate(max);
    match d {
        None => rep.pure = c.isolated_vertices == 0,
        Some(_) => {
            rep.pure = c.lower_dimensional_cells == 0 && c.isolated_vertices == 0;
            rep.pseudo_manifold =
                rep.pure && c.faces_in_more_than_two_cells == 0 && rep.facet_connected;
            if c.faces_in_more_than_two_cells == 0 {
                match conflict {
                    Some((a, b)) => {
                        rep.orientable = Some(false);
                        rep.orientation_conflict = Some((CellId(a), CellId(b)));
                    }
                    None => {
                        rep.orientable = Some(true);
                        // only the count is reported; the ids stay on their ranks
                        rep.cells_to_flip = Some(Vec::new());
                    }
                }
            }
        }
    }
    rep
}

/// The first `max` ids of a rank's list, sorted.
fn first_ids(mut v: Vec<u32>, max: usize) -> Vec<u32> {
    v.sort_unstable();
    v.truncate(max);
    v
}

/// The first `max` edges (flat pairs) in the single process's order: by first vertex, each
/// vertex's edges in the order found (a vertex's edges all come from its owner).
fn first_edges(v: Vec<u32>, max: usize) -> Vec<u32> {
    let mut e: Vec<[u32; 2]> = v.chunks_exact(2).map(|c| [c[0], c[1]]).collect();
    e.sort_by_key(|e| e[0]);
    e.truncate(max);
    e.into_iter().flatten().collect()
}

/// Number of faces of a flat face list (`n, v.., n, v..`).
pub(crate) fn bnd_len(x: &[u32]) -> usize {
    let (mut i, mut n) = (0, 0);
    while i < x.len() {
        i += 1 + x[i] as usize;
        n += 1;
    }
    n
}

/// The first `max` faces of a flat face list, sorted, flat again.
fn first_faces(x: &[u32], max: usize) -> Vec<u32> {
    let mut f = unflat_faces(x);
    f.truncate(max);
    let mut out = Vec::new();
    for g in f {
        out.push(g.len() as u32);
        out.extend(g.iter().map(|v| v.0));
    }
    out
}

/// Peak resident set of this process in KiB (`VmHWM`), 0 when unknown.
fn peak_rss_kib() -> u64 {
    starplex::measure::memory().map_or(0, |m| m.peak / 1024)
}

/// `--stats` of `simplify` (the local complexes change every round): bytes sent and peak
/// memory of every rank.
fn print_peaks(w: &World) -> Result<(), Failure> {
    let row = [w.rank() as u64, comm::bytes_sent(), peak_rss_kib()];
    if let Some(all) = comm::gather(w, &row)? {
        eprintln!("rank bytes_sent peak_rss_kib");
        for r in all.chunks_exact(row.len()) {
            eprintln!("{} {} {}", r[0], r[1], r[2]);
        }
    }
    Ok(())
}

fn print_stats(w: &World, ld: &Loaded) -> Result<(), Failure> {
    let l = &ld.l;
    let row = [
        w.rank() as u64,
        l.owned.count_ones(..) as u64,
        l.vertex_gid.len() as u64,
        l.n_owned_cells,
        l.cell_gid.len() as u64, // held cells (a verb may have freed the local complex)
        comm::bytes_sent(),
        peak_rss_kib(),
    ];
    if let Some(all) = comm::gather(w, &row)? {
        let owned: Vec<u64> = all.chunks_exact(row.len()).map(|r| r[3]).collect();
        let (max, total) = (
            owned.iter().copied().max().unwrap_or(0),
            owned.iter().sum::<u64>(),
        );
        let mean = total as f64 / owned.len().max(1) as f64;
        eprintln!(
            "owned top cells per rank {owned:?}: max / mean {:.3} (the split balances owned top cells)",
            if mean > 0.0 { max as f64 / mean } else { 1.0 }
        );
        eprintln!("rank owned_vertices held_vertices owned_cells held_cells ghost_share bytes_sent peak_rss_kib");
        for r in all.chunks_exact(row.len()) {
            let ghost = if r[4] > 0 {
                (r[4] - r[3]) as f64 / r[4] as f64
            } else {
                0.0
            };
            eprintln!(
                "{} {} {} {} {} {:.4} {} {}",
                r[0], r[1], r[2], r[3], r[4], ghost, r[5], r[6]
            );
        }
    }
    Ok(())
}
