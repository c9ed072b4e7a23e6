//! A multivariate part by evaluation and Hensel lifting (the extended
//! Zassenhaus method): an evaluation point, the image factored over ℤ, the
//! factors lifted in all the other variables at once, subsets recombined.

use super::qpoly::{q_divrem, q_inverse_mod, q_mul, q_trim, QPoly};
use super::univariate::zassenhaus;
use super::zpoly::{to_dense, ZPoly};
use super::{content_in, next_combination, normalize, Trials};
use crate::num::Q;
use crate::poly::{Mono, Poly, Var};
use crate::rng::SplitMix64;

/// Total degree of a monomial in the variables other than `x`.
fn ydeg(m: &Mono, x: Var) -> u32 {
    m.total_degree() - m.degree(x)
}

/// Drops the terms of total degree ≥ `prec` in the variables other than `x`.
fn truncate_y(p: &Poly, x: Var, prec: u32) -> Poly {
    Poly::from_terms(
        p.terms()
            .iter()
            .filter(|t| ydeg(&t.0, x) < prec)
            .cloned()
            .collect(),
    )
}

/// The terms of `p` of total degree exactly `k` in the variables other than `x`.
fn homogeneous_y(p: &Poly, x: Var, k: u32) -> Poly {
    Poly::from_terms(
        p.terms()
            .iter()
            .filter(|t| ydeg(&t.0, x) == k)
            .cloned()
            .collect(),
    )
}

/// `p` with every `yⱼ` replaced by `yⱼ + cⱼ`.
fn shift(p: &Poly, ys: &[Var], c: &[i64]) -> Poly {
    let mut out = p.clone();
    for (&y, &cj) in ys.iter().zip(c) {
        if cj != 0 {
            out = out.subst(y, &(&Poly::var(y) + &Poly::constant(Q::from_i64(cj))));
        }
    }
    out
}

/// `(s · e) mod u` in `x`, coefficientwise over the monomials in the other
/// variables.
fn rem_coeffwise(e: &Poly, s: &[Q], u: &[Q], x: Var) -> Poly {
    let mut groups: rustc_hash::FxHashMap<Mono, QPoly> = rustc_hash::FxHashMap::default();
    for (m, c) in e.terms() {
        let d = m.degree(x) as usize;
        let rest = m.without(x);
        let v = groups.entry(rest).or_default();
        if v.len() <= d {
            v.resize(d + 1, Q::zero());
        }
        v[d] = c.clone();
    }
    let mut terms = Vec::new();
    for (rest, mut v) in groups {
        q_trim(&mut v);
        let r = q_divrem(&q_mul(&v, s), u).1;
        for (i, c) in r.into_iter().enumerate() {
            if !c.is_zero() {
                terms.push((rest.mul(&Mono::var_pow(x, i as u32)), c));
            }
        }
    }
    Poly::from_terms(terms)
}

/// Budget of the lifting in several variables: M² · r · prec with `M` the
/// number of monomials of a dense lifted factor (`(deg_x + 1)·C(prec − 1 +
/// k, k)` for `k` other variables), `r` image factors and the precision
/// `prec` (a fraction of a second at the limit); beyond it Kronecker's method is used.
pub const MAX_LIFTING_WORK: u64 = 200_000_000;

/// `C(n, k)`, saturating.
fn binomial(n: u64, k: u64) -> u64 {
    let mut r: u64 = 1;
    for i in 0..k.min(n) {
        r = r.saturating_mul(n - i) / (i + 1);
    }
    r
}

/// Evaluation points tried (at most) per polynomial, and good ones compared.
const POINTS_TRIED: usize = 24;
const GOOD_POINTS: usize = 3;

/// The `k`-th evaluation point for `n` variables: zero first, then small
/// integers in a fixed pseudo-random order.
fn point(k: usize, n: usize) -> Vec<i64> {
    if k == 0 {
        return vec![0; n];
    }
    let mut rng = SplitMix64::new(k as u64);
    let r = 1 + (k as u64) / 4;
    (0..n)
        .map(|_| rng.below(2 * r + 1) as i64 - r as i64)
        .collect()
}

