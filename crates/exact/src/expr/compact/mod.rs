//! Compact forms: the shortest of several exact rewritings of an
//! expression, for display only.
//!
//! The canonical form (see [`super`]) is made for equality: sin² + cos² = 1
//! is applied one way (cos² → 1 − sin²), products of sines and cosines are
//! expanded, nothing is factored. A lecturer writes the same value
//! otherwise: F·cos θ for F·(1 − sin²θ)/cos θ, l₁·(2·m₁ + m₂ − m₂·cos(2·θ₁ −
//! 2·θ₂)) for the expanded quartic in sin θ₁, cos θ₁, sin θ₂, cos θ₂,
//! 3/4·m·(R − r)² for −3/4·m·(2·R·r − R² − r²). [`display_parts`] searches
//! the representations of num/den modulo the ideal (sin²uᵢ + cos²uᵢ − 1)
//! that a lecturer would consider, in the spirit of Monagan and Pearce's
//! rational simplification modulo a polynomial ideal ("Rational
//! simplification modulo a polynomial ideal", ISSAC 2006) — not their
//! minimal-degree linear algebra, but the representations that decide
//! the size of mechanics' results:
//!
//! 1. each angle reduced either way (sin² → 1 − cos² or cos² → 1 − sin²);
//! 2. the Fourier form (multiple angles of the scene's own combinations:
//!    2·θ₁ − 2·θ₂, θ₁ − 2·θ₂), see `fourier.rs`;
//! 3. in each, the gcd of num and den cancelled (cancellation that only
//!    exists modulo the ideal: (1 − sin²θ)/cos θ is cos θ);
//! 4. the addition theorems folded back (cos θ₁·cos θ₂ + sin θ₁·sin θ₂ →
//!    cos(θ₁ − θ₂));
//! 5. sums grouped: a factorization over ℚ where it is shorter ((R − r)²),
//!    and inside a quotient's sums the terms collected by their coordinate
//!    monomial ((l²·m + A − C)·cos²θ·φ̇).
//!
//! The winner has the fewest operations as SymPy's `count_ops` counts them
//! ([`count_ops`]); on a tie the canonical form stays. Every candidate is an
//! identity, so the printed text re-parses to the same canonical value
//! (tests/compact.rs checks it on a panel and on random expressions).
//!
//! **Invariant:** the search is bounded: only expressions of at most
//! [`MAX_COMPACT_TERMS`] terms are searched, at most 2³ reduction choices
//! (then all-sine and all-cosine only), a rewriting only when its size,
//! estimated before it is made, is at most [`MAX_TRIG_EXPANSION`] terms,
//! all the rewritings of one expression together at most
//! [`work_allowance`] of its size ([`COMPACT_WORK_BASE`] +
//! [`COMPACT_WORK_PER_TERM`] per term, so that printing a result takes
//! time proportional to its size), and factorization only of sums of at
//! most [`MAX_FACTORED_TERMS`] terms; beyond, the canonical form is
//! printed with its addition theorems folded.

mod cost;
pub(crate) mod fourier;
pub mod parameters;
#[cfg(test)]
mod work_tests;

use super::atom::{self, Atom};
use super::print::{self, Style};
use crate::num::Q;
use crate::poly::{Mono, Poly, Var};
use std::sync::Arc;

pub use crate::limits::{
    COMPACT_WORK_BASE, COMPACT_WORK_PER_TERM, MAX_COMPACT_TERMS, MAX_FACTORED_TERMS,
    MAX_PRINTED_FACTOR_SUBSETS, MAX_TRIG_EXPANSION,
};

