//! The output of `starplex info` and `starplex validate` (JSON and human), shared by the CLI and
//! `starplex-mpi`, whose rank 0 prints exactly what the single-process command prints.
use serde_json::{json, Value};
use starplex::algo::info::Info;
use starplex::algo::validate::ValidationReport;
use starplex::stellar::StellarStats;

/// The JSON object of `starplex info --json` (keys as in the dataset oracles), before the
/// `format`, `timings`, `betti_z2` and `notes` keys the command adds.
///
/// ```
/// use starplex::algo::info::{info, InfoOptions};
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// let v = starplex_cli::report::info_json(&info(&k, &InfoOptions::default()));
/// assert_eq!(v["f_vector"], serde_json::json!([3, 3, 1]));
/// starplex_cli::report::print_info(&info(&k, &InfoOptions::default()), "k", 0.0, 0.0, 1000);
/// ```
pub fn info_json(s: &Info) -> Value {
    json!({
        "n_vertices": s.n_vertices,
        "n_isolated_vertices": s.n_isolated_vertices,
        "ambient_dim": s.ambient_dim,
        "dim": s.dim,
        "pure": s.pure,
        "top_cells": s.top_cells,
        "n_top_cells": s.n_top_cells,
        "bbox": s.bbox.as_ref().map(|(lo, hi)| json!([lo, hi])),
        "f_vector": s.f_vector,
        "f_vector_estimate": s.f_vector_estimate.map(|e| e.to_string()),
        "euler_characteristic": s.euler_characteristic,
        "n_boundary_faces": s.n_boundary_faces,
        "n_faces_shared_by_more_than_2_top_cells": s.n_faces_shared_by_more_than_2_top_cells,
        "faces_by_type": s.faces_by_type,
        "n_connected_components": s.n_connected_components,
    })
}

/// Prints the human output of `starplex info` (`name` heads it; `budget` is the f-vector budget
/// named when the f-vector was skipped). Example: [`info_json`].
pub fn print_info(s: &Info, name: &str, load_s: f64, info_s: f64, budget: u128) {
    println!("{name}");
    let kinds: Vec<String> = s
        .top_cells
        .iter()
        .map(|(k, n)| format!("{n} {k}"))
        .collect();
    println!(
        "  vertices            {} ({} isolated), ambient dimension {}",
        s.n_vertices, s.n_isolated_vertices, s.ambient_dim
    );
    println!(
        "  top cells           {} ({})",
        s.n_top_cells,
        kinds.join(", ")
    );
    println!(
        "  dimension           {}{}",
        s.dim,
        if s.pure { ", pure" } else { ", not pure" }
    );
    if let Some((lo, hi)) = &s.bbox {
        let f = |v: &Vec<f64>| {
            v.iter()
                .map(|x| format!("{x:.6}"))
                .collect::<Vec<_>>()
                .join(" ")
        };
        println!("  bounding box        [{}] .. [{}]", f(lo), f(hi));
    }
    match (&s.f_vector, s.f_vector_estimate) {
        (Some(f), _) => {
            println!("  f-vector            {f:?}");
            if let Some(m) = &s.faces_by_type {
                let parts: Vec<String> = m.iter().map(|(k, n)| format!("{n} {k}")).collect();
                println!("  2-faces by kind     {}", parts.join(", "));
            }
        }
        (None, Some(e)) => println!(
            "  f-vector            skipped: about {e} (cell, face) pairs to visit, over the budget of {budget} (raise it with --max-faces)"
        ),
        _ => {}
    }
    if let Some(x) = s.euler_characteristic {
        println!("  Euler char.         {x}");
    }
    if let Some(b) = s.n_boundary_faces {
        println!("  boundary faces      {b}");
    }
    if let Some(b) = s.n_faces_shared_by_more_than_2_top_cells {
        println!("  faces in >2 cells   {b}");
    }
    println!("  components          {}", s.n_connected_components);
    println!("  time                read {load_s:.3} s, info {info_s:.3} s");
}

fn ids<T: Clone>(v: &[T], max: usize) -> Vec<T> {
    v[..v.len().min(max)].to_vec()
}

