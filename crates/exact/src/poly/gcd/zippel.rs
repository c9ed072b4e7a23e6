//! Zippel's sparse modular gcd: images modulo a 62-bit prime at random
//! points, interpolated one variable at a time on the skeleton of the first
//! image (with Brown's leading-coefficient normalization), verified by
//! division.

use super::gcd_core;
use super::modp::gcd_modp;
use super::prs::dense_primitive;
use crate::poly::modular::{
    addmod, invmod, lift_sym, mulmod, next_rand, powmod, q_mod, submod, PRIMES,
};
use crate::poly::{Mono, Poly, Var};

/// Terms of a polynomial mod p as (exponent of the main variable, exponents
/// of the other variables `ys`, coefficient).
type ModTerms = Vec<(u32, Vec<u32>, u64)>;

fn to_mod_terms(a: &Poly, x1: Var, ys: &[Var], p: u64) -> Option<ModTerms> {
    let mut out = Vec::with_capacity(a.len());
    for (m, c) in &a.terms {
        let mut e1 = 0;
        let mut ex = vec![0u32; ys.len()];
        for &(v, e) in m.0.iter() {
            if v == x1 {
                e1 = e;
            } else {
                ex[ys.binary_search(&v).ok()?] = e;
            }
        }
        out.push((e1, ex, q_mod(c, p)?));
    }
    Some(out)
}

/// Dense univariate image in the main variable at the point given by the
/// power tables `pows[i][e] = y_i^e`.
fn eval_mod_terms(t: &ModTerms, deg1: usize, pows: &[Vec<u64>], p: u64) -> Vec<u64> {
    let mut out = vec![0u64; deg1 + 1];
    for (e1, ex, c) in t {
        let mut v = *c;
        for (i, &e) in ex.iter().enumerate() {
            if e > 0 {
                v = mulmod(v, pows[i][e as usize], p);
            }
        }
        let slot = &mut out[*e1 as usize];
        *slot = addmod(*slot, v, p);
    }
    out
}

/// Newton interpolation: coefficients (index = power) of the polynomial of
/// degree < n through `(z[i], v[i])`; `inv[i][j] = 1 / (z[i] - z[j])`.
fn interp_modp(z: &[u64], v: &[u64], inv: &[Vec<u64>], p: u64) -> Vec<u64> {
    let n = z.len();
    let mut dd = v.to_vec();
    for j in 1..n {
        for i in (j..n).rev() {
            dd[i] = mulmod(submod(dd[i], dd[i - 1], p), inv[i][i - j], p);
        }
    }
    let mut poly = vec![dd[n - 1]];
    for i in (0..n - 1).rev() {
        // poly = poly * (x - z[i]) + dd[i]
        let mut next = vec![0u64; poly.len() + 1];
        for (k, &c) in poly.iter().enumerate() {
            next[k + 1] = addmod(next[k + 1], c, p);
            next[k] = submod(next[k], mulmod(c, z[i], p), p);
        }
        next[0] = addmod(next[0], dd[i], p);
        poly = next;
    }
    poly
}

/// Solves the transposed Vandermonde system `sum_i c_i m_i^s = v_s`
/// (s = 0..t); `None` if the `m_i` are not distinct.
fn vandermonde_modp(m: &[u64], v: &[u64], p: u64) -> Option<Vec<u64>> {
    let t = m.len();
    // master polynomial prod (z - m_i), index = power
    let mut master = vec![1u64];
    for &mi in m {
        let mut next = vec![0u64; master.len() + 1];
        for (k, &c) in master.iter().enumerate() {
            next[k + 1] = addmod(next[k + 1], c, p);
            next[k] = submod(next[k], mulmod(c, mi, p), p);
        }
        master = next;
    }
    let mut out = Vec::with_capacity(t);
    let mut q = vec![0u64; t];
    for &mi in m {
        // q = master / (z - mi), synthetic division from the top
        let mut carry = 0u64;
        for k in (0..t).rev() {
            carry = addmod(master[k + 1], mulmod(carry, mi, p), p);
            q[k] = carry;
        }
        let mut denom = 0u64;
        let mut num = 0u64;
        for k in (0..t).rev() {
            denom = addmod(mulmod(denom, mi, p), q[k], p);
        }
        for (k, &qk) in q.iter().enumerate() {
            num = addmod(num, mulmod(qk, v[k], p), p);
        }
        if denom == 0 {
            return None;
        }
        out.push(mulmod(num, invmod(denom, p), p));
    }
    Some(out)
}

