//! `homology --method algebraic` (and CP complexes): Betti numbers over Z/2, each rank reducing
//! what lies inside its own region by column reduction, rank 0 combining the small rest; and
//! `--method contract`. The default for simplicial complexes is [`crate::morse`], the same
//! scheme with the library's discrete gradient.
//!
//! **Scheme** (an exact algebraic reduction, not an approximation). Split the faces of the
//! complex in two: `A = ⋃_r I_r`, where `I_r` holds the faces whose vertices are *all* owned by
//! rank `r`, and `J`, the faces whose vertices have two or more owners (the interface). Each `I_r`
//! is closed under faces, so `A` is a subcomplex and a direct sum of the `I_r`.
//! 1. Rank `r` enumerates the faces of its held cells that contain an owned vertex (it holds
//!    every coface of such a face), and reduces the boundary matrix of `I_r` over Z/2 (column
//!    reduction with clearing, faces ordered by dimension then vertex list). Its *essential*
//!    faces (neither a pivot nor with a nonzero reduced column) are a basis of `H(I_r)`, and the
//!    reduced columns give a map `f_r: C(I_r) → H(I_r)` that vanishes on boundaries and induces
//!    the identity in homology (write a chain in the basis {reduced columns, faces that are not
//!    pivots}, keep its essential coordinates).
//! 2. For every interface face `j` with facets in `I_r`, rank `r` sends `f_r(∂j ∩ I_r)` (a few
//!    essential ids); the owner of `j` (the owner of its smallest vertex) sends `j` with its
//!    facets that are themselves interface faces.
//! 3. Rank 0 builds the complex `N = H(A) ⊕ C(J)` with `∂' e = 0` on essentials and
//!    `∂' j = ∂j ∩ J + Σ_r f_r(∂j ∩ I_r)`, and ranks its boundary matrices over Z/2. The chain map
//!    `a + j ↦ f(a) + j` from `C(K)` to `N` is the identity on `C(J) = C(K)/C(A)` and a
//!    quasi-isomorphism on `A`, so by the five lemma `H(N) = H(K)`: the Betti numbers are exact.
//!
//! Memory: rank `r` holds every face of its held cells that has an owned vertex, with its facet
//! lists (about 100-200 bytes a face: a tetrahedral region of `n` tets has ~`7.5 n` faces), and the
//! reduced columns; rank 0 also holds the interface faces of all ranks and the essentials, which
//! is the ghost layer's size, not the complex's. The `critical_cells` of the output are the
//! cells of `N` per dimension (not the single process's Morse complex, which depends on its
//! sequential vertex order): the Betti numbers and Euler characteristic equal the single
//! process's; `critical_cells` need not.
use std::path::Path;
use std::time::Instant;

use mpi::traits::Communicator;
use rustc_hash::FxHashMap;
use serde_json::json;
use starplex::cell::CellKind;

use crate::comm::{self, agree, Failure, World};
use crate::dist::{Local, Spb};

/// The symmetric difference of two increasing lists.
fn xor(a: &[u32], b: &[u32]) -> Vec<u32> {
    let mut out = Vec::with_capacity(a.len() + b.len());
    let (mut i, mut j) = (0, 0);
    while i < a.len() && j < b.len() {
        match a[i].cmp(&b[j]) {
            std::cmp::Ordering::Less => {
                out.push(a[i]);
                i += 1;
            }
            std::cmp::Ordering::Greater => {
                out.push(b[j]);
                j += 1;
            }
            std::cmp::Ordering::Equal => {
                i += 1;
                j += 1;
            }
        }
    }
    out.extend_from_slice(&a[i..]);
    out.extend_from_slice(&b[j..]);
    out
}

