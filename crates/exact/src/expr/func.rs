//! Elementary functions with exact rules.
//!
//! * `sin`/`cos` of a sum expand by the addition theorems, integer multiples
//!   by the multiple-angle formulas, so every trig atom has a *base angle*:
//!   a single monomial divided by a positive integer (`θ`, `θ/2`, `Ω·t`), or
//!   an irreducible non-polynomial argument. Multiples of π/12, π/10 and
//!   π/8 have exact values (`sin(π/6) = 1/2`, `cos(π/4) = √2/2`,
//!   `cos(π/5) = (1 + √5)/4`, `cos(π/8) = √(2 + √2)/2`).
//! * `sqrt` of a rational is a product of prime radicals `√p`
//!   (`√12 = 2√3`); of a polynomial, positive-parameter square factors come
//!   out (`√(k·m²) = m·√k`) and the rest is a radical atom `√P`.
//! * `exp`, `ln`, `atan`, `asin`, `acos` are atoms, with `exp(0) = 1`,
//!   `ln(1) = 0`, `ln(exp(x)) = x`, `atan(0) = asin(0) = 0`, `acos(0) = π/2`,
//!   and sin/cos of them algebraic: `sin(atan x) = x/√(1 + x²)`,
//!   `cos(asin x) = √(1 − x²)`, `sin(acos x) = √(1 − x²)`.
//!   An inverse-trig atom (to the first power) is a simple term of an
//!   argument, so `sin(atan x + π)` and `cos(2·asin x)` expand.

use super::atom::{self, Atom};
use super::{Expr, MathError};
use crate::num::Q;
use crate::poly::{Mono, Poly, Var};
use num_bigint::BigInt;
use num_traits::{One, Signed, ToPrimitive, Zero};
use rustc_hash::FxHashMap;
use std::sync::Arc;

/// Largest multiple of a base angle expanded by the multiple-angle formulas.
const MAX_MULTIPLE: i64 = 12;

/// Most terms of an argument expanded by the addition theorems; an argument
/// with more simple terms keeps them all together in one base angle.
const MAX_EXPANDED_TERMS: usize = 6;

/// Whether a term of an argument is expanded on its own: a power product of
/// parameters, coordinates, t and π (θ1, Ω·t, π/6), not of functions.
fn is_simple_term(m: &Mono) -> bool {
    if let [(v, 1)] = m.0.as_slice() {
        if inverse_trig(*v).is_some() {
            return true;
        }
    }
    m.0.iter().all(|&(v, _)| {
        matches!(
            atom::atom(v),
            Atom::Param(_) | Atom::Unknown(_) | Atom::Coord(..) | Atom::Time | Atom::Pi
        )
    })
}

/// Whether `u` is a base angle that integer multiples and sums of come
/// back to: one simple term m/q (`θ`, `θ/2`, `Ω·t`), so sin(k·u + …) is
/// expanded onto u again. The compact forms write multiple angles only
/// of such angles (their printed text must re-parse to the same value).
pub(crate) fn is_multiple_angle_base(u: &Expr) -> bool {
    if !u.is_poly() {
        return false;
    }
    match u.num().terms() {
        [(m, c)] => {
            !m.0.is_empty()
                && is_simple_term(m)
                && m.0.iter().all(|&(v, _)| inverse_trig(v).is_none())
                && c.numer() == BigInt::from(1)
        }
        _ => false,
    }
}

/// The largest multiple and the most angles in one argument that
/// [`sin_cos`] expands back exactly (the compact forms stay within them).
pub(crate) const MULTIPLE_ANGLE_BOUNDS: (i64, usize) = (MAX_MULTIPLE, MAX_EXPANDED_TERMS);

/// sin and cos of an inverse-trig atom, algebraically: (sin, cos) of
/// atan x = (x, 1)/√(1 + x²), of asin x = (x, √(1 − x²)), of acos x =
/// (√(1 − x²), x). None for any other atom (or a root that can't be taken).
fn inverse_trig(v: Var) -> Option<(Expr, Expr)> {
    match atom::atom(v) {
        Atom::Atan(x) => {
            let r = sqrt(&Expr::one().add(&x.mul(&x))).ok()?;
            Some((x.div(&r).ok()?, r.recip().ok()?))
        }
        Atom::Asin(x) => {
            let r = sqrt(&Expr::one().sub(&x.mul(&x))).ok()?;
            Some((x, r))
        }
        Atom::Acos(x) => {
            let r = sqrt(&Expr::one().sub(&x.mul(&x))).ok()?;
            Some((r, x))
        }
        _ => None,
    }
}

