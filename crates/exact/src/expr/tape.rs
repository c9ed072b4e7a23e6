//! Named intermediates: a straight-line program of exact definitions.
//!
//! A [`Tape`] holds intermediates `name = value` in the order they were
//! defined; each value is a canonical [`Expr`] in the coordinates, their
//! derivatives, t, the parameters and *earlier* intermediates, which it
//! mentions as [`Atom::Named`] atoms. A result written through a tape
//! stays the size of its recursion (a chain's kinematics link by link)
//! where its expansion grows like a product of sums.
//!
//! The canonical form treats an intermediate as an independent symbol, so
//! every operation on tape expressions is exact: a relation between
//! intermediates the canonical form cannot see (R·Rᵀ = I) is only left
//! unsimplified, never used wrongly. Differentiation goes through the
//! tape's chain rule ([`Tape::partial`], [`Tape::dt`]), which defines
//! the derivatives of the intermediates as intermediates in their turn,
//! memoized. [`Tape::expand`] substitutes the values back: the expanded
//! result equals the one derived without a tape.
//!
//! Invariants: an entry's value mentions only entries before it (checked
//! by `debug_assert` when it is defined), so one pass in order evaluates,
//! expands or prints the whole tape, and no walk recurses; and no entry
//! mentions a coordinate's acceleration, so the q̈ of a result are all in
//! sight (the rates are taken with q̈ = 0, their q̈ terms written out).

use super::atom::{self, Atom, NamedAtom};
use super::Expr;
use super::MathError;
use crate::poly::Var;
use rustc_hash::{FxHashMap, FxHashSet};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;

/// One intermediate: `name = value`.
#[derive(Clone, Debug)]
pub struct TapeEntry {
    /// The name as given (its input syntax is [`TapeEntry::input_name`]).
    pub name: String,
    /// The atom that stands for it in later values and in results.
    pub var: Var,
    /// Its value, in earlier entries.
    pub value: Expr,
    /// The coordinates (of every order), given functions and t that the
    /// value depends on through its whole definition, sorted: what decides
    /// that a derivative is zero without differentiating.
    leaves: Arc<[Var]>,
}

impl TapeEntry {
    /// The name in input syntax (with its order: `P1_x_dot`).
    pub fn input_name(&self) -> String {
        crate::expr::print::atom_input(&atom::atom(self.var))
    }

    /// The entry's atom as an expression.
    pub fn expr(&self) -> Expr {
        Expr::var(self.var)
    }
}

/// A growing list of named intermediates (see the module docs).
#[derive(Clone, Debug)]
pub struct Tape {
    id: u64,
    entries: Vec<TapeEntry>,
    /// Entry index of each intermediate's atom.
    index: FxHashMap<Var, usize>,
    /// Names in use: the entries' and the reserved ones (a scene's).
    taken: FxHashSet<String>,
    /// ∂(entry)/∂v, memoized.
    partials: FxHashMap<(usize, Var), Expr>,
    /// The rate of an entry: its time derivative with every coordinate
    /// acceleration set to zero, memoized.
    rates: FxHashMap<usize, Expr>,
    /// The terms of all values: the tape's size, under the work budget.
    terms: usize,
    /// Each value once: an intermediate whose value is already on the tape
    /// is that entry (∂Ẋ/∂q and the rate of ∂X/∂q are one).
    by_value: FxHashMap<Expr, Var>,
    /// For the rate Ẋ of an entry X of the coordinates and t alone: X.
    /// Then ∂Ẋ/∂q̇ = ∂X/∂q, which is reused instead of differentiated again.
    rate_of: FxHashMap<usize, usize>,
}

/// Two tapes are equal when they are the same tape at the same length.
impl PartialEq for Tape {
    fn eq(&self, other: &Tape) -> bool {
        self.id == other.id && self.entries.len() == other.entries.len()
    }
}

impl Default for Tape {
    fn default() -> Self {
        Tape::new()
    }
}

static TAPES: AtomicU64 = AtomicU64::new(1);

