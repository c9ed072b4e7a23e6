//! The likely fix of a dimension error, from how far the two dimensions
//! are apart and what the wrong expression is made of.

use super::dim::Dimension;
use super::form::DimForm;
use super::walk::{DimValue, NameDim, Walker};
use crate::diag::Diagnostic;
use crate::num::Q;
use crate::parse::ast::{Expr, ExprKind, Span};

/// A name or a derivative of one written in an expression, with its
/// dimension and how often it occurs.
struct Written {
    text: String,
    name: String,
    dimension: Option<Dimension>,
    count: usize,
}

/// The hint for `e`, of dimension `have` where `want` is needed.
pub(super) fn hint(w: &Walker, e: &Expr, have: &DimForm, want: &DimForm) -> Option<String> {
    let have = w.vars.normalize(have);
    let want = w.vars.normalize(want);
    let written = written(w, e);
    let mut parts = Vec::new();
    if let (Some(h), Some(n)) = (have.as_known(), want.as_known()) {
        parts.extend(by_ratio(&h.div(n), &written));
    }
    for x in &written {
        let Some(v) = w.unknown_of(&x.name) else {
            continue;
        };
        let Some(s) = w.vars.solution(v) else {
            continue;
        };
        if x.text != x.name
            || parts
                .iter()
                .any(|p: &String| p.contains(&format!("`{}` is", x.name)))
        {
            continue;
        }
        let (line, col) = Diagnostic::line_col(w.src, s.at.start);
        parts.push(format!(
            "`{}` is {}, found from {line}:{col} (`{}`); annotate it to say otherwise",
            x.name,
            w.vars.phrase(&DimForm::var(v)),
            short(&w.src[s.at.start..s.at.end]),
        ));
    }
    (!parts.is_empty()).then(|| parts.join("; "))
}

/// The most places an error's labels show.
const ORIGINS_SHOWN: usize = 3;

/// Where the dimensions of the names written in `e` come from, as an
/// error's labels: an annotation (`m: mass`), a definition, or the
/// expression an unannotated name's dimension was found from.
pub(super) fn origins(w: &Walker, e: &Expr) -> Vec<(Span, String)> {
    let mut out: Vec<(Span, String)> = Vec::new();
    for x in written(w, e) {
        let Some(dimension) = name_dimension(w, &x.name) else {
            continue;
        };
        let phrase = w.vars.phrase(&DimForm::known(dimension));
        let found = w
            .unknown_of(&x.name)
            .and_then(|v| w.vars.solution(v))
            .map(|s| (s.at, "found"));
        let written_at = match w.names.get(x.name.as_str()) {
            Some(NameDim::Def(_)) => w.origins.get(x.name.as_str()).map(|&s| (s, "defined")),
            _ => w.origins.get(x.name.as_str()).map(|&s| (s, "declared")),
        };
        let Some((span, how)) = written_at.or(found) else {
            continue;
        };
        if span == e.span || out.iter().any(|(s, _)| *s == span) {
            continue;
        }
        out.push((span, format!("`{}` is {phrase}, {how} here", x.name)));
        if out.len() == ORIGINS_SHOWN {
            break;
        }
    }
    // shown in the order of the source
    out.sort_by_key(|(span, _)| span.start);
    out
}

fn short(s: &str) -> String {
    let one_line = s.split_whitespace().collect::<Vec<_>>().join(" ");
    if one_line.chars().count() <= 40 {
        one_line
    } else {
        format!("{}…", one_line.chars().take(39).collect::<String>())
    }
}

