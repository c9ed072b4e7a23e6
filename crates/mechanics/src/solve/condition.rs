//! A condition x > 0 on the parameters, as a lecturer writes it.
//!
//! x's numerator is factored over ℚ in the representation modulo
//! sin² + cos² = 1 that splits it most (Ω·cos(lat)·(C·s + (C − A)·Ω·cos(lat))
//! rather than its expansion in sin²(lat)); then each factor:
//!
//! * of a sign decided for all positive parameters under the scene's
//!   `assume` facts is left out (a negative one flips the inequality);
//! * to an even power, p², is positive except where p = 0: the condition is
//!   "unless p = 0" (the Foucault pendulum's (g − l·W²)², stable unless
//!   g = l·W²);
//! * a sum of squares, found by completing the square one variable at a
//!   time (4a·(a·v² + b·v + c) = (2a·v + b)² + (4ac − b²), a > 0 and the
//!   rest ≥ 0 in turn), is positive except where every square is 0;
//! * the others, to an odd power, decide: p³ > 0 exactly where p > 0.
//!
//! A denominator's factors count the same way (x > 0 where num·den > 0).
//! Where an "unless" equation holds x is 0, not negative: there the
//! linearization does not decide, and the verdict says so.

use crate::algebra::sign::{sign_exact, Sign};
use crate::expr::compact::parameters::{trig_representations, unicode_collected};
use crate::expr::print::leads_negative;
use crate::expr::Expr;
use crate::num::Q;
use crate::poly::factor::factor;
use crate::poly::{Mono, Poly};

/// The most terms of a sum tried as a sum of squares.
const MAX_SQUARES_TERMS: usize = 40;
/// The most variables completed into squares, one after the other.
const MAX_SQUARES_DEPTH: usize = 3;

/// One condition of a verdict, printed.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(super) enum Condition {
    /// An inequality that must hold: `cos(lat)·(C·s + …) > 0`.
    Holds(String),
    /// Equations whose common solutions are left out: `g = l·W²`.
    Unless(String),
}

/// What x > 0 comes to.
pub(super) enum Positivity {
    /// x > 0 for every value of the parameters.
    Holds,
    /// x < 0 for every value of the parameters.
    Fails,
    /// x > 0 exactly where every condition holds.
    When(Vec<Condition>),
}

/// x > 0 in the fewest and simplest conditions (see the module docs).
pub(super) fn positive(x: &Expr) -> Positivity {
    let Factors {
        negative,
        kept,
        unless,
    } = deciding_factors(x);
    if kept.is_empty() && negative {
        return if unless.is_empty() {
            Positivity::Fails
        } else {
            // −p² > 0 nowhere, and not "unstable" where p = 0
            Positivity::When(vec![Condition::Holds(format!(
                "{} > 0",
                crate::expr::print::expanded(x)
            ))])
        };
    }
    if kept.is_empty() && unless.is_empty() {
        return Positivity::Holds;
    }
    let mut out = Vec::new();
    if !kept.is_empty() {
        out.push(Condition::Holds(inequality(kept, negative).holds()));
    }
    out.extend(unless.iter().map(|zeros| {
        let eqs: Vec<String> = zeros.iter().map(equation).collect();
        Condition::Unless(eqs.join(" and "))
    }));
    Positivity::When(out)
}

/// The verdict on the sign of x when it is one inequality between the
/// parameters ("stable when Ω²·R < g, unstable when Ω²·R > g"); `None`
/// when the factors of x decide nothing alone or leave an "unless".
pub(super) fn sign_decides(x: &Expr) -> Option<String> {
    let Factors {
        negative,
        kept,
        unless,
    } = deciding_factors(x);
    if kept.is_empty() || !unless.is_empty() {
        return None;
    }
    let i = inequality(kept, negative);
    Some(format!(
        "stable when {}, unstable when {}",
        i.holds(),
        i.fails()
    ))
}

/// The factors of x that decide its sign.
struct Factors {
    /// Whether the factors left out make x's sign the opposite of the
    /// product of `kept`.
    negative: bool,
    /// The factors of odd power and no sign of their own, each with its
    /// first printed term positive, in the order of their texts.
    kept: Vec<Poly>,
    /// The zeros of the factors of even power (or sums of squares).
    unless: Vec<Vec<Poly>>,
}