/// Whether `v` is a coordinate velocity or higher derivative (its time
/// derivative is an acceleration the equations keep explicit).
fn is_rate_of_coordinate(v: Var) -> Option<Var> {
    match atom::atom(v) {
        Atom::Coord(name, k) if k >= 1 => Some(atom::coord(&name, k + 1)),
        _ => None,
    }
}

/// The atoms of `e` and every atom inside their arguments, at any depth.
fn atoms_within(e: &Expr) -> impl Iterator<Item = Var> {
    e.vars().into_iter().flat_map(|v| {
        let inner = atom::inner_atoms(v);
        std::iter::once(v).chain((0..inner.len()).map(move |k| inner[k]))
    })
}

/// Whether `v` is a base symbol that moves: a coordinate of any order, a
/// given function of time or t itself.
fn is_leaf(v: Var) -> bool {
    matches!(
        atom::atom(v),
        Atom::Coord(..) | Atom::Given(..) | Atom::Time
    )
}

impl Tape {
    /// An empty tape with a process-unique identity.
    pub fn new() -> Tape {
        Tape {
            id: TAPES.fetch_add(1, Ordering::Relaxed),
            entries: Vec::new(),
            index: FxHashMap::default(),
            taken: FxHashSet::default(),
            partials: FxHashMap::default(),
            rates: FxHashMap::default(),
            terms: 0,
            by_value: FxHashMap::default(),
            rate_of: FxHashMap::default(),
        }
    }

    /// Keep `name` out of the names the tape gives (a scene's own names).
    pub fn reserve(&mut self, name: &str) {
        self.taken.insert(name.to_string());
    }

    /// The entries, in definition order.
    pub fn entries(&self) -> &[TapeEntry] {
        &self.entries
    }

    /// How many entries the tape holds.
    pub fn len(&self) -> usize {
        self.entries.len()
    }

