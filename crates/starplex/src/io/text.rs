//! Streaming line reader and tokenizer shared by the text readers.
//!
//! Lines are read into one reused buffer (never the whole file); every line carries its number
//! and the file path, so any token error says where it is.
//!
//! ```
//! use starplex::io::text::LineReader;
//! let data = b"# comment\n\n3 4.5\r\nx\n";
//! let mut r = LineReader::new(&data[..], "mem.txt".as_ref(), Some(b'#'));
//! let line = r.next_content_line().unwrap().unwrap();
//! assert_eq!(line.no, 3);
//! let mut t = line.tokens();
//! assert_eq!(t.u64("count").unwrap(), 3);
//! assert_eq!(t.f64("x").unwrap(), 4.5);
//! assert!(t.end().is_ok());
//! let line = r.next_content_line().unwrap().unwrap();
//! let e = line.tokens().u64("count").unwrap_err();
//! assert_eq!(e.to_string(), "mem.txt:4: expected count (an unsigned integer), found 'x'");
//! ```
use std::io::BufRead;
use std::path::Path;

use super::{IoError, Location};

/// A reader of lines with numbers, skipping blank lines and comments on request.
pub struct LineReader<'p, R: BufRead> {
    r: R,
    buf: Vec<u8>,
    no: u64,
    path: &'p Path,
    comment: Option<u8>,
    offset: u64,
}

/// One line of a file with its context.
#[derive(Clone, Copy)]
pub struct Line<'a> {
    /// The line's bytes without the line terminator (and without a comment when stripped).
    pub bytes: &'a [u8],
    /// 1-based line number.
    pub no: u64,
    /// The file.
    pub path: &'a Path,
}

/// Whitespace-separated tokens of a line.
pub struct Tokens<'a> {
    s: &'a [u8],
    pos: usize,
    no: u64,
    path: &'a Path,
}

#[inline]
fn is_space(b: u8) -> bool {
    matches!(b, b' ' | b'\t' | b'\r' | b'\x0b' | b'\x0c')
}

impl<'p, R: BufRead> LineReader<'p, R> {
    /// Wraps `r`; `comment` is the byte that starts a comment (`#` for most formats).
    pub fn new(r: R, path: &'p Path, comment: Option<u8>) -> Self {
        LineReader {
            r,
            buf: Vec::with_capacity(256),
            no: 0,
            path,
            comment,
            offset: 0,
        }
    }

    /// The number of the last line read (0 before the first).
    pub fn line_no(&self) -> u64 {
        self.no
    }

    /// Bytes consumed so far.
    pub fn offset(&self) -> u64 {
        self.offset
    }

    /// The file path.
    pub fn path(&self) -> &'p Path {
        self.path
    }

    /// The next raw line (terminator and trailing `\r` removed), or `None` at the end.
    ///
    /// # Errors
    /// OS errors, or a line longer than 64 MiB (binary garbage).
    pub fn next_line(&mut self) -> Result<Option<Line<'_>>, IoError> {
        self.buf.clear();
        let n = read_line_limited(&mut self.r, &mut self.buf, 64 << 20)
            .map_err(|e| IoError::new(self.path, e).at(Location::Line(self.no + 1)))?;
        if n == 0 {
            return Ok(None);
        }
        self.offset += n as u64;
        self.no += 1;
        let mut end = self.buf.len();
        if end > 0 && self.buf[end - 1] == b'\n' {
            end -= 1;
        }
        if end > 0 && self.buf[end - 1] == b'\r' {
            end -= 1;
        }
        Ok(Some(Line {
            bytes: &self.buf[..end],
            no: self.no,
            path: self.path,
        }))
    }

    /// The next line with content: comments stripped, blank lines skipped.
    ///
    /// # Errors
    /// As [`LineReader::next_line`].
    pub fn next_content_line(&mut self) -> Result<Option<Line<'_>>, IoError> {
        loop {
            self.buf.clear();
            let n = read_line_limited(&mut self.r, &mut self.buf, 64 << 20)
                .map_err(|e| IoError::new(self.path, e).at(Location::Line(self.no + 1)))?;
            if n == 0 {
                return Ok(None);
            }
            self.offset += n as u64;
            self.no += 1;
            let mut end = self.buf.len();
            if let Some(c) = self.comment {
                if let Some(p) = memchr::memchr(c, &self.buf[..end]) {
                    end = p;
                }
            }
            while end > 0 && (self.buf[end - 1] == b'\n' || is_space(self.buf[end - 1])) {
                end -= 1;
            }
            let start = self.buf[..end]
                .iter()
                .position(|&b| !is_space(b))
                .unwrap_or(end);
            if start < end {
                // Borrow split: return a view of the buffer.
                let no = self.no;
                return Ok(Some(Line {
                    bytes: &self.buf[start..end],
                    no,
                    path: self.path,
                }));
            }
        }
    }

    /// The next content line, or an error saying the file ended while `what` was expected.
    ///
    /// # Errors
    /// End of file, OS errors.
    pub fn expect_line(&mut self, what: impl std::fmt::Display) -> Result<Line<'_>, IoError> {
        let no = self.no;
        let path = self.path;
        match self.next_content_line()? {
            Some(l) => Ok(l),
            None => Err(IoError::parse(
                path,
                Some(Location::Line(no + 1)),
                format!("unexpected end of file: expected {what} (the file is truncated or a count is wrong)"),
            )),
        }
    }

    /// An error at the current line.
    pub fn err(&self, msg: impl Into<String>) -> IoError {
        IoError::parse(self.path, Some(Location::Line(self.no.max(1))), msg)
    }
}

