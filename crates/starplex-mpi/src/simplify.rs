//! `simplify`: edge contraction distributed over the ranks, in rounds, with the library's
//! [`simplify`] (homology mode or QEM, the link condition and every geometric check) run
//! unchanged on each rank's local complex.
//!
//! **What a rank may change.** A vertex is *interior* to its rank when the rank owns it and every
//! vertex of every cell of its star too. No other rank holds a cell of an interior vertex's star
//! (cells go only to the owners of their vertices), and the rank holds the full star of every
//! vertex it owns. So each rank locks every local vertex that is not interior (locked vertices
//! are neither removed nor moved, `SimplifyOptions::keep_vertices`): every contraction removes an
//! interior vertex into an owned neighbour, whose star, link and quadric are complete locally, so
//! the link condition and the geometric tests decide exactly as they would on the whole complex,
//! and the cells it changes are held by this rank alone.
//!
//! **Rounds.** Vertices near the boundaries between ranks are locked in a round, so the next
//! round splits the complex again with every boundary moved to the middle of a rank
//! (`dist::split`, shifted every other round) and goes on from the previous round's output
//! (written in parallel to a temporary `.spb` beside the output). Rounds end when one makes no
//! contraction (after the second), when the target is reached, or after `--rounds`. A
//! simplified complex has long cells, whose stars reach across ranks, so the locked share grows
//! round after round: once a round leaves at most `--gather-below` top cells (default 2M), the
//! last round gives the whole rest to rank 0, which simplifies it with no lock. One rank needs
//! one round: the result is then the single-process `starplex simplify` result (up to the
//! order of the cells).
//!
//! **Targets.** `--ratio` and `--faces` give a global number of top cells, `--vertices` one of
//! vertices; each round every rank aims at its share, proportional to the top cells (vertices)
//! it owns. `--max-error` bounds each QEM
//! contraction, which is a local decision.
//!
//! **Output.** Each rank writes the cells it owns (those whose smallest vertex, by global id, it
//! owns) and the surviving vertices it owns, numbered rank after rank in increasing input id,
//! into one `.spb` ([`crate::write`]).
//!
//! **Attributes.** The `.spb` attribute columns are fixed-width, so each rank reads the values
//! of the vertices and cells it holds by global id ([`Spb::attributes_of`]); the library carries
//! them as `starplex simplify` does (a surviving vertex keeps its values, a cell has those of
//! the input cell it is the image of), every round's file holds them, and each rank writes its
//! part of every column. Labels are kept as `starplex simplify` keeps them (`--keep-labels`, the
//! default `gmsh:physical` / `medit:ref`, `--ignore-labels`): whether a vertex is on a label
//! interface is decided on its full star, which the rank holds for the vertices it may move.
//! `--keep-vertex-attribute NAME` keeps the vertices of a non-zero value, read likewise.
use std::path::{Path, PathBuf};
use std::time::Instant;

use fixedbitset::FixedBitSet;
use rustc_hash::FxHashMap;
use serde_json::json;
use starplex::algo::simplify::{
    default_label_attribute, label_interface_vertices, TopologySummary,
};
use starplex::algo::simplify::{simplify, Mode, SimplifyOptions, Target};
use starplex::attr::{AttrTarget, AttrValues, Attribute};
use starplex::cell::CellKind;
use starplex::io::binary::SpbAttr;

use mpi::traits::Communicator;

use crate::comm::{self, agree, Failure, World};
use crate::dist::{self, Local, Spb, SplitKind};
use crate::write::{self, Part};

