//! A trigonometric polynomial in its Fourier form: products of sines and
//! cosines of the angles u₁ … uₙ written as a sum of cos(k·u) and sin(k·u)
//! over integer frequency vectors k (sin a·sin b = ½·(cos(a − b) −
//! cos(a + b)), …). The Fourier form is unique (the functions cos(k·u),
//! sin(k·u) with k's first nonzero entry positive are linearly independent),
//! and it is where the angles of a mechanism show themselves: the double
//! pendulum's denominator m₁ + m₂·sin²θ₁·cos²θ₂ + … is
//! m₁ + ½·m₂ − ½·m₂·cos(2·θ₁ − 2·θ₂).

use super::super::atom::{self, Atom, Folded};
use super::super::print;
use super::super::Expr;
use crate::num::Q;
use crate::poly::{Mono, Poly, Var};
use rustc_hash::FxHashMap;
use std::sync::Arc;

/// The angles of the sines and cosines in a polynomial: (sin var, cos var,
/// the angle), in the order they are written ([`print::angle_rank`]: the
/// print order, then names) so that the frequency vectors' signs do not
/// depend on interning order: 2·θ₁ − 2·θ₂ when θ₁ is declared first.
pub(crate) fn angles(ps: &[&Poly]) -> Vec<(Var, Var, Expr)> {
    let mut seen: Vec<(Var, Var, Expr)> = Vec::new();
    for p in ps {
        for v in p.vars() {
            let sin = match atom::atom(v) {
                Atom::Sin(_) => v,
                Atom::Cos(_) => atom::sin_partner(v),
                _ => continue,
            };
            if seen.iter().any(|s| s.0 == sin) {
                continue;
            }
            let (Atom::Sin(u), Some(cos)) = (atom::atom(sin), atom::cos_partner(sin)) else {
                continue;
            };
            seen.push((sin, cos, u));
        }
    }
    seen.sort_by_cached_key(|s| print::angle_rank(s.0));
    seen
}

/// A Fourier series: (k, the coefficient of e^{i·k·u}).
type Series = Vec<(Vec<i32>, Complex)>;
/// Terms of a polynomial, not yet merged.
type Terms = Vec<(Mono, Q)>;

/// A complex rational, the coefficient of e^{i·k·u}.
#[derive(Clone, Debug, Default)]
struct Complex {
    re: Q,
    im: Q,
}

impl Complex {
    fn mul(&self, o: &Complex) -> Complex {
        Complex {
            re: &(&self.re * &o.re) - &(&self.im * &o.im),
            im: &(&self.re * &o.im) + &(&self.im * &o.re),
        }
    }
}

/// sinᵃ·cosᵇ of one angle as Σ c_j·e^{i·j·u}: cos = (z + 1/z)/2, sin =
/// (z − 1/z)/(2i).
fn one_angle(a: u32, b: u32) -> Vec<(i32, Complex)> {
    let half = Q::new(1, 2).unwrap_or_else(Q::one);
    let mut cur: FxHashMap<i32, Complex> = FxHashMap::default();
    cur.insert(
        0,
        Complex {
            re: Q::one(),
            im: Q::zero(),
        },
    );
    let cos_step = [
        (
            1,
            Complex {
                re: half.clone(),
                im: Q::zero(),
            },
        ),
        (
            -1,
            Complex {
                re: half.clone(),
                im: Q::zero(),
            },
        ),
    ];
    let sin_step = [
        (
            1,
            Complex {
                re: Q::zero(),
                im: -half.clone(),
            },
        ),
        (
            -1,
            Complex {
                re: Q::zero(),
                im: half.clone(),
            },
        ),
    ];
    let steps = std::iter::repeat_n(&cos_step, b as usize)
        .chain(std::iter::repeat_n(&sin_step, a as usize));
    for step in steps {
        let mut next: FxHashMap<i32, Complex> = FxHashMap::default();
        for (j, c) in &cur {
            for (dj, s) in step {
                let t = c.mul(s);
                let e = next.entry(j + dj).or_default();
                e.re += &t.re;
                e.im += &t.im;
            }
        }
        cur = next;
    }
    let mut out: Vec<(i32, Complex)> = cur
        .into_iter()
        .filter(|(_, c)| !c.re.is_zero() || !c.im.is_zero())
        .collect();
    out.sort_by_key(|(j, _)| *j);
    out
}