/// The lengths of the lists of a [`ValidationReport`]: what the reports print as counts. A
/// report whose lists were cut (`starplex-mpi validate` gathers only the first entries of
/// each rank's lists) comes with the complete counts.
///
/// ```
/// use starplex_cli::report::ListCounts;
/// let k = starplex::generate::kuhn_grid(&[2, 2]).unwrap();
/// let r = starplex::algo::validate::validate(&starplex::topo::naive::VtIndex::new(&k));
/// let c = ListCounts::of(&r);
/// assert_eq!((c.boundary_faces, c.cells_to_flip), (8, Some(4))); // the grid alternates orientations
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ListCounts {
    /// Boundary faces.
    pub boundary_faces: usize,
    /// Faces in more than two top cells.
    pub faces_in_more_than_two_cells: usize,
    /// Non-manifold vertices.
    pub non_manifold_vertices: usize,
    /// Non-manifold edges.
    pub non_manifold_edges: usize,
    /// Vertices whose link is not classified.
    pub unknown_vertices: usize,
    /// Edges whose link is not classified.
    pub unknown_edges: usize,
    /// Isolated vertices.
    pub isolated_vertices: usize,
    /// Lower-dimensional top cells.
    pub lower_dimensional_cells: usize,
    /// Cells to flip (when orientable).
    pub cells_to_flip: Option<usize>,
}

impl ListCounts {
    /// The counts of a report's (complete) lists. Example: [`ListCounts`].
    pub fn of(r: &ValidationReport) -> ListCounts {
        ListCounts {
            boundary_faces: r.boundary_faces.len(),
            faces_in_more_than_two_cells: r.faces_in_more_than_two_cells.len(),
            non_manifold_vertices: r.non_manifold_vertices.len(),
            non_manifold_edges: r.non_manifold_edges.len(),
            unknown_vertices: r.unknown_vertices.len(),
            unknown_edges: r.unknown_edges.len(),
            isolated_vertices: r.isolated_vertices.len(),
            lower_dimensional_cells: r.lower_dimensional_cells.len(),
            cells_to_flip: r.cells_to_flip.as_ref().map(Vec::len),
        }
    }
}

/// The JSON object of `starplex validate --json` before the `timings` and `notes` keys; every
/// list is cut to its first `max` entries (the counts are complete).
///
/// ```
/// use starplex::algo::validate::validate;
/// use starplex::topo::naive::VtIndex;
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// let r = validate(&VtIndex::new(&k));
/// let v = starplex_cli::report::validation_json(&r, 2);
/// assert_eq!(v["n_boundary_faces"], 3);
/// assert_eq!(v["boundary_faces"].as_array().unwrap().len(), 2);
/// starplex_cli::report::print_validation(&r, 2);
/// ```
pub fn validation_json(r: &ValidationReport, max: usize) -> Value {
    validation_json_counted(r, &ListCounts::of(r), max)
}

/// [`validation_json`] of a report whose lists may be cut, with their complete counts `c`.
///
/// ```
/// use starplex_cli::report::{validation_json_counted, ListCounts};
/// let k = starplex::generate::kuhn_grid(&[2, 2]).unwrap();
/// let mut r = starplex::algo::validate::validate(&starplex::topo::naive::VtIndex::new(&k));
/// let c = ListCounts::of(&r);
/// r.boundary_faces.truncate(3);
/// let v = validation_json_counted(&r, &c, 3);
/// assert_eq!((v["n_boundary_faces"].as_u64(), v["boundary_faces"].as_array().unwrap().len()), (Some(8), 3));
/// ```
pub fn validation_json_counted(r: &ValidationReport, c: &ListCounts, max: usize) -> Value {
    let vids = |v: &[starplex::ids::VertexId]| ids(v, max).iter().map(|x| x.0).collect::<Vec<_>>();
    let edges = |e: &[[starplex::ids::VertexId; 2]]| {
        ids(e, max)
            .iter()
            .map(|e| [e[0].0, e[1].0])
            .collect::<Vec<_>>()
    };
    let faces = |f: &[Vec<starplex::ids::VertexId>]| {
        ids(f, max)
            .iter()
            .map(|f| f.iter().map(|v| v.0).collect::<Vec<_>>())
            .collect::<Vec<_>>()
    };
    json!({
        "dim": r.dim,
        "n_connected_components": r.n_connected_components,
        "n_boundary_faces": c.boundary_faces,
        "n_faces_shared_by_more_than_2_top_cells": c.faces_in_more_than_two_cells,
        "n_non_manifold_vertices": c.non_manifold_vertices,
        "n_non_manifold_edges": c.non_manifold_edges,
        "n_unknown_vertices": c.unknown_vertices,
        "n_unknown_edges": c.unknown_edges,
        "n_isolated_vertices": c.isolated_vertices,
        "n_lower_dimensional_cells": c.lower_dimensional_cells,
        "n_facet_components": r.n_facet_components,
        "pure": r.pure,
        "facet_connected": r.facet_connected,
        "pseudo_manifold": r.pseudo_manifold,
        "orientable": r.orientable,
        "n_cells_to_flip": c.cells_to_flip,
        "orientation_conflict": r.orientation_conflict.map(|(a, b)| [a.0, b.0]),
        "non_manifold_vertices": vids(&r.non_manifold_vertices),
        "non_manifold_edges": edges(&r.non_manifold_edges),
        "unknown_vertices": vids(&r.unknown_vertices),
        "isolated_vertices": vids(&r.isolated_vertices),
        "lower_dimensional_cells": ids(&r.lower_dimensional_cells, max).iter().map(|c| c.0).collect::<Vec<_>>(),
        "boundary_faces": faces(&r.boundary_faces),
        "faces_shared_by_more_than_2_top_cells": faces(&r.faces_in_more_than_two_cells),
        "lists_truncated_to": max,
    })
}

