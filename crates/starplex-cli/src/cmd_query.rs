//! `starplex query FILE --structure S --relation R [--vertex ID ...] [--all]`: one query
//! interface over every data structure. Written once against the `topo` traits; the
//! structures come from the library's registry (`starplex::structures`).
use std::time::Instant;

use rayon::prelude::*;
use starplex::complex::IndexedComplex;
use starplex::ids::{CellId, VertexId};
use starplex::stellar::Decomposition;
use starplex::structures::{Structure, StructureError, StructureOptions};
use starplex::topo::{batch, generic, Queries, QueryError};

use crate::common::{self, CliError, Ctx, InputArgs};

/// The data structures.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum StructureKind {
    /// Incidence graph: all simplices, full boundary and co-boundary.
    Ig,
    /// IS: all simplices, boundary, one coface per link component.
    Is,
    /// IA*: top simplices, adjacencies, one top per cluster per vertex.
    IaStar,
    /// Simplex tree (with label lists).
    SimplexTree,
    /// The indexed complex with its vertex → top cells relation (baseline).
    Vt,
    /// Stellar tree (leaf-by-leaf spatial index; --kv sets its bucketing threshold).
    Stellar,
    /// CASC Hasse diagram: every simplex with its up and down incidences.
    Hasse,
}

impl StructureKind {
    /// The structures `compare` builds.
    pub const AVAILABLE: [StructureKind; 7] = [
        StructureKind::Vt,
        StructureKind::IaStar,
        StructureKind::SimplexTree,
        StructureKind::Ig,
        StructureKind::Is,
        StructureKind::Hasse,
        StructureKind::Stellar,
    ];
    /// The library's registry entry.
    pub fn structure(self) -> Structure {
        match self {
            StructureKind::Ig => Structure::Ig,
            StructureKind::Is => Structure::Is,
            StructureKind::IaStar => Structure::IaStar,
            StructureKind::SimplexTree => Structure::SimplexTree,
            StructureKind::Vt => Structure::Vt,
            StructureKind::Stellar => Structure::Stellar,
            StructureKind::Hasse => Structure::Hasse,
        }
    }
    /// Whether the structure holds CP cells (quads, hexahedra, prisms, pyramids); the others
    /// refuse CP complexes.
    pub fn holds_cp(self) -> bool {
        self.structure().holds_cp()
    }
    pub fn name(self) -> &'static str {
        self.structure().name()
    }
}

pub use starplex_cli::export::RelationKind;

#[derive(clap::Args, Debug, Clone)]
pub struct QueryArgs {
    #[command(flatten)]
    pub input: InputArgs,
    /// Data structure.
    #[arg(long, value_enum, default_value = "ia-star")]
    pub structure: StructureKind,
    /// Relation. With --vertex --json, the objects hold the vertex and what the relations
    /// name (repeat it, or list several, for more: --relation vt vv link).
    #[arg(long, value_enum, num_args = 1.., default_value = "vt")]
    pub relation: Vec<RelationKind>,
    /// Stellar tree bucket threshold k_V (used by the Stellar tree only).
    #[arg(long)]
    pub kv: Option<usize>,
    /// How the Stellar tree splits vertices into blocks: spatial (by coordinates) or graph (by
    /// connectivity alone); with --structure stellar only.
    #[arg(long)]
    pub decomposition: Option<String>,
    /// Vertices to query (input ids).
    #[arg(long, num_args = 1..)]
    pub vertex: Vec<u32>,
    /// A file of vertex ids to query (white space or commas between them; `-`: standard input).
    #[arg(long)]
    pub vertex_file: Option<std::path::PathBuf>,
    /// Write every answer to this file: .jsonl (one object per item, streamed), .npz (CSR
    /// `offsets` and `values` arrays with the item `ids`; per level `offsets_P`/`values_P` for
    /// link and star, `faces_P` for pfaces) or .csv (one line per item and answer element).
    /// With --all: every vertex (every top cell for adj and ia-star, every simplex for pfaces).
    #[arg(long)]
    pub out: Option<std::path::PathBuf>,
    /// The batched query over the whole complex (sizes and time).
    #[arg(long)]
    pub all: bool,
    /// Worker threads for --all.
    #[arg(long, default_value_t = 1)]
    pub threads: usize,
    /// JSON output.
    #[arg(long)]
    pub json: bool,
}

/// A built structure.
pub type Built<'a> = starplex::structures::BoxedQueries<'a>;

