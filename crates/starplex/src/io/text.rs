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
///
/// ```
/// use starplex::io::text::LineReader;
/// let data = b"3 # three\n\n1 2 3\n";
/// let mut r = LineReader::new(&data[..], "mem.txt".as_ref(), Some(b'#'));
/// let n = r.next_content_line().unwrap().unwrap().tokens().u64("a count").unwrap();
/// assert_eq!(n, 3);
/// let line = r.next_content_line().unwrap().unwrap();
/// assert_eq!((line.no, line.bytes), (3, &b"1 2 3"[..])); // the blank line 2 is skipped
/// assert!(r.next_content_line().unwrap().is_none());
/// ```
pub struct LineReader<'p, R: BufRead> {
    r: R,
    buf: Vec<u8>,
    no: u64,
    path: &'p Path,
    comment: Option<u8>,
    offset: u64,
}

/// One line of a file with its context.
///
/// ```
/// use starplex::io::text::LineReader;
/// let mut r = LineReader::new(&b"a\nb c\n"[..], "mem.txt".as_ref(), None);
/// r.next_line().unwrap();
/// let line = r.next_line().unwrap().unwrap();
/// assert_eq!((line.bytes, line.no), (&b"b c"[..], 2));
/// assert_eq!(line.path, std::path::Path::new("mem.txt"));
/// ```
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
///
/// ```
/// use starplex::io::text::LineReader;
/// let mut r = LineReader::new(&b"tri 3  0 1\t2\n"[..], "mem.txt".as_ref(), None);
/// let line = r.next_line().unwrap().unwrap();
/// let mut t = line.tokens();
/// assert_eq!(t.word("a type").unwrap(), b"tri");
/// assert_eq!(t.count_rest(), 4);
/// let v: Vec<u64> = (0..4).map(|_| t.u64("a value").unwrap()).collect();
/// assert_eq!(v, [3, 0, 1, 2]);
/// ```
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
    ///
    /// ```
    /// use starplex::io::text::LineReader;
    /// let r = LineReader::new(std::io::Cursor::new("x\n"), "in.txt".as_ref(), Some(b'%'));
    /// assert_eq!(r.line_no(), 0);
    /// assert_eq!(r.path(), std::path::Path::new("in.txt"));
    /// ```
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
    ///
    /// ```
    /// use starplex::io::text::LineReader;
    /// let mut r = LineReader::new(&b"# header\n\nvalue\n"[..], "mem.txt".as_ref(), Some(b'#'));
    /// r.next_content_line().unwrap();
    /// assert_eq!(r.line_no(), 3); // comment and blank lines are counted
    /// ```
    pub fn line_no(&self) -> u64 {
        self.no
    }

    /// Bytes consumed so far.
    ///
    /// ```
    /// use starplex::io::text::LineReader;
    /// let mut r = LineReader::new(&b"ab\r\ncd\n"[..], "mem.txt".as_ref(), None);
    /// r.next_line().unwrap();
    /// assert_eq!(r.offset(), 4); // "ab\r\n"
    /// ```
    pub fn offset(&self) -> u64 {
        self.offset
    }

    /// The file path.
    ///
    /// ```
    /// use starplex::io::text::LineReader;
    /// use std::path::Path;
    /// let r = LineReader::new(&b""[..], Path::new("dir/mesh.off"), None);
    /// assert_eq!(r.path(), Path::new("dir/mesh.off"));
    /// ```
    pub fn path(&self) -> &'p Path {
        self.path
    }

    /// The next raw line (terminator and trailing `\r` removed), or `None` at the end.
    ///
    /// ```
    /// use starplex::io::text::LineReader;
    /// let mut r = LineReader::new(&b"a # b\r\n\n"[..], "mem.txt".as_ref(), Some(b'#'));
    /// assert_eq!(r.next_line().unwrap().unwrap().bytes, b"a # b"); // comments are kept
    /// assert_eq!(r.next_line().unwrap().unwrap().bytes, b"");      // blank lines too
    /// assert!(r.next_line().unwrap().is_none());
    /// ```
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
    /// ```
    /// use starplex::io::text::LineReader;
    /// let mut r = LineReader::new(&b"  # only a comment\n\t7 8  # tail\n"[..], "mem.txt".as_ref(), Some(b'#'));
    /// let line = r.next_content_line().unwrap().unwrap();
    /// assert_eq!((line.no, line.bytes), (2, &b"7 8"[..])); // trimmed, comment removed
    /// assert!(r.next_content_line().unwrap().is_none());
    /// ```
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
            if let Some(c) = self.comment
                && let Some(p) = memchr::memchr(c, &self.buf[..end])
            {
                end = p;
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
    /// ```
    /// use starplex::io::text::LineReader;
    /// let mut r = LineReader::new(&b"1\n"[..], "mem.txt".as_ref(), None);
    /// assert_eq!(r.expect_line("the count").unwrap().bytes, b"1");
    /// let e = r.expect_line("the vertices").err().unwrap();
    /// assert_eq!(
    ///     e.to_string(),
    ///     "mem.txt:2: unexpected end of file: expected the vertices (the file is truncated or a count is wrong)"
    /// );
    /// ```
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
    ///
    /// ```
    /// use starplex::io::text::LineReader;
    /// let mut r = LineReader::new(&b"a\nb\n"[..], "mem.txt".as_ref(), None);
    /// r.next_line().unwrap();
    /// r.next_line().unwrap();
    /// assert_eq!(r.err("too many lines").to_string(), "mem.txt:2: too many lines");
    /// ```
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
    ///
    /// ```
    /// use starplex::io::text::LineReader;
    /// let mut r = LineReader::new(&b"4 5\n"[..], "mem.txt".as_ref(), None);
    /// let line = r.next_line().unwrap().unwrap();
    /// let mut t = line.tokens();
    /// assert_eq!((t.u64("n").unwrap(), t.u64("m").unwrap()), (4, 5));
    /// assert!(t.end().is_ok());
    /// ```
    pub fn tokens(&self) -> Tokens<'a> {
        Tokens {
            s: self.bytes,
            pos: 0,
            no: self.no,
            path: self.path,
        }
    }

    /// An error at this line.
    ///
    /// ```
    /// use starplex::io::text::LineReader;
    /// let mut r = LineReader::new(&b"x\nSPX 9\n"[..], "mem.spx".as_ref(), None);
    /// r.next_line().unwrap();
    /// let line = r.next_line().unwrap().unwrap();
    /// assert_eq!(line.err("unknown version").to_string(), "mem.spx:2: unknown version");
    /// ```
    pub fn err(&self, msg: impl Into<String>) -> IoError {
        IoError::parse(self.path, Some(Location::Line(self.no)), msg)
    }

    /// The line as text (lossy), for messages.
    ///
    /// ```
    /// use starplex::io::text::LineReader;
    /// let mut r = LineReader::new(&b"caf\xc3\xa9 \xff\n"[..], "mem.txt".as_ref(), None);
    /// let line = r.next_line().unwrap().unwrap();
    /// assert_eq!(line.text(), "café \u{fffd}"); // invalid UTF-8 shown as U+FFFD
    /// ```
    pub fn text(&self) -> String {
        String::from_utf8_lossy(self.bytes).into_owned()
    }
}