/// Prints the human output of `starplex validate` (without the file name and time lines).
/// Example: [`validation_json`].
pub fn print_validation(r: &ValidationReport, max: usize) {
    print_validation_counted(r, &ListCounts::of(r), max)
}

/// [`print_validation`] of a report whose lists may be cut, with their complete counts `c`.
/// Example: [`validation_json_counted`].
pub fn print_validation_counted(r: &ValidationReport, c: &ListCounts, max: usize) {
    let yes = |b: bool| if b { "yes" } else { "no" };
    println!("  components          {}", r.n_connected_components);
    println!(
        "  pure                {} ({} isolated vertices, {} lower-dimensional cells)",
        yes(r.pure),
        c.isolated_vertices,
        c.lower_dimensional_cells
    );
    println!(
        "  (d-1)-connected     {} ({} classes of top cells)",
        yes(r.facet_connected),
        r.n_facet_components
    );
    println!("  pseudo-manifold     {}", yes(r.pseudo_manifold));
    println!(
        "  boundary faces      {} ({} faces in more than 2 top cells)",
        c.boundary_faces, c.faces_in_more_than_two_cells
    );
    let show = |v: Vec<String>, n: usize| {
        if v.is_empty() {
            String::new()
        } else {
            format!(
                ": {}{}",
                v.iter()
                    .take(max.min(10))
                    .cloned()
                    .collect::<Vec<_>>()
                    .join(" "),
                if n > 10 { " ..." } else { "" }
            )
        }
    };
    println!(
        "  non-manifold        {} vertices{}",
        c.non_manifold_vertices,
        show(
            r.non_manifold_vertices
                .iter()
                .map(|v| v.to_string())
                .collect(),
            c.non_manifold_vertices
        )
    );
    println!(
        "                      {} edges{}",
        c.non_manifold_edges,
        show(
            r.non_manifold_edges
                .iter()
                .map(|e| format!("{}-{}", e[0], e[1]))
                .collect(),
            c.non_manifold_edges
        )
    );
    if c.unknown_vertices + c.unknown_edges > 0 {
        println!(
            "  undecided (d >= 4)  {} vertices, {} edges",
            c.unknown_vertices, c.unknown_edges
        );
    }
    match (r.orientable, c.cells_to_flip, r.orientation_conflict) {
        (Some(true), Some(f), _) => {
            println!("  orientable          yes ({f} cells to flip for a consistent orientation)")
        }
        (Some(false), _, Some((a, b))) => {
            println!("  orientable          no (cells {a} and {b} cannot agree)")
        }
        _ => println!("  orientable          undefined (a (d-1)-face in more than two top cells)"),
    }
}

