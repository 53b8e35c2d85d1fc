//! The parallel `.spb` writer: every rank writes its own vertices and cells into one file at
//! offsets agreed by prefix sums, so no rank ever holds the whole output.
//!
//! 1. The ranks agree on the blocks (one per cell kind, in [`CellKind`] order) and on the counts:
//!    every rank's vertices and cells per kind are summed, and each rank's first vertex and first
//!    cell of every block is the sum over the ranks before it.
//! 2. Rank 0 creates the file (a temporary name beside the target), sets its length and writes
//!    the header ([`SpbPlan`]); after a collective check every rank writes its coordinates and
//!    its cells (`pwrite` at the planned offsets); after another, rank 0 syncs it and renames it
//!    over the target. A failure on any rank removes the temporary file and leaves the target
//!    untouched.
use std::os::unix::fs::FileExt;
use std::path::{Path, PathBuf};

use starplex::attr::{AttrTarget, AttrValues, Attribute};
use starplex::cell::CellKind;
use starplex::io::binary::{SpbAttr, SpbPlan};
use starplex::io::output::{self, OutputTarget};

use mpi::traits::Communicator;

use crate::comm::{self, agree, Failure, World};

/// This rank's part of the output: its vertices (in their output order, which is global id
/// order over the ranks) and its cells by kind, with output vertex ids.
pub struct Part {
    /// Coordinates of this rank's vertices, `ambient_dim` per vertex.
    pub coords: Vec<f64>,
    /// Cells of each kind (flat vertex lists), kinds in any order, each at most once.
    pub blocks: Vec<(CellKind, Vec<u32>)>,
    /// The values of each attribute column of the output ([`write`]'s `columns`, in that
    /// order) as the bits of their 8-byte numbers ([`words`]): a vertex column's for this
    /// rank's vertices, a cell column's for its cells of `blocks[0]`, then of `blocks[1]`, ...
    pub values: Vec<Vec<u64>>,
}

/// The values of `col` for `items`, in that order, as the bits of their `i64` or `f64` numbers
/// (what the `.spb` stores, little-endian).
pub fn words(col: &Attribute, items: impl Iterator<Item = usize>) -> Vec<u64> {
    let c = col.components;
    let mut out = Vec::with_capacity(items.size_hint().0 * c);
    for i in items {
        match &col.values {
            AttrValues::Int(v) => out.extend(v[i * c..(i + 1) * c].iter().map(|&x| x as u64)),
            AttrValues::Float(v) => out.extend(v[i * c..(i + 1) * c].iter().map(|x| x.to_bits())),
        }
    }
    out
}

/// Every cell kind a `.spb` can hold, as a dense index (the order of the blocks).
fn kind_index(k: CellKind) -> usize {
    match k {
        CellKind::Simplex(d) => d as usize,
        CellKind::Quad => KINDS - 4,
        CellKind::Pyramid => KINDS - 3,
        CellKind::Prism => KINDS - 2,
        CellKind::Hex => KINDS - 1,
    }
}

const KINDS: usize = starplex::cell::MAX_SIMPLEX_DIM + 1 + 4;

fn kind_of(i: usize) -> CellKind {
    match i {
        _ if i == KINDS - 4 => CellKind::Quad,
        _ if i == KINDS - 3 => CellKind::Pyramid,
        _ if i == KINDS - 2 => CellKind::Prism,
        _ if i == KINDS - 1 => CellKind::Hex,
        d => CellKind::Simplex(d as u8),
    }
}

/// `target`'s file name with `suffix` appended, in the same directory (temporary files).
pub fn beside(target: &Path, suffix: &str) -> PathBuf {
    let mut name = target
        .file_name()
        .map(|n| n.to_os_string())
        .unwrap_or_default();
    name.push(suffix);
    target.with_file_name(name)
}

/// Where `path` is written: the final target of a regular file (a symbolic link is followed);
/// standard output, FIFOs and devices are refused (ranks write at offsets).
pub fn target_of(path: &Path) -> Result<PathBuf, String> {
    match output::resolve(path).map_err(|e| e.to_string())? {
        OutputTarget::File(p) => Ok(p),
        _ => Err(format!(
            "{}: starplex-mpi writes its output as a regular file (every rank writes its own byte ranges of it), not to a stream or device: name a file",
            path.display()
        )),
    }
}

/// What was written.
pub struct Written {
    /// Vertices and cells of the whole file.
    pub n_vertices: u64,
    /// Cells of the whole file.
    pub n_cells: u64,
    /// Bytes of the file.
    pub bytes: u64,
}

