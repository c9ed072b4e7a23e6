//! A body's inertia tensor must be one a rigid body can have: I = tr(S)·E − S
//! with S = Σ m·r·rᵀ positive semidefinite. That is I positive
//! semidefinite and its principal moments satisfying the triangle
//! inequality (each at most the sum of the other two), together: S =
//! tr(I)/2·E − I positive semidefinite. Both are decided on all principal
//! minors (a symmetric matrix is positive semidefinite exactly when every
//! principal minor is ≥ 0), exactly under the scene's assumptions: a minor
//! proved negative is refused where the inertia is written, one whose sign
//! is not decided is a warning.

use crate::algebra::assume::{sign_under, Assumptions};
use crate::algebra::sign::Sign;
use crate::diag::Diagnostic;
use crate::expr::Expr;
use crate::num::Q;
use crate::parse::ast::Span;

const HINT: &str = "a rigid body's inertia is positive semidefinite and its principal moments satisfy the triangle inequality (each at most the sum of the other two; equal for a flat body)";

/// Where an inertia is written: the whole value, and each principal
/// moment when it is written as `[I1, I2, I3]`; `about`, the point of
/// `inertia I about P` when the inertia checked is the centroidal one
/// converted from it.
pub(super) struct Written<'a> {
    pub(super) body: &'a str,
    pub(super) span: Span,
    pub(super) moments: Option<[Span; 3]>,
    pub(super) about: Option<Span>,
}

impl Written<'_> {
    /// "`top`", or "`top` about its centre of mass" for a converted inertia.
    fn who(&self) -> String {
        match self.about {
            Some(_) => format!("`{}` about its centre of mass", self.body),
            None => format!("`{}`", self.body),
        }
    }

    /// A diagnostic on a converted inertia points at the point too.
    fn label(&self, d: Diagnostic) -> Diagnostic {
        match self.about {
            Some(p) => d.with_label(p, ABOUT_LABEL),
            None => d,
        }
    }
}

/// The label at `about P`.
const ABOUT_LABEL: &str = "the inertia is given about this point; about the centre of mass it is I − m·(|d|²·1 − d·dᵀ), d from this point to the centre along the body's axes";

/// The principal minors of a 3×3 matrix: the index sets and the values
/// (`None` for a minor without a canonical form: its sign is undecided).
fn principal_minors(m: &[[Expr; 3]; 3]) -> Vec<(Vec<usize>, Option<Expr>)> {
    let sets: [&[usize]; 7] = [&[0], &[1], &[2], &[0, 1], &[0, 2], &[1, 2], &[0, 1, 2]];
    sets.iter()
        .map(|set| {
            let sub: Vec<Vec<Expr>> = set
                .iter()
                .map(|&i| set.iter().map(|&j| m[i][j].clone()).collect())
                .collect();
            (set.to_vec(), crate::algebra::linear::det(sub))
        })
        .collect()
}

/// S = tr(I)/2·E − I.
fn second_moments(i: &[[Expr; 3]; 3]) -> [[Expr; 3]; 3] {
    let half = Q::new(1, 2).unwrap_or_else(Q::one);
    let trace = i[0][0].add(&i[1][1]).add(&i[2][2]).scale(&half);
    std::array::from_fn(|a| {
        std::array::from_fn(|b| {
            let x = i[a][b].neg();
            if a == b {
                x.add(&trace)
            } else {
                x
            }
        })
    })
}

/// "rows 1, 2" for the index set {0, 1}.
fn rows(set: &[usize]) -> String {
    let r: Vec<String> = set.iter().map(|i| (i + 1).to_string()).collect();
    format!("rows {}", r.join(", "))
}

/// The other two axes of axis `k`.
fn others(k: usize) -> (usize, usize) {
    match k {
        0 => (1, 2),
        1 => (0, 2),
        _ => (0, 1),
    }
}