/// The JSON object of `starplex stellar --json` before the `split` and `timings` keys (shared
/// with `starplex-mpi stellar`, whose rank 0 fills the same statistics over all ranks).
///
/// ```
/// use starplex::stellar::{StellarOptions, StellarTree};
/// # use starplex::complex::{ComplexBuilder, BuildOptions};
/// # use starplex::cell::CellKind;
/// # let mut b = ComplexBuilder::new(2).unwrap();
/// # for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]] { b.push_vertex(&p).unwrap(); }
/// # b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// # let k = b.build(&BuildOptions::default()).unwrap().0;
/// let t = StellarTree::build(&k, &StellarOptions::default()).unwrap();
/// let v = starplex_cli::report::stellar_stats_json(&t.stats());
/// assert_eq!(v["n_leaves"], 1);
/// starplex_cli::report::print_stellar_stats(&t.stats());
/// ```
pub fn stellar_stats_json(s: &StellarStats) -> Value {
    let enc =
        |e: &starplex::stellar::stats::EncodingStorage| json!({"refs": e.refs, "bytes": e.bytes});
    json!({
        "n_nodes": s.n_nodes,
        "n_leaves": s.n_leaves,
        "kv": s.kv,
        "n_vertices": s.n_vertices,
        "n_top_cells": s.n_top_cells,
        "max_depth": s.max_depth,
        "chi": s.chi,
        "mu": s.mu,
        "leaf_max_vertices": s.leaf_max_vertices,
        "leaf_mean_vertices": s.leaf_mean_vertices,
        "leaf_max_cells": s.leaf_max_cells,
        "leaf_mean_cells": s.leaf_mean_cells,
        "storage": {
            "base_complex": {"refs": s.storage.base_refs, "bytes": s.storage.base_bytes},
            "explicit": enc(&s.storage.explicit),
            "vertex_compressed": enc(&s.storage.vertex_compressed),
            "compressed": enc(&s.storage.compressed),
            "in_memory_bytes": s.storage.in_memory_bytes,
        },
    })
}

/// Prints the human statistics lines of `starplex stellar`. Example: [`stellar_stats_json`].
pub fn print_stellar_stats(s: &StellarStats) {
    let mb = |b: u64| b as f64 / 1e6;
    println!(
        "  tree                {} nodes, {} leaves, depth {}, k_V {}",
        s.n_nodes, s.n_leaves, s.max_depth, s.kv
    );
    println!(
        "  leaves              vertices max {} mean {:.1}; top cells max {} mean {:.1}",
        s.leaf_max_vertices, s.leaf_mean_vertices, s.leaf_max_cells, s.leaf_mean_cells
    );
    println!("  chi / mu            {:.3} / {:.3}", s.chi, s.mu);
    let st = &s.storage;
    println!(
        "  storage (MB)        base complex {:.2}; explicit {:.2}, vertex-compressed {:.2}, compressed {:.2} (in memory {:.2})",
        mb(st.base_bytes),
        mb(st.explicit.bytes),
        mb(st.vertex_compressed.bytes),
        mb(st.compressed.bytes),
        mb(st.in_memory_bytes)
    );
}

/// A property `validate --fail-on` can fail on.
///
/// ```
/// use starplex_cli::report::Defect;
/// let w = Defect::wanted(true, &[Defect::Boundary]);
/// assert_eq!(w, vec![Defect::Boundary, Defect::NonManifold, Defect::NonPure, Defect::NonOrientable, Defect::Isolated]);
/// ```
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum Defect {
    /// Non-manifold vertices or edges, or faces in more than two top cells.
    NonManifold,
    /// Lower-dimensional top cells.
    NonPure,
    /// Not orientable.
    NonOrientable,
    /// Isolated vertices.
    Isolated,
    /// Boundary faces.
    Boundary,
    /// More than one connected component.
    Disconnected,
    /// Links not classified (d >= 4).
    Undecided,
}

impl Defect {
    /// The defects `--fail-on LIST` asks for, plus what `--check` stands for (non-manifold,
    /// non-pure, non-orientable, isolated) when `check`. Example: [`Defect`].
    pub fn wanted(check: bool, fail_on: &[Defect]) -> Vec<Defect> {
        let mut wanted = fail_on.to_vec();
        if check {
            for d in [
                Defect::NonManifold,
                Defect::NonPure,
                Defect::NonOrientable,
                Defect::Isolated,
            ] {
                if !wanted.contains(&d) {
                    wanted.push(d);
                }
            }
        }
        wanted
    }
}

