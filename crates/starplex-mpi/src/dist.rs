//! The distributed decomposition: the parallel read of a `.spb`, the spatial split of the
//! vertices, and each rank's local complex (the top cells incident to its vertices, with their
//! global ids).
//!
//! 1. Every rank maps the file and checks its header ([`binary::open_mapped`]); rank `r` reads
//!    only the `r`-th slice of the coordinate array and the `r`-th slice of the top cells (its
//!    byte ranges), plus the coordinates of the vertices those cells use.
//! 2. The bounding box is reduced over ranks; each vertex gets a Morton key (its first three
//!    coordinates, 21 bits each, ties broken by id). Ranks share a regular sample of their slice
//!    of top cells, each cell keyed by its smallest vertex (the vertex whose owner owns the cell),
//!    and all pick the same `P - 1` splitters, the P-quantiles of the sample: the owned top cells
//!    are balanced (vertices are sampled instead when there are no cells). The owner of a vertex
//!    is the range its key falls in, computable by any rank from the vertex's coordinates.
//! 3. Rank `r` sends every cell of its slice to the owner of each of its vertices (all-to-all):
//!    each rank receives the full star of every vertex it owns (owned + ghost cells). A cell is
//!    *owned* by the owner of its smallest vertex, a face likewise.
//! 4. Each rank numbers its vertices and cells in increasing global id, so that "smallest
//!    vertex" and "smallest cell" mean the same locally as globally, and builds an
//!    [`IndexedComplex`] over them.
use std::path::Path;
use std::sync::Arc;

use fixedbitset::FixedBitSet;
use rustc_hash::FxHashMap;
use starplex::attr::{AttrTarget, Attributes};
use starplex::buf::Buf;
use starplex::cell::CellKind;
use starplex::complex::IndexedComplex;
use starplex::io::binary::{self, SpbHeader};

use mpi::traits::Communicator;

use crate::comm::{self, agree, Failure, World};

/// A `.spb` file mapped by one rank (nothing is read until asked).
pub struct Spb {
    map: Arc<memmap2::Mmap>,
    /// The checked header.
    pub h: SpbHeader,
    /// First global cell id of each block, and the total at the end.
    starts: Vec<u64>,
    path: String,
    stamp: (u64, Option<std::time::SystemTime>),
}

fn stamp(path: &Path) -> Result<(u64, Option<std::time::SystemTime>), String> {
    let m = std::fs::metadata(path).map_err(|e| format!("{}: {e}", path.display()))?;
    Ok((m.len(), m.modified().ok()))
}

impl Spb {
    /// Maps `path`; text formats are refused with the command that converts them.
    pub fn open(path: &Path) -> Result<Spb, String> {
        let name = path.display().to_string();
        let mut magic = [0u8; 8];
        {
            use std::io::Read;
            let mut f = std::fs::File::open(path).map_err(|e| format!("{name}: {e}"))?;
            let n = f.read(&mut magic).map_err(|e| format!("{name}: {e}"))?;
            if n < 8 || magic != binary::MAGIC {
                return Err(format!(
                    "{name}: not a .spb file; starplex-mpi reads only the binary format, each rank its own byte ranges: convert it once with `starplex convert {name} {}` first",
                    path.with_extension("spb").display()
                ));
            }
        }
        let st = stamp(path)?;
        let (map, h) = binary::open_mapped(path).map_err(|e| e.to_string())?;
        let mut starts = Vec::with_capacity(h.blocks.len() + 1);
        let mut at = 0u64;
        for &(_, n, _) in &h.blocks {
            starts.push(at);
            at += n;
        }
        starts.push(at);
        Ok(Spb {
            map,
            h,
            starts,
            path: name,
            stamp: st,
        })
    }

    /// The largest dimension of the file's cells (`None` without cells).
    pub fn dim(&self) -> Option<usize> {
        self.h.blocks.iter().map(|&(k, _, _)| k.dim()).max()
    }

    /// An error when the file's length or modification time changed since it was opened.
    pub fn check_unchanged(&self) -> Result<(), String> {
        let now = stamp(Path::new(&self.path))?;
        if now != self.stamp {
            return Err(format!(
                "{}: the file changed while it was being read (length or modification time); run again on a file that is not being written",
                self.path
            ));
        }
        Ok(())
    }

