//! Sparse multivariate polynomials over the exact rationals [`Q`].
//!
//! A [`Poly`] is a list of `(Mono, Q)` terms kept sorted in descending
//! lexicographic order (smallest variable id most significant), with no zero
//! coefficients and no duplicate monomials, so structural equality is value
//! equality.
//!
//! Multiplication and exact division temporarily pack monomials into `u128`
//! keys (one bit field per variable, smallest variable in the most significant
//! bits, so integer order is the monomial order) whenever the exponents fit;
//! otherwise they fall back to working on [`Mono`] directly.
//!
//! The GCD ([`Poly::gcd`]) works over Z after clearing denominators:
//! 1. trivial cases (zero, constants, monomials, equal inputs);
//! 2. the monomial gcd is split off;
//! 3. variables present in only one argument are eliminated by taking the
//!    gcd with all coefficients with respect to them;
//! 4. univariate images modulo a 62-bit prime at random points give upper
//!    bounds on the degree of the gcd in every variable; variables with bound
//!    0 are eliminated the same way (so coprime inputs are detected cheaply);
//! 5. trial division when the bounds say one input may divide the other;
//! 6. for inputs linear in some variable (and more than 3 variables): a
//!    recursive subresultant PRS (one pseudo-remainder step);
//! 7. otherwise the heuristic gcd GCDHEU (at most 3 variables) and Zippel's
//!    sparse modular interpolation (with Brown's leading-coefficient
//!    normalization), each verified by exact division;
//! 8. the recursive subresultant PRS as the always-correct fallback.
//!
//! A verified common divisor whose degrees meet the bounds of step 4 is
//! certified to be the gcd; a verified common divisor of smaller degree is
//! factored out and the gcd of the cofactors computed recursively. The result
//! is therefore always exact; randomness only affects speed.

mod arith;
mod content;
pub mod factor;
mod modular;
mod monomial;
mod ops;
mod packed;
mod structure;

pub use monomial::{mono_gcd, Mono};

use modular::{addmod, invmod, lift_sym, mulmod, next_rand, powmod, q_mod, submod, trim, PRIMES};

use crate::num::Q;
use num_bigint::BigInt;
use num_integer::Integer;
use num_traits::{Signed, ToPrimitive, Zero};
use smallvec::SmallVec;
use std::fmt;
use std::hash::Hash;

/// A variable id.
pub type Var = u32;

/// A polynomial: terms sorted by monomial in DESCENDING lexicographic order,
/// no zero coefficients, no duplicate monomials. The leading term is `terms[0]`.
#[derive(Clone, PartialEq, Eq, Hash, Debug, Default)]
pub struct Poly {
    terms: Vec<(Mono, Q)>,
}

static ZERO_Q: Q = Q::zero();

// ===========================================================================
// Poly: construction and inspection
// ===========================================================================

impl Poly {
    /// The zero polynomial.
    #[inline]
    pub fn zero() -> Poly {
        Poly { terms: Vec::new() }
    }

    /// The constant 1.
    #[inline]
    pub fn one() -> Poly {
        Poly::constant(Q::one())
    }

    /// A constant.
    pub fn constant(c: Q) -> Poly {
        if c.is_zero() {
            Poly::zero()
        } else {
            Poly {
                terms: vec![(Mono::one(), c)],
            }
        }
    }

    /// The variable `v`.
    pub fn var(v: Var) -> Poly {
        Poly {
            terms: vec![(Mono::var(v), Q::one())],
        }
    }

    /// The single term `c * m`.
    pub fn monomial(m: Mono, c: Q) -> Poly {
        if c.is_zero() {
            Poly::zero()
        } else {
            Poly {
                terms: vec![(m, c)],
            }
        }
    }

    /// From arbitrary terms: sorts, merges duplicate monomials, drops zeros.
    /// Monomials must themselves be normalized (see [`Mono::from_pairs`]).
    pub fn from_terms(mut terms: Vec<(Mono, Q)>) -> Poly {
        terms.sort_unstable_by(|a, b| b.0.cmp(&a.0));
        let mut out: Vec<(Mono, Q)> = Vec::with_capacity(terms.len());
        for (m, c) in terms {
            match out.last_mut() {
                Some(last) if last.0 == m => last.1 += c,
                _ => {
                    if let Some(last) = out.last() {
                        if last.1.is_zero() {
                            out.pop();
                        }
                    }
                    out.push((m, c));
                }
            }
        }
        if let Some(last) = out.last() {
            if last.1.is_zero() {
                out.pop();
            }
        }
        Poly { terms: out }
    }

    /// From terms already sorted descending, distinct and nonzero.
    #[inline]
    fn from_sorted(terms: Vec<(Mono, Q)>) -> Poly {
        debug_assert!(terms.windows(2).all(|w| w[0].0 > w[1].0));
        debug_assert!(terms.iter().all(|t| !t.1.is_zero()));
        Poly { terms }
    }

    /// The terms, in descending monomial order.
    #[inline]
    pub fn terms(&self) -> &[(Mono, Q)] {
        &self.terms
    }

    /// Consumes the polynomial, returning its terms.
    #[inline]
    pub fn into_terms(self) -> Vec<(Mono, Q)> {
        self.terms
    }

    /// Number of terms.
    #[inline]
    pub fn len(&self) -> usize {
        self.terms.len()
    }

    /// `self == 0`.
    #[inline]
    pub fn is_zero(&self) -> bool {
        self.terms.is_empty()
    }

    /// No terms, i.e. `self == 0` (same as [`Poly::is_zero`]).
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.terms.is_empty()
    }

    /// `self == 1`.
    #[inline]
    pub fn is_one(&self) -> bool {
        self.terms.len() == 1 && self.terms[0].0.is_one() && self.terms[0].1.is_one()
    }

    /// `self` is a constant (including zero).
    #[inline]
    pub fn is_constant(&self) -> bool {
        self.terms.is_empty() || (self.terms.len() == 1 && self.terms[0].0.is_one())
    }

    /// The value if `self` is constant; `Some(&0)` for the zero polynomial
    /// (a reference to a static zero, no allocation).
    #[inline]
    pub fn as_constant(&self) -> Option<&Q> {
        match self.terms.len() {
            0 => Some(&ZERO_Q),
            1 if self.terms[0].0.is_one() => Some(&self.terms[0].1),
            _ => None,
        }
    }

    /// Exactly one term (nonzero).
    #[inline]
    pub fn is_monomial(&self) -> bool {
        self.terms.len() == 1
    }

    /// Coefficient of the leading term.
    #[inline]
    pub fn leading_coeff(&self) -> Option<&Q> {
        self.terms.first().map(|t| &t.1)
    }

    /// Monomial of the leading term.
    #[inline]
    pub fn leading_mono(&self) -> Option<&Mono> {
        self.terms.first().map(|t| &t.0)
    }

    /// The leading term.
    #[inline]
    pub fn leading_term(&self) -> Option<&(Mono, Q)> {
        self.terms.first()
    }

    /// Coefficient of monomial `m` (zero if absent).
    pub fn coeff_of(&self, m: &Mono) -> Q {
        match self.terms.binary_search_by(|t| m.cmp(&t.0)) {
            Ok(i) => self.terms[i].1.clone(),
            Err(_) => Q::zero(),
        }
    }

    // -----------------------------------------------------------------------
    // gcd
    // -----------------------------------------------------------------------

    /// Greatest common divisor over Q, monic (leading coefficient 1);
    /// `gcd(0, 0) == 0`, `gcd(0, p) == p.monic()`.
    pub fn gcd(&self, other: &Poly) -> Poly {
        crate::cancel::check();
        if self.is_zero() {
            return other.monic();
        }
        if other.is_zero() {
            return self.monic();
        }
        gcd_core(&self.normalize_z(), &other.normalize_z()).monic()
    }

    /// `(g, self / g, other / g)` with `g = self.gcd(other)`. For two zero
    /// inputs returns three zeros.
    pub fn gcd_cofactors(&self, other: &Poly) -> (Poly, Poly, Poly) {
        let g = self.gcd(other);
        if g.is_zero() {
            return (Poly::zero(), Poly::zero(), Poly::zero());
        }
        let a = self.div_exact(&g).unwrap_or_default();
        let b = other.div_exact(&g).unwrap_or_default();
        (g, a, b)
    }

    /// Least common multiple, monic (0 if either is 0).
    pub fn lcm(&self, other: &Poly) -> Poly {
        if self.is_zero() || other.is_zero() {
            return Poly::zero();
        }
        let g = self.gcd(other);
        match self.div_exact(&g) {
            Some(q) => (&q * other).monic(),
            None => Poly::zero(),
        }
    }
}

