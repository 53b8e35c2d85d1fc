//! `query --relation R --all --out FILE`: every rank answers relation R for the items it owns
//! (its owned vertices; its owned top cells for `adj` and `ia-star`) with a structure built
//! over its local complex, and writes them as `starplex query --all --out` does
//! (`starplex_cli::export`, ids mapped back to the file's), so nothing is written twice.
//!
//! - **Exact answers.** A rank holds the full star of each vertex it owns, so VT, VV, link,
//!   star and vertex adjacency are the global answers. For the relations between top cells the
//!   ghost layer is first widened by one ring ([`dist::widen`]): the rank then holds every cell
//!   sharing a vertex with a cell it owns, hence every cell across each of its facets.
//! - **Output.** `--per-rank` writes `STEM.rankR.EXT` on each rank (its items in increasing
//!   id; `.npz` files carry their `ids`). Otherwise every rank writes its part beside the
//!   output and rank 0 merges the parts by item id into `FILE` (`.jsonl`, `.csv`, `.npz`): the bytes
//!   `starplex query FILE --all --out` writes. Rank 0 streams the merge (one line per rank in
//!   memory; for `.npz`, [`export::merge_npz`], a read buffer per rank and array).
//! - `pfaces` (every simplex): each rank lists the simplices whose smallest vertex it owns
//!   (it holds the star of that vertex, hence the simplex), and the merge orders them by
//!   dimension, then lexicographically, as the single process does.
use std::io::BufRead;
use std::path::{Path, PathBuf};
use std::time::Instant;

use mpi::traits::Communicator;
use serde_json::json;
use starplex::structures::{Structure, StructureOptions};
use starplex_cli::export::{self, IdMap, OutFormat, RelationKind};

use crate::comm::{self, agree, Failure, World};
use crate::dist::{self, Local, Spb, Split};

/// Options of the verb.
pub struct QueryArgs<'a> {
    /// The relation.
    pub relation: RelationKind,
    /// The structure each rank builds over its local complex.
    pub structure: Structure,
    /// Where the answers go.
    pub out: &'a Path,
    /// One file per rank instead of one merged file.
    pub per_rank: bool,
    /// The Stellar tree's bucketing threshold.
    pub kv: Option<u32>,
    /// One JSON summary.
    pub json: bool,
}

/// `STEM.TAG.EXT` beside `p`.
fn tagged(p: &Path, tag: &str) -> PathBuf {
    let stem = p
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    let ext = p
        .extension()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    p.with_file_name(format!("{stem}.{tag}.{ext}"))
}

/// The relations over top cells (items are owned top cells, the ghost layer is widened).
fn over_cells(r: RelationKind) -> bool {
    matches!(r, RelationKind::Adj | RelationKind::IaStar)
}

/// The sort key of a `.jsonl` or `.csv` line: its leading item id (`{"vertex":12,...` or
/// `12,...`), or for p-faces (`faces`) every number of the line, the dimension then the
/// simplex's vertices (`{"dim":2,"simplex":[4,7,9]}` or `2,4 7 9`).
fn key_of(line: &str, csv: bool, faces: bool) -> Vec<u64> {
    if faces {
        return line
            .split(|c: char| !c.is_ascii_digit())
            .filter(|w| !w.is_empty())
            .map(|w| w.parse().unwrap_or(u64::MAX))
            .collect();
    }
    let rest = if csv {
        line
    } else {
        line.split_once(':').map_or("", |(_, r)| r)
    };
    let digits = rest.bytes().take_while(u8::is_ascii_digit).count();
    vec![rest[..digits].parse().unwrap_or(u64::MAX)]
}

/// Merges the parts (each sorted by item or, for p-faces, by simplex; every item in one part)
/// into `out`, in that order.
fn merge(parts: &[PathBuf], out: &Path, csv: bool, faces: bool) -> Result<(), String> {
    let mut readers = Vec::with_capacity(parts.len());
    for p in parts {
        let f = std::fs::File::open(p).map_err(|e| format!("{}: {e}", p.display()))?;
        readers.push(std::io::BufReader::new(f).lines());
    }
    let next = |r: &mut std::io::Lines<std::io::BufReader<std::fs::File>>| {
        r.next().transpose().map_err(|e| e.to_string())
    };
    starplex::io::output::write_with(out, |w| {
        let io = |e: String| starplex::io::IoErrorKind::Os(std::io::Error::other(e));
        let mut head: Vec<Option<String>> = Vec::with_capacity(readers.len());
        for (i, r) in readers.iter_mut().enumerate() {
            let mut l = next(r).map_err(io)?;
            if csv {
                // every part starts with the header: write it once
                if i == 0
                    && let Some(h) = &l
                {
                    writeln!(w, "{h}")?;
                }
                l = next(r).map_err(io)?;
            }
            head.push(l);
        }
        loop {
            let best = head
                .iter()
                .enumerate()
                .filter_map(|(i, l)| l.as_ref().map(|l| (key_of(l, csv, faces), i)))
                .min();
            let Some((item, i)) = best else { break };
            // every line of this item (csv: one line per answer element)
            while let Some(l) = head[i].take() {
                if key_of(&l, csv, faces) != item {
                    head[i] = Some(l);
                    break;
                }
                writeln!(w, "{l}")?;
                head[i] = next(&mut readers[i]).map_err(io)?;
            }
        }
        Ok(())
    })
    .map_err(|e| e.to_string())
}