/// The defects of `r` among `wanted`, each with its count, in words.
///
/// ```
/// use starplex_cli::report::{defects_found, Defect};
/// let k = starplex::generate::kuhn_grid(&[2, 2]).unwrap();
/// let r = starplex::algo::validate::validate(&starplex::topo::naive::VtIndex::new(&k));
/// assert_eq!(defects_found(&r, &[Defect::Boundary]), vec!["8 boundary faces".to_string()]);
/// assert!(defects_found(&r, &[Defect::NonManifold]).is_empty());
/// ```
pub fn defects_found(r: &ValidationReport, wanted: &[Defect]) -> Vec<String> {
    defects_found_counted(r, &ListCounts::of(r), wanted)
}

/// [`defects_found`] of a report whose lists may be cut, with their complete counts `c`.
///
/// ```
/// use starplex_cli::report::{defects_found_counted, Defect, ListCounts};
/// let k = starplex::generate::kuhn_grid(&[2, 2]).unwrap();
/// let mut r = starplex::algo::validate::validate(&starplex::topo::naive::VtIndex::new(&k));
/// let c = ListCounts::of(&r);
/// r.boundary_faces.clear();
/// assert_eq!(defects_found_counted(&r, &c, &[Defect::Boundary]), vec!["8 boundary faces".to_string()]);
/// ```
pub fn defects_found_counted(
    r: &ValidationReport,
    c: &ListCounts,
    wanted: &[Defect],
) -> Vec<String> {
    let mut out = Vec::new();
    for &d in wanted {
        let found = match d {
            Defect::NonManifold => {
                let (v, e, f) = (
                    c.non_manifold_vertices,
                    c.non_manifold_edges,
                    c.faces_in_more_than_two_cells,
                );
                (v + e + f > 0).then(|| {
                    format!("{v} non-manifold vertices, {e} non-manifold edges, {f} faces in more than two top cells")
                })
            }
            Defect::NonPure => (c.lower_dimensional_cells > 0).then(|| {
                format!(
                    "{} lower-dimensional top cells (not pure)",
                    c.lower_dimensional_cells
                )
            }),
            Defect::NonOrientable => {
                (r.orientable == Some(false)).then(|| "not orientable".to_string())
            }
            Defect::Isolated => (c.isolated_vertices > 0)
                .then(|| format!("{} isolated vertices", c.isolated_vertices)),
            Defect::Boundary => {
                (c.boundary_faces > 0).then(|| format!("{} boundary faces", c.boundary_faces))
            }
            Defect::Disconnected => (r.n_connected_components > 1)
                .then(|| format!("{} connected components", r.n_connected_components)),
            Defect::Undecided => {
                let (v, e) = (c.unknown_vertices, c.unknown_edges);
                (v + e > 0).then(|| format!("{v} vertices and {e} edges not classified"))
            }
        };
        out.extend(found);
    }
    out
}

/// The JSON object of `starplex homology --json` before the `timings` key (shared with
/// `starplex-mpi homology`): field, Betti numbers, Euler characteristic, critical cells,
/// `betti_z2` over Z/2, torsion over Z (as strings: they can exceed 2^53), components when
/// computed.
///
/// ```
/// use starplex::algo::homology::{homology_indexed, Field, HomologyOptions};
/// let k = starplex::generate::kuhn_grid(&[2, 2]).unwrap();
/// let h = homology_indexed(&k, &HomologyOptions { field: Field::Z, ..Default::default() }).unwrap();
/// let v = starplex_cli::report::homology_json(&h);
/// assert_eq!((v["betti"].clone(), v["torsion"].clone()), (serde_json::json!([1, 0, 0]), serde_json::json!([[], [], []])));
/// ```
pub fn homology_json(h: &starplex::algo::homology::Homology) -> Value {
    use starplex::algo::homology::Field;
    let mut v = json!({
        "field": h.field.to_string(),
        "betti": h.betti,
        "euler_characteristic": h.euler_characteristic(),
        "critical_cells": h.critical,
    });
    if h.field == Field::Z2 {
        v["betti_z2"] = json!(h.betti);
    }
    if h.field == Field::Z {
        v["torsion"] = json!(h
            .torsion
            .iter()
            .map(|t| t.iter().map(|x| x.to_string()).collect::<Vec<_>>())
            .collect::<Vec<_>>());
    }
    if let Some(comps) = &h.components {
        v["components"] = Value::Array(
            comps
                .iter()
                .map(|c| {
                    json!({
                        "first_vertex": c.first_vertex,
                        "betti": c.betti,
                        "torsion": c.torsion.iter().map(|t| t.iter().map(|x| x.to_string()).collect::<Vec<_>>()).collect::<Vec<_>>(),
                        "surface": c.surface.map(|s| json!({
                            "orientable": s.orientable,
                            "genus": s.genus,
                            "boundary_loops": s.boundary_loops,
                            "euler_characteristic": s.euler_characteristic,
                            "summary": s.to_string(),
                        })),
                    })
                })
                .collect(),
        );
    }
    v
}

