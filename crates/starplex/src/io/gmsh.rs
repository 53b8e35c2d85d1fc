//! gmsh `.msh`, versions 4.1 and 2.2, ascii and binary.
//!
//! Binary files (file type 1) are read in either byte order (the integer 1 after the version
//! line says which) with `size_t` of 8 or 4 bytes (4.1); node coordinates and element node
//! lists are read in bulk, a few MB at a time. Errors in a binary file name the byte offset
//! instead of the line.
//!
//! Read: `$MeshFormat`, `$Nodes` and `$Elements` (4.1: entity blocks, node tags in any order and
//! possibly non-contiguous; 2.2: one node or element per entry, elements with their tag counts),
//! `$Entities` (4.1, ascii and binary: the physical tag of each entity), `$NodeData` and
//! `$ElementData`; every other section (`$PhysicalNames`, `$Periodic`, `$ElementNodeData`,
//! `$InterpolationScheme`, ...) is skipped up to its `$End` line. Element types 1 (line),
//! 2 (triangle), 3 (quad), 4 (tetrahedron), 5 (hexahedron), 6 (prism), 7 (pyramid) and 15
//! (point) are read; others are an error naming the type.
//!
//! Attributes: the first physical tag and the elementary tag of every element become the cell
//! [attributes](crate::attr) `gmsh:physical` and `gmsh:geometrical` (absent when the file gives
//! none, or only zeros). Each `$NodeData` / `$ElementData` section (ascii, or binary with `int`
//! tags and `double` values) is a float vertex / cell attribute named by its first string tag,
//! with as many components as its second integer tag says; when several sections share a name
//! (time steps) the one of the largest time step (first integer tag; the last one among equal
//! steps) is kept, with a note. Entries for nodes or elements the reader drops are ignored;
//! vertices or cells without an entry get NaN (noted).
//!
//! A gmsh file lists the mesh of every geometric entity: besides the volume cells, the boundary
//! triangles, quads and lines, and a point element on each geometry vertex. The reader keeps only
//! the maximal cells, whatever [`ReadOptions::build`] says: elements that are faces of other
//! elements and exact duplicates (gmsh occasionally emits a tetrahedron twice) are dropped, point
//! elements are dropped, and nodes then used by no cell (the centre of a circle, a geometry point)
//! are dropped, keeping the order of the others; [`ReadResult::notes`] says how many of each.
//! Node ids are the nodes' positions in order of appearance in the file.
//!
//! Vertex order: gmsh's first-order line, triangle, quad, tetrahedron, hexahedron and pyramid are
//! in VTK order; gmsh's prism is the mirror image of VTK's wedge (its triangle 0-1-2 faces the
//! other one, VTK's faces outward), so prisms are read as `[0, 2, 1, 3, 5, 4]` of the gmsh nodes
//! and written back the same way, as gmsh itself does when it exports VTK.
//!
//! Write: [`write()`] writes version 4.1 ascii and [`write_binary`] version 4.1 binary (format
//! name `msh-binary`): `$Entities` with one geometric entity per `gmsh:geometrical` tag and
//! dimension, carrying its `gmsh:physical` tag (or, when the two columns disagree, one entity
//! per physical tag and dimension; without tags, one entity per dimension), one node block, one
//! element block per run of cells of one kind on one entity; [`write_22`] writes version 2.2
//! ascii (format name `msh22` on the command line: `starplex convert in.spx out.msh --to
//! msh22`), with the `gmsh:physical` and `gmsh:geometrical` columns as element tags. All write
//! every other attribute [`holds`] keeps as a `$NodeData` / `$ElementData` section (time step
//! 0); [`dropped`] names what a format leaves out.
//! Points of ambient dimension 1 or 2 are padded with zeros. Vertices in no cell are written as
//! nodes, which this reader then drops.
//!
//! ```
//! use starplex::io::{gmsh, ReadOptions};
//! let text = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n\
//!             $Nodes\n1 4 10 40\n3 1 0 4\n10\n20\n30\n40\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n$EndNodes\n\
//!             $Elements\n2 2 1 2\n2 1 2 1\n1 10 20 30\n3 1 4 1\n2 10 20 30 40\n$EndElements\n";
//! let r = gmsh::read_from(text.as_bytes(), "mem.msh".as_ref(), &ReadOptions::default()).unwrap();
//! assert_eq!(r.complex.n_cells(), 1); // the boundary triangle is a face of the tetrahedron
//! assert_eq!(r.notes, vec!["dropped 1 elements that are faces of other elements (boundary elements)"]);
//! let mut out = Vec::new();
//! gmsh::write(&mut out, &r.complex).unwrap();
//! let back = gmsh::read_from(&out[..], "mem.msh".as_ref(), &ReadOptions::default()).unwrap();
//! assert_eq!(back.complex, r.complex);
//! ```
use std::io::{BufRead, Write};
use std::path::Path;

use rustc_hash::FxHashMap;

use super::raw::{get_i32, get_uint, push_f64s, read_records, Endian};
use super::text::write_f64;
use super::words::Words;
use super::{Format, IoError, IoErrorKind, Location, ReadOptions, ReadResult};
use crate::attr::{AttrTarget, AttrValues, Attribute, Attributes};
use crate::cell::CellKind;
use crate::complex::{BuildOptions, ComplexBuilder, IndexedComplex};

/// gmsh prism node `PRISM_PERM[i]` is VTK wedge node `i` (an involution: the same map converts
/// back).
///
/// ```
/// let gmsh_prism = [10, 11, 12, 13, 14, 15];
/// let vtk: Vec<u32> = starplex::io::gmsh::PRISM_PERM.iter().map(|&i| gmsh_prism[i]).collect();
/// assert_eq!(vtk, [10, 12, 11, 13, 15, 14]);
/// ```
pub const PRISM_PERM: [usize; 6] = [0, 2, 1, 3, 5, 4];

/// The gmsh element type of a kind (`None` for kinds gmsh has no first-order element for here).
///
/// ```
/// use starplex::{cell::CellKind, io::gmsh};
/// assert_eq!(gmsh::gmsh_type(CellKind::Hex), Some(5));
/// assert_eq!(gmsh::gmsh_type(CellKind::Simplex(5)), None);
/// ```
pub fn gmsh_type(kind: CellKind) -> Option<u32> {
    Some(match kind {
        CellKind::Simplex(0) => 15,
        CellKind::Simplex(1) => 1,
        CellKind::Simplex(2) => 2,
        CellKind::Quad => 3,
        CellKind::Simplex(3) => 4,
        CellKind::Hex => 5,
        CellKind::Prism => 6,
        CellKind::Pyramid => 7,
        CellKind::Simplex(_) => return None,
    })
}

/// The kind of a gmsh element type starplex reads.
///
/// ```
/// use starplex::{cell::CellKind, io::gmsh};
/// assert_eq!(gmsh::kind_of_gmsh_type(6), Some(CellKind::Prism));
/// assert_eq!(gmsh::kind_of_gmsh_type(11), None); // 10-node tetrahedron
/// ```
pub fn kind_of_gmsh_type(t: u64) -> Option<CellKind> {
    Some(match t {
        15 => CellKind::Simplex(0),
        1 => CellKind::Simplex(1),
        2 => CellKind::Simplex(2),
        3 => CellKind::Quad,
        4 => CellKind::Simplex(3),
        5 => CellKind::Hex,
        6 => CellKind::Prism,
        7 => CellKind::Pyramid,
        _ => return None,
    })
}

/// The kind of a gmsh element type starplex reads and its number of nodes: the first-order
/// types of [`kind_of_gmsh_type`], and the Lagrange elements of higher order (types 8-14 and
/// 16-31: lines of 3-6 nodes, triangles of 6-21, quadrangles of 8 and 9, tetrahedra of 10-56,
/// hexahedra of 20 and 27, prisms of 15 and 18, pyramids of 13 and 14). A higher-order
/// element's first nodes are its corners, in the first-order element's order: it is read as
/// that first-order cell, and its other nodes are not vertices (the reader notes it).
///
/// ```
/// use starplex::{cell::CellKind, io::gmsh};
/// assert_eq!(gmsh::gmsh_type_nodes(4), Some((CellKind::Simplex(3), 4)));
/// assert_eq!(gmsh::gmsh_type_nodes(11), Some((CellKind::Simplex(3), 10))); // 10-node tetrahedron
/// assert_eq!(gmsh::gmsh_type_nodes(17), Some((CellKind::Hex, 20)));
/// assert_eq!(gmsh::gmsh_type_nodes(32), None);
/// ```
pub fn gmsh_type_nodes(t: u64) -> Option<(CellKind, usize)> {
    if let Some(k) = kind_of_gmsh_type(t) {
        return Some((k, k.n_vertices()));
    }
    let (line, tri, tet) = (
        CellKind::Simplex(1),
        CellKind::Simplex(2),
        CellKind::Simplex(3),
    );
    Some(match t {
        8 => (line, 3),
        26 => (line, 4),
        27 => (line, 5),
        28 => (line, 6),
        9 => (tri, 6),
        20 => (tri, 9),
        21 => (tri, 10),
        22 => (tri, 12),
        23 | 24 => (tri, 15),
        25 => (tri, 21),
        10 => (CellKind::Quad, 9),
        16 => (CellKind::Quad, 8),
        11 => (tet, 10),
        29 => (tet, 20),
        30 => (tet, 35),
        31 => (tet, 56),
        12 => (CellKind::Hex, 27),
        17 => (CellKind::Hex, 20),
        13 => (CellKind::Prism, 18),
        18 => (CellKind::Prism, 15),
        14 => (CellKind::Pyramid, 14),
        19 => (CellKind::Pyramid, 13),
        _ => return None,
    })
}

fn unsupported_type(t: u64) -> String {
    format!(
        "gmsh element type {t} is not supported (starplex reads types 1-31: points, lines, \
         triangles, quadrangles, tetrahedra, hexahedra, prisms and pyramids of first order, and \
         the higher-order ones as their first-order cells)"
    )
}

/// Reads a `.msh` file.
///
/// ```
/// use starplex::io::{gmsh, ReadOptions};
/// let path = std::env::temp_dir().join(format!("starplex-doc-gmsh-read-{}.msh", std::process::id()));
/// // gmsh 2.2: two nodes and a line element (type 1, two tags).
/// std::fs::write(&path, "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n2\n1 0 0 0\n2 1 0 0\n$EndNodes\n\
///                        $Elements\n1\n1 1 2 0 1 1 2\n$EndElements\n").unwrap();
/// let r = gmsh::read(&path, &ReadOptions::default()).unwrap();
/// std::fs::remove_file(&path).unwrap();
/// assert_eq!(r.complex.cells().next().unwrap().vertices, &[0, 1]);
/// ```
///
/// # Errors
/// See [`read_from`].
pub fn read(path: &Path, opts: &ReadOptions) -> Result<ReadResult, IoError> {
    let f = std::fs::File::open(path).map_err(|e| IoError::new(path, e))?;
    read_from(std::io::BufReader::with_capacity(1 << 20, f), path, opts)
}

