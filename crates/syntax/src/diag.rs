//! Diagnostics: an error (or warning) at a place in the source, with a hint.
//!
//! Every user-facing error of qdot is a [`Diagnostic`]; [`Diagnostic::render`]
//! prints it with `file:line:column`, the source line and a caret under the
//! offending text, and under it the places its [`Label`]s point at. Its
//! [`ErrorKind`] says what class of error it is, for a program to match;
//! [`Diagnostic::to_json`] is the object `--format json` prints.

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

/// What class of error a [`Diagnostic`] is, for a program to match on
/// (the message is for people and may be reworded). New classes may come:
/// match with a `_` arm.
#[derive(Clone, Debug, PartialEq, Eq, Default)]
#[non_exhaustive]
pub enum ErrorKind {
    /// The text does not parse: the parser's errors.
    Syntax,
    /// A name, function or dimension the scene does not know.
    UnknownName {
        /// The name as written.
        name: String,
    },
    /// A name declared or given twice; the first place is a label.
    DuplicateName {
        /// The name.
        name: String,
    },
    /// A term whose dimension is not the one needed there.
    DimensionMismatch,
    /// A linear system without a unique solution: the mass matrix, the
    /// momenta's velocities, a `solve` block, the modes' amplitudes.
    SingularSystem {
        /// The names of the unknowns (coordinates, velocities, `solve`
        /// unknowns) that the system leaves undetermined; empty where the
        /// system has no named unknowns (a matrix found singular).
        unknowns: Vec<String>,
    },
    /// The work budget (`--max-terms`) was exceeded.
    TooLarge {
        /// What passed the budget.
        measure: crate::budget::Measure,
    },
    /// A file that cannot be read.
    UnreadableFile {
        /// The path as given.
        path: String,
    },
    /// A file that is not UTF-8.
    NotUtf8 {
        /// The path as given.
        path: String,
    },
    /// A command-line option with a value qdot cannot use.
    BadOption {
        /// The option, `--set`.
        option: String,
    },
    /// A scene with nothing the command can work on (no coordinates).
    NothingToSolve,
    /// Constraints that are redundant or contradict each other.
    Constraints,
    /// A numeric integration that stopped before its end.
    Integration,
    /// A value of the wrong sort where it is used: a vector where a number
    /// is needed, a rotation in arithmetic, vectors of different sizes, a
    /// point with 3 components in a planar joint.
    TypeMismatch,
    /// A statement that reads, and that the scene's rules refuse: a body
    /// without a mass or an orientation, a constant that moves with time,
    /// a definition that uses itself, a function given the wrong number
    /// of arguments, a name used as what it is not.
    InvalidScene,
    /// A value physics rules out: a negative mass or moment of inertia, an
    /// inertia matrix that is not symmetric positive semidefinite, an
    /// `assume` fact false for the parameters as declared, a mass matrix
    /// not positive definite at the `--set` values.
    Unphysical,
    /// An operation undefined for its operands, or not known to be
    /// defined: division by zero, the square root or logarithm of a
    /// negative number, a division by a quantity whose sign is undecided.
    Undefined,
    /// A limit of qdot's ([`crate::limits`]) passed in a scene that reads:
    /// too many equilibrium cases, a derivative of too high an order,
    /// functions nested too deep. Not the work budget (that is
    /// [`ErrorKind::TooLarge`]), and not the parser's limits (digits,
    /// nesting of the text: those are [`ErrorKind::Syntax`]).
    LimitExceeded,
    /// Something qdot does not do, said with the reason: symbolic powers,
    /// the complex modes of a gyroscopic system, steady motions with
    /// constraints, a structured scene where an expanded one is needed.
    Unsupported,
    /// An exact answer that exists in general but not in closed form here
    /// (the equilibria, the steady motions, the accelerations with
    /// Coulomb friction, the Legendre transform): parameter values
    /// (`--set`) or a numeric command may give one.
    NoClosedForm,
    /// No equilibrium or steady motion where one was asked for: a force
    /// that depends on time, a position (`--at`) that is not one, a rate
    /// no real number satisfies.
    NoEquilibrium,
    /// A numeric computation without a certified finite answer (not
    /// converged, or not finite at the values given).
    Convergence,
    /// An invariant of the engine that does not hold: a bug in qdot, or a
    /// library call outside the context the engine needs (the scene's
    /// assumptions not in force: run it through `qdot::app` or
    /// `Scene::assumptions_in_force`).
    Internal,
    /// Every other error (and every warning).
    #[default]
    Other,
}

