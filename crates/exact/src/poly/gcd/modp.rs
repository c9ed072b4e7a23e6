//! Univariate images modulo a prime: the monic gcd of dense polynomials over
//! Z_p, and the upper bounds on the degrees of the gcd in every variable that
//! images at random points give (step 4 of the gcd).

use crate::poly::modular::{
    addmod, invmod, mulmod, next_rand, powmod, q_mod, submod, trim, PRIMES,
};
use crate::poly::{Poly, Var};
use smallvec::SmallVec;

/// Monic gcd of two dense polynomials over Z_p (index = power).
pub(super) fn gcd_modp(mut a: Vec<u64>, mut b: Vec<u64>, p: u64) -> Vec<u64> {
    trim(&mut a);
    trim(&mut b);
    if a.len() < b.len() {
        std::mem::swap(&mut a, &mut b);
    }
    while !b.is_empty() {
        // a <- a mod b
        let lb = match b.last() {
            Some(&x) => x,
            None => break,
        };
        let inv = invmod(lb, p);
        while a.len() >= b.len() {
            let top = match a.last() {
                Some(&x) => x,
                None => break,
            };
            let c = mulmod(top, inv, p);
            let shift = a.len() - b.len();
            for (i, &bi) in b.iter().enumerate() {
                a[shift + i] = submod(a[shift + i], mulmod(c, bi, p), p);
            }
            a.pop();
            trim(&mut a);
        }
        std::mem::swap(&mut a, &mut b);
    }
    if let Some(&l) = a.last() {
        let inv = invmod(l, p);
        for x in a.iter_mut() {
            *x = mulmod(*x, inv, p);
        }
    }
    a
}

/// Degree of the monic gcd of two nonzero dense polynomials over Z_p.
fn gcd_degree_modp(a: Vec<u64>, b: Vec<u64>, p: u64) -> usize {
    gcd_modp(a, b, p).len().saturating_sub(1)
}

/// For each variable `vars[i]`, the univariate image of `a` in that variable
/// with all other variables evaluated at `pts` mod `p` (dense, index = power).
fn univariate_images(
    a: &Poly,
    vars: &[Var],
    degs: &[u32],
    pts: &[u64],
    p: u64,
) -> Option<Vec<Vec<u64>>> {
    let mut imgs: Vec<Vec<u64>> = degs.iter().map(|&d| vec![0u64; d as usize + 1]).collect();
    let mut total = 0u64;
    let mut pw: SmallVec<[u64; 16]> = SmallVec::new();
    let mut idx: SmallVec<[usize; 16]> = SmallVec::new();
    let mut suffix: SmallVec<[u64; 16]> = SmallVec::new();
    for (m, c) in &a.terms {
        let cm = q_mod(c, p)?;
        pw.clear();
        idx.clear();
        for &(v, e) in m.0.iter() {
            let i = vars.binary_search(&v).ok()?;
            idx.push(i);
            pw.push(powmod(pts[i], e as u64, p));
        }
        let k = pw.len();
        suffix.clear();
        suffix.resize(k + 1, 1);
        for j in (0..k).rev() {
            suffix[j] = mulmod(suffix[j + 1], pw[j], p);
        }
        let full = mulmod(cm, suffix[0], p);
        total = addmod(total, full, p);
        let mut prefix = cm;
        for j in 0..k {
            let excl = mulmod(prefix, suffix[j + 1], p);
            let i = idx[j];
            let e = m.0[j].1 as usize;
            imgs[i][0] = submod(imgs[i][0], full, p);
            imgs[i][e] = addmod(imgs[i][e], excl, p);
            prefix = mulmod(prefix, pw[j], p);
        }
    }
    for img in imgs.iter_mut() {
        img[0] = addmod(img[0], total, p);
    }
    Some(imgs)
}

/// Upper bounds on the degree of `gcd(a, b)` in each variable of `vars`
/// (both `a` and `b` have exactly these variables, degrees `da`, `db`).
pub(super) fn degree_bounds(a: &Poly, b: &Poly, vars: &[Var], da: &[u32], db: &[u32]) -> Vec<u32> {
    let n = vars.len();
    let mut bounds: Vec<Option<u32>> = vec![None; n];
    for attempt in 0..3 {
        let p = PRIMES[(attempt + (next_rand() as usize)) % PRIMES.len()];
        let pts: Vec<u64> = (0..n).map(|_| 1 + next_rand() % (p - 1)).collect();
        let (ia, ib) = match (
            univariate_images(a, vars, da, &pts, p),
            univariate_images(b, vars, db, &pts, p),
        ) {
            (Some(x), Some(y)) => (x, y),
            _ => continue,
        };
        for (i, (mut x, mut y)) in ia.into_iter().zip(ib).enumerate() {
            if bounds[i].is_some() {
                continue;
            }
            trim(&mut x);
            trim(&mut y);
            let okx = x.len() == da[i] as usize + 1;
            let oky = y.len() == db[i] as usize + 1;
            if !(okx || oky) || x.is_empty() || y.is_empty() {
                continue;
            }
            bounds[i] = Some(gcd_degree_modp(x, y, p) as u32);
        }
        if bounds.iter().all(|b| b.is_some()) {
            break;
        }
    }
    bounds
        .iter()
        .enumerate()
        .map(|(i, b)| b.unwrap_or(da[i].min(db[i])))
        .collect()
}