/// Node tag -> 0-based id, dense while the tags are, hashed otherwise. Its size follows the
/// nodes actually read, never a declared count or a tag's value alone.
#[derive(Default)]
struct TagMap {
    dense: Vec<u32>,
    sparse: FxHashMap<u64, u32>,
    n: usize,
    /// `--drop-degenerate`: an element with a repeated node passes the element checks (only
    /// the node tags are checked) and is dropped by the build.
    drop_degenerate: bool,
}

impl TagMap {
    /// The element checks: the node ids in range and, unless degenerate elements are dropped,
    /// pairwise distinct.
    fn check(&self, n_elem: u64, verts: &[u32]) -> Result<(), crate::complex::ComplexError> {
        let opts = BuildOptions {
            drop_degenerate: self.drop_degenerate,
            ..BuildOptions::default()
        };
        opts.check_cell(n_elem, verts, self.n)
    }
}

impl TagMap {
    /// Inserts `tag -> id`; false when the tag is already there.
    fn insert(&mut self, tag: u64, id: u32) -> bool {
        if (tag as usize) < self.dense.len() || tag <= 2 * self.n as u64 + 4096 {
            let t = tag as usize;
            if t >= self.dense.len() {
                let want = (t + 1).max(self.dense.len() * 3 / 2);
                self.dense.resize(want, u32::MAX);
            }
            if self.dense[t] != u32::MAX || self.sparse.contains_key(&tag) {
                return false;
            }
            self.dense[t] = id;
        } else {
            if self.sparse.contains_key(&tag) {
                return false;
            }
            self.sparse.insert(tag, id);
        }
        self.n += 1;
        true
    }

    #[inline]
    fn get(&self, tag: u64) -> Option<u32> {
        match self.dense.get(tag as usize) {
            Some(&id) if id != u32::MAX => Some(id),
            // a tag stored sparsely before the dense part grew past it
            _ => self.sparse.get(&tag).copied(),
        }
    }
}

/// A column of element tags as runs `(count, tag)` of equal tags.
#[derive(Default)]
struct TagRuns {
    runs: Vec<(u64, i64)>,
    len: u64,
}

impl TagRuns {
    /// Appends `n` elements with tag `t`.
    fn push_n(&mut self, n: u64, t: i64) {
        match self.runs.last_mut() {
            Some((c, last)) if *last == t => *c += n,
            _ if n > 0 => self.runs.push((n, t)),
            _ => {}
        }
        self.len += n;
    }

    /// Whether some element has a tag other than 0.
    fn any_nonzero(&self) -> bool {
        self.runs.iter().any(|&(_, t)| t != 0)
    }

    /// One tag per element.
    fn to_vec(&self) -> Vec<i64> {
        let mut v = Vec::with_capacity(self.len as usize);
        for &(c, t) in &self.runs {
            v.resize(v.len() + c as usize, t);
        }
        v
    }
}

/// What the element pass collects.
#[derive(Default)]
struct Elements {
    /// `(kind, flat vertex ids)` runs in file order.
    blocks: Vec<(CellKind, Vec<u32>)>,
    points: usize,
    /// Elements of higher order read as their first-order cells.
    higher_order: usize,
    /// Physical and elementary (geometrical) tag of every element kept, in file order, as
    /// runs of equal tags (a block's elements share them; most files give none).
    physical: TagRuns,
    geometrical: TagRuns,
    /// Whether the file gave physical tags (2.2 tags, 4.1 `$Entities`).
    has_physical: bool,
    /// The element tag of every element kept, in file order; empty while every tag so far is
    /// the element's position + 1 (the usual numbering: nothing to store).
    tags: Vec<u64>,
}

impl Elements {
    /// Counts a higher-order element (more nodes than corners).
    fn count_order(&mut self, (kind, nn): (CellKind, usize)) {
        if nn > kind.n_vertices() {
            self.higher_order += 1;
        }
    }

    /// The first element tag that keeps the usual numbering (position + 1), or `None` once
    /// some tag broke it.
    fn next_plain_tag(&self) -> Option<u64> {
        self.tags.is_empty().then_some(self.physical.len + 1)
    }

    /// The vertex array of the current run of `kind` elements, started when the kind changes.
    fn run_of(&mut self, kind: CellKind) -> &mut Vec<u32> {
        if self.blocks.last().is_none_or(|(k, _)| *k != kind) {
            self.blocks.push((kind, Vec::new()));
        }
        &mut self.blocks.last_mut().expect("just pushed").1
    }

    /// Adds an element with its physical and elementary tags.
    fn push(&mut self, tag: u64, kind: CellKind, verts: &[u32], physical: i64, geometrical: i64) {
        let n = self.physical.len;
        if !self.tags.is_empty() || tag != n + 1 {
            if self.tags.is_empty() {
                self.tags.extend(1..=n);
            }
            self.tags.push(tag);
        }
        match self.blocks.last_mut() {
            Some((k, v)) if *k == kind => v.extend_from_slice(verts),
            _ => self.blocks.push((kind, verts.to_vec())),
        }
        self.physical.push_n(1, physical);
        self.geometrical.push_n(1, geometrical);
    }
}

/// Physical tag of each geometric entity `(dimension, tag)` (the first one listed), from an
/// ascii `$Entities` section (the `$Entities` word already read, up to `$EndEntities`).
fn read_entities(
    w: &mut Words<'_, impl BufRead>,
) -> Result<std::collections::HashMap<(u64, i64), i64>, IoError> {
    let mut map = std::collections::HashMap::new();
    let mut counts = [0u64; 4];
    for (d, c) in counts.iter_mut().enumerate() {
        *c = w.u64(
            [
                "the number of points",
                "the number of curves",
                "the number of surfaces",
                "the number of volumes",
            ][d],
        )?;
    }
    for (dim, &n) in counts.iter().enumerate() {
        for _ in 0..n {
            let tag = w.i64("an entity tag")?;
            // a point has its coordinates, the others a bounding box
            for _ in 0..if dim == 0 { 3 } else { 6 } {
                w.f64("an entity coordinate")?;
            }
            let n_phys = w.u64("the number of physical tags")?;
            for i in 0..n_phys {
                let p = w.i64("a physical tag")?;
                if i == 0 {
                    map.insert((dim as u64, tag), p);
                }
            }
            if dim > 0 {
                let n_bound = w.u64("the number of bounding entities")?;
                for _ in 0..n_bound {
                    w.i64("a bounding entity tag")?;
                }
            }
        }
    }
    w.keyword("$EndEntities")?;
    Ok(map)
}

/// Reads an element's node tags into `verts` (VTK order), checking them.
/// Reads the `nn` node tags of an element of `kind` (its corners first, then, for a
/// higher-order element, the other nodes: checked to be nodes, not kept).
fn read_element_nodes(
    w: &mut Words<'_, impl BufRead>,
    (kind, nn): (CellKind, usize),
    tags: &TagMap,
    n_elem: u64,
    verts: &mut Vec<u32>,
) -> Result<(), IoError> {
    let k = kind.n_vertices();
    verts.clear();
    let mut raw = [0u32; 8];
    let line = w.line();
    for i in 0..nn {
        let t = w.u64("a node tag")?;
        let v = tags.get(t).ok_or_else(|| {
            w.err(format!(
                "element node tag {t} is not a node of the $Nodes section"
            ))
        })?;
        if let Some(slot) = raw.get_mut(i).filter(|_| i < k) {
            *slot = v;
        }
    }
    if kind == CellKind::Prism {
        verts.extend(PRISM_PERM.iter().map(|&i| raw[i]));
    } else {
        verts.extend_from_slice(&raw[..k]);
    }
    tags.check(n_elem, verts)
        .map_err(|e| IoError::new(w.path(), e).at(Location::Line(line.max(w.line()))))
}

/// Reads gmsh ascii text from any buffered reader; `path` names it in errors. Of `opts.build`
/// only `drop_degenerate` is used: a gmsh file always has its boundary elements and point
/// elements dropped (see the module docs).
///
/// ```
/// use starplex::io::{gmsh, ReadOptions};
/// // a binary file whose byte-order marker is cut off
/// let text = "$MeshFormat\n4.1 1 8\n\x01";
/// let e = gmsh::read_from(text.as_bytes(), "m.msh".as_ref(), &ReadOptions::default()).unwrap_err();
/// assert_eq!(e.to_string(), "m.msh: byte 20: unexpected end of file in the binary marker (the integer 1) \
///                            (4 bytes needed): the file is truncated or a count is wrong");
/// ```
///
/// # Errors
/// A missing `$MeshFormat`, a binary marker that is not the integer 1 in either byte order,
/// versions other than 2.x and 4.1, malformed or non-finite numbers, repeated node tags, element
/// nodes that are not in `$Nodes`, unsupported element types, repeated nodes in one element,
/// counts that do not match the data, a missing `$End...` line; each with the line.
pub fn read_from(r: impl BufRead, path: &Path, opts: &ReadOptions) -> Result<ReadResult, IoError> {
    let mut w = Words::new(r, path, None);
    let (bin, v4) = read_format(&mut w, path)?;

    let mut tags = TagMap {
        drop_degenerate: opts.build.drop_degenerate,
        ..TagMap::default()
    };
    let mut coords: Vec<f64> = Vec::new();
    let mut have_nodes = false;
    let mut elems = Elements::default();
    let mut entities: Option<std::collections::HashMap<(u64, i64), i64>> = None;
    let mut have_elements = false;
    let mut verts: Vec<u32> = Vec::with_capacity(8);
    let mut data: Vec<DataSection> = Vec::new();
    while let Some(sec) = w.next_word()?.map(|s| s.to_vec()) {
        let name = String::from_utf8_lossy(&sec[..sec.len().min(60)]).into_owned();
        match name.as_str() {
            "$Nodes" => {
                if have_nodes {
                    return Err(w.err("a second $Nodes section"));
                }
                have_nodes = true;
                match (bin, v4) {
                    (Some(b), true) => read_nodes_41_bin(&mut w, b, &mut tags, &mut coords)?,
                    (Some(b), false) => read_nodes_22_bin(&mut w, b, &mut tags, &mut coords)?,
                    (None, true) => read_nodes_41(&mut w, &mut tags, &mut coords)?,
                    (None, false) => read_nodes_22(&mut w, &mut tags, &mut coords)?,
                }
                w.keyword("$EndNodes")?;
            }
            "$Elements" => {
                if !have_nodes {
                    return Err(w.err("$Elements before $Nodes"));
                }
                if have_elements {
                    return Err(w.err("a second $Elements section"));
                }
                have_elements = true;
                match (bin, v4) {
                    (Some(b), true) => {
                        elems.has_physical = entities.is_some();
                        let ent = entities.take().unwrap_or_default();
                        read_elements_41_bin(&mut w, b, &tags, &mut elems, &ent)?
                    }
                    (Some(b), false) => read_elements_22_bin(&mut w, b, &tags, &mut elems)?,
                    (None, true) => {
                        elems.has_physical = entities.is_some();
                        let ent = entities.take().unwrap_or_default();
                        read_elements_41(&mut w, &tags, &mut elems, &mut verts, &ent)?
                    }
                    (None, false) => read_elements_22(&mut w, &tags, &mut elems, &mut verts)?,
                }
                w.keyword("$EndElements")?;
            }
            "$Entities" if v4 => {
                entities = Some(match bin {
                    None => read_entities(&mut w)?,
                    Some(b) => read_entities_bin(&mut w, b)?,
                })
            }
            "$NodeData" | "$ElementData" => {
                let node = name == "$NodeData";
                data.push(read_data_section(&mut w, bin, node)?);
                w.keyword(if node {
                    "$EndNodeData"
                } else {
                    "$EndElementData"
                })?;
            }
            s if s.starts_with('$') && !s.starts_with("$End") && bin.is_some() => {
                // binary sections ($Entities, $PartitionedEntities, $NodeData, ...) may hold
                // any byte: skip to the end marker
                let end = format!("$End{}", &s[1..]);
                if !w.skip_raw_past(end.as_bytes())? {
                    return Err(w.eof(&format!("'{end}'")));
                }
            }
            s if s.starts_with('$') && !s.starts_with("$End") => {
                let end = format!("$End{}", &s[1..]);
                loop {
                    match w.next_word()? {
                        Some(x) if x == end.as_bytes() => break,
                        Some(_) => {}
                        None => return Err(w.eof(&format!("'{end}'"))),
                    }
                }
            }
            _ => {
                return Err(w.err(format!(
                    "expected a section such as '$Nodes' or '$Elements', found '{name}'"
                )))
            }
        }
    }
    if !have_nodes {
        return Err(w.err("the file has no $Nodes section"));
    }
    assemble(path, tags, coords, elems, data)
}

