//! Stability of the linearized system M·q̈ + C·q̇ + K·q = 0 about an
//! equilibrium, decided exactly where it can be and numerically whenever
//! every entry has a value. The steps below read M as positive definite;
//! `definite.rs` decides M first (negative definite: the same verdict on
//! −K; neither: unstable where that is proved, never stable).
//!
//! In this order, each shortcut only where its precondition is proved:
//! 1. K symmetric: its definiteness by Sylvester's criterion (its leading
//!    minors, one source of truth with the equilibria:
//!    [`super::equilibrium::minor_signs`]). K positive definite is stable
//!    when the velocity terms dissipate no negative energy (C's symmetric
//!    part positive semidefinite: none, gyroscopic terms by Kelvin–Tait,
//!    damping); an odd number of negative directions is unstable whatever
//!    the velocity terms (det K < 0: a real root s > 0), any negative
//!    direction is without velocity terms, and any is under complete
//!    damping (Kelvin–Tait–Chetaev).
//! 2. Without damping (C zero, or skew with K symmetric) the roots λ = ω²
//!    of the characteristic polynomial in λ, from its factors over ℚ:
//!    stable when every root is real and positive. A linear factor gives
//!    λ > 0; a quadratic a·λ² + b·λ + c, whose roots are real for symmetric
//!    K and M, gives c/a > 0 and −b/a > 0; where the roots need not be real
//!    (C skew: gyroscopic, or K not symmetric: circulatory) they are real,
//!    positive and distinct exactly when c/a > 0 and −b/a > 2·√(c/a), one
//!    condition that holds the roots' existence (real) and their sign
//!    together, so a root that is real only where it would be negative
//!    makes the system unstable, not "stable when …" (a cubic: its
//!    discriminant and its coefficients' signs). A condition the
//!    parameters do not decide is printed, its positive factors left out.
//! 3. Otherwise (damping with circulatory forces, a damping of no proved
//!    sign, …) the Routh–Hurwitz conditions on det(s²·M + s·C + K)
//!    (`hurwitz.rs`).
//! 4. With every parameter given (`--set`), the eigenvalues s of the
//!    first-order system [[0, I], [−M⁻¹K, −M⁻¹C]]: one with Re s > 0 is
//!    unstable, all on the left or on the imaginary axis is stable.
//!
//! Only a zero frequency (higher-order terms decide), a repeated frequency
//! without damping, and a root on the imaginary axis of a damped system
//! exactly at the boundary stay undecided.

use super::condition::{describe, Condition, Positivity};
use super::definite::{negated, Mass, Stiffness};
use super::equilibrium::{jacobi, minor_signs, Stability};
use super::hurwitz::Dissipation;
use crate::algebra::sign::{sign_of, Sign, Values};
use crate::expr::atom::Atom;
use crate::expr::{func, Expr};
use crate::num::Q;
use crate::poly::Var;
use nalgebra::DMatrix;

/// The linearized system whose stability is decided.
pub(super) struct Linearized<'a> {
    pub(super) mass: &'a [Vec<Expr>],
    pub(super) damping: &'a [Vec<Expr>],
    pub(super) stiffness: &'a [Vec<Expr>],
    /// C is skew (and not zero): the characteristic polynomial is that of
    /// det(K + s·C + s²·M).
    pub(super) gyroscopic: bool,
}