    /// Drops the pages of the map this rank has read from its resident memory (once the local
    /// complex holds what it needs): they are clean pages of a read-only file mapping, so a
    /// later read faults them back in from the file. Advisory: an error is ignored.
    pub fn release_pages(&self) {
        // SAFETY: MADV_DONTNEED on a shared read-only file mapping only unmaps this process's
        // page references; the memory stays valid and reads return the file's bytes again (a
        // file truncated meanwhile raises SIGBUS, which `fault::guard_sigbus` turns into an
        // error). No reference into the map is invalidated.
        let _ = unsafe {
            self.map
                .unchecked_advise(memmap2::UncheckedAdvice::DontNeed)
        };
    }

    /// Coordinates of vertex `v` (checked in range by the caller).
    pub fn point(&self, v: u32) -> &[f64] {
        let d = self.h.ambient_dim;
        let at = self.h.coords_offset as usize + v as usize * d * 8;
        bytemuck::cast_slice(&self.map[at..at + d * 8])
    }

    /// The file's attribute columns for the given vertices and cells (global ids, checked in
    /// range by the caller), in the file's column order: what a local complex over them
    /// carries. The columns are fixed-width, so each value is read at its own offset.
    pub fn attributes_of(&self, vertices: &[u32], cells: &[u32]) -> Attributes {
        let mut a = Attributes::default();
        for e in &self.h.attrs {
            let c = e.components as usize;
            let items = match e.target {
                AttrTarget::Vertex => vertices,
                AttrTarget::Cell => cells,
            };
            let word = |i: u32, j: usize| {
                let at = e.offset as usize + (i as usize * c + j) * 8;
                &self.map[at..at + 8]
            };
            e.push_column(
                &mut a,
                items.iter().flat_map(|&i| (0..c).map(move |j| word(i, j))),
            );
        }
        a
    }

    /// The cells `[lo, hi)` of block `b`, as a flat vertex array.
    fn block_cells(&self, b: usize, lo: u64, hi: u64) -> &[u32] {
        let (kind, _, off) = self.h.blocks[b];
        let a = kind.n_vertices();
        let s = off as usize + lo as usize * a * 4;
        let e = off as usize + hi as usize * a * 4;
        bytemuck::cast_slice(&self.map[s..e])
    }

    /// The cells `[lo, hi)` (global ids), block by block: (block, global id of its first cell
    /// here, flat vertex array).
    fn cells_in(&self, lo: u64, hi: u64) -> impl Iterator<Item = (usize, u64, &[u32])> + '_ {
        let blocks = if lo < hi {
            self.block_of(lo)..self.block_of(hi - 1) + 1
        } else {
            0..0
        };
        blocks.map(move |b| {
            let (l, h) = (
                lo.max(self.starts[b]) - self.starts[b],
                hi.min(self.starts[b + 1]) - self.starts[b],
            );
            (b, self.starts[b] + l, self.block_cells(b, l, h))
        })
    }

    /// The block holding global cell `c`.
    fn block_of(&self, c: u64) -> usize {
        self.starts.partition_point(|&s| s <= c) - 1
    }
}

/// `[n * r / p, n * (r + 1) / p)`: rank `r`'s slice of `n` items.
pub fn slice(n: u64, r: usize, p: usize) -> (u64, u64) {
    let f = |i: usize| ((n as u128 * i as u128) / p as u128) as u64;
    (f(r), f(r + 1))
}

/// The spatial split every rank agrees on.
pub struct Split {
    lo: Vec<f64>,
    scale: Vec<f64>,
    splitters: Vec<(u64, u32)>,
    /// Shifted split: `P` splitters at the quantiles `(i + 1/2) / P`, the last range wrapping
    /// around to rank 0 (see [`split`]).
    wrap: bool,
    /// Every vertex to rank 0 ([`SplitKind::Rank0`]).
    rank0: bool,
    /// The bounding box of all vertices (`None` without vertices).
    pub bbox: Option<(Vec<f64>, Vec<f64>)>,
}

const BITS: u32 = 21;

fn spread(mut x: u64) -> u64 {
    // 21 bits -> every third bit
    x &= 0x1f_ffff;
    x = (x | (x << 32)) & 0x001f_0000_0000_ffff;
    x = (x | (x << 16)) & 0x001f_0000_ff00_00ff;
    x = (x | (x << 8)) & 0x100f_00f0_0f00_f00f;
    x = (x | (x << 4)) & 0x10c3_0c30_c30c_30c3;
    x = (x | (x << 2)) & 0x1249_2492_4924_9249;
    x
}

