//! Factorization of multivariate polynomials over ℚ into irreducible factors.
//!
//! [`factor`] writes `p = unit · ∏ fᵢ^eᵢ` with every `fᵢ` irreducible over ℚ,
//! primitive with integer coefficients and a positive leading coefficient (in
//! [`Poly`]'s term order). The steps:
//!
//! 1. the numeric content (a rational) and the monomial content (powers of
//!    single variables) are split off;
//! 2. `square_free`: Yun's algorithm with respect to the first variable on
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

mod fp;
mod kronecker;
mod multivariate;
mod qpoly;
mod square_free;
mod univariate;
mod zpoly;

pub use kronecker::MAX_KRONECKER_DEGREE;
pub use multivariate::MAX_LIFTING_WORK;
pub use square_free::square_free;

use super::{Poly, Var};
use crate::num::Q;
use kronecker::kronecker_factor;
use multivariate::hensel_factor;
use std::cell::Cell;
use std::cmp::Ordering;
use univariate::zassenhaus;
use zpoly::{from_dense, to_dense};

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

/// The subsets of modular (or image) factors a factorization may still
/// try to recombine: under the work budget, or a fixed number of them.
pub(super) struct Trials {
    tried: Cell<usize>,
    /// `None`: the work budget ([`crate::budget::check_subsets`]) bounds
    /// them and unwinds past it; `Some(n)`: at most n, then `spent`.
    most: Option<usize>,
}

impl Trials {
    /// Bounded by the thread's work budget (unbounded outside one).
    pub(super) fn budgeted() -> Trials {
        Trials {
            tried: Cell::new(0),
            most: None,
        }
    }

    /// At most `n` subsets.
    fn at_most(n: usize) -> Trials {
        Trials {
            tried: Cell::new(0),
            most: Some(n),
        }
    }

    /// Count one more subset; `false` when a fixed allowance is spent (the
    /// search then stops, and its result is not used).
    pub(super) fn next(&self) -> bool {
        let tried = self.tried.get() + 1;
        self.tried.set(tried);
        match self.most {
            None => {
                crate::budget::check_subsets(tried);
                true
            }
            Some(n) => tried <= n,
        }
    }

    /// Whether a fixed allowance ran out (the search stopped early).
    pub(super) fn spent(&self) -> bool {
        self.most.is_some_and(|n| self.tried.get() > n)
    }
}

/// Factors `p` into irreducibles over ℚ (see the module docs for the method
/// and its limits). `factor(0)` has unit 0 and no factors; a constant has
/// itself as unit and no factors. Under a work budget, a recombination
/// that would try more subsets of factors than it allows
/// ([`crate::budget::check_subsets`]) unwinds.
pub fn factor(p: &Poly) -> Factorization {
    factor_with(p, &Trials::budgeted())
}

/// [`factor`] trying at most `subsets` subsets of factors in all; `None`
/// when that is not enough (for optional uses: a printed form).
pub fn factor_within(p: &Poly, subsets: usize) -> Option<Factorization> {
    let trials = Trials::at_most(subsets);
    let f = factor_with(p, &trials);
    (!trials.spent()).then_some(f)
}

fn factor_with(p: &Poly, trials: &Trials) -> Factorization {
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
        factor_squarefree(&part, &mut irr, trials);
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

/// Factors a square-free primitive polynomial with positive leading
/// coefficient and no monomial content, pushing the irreducible factors.
fn factor_squarefree(g: &Poly, out: &mut Vec<Poly>, trials: &Trials) {
    if g.is_constant() {
        return;
    }
    let vars = g.vars();
    if vars.len() == 1 {
        let v = vars[0];
        for h in zassenhaus(&to_dense(g, v), trials) {
            out.push(from_dense(&h, v));
        }
        return;
    }
    for &v in &vars {
        let c = content_in(g, v);
        if !c.is_constant() {
            let pp = g.div_exact(&c).map(|q| normalize(&q));
            if let Some(pp) = pp {
                factor_squarefree(&c, out, trials);
                factor_squarefree(&pp, out, trials);
                return;
            }
        }
    }
    // primitive in every variable: degree 1 in one of them means irreducible
    if vars.iter().any(|&v| g.degree(v) == 1) {
        out.push(g.clone());
        return;
    }
    match hensel_factor(g, &vars, trials) {
        Some(fs) => out.extend(fs),
        None => out.extend(kronecker_factor(g, &vars, trials)),
    }
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

#[cfg(test)]
mod tests;
