//! Dense univariate polynomials over ℤ (the univariate parts and their
//! lifted factors): conversions from and to [`Poly`], ring operations,
//! reduction modulo an integer, contents and exact division.

use crate::num::Q;
use crate::poly::{Mono, Poly, Var};
use num_bigint::BigInt;
use num_integer::Integer;
use num_traits::{One, Signed, Zero};

/// Dense coefficients, lowest degree first, no trailing zeros.
pub(super) type ZPoly = Vec<BigInt>;

fn z_trim(a: &mut ZPoly) {
    while a.last().is_some_and(|c| c.is_zero()) {
        a.pop();
    }
}

pub(super) fn deg_z(a: &ZPoly) -> usize {
    a.len().saturating_sub(1)
}

/// The integer coefficients of `p` in `v` (p must be univariate in `v` with
/// integer coefficients).
pub(super) fn to_dense(p: &Poly, v: Var) -> ZPoly {
    let d = p.degree(v) as usize;
    let mut out = vec![BigInt::zero(); d + 1];
    for (m, c) in p.terms() {
        out[m.degree(v) as usize] = c.numer();
    }
    z_trim(&mut out);
    out
}

pub(super) fn from_dense(a: &[BigInt], v: Var) -> Poly {
    Poly::from_terms(
        a.iter()
            .enumerate()
            .filter(|(_, c)| !c.is_zero())
            .map(|(i, c)| (Mono::var_pow(v, i as u32), Q::from_bigint(c.clone())))
            .collect(),
    )
}

pub(super) fn z_mul(a: &[BigInt], b: &[BigInt]) -> ZPoly {
    if a.is_empty() || b.is_empty() {
        return Vec::new();
    }
    let mut out = vec![BigInt::zero(); a.len() + b.len() - 1];
    for (i, x) in a.iter().enumerate() {
        if x.is_zero() {
            continue;
        }
        for (j, y) in b.iter().enumerate() {
            out[i + j] += x * y;
        }
    }
    z_trim(&mut out);
    out
}

pub(super) fn z_add(a: &[BigInt], b: &[BigInt]) -> ZPoly {
    let n = a.len().max(b.len());
    let mut out: ZPoly = (0..n)
        .map(|i| {
            let x = a.get(i).cloned().unwrap_or_default();
            match b.get(i) {
                Some(y) => x + y,
                None => x,
            }
        })
        .collect();
    z_trim(&mut out);
    out
}

pub(super) fn z_sub(a: &[BigInt], b: &[BigInt]) -> ZPoly {
    let n = a.len().max(b.len());
    let mut out: ZPoly = (0..n)
        .map(|i| {
            let x = a.get(i).cloned().unwrap_or_default();
            match b.get(i) {
                Some(y) => x - y,
                None => x,
            }
        })
        .collect();
    z_trim(&mut out);
    out
}

/// Coefficients reduced to `[0, m)`.
pub(super) fn z_mod(a: &[BigInt], m: &BigInt) -> ZPoly {
    let mut out: ZPoly = a.iter().map(|c| c.mod_floor(m)).collect();
    z_trim(&mut out);
    out
}

/// Coefficients reduced to the symmetric range `(−m/2, m/2]`.
pub(super) fn z_sym(a: &[BigInt], m: &BigInt) -> ZPoly {
    let half: BigInt = m >> 1usize;
    let mut out: ZPoly = a
        .iter()
        .map(|c| {
            let r = c.mod_floor(m);
            if r > half {
                r - m
            } else {
                r
            }
        })
        .collect();
    z_trim(&mut out);
    out
}

pub(super) fn z_mulm(a: &[BigInt], b: &[BigInt], m: &BigInt) -> ZPoly {
    z_mod(&z_mul(a, b), m)
}

/// Division with remainder modulo `m` by `b` with leading coefficient 1
/// modulo `m`.
pub(super) fn z_divrem_monic(a: &[BigInt], b: &[BigInt], m: &BigInt) -> (ZPoly, ZPoly) {
    let mut r = z_mod(a, m);
    let db = deg_z(&b.to_vec());
    if r.len() < b.len() {
        return (Vec::new(), r);
    }
    let mut q = vec![BigInt::zero(); r.len() - db];
    for k in (0..q.len()).rev() {
        let c = r[k + db].mod_floor(m);
        if c.is_zero() {
            continue;
        }
        for (j, bj) in b.iter().enumerate() {
            r[k + j] -= &c * bj;
        }
        q[k] = c;
    }
    r.truncate(db);
    (z_mod(&q, m), z_mod(&r, m))
}

/// Content (gcd of the coefficients, positive).
fn z_content(a: &[BigInt]) -> BigInt {
    let mut g = BigInt::zero();
    for c in a {
        g = g.gcd(c);
        if g.is_one() {
            break;
        }
    }
    g
}

/// Primitive part with a positive leading coefficient.
pub(super) fn z_primitive(a: &[BigInt]) -> ZPoly {
    let mut g = z_content(a);
    if g.is_zero() {
        return Vec::new();
    }
    if a.last().is_some_and(|c| c.is_negative()) {
        g = -g;
    }
    a.iter().map(|c| c / &g).collect()
}

/// `Some(a / b)` if `b` divides `a` exactly over ℤ.
pub(super) fn z_div_exact(a: &[BigInt], b: &[BigInt]) -> Option<ZPoly> {
    if b.is_empty() {
        return None;
    }
    if a.is_empty() {
        return Some(Vec::new());
    }
    if a.len() < b.len() {
        return None;
    }
    // quick rejection on the constant terms
    if !b[0].is_zero() && !(&a[0] % &b[0]).is_zero() {
        return None;
    }
    let db = b.len() - 1;
    let lb = &b[db];
    let mut r = a.to_vec();
    let mut q = vec![BigInt::zero(); a.len() - db];
    for k in (0..q.len()).rev() {
        let (c, rem) = r[k + db].div_rem(lb);
        if !rem.is_zero() {
            return None;
        }
        if c.is_zero() {
            continue;
        }
        for (j, bj) in b.iter().enumerate() {
            r[k + j] -= &c * bj;
        }
        q[k] = c;
    }
    if r.iter().any(|c| !c.is_zero()) {
        return None;
    }
    z_trim(&mut q);
    Some(q)
}