impl Split {
    /// The Morton key of a point (its first three coordinates).
    fn key(&self, p: &[f64]) -> u64 {
        let mut k = 0u64;
        for (i, (&x, (&lo, &s))) in p.iter().zip(self.lo.iter().zip(&self.scale)).enumerate() {
            let q = ((x - lo) * s).clamp(0.0, ((1u64 << BITS) - 1) as f64) as u64;
            k |= spread(q) << i;
        }
        k
    }

    /// The rank owning vertex `v` at `p`.
    pub fn owner(&self, v: u32, p: &[f64]) -> usize {
        if self.rank0 {
            return 0;
        }
        let kv = (self.key(p), v);
        let r = self.splitters.partition_point(|s| *s <= kv);
        if self.wrap && r == self.splitters.len() {
            0
        } else {
            r
        }
    }
}

/// Which split [`split`] makes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SplitKind {
    /// `P` ranges of Morton keys, balanced by owned top cells.
    Plain,
    /// Every boundary of the plain split moved to the middle of a rank's range: the `P`
    /// splitters are the quantiles `(i + 1/2) / P` of the sample and the keys above the last one
    /// go to rank 0 with those below the first. (`simplify` alternates the two, so what one
    /// round left near a boundary is inside a rank in the next.)
    Shifted,
    /// Every vertex to rank 0 (`simplify`'s last round on a complex already made small).
    Rank0,
}

/// Agrees on the split: bounding box, then splitters from a regular sample of Morton keys (of
/// the smallest vertex of this rank's slice of cells; of its vertex slice without cells).
pub fn split(w: &World, f: &Spb, kind: SplitKind) -> Result<Split, Failure> {
    let shifted = kind == SplitKind::Shifted;
    let (rank, p) = (w.rank() as usize, w.size() as usize);
    let d = f.h.ambient_dim;
    let (v0, v1) = slice(f.h.n_vertices, rank, p);
    let (mut lo, mut hi) = (vec![f64::INFINITY; d], vec![f64::NEG_INFINITY; d]);
    let mut bad = None;
    for v in v0..v1 {
        let q = f.point(v as u32);
        if bad.is_none() && q.iter().any(|x| !x.is_finite()) {
            bad = Some(format!(
                "{}: vertex {v} has a coordinate that is not finite",
                f.path
            ));
        }
        for i in 0..d {
            lo[i] = lo[i].min(q[i]);
            hi[i] = hi[i].max(q[i]);
        }
    }
    agree(w, bad.map_or(Ok(()), Err))?;
    let (lo, hi) = comm::min_max(w, &lo, &hi);
    let k = d.min(3);
    let scale: Vec<f64> = (0..k)
        .map(|i| {
            let ext = hi[i] - lo[i];
            if ext > 0.0 {
                ((1u64 << BITS) - 1) as f64 / ext
            } else {
                0.0
            }
        })
        .collect();
    let mut s = Split {
        lo: lo[..k].to_vec(),
        scale,
        splitters: Vec::new(),
        wrap: shifted && p > 1,
        rank0: kind == SplitKind::Rank0,
        bbox: (f.h.n_vertices > 0).then(|| (lo.clone(), hi.clone())),
    };
    // the sample the splitters are chosen from: balanced by top cells when there are cells
    // (each cell stands for its smallest vertex, whose owner owns the cell), by vertices else
    let per = (64 * p).max(4096);
    let sample = if f.h.n_cells > 0 {
        agree(w, cell_sample(f, &s, rank, p, per))?
    } else {
        let keys: Vec<(u64, u32)> = (v0..v1)
            .map(|v| (s.key(f.point(v as u32)), v as u32))
            .collect();
        strided(&keys, per)
    };
    let mut flat = Vec::with_capacity(2 * sample.len());
    for (k, v) in sample {
        flat.push(k);
        flat.push(v as u64);
    }
    let all = comm::all_gather(w, &flat);
    let mut all: Vec<(u64, u32)> = all.chunks_exact(2).map(|c| (c[0], c[1] as u32)).collect();
    all.sort_unstable();
    // the splitters cut the sorted sample in P equal parts; equal keys of the same vertex
    // (cells sharing their smallest vertex) fall on one side of a splitter, as they must
    s.splitters = if s.wrap {
        (0..p)
            .filter_map(|i| all.get((2 * i + 1) * all.len() / (2 * p)).copied())
            .collect()
    } else {
        (1..p)
            .filter_map(|i| all.get(i * all.len() / p).copied())
            .collect()
    };
    // fewer samples than ranks: the last ranks own nothing
    let want = if s.wrap { p } else { p - 1 };
    while s.splitters.len() < want {
        s.splitters.push((u64::MAX, u32::MAX));
    }
    Ok(s)
}

