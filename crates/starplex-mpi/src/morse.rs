//! `homology` by rank-local discrete Morse reduction (the default for simplicial complexes):
//! every rank reduces the faces whose vertices it all owns with the library's gradient, rank 0
//! ranks the interface glued onto the critical cells. Exact over Z/2, Z/p, Q and Z.
//!
//! **Scheme.** `I_r` = the faces whose vertices are all owned by rank `r` (a subcomplex: the
//! owned part of every cell it holds), `J` = the faces whose vertices have two or more owners.
//! 1. Rank `r` builds `I_r` as a complex (the owned part of each held cell, the maximal ones
//!    kept, its owned vertices numbered in increasing global id so orientations agree) and its
//!    [`MorseComplex`]: the critical cells and their Morse boundaries.
//! 2. Every face `j ∈ J` is listed by the owner of its smallest vertex (it holds every cell
//!    with that vertex). A face of `J` has a facet in `I_r` only when exactly one of its vertices
//!    is not `r`'s: rank `r` sends, for each such `j`, `± π_r(j minus that vertex)`, the
//!    projection onto its critical cells (the gradient paths of `I_r` stay in `I_r`).
//! 3. Rank 0 builds `N = ⊕_r M(I_r) ⊕ C(J)` with the Morse boundaries on the critical cells and
//!    `∂' j = (∂j ∩ J) + Σ_r π_r(∂j ∩ I_r)`. The gradients of the `I_r` together are an acyclic
//!    matching of the whole complex whose critical cells are those of `N`, and `N` is its Morse
//!    complex: `H(N) = H(K)` over any coefficients ([`chain_complex_homology`]). The library's
//!    property test `gluing_a_morse_complex_keeps_the_homology` checks this identity.
//!
//! Work per rank: the single process's Morse reduction of its own region, plus the faces of the
//! cells that span ranks (the ghost layer); rank 0 also ranks `N`, whose size is the interface's
//! plus the critical cells. A cell of `n` vertices that spans ranks has up to `2^n` interface
//! faces: their total is checked against `--max-faces` first (contraction,
//! `--method contract`, has no such bound).
use std::path::Path;
use std::time::Instant;

use fixedbitset::FixedBitSet;
use mpi::traits::Communicator;
use serde_json::json;
use starplex::algo::homology::{
    chain_complex_homology, Field, Homology, HomologyOptions, MorseComplex,
};
use starplex::buf::Buf;
use starplex::cell::CellKind;
use starplex::complex::IndexedComplex;

use crate::comm::{self, agree, Failure, World};
use crate::dist::Local;

/// The most interface faces (on one rank) for which the default method is this one: above,
/// `homology` without `--method` contracts instead (a cell of `n` vertices that spans ranks has
/// up to `2^n` interface faces, which high-dimensional complexes reach quickly).
pub const AUTO_FACES: u64 = 1 << 26;

/// The interface faces this rank would list, at most: `2^n` for each held cell of `n`
/// vertices whose vertices have several owners.
pub fn interface_estimate(l: &Local) -> u128 {
    let mut estimate: u128 = 0;
    for c in l.k.cells() {
        let o0 = l.vertex_owner[c.vertices[0] as usize];
        if c.vertices.iter().any(|&v| l.vertex_owner[v as usize] != o0) {
            let n = c.vertices.len() as u32;
            estimate = estimate.saturating_add(if n > 40 { u128::MAX } else { 1u128 << n });
        }
    }
    estimate
}

/// Sorts the runs of `arity` values of `flat` and removes repeated runs.
fn sort_runs(flat: Vec<u32>, arity: usize) -> Vec<u32> {
    if arity == 0 || flat.is_empty() {
        return flat;
    }
    let n = flat.len() / arity;
    let mut idx: Vec<u32> = (0..n as u32).collect();
    let run = |i: u32| &flat[i as usize * arity..(i as usize + 1) * arity];
    idx.sort_unstable_by(|&a, &b| run(a).cmp(run(b)));
    idx.dedup_by(|a, b| run(*a) == run(*b));
    let mut out = Vec::with_capacity(idx.len() * arity);
    for i in idx {
        out.extend_from_slice(run(i));
    }
    out
}

