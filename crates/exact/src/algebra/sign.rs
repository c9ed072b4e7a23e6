//! Signs of canonical expressions: exactly, for every positive value of the
//! parameters, or at given parameter values.

use crate::expr::atom::{self, Atom};
use crate::expr::Expr;
use crate::num::Q;
use crate::poly::{Poly, Var};

/// Parameter values for numeric work (`--set m=1,g=9.81`).
pub type Values = std::collections::BTreeMap<String, f64>;

/// The sign of a real number.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Sign {
    /// Less than zero.
    Negative,
    /// Zero.
    Zero,
    /// Greater than zero.
    Positive,
}

impl Sign {
    /// The sign of a nonzero `x`: positive or negative (not zero).
    fn of_nonzero(x: f64) -> Sign {
        if x > 0.0 {
            Sign::Positive
        } else {
            Sign::Negative
        }
    }
}

impl std::ops::Mul for Sign {
    type Output = Sign;
    fn mul(self, other: Sign) -> Sign {
        match (self, other) {
            (Sign::Zero, _) | (_, Sign::Zero) => Sign::Zero,
            (a, b) if a == b => Sign::Positive,
            _ => Sign::Negative,
        }
    }
}

/// The sign when decided exactly: for every positive value of the
/// parameters, under the assumptions in force ([`super::assume`]).
pub fn sign_exact(e: &Expr) -> Option<Sign> {
    super::assume::decide(e, sign_positive)
}

/// The sign when decided exactly for every positive value of the parameters.
fn sign_positive(e: &Expr) -> Option<Sign> {
    if let Some(q) = e.as_rational() {
        return Some(rational_sign(&q));
    }
    let n = definite(e.num())?;
    let d = definite(e.den())?;
    Some(n * d)
}

fn rational_sign(q: &Q) -> Sign {
    if q.is_zero() {
        Sign::Zero
    } else if q.is_negative() {
        Sign::Negative
    } else {
        Sign::Positive
    }
}

/// The sign of a polynomial whose atoms are all positive and whose
/// coefficients all have one sign, or which is a positive monomial times
/// a real number built from radicals (2·g − √2·g = g·(2 − √2)), or
/// A + B·√P with A and B definite (the roots of a quadratic in ω²).
fn definite(p: &Poly) -> Option<Sign> {
    one_signed(p)
        .or_else(|| radical_number(p))
        .or_else(|| with_one_root(p))
}

/// The sign, exactly or at the given parameter values.
///
/// With parameter values, the numeric sign comes first: an exact sign is a
/// claim for all positive parameters, and a radical in it (a discriminant)
/// can vanish at particular values, where two equilibria merge.
pub fn sign_of(e: &Expr, set: &Values) -> Option<Sign> {
    if let Some(s) = sign_numeric(e, set) {
        return Some(s);
    }
    sign_exact(e)
}

/// The sign at the given parameter values, if they determine it.
fn sign_numeric(e: &Expr, set: &Values) -> Option<Sign> {
    if let Some(q) = e.as_rational() {
        return Some(rational_sign(&q));
    }
    if set.is_empty() {
        return None;
    }
    let at = |a: &Atom| match a {
        Atom::Param(n) => set.get(&**n).copied(),
        _ => None,
    };
    let num = Expr::from_poly(e.num().clone());
    let v = num.eval_f64(&at)?;
    let den = Expr::from_poly(e.den().clone()).eval_f64(&at)?;
    if !v.is_finite() || !den.is_finite() || den == 0.0 {
        return None;
    }
    // zero relative to the size of the numerator's terms
    let scale = e
        .num()
        .terms()
        .iter()
        .filter_map(|(m, c)| {
            Expr::from_poly(Poly::monomial(m.clone(), c.clone()))
                .eval_f64(&at)
                .map(f64::abs)
        })
        .fold(0.0, f64::max);
    if v.abs() <= 1e-12 * scale {
        return Some(Sign::Zero);
    }
    Some(Sign::of_nonzero(v) * Sign::of_nonzero(den))
}

/// p = A + B·√P with one radical atom √P (degree 1) and A, B of decided
/// signs: if they agree, that sign; otherwise A − B·√P has A's sign and
/// (A + B√P)(A − B√P) = A² − B²·P, so the sign is sign(A)·sign(A² − B²P).
fn with_one_root(p: &Poly) -> Option<Sign> {
    let roots: Vec<Var> = p
        .vars()
        .into_iter()
        .filter(|&v| matches!(atom::atom(v), Atom::SqrtOf(_)))
        .collect();
    let [r] = roots.as_slice() else {
        return None;
    };
    let cs = p.coeffs_in(*r);
    if cs.len() != 2 {
        return None;
    }
    let (a, b) = (&cs[0], &cs[1]);
    let sb = definite(b)?;
    if a.is_zero() {
        return Some(sb);
    }
    let sa = definite(a)?;
    if sa == sb {
        return Some(sa);
    }
    let square = atom::square_of(*r)?;
    let diff = &(a * a) - &(&(b * b) * &square);
    if diff.is_zero() {
        return None;
    }
    let sd = definite(&crate::expr::reduce_poly(&diff))?;
    Some(sa * sd)
}

/// p = (monomial in positive atoms) × (a combination of √n): the sign of
/// the number, which is nonzero (p is canonical and not zero) and is
/// evaluated in f64 only when far from 0.
fn radical_number(p: &Poly) -> Option<Sign> {
    let mut terms = p.terms().iter();
    let first = terms.next()?.0.clone();
    let g = terms.fold(first, |g, (m, _)| g.gcd(m));
    let rest = p.div_mono(&g)?;
    if !rest
        .vars()
        .iter()
        .all(|&v| matches!(atom::atom(v), Atom::Root(_)))
    {
        return None;
    }
    let positive_part = g.0.iter().all(|&(v, k)| {
        k % 2 == 0
            || matches!(
                atom::atom(v),
                Atom::Param(_) | Atom::Pi | Atom::Root(_) | Atom::SqrtOf(_) | Atom::Exp(_)
            )
    });
    if !positive_part {
        return None;
    }
    let v = Expr::from_poly(rest.clone()).eval_f64(&|_| None)?;
    let scale = rest
        .terms()
        .iter()
        .filter_map(|(m, c)| {
            Expr::from_poly(Poly::monomial(m.clone(), c.clone()))
                .eval_f64(&|_| None)
                .map(f64::abs)
        })
        .fold(0.0, f64::max);
    if !v.is_finite() || v.abs() <= 1e-9 * scale {
        return None;
    }
    Some(Sign::of_nonzero(v))
}

fn one_signed(p: &Poly) -> Option<Sign> {
    let positive = |v: Var| {
        matches!(
            atom::atom(v),
            Atom::Param(_) | Atom::Pi | Atom::Root(_) | Atom::SqrtOf(_) | Atom::Exp(_)
        )
    };
    let mut sign = Sign::Zero;
    for (m, c) in p.terms() {
        if !m.0.iter().all(|&(v, k)| k % 2 == 0 || positive(v)) {
            return None;
        }
        let sg = if c.is_negative() {
            Sign::Negative
        } else {
            Sign::Positive
        };
        if sign != Sign::Zero && sg != sign {
            return None;
        }
        sign = sg;
    }
    Some(sign)
}