/// x's numerator and denominator factored, each factor sorted out (see
/// the module docs).
fn deciding_factors(x: &Expr) -> Factors {
    let num = best_factored(x.num());
    let den = factor(x.den());
    let mut negative = num.unit.is_negative() != den.unit.is_negative();
    let mut kept: Vec<Poly> = Vec::new();
    let mut unless: Vec<Vec<Poly>> = Vec::new();
    for (g, mult) in num.factors.into_iter().chain(den.factors) {
        match sign_exact(&Expr::from_poly(g.clone())).or_else(|| sign_in_sin_squared(&g)) {
            Some(Sign::Positive) => continue,
            Some(Sign::Negative) => {
                negative ^= mult % 2 == 1;
                continue;
            }
            _ => {}
        }
        if mult % 2 == 0 {
            unless.push(vec![g]);
            continue;
        }
        match sum_of_squares(&g, MAX_SQUARES_DEPTH) {
            Some(zeros) if zeros.is_empty() => {}
            // a square whose base has a sign never vanishes: the sum is positive
            Some(zeros)
                if zeros.iter().any(|z| {
                    matches!(
                        sign_exact(&Expr::from_poly(z.clone())),
                        Some(Sign::Positive | Sign::Negative)
                    )
                }) => {}
            Some(zeros) => unless.push(zeros),
            None => {
                // each factor as it prints with a positive first term, and
                // in the order of their texts: the canonical signs and the
                // factors' order follow the atoms' interning order, the
                // printed condition must not
                let flip = leads_negative(&g);
                negative ^= flip;
                kept.push(if flip { -&g } else { g });
            }
        }
    }
    kept.sort_by_cached_key(unicode_collected);
    Factors {
        negative,
        kept,
        unless,
    }
}

/// `smaller < larger`, or `larger > 0` when `smaller` is `None`.
struct Inequality {
    smaller: Option<String>,
    larger: String,
}

impl Inequality {
    /// The inequality as it must hold.
    fn holds(&self) -> String {
        match &self.smaller {
            Some(s) => format!("{s} < {}", self.larger),
            None => format!("{} > 0", self.larger),
        }
    }

    /// The opposite strict inequality (`< 0` after a product's `… > 0`).
    fn fails(&self) -> String {
        match &self.smaller {
            Some(s) => format!("{s} > {}", self.larger),
            None => "< 0".to_string(),
        }
    }
}

/// The product of `kept` (negated when `negative`) > 0 as a lecturer
/// writes it: one sum with terms of both signs as `B < A`, its negative
/// terms on the left (Ω²·R < g for g − Ω²·R > 0); a product as `… > 0`,
/// the sign taken by a sum (C·s − A·Ω·cos(lat) rather than −cos(lat)).
fn inequality(mut kept: Vec<Poly>, negative: bool) -> Inequality {
    if negative {
        let i = kept.iter().position(|g| g.len() > 1).unwrap_or(0);
        kept[i] = -&kept[i];
    }
    if let [g] = kept.as_slice() {
        let (plus, minus): (Vec<_>, Vec<_>) = g
            .terms()
            .iter()
            .map(|(m, c)| (m.clone(), c.clone()))
            .partition(|(_, c)| !c.is_negative());
        if !plus.is_empty() && !minus.is_empty() {
            return Inequality {
                smaller: Some(side(minus, true)),
                larger: side(plus, false),
            };
        }
    }
    let factors: Vec<String> = kept.iter().map(unicode_collected).collect();
    let product: Vec<String> = factors
        .iter()
        .map(|f| {
            if factors.len() > 1 && crate::expr::print::is_sum(f) {
                format!("({f})")
            } else {
                f.clone()
            }
        })
        .collect();
    Inequality {
        smaller: None,
        larger: product.join("·"),
    }
}

/// The sum of the terms `ts` (negated when `flip`), printed.
fn side(ts: Vec<(Mono, Q)>, flip: bool) -> String {
    let q = Poly::from_terms(
        ts.into_iter()
            .map(|(m, c)| (m, if flip { -c } else { c }))
            .collect(),
    );
    unicode_collected(&q)
}

