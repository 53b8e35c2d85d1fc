//! `.spb`, the starplex binary format: a small checked header, then the coordinate and cell arrays
//! exactly as [`IndexedComplex`] holds them, so a file is loaded by memory-mapping it, with no
//! copy and no parsing ([`Buf::Mapped`]).
//!
//! Layout (every number little-endian, every array 8-byte aligned). Version 1 is written for a
//! complex without attributes, version 2 (the same plus an attribute table and arrays) for one
//! with attributes; both are read:
//!
//! ```text
//! offset  size  field
//!      0     8  magic b"STARPLX\0"
//!      8     4  format version (u32) = 1, or 2 with attributes
//!     12     4  endianness tag (u32) = 0x0102_0304 (bytes 04 03 02 01)
//!     16     4  ambient dimension (u32, 1..=64)
//!     20     4  number of blocks (u32)
//!     24     8  number of vertices (u64)
//!     32     8  number of cells (u64, the sum over blocks)
//!     40     8  byte offset of the coordinate array (u64)
//!     48     8  total file length in bytes (u64)
//!     56     8  FNV-1a 64 checksum of bytes 0..56, the block table and (version 2) the
//!               attribute table
//!     64  32*n  block table, one entry per block:
//!                 kind code (u32: 0 simplex, 1 quad, 2 pyramid, 3 prism, 4 hex),
//!                 dimension (u32), number of cells (u64), byte offset of its vertex array (u64),
//!                 reserved (u64, 0)
//!  (version 2 only) attribute table, right after the block table:
//!      T    16  head: number of columns (u32), reserved (u32, 0), bytes of the entries (u64)
//!   T+16   ...  one entry per column (vertex columns first, then cell columns):
//!                 target (u8: 0 vertex, 1 cell), type (u8: 0 int = i64, 1 float = f64),
//!                 reserved (u16, 0), name length (u32), components (u64),
//!                 byte offset of its values (u64), the UTF-8 name, zero padding to 8
//!    ...        coordinates: n_vertices * ambient_dim f64, at the offset above
//!    ...        each block's vertex ids: n_cells * vertices-per-cell u32, at its offset
//!    ...        (version 2) each column's values: items * components i64 or f64, at its offset
//! ```
//!
//! Arrays follow each other in this order, each starting at the end of the previous one rounded
//! up to a multiple of 8 (zero padding); the reader accepts exactly this layout and checks every
//! field against the file's real length before touching an array, so a corrupted or hostile file
//! gives an [`IoError`] with the byte offset of the bad field, never a panic or an allocation sized
//! by a declared count. The arrays themselves are not checksummed: [`IndexedComplex::from_parts`]
//! checks every vertex index (in range, no repeats) and every coordinate (finite). Maximality of
//! the top cells is not re-checked (the writer only writes checked complexes).
//!
//! Big-endian hosts are refused with a clear error (the arrays could not be used in place).
//!
//! ```
//! use starplex::io::{self, ReadOptions};
//! use starplex::complex::{ComplexBuilder, BuildOptions};
//! use starplex::cell::CellKind;
//! let mut b = ComplexBuilder::new(3).unwrap();
//! for p in [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]] {
//!     b.push_vertex(&p).unwrap();
//! }
//! b.push_cell(CellKind::Simplex(3), &[0, 1, 2, 3]).unwrap();
//! let (k, _) = b.build(&BuildOptions::default()).unwrap();
//! let path = std::env::temp_dir().join(format!("starplex-doc-spb-{}.spb", std::process::id()));
//! io::write(&path, &k, None).unwrap();
//! let back = io::read(&path, &ReadOptions::default()).unwrap().complex;
//! assert_eq!(back, k);
//! assert!(back.coords_buf().is_mapped());
//! std::fs::remove_file(&path).ok();
//! ```
use std::io::Write;
use std::path::Path;
use std::sync::Arc;

use super::{spb_attrs, Format, IoError, IoErrorKind, Location, ReadOptions, ReadResult};
use crate::attr::AttrTarget;
use crate::buf::Buf;
use crate::cell::{CellKind, MAX_SIMPLEX_DIM};
use crate::complex::{IndexedComplex, MAX_AMBIENT_DIM};

/// The first 8 bytes of every `.spb` file.
///
/// ```
/// assert_eq!(&starplex::io::binary::MAGIC, b"STARPLX\0");
/// ```
pub const MAGIC: [u8; 8] = *b"STARPLX\0";
/// The newest format version this code writes and reads (version 2: with attributes).
///
/// ```
/// assert_eq!(starplex::io::binary::VERSION, 2);
/// ```
pub const VERSION: u32 = 2;
/// The version written for a complex without attributes (the same bytes as before attributes
/// existed, so older readers and `starplex-mpi` keep reading them).
///
/// ```
/// assert_eq!(starplex::io::binary::VERSION_NO_ATTRIBUTES, 1);
/// ```
pub const VERSION_NO_ATTRIBUTES: u32 = 1;
/// Written as a little-endian u32; reads back as this value only on a little-endian reading.
///
/// ```
/// assert_eq!(starplex::io::binary::ENDIAN_TAG.to_le_bytes(), [4, 3, 2, 1]);
/// ```
pub const ENDIAN_TAG: u32 = 0x0102_0304;
/// Size of the fixed header in bytes.
///
/// ```
/// assert_eq!(starplex::io::binary::HEADER_LEN, 64);
/// ```
pub const HEADER_LEN: usize = 64;
/// Size of one block-table entry in bytes.
///
/// ```
/// assert_eq!(starplex::io::binary::BLOCK_ENTRY_LEN, 32);
/// ```
pub const BLOCK_ENTRY_LEN: usize = 32;
/// Size of the attribute table's head (version 2) in bytes.
///
/// ```
/// assert_eq!(starplex::io::binary::ATTR_HEAD_LEN, 16);
/// ```
pub const ATTR_HEAD_LEN: usize = 16;
/// Size of the fixed part of one attribute entry (the name and its padding follow) in bytes.
///
/// ```
/// assert_eq!(starplex::io::binary::ATTR_ENTRY_LEN, 24);
/// ```
pub const ATTR_ENTRY_LEN: usize = 24;

