//! Zassenhaus' factorization of a univariate part over ℤ: the choice of a
//! prime, the factors modulo it, quadratic Hensel lifting along a binary
//! tree, and the recombination of subsets of the lifted factors.

use super::fp::{
    deg_fp, fp_ddf, fp_deriv, fp_edf, fp_ext_gcd, fp_from_z, fp_gcd, fp_monic, fp_mul, z_from_fp,
    Ddf, Fp,
};
use super::zpoly::{
    deg_z, z_add, z_div_exact, z_divrem_monic, z_mod, z_mul, z_mulm, z_primitive, z_sub, z_sym,
    ZPoly,
};
use super::{next_combination, Trials};
use crate::rng::SplitMix64;
use num_bigint::BigInt;
use num_integer::Integer;
use num_traits::{One, Signed, ToPrimitive, Zero};

/// Primes are taken below this bound for the modular factorization.
const PRIME_LIMIT: u64 = 1 << 16;

/// Number of usable primes whose distinct-degree factorizations are compared.
const PRIMES_TRIED: usize = 5;

/// Odd primes below [`PRIME_LIMIT`], ascending.
fn primes() -> impl Iterator<Item = u64> {
    (3..PRIME_LIMIT).step_by(2).filter(|&n| {
        (3..)
            .step_by(2)
            .take_while(|d| d * d <= n)
            .all(|d| n % d != 0)
    })
}

/// One quadratic Hensel step (MCA Alg. 15.10): from `f ≡ g·h`, `s·g + t·h ≡
/// 1 (mod m)`, `h` monic, to the same modulo `m2 = m²`.
fn hensel_step(
    f: &[BigInt],
    g: &mut ZPoly,
    h: &mut ZPoly,
    s: &mut ZPoly,
    t: &mut ZPoly,
    m2: &BigInt,
) {
    let e = z_mod(&z_sub(f, &z_mul(g, h)), m2);
    let (q, r) = z_divrem_monic(&z_mulm(s, &e, m2), h, m2);
    let g1 = z_mod(&z_add(&z_add(g, &z_mul(t, &e)), &z_mul(&q, g)), m2);
    let h1 = z_mod(&z_add(h, &r), m2);
    let b = z_mod(
        &z_sub(&z_add(&z_mul(s, &g1), &z_mul(t, &h1)), &[BigInt::one()]),
        m2,
    );
    let (c, d) = z_divrem_monic(&z_mulm(s, &b, m2), &h1, m2);
    let s1 = z_mod(&z_sub(s, &d), m2);
    let t1 = z_mod(&z_sub(&z_sub(t, &z_mul(t, &b)), &z_mul(&c, &g1)), m2);
    *g = g1;
    *h = h1;
    *s = s1;
    *t = t1;
}

/// Multifactor Hensel lifting along a binary tree (MCA Alg. 15.17 done
/// top-down): `f ≡ lc(f)·∏ us (mod p)` with the `us` monic, pairwise coprime;
/// returns monic `Us ≡ us (mod p)` with `f ≡ lc(f)·∏ Us (mod p^(2^k))`.
fn hensel_lift(f: &[BigInt], us: &[Fp], p: u64, k: u32) -> Vec<ZPoly> {
    let pb = BigInt::from(p);
    let big_m = pb.pow(1u32 << k);
    let lc = f.last().cloned().unwrap_or_else(BigInt::one);
    if us.len() == 1 {
        let inv = lc
            .mod_floor(&big_m)
            .extended_gcd(&big_m)
            .x
            .mod_floor(&big_m);
        return vec![z_mod(
            &f.iter().map(|c| c * &inv).collect::<Vec<_>>(),
            &big_m,
        )];
    }
    let mid = us.len() / 2;
    let lcp = lc.mod_floor(&pb).to_u64().unwrap_or(1);
    let mut g0: Fp = vec![lcp];
    for u in &us[..mid] {
        g0 = fp_mul(&g0, u, p);
    }
    let mut h0: Fp = vec![1];
    for u in &us[mid..] {
        h0 = fp_mul(&h0, u, p);
    }
    let (_, s0, t0) = fp_ext_gcd(&g0, &h0, p);
    let (mut g, mut h, mut s, mut t) = (
        z_from_fp(&g0),
        z_from_fp(&h0),
        z_from_fp(&s0),
        z_from_fp(&t0),
    );
    let mut m = pb.clone();
    for _ in 0..k {
        m = &m * &m;
        let fm = z_mod(f, &m);
        hensel_step(&fm, &mut g, &mut h, &mut s, &mut t, &m);
    }
    let mut out = hensel_lift(&g, &us[..mid], p, k);
    out.extend(hensel_lift(&h, &us[mid..], p, k));
    out
}