/// Reads `$MeshFormat` ... `$EndMeshFormat`: the binary encoding (`None` for ascii) and
/// whether the version is 4.1 (else 2.x).
fn read_format(
    w: &mut Words<'_, impl BufRead>,
    path: &Path,
) -> Result<(Option<Bin>, bool), IoError> {
    w.keyword("$MeshFormat").map_err(|e| {
        IoError::parse(
            path,
            e.location,
            "not a gmsh file: expected '$MeshFormat' first",
        )
    })?;
    let version = w.expect("the format version")?.to_vec();
    let version = String::from_utf8_lossy(&version).into_owned();
    let file_type = w.u64("the file type (0 ascii, 1 binary)")?;
    if file_type > 1 {
        return Err(w.err(format!(
            "file type {file_type} is neither 0 (ascii) nor 1 (binary)"
        )));
    }
    let data_size = w.u64("the data size")?;
    let v4 = match version.as_str() {
        "4.1" => true,
        v if v == "2" || v.starts_with("2.") => false,
        v => {
            return Err(w.err(format!(
                "gmsh format version {v} is not supported (starplex reads 4.1 and 2.2; re-save in one of them)"
            )))
        }
    };
    let bin = if file_type == 1 {
        if data_size != 8 && !(v4 && data_size == 4) {
            return Err(w.err(format!(
                "binary data size {data_size} is not supported (gmsh writes 8)"
            )));
        }
        w.rest_of_line()?;
        let at = w.offset();
        let mut one = [0u8; 4];
        w.read_raw(&mut one, "the binary marker (the integer 1)")?;
        let endian = if u32::from_le_bytes(one) == 1 {
            Endian::Little
        } else if u32::from_be_bytes(one) == 1 {
            Endian::Big
        } else {
            return Err(IoError::parse(
                path,
                Some(Location::Byte(at)),
                format!(
                    "expected the integer 1 that gives the byte order of a binary .msh, found bytes {one:02x?}"
                ),
            ));
        };
        w.set_binary();
        Some(Bin {
            e: endian,
            size: data_size as usize,
        })
    } else {
        None
    };
    w.keyword("$EndMeshFormat")?;
    Ok((bin, v4))
}

/// The complex of the sections read: the nodes some element uses (renumbered in order), the
/// elements, their tags and data as attributes, and the notes on what was dropped.
fn assemble(
    path: &Path,
    tags: TagMap,
    coords: Vec<f64>,
    mut elems: Elements,
    data: Vec<DataSection>,
) -> Result<ReadResult, IoError> {
    // Keep the nodes used by some cell, in order.
    let nv = tags.n;
    let drop_degenerate = tags.drop_degenerate;
    let mut new_id = vec![u32::MAX; nv];
    for (_, v) in &elems.blocks {
        for &x in v {
            new_id[x as usize] = 0;
        }
    }
    let mut b = ComplexBuilder::new(3).map_err(|e| IoError::new(path, e))?;
    let dropped_nodes = new_id.iter().filter(|&&id| id == u32::MAX).count();
    let kept: Vec<f64> = if dropped_nodes == 0 {
        // every node is used: the ids stay as they are
        for (i, id) in new_id.iter_mut().enumerate() {
            *id = i as u32;
        }
        coords
    } else {
        let mut kept = Vec::with_capacity(3 * (nv - dropped_nodes));
        for (i, id) in new_id.iter_mut().enumerate() {
            if *id != u32::MAX {
                *id = (kept.len() / 3) as u32;
                kept.extend_from_slice(&coords[3 * i..3 * i + 3]);
            }
        }
        for (_, v) in &mut elems.blocks {
            for x in v.iter_mut() {
                *x = new_id[*x as usize];
            }
        }
        kept
    };
    b.push_vertices(kept).map_err(|e| IoError::new(path, e))?;
    for (kind, v) in std::mem::take(&mut elems.blocks) {
        b.push_cells(kind, v).map_err(|e| IoError::new(path, e))?;
    }
    let mut attrs = Attributes::default();
    let n_elems = elems.physical.len as usize;
    // (gmsh's entity tags start at 1: all zeros means the file gave none)
    if elems.has_physical && elems.physical.any_nonzero() {
        attrs
            .cell
            .push(Attribute::int("gmsh:physical", 1, elems.physical.to_vec()));
    }
    if elems.geometrical.any_nonzero() {
        attrs.cell.push(Attribute::int(
            "gmsh:geometrical",
            1,
            elems.geometrical.to_vec(),
        ));
    }
    let mut notes = Vec::new();
    if !data.is_empty() && elems.tags.is_empty() {
        elems.tags.extend(1..=n_elems as u64);
    }
    data_attributes(
        data,
        &tags,
        &new_id,
        b.n_vertices(),
        &elems.tags,
        &mut attrs,
        &mut notes,
    );
    b.set_attributes(attrs);
    let (complex, report) = b
        .build(&BuildOptions {
            drop_face_cells: true,
            drop_duplicates: true,
            trust_maximality: false,
            drop_degenerate,
        })
        .map_err(|e| IoError::new(path, e))?;
    super::faces::push_degenerate_note(&mut notes, &report);
    if report.dropped_face_cells > 0 {
        notes.push(format!(
            "dropped {} elements that are faces of other elements (boundary elements)",
            report.dropped_face_cells
        ));
    }
    if report.dropped_duplicates > 0 {
        notes.push(format!(
            "dropped {} duplicate elements",
            report.dropped_duplicates
        ));
    }
    if elems.points > 0 {
        notes.push(format!("dropped {} point elements (type 15)", elems.points));
    }
    if elems.higher_order > 0 {
        notes.push(format!(
            "read {} higher-order elements as their first-order cells (their corner nodes \
             are the vertices; their other nodes are dropped with the unused nodes)",
            elems.higher_order
        ));
    }
    if dropped_nodes > 0 {
        notes.push(format!(
            "dropped {dropped_nodes} nodes used by no element{}",
            if elems.higher_order > 0 {
                " as a corner (geometry points, higher-order nodes)"
            } else {
                " (geometry points)"
            }
        ));
    }
    Ok(ReadResult {
        complex,
        format: Format::Gmsh,
        notes,
    })
}

/// The physical tag of each geometric entity, from a binary 4.1 `$Entities` section (the
/// `$Entities` word already read, up to its data's end).
fn read_entities_bin(
    w: &mut Words<'_, impl BufRead>,
    b: Bin,
) -> Result<std::collections::HashMap<(u64, i64), i64>, IoError> {
    let (sz, e) = (b.size, b.e);
    w.rest_of_line()?;
    let mut buf = [0u8; 64];
    let mut map = std::collections::HashMap::new();
    w.read_raw(&mut buf[..4 * sz], "the $Entities counts")?;
    let counts: Vec<u64> = (0..4).map(|i| get_uint(&buf[i * sz..], sz, e)).collect();
    for (dim, &n) in counts.iter().enumerate() {
        for _ in 0..n {
            // tag, then a point's coordinates or a bounding box, then the physical tag count
            let fixed = 4 + if dim == 0 { 24 } else { 48 };
            w.read_raw(&mut buf[..fixed], "an entity")?;
            let tag = get_i32(&buf, e) as i64;
            w.read_raw(&mut buf[..sz], "the number of physical tags")?;
            let n_phys = get_uint(&buf, sz, e);
            for i in 0..n_phys {
                w.read_raw(&mut buf[..4], "a physical tag")?;
                if i == 0 {
                    map.insert((dim as u64, tag), get_i32(&buf, e) as i64);
                }
            }
            if dim > 0 {
                w.read_raw(&mut buf[..sz], "the number of bounding entities")?;
                let n_bound = get_uint(&buf, sz, e);
                for _ in 0..n_bound {
                    w.read_raw(&mut buf[..4], "a bounding entity tag")?;
                }
            }
        }
    }
    w.keyword("$EndEntities")?;
    Ok(map)
}

/// One `$NodeData` or `$ElementData` section.
struct DataSection {
    node: bool,
    /// The first string tag (the field's name).
    name: String,
    /// The first integer tag (the time step index).
    step: i64,
    components: usize,
    /// Node or element tag of every entry, and its values.
    tags: Vec<u64>,
    values: Vec<f64>,
}

/// A string tag: `"name"` (quotes removed; it may hold spaces) or a bare word.
fn read_string_tag(w: &mut Words<'_, impl BufRead>) -> Result<String, IoError> {
    let first = w.expect("a string tag")?.to_vec();
    let mut s = first;
    if s.first() == Some(&b'"') && (s.len() == 1 || s.last() != Some(&b'"')) {
        // a quoted name with spaces: the rest of its line
        s.extend_from_slice(&w.rest_of_line()?);
        while s.last().is_some_and(|c| c.is_ascii_whitespace()) {
            s.pop();
        }
    }
    let t = s.strip_prefix(b"\"").unwrap_or(&s);
    let t = t.strip_suffix(b"\"").unwrap_or(t);
    Ok(String::from_utf8_lossy(t).into_owned())
}

