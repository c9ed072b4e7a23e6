//! The heuristic gcd GCDHEU: evaluate at a large integer, take the gcd of
//! the values, interpolate back xi-adically, and verify by division (tried
//! first for at most 3 variables).

use crate::num::Q;
use crate::poly::{Mono, Poly, Var};
use num_bigint::BigInt;
use num_integer::Integer;
use num_traits::{Signed, ToPrimitive, Zero};

/// Max |coefficient| as BigInt.
fn max_norm(p: &Poly) -> BigInt {
    let mut best = BigInt::zero();
    for (_, c) in &p.terms {
        let n = c.numer().abs();
        if n > best {
            best = n;
        }
    }
    best
}

pub(super) fn heu_entry(a: &Poly, b: &Poly, vars: &[Var], da: &[u32], db: &[u32]) -> Option<Poly> {
    if vars.len() > 3 {
        return None;
    }
    // estimate the size of the integers met at the bottom of the recursion
    let mut bits = max_norm(a).bits().min(max_norm(b).bits()) as f64 + 6.0;
    for i in 0..vars.len() {
        let d = da[i].max(db[i]) as f64;
        bits += d * (bits + 8.0);
        if bits > 60_000.0 {
            return None;
        }
    }
    // evaluate the variable of highest degree last (innermost)
    let mut order: Vec<usize> = (0..vars.len()).collect();
    order.sort_by_key(|&i| da[i].max(db[i]));
    let ovars: Vec<Var> = order.iter().map(|&i| vars[i]).collect();
    let h = heu_gcd(a, b, &ovars)?;
    Some(h.normalize_z())
}

/// Symmetric residue of the integer `c` modulo the positive integer `m`.
fn sym_mod(c: &Q, m: &BigInt, m_small: Option<i64>) -> Q {
    if let (Some((n, 1)), Some(ms)) = (c.small(), m_small) {
        let r = n.rem_euclid(ms);
        return Q::from_i64(if r > ms / 2 { r - ms } else { r });
    }
    let r = c.numer().mod_floor(m);
    let r = if &r * 2 > *m { r - m } else { r };
    Q::from_bigint(r)
}

/// xi-adic interpolation of `h` into a polynomial in `v`.
fn heu_interpolate(h: &Poly, xi: &BigInt, v: Var) -> Poly {
    let xi_small = xi.to_i64();
    let xi_q = Q::from_bigint(xi.clone());
    let xi_inv = match xi_q.recip() {
        Some(r) => r,
        None => return Poly::zero(),
    };
    let mut terms: Vec<(Mono, Q)> = Vec::new();
    let mut h = h.clone();
    let mut i = 0u32;
    while !h.is_zero() {
        let g = h.map_coeffs(|c| sym_mod(c, xi, xi_small));
        let vm = Mono::var_pow(v, i);
        for (m, c) in &g.terms {
            terms.push((m.mul(&vm), c.clone()));
        }
        h = (&h - &g).scale(&xi_inv);
        i += 1;
        if i > 100_000 {
            return Poly::zero();
        }
    }
    let r = Poly::from_terms(terms);
    match r.leading_coeff() {
        Some(c) if c.is_negative() => -&r,
        _ => r,
    }
}

/// Heuristic gcd in Z[vars] (including the integer content), or `None`.
fn heu_gcd(a: &Poly, b: &Poly, vars: &[Var]) -> Option<Poly> {
    if a.is_zero() {
        return Some(b.normalize_z().scale(&b.content()));
    }
    if b.is_zero() {
        return Some(a.normalize_z().scale(&a.content()));
    }
    let ca = a.content();
    let cb = b.content();
    let cg = ca.gcd(&cb);
    if a.is_constant() || b.is_constant() {
        return Some(Poly::constant(cg));
    }
    let (v, rest) = match vars.split_first() {
        Some(x) => x,
        None => return Some(Poly::constant(cg)),
    };
    if !a.contains_var(*v) && !b.contains_var(*v) {
        return heu_gcd(a, b, rest);
    }
    let ap = a.scale(&ca.recip()?);
    let bp = b.scale(&cb.recip()?);
    let na = max_norm(&ap);
    let nb = max_norm(&bp);
    let lca = ap.terms[0].1.numer().abs();
    let lcb = bp.terms[0].1.numer().abs();
    let bb: BigInt = BigInt::from(2) * (&na).min(&nb) + 29;
    let sq: BigInt = BigInt::from(99) * bb.sqrt();
    let x1: BigInt = bb.min(sq);
    let ra: BigInt = &na / &lca;
    let rb: BigInt = &nb / &lcb;
    let x2: BigInt = BigInt::from(2) * ra.min(rb) + 2;
    let mut xi = x1.max(x2);
    for _ in 0..6 {
        if xi.bits() > 1_000_000 {
            return None;
        }
        let xq = Q::from_bigint(xi.clone());
        let aa = ap.eval_var(*v, &xq);
        let bbv = bp.eval_var(*v, &xq);
        if !aa.is_zero() && !bbv.is_zero() {
            let h = heu_gcd(&aa, &bbv, rest)?;
            let hh = heu_interpolate(&h, &xi, *v).normalize_z();
            if !hh.is_zero() && ap.div_exact(&hh).is_some() && bp.div_exact(&hh).is_some() {
                return Some(hh.scale(&cg));
            }
            // cofactor attempts
            for (x, xx, y) in [(&aa, &ap, &bp), (&bbv, &bp, &ap)] {
                if let Some(cf) = x.div_exact(&h) {
                    let c = heu_interpolate(&cf, &xi, *v);
                    if let Some(g) = xx.div_exact(&c) {
                        let g = g.normalize_z();
                        if !g.is_zero() && y.div_exact(&g).is_some() {
                            return Some(g.scale(&cg));
                        }
                    }
                }
            }
        }
        let s = xi.sqrt().sqrt();
        xi = xi * BigInt::from(73794) * s / BigInt::from(27011);
    }
    None
}