/// Subset sums of a multiset of degrees, as a table over `0..=n`.
fn subset_sums(degs: &[usize], n: usize) -> Vec<bool> {
    let mut can = vec![false; n + 1];
    can[0] = true;
    for &d in degs {
        for s in (d..=n).rev() {
            if can[s - d] {
                can[s] = true;
            }
        }
    }
    can
}

/// Irreducible factors over ℤ of a primitive square-free `f` with positive
/// leading coefficient (primitive, positive leading coefficients).
pub(super) fn zassenhaus(f: &[BigInt], trials: &Trials) -> Vec<ZPoly> {
    let n = deg_z(&f.to_vec());
    if n <= 1 {
        return vec![f.to_vec()];
    }
    let lc = f[n].clone();
    // choose the prime: the fewest modular factors among PRIMES_TRIED usable
    let mut allowed = vec![true; n + 1];
    let mut cands: Vec<(usize, u64, Ddf)> = Vec::new();
    for p in primes() {
        if (&lc % BigInt::from(p)).is_zero() {
            continue;
        }
        let fp = fp_monic(&fp_from_z(f, p), p);
        if deg_fp(&fp) != n || deg_fp(&fp_gcd(&fp, &fp_deriv(&fp, p), p)) > 0 {
            continue;
        }
        let dd = fp_ddf(&fp, p);
        let mut degs = Vec::new();
        for (g, d) in &dd {
            degs.extend(std::iter::repeat_n(*d, deg_fp(g) / d));
        }
        if degs.len() == 1 {
            return vec![f.to_vec()];
        }
        let sums = subset_sums(&degs, n);
        for (a, b) in allowed.iter_mut().zip(&sums) {
            *a &= *b;
        }
        if allowed[1..n].iter().all(|a| !a) {
            return vec![f.to_vec()];
        }
        cands.push((degs.len(), p, dd));
        if cands.len() >= PRIMES_TRIED {
            break;
        }
    }
    cands.sort_by_key(|c| (c.0, std::cmp::Reverse(c.1)));
    let mut rng = SplitMix64::new(0x9E37_79B9_7F4A_7C15);
    let mut chosen = None;
    for (_, p, dd) in &cands {
        let mut us = Vec::new();
        let mut ok = true;
        for (g, d) in dd {
            match fp_edf(g, *d, *p, &mut rng) {
                Some(fs) => us.extend(fs),
                None => {
                    ok = false;
                    break;
                }
            }
        }
        if ok {
            chosen = Some((*p, us));
            break;
        }
    }
    let Some((p, us)) = chosen else {
        return vec![f.to_vec()];
    };
    // Mignotte: coefficients of lc·g/lc(g) for a factor g are at most
    // B = √(n+1)·2ⁿ·‖f‖∞·|lc|; lift until p^(2^k) > 2B.
    let norm = f.iter().map(|c| c.abs()).max().unwrap_or_else(BigInt::one);
    let sq = BigInt::from((((n + 1) as f64).sqrt().ceil() as u64).max(1) + 1);
    let bound: BigInt = (sq * norm * lc.abs()) << (n + 1);
    let pb = BigInt::from(p);
    let mut k = 0u32;
    let mut m = pb.clone();
    while m <= bound {
        m = &m * &m;
        k += 1;
    }
    let lifted = hensel_lift(f, &us, p, k);
    recombine(f, lifted, &m, &allowed, trials)
}

