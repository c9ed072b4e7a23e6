//! What lazy evaluation asks of the evaluator: an evaluator whose
//! definitions are partly known (the others evaluated when asked), the
//! checks of a definition that is not evaluated (its names resolve, no
//! cycle through it), and recovery after the work budget stopped an
//! evaluation midway.

use super::{cycle_message, frames, PathStep, State, SyntaxEvaluator};
use crate::diag::Diagnostic;
use crate::parse::ast::{self, ExprKind, Span};
use crate::parse::functions::Builtin;
use crate::scene::{Binding, Value};
use rustc_hash::{FxHashMap, FxHashSet};

/// A definition given to [`SyntaxEvaluator::with_entries`].
pub(crate) enum Entry<'a> {
    /// Its value.
    Known(Value),
    /// Its name and body, evaluated when asked.
    Pending(&'a ast::Ident, &'a ast::Expr),
}

/// The name of a definition whose value is given to the evaluator: it is
/// never evaluated, so never named in a message.
static GIVEN: ast::Ident = ast::Ident {
    name: String::new(),
    span: Span { start: 0, end: 0 },
};

/// The names `e` evaluates, with where each is written, left to right:
/// not the axis of `rot(x, a)` (nor a name there that means nothing,
/// which evaluation reports as a bad axis), not the name on the left of
/// `x = a` in a call. Found without recursion.
pub(crate) fn names_in<'e>(
    names: &FxHashMap<String, (Binding, Span)>,
    e: &'e ast::Expr,
) -> Vec<(&'e str, Span)> {
    let mut out = Vec::new();
    let mut stack = vec![e];
    while let Some(e) = stack.pop() {
        match &e.kind {
            ExprKind::Name(n) => out.push((n.as_str(), e.span)),
            ExprKind::Neg(x) | ExprKind::Prime(x, _) => stack.push(x),
            ExprKind::Bin(_, a, b) | ExprKind::Index(a, b) => {
                stack.push(b);
                stack.push(a);
            }
            ExprKind::Call(ast::Callee::Builtin(Builtin::Rot, _), args)
                if frames::axis_name(args).is_some()
                    || matches!(args.first().map(|a| &a.kind),
                        Some(ExprKind::Name(n)) if !names.contains_key(n.as_str())) =>
            {
                stack.extend(args[1..].iter().rev())
            }
            ExprKind::Assign(_, b) => stack.push(b),
            ExprKind::Call(_, args) | ExprKind::Vector(args) => stack.extend(args.iter().rev()),
            ExprKind::Num(_) | ExprKind::Degrees(_) => {}
        }
    }
    out
}

/// The names called as functions in `e` that are no built-in function
/// (`s(t)` of a given function, or a name that is no function).
fn named_callees(e: &ast::Expr) -> Vec<&ast::Ident> {
    let mut out = Vec::new();
    let mut stack = vec![e];
    while let Some(e) = stack.pop() {
        match &e.kind {
            ExprKind::Neg(x) | ExprKind::Prime(x, _) => stack.push(x),
            ExprKind::Bin(_, a, b) | ExprKind::Index(a, b) | ExprKind::Assign(a, b) => {
                stack.push(b);
                stack.push(a);
            }
            ExprKind::Call(callee, args) => {
                if let ast::Callee::Named(f) = callee {
                    out.push(f);
                }
                stack.extend(args.iter().rev());
            }
            ExprKind::Vector(args) => stack.extend(args.iter().rev()),
            ExprKind::Num(_) | ExprKind::Degrees(_) | ExprKind::Name(_) => {}
        }
    }
    out
}