/// Builds structure `s` on `k`.
pub fn build(k: &IndexedComplex, s: StructureKind) -> Result<Built<'_>, CliError> {
    build_with(k, s, None, Decomposition::Spatial)
}

/// Builds structure `s` on `k`, with the Stellar tree's bucketing threshold `kv` when given
/// (the library's registry, [`Structure::build`]).
pub fn build_with(
    k: &IndexedComplex,
    s: StructureKind,
    kv: Option<usize>,
    decomposition: Decomposition,
) -> Result<Built<'_>, CliError> {
    let opts = StructureOptions {
        kv: kv.map(|x| x.min(u32::MAX as usize) as u32),
        decomposition,
        ..Default::default()
    };
    s.structure().build(k, &opts).map_err(|e| {
        let hint = matches!(e, StructureError::NotSimplicial { .. })
            .then(|| "use --structure ig, ia-star, stellar or vt for CP cells".to_string());
        CliError::Input(e.to_string(), hint)
    })
}

/// A query's error: asking a simplex's question of a CP cell, or of vertices that are no
/// simplex, is the user's input (exit 2, with what to do); an answer over budget is not.
fn qerr(e: QueryError) -> CliError {
    let hint = match &e {
        QueryError::NotSimplicial(_) => Some(
            "vt, vv and ia-star answer on CP cells; for the others, triangulate first with \
             `starplex convert IN OUT --triangulate`"
                .to_string(),
        ),
        QueryError::NotInComplex(_) => None,
        QueryError::TooLarge(_) => return CliError::Other(e.to_string()),
    };
    CliError::Input(e.to_string(), hint)
}

/// The oracle-format answer for one vertex.
pub fn vertex_object(s: &dyn Queries, v: VertexId) -> Result<serde_json::Value, CliError> {
    if v.index() >= s.n_vertices() {
        return Err(CliError::Input(
            format!(
                "vertex {v} out of range (the complex has {} vertices)",
                s.n_vertices()
            ),
            None,
        ));
    }
    let mut cells = Vec::new();
    s.vertex_top_cells(v, &mut cells);
    let mut vv = Vec::new();
    s.vertex_neighbours(v, &mut vv);
    let mut maximal: Vec<Vec<u32>> = Vec::new();
    let mut buf = Vec::new();
    for &c in &cells {
        buf.clear();
        s.top_cell_vertices(c, &mut buf);
        let mut m: Vec<u32> = buf.iter().map(|w| w.0).filter(|&w| w != v.0).collect();
        m.sort_unstable();
        if !m.is_empty() {
            maximal.push(m);
        }
    }
    maximal.sort();
    // links are defined for simplicial stars; a CP star leaves the link fields null
    let link_f = match generic::link(s, &[v]) {
        Ok(l) => serde_json::json!(l.f_vector()),
        Err(QueryError::NotSimplicial(_)) => serde_json::Value::Null,
        Err(e) => return Err(qerr(e)),
    };
    if link_f.is_null() {
        maximal.clear();
    }
    Ok(serde_json::json!({
        "vertex": v.0,
        "incident_top_cells": cells.iter().map(|c| c.0).collect::<Vec<_>>(),
        "vv": vv.iter().map(|w| w.0).collect::<Vec<_>>(),
        "link_f_vector": link_f,
        "link_maximal_simplices": if link_f.is_null() { serde_json::Value::Null } else { serde_json::json!(maximal) },
    }))
}

/// The size of one vertex's (or top's, for adj/ia-star) answer.
pub fn answer_size(
    s: &dyn Queries,
    r: RelationKind,
    i: u32,
    cells: &mut Vec<CellId>,
    verts: &mut Vec<VertexId>,
) -> Result<u64, QueryError> {
    let v = VertexId(i);
    Ok(match r {
        RelationKind::Vt => {
            s.vertex_top_cells(v, cells);
            cells.len() as u64
        }
        RelationKind::Vv => {
            s.vertex_neighbours(v, verts);
            verts.len() as u64
        }
        RelationKind::Link => generic::link(s, &[v])?.len() as u64,
        RelationKind::Star => s.star(&[v])?.len() as u64,
        RelationKind::Pfaces => {
            let mut n = 0u64;
            s.for_each_simplex(i as usize, &mut |_| n += 1)?;
            n
        }
        RelationKind::Adj => {
            let kind = s.top_cell_kind(CellId(i));
            if !kind.is_simplex() {
                return Err(QueryError::NotSimplicial(format!(
                    "adj of top cell {i} (a {kind})"
                )));
            }
            let mut tv = Vec::new();
            s.top_cell_vertices(CellId(i), &mut tv);
            s.adjacent(&tv, verts)?;
            (verts.len() / tv.len()) as u64
        }
        RelationKind::IaStar => {
            // the IA* stores R_{k,k} for k >= 2 only
            if s.top_cell_kind(CellId(i)).dim() < 2 {
                return Ok(0);
            }
            let (mut facet, mut tops) = (Vec::new(), Vec::new());
            generic::facet_neighbours(s, CellId(i), &mut facet, cells, &mut tops)?;
            tops.len() as u64
        }
    })
}

