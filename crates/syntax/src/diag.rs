//! Diagnostics: an error (or warning) at a place in the source, with a hint.
//!
//! Every user-facing error of qdot is a [`Diagnostic`]; [`Diagnostic::render`]
//! prints it with `file:line:column`, the source line and a caret under the
//! offending text.

use std::fmt;

/// Byte range `start..end` into the scene source.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub struct Span {
    /// Byte offset of the first byte.
    pub start: usize,
    /// Byte offset one past the last byte.
    pub end: usize,
}

impl Span {
    /// The span `start..end`.
    pub fn new(start: usize, end: usize) -> Span {
        Span { start, end }
    }
    /// The smallest span covering both.
    pub fn to(self, other: Span) -> Span {
        Span::new(self.start.min(other.start), self.end.max(other.end))
    }
}

/// Whether a [`Diagnostic`] rejects the input or only points at something worth a look.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Severity {
    /// The input is rejected.
    Error,
    /// The input is accepted, but something in it is likely a mistake
    /// (e.g. a load that does no virtual work).
    Warning,
}

/// A message about the input, located by a byte span.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Diagnostic {
    /// Error or warning.
    pub severity: Severity,
    /// Where in the source, if the message is about one place.
    pub span: Option<Span>,
    /// What is wrong, in one sentence.
    pub message: String,
    /// A suggestion for fixing it, when there is one.
    pub hint: Option<String>,
}

impl Diagnostic {
    /// An error at `span`.
    pub fn error(span: Span, message: impl Into<String>) -> Diagnostic {
        Diagnostic {
            severity: Severity::Error,
            span: Some(span),
            message: message.into(),
            hint: None,
        }
    }
    /// An error that is not tied to one place in the source.
    pub fn global(message: impl Into<String>) -> Diagnostic {
        Diagnostic {
            severity: Severity::Error,
            span: None,
            message: message.into(),
            hint: None,
        }
    }
    /// A warning at `span`.
    pub fn warning(span: Span, message: impl Into<String>) -> Diagnostic {
        Diagnostic {
            severity: Severity::Warning,
            span: Some(span),
            message: message.into(),
            hint: None,
        }
    }
    /// The same diagnostic with a hint attached.
    pub fn with_hint(mut self, hint: impl Into<String>) -> Diagnostic {
        self.hint = Some(hint.into());
        self
    }

    /// 1-based (line, column) of a byte offset; columns count characters.
    pub fn line_col(src: &str, offset: usize) -> (usize, usize) {
        LineIndex::new(src).line_col(offset)
    }

    /// Render as
    /// ```text
    /// error: unknown name `x`
    ///  --> scene.qd:3:7
    ///   |
    /// 3 | m = x*2
    ///   |     ^
    ///   = hint: declare it with `parameters x`
    /// ```
    pub fn render(&self, file: &str, src: &str) -> String {
        let kind = match self.severity {
            Severity::Error => "error",
            Severity::Warning => "warning",
        };
        let mut out = format!("{kind}: {}\n", self.message);
        // a span that is not a place in `src` (a diagnostic rendered
        // without its source) is left out, never indexed
        let placed = self
            .span
            .filter(|s| s.start <= src.len() && src.is_char_boundary(s.start));
        if let Some(span) = placed {
            let (line, col) = Diagnostic::line_col(src, span.start);
            let line_start = src[..span.start.min(src.len())]
                .rfind('\n')
                .map(|i| i + 1)
                .unwrap_or(0);
            let line_end = src[line_start..]
                .find('\n')
                .map(|i| line_start + i)
                .unwrap_or(src.len());
            let text: Vec<char> = shown_line(&src[line_start..line_end]).chars().collect();
            let gutter = line.to_string().len();
            let pad = " ".repeat(gutter);
            let end = span.end.clamp(span.start, line_end);
            let width = src
                .get(span.start.min(src.len())..end)
                .map(|s| s.chars().count())
                .unwrap_or(0)
                .max(1);
            let (shown, indent, width) = excerpt_of_line(&text, col - 1, width);
            out.push_str(&format!("{pad}--> {file}:{line}:{col}\n"));
            out.push_str(&format!("{pad} |\n"));
            out.push_str(&format!("{line} | {shown}\n"));
            out.push_str(&format!("{pad} | {indent}{}\n", "^".repeat(width)));
        }
        if let Some(h) = &self.hint {
            out.push_str(&format!("  = hint: {h}\n"));
        }
        out
    }
}

