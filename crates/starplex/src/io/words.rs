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
pub const MAX_WORD: usize = 4096;

#[inline]
fn is_ws(b: u8) -> bool {
    matches!(b, b' ' | b'\t' | b'\r' | b'\n' | b'\x0b' | b'\x0c')
}

/// Whitespace-separated words of a buffered reader, each with its line number.
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
}

impl<'p, R: BufRead> Words<'p, R> {
    /// Wraps `r`; `comment` starts a comment that runs to the end of the line (only at the start
    /// of a word).
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
        }
    }

    /// The file path.
    pub fn path(&self) -> &'p Path {
        self.path
    }

    /// Line of the last word read (the read position's line before the first word).
    pub fn line(&self) -> u64 {
        if self.word_line == 0 {
            self.line
        } else {
            self.word_line
        }
    }

    /// An error at the line of the last word.
    pub fn err(&self, msg: impl Into<String>) -> IoError {
        IoError::parse(self.path, Some(Location::Line(self.line())), msg)
    }

    /// An error at line `line`.
    pub fn err_at(&self, line: u64, msg: impl Into<String>) -> IoError {
        IoError::parse(self.path, Some(Location::Line(line.max(1))), msg)
    }

    /// Makes the next [`next_word`](Self::next_word) return the last word again.
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
                    continue;
                }
                self.word_line = self.line;
            }
            let start = i;
            while i < n && !is_ws(buf[i]) {
                i += 1;
            }
            if self.word.len() + (i - start) > MAX_WORD {
                let line = self.line;
                self.r.consume(i);
                return Err(self.err_at(
                    line,
                    format!("a word longer than {MAX_WORD} bytes (is this a binary file?)"),
                ));
            }
            self.word.extend_from_slice(&buf[start..i]);
            self.r.consume(i);
            if i < n {
                return Ok(true);
            }
        }
    }

    /// The next word, or `None` at the end of the input.
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
    pub fn eof(&self, what: &str) -> IoError {
        self.err_at(
            self.line,
            format!(
                "unexpected end of file: expected {what} (the file is truncated or a count is wrong)"
            ),
        )
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

    /// The rest of the current line (after the last word; the whole next line before any word),
    /// without the terminator, at most [`MAX_WORD`] bytes; the line terminator is consumed.
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
