//! Whether the kinetic energy is positive definite where a stability
//! verdict rests on it, and the verdict when it is not.
//!
//! Lagrange–Dirichlet (K positive definite is stable), Jacobi's rule on K
//! (a negative direction is unstable) and "every root λ = ω² of
//! det(K − λ·M) is real and positive" all read M as positive definite. M
//! (at the equilibrium) is decided by Sylvester's criterion on its leading
//! minors, exactly under the assumptions or at the `--set` values:
//!
//! * positive definite: the verdicts above;
//! * negative definite: L and −L have the same equations, so the verdict
//!   is that of (−M, −C, −K);
//! * otherwise (indefinite, singular, or a minor of undecided sign) the
//!   equilibrium is unstable when det M·det K < 0 (det(K + s·C + s²·M) is
//!   det K at s = 0 and det M·s²ⁿ for large s: a real root s > 0, whatever
//!   C is), when M is indefinite, K definite and there are no velocity
//!   terms (K^(−1/2)·M·K^(−1/2) has a negative eigenvalue, so some ω² < 0),
//!   or when the caller finds a growing solution of the linearization;
//!   else the verdict is undecided, with the reason. It is never "stable":
//!   with an indefinite kinetic energy the energy bounds nothing, and an
//!   equilibrium whose linearization only oscillates can still be unstable
//!   (the nonlinear terms decide).

use super::equilibrium::Stability;
use crate::algebra::linear::det;
use crate::algebra::sign::{sign_of, Sign, Values};
use crate::expr::{atom, Expr};
use crate::mechanics::Lagrange;
use crate::poly::Var;
use rustc_hash::FxHashMap;

/// What the leading minors D₁ … Dₙ of a symmetric matrix say.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Definiteness {
    /// Every Dᵢ > 0.
    Positive,
    /// The Dᵢ alternate from D₁ < 0.
    Negative,
    /// Eigenvalues of both signs: Dᵢ (0-based `not_negative`) rules out
    /// negative and Dⱼ (`not_positive`) positive definiteness, either in a
    /// leading block of nonzero minors or with det ≠ 0.
    Indefinite {
        not_negative: usize,
        not_positive: usize,
    },
    /// det = 0: a direction without inertia.
    Singular,
    /// Dᵢ (0-based) is the first minor whose sign is not decided.
    Undecided(usize),
}

/// The sign Dᵢ (0-based i) has in a negative definite matrix: (−1)^(i+1).
fn negative_definite_sign(i: usize) -> Sign {
    if i.is_multiple_of(2) {
        Sign::Negative
    } else {
        Sign::Positive
    }
}

/// Sylvester's criterion on the signs of the leading minors.
pub(super) fn from_signs(signs: &[Option<Sign>]) -> Definiteness {
    if signs.iter().all(|s| *s == Some(Sign::Positive)) {
        return Definiteness::Positive;
    }
    if signs
        .iter()
        .enumerate()
        .all(|(i, s)| *s == Some(negative_definite_sign(i)))
    {
        return Definiteness::Negative;
    }
    // a leading block of nonzero minors that is neither: by Jacobi's rule
    // it has eigenvalues of both signs, and so (interlacing) has M
    let (mut not_negative, mut not_positive) = (None, None);
    for (i, s) in signs.iter().enumerate() {
        let Some(s) = s.filter(|s| *s != Sign::Zero) else {
            break;
        };
        if s != Sign::Positive {
            not_positive.get_or_insert(i);
        }
        if s != negative_definite_sign(i) {
            not_negative.get_or_insert(i);
        }
        if let (Some(&not_negative), Some(&not_positive)) =
            (not_negative.as_ref(), not_positive.as_ref())
        {
            return Definiteness::Indefinite {
                not_negative,
                not_positive,
            };
        }
    }
    if signs.last() == Some(&Some(Sign::Zero)) {
        return Definiteness::Singular;
    }
    match signs.iter().position(Option::is_none) {
        Some(i) => Definiteness::Undecided(i),
        None => {
            // det ≠ 0 and a leading minor is 0: neither definite
            let zero = signs
                .iter()
                .position(|s| *s == Some(Sign::Zero))
                .unwrap_or(0);
            Definiteness::Indefinite {
                not_negative: zero,
                not_positive: zero,
            }
        }
    }
}

