//! The layouts of a REPL result: one expression shown as qdot prints it,
//! term by term (`expand`), as a product of irreducible factors
//! (`factor`), or in ascending powers of x − a (`taylor`, `series`).
//! Display only: the value is always the canonical expression.

use crate::expr::latex::{self as tex, Names};
use crate::expr::print::{self, Style};
use crate::expr::Expr;
use crate::poly::{Poly, Var};

/// How an expression is laid out: as qdot prints it, every term of the
/// numerator separately (`expand`), as a product of irreducible factors
/// (`factor`), or in ascending powers of x − a (`taylor`, `series`).
#[derive(Clone, Debug, PartialEq)]
pub(super) enum Layout {
    Plain,
    Expanded,
    Factored,
    Series { var: Var, point: Expr },
}

impl Layout {
    /// The expression in Unicode, in this layout.
    pub(super) fn text(&self, e: &Expr) -> String {
        match self {
            Layout::Plain => print::unicode(e),
            Layout::Expanded => expanded(e, Style::Unicode),
            Layout::Factored => factored(e, Style::Unicode),
            Layout::Series { var, point } => series_layout(e, *var, point, None),
        }
    }
    /// The expression in LaTeX with a scene's notation, in this layout.
    pub(super) fn latex(&self, e: &Expr, names: &Names) -> String {
        match self {
            Layout::Plain => tex::latex_with(e, names),
            Layout::Factored => factored_latex(e, names),
            Layout::Expanded => tex::latex_expanded(e, names),
            Layout::Series { var, point } => series_layout(e, *var, point, Some(names)),
        }
    }
}

/// A polynomial p in `var` as Σ cₖ·(var − a)ᵏ in ascending k, with
/// cₖ = p⁽ᵏ⁾(a)/k! (Unicode, or LaTeX with `names`); anything else plainly.
fn series_layout(e: &Expr, var: Var, a: &Expr, names: Option<&Names>) -> String {
    let plain = |x: &Expr| match names {
        Some(n) => tex::latex_with(x, n),
        None => print::unicode(x),
    };
    let degree = e.num().degree(var);
    if e.den().contains_var(var) || degree == 0 {
        return plain(e);
    }
    let x = Expr::var(var);
    // x − a, written that way round whatever the names' order
    let base = if a.is_zero() {
        plain(&x)
    } else {
        let at = plain(a);
        let (sign, mag) = match at.strip_prefix('−').or_else(|| at.strip_prefix('-')) {
            Some(_) => ("+", plain(&a.neg())),
            None => ("−", at),
        };
        let mag = if a.num().len() > 1 {
            format!("({mag})")
        } else {
            mag
        };
        match names {
            Some(_) => format!(
                "\\left({} {} {mag}\\right)",
                plain(&x),
                if sign == "+" { "+" } else { "-" }
            ),
            None => format!("({} {sign} {mag})", plain(&x)),
        }
    };
    let mut items: Vec<(bool, String)> = Vec::new();
    let mut d = e.clone();
    let mut fact = crate::num::Q::one();
    for k in 0..=degree {
        if k > 0 {
            d = d.diff(var);
            fact = &fact * &crate::num::Q::from_i64(i64::from(k));
        }
        let Ok(at) = d.subs(var, a) else {
            return plain(e);
        };
        let c = at.scale(&fact.recip().unwrap_or_else(crate::num::Q::zero));
        if c.is_zero() {
            continue;
        }
        let power = match (k, names) {
            (0, _) => String::new(),
            (1, _) => base.clone(),
            (k, Some(_)) => format!("{base}^{{{k}}}"),
            (k, None) => format!("{base}{}", print::superscript(k)),
        };
        let text = plain(&c);
        let neg = text.starts_with('−') || text.starts_with('-');
        let mag = if neg { c.neg() } else { c.clone() };
        let coef = plain(&mag);
        let sum = mag.num().len() > 1;
        let term = match (power.is_empty(), mag.is_one(), sum, names) {
            (true, ..) => coef,
            (false, true, ..) => power,
            (false, false, true, Some(_)) => format!("\\left({coef}\\right) {power}"),
            (false, false, true, None) => format!("({coef})·{power}"),
            (false, false, false, Some(_)) => format!("{coef} {power}"),
            (false, false, false, None) => format!("{coef}·{power}"),
        };
        items.push((neg, term));
    }
    match names {
        Some(_) => tex::join(items),
        None => print::join_terms(items.into_iter(), Style::Unicode),
    }
}

/// Every term of the numerator on its own, over the denominator.
fn expanded(e: &Expr, st: Style) -> String {
    if e.den().is_one() {
        return terms_text(e.num(), st);
    }
    if e.den().len() == 1 && e.num().len() > 1 {
        return print::expanded(e);
    }
    // The canonical denominator is monic in the atoms' interning order,
    // which depends on the session's history: the sign shown is the one
    // that makes the denominator's first displayed term positive.
    let (den_sign, _, _) = print::split_poly(e.den());
    let (num, den) = if den_sign.is_negative() {
        (-e.num(), -e.den())
    } else {
        (e.num().clone(), e.den().clone())
    };
    let num_text = terms_text(&num, st);
    let den_text = print::render(&Expr::from_poly(den.clone()), st);
    let (num, den) = (num_text, den_text);
    let den = if e.den().len() > 1 || den.contains('·') {
        format!("({den})")
    } else {
        den
    };
    if e.num().len() > 1 {
        format!("({num})/{den}")
    } else {
        format!("{num}/{den}")
    }
}

