//! The dimension of every written expression, checked as it is found.
//!
//! Checking is bidirectional: where the dimension an expression must have
//! is known (a role statement's energy, a `force`'s generalized force, one
//! side of a `solve` equation), it is pushed into sums, through products
//! with known factors, so a mistake is reported at the term that makes it,
//! not at the statement. Elsewhere a sum's terms are compared with the
//! dimension most of them share.

use super::dim::Dimension;
use super::form::{DimForm, DimVar, DimVars};
use super::hint;
use crate::diag::Diagnostic;
use crate::num::Q;
use crate::parse::ast::{BinOp, Builtin, Callee, Expr, ExprKind};
use rustc_hash::FxHashMap;

/// The dimension of a value: `None` for the number 0 (of every dimension).
pub(super) type Term = Option<DimForm>;

/// The dimension of a scalar, or of each component of a vector.
#[derive(Clone, Debug)]
pub(super) enum DimValue {
    Scalar(Term),
    Vector(Vec<Term>),
}

impl DimValue {
    fn one() -> DimValue {
        DimValue::Scalar(Some(DimForm::one()))
    }
    /// `f` applied to the dimension of each component (zero stays zero).
    pub fn map(&self, mut f: impl FnMut(&DimForm) -> DimForm) -> DimValue {
        match self {
            DimValue::Scalar(t) => DimValue::Scalar(t.as_ref().map(&mut f)),
            DimValue::Vector(c) => {
                DimValue::Vector(c.iter().map(|t| t.as_ref().map(&mut f)).collect())
            }
        }
    }
    pub fn components(&self) -> &[Term] {
        match self {
            DimValue::Scalar(t) => std::slice::from_ref(t),
            DimValue::Vector(c) => c,
        }
    }
}

/// Why an expression must have a dimension: the end of the message "…;
/// a force is needed here (WHY)".
#[derive(Clone, Debug)]
pub(super) enum Why {
    /// A role statement: `E1` is a kinetic energy.
    Role { name: String, role: &'static str },
    /// `force q: …`: the generalized force conjugate to q.
    Force { coordinate: String },
    /// One side of a `solve` equation, of the other side's dimension.
    OtherSide,
    /// One side of an `assume` order fact, of the other side's dimension.
    Compared,
    /// The argument of a function that needs a pure number.
    Argument { function: String },
    /// A power with a symbolic exponent.
    SymbolicPower,
    /// The exponent of a power.
    Exponent,
    /// A factor of a product whose other factors are known.
    Factor(Box<Why>),
    /// The value given to a variable in `subs`/`taylor`.
    Substituted { variable: String },
    /// A property of a body (`the mass of `top``) or gravity.
    Property { what: String },
}

impl Why {
    fn describe(&self) -> String {
        match self {
            Why::Role { name, role } => format!("`{name}` is {role}"),
            Why::Force { coordinate } => format!(
                "the generalized force on `{coordinate}` does work over δ{coordinate}: an energy per unit of `{coordinate}`"
            ),
            Why::OtherSide => "the other side of the equation".into(),
            Why::Compared => "the other side of the comparison".into(),
            Why::Argument { function } => format!("the argument of `{function}`"),
            Why::SymbolicPower => "the base of a power with a symbolic exponent".into(),
            Why::Exponent => "an exponent".into(),
            Why::Factor(w) => format!("{}, with the other factors taken out", w.describe()),
            Why::Substituted { variable } => format!("the value of `{variable}`"),
            Why::Property { what } => what.clone(),
        }
    }
}

/// The dimension an expression must have, and why.
#[derive(Clone, Debug)]
pub(super) struct Want {
    pub form: DimForm,
    pub why: Why,
}

/// What a name's dimension is.
#[derive(Clone, Debug)]
pub(super) enum NameDim {
    /// A coordinate, parameter or `solve` unknown: declared, or an unknown.
    Fixed(DimForm),
    /// A definition, by index.
    Def(usize),
    /// `t`.
    Time,
    /// `pi`.
    Pi,
}

/// The expression checker: names, definitions' dimensions so far, unknowns.
pub(super) struct Walker<'a> {
    pub src: &'a str,
    pub vars: DimVars,
    pub names: FxHashMap<&'a str, NameDim>,
    /// The coordinates' names (`series(f, q, n)` is a Taylor series).
    pub coordinates: rustc_hash::FxHashSet<&'a str>,
    /// The dimension of each definition, once checked.
    pub defs: Vec<Option<DimValue>>,
    /// A definition's value when it is a rational constant (exponents).
    pub constant: &'a dyn Fn(&str) -> Option<Q>,
    /// Whether a definition was used before it was checked.
    pub forward: bool,
    /// Where a name's dimension is written: its annotation, or its
    /// definition's name (an error's labels point there).
    pub origins: FxHashMap<&'a str, crate::diag::Span>,
}

