//! Bulk reading of the binary arrays in binary gmsh and legacy VTK files: fixed-size records
//! read in chunks of a few MB, decoded with per-element byte swaps the compiler vectorises.
//! A declared count never sizes a buffer that is written before the values arrive: an output
//! array may be reserved for it ([`reserve_declared`]: at most 256 MiB, virtual memory touched
//! only as values are read; beyond that, or refused, the array grows as they come).
use std::io::BufRead;

use super::words::Words;
use super::IoError;

/// Byte order of a binary section.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Endian {
    Little,
    Big,
}

/// Reserves room in `v` for `n` more values declared by a file (whose data may be missing):
/// at most 256 MiB, and nothing if the allocator refuses. Larger arrays grow as their values
/// arrive (a reallocation of a large block remaps its pages rather than copying them).
pub(crate) fn reserve_declared<T>(v: &mut Vec<T>, n: u64) {
    const MAX_BYTES: u64 = 256 << 20;
    let cap = MAX_BYTES / std::mem::size_of::<T>().max(1) as u64;
    let _ = v.try_reserve_exact(n.min(cap) as usize);
}

/// Bytes per chunk (rounded down to whole records).
pub(crate) const CHUNK: usize = 8 << 20;

/// Reads `n` records of `rec` bytes, calling `f(chunk, index_of_first_record)` on whole records.
pub(crate) fn read_records<R: BufRead>(
    w: &mut Words<'_, R>,
    n: u64,
    rec: usize,
    what: &str,
    f: impl FnMut(&mut Words<'_, R>, &[u8], u64) -> Result<(), IoError>,
) -> Result<(), IoError> {
    read_records_in(w, n, rec, CHUNK, what, f)
}

/// [`read_records`] in chunks of about `chunk` bytes (unit tests use tiny ones to cross chunk
/// boundaries on small inputs).
pub(crate) fn read_records_in<R: BufRead>(
    w: &mut Words<'_, R>,
    n: u64,
    rec: usize,
    chunk: usize,
    what: &str,
    mut f: impl FnMut(&mut Words<'_, R>, &[u8], u64) -> Result<(), IoError>,
) -> Result<(), IoError> {
    if n == 0 || rec == 0 {
        return Ok(());
    }
    let per = (chunk / rec).max(1) as u64;
    let first_len = n.min(per) as usize * rec;
    let mut buf = vec![0u8; first_len];
    let mut done = 0u64;
    while done < n {
        let k = (n - done).min(per) as usize;
        let b = &mut buf[..k * rec];
        w.read_raw(b, what)?;
        f(w, b, done)?;
        done += k as u64;
    }
    Ok(())
}

macro_rules! getter {
    ($name:ident, $t:ty, $n:expr) => {
        #[inline(always)]
        pub(crate) fn $name(b: &[u8], e: Endian) -> $t {
            let a: [u8; $n] = b[..$n].try_into().expect("record size checked");
            match e {
                Endian::Little => <$t>::from_le_bytes(a),
                Endian::Big => <$t>::from_be_bytes(a),
            }
        }
    };
}
getter!(get_i32, i32, 4);
getter!(get_u32, u32, 4);
getter!(get_i64, i64, 8);
getter!(get_u64, u64, 8);

/// Appends the `f64`s of `b` (whole 8-byte values) to `out`.
pub(crate) fn push_f64s(b: &[u8], e: Endian, out: &mut Vec<f64>) {
    match e {
        Endian::Little => out.extend(
            b.chunks_exact(8)
                .map(|c| f64::from_le_bytes(c.try_into().expect("8 bytes"))),
        ),
        Endian::Big => out.extend(
            b.chunks_exact(8)
                .map(|c| f64::from_be_bytes(c.try_into().expect("8 bytes"))),
        ),
    }
}

/// Appends the `f32`s of `b`, widened, to `out`.
pub(crate) fn push_f32s(b: &[u8], e: Endian, out: &mut Vec<f64>) {
    match e {
        Endian::Little => out.extend(
            b.chunks_exact(4)
                .map(|c| f32::from_le_bytes(c.try_into().expect("4 bytes")) as f64),
        ),
        Endian::Big => out.extend(
            b.chunks_exact(4)
                .map(|c| f32::from_be_bytes(c.try_into().expect("4 bytes")) as f64),
        ),
    }
}

/// An unsigned integer of `width` (4 or 8) bytes.
#[inline(always)]
pub(crate) fn get_uint(b: &[u8], width: usize, e: Endian) -> u64 {
    if width == 4 {
        get_u32(b, e) as u64
    } else {
        get_u64(b, e)
    }
}
