//! Stability from the full characteristic polynomial det(s²·M + s·C + K)
//! by the Routh–Hurwitz (Liénard–Chipart) conditions, for a linearization
//! that has none of the structures the shortcuts of `linear_stability.rs`
//! need: damping (C with a symmetric part) together with circulatory forces
//! (K not symmetric), a damping matrix of no known sign, or a stiffness of
//! undecided sign under damping.
//!
//! With p(s) = b₀·s^N + b₁·s^(N−1) + … + b_N (N = 2n, b₀ = det M > 0):
//!
//! * a coefficient bᵢ < 0 is a root with Re s > 0 (a polynomial whose roots
//!   are all in the closed left half-plane has no negative coefficient);
//! * every root has Re s < 0 exactly when b₀, b₂, …, b_N > 0 and the odd
//!   Hurwitz determinants Δ₁, Δ₃, …, Δ_(N−1) > 0 (Liénard–Chipart);
//! * when every bᵢ and Δₖ is nonzero, the number of roots with Re s > 0 is
//!   the number of sign changes in b₀, Δ₁, Δ₂/Δ₁, …, Δ_N/Δ_(N−1) (Routh),
//!   so a negative one is unstable;
//! * a zero among them is a root on the imaginary axis (or a pair ±s): the
//!   linearization does not decide.
//!
//! A condition the parameters do not decide is printed as the conditions
//! of Liénard–Chipart, their positive factors left out.

use super::condition::{describe, Condition, Positivity};
use super::equilibrium::Stability;
use crate::algebra::linear::det;
use crate::algebra::sign::{sign_of, Sign, Values};
use crate::expr::Expr;
use crate::num::Q;

/// The most coordinates whose Hurwitz determinants are formed exactly
/// (degree 2n, determinants up to (2n − 1)×(2n − 1) of polynomials);
/// past it the numeric eigenvalues at `--set` decide.
const MAX_COORDINATES: usize = 3;

/// Why a root on the imaginary axis leaves the verdict open.
const BOUNDARY: &str = "a root of det(s²·M + s·C + K) on the imaginary axis (a Routh–Hurwitz coefficient or determinant is zero): the linearization does not decide";

/// The verdict for M positive definite (see the module docs).
pub(super) fn verdict(
    m: &[Vec<Expr>],
    c: &[Vec<Expr>],
    k: &[Vec<Expr>],
    set: &Values,
) -> Stability {
    let n = m.len();
    if n > MAX_COORDINATES {
        return Stability::Undecided(format!(
            "the forces are neither conservative, damped nor gyroscopic, and the Routh–Hurwitz conditions of {n} coordinates are not formed exactly; give values with --set"
        ));
    }
    let failed = || {
        Stability::Undecided(
            "the characteristic polynomial det(s²·M + s·C + K) could not be evaluated".into(),
        )
    };
    let Some(b) = coefficients(m, c, k) else {
        return failed();
    };
    if sign_of(&b[0], set) != Some(Sign::Positive) {
        return failed();
    }
    let b_signs: Vec<Option<Sign>> = b.iter().map(|x| sign_of(x, set)).collect();
    if b_signs.contains(&Some(Sign::Negative)) {
        return Stability::Unstable;
    }
    let Some(delta) = hurwitz_determinants(&b) else {
        return failed();
    };
    let d_signs: Vec<Option<Sign>> = delta.iter().map(|x| sign_of(x, set)).collect();
    // Liénard–Chipart: b₀, b₂, …, b_N and Δ₁, Δ₃, …, Δ_(N−1)
    let chipart: Vec<(&Expr, Option<Sign>)> = b
        .iter()
        .zip(&b_signs)
        .step_by(2)
        .chain(delta.iter().zip(&d_signs).step_by(2))
        .map(|(x, s)| (x, *s))
        .collect();
    if chipart.iter().all(|(_, s)| *s == Some(Sign::Positive)) {
        return Stability::Stable;
    }
    // Δ_N = b_N·Δ_(N−1)
    let last = b_signs[b.len() - 1].zip(*d_signs.last().unwrap_or(&None));
    let all: Vec<Option<Sign>> = b_signs
        .iter()
        .chain(&d_signs)
        .copied()
        .chain([last.map(|(x, y)| x * y)])
        .collect();
    if all
        .iter()
        .all(|s| matches!(s, Some(Sign::Positive | Sign::Negative)))
    {
        return Stability::Unstable;
    }
    if b_signs.last() == Some(&Some(Sign::Zero)) {
        // det K = 0: s = 0 is a root, as without damping
        return Stability::Undecided("a zero frequency: higher-order terms decide".into());
    }
    if all.contains(&Some(Sign::Zero)) {
        return Stability::Undecided(BOUNDARY.into());
    }
    conditions(&chipart)
}