/// The batched query: every vertex (vt, vv, link, star), every top (adj, ia-star), every level
/// (pfaces). Returns (items, total answer size, seconds).
pub fn run_all(
    s: &(dyn Queries + Sync),
    r: RelationKind,
    threads: usize,
) -> Result<(u64, u64, f64), CliError> {
    try_run_all(s, r, threads)?.map_err(qerr)
}

/// [`run_all`] with the query's own error kept apart (e.g. `NotSimplicial` on a CP complex).
pub fn try_run_all(
    s: &(dyn Queries + Sync),
    r: RelationKind,
    threads: usize,
) -> Result<Result<(u64, u64, f64), QueryError>, CliError> {
    let n = match r {
        RelationKind::Adj | RelationKind::IaStar => s.n_top_cells(),
        RelationKind::Pfaces => match s.f_vector() {
            Ok(f) => f.len(),
            Err(e) => return Ok(Err(e)),
        },
        _ => s.n_vertices(),
    } as u32;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads.max(1))
        .build()
        .map_err(|e| CliError::Other(e.to_string()))?;
    let t = Instant::now();
    // every top's facet neighbours at once (the batched rows `--out` writes), not one top star
    // per facet per cell: the answer is the same, in a fraction of the time
    if matches!(r, RelationKind::Adj | RelationKind::IaStar)
        && let Some(total) = pool.install(|| facet_neighbour_total(s, r, n as usize))
    {
        return Ok(total.map(|total| (n as u64, total, t.elapsed().as_secs_f64())));
    }
    let total: Result<u64, QueryError> = pool.install(|| {
        (0..n)
            .into_par_iter()
            .with_min_len(1024)
            .map_init(
                || (Vec::new(), Vec::new()),
                |(c, v), i| answer_size(s, r, i, c, v),
            )
            .try_reduce(|| 0, |a, b| Ok(a + b))
    });
    let secs = t.elapsed().as_secs_f64();
    Ok(total.map(|total| (n as u64, total, secs)))
}

/// The total size of [`answer_size`] over every top cell for `adj` and `ia-star`, from the
/// facet neighbours of every top made at once ([`batch::gather`] of TT in bulk); `None` where
/// those rows are not made in bulk (few cells, or `adj` on a complex with a CP cell). A top of
/// the complex's dimension `d` is adjacent to the tops across its facets, which are its facet
/// neighbours; the IA* holds them for tops of dimension 2 and more; a lower top's adjacency is
/// asked of the structure.
fn facet_neighbour_total(
    s: &(dyn Queries + Sync),
    r: RelationKind,
    n: usize,
) -> Option<Result<u64, QueryError>> {
    if !batch::is_bulk(s, batch::Relation::Tt, n) {
        return None;
    }
    let d = starplex::algo::manifold::complex_dim(s)?;
    // the IA*'s rows are every cell's, CP cells included; adjacency in bulk is of simplices
    let tt = match r {
        RelationKind::IaStar => Some(batch::gather(s, batch::Relation::Tt, &batch::all(n))),
        _ => batch::facet_neighbours_all(s),
    };
    let tt = match tt? {
        Ok(tt) => tt,
        Err(e) => return Some(Err(e)),
    };
    Some(
        (0..n as u32)
            .into_par_iter()
            .with_min_len(4096)
            .map_init(
                || (Vec::new(), Vec::new()),
                |(c, v), i| {
                    let k = s.top_cell_kind(CellId(i)).dim();
                    match r {
                        RelationKind::IaStar if k < 2 => Ok(0),
                        RelationKind::IaStar => Ok(tt.row(i as usize).len() as u64),
                        _ if k == d && d >= 1 => Ok(tt.row(i as usize).len() as u64),
                        _ => answer_size(s, r, i, c, v),
                    }
                },
            )
            .try_reduce(|| 0, |a, b| Ok(a + b)),
    )
}