/// sin and cos of an expression, expanded into base-angle atoms.
///
/// A polynomial argument is split into its simple terms (see
/// `is_simple_term`), each expanded by the addition and multiple-angle
/// theorems, and the rest, which is kept as one base angle: `cos(θ1 − θ2)`
/// expands, `cos(y·cos x)` does not (expanding it would multiply the size of
/// the expression without making zero-testing any more complete).
pub fn sin_cos(u: &Expr) -> (Expr, Expr) {
    if u.is_zero() {
        return (Expr::zero(), Expr::one());
    }
    if !u.is_poly() {
        return base_sin_cos_signed(u);
    }
    let pi = atom::pi();
    let is_pi = |m: &Mono| m.0.len() == 1 && m.0[0] == (pi, 1);
    // All simple terms expand, or none: were only the first few expanded,
    // the printed atom of the rest would be an argument of few terms,
    // which reads back expanded, another canonical form.
    let simple = u
        .num()
        .terms()
        .iter()
        .filter(|(m, _)| !is_pi(m) && is_simple_term(m))
        .count();
    let expand = simple <= MAX_EXPANDED_TERMS;
    let mut s = Expr::zero();
    let mut c = Expr::one();
    let mut rest: Vec<(Mono, Q)> = Vec::new();
    for (m, coef) in u.num().terms() {
        let (ts, tc) = if is_pi(m) {
            pi_sin_cos(coef)
        } else if expand && is_simple_term(m) {
            term_sin_cos(m, coef)
        } else {
            rest.push((m.clone(), coef.clone()));
            continue;
        };
        (s, c) = add_angles(&s, &c, &ts, &tc);
    }
    if !rest.is_empty() {
        let r = Expr::poly(Poly::from_terms(rest));
        let (ts, tc) = base_sin_cos_signed(&r);
        (s, c) = add_angles(&s, &c, &ts, &tc);
    }
    (s, c)
}

/// sin and cos of a + b from those of a and b (the addition theorems).
fn add_angles(sa: &Expr, ca: &Expr, sb: &Expr, cb: &Expr) -> (Expr, Expr) {
    (sa.mul(cb).add(&ca.mul(sb)), ca.mul(cb).sub(&sa.mul(sb)))
}

/// Split a coefficient c = p/q of a term c·m into a base coefficient and a
/// multiple: (1/q, p) when |p| ≤ MAX_MULTIPLE and `multiples` allows it,
/// else (|c|, ±1). So sin(3θ/2) uses the base angle θ/2, three times.
pub(crate) fn split_multiple(c: &Q, multiples: bool) -> (Q, i64) {
    let p = c.numer();
    if multiples && p.abs() <= BigInt::from(MAX_MULTIPLE) {
        let base = Q::one()
            .checked_div(&Q::from_bigint(c.denom()))
            .unwrap_or_else(Q::one);
        return (base, p.to_i64().unwrap_or(1));
    }
    if c.is_negative() {
        (-c.clone(), -1)
    } else {
        (c.clone(), 1)
    }
}

/// sin u, expanded into base-angle atoms (exact at multiples of π/12, π/10, π/8).
pub fn sin(u: &Expr) -> Expr {
    sin_cos(u).0
}
/// cos u, expanded into base-angle atoms (exact at multiples of π/12, π/10, π/8).
pub fn cos(u: &Expr) -> Expr {
    sin_cos(u).1
}
/// tan u = sin u / cos u; an error where cos u is zero.
pub fn tan(u: &Expr) -> Result<Expr, MathError> {
    let (s, c) = sin_cos(u);
    s.div(&c)
        .map_err(|_| MathError::new("tan is undefined here: cos of its argument is zero"))
}