/// One column of a version-2 file's attribute table (what [`read_header`] returns in
/// [`SpbHeader::attrs`]).
///
/// ```
/// use starplex::attr::{AttrTarget, Attribute, Attributes};
/// use starplex::cell::CellKind;
/// use starplex::complex::IndexedComplex;
/// use starplex::io::binary;
/// let mut k = IndexedComplex::from_parts(1, vec![0.0, 1.0].into(),
///     vec![(CellKind::Simplex(1), vec![0, 1].into())]).unwrap();
/// k.set_attributes(Attributes { vertex: vec![], cell: vec![Attribute::int("tag", 2, vec![4, 5])] }).unwrap();
/// let mut bytes = Vec::new();
/// binary::write(&mut bytes, &k).unwrap();
/// let h = binary::read_header(&bytes, "a.spb".as_ref()).unwrap();
/// assert_eq!(h.version, 2);
/// let a = &h.attrs[0];
/// assert_eq!((a.name.as_str(), a.target, a.int, a.components), ("tag", AttrTarget::Cell, true, 2));
/// assert_eq!(&bytes[a.offset as usize..a.offset as usize + 8], &4i64.to_le_bytes());
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SpbAttr {
    /// The column's name.
    pub name: String,
    /// Vertices or cells.
    pub target: AttrTarget,
    /// Integer (`i64`) values, else float (`f64`).
    pub int: bool,
    /// Values per item.
    pub components: u64,
    /// Byte offset of the values (items × components, 8 bytes each).
    pub offset: u64,
}

impl SpbAttr {
    /// Adds this column to `a` (to its vertex or cell columns) with the given values: 8-byte
    /// little-endian numbers, items × components of them.
    ///
    /// ```
    /// use starplex::attr::{AttrTarget, Attributes};
    /// use starplex::io::binary::SpbAttr;
    /// let e = SpbAttr { name: "t".into(), target: AttrTarget::Cell, int: true, components: 1, offset: 0 };
    /// let mut a = Attributes::default();
    /// let bytes: Vec<u8> = [7i64, -1].iter().flat_map(|x| x.to_le_bytes()).collect();
    /// e.push_column(&mut a, bytes.chunks_exact(8));
    /// assert_eq!(a.cell[0].values.get_f64(1), -1.0);
    /// ```
    pub fn push_column<'a>(
        &self,
        a: &mut crate::attr::Attributes,
        words: impl Iterator<Item = &'a [u8]>,
    ) {
        use crate::attr::{AttrValues, Attribute};
        let words = words.map(|c| {
            let mut b = [0u8; 8];
            b.copy_from_slice(&c[..8]);
            b
        });
        let values = if self.int {
            AttrValues::Int(words.map(i64::from_le_bytes).collect())
        } else {
            AttrValues::Float(words.map(f64::from_le_bytes).collect())
        };
        let col = Attribute {
            name: self.name.clone(),
            components: self.components as usize,
            values,
        };
        match self.target {
            AttrTarget::Vertex => a.vertex.push(col),
            AttrTarget::Cell => a.cell.push(col),
        }
    }
}

/// The parsed header of a `.spb` file (what [`read_header`] returns).
///
/// ```
/// use starplex::io::binary;
/// use starplex::complex::{ComplexBuilder, BuildOptions};
/// use starplex::cell::CellKind;
/// let mut b = ComplexBuilder::new(2).unwrap();
/// for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]] {
///     b.push_vertex(&p).unwrap();
/// }
/// b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// let (k, _) = b.build(&BuildOptions::default()).unwrap();
/// let mut bytes = Vec::new();
/// binary::write(&mut bytes, &k).unwrap();
/// let h = binary::read_header(&bytes, "t.spb".as_ref()).unwrap();
/// assert_eq!((h.ambient_dim, h.n_vertices, h.n_cells), (2, 3, 1));
/// assert_eq!(h.blocks, vec![(CellKind::Simplex(2), 1, 64 + 32 + 48)]);
/// assert_eq!((h.version, h.attrs.len()), (1, 0)); // no attributes: version 1
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SpbHeader {
    /// Coordinates per vertex.
    pub ambient_dim: usize,
    /// Number of vertices.
    pub n_vertices: u64,
    /// Number of top cells.
    pub n_cells: u64,
    /// Byte offset of the coordinate array.
    pub coords_offset: u64,
    /// Blocks: kind, number of cells, byte offset of the vertex array.
    pub blocks: Vec<(CellKind, u64, u64)>,
    /// File length in bytes.
    pub file_len: u64,
    /// The format version (1, or 2 when the file holds attributes).
    pub version: u32,
    /// The attribute table (empty in version 1).
    pub attrs: Vec<SpbAttr>,
}

fn kind_code(k: CellKind) -> (u32, u32) {
    match k {
        CellKind::Simplex(d) => (0, d as u32),
        CellKind::Quad => (1, 2),
        CellKind::Pyramid => (2, 3),
        CellKind::Prism => (3, 3),
        CellKind::Hex => (4, 3),
    }
}

fn kind_from_code(code: u32, dim: u32) -> Result<CellKind, String> {
    let k = match (code, dim) {
        (0, d) if d as usize <= MAX_SIMPLEX_DIM => CellKind::Simplex(d as u8),
        (0, d) => {
            return Err(format!(
                "simplex dimension {d} is above the supported maximum {MAX_SIMPLEX_DIM}"
            ))
        }
        (1, 2) => CellKind::Quad,
        (2, 3) => CellKind::Pyramid,
        (3, 3) => CellKind::Prism,
        (4, 3) => CellKind::Hex,
        (1..=4, d) => return Err(format!("cell kind code {code} with wrong dimension {d}")),
        _ => return Err(format!("unknown cell kind code {code}")),
    };
    Ok(k)
}

