//! LaTeX, as a careful lecturer types it: `\frac{13 G}{2 g} \ddot{y}_{3}`,
//! `\sqrt{3}`, `\sin^{2}\theta_{3}`, `\dot{\theta}_{3}`.
//!
//! The layout is the text printer's ([`super::print`]): terms collected by
//! their coordinate monomials, q̈ first, then q̇, then q, then the rest, in
//! the same order as the Unicode output; coefficients in lowest terms with
//! their contents pulled out. What changes is the notation:
//!
//! * fractions are `\frac{…}{…}`, the sign outside;
//! * products have no `\cdot` (a space only) unless two numbers meet or
//!   a factor is a name of several letters: `\mathit{AB} \cdot B_{x}`, never
//!   `\mathit{AB} B_{x}`, which the page shows as one name ABBₓ;
//! * functions go last in a product, so `\sin\theta_{3}` needs no
//!   parentheses (`m g l \sin\theta`); an argument that is more than one
//!   symbol is parenthesized: `\cos(\theta_{1} - \theta_{2})`;
//! * names become notation ([`Names`]): `theta3` → `\theta_{3}`, `eps3` →
//!   `\varepsilon_{3}`, `J2` → `J_{2}`, `y3''` → `\ddot{y}_{3}`, `θ3` →
//!   `\theta_{3}`, and a scene's `latex NAME = "…"` overrides any of them.

use super::atom::{self, Atom};
use super::print;
use super::Expr;
use crate::num::Q;
use crate::poly::{Mono, Poly, Var};
use rustc_hash::FxHashMap;

/// Notation for names: the defaults of [`Names::symbol`] and a scene's
/// overrides.
#[derive(Clone, Debug, Default)]
pub struct Names {
    overrides: FxHashMap<String, String>,
}

impl Names {
    /// The default notation, no overrides.
    pub fn new() -> Names {
        Names::default()
    }

    /// Set the LaTeX of `name` (a later call for one name wins).
    pub fn set(&mut self, name: &str, tex: &str) {
        self.overrides.insert(name.to_string(), tex.to_string());
    }

    /// Whether `name` is written as a word of several letters
    /// (`\mathit{AB}`, or an override such as `\mathrm{Re}`), which a
    /// product sets apart from its neighbours: see `product` below.
    pub fn is_word(&self, name: &str) -> bool {
        if let Some(tex) = self.overrides.get(name) {
            return word_tex(split_subscript(tex).0);
        }
        let (base, _) = split_name(name);
        base.chars().count() > 1 && greek(base).is_none()
    }

    /// The notation of `name` with `dots` time derivatives:
    /// `symbol("theta3", 2)` = `\ddot{\theta}_{3}`.
    pub fn symbol(&self, name: &str, dots: u32) -> String {
        if let Some(tex) = self.overrides.get(name) {
            // Dot the head only: `\vartheta_3` → `\dot{\vartheta}_3`.
            let (head, tail) = split_subscript(tex);
            return format!("{}{tail}", dotted(head, dots));
        }
        let (base, sub) = split_name(name);
        let head = base_tex(base);
        let s = dotted(&head, dots);
        match sub {
            None => s,
            Some(sub) => format!("{s}_{{{}}}", sub_tex(sub)),
        }
    }
}

/// Whether the head of an override reads as several letters: a word in
/// a font command (`\mathit{Ff}`, `\mathrm{Re}`) or bare letters (`AB`).
fn word_tex(head: &str) -> bool {
    let letters = |s: &str| s.chars().filter(|c| c.is_alphabetic()).count() > 1;
    const FONTS: [&str; 7] = [
        "\\mathit{",
        "\\mathrm{",
        "\\mathsf{",
        "\\mathbf{",
        "\\text{",
        "\\textit{",
        "\\operatorname{",
    ];
    if let Some(inner) = FONTS.iter().find_map(|f| head.strip_prefix(f)) {
        return letters(inner);
    }
    !head.contains('\\') && letters(head)
}