/// sin and cos of k·π for a rational k, however large: k is reduced
/// modulo 2 exactly, then into [0, 1/2] by sin(−φ) = −sin φ and
/// sin(π − φ) = sin φ, cos(π − φ) = −cos φ, so equal angles (and
/// supplementary ones) give one canonical form.
fn pi_sin_cos(k: &Q) -> (Expr, Expr) {
    let k = reduce_pi_multiple(k);
    if is_twelfth(&k) {
        return exact_pi(&k);
    }
    let (k, sin_sign) = if k.is_negative() { (-k, -1) } else { (k, 1) };
    let half = Q::new(1, 2).unwrap_or_else(Q::one);
    let (k, cos_sign) = if k > half {
        (&Q::one() - &k, -1)
    } else {
        (k, 1)
    };
    let (s, c) = match exact_tenth_or_eighth(&k) {
        Some(sc) => sc,
        None => term_sin_cos(&Mono::var_pow(atom::pi(), 1), &k),
    };
    (
        if sin_sign < 0 { s.neg() } else { s },
        if cos_sign < 0 { c.neg() } else { c },
    )
}

/// k − 2·j for the integer j that puts the result in (−1, 1]: the same
/// angle k·π modulo 2π, computed on big integers (k = p/q: p mod 2q).
pub fn reduce_pi_multiple(k: &Q) -> Q {
    let q = k.denom();
    let two_q: BigInt = &q * 2u32;
    let mut r = k.numer() % &two_q;
    if r.is_negative() {
        r += &two_q;
    }
    if r > q {
        r -= &two_q;
    }
    Q::from_bigint(r)
        .checked_div(&Q::from_bigint(q))
        .unwrap_or_else(Q::zero)
}

fn is_twelfth(q: &Q) -> bool {
    (q * &Q::from_i64(12)).is_integer()
}

/// Whether sin(k·π) and cos(k·π) have exact values here: k a multiple of
/// 1/12, 1/10 or 1/8 (the angles of the hexagon, the pentagon and the
/// octagon). Other constant angles are atoms.
pub(crate) fn has_exact_value(k: &Q) -> bool {
    [12, 10, 8]
        .iter()
        .any(|&n| (k * &Q::from_i64(n)).is_integer())
}

/// sin, cos of k·π for k in (0, 1/2) a multiple of 1/10 or 1/8 (and not of
/// 1/12), in radicals over ℚ(√5, √(5 − √5)) and ℚ(√2, √(2 + √2)):
/// cos(π/5) = (1 + √5)/4, sin(π/5) = √2·√(5 − √5)/4, sin(π/10) =
/// (√5 − 1)/4, cos(π/8) = √(2 + √2)/2, sin(π/8) = (√2 − 1)·√(2 + √2)/2.
/// In each field the products of the radicals are a basis (√(5 − √5) is
/// not in ℚ(√2, √5), √(2 + √2) not in ℚ(√2)), so the canonical form decides
/// every identity between these values (cos(π/5) − cos(2π/5) = 1/2).
fn exact_tenth_or_eighth(k: &Q) -> Option<(Expr, Expr)> {
    static TABLE: std::sync::OnceLock<Option<[(Expr, Expr); 6]>> = std::sync::OnceLock::new();
    let table = TABLE.get_or_init(|| {
        let q = |n, d| Expr::rational(Q::new(n, d).unwrap_or_else(Q::one));
        let (r2, r5) = (
            sqrt_rational(&Q::from_i64(2)),
            sqrt_rational(&Q::from_i64(5)),
        );
        let pentagon = sqrt(&Expr::int(5).sub(&r5)).ok()?; // √(5 − √5)
        let octagon = sqrt(&Expr::int(2).add(&r2)).ok()?; // √(2 + √2)
        let sin_fifth = r2.mul(&pentagon).mul(&q(1, 4));
        let cos_fifth = r5.add(&Expr::one()).mul(&q(1, 4));
        let sin_tenth = r5.sub(&Expr::one()).mul(&q(1, 4));
        let cos_tenth = sin_fifth.mul(&r5.add(&Expr::one())).mul(&q(1, 2));
        let cos_eighth = octagon.mul(&q(1, 2));
        let sin_eighth = r2.sub(&Expr::one()).mul(&cos_eighth);
        Some([
            (sin_tenth.clone(), cos_tenth.clone()),   // π/10
            (sin_fifth.clone(), cos_fifth.clone()),   // π/5
            (cos_fifth, sin_fifth),                   // 3π/10
            (cos_tenth, sin_tenth),                   // 2π/5
            (sin_eighth.clone(), cos_eighth.clone()), // π/8
            (cos_eighth, sin_eighth),                 // 3π/8
        ])
    });
    let table = table.as_ref()?;
    let ten = k * &Q::from_i64(10);
    let eight = k * &Q::from_i64(8);
    let row = match (ten.as_i64(), eight.as_i64()) {
        (Some(j @ 1..=4), _) => j as usize - 1,
        (_, Some(1)) => 4,
        (_, Some(3)) => 5,
        _ => return None,
    };
    Some(table[row].clone())
}