/// Writes the parts of every rank as one `.spb` at `target` (collective; see the module docs),
/// with the attribute `columns` (in file order: vertex columns first; their offsets are
/// ignored), whose values each part holds.
pub fn write(
    w: &World,
    target: &Path,
    ambient_dim: usize,
    columns: &[SpbAttr],
    part: &Part,
) -> Result<Written, Failure> {
    let (rank, p) = (w.rank() as usize, w.size() as usize);
    let d = ambient_dim.max(1);
    // [vertices, cells of kind 0, 1, ...] of every rank, on every rank
    let mut mine = vec![0u64; 1 + KINDS];
    mine[0] = (part.coords.len() / d) as u64;
    for (k, v) in &part.blocks {
        mine[1 + kind_index(*k)] += (v.len() / k.n_vertices()) as u64;
    }
    let all = comm::all_gather(w, &mine);
    let row = |r: usize| &all[r * (1 + KINDS)..(r + 1) * (1 + KINDS)];
    let total: Vec<u64> = (0..1 + KINDS)
        .map(|i| (0..p).map(|r| row(r)[i]).sum())
        .collect();
    let before: Vec<u64> = (0..1 + KINDS)
        .map(|i| (0..rank).map(|r| row(r)[i]).sum())
        .collect();
    let kinds: Vec<usize> = (0..KINDS).filter(|&i| total[1 + i] > 0).collect();
    let blocks: Vec<(CellKind, u64)> = kinds.iter().map(|&i| (kind_of(i), total[1 + i])).collect();
    let plan = agree(
        w,
        SpbPlan::with_attributes(ambient_dim, total[0], &blocks, columns).ok_or_else(|| {
            format!(
                "{}: the output is too large for the .spb layout",
                target.display()
            )
        }),
    )?;
    // the values of each part follow `columns`: the plan must keep their order
    let same = plan.attrs.len() == columns.len()
        && plan
            .attrs
            .iter()
            .zip(columns)
            .all(|(a, c)| a.name == c.name && a.target == c.target);
    comm::agree_that(
        w,
        same && part.values.len() == columns.len(),
        "internal error: attribute columns not in file order",
    )?;
    let tmp = beside(target, ".starplex-mpi-part");
    let created = if rank == 0 {
        (|| -> std::io::Result<()> {
            let f = std::fs::File::create(&tmp)?;
            f.set_len(plan.file_len)?;
            f.write_all_at(&plan.header, 0)
        })()
        .map_err(|e| format!("{}: {e}", tmp.display()))
    } else {
        Ok(())
    };
    agree(w, created)?;
    let wrote = (|| -> std::io::Result<()> {
        let f = std::fs::OpenOptions::new().write(true).open(&tmp)?;
        let at = plan.coords_offset + before[0] * 8 * ambient_dim as u64;
        f.write_all_at(bytemuck::cast_slice(&part.coords), at)?;
        for (b, &i) in kinds.iter().enumerate() {
            let k = kind_of(i);
            let Some((_, v)) = part.blocks.iter().find(|(x, _)| *x == k) else {
                continue;
            };
            let at = plan.block_offsets[b] + before[1 + i] * 4 * k.n_vertices() as u64;
            f.write_all_at(bytemuck::cast_slice(v), at)?;
        }
        // attribute values: a vertex column at this rank's first vertex; a cell column per
        // block, at the block's first cell in the file plus the cells of the ranks before
        for (e, vals) in plan.attrs.iter().zip(&part.values) {
            let c = e.components;
            match e.target {
                AttrTarget::Vertex => {
                    f.write_all_at(bytemuck::cast_slice(vals), e.offset + before[0] * c * 8)?;
                }
                AttrTarget::Cell => {
                    let mut from = 0usize;
                    for (k, v) in &part.blocks {
                        let n = (v.len() / k.n_vertices()) as u64;
                        // a kind with cells here has cells in the file: it is planned
                        let Some(b) = kinds.iter().position(|&i| i == kind_index(*k)) else {
                            continue;
                        };
                        let first: u64 = blocks[..b].iter().map(|&(_, n)| n).sum::<u64>()
                            + before[1 + kind_index(*k)];
                        let to = from + (n * c) as usize;
                        f.write_all_at(
                            bytemuck::cast_slice(&vals[from..to]),
                            e.offset + first * c * 8,
                        )?;
                        from = to;
                    }
                }
            }
        }
        Ok(())
    })()
    .map_err(|e| format!("{}: {e}", tmp.display()));
    if let Err(e) = agree(w, wrote) {
        if rank == 0 {
            let _ = std::fs::remove_file(&tmp);
        }
        return Err(e);
    }
    let done = if rank == 0 {
        let r = std::fs::File::open(&tmp)
            .and_then(|f| f.sync_all())
            .and_then(|_| std::fs::rename(&tmp, target))
            .map_err(|e| format!("{}: {e}", target.display()));
        if r.is_err() {
            let _ = std::fs::remove_file(&tmp);
        }
        r
    } else {
        Ok(())
    };
    agree(w, done)?;
    Ok(Written {
        n_vertices: total[0],
        n_cells: total[1..].iter().sum(),
        bytes: plan.file_len,
    })
}
