//! From canonical expressions to a hash-consed graph of nodes: constant
//! folding, shared subexpressions, greedy multivariate Horner schemes.

use crate::expr::atom::{self, Atom};
use crate::expr::Expr;
use crate::poly::{Mono, Poly, Var};
use qdot_exact::num::Q;
use rustc_hash::FxHashMap;
use smallvec::SmallVec;

use super::error::CompileError;
use super::program::{powi, Program};

/// Compile `outputs` as functions of the atoms `inputs` (given in this
/// order to [`Program::eval`]). Every parameter, coordinate or time the
/// outputs mention must be an input.
pub fn compile(outputs: &[Expr], inputs: &[Var]) -> Result<Program, CompileError> {
    compile_with(outputs, inputs, &FxHashMap::default())
}

/// [`compile`] with some atoms (usually parameters) bound to numbers at
/// compile time: they are folded into the constants (a bound atom that is
/// also an input takes its bound value; its input slot is then ignored).
pub fn compile_with(
    outputs: &[Expr],
    inputs: &[Var],
    params: &FxHashMap<Var, f64>,
) -> Result<Program, CompileError> {
    compile_through(outputs, inputs, params, None)
}

/// [`compile_with`] for outputs written through the intermediates of
/// `tape`: each intermediate they use is compiled once, in the tape's
/// order, and its node stands for it wherever it appears (the shared
/// subexpressions of a recursive derivation, by construction).
pub fn compile_through(
    outputs: &[Expr],
    inputs: &[Var],
    params: &FxHashMap<Var, f64>,
    tape: Option<&crate::expr::tape::Tape>,
) -> Result<Program, CompileError> {
    let mut b = Builder::new(inputs, params);
    if let Some(tape) = tape {
        for i in tape.used_by(outputs) {
            let entry = &tape.entries()[i];
            let node = b.expr(&entry.value)?;
            b.atoms.insert(entry.var, node);
        }
    }
    let mut outs = Vec::with_capacity(outputs.len());
    for e in outputs {
        outs.push(b.expr(e)?);
    }
    Ok(b.finish(&outs))
}

/// The number of arithmetic operations and function calls a tree walk
/// ([`Expr::eval_f64`]) performs on `outputs`: per polynomial, every atom
/// evaluated once (recursively through function arguments), then per term
/// one multiplication per factor (`vᵉ` counts e) and one addition; one
/// division per non-polynomial expression. The yardstick of the
/// compiler's common-subexpression sharing.
pub fn naive_op_count(outputs: &[Expr]) -> usize {
    fn expr(e: &Expr) -> usize {
        poly(e.num()) + if e.is_poly() { 0 } else { poly(e.den()) + 1 }
    }
    fn poly(p: &Poly) -> usize {
        let mut n = 0;
        for v in p.vars() {
            n += 1 + atom::atom(v).argument().map(expr).unwrap_or(0);
        }
        for (m, _) in p.terms() {
            n += 1 + m.0.iter().map(|&(_, e)| e as usize).sum::<usize>();
        }
        n
    }
    outputs.iter().map(expr).sum()
}

/// A quotient's two sides, borrowed.
struct Parts<'a>(&'a Poly, &'a Poly);

impl Parts<'_> {
    fn num(&self) -> &Poly {
        self.0
    }
    fn den(&self) -> &Poly {
        self.1
    }
}

/// A node of the expression DAG; operands are node ids.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(super) enum Node {
    Input(u32),
    Const(u64),
    Add(u32, u32),
    Sub(u32, u32),
    Mul(u32, u32),
    MulAdd(u32, u32, u32),
    Div(u32, u32),
    Neg(u32),
    Powi(u32, u32),
    Sin(u32),
    Cos(u32),
    Exp(u32),
    Ln(u32),
    Sqrt(u32),
    Atan(u32),
    Asin(u32),
    Acos(u32),
}