/// The Fourier form of `p` over `angles`: (k, the real part's and the
/// imaginary part's coefficient polynomials) for k = 0 and every k whose
/// first nonzero entry is positive; p = Σ 2·Re·cos(k·u) − 2·Im·sin(k·u)
/// (plus Re at k = 0).
pub(crate) fn fourier(p: &Poly, angles: &[(Var, Var, Expr)]) -> Vec<(Vec<i32>, Poly, Poly)> {
    let index = angle_index(angles);
    let mut memo: FxHashMap<Vec<(u32, u32)>, Series> = FxHashMap::default();
    let mut acc: FxHashMap<Vec<i32>, (Terms, Terms)> = FxHashMap::default();
    for (m, c) in p.terms() {
        let mut exps = vec![(0u32, 0u32); angles.len()];
        let mut rest: Vec<(Var, u32)> = Vec::new();
        for &(v, e) in m.pairs() {
            match index.get(&v) {
                Some(&(i, true)) => exps[i].1 += e,
                Some(&(i, false)) => exps[i].0 += e,
                None => rest.push((v, e)),
            }
        }
        let rest = Mono::from_pairs(rest);
        let series = memo
            .entry(exps.clone())
            .or_insert_with(|| product_series(&exps));
        for (k, z) in series.iter() {
            let slot = acc.entry(k.clone()).or_default();
            if !z.re.is_zero() {
                slot.0.push((rest.clone(), c * &z.re));
            }
            if !z.im.is_zero() {
                slot.1.push((rest.clone(), c * &z.im));
            }
        }
    }
    let mut out: Vec<(Vec<i32>, Poly, Poly)> = acc
        .into_iter()
        .map(|(k, (re, im))| (k, Poly::from_terms(re), Poly::from_terms(im)))
        .filter(|(_, re, im)| !re.is_zero() || !im.is_zero())
        .collect();
    out.sort_by(|a, b| a.0.cmp(&b.0));
    out
}

/// Π sinᵃⁱ·cosᵇⁱ as a Fourier series, only k = 0 and k canonical (first
/// nonzero entry positive) kept: the rest are their conjugates.
fn product_series(exps: &[(u32, u32)]) -> Series {
    let mut cur: Series = vec![(
        Vec::new(),
        Complex {
            re: Q::one(),
            im: Q::zero(),
        },
    )];
    for &(a, b) in exps {
        let one = one_angle(a, b);
        let mut next = Vec::with_capacity(cur.len() * one.len());
        for (k, c) in &cur {
            for (j, z) in &one {
                let mut k2 = k.clone();
                k2.push(*j);
                next.push((k2, c.mul(z)));
            }
        }
        cur = next;
    }
    cur.retain(|(k, _)| k.iter().find(|&&x| x != 0).is_none_or(|&x| x > 0));
    cur
}

/// The polynomial Σ 2·Re·cos(k·u) − 2·Im·sin(k·u) over display atoms
/// (the plain sin/cos atoms for k a unit vector).
pub(crate) fn to_display(series: &[(Vec<i32>, Poly, Poly)], angles: &[(Var, Var, Expr)]) -> Poly {
    let two = Q::from_i64(2);
    let mut out = Poly::zero();
    for (k, re, im) in series {
        if k.iter().all(|&x| x == 0) {
            out = &out + re;
            continue;
        }
        if !re.is_zero() {
            let v = trig_var(k, true, angles);
            out = &out + &re.scale(&two).mul_mono(&Mono::var(v), &Q::one());
        }
        if !im.is_zero() {
            let v = trig_var(k, false, angles);
            out = &out - &im.scale(&two).mul_mono(&Mono::var(v), &Q::one());
        }
    }
    out
}