/// The position of the run `key` among the sorted runs of `arity` values of `flat`.
fn find_run(flat: &[u32], arity: usize, key: &[u32]) -> Option<usize> {
    let n = flat.len() / arity;
    let (mut lo, mut hi) = (0, n);
    while lo < hi {
        let mid = (lo + hi) / 2;
        match flat[mid * arity..(mid + 1) * arity].cmp(key) {
            std::cmp::Ordering::Less => lo = mid + 1,
            std::cmp::Ordering::Greater => hi = mid,
            std::cmp::Ordering::Equal => return Some(mid),
        }
    }
    None
}

/// What one rank found, before it is sent.
struct LocalPart {
    /// The message to rank 0 (laid out as [`local_part`] says).
    msg: Vec<i64>,
    /// Statistics: cells of `I_r`, critical cells, interface faces owned, projections sent.
    n_inner_cells: u64,
    n_critical: u64,
    n_interface: u64,
    n_images: u64,
}

/// When every part of `by_arity` (flat sorted vertex lists, `by_arity[a]` of arity `a`, over
/// `nv` vertices) of a smaller arity than the largest is a face of a part of the largest
/// arity, removes them all (the closure, which is the complex, does not change) and returns
/// true: the owned part of a mesh is then one block, which the gradient takes over in place
/// instead of copying it. Otherwise nothing changes (the parts and their order, which sets the
/// gradient's vertex order, stay as they are).
fn drop_covered_parts(by_arity: &mut [Vec<u32>], nv: usize) -> bool {
    let Some(amax) = (1..by_arity.len()).rev().find(|&a| !by_arity[a].is_empty()) else {
        return false;
    };
    if amax > 16 {
        return false; // the subsets of a long cell are too many to look up
    }
    // the smaller parts, sorted and deduplicated, and their vertices marked
    let mut near = FixedBitSet::with_capacity(nv);
    let low: Vec<Vec<u32>> = (0..amax)
        .map(|a| {
            if a == 0 || by_arity[a].is_empty() {
                return Vec::new();
            }
            let parts = sort_runs(by_arity[a].clone(), a);
            parts.iter().for_each(|&v| near.insert(v as usize));
            parts
        })
        .collect();
    if low.iter().all(Vec::is_empty) {
        return false;
    }
    let mut covered: Vec<FixedBitSet> = low
        .iter()
        .enumerate()
        .map(|(a, p)| FixedBitSet::with_capacity(p.len().checked_div(a).unwrap_or(0)))
        .collect();
    let mut face: Vec<u32> = Vec::with_capacity(amax);
    for c in by_arity[amax].chunks_exact(amax) {
        if !c.iter().any(|&v| near.contains(v as usize)) {
            continue;
        }
        // every proper subset of c (c is sorted: so is each subset) of an arity with parts
        for mask in 1u32..(1u32 << amax) - 1 {
            let a = mask.count_ones() as usize;
            if low[a].is_empty() {
                continue;
            }
            face.clear();
            face.extend((0..amax).filter(|i| mask >> i & 1 == 1).map(|i| c[i]));
            if let Some(i) = find_run(&low[a], a, &face) {
                covered[a].insert(i);
            }
        }
    }
    let all = (1..amax).all(|a| covered[a].count_ones(..) == covered[a].len());
    if all {
        by_arity[1..amax].iter_mut().for_each(Vec::clear);
    }
    all
}