/// The `before` / `after` objects of `simplify --json` (shared by `starplex simplify` and
/// `starplex-mpi simplify`).
///
/// ```
/// let s = starplex::algo::simplify::summary(&starplex::generate::kuhn_grid(&[1, 1]).unwrap());
/// let v = starplex_cli::report::topology_json(&s);
/// assert_eq!((v["f_vector"].clone(), v["boundary_faces"].clone()), (serde_json::json!([4, 5, 2]), serde_json::json!(4)));
/// ```
pub fn topology_json(s: &starplex::algo::simplify::TopologySummary) -> Value {
    json!({
        "n_vertices": s.n_vertices,
        "n_cells": s.n_cells,
        "f_vector": s.f_vector,
        "euler_characteristic": s.euler_characteristic,
        "betti_z2": s.betti,
        "non_manifold_vertices": s.non_manifold_vertices,
        "non_manifold_edges": s.non_manifold_edges,
        "boundary_faces": s.boundary_faces,
    })
}

/// `simplify`'s `topology_kept`: the same Betti numbers and Euler characteristic, and no more
/// non-manifold vertices or edges than before.
///
/// ```
/// let s = starplex::algo::simplify::summary(&starplex::generate::kuhn_grid(&[1, 1]).unwrap());
/// assert!(starplex_cli::report::topology_kept(&s, &s));
/// let mut t = s.clone();
/// t.non_manifold_edges += 1;
/// assert!(!starplex_cli::report::topology_kept(&s, &t));
/// ```
pub fn topology_kept(
    before: &starplex::algo::simplify::TopologySummary,
    after: &starplex::algo::simplify::TopologySummary,
) -> bool {
    before.betti == after.betti
        && before.euler_characteristic == after.euler_characteristic
        && after.non_manifold_vertices <= before.non_manifold_vertices
        && after.non_manifold_edges <= before.non_manifold_edges
}

/// A value of the topology summary as a person reads it: `[1, 0, 0]`, `-4`, or why it is
/// missing (over the counting budget).
fn shown<T: std::fmt::Debug>(v: &Option<T>) -> String {
    match v {
        Some(x) => format!("{x:?}"),
        None => "not computed (over the budget)".to_string(),
    }
}

/// The human lines of `simplify` for the topology before and after.
///
/// ```
/// let s = starplex::algo::simplify::summary(&starplex::generate::kuhn_grid(&[1, 1]).unwrap());
/// starplex_cli::report::print_topology_change(&s, &s);
/// ```
pub fn print_topology_change(
    b: &starplex::algo::simplify::TopologySummary,
    f: &starplex::algo::simplify::TopologySummary,
) {
    println!(
        "  f-vector            {} -> {}",
        shown(&b.f_vector),
        shown(&f.f_vector)
    );
    println!(
        "  Euler char.         {} -> {}",
        shown(&b.euler_characteristic),
        shown(&f.euler_characteristic)
    );
    println!(
        "  Betti (Z/2)         {} -> {}",
        shown(&b.betti),
        shown(&f.betti)
    );
    println!(
        "  non-manifold        {} vertices, {} edges -> {} vertices, {} edges",
        b.non_manifold_vertices,
        b.non_manifold_edges,
        f.non_manifold_vertices,
        f.non_manifold_edges
    );
    println!(
        "  boundary faces      {} -> {}",
        b.boundary_faces, f.boundary_faces
    );
}
