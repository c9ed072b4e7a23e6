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
//! Two limits keep hostile input from exhausting the stack:
//! [`MAX_NESTING`] bounds the recursion of the parser (parentheses, call
//! arguments, chains of unary signs and of `^`), and [`MAX_DEPTH`] bounds the
//! depth of the produced tree (so long `a + b + c + …` chains, which are parsed
//! by a loop, cannot build a tree too deep to drop or to walk recursively).

// `ast.rs` is kept byte-identical to the main repository's copy; default
// rustfmt would re-wrap its `Stmt::Def` variant, so it is not formatted here.
#[rustfmt::skip]
pub mod ast;
mod chars;
pub mod keywords;

pub use chars::is_hidden;

use std::cell::Cell;

use nom::error::{ErrorKind, ParseError};
use nom::IResult;
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Zero};

use crate::diag::Diagnostic;
use ast::{BinOp, Decl, Equation, Expr, ExprKind, Ident, Role, SolveBlock, Span, Stmt};

/// Deepest recursion of the parser: parentheses, call arguments, unary signs
/// and `^` chains each count one level.
pub const MAX_NESTING: u32 = 200;

/// Deepest expression tree the parser builds (a leaf has depth 1).
pub const MAX_DEPTH: u32 = 1000;

/// Largest `|n|` accepted in a scientific exponent `…e±n`.
pub const MAX_EXPONENT: u32 = 1000;

/// Parse a whole scene.
pub fn parse_scene(src: &str) -> Result<Vec<Stmt>, Diagnostic> {
    chars::no_bidi_control(src)?;
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
    chars::no_bidi_control(src)?;
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

#[cold]
#[inline(never)]
fn unclosed_bracket(open: usize) -> nom::Err<PErr> {
    failure(
        Diagnostic::error(Span::new(open, open + 1), "unclosed `[`")
            .with_hint("add the matching `]`"),
    )
}

#[cold]
#[inline(never)]
fn unclosed_block(open: usize) -> nom::Err<PErr> {
    failure(
        Diagnostic::error(Span::new(open, open + 1), "unclosed `{`").with_hint(HINT_UNCLOSED_BLOCK),
    )
}

const HINT_EXPR: &str =
    "an expression is a number, a name, a call like `sin(x)` or an expression in parentheses";

const HINT_UNCLOSED_BLOCK: &str = "add the matching `}` after the last equation of the solve block";

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
    ident_char(c) || is_space(c) || "\n#+-*/^'()[]{}=,:;.°".contains(c)
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

/// Does the input start with a character of `class` (`ident_start` or
/// `ident_char`)? ASCII is decided on the byte; other characters are decoded.
#[inline]
fn starts_with_class(i: &str, class: fn(char) -> bool) -> bool {
    match i.as_bytes().first() {
        Some(&b) if b < 0x80 => class(char::from(b)),
        Some(_) => first(i).is_some_and(class),
        None => false,
    }
}

/// Does an `ident` start here?
#[inline]
fn starts_ident(i: &str) -> bool {
    starts_with_class(i, ident_start)
}

/// Length in bytes of the `ident` at the start of `i` (0 if there is none).
#[cfg_attr(not(debug_assertions), inline(always))]
fn ident_len(i: &str) -> usize {
    let b = i.as_bytes();
    match b.first() {
        Some(&c) if c.is_ascii_alphabetic() || c == b'_' => {}
        Some(&c) if c >= 0x80 => return ident_len_unicode(i, 0),
        _ => return 0,
    }
    let mut p = 1;
    while let Some(&c) = b.get(p) {
        if c.is_ascii_alphanumeric() || c == b'_' {
            p += 1;
        } else if c >= 0x80 {
            return ident_len_unicode(i, p);
        } else {
            break;
        }
    }
    p
}

/// [`ident_len`] from byte `p` on (where `i` has a non-ASCII character or,
/// for `p == 0`, must start with an `ident_start`), decoding characters.
#[inline(never)]
fn ident_len_unicode(i: &str, mut p: usize) -> usize {
    if p == 0 {
        match first(i) {
            Some(c) if ident_start(c) => p = c.len_utf8(),
            _ => return 0,
        }
    }
    while let Some(c) = first(&i[p..]) {
        if ident_char(c) {
            p += c.len_utf8();
        } else {
            break;
        }
    }
    p
}

/// Number of ASCII digits at the start of `i`.
#[inline]
fn digits_len(i: &str) -> usize {
    i.bytes().take_while(u8::is_ascii_digit).count()
}

/// The number of `\n` bytes in `b` (eight bytes at a time).
fn count_newlines(b: &[u8]) -> usize {
    const LOW7: u64 = 0x7f7f_7f7f_7f7f_7f7f;
    let chunks = b.chunks_exact(8);
    let tail = chunks.remainder();
    let mut n = 0;
    for c in chunks {
        let x = u64::from_le_bytes(c.try_into().unwrap_or([0; 8])) ^ 0x0a0a_0a0a_0a0a_0a0a;
        // the high bit of each byte is set iff the byte is not zero
        let nonzero = (((x & LOW7) + LOW7) | x) & !LOW7;
        n += 8 - nonzero.count_ones() as usize;
    }
    n + tail.iter().filter(|&&c| c == b'\n').count()
}

/// Skip `( space | comment )*`, and newlines too if `nl` (`ws_nl`).
#[cfg_attr(not(debug_assertions), inline(always))]
fn skip_ws(i: &str, nl: bool) -> &str {
    let b = i.as_bytes();
    // the common cases: no white space, or a single space before a token
    match b.first().map(|&c| WS_START[usize::from(c)]) {
        None | Some(NOT_WS) => i,
        Some(NEWLINE) if !nl => i,
        Some(SPACE)
            if b.get(1)
                .is_some_and(|&c| WS_START[usize::from(c)] == NOT_WS) =>
        {
            &i[1..]
        }
        Some(_) => skip_ws_loop(i, nl),
    }
}

/// Classes of a first byte for [`skip_ws`].
const NOT_WS: u8 = 0;
const SPACE: u8 = 1;
const NEWLINE: u8 = 2;
/// Other bytes that may start `space` or `comment` (a non-ASCII byte may
/// start a Unicode space).
const OTHER_WS: u8 = 3;

/// The class of each byte as the first byte of white space.
static WS_START: [u8; 256] = {
    let mut t = [NOT_WS; 256];
    let mut b = 0x80;
    while b < 256 {
        t[b] = OTHER_WS;
        b += 1;
    }
    t[b' ' as usize] = SPACE;
    t[b'\n' as usize] = NEWLINE;
    t[b'\t' as usize] = OTHER_WS;
    t[b'\r' as usize] = OTHER_WS;
    t[0x0B] = OTHER_WS;
    t[0x0C] = OTHER_WS;
    t[b'#' as usize] = OTHER_WS;
    t
};

/// [`skip_ws`] beyond its fast cases.
fn skip_ws_loop(i: &str, nl: bool) -> &str {
    let b = i.as_bytes();
    let mut p = 0;
    while let Some(&c) = b.get(p) {
        match c {
            // the ASCII characters of `space` (`char::is_whitespace` but `\n`)
            b' ' | b'\t' | b'\r' | 0x0B | 0x0C => p += 1,
            b'\n' if nl => p += 1,
            // `comment`: up to (not including) the end of the line
            b'#' => match P::comment(&i[p..]) {
                Ok((rest, _)) => p = i.len() - rest.len(),
                Err(_) => break,
            },
            0x80.. => match first(&i[p..]) {
                Some(c) if is_space(c) => p += c.len_utf8(),
                _ => break,
            },
            _ => break,
        }
    }
    &i[p..]
}

/// Can an operand (an `atom`) start here? Used to detect `a b`.
///
/// Decided by a table on the first byte (this runs after every operand);
/// only `.` and non-ASCII characters look further.
#[inline]
fn starts_operand(i: &str) -> bool {
    match i.as_bytes().first().map(|&b| OPERAND_START[usize::from(b)]) {
        None | Some(OPERAND_NO) => false,
        Some(OPERAND_YES) => true,
        Some(_) => starts_operand_slow(i),
    }
}

/// [`starts_operand`] for `.` and non-ASCII characters.
#[inline(never)]
fn starts_operand_slow(i: &str) -> bool {
    match i.as_bytes() {
        [b'.', d, ..] => d.is_ascii_digit(),
        _ => starts_ident(i),
    }
}

/// Classes of a first byte for [`starts_operand`].
const OPERAND_NO: u8 = 0;
const OPERAND_YES: u8 = 1;
/// `.` (a number if a digit follows) and the bytes of non-ASCII characters.
const OPERAND_MAYBE: u8 = 2;

/// The class of each byte as the first byte of an operand: digits, ASCII
/// letters, `_`, `(` and `[` start one.
static OPERAND_START: [u8; 256] = {
    let mut t = [OPERAND_NO; 256];
    let mut b = 0;
    while b < 256 {
        let c = b as u8;
        if c.is_ascii_alphanumeric() || c == b'_' || c == b'(' || c == b'[' {
            t[b] = OPERAND_YES;
        } else if c == b'.' || c >= 0x80 {
            t[b] = OPERAND_MAYBE;
        }
        b += 1;
    }
    t
};

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

/// A `number` as written: `int.frac` times `10^exp` (the digit strings
/// are ASCII digits).
struct Decimal<'s> {
    int: &'s str,
    frac: &'s str,
    exp: i64,
}

