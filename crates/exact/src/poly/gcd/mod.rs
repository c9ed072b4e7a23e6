//! The gcd of [`Poly`]s: the entry points ([`Poly::gcd`],
//! [`Poly::gcd_cofactors`], [`Poly::lcm`]) and the dispatch that splits off
//! contents and picks an algorithm (the steps are listed in the docs of
//! `poly`). Below the entry points every polynomial has integer coefficients.

mod heuristic;
mod modp;
mod prs;
mod zippel;

use super::{Poly, Var};
use crate::num::Q;
use heuristic::heu_entry;
use modp::degree_bounds;
use prs::prs_gcd;
use zippel::zippel_gcd;

impl Poly {
    /// Greatest common divisor over Q, monic (leading coefficient 1);
    /// `gcd(0, 0) == 0`, `gcd(0, p) == p.monic()`.
    pub fn gcd(&self, other: &Poly) -> Poly {
        crate::cancel::check();
        if self.is_zero() {
            return other.monic();
        }
        if other.is_zero() {
            return self.monic();
        }
        gcd_core(&self.normalize_z(), &other.normalize_z()).monic()
    }

    /// `(g, self / g, other / g)` with `g = self.gcd(other)`. For two zero
    /// inputs returns three zeros.
    pub fn gcd_cofactors(&self, other: &Poly) -> (Poly, Poly, Poly) {
        let g = self.gcd(other);
        if g.is_zero() {
            return (Poly::zero(), Poly::zero(), Poly::zero());
        }
        let a = self.div_exact(&g).unwrap_or_default();
        let b = other.div_exact(&g).unwrap_or_default();
        (g, a, b)
    }

    /// Least common multiple, monic (0 if either is 0).
    pub fn lcm(&self, other: &Poly) -> Poly {
        if self.is_zero() || other.is_zero() {
            return Poly::zero();
        }
        let g = self.gcd(other);
        match self.div_exact(&g) {
            Some(q) => (&q * other).monic(),
            None => Poly::zero(),
        }
    }
}

/// gcd of a list of nonzero integer polynomials (primitive, positive lc).
fn multi_gcd(mut list: Vec<Poly>) -> Poly {
    list.retain(|p| !p.is_zero());
    if list.is_empty() {
        return Poly::zero();
    }
    if list.iter().any(|p| p.is_constant()) {
        return Poly::one();
    }
    list.sort_by_key(|p| p.len());
    let mut it = list.into_iter();
    let mut g = match it.next() {
        Some(p) => p.normalize_z(),
        None => return Poly::zero(),
    };
    for p in it {
        g = gcd_core(&g, &p);
        if g.is_constant() {
            return Poly::one();
        }
    }
    g
}

/// gcd of two nonzero integer polynomials: primitive, positive leading coeff.
fn gcd_core(a: &Poly, b: &Poly) -> Poly {
    if a.is_constant() || b.is_constant() {
        return Poly::one();
    }
    if a.terms.len() == 1 {
        return Poly::monomial(a.terms[0].0.gcd(&b.mono_content()), Q::one());
    }
    if b.terms.len() == 1 {
        return Poly::monomial(b.terms[0].0.gcd(&a.mono_content()), Q::one());
    }
    let a = a.normalize_z();
    let b = b.normalize_z();
    if a == b {
        return a;
    }
    let ma = a.mono_content();
    let mb = b.mono_content();
    let gm = ma.gcd(&mb);
    let a = a.div_mono(&ma).unwrap_or_else(|| a.clone());
    let b = b.div_mono(&mb).unwrap_or_else(|| b.clone());
    let g = gcd_nomono(&a, &b);
    if gm.is_one() {
        g
    } else {
        g.mul_mono(&gm, &Q::one())
    }
}

/// gcd of primitive integer polynomials without monomial content.
fn gcd_nomono(a: &Poly, b: &Poly) -> Poly {
    if a.is_constant() || b.is_constant() || a.terms.len() == 1 || b.terms.len() == 1 {
        return Poly::one();
    }
    let dla = a.max_degrees();
    let dlb = b.max_degrees();
    let only_a: Vec<Var> = dla
        .iter()
        .map(|p| p.0)
        .filter(|v| dlb.binary_search_by_key(v, |p| p.0).is_err())
        .collect();
    let only_b: Vec<Var> = dlb
        .iter()
        .map(|p| p.0)
        .filter(|v| dla.binary_search_by_key(v, |p| p.0).is_err())
        .collect();
    if !only_a.is_empty() || !only_b.is_empty() {
        let mut list = if only_a.is_empty() {
            vec![a.clone()]
        } else {
            a.split_by_vars(&only_a)
        };
        if only_b.is_empty() {
            list.push(b.clone());
        } else {
            list.extend(b.split_by_vars(&only_b));
        }
        return multi_gcd(list);
    }
    // same variable set
    let vars: Vec<Var> = dla.iter().map(|p| p.0).collect();
    let da: Vec<u32> = dla.iter().map(|p| p.1).collect();
    let db: Vec<u32> = dlb.iter().map(|p| p.1).collect();
    let bounds = degree_bounds(a, b, &vars, &da, &db);
    let zero_vars: Vec<Var> = vars
        .iter()
        .zip(bounds.iter())
        .filter(|(_, &d)| d == 0)
        .map(|(v, _)| *v)
        .collect();
    if zero_vars.len() == vars.len() {
        return Poly::one();
    }
    if !zero_vars.is_empty() {
        let mut list = a.split_by_vars(&zero_vars);
        list.extend(b.split_by_vars(&zero_vars));
        return multi_gcd(list);
    }
    // one divides the other?
    if bounds == db && a.len() >= b.len() && a.div_exact(b).is_some() {
        return b.clone();
    }
    if bounds == da && b.div_exact(a).is_some() {
        return a.clone();
    }
    // linear in some variable: a single pseudo-remainder step decides
    if vars.len() > 3 && (0..vars.len()).any(|i| da[i].min(db[i]) <= 1) {
        return prs_gcd(a, b, &vars, &da, &db, &bounds);
    }
    // candidates: heuristic gcd for few variables, then sparse modular gcd
    let mut candidates = 0;
    for attempt in 0..4 {
        let cand = if attempt == 0 {
            heu_entry(a, b, &vars, &da, &db)
        } else {
            zippel_gcd(a, b, &vars, &bounds)
        };

        if let Some(h) = cand {
            let hd: Vec<u32> = vars.iter().map(|&v| h.degree(v)).collect();
            if hd == bounds {
                return h;
            }
            if !h.is_constant() {
                // a proper common divisor: recurse on the cofactors
                if let (Some(qa), Some(qb)) = (a.div_exact(&h), b.div_exact(&h)) {
                    let rest = gcd_core(&qa, &qb);
                    return (&h * &rest).normalize_z();
                }
            }
            candidates += 1;
            if candidates >= 2 {
                // two verified answers that the (probabilistic) degree bounds
                // call too small: trust the exact PRS instead
                break;
            }
        }
    }
    prs_gcd(a, b, &vars, &da, &db, &bounds)
}

#[cfg(test)]
mod tests;