/// Options of the verb.
pub struct SimplifyArgs<'a> {
    /// The output `.spb`.
    pub out: &'a Path,
    /// `None`: QEM for a pure triangle mesh in 2D/3D or a pure tetrahedral mesh in 3D, homology
    /// otherwise (as `starplex simplify`).
    pub mode: Option<Mode>,
    /// Target share of the input's top cells.
    pub ratio: Option<f64>,
    /// Target number of top cells.
    pub faces: Option<u64>,
    /// Target number of vertices.
    pub vertices: Option<u64>,
    /// QEM: largest quadric error of a contraction.
    pub max_error: Option<f64>,
    /// Homology mode: the extended link condition (a manifold stays one).
    pub keep_manifold: bool,
    /// QEM: boundary vertices neither move nor disappear.
    pub lock_boundary: bool,
    /// A file of input vertex ids that neither move nor disappear (as `starplex simplify
    /// --keep-vertices`).
    pub keep_vertices: Option<&'a Path>,
    /// Keep the regions of this cell attribute (as `starplex simplify --keep-labels`).
    pub keep_labels: Option<&'a str>,
    /// Do not keep the default label attribute's regions.
    pub ignore_labels: bool,
    /// Vertices whose value of this vertex attribute is not 0 neither move nor disappear.
    pub keep_vertex_attribute: Option<&'a str>,
    /// Carry the input's attribute columns to the output (off when only the topology of the
    /// output is wanted).
    pub attributes: bool,
    /// The topology before and after (as `starplex simplify` without `--no-report`).
    pub report: bool,
    /// At most this many rounds.
    pub max_rounds: u32,
    /// When a round leaves at most this many top cells, the last round runs on rank 0 alone
    /// (0: never).
    pub gather_below: u64,
    /// One JSON object.
    pub json: bool,
}

/// The name of the column that carries each local vertex's id through the library's
/// simplification (vertex columns follow the surviving vertices).
const LOCAL_ID: &str = "starplex-mpi:local-id";

/// One round on one rank.
struct RoundOut {
    part: Part,
    contractions: u64,
    /// QEM: the largest quadric error of this rank's contractions, and their sum.
    errors: (f64, f64),
    owned_tops_after: u64,
    owned_vertices_after: u64,
    locked: u64,
    /// The output ids of the kept vertices this rank owns: (index in the kept list, new id).
    kept_new: Vec<(usize, u32)>,
    /// Owned vertices the user keeps (listed or by attribute).
    user_kept: u64,
    /// Owned vertices kept by the user or on a label interface (what `starplex simplify`
    /// reports as locked).
    fixed: u64,
}

/// What the user asked to keep, resolved against the input's attribute columns.
struct Keep<'a> {
    /// The kept vertices, in the numbering of the round's input (sorted).
    listed: &'a [u32],
    /// The cell attribute whose regions are kept.
    labels: Option<&'a str>,
    /// The vertex attribute whose non-zero vertices are kept.
    by_attribute: Option<&'a str>,
}

/// The mode `starplex simplify` picks, from the blocks of the file.
fn default_mode(f: &Spb) -> Mode {
    let dims: std::collections::BTreeSet<usize> =
        f.h.blocks.iter().map(|&(k, _, _)| k.dim()).collect();
    let simplicial = f.h.blocks.iter().all(|&(k, _, _)| k.is_simplex());
    match (dims.iter().next(), dims.len(), f.h.ambient_dim) {
        (Some(2), 1, 2 | 3) | (Some(3), 1, 3) if simplicial => Mode::Qem,
        _ => Mode::Homology,
    }
}

/// Top cells this rank owns: owned cells and owned isolated vertices.
fn owned_tops(l: &Local) -> u64 {
    let used = l.k.used_vertices();
    l.n_owned_cells + l.owned.ones().filter(|&v| !used.contains(v)).count() as u64
}

/// The local vertices this rank must not remove nor move: every vertex that is not interior.
fn locked(l: &Local) -> Vec<u32> {
    let n = l.vertex_gid.len();
    let mut near = FixedBitSet::with_capacity(n);
    for c in l.k.cells() {
        if c.vertices.iter().any(|&v| !l.owned.contains(v as usize)) {
            for &v in c.vertices {
                near.insert(v as usize);
            }
        }
    }
    (0..n)
        .filter(|&v| !l.owned.contains(v) || near.contains(v))
        .map(|v| v as u32)
        .collect()
}

/// This rank's share of a global target `t` (collective), proportional to the `mine` items it
/// owns, at most `mine`: the shares of the ranks add up to `t` exactly (when `t` is at most
/// the total), each the difference of two rounded-down prefix proportions.
fn share(w: &World, mine: u64, t: u64) -> u64 {
    let all = comm::all_gather(w, &[mine]);
    let total: u64 = all.iter().sum();
    if total == 0 {
        return 0;
    }
    let before: u64 = all[..w.rank() as usize].iter().sum();
    let at = |x: u64| (u128::from(t) * u128::from(x) / u128::from(total)) as u64;
    (at(before + mine) - at(before)).min(mine)
}