/// The terms by descending degree in the coordinates (as qdot's printer
/// orders them), then by descending total degree, then lexicographically
/// by name (never in the polynomial's order, which follows interning).
fn terms_text(p: &Poly, st: Style) -> String {
    let mut terms: Vec<&(crate::poly::Mono, crate::num::Q)> = p.terms().iter().collect();
    let moving = |m: &crate::poly::Mono| -> u32 {
        m.pairs()
            .iter()
            .filter(|(v, _)| Expr::var(*v).is_time_dependent())
            .map(|(_, e)| e)
            .sum()
    };
    terms.sort_by_cached_key(|(m, _)| {
        (
            std::cmp::Reverse((moving(m), m.total_degree())),
            print::name_key(m),
        )
    });
    let items = terms.into_iter().map(|(m, c)| {
        let t = Expr::from_poly(Poly::monomial(m.clone(), c.abs()));
        (c.is_negative(), print::render(&t, st))
    });
    print::join_terms(items, st)
}

/// The numerator and denominator as products of irreducible factors over ℚ.
fn factored(e: &Expr, st: Style) -> String {
    let (top, top_parts) = factor_text(e.num(), st);
    if e.den().is_one() {
        return top;
    }
    let (bottom, bottom_parts) = factor_text(e.den(), st);
    // a product or a bare sum below the bar, and a bare sum above it,
    // take parentheses; a lone power (x + y)² does not
    let bare_sum = |t: &str| t.contains(' ') && !t.starts_with('(');
    let bottom = if bottom_parts > 1 || bare_sum(&bottom) {
        format!("({bottom})")
    } else {
        bottom
    };
    let top = if top_parts == 1 && bare_sum(&top) {
        format!("({top})")
    } else {
        top
    };
    format!("{top}/{bottom}")
}

/// `p`'s factorization with each factor starting with a positive term as
/// printed (the sign moved into the unit), sorted by degree and printed
/// text: the order must not depend on the order atoms were interned in.
fn display_factors(p: &Poly) -> (crate::num::Q, Vec<(Poly, u32)>) {
    let f = crate::poly::factor::factor(p);
    let mut unit = f.unit.clone();
    let mut out: Vec<(Poly, u32, String)> = Vec::with_capacity(f.factors.len());
    for (g, k) in &f.factors {
        let g = if print::leads_negative(g) {
            if k % 2 == 1 {
                unit = -unit;
            }
            g.scale(&crate::num::Q::from_i64(-1))
        } else {
            g.clone()
        };
        let text = print::render(&Expr::from_poly(g.clone()), Style::Unicode);
        out.push((g, *k, text));
    }
    out.sort_by(|a, b| {
        (a.0.total_degree(), a.0.len(), &a.2).cmp(&(b.0.total_degree(), b.0.len(), &b.2))
    });
    (unit, out.into_iter().map(|(g, k, _)| (g, k)).collect())
}

/// LaTeX of the factored form: \\frac of the factored numerator and
/// denominator.
fn factored_latex(e: &Expr, names: &Names) -> String {
    let body = |fs: &[(Poly, u32)], lead: &num_bigint::BigInt| -> String {
        let alone = fs.len() == 1 && fs[0].1 == 1 && *lead == num_bigint::BigInt::from(1);
        let mut items: Vec<String> = Vec::new();
        if *lead != num_bigint::BigInt::from(1) || fs.is_empty() {
            items.push(lead.to_string());
        }
        for (g, k) in fs {
            let b = tex::latex_with(&Expr::from_poly(g.clone()), names);
            let b = if g.len() > 1 && !alone {
                format!("\\left({b}\\right)")
            } else {
                b
            };
            items.push(if *k == 1 { b } else { format!("{b}^{{{k}}}") });
        }
        items.join(" ")
    };
    let (un, top) = display_factors(e.num());
    let (ud, bottom) = display_factors(e.den());
    let unit = un.checked_div(&ud).unwrap_or_else(crate::num::Q::one);
    let sign = if unit.is_negative() { "-" } else { "" };
    let unit = unit.abs().to_big();
    let top = body(&top, unit.numer());
    if bottom.is_empty() && unit.denom() == &num_bigint::BigInt::from(1) {
        return format!("{sign}{top}");
    }
    format!("{sign}\\frac{{{top}}}{{{}}}", body(&bottom, unit.denom()))
}

/// The factored text of `p` and its number of factors (with the unit).
fn factor_text(p: &Poly, st: Style) -> (String, usize) {
    let (unit, factors) = display_factors(p);
    if factors.is_empty() {
        return (print::render(&Expr::rational(unit), st), 1);
    }
    let times = if st == Style::Unicode { "·" } else { "*" };
    let mut parts: Vec<String> = Vec::new();
    let (neg, mag) = (unit.is_negative(), unit.abs());
    if !mag.is_one() {
        parts.push(print::render(&Expr::rational(mag), st));
    }
    // a lone irreducible polynomial needs no parentheses
    let alone = factors.len() == 1 && factors[0].1 == 1 && unit.is_one();
    for (g, k) in &factors {
        let s = print::render(&Expr::from_poly(g.clone()), st);
        let s = if g.len() > 1 && !alone {
            format!("({s})")
        } else {
            s
        };
        parts.push(match (k, st) {
            (1, _) => s,
            (k, Style::Unicode) => format!("{s}{}", print::superscript(*k)),
            (k, _) => format!("{s}^{k}"),
        });
    }
    let body = parts.join(times);
    let minus = if st == Style::Unicode { "−" } else { "-" };
    let n = parts.len();
    if neg {
        (format!("{minus}{body}"), n)
    } else {
        (body, n)
    }
}
