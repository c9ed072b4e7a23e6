//! Printing: qdot's input syntax (re-parseable, used in JSON) and readable
//! Unicode (θ̈₃, 14/23·g, −, ·, superscripts).
//!
//! Layout, as a person writes it: an expression is *collected* by its
//! coordinate monomials (q̈ terms first, then q̇, then q, then the rest), each
//! with its coefficient in the parameters printed in lowest terms
//! (`13/2·G/g·ÿ₃ + 2·G·r/g·θ̈₃`). A coefficient with several terms is
//! printed as content × primitive part (`g·R·(G·R − P·r)/(G·R² + J₂·g + P·r²)`).

use super::atom::{self, Atom};
use super::Expr;
use crate::num::Q;
use crate::poly::{Mono, Poly, Var};

/// Which notation.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Style {
    /// qdot's input syntax: `14*g/23`, `theta3''`, `sin(theta3)^2`.
    Input,
    /// Unicode text: `14/23·g`, `θ̈₃`, `sin²(θ₃)`.
    Unicode,
}

/// qdot's input syntax.
pub fn input(e: &Expr) -> String {
    render(e, Style::Input)
}

/// Readable Unicode.
pub fn unicode(e: &Expr) -> String {
    render(e, Style::Unicode)
}

/// Unicode, with a fraction over a monomial denominator shown term by
/// term, as the seed writes it: 16/81·k/m − g/(9·r) rather than
/// (16·k·r − 9·g·m)/(81·m·r). Display only.
pub fn expanded(e: &Expr) -> String {
    expanded_in(e, Style::Unicode)
}

/// [`expanded`] in input syntax (`3*k/m - 3*g/(2*l)`): the JSON of a value
/// the text shows expanded, in the same form.
pub fn expanded_input(e: &Expr) -> String {
    expanded_in(e, Style::Input)
}

fn expanded_in(e: &Expr, st: Style) -> String {
    match expanded_terms(e) {
        Some(items) => join_terms(items.into_iter().map(|(neg, t)| (neg, render(&t, st))), st),
        None => render(e, st),
    }
}

/// The terms of a fraction over a monomial denominator, each (is negative,
/// its absolute value over the denominator), a positive term first; `None`
/// when `e` is not such a fraction of several terms.
pub(crate) fn expanded_terms(e: &Expr) -> Option<Vec<(bool, Expr)>> {
    if e.den().len() != 1 || e.num().len() < 2 {
        return None;
    }
    let den = Expr::from_poly(e.den().clone());
    // a positive term first: 16/81·k/m − g/(9·r)
    let mut terms = sorted_terms(e.num());
    terms.sort_by_key(|(_, c)| c.is_negative());
    terms
        .into_iter()
        .map(|(m, c)| {
            let t = Expr::from_poly(Poly::monomial(m, c.abs()));
            t.div(&den).ok().map(|t| (c.is_negative(), t))
        })
        .collect()
}

/// `e` in the notation `st`, collected by coordinate monomials.
pub fn render(e: &Expr, st: Style) -> String {
    if e.is_zero() {
        return "0".into();
    }
    crate::budget::check_printed(atom::written_size(e));
    let (n, d) = shown_parts(e);
    render_parts(&n, &d, st)
}

/// The polynomials every printer writes for `e`: its compact form
/// ([`super::compact`]), over display atoms.
pub(crate) fn shown_parts(e: &Expr) -> (Poly, Poly) {
    super::compact::display_parts(e.num(), e.den())
}

pub(crate) fn render_parts(num: &Poly, den: &Poly, st: Style) -> String {
    let Some(groups) = collect(num, den) else {
        return fraction(num, den, st);
    };
    let mut items: Vec<(TermKey, String, bool)> = groups
        .into_iter()
        .map(|(key, c)| {
            let (neg, body) = term_with_coef(&c, &key, st);
            (term_key(&key, neg), body, neg)
        })
        .collect();
    items.sort_by(|a, b| a.0.cmp(&b.0).then_with(|| a.1.cmp(&b.1)));
    join_terms(items.into_iter().map(|(_, s, n)| (n, s)), st)
}

/// The layout of num/den as a person writes it: `None` for one fraction
/// (the denominator has coordinates, or the numerator has none), else the
/// terms collected by their coordinate monomials, as (monomial, coefficient)
/// pairs in no particular order; the terms free of coordinates come one
/// by one.
pub(crate) fn collect(num: &Poly, den: &Poly) -> Option<Vec<(Mono, Expr)>> {
    let den_has_coord = den.vars().into_iter().any(is_dynamic);
    let num_has_coord = num.vars().into_iter().any(is_dynamic);
    if den_has_coord || !num_has_coord {
        return None;
    }
    // Split num into Σ key·coef with key a monomial in dynamic atoms (each
    // key's place found by a hash, each coefficient built once: a scan and
    // a sum per term would make printing quadratic in the terms).
    let mut groups: Vec<(Mono, Vec<(Mono, Q)>)> = Vec::new();
    let mut index: rustc_hash::FxHashMap<Mono, usize> = rustc_hash::FxHashMap::default();
    for (m, c) in num.terms() {
        let mut key = Mono::default();
        let mut rest = Mono::default();
        for &(v, x) in m.0.iter() {
            if is_dynamic(v) {
                key.0.push((v, x));
            } else {
                rest.0.push((v, x));
            }
        }
        match index.get(&key) {
            Some(&i) => groups[i].1.push((rest, c.clone())),
            None => {
                index.insert(key.clone(), groups.len());
                groups.push((key, vec![(rest, c.clone())]));
            }
        }
    }
    let groups: Vec<(Mono, Poly)> = groups
        .into_iter()
        .map(|(key, terms)| (key, Poly::from_terms(terms)))
        .collect();
    if groups.len() == 1 && groups[0].0 .0.is_empty() {
        return None;
    }
    let mut out = Vec::with_capacity(groups.len());
    for (key, coef) in groups {
        let c = Expr::from_parts(coef, den.clone()).unwrap_or_else(|_| Expr::zero());
        if key.0.is_empty() && c.den().is_one() {
            // The terms free of coordinates, one by one (the denominator
            // may cancel: x/(a + 1) − (a + 1)² /(a + 1) gives −a − 1).
            for (m, q) in sorted_terms(c.num()) {
                out.push((key.clone(), Expr::from_poly(Poly::monomial(m, q))));
            }
            continue;
        }
        out.push((key, c));
    }
    Some(out)
}

