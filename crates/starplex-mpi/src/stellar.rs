//! `stellar`: every rank builds the library's Stellar tree over its local complex (owned and
//! ghost cells, renumbered locally in increasing global id; the global ids are kept beside it),
//! and rank 0 prints the statistics of `starplex stellar` summed over the ranks.
//!
//! **Ownership rule** (nothing counted twice): every vertex is owned by one rank and lies in one
//! leaf of that rank's tree. A leaf is *counted* by its rank when it holds an owned vertex or no
//! vertex at all (an empty block of the local hierarchy); a counted leaf's top cells are the cells
//! incident to its *owned* vertices (its ghost vertices' cells are counted by their owners). So
//! `chi = Σ |T_owned(leaf)| / |T|` and `mu = Σ |SRE(T_owned(leaf))| / |T|` over the counted leaves
//! of all ranks; with one rank this is exactly `starplex stellar`. Nodes, in-memory bytes and
//! held leaves are summed as they are (the ghost layer is real storage), the depth is the
//! largest.
use std::path::Path;
use std::time::Instant;

use mpi::traits::Communicator;
use serde_json::json;
use starplex::ids::VertexId;
use starplex::stellar::{sre, StellarOptions, StellarStats, StellarTree};
use starplex::topo::LocalStar;

use crate::comm::{self, agree, Failure, World};
use crate::dist::Local;

/// What one rank contributes under the ownership rule.
#[derive(Default, Debug, PartialEq)]
pub struct Owned {
    /// Counted leaves (an owned vertex, or no vertex).
    pub leaves: u64,
    /// Σ |cells incident to the owned vertices of a counted leaf|.
    pub sum_t: u64,
    /// Σ of the same lists' SRE lengths.
    pub sum_sre: u64,
    /// Most owned vertices in one leaf.
    pub max_v: u64,
    /// Most cells in one counted leaf's list.
    pub max_t: u64,
}

/// The counted leaves of `t` (built over `l.k`) under the ownership rule.
pub fn owned_stats(t: &StellarTree, l: &Local) -> Owned {
    let mut o = Owned::default();
    let (mut cells, mut enc) = (Vec::new(), Vec::new());
    t.for_each_leaf(|view| {
        cells.clear();
        let mut nv = 0u64;
        let mut any = false;
        for tv in view.owned_vertices() {
            any = true;
            if l.owned.contains(view.input_vertex(tv).index()) {
                nv += 1;
                cells.extend(view.local_star(tv).iter().map(|c| c.0));
            }
        }
        if nv == 0 && any {
            return;
        }
        cells.sort_unstable();
        cells.dedup();
        enc.clear();
        sre::encode(&cells, &mut enc);
        o.leaves += 1;
        o.sum_t += cells.len() as u64;
        o.sum_sre += enc.len() as u64;
        o.max_v = o.max_v.max(nv);
        o.max_t = o.max_t.max(cells.len() as u64);
    });
    o
}

/// Writes `PREFIX.rankR.txt`: one line `v|VT|VV` per owned vertex (global ids, increasing),
/// answered by the local tree.
fn write_vt_vv(t: &StellarTree, l: &Local, prefix: &Path, rank: i32) -> Result<(), String> {
    use std::io::Write;
    let vs: Vec<VertexId> = l.owned.ones().map(|v| VertexId(v as u32)).collect();
    let vt = t.vt_of(&vs).map_err(|e| e.to_string())?;
    let vv = t.vv_of(&vs).map_err(|e| e.to_string())?;
    let path = format!("{}.rank{rank}.txt", prefix.display());
    let file = std::fs::File::create(&path).map_err(|e| format!("{path}: {e}"))?;
    let mut out = std::io::BufWriter::new(file);
    let join = |x: Vec<u32>| {
        let mut x = x;
        x.sort_unstable();
        x.iter()
            .map(|g| g.to_string())
            .collect::<Vec<_>>()
            .join(" ")
    };
    for ((v, cs), ws) in vs.iter().zip(vt).zip(vv) {
        let cells = join(cs.iter().map(|c| l.cell_gid[c.index()]).collect());
        let verts = join(ws.iter().map(|w| l.vertex_gid[w.index()]).collect());
        writeln!(out, "{}|{cells}|{verts}", l.vertex_gid[v.index()])
            .map_err(|e| format!("{path}: {e}"))?;
    }
    out.flush().map_err(|e| format!("{path}: {e}"))
}

/// Options of the verb.
pub struct StellarArgs<'a> {
    /// Bucketing threshold (`None`: 100 up to dimension 2, 400 above, from the global dimension).
    pub kv: Option<u32>,
    /// Where the VT/VV answers of the owned vertices go (one file per rank).
    pub vt_vv_out: Option<&'a Path>,
    /// One JSON object.
    pub json: bool,
}