/// Rank `r`'s reduction (steps 1 and 2). `dims`: the number of dimensions of the input
/// (its dimension + 1). The message: `n_crit[0..dims]`; the Morse boundary columns of the
/// critical cells of dimensions 1.. (`len, (row, coef)..`); per dimension the number of owned
/// interface faces and their global vertex ids; the number of projections and each as
/// `arity, gids.., len, (row, coef)..`.
fn local_part(
    l: &mut Local,
    me: u32,
    dims: usize,
    field: Field,
    max_faces: u128,
) -> Result<LocalPart, String> {
    let nl = l.vertex_gid.len();
    let t0 = Instant::now();
    let tm = |w: &str| {
        if std::env::var_os("STARPLEX_HOMOLOGY_TIMES").is_some() {
            let m = starplex::measure::memory();
            eprintln!(
                "rank {me}: {w}: {:.3} s, resident {} MB, peak {} MB",
                t0.elapsed().as_secs_f64(),
                m.map_or(0, |m| m.resident >> 20),
                m.map_or(0, |m| m.peak >> 20)
            );
        }
    };
    tm("start");
    // owned vertices numbered in increasing local (= global) order: I_r's vertices
    let mut kid = vec![u32::MAX; nl];
    let mut n_owned = 0u32;
    for v in l.owned.ones() {
        kid[v] = n_owned;
        n_owned += 1;
    }
    // 2. (first, while the local complex is held) the interface faces of the cells that span
    //    ranks: owned ones (smallest vertex mine), and those with exactly one vertex that is
    //    not mine (a facet in I_r)
    if let Some(c) = l.k.cells().find(|c| !c.kind.is_simplex()) {
        return Err(format!(
            "a {} cell: the Morse method needs a simplicial complex (use --method algebraic)",
            c.kind
        ));
    }
    let estimate = interface_estimate(l);
    if estimate > max_faces {
        return Err(format!(
            "homology: about {estimate} interface faces (of cells spanning ranks) to list on one rank, over the budget of {max_faces} (raise --max-faces, or use --method contract)"
        ));
    }
    let mut owned_j: Vec<Vec<u32>> = vec![Vec::new(); dims + 1];
    let mut image_j: Vec<Vec<u32>> = vec![Vec::new(); dims + 1];
    let mut f: Vec<u32> = Vec::new();
    let mut sorted: Vec<u32> = Vec::new();
    for c in l.k.cells() {
        let o0 = l.vertex_owner[c.vertices[0] as usize];
        if c.vertices.iter().all(|&v| l.vertex_owner[v as usize] == o0) {
            continue;
        }
        sorted.clear();
        sorted.extend_from_slice(c.vertices);
        sorted.sort_unstable();
        let n = sorted.len();
        if n > 40 {
            return Err(format!(
                "homology: a cell of {n} vertices spans ranks (2^{n} faces to list): use --method contract"
            ));
        }
        for mask in 1u64..(1u64 << n) {
            if mask.count_ones() < 2 {
                continue;
            }
            f.clear();
            let mut foreign = 0;
            let mut first_owner = u32::MAX;
            let mut several = false;
            for (i, &v) in sorted.iter().enumerate() {
                if mask >> i & 1 == 1 {
                    let o = l.vertex_owner[v as usize];
                    if first_owner == u32::MAX {
                        first_owner = o;
                    } else if o != first_owner {
                        several = true;
                    }
                    if o != me {
                        foreign += 1;
                    }
                    f.push(v);
                }
            }
            if !several {
                continue;
            }
            let a = f.len();
            if a >= owned_j.len() {
                owned_j.resize(a + 1, Vec::new());
                image_j.resize(a + 1, Vec::new());
            }
            if first_owner == me {
                owned_j[a].extend_from_slice(&f);
            }
            if foreign == 1 {
                image_j[a].extend_from_slice(&f);
            }
        }
    }
    tm("interface faces");
    // 1. I_r: the owned part of every held cell (parts that are faces of others, or repeat,
    //    add no face: `MorseComplex::from_complex` takes them as they are)
    let mut by_arity: Vec<Vec<u32>> = vec![Vec::new(); dims + 1];
    for c in l.k.cells() {
        sorted.clear();
        sorted.extend(c.vertices.iter().filter(|&&v| kid[v as usize] != u32::MAX));
        if sorted.is_empty() {
            continue;
        }
        sorted.sort_unstable();
        let a = sorted.len();
        if a >= by_arity.len() {
            by_arity.resize(a + 1, Vec::new());
        }
        by_arity[a].extend(sorted.iter().map(|&v| kid[v as usize]));
    }
    // the local complex is not needed any more (its cell count stays in `cell_gid`)
    drop(std::mem::replace(&mut l.k, Local::empty().k));
    // the smaller parts, when all are faces of the largest, add no face: dropped, the owned
    // part of a mesh is one block, which the gradient takes over in place
    let one_block = drop_covered_parts(&mut by_arity, n_owned as usize);
    let blocks: Vec<(CellKind, Buf<u32>)> = by_arity
        .into_iter()
        .enumerate()
        .filter(|(a, v)| *a > 0 && !v.is_empty())
        .map(|(a, v)| (CellKind::Simplex((a - 1) as u8), Buf::Owned(v)))
        .collect();
    let coords = Buf::Owned(vec![0.0f64; n_owned as usize]);
    let inner = IndexedComplex::from_parts(1, coords, blocks)
        .map_err(|e| format!("the owned part of the complex: {e}"))?;
    let n_inner_cells = inner.n_cells() as u64;
    tm(if one_block {
        "owned complex (one block)"
    } else {
        "owned complex"
    });
    let hopts = HomologyOptions {
        field,
        ..Default::default()
    };
    let m = MorseComplex::from_complex(inner, &hopts).map_err(|e| e.to_string())?;
    tm("gradient");
    let mut crit = m.n_critical();
    crit.resize(crit.len().max(dims), 0);
    let mut msg: Vec<i64> = Vec::new();
    msg.extend(crit[..dims].iter().map(|&x| x as i64));
    for d in 1..dims {
        for col in m.boundaries(d).map_err(|e| e.to_string())? {
            msg.push(col.len() as i64);
            for (r, c) in col {
                msg.push(r as i64);
                msg.push(c);
            }
        }
    }
    tm("boundaries");
    let g = |v: u32| l.vertex_gid[v as usize] as i64;
    let mut n_interface = 0u64;
    for d in 0..dims {
        let a = d + 1;
        let list = match owned_j.get_mut(a) {
            Some(x) => sort_runs(std::mem::take(x), a),
            None => Vec::new(),
        };
        msg.push((list.len() / a) as i64);
        msg.extend(list.iter().map(|&v| g(v)));
        n_interface += (list.len() / a) as u64;
    }
    let mut n_images = 0u64;
    let mut images: Vec<i64> = Vec::new();
    for (a, list) in image_j.into_iter().enumerate() {
        if a < 2 || list.is_empty() {
            continue;
        }
        let list = sort_runs(list, a);
        // the facet in I_r: the run without its one foreign vertex, in I_r's numbering
        let mut sigma: Vec<u32> = Vec::with_capacity(list.len() / a * (a - 1));
        let mut signs: Vec<i64> = Vec::with_capacity(list.len() / a);
        for run in list.chunks_exact(a) {
            let p = run
                .iter()
                .position(|&v| kid[v as usize] == u32::MAX)
                .unwrap_or(0);
            signs.push(if p % 2 == 0 { 1 } else { -1 });
            sigma.extend(
                run.iter()
                    .enumerate()
                    .filter(|&(i, _)| i != p)
                    .map(|(_, &v)| kid[v as usize]),
            );
        }
        let tp = Instant::now();
        let pi = m.project(&sigma, a - 1).map_err(|e| e.to_string())?;
        if std::env::var_os("STARPLEX_HOMOLOGY_TIMES").is_some() {
            eprintln!(
                "rank {me}: {} projections of arity {}: {:.3} s",
                signs.len(),
                a - 1,
                tp.elapsed().as_secs_f64()
            );
        }
        for ((run, s), col) in list.chunks_exact(a).zip(signs).zip(pi) {
            if col.is_empty() {
                continue;
            }
            n_images += 1;
            images.push(a as i64);
            images.extend(run.iter().map(|&v| g(v)));
            images.push(col.len() as i64);
            for (r, c) in col {
                images.push(r as i64);
                images.push(c * s);
            }
        }
    }
    tm("projections");
    msg.push(n_images as i64);
    msg.extend(images);
    Ok(LocalPart {
        msg,
        n_inner_cells,
        n_critical: crit.iter().map(|&x| x as u64).sum(),
        n_interface,
        n_images,
    })
}

