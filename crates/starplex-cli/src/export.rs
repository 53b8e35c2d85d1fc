//! `query ... --out FILE`: every answer written as `.jsonl` (streamed, one object per item),
//! `.npz` (CSR `offsets` / `values` arrays and the item `ids`) or `.csv` (one line per item and
//! answer element). The answers come from `starplex::topo::batch`, the same code as the Python
//! bindings.
use std::io::Write;
use std::path::Path;

use starplex::io::{output, IoErrorKind};
use starplex::topo::batch::{self, Answers, Relation};
use starplex::topo::{Queries, QueryError};

use crate::error::CliError;

/// The relations of `query --relation` (and of `starplex-mpi query`).
///
/// ```
/// use clap::ValueEnum;
/// use starplex_cli::export::RelationKind;
/// assert_eq!(RelationKind::from_str("ia-star", false), Ok(RelationKind::IaStar));
/// ```
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum RelationKind {
    /// Top cells incident to a vertex.
    Vt,
    /// Vertices adjacent to a vertex.
    Vv,
    /// Link of a vertex.
    Link,
    /// Star of a vertex.
    Star,
    /// p-faces: the co-boundaries R_{0,q} of a vertex; with --all every p-simplex.
    Pfaces,
    /// Adjacency: R_{0,0} of a vertex; with --all R_{k,k} of every top k-simplex.
    Adj,
    /// The IA* relations extracted through the interface: adjacent tops across each facet.
    IaStar,
}

/// Items answered (and held in memory) per block of a streamed output.
const BLOCK: usize = 1 << 16;

/// The output formats of `query --out`.
///
/// ```
/// use starplex_cli::export::OutFormat;
/// assert_eq!(OutFormat::from_path("a.npz".as_ref()).unwrap(), OutFormat::Npz);
/// assert!(OutFormat::from_path("a.txt".as_ref()).is_err());
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OutFormat {
    Jsonl,
    Npz,
    Csv,
}

impl OutFormat {
    /// The format named by the output's extension (`.jsonl`, `.npz`, `.csv`).
    ///
    /// ```
    /// use starplex_cli::export::OutFormat;
    /// assert_eq!(OutFormat::from_path("x.jsonl".as_ref()).unwrap(), OutFormat::Jsonl);
    /// ```
    ///
    /// # Errors
    /// Any other extension, with a hint.
    pub fn from_path(p: &Path) -> Result<OutFormat, CliError> {
        match p.extension().and_then(|e| e.to_str()) {
            Some("jsonl") => Ok(OutFormat::Jsonl),
            Some("npz") => Ok(OutFormat::Npz),
            Some("csv") => Ok(OutFormat::Csv),
            _ => Err(CliError::Input(
                format!("{}: --out writes .jsonl, .npz or .csv", p.display()),
                Some("name the output file with one of these extensions".into()),
            )),
        }
    }
}

/// Reads vertex ids from a file (`-`: standard input): integers separated by white space or
/// commas.
///
/// ```
/// let p = std::env::temp_dir().join(format!("starplex-doc-ids-{}.txt", std::process::id()));
/// std::fs::write(&p, "1 2,3\n4").unwrap();
/// assert_eq!(starplex_cli::export::read_ids(&p).unwrap(), vec![1, 2, 3, 4]);
/// # std::fs::remove_file(&p).ok();
/// ```
///
/// # Errors
/// An unreadable file, a token that is not a vertex id (with its line).
pub fn read_ids(p: &Path) -> Result<Vec<u32>, CliError> {
    let text = if p.as_os_str() == "-" {
        let mut s = String::new();
        std::io::Read::read_to_string(&mut std::io::stdin(), &mut s)
            .map_err(|e| CliError::Input(format!("standard input: {e}"), None))?;
        s
    } else {
        std::fs::read_to_string(p)
            .map_err(|e| CliError::Input(format!("{}: {e}", p.display()), None))?
    };
    let mut out = Vec::new();
    for (ln, line) in text.lines().enumerate() {
        for tok in line
            .split(|c: char| c.is_whitespace() || c == ',')
            .filter(|t| !t.is_empty())
        {
            let v: u32 = tok.parse().map_err(|_| {
                CliError::Input(
                    format!(
                        "{}:{}: '{tok}' is not a vertex id",
                        if p.as_os_str() == "-" {
                            "standard input".to_string()
                        } else {
                            p.display().to_string()
                        },
                        ln + 1
                    ),
                    None,
                )
            })?;
            out.push(v);
        }
    }
    Ok(out)
}

fn qerr(e: QueryError) -> IoErrorKind {
    IoErrorKind::Parse(e.to_string())
}

/// What one relation is over: vertices, top cells or levels.
enum Plan {
    /// Ids per item (vt, vv, adjacent tops).
    Ids(Relation),
    /// Simplices per item, level by level (link, star).
    Levels { link: bool },
    /// The simplices adjacent to each top cell (rows of the cell's size).
    AdjTops,
    /// The vertices adjacent to each vertex through an edge (R_{0,0}).
    AdjVertices,
    /// Every p-simplex of every level.
    Faces,
}