/// Column reduction over Z/2 of one boundary matrix: `cols[j]` (increasing row ids), skipping
/// the columns in `skip`. Returns the reduced columns (empty when zero) and `pivot[row]` = the
/// column whose reduced lowest row it is.
pub fn reduce(cols: Vec<Vec<u32>>, n_rows: usize, skip: &[bool]) -> (Vec<Vec<u32>>, Vec<u32>) {
    let mut pivot = vec![u32::MAX; n_rows];
    let mut out: Vec<Vec<u32>> = Vec::with_capacity(cols.len());
    for (j, mut c) in cols.into_iter().enumerate() {
        if skip.get(j).copied().unwrap_or(false) {
            out.push(Vec::new());
            continue;
        }
        while let Some(&low) = c.last() {
            let p = pivot[low as usize];
            if p == u32::MAX {
                pivot[low as usize] = j as u32;
                break;
            }
            c = xor(&c, &out[p as usize]);
        }
        out.push(c);
    }
    (out, pivot)
}

/// Ranks of the boundary matrices over Z/2 (`cols[k]`: the columns of `d_k`, one per `k`-cell,
/// rows the `(k-1)`-cells; `cols[0]` has only empty columns), with clearing from the top
/// dimension down (a `k`-cell that is a pivot of `d_{k+1}` has a zero reduced column in `d_k`).
pub fn ranks(cols: Vec<Vec<Vec<u32>>>, n: &[usize]) -> Vec<u64> {
    let d = cols.len();
    let mut rank = vec![0u64; d];
    let mut skip: Vec<bool> = Vec::new();
    for (k, c) in cols.into_iter().enumerate().rev() {
        let rows = if k == 0 { 0 } else { n[k - 1] };
        let (red, piv) = reduce(c, rows, &skip);
        rank[k] = red.iter().filter(|c| !c.is_empty()).count() as u64;
        skip = piv.iter().map(|&p| p != u32::MAX).collect();
    }
    rank
}

/// Betti numbers over Z/2 from the number of cells per dimension and the boundary columns
/// (`cols[k]` = columns of `d_k`, `cols[0]` empty).
///
/// A brute-force model of the definition `b_k = n_k - rank d_k - rank d_{k+1}`.
pub fn betti(n: &[usize], cols: Vec<Vec<Vec<u32>>>) -> Vec<u64> {
    let r = ranks(cols, n);
    (0..n.len())
        .map(|k| {
            let rk = r.get(k).copied().unwrap_or(0);
            let rk1 = r.get(k + 1).copied().unwrap_or(0);
            (n[k] as u64).saturating_sub(rk + rk1)
        })
        .collect()
}

/// The faces of a cell kind by dimension: local positions (sorted) and the positions of the
/// facets among the faces one dimension lower.
type KindFaces = Vec<Vec<(Vec<u8>, Vec<usize>)>>;
/// Faces by their sorted local vertex list.
type FaceIndex = FxHashMap<Box<[u32]>, u32>;

/// One face seen by this rank.
struct Face {
    dim: usize,
    key: Box<[u32]>,
    /// All vertices owned here.
    inner: bool,
    facets: Vec<Box<[u32]>>,
}

/// Every face (of dimension `k`, local vertex positions sorted) of a cell, by dimension, with
/// the positions of its facets among the `(k-1)`-faces.
fn faces_of_kind(kind: CellKind) -> KindFaces {
    let d = kind.dim();
    let mut by_dim: Vec<Vec<Vec<u8>>> = vec![Vec::new(); d + 1];
    for (k, dst) in by_dim.iter_mut().enumerate() {
        kind.for_each_face(k, |f| {
            let mut f = f.to_vec();
            f.sort_unstable();
            dst.push(f);
        });
    }
    (0..=d)
        .map(|k| {
            by_dim[k]
                .iter()
                .map(|f| {
                    let facets = if k == 0 {
                        Vec::new()
                    } else {
                        by_dim[k - 1]
                            .iter()
                            .enumerate()
                            .filter(|(_, g)| g.iter().all(|x| f.contains(x)))
                            .map(|(i, _)| i)
                            .collect()
                    };
                    (f.clone(), facets)
                })
                .collect()
        })
        .collect()
}