/// Zassenhaus recombination (MCA Alg. 15.19 with trial division): subsets of
/// the lifted monic factors, smallest first, each candidate
/// `pp(lc·∏ uᵢ mods m)` tested by the degree table, the constant term and
/// exact division.
fn recombine(
    f: &[BigInt],
    lifted: Vec<ZPoly>,
    m: &BigInt,
    allowed: &[bool],
    trials: &Trials,
) -> Vec<ZPoly> {
    let mut t: Vec<usize> = (0..lifted.len()).collect();
    let mut fstar = f.to_vec();
    let mut out = Vec::new();
    let mut s = 1usize;
    'sizes: while 2 * s <= t.len() {
        let mut found: Option<(Vec<usize>, ZPoly, ZPoly)> = None;
        let mut c: Vec<usize> = (0..s).collect();
        loop {
            if !trials.next() {
                break 'sizes;
            }
            let idx: Vec<usize> = c.iter().map(|&i| t[i]).collect();
            let deg: usize = idx.iter().map(|&i| deg_z(&lifted[i])).sum();
            if allowed.get(deg).copied().unwrap_or(false) {
                let lcf = fstar.last().cloned().unwrap_or_else(BigInt::one);
                let mut pass = true;
                if !fstar[0].is_zero() {
                    let mut c0 = lcf.clone();
                    for &i in &idx {
                        c0 = (c0 * &lifted[i][0]).mod_floor(m);
                    }
                    let c0 = z_sym(&[c0], m);
                    pass = match c0.first() {
                        None => false,
                        Some(c0) => (&lcf * &fstar[0] % c0).is_zero(),
                    };
                }
                if pass {
                    let mut g: ZPoly = vec![lcf];
                    for &i in &idx {
                        g = z_mulm(&g, &lifted[i], m);
                    }
                    let g = z_primitive(&z_sym(&g, m));
                    if g.len() > 1 {
                        if let Some(q) = z_div_exact(&fstar, &g) {
                            found = Some((c.clone(), g, q));
                            break;
                        }
                    }
                }
            }
            if !next_combination(&mut c, t.len()) {
                break;
            }
        }
        match found {
            Some((c, g, q)) => {
                for &i in c.iter().rev() {
                    t.remove(i);
                }
                out.push(g);
                fstar = q;
            }
            None => s += 1,
        }
    }
    if fstar.len() > 1 {
        out.push(fstar);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hensel_lifting_reproduces_the_product() {
        // (2x - 1)(x + 1)(x - 2)(x + 3) modulo 11^(2^3): a non-monic product
        let lin = |a: i64, b: i64| -> ZPoly { vec![BigInt::from(b), BigInt::from(a)] };
        let f = z_mul(
            &z_mul(&lin(2, -1), &lin(1, 1)),
            &z_mul(&lin(1, -2), &lin(1, 3)),
        );
        let p = 11u64;
        let fp = fp_monic(&fp_from_z(&f, p), p);
        assert!(deg_fp(&fp_gcd(&fp, &fp_deriv(&fp, p), p)) == 0);
        let us: Vec<Fp> = fp_ddf(&fp, p)
            .into_iter()
            .flat_map(|(g, d)| fp_edf(&g, d, p, &mut SplitMix64::new(3)).expect("splits"))
            .collect();
        assert_eq!(us.len(), 4);
        let lifted = hensel_lift(&f, &us, p, 3);
        let m = BigInt::from(p).pow(8u32);
        let mut prod: ZPoly = vec![BigInt::from(2)];
        for u in &lifted {
            assert_eq!(u.last(), Some(&BigInt::one()));
            prod = z_mulm(&prod, u, &m);
        }
        assert_eq!(prod, z_mod(&f, &m));
        // the lifted factors recombine to the four linear factors
        let fs = recombine(&f, lifted, &m, &[true; 5], &Trials::budgeted());
        assert_eq!(fs.len(), 4);
    }
}