fn plan(r: RelationKind, all: bool) -> Result<Plan, CliError> {
    Ok(match r {
        RelationKind::Vt => Plan::Ids(Relation::Vt),
        RelationKind::Vv => Plan::Ids(Relation::Vv),
        RelationKind::Link => Plan::Levels { link: true },
        RelationKind::Star => Plan::Levels { link: false },
        RelationKind::Adj if all => Plan::AdjTops,
        RelationKind::Adj => Plan::AdjVertices,
        RelationKind::IaStar if all => Plan::Ids(Relation::Tt),
        RelationKind::Pfaces if all => Plan::Faces,
        RelationKind::IaStar | RelationKind::Pfaces => {
            return Err(CliError::Input(
                "--out with --relation ia-star or pfaces needs --all".into(),
                None,
            ))
        }
    })
}

/// The key of the item and of the answer in `.jsonl` / `.csv`.
fn names(r: RelationKind, all: bool) -> (&'static str, &'static str) {
    match r {
        RelationKind::Vt => ("vertex", "incident_top_cells"),
        RelationKind::Vv => ("vertex", "vv"),
        RelationKind::Link => ("vertex", "link"),
        RelationKind::Star => ("vertex", "star"),
        RelationKind::Adj if all => ("cell", "adjacent"),
        RelationKind::Adj => ("vertex", "adjacent"),
        RelationKind::IaStar => ("cell", "adjacent_top_cells"),
        RelationKind::Pfaces => ("dim", "simplex"),
    }
}

/// Global ids of a structure's vertices and top cells: [`write_mapped`] writes them instead of
/// the structure's own (a rank of `starplex-mpi` answers for its local complex in the file's
/// numbering).
///
/// ```
/// use starplex_cli::export::IdMap;
/// let m = IdMap { vertices: &[3, 7, 9], cells: &[5] };
/// assert_eq!((m.vertices[1], m.cells[0]), (7, 5));
/// ```
#[derive(Clone, Copy, Debug)]
pub struct IdMap<'a> {
    /// Global id of each vertex.
    pub vertices: &'a [u32],
    /// Global id of each top cell.
    pub cells: &'a [u32],
}

/// Which numbering the items and the answer elements of a plan are in.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Ids {
    Vertex,
    Cell,
}

fn id_kinds(p: &Plan) -> (Ids, Ids) {
    match p {
        Plan::Ids(Relation::Vt) => (Ids::Vertex, Ids::Cell),
        Plan::Ids(Relation::Tt) => (Ids::Cell, Ids::Cell),
        Plan::Ids(Relation::Tv) | Plan::AdjTops => (Ids::Cell, Ids::Vertex),
        _ => (Ids::Vertex, Ids::Vertex),
    }
}

impl IdMap<'_> {
    fn table(&self, k: Ids) -> &[u32] {
        match k {
            Ids::Vertex => self.vertices,
            Ids::Cell => self.cells,
        }
    }
}

/// `values` in the numbering of `map` (unchanged without one).
fn map_in_place(map: Option<&IdMap>, k: Ids, values: &mut [u32]) {
    if let Some(m) = map {
        let t = m.table(k);
        for v in values {
            *v = t[*v as usize];
        }
    }
}

/// Writes relation `r` of `items` (None: every vertex or top cell) to `out`. Returns the number
/// of items and of answer elements (ids or simplices).
///
/// ```
/// use starplex_cli::export::{write, RelationKind};
/// use starplex::structures::Structure;
/// let k = starplex::generate::kuhn_grid(&[2, 2]).unwrap();
/// let s = Structure::Stellar.build(&k, &Default::default()).unwrap();
/// let out = std::env::temp_dir().join(format!("starplex-doc-export-{}.jsonl", std::process::id()));
/// let (items, values) = write(s.as_ref(), RelationKind::Vt, Some(&[4]), &out).unwrap();
/// assert_eq!((items, values), (1, 6)); // the centre of a 2x2 grid is in 6 triangles
/// let line = std::fs::read_to_string(&out).unwrap();
/// assert!(line.starts_with("{\"vertex\":4,\"incident_top_cells\":["));
/// # std::fs::remove_file(&out).ok();
/// ```
///
/// # Errors
/// An unknown output extension, items out of range, a relation that needs `all`, a query or
/// write error.
pub fn write(
    s: &(dyn Queries + Sync),
    r: RelationKind,
    items: Option<&[u32]>,
    out: &Path,
) -> Result<(u64, u64), CliError> {
    write_mapped(s, r, items, items.is_none(), out, None)
}