impl<'a> SyntaxEvaluator<'a> {
    /// An evaluator whose definitions are `entries`, in the order of the
    /// names' [`Binding::Def`] indices: values, or bodies evaluated when a
    /// name asks for them.
    pub fn with_entries(
        names: &'a FxHashMap<String, (Binding, Span)>,
        entries: impl IntoIterator<Item = Entry<'a>>,
    ) -> SyntaxEvaluator<'a> {
        let mut ev = SyntaxEvaluator::with_values(names, Vec::new());
        for entry in entries {
            let (def, state) = match entry {
                Entry::Known(v) => ((&GIVEN, None), State::Done(v)),
                Entry::Pending(name, body) => ((name, Some(body)), State::Todo),
            };
            ev.defs.push(def);
            ev.state.push(state);
        }
        ev
    }

    /// Definition `i`'s value, when it has been evaluated.
    pub fn evaluated(&self, i: usize) -> Option<&Value> {
        match self.state.get(i) {
            Some(State::Done(v)) => Some(v),
            _ => None,
        }
    }

    /// After an evaluation the work budget stopped midway: the definitions
    /// it had begun are to be evaluated again, from the start.
    pub fn abandon(&mut self) {
        for s in &mut self.state {
            if matches!(s, State::Busy) {
                *s = State::Todo;
            }
        }
        self.stack.clear();
    }

    /// Check definition `i` without evaluating it: every name its body
    /// evaluates has a value (the error evaluation would give otherwise),
    /// and no chain of definitions from it comes back (the cycle's error,
    /// as evaluation reports it). `walked` marks the definitions whose
    /// chains are already known to end, and `order` lists them as they are
    /// found, each after those it uses; both are shared between calls.
    pub fn check_unevaluated(
        &self,
        i: usize,
        walked: &mut Vec<bool>,
        order: &mut Vec<usize>,
    ) -> Result<(), Diagnostic> {
        walked.resize(self.state.len(), false);
        let Some((_, Some(body))) = self.defs.get(i).copied() else {
            return Ok(());
        };
        let names = names_in(self.names, body);
        let bad = names
            .iter()
            .filter_map(|&(n, span)| self.not_a_value(n, span));
        let calls = named_callees(body).into_iter().filter_map(|f| {
            let given = matches!(self.names.get(&f.name), Some((Binding::Given, _)));
            (!given).then(|| self.unknown_function(f))
        });
        // the first in the text, as evaluation (left to right) meets it
        let first = bad.chain(calls).min_by_key(|d| d.span.map(|s| s.start));
        if let Some(d) = first {
            return Err(d);
        }
        let uses_definitions = names
            .iter()
            .any(|(n, _)| matches!(self.names.get(*n), Some((Binding::Def(_), _))));
        if uses_definitions {
            return self.acyclic_from(i, walked, order);
        }
        // nothing to walk: the common case of a body of parameters and
        // coordinates
        if !std::mem::replace(&mut walked[i], true) {
            order.push(i);
        }
        Ok(())
    }

    /// [`SyntaxEvaluator::evaluate_dependencies`]'s walk without the
    /// evaluation: an error for a cycle among the definitions not yet
    /// evaluated that `i` reaches.
    fn acyclic_from(
        &self,
        i: usize,
        walked: &mut [bool],
        order: &mut Vec<usize>,
    ) -> Result<(), Diagnostic> {
        if walked[i] || !matches!(self.state[i], State::Todo) {
            return Ok(());
        }
        let mut path: Vec<PathStep> = vec![(i, self.dependencies(i), 0)];
        // a set, not a flag per definition: most walks are short
        let mut on_path: FxHashSet<usize> = FxHashSet::default();
        on_path.insert(i);
        while let Some((j, deps, next)) = path.last_mut() {
            let Some(&(k, span)) = deps.get(*next) else {
                let j = *j;
                path.pop();
                on_path.remove(&j);
                walked[j] = true;
                order.push(j);
                continue;
            };
            *next += 1;
            if on_path.contains(&k) {
                let start = path.iter().position(|p| p.0 == k).unwrap_or(0);
                let mut chain: Vec<String> = path[start..]
                    .iter()
                    .map(|p| self.defs[p.0].0.name.clone())
                    .collect();
                chain.push(self.defs[k].0.name.clone());
                return Err(Diagnostic::error(span, cycle_message(&chain))
                    .with_hint("a definition cannot use itself, directly or through others")
                    .with_kind(crate::diag::ErrorKind::InvalidScene));
            }
            if !walked[k] && matches!(self.state[k], State::Todo) {
                on_path.insert(k);
                path.push((k, self.dependencies(k), 0));
            }
        }
        Ok(())
    }
}

/// The growth allowed per time derivative in [`SyntaxEvaluator::estimated_size`]
/// (d/dt of a term in q and q̇ is a term per variable).
const DERIVATIVE_GROWTH: u64 = 4;