    /// Whether the tape holds no entry.
    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }

    /// The entry behind an atom of this tape.
    pub fn entry_of(&self, v: Var) -> Option<&TapeEntry> {
        self.index.get(&v).map(|&i| &self.entries[i])
    }

    /// `value` under a new name built from `hint`, unless it is too small to
    /// be worth one (a number, or a number times one symbol): then `value`
    /// itself.
    pub fn define(&mut self, hint: &str, value: Expr) -> Expr {
        if is_trivial(&value) || mentions_acceleration(&value) {
            return value;
        }
        self.name(hint, 0, value)
    }

    /// `value` under the name `hint` (or the first free `hint_k`), however
    /// small: a name the user asked to keep.
    pub fn keep(&mut self, hint: &str, value: Expr) -> Expr {
        if mentions_acceleration(&value) {
            return value;
        }
        // the name is the definition's own (reserved against generated
        // names, not against itself)
        if !self.entries.iter().any(|e| e.name == hint) {
            self.taken.remove(hint);
        }
        self.name(hint, 0, value)
    }

    fn free_name(&self, hint: &str, order: u32) -> String {
        let mark = |n: &str| input_name(n, order);
        if !self.taken.contains(&mark(hint)) {
            return hint.to_string();
        }
        (2..)
            .map(|k| format!("{hint}_{k}"))
            .find(|n| !self.taken.contains(&mark(n)))
            .unwrap_or_default()
    }

    fn name(&mut self, hint: &str, order: u32, value: Expr) -> Expr {
        if let Some(&v) = self.by_value.get(&value) {
            return Expr::var(v);
        }
        let name = self.free_name(hint, order);
        self.terms = self
            .terms
            .saturating_add(value.num().terms().len() + value.den().terms().len());
        crate::budget::check_terms(self.terms);
        let leaves = self.leaves_of(&value);
        debug_assert!(
            value
                .vars()
                .iter()
                .all(|v| self.index.contains_key(v) || !matches!(atom::atom(*v), Atom::Named(_))),
            "a tape value mentions an intermediate of another tape"
        );
        let highest = leaves
            .iter()
            .filter_map(|&v| match atom::atom(v) {
                Atom::Coord(n, k) => Some((n, k)),
                _ => None,
            })
            .max_by_key(|(_, k)| *k);
        let var = atom::named(NamedAtom {
            name: Arc::from(name.as_str()),
            order,
            tape: self.id,
            highest,
            moving: !leaves.is_empty(),
        });
        self.taken.insert(input_name(&name, order));
        self.index.insert(var, self.entries.len());
        self.by_value.insert(value.clone(), var);
        self.entries.push(TapeEntry {
            name,
            var,
            value,
            leaves,
        });
        Expr::var(var)
    }

    /// The moving base symbols `e` depends on, through its intermediates
    /// (those inside a function's argument too).
    fn leaves_of(&self, e: &Expr) -> Arc<[Var]> {
        let mut out: Vec<Var> = Vec::new();
        for w in atoms_within(e) {
            if let Some(&i) = self.index.get(&w) {
                out.extend_from_slice(&self.entries[i].leaves);
            } else if is_leaf(w) {
                out.push(w);
            }
        }
        out.sort_unstable();
        out.dedup();
        out.into()
    }

    /// The entries `e` mentions, as atoms or inside a function's argument
    /// (`cos(alpha)` mentions `alpha`): every intermediate the chain rule
    /// must go through. Differentiating `e` with respect to such an atom
    /// goes through the function ([`Expr::diff`] treats it as a symbol).
    fn named_in(&self, e: &Expr) -> Vec<usize> {
        let mut out: Vec<usize> = atoms_within(e)
            .filter_map(|w| self.index.get(&w).copied())
            .collect();
        out.sort_unstable();
        out.dedup();
        out
    }

    /// Whether entry `i` depends on the symbol `v`.
    fn entry_depends_on(&self, i: usize, v: Var) -> bool {
        self.entries[i].leaves.binary_search(&v).is_ok()
    }

    /// The intermediates of `e` (entry indices) that depend on `v`.
    fn dependent_entries(&self, e: &Expr, v: Var) -> Vec<usize> {
        self.named_in(e)
            .into_iter()
            .filter(|&i| self.entry_depends_on(i, v))
            .collect()
    }

    /// ∂e/∂v by the chain rule through the intermediates: v is a
    /// coordinate, a velocity or t. The partials of intermediates are
    /// defined as intermediates (`d_NAME_v`), each once.
    pub fn partial(&mut self, e: &Expr, v: Var) -> Expr {
        let mut out = e.diff(v);
        let needed = self.dependent_entries(e, v);
        self.ensure_partials(&needed, v);
        for i in needed {
            let d = self.partials[&(i, v)].clone();
            if !d.is_zero() {
                out = out.add(&e.diff(self.entries[i].var).mul(&d));
            }
        }
        out
    }

    /// Define ∂(entry)/∂v for `roots` and every intermediate they need, in
    /// an order where each comes after those its value mentions (a stack,
    /// not recursion: the depth of a tape is the user's).
    fn ensure_partials(&mut self, roots: &[usize], v: Var) {
        let mut stack: Vec<usize> = roots
            .iter()
            .copied()
            .filter(|&i| !self.partials.contains_key(&(i, v)))
            .collect();
        while let Some(&top) = stack.last() {
            if self.partials.contains_key(&(top, v)) {
                stack.pop();
                continue;
            }
            if let Some(d) = self.velocity_partial_of_rate(top, v) {
                stack.pop();
                self.partials.insert((top, v), d);
                continue;
            }
            let value = self.entries[top].value.clone();
            let missing: Vec<usize> = self
                .dependent_entries(&value, v)
                .into_iter()
                .filter(|&i| !self.partials.contains_key(&(i, v)))
                .collect();
            if !missing.is_empty() {
                stack.extend(missing);
                continue;
            }
            stack.pop();
            let mut d = value.diff(v);
            for i in self.dependent_entries(&value, v) {
                let di = self.partials[&(i, v)].clone();
                if !di.is_zero() {
                    d = d.add(&value.diff(self.entries[i].var).mul(&di));
                }
            }
            let hint = format!("d_{}_{}", self.entries[top].name, var_hint(v));
            let named = self.define(&hint, d);
            self.partials.insert((top, v), named);
        }
    }

    /// ∂Ẋ/∂q̇ = ∂X/∂q when entry `i` is the rate of an X of the
    /// coordinates and t and `v` is a velocity q̇.
    fn velocity_partial_of_rate(&mut self, i: usize, v: Var) -> Option<Expr> {
        let &x = self.rate_of.get(&i)?;
        let Atom::Coord(name, 1) = atom::atom(v) else {
            return None;
        };
        let q = atom::coord(&name, 0);
        let e = self.entries[x].expr();
        Some(self.partial(&e, q))
    }

    /// de/dt, the total time derivative, with every coordinate acceleration
    /// written out (q̈ appears in the result itself, never inside an
    /// intermediate): an intermediate X contributes ∂e/∂X·(Ẋ⁰ + Σ ∂X/∂q̇·q̈),
    /// where the rate Ẋ⁰ (X's derivative with q̈ = 0) is an intermediate
    /// `NAME'`.
    pub fn dt(&mut self, e: &Expr) -> Expr {
        let mut out = e.dt();
        let moving: Vec<usize> = self
            .named_in(e)
            .into_iter()
            .filter(|&i| !self.entries[i].leaves.is_empty())
            .collect();
        self.ensure_rates(&moving);
        for i in moving {
            let total = self.total_rate(i);
            if !total.is_zero() {
                out = out.add(&e.diff(self.entries[i].var).mul(&total));
            }
        }
        out
    }

    /// Entry `i`'s whole time derivative: its rate plus its acceleration
    /// terms Σ ∂X/∂q̇·q̈ (rates must be defined).
    fn total_rate(&mut self, i: usize) -> Expr {
        let mut total = self.rates[&i].clone();
        // the partials are defined (and named) in the atoms'
        // history-independent order, not the ids'
        let mut leaves = self.entries[i].leaves.to_vec();
        leaves.sort_by_cached_key(|&w| atom::stable_key(w));
        for w in leaves {
            let Some(acc) = is_rate_of_coordinate(w) else {
                continue;
            };
            let d = self.partial(&self.entries[i].expr(), w);
            if !d.is_zero() {
                total = total.add(&d.mul(&Expr::var(acc)));
            }
        }
        total
    }

    /// Define the rates of `roots` and of what they need (see
    /// [`Tape::ensure_partials`]).
    fn ensure_rates(&mut self, roots: &[usize]) {
        let mut stack: Vec<usize> = roots
            .iter()
            .copied()
            .filter(|i| !self.rates.contains_key(i))
            .collect();
        while let Some(&top) = stack.last() {
            if self.rates.contains_key(&top) {
                stack.pop();
                continue;
            }
            let value = self.entries[top].value.clone();
            let inner: Vec<usize> = self
                .named_in(&value)
                .into_iter()
                .filter(|&i| !self.entries[i].leaves.is_empty())
                .collect();
            let missing: Vec<usize> = inner
                .iter()
                .copied()
                .filter(|i| !self.rates.contains_key(i))
                .collect();
            if !missing.is_empty() {
                stack.extend(missing);
                continue;
            }
            stack.pop();
            // the rate: d/dt of the value with the accelerations dropped
            let mut d = drop_accelerations(&value.dt());
            for i in inner {
                let r = self.rates[&i].clone();
                if !r.is_zero() {
                    d = d.add(&value.diff(self.entries[i].var).mul(&r));
                }
            }
            let entry = &self.entries[top];
            let named = if is_trivial(&d) {
                d
            } else if entry
                .leaves
                .iter()
                .any(|&w| is_rate_of_coordinate(w).is_some())
            {
                // not the whole derivative (its q̈ terms are outside): no prime
                let hint = format!("{}_dt", entry.name);
                self.name(&hint, 0, d)
            } else {
                // a function of q and t: the rate is the derivative, `NAME'`
                let (name, order) = (entry.name.clone(), self.order_of(top) + 1);
                let named = self.name(&name, order, d);
                if let Some(&i) = named.as_var().and_then(|v| self.index.get(&v)) {
                    // a value met before is that entry's: ∂Ẋ/∂q̇ = ∂X/∂q holds
                    // for it all the same (it is Ẋ)
                    self.rate_of.entry(i).or_insert(top);
                }
                named
            };
            self.rates.insert(top, named);
        }
    }

    fn order_of(&self, i: usize) -> u32 {
        match atom::atom(self.entries[i].var) {
            Atom::Named(n) => n.order,
            _ => 0,
        }
    }

    /// The entries `roots` depend on, transitively, in definition order:
    /// what a result written through the tape must print before it.
    pub fn used_by<'a>(&self, roots: impl IntoIterator<Item = &'a Expr>) -> Vec<usize> {
        let mut seen = vec![false; self.entries.len()];
        let mut stack: Vec<usize> = Vec::new();
        for e in roots {
            stack.extend(self.named_in(e));
        }
        while let Some(i) = stack.pop() {
            if std::mem::replace(&mut seen[i], true) {
                continue;
            }
            stack.extend(self.named_in(&self.entries[i].value));
        }
        (0..self.entries.len()).filter(|&i| seen[i]).collect()
    }

    /// The numeric value of `e`, with `f` giving the parameters,
    /// coordinates and t, every intermediate it needs evaluated once in
    /// order. `None` where a value is undefined (a division by zero).
    pub fn eval_f64(&self, e: &Expr, f: &dyn Fn(&Atom) -> Option<f64>) -> Option<f64> {
        self.eval_many_f64(std::slice::from_ref(e), f).map(|v| v[0])
    }

    /// [`Tape::eval_f64`] of several expressions, the intermediates they
    /// share evaluated once.
    pub fn eval_many_f64(&self, es: &[Expr], f: &dyn Fn(&Atom) -> Option<f64>) -> Option<Vec<f64>> {
        let eval = |x: &Expr, values: &FxHashMap<Arc<NamedAtom>, f64>| {
            x.eval_f64(&|a: &Atom| match a {
                Atom::Named(n) => values.get(n).copied(),
                other => f(other),
            })
        };
        let mut values: FxHashMap<Arc<NamedAtom>, f64> = FxHashMap::default();
        for i in self.used_by(es) {
            let entry = &self.entries[i];
            let v = eval(&entry.value, &values)?;
            if let Atom::Named(n) = atom::atom(entry.var) {
                values.insert(n, v);
            }
        }
        es.iter().map(|e| eval(e, &values)).collect()
    }

    /// `e` with every intermediate replaced by its expanded value: the
    /// canonical result the tape stands for. Work on the expansions is
    /// charged to the budget like any other.
    pub fn expand(&self, e: &Expr) -> Result<Expr, MathError> {
        let order = self.used_by(std::iter::once(e));
        let mut map: FxHashMap<Var, Expr> = FxHashMap::default();
        // every expanded value is held until the end: their terms together
        // are bounded as one expression's (each alone may stay under the
        // budget while a long chain's hundreds of them fill the memory)
        let mut held = 0usize;
        for i in order {
            let entry = &self.entries[i];
            let v = entry.value.subs_many(&map)?;
            held = held.saturating_add(v.num().len() + v.den().len());
            crate::budget::check_terms(held);
            map.insert(entry.var, v);
        }
        if map.is_empty() {
            return Ok(e.clone());
        }
        e.subs_many(&map)
    }
}