/// Reads a `$NodeData` / `$ElementData` section after its keyword, up to its `$End` line
/// (not read): string, real and integer tags in ascii, then the entries (ascii, or binary: an
/// `int` tag, then the doubles; gmsh and meshio write an `int` in 4.1 too).
fn read_data_section(
    w: &mut Words<'_, impl BufRead>,
    bin: Option<Bin>,
    node: bool,
) -> Result<DataSection, IoError> {
    let n_str = w.u64("the number of string tags")?;
    let mut name = String::new();
    for i in 0..n_str {
        let s = read_string_tag(w)?;
        if i == 0 {
            name = s;
        }
    }
    let n_real = w.u64("the number of real tags")?;
    for _ in 0..n_real {
        w.expect("a real tag")?;
    }
    let head = w.line();
    let n_int = w.u64("the number of integer tags")?;
    let mut ints = [0i64; 3];
    for i in 0..n_int {
        let x = w.i64("an integer tag")?;
        if let Some(slot) = ints.get_mut(i as usize) {
            *slot = x;
        }
    }
    let what = if node { "$NodeData" } else { "$ElementData" };
    if n_int < 3 {
        return Err(w.err_at(
            head,
            format!("{what} has {n_int} integer tags; gmsh gives 3 or more (time step, components, entries)"),
        ));
    }
    let [step, comps, n] = ints;
    if !(1..=64).contains(&comps) || n < 0 {
        return Err(w.err_at(
            head,
            format!("{what} declares {comps} components and {n} entries"),
        ));
    }
    let (c, n) = (comps as usize, n as u64);
    let mut sec = DataSection {
        node,
        name: if name.is_empty() {
            what[1..].to_string()
        } else {
            name
        },
        step,
        components: c,
        tags: Vec::new(),
        values: Vec::new(),
    };
    match bin {
        None => {
            for _ in 0..n {
                sec.tags
                    .push(w.u64(if node { "a node tag" } else { "an element tag" })?);
                for _ in 0..c {
                    let tok = w.expect("a data value")?;
                    match super::text::parse_f64(tok) {
                        Some(x) => sec.values.push(x),
                        None => {
                            let shown =
                                String::from_utf8_lossy(&tok[..tok.len().min(40)]).into_owned();
                            return Err(w.err(format!(
                                "expected a data value (a number), found '{shown}'"
                            )));
                        }
                    }
                }
            }
        }
        Some(b) => {
            let tw = 4;
            w.rest_of_line()?;
            let rec = tw + 8 * c;
            read_records(w, n, rec, "data entries", |_, chunk, _| {
                for r in chunk.chunks_exact(rec) {
                    sec.tags.push(get_uint(r, tw, b.e));
                    push_f64s(&r[tw..], b.e, &mut sec.values);
                }
                Ok(())
            })?;
        }
    }
    Ok(sec)
}

/// Turns the data sections into attributes: per name and kind, the section of the largest
/// time step (the last of equal steps); entries for nodes or elements that are not kept are
/// ignored, nodes or elements without an entry get NaN.
fn data_attributes(
    data: Vec<DataSection>,
    node_tags: &TagMap,
    new_id: &[u32],
    n_vertices: usize,
    elem_tags: &[u64],
    attrs: &mut Attributes,
    notes: &mut Vec<String>,
) {
    let mut chosen: Vec<DataSection> = Vec::new();
    let mut n_steps = 0usize;
    for d in data {
        match chosen
            .iter_mut()
            .find(|c| c.node == d.node && c.name == d.name)
        {
            Some(c) => {
                n_steps += 1;
                if d.step >= c.step {
                    *c = d;
                }
            }
            None => chosen.push(d),
        }
    }
    if n_steps > 0 {
        notes.push(format!(
            "kept the last time step of each data field ({n_steps} earlier sections ignored)"
        ));
    }
    let mut elem_map: Option<TagMap> = None;
    let mut missing = 0usize;
    for d in chosen {
        let c = d.components;
        let (n, ids): (usize, Vec<Option<u32>>) = if d.node {
            let ids = d
                .tags
                .iter()
                .map(|&t| {
                    node_tags
                        .get(t)
                        .map(|i| new_id[i as usize])
                        .filter(|&v| v != u32::MAX)
                })
                .collect();
            (n_vertices, ids)
        } else {
            let m = elem_map.get_or_insert_with(|| {
                let mut m = TagMap::default();
                for (i, &t) in elem_tags.iter().enumerate() {
                    m.insert(t, i as u32);
                }
                m
            });
            (elem_tags.len(), d.tags.iter().map(|&t| m.get(t)).collect())
        };
        let mut values = vec![f64::NAN; n * c];
        let mut filled = vec![false; n];
        for (j, id) in ids.into_iter().enumerate() {
            if let Some(i) = id {
                let i = i as usize;
                values[i * c..(i + 1) * c].copy_from_slice(&d.values[j * c..(j + 1) * c]);
                filled[i] = true;
            }
        }
        missing += filled.iter().filter(|f| !**f).count();
        let a = Attribute::float(d.name, c, values);
        let list = if d.node {
            &mut attrs.vertex
        } else {
            &mut attrs.cell
        };
        if list.iter().any(|x| x.name == a.name) {
            notes.push(format!("ignored a second data field named '{}'", a.name));
        } else {
            list.push(a);
        }
    }
    if missing > 0 {
        notes.push(format!(
            "{missing} nodes or elements have no value in a data field (NaN)"
        ));
    }
}

fn add_node(
    w: &Words<'_, impl BufRead>,
    tags: &mut TagMap,
    tag: u64,
    line: u64,
) -> Result<(), IoError> {
    let id = tags.n;
    if id as u64 >= u32::MAX as u64 - 1 {
        return Err(w.err_at(
            line,
            "more nodes than the 32-bit ids of starplex can address",
        ));
    }
    if !tags.insert(tag, id as u32) {
        return Err(w.err_at(line, format!("node tag {tag} appears twice")));
    }
    Ok(())
}

fn read_xyz(w: &mut Words<'_, impl BufRead>, coords: &mut Vec<f64>) -> Result<(), IoError> {
    for _ in 0..3 {
        coords.push(w.f64("a node coordinate")?);
    }
    Ok(())
}

fn read_nodes_41(
    w: &mut Words<'_, impl BufRead>,
    tags: &mut TagMap,
    coords: &mut Vec<f64>,
) -> Result<(), IoError> {
    let n_blocks = w.u64("the number of node blocks")?;
    let n_nodes = w.u64("the number of nodes")?;
    let head = w.line();
    w.u64("the smallest node tag")?;
    w.u64("the largest node tag")?;
    let mut block_tags: Vec<(u64, u64)> = Vec::new();
    for _ in 0..n_blocks {
        let dim = w.u64("the entity dimension")?;
        w.u64("the entity tag")?;
        let parametric = w.u64("the parametric flag")?;
        let n = w.u64("the number of nodes in the block")?;
        if dim > 3 || parametric > 1 {
            return Err(w.err(format!(
                "node block with entity dimension {dim} and parametric flag {parametric}"
            )));
        }
        let extra = if parametric == 1 { dim } else { 0 };
        block_tags.clear();
        for _ in 0..n {
            let t = w.u64("a node tag")?;
            block_tags.push((t, w.line()));
        }
        for &(t, line) in &block_tags {
            read_xyz(w, coords)?;
            for _ in 0..extra {
                w.f64("a parametric coordinate")?;
            }
            add_node(w, tags, t, line)?;
        }
    }
    if tags.n as u64 != n_nodes {
        return Err(w.err_at(
            head,
            format!(
                "$Nodes declares {n_nodes} nodes, its blocks hold {}",
                tags.n
            ),
        ));
    }
    Ok(())
}

fn read_nodes_22(
    w: &mut Words<'_, impl BufRead>,
    tags: &mut TagMap,
    coords: &mut Vec<f64>,
) -> Result<(), IoError> {
    let n = w.u64("the number of nodes")?;
    for _ in 0..n {
        let t = w.u64("a node tag")?;
        let line = w.line();
        read_xyz(w, coords)?;
        add_node(w, tags, t, line)?;
    }
    Ok(())
}

fn read_elements_41(
    w: &mut Words<'_, impl BufRead>,
    tags: &TagMap,
    elems: &mut Elements,
    verts: &mut Vec<u32>,
    entities: &std::collections::HashMap<(u64, i64), i64>,
) -> Result<(), IoError> {
    let n_blocks = w.u64("the number of element blocks")?;
    let n_elems = w.u64("the number of elements")?;
    let head = w.line();
    w.u64("the smallest element tag")?;
    w.u64("the largest element tag")?;
    let mut seen: u64 = 0;
    for _ in 0..n_blocks {
        let dim = w.u64("the entity dimension")?;
        let entity = w.i64("the entity tag")?;
        let physical = entities.get(&(dim, entity)).copied().unwrap_or(0);
        let ty = w.u64("the element type")?;
        let shape = gmsh_type_nodes(ty).ok_or_else(|| w.err(unsupported_type(ty)))?;
        let kind = shape.0;
        let n = w.u64("the number of elements in the block")?;
        for _ in 0..n {
            let tag = w.u64("an element tag")?;
            read_element_nodes(w, shape, tags, seen, verts)?;
            elems.count_order(shape);
            seen += 1;
            if kind == CellKind::Simplex(0) {
                elems.points += 1;
            } else {
                elems.push(tag, kind, verts, physical, entity);
            }
        }
    }
    if seen != n_elems {
        return Err(w.err_at(
            head,
            format!("$Elements declares {n_elems} elements, its blocks hold {seen}"),
        ));
    }
    Ok(())
}

fn read_elements_22(
    w: &mut Words<'_, impl BufRead>,
    tags: &TagMap,
    elems: &mut Elements,
    verts: &mut Vec<u32>,
) -> Result<(), IoError> {
    let n = w.u64("the number of elements")?;
    for i in 0..n {
        let tag = w.u64("an element tag")?;
        let ty = w.u64("the element type")?;
        let shape = gmsh_type_nodes(ty).ok_or_else(|| w.err(unsupported_type(ty)))?;
        let kind = shape.0;
        let n_tags = w.u64("the number of element tags")?;
        let mut t = [0i64; 2];
        for j in 0..n_tags {
            let x = w.i64("an element tag value")?;
            if let Some(slot) = t.get_mut(j as usize) {
                *slot = x;
            }
        }
        read_element_nodes(w, shape, tags, i, verts)?;
        elems.count_order(shape);
        if kind == CellKind::Simplex(0) {
            elems.points += 1;
        } else {
            elems.has_physical |= n_tags > 0;
            elems.push(tag, kind, verts, t[0], t[1]);
        }
    }
    Ok(())
}

/// Byte order and `size_t` width of a binary file.
#[derive(Clone, Copy)]
struct Bin {
    e: Endian,
    size: usize,
}

fn byte_err(path: &Path, at: u64, msg: impl Into<String>) -> IoError {
    IoError::parse(path, Some(Location::Byte(at)), msg)
}