impl Node {
    pub(super) fn operands(&self) -> SmallVec<[u32; 3]> {
        use Node::*;
        match *self {
            Input(_) | Const(_) => SmallVec::new(),
            Add(a, b) | Sub(a, b) | Mul(a, b) | Div(a, b) => SmallVec::from_slice(&[a, b]),
            MulAdd(a, b, c) => SmallVec::from_slice(&[a, b, c]),
            Neg(a)
            | Powi(a, _)
            | Sin(a)
            | Cos(a)
            | Exp(a)
            | Ln(a)
            | Sqrt(a)
            | Atan(a)
            | Asin(a)
            | Acos(a) => SmallVec::from_slice(&[a]),
        }
    }
}

/// A power product over node ids (sorted by id, exponents > 0).
type NodeMonomial = SmallVec<[(u32, u32); 4]>;
/// A polynomial over nodes with f64 coefficients (after constant folding).
type NodePoly = Vec<(NodeMonomial, f64)>;

pub(super) struct Builder<'a> {
    pub(super) nodes: Vec<Node>,
    pub(super) index: FxHashMap<Node, u32>,
    pub(super) inputs: FxHashMap<Var, u32>,
    pub(super) params: &'a FxHashMap<Var, f64>,
    pub(super) atoms: FxHashMap<Var, u32>,
    pub(super) polys: FxHashMap<Poly, u32>,
    pub(super) monos: FxHashMap<NodeMonomial, u32>,
    /// Per node: whether it depends on an input other than a parameter
    /// (the state or the time). Nodes that do not are the same on every
    /// call of a simulation, and are grouped so that they stay off the
    /// state's critical path (`k/m` once, not `(k·x)·(1/m)`).
    varies: Vec<bool>,
    /// The input slots that hold parameters.
    param_slots: Vec<bool>,
}