/// How a derivation differentiates: on expanded expressions
/// ([`Expanded`]) or through a tape's intermediates ([`Tape`]). Lagrange's
/// equations are written once, over this.
pub trait Calculus {
    /// ∂e/∂v.
    fn partial(&mut self, e: &Expr, v: Var) -> Expr;
    /// de/dt, with the coordinate accelerations in the result itself.
    fn dt(&mut self, e: &Expr) -> Expr;
    /// Whether `e` depends on `v` at all (a cheap test before a derivative).
    fn depends(&self, e: &Expr, v: Var) -> bool;
}

/// Differentiation of canonical expressions without intermediates.
#[derive(Clone, Copy, Debug, Default)]
pub struct Expanded;

impl Calculus for Expanded {
    fn partial(&mut self, e: &Expr, v: Var) -> Expr {
        e.diff(v)
    }
    fn dt(&mut self, e: &Expr) -> Expr {
        e.dt()
    }
    fn depends(&self, e: &Expr, v: Var) -> bool {
        crate::expr::diff::vars_depend_on(&e.vars(), v)
    }
}

impl Calculus for Tape {
    fn partial(&mut self, e: &Expr, v: Var) -> Expr {
        Tape::partial(self, e, v)
    }
    fn dt(&mut self, e: &Expr) -> Expr {
        Tape::dt(self, e)
    }
    fn depends(&self, e: &Expr, v: Var) -> bool {
        crate::expr::diff::vars_depend_on(&e.vars(), v)
            || self
                .named_in(e)
                .into_iter()
                .any(|i| self.entry_depends_on(i, v))
    }
}

