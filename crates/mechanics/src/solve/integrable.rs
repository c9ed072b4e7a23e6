//! Velocity constraints that integrate to a position constraint.
//!
//! A constraint Σ a_k(q, t)·q̇_k + b(q, t) = 0 is the time derivative of
//! f(q, t) = C when μ·(a, b) is a gradient, which the symmetric-derivative
//! test ∂(μ·a_i)/∂q_j = ∂(μ·a_j)/∂q_i (t counted as a coordinate with
//! coefficient b) decides exactly. The factors μ tried are 1 and 1/a_k
//! (the constraint divided by one of its coefficients): the simple cases,
//! not a search for every integrating factor. f is found by integrating
//! coordinate by coordinate, for the integrands whose antiderivative is
//! elementary here (polynomials in the coordinate, sinᵏ·cos, sin), and
//! checked by differentiating it back.
//!
//! The constant C is chosen so that f = C holds where every coordinate and
//! t are 0: the reference from which a scene measures its coordinates, and
//! about which `modes` linearizes by default.

use crate::expr::{atom, func, print, Expr};
use crate::num::Q;
use crate::poly::{Mono, Poly, Var};
use crate::scene::Constraint;
use rustc_hash::FxHashMap;

/// What a velocity constraint integrates to.
#[derive(Clone, Debug, PartialEq)]
pub enum Integral {
    /// The position form `lhs = rhs`, in the input syntax, holding where
    /// every coordinate and t are 0.
    Written(String),
    /// The position form f = C, with f written (in the input syntax), where
    /// f is undefined at the coordinates' zero so C is left to the user.
    WithConstant(String),
    /// Exact (a gradient after a simple factor), but f has no closed form
    /// here.
    Unwritten,
}

/// The integral of the velocity constraint `c` in the coordinates `q`, or
/// `None` when no simple factor makes it exact (rolling of a coin: not
/// integrable at all).
pub fn integral(c: &Constraint, q: &[Var]) -> Option<Integral> {
    if c.holonomic {
        return None;
    }
    let mut vars = q.to_vec();
    vars.push(atom::time());
    let mut coefficients = c.coefficients.clone();
    coefficients.push(c.rest.clone());
    let mut exact_unwritten = false;
    for factor in factors(&c.coefficients) {
        let scaled: Vec<Expr> = coefficients.iter().map(|a| a.mul(&factor)).collect();
        if !is_gradient(&scaled, &vars) {
            continue;
        }
        match potential(&scaled, &vars) {
            Some(f) => return Some(written(&f, &scaled[..q.len()], &vars)),
            None => exact_unwritten = true,
        }
    }
    exact_unwritten.then_some(Integral::Unwritten)
}

/// The hint of a refusal of the velocity constraint `c` (`label` as the
/// messages name it): its position form when it integrates, else `fallback`.
pub fn hint(c: &Constraint, q: &[Var], fallback: &str) -> String {
    let statement = |eq: &str| match &c.name {
        Some(n) => format!("`constraint {n}: {eq}`"),
        None => format!("`constraint {eq}`"),
    };
    match integral(c, q) {
        Some(Integral::Written(eq)) => format!(
            "the constraint integrates: write it in the positions, {} (the constant of integration taken so that it holds where every coordinate is 0)",
            statement(&eq)
        ),
        Some(Integral::WithConstant(f)) => format!(
            "the constraint integrates: write it in the positions, {} with C0 a parameter, the constant of integration, from the initial position",
            statement(&format!("{f} = C0"))
        ),
        Some(Integral::Unwritten) => format!(
            "the constraint integrates (its coefficients are a gradient): write it in the positions; {fallback}"
        ),
        None => fallback.to_string(),
    }
}

/// The factors μ tried: 1, then the reciprocals of the non-constant
/// coefficients (a constant one gives the same test as 1).
fn factors(coefficients: &[Expr]) -> Vec<Expr> {
    let mut out = vec![Expr::one()];
    for a in coefficients {
        if a.is_zero() || a.as_rational().is_some() {
            continue;
        }
        if let Ok(r) = a.recip() {
            if !out.iter().any(|f: &Expr| f.equals(&r)) {
                out.push(r);
            }
        }
    }
    out
}