/// A sparse column: (row, coefficient).
type Column = Vec<(u32, i64)>;

/// Betti numbers, torsion per dimension, and the combined complex's cells per dimension.
pub type Combined = (Vec<u64>, Vec<Vec<u128>>, Vec<u64>);

/// Reads the next value of a message.
fn next(msg: &[i64], at: &mut usize) -> Result<i64, String> {
    let x = msg
        .get(*at)
        .copied()
        .ok_or("a truncated message from a rank (internal error)")?;
    *at += 1;
    Ok(x)
}

/// Rank 0 (step 3): the combined complex from every rank's message, and its homology.
fn combine(msgs: &[i64], ranks: usize, dims: usize, field: Field) -> Result<Combined, String> {
    let mut at = 0usize;
    // per rank: critical counts, their columns (rows local to the rank)
    let mut crit_n: Vec<Vec<usize>> = Vec::with_capacity(ranks);
    let mut crit_cols: Vec<Vec<Vec<Column>>> = Vec::with_capacity(ranks);
    let mut j_keys: Vec<Vec<Vec<u32>>> = Vec::with_capacity(ranks);
    type Image = (usize, Vec<u32>, usize, Column);
    let mut images: Vec<Image> = Vec::new();
    for r in 0..ranks {
        let mut n = Vec::with_capacity(dims);
        for _ in 0..dims {
            n.push(next(msgs, &mut at)? as usize);
        }
        let mut cols = vec![Vec::new(); dims];
        for d in 1..dims {
            for _ in 0..n[d] {
                let len = next(msgs, &mut at)? as usize;
                let mut col = Vec::with_capacity(len);
                for _ in 0..len {
                    let row = next(msgs, &mut at)? as u32;
                    col.push((row, next(msgs, &mut at)?));
                }
                cols[d].push(col);
            }
        }
        let mut keys = Vec::with_capacity(dims);
        for d in 0..dims {
            let cnt = next(msgs, &mut at)? as usize;
            let mut k = Vec::with_capacity(cnt * (d + 1));
            for _ in 0..cnt * (d + 1) {
                k.push(next(msgs, &mut at)? as u32);
            }
            keys.push(k);
        }
        let ni = next(msgs, &mut at)? as usize;
        for _ in 0..ni {
            let a = next(msgs, &mut at)? as usize;
            let mut key = Vec::with_capacity(a);
            for _ in 0..a {
                key.push(next(msgs, &mut at)? as u32);
            }
            let len = next(msgs, &mut at)? as usize;
            let mut col = Vec::with_capacity(len);
            for _ in 0..len {
                let row = next(msgs, &mut at)? as u32;
                col.push((row, next(msgs, &mut at)?));
            }
            images.push((r, key, a, col));
        }
        crit_n.push(n);
        crit_cols.push(cols);
        j_keys.push(keys);
    }
    // numbering per dimension: the critical cells rank by rank, then the interface faces
    let mut crit_off = vec![vec![0usize; dims]; ranks + 1];
    for r in 0..ranks {
        for d in 0..dims {
            crit_off[r + 1][d] = crit_off[r][d] + crit_n[r][d];
        }
    }
    let n_crit_total: Vec<usize> = (0..dims).map(|d| crit_off[ranks][d]).collect();
    let mut j: Vec<Vec<u32>> = Vec::with_capacity(dims);
    for d in 0..dims {
        let mut all = Vec::new();
        for k in &mut j_keys {
            all.append(&mut k[d]);
        }
        let before = all.len();
        let all = sort_runs(all, d + 1);
        if all.len() != before {
            return Err("an interface face listed by two ranks (internal error)".into());
        }
        j.push(all);
    }
    let n: Vec<usize> = (0..dims)
        .map(|d| n_crit_total[d] + j[d].len() / (d + 1))
        .collect();
    let mut cols: Vec<Vec<Column>> = vec![Vec::new(); dims];
    for d in 1..dims {
        let mut c = Vec::with_capacity(n[d]);
        for r in 0..ranks {
            let off = crit_off[r][d - 1] as u32;
            for col in std::mem::take(&mut crit_cols[r][d]) {
                c.push(col.into_iter().map(|(row, x)| (row + off, x)).collect());
            }
        }
        let a = d + 1;
        let joff = n_crit_total[d - 1] as u32;
        let mut facet = Vec::with_capacity(d);
        for key in j[d].chunks_exact(a) {
            let mut col = Vec::new();
            for i in 0..a {
                facet.clear();
                facet.extend(
                    key.iter()
                        .enumerate()
                        .filter(|&(x, _)| x != i)
                        .map(|(_, &v)| v),
                );
                if let Some(p) = find_run(&j[d - 1], d, &facet) {
                    col.push((joff + p as u32, if i % 2 == 0 { 1 } else { -1 }));
                }
            }
            c.push(col);
        }
        cols[d] = c;
    }
    for (r, key, a, col) in images {
        let d = a - 1;
        let p = find_run(&j[d], a, &key)
            .ok_or("a projection for an interface face no rank listed (internal error)")?;
        let off = crit_off[r][d - 1] as u32;
        let target = &mut cols[d][n_crit_total[d] + p];
        target.extend(col.into_iter().map(|(row, x)| (row + off, x)));
    }
    let (betti, torsion) =
        chain_complex_homology(&n, cols, field, u64::MAX).map_err(|e| e.to_string())?;
    Ok((betti, torsion, n.iter().map(|&x| x as u64).collect()))
}