/// The faces with an owned vertex, their classes and facets.
fn enumerate(l: &Local, max_faces: u128) -> Result<(Vec<Face>, FaceIndex), String> {
    let mut estimate: u128 = 0;
    for c in l.k.cells() {
        if c.vertices.iter().any(|&v| l.owned.contains(v as usize)) {
            estimate += (0..=c.kind.dim()).map(|k| c.kind.n_faces(k)).sum::<u128>();
        }
    }
    if estimate > max_faces {
        return Err(format!(
            "homology: about {estimate} faces to enumerate on one rank, over the budget of {max_faces} (raise it with --max-faces, or use more ranks)"
        ));
    }
    let mut tables: FxHashMap<CellKind, KindFaces> = FxHashMap::default();
    let mut faces: Vec<Face> = Vec::new();
    let mut index: FaceIndex = FxHashMap::default();
    let mut verts: Vec<u32> = Vec::new();
    let mut keys: Vec<Vec<Box<[u32]>>> = Vec::new();
    for c in l.k.cells() {
        if !c.vertices.iter().any(|&v| l.owned.contains(v as usize)) {
            continue;
        }
        let t = tables
            .entry(c.kind)
            .or_insert_with(|| faces_of_kind(c.kind));
        verts.clear();
        verts.extend_from_slice(c.vertices);
        keys.clear();
        for (k, level) in t.iter().enumerate() {
            let mut row = Vec::with_capacity(level.len());
            for (pos, facets) in level {
                let mut key: Vec<u32> = pos.iter().map(|&p| verts[p as usize]).collect();
                key.sort_unstable();
                let key: Box<[u32]> = key.into_boxed_slice();
                let n_owned = key
                    .iter()
                    .filter(|&&v| l.owned.contains(v as usize))
                    .count();
                if n_owned > 0 && !index.contains_key(&key) {
                    index.insert(key.clone(), faces.len() as u32);
                    faces.push(Face {
                        dim: k,
                        key: key.clone(),
                        inner: n_owned == key.len(),
                        facets: facets.iter().map(|&i| keys[k - 1][i].clone()).collect(),
                    });
                }
                row.push(key);
            }
            keys.push(row);
        }
    }
    // isolated owned vertices are 0-faces of no cell
    let used = l.k.used_vertices();
    for v in l.owned.ones().filter(|&v| !used.contains(v)) {
        let key: Box<[u32]> = vec![v as u32].into_boxed_slice();
        index.insert(key.clone(), faces.len() as u32);
        faces.push(Face {
            dim: 0,
            key,
            inner: true,
            facets: Vec::new(),
        });
    }
    Ok((faces, index))
}

/// What one rank sends to rank 0 (flat `u32` records, vertex ids global).
#[derive(Default)]
struct Parts {
    /// Dimension of each essential face, in essential-id order.
    essential_dims: Vec<u32>,
    /// `dim, n, v.., n_facets, (n, v..)..` for the interface faces this rank owns.
    interface: Vec<u32>,
    /// `n, v.., n_ids, id..` for the interface faces with facets inside this rank.
    images: Vec<u32>,
    /// Statistics: faces enumerated, inner faces, interface faces owned.
    n_faces: u64,
    n_inner: u64,
    n_interface_owned: u64,
}