/// Whether a named intermediate's LaTeX ([`super::tape::latex_name`]) has
/// a head of several letters (`rA_{x}`, not `P1_{x}` or `\omega_{B2}`).
fn named_is_word(name: &str) -> bool {
    let head = name.split_once('_').map_or(name, |(h, _)| h);
    head != "omega" && head.chars().filter(|c| c.is_alphabetic()).count() > 1
}

/// `\vartheta_3` → (`\vartheta`, `_3`); the split is at the first `_`
/// outside braces.
fn split_subscript(tex: &str) -> (&str, &str) {
    let mut depth = 0i32;
    for (i, c) in tex.char_indices() {
        match c {
            '{' => depth += 1,
            '}' => depth -= 1,
            '_' if depth == 0 && i > 0 => return tex.split_at(i),
            _ => {}
        }
    }
    (tex, "")
}

/// `theta3` → (`theta`, `3`); `y_1` → (`y`, `1`); `F_max` → (`F`, `max`);
/// a small letter before capitals, a point's coordinate, `xB` → (`x`,
/// `B`), so that a dot sits on the letter alone (`\dot{x}_{B}`).
fn split_name(name: &str) -> (&str, Option<&str>) {
    if let Some(i) = name.find('_') {
        if i > 0 && i + 1 < name.len() {
            return (&name[..i], Some(&name[i + 1..]));
        }
    }
    let mut chars = name.chars();
    if chars.next().is_some_and(|c| c.is_ascii_lowercase())
        && name.len() > 1
        && chars.all(|c| c.is_ascii_uppercase())
    {
        return (&name[..1], Some(&name[1..]));
    }
    let split = name
        .char_indices()
        .rev()
        .take_while(|(_, c)| c.is_ascii_digit())
        .last()
        .map(|(i, _)| i);
    match split {
        Some(i) if i > 0 => (&name[..i], Some(&name[i..])),
        _ => (name, None),
    }
}

/// A subscript: digits as they are, one letter italic, a word upright.
fn sub_tex(sub: &str) -> String {
    if sub.chars().all(|c| c.is_ascii_digit()) {
        return sub.to_string();
    }
    let (base, more) = split_name(sub);
    let head = if base.chars().count() > 1 && greek(base).is_none() {
        format!("\\mathrm{{{}}}", escape(base))
    } else {
        base_tex(base)
    };
    match more {
        None => head,
        Some(m) => format!("{head}{}", sub_tex(m)),
    }
}

/// Greek letters by name, ASCII and Unicode. `eps`/`epsilon`/`ε` and
/// `phi`/`φ` are the curly forms the seed prints (`\varepsilon`,
/// `\varphi`); `ϵ` and `ϕ` are the straight ones.
const GREEK: &[(&str, &str, &str)] = &[
    ("alpha", "α", "\\alpha"),
    ("beta", "β", "\\beta"),
    ("gamma", "γ", "\\gamma"),
    ("delta", "δ", "\\delta"),
    ("epsilon", "ε", "\\varepsilon"),
    ("eps", "ϵ", "\\epsilon"),
    ("zeta", "ζ", "\\zeta"),
    ("eta", "η", "\\eta"),
    ("theta", "θ", "\\theta"),
    ("th", "ϑ", "\\vartheta"),
    ("iota", "ι", "\\iota"),
    ("kappa", "κ", "\\kappa"),
    ("lambda", "λ", "\\lambda"),
    ("mu", "μ", "\\mu"),
    ("nu", "ν", "\\nu"),
    ("xi", "ξ", "\\xi"),
    ("pi", "π", "\\pi"),
    ("rho", "ρ", "\\rho"),
    ("sigma", "σ", "\\sigma"),
    ("tau", "τ", "\\tau"),
    ("upsilon", "υ", "\\upsilon"),
    ("phi", "φ", "\\varphi"),
    ("chi", "χ", "\\chi"),
    ("psi", "ψ", "\\psi"),
    ("omega", "ω", "\\omega"),
    ("Gamma", "Γ", "\\Gamma"),
    ("Delta", "Δ", "\\Delta"),
    ("Theta", "Θ", "\\Theta"),
    ("Lambda", "Λ", "\\Lambda"),
    ("Xi", "Ξ", "\\Xi"),
    ("Pi", "Π", "\\Pi"),
    ("Sigma", "Σ", "\\Sigma"),
    ("Upsilon", "Υ", "\\Upsilon"),
    ("Phi", "Φ", "\\Phi"),
    ("Psi", "Ψ", "\\Psi"),
    ("Omega", "Ω", "\\Omega"),
];