/// The verdict: K's minors, then the characteristic polynomial `p` in `lv`,
/// then the numeric eigenvalues at `set`.
///
/// All of it reads M as positive definite; [`Mass::verdict`] decides M
/// first (a negative definite M is the system of −L, whose verdict this
/// is with −K; anything else is never "stable").
pub(super) fn stability(
    sys: &Linearized,
    mass: &Mass,
    p: &Expr,
    lv: Var,
    set: &Values,
) -> Stability {
    let damped = sys.damping.iter().flatten().any(|e| !e.is_zero());
    mass.verdict(
        || Stiffness::exact(sys.stiffness, set),
        || !damped,
        || {
            // a root λ off [0, ∞) of a polynomial that holds C (none, or
            // skew) grows whatever M is; so does an eigenvalue Re s > 0
            let exact = (!damped || sys.gyroscopic)
                && (from_factors(p, lv, false, set) == Stability::Unstable
                    || complex_root(p, lv, set));
            exact || numeric(sys, set) == Some(Stability::Unstable)
        },
        |negate| {
            // the system of −L is (−M, −C, −K)
            let flip = |x: &[Vec<Expr>]| if negate { negated(x) } else { x.to_vec() };
            let exact = positive_mass(
                &flip(sys.mass),
                &flip(sys.damping),
                &flip(sys.stiffness),
                sys.gyroscopic,
                p,
                lv,
                set,
            );
            if !matches!(exact, Stability::Undecided(_)) {
                return exact;
            }
            numeric(sys, set).unwrap_or(exact)
        },
    )
}

/// The verdict on M·q̈ + C·q̇ + K·q = 0 as `modes` gives it, for the
/// equilibria whose forces are not conservative or whose velocity terms
/// may feed energy in.
pub(super) fn of_matrices(
    m: &[Vec<Expr>],
    c: &[Vec<Expr>],
    k: &[Vec<Expr>],
    set: &Values,
) -> Stability {
    let n = m.len();
    let any = c.iter().flatten().any(|e| !e.is_zero());
    let gyroscopic = any && (0..n).all(|i| (0..n).all(|j| c[i][j].add(&c[j][i]).is_zero()));
    let lv = crate::expr::atom::unknown(super::oscillations::LAMBDA);
    let p = super::characteristic::polynomial(k, m, gyroscopic.then_some(c), lv)
        .or_else(|| super::characteristic::polynomial(k, m, None, lv));
    let Some(p) = p else {
        return Stability::Undecided("the characteristic polynomial could not be evaluated".into());
    };
    let sys = Linearized {
        mass: m,
        damping: c,
        stiffness: k,
        gyroscopic,
    };
    stability(&sys, &Mass::exact(m, set), &p, lv, set)
}

/// The exact verdict for a positive definite M (see the module docs).
fn positive_mass(
    m: &[Vec<Expr>],
    c: &[Vec<Expr>],
    k: &[Vec<Expr>],
    gyroscopic: bool,
    p: &Expr,
    lv: Var,
    set: &Values,
) -> Stability {
    let n = k.len();
    let damped = c.iter().flatten().any(|e| !e.is_zero());
    let symmetric = (0..n).all(|i| (0..i).all(|j| k[i][j].equals(&k[j][i])));
    if symmetric {
        if let Some(v) = shortcut(c, k, damped, set) {
            return v;
        }
        if !damped || gyroscopic {
            return from_factors(p, lv, !gyroscopic, set);
        }
    } else if !damped {
        // circulatory forces alone: p is det(K − λ·M), its roots not
        // necessarily real
        return from_factors(p, lv, false, set);
    }
    super::hurwitz::verdict(m, c, k, set)
}

/// What K's leading minors decide for a symmetric K, each verdict where
/// the velocity terms allow it; `None` when they do not decide.
fn shortcut(c: &[Vec<Expr>], k: &[Vec<Expr>], damped: bool, set: &Values) -> Option<Stability> {
    let signs = minor_signs(k, set).ok()?;
    let dissipation = super::hurwitz::dissipation(c, set);
    match jacobi(&signs, damped) {
        Stability::Stable if dissipation != Dissipation::Unknown => Some(Stability::Stable),
        Stability::Unstable => Some(Stability::Unstable),
        // a nonsingular K that is not positive definite under complete
        // damping (Kelvin–Tait–Chetaev)
        _ if dissipation == Dissipation::Complete
            && signs
                .iter()
                .all(|s| matches!(s, Some(Sign::Positive | Sign::Negative))) =>
        {
            Some(Stability::Unstable)
        }
        _ => None,
    }
}