/// Simplifies this rank's local complex and keeps what it owns, numbered for the output.
fn round(
    w: &World,
    l: &mut Local,
    mode: Mode,
    a: &SimplifyArgs,
    (faces, vertices): (Option<u64>, Option<u64>),
    user: &Keep,
    cols: &[SpbAttr],
) -> Result<RoundOut, Failure> {
    let (rank, p) = (w.rank() as usize, w.size() as usize);
    let kept = user.listed;
    let n = l.vertex_gid.len();
    let mut keep = locked(l);
    let n_locked = keep.len() as u64;
    // the vertices the user keeps (global ids of this round's input, sorted), where held
    // here, and those of a non-zero value of the vertex attribute
    let mut users: Vec<u32> = kept
        .iter()
        .filter_map(|g| l.vertex_gid.binary_search(g).ok())
        .map(|i| i as u32)
        .collect();
    if let Some(col) = user
        .by_attribute
        .and_then(|name| l.k.attributes().get(AttrTarget::Vertex, name))
    {
        let c = col.components;
        users.extend(
            (0..n)
                .filter(|&v| (v * c..(v + 1) * c).any(|i| col.values.get_f64(i) != 0.0))
                .map(|v| v as u32),
        );
    }
    users.sort_unstable();
    users.dedup();
    let owned_count = |vs: &[u32]| vs.iter().filter(|&&v| l.owned.contains(v as usize)).count();
    let user_kept = owned_count(&users) as u64;
    // with the label interfaces (decided on whole stars for the owned vertices)
    let fixed = match user.labels {
        Some(name) => {
            let mut f = agree(
                w,
                label_interface_vertices(&l.k, name).map_err(|e| e.to_string()),
            )?;
            f.extend_from_slice(&users);
            f.sort_unstable();
            f.dedup();
            owned_count(&f) as u64
        }
        None => user_kept,
    };
    keep.extend(users);
    keep.sort_unstable();
    keep.dedup();
    let mine = owned_tops(l);
    let local_tops = (l.k.n_cells() + l.k.n_isolated_vertices()) as u64;
    // this rank's share of the global target, in local top cells (ghosts stay as they are)
    let local_target = faces.map(|t| (local_tops - mine + share(w, mine, t)) as usize);
    // and of the global vertex target, in local vertices
    let mine_v = l.owned.count_ones(..) as u64;
    let local_vertices = vertices.map(|t| (n as u64 - mine_v + share(w, mine_v, t)) as usize);
    // the file's columns (read with the local complex) and each vertex's local id
    let mut attrs = l.k.attributes().clone();
    attrs
        .vertex
        .push(Attribute::int(LOCAL_ID, 1, (0..n as i64).collect()));
    agree(w, l.k.set_attributes(attrs).map_err(|e| e.to_string()))?;
    let opts = SimplifyOptions {
        mode: Some(mode),
        target: Target {
            faces: local_target,
            vertices: local_vertices,
            max_error: a.max_error,
            ..Default::default()
        },
        lock_boundary: a.lock_boundary,
        keep_manifold: a.keep_manifold,
        keep_vertices: keep,
        keep_labels: user.labels.map(str::to_string),
        ..Default::default()
    };
    let done = if l.k.n_cells() == 0 {
        // nothing to simplify here (an empty rank): the vertices as they are
        Ok(None)
    } else {
        simplify(&l.k, &opts).map(Some).map_err(|e| e.to_string())
    };
    let done = agree(w, done)?;
    let (out, contractions, errors) = match done {
        Some((out, r)) => {
            let n = r.n_contractions as f64;
            let errors = (r.max_error.unwrap_or(0.0), r.mean_error.unwrap_or(0.0) * n);
            (out, r.n_contractions, errors)
        }
        None => (l.k.clone(), 0, (0.0, 0.0)),
    };
    let local_of: Vec<u32> = match out.attributes().vertex.iter().find(|c| c.name == LOCAL_ID) {
        Some(Attribute {
            values: AttrValues::Int(v),
            ..
        }) => v.iter().map(|&x| x as u32).collect(),
        _ => (0..out.n_vertices() as u32).collect(),
    };
    // owned surviving vertices, in increasing global id (local ids increase with global ids)
    let owned_out: Vec<u32> = (0..out.n_vertices() as u32)
        .filter(|&i| l.owned.contains(local_of[i as usize] as usize))
        .collect();
    let counts = comm::all_gather(w, &[owned_out.len() as u64]);
    let first: u64 = counts[..rank].iter().sum();
    let mut new_id = vec![u32::MAX; out.n_vertices()];
    for (j, &i) in owned_out.iter().enumerate() {
        new_id[i as usize] = (first + j as u64) as u32;
    }
    let gid = |i: u32| l.vertex_gid[local_of[i as usize] as usize];
    let owner = |i: u32| l.vertex_owner[local_of[i as usize] as usize] as usize;
    // the cells this rank writes: those whose smallest vertex (global id) it owns
    let owns = |c: &[u32]| {
        let m = c.iter().copied().min_by_key(|&i| gid(i)).unwrap_or(0);
        owner(m) == rank
    };
    // new ids of the ghost vertices of those cells, from their owners
    let mut ask: Vec<Vec<u32>> = vec![Vec::new(); p];
    for c in out.cells() {
        if owns(c.vertices) {
            for &i in c.vertices {
                if owner(i) != rank {
                    ask[owner(i)].push(gid(i));
                }
            }
        }
    }
    for v in &mut ask {
        v.sort_unstable();
        v.dedup();
    }
    let asked = comm::exchange(w, ask.clone())?;
    let owned_gids: Vec<u32> = owned_out.iter().map(|&i| gid(i)).collect();
    let mut missing = None;
    let answers: Vec<Vec<u32>> = asked
        .parts()
        .map(|q| {
            q.iter()
                .map(|g| match owned_gids.binary_search(g) {
                    Ok(j) => (first + j as u64) as u32,
                    Err(_) => {
                        missing.get_or_insert(*g);
                        u32::MAX
                    }
                })
                .collect()
        })
        .collect();
    agree(
        w,
        missing.map_or(Ok(()), |g| {
            Err(format!(
                "internal error: vertex {g} is used by another rank's cell but did not survive here"
            ))
        }),
    )?;
    let replies = comm::exchange(w, answers)?;
    let mut ghost: FxHashMap<u32, u32> = FxHashMap::default();
    for (q, r) in ask.iter().zip(replies.parts()) {
        ghost.extend(q.iter().copied().zip(r.iter().copied()));
    }
    let mut blocks: Vec<(CellKind, Vec<u32>)> = Vec::new();
    // the output cells of each block, for their attribute values
    let mut block_cells: Vec<Vec<usize>> = Vec::new();
    let mut owned_cells = 0u64;
    for (j, c) in out.cells().enumerate() {
        if !owns(c.vertices) {
            continue;
        }
        owned_cells += 1;
        let at = match blocks.iter().position(|(k, _)| *k == c.kind) {
            Some(i) => i,
            None => {
                blocks.push((c.kind, Vec::new()));
                block_cells.push(Vec::new());
                blocks.len() - 1
            }
        };
        block_cells[at].push(j);
        let dst = &mut blocks[at].1;
        for &i in c.vertices {
            dst.push(if owner(i) == rank {
                new_id[i as usize]
            } else {
                ghost[&gid(i)]
            });
        }
    }
    let d = out.ambient_dim();
    let mut coords = Vec::with_capacity(owned_out.len() * d);
    for &i in &owned_out {
        coords.extend_from_slice(out.point(starplex::ids::VertexId(i)));
    }
    // the file's columns, carried by the library to the surviving vertices and to the images
    // of the cells: this rank's vertices, then its cells block after block
    let owned_cells_in_order: Vec<usize> = block_cells.concat();
    let values = agree(
        w,
        cols.iter()
            .map(|e| {
                let (col, items): (_, Box<dyn Iterator<Item = usize>>) = match e.target {
                    AttrTarget::Vertex => (
                        out.attributes().get(AttrTarget::Vertex, &e.name),
                        Box::new(owned_out.iter().map(|&i| i as usize)),
                    ),
                    AttrTarget::Cell => (
                        out.attributes().get(AttrTarget::Cell, &e.name),
                        Box::new(owned_cells_in_order.iter().copied()),
                    ),
                };
                let col = col.ok_or_else(|| {
                    format!("internal error: the attribute {} was not carried", e.name)
                })?;
                Ok(write::words(col, items))
            })
            .collect::<Result<Vec<Vec<u64>>, String>>(),
    )?;
    // where the kept vertices this rank owns go in the output (they all survive)
    let mut kept_new = Vec::new();
    for (x, g) in kept.iter().enumerate() {
        if let Ok(i) = l.vertex_gid.binary_search(g)
            && l.owned.contains(i)
        {
            match owned_gids.binary_search(g) {
                Ok(j) => kept_new.push((x, (first + j as u64) as u32)),
                Err(_) => {
                    return Err(Failure(format!(
                        "internal error: kept vertex {g} did not survive the round"
                    )))
                }
            }
        }
    }
    let used = out.used_vertices();
    let isolated = owned_out
        .iter()
        .filter(|&&i| !used.contains(i as usize))
        .count() as u64;
    Ok(RoundOut {
        part: Part {
            coords,
            blocks,
            values,
        },
        contractions,
        errors,
        owned_tops_after: owned_cells + isolated,
        owned_vertices_after: owned_out.len() as u64,
        locked: n_locked,
        kept_new,
        user_kept,
        fixed,
    })
}

