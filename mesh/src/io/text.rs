//! Line-oriented text parsing with line numbers, shared by the Gmsh and TetGen readers:
//! every failure becomes a [`MeshError::Parse`] that says what was expected where.

use crate::MeshError;
use std::path::Path;

/// Characters of a token shown in a message; a longer one is cut (see [`excerpt`]).
const SHOWN_CHARS: usize = 80;

/// A token of a file or the command line as shown in a message: control and other
/// non-printable characters escaped (`\u{1b}`), the replacement character of invalid UTF-8
/// shown as `\u{fffd}`, and anything longer than 80 characters cut, with an ellipsis and
/// the full length.
pub fn excerpt(text: &str) -> String {
    let escaped = |c: char| -> String {
        if c.is_control() || c == char::REPLACEMENT_CHARACTER || c.is_whitespace() && c != ' ' {
            c.escape_unicode().to_string()
        } else {
            c.to_string()
        }
    };
    let length = text.chars().count();
    let shown: String = text.chars().take(SHOWN_CHARS).map(escaped).collect();
    if length > SHOWN_CHARS {
        format!("{shown}... ({length} characters)")
    } else {
        shown
    }
}

/// The non-blank lines of a file, numbered from 1, with `comment` stripped when given.
pub(crate) struct Lines<'a> {
    path: &'a Path,
    lines: std::iter::Enumerate<std::str::Lines<'a>>,
    comment: Option<char>,
    /// Number of the last line returned (0 before the first).
    pub last: usize,
}

impl<'a> Lines<'a> {
    pub fn new(path: &'a Path, text: &'a str, comment: Option<char>) -> Self {
        Lines {
            path,
            lines: text.lines().enumerate(),
            comment,
            last: 0,
        }
    }

    /// The next non-blank line as `(number, trimmed text)`.
    pub fn next_line(&mut self) -> Option<(usize, &'a str)> {
        for (i, line) in self.lines.by_ref() {
            let line = match self.comment {
                Some(c) => line.split(c).next().unwrap_or(""),
                None => line,
            }
            .trim();
            self.last = i + 1;
            if !line.is_empty() {
                return Some((i + 1, line));
            }
        }
        None
    }

    /// The next non-blank line split into fields, or an "unexpected end of file" error
    /// saying that `what` was expected.
    pub fn fields(&mut self, what: &str) -> Result<Fields<'a>, MeshError> {
        match self.next_line() {
            Some((line, text)) => Ok(Fields::new(self.path, line, text)),
            None => Err(self.eof(what)),
        }
    }

    /// The next non-blank line split into fields, `None` at the end of the file.
    pub fn next_fields(&mut self) -> Option<Fields<'a>> {
        let path = self.path;
        self.next_line()
            .map(|(line, text)| Fields::new(path, line, text))
    }

    /// Like [`Lines::fields`], but a line starting with `$` (a Gmsh section marker) means the
    /// section ended before its declared count.
    pub fn data(&mut self, what: &str) -> Result<Fields<'a>, MeshError> {
        let fields = self.fields(what)?;
        if fields.text.starts_with('$') {
            return Err(fields.error(format!(
                "expected {what}, found `{}`: the section is shorter than its declared count",
                excerpt(fields.text)
            )));
        }
        Ok(fields)
    }

    /// "Unexpected end of file" after the last line read.
    pub fn eof(&self, what: &str) -> MeshError {
        MeshError::parse(
            self.path,
            self.last + 1,
            format!("unexpected end of file: expected {what}"),
        )
    }

    /// An error at line `line` of this file.
    pub fn error(&self, line: usize, message: impl Into<String>) -> MeshError {
        MeshError::parse(self.path, line, message)
    }
}

/// The whitespace-separated fields of one line.
pub(crate) struct Fields<'a> {
    path: &'a Path,
    pub line: usize,
    pub text: &'a str,
    tokens: std::str::SplitWhitespace<'a>,
}

impl<'a> Fields<'a> {
    fn new(path: &'a Path, line: usize, text: &'a str) -> Self {
        Fields {
            path,
            line,
            text,
            tokens: text.split_whitespace(),
        }
    }

    /// An error at this line.
    pub fn error(&self, message: impl Into<String>) -> MeshError {
        MeshError::parse(self.path, self.line, message)
    }

    fn token(&mut self, what: &str) -> Result<&'a str, MeshError> {
        self.tokens
            .next()
            .ok_or_else(|| self.error(format!("expected {what}, found end of line")))
    }

    /// The next field as it is, `None` at the end of the line.
    pub fn word(&mut self) -> Option<&'a str> {
        self.tokens.next()
    }

    /// The next field as a non-negative integer.
    pub fn usize(&mut self, what: &str) -> Result<usize, MeshError> {
        let t = self.token(what)?;
        t.parse().map_err(|_| {
            self.error(format!(
                "expected {what} (a non-negative integer), found `{}`",
                excerpt(t)
            ))
        })
    }

    /// The next field as an integer of either sign.
    pub fn i64(&mut self, what: &str) -> Result<i64, MeshError> {
        let t = self.token(what)?;
        t.parse().map_err(|_| {
            self.error(format!(
                "expected {what} (an integer), found `{}`",
                excerpt(t)
            ))
        })
    }

    /// The next field as a finite real number.
    pub fn f64(&mut self, what: &str) -> Result<f64, MeshError> {
        let t = self.token(what)?;
        match t.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(v),
            Ok(_) => Err(self.error(format!("expected a finite {what}, found `{}`", excerpt(t)))),
            Err(_) => Err(self.error(format!(
                "expected {what} (a number), found `{}`",
                excerpt(t)
            ))),
        }
    }

    /// Skips `n` fields that must be present.
    pub fn skip(&mut self, n: usize, what: &str) -> Result<(), MeshError> {
        for _ in 0..n {
            self.token(what)?;
        }
        Ok(())
    }

    /// Number of fields not yet read.
    pub fn remaining(&self) -> usize {
        self.tokens.clone().count()
    }

    /// Fails if fields remain: the line holds more than `what`.
    pub fn end(&self, what: &str) -> Result<(), MeshError> {
        match self.remaining() {
            0 => Ok(()),
            n => Err(self.error(format!("{n} unexpected extra field(s) after {what}"))),
        }
    }
}