/// sin, cos of (k·π) where 12k is an integer and k ∈ (−1, 1] (reduced by
/// [`reduce_pi_multiple`], so 12k fits an i64).
fn exact_pi(k: &Q) -> (Expr, Expr) {
    debug_assert!(k.abs() <= Q::one(), "exact_pi takes a reduced multiple");
    let n = (k * &Q::from_i64(12))
        .as_i64()
        .unwrap_or(0) // ok: |12k| ≤ 12 after reduction
        .rem_euclid(24);
    (sin_twelfths(n), sin_twelfths((n + 6) % 24))
}

/// sin(n·π/12), exactly (the 13 values for n = 0…12 are built once).
fn sin_twelfths(n: i64) -> Expr {
    static TABLE: std::sync::OnceLock<Vec<Expr>> = std::sync::OnceLock::new();
    let n = n.rem_euclid(24);
    let (n, neg) = if n >= 12 { (n - 12, true) } else { (n, false) };
    let table = TABLE.get_or_init(|| {
        let r2 = sqrt_rational(&Q::from_i64(2));
        let r3 = sqrt_rational(&Q::from_i64(3));
        let r6 = sqrt_rational(&Q::from_i64(6));
        let quarter = Q::new(1, 4).unwrap_or_else(Q::one);
        let half = Q::new(1, 2).unwrap_or_else(Q::one);
        let first = [
            Expr::zero(),
            r6.sub(&r2).scale(&quarter),
            Expr::rational(half.clone()),
            r2.scale(&half),
            r3.scale(&half),
            r6.add(&r2).scale(&quarter),
            Expr::one(),
        ];
        (0..=12)
            .map(|k| first[if k > 6 { 12 - k } else { k }].clone())
            .collect()
    });
    let v = table[n as usize].clone();
    if neg {
        v.neg()
    } else {
        v
    }
}

/// sin, cos of one term `coef·m` of a polynomial argument.
fn term_sin_cos(m: &Mono, coef: &Q) -> (Expr, Expr) {
    // coef = p/q; base angle m/q, multiple p (when small).
    let (base_coef, mult) = split_multiple(coef, !m.0.is_empty());
    let base = Expr::poly(Poly::monomial(m.clone(), base_coef));
    let (s1, c1) = intern_base(&base);
    multiple(&s1, &c1, mult)
}

/// sin(n·x), cos(n·x) from sin x, cos x.
fn multiple(s1: &Expr, c1: &Expr, n: i64) -> (Expr, Expr) {
    // A rotation by −x is (cos x, −sin x).
    let s1 = if n < 0 { s1.neg() } else { s1.clone() };
    let n = n.unsigned_abs();
    let mut s = Expr::zero();
    let mut c = Expr::one();
    // Binary powering of the rotation (c + i s).
    let (mut bs, mut bc) = (s1, c1.clone());
    let mut k = n;
    while k > 0 {
        if k & 1 == 1 {
            (s, c) = add_angles(&s, &c, &bs, &bc);
        }
        k >>= 1;
        if k > 0 {
            let ns = bs.mul(&bc).scale(&Q::from_i64(2));
            let nc = bc.mul(&bc).sub(&bs.mul(&bs));
            bs = ns;
            bc = nc;
        }
    }
    (s, c)
}

/// Whether `u` is the negative of the argument an atom keeps: its first
/// term in the history-independent order ([`atom::leads_negative_stable`]),
/// over its denominator's, is negative. Never the ids' order: the atom made
/// (`sin(x·y − z)` or `−sin(z − x·y)`) would depend on what the process
/// interned first.
fn negative_lead(u: &Expr) -> bool {
    atom::leads_negative_stable(u.num()) != atom::leads_negative_stable(u.den())
}