/// FNV-1a, 64 bit: a small checksum of the header and block table.
fn fnv1a(chunks: &[&[u8]]) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for c in chunks {
        for &b in *c {
            h ^= b as u64;
            h = h.wrapping_mul(0x0000_0100_0000_01b3);
        }
    }
    h
}

use super::spb_attrs::align8;

/// Where each array goes.
struct Layout {
    coords: u64,
    blocks: Vec<u64>,
    attrs: Vec<u64>,
    file_len: u64,
}

/// The layout a complex is written with. `attr_table` is the attribute table's total length
/// (head and entries; `None` in version 1) and `attrs` the number of values of each column.
fn layout(
    ambient_dim: u64,
    n_vertices: u64,
    blocks: &[(CellKind, u64)],
    attr_table: Option<u64>,
    attrs: &[u64],
) -> Option<Layout> {
    let table = (HEADER_LEN as u64)
        .checked_add((BLOCK_ENTRY_LEN as u64).checked_mul(blocks.len() as u64)?)?
        .checked_add(attr_table.unwrap_or(0))?;
    let coords_offset = align8(table);
    let mut end =
        coords_offset.checked_add(n_vertices.checked_mul(ambient_dim)?.checked_mul(8)?)?;
    let mut offs = Vec::with_capacity(blocks.len());
    for &(kind, n) in blocks {
        let start = align8(end);
        offs.push(start);
        end = start.checked_add(n.checked_mul(kind.n_vertices() as u64)?.checked_mul(4)?)?;
    }
    let mut a_offs = Vec::with_capacity(attrs.len());
    for &n in attrs {
        let start = align8(end);
        a_offs.push(start);
        end = start.checked_add(n.checked_mul(8)?)?;
    }
    Some(Layout {
        coords: coords_offset,
        blocks: offs,
        attrs: a_offs,
        file_len: align8(end),
    })
}

/// Where the arrays of a `.spb` go, and its first bytes: what a writer that writes the arrays
/// in pieces needs (`starplex-mpi`: every rank writes its own byte ranges of one file). The
/// header bytes (header, checksum, block table, and in version 2 the attribute table) start
/// the file; the coordinates start at `coords_offset`, block `b`'s vertex ids at
/// `block_offsets[b]`, attribute column `i`'s values at `attrs[i].offset`; the file is
/// `file_len` bytes long, zero between the arrays.
///
/// ```
/// use starplex::io::binary::{self, SpbPlan};
/// use starplex::complex::{ComplexBuilder, BuildOptions};
/// use starplex::cell::CellKind;
/// let mut b = ComplexBuilder::new(2).unwrap();
/// for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]] {
///     b.push_vertex(&p).unwrap();
/// }
/// b.push_cell(CellKind::Simplex(2), &[0, 1, 2]).unwrap();
/// let (k, _) = b.build(&BuildOptions::default()).unwrap();
/// let plan = SpbPlan::new(2, 3, &[(CellKind::Simplex(2), 1)]).unwrap();
/// // the pieces, put where the plan says, are the bytes `write` writes
/// let mut bytes = vec![0u8; plan.file_len as usize];
/// bytes[..plan.header.len()].copy_from_slice(&plan.header);
/// let at = plan.coords_offset as usize;
/// for (i, x) in k.coords().iter().enumerate() {
///     bytes[at + 8 * i..at + 8 * i + 8].copy_from_slice(&x.to_le_bytes());
/// }
/// let at = plan.block_offsets[0] as usize;
/// for (i, v) in k.blocks()[0].vertices.iter().enumerate() {
///     bytes[at + 4 * i..at + 4 * i + 4].copy_from_slice(&v.to_le_bytes());
/// }
/// let mut whole = Vec::new();
/// binary::write(&mut whole, &k).unwrap();
/// assert_eq!(bytes, whole);
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SpbPlan {
    /// The first bytes of the file: header, checksum, block table.
    pub header: Vec<u8>,
    /// Byte offset of the coordinate array.
    pub coords_offset: u64,
    /// Byte offset of each block's vertex array.
    pub block_offsets: Vec<u64>,
    /// Length of the file.
    pub file_len: u64,
    /// The attribute columns in file order (vertex columns first), each with the byte offset
    /// of its values (items × components, 8 bytes each); empty in version 1.
    pub attrs: Vec<SpbAttr>,
}

impl SpbPlan {
    /// The plan of a version-1 file with `n_vertices` points of `ambient_dim` coordinates and
    /// `blocks` (kind, number of cells); `None` when the sizes overflow the layout.
    ///
    /// ```
    /// use starplex::io::binary::SpbPlan;
    /// use starplex::cell::CellKind;
    /// let p = SpbPlan::new(3, 4, &[(CellKind::Simplex(3), 1)]).unwrap();
    /// assert_eq!((p.coords_offset, p.block_offsets[0], p.file_len), (96, 192, 208));
    /// assert!(SpbPlan::new(3, u64::MAX, &[]).is_none());
    /// ```
    pub fn new(ambient_dim: usize, n_vertices: u64, blocks: &[(CellKind, u64)]) -> Option<SpbPlan> {
        let lay = layout(ambient_dim as u64, n_vertices, blocks, None, &[])?;
        let n_cells = blocks
            .iter()
            .try_fold(0u64, |a, &(_, n)| a.checked_add(n))?;
        let (mut header, table) = header_parts(
            VERSION_NO_ATTRIBUTES,
            ambient_dim,
            n_vertices,
            n_cells,
            blocks,
            &lay,
        );
        let sum = fnv1a(&[&header, &table]);
        header.extend_from_slice(&sum.to_le_bytes());
        header.extend_from_slice(&table);
        Some(SpbPlan {
            header,
            coords_offset: lay.coords,
            block_offsets: lay.blocks,
            file_len: lay.file_len,
            attrs: Vec::new(),
        })
    }

