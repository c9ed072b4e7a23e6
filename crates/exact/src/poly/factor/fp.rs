//! Dense univariate polynomials over ℤ/p for the small primes of the
//! factorization (p < 2^16, so products fit a `u64`): arithmetic, gcds,
//! and the distinct- and equal-degree factorizations.

use super::zpoly::ZPoly;
use crate::poly::modular::{invmod, trim};
use crate::rng::SplitMix64;
use num_bigint::{BigInt, BigUint};
use num_integer::Integer;
use num_traits::ToPrimitive;

/// Dense coefficients in `[0, p)`, lowest degree first, no trailing zeros.
pub(super) type Fp = Vec<u64>;

/// A distinct-degree factorization: `(product of the factors of degree d, d)`.
pub(super) type Ddf = Vec<(Fp, usize)>;

pub(super) fn deg_fp(a: &Fp) -> usize {
    a.len().saturating_sub(1)
}

pub(super) fn fp_from_z(a: &[BigInt], p: u64) -> Fp {
    let pb = BigInt::from(p);
    let mut out: Fp = a
        .iter()
        .map(|c| c.mod_floor(&pb).to_u64().unwrap_or(0))
        .collect();
    trim(&mut out);
    out
}

pub(super) fn z_from_fp(a: &[u64]) -> ZPoly {
    a.iter().map(|&c| BigInt::from(c)).collect()
}

fn fp_sub(a: &[u64], b: &[u64], p: u64) -> Fp {
    let n = a.len().max(b.len());
    let mut out: Fp = (0..n)
        .map(|i| {
            let x = a.get(i).copied().unwrap_or(0);
            let y = b.get(i).copied().unwrap_or(0);
            (x + p - y) % p
        })
        .collect();
    trim(&mut out);
    out
}

fn fp_scale(a: &[u64], c: u64, p: u64) -> Fp {
    let mut out: Fp = a.iter().map(|&x| x * c % p).collect();
    trim(&mut out);
    out
}

pub(super) fn fp_mul(a: &[u64], b: &[u64], p: u64) -> Fp {
    if a.is_empty() || b.is_empty() {
        return Vec::new();
    }
    let mut out = vec![0u64; a.len() + b.len() - 1];
    for (i, &x) in a.iter().enumerate() {
        if x == 0 {
            continue;
        }
        for (j, &y) in b.iter().enumerate() {
            out[i + j] = (out[i + j] + x * y) % p;
        }
    }
    trim(&mut out);
    out
}

/// Quotient and remainder (`b ≠ 0`).
fn fp_divrem(a: &[u64], b: &[u64], p: u64) -> (Fp, Fp) {
    let db = deg_fp(&b.to_vec());
    if a.len() < b.len() {
        return (Vec::new(), a.to_vec());
    }
    let inv = invmod(b[db], p);
    let mut r = a.to_vec();
    let mut q = vec![0u64; a.len() - db];
    for k in (0..q.len()).rev() {
        let c = r[k + db] * inv % p;
        if c == 0 {
            continue;
        }
        for (j, &bj) in b.iter().enumerate() {
            r[k + j] = (r[k + j] + p - c * bj % p) % p;
        }
        q[k] = c;
    }
    r.truncate(db);
    trim(&mut r);
    trim(&mut q);
    (q, r)
}

fn fp_rem(a: &[u64], b: &[u64], p: u64) -> Fp {
    fp_divrem(a, b, p).1
}

pub(super) fn fp_monic(a: &[u64], p: u64) -> Fp {
    match a.last() {
        None => Vec::new(),
        Some(&l) => fp_scale(a, invmod(l, p), p),
    }
}

pub(super) fn fp_gcd(a: &[u64], b: &[u64], p: u64) -> Fp {
    let (mut a, mut b) = (a.to_vec(), b.to_vec());
    while !b.is_empty() {
        let r = fp_rem(&a, &b, p);
        a = b;
        b = r;
    }
    fp_monic(&a, p)
}