/// The name of an intermediate in input syntax and JSON: an identifier,
/// `P1_x` and its rate `P1_x_dot` (`_ddot`, then `_d3`, …), so that a
/// consumer binds every name of the list as a plain variable.
pub fn input_name(name: &str, order: u32) -> String {
    match order {
        0 => name.to_string(),
        1 => format!("{name}_dot"),
        2 => format!("{name}_ddot"),
        k => format!("{name}_d{k}"),
    }
}

/// The name of an intermediate in text: as given, each part between
/// underscores that names a Greek letter written as that letter, with a
/// prime per time derivative (`P1_x′`, `ω_B2_x`, `h_θ`).
pub fn unicode_name(name: &str, order: u32) -> String {
    let greek = |part: &str| -> String {
        crate::expr::print::GREEK
            .iter()
            .find(|(k, _)| *k == part)
            .map_or_else(|| part.to_string(), |(_, g)| (*g).to_string())
    };
    let base: Vec<String> = name.split('_').map(greek).collect();
    format!("{}{}", base.join("_"), "′".repeat(order as usize))
}

/// The name of an intermediate in LaTeX: the part before the first `_`
/// with the rest as its subscript, further underscores as commas
/// (`B2_{23}`, `\omega_{B2,x}`), and a prime per time derivative.
pub fn latex_name(name: &str, order: u32) -> String {
    let escape = |s: &str| s.replace('_', ",");
    let (head, tail) = match name.split_once('_') {
        Some((h, t)) if !h.is_empty() && !t.is_empty() => (h, Some(t)),
        _ => (name, None),
    };
    let head = if head == "omega" {
        "\\omega".to_string()
    } else {
        head.to_string()
    };
    let body = match tail {
        Some(t) => format!("{head}_{{{}}}", escape(t)),
        None => head,
    };
    if order == 0 {
        body
    } else {
        format!("{{{body}}}{}", "'".repeat(order as usize))
    }
}