/// The sign of a factor a + b·sin²(u) for every u: a linear function of
/// sin² ∈ [0, 1] has the sign its two ends share (4 − 3·sin²(θ₀) ≥ 1, so
/// the conical pendulum's condition is cos(θ₀) > 0). `None` when the ends
/// differ or are not decided, or the factor is not of that form.
fn sign_in_sin_squared(g: &Poly) -> Option<Sign> {
    let vars = g.vars();
    let s = vars.iter().copied().find(|&v| {
        matches!(crate::expr::atom::atom(v), crate::expr::atom::Atom::Sin(_)) && g.degree(v) == 2
    })?;
    let crate::expr::atom::Atom::Sin(u) = crate::expr::atom::atom(s) else {
        return None;
    };
    let (_, c) = crate::expr::atom::intern_trig(&u);
    if vars.contains(&c) {
        return None;
    }
    let cs = g.coeffs_in(s);
    if !cs[1].is_zero() {
        return None;
    }
    let at_zero = sign_exact(&Expr::from_poly(cs[0].clone()))?;
    let at_one = sign_exact(&Expr::from_poly(&cs[0] + &cs[2]))?;
    (at_zero == at_one && at_zero != Sign::Zero).then_some(at_zero)
}

/// The conditions in words: "stable when A > 0 and B > 0, unless C = D".
pub(super) fn describe(conditions: &[Condition]) -> String {
    let holds: Vec<&str> = conditions
        .iter()
        .filter_map(|c| match c {
            Condition::Holds(s) => Some(s.as_str()),
            Condition::Unless(_) => None,
        })
        .collect();
    let unless: Vec<&str> = conditions
        .iter()
        .filter_map(|c| match c {
            Condition::Unless(s) => Some(s.as_str()),
            Condition::Holds(_) => None,
        })
        .collect();
    match (holds.is_empty(), unless.is_empty()) {
        (false, true) => format!("stable when {}", holds.join(" and ")),
        (true, _) => format!("stable unless {}", unless.join(" or ")),
        (false, false) => format!(
            "stable when {}, unless {}",
            holds.join(" and "),
            unless.join(" or ")
        ),
    }
}

/// The factorization of `p` over ℚ in the representation modulo
/// sin² + cos² = 1 with the most factors (then the fewest terms).
fn best_factored(p: &Poly) -> crate::poly::factor::Factorization {
    let mut best: Option<(usize, usize, crate::poly::factor::Factorization)> = None;
    for rep in trig_representations(p) {
        let f = factor(&rep);
        let count: usize = f.factors.iter().map(|(_, m)| *m as usize).sum();
        let size: usize = f.factors.iter().map(|(g, _)| g.len()).sum();
        let better = best
            .as_ref()
            .is_none_or(|(c, s, _)| count > *c || (count == *c && size < *s));
        if better {
            best = Some((count, size, f));
        }
    }
    best.map(|(_, _, f)| f).unwrap_or_else(|| factor(p))
}

/// p ≥ 0 for every value by completing squares: the polynomials whose
/// common zeros are p's (none when p > 0 everywhere); `None` when not
/// found within `depth` variables.
fn sum_of_squares(p: &Poly, depth: usize) -> Option<Vec<Poly>> {
    if depth == 0 || p.len() < 2 || p.len() > MAX_SQUARES_TERMS {
        return None;
    }
    let four = Poly::constant(Q::from_i64(4));
    // by name: the interning order must not choose the squares
    let mut vars = p.vars();
    vars.sort_by_cached_key(|&v| crate::expr::print::input(&Expr::var(v)));
    for v in vars {
        let cs = p.coeffs_in(v);
        let [c, b, a] = cs.as_slice() else {
            continue;
        };
        if sign_exact(&Expr::from_poly(a.clone())) != Some(Sign::Positive) {
            continue;
        }
        // 4a·p = (2a·v + b)² + (4ac − b²)
        let square = &(&(a * &Poly::var(v)) * &Poly::constant(Q::from_i64(2))) + b;
        let rest = &(&(a * c) * &four) - &(b * b);
        if rest.is_zero() {
            return Some(vec![square]);
        }
        match sign_exact(&Expr::from_poly(rest.clone())) {
            Some(Sign::Positive) => return Some(Vec::new()),
            Some(_) => continue,
            None => {}
        }
        match sum_of_squares(&rest, depth - 1) {
            Some(z) if z.is_empty() => return Some(z),
            Some(mut z) => {
                z.insert(0, square);
                return Some(z);
            }
            None => continue,
        }
    }
    None
}

