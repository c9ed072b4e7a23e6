//! Evaluation of syntax trees into canonical expressions.

mod frames;
mod pending;
pub use frames::axis_name;
pub(crate) use pending::{names_in, Entry};

use super::{Binding, Value};
use crate::diag::Diagnostic;
use crate::expr::atom::{self, Atom};
use crate::expr::tape::Tape;
use crate::expr::{func, Expr, MathError};
use crate::num::Q;
use crate::parse::ast::{self, BinOp, ExprKind, Role, Span};
use crate::parse::functions::{self, Arity, Builtin};
use crate::poly::Var;
use rustc_hash::FxHashMap;

#[derive(Clone)]
enum State {
    Todo,
    Busy,
    Done(Value),
}

pub(crate) struct SyntaxEvaluator<'a> {
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
    /// The scene's `assume` facts, once read: √(q²) is q where they make
    /// q positive (−q where negative).
    pub assumed: crate::algebra::assume::Assumptions,
    /// With a tape, moving vectors and frames are kept as intermediates:
    /// their components are named on it, and later values mention the
    /// names ([`crate::scene::Scene::parse_structured`]).
    pub tape: Option<Tape>,
    /// Per definition: whether it may be kept (not an energy or other role).
    keepable: Vec<bool>,
    /// Per definition: whether the user asked to keep it (`--keep`), a
    /// scalar too.
    pub kept_by_name: Vec<bool>,
}

/// How `series` and `parallel` combine springs.
#[derive(Clone, Copy)]
enum Springs {
    /// 1/Σ(1/k_i).
    Series,
    /// Σ k_i.
    Parallel,
}

impl Springs {
    fn builtin(self) -> Builtin {
        match self {
            Springs::Series => Builtin::Series,
            Springs::Parallel => Builtin::Parallel,
        }
    }
}

/// The product `dot` or `cross` takes.
#[derive(Clone, Copy)]
enum Product {
    Dot,
    Cross,
}

impl Product {
    fn builtin(self) -> Builtin {
        match self {
            Product::Dot => Builtin::Dot,
            Product::Cross => Builtin::Cross,
        }
    }
}

/// A definition on the path of [`SyntaxEvaluator::evaluate_dependencies`]: its
/// index, the definitions it uses (with the span of the name), and how many
/// of those are handled.
type PathStep = (usize, Vec<(usize, Span)>, usize);

/// "cyclic definition: a → b → a"; a long cycle shows its first and last
/// five links and its length.
fn cycle_message(chain: &[String]) -> String {
    if chain.len() <= 12 {
        return format!("cyclic definition: {}", chain.join(" → "));
    }
    let n = chain.len();
    format!(
        "cyclic definition: {} → … → {} ({} definitions)",
        chain[..5].join(" → "),
        chain[n - 6..].join(" → "),
        n - 1
    )
}

use crate::limits::{MAX_FUNCTION_ARGUMENT_SIZE, MAX_TAYLOR_ORDER, MAX_TIME_DERIVATIVE_ORDER};

/// Hint for a vector where a number is needed.
const HINT_VECTOR: &str =
    "vectors combine with + and -, scale by numbers, and reduce with dot(a, b), cross(a, b) or norm(a)";