/// The LaTeX of a Greek name or letter. The ASCII spellings are the
/// names; `eps` is `\varepsilon` like `epsilon` (the seed's ε) and `th`
/// is `\theta` (the Unicode column pairs each command with its letter).
fn greek(base: &str) -> Option<&'static str> {
    match base {
        "eps" => return Some("\\varepsilon"),
        "th" => return Some("\\theta"),
        "ϕ" => return Some("\\phi"),
        _ => {}
    }
    GREEK
        .iter()
        .find(|(name, letter, _)| *name == base || *letter == base)
        .map(|(_, _, tex)| *tex)
}

/// The head of a name: a Greek command, one letter, or a word in italics.
fn base_tex(base: &str) -> String {
    if let Some(g) = greek(base) {
        return g.to_string();
    }
    if base.chars().count() == 1 {
        return escape(base);
    }
    format!("\\mathit{{{}}}", escape(base))
}

/// Characters special to TeX in a name (`_` never reaches here).
fn escape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '_' => out.push_str("\\_"),
            c if c.is_ascii() => out.push(c),
            c => match GREEK.iter().find(|(_, l, _)| l.starts_with(c)) {
                // a Greek letter inside a longer name: `θx`
                Some((_, _, tex)) => {
                    out.push_str(tex);
                    out.push(' ');
                }
                None => out.push(c),
            },
        }
    }
    out.trim_end().to_string()
}

/// `\dot{x}`, `\ddot{x}`, `\dddot{x}`, `\ddddot{x}`, then `x^{(5)}`.
fn dotted(head: &str, dots: u32) -> String {
    match dots {
        0 => head.to_string(),
        1 => format!("\\dot{{{head}}}"),
        2 => format!("\\ddot{{{head}}}"),
        3 => format!("\\dddot{{{head}}}"),
        4 => format!("\\ddddot{{{head}}}"),
        k => format!("{{{head}}}^{{({k})}}"),
    }
}

/// LaTeX of an expression with the default notation.
pub fn latex(e: &Expr) -> String {
    latex_with(e, &Names::default())
}

/// LaTeX of an expression with a scene's notation.
pub fn latex_with(e: &Expr, names: &Names) -> String {
    Tex { names }.expr(e)
}

/// The terms of an expression in display order, each (is negative, text
/// without the sign), for breaking long equations.
pub fn terms_with(e: &Expr, names: &Names) -> Vec<(bool, String)> {
    Tex { names }.terms(e)
}

/// (is negative, D, the signed terms of N): see [`quotient_terms`].
pub type Quotient = (bool, String, Vec<(bool, String)>);

/// A quotient N/D with a sum N as (is negative, D, the terms of N), for
/// writing a long quotient as `\frac{1}{D} \bigl(N\bigr)` over several
/// lines; `None` when `e` is not one quotient of a sum.
pub fn quotient_terms(e: &Expr, names: &Names) -> Option<Quotient> {
    let tex = Tex { names };
    let (num, den) = print::shown_parts(e);
    if den.is_one() || num.len() < 2 || print::collect(&num, &den).is_some() {
        return None;
    }
    // D without its rational content, which joins the numerator
    let (cd, md, pd) = print::split_poly(&den);
    let num = num.scale(&Q::one().checked_div(&cd)?);
    // sign outside, the numerator's first displayed term positive
    let neg = print::leads_negative(&num);
    let num = if neg { -&num } else { num };
    let mut fs = tex.mono(&md);
    if !pd.is_one() {
        fs.push(Factor::new(tex.sum(&pd), Kind::Sum));
    }
    let inner = product(fs);
    let terms = print::sorted_terms(&num)
        .into_iter()
        .map(|(m, c)| (c.is_negative(), tex.sum(&Poly::monomial(m, c.abs()))))
        .collect();
    Some((neg, inner, terms))
}

