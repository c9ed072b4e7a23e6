//! The recursive subresultant PRS in a main variable (coefficients in the
//! others): the always-correct gcd, and the pseudo-remainders and dense
//! primitive parts that Zippel's gcd uses too.

use super::{gcd_core, multi_gcd};
use crate::poly::{Poly, Var};

fn dense_trim(v: &mut Vec<Poly>) {
    while v.last().is_some_and(|p| p.is_zero()) {
        v.pop();
    }
}

/// Pseudo-remainder of dense polynomials (coefficients in the other vars).
pub(super) fn prem(f: &[Poly], g: &[Poly]) -> Vec<Poly> {
    let mut r = f.to_vec();
    dense_trim(&mut r);
    let dg = g.len() - 1;
    let lc = &g[dg];
    let mut e = (f.len() + 1).saturating_sub(g.len()) as u32;
    while r.len() >= g.len() {
        let t = match r.last() {
            Some(t) => t.clone(),
            None => break,
        };
        let k = r.len() - g.len();
        let top = r.len() - 1;
        for x in r[..top].iter_mut() {
            if !x.is_zero() {
                *x = &*x * lc;
            }
        }
        for j in 0..dg {
            if !g[j].is_zero() {
                r[k + j] -= &(&t * &g[j]);
            }
        }
        r.pop();
        dense_trim(&mut r);
        e = e.saturating_sub(1);
    }
    if e > 0 && !r.is_empty() {
        let m = lc.pow(e);
        for x in r.iter_mut() {
            *x = &*x * &m;
        }
    }
    r
}

/// Content (w.r.t. the main variable) and primitive part of a dense poly.
pub(super) fn dense_primitive(f: &[Poly]) -> (Poly, Vec<Poly>) {
    let c = multi_gcd(f.to_vec());
    if c.is_one() || c.is_zero() {
        return (Poly::one(), f.to_vec());
    }
    let mut out = Vec::with_capacity(f.len());
    for x in f {
        match x.div_exact(&c) {
            Some(q) => out.push(q),
            None => return (Poly::one(), f.to_vec()),
        }
    }
    (c, out)
}

pub(super) fn prs_gcd(
    a: &Poly,
    b: &Poly,
    vars: &[Var],
    da: &[u32],
    db: &[u32],
    bounds: &[u32],
) -> Poly {
    // main variable: smallest degree (fewest PRS steps), then smallest bound
    let mut best = 0;
    for i in 1..vars.len() {
        let key = (da[i].min(db[i]), da[i].max(db[i]), bounds[i]);
        let bk = (da[best].min(db[best]), da[best].max(db[best]), bounds[best]);
        if key < bk {
            best = i;
        }
    }
    let v = vars[best];
    let (conta, pa) = dense_primitive(&a.coeffs_in(v));
    let (contb, pb) = dense_primitive(&b.coeffs_in(v));
    let cont = gcd_core(&conta, &contb);
    let g = subresultant(pa, pb);
    if g.len() <= 1 {
        return cont;
    }
    let (_, pg) = dense_primitive(&g);
    let res = Poly::from_coeffs_in(v, &pg);
    (&res * &cont).normalize_z()
}

/// Last nonzero subresultant (or a primitive PRS element) of two dense
/// polynomials of positive degree in the main variable.
fn subresultant(a: Vec<Poly>, b: Vec<Poly>) -> Vec<Poly> {
    let (mut f, mut g) = if a.len() >= b.len() { (a, b) } else { (b, a) };
    let mut gg = Poly::one();
    let mut h = Poly::one();
    let mut primitive_mode = false;
    loop {
        let delta = (f.len() - g.len()) as u32;
        let r = prem(&f, &g);
        if r.is_empty() {
            return g;
        }
        if r.len() == 1 {
            return vec![Poly::one()];
        }
        let next = if primitive_mode {
            None
        } else {
            let div = &gg * &h.pow(delta);
            r.iter()
                .map(|c| c.div_exact(&div))
                .collect::<Option<Vec<_>>>()
        };
        let next = match next {
            Some(n) => n,
            None => {
                primitive_mode = true;
                dense_primitive(&r).1
            }
        };
        f = g;
        g = next;
        if !primitive_mode {
            gg = f.last().cloned().unwrap_or_else(Poly::one);
            h = match delta {
                0 => h,
                1 => gg.clone(),
                _ => match gg.pow(delta).div_exact(&h.pow(delta - 1)) {
                    Some(x) => x,
                    None => {
                        primitive_mode = true;
                        h
                    }
                },
            };
        } else {
            g = dense_primitive(&g).1;
        }
    }
}
