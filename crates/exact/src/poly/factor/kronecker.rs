//! Kronecker's substitution for a multivariate part that evaluation and
//! lifting do not handle: the univariate image factored completely over ℤ,
//! and subsets of its factors mapped back and tried by exact division.

use super::square_free::square_free;
use super::univariate::zassenhaus;
use super::zpoly::{from_dense, to_dense, z_mul, ZPoly};
use super::{next_combination, normalize, Trials};
use crate::num::Q;
use crate::poly::{Mono, Poly, Var};
use num_bigint::BigInt;
use num_traits::{One, Zero};
use rustc_hash::FxHashSet;

/// Degree limit of the univariate Kronecker image of a multivariate part
/// (see the module docs): beyond it the part is not split.
pub const MAX_KRONECKER_DEGREE: u64 = 256;

/// Irreducible factors of a multivariate `g` (primitive in every variable,
/// square-free, no monomial content, positive leading coefficient) by
/// Kronecker's substitution (see the module docs).
pub(super) fn kronecker_factor(g: &Poly, vars: &[Var], trials: &Trials) -> Vec<Poly> {
    // mixed radices
    let mut weights: Vec<u64> = Vec::with_capacity(vars.len());
    let mut w = 1u64;
    for &v in vars {
        weights.push(w);
        w = match w.checked_mul(g.degree(v) as u64 + 1) {
            Some(x) if x <= MAX_KRONECKER_DEGREE + 1 => x,
            _ => return vec![g.clone()],
        };
    }
    let image_exp = |m: &Mono| -> usize {
        m.pairs()
            .iter()
            .map(|&(v, e)| {
                let j = vars.iter().position(|&x| x == v).unwrap_or(0);
                weights[j] as usize * e as usize
            })
            .sum()
    };
    let deg = g.terms().iter().map(|t| image_exp(&t.0)).max().unwrap_or(0);
    let mut img = vec![BigInt::zero(); deg + 1];
    for (m, c) in g.terms() {
        img[image_exp(m)] = c.numer();
    }
    let a = img.iter().position(|c| !c.is_zero()).unwrap_or(0);
    let img: ZPoly = img[a..].to_vec();
    // the complete factorization of the image over Z, as a multiset
    let y: Var = 0;
    let mut distinct: Vec<ZPoly> = Vec::new();
    let mut ids: Vec<usize> = Vec::new();
    for (part, mult) in square_free(&from_dense(&img, y)) {
        for h in zassenhaus(&to_dense(&part, y), trials) {
            distinct.push(h);
            ids.extend(std::iter::repeat_n(distinct.len() - 1, mult as usize));
        }
    }
    // recombination
    let mut t: Vec<usize> = ids;
    let mut a_rem = a;
    let mut fstar = g.clone();
    let mut out = Vec::new();
    let mut s = 1usize;
    'sizes: while 2 * s <= t.len() {
        let degs: Vec<u32> = vars.iter().map(|&v| fstar.degree(v)).collect();
        let mut seen: FxHashSet<Vec<usize>> = FxHashSet::default();
        let mut found: Option<(Vec<usize>, usize, Poly, Poly)> = None;
        let mut c: Vec<usize> = (0..s).collect();
        'search: loop {
            if !trials.next() {
                break 'sizes;
            }
            let mut key: Vec<usize> = c.iter().map(|&i| t[i]).collect();
            key.sort_unstable();
            if seen.insert(key.clone()) {
                let mut prod: ZPoly = vec![BigInt::one()];
                for &i in &key {
                    prod = z_mul(&prod, &distinct[i]);
                }
                for k in 0..=a_rem {
                    let Some(cand) = inverse_kronecker(&prod, k, vars, &weights, &degs) else {
                        continue;
                    };
                    let cand = normalize(&cand);
                    if cand.is_constant() {
                        continue;
                    }
                    if let Some(q) = fstar.div_exact(&cand) {
                        found = Some((c.clone(), k, cand, q));
                        break 'search;
                    }
                }
            }
            if !next_combination(&mut c, t.len()) {
                break;
            }
        }
        match found {
            Some((c, k, cand, q)) => {
                for &i in c.iter().rev() {
                    t.remove(i);
                }
                a_rem -= k;
                out.push(cand);
                fstar = normalize(&q);
            }
            None => s += 1,
        }
    }
    if !fstar.is_constant() {
        out.push(fstar);
    }
    out
}

/// The polynomial whose Kronecker image is `y^k·prod`, or `None` when an
/// exponent exceeds the degree bound `degs` (so it cannot divide).
fn inverse_kronecker(
    prod: &[BigInt],
    k: usize,
    vars: &[Var],
    weights: &[u64],
    degs: &[u32],
) -> Option<Poly> {
    let mut terms = Vec::new();
    for (i, c) in prod.iter().enumerate() {
        if c.is_zero() {
            continue;
        }
        let mut e = (i + k) as u64;
        let mut pairs = Vec::with_capacity(vars.len());
        for j in (0..vars.len()).rev() {
            let d = e / weights[j];
            e %= weights[j];
            if d > degs[j] as u64 {
                return None;
            }
            pairs.push((vars[j], d as u32));
        }
        terms.push((Mono::from_pairs(pairs), Q::from_bigint(c.clone())));
    }
    Some(Poly::from_terms(terms))
}