fn local_reduction(l: &Local, max_faces: u128) -> Result<Parts, String> {
    let (faces, index) = enumerate(l, max_faces)?;
    let top = faces.iter().map(|f| f.dim).max().unwrap_or(0);
    // inner faces by dimension, ordered by vertex list: position = row/column id
    let mut inner: Vec<Vec<u32>> = vec![Vec::new(); top + 1];
    for (i, f) in faces.iter().enumerate() {
        if f.inner {
            inner[f.dim].push(i as u32);
        }
    }
    let mut pos = vec![u32::MAX; faces.len()];
    for list in inner.iter_mut() {
        list.sort_unstable_by(|&a, &b| faces[a as usize].key.cmp(&faces[b as usize].key));
        for (p, &i) in list.iter().enumerate() {
            pos[i as usize] = p as u32;
        }
    }
    let col_of = |f: &Face| -> Vec<u32> {
        let mut c: Vec<u32> = f.facets.iter().map(|k| pos[index[k] as usize]).collect();
        c.sort_unstable();
        c
    };
    // reduce d_top .. d_1 with clearing
    let mut reduced: Vec<Vec<Vec<u32>>> = vec![Vec::new(); top + 1];
    let mut pivots: Vec<Vec<u32>> = vec![Vec::new(); top + 1];
    let mut killed: Vec<bool> = Vec::new();
    for k in (1..=top).rev() {
        let cols: Vec<Vec<u32>> = inner[k]
            .iter()
            .map(|&i| col_of(&faces[i as usize]))
            .collect();
        let (red, piv) = reduce(cols, inner[k - 1].len(), &killed);
        killed = piv.iter().map(|&p| p != u32::MAX).collect();
        reduced[k] = red;
        pivots[k] = piv;
    }
    // essentials: not a pivot of d_{k+1}, zero reduced column in d_k
    let mut ess_id: Vec<Vec<u32>> = vec![Vec::new(); top + 1];
    let mut parts = Parts::default();
    for k in 0..=top {
        ess_id[k] = vec![u32::MAX; inner[k].len()];
        for p in 0..inner[k].len() {
            let is_pivot = k < top && pivots[k + 1][p] != u32::MAX;
            let zero = k == 0 || reduced[k][p].is_empty();
            if !is_pivot && zero {
                ess_id[k][p] = parts.essential_dims.len() as u32;
                parts.essential_dims.push(k as u32);
            }
        }
    }
    let g = |v: u32| l.vertex_gid[v as usize];
    for f in faces.iter().filter(|f| !f.inner) {
        // the image of its facets inside this rank
        if f.dim > 0 {
            let m = f.dim - 1;
            let mut x: Vec<u32> = f
                .facets
                .iter()
                .filter_map(|k| index.get(k).map(|&i| i as usize))
                .filter(|&i| faces[i].inner)
                .map(|i| pos[i])
                .collect();
            if !x.is_empty() {
                x.sort_unstable();
                let mut ids = Vec::new();
                while let Some(&low) = x.last() {
                    let p = pivots[m + 1][low as usize];
                    if p != u32::MAX {
                        x = xor(&x, &reduced[m + 1][p as usize]);
                    } else {
                        if ess_id[m][low as usize] != u32::MAX {
                            ids.push(ess_id[m][low as usize]);
                        }
                        x.pop();
                    }
                }
                if !ids.is_empty() {
                    parts.images.push(f.key.len() as u32);
                    parts.images.extend(f.key.iter().map(|&v| g(v)));
                    parts.images.push(ids.len() as u32);
                    parts.images.extend_from_slice(&ids);
                }
            }
        }
        // the owner of its smallest vertex sends it, with its interface facets
        if l.owned.contains(f.key[0] as usize) {
            parts.n_interface_owned += 1;
            parts.interface.push(f.dim as u32);
            parts.interface.push(f.key.len() as u32);
            parts.interface.extend(f.key.iter().map(|&v| g(v)));
            let jf: Vec<&Box<[u32]>> = f
                .facets
                .iter()
                .filter(|k| {
                    let o = l.vertex_owner[k[0] as usize];
                    k.iter().any(|&v| l.vertex_owner[v as usize] != o)
                })
                .collect();
            parts.interface.push(jf.len() as u32);
            for k in jf {
                parts.interface.push(k.len() as u32);
                parts.interface.extend(k.iter().map(|&v| g(v)));
            }
        }
    }
    parts.n_faces = faces.len() as u64;
    parts.n_inner = inner.iter().map(|x| x.len() as u64).sum();
    Ok(parts)
}