/// The verb (collective).
pub fn run(
    w: &World,
    a: &QueryArgs,
    file: &Path,
    f: &Spb,
    split: &Split,
    l: &mut Local,
    read_s: f64,
) -> Result<(), Failure> {
    let rank = w.rank() as usize;
    let fmt = agree(w, OutFormat::from_path(a.out).map_err(|e| e.to_string()))?;
    let target = agree(w, crate::write::target_of(a.out))?;
    let t0 = Instant::now();
    if over_cells(a.relation) {
        let held = std::mem::replace(l, Local::empty());
        *l = dist::widen(w, f, split, held)?;
    }
    let l = &*l;
    let opts = StructureOptions {
        kv: a.kv,
        ..Default::default()
    };
    let s = agree(
        w,
        a.structure
            .build(&l.k, &opts)
            .map_err(|e| format!("{}: {e}", file.display())),
    )?;
    let build_s = t0.elapsed().as_secs_f64();
    let items: Vec<u32> = if over_cells(a.relation) {
        (0..l.k.n_cells())
            .filter(|&c| l.owns_cell(c))
            .map(|c| c as u32)
            .collect()
    } else {
        l.owned.ones().map(|v| v as u32).collect()
    };
    let map = IdMap {
        vertices: &l.vertex_gid,
        cells: &l.cell_gid,
    };
    let mine = if a.per_rank {
        tagged(&target, &format!("rank{rank}"))
    } else {
        tagged(&target, &format!("part{rank}.starplex-mpi"))
    };
    let t1 = Instant::now();
    // p-faces: the simplices whose smallest vertex this rank owns (it holds their stars)
    let faces = a.relation == RelationKind::Pfaces;
    let wrote = export::write_mapped(
        s.as_ref(),
        a.relation,
        Some(&items),
        over_cells(a.relation) || faces,
        &mine,
        Some(&map),
    )
    .map_err(|e| e.to_string());
    let parts: Vec<PathBuf> = (0..w.size())
        .map(|r| tagged(&target, &format!("part{r}.starplex-mpi")))
        .collect();
    let (n_items, n_values) = match agree(w, wrote) {
        Ok(x) => x,
        Err(e) => {
            if !a.per_rank {
                let _ = std::fs::remove_file(&mine);
            }
            return Err(e);
        }
    };
    let merged = if !a.per_rank && rank == 0 {
        let r = if fmt == OutFormat::Npz {
            export::merge_npz(&parts, &target).map_err(|e| e.to_string())
        } else {
            merge(&parts, &target, fmt == OutFormat::Csv, faces)
        };
        for p in &parts {
            let _ = std::fs::remove_file(p);
        }
        r
    } else {
        Ok(())
    };
    agree(w, merged)?;
    let write_s = comm::max(w, (t1.elapsed().as_secs_f64() * 1e6) as u64) as f64 / 1e6;
    let build_s = comm::max(w, (build_s * 1e6) as u64) as f64 / 1e6;
    let sums = comm::sums(w, &[n_items, n_values]);
    if rank != 0 {
        return Ok(());
    }
    let files: Vec<String> = if a.per_rank {
        (0..w.size())
            .map(|r| tagged(a.out, &format!("rank{r}")).display().to_string())
            .collect()
    } else {
        vec![a.out.display().to_string()]
    };
    let v = json!({
        "input": file.display().to_string(),
        "relation": format!("{:?}", a.relation),
        "structure": format!("{:?}", a.structure),
        "ranks": w.size(),
        "items": sums[0],
        "answer_elements": sums[1],
        "files": files,
        "timings": {"read_s": read_s, "build_s": build_s, "write_s": write_s},
    });
    if a.json {
        crate::print_json(&v);
    } else {
        println!(
            "{}: {} items, {} answer elements -> {} ({} ranks; read {read_s:.3} s, build {build_s:.3} s, answer and write {write_s:.3} s, slowest rank)",
            file.display(),
            sums[0],
            sums[1],
            files.join(", "),
            w.size()
        );
    }
    Ok(())
}
