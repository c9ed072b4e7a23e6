//! Square-free decomposition by Yun's algorithm, with respect to the first
//! variable on the part primitive in it and recursively on its content.

use super::{content_in, normalize};
use crate::poly::{Poly, Var};

/// Square-free decomposition (Yun's algorithm): `p = c · ∏ aᵢ^i` with the
/// `aᵢ` pairwise coprime and square-free. Returns the non-constant `aᵢ` with
/// their multiplicity `i`, ascending, each primitive with integer
/// coefficients and a positive leading coefficient; the rational constant `c`
/// is dropped. Multivariate: Yun with respect to the first variable on the
/// part primitive in it, the content (free of that variable) recursively.
/// Empty for constants. (Yun, "On square-free decomposition algorithms",
/// SYMSAC 1976; MCA Alg. 14.21.)
pub fn square_free(p: &Poly) -> Vec<(Poly, u32)> {
    if p.is_constant() {
        return Vec::new();
    }
    let mut acc: Vec<Poly> = Vec::new();
    sqf_rec(&normalize(p), &mut acc);
    acc.into_iter()
        .enumerate()
        .filter(|(_, a)| !a.is_constant())
        .map(|(i, a)| (a, i as u32 + 1))
        .collect()
}

/// `acc[i] *= g` (growing `acc` with ones).
fn mul_into(acc: &mut Vec<Poly>, i: usize, g: &Poly) {
    while acc.len() <= i {
        acc.push(Poly::one());
    }
    acc[i] = &acc[i] * g;
}

fn sqf_rec(p: &Poly, acc: &mut Vec<Poly>) {
    let Some(&v) = p.vars().first() else {
        return;
    };
    let c = content_in(p, v);
    let pp = if c.is_one() {
        p.clone()
    } else {
        p.div_exact(&c)
            .map(|q| normalize(&q))
            .unwrap_or_else(|| p.clone())
    };
    yun(&pp, v, acc);
    if !c.is_constant() {
        sqf_rec(&c, acc);
    }
}

/// Yun's algorithm in `v` for `f` primitive in `v` (every irreducible factor
/// involves `v`, so none divides its own derivative).
fn yun(f: &Poly, v: Var, acc: &mut Vec<Poly>) {
    let fp = f.diff(v);
    let a0 = f.gcd(&fp);
    let (Some(mut b), Some(c)) = (f.div_exact(&a0), fp.div_exact(&a0)) else {
        mul_into(acc, 0, f);
        return;
    };
    let mut d = &c - &b.diff(v);
    let max = f.degree(v) as usize + 1;
    let mut i = 0usize;
    while !b.is_constant() && i < max {
        let a = b.gcd(&d);
        if !a.is_constant() {
            mul_into(acc, i, &normalize(&a));
        }
        let (Some(nb), Some(nc)) = (b.div_exact(&a), d.div_exact(&a)) else {
            break;
        };
        b = nb;
        d = &nc - &b.diff(v);
        i += 1;
    }
}