/// The leading minors of a square matrix of expressions; `None` when one
/// cannot be evaluated.
pub(super) fn leading_minors(m: &[Vec<Expr>]) -> Option<Vec<Expr>> {
    (1..=m.len())
        .map(|k| det(m[..k].iter().map(|r| r[..k].to_vec()).collect()))
        .collect()
}

/// The leading minors of a numeric matrix.
fn leading_minors_f64(m: &[Vec<f64>]) -> Vec<f64> {
    (1..=m.len())
        .map(|k| super::equilibrium::det_f64(m[..k].iter().map(|r| r[..k].to_vec()).collect()))
        .collect()
}

/// The sign of each numeric minor, 0 within `1e-9·scaleᵐ` (m×m minor of a
/// matrix whose largest entry is `scale`), as `classify_numeric` reads K.
fn numeric_signs(minors: &[f64], scale: f64) -> Vec<Option<Sign>> {
    minors
        .iter()
        .enumerate()
        .map(|(i, &d)| {
            let tol = 1e-9 * scale.powi(i as i32 + 1);
            Some(if !d.is_finite() {
                return None;
            } else if d.abs() <= tol {
                Sign::Zero
            } else if d > 0.0 {
                Sign::Positive
            } else {
                Sign::Negative
            })
        })
        .collect()
}

fn largest(m: &[Vec<f64>]) -> f64 {
    m.iter()
        .flatten()
        .fold(0.0f64, |a, v| a.max(v.abs()))
        .max(f64::MIN_POSITIVE)
}

/// A number as a message shows it (seven significant digits).
fn shown(x: f64) -> String {
    let s = format!("{x:.7e}");
    let v: f64 = s.parse().unwrap_or(x);
    format!("{v}").replace('-', "−")
}

/// The mass matrix at an equilibrium, as the verdict reads it.
pub(super) struct Mass {
    kind: Definiteness,
    /// The leading minors as the messages show them.
    minors: Vec<String>,
    /// det M's sign, when decided.
    det: Option<Sign>,
}

impl Mass {
    /// Exact M, signs decided under the assumptions or at `set`.
    pub(super) fn exact(m: &[Vec<Expr>], set: &Values) -> Mass {
        let Some(minors) = leading_minors(m) else {
            return Mass {
                kind: Definiteness::Undecided(0),
                minors: vec!["(not evaluated)".into(); m.len().max(1)],
                det: None,
            };
        };
        let signs: Vec<Option<Sign>> = minors.iter().map(|d| sign_of(d, set)).collect();
        Mass {
            kind: from_signs(&signs),
            minors: minors.iter().map(crate::expr::print::unicode).collect(),
            det: signs.last().copied().flatten(),
        }
    }

    /// Numeric M (relative tolerance 1e-9 for a zero minor).
    pub(super) fn numeric(m: &[Vec<f64>]) -> Mass {
        let minors = leading_minors_f64(m);
        let signs = numeric_signs(&minors, largest(m));
        Mass {
            kind: from_signs(&signs),
            minors: minors.iter().map(|&d| shown(d)).collect(),
            det: signs.last().copied().flatten(),
        }
    }

    /// What Sylvester's criterion says.
    pub(super) fn definiteness(&self) -> Definiteness {
        self.kind
    }

    /// Why no verdict rests on M, when it is not definite.
    fn reason(&self) -> String {
        match self.kind {
            Definiteness::Positive | Definiteness::Negative => String::new(),
            Definiteness::Indefinite {
                not_negative,
                not_positive,
            } if not_negative == not_positive => format!(
                "the kinetic energy is indefinite here (the mass matrix's leading minor D{} = 0 while det M ≠ 0): the linearization does not decide",
                not_negative + 1
            ),
            Definiteness::Indefinite {
                not_negative,
                not_positive,
            } => {
                let (i, j) = (not_negative.min(not_positive), not_negative.max(not_positive));
                format!(
                    "the kinetic energy is indefinite here (the mass matrix's leading minors D{} = {} and D{} = {}): the linearization does not decide",
                    i + 1,
                    self.minors[i],
                    j + 1,
                    self.minors[j]
                )
            }
            Definiteness::Singular => "the mass matrix is singular here (det M = 0: a direction without inertia, or coordinates singular here such as an azimuth at the pole): the linearization does not decide".into(),
            Definiteness::Undecided(i) => format!(
                "the sign of the kinetic energy here depends on the parameters: the mass matrix's leading minor D{} = {} has no decided sign; give values with --set",
                i + 1,
                self.minors[i]
            ),
        }
    }