/// [`write`], with every item and answer element written in the numbering of `map` (the items
/// are given in the structure's own numbering). `all` asks for what `--all` writes (adjacent
/// tops and IA* of top cells, every simplex for p-faces); with `items` as well, only those
/// items (top cells for adj and ia-star; for p-faces, the simplices whose smallest vertex is
/// one of them).
///
/// ```
/// use starplex_cli::export::{write_mapped, IdMap, RelationKind};
/// use starplex::structures::Structure;
/// let k = starplex::generate::kuhn_grid(&[1, 1]).unwrap(); // 4 vertices, 2 triangles
/// let s = Structure::Stellar.build(&k, &Default::default()).unwrap();
/// let out = std::env::temp_dir().join(format!("starplex-doc-export-map-{}.csv", std::process::id()));
/// let map = IdMap { vertices: &[10, 11, 12, 13], cells: &[20, 21] };
/// write_mapped(s.as_ref(), RelationKind::Vv, Some(&[0]), false, &out, Some(&map)).unwrap();
/// let text = std::fs::read_to_string(&out).unwrap();
/// assert!(text.lines().skip(1).all(|l| l.starts_with("10,1")));
/// # std::fs::remove_file(&out).ok();
/// ```
///
/// # Errors
/// As [`write`].
pub fn write_mapped(
    s: &(dyn Queries + Sync),
    r: RelationKind,
    items: Option<&[u32]>,
    all: bool,
    out: &Path,
    map: Option<&IdMap>,
) -> Result<(u64, u64), CliError> {
    let fmt = OutFormat::from_path(out)?;
    let p = plan(r, all)?;
    let n_items = match &p {
        Plan::Ids(rel) => rel.n_items(s),
        Plan::AdjTops => s.n_top_cells(),
        _ => s.n_vertices(),
    };
    let owned;
    let given = items.is_some();
    let items: &[u32] = match items {
        Some(v) => {
            let what = if matches!(p, Plan::Ids(Relation::Tt) | Plan::AdjTops) {
                "cell"
            } else {
                "vertex"
            };
            batch::check_items(v, n_items, what).map_err(|m| CliError::Input(m, None))?;
            v
        }
        // p-faces are not listed by item
        None if matches!(p, Plan::Faces) => &[],
        None => {
            owned = batch::all(n_items);
            &owned
        }
    };
    // p-faces with items: the simplices whose smallest vertex is one of them
    let keep: Option<Vec<bool>> = match (&p, given) {
        (Plan::Faces, true) => {
            let mut k = vec![false; n_items];
            items.iter().for_each(|&v| k[v as usize] = true);
            Some(k)
        }
        _ => None,
    };
    let kept = |smallest: Option<u32>| {
        keep.as_ref()
            .is_none_or(|k| smallest.is_some_and(|v| k[v as usize]))
    };
    let (item_key, answer_key) = names(r, all);
    let (item_ids, value_ids) = id_kinds(&p);
    let item_id = |i: u32| map.map_or(i, |m| m.table(item_ids)[i as usize]);
    let mut counts = (0u64, 0u64);
    let tops = |chunk: &[u32]| -> Result<(Vec<u32>, Vec<usize>), QueryError> {
        // the top cells' vertices, and each cell's size
        let c = batch::gather(s, Relation::Tv, chunk)?;
        let w = (0..c.n_rows()).map(|i| c.row(i).len()).collect();
        Ok((c.values, w))
    };
    // adjacent tops of many cells of a simplicial complex of dimension d >= 1: for a d-cell, the
    // d-simplices across its facets are the d-cells there (every d-simplex is a top cell), read
    // from the TT rows of every cell made at once
    let tt_all: Option<(batch::Answers, usize)> =
        match (&p, starplex::algo::manifold::complex_dim(s)) {
            (Plan::AdjTops, Some(d)) if d >= 1 && batch::is_bulk(s, Relation::Tt, items.len()) => {
                match batch::facet_neighbours_all(s) {
                    Some(tt) => Some((tt.map_err(|e| CliError::Other(e.to_string()))?, d)),
                    None => None,
                }
            }
            _ => None,
        };
    // one block of answers: (per-level CSR, the width of one simplex per row or level)
    let answer_block_local = |chunk: &[u32]| -> Result<(Vec<Answers>, Widths), QueryError> {
        Ok(match &p {
            Plan::Ids(rel) => (vec![batch::gather(s, *rel, chunk)?], Widths::Ids),
            Plan::Levels { link } => (batch::levels(s, *link, chunk)?, Widths::Levels),
            Plan::AdjVertices => (vec![batch::adjacent(s, chunk, 1)?], Widths::Fixed(1)),
            Plan::AdjTops => {
                let (tv, w) = tops(chunk)?;
                if let Some((tt, d)) = &tt_all
                    && w.iter().all(|&k| k == d + 1)
                {
                    let mut c = Answers {
                        offsets: vec![0],
                        values: Vec::new(),
                    };
                    let (mut row, mut vs) = (Vec::new(), Vec::new());
                    for &x in chunk {
                        row.clear();
                        for &u in tt.row(x as usize) {
                            vs.clear();
                            s.top_cell_vertices(starplex::ids::CellId(u), &mut vs);
                            vs.sort_unstable();
                            row.extend(vs.iter().map(|v| v.0));
                        }
                        starplex::topo::sort_flat(&mut row, d + 1);
                        c.values.extend_from_slice(&row);
                        c.offsets.push(c.values.len() as u64);
                    }
                    return Ok((vec![c], Widths::PerRow(w)));
                }
                if let Some(&k) = w.first().filter(|&&k| w.iter().all(|&x| x == k)) {
                    // one size of cell (the usual case): one batched call
                    return Ok((vec![batch::adjacent(s, &tv, k)?], Widths::PerRow(w)));
                }
                // cells of mixed sizes, one at a time
                let mut rows: Vec<Vec<u32>> = vec![Vec::new(); chunk.len()];
                let mut start = 0;
                for (i, &k) in w.iter().enumerate() {
                    let a = batch::adjacent(s, &tv[start..start + k], k)?;
                    rows[i] = a.values;
                    start += k;
                }
                let mut c = Answers {
                    offsets: vec![0],
                    values: Vec::new(),
                };
                for r in rows {
                    c.values.extend(r);
                    c.offsets.push(c.values.len() as u64);
                }
                (vec![c], Widths::PerRow(w))
            }
            Plan::Faces => unreachable!("levels are written whole"),
        })
    };
    let answer_block = |chunk: &[u32]| -> Result<(Vec<Answers>, Widths), QueryError> {
        let (mut lv, widths) = answer_block_local(chunk)?;
        for c in &mut lv {
            map_in_place(map, value_ids, &mut c.values);
        }
        Ok((lv, widths))
    };
    output::write_with(out, |w| {
        match fmt {
            OutFormat::Jsonl | OutFormat::Csv => {
                let csv = fmt == OutFormat::Csv;
                if csv {
                    writeln!(w, "{item_key},{answer_key}")?;
                }
                if let Plan::Faces = p {
                    for dim in 0..n_levels(s) {
                        let mut err = Ok(());
                        s.for_each_simplex(dim, &mut |x| {
                            if err.is_ok() && kept(x.iter().map(|v| v.0).min()) {
                                counts.1 += 1;
                                err = write_simplex_line(w, csv, dim, x, map);
                            }
                        })
                        .map_err(qerr)?;
                        err?;
                    }
                    return Ok(());
                }
                // answers in blocks, or in one when every row is made at once anyway
                let block = match &p {
                    Plan::Ids(rel) if batch::is_bulk(s, *rel, items.len()) => items.len(),
                    _ => BLOCK,
                };
                for chunk in items.chunks(block.max(1)) {
                    let (lv, widths) = answer_block(chunk).map_err(qerr)?;
                    for (j, &item) in chunk.iter().enumerate() {
                        counts.0 += 1;
                        let item = item_id(item);
                        write_item(w, csv, item_key, answer_key, item, j, &lv, &widths)?;
                    }
                    counts.1 += lv.iter().map(|c| c.values.len() as u64).sum::<u64>();
                }
                Ok(())
            }
            OutFormat::Npz => {
                let mut arrays: Vec<(String, Array)> = Vec::new();
                if let Plan::Faces = p {
                    for dim in 0..n_levels(s) {
                        let mut v = batch::faces(s, dim).map_err(qerr)?;
                        if keep.is_some() {
                            let mut at = 0;
                            for i in 0..v.len() / (dim + 1) {
                                let r = i * (dim + 1)..(i + 1) * (dim + 1);
                                if kept(v[r.clone()].iter().copied().min()) {
                                    v.copy_within(r, at);
                                    at += dim + 1;
                                }
                            }
                            v.truncate(at);
                        }
                        map_in_place(map, Ids::Vertex, &mut v);
                        counts.1 += (v.len() / (dim + 1)) as u64;
                        arrays.push((format!("faces_{dim}"), Array::U32(v, dim + 1)));
                    }
                } else {
                    let (lv, widths) = answer_block(items).map_err(qerr)?;
                    counts.0 = items.len() as u64;
                    let ids = items.iter().map(|&i| item_id(i)).collect();
                    arrays.push(("ids".into(), Array::U32(ids, 0)));
                    let single = lv.len() == 1 && !matches!(widths, Widths::Levels);
                    for (p, c) in lv.into_iter().enumerate() {
                        counts.1 += c.values.len() as u64;
                        let (sfx, width) = match &widths {
                            Widths::Levels => (format!("_{p}"), p + 1),
                            Widths::Fixed(k) => (String::new(), *k),
                            _ => (String::new(), 0),
                        };
                        let div = width.max(1) as u64;
                        let off: Vec<i64> = c.offsets.iter().map(|&o| (o / div) as i64).collect();
                        let key = if single { String::new() } else { sfx };
                        arrays.push((format!("offsets{key}"), Array::I64(off)));
                        arrays.push((format!("values{key}"), Array::U32(c.values, width)));
                    }
                    if let Widths::PerRow(_) = widths {
                        // adjacent simplices of mixed sizes: offsets count vertex ids
                        arrays.push(("values_are_flat_vertex_lists".into(), Array::I64(vec![1])));
                    }
                }
                write_npz(w, arrays)
            }
        }
    })?;
    if matches!(fmt, OutFormat::Npz) && all && !matches!(p, Plan::Faces) {
        counts.0 = items.len() as u64;
    }
    Ok(counts)
}