impl<'a> SyntaxEvaluator<'a> {
    pub fn new(
        names: &'a FxHashMap<String, (Binding, Span)>,
        defs: &'a [(&'a ast::Ident, &'a ast::Expr, Option<Role>)],
    ) -> SyntaxEvaluator<'a> {
        SyntaxEvaluator {
            names,
            defs: defs.iter().map(|(n, e, _)| (*n, Some(*e))).collect(),
            state: vec![State::Todo; defs.len()],
            stack: Vec::new(),
            atoms: FxHashMap::default(),
            derivatives: FxHashMap::default(),
            warnings: Vec::new(),
            assumed: Default::default(),
            tape: None,
            keepable: defs.iter().map(|d| d.2.is_none()).collect(),
            kept_by_name: vec![false; defs.len()],
        }
    }

    /// √x, with √(q²) = ±q where the scene's assumptions decide q's sign.
    fn root(&self, x: &Expr) -> Result<Expr, MathError> {
        let r = func::sqrt(x)?;
        if self.assumed.is_empty() {
            return Ok(r);
        }
        let Some(atom::Atom::SqrtOf(u)) = r.as_var().map(atom::atom) else {
            return Ok(r);
        };
        let Some(q) = crate::expr::print::square_root_of_square(&u) else {
            return Ok(r);
        };
        let sign = crate::algebra::assume::sign_under(&self.assumed, &q);
        Ok(match sign {
            Some(crate::algebra::sign::Sign::Positive) => q,
            Some(crate::algebra::sign::Sign::Negative) => q.neg(),
            _ => r,
        })
    }

    /// An evaluator whose definitions are already known.
    pub fn with_values(
        names: &'a FxHashMap<String, (Binding, Span)>,
        values: Vec<Value>,
    ) -> SyntaxEvaluator<'a> {
        SyntaxEvaluator {
            names,
            defs: Vec::new(),
            state: values.into_iter().map(State::Done).collect(),
            stack: Vec::new(),
            atoms: FxHashMap::default(),
            derivatives: FxHashMap::default(),
            warnings: Vec::new(),
            assumed: Default::default(),
            tape: None,
            keepable: Vec::new(),
            kept_by_name: Vec::new(),
        }
    }

    /// The value of definition `i`, evaluating it (and what it needs) first.
    pub fn definition(&mut self, i: usize) -> Result<Value, Diagnostic> {
        if matches!(self.state.get(i), Some(State::Todo)) && self.stack.is_empty() {
            self.evaluate_dependencies(i)?;
        }
        self.definition_now(i)
    }

    /// Evaluate the definitions `i` uses, and theirs, deepest first, with an
    /// explicit stack: a chain of thousands of definitions, each using the
    /// next, must not recurse once per link. A cycle is reported here with
    /// the whole chain.
    fn evaluate_dependencies(&mut self, i: usize) -> Result<(), Diagnostic> {
        let mut path: Vec<PathStep> = vec![(i, self.dependencies(i), 0)];
        let mut on_path = vec![false; self.state.len()];
        on_path[i] = true;
        while let Some((j, deps, next)) = path.last_mut() {
            let Some(&(k, span)) = deps.get(*next) else {
                let j = *j;
                path.pop();
                on_path[j] = false;
                if !path.is_empty() {
                    // `i` itself is left to the caller
                    self.definition_now(j)?;
                }
                continue;
            };
            *next += 1;
            if on_path[k] {
                let start = path.iter().position(|p| p.0 == k).unwrap_or(0);
                let mut chain: Vec<String> = path[start..]
                    .iter()
                    .filter_map(|p| self.defs.get(p.0).map(|d| d.0.name.clone()))
                    .collect();
                chain.push(self.defs.get(k).map_or(String::new(), |d| d.0.name.clone()));
                return Err(Diagnostic::error(span, cycle_message(&chain))
                    .with_hint("a definition cannot use itself, directly or through others")
                    .with_kind(crate::diag::ErrorKind::InvalidScene));
            }
            if matches!(self.state.get(k), Some(State::Todo)) {
                on_path[k] = true;
                let deps = self.dependencies(k);
                path.push((k, deps, 0));
            }
        }
        Ok(())
    }

    /// The definitions named in definition `i`'s body (with the span of the
    /// name), in the order evaluation meets them: left to right.
    fn dependencies(&self, i: usize) -> Vec<(usize, Span)> {
        let Some((_, Some(body))) = self.defs.get(i).copied() else {
            return Vec::new();
        };
        names_in(self.names, body)
            .into_iter()
            .filter_map(|(n, span)| match self.names.get(n) {
                Some((Binding::Def(k), _)) => Some((*k, span)),
                _ => None,
            })
            .collect()
    }

    /// [`SyntaxEvaluator::definition`] once its dependencies are evaluated (or
    /// inside another definition's evaluation).
    fn definition_now(&mut self, i: usize) -> Result<Value, Diagnostic> {
        match &self.state[i] {
            State::Done(e) => return Ok(e.clone()),
            State::Busy => {
                return Err(
                    Diagnostic::global("internal error: a definition re-entered itself")
                        .with_kind(crate::diag::ErrorKind::Internal),
                )
            }
            State::Todo => {}
        }
        let Some((_, Some(body))) = self.defs.get(i).copied() else {
            return Err(Diagnostic::global("internal: definition without a body")
                .with_kind(crate::diag::ErrorKind::Internal));
        };
        self.state[i] = State::Busy;
        self.stack.push(i);
        let name = self.defs[i].0;
        let _context = crate::budget::enter(
            || format!("evaluating `{}`", name.name),
            Some((body.span.start, body.span.end)),
        );
        let v = self.value(body);
        self.stack.pop();
        let v = self.kept(i, v?);
        self.state[i] = State::Done(v.clone());
        Ok(v)
    }

    /// With a tape, definition `i`'s value as later values see it: a moving
    /// vector's components and a moving frame's matrix and angular velocity
    /// named on the tape (`P_x`, `B_12`, `omega_B_x`).
    fn kept(&mut self, i: usize, v: Value) -> Value {
        let Some(tape) = self.tape.as_mut() else {
            return v;
        };
        if !self.keepable.get(i).copied().unwrap_or(false) {
            return v;
        }
        let name = self.defs[i].0.name.as_str();
        if self.kept_by_name.get(i).copied().unwrap_or(false) {
            if let Value::Scalar(x) = v {
                return Value::Scalar(tape.keep(name, x));
            }
        } else if self.kept_by_name.iter().any(|&k| k) {
            // `--keep` names what to keep: nothing else is
            return v;
        }
        match v {
            Value::Vector(c) if c.iter().any(Expr::is_time_dependent) => {
                let n = c.len();
                Value::Vector(
                    c.into_iter()
                        .enumerate()
                        .map(|(k, x)| tape.define(&format!("{name}_{}", component_name(k, n)), x))
                        .collect(),
                )
            }
            Value::Rotation(r) if r.is_moving() => {
                let omega = r.omega_frame();
                let m = r.matrix();
                let matrix: crate::scene::rotation::Matrix3 = std::array::from_fn(|a| {
                    std::array::from_fn(|b| {
                        tape.define(&format!("{name}_{}{}", a + 1, b + 1), m[a][b].clone())
                    })
                });
                let omega: [Expr; 3] = std::array::from_fn(|k| {
                    tape.define(
                        &format!("omega_{name}_{}", component_name(k, 3)),
                        omega[k].clone(),
                    )
                });
                Value::Rotation(Box::new(r.with_structure(matrix, omega)))
            }
            other => other,
        }
    }

    /// d/dt through the tape's intermediates when there is one.
    pub(crate) fn time_derivative(&mut self, e: &Expr) -> Expr {
        match self.tape.as_mut() {
            Some(tape) => tape.dt(e),
            None => e.dt(),
        }
    }

    /// An error unless `v` is written without intermediates: `subs` and
    /// `taylor` need the expanded value (an intermediate hides the
    /// coordinates it depends on).
    pub(super) fn expanded_only(
        &self,
        v: &Value,
        span: Span,
        what: &str,
    ) -> Result<(), Diagnostic> {
        if self.tape.is_none() {
            return Ok(());
        }
        let named = v.components().iter().any(|c| {
            c.vars()
                .into_iter()
                .any(|w| matches!(atom::atom(w), Atom::Named(_)))
        });
        if named {
            return Err(Diagnostic::error(
                span,
                format!("{what} needs this value expanded, and it is kept as intermediates"),
            )
            .with_hint("derive the scene expanded (`--expand`)")
            .with_kind(crate::diag::ErrorKind::Unsupported));
        }
        Ok(())
    }

    fn err(&self, span: Span, e: MathError) -> Diagnostic {
        let d = Diagnostic::error(span, e.message).with_kind(crate::diag::ErrorKind::Undefined);
        match e.hint {
            Some(h) => d.with_hint(h),
            None => d,
        }
    }

    /// A scalar expression: a vector here is an error.
    pub fn expr(&mut self, e: &ast::Expr) -> Result<Expr, Diagnostic> {
        let v = self.value(e)?;
        self.scalar(v, e.span, "a number")
    }

    /// `v` as a scalar, or an error at `span` saying a vector is not `what`.
    fn scalar(&self, v: Value, span: Span, what: &str) -> Result<Expr, Diagnostic> {
        match v {
            Value::Scalar(x) => Ok(x),
            Value::Vector(c) => Err(Diagnostic::error(
                span,
                format!(
                    "expected {what}, found a vector with {} components",
                    c.len()
                ),
            )
            .with_hint(HINT_VECTOR)
            .with_kind(crate::diag::ErrorKind::TypeMismatch)),
            Value::Rotation(_) => Err(Diagnostic::error(
                span,
                format!("expected {what}, found a rotation (a frame)"),
            )
            .with_hint(frames::HINT_ROTATION)
            .with_kind(crate::diag::ErrorKind::TypeMismatch)),
        }
    }

    /// A scalar, a vector or a rotation.
    pub fn value(&mut self, e: &ast::Expr) -> Result<Value, Diagnostic> {
        match &e.kind {
            ExprKind::Num(r) => Ok(Value::Scalar(Expr::rational(Q::from_big(r.clone())))),
            ExprKind::Degrees(r) => {
                let q = Q::from_big(r.clone());
                let k = q.checked_div(&Q::from_i64(180)).unwrap_or_else(Q::zero);
                Ok(Value::Scalar(Expr::pi().scale(&k)))
            }
            ExprKind::Name(n) => self.name(n, e.span),
            ExprKind::Neg(x) => {
                let v = self.value(x)?;
                frames::not_a_rotation(&v, x.span, "can't be negated")?;
                Ok(v.map(|c| c.neg()))
            }
            ExprKind::Index(v, k) => self.index(v, k),
            ExprKind::Bin(op, a, b) => {
                let x = self.value(a)?;
                if *op == BinOp::Pow {
                    let x = match x {
                        Value::Scalar(x) => x,
                        Value::Vector(_) => {
                            return Err(Diagnostic::error(
                                a.span,
                                "a vector can't be raised to a power",
                            )
                            .with_hint("for the squared length of a vector v write dot(v, v)").with_kind(crate::diag::ErrorKind::TypeMismatch))
                        }
                        Value::Rotation(_) => {
                            return Err(Diagnostic::error(
                                a.span,
                                "a rotation can't be raised to a power",
                            )
                            .with_hint("compose rotations with `*`: rot(z, a) * rot(z, b)").with_kind(crate::diag::ErrorKind::TypeMismatch))
                        }
                    };
                    return Ok(Value::Scalar(self.pow(&x, b, e.span)?));
                }
                let y = self.value(b)?;
                self.binary(*op, x, y, a, b)
            }
            ExprKind::Call(f, args) => self.call(f, args, e.span),
            ExprKind::Assign(..) => Err(Diagnostic::error(
                e.span,
                "`x = value` is a named argument, and only subs, taylor and series take one",
            )
            .with_hint("write subs(E, x = 0), taylor(f, x = a, 3); a definition `x = …` stands on a line of its own").with_kind(crate::diag::ErrorKind::InvalidScene)),
            ExprKind::Vector(items) => {
                if !(2..=3).contains(&items.len()) {
                    return Err(Diagnostic::error(
                        e.span,
                        format!(
                            "a vector has 2 or 3 components, this one has {}",
                            items.len()
                        ),
                    )
                    .with_hint("write a plane vector [x, y] or a space vector [x, y, z]").with_kind(crate::diag::ErrorKind::InvalidScene));
                }
                let mut out = Vec::with_capacity(items.len());
                for it in items {
                    let v = self.value(it)?;
                    out.push(self.scalar(v, it.span, "a number as a vector component")?);
                }
                Ok(Value::Vector(out))
            }
            ExprKind::Prime(x, order) => {
                let v = self.value(x)?;
                frames::not_a_rotation(&v, x.span, "has no time derivative `'`; its angular velocity is omega(F)")?;
                let moving = v.components().iter().any(|s| s.is_time_dependent());
                if !moving {
                    let what = match &x.kind {
                        ExprKind::Name(n) => format!("`{n}`"),
                        _ => "this expression".to_string(),
                    };
                    return Err(Diagnostic::error(
                        x.span,
                        format!("{what} is not a function of time, so `'` cannot be taken"),
                    )
                    .with_hint("`'` is d/dt: it applies to coordinates, `t`, and expressions built from them; declare it in `coordinates` if it moves").with_kind(crate::diag::ErrorKind::InvalidScene));
                }
                self.check_derivative_order(&v, *order, e.span)?;
                Ok(v.map(|c| self.dt(c, *order)))
            }
        }
    }

    /// An error when taking `order` more time derivatives of `v` would pass
    /// [`MAX_TIME_DERIVATIVE_ORDER`].
    fn check_derivative_order(&self, v: &Value, order: u32, span: Span) -> Result<(), Diagnostic> {
        let Some((name, k)) = v
            .components()
            .iter()
            .filter_map(|c| c.highest_time_derivative())
            .max_by_key(|(_, k)| *k)
        else {
            return Ok(());
        };
        let total = k.saturating_add(order);
        if total <= MAX_TIME_DERIVATIVE_ORDER {
            return Ok(());
        }
        Err(Diagnostic::error(
            span,
            format!(
                "this takes the time derivative of order {total} of `{name}`; qdot allows at most {MAX_TIME_DERIVATIVE_ORDER}"
            ),
        )
        .with_hint("mechanics needs velocities and accelerations (x', x''); each further order multiplies the terms").with_kind(crate::diag::ErrorKind::LimitExceeded))
    }

    /// The `order`-th time derivative, memoized by the shared value.
    fn dt(&mut self, v: &Expr, order: u32) -> Expr {
        let key = (v.id(), order);
        if let Some((_, d)) = self.derivatives.get(&key) {
            return d.clone();
        }
        let mut d = v.clone();
        for _ in 0..order {
            d = self.time_derivative(&d);
        }
        self.derivatives.insert(key, (v.clone(), d.clone()));
        d
    }

    /// `x op y` for + − * / on scalars and vectors.
    fn binary(
        &self,
        op: BinOp,
        x: Value,
        y: Value,
        a: &ast::Expr,
        b: &ast::Expr,
    ) -> Result<Value, Diagnostic> {
        let span = a.span.to(b.span);
        let div = |x: &Expr, y: &Expr| {
            x.div(y).map_err(|e| {
                if y.is_zero() {
                    Diagnostic::error(b.span, "division by zero: this divisor is exactly 0")
                        .with_hint("check the definitions it uses")
                        .with_kind(crate::diag::ErrorKind::Undefined)
                } else {
                    self.err(b.span, e)
                }
            })
        };
        if matches!(x, Value::Rotation(_)) || matches!(y, Value::Rotation(_)) {
            return frames::rotation_binary(op, x, y, a, b);
        }
        match (op, x, y) {
            (BinOp::Add, Value::Scalar(x), Value::Scalar(y)) => Ok(Value::Scalar(x.add(&y))),
            (BinOp::Sub, Value::Scalar(x), Value::Scalar(y)) => Ok(Value::Scalar(x.sub(&y))),
            (BinOp::Mul, Value::Scalar(x), Value::Scalar(y)) => Ok(Value::Scalar(x.mul(&y))),
            (BinOp::Div, Value::Scalar(x), Value::Scalar(y)) => Ok(Value::Scalar(div(&x, &y)?)),
            (BinOp::Add | BinOp::Sub, Value::Vector(u), Value::Vector(w)) => {
                if u.len() != w.len() {
                    return Err(Diagnostic::error(
                        span,
                        format!(
                            "vectors of different sizes: {} and {} components",
                            u.len(),
                            w.len()
                        ),
                    )
                    .with_hint(
                        "write plane vectors as [x, y, 0] to combine them with space vectors",
                    )
                    .with_kind(crate::diag::ErrorKind::TypeMismatch));
                }
                let f = if op == BinOp::Add {
                    Expr::add
                } else {
                    Expr::sub
                };
                Ok(Value::Vector(
                    u.iter().zip(&w).map(|(p, q)| f(p, q)).collect(),
                ))
            }
            (BinOp::Add | BinOp::Sub, x, _) => {
                let sign = if op == BinOp::Add { "add" } else { "subtract" };
                let sides = if matches!(x, Value::Vector(_)) {
                    "the left side is a vector and the right side a number"
                } else {
                    "the left side is a number and the right side a vector"
                };
                Err(Diagnostic::error(span, format!("can't {sign} a vector and a number"))
                    .with_hint(format!("{sides}; both sides of + and - must be numbers, or vectors of the same size")).with_kind(crate::diag::ErrorKind::TypeMismatch))
            }
            (BinOp::Mul, Value::Scalar(k), Value::Vector(u))
            | (BinOp::Mul, Value::Vector(u), Value::Scalar(k)) => {
                Ok(Value::Vector(u.iter().map(|c| c.mul(&k)).collect()))
            }
            (BinOp::Mul, Value::Vector(_), Value::Vector(_)) => Err(Diagnostic::error(
                span,
                "two vectors can't be multiplied with `*`",
            )
            .with_hint(
                "write dot(a, b) for the scalar product or cross(a, b) for the vector product",
            )
            .with_kind(crate::diag::ErrorKind::TypeMismatch)),
            (BinOp::Div, Value::Vector(u), Value::Scalar(k)) => {
                let mut out = Vec::with_capacity(u.len());
                for c in &u {
                    out.push(div(c, &k)?);
                }
                Ok(Value::Vector(out))
            }
            (BinOp::Div, _, Value::Vector(_)) => {
                Err(Diagnostic::error(b.span, "can't divide by a vector")
                    .with_hint("divide by a number, such as norm(v)")
                    .with_kind(crate::diag::ErrorKind::TypeMismatch))
            }
            (BinOp::Pow, ..) => Err(Diagnostic::global("internal: power on a vector")
                .with_kind(crate::diag::ErrorKind::Internal)),
            (_, Value::Rotation(_), _) | (_, _, Value::Rotation(_)) => Err(Diagnostic::global(
                "internal: a rotation in vector arithmetic",
            )
            .with_kind(crate::diag::ErrorKind::Internal)),
        }
    }

    fn name(&mut self, n: &str, span: Span) -> Result<Value, Diagnostic> {
        if let Some(e) = self.atoms.get(n) {
            return Ok(Value::Scalar(e.clone()));
        }
        match self.names.get_key_value(n) {
            Some((key, (Binding::Param, _))) => {
                let e = Expr::param(n);
                self.atoms.insert(key.as_str(), e.clone());
                Ok(Value::Scalar(e))
            }
            Some((key, (Binding::Unknown, _))) => {
                let e = Expr::unknown(n);
                self.atoms.insert(key.as_str(), e.clone());
                Ok(Value::Scalar(e))
            }
            Some((key, (Binding::Coord, _))) => {
                let e = Expr::coord(n, 0);
                self.atoms.insert(key.as_str(), e.clone());
                Ok(Value::Scalar(e))
            }
            Some((key, (Binding::Given, _))) => {
                let e = Expr::given(n, 0);
                self.atoms.insert(key.as_str(), e.clone());
                Ok(Value::Scalar(e))
            }
            Some((_, (Binding::Body | Binding::Multiplier | Binding::Reaction, _))) | None => {
                Err(self.not_a_value(n, span).unwrap_or_else(|| {
                    Diagnostic::global(format!("internal: `{n}` has a value"))
                        .with_kind(crate::diag::ErrorKind::Internal)
                }))
            }
            Some((_, (Binding::Time, _))) => Ok(Value::Scalar(Expr::time())),
            Some((_, (Binding::Pi, _))) => Ok(Value::Scalar(Expr::pi())),
            Some((_, (Binding::Def(i), _))) => {
                let i = *i;
                if matches!(self.state.get(i), Some(State::Busy)) {
                    let start = self.stack.iter().position(|&j| j == i).unwrap_or(0);
                    let mut chain: Vec<String> = self.stack[start..]
                        .iter()
                        .filter_map(|&j| self.defs.get(j).map(|d| d.0.name.clone()))
                        .collect();
                    chain.push(n.to_string());
                    return Err(Diagnostic::error(span, cycle_message(&chain))
                        .with_hint("a definition cannot use itself, directly or through others")
                        .with_kind(crate::diag::ErrorKind::InvalidScene));
                }
                self.definition(i)
            }
        }
    }

    /// The error of `n` used as a value when it is none: a body, a
    /// multiplier or an unknown name; `None` for a name with a value.
    fn not_a_value(&self, n: &str, span: Span) -> Option<Diagnostic> {
        match self.names.get(n) {
            Some((Binding::Body, _)) => Some(Diagnostic::error(
                span,
                format!("`{n}` is a body, not a value"),
            )
            .with_hint(format!("use its position or its frame; its kinetic energy is `E_{n}`, outside the scene (the REPL, `--at`)")).with_kind(crate::diag::ErrorKind::TypeMismatch)),
            Some((Binding::Multiplier, _)) => Some(Diagnostic::error(
                span,
                format!("`{n}` is the Lagrange multiplier of a constraint, not a value in the scene"),
            )
            .with_hint("`qdot solve` finds it with the accelerations; in the REPL and in `--at` expressions it is an unknown").with_kind(crate::diag::ErrorKind::TypeMismatch)),
            Some((Binding::Reaction, _)) => Some(Diagnostic::error(
                span,
                format!("`{n}` is a joint's reaction, a drive's force or a friction, not a value in the scene"),
            )
            .with_hint("`qdot solve` and `qdot cycle` find it from the kinetostatic equations").with_kind(crate::diag::ErrorKind::TypeMismatch)),
            Some(_) => None,
            None => {
                let d = Diagnostic::error(span, format!("unknown name `{n}`")).with_kind(
                    crate::diag::ErrorKind::UnknownName {
                        name: n.to_string(),
                    },
                );
                Some(d.with_hint(match self.nearest(n) {
                    Some(m) => format!("did you mean `{m}`? Otherwise declare it with `parameters {n}` or define it with `{n} = …`"),
                    None => format!("declare it with `parameters {n}` (a constant) or `coordinates {n}` (a function of time), or define it with `{n} = …`"),
                }))
            }
        }
    }

    fn nearest(&self, n: &str) -> Option<String> {
        let mut best: Option<(usize, &String)> = None;
        for k in self.names.keys() {
            let d = crate::spelling::distance(n, k);
            // ties go to the name first in alphabetical order (the map's
            // order is arbitrary)
            if d <= 2
                && d < n.chars().count()
                && best.is_none_or(|(bd, bk)| d < bd || (d == bd && k < bk))
            {
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
            .with_hint("write exp(y*ln(x)) for x^y")
            .with_kind(crate::diag::ErrorKind::Unsupported));
        };
        if q.is_integer() {
            let n = q.as_i64().filter(|n| n.abs() <= 10_000).ok_or_else(|| {
                Diagnostic::error(exp.span, format!("exponent {q} is too large"))
                    .with_kind(crate::diag::ErrorKind::LimitExceeded)
            })?;
            return base.powi(n).map_err(|m| self.err(span, m));
        }
        let twice = &q * &Q::from_i64(2);
        if twice.is_integer() {
            let n = twice
                .as_i64()
                .filter(|n| n.abs() <= 10_000)
                .ok_or_else(|| {
                    Diagnostic::error(exp.span, format!("exponent {q} is too large"))
                        .with_kind(crate::diag::ErrorKind::LimitExceeded)
                })?;
            let r = self.root(base).map_err(|m| self.err(span, m))?;
            bounded_functions(std::slice::from_ref(&r), span)?;
            return r.powi(n).map_err(|m| self.err(span, m));
        }
        Err(Diagnostic::error(
            exp.span,
            format!("the exponent {q} is not exact here: only integers and halves are"),
        )
        .with_hint("qdot keeps results exact; square roots are supported, other roots are not yet")
        .with_kind(crate::diag::ErrorKind::Unsupported))
    }

    /// A function call, its result's nesting depth bounded
    /// ([`atom::MAX_NESTING`]: every walk into arguments recurses per level).
    fn call(
        &mut self,
        callee: &ast::Callee,
        args: &[ast::Expr],
        span: Span,
    ) -> Result<Value, Diagnostic> {
        let v = self.call_unbounded(callee, args, span)?;
        bounded_functions(v.components(), span)?;
        Ok(v)
    }

    /// `series(k1, k2, …)` = 1/Σ(1/k_i) and `parallel(k1, k2, …)` = Σ k_i:
    /// springs combined.
    fn springs(
        &mut self,
        how: Springs,
        args: &[ast::Expr],
        span: Span,
    ) -> Result<Value, Diagnostic> {
        let b = how.builtin();
        if args.len() < 2 {
            return Err(Diagnostic::error(
                span,
                format!("`{}` combines two or more springs", b.name()),
            )
            .with_hint(b.usage())
            .with_kind(crate::diag::ErrorKind::InvalidScene));
        }
        let mut acc = Expr::zero();
        for a in args {
            let k = self.expr(a)?;
            acc = acc.add(&match how {
                Springs::Series => k.recip().map_err(|_| {
                    Diagnostic::error(a.span, "a spring of stiffness 0 in series")
                        .with_hint("series(k1, k2) = k1·k2/(k1 + k2) needs nonzero stiffnesses")
                        .with_kind(crate::diag::ErrorKind::Undefined)
                })?,
                Springs::Parallel => k,
            });
        }
        match how {
            Springs::Series => acc.recip().map(Value::Scalar).map_err(|_| {
                Diagnostic::error(span, "the series stiffness is undefined: Σ 1/k_i = 0")
                    .with_kind(crate::diag::ErrorKind::Undefined)
            }),
            Springs::Parallel => Ok(Value::Scalar(acc)),
        }
    }

    fn call_unbounded(
        &mut self,
        callee: &ast::Callee,
        args: &[ast::Expr],
        span: Span,
    ) -> Result<Value, Diagnostic> {
        let b = match callee {
            ast::Callee::Named(f) => return self.named_call(f, args, span),
            ast::Callee::Builtin(b, at) => {
                self.not_a_given_function(*b, *at)?;
                *b
            }
        };
        if let Arity::Exactly(n) = b.arity() {
            if args.len() != n {
                let what = if n == 1 { "argument" } else { "arguments" };
                return Err(Diagnostic::error(
                    span,
                    format!("`{}` takes {n} {what}, not {}", b.name(), args.len()),
                )
                .with_hint(b.usage())
                .with_kind(crate::diag::ErrorKind::InvalidScene));
            }
        }
        // every built-in function has its arm: no name falls through to another
        #[deny(
            clippy::wildcard_enum_match_arm,
            clippy::match_wildcard_for_single_variants
        )]
        match b {
            Builtin::Subs => self.subs(args, span),
            Builtin::Series => self.series(args, span),
            Builtin::Parallel => self.springs(Springs::Parallel, args, span),
            Builtin::Rot => self.rot(args),
            Builtin::Axis => self.axis(args),
            Builtin::Express => self.express(args),
            Builtin::Omega => self.omega(args),
            Builtin::Dot => self.vector_product(Product::Dot, args, span),
            Builtin::Cross => self.vector_product(Product::Cross, args, span),
            Builtin::Norm => self.norm(&args[0], span),
            Builtin::Diff => {
                let v = self.variable(&args[1], Builtin::Diff)?;
                let x = self.value(&args[0])?;
                frames::not_a_rotation(
                    &x,
                    args[0].span,
                    "can't be differentiated; its angular velocity is omega(F)",
                )?;
                match self.tape.as_mut() {
                    Some(tape) => Ok(x.map(|c| tape.partial(c, v))),
                    None => Ok(x.map(|c| c.diff(v))),
                }
            }
            Builtin::Dt => {
                let v = self.value(&args[0])?;
                frames::not_a_rotation(
                    &v,
                    args[0].span,
                    "has no time derivative; its angular velocity is omega(F)",
                )?;
                self.check_derivative_order(&v, 1, span)?;
                match self.tape.as_mut() {
                    Some(tape) => Ok(v.map(|c| tape.dt(c))),
                    None => Ok(v.map(|c| c.dt())),
                }
            }
            // The value is the canonical form itself; the REPL shows the
            // outermost expand/factor as a layout.
            Builtin::Expand | Builtin::Factor => self.value(&args[0]),
            Builtin::Taylor => self.taylor(args, span),
            Builtin::Inertia => self.inertia(args),
            Builtin::Sin => self.elementary(&args[0], span, |_, x| Ok(func::sin(x))),
            Builtin::Cos => self.elementary(&args[0], span, |_, x| Ok(func::cos(x))),
            Builtin::Tan => self.elementary(&args[0], span, |_, x| func::tan(x)),
            Builtin::Sqrt => self.elementary(&args[0], span, |ev, x| ev.root(x)),
            Builtin::Exp => self.elementary(&args[0], span, |_, x| Ok(func::exp(x))),
            Builtin::Ln => self.elementary(&args[0], span, |_, x| func::ln(x)),
            Builtin::Atan => self.elementary(&args[0], span, |_, x| Ok(func::atan(x))),
            Builtin::Asin => self.elementary(&args[0], span, |_, x| func::asin(x)),
            Builtin::Acos => self.elementary(&args[0], span, |_, x| func::acos(x)),
        }
    }

    /// A call of a name that is no built-in function: a given function of
    /// time `s(t)`, else an error.
    fn named_call(
        &mut self,
        f: &ast::Ident,
        args: &[ast::Expr],
        span: Span,
    ) -> Result<Value, Diagnostic> {
        if let Some((Binding::Given, _)) = self.names.get(&f.name) {
            // `s(t)`: the given function itself, as `s`
            return match args {
                [a] if matches!(&a.kind, ExprKind::Name(n) if n == "t") => {
                    Ok(Value::Scalar(Expr::given(&f.name, 0)))
                }
                _ => Err(Diagnostic::error(
                    span,
                    format!("`{}` is a given function of time: write `{0}(t)` or `{0}`", f.name),
                )
                .with_hint(format!("its derivatives are `{0}'`, `{0}''`; a function of anything but t is not supported", f.name)).with_kind(crate::diag::ErrorKind::InvalidScene)),
            };
        }
        Err(self.unknown_function(f))
    }

    /// The error of calling `f`, a name that is no function.
    fn unknown_function(&self, f: &ast::Ident) -> Diagnostic {
        let hint = if self.names.contains_key(&f.name) {
            format!(
                "`{}` is not a function; write `{}*(…)` to multiply",
                f.name, f.name
            )
        } else {
            let list: Vec<&str> = functions::names().collect();
            format!("the functions are {}", list.join(", "))
        };
        Diagnostic::error(f.span, format!("unknown function `{}`", f.name))
            .with_hint(hint)
            .with_kind(crate::diag::ErrorKind::UnknownName {
                name: f.name.clone(),
            })
    }

    /// A call of the built-in `b` when the scene declares a given function
    /// of the same name (`functions exp`): the call can't say which it means.
    fn not_a_given_function(&self, b: Builtin, at: Span) -> Result<(), Diagnostic> {
        match self.names.get(b.name()) {
            Some((Binding::Given, _)) => Err(Diagnostic::error(
                at,
                format!(
                    "`{}` is a built-in function and also a given function of time here",
                    b.name()
                ),
            )
            .with_hint("give the given function another name in `functions …`")
            .with_kind(crate::diag::ErrorKind::InvalidScene)),
            _ => Ok(()),
        }
    }

    /// A function of one scalar (`sin`, `sqrt`, …) of `arg`, its math
    /// error (a root of a negative number, …) reported at the call.
    fn elementary(
        &mut self,
        arg: &ast::Expr,
        span: Span,
        f: impl FnOnce(&Self, &Expr) -> Result<Expr, MathError>,
    ) -> Result<Value, Diagnostic> {
        let x = self.expr(arg)?;
        f(self, &x)
            .map(Value::Scalar)
            .map_err(|m| self.err(span, m))
    }

    /// `norm(v)`: the length of a vector.
    fn norm(&mut self, arg: &ast::Expr, span: Span) -> Result<Value, Diagnostic> {
        let v = self.value(arg)?;
        let Value::Vector(c) = v else {
            return Err(Diagnostic::error(arg.span, format!("norm needs a vector, found {}", v.describe()))
                .with_hint("the absolute value of a number is not exact-friendly; write sqrt(x^2) for a positive x").with_kind(crate::diag::ErrorKind::TypeMismatch));
        };
        let sq = c.iter().fold(Expr::zero(), |acc, x| acc.add(&x.mul(x)));
        func::sqrt(&sq)
            .map(Value::Scalar)
            .map_err(|m| self.err(span, m))
    }

    /// `inertia(m, x)` = m·x'': the inertia force of a moving x.
    fn inertia(&mut self, args: &[ast::Expr]) -> Result<Value, Diagnostic> {
        let m = self.expr(&args[0])?;
        let x = self.value(&args[1])?;
        frames::not_a_rotation(
            &x,
            args[1].span,
            "has no inertia force; a body's inertia is given in a `body` statement",
        )?;
        let moving = x.components().iter().any(|s| s.is_time_dependent());
        if !moving {
            return Err(Diagnostic::error(
                args[1].span,
                "this does not move, so it has no inertia force",
            )
            .with_hint("inertia(m, x) is m·x'': x must depend on the coordinates or on t")
            .with_kind(crate::diag::ErrorKind::InvalidScene));
        }
        Ok(x.map(|c| self.dt(c, 2).mul(&m)))
    }

    /// `series(…)`: a Taylor series when its second argument is a moving
    /// variable or a named point (`series(f, q, n)`, `series(f, x = a, n)`),
    /// else springs in series.
    fn series(&mut self, args: &[ast::Expr], span: Span) -> Result<Value, Diagnostic> {
        if self.is_taylor_call(args) {
            return self.taylor(args, span);
        }
        if args.len() == 3 && self.looks_like_taylor(args) {
            self.warnings.push(
                Diagnostic::warning(span, "series(a, b, n) combines three springs in series here")
                    .with_hint("for a Taylor series in a parameter write taylor(f, x, n) or series(f, x = 0, n)"),
            );
        }
        self.springs(Springs::Series, args, span)
    }

    /// The variable of `diff`, `subs` and `taylor`: a coordinate or one of
    /// its derivatives, a parameter, a `solve` unknown, or `t`.
    fn variable(&mut self, a: &ast::Expr, what: Builtin) -> Result<Var, Diagnostic> {
        let what = what.name();
        let v = self.expr(a)?;
        let var = v.as_var().filter(|&x| {
            matches!(
                atom::atom(x),
                Atom::Param(_) | Atom::Unknown(_) | Atom::Coord(..) | Atom::Time
            )
        });
        var.ok_or_else(|| {
            Diagnostic::error(
                a.span,
                format!("`{what}` needs a variable here: a coordinate, a velocity, a parameter or t"),
            )
            .with_hint(match &a.kind {
                ExprKind::Name(n) => format!("`{n}` is a definition, not a variable; use the coordinate or parameter it is made of"),
                _ => "write a name such as theta, theta' or m".to_string(),
            }).with_kind(crate::diag::ErrorKind::InvalidScene)
        })
    }

    /// `subs(f, x = a, y = b, …)`: every `x` replaced by `a` at once (also
    /// inside functions); `x'` is a variable of its own.
    fn subs(&mut self, args: &[ast::Expr], span: Span) -> Result<Value, Diagnostic> {
        if args.len() < 2 {
            return Err(Diagnostic::error(
                span,
                "`subs` needs an expression and at least one `x = value`",
            )
            .with_hint("write subs(E, x = 0) or subs(E, x = 0, m = 2)")
            .with_kind(crate::diag::ErrorKind::InvalidScene));
        }
        let mut map: FxHashMap<Var, Expr> = FxHashMap::default();
        for a in &args[1..] {
            let ExprKind::Assign(x, value) = &a.kind else {
                return Err(Diagnostic::error(a.span, "expected `x = value` here")
                    .with_hint("write subs(E, x = 0): each replacement names its variable")
                    .with_kind(crate::diag::ErrorKind::InvalidScene));
            };
            let v = self.variable(x, Builtin::Subs)?;
            let value = self.expr(value)?;
            if map.insert(v, value).is_some() {
                return Err(Diagnostic::error(x.span, "this variable is replaced twice")
                    .with_hint("give each variable one value")
                    .with_kind(crate::diag::ErrorKind::InvalidScene));
            }
        }
        let target = self.value(&args[0])?;
        frames::not_a_rotation(
            &target,
            args[0].span,
            "can't be substituted into; substitute in its angles",
        )?;
        self.expanded_only(&target, args[0].span, "a substitution")?;
        let mut out = Vec::with_capacity(target.components().len());
        for c in target.components() {
            out.push(c.subs_many(&map).map_err(|m| self.err(span, m))?);
        }
        Ok(match target {
            Value::Scalar(_) => Value::Scalar(out.remove(0)),
            _ => Value::Vector(out),
        })
    }

    /// `taylor(f, x, n)` / `taylor(f, x = a, n)` (also spelled `series` with
    /// a named point): Σ_{k ≤ n} f⁽ᵏ⁾(a)/k!·(x − a)ᵏ.
    fn taylor(&mut self, args: &[ast::Expr], span: Span) -> Result<Value, Diagnostic> {
        if args.len() != 3 {
            return Err(Diagnostic::error(
                span,
                format!("a Taylor series takes 3 arguments, not {}", args.len()),
            )
            .with_hint("write taylor(f, x, n) or taylor(f, x = a, n)")
            .with_kind(crate::diag::ErrorKind::InvalidScene));
        }
        let (x, at) = match &args[1].kind {
            ExprKind::Assign(x, a) => (&**x, Some(&**a)),
            _ => (&args[1], None),
        };
        let v = self.variable(x, Builtin::Taylor)?;
        let a = match at {
            Some(a) => self.expr(a)?,
            None => Expr::zero(),
        };
        let n = self.expr(&args[2])?;
        let n = n
            .as_rational()
            .filter(|q| q.is_integer())
            .and_then(|q| q.as_i64())
            .filter(|k| (0..=MAX_TAYLOR_ORDER).contains(k))
            .ok_or_else(|| {
                Diagnostic::error(
                    args[2].span,
                    format!("the order must be a whole number from 0 to {MAX_TAYLOR_ORDER}"),
                )
                .with_hint("taylor(sin(x), x, 5) keeps the powers x⁰ … x⁵")
                .with_kind(crate::diag::ErrorKind::InvalidScene)
            })?;
        let f = self.value(&args[0])?;
        frames::not_a_rotation(
            &f,
            args[0].span,
            "has no Taylor series here; expand its angles",
        )?;
        self.expanded_only(&f, args[0].span, "a Taylor series")?;
        let dx = Expr::var(v).sub(&a);
        let mut out = Vec::with_capacity(f.components().len());
        for c in f.components() {
            let mut d = c.clone();
            let mut sum = Expr::zero();
            let mut power = Expr::one();
            let mut fact = Q::one();
            for k in 0..=n {
                if k > 0 {
                    d = d.diff(v);
                    power = power.mul(&dx);
                    fact = &fact * &Q::from_i64(k);
                }
                if d.is_zero() {
                    break;
                }
                let at_a = d.subs(v, &a).map_err(|m| {
                    if !m.message.contains("division by zero") {
                        return self.err(span, m);
                    }
                    let what = if k == 0 { "it" } else { "its derivative" };
                    Diagnostic::error(
                        args[0].span,
                        format!(
                            "this function is not defined at {} = {} ({what} divides by zero there), so it has no Taylor series about that point",
                            crate::expr::print::input(&Expr::var(v)),
                            crate::expr::print::input(&a)
                        ),
                    )
                    .with_hint("qdot expands by derivatives at the point; write the function in a form defined there (sin(x)/x is 1 − x²/6 + x⁴/120 − …), or expand about another point: taylor(f, x = 1, 5)").with_kind(crate::diag::ErrorKind::Undefined)
                })?;
                let coef = at_a.scale(&fact.recip().unwrap_or_else(Q::zero));
                sum = sum.add(&coef.mul(&power));
            }
            out.push(sum);
        }
        Ok(match f {
            Value::Scalar(_) => Value::Scalar(out.remove(0)),
            _ => Value::Vector(out),
        })
    }

    fn is_taylor_call(&self, args: &[ast::Expr]) -> bool {
        is_taylor_form(args, |n| {
            matches!(self.names.get(n), Some((Binding::Coord | Binding::Time, _)))
        })
    }

    /// `series(a, b, n)` with a name `b` and a whole number `n`: what a
    /// Taylor series would look like (three springs are meant otherwise).
    fn looks_like_taylor(&self, args: &[ast::Expr]) -> bool {
        matches!(args[1].kind, ExprKind::Name(_))
            && matches!(&args[2].kind, ExprKind::Num(r) if r.is_integer())
    }

    /// dot(a, b) and cross(a, b); a plane cross product is the scalar
    /// a_x·b_y − a_y·b_x (the z component, as in the seed's eq. 21.71).
    fn vector_product(
        &mut self,
        product: Product,
        args: &[ast::Expr],
        span: Span,
    ) -> Result<Value, Diagnostic> {
        let name = product.builtin().name();
        let mut vs = Vec::with_capacity(2);
        for a in args {
            match self.value(a)? {
                Value::Vector(c) => vs.push(c),
                v @ (Value::Scalar(_) | Value::Rotation(_)) => {
                    return Err(Diagnostic::error(
                        a.span,
                        format!("`{name}` needs two vectors, and this is {}", v.describe()),
                    )
                    .with_hint("write vectors as [x, y] or [x, y, z]; axis(F, k) is the k-th unit vector of a frame F").with_kind(crate::diag::ErrorKind::TypeMismatch))
                }
            }
        }
        let (u, w) = (&vs[0], &vs[1]);
        if u.len() != w.len() {
            return Err(Diagnostic::error(
                span,
                format!(
                    "`{name}` of vectors of different sizes: {} and {} components",
                    u.len(),
                    w.len()
                ),
            )
            .with_hint("write plane vectors as [x, y, 0] to combine them with space vectors")
            .with_kind(crate::diag::ErrorKind::TypeMismatch));
        }
        let c = |i: usize, j: usize| u[i].mul(&w[j]).sub(&u[j].mul(&w[i]));
        Ok(match product {
            Product::Dot => Value::Scalar(
                u.iter()
                    .zip(w)
                    .fold(Expr::zero(), |acc, (p, q)| acc.add(&p.mul(q))),
            ),
            Product::Cross if u.len() == 2 => Value::Scalar(c(0, 1)),
            Product::Cross => Value::Vector(vec![c(1, 2), c(2, 0), c(0, 1)]),
        })
    }
}