impl ErrorKind {
    /// [`ErrorKind::BadOption`] of `option` (`"--set"`).
    pub fn bad_option(option: &str) -> ErrorKind {
        ErrorKind::BadOption {
            option: option.to_string(),
        }
    }

    /// The kind's data in `--format json`: `{"name"}` of an unknown or
    /// duplicate name, `{"unknowns"}` of a singular system, `{"measure"}`
    /// of an exceeded budget, `{"path"}` of a file, `{"option"}` of a bad
    /// option value; `{}` for the kinds without data.
    pub fn data(&self) -> serde_json::Value {
        use crate::budget::Measure;
        match self {
            ErrorKind::UnknownName { name } | ErrorKind::DuplicateName { name } => {
                serde_json::json!({ "name": name })
            }
            ErrorKind::SingularSystem { unknowns } => serde_json::json!({ "unknowns": unknowns }),
            ErrorKind::TooLarge { measure } => serde_json::json!({
                "measure": match measure {
                    Measure::Terms => "terms",
                    Measure::Product(..) => "product",
                    Measure::Printed => "printed",
                    Measure::Work | Measure::Built => "work",
                    Measure::Subsets => "subsets",
                    Measure::Division(..) => "division",
                    Measure::Digits(..) => "digits",
                }
            }),
            ErrorKind::UnreadableFile { path } | ErrorKind::NotUtf8 { path } => {
                serde_json::json!({ "path": path })
            }
            ErrorKind::BadOption { option } => serde_json::json!({ "option": option }),
            ErrorKind::Syntax
            | ErrorKind::DimensionMismatch
            | ErrorKind::NothingToSolve
            | ErrorKind::Constraints
            | ErrorKind::Integration
            | ErrorKind::TypeMismatch
            | ErrorKind::InvalidScene
            | ErrorKind::Unphysical
            | ErrorKind::Undefined
            | ErrorKind::LimitExceeded
            | ErrorKind::Unsupported
            | ErrorKind::NoClosedForm
            | ErrorKind::NoEquilibrium
            | ErrorKind::Convergence
            | ErrorKind::Internal
            | ErrorKind::Other => serde_json::json!({}),
        }
    }

    /// The kind's name in `--format json` (`"unknown_name"`).
    pub fn name(&self) -> &'static str {
        match self {
            ErrorKind::Syntax => "syntax",
            ErrorKind::UnknownName { .. } => "unknown_name",
            ErrorKind::DuplicateName { .. } => "duplicate_name",
            ErrorKind::DimensionMismatch => "dimension_mismatch",
            ErrorKind::SingularSystem { .. } => "singular_system",
            ErrorKind::TooLarge { .. } => "too_large",
            ErrorKind::UnreadableFile { .. } => "unreadable_file",
            ErrorKind::NotUtf8 { .. } => "not_utf8",
            ErrorKind::BadOption { .. } => "bad_option",
            ErrorKind::NothingToSolve => "nothing_to_solve",
            ErrorKind::Constraints => "constraints",
            ErrorKind::Integration => "integration",
            ErrorKind::TypeMismatch => "type_mismatch",
            ErrorKind::InvalidScene => "invalid_scene",
            ErrorKind::Unphysical => "unphysical",
            ErrorKind::Undefined => "undefined",
            ErrorKind::LimitExceeded => "limit_exceeded",
            ErrorKind::Unsupported => "unsupported",
            ErrorKind::NoClosedForm => "no_closed_form",
            ErrorKind::NoEquilibrium => "no_equilibrium",
            ErrorKind::Convergence => "convergence",
            ErrorKind::Internal => "internal",
            ErrorKind::Other => "other",
        }
    }
}

/// A second place a [`Diagnostic`] points at (where the other side's
/// dimension comes from, a name's first declaration), with what it is.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Label {
    /// The place in the source.
    pub span: Span,
    /// What is there, in a few words.
    pub message: String,
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
    /// The class of error, for a program to match (boxed: a
    /// `Result<_, Diagnostic>` stays small).
    pub kind: Box<ErrorKind>,
    /// Other places that matter, shown under the main one.
    pub labels: Vec<Label>,
}