/// What the reduction found, on rank 0.
pub struct Reduced {
    /// Betti numbers, torsion per dimension, the combined complex's cells per dimension.
    pub combined: Combined,
    /// Per rank: inner cells, critical cells, interface faces owned, projections, bytes sent.
    pub stats: Vec<u64>,
    /// Seconds of the rank-local part.
    pub local_s: f64,
}

/// The homology of the complex held by the ranks (collective; the local complex is freed on
/// the way): `Some` on rank 0.
pub fn reduce(
    w: &World,
    file: &Path,
    dims: usize,
    l: &mut Local,
    field: Field,
    max_faces: u128,
) -> Result<Option<Reduced>, Failure> {
    let t1 = Instant::now();
    let part = agree(
        w,
        local_part(l, w.rank() as u32, dims, field, max_faces)
            .map_err(|e| format!("{}: {e}", file.display())),
    )?;
    let local_s = t1.elapsed().as_secs_f64();
    let sent_before = comm::bytes_sent();
    let msgs = comm::gather(w, &part.msg)?;
    let stats = comm::gather(
        w,
        &[
            part.n_inner_cells,
            part.n_critical,
            part.n_interface,
            part.n_images,
            comm::bytes_sent() - sent_before,
        ],
    )?;
    drop(part);
    let r = match msgs {
        Some(m) => combine(&m, w.size() as usize, dims, field)
            .map(Some)
            .map_err(|e| format!("{}: {e}", file.display())),
        None => Ok(None),
    };
    let r = agree(w, r)?;
    Ok(r.map(|combined| Reduced {
        combined,
        stats: stats.unwrap_or_default(),
        local_s,
    }))
}