/// Whether `e` mentions a coordinate's acceleration (or a higher
/// derivative): such a value is never named, so that the equations keep
/// every q̈ in sight (they are split into M·q̈ and the rest by reading q̈).
fn mentions_acceleration(e: &Expr) -> bool {
    e.highest_time_derivative().is_some_and(|(_, k)| k >= 2)
}

/// Whether a value is too small for a name: a number, or a number times a
/// single atom to the first power.
fn is_trivial(e: &Expr) -> bool {
    if !e.is_poly() {
        return false;
    }
    match e.num().terms() {
        [] => true,
        [(m, _)] => m.is_one() || matches!(m.0.as_slice(), [(_, 1)]),
        _ => false,
    }
}

/// `e` with every coordinate acceleration (q̈ and higher) set to zero.
fn drop_accelerations(e: &Expr) -> Expr {
    let map: FxHashMap<Var, Expr> = e
        .vars()
        .into_iter()
        .filter(|&v| matches!(atom::atom(v), Atom::Coord(_, k) if k >= 2))
        .map(|v| (v, Expr::zero()))
        .collect();
    if map.is_empty() {
        return e.clone();
    }
    e.subs_many(&map).unwrap_or_else(|_| e.clone())
}

/// A short name for a variable in a derivative's name: `q1`, `q1_t` for
/// q̇1, `t`.
fn var_hint(v: Var) -> String {
    match atom::atom(v) {
        Atom::Coord(n, 0) | Atom::Given(n, 0) => n.to_string(),
        Atom::Coord(n, k) | Atom::Given(n, k) => format!("{n}{}", "_t".repeat(k as usize)),
        Atom::Time => "t".into(),
        other => crate::expr::print::atom_input(&other),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn q(n: &str, k: u32) -> Expr {
        Expr::coord(n, k)
    }

    /// A two-link chain of sines written through intermediates expands to
    /// the same derivatives as the expanded form.
    #[test]
    fn chain_rule_through_intermediates_equals_the_expanded_derivative() {
        let mut tape = Tape::new();
        let s1 = crate::expr::func::sin(&q("a", 0));
        let c2 = crate::expr::func::cos(&q("b", 0));
        let x = tape.define("x", s1.mul(&q("b", 0)).add(&c2));
        let y = tape.define("y", x.mul(&x).add(&x.mul(&s1)));
        let y_value = tape.expand(&y).unwrap();
        for v in [atom::coord("a", 0), atom::coord("b", 0)] {
            let d = tape.partial(&y, v);
            assert!(tape.expand(&d).unwrap().equals(&y_value.diff(v)));
        }
        // velocities: y depends on q̇ through nothing, so ẏ has no q̈
        let w = tape.define("w", y.mul(&q("a", 1)));
        let dw = tape.dt(&w);
        let w_value = tape.expand(&w).unwrap();
        assert!(tape.expand(&dw).unwrap().equals(&w_value.dt()));
        // q̈ stays outside the intermediates
        assert!(dw.depends_on(atom::coord("a", 2)));
        for e in tape.entries() {
            assert!(e.value.highest_time_derivative().is_none_or(|(_, k)| k < 2));
        }
    }

    /// An intermediate inside a function's argument (`cos(x)` of a named
    /// x) is differentiated through the function.
    #[test]
    fn intermediates_inside_functions_are_differentiated_through_them() {
        let mut tape = Tape::new();
        let x = tape.keep("x", crate::expr::func::sin(&q("a", 0)).add(&q("a", 0)));
        let y = tape.define("y", crate::expr::func::cos(&x).mul(&q("b", 0)).add(&x));
        let z = crate::expr::func::sqrt(&y.mul(&y).add(&Expr::one())).unwrap();
        let z_value = tape.expand(&z).unwrap();
        assert!(!z_value.vars().iter().any(|&v| tape.entry_of(v).is_some()));
        for v in [atom::coord("a", 0), atom::coord("b", 0)] {
            let d = tape.partial(&z, v);
            assert!(tape.expand(&d).unwrap().equals(&z_value.diff(v)));
        }
        let dz = tape.dt(&z);
        assert!(tape.expand(&dz).unwrap().equals(&z_value.dt()));
        assert_eq!(tape.used_by([&z]).len(), 2);
    }

    #[test]
    fn trivial_values_are_not_named_and_names_do_not_collide() {
        let mut tape = Tape::new();
        tape.reserve("x");
        assert!(tape.define("c", Expr::int(3)).equals(&Expr::int(3)));
        let s = crate::expr::func::sin(&q("a", 0));
        assert!(tape.define("c", s.clone()).equals(&s));
        let named = tape.define("x", s.add(&Expr::one()));
        assert_eq!(tape.entries()[0].name, "x_2");
        assert_eq!(named.to_input(), "x_2");
        let used = tape.used_by([&named.mul(&named)]);
        assert_eq!(used, vec![0]);
    }
}