/// Removes a temporary round file (rank 0).
fn remove(w: &World, path: Option<PathBuf>) {
    if let (Some(p), 0) = (path, w.rank()) {
        let _ = std::fs::remove_file(p);
    }
}

/// The verb (collective).
pub fn run(w: &World, a: &SimplifyArgs, file: &Path) -> Result<(), Failure> {
    let o = rounds(w, a, file)?;
    if w.rank() != 0 {
        return Ok(());
    }
    let v = o.json(file, a.out, w.size() as u32);
    if a.json {
        crate::print_json(&v);
    } else {
        println!("{} -> {}", file.display(), a.out.display());
        println!(
            "  mode                {} ({} ranks)",
            o.mode.name(),
            w.size()
        );
        println!(
            "  vertices            {} -> {}",
            o.before.0, o.written.n_vertices
        );
        println!(
            "  top cells           {} -> {}",
            o.before.1, o.written.n_cells
        );
        println!(
            "  contractions        {} in {} rounds",
            o.contractions,
            o.rows.len()
        );
        match (&o.labels_kept, o.labels_available.is_empty()) {
            (Some(l), _) => println!(
                "  labels              {l} kept ({} interface/kept vertices locked)",
                o.locked_vertices
            ),
            (None, false) => println!(
                "  labels              not kept (cell attributes: {})",
                o.labels_available.join(", ")
            ),
            (None, true) => {}
        }
        if o.labels_kept.is_none() && o.locked_vertices > 0 {
            println!("  kept vertices       {}", o.locked_vertices);
        }
        if let Some((m, e)) = o.errors {
            println!("  quadric error       max {m:.3e}, mean {e:.3e}");
        }
        if let (Some(b), Some(f)) = (&o.topology_before, &o.topology_after) {
            starplex_cli::report::print_topology_change(b, f);
        }
        println!("  time                {:.3} s", o.time_s);
    }
    Ok(())
}

