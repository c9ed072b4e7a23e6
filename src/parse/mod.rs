//! The parser of `.qd` scenes.
//!
//! The grammar is `grammar/qd.ebnf`; every rule there has one method here,
//! named after the rule and documented with it. The parser works on `&str`
//! with nom 8 combinators; spans are byte offsets into the source, computed
//! from the length of the remaining input.
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

use std::cell::Cell;

use nom::branch::alt;
use nom::bytes::complete::{tag, take_till, take_while, take_while1};
use nom::character::complete::{char, digit1, one_of, satisfy};
use nom::combinator::{opt, recognize};
use nom::error::{ErrorKind, ParseError};
use nom::multi::many0_count;
use nom::sequence::preceded;
use nom::{IResult, Parser};
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Zero};

use crate::diag::Diagnostic;
use ast::{BinOp, Decl, Expr, ExprKind, Ident, Role, Span, Stmt};

/// Deepest recursion of the parser: parentheses, call arguments, unary signs
/// and `^` chains each count one level.
pub const MAX_NESTING: u32 = 200;

/// Deepest expression tree the parser builds (a leaf has depth 1).
pub const MAX_DEPTH: u32 = 1000;

/// Largest `|n|` accepted in a scientific exponent `…e±n`.
pub const MAX_EXPONENT: u32 = 1000;

/// Parse a whole scene.
pub fn parse_scene(src: &str) -> Result<Vec<Stmt>, Diagnostic> {
    let p = P::new(src);
    match p.scene(src) {
        Ok((_, stmts)) => Ok(stmts),
        Err(e) => Err(p.finish(e)),
    }
}

/// Parse a string that must hold exactly one expression (surrounding white
/// space, newlines and comments are allowed; newlines are white space
/// throughout, as inside parentheses).
pub fn parse_expr(src: &str) -> Result<Expr, Diagnostic> {
    let p = P::new(src);
    match p.whole_expr(src) {
        Ok((_, node)) => Ok(*node.e),
        Err(nom::Err::Error(_)) => {
            let d = p.expected(p.ws_nl(src), "an expression", HINT_EXPR, None);
            Err(p.finish(failure(d)))
        }
        Err(e) => Err(p.finish(e)),
    }
}

// ---------------------------------------------------------------------------
// Errors

/// The error type threaded through the nom parsers.
///
/// `At` is a recoverable "nothing here" from a nom primitive (it records the
/// length of the remaining input, from which the offset follows); `Diag` is a
/// finished diagnostic, always raised as `nom::Err::Failure` so that no
/// alternative is tried after it.
#[derive(Debug)]
enum PErr {
    At(usize),
    Diag(Box<Diagnostic>),
}

impl<'s> ParseError<&'s str> for PErr {
    fn from_error_kind(input: &'s str, _kind: ErrorKind) -> Self {
        PErr::At(input.len())
    }
    fn append(_input: &'s str, _kind: ErrorKind, other: Self) -> Self {
        other
    }
}

type PResult<'s, T> = IResult<&'s str, T, PErr>;

/// A finished diagnostic as an unrecoverable nom error.
fn failure(d: Diagnostic) -> nom::Err<PErr> {
    nom::Err::Failure(PErr::Diag(Box::new(d)))
}

// The error constructors used on the recursive path are kept out of line, so
// that the frames of the recursive rules stay small (deep nesting must not
// exhaust a 2 MiB thread stack, even in debug builds).

#[cold]
#[inline(never)]
fn too_deep(at: Span) -> nom::Err<PErr> {
    failure(
        Diagnostic::error(
            at,
            format!("expression too deep (more than {MAX_DEPTH} levels)"),
        )
        .with_hint("split it into several named definitions"),
    )
}

#[cold]
#[inline(never)]
fn star_star(op: Span) -> nom::Err<PErr> {
    failure(
        Diagnostic::error(Span::new(op.start, op.end + 1), "`**` is not an operator")
            .with_hint("write powers with `^`, like `x^2`"),
    )
}

#[cold]
#[inline(never)]
fn too_many_primes(at: Span) -> nom::Err<PErr> {
    failure(
        Diagnostic::error(at, "too many primes")
            .with_hint("a derivative order must fit in 32 bits"),
    )
}

#[cold]
#[inline(never)]
fn prime_on_number(at: Span) -> nom::Err<PErr> {
    failure(
        Diagnostic::error(at, "a prime `'` (time derivative) can't follow a number").with_hint(
            "primes apply to names, calls and parenthesized expressions: `x'`, `sin(x)'`, `(2*x)'`; the derivative of a constant is 0",
        ),
    )
}

/// An operator character as a static string, for messages.
fn op_str(c: char) -> &'static str {
    match c {
        '+' => "+",
        '-' => "-",
        '*' => "*",
        '/' => "/",
        _ => "^",
    }
}

const HINT_EXPR: &str =
    "an expression is a number, a name, a call like `sin(x)` or an expression in parentheses";

/// An expression together with the depth of its tree. The expression is
/// boxed so that parse results stay small on the stack (the recursive rules
/// pass them around at every nesting level) and move into parents for free.
///
/// `outer` is the source text the operand came from: the node's own span
/// widened by enclosing parentheses and leading unary `+` signs (which leave
/// no node). Parents take their spans from the `outer` spans of their
/// children, so `(a+b)*c` spans from `(` while the sum inside keeps the
/// precise span `a+b`.
struct Node {
    e: Box<Expr>,
    d: u32,
    outer: Span,
}

/// Decrements a counter when dropped (on success and on error alike).
struct Guard<'a>(&'a Cell<u32>);

impl Drop for Guard<'_> {
    fn drop(&mut self) {
        self.0.set(self.0.get() - 1);
    }
}

// ---------------------------------------------------------------------------
// Character classes

/// `ident_start ::= Letter | "_"` (Letter: Unicode `Alphabetic`)
fn ident_start(c: char) -> bool {
    c.is_alphabetic() || c == '_'
}

