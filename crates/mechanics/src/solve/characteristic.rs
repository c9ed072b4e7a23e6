//! The characteristic polynomial of small oscillations and its roots
//! λ = ω², exactly.
//!
//! Without velocity terms, or with damping (C symmetric), the polynomial is
//! det(K − λ·M). With gyroscopic terms (C skew: a spinning rotor, a
//! rotating frame, a magnetic field) q = u·e^{s·t} gives
//! det(K + s·C + s²·M) = 0, a polynomial in s² (the determinant of a
//! matrix and of its transpose, K − s·C + s²·M, agree), and ω² = −s² = λ.
//!
//! The roots come from the full factorization over ℚ (with the parameters,
//! `crate::poly::factor`): every irreducible factor of degree 1 or 2 in λ is
//! solved exactly (a quadratic one with its radical), a biquadratic one
//! (c₀ + c₂·λ² + c₄·λ⁴) by λ² = u, λ = ±√u. An irreducible cubic with three
//! real roots has no expression in real radicals (casus irreducibilis), and
//! nothing of higher degree is attempted: then [`Roots::why`] says so, and
//! the numeric values under `--set` stand in.

use super::equilibrium::quadratic;
use crate::algebra::linear::det;
use crate::algebra::sign::{sign_of, Sign, Values};
use crate::expr::atom::{self, Atom};
use crate::expr::{func, Expr};
use crate::num::Q;
use crate::poly::Var;

/// The roots λ of the characteristic polynomial.
pub(super) struct Roots {
    /// λ = ω², each as often as its multiplicity; empty if one has no
    /// closed form.
    pub(super) roots: Vec<Expr>,
    /// The factors over ℚ (the constant content first when it is not 1).
    pub(super) factors: Vec<Expr>,
    /// Why there is no closed form (when `roots` is empty).
    pub(super) why: Option<String>,
}

/// The name of s in det(K + s·C + s²·M) while it is expanded.
const S: &str = "s_characteristic";

/// det(K − λ·M) in `lv`, or with a skew C (gyroscopic) det(K + s·C + s²·M)
/// at s² = −λ. `None` when the determinant fails, or when C's polynomial
/// has odd powers of s (C not skew).
pub(super) fn polynomial(
    k: &[Vec<Expr>],
    m: &[Vec<Expr>],
    gyroscopic: Option<&[Vec<Expr>]>,
    lv: Var,
) -> Option<Expr> {
    let n = k.len();
    let lambda = Expr::var(lv);
    let Some(g) = gyroscopic else {
        let a = (0..n)
            .map(|i| (0..n).map(|j| k[i][j].sub(&lambda.mul(&m[i][j]))).collect())
            .collect();
        return det(a);
    };
    let (coefficients, den) = pencil(m, g, k)?;
    let minus_lambda = lambda.neg();
    let mut p = Expr::zero();
    let mut power = Expr::one();
    for (i, c) in coefficients.into_iter().enumerate() {
        if i % 2 == 1 {
            if !c.is_zero() {
                return None;
            }
            continue;
        }
        if i > 0 {
            power = power.mul(&minus_lambda);
        }
        p = p.add(&Expr::from_poly(c).mul(&power));
    }
    p.div(&den).ok()
}

/// det(K + s·C + s²·M) as its numerator's coefficients in s (lowest
/// first) and its denominator; `None` when the determinant fails or its
/// denominator holds s.
pub(super) fn pencil(
    m: &[Vec<Expr>],
    c: &[Vec<Expr>],
    k: &[Vec<Expr>],
) -> Option<(Vec<crate::poly::Poly>, Expr)> {
    let n = m.len();
    let sv = atom::unknown(S);
    let s = Expr::var(sv);
    let s2 = s.mul(&s);
    let a = (0..n)
        .map(|i| {
            (0..n)
                .map(|j| k[i][j].add(&s.mul(&c[i][j])).add(&s2.mul(&m[i][j])))
                .collect()
        })
        .collect();
    let d = det(a)?;
    if d.den().contains_var(sv) {
        return None;
    }
    Some((d.num().coeffs_in(sv), Expr::from_poly(d.den().clone())))
}

/// The cubic discriminant 18abcd − 4b³d + b²c² − 4ac³ − 27a²d² of
/// a·x³ + b·x² + c·x + d.
pub(super) fn cubic_discriminant(a: &Expr, b: &Expr, c: &Expr, d: &Expr) -> Expr {
    let q = |n: i64| Q::from_i64(n);
    a.mul(b)
        .mul(c)
        .mul(d)
        .scale(&q(18))
        .sub(&b.mul(b).mul(b).mul(d).scale(&q(4)))
        .add(&b.mul(b).mul(c).mul(c))
        .sub(&a.mul(c).mul(c).mul(c).scale(&q(4)))
        .sub(&a.mul(a).mul(d).mul(d).scale(&q(27)))
}