    /// The plan of a file with attribute columns (version 2; version 1 when `columns` is
    /// empty): `columns` gives each column's name, target, type and components (their
    /// `offset` is ignored; vertex columns are put before cell columns, as the format orders
    /// them), and [`SpbPlan::attrs`] says where each column's values go. `None` when the sizes
    /// overflow the layout or two columns of one target share a name.
    ///
    /// ```
    /// use starplex::attr::{AttrTarget, Attribute, Attributes};
    /// use starplex::cell::CellKind;
    /// use starplex::complex::IndexedComplex;
    /// use starplex::io::binary::{self, SpbAttr, SpbPlan};
    /// let mut k = IndexedComplex::from_parts(1, vec![0.0, 1.0, 2.0].into(),
    ///     vec![(CellKind::Simplex(1), vec![0, 1, 1, 2].into())]).unwrap();
    /// k.set_attributes(Attributes {
    ///     vertex: vec![Attribute::float("t", 1, vec![0.5, 1.5, 2.5])],
    ///     cell: vec![Attribute::int("tag", 1, vec![7, 8])],
    /// }).unwrap();
    /// let mut whole = Vec::new();
    /// binary::write(&mut whole, &k).unwrap();
    /// let cols = binary::read_header(&whole, "a.spb".as_ref()).unwrap().attrs;
    /// let plan = SpbPlan::with_attributes(1, 3, &[(CellKind::Simplex(1), 2)], &cols).unwrap();
    /// // the pieces, put where the plan says, are the bytes `write` writes
    /// let mut bytes = vec![0u8; plan.file_len as usize];
    /// bytes[..plan.header.len()].copy_from_slice(&plan.header);
    /// let mut put = |at: u64, words: Vec<[u8; 8]>| {
    ///     for (i, w) in words.iter().enumerate() {
    ///         bytes[at as usize + 8 * i..at as usize + 8 * i + 8].copy_from_slice(w);
    ///     }
    /// };
    /// put(plan.coords_offset, k.coords().iter().map(|x| x.to_le_bytes()).collect());
    /// put(plan.attrs[0].offset, vec![0.5f64.to_le_bytes(), 1.5f64.to_le_bytes(), 2.5f64.to_le_bytes()]);
    /// put(plan.attrs[1].offset, vec![7i64.to_le_bytes(), 8i64.to_le_bytes()]);
    /// let at = plan.block_offsets[0] as usize;
    /// for (i, v) in [0u32, 1, 1, 2].iter().enumerate() {
    ///     bytes[at + 4 * i..at + 4 * i + 4].copy_from_slice(&v.to_le_bytes());
    /// }
    /// assert_eq!(bytes, whole);
    /// ```
    pub fn with_attributes(
        ambient_dim: usize,
        n_vertices: u64,
        blocks: &[(CellKind, u64)],
        columns: &[SpbAttr],
    ) -> Option<SpbPlan> {
        if columns.is_empty() {
            return SpbPlan::new(ambient_dim, n_vertices, blocks);
        }
        let n_cells = blocks
            .iter()
            .try_fold(0u64, |a, &(_, n)| a.checked_add(n))?;
        // the format's column order: vertex columns, then cell columns (each in given order)
        let mut schema = crate::attr::Attributes::default();
        for c in columns {
            let values = if c.int {
                crate::attr::AttrValues::Int(Vec::new())
            } else {
                crate::attr::AttrValues::Float(Vec::new())
            };
            let col = crate::attr::Attribute {
                name: c.name.clone(),
                components: usize::try_from(c.components).ok()?,
                values,
            };
            let same = |a: &crate::attr::Attribute| a.name == c.name;
            match c.target {
                AttrTarget::Vertex if !schema.vertex.iter().any(same) => schema.vertex.push(col),
                AttrTarget::Cell if !schema.cell.iter().any(same) => schema.cell.push(col),
                _ => return None,
            }
        }
        let cols = spb_attrs::columns(&schema);
        let entries = spb_attrs::entries_len(&cols)?;
        let n_values = cols
            .iter()
            .map(|(t, c)| {
                let items = match t {
                    AttrTarget::Vertex => n_vertices,
                    AttrTarget::Cell => n_cells,
                };
                items.checked_mul(c.components as u64)
            })
            .collect::<Option<Vec<u64>>>()?;
        let lay = layout(
            ambient_dim as u64,
            n_vertices,
            blocks,
            Some(ATTR_HEAD_LEN as u64 + entries),
            &n_values,
        )?;
        let (mut header, table) =
            header_parts(VERSION, ambient_dim, n_vertices, n_cells, blocks, &lay);
        let atable = spb_attrs::encode(&cols, &lay.attrs, entries);
        let sum = fnv1a(&[&header, &table, &atable]);
        header.extend_from_slice(&sum.to_le_bytes());
        header.extend_from_slice(&table);
        header.extend_from_slice(&atable);
        let attrs = cols
            .iter()
            .zip(&lay.attrs)
            .map(|((t, c), &offset)| SpbAttr {
                name: c.name.clone(),
                target: *t,
                int: matches!(c.values, crate::attr::AttrValues::Int(_)),
                components: c.components as u64,
                offset,
            })
            .collect();
        Some(SpbPlan {
            header,
            coords_offset: lay.coords,
            block_offsets: lay.blocks,
            file_len: lay.file_len,
            attrs,
        })
    }
}