type Checked<T> = Result<T, Diagnostic>;

/// `a + b − c` as its terms, left to right (no recursion: sums are
/// left-leaning trees as deep as they are long).
fn sum_terms(e: &Expr) -> Vec<&Expr> {
    let mut out = Vec::new();
    let mut cur = e;
    while let ExprKind::Bin(BinOp::Add | BinOp::Sub, a, b) = &cur.kind {
        out.push(&**b);
        cur = a;
    }
    out.push(cur);
    out.reverse();
    out
}

/// `a·b/c` as its factors with exponents ±1, left to right.
fn product_factors(e: &Expr) -> Vec<(&Expr, i64)> {
    let mut out = Vec::new();
    let mut cur = e;
    while let ExprKind::Bin(op @ (BinOp::Mul | BinOp::Div), a, b) = &cur.kind {
        out.push((&**b, if *op == BinOp::Div { -1 } else { 1 }));
        cur = a;
    }
    out.push((cur, 1));
    out.reverse();
    out
}

/// Call `f` on every name written in `roots`, in no particular order
/// (an explicit stack: no recursion over the syntax's depth).
pub(super) fn for_each_name<'e>(roots: &[&'e Expr], mut f: impl FnMut(&'e str)) {
    let mut stack: Vec<&Expr> = roots.to_vec();
    while let Some(e) = stack.pop() {
        match &e.kind {
            ExprKind::Name(n) => f(n),
            ExprKind::Neg(x) | ExprKind::Prime(x, _) => stack.push(x),
            ExprKind::Bin(_, a, b) | ExprKind::Assign(a, b) | ExprKind::Index(a, b) => {
                stack.push(a);
                stack.push(b);
            }
            // `rot(x, a)`: the axis names x, y, z are no names of the scene
            ExprKind::Call(Callee::Builtin(Builtin::Rot, _), args)
                if crate::scene::axis_name(args).is_some() =>
            {
                stack.extend(&args[1..])
            }
            ExprKind::Call(_, args) | ExprKind::Vector(args) => stack.extend(args),
            ExprKind::Num(_) | ExprKind::Degrees(_) => {}
        }
    }
}

fn is_sum(e: &Expr) -> bool {
    match &e.kind {
        ExprKind::Bin(BinOp::Add | BinOp::Sub, ..) => true,
        ExprKind::Neg(x) => is_sum(x),
        _ => false,
    }
}

impl<'a> Walker<'a> {
    pub fn time() -> DimForm {
        DimForm::known(super::dim::Dimension::TIME)
    }

    /// The dimension of `e`, which must be `want`'s when there is one.
    pub fn value(&mut self, e: &Expr, want: Option<&Want>) -> Checked<DimValue> {
        self.value_as(e, want, "this")
    }

    /// [`Walker::value`], naming `e` as `noun` ("this term") in an error.
    fn value_as(&mut self, e: &Expr, want: Option<&Want>, noun: &str) -> Checked<DimValue> {
        let v = self.value_inner(e, want)?;
        if let Some(w) = want {
            for c in v.components().iter().flatten() {
                self.expect(c, w, e, noun)?;
            }
        }
        Ok(v)
    }

    /// Unify `have` with `want`, or the error at `e`.
    pub fn expect(&mut self, have: &DimForm, want: &Want, e: &Expr, noun: &str) -> Checked<()> {
        if self.vars.unify(have, &want.form, e.span) {
            return Ok(());
        }
        let needed = self.needed(&want.form);
        let msg = format!(
            "{noun} is {}; {needed} is needed here ({})",
            self.vars.phrase(have),
            want.why.describe()
        );
        Err(self.error(e, msg, have, &want.form))
    }

    /// "a force", or "a pure number (dimensionless)".
    pub fn needed(&self, f: &DimForm) -> String {
        let f = self.vars.normalize(f);
        match f.as_known() {
            Some(d) if d.is_one() => "a pure number (dimensionless)".into(),
            _ => self.vars.phrase(&f),
        }
    }

