//! A streaming reader of whitespace-separated words with line numbers, for formats whose line
//! structure does not matter (Medit, legacy VTK, gmsh).
//!
//! Unlike [`LineReader`](super::text::LineReader), it never holds a whole line: meshio writes the
//! whole `POINTS` array of a legacy VTK file on one line (20 MB for 376k points), so the words are
//! cut straight from the buffered reader. Words longer than [`MAX_WORD`] bytes are refused (binary
//! garbage). Every error names the file and the line of the word in question.
//!
//! ```
//! use starplex::io::words::Words;
//! let data = b"Vertices # comment\n 2\n1.5 -2 7\n";
//! let mut w = Words::new(&data[..], "mem.mesh".as_ref(), Some(b'#'));
//! assert_eq!(w.expect("a keyword").unwrap(), b"Vertices");
//! assert_eq!(w.u64("the vertex count").unwrap(), 2);
//! assert_eq!(w.line(), 2);
//! assert_eq!(w.f64("x").unwrap(), 1.5);
//! assert_eq!(w.i64("y").unwrap(), -2);
//! assert_eq!(w.f64("z").unwrap(), 7.0);
//! let e = w.f64("w").unwrap_err();
//! assert_eq!(e.to_string(), "mem.mesh:4: unexpected end of file: expected w (the file is truncated or a count is wrong)");
//! ```
use std::io::BufRead;
use std::path::Path;

use super::text::{parse_f64, parse_u64};
use super::{IoError, Location};

/// Longest accepted word, in bytes.
///
/// ```
/// use starplex::io::words::{Words, MAX_WORD};
/// let garbage = vec![b'x'; MAX_WORD + 1];
/// let mut w = Words::new(&garbage[..], "blob.vtk".as_ref(), None);
/// let e = w.next_word().unwrap_err();
/// assert_eq!(e.to_string(), format!("blob.vtk:1: a word longer than {MAX_WORD} bytes (is this a binary file?)"));
/// ```
pub const MAX_WORD: usize = 4096;

#[inline]
fn is_ws(b: u8) -> bool {
    matches!(b, b' ' | b'\t' | b'\r' | b'\n' | b'\x0b' | b'\x0c')
}

/// Whitespace-separated words of a buffered reader, each with its line number.
///
/// ```
/// use starplex::io::words::Words;
/// // Line structure does not matter: words may be spread over lines in any way.
/// let mut w = Words::new(&b"Triangles 2\n1 2 3   2\n3 4"[..], "mem.mesh".as_ref(), None);
/// w.keyword("Triangles").unwrap();
/// let n = w.u64("the triangle count").unwrap();
/// let tris: Vec<u32> = (0..3 * n).map(|_| w.index("a vertex", 1, 4).unwrap()).collect();
/// assert_eq!(tris, [0, 1, 2, 1, 2, 3]);
/// assert_eq!(w.line(), 3);
/// ```
pub struct Words<'p, R: BufRead> {
    r: R,
    path: &'p Path,
    /// Line of the read position (1-based).
    line: u64,
    word: Vec<u8>,
    word_line: u64,
    comment: Option<u8>,
    in_comment: bool,
    pushed_back: bool,
    at_eof: bool,
    /// Bytes consumed from `r`.
    pos: u64,
    /// Byte offset of the last word.
    word_pos: u64,
    /// Errors name byte offsets instead of lines (binary files, see [`Words::set_binary`]).
    binary: bool,
}

impl<'p, R: BufRead> Words<'p, R> {
    /// Wraps `r`; `comment` starts a comment that runs to the end of the line (only at the start
    /// of a word).
    ///
    /// ```
    /// use starplex::io::words::Words;
    /// let mut w = Words::new(std::io::Cursor::new("a % note\nb"), "in.txt".as_ref(), Some(b'%'));
    /// assert_eq!(w.expect("a").unwrap(), b"a");
    /// assert_eq!(w.expect("b").unwrap(), b"b"); // the comment was skipped
    /// assert_eq!(w.line(), 2);
    /// ```
    pub fn new(r: R, path: &'p Path, comment: Option<u8>) -> Self {
        Words {
            r,
            path,
            line: 1,
            word: Vec::with_capacity(64),
            word_line: 0,
            comment,
            in_comment: false,
            pushed_back: false,
            at_eof: false,
            pos: 0,
            word_pos: 0,
            binary: false,
        }
    }