/// The header up to its checksum, and the block table.
fn header_parts(
    version: u32,
    ambient_dim: usize,
    n_vertices: u64,
    n_cells: u64,
    blocks: &[(CellKind, u64)],
    lay: &Layout,
) -> (Vec<u8>, Vec<u8>) {
    let mut head = Vec::with_capacity(HEADER_LEN);
    head.extend_from_slice(&MAGIC);
    head.extend_from_slice(&version.to_le_bytes());
    head.extend_from_slice(&ENDIAN_TAG.to_le_bytes());
    head.extend_from_slice(&(ambient_dim as u32).to_le_bytes());
    head.extend_from_slice(&(blocks.len() as u32).to_le_bytes());
    head.extend_from_slice(&n_vertices.to_le_bytes());
    head.extend_from_slice(&n_cells.to_le_bytes());
    head.extend_from_slice(&lay.coords.to_le_bytes());
    head.extend_from_slice(&lay.file_len.to_le_bytes());
    let mut table = Vec::with_capacity(BLOCK_ENTRY_LEN * blocks.len());
    for (&(kind, n), &off) in blocks.iter().zip(&lay.blocks) {
        let (code, dim) = kind_code(kind);
        table.extend_from_slice(&code.to_le_bytes());
        table.extend_from_slice(&dim.to_le_bytes());
        table.extend_from_slice(&n.to_le_bytes());
        table.extend_from_slice(&off.to_le_bytes());
        table.extend_from_slice(&0u64.to_le_bytes());
    }
    (head, table)
}

/// Writes `k` as `.spb`: version 1 without attributes, version 2 with its attribute table and
/// arrays otherwise.
///
/// ```
/// use starplex::io::binary;
/// use starplex::complex::{ComplexBuilder, BuildOptions};
/// let mut b = ComplexBuilder::new(2).unwrap();
/// b.push_vertex(&[0.5, 1.5]).unwrap();
/// let (k, _) = b.build(&BuildOptions::default()).unwrap();
/// let mut out = Vec::new();
/// binary::write(&mut out, &k).unwrap();
/// assert_eq!(&out[..8], b"STARPLX\0");
/// assert_eq!(out.len(), 64 + 16);
/// let h = binary::read_header(&out, "mem.spb".as_ref()).unwrap();
/// assert_eq!(h.n_vertices, 1);
/// ```
///
/// # Errors
/// OS errors of the writer.
pub fn write(w: &mut dyn Write, k: &IndexedComplex) -> Result<(), IoErrorKind> {
    let blocks: Vec<(CellKind, u64)> = k
        .blocks()
        .iter()
        .map(|b| (b.kind, b.len() as u64))
        .collect();
    let nv = k.n_vertices() as u64;
    let cols = spb_attrs::columns(k.attributes());
    let too_large = || IoErrorKind::Parse("complex too large for the .spb layout".into());
    let entries = spb_attrs::entries_len(&cols).ok_or_else(too_large)?;
    let attr_table = (!cols.is_empty()).then_some(ATTR_HEAD_LEN as u64 + entries);
    let n_values: Vec<u64> = cols.iter().map(|(_, c)| c.values.len() as u64).collect();
    let lay =
        layout(k.ambient_dim() as u64, nv, &blocks, attr_table, &n_values).ok_or_else(too_large)?;
    let (coords_offset, file_len) = (lay.coords, lay.file_len);
    let version = if cols.is_empty() {
        VERSION_NO_ATTRIBUTES
    } else {
        VERSION
    };
    let (mut head, table) = header_parts(
        version,
        k.ambient_dim(),
        nv,
        k.n_cells() as u64,
        &blocks,
        &lay,
    );
    let atable = if cols.is_empty() {
        Vec::new()
    } else {
        spb_attrs::encode(&cols, &lay.attrs, entries)
    };
    let sum = fnv1a(&[&head, &table, &atable]);
    head.extend_from_slice(&sum.to_le_bytes());
    w.write_all(&head)?;
    w.write_all(&table)?;
    w.write_all(&atable)?;
    let mut pos = (HEADER_LEN + table.len() + atable.len()) as u64;
    let pad = |w: &mut dyn Write, pos: &mut u64, to: u64| -> std::io::Result<()> {
        let zeros = [0u8; 8];
        w.write_all(&zeros[..(to - *pos) as usize])?;
        *pos = to;
        Ok(())
    };
    pad(w, &mut pos, coords_offset)?;
    write_le_f64(w, k.coords())?;
    pos += 8 * k.coords().len() as u64;
    for (b, &off) in k.blocks().iter().zip(&lay.blocks) {
        pad(w, &mut pos, off)?;
        write_le_u32(w, &b.vertices)?;
        pos += 4 * b.vertices.len() as u64;
    }
    for ((_, c), &off) in cols.iter().zip(&lay.attrs) {
        pad(w, &mut pos, off)?;
        spb_attrs::write_values(w, c)?;
        pos += 8 * c.values.len() as u64;
    }
    pad(w, &mut pos, file_len)?;
    Ok(())
}

fn write_le_f64(w: &mut dyn Write, v: &[f64]) -> std::io::Result<()> {
    if cfg!(target_endian = "little") {
        w.write_all(bytemuck::cast_slice(v))
    } else {
        for x in v {
            w.write_all(&x.to_le_bytes())?;
        }
        Ok(())
    }
}

fn write_le_u32(w: &mut dyn Write, v: &[u32]) -> std::io::Result<()> {
    if cfg!(target_endian = "little") {
        w.write_all(bytemuck::cast_slice(v))
    } else {
        for x in v {
            w.write_all(&x.to_le_bytes())?;
        }
        Ok(())
    }
}

#[inline]
fn u32_at(b: &[u8], at: usize) -> u32 {
    u32::from_le_bytes(b[at..at + 4].try_into().expect("4 bytes"))
}

#[inline]
fn u64_at(b: &[u8], at: usize) -> u64 {
    u64::from_le_bytes(b[at..at + 8].try_into().expect("8 bytes"))
}