/// `per` items of `keys` at a regular stride (all of them when fewer).
fn strided(keys: &[(u64, u32)], per: usize) -> Vec<(u64, u32)> {
    let n = keys.len();
    if n <= per {
        return keys.to_vec();
    }
    (0..per).map(|i| keys[i * n / per]).collect()
}

/// A regular sample of this rank's slice of top cells, each cell as the key of its smallest
/// vertex: splitters cut from it balance the owned top cells (not the vertices). The cells
/// sampled are checked (vertex ids in range), the others are checked by `distribute`.
fn cell_sample(
    f: &Spb,
    s: &Split,
    rank: usize,
    p: usize,
    per: usize,
) -> Result<Vec<(u64, u32)>, String> {
    let (c0, c1) = slice(f.h.n_cells, rank, p);
    let n = (c1 - c0) as usize;
    let take = n.min(per);
    let mut out = Vec::with_capacity(take);
    for i in 0..take {
        let cid = c0 + (i * n / take) as u64;
        let b = f.block_of(cid);
        let cv = f.block_cells(b, cid - f.starts[b], cid - f.starts[b] + 1);
        let m = cv.iter().copied().min().unwrap_or(0);
        if let Some(&x) = cv.iter().find(|&&x| x as u64 >= f.h.n_vertices) {
            return Err(format!(
                "{}: cell {cid} has vertex {x}, but the file has {} vertices",
                f.path, f.h.n_vertices
            ));
        }
        out.push((s.key(f.point(m)), m));
    }
    Ok(out)
}

/// What one rank holds: its local complex over owned and ghost cells.
pub struct Local {
    /// The local complex (vertices and cells numbered in increasing global id).
    pub k: IndexedComplex,
    /// Global id of each local vertex.
    pub vertex_gid: Vec<u32>,
    /// Global id of each local cell.
    pub cell_gid: Vec<u32>,
    /// Local vertices this rank owns.
    pub owned: FixedBitSet,
    /// Owner rank of each local vertex.
    pub vertex_owner: Vec<u32>,
    /// Number of local cells this rank owns (those whose smallest vertex it owns).
    pub n_owned_cells: u64,
}

impl Local {
    /// Nothing held (a placeholder while a local complex is rebuilt).
    pub fn empty() -> Local {
        Local {
            k: IndexedComplex::from_parts(1, Buf::Owned(Vec::new()), Vec::new())
                .expect("the empty complex is valid"),
            vertex_gid: Vec::new(),
            cell_gid: Vec::new(),
            owned: FixedBitSet::new(),
            vertex_owner: Vec::new(),
            n_owned_cells: 0,
        }
    }

    /// True when this rank owns local cell `c` (it owns the cell's smallest vertex).
    pub fn owns_cell(&self, c: usize) -> bool {
        let cell = self.k.cell(starplex::ids::CellId(c as u32));
        let m = cell.vertices.iter().copied().min().unwrap_or(0);
        self.owned.contains(m as usize)
    }
}

/// The owners of the vertices of a slice of cells, each computed once ([`Split::owner`]).
struct OwnerCache {
    /// First vertex id of the table.
    first: u32,
    /// Owner + 1 of each vertex of the range (0: not computed yet); empty without a table.
    table: Vec<u16>,
}

impl OwnerCache {
    /// Entries at most (64 MB).
    const MAX: u64 = 1 << 25;