/// Reads up to and including `\n`, refusing lines longer than `limit` bytes.
fn read_line_limited<R: BufRead>(
    r: &mut R,
    buf: &mut Vec<u8>,
    limit: usize,
) -> std::io::Result<usize> {
    let mut total = 0;
    loop {
        let (done, used) = {
            let available = match r.fill_buf() {
                Ok(b) => b,
                Err(e) if e.kind() == std::io::ErrorKind::Interrupted => continue,
                Err(e) => return Err(e),
            };
            match memchr::memchr(b'\n', available) {
                Some(i) => {
                    buf.extend_from_slice(&available[..=i]);
                    (true, i + 1)
                }
                None => {
                    buf.extend_from_slice(available);
                    (available.is_empty(), available.len())
                }
            }
        };
        r.consume(used);
        total += used;
        if done {
            return Ok(total);
        }
        if buf.len() > limit {
            return Err(std::io::Error::new(
                std::io::ErrorKind::InvalidData,
                format!("line longer than {limit} bytes (is this a binary file?)"),
            ));
        }
    }
}

impl<'a> Line<'a> {
    /// The line's tokens.
    pub fn tokens(&self) -> Tokens<'a> {
        Tokens {
            s: self.bytes,
            pos: 0,
            no: self.no,
            path: self.path,
        }
    }

    /// An error at this line.
    pub fn err(&self, msg: impl Into<String>) -> IoError {
        IoError::parse(self.path, Some(Location::Line(self.no)), msg)
    }

    /// The line as text (lossy), for messages.
    pub fn text(&self) -> String {
        String::from_utf8_lossy(self.bytes).into_owned()
    }
}