/// The part of a source line shown under a message, the caret's indent and
/// the caret's width, for a caret at character `at` of `width` characters.
/// A line longer than [`LINE_SHOWN`] is cut to a window around the caret,
/// marked with `…`; the indent copies the line's tabs, so the caret stays
/// under its column whatever the terminal's tab stops.
fn excerpt_of_line(text: &[char], at: usize, width: usize) -> (String, String, usize) {
    let at = at.min(text.len());
    let (from, to) = if text.len() <= LINE_SHOWN {
        (0, text.len())
    } else {
        let from = at.saturating_sub(LINE_SHOWN / 3);
        (from, (from + LINE_SHOWN).min(text.len()))
    };
    let mut shown: String = text[from..to].iter().collect();
    let mut indent: String = text[from..at]
        .iter()
        .map(|&c| if c == '\t' { '\t' } else { ' ' })
        .collect();
    if from > 0 {
        shown.insert(0, '…');
        indent.insert(0, ' ');
    }
    if to < text.len() {
        shown.push('…');
    }
    let width = width.min(to.saturating_sub(at)).max(1);
    (shown, indent, width)
}

/// The most characters of a source line shown under a message.
const LINE_SHOWN: usize = 150;

/// A source line as printed under a message: characters that can't be seen
/// or that reorder the display (a zero-width space, a right-to-left
/// override, control characters but the tab) are shown as `�`, one
/// character for one, so the caret stays under its column.
fn shown_line(text: &str) -> String {
    text.chars()
        .map(|c| {
            if crate::unicode::is_hidden(c) {
                '\u{FFFD}'
            } else {
                c
            }
        })
        .collect()
}

/// Why a source file is not text qdot can read. Its `Display` is the
/// whole message to print, ending in a newline.
#[derive(Debug)]
#[non_exhaustive]
pub enum SourceError {
    /// The file could not be read.
    Unreadable {
        /// The path as given.
        path: String,
        /// The system's reason.
        error: std::io::Error,
    },
    /// The file is not UTF-8: the diagnostic at the first byte that is not,
    /// and the text it points into (that byte and the rest of its
    /// character shown as `�`).
    NotUtf8 {
        /// The path as given.
        path: String,
        /// The error, at the first byte that is not UTF-8.
        diagnostic: Box<Diagnostic>,
        /// The file decoded lossily (positions before the byte agree).
        text: String,
    },
}

impl std::fmt::Display for SourceError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            SourceError::Unreadable { path, error } => {
                writeln!(f, "error: cannot read `{path}`: {error}")
            }
            SourceError::NotUtf8 {
                path,
                diagnostic,
                text,
            } => f.write_str(&diagnostic.render(path, text)),
        }
    }
}

impl std::error::Error for SourceError {}

/// The error of an exceeded work budget ([`crate::budget::within`]), at
/// the statement it names.
pub fn too_large(e: &crate::budget::TooLarge) -> Diagnostic {
    let why = match e.measure {
        // the polynomial is small; its factors modulo primes are many
        crate::budget::Measure::Subsets => "a polynomial whose factors modulo every prime are many takes time exponential in their number to factor over ℚ",
        // the terms are few; their numbers are long
        crate::budget::Measure::Digits(_) => "exact numbers this long (a huge or very precise constant, raised to powers by the derivation) make every step slow; a constant in a unit nearer the scene's scale keeps them short",
        _ => "exact expressions this large are rarely what a scene means (expand less, or choose other coordinates)",
    };
    let hint = format!(
        "{why}; to go on, raise the limit: --max-terms {}",
        e.limit.saturating_mul(10)
    );
    match e.context.as_ref().and_then(|c| c.span) {
        Some((a, b)) => Diagnostic::error(Span::new(a, b), e.message()),
        None => Diagnostic::global(e.message()),
    }
    .with_hint(hint)
}