/// The display polynomials of num/den: the shortest representation found
/// (see the module docs). The result may contain display atoms
/// ([`Atom::Shown`], [`Atom::Group`]) and is only for the printers.
pub fn display_parts(num: &Poly, den: &Poly) -> (Poly, Poly) {
    // The canonical quotient's sign convention follows the atoms' interning
    // order; the printers' must not (a scene prints the same whatever was
    // parsed before it): the denominator's first term by name is positive.
    let (num, den) = &print::name_signed(num, den);
    let folded = || {
        (
            print::fold_trig(num).unwrap_or_else(|| num.clone()),
            print::fold_trig(den).unwrap_or_else(|| den.clone()),
        )
    };
    let terms = num.len() + den.len();
    // a monomial over a monomial has no sum to rewrite
    if CANONICAL_ONLY.with(|c| c.get())
        || terms > MAX_COMPACT_TERMS
        || (num.len() < 2 && den.len() < 2)
    {
        return folded();
    }
    let angles = fourier::angles(&[num, den]);
    let plan = Plan::new(num, den, &angles);
    if plan.work > work_allowance(terms) {
        return folded();
    }
    SEARCH_WORK.with(|w| w.set(w.get().saturating_add(plan.work as u64)));
    // where the printers split the numerator by coordinate monomials and
    // cancel each coefficient against the denominator, sums stay sums
    // (each coefficient is compacted when it is printed)
    let collects = printer_collects(num, den);
    let mut search = Search {
        group: !collects,
        ..Search::default()
    };
    // the canonical form is offered first (folded, then as it is), so it
    // stays on a tie
    if angles.is_empty() {
        search.offer_cancelled(num, den);
    } else {
        for (n, d) in plan.representations(num, den, &angles) {
            search.offer_cancelled(&n, &d);
        }
        search.offer_independent();
    }
    // factored last, the winner only: factoring is the search's dearest step
    let (n, d) = match search.best {
        Some((_, n, d)) => (n, d),
        None => folded(),
    };
    if collects {
        // a factored denominator would hide the per-coefficient
        // cancellation (g·m·(R − r)³/(R − r)²)
        return (n, d);
    }
    (factored_if_shorter(&n), factored_if_shorter(&d))
}

/// The most work (terms of candidates built, `Plan::work`) the search
/// of an expression of `terms` terms may take: a fixed allowance and a
/// share proportional to its size, so that printing a result costs time
/// proportional to what it prints.
pub fn work_allowance(terms: usize) -> usize {
    COMPACT_WORK_BASE.saturating_add(COMPACT_WORK_PER_TERM.saturating_mul(terms))
}

thread_local! {
    /// The search work done in this thread ([`search_work`]).
    static SEARCH_WORK: std::cell::Cell<u64> = const { std::cell::Cell::new(0) };
}

/// The work the compact search has done in this thread so far: the terms
/// of every candidate it built (`Plan::work` of each search made). Only
/// differences mean anything (tests and benches count a rendering's work).
pub fn search_work() -> u64 {
    SEARCH_WORK.with(|w| w.get())
}

/// Whether the printers write num/den term by term, each coefficient a
/// quotient of its own that may cancel against the denominator (a sum free
/// of coordinates below, coordinates above).
fn printer_collects(num: &Poly, den: &Poly) -> bool {
    let moving = |p: &Poly| p.vars().into_iter().any(atom::is_moving);
    // a monomial denominator cancels nothing a group would hide
    den.len() > 1 && !moving(den) && moving(num)
}

/// `p` factored over ℚ when that is shorter.
fn factored_if_shorter(p: &Poly) -> Poly {
    match factored(p) {
        Some(f) if ops_of(&f) < ops_of(p) => f,
        _ => p.clone(),
    }
}