    /// From now on errors name the byte offset of the word (or of the binary data) in question
    /// instead of its line: for formats whose text header is followed by binary sections, whose
    /// line numbers mean nothing.
    ///
    /// ```
    /// use starplex::io::words::Words;
    /// let mut w = Words::new(&b"$Nodes x"[..], "b.msh".as_ref(), None);
    /// w.set_binary();
    /// w.expect("a section").unwrap();
    /// assert_eq!(w.u64("a count").unwrap_err().to_string(),
    ///            "b.msh: byte 7: expected a count (an unsigned integer), found 'x'");
    /// ```
    pub fn set_binary(&mut self) {
        self.binary = true;
    }

    /// Bytes consumed so far (the offset of the next raw byte).
    ///
    /// ```
    /// use starplex::io::words::Words;
    /// let mut w = Words::new(&b"ab cd"[..], "m".as_ref(), None);
    /// w.expect("a word").unwrap();
    /// assert_eq!(w.offset(), 2);
    /// ```
    pub fn offset(&self) -> u64 {
        self.pos
    }

    /// Reads exactly `buf.len()` raw bytes (binary data after a text header line; call
    /// [`rest_of_line`](Self::rest_of_line) first to consume the header's line end).
    ///
    /// ```
    /// use starplex::io::words::Words;
    /// let mut w = Words::new(&b"POINTS 1 float\n\x00\x00\x80\x3f\nEND"[..], "b.vtk".as_ref(), None);
    /// w.keyword("POINTS").unwrap();
    /// w.u64("n").unwrap();
    /// w.expect("type").unwrap();
    /// w.rest_of_line().unwrap();
    /// let mut b = [0u8; 4];
    /// w.read_raw(&mut b, "a coordinate").unwrap();
    /// assert_eq!(f32::from_le_bytes(b), 1.0);
    /// assert_eq!(w.expect("a keyword").unwrap(), b"END");
    /// let e = w.read_raw(&mut b, "more data").unwrap_err();
    /// assert!(e.to_string().contains("unexpected end of file in more data"), "{e}");
    /// ```
    ///
    /// # Errors
    /// OS errors; the end of the input before `buf` is full (located at the byte where the
    /// data started).
    pub fn read_raw(&mut self, buf: &mut [u8], what: &str) -> Result<(), IoError> {
        debug_assert!(!self.pushed_back);
        let start = self.pos;
        match std::io::Read::read_exact(&mut self.r, buf) {
            Ok(()) => {
                self.pos += buf.len() as u64;
                Ok(())
            }
            Err(e) if e.kind() == std::io::ErrorKind::UnexpectedEof => Err(IoError::parse(
                self.path,
                Some(Location::Byte(start)),
                format!(
                    "unexpected end of file in {what} ({} bytes needed): the file is truncated or a count is wrong",
                    buf.len()
                ),
            )),
            Err(e) => Err(IoError::new(self.path, e).at(Location::Byte(start))),
        }
    }