/// What the rounds did.
pub struct Outcome {
    /// The mode that ran.
    pub mode: Mode,
    /// Vertices and top cells of the input.
    pub before: (u64, u64),
    /// The output file's counts.
    pub written: write::Written,
    /// Edges contracted in all.
    pub contractions: u64,
    /// The global target of top cells, if any.
    pub goal: Option<u64>,
    /// The global target of vertices, if any.
    pub goal_vertices: Option<u64>,
    /// One JSON object per round.
    pub rows: Vec<serde_json::Value>,
    /// The cell attribute whose regions were kept.
    pub labels_kept: Option<String>,
    /// The input's cell attributes.
    pub labels_available: Vec<String>,
    /// QEM: the largest and the mean quadric error of the contractions.
    pub errors: Option<(f64, f64)>,
    /// The topology of the input and of the output (rank 0, with the report).
    pub topology_before: Option<TopologySummary>,
    /// See `topology_before`.
    pub topology_after: Option<TopologySummary>,
    /// Seconds of the topology report.
    pub report_s: f64,
    /// Input vertices kept by the user or on a label interface.
    pub locked_vertices: u64,
    /// The attribute columns carried.
    pub attributes: Vec<(AttrTarget, String)>,
    /// Seconds (the slowest rank's view: every round ends collectively), the report aside.
    pub time_s: f64,
}

