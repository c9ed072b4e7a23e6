//! Evaluation of syntax trees into canonical expressions.

use super::Binding;
use crate::diag::Diagnostic;
use crate::expr::{func, Expr, MathError};
use crate::num::Q;
use crate::parse::ast::{self, BinOp, ExprKind, Role, Span};
use rustc_hash::FxHashMap;

#[derive(Clone)]
enum State {
    Todo,
    Busy,
    Done(Expr),
}

pub(crate) struct Evaluator<'a> {
    names: &'a FxHashMap<String, (Binding, Span)>,
    defs: Vec<(&'a ast::Ident, Option<&'a ast::Expr>)>,
    state: Vec<State>,
    /// The chain of definitions being evaluated (for cycle reports).
    stack: Vec<usize>,
    /// Parameters and coordinates already turned into expressions.
    atoms: FxHashMap<&'a str, Expr>,
    /// Time derivatives already taken, by shared value and order (the
    /// value is kept alive beside its derivative so its id stays unique).
    derivatives: FxHashMap<(usize, u32), (Expr, Expr)>,
    pub warnings: Vec<Diagnostic>,
}

const FUNCTIONS: &[(&str, usize)] = &[
    ("sin", 1),
    ("cos", 1),
    ("tan", 1),
    ("sqrt", 1),
    ("exp", 1),
    ("ln", 1),
    ("atan", 1),
];