/// One attempt of Zippel's sparse modular gcd for primitive integer
/// polynomials with the same variables, no monomial content, and gcd degree
/// bounds `bounds`. Returns a verified common divisor, primitive with
/// positive leading coefficient, or `None` (unlucky choices or too large
/// coefficients; callers fall back).
pub(super) fn zippel_gcd(a: &Poly, b: &Poly, vars: &[Var], bounds: &[u32]) -> Option<Poly> {
    // main variable: largest gcd degree bound
    let mut i1 = 0;
    for i in 1..vars.len() {
        if bounds[i] > bounds[i1] {
            i1 = i;
        }
    }
    let x1 = vars[i1];
    let ys: Vec<Var> = vars.iter().copied().filter(|&v| v != x1).collect();
    // content with respect to the main variable
    let (conta, pa) = dense_primitive(&a.coeffs_in(x1));
    let (contb, pb) = dense_primitive(&b.coeffs_in(x1));
    let cont = if conta.is_one() && contb.is_one() {
        Poly::one()
    } else {
        gcd_core(&conta, &contb)
    };
    if pa.len() <= 1 || pb.len() <= 1 {
        return Some(cont);
    }
    // gcd of the leading coefficients over Z (including the integer content),
    // a multiple of lc(G): H = gamma * G / lc(G) has integer coefficients
    let (la, lb) = (pa.last()?, pb.last()?);
    let gamma = gcd_core(la, lb).scale(&la.content().gcd(&lb.content()));
    let pa_poly = if conta.is_one() {
        a.clone()
    } else {
        Poly::from_coeffs_in(x1, &pa)
    };
    let pb_poly = if contb.is_one() {
        b.clone()
    } else {
        Poly::from_coeffs_in(x1, &pb)
    };
    let m = ys.len();
    // degree bounds of H = gamma * G / lc(G) in each y
    let dh: Vec<usize> = ys
        .iter()
        .map(|&y| {
            let i = vars.binary_search(&y).unwrap_or(0);
            (bounds[i] + gamma.degree(y)) as usize
        })
        .collect();
    let maxdeg: Vec<usize> = ys
        .iter()
        .map(|&y| {
            pa_poly
                .degree(y)
                .max(pb_poly.degree(y))
                .max(gamma.degree(y)) as usize
        })
        .collect();
    let p = PRIMES[next_rand() as usize % PRIMES.len()];
    let ta = to_mod_terms(&pa_poly, x1, &ys, p)?;
    let tb = to_mod_terms(&pb_poly, x1, &ys, p)?;
    let tg = to_mod_terms(&gamma, x1, &ys, p)?;
    let (da1, db1) = (pa.len() - 1, pb.len() - 1);
    let rnd = || 1 + next_rand() % (p - 1);
    // work budget in term evaluations (beyond it the PRS is likely cheaper)
    let mut budget: usize = 40_000_000;
    let per_image = ta.len() + tb.len() + tg.len() + 1;
    // gamma(pt) * monic gcd of the images at `pt`, or None if unlucky
    let mut image = |pt: &[u64]| -> Option<Vec<u64>> {
        budget = budget.checked_sub(per_image)?;
        let pows: Vec<Vec<u64>> = pt
            .iter()
            .zip(maxdeg.iter())
            .map(|(&x, &d)| {
                let mut v = Vec::with_capacity(d + 1);
                let mut acc = 1u64;
                for _ in 0..=d {
                    v.push(acc);
                    acc = mulmod(acc, x, p);
                }
                v
            })
            .collect();
        let ia = eval_mod_terms(&ta, da1, &pows, p);
        let ib = eval_mod_terms(&tb, db1, &pows, p);
        if ia[da1] == 0 || ib[db1] == 0 {
            return None;
        }
        let g = gcd_modp(ia, ib, p);
        let gv = eval_mod_terms(&tg, 0, &pows, p)[0];
        if gv == 0 {
            return None;
        }
        Some(g.into_iter().map(|c| mulmod(c, gv, p)).collect())
    };
    let beta: Vec<u64> = (0..m).map(|_| rnd()).collect();
    let first = image(&beta)?;
    let d1 = first.len() - 1;
    if d1 == 0 {
        // rigorous: the gcd of the primitive parts has degree 0 in x1
        return Some(cont);
    }
    // skeleton: per power j of x1, (exponents over ys, coefficient)
    let mut skel: Vec<Vec<(Vec<u32>, u64)>> = first
        .iter()
        .map(|&c| {
            if c == 0 {
                Vec::new()
            } else {
                vec![(vec![0u32; m], c)]
            }
        })
        .collect();
    for k in 0..m {
        let npts = dh[k] + 1;
        let mut zs: Vec<u64> = Vec::with_capacity(npts);
        while zs.len() < npts {
            let z = rnd();
            if !zs.contains(&z) {
                zs.push(z);
            }
        }
        let inv: Vec<Vec<u64>> = (0..npts)
            .map(|i| {
                (0..npts)
                    .map(|j| {
                        if i == j {
                            0
                        } else {
                            invmod(submod(zs[i], zs[j], p), p)
                        }
                    })
                    .collect()
            })
            .collect();
        let tmax = skel.iter().map(|s| s.len()).max().unwrap_or(0);
        let r: Vec<u64> = (0..k).map(|_| rnd()).collect();
        // values of the skeleton monomials at r
        let mvals: Vec<Vec<u64>> = skel
            .iter()
            .map(|s| {
                s.iter()
                    .map(|(ex, _)| {
                        (0..k).fold(1u64, |acc, t| mulmod(acc, powmod(r[t], ex[t] as u64, p), p))
                    })
                    .collect()
            })
            .collect();
        // coefficient values per (j, monomial) at each z
        let mut vals: Vec<Vec<Vec<u64>>> = skel
            .iter()
            .map(|s| vec![Vec::with_capacity(npts); s.len()])
            .collect();
        for &z in &zs {
            let nimg = if k == 0 { 1 } else { tmax };
            let mut imgs: Vec<Vec<u64>> = Vec::with_capacity(nimg);
            let mut rp: Vec<u64> = vec![1u64; k];
            for _ in 0..nimg {
                let mut pt = Vec::with_capacity(m);
                pt.extend_from_slice(&rp);
                pt.push(z);
                pt.extend_from_slice(&beta[k + 1..]);
                let img = image(&pt)?;
                if img.len() != d1 + 1 {
                    return None;
                }
                imgs.push(img);
                for (x, &rv) in rp.iter_mut().zip(r.iter()) {
                    *x = mulmod(*x, rv, p);
                }
            }
            for (j, s) in skel.iter().enumerate() {
                let t = s.len();
                if t == 0 {
                    // the coefficient must stay zero
                    if imgs.iter().any(|img| img[j] != 0) {
                        return None;
                    }
                    continue;
                }
                let v: Vec<u64> = imgs.iter().take(t).map(|img| img[j]).collect();
                let c = if k == 0 {
                    vec![v[0]]
                } else {
                    vandermonde_modp(&mvals[j], &v, p)?
                };
                for (l, cl) in c.into_iter().enumerate() {
                    vals[j][l].push(cl);
                }
            }
        }
        // interpolate each monomial's coefficient in y_k
        let mut next: Vec<Vec<(Vec<u32>, u64)>> = Vec::with_capacity(skel.len());
        for (j, s) in skel.iter().enumerate() {
            let mut terms = Vec::new();
            for (l, (ex, _)) in s.iter().enumerate() {
                let poly = interp_modp(&zs, &vals[j][l], &inv, p);
                for (e, &c) in poly.iter().enumerate() {
                    if c != 0 {
                        let mut ne = ex.clone();
                        ne[k] = e as u32;
                        terms.push((ne, c));
                    }
                }
            }
            next.push(terms);
        }
        skel = next;
    }
    // lift to Z and rebuild H
    let mut terms = Vec::new();
    for (j, s) in skel.iter().enumerate() {
        for (ex, c) in s {
            let mono = Mono::from_pairs(
                std::iter::once((x1, j as u32)).chain(ys.iter().copied().zip(ex.iter().copied())),
            );
            terms.push((mono, lift_sym(*c, p)));
        }
    }
    let h = Poly::from_terms(terms);
    let (_, hp) = dense_primitive(&h.coeffs_in(x1));
    let g = Poly::from_coeffs_in(x1, &hp).normalize_z();
    if g.is_zero() {
        return None;
    }
    pa_poly.div_exact(&g)?;
    pb_poly.div_exact(&g)?;
    Some((&g * &cont).normalize_z())
}