impl Outcome {
    fn names(&self, t: AttrTarget) -> Vec<&str> {
        self.attributes
            .iter()
            .filter(|(x, _)| *x == t)
            .map(|(_, n)| n.as_str())
            .collect()
    }

    /// The report of `simplify --json`.
    pub fn json(&self, file: &Path, out: &Path, ranks: u32) -> serde_json::Value {
        use starplex_cli::report::{topology_json, topology_kept};
        let mut v = json!({
            "input": file.display().to_string(),
            "output": out.display().to_string(),
            "mode": self.mode.name(),
            "ranks": ranks,
            "target_faces": self.goal,
            "target_vertices": self.goal_vertices,
            "n_contractions": self.contractions,
            "rounds": self.rows.len(),
            "per_round": self.rows,
            "labels_kept": self.labels_kept,
            "labels_available": self.labels_available,
            "locked_vertices": self.locked_vertices,
            "attributes": {
                "vertex": self.names(AttrTarget::Vertex),
                "cell": self.names(AttrTarget::Cell),
            },
            "vertices": [self.before.0, self.written.n_vertices],
            "cells": [self.before.1, self.written.n_cells],
            "bytes": self.written.bytes,
            "time_s": self.time_s,
            "report_time_s": self.report_s,
            "before": self.topology_before.as_ref().map(topology_json),
            "after": self.topology_after.as_ref().map(topology_json),
            // the sampled Hausdorff estimate compares the whole meshes: not distributed
            "hausdorff": null,
        });
        if let Some((m, e)) = self.errors {
            v["max_error"] = json!(m);
            v["mean_error"] = json!(e);
        }
        if let (Some(b), Some(f)) = (&self.topology_before, &self.topology_after) {
            v["topology_kept"] = json!(topology_kept(b, f));
        }
        v
    }
}