/// p = 0 as an equation, the negative terms on the right: g = l·W².
fn equation(p: &Poly) -> String {
    let p = p.primitive();
    // the side of the term printed first on the left, whatever the
    // canonical sign (which follows the interning order)
    let p = if leads_negative(&p) { -&p } else { p };
    let (plus, minus): (Vec<_>, Vec<_>) = p
        .terms()
        .iter()
        .map(|(m, c)| (m.clone(), c.clone()))
        .partition(|(_, c)| !c.is_negative());
    match (plus.is_empty(), minus.is_empty()) {
        (false, false) => format!("{} = {}", side(plus, false), side(minus, true)),
        (false, true) => format!("{} = 0", side(plus, false)),
        _ => format!("{} = 0", side(minus, true)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(name: &str) -> Expr {
        Expr::param(name)
    }

    fn when(x: &Expr) -> Vec<Condition> {
        match positive(x) {
            Positivity::When(c) => c,
            Positivity::Holds => panic!("holds"),
            Positivity::Fails => panic!("fails"),
        }
    }

    #[test]
    fn a_perfect_square_is_positive_unless_it_is_zero() {
        // (g − l·W²)²/l²
        let d = p("g").sub(&p("l").mul(&p("W").mul(&p("W"))));
        let x = d.mul(&d).div(&p("l").mul(&p("l"))).unwrap();
        let c = when(&x);
        assert_eq!(c, vec![Condition::Unless("l·W² = g".into())]);
        assert_eq!(describe(&c), "stable unless l·W² = g");
    }

    #[test]
    fn a_factor_linear_in_a_sine_squared_has_the_sign_of_its_ends() {
        let th = Expr::unknown("theta0");
        let s2 = crate::expr::func::sin(&th).powi(2).unwrap();
        let c = crate::expr::func::cos(&th);
        // (4 − 3·sin²θ₀)·cos θ₀: the first factor is at least 1
        let x = Expr::int(4).sub(&Expr::int(3).mul(&s2)).mul(&c);
        assert_eq!(when(&x), vec![Condition::Holds("cos(θ₀) > 0".into())]);
        // 1 − 2·sin²θ₀ changes sign: it stays
        let y = Expr::one().sub(&Expr::int(2).mul(&s2));
        assert!(matches!(positive(&y), Positivity::When(_)));
        // 3·sin²θ₀ − 5 < 0 always
        let z = Expr::int(3).mul(&s2).sub(&Expr::int(5));
        assert!(matches!(positive(&z), Positivity::Fails));
    }

    #[test]
    fn positive_factors_are_left_out_and_a_negative_one_flips() {
        // −m·(a − b): b − a > 0
        let x = p("m").neg().mul(&p("a").sub(&p("b")));
        assert_eq!(when(&x), vec![Condition::Holds("a < b".into())]);
    }

    #[test]
    fn a_sum_of_squares_holds_or_is_zero_where_every_square_is() {
        // a² − 2·a·b + 2·b² = (a − b)² + b² > 0 for positive b
        let (a, b) = (p("a"), p("b"));
        let x = a
            .mul(&a)
            .sub(&a.mul(&b).scale(&Q::from_i64(2)))
            .add(&b.mul(&b).scale(&Q::from_i64(2)));
        assert!(matches!(positive(&x), Positivity::Holds));
        // (a − b)² + (c − d)², expanded: zero where a = b and c = d
        let (c, d) = (p("c"), p("d"));
        let y = a.sub(&b).powi(2).unwrap().add(&c.sub(&d).powi(2).unwrap());
        assert_eq!(when(&y), vec![Condition::Unless("a = b and c = d".into())]);
    }

    #[test]
    fn an_odd_power_decides_like_its_base() {
        let d = p("a").sub(&p("b"));
        let x = d.mul(&d).mul(&d);
        assert_eq!(when(&x), vec![Condition::Holds("b < a".into())]);
    }
}