/// The number of levels of simplices (the f-vector's length): the dimension + 1, 1 for
/// vertices without cells, 0 for nothing. Counting the faces first would list them twice.
fn n_levels(s: &(dyn Queries + Sync)) -> usize {
    match starplex::algo::manifold::complex_dim(s) {
        Some(d) => d + 1,
        None => usize::from(s.n_vertices() > 0),
    }
}

/// How the values of a block split into simplices.
enum Widths {
    /// Plain ids.
    Ids,
    /// Level p holds simplices of p + 1 ids.
    Levels,
    /// Simplices of k ids.
    Fixed(usize),
    /// Row i holds simplices of `w[i]` ids.
    PerRow(Vec<usize>),
}

fn json_simplices(v: &[u32], k: usize) -> String {
    let mut s = String::from("[");
    for (i, c) in v.chunks(k.max(1)).enumerate() {
        if i > 0 {
            s.push(',');
        }
        s.push_str(&json_ids(c));
    }
    s.push(']');
    s
}

fn json_ids(v: &[u32]) -> String {
    let mut s = String::with_capacity(v.len() * 7 + 2);
    s.push('[');
    for (i, x) in v.iter().enumerate() {
        if i > 0 {
            s.push(',');
        }
        s.push_str(&x.to_string());
    }
    s.push(']');
    s
}

fn space_ids(v: &[u32]) -> String {
    v.iter()
        .map(|x| x.to_string())
        .collect::<Vec<_>>()
        .join(" ")
}