/// The conditions of Liénard–Chipart the parameters do not decide.
fn conditions(chipart: &[(&Expr, Option<Sign>)]) -> Stability {
    let mut conditions: Vec<Condition> = Vec::new();
    for (x, s) in chipart {
        if s.is_some() {
            continue;
        }
        match super::condition::positive(x) {
            Positivity::Holds => {}
            Positivity::Fails => {
                return Stability::Undecided(
                    "a Routh–Hurwitz determinant is negative for every value of the parameters: not asymptotically stable, and the linearization does not decide between growth and a root on the imaginary axis".into(),
                )
            }
            Positivity::When(cs) => {
                for c in cs {
                    if !conditions.contains(&c) {
                        conditions.push(c);
                    }
                }
            }
        }
    }
    if conditions.is_empty() {
        return Stability::Stable;
    }
    Stability::Undecided(format!("{}; give values with --set", describe(&conditions)))
}

/// b₀ … b_N of det(s²·M + s·C + K), highest power first; `None` when the
/// determinant cannot be formed.
pub(super) fn coefficients(m: &[Vec<Expr>], c: &[Vec<Expr>], k: &[Vec<Expr>]) -> Option<Vec<Expr>> {
    let n = m.len();
    let (coefficients, den) = super::characteristic::pencil(m, c, k)?;
    let mut b = coefficients
        .into_iter()
        .map(|x| Expr::from_poly(x).div(&den).ok())
        .collect::<Option<Vec<Expr>>>()?;
    if b.len() > 2 * n + 1 {
        return None;
    }
    b.resize(2 * n + 1, Expr::zero());
    b.reverse();
    Some(b)
}

/// Δ₁ … Δ_(N−1), the leading minors of the Hurwitz matrix Hᵢⱼ = b_(2j−i)
/// (1-based, b outside 0..=N is 0).
fn hurwitz_determinants(b: &[Expr]) -> Option<Vec<Expr>> {
    let degree = b.len() - 1;
    let entry = |i: usize, j: usize| {
        (2 * j + 1)
            .checked_sub(i)
            .and_then(|x| b.get(x))
            .cloned()
            .unwrap_or_else(Expr::zero)
    };
    (1..degree)
        .map(|size| {
            det((0..size)
                .map(|i| (0..size).map(|j| entry(i, j)).collect())
                .collect())
        })
        .collect()
}

/// The sign of the velocity terms' dissipation: the symmetric part of C.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Dissipation {
    /// C is skew (or zero): no dissipation.
    Zero,
    /// Positive definite: complete damping.
    Complete,
    /// Positive semidefinite, not definite (or not proved definite).
    Partial,
    /// Of no sign proved: it may feed energy in.
    Unknown,
}

/// The most coordinates whose principal minors (2ⁿ − 1 of them) are tried
/// for semidefiniteness.
const MAX_PRINCIPAL: usize = 4;

/// What the symmetric part of C is, under the assumptions or at `set`.
pub(super) fn dissipation(c: &[Vec<Expr>], set: &Values) -> Dissipation {
    let n = c.len();
    let half = Q::new(1, 2).unwrap_or_else(Q::one);
    let d: Vec<Vec<Expr>> = (0..n)
        .map(|i| (0..n).map(|j| c[i][j].add(&c[j][i]).scale(&half)).collect())
        .collect();
    if d.iter().flatten().all(Expr::is_zero) {
        return Dissipation::Zero;
    }
    let positive = |x: &Expr| sign_of(x, set) == Some(Sign::Positive);
    let non_negative = |x: &Expr| matches!(sign_of(x, set), Some(Sign::Positive | Sign::Zero));
    let diagonal = (0..n).all(|i| (0..n).all(|j| i == j || d[i][j].is_zero()));
    if diagonal {
        return if (0..n).all(|i| positive(&d[i][i])) {
            Dissipation::Complete
        } else if (0..n).all(|i| non_negative(&d[i][i])) {
            Dissipation::Partial
        } else {
            Dissipation::Unknown
        };
    }
    if super::definite::leading_minors(&d).is_some_and(|ms| ms.iter().all(positive)) {
        return Dissipation::Complete;
    }
    if n > MAX_PRINCIPAL {
        return Dissipation::Unknown;
    }
    let semidefinite = (1u32..1 << n).all(|mask| {
        let rows: Vec<usize> = (0..n).filter(|i| mask & (1 << i) != 0).collect();
        let sub = rows
            .iter()
            .map(|&i| rows.iter().map(|&j| d[i][j].clone()).collect())
            .collect();
        det(sub).is_some_and(|x| non_negative(&x))
    });
    if semidefinite {
        Dissipation::Partial
    } else {
        Dissipation::Unknown
    }
}