/// The verb (collective).
pub fn run(
    w: &World,
    a: &StellarArgs,
    file: &Path,
    f: &crate::dist::Spb,
    l: &Local,
    read_s: f64,
) -> Result<(), Failure> {
    let gdim = f.dim();
    let kv = a.kv.unwrap_or(if gdim.is_some_and(|d| d >= 3) {
        400
    } else {
        100
    });
    let t1 = Instant::now();
    let t = agree(
        w,
        StellarTree::build(
            &l.k,
            &StellarOptions {
                kv: Some(kv),
                ..Default::default()
            },
        )
        .map_err(|e| format!("{}: {e}", file.display())),
    )?;
    let build_s = t1.elapsed().as_secs_f64();
    let local = t.stats();
    let o = owned_stats(&t, l);
    if let Some(p) = a.vt_vv_out {
        agree(w, write_vt_vv(&t, l, p, w.rank()))?;
    }
    let sums = comm::sums(
        w,
        &[
            local.n_nodes,
            o.leaves,
            local.n_leaves,
            o.sum_t,
            o.sum_sre,
            local.storage.in_memory_bytes,
        ],
    );
    let [n_nodes, n_leaves, held_leaves, sum_t, sum_sre, in_memory] = sums[..] else {
        unreachable!("six sums")
    };
    let depth = comm::max(w, u64::from(local.max_depth));
    let max_v = comm::max(w, o.max_v);
    let max_t = comm::max(w, o.max_t);
    let build_max = comm::max(w, (build_s * 1e6) as u64) as f64 / 1e6;
    let per_rank = comm::gather(w, &[o.leaves, local.n_leaves, local.n_nodes, o.sum_t])?;
    if w.rank() != 0 {
        return Ok(());
    }
    let nv = f.h.n_vertices;
    let nt = f.h.n_cells;
    let base_refs: u64 =
        f.h.blocks
            .iter()
            .map(|&(k, n, _)| n * k.n_vertices() as u64)
            .sum();
    let enc = |lists: u64| starplex::stellar::stats::EncodingStorage {
        refs: 7 * n_nodes + lists,
        bytes: 48 * n_nodes + 4 * lists,
    };
    let ratio = |x: u64, n: u64| if n > 0 { x as f64 / n as f64 } else { 0.0 };
    let s = StellarStats {
        n_nodes,
        n_leaves,
        kv,
        n_vertices: nv,
        n_top_cells: nt,
        max_depth: depth as u32,
        chi: ratio(sum_t, nt),
        mu: ratio(sum_sre, nt),
        leaf_max_vertices: max_v,
        leaf_mean_vertices: ratio(nv, n_leaves),
        leaf_max_cells: max_t,
        leaf_mean_cells: ratio(sum_t, n_leaves),
        storage: starplex::stellar::stats::StorageStats {
            base_refs,
            base_bytes: 8 * nv * f.h.ambient_dim as u64 + 4 * base_refs,
            explicit: enc(nv + sum_t),
            vertex_compressed: enc(2 * n_leaves + sum_t),
            compressed: enc(2 * n_leaves + sum_sre),
            in_memory_bytes: in_memory,
        },
    };
    let per_rank = per_rank.unwrap_or_default();
    let rows: Vec<serde_json::Value> = per_rank
        .chunks_exact(4)
        .enumerate()
        .map(|(r, x)| {
            json!({"rank": r, "counted_leaves": x[0], "held_leaves": x[1], "nodes": x[2], "owned_leaf_cell_refs": x[3]})
        })
        .collect();
    let rule = "a leaf is counted by its rank when it holds an owned vertex (or no vertex); its top cells are those incident to its owned vertices, so chi and mu count each (leaf, cell) pair once over all ranks";
    let split = format!("{:?}", t.split()).to_lowercase();
    if a.json {
        let mut v = starplex_cli::report::stellar_stats_json(&s);
        v["split"] = json!(split);
        v["decomposition"] = json!(format!("{:?}", t.decomposition()).to_lowercase());
        v["distributed"] = json!({
            "ranks": w.size(),
            "rule": rule,
            "held_leaves": held_leaves,
            "per_rank": rows,
        });
        v["timings"] = json!({"read_s": read_s, "build_s": build_max});
        crate::print_json(&v);
    } else {
        println!("{}", file.display());
        starplex_cli::report::print_stellar_stats(&s);
        println!(
            "  distributed         {} ranks, {n_leaves} counted leaves of {held_leaves} held ({rule})",
            w.size()
        );
        println!("  time                read {read_s:.3} s, build {build_max:.3} s (slowest rank)");
    }
    Ok(())
}