/// The roots λ of `p` (a polynomial in `lv`) and its factors; `real` when
/// every root is known to be real (K and M symmetric, no gyroscopic terms).
pub(super) fn roots(p: &Expr, lv: Var, real: bool, set: &Values) -> Roots {
    if let Some((roots, mut factors)) = lambda_roots(p, lv).or_else(|| lambda_roots_factored(p, lv))
    {
        signed_by_name(&mut factors, lv);
        return Roots {
            roots,
            factors,
            why: None,
        };
    }
    let (mut factors, why) = unsolved(p, lv, real, set);
    signed_by_name(&mut factors, lv);
    Roots {
        roots: Vec::new(),
        factors,
        why: Some(why),
    }
}

/// Each factor in λ signed as the printers write a polynomial in λ,
/// lowest power first: its lowest coefficient positive (k − 6·m·λ,
/// k + m·λ); when that coefficient has terms of both signs, its first term
/// by name positive. The factorization's own sign follows the atoms'
/// interning order, which would make the output depend on what the
/// process parsed before. The constant content takes the signs given up,
/// so the product is unchanged.
fn signed_by_name(factors: &mut Vec<Expr>, lv: Var) {
    let mut flips = 0;
    for f in factors.iter_mut() {
        if !f.depends_on(lv) {
            continue;
        }
        let cs = f.num().coeffs_in(lv);
        let Some(low) = cs.iter().find(|c| !c.is_zero()) else {
            continue;
        };
        let positive = low.terms().iter().any(|(_, c)| c.is_positive());
        let negative = low.terms().iter().any(|(_, c)| c.is_negative());
        let flip = if positive && negative {
            crate::expr::print::leads_negative(low)
        } else {
            negative
        };
        if flip != crate::expr::print::leads_negative(f.den()) {
            *f = f.neg();
            flips += 1;
        }
    }
    if flips % 2 == 1 {
        match factors.first_mut() {
            Some(c) if !c.depends_on(lv) => *c = c.neg(),
            _ => factors.insert(0, Expr::int(-1)),
        }
    }
}

/// The factors of a polynomial whose roots have no closed form here, and
/// why: the first factor that has none, described.
fn unsolved(p: &Expr, lv: Var, real: bool, set: &Values) -> (Vec<Expr>, String) {
    let mut factors = Vec::new();
    let mut why = String::from("no closed form for its roots");
    let mut found = false;
    for (f, mult) in atom::stable_factorization(crate::poly::factor::factor(p.num())).factors {
        let cs: Vec<Expr> = f.coeffs_in(lv).into_iter().map(Expr::from_poly).collect();
        if cs.len() <= 1 {
            continue;
        }
        for _ in 0..mult {
            factors.push(Expr::from_poly(f.clone()));
        }
        if found {
            continue;
        }
        let described = describe(&cs, real, set);
        if let Some(d) = described {
            why = d;
            found = true;
        }
    }
    if factors.len() == 1 {
        factors.clear(); // irreducible: the polynomial itself
    } else {
        with_content(p, &mut factors);
    }
    (factors, why)
}

/// Why the roots of the irreducible factor Σ cs[i]·λ^i are not given, or
/// `None` for a factor whose roots are solved.
fn describe(cs: &[Expr], real: bool, set: &Values) -> Option<String> {
    match cs.len() - 1 {
        0 | 1 => None,
        2 => {
            let disc = cs[1]
                .mul(&cs[1])
                .sub(&cs[0].mul(&cs[2]).scale(&Q::from_i64(4)));
            (sign_of(&disc, set) == Some(Sign::Negative))
                .then(|| "a quadratic factor has complex roots λ".to_string())
        }
        3 => {
            let (d, c, b, a) = (&cs[0], &cs[1], &cs[2], &cs[3]);
            let disc = cubic_discriminant(a, b, c, d);
            let sign = if real {
                Some(Sign::Positive)
            } else {
                sign_of(&disc, set)
            };
            Some(match sign {
                Some(Sign::Positive) => "an irreducible cubic factor with three real roots, which have no expression in real radicals (casus irreducibilis)".into(),
                Some(Sign::Negative) => "an irreducible cubic factor with one real root and two complex ones, not solved here".into(),
                _ => "an irreducible cubic factor, not solved here".into(),
            })
        }
        4 => Some("an irreducible quartic factor (not biquadratic), not solved here".into()),
        n => Some(format!(
            "an irreducible factor of degree {n}, not solved here"
        )),
    }
}