/// Whether every frequency vector is one that sin/cos expand back onto
/// the same angles (multiples and number of angles within
/// [`MULTIPLE_ANGLE_BOUNDS`](super::super::func::MULTIPLE_ANGLE_BOUNDS)),
/// so that the folded form reads back as the expression it came from.
/// For angles c·m, one power product m each, sin and cos of the argument
/// Σ k·c·m take each term's own base angle (`split_multiple`), so:
/// - k·c must split into the base c and the multiple k (cos(2·(x/4)) would
///   read back as an atom of x/2, a stranger to x/4's);
/// - no two angles of one vector may share m (3·(x/4) + x reads back in
///   x/4 alone);
/// - a constant angle k·c·π stays in [−π/2, π/2] and off the multiples
///   of π/12, π/10 and π/8: sin and cos reduce other multiples of π by
///   supplementary angles (cos(6π/7) = −cos(π/7)), a fact about that
///   number, not about the multiple-angle algebra the fold used, and those
///   multiples are numbers (cos(2·π/16) reads back as √(2 + √2)/2).
pub(crate) fn within_bounds(
    series: &[(Vec<i32>, Poly, Poly)],
    angles: &[(Var, Var, Expr)],
) -> bool {
    let (max_multiple, max_terms) = super::super::func::MULTIPLE_ANGLE_BOUNDS;
    let terms: Vec<Option<(Mono, Q)>> = angles.iter().map(|a| one_term(&a.2)).collect();
    series.iter().all(|(k, _, _)| {
        k.iter().all(|&x| (x as i64).abs() <= max_multiple)
            && k.iter().filter(|&&x| x != 0).count() <= max_terms
            && reads_back(k, &terms)
    })
}

/// The conditions of [`within_bounds`] on one frequency vector.
fn reads_back(k: &[i32], terms: &[Option<(Mono, Q)>]) -> bool {
    let half = Q::new(1, 2).unwrap_or_else(Q::one);
    let pi = Mono::var(atom::pi());
    let mut seen: Vec<&Mono> = Vec::new();
    for (&x, term) in k.iter().zip(terms) {
        let (Some((m, c)), true) = (term, x != 0) else {
            continue;
        };
        if seen.contains(&m) {
            return false;
        }
        seen.push(m);
        let angle = c * &Q::from_i64(x as i64);
        let (base, multiple) = super::super::func::split_multiple(&angle, !m.is_one());
        if base != c.abs() || multiple * i64::from(c.signum()) != x as i64 {
            return false;
        }
        let exact = super::super::func::has_exact_value(&angle);
        if *m == pi && (angle.abs() > half || exact) {
            return false;
        }
    }
    true
}

/// (m, c) for an angle c·m of one term.
fn one_term(u: &Expr) -> Option<(Mono, Q)> {
    if !u.is_poly() || u.num().len() != 1 {
        return None;
    }
    let (m, c) = &u.num().terms()[0];
    Some((m.clone(), c.clone()))
}

/// cos(k·u) or sin(k·u) as one atom.
fn trig_var(k: &[i32], cos: bool, angles: &[(Var, Var, Expr)]) -> Var {
    let nonzero: Vec<usize> = (0..k.len()).filter(|&i| k[i] != 0).collect();
    if let [i] = nonzero[..] {
        if k[i] == 1 {
            return if cos { angles[i].1 } else { angles[i].0 };
        }
    }
    let mut arg = Expr::zero();
    for &i in &nonzero {
        arg = arg.add(&angles[i].2.scale(&Q::from_i64(k[i] as i64)));
    }
    atom::intern(Atom::Shown(Arc::new(Folded {
        cos,
        a: arg,
        b: Expr::zero(),
        minus: false,
    })))
}

/// The terms the Fourier form of `p` can have at most (each monomial's
/// Π (aᵢ + bᵢ + 1) over its sinᵃ·cosᵇ factors, saturating), or `None` when
/// some angle's degree exceeds `max_degree` (its multiple would too).
pub(crate) fn fourier_size(
    p: &Poly,
    angles: &[(Var, Var, Expr)],
    max_degree: u32,
) -> Option<usize> {
    let index = angle_index(angles);
    let mut total = 0usize;
    for (m, _) in p.terms() {
        let mut degrees = vec![0u32; angles.len()];
        for &(v, e) in m.pairs() {
            if let Some(&(i, _)) = index.get(&v) {
                degrees[i] += e;
            }
        }
        if degrees.iter().any(|&d| d > max_degree) {
            return None;
        }
        let size = degrees
            .iter()
            .fold(1usize, |n, &d| n.saturating_mul(d as usize + 1));
        total = total.saturating_add(size);
    }
    Some(total)
}

/// The terms [`cos_reduced`] can give at most: each monomial's
/// Π (eᵢ/2 + 1) over the flipped sines sinᵉⁱ (saturating).
pub(crate) fn cos_reduced_size(p: &Poly, angles: &[(Var, Var, Expr)], mask: u32) -> usize {
    let flipped: Vec<Var> = angles
        .iter()
        .enumerate()
        .filter(|(i, _)| mask & (1 << i) != 0)
        .map(|(_, (s, _, _))| *s)
        .collect();
    p.terms().iter().fold(0usize, |total, (m, _)| {
        let size = m
            .pairs()
            .iter()
            .filter(|(v, _)| flipped.contains(v))
            .fold(1usize, |n, &(_, e)| n.saturating_mul(e as usize / 2 + 1));
        total.saturating_add(size)
    })
}