    /// A table over the vertex ids of the cells `[c0, c1)` when their range has at most
    /// [`OwnerCache::MAX`] ids and the ranks fit; none otherwise (owners are then computed at
    /// each use). Vertex ids out of range are left to the walk, which reports them.
    fn new(f: &Spb, c0: u64, c1: u64, p: usize) -> OwnerCache {
        let none = OwnerCache {
            first: 0,
            table: Vec::new(),
        };
        if c0 >= c1 || p >= u16::MAX as usize {
            return none;
        }
        let (mut lo, mut hi) = (u32::MAX, 0u32);
        for (_, _, verts) in f.cells_in(c0, c1) {
            for &v in verts {
                lo = lo.min(v);
                hi = hi.max(v);
            }
        }
        let hi = hi.min(f.h.n_vertices.saturating_sub(1) as u32);
        if lo > hi || u64::from(hi - lo) + 1 > Self::MAX {
            return none;
        }
        OwnerCache {
            first: lo,
            table: vec![0; (hi - lo) as usize + 1],
        }
    }

    /// The owner of vertex `v` (in range of the file).
    fn get(&mut self, s: &Split, f: &Spb, v: u32) -> usize {
        let i = v.wrapping_sub(self.first) as usize;
        match self.table.get_mut(i) {
            Some(slot) if v >= self.first => {
                if *slot == 0 {
                    *slot = s.owner(v, f.point(v)) as u16 + 1;
                }
                usize::from(*slot - 1)
            }
            _ => s.owner(v, f.point(v)),
        }
    }
}

/// Called with (destination rank, global cell id, block, vertices) for each cell sent.
type CellVisit<'a> = dyn FnMut(usize, u64, usize, &[u32]) + 'a;

/// Values (`u32`) a rank packs per round of the cell shuffle, at most (64 MB): the shuffle runs
/// in as many rounds as the fullest rank needs, so its buffers stay bounded whatever the file.
const ROUND_VALUES: usize = 1 << 24;

