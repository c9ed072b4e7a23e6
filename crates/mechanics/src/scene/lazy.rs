//! Lazy evaluation: a scene evaluates the definitions its statements use
//! (role statements, frames, and every definition that a force, load,
//! torque, body, gravity, constraint, reaction, `assume` or `solve` block
//! reaches). A definition nothing uses is checked without evaluating it
//! (its names resolve, no cycle runs through it; an error as before), then
//! evaluated only when it is small: its estimated size at most
//! [`CHEAP_SIZE`] terms, under a work budget of [`CHECK_BUDGET`] terms. An
//! error found so is a warning (nothing depends on the definition); one
//! too large to check is kept unevaluated on [`Scene::deferred`] and
//! evaluated when something asks for it ([`Scene::value`], [`Scene::expr`]).

use super::eval::{names_in, Entry, SyntaxEvaluator};
use super::{momentum_name, Binding, Scene, Value};
use crate::diag::{Diagnostic, Severity};
use crate::parse::ast::{self, Span, Stmt};
use rustc_hash::{FxHashMap, FxHashSet};
use std::sync::OnceLock;

use crate::limits::{LAZY_CHECK_BUDGET as CHECK_BUDGET, LAZY_CHECK_SIZE as CHEAP_SIZE};

/// A definition that nothing in the scene uses and that was too large to
/// evaluate when the scene was read (or whose evaluation fails, which
/// [`Scene::warnings`] reports). [`Scene::value`] evaluates it on first ask
/// and keeps the value.
#[derive(Clone, Debug)]
pub struct DeferredDefinition {
    /// The defined name, where it is written.
    pub name: ast::Ident,
    /// The right-hand side as written.
    pub body: ast::Expr,
    /// The value, or the error of evaluating it, once asked for.
    value: OnceLock<Result<Value, Diagnostic>>,
}

impl DeferredDefinition {
    pub(super) fn new(name: &ast::Ident, body: &ast::Expr) -> DeferredDefinition {
        DeferredDefinition {
            name: name.clone(),
            body: body.clone(),
            value: OnceLock::new(),
        }
    }
}

/// The expressions of a statement that are not a definition (role
/// statements and frames are roots by themselves).
fn statement_exprs(st: &Stmt) -> Vec<&ast::Expr> {
    match st {
        Stmt::Force { value, .. } | Stmt::Gravity { value, .. } => vec![value],
        Stmt::Load { force, point, .. } => vec![force, point],
        Stmt::Torque { moment, angle, .. } => vec![moment, angle],
        Stmt::Solve(block) => block
            .equations
            .iter()
            .flat_map(|eq| [&eq.lhs, &eq.rhs])
            .collect(),
        Stmt::Body(b) => b
            .properties
            .iter()
            .flat_map(|p| std::iter::once(&p.value).chain(p.about.as_ref().map(|a| &a.point)))
            .collect(),
        Stmt::Constraint { equation, .. } => vec![&equation.lhs, &equation.rhs],
        Stmt::Reaction { point, .. } => vec![point],
        Stmt::Joint(j) => [&j.first.point, &j.second.point]
            .into_iter()
            .chain(j.along.as_ref())
            .collect(),
        Stmt::Drive { value, .. } => vec![value],
        Stmt::Friction { coefficient, .. } => vec![coefficient],
        Stmt::Assume(facts, _) => facts
            .iter()
            .flat_map(|f| match f {
                ast::Fact::Order { greater, less, .. } => vec![greater, less],
                ast::Fact::Real(_) => Vec::new(),
            })
            .collect(),
        Stmt::Coordinates(..)
        | Stmt::Parameters(..)
        | Stmt::Functions(..)
        | Stmt::Def { .. }
        | Stmt::Role { .. }
        | Stmt::Frame { .. }
        | Stmt::Latex { .. } => Vec::new(),
    }
}

