//! Factorization of multivariate polynomials over ℚ into irreducible factors.
//!
//! [`factor`] writes `p = unit · ∏ fᵢ^eᵢ` with every `fᵢ` irreducible over ℚ,
//! primitive with integer coefficients and a positive leading coefficient (in
//! [`Poly`]'s term order). The steps:
//!
//! 1. the numeric content (a rational) and the monomial content (powers of
//!    single variables) are split off;
//! 2. [`square_free`]: Yun's algorithm with respect to the first variable on
//!    the part primitive in it, recursively on the content (which is free of
//!    that variable), so every part is a product of distinct irreducibles;
//! 3. each square-free part is split by its contents with respect to every
//!    variable (the gcd of its coefficients in `v`, the factors free of `v`);
//!    a part primitive in `v` and of degree 1 in `v` is irreducible;
//! 4. univariate parts: Zassenhaus' algorithm — distinct-degree and
//!    Cantor–Zassenhaus equal-degree factorization modulo the best of a few
//!    primes (fewest factors; the possible factor degrees of all of them
//!    intersected), multifactor quadratic Hensel lifting along a binary tree
//!    to beyond twice the Mignotte bound, and recombination of subsets by
//!    trial division with the degree and constant-term tests (von zur Gathen
//!    & Gerhard, *Modern Computer Algebra*, 3rd ed., §14.2–14.3, Alg. 15.10,
//!    15.17, 15.19; Cohen, *A Course in Computational Algebraic Number
//!    Theory*, §3.5);
//! 5. multivariate parts: the extended Zassenhaus method — the variables
//!    other than the main one `x` (smallest degree) are set to an integer
//!    point `c` (zero first) that keeps `deg_x` and leaves the image
//!    square-free; an irreducible image proves irreducibility; otherwise the
//!    image factors (the best of a few points: fewest factors) are lifted
//!    in `ℚ[[y − c]][x]` by linear Hensel lifting in all the other variables
//!    at once, and subsets recombined by exact division (Wang & Rothschild,
//!    "Factoring multivariate polynomials over the integers", Math. Comp.
//!    29, 1975; MCA §15.4–15.6, §16.6);
//! 6. when no suitable point is found: Kronecker's substitution
//!    `xⱼ ↦ y^Dⱼ` with mixed radices `Dⱼ₊₁ = Dⱼ·(deg_{xⱼ} p + 1)` (injective
//!    on every divisor of `p`), the univariate image factored completely
//!    over ℤ, and subsets of its irreducible factors (and of the power of `y`
//!    it contains) mapped back and tested by exact division, smallest
//!    subsets first (Kaltofen, "Factorization of polynomials", Computer
//!    Algebra, 1982).
//!
//! Every search is finite. The costs to know:
//! * recombination is exponential in the number `r` of modular
//!   (univariate), image (evaluation) or ℤ-irreducible (Kronecker image)
//!   factors: `Σ_{s ≤ r/2} C(r, s)` trial candidates at worst
//!   (Swinnerton-Dyer polynomials of degree 2ᵏ split into ≥ 2ᵏ⁻¹ factors
//!   modulo every prime); no lattice reduction (van Hoeij) is done;
//! * the lifting in several variables works on dense truncated power
//!   series: its cost grows with `deg_x · (number of monomials of total
//!   degree ≤ 2·deg_y)`;
//! * the lifting is skipped beyond [`MAX_LIFTING_WORK`] (sparse polynomials
//!   whose leading coefficient in every variable vanishes at 0 need a
//!   shifted point, which makes them dense), and the Kronecker image has
//!   degree up to `∏ (deg_{xⱼ} p + 1) − 1`; when the lifting is skipped and
//!   the image is above [`MAX_KRONECKER_DEGREE`], a multivariate part is
//!   returned unsplit: it is then a factor, but not certified irreducible
//!   (seen on products of sparse quartic-by-cubic pieces in 4 variables);
//! * a univariate part for which no prime below 2¹⁶ keeps it square-free (a
//!   discriminant divisible by all of them) is likewise returned unsplit.

use super::modular::{invmod, trim, XorShift64Star};
use super::{Mono, Poly, Var};
use crate::num::Q;
use num_bigint::{BigInt, BigUint};
use num_integer::Integer;
use num_traits::{One, Signed, ToPrimitive, Zero};
use rustc_hash::FxHashSet;
use std::cmp::Ordering;