/// Reads this rank's slices, sends every cell to the owners of its vertices, builds the local
/// complex.
///
/// The cells go in rounds (each rank's slice cut into the same number of consecutive pieces,
/// about [`ROUND_VALUES`] values each), after one exchange of counts per (destination, block):
/// every receiver knows where each sender's cells go in its local blocks (senders in rank
/// order are in cell-id order, and so are a sender's rounds), and writes every record straight
/// there. The peak is the local complex plus one round's buffers, not the whole send and
/// receive buffers beside it.
pub fn distribute(w: &World, f: &Spb, s: &Split) -> Result<Local, Failure> {
    let (rank, p) = (w.rank() as usize, w.size() as usize);
    let nv = f.h.n_vertices;
    let nb = f.h.blocks.len();
    // owned vertices: each rank tells the owners of its vertex slice
    let (v0, v1) = slice(nv, rank, p);
    let mut out: Vec<Vec<u32>> = vec![Vec::new(); p];
    for v in v0..v1 {
        out[s.owner(v as u32, f.point(v as u32))].push(v as u32);
    }
    let mut owned_gids: Vec<u32> = comm::exchange(w, out)?.into_flat();
    owned_gids.sort_unstable();
    // cells: [id, block, vertices...] to the owner of each vertex
    let (c0, c1) = slice(f.h.n_cells, rank, p);
    let mut ranks: Vec<usize> = Vec::with_capacity(8);
    // the owner of every vertex the slice's cells use, computed once (the cells are walked once
    // to count and once per round, and each vertex is in several cells): a table over the range
    // of their ids, which is narrow for a file in space order; none when it is too wide
    let mut owners = OwnerCache::new(f, c0, c1, p);
    let mut walk = |lo_c: u64, hi_c: u64, visit: &mut CellVisit| -> Result<(), String> {
        for (b, first, verts) in f.cells_in(lo_c, hi_c) {
            let a = f.h.blocks[b].0.n_vertices();
            for (i, cv) in verts.chunks_exact(a).enumerate() {
                let cid = first + i as u64;
                if let Some(&x) = cv.iter().find(|&&x| x as u64 >= nv) {
                    return Err(format!(
                        "{}: cell {cid} has vertex {x}, but the file has {nv} vertices",
                        f.path
                    ));
                }
                if (1..a).any(|j| cv[..j].contains(&cv[j])) {
                    return Err(format!("{}: cell {cid} repeats a vertex: {cv:?}", f.path));
                }
                ranks.clear();
                ranks.extend(cv.iter().map(|&x| owners.get(s, f, x)));
                ranks.sort_unstable();
                ranks.dedup();
                for &r in &ranks {
                    visit(r, cid, b, cv);
                }
            }
        }
        Ok(())
    };
    // cells per (destination, block), and the values to send
    let mut cells_to = vec![0u32; p * nb];
    let mut values = 0usize;
    let counted = walk(c0, c1, &mut |r, _, b, cv| {
        cells_to[r * nb + b] += 1;
        values += 2 + cv.len();
    });
    agree(w, counted)?;
    // (STARPLEX_MPI_ROUND_VALUES sets a smaller round, for the tests of many rounds)
    let per_round = std::env::var("STARPLEX_MPI_ROUND_VALUES")
        .ok()
        .and_then(|x| x.parse::<usize>().ok())
        .filter(|&x| x > 0)
        .unwrap_or(ROUND_VALUES);
    let rounds = comm::max(w, values.div_ceil(per_round).max(1) as u64) as usize;
    // what every sender will send here, per block: the places of its cells in the local blocks
    let from = comm::exchange(w, cells_to.chunks(nb).map(<[u32]>::to_vec).collect())?;
    let from: Vec<Vec<u32>> = from.parts().map(<[u32]>::to_vec).collect();
    let arity = |b: usize| f.h.blocks[b].0.n_vertices();
    let mut n_block = vec![0usize; nb];
    // cursor[r][b]: where sender r's next cell of block b goes (cells), senders in rank order
    let mut cursor = vec![vec![0usize; nb]; p];
    for b in 0..nb {
        for r in 0..p {
            cursor[r][b] = n_block[b];
            n_block[b] += from[r][b] as usize;
        }
    }
    let mut block_cells: Vec<Vec<u32>> =
        (0..nb).map(|b| vec![0u32; n_block[b] * arity(b)]).collect();
    let mut block_gid: Vec<Vec<u32>> = (0..nb).map(|b| vec![0u32; n_block[b]]).collect();
    let mut held = FixedBitSet::with_capacity(nv as usize);
    for &g in &owned_gids {
        held.insert(g as usize);
    }
    let mut counts = vec![0usize; p];
    for t in 0..rounds {
        let (lo, hi) = (
            c0 + (c1 - c0) * t as u64 / rounds as u64,
            c0 + (c1 - c0) * (t as u64 + 1) / rounds as u64,
        );
        // packed by destination in two passes (count, then fill): the send buffer is one copy
        counts.iter_mut().for_each(|c| *c = 0);
        agree(
            w,
            walk(lo, hi, &mut |r, _, _, cv| counts[r] += 2 + cv.len()),
        )?;
        let mut at: Vec<usize> = counts
            .iter()
            .scan(0, |acc, &c| {
                let start = *acc;
                *acc += c;
                Some(start)
            })
            .collect();
        let mut flat = vec![0u32; counts.iter().sum()];
        agree(
            w,
            walk(lo, hi, &mut |r, cid, b, cv| {
                let o = &mut flat[at[r]..at[r] + 2 + cv.len()];
                o[0] = cid as u32;
                o[1] = b as u32;
                o[2..].copy_from_slice(cv);
                at[r] += 2 + cv.len();
            }),
        )?;
        // the pages of the map this round read leave the resident set
        f.release_pages();
        let got = comm::exchange_packed(w, flat, &counts)?;
        let mut bad = None;
        for (r, g) in got.parts().enumerate() {
            let mut i = 0;
            while i + 1 < g.len() {
                let b = g[i + 1] as usize;
                let a = if b < nb { arity(b) } else { usize::MAX };
                if a == usize::MAX || i + 2 + a > g.len() || cursor[r][b] >= n_block[b] {
                    bad = Some(format!("internal error: a bad cell record from rank {r}"));
                    break;
                }
                let c = cursor[r][b];
                block_gid[b][c] = g[i];
                let dst = &mut block_cells[b][c * a..(c + 1) * a];
                dst.copy_from_slice(&g[i + 2..i + 2 + a]);
                for &v in dst.iter() {
                    held.insert(v as usize);
                }
                cursor[r][b] = c + 1;
                i += 2 + a;
            }
        }
        agree(w, bad.map_or(Ok(()), Err))?;
    }
    // every cell arrived where it was announced, in increasing cell id
    let complete = (0..p).all(|r| {
        (0..nb).all(|b| {
            let start: usize = (0..r).map(|q| from[q][b] as usize).sum();
            cursor[r][b] == start + from[r][b] as usize
        })
    }) && block_gid.iter().all(|g| g.windows(2).all(|x| x[0] < x[1]));
    comm::agree_that(
        w,
        complete,
        "internal error: cells missing after the shuffle",
    )?;
    // local numbering: vertices in increasing global id
    let (gids, local, owned) = numbering(held, &owned_gids);
    for cells in &mut block_cells {
        for v in cells.iter_mut() {
            *v = local[v];
        }
    }
    drop(local);
    let cell_gid: Vec<u32> = block_gid.into_iter().flatten().collect();
    let blocks: Vec<(CellKind, Buf<u32>)> = block_cells
        .into_iter()
        .enumerate()
        .filter(|(_, v)| !v.is_empty())
        .map(|(b, v)| (f.h.blocks[b].0, Buf::Owned(v)))
        .collect();
    local_complex(w, f, s, gids, owned, cell_gid, blocks)
}