/// The roots λ of a polynomial in `lv` and its factors over the rationals.
fn lambda_roots(p: &Expr, lv: Var) -> Option<(Vec<Expr>, Vec<Expr>)> {
    let den = Expr::from_poly(p.den().clone());
    let cs: Vec<Expr> = p
        .num()
        .coeffs_in(lv)
        .into_iter()
        .map(|c| {
            Expr::from_poly(c)
                .div(&den)
                .unwrap_or_else(|_| Expr::zero())
        })
        .collect();
    let lam = Expr::var(lv);
    let mut roots = Vec::new();
    let mut factors = Vec::new();
    let mut rest = cs;
    // take out λ = 0 roots
    while rest.len() > 1 && rest[0].is_zero() {
        roots.push(Expr::zero());
        factors.push(lam.clone());
        rest.remove(0);
    }
    // rational roots of the scaled polynomial (degree ≥ 3)
    if rest.len() > 3 {
        let n = rest.len() - 1;
        let s = rest[n - 1].neg().div(&rest[n]).ok()?;
        if s.is_zero() {
            return None;
        }
        // p(x·s)/(c_n·s^n): rational coefficients?
        let mut xs: Vec<Q> = Vec::with_capacity(n + 1);
        for (i, c) in rest.iter().enumerate() {
            let v = c
                .mul(&s.powi(i as i64 - n as i64).ok()?)
                .div(&rest[n])
                .ok()?;
            xs.push(v.as_rational()?);
        }
        for x in rational_roots(&xs) {
            // divide by (x·s − λ) in λ: synthetic division of rest by λ − r
            let r = s.scale(&x);
            rest = deflate(&rest, &r)?;
            roots.push(r.clone());
            factors.push(linear_factor(&lam, &r));
            if rest.len() <= 3 {
                break;
            }
        }
        if rest.len() > 3 {
            return None;
        }
    }
    let mut quad = quadratic(&rest)?;
    if rest.len() == 3 && quad.len() == 1 {
        // a double root: two modes share the frequency
        quad.push(quad[0].clone());
    }
    let irrational = quad.len() == 2
        && quad[0]
            .0
            .vars()
            .iter()
            .any(|&v| matches!(atom::atom(v), Atom::Root(_) | Atom::SqrtOf(_)));
    if irrational {
        // keep the quadratic factor whole (factored over the rationals)
        let lead = rest[2].clone();
        let monic = rest[0]
            .div(&lead)
            .ok()?
            .add(&rest[1].div(&lead).ok()?.mul(&lam))
            .add(&lam.mul(&lam));
        factors.push(clear(&monic));
    } else {
        for (r, _) in &quad {
            factors.push(linear_factor(&lam, r));
        }
    }
    roots.extend(quad.into_iter().map(|(r, _)| r));
    with_content(p, &mut factors);
    Some((roots, factors))
}

/// The constant content in front of the factors: det = content · Π factors.
fn with_content(p: &Expr, factors: &mut Vec<Expr>) {
    let mut prod = Expr::one();
    for f in factors.iter() {
        prod = prod.mul(f);
    }
    if let Ok(content) = p.div(&prod) {
        if !content.is_one() {
            factors.insert(0, content);
        }
    }
}

/// The roots λ and factors of a polynomial in `lv` from its full
/// factorization over ℚ: every irreducible factor of degree ≤ 2 in λ is
/// solved exactly (a quadratic one kept whole for display); `None` when a
/// factor has degree 3 or more (but for a biquadratic one). The path for what [`lambda_roots`] can't
/// scale: a cubic without a λ² term (V = k/2·(2z² − x² − y²), every
/// potential satisfying Laplace's equation), quadratic factors irreducible
/// over ℚ (a chain of four equal masses).
fn lambda_roots_factored(p: &Expr, lv: Var) -> Option<(Vec<Expr>, Vec<Expr>)> {
    let lam = Expr::var(lv);
    let mut roots = Vec::new();
    let mut factors = Vec::new();
    for (f, mult) in atom::stable_factorization(crate::poly::factor::factor(p.num())).factors {
        let cs: Vec<Expr> = f.coeffs_in(lv).into_iter().map(Expr::from_poly).collect();
        match cs.len() {
            0 | 1 => continue, // free of λ: part of the content
            2 | 3 => {}
            5 if cs[1].is_zero() && cs[3].is_zero() => {
                let quartic = biquadratic(&cs)?;
                for _ in 0..mult {
                    roots.extend(quartic.iter().cloned());
                    factors.push(Expr::from_poly(f.clone()));
                }
                continue;
            }
            _ => return None,
        }
        let quad = quadratic(&cs)?;
        if quad.len() + 1 != cs.len() {
            return None; // an irreducible quadratic has two distinct roots
        }
        for _ in 0..mult {
            roots.extend(quad.iter().map(|(r, _)| r.clone()));
            if cs.len() == 2 {
                factors.push(linear_factor(&lam, &quad[0].0));
            } else {
                let monic = cs[0]
                    .div(&cs[2])
                    .ok()?
                    .add(&cs[1].div(&cs[2]).ok()?.mul(&lam))
                    .add(&lam.mul(&lam));
                factors.push(clear(&monic));
            }
        }
    }
    if roots.is_empty() {
        return None;
    }
    with_content(p, &mut factors);
    Some((roots, factors))
}