impl<'a> Tokens<'a> {
    /// The next token, if any.
    ///
    /// ```
    /// use starplex::io::text::LineReader;
    /// let mut r = LineReader::new(&b" a\tbc  \n"[..], "mem.txt".as_ref(), None);
    /// let line = r.next_line().unwrap().unwrap();
    /// let mut t = line.tokens();
    /// assert_eq!(t.next_token(), Some(&b"a"[..]));
    /// assert_eq!(t.next_token(), Some(&b"bc"[..]));
    /// assert_eq!(t.next_token(), None);
    /// ```
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
    ///
    /// ```
    /// use starplex::io::text::LineReader;
    /// let mut r = LineReader::new(&b"\n\nquad 5\n"[..], "mem.txt".as_ref(), None);
    /// let l = r.next_content_line().unwrap().unwrap(); // line 3
    /// let mut t = l.tokens();
    /// t.word("a type").unwrap();
    /// assert_eq!(t.err("a quad has 4 vertices").to_string(), "mem.txt:3: a quad has 4 vertices");
    /// ```
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
    /// ```
    /// use starplex::io::text::LineReader;
    /// let mut r = LineReader::new(&b"hex\n"[..], "mem.txt".as_ref(), None);
    /// let line = r.next_line().unwrap().unwrap();
    /// let mut t = line.tokens();
    /// assert_eq!(t.word("a cell type").unwrap(), b"hex");
    /// let e = t.word("a vertex count").unwrap_err();
    /// assert_eq!(e.to_string(), "mem.txt:1: expected a vertex count, found the end of the line");
    /// ```
    ///
    /// # Errors
    /// A missing token.
    pub fn word(&mut self, what: impl std::fmt::Display) -> Result<&'a [u8], IoError> {
        self.next_token().ok_or_else(|| self.missing(&what))
    }

    /// The next token as an unsigned integer.
    ///
    /// ```
    /// use starplex::io::text::LineReader;
    /// let mut r = LineReader::new(&b"12 -3\n"[..], "mem.txt".as_ref(), None);
    /// let line = r.next_line().unwrap().unwrap();
    /// let mut t = line.tokens();
    /// assert_eq!(t.u64("n").unwrap(), 12);
    /// let e = t.u64("m").unwrap_err();
    /// assert_eq!(e.to_string(), "mem.txt:1: expected m (an unsigned integer), found '-3'");
    /// ```
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
    /// ```
    /// use starplex::io::text::LineReader;
    /// let mut r = LineReader::new(&b"-3 +4 1.5\n"[..], "mem.txt".as_ref(), None);
    /// let line = r.next_line().unwrap().unwrap();
    /// let mut t = line.tokens();
    /// assert_eq!((t.i64("a").unwrap(), t.i64("b").unwrap()), (-3, 4));
    /// assert!(t.i64("c").is_err());
    /// ```
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
    /// ```
    /// use starplex::io::text::LineReader;
    /// let mut r = LineReader::new(&b"1 3 4\n"[..], "mem.txt".as_ref(), None);
    /// let line = r.next_line().unwrap().unwrap();
    /// let mut t = line.tokens();
    /// // 1-based indices of a file with 3 vertices.
    /// assert_eq!(t.index("vertex", 1, 3).unwrap(), 0);
    /// assert_eq!(t.index("vertex", 1, 3).unwrap(), 2);
    /// let e = t.index("vertex", 1, 3).unwrap_err();
    /// assert_eq!(e.to_string(), "mem.txt:1: vertex 4 is out of range: the file has 3 vertices, numbered from 1");
    /// ```
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
    /// ```
    /// use starplex::io::text::LineReader;
    /// let mut r = LineReader::new(&b"2.5e-1 inf\n"[..], "mem.txt".as_ref(), None);
    /// let line = r.next_line().unwrap().unwrap();
    /// let mut t = line.tokens();
    /// assert_eq!(t.f64("x").unwrap(), 0.25);
    /// assert_eq!(t.f64("y").unwrap_err().to_string(), "mem.txt:1: y is not finite (inf)");
    /// ```
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
    /// ```
    /// use starplex::io::text::LineReader;
    /// let mut r = LineReader::new(&b"1 2\n"[..], "mem.txt".as_ref(), None);
    /// let line = r.next_line().unwrap().unwrap();
    /// let mut t = line.tokens();
    /// t.u64("x").unwrap();
    /// let e = t.end().unwrap_err();
    /// assert_eq!(e.to_string(), "mem.txt:1: unexpected extra value '2' at the end of the line");
    /// ```
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
    ///
    /// ```
    /// use starplex::io::text::LineReader;
    /// let mut r = LineReader::new(&b"0.5 1 2\n"[..], "mem.txt".as_ref(), None);
    /// let line = r.next_line().unwrap().unwrap();
    /// let mut t = line.tokens();
    /// assert_eq!(t.count_rest(), 3); // e.g. the ambient dimension from the first vertex line
    /// t.f64("x").unwrap();
    /// assert_eq!(t.count_rest(), 2);
    /// assert_eq!(t.count_rest(), 2); // nothing consumed
    /// ```
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
///
/// ```
/// use starplex::io::text::parse_u64;
/// assert_eq!(parse_u64(b"42"), Some(42));
/// assert_eq!(parse_u64(b"18446744073709551616"), None); // u64::MAX + 1
/// assert_eq!(parse_u64(b"+1"), None);
/// assert_eq!(parse_u64(b"1e3"), None);
/// ```
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
///
/// ```
/// use starplex::io::text::parse_f64;
/// assert_eq!(parse_f64(b"-1.5e2"), Some(-150.0));
/// assert_eq!(parse_f64(b"1,5"), None);
/// assert!(parse_f64(b"nan").unwrap().is_nan());
/// ```
#[inline]
pub fn parse_f64(tok: &[u8]) -> Option<f64> {
    fast_float2::parse(tok).ok()
}