impl<'a> Builder<'a> {
    fn new(inputs: &[Var], params: &'a FxHashMap<Var, f64>) -> Builder<'a> {
        let mut map = FxHashMap::default();
        for (i, &v) in inputs.iter().enumerate() {
            map.entry(v).or_insert(i as u32);
        }
        let param_slots = inputs
            .iter()
            .map(|&v| matches!(atom::atom(v), Atom::Param(_)))
            .collect();
        Builder {
            nodes: Vec::new(),
            index: FxHashMap::default(),
            inputs: map,
            params,
            atoms: FxHashMap::default(),
            polys: FxHashMap::default(),
            monos: FxHashMap::default(),
            varies: Vec::new(),
            param_slots,
        }
        .with_input_count(inputs.len())
    }

    /// Create the input nodes first (ids 0..n), so an input's node id is
    /// its slot.
    fn with_input_count(mut self, n: usize) -> Self {
        for i in 0..n {
            self.node(Node::Input(i as u32));
        }
        self
    }

    fn node(&mut self, n: Node) -> u32 {
        if let Some(&id) = self.index.get(&n) {
            return id;
        }
        let id = self.nodes.len() as u32;
        let varies = match n {
            Node::Input(slot) => !self.param_slots[slot as usize],
            _ => n.operands().iter().any(|&o| self.varies[o as usize]),
        };
        self.nodes.push(n);
        self.varies.push(varies);
        self.index.insert(n, id);
        id
    }

    fn constant(&mut self, x: f64) -> u32 {
        // One zero (−0.0 and 0.0 are the same constant here).
        let x = if x == 0.0 { 0.0 } else { x };
        self.node(Node::Const(x.to_bits()))
    }

    fn as_const(&self, id: u32) -> Option<f64> {
        match self.nodes[id as usize] {
            Node::Const(b) => Some(f64::from_bits(b)),
            _ => None,
        }
    }

    fn add(&mut self, a: u32, b: u32) -> u32 {
        match (self.as_const(a), self.as_const(b)) {
            (Some(x), Some(y)) => self.constant(x + y),
            (Some(0.0), _) => b,
            (_, Some(0.0)) => a,
            _ => self.node(Node::Add(a.min(b), a.max(b))),
        }
    }

    fn sub(&mut self, a: u32, b: u32) -> u32 {
        match (self.as_const(a), self.as_const(b)) {
            (Some(x), Some(y)) => self.constant(x - y),
            (Some(0.0), _) => self.neg(b),
            (_, Some(0.0)) => a,
            _ => self.node(Node::Sub(a, b)),
        }
    }

    fn neg(&mut self, a: u32) -> u32 {
        match self.nodes[a as usize] {
            Node::Const(b) => self.constant(-f64::from_bits(b)),
            Node::Neg(x) => x,
            _ => self.node(Node::Neg(a)),
        }
    }

    fn mul(&mut self, a: u32, b: u32) -> u32 {
        match (self.as_const(a), self.as_const(b)) {
            (Some(x), Some(y)) => self.constant(x * y),
            (Some(1.0), _) => b,
            (_, Some(1.0)) => a,
            (Some(-1.0), _) => self.neg(b),
            (_, Some(-1.0)) => self.neg(a),
            _ => self.node(Node::Mul(a.min(b), a.max(b))),
        }
    }

    /// a·b + c.
    fn mul_add(&mut self, a: u32, b: u32, c: u32) -> u32 {
        let c_zero = self.as_const(c) == Some(0.0);
        let ab_const = self.as_const(a).is_some() && self.as_const(b).is_some();
        let unit = |x: Option<f64>| matches!(x, Some(v) if v == 1.0 || v == -1.0);
        if c_zero || ab_const || unit(self.as_const(a)) || unit(self.as_const(b)) {
            let p = self.mul(a, b);
            return self.add(p, c);
        }
        self.node(Node::MulAdd(a.min(b), a.max(b), c))
    }

    fn div(&mut self, a: u32, b: u32) -> u32 {
        match (self.as_const(a), self.as_const(b)) {
            (Some(x), Some(y)) => self.constant(x / y),
            (_, Some(1.0)) => a,
            (_, Some(y)) if y.is_finite() && y != 0.0 => {
                let r = self.constant(1.0 / y);
                self.mul(a, r)
            }
            _ => self.node(Node::Div(a, b)),
        }
    }

    fn powi(&mut self, a: u32, n: u32) -> u32 {
        match n {
            0 => self.constant(1.0),
            1 => a,
            _ => match self.as_const(a) {
                Some(x) => self.constant(powi(x, n)),
                None => self.node(Node::Powi(a, n)),
            },
        }
    }

    /// A function of one argument, folded when the argument is constant.
    fn func(&mut self, a: u32, make: fn(u32) -> Node, f: fn(f64) -> f64) -> u32 {
        match self.as_const(a) {
            Some(x) => self.constant(f(x)),
            None => self.node(make(a)),
        }
    }

    // ------------------------------------------------------------ lowering

    fn expr(&mut self, e: &Expr) -> Result<u32, CompileError> {
        // num/den scaled so that the denominator's first term by the atoms'
        // names has coefficient 1: the canonical scaling follows the ids
        let scaled;
        let e = match atom::stable_leading_coeff(e.den()).and_then(|c| c.recip()) {
            Some(r) if !e.den().is_constant() && !r.is_one() => {
                scaled = (e.num().scale(&r), e.den().scale(&r));
                Parts(&scaled.0, &scaled.1)
            }
            _ => Parts(e.num(), e.den()),
        };
        let den = self.node_poly(e.den())?;
        if let Some(c) = constant_of(&den) {
            // A constant denominator folds into the numerator's coefficients.
            if e.den().is_one() {
                return self.poly(e.num());
            }
            let mut num = self.node_poly(e.num())?;
            for t in num.iter_mut() {
                t.1 /= c;
            }
            return Ok(self.horner(num));
        }
        let d = self.poly(e.den())?;
        if !self.varies[d as usize] {
            return self.over_parameters(e.num(), d);
        }
        let n = self.poly(e.num())?;
        Ok(self.div(n, d))
    }

    /// n/d for a denominator d of parameters only: (±g/d)·h, where g is
    /// the power product of parameters common to n's terms and the sign
    /// one all of them share, so that g/d is computed apart from the state
    /// and shared by every output that has it (`(−g/l)·sin θ`, `k/m`).
    fn over_parameters(&mut self, num: &Poly, d: u32) -> Result<u32, CompileError> {
        let mut p = self.node_poly(num)?;
        if p.is_empty() {
            return Ok(self.constant(0.0));
        }
        let fixed = |b: &Self, m: &NodeMonomial| -> NodeMonomial {
            m.iter()
                .filter(|t| !b.varies[t.0 as usize])
                .copied()
                .collect()
        };
        let mut g = fixed(self, &p[0].0);
        for (m, _) in &p[1..] {
            g = mono_gcd(&g, &fixed(self, m));
        }
        let negative = p.iter().all(|t| t.1 < 0.0);
        for t in p.iter_mut() {
            t.0 = mono_div(&t.0, &g);
            if negative {
                t.1 = -t.1;
            }
        }
        let gm = self.mono(&g);
        let base = self.div(gm, d);
        let scale = if negative { self.neg(base) } else { base };
        let rest = self.horner(p);
        Ok(self.mul(scale, rest))
    }

    /// A polynomial, memoized by its exact form.
    fn poly(&mut self, p: &Poly) -> Result<u32, CompileError> {
        if let Some(&id) = self.polys.get(p) {
            return Ok(id);
        }
        let f = self.node_poly(p)?;
        let id = self.horner(f);
        self.polys.insert(p.clone(), id);
        Ok(id)
    }

    /// The terms of `p` over runtime nodes, constant atoms folded into the
    /// coefficients and equal power products merged.
    fn node_poly(&mut self, p: &Poly) -> Result<NodePoly, CompileError> {
        let mut merged: FxHashMap<NodeMonomial, f64> = FxHashMap::default();
        let mut order: Vec<NodeMonomial> = Vec::new();
        // terms and factors in the atoms' history-independent order: the
        // nodes (and so the program, the generated code, the rounding) are
        // the same whatever the process interned first
        let mut terms: Vec<&(Mono, Q)> = p.terms().iter().collect();
        terms.sort_by_cached_key(|(m, _)| atom::stable_mono_key(m));
        for (m, c) in terms {
            let mut coef = c.to_f64();
            let mut mono: NodeMonomial = SmallVec::new();
            let mut factors: SmallVec<[(Var, u32); 4]> = m.0.clone();
            factors.sort_by_cached_key(|&(v, _)| atom::stable_key(v));
            for (v, e) in factors {
                let id = self.atom(v)?;
                match self.as_const(id) {
                    Some(x) => coef *= powi(x, e),
                    None => mono.push((id, e)),
                }
            }
            mono.sort_unstable();
            let mono = merge_dups(mono);
            match merged.get_mut(&mono) {
                Some(x) => *x += coef,
                None => {
                    merged.insert(mono.clone(), coef);
                    order.push(mono);
                }
            }
        }
        Ok(order
            .into_iter()
            .filter_map(|m| {
                let c = merged[&m];
                (c != 0.0).then_some((m, c))
            })
            .collect())
    }

    /// The node of an atom.
    fn atom(&mut self, v: Var) -> Result<u32, CompileError> {
        if let Some(&id) = self.atoms.get(&v) {
            return Ok(id);
        }
        let a = atom::atom(v);
        let id = if let Some(&x) = self.params.get(&v) {
            self.constant(x)
        } else if let Some(&slot) = self.inputs.get(&v) {
            slot
        } else {
            match &a {
                Atom::Param(name) | Atom::Unknown(name) => {
                    return Err(CompileError::UnsetParameter(name.to_string()))
                }
                Atom::Coord(name, k) => {
                    return Err(CompileError::NotAnInput(format!(
                        "the coordinate {name}{}",
                        "'".repeat(*k as usize)
                    )))
                }
                Atom::Time => return Err(CompileError::NotAnInput("the time t".to_string())),
                // a tape's entries are compiled before what mentions them
                Atom::Named(n) => {
                    return Err(CompileError::NotAnInput(format!(
                        "the intermediate {}",
                        n.name
                    )))
                }
                Atom::Given(name, k) => {
                    return Err(CompileError::UndefinedFunction(format!(
                        "{name}{}",
                        "'".repeat(*k as usize)
                    )))
                }
                Atom::Pi => self.constant(std::f64::consts::PI),
                Atom::Root(n) => {
                    let x: f64 = n
                        .parse()
                        .map_err(|_| CompileError::BadRadical(n.to_string()))?;
                    self.constant(x.sqrt())
                }
                Atom::SqrtOf(u) => {
                    let x = self.expr(u)?;
                    self.func(x, Node::Sqrt, f64::sqrt)
                }
                Atom::Sin(u) => {
                    let x = self.expr(u)?;
                    self.func(x, Node::Sin, f64::sin)
                }
                Atom::Cos(u) => {
                    let x = self.expr(u)?;
                    self.func(x, Node::Cos, f64::cos)
                }
                Atom::Exp(u) => {
                    let x = self.expr(u)?;
                    self.func(x, Node::Exp, f64::exp)
                }
                Atom::Ln(u) => {
                    let x = self.expr(u)?;
                    self.func(x, Node::Ln, f64::ln)
                }
                Atom::Atan(u) => {
                    let x = self.expr(u)?;
                    self.func(x, Node::Atan, f64::atan)
                }
                Atom::Asin(u) => {
                    let x = self.expr(u)?;
                    self.func(x, Node::Asin, f64::asin)
                }
                Atom::Acos(u) => {
                    let x = self.expr(u)?;
                    self.func(x, Node::Acos, f64::acos)
                }
                Atom::Shown(_) | Atom::Group(_) => return Err(CompileError::PrintOnly),
            }
        };
        self.atoms.insert(v, id);
        Ok(id)
    }

    /// A power product, built as (shared prefix) × (last factor).
    fn mono(&mut self, m: &[(u32, u32)]) -> u32 {
        match m {
            [] => self.constant(1.0),
            [(v, e)] => self.powi(*v, *e),
            _ => {
                if let Some(&id) = self.monos.get(m) {
                    return id;
                }
                let (last, prefix) = m.split_last().unwrap_or((&(0, 0), &[]));
                let p = self.mono(prefix);
                let l = self.powi(last.0, last.1);
                let id = self.mul(p, l);
                self.monos.insert(SmallVec::from_slice(m), id);
                id
            }
        }
    }

    /// Greedy multivariate Horner evaluation of a folded polynomial.
    fn horner(&mut self, mut p: NodePoly) -> u32 {
        if p.is_empty() {
            return self.constant(0.0);
        }
        if let Some(c) = constant_of(&p) {
            return self.constant(c);
        }
        // The common power product of all terms.
        let mut g: NodeMonomial = p[0].0.clone();
        for (m, _) in &p[1..] {
            g = mono_gcd(&g, m);
            if g.is_empty() {
                break;
            }
        }
        if !g.is_empty() {
            for t in p.iter_mut() {
                t.0 = mono_div(&t.0, &g);
            }
            let rest = self.horner(p);
            let gm = self.mono(&g);
            return self.mul(gm, rest);
        }
        // A common coefficient magnitude.
        let c0 = p[0].1.abs();
        if c0 != 1.0 && p.len() > 1 && p.iter().all(|t| t.1.abs() == c0) {
            for t in p.iter_mut() {
                t.1 /= c0;
            }
            let rest = self.horner(p);
            let k = self.constant(c0);
            return self.mul(k, rest);
        }
        if p.len() == 1 {
            let (m, c) = &p[0];
            let c = *c;
            let mm = self.mono(m);
            let k = self.constant(c);
            return self.mul(k, mm);
        }
        // The variable in most terms.
        let mut count: FxHashMap<u32, usize> = FxHashMap::default();
        for (m, _) in &p {
            for &(v, _) in m.iter() {
                *count.entry(v).or_default() += 1;
            }
        }
        let best = count
            .iter()
            .max_by_key(|(v, n)| (**n, std::cmp::Reverse(**v)))
            .map(|(v, n)| (*v, *n));
        match best {
            Some((v, n)) if n >= 2 => {
                let (mut with, mut without): (NodePoly, NodePoly) = (Vec::new(), Vec::new());
                for (m, c) in p {
                    if m.iter().any(|&(w, _)| w == v) {
                        let d: NodeMonomial = SmallVec::from_slice(&[(v, 1)]);
                        with.push((mono_div(&m, &d), c));
                    } else {
                        without.push((m, c));
                    }
                }
                let q = self.horner(with);
                if without.is_empty() {
                    return self.mul(v, q);
                }
                let r = self.horner(without);
                self.mul_add(v, q, r)
            }
            _ => self.sum_of_terms(p),
        }
    }

    /// Σ cᵢ·mᵢ with shared power products.
    fn sum_of_terms(&mut self, mut p: NodePoly) -> u32 {
        p.sort_by(|a, b| a.0.cmp(&b.0));
        let mut acc: Option<u32> = None;
        for (m, c) in p {
            let mm = self.mono(&m);
            acc = Some(match acc {
                None => {
                    let k = self.constant(c);
                    self.mul(k, mm)
                }
                Some(a) if c == 1.0 => self.add(a, mm),
                Some(a) if c == -1.0 => self.sub(a, mm),
                Some(a) => {
                    let k = self.constant(c);
                    self.mul_add(k, mm, a)
                }
            });
        }
        acc.unwrap_or_else(|| self.constant(0.0))
    }
}

/// The value of a polynomial without runtime variables.
fn constant_of(p: &NodePoly) -> Option<f64> {
    if p.iter().all(|(m, _)| m.is_empty()) {
        Some(p.iter().map(|t| t.1).sum())
    } else {
        None
    }
}

/// Merge repeated nodes of a sorted power product (two atoms folded to the
/// same node).
fn merge_dups(m: NodeMonomial) -> NodeMonomial {
    if m.windows(2).all(|w| w[0].0 != w[1].0) {
        return m;
    }
    let mut out: NodeMonomial = SmallVec::new();
    for (v, e) in m {
        match out.last_mut() {
            Some(l) if l.0 == v => l.1 += e,
            _ => out.push((v, e)),
        }
    }
    out
}

fn mono_gcd(a: &NodeMonomial, b: &NodeMonomial) -> NodeMonomial {
    let mut out = SmallVec::new();
    let (mut i, mut j) = (0, 0);
    while i < a.len() && j < b.len() {
        match a[i].0.cmp(&b[j].0) {
            std::cmp::Ordering::Less => i += 1,
            std::cmp::Ordering::Greater => j += 1,
            std::cmp::Ordering::Equal => {
                out.push((a[i].0, a[i].1.min(b[j].1)));
                i += 1;
                j += 1;
            }
        }
    }
    out
}

/// a / b for b dividing a.
fn mono_div(a: &NodeMonomial, b: &NodeMonomial) -> NodeMonomial {
    let mut out = SmallVec::new();
    for &(v, e) in a.iter() {
        let d = b.iter().find(|t| t.0 == v).map_or(0, |t| t.1);
        if e > d {
            out.push((v, e - d));
        }
    }
    out
}