impl Diagnostic {
    /// An error at `span`.
    pub fn error(span: Span, message: impl Into<String>) -> Diagnostic {
        Diagnostic {
            severity: Severity::Error,
            span: Some(span),
            message: message.into(),
            hint: None,
            kind: Box::default(),
            labels: Vec::new(),
        }
    }
    /// An error that is not tied to one place in the source.
    pub fn global(message: impl Into<String>) -> Diagnostic {
        Diagnostic {
            severity: Severity::Error,
            span: None,
            message: message.into(),
            hint: None,
            kind: Box::default(),
            labels: Vec::new(),
        }
    }
    /// A warning at `span`.
    pub fn warning(span: Span, message: impl Into<String>) -> Diagnostic {
        Diagnostic {
            severity: Severity::Warning,
            span: Some(span),
            message: message.into(),
            hint: None,
            kind: Box::default(),
            labels: Vec::new(),
        }
    }
    /// A warning that is not tied to one place in the source.
    pub fn global_warning(message: impl Into<String>) -> Diagnostic {
        Diagnostic {
            severity: Severity::Warning,
            span: None,
            message: message.into(),
            hint: None,
            kind: Box::default(),
            labels: Vec::new(),
        }
    }
    /// The same diagnostic with a hint attached.
    pub fn with_hint(mut self, hint: impl Into<String>) -> Diagnostic {
        self.hint = Some(hint.into());
        self
    }
    /// The same diagnostic of class `kind`.
    pub fn with_kind(mut self, kind: ErrorKind) -> Diagnostic {
        *self.kind = kind;
        self
    }
    /// The same diagnostic pointing also at `span`, with what is there.
    pub fn with_label(mut self, span: Span, message: impl Into<String>) -> Diagnostic {
        self.labels.push(Label {
            span,
            message: message.into(),
        });
        self
    }
    /// The class of error, for a program to match.
    pub fn kind(&self) -> &ErrorKind {
        &self.kind
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
        self.render_from(file, src, 1)
    }

    /// [`render`](Self::render) for a `src` that starts at line
    /// `first_line` of `file` (an entry of a script read line by line): the
    /// lines shown are numbered as in the file.
    pub fn render_from(&self, file: &str, src: &str, first_line: usize) -> String {
        let at = |c: Caret| Caret {
            line: c.line + first_line.max(1) - 1,
            ..c
        };
        let kind = match self.severity {
            Severity::Error => "error",
            Severity::Warning => "warning",
        };
        let mut out = format!("{kind}: {}\n", self.message);
        if let Some(main) = self.span.and_then(|s| Caret::of(src, s)).map(at) {
            let labels: Vec<(Caret, &str)> = self
                .labels
                .iter()
                .filter_map(|l| Caret::of(src, l.span).map(|c| (at(c), l.message.as_str())))
                .collect();
            let widest = labels
                .iter()
                .map(|(c, _)| c.line)
                .fold(main.line, usize::max);
            let gutter = widest.to_string().len();
            let pad = " ".repeat(gutter);
            out.push_str(&format!("{pad}--> {file}:{}:{}\n", main.line, main.column));
            out.push_str(&format!("{pad} |\n"));
            out.push_str(&main.excerpt(gutter));
            out.push_str(&format!(
                "{pad} | {}{}\n",
                main.indent,
                "^".repeat(main.width)
            ));
            // a label on the line shown last goes under the same copy of it
            let mut shown = main.whole_line.then_some(main.line);
            for (c, message) in labels {
                if !(c.whole_line && shown == Some(c.line)) {
                    out.push_str(&format!("{pad} |\n"));
                    out.push_str(&c.excerpt(gutter));
                    shown = c.whole_line.then_some(c.line);
                }
                out.push_str(&format!(
                    "{pad} | {}{} {message}\n",
                    c.indent,
                    "-".repeat(c.width)
                ));
            }
        }
        if let Some(h) = &self.hint {
            out.push_str(&format!("  = hint: {h}\n"));
        }
        out
    }