/// LaTeX with a fraction over a monomial denominator shown term by term
/// (`\frac{16 k}{81 m} - \frac{g}{9 r}`), like [`print::expanded`].
pub fn latex_expanded(e: &Expr, names: &Names) -> String {
    let tex = Tex { names };
    match print::expanded_terms(e) {
        Some(items) => join(items.into_iter().map(|(neg, t)| (neg, tex.expr(&t)))),
        None => tex.expr(e),
    }
}

/// A rational number: `3`, `\frac{3}{2}`, `-\frac{1}{2}`.
pub fn rational(q: &Q) -> String {
    let sign = if q.is_negative() { "-" } else { "" };
    let q = q.abs();
    if q.denom() == num_bigint::BigInt::from(1) {
        format!("{sign}{}", q.numer())
    } else {
        format!("{sign}\\frac{{{}}}{{{}}}", q.numer(), q.denom())
    }
}

/// Terms with their signs outside: `a + b - c`, `-a + b`.
pub fn join(items: impl IntoIterator<Item = (bool, String)>) -> String {
    let mut out = String::new();
    for (i, (neg, s)) in items.into_iter().enumerate() {
        match (i, neg) {
            (0, true) => out.push('-'),
            (0, false) => {}
            (_, true) => out.push_str(" - "),
            (_, false) => out.push_str(" + "),
        }
        out.push_str(&s);
    }
    out
}

/// Terms with the positive ones first when the first is negative, each
/// side in its order.
fn positive_first(terms: Vec<(bool, String)>) -> Vec<(bool, String)> {
    if !terms.first().is_some_and(|t| t.0) {
        return terms;
    }
    let (pos, neg): (Vec<_>, Vec<_>) = terms.into_iter().partition(|t| !t.0);
    pos.into_iter().chain(neg).collect()
}

/// What a factor is, for joining factors into a product.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Kind {
    /// A number (`3`, `\frac{3}{2}`).
    Num,
    /// A symbol, power, radical or fraction: safe anywhere in a product.
    Plain,
    /// A fraction, `\frac{…}{…}`: its bar sets it apart from any neighbour.
    Frac,
    /// A name of several letters (`\mathit{AB}`, `\dot{\mathit{xy}}^{2}`):
    /// side by side with another factor it would read as a longer name.
    Word,
    /// A sum: parenthesized when it is not alone.
    Sum,
    /// A function with its argument (`\sin\theta`): last in a product.
    Func,
}

struct Factor {
    tex: String,
    kind: Kind,
}

impl Factor {
    fn new(tex: String, kind: Kind) -> Factor {
        Factor { tex, kind }
    }
}

/// Parentheses that grow around tall content.
fn parens(s: &str) -> String {
    if s.contains("\\frac") {
        format!("\\left({s}\\right)")
    } else {
        format!("({s})")
    }
}

/// Factors side by side: functions last, sums parenthesized unless alone,
/// `\cdot` only between two numbers and beside a word (see [`separated`]).
/// Every product of the LaTeX is joined here.
fn product(mut fs: Vec<Factor>) -> String {
    if fs.is_empty() {
        return "1".into();
    }
    if fs.len() == 1 {
        return fs.remove(0).tex;
    }
    fs.sort_by_key(|f| f.kind == Kind::Func);
    let mut out = String::new();
    let mut prev: Option<Kind> = None;
    for f in fs {
        let tex = if f.kind == Kind::Sum {
            parens(&f.tex)
        } else {
            f.tex
        };
        if let Some(p) = prev {
            let digit_next = tex.starts_with(|c: char| c.is_ascii_digit());
            if separated(p, f.kind, digit_next) {
                out.push_str(" \\cdot ");
            } else {
                out.push(' ');
            }
        }
        out.push_str(&tex);
        prev = Some(f.kind);
    }
    out
}