fn write_simplex_line(
    w: &mut dyn Write,
    csv: bool,
    dim: usize,
    x: &[starplex::ids::VertexId],
    map: Option<&IdMap>,
) -> Result<(), IoErrorKind> {
    let ids: Vec<u32> = x
        .iter()
        .map(|v| map.map_or(v.0, |m| m.vertices[v.index()]))
        .collect();
    if csv {
        writeln!(w, "{dim},{}", space_ids(&ids))?;
    } else {
        writeln!(w, "{{\"dim\":{dim},\"simplex\":{}}}", json_ids(&ids))?;
    }
    Ok(())
}

#[allow(clippy::too_many_arguments)]
fn write_item(
    w: &mut dyn Write,
    csv: bool,
    item_key: &str,
    answer_key: &str,
    item: u32,
    j: usize,
    lv: &[Answers],
    widths: &Widths,
) -> Result<(), IoErrorKind> {
    match widths {
        Widths::Ids => {
            let row = lv[0].row(j);
            if csv {
                for x in row {
                    writeln!(w, "{item},{x}")?;
                }
            } else {
                writeln!(
                    w,
                    "{{\"{item_key}\":{item},\"{answer_key}\":{}}}",
                    json_ids(row)
                )?;
            }
        }
        Widths::Fixed(_) | Widths::PerRow(_) => {
            let k = match widths {
                Widths::Fixed(k) => *k,
                Widths::PerRow(ws) => ws[j],
                _ => 1,
            };
            let row = lv[0].row(j);
            if csv {
                for c in row.chunks(k.max(1)) {
                    writeln!(w, "{item},{}", space_ids(c))?;
                }
            } else {
                writeln!(
                    w,
                    "{{\"{item_key}\":{item},\"{answer_key}\":{}}}",
                    json_simplices(row, k)
                )?;
            }
        }
        Widths::Levels => {
            if csv {
                for (p, c) in lv.iter().enumerate() {
                    for x in c.row(j).chunks(p + 1) {
                        writeln!(w, "{item},{}", space_ids(x))?;
                    }
                }
            } else {
                let levels: Vec<String> = lv
                    .iter()
                    .enumerate()
                    .map(|(p, c)| json_simplices(c.row(j), p + 1))
                    .collect();
                // trailing empty levels are left out, as in a SimplexSet
                let n = levels.iter().rposition(|l| l != "[]").map_or(0, |i| i + 1);
                writeln!(
                    w,
                    "{{\"{item_key}\":{item},\"{answer_key}\":[{}]}}",
                    levels[..n].join(",")
                )?;
            }
        }
    }
    Ok(())
}

/// One array of an `.npz`.
enum Array {
    /// uint32 values, shaped `(n, width)` when `width > 0`.
    U32(Vec<u32>, usize),
    /// int64 values, 1-D.
    I64(Vec<i64>),
}

/// A `.npz` being written: a zip of `.npy` members, stored, streamed.
type NpzOut<'w> = zip::ZipWriter<zip::write::StreamWriter<&'w mut dyn Write>>;

fn zip_err(e: zip::result::ZipError) -> IoErrorKind {
    IoErrorKind::Os(std::io::Error::other(e.to_string()))
}

/// Writes one `.npy` member `NAME.npy` of shape `shape`, its elements pushed by `fill`.
fn npz_member<T: npyz::AutoSerialize>(
    z: &mut NpzOut<'_>,
    name: &str,
    shape: &[u64],
    fill: impl FnOnce(&mut dyn FnMut(T) -> std::io::Result<()>) -> std::io::Result<()>,
) -> Result<(), IoErrorKind> {
    use npyz::WriterBuilder;
    let bytes = shape.iter().product::<u64>() * std::mem::size_of::<T>() as u64;
    let opts = zip::write::SimpleFileOptions::default()
        .compression_method(zip::CompressionMethod::Stored)
        .large_file(bytes > (1u64 << 31));
    z.start_file(format!("{name}.npy"), opts).map_err(zip_err)?;
    // the elements come one at a time: buffered, the zip's checksum runs over whole blocks
    let mut bw = std::io::BufWriter::with_capacity(1 << 16, &mut *z);
    let mut nw = npyz::WriteOptions::<T>::new()
        .default_dtype()
        .shape(shape)
        .writer(&mut bw)
        .begin_nd()?;
    fill(&mut |x| nw.push(&x))?;
    nw.finish()?;
    bw.flush()?;
    Ok(())
}

/// Writes `arrays` as an uncompressed `.npz` (a zip of `.npy` files), streamed.
fn write_npz(w: &mut dyn Write, arrays: Vec<(String, Array)>) -> Result<(), IoErrorKind> {
    let mut z = zip::ZipWriter::new_stream(w);
    for (name, a) in arrays {
        match a {
            Array::U32(v, width) => {
                let shape: Vec<u64> = match v.len().checked_div(width) {
                    Some(rows) => vec![rows as u64, width as u64],
                    None => vec![v.len() as u64],
                };
                npz_member(&mut z, &name, &shape, |push| {
                    v.into_iter().try_for_each(push)
                })?;
            }
            Array::I64(v) => {
                let shape = [v.len() as u64];
                npz_member(&mut z, &name, &shape, |push| {
                    v.into_iter().try_for_each(push)
                })?;
            }
        }
    }
    z.finish().map_err(zip_err)?;
    Ok(())
}