/// The fix suggested by have/want = `ratio`.
fn by_ratio(ratio: &Dimension, written: &[Written]) -> Option<String> {
    if ratio.is_one() {
        return None;
    }
    let inverse = |d: &Dimension| d.pow(&Q::from_i64(-1));
    let with_dim = |d: &Dimension| written.iter().find(|x| x.dimension.as_ref() == Some(d));
    if *ratio == Dimension::ACCELERATION {
        if let Some(x) = with_dim(&Dimension::FORCE) {
            return Some(format!(
                "`{}` is a weight (a force): the mass is {}/g",
                x.text, x.text
            ));
        }
    }
    if *ratio == inverse(&Dimension::ACCELERATION) {
        if let Some(x) = with_dim(&Dimension::MASS) {
            return Some(format!(
                "`{}` is a mass: its weight (a force) is {}*g",
                x.text, x.text
            ));
        }
    }
    if *ratio == inverse(&Dimension::AREA) {
        if let Some(x) = with_dim(&Dimension::MASS) {
            return Some(format!(
                "`{}` is a mass: a rotation needs a moment of inertia (`{}*l^2`, an inertia)",
                x.text, x.text
            ));
        }
    }
    for x in written {
        let Some(d) = &x.dimension else { continue };
        if d.is_one() {
            continue;
        }
        if *ratio == inverse(d) {
            return Some(if x.count == 1 {
                format!(
                    "one factor of `{}` short: a missing square (`{}^2`)?",
                    x.text, x.text
                )
            } else {
                format!("one factor of `{}` short", x.text)
            });
        }
        if ratio == d {
            return Some(format!("one factor of `{}` too many", x.text));
        }
    }
    let time = Dimension::TIME;
    if *ratio == inverse(&time) {
        return Some(
            "one time derivative (') too many, or a stiffness where a damping coefficient belongs?"
                .into(),
        );
    }
    if *ratio == time {
        return Some(
            "a time derivative (') missing, or a damping coefficient where a stiffness belongs?"
                .into(),
        );
    }
    let length = Dimension::LENGTH;
    if *ratio == length {
        return Some(
            "one length too many: a moment (force × arm) where a force belongs, or a length where an angle belongs?"
                .into(),
        );
    }
    if *ratio == inverse(&length) {
        return Some(
            "one length short: a force where a moment belongs, or an angle where a length belongs (an arc is r*theta)?"
                .into(),
        );
    }
    Some(format!("the two differ by a factor of {}", ratio.unicode()))
}

/// The names and derivatives of names written in `e` (not inside calls).
fn written(w: &Walker, e: &Expr) -> Vec<Written> {
    let mut out: Vec<Written> = Vec::new();
    let mut stack = vec![e];
    while let Some(x) = stack.pop() {
        let (name, order) = match &x.kind {
            ExprKind::Name(n) => (n, 0),
            ExprKind::Prime(inner, k) => match &inner.kind {
                ExprKind::Name(n) => (n, *k),
                _ => {
                    stack.push(inner);
                    continue;
                }
            },
            ExprKind::Neg(a) => {
                stack.push(a);
                continue;
            }
            ExprKind::Bin(_, a, b) => {
                stack.push(b);
                stack.push(a);
                continue;
            }
            _ => continue,
        };
        let text = format!("{name}{}", "'".repeat(order as usize));
        if let Some(seen) = out.iter_mut().find(|s| s.text == text) {
            seen.count += 1;
            continue;
        }
        let dimension = name_dimension(w, name).map(|d| {
            let t = Walker::time().pow(&Q::from_i64(-i64::from(order)));
            d.mul(&t.base)
        });
        out.push(Written {
            text,
            name: name.clone(),
            dimension,
            count: 1,
        });
    }
    out.reverse();
    out
}

/// A name's dimension, when it is known.
fn name_dimension(w: &Walker, n: &str) -> Option<Dimension> {
    let f = match w.names.get(n)? {
        NameDim::Fixed(f) => f.clone(),
        NameDim::Def(i) => match w.defs.get(*i)?.as_ref()? {
            DimValue::Scalar(Some(f)) => f.clone(),
            _ => return None,
        },
        NameDim::Time => Walker::time(),
        NameDim::Pi => DimForm::one(),
    };
    w.vars.normalize(&f).as_known().cloned()
}