/// Read a source file: its text, or why it can't be read or is not UTF-8
/// (see [`decode_source`]).
pub fn read_source(path: &str) -> Result<String, SourceError> {
    match std::fs::read(path) {
        Ok(bytes) => decode_source(path, bytes),
        Err(error) => Err(SourceError::Unreadable {
            path: path.to_string(),
            error,
        }),
    }
}

/// `bytes` as UTF-8 text, or the diagnostic at the first byte that is
/// not UTF-8 (its line and column; the line shown with `�` for every byte
/// that is not UTF-8). `path` names the file in the message.
pub fn decode_source(path: &str, bytes: Vec<u8>) -> Result<String, SourceError> {
    let e = match String::from_utf8(bytes) {
        Ok(s) => return Ok(s),
        Err(e) => e,
    };
    let at = e.utf8_error().valid_up_to();
    let bytes = e.as_bytes();
    let bad = match e.utf8_error().error_len() {
        Some(n) => &bytes[at..at + n],
        None => &bytes[at..],
    };
    let hex: Vec<String> = bad.iter().map(|b| format!("0x{b:02X}")).collect();
    let message = if bad.len() == 1 {
        format!("the file is not valid UTF-8: byte {} here", hex[0])
    } else {
        format!(
            "the file is not valid UTF-8: bytes {} here (an incomplete character)",
            hex.join(" ")
        )
    };
    let hint = match bad {
        [b] => match latin(*b) {
            Some(c) => format!(
                "save the file as UTF-8 (in Latin-1 or Windows-1252, {} is `{c}`)",
                hex[0]
            ),
            None => "save the file as UTF-8".to_string(),
        },
        _ => "save the file as UTF-8".to_string(),
    };
    // the text before `at` is the same in the lossy copy, so are positions
    let text = String::from_utf8_lossy(bytes).into_owned();
    let diagnostic =
        Diagnostic::error(Span::new(at, at + '\u{FFFD}'.len_utf8()), message).with_hint(hint);
    Err(SourceError::NotUtf8 {
        path: path.to_string(),
        diagnostic: Box::new(diagnostic),
        text,
    })
}

/// The character a byte stands for in Windows-1252 (Latin-1 above 0x9F),
/// for the bytes an editor most often writes in place of UTF-8.
fn latin(b: u8) -> Option<char> {
    match b {
        0xA0..=0xFF => Some(char::from(b)),
        0x80 => Some('€'),
        0x91 => Some('‘'),
        0x92 => Some('’'),
        0x93 => Some('“'),
        0x94 => Some('”'),
        0x96 => Some('–'),
        0x97 => Some('—'),
        _ => None,
    }
}

impl fmt::Display for Diagnostic {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.message)?;
        if let Some(h) = &self.hint {
            write!(f, " (hint: {h})")?;
        }
        Ok(())
    }
}

impl std::error::Error for Diagnostic {}

/// Where a source's lines start, for many (line, column) lookups in one
/// source (one search each, not a scan from the start).
pub struct LineIndex<'a> {
    src: &'a str,
    starts: Vec<usize>,
}

impl<'a> LineIndex<'a> {
    /// The index of `src`'s lines.
    pub fn new(src: &'a str) -> LineIndex<'a> {
        let starts = std::iter::once(0)
            .chain(src.match_indices('\n').map(|(i, _)| i + 1))
            .collect();
        LineIndex { src, starts }
    }

    /// 1-based (line, column) of a byte offset; columns count characters.
    pub fn line_col(&self, offset: usize) -> (usize, usize) {
        let src = self.src;
        let mut off = offset.min(src.len());
        while off > 0 && !src.is_char_boundary(off) {
            off -= 1;
        }
        let line = self.starts.partition_point(|&s| s <= off);
        let line_start = self.starts[line - 1];
        (line, src[line_start..off].chars().count() + 1)
    }
}
