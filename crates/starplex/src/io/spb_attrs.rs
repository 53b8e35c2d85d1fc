//! The attribute table of `.spb` version 2 (layout in [`super::binary`]'s module documentation
//! and `docs/FORMATS.md`): a 16-byte head after the block table, one entry per column (target,
//! type, name, components, offset of its values), the values themselves after the cell arrays.
//! Every field is checked against the file's length before use; the table is covered by the
//! header checksum.
use std::io::Write;

use super::binary::{SpbAttr, ATTR_ENTRY_LEN, ATTR_HEAD_LEN};
use super::{IoError, Location};
use crate::attr::{AttrTarget, AttrValues, Attribute, Attributes};

/// An error at a byte offset (as `binary`'s header errors).
pub(super) type ByteErr<'a> = &'a dyn Fn(usize, String) -> IoError;

#[inline]
pub(super) fn align8(x: u64) -> u64 {
    x.div_ceil(8) * 8
}

/// The columns in file order: vertex columns, then cell columns.
pub(super) fn columns(a: &Attributes) -> Vec<(AttrTarget, &Attribute)> {
    a.vertex
        .iter()
        .map(|c| (AttrTarget::Vertex, c))
        .chain(a.cell.iter().map(|c| (AttrTarget::Cell, c)))
        .collect()
}

/// Bytes of the entries (without the 16-byte head) for these columns.
pub(super) fn entries_len(cols: &[(AttrTarget, &Attribute)]) -> Option<u64> {
    let mut n: u64 = 0;
    for (_, c) in cols {
        n = n.checked_add(ATTR_ENTRY_LEN as u64 + align8(c.name.len() as u64))?;
    }
    Some(n)
}

/// The head and entries, given the values' offsets.
pub(super) fn encode(cols: &[(AttrTarget, &Attribute)], offsets: &[u64], entries: u64) -> Vec<u8> {
    let mut t = Vec::with_capacity(ATTR_HEAD_LEN + entries as usize);
    t.extend_from_slice(&(cols.len() as u32).to_le_bytes());
    t.extend_from_slice(&0u32.to_le_bytes());
    t.extend_from_slice(&entries.to_le_bytes());
    for (&(target, c), &off) in cols.iter().zip(offsets) {
        t.push(match target {
            AttrTarget::Vertex => 0,
            AttrTarget::Cell => 1,
        });
        t.push(match c.values {
            AttrValues::Int(_) => 0,
            AttrValues::Float(_) => 1,
        });
        t.extend_from_slice(&0u16.to_le_bytes());
        t.extend_from_slice(&(c.name.len() as u32).to_le_bytes());
        t.extend_from_slice(&(c.components as u64).to_le_bytes());
        t.extend_from_slice(&off.to_le_bytes());
        t.extend_from_slice(c.name.as_bytes());
        let pad = align8(c.name.len() as u64) as usize - c.name.len();
        t.extend_from_slice(&[0u8; 8][..pad]);
    }
    t
}

/// Writes the values of every column, each at its offset (the caller pads to it).
pub(super) fn write_values(w: &mut dyn Write, c: &Attribute) -> std::io::Result<()> {
    let mut buf: Vec<u8> = Vec::with_capacity(c.values.len().min(1 << 16) * 8);
    let flush = |buf: &mut Vec<u8>, w: &mut dyn Write| -> std::io::Result<()> {
        w.write_all(buf)?;
        buf.clear();
        Ok(())
    };
    match &c.values {
        AttrValues::Int(v) => {
            for x in v {
                buf.extend_from_slice(&x.to_le_bytes());
                if buf.len() >= 1 << 19 {
                    flush(&mut buf, w)?;
                }
            }
        }
        AttrValues::Float(v) => {
            for x in v {
                buf.extend_from_slice(&x.to_le_bytes());
                if buf.len() >= 1 << 19 {
                    flush(&mut buf, w)?;
                }
            }
        }
    }
    flush(&mut buf, w)
}

/// The extent of the attribute head and entries starting at `at`: `(n_attrs, entries_len)`,
/// each checked against the file length `len`.
pub(super) fn read_head(bytes: &[u8], at: usize, err: ByteErr<'_>) -> Result<(u64, u64), IoError> {
    let len = bytes.len() as u64;
    if at as u64 + ATTR_HEAD_LEN as u64 > len {
        return Err(err(
            at,
            format!("truncated .spb: the attribute table head at byte {at} passes the end of the {len}-byte file"),
        ));
    }
    let n = u32_at(bytes, at) as u64;
    if u32_at(bytes, at + 4) != 0 {
        return Err(err(
            at + 4,
            "attribute table: reserved field is not zero".into(),
        ));
    }
    let entries = u64_at(bytes, at + 8);
    if !entries.is_multiple_of(8) {
        return Err(err(
            at + 8,
            format!("attribute table: its length {entries} is not a multiple of 8"),
        ));
    }
    let end = at as u128 + ATTR_HEAD_LEN as u128 + entries as u128;
    if end > len as u128 {
        return Err(err(
            at + 8,
            format!("attribute table of {entries} bytes from byte {} passes the end of the {len}-byte file", at + ATTR_HEAD_LEN),
        ));
    }
    if n as u128 * ATTR_ENTRY_LEN as u128 > entries as u128 {
        return Err(err(
            at,
            format!(
                "{n} attributes need at least {} table bytes, the table has {entries}",
                n as u128 * ATTR_ENTRY_LEN as u128
            ),
        ));
    }
    Ok((n, entries))
}