/// Whether a `\cdot` goes between factors of kinds `a` then `b` (`b`'s
/// text starting with a digit when `digit_next`). Math mode ignores the
/// space between `\mathit{AB} B_{x}`: the page shows ABBₓ, so a word
/// takes a dot on each side, except after a number (`2 \mathit{AB}` reads
/// as 2·AB), beside a fraction (`\frac{G}{g} \mathit{AB}`) and before a
/// function, whose name TeX sets apart (`\mathit{AB} \sin\alpha`).
fn separated(a: Kind, b: Kind, digit_next: bool) -> bool {
    match (a, b) {
        (Kind::Num, _) => b == Kind::Num || digit_next,
        (Kind::Frac, _) | (_, Kind::Frac | Kind::Func) => false,
        _ => a == Kind::Word || b == Kind::Word,
    }
}

struct Tex<'a> {
    names: &'a Names,
}

impl Tex<'_> {
    fn expr(&self, e: &Expr) -> String {
        join(self.terms(e))
    }

    /// `e` inside a radical, a function's argument, an exponent or a
    /// power's parentheses: a positive term first when there is one
    /// (`\sqrt{L^{2} - R^{2} \sin^{2}\varphi}`, not `\sqrt{-R^{2} … + L^{2}}`),
    /// as [`print::sum_terms`] writes the sums inside a product.
    fn inner(&self, e: &Expr) -> String {
        join(positive_first(self.terms(e)))
    }

    /// The terms of `e` in display order, each (is negative, text).
    fn terms(&self, e: &Expr) -> Vec<(bool, String)> {
        if e.is_zero() {
            return vec![(false, "0".into())];
        }
        crate::budget::check_printed(super::atom::written_size(e));
        let (num, den) = print::shown_parts(e);
        self.parts_terms(&num, &den)
    }

    /// The terms of num/den (display polynomials: see `expr::compact`).
    fn parts_terms(&self, num: &Poly, den: &Poly) -> Vec<(bool, String)> {
        let Some(groups) = print::collect(num, den) else {
            let (neg, fs) = self.fraction(num, den);
            if !neg && fs.len() == 1 && fs[0].kind == Kind::Sum {
                // a bare sum: its own terms
                return print::sorted_terms(num)
                    .into_iter()
                    .map(|(m, c)| (c.is_negative(), self.sum(&Poly::monomial(m, c.abs()))))
                    .collect();
            }
            return vec![(neg, product(fs))];
        };
        // The text printer's order: by monomial, then (only terms free of
        // coordinates share a monomial) by the Unicode text of the term.
        let mut keyed: Vec<(print::TermKey, String, &(Mono, Expr))> = groups
            .iter()
            .map(|g| {
                let (neg, text) = print::unicode_term(&g.1, &g.0);
                (print::term_key(&g.0, neg), text, g)
            })
            .collect();
        keyed.sort_by(|a, b| a.0.cmp(&b.0).then_with(|| a.1.cmp(&b.1)));
        let groups: Vec<&(Mono, Expr)> = keyed.into_iter().map(|(_, _, g)| g).collect();
        groups.iter().map(|(key, c)| self.term(c, key)).collect()
    }

    /// `coef·key`: (is negative, text without the sign).
    fn term(&self, c: &Expr, key: &Mono) -> (bool, String) {
        let neg = print::coefficient_negative(c);
        let c = if neg { c.neg() } else { c.clone() };
        let (cn, cd) = super::compact::display_parts(c.num(), c.den());
        let (_, mut fs) = self.fraction(&cn, &cd);
        if fs.len() == 1 && fs[0].tex == "1" {
            fs.clear();
        }
        fs.extend(self.mono(key));
        (neg, product(fs))
    }

    /// num/den as factors, the sign apart: a polynomial gives its content,
    /// its monomial gcd and its primitive sum; a quotient one `\frac`.
    fn fraction(&self, num: &Poly, den: &Poly) -> (bool, Vec<Factor>) {
        let (cn, mn, pn) = print::split_poly(num);
        if den.is_one() {
            if num.len() == 1 && mn.0.is_empty() {
                return (
                    cn.is_negative(),
                    vec![Factor::new(rational(&cn.abs()), Kind::Num)],
                );
            }
            if mn.0.is_empty() {
                // a sum with no common power product, signs as they are
                return (false, vec![Factor::new(self.sum(num), Kind::Sum)]);
            }
            let mut fs = self.mono(&mn);
            self.content(&cn.abs(), &mut fs);
            if !pn.is_one() {
                fs.push(Factor::new(self.sum(&pn), Kind::Sum));
            }
            return (cn.is_negative(), fs);
        }
        let (neg, c, mn, pn, md, pd) = print::fraction_parts(num, den);
        // exponentials in the denominator go up with a negative exponent:
        // x e^{-\alpha t}, not x/e^{\alpha t}
        type Factors = Vec<(Var, u32)>;
        let (ups, md): (Factors, Factors) =
            md.0.iter()
                .partition(|&&(v, _)| matches!(atom::atom(v), Atom::Exp(_)));
        let md = Mono(md.into_iter().collect());
        let up: Vec<Factor> = ups
            .into_iter()
            .filter_map(|(v, e)| match atom::atom(v) {
                Atom::Exp(u) => Some(Factor::new(
                    format!("e^{{{}}}", self.inner(&u.scale(&Q::from_i64(-(e as i64))))),
                    Kind::Plain,
                )),
                _ => None,
            })
            .collect();
        let side = |n: num_bigint::BigInt, m: &Mono, p: &Poly, extra: Vec<Factor>| {
            let mut fs = Vec::new();
            let q = Q::from_bigint(n);
            if !q.is_one() {
                fs.push(Factor::new(q.to_string(), Kind::Num));
            }
            fs.extend(self.mono(m));
            if !p.is_one() {
                fs.push(Factor::new(self.sum(p), Kind::Sum));
            }
            fs.extend(extra);
            fs
        };
        let bottom = side(c.denom(), &md, &pd, Vec::new());
        if bottom.is_empty() {
            let mut fs = self.mono(&mn);
            self.content(&Q::from_bigint(c.numer()), &mut fs);
            if !pn.is_one() {
                fs.push(Factor::new(self.sum(&pn), Kind::Sum));
            }
            fs.extend(up);
            return (neg, fs);
        }
        let top = product(side(c.numer(), &mn, &pn, up));
        let bottom = product(bottom);
        (
            neg,
            vec![Factor::new(
                format!("\\frac{{{top}}}{{{bottom}}}"),
                Kind::Frac,
            )],
        )
    }

    /// A polynomial as a sum, terms in display order.
    fn sum(&self, p: &Poly) -> String {
        join(print::sum_terms(p).into_iter().map(|(m, c)| {
            let neg = c.is_negative();
            let c = c.abs();
            if m.0.is_empty() {
                return (neg, rational(&c));
            }
            let mut fs = self.mono(&m);
            self.content(&c, &mut fs);
            (neg, product(fs))
        }))
    }

    /// The factors of a monomial, in the text printer's order but with
    /// radicals of numbers first, as numbers are: `2 \sqrt{3} G`.
    fn mono(&self, m: &Mono) -> Vec<Factor> {
        let mut fs: Vec<(Var, u32)> = m.0.iter().copied().collect();
        fs.sort_by_key(|&(v, _)| {
            let rank = print::factor_rank(v);
            (!matches!(atom::atom(v), Atom::Root(_)), rank)
        });
        fs.into_iter().map(|(v, e)| self.power(v, e)).collect()
    }

    /// A rational content with a numeric radical after it joins it:
    /// `\frac{1}{2} \sqrt{3}` → `\frac{\sqrt{3}}{2}`, `\frac{3}{2} \sqrt{3}` →
    /// `\frac{3 \sqrt{3}}{2}`.
    fn content(&self, c: &Q, fs: &mut Vec<Factor>) {
        let one = num_bigint::BigInt::from(1);
        let root = fs
            .first()
            .is_some_and(|f| f.tex.starts_with("\\sqrt{") && !f.tex.contains('^'));
        if root && c.denom() != one {
            let r = fs.remove(0).tex;
            let top = if c.numer() == one {
                r
            } else {
                format!("{} {r}", c.numer())
            };
            fs.insert(
                0,
                Factor::new(format!("\\frac{{{top}}}{{{}}}", c.denom()), Kind::Frac),
            );
        } else if !c.is_one() {
            fs.insert(0, Factor::new(rational(c), Kind::Num));
        }
    }

    fn power(&self, v: Var, e: u32) -> Factor {
        let a = atom::atom(v);
        let sup = if e == 1 {
            String::new()
        } else {
            format!("^{{{e}}}")
        };
        let func = |name: &str, arg: &Expr| {
            Factor::new(format!("{name}{sup}{}", self.argument(arg)), Kind::Func)
        };
        match &a {
            Atom::Sin(u) => func("\\sin", u),
            Atom::Cos(u) => func("\\cos", u),
            Atom::Ln(u) => func("\\ln", u),
            // \arctan^{2} reads badly: a power of an inverse function is
            // written as a power of its parenthesized value
            Atom::Atan(u) | Atom::Asin(u) | Atom::Acos(u) => {
                let name = match a {
                    Atom::Atan(_) => "\\arctan",
                    Atom::Asin(_) => "\\arcsin",
                    _ => "\\arccos",
                };
                if e == 1 {
                    func(name, u)
                } else {
                    Factor::new(
                        format!("\\left({name}{}\\right){sup}", self.argument(u)),
                        Kind::Plain,
                    )
                }
            }
            Atom::Exp(u) => {
                let x = u.scale(&Q::from_i64(e as i64));
                Factor::new(format!("e^{{{}}}", self.inner(&x)), Kind::Plain)
            }
            Atom::Group(p) => {
                let inner = join(positive_first(self.parts_terms(p, &Poly::one())));
                Factor::new(format!("{}{sup}", parens(&inner)), Kind::Plain)
            }
            Atom::Shown(f) if f.b.is_zero() => {
                let name = if f.cos { "\\cos" } else { "\\sin" };
                let angle = self.inner(&f.a);
                Factor::new(format!("{name}{sup}{}", parens(&angle)), Kind::Func)
            }
            Atom::Shown(f) => {
                let name = if f.cos { "\\cos" } else { "\\sin" };
                let op = if f.minus { "-" } else { "+" };
                // parentheses only where a sign changes what follows
                let b = self.expr(&f.b);
                let b = if print::is_sum(&b) && (f.minus || b.starts_with('-')) {
                    parens(&b)
                } else {
                    b
                };
                let angle = format!("{} {op} {b}", self.expr(&f.a));
                Factor::new(format!("{name}{sup}{}", parens(&angle)), Kind::Func)
            }
            Atom::Root(n) => {
                let s = format!("\\sqrt{{{n}}}");
                self.raised(s, e)
            }
            Atom::SqrtOf(u) => {
                let s = match print::square_root_of_square(u) {
                    Some(q) => format!("\\left|{}\\right|", self.expr(&q)),
                    None => format!("\\sqrt{{{}}}", self.inner(u)),
                };
                self.raised(s, e)
            }
            Atom::Pi => Factor::new(format!("\\pi{sup}"), Kind::Plain),
            Atom::Time => Factor::new(format!("t{sup}"), Kind::Plain),
            Atom::Param(n) | Atom::Unknown(n) => Factor::new(
                format!("{}{sup}", self.names.symbol(n, 0)),
                self.name_kind(n),
            ),
            Atom::Coord(n, k) | Atom::Given(n, k) => Factor::new(
                format!("{}{sup}", self.names.symbol(n, *k)),
                self.name_kind(n),
            ),
            Atom::Named(n) => Factor::new(
                format!("{}{sup}", super::tape::latex_name(&n.name, n.order)),
                if named_is_word(&n.name) {
                    Kind::Word
                } else {
                    Kind::Plain
                },
            ),
        }
    }

    /// A scene's name as a factor: a word or a plain symbol.
    fn name_kind(&self, name: &str) -> Kind {
        if self.names.is_word(name) {
            Kind::Word
        } else {
            Kind::Plain
        }
    }

    /// `\sqrt{3}^{2}` is ambiguous to read: parenthesize a raised radical.
    fn raised(&self, s: String, e: u32) -> Factor {
        if e == 1 {
            Factor::new(s, Kind::Plain)
        } else {
            Factor::new(format!("\\left({s}\\right)^{{{e}}}"), Kind::Plain)
        }
    }

    /// A function's argument: bare when it is one symbol (`\sin\theta_{3}`),
    /// else in parentheses (`\sin(\omega t)`).
    fn argument(&self, u: &Expr) -> String {
        let s = self.inner(u);
        let simple = u.as_var().is_some_and(|v| {
            matches!(
                atom::atom(v),
                Atom::Param(_)
                    | Atom::Unknown(_)
                    | Atom::Named(_)
                    | Atom::Coord(..)
                    | Atom::Given(..)
                    | Atom::Time
                    | Atom::Pi
            )
        });
        if simple {
            if s.starts_with('\\') {
                s
            } else {
                format!(" {s}")
            }
        } else {
            parens(&s)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_become_notation() {
        let n = Names::new();
        assert_eq!(n.symbol("theta3", 0), "\\theta_{3}");
        assert_eq!(n.symbol("eps3", 0), "\\varepsilon_{3}");
        assert_eq!(n.symbol("omega", 0), "\\omega");
        assert_eq!(n.symbol("mu", 0), "\\mu");
        assert_eq!(n.symbol("J2", 0), "J_{2}");
        assert_eq!(n.symbol("F0", 0), "F_{0}");
        assert_eq!(n.symbol("y3", 1), "\\dot{y}_{3}");
        assert_eq!(n.symbol("y3", 2), "\\ddot{y}_{3}");
        assert_eq!(n.symbol("θ3", 0), "\\theta_{3}");
        assert_eq!(n.symbol("φ", 1), "\\dot{\\varphi}");
        assert_eq!(n.symbol("y_1", 0), "y_{1}");
        assert_eq!(n.symbol("F_max", 0), "F_{\\mathrm{max}}");
        assert_eq!(n.symbol("mass", 0), "\\mathit{mass}");
        assert_eq!(n.symbol("Omega", 0), "\\Omega");
        assert_eq!(n.symbol("x", 5), "{x}^{(5)}");
    }

    #[test]
    fn overrides_win_and_dot_their_head() {
        let mut n = Names::new();
        n.set("theta3", "\\vartheta_3");
        assert_eq!(n.symbol("theta3", 0), "\\vartheta_3");
        assert_eq!(n.symbol("theta3", 2), "\\ddot{\\vartheta}_3");
    }

    #[test]
    fn a_radicand_and_an_argument_start_with_a_positive_term() {
        use crate::expr::func;
        let p = |n: &str| Expr::var(atom::param(n));
        let q = Expr::var(atom::coord("phi", 0));
        let s = func::sin(&q);
        // L² − R²·sin²φ: its display order puts the sin² term first
        let radicand = p("L")
            .powi(2)
            .unwrap()
            .sub(&p("R").powi(2).unwrap().mul(&s.mul(&s)));
        let root = func::sqrt(&radicand).unwrap();
        assert_eq!(latex(&root), "\\sqrt{L^{2} - R^{2} \\sin^{2}\\varphi}");
        let one_minus = Expr::one().sub(&q.mul(&q));
        assert_eq!(
            latex(&func::sqrt(&one_minus).unwrap()),
            "\\sqrt{1 - \\varphi^{2}}"
        );
        // a whole expression keeps the display order
        assert_eq!(latex(&radicand), "-R^{2} \\sin^{2}\\varphi + L^{2}");
    }
}
