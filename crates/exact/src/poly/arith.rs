//! Ring arithmetic on [`Poly`]: scaling, monomial multiples, powers, the
//! sorted merges behind addition and subtraction, the product and exact
//! division (through the encodings of `packed.rs`).

use super::packed::{div_terms, merge_deglists, mul_terms};
use super::{Mono, Poly};
use crate::num::Q;
use smallvec::SmallVec;
use std::cmp::Ordering;

impl Poly {
    /// `c * self`.
    pub fn scale(&self, c: &Q) -> Poly {
        if c.is_zero() {
            return Poly::zero();
        }
        if c.is_one() {
            return self.clone();
        }
        Poly::from_sorted(self.terms.iter().map(|(m, x)| (m.clone(), x * c)).collect())
    }

    /// `c * m * self`.
    pub fn mul_mono(&self, m: &Mono, c: &Q) -> Poly {
        if c.is_zero() {
            return Poly::zero();
        }
        Poly::from_sorted(
            self.terms
                .iter()
                .map(|(mm, x)| (mm.mul(m), x * c))
                .collect(),
        )
    }

    /// `self / m` if `m` divides every term.
    pub fn div_mono(&self, m: &Mono) -> Option<Poly> {
        if m.is_one() {
            return Some(self.clone());
        }
        let terms = self
            .terms
            .iter()
            .map(|(mm, c)| mm.div(m).map(|q| (q, c.clone())))
            .collect::<Option<Vec<_>>>()?;
        Some(Poly::from_sorted(terms))
    }

    /// `self^e` (`0^0 == 1`).
    pub fn pow(&self, mut e: u32) -> Poly {
        if e == 0 {
            return Poly::one();
        }
        if self.is_zero() {
            return Poly::zero();
        }
        if self.terms.len() == 1 {
            let (m, c) = &self.terms[0];
            return Poly::monomial(m.pow(e), c.pow_u32(e));
        }
        let mut result: Option<Poly> = None;
        let mut base = self.clone();
        loop {
            if e & 1 == 1 {
                result = Some(match result {
                    None => base.clone(),
                    Some(r) => &r * &base,
                });
            }
            e >>= 1;
            if e == 0 {
                break;
            }
            base = &base * &base;
        }
        result.unwrap_or_else(Poly::one)
    }

    pub(super) fn merge(a: &[(Mono, Q)], b: &[(Mono, Q)], negate_b: bool) -> Vec<(Mono, Q)> {
        let mut out = Vec::with_capacity(a.len() + b.len());
        let (mut i, mut j) = (0, 0);
        while i < a.len() && j < b.len() {
            match a[i].0.cmp(&b[j].0) {
                Ordering::Greater => {
                    out.push(a[i].clone());
                    i += 1;
                }
                Ordering::Less => {
                    let c = if negate_b { -&b[j].1 } else { b[j].1.clone() };
                    out.push((b[j].0.clone(), c));
                    j += 1;
                }
                Ordering::Equal => {
                    let c = if negate_b {
                        &a[i].1 - &b[j].1
                    } else {
                        &a[i].1 + &b[j].1
                    };
                    if !c.is_zero() {
                        out.push((a[i].0.clone(), c));
                    }
                    i += 1;
                    j += 1;
                }
            }
        }
        out.extend_from_slice(&a[i..]);
        if negate_b {
            out.extend(b[j..].iter().map(|(m, c)| (m.clone(), -c)));
        } else {
            out.extend_from_slice(&b[j..]);
        }
        out
    }

    /// In-place merge consuming `self`'s terms (no clones of `self`'s monomials).
    pub(super) fn merge_into(&mut self, b: &[(Mono, Q)], negate_b: bool) {
        if b.is_empty() {
            return;
        }
        if self.terms.is_empty() {
            self.terms = if negate_b {
                b.iter().map(|(m, c)| (m.clone(), -c)).collect()
            } else {
                b.to_vec()
            };
            return;
        }
        let a = std::mem::take(&mut self.terms);
        let mut out = Vec::with_capacity(a.len() + b.len());
        let mut j = 0;
        for (m, c) in a {
            while j < b.len() && b[j].0 > m {
                let c2 = if negate_b { -&b[j].1 } else { b[j].1.clone() };
                out.push((b[j].0.clone(), c2));
                j += 1;
            }
            if j < b.len() && b[j].0 == m {
                let s = if negate_b { c - &b[j].1 } else { c + &b[j].1 };
                if !s.is_zero() {
                    out.push((m, s));
                }
                j += 1;
            } else {
                out.push((m, c));
            }
        }
        if negate_b {
            out.extend(b[j..].iter().map(|(m, c)| (m.clone(), -c)));
        } else {
            out.extend_from_slice(&b[j..]);
        }
        self.terms = out;
    }

    pub(super) fn mul_impl(&self, other: &Poly) -> Poly {
        let (a, b) = (&self.terms, &other.terms);
        if a.is_empty() || b.is_empty() {
            return Poly::zero();
        }
        if a.len() == 1 {
            return other.mul_mono(&a[0].0, &a[0].1);
        }
        if b.len() == 1 {
            return self.mul_mono(&b[0].0, &b[0].1);
        }
        crate::budget::check_product(a.len(), b.len());
        let deg = merge_deglists(&self.max_degrees(), &other.max_degrees(), true);
        Poly::from_sorted(mul_terms(a, b, &deg))
    }

    /// `Some(q)` iff `d` divides `self` exactly (`self == q * d`); `None` if
    /// a remainder appears or `d == 0`.
    pub fn div_exact(&self, d: &Poly) -> Option<Poly> {
        if d.is_zero() {
            return None;
        }
        if self.is_zero() {
            return Some(Poly::zero());
        }
        if d.terms.len() == 1 {
            let (m, c) = &d.terms[0];
            let inv = c.recip()?;
            return Some(self.div_mono(m)?.scale(&inv));
        }
        if self.terms.len() < 2 {
            return None;
        }
        // leading and trailing monomials must divide
        if !d.terms[0].0.divides(&self.terms[0].0) {
            return None;
        }
        let (ld, la) = (
            &d.terms[d.terms.len() - 1].0,
            &self.terms[self.terms.len() - 1].0,
        );
        if !ld.divides(la) {
            return None;
        }
        let da = self.max_degrees();
        let dd = d.max_degrees();
        // quotient bounds per variable of self; every var of d must occur in self
        let mut qb: SmallVec<[u32; 16]> = SmallVec::with_capacity(da.len());
        let mut j = 0;
        for &(v, e) in da.iter() {
            let mut f = 0;
            if j < dd.len() && dd[j].0 == v {
                f = dd[j].1;
                j += 1;
            } else if j < dd.len() && dd[j].0 < v {
                return None;
            }
            if f > e {
                return None;
            }
            qb.push(e - f);
        }
        if j < dd.len() {
            return None;
        }
        div_terms(&self.terms, &d.terms, &da, &qb).map(Poly::from_sorted)
    }
}