// ===========================================================================
// GCD machinery (all polynomials here have integer coefficients)
// ===========================================================================

/// Monic gcd of two dense polynomials over Z_p (index = power).
fn gcd_modp(mut a: Vec<u64>, mut b: Vec<u64>, p: u64) -> Vec<u64> {
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
fn degree_bounds(a: &Poly, b: &Poly, vars: &[Var], da: &[u32], db: &[u32]) -> Vec<u32> {
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

/// gcd of a list of nonzero integer polynomials (primitive, positive lc).
fn multi_gcd(mut list: Vec<Poly>) -> Poly {
    list.retain(|p| !p.is_zero());
    if list.is_empty() {
        return Poly::zero();
    }
    if list.iter().any(|p| p.is_constant()) {
        return Poly::one();
    }
    list.sort_by_key(|p| p.len());
    let mut it = list.into_iter();
    let mut g = match it.next() {
        Some(p) => p.normalize_z(),
        None => return Poly::zero(),
    };
    for p in it {
        g = gcd_core(&g, &p);
        if g.is_constant() {
            return Poly::one();
        }
    }
    g
}

/// gcd of two nonzero integer polynomials: primitive, positive leading coeff.
fn gcd_core(a: &Poly, b: &Poly) -> Poly {
    if a.is_constant() || b.is_constant() {
        return Poly::one();
    }
    if a.terms.len() == 1 {
        return Poly::monomial(a.terms[0].0.gcd(&b.mono_content()), Q::one());
    }
    if b.terms.len() == 1 {
        return Poly::monomial(b.terms[0].0.gcd(&a.mono_content()), Q::one());
    }
    let a = a.normalize_z();
    let b = b.normalize_z();
    if a == b {
        return a;
    }
    let ma = a.mono_content();
    let mb = b.mono_content();
    let gm = ma.gcd(&mb);
    let a = a.div_mono(&ma).unwrap_or_else(|| a.clone());
    let b = b.div_mono(&mb).unwrap_or_else(|| b.clone());
    let g = gcd_nomono(&a, &b);
    if gm.is_one() {
        g
    } else {
        g.mul_mono(&gm, &Q::one())
    }
}

/// gcd of primitive integer polynomials without monomial content.
fn gcd_nomono(a: &Poly, b: &Poly) -> Poly {
    if a.is_constant() || b.is_constant() || a.terms.len() == 1 || b.terms.len() == 1 {
        return Poly::one();
    }
    let dla = a.max_degrees();
    let dlb = b.max_degrees();
    let only_a: Vec<Var> = dla
        .iter()
        .map(|p| p.0)
        .filter(|v| dlb.binary_search_by_key(v, |p| p.0).is_err())
        .collect();
    let only_b: Vec<Var> = dlb
        .iter()
        .map(|p| p.0)
        .filter(|v| dla.binary_search_by_key(v, |p| p.0).is_err())
        .collect();
    if !only_a.is_empty() || !only_b.is_empty() {
        let mut list = if only_a.is_empty() {
            vec![a.clone()]
        } else {
            a.split_by_vars(&only_a)
        };
        if only_b.is_empty() {
            list.push(b.clone());
        } else {
            list.extend(b.split_by_vars(&only_b));
        }
        return multi_gcd(list);
    }
    // same variable set
    let vars: Vec<Var> = dla.iter().map(|p| p.0).collect();
    let da: Vec<u32> = dla.iter().map(|p| p.1).collect();
    let db: Vec<u32> = dlb.iter().map(|p| p.1).collect();
    let bounds = degree_bounds(a, b, &vars, &da, &db);
    let zero_vars: Vec<Var> = vars
        .iter()
        .zip(bounds.iter())
        .filter(|(_, &d)| d == 0)
        .map(|(v, _)| *v)
        .collect();
    if zero_vars.len() == vars.len() {
        return Poly::one();
    }
    if !zero_vars.is_empty() {
        let mut list = a.split_by_vars(&zero_vars);
        list.extend(b.split_by_vars(&zero_vars));
        return multi_gcd(list);
    }
    // one divides the other?
    if bounds == db && a.len() >= b.len() && a.div_exact(b).is_some() {
        return b.clone();
    }
    if bounds == da && b.div_exact(a).is_some() {
        return a.clone();
    }
    // linear in some variable: a single pseudo-remainder step decides
    if vars.len() > 3 && (0..vars.len()).any(|i| da[i].min(db[i]) <= 1) {
        return prs_gcd(a, b, &vars, &da, &db, &bounds);
    }
    // candidates: heuristic gcd for few variables, then sparse modular gcd
    let mut candidates = 0;
    for attempt in 0..4 {
        let cand = if attempt == 0 {
            heu_entry(a, b, &vars, &da, &db)
        } else {
            zippel_gcd(a, b, &vars, &bounds)
        };

        if let Some(h) = cand {
            let hd: Vec<u32> = vars.iter().map(|&v| h.degree(v)).collect();
            if hd == bounds {
                return h;
            }
            if !h.is_constant() {
                // a proper common divisor: recurse on the cofactors
                if let (Some(qa), Some(qb)) = (a.div_exact(&h), b.div_exact(&h)) {
                    let rest = gcd_core(&qa, &qb);
                    return (&h * &rest).normalize_z();
                }
            }
            candidates += 1;
            if candidates >= 2 {
                // two verified answers that the (probabilistic) degree bounds
                // call too small: trust the exact PRS instead
                break;
            }
        }
    }
    prs_gcd(a, b, &vars, &da, &db, &bounds)
}

// ---------------------------------------------------------------------------
// heuristic gcd (GCDHEU)
// ---------------------------------------------------------------------------

/// Max |coefficient| as BigInt.
fn max_norm(p: &Poly) -> BigInt {
    let mut best = BigInt::zero();
    for (_, c) in &p.terms {
        let n = c.numer().abs();
        if n > best {
            best = n;
        }
    }
    best
}

fn heu_entry(a: &Poly, b: &Poly, vars: &[Var], da: &[u32], db: &[u32]) -> Option<Poly> {
    if vars.len() > 3 {
        return None;
    }
    // estimate the size of the integers met at the bottom of the recursion
    let mut bits = max_norm(a).bits().min(max_norm(b).bits()) as f64 + 6.0;
    for i in 0..vars.len() {
        let d = da[i].max(db[i]) as f64;
        bits += d * (bits + 8.0);
        if bits > 60_000.0 {
            return None;
        }
    }
    // evaluate the variable of highest degree last (innermost)
    let mut order: Vec<usize> = (0..vars.len()).collect();
    order.sort_by_key(|&i| da[i].max(db[i]));
    let ovars: Vec<Var> = order.iter().map(|&i| vars[i]).collect();
    let h = heu_gcd(a, b, &ovars)?;
    Some(h.normalize_z())
}

/// Symmetric residue of the integer `c` modulo the positive integer `m`.
fn sym_mod(c: &Q, m: &BigInt, m_small: Option<i64>) -> Q {
    if let (Q::Small(n, 1), Some(ms)) = (c, m_small) {
        let r = n.rem_euclid(ms);
        return Q::from_i64(if r > ms / 2 { r - ms } else { r });
    }
    let r = c.numer().mod_floor(m);
    let r = if &r * 2 > *m { r - m } else { r };
    Q::from_bigint(r)
}

/// xi-adic interpolation of `h` into a polynomial in `v`.
fn heu_interpolate(h: &Poly, xi: &BigInt, v: Var) -> Poly {
    let xi_small = xi.to_i64();
    let xi_q = Q::from_bigint(xi.clone());
    let xi_inv = match xi_q.recip() {
        Some(r) => r,
        None => return Poly::zero(),
    };
    let mut terms: Vec<(Mono, Q)> = Vec::new();
    let mut h = h.clone();
    let mut i = 0u32;
    while !h.is_zero() {
        let g = h.map_coeffs(|c| sym_mod(c, xi, xi_small));
        let vm = Mono::var_pow(v, i);
        for (m, c) in &g.terms {
            terms.push((m.mul(&vm), c.clone()));
        }
        h = (&h - &g).scale(&xi_inv);
        i += 1;
        if i > 100_000 {
            return Poly::zero();
        }
    }
    let r = Poly::from_terms(terms);
    match r.leading_coeff() {
        Some(c) if c.is_negative() => -&r,
        _ => r,
    }
}

/// Heuristic gcd in Z[vars] (including the integer content), or `None`.
fn heu_gcd(a: &Poly, b: &Poly, vars: &[Var]) -> Option<Poly> {
    if a.is_zero() {
        return Some(b.normalize_z().scale(&b.content()));
    }
    if b.is_zero() {
        return Some(a.normalize_z().scale(&a.content()));
    }
    let ca = a.content();
    let cb = b.content();
    let cg = ca.gcd(&cb);
    if a.is_constant() || b.is_constant() {
        return Some(Poly::constant(cg));
    }
    let (v, rest) = match vars.split_first() {
        Some(x) => x,
        None => return Some(Poly::constant(cg)),
    };
    if !a.contains_var(*v) && !b.contains_var(*v) {
        return heu_gcd(a, b, rest);
    }
    let ap = a.scale(&ca.recip()?);
    let bp = b.scale(&cb.recip()?);
    let na = max_norm(&ap);
    let nb = max_norm(&bp);
    let lca = ap.terms[0].1.numer().abs();
    let lcb = bp.terms[0].1.numer().abs();
    let bb: BigInt = BigInt::from(2) * (&na).min(&nb) + 29;
    let sq: BigInt = BigInt::from(99) * bb.sqrt();
    let x1: BigInt = bb.min(sq);
    let ra: BigInt = &na / &lca;
    let rb: BigInt = &nb / &lcb;
    let x2: BigInt = BigInt::from(2) * ra.min(rb) + 2;
    let mut xi = x1.max(x2);
    for _ in 0..6 {
        if xi.bits() > 1_000_000 {
            return None;
        }
        let xq = Q::from_bigint(xi.clone());
        let aa = ap.eval_var(*v, &xq);
        let bbv = bp.eval_var(*v, &xq);
        if !aa.is_zero() && !bbv.is_zero() {
            let h = heu_gcd(&aa, &bbv, rest)?;
            let hh = heu_interpolate(&h, &xi, *v).normalize_z();
            if !hh.is_zero() && ap.div_exact(&hh).is_some() && bp.div_exact(&hh).is_some() {
                return Some(hh.scale(&cg));
            }
            // cofactor attempts
            for (x, xx, y) in [(&aa, &ap, &bp), (&bbv, &bp, &ap)] {
                if let Some(cf) = x.div_exact(&h) {
                    let c = heu_interpolate(&cf, &xi, *v);
                    if let Some(g) = xx.div_exact(&c) {
                        let g = g.normalize_z();
                        if !g.is_zero() && y.div_exact(&g).is_some() {
                            return Some(g.scale(&cg));
                        }
                    }
                }
            }
        }
        let s = xi.sqrt().sqrt();
        xi = xi * BigInt::from(73794) * s / BigInt::from(27011);
    }
    None
}

// ---------------------------------------------------------------------------
// sparse modular gcd (Zippel)
// ---------------------------------------------------------------------------

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
fn zippel_gcd(a: &Poly, b: &Poly, vars: &[Var], bounds: &[u32]) -> Option<Poly> {
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

// ---------------------------------------------------------------------------
// recursive subresultant PRS
// ---------------------------------------------------------------------------

fn dense_trim(v: &mut Vec<Poly>) {
    while v.last().is_some_and(|p| p.is_zero()) {
        v.pop();
    }
}

/// Pseudo-remainder of dense polynomials (coefficients in the other vars).
fn prem(f: &[Poly], g: &[Poly]) -> Vec<Poly> {
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
fn dense_primitive(f: &[Poly]) -> (Poly, Vec<Poly>) {
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

fn prs_gcd(a: &Poly, b: &Poly, vars: &[Var], da: &[u32], db: &[u32], bounds: &[u32]) -> Poly {
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

impl fmt::Display for Poly {
    /// Like `3*x0^2*x1 - 1/2*x2 + 1`; `0` for the zero polynomial.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.terms.is_empty() {
            return write!(f, "0");
        }
        for (i, (m, c)) in self.terms.iter().enumerate() {
            let neg = c.is_negative();
            let a = c.abs();
            if i == 0 {
                if neg {
                    write!(f, "-")?;
                }
            } else if neg {
                write!(f, " - ")?;
            } else {
                write!(f, " + ")?;
            }
            if m.is_one() {
                write!(f, "{a}")?;
            } else if a.is_one() {
                write!(f, "{m}")?;
            } else {
                write!(f, "{a}*{m}")?;
            }
        }
        Ok(())
    }
}

// ===========================================================================
// tests
// ===========================================================================

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn x(v: Var) -> Poly {
        Poly::var(v)
    }

    fn c(n: i64) -> Poly {
        Poly::constant(Q::from_i64(n))
    }

    fn cq(n: i64, d: i64) -> Poly {
        Poly::constant(Q::new(n, d).expect("nonzero denominator"))
    }

    fn m(pairs: &[(Var, u32)]) -> Mono {
        Mono::from_pairs(pairs.iter().copied())
    }

    fn is_canonical(p: &Poly) -> bool {
        p.terms.windows(2).all(|w| w[0].0 > w[1].0)
            && p.terms.iter().all(|t| !t.1.is_zero())
            && p.terms.iter().all(|t| {
                t.0 .0.windows(2).all(|w| w[0].0 < w[1].0) && t.0 .0.iter().all(|e| e.1 > 0)
            })
    }

    #[test]
    fn modular_helpers() {
        for &p in PRIMES.iter() {
            let mut st = p;
            for _ in 0..200 {
                let a = lcg(&mut st) * lcg(&mut st) % p;
                let b = (lcg(&mut st) << 31 | lcg(&mut st)) % p;
                let expect = ((a as u128 * b as u128) % p as u128) as u64;
                assert_eq!(mulmod(a, b, p), expect);
                assert_eq!(mulmod(p - 1, p - 1, p), 1);
                if a != 0 {
                    assert_eq!(mulmod(a, invmod(a, p), p), 1);
                }
            }
            // Fermat: the moduli are prime (for these witnesses)
            for w in [2u64, 3, 5, 7, 11, 13] {
                assert_eq!(powmod(w, p - 1, p), 1);
            }
        }
        assert_eq!(mulmod(10, 10, 7), 2);
    }

    #[test]
    fn mono_order() {
        let a = m(&[(0, 2)]);
        let b = m(&[(0, 1), (1, 5)]);
        let cc = m(&[(0, 1)]);
        let d = m(&[(1, 9)]);
        let e = Mono::one();
        assert!(a > b && b > cc && cc > d && d > e);
        let mut v = vec![e.clone(), cc.clone(), a.clone(), d.clone(), b.clone()];
        v.sort();
        assert_eq!(v, vec![e, d, cc, b, a]);
        assert_eq!(
            m(&[(0, 1), (2, 3)]).mul(&m(&[(1, 1), (2, 1)])),
            m(&[(0, 1), (1, 1), (2, 4)])
        );
        assert_eq!(
            m(&[(0, 2), (2, 3)]).div(&m(&[(2, 1)])),
            Some(m(&[(0, 2), (2, 2)]))
        );
        assert_eq!(m(&[(0, 2), (2, 3)]).div(&m(&[(1, 1)])), None);
        assert_eq!(m(&[(0, 2)]).div(&m(&[(0, 3)])), None);
        assert_eq!(
            m(&[(0, 2), (3, 1)]).gcd(&m(&[(0, 1), (1, 4), (3, 2)])),
            m(&[(0, 1), (3, 1)])
        );
        assert_eq!(
            m(&[(0, 2), (3, 1)]).lcm(&m(&[(0, 1), (1, 4)])),
            m(&[(0, 2), (1, 4), (3, 1)])
        );
        assert!(m(&[(1, 1)]).divides(&m(&[(0, 1), (1, 2)])));
        assert!(!m(&[(1, 3)]).divides(&m(&[(0, 1), (1, 2)])));
        assert_eq!(m(&[(3, 2), (1, 1), (3, 1), (0, 0)]), m(&[(1, 1), (3, 3)]));
        assert_eq!(m(&[(1, 1), (3, 3)]).total_degree(), 4);
        assert_eq!(m(&[(1, 1), (3, 3)]).degree(3), 3);
        assert_eq!(m(&[(1, 1), (3, 3)]).to_string(), "x1*x3^3");
    }

    #[test]
    fn construction_and_display() {
        let p = Poly::from_terms(vec![
            (m(&[(1, 1)]), Q::from_i64(2)),
            (Mono::one(), Q::from_i64(1)),
            (m(&[(0, 2)]), Q::from_i64(3)),
            (m(&[(1, 1)]), Q::from_i64(-2)),
            (m(&[(0, 1), (1, 1)]), Q::new(-1, 2).expect("q")),
        ]);
        assert!(is_canonical(&p));
        assert_eq!(p.to_string(), "3*x0^2 - 1/2*x0*x1 + 1");
        assert_eq!(p.len(), 3);
        assert_eq!(p.leading_coeff(), Some(&Q::from_i64(3)));
        assert_eq!(p.leading_mono(), Some(&m(&[(0, 2)])));
        assert_eq!(Poly::zero().as_constant(), Some(&Q::zero()));
        assert_eq!(c(5).as_constant(), Some(&Q::from_i64(5)));
        assert_eq!(p.as_constant(), None);
        assert!(Poly::one().is_one());
        assert!(x(3).is_monomial());
        assert_eq!(Poly::zero().to_string(), "0");
        assert_eq!((-&x(2) + c(1)).to_string(), "-x2 + 1");
        assert_eq!(p.vars(), vec![0, 1]);
        assert_eq!(p.degree(0), 2);
        assert_eq!(p.total_degree(), 2);
        assert!(p.contains_var(1) && !p.contains_var(2));
        assert_eq!(p.coeff_of(&m(&[(0, 2)])), Q::from_i64(3));
        assert_eq!(p.coeff_of(&m(&[(0, 1)])), Q::zero());
    }

    #[test]
    fn arithmetic_exact() {
        let (a, b) = (x(0), x(1));
        let s = &a + &b;
        let sq = &s * &s;
        assert_eq!(sq.to_string(), "x0^2 + 2*x0*x1 + x1^2");
        assert_eq!(s.pow(3).to_string(), "x0^3 + 3*x0^2*x1 + 3*x0*x1^2 + x1^3");
        assert_eq!((&sq - &sq), Poly::zero());
        let d = &a - &b;
        assert_eq!((&s * &d).to_string(), "x0^2 - x1^2");
        assert_eq!(
            s.scale(&Q::new(1, 2).expect("q")).to_string(),
            "1/2*x0 + 1/2*x1"
        );
        assert_eq!(
            s.mul_mono(&m(&[(1, 2)]), &Q::from_i64(-3)).to_string(),
            "-3*x0*x1^2 - 3*x1^3"
        );
        let mut acc = Poly::zero();
        acc += &s;
        acc -= &a;
        acc *= &b;
        assert_eq!(acc.to_string(), "x1^2");
        assert_eq!(s.clone() + d.clone(), a.scale(&Q::from_i64(2)));
        assert_eq!(s.clone() - d.clone(), b.scale(&Q::from_i64(2)));
        assert_eq!(&s - d.clone(), b.scale(&Q::from_i64(2)));
        assert_eq!(s.clone() * &d, &s * &d);
        assert_eq!(Poly::zero().pow(0), Poly::one());
        assert_eq!(c(2).pow(10), c(1024));
        assert_eq!(-(s.clone()), -&s);
    }

    #[test]
    fn division() {
        let s = &(&x(0) + &x(1)) + &c(1);
        let p3 = s.pow(3);
        assert_eq!(p3.div_exact(&s), Some(s.pow(2)));
        assert_eq!(p3.div_exact(&s.pow(3)), Some(Poly::one()));
        assert_eq!(p3.div_exact(&s.pow(4)), None);
        let q = &x(0) * &x(0) + c(1);
        assert_eq!(q.div_exact(&(&x(0) + &c(1))), None);
        assert_eq!(q.div_exact(&Poly::zero()), None);
        assert_eq!(Poly::zero().div_exact(&q), Some(Poly::zero()));
        assert_eq!(q.div_exact(&c(2)), Some(q.scale(&Q::new(1, 2).expect("q"))));
        assert_eq!(x(0).div_exact(&(&x(0) - &x(1))), None);
        assert_eq!((&x(0) * &x(1)).div_exact(&x(1)), Some(x(0)));
        assert_eq!(x(0).div_exact(&x(1)), None);
        // huge exponents: exercises the unpacked (plain) paths
        let big: Poly = (0..6)
            .map(|v| Poly::monomial(Mono::var_pow(v, 1 << 30), Q::one()))
            .fold(Poly::zero(), |a, b| a + b);
        let big2 = &big + &c(1);
        let prod = &big * &big2;
        assert!(is_canonical(&prod));
        assert_eq!(prod.div_exact(&big2), Some(big.clone()));
        assert_eq!(prod.div_exact(&big), Some(big2.clone()));
        assert_eq!((&prod + &c(1)).div_exact(&big), None);
    }

    #[test]
    fn structure_ops() {
        // p = 3 x0^2 x1 + x0 x2 - 5 x1 + 7
        let p = Poly::from_terms(vec![
            (m(&[(0, 2), (1, 1)]), Q::from_i64(3)),
            (m(&[(0, 1), (2, 1)]), Q::from_i64(1)),
            (m(&[(1, 1)]), Q::from_i64(-5)),
            (Mono::one(), Q::from_i64(7)),
        ]);
        let cs = p.coeffs_in(0);
        assert_eq!(cs.len(), 3);
        assert_eq!(cs[0].to_string(), "-5*x1 + 7");
        assert_eq!(cs[1].to_string(), "x2");
        assert_eq!(cs[2].to_string(), "3*x1");
        assert_eq!(Poly::from_coeffs_in(0, &cs), p);
        let cs1 = p.coeffs_in(1);
        assert_eq!(Poly::from_coeffs_in(1, &cs1), p);
        assert_eq!(p.diff(0).to_string(), "6*x0*x1 + x2");
        assert_eq!(p.diff(1).to_string(), "3*x0^2 - 5");
        assert_eq!(p.diff(5), Poly::zero());
        // subst x0 -> x1 + 1
        let s = p.subst(0, &(&x(1) + &c(1)));
        let expect = &(&(&c(3) * &(&x(1) + &c(1)).pow(2)) * &x(1) + &(&(&x(1) + &c(1)) * &x(2)))
            - &(&c(5) * &x(1))
            + c(7);
        assert_eq!(s, expect);
        let val = p.eval_q(&|v| Some(Q::from_i64(v as i64 + 2)));
        // x0=2,x1=3,x2=4: 3*4*3 + 2*4 - 15 + 7 = 36
        assert_eq!(val, Some(Q::from_i64(36)));
        assert_eq!(
            p.eval_q(&|v| if v == 2 { None } else { Some(Q::one()) }),
            None
        );
        assert_eq!(p.eval_f64(&|v| v as f64 + 2.0), 36.0);
        assert_eq!(p.eval_var(0, &Q::from_i64(2)), p.subst(0, &c(2)));
        let r = p.map_vars(&|v| v + 10);
        assert_eq!(r.vars(), vec![10, 11, 12]);
        assert_eq!(r.map_vars(&|v| v - 10), p);
        // content / primitive / monic
        let q = Poly::from_terms(vec![
            (m(&[(0, 1)]), Q::new(3, 4).expect("q")),
            (Mono::one(), Q::new(-9, 10).expect("q")),
        ]);
        assert_eq!(q.content(), Q::new(3, 20).expect("q"));
        assert_eq!(q.primitive().to_string(), "5*x0 - 6");
        assert_eq!(q.monic().to_string(), "x0 - 6/5");
        assert_eq!((-&q).primitive().to_string(), "-5*x0 + 6");
        assert_eq!(Poly::zero().content(), Q::zero());
        assert_eq!((&x(0) * &x(1) + x(0).pow(2)).mono_content(), m(&[(0, 1)]));
    }

    fn check_gcd(a: &Poly, b: &Poly, expect: &Poly) {
        let g = a.gcd(b);
        assert_eq!(&g, &expect.monic(), "gcd({a}, {b})");
        let g2 = b.gcd(a);
        assert_eq!(&g2, &expect.monic());
        let (gg, ca, cb) = a.gcd_cofactors(b);
        assert_eq!(gg, g);
        assert_eq!(&(&ca * &g), a);
        assert_eq!(&(&cb * &g), b);
    }

    #[test]
    fn gcd_simple() {
        let (a, b, z) = (x(0), x(1), x(2));
        check_gcd(&Poly::zero(), &Poly::zero(), &Poly::zero());
        check_gcd(
            &Poly::zero(),
            &(&a.scale(&Q::from_i64(3)) + &c(6)),
            &(&a + &c(2)),
        );
        check_gcd(&c(4), &c(6), &c(1));
        check_gcd(&(&a * &b), &(&b * &z), &b);
        check_gcd(
            &(&a.pow(3) * &b),
            &(&(&a.pow(2) * &b.pow(2)) + &a.pow(5)),
            &a.pow(2),
        );
        check_gcd(&(&a + &b), &(&a - &b), &c(1));
        check_gcd(
            &(&a.pow(2) - &b.pow(2)),
            &(&(&a + &b) * &(&a + &z)),
            &(&a + &b),
        );
        check_gcd(
            &(&a.pow(2) - &c(1)),
            &(&a.pow(2) - &(&c(2) * &a) + c(1)),
            &(&a - &c(1)),
        );
    }

    #[test]
    fn gcd_hard_cases() {
        let (xx, yy, zz) = (x(0), x(1), x(2));
        // (x+y+z)^5 (x-y) and (x+y+z)^3 (x+2z)^2
        let s = &(&xx + &yy) + &zz;
        let a = &s.pow(5) * &(&xx - &yy);
        let b = &s.pow(3) * &(&xx + &zz.scale(&Q::from_i64(2))).pow(2);
        check_gcd(&a, &b, &s.pow(3));
        // rational coefficients
        let f = &xx.scale(&Q::new(1, 2).expect("q")) + &yy.scale(&Q::new(1, 3).expect("q"));
        let a = &f * &(&xx - &cq(1, 5));
        let b = &f * &(&yy + &cq(7, 4));
        check_gcd(&a, &b, &f);
        // many variables only in one argument
        let mut big = Poly::zero();
        for v in 10..40u32 {
            big += &(&x(v) * &x(v + 1)).scale(&Q::from_i64(v as i64 - 20));
        }
        big += &c(3);
        let common = &xx + &yy;
        let a = &common * &big;
        let b = &common * &(&xx - &yy.scale(&Q::from_i64(3)));
        check_gcd(&a, &b, &common);
        // univariate degree 20
        let g: Poly = (0..=10)
            .map(|i| Poly::monomial(Mono::var_pow(0, i), Q::from_i64((i as i64 * 7) % 5 - 2)))
            .fold(Poly::zero(), |p, q| p + q);
        let u1: Poly = (0..=10)
            .map(|i| Poly::monomial(Mono::var_pow(0, i), Q::from_i64((i as i64 * 3) % 7 - 3)))
            .fold(Poly::zero(), |p, q| p + q);
        let u2: Poly = (0..=9)
            .map(|i| Poly::monomial(Mono::var_pow(0, i), Q::from_i64((i as i64 * 5) % 11 - 5)))
            .fold(Poly::zero(), |p, q| p + q);
        let e = &g * &u1.gcd(&u2);
        check_gcd(&(&g * &u1), &(&g * &u2), &e);
        // many variables in the gcd itself (PRS path): 8 variables
        let mut lin = c(1);
        for v in 0..8u32 {
            lin += &x(v).scale(&Q::from_i64(v as i64 + 1));
        }
        let mut other = c(-2);
        for v in 0..8u32 {
            other += &(&x(v) * &x((v + 1) % 8));
        }
        let a = &lin * &other;
        let b = &lin * &(&lin + &x(3).pow(2));
        check_gcd(&a, &b, &lin);
        check_gcd(&(&a * &lin), &(&b * &lin), &lin.pow(2));
    }

    #[test]
    fn gcd_dense_bivariate_degree_10() {
        let (xx, yy) = (x(0), x(1));
        let dense = |seed: i64, dx: u32, dy: u32| -> Poly {
            let mut t = Vec::new();
            for i in 0..=dx {
                for j in 0..=dy {
                    let cf = ((seed + 3 * i as i64 + 7 * j as i64 + (i * j) as i64) % 9) - 4;
                    t.push((m(&[(0, i), (1, j)]), Q::from_i64(cf)));
                }
            }
            Poly::from_terms(t)
        };
        let g = &dense(1, 5, 5) + &(&xx.pow(5) * &yy.pow(5));
        let a = &g * &(&dense(2, 5, 5) + &xx.pow(6));
        let b = &g * &(&dense(5, 5, 5) + &yy.pow(6));
        let expect = &g * &(&dense(2, 5, 5) + &xx.pow(6)).gcd(&(&dense(5, 5, 5) + &yy.pow(6)));
        check_gcd(&a, &b, &expect);
        assert!(a.degree(0) >= 10 && a.degree(1) >= 10);
    }

    #[test]
    fn gcd_sparse_many_vars() {
        // nontrivial gcd of degree 3 in 8 variables (sparse modular path)
        let t = |c: i64, e: &[(Var, u32)]| Poly::monomial(m(e), Q::from_i64(c));
        let g = &(&(&t(3, &[(1, 3), (4, 1), (10, 1), (19, 2)])
            - &t(1, &[(1, 2), (4, 2), (13, 1), (34, 2)]))
            + &t(8, &[(1, 1), (10, 2), (19, 3), (25, 2)]))
            - &(&t(8, &[(4, 3), (10, 3), (13, 3), (25, 3), (28, 2), (34, 3)])
                + &t(1, &[(4, 2), (19, 1), (25, 3), (28, 2), (34, 1)]));
        let ca = &(&t(2, &[(1, 1), (28, 3), (34, 1)]) - &t(5, &[(4, 2), (13, 1)]))
            + &t(7, &[(10, 1), (19, 1), (25, 2)]);
        let cb = &(&t(1, &[(1, 2), (10, 1)]) + &t(4, &[(13, 2), (28, 1), (34, 3)]))
            - &t(3, &[(4, 1), (19, 2), (25, 1)]);
        check_gcd(&(&g * &ca), &(&g * &cb), &g);
        check_gcd(&(&(&g * &ca) * &cb), &(&g * &cb.pow(2)), &(&g * &cb));
        // the same through the Zippel routine directly
        let (a, b) = ((&g * &ca).normalize_z(), (&g * &cb).normalize_z());
        let vars = a.vars();
        let bounds: Vec<u32> = vars.iter().map(|&v| g.degree(v)).collect();
        let z = zippel_gcd(&a, &b, &vars, &bounds).expect("zippel succeeds");
        assert_eq!(z.monic(), g.monic());
    }

    #[test]
    fn gcd_pendulum_like() {
        // trig-polynomial style expressions: s_i, c_i, masses, lengths
        let n = 6u32;
        let sv = |i: u32| x(i);
        let cv = |i: u32| x(10 + i);
        let mv = |i: u32| x(20 + i);
        let lv = |i: u32| x(30 + i);
        let mut mass_sum = Poly::zero();
        for i in 0..n {
            mass_sum += &mv(i);
        }
        let mut e1 = Poly::zero();
        for i in 0..n {
            e1 += &(&(&mv(i) * &lv(i))
                * &(&(&sv(i) * &cv((i + 1) % n)) - &(&cv(i) * &sv((i + 1) % n))));
        }
        let mut e2 = Poly::zero();
        for i in 0..n {
            e2 += &(&lv(i).pow(2) * &(&sv(i).pow(2) + &cv(i).pow(2)));
        }
        let a = &mass_sum * &e1;
        let b = &mass_sum * &e2;
        check_gcd(&a, &b, &mass_sum);
        check_gcd(&e1, &e2, &c(1));
        let k = &lv(0) * &mv(1);
        check_gcd(&(&a * &k), &(&e2 * &(&k * &lv(2))), &k);
    }

    /// Independent reference gcd: plain recursive primitive PRS, no shortcuts.
    fn ref_gcd(a: &Poly, b: &Poly) -> Poly {
        if a.is_zero() {
            return b.normalize_z();
        }
        if b.is_zero() {
            return a.normalize_z();
        }
        let (ma, mb) = (a.mono_content(), b.mono_content());
        if !ma.is_one() || !mb.is_one() {
            let g = ref_gcd(
                &a.div_mono(&ma).expect("mono"),
                &b.div_mono(&mb).expect("mono"),
            );
            return g.mul_mono(&ma.gcd(&mb), &Q::one());
        }
        let mut vars = a.vars();
        vars.extend(b.vars());
        vars.sort_unstable();
        vars.dedup();
        // main variable: smallest total degree in a and b
        let v = match vars.iter().min_by_key(|&&v| (a.degree(v) + b.degree(v), v)) {
            Some(v) => *v,
            None => return Poly::one(),
        };
        if !a.contains_var(v) {
            return b
                .coeffs_in(v)
                .iter()
                .fold(a.normalize_z(), |g, c| ref_gcd(&g, c));
        }
        if !b.contains_var(v) {
            return a
                .coeffs_in(v)
                .iter()
                .fold(b.normalize_z(), |g, c| ref_gcd(&g, c));
        }
        let content = |cs: &[Poly]| cs.iter().fold(Poly::zero(), |g, c| ref_gcd(&g, c));
        let prim = |cs: &[Poly]| -> Vec<Poly> {
            let ct = content(cs);
            cs.iter()
                .map(|c| c.div_exact(&ct).expect("content divides"))
                .collect()
        };
        let (ca, cb) = (a.coeffs_in(v), b.coeffs_in(v));
        let cont = ref_gcd(&content(&ca), &content(&cb));
        let (mut u, mut w) = (prim(&ca), prim(&cb));
        if u.len() < w.len() {
            std::mem::swap(&mut u, &mut w);
        }
        let last = loop {
            let r = prem(&u, &w);
            if r.is_empty() {
                break prim(&w);
            }
            if r.len() == 1 {
                break vec![Poly::one()];
            }
            u = w;
            w = prim(&r);
        };
        (&Poly::from_coeffs_in(v, &last) * &cont).normalize_z()
    }

    fn lcg(state: &mut u64) -> u64 {
        *state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        *state >> 33
    }

    fn rand_poly(st: &mut u64, vars: &[Var], maxdeg: u32, nterms: usize, cmax: i64) -> Poly {
        let mut t = Vec::new();
        for _ in 0..nterms {
            let mo = Mono::from_pairs(
                vars.iter()
                    .map(|&v| (v, (lcg(st) % (maxdeg as u64 + 1)) as u32)),
            );
            let cf = (lcg(st) % (2 * cmax as u64 + 1)) as i64 - cmax;
            t.push((mo, Q::from_i64(cf)));
        }
        Poly::from_terms(t)
    }

    /// 1…maxvars distinct variables out of twelve, sorted.
    fn random_vars(st: &mut u64, maxvars: usize) -> Vec<Var> {
        let all: Vec<Var> = (0..12).map(|i| i * 3 + 1).collect();
        let nv = 1 + (lcg(st) as usize % maxvars);
        let mut vars: Vec<Var> = Vec::new();
        while vars.len() < nv {
            let v = all[lcg(st) as usize % all.len()];
            if !vars.contains(&v) {
                vars.push(v);
            }
        }
        vars.sort_unstable();
        vars
    }

    fn random_gcd_round(seed: u64, rounds: usize, maxvars: usize) {
        let mut st = seed;
        for round in 0..rounds {
            let vars = random_vars(&mut st, maxvars);
            let pick = |st: &mut u64| -> Vec<Var> {
                vars.iter()
                    .copied()
                    .filter(|_| !lcg(st).is_multiple_of(3))
                    .collect()
            };
            let (va, vb, vg) = (pick(&mut st), pick(&mut st), pick(&mut st));
            let deg = 1 + (lcg(&mut st) % 3) as u32;
            let na = 1 + lcg(&mut st) as usize % 5;
            let a = rand_poly(&mut st, &va, deg, na, 5);
            let nb = 1 + lcg(&mut st) as usize % 5;
            let b = rand_poly(&mut st, &vb, deg, nb, 5);
            let ng = 1 + lcg(&mut st) as usize % 4;
            let g = rand_poly(&mut st, &vg, deg, ng, 5);
            let (ag, bg) = (&a * &g, &b * &g);
            if ag.len() + bg.len() > 24 || ag.total_degree() + bg.total_degree() > 12 {
                // the naive reference gets too slow
                continue;
            }
            if std::env::var("GCD_TRACE").is_ok() {
                eprintln!("seed {seed} round {round}: a={ag}\n b={bg}");
            }
            let t0 = std::time::Instant::now();
            let h = ag.gcd(&bg);
            let t1 = t0.elapsed();
            let r = ref_gcd(&ag, &bg).monic();
            let t2 = t0.elapsed() - t1;
            if t1.as_millis() > 200 || t2.as_millis() > 200 {
                eprintln!(
                    "slow round {round}: gcd {t1:?} ref {t2:?} vars {} terms {}/{}",
                    vars.len(),
                    ag.len(),
                    bg.len()
                );
            }
            assert_eq!(h, r, "round {round}: gcd({ag}, {bg})");
        }
    }

    #[test]
    fn gcd_matches_reference() {
        random_gcd_round(12345, 150, 4);
    }

    /// Remainder of univariate polynomials in `v` over Q.
    fn urem(mut a: Poly, b: &Poly, v: Var) -> Poly {
        let db = b.degree(v);
        let lb = b.leading_coeff().cloned().unwrap_or_else(Q::one);
        while !a.is_zero() && a.degree(v) >= db {
            let k = a.degree(v) - db;
            let f = a.leading_coeff().cloned().unwrap_or_else(Q::zero) / &lb;
            a = &a - &b.mul_mono(&Mono::var_pow(v, k), &f);
        }
        a
    }

    /// Independent coprimality proof: for every variable, the univariate
    /// images (all other variables at random rationals, leading coefficient
    /// kept) have a constant gcd. `false` means "not proven".
    fn proven_coprime(a: &Poly, b: &Poly, st: &mut u64) -> bool {
        if a.is_constant() || b.is_constant() {
            return !(a.is_zero() && b.is_zero());
        }
        let mut vars = a.vars();
        vars.extend(b.vars());
        vars.sort_unstable();
        vars.dedup();
        'var: for &x in &vars {
            for _ in 0..8 {
                let vals: Vec<(Var, Q)> = vars
                    .iter()
                    .map(|&w| {
                        (
                            w,
                            Q::new(lcg(st) as i64 % 97 - 48, 1 + lcg(st) as i64 % 5).expect("q"),
                        )
                    })
                    .collect();
                let sub = |p: &Poly| {
                    vals.iter()
                        .filter(|(w, _)| *w != x)
                        .fold(p.clone(), |p, (w, q)| p.eval_var(*w, q))
                };
                let (ua, ub) = (sub(a), sub(b));
                if ua.degree(x) != a.degree(x)
                    || ub.degree(x) != b.degree(x)
                    || ua.is_zero()
                    || ub.is_zero()
                {
                    continue;
                }
                let (mut f, mut g) = (ua, ub);
                while !g.is_zero() {
                    let r = urem(f, &g, x);
                    f = g;
                    g = r;
                }
                if f.is_constant() {
                    continue 'var;
                }
                // an unlucky point can only make the image gcd larger: retry
            }
            return false;
        }
        true
    }

    fn random_gcd_proof_round(seed: u64, rounds: usize, maxvars: usize, maxdeg: u64) {
        let mut st = seed;
        for round in 0..rounds {
            let vars = random_vars(&mut st, maxvars);
            let pick = |st: &mut u64| -> Vec<Var> {
                vars.iter()
                    .copied()
                    .filter(|_| !lcg(st).is_multiple_of(4))
                    .collect()
            };
            let (va, vb, vg) = (pick(&mut st), pick(&mut st), pick(&mut st));
            let deg = 1 + (lcg(&mut st) % maxdeg) as u32;
            let na = 1 + lcg(&mut st) as usize % 8;
            let a = rand_poly(&mut st, &va, deg, na, 9);
            let nb = 1 + lcg(&mut st) as usize % 8;
            let b = rand_poly(&mut st, &vb, deg, nb, 9);
            let ng = 1 + lcg(&mut st) as usize % 6;
            let g = rand_poly(&mut st, &vg, deg, ng, 9);
            let (ag, bg) = (&a * &g, &b * &g);
            if std::env::var("GCD_TRACE").is_ok() {
                eprintln!("seed {seed} round {round}: a={ag}\n b={bg}");
            }
            let t0 = std::time::Instant::now();
            let h = ag.gcd(&bg);
            let el = t0.elapsed();
            if el.as_millis() > 500 {
                eprintln!("slow gcd round {round}: {el:?}\n a={ag}\n b={bg}");
            }
            if ag.is_zero() && bg.is_zero() {
                assert!(h.is_zero());
                continue;
            }
            let ca = ag.div_exact(&h).expect("gcd divides a");
            let cb = bg.div_exact(&h).expect("gcd divides b");
            assert!(
                h.div_exact(&g).is_some() || g.is_zero(),
                "g does not divide gcd"
            );
            assert!(
                proven_coprime(&ca, &cb, &mut st),
                "seed {seed} round {round}: cofactors not coprime: gcd({ag}, {bg}) = {h}; cofactors {ca} ; {cb}"
            );
        }
    }

    #[test]
    fn gcd_cofactors_proven_coprime() {
        random_gcd_proof_round(777, 60, 5, 3);
    }

    /// Longer randomized checks (about 3 s in release builds, which CI uses).
    #[test]
    fn gcd_long_random_reference() {
        for seed in 0..10 {
            let t = std::time::Instant::now();
            random_gcd_round(seed * 7919 + 1, 300, 3);
            eprintln!("reference seed {seed}: {:?}", t.elapsed());
        }
    }

    #[test]
    fn gcd_long_random_big() {
        for seed in 0..10 {
            let t = std::time::Instant::now();
            random_gcd_proof_round(seed * 15485863 + 11, 200, 12, 6);
            eprintln!("big seed {seed}: {:?}", t.elapsed());
        }
    }

    #[test]
    fn gcd_long_random_proof() {
        for seed in 0..20 {
            let t = std::time::Instant::now();
            random_gcd_proof_round(seed * 104729 + 5, 500, 8, 4);
            eprintln!("proof seed {seed}: {:?}", t.elapsed());
        }
    }

    // ------------------------------------------------------------------
    // property tests
    // ------------------------------------------------------------------

    const VARS: [Var; 4] = [0, 3, 17, 40];

    fn arb_coeff() -> impl Strategy<Value = Q> {
        prop_oneof![
            4 => (-6i64..=6).prop_filter("nonzero", |n| *n != 0).prop_map(Q::from_i64),
            1 => ((-6i64..=6), (1i64..=5)).prop_filter_map("nonzero", |(n, d)| Q::new(n, d).filter(|q| !q.is_zero())),
            1 => any::<i32>().prop_map(|n| Q::from_i64(n as i64)),
        ]
    }

    fn arb_poly(nvars: usize, maxdeg: u32, maxterms: usize) -> impl Strategy<Value = Poly> {
        proptest::collection::vec(
            (proptest::collection::vec(0..=maxdeg, nvars), arb_coeff()),
            0..=maxterms,
        )
        .prop_map(move |ts| {
            Poly::from_terms(
                ts.into_iter()
                    .map(|(es, cf)| (Mono::from_pairs(VARS.iter().copied().zip(es)), cf))
                    .collect(),
            )
        })
    }

    fn arb_small() -> impl Strategy<Value = Poly> {
        arb_poly(3, 2, 4).prop_map(|p| {
            p.map_coeffs(|c| {
                if c.numer().bits() > 8 {
                    Q::from_i64(3)
                } else {
                    c.clone()
                }
            })
        })
    }

    fn pt(v: Var) -> Option<Q> {
        Q::new(v as i64 * 7 + 3, (v as i64 % 5) + 2)
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(200))]

        #[test]
        fn prop_ring_laws(a in arb_poly(4, 3, 6), b in arb_poly(4, 3, 6), d in arb_poly(4, 3, 6)) {
            prop_assert!(is_canonical(&a));
            let ab = &a * &b;
            prop_assert!(is_canonical(&ab));
            prop_assert_eq!(&ab, &(&b * &a));
            prop_assert_eq!(&a * &(&b + &d), &(&a * &b) + &(&a * &d));
            prop_assert_eq!(&(&a + &b) - &b, a.clone());
            prop_assert_eq!(&a + &b, &b + &a);
            prop_assert_eq!(a.clone() + b.clone(), &a + &b);
            prop_assert_eq!(a.clone() - b.clone(), &a - &b);
            prop_assert_eq!(&a - b.clone(), &a - &b);
            prop_assert_eq!(a.clone() - &b, &a - &b);
            prop_assert_eq!(&a + b.clone(), &a + &b);
            prop_assert_eq!(&(&a * &b) * &d, &a * &(&b * &d));
            prop_assert_eq!(ab.eval_q(&pt), Some(a.eval_q(&pt).expect("eval") * b.eval_q(&pt).expect("eval")));
            prop_assert_eq!((&a + &b).eval_q(&pt), Some(a.eval_q(&pt).expect("eval") + b.eval_q(&pt).expect("eval")));
            let f = |v: Var| pt(v).map(|q| q.to_f64()).unwrap_or(0.0);
            let (ef, eq) = (ab.eval_f64(&f), ab.eval_q(&pt).expect("eval").to_f64());
            prop_assert!((ef - eq).abs() <= 1e-6 * (1.0 + eq.abs()));
            prop_assert_eq!(a.pow(3), &(&a * &a) * &a);
            // derivative: product rule
            prop_assert_eq!(ab.diff(3), &(&a.diff(3) * &b) + &(&a * &b.diff(3)));
            // coeffs round trip
            prop_assert_eq!(Poly::from_coeffs_in(17, &a.coeffs_in(17)), a.clone());
            // substitution is a ring homomorphism
            let d2 = Poly::from_terms(d.terms().iter().take(2).cloned().collect());
            prop_assert_eq!(ab.subst(0, &d2), &a.subst(0, &d2) * &b.subst(0, &d2));
        }

        #[test]
        fn prop_big_coefficients(
            a in arb_poly(3, 2, 4),
            b in arb_poly(3, 2, 4),
            k in prop_oneof![Just(i64::MAX), Just(i64::MIN), Just(i64::MAX - 1), any::<i64>()],
        ) {
            // coefficients near the i64 limits: overflow into BigRational and back
            let kq = Q::from_i64(k);
            let ak = a.scale(&kq);
            let bk = &b + &Poly::constant(kq.clone());
            let p = &ak * &bk;
            prop_assert!(is_canonical(&p));
            prop_assert_eq!(&p, &(&bk * &ak));
            prop_assert_eq!(p.eval_q(&pt), Some(ak.eval_q(&pt).expect("eval") * bk.eval_q(&pt).expect("eval")));
            if !bk.is_zero() {
                prop_assert_eq!(p.div_exact(&bk), Some(ak.clone()));
            }
            prop_assert_eq!(&(&p - &(&ak * &b)) - &ak.scale(&kq), Poly::zero());
            if !ak.is_zero() && !bk.is_zero() {
                let g = (&ak * &bk).gcd(&ak);
                prop_assert_eq!(g, ak.monic());
            }
        }

        #[test]
        fn prop_div_exact(a in arb_poly(4, 3, 6), b in arb_poly(4, 3, 6)) {
            let ab = &a * &b;
            if !b.is_zero() {
                prop_assert_eq!(ab.div_exact(&b), Some(a.clone()));
                let r = &ab + &c(1);
                if let Some(q) = r.div_exact(&b) {
                    prop_assert_eq!(&q * &b, r);
                }
            } else {
                prop_assert_eq!(ab.div_exact(&b), None);
            }
        }

        #[test]
        fn prop_gcd(a in arb_small(), b in arb_small(), g in arb_small()) {
            prop_assume!(!g.is_zero());
            let ag = &a * &g;
            let bg = &b * &g;
            let h = ag.gcd(&bg);
            prop_assert!(is_canonical(&h));
            if ag.is_zero() && bg.is_zero() {
                prop_assert!(h.is_zero());
                return Ok(());
            }
            prop_assert_eq!(h.leading_coeff(), Some(&Q::one()));
            prop_assert!(h.div_exact(&g).is_some(), "g does not divide gcd: {} / {}", h, g);
            prop_assert!(ag.div_exact(&h).is_some());
            prop_assert!(bg.div_exact(&h).is_some());
            let gab = a.gcd(&b);
            prop_assert_eq!(&h, &(&g * &gab).monic());
            prop_assert_eq!(&h, &bg.gcd(&ag));
            // cofactors are coprime
            let (_, ca, cb) = ag.gcd_cofactors(&bg);
            prop_assert!(ca.gcd(&cb).is_one() || (ca.is_zero() || cb.is_zero()));
        }

        #[test]
        fn prop_gcd_coprime(a in arb_poly(3, 2, 4), b in arb_poly(3, 2, 4)) {
            // a*x0 + 1 and b*x3 + x0 + 2 ... constructions that are coprime
            let p = &(&a * &x(0)) + &c(1);
            let q = &p + &x(3);
            // gcd(p, p + x3) = gcd(p, x3) = 1 since p(x3=0) != 0 mod x3 ... p has constant term 1
            prop_assume!(!p.is_zero());
            prop_assert!(p.gcd(&q).is_one());
            let r = &(&b * &x(3)) + &c(2);
            let pr = &p * &r;
            prop_assert_eq!(pr.gcd(&p), p.monic());
        }
    }
}