/// Parses and checks the header and block table of a `.spb` file held in `bytes` (the whole
/// file); `path` names it in errors. Every declared size is checked against `bytes.len()`.
///
/// ```
/// use starplex::io::binary;
/// let e = binary::read_header(b"not a starplex file at all, sorry", "x.spb".as_ref()).unwrap_err();
/// assert!(e.to_string().starts_with("x.spb: byte 0: "), "{e}");
/// ```
///
/// # Errors
/// A file shorter than the header, a wrong magic, version or endianness tag, a checksum mismatch,
/// counts or offsets that do not fit the file (with the byte offset of the field).
pub fn read_header(bytes: &[u8], path: &Path) -> Result<SpbHeader, IoError> {
    let err = |at: usize, msg: String| IoError::parse(path, Some(Location::Byte(at as u64)), msg);
    let len = bytes.len() as u64;
    let version = check_preamble(bytes, &err)?;
    let ambient = u32_at(bytes, 16) as u64;
    let n_blocks = u32_at(bytes, 20) as u64;
    let n_vertices = u64_at(bytes, 24);
    let n_cells = u64_at(bytes, 32);
    let coords_offset = u64_at(bytes, 40);
    let file_len = u64_at(bytes, 48);
    let sum = u64_at(bytes, 56);
    if file_len != len {
        let what = if file_len > len {
            "truncated"
        } else {
            "has trailing bytes"
        };
        return Err(err(
            48,
            format!("the header says the file has {file_len} bytes but it has {len}: the file is {what}"),
        ));
    }
    let attr_head = check_table(bytes, n_blocks, sum, version, &err)?;
    check_counts(ambient, n_vertices, n_cells, coords_offset, len, &err)?;
    let blocks = read_blocks(bytes, n_blocks, n_cells, len, &err)?;
    let attrs = match attr_head {
        Some((at, n, entries)) => spb_attrs::read_entries(
            bytes,
            at + ATTR_HEAD_LEN,
            n,
            entries,
            n_vertices,
            n_cells,
            &err,
        )?,
        None => Vec::new(),
    };
    let attr_table = attr_head.map(|(_, _, e)| ATTR_HEAD_LEN as u64 + e);
    check_layout(
        ambient,
        n_vertices,
        coords_offset,
        &blocks,
        (attr_table, &attrs, n_cells),
        len,
        &err,
    )?;
    Ok(SpbHeader {
        ambient_dim: ambient as usize,
        n_vertices,
        n_cells,
        coords_offset,
        blocks,
        file_len,
        version,
        attrs,
    })
}

/// An error of [`read_header`] at a byte offset.
type HeaderErr<'a> = &'a dyn Fn(usize, String) -> IoError;

/// The header's length, magic, version and endianness tag; the version.
fn check_preamble(bytes: &[u8], err: HeaderErr<'_>) -> Result<u32, IoError> {
    if bytes.len() < HEADER_LEN {
        if bytes.len() < 8 || bytes[..8] != MAGIC {
            return Err(err(
                0,
                format!("not a .spb file: {} bytes, no 'STARPLX' magic", bytes.len()),
            ));
        }
        return Err(err(
            bytes.len(),
            format!(
                "truncated .spb header: {} bytes, the header has {HEADER_LEN}",
                bytes.len()
            ),
        ));
    }
    if bytes[..8] != MAGIC {
        return Err(err(
            0,
            "not a .spb file: the magic 'STARPLX\\0' is missing".into(),
        ));
    }
    let version = u32_at(bytes, 8);
    if !(VERSION_NO_ATTRIBUTES..=VERSION).contains(&version) {
        return Err(err(
            8,
            format!("unsupported .spb version {version} (this starplex reads versions {VERSION_NO_ATTRIBUTES} to {VERSION})"),
        ));
    }
    let tag = u32_at(bytes, 12);
    if tag != ENDIAN_TAG {
        let msg = if tag == ENDIAN_TAG.swap_bytes() {
            "the file is big-endian; starplex writes and reads little-endian .spb only".to_string()
        } else {
            format!("bad endianness tag {tag:#010x} (expected {ENDIAN_TAG:#010x})")
        };
        return Err(err(12, msg));
    }
    Ok(version)
}

/// The block table (and in version 2 the attribute table) fits the file and the checksum over
/// the header and tables matches; in version 2, the attribute table's (byte offset, number of
/// columns, bytes of entries).
fn check_table(
    bytes: &[u8],
    n_blocks: u64,
    sum: u64,
    version: u32,
    err: HeaderErr<'_>,
) -> Result<Option<(usize, u64, u64)>, IoError> {
    let len = bytes.len() as u64;
    let table_end = (n_blocks as u128) * BLOCK_ENTRY_LEN as u128 + HEADER_LEN as u128;
    if table_end > len as u128 {
        return Err(err(
            20,
            format!(
                "{n_blocks} blocks need a {} byte table, more than the file's {len} bytes",
                table_end - HEADER_LEN as u128
            ),
        ));
    }
    let table = &bytes[HEADER_LEN..table_end as usize];
    let (attr_table, attr_head): (&[u8], _) = if version >= 2 {
        let at = table_end as usize;
        let (n, entries) = spb_attrs::read_head(bytes, at, err)?;
        let end = at + ATTR_HEAD_LEN + entries as usize;
        (&bytes[at..end], Some((at, n, entries)))
    } else {
        (&[], None)
    };
    let expect = fnv1a(&[&bytes[..56], table, attr_table]);
    if expect != sum {
        return Err(err(
            56,
            format!("header checksum mismatch (stored {sum:#018x}, computed {expect:#018x}): the header, block table or attribute table is corrupted"),
        ));
    }
    Ok(attr_head)
}

/// The ambient dimension, the 32-bit id limits and the coordinate array's extent.
fn check_counts(
    ambient: u64,
    n_vertices: u64,
    n_cells: u64,
    coords_offset: u64,
    len: u64,
    err: HeaderErr<'_>,
) -> Result<(), IoError> {
    if ambient == 0 || ambient > MAX_AMBIENT_DIM as u64 {
        return Err(err(
            16,
            format!("ambient dimension {ambient} is outside 1..={MAX_AMBIENT_DIM}"),
        ));
    }
    if n_vertices >= u32::MAX as u64 {
        return Err(err(
            24,
            format!("{n_vertices} vertices exceed the 32-bit id limit of starplex"),
        ));
    }
    if n_cells >= u32::MAX as u64 {
        return Err(err(
            32,
            format!("{n_cells} cells exceed the 32-bit id limit of starplex"),
        ));
    }
    let coords_bytes = n_vertices as u128 * ambient as u128 * 8;
    if coords_offset as u128 + coords_bytes > len as u128 {
        return Err(err(
            24,
            format!(
                "{n_vertices} vertices of {ambient} coordinates need {coords_bytes} bytes from offset {coords_offset}, past the end of the {len}-byte file"
            ),
        ));
    }
    Ok(())
}