/// The local numbering of the held vertices (a bit per vertex of the file): their global ids
/// in increasing order, the map from global to local id, and the owned ones as local bits.
fn numbering(
    held: FixedBitSet,
    owned_gids: &[u32],
) -> (Vec<u32>, FxHashMap<u32, u32>, FixedBitSet) {
    let gids: Vec<u32> = held.ones().map(|v| v as u32).collect();
    drop(held);
    let local: FxHashMap<u32, u32> = gids
        .iter()
        .enumerate()
        .map(|(i, &g)| (g, i as u32))
        .collect();
    let mut owned = FixedBitSet::with_capacity(gids.len());
    for g in owned_gids {
        owned.insert(local[g] as usize);
    }
    (gids, local, owned)
}

/// The [`Local`] of numbered vertices (`gids`, increasing), owned ones, cells (in increasing
/// global id, `cell_gid`) and their blocks in local vertex ids.
fn local_complex(
    w: &World,
    f: &Spb,
    s: &Split,
    gids: Vec<u32>,
    owned: FixedBitSet,
    cell_gid: Vec<u32>,
    blocks: Vec<(CellKind, Buf<u32>)>,
) -> Result<Local, Failure> {
    let d = f.h.ambient_dim;
    let mut coords = Vec::with_capacity(gids.len() * d);
    let mut vertex_owner = Vec::with_capacity(gids.len());
    for &g in &gids {
        let q = f.point(g);
        coords.extend_from_slice(q);
        vertex_owner.push(s.owner(g, q) as u32);
    }
    let k = agree(
        w,
        IndexedComplex::from_parts(d, Buf::Owned(coords), blocks)
            .map_err(|e| format!("{}: {e}", f.path)),
    )?;
    let mut l = Local {
        k,
        vertex_gid: gids,
        cell_gid,
        owned,
        vertex_owner,
        n_owned_cells: 0,
    };
    l.n_owned_cells = (0..l.k.n_cells()).filter(|&c| l.owns_cell(c)).count() as u64;
    Ok(l)
}