fn add_node_bin(path: &Path, tags: &mut TagMap, tag: u64, at: u64) -> Result<(), IoError> {
    let id = tags.n;
    if id as u64 >= u32::MAX as u64 - 1 {
        return Err(byte_err(
            path,
            at,
            "more nodes than the 32-bit ids of starplex can address",
        ));
    }
    if !tags.insert(tag, id as u32) {
        return Err(byte_err(path, at, format!("node tag {tag} appears twice")));
    }
    Ok(())
}

/// Checks that the coordinates appended from `from` on are finite.
fn check_finite(path: &Path, coords: &[f64], from: usize, at: u64) -> Result<(), IoError> {
    match coords[from..].iter().position(|x| !x.is_finite()) {
        None => Ok(()),
        Some(i) => Err(byte_err(
            path,
            at,
            format!(
                "node {} of the block has a non-finite coordinate ({})",
                i / 3,
                coords[from + i]
            ),
        )),
    }
}

fn read_nodes_41_bin(
    w: &mut Words<'_, impl BufRead>,
    b: Bin,
    tags: &mut TagMap,
    coords: &mut Vec<f64>,
) -> Result<(), IoError> {
    let (sz, e) = (b.size, b.e);
    let path = w.path();
    w.rest_of_line()?;
    let head_at = w.offset();
    let mut h = [0u8; 32];
    w.read_raw(&mut h[..4 * sz], "the $Nodes header")?;
    let n_blocks = get_uint(&h, sz, e);
    let n_nodes = get_uint(&h[sz..], sz, e);
    let mut block_tags: Vec<u64> = Vec::new();
    for _ in 0..n_blocks {
        let at = w.offset();
        let mut bh = [0u8; 20];
        w.read_raw(&mut bh[..12 + sz], "a node block header")?;
        let dim = get_i32(&bh, e);
        let parametric = get_i32(&bh[8..], e);
        let n = get_uint(&bh[12..], sz, e);
        if !(0..=3).contains(&dim) || !(0..=1).contains(&parametric) {
            return Err(byte_err(
                path,
                at,
                format!("node block with entity dimension {dim} and parametric flag {parametric}"),
            ));
        }
        let extra = if parametric == 1 { dim as usize } else { 0 };
        block_tags.clear();
        read_records(w, n, sz, "node tags", |_, c, _| {
            block_tags.extend(c.chunks_exact(sz).map(|x| get_uint(x, sz, e)));
            Ok(())
        })?;
        let from = coords.len();
        let coords_at = w.offset();
        let rec = (3 + extra) * 8;
        read_records(w, n, rec, "node coordinates", |_, c, _| {
            if extra == 0 {
                push_f64s(c, e, coords);
            } else {
                for r in c.chunks_exact(rec) {
                    push_f64s(&r[..24], e, coords);
                }
            }
            Ok(())
        })?;
        check_finite(path, coords, from, coords_at)?;
        for &t in &block_tags {
            add_node_bin(path, tags, t, at)?;
        }
    }
    if tags.n as u64 != n_nodes {
        return Err(byte_err(
            path,
            head_at,
            format!(
                "$Nodes declares {n_nodes} nodes, its blocks hold {}",
                tags.n
            ),
        ));
    }
    Ok(())
}

fn read_nodes_22_bin(
    w: &mut Words<'_, impl BufRead>,
    b: Bin,
    tags: &mut TagMap,
    coords: &mut Vec<f64>,
) -> Result<(), IoError> {
    let e = b.e;
    let path = w.path();
    let n = w.u64("the number of nodes")?;
    w.rest_of_line()?;
    let at = w.offset();
    let from = coords.len();
    let mut node_tags: Vec<u64> = Vec::new();
    read_records(w, n, 28, "nodes", |_, c, _| {
        for r in c.chunks_exact(28) {
            node_tags.push(get_i32(r, e) as u32 as u64);
            push_f64s(&r[4..], e, coords);
        }
        Ok(())
    })?;
    check_finite(path, coords, from, at)?;
    for (i, &t) in node_tags.iter().enumerate() {
        add_node_bin(path, tags, t, at + 28 * i as u64)?;
    }
    Ok(())
}

/// Where the fields of a binary element record are: its tag, its node tags, its physical and
/// elementary tags (2.2: per element; 4.1: per block, given as values).
#[derive(Clone, Copy)]
struct RecordLayout {
    rec: usize,
    /// Byte offset and width of the node tags.
    nodes_at: usize,
    width: usize,
    e: Endian,
    shape: (CellKind, usize),
    /// Per-element tags (2.2): how many (the physical tag first, then the elementary one)
    /// after the element tag; `None` for 4.1's per-block values.
    n_tags: Option<usize>,
}

/// Decodes a chunk of whole element records (none a point element) in parallel straight into
/// `elems`: node tags to ids, tags to the attribute columns. The fast path of the binary
/// readers: it succeeds only when every record passes the element checks with distinct
/// vertices and the element tags keep the usual numbering; otherwise it leaves `elems`
/// unchanged and returns false, and the caller decodes the chunk record by record to name the
/// problem or keep the tags.
fn decode_records_par(
    c: &[u8],
    l: RecordLayout,
    tags: &TagMap,
    (physical, geometrical): (i64, i64),
    elems: &mut Elements,
) -> bool {
    use rayon::prelude::*;
    const PER: usize = 4096;
    let (kind, _) = l.shape;
    let k = kind.n_vertices();
    let n = c.len() / l.rec;
    let Some(first_tag) = elems.next_plain_tag() else {
        return false;
    };
    // 2.2's per-element tags: the fast path takes a chunk whose elements share them
    let tag_at = |r: &[u8], j: usize| get_i32(&r[4 * (1 + j)..], l.e) as i64;
    let per_elem = l.n_tags.unwrap_or(0);
    let (physical, geometrical) = match c.get(..l.rec) {
        Some(r) if per_elem > 0 => (tag_at(r, 0), if per_elem > 1 { tag_at(r, 1) } else { 0 }),
        _ => (physical, geometrical),
    };
    elems.run_of(kind);
    let run = &mut elems.blocks.last_mut().expect("run_of pushed it").1;
    let vbase = run.len();
    run.resize(vbase + n * k, 0);
    let ok = c
        .par_chunks(l.rec * PER)
        .zip(run[vbase..].par_chunks_mut(k * PER))
        .enumerate()
        .all(|(i, (src, dst))| {
            let mut ok = true;
            for (j, (r, d)) in src
                .chunks_exact(l.rec)
                .zip(dst.chunks_exact_mut(k))
                .enumerate()
            {
                let want = first_tag + (i * PER + j) as u64;
                ok &= get_uint(r, l.width, l.e) == want;
                if per_elem > 0 {
                    ok &= tag_at(r, 0) == physical;
                }
                if per_elem > 1 {
                    ok &= tag_at(r, 1) == geometrical;
                }
                let mut raw = [0u32; 8];
                for (x, slot) in r[l.nodes_at..]
                    .chunks_exact(l.width)
                    .take(k)
                    .zip(raw.iter_mut())
                {
                    *slot = tags.get(get_uint(x, l.width, l.e)).unwrap_or(u32::MAX);
                }
                // higher-order nodes must name nodes too
                for x in r[l.nodes_at..].chunks_exact(l.width).skip(k) {
                    ok &= tags.get(get_uint(x, l.width, l.e)).is_some();
                }
                for a in 0..k {
                    ok &= raw[a] != u32::MAX;
                    for b in 0..a {
                        ok &= raw[a] != raw[b];
                    }
                }
                if kind == CellKind::Prism {
                    for (slot, &p) in d.iter_mut().zip(PRISM_PERM.iter()) {
                        *slot = raw[p];
                    }
                } else {
                    d.copy_from_slice(&raw[..k]);
                }
            }
            ok
        });
    if !ok {
        run.truncate(vbase);
        if run.is_empty() {
            elems.blocks.pop();
        }
        return false;
    }
    elems.physical.push_n(n as u64, physical);
    elems.geometrical.push_n(n as u64, geometrical);
    if l.shape.1 > k {
        elems.higher_order += n;
    }
    true
}

/// One binary element record's node tags (`width` bytes each) into `verts`, checked.
#[allow(clippy::too_many_arguments)]
fn element_bin(
    path: &Path,
    r: &[u8],
    width: usize,
    e: Endian,
    (kind, nn): (CellKind, usize),
    tags: &TagMap,
    n_elem: u64,
    at: u64,
    verts: &mut Vec<u32>,
) -> Result<(), IoError> {
    let k = kind.n_vertices();
    let mut raw = [0u32; 8];
    for (i, x) in r.chunks_exact(width).take(nn).enumerate() {
        let t = get_uint(x, width, e);
        let v = tags.get(t).ok_or_else(|| {
            byte_err(
                path,
                at,
                format!("element node tag {t} is not a node of the $Nodes section"),
            )
        })?;
        if let Some(slot) = raw.get_mut(i).filter(|_| i < k) {
            *slot = v;
        }
    }
    verts.clear();
    if kind == CellKind::Prism {
        verts.extend(PRISM_PERM.iter().map(|&i| raw[i]));
    } else {
        verts.extend_from_slice(&raw[..k]);
    }
    tags.check(n_elem, verts)
        .map_err(|x| IoError::new(path, x).at(Location::Byte(at)))
}

fn read_elements_41_bin(
    w: &mut Words<'_, impl BufRead>,
    b: Bin,
    tags: &TagMap,
    elems: &mut Elements,
    entities: &std::collections::HashMap<(u64, i64), i64>,
) -> Result<(), IoError> {
    let (sz, e) = (b.size, b.e);
    let path = w.path();
    w.rest_of_line()?;
    let head_at = w.offset();
    let mut h = [0u8; 32];
    w.read_raw(&mut h[..4 * sz], "the $Elements header")?;
    let n_blocks = get_uint(&h, sz, e);
    let n_elems = get_uint(&h[sz..], sz, e);
    let mut seen: u64 = 0;
    let mut verts: Vec<u32> = Vec::with_capacity(8);
    for _ in 0..n_blocks {
        let at = w.offset();
        let mut bh = [0u8; 20];
        w.read_raw(&mut bh[..12 + sz], "an element block header")?;
        let dim = get_i32(&bh, e) as u32 as u64;
        let entity = get_i32(&bh[4..], e) as i64;
        let ty = get_i32(&bh[8..], e);
        let n = get_uint(&bh[12..], sz, e);
        let shape = gmsh_type_nodes(ty as u32 as u64)
            .ok_or_else(|| byte_err(path, at, unsupported_type(ty as u32 as u64)))?;
        let kind = shape.0;
        let rec = (1 + shape.1) * sz;
        let layout = RecordLayout {
            rec,
            nodes_at: sz,
            width: sz,
            e,
            shape,
            n_tags: None,
        };
        let physical = entities.get(&(dim, entity)).copied().unwrap_or(0);
        read_records(w, n, rec, "elements", |w, c, first| {
            if kind != CellKind::Simplex(0)
                && decode_records_par(c, layout, tags, (physical, entity), elems)
            {
                return Ok(());
            }
            let start = w.offset() - c.len() as u64;
            for (j, r) in c.chunks_exact(rec).enumerate() {
                let at = start + (j * rec) as u64;
                let id = seen + first + j as u64;
                element_bin(path, &r[sz..], sz, e, shape, tags, id, at, &mut verts)?;
                elems.count_order(shape);
                if kind == CellKind::Simplex(0) {
                    elems.points += 1;
                } else {
                    elems.push(get_uint(r, sz, e), kind, &verts, physical, entity);
                }
            }
            Ok(())
        })?;
        seen += n;
    }
    if seen != n_elems {
        return Err(byte_err(
            path,
            head_at,
            format!("$Elements declares {n_elems} elements, its blocks hold {seen}"),
        ));
    }
    Ok(())
}