/// The conditions on the factors of `p` over ℚ; `real` when every root is
/// known to be real (K and M symmetric, no velocity terms).
fn from_factors(p: &Expr, lv: Var, real: bool, set: &Values) -> Stability {
    let mut conditions: Vec<Condition> = Vec::new();
    let mut undecided: Option<String> = None;
    for (f, mult) in crate::poly::factor::factor(p.num()).factors {
        let cs: Vec<Expr> = f.coeffs_in(lv).into_iter().map(Expr::from_poly).collect();
        let verdict = match cs.len() {
            0 | 1 => continue,
            2 => linear(&cs, set),
            3 => quadratic(&cs, !real, set),
            4 if !real => cubic(&cs, set),
            _ => {
                undecided.get_or_insert_with(|| {
                    "no closed form for the frequencies; give values with --set".into()
                });
                continue;
            }
        };
        match verdict {
            Verdict::Fails => return Stability::Unstable,
            Verdict::Zero(why) => {
                undecided.get_or_insert(why);
            }
            Verdict::Holds if !real && mult > 1 => {
                undecided.get_or_insert_with(|| {
                    "a repeated frequency without damping: the linearization may grow (give values with --set)".into()
                });
            }
            Verdict::Holds => {}
            Verdict::When(c) => {
                for c in c {
                    if !conditions.contains(&c) {
                        conditions.push(c);
                    }
                }
            }
        }
    }
    if let Some(why) = undecided {
        return Stability::Undecided(why);
    }
    if conditions.is_empty() {
        return Stability::Stable;
    }
    let decides = conditions.iter().any(|c| matches!(c, Condition::Holds(_)));
    Stability::Undecided(if decides {
        format!("{}; give values with --set", describe(&conditions))
    } else {
        // stable but where an equation holds: there a frequency is zero
        format!(
            "{}, where the linearization does not decide",
            describe(&conditions)
        )
    })
}

/// Whether M·q̈ + K·q = 0 (no velocity terms) provably has a growing
/// solution: a root of det(K − λ·M) off the positive axis, exactly, or an
/// eigenvalue Re s > 0 at `set`.
pub(super) fn undamped_grows(m: &[Vec<Expr>], k: &[Vec<Expr>], set: &Values) -> bool {
    let lv = crate::expr::atom::unknown(super::oscillations::LAMBDA);
    let Some(p) = super::characteristic::polynomial(k, m, None, lv) else {
        return false;
    };
    if from_factors(&p, lv, true, set) == Stability::Unstable || complex_root(&p, lv, set) {
        return true;
    }
    let zero = vec![vec![Expr::zero(); m.len()]; m.len()];
    let sys = Linearized {
        mass: m,
        damping: &zero,
        stiffness: k,
        gyroscopic: false,
    };
    numeric(&sys, set) == Some(Stability::Unstable)
}

/// Whether a quadratic factor of `p` has non-real roots λ (then s² = −λ
/// has a root with Re s > 0). Its roots are real when M is definite, so
/// only an indefinite or undecided M asks.
fn complex_root(p: &Expr, lv: Var, set: &Values) -> bool {
    crate::poly::factor::factor(p.num())
        .factors
        .iter()
        .any(|(f, _)| {
            let cs: Vec<Expr> = f.coeffs_in(lv).into_iter().map(Expr::from_poly).collect();
            let [c, b, a] = cs.as_slice() else {
                return false;
            };
            let disc = b.mul(b).sub(&a.mul(c).scale(&Q::from_i64(4)));
            sign_of(&disc, set) == Some(Sign::Negative)
        })
}

/// Why a double root λ without damping leaves the verdict open.
const BOUNDARY: &str = "a double frequency at the boundary of gyroscopic or circulatory (flutter) stability: the linearization does not decide";

/// What one factor says.
enum Verdict {
    Holds,
    Fails,
    /// A zero (or double gyroscopic) root: the linearization does not decide.
    Zero(String),
    /// Holds under these conditions.
    When(Vec<Condition>),
}

