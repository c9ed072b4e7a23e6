//! Zeros the canonical form cannot see.
//!
//! A function of constants alone — `sin(π/7)`, `√(5 − √5)`, `exp(1)` — is an
//! atom related to the others only by r² = P, sin² + cos² = 1 and the
//! multiple-angle formulas ([`atom::is_opaque_constant`]). A polynomial in
//! such atoms can be zero while its canonical form is not:
//! cos(π/7) − cos(2π/7) + cos(3π/7) − 1/2 is a polynomial in sin(π/7) and
//! cos(π/7) that no rule reduces. Dividing by it would give an expression
//! with a zero
//! denominator, silently. [`may_be_zero`] finds the denominators that could
//! be such a zero, so that the division refuses instead.
//!
//! The test: a polynomial is zero only if, grouped by its power products of
//! everything that is not a constant (parameters, coordinates, t, functions
//! of them), every group's coefficient — a polynomial in constants — is
//! zero. A coefficient in π and √n alone is zero exactly when its canonical
//! form is (π is transcendental, and the products of distinct prime
//! radicals are linearly independent over ℚ), so one such group decides.
//! A coefficient with opaque constants is evaluated in floating point: if
//! its value exceeds 10^−[`ZERO_DIGITS`] times the sum of its terms' sizes, it
//! is certainly not zero (the rounding error of that evaluation is about
//! 10⁻¹⁶ per operation, far below the threshold). Only when every group is
//! zero to that precision is the polynomial reported as possibly zero.

use super::atom::{self, Atom};
use crate::num::Q;
use crate::poly::{Mono, Poly, Var};
use rustc_hash::FxHashMap;

/// A constant coefficient is numerically zero when it is below 10^−this
/// times the sum of its terms' sizes: far above the rounding error of its
/// evaluation in f64 (the number of operations times 2⁻⁵³, about 10⁻¹³ for
/// a coefficient of a thousand terms), and far below any nonzero algebraic
/// number of the sizes met.
pub const ZERO_DIGITS: i32 = 9;

/// Whether a constant of a power product is known exactly (π, √n), so that
/// the canonical form alone decides whether a polynomial in it is zero.
fn is_exact_constant(v: Var) -> bool {
    matches!(atom::atom(v), Atom::Pi | Atom::Root(_))
}

/// Whether the nonzero canonical polynomial `p` may nevertheless be zero:
/// some opaque constants in it, and every coefficient they make numerically
/// zero. False at once (without touching the atom table) while no opaque
/// constant exists in the process.
pub fn may_be_zero(p: &Poly) -> bool {
    if p.is_zero() || !atom::any_opaque_constant() {
        return false;
    }
    if !p.vars().into_iter().any(atom::is_opaque_constant) {
        return false;
    }
    let mut kinds: FxHashMap<Var, Kind> = FxHashMap::default();
    let mut kind = |v: Var| {
        *kinds.entry(v).or_insert_with(|| {
            if atom::is_opaque_constant(v) {
                Kind::Opaque
            } else if is_exact_constant(v) {
                Kind::Exact
            } else {
                Kind::Variable
            }
        })
    };
    // group the terms by their power product of non-constants
    let mut groups: FxHashMap<Mono, Vec<(Mono, &Q)>> = FxHashMap::default();
    for (m, c) in p.terms() {
        let (mut constant, mut variable) = (Mono::one(), Mono::one());
        for &(v, e) in m.0.iter() {
            match kind(v) {
                Kind::Variable => variable.0.push((v, e)),
                _ => constant.0.push((v, e)),
            }
        }
        groups.entry(variable).or_default().push((constant, c));
    }
    let threshold = 10f64.powi(-ZERO_DIGITS);
    let mut values: FxHashMap<Var, Option<f64>> = FxHashMap::default();
    for coefficient in groups.values() {
        let opaque = coefficient
            .iter()
            .any(|(m, _)| m.0.iter().any(|&(v, _)| kind(v) == Kind::Opaque));
        if !opaque {
            return false; // exact constants alone: the canonical form decides
        }
        let (mut sum, mut size) = (0.0f64, 0.0f64);
        for (m, c) in coefficient {
            let mut t = c.to_f64();
            for &(v, e) in m.0.iter() {
                let x = *values
                    .entry(v)
                    .or_insert_with(|| super::func::eval_atom(v, &|_| None));
                match x {
                    Some(x) => t *= x.powi(e.min(i32::MAX as u32) as i32),
                    None => t = f64::NAN,
                }
            }
            sum += t;
            size += t.abs();
        }
        if sum.is_finite() && size.is_finite() && sum.abs() > threshold * size {
            return false;
        }
    }
    true
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum Kind {
    Opaque,
    Exact,
    Variable,
}