/// Whether (a_k) over `vars` has a symmetric Jacobian: ∂a_i/∂v_j = ∂a_j/∂v_i.
fn is_gradient(a: &[Expr], vars: &[Var]) -> bool {
    (0..vars.len())
        .all(|i| (i + 1..vars.len()).all(|j| a[i].diff(vars[j]).equals(&a[j].diff(vars[i]))))
}

/// f with ∂f/∂v_k = a_k for every k, integrated variable by variable and
/// checked; `None` when an integrand has no antiderivative here.
fn potential(a: &[Expr], vars: &[Var]) -> Option<Expr> {
    let mut f = Expr::zero();
    for (k, &v) in vars.iter().enumerate() {
        let remainder = a[k].sub(&f.diff(v));
        if remainder.is_zero() {
            continue;
        }
        f = f.add(&antiderivative(&remainder, v)?);
    }
    vars.iter()
        .zip(a)
        .all(|(&v, ak)| f.diff(v).equals(ak))
        .then_some(f)
}

/// ∫ e dv for e a sum of terms c·vⁿ, c·sinᵏ(v)·cos(v) and c·sin(v), with c
/// free of v over a denominator free of v; `None` otherwise.
fn antiderivative(e: &Expr, v: Var) -> Option<Expr> {
    let den = Expr::from_poly(e.den().clone());
    if den.depends_on(v) {
        return None;
    }
    let angle = Expr::var(v);
    let sin = func::sin(&angle).as_var();
    let cos = func::cos(&angle).as_var();
    let mut sum = Expr::zero();
    for (m, c) in e.num().terms() {
        let mut rest = Vec::new();
        let (mut n, mut ks, mut kc) = (0, 0, 0);
        for &(x, d) in m.pairs() {
            if x == v {
                n = d;
            } else if Some(x) == sin {
                ks = d;
            } else if Some(x) == cos {
                kc = d;
            } else if atom::contains(x, v) {
                return None;
            } else {
                rest.push((x, d));
            }
        }
        let coefficient = Expr::from_poly(Poly::monomial(Mono::from_pairs(rest), c.clone()));
        let integrated = match (n, ks, kc) {
            (n, 0, 0) => angle.powi(i64::from(n) + 1).ok()?.scale(&inverse(n + 1)?),
            (0, k, 1) => func::sin(&angle)
                .powi(i64::from(k) + 1)
                .ok()?
                .scale(&inverse(k + 1)?),
            (0, 1, 0) => func::cos(&angle).neg(),
            _ => return None,
        };
        sum = sum.add(&coefficient.mul(&integrated));
    }
    sum.div(&den).ok()
}

/// 1/n.
fn inverse(n: u32) -> Option<Q> {
    Q::new(1, i64::from(n))
}

/// f = C as written: C taken from f where every variable is 0, the terms
/// split by sign into the two sides (`R*phi + s = x`). Where f's gradient
/// `gradient` is 0 or undefined there (x² + y² = C through the origin is
/// a point, not a curve) the constant is left to the user.
fn written(f: &Expr, gradient: &[Expr], vars: &[Var]) -> Integral {
    let zero: FxHashMap<Var, Expr> = vars.iter().map(|&v| (v, Expr::zero())).collect();
    let regular = gradient
        .iter()
        .any(|a| a.subs_many(&zero).is_ok_and(|a| !a.is_zero()));
    let at_zero = match f.subs_many(&zero) {
        Ok(c) if regular => c,
        _ => return Integral::WithConstant(print::input(f)),
    };
    let g = f.sub(&at_zero);
    let den = Expr::from_poly(g.den().clone());
    let (mut lhs, mut rhs) = (Expr::zero(), Expr::zero());
    for (m, c) in g.num().terms() {
        let term = Expr::from_poly(Poly::monomial(m.clone(), c.abs()));
        if c.is_negative() {
            rhs = rhs.add(&term);
        } else {
            lhs = lhs.add(&term);
        }
    }
    // the coordinates on the left: `x + cos(z) = 1`, not `1 = x + cos(z)`
    if !vars.iter().any(|&v| lhs.depends_on(v)) {
        std::mem::swap(&mut lhs, &mut rhs);
    }
    let side = |e: &Expr| {
        e.div(&den)
            .map_or_else(|_| print::input(e), |e| print::input(&e))
    };
    Integral::Written(format!("{} = {}", side(&lhs), side(&rhs)))
}