pub fn run(ctx: &Ctx, a: &QueryArgs) -> Result<(), CliError> {
    let a = &checked_args(ctx, a)?;
    let saved = starplex::stellar::is_saved_tree(&a.input.file);
    if saved && a.structure != StructureKind::Stellar {
        return Err(CliError::Input(
            format!("{} is a saved Stellar tree", a.input.file.display()),
            Some("query it with --structure stellar, or pass the mesh file".into()),
        ));
    }
    let decomposition = match a.decomposition.as_deref() {
        None => Decomposition::Spatial,
        Some(_) if a.structure != StructureKind::Stellar => {
            return Err(CliError::Input(
                "--decomposition is the Stellar tree's: it needs --structure stellar".into(),
                None,
            ))
        }
        Some(_) if saved => {
            return Err(crate::cmd_validate::saved_tree_decomposition(&a.input.file))
        }
        Some(d) => crate::cmd_stellar::decomposition(d)?,
    };
    let k = if saved {
        None
    } else {
        Some(common::load(ctx, &a.input)?.complex)
    };
    let t = Instant::now();
    let s: Built<'_> = match &k {
        Some(k) => build_with(k, a.structure, a.kv, decomposition)?,
        None => Box::new(crate::cmd_stellar::load_saved_tree(ctx, &a.input.file)?),
    };
    let build_s = t.elapsed().as_secs_f64();
    if let Some(out) = &a.out {
        return write_out(ctx, a, s.as_ref(), out, build_s);
    }
    if !a.vertex.is_empty() {
        print_vertices(a, s.as_ref())?;
    }
    if a.all {
        print_all(a, s.as_ref(), build_s)?;
    }
    Ok(())
}

/// The arguments with `--vertex-file`'s ids appended to `--vertex`, after the checks that need
/// no input: one relation with `--all` / `--out`, a known `--out` format, something to query.
fn checked_args(ctx: &Ctx, a: &QueryArgs) -> Result<QueryArgs, CliError> {
    let mut a_vertex = a.vertex.clone();
    if let Some(f) = &a.vertex_file {
        a_vertex.extend(starplex_cli::export::read_ids(f)?);
    }
    if a.relation.len() > 1 && (a.all || a.out.is_some()) {
        return Err(CliError::Input(
            "--all and --out answer one relation at a time".into(),
            Some("pass one --relation".into()),
        ));
    }
    if let Some(out) = &a.out {
        starplex_cli::export::OutFormat::from_path(out)?;
    }
    let a = QueryArgs {
        vertex: a_vertex,
        ..a.clone()
    };
    if a.kv.is_some() && a.structure != StructureKind::Stellar && !ctx.quiet {
        eprintln!("note: --kv is used by the Stellar tree only");
    }
    if a.vertex.is_empty() && !a.all {
        return Err(CliError::Input(
            "nothing to query".into(),
            Some("pass --vertex ID ..., --vertex-file FILE or --all".into()),
        ));
    }
    Ok(a)
}

/// `--out FILE`: writes the relation's answers (every item with `--all`, else the given
/// vertices) and reports counts and time.
fn write_out(
    ctx: &Ctx,
    a: &QueryArgs,
    s: &(dyn Queries + Sync),
    out: &std::path::Path,
    build_s: f64,
) -> Result<(), CliError> {
    let relation = a.relation[0];
    let t = Instant::now();
    let items = (!a.all).then_some(&a.vertex[..]);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(a.threads.max(1))
        .build()
        .map_err(|e| CliError::Other(e.to_string()))?;
    let (n, total) = pool.install(|| starplex_cli::export::write(s, relation, items, out))?;
    let secs = t.elapsed().as_secs_f64();
    if a.json {
        println!(
            "{}",
            serde_json::json!({
                "structure": a.structure.name(),
                "relation": format!("{relation:?}").to_lowercase(),
                "out": out.display().to_string(),
                "build_s": build_s,
                "items": n,
                "total_size": total,
                "write_s": secs,
                "threads": a.threads,
            })
        );
    } else if !ctx.quiet {
        eprintln!(
            "{}: {n} items, {total} answers ({:?}) in {secs:.3} s",
            out.display(),
            relation
        );
    }
    Ok(())
}