/// Coordinates, their derivatives, time and anything built on them.
fn is_dynamic(v: Var) -> bool {
    match atom::atom(v) {
        Atom::Coord(..) | Atom::Given(..) | Atom::Time => true,
        Atom::Param(_) | Atom::Unknown(_) | Atom::Pi | Atom::Root(_) => false,
        _ => Expr::var(v).is_time_dependent(),
    }
}

/// The display order of a term's monomial, greatest first (highest
/// derivative order first, then higher degree, then coordinates before
/// functions of them): (the highest derivative
/// order of a coordinate, the degree in coordinates, the total degree).
fn display_key(m: &Mono) -> (i64, i64, i64) {
    let mut order = -1i64;
    let mut deg = 0i64;
    for &(v, e) in m.0.iter() {
        if let Atom::Coord(_, k) = atom::atom(v) {
            order = order.max(k as i64);
            deg += e as i64;
        }
    }
    (order, deg, m.total_degree() as i64)
}

thread_local! {
    /// The coordinates of the scene being printed, in declaration order
    /// ([`with_coordinate_order`]).
    static COORDINATE_ORDER: std::cell::RefCell<Vec<String>> =
        const { std::cell::RefCell::new(Vec::new()) };
}

/// Run `f` with the coordinates ranked in the order of `names` (a scene's
/// declaration order): terms that `display_key` ties are written in
/// that order, ÿ₃ before θ̈₃ when y3 is declared first. Outside it, and for
/// other names, by name. Never by interning order, so a scene prints the
/// same whatever the process parsed before it (the REPL, Python).
pub fn with_coordinate_order<R>(names: &[String], f: impl FnOnce() -> R) -> R {
    struct Restore(Vec<String>);
    impl Drop for Restore {
        fn drop(&mut self) {
            set_coordinate_order(std::mem::take(&mut self.0));
        }
    }
    let _restore = Restore(set_coordinate_order(names.to_vec()));
    f()
}

/// Installs `names` as the print order and returns the one it replaces.
/// The caches of atom texts (and of what is computed from them) hold
/// texts of the order in force: a new order empties them.
fn set_coordinate_order(names: Vec<String>) -> Vec<String> {
    let old = COORDINATE_ORDER.with(|c| c.replace(names));
    let changed = COORDINATE_ORDER.with(|c| *c.borrow() != old);
    if changed {
        ATOM_TEXTS.with(|c| c.borrow_mut().clear());
        super::compact::forget_atom_texts();
    }
    old
}

/// The order in which the angles of sines and cosines are written
/// (`cos(θ₁ − θ₂)`, the Fourier form's frequencies): as their terms print
/// (the print order in force, then names), then by
/// [`atom::stable_cmp`] — never by interning order. `sin` is a sine atom.
pub(crate) fn angle_rank(sin: Var) -> (Vec<TermKey>, std::sync::Arc<str>) {
    let keys = match atom::atom(sin) {
        Atom::Sin(u) => {
            let mut k: Vec<TermKey> = u
                .num()
                .terms()
                .iter()
                .map(|(m, c)| term_key(m, c.is_negative()))
                .collect();
            k.sort();
            k
        }
        _ => Vec::new(),
    };
    (keys, atom::stable_key(sin))
}

/// Where a term of a printed sum goes, computed once per term (the keys
/// name atoms, and sorting with a comparator that named them would print
/// each atom O(n log n) times): [`display_key`] first, then the
/// coordinates' declaration order ([`with_coordinate_order`]), then the
/// positive terms of what is still tied, then by name ([`name_key`]).
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) struct TermKey {
    display: std::cmp::Reverse<(i64, i64, i64)>,
    coordinates: Vec<(usize, std::cmp::Reverse<u32>, std::cmp::Reverse<u32>)>,
    negative: bool,
    names: Vec<NameRank>,
}

/// One variable of `TermKey::names`; `End` sorts after every variable,
/// so that of two monomials equal as far as the shorter goes the longer
/// comes first ([`name_key`]).
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum NameRank {
    /// A variable's print rank and its exponent (higher powers first).
    Var((u8, u32, String, String), std::cmp::Reverse<u32>),
    /// Past the monomial's last variable.
    End,
}