    /// The diagnostic as one line of JSON, the object `--format json`
    /// prints on stderr: `{"error": {"kind", "message", "line", "column",
    /// "hint", "labels": [{"line", "column", "message"}]}}` (`"warning"`
    /// for a warning); line and column 1-based as in the text, `null` for
    /// a diagnostic not tied to a place in `src`.
    pub fn to_json(&self, src: &str) -> String {
        let index = LineIndex::new(src);
        let place = |span: Option<Span>| match span.filter(|&s| is_place(src, s)) {
            Some(s) => {
                let (line, column) = index.line_col(s.start);
                (serde_json::json!(line), serde_json::json!(column))
            }
            None => (serde_json::Value::Null, serde_json::Value::Null),
        };
        let (line, column) = place(self.span);
        let labels: Vec<serde_json::Value> = self
            .labels
            .iter()
            .map(|l| {
                let (line, column) = place(Some(l.span));
                serde_json::json!({"line": line, "column": column, "message": l.message})
            })
            .collect();
        let severity = match self.severity {
            Severity::Error => "error",
            Severity::Warning => "warning",
        };
        serde_json::json!({
            severity: {
                "kind": self.kind.name(),
                "data": self.kind.data(),
                "message": self.message,
                "line": line,
                "column": column,
                "hint": self.hint,
                "labels": labels,
            }
        })
        .to_string()
    }
}

/// Whether `span` starts at a place in `src` (a diagnostic shown with
/// another source, or none, has spans that are not).
fn is_place(src: &str, span: Span) -> bool {
    span.start <= src.len() && src.is_char_boundary(span.start)
}

/// A caret under a span of the source: the line it is on, as shown.
struct Caret {
    /// 1-based line and column (in characters) of the span's start.
    line: usize,
    column: usize,
    /// The line as shown (cut to a window around the caret when long).
    shown: String,
    /// What goes before the caret, under the shown line.
    indent: String,
    /// The caret's width in characters.
    width: usize,
    /// Whether `shown` is the whole line (no window): then carets of
    /// several spans of it can go under one copy.
    whole_line: bool,
}

impl Caret {
    /// The caret under `span`, or `None` for a span that is not a place in
    /// `src` (a diagnostic rendered without its source is left out, never
    /// indexed).
    fn of(src: &str, span: Span) -> Option<Caret> {
        if !is_place(src, span) {
            return None;
        }
        let (line, column) = Diagnostic::line_col(src, span.start);
        let line_start = src[..span.start].rfind('\n').map(|i| i + 1).unwrap_or(0);
        let line_end = src[line_start..]
            .find('\n')
            .map(|i| line_start + i)
            .unwrap_or(src.len());
        let text: Vec<char> = shown_line(&src[line_start..line_end]).chars().collect();
        let end = span.end.clamp(span.start, line_end);
        let width = src
            .get(span.start..end)
            .map(|s| s.chars().count())
            .unwrap_or(0)
            .max(1);
        let whole_line = text.len() <= LINE_SHOWN;
        let (shown, indent, width) = excerpt_of_line(&text, column - 1, width);
        Some(Caret {
            line,
            column,
            shown,
            indent,
            width,
            whole_line,
        })
    }

    /// `3 | m = x*2`, the line number right-aligned in `gutter` columns.
    fn excerpt(&self, gutter: usize) -> String {
        format!("{:>gutter$} | {}\n", self.line, self.shown)
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

impl SourceError {
    /// The error as a diagnostic (of kind [`ErrorKind::UnreadableFile`] or
    /// [`ErrorKind::NotUtf8`]) and the text its span points into.
    pub fn diagnostic(&self) -> (Diagnostic, &str) {
        match self {
            SourceError::Unreadable { path, error } => (
                Diagnostic::global(format!("cannot read `{path}`: {error}"))
                    .with_kind(ErrorKind::UnreadableFile { path: path.clone() }),
                "",
            ),
            SourceError::NotUtf8 {
                diagnostic, text, ..
            } => ((**diagnostic).clone(), text),
        }
    }
}

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
    let kind = ErrorKind::TooLarge { measure: e.measure };
    match e.context.as_ref().and_then(|c| c.span) {
        Some((a, b)) => Diagnostic::error(Span::new(a, b), e.message()).with_kind(kind),
        None => Diagnostic::global(e.message()).with_kind(kind),
    }
    .with_hint(hint)
}

/// Run `f` within the work budget in force, or the default one where none
/// is installed ([`crate::budget::bounded`]); past it, the error of
/// [`too_large`]. The library's entry points run so.
pub fn bounded<T>(f: impl FnOnce() -> Result<T, Diagnostic>) -> Result<T, Diagnostic> {
    crate::budget::bounded(f, |e| too_large(&e))
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
    let diagnostic = Diagnostic::error(Span::new(at, at + '\u{FFFD}'.len_utf8()), message)
        .with_hint(hint)
        .with_kind(ErrorKind::NotUtf8 {
            path: path.to_string(),
        });
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