/// Factors a multivariate `g` (primitive in every variable, square-free, no
/// monomial content, positive leading coefficient) by evaluation and Hensel
/// lifting (the extended Zassenhaus method, Wang & Rothschild 1975; MCA
/// §16.4–16.6, with the lifting done at once in all evaluated variables
/// modulo the powers of the ideal (y − c)): the other variables are set
/// to a point `c` keeping the degree in the main variable `x` and the image
/// square-free; the image is factored over ℤ; the monic factors are lifted
/// in `ℚ[[y − c]][x]` up to the total degree that bounds `lc(g)·h/lc(h)` for
/// every factor `h`; subsets of the lifted factors, smallest first, are
/// tested by exact division. `None` when no point among the first
/// [`POINTS_TRIED`] is suitable (then Kronecker's method is used).
pub(super) fn hensel_factor(g: &Poly, vars: &[Var], trials: &Trials) -> Option<Vec<Poly>> {
    // candidates: every variable as the main one at the zero point (sparse),
    // then the smallest-degree variable at other points
    let mut order: Vec<Var> = vars.to_vec();
    order.sort_by_key(|&v| (g.degree(v), v));
    let mut best: Option<(Var, Vec<i64>, Vec<ZPoly>)> = None;
    let mut good = 0;
    let tries = order
        .iter()
        .map(|&x| (x, 0usize))
        .chain((1..POINTS_TRIED).map(|k| (order[0], k)));
    for (x, k) in tries {
        if k > 0 && best.as_ref().is_some_and(|b| b.1.iter().all(|&v| v == 0)) {
            break;
        }
        let n = g.degree(x) as usize;
        let lcx = g.coeffs_in(x).pop()?;
        let ys: Vec<Var> = vars.iter().copied().filter(|&v| v != x).collect();
        let c = point(k, ys.len());
        let mut lc0 = lcx.clone();
        let mut f0 = g.clone();
        for (&y, &cj) in ys.iter().zip(&c) {
            lc0 = lc0.eval_var(y, &Q::from_i64(cj));
            f0 = f0.eval_var(y, &Q::from_i64(cj));
        }
        if lc0.is_zero() || f0.degree(x) as usize != n {
            continue;
        }
        if !f0.gcd(&f0.diff(x)).is_constant() {
            continue;
        }
        let f0 = normalize(&f0);
        let fs = zassenhaus(&to_dense(&f0, x), trials);
        if fs.len() == 1 {
            return Some(vec![g.clone()]);
        }
        if best.as_ref().is_none_or(|b| fs.len() < b.2.len()) {
            best = Some((x, c, fs));
        }
        good += 1;
        if good >= GOOD_POINTS && k > 0 {
            break;
        }
    }
    let (x, c, us) = best?;
    let ys: Vec<Var> = vars.iter().copied().filter(|&v| v != x).collect();
    let n = g.degree(x);
    let fs = shift(g, &ys, &c);
    let lcs = fs.coeffs_in(x).pop()?;
    let dy = fs.terms().iter().map(|t| ydeg(&t.0, x)).max().unwrap_or(0);
    let dl = lcs.terms().iter().map(|t| ydeg(&t.0, x)).max().unwrap_or(0);
    let prec = dy + dl + 1;
    // work budget of the dense lifting (see the module docs)
    let dense = (n as u64 + 1) * binomial(prec as u64 - 1 + ys.len() as u64, ys.len() as u64);
    let work = dense
        .saturating_mul(dense)
        .saturating_mul(us.len() as u64 * prec as u64);
    if work > MAX_LIFTING_WORK {
        return None;
    }
    // monic target fs / lc (a power series: lc has constant term lc0 ≠ 0)
    let lc0 = lcs.as_constant().cloned().unwrap_or_else(|| {
        lcs.terms()
            .last()
            .filter(|t| t.0.is_one())
            .map(|t| t.1.clone())
            .unwrap_or_else(Q::zero)
    });
    let inv0 = lc0.recip()?;
    let tser = &Poly::one() - &lcs.scale(&inv0);
    let mut inv = Poly::one();
    let mut pw = Poly::one();
    for _ in 1..prec {
        pw = truncate_y(&(&pw * &tser), x, prec);
        if pw.is_zero() {
            break;
        }
        inv = &inv + &pw;
    }
    let inv = inv.scale(&inv0);
    let target = truncate_y(&(&fs * &inv), x, prec);
    // monic univariate factors over Q and their Bézout cofactors
    let ubar: Vec<QPoly> = us
        .iter()
        .map(|u| {
            let l = Q::from_bigint(u[u.len() - 1].clone());
            let il = l.recip().unwrap_or_else(Q::one);
            u.iter().map(|c| &Q::from_bigint(c.clone()) * &il).collect()
        })
        .collect();
    let mut cof: Vec<QPoly> = Vec::with_capacity(ubar.len());
    for i in 0..ubar.len() {
        let mut prod: QPoly = vec![Q::one()];
        for (j, u) in ubar.iter().enumerate() {
            if j != i {
                prod = q_mul(&prod, u);
            }
        }
        cof.push(q_inverse_mod(&prod, &ubar[i])?);
    }
    let mut lifted: Vec<Poly> = ubar
        .iter()
        .map(|u| {
            Poly::from_terms(
                u.iter()
                    .enumerate()
                    .map(|(i, c)| (Mono::var_pow(x, i as u32), c.clone()))
                    .collect(),
            )
        })
        .collect();
    for k in 1..prec {
        let mut prod = Poly::one();
        for u in &lifted {
            prod = truncate_y(&(&prod * u), x, k + 1);
        }
        let e = homogeneous_y(&(&target - &prod), x, k);
        if e.is_zero() {
            continue;
        }
        for (i, u) in lifted.iter_mut().enumerate() {
            let d = rem_coeffwise(&e, &cof[i], &ubar[i], x);
            *u = &*u + &d;
        }
    }
    // recombination
    let mut t: Vec<usize> = (0..lifted.len()).collect();
    let mut fstar = fs;
    let mut out = Vec::new();
    let mut s = 1usize;
    'sizes: while 2 * s <= t.len() {
        let lcf = fstar.coeffs_in(x).pop().unwrap_or_else(Poly::one);
        let mut found: Option<(Vec<usize>, Poly, Poly)> = None;
        let mut comb: Vec<usize> = (0..s).collect();
        loop {
            if !trials.next() {
                break 'sizes;
            }
            let mut cand = lcf.clone();
            for &i in &comb {
                cand = truncate_y(&(&cand * &lifted[t[i]]), x, prec);
            }
            let cont = content_in(&cand, x);
            let cand = if cont.is_constant() {
                normalize(&cand)
            } else {
                cand.div_exact(&cont)
                    .map(|q| normalize(&q))
                    .unwrap_or_default()
            };
            let ok = !cand.is_constant() && cand.terms().iter().all(|t| ydeg(&t.0, x) <= dy);
            if ok {
                if let Some(q) = fstar.div_exact(&cand) {
                    found = Some((comb.clone(), cand, q));
                    break;
                }
            }
            if !next_combination(&mut comb, t.len()) {
                break;
            }
        }
        match found {
            Some((comb, cand, q)) => {
                for &i in comb.iter().rev() {
                    t.remove(i);
                }
                out.push(cand);
                fstar = normalize(&q);
            }
            None => s += 1,
        }
    }
    if !fstar.is_constant() {
        out.push(fstar);
    }
    let neg: Vec<i64> = c.iter().map(|v| -v).collect();
    Some(
        out.iter()
            .map(|h| normalize(&shift(h, &ys, &neg)))
            .collect(),
    )
}