/// The block table's (kind, cells, offset) entries, each within the file, holding `n_cells`
/// cells in all.
fn read_blocks(
    bytes: &[u8],
    n_blocks: u64,
    n_cells: u64,
    len: u64,
    err: HeaderErr<'_>,
) -> Result<Vec<(CellKind, u64, u64)>, IoError> {
    let mut blocks = Vec::with_capacity(n_blocks as usize);
    let mut total: u64 = 0;
    for i in 0..n_blocks as usize {
        let at = HEADER_LEN + i * BLOCK_ENTRY_LEN;
        let kind = kind_from_code(u32_at(bytes, at), u32_at(bytes, at + 4))
            .map_err(|m| err(at, format!("block {i}: {m}")))?;
        let n = u64_at(bytes, at + 8);
        let off = u64_at(bytes, at + 16);
        if u64_at(bytes, at + 24) != 0 {
            return Err(err(
                at + 24,
                format!("block {i}: reserved field is not zero"),
            ));
        }
        let need = n as u128 * kind.n_vertices() as u128 * 4;
        if off as u128 + need > len as u128 {
            return Err(err(
                at + 8,
                format!(
                    "block {i}: {n} cells of kind {} need {need} bytes from offset {off}, past the end of the {len}-byte file",
                    kind.type_name()
                ),
            ));
        }
        total = total.saturating_add(n);
        blocks.push((kind, n, off));
    }
    if total != n_cells {
        return Err(err(
            32,
            format!("the header says {n_cells} cells but the blocks hold {total}"),
        ));
    }
    Ok(blocks)
}

/// The attribute table's length (`None` in version 1), its entries and the cell count.
type AttrLayout<'a> = (Option<u64>, &'a [SpbAttr], u64);

/// The arrays sit exactly where the canonical layout puts them and end at the end of the file.
fn check_layout(
    ambient: u64,
    n_vertices: u64,
    coords_offset: u64,
    blocks: &[(CellKind, u64, u64)],
    (attr_table, attrs, n_cells): AttrLayout<'_>,
    len: u64,
    err: HeaderErr<'_>,
) -> Result<(), IoError> {
    let kinds: Vec<(CellKind, u64)> = blocks.iter().map(|&(k, n, _)| (k, n)).collect();
    // each product is at most the file length (checked by read_entries)
    let n_values: Vec<u64> = attrs
        .iter()
        .map(|a| {
            let items = match a.target {
                AttrTarget::Vertex => n_vertices,
                AttrTarget::Cell => n_cells,
            };
            items.saturating_mul(a.components)
        })
        .collect();
    let lay = layout(ambient, n_vertices, &kinds, attr_table, &n_values)
        .ok_or_else(|| err(24, "counts overflow the 64-bit layout".into()))?;
    let (c_off, offs, f_len) = (lay.coords, &lay.blocks, lay.file_len);
    if c_off != coords_offset {
        return Err(err(
            40,
            format!("coordinate array at offset {coords_offset}, expected {c_off}"),
        ));
    }
    for (i, (&(_, _, off), &want)) in blocks.iter().zip(offs).enumerate() {
        if off != want {
            return Err(err(
                HEADER_LEN + i * BLOCK_ENTRY_LEN + 16,
                format!("block {i}: vertex array at offset {off}, expected {want}"),
            ));
        }
    }
    for (i, (a, &want)) in attrs.iter().zip(&lay.attrs).enumerate() {
        if a.offset != want {
            return Err(err(
                HEADER_LEN + blocks.len() * BLOCK_ENTRY_LEN + ATTR_HEAD_LEN,
                format!(
                    "attribute {i} ('{}'): values at offset {}, expected {want}",
                    a.name, a.offset
                ),
            ));
        }
    }
    if f_len != len {
        return Err(err(
            48,
            format!("the arrays end at byte {f_len} but the file has {len} bytes"),
        ));
    }
    Ok(())
}

/// Maps `file` read-only. The only `unsafe` of the binary reader.
fn map_file(file: &std::fs::File) -> std::io::Result<memmap2::Mmap> {
    // SAFETY: memmap2 requires that the file is not modified (truncated or written) by anyone while
    // the map lives, which Rust cannot enforce; the map is read-only and private to this process.
    // Every slice taken from it is bounds-checked against the map length by `read_header` before
    // use, and values are plain data (any bit pattern is a valid f64/u32), so a concurrently
    // modified file can give wrong values but the reader itself never indexes out of bounds.
    unsafe { memmap2::MmapOptions::new().map(file) }
}

/// Opens and memory-maps a `.spb` file and checks its header, touching none of its arrays:
/// for readers of a part of the file (each rank of `starplex-mpi` reads its own byte ranges).
///
/// ```
/// use starplex::io::binary;
/// use starplex::complex::{ComplexBuilder, BuildOptions};
/// let mut b = ComplexBuilder::new(1).unwrap();
/// b.push_vertex(&[1.0]).unwrap();
/// let (k, _) = b.build(&BuildOptions::default()).unwrap();
/// let path = std::env::temp_dir().join(format!("starplex-doc-spb-open-{}.spb", std::process::id()));
/// let mut bytes = Vec::new();
/// binary::write(&mut bytes, &k).unwrap();
/// std::fs::write(&path, &bytes).unwrap();
/// let (map, h) = binary::open_mapped(&path).unwrap();
/// assert_eq!((h.n_vertices, map.len() as u64), (1, h.file_len));
/// std::fs::remove_file(&path).ok();
/// ```
///
/// # Errors
/// OS errors and a malformed header (see [`read_header`]).
pub fn open_mapped(path: &Path) -> Result<(Arc<memmap2::Mmap>, SpbHeader), IoError> {
    let file = std::fs::File::open(path).map_err(|e| IoError::new(path, e))?;
    let len = file.metadata().map_err(|e| IoError::new(path, e))?.len();
    if len < HEADER_LEN as u64 {
        let mut head = Vec::new();
        use std::io::Read;
        file.take(HEADER_LEN as u64)
            .read_to_end(&mut head)
            .map_err(|e| IoError::new(path, e))?;
        return Err(match read_header(&head, path) {
            Err(e) => e,
            Ok(_) => IoError::parse(path, Some(Location::Byte(len)), "truncated .spb header"),
        });
    }
    let map = map_file(&file).map_err(|e| IoError::new(path, e))?;
    let h = read_header(&map, path)?;
    Ok((Arc::new(map), h))
}

