//! The parser of `.qd` scenes.
//!
//! The grammar is `grammar/qd.ebnf`; every rule there has one method here,
//! named after the rule and documented with it. The parser works on `&str`
//! in nom 8's style (every rule maps the remaining input to an
//! [`nom::IResult`]); spans are byte offsets into the source, computed from
//! the length of the remaining input.
//!
//! The rules scan their tokens byte by byte (white space, comments, names and
//! numbers are the hot path), numbers that fit are computed with machine
//! integers, and nothing but the syntax tree is allocated unless an error is
//! returned: messages and hints are built only on the error paths, which are
//! kept out of line.
//!
//! The files: `lexer` (character classes, white space, names), `number`
//! (literals and their exact values), `expressions` and `statements` (the
//! rules, as methods of `Parser`), `failure` (the error type threaded
//! through the rules), `chars` (messages about characters) and `keywords`
//! (the one keyword table).
//!
//! Two limits keep hostile input from exhausting the stack:
//! [`MAX_NESTING`] bounds the recursion of the parser (parentheses, call
//! arguments, chains of unary signs and of `^`), and [`MAX_DEPTH`] bounds the
//! depth of the produced tree (so long `a + b + c + …` chains, which are parsed
//! by a loop, cannot build a tree too deep to drop or to walk recursively).

// `ast.rs` is kept byte-identical to the main repository's copy; default
// rustfmt would re-wrap its `Stmt::Def` variant, so it is not formatted here.
#[rustfmt::skip]
pub mod ast;
mod assume;
mod bodies;
mod chars;
mod constraint;
mod expressions;
mod failure;
pub mod functions;
mod joints;
pub mod keywords;
mod lexer;
mod number;
mod statements;

pub use crate::unicode::is_hidden;

use std::cell::Cell;

use nom::error::{ErrorKind, ParseError};
use nom::IResult;
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Zero};

use crate::diag::Diagnostic;
use ast::{BinOp, Callee, Decl, Equation, Expr, ExprKind, Ident, Role, SolveBlock, Span, Stmt};
use failure::*;
use lexer::*;

pub use crate::limits::MAX_PARSE_NESTING as MAX_NESTING;

pub use crate::limits::MAX_TREE_DEPTH as MAX_DEPTH;

pub use crate::limits::MAX_DECIMAL_EXPONENT as MAX_EXPONENT;

/// Parse a whole scene. Every error is of kind [`crate::diag::ErrorKind::Syntax`].
pub fn parse_scene(src: &str) -> Result<Vec<Stmt>, Diagnostic> {
    parse_scene_text(src).map_err(|d| d.with_kind(crate::diag::ErrorKind::Syntax))
}

fn parse_scene_text(src: &str) -> Result<Vec<Stmt>, Diagnostic> {
    chars::no_bidi_control(src)?;
    let p = Parser::new(src);
    match p.scene(src) {
        Ok((_, stmts)) => Ok(stmts),
        Err(e) => Err(p.finish(e)),
    }
}

/// Parse a string that must hold exactly one expression (surrounding white
/// space, newlines and comments are allowed; newlines are white space
/// throughout, as inside parentheses). Every error is of kind
/// [`crate::diag::ErrorKind::Syntax`].
pub fn parse_expr(src: &str) -> Result<Expr, Diagnostic> {
    parse_expr_text(src).map_err(|d| d.with_kind(crate::diag::ErrorKind::Syntax))
}

fn parse_expr_text(src: &str) -> Result<Expr, Diagnostic> {
    chars::no_bidi_control(src)?;
    let p = Parser::new(src);
    match p.whole_expr(src) {
        Ok((_, node)) => Ok(*node.e),
        Err(nom::Err::Error(_)) => {
            let d = p.expected(p.ws_nl(src), "an expression", HINT_EXPR, None);
            Err(p.finish(failure(d)))
        }
        Err(e) => Err(p.finish(e)),
    }
}

/// An expression together with the depth of its tree. The expression is
/// boxed so that parse results stay small on the stack (the recursive rules
/// pass them around at every nesting level) and move into parents for free.
///
/// `outer` is the source text the operand came from: the node's own span
/// widened by enclosing parentheses and leading unary `+` signs (which leave
/// no node). Parents take their spans from the `outer` spans of their
/// children, so `(a+b)*c` spans from `(` while the sum inside keeps the
/// precise span `a+b`.
pub(super) struct Node {
    e: Box<Expr>,
    d: u32,
    outer: Span,
}

/// Decrements a counter when dropped (on success and on error alike).
pub(super) struct Guard<'a>(&'a Cell<u32>);

impl Drop for Guard<'_> {
    fn drop(&mut self) {
        self.0.set(self.0.get() - 1);
    }
}

// ---------------------------------------------------------------------------
// The parser

/// Parser state: the source (for offsets), the recursion depth, the
/// number of open parentheses and brackets (inside them a newline is white
/// space), and whether a stop word (`at`, `on`) ends the expression being
/// parsed (the first expression of a `load` or `torque` statement).
struct Parser<'s> {
    src: &'s str,
    nest: Cell<u32>,
    parens: Cell<u32>,
    stop: Cell<bool>,
}