impl<'a> Tokens<'a> {
    /// The next token, if any.
    #[inline]
    pub fn next_token(&mut self) -> Option<&'a [u8]> {
        let s = self.s;
        let mut i = self.pos;
        while i < s.len() && is_space(s[i]) {
            i += 1;
        }
        if i == s.len() {
            self.pos = i;
            return None;
        }
        let start = i;
        while i < s.len() && !is_space(s[i]) {
            i += 1;
        }
        self.pos = i;
        Some(&s[start..i])
    }

    /// An error at this line.
    pub fn err(&self, msg: impl Into<String>) -> IoError {
        IoError::parse(self.path, Some(Location::Line(self.no)), msg)
    }

    fn missing(&self, what: &dyn std::fmt::Display) -> IoError {
        self.err(format!("expected {what}, found the end of the line"))
    }

    fn bad(&self, what: &dyn std::fmt::Display, kind: &str, tok: &[u8]) -> IoError {
        let shown: String = String::from_utf8_lossy(&tok[..tok.len().min(40)]).into_owned();
        self.err(format!("expected {what} ({kind}), found '{shown}'"))
    }

    /// The next token as a word.
    ///
    /// # Errors
    /// A missing token.
    pub fn word(&mut self, what: impl std::fmt::Display) -> Result<&'a [u8], IoError> {
        self.next_token().ok_or_else(|| self.missing(&what))
    }

    /// The next token as an unsigned integer.
    ///
    /// # Errors
    /// A missing or malformed token.
    #[inline]
    pub fn u64(&mut self, what: impl std::fmt::Display) -> Result<u64, IoError> {
        let tok = self.next_token().ok_or_else(|| self.missing(&what))?;
        parse_u64(tok).ok_or_else(|| self.bad(&what, "an unsigned integer", tok))
    }

    /// The next token as a signed integer.
    ///
    /// # Errors
    /// A missing or malformed token.
    pub fn i64(&mut self, what: impl std::fmt::Display) -> Result<i64, IoError> {
        let tok = self.next_token().ok_or_else(|| self.missing(&what))?;
        let (neg, digits) = match tok.first() {
            Some(b'-') => (true, &tok[1..]),
            Some(b'+') => (false, &tok[1..]),
            _ => (false, tok),
        };
        let v = parse_u64(digits)
            .filter(|&v| v <= i64::MAX as u64)
            .ok_or_else(|| self.bad(&what, "an integer", tok))? as i64;
        Ok(if neg { -v } else { v })
    }

    /// The next token as a vertex index below `n` (after subtracting `base`), as `u32`.
    ///
    /// # Errors
    /// A missing or malformed token, or an index out of range.
    #[inline]
    pub fn index(
        &mut self,
        what: impl std::fmt::Display,
        base: u64,
        n: usize,
    ) -> Result<u32, IoError> {
        let tok = self.next_token().ok_or_else(|| self.missing(&what))?;
        let v = parse_u64(tok).ok_or_else(|| self.bad(&what, "a vertex index", tok))?;
        if v < base || v - base >= n as u64 {
            return Err(self.err(format!(
                "{what} {v} is out of range: the file has {n} vertices, numbered from {base}"
            )));
        }
        Ok((v - base) as u32)
    }

    /// The next token as a finite `f64`.
    ///
    /// # Errors
    /// A missing token, a malformed number, NaN or infinity.
    #[inline]
    pub fn f64(&mut self, what: impl std::fmt::Display) -> Result<f64, IoError> {
        let tok = self.next_token().ok_or_else(|| self.missing(&what))?;
        match parse_f64(tok) {
            Some(x) if x.is_finite() => Ok(x),
            Some(x) => Err(self.err(format!("{what} is not finite ({x})"))),
            None => Err(self.bad(&what, "a number", tok)),
        }
    }

    /// Succeeds when no token is left.
    ///
    /// # Errors
    /// Extra tokens.
    pub fn end(&mut self) -> Result<(), IoError> {
        match self.next_token() {
            None => Ok(()),
            Some(t) => Err(self.err(format!(
                "unexpected extra value '{}' at the end of the line",
                String::from_utf8_lossy(&t[..t.len().min(40)])
            ))),
        }
    }

    /// Number of tokens left (consumes nothing).
    pub fn count_rest(&self) -> usize {
        let mut t = Tokens {
            s: self.s,
            pos: self.pos,
            no: self.no,
            path: self.path,
        };
        let mut n = 0;
        while t.next_token().is_some() {
            n += 1;
        }
        n
    }
}

/// Parses a decimal unsigned integer (no sign, no spaces), `None` on overflow or junk.
#[inline]
pub fn parse_u64(tok: &[u8]) -> Option<u64> {
    if tok.is_empty() || tok.len() > 20 {
        return None;
    }
    let mut v: u64 = 0;
    for &b in tok {
        let d = b.wrapping_sub(b'0');
        if d > 9 {
            return None;
        }
        v = v.checked_mul(10)?.checked_add(d as u64)?;
    }
    Some(v)
}

/// Parses a floating-point number (decimal or scientific; `nan`/`inf` parse and are rejected by
/// the callers that need finite values).
#[inline]
pub fn parse_f64(tok: &[u8]) -> Option<f64> {
    fast_float2::parse(tok).ok()
}

/// Writes `x` so that it reads back to the same `f64` (shortest round-trip form).
pub fn write_f64(w: &mut dyn std::io::Write, x: f64) -> std::io::Result<()> {
    if x == x.trunc() && x.abs() < 1e15 {
        write!(w, "{}", x as i64)
    } else {
        write!(w, "{x}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_integers_strictly() {
        assert_eq!(parse_u64(b"0"), Some(0));
        assert_eq!(parse_u64(b"18446744073709551615"), Some(u64::MAX));
        assert_eq!(parse_u64(b"18446744073709551616"), None);
        assert_eq!(parse_u64(b"1e3"), None);
        assert_eq!(parse_u64(b"-1"), None);
        assert_eq!(parse_u64(b""), None);
    }

    #[test]
    fn f64_round_trips_through_write() {
        for x in [0.0, -1.5, 1e-300, 0.1 + 0.2, 123456789.0, -7.0e20] {
            let mut s = Vec::new();
            write_f64(&mut s, x).unwrap();
            assert_eq!(parse_f64(&s), Some(x), "{}", String::from_utf8_lossy(&s));
        }
    }

    #[test]
    fn long_garbage_line_is_an_error_not_an_allocation_bomb() {
        let data = vec![b'x'; 70 << 20];
        let mut r = LineReader::new(&data[..], "g".as_ref(), None);
        assert!(r.next_line().is_err());
    }
}