/// The definitions the scene's statements use, one flag per definition:
/// those named in a statement that is not a definition, the role
/// statements and frames (`roots`), and what they use.
pub(super) fn used_definitions(
    ev: &SyntaxEvaluator,
    names: &FxHashMap<String, (Binding, Span)>,
    stmts: &[Stmt],
    roots: impl IntoIterator<Item = usize>,
) -> Vec<bool> {
    let mut all: Vec<usize> = roots.into_iter().collect();
    for e in stmts.iter().flat_map(statement_exprs) {
        for (n, _) in names_in(names, e) {
            if let Some((Binding::Def(k), _)) = names.get(n) {
                all.push(*k);
            }
        }
    }
    ev.reached_from(all)
}

/// Evaluate the unused definitions `order` lists (each after those it
/// uses) that are small enough, each within the budget: the values found,
/// by definition index, and a warning for each that fails. `names` gives
/// each definition's name, by index.
pub(super) fn check_unused(
    ev: &mut SyntaxEvaluator,
    order: &[usize],
    names: &[&ast::Ident],
) -> (FxHashMap<usize, Value>, Vec<Diagnostic>) {
    let mut values = FxHashMap::default();
    let mut warnings = Vec::new();
    let mut sizes: FxHashMap<usize, u64> = FxHashMap::default();
    // those left unevaluated: what uses one is left too (its error, if
    // any, is reported once, at the definition it is in)
    let mut left: FxHashSet<usize> = FxHashSet::default();
    for &i in order {
        let size = ev.estimated_size(i, &sizes);
        sizes.insert(i, size);
        if size > CHEAP_SIZE || ev.uses(i).any(|k| left.contains(&k)) {
            left.insert(i);
            continue;
        }
        // (a budget already smaller than the check's stays in force)
        match crate::budget::probe(CHECK_BUDGET, || ev.definition(i)) {
            Ok(Ok(v)) => {
                values.insert(i, v);
            }
            Ok(Err(d)) => {
                ev.abandon();
                left.insert(i);
                warnings.push(unused_warning(names[i], d));
            }
            Err(_) => {
                ev.abandon();
                left.insert(i);
            }
        }
    }
    (values, warnings)
}

/// The error of evaluating the unused definition `name`, as a warning.
fn unused_warning(name: &ast::Ident, mut d: Diagnostic) -> Diagnostic {
    d.severity = Severity::Warning;
    d.span = d.span.or(Some(name.span));
    d.message = format!(
        "{} (in `{}`, which nothing in the scene uses)",
        d.message, name.name
    );
    d
}

impl Scene {
    /// The meaning of every name outside the scene (the REPL, `--at`): the
    /// definitions, then the deferred ones, as `Binding::Def` in that
    /// order; `solve` unknowns, multipliers and free momenta as unknowns.
    pub(super) fn bindings(&self) -> FxHashMap<String, (Binding, Span)> {
        let mut names: FxHashMap<String, (Binding, Span)> = FxHashMap::default();
        for c in &self.coordinates {
            names.insert(c.name.clone(), (Binding::Coord, c.span));
        }
        for p in &self.parameters {
            names.insert(p.name.clone(), (Binding::Param, p.span));
        }
        for f in &self.functions {
            names.insert(f.name.clone(), (Binding::Given, f.span));
        }
        for (i, d) in self.definitions.iter().enumerate() {
            names.insert(d.name.clone(), (Binding::Def(i), d.span));
        }
        let n = self.definitions.len();
        for (j, d) in self.deferred.iter().enumerate() {
            names.insert(d.name.name.clone(), (Binding::Def(n + j), d.name.span));
        }
        names.insert("t".into(), (Binding::Time, Span::default()));
        names.insert("pi".into(), (Binding::Pi, Span::default()));
        for sys in &self.systems {
            for u in &sys.unknowns {
                names.insert(u.name.clone(), (Binding::Unknown, u.span));
            }
        }
        // a multiplier is an unknown outside the scene (the REPL, `--at`),
        // and so is a momentum `p_q` the scene leaves free (`qdot hamilton`)
        for c in &self.constraints {
            names.insert(c.multiplier.clone(), (Binding::Unknown, c.span));
        }
        // so is a joint's friction (`G_f`)
        for f in self.joints.iter().filter_map(|j| j.friction.as_ref()) {
            names.insert(f.unknown.clone(), (Binding::Unknown, f.span));
        }
        for c in &self.coordinates {
            let p = momentum_name(&c.name);
            names.entry(p).or_insert((Binding::Unknown, c.span));
        }
        names
    }