/// sin, cos of a non-polynomial argument: an atom pair, with the sign of
/// the argument normalized ([`negative_lead`]).
fn base_sin_cos_signed(u: &Expr) -> (Expr, Expr) {
    if negative_lead(u) {
        let (s, c) = intern_base(&u.neg());
        (s.neg(), c)
    } else {
        intern_base(u)
    }
}

fn intern_base(u: &Expr) -> (Expr, Expr) {
    if let Some(v) = u.as_var() {
        if let Some(sc) = inverse_trig(v) {
            return sc;
        }
    }
    let (s, c) = atom::intern_trig(u);
    (Expr::var(s), Expr::var(c))
}

// ---------------------------------------------------------------- radicals

/// Factor n > 0 as (square part s, square-free part r): n = s²·r, with the
/// primes of r found by trial division (a large unfactored cofactor that is
/// not a perfect square stays in r as one number).
fn square_free(n: &BigInt) -> (BigInt, Vec<BigInt>) {
    let mut n = n.clone();
    let mut s = BigInt::one();
    let mut primes = Vec::new();
    let mut p = BigInt::from(2u32);
    let limit = BigInt::from(100_000u32);
    while &p * &p <= n && p <= limit {
        let mut e = 0u32;
        while (&n % &p).is_zero() {
            n /= &p;
            e += 1;
        }
        for _ in 0..e / 2 {
            s *= &p;
        }
        if e % 2 == 1 {
            primes.push(p.clone());
        }
        p += if p == BigInt::from(2u32) { 1u32 } else { 2u32 };
    }
    if n > BigInt::one() {
        let r = n.sqrt();
        if &r * &r == n {
            s *= r;
        } else {
            primes.push(n);
        }
    }
    (s, primes)
}

/// √q for a rational q ≥ 0 (an error for q < 0).
pub fn sqrt_q(q: &Q) -> Result<Expr, MathError> {
    if q.is_negative() {
        return Err(
            MathError::new(format!("square root of the negative number {q}"))
                .hint("qdot works over the reals"),
        );
    }
    Ok(sqrt_rational(q))
}

fn sqrt_rational(q: &Q) -> Expr {
    if q.is_zero() {
        return Expr::zero();
    }
    type Cache = std::sync::RwLock<FxHashMap<Q, Expr>>;
    static CACHE: std::sync::OnceLock<Cache> = std::sync::OnceLock::new();
    let cache = CACHE.get_or_init(Default::default);
    if let Some(e) = cache.read().ok().and_then(|c| c.get(q).cloned()) {
        return e;
    }
    let e = sqrt_rational_uncached(q);
    if let Ok(mut c) = cache.write() {
        if c.len() < 4096 {
            c.insert(q.clone(), e.clone());
        }
    }
    e
}

fn sqrt_rational_uncached(q: &Q) -> Expr {
    // √(a/b) = √(a·b)/b
    let a = q.numer().abs();
    let b = q.denom();
    let (s, primes) = square_free(&(&a * &b));
    let mut out = Expr::rational(
        Q::from_bigint(s)
            .checked_div(&Q::from_bigint(b))
            .unwrap_or_else(Q::one),
    );
    for p in primes {
        let v = atom::intern_radical(
            Atom::Root(Arc::from(p.to_string())),
            Poly::constant(Q::from_bigint(p)),
        );
        out = out.mul(&Expr::var(v));
    }
    out
}

/// Whether a variable stands for a positive quantity (a parameter, π, a
/// positive radical), so its square root may be taken out of a radical.
fn is_positive_atom(v: Var) -> bool {
    matches!(atom::atom(v), Atom::Param(_) | Atom::Pi)
}

