//! Contents and normal forms of a [`Poly`]: the rational content and
//! primitive part, the monic and the primitive-integer normalizations, and
//! the monomial content.

use super::{Mono, Poly};
use crate::num::Q;

impl Poly {
    /// Positive rational gcd of the coefficients (0 for the zero polynomial).
    pub fn content(&self) -> Q {
        let all_integer = self.terms.iter().all(|t| t.1.is_integer());
        let mut g = Q::zero();
        for (_, c) in &self.terms {
            g = g.gcd(c);
            // with fractional coefficients the gcd can still shrink below 1
            if all_integer && g.is_one() {
                return g;
            }
        }
        g
    }

    /// `self / content()`: integer coefficients with gcd 1, same signs as
    /// `self` (so `self == content * primitive`).
    pub fn primitive(&self) -> Poly {
        let c = self.content();
        if c.is_zero() || c.is_one() {
            return self.clone();
        }
        match c.recip() {
            Some(r) => self.scale(&r),
            None => self.clone(),
        }
    }

    /// Leading coefficient 1 (zero stays zero).
    pub fn monic(&self) -> Poly {
        match self.leading_coeff() {
            None => Poly::zero(),
            Some(c) if c.is_one() => self.clone(),
            Some(c) => match c.recip() {
                Some(r) => self.scale(&r),
                None => self.clone(),
            },
        }
    }

    /// Primitive integer polynomial with positive leading coefficient.
    pub(super) fn normalize_z(&self) -> Poly {
        let c = self.content();
        if c.is_zero() {
            return Poly::zero();
        }
        let c = if self.terms[0].1.is_negative() { -c } else { c };
        if c.is_one() {
            return self.clone();
        }
        match c.recip() {
            Some(r) => self.scale(&r),
            None => self.clone(),
        }
    }

    /// The gcd of all monomials (largest monomial dividing every term).
    pub fn mono_content(&self) -> Mono {
        let mut it = self.terms.iter();
        let mut g = match it.next() {
            Some(t) => t.0.clone(),
            None => return Mono::one(),
        };
        for (m, _) in it {
            if g.is_one() {
                break;
            }
            g = g.gcd(m);
        }
        g
    }
}