    /// An error at `e` whose dimension `have` should be `want`, with the
    /// likely fix as its hint.
    pub fn error(&self, e: &Expr, msg: String, have: &DimForm, want: &DimForm) -> Diagnostic {
        if self.vars.exhausted() {
            return Diagnostic::error(
                e.span,
                format!(
                    "the dimension check gave up here: finding the dimensions of the names nobody annotated took more than {} substitutions",
                    crate::budget::grouped(crate::limits::MAX_DIMENSION_WORK as usize)
                ),
            )
            .with_hint("annotate the names whose dimensions are found from each other (`p: length`), or remove every annotation to skip the check").with_kind(crate::diag::ErrorKind::LimitExceeded);
        }
        let mut d =
            Diagnostic::error(e.span, msg).with_kind(crate::diag::ErrorKind::DimensionMismatch);
        for (span, message) in hint::origins(self, e) {
            d = d.with_label(span, message);
        }
        match hint::hint(self, e, have, want) {
            Some(h) => d.with_hint(h),
            None => d,
        }
    }

    fn value_inner(&mut self, e: &Expr, want: Option<&Want>) -> Checked<DimValue> {
        match &e.kind {
            ExprKind::Num(q) if num_traits::Zero::is_zero(q) => Ok(DimValue::Scalar(None)),
            ExprKind::Num(_) | ExprKind::Degrees(_) => Ok(DimValue::one()),
            ExprKind::Name(n) => Ok(self.name(n)),
            ExprKind::Neg(x) => self.value_as(x, want, "this"),
            ExprKind::Bin(BinOp::Add | BinOp::Sub, ..) => self.sum(e, want),
            ExprKind::Bin(BinOp::Mul | BinOp::Div, ..) => self.product(e, want),
            ExprKind::Bin(BinOp::Pow, base, exp) => self.power(base, exp),
            ExprKind::Prime(x, k) => {
                let v = self.value(x, None)?;
                let t = Self::time().pow(&Q::from_i64(i64::from(*k)));
                Ok(v.map(|f| f.div(&t)))
            }
            ExprKind::Vector(cs) => {
                let mut out = Vec::with_capacity(cs.len());
                for c in cs {
                    match self.value(c, None)? {
                        DimValue::Scalar(t) => out.push(t),
                        DimValue::Vector(_) => out.push(None),
                    }
                }
                Ok(DimValue::Vector(out))
            }
            ExprKind::Call(f, args) => super::call::call(self, f, args),
            ExprKind::Assign(_, v) => self.value(v, None),
            ExprKind::Index(v, k) => {
                let v = self.value(v, None)?;
                let k = match &k.kind {
                    ExprKind::Num(q) if q.is_integer() => q.to_integer().try_into().ok(),
                    _ => None,
                };
                let c = v.components();
                Ok(DimValue::Scalar(match k {
                    Some(k) if (1..=c.len()).contains(&k) => c[k - 1].clone(),
                    _ => None,
                }))
            }
        }
    }

    /// The dimension of a name.
    pub fn name(&mut self, n: &str) -> DimValue {
        match self.names.get(n) {
            Some(NameDim::Fixed(f)) => DimValue::Scalar(Some(f.clone())),
            Some(NameDim::Def(i)) => match self.defs.get(*i).cloned().flatten() {
                Some(v) => v,
                // not checked yet (a forward reference, in source order):
                // the pass is done again in dependency order
                None => {
                    self.forward = true;
                    DimValue::Scalar(Some(DimForm::var(self.vars.fresh(n))))
                }
            },
            Some(NameDim::Time) => DimValue::Scalar(Some(Self::time())),
            Some(NameDim::Pi) => DimValue::one(),
            None => DimValue::Scalar(Some(DimForm::var(self.vars.fresh(n)))),
        }
    }

    /// The unknown that stands for a name's dimension, if it has one.
    pub fn unknown_of(&self, n: &str) -> Option<DimVar> {
        match self.names.get(n) {
            Some(NameDim::Fixed(f)) => match &f.vars[..] {
                [(v, c)] if c.is_one() && f.base.is_one() => Some(*v),
                _ => None,
            },
            _ => None,
        }
    }