impl SyntaxEvaluator<'_> {
    /// The definitions `roots` use, directly or through others (the roots
    /// included), one flag per definition.
    pub fn reached_from(&self, roots: impl IntoIterator<Item = usize>) -> Vec<bool> {
        let mut reached = vec![false; self.state.len()];
        let mut stack: Vec<usize> = roots.into_iter().collect();
        while let Some(i) = stack.pop() {
            if std::mem::replace(&mut reached[i], true) {
                continue;
            }
            stack.extend(self.dependencies(i).into_iter().map(|(k, _)| k));
        }
        reached
    }

    /// The definitions definition `i`'s body names.
    pub fn uses(&self, i: usize) -> impl Iterator<Item = usize> {
        self.dependencies(i).into_iter().map(|(k, _)| k)
    }

    /// A rough size (terms) of definition `i`'s value, read from its body
    /// without evaluating it: sums add, products and calls multiply, an
    /// integer power n raises to n. A definition it uses counts with its
    /// value's size when evaluated, else with its entry in `sizes` (absent:
    /// unbounded). It decides whether an unused definition is cheap enough
    /// to evaluate; the work budget bounds the evaluation either way.
    pub fn estimated_size(&self, i: usize, sizes: &FxHashMap<usize, u64>) -> u64 {
        match self.defs.get(i).copied() {
            Some((_, Some(body))) => self.size_of(body, sizes),
            _ => u64::MAX,
        }
    }

    fn size_of(&self, e: &ast::Expr, sizes: &FxHashMap<usize, u64>) -> u64 {
        let size = |x: &ast::Expr| self.size_of(x, sizes);
        match &e.kind {
            ExprKind::Num(_) | ExprKind::Degrees(_) => 1,
            ExprKind::Name(n) => match self.names.get(n.as_str()) {
                Some((Binding::Def(k), _)) => match self.state.get(*k) {
                    Some(State::Done(v)) => value_size(v),
                    _ => sizes.get(k).copied().unwrap_or(u64::MAX),
                },
                _ => 1,
            },
            ExprKind::Neg(x) | ExprKind::Index(x, _) => size(x),
            // a derivative of a coordinate is one variable
            ExprKind::Prime(x, _) if self.is_variable(x) => 1,
            ExprKind::Prime(x, k) => size(x).saturating_mul(DERIVATIVE_GROWTH.saturating_pow(*k)),
            ExprKind::Bin(op, a, b) => {
                let (x, y) = (size(a), size(b));
                match op {
                    ast::BinOp::Add | ast::BinOp::Sub => x.saturating_add(y),
                    ast::BinOp::Mul | ast::BinOp::Div => x.saturating_mul(y),
                    ast::BinOp::Pow => match &b.kind {
                        ExprKind::Num(r) => {
                            // integers and halves (a root counts as a power)
                            let n = u32::try_from(r.numer().magnitude()).ok();
                            match (n, u32::try_from(r.denom().magnitude()).ok()) {
                                (Some(n), Some(1)) => x.saturating_pow(n),
                                (Some(n), Some(2)) => x.saturating_pow(n.div_ceil(2)),
                                _ => u64::MAX,
                            }
                        }
                        _ => u64::MAX,
                    },
                }
            }
            ExprKind::Assign(_, b) => size(b),
            ExprKind::Call(_, args) => args.iter().fold(1u64, |acc, a| acc.saturating_mul(size(a))),
            ExprKind::Vector(items) => items
                .iter()
                .fold(0u64, |acc, a| acc.saturating_add(size(a))),
        }
    }
}

impl SyntaxEvaluator<'_> {
    /// Whether `e` is the name of a coordinate, a given function or t.
    fn is_variable(&self, e: &ast::Expr) -> bool {
        let ExprKind::Name(n) = &e.kind else {
            return false;
        };
        matches!(
            self.names.get(n.as_str()),
            Some((Binding::Coord | Binding::Given | Binding::Time, _))
        )
    }
}

/// The terms of a value: numerators and denominators of its components.
fn value_size(v: &Value) -> u64 {
    v.components()
        .iter()
        .map(|c| (c.num().len() + c.den().len()) as u64)
        .sum()
}