/// `--vertex`: one object per vertex with the relations asked for, as JSON or one line each.
fn print_vertices(a: &QueryArgs, s: &dyn Queries) -> Result<(), CliError> {
    let relation = a.relation[0];
    let mut objs = Vec::new();
    for &v in &a.vertex {
        objs.push(filter(vertex_relations(a, s, v)?, &a.relation));
    }
    if a.json {
        println!("{}", serde_json::Value::Array(objs));
    } else {
        for o in &objs {
            let key = match relation {
                RelationKind::Vt | RelationKind::IaStar => "incident_top_cells",
                RelationKind::Vv => "vv",
                RelationKind::Link => "link_maximal_simplices",
                RelationKind::Star => "star_f_vector",
                RelationKind::Pfaces => "coboundary_sizes",
                RelationKind::Adj => "adjacent",
            };
            println!("vertex {}: {} = {}", o["vertex"], key, o[key]);
            if relation == RelationKind::Link {
                println!("  link f-vector = {}", o["link_f_vector"]);
            }
        }
    }
    Ok(())
}

/// The JSON object of vertex `v` with the relations of `--relation` that [`vertex_object`]
/// does not fill.
fn vertex_relations(a: &QueryArgs, s: &dyn Queries, v: u32) -> Result<serde_json::Value, CliError> {
    let mut o = vertex_object(s, VertexId(v))?;
    let (mut cells, mut verts) = (Vec::new(), Vec::new());
    for &rel in &a.relation {
        match rel {
            RelationKind::Star => {
                let st = s.star(&[VertexId(v)]).map_err(qerr)?;
                o["star_f_vector"] = serde_json::json!(st.f_vector());
            }
            RelationKind::Pfaces => {
                let mut co = Vec::new();
                for q in 1..s.f_vector().map_err(qerr)?.len() {
                    s.coboundary(&[VertexId(v)], q, &mut verts).map_err(qerr)?;
                    co.push(verts.len() / (q + 1));
                }
                o["coboundary_sizes"] = serde_json::json!(co);
            }
            RelationKind::Adj => {
                s.adjacent(&[VertexId(v)], &mut verts).map_err(qerr)?;
                o["adjacent"] = serde_json::json!(verts.iter().map(|w| w.0).collect::<Vec<_>>());
            }
            RelationKind::IaStar => {
                s.vertex_top_cells(VertexId(v), &mut cells);
                o["n_incident_top_cells"] = serde_json::json!(cells.len());
            }
            _ => {}
        }
    }
    Ok(o)
}

/// `--all`: answers the relation for every item and reports counts and time.
fn print_all(a: &QueryArgs, s: &(dyn Queries + Sync), build_s: f64) -> Result<(), CliError> {
    let relation = a.relation[0];
    let (items, total, secs) = run_all(s, relation, a.threads)?;
    if a.json {
        println!(
            "{}",
            serde_json::json!({
                "structure": a.structure.name(),
                "relation": format!("{relation:?}").to_lowercase(),
                "build_s": build_s,
                "items": items,
                "total_size": total,
                "query_s": secs,
                "threads": a.threads,
            })
        );
    } else {
        println!(
            "{} on {}: built in {build_s:.3} s; {:?} over {items} items: {total} results in {secs:.3} s ({} thread(s))",
            a.structure.name(),
            a.input.file.display(),
            relation,
            a.threads
        );
    }
    Ok(())
}

/// The keys of one vertex's JSON object that `--relation` asks for.
fn keys(r: RelationKind) -> &'static [&'static str] {
    match r {
        RelationKind::Vt => &["incident_top_cells"],
        RelationKind::Vv => &["vv"],
        RelationKind::Link => &["link_f_vector", "link_maximal_simplices"],
        RelationKind::Star => &["star_f_vector"],
        RelationKind::Pfaces => &["coboundary_sizes"],
        RelationKind::Adj => &["adjacent"],
        RelationKind::IaStar => &["incident_top_cells", "n_incident_top_cells"],
    }
}

/// One vertex's object with the vertex and the keys the relations name.
fn filter(o: serde_json::Value, rels: &[RelationKind]) -> serde_json::Value {
    let mut m = serde_json::Map::new();
    m.insert("vertex".into(), o["vertex"].clone());
    for r in rels {
        for k in keys(*r) {
            if let Some(v) = o.get(*k) {
                m.insert((*k).into(), v.clone());
            }
        }
    }
    serde_json::Value::Object(m)
}