/// The `n` entries of the table starting at `at` (after the head), which is `entries` bytes
/// long, for `nv` vertices and `nc` cells; each values array within the file.
pub(super) fn read_entries(
    bytes: &[u8],
    at: usize,
    n: u64,
    entries: u64,
    nv: u64,
    nc: u64,
    err: ByteErr<'_>,
) -> Result<Vec<SpbAttr>, IoError> {
    let len = bytes.len() as u64;
    let end = at + entries as usize; // checked by read_head
                                     // bounded: n * ATTR_ENTRY_LEN <= entries <= file length (read_head)
    let mut out = Vec::with_capacity(n as usize);
    let mut p = at;
    for i in 0..n as usize {
        if p + ATTR_ENTRY_LEN > end {
            return Err(err(
                p,
                format!("attribute {i}: its entry passes the end of the attribute table"),
            ));
        }
        let target = match bytes[p] {
            0 => AttrTarget::Vertex,
            1 => AttrTarget::Cell,
            x => {
                return Err(err(
                    p,
                    format!("attribute {i}: unknown target code {x} (0 vertex, 1 cell)"),
                ))
            }
        };
        let int = match bytes[p + 1] {
            0 => true,
            1 => false,
            x => {
                return Err(err(
                    p + 1,
                    format!("attribute {i}: unknown value type code {x} (0 int, 1 float)"),
                ))
            }
        };
        if bytes[p + 2] != 0 || bytes[p + 3] != 0 {
            return Err(err(
                p + 2,
                format!("attribute {i}: reserved field is not zero"),
            ));
        }
        let name_len = u32_at(bytes, p + 4) as u64;
        let components = u64_at(bytes, p + 8);
        let offset = u64_at(bytes, p + 16);
        let name_end = (p + ATTR_ENTRY_LEN) as u64 + name_len;
        if align8(name_end) > end as u64 {
            return Err(err(
                p + 4,
                format!("attribute {i}: a name of {name_len} bytes passes the end of the attribute table"),
            ));
        }
        let name_bytes = &bytes[p + ATTR_ENTRY_LEN..name_end as usize];
        let name = std::str::from_utf8(name_bytes)
            .map_err(|_| {
                err(
                    p + ATTR_ENTRY_LEN,
                    format!("attribute {i}: the name is not UTF-8"),
                )
            })?
            .to_string();
        if bytes[name_end as usize..align8(name_end) as usize]
            .iter()
            .any(|&b| b != 0)
        {
            return Err(err(
                name_end as usize,
                format!("attribute {i} ('{name}'): the name's padding is not zero"),
            ));
        }
        if components == 0 {
            return Err(err(
                p + 8,
                format!("attribute {i} ('{name}') has 0 components"),
            ));
        }
        let n_items = match target {
            AttrTarget::Vertex => nv,
            AttrTarget::Cell => nc,
        };
        let need = n_items as u128 * components as u128 * 8;
        if offset as u128 + need > len as u128 {
            return Err(err(
                p + 8,
                format!(
                    "attribute {i} ('{name}'): {n_items} items of {components} components need {need} bytes from offset {offset}, past the end of the {len}-byte file"
                ),
            ));
        }
        out.push(SpbAttr {
            name,
            target,
            int,
            components,
            offset,
        });
        p = align8(name_end) as usize;
    }
    if p != end {
        return Err(err(
            p,
            format!("attribute table: {} bytes after its {n} entries", end - p),
        ));
    }
    Ok(out)
}

/// The columns described by `table`, copied out of `bytes` (offsets checked by
/// [`read_entries`]); `table_at` (the table head's byte offset) locates errors.
pub(super) fn load(
    bytes: &[u8],
    table: &[SpbAttr],
    nv: u64,
    nc: u64,
    table_at: u64,
    path: &std::path::Path,
) -> Result<Attributes, IoError> {
    let mut a = Attributes::default();
    for e in table {
        let n = match e.target {
            AttrTarget::Vertex => nv,
            AttrTarget::Cell => nc,
        } as usize
            * e.components as usize;
        let raw = &bytes[e.offset as usize..e.offset as usize + n * 8];
        e.push_column(&mut a, raw.chunks_exact(8));
    }
    a.check(nv as usize, nc as usize).map_err(|x| {
        IoError::new(path, crate::complex::ComplexError::from(x)).at(Location::Byte(table_at))
    })?;
    Ok(a)
}

#[inline]
fn u32_at(b: &[u8], at: usize) -> u32 {
    let mut x = [0u8; 4];
    x.copy_from_slice(&b[at..at + 4]);
    u32::from_le_bytes(x)
}

#[inline]
fn u64_at(b: &[u8], at: usize) -> u64 {
    let mut x = [0u8; 8];
    x.copy_from_slice(&b[at..at + 8]);
    u64::from_le_bytes(x)
}