    /// The file path.
    ///
    /// ```
    /// use starplex::io::words::Words;
    /// use std::path::Path;
    /// let w = Words::new(&b""[..], Path::new("dir/mesh.msh"), None);
    /// assert_eq!(w.path(), Path::new("dir/mesh.msh"));
    /// ```
    pub fn path(&self) -> &'p Path {
        self.path
    }

    /// Line of the last word read (the read position's line before the first word).
    ///
    /// ```
    /// use starplex::io::words::Words;
    /// let mut w = Words::new(&b"\n\n  a\nb"[..], "mem.txt".as_ref(), None);
    /// assert_eq!(w.line(), 1);
    /// w.next_word().unwrap();
    /// assert_eq!(w.line(), 3);
    /// w.next_word().unwrap();
    /// assert_eq!(w.line(), 4);
    /// ```
    pub fn line(&self) -> u64 {
        if self.word_line == 0 {
            self.line
        } else {
            self.word_line
        }
    }

    /// An error at the line of the last word.
    ///
    /// ```
    /// use starplex::io::words::Words;
    /// let mut w = Words::new(&b"Vertices\n-1\n"[..], "mem.mesh".as_ref(), None);
    /// w.expect("a keyword").unwrap();
    /// w.expect("a count").unwrap();
    /// assert_eq!(w.err("a negative count").to_string(), "mem.mesh:2: a negative count");
    /// ```
    pub fn err(&self, msg: impl Into<String>) -> IoError {
        if self.binary {
            return IoError::parse(self.path, Some(Location::Byte(self.word_pos)), msg);
        }
        IoError::parse(self.path, Some(Location::Line(self.line())), msg)
    }

    /// An error at line `line`.
    ///
    /// ```
    /// use starplex::io::words::Words;
    /// let w = Words::new(&b""[..], "mem.vtk".as_ref(), None);
    /// assert_eq!(w.err_at(7, "bad header").to_string(), "mem.vtk:7: bad header");
    /// assert_eq!(w.err_at(0, "empty").to_string(), "mem.vtk:1: empty"); // lines start at 1
    /// ```
    pub fn err_at(&self, line: u64, msg: impl Into<String>) -> IoError {
        if self.binary {
            return IoError::parse(self.path, Some(Location::Byte(self.word_pos)), msg);
        }
        IoError::parse(self.path, Some(Location::Line(line.max(1))), msg)
    }

    /// Makes the next [`next_word`](Self::next_word) return the last word again.
    ///
    /// ```
    /// use starplex::io::words::Words;
    /// let mut w = Words::new(&b"POINT_DATA 4"[..], "mem.vtk".as_ref(), None);
    /// let first = w.expect("a section").unwrap().to_vec();
    /// assert_eq!(first, b"POINT_DATA");
    /// w.unread(); // not ours: leave it for the next reader
    /// assert_eq!(w.next_word().unwrap(), Some(&b"POINT_DATA"[..]));
    /// assert_eq!(w.u64("a count").unwrap(), 4);
    /// ```
    pub fn unread(&mut self) {
        self.pushed_back = true;
    }

    fn os(&self, e: std::io::Error) -> IoError {
        IoError::new(self.path, e).at(Location::Line(self.line))
    }

    /// Reads the next word into the internal buffer; `false` at the end of the input.
    fn advance(&mut self) -> Result<bool, IoError> {
        if self.pushed_back {
            self.pushed_back = false;
            return Ok(!self.at_eof);
        }
        self.word.clear();
        loop {
            let buf = match self.r.fill_buf() {
                Ok(b) => b,
                Err(e) if e.kind() == std::io::ErrorKind::Interrupted => continue,
                Err(e) => return Err(self.os(e)),
            };
            let n = buf.len();
            if n == 0 {
                self.at_eof = self.word.is_empty();
                return Ok(!self.word.is_empty());
            }
            let mut i = 0;
            if self.word.is_empty() {
                while i < n {
                    let b = buf[i];
                    if b == b'\n' {
                        self.line += 1;
                        self.in_comment = false;
                    } else if self.in_comment || is_ws(b) {
                    } else if Some(b) == self.comment {
                        self.in_comment = true;
                    } else {
                        break;
                    }
                    i += 1;
                }
                if i == n {
                    self.r.consume(n);
                    self.pos += n as u64;
                    continue;
                }
                self.word_line = self.line;
                self.word_pos = self.pos + i as u64;
            }
            let start = i;
            while i < n && !is_ws(buf[i]) {
                i += 1;
            }
            if self.word.len() + (i - start) > MAX_WORD {
                let line = self.line;
                self.r.consume(i);
                self.pos += i as u64;
                return Err(self.err_at(
                    line,
                    format!("a word longer than {MAX_WORD} bytes (is this a binary file?)"),
                ));
            }
            self.word.extend_from_slice(&buf[start..i]);
            self.r.consume(i);
            self.pos += i as u64;
            if i < n {
                return Ok(true);
            }
        }
    }

    /// The next word, or `None` at the end of the input.
    ///
    /// ```
    /// use starplex::io::words::Words;
    /// let mut w = Words::new(&b"a\tb\r\n"[..], "mem.txt".as_ref(), None);
    /// assert_eq!(w.next_word().unwrap(), Some(&b"a"[..]));
    /// assert_eq!(w.next_word().unwrap(), Some(&b"b"[..]));
    /// assert_eq!(w.next_word().unwrap(), None);
    /// ```
    ///
    /// # Errors
    /// OS errors, a word longer than [`MAX_WORD`].
    pub fn next_word(&mut self) -> Result<Option<&[u8]>, IoError> {
        Ok(if self.advance()? {
            Some(&self.word)
        } else {
            None
        })
    }

    /// The next word, or an error saying the file ended while `what` was expected.
    ///
    /// ```
    /// use starplex::io::words::Words;
    /// let mut w = Words::new(&b"End"[..], "mem.mesh".as_ref(), None);
    /// assert_eq!(w.expect("'End'").unwrap(), b"End");
    /// let e = w.expect("more").unwrap_err();
    /// assert_eq!(
    ///     e.to_string(),
    ///     "mem.mesh:1: unexpected end of file: expected more (the file is truncated or a count is wrong)"
    /// );
    /// ```
    ///
    /// # Errors
    /// End of input, OS errors.
    pub fn expect(&mut self, what: &str) -> Result<&[u8], IoError> {
        if self.advance()? {
            Ok(&self.word)
        } else {
            Err(self.eof(what))
        }
    }

    /// The error "unexpected end of file: expected `what`" at the read position.
    ///
    /// ```
    /// use starplex::io::words::Words;
    /// let w = Words::new(&b"1\n2\n"[..], "mem.txt".as_ref(), None);
    /// assert!(w.eof("the cells").to_string().ends_with("expected the cells (the file is truncated or a count is wrong)"));
    /// ```
    pub fn eof(&self, what: &str) -> IoError {
        let msg = format!(
            "unexpected end of file: expected {what} (the file is truncated or a count is wrong)"
        );
        if self.binary {
            return IoError::parse(self.path, Some(Location::Byte(self.pos)), msg);
        }
        self.err_at(self.line, msg)
    }

    fn bad(&self, what: &str, kind: &str) -> IoError {
        let w = &self.word[..self.word.len().min(40)];
        self.err(format!(
            "expected {what} ({kind}), found '{}'",
            String::from_utf8_lossy(w)
        ))
    }

    /// The next word as an unsigned integer.
    ///
    /// ```
    /// use starplex::io::words::Words;
    /// let mut w = Words::new(&b"7 x"[..], "mem.txt".as_ref(), None);
    /// assert_eq!(w.u64("a count").unwrap(), 7);
    /// let e = w.u64("a count").unwrap_err();
    /// assert_eq!(e.to_string(), "mem.txt:1: expected a count (an unsigned integer), found 'x'");
    /// ```
    ///
    /// # Errors
    /// End of input, a malformed number.
    #[inline]
    pub fn u64(&mut self, what: &str) -> Result<u64, IoError> {
        if !self.advance()? {
            return Err(self.eof(what));
        }
        parse_u64(&self.word).ok_or_else(|| self.bad(what, "an unsigned integer"))
    }

    /// The next word as a signed integer.
    ///
    /// ```
    /// use starplex::io::words::Words;
    /// let mut w = Words::new(&b"-12 +3 4.0"[..], "mem.txt".as_ref(), None);
    /// assert_eq!(w.i64("a tag").unwrap(), -12);
    /// assert_eq!(w.i64("a tag").unwrap(), 3);
    /// assert!(w.i64("a tag").is_err());
    /// ```
    ///
    /// # Errors
    /// End of input, a malformed number.
    pub fn i64(&mut self, what: &str) -> Result<i64, IoError> {
        if !self.advance()? {
            return Err(self.eof(what));
        }
        let w = &self.word[..];
        let (neg, digits) = match w.first() {
            Some(b'-') => (true, &w[1..]),
            Some(b'+') => (false, &w[1..]),
            _ => (false, w),
        };
        let v = parse_u64(digits)
            .filter(|&v| v <= i64::MAX as u64)
            .ok_or_else(|| self.bad(what, "an integer"))? as i64;
        Ok(if neg { -v } else { v })
    }

    /// The next word as a finite `f64`.
    ///
    /// ```
    /// use starplex::io::words::Words;
    /// let mut w = Words::new(&b"1e-3 -0.5 inf"[..], "mem.txt".as_ref(), None);
    /// assert_eq!(w.f64("x").unwrap(), 0.001);
    /// assert_eq!(w.f64("y").unwrap(), -0.5);
    /// assert_eq!(w.f64("z").unwrap_err().to_string(), "mem.txt:1: z is not finite (inf)");
    /// ```
    ///
    /// # Errors
    /// End of input, a malformed number, NaN or infinity.
    #[inline]
    pub fn f64(&mut self, what: &str) -> Result<f64, IoError> {
        if !self.advance()? {
            return Err(self.eof(what));
        }
        match parse_f64(&self.word) {
            Some(x) if x.is_finite() => Ok(x),
            Some(x) => Err(self.err(format!("{what} is not finite ({x})"))),
            None => Err(self.bad(what, "a number")),
        }
    }

    /// The next word as an index in `base..base + n`, returned 0-based.
    ///
    /// ```
    /// use starplex::io::words::Words;
    /// let mut w = Words::new(&b"1 3 0"[..], "mem.mesh".as_ref(), None);
    /// // Medit indices are 1-based; the file has 3 vertices.
    /// assert_eq!(w.index("a vertex", 1, 3).unwrap(), 0);
    /// assert_eq!(w.index("a vertex", 1, 3).unwrap(), 2);
    /// let e = w.index("a vertex", 1, 3).unwrap_err();
    /// assert_eq!(e.to_string(), "mem.mesh:1: a vertex 0 is out of range: the file has 3 vertices (1-based)");
    /// ```
    ///
    /// # Errors
    /// End of input, a malformed number, an index out of range.
    #[inline]
    pub fn index(&mut self, what: &str, base: u64, n: usize) -> Result<u32, IoError> {
        let v = self.u64(what)?;
        if v < base || v - base >= n as u64 {
            return Err(self.err(format!(
                "{what} {v} is out of range: the file has {n} vertices ({base}-based)"
            )));
        }
        Ok((v - base) as u32)
    }

    /// The next word, which must equal `want` (ASCII case-insensitive).
    ///
    /// ```
    /// use starplex::io::words::Words;
    /// let mut w = Words::new(&b"$nodes $Elements"[..], "mem.msh".as_ref(), None);
    /// assert!(w.keyword("$Nodes").is_ok()); // case-insensitive
    /// let e = w.keyword("$EndNodes").unwrap_err();
    /// assert_eq!(e.to_string(), "mem.msh:1: expected '$EndNodes', found '$Elements'");
    /// ```
    ///
    /// # Errors
    /// End of input or another word.
    pub fn keyword(&mut self, want: &str) -> Result<(), IoError> {
        let w = self.expect(&format!("'{want}'"))?;
        if w.eq_ignore_ascii_case(want.as_bytes()) {
            Ok(())
        } else {
            let shown = String::from_utf8_lossy(&w[..w.len().min(40)]).into_owned();
            Err(self.err(format!("expected '{want}', found '{shown}'")))
        }
    }

    /// Skips raw bytes up to and including the next occurrence of `marker` (a section end in a
    /// binary file, whose data may hold any byte). Returns false at the end of the input.
    ///
    /// ```
    /// use starplex::io::words::Words;
    /// let mut w = Words::new(&b"$Data\n\x00\xff$End x\n$EndData\n$Next"[..], "b.msh".as_ref(), None);
    /// w.expect("a section").unwrap();
    /// assert!(w.skip_raw_past(b"$EndData").unwrap());
    /// assert_eq!(w.expect("a section").unwrap(), b"$Next");
    /// assert!(!w.skip_raw_past(b"$EndNext").unwrap());
    /// ```
    ///
    /// # Errors
    /// OS errors.
    pub fn skip_raw_past(&mut self, marker: &[u8]) -> Result<bool, IoError> {
        debug_assert!(!self.pushed_back && !marker.is_empty());
        let finder = memchr::memmem::Finder::new(marker);
        let mut carry: Vec<u8> = Vec::with_capacity(2 * marker.len());
        loop {
            let buf = match self.r.fill_buf() {
                Ok(b) => b,
                Err(e) if e.kind() == std::io::ErrorKind::Interrupted => continue,
                Err(e) => return Err(self.os(e)),
            };
            if buf.is_empty() {
                return Ok(false);
            }
            let n = buf.len();
            // a marker straddling the previous buffer and this one
            let head = n.min(marker.len() - 1);
            if !carry.is_empty() {
                carry.extend_from_slice(&buf[..head]);
                if let Some(i) = finder.find(&carry) {
                    let old = carry.len() - head;
                    let used = i + marker.len() - old;
                    self.r.consume(used);
                    self.pos += used as u64;
                    return Ok(true);
                }
            }
            if let Some(i) = finder.find(buf) {
                let used = i + marker.len();
                self.r.consume(used);
                self.pos += used as u64;
                return Ok(true);
            }
            carry.clear();
            carry.extend_from_slice(&buf[n - head..]);
            self.r.consume(n);
            self.pos += n as u64;
        }
    }

    /// The rest of the current line (after the last word; the whole next line before any word),
    /// without the terminator, at most [`MAX_WORD`] bytes; the line terminator is consumed.
    ///
    /// ```
    /// use starplex::io::words::Words;
    /// let mut w = Words::new(&b"# vtk DataFile Version 4.2\r\nmy title\nASCII"[..], "mem.vtk".as_ref(), None);
    /// assert_eq!(w.rest_of_line().unwrap(), b"# vtk DataFile Version 4.2");
    /// assert_eq!(w.rest_of_line().unwrap(), b"my title");
    /// assert_eq!(w.expect("the encoding").unwrap(), b"ASCII");
    /// assert_eq!(w.line(), 3);
    /// ```
    ///
    /// # Errors
    /// OS errors, a line longer than [`MAX_WORD`].
    pub fn rest_of_line(&mut self) -> Result<Vec<u8>, IoError> {
        debug_assert!(!self.pushed_back);
        let mut out = Vec::new();
        if self.in_comment {
            // the comment is the rest of the line
            self.in_comment = false;
        }
        loop {
            let buf = match self.r.fill_buf() {
                Ok(b) => b,
                Err(e) if e.kind() == std::io::ErrorKind::Interrupted => continue,
                Err(e) => return Err(self.os(e)),
            };
            if buf.is_empty() {
                break;
            }
            let (take, done) = match memchr::memchr(b'\n', buf) {
                Some(i) => (i, true),
                None => (buf.len(), false),
            };
            if out.len() + take > MAX_WORD {
                let line = self.line;
                return Err(self.err_at(
                    line,
                    format!("a line longer than {MAX_WORD} bytes where a header line was expected"),
                ));
            }
            out.extend_from_slice(&buf[..take]);
            self.r.consume(take + done as usize);
            self.pos += (take + done as usize) as u64;
            if done {
                self.line += 1;
                break;
            }
        }
        if out.last() == Some(&b'\r') {
            out.pop();
        }
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A reader that hands out one byte per `fill_buf`, to exercise words split across buffers.
    struct Trickle<'a>(&'a [u8]);
    impl std::io::Read for Trickle<'_> {
        fn read(&mut self, out: &mut [u8]) -> std::io::Result<usize> {
            let n = self.0.len().min(out.len()).min(1);
            out[..n].copy_from_slice(&self.0[..n]);
            self.0 = &self.0[n..];
            Ok(n)
        }
    }

    #[test]
    fn words_split_across_buffers_keep_lines() {
        let text = b"ab  12\n# c d\n\n 3.5e2 x#y\r\nlast";
        let r = std::io::BufReader::with_capacity(1, Trickle(text));
        let mut w = Words::new(r, "t".as_ref(), Some(b'#'));
        let mut got = Vec::new();
        while let Some(word) = w.next_word().unwrap() {
            got.push((String::from_utf8(word.to_vec()).unwrap(), w.line()));
        }
        let want: Vec<(String, u64)> =
            [("ab", 1), ("12", 1), ("3.5e2", 4), ("x#y", 4), ("last", 5)]
                .iter()
                .map(|(s, l)| (s.to_string(), *l))
                .collect();
        assert_eq!(got, want);
    }

    #[test]
    fn rest_of_line_and_unread() {
        let mut w = Words::new(
            &b"# vtk DataFile Version 4.2\ntitle here\nASCII\n"[..],
            "t".as_ref(),
            None,
        );
        assert_eq!(w.rest_of_line().unwrap(), b"# vtk DataFile Version 4.2");
        assert_eq!(w.rest_of_line().unwrap(), b"title here");
        assert_eq!(w.expect("kind").unwrap(), b"ASCII");
        assert_eq!(w.line(), 3);
        w.unread();
        assert_eq!(w.next_word().unwrap(), Some(&b"ASCII"[..]));
        assert_eq!(w.next_word().unwrap(), None);
        w.unread();
        assert_eq!(w.next_word().unwrap(), None);
    }

    #[test]
    fn refuses_giant_words() {
        let data = vec![b'x'; MAX_WORD + 10];
        let mut w = Words::new(&data[..], "g".as_ref(), None);
        assert!(w.next_word().is_err());
    }

    #[test]
    fn numbers_are_checked() {
        let mut w = Words::new(&b"nan 5 -3 x 7"[..], "n".as_ref(), None);
        assert!(w.f64("x").unwrap_err().to_string().contains("not finite"));
        assert!(w
            .index("v", 1, 4)
            .unwrap_err()
            .to_string()
            .contains("out of range"));
        assert_eq!(w.i64("i").unwrap(), -3);
        assert!(w.u64("u").is_err());
        assert_eq!(w.index("v", 1, 7).unwrap(), 6);
    }
}
