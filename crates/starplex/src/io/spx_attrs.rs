//! The attribute sections of `.spx` version 2 (see `docs/FORMATS.md`): after the cells, zero or
//! more sections, each a header line
//!
//! ```text
//! attribute <vertex|cell> <int|float> <components> <name>
//! ```
//!
//! then one line per vertex (or per top cell, in the file's cell order) holding `components`
//! values. `<name>` is one token, percent-encoded: every byte outside `!`..=`~`, and `%` and `#`,
//! is written `%XX` (two upper-case hex digits); the empty name is written `%`. Integers are
//! decimal `i64`; floats are Rust's shortest round-trip form (`0.1`, `-0.0`, `1e-300`, `NaN`,
//! `inf`, `-inf`), so every value comes back bit for bit (NaN payloads excepted).
use std::io::Write;

use super::text::LineReader;
use super::IoError;
use crate::attr::{AttrTarget, AttrValues, Attribute, Attributes};

/// The first word of an attribute section's header line.
pub(super) const KEYWORD: &[u8] = b"attribute";

/// `name` percent-encoded as one token.
pub(super) fn encode_name(name: &str) -> String {
    if name.is_empty() {
        return "%".into();
    }
    let mut s = String::with_capacity(name.len());
    for &b in name.as_bytes() {
        if (b'!'..=b'~').contains(&b) && b != b'%' && b != b'#' {
            s.push(b as char);
        } else {
            s.push_str(&format!("%{b:02X}"));
        }
    }
    s
}

/// The name a token encodes, or why it is not one.
pub(super) fn decode_name(tok: &[u8]) -> Result<String, String> {
    if tok == b"%" {
        return Ok(String::new());
    }
    let mut out = Vec::with_capacity(tok.len());
    let mut i = 0;
    while i < tok.len() {
        if tok[i] == b'%' {
            let hex = tok
                .get(i + 1..i + 3)
                .and_then(|h| std::str::from_utf8(h).ok())
                .and_then(|h| u8::from_str_radix(h, 16).ok())
                .ok_or("a '%' in the attribute name is not followed by two hex digits")?;
            out.push(hex);
            i += 3;
        } else {
            out.push(tok[i]);
            i += 1;
        }
    }
    String::from_utf8(out).map_err(|_| "the attribute name is not UTF-8".to_string())
}

/// Writes every column of `a` as a section.
pub(super) fn write(w: &mut dyn Write, a: &Attributes) -> std::io::Result<()> {
    let mut line = String::with_capacity(256);
    for (target, cols) in [(AttrTarget::Vertex, &a.vertex), (AttrTarget::Cell, &a.cell)] {
        for c in cols {
            writeln!(
                w,
                "attribute {target} {} {} {}",
                c.values.type_name(),
                c.components,
                encode_name(&c.name)
            )?;
            let k = c.components.max(1);
            for i in 0..c.n_items() {
                use std::fmt::Write as _;
                line.clear();
                for j in i * k..(i + 1) * k {
                    if j > i * k {
                        line.push(' ');
                    }
                    let _ = match &c.values {
                        AttrValues::Int(v) => write!(line, "{}", v[j]),
                        AttrValues::Float(v) => write!(line, "{:?}", v[j]),
                    };
                }
                line.push('\n');
                w.write_all(line.as_bytes())?;
            }
        }
    }
    Ok(())
}

/// Reads the sections that follow the cells, up to the end of the file, for a complex of `nv`
/// vertices and `nc` cells. Each column is checked against its count here (one line per item,
/// `components` values per line); names unique per target are checked by the caller
/// ([`Attributes::check`]).
pub(super) fn read<R: std::io::BufRead>(
    lr: &mut LineReader<'_, R>,
    nv: usize,
    nc: usize,
) -> Result<Attributes, IoError> {
    let mut out = Attributes::default();
    loop {
        let (target, is_int, comps, name) = {
            let Some(l) = lr.next_content_line()? else {
                break;
            };
            let mut t = l.tokens();
            let kw = t.word("'attribute'")?;
            if kw != KEYWORD {
                return Err(l.err(format!(
                    "expected an attribute section ('attribute <vertex|cell> <int|float> <components> <name>') or the end of the file, found '{}'",
                    String::from_utf8_lossy(&l.bytes[..l.bytes.len().min(60)])
                )));
            }
            let target = match t.word("the target 'vertex' or 'cell'")? {
                b"vertex" => AttrTarget::Vertex,
                b"cell" => AttrTarget::Cell,
                w => {
                    return Err(l.err(format!(
                        "attribute target '{}' is neither 'vertex' nor 'cell'",
                        String::from_utf8_lossy(w)
                    )))
                }
            };
            let is_int = match t.word("the value type 'int' or 'float'")? {
                b"int" => true,
                b"float" => false,
                w => {
                    return Err(l.err(format!(
                        "attribute value type '{}' is neither 'int' nor 'float'",
                        String::from_utf8_lossy(w)
                    )))
                }
            };
            let comps = t.u64("the number of components")?;
            if comps == 0 || comps > u32::MAX as u64 {
                return Err(l.err(format!(
                    "an attribute has {comps} components; .spx takes 1 to 2^32-1"
                )));
            }
            let name = decode_name(t.word("the attribute name")?).map_err(|m| l.err(m))?;
            t.end()?;
            if out.get(target, &name).is_some() {
                return Err(l.err(format!("two {target} attributes are named '{name}'")));
            }
            (target, is_int, comps as usize, name)
        };
        let n = match target {
            AttrTarget::Vertex => nv,
            AttrTarget::Cell => nc,
        };
        // bounded: n < 2^32 lines must follow, each read before its values are stored
        let cap = n.saturating_mul(comps).min(1 << 20);
        let mut ints: Vec<i64> = Vec::with_capacity(if is_int { cap } else { 0 });
        let mut floats: Vec<f64> = Vec::with_capacity(if is_int { 0 } else { cap });
        for i in 0..n {
            let l = lr.expect_line(format_args!("{target} {i} of attribute '{name}'"))?;
            let mut t = l.tokens();
            for j in 0..comps {
                let tok = t.word(format_args!(
                    "component {j} of {target} {i} of attribute '{name}'"
                ))?;
                let s = std::str::from_utf8(tok).unwrap_or("");
                if is_int {
                    let v = s.parse::<i64>().map_err(|_| {
                        t.err(format!(
                            "attribute '{name}': expected an integer, found '{}'",
                            String::from_utf8_lossy(&tok[..tok.len().min(40)])
                        ))
                    })?;
                    ints.push(v);
                } else {
                    let v = s.parse::<f64>().map_err(|_| {
                        t.err(format!(
                            "attribute '{name}': expected a number, found '{}'",
                            String::from_utf8_lossy(&tok[..tok.len().min(40)])
                        ))
                    })?;
                    floats.push(v);
                }
            }
            t.end()?;
        }
        let col = if is_int {
            Attribute::int(name, comps, ints)
        } else {
            Attribute::float(name, comps, floats)
        };
        match target {
            AttrTarget::Vertex => out.vertex.push(col),
            AttrTarget::Cell => out.cell.push(col),
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip() {
        for n in ["", "%", "gmsh:physical", "a b", "#x", "é\n\t", "%41", "-"] {
            let e = encode_name(n);
            assert!(!e.is_empty() && !e.contains([' ', '#', '\n']), "{e}");
            assert_eq!(decode_name(e.as_bytes()).unwrap(), n);
        }
        assert!(decode_name(b"%4").is_err());
        assert!(decode_name(b"%zz").is_err());
        assert!(decode_name(b"%FF").is_err()); // not UTF-8
    }
}