impl Decimal<'_> {
    /// The exact value, in lowest terms.
    #[inline]
    fn value(&self) -> BigRational {
        exact_value(self.int, self.frac, self.exp)
    }
}

/// The exact value of the decimal number `int.frac` times `10^exp` (the
/// digit strings are ASCII digits), in lowest terms.
#[cfg_attr(not(debug_assertions), inline(always))]
fn exact_value(int: &str, frac: &str, exp: i64) -> BigRational {
    // fast path: the significant digits fit in a u64 (at most 19 digits)
    if int.len() + frac.len() <= 19 {
        let mut n = 0u64;
        for &c in int.as_bytes() {
            n = n * 10 + u64::from(c - b'0');
        }
        for &c in frac.as_bytes() {
            n = n * 10 + u64::from(c - b'0');
        }
        if n == 0 {
            return BigRational::zero();
        }
        let e = exp - frac.len() as i64;
        if e >= 0 {
            let m = u32::try_from(e)
                .ok()
                .and_then(|e| 10u64.checked_pow(e))
                .and_then(|p| n.checked_mul(p));
            if let Some(m) = m {
                return BigRational::from_integer(BigInt::from(m));
            }
        } else if let Some(d) = u32::try_from(-e).ok().and_then(|e| 10u64.checked_pow(e)) {
            let g = num_integer::gcd(n, d);
            return BigRational::new_raw(BigInt::from(n / g), BigInt::from(d / g));
        }
    }
    exact_value_big(int, frac, exp)
}

/// [`exact_value`] for numbers too long for machine integers.
#[cold]
#[inline(never)]
fn exact_value_big(int: &str, frac: &str, exp: i64) -> BigRational {
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
    BigRational::new(numer, denom)
}

/// The words of a `load` or `torque` statement, for parsing and messages.
struct Applied {
    keyword: &'static str,
    separator: &'static str,
    /// "a force": what comes after the keyword.
    first: &'static str,
    /// "force": the first expression in "`at` after the force".
    first_noun: &'static str,
    /// "a point": what comes after the separator.
    second: &'static str,
    /// "a load": the statement.
    what: &'static str,
    form: &'static str,
    parts: &'static str,
    example: &'static str,
}

const LOAD: Applied = Applied {
    keyword: "load",
    separator: "at",
    first: "a force",
    first_noun: "force",
    second: "a point",
    what: "a load",
    form: "load F at P",
    parts: "the force F, then `at` and the point P it acts on",
    example: "load [0, -m*g] at [x, y]",
};

const TORQUE: Applied = Applied {
    keyword: "torque",
    separator: "on",
    first: "a moment",
    first_noun: "moment",
    second: "an angle",
    what: "a torque",
    form: "torque M on phi",
    parts: "the moment M, then `on` and the angle phi it turns",
    example: "torque -c*phi' on phi",
};

// ---------------------------------------------------------------------------
// The parser

/// Parser state: the source (for offsets), the recursion depth, the
/// number of open parentheses and brackets (inside them a newline is white
/// space), and whether a stop word (`at`, `on`) ends the expression being
/// parsed (the first expression of a `load` or `torque` statement).
struct P<'s> {
    src: &'s str,
    nest: Cell<u32>,
    parens: Cell<u32>,
    stop: Cell<bool>,
}