/// Rank 0: the complex `H(A) ⊕ C(J)` and its Betti numbers (`dims + 1` of them).
fn combine(
    dims: usize,
    ess: &[u32],
    ess_counts: &[u32],
    interface: &[u32],
    images: &[u32],
) -> Result<(Vec<u64>, Vec<usize>), String> {
    let mut n = vec![0usize; dims + 1];
    let bad = || "internal: a malformed record reached rank 0".to_string();
    // essentials: (rank, id) -> (dim, index in dim)
    let mut ess_index: Vec<Vec<(usize, u32)>> = Vec::new();
    let mut at = 0usize;
    for &c in ess_counts {
        let mut row = Vec::with_capacity(c as usize);
        for &d in ess.get(at..at + c as usize).ok_or_else(bad)? {
            let d = d as usize;
            if d > dims {
                return Err(bad());
            }
            row.push((d, n[d] as u32));
            n[d] += 1;
        }
        ess_index.push(row);
        at += c as usize;
    }
    // interface faces
    let mut jidx: FxHashMap<Vec<u32>, (usize, u32)> = FxHashMap::default();
    let mut i = 0;
    while i < interface.len() {
        let d = interface[i] as usize;
        let len = *interface.get(i + 1).ok_or_else(bad)? as usize;
        let key = interface.get(i + 2..i + 2 + len).ok_or_else(bad)?.to_vec();
        i += 2 + len;
        let nf = *interface.get(i).ok_or_else(bad)? as usize;
        i += 1;
        for _ in 0..nf {
            let len = *interface.get(i).ok_or_else(bad)? as usize;
            interface.get(i + 1..i + 1 + len).ok_or_else(bad)?;
            i += 1 + len;
        }
        if d > dims || jidx.insert(key, (d, n[d] as u32)).is_some() {
            return Err(bad());
        }
        n[d] += 1;
    }
    let mut cols: Vec<Vec<Vec<u32>>> = (0..=dims).map(|_| Vec::new()).collect();
    for (k, c) in cols.iter_mut().enumerate() {
        c.resize(n[k], Vec::new());
    }
    // interface columns: their interface facets
    let mut i = 0;
    while i < interface.len() {
        let len = interface[i + 1] as usize;
        let key = &interface[i + 2..i + 2 + len];
        i += 2 + len;
        let nf = interface[i] as usize;
        i += 1;
        let &(d, at) = jidx.get(key).ok_or_else(bad)?;
        let mut col = Vec::with_capacity(nf);
        for _ in 0..nf {
            let len = interface[i] as usize;
            let fk = &interface[i + 1..i + 1 + len];
            i += 1 + len;
            let &(fd, fat) = jidx.get(fk).ok_or_else(|| {
                format!("internal: interface facet {fk:?} of {key:?} was sent by no rank")
            })?;
            if fd + 1 != d {
                return Err(bad());
            }
            col.push(fat);
        }
        col.sort_unstable();
        cols[d][at as usize] = col;
    }
    // images of the facets inside each rank
    let mut i = 0;
    while i < images.len() {
        let src = images[i] as usize;
        let len = *images.get(i + 1).ok_or_else(bad)? as usize;
        let key = images.get(i + 2..i + 2 + len).ok_or_else(bad)?;
        i += 2 + len;
        let ni = *images.get(i).ok_or_else(bad)? as usize;
        let ids = images.get(i + 1..i + 1 + ni).ok_or_else(bad)?;
        i += 1 + ni;
        let &(d, at) = jidx
            .get(key)
            .ok_or_else(|| format!("internal: interface face {key:?} was sent by no rank"))?;
        let mut add: Vec<u32> = Vec::with_capacity(ids.len());
        for &e in ids {
            let &(ed, ei) = ess_index
                .get(src)
                .and_then(|r| r.get(e as usize))
                .ok_or_else(bad)?;
            if ed + 1 != d {
                return Err(bad());
            }
            add.push(ei);
        }
        add.sort_unstable();
        let col = &mut cols[d][at as usize];
        *col = xor(col, &add);
    }
    Ok((betti(&n, cols), n))
}