/// The rounds (collective): reads `file`, writes `a.out`.
pub fn rounds(w: &World, a: &SimplifyArgs, file: &Path) -> Result<Outcome, Failure> {
    let t0 = Instant::now();
    let target = agree(w, write::target_of(a.out))?;
    let p = w.size() as u32;
    let mut input = file.to_path_buf();
    let mut temp: Option<PathBuf> = None;
    let mut rows = Vec::new();
    let (mut before, mut goal) = ((0u64, 0u64), None);
    let mut total = 0u64;
    let (mut tops_now, mut vertices_now) = (0u64, 0u64);
    let mut r = 0u32;
    let mut kind = SplitKind::Plain;
    // the kept vertices, in the numbering of each round's input (sorted)
    let mut kept: Vec<u32> = Vec::new();
    // the input's attribute columns (every round's file has them), the label kept
    let mut cols: Vec<SpbAttr> = Vec::new();
    let (mode, labels): (Mode, Option<String>);
    let (mut topology_before, mut report_s) = (None, 0.0);
    let (mut max_error, mut error_sum) = (0.0f64, 0.0f64);
    let mut locked_vertices = 0u64;
    // what the header and the options decide, before any cell is read; then the topology
    // before (its own read, so that no two local complexes are held at once)
    {
        let f0 = agree(w, Spb::open(file))?;
        if let Some(&(k, _, _)) = f0.h.blocks.iter().find(|&&(k, _, _)| !k.is_simplex()) {
            return Err(Failure(format!(
                "{}: the complex has {} cells; simplify contracts edges of simplicial complexes only: triangulate first (starplex convert --triangulate {} triangulated.spb)",
                file.display(),
                k.type_name(),
                file.display()
            )));
        }
        mode = a.mode.unwrap_or_else(|| default_mode(&f0));
        if mode == Mode::Homology && a.max_error.is_some() {
            return Err(Failure(
                "--max-error is a quadric error: it needs --mode qem".into(),
            ));
        }
        if let Some(x) = a.ratio.filter(|x| !(0.0..=1.0).contains(x)) {
            return Err(Failure(format!("--ratio {x}: it must be between 0 and 1")));
        }
        if let Some(v) = a.vertices.filter(|&v| v > f0.h.n_vertices) {
            return Err(Failure(format!(
                "{v} vertices asked, the complex has {}",
                f0.h.n_vertices
            )));
        }
        if let Some(path) = a.keep_vertices {
            let nv = f0.h.n_vertices;
            kept = agree(
                w,
                starplex_cli::export::read_ids(path)
                    .map_err(|e| format!("--keep-vertices: {e}"))
                    .and_then(|ids| match ids.iter().find(|&&v| v as u64 >= nv) {
                        Some(v) => Err(format!(
                            "--keep-vertices {}: vertex {v} is out of range (the input has {nv} vertices, ids from 0)",
                            path.display()
                        )),
                        None => Ok(ids),
                    }),
            )?;
            kept.sort_unstable();
            kept.dedup();
        }
        if a.attributes {
            cols = f0.h.attrs.clone();
        }
        labels = agree(w, resolve_labels(a, &cols))?;
        drop(f0);
        if a.report {
            let t = Instant::now();
            topology_before = crate::summary::summary(w, file)?;
            report_s += t.elapsed().as_secs_f64();
        }
    }
    let written = loop {
        // reading a round's file back: on any error, the file goes too
        let read = (|| {
            let f = agree(w, Spb::open(&input))?;
            let split = dist::split(w, &f, kind)?;
            let mut l = dist::distribute(w, &f, &split)?;
            if a.attributes && !f.h.attrs.is_empty() {
                let a = f.attributes_of(&l.vertex_gid, &l.cell_gid);
                agree(w, l.k.set_attributes(a).map_err(|e| e.to_string()))?;
            }
            agree(w, f.check_unchanged())?;
            f.release_pages();
            Ok((f, l))
        })();
        let (f, mut l) = match read {
            Ok(x) => x,
            Err(e) => {
                remove(w, temp.take());
                return Err(e);
            }
        };
        if r == 0 {
            let tops = comm::sum(w, owned_tops(&l));
            tops_now = tops;
            before = (f.h.n_vertices, f.h.n_cells);
            let by_ratio = a.ratio.map(|x| (x * tops as f64).round() as u64);
            goal = match (a.faces, by_ratio) {
                (Some(f), Some(g)) => Some(f.max(g)),
                (f, g) => f.or(g),
            };
            if let Some(g) = goal.filter(|&g| g > tops) {
                return Err(Failure(format!(
                    "{g} faces asked, the complex has {tops} top cells"
                )));
            }
            vertices_now = f.h.n_vertices;
        }
        let d = f.h.ambient_dim;
        drop(f);
        remove(w, temp.take());
        // with several ranks, the first round stops short of the target (90 % of the way), so
        // that the next round (another split, or rank 0 alone) does the rest over the first
        // round's locked bands instead of leaving them denser than the rest
        let short = |g: Option<u64>, now: u64| match g {
            Some(g) if p > 1 && r == 0 && kind != SplitKind::Rank0 => {
                Some(g + (now.saturating_sub(g)) / 10)
            }
            g => g,
        };
        let round_goal = (short(goal, tops_now), short(a.vertices, vertices_now));
        let user = Keep {
            listed: &kept,
            labels: labels.as_deref(),
            by_attribute: a.keep_vertex_attribute,
        };
        let out = round(w, &mut l, mode, a, round_goal, &user, &cols)?;
        drop(l);
        // the kept vertices' ids in the round's output, from their owners
        if !kept.is_empty() {
            let mut at = vec![0u64; kept.len()];
            for &(x, id) in &out.kept_new {
                at[x] = u64::from(id) + 1;
            }
            let at = comm::sums(w, &at);
            comm::agree_that(
                w,
                at.iter().all(|&x| x > 0),
                "internal error: a kept vertex has no owner",
            )?;
            kept = at.iter().map(|&x| (x - 1) as u32).collect();
            kept.sort_unstable();
        }
        let contractions = comm::sum(w, out.contractions);
        max_error = max_error.max(comm::min_max(w, &[], &[out.errors.0]).1[0]);
        error_sum += comm::sum_f64(w, out.errors.1);
        let tops_after = comm::sum(w, out.owned_tops_after);
        vertices_now = comm::sum(w, out.owned_vertices_after);
        let locked = comm::sum(w, out.locked);
        let user_kept = comm::sum(w, out.user_kept);
        let fixed = comm::sum(w, out.fixed);
        if r == 0 {
            locked_vertices = fixed;
        }
        total += contractions;
        tops_now = tops_after;
        rows.push(json!({"round": r + 1, "split": format!("{kind:?}").to_lowercase(), "contractions": contractions, "top_cells": tops_after, "locked_vertices": locked, "kept_vertices": user_kept}));
        let next = if tops_after <= a.gather_below {
            SplitKind::Rank0
        } else if kind == SplitKind::Plain {
            SplitKind::Shifted
        } else {
            SplitKind::Plain
        };
        let last = p == 1
            || kind == SplitKind::Rank0
            || r + 1 >= a.max_rounds
            || (contractions == 0 && r >= 1 && next != SplitKind::Rank0)
            || goal.is_some_and(|g| tops_after <= g)
            || a.vertices.is_some_and(|g| vertices_now <= g);
        kind = next;
        let path = if last {
            target.clone()
        } else {
            write::beside(&target, &format!(".round{r}.starplex-mpi.spb"))
        };
        let written = write::write(w, &path, d, &cols, &out.part)?;
        if last {
            break written;
        }
        temp = Some(path.clone());
        input = path;
        r += 1;
    };
    let time_s = t0.elapsed().as_secs_f64() - report_s;
    let topology_after = if a.report {
        let t = Instant::now();
        let s = crate::summary::summary(w, &target)?;
        report_s += t.elapsed().as_secs_f64();
        s
    } else {
        None
    };
    Ok(Outcome {
        mode,
        before,
        written,
        contractions: total,
        goal,
        goal_vertices: a.vertices,
        rows,
        labels_kept: labels,
        labels_available: cols
            .iter()
            .filter(|c| c.target == AttrTarget::Cell)
            .map(|c| c.name.clone())
            .collect(),
        errors: (mode == Mode::Qem).then(|| {
            let mean = if total > 0 {
                error_sum / total as f64
            } else {
                0.0
            };
            (max_error, mean)
        }),
        topology_before,
        topology_after,
        report_s,
        locked_vertices,
        attributes: cols.iter().map(|c| (c.target, c.name.clone())).collect(),
        time_s,
    })
}