/// The [`TermKey`] of the term `negative`·`m`.
pub(crate) fn term_key(m: &Mono, negative: bool) -> TermKey {
    let mut coordinates: Vec<_> = COORDINATE_ORDER.with(|order| {
        let order = order.borrow();
        m.0.iter()
            .filter_map(|&(v, e)| match atom::atom(v) {
                Atom::Coord(name, k) => Some((
                    order
                        .iter()
                        .position(|n| n.as_str() == &*name)
                        .unwrap_or(usize::MAX),
                    std::cmp::Reverse(k),
                    std::cmp::Reverse(e),
                )),
                _ => None,
            })
            .collect()
    });
    coordinates.sort();
    TermKey {
        display: std::cmp::Reverse(display_key(m)),
        coordinates,
        negative,
        names: name_key(m),
    }
}

/// Lexicographic order of monomials with the variables ranked by
/// `factor_rank` (by name, not by interning order): `l³, l²·m, l·m², m³`;
/// of two monomials equal as far as the shorter goes, the longer first.
pub fn name_key(m: &Mono) -> Vec<NameRank> {
    let mut names: Vec<NameRank> =
        m.0.iter()
            .map(|&(v, e)| NameRank::Var(factor_rank(v), std::cmp::Reverse(e)))
            .collect();
    names.sort();
    names.push(NameRank::End);
    names
}

/// The Unicode text of `coef·key`, (is negative, text without the sign):
/// the text printer's order of terms with one monomial.
pub(crate) fn unicode_term(c: &Expr, key: &Mono) -> (bool, String) {
    term_with_coef(c, key, Style::Unicode)
}

/// `coef·key`, returning (is negative, text without the sign).
fn term_with_coef(c: &Expr, key: &Mono, st: Style) -> (bool, String) {
    let (neg, s) = term_with_coef_signed(c, key, st);
    // one sign, outside: a product or fraction that still prints with a
    // leading minus (its content's sign decided on other terms) gives it up
    match s.strip_prefix('−').or_else(|| s.strip_prefix('-')) {
        Some(rest) if !is_sum(&s) => (!neg, rest.to_string()),
        _ => (neg, s),
    }
}

/// [`term_with_coef`] before its sign is made the only one.
fn term_with_coef_signed(c: &Expr, key: &Mono, st: Style) -> (bool, String) {
    // The sign goes outside: the coefficient's first displayed term is
    // positive (what still prints with a sign, `term_with_coef` takes out).
    let neg = coefficient_negative(c);
    let c = if neg { c.neg() } else { c.clone() };
    // a coefficient is compacted on its own: g·m·(R − r), p²/(3·m·(R − r)²)
    let (cn, cd) = super::compact::display_parts(c.num(), c.den());
    let body = fraction(&cn, &cd, st);
    if key.0.is_empty() {
        return (neg, body);
    }
    let key_s = mono_str(key, st);
    let mul = mul_sign(st);
    if let Some(q) = c.as_rational() {
        if q.is_one() {
            return (neg, key_s);
        }
        return (neg, coef_times(&q, &key_s, st));
    }
    if c.num().len() == 1 {
        let numeric_top = c.num().terms()[0].0 .0.is_empty();
        if st == Style::Input || numeric_top {
            // `k*x/m`: the key joins the numerator.
            let top = c.num().mul_mono(key, &Q::one());
            return (neg, fraction(&top, c.den(), st));
        }
        return (neg, format!("{body}{mul}{key_s}"));
    }
    if is_sum(&body) {
        (neg, format!("({body}){mul}{key_s}"))
    } else {
        (neg, format!("{body}{mul}{key_s}"))
    }
}

/// Whether a printed expression is a sum at its top level (so it needs
/// parentheses as a factor).
pub fn is_sum(s: &str) -> bool {
    let mut depth = 0i32;
    let mut prev = ' ';
    for (i, ch) in s.char_indices() {
        match ch {
            '(' => depth += 1,
            ')' => depth -= 1,
            '+' | '-' | '−' if depth == 0 && i > 0 && prev == ' ' => return true,
            _ => {}
        }
        prev = ch;
    }
    false
}

fn mul_sign(st: Style) -> &'static str {
    match st {
        Style::Input => "*",
        Style::Unicode => "·",
    }
}

/// `q·x`: `3/2·x` (Unicode) or `3*x/2` (input).
fn coef_times(q: &Q, x: &str, st: Style) -> String {
    let (n, d) = (q.numer(), q.denom());
    let one = num_bigint::BigInt::from(1);
    match st {
        Style::Unicode => {
            if d == one {
                format!("{n}·{x}")
            } else {
                format!("{n}/{d}·{x}")
            }
        }
        Style::Input => {
            let head = if n == one {
                x.to_string()
            } else {
                format!("{n}*{x}")
            };
            if d == one {
                head
            } else {
                format!("{head}/{d}")
            }
        }
    }
}

/// Terms with their signs outside: `a + b − c`, `−a + b`.
pub fn join_terms(items: impl Iterator<Item = (bool, String)>, st: Style) -> String {
    let (plus, minus, lead_minus) = match st {
        Style::Input => (" + ", " - ", "-"),
        Style::Unicode => (" + ", " − ", "−"),
    };
    let mut out = String::new();
    for (i, (neg, s)) in items.enumerate() {
        if i == 0 {
            if neg {
                out.push_str(lead_minus);
            }
        } else {
            out.push_str(if neg { minus } else { plus });
        }
        out.push_str(&s);
    }
    out
}