/// The verb (collective).
pub fn run(
    w: &World,
    json_out: bool,
    file: &Path,
    f: &Spb,
    l: &Local,
    read_s: f64,
    max_faces: u128,
) -> Result<(), Failure> {
    let t1 = Instant::now();
    let dims = f.dim().unwrap_or(0);
    let mut parts = agree(
        w,
        local_reduction(l, max_faces).map_err(|e| format!("{}: {e}", file.display())),
    )?;
    // tag the images with this rank (rank 0 resolves essential ids per rank)
    {
        let me = w.rank() as u32;
        let mut tagged = Vec::with_capacity(parts.images.len() + parts.images.len() / 4);
        let x = &parts.images;
        let mut i = 0;
        while i < x.len() {
            let len = x[i] as usize;
            let ni = x[i + 1 + len] as usize;
            tagged.push(me);
            tagged.extend_from_slice(&x[i..i + 2 + len + ni]);
            i += 2 + len + ni;
        }
        parts.images = tagged;
    }
    let local_s = t1.elapsed().as_secs_f64();
    let sent_before = comm::bytes_sent();
    let ess = comm::gather(w, &parts.essential_dims)?;
    let counts = comm::gather(w, &[parts.essential_dims.len() as u32])?;
    let interface = comm::gather(w, &parts.interface)?;
    let images = comm::gather(w, &parts.images)?;
    let stats = comm::gather(
        w,
        &[
            parts.n_faces,
            parts.n_inner,
            parts.essential_dims.len() as u64,
            parts.n_interface_owned,
            comm::bytes_sent() - sent_before,
        ],
    )?;
    let r = match (ess, counts, interface, images) {
        (Some(e), Some(c), Some(j), Some(im)) => combine(dims, &e, &c, &j, &im),
        _ => Ok((Vec::new(), Vec::new())),
    };
    let (b, n) = agree(w, r)?;
    let total_s = t1.elapsed().as_secs_f64();
    if w.rank() != 0 {
        return Ok(());
    }
    let euler: i64 = b
        .iter()
        .enumerate()
        .map(|(i, &x)| if i % 2 == 0 { x as i64 } else { -(x as i64) })
        .sum();
    let rows: Vec<serde_json::Value> = stats
        .unwrap_or_default()
        .chunks_exact(5)
        .enumerate()
        .map(|(r, x)| {
            json!({"rank": r, "faces": x[0], "inner_faces": x[1], "essential": x[2], "interface_owned": x[3], "bytes_to_rank0": x[4]})
        })
        .collect();
    let scheme = "each rank reduces the faces whose vertices it all owns (Z/2 column reduction) to their homology; rank 0 ranks the interface faces (vertices of several owners) plus those homology classes";
    if json_out {
        let v = json!({
            "field": "Z/2",
            "betti": b,
            "euler_characteristic": euler,
            "critical_cells": n,
            "betti_z2": b,
            "ranks": w.size(),
            "distributed": {"scheme": scheme, "critical_cells": "cells of the combined complex (essential classes + interface faces), not the single process's Morse complex", "per_rank": rows},
            "timings": {"read_s": read_s, "local_s": local_s, "homology_s": total_s},
        });
        crate::print_json(&v);
    } else {
        println!("{}", file.display());
        println!("  field               Z/2");
        println!("  Betti numbers       {b:?}");
        println!("  Euler char.         {euler}");
        println!("  combined complex    {n:?} cells per dimension ({scheme})");
        println!(
            "  time                read {read_s:.3} s, homology {total_s:.3} s ({} ranks)",
            w.size()
        );
    }
    Ok(())
}

