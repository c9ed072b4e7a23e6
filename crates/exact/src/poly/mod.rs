//! Sparse multivariate polynomials over the exact rationals [`Q`].
//!
//! A [`Poly`] is a list of `(Mono, Q)` terms kept sorted in descending
//! lexicographic order (smallest variable id most significant), with no zero
//! coefficients and no duplicate monomials, so structural equality is value
//! equality.
//!
//! Multiplication and exact division temporarily pack monomials into `u128`
//! keys (one bit field per variable, smallest variable in the most significant
//! bits, so integer order is the monomial order) whenever the exponents fit;
//! otherwise they fall back to working on [`Mono`] directly.
//!
//! The GCD ([`Poly::gcd`]) works over Z after clearing denominators:
//! 1. trivial cases (zero, constants, monomials, equal inputs);
//! 2. the monomial gcd is split off;
//! 3. variables present in only one argument are eliminated by taking the
//!    gcd with all coefficients with respect to them;
//! 4. univariate images modulo a 62-bit prime at random points give upper
//!    bounds on the degree of the gcd in every variable; variables with bound
//!    0 are eliminated the same way (so coprime inputs are detected cheaply);
//! 5. trial division when the bounds say one input may divide the other;
//! 6. for inputs linear in some variable (and more than 3 variables): a
//!    recursive subresultant PRS (one pseudo-remainder step);
//! 7. otherwise the heuristic gcd GCDHEU (at most 3 variables) and Zippel's
//!    sparse modular interpolation (with Brown's leading-coefficient
//!    normalization), each verified by exact division;
//! 8. the recursive subresultant PRS as the always-correct fallback.
//!
//! A verified common divisor whose degrees meet the bounds of step 4 is
//! certified to be the gcd; a verified common divisor of smaller degree is
//! factored out and the gcd of the cofactors computed recursively. The result
//! is therefore always exact; randomness only affects speed.

mod arith;
mod content;
pub mod factor;
mod gcd;
mod modular;
mod monomial;
mod ops;
mod packed;
mod sqrt;
mod structure;

pub use monomial::{mono_gcd, Mono};

use crate::num::Q;
use std::fmt;
use std::hash::Hash;

/// A variable id.
pub type Var = u32;

/// A polynomial: terms sorted by monomial in DESCENDING lexicographic order,
/// no zero coefficients, no duplicate monomials. The leading term is `terms[0]`.
#[derive(Clone, PartialEq, Eq, Hash, Debug, Default)]
pub struct Poly {
    terms: Vec<(Mono, Q)>,
}

static ZERO_Q: Q = Q::zero();

// ===========================================================================
// Poly: construction and inspection
// ===========================================================================

impl Poly {
    /// The zero polynomial.
    #[inline]
    pub fn zero() -> Poly {
        Poly { terms: Vec::new() }
    }

    /// The constant 1.
    #[inline]
    pub fn one() -> Poly {
        Poly::constant(Q::one())
    }

    /// A constant.
    pub fn constant(c: Q) -> Poly {
        if c.is_zero() {
            Poly::zero()
        } else {
            Poly {
                terms: vec![(Mono::one(), c)],
            }
        }
    }

    /// The variable `v`.
    pub fn var(v: Var) -> Poly {
        Poly {
            terms: vec![(Mono::var(v), Q::one())],
        }
    }

    /// The single term `c * m`.
    pub fn monomial(m: Mono, c: Q) -> Poly {
        if c.is_zero() {
            Poly::zero()
        } else {
            Poly {
                terms: vec![(m, c)],
            }
        }
    }