/// (signed rational content, monomial gcd, primitive integer polynomial
/// whose first displayed term is positive).
pub fn split_poly(p: &Poly) -> (Q, Mono, Poly) {
    let mut g: Option<Mono> = None;
    for (m, _) in p.terms() {
        g = Some(match g {
            None => m.clone(),
            Some(x) => x.gcd(m),
        });
    }
    let g = g.unwrap_or_default();
    let content = p.content();
    let mut prim = p.scale(&Q::one().checked_div(&content).unwrap_or_else(Q::one));
    if !g.0.is_empty() {
        if let Some(x) = prim.div_exact(&Poly::monomial(g.clone(), Q::one())) {
            prim = x;
        }
    }
    let mut content = content;
    let first_neg = leads_negative(&prim);
    if first_neg {
        prim = -&prim;
        content = -content;
    }
    (content, g, prim)
}

/// Terms in display order, a positive term first when there is one
/// (2·m₁ + m₂ − m₂·cos(2·θ₁ − 2·θ₂), not −m₂·cos(…) + 2·m₁ + m₂).
pub(crate) fn sum_terms(p: &Poly) -> Vec<(Mono, Q)> {
    let t = sorted_terms(p);
    if t.first().is_some_and(|(_, c)| c.is_negative()) {
        // the positive terms first, each side in display order
        let (pos, neg): (Vec<_>, Vec<_>) = t.into_iter().partition(|(_, c)| !c.is_negative());
        return pos.into_iter().chain(neg).collect();
    }
    t
}

/// num/den with the printers' sign convention, not the canonical form's
/// (which follows the atoms' interning order, so it would depend on what
/// the process parsed before): the denominator's first term, in display
/// order (by name), is positive.
pub(crate) fn name_signed(num: &Poly, den: &Poly) -> (Poly, Poly) {
    if leads_negative(den) {
        (-num, -den)
    } else {
        (num.clone(), den.clone())
    }
}

/// Whether the coefficient `c` prints with its sign outside: its
/// numerator's first term is negative under [`name_signed`].
pub(crate) fn coefficient_negative(c: &Expr) -> bool {
    leads_negative(c.num()) != leads_negative(c.den())
}

/// Whether the first term of `p` in display order is negative (the sign a
/// factor gives up: k − 6·m rather than −k + 6·m, whatever the order the
/// atoms were interned in).
pub fn leads_negative(p: &Poly) -> bool {
    // the first term of `sorted_terms` without sorting: the greatest
    // display key, then the first least text among those
    let Some(top) = p.terms().iter().map(|(m, _)| display_key(m)).max() else {
        return false;
    };
    p.terms()
        .iter()
        .filter(|(m, _)| display_key(m) == top)
        .map(|(m, c)| (mono_str(m, Style::Input), c))
        .min_by(|a, b| a.0.cmp(&b.0))
        .is_some_and(|(_, c)| c.is_negative())
}

/// Terms in display order.
pub(crate) fn sorted_terms(p: &Poly) -> Vec<(Mono, Q)> {
    // each term's key computed once ([`display_key`], then the text)
    let mut t: Vec<&(Mono, Q)> = p.terms().iter().collect();
    t.sort_by_cached_key(|(m, _)| (std::cmp::Reverse(display_key(m)), mono_str(m, Style::Input)));
    t.into_iter().cloned().collect()
}

/// A polynomial as a sum, terms in display order.
fn sum_str(p: &Poly, st: Style) -> String {
    let items = sum_terms(p).into_iter().map(|(m, c)| {
        let neg = c.is_negative();
        let c = c.abs();
        let ms = mono_str(&m, st);
        let s = if m.0.is_empty() {
            q_str(&c, st)
        } else if c.is_one() {
            ms
        } else {
            coef_times(&c, &ms, st)
        };
        (neg, s)
    });
    join_terms(items, st)
}

fn q_str(q: &Q, _st: Style) -> String {
    q.to_string()
}