/// (b·λ − a) for a root a/b, with the sign making the λ term negative when
/// the root is a ratio (k − m·λ), as the seed writes (24.2).
fn linear_factor(lam: &Expr, r: &Expr) -> Expr {
    // a/b with integer coefficients: k/(6·m) → (k, 6·m)
    let l = r
        .num()
        .terms()
        .iter()
        .chain(r.den().terms())
        .fold(num_bigint::BigInt::from(1), |l, (_, c)| {
            num_integer::Integer::lcm(&l, &c.denom())
        });
    let lq = Q::from_bigint(l);
    let a = Expr::from_poly(r.num().clone()).scale(&lq);
    let b = Expr::from_poly(r.den().clone()).scale(&lq);
    a.sub(&b.mul(lam))
}

/// A polynomial in λ with its denominators cleared (a monic quadratic
/// times the lcm of its coefficients' denominators).
fn clear(e: &Expr) -> Expr {
    // primitive, its sign by the atoms' names: the numerator alone scales
    // with the denominator's normalization, which follows the ids
    let p = e.num().primitive();
    let p = if atom::leads_negative_stable(&p) {
        -p
    } else {
        p
    };
    Expr::from_poly(p)
}

/// Divide Σ cs[i]·λ^i by (λ − r) (r a root): the quotient's coefficients.
fn deflate(cs: &[Expr], r: &Expr) -> Option<Vec<Expr>> {
    let n = cs.len() - 1;
    let mut out = vec![Expr::zero(); n];
    let mut carry = Expr::zero();
    for i in (0..=n).rev() {
        let v = cs[i].add(&carry.mul(r));
        if i == 0 {
            if !v.is_zero() {
                return None; // not a root
            }
        } else {
            out[i - 1] = v.clone();
            carry = v;
        }
    }
    Some(out)
}

/// Rational roots of Σ xs[i]·x^i (rational root theorem), with small
/// numerators and denominators; multiplicities not repeated.
fn rational_roots(xs: &[Q]) -> Vec<Q> {
    use num_traits::ToPrimitive;
    // integer coefficients
    let mut l = num_bigint::BigInt::from(1);
    for x in xs {
        let d = x.denom();
        l = num_integer::Integer::lcm(&l, &d);
    }
    let ints: Vec<i64> = xs
        .iter()
        .filter_map(|x| (x * &Q::from_bigint(l.clone())).numer().to_i64())
        .collect();
    if ints.len() != xs.len() || ints[0] == 0 {
        return Vec::new();
    }
    let divisors = |n: i64| -> Vec<i64> {
        let n = n.unsigned_abs().min(1_000_000) as i64;
        (1..=n).filter(|d| n % d == 0).take(64).collect()
    };
    let lead = ints[ints.len() - 1];
    let mut out = Vec::new();
    for p in divisors(ints[0]) {
        for qd in divisors(lead) {
            for sign in [1, -1] {
                let Some(cand) = Q::new(sign * p, qd) else {
                    continue;
                };
                if out.contains(&cand) {
                    continue;
                }
                let mut v = Q::zero();
                for c in xs.iter().rev() {
                    v = &(&v * &cand) + c;
                }
                if v.is_zero() {
                    out.push(cand);
                }
            }
        }
    }
    out
}

/// The roots of c₀ + c₂·λ² + c₄·λ⁴ (irreducible): λ² = u for the two
/// roots u of c₀ + c₂·u + c₄·u², λ = ±√u; `None` unless both u are real
/// and positive (decided exactly).
fn biquadratic(cs: &[Expr]) -> Option<Vec<Expr>> {
    let us = quadratic(&[cs[0].clone(), cs[2].clone(), cs[4].clone()])?;
    if us.len() != 2 {
        return None;
    }
    let mut out = Vec::with_capacity(4);
    for (u, cond) in us {
        if !cond.is_empty() || crate::algebra::sign::sign_exact(&u) != Some(Sign::Positive) {
            return None;
        }
        let r = func::sqrt(&u).ok()?;
        out.push(r.neg());
        out.push(r);
    }
    Some(out)
}