/// √u, exactly.
pub fn sqrt(u: &Expr) -> Result<Expr, MathError> {
    if let Some(q) = u.as_rational() {
        return sqrt_q(&q);
    }
    // √(n/d) = √(n·d)/d
    let nd = &(u.num() * u.den()) * &Poly::one();
    // numeric content
    let content = nd.content();
    let mut prim = nd.scale(&Q::one().checked_div(&content).unwrap_or_else(Q::one));
    let mut outside = sqrt_rational(&content);
    // a negative leading coefficient stays inside: √(−x) is √(−x).
    // monomial content of positive atoms
    let mut mono_gcd: Option<Mono> = None;
    for (m, _) in prim.terms() {
        mono_gcd = Some(match mono_gcd {
            None => m.clone(),
            Some(g) => g.gcd(m),
        });
    }
    if let Some(g) = mono_gcd {
        let mut take = Mono::default();
        for &(v, e) in g.0.iter() {
            if is_positive_atom(v) {
                // √(a^e) = a^(e div 2)·√a for a positive atom a.
                take.0.push((v, e));
                if e >= 2 {
                    outside = outside.mul(&Expr::poly(Poly::monomial(
                        Mono(std::iter::once((v, e / 2)).collect()),
                        Q::one(),
                    )));
                }
                if e % 2 == 1 {
                    outside = outside.mul(&positive_atom_sqrt(v));
                }
            }
        }
        if !take.0.is_empty() {
            let divisor = Poly::monomial(take, Q::one());
            if let Some(p) = prim.div_exact(&divisor) {
                prim = p;
            }
        }
    }
    if certainly_negative(&prim) {
        return Err(
            MathError::new(format!("square root of a negative quantity: {} < 0", u))
                .hint("qdot works over the reals, and parameters are positive"),
        );
    }
    let inner = if prim.is_one() {
        Expr::one()
    } else if let Some(r) = perfect_square_monomial(&prim) {
        r
    } else {
        let v = atom::intern_radical(Atom::SqrtOf(Expr::from_poly(prim.clone())), prim);
        Expr::var(v)
    };
    outside.mul(&inner).div(&abs_of_denominator(u.den()))
}

/// |d| for a canonical denominator d, the divisor of √(n/d) = √(n·d)/|d|:
/// d itself when it is positive (monomials in parameters, and sums of
/// them), −d when it is negative, else √(d²) — the sign of a denominator
/// such as g·M − 6·k·l is not known, and taking it positive would flip
/// the root's sign where it is negative.
fn abs_of_denominator(d: &Poly) -> Expr {
    let neg = -d;
    if d.is_one() || certainly_negative(&neg) {
        Expr::from_poly(d.clone())
    } else if certainly_negative(d) {
        Expr::from_poly(neg)
    } else {
        // |c·p| = |c|·√(p²) with p primitive: the root shows as |g·M − 6·k·l|.
        // √(p²) is taken by `sqrt` itself, so that it takes out what `sqrt`
        // takes out (a parameter's powers, √(a⁴·q) = a²·√q) and reads back
        // as the same expression when printed and parsed again.
        let c = d.content().abs();
        let p = d.scale(&Q::one().checked_div(&c).unwrap_or_else(Q::one));
        // p may hold radicals or cosines: its square is reduced like any
        // polynomial before it is an expression
        let square = super::reduced(&p * &p);
        match sqrt(&Expr::poly(square.clone())) {
            Ok(root) => root.scale(&c),
            // p² ≥ 0 is never certainly negative; were it refused, √(p²)
            // as an atom is still |p|
            Err(_) => {
                let v = atom::intern_radical(Atom::SqrtOf(Expr::from_poly(square.clone())), square);
                Expr::var(v).scale(&c)
            }
        }
    }
}

/// Whether p < 0 wherever it is defined: every term is ≤ 0 (a negative
/// coefficient times positive atoms and even powers of anything) and one
/// is < 0 (positive atoms only). So −a, −a − b and −x² − 1 are, −x² is not.
fn certainly_negative(p: &Poly) -> bool {
    let mut strict = false;
    for (m, c) in p.terms() {
        if !c.is_negative() {
            return false;
        }
        let mut positive = true;
        for &(v, e) in m.0.iter() {
            if !is_positive_atom(v) {
                if e % 2 != 0 {
                    return false;
                }
                positive = false;
            }
        }
        strict |= positive;
    }
    strict
}

/// √a for a positive atom a (a parameter or π; √(√p) is not simplified).
fn positive_atom_sqrt(v: Var) -> Expr {
    let a = Expr::var(v);
    let r = atom::intern_radical(Atom::SqrtOf(a), Poly::var(v));
    Expr::var(r)
}