/// c₀ + c₁·λ: λ = −c₀/c₁ > 0.
fn linear(cs: &[Expr], set: &Values) -> Verdict {
    let Ok(r) = cs[0].neg().div(&cs[1]) else {
        return Verdict::Zero("the characteristic polynomial could not be evaluated".into());
    };
    positive(&r, set, "a zero frequency: higher-order terms decide")
}

/// c + b·λ + a·λ²: c/a > 0 and −b/a > 0 (real roots), or where the roots
/// need not be real (`gyroscopic`: C skew, or K not symmetric)
/// −b/a − 2·√(c/a) > 0 (real, positive and distinct roots).
fn quadratic(cs: &[Expr], gyroscopic: bool, set: &Values) -> Verdict {
    let (c, b, a) = (&cs[0], &cs[1], &cs[2]);
    let (Ok(product), Ok(sum)) = (c.div(a), b.neg().div(a)) else {
        return Verdict::Zero("the characteristic polynomial could not be evaluated".into());
    };
    let zero = "a zero frequency: higher-order terms decide";
    let boundary = BOUNDARY;
    let first = positive(&product, set, zero);
    let second = if !gyroscopic {
        positive(&sum, set, zero)
    } else {
        let two = Q::from_i64(2);
        match (&first, root_of(&product, set)) {
            (Verdict::Fails | Verdict::Zero(_), _) => return first,
            (_, Root::Known(r)) => positive(&sum.sub(&r.scale(&two)), set, boundary),
            // √(r²) = |r|: −b/a > 2·|r| is −b/a > 2·r and −b/a > −2·r
            (_, Root::Either(r)) => both(
                positive(&sum.sub(&r.scale(&two)), set, boundary),
                positive(&sum.add(&r.scale(&two)), set, boundary),
            ),
            (_, Root::None) => Verdict::When(vec![Condition::Holds(format!(
                "{} > 2·√({})",
                crate::expr::print::expanded(&sum),
                crate::expr::print::expanded(&product)
            ))]),
        }
    };
    both(first, second)
}

/// d + c·λ + b·λ² + a·λ³ whose roots need not be real: real, positive and
/// distinct exactly when its discriminant is positive and −b/a, c/a and
/// −d/a are (Descartes' rule counts the positive roots of a polynomial
/// whose roots are all real).
fn cubic(cs: &[Expr], set: &Values) -> Verdict {
    let (d, c, b, a) = (&cs[0], &cs[1], &cs[2], &cs[3]);
    let ratio = |x: &Expr, negate: bool| {
        let r = x.div(a).ok()?;
        Some(if negate { r.neg() } else { r })
    };
    let (Some(sum), Some(pairs), Some(product)) = (ratio(b, true), ratio(c, false), ratio(d, true))
    else {
        return Verdict::Zero("the characteristic polynomial could not be evaluated".into());
    };
    let disc = super::characteristic::cubic_discriminant(a, b, c, d);
    let zero = "a zero frequency: higher-order terms decide";
    let boundary = BOUNDARY;
    [
        positive(&product, set, zero),
        positive(&pairs, set, zero),
        positive(&sum, set, zero),
        positive(&disc, set, boundary),
    ]
    .into_iter()
    .fold(Verdict::Holds, both)
}

/// Both verdicts together.
fn both(first: Verdict, second: Verdict) -> Verdict {
    match (first, second) {
        (Verdict::Fails, _) | (_, Verdict::Fails) => Verdict::Fails,
        (Verdict::Zero(w), _) | (_, Verdict::Zero(w)) => Verdict::Zero(w),
        (Verdict::Holds, v) | (v, Verdict::Holds) => v,
        (Verdict::When(mut x), Verdict::When(y)) => {
            x.extend(y);
            Verdict::When(x)
        }
    }
}

/// √x, when it can be written.
enum Root {
    /// P/D when x = P²/D² with P/D of known sign, else the radical √x.
    Known(Expr),
    /// x = r² with r of undecided sign: √x = |r|.
    Either(Expr),
    /// x is negative, or not formed.
    None,
}