fn read_elements_22_bin(
    w: &mut Words<'_, impl BufRead>,
    b: Bin,
    tags: &TagMap,
    elems: &mut Elements,
) -> Result<(), IoError> {
    let e = b.e;
    let path = w.path();
    let n = w.u64("the number of elements")?;
    w.rest_of_line()?;
    let mut seen: u64 = 0;
    let mut verts: Vec<u32> = Vec::with_capacity(8);
    while seen < n {
        let at = w.offset();
        let mut h = [0u8; 12];
        w.read_raw(&mut h, "an element header")?;
        let ty = get_i32(&h, e) as u32 as u64;
        let follow = get_i32(&h[4..], e);
        let n_tags = get_i32(&h[8..], e);
        let shape = gmsh_type_nodes(ty).ok_or_else(|| byte_err(path, at, unsupported_type(ty)))?;
        let kind = shape.0;
        if follow <= 0 || follow as u64 > n - seen || !(0..=64).contains(&n_tags) {
            return Err(byte_err(
                path,
                at,
                format!(
                    "element header says {follow} elements with {n_tags} tags follow, with {} of the {n} declared left",
                    n - seen
                ),
            ));
        }
        elems.has_physical |= n_tags > 0;
        let rec = (1 + n_tags as usize + shape.1) * 4;
        let skip = (1 + n_tags as usize) * 4;
        let layout = RecordLayout {
            rec,
            nodes_at: skip,
            width: 4,
            e,
            shape,
            n_tags: Some(n_tags as usize),
        };
        read_records(w, follow as u64, rec, "elements", |w, c, first| {
            if kind != CellKind::Simplex(0) && decode_records_par(c, layout, tags, (0, 0), elems) {
                return Ok(());
            }
            let start = w.offset() - c.len() as u64;
            for (j, r) in c.chunks_exact(rec).enumerate() {
                let at = start + (j * rec) as u64;
                let id = seen + first + j as u64;
                element_bin(path, &r[skip..], 4, e, shape, tags, id, at, &mut verts)?;
                elems.count_order(shape);
                if kind == CellKind::Simplex(0) {
                    elems.points += 1;
                } else {
                    let tag = |j: usize| get_i32(&r[4 * (1 + j)..], e) as i64;
                    let physical = if n_tags > 0 { tag(0) } else { 0 };
                    let geometrical = if n_tags > 1 { tag(1) } else { 0 };
                    elems.push(
                        get_i32(r, e) as u32 as u64,
                        kind,
                        &verts,
                        physical,
                        geometrical,
                    );
                }
            }
            Ok(())
        })?;
        seen += follow as u64;
    }
    Ok(())
}

/// Writes `k` as gmsh 4.1 ascii.
///
/// ```
/// use starplex::io::{gmsh, IoErrorKind, ReadOptions};
/// # use starplex::complex::IndexedComplex;
/// # use starplex::cell::CellKind;
/// let k = IndexedComplex::from_parts(3, vec![0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0].into(),
///                                    vec![(CellKind::Simplex(2), vec![0, 1, 2].into())]).unwrap();
/// let mut out = Vec::new();
/// gmsh::write(&mut out, &k).unwrap();
/// assert!(out.starts_with(b"$MeshFormat\n4.1 0 8\n$EndMeshFormat\n"));
/// let mut back = gmsh::read_from(&out[..], "m.msh".as_ref(), &ReadOptions::default()).unwrap();
/// // every gmsh element lies on a geometric entity: its tag comes back as an attribute
/// let tags = back.complex.take_attributes();
/// assert_eq!(tags.cell[0].name, "gmsh:geometrical");
/// assert_eq!(back.complex, k);
/// let k4 = IndexedComplex::from_parts(4, vec![0.0; 4].into(), vec![]).unwrap();
/// assert!(matches!(gmsh::write(&mut Vec::new(), &k4), Err(IoErrorKind::CannotWrite { .. })));
/// ```
///
/// # Errors
/// [`IoErrorKind::CannotWrite`] for an ambient dimension above 3 or simplices of dimension 4 and
/// more; OS errors of the writer.
pub fn write(w: &mut dyn Write, k: &IndexedComplex) -> Result<(), IoErrorKind> {
    check_writable(k, Format::Gmsh)?;
    write_41(w, k, false)
}

/// Writes `k` as gmsh 4.1 binary (file type 1, little-endian, 8-byte `size_t`): the same
/// sections as [`write()`], with the arrays in binary (format name `msh-binary` on the command
/// line: `starplex convert in.spx out.msh --to msh-binary`). Data sections have ascii headers
/// and binary entries (an `int` tag, then the doubles), as gmsh writes them.
///
/// ```
/// use starplex::attr::Attribute;
/// use starplex::cell::CellKind;
/// use starplex::complex::IndexedComplex;
/// use starplex::io::{gmsh, ReadOptions};
/// let mut k = IndexedComplex::from_parts(3, vec![0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.5].into(),
///     vec![(CellKind::Simplex(2), vec![0, 1, 2, 1, 3, 2].into())]).unwrap();
/// let mut a = k.take_attributes();
/// a.cell.push(Attribute::int("gmsh:physical", 1, vec![7, 9]));
/// k.set_attributes(a).unwrap();
/// let mut out = Vec::new();
/// gmsh::write_binary(&mut out, &k).unwrap();
/// assert!(out.starts_with(b"$MeshFormat\n4.1 1 8\n\x01\0\0\0\n$EndMeshFormat\n"));
/// let back = gmsh::read_from(&out[..], "b.msh".as_ref(), &ReadOptions::default()).unwrap();
/// let phys = back.complex.attributes().get(starplex::attr::AttrTarget::Cell, "gmsh:physical");
/// assert_eq!(phys, Some(&Attribute::int("gmsh:physical", 1, vec![7, 9])));
/// assert_eq!(back.complex.coords(), k.coords());
/// ```
///
/// # Errors
/// As [`write()`].
pub fn write_binary(w: &mut dyn Write, k: &IndexedComplex) -> Result<(), IoErrorKind> {
    check_writable(k, Format::GmshBinary)?;
    write_41(w, k, true)
}

/// Values of the 4.1 sections, as ascii words (spaces, one record per line) or binary
/// little-endian (`size_t` of 8 bytes, `int` of 4), buffered.
struct Out<'a> {
    w: &'a mut dyn Write,
    bin: bool,
    buf: Vec<u8>,
    /// At the start of an ascii line (no space before the next word).
    fresh: bool,
}

impl Out<'_> {
    fn sep(&mut self) {
        if !self.bin && !self.fresh {
            self.buf.push(b' ');
        }
        self.fresh = false;
    }
    fn size(&mut self, x: u64) {
        if self.bin {
            self.buf.extend_from_slice(&x.to_le_bytes());
        } else {
            self.sep();
            let _ = write!(self.buf, "{x}"); // (writing to a Vec cannot fail)
        }
    }
    fn int(&mut self, x: i32) {
        if self.bin {
            self.buf.extend_from_slice(&x.to_le_bytes());
        } else {
            self.sep();
            let _ = write!(self.buf, "{x}"); // (writing to a Vec cannot fail)
        }
    }
    fn real(&mut self, x: f64) -> std::io::Result<()> {
        if self.bin {
            self.buf.extend_from_slice(&x.to_le_bytes());
            Ok(())
        } else {
            self.sep();
            write_f64(&mut self.buf, x)
        }
    }
    /// Ends an ascii record (nothing in binary).
    fn nl(&mut self) -> std::io::Result<()> {
        if !self.bin {
            self.buf.push(b'\n');
        }
        self.fresh = true;
        if self.buf.len() >= 1 << 16 {
            self.w.write_all(&self.buf)?;
            self.buf.clear();
        }
        Ok(())
    }
    /// Text written as is in both encodings (section keywords, data headers).
    fn text(&mut self, s: &str) {
        self.buf.extend_from_slice(s.as_bytes());
        self.fresh = true;
    }
    /// `$End{name}` on a line of its own (after binary data, a line end first, as gmsh does).
    fn end(&mut self, name: &str) {
        if self.bin {
            self.buf.push(b'\n');
        }
        self.text(&format!("$End{name}\n"));
    }
    fn flush(&mut self) -> std::io::Result<()> {
        self.w.write_all(&self.buf)?;
        self.buf.clear();
        Ok(())
    }
}

/// The geometric entities of a 4.1 file: the entity tag of every cell, and per dimension the
/// entities `(tag, physical tag; 0 for none)` in order of first use.
struct EntityPlan {
    cell_entity: Vec<i32>,
    per_dim: [Vec<(i32, i32)>; 4],
}

/// The `gmsh:physical` and `gmsh:geometrical` columns that a 4.1 file holds (`physical`,
/// `geometrical`), decided together: physical tags must fit an `int`; geometrical tags must be
/// in `1..=i32::MAX` and, when physical tags are written, each geometrical tag must go with one
/// physical tag (in 4.1 the physical tag belongs to the entity, whatever the cells' dimension).
fn tag_columns_41(a: &Attributes) -> (Option<&[i64]>, Option<&[i64]>) {
    let col = |name: &str, lo: i64| match a.get(AttrTarget::Cell, name) {
        Some(c) if c.components == 1 => match &c.values {
            AttrValues::Int(v) if v.iter().all(|&x| x >= lo && x <= i32::MAX as i64) => {
                Some(v.as_slice())
            }
            _ => None,
        },
        _ => None,
    };
    let phys = col(TAG_NAMES[0], i32::MIN as i64);
    let mut geom = col(TAG_NAMES[1], 1);
    if let (Some(p), Some(g)) = (phys, geom) {
        let mut seen: FxHashMap<i64, i64> = FxHashMap::default();
        if g.iter()
            .zip(p)
            .any(|(&g, &p)| *seen.entry(g).or_insert(p) != p)
        {
            geom = None;
        }
    }
    (phys, geom)
}