/// √m for a monomial m with only even exponents of positive atoms.
fn perfect_square_monomial(p: &Poly) -> Option<Expr> {
    if p.len() != 1 {
        return None;
    }
    let (m, c) = &p.terms()[0];
    if !c.is_one() {
        return None;
    }
    let mut half = Mono::default();
    for &(v, e) in m.0.iter() {
        if e % 2 != 0 || !is_positive_atom(v) {
            return None;
        }
        half.0.push((v, e / 2));
    }
    Some(Expr::poly(Poly::monomial(half, Q::one())))
}

// ---------------------------------------------------------------- exp, ln, atan

/// eᵘ: exp(0) = 1, exp(ln x) = x; a polynomial exponent gives a product of
/// powers of exp atoms.
pub fn exp(u: &Expr) -> Expr {
    if u.is_zero() {
        return Expr::one();
    }
    if let Some(v) = u.as_var() {
        if let Atom::Ln(inner) = atom::atom(v) {
            return inner;
        }
    }
    if !u.is_poly() {
        // exp(−u) = 1/exp(u): the atom's argument is the one [`negative_lead`] keeps.
        if negative_lead(u) {
            return exp_atom(&u.neg()).recip().unwrap_or_else(|_| Expr::one());
        }
        return exp_atom(u);
    }
    // exp(Σ c·m) = Π exp(m/q)^p for c = p/q: products and powers of base atoms.
    let mut out = Expr::one();
    for (m, c) in u.num().terms() {
        let (base_coef, mult) = split_multiple(c, true);
        let base = exp_atom(&Expr::poly(Poly::monomial(m.clone(), base_coef)));
        if let Ok(f) = base.powi(mult) {
            out = out.mul(&f);
        }
    }
    out
}

fn exp_atom(u: &Expr) -> Expr {
    Expr::var(atom::intern(Atom::Exp(u.clone())))
}

/// ln u: ln 1 = 0, ln(exp x) = x, otherwise an atom; an error for 0 or a
/// negative number.
pub fn ln(u: &Expr) -> Result<Expr, MathError> {
    if u.is_zero() {
        return Err(MathError::new("ln(0) is undefined"));
    }
    if u.is_one() {
        return Ok(Expr::zero());
    }
    if let Some(q) = u.as_rational() {
        if q.is_negative() {
            return Err(MathError::new(format!("ln of the negative number {q}")));
        }
    }
    if let Some(v) = u.as_var() {
        if let Atom::Exp(inner) = atom::atom(v) {
            return Ok(inner);
        }
    }
    Ok(Expr::var(atom::intern(Atom::Ln(u.clone()))))
}

/// atan u (principal value): exact at multiples of π/12 (atan 1 = π/4),
/// atan(−u) = −atan u, otherwise an atom.
pub fn atan(u: &Expr) -> Expr {
    if u.is_zero() {
        return Expr::zero();
    }
    if negative_lead(u) {
        return atan(&u.neg()).neg();
    }
    if let Some(k) = exact_angle(u, -5..=5, tan_twelfths) {
        return k;
    }
    Expr::var(atom::intern(Atom::Atan(u.clone())))
}

/// tan(n·π/12) for n = 1…5.
fn tan_twelfths(n: i64) -> Expr {
    sin_twelfths(n)
        .div(&sin_twelfths(n + 6))
        .unwrap_or_else(|_| Expr::zero())
}

/// The angle n·π/12 (n in `range`) whose `f` value is `u`, if any: the
/// exact values of atan, asin and acos at the table's points (atan 1 = π/4,
/// asin(1/2) = π/6, acos(−√3/2) = 5π/6, atan(√3 − 2) = −π/12).
fn exact_angle(
    u: &Expr,
    range: std::ops::RangeInclusive<i64>,
    f: impl Fn(i64) -> Expr,
) -> Option<Expr> {
    if !u
        .vars()
        .iter()
        .all(|&v| matches!(atom::atom(v), Atom::Root(_)))
    {
        return None;
    }
    range
        .filter(|&n| n != 0)
        .find(|&n| f(n).equals(u))
        .map(|n| Expr::pi().scale(&Q::new(n, 12).unwrap_or_else(Q::one)))
}