    /// A sum: every term of one dimension, `want`'s when there is one.
    fn sum(&mut self, e: &Expr, want: Option<&Want>) -> Checked<DimValue> {
        let terms = sum_terms(e);
        if let Some(w) = want {
            let mut out = DimValue::Scalar(None);
            for t in terms {
                let v = self.value_as(t, Some(w), "this term")?;
                if !matches!(v, DimValue::Scalar(None)) {
                    out = v;
                }
            }
            return Ok(out);
        }
        let mut values = Vec::with_capacity(terms.len());
        for t in &terms {
            values.push(self.value(t, None)?);
        }
        if let Some(same) = same_known(&values) {
            return Ok(same);
        }
        let width = values
            .iter()
            .map(|v| v.components().len())
            .max()
            .unwrap_or(1);
        let mut result = Vec::with_capacity(width);
        for k in 0..width {
            let column: Vec<(&Expr, &DimForm)> = terms
                .iter()
                .zip(&values)
                .filter_map(|(t, v)| {
                    v.components()
                        .get(k)
                        .and_then(|c| c.as_ref())
                        .map(|c| (*t, c))
                })
                .collect();
            result.push(self.same_dimension(&column)?);
        }
        Ok(match values.first() {
            Some(DimValue::Vector(_)) => DimValue::Vector(result),
            _ => DimValue::Scalar(result.pop().flatten()),
        })
    }

    /// The terms of a sum share one dimension: the one most of the known
    /// terms have (the first on a tie), or the first term's.
    fn same_dimension(&mut self, terms: &[(&Expr, &DimForm)]) -> Checked<Term> {
        let normal: Vec<DimForm> = terms.iter().map(|(_, f)| self.vars.normalize(f)).collect();
        // votes of the known dimensions: (first term, count)
        let mut votes: FxHashMap<Dimension, (usize, usize)> = FxHashMap::default();
        for (i, f) in normal.iter().enumerate() {
            if let Some(d) = f.as_known() {
                votes.entry(*d).or_insert((i, 0)).1 += 1;
            }
        }
        // the most votes; on a tie, the first term
        let best = votes
            .values()
            .max_by(|a, b| a.1.cmp(&b.1).then(b.0.cmp(&a.0)))
            .map(|&(i, _)| i);
        let Some(reference) = best.or((!normal.is_empty()).then_some(0)) else {
            return Ok(None);
        };
        let r = normal[reference].clone();
        for (i, (t, f)) in terms.iter().enumerate() {
            if i == reference || self.vars.unify(f, &r, t.span) {
                continue;
            }
            let others = if terms.len() == 2 {
                "the other term is"
            } else {
                "the other terms are"
            };
            let msg = format!(
                "this term is {}; {others} {}",
                self.vars.phrase(f),
                if terms.len() == 2 {
                    self.vars.phrase(&r)
                } else {
                    self.vars.plural(&r)
                }
            );
            return Err(self.error(t, msg, f, &r));
        }
        Ok(Some(r))
    }

    /// A product: the dimensions multiply. With `want` known and exactly
    /// one factor a sum, the sum is checked against what the other factors
    /// leave, so its wrong term is found.
    fn product(&mut self, e: &Expr, want: Option<&Want>) -> Checked<DimValue> {
        if want.is_none() {
            // the common case: the dimensions multiply (a product is a
            // left-leaning tree, as deep as it is long, like the syntax)
            if let ExprKind::Bin(op, a, b) = &e.kind {
                let l = self.value(a, None)?;
                let r = self.value(b, None)?;
                return Ok(multiply(&l, &r, if *op == BinOp::Div { -1 } else { 1 }));
            }
        }
        let factors = product_factors(e);
        let mut sums = factors.iter().enumerate().filter(|(_, f)| is_sum(f.0));
        let pushed = match (want, sums.next(), sums.next()) {
            (Some(_), Some((s, _)), None) => Some(s),
            _ => None,
        };
        if pushed.is_none() {
            // the common case: the dimensions multiply, left to right
            let mut out = DimValue::one();
            for (f, p) in &factors {
                let v = self.value(f, None)?;
                out = multiply(&out, &v, *p);
            }
            return Ok(out);
        }
        let mut values: Vec<Option<DimValue>> = vec![None; factors.len()];
        for (i, (f, _)) in factors.iter().enumerate() {
            if Some(i) != pushed {
                values[i] = Some(self.value(f, None)?);
            }
        }
        if let (Some(s), Some(w)) = (pushed, want) {
            // the other factors' product, when every one is a known scalar
            let mut rest = Some(DimForm::one());
            for (i, (_, p)) in factors.iter().enumerate() {
                if i == s {
                    continue;
                }
                rest = match (&rest, &values[i]) {
                    (Some(r), Some(DimValue::Scalar(Some(f)))) => {
                        Some(r.mul(&self.vars.normalize(f).pow(&Q::from_i64(*p))))
                    }
                    _ => None,
                };
            }
            let inner = rest.map(|r| {
                let need = w.form.div(&r).pow(&Q::from_i64(factors[s].1));
                Want {
                    form: need,
                    why: Why::Factor(Box::new(w.why.clone())),
                }
            });
            values[s] = Some(self.value(factors[s].0, inner.as_ref())?);
        }
        let mut out = DimValue::one();
        for ((_, p), v) in factors.iter().zip(values) {
            let v = v.unwrap_or(DimValue::Scalar(None));
            out = multiply(&out, &v, *p);
        }
        Ok(out)
    }