/// Degree limit of the univariate Kronecker image of a multivariate part
/// (see the module docs): beyond it the part is not split.
pub const MAX_KRONECKER_DEGREE: u64 = 256;

/// Primes are taken below this bound for the modular factorization.
const PRIME_LIMIT: u64 = 1 << 16;

/// Number of usable primes whose distinct-degree factorizations are compared.
const PRIMES_TRIED: usize = 5;

/// A complete factorization `unit · ∏ factorᵢ^expᵢ` over ℚ.
///
/// Each factor is irreducible over ℚ, primitive with integer coefficients and
/// has a positive leading coefficient; factors are distinct and sorted by
/// total degree, then number of terms, then terms (largest monomial first,
/// coefficients ascending), so the result is canonical.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Factorization {
    /// The rational unit (0 for the zero polynomial).
    pub unit: Q,
    /// The irreducible factors with their multiplicities.
    pub factors: Vec<(Poly, u32)>,
}

impl Factorization {
    /// The product `unit · ∏ factorᵢ^expᵢ` (equal to the factored polynomial).
    pub fn expand(&self) -> Poly {
        let mut acc = Poly::constant(self.unit.clone());
        for (f, e) in &self.factors {
            acc = &acc * &f.pow(*e);
        }
        acc
    }
}

/// Factors `p` into irreducibles over ℚ (see the module docs for the method
/// and its limits). `factor(0)` has unit 0 and no factors; a constant has
/// itself as unit and no factors.
pub fn factor(p: &Poly) -> Factorization {
    if let Some(c) = p.as_constant() {
        return Factorization {
            unit: c.clone(),
            factors: Vec::new(),
        };
    }
    let mut factors: Vec<(Poly, u32)> = Vec::new();
    let m = p.mono_content();
    for &(v, e) in m.pairs() {
        factors.push((Poly::var(v), e));
    }
    let rest = normalize(&p.div_mono(&m).unwrap_or_else(|| p.clone()));
    for (part, mult) in square_free(&rest) {
        let mut irr = Vec::new();
        factor_squarefree(&part, &mut irr);
        factors.extend(irr.into_iter().map(|g| (g, mult)));
    }
    factors.sort_by(|a, b| canonical_cmp(&a.0, &b.0).then(a.1.cmp(&b.1)));
    let mut den = Q::one();
    for (f, e) in &factors {
        if let Some(c) = f.leading_coeff() {
            den *= c.pow_u32(*e);
        }
    }
    let lc = p.leading_coeff().cloned().unwrap_or_else(Q::zero);
    let unit = lc.checked_div(&den).unwrap_or(lc);
    Factorization { unit, factors }
}

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

// ===========================================================================
// helpers on Poly
// ===========================================================================

/// Primitive integer polynomial with a positive leading coefficient.
fn normalize(p: &Poly) -> Poly {
    let q = p.primitive();
    match q.leading_coeff() {
        Some(c) if c.is_negative() => -q,
        _ => q,
    }
}

/// The content of `p` with respect to `v` (gcd of its coefficients in `v`),
/// normalized; free of `v`.
fn content_in(p: &Poly, v: Var) -> Poly {
    let mut cs = p.coeffs_in(v);
    cs.retain(|c| !c.is_zero());
    cs.sort_by_key(|c| c.len());
    let mut g = match cs.first() {
        Some(c) => c.clone(),
        None => return Poly::zero(),
    };
    for c in &cs[1..] {
        if g.is_constant() {
            break;
        }
        g = g.gcd(c);
    }
    if g.is_constant() {
        Poly::one()
    } else {
        normalize(&g)
    }
}