    /// The verdict: `positive(negate)` is the verdict for a positive
    /// definite M on the stiffness K (on −K when `negate`, for a negative
    /// definite M); otherwise unstable when `stiffness` proves it, when
    /// M is indefinite, K definite and `velocity_free()` (no velocity
    /// terms), or when `grows()` (the caller's own proof of a growing
    /// solution); else undecided with the reason.
    pub(super) fn verdict(
        &self,
        stiffness: impl FnOnce() -> Stiffness,
        velocity_free: impl FnOnce() -> bool,
        grows: impl FnOnce() -> bool,
        positive: impl FnOnce(bool) -> Stability,
    ) -> Stability {
        match self.kind {
            Definiteness::Positive => return positive(false),
            Definiteness::Negative => return positive(true),
            _ => {}
        }
        let stiffness = stiffness();
        if let (Some(m), Some(k)) = (self.det, stiffness.det) {
            if m * k == Sign::Negative {
                return Stability::Unstable;
            }
        }
        let definite_k = matches!(
            stiffness.kind,
            Some(Definiteness::Positive | Definiteness::Negative)
        );
        if matches!(self.kind, Definiteness::Indefinite { .. }) && definite_k && velocity_free() {
            return Stability::Unstable;
        }
        if grows() {
            return Stability::Unstable;
        }
        Stability::Undecided(self.reason())
    }
}

/// What the verdict needs of K: its definiteness (when symmetric) and the
/// sign of its determinant.
pub(super) struct Stiffness {
    kind: Option<Definiteness>,
    det: Option<Sign>,
}

impl Stiffness {
    /// Exact K, signs decided under the assumptions or at `set`.
    pub(super) fn exact(k: &[Vec<Expr>], set: &Values) -> Stiffness {
        let kind = super::equilibrium::minor_signs(k, set)
            .ok()
            .map(|s| from_signs(&s));
        let det = det(k.to_vec()).and_then(|d| sign_of(&d, set));
        Stiffness { kind, det }
    }

    /// Numeric K.
    pub(super) fn numeric(k: &[Vec<f64>]) -> Stiffness {
        let scale = largest(k);
        let n = k.len();
        let symmetric = (0..n).all(|i| (0..n).all(|j| (k[i][j] - k[j][i]).abs() <= 1e-8 * scale));
        let signs = numeric_signs(&leading_minors_f64(k), scale);
        let det = numeric_signs(
            &[super::equilibrium::det_f64(k.to_vec())],
            scale.powi(n as i32),
        )
        .pop()
        .flatten();
        Stiffness {
            kind: symmetric.then(|| from_signs(&signs)),
            det,
        }
    }
}

/// Whether M·q̈ + K·q = 0 (numeric, no velocity terms) has a growing
/// solution: an eigenvalue λ of M⁻¹·K off the positive axis (complex, or
/// negative) beyond 1e-9 of the largest.
pub(super) fn undamped_grows_f64(m: &[Vec<f64>], k: &[Vec<f64>]) -> bool {
    let n = m.len();
    let mm = nalgebra::DMatrix::from_fn(n, n, |i, j| m[i][j]);
    let kk = nalgebra::DMatrix::from_fn(n, n, |i, j| k[i][j]);
    let Some(a) = mm.lu().solve(&kk) else {
        return false;
    };
    if a.iter().any(|v| !v.is_finite()) {
        return false;
    }
    // a stalled iteration proves nothing grows: the verdict stays undecided
    let Ok(lambda) = super::eigen::general_eigenvalues(&a) else {
        return false;
    };
    let scale = lambda.iter().fold(0.0f64, |s, z| s.max(z.norm()));
    let tol = 1e-9 * scale;
    lambda.iter().any(|z| z.im.abs() > tol || z.re < -tol)
}