/// num/den, with contents pulled out: `g·R·(G·R − P·r)/(G·R² + J₂·g + P·r²)`.
fn fraction(num: &Poly, den: &Poly, st: Style) -> String {
    if den.is_one() {
        if num.len() == 1 {
            return sum_str(num, st);
        }
        // A sum with a common power product: `l₁²·(m₁ + m₂)`.
        let (neg, cn, mn, pn, _, _) = fraction_parts(num, den);
        if mn.0.is_empty() {
            return sum_str(num, st);
        }
        let c = cn.abs();
        let head = mono_str(&mn, st);
        let body = format!("{}{}({})", head, mul_sign(st), sum_str(&pn, st));
        let s = if c.is_one() {
            body
        } else {
            coef_times(&c, &body, st)
        };
        return match (neg, st) {
            (false, _) => s,
            (true, Style::Input) => format!("-{s}"),
            (true, Style::Unicode) => format!("−{s}"),
        };
    }
    let (neg, c, mn, pn, md, pd) = fraction_parts(num, den);
    let mul = mul_sign(st);
    let unit_numerator = c.numer() == num_bigint::BigInt::from(1) && !c.is_one();
    if st == Style::Unicode
        && pn.is_one()
        && pd.is_one()
        && !mn.0.is_empty()
        && !md.0.is_empty()
        && !unit_numerator
    {
        // `13/2·G/g`, `G·r/g`, `3/4·G/(g·r)`
        let head = if c.is_one() {
            String::new()
        } else {
            format!("{c}·")
        };
        let sign = if neg { "−" } else { "" };
        let d = mono_str(&md, st);
        let d = if md.0.len() > 1 { format!("({d})") } else { d };
        return format!("{sign}{head}{}/{d}", mono_str(&mn, st));
    }
    let mut top: Vec<String> = Vec::new();
    let cnum = Q::from_bigint(c.numer());
    let cden = Q::from_bigint(c.denom());
    if !cnum.is_one() {
        top.push(cnum.to_string());
    }
    if !mn.0.is_empty() {
        top.push(mono_str(&mn, st));
    }
    if !pn.is_one() {
        let s = sum_str(&pn, st);
        top.push(if pn.len() > 1 { format!("({s})") } else { s });
    }
    let mut bottom: Vec<String> = Vec::new();
    if !cden.is_one() {
        bottom.push(cden.to_string());
    }
    if !md.0.is_empty() {
        bottom.push(mono_str(&md, st));
    }
    // a lone parenthesized sum needs no second pair of parentheses
    let mut grouped = false;
    if !pd.is_one() {
        let s = sum_str(&pd, st);
        grouped = pd.len() > 1 && bottom.is_empty();
        bottom.push(if pd.len() > 1 { format!("({s})") } else { s });
    }
    let t = if top.is_empty() {
        "1".to_string()
    } else {
        top.join(mul)
    };
    let s = if bottom.is_empty() {
        t
    } else {
        let b = if bottom.len() == 1 && (grouped || !bottom[0].contains(mul)) {
            bottom.remove(0)
        } else {
            format!("({})", bottom.join(mul))
        };
        format!("{t}/{b}")
    };
    if neg {
        match st {
            Style::Input => format!("-{s}"),
            Style::Unicode => format!("−{s}"),
        }
    } else {
        s
    }
}

/// num/den as (is negative, |content|, numerator's monomial and sum,
/// denominator's monomial and sum), the signs as a lecturer sets them: the
/// denominator's sum with more positive terms than negative ones (its first
/// displayed term positive on a tie), and no minus outside a numerator sum
/// that has a negative term to take it (−(a + b − c) is c − a − b).
pub(crate) fn fraction_parts(num: &Poly, den: &Poly) -> (bool, Q, Mono, Poly, Mono, Poly) {
    let (cn, mn, mut pn) = split_poly(num);
    let (mut cd, md, mut pd) = split_poly(den);
    let negatives = |p: &Poly| p.terms().iter().filter(|(_, c)| c.is_negative()).count();
    if 2 * negatives(&pd) > pd.len() {
        pd = -&pd;
        cd = -cd;
    }
    let c = cn.checked_div(&cd).unwrap_or_else(Q::one);
    let mut neg = c.is_negative();
    if neg && negatives(&pn) > 0 {
        pn = -&pn;
        neg = false;
    } else if neg && negatives(&pd) > 0 && 2 * negatives(&pd) >= pd.len() {
        // or the denominator takes it, if that leaves it no more negative
        // terms than positive ones: x/(16·k·r − 9·g·m)
        pd = -&pd;
        neg = false;
    }
    (neg, c.abs(), mn, pn, md, pd)
}

/// Factor order inside a monomial: parameters, π, radicals, t, functions,
/// then coordinates by derivative order.
pub(crate) fn factor_rank(v: Var) -> (u8, u32, String, String) {
    let a = atom::atom(v);
    let name = atom_text(v, AtomText::Input).to_string();
    let name = (name.to_lowercase(), name);
    match a {
        Atom::Param(_) | Atom::Unknown(_) => (0, 0, name.0, name.1),
        // intermediates stand for what moves: after the constants
        Atom::Named(_) => (3, 1, name.0, name.1),
        // a grouped sum after the symbols: g·m·(R − r)·sin(θ)
        Atom::Group(_) => (0, 1, name.0, name.1),
        Atom::Pi => (1, 0, name.0, name.1),
        Atom::Root(_) | Atom::SqrtOf(_) => (2, 0, name.0, name.1),
        Atom::Time => (3, 0, name.0, name.1),
        Atom::Sin(_)
        | Atom::Cos(_)
        | Atom::Exp(_)
        | Atom::Ln(_)
        | Atom::Atan(_)
        | Atom::Asin(_)
        | Atom::Acos(_)
        | Atom::Shown(..) => (4, 0, name.0, name.1),
        Atom::Coord(_, k) => (5, k, name.0, name.1),
        Atom::Given(_, k) => (3, k, name.0, name.1),
    }
}

/// A power product of atoms in the notation `st`: parameters first,
/// coordinates last; `1` when empty.
pub fn mono_str(m: &Mono, st: Style) -> String {
    if m.0.is_empty() {
        return "1".into();
    }
    let mut fs: Vec<(Var, u32)> = m.0.iter().copied().collect();
    // a rank names its atom: made once per factor, not per comparison
    fs.sort_by_cached_key(|&(v, _)| factor_rank(v));
    let parts: Vec<String> = fs.into_iter().map(|(v, e)| power_str(v, e, st)).collect();
    parts.join(mul_sign(st))
}