/// One entity per geometrical tag (with its physical tag) when `gmsh:geometrical` is held
/// ([`tag_columns_41`]), else one entity per physical tag and dimension (tags 1, 2, ... in each
/// dimension), else one entity per dimension (tag 1). A complex with vertices and no cells has
/// the point entity 1 for its node block.
fn plan_entities(k: &IndexedComplex) -> EntityPlan {
    let (phys, geom) = tag_columns_41(k.attributes());
    let mut plan = EntityPlan {
        cell_entity: Vec::with_capacity(k.n_cells()),
        per_dim: Default::default(),
    };
    let mut known: FxHashMap<(usize, i64), i32> = FxHashMap::default();
    for b in k.blocks() {
        let d = b.kind.dim();
        for i in 0..b.len() {
            let id = b.first as usize + i;
            let p = phys.map_or(0, |v| v[id]) as i32;
            let key = match geom {
                Some(g) => g[id],
                None => p as i64,
            };
            let list = &mut plan.per_dim[d];
            let tag = *known.entry((d, key)).or_insert_with(|| {
                let t = match geom {
                    Some(_) => key as i32,
                    None => list.len() as i32 + 1,
                };
                list.push((t, p));
                t
            });
            plan.cell_entity.push(tag);
        }
    }
    if k.n_cells() == 0 && k.n_vertices() > 0 {
        plan.per_dim[0].push((1, 0));
    }
    plan
}

/// The 4.1 writer of both encodings.
fn write_41(w: &mut dyn Write, k: &IndexedComplex, bin: bool) -> Result<(), IoErrorKind> {
    let d = k.ambient_dim();
    let nv = k.n_vertices();
    let mut o = Out {
        w,
        bin,
        buf: Vec::with_capacity(1 << 16),
        fresh: true,
    };
    if bin {
        o.text("$MeshFormat\n4.1 1 8\n");
        o.int(1);
        o.text("\n$EndMeshFormat\n");
    } else {
        o.text("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n");
    }
    let plan = plan_entities(k);
    let mut lo = [0.0f64; 3];
    let mut hi = [0.0f64; 3];
    for (i, p) in k.coords().chunks_exact(d.max(1)).enumerate() {
        for a in 0..d {
            if i == 0 || p[a] < lo[a] {
                lo[a] = p[a];
            }
            if i == 0 || p[a] > hi[a] {
                hi[a] = p[a];
            }
        }
    }
    o.text("$Entities\n");
    for list in &plan.per_dim {
        o.size(list.len() as u64);
    }
    o.nl()?;
    for (dim, list) in plan.per_dim.iter().enumerate() {
        for &(tag, phys) in list {
            o.int(tag);
            let corners = if dim == 0 {
                &lo[..]
            } else {
                &[lo, hi].concat()[..]
            };
            for &x in corners {
                o.real(x)?;
            }
            o.size((phys != 0) as u64);
            if phys != 0 {
                o.int(phys);
            }
            if dim > 0 {
                o.size(0); // no bounding entities
            }
            o.nl()?;
        }
    }
    o.end("Entities");
    // the nodes: one block, on the first entity of the highest dimension in use
    o.text("$Nodes\n");
    match plan
        .per_dim
        .iter()
        .enumerate()
        .rev()
        .find(|(_, l)| !l.is_empty())
    {
        Some((node_dim, list)) if nv > 0 => {
            for x in [1, nv as u64, 1, nv as u64] {
                o.size(x);
            }
            o.nl()?;
            o.int(node_dim as i32);
            o.int(list[0].0);
            o.int(0);
            o.size(nv as u64);
            o.nl()?;
            for i in 1..=nv as u64 {
                o.size(i);
                o.nl()?;
            }
            for p in k.coords().chunks_exact(d.max(1)) {
                for &x in p {
                    o.real(x)?;
                }
                for _ in d..3 {
                    o.real(0.0)?;
                }
                o.nl()?;
            }
        }
        _ => {
            for _ in 0..4 {
                o.size(0);
            }
            o.nl()?;
        }
    }
    o.end("Nodes");
    // the elements: one block per run of cells of one kind on one entity
    let mut runs: Vec<(CellKind, i32, usize, usize)> = Vec::new();
    for b in k.blocks() {
        for i in 0..b.len() {
            let id = b.first as usize + i;
            let e = plan.cell_entity[id];
            match runs.last_mut() {
                Some((kind, t, _, n)) if *kind == b.kind && *t == e => *n += 1,
                _ => runs.push((b.kind, e, id, 1)),
            }
        }
    }
    let ne = k.n_cells() as u64;
    o.text("$Elements\n");
    for x in [runs.len() as u64, ne, ne.min(1), ne] {
        o.size(x);
    }
    o.nl()?;
    let mut cell = [0u32; 8];
    for &(kind, e, first, n) in &runs {
        o.int(kind.dim() as i32);
        o.int(e);
        o.int(gmsh_type(kind).unwrap_or(0) as i32);
        o.size(n as u64);
        o.nl()?;
        for id in first..first + n {
            o.size(id as u64 + 1);
            let c = k.cell(crate::ids::CellId(id as u32)).vertices;
            let c = if kind == CellKind::Prism {
                for (slot, &j) in cell.iter_mut().zip(&PRISM_PERM) {
                    *slot = c[j];
                }
                &cell[..6]
            } else {
                c
            };
            for &v in c {
                o.size(v as u64 + 1);
            }
            o.nl()?;
        }
    }
    o.end("Elements");
    o.flush()?;
    write_data(o.w, k, Format::Gmsh, bin)
}

/// The names of the attributes that the element tags carry.
const TAG_NAMES: [&str; 2] = ["gmsh:physical", "gmsh:geometrical"];

/// Whether a gmsh file written as `format` ([`Format::Gmsh`], [`Format::GmshBinary`],
/// [`Format::Gmsh22`] or [`Format::Gmsh22Binary`]) can hold the attribute `a` of `target`, looking
/// at `a` alone: `gmsh:physical` and `gmsh:geometrical` are integer cell columns of one component
/// written as element tags (2.2 ascii: any values; 2.2 binary: values that fit an `int`) or as geometric entities (4.1: physical tags that fit an
/// `int`, geometrical tags in `1..=i32::MAX`; [`dropped`] also checks that the two columns
/// agree); every other column is a `$NodeData` or `$ElementData` section (a name without `"`
/// or line breaks, 1 to 64 components, integers up to 2^53 in magnitude: gmsh data is double,
/// so integer columns read back as floats).
///
/// ```
/// use starplex::attr::{AttrTarget, Attribute};
/// use starplex::io::{gmsh, Format};
/// let phys = Attribute::int("gmsh:physical", 1, vec![1, 2]);
/// assert!(gmsh::holds(Format::Gmsh22, AttrTarget::Cell, &phys));
/// assert!(gmsh::holds(Format::Gmsh, AttrTarget::Cell, &phys));
/// let geom = Attribute::int("gmsh:geometrical", 1, vec![0, 2]);
/// assert!(!gmsh::holds(Format::Gmsh, AttrTarget::Cell, &geom)); // 4.1 entity tags start at 1
/// let big = Attribute::int("gmsh:physical", 1, vec![1 << 40]);
/// assert!(gmsh::holds(Format::Gmsh22, AttrTarget::Cell, &big));
/// assert!(!gmsh::holds(Format::Gmsh22Binary, AttrTarget::Cell, &big)); // tags are 32-bit ints
/// assert!(gmsh::holds(Format::Gmsh, AttrTarget::Vertex, &Attribute::float("T", 3, vec![0.0; 6])));
/// ```
pub fn holds(format: Format, target: AttrTarget, a: &Attribute) -> bool {
    if TAG_NAMES.contains(&a.name.as_str()) {
        if target != AttrTarget::Cell || a.components != 1 {
            return false;
        }
        let AttrValues::Int(v) = &a.values else {
            return false;
        };
        if format == Format::Gmsh22 {
            return true;
        }
        if format == Format::Gmsh22Binary {
            return v.iter().all(|&x| i32::try_from(x).is_ok());
        }
        let lo = if a.name == TAG_NAMES[0] {
            i32::MIN as i64
        } else {
            1
        };
        return v.iter().all(|&x| x >= lo && x <= i32::MAX as i64);
    }
    !a.name.contains(['"', '\n', '\r'])
        && (1..=64).contains(&a.components)
        && match &a.values {
            AttrValues::Int(v) => v.iter().all(|x| x.unsigned_abs() <= 1 << 53),
            AttrValues::Float(_) => true,
        }
}

/// The attributes of `a` that a gmsh file written as `format` does not hold (`kind name`, as
/// [`Format::dropped_attributes`]): those [`holds`] refuses and, in 4.1, a `gmsh:geometrical`
/// column whose tags do not each go with one physical tag (the writer then numbers the
/// entities by physical tag instead).
///
/// ```
/// use starplex::attr::{Attribute, Attributes};
/// use starplex::io::{gmsh, Format};
/// let a = Attributes {
///     vertex: vec![],
///     cell: vec![Attribute::int("gmsh:physical", 1, vec![5, 6]),
///                Attribute::int("gmsh:geometrical", 1, vec![1, 1])], // entity 1 in two groups
/// };
/// assert_eq!(gmsh::dropped(Format::Gmsh, &a), ["cell gmsh:geometrical"]);
/// assert!(gmsh::dropped(Format::Gmsh22, &a).is_empty()); // 2.2 tags each element
/// ```
pub fn dropped(format: Format, a: &Attributes) -> Vec<String> {
    let four = !matches!(format, Format::Gmsh22 | Format::Gmsh22Binary);
    let (_, geom) = tag_columns_41(a);
    let mut out = Vec::new();
    for target in [AttrTarget::Vertex, AttrTarget::Cell] {
        for c in a.of(target) {
            let joint =
                four && target == AttrTarget::Cell && c.name == TAG_NAMES[1] && geom.is_none();
            if joint || !holds(format, target, c) {
                out.push(format!("{target} {}", c.name));
            }
        }
    }
    out
}

/// Writes every data column `holds` keeps as `$NodeData` / `$ElementData` (time step 0, time
/// 0.0; node tag = vertex id + 1, element tag = cell id + 1, as the writers number them); in
/// `bin`, each entry as an `int` tag and its doubles, little-endian.
fn write_data(
    w: &mut dyn Write,
    k: &IndexedComplex,
    format: Format,
    bin: bool,
) -> Result<(), IoErrorKind> {
    let attrs = k.attributes();
    let mut line: Vec<u8> = Vec::with_capacity(1 << 16);
    for (target, cols, sec) in [
        (AttrTarget::Vertex, &attrs.vertex, "NodeData"),
        (AttrTarget::Cell, &attrs.cell, "ElementData"),
    ] {
        for a in cols {
            if TAG_NAMES.contains(&a.name.as_str()) || !holds(format, target, a) {
                continue;
            }
            let c = a.components;
            let n = a.n_items();
            writeln!(w, "${sec}\n1\n\"{}\"\n1\n0\n3\n0\n{c}\n{n}", a.name)?;
            for i in 0..n {
                use std::io::Write as _;
                if bin {
                    line.extend_from_slice(&(i as i32 + 1).to_le_bytes());
                } else {
                    write!(line, "{}", i + 1)?;
                }
                for j in i * c..(i + 1) * c {
                    let x = match &a.values {
                        AttrValues::Int(v) if bin => v[j] as f64,
                        AttrValues::Int(v) => {
                            write!(line, " {}", v[j])?;
                            continue;
                        }
                        AttrValues::Float(v) => v[j],
                    };
                    if bin {
                        line.extend_from_slice(&x.to_le_bytes());
                    } else {
                        line.push(b' ');
                        write_f64(&mut line, x)?;
                    }
                }
                if !bin {
                    line.push(b'\n');
                }
                if line.len() >= 1 << 16 {
                    w.write_all(&line)?;
                    line.clear();
                }
            }
            w.write_all(&line)?;
            line.clear();
            if bin {
                w.write_all(b"\n")?;
            }
            writeln!(w, "$End{sec}")?;
        }
    }
    Ok(())
}