/// `ident_char ::= Letter | [0-9] | "_"`
fn ident_char(c: char) -> bool {
    c.is_alphabetic() || c.is_ascii_digit() || c == '_'
}

/// One character of `space` (everything white except the newline).
fn is_space(c: char) -> bool {
    c != '\n' && (c.is_whitespace() || c == '\u{feff}')
}

/// Characters that have a meaning somewhere in the language.
fn is_known(c: char) -> bool {
    ident_char(c) || is_space(c) || "\n#+-*/^'()=,:;.°".contains(c)
}

/// A character for a message: control characters escaped.
fn show_char(c: char) -> String {
    if c.is_control() || c == '\u{feff}' {
        c.escape_default().to_string()
    } else {
        c.to_string()
    }
}

/// The next character of the input.
fn first(i: &str) -> Option<char> {
    i.chars().next()
}

/// Can an operand (an `atom`) start here? Used to detect `a b`.
fn starts_operand(i: &str) -> bool {
    let mut cs = i.chars();
    match cs.next() {
        Some(c) if ident_start(c) || c.is_ascii_digit() || c == '(' => true,
        Some('.') => cs.next().is_some_and(|c| c.is_ascii_digit()),
        _ => false,
    }
}

/// Show a piece of source in a message, shortened if long.
fn excerpt(s: &str) -> String {
    let s = s.split_whitespace().collect::<Vec<_>>().join(" ");
    if s.chars().count() > 40 {
        let head: String = s.chars().take(37).collect();
        format!("{head}…")
    } else {
        s
    }
}

/// `10^n`.
fn pow10(n: usize) -> BigInt {
    num_traits::pow(BigInt::from(10u32), n)
}

// ---------------------------------------------------------------------------
// The parser

/// Parser state: the source (for offsets), the recursion depth and the
/// number of open parentheses (inside them a newline is white space).
struct P<'s> {
    src: &'s str,
    nest: Cell<u32>,
    parens: Cell<u32>,
}

impl<'s> P<'s> {
    fn new(src: &'s str) -> Self {
        P {
            src,
            nest: Cell::new(0),
            parens: Cell::new(0),
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

    fn fail<T>(&self, d: Diagnostic) -> PResult<'s, T> {
        Err(failure(d))
    }

    fn nothing<T>(&self, i: &'s str) -> PResult<'s, T> {
        Err(nom::Err::Error(PErr::At(i.len())))
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
                .with_hint("the statement is incomplete");
        };
        let (msg, hint): (String, String) = match c {
            '\n' => (
                "unexpected end of the line".into(),
                "the statement is incomplete".into(),
            ),
            ')' => (
                "unmatched `)`".into(),
                "remove it, or add the matching `(` before it".into(),
            ),
            '=' => (
                "unexpected `=`".into(),
                "a statement has one `=`; put each statement on its own line or separate them with `;`".into(),
            ),
            ',' => (
                "unexpected `,`".into(),
                "commas separate call arguments like `atan(y, x)` and the names after `coordinates` or `parameters`".into(),
            ),
            ':' => (
                "unexpected `:`".into(),
                "`:` appears only in `force COORD: expression` and in annotations like `parameters r: length`".into(),
            ),
            '\'' => (
                "unexpected `'`".into(),
                "a prime (time derivative) follows a name, a call or a parenthesized expression: `x'`, `sin(x)'`, `(x*y)'`".into(),
            ),
            '°' => (
                "unexpected `°`".into(),
                "`°` follows a number: `30°`".into(),
            ),
            '.' => (
                "unexpected `.`".into(),
                "a decimal point belongs inside a number, like `0.5`".into(),
            ),
            '(' => (
                "unexpected `(`".into(),
                "to call a function write the name directly before `(`: `sin(x)`; to multiply, write `*`".into(),
            ),
            '+' | '-' | '*' | '/' | '^' => (
                format!("unexpected `{c}`"),
                format!("to continue an expression on the next line, end the previous line with the operator `{c}`"),
            ),
            ';' => (
                "unexpected `;`".into(),
                "`;` separates two statements on one line".into(),
            ),
            '²' | '³' | '¹' => (
                format!("unknown character `{c}`"),
                "write powers with `^`, like `x^2`".into(),
            ),
            '×' | '·' | '⋅' | '∙' => (
                format!("unknown character `{c}`"),
                "write multiplication with `*`".into(),
            ),
            '÷' | '∕' => (
                format!("unknown character `{c}`"),
                "write division with `/`".into(),
            ),
            '−' | '–' | '—' => (
                format!("unknown character `{c}`"),
                "write minus with the ASCII `-`".into(),
            ),
            '′' | '’' | '`' | '´' => (
                format!("unknown character `{c}`"),
                "write a time derivative with the ASCII prime `'`: `x'`".into(),
            ),
            '"' => (
                "unknown character `\"`".into(),
                "strings are not part of scenes (yet)".into(),
            ),
            '[' | ']' | '{' | '}' => (
                format!("unknown character `{c}`"),
                "group expressions with `(` and `)`".into(),
            ),
            _ if !is_known(c) => (
                format!("unknown character `{}`", show_char(c)),
                "this character is not part of the .qd language".into(),
            ),
            _ => (
                format!("unexpected {shown}"),
                "check the statement against `NAME = expression`".into(),
            ),
        };
        Diagnostic::error(span, msg).with_hint(hint)
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
            .with_hint(hint),
            Some('\n') => Diagnostic::error(span, format!("expected {what}, but the line ends"))
                .with_hint(hint),
            Some(c) if !is_known(c) => self.unexpected(i),
            Some(_) => {
                Diagnostic::error(span, format!("expected {what}, found {shown}")).with_hint(hint)
            }
        }
    }