/// Reads a `.spb` file by memory-mapping it: coordinates and cell arrays stay in the map
/// ([`Buf::Mapped`]), nothing is copied.
///
/// `opts` is not used: a `.spb` holds a complex that was checked when it was written, so the
/// maximality/duplicate checks (and their drop options) are not run again; vertex indices and
/// coordinates are always checked.
///
/// ```
/// use starplex::io::{binary, ReadOptions};
/// use starplex::complex::{ComplexBuilder, BuildOptions};
/// let mut b = ComplexBuilder::new(3).unwrap();
/// b.push_vertex(&[1.0, 2.0, 3.0]).unwrap();
/// let (k, _) = b.build(&BuildOptions::default()).unwrap();
/// let path = std::env::temp_dir().join(format!("starplex-doc-spb-read-{}.spb", std::process::id()));
/// let mut bytes = Vec::new();
/// binary::write(&mut bytes, &k).unwrap();
/// std::fs::write(&path, &bytes).unwrap();
/// let r = binary::read(&path, &ReadOptions::default()).unwrap();
/// assert_eq!(r.complex.point(starplex::ids::VertexId(0)), &[1.0, 2.0, 3.0]);
/// std::fs::write(&path, &bytes[..70]).unwrap(); // truncated
/// assert!(binary::read(&path, &ReadOptions::default()).is_err());
/// std::fs::remove_file(&path).ok();
/// ```
///
/// # Errors
/// A big-endian host, OS errors, a malformed header (see [`read_header`]), and the checks of
/// [`IndexedComplex::from_parts`] (indices in range and not repeated, finite coordinates).
pub fn read(path: &Path, _opts: &ReadOptions) -> Result<ReadResult, IoError> {
    if cfg!(target_endian = "big") {
        return Err(IoError::parse(
            path,
            None,
            "reading .spb on a big-endian machine is not supported (the arrays are little-endian); convert to .spx on a little-endian machine",
        ));
    }
    let (map, h) = open_mapped(path)?;
    #[cfg(unix)]
    let _ = map.advise(memmap2::Advice::Sequential);
    let coords: Buf<f64> = Buf::Mapped {
        map: Arc::clone(&map),
        offset: h.coords_offset as usize,
        len: (h.n_vertices as usize) * h.ambient_dim,
    };
    let blocks: Vec<(CellKind, Buf<u32>)> = h
        .blocks
        .iter()
        .map(|&(kind, n, off)| {
            (
                kind,
                Buf::Mapped {
                    map: Arc::clone(&map),
                    offset: off as usize,
                    len: n as usize * kind.n_vertices(),
                },
            )
        })
        .collect();
    let mut complex = IndexedComplex::from_parts(h.ambient_dim, coords, blocks)
        .map_err(|e| IoError::new(path, e))?;
    if !h.attrs.is_empty() {
        let at = (HEADER_LEN + h.blocks.len() * BLOCK_ENTRY_LEN) as u64;
        let a = spb_attrs::load(&map, &h.attrs, h.n_vertices, h.n_cells, at, path)?;
        complex
            .set_attributes(a)
            .map_err(|e| IoError::new(path, e).at(Location::Byte(at)))?;
    }
    Ok(ReadResult {
        complex,
        format: Format::Binary,
        notes: Vec::new(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::complex::{BuildOptions, ComplexBuilder};

    fn sample() -> IndexedComplex {
        let mut b = ComplexBuilder::new(3).unwrap();
        for i in 0..12 {
            b.push_vertex(&[i as f64, (i * i) as f64 * 0.5, -(i as f64)])
                .unwrap();
        }
        b.push_cell(CellKind::Simplex(3), &[0, 1, 2, 3]).unwrap();
        b.push_cell(CellKind::Simplex(2), &[4, 5, 6]).unwrap();
        b.push_cell(CellKind::Prism, &[5, 6, 7, 8, 9, 10]).unwrap();
        b.build(&BuildOptions::default()).unwrap().0
    }

    #[test]
    fn layout_is_aligned_and_header_round_trips() {
        let k = sample();
        let mut out = Vec::new();
        write(&mut out, &k).unwrap();
        assert_eq!(out.len() % 8, 0);
        let h = read_header(&out, "m.spb".as_ref()).unwrap();
        assert_eq!(h.blocks.len(), 3);
        assert_eq!(h.coords_offset, 64 + 3 * 32);
        for &(_, _, off) in &h.blocks {
            assert_eq!(off % 8, 0);
        }
        assert_eq!(
            h.blocks[1],
            (CellKind::Simplex(2), 1, h.coords_offset + 12 * 3 * 8 + 16)
        );
    }

    #[test]
    fn kind_codes_round_trip() {
        for k in [
            CellKind::Simplex(0),
            CellKind::Simplex(40),
            CellKind::Simplex(64),
            CellKind::Quad,
            CellKind::Pyramid,
            CellKind::Prism,
            CellKind::Hex,
        ] {
            let (c, d) = kind_code(k);
            assert_eq!(kind_from_code(c, d).unwrap(), k);
        }
        assert!(kind_from_code(0, 65).is_err());
        assert!(kind_from_code(4, 2).is_err());
        assert!(kind_from_code(9, 3).is_err());
    }
}