/// The label attribute whose regions are kept: `--keep-labels NAME` (a cell attribute of the
/// input), else the default label attribute (`gmsh:physical`, `medit:ref`) unless
/// `--ignore-labels`, as `starplex simplify` decides; `--keep-vertex-attribute` names a vertex
/// attribute.
fn resolve_labels(a: &SimplifyArgs, cols: &[SpbAttr]) -> Result<Option<String>, String> {
    let names = |t: AttrTarget| -> Vec<&str> {
        cols.iter()
            .filter(|c| c.target == t)
            .map(|c| c.name.as_str())
            .collect()
    };
    let listed = |t: AttrTarget, what: &str| {
        let n = names(t);
        if n.is_empty() {
            format!("the input has no {what} attribute")
        } else {
            format!("its {what} attributes: {}", n.join(", "))
        }
    };
    if let Some(n) = a
        .keep_vertex_attribute
        .filter(|n| !names(AttrTarget::Vertex).contains(n))
    {
        return Err(format!(
            "--keep-vertex-attribute {n}: no vertex attribute of that name ({})",
            listed(AttrTarget::Vertex, "vertex")
        ));
    }
    match (a.keep_labels, a.ignore_labels) {
        (Some(n), _) if names(AttrTarget::Cell).contains(&n) => Ok(Some(n.to_string())),
        (Some(n), _) => Err(format!(
            "--keep-labels {n}: no cell attribute of that name ({})",
            listed(AttrTarget::Cell, "cell")
        )),
        (None, true) => Ok(None),
        (None, false) => {
            let schema = starplex::attr::Attributes {
                vertex: Vec::new(),
                cell: cols
                    .iter()
                    .filter(|c| c.target == AttrTarget::Cell)
                    .map(|c| Attribute::int(c.name.clone(), 1, Vec::new()))
                    .collect(),
            };
            Ok(default_label_attribute(&schema).map(str::to_string))
        }
    }
}