/// Merges `.npz` answer files of one relation, written by [`write_mapped`] for disjoint sets
/// of items (each file's `ids` ascending), into `out` by item id: the bytes `write_mapped`
/// writes for all their items at once. Streamed: each output array is made by reading the
/// parts' arrays once, in order, so no more than a buffer per part is in memory (this is how
/// `starplex-mpi query --out FILE.npz` gathers the ranks' answers).
///
/// ```
/// use starplex_cli::export::{merge_npz, write, RelationKind};
/// use starplex::structures::Structure;
/// let k = starplex::generate::kuhn_grid(&[2, 2]).unwrap(); // 9 vertices
/// let s = Structure::Stellar.build(&k, &Default::default()).unwrap();
/// let dir = std::env::temp_dir();
/// let f = |n: &str| dir.join(format!("starplex-doc-merge-{}-{n}.npz", std::process::id()));
/// write(s.as_ref(), RelationKind::Star, Some(&[0, 2, 3, 7]), &f("a")).unwrap();
/// write(s.as_ref(), RelationKind::Star, Some(&[1, 4, 5, 6, 8]), &f("b")).unwrap();
/// write(s.as_ref(), RelationKind::Star, None, &f("all")).unwrap();
/// merge_npz(&[f("a"), f("b")], &f("merged")).unwrap();
/// assert_eq!(std::fs::read(f("merged")).unwrap(), std::fs::read(f("all")).unwrap());
/// // every simplex, the parts split by their smallest vertex
/// use starplex_cli::export::write_mapped;
/// let pf = RelationKind::Pfaces;
/// write_mapped(s.as_ref(), pf, Some(&[0, 2, 3, 7]), true, &f("a"), None).unwrap();
/// write_mapped(s.as_ref(), pf, Some(&[1, 4, 5, 6, 8]), true, &f("b"), None).unwrap();
/// write_mapped(s.as_ref(), pf, None, true, &f("all"), None).unwrap();
/// merge_npz(&[f("a"), f("b")], &f("merged")).unwrap();
/// assert_eq!(std::fs::read(f("merged")).unwrap(), std::fs::read(f("all")).unwrap());
/// // an item in two parts is refused, and nothing is written
/// let e = merge_npz(&[f("a"), f("b"), f("a")], &f("bad")).unwrap_err();
/// assert!(e.to_string().contains("is in two parts"));
/// assert!(!f("bad").exists());
/// # for n in ["a", "b", "all", "merged"] { std::fs::remove_file(f(n)).ok(); }
/// ```
///
/// # Errors
/// A part that cannot be read, is not such a file, or disagrees with the others (its arrays or
/// their shapes), an item in two parts, or a write error.
pub fn merge_npz(parts: &[std::path::PathBuf], out: &Path) -> Result<(), CliError> {
    let faces = NpzLayout::faces_dims(parts).map_err(CliError::Other)?;
    let layout = if faces == 0 {
        Some(NpzLayout::of(parts).map_err(CliError::Other)?)
    } else {
        None
    };
    output::write_with(out, |w| {
        let mut z = zip::ZipWriter::new_stream(w);
        match &layout {
            Some(l) => l.write(&mut z)?,
            None => merge_faces(parts, faces, &mut z)?,
        }
        z.finish().map_err(zip_err)?;
        Ok(())
    })?;
    Ok(())
}

/// The `faces_D` arrays of p-faces parts merged, dimension by dimension: the rows (each a
/// simplex, ascending) of every part in lexicographic order, by a heap over the parts' next rows.
fn merge_faces(
    parts: &[std::path::PathBuf],
    n_dims: usize,
    z: &mut NpzOut<'_>,
) -> Result<(), IoErrorKind> {
    use std::cmp::Reverse;
    for d in 0..n_dims {
        let name = format!("faces_{d}");
        let mut archives: Vec<Part> = parts
            .iter()
            .map(|p| NpzLayout::open(p))
            .collect::<Result<_, _>>()
            .map_err(IoErrorKind::Parse)?;
        let mut rows = 0u64;
        for (a, p) in archives.iter_mut().zip(parts) {
            if a.index_for_name(&format!("{name}.npy")).is_some() {
                let m = NpzLayout::member(a, p, &name).map_err(IoErrorKind::Parse)?;
                if m.shape().len() != 2 || m.shape()[1] != d as u64 + 1 {
                    let e = format!("{}: {name} has shape {:?}", p.display(), m.shape());
                    return Err(IoErrorKind::Parse(e));
                }
                rows += m.shape()[0];
            }
        }
        let mut s = NpzLayout::streams_of::<u32>(&mut archives, parts, &name)
            .map_err(IoErrorKind::Parse)?;
        npz_member::<u32>(z, &name, &[rows, d as u64 + 1], |push| {
            let mut heads = std::collections::BinaryHeap::new();
            let next = |r: usize, s: &mut [Stream<'_, u32>]| -> std::io::Result<Option<Vec<u32>>> {
                if s[r].is_none() {
                    return Ok(None);
                }
                let Some(x) = s[r].as_mut().and_then(|s| s.next()) else {
                    return Ok(None);
                };
                let mut row = vec![x?];
                for _ in 0..d {
                    row.push(next_of(&mut s[r])?);
                }
                Ok(Some(row))
            };
            for r in 0..parts.len() {
                if let Some(row) = next(r, &mut s)? {
                    heads.push(Reverse((row, r)));
                }
            }
            let mut last: Option<Vec<u32>> = None;
            while let Some(Reverse((row, r))) = heads.pop() {
                if last.as_ref().is_some_and(|l| *l >= row) {
                    return Err(std::io::Error::other(format!(
                        "simplex {row:?} is in two parts, or a part's rows are not in order"
                    )));
                }
                row.iter().try_for_each(|&v| push(v))?;
                last = Some(row);
                if let Some(row) = next(r, &mut s)? {
                    heads.push(Reverse((row, r)));
                }
            }
            Ok(())
        })?;
    }
    Ok(())
}

