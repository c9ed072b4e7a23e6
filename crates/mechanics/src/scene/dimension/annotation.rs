//! Reading a dimension annotation (`k: force/length`) into a [`Dimension`].

use super::dim::{dimension_named, Dimension, DimensionNameKind, DIMENSION_NAMES};
use crate::diag::Diagnostic;
use crate::num::Q;
use crate::parse::ast::{BinOp, Expr, ExprKind};

const HINT_FORM: &str =
    "write a dimension with names, `*`, `/` and `^`: `length`, `force/length`, `mass*length^2`, `N*m/rad`";

/// The dimension an annotation names.
pub(super) fn dimension_of(e: &Expr) -> Result<Dimension, Diagnostic> {
    match &e.kind {
        ExprKind::Name(n) => dimension_named(n).ok_or_else(|| unknown(e, n)),
        ExprKind::Num(q) if q.is_integer() && *q.numer() == 1.into() => Ok(Dimension::one()),
        ExprKind::Bin(BinOp::Mul, a, b) => Ok(dimension_of(a)?.mul(&dimension_of(b)?)),
        ExprKind::Bin(BinOp::Div, a, b) => Ok(dimension_of(a)?.div(&dimension_of(b)?)),
        ExprKind::Bin(BinOp::Pow, a, b) => {
            let p = exponent(b).ok_or_else(|| {
                Diagnostic::error(b.span, "the power of a dimension must be a number")
                    .with_hint("write `length^2`, `time^-1` or `length^(1/2)`")
                    .with_kind(crate::diag::ErrorKind::InvalidScene)
            })?;
            Ok(dimension_of(a)?.pow(&p))
        }
        _ => Err(Diagnostic::error(e.span, "this is not a dimension")
            .with_hint(HINT_FORM)
            .with_kind(crate::diag::ErrorKind::InvalidScene)),
    }
}

/// A rational exponent: `2`, `-1`, `(1/2)`, `-(3/2)`.
fn exponent(e: &Expr) -> Option<Q> {
    match &e.kind {
        ExprKind::Num(q) => Some(Q::from_big(q.clone())),
        ExprKind::Neg(x) => exponent(x).map(|q| -q),
        ExprKind::Bin(BinOp::Div, a, b) => exponent(a)?.checked_div(&exponent(b)?),
        _ => None,
    }
}

fn unknown(e: &Expr, n: &str) -> Diagnostic {
    let near = DIMENSION_NAMES
        .iter()
        .map(|d| (crate::spelling::distance(n, d.name), d.name))
        .filter(|(k, name)| *k <= 2 && *k < name.len())
        .min();
    let list = |unit: bool| {
        DIMENSION_NAMES
            .iter()
            .filter(|d| (d.kind == DimensionNameKind::Unit) == unit)
            .map(|d| d.name)
            .collect::<Vec<_>>()
            .join(", ")
    };
    let hint = match near {
        Some((_, m)) => format!("did you mean `{m}`?"),
        None => format!(
            "the dimensions are {}; the SI units {}",
            list(false),
            list(true)
        ),
    };
    Diagnostic::error(e.span, format!("unknown dimension `{n}`"))
        .with_hint(hint)
        .with_kind(crate::diag::ErrorKind::UnknownName {
            name: n.to_string(),
        })
}