fn power_str(v: Var, e: u32, st: Style) -> String {
    match st {
        Style::Input => {
            let s = atom_text(v, AtomText::Input);
            if e == 1 {
                s.to_string()
            } else {
                format!("{s}^{e}")
            }
        }
        Style::Unicode => {
            if e == 1 {
                return atom_text(v, AtomText::Unicode).to_string();
            }
            let sup = superscript(e);
            // a named function's power goes on its name: sin²(θ)
            match fn_name(&atom::atom(v)) {
                None => format!("{}{sup}", atom_text(v, AtomText::Unicode)),
                Some(f) => format!("{f}{sup}({})", atom_text(v, AtomText::UnicodeArgument)),
            }
        }
    }
}

/// Which text of an atom [`atom_text`] gives.
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
enum AtomText {
    Input,
    Unicode,
    /// A function's argument in Unicode, for `sin²(…)`.
    UnicodeArgument,
}

thread_local! {
    /// Atom texts already printed, per (atom, text, whether the compact
    /// forms are off): an atom's text depends on nothing else but the
    /// print order, and a new print order empties the cache
    /// ([`set_coordinate_order`]). Printing it again per occurrence and per
    /// sort comparison would cost exponentially in the nesting of
    /// arguments.
    static ATOM_TEXTS: std::cell::RefCell<rustc_hash::FxHashMap<(Var, AtomText, bool), std::rc::Rc<str>>> =
        std::cell::RefCell::new(rustc_hash::FxHashMap::default());
}

/// The input-syntax text of atom `v` (printed once per thread and order).
pub(crate) fn atom_input_text(v: Var) -> std::rc::Rc<str> {
    atom_text(v, AtomText::Input)
}

/// The text of atom `v`, printed once per thread and print order.
fn atom_text(v: Var, which: AtomText) -> std::rc::Rc<str> {
    let key = (v, which, super::compact::is_canonical_only());
    if let Some(s) = ATOM_TEXTS.with(|c| c.borrow().get(&key).cloned()) {
        return s;
    }
    let a = atom::atom(v);
    let s: std::rc::Rc<str> = match which {
        AtomText::Input => atom_input(&a),
        AtomText::Unicode => atom_unicode(&a),
        AtomText::UnicodeArgument => unicode_arg(&a),
    }
    .into();
    ATOM_TEXTS.with(|c| c.borrow_mut().insert(key, s.clone()));
    s
}

/// The name a function atom is written with (in the input syntax and in
/// Unicode alike); `None` for the atoms that are no named function call.
/// Each is the name of the built-in function that makes the atom.
fn fn_name(a: &Atom) -> Option<&'static str> {
    #[deny(
        clippy::wildcard_enum_match_arm,
        clippy::match_wildcard_for_single_variants
    )]
    match a {
        Atom::Sin(_) => Some("sin"),
        Atom::Cos(_) => Some("cos"),
        Atom::Exp(_) => Some("exp"),
        Atom::Ln(_) => Some("ln"),
        Atom::Atan(_) => Some("atan"),
        Atom::Asin(_) => Some("asin"),
        Atom::Acos(_) => Some("acos"),
        Atom::Param(_)
        | Atom::Unknown(_)
        | Atom::Named(_)
        | Atom::Coord(..)
        | Atom::Given(..)
        | Atom::Time
        | Atom::Pi
        | Atom::Root(_)
        | Atom::SqrtOf(_)
        | Atom::Shown(_)
        | Atom::Group(_) => None,
    }
}

/// An atom in input syntax.
pub fn atom_input(a: &Atom) -> String {
    match a {
        Atom::Shown(f) => folded_text(f, Style::Input),
        Atom::Group(p) => format!("({})", render_parts(p, &Poly::one(), Style::Input)),
        Atom::Param(n) | Atom::Unknown(n) => n.to_string(),
        Atom::Coord(n, k) | Atom::Given(n, k) => format!("{n}{}", "'".repeat(*k as usize)),
        Atom::Named(n) => super::tape::input_name(&n.name, n.order),
        Atom::Time => "t".into(),
        Atom::Pi => "pi".into(),
        Atom::Root(n) => format!("sqrt({n})"),
        Atom::SqrtOf(u) => format!("sqrt({})", input(u)),
        Atom::Sin(u)
        | Atom::Cos(u)
        | Atom::Exp(u)
        | Atom::Ln(u)
        | Atom::Atan(u)
        | Atom::Asin(u)
        | Atom::Acos(u) => format!("{}({})", fn_name(a).unwrap_or_default(), input(u)),
    }
}