/// `(g, s, t)` with `s·a + t·b = g` monic.
pub(super) fn fp_ext_gcd(a: &[u64], b: &[u64], p: u64) -> (Fp, Fp, Fp) {
    let (mut r0, mut r1) = (a.to_vec(), b.to_vec());
    let (mut s0, mut s1): (Fp, Fp) = (vec![1], Vec::new());
    let (mut t0, mut t1): (Fp, Fp) = (Vec::new(), vec![1]);
    while !r1.is_empty() {
        let (q, r) = fp_divrem(&r0, &r1, p);
        let s2 = fp_sub(&s0, &fp_mul(&q, &s1, p), p);
        let t2 = fp_sub(&t0, &fp_mul(&q, &t1, p), p);
        r0 = std::mem::replace(&mut r1, r);
        s0 = std::mem::replace(&mut s1, s2);
        t0 = std::mem::replace(&mut t1, t2);
    }
    let l = r0.last().copied().unwrap_or(1);
    let inv = invmod(l, p);
    (
        fp_scale(&r0, inv, p),
        fp_scale(&s0, inv, p),
        fp_scale(&t0, inv, p),
    )
}

pub(super) fn fp_deriv(a: &[u64], p: u64) -> Fp {
    let mut out: Fp = a
        .iter()
        .enumerate()
        .skip(1)
        .map(|(i, &c)| (i as u64 % p) * c % p)
        .collect();
    trim(&mut out);
    out
}

/// `base^e mod f`, the exponent given by its bits (most significant first).
fn fp_powmod_bits(base: &[u64], bits: impl Iterator<Item = bool>, f: &[u64], p: u64) -> Fp {
    let base = fp_rem(base, f, p);
    let mut r: Fp = vec![1];
    for bit in bits {
        r = fp_rem(&fp_mul(&r, &r, p), f, p);
        if bit {
            r = fp_rem(&fp_mul(&r, &base, p), f, p);
        }
    }
    r
}

fn fp_powmod(base: &[u64], e: u64, f: &[u64], p: u64) -> Fp {
    let n = 64 - e.leading_zeros();
    fp_powmod_bits(base, (0..n).rev().map(|i| (e >> i) & 1 == 1), f, p)
}

/// Distinct-degree factorization of a monic square-free `f`: `(g, d)` with
/// `g` the product of the irreducible factors of degree `d` (MCA Alg. 14.3).
pub(super) fn fp_ddf(f: &[u64], p: u64) -> Ddf {
    let x: Fp = vec![0, 1];
    let mut out = Vec::new();
    let mut rest = f.to_vec();
    let mut h = x.clone();
    let mut d = 0usize;
    while deg_fp(&rest) >= 2 * (d + 1) {
        d += 1;
        h = fp_powmod(&h, p, &rest, p);
        let g = fp_gcd(&fp_sub(&h, &x, p), &rest, p);
        if deg_fp(&g) > 0 {
            rest = fp_divrem(&rest, &g, p).0;
            h = fp_rem(&h, &rest, p);
            out.push((g, d));
        }
    }
    if deg_fp(&rest) > 0 {
        let d = deg_fp(&rest);
        out.push((rest, d));
    }
    out
}

/// Equal-degree factorization (Cantor–Zassenhaus, odd `p`) of a monic
/// product `g` of irreducibles of degree `d`; `None` if 64 random splits in
/// a row fail (probability ≤ 2⁻⁶⁴ per split).
pub(super) fn fp_edf(g: &[u64], d: usize, p: u64, rng: &mut SplitMix64) -> Option<Vec<Fp>> {
    let n = deg_fp(&g.to_vec());
    if n == d {
        return Some(vec![g.to_vec()]);
    }
    let e: BigUint = (BigUint::from(p).pow(d as u32) - 1u32) >> 1usize;
    let nbits = e.bits();
    for _ in 0..64 {
        let mut a: Fp = (0..n).map(|_| rng.below(p)).collect();
        trim(&mut a);
        if deg_fp(&a) == 0 {
            continue;
        }
        let b = fp_powmod_bits(&a, (0..nbits).rev().map(|i| e.bit(i)), g, p);
        let b = fp_sub(&b, &[1], p);
        let h = fp_gcd(&b, g, p);
        let dh = deg_fp(&h);
        if dh > 0 && dh < n {
            let other = fp_divrem(g, &h, p).0;
            let mut out = fp_edf(&h, d, p, rng)?;
            out.extend(fp_edf(&other, d, p, rng)?);
            return Some(out);
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mod_p_factorization_of_x4_plus_1() {
        // x^4 + 1 splits into two quadratics modulo 3
        let f: Fp = vec![1, 0, 0, 0, 1];
        let dd = fp_ddf(&f, 3);
        assert_eq!(dd.len(), 1);
        assert_eq!(dd[0].1, 2);
        let fs = fp_edf(&dd[0].0, 2, 3, &mut SplitMix64::new(1)).expect("splits");
        assert_eq!(fs.len(), 2);
        assert_eq!(fp_mul(&fs[0], &fs[1], 3), f);
    }
}
