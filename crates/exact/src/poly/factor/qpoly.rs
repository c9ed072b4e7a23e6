//! Dense univariate polynomials over ℚ: the image factors in the main
//! variable during the lifting in several variables, with the division and
//! modular inverse their Bézout cofactors need.

use crate::num::Q;

/// Dense univariate polynomial over ℚ, lowest degree first, no trailing
/// zeros.
pub(super) type QPoly = Vec<Q>;

pub(super) fn q_trim(a: &mut QPoly) {
    while a.last().is_some_and(|c| c.is_zero()) {
        a.pop();
    }
}

pub(super) fn q_mul(a: &[Q], b: &[Q]) -> QPoly {
    if a.is_empty() || b.is_empty() {
        return Vec::new();
    }
    let mut out = vec![Q::zero(); a.len() + b.len() - 1];
    for (i, x) in a.iter().enumerate() {
        if x.is_zero() {
            continue;
        }
        for (j, y) in b.iter().enumerate() {
            out[i + j] += x * y;
        }
    }
    q_trim(&mut out);
    out
}

fn q_sub(a: &[Q], b: &[Q]) -> QPoly {
    let n = a.len().max(b.len());
    let mut out: QPoly = (0..n)
        .map(|i| {
            let x = a.get(i).cloned().unwrap_or_else(Q::zero);
            match b.get(i) {
                Some(y) => &x - y,
                None => x,
            }
        })
        .collect();
    q_trim(&mut out);
    out
}

/// Quotient and remainder by a nonzero `b`.
pub(super) fn q_divrem(a: &[Q], b: &[Q]) -> (QPoly, QPoly) {
    let db = b.len() - 1;
    if a.len() < b.len() {
        return (Vec::new(), a.to_vec());
    }
    let inv = b[db].recip().unwrap_or_else(Q::one);
    let mut r = a.to_vec();
    let mut q = vec![Q::zero(); a.len() - db];
    for k in (0..q.len()).rev() {
        let c = &r[k + db] * &inv;
        if c.is_zero() {
            continue;
        }
        for (j, bj) in b.iter().enumerate() {
            let t = &c * bj;
            r[k + j] -= t;
        }
        q[k] = c;
    }
    r.truncate(db);
    q_trim(&mut r);
    q_trim(&mut q);
    (q, r)
}

/// The inverse of `a` modulo `m` (coprime), or `None`.
pub(super) fn q_inverse_mod(a: &[Q], m: &[Q]) -> Option<QPoly> {
    let (mut r0, mut r1) = (m.to_vec(), q_divrem(a, m).1);
    let (mut t0, mut t1): (QPoly, QPoly) = (Vec::new(), vec![Q::one()]);
    while !r1.is_empty() {
        let (q, r) = q_divrem(&r0, &r1);
        let t2 = q_sub(&t0, &q_mul(&q, &t1));
        r0 = std::mem::replace(&mut r1, r);
        t0 = std::mem::replace(&mut t1, t2);
    }
    if r0.len() != 1 {
        return None;
    }
    let inv = r0[0].recip()?;
    Some(t0.iter().map(|c| c * &inv).collect())
}