fn atom_unicode(a: &Atom) -> String {
    match a {
        Atom::Shown(f) => folded_text(f, Style::Unicode),
        Atom::Group(p) => format!("({})", render_parts(p, &Poly::one(), Style::Unicode)),
        Atom::Param(n) | Atom::Unknown(n) => pretty_name(n, 0),
        Atom::Coord(n, k) | Atom::Given(n, k) => pretty_name(n, *k),
        Atom::Named(n) => super::tape::unicode_name(&n.name, n.order),
        Atom::Time => "t".into(),
        Atom::Pi => "π".into(),
        Atom::Root(n) => format!("√{n}"),
        // √(q²) = |q|, as a lecturer writes it (the input syntax keeps sqrt)
        Atom::SqrtOf(u) => match square_root_of_square(u) {
            // |q| = |−q|: the sign the printers give a sum, not the root's
            Some(q) if leads_negative(q.num()) => format!("|{}|", unicode(&q.neg())),
            Some(q) => format!("|{}|", unicode(&q)),
            None => format!("√({})", unicode(u)),
        },
        Atom::Sin(u)
        | Atom::Cos(u)
        | Atom::Exp(u)
        | Atom::Ln(u)
        | Atom::Atan(u)
        | Atom::Asin(u)
        | Atom::Acos(u) => format!("{}({})", fn_name(a).unwrap_or_default(), unicode(u)),
    }
}

fn unicode_arg(a: &Atom) -> String {
    a.argument().map(unicode).unwrap_or_default()
}

/// `²`, `¹²`: a number in superscript digits.
pub fn superscript(e: u32) -> String {
    const S: [char; 10] = ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹'];
    e.to_string()
        .chars()
        .map(|c| S[c.to_digit(10).unwrap_or(0) as usize])
        .collect()
}

/// `₁₂`: the digits of `s` in subscript.
pub fn subscript(s: &str) -> String {
    const S: [char; 10] = ['₀', '₁', '₂', '₃', '₄', '₅', '₆', '₇', '₈', '₉'];
    s.chars()
        .map(|c| c.to_digit(10).map(|d| S[d as usize]).unwrap_or(c))
        .collect()
}

pub(crate) const GREEK: &[(&str, &str)] = &[
    ("alpha", "α"),
    ("beta", "β"),
    ("gamma", "γ"),
    ("delta", "δ"),
    ("epsilon", "ε"),
    ("eps", "ε"),
    ("zeta", "ζ"),
    ("eta", "η"),
    ("theta", "θ"),
    ("th", "θ"),
    ("iota", "ι"),
    ("kappa", "κ"),
    ("lambda", "λ"),
    ("mu", "μ"),
    ("nu", "ν"),
    ("xi", "ξ"),
    ("rho", "ρ"),
    ("sigma", "σ"),
    ("tau", "τ"),
    ("phi", "φ"),
    ("chi", "χ"),
    ("psi", "ψ"),
    ("omega", "ω"),
    ("Gamma", "Γ"),
    ("Delta", "Δ"),
    ("Theta", "Θ"),
    ("Lambda", "Λ"),
    ("Phi", "Φ"),
    ("Psi", "Ψ"),
    ("Omega", "Ω"),
];

/// `theta3` → `θ₃`, with one (˙) or two (¨) dots for derivatives.
pub fn pretty_name(name: &str, dots: u32) -> String {
    let split = name
        .char_indices()
        .rev()
        .take_while(|(_, c)| c.is_ascii_digit())
        .last()
        .map(|(i, _)| i)
        .unwrap_or(name.len());
    let (base, digits) = name.split_at(split);
    let (base, digits) = if base.is_empty() {
        (name, "")
    } else {
        (base, digits)
    };
    let greek = |b: &str| GREEK.iter().find(|(k, _)| *k == b).map(|(_, g)| *g);
    // `lambda_rod` (a constraint's multiplier) reads λ_rod, `p_theta` (a
    // momentum) p_θ
    let base = match (greek(base), base.split_once('_')) {
        (Some(g), _) => g.to_string(),
        (None, Some((head, tail)))
            if !head.is_empty() && (greek(head).is_some() || greek(tail).is_some()) =>
        {
            format!(
                "{}_{}",
                greek(head).unwrap_or(head),
                greek(tail).unwrap_or(tail)
            )
        }
        _ => base.to_string(),
    };
    let mark = match dots {
        0 => String::new(),
        1 => "\u{307}".into(),
        2 => "\u{308}".into(),
        3 => "\u{20DB}".into(),
        _ => "\u{20DC}".into(),
    };
    let base = if base.chars().count() == 1 || dots == 0 {
        format!("{base}{mark}")
    } else {
        // Long names: mark the whole name with primes instead.
        format!("{base}{}", "′".repeat(dots as usize))
    };
    format!("{base}{}", subscript(digits))
}

// ---------------------------------------------------------------- folding

/// A trig factor of a monomial: (sin var, is cosine).
fn trig_factor(v: Var) -> Option<(Var, bool)> {
    match atom::atom(v) {
        Atom::Sin(_) => Some((v, false)),
        Atom::Cos(_) => Some((atom::sin_partner(v), true)),
        _ => None,
    }
}

fn base_angle(sin: Var) -> Option<Expr> {
    match atom::atom(sin) {
        Atom::Sin(u) => Some(u),
        _ => None,
    }
}

/// `a ∓ b` as text, each angle parenthesized when it is a sum.
fn angle_text(f: &atom::Folded, st: Style) -> String {
    // a sum reads left to right: parentheses only where a sign would change
    // what follows it (a − (b + c), a + (−b + c))
    let a = render(&f.a, st);
    if f.b.is_zero() {
        // a multiple angle of the compact forms: cos(2·θ₁ − 2·θ₂)
        return a;
    }
    let b = render(&f.b, st);
    let signed = b.starts_with('-') || b.starts_with('−');
    let b = if is_sum(&b) && (f.minus || signed) {
        format!("({b})")
    } else {
        b
    };
    let op = match (f.minus, st) {
        (false, _) => "+",
        (true, Style::Input) => "-",
        (true, Style::Unicode) => "−",
    };
    format!("{a} {op} {b}")
}