/// The local complex of the cell records `[global id, block, global vertex ids...]` of
/// `streams`, each sorted by global cell id (a cell in two streams is kept once), this rank
/// owning `owned_gids` (sorted). The streams are merged in place: no record array, no sort.
fn assemble(
    w: &World,
    f: &Spb,
    s: &Split,
    owned_gids: Vec<u32>,
    streams: &[&[u32]],
) -> Result<Local, Failure> {
    let arity = |b: u32| f.h.blocks[b as usize].0.n_vertices();
    // every stream sorted by cell id (the senders walk their cells in that order)
    let sorted = streams.iter().all(|g| {
        let (mut i, mut last) = (0, None);
        while i + 1 < g.len() {
            if last.is_some_and(|l| g[i] <= l) {
                return false;
            }
            last = Some(g[i]);
            i += 2 + arity(g[i + 1]);
        }
        true
    });
    comm::agree_that(w, sorted, "internal error: cell records out of order")?;
    // the vertices held: a bit per vertex of the file
    let mut held = FixedBitSet::with_capacity(f.h.n_vertices as usize);
    for &g in &owned_gids {
        held.insert(g as usize);
    }
    for g in streams {
        let mut i = 0;
        while i < g.len() {
            let a = arity(g[i + 1]);
            for &v in &g[i + 2..i + 2 + a] {
                held.insert(v as usize);
            }
            i += 2 + a;
        }
    }
    let (gids, local, owned) = numbering(held, &owned_gids);
    // one local block per global block, cells in increasing global id: a merge of the streams
    let mut blocks: Vec<(CellKind, Vec<u32>)> =
        f.h.blocks
            .iter()
            .map(|&(k, _, _)| (k, Vec::new()))
            .collect();
    let mut cell_gid = Vec::new();
    let mut heads: std::collections::BinaryHeap<std::cmp::Reverse<(u32, usize)>> = streams
        .iter()
        .enumerate()
        .filter(|(_, g)| !g.is_empty())
        .map(|(k, g)| std::cmp::Reverse((g[0], k)))
        .collect();
    let mut at = vec![0usize; streams.len()];
    while let Some(std::cmp::Reverse((cid, k))) = heads.pop() {
        let g = streams[k];
        let i = at[k];
        let (b, a) = (g[i + 1], arity(g[i + 1]));
        if cell_gid.last() != Some(&cid) {
            blocks[b as usize]
                .1
                .extend(g[i + 2..i + 2 + a].iter().map(|v| local[v]));
            cell_gid.push(cid);
        }
        at[k] = i + 2 + a;
        if at[k] < g.len() {
            heads.push(std::cmp::Reverse((g[at[k]], k)));
        }
    }
    let blocks: Vec<(CellKind, Buf<u32>)> = blocks
        .into_iter()
        .filter(|(_, v)| !v.is_empty())
        .map(|(k, v)| (k, Buf::Owned(v)))
        .collect();
    local_complex(w, f, s, gids, owned, cell_gid, blocks)
}

/// Widens the ghost layer of `l` by one ring: every rank also receives, from their owners, the
/// stars of the ghost vertices of the cells it owns. Afterwards a rank holds every cell that
/// shares a vertex with a cell it owns, so relations between top cells (adjacency across
/// facets, IA*) are exact for its owned cells. Ownership does not change.
pub fn widen(w: &World, f: &Spb, s: &Split, l: Local) -> Result<Local, Failure> {
    let (rank, p) = (w.rank() as usize, w.size() as usize);
    // the ghost vertices of owned cells, asked from their owners
    let mut ask: Vec<Vec<u32>> = vec![Vec::new(); p];
    for c in l.k.cells() {
        if !l.owns_cell(c.id.index()) {
            continue;
        }
        for &v in c.vertices {
            let o = l.vertex_owner[v as usize] as usize;
            if o != rank {
                ask[o].push(l.vertex_gid[v as usize]);
            }
        }
    }
    for a in &mut ask {
        a.sort_unstable();
        a.dedup();
    }
    let asked = comm::exchange(w, ask)?;
    // the stars asked for: each cell once per asking rank
    let n = l.vertex_gid.len();
    let wanted: Vec<FixedBitSet> = asked
        .parts()
        .map(|q| {
            let mut b = FixedBitSet::with_capacity(n);
            for g in q {
                if let Ok(i) = l.vertex_gid.binary_search(g) {
                    b.insert(i);
                }
            }
            b
        })
        .collect();
    let block_of = |cid: u32| f.block_of(cid as u64) as u32;
    let record = |dst: &mut Vec<u32>, cid: u32, verts: &[u32]| {
        dst.push(cid);
        dst.push(block_of(cid));
        dst.extend(verts.iter().map(|&v| l.vertex_gid[v as usize]));
    };
    let mut out: Vec<Vec<u32>> = vec![Vec::new(); p];
    for c in l.k.cells() {
        let cid = l.cell_gid[c.id.index()];
        for (r, b) in wanted.iter().enumerate() {
            if r != rank && c.vertices.iter().any(|&v| b.contains(v as usize)) {
                record(&mut out[r], cid, c.vertices);
            }
        }
    }
    let got = comm::exchange(w, out)?;
    // this rank's own cells, as records too
    let mut mine = Vec::new();
    for c in l.k.cells() {
        record(&mut mine, l.cell_gid[c.id.index()], c.vertices);
    }
    let owned: Vec<u32> = l.owned.ones().map(|v| l.vertex_gid[v]).collect();
    drop(l);
    let mut streams: Vec<&[u32]> = got.parts().collect();
    streams.push(&mine);
    assemble(w, f, s, owned, &streams)
}