fn angle_index(angles: &[(Var, Var, Expr)]) -> FxHashMap<Var, (usize, bool)> {
    angles
        .iter()
        .enumerate()
        .flat_map(|(i, (s, c, _))| [(*s, (i, false)), (*c, (i, true))])
        .collect()
}

/// `p` with sin²(uᵢ) written as 1 − cos²(uᵢ) for the angles in `mask`
/// (canonical polynomials keep cos² as 1 − sin²; sometimes the other
/// choice is the short one: F·(1 − sin²θ) is F·cos²θ).
pub(crate) fn cos_reduced(p: &Poly, angles: &[(Var, Var, Expr)], mask: u32) -> Poly {
    let flip: FxHashMap<Var, Var> = angles
        .iter()
        .enumerate()
        .filter(|(i, _)| mask & (1 << i) != 0)
        .map(|(_, (s, c, _))| (*s, *c))
        .collect();
    let mut memo: FxHashMap<(Var, u32), Poly> = FxHashMap::default();
    let mut out: Vec<(Mono, Q)> = Vec::new();
    let mut sums = Poly::zero();
    for (m, c) in p.terms() {
        let high = m
            .pairs()
            .iter()
            .find(|(v, e)| *e >= 2 && flip.contains_key(v));
        if high.is_none() {
            out.push((m.clone(), c.clone()));
            continue;
        }
        let mut term = Poly::monomial(Mono::one(), c.clone());
        let mut plain: Vec<(Var, u32)> = Vec::new();
        for &(v, e) in m.pairs() {
            match flip.get(&v) {
                Some(&cv) if e >= 2 => {
                    let f = memo
                        .entry((v, e / 2))
                        .or_insert_with(|| one_minus_square(cv).pow(e / 2));
                    term = &term * &*f;
                    if e % 2 == 1 {
                        plain.push((v, 1));
                    }
                }
                _ => plain.push((v, e)),
            }
        }
        let term = term.mul_mono(&Mono::from_pairs(plain), &Q::one());
        sums = &sums + &term;
    }
    &Poly::from_terms(out) + &sums
}

fn one_minus_square(v: Var) -> Poly {
    Poly::from_terms(vec![
        (Mono::one(), Q::one()),
        (Mono::var_pow(v, 2), Q::from_i64(-1)),
    ])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::expr::func;

    #[test]
    fn products_become_sums_of_multiple_angles() {
        let (a, b) = (Expr::coord("fa", 0), Expr::coord("fb", 0));
        // sin²a·cos²b + cos²a·sin²b − 2·sin a·cos a·sin b·cos b = sin²(a − b)
        //   = ½ − ½·cos(2a − 2b)
        let (sa, ca, sb, cb) = (func::sin(&a), func::cos(&a), func::sin(&b), func::cos(&b));
        let e = sa.mul(&cb).sub(&ca.mul(&sb)).powi(2).unwrap();
        let ang = angles(&[e.num()]);
        assert_eq!(ang.len(), 2);
        let series = fourier(e.num(), &ang);
        let shown = to_display(&series, &ang);
        assert_eq!(shown.len(), 2, "{shown:?}");
        let text = super::super::super::print::render_parts(
            &shown,
            &Poly::one(),
            super::super::super::print::Style::Input,
        );
        assert_eq!(text, "-cos(2*fa - 2*fb)/2 + 1/2");
    }

    #[test]
    fn cos_reduction_keeps_the_value() {
        let a = Expr::coord("fc", 0);
        let s = func::sin(&a);
        let f = Expr::param("F");
        let e = Expr::one().sub(&s.powi(2).unwrap()).mul(&f);
        let ang = angles(&[e.num()]);
        let r = cos_reduced(e.num(), &ang, 1);
        // F·cos²: kept as written, not reduced back to F − F·sin²
        let want = Poly::monomial(
            Mono::from_pairs([(ang[0].1, 2), (f.as_var().unwrap(), 1)]),
            Q::one(),
        );
        assert_eq!(r, want);
    }
}