    /// The error for the operand after operator `op` (at `at`): a
    /// recoverable "nothing here" becomes "expected an expression after …".
    #[cold]
    #[inline(never)]
    fn op_error(&self, e: nom::Err<PErr>, at: &'s str, op: &str, op_span: Span) -> nom::Err<PErr> {
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
    fn enter(&self, i: &'s str) -> Result<Guard<'_>, nom::Err<PErr>> {
        let n = self.nest.get() + 1;
        if n > MAX_NESTING {
            let (span, _) = self.token(i);
            return Err(failure(
                Diagnostic::error(
                    span,
                    format!("expression nested too deeply (more than {MAX_NESTING} levels)"),
                )
                .with_hint("split it into several named definitions"),
            ));
        }
        self.nest.set(n);
        Ok(Guard(&self.nest))
    }

    /// Note one more open parenthesis until the guard is dropped.
    fn open_paren(&self) -> Guard<'_> {
        self.parens.set(self.parens.get() + 1);
        Guard(&self.parens)
    }

    /// A leaf node (depth 1).
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
    fn node(&self, kind: ExprKind, span: Span, d: u32, at: Span) -> Result<Node, nom::Err<PErr>> {
        if d > MAX_DEPTH {
            return Err(too_deep(at));
        }
        Ok(Node {
            e: Box::new(Expr { kind, span }),
            d,
            outer: span,
        })
    }

    fn bin(&self, op: BinOp, l: Node, r: Node) -> Result<Node, nom::Err<PErr>> {
        let span = l.outer.to(r.outer);
        let d = l.d.max(r.d) + 1;
        let at = r.outer;
        self.node(ExprKind::Bin(op, l.e, r.e), span, d, at)
    }

    /// Final conversion of a parse error into a diagnostic. If a `(` left
    /// open before the error swallowed a line break (or the file ended
    /// inside it), the open `(` is the real problem and is reported instead.
    fn finish(&self, e: nom::Err<PErr>) -> Diagnostic {
        let d = match e {
            nom::Err::Error(PErr::At(n)) | nom::Err::Failure(PErr::At(n)) => {
                let at = self.src.len().saturating_sub(n);
                self.unexpected(&self.src[at..])
            }
            nom::Err::Error(PErr::Diag(d)) | nom::Err::Failure(PErr::Diag(d)) => *d,
            nom::Err::Incomplete(_) => Diagnostic::global("incomplete input"),
        };
        let Some(span) = d.span else { return d };
        if let Some(open) = unclosed_paren_before(self.src, span.start) {
            let swallowed = self.src[open..span.start.min(self.src.len())].contains('\n')
                || span.start >= self.src.len();
            if swallowed && d.message != "unclosed `(`" {
                return Diagnostic::error(Span::new(open, open + 1), "unclosed `(`").with_hint(
                    "add the matching `)`; inside parentheses a line break does not end the statement",
                );
            }
        }
        d
    }

    // ----- white space -------------------------------------------------------

    /// `space ::= ( #x20 | #x09 | #x0D | #xFEFF | OtherWhiteSpace )+`
    fn space(i: &'s str) -> PResult<'s, &'s str> {
        take_while1(is_space).parse(i)
    }

    /// `comment ::= "#" [^#x0A]*`
    fn comment(i: &'s str) -> PResult<'s, &'s str> {
        recognize(preceded(char('#'), take_till(|c| c == '\n'))).parse(i)
    }

    /// `newline ::= #x0A`
    fn newline(i: &'s str) -> PResult<'s, &'s str> {
        tag("\n").parse(i)
    }

    /// `ws ::= ( space | comment )*` — inside parentheses, `ws_nl`.
    fn ws(&self, i: &'s str) -> &'s str {
        if self.parens.get() > 0 {
            return self.ws_nl(i);
        }
        match many0_count(alt((Self::space, Self::comment))).parse(i) {
            Ok((rest, _)) => rest,
            Err(_) => i,
        }
    }

    /// `ws_nl ::= ( space | comment | newline )*`
    fn ws_nl(&self, i: &'s str) -> &'s str {
        match many0_count(alt((Self::space, Self::comment, Self::newline))).parse(i) {
            Ok((rest, _)) => rest,
            Err(_) => i,
        }
    }

    // ----- scene structure ---------------------------------------------------

    /// `scene ::= line ( newline line )*`
    fn scene(&self, mut i: &'s str) -> PResult<'s, Vec<Stmt>> {
        let mut out = Vec::new();
        loop {
            let (rest, mut stmts) = self.line(i)?;
            out.append(&mut stmts);
            if rest.is_empty() {
                return Ok((rest, out));
            }
            match Self::newline(rest) {
                Ok((rest, _)) => i = rest,
                Err(_) => return self.fail(self.unexpected(rest)),
            }
        }
    }

    /// `line ::= ws statement? ( ws ";" ws statement? )* ws`
    fn line(&self, mut i: &'s str) -> PResult<'s, Vec<Stmt>> {
        let mut out = Vec::new();
        loop {
            i = self.ws(i);
            let start = self.pos(i);
            if !matches!(first(i), None | Some('\n') | Some(';')) {
                let (rest, stmt) = match self.statement(i) {
                    Err(nom::Err::Failure(PErr::Diag(d))) => {
                        return Err(failure(self.note_continuation(start, *d)))
                    }
                    other => other?,
                };
                out.push(stmt);
                i = self.ws(rest);
            }
            match first(i) {
                Some(';') => i = &i[1..],
                None | Some('\n') => return Ok((i, out)),
                Some(_) => {
                    let d = self.unexpected(i);
                    return Err(failure(self.note_continuation(start, d)));
                }
            }
        }
    }

    /// If the statement starting at `start` ran over a line break outside
    /// parentheses before the error, a line ended in an operator: that
    /// trailing operator is the likely mistake, so the hint says so.
    fn note_continuation(&self, start: usize, d: Diagnostic) -> Diagnostic {
        let Some(span) = d.span else { return d };
        let end = span.start.min(self.src.len());
        let mut depth = 0i64;
        let mut in_comment = false;
        let mut last = None; // last significant char on the current line
        let mut continued = None; // (line offset, operator)
        for (p, c) in self.src[start.min(end)..end].char_indices() {
            match c {
                '\n' => {
                    in_comment = false;
                    if depth <= 0 {
                        if let Some(op) = last {
                            continued = Some((start + p, op));
                        }
                    }
                    last = None;
                }
                _ if in_comment => {}
                '#' => in_comment = true,
                c if is_space(c) => {}
                c => {
                    match c {
                        '(' => depth += 1,
                        ')' => depth -= 1,
                        _ => {}
                    }
                    last = Some(c);
                }
            }
        }
        match continued {
            Some((p, op)) => {
                let (line, _) = Diagnostic::line_col(self.src, p);
                let hint = format!(
                    "line {line} ends with `{op}`, so the expression continues on the next line; complete it or remove the trailing `{op}`"
                );
                d.with_hint(hint)
            }
            None => d,
        }
    }

    /// `statement ::= declaration | role_stmt | force_stmt | definition`
    ///
    /// Keywords do not reserve names: the tokens after the first identifier
    /// decide (see the grammar).
    fn statement(&self, i: &'s str) -> PResult<'s, Stmt> {
        let (after, kw) = match self.ident(i) {
            Ok(x) => x,
            Err(nom::Err::Error(_)) => return self.fail(self.statement_start(i)),
            Err(e) => return Err(e),
        };
        let next = self.ws(after);
        let next_is_ident = first(next).is_some_and(ident_start);
        let next_is_eq = next.starts_with('=');
        let at_end = matches!(first(next), None | Some('\n') | Some(';'));
        let word = kw.name.as_str();
        match word {
            "coordinates" | "parameters" if !next_is_eq => {
                if next_is_ident {
                    self.declaration(i)
                } else if at_end {
                    self.fail(
                        Diagnostic::error(kw.span, format!("empty `{word}` list"))
                            .with_hint(format!("list at least one name: `{word} x, y`")),
                    )
                } else {
                    self.fail(self.expected(
                        next,
                        &format!("a name after `{word}`"),
                        &format!("declare names like `{word} x, y`; to define a name `{word}`, write `{word} = expression`"),
                        None,
                    ))
                }
            }
            "force" if !next_is_eq => {
                if next_is_ident {
                    self.force_stmt(i)
                } else {
                    self.fail(self.expected(
                        next,
                        "a coordinate name after `force`",
                        "a generalized force is written `force COORD: expression`",
                        None,
                    ))
                }
            }
            _ if !next_is_eq && Role::from_keyword(word).is_some() => {
                if next_is_ident {
                    self.role_stmt(i)
                } else {
                    self.fail(self.expected(
                        next,
                        &format!("a name after `{word}`"),
                        &format!("write `{word} NAME = expression`; to define a name `{word}`, write `{word} = expression`"),
                        None,
                    ))
                }
            }
            _ => self.definition(i),
        }
    }

    /// The error for a line that does not start with an identifier.
    fn statement_start(&self, i: &'s str) -> Diagnostic {
        let (span, shown) = self.token(i);
        match first(i) {
            Some(c) if c.is_ascii_digit() || c == '(' || c == '.' => Diagnostic::error(
                span,
                format!("a statement must start with a name or a keyword, found {shown}"),
            )
            .with_hint("a definition is written `NAME = expression`"),
            Some('+' | '-' | '*' | '/' | '^') => Diagnostic::error(
                span,
                format!("a statement can't start with {shown}"),
            )
            .with_hint("to continue an expression on the next line, end the previous line with the operator"),
            _ => self.unexpected(i),
        }
    }

    /// `declaration ::= ( "coordinates" | "parameters" ) ws decl ( ws "," ws decl )*`
    fn declaration(&self, i: &'s str) -> PResult<'s, Stmt> {
        let i = self.ws(i);
        let start = self.pos(i);
        let (mut i, kw) = alt((tag("coordinates"), tag("parameters"))).parse(i)?;
        let mut decls = Vec::new();
        let (rest, d) = self.decl(i)?;
        decls.push(d);
        i = rest;
        loop {
            let j = self.ws(i);
            match char::<_, PErr>(',').parse(j) {
                Ok((k, _)) => match self.decl(k) {
                    Ok((rest, d)) => {
                        decls.push(d);
                        i = rest;
                    }
                    Err(nom::Err::Error(_)) => {
                        return self.fail(self.expected(
                            self.ws(k),
                            "a name after `,`",
                            "list names separated by commas: `x, y`",
                            None,
                        ))
                    }
                    Err(e) => return Err(e),
                },
                Err(_) => {
                    if starts_operand(j) {
                        let (span, shown) = self.token(j);
                        return self.fail(
                            Diagnostic::error(span, format!("expected `,` before {shown}"))
                                .with_hint("separate the names with commas: `x, y`"),
                        );
                    }
                    if j.starts_with('=') {
                        let name = &decls[decls.len() - 1].name.name;
                        return self.fail(
                            Diagnostic::error(self.token(j).0, "a declaration can't have a value")
                                .with_hint(format!(
                                    "to give `{name}` a value, write a definition `{name} = …` instead of declaring it"
                                )),
                        );
                    }
                    break;
                }
            }
        }
        let end = decls[decls.len() - 1]
            .dimension
            .as_ref()
            .unwrap_or(&decls[decls.len() - 1].name)
            .span
            .end;
        let span = Span::new(start, end);
        let stmt = if kw == "coordinates" {
            Stmt::Coordinates(decls, span)
        } else {
            Stmt::Parameters(decls, span)
        };
        Ok((i, stmt))
    }

    /// `decl ::= ident ( ws ":" ws ident )?`
    fn decl(&self, i: &'s str) -> PResult<'s, Decl> {
        let (i, name) = self.ident(i)?;
        let j = self.ws(i);
        match char::<_, PErr>(':').parse(j) {
            Ok((k, _)) => match self.ident(k) {
                Ok((rest, dim)) => Ok((
                    rest,
                    Decl {
                        name,
                        dimension: Some(dim),
                    },
                )),
                Err(nom::Err::Error(_)) => self.fail(self.expected(
                    self.ws(k),
                    &format!("a dimension name after `{}:`", name.name),
                    "annotate a dimension like `r: length`",
                    None,
                )),
                Err(e) => Err(e),
            },
            Err(_) => Ok((
                i,
                Decl {
                    name,
                    dimension: None,
                },
            )),
        }
    }

    /// `role_stmt ::= role ws ident ws "=" ws expr`
    fn role_stmt(&self, i: &'s str) -> PResult<'s, Stmt> {
        let (rest, role) = self.role(i)?;
        let start = self.pos(self.ws(i));
        let (rest, name) = self.ident(rest)?;
        let head = format!("{} {}", role.keyword(), name.name);
        let rest = self.equals(rest, &head, &format!("write `{head} = expression`"))?;
        let (rest, (value, outer)) = self.rhs(rest, "=")?;
        let span = Span::new(start, outer.end);
        Ok((
            rest,
            Stmt::Role {
                role,
                name,
                value,
                span,
            },
        ))
    }

    /// `role ::= "kinetic" | "potential" | "forcefunction" | "work" | "dissipation" | "rayleigh"`
    fn role(&self, i: &'s str) -> PResult<'s, Role> {
        let (rest, id) = self.ident(i)?;
        match Role::from_keyword(&id.name) {
            Some(r) => Ok((rest, r)),
            None => self.nothing(i),
        }
    }

    /// `force_stmt ::= "force" ws ident ws ":" ws expr`
    fn force_stmt(&self, i: &'s str) -> PResult<'s, Stmt> {
        let i = self.ws(i);
        let start = self.pos(i);
        let (rest, _) = tag("force").parse(i)?;
        let (rest, coordinate) = self.ident(rest)?;
        let j = self.ws(rest);
        let rest = match char::<_, PErr>(':').parse(j) {
            Ok((k, _)) => k,
            Err(_) => {
                let c = &coordinate.name;
                return self.fail(self.expected(
                    j,
                    &format!("`:` after `force {c}`"),
                    &format!("a generalized force is written `force {c}: expression`"),
                    None,
                ));
            }
        };
        let (rest, (value, outer)) = self.rhs(rest, ":")?;
        let span = Span::new(start, outer.end);
        Ok((
            rest,
            Stmt::Force {
                coordinate,
                value,
                span,
            },
        ))
    }

    /// `definition ::= ident ws "=" ws expr`
    fn definition(&self, i: &'s str) -> PResult<'s, Stmt> {
        let (rest, name) = self.ident(i)?;
        let hint = if rest.starts_with('(') {
            format!(
                "functions can't be defined in a scene; define a name instead: `{} = expression`",
                name.name
            )
        } else {
            format!("a definition is written `{} = expression`", name.name)
        };
        let rest = self.equals(rest, &name.name, &hint)?;
        let (rest, (value, outer)) = self.rhs(rest, "=")?;
        let span = name.span.to(outer);
        Ok((rest, Stmt::Def { name, value, span }))
    }

    /// The `"="` of a definition or role statement, after `head`.
    fn equals(&self, i: &'s str, head: &str, hint: &str) -> Result<&'s str, nom::Err<PErr>> {
        let j = self.ws(i);
        match char::<_, PErr>('=').parse(j) {
            Ok((k, _)) => Ok(k),
            Err(_) => Err(failure(self.expected(
                j,
                &format!("`=` after `{head}`"),
                hint,
                None,
            ))),
        }
    }

    /// The expression after `=` or `:` that ends a statement, with the
    /// source span it came from (including enclosing parentheses).
    fn rhs(&self, i: &'s str, after: &str) -> PResult<'s, (Expr, Span)> {
        let at = self.ws(i);
        let op_span = Span::new(self.pos(i) - after.len(), self.pos(i));
        match self.expr(i) {
            Ok((rest, node)) => Ok((rest, (*node.e, node.outer))),
            Err(nom::Err::Error(_)) => self.fail(self.expected(
                at,
                &format!("an expression after `{after}`"),
                HINT_EXPR,
                Some(op_span),
            )),
            Err(e) => Err(e),
        }
    }

    // ----- expressions -------------------------------------------------------

    /// `whole_expr ::= ws_nl expr ws_nl` — the input of [`parse_expr`]; it
    /// must end after the expression.
    fn whole_expr(&self, i: &'s str) -> PResult<'s, Node> {
        let _p = self.open_paren();
        let (rest, node) = self.expr(i)?;
        let rest = self.ws_nl(rest);
        if !rest.is_empty() {
            return self.fail(self.unexpected(rest));
        }
        Ok((rest, node))
    }

    /// `expr ::= sum`
    fn expr(&self, i: &'s str) -> PResult<'s, Node> {
        let _g = self.enter(self.ws(i))?;
        self.sum(i)
    }

    /// `sum ::= product ( ws ( "+" | "-" ) ws_nl product )*`
    fn sum(&self, i: &'s str) -> PResult<'s, Node> {
        let (mut i, mut lhs) = self.product(i)?;
        loop {
            let j = self.ws(i);
            let Ok((k, op)) = one_of::<_, _, PErr>("+-").parse(j) else {
                break;
            };
            let op_span = self.span(j, k);
            let k = self.ws_nl(k);
            let (rest, rhs) = match self.product(k) {
                Ok(x) => x,
                Err(e) => return Err(self.op_error(e, k, op_str(op), op_span)),
            };
            let op = if op == '+' { BinOp::Add } else { BinOp::Sub };
            lhs = self.bin(op, lhs, rhs)?;
            i = rest;
        }
        Ok((i, lhs))
    }

    /// `product ::= unary ( ws ( "*" | "/" ) ws_nl unary | implicit_factor )*`
    fn product(&self, i: &'s str) -> PResult<'s, Node> {
        let (mut i, mut lhs) = self.unary(i)?;
        let mut last = lhs.outer;
        let mut last_is_name = matches!(lhs.e.kind, ExprKind::Name(_));
        loop {
            if self.implicit_here(i) {
                let (rest, f) = self.implicit_factor(i)?;
                last = f.outer;
                last_is_name = false;
                lhs = self.bin(BinOp::Mul, lhs, f)?;
                i = rest;
                continue;
            }
            let j = self.ws(i);
            let Ok((k, op)) = one_of::<_, _, PErr>("*/").parse(j) else {
                break;
            };
            let op_span = self.span(j, k);
            if op == '*' && k.starts_with('*') {
                return Err(star_star(op_span));
            }
            let k = self.ws_nl(k);
            let (rest, rhs) = match self.unary(k) {
                Ok(x) => x,
                Err(e) => return Err(self.op_error(e, k, op_str(op), op_span)),
            };
            last = rhs.outer;
            last_is_name = matches!(rhs.e.kind, ExprKind::Name(_));
            let op = if op == '*' { BinOp::Mul } else { BinOp::Div };
            lhs = self.bin(op, lhs, rhs)?;
            i = rest;
        }
        self.side_by_side(i, last, last_is_name)?;
        Ok((i, lhs))
    }

    /// Is an implicit product allowed at `i` (directly after a number or `)`)?
    fn implicit_here(&self, i: &str) -> bool {
        let p = self.pos(i);
        let prev = self.src[..p].chars().next_back();
        match (prev, first(i)) {
            (Some(d), Some(n)) if d.is_ascii_digit() => ident_start(n) || n == '(',
            (Some(')'), Some('(')) => true,
            _ => false,
        }
    }

    /// `implicit_factor ::= power` — only where [`P::implicit_here`] holds.
    fn implicit_factor(&self, i: &'s str) -> PResult<'s, Node> {
        self.power(i)
    }

    /// Reject two operands side by side (`a b`) with a helpful hint.
    fn side_by_side(
        &self,
        i: &'s str,
        left: Span,
        left_is_name: bool,
    ) -> Result<(), nom::Err<PErr>> {
        let j = self.ws(i);
        if !starts_operand(j) {
            return Ok(());
        }
        let right = match self.power(j) {
            Ok((_, r)) => r.outer,
            Err(nom::Err::Error(_)) => self.token(j).0,
            Err(e) => return Err(e),
        };
        let l = excerpt(&self.src[left.start..left.end]);
        let r = excerpt(&self.src[right.start..right.end]);
        let after_number = l.ends_with(|c: char| c.is_ascii_digit());
        let mut hint = if left_is_name && j.starts_with('(') {
            format!("to call `{l}`, write `{l}{r}` without a space; to multiply, write `{l}*{r}`")
        } else if after_number && r == "deg" {
            format!("for an angle in degrees write `{l}deg` without a space, or `{l}°`")
        } else if after_number && (j.starts_with('(') || first(j).is_some_and(ident_start)) {
            format!("did you mean `{l}*{r}`? (an implicit product is written without a space: `{l}{r}`)")
        } else {
            format!("did you mean `{l}*{r}`?")
        };
        if self.src[left.end..right.start].contains('\n') {
            hint.push_str(" (or is a `)` missing before the line break?)");
        }
        Err(failure(
            Diagnostic::error(right, "two expressions side by side").with_hint(hint),
        ))
    }

    /// `unary ::= ws ( "-" | "+" ) unary | power`
    fn unary(&self, i: &'s str) -> PResult<'s, Node> {
        let j = self.ws(i);
        let Ok((k, sign)) = one_of::<_, _, PErr>("+-").parse(j) else {
            return self.power(j);
        };
        let _g = self.enter(j)?;
        let sign_span = self.span(j, k);
        let (rest, inner) = match self.unary(k) {
            Ok(x) => x,
            Err(e) => return Err(self.op_error(e, k, op_str(sign), sign_span)),
        };
        let span = sign_span.to(inner.outer);
        if sign == '-' {
            let node = self.node(ExprKind::Neg(inner.e), span, inner.d + 1, sign_span)?;
            Ok((rest, node))
        } else {
            // unary plus leaves no node; the operand keeps its own span
            let mut inner = inner;
            inner.outer = span;
            Ok((rest, inner))
        }
    }

    /// `power ::= postfix ( ws "^" ws_nl exponent )?`
    fn power(&self, i: &'s str) -> PResult<'s, Node> {
        let (i, base) = self.postfix(i)?;
        let j = self.ws(i);
        let Ok((k, _)) = char::<_, PErr>('^').parse(j) else {
            return Ok((i, base));
        };
        let op_span = self.span(j, k);
        let k = self.ws_nl(k);
        let (rest, ex) = match self.exponent(k) {
            Ok(x) => x,
            Err(e) => return Err(self.op_error(e, k, "^", op_span)),
        };
        Ok((rest, self.bin(BinOp::Pow, base, ex)?))
    }

    /// `exponent ::= ws ( "-" | "+" ) exponent | power`
    fn exponent(&self, i: &'s str) -> PResult<'s, Node> {
        let j = self.ws(i);
        let _g = self.enter(j)?;
        let Ok((k, sign)) = one_of::<_, _, PErr>("+-").parse(j) else {
            return self.power(j);
        };
        let sign_span = self.span(j, k);
        let (rest, inner) = match self.exponent(k) {
            Ok(x) => x,
            Err(e) => return Err(self.op_error(e, k, op_str(sign), sign_span)),
        };
        let span = sign_span.to(inner.outer);
        if sign == '-' {
            let node = self.node(ExprKind::Neg(inner.e), span, inner.d + 1, sign_span)?;
            Ok((rest, node))
        } else {
            // unary plus leaves no node; the operand keeps its own span
            let mut inner = inner;
            inner.outer = span;
            Ok((rest, inner))
        }
    }

    /// `postfix ::= atom ( ws "'" )*`
    fn postfix(&self, i: &'s str) -> PResult<'s, Node> {
        let start = self.ws(i);
        let (mut i, a) = self.atom(start)?;
        let mut order: u32 = 0;
        let mut first_prime = None;
        loop {
            let j = self.ws(i);
            match char::<_, PErr>('\'').parse(j) {
                Ok((k, _)) => {
                    first_prime.get_or_insert(self.span(j, k));
                    order = order.saturating_add(1);
                    i = k;
                }
                Err(_) => break,
            }
        }
        let Some(prime_span) = first_prime else {
            return Ok((i, a));
        };
        let is_group = start.starts_with('(');
        if !is_group && matches!(a.e.kind, ExprKind::Num(_) | ExprKind::Degrees(_)) {
            return Err(prime_on_number(prime_span));
        }
        if order == u32::MAX {
            return Err(too_many_primes(prime_span));
        }
        let span = Span::new(a.outer.start, self.pos(i));
        let d = a.d + 1;
        Ok((
            i,
            self.node(ExprKind::Prime(a.e, order), span, d, prime_span)?,
        ))
    }

    /// `atom ::= literal | call | name | group`
    fn atom(&self, i: &'s str) -> PResult<'s, Node> {
        let i = self.ws(i);
        match first(i) {
            Some(c) if c.is_ascii_digit() || (c == '.' && starts_operand(i)) => self.literal(i),
            Some(c) if ident_start(c) => {
                let (rest, _) = self.ident(i)?;
                if rest.starts_with('(') {
                    self.call(i)
                } else {
                    self.name(i)
                }
            }
            Some('(') => self.group(i),
            _ => self.nothing(i),
        }
    }

    /// `call ::= ident "(" ws_nl ( expr ( ws_nl "," ws_nl expr )* ws_nl )? ")"`
    fn call(&self, i: &'s str) -> PResult<'s, Node> {
        let (rest, name) = self.ident(i)?;
        let (mut k, _) = char('(').parse(rest)?;
        let open = self.pos(rest);
        let _p = self.open_paren();
        let mut args = Vec::new();
        let mut d = 0;
        let j = self.ws(k);
        if let Ok((after, _)) = char::<_, PErr>(')').parse(j) {
            k = after;
        } else {
            loop {
                let (rest, arg) = match self.expr(k) {
                    Ok(x) => x,
                    Err(e) => return Err(self.arg_error(e, k, &name, args.is_empty())),
                };
                d = d.max(arg.d);
                args.push(*arg.e);
                let j = self.ws(rest);
                match first(j) {
                    Some(',') => k = &j[1..],
                    Some(')') => {
                        k = &j[1..];
                        break;
                    }
                    _ => return Err(self.args_unclosed(j, open, &name)),
                }
            }
        }
        let span = Span::new(name.span.start, self.pos(k));
        let at = name.span;
        Ok((k, self.node(ExprKind::Call(name, args), span, d + 1, at)?))
    }

    /// The error for a missing argument at `k` of the call of `name`.
    #[cold]
    #[inline(never)]
    fn arg_error(
        &self,
        e: nom::Err<PErr>,
        k: &'s str,
        name: &Ident,
        first_arg: bool,
    ) -> nom::Err<PErr> {
        if !matches!(e, nom::Err::Error(_)) {
            return e;
        }
        let at = self.ws(k);
        let (what, hint) = if first_arg {
            (format!("an argument of `{}`", name.name), HINT_EXPR)
        } else if at.starts_with(')') {
            (
                "an argument after `,`".to_string(),
                "remove the trailing `,`",
            )
        } else {
            ("an argument after `,`".to_string(), HINT_EXPR)
        };
        failure(self.expected(at, &what, hint, None))
    }

    /// The error when neither `,` nor `)` follows an argument of `name`.
    #[cold]
    #[inline(never)]
    fn args_unclosed(&self, j: &'s str, open: usize, name: &Ident) -> nom::Err<PErr> {
        let what = format!("`,` or `)` after an argument of `{}`", name.name);
        failure(self.close_expected(j, open, &what))
    }

    /// The error when `)` (or `,`) is expected at `j` for the `(` at `open`.
    fn close_expected(&self, j: &'s str, open: usize, what: &str) -> Diagnostic {
        if j.is_empty() {
            return Diagnostic::error(Span::new(open, open + 1), "unclosed `(`")
                .with_hint("add the matching `)`");
        }
        let (line, col) = Diagnostic::line_col(self.src, open);
        self.expected(
            j,
            what,
            &format!("the `(` at line {line}, column {col} is still open"),
            None,
        )
    }

    /// `name ::= ident`
    fn name(&self, i: &'s str) -> PResult<'s, Node> {
        let (rest, id) = self.ident(i)?;
        Ok((rest, Self::leaf(ExprKind::Name(id.name), id.span)))
    }

    /// `group ::= "(" ws_nl expr ws_nl ")"`
    fn group(&self, i: &'s str) -> PResult<'s, Node> {
        let (k, _) = char('(').parse(i)?;
        let open = self.pos(i);
        let _p = self.open_paren();
        let (rest, mut inner) = match self.expr(k) {
            Ok(x) => x,
            Err(e) => return Err(self.group_error(e, k, open)),
        };
        let j = self.ws(rest);
        match char::<_, PErr>(')').parse(j) {
            Ok((after, _)) => {
                inner.outer = Span::new(open, self.pos(after));
                Ok((after, inner))
            }
            Err(_) => Err(failure(self.close_expected(j, open, "`)`"))),
        }
    }

    /// The error when no expression follows the `(` at `open`.
    #[cold]
    #[inline(never)]
    fn group_error(&self, e: nom::Err<PErr>, k: &'s str, open: usize) -> nom::Err<PErr> {
        if !matches!(e, nom::Err::Error(_)) {
            return e;
        }
        let at = self.ws(k);
        if at.starts_with(')') {
            return failure(
                Diagnostic::error(Span::new(open, self.pos(at) + 1), "empty parentheses `()`")
                    .with_hint("put an expression inside the parentheses, or remove them"),
            );
        }
        if at.is_empty() {
            return failure(self.close_expected(at, open, ""));
        }
        failure(self.expected(at, "an expression after `(`", HINT_EXPR, None))
    }

    // ----- tokens ------------------------------------------------------------

    /// `literal ::= number angle_unit?`
    fn literal(&self, i: &'s str) -> PResult<'s, Node> {
        let i = self.ws(i);
        let (rest, value) = self.number(i)?;
        match self.angle_unit(rest) {
            Ok((rest, _)) => {
                let span = self.span(i, rest);
                Ok((rest, Self::leaf(ExprKind::Degrees(value), span)))
            }
            Err(_) => {
                let span = self.span(i, rest);
                Ok((rest, Self::leaf(ExprKind::Num(value), span)))
            }
        }
    }

    /// `angle_unit ::= "deg" | space? "°"` — `deg` not followed by an `ident_char`.
    fn angle_unit(&self, i: &'s str) -> PResult<'s, &'s str> {
        if let Ok((rest, d)) = tag::<_, _, PErr>("deg").parse(i) {
            if !first(rest).is_some_and(ident_char) {
                return Ok((rest, d));
            }
            return self.nothing(i);
        }
        preceded(opt(Self::space), tag("°")).parse(i)
    }

    /// `number ::= digits ( "." digits )? sci_exponent?`
    fn number(&self, i: &'s str) -> PResult<'s, BigRational> {
        if let Ok((rest, _)) = char::<_, PErr>('.').parse(i) {
            if let Ok((rest, frac)) = Self::digits(rest) {
                return self.fail(
                    Diagnostic::error(
                        self.span(i, rest),
                        "a number can't start with a decimal point",
                    )
                    .with_hint(format!("write `0.{frac}`")),
                );
            }
        }
        let (mut rest, int) = Self::digits(i)?;
        let mut frac = "";
        if let Ok((after_dot, _)) = char::<_, PErr>('.').parse(rest) {
            match Self::digits(after_dot) {
                Ok((after, f)) => {
                    frac = f;
                    rest = after;
                }
                Err(_) => {
                    return self.fail(
                        Diagnostic::error(self.span(i, after_dot), format!("malformed number `{int}.`"))
                            .with_hint(format!("a decimal point must be followed by digits: write `{int}.0` or `{int}`")),
                    );
                }
            }
        }
        let (rest, exp) = match self.sci_exponent(rest) {
            Ok((after, e)) => (after, e),
            Err(nom::Err::Error(_)) => (rest, 0),
            Err(e) => return Err(e),
        };
        if rest.starts_with('.') {
            let end = rest
                .find(|c: char| !(c.is_ascii_digit() || c == '.'))
                .unwrap_or(rest.len());
            let span = Span::new(self.pos(i), self.pos(rest) + end);
            return self.fail(
                Diagnostic::error(
                    span,
                    format!("malformed number `{}`", &self.src[span.start..span.end]),
                )
                .with_hint(
                    "a number has at most one decimal point, before any exponent: `1.25`, `1.5e-3`",
                ),
            );
        }
        let mut numer: BigInt = format!("{int}{frac}")
            .parse()
            .unwrap_or_else(|_| BigInt::zero());
        let mut denom = pow10(frac.len());
        if exp >= 0 {
            numer *= pow10(exp as usize);
        } else {
            denom *= pow10(exp.unsigned_abs() as usize);
        }
        if denom.is_zero() {
            denom = BigInt::one();
        }
        Ok((rest, BigRational::new(numer, denom)))
    }

    /// `sci_exponent ::= [eE] [+-]? digits` — taken only when a digit follows.
    fn sci_exponent(&self, i: &'s str) -> PResult<'s, i64> {
        let (rest, (_, sign, digits)) = (one_of("eE"), opt(one_of("+-")), Self::digits).parse(i)?;
        let significant = digits.trim_start_matches('0');
        let n: u32 = if significant.len() > 6 {
            u32::MAX
        } else {
            significant.parse().unwrap_or(0)
        };
        if n > MAX_EXPONENT {
            return self.fail(
                Diagnostic::error(self.span(i, rest), "exponent out of range")
                    .with_hint(format!("exponents up to {MAX_EXPONENT} are accepted")),
            );
        }
        let n = i64::from(n);
        Ok((rest, if sign == Some('-') { -n } else { n }))
    }

    /// `digits ::= [0-9]+`
    fn digits(i: &'s str) -> PResult<'s, &'s str> {
        digit1(i)
    }

    /// `ident ::= ident_start ident_char*`
    fn ident(&self, i: &'s str) -> PResult<'s, Ident> {
        let i = self.ws(i);
        let (rest, name) = recognize((satisfy(ident_start), take_while(ident_char))).parse(i)?;
        Ok((
            rest,
            Ident {
                name: name.to_string(),
                span: self.span(i, rest),
            },
        ))
    }
}

/// The innermost `(` that is still open at the end of `src` and starts before
/// `limit` (comments are skipped).
fn unclosed_paren_before(src: &str, limit: usize) -> Option<usize> {
    let mut stack = Vec::new();
    let mut in_comment = false;
    for (p, c) in src.char_indices() {
        match c {
            '\n' => in_comment = false,
            _ if in_comment => {}
            '#' => in_comment = true,
            '(' => stack.push(p),
            ')' => {
                stack.pop();
            }
            _ => {}
        }
    }
    stack.into_iter().rev().find(|&p| p < limit)
}