/// asin u (principal value); an error for a rational |u| > 1.
pub fn asin(u: &Expr) -> Result<Expr, MathError> {
    if u.is_zero() {
        return Ok(Expr::zero());
    }
    if negative_lead(u) {
        return Ok(asin(&u.neg())?.neg());
    }
    if let Some(q) = u.as_rational() {
        if q > Q::one() {
            return Err(MathError::new(format!("asin({q}) is not real: |x| > 1")));
        }
    }
    if let Some(k) = exact_angle(u, -6..=6, sin_twelfths) {
        return Ok(k);
    }
    Ok(Expr::var(atom::intern(Atom::Asin(u.clone()))))
}

/// acos u = π/2 − asin u, kept as its own atom (principal value in [0, π]).
pub fn acos(u: &Expr) -> Result<Expr, MathError> {
    if let Some(q) = u.as_rational() {
        if q.abs() > Q::one() {
            return Err(MathError::new(format!("acos({q}) is not real: |x| > 1")));
        }
        if q.is_zero() || q.abs().is_one() {
            let half = Q::new(1, 2).unwrap_or_else(Q::one);
            let k = if q.is_zero() {
                half
            } else if q.is_one() {
                Q::zero()
            } else {
                Q::one()
            };
            return Ok(Expr::pi().scale(&k));
        }
    }
    if negative_lead(u) {
        // acos(−x) = π − acos x
        return Ok(Expr::pi().sub(&acos(&u.neg())?));
    }
    if let Some(k) = exact_angle(u, 1..=11, |n| sin_twelfths(n + 6)) {
        return Ok(k);
    }
    Ok(Expr::var(atom::intern(Atom::Acos(u.clone()))))
}

// ---------------------------------------------------------------- evaluation, substitution

/// The numeric value of an atom, with `f` giving parameters, coordinates and time.
pub fn eval_atom(v: Var, f: &dyn Fn(&Atom) -> Option<f64>) -> Option<f64> {
    let a = atom::atom(v);
    let ev = |e: &Expr| e.eval_f64(f);
    match &a {
        Atom::Param(_)
        | Atom::Unknown(_)
        | Atom::Named(_)
        | Atom::Coord(..)
        | Atom::Given(..)
        | Atom::Time => f(&a),
        Atom::Pi => Some(std::f64::consts::PI),
        Atom::Root(n) => n.parse::<f64>().ok().map(f64::sqrt),
        Atom::SqrtOf(u) => ev(u).map(f64::sqrt),
        Atom::Sin(u) => ev(u).map(f64::sin),
        Atom::Cos(u) => ev(u).map(f64::cos),
        Atom::Exp(u) => ev(u).map(f64::exp),
        Atom::Ln(u) => ev(u).map(f64::ln),
        Atom::Atan(u) => ev(u).map(f64::atan),
        Atom::Asin(u) => ev(u).map(f64::asin),
        Atom::Acos(u) => ev(u).map(f64::acos),
        Atom::Shown(..) | Atom::Group(_) => None,
    }
}

/// The value of atom `v` after substituting `map` (None: unchanged).
pub fn subs_atom(v: Var, map: &FxHashMap<Var, Expr>) -> Result<Option<Expr>, MathError> {
    if let Some(x) = map.get(&v) {
        return Ok(Some(x.clone()));
    }
    let a = atom::atom(v);
    let Some(inner) = a.argument() else {
        return Ok(None);
    };
    if !inner
        .vars()
        .iter()
        .any(|w| map.contains_key(w) || super::diff::atom_depends_on_any(*w, map))
    {
        return Ok(None);
    }
    let u = inner.subs_many(map)?;
    #[deny(
        clippy::wildcard_enum_match_arm,
        clippy::match_wildcard_for_single_variants
    )]
    let value = match &a {
        Atom::SqrtOf(_) => sqrt(&u)?,
        Atom::Sin(_) => sin(&u),
        Atom::Cos(_) => cos(&u),
        Atom::Exp(_) => exp(&u),
        Atom::Ln(_) => ln(&u)?,
        Atom::Asin(_) => asin(&u)?,
        Atom::Acos(_) => acos(&u)?,
        Atom::Atan(_) => atan(&u),
        // no argument: returned unchanged above
        Atom::Param(_)
        | Atom::Unknown(_)
        | Atom::Named(_)
        | Atom::Coord(..)
        | Atom::Given(..)
        | Atom::Time
        | Atom::Pi
        | Atom::Root(_)
        | Atom::Shown(_)
        | Atom::Group(_) => return Ok(None),
    };
    Ok(Some(value))
}