    /// The definitions as an evaluator's entries, in the order of
    /// [`Scene::bindings`]: the deferred ones with a value once evaluated.
    fn entries(&self) -> impl Iterator<Item = Entry<'_>> {
        let known = self
            .definitions
            .iter()
            .map(|d| Entry::Known(d.value.clone()));
        let deferred = self.deferred.iter().map(|d| match d.value.get() {
            Some(Ok(v)) => Entry::Known(v.clone()),
            _ => Entry::Pending(&d.name, &d.body),
        });
        known.chain(deferred)
    }

    /// The value of the deferred definition `j`, evaluated on first ask
    /// (with the deferred ones it uses, which keep their values too).
    pub(super) fn deferred_value(&self, j: usize) -> Result<&Value, &Diagnostic> {
        self.deferred[j]
            .value
            .get_or_init(|| {
                let names = self.bindings();
                let mut ev = SyntaxEvaluator::with_entries(&names, self.entries());
                ev.assumed = self.assumptions.clone();
                let n = self.definitions.len();
                let v = ev.definition(n + j);
                for (k, d) in self.deferred.iter().enumerate() {
                    if let (true, Some(w)) = (k != j, ev.evaluated(n + k)) {
                        // set once: a value found before stays
                        let _ = d.value.set(Ok(w.clone()));
                    }
                }
                v
            })
            .as_ref()
    }

    /// The value of the definition `name` (evaluated when it was deferred),
    /// or the error of evaluating it; `None` when the scene has no
    /// definition `name`.
    pub fn try_value(&self, name: &str) -> Option<Result<&Value, &Diagnostic>> {
        if let Some(d) = self.definitions.iter().find(|d| d.name == name) {
            return Some(Ok(&d.value));
        }
        let j = self.deferred.iter().position(|d| d.name.name == name)?;
        Some(self.deferred_value(j))
    }

    /// Evaluate a parsed expression in the scene's names (see
    /// [`Scene::evaluate`]); a deferred definition it names is evaluated
    /// first, and its error says which definition failed (its span points
    /// into the scene, not into `e`'s text).
    pub(super) fn evaluate_in_scene(
        &self,
        e: &ast::Expr,
        extra: &[(&str, Value)],
    ) -> Result<(Value, Vec<Diagnostic>), Diagnostic> {
        let mut names = self.bindings();
        let n = self.definitions.len();
        for (name, _) in names_in(&names, e) {
            let Some((Binding::Def(k), _)) = names.get(name) else {
                continue;
            };
            if let Some(Err(d)) = k.checked_sub(n).map(|j| self.deferred_value(j)) {
                let (line, _) = Diagnostic::line_col(&self.source, d.span.map_or(0, |s| s.start));
                let mut out = Diagnostic::global(format!(
                    "`{name}` can't be evaluated: {} (line {line} of the scene)",
                    d.message
                ))
                .with_kind(d.kind.as_ref().clone());
                out.hint = d.hint.clone();
                return Err(out);
            }
        }
        let mut entries: Vec<Entry> = self.entries().collect();
        for (name, v) in extra {
            names.insert(
                (*name).to_string(),
                (Binding::Def(entries.len()), Span::default()),
            );
            entries.push(Entry::Known(v.clone()));
        }
        let mut ev = SyntaxEvaluator::with_entries(&names, entries);
        ev.assumed = self.assumptions.clone();
        let v = ev.value(e)?;
        Ok((v, std::mem::take(&mut ev.warnings)))
    }
}
