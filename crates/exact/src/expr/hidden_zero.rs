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

/// Whether a hidden zero can arise in this process at all: some opaque
/// constant or some pair of commensurable angles has been interned. Callers
/// that must prepare a polynomial for [`may_be_zero`] ask this first.
pub fn can_arise() -> bool {
    atom::any_opaque_constant() || atom::any_commensurable_angles()
}

/// Whether the nonzero canonical polynomial `p` may nevertheless be zero:
/// with sin/cos of rationally related angles in it (x and x/2), when it
/// vanishes at three sample points; else with opaque constants in it, when
/// every coefficient they make is numerically zero. False at once (without
/// touching the atom table) while neither kind of atom exists in the
/// process.
pub fn may_be_zero(p: &Poly) -> bool {
    if p.is_zero() || !can_arise() {
        return false;
    }
    if atom::any_commensurable_angles() && has_commensurable_angles(p) {
        return vanishes_at_sample_points(p);
    }
    if !atom::any_opaque_constant() {
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

/// Whether `p` holds, itself or inside its atoms' arguments, sin or cos
/// of two angles c·m and c'·m with c ≠ c' (x and x/2): independent atoms
/// whose relations the canonical form does not use.
fn has_commensurable_angles(p: &Poly) -> bool {
    let mut all: Vec<Var> = Vec::new();
    for v in p.vars() {
        all.push(v);
        all.extend_from_slice(&atom::inner_atoms(v));
    }
    all.sort_unstable();
    all.dedup();
    let mut bases: FxHashMap<Mono, Q> = FxHashMap::default();
    for v in all {
        let a = atom::atom(v);
        if !matches!(a, Atom::Sin(_) | Atom::Cos(_)) {
            continue;
        }
        if let Some((m, c)) = atom::single_term(a.argument()) {
            match bases.get(&m) {
                Some(first) if *first != c => return true,
                Some(_) => {}
                None => {
                    bases.insert(m, c);
                }
            }
        }
    }
    false
}

/// Whether `p` is zero to 10^−[`ZERO_DIGITS`] of the sum of its terms'
/// sizes at three points of every symbol (parameters and unknowns in
/// [0.5, 2.5), coordinates, t and given functions in [−1.5, 1.5), from a
/// fixed hash of each symbol, so the answer is reproducible). A polynomial
/// in functions of the symbols that is not identically zero is nonzero at
/// almost every point.
fn vanishes_at_sample_points(p: &Poly) -> bool {
    use std::hash::{Hash, Hasher};
    let threshold = 10f64.powi(-ZERO_DIGITS);
    (0u64..3).all(|point| {
        let leaf = |a: &Atom| {
            let mut h = rustc_hash::FxHasher::default();
            (a, point).hash(&mut h);
            // 53 bits of a mixed hash: a number in [0, 1)
            let z = h.finish().wrapping_mul(0x9E37_79B9_7F4A_7C15);
            let unit = (z >> 11) as f64 / (1u64 << 53) as f64;
            match a {
                Atom::Param(_) | Atom::Unknown(_) => Some(0.5 + 2.0 * unit),
                Atom::Coord(..) | Atom::Given(..) | Atom::Time => Some(3.0 * unit - 1.5),
                _ => None,
            }
        };
        let mut values: FxHashMap<Var, Option<f64>> = FxHashMap::default();
        let (mut sum, mut size) = (0.0f64, 0.0f64);
        for (m, c) in p.terms() {
            let mut t = c.to_f64();
            for &(v, e) in m.0.iter() {
                let x = *values
                    .entry(v)
                    .or_insert_with(|| super::func::eval_atom(v, &leaf));
                match x {
                    Some(x) => t *= x.powi(e.min(i32::MAX as u32) as i32),
                    None => t = f64::NAN,
                }
            }
            sum += t;
            size += t.abs();
        }
        !(sum.is_finite() && size.is_finite() && sum.abs() > threshold * size)
    })
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum Kind {
    Opaque,
    Exact,
    Variable,
}