impl<'s> Parser<'s> {
    fn new(src: &'s str) -> Self {
        Parser {
            src,
            nest: Cell::new(0),
            parens: Cell::new(0),
            stop: Cell::new(false),
        }
    }

    // ----- positions and error helpers ------------------------------------

    /// Byte offset of a remaining input.
    fn pos(&self, i: &str) -> usize {
        self.src.len() - i.len()
    }

    fn span(&self, from: &str, to: &str) -> Span {
        Span::new(self.pos(from), self.pos(to))
    }

    fn fail<T>(&self, d: Diagnostic) -> RuleResult<'s, T> {
        Err(failure(d))
    }

    fn nothing<T>(&self, i: &'s str) -> RuleResult<'s, T> {
        Err(nom::Err::Error(RuleError::At(i.len())))
    }

    /// The token at `i`, for messages: its span and how to name it.
    fn token(&self, i: &str) -> (Span, String) {
        let p = self.pos(i);
        let Some(c) = first(i) else {
            return (Span::new(p, p), "the end of the file".into());
        };
        if c == '\n' {
            return (Span::new(p, p), "the end of the line".into());
        }
        let len = if ident_start(c) {
            i.find(|c: char| !ident_char(c)).unwrap_or(i.len())
        } else if c.is_ascii_digit() {
            i.find(|c: char| !(c.is_ascii_digit() || c == '.'))
                .unwrap_or(i.len())
        } else {
            c.len_utf8()
        };
        let text = &i[..len];
        let shown = if c.is_control() {
            format!("the character `{}`", show_char(c))
        } else {
            format!("`{text}`")
        };
        (Span::new(p, p + len), shown)
    }

    /// A diagnostic for a token that has no place at `i`.
    fn unexpected(&self, i: &str) -> Diagnostic {
        let (span, shown) = self.token(i);
        let Some(c) = first(i) else {
            return Diagnostic::error(span, "unexpected end of the file")
                .with_hint("the statement is incomplete")
                .with_kind(crate::diag::ErrorKind::Syntax);
        };
        let (msg, hint) = chars::unexpected(c, &shown);
        Diagnostic::error(span, msg)
            .with_hint(hint)
            .with_kind(crate::diag::ErrorKind::Syntax)
    }

    /// "expected WHAT, found …" at `i`. For the end of the file, `anchor`
    /// (e.g. the span of a trailing operator) is pointed at if given.
    fn expected(&self, i: &str, what: &str, hint: &str, anchor: Option<Span>) -> Diagnostic {
        let (span, shown) = self.token(i);
        match first(i) {
            None => Diagnostic::error(
                anchor.unwrap_or(span),
                format!("expected {what}, but the file ends"),
            )
            .with_hint(hint)
            .with_kind(crate::diag::ErrorKind::Syntax),
            Some('\n') => Diagnostic::error(span, format!("expected {what}, but the line ends"))
                .with_hint(hint)
                .with_kind(crate::diag::ErrorKind::Syntax),
            Some(c) if !is_known(c) => self.unexpected(i),
            Some(_) => Diagnostic::error(span, format!("expected {what}, found {shown}"))
                .with_hint(hint)
                .with_kind(crate::diag::ErrorKind::Syntax),
        }
    }

    /// The error for the operand after operator `op` (at `at`): a
    /// recoverable "nothing here" becomes "expected an expression after …".
    #[cold]
    #[inline(never)]
    fn op_error(
        &self,
        e: nom::Err<RuleError>,
        at: &'s str,
        op: &str,
        op_span: Span,
    ) -> nom::Err<RuleError> {
        match e {
            nom::Err::Error(_) => {
                let at = self.ws(at);
                let hint = if at.is_empty() {
                    format!("complete the expression or remove the trailing `{op}`")
                } else {
                    HINT_EXPR.to_string()
                };
                failure(self.expected(
                    at,
                    &format!("an expression after `{op}`"),
                    &hint,
                    Some(op_span),
                ))
            }
            other => other,
        }
    }

    /// Enter one level of recursion; errors past [`MAX_NESTING`].
    #[inline]
    fn enter(&self, i: &'s str) -> Result<Guard<'_>, nom::Err<RuleError>> {
        let n = self.nest.get() + 1;
        if n > MAX_NESTING {
            return Err(self.too_nested(i));
        }
        self.nest.set(n);
        Ok(Guard(&self.nest))
    }

    /// [`Parser::enter`] at the token after the white space at `i`.
    #[inline]
    fn enter_ws(&self, i: &'s str) -> Result<Guard<'_>, nom::Err<RuleError>> {
        let n = self.nest.get() + 1;
        if n > MAX_NESTING {
            return Err(self.too_nested(self.ws(i)));
        }
        self.nest.set(n);
        Ok(Guard(&self.nest))
    }

    /// The error past [`MAX_NESTING`], at the token `i`.
    #[cold]
    #[inline(never)]
    fn too_nested(&self, i: &'s str) -> nom::Err<RuleError> {
        let (span, _) = self.token(i);
        failure(
            Diagnostic::error(
                span,
                format!("expression nested too deeply (more than {MAX_NESTING} levels)"),
            )
            .with_hint("split it into several named definitions")
            .with_kind(crate::diag::ErrorKind::Syntax),
        )
    }

    /// Note one more open parenthesis (or bracket) until the guard is
    /// dropped.
    fn open_paren(&self) -> Guard<'_> {
        self.parens.set(self.parens.get() + 1);
        Guard(&self.parens)
    }

    /// Is a stop word active here: in the first expression of a `load` or
    /// `torque` statement, outside parentheses, brackets and calls?
    #[inline]
    fn stopping(&self) -> bool {
        self.stop.get() && self.parens.get() == 0
    }

    /// A leaf node (depth 1).
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn leaf(kind: ExprKind, span: Span) -> Node {
        Node {
            e: Box::new(Expr { kind, span }),
            d: 1,
            outer: span,
        }
    }

    /// Build an inner node of depth `d`, refusing trees deeper than
    /// [`MAX_DEPTH`]; the error points at `at` (the operator or operand that
    /// went too deep).
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn node(
        &self,
        kind: ExprKind,
        span: Span,
        d: u32,
        at: Span,
    ) -> Result<Node, nom::Err<RuleError>> {
        if d > MAX_DEPTH {
            return Err(too_deep(at));
        }
        Ok(Node {
            e: Box::new(Expr { kind, span }),
            d,
            outer: span,
        })
    }

    #[cfg_attr(not(debug_assertions), inline(always))]
    fn bin(&self, op: BinOp, l: Node, r: Node) -> Result<Node, nom::Err<RuleError>> {
        let span = l.outer.to(r.outer);
        let d = l.d.max(r.d) + 1;
        let at = r.outer;
        self.node(ExprKind::Bin(op, l.e, r.e), span, d, at)
    }

    /// Final conversion of a parse error into a diagnostic. If a `(`, `[`
    /// or `{` left open before the error swallowed a line break (or the file
    /// ended inside it), the open bracket is the real problem and is reported
    /// instead.
    fn finish(&self, e: nom::Err<RuleError>) -> Diagnostic {
        let d = match e {
            nom::Err::Error(RuleError::At(n)) | nom::Err::Failure(RuleError::At(n)) => {
                let at = self.src.len().saturating_sub(n);
                self.unexpected(&self.src[at..])
            }
            nom::Err::Error(RuleError::Diag(d)) | nom::Err::Failure(RuleError::Diag(d)) => *d,
            nom::Err::Incomplete(_) => {
                Diagnostic::global("incomplete input").with_kind(crate::diag::ErrorKind::Syntax)
            }
        };
        let Some(span) = d.span else { return d };
        if let Some((open, c)) = unclosed_before(self.src, span.start) {
            let swallowed = self.src[open..span.start.min(self.src.len())].contains('\n')
                || span.start >= self.src.len();
            if swallowed && !d.message.starts_with("unclosed `") {
                let hint = match c {
                    b'(' => "add the matching `)`; inside parentheses a line break does not end the statement",
                    b'[' => "add the matching `]`; inside brackets a line break does not end the statement",
                    _ => HINT_UNCLOSED_BLOCK,
                };
                let msg = format!("unclosed `{}`", char::from(c));
                return Diagnostic::error(Span::new(open, open + 1), msg)
                    .with_hint(hint)
                    .with_kind(crate::diag::ErrorKind::Syntax);
            }
        }
        d
    }

    // ----- white space -------------------------------------------------------

    /// `space ::= ( #x20 | #x09 | #x0D | #xFEFF | OtherWhiteSpace )+`
    fn space(i: &'s str) -> RuleResult<'s, &'s str> {
        let rest = i.trim_start_matches(is_space);
        if rest.len() == i.len() {
            return Err(nom::Err::Error(RuleError::At(i.len())));
        }
        Ok((rest, &i[..i.len() - rest.len()]))
    }

    /// `comment ::= "#" [^#x0A]*`
    #[inline]
    fn comment(i: &'s str) -> RuleResult<'s, &'s str> {
        if !i.starts_with('#') {
            return Err(nom::Err::Error(RuleError::At(i.len())));
        }
        let len = i.find('\n').unwrap_or(i.len());
        Ok((&i[len..], &i[..len]))
    }

    /// `newline ::= #x0A`
    fn newline(i: &'s str) -> RuleResult<'s, &'s str> {
        match i.strip_prefix('\n') {
            Some(rest) => Ok((rest, &i[..1])),
            None => Err(nom::Err::Error(RuleError::At(i.len()))),
        }
    }

    /// `ws ::= ( space | comment )*` — inside parentheses, `ws_nl`.
    ///
    /// Scanned byte by byte (see [`skip_ws`]); this is the hottest rule.
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn ws(&self, i: &'s str) -> &'s str {
        skip_ws(i, self.parens.get() > 0)
    }

    /// `ws_nl ::= ( space | comment | newline )*`
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn ws_nl(&self, i: &'s str) -> &'s str {
        skip_ws(i, true)
    }

    // ----- scene structure ---------------------------------------------------
}