/// The arrays of answer `.npz` parts ([`merge_npz`]).
struct NpzLayout<'p> {
    parts: &'p [std::path::PathBuf],
    /// Per part, its number of items.
    n_items: Vec<u64>,
    /// The answer levels, by suffix (`""` for one unsuffixed level, else `_0`, `_1`, ...):
    /// per part, its values' shape if it has the level.
    levels: Vec<(String, Vec<Option<Vec<u64>>>)>,
    /// The flag of adjacent cells of mixed sizes.
    flat: bool,
}

/// An answer `.npz` part, open.
type Part = zip::ZipArchive<std::io::BufReader<std::fs::File>>;

/// One array of a part, streamed (`None`: the part does not have it).
type Stream<'a, T> = Option<Box<dyn Iterator<Item = std::io::Result<T>> + 'a>>;

/// The next element of a part's stream.
fn next_of<T>(s: &mut Stream<'_, T>) -> std::io::Result<T> {
    match s.as_mut().and_then(|s| s.next()) {
        Some(x) => x,
        None => Err(std::io::Error::other("a part's array ends early")),
    }
}

/// Each part's first offset (0), read: a row's length is the step to the next one (0 for a
/// part without the array, whose rows are empty).
fn first_offsets(offs: &mut [Stream<'_, i64>]) -> std::io::Result<Vec<i64>> {
    offs.iter_mut()
        .map(|s| if s.is_some() { next_of(s) } else { Ok(0) })
        .collect()
}

/// Calls `each(part, id)` for the items of every part, in increasing id (each part's `ids`
/// ascending, no id in two parts).
fn merge_order(
    ids: &mut [Stream<'_, u32>],
    mut each: impl FnMut(usize, u32) -> std::io::Result<()>,
) -> std::io::Result<()> {
    use std::cmp::Reverse;
    let mut heads = std::collections::BinaryHeap::new();
    for (r, s) in ids.iter_mut().enumerate() {
        if let Some(x) = s.as_mut().and_then(|s| s.next()) {
            heads.push(Reverse((x?, r)));
        }
    }
    let mut last = None;
    while let Some(Reverse((id, r))) = heads.pop() {
        if last.is_some_and(|l| l >= id) {
            return Err(std::io::Error::other(format!(
                "item {id} is in two parts, or a part's ids are not ascending"
            )));
        }
        last = Some(id);
        each(r, id)?;
        if let Some(x) = ids[r].as_mut().and_then(|s| s.next()) {
            heads.push(Reverse((x?, r)));
        }
    }
    Ok(())
}

impl<'p> NpzLayout<'p> {
    fn open(p: &Path) -> Result<Part, String> {
        let f = std::fs::File::open(p).map_err(|e| format!("{}: {e}", p.display()))?;
        zip::ZipArchive::new(std::io::BufReader::with_capacity(1 << 16, f))
            .map_err(|e| format!("{}: not an .npz: {e}", p.display()))
    }

    /// The `.npy` member `name` of a part, its header read.
    fn member<'a>(
        a: &'a mut Part,
        p: &Path,
        name: &str,
    ) -> Result<npyz::NpyFile<zip::read::ZipFile<'a, std::io::BufReader<std::fs::File>>>, String>
    {
        let m = a
            .by_name(&format!("{name}.npy"))
            .map_err(|e| format!("{}: {name}: {e}", p.display()))?;
        npyz::NpyFile::new(m).map_err(|e| format!("{}: {name}: {e}", p.display()))
    }

    fn of(parts: &'p [std::path::PathBuf]) -> Result<Self, String> {
        let mut n_items = Vec::with_capacity(parts.len());
        let mut names: Vec<Vec<String>> = Vec::with_capacity(parts.len());
        for p in parts {
            let mut a = Self::open(p)?;
            let ids = Self::member(&mut a, p, "ids")?;
            if ids.shape().len() != 1 {
                return Err(format!("{}: ids is not one-dimensional", p.display()));
            }
            n_items.push(ids.shape()[0]);
            drop(ids);
            names.push(
                a.file_names()
                    .filter_map(|n| n.ok().map(|n| n.into_owned()))
                    .collect(),
            );
        }
        let has = |i: usize, n: &str| names[i].iter().any(|x| *x == format!("{n}.npy"));
        let single = (0..parts.len()).any(|i| has(i, "offsets"));
        let n_levels = if single {
            1
        } else {
            (0..)
                .take_while(|l| (0..parts.len()).any(|i| has(i, &format!("offsets_{l}"))))
                .count()
        };
        let mut levels = Vec::with_capacity(n_levels);
        for l in 0..n_levels {
            let sfx = if single {
                String::new()
            } else {
                format!("_{l}")
            };
            let mut shapes = Vec::with_capacity(parts.len());
            for (i, p) in parts.iter().enumerate() {
                if !has(i, &format!("offsets{sfx}")) {
                    shapes.push(None);
                    continue;
                }
                let mut a = Self::open(p)?;
                let shape = Self::member(&mut a, p, &format!("values{sfx}"))?
                    .shape()
                    .to_vec();
                if shape.is_empty() || shape.len() > 2 {
                    return Err(format!("{}: values{sfx} has shape {shape:?}", p.display()));
                }
                shapes.push(Some(shape));
            }
            let widths: Vec<&[u64]> = shapes.iter().flatten().map(|s| &s[1..]).collect();
            if widths.windows(2).any(|w| w[0] != w[1]) {
                return Err(format!("the parts' values{sfx} differ in shape"));
            }
            levels.push((sfx, shapes));
        }
        let flat = (0..parts.len()).any(|i| has(i, "values_are_flat_vertex_lists"));
        Ok(NpzLayout {
            parts,
            n_items,
            levels,
            flat,
        })
    }

    /// The number of `faces_D` arrays of p-faces parts (0 for other relations).
    fn faces_dims(parts: &[std::path::PathBuf]) -> Result<usize, String> {
        let mut n = 0;
        for p in parts {
            let a = Self::open(p)?;
            let d = (0..)
                .take_while(|d| a.index_for_name(&format!("faces_{d}.npy")).is_some())
                .count();
            n = n.max(d);
        }
        Ok(n)
    }

    fn open_all(&self) -> Result<Vec<Part>, String> {
        self.parts.iter().map(|p| Self::open(p)).collect()
    }

    /// Every part's `name` array, streamed.
    fn streams<'a, T: npyz::Deserialize + 'a>(
        &self,
        archives: &'a mut [Part],
        name: &str,
    ) -> Result<Vec<Stream<'a, T>>, String> {
        Self::streams_of(archives, self.parts, name)
    }

    /// The `name` array of each part (`archives[i]` open on `parts[i]`), streamed.
    fn streams_of<'a, T: npyz::Deserialize + 'a>(
        archives: &'a mut [Part],
        parts: &[std::path::PathBuf],
        name: &str,
    ) -> Result<Vec<Stream<'a, T>>, String> {
        let mut out: Vec<Stream<'a, T>> = Vec::with_capacity(archives.len());
        for (a, p) in archives.iter_mut().zip(parts) {
            if a.index_for_name(&format!("{name}.npy")).is_none() {
                out.push(None);
                continue;
            }
            let m = Self::member(a, p, name)?;
            let data = m
                .data::<T>()
                .map_err(|e| format!("{}: {name}: {e}", p.display()))?;
            out.push(Some(Box::new(data)));
        }
        Ok(out)
    }

    /// Writes the merged arrays, in `write_mapped`'s order.
    fn write(&self, z: &mut NpzOut<'_>) -> Result<(), IoErrorKind> {
        let total: u64 = self.n_items.iter().sum();
        {
            let mut a = self.open_all().map_err(IoErrorKind::Parse)?;
            let mut ids = self
                .streams::<u32>(&mut a, "ids")
                .map_err(IoErrorKind::Parse)?;
            npz_member(z, "ids", &[total], |push| {
                merge_order(&mut ids, |_, id| push(id))
            })?;
        }
        for (sfx, shapes) in &self.levels {
            let name = format!("offsets{sfx}");
            {
                let (mut a, mut b) = (
                    self.open_all().map_err(IoErrorKind::Parse)?,
                    self.open_all().map_err(IoErrorKind::Parse)?,
                );
                let mut ids = self
                    .streams::<u32>(&mut a, "ids")
                    .map_err(IoErrorKind::Parse)?;
                let mut offs = self
                    .streams::<i64>(&mut b, &name)
                    .map_err(IoErrorKind::Parse)?;
                npz_member::<i64>(z, &name, &[total + 1], |push| {
                    let mut prev = first_offsets(&mut offs)?;
                    let mut acc = 0i64;
                    push(acc)?;
                    merge_order(&mut ids, |r, _| {
                        if offs[r].is_some() {
                            let x = next_of(&mut offs[r])?;
                            acc += x - prev[r];
                            prev[r] = x;
                        }
                        push(acc)
                    })
                })?;
            }
            // values: each item's row copied from its part, rows of `per_row` elements
            let shape0 = shapes.iter().flatten().next();
            let per_row = shape0.map_or(1, |s| s.get(1).copied().unwrap_or(1)) as i64;
            let rows: u64 = shapes.iter().flatten().map(|s| s[0]).sum();
            let shape: Vec<u64> = match shape0 {
                Some(s) if s.len() == 2 => vec![rows, s[1]],
                _ => vec![rows],
            };
            let (mut a, mut b, mut c) = (
                self.open_all().map_err(IoErrorKind::Parse)?,
                self.open_all().map_err(IoErrorKind::Parse)?,
                self.open_all().map_err(IoErrorKind::Parse)?,
            );
            let mut ids = self
                .streams::<u32>(&mut a, "ids")
                .map_err(IoErrorKind::Parse)?;
            let mut offs = self
                .streams::<i64>(&mut b, &name)
                .map_err(IoErrorKind::Parse)?;
            let mut vals = self
                .streams::<u32>(&mut c, &format!("values{sfx}"))
                .map_err(IoErrorKind::Parse)?;
            npz_member::<u32>(z, &format!("values{sfx}"), &shape, |push| {
                let mut prev = first_offsets(&mut offs)?;
                merge_order(&mut ids, |r, _| {
                    if offs[r].is_none() {
                        return Ok(());
                    }
                    let x = next_of(&mut offs[r])?;
                    let len = (x - prev[r]) * per_row;
                    prev[r] = x;
                    for _ in 0..len {
                        push(next_of(&mut vals[r])?)?;
                    }
                    Ok(())
                })
            })?;
        }
        if self.flat {
            npz_member::<i64>(z, "values_are_flat_vertex_lists", &[1], |push| push(1))?;
        }
        Ok(())
    }
}