/// √x exactly (see [`Root`]).
fn root_of(x: &Expr, set: &Values) -> Root {
    if sign_of(x, set) == Some(Sign::Negative) {
        return Root::None;
    }
    if let (Some(p), Some(d)) = (x.num().exact_sqrt(), x.den().exact_sqrt()) {
        let Ok(r) = Expr::from_parts(p, d) else {
            return Root::None;
        };
        return match sign_of(&r, set) {
            Some(Sign::Negative) => Root::Known(r.neg()),
            Some(_) => Root::Known(r),
            None => Root::Either(r),
        };
    }
    func::sqrt(x).map_or(Root::None, Root::Known)
}

/// x > 0 decided, failed, zero (`zero` says why) or a condition.
fn positive(x: &Expr, set: &Values, zero: &str) -> Verdict {
    match sign_of(x, set) {
        Some(Sign::Positive) => Verdict::Holds,
        Some(Sign::Negative) => Verdict::Fails,
        Some(Sign::Zero) => Verdict::Zero(zero.into()),
        None => match super::condition::positive(x) {
            Positivity::Holds => Verdict::Holds,
            Positivity::Fails => Verdict::Fails,
            Positivity::When(c) => Verdict::When(c),
        },
    }
}

/// The verdict from the eigenvalues of the first-order system at `set`,
/// when every entry of M, C and K has a value there.
///
/// s = 0 is a root exactly when det K = 0, decided exactly (at the values)
/// rather than from the eigenvalues: a zero frequency is a Jordan block in
/// the first-order system, which rounding splits into s ≈ ±√ε·|A|, a
/// "growing" or "oscillating" pair that is neither. So with det K = 0 (or
/// undecided) the eigenvalues within [`ZERO_CLUSTER`] of the largest are
/// that zero, and the verdict is undecided unless another one grows, as
/// the exact verdict is without values.
fn numeric(sys: &Linearized, set: &Values) -> Option<Stability> {
    let s = match eigenvalues(sys.mass, sys.damping, sys.stiffness, set) {
        Ok(s) => s?,
        Err(why) => {
            return Some(Stability::Undecided(format!(
                "the eigenvalues at the given values could not be computed ({why})"
            )))
        }
    };
    let scale = s.iter().fold(0.0f64, |a, z| a.max(z.norm()));
    let tol = 1e-9 * scale.max(f64::MIN_POSITIVE);
    let singular = crate::algebra::linear::det(sys.stiffness.to_vec())
        .and_then(|d| sign_of(&d, set))
        .is_none_or(|d| d == Sign::Zero);
    let zero = |z: &nalgebra::Complex<f64>| singular && z.norm() <= ZERO_CLUSTER * scale;
    if s.iter().any(|z| !zero(z) && z.re > tol) {
        return Some(Stability::Unstable);
    }
    if scale == 0.0 || s.iter().any(zero) {
        return Some(Stability::Undecided(
            "a zero frequency: higher-order terms decide".into(),
        ));
    }
    Some(Stability::Stable)
}