/// Writes one node's coordinates, padded with zeros to 3, and the line end.
fn write_xyz(w: &mut dyn Write, p: &[f64]) -> std::io::Result<()> {
    for (i, &x) in p.iter().enumerate() {
        if i > 0 {
            w.write_all(b" ")?;
        }
        write_f64(w, x)?;
    }
    for _ in p.len()..3 {
        w.write_all(b" 0")?;
    }
    w.write_all(b"\n")
}

/// Refuses what gmsh cannot hold: more than 3 coordinates, simplices of dimension 4 and more.
///
/// ```
/// use starplex::complex::IndexedComplex;
/// use starplex::io::{gmsh, Format};
/// let k4 = IndexedComplex::from_parts(4, vec![0.0; 4].into(), vec![]).unwrap();
/// assert!(gmsh::check_writable(&k4, Format::Gmsh).is_err());
/// ```
///
/// # Errors
/// [`IoErrorKind::CannotWrite`] with the reason.
pub fn check_writable(k: &IndexedComplex, format: Format) -> Result<(), IoErrorKind> {
    let d = k.ambient_dim();
    if d > 3 {
        return Err(IoErrorKind::CannotWrite {
            format,
            reason: format!("gmsh nodes have 3 coordinates, the complex has {d}"),
        });
    }
    for b in k.blocks() {
        if gmsh_type(b.kind).is_none() {
            return Err(IoErrorKind::CannotWrite {
                format,
                reason: format!("gmsh has no first-order element for {} cells", b.kind),
            });
        }
    }
    Ok(())
}

/// Appends ` n1 n2 ...` (1-based node tags, prisms in gmsh's order) and a newline to `line`.
fn push_nodes(line: &mut String, kind: CellKind, c: &[u32]) {
    use std::fmt::Write as _;
    if kind == CellKind::Prism {
        for &j in &PRISM_PERM {
            let _ = write!(line, " {}", c[j] + 1);
        }
    } else {
        for v in c {
            let _ = write!(line, " {}", v + 1);
        }
    }
    line.push('\n');
}

/// Writes `k` as gmsh 2.2 ascii (the version older tools and meshio's default read): one
/// `$Nodes` entry per vertex, one `$Elements` entry per cell with two tags (physical group 0,
/// elementary entity 1 + the cell's dimension). Same node numbering, prism order and padding as
/// [`write()`].
///
/// ```
/// use starplex::cell::CellKind;
/// use starplex::complex::{BuildOptions, ComplexBuilder};
/// use starplex::io::{gmsh, ReadOptions};
/// let mut b = ComplexBuilder::new(3).unwrap();
/// for p in [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]] {
///     b.push_vertex(&p).unwrap();
/// }
/// b.push_cell(CellKind::Simplex(3), &[0, 1, 2, 3]).unwrap();
/// let k = b.build(&BuildOptions::default()).unwrap().0;
/// let mut out = Vec::new();
/// gmsh::write_22(&mut out, &k).unwrap();
/// assert!(out.starts_with(b"$MeshFormat\n2.2 0 8\n"));
/// let mut back = gmsh::read_from(&out[..], "t.msh".as_ref(), &ReadOptions::default()).unwrap();
/// // the elementary tag (1 + the dimension) comes back as the attribute gmsh:geometrical
/// let tags = back.complex.take_attributes();
/// assert_eq!(tags.cell[0], starplex::attr::Attribute::int("gmsh:geometrical", 1, vec![4]));
/// assert_eq!(back.complex, k);
/// ```
///
/// # Errors
/// As [`write()`].
pub fn write_22(w: &mut dyn Write, k: &IndexedComplex) -> Result<(), IoErrorKind> {
    check_writable(k, Format::Gmsh22)?;
    let d = k.ambient_dim();
    writeln!(w, "$MeshFormat\n2.2 0 8\n$EndMeshFormat")?;
    writeln!(w, "$Nodes\n{}", k.n_vertices())?;
    for (i, p) in k.coords().chunks_exact(d.max(1)).enumerate() {
        write!(w, "{} ", i + 1)?;
        write_xyz(w, p)?;
    }
    writeln!(w, "$EndNodes")?;
    writeln!(w, "$Elements\n{}", k.n_cells())?;
    let tag_col = |name: &str| match k.attributes().get(AttrTarget::Cell, name) {
        Some(a) if holds(Format::Gmsh22, AttrTarget::Cell, a) => match &a.values {
            AttrValues::Int(v) => Some(v.as_slice()),
            AttrValues::Float(_) => None,
        },
        _ => None,
    };
    let (phys, geom) = (tag_col(TAG_NAMES[0]), tag_col(TAG_NAMES[1]));
    let mut line = String::with_capacity(128);
    for b in k.blocks() {
        let t = gmsh_type(b.kind).unwrap_or(0);
        for i in 0..b.len() {
            use std::fmt::Write as _;
            let id = b.first as usize + i;
            let p = phys.map_or(0, |v| v[id]);
            let g = geom.map_or(1 + b.kind.dim() as i64, |v| v[id]);
            line.clear();
            let _ = write!(line, "{} {t} 2 {p} {g}", id + 1);
            push_nodes(&mut line, b.kind, b.cell(i));
            w.write_all(line.as_bytes())?;
        }
    }
    writeln!(w, "$EndElements")?;
    write_data(w, k, Format::Gmsh22, false)
}

/// Writes `k` as gmsh 2.2 binary (file type 1, little-endian, 8-byte doubles; format name
/// `msh22-binary` on the command line: `starplex convert in.spx out.msh --to msh22-binary`):
/// the `int` 1 after the format line for the endianness, `$Nodes` as (`int` tag, 3 doubles),
/// `$Elements` in one run per block (`int` header: type, count, 2 tags; then per element its
/// `int` tag, physical and elementary tags and nodes), data sections as in
/// [`write_binary`]. Tags and numbering as [`write_22`]; the physical and geometrical tags must
/// fit an `int` ([`holds`]), and so must the node and element counts.
///
/// ```
/// use starplex::attr::{AttrTarget, Attribute};
/// use starplex::cell::CellKind;
/// use starplex::complex::IndexedComplex;
/// use starplex::io::{gmsh, ReadOptions};
/// let mut k = IndexedComplex::from_parts(3, vec![0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.5].into(),
///     vec![(CellKind::Simplex(2), vec![0, 1, 2, 1, 3, 2].into())]).unwrap();
/// let mut a = k.take_attributes();
/// a.cell.push(Attribute::int("gmsh:physical", 1, vec![7, -9]));
/// k.set_attributes(a).unwrap();
/// let mut out = Vec::new();
/// gmsh::write_22_binary(&mut out, &k).unwrap();
/// assert!(out.starts_with(b"$MeshFormat\n2.2 1 8\n\x01\0\0\0\n$EndMeshFormat\n"));
/// let back = gmsh::read_from(&out[..], "b.msh".as_ref(), &ReadOptions::default()).unwrap();
/// let phys = back.complex.attributes().get(AttrTarget::Cell, "gmsh:physical");
/// assert_eq!(phys, Some(&Attribute::int("gmsh:physical", 1, vec![7, -9])));
/// assert_eq!(back.complex.coords(), k.coords());
/// ```
///
/// # Errors
/// As [`write()`], and [`IoErrorKind::CannotWrite`] for more than `i32::MAX` nodes or elements.
pub fn write_22_binary(w: &mut dyn Write, k: &IndexedComplex) -> Result<(), IoErrorKind> {
    let format = Format::Gmsh22Binary;
    check_writable(k, format)?;
    for (what, n) in [("nodes", k.n_vertices()), ("elements", k.n_cells())] {
        if n > i32::MAX as usize {
            return Err(IoErrorKind::CannotWrite {
                format,
                reason: format!("{n} {what}: gmsh 2.2 binary numbers them with 32-bit ints"),
            });
        }
    }
    let d = k.ambient_dim();
    w.write_all(b"$MeshFormat\n2.2 1 8\n")?;
    w.write_all(&1i32.to_le_bytes())?;
    w.write_all(b"\n$EndMeshFormat\n")?;
    writeln!(w, "$Nodes\n{}", k.n_vertices())?;
    let mut buf: Vec<u8> = Vec::with_capacity(1 << 16);
    for (i, p) in k.coords().chunks_exact(d.max(1)).enumerate() {
        buf.extend_from_slice(&(i as i32 + 1).to_le_bytes());
        for a in 0..3 {
            buf.extend_from_slice(&p.get(a).copied().unwrap_or(0.0).to_le_bytes());
        }
        if buf.len() >= 1 << 16 {
            w.write_all(&buf)?;
            buf.clear();
        }
    }
    w.write_all(&buf)?;
    buf.clear();
    writeln!(w, "\n$EndNodes\n$Elements\n{}", k.n_cells())?;
    let tag_col = |name: &str| match k.attributes().get(AttrTarget::Cell, name) {
        Some(a) if holds(format, AttrTarget::Cell, a) => match &a.values {
            AttrValues::Int(v) => Some(v.as_slice()),
            AttrValues::Float(_) => None,
        },
        _ => None,
    };
    let (phys, geom) = (tag_col(TAG_NAMES[0]), tag_col(TAG_NAMES[1]));
    for b in k.blocks() {
        if b.is_empty() {
            continue;
        }
        let t = gmsh_type(b.kind).unwrap_or(0) as i32;
        for x in [t, b.len() as i32, 2] {
            buf.extend_from_slice(&x.to_le_bytes());
        }
        for i in 0..b.len() {
            let id = b.first as usize + i;
            // holds() checked that both columns fit an int
            let p = phys.map_or(0, |v| v[id] as i32);
            let g = geom.map_or(1 + b.kind.dim() as i32, |v| v[id] as i32);
            for x in [id as i32 + 1, p, g] {
                buf.extend_from_slice(&x.to_le_bytes());
            }
            let c = b.cell(i);
            if b.kind == CellKind::Prism {
                for &j in &PRISM_PERM {
                    buf.extend_from_slice(&(c[j] as i32 + 1).to_le_bytes());
                }
            } else {
                for &v in c {
                    buf.extend_from_slice(&(v as i32 + 1).to_le_bytes());
                }
            }
            if buf.len() >= 1 << 16 {
                w.write_all(&buf)?;
                buf.clear();
            }
        }
    }
    w.write_all(&buf)?;
    writeln!(w, "\n$EndElements")?;
    write_data(w, k, format, true)
}