/// The text of a folded factor: `cos(a - b)`.
fn folded_text(f: &atom::Folded, st: Style) -> String {
    let name = if f.cos { "cos" } else { "sin" };
    format!("{name}({})", angle_text(f, st))
}

fn shown(cos: bool, a: &Expr, b: &Expr, minus: bool) -> Var {
    atom::intern(Atom::Shown(std::sync::Arc::new(atom::Folded {
        cos,
        a: a.clone(),
        b: b.clone(),
        minus,
    })))
}

/// Fold pairs of terms back by the addition theorems, for display only:
/// `c·X·cos a·cos b ± c·X·sin a·sin b → c·X·cos(a ∓ b)` and
/// `c·X·sin a·cos b ± c·X·cos a·sin b → c·X·sin(a ± b)`. Returns `None`
/// when nothing folds.
pub(crate) fn fold_trig(p: &Poly) -> Option<Poly> {
    let terms = p.terms();
    let trig_terms = terms
        .iter()
        .filter(|(m, _)| m.0.iter().any(|&(v, e)| e == 1 && trig_factor(v).is_some()))
        .count();
    if trig_terms < 2 {
        return None;
    }
    let index: rustc_hash::FxHashMap<&Mono, usize> =
        terms.iter().enumerate().map(|(i, (m, _))| (m, i)).collect();
    let mut used = vec![false; terms.len()];
    let mut out: Vec<(Mono, Q)> = Vec::new();
    let mut folded = false;
    // which pairs fold is decided in an order independent of the ids
    let mut order: Vec<usize> = (0..terms.len()).collect();
    order.sort_by_cached_key(|&i| atom::stable_mono_key(&terms[i].0));
    let mut ranks: rustc_hash::FxHashMap<Var, (Vec<TermKey>, std::sync::Arc<str>)> =
        rustc_hash::FxHashMap::default();
    for i in order {
        if used[i] {
            continue;
        }
        let (m, c) = &terms[i];
        let mut trig: Vec<(Var, Var, bool)> =
            m.0.iter()
                .filter(|&&(_, e)| e == 1)
                .filter_map(|&(v, _)| trig_factor(v).map(|(s, is_cos)| (v, s, is_cos)))
                .collect();
        if trig.len() < 2 {
            continue;
        }
        trig.sort_by_cached_key(|&(v, _, _)| atom::stable_key(v));
        'pairs: for x in 0..trig.len() {
            for y in 0..trig.len() {
                if x == y || trig[x].1 == trig[y].1 {
                    continue;
                }
                let (vx, sx, cx) = trig[x];
                let (vy, sy, cy) = trig[y];
                // Patterns keyed on the first factor: cos·cos (x < y) or sin·cos.
                let partner = match (cx, cy) {
                    (true, true) if x < y => (sx, sy),
                    (false, true) => (atom::cos_partner(sx).unwrap_or(sx), sy),
                    _ => continue,
                };
                let rest = m
                    .div(&Mono::from_pairs([(vx, 1), (vy, 1)]))
                    .unwrap_or_default();
                let pm = rest.mul(&Mono::from_pairs([(partner.0, 1), (partner.1, 1)]));
                let Some(&j) = index.get(&pm) else { continue };
                if used[j] || j == i {
                    continue;
                }
                let d = &terms[j].1;
                let same = d == c;
                let opposite = *d == -c.clone();
                if !same && !opposite {
                    continue;
                }
                let (Some(a), Some(b)) = (base_angle(sx), base_angle(sy)) else {
                    continue;
                };
                // Put the angle written first first; sin(b − a) = −sin(a − b).
                for v in [sx, sy] {
                    ranks.entry(v).or_insert_with(|| angle_rank(v));
                }
                let a_first = ranks.get(&sx) <= ranks.get(&sy);
                let (var, coef) = if cx {
                    // cos a cos b (+) sin a sin b = cos(a − b); (−): cos(a + b)
                    let (p, q) = if a_first { (&a, &b) } else { (&b, &a) };
                    (shown(true, p, q, same), c.clone())
                } else if same {
                    let (p, q) = if a_first { (&a, &b) } else { (&b, &a) };
                    (shown(false, p, q, false), c.clone())
                } else if a_first {
                    // sin a cos b − cos a sin b = sin(a − b)
                    (shown(false, &a, &b, true), c.clone())
                } else {
                    (shown(false, &b, &a, true), -c.clone())
                };
                out.push((rest.mul(&Mono::var(var)), coef));
                used[i] = true;
                used[j] = true;
                folded = true;
                break 'pairs;
            }
        }
    }
    if !folded {
        return None;
    }
    for (i, t) in terms.iter().enumerate() {
        if !used[i] {
            out.push(t.clone());
        }
    }
    Some(Poly::from_terms(out))
}

/// q when `u` is the polynomial q² (√u = |q|).
pub fn square_root_of_square(u: &Expr) -> Option<Expr> {
    if !u.is_poly() {
        return None;
    }
    u.num().exact_sqrt().map(Expr::from_poly)
}