/// Writes `x` so that it reads back to the same `f64` (shortest round-trip form).
///
/// ```
/// use starplex::io::text::{parse_f64, write_f64};
/// let mut out = Vec::new();
/// write_f64(&mut out, 3.0).unwrap();
/// out.push(b' ');
/// write_f64(&mut out, 0.1 + 0.2).unwrap();
/// assert_eq!(out, b"3 0.30000000000000004");
/// assert_eq!(parse_f64(&out[2..]), Some(0.1 + 0.2)); // reads back exactly
/// out.clear();
/// write_f64(&mut out, 1e-300).unwrap(); // tiny and huge values use an exponent
/// assert_eq!(out, b"1e-300");
/// ```
pub fn write_f64(w: &mut dyn std::io::Write, x: f64) -> std::io::Result<()> {
    let a = x.abs();
    if x == x.trunc() && a < 1e15 {
        write!(w, "{}", x as i64)
    } else if (1e-5..1e16).contains(&a) || !x.is_finite() {
        write!(w, "{x}")
    } else {
        // `{}` would print every digit of 1e-300 or 1e300 (hundreds of characters, which some
        // readers refuse); `{:e}` is the same shortest round-trip digits with an exponent.
        write!(w, "{x:e}")
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
        for x in [
            0.0,
            -1.5,
            1e-300,
            0.1 + 0.2,
            123456789.0,
            -7.0e20,
            f64::MIN_POSITIVE,
            5e-324,
            f64::MAX,
            -1.2345678901234567e-7,
            1e16 + 2.0,
        ] {
            let mut s = Vec::new();
            write_f64(&mut s, x).unwrap();
            assert!(s.len() <= 24, "{}", String::from_utf8_lossy(&s));
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
