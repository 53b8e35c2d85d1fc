//! The attribute section of a saved Stellar tree (version 2 of the file, written only when the
//! tree carries attributes): after the cell permutation, a `u64` column count, then per column
//! four `u64` words (target: 0 vertex, 1 cell; type: 0 int = `i64`, 1 float = `f64`;
//! components; name length), the UTF-8 name zero-padded to 8 bytes, and the values in tree
//! order (items × components, 8 bytes each). Every length is checked against the file before
//! anything is allocated (the loader's `Reader`).
use std::io::Write;

use super::StellarError;
use crate::attr::{AttrTarget, AttrValues, Attribute, Attributes};

/// Writes the section for `a` (tree order).
pub(super) fn write(w: &mut dyn Write, a: &Attributes) -> std::io::Result<()> {
    let n = (a.vertex.len() + a.cell.len()) as u64;
    w.write_all(&n.to_le_bytes())?;
    for (target, cols) in [(0u64, &a.vertex), (1u64, &a.cell)] {
        for c in cols {
            let ty = match c.values {
                AttrValues::Int(_) => 0u64,
                AttrValues::Float(_) => 1,
            };
            for x in [target, ty, c.components as u64, c.name.len() as u64] {
                w.write_all(&x.to_le_bytes())?;
            }
            w.write_all(c.name.as_bytes())?;
            w.write_all(&[0u8; 8][..(8 - c.name.len() % 8) % 8])?;
            match &c.values {
                AttrValues::Int(v) => w.write_all(bytemuck::cast_slice(v))?,
                AttrValues::Float(v) => w.write_all(bytemuck::cast_slice(v))?,
            }
        }
    }
    Ok(())
}

/// Reads the section through `take(n)` (the next `n` bytes of the file, checked against its
/// length) for a tree of `nv` vertices and `nc` cells.
pub(super) fn read<'a>(
    take: &mut dyn FnMut(usize) -> Result<&'a [u8], StellarError>,
    nv: usize,
    nc: usize,
    err: &dyn Fn(String) -> StellarError,
) -> Result<Attributes, StellarError> {
    let word = |b: &[u8]| {
        let mut x = [0u8; 8];
        x.copy_from_slice(&b[..8]);
        u64::from_le_bytes(x)
    };
    let n = word(take(8)?);
    let mut a = Attributes::default();
    for i in 0..n {
        let h = take(32)?;
        let (target, ty, comps, name_len) =
            (word(h), word(&h[8..]), word(&h[16..]), word(&h[24..]));
        let (target, items) = match target {
            0 => (AttrTarget::Vertex, nv),
            1 => (AttrTarget::Cell, nc),
            x => return Err(err(format!("attribute {i}: bad target code {x}"))),
        };
        if ty > 1 || comps == 0 {
            return Err(err(format!(
                "attribute {i}: bad type code {ty} or 0 components"
            )));
        }
        let padded = usize::try_from(name_len)
            .ok()
            .and_then(|l| l.checked_add(7))
            .map(|l| l / 8 * 8)
            .ok_or_else(|| err(format!("attribute {i}: name length {name_len} overflows")))?;
        let raw = take(padded)?;
        let name = std::str::from_utf8(&raw[..name_len as usize])
            .map_err(|_| err(format!("attribute {i}: the name is not UTF-8")))?
            .to_string();
        let len = usize::try_from(comps)
            .ok()
            .and_then(|c| c.checked_mul(items))
            .and_then(|v| v.checked_mul(8))
            .ok_or_else(|| err(format!("attribute {i} ('{name}'): size overflows")))?;
        let bytes = take(len)?; // checked against the file before the copy below
        let words = bytes.chunks_exact(8).map(|b| {
            let mut x = [0u8; 8];
            x.copy_from_slice(b);
            x
        });
        let values = if ty == 0 {
            AttrValues::Int(words.map(i64::from_le_bytes).collect())
        } else {
            AttrValues::Float(words.map(f64::from_le_bytes).collect())
        };
        let col = Attribute {
            name,
            components: comps as usize,
            values,
        };
        match target {
            AttrTarget::Vertex => a.vertex.push(col),
            AttrTarget::Cell => a.cell.push(col),
        }
    }
    a.check(nv, nc).map_err(|e| err(e.to_string()))?;
    Ok(a)
}