    /// `base^exp`: a rational exponent scales the dimension; any other
    /// needs a dimensionless base.
    fn power(&mut self, base: &Expr, exp: &Expr) -> Checked<DimValue> {
        if let Some(q) = self.constant(exp) {
            let b = self.value(base, None)?;
            return Ok(match &b {
                DimValue::Scalar(None) if q.is_positive() => b,
                _ => b.map(|f| f.pow(&q)),
            });
        }
        let one = DimForm::one();
        self.value(
            base,
            Some(&Want {
                form: one.clone(),
                why: Why::SymbolicPower,
            }),
        )?;
        self.value(
            exp,
            Some(&Want {
                form: one,
                why: Why::Exponent,
            }),
        )?;
        Ok(DimValue::one())
    }

    /// The value of `e` when it is a rational constant.
    pub fn constant(&self, e: &Expr) -> Option<Q> {
        match &e.kind {
            ExprKind::Num(q) => Some(Q::from_big(q.clone())),
            ExprKind::Neg(x) => self.constant(x).map(|q| -q),
            ExprKind::Name(n) => (self.constant)(n),
            ExprKind::Bin(op, a, b) => {
                let (mut x, y) = (self.constant(a)?, self.constant(b)?);
                match op {
                    BinOp::Add => x += y,
                    BinOp::Sub => x -= y,
                    BinOp::Mul => x *= y,
                    BinOp::Div => x = x.checked_div(&y)?,
                    BinOp::Pow => {
                        let k = y.as_i64().filter(|k| k.abs() <= 64)?;
                        x = x.pow(i32::try_from(k).ok()?)?;
                    }
                }
                Some(x)
            }
            _ => None,
        }
    }
}

/// The common value of scalar terms that all have one known dimension
/// (the usual sum), without the bookkeeping of [`Walker::same_dimension`].
fn same_known(values: &[DimValue]) -> Option<DimValue> {
    let mut common: Option<&DimForm> = None;
    for v in values {
        match v {
            DimValue::Scalar(None) => {}
            DimValue::Scalar(Some(f)) if f.vars.is_empty() => match common {
                None => common = Some(f),
                Some(c) if c.base == f.base && !f.base.overflowed() => {}
                Some(_) => return None,
            },
            _ => return None,
        }
    }
    Some(DimValue::Scalar(common.cloned()))
}

/// `a · b^p` for dimensions of values (a zero factor makes the product 0).
fn multiply(a: &DimValue, b: &DimValue, p: i64) -> DimValue {
    let times = |x: &Term, y: &Term| -> Term {
        match (x, y) {
            (Some(x), Some(y)) if p == 1 => Some(x.mul(y)),
            (Some(x), Some(y)) => Some(x.div(y)),
            _ => None,
        }
    };
    match (a, b) {
        (DimValue::Scalar(x), DimValue::Scalar(y)) => DimValue::Scalar(times(x, y)),
        (DimValue::Scalar(x), DimValue::Vector(c)) => {
            DimValue::Vector(c.iter().map(|y| times(x, y)).collect())
        }
        (DimValue::Vector(c), DimValue::Scalar(y)) => {
            DimValue::Vector(c.iter().map(|x| times(x, y)).collect())
        }
        // a rotation (nine pure numbers) composes with a rotation and
        // turns a space vector (of one dimension: its components mix)
        (DimValue::Vector(c), DimValue::Vector(d)) if c.len() == 9 => match d.len() {
            9 => DimValue::Vector(d.clone()),
            _ => DimValue::Vector(vec![d.iter().flatten().next().cloned(); d.len()]),
        },
        // vector × vector is refused by the evaluator before this runs
        (DimValue::Vector(c), DimValue::Vector(_)) => DimValue::Vector(vec![None; c.len()]),
    }
}