/// What is wrong with the minor `set` of S (`triangle`) or of I, and
/// where: (span, what it is, the condition to state).
fn describe(
    i: &[[Expr; 3]; 3],
    set: &[usize],
    minor: &Expr,
    triangle: bool,
    at: &Written,
) -> (Span, String, String) {
    match (triangle, set, at.moments) {
        (true, [k], _) => {
            let (a, b) = others(*k);
            let span = at.moments.map_or(at.span, |s| s[*k]);
            (
                span,
                match at.about {
                    Some(_) => format!(
                        "{} ≤ {}",
                        i[*k][*k].to_input(),
                        i[a][a].add(&i[b][b]).to_input()
                    ),
                    None => format!(
                        "{} ≤ {} + {}",
                        i[*k][*k].to_input(),
                        i[a][a].to_input(),
                        i[b][b].to_input()
                    ),
                },
                match at.about {
                    // converted moments: their sum, collected
                    Some(_) => format!(
                        "{} > {}",
                        i[a][a].add(&i[b][b]).to_input(),
                        i[*k][*k].to_input()
                    ),
                    None => format!(
                        "{} + {} > {}",
                        i[a][a].to_input(),
                        i[b][b].to_input(),
                        i[*k][*k].to_input()
                    ),
                },
            )
        }
        (true, _, _) => (
            at.span,
            format!(
                "the triangle inequality of its principal moments (tr(I)/2·E − I's minor of {} = {} ≥ 0)",
                rows(set),
                minor.to_input()
            ),
            format!("{} > 0", minor.to_input()),
        ),
        (false, [k], moments) => (
            moments.map_or(at.span, |s| s[*k]),
            format!("{} ≥ 0", i[*k][*k].to_input()),
            format!("{} > 0", i[*k][*k].to_input()),
        ),
        (false, _, _) => (
            at.span,
            format!("its minor of {} = {} ≥ 0", rows(set), minor.to_input()),
            format!("{} > 0", minor.to_input()),
        ),
    }
}

/// Check the inertia `i` (symmetric, constant): an error when it is
/// provably not a rigid body's, a warning when that is not decided.
pub(super) fn check(
    i: &[[Expr; 3]; 3],
    at: &Written,
    assumed: &Assumptions,
) -> Result<Option<Diagnostic>, Diagnostic> {
    let sign = |e: &Expr| sign_under(assumed, e);
    let mut undecided: Option<Diagnostic> = None;
    let s = second_moments(i);
    for (triangle, m) in [(false, i), (true, &s)] {
        for (set, minor) in principal_minors(m) {
            let Some(minor) = minor else {
                undecided.get_or_insert_with(|| {
                    Diagnostic::warning(
                        at.span,
                        format!(
                            "qdot can't tell that the inertia of {} is one a rigid body can have: its minor of {} has no canonical form",
                            at.who(),
                            rows(&set)
                        ),
                    )
                    .with_hint(format!("{HINT}; give numbers"))
                });
                continue;
            };
            match sign(&minor) {
                Some(Sign::Negative) => {
                    return Err(at.label(refusal(i, &set, &minor, triangle, at)))
                }
                Some(_) => {}
                None => {
                    if undecided.is_none() {
                        let (span, what, fact) = describe(i, &set, &minor, triangle, at);
                        undecided = Some(
                            Diagnostic::warning(
                                span,
                                format!(
                                    "qdot can't tell that the inertia of {} is one a rigid body can have: {what} is not decided",
                                    at.who()
                                ),
                            )
                            .with_hint(format!("{HINT}; state it with `assume {fact}` or give numbers")),
                        );
                    }
                }
            }
        }
    }
    Ok(undecided.map(|w| at.label(w)))
}

/// The error for a minor proved negative.
fn refusal(
    i: &[[Expr; 3]; 3],
    set: &[usize],
    minor: &Expr,
    triangle: bool,
    at: &Written,
) -> Diagnostic {
    let (span, message) = match (triangle, set) {
        (true, [k]) => {
            let (a, b) = others(*k);
            (
                at.moments.map_or(at.span, |s| s[*k]),
                format!(
                    "the principal moments of inertia of {} violate the triangle inequality: {} > {} + {}",
                    at.who(),
                    i[*k][*k].to_input(),
                    i[a][a].to_input(),
                    i[b][b].to_input()
                ),
            )
        }
        (true, _) => (
            at.span,
            format!(
                "the principal moments of this inertia matrix violate the triangle inequality: tr(I)/2·E − I is not positive semidefinite (its minor of {} is {} < 0)",
                rows(set),
                minor.to_input()
            ),
        ),
        (false, [k]) => (
            at.moments.map_or(at.span, |s| s[*k]),
            format!(
                "a moment of inertia can't be negative, and {} is",
                i[*k][*k].to_input()
            ),
        ),
        (false, _) => (
            at.span,
            format!(
                "an inertia matrix is positive semidefinite, and this one is not: its minor of {} is {} < 0",
                rows(set),
                minor.to_input()
            ),
        ),
    };
    let message = match at.about {
        Some(_) if !triangle || set.len() > 1 => format!("the inertia of {}: {message}", at.who()),
        _ => message,
    };
    let hint = match at.about {
        Some(_) => format!("{HINT}; about a point the inertia exceeds the one about the centre by m·(|d|²·1 − d·dᵀ): check the inertia and the point"),
        None => HINT.to_string(),
    };
    Diagnostic::error(span, message)
        .with_hint(hint)
        .with_kind(crate::diag::ErrorKind::Unphysical)
}
