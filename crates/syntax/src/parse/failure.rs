//! The error type threaded through the rules, and the error constructors
//! shared by several rules.

use super::*;

/// The error type threaded through the nom parsers.
///
/// `At` is a recoverable "nothing here" from a nom primitive (it records the
/// length of the remaining input, from which the offset follows); `Diag` is a
/// finished diagnostic, always raised as `nom::Err::Failure` so that no
/// alternative is tried after it.
#[derive(Debug)]
pub(super) enum RuleError {
    At(usize),
    Diag(Box<Diagnostic>),
}

impl<'s> ParseError<&'s str> for RuleError {
    fn from_error_kind(input: &'s str, _kind: ErrorKind) -> Self {
        RuleError::At(input.len())
    }
    fn append(_input: &'s str, _kind: ErrorKind, other: Self) -> Self {
        other
    }
}

pub(super) type RuleResult<'s, T> = IResult<&'s str, T, RuleError>;

/// A finished diagnostic as an unrecoverable nom error.
pub(super) fn failure(d: Diagnostic) -> nom::Err<RuleError> {
    nom::Err::Failure(RuleError::Diag(Box::new(d)))
}

// The error constructors used on the recursive path are kept out of line, so
// that the frames of the recursive rules stay small (deep nesting must not
// exhaust a 2 MiB thread stack, even in debug builds).

#[cold]
#[inline(never)]
pub(super) fn too_deep(at: Span) -> nom::Err<RuleError> {
    failure(
        Diagnostic::error(
            at,
            format!("expression too deep (more than {MAX_DEPTH} levels)"),
        )
        .with_hint("split it into several named definitions")
        .with_kind(crate::diag::ErrorKind::Syntax),
    )
}

#[cold]
#[inline(never)]
pub(super) fn star_star(op: Span) -> nom::Err<RuleError> {
    failure(
        Diagnostic::error(Span::new(op.start, op.end + 1), "`**` is not an operator")
            .with_hint("write powers with `^`, like `x^2`")
            .with_kind(crate::diag::ErrorKind::Syntax),
    )
}

#[cold]
#[inline(never)]
pub(super) fn too_many_primes(at: Span) -> nom::Err<RuleError> {
    failure(
        Diagnostic::error(at, "too many primes")
            .with_hint("a derivative order must fit in 32 bits")
            .with_kind(crate::diag::ErrorKind::Syntax),
    )
}

#[cold]
#[inline(never)]
pub(super) fn prime_on_number(at: Span) -> nom::Err<RuleError> {
    failure(
        Diagnostic::error(at, "a prime `'` (time derivative) can't follow a number").with_hint(
            "primes apply to names, calls and parenthesized expressions: `x'`, `sin(x)'`, `(2*x)'`; the derivative of a constant is 0",
        ).with_kind(crate::diag::ErrorKind::Syntax),
    )
}

#[cold]
#[inline(never)]
pub(super) fn unclosed_bracket(open: usize) -> nom::Err<RuleError> {
    failure(
        Diagnostic::error(Span::new(open, open + 1), "unclosed `[`")
            .with_hint("add the matching `]`")
            .with_kind(crate::diag::ErrorKind::Syntax),
    )
}

#[cold]
#[inline(never)]
pub(super) fn unclosed_block(open: usize) -> nom::Err<RuleError> {
    failure(
        Diagnostic::error(Span::new(open, open + 1), "unclosed `{`")
            .with_hint(HINT_UNCLOSED_BLOCK)
            .with_kind(crate::diag::ErrorKind::Syntax),
    )
}

pub(super) const HINT_EXPR: &str =
    "an expression is a number, a name, a call like `sin(x)` or an expression in parentheses";

pub(super) const HINT_UNCLOSED_BLOCK: &str =
    "add the matching `}` after the last equation of the solve block";