/// The verdict on numeric M, C, K with non-conservative terms (K not
/// symmetric, or C's symmetric part not positive semidefinite) from the
/// eigenvalues of the first-order system: `None` when the dissipation is
/// of known sign and K symmetric (K's minors decide), or M is singular.
pub(super) fn numeric_verdict(m: &[Vec<f64>], c: &[Vec<f64>], k: &[Vec<f64>]) -> Option<Stability> {
    let n = m.len();
    let scale = |x: &[Vec<f64>]| x.iter().flatten().fold(0.0f64, |a, v| a.max(v.abs()));
    let (ks, cs) = (scale(k), scale(c));
    let symmetric = (0..n).all(|i| (0..i).all(|j| (k[i][j] - k[j][i]).abs() <= 1e-8 * ks));
    let half = DMatrix::from_fn(n, n, |i, j| 0.5 * (c[i][j] + c[j][i]));
    let dissipative = cs == 0.0
        || nalgebra::SymmetricEigen::try_new(half, f64::EPSILON, 100 * n + 100)
            .is_some_and(|e| e.eigenvalues.iter().all(|&v| v >= -1e-9 * cs));
    if symmetric && dissipative {
        return None;
    }
    let mm = DMatrix::from_fn(n, n, |i, j| m[i][j]);
    let cc = DMatrix::from_fn(n, n, |i, j| c[i][j]);
    let kk = DMatrix::from_fn(n, n, |i, j| k[i][j]);
    let lu = mm.lu();
    let (mk, mc) = (lu.solve(&kk)?, lu.solve(&cc)?);
    let a = DMatrix::from_fn(2 * n, 2 * n, |i, j| match (i < n, j < n) {
        (true, true) => 0.0,
        (true, false) => f64::from(u8::from(j - n == i)),
        (false, true) => -mk[(i - n, j)],
        (false, false) => -mc[(i - n, j - n)],
    });
    if a.iter().any(|v| !v.is_finite()) {
        return None;
    }
    let s = match super::eigen::general_eigenvalues(&a) {
        Ok(s) => s,
        Err(e) => {
            return Some(Stability::Undecided(format!(
                "the eigenvalues here could not be computed ({e})"
            )))
        }
    };
    let scale = s.iter().fold(0.0f64, |x, z| x.max(z.norm()));
    let tol = 1e-9 * scale.max(f64::MIN_POSITIVE);
    let re = s.iter().fold(f64::NEG_INFINITY, |x, z| x.max(z.re));
    // on the axis, simple and nonzero: bounded, as `modes` says of it
    let simple = s.iter().enumerate().all(|(i, a)| {
        a.norm() > 1e-6 * scale && s[..i].iter().all(|b| (a - b).norm() > 1e-6 * scale)
    });
    Some(if re > tol {
        Stability::Unstable
    } else if re < -tol || simple {
        Stability::Stable
    } else {
        Stability::Undecided(
            "an eigenvalue on the imaginary axis within rounding, with non-conservative forces: the linearization does not decide".into(),
        )
    })
}

/// With det K = 0, the eigenvalues s of the first-order system within this
/// fraction of the largest |s| are its zero root, split by rounding (a
/// Jordan block of size k splits by about ε^(1/k)).
const ZERO_CLUSTER: f64 = 1e-4;

/// The eigenvalues s of [[0, I], [−M⁻¹K, −M⁻¹C]] at `set` (q = u·e^{s·t}).
/// `Ok(None)` when an entry has no value at `set` (or M is singular
/// there); an error when the eigenvalue iteration does not converge.
pub(super) fn eigenvalues(
    m: &[Vec<Expr>],
    c: &[Vec<Expr>],
    k: &[Vec<Expr>],
    set: &Values,
) -> Result<Option<Vec<nalgebra::Complex<f64>>>, String> {
    if set.is_empty() {
        return Ok(None);
    }
    let n = m.len();
    let at = |a: &Atom| match a {
        Atom::Param(name) => set.get(&**name).copied(),
        _ => None,
    };
    let num = |x: &[Vec<Expr>]| -> Option<DMatrix<f64>> {
        let mut out = DMatrix::zeros(n, n);
        for i in 0..n {
            for j in 0..n {
                let v = x[i][j].eval_f64(&at)?;
                if !v.is_finite() {
                    return None;
                }
                out[(i, j)] = v;
            }
        }
        Some(out)
    };
    let (Some(m), Some(c), Some(k)) = (num(m), num(c), num(k)) else {
        return Ok(None);
    };
    let lu = m.lu();
    let (Some(mk), Some(mc)) = (lu.solve(&k), lu.solve(&c)) else {
        return Ok(None);
    };
    let mut a = DMatrix::zeros(2 * n, 2 * n);
    for i in 0..n {
        a[(i, n + i)] = 1.0;
        for j in 0..n {
            a[(n + i, j)] = -mk[(i, j)];
            a[(n + i, n + j)] = -mc[(i, j)];
        }
    }
    if a.iter().any(|v| !v.is_finite()) {
        return Ok(None);
    }
    super::eigen::general_eigenvalues(&a)
        .map(Some)
        .map_err(|e| e.to_string())
}