    /// From arbitrary terms: sorts, merges duplicate monomials, drops zeros.
    /// Monomials must themselves be normalized (see [`Mono::from_pairs`]).
    pub fn from_terms(mut terms: Vec<(Mono, Q)>) -> Poly {
        terms.sort_unstable_by(|a, b| b.0.cmp(&a.0));
        let mut out: Vec<(Mono, Q)> = Vec::with_capacity(terms.len());
        for (m, c) in terms {
            match out.last_mut() {
                Some(last) if last.0 == m => last.1 += c,
                _ => {
                    if let Some(last) = out.last() {
                        if last.1.is_zero() {
                            out.pop();
                        }
                    }
                    out.push((m, c));
                }
            }
        }
        if let Some(last) = out.last() {
            if last.1.is_zero() {
                out.pop();
            }
        }
        Poly { terms: out }
    }

    /// From terms already sorted descending, distinct and nonzero.
    #[inline]
    fn from_sorted(terms: Vec<(Mono, Q)>) -> Poly {
        debug_assert!(terms.windows(2).all(|w| w[0].0 > w[1].0));
        debug_assert!(terms.iter().all(|t| !t.1.is_zero()));
        Poly { terms }
    }

    /// The terms, in descending monomial order.
    #[inline]
    pub fn terms(&self) -> &[(Mono, Q)] {
        &self.terms
    }

    /// Consumes the polynomial, returning its terms.
    #[inline]
    pub fn into_terms(self) -> Vec<(Mono, Q)> {
        self.terms
    }

    /// Number of terms.
    #[inline]
    pub fn len(&self) -> usize {
        self.terms.len()
    }

    /// `self == 0`.
    #[inline]
    pub fn is_zero(&self) -> bool {
        self.terms.is_empty()
    }

    /// No terms, i.e. `self == 0` (same as [`Poly::is_zero`]).
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.terms.is_empty()
    }

    /// `self == 1`.
    #[inline]
    pub fn is_one(&self) -> bool {
        self.terms.len() == 1 && self.terms[0].0.is_one() && self.terms[0].1.is_one()
    }

    /// `self` is a constant (including zero).
    #[inline]
    pub fn is_constant(&self) -> bool {
        self.terms.is_empty() || (self.terms.len() == 1 && self.terms[0].0.is_one())
    }

    /// The value if `self` is constant; `Some(&0)` for the zero polynomial
    /// (a reference to a static zero, no allocation).
    #[inline]
    pub fn as_constant(&self) -> Option<&Q> {
        match self.terms.len() {
            0 => Some(&ZERO_Q),
            1 if self.terms[0].0.is_one() => Some(&self.terms[0].1),
            _ => None,
        }
    }

    /// Exactly one term (nonzero).
    #[inline]
    pub fn is_monomial(&self) -> bool {
        self.terms.len() == 1
    }

    /// Coefficient of the leading term.
    #[inline]
    pub fn leading_coeff(&self) -> Option<&Q> {
        self.terms.first().map(|t| &t.1)
    }

    /// Monomial of the leading term.
    #[inline]
    pub fn leading_mono(&self) -> Option<&Mono> {
        self.terms.first().map(|t| &t.0)
    }

    /// The leading term.
    #[inline]
    pub fn leading_term(&self) -> Option<&(Mono, Q)> {
        self.terms.first()
    }

    /// Coefficient of monomial `m` (zero if absent).
    pub fn coeff_of(&self, m: &Mono) -> Q {
        match self.terms.binary_search_by(|t| m.cmp(&t.0)) {
            Ok(i) => self.terms[i].1.clone(),
            Err(_) => Q::zero(),
        }
    }
}

impl fmt::Display for Poly {
    /// Like `3*x0^2*x1 - 1/2*x2 + 1`; `0` for the zero polynomial.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.terms.is_empty() {
            return write!(f, "0");
        }
        for (i, (m, c)) in self.terms.iter().enumerate() {
            let neg = c.is_negative();
            let a = c.abs();
            if i == 0 {
                if neg {
                    write!(f, "-")?;
                }
            } else if neg {
                write!(f, " - ")?;
            } else {
                write!(f, " + ")?;
            }
            if m.is_one() {
                write!(f, "{a}")?;
            } else if a.is_one() {
                write!(f, "{m}")?;
            } else {
                write!(f, "{a}*{m}")?;
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests;