/// −X.
pub(super) fn negated(x: &[Vec<Expr>]) -> Vec<Vec<Expr>> {
    x.iter()
        .map(|r| r.iter().map(Expr::neg).collect())
        .collect()
}

/// −X, numeric.
pub(super) fn negated_f64(x: &[Vec<f64>]) -> Vec<Vec<f64>> {
    x.iter().map(|r| r.iter().map(|v| -v).collect()).collect()
}

/// The equations' inertia at rest, for the verdicts of equilibria: M(q)
/// at q̇ = 0, and the velocity terms C(q) = ∂R/∂q̇ (R = lhs − Q) formed
/// when a verdict asks for them.
pub(super) struct AtRest {
    mass: Vec<Vec<Expr>>,
    residuals: Vec<Expr>,
    /// q̇
    rates: Vec<Var>,
    /// q̇ and q̈ at 0
    rest: FxHashMap<Var, Expr>,
    /// [`AtRest::velocity_free`], the same at every equilibrium: formed once.
    velocity_free: std::cell::OnceCell<bool>,
}

impl AtRest {
    /// M and the residuals of `l`'s equations.
    pub(super) fn of(l: &Lagrange) -> Option<AtRest> {
        let rates: Vec<Var> = l.coordinates.iter().map(|c| atom::coord(c, 1)).collect();
        let rest: FxHashMap<Var, Expr> = rates
            .iter()
            .copied()
            .chain(l.coordinates.iter().map(|c| atom::coord(c, 2)))
            .map(|v| (v, Expr::zero()))
            .collect();
        let mass = matrix_at(&l.mass_matrix, &rest)?;
        Some(AtRest {
            mass,
            residuals: l.equations.iter().map(|e| e.lhs.sub(&e.rhs)).collect(),
            rates,
            rest,
            velocity_free: std::cell::OnceCell::new(),
        })
    }

    /// M(q) at rest.
    pub(super) fn mass(&self) -> &[Vec<Expr>] {
        &self.mass
    }

    /// C(q) = ∂R/∂q̇ at rest; `None` when it has no canonical form.
    pub(super) fn velocity_terms(&self) -> Option<Vec<Vec<Expr>>> {
        self.residuals
            .iter()
            .map(|r| {
                self.rates
                    .iter()
                    .map(|&v| r.diff(v).subs_many(&self.rest).ok())
                    .collect()
            })
            .collect()
    }

    /// Whether the equations have no velocity terms at rest (C(q) = 0).
    pub(super) fn velocity_free(&self) -> bool {
        *self.velocity_free.get_or_init(|| {
            self.velocity_terms()
                .is_some_and(|c| c.iter().flatten().all(Expr::is_zero))
        })
    }
}

/// X at the point `at` (every entry); `None` when an entry is undefined.
pub(super) fn matrix_at(x: &[Vec<Expr>], at: &FxHashMap<Var, Expr>) -> Option<Vec<Vec<Expr>>> {
    x.iter()
        .map(|r| r.iter().map(|e| e.subs_many(at).ok()).collect())
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use Sign::*;

    #[test]
    fn sylvester_reads_the_leading_minors() {
        let d = |s: &[Option<Sign>]| from_signs(s);
        assert_eq!(d(&[Some(Positive), Some(Positive)]), Definiteness::Positive);
        assert_eq!(d(&[Some(Negative), Some(Positive)]), Definiteness::Negative);
        assert_eq!(
            d(&[Some(Positive), Some(Negative), None]),
            Definiteness::Indefinite {
                not_negative: 0,
                not_positive: 1
            }
        );
        assert_eq!(d(&[Some(Positive), Some(Zero)]), Definiteness::Singular);
        assert_eq!(
            d(&[Some(Zero), Some(Negative)]),
            Definiteness::Indefinite {
                not_negative: 0,
                not_positive: 0
            }
        );
        assert_eq!(d(&[Some(Positive), None]), Definiteness::Undecided(1));
        assert_eq!(d(&[None, Some(Positive)]), Definiteness::Undecided(0));
    }
}