impl<'a> Evaluator<'a> {
    pub fn new(
        names: &'a FxHashMap<String, (Binding, Span)>,
        defs: &'a [(&'a ast::Ident, &'a ast::Expr, Option<Role>)],
    ) -> Evaluator<'a> {
        Evaluator {
            names,
            defs: defs.iter().map(|(n, e, _)| (*n, Some(*e))).collect(),
            state: vec![State::Todo; defs.len()],
            stack: Vec::new(),
            atoms: FxHashMap::default(),
            derivatives: FxHashMap::default(),
            warnings: Vec::new(),
        }
    }

    /// An evaluator whose definitions are already known.
    pub fn with_values(
        names: &'a FxHashMap<String, (Binding, Span)>,
        values: Vec<Expr>,
    ) -> Evaluator<'a> {
        Evaluator {
            names,
            defs: Vec::new(),
            state: values.into_iter().map(State::Done).collect(),
            stack: Vec::new(),
            atoms: FxHashMap::default(),
            derivatives: FxHashMap::default(),
            warnings: Vec::new(),
        }
    }

    /// The value of definition `i`, evaluating it (and what it needs) first.
    pub fn definition(&mut self, i: usize) -> Result<Expr, Diagnostic> {
        match &self.state[i] {
            State::Done(e) => return Ok(e.clone()),
            State::Busy => {
                return Err(Diagnostic::global(
                    "internal error: a definition re-entered itself",
                ))
            }
            State::Todo => {}
        }
        let Some((_, Some(body))) = self.defs.get(i).copied() else {
            return Err(Diagnostic::global("internal: definition without a body"));
        };
        self.state[i] = State::Busy;
        self.stack.push(i);
        let v = self.expr(body);
        self.stack.pop();
        let v = v?;
        self.state[i] = State::Done(v.clone());
        Ok(v)
    }

    fn err(&self, span: Span, e: MathError) -> Diagnostic {
        let d = Diagnostic::error(span, e.message);
        match e.hint {
            Some(h) => d.with_hint(h),
            None => d,
        }
    }

    pub fn expr(&mut self, e: &ast::Expr) -> Result<Expr, Diagnostic> {
        match &e.kind {
            ExprKind::Num(r) => Ok(Expr::rational(Q::from_big(r.clone()))),
            ExprKind::Degrees(r) => {
                let q = Q::from_big(r.clone());
                let k = q.checked_div(&Q::from_i64(180)).unwrap_or_else(Q::zero);
                Ok(Expr::pi().scale(&k))
            }
            ExprKind::Name(n) => self.name(n, e.span),
            ExprKind::Neg(x) => Ok(self.expr(x)?.neg()),
            ExprKind::Bin(op, a, b) => {
                let x = self.expr(a)?;
                match op {
                    BinOp::Pow => self.pow(&x, b, e.span),
                    _ => {
                        let y = self.expr(b)?;
                        match op {
                            BinOp::Add => Ok(x.add(&y)),
                            BinOp::Sub => Ok(x.sub(&y)),
                            BinOp::Mul => Ok(x.mul(&y)),
                            _ => x.div(&y).map_err(|_| {
                                Diagnostic::error(
                                    b.span,
                                    "division by zero: this divisor is exactly 0",
                                )
                                .with_hint("check the definitions it uses")
                            }),
                        }
                    }
                }
            }
            ExprKind::Call(f, args) => self.call(f, args, e.span),
            ExprKind::Vector(_) => Err(Diagnostic::error(e.span, "vectors are not evaluated yet")),
            ExprKind::Prime(x, order) => {
                let v = self.expr(x)?;
                if !v.is_time_dependent() {
                    let what = match &x.kind {
                        ExprKind::Name(n) => format!("`{n}`"),
                        _ => "this expression".to_string(),
                    };
                    return Err(Diagnostic::error(
                        x.span,
                        format!("{what} is not a function of time, so `'` cannot be taken"),
                    )
                    .with_hint("`'` is d/dt: it applies to coordinates, `t`, and expressions built from them; declare it in `coordinates` if it moves"));
                }
                let key = (v.id(), *order);
                if let Some((_, d)) = self.derivatives.get(&key) {
                    return Ok(d.clone());
                }
                let mut d = v.clone();
                for _ in 0..*order {
                    d = d.dt();
                }
                self.derivatives.insert(key, (v, d.clone()));
                Ok(d)
            }
        }
    }

    fn name(&mut self, n: &str, span: Span) -> Result<Expr, Diagnostic> {
        if let Some(e) = self.atoms.get(n) {
            return Ok(e.clone());
        }
        match self.names.get_key_value(n) {
            Some((key, (Binding::Param, _))) => {
                let e = Expr::param(n);
                self.atoms.insert(key.as_str(), e.clone());
                Ok(e)
            }
            Some((key, (Binding::Coord, _))) => {
                let e = Expr::coord(n, 0);
                self.atoms.insert(key.as_str(), e.clone());
                Ok(e)
            }
            Some((_, (Binding::Time, _))) => Ok(Expr::time()),
            Some((_, (Binding::Pi, _))) => Ok(Expr::pi()),
            Some((_, (Binding::Def(i), _))) => {
                let i = *i;
                if matches!(self.state.get(i), Some(State::Busy)) {
                    let start = self.stack.iter().position(|&j| j == i).unwrap_or(0);
                    let mut chain: Vec<String> = self.stack[start..]
                        .iter()
                        .filter_map(|&j| self.defs.get(j).map(|d| d.0.name.clone()))
                        .collect();
                    chain.push(n.to_string());
                    return Err(Diagnostic::error(
                        span,
                        format!("cyclic definition: {}", chain.join(" → ")),
                    )
                    .with_hint("a definition cannot use itself, directly or through others"));
                }
                self.definition(i)
            }
            None => {
                let mut d = Diagnostic::error(span, format!("unknown name `{n}`"));
                let near = self.nearest(n);
                d = d.with_hint(match near {
                    Some(m) => format!("did you mean `{m}`? Otherwise declare it with `parameters {n}` or define it with `{n} = …`"),
                    None => format!("declare it with `parameters {n}` (a constant) or `coordinates {n}` (a function of time), or define it with `{n} = …`"),
                });
                Err(d)
            }
        }
    }

    fn nearest(&self, n: &str) -> Option<String> {
        let mut best: Option<(usize, &String)> = None;
        for k in self.names.keys() {
            let d = edit_distance(n, k);
            if d <= 2 && d < n.chars().count() && best.is_none_or(|(bd, _)| d < bd) {
                best = Some((d, k));
            }
        }
        best.map(|(_, k)| k.clone())
    }

    fn pow(&mut self, base: &Expr, exp: &ast::Expr, span: Span) -> Result<Expr, Diagnostic> {
        let e = self.expr(exp)?;
        let Some(q) = e.as_rational() else {
            return Err(Diagnostic::error(
                exp.span,
                "the exponent must be a number: symbolic powers are not supported",
            )
            .with_hint("write exp(y*ln(x)) for x^y"));
        };
        if q.is_integer() {
            let n = q
                .as_i64()
                .filter(|n| n.abs() <= 10_000)
                .ok_or_else(|| Diagnostic::error(exp.span, format!("exponent {q} is too large")))?;
            return base.powi(n).map_err(|m| self.err(span, m));
        }
        let twice = &q * &Q::from_i64(2);
        if twice.is_integer() {
            let n = twice
                .as_i64()
                .filter(|n| n.abs() <= 10_000)
                .ok_or_else(|| Diagnostic::error(exp.span, format!("exponent {q} is too large")))?;
            let r = func::sqrt(base).map_err(|m| self.err(span, m))?;
            return r.powi(n).map_err(|m| self.err(span, m));
        }
        Err(Diagnostic::error(
            exp.span,
            format!("the exponent {q} is not exact here: only integers and halves are"),
        )
        .with_hint("qdot keeps results exact; square roots are supported, other roots are not yet"))
    }

    fn call(&mut self, f: &ast::Ident, args: &[ast::Expr], span: Span) -> Result<Expr, Diagnostic> {
        let Some(&(_, arity)) = FUNCTIONS.iter().find(|(n, _)| *n == f.name) else {
            let list: Vec<&str> = FUNCTIONS.iter().map(|(n, _)| *n).collect();
            let hint = if self.names.contains_key(&f.name) {
                format!(
                    "`{}` is not a function; write `{}*(…)` to multiply",
                    f.name, f.name
                )
            } else {
                format!("the functions are {}", list.join(", "))
            };
            return Err(
                Diagnostic::error(f.span, format!("unknown function `{}`", f.name)).with_hint(hint),
            );
        };
        if args.len() != arity {
            return Err(Diagnostic::error(
                span,
                format!("`{}` takes {arity} argument, not {}", f.name, args.len()),
            )
            .with_hint(if f.name == "atan" {
                "atan(y/x) is the arctangent of one ratio"
            } else {
                "one argument, in parentheses"
            }));
        }
        let x = self.expr(&args[0])?;
        let r = match f.name.as_str() {
            "sin" => Ok(func::sin(&x)),
            "cos" => Ok(func::cos(&x)),
            "tan" => func::tan(&x),
            "sqrt" => func::sqrt(&x),
            "exp" => Ok(func::exp(&x)),
            "ln" => func::ln(&x),
            _ => Ok(func::atan(&x)),
        };
        r.map_err(|m| self.err(span, m))
    }
}

/// Levenshtein distance over characters.
fn edit_distance(a: &str, b: &str) -> usize {
    let a: Vec<char> = a.chars().collect();
    let b: Vec<char> = b.chars().collect();
    let mut prev: Vec<usize> = (0..=b.len()).collect();
    for i in 1..=a.len() {
        let mut cur = vec![i; b.len() + 1];
        for j in 1..=b.len() {
            let cost = usize::from(a[i - 1] != b[j - 1]);
            cur[j] = (prev[j] + 1).min(cur[j - 1] + 1).min(prev[j - 1] + cost);
        }
        prev = cur;
    }
    prev[b.len()]
}