/// A deterministic total order on normalized polynomials (see
/// [`Factorization`]).
fn canonical_cmp(a: &Poly, b: &Poly) -> Ordering {
    a.total_degree()
        .cmp(&b.total_degree())
        .then(a.len().cmp(&b.len()))
        .then_with(|| {
            for (x, y) in a.terms().iter().zip(b.terms()) {
                let o = y.0.cmp(&x.0).then_with(|| x.1.cmp(&y.1));
                if o != Ordering::Equal {
                    return o;
                }
            }
            Ordering::Equal
        })
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

/// Factors a square-free primitive polynomial with positive leading
/// coefficient and no monomial content, pushing the irreducible factors.
fn factor_squarefree(g: &Poly, out: &mut Vec<Poly>) {
    if g.is_constant() {
        return;
    }
    let vars = g.vars();
    if vars.len() == 1 {
        let v = vars[0];
        for h in zassenhaus(&to_dense(g, v)) {
            out.push(from_dense(&h, v));
        }
        return;
    }
    for &v in &vars {
        let c = content_in(g, v);
        if !c.is_constant() {
            let pp = g.div_exact(&c).map(|q| normalize(&q));
            if let Some(pp) = pp {
                factor_squarefree(&c, out);
                factor_squarefree(&pp, out);
                return;
            }
        }
    }
    // primitive in every variable: degree 1 in one of them means irreducible
    if vars.iter().any(|&v| g.degree(v) == 1) {
        out.push(g.clone());
        return;
    }
    match hensel_factor(g, &vars) {
        Some(fs) => out.extend(fs),
        None => out.extend(kronecker_factor(g, &vars)),
    }
}

// ===========================================================================
// dense univariate polynomials over Z
// ===========================================================================

/// Dense coefficients, lowest degree first, no trailing zeros.
type ZPoly = Vec<BigInt>;

fn z_trim(a: &mut ZPoly) {
    while a.last().is_some_and(|c| c.is_zero()) {
        a.pop();
    }
}

fn deg_z(a: &ZPoly) -> usize {
    a.len().saturating_sub(1)
}

/// The integer coefficients of `p` in `v` (p must be univariate in `v` with
/// integer coefficients).
fn to_dense(p: &Poly, v: Var) -> ZPoly {
    let d = p.degree(v) as usize;
    let mut out = vec![BigInt::zero(); d + 1];
    for (m, c) in p.terms() {
        out[m.degree(v) as usize] = c.numer();
    }
    z_trim(&mut out);
    out
}

fn from_dense(a: &[BigInt], v: Var) -> Poly {
    Poly::from_terms(
        a.iter()
            .enumerate()
            .filter(|(_, c)| !c.is_zero())
            .map(|(i, c)| (Mono::var_pow(v, i as u32), Q::from_bigint(c.clone())))
            .collect(),
    )
}

fn z_mul(a: &[BigInt], b: &[BigInt]) -> ZPoly {
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

fn z_add(a: &[BigInt], b: &[BigInt]) -> ZPoly {
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

fn z_sub(a: &[BigInt], b: &[BigInt]) -> ZPoly {
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
fn z_mod(a: &[BigInt], m: &BigInt) -> ZPoly {
    let mut out: ZPoly = a.iter().map(|c| c.mod_floor(m)).collect();
    z_trim(&mut out);
    out
}

/// Coefficients reduced to the symmetric range `(−m/2, m/2]`.
fn z_sym(a: &[BigInt], m: &BigInt) -> ZPoly {
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

fn z_mulm(a: &[BigInt], b: &[BigInt], m: &BigInt) -> ZPoly {
    z_mod(&z_mul(a, b), m)
}

/// Division with remainder modulo `m` by `b` with leading coefficient 1
/// modulo `m`.
fn z_divrem_monic(a: &[BigInt], b: &[BigInt], m: &BigInt) -> (ZPoly, ZPoly) {
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
fn z_primitive(a: &[BigInt]) -> ZPoly {
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
fn z_div_exact(a: &[BigInt], b: &[BigInt]) -> Option<ZPoly> {
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

// ===========================================================================
// dense univariate polynomials over Z/p (p < 2^31)
// ===========================================================================

/// Dense coefficients in `[0, p)`, lowest degree first, no trailing zeros.
type Fp = Vec<u64>;

/// A distinct-degree factorization: `(product of the factors of degree d, d)`.
type Ddf = Vec<(Fp, usize)>;

fn deg_fp(a: &Fp) -> usize {
    a.len().saturating_sub(1)
}

fn fp_from_z(a: &[BigInt], p: u64) -> Fp {
    let pb = BigInt::from(p);
    let mut out: Fp = a
        .iter()
        .map(|c| c.mod_floor(&pb).to_u64().unwrap_or(0))
        .collect();
    trim(&mut out);
    out
}

fn z_from_fp(a: &[u64]) -> ZPoly {
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

fn fp_mul(a: &[u64], b: &[u64], p: u64) -> Fp {
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

fn fp_monic(a: &[u64], p: u64) -> Fp {
    match a.last() {
        None => Vec::new(),
        Some(&l) => fp_scale(a, invmod(l, p), p),
    }
}

fn fp_gcd(a: &[u64], b: &[u64], p: u64) -> Fp {
    let (mut a, mut b) = (a.to_vec(), b.to_vec());
    while !b.is_empty() {
        let r = fp_rem(&a, &b, p);
        a = b;
        b = r;
    }
    fp_monic(&a, p)
}

/// `(g, s, t)` with `s·a + t·b = g` monic.
fn fp_ext_gcd(a: &[u64], b: &[u64], p: u64) -> (Fp, Fp, Fp) {
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

fn fp_deriv(a: &[u64], p: u64) -> Fp {
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
fn fp_ddf(f: &[u64], p: u64) -> Ddf {
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
fn fp_edf(g: &[u64], d: usize, p: u64, rng: &mut XorShift64Star) -> Option<Vec<Fp>> {
    let n = deg_fp(&g.to_vec());
    if n == d {
        return Some(vec![g.to_vec()]);
    }
    let e: BigUint = (BigUint::from(p).pow(d as u32) - 1u32) >> 1usize;
    let nbits = e.bits();
    for _ in 0..64 {
        let mut a: Fp = (0..n).map(|_| rng.next() % p).collect();
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

/// Odd primes below [`PRIME_LIMIT`], ascending.
fn primes() -> impl Iterator<Item = u64> {
    (3..PRIME_LIMIT).step_by(2).filter(|&n| {
        (3..)
            .step_by(2)
            .take_while(|d| d * d <= n)
            .all(|d| n % d != 0)
    })
}

// ===========================================================================
// Zassenhaus
// ===========================================================================

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

/// The next `s`-subset of `0..n` in lexicographic order (in place).
fn next_combination(c: &mut [usize], n: usize) -> bool {
    let s = c.len();
    let mut i = s;
    while i > 0 {
        i -= 1;
        if c[i] < n - s + i {
            c[i] += 1;
            for j in i + 1..s {
                c[j] = c[j - 1] + 1;
            }
            return true;
        }
    }
    false
}

/// Irreducible factors over ℤ of a primitive square-free `f` with positive
/// leading coefficient (primitive, positive leading coefficients).
fn zassenhaus(f: &[BigInt]) -> Vec<ZPoly> {
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
    let mut rng = XorShift64Star(0x9E37_79B9_7F4A_7C15);
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
    recombine(f, lifted, &m, &allowed)
}

/// Zassenhaus recombination (MCA Alg. 15.19 with trial division): subsets of
/// the lifted monic factors, smallest first, each candidate
/// `pp(lc·∏ uᵢ mods m)` tested by the degree table, the constant term and
/// exact division.
fn recombine(f: &[BigInt], lifted: Vec<ZPoly>, m: &BigInt, allowed: &[bool]) -> Vec<ZPoly> {
    let mut t: Vec<usize> = (0..lifted.len()).collect();
    let mut fstar = f.to_vec();
    let mut out = Vec::new();
    let mut s = 1usize;
    while 2 * s <= t.len() {
        let mut found: Option<(Vec<usize>, ZPoly, ZPoly)> = None;
        let mut c: Vec<usize> = (0..s).collect();
        loop {
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

// ===========================================================================
// Kronecker
// ===========================================================================

/// Irreducible factors of a multivariate `g` (primitive in every variable,
/// square-free, no monomial content, positive leading coefficient) by
/// Kronecker's substitution (see the module docs).
fn kronecker_factor(g: &Poly, vars: &[Var]) -> Vec<Poly> {
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
        for h in zassenhaus(&to_dense(&part, y)) {
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
    while 2 * s <= t.len() {
        let degs: Vec<u32> = vars.iter().map(|&v| fstar.degree(v)).collect();
        let mut seen: FxHashSet<Vec<usize>> = FxHashSet::default();
        let mut found: Option<(Vec<usize>, usize, Poly, Poly)> = None;
        let mut c: Vec<usize> = (0..s).collect();
        'search: loop {
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

// ===========================================================================
// evaluation and Hensel lifting over Q[[y]] (several variables)
// ===========================================================================

/// Dense univariate polynomial over ℚ, lowest degree first, no trailing
/// zeros.
type QPoly = Vec<Q>;

fn q_trim(a: &mut QPoly) {
    while a.last().is_some_and(|c| c.is_zero()) {
        a.pop();
    }
}

fn q_mul(a: &[Q], b: &[Q]) -> QPoly {
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
fn q_divrem(a: &[Q], b: &[Q]) -> (QPoly, QPoly) {
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
fn q_inverse_mod(a: &[Q], m: &[Q]) -> Option<QPoly> {
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
    let mut rng = XorShift64Star(0x2545_F491_4F6C_DD1D ^ (k as u64).wrapping_mul(0x9E37_79B9));
    let r = 1 + (k as u64) / 4;
    (0..n)
        .map(|_| (rng.next() % (2 * r + 1)) as i64 - r as i64)
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
fn hensel_factor(g: &Poly, vars: &[Var]) -> Option<Vec<Poly>> {
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
        let fs = zassenhaus(&to_dense(&f0, x));
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
    while 2 * s <= t.len() {
        let lcf = fstar.coeffs_in(x).pop().unwrap_or_else(Poly::one);
        let mut found: Option<(Vec<usize>, Poly, Poly)> = None;
        let mut comb: Vec<usize> = (0..s).collect();
        loop {
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

#[cfg(test)]
mod tests {
    use super::*;

    fn x() -> Poly {
        Poly::var(0)
    }

    fn c(n: i64) -> Poly {
        Poly::constant(Q::from_i64(n))
    }

    #[test]
    fn mod_p_factorization_of_x4_plus_1() {
        // x^4 + 1 splits into two quadratics modulo 3
        let f: Fp = vec![1, 0, 0, 0, 1];
        let dd = fp_ddf(&f, 3);
        assert_eq!(dd.len(), 1);
        assert_eq!(dd[0].1, 2);
        let fs = fp_edf(&dd[0].0, 2, 3, &mut XorShift64Star(1)).expect("splits");
        assert_eq!(fs.len(), 2);
        assert_eq!(fp_mul(&fs[0], &fs[1], 3), f);
    }

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
            .flat_map(|(g, d)| fp_edf(&g, d, p, &mut XorShift64Star(3)).expect("splits"))
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
        let fs = recombine(&f, lifted, &m, &[true; 5]);
        assert_eq!(fs.len(), 4);
    }

    #[test]
    fn univariate_known_answers() {
        let f = &x().pow(2) - &c(1);
        let r = factor(&f);
        assert_eq!(r.factors.len(), 2);
        assert_eq!(r.factors[0].0, &x() - &c(1));
        assert_eq!(r.factors[1].0, &x() + &c(1));
        assert_eq!(r.expand(), f);
        // x^4 + 1 and x^4 - 10x^2 + 1 are irreducible over Q
        for f in [
            &x().pow(4) + &c(1),
            &(&x().pow(4) - &(&c(10) * &x().pow(2))) + &c(1),
        ] {
            let r = factor(&f);
            assert_eq!(r.factors, vec![(f.clone(), 1)]);
            assert_eq!(r.unit, Q::one());
        }
    }

    #[test]
    fn square_free_of_powers() {
        let a = &x() + &c(1);
        let b = &x() - &c(2);
        let f = &(&a.pow(3) * &b.pow(2)) * &c(-3);
        let sf = square_free(&f);
        assert_eq!(sf, vec![(b, 2), (a, 3)]);
    }

    fn parse2(terms: &[(i64, u32, u32)]) -> Poly {
        Poly::from_terms(
            terms
                .iter()
                .map(|&(c, i, j)| (Mono::from_pairs([(0, i), (1, j)]), Q::from_i64(c)))
                .collect(),
        )
    }

    #[test]
    fn kronecker_and_hensel_agree() {
        // x^4 - y^4 (after the linear factors: x^2 + y^2 irreducible) and
        // (x^2 + xy + y^2)(x^2 - xy + y^2) = x^4 + x^2 y^2 + y^4;
        // x^2 y^2 - 1 needs a nonzero evaluation point (lc_x = y^2)
        let cases = [
            (parse2(&[(1, 4, 0), (-1, 0, 4)]), 3),
            (parse2(&[(1, 4, 0), (1, 2, 2), (1, 0, 4)]), 2),
            (parse2(&[(1, 2, 2), (-1, 0, 0)]), 2),
            (parse2(&[(1, 2, 0), (1, 0, 2)]), 1),
        ];
        for (f, n) in cases {
            let vars = f.vars();
            let mut k = kronecker_factor(&f, &vars);
            let mut h = hensel_factor(&f, &vars).expect("a good point");
            k.sort_by(canonical_cmp);
            h.sort_by(canonical_cmp);
            assert_eq!(k.len(), n, "{f}");
            assert_eq!(k, h, "{f}");
            assert_eq!(k.iter().cloned().product::<Poly>(), f);
        }
    }
}