/// Homology by contraction (`--method contract`, simplicial complexes): the ranks contract edges
/// under the link condition in one distributed round of `simplify --mode homology` (every
/// contraction keeps the homotopy type, hence the integer homology), write the much smaller
/// complex left as a temporary `.spb` in `tmp_dir` (every rank its part), and rank 0 computes
/// its homology with the library's Morse reduction, over any field. Memory per rank is that of
/// the local complex (as `validate`), and rank 0 also holds the reduced complex; the Betti
/// numbers are padded with zeros to the input's dimension (a contracted complex can lose
/// dimensions, never homology).
pub fn run_by_contraction(
    w: &World,
    json_out: bool,
    file: &Path,
    field: starplex::algo::homology::Field,
    tmp_dir: &Path,
) -> Result<(), Failure> {
    use starplex::algo::homology::{homology_indexed, Field, HomologyOptions};
    let t0 = Instant::now();
    let f = agree(w, Spb::open(file))?;
    let dims = f.dim().unwrap_or(0);
    drop(f);
    // one name on every rank: rank 0's process id
    let token = comm::all_gather(w, &[u64::from(std::process::id())])[0];
    let stem = file
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    let tmp = tmp_dir.join(format!(".{stem}.starplex-mpi-homology-{token}.spb"));
    let args = crate::simplify::SimplifyArgs {
        out: &tmp,
        mode: Some(starplex::algo::simplify::Mode::Homology),
        ratio: None,
        faces: None,
        vertices: None,
        max_error: None,
        keep_manifold: false,
        lock_boundary: false,
        keep_vertices: None,
        keep_labels: None,
        ignore_labels: true,
        keep_vertex_attribute: None,
        attributes: false,
        report: false,
        max_rounds: 1,
        gather_below: 0,
        json: false,
    };
    let o = crate::simplify::rounds(w, &args, file);
    let o = match o {
        Ok(o) => o,
        Err(e) => {
            if w.rank() == 0 {
                let _ = std::fs::remove_file(&tmp);
            }
            return Err(e);
        }
    };
    let contract_s = t0.elapsed().as_secs_f64();
    let h = if w.rank() == 0 {
        let r = starplex::io::read(&tmp, &Default::default())
            .map_err(|e| e.to_string())
            .and_then(|r| {
                homology_indexed(
                    &r.complex,
                    &HomologyOptions {
                        field,
                        ..Default::default()
                    },
                )
                .map_err(|e| format!("{}: {e}", file.display()))
            });
        let _ = std::fs::remove_file(&tmp);
        r.map(Some)
    } else {
        Ok(None)
    };
    let h = agree(w, h)?;
    let Some(mut h) = h else { return Ok(()) };
    h.betti.resize(h.betti.len().max(dims + 1), 0);
    if field == Field::Z {
        h.torsion.resize(h.betti.len(), Vec::new());
    }
    let total_s = t0.elapsed().as_secs_f64();
    let scheme = "the ranks contract edges under the link condition (homotopy type kept), each removing only vertices whose stars it alone holds; rank 0 computes the homology of the complex left";
    if json_out {
        let mut v = starplex_cli::report::homology_json(&h);
        v["ranks"] = json!(w.size());
        v["distributed"] = json!({
            "scheme": scheme,
            "contractions": o.contractions,
            "reduced_complex": {"vertices": o.written.n_vertices, "cells": o.written.n_cells},
            "critical_cells": "of the Morse complex of the reduced complex",
        });
        v["timings"] = json!({"contract_s": contract_s, "homology_s": total_s});
        crate::print_json(&v);
    } else {
        println!("{}", file.display());
        println!("  field               {}", h.field);
        println!("  Betti numbers       {:?}", h.betti);
        if h.field == Field::Z && h.torsion.iter().any(|t| !t.is_empty()) {
            println!("  torsion             {:?}", h.torsion);
        }
        println!("  Euler char.         {}", h.euler_characteristic());
        println!(
            "  reduced complex     {} vertices, {} top cells after {} contractions ({scheme})",
            o.written.n_vertices, o.written.n_cells, o.contractions
        );
        println!(
            "  time                contraction {contract_s:.3} s, total {total_s:.3} s ({} ranks)",
            w.size()
        );
    }
    Ok(())
}