thread_local! {
    static CANONICAL_ONLY: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

/// Whether the compact forms are off ([`canonical_only`]): the text of an
/// atom printed then differs.
pub(crate) fn is_canonical_only() -> bool {
    CANONICAL_ONLY.with(|c| c.get())
}

/// Empties the caches computed from atom texts (the print order changed).
pub(crate) fn forget_atom_texts() {
    cost::forget();
}

/// Runs `f` with the compact forms off: what it prints is the canonical
/// (expanded) form, for the places that show it on purpose
/// (det(K − λ·M) expanded, then factored).
pub fn canonical_only<T>(f: impl FnOnce() -> T) -> T {
    let before = CANONICAL_ONLY.with(|c| c.replace(true));
    let out = f();
    CANONICAL_ONLY.with(|c| c.set(before));
    out
}

/// The representations of num/den to try, chosen from their sizes
/// estimated before any is made: each reduction choice (`masks`) and the
/// Fourier form, each within [`MAX_TRIG_EXPANSION`] terms.
struct Plan {
    masks: Vec<u32>,
    fourier: bool,
    /// The terms of every candidate together, num/den as they are
    /// included (estimated: an upper bound of what is built).
    work: usize,
}

impl Plan {
    fn new(num: &Poly, den: &Poly, angles: &[(Var, Var, super::Expr)]) -> Plan {
        let mut plan = Plan {
            masks: Vec::new(),
            fourier: false,
            work: num.len() + den.len(),
        };
        if angles.is_empty() {
            return plan;
        }
        let n = angles.len();
        let masks: Vec<u32> = if n <= 3 {
            (1..(1u32 << n)).collect()
        } else {
            vec![(1u32 << n.min(31)) - 1]
        };
        for mask in masks {
            let size = fourier::cos_reduced_size(num, angles, mask)
                .saturating_add(fourier::cos_reduced_size(den, angles, mask));
            if size <= MAX_TRIG_EXPANSION {
                plan.masks.push(mask);
                plan.work = plan.work.saturating_add(size);
            }
        }
        let (max_multiple, _) = super::func::MULTIPLE_ANGLE_BOUNDS;
        let max_degree = max_multiple as u32;
        let size = fourier::fourier_size(num, angles, max_degree)
            .zip(fourier::fourier_size(den, angles, max_degree))
            .map(|(a, b)| a.saturating_add(b))
            .filter(|&s| s <= MAX_TRIG_EXPANSION);
        if let Some(size) = size {
            if angles
                .iter()
                .all(|(_, _, u)| super::func::is_multiple_angle_base(u))
            {
                plan.fourier = true;
                plan.work = plan.work.saturating_add(size);
            }
        }
        plan
    }

    /// num/den in every representation planned: as they are, each
    /// reduction choice, the Fourier form.
    fn representations(
        &self,
        num: &Poly,
        den: &Poly,
        angles: &[(Var, Var, super::Expr)],
    ) -> Vec<(Poly, Poly)> {
        let mut out = vec![(num.clone(), den.clone())];
        for &mask in &self.masks {
            out.push((
                fourier::cos_reduced(num, angles, mask),
                fourier::cos_reduced(den, angles, mask),
            ));
        }
        if self.fourier {
            let (sn, sd) = (fourier::fourier(num, angles), fourier::fourier(den, angles));
            if fourier::within_bounds(&sn, angles) && fourier::within_bounds(&sd, angles) {
                out.push((
                    fourier::to_display(&sn, angles),
                    fourier::to_display(&sd, angles),
                ));
            }
        }
        out
    }
}

/// The best candidate so far, and the numerators and denominators that
/// may be paired freely (representations in which nothing cancelled).
#[derive(Default)]
struct Search {
    best: Option<(usize, Poly, Poly)>,
    /// Each free numerator as it is and with its addition theorems
    /// folded, both grouped, with their operations.
    nums: Vec<[(Poly, usize); 2]>,
    dens: Vec<[(Poly, usize); 2]>,
    /// Whether sums may be grouped into display atoms.
    group: bool,
}

impl Search {
    fn offer(&mut self, (n, d): (Poly, Poly)) {
        let cost = cost::quotient(&n, &d);
        if self.best.as_ref().is_none_or(|(c, _, _)| cost < *c) {
            self.best = Some((cost, n, d));
        }
    }

    /// num/den with their gcd cancelled, folded or not.
    fn offer_cancelled(&mut self, num: &Poly, den: &Poly) {
        let g = num.gcd(den);
        let free = g.is_constant();
        let (n, d) = if free {
            (num.clone(), den.clone())
        } else {
            let n = num.div_exact(&g).unwrap_or_else(|| num.clone());
            let d = den.div_exact(&g).unwrap_or_else(|| den.clone());
            // the quotient once more in the canonical reduction
            let (rn, rd) = (super::reduce_poly(&n), super::reduce_poly(&d));
            let pair = self.grouped_pair(&rn, &rd);
            self.offer(pair);
            (n, d)
        };
        let (fnum, fden) = (print::fold_trig(&n), print::fold_trig(&d));
        let (gn, gd) = self.grouped_pair(&n, &d);
        let gfnum = fnum.as_ref().map(|f| grouped(f, self.group));
        let gfden = fden.as_ref().map(|f| grouped(f, self.group));
        // the folded pair and the pair as it is, each side grouped
        let folded_n = gfnum.unwrap_or_else(|| gn.clone());
        let folded_d = gfden.unwrap_or_else(|| gd.clone());
        if free {
            // each side's two forms, kept for [`Search::offer_independent`]
            let sides = |p: &Poly, f: &Poly| [(p.clone(), ops_of(p)), (f.clone(), ops_of(f))];
            self.nums.push(sides(&gn, &folded_n));
            self.dens.push(sides(&gd, &folded_d));
        }
        if fnum.is_some() || fden.is_some() {
            self.offer((folded_n, folded_d));
        }
        self.offer((gn, gd));
    }

    /// The shortest numerator over the shortest denominator, each chosen
    /// alone among the representations of the same value.
    fn offer_independent(&mut self) {
        let shortest = |ps: &[[(Poly, usize); 2]]| -> Option<Poly> {
            ps.iter()
                .flatten()
                .min_by_key(|(_, ops)| *ops)
                .map(|(p, _)| p.clone())
        };
        let (Some(n), Some(d)) = (shortest(&self.nums), shortest(&self.dens)) else {
            return;
        };
        self.offer((n, d));
    }

    /// Both sides with their terms collected (the printers collect a
    /// polynomial's terms themselves, but not a quotient's sides; collecting
    /// here makes the cost of both alike).
    fn grouped_pair(&self, n: &Poly, d: &Poly) -> (Poly, Poly) {
        (grouped(n, self.group), grouped(d, self.group))
    }
}

/// `p` with its terms collected by their monomial in moving atoms (when
/// `collect` and that is shorter); factoring comes after the search.
fn grouped(p: &Poly, collect: bool) -> Poly {
    match collected(p).filter(|_| collect) {
        Some(c) if ops_of(&c) < ops_of(p) => c,
        _ => p.clone(),
    }
}

/// The operations of `p` printed as one sum (as a quotient's numerator or
/// denominator is: not collected by the printer).
fn ops_of(p: &Poly) -> usize {
    cost::factored_sum(p)
}

/// `p` as a product of its irreducible factors over ℚ, each sum a
/// [`Atom::Group`]; `None` when it has at most one factor that is a sum
/// (to the first power) or is too large to factor.
fn factored(p: &Poly) -> Option<Poly> {
    if p.len() < 2 || p.len() > MAX_FACTORED_TERMS {
        return None;
    }
    let f = atom::stable_factor_within(p, MAX_PRINTED_FACTOR_SUBSETS)?;
    let sums: Vec<&(Poly, u32)> = f.factors.iter().filter(|(g, _)| g.len() > 1).collect();
    if sums.is_empty() || (sums.len() == 1 && sums[0].1 == 1) {
        return None;
    }
    let mut unit = f.unit.clone();
    let mut mono: Vec<(Var, u32)> = Vec::new();
    let mut sums: Vec<(Poly, u32)> = Vec::new();
    for (g, e) in &f.factors {
        if g.len() == 1 {
            let (m, c) = &g.terms()[0];
            unit *= c.pow_u32(*e);
            mono.extend(m.pairs().iter().map(|&(v, k)| (v, k * e)));
            continue;
        }
        let (g, flipped) = positive_first(g);
        if flipped && e % 2 == 1 {
            unit = -unit;
        }
        sums.push((g, *e));
    }
    if unit.is_negative() {
        negate_into_a_sum(&mut sums, &mut unit);
    }
    mono.extend(sums.into_iter().map(|(g, e)| (group(g), e)));
    Some(Poly::monomial(Mono::from_pairs(mono), unit))
}

/// A negative unit taken into the sum (to an odd power) most of whose
/// terms are negative, as a lecturer distributes the sign:
/// `(m₁ + m₂)·(l₁²·m₁ + … − 2·l₁·l₂·m₁)` rather than
/// `−(2·l₁·l₂·m₁ − l₁²·m₁ − …)·(m₁ + m₂)`; the unit stays when no sum has
/// more negative terms than positive ones.
fn negate_into_a_sum(sums: &mut [(Poly, u32)], unit: &mut Q) {
    let surplus = |g: &Poly| {
        let minus = g.terms().iter().filter(|(_, c)| c.is_negative()).count();
        minus as i64 - (g.len() - minus) as i64
    };
    let best = sums
        .iter()
        .enumerate()
        .filter(|(_, (g, e))| e % 2 == 1 && surplus(g) > 0)
        .max_by_key(|(i, (g, _))| (surplus(g), std::cmp::Reverse(*i)));
    if let Some((i, _)) = best {
        sums[i].0 = -&sums[i].0;
        *unit = -unit.clone();
    }
}

/// `p` with the terms that share a monomial in moving atoms collected:
/// Σ key·(coefficient sum); `None` when no two terms share one.
fn collected(p: &Poly) -> Option<Poly> {
    collected_by(p, atom::is_moving)
}

/// `p` with the terms that share a monomial in the atoms `key` picks
/// collected (see [`collected`]).
fn collected_by(p: &Poly, key: impl Fn(Var) -> bool) -> Option<Poly> {
    let mut groups: Vec<(Mono, Vec<(Mono, Q)>)> = Vec::new();
    // each key's place in `groups`: finding it by a scan would make
    // collecting quadratic in the terms
    let mut index: rustc_hash::FxHashMap<Mono, usize> = rustc_hash::FxHashMap::default();
    for (m, c) in p.terms() {
        type Factors = Vec<(Var, u32)>;
        let (key, rest): (Factors, Factors) = m.pairs().iter().partition(|&&(v, _)| key(v));
        let key = Mono::from_pairs(key);
        let t = (Mono::from_pairs(rest), c.clone());
        match index.get(&key) {
            Some(&i) => groups[i].1.push(t),
            None => {
                index.insert(key.clone(), groups.len());
                groups.push((key, vec![t]));
            }
        }
    }
    if groups.iter().all(|(_, ts)| ts.len() < 2) {
        return None;
    }
    let mut out: Vec<(Mono, Q)> = Vec::new();
    for (key, ts) in groups {
        // terms free of moving atoms are a sum already
        if ts.len() < 2 || key.is_one() {
            out.extend(ts.into_iter().map(|(m, c)| (m.mul(&key), c)));
            continue;
        }
        let coef = Poly::from_terms(ts);
        let (content, common, prim) = print::split_poly(&coef);
        let mono = common.mul(&key).mul(&Mono::var(group(prim)));
        out.push((mono, content));
    }
    Some(Poly::from_terms(out))
}

/// `p` or −p, whichever prints without a leading minus, else whichever
/// shows a positive first term in display order (which the names decide,
/// not the order atoms were interned in); and whether it flipped:
/// (R − r)², (ẏ − r·θ̇)².
fn positive_first(p: &Poly) -> (Poly, bool) {
    let minus = |q: &Poly| print::render_parts(q, &Poly::one(), Style::Input).starts_with('-');
    let (here, there) = (minus(p), minus(&-p));
    let flip = if here != there {
        here
    } else {
        print::leads_negative(p)
    };
    if flip {
        (-p, true)
    } else {
        (p.clone(), false)
    }
}

/// The display atom of a parenthesized sum.
fn group(p: Poly) -> Var {
    atom::intern(Atom::Group(Arc::new(p)))
}

/// Operations in a printed expression, as SymPy's `count_ops` counts them
/// on the same text: each `+ - * / ^` once (a leading or unary minus is
/// SymPy's NEG), each function application once.
pub fn count_ops(text: &str) -> usize {
    let b = text.as_bytes();
    let mut n = 0;
    let mut i = 0;
    while i < b.len() {
        let c = b[i];
        if c.is_ascii_alphabetic() || c == b'_' {
            let start = i;
            while i < b.len() && (b[i].is_ascii_alphanumeric() || b[i] == b'_' || b[i] == b'\'') {
                i += 1;
            }
            if i < b.len() && b[i] == b'(' && i > start {
                n += 1;
            }
            continue;
        }
        if matches!(c, b'+' | b'-' | b'*' | b'/' | b'^') {
            n += 1;
        }
        i += 1;
    }
    n
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::expr::{func, Expr};

    fn shown(e: &Expr) -> String {
        let (n, d) = display_parts(e.num(), e.den());
        print::render_parts(&n, &d, Style::Unicode)
    }

    #[test]
    fn counts_operations_like_sympy() {
        assert_eq!(count_ops("x"), 0);
        assert_eq!(count_ops("-x"), 1);
        assert_eq!(count_ops("a - b*c"), 2);
        assert_eq!(count_ops("sin(th)^2 + 1/2"), 4);
        assert_eq!(count_ops("g*sin(2*th1 - 2*th2)/l1"), 6);
        assert_eq!(count_ops("x1'' + th'"), 1);
    }

    #[test]
    fn a_square_of_a_difference_is_factored() {
        let (m, r, big_r) = (Expr::param("m"), Expr::param("r"), Expr::param("R"));
        let th = Expr::coord("th", 0);
        let e = Expr::rational(Q::new(3, 4).unwrap())
            .mul(&m)
            .mul(&big_r.sub(&r).powi(2).unwrap())
            .mul(&th.dt().powi(2).unwrap());
        assert_eq!(shown(&e), "3/4·m·(R − r)²·θ̇²");
    }

    #[test]
    fn cancellation_modulo_the_ideal() {
        // F·(1 − sin²θ)/cos θ is F·cos θ
        let th = Expr::coord("th", 0);
        let f = Expr::param("F");
        let num = f.mul(&Expr::one().sub(&func::sin(&th).powi(2).unwrap()));
        let e = num.div(&func::cos(&th)).unwrap();
        assert_eq!(shown(&e), "F·cos(θ)");
    }

    #[test]
    fn the_double_pendulum_denominator() {
        let (a, b) = (Expr::coord("th1", 0), Expr::coord("th2", 0));
        let (m1, m2) = (Expr::param("m1"), Expr::param("m2"));
        let s = func::sin(&a.sub(&b));
        let den = m1.add(&m2.mul(&s.powi(2).unwrap()));
        let e = Expr::param("g").div(&den).unwrap();
        let text = shown(&e);
        assert!(
            text == "g/(m₁ + m₂·sin²(θ₁ − θ₂))" || text == "2·g/(2·m₁ + m₂ − m₂·cos(2·θ₁ − 2·θ₂))",
            "{text}"
        );
    }
}