/// The verb (collective).
#[allow(clippy::too_many_arguments)]
pub fn run(
    w: &World,
    json_out: bool,
    file: &Path,
    dims: usize,
    l: &mut Local,
    read_s: f64,
    field: Field,
    max_faces: u128,
) -> Result<(), Failure> {
    let t1 = Instant::now();
    let r = reduce(w, file, dims, l, field, max_faces)?;
    let total_s = t1.elapsed().as_secs_f64();
    let Some(Reduced {
        combined: (betti, torsion, n),
        stats,
        local_s,
    }) = r
    else {
        return Ok(());
    };
    let h = Homology {
        field,
        betti,
        torsion: if field == Field::Z {
            torsion
        } else {
            vec![Vec::new(); dims]
        },
        critical: n.clone(),
        components: None,
        generators: Vec::new(),
    };
    let rows: Vec<serde_json::Value> = stats
        .chunks_exact(5)
        .enumerate()
        .map(|(r, x)| {
            json!({"rank": r, "inner_cells": x[0], "critical": x[1], "interface_owned": x[2], "projections": x[3], "bytes_to_rank0": x[4]})
        })
        .collect();
    let scheme = "each rank reduces the faces whose vertices it all owns to their Morse complex; rank 0 ranks the interface faces (vertices of several owners) glued onto the critical cells";
    if json_out {
        let mut v = starplex_cli::report::homology_json(&h);
        v["ranks"] = json!(w.size());
        v["distributed"] = json!({
            "scheme": scheme,
            "critical_cells": "cells of the combined complex (critical cells of every rank + interface faces), not the single process's Morse complex",
            "per_rank": rows,
        });
        v["timings"] = json!({"read_s": read_s, "local_s": local_s, "homology_s": total_s});
        crate::print_json(&v);
    } else {
        println!("{}", file.display());
        println!("  field               {}", h.field);
        println!("  Betti numbers       {:?}", h.betti);
        if h.field == Field::Z && h.torsion.iter().any(|t| !t.is_empty()) {
            println!("  torsion             {:?}", h.torsion);
        }
        println!("  Euler char.         {}", h.euler_characteristic());
        println!("  combined complex    {n:?} cells per dimension ({scheme})");
        println!(
            "  time                read {read_s:.3} s, homology {total_s:.3} s ({} ranks)",
            w.size()
        );
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::drop_covered_parts;

    /// The smaller parts go when every one is a face of a tetrahedron; else nothing changes.
    #[test]
    fn covered_parts_are_dropped() {
        // all covered (repeats included): only the tetrahedra stay
        let mut by_arity = vec![
            vec![],
            vec![4, 0, 4],                   // vertices (one twice)
            vec![3, 4, 0, 3, 3, 4],          // edges (one twice)
            vec![1, 2, 4, 0, 1, 2, 0, 1, 2], // triangles (one twice)
            vec![0, 1, 2, 3, 1, 2, 3, 4],
        ];
        assert!(drop_covered_parts(&mut by_arity, 5));
        assert_eq!(
            by_arity,
            vec![vec![], vec![], vec![], vec![], vec![0, 1, 2, 3, 1, 2, 3, 4]]
        );
        // one part not covered (the triangle 1 2 5): nothing changes
        let mut some = vec![
            vec![],
            vec![0],
            vec![3, 4, 0, 3],
            vec![1, 2, 5, 0, 1, 2],
            vec![0, 1, 2, 3, 1, 2, 3, 4],
        ];
        let before = some.clone();
        assert!(!drop_covered_parts(&mut some, 6));
        assert_eq!(some, before);
        // nothing smaller: unchanged
        let mut only = vec![vec![], vec![], vec![], vec![], vec![0, 1, 2, 3, 0, 1, 2, 4]];
        let before = only.clone();
        assert!(!drop_covered_parts(&mut only, 5));
        assert_eq!(only, before);
    }
}