/// `series(f, x = a, n)`, or `series(f, q, n)` with `q` a coordinate, a
/// velocity or `t` (`moves(name)` tells which names are; never a
/// stiffness): the Taylor series, not springs.
pub fn is_taylor_form(args: &[ast::Expr], moves: impl Fn(&str) -> bool) -> bool {
    if args.len() != 3 {
        return false;
    }
    match &args[1].kind {
        ExprKind::Assign(..) | ExprKind::Prime(..) => true,
        ExprKind::Name(n) => moves(n),
        _ => false,
    }
}

/// An error when a function in `es` (just built at `span`) nests deeper
/// than [`atom::MAX_NESTING`] or has an argument longer written out than
/// [`MAX_FUNCTION_ARGUMENT_SIZE`]: walks into arguments recurse per level,
/// and an argument shared by definitions prints, differentiates and
/// evaluates at each occurrence.
fn bounded_functions(es: &[Expr], span: Span) -> Result<(), Diagnostic> {
    let depth = es.iter().map(atom::nesting_depth).max().unwrap_or(0);
    if depth > atom::MAX_NESTING {
        return Err(Diagnostic::error(
            span,
            format!(
                "functions nested {depth} deep here; qdot allows at most {}",
                atom::MAX_NESTING
            ),
        )
        .with_hint("a chain of definitions that each apply a function to the previous one nests them; no mechanics needs this depth").with_kind(crate::diag::ErrorKind::LimitExceeded));
    }
    let size = es.iter().map(atom::largest_argument).max().unwrap_or(0);
    if size > MAX_FUNCTION_ARGUMENT_SIZE {
        return Err(Diagnostic::error(
            span,
            format!(
                "a function's argument here is {} symbols long written out; qdot allows at most {}",
                crate::budget::grouped(usize::try_from(size).unwrap_or(usize::MAX)),
                crate::budget::grouped(MAX_FUNCTION_ARGUMENT_SIZE as usize)
            ),
        )
        .with_hint("definitions that each use the previous one twice inside a function (`f2 = sin(f1) + cos(f1)`) double its length per line; no mechanics needs this").with_kind(crate::diag::ErrorKind::LimitExceeded));
    }
    Ok(())
}

/// The name of component `k` of a vector with `n`: x, y, z in the plane
/// and in space, else 1-based.
fn component_name(k: usize, n: usize) -> String {
    match (n, k) {
        (2 | 3, 0) => "x".into(),
        (2 | 3, 1) => "y".into(),
        (3, 2) => "z".into(),
        _ => (k + 1).to_string(),
    }
}
