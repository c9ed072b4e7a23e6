//! Diagnostics: an error (or warning) at a place in the source, with a hint.
//!
//! Every user-facing error of qdot is a [`Diagnostic`]; [`Diagnostic::render`]
//! prints it with `file:line:column`, the source line and a caret under the
//! offending text.

use crate::parse::ast::Span;
use std::fmt;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Severity {
    Error,
    Warning,
}

/// A message about the input, located by a byte span.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Diagnostic {
    pub severity: Severity,
    pub span: Option<Span>,
    pub message: String,
    pub hint: Option<String>,
}

impl Diagnostic {
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
    pub fn warning(span: Span, message: impl Into<String>) -> Diagnostic {
        Diagnostic {
            severity: Severity::Warning,
            span: Some(span),
            message: message.into(),
            hint: None,
        }
    }
    pub fn with_hint(mut self, hint: impl Into<String>) -> Diagnostic {
        self.hint = Some(hint.into());
        self
    }

    /// 1-based (line, column) of a byte offset; columns count characters.
    pub fn line_col(src: &str, offset: usize) -> (usize, usize) {
        let offset = offset.min(src.len());
        let mut off = offset;
        while off > 0 && !src.is_char_boundary(off) {
            off -= 1;
        }
        let before = &src[..off];
        let line = before.matches('\n').count() + 1;
        let line_start = before.rfind('\n').map(|i| i + 1).unwrap_or(0);
        let col = src[line_start..off].chars().count() + 1;
        (line, col)
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
        if let Some(span) = self.span {
            let (line, col) = Diagnostic::line_col(src, span.start);
            let line_start = src[..span.start.min(src.len())]
                .rfind('\n')
                .map(|i| i + 1)
                .unwrap_or(0);
            let line_end = src[line_start..]
                .find('\n')
                .map(|i| line_start + i)
                .unwrap_or(src.len());
            let text = &src[line_start..line_end];
            let gutter = line.to_string().len();
            let pad = " ".repeat(gutter);
            let end = span.end.clamp(span.start, line_end);
            let width = src
                .get(span.start.min(src.len())..end)
                .map(|s| s.chars().count())
                .unwrap_or(0)
                .max(1);
            out.push_str(&format!("{pad}--> {file}:{line}:{col}\n"));
            out.push_str(&format!("{pad} |\n"));
            out.push_str(&format!("{line} | {text}\n"));
            out.push_str(&format!(
                "{pad} | {}{}\n",
                " ".repeat(col - 1),
                "^".repeat(width)
            ));
        }
        if let Some(h) = &self.hint {
            out.push_str(&format!("  = hint: {h}\n"));
        }
        out
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