impl<'s> P<'s> {
    fn new(src: &'s str) -> Self {
        P {
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
        let (msg, hint) = chars::unexpected(c, &shown);
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
    #[inline]
    fn enter(&self, i: &'s str) -> Result<Guard<'_>, nom::Err<PErr>> {
        let n = self.nest.get() + 1;
        if n > MAX_NESTING {
            return Err(self.too_nested(i));
        }
        self.nest.set(n);
        Ok(Guard(&self.nest))
    }

    /// [`P::enter`] at the token after the white space at `i`.
    #[inline]
    fn enter_ws(&self, i: &'s str) -> Result<Guard<'_>, nom::Err<PErr>> {
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
    fn too_nested(&self, i: &'s str) -> nom::Err<PErr> {
        let (span, _) = self.token(i);
        failure(
            Diagnostic::error(
                span,
                format!("expression nested too deeply (more than {MAX_NESTING} levels)"),
            )
            .with_hint("split it into several named definitions"),
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

    #[cfg_attr(not(debug_assertions), inline(always))]
    fn bin(&self, op: BinOp, l: Node, r: Node) -> Result<Node, nom::Err<PErr>> {
        let span = l.outer.to(r.outer);
        let d = l.d.max(r.d) + 1;
        let at = r.outer;
        self.node(ExprKind::Bin(op, l.e, r.e), span, d, at)
    }

    /// Final conversion of a parse error into a diagnostic. If a `(`, `[`
    /// or `{` left open before the error swallowed a line break (or the file
    /// ended inside it), the open bracket is the real problem and is reported
    /// instead.
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
                return Diagnostic::error(Span::new(open, open + 1), msg).with_hint(hint);
            }
        }
        d
    }

    // ----- white space -------------------------------------------------------

    /// `space ::= ( #x20 | #x09 | #x0D | #xFEFF | OtherWhiteSpace )+`
    fn space(i: &'s str) -> PResult<'s, &'s str> {
        let rest = i.trim_start_matches(is_space);
        if rest.len() == i.len() {
            return Err(nom::Err::Error(PErr::At(i.len())));
        }
        Ok((rest, &i[..i.len() - rest.len()]))
    }

    /// `comment ::= "#" [^#x0A]*`
    #[inline]
    fn comment(i: &'s str) -> PResult<'s, &'s str> {
        if !i.starts_with('#') {
            return Err(nom::Err::Error(PErr::At(i.len())));
        }
        let len = i.find('\n').unwrap_or(i.len());
        Ok((&i[len..], &i[..len]))
    }

    /// `newline ::= #x0A`
    fn newline(i: &'s str) -> PResult<'s, &'s str> {
        match i.strip_prefix('\n') {
            Some(rest) => Ok((rest, &i[..1])),
            None => Err(nom::Err::Error(PErr::At(i.len()))),
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

    /// `scene ::= line ( newline line )*`
    fn scene(&self, mut i: &'s str) -> PResult<'s, Vec<Stmt>> {
        // room for one statement per line (up to a bound), so that the
        // vector is not reallocated as it grows
        let lines = count_newlines(i.as_bytes()) + 1;
        let mut out = Vec::with_capacity(lines.min(256));
        loop {
            let (rest, ()) = self.line(i, &mut out)?;
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
    ///
    /// The statements are appended to `out`.
    fn line(&self, mut i: &'s str, out: &mut Vec<Stmt>) -> PResult<'s, ()> {
        loop {
            i = self.ws(i);
            let start = self.pos(i);
            if !matches!(i.as_bytes().first(), None | Some(b'\n' | b';')) {
                let (rest, stmt) = match self.statement(i) {
                    Err(nom::Err::Failure(PErr::Diag(d))) => {
                        return Err(failure(self.note_continuation(start, *d)))
                    }
                    other => other?,
                };
                out.push(stmt);
                i = self.ws(rest);
            }
            match i.as_bytes().first() {
                Some(b';') => i = &i[1..],
                None | Some(b'\n') => return Ok((i, ())),
                Some(_) => {
                    let d = self.unexpected(i);
                    return Err(failure(self.note_continuation(start, d)));
                }
            }
        }
    }

    /// If the statement starting at `start` ran over a line break outside
    /// parentheses and brackets before the error because a line ended in an
    /// operator, that trailing operator is the likely mistake, so the hint
    /// says so. (Inside a solve block a line break also ends an equation; a
    /// line that ends in anything else forgets an earlier operator.)
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
                        match last {
                            Some(op @ ('+' | '-' | '*' | '/' | '^')) => {
                                continued = Some((start + p, op))
                            }
                            Some(_) => continued = None,
                            None => {}
                        }
                    }
                    last = None;
                }
                _ if in_comment => {}
                '#' => in_comment = true,
                c if is_space(c) => {}
                c => {
                    match c {
                        '(' | '[' => depth += 1,
                        ')' | ']' => depth -= 1,
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

    /// `statement ::= declaration | role_stmt | force_stmt | load_stmt | torque_stmt | solve_block | latex_stmt | definition`
    ///
    /// Keywords do not reserve names: the tokens after the first identifier
    /// decide (see the grammar).
    fn statement(&self, i: &'s str) -> PResult<'s, Stmt> {
        // the first identifier, looked at without building an `Ident`
        let j = self.ws(i);
        let len = ident_len(j);
        if len == 0 {
            return self.fail(self.statement_start(i));
        }
        let (word, after) = j.split_at(len);
        let next = self.ws(after);
        let next_is_ident = starts_ident(next);
        let next_is_eq = next.starts_with('=');
        let at_end = matches!(next.as_bytes().first(), None | Some(b'\n' | b';'));
        match word {
            "coordinates" | "parameters" if !next_is_eq => {
                if next_is_ident {
                    self.declaration(i)
                } else if at_end {
                    self.fail(
                        Diagnostic::error(self.span(j, after), format!("empty `{word}` list"))
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
            "load" if !next_is_eq => self.load_stmt(i),
            "torque" if !next_is_eq => self.torque_stmt(i),
            "solve" if !next_is_eq => self.solve_block(i),
            "latex" if !next_is_eq => {
                if next_is_ident {
                    self.latex_stmt(i)
                } else {
                    self.fail(self.expected(
                        next,
                        "a name after `latex`",
                        "give a name its LaTeX like `latex theta3 = \"\\vartheta_{3}\"`; to define a name `latex`, write `latex = expression`",
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
            _ if !next_is_eq && !next.starts_with('(') => match keywords::suggest(word) {
                // a definition needs `=` next: this line is no definition
                Some(k) => {
                    if !word.is_ascii() {
                        // `pоtential` with a Cyrillic о: that letter first
                        self.check_letters(word, self.pos(j))?;
                    }
                    self.fail(
                        Diagnostic::error(self.span(j, after), format!("unknown keyword `{word}`"))
                            .with_hint(format!("did you mean `{k}`?")),
                    )
                }
                None => self.definition(i),
            },
            _ => self.definition(i),
        }
    }

    /// The error for a line that does not start with an identifier.
    fn statement_start(&self, i: &'s str) -> Diagnostic {
        let (span, shown) = self.token(i);
        match first(i) {
            Some(c) if c.is_ascii_digit() || c == '(' || c == '[' || c == '.' => Diagnostic::error(
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
        let (mut i, kw) = if let Some(rest) = i.strip_prefix("coordinates") {
            (rest, "coordinates")
        } else if let Some(rest) = i.strip_prefix("parameters") {
            (rest, "parameters")
        } else {
            return self.nothing(i);
        };
        let mut decls = Vec::new();
        let (rest, d) = self.decl(i)?;
        decls.push(d);
        i = rest;
        loop {
            let j = self.ws(i);
            match j.strip_prefix(',') {
                Some(k) => match self.decl(k) {
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
                None => {
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
        match j.strip_prefix(':') {
            Some(k) => match self.ident(k) {
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
            None => Ok((
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
        let rest = match self.equals(rest) {
            Ok(k) => k,
            Err(j) => {
                let head = format!("{} {}", role.keyword(), name.name);
                let hint = format!("write `{head} = expression`");
                return Err(self.equals_error(j, &head, &hint));
            }
        };
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
        let j = self.ws(i);
        let len = ident_len(j);
        if len == 0 {
            return self.nothing(j);
        }
        match Role::from_keyword(&j[..len]) {
            Some(r) => Ok((&j[len..], r)),
            None => self.nothing(i),
        }
    }

    /// `force_stmt ::= "force" ws ident ws ":" ws expr`
    fn force_stmt(&self, i: &'s str) -> PResult<'s, Stmt> {
        let i = self.ws(i);
        let start = self.pos(i);
        let Some(rest) = i.strip_prefix("force") else {
            return self.nothing(i);
        };
        let (rest, coordinate) = self.ident(rest)?;
        let j = self.ws(rest);
        let rest = match j.strip_prefix(':') {
            Some(k) => k,
            None => {
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

    /// `latex_stmt ::= "latex" ws ident ws "=" ws string`
    #[inline(never)]
    fn latex_stmt(&self, i: &'s str) -> PResult<'s, Stmt> {
        let i = self.ws(i);
        let start = self.pos(i);
        let Some(rest) = i.strip_prefix("latex") else {
            return self.nothing(i);
        };
        let (rest, name) = self.ident(rest)?;
        let hint = format!(
            "write the notation in double quotes: `latex {} = \"\\vartheta_{{3}}\"`",
            name.name
        );
        let rest = match self.equals(rest) {
            Ok(k) => k,
            Err(j) => {
                return Err(self.equals_error(j, &format!("latex {}", name.name), &hint));
            }
        };
        let j = self.ws(rest);
        let (rest, tex) = match self.string(j) {
            Ok(x) => x,
            Err(nom::Err::Error(_)) => {
                return self.fail(self.expected(j, "a string in double quotes", &hint, None));
            }
            Err(e) => return Err(e),
        };
        let span = Span::new(start, self.pos(rest));
        Ok((rest, Stmt::Latex { name, tex, span }))
    }

    /// `string ::= '"' [^"#x0A]* '"'` (not empty; no escapes: a backslash
    /// is itself)
    fn string(&self, i: &'s str) -> PResult<'s, String> {
        let Some(body) = i.strip_prefix('"') else {
            return self.nothing(i);
        };
        let end = body.find(['"', '\n']).unwrap_or(body.len());
        if !body[end..].starts_with('"') {
            let open = Span::new(self.pos(i), self.pos(i) + 1);
            return self.fail(
                Diagnostic::error(open, "this string is not closed on its line")
                    .with_hint("end the string with `\"` before the end of the line"),
            );
        }
        if end == 0 {
            return self.fail(
                Diagnostic::error(self.span(i, &body[1..]), "empty LaTeX notation")
                    .with_hint("write the notation between the quotes, e.g. `\"\\vartheta_{3}\"`"),
            );
        }
        Ok((&body[end + 1..], body[..end].to_string()))
    }

    /// `load_stmt ::= "load" ws expr ws "at" ws expr`
    ///
    /// The force ends at the stop word `at` (see the grammar). (Not inlined,
    /// like the other new statements and [`P::vector`]: they are rare, and
    /// inlined they would make the hot paths larger.)
    #[inline(never)]
    fn load_stmt(&self, i: &'s str) -> PResult<'s, Stmt> {
        let (rest, (force, point, span)) = self.applied(i, &LOAD)?;
        Ok((rest, Stmt::Load { force, point, span }))
    }

    /// `torque_stmt ::= "torque" ws expr ws "on" ws expr`
    ///
    /// The moment ends at the stop word `on` (see the grammar).
    #[inline(never)]
    fn torque_stmt(&self, i: &'s str) -> PResult<'s, Stmt> {
        let (rest, (moment, angle, span)) = self.applied(i, &TORQUE)?;
        Ok((
            rest,
            Stmt::Torque {
                moment,
                angle,
                span,
            },
        ))
    }

    /// `KEYWORD ws expr ws SEPARATOR ws expr` (a `load_stmt` or a
    /// `torque_stmt`): both expressions and the statement's span.
    fn applied(&self, i: &'s str, w: &Applied) -> PResult<'s, (Expr, Expr, Span)> {
        let i = self.ws(i);
        let start = self.pos(i);
        let Some(rest) = i.strip_prefix(w.keyword) else {
            return self.nothing(i);
        };
        let kw_span = self.span(i, rest);
        // the first expression, ended by the stop word
        self.stop.set(true);
        let first = self.expr(rest);
        self.stop.set(false);
        let (rest, first) = match first {
            Ok((rest, node)) => (rest, node),
            Err(e) => return Err(self.applied_error(e, rest, w, kw_span, true)),
        };
        let j = self.ws(rest);
        let len = w.separator.len();
        let sep = j
            .strip_prefix(w.separator)
            .filter(|k| !starts_with_class(k, ident_char) && !k.starts_with('('));
        let Some(k) = sep else {
            return Err(self.separator_error(j, w, &first));
        };
        let sep_span = Span::new(self.pos(j), self.pos(j) + len);
        let (rest, second) = match self.expr(k) {
            Ok(x) => x,
            Err(e) => return Err(self.applied_error(e, k, w, sep_span, false)),
        };
        let span = Span::new(start, second.outer.end);
        Ok((rest, (*first.e, *second.e, span)))
    }

    /// The error for a missing first (`first`) or second expression at `k`
    /// of a `load` or `torque` statement, after the token at `after`.
    #[cold]
    #[inline(never)]
    fn applied_error(
        &self,
        e: nom::Err<PErr>,
        k: &'s str,
        w: &Applied,
        after: Span,
        first: bool,
    ) -> nom::Err<PErr> {
        if !matches!(e, nom::Err::Error(_)) {
            return e;
        }
        let j = self.ws(k);
        let (what, after_word) = if first {
            (w.first, w.keyword)
        } else {
            (w.second, w.separator)
        };
        let mut hint = format!("{} is written `{}`, like `{}`", w.what, w.form, w.example);
        if first {
            hint.push_str(&format!(
                "; to define a name `{0}`, write `{0} = expression`",
                w.keyword
            ));
        }
        failure(self.expected(
            j,
            &format!("{what} after `{after_word}`"),
            &hint,
            Some(after),
        ))
    }

    /// The error when the separator (`at`, `on`) is missing at `j`, after
    /// the first expression `first`.
    #[cold]
    #[inline(never)]
    fn separator_error(&self, j: &'s str, w: &Applied, first: &Node) -> nom::Err<PErr> {
        let sep = w.separator;
        // `load at P`: the "force" is the bare word `at` (as written, not
        // parenthesized), so the force is missing
        if matches!(&first.e.kind, ExprKind::Name(n) if n == sep) && first.outer == first.e.span {
            let at = &self.src[first.outer.start..];
            let hint = format!(
                "{} is written `{}`, like `{}`; the {} is missing before `{sep}` (for a name `{sep}`, write `({sep})`)",
                w.what, w.form, w.example, w.first_noun
            );
            return failure(self.expected(
                at,
                &format!("{} after `{}`", w.first, w.keyword),
                &hint,
                None,
            ));
        }
        let mut hint = format!("{} is written `{}`: {}", w.what, w.form, w.parts);
        let text = &self.src[first.outer.start..first.outer.end];
        let number = text
            .strip_suffix(sep)
            .map(|head| head.trim_end_matches(|c: char| c.is_ascii_digit() || c == '.'))
            .filter(|n| n.len() + sep.len() < text.len() && !n.ends_with(ident_char));
        if let Some(n) = number {
            // `load 2at P`: the number and `at` form an implicit product
            let glued = &text[n.len()..];
            hint.push_str(&format!(
                "; `{glued}` is an implicit product, write a space before `{sep}`"
            ));
        } else if j.starts_with(sep) && j[sep.len()..].starts_with('(') {
            hint = format!(
                "directly before `(`, `{0}` is a call: write a space, `{0} (…)`",
                w.separator
            );
        } else if j.starts_with('=') {
            hint.push_str(&format!(
                "; to define a name `{0}`, write `{0} = expression`",
                w.keyword
            ));
        }
        failure(self.expected(
            j,
            &format!(
                "`{}` after the {} in `{}`",
                w.separator, w.first_noun, w.form
            ),
            &hint,
            None,
        ))
    }

    /// `solve_block ::= "solve" ws ident ( ws "," ws ident )* ws "{" block_ws equation ( ws ( ";" | newline ) block_ws equation )* block_ws "}"`
    #[inline(never)]
    fn solve_block(&self, i: &'s str) -> PResult<'s, Stmt> {
        let i = self.ws(i);
        let start = self.pos(i);
        let Some(rest) = i.strip_prefix("solve") else {
            return self.nothing(i);
        };
        // the unknowns
        let mut unknowns = Vec::new();
        let (mut rest, first) = match self.ident(rest) {
            Ok(x) => x,
            Err(nom::Err::Error(_)) => {
                return self.fail(self.expected(
                    self.ws(rest),
                    "the unknowns after `solve`",
                    "name the unknowns before the equations: `solve x, y { … }`; to define a name `solve`, write `solve = expression`",
                    None,
                ))
            }
            Err(e) => return Err(e),
        };
        unknowns.push(first);
        loop {
            let j = self.ws(rest);
            let Some(k) = j.strip_prefix(',') else {
                rest = j;
                break;
            };
            match self.ident(k) {
                Ok((after, name)) => {
                    unknowns.push(name);
                    rest = after;
                }
                Err(nom::Err::Error(_)) => {
                    return self.fail(self.expected(
                        self.ws(k),
                        "a name after `,`",
                        "list the unknowns separated by commas: `solve x, y { … }`",
                        None,
                    ))
                }
                Err(e) => return Err(e),
            }
        }
        // `{`, on this line
        let Some(body) = rest.strip_prefix('{') else {
            return Err(self.open_brace_error(rest));
        };
        let open = self.pos(rest);
        let mut equations = Vec::new();
        let mut k = self.block_ws(body);
        loop {
            match k.as_bytes().first() {
                Some(b'}') if equations.is_empty() => return Err(self.empty_block(open, k)),
                Some(b'}') => break,
                None => return Err(unclosed_block(open)),
                _ => {}
            }
            let (rest, eq) = self.equation(k)?;
            equations.push(eq);
            let j = self.ws(rest);
            k = match j.as_bytes().first() {
                Some(b';' | b'\n') => self.block_ws(&j[1..]),
                Some(b'}') => j,
                None => return Err(unclosed_block(open)),
                Some(b'=') => return Err(self.second_equals(j)),
                Some(_) => return Err(self.after_equation(j)),
            };
        }
        let after = &k[1..];
        let span = Span::new(start, self.pos(after));
        let j = self.ws(after);
        if !matches!(j.as_bytes().first(), None | Some(b'\n' | b';')) {
            return Err(self.after_block(j));
        }
        Ok((
            after,
            Stmt::Solve(SolveBlock {
                unknowns,
                equations,
                span,
            }),
        ))
    }

    /// The error when the `{` of a solve block is missing at `j`.
    #[cold]
    #[inline(never)]
    fn open_brace_error(&self, j: &'s str) -> nom::Err<PErr> {
        if starts_operand(j) {
            let (span, shown) = self.token(j);
            return failure(
                Diagnostic::error(span, format!("expected `,` before {shown}"))
                    .with_hint("separate the unknowns with commas: `solve x, y { … }`"),
            );
        }
        failure(self.expected(
            j,
            "`{` after the unknowns of `solve`",
            "the equations follow in braces that open on the `solve` line: `solve x, y { … }`",
            None,
        ))
    }

    /// The error for a solve block without equations (`{` at `open`, `}` at
    /// `close`).
    #[cold]
    #[inline(never)]
    fn empty_block(&self, open: usize, close: &'s str) -> nom::Err<PErr> {
        let end = self.pos(close) + 1;
        // the whole `{ … }` if it is on one line, else the `{`
        let end = if self.src[open..end].contains('\n') {
            open + 1
        } else {
            end
        };
        failure(
            Diagnostic::error(Span::new(open, end), "empty solve block").with_hint(
                "write the equations inside the braces, one per line or separated by `;`: `solve x { a*x = b }`",
            ),
        )
    }

    /// The error for the token at `j` after an equation (not `;`, a line
    /// break, `}` or `=`).
    #[cold]
    #[inline(never)]
    fn after_equation(&self, j: &'s str) -> nom::Err<PErr> {
        if matches!(j.as_bytes().first(), Some(b')' | b']')) {
            return failure(self.unexpected(j));
        }
        failure(self.expected(
            j,
            "`;`, a line break or `}` after the equation",
            "put each equation on its own line or separate them with `;`",
            None,
        ))
    }

    /// The error for the token at `j` after the `}` of a solve block.
    #[cold]
    #[inline(never)]
    fn after_block(&self, j: &'s str) -> nom::Err<PErr> {
        if matches!(j.as_bytes().first(), Some(b')' | b']' | b'}')) {
            return failure(self.unexpected(j));
        }
        failure(self.expected(
            j,
            "the end of the line after `}`",
            "a solve block ends its statement: start the next statement on a new line, or after `;`",
            None,
        ))
    }

    /// The error for a second `=` at `j` in one equation.
    #[cold]
    #[inline(never)]
    fn second_equals(&self, j: &'s str) -> nom::Err<PErr> {
        failure(
            Diagnostic::error(self.token(j).0, "an equation has exactly one `=`").with_hint(
                "write each equation on its own line or separate them with `;`: `a = b; b = c`",
            ),
        )
    }

    /// `block_ws ::= ( space | comment | newline | ";" )*`
    fn block_ws(&self, mut i: &'s str) -> &'s str {
        loop {
            i = self.ws_nl(i);
            match i.strip_prefix(';') {
                Some(rest) => i = rest,
                None => return i,
            }
        }
    }

    /// `equation ::= expr ws "=" ws expr`
    fn equation(&self, i: &'s str) -> PResult<'s, Equation> {
        let (rest, lhs) = match self.expr(i) {
            Ok(x) => x,
            Err(e) => return Err(self.equation_error(e, i)),
        };
        let j = self.ws(rest);
        let Some(k) = j.strip_prefix('=') else {
            return Err(self.no_equals(j, lhs.outer));
        };
        let (rest, (rhs, outer)) = self.rhs(k, "=")?;
        let span = lhs.outer.to(outer);
        Ok((
            rest,
            Equation {
                lhs: *lhs.e,
                rhs,
                span,
            },
        ))
    }

    /// The error for a missing left side at `i` of an equation.
    #[cold]
    #[inline(never)]
    fn equation_error(&self, e: nom::Err<PErr>, i: &'s str) -> nom::Err<PErr> {
        if !matches!(e, nom::Err::Error(_)) {
            return e;
        }
        let what = if i.starts_with('=') {
            "an expression before `=`"
        } else {
            "an equation"
        };
        failure(self.expected(
            i,
            what,
            "an equation is written `lhs = rhs`, one per line or separated by `;`",
            None,
        ))
    }

    /// The error when no `=` follows (at `j`) the left side `lhs` of an
    /// equation.
    #[cold]
    #[inline(never)]
    fn no_equals(&self, j: &'s str, lhs: Span) -> nom::Err<PErr> {
        if matches!(j.as_bytes().first(), None | Some(b'\n' | b';' | b'}')) {
            let l = excerpt(&self.src[lhs.start..lhs.end]);
            return failure(
                Diagnostic::error(lhs, "an equation needs `=`")
                    .with_hint(format!("write it as `lhs = rhs`, like `{l} = 0`")),
            );
        }
        failure(self.expected(
            j,
            "`=` after the left side of the equation",
            "an equation is written `lhs = rhs`",
            None,
        ))
    }

    /// `definition ::= ident ws "=" ws expr`
    fn definition(&self, i: &'s str) -> PResult<'s, Stmt> {
        let (rest, name) = self.ident(i)?;
        let rest = match self.equals(rest) {
            Ok(k) => k,
            Err(j) => {
                let hint = if rest.starts_with('(') {
                    format!(
                        "functions can't be defined in a scene; define a name instead: `{} = expression`",
                        name.name
                    )
                } else {
                    format!("a definition is written `{} = expression`", name.name)
                };
                return Err(self.equals_error(j, &name.name, &hint));
            }
        };
        let (rest, (value, outer)) = self.rhs(rest, "=")?;
        let span = name.span.to(outer);
        Ok((rest, Stmt::Def { name, value, span }))
    }

    /// The `"="` of a definition or role statement: the input after it, or
    /// (as the error) the input where it is missing.
    fn equals(&self, i: &'s str) -> Result<&'s str, &'s str> {
        let j = self.ws(i);
        j.strip_prefix('=').ok_or(j)
    }

    /// The error for a missing `"="` at `j`, after `head`.
    #[cold]
    #[inline(never)]
    fn equals_error(&self, j: &'s str, head: &str, hint: &str) -> nom::Err<PErr> {
        failure(self.expected(j, &format!("`=` after `{head}`"), hint, None))
    }

    /// The expression after `=` or `:` that ends a statement, with the
    /// source span it came from (including enclosing parentheses).
    fn rhs(&self, i: &'s str, after: &str) -> PResult<'s, (Expr, Span)> {
        match self.expr(i) {
            Ok((rest, node)) => Ok((rest, (*node.e, node.outer))),
            Err(e) => Err(self.rhs_error(e, i, after)),
        }
    }

    /// The error for a missing expression at `i`, after `after`.
    #[cold]
    #[inline(never)]
    fn rhs_error(&self, e: nom::Err<PErr>, i: &'s str, after: &str) -> nom::Err<PErr> {
        if !matches!(e, nom::Err::Error(_)) {
            return e;
        }
        let op_span = Span::new(self.pos(i) - after.len(), self.pos(i));
        failure(self.expected(
            self.ws(i),
            &format!("an expression after `{after}`"),
            HINT_EXPR,
            Some(op_span),
        ))
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
    #[inline(never)]
    fn expr(&self, i: &'s str) -> PResult<'s, Node> {
        let _g = self.enter_ws(i)?;
        self.sum(i)
    }

    /// `sum ::= product ( ws ( "+" | "-" ) ws_nl product )*`
    fn sum(&self, i: &'s str) -> PResult<'s, Node> {
        let (mut i, mut lhs) = self.product(i)?;
        loop {
            let j = self.ws(i);
            let (op, op_str) = match j.as_bytes().first() {
                Some(b'+') => (BinOp::Add, "+"),
                Some(b'-') => (BinOp::Sub, "-"),
                _ => break,
            };
            let k = &j[1..];
            let op_span = self.span(j, k);
            let k = self.ws_nl(k);
            let (rest, rhs) = match self.product(k) {
                Ok(x) => x,
                Err(e) => return Err(self.op_error(e, k, op_str, op_span)),
            };
            lhs = self.bin(op, lhs, rhs)?;
            i = rest;
        }
        Ok((i, lhs))
    }

    /// `product ::= unary ( ws ( "*" | "/" ) ws_nl unary | implicit_factor )*`
    #[cfg_attr(not(debug_assertions), inline(always))]
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
            let (op, op_str) = match j.as_bytes().first() {
                Some(b'*') => (BinOp::Mul, "*"),
                Some(b'/') => (BinOp::Div, "/"),
                _ => {
                    self.side_by_side(j, last, last_is_name)?;
                    return Ok((i, lhs));
                }
            };
            let k = &j[1..];
            let op_span = self.span(j, k);
            if op == BinOp::Mul && k.starts_with('*') {
                return Err(star_star(op_span));
            }
            let k = self.ws_nl(k);
            let (rest, rhs) = match self.unary(k) {
                Ok(x) => x,
                Err(e) => return Err(self.op_error(e, k, op_str, op_span)),
            };
            last = rhs.outer;
            last_is_name = matches!(rhs.e.kind, ExprKind::Name(_));
            lhs = self.bin(op, lhs, rhs)?;
            i = rest;
        }
    }

    /// Is an implicit product allowed at `i` (directly after a number or `)`)?
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn implicit_here(&self, i: &str) -> bool {
        let p = self.pos(i);
        // a non-ASCII character never ends in an ASCII byte
        match self.src.as_bytes()[..p].last() {
            Some(d) if d.is_ascii_digit() => i.starts_with('(') || starts_ident(i),
            Some(b')') => i.starts_with('('),
            _ => false,
        }
    }

    /// `implicit_factor ::= power` — only where [`P::implicit_here`] holds.
    fn implicit_factor(&self, i: &'s str) -> PResult<'s, Node> {
        self.power(i)
    }

    /// Reject two operands side by side (`a b`) with a helpful hint; `j` is
    /// after the white space following the left operand. Where a stop word
    /// is active (the first expression of `load` or `torque`), the
    /// expression ends instead: the statement then expects its keyword.
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn side_by_side(
        &self,
        j: &'s str,
        left: Span,
        left_is_name: bool,
    ) -> Result<(), nom::Err<PErr>> {
        if !starts_operand(j) || self.stopping() {
            return Ok(());
        }
        Err(self.side_by_side_error(j, left, left_is_name))
    }

    /// The error for an operand at `j` right after the operand at `left`.
    #[cold]
    #[inline(never)]
    fn side_by_side_error(&self, j: &'s str, left: Span, left_is_name: bool) -> nom::Err<PErr> {
        let right = match self.power(j) {
            Ok((_, r)) => r.outer,
            Err(nom::Err::Error(_)) => self.token(j).0,
            Err(e) => return e,
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
        failure(Diagnostic::error(right, "two expressions side by side").with_hint(hint))
    }

    /// `unary ::= ws ( "-" | "+" ) unary | power`
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn unary(&self, i: &'s str) -> PResult<'s, Node> {
        let j = self.ws(i);
        match j.as_bytes().first() {
            Some(b'-') => self.signed(j, "-"),
            Some(b'+') => self.signed(j, "+"),
            _ => self.power(j),
        }
    }

    /// The first alternative of `unary`: `sign` at `j`, then a `unary`.
    #[inline(never)]
    fn signed(&self, j: &'s str, sign: &'static str) -> PResult<'s, Node> {
        let k = &j[1..];
        let _g = self.enter(j)?;
        let sign_span = self.span(j, k);
        let (rest, inner) = match self.unary(k) {
            Ok(x) => x,
            Err(e) => return Err(self.op_error(e, k, sign, sign_span)),
        };
        let span = sign_span.to(inner.outer);
        if sign == "-" {
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
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn power(&self, i: &'s str) -> PResult<'s, Node> {
        let (i, base) = self.postfix(i)?;
        let j = self.ws(i);
        let Some(k) = j.strip_prefix('^') else {
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
        let sign = match j.as_bytes().first() {
            Some(b'-') => "-",
            Some(b'+') => "+",
            _ => return self.power(j),
        };
        let k = &j[1..];
        let sign_span = self.span(j, k);
        let (rest, inner) = match self.exponent(k) {
            Ok(x) => x,
            Err(e) => return Err(self.op_error(e, k, sign, sign_span)),
        };
        let span = sign_span.to(inner.outer);
        if sign == "-" {
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
    ///
    /// `i` is after white space: [`P::power`] is only called there.
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn postfix(&self, i: &'s str) -> PResult<'s, Node> {
        let start = i;
        let (mut i, a) = self.atom(start)?;
        let mut order: u32 = 0;
        let mut first_prime = None;
        loop {
            let j = self.ws(i);
            match j.strip_prefix('\'') {
                Some(k) => {
                    first_prime.get_or_insert(self.span(j, k));
                    order = order.saturating_add(1);
                    i = k;
                }
                None => break,
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

    /// `atom ::= literal | call | name | group | vector`
    ///
    /// `i` is after white space (see [`P::postfix`]).
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn atom(&self, i: &'s str) -> PResult<'s, Node> {
        match i.as_bytes().first() {
            Some(c) if c.is_ascii_digit() => self.literal(i),
            Some(b'.') if starts_operand(i) => self.literal(i),
            Some(b'(') => self.group(i),
            _ => match ident_len(i) {
                // `[` is tested last (a vector is rare; the hot path of
                // names stays as short as it was)
                0 => self.vector(i),
                len if i[len..].starts_with('(') => self.call(i),
                len => self.name(i, len),
            },
        }
    }

    /// `call ::= ident "(" ws_nl ( arg ( ws_nl "," ws_nl arg )* ws_nl )? ")"`
    fn call(&self, i: &'s str) -> PResult<'s, Node> {
        let (rest, name) = self.ident(i)?;
        let Some(mut k) = rest.strip_prefix('(') else {
            return self.nothing(rest);
        };
        let open = self.pos(rest);
        let _p = self.open_paren();
        let mut args = Vec::new();
        let mut d = 0;
        let j = self.ws(k);
        if let Some(after) = j.strip_prefix(')') {
            k = after;
        } else {
            loop {
                let (rest, arg) = match self.arg(k) {
                    Ok(x) => x,
                    Err(e) => return Err(self.arg_error(e, k, &name, args.is_empty())),
                };
                d = d.max(arg.d);
                args.push(*arg.e);
                let j = self.ws(rest);
                match j.as_bytes().first() {
                    Some(b',') => k = &j[1..],
                    Some(b')') => {
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

    /// `arg ::= expr ( ws_nl "=" ws_nl expr )?`
    fn arg(&self, i: &'s str) -> PResult<'s, Node> {
        let (rest, arg) = self.expr(i)?;
        let j = self.ws(rest);
        let Some(after) = j.strip_prefix('=') else {
            return Ok((rest, arg));
        };
        let (rest, value) = match self.expr(after) {
            Ok(x) => x,
            Err(nom::Err::Error(_)) => {
                return Err(failure(self.expected(
                    self.ws(after),
                    "a value after `=`",
                    "a named argument is written `x = value`, as in subs(E, x = 0)",
                    None,
                )))
            }
            Err(e) => return Err(e),
        };
        let span = arg.outer.to(value.outer);
        let d = arg.d.max(value.d) + 1;
        let at = value.outer;
        Ok((
            rest,
            self.node(ExprKind::Assign(arg.e, value.e), span, d, at)?,
        ))
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
    ///
    /// `i` is after white space and starts with an `ident` of `len` bytes
    /// (scanned by [`P::atom`]).
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn name(&self, i: &'s str, len: usize) -> PResult<'s, Node> {
        let start = self.pos(i);
        let span = Span::new(start, start + len);
        if !i.as_bytes()[..len].is_ascii() {
            self.check_letters(&i[..len], start)?;
        }
        Ok((
            &i[len..],
            Self::leaf(ExprKind::Name(i[..len].to_string()), span),
        ))
    }

    /// `group ::= "(" ws_nl expr ws_nl ")"`
    fn group(&self, i: &'s str) -> PResult<'s, Node> {
        let Some(k) = i.strip_prefix('(') else {
            return self.nothing(i);
        };
        let open = self.pos(i);
        let _p = self.open_paren();
        let (rest, mut inner) = match self.expr(k) {
            Ok(x) => x,
            Err(e) => return Err(self.group_error(e, k, open)),
        };
        let j = self.ws(rest);
        match j.strip_prefix(')') {
            Some(after) => {
                inner.outer = Span::new(open, self.pos(after));
                Ok((after, inner))
            }
            None => Err(failure(self.close_expected(j, open, "`)`"))),
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

    /// `vector ::= "[" ws_nl expr ( ws_nl "," ws_nl expr )* ws_nl "]"`
    ///
    /// "Nothing here" unless `i` starts with `[`.
    #[inline(never)]
    fn vector(&self, i: &'s str) -> PResult<'s, Node> {
        let Some(mut k) = i.strip_prefix('[') else {
            return self.nothing(i);
        };
        let open = self.pos(i);
        let _p = self.open_paren();
        let mut components = Vec::new();
        let mut d = 0;
        loop {
            let (rest, c) = match self.expr(k) {
                Ok(x) => x,
                Err(e) => return Err(self.component_error(e, k, open, components.is_empty())),
            };
            d = d.max(c.d);
            components.push(*c.e);
            let j = self.ws(rest);
            match j.as_bytes().first() {
                Some(b',') => k = &j[1..],
                Some(b']') => {
                    k = &j[1..];
                    break;
                }
                _ => return Err(self.vector_unclosed(j, open)),
            }
        }
        let span = Span::new(open, self.pos(k));
        let at = Span::new(open, open + 1);
        Ok((k, self.node(ExprKind::Vector(components), span, d + 1, at)?))
    }

    /// The error for a missing component at `k` of the vector opened at
    /// `open` (`first`: no component yet).
    #[cold]
    #[inline(never)]
    fn component_error(
        &self,
        e: nom::Err<PErr>,
        k: &'s str,
        open: usize,
        first: bool,
    ) -> nom::Err<PErr> {
        if !matches!(e, nom::Err::Error(_)) {
            return e;
        }
        let at = self.ws(k);
        if at.is_empty() {
            return unclosed_bracket(open);
        }
        let closes = at.starts_with(']');
        let d = if first && closes {
            Diagnostic::error(
                Span::new(open, self.pos(at) + 1),
                "a vector needs at least one component",
            )
            .with_hint("write its components separated by commas, like `[x, y]`")
        } else if first {
            self.expected(at, "an expression after `[`", HINT_EXPR, None)
        } else if closes {
            self.expected(at, "a component after `,`", "remove the trailing `,`", None)
        } else {
            self.expected(at, "a component after `,`", HINT_EXPR, None)
        };
        failure(d)
    }

    /// The error when neither `,` nor `]` follows (at `j`) a component of
    /// the vector opened at `open`.
    #[cold]
    #[inline(never)]
    fn vector_unclosed(&self, j: &'s str, open: usize) -> nom::Err<PErr> {
        if j.is_empty() {
            return unclosed_bracket(open);
        }
        let (line, col) = Diagnostic::line_col(self.src, open);
        failure(self.expected(
            j,
            "`,` or `]` after a component of the vector",
            &format!("the `[` at line {line}, column {col} is still open"),
            None,
        ))
    }

    // ----- tokens ------------------------------------------------------------

    /// `literal ::= number angle_unit?`
    ///
    /// `i` is after white space (see [`P::atom`]).
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn literal(&self, i: &'s str) -> PResult<'s, Node> {
        let (rest, number) = self.number(i)?;
        // the value is built last, in place (it is large to move)
        let (rest, degrees) = match self.angle_unit(rest) {
            Ok((rest, _)) => (rest, true),
            Err(_) => (rest, false),
        };
        let span = self.span(i, rest);
        let kind = if degrees {
            ExprKind::Degrees(number.value())
        } else {
            ExprKind::Num(number.value())
        };
        Ok((rest, Self::leaf(kind, span)))
    }

    /// `angle_unit ::= "deg" | space? "°"` — `deg` not followed by an `ident_char`.
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn angle_unit(&self, i: &'s str) -> PResult<'s, &'s str> {
        if let Some(rest) = i.strip_prefix("deg") {
            if !starts_with_class(rest, ident_char) {
                return Ok((rest, &i[..3]));
            }
            return self.nothing(i);
        }
        let j = match Self::space(i) {
            Ok((rest, _)) => rest,
            Err(_) => i,
        };
        match j.strip_prefix('°') {
            Some(rest) => Ok((rest, &j[..j.len() - rest.len()])),
            None => self.nothing(j),
        }
    }

    /// `number ::= digits ( "." digits )? sci_exponent?`
    ///
    /// Scanned on bytes; the value is computed with machine integers when
    /// it fits (see [`exact_value`]).
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn number(&self, i: &'s str) -> PResult<'s, Decimal<'s>> {
        if let Some(after_dot) = i.strip_prefix('.') {
            return match Self::digits(after_dot) {
                Ok((rest, frac)) => Err(self.leading_dot(i, rest, frac)),
                Err(_) => self.nothing(i),
            };
        }
        let (mut rest, int) = Self::digits(i)?;
        let mut frac = "";
        if let Some(after_dot) = rest.strip_prefix('.') {
            match Self::digits(after_dot) {
                Ok((after, f)) => {
                    frac = f;
                    rest = after;
                }
                Err(_) => return Err(self.trailing_dot(i, after_dot, int)),
            }
        }
        let (rest, exp) = match self.sci_exponent(rest) {
            Ok((after, e)) => (after, e),
            Err(nom::Err::Error(_)) => (rest, 0),
            Err(e) => return Err(e),
        };
        if rest.starts_with('.') {
            return Err(self.second_dot(i, rest));
        }
        Ok((rest, Decimal { int, frac, exp }))
    }

    /// The error for `.5`.
    #[cold]
    #[inline(never)]
    fn leading_dot(&self, i: &'s str, rest: &'s str, frac: &str) -> nom::Err<PErr> {
        failure(
            Diagnostic::error(
                self.span(i, rest),
                "a number can't start with a decimal point",
            )
            .with_hint(format!("write `0.{frac}`")),
        )
    }

    /// The error for `3.`.
    #[cold]
    #[inline(never)]
    fn trailing_dot(&self, i: &'s str, after_dot: &'s str, int: &str) -> nom::Err<PErr> {
        failure(
            Diagnostic::error(
                self.span(i, after_dot),
                format!("malformed number `{int}.`"),
            )
            .with_hint(format!(
                "a decimal point must be followed by digits: write `{int}.0` or `{int}`"
            )),
        )
    }

    /// The error for `1.2.3` or `1e3.5` (a `.` at `rest`, after the number).
    #[cold]
    #[inline(never)]
    fn second_dot(&self, i: &'s str, rest: &'s str) -> nom::Err<PErr> {
        let end = rest
            .find(|c: char| !(c.is_ascii_digit() || c == '.'))
            .unwrap_or(rest.len());
        let span = Span::new(self.pos(i), self.pos(rest) + end);
        failure(
            Diagnostic::error(
                span,
                format!("malformed number `{}`", &self.src[span.start..span.end]),
            )
            .with_hint(
                "a number has at most one decimal point, before any exponent: `1.25`, `1.5e-3`",
            ),
        )
    }

    /// `sci_exponent ::= [eE] [+-]? digits` — taken only when a digit follows.
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn sci_exponent(&self, i: &'s str) -> PResult<'s, i64> {
        let b = i.as_bytes();
        if !matches!(b.first(), Some(b'e' | b'E')) {
            return self.nothing(i);
        }
        let (negative, at) = match b.get(1) {
            Some(b'-') => (true, 2),
            Some(b'+') => (false, 2),
            _ => (false, 1),
        };
        let (rest, digits) = Self::digits(&i[at..])?;
        let significant = digits.trim_start_matches('0');
        let n: u32 = if significant.len() > 6 {
            u32::MAX
        } else {
            significant.parse().unwrap_or(0)
        };
        if n > MAX_EXPONENT {
            return Err(self.exponent_out_of_range(i, rest));
        }
        let n = i64::from(n);
        Ok((rest, if negative { -n } else { n }))
    }

    /// The error for an exponent beyond [`MAX_EXPONENT`].
    #[cold]
    #[inline(never)]
    fn exponent_out_of_range(&self, i: &'s str, rest: &'s str) -> nom::Err<PErr> {
        failure(
            Diagnostic::error(self.span(i, rest), "exponent out of range")
                .with_hint(format!("exponents up to {MAX_EXPONENT} are accepted")),
        )
    }

    /// `digits ::= [0-9]+`
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn digits(i: &'s str) -> PResult<'s, &'s str> {
        match digits_len(i) {
            0 => Err(nom::Err::Error(PErr::At(i.len()))),
            n => Ok((&i[n..], &i[..n])),
        }
    }

    /// `ident ::= ident_start ident_char*`
    fn ident(&self, i: &'s str) -> PResult<'s, Ident> {
        let i = self.ws(i);
        let len = ident_len(i);
        if len == 0 {
            return self.nothing(i);
        }
        if !i.as_bytes()[..len].is_ascii() {
            self.check_letters(&i[..len], self.pos(i))?;
        }
        Ok((
            &i[len..],
            Ident {
                name: i[..len].to_string(),
                span: Span::new(self.pos(i), self.pos(i) + len),
            },
        ))
    }
}

impl P<'_> {
    /// Refuse a look-alike letter in the name `name` at byte `start` (see
    /// [`chars::refused_letter`]).
    #[cold]
    #[inline(never)]
    fn check_letters(&self, name: &str, start: usize) -> Result<(), nom::Err<PErr>> {
        match chars::refused_letter(name) {
            None => Ok(()),
            Some((p, c, message, hint)) => {
                let at = Span::new(start + p, start + p + c.len_utf8());
                Err(failure(Diagnostic::error(at, message).with_hint(hint)))
            }
        }
    }
}

/// The innermost bracket (`(`, `[` or `{`, with its offset) that is still
/// open at the end of `src` and starts before `limit` (comments are skipped).
/// `)` and `]` close the last open `(` or `[`; `}` closes the last open `{`.
fn unclosed_before(src: &str, limit: usize) -> Option<(usize, u8)> {
    let mut parens = Vec::new();
    let mut braces = Vec::new();
    let mut in_comment = false;
    for (p, c) in src.bytes().enumerate() {
        match c {
            b'\n' => in_comment = false,
            _ if in_comment => {}
            b'#' => in_comment = true,
            b'(' | b'[' => parens.push((p, c)),
            b')' | b']' => {
                parens.pop();
            }
            b'{' => braces.push((p, c)),
            b'}' => {
                braces.pop();
            }
            _ => {}
        }
    }
    let paren = parens.into_iter().rev().find(|&(p, _)| p < limit);
    let brace = braces.into_iter().rev().find(|&(p, _)| p < limit);
    paren.max(brace)
}
