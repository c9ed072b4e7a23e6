//! Exact expressions compiled to a flat f64 register program.
//!
//! [`compile`] turns canonical expressions (`num/den` over atoms, see
//! [`crate::expr`]) into a [`Program`]: a straight-line list of register
//! instructions, in topological order, that evaluates all outputs at once
//! without allocating. The compiler
//!
//! * folds constants: π, √n, rational coefficients, parameters bound to
//!   numbers ([`compile_with`]) and every atom whose argument is constant
//!   become constants, multiplied into the coefficients of the terms;
//! * shares common subexpressions: every node is hash-consed (an atom is
//!   evaluated once, `sin u` and `cos u` of one angle by one `sin_cos`, a
//!   power product once for all outputs, an equal numerator or denominator
//!   once);
//! * evaluates each polynomial by a greedy multivariate Horner scheme
//!   (Ceberio & Kreinovich, "Greedy algorithms for optimizing multivariate
//!   Horner schemes", ACM SIGSAM Bull. 38 (2004)): the common monomial
//!   factor of all terms is split off, then the polynomial is written
//!   `v·q + r` in the variable `v` that occurs in most terms, recursively;
//!   the remaining power products are built by multiplying a shared prefix
//!   by one more factor (a trie of monomials);
//! * removes dead code and reuses registers (linear scan over the last
//!   uses, Poletto & Sarkar, TOPLAS 21 (1999)).
//!
//! [`CompiledDynamics`] evaluates M(q, t) (its upper triangle) and f(q, q̇, t)
//! of Lagrange's equations in one program and solves M·q̈ = f by
//! [`solve_spd`] (Cholesky, LU with partial pivoting as fallback; Golub &
//! Van Loan, Matrix Computations, 4.2 and 3.4), as a [`System`] for the
//! integrators.

use crate::expr::atom::{self, Atom};
use crate::expr::Expr;
use crate::mechanics::Lagrange;
use crate::poly::{Poly, Var};
use crate::simulate::System;
use rustc_hash::FxHashMap;
use smallvec::SmallVec;

// ================================================================ program

/// One instruction of a [`Program`]: registers are indices into the
/// register file; `dst` is written after all operands are read.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Instr {
    /// `dst = a + b`.
    Add { dst: u32, a: u32, b: u32 },
    /// `dst = a − b`.
    Sub { dst: u32, a: u32, b: u32 },
    /// `dst = a · b`.
    Mul { dst: u32, a: u32, b: u32 },
    /// `dst = a · b + c` (two roundings, not a fused multiply-add).
    MulAdd { dst: u32, a: u32, b: u32, c: u32 },
    /// `dst = init + Σ a_k·b_k` over the register pairs
    /// `start..start + len` of [`Program::pairs`], summed left to right
    /// (`init == u32::MAX`: no initial value).
    Dot {
        dst: u32,
        init: u32,
        start: u32,
        len: u32,
    },
    /// `dst = a / b`.
    Div { dst: u32, a: u32, b: u32 },
    /// `dst = −a`.
    Neg { dst: u32, a: u32 },
    /// `dst = aⁿ` (n ≥ 2) by repeated squaring and multiplication.
    Powi { dst: u32, a: u32, n: u32 },
    /// `dst = sin a`.
    Sin { dst: u32, a: u32 },
    /// `dst = cos a`.
    Cos { dst: u32, a: u32 },
    /// `(sin, cos) = (sin a, cos a)` by one `f64::sin_cos`.
    SinCos { sin: u32, cos: u32, a: u32 },
    /// `dst = exp a`.
    Exp { dst: u32, a: u32 },
    /// `dst = ln a`.
    Ln { dst: u32, a: u32 },
    /// `dst = √a`.
    Sqrt { dst: u32, a: u32 },
    /// `dst = atan a`.
    Atan { dst: u32, a: u32 },
    /// `dst = asin a`.
    Asin { dst: u32, a: u32 },
    /// `dst = acos a`.
    Acos { dst: u32, a: u32 },
}

/// A compiled straight-line program: constants in registers
/// `0..consts.len()`, the inputs in the next `n_inputs` registers, then
/// temporaries; [`Program::eval`] runs the instructions and copies the
/// output registers out.
#[derive(Clone, Debug)]
pub struct Program {
    consts: Vec<f64>,
    n_inputs: usize,
    n_regs: usize,
    code: Vec<Instr>,
    pairs: Vec<(u32, u32)>,
    outputs: Vec<u32>,
}

impl Program {
    /// The number of input values [`Program::eval`] expects.
    pub fn n_inputs(&self) -> usize {
        self.n_inputs
    }
    /// The number of outputs.
    pub fn n_outputs(&self) -> usize {
        self.outputs.len()
    }
    /// The size of the register file [`Program::eval`] needs.
    pub fn n_registers(&self) -> usize {
        self.n_regs
    }
    /// The instructions, in execution order.
    pub fn instructions(&self) -> &[Instr] {
        &self.code
    }
    /// The register pairs of the [`Instr::Dot`] instructions.
    pub fn pairs(&self) -> &[(u32, u32)] {
        &self.pairs
    }
    /// The folded constants (loaded into the first registers).
    pub fn constants(&self) -> &[f64] {
        &self.consts
    }
    /// A register file of the right size with the constants loaded (no
    /// instruction ever writes a constant's or an input's register, so they
    /// stay loaded: see [`Program::run`]).
    pub fn registers(&self) -> Vec<f64> {
        let mut r = vec![0.0; self.n_regs];
        r[..self.consts.len()].copy_from_slice(&self.consts);
        r
    }
    /// Where the inputs go in the register file, for [`Program::run`]:
    /// input k is register `input_offset() + k`.
    pub fn input_offset(&self) -> usize {
        self.consts.len()
    }
    /// The register holding each output after [`Program::run`].
    pub fn output_registers(&self) -> &[u32] {
        &self.outputs
    }
    /// Floating-point operations per evaluation: `(additions, subtractions
    /// and negations; multiplications, powers counted once; divisions;
    /// function calls)`. A mul-add counts one addition and one
    /// multiplication, a dot product of k pairs k multiplications and k − 1
    /// or k additions, a sin_cos one call.
    pub fn op_counts(&self) -> (usize, usize, usize, usize) {
        let (mut add, mut mul, mut div, mut fun) = (0, 0, 0, 0);
        for i in &self.code {
            match i {
                Instr::Add { .. } | Instr::Sub { .. } | Instr::Neg { .. } => add += 1,
                Instr::Mul { .. } | Instr::Powi { .. } => mul += 1,
                Instr::MulAdd { .. } => {
                    mul += 1;
                    add += 1;
                }
                Instr::Dot { len, init, .. } => {
                    mul += *len as usize;
                    add += *len as usize - usize::from(*init == NONE);
                }
                Instr::Div { .. } => div += 1,
                _ => fun += 1,
            }
        }
        (add, mul, div, fun)
    }

    /// Evaluate every output at `inputs` (in the order given to
    /// [`compile`]), using `regs` as scratch. Allocation-free.
    ///
    /// # Panics
    /// When `inputs.len() != self.n_inputs()`, `regs.len() <
    /// self.n_registers()` or `out.len() != self.n_outputs()`.
    pub fn eval(&self, inputs: &[f64], regs: &mut [f64], out: &mut [f64]) {
        assert_eq!(inputs.len(), self.n_inputs, "wrong number of inputs");
        assert!(regs.len() >= self.n_regs, "register file too small");
        assert_eq!(out.len(), self.outputs.len(), "wrong number of outputs");
        let nc = self.consts.len();
        regs[..nc].copy_from_slice(&self.consts);
        regs[nc..nc + self.n_inputs].copy_from_slice(inputs);
        self.run(regs);
        for (o, &k) in out.iter_mut().zip(&self.outputs) {
            *o = regs[k as usize];
        }
    }

    /// Run the instructions on a register file that already holds the
    /// constants (as [`Program::registers`] returns it) and the inputs (at
    /// [`Program::input_offset`]); the outputs are then in the registers
    /// [`Program::output_registers`] names. The allocation- and copy-free
    /// core of [`Program::eval`], for callers that evaluate in a loop.
    ///
    /// # Panics
    /// When `regs.len() < self.n_registers()`.
    #[inline]
    pub fn run(&self, regs: &mut [f64]) {
        let r = &mut regs[..self.n_regs];
        for ins in &self.code {
            // SAFETY: `Program`s are only built by `Builder::finish`, which
            // gives every operand and destination an index < n_regs, and
            // `r.len() == n_regs` here.
            unsafe { step(r, &self.pairs, *ins) }
        }
    }
}

/// One instruction.
///
/// # Safety
/// Every register index of `ins` (and of its `pairs`) is `< r.len()`, and a
/// dot product's pairs are within `pairs`.
#[inline(always)]
unsafe fn step(r: &mut [f64], pairs: &[(u32, u32)], ins: Instr) {
    macro_rules! g {
        ($i:expr) => {
            *r.get_unchecked($i as usize)
        };
    }
    macro_rules! s {
        ($i:expr, $v:expr) => {{
            let v = $v;
            *r.get_unchecked_mut($i as usize) = v;
        }};
    }
    match ins {
        Instr::Add { dst, a, b } => s!(dst, g!(a) + g!(b)),
        Instr::Sub { dst, a, b } => s!(dst, g!(a) - g!(b)),
        Instr::Mul { dst, a, b } => s!(dst, g!(a) * g!(b)),
        Instr::MulAdd { dst, a, b, c } => s!(dst, g!(a) * g!(b) + g!(c)),
        Instr::Dot {
            dst,
            init,
            start,
            len,
        } => {
            let mut acc = if init == NONE { 0.0 } else { g!(init) };
            let ps = pairs.get_unchecked(start as usize..(start + len) as usize);
            for &(a, b) in ps {
                acc += g!(a) * g!(b);
            }
            s!(dst, acc)
        }
        Instr::Div { dst, a, b } => s!(dst, g!(a) / g!(b)),
        Instr::Neg { dst, a } => s!(dst, -g!(a)),
        Instr::Powi { dst, a, n } => s!(dst, powi(g!(a), n)),
        Instr::Sin { dst, a } => s!(dst, g!(a).sin()),
        Instr::Cos { dst, a } => s!(dst, g!(a).cos()),
        Instr::SinCos { sin, cos, a } => {
            let (sv, cv) = g!(a).sin_cos();
            s!(sin, sv);
            s!(cos, cv);
        }
        Instr::Exp { dst, a } => s!(dst, g!(a).exp()),
        Instr::Ln { dst, a } => s!(dst, g!(a).ln()),
        Instr::Sqrt { dst, a } => s!(dst, g!(a).sqrt()),
        Instr::Atan { dst, a } => s!(dst, g!(a).atan()),
        Instr::Asin { dst, a } => s!(dst, g!(a).asin()),
        Instr::Acos { dst, a } => s!(dst, g!(a).acos()),
    }
}

/// xⁿ by binary powering (exact for small n as repeated multiplication).
#[inline]
fn powi(x: f64, n: u32) -> f64 {
    match n {
        0 => 1.0,
        1 => x,
        2 => x * x,
        3 => x * x * x,
        _ => {
            let (mut acc, mut base, mut e) = (1.0, x, n);
            while e > 0 {
                if e & 1 == 1 {
                    acc *= base;
                }
                base *= base;
                e >>= 1;
            }
            acc
        }
    }
}

// ================================================================ compiler

/// Compile `outputs` as functions of the atoms `inputs` (given in this
/// order to [`Program::eval`]). Every parameter, coordinate or time the
/// outputs mention must be an input.
pub fn compile(outputs: &[Expr], inputs: &[Var]) -> Result<Program, String> {
    compile_with(outputs, inputs, &FxHashMap::default())
}

/// [`compile`] with some atoms (usually parameters) bound to numbers at
/// compile time: they are folded into the constants (a bound atom that is
/// also an input takes its bound value; its input slot is then ignored).
pub fn compile_with(
    outputs: &[Expr],
    inputs: &[Var],
    params: &FxHashMap<Var, f64>,
) -> Result<Program, String> {
    let mut b = Builder::new(inputs, params);
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

/// A node of the expression DAG; operands are node ids.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
enum Node {
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
    fn operands(&self) -> SmallVec<[u32; 3]> {
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
type NMono = SmallVec<[(u32, u32); 4]>;
/// A polynomial over nodes with f64 coefficients (after constant folding).
type FPoly = Vec<(NMono, f64)>;

struct Builder<'a> {
    nodes: Vec<Node>,
    index: FxHashMap<Node, u32>,
    inputs: FxHashMap<Var, u32>,
    params: &'a FxHashMap<Var, f64>,
    atoms: FxHashMap<Var, u32>,
    polys: FxHashMap<Poly, u32>,
    monos: FxHashMap<NMono, u32>,
}

impl<'a> Builder<'a> {
    fn new(inputs: &[Var], params: &'a FxHashMap<Var, f64>) -> Builder<'a> {
        let mut map = FxHashMap::default();
        for (i, &v) in inputs.iter().enumerate() {
            map.entry(v).or_insert(i as u32);
        }
        Builder {
            nodes: Vec::new(),
            index: FxHashMap::default(),
            inputs: map,
            params,
            atoms: FxHashMap::default(),
            polys: FxHashMap::default(),
            monos: FxHashMap::default(),
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
        self.nodes.push(n);
        self.index.insert(n, id);
        id
    }

    fn konst(&mut self, x: f64) -> u32 {
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
            (Some(x), Some(y)) => self.konst(x + y),
            (Some(0.0), _) => b,
            (_, Some(0.0)) => a,
            _ => self.node(Node::Add(a.min(b), a.max(b))),
        }
    }

    fn sub(&mut self, a: u32, b: u32) -> u32 {
        match (self.as_const(a), self.as_const(b)) {
            (Some(x), Some(y)) => self.konst(x - y),
            (Some(0.0), _) => self.neg(b),
            (_, Some(0.0)) => a,
            _ => self.node(Node::Sub(a, b)),
        }
    }

    fn neg(&mut self, a: u32) -> u32 {
        match self.nodes[a as usize] {
            Node::Const(b) => self.konst(-f64::from_bits(b)),
            Node::Neg(x) => x,
            _ => self.node(Node::Neg(a)),
        }
    }

    fn mul(&mut self, a: u32, b: u32) -> u32 {
        match (self.as_const(a), self.as_const(b)) {
            (Some(x), Some(y)) => self.konst(x * y),
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
            (Some(x), Some(y)) => self.konst(x / y),
            (_, Some(1.0)) => a,
            (_, Some(y)) if y.is_finite() && y != 0.0 => {
                let r = self.konst(1.0 / y);
                self.mul(a, r)
            }
            _ => self.node(Node::Div(a, b)),
        }
    }

    fn powi(&mut self, a: u32, n: u32) -> u32 {
        match n {
            0 => self.konst(1.0),
            1 => a,
            _ => match self.as_const(a) {
                Some(x) => self.konst(powi(x, n)),
                None => self.node(Node::Powi(a, n)),
            },
        }
    }

    /// A function of one argument, folded when the argument is constant.
    fn func(&mut self, a: u32, make: fn(u32) -> Node, f: fn(f64) -> f64) -> u32 {
        match self.as_const(a) {
            Some(x) => self.konst(f(x)),
            None => self.node(make(a)),
        }
    }

    // ------------------------------------------------------------ lowering

    fn expr(&mut self, e: &Expr) -> Result<u32, String> {
        let den = self.fpoly(e.den())?;
        if let Some(c) = constant_of(&den) {
            // A constant denominator folds into the numerator's coefficients.
            if e.den().is_one() {
                return self.poly(e.num());
            }
            let mut num = self.fpoly(e.num())?;
            for t in num.iter_mut() {
                t.1 /= c;
            }
            return Ok(self.horner(num));
        }
        let n = self.poly(e.num())?;
        let d = self.poly(e.den())?;
        Ok(self.div(n, d))
    }

    /// A polynomial, memoized by its exact form.
    fn poly(&mut self, p: &Poly) -> Result<u32, String> {
        if let Some(&id) = self.polys.get(p) {
            return Ok(id);
        }
        let f = self.fpoly(p)?;
        let id = self.horner(f);
        self.polys.insert(p.clone(), id);
        Ok(id)
    }

    /// The terms of `p` over runtime nodes, constant atoms folded into the
    /// coefficients and equal power products merged.
    fn fpoly(&mut self, p: &Poly) -> Result<FPoly, String> {
        let mut merged: FxHashMap<NMono, f64> = FxHashMap::default();
        let mut order: Vec<NMono> = Vec::new();
        for (m, c) in p.terms() {
            let mut coef = c.to_f64();
            let mut mono: NMono = SmallVec::new();
            for &(v, e) in m.0.iter() {
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
    fn atom(&mut self, v: Var) -> Result<u32, String> {
        if let Some(&id) = self.atoms.get(&v) {
            return Ok(id);
        }
        let a = atom::atom(v);
        let id = if let Some(&x) = self.params.get(&v) {
            self.konst(x)
        } else if let Some(&slot) = self.inputs.get(&v) {
            slot
        } else {
            match &a {
                Atom::Param(name) | Atom::Unknown(name) => {
                    return Err(format!(
                        "the parameter {name} has no value and is not an input"
                    ))
                }
                Atom::Coord(name, k) => {
                    return Err(format!(
                        "the coordinate {name}{} is not an input",
                        "'".repeat(*k as usize)
                    ))
                }
                Atom::Time => return Err("the time t is not an input".to_string()),
                Atom::Pi => self.konst(std::f64::consts::PI),
                Atom::Root(n) => {
                    let x: f64 = n.parse().map_err(|_| format!("bad radical √{n}"))?;
                    self.konst(x.sqrt())
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
                Atom::Shown(_) => return Err("a print-only atom cannot be evaluated".into()),
            }
        };
        self.atoms.insert(v, id);
        Ok(id)
    }

    /// A power product, built as (shared prefix) × (last factor).
    fn mono(&mut self, m: &[(u32, u32)]) -> u32 {
        match m {
            [] => self.konst(1.0),
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
    fn horner(&mut self, mut p: FPoly) -> u32 {
        if p.is_empty() {
            return self.konst(0.0);
        }
        if let Some(c) = constant_of(&p) {
            return self.konst(c);
        }
        // The common power product of all terms.
        let mut g: NMono = p[0].0.clone();
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
            let k = self.konst(c0);
            return self.mul(k, rest);
        }
        if p.len() == 1 {
            let (m, c) = &p[0];
            let c = *c;
            let mm = self.mono(m);
            let k = self.konst(c);
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
                let (mut with, mut without): (FPoly, FPoly) = (Vec::new(), Vec::new());
                for (m, c) in p {
                    if m.iter().any(|&(w, _)| w == v) {
                        let d: NMono = SmallVec::from_slice(&[(v, 1)]);
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
    fn sum_of_terms(&mut self, mut p: FPoly) -> u32 {
        p.sort_by(|a, b| a.0.cmp(&b.0));
        let mut acc: Option<u32> = None;
        for (m, c) in p {
            let mm = self.mono(&m);
            acc = Some(match acc {
                None => {
                    let k = self.konst(c);
                    self.mul(k, mm)
                }
                Some(a) if c == 1.0 => self.add(a, mm),
                Some(a) if c == -1.0 => self.sub(a, mm),
                Some(a) => {
                    let k = self.konst(c);
                    self.mul_add(k, mm, a)
                }
            });
        }
        acc.unwrap_or_else(|| self.konst(0.0))
    }

    // ------------------------------------------------------------ emission

    /// Dead code removal, sin/cos pairing, fusion of multiply-add chains
    /// into dot products, register allocation.
    fn finish(self, outs: &[u32]) -> Program {
        let n_inputs = self
            .nodes
            .iter()
            .filter(|n| matches!(n, Node::Input(_)))
            .count();
        let nn = self.nodes.len();
        let fixed = |id: u32| matches!(self.nodes[id as usize], Node::Const(_) | Node::Input(_));
        // Liveness (nodes are in topological order: operands first).
        let mut live = vec![false; nn];
        for &o in outs {
            live[o as usize] = true;
        }
        for id in (0..nn).rev() {
            if live[id] {
                for a in self.nodes[id].operands() {
                    live[a as usize] = true;
                }
            }
        }
        // sin and cos of one argument: one sin_cos, at the first of the two.
        let mut partner: FxHashMap<u32, u32> = FxHashMap::default();
        for id in 0..nn {
            if let (true, Node::Sin(a)) = (live[id], self.nodes[id]) {
                if let Some(&c) = self.index.get(&Node::Cos(a)) {
                    if live[c as usize] {
                        partner.insert(id as u32, c);
                        partner.insert(c, id as u32);
                    }
                }
            }
        }
        // Dot products: a multiply-add (or a sum of products) whose
        // accumulated operand is a product or a dot product used nowhere
        // else absorbs it, so a chain of k multiply-adds is one instruction
        // with a tight loop (summed in the same order).
        let mut uses = vec![0u32; nn];
        for (id, node) in self.nodes.iter().enumerate() {
            if live[id] {
                for a in node.operands() {
                    uses[a as usize] += 1;
                }
            }
        }
        for &o in outs {
            uses[o as usize] += 1;
        }
        let mut absorbed = vec![false; nn];
        let mut dots: FxHashMap<u32, Dot> = FxHashMap::default();
        for (id, _) in live.iter().enumerate().filter(|(_, &l)| l) {
            let single = |c: u32| uses[c as usize] == 1 && !fixed(c);
            let as_dot = |c: u32, dots: &FxHashMap<u32, Dot>| -> Option<Dot> {
                if !single(c) {
                    return None;
                }
                match self.nodes[c as usize] {
                    Node::Mul(x, y) => Some(Dot {
                        init: None,
                        terms: vec![(x, y)],
                    }),
                    Node::MulAdd(..) | Node::Add(..) => dots.get(&c).cloned(),
                    _ => None,
                }
            };
            let dot = match self.nodes[id] {
                Node::MulAdd(x, y, c) => {
                    let mut d = match as_dot(c, &dots) {
                        Some(d) => {
                            absorbed[c as usize] = true;
                            dots.remove(&c);
                            d
                        }
                        None => Dot {
                            init: Some(c),
                            terms: Vec::new(),
                        },
                    };
                    d.terms.push((x, y));
                    d
                }
                Node::Add(x, y) => match (as_dot(x, &dots), as_dot(y, &dots)) {
                    (Some(mut dx), Some(dy)) if dx.init.is_none() || dy.init.is_none() => {
                        for c in [x, y] {
                            absorbed[c as usize] = true;
                            dots.remove(&c);
                        }
                        dx.init = dx.init.or(dy.init);
                        dx.terms.extend(dy.terms);
                        dx
                    }
                    (Some(mut d), None) if d.init.is_none() => {
                        absorbed[x as usize] = true;
                        dots.remove(&x);
                        d.init = Some(y);
                        d
                    }
                    (None, Some(mut d)) if d.init.is_none() => {
                        absorbed[y as usize] = true;
                        dots.remove(&y);
                        d.init = Some(x);
                        d
                    }
                    _ => continue,
                },
                _ => continue,
            };
            dots.insert(id as u32, dot);
        }
        // The operands an emitted node reads.
        let operands = |id: u32| -> SmallVec<[u32; 3]> {
            match dots.get(&id) {
                Some(d) => d
                    .init
                    .iter()
                    .copied()
                    .chain(d.terms.iter().flat_map(|&(a, b)| [a, b]))
                    .collect(),
                None => self.nodes[id as usize].operands(),
            }
        };
        let emitted = |id: usize| live[id] && !absorbed[id];
        // Constants and inputs get fixed registers.
        let mut reg = vec![u32::MAX; nn];
        let mut consts = Vec::new();
        for id in 0..nn {
            if let (true, Node::Const(b)) = (live[id], self.nodes[id]) {
                reg[id] = consts.len() as u32;
                consts.push(f64::from_bits(b));
            }
        }
        let nc = consts.len() as u32;
        for (r, node) in reg.iter_mut().zip(&self.nodes) {
            if let Node::Input(i) = *node {
                *r = nc + i;
            }
        }
        // Last uses, in node order (an instruction's position is its node's,
        // a sin_cos's the earlier of the pair).
        let pos = |id: u32| -> u32 {
            match partner.get(&id) {
                Some(&p) => id.min(p),
                None => id,
            }
        };
        let mut last = vec![0u32; nn];
        for id in 0..nn {
            if emitted(id) {
                for a in operands(id as u32) {
                    last[a as usize] = last[a as usize].max(pos(id as u32));
                }
            }
        }
        for &o in outs {
            last[o as usize] = u32::MAX;
        }
        // Nodes whose last use is at position p, to free there.
        let mut dying: Vec<Vec<u32>> = vec![Vec::new(); nn];
        for id in 0..nn {
            if emitted(id) && !fixed(id as u32) && (last[id] as usize) < nn {
                dying[last[id] as usize].push(id as u32);
            }
        }
        let mut free: Vec<u32> = Vec::new();
        let mut next = nc + n_inputs as u32;
        let mut code = Vec::new();
        let mut pairs: Vec<(u32, u32)> = Vec::new();
        let mut alloc = |free: &mut Vec<u32>| -> u32 {
            free.pop().unwrap_or_else(|| {
                next += 1;
                next - 1
            })
        };
        for id in 0..nn {
            if !emitted(id) || fixed(id as u32) || reg[id] != u32::MAX {
                continue; // dead, absorbed, preloaded, or the second of a sin_cos
            }
            let node = self.nodes[id];
            let ops: SmallVec<[u32; 3]> =
                node.operands().iter().map(|&a| reg[a as usize]).collect();
            let dot = dots.get(&(id as u32)).map(|d| {
                let start = pairs.len() as u32;
                pairs.extend(
                    d.terms
                        .iter()
                        .map(|&(a, b)| (reg[a as usize], reg[b as usize])),
                );
                (
                    d.init.map_or(NONE, |i| reg[i as usize]),
                    start,
                    d.terms.len() as u32,
                )
            });
            // Operands dying here may be reused for the result.
            for &d in &dying[id] {
                free.push(reg[d as usize]);
            }
            let r = |i: usize| ops[i];
            if let Some(&p) = partner.get(&(id as u32)) {
                let s_id = if matches!(node, Node::Sin(_)) {
                    id as u32
                } else {
                    p
                };
                let c_id = if s_id == id as u32 { p } else { id as u32 };
                let rs = alloc(&mut free);
                let rc = alloc(&mut free);
                reg[s_id as usize] = rs;
                reg[c_id as usize] = rc;
                code.push(Instr::SinCos {
                    sin: rs,
                    cos: rc,
                    a: r(0),
                });
                continue;
            }
            let dst = alloc(&mut free);
            reg[id] = dst;
            if let Some((init, start, len)) = dot {
                let one = pairs[start as usize];
                code.push(match (len, init) {
                    (1, NONE) => Instr::Mul {
                        dst,
                        a: one.0,
                        b: one.1,
                    },
                    (1, c) => {
                        pairs.pop();
                        Instr::MulAdd {
                            dst,
                            a: one.0,
                            b: one.1,
                            c,
                        }
                    }
                    _ => Instr::Dot {
                        dst,
                        init,
                        start,
                        len,
                    },
                });
                continue;
            }
            code.push(match node {
                Node::Add(..) => Instr::Add {
                    dst,
                    a: r(0),
                    b: r(1),
                },
                Node::Sub(..) => Instr::Sub {
                    dst,
                    a: r(0),
                    b: r(1),
                },
                Node::Mul(..) => Instr::Mul {
                    dst,
                    a: r(0),
                    b: r(1),
                },
                Node::MulAdd(..) => Instr::MulAdd {
                    dst,
                    a: r(0),
                    b: r(1),
                    c: r(2),
                },
                Node::Div(..) => Instr::Div {
                    dst,
                    a: r(0),
                    b: r(1),
                },
                Node::Neg(_) => Instr::Neg { dst, a: r(0) },
                Node::Powi(_, n) => Instr::Powi { dst, a: r(0), n },
                Node::Sin(_) => Instr::Sin { dst, a: r(0) },
                Node::Cos(_) => Instr::Cos { dst, a: r(0) },
                Node::Exp(_) => Instr::Exp { dst, a: r(0) },
                Node::Ln(_) => Instr::Ln { dst, a: r(0) },
                Node::Sqrt(_) => Instr::Sqrt { dst, a: r(0) },
                Node::Atan(_) => Instr::Atan { dst, a: r(0) },
                Node::Asin(_) => Instr::Asin { dst, a: r(0) },
                Node::Acos(_) => Instr::Acos { dst, a: r(0) },
                Node::Const(_) | Node::Input(_) => continue,
            });
        }
        let outputs = outs.iter().map(|&o| reg[o as usize]).collect();
        Program {
            consts,
            n_inputs,
            n_regs: next as usize,
            code,
            pairs,
            outputs,
        }
    }
}

/// "No register": a dot product without an initial value.
const NONE: u32 = u32::MAX;

/// A dot product `init + Σ a·b` over node ids, before register allocation.
#[derive(Clone, Debug)]
struct Dot {
    init: Option<u32>,
    terms: Vec<(u32, u32)>,
}

/// The value of a polynomial without runtime variables.
fn constant_of(p: &FPoly) -> Option<f64> {
    if p.iter().all(|(m, _)| m.is_empty()) {
        Some(p.iter().map(|t| t.1).sum())
    } else {
        None
    }
}

/// Merge repeated nodes of a sorted power product (two atoms folded to the
/// same node).
fn merge_dups(m: NMono) -> NMono {
    if m.windows(2).all(|w| w[0].0 != w[1].0) {
        return m;
    }
    let mut out: NMono = SmallVec::new();
    for (v, e) in m {
        match out.last_mut() {
            Some(l) if l.0 == v => l.1 += e,
            _ => out.push((v, e)),
        }
    }
    out
}

fn mono_gcd(a: &NMono, b: &NMono) -> NMono {
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
fn mono_div(a: &NMono, b: &NMono) -> NMono {
    let mut out = SmallVec::new();
    for &(v, e) in a.iter() {
        let d = b.iter().find(|t| t.0 == v).map_or(0, |t| t.1);
        if e > d {
            out.push((v, e - d));
        }
    }
    out
}

// ================================================================ linear algebra

/// Solve M·x = f in place for a symmetric M (n×n, row-major, both
/// triangles filled): Cholesky M = L·Lᵀ (Golub & Van Loan, Matrix
/// Computations, 4.2.5), and when M is not numerically positive definite
/// Gaussian elimination with partial pivoting (3.4) on the restored M.
/// The solution replaces `f`; `m` is overwritten. Allocation-free.
/// An error when M is numerically singular (a zero pivot).
pub fn solve_spd(m: &mut [f64], f: &mut [f64], n: usize) -> Result<(), String> {
    if m.len() < n * n || f.len() < n {
        return Err(format!(
            "solve_spd: a {n}×{n} system needs {} and {n} values",
            n * n
        ));
    }
    match cholesky(m, n) {
        Ok(()) => {
            cholesky_solve(m, f, n);
            Ok(())
        }
        Err(j) => {
            restore(m, n, j);
            gauss_solve(m, f, n)
        }
    }
}

/// In-place Cholesky: L into the lower triangle and the diagonal, the
/// strict upper triangle untouched. Err(j) when the pivot of column j is
/// not positive (columns < j are then factored, column j untouched).
fn cholesky(a: &mut [f64], n: usize) -> Result<(), usize> {
    let dot = |x: &[f64], y: &[f64]| -> f64 { x.iter().zip(y).map(|(p, q)| p * q).sum() };
    for j in 0..n {
        let (done, rest) = a[..n * n].split_at_mut((j + 1) * n);
        let row_j = &mut done[j * n..];
        let d = row_j[j] - dot(&row_j[..j], &row_j[..j]);
        if d.is_nan() || d <= 0.0 {
            return Err(j);
        }
        let d = d.sqrt();
        row_j[j] = d;
        let (lj, inv) = (&row_j[..j], 1.0 / d);
        for row_i in rest.chunks_exact_mut(n) {
            row_i[j] = (row_i[j] - dot(&row_i[..j], lj)) * inv;
        }
    }
    Ok(())
}

fn cholesky_solve(l: &[f64], b: &mut [f64], n: usize) {
    for i in 0..n {
        let row = &l[i * n..i * n + i];
        let s: f64 = row.iter().zip(&b[..i]).map(|(p, q)| p * q).sum();
        b[i] = (b[i] - s) / l[i * n + i];
    }
    for i in (0..n).rev() {
        let mut s = b[i];
        for k in i + 1..n {
            s -= l[k * n + i] * b[k];
        }
        b[i] = s / l[i * n + i];
    }
}

/// Undo a Cholesky factorization that failed at column `j`: the diagonal
/// entries k < j from the rows of L (M_kk = Σ L_ki²), the lower triangle
/// from the untouched upper one.
fn restore(a: &mut [f64], n: usize, j: usize) {
    for k in 0..j.min(n) {
        let s: f64 = (0..=k).map(|i| a[k * n + i] * a[k * n + i]).sum();
        a[k * n + k] = s;
    }
    for i in 0..n {
        for k in 0..i {
            a[i * n + k] = a[k * n + i];
        }
    }
}

/// Gaussian elimination with partial pivoting on (a | b), in place.
fn gauss_solve(a: &mut [f64], b: &mut [f64], n: usize) -> Result<(), String> {
    for j in 0..n {
        let p = (j..n)
            .max_by(|&x, &y| a[x * n + j].abs().total_cmp(&a[y * n + j].abs()))
            .unwrap_or(j);
        let piv = a[p * n + j];
        if piv == 0.0 || !piv.is_finite() {
            return Err(format!("the matrix is singular (column {j})"));
        }
        if p != j {
            for k in 0..n {
                a.swap(j * n + k, p * n + k);
            }
            b.swap(j, p);
        }
        for i in j + 1..n {
            let f = a[i * n + j] / piv;
            if f != 0.0 {
                for k in j + 1..n {
                    a[i * n + k] -= f * a[j * n + k];
                }
                b[i] -= f * b[j];
            }
        }
    }
    for i in (0..n).rev() {
        let mut s = b[i];
        for k in i + 1..n {
            s -= a[i * n + k] * b[k];
        }
        b[i] = s / a[i * n + i];
    }
    Ok(())
}

// ================================================================ dynamics

/// How [`CompiledDynamics`] gets q̈.
#[derive(Clone, Debug)]
enum Mode {
    /// Outputs: M's upper triangle (row by row) then f; solve each time.
    MassMatrix,
    /// Outputs: f; M was constant, factored once and its inverse kept
    /// (row-major), so q̈ = M⁻¹·f is one product with no division.
    ConstantMass(Vec<f64>),
    /// Outputs: the exact accelerations.
    Accelerations,
}

/// How a [`CompiledDynamics`] evaluates q̈.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Evaluator {
    /// M (upper triangle) and f compiled, M·q̈ = f solved at each call
    /// (Cholesky, Golub & Van Loan 4.2.5): about n³/3 + 2n² flops, n
    /// square roots and n(n − 1)/2 + 2n divisions.
    MassMatrix,
    /// f compiled; the constant M factored once at compile time and M⁻¹
    /// kept, so each call is one product (n² multiplications).
    ConstantMass,
    /// The exact accelerations q̈ = M⁻¹·f (`Lagrange::accelerations`)
    /// compiled: no solve.
    Accelerations,
}

impl Evaluator {
    /// The name in `--stats` and JSON: `mass_matrix`, `constant_mass`,
    /// `accelerations`.
    pub fn name(self) -> &'static str {
        match self {
            Evaluator::MassMatrix => "mass_matrix",
            Evaluator::ConstantMass => "constant_mass",
            Evaluator::Accelerations => "accelerations",
        }
    }
}

/// The largest number of coordinates for which [`CompiledDynamics::best`]
/// derives the exact accelerations to compare: their expressions (Cramer's
/// rule, exact) grow quickly with n — for the pendulum chain ≈ 0.1 ms at
/// n = 2 and ≈ 5 ms at n = 3 to derive, and at n = 3 the compiled program
/// is already ≈ 1.3 times as slow as M, f and the solve.
pub const BEST_MAX_N: usize = 3;

/// Weights of [`CompiledDynamics::estimated_cost`], in additions: a
/// division and a function call (sin, cos, sin_cos, exp, …) take several
/// times the latency of an addition or a multiplication.
pub const DIVISION_COST: f64 = 4.0;
/// See [`DIVISION_COST`].
pub const CALL_COST: f64 = 20.0;

/// What [`CompiledDynamics::best`] chose, and why.
#[derive(Clone, Debug, PartialEq)]
pub struct Choice {
    /// The evaluator kept.
    pub evaluator: Evaluator,
    /// The estimated cost per right-hand side of M and f with their solve
    /// ([`CompiledDynamics::estimated_cost`]).
    pub mass_cost: f64,
    /// The estimated cost of the compiled exact accelerations; `None` when
    /// they were not derived (n > [`BEST_MAX_N`], or no exact solution).
    pub accelerations_cost: Option<f64>,
    /// Why, in a few words for `--stats` (the estimated costs compared, or
    /// why the exact accelerations were not derived).
    pub reason: String,
}

/// Lagrange's equations M(q, t)·q̈ = f(q, q̇, t) compiled for simulation:
/// the state is y = (q, q̇) and y' = (q̇, M⁻¹·f). The program's inputs are
/// `[t, q₁ … qₙ, q̇₁ … q̇ₙ]`; every parameter is bound at compile time.
#[derive(Clone, Debug)]
pub struct CompiledDynamics {
    n: usize,
    program: Program,
    mode: Mode,
    /// The register file, constants loaded (see [`Program::run`]).
    regs: Vec<f64>,
    m: Vec<f64>,
    f: Vec<f64>,
}

/// The input atoms `[t, q…, q̇…]` of a [`CompiledDynamics`] program.
pub fn state_inputs(coordinates: &[String]) -> Vec<Var> {
    let mut v = vec![atom::time()];
    v.extend(coordinates.iter().map(|c| atom::coord(c, 0)));
    v.extend(coordinates.iter().map(|c| atom::coord(c, 1)));
    v
}

impl CompiledDynamics {
    /// Compile M and f of `lagrange` with the parameter values `params`.
    pub fn new(lagrange: &Lagrange, params: &FxHashMap<Var, f64>) -> Result<Self, String> {
        Self::from_parts(
            &lagrange.coordinates,
            &lagrange.mass_matrix,
            &lagrange.forcing,
            params,
        )
    }

    /// Compile a mass matrix (symmetric; its upper triangle is read) and a
    /// forcing vector over `coordinates`. When no entry of M depends on the
    /// coordinates, their velocities or t, M is evaluated and factored once.
    pub fn from_parts(
        coordinates: &[String],
        mass: &[Vec<Expr>],
        forcing: &[Expr],
        params: &FxHashMap<Var, f64>,
    ) -> Result<Self, String> {
        let n = coordinates.len();
        if mass.len() != n || mass.iter().any(|r| r.len() != n) || forcing.len() != n {
            return Err(format!(
                "the mass matrix must be {n}×{n} and the forcing of length {n}"
            ));
        }
        let inputs = state_inputs(coordinates);
        let upper: Vec<Expr> = (0..n)
            .flat_map(|i| (i..n).map(move |j| (i, j)))
            .map(|(i, j)| mass[i][j].clone())
            .collect();
        let constant = upper
            .iter()
            .all(|e| inputs.iter().all(|&v| !e.depends_on(v)));
        if constant {
            let pm = compile_with(&upper, &inputs, params)?;
            let mut vals = vec![0.0; upper.len()];
            pm.eval(&vec![0.0; inputs.len()], &mut pm.registers(), &mut vals);
            let mut m = vec![0.0; n * n];
            // M⁻¹ column by column, once, at construction (Cholesky, else
            // Gaussian elimination when M is not numerically positive
            // definite): each step is then one product and no division.
            let mut inverse = vec![0.0; n * n];
            let mut col = vec![0.0; n];
            for j in 0..n {
                fill_symmetric(&vals, &mut m, n);
                col.fill(0.0);
                col[j] = 1.0;
                solve_spd(&mut m, &mut col, n)
                    .map_err(|e| format!("the constant mass matrix: {e}"))?;
                for i in 0..n {
                    inverse[i * n + j] = col[i];
                }
            }
            let program = compile_with(forcing, &inputs, params)?;
            return Ok(Self::with(n, program, Mode::ConstantMass(inverse)));
        }
        let mut outputs = upper;
        outputs.extend(forcing.iter().cloned());
        let program = compile_with(&outputs, &inputs, params)?;
        Ok(Self::with(n, program, Mode::MassMatrix))
    }

    /// Compile the exact accelerations q̈ = M⁻¹·f of `lagrange` instead
    /// (cheaper for small systems, whose exact inverse is small).
    pub fn from_accelerations(
        lagrange: &Lagrange,
        params: &FxHashMap<Var, f64>,
    ) -> Result<Self, String> {
        let acc = lagrange.accelerations().map_err(|d| d.message)?;
        let exprs: Vec<Expr> = acc.into_iter().map(|(_, e)| e).collect();
        let n = lagrange.coordinates.len();
        let program = compile_with(&exprs, &state_inputs(&lagrange.coordinates), params)?;
        Ok(Self::with(n, program, Mode::Accelerations))
    }

    /// The cheaper evaluator of q̈ for `lagrange`: M and f with their solve
    /// ([`CompiledDynamics::new`]) and, for n ≤ [`BEST_MAX_N`] coordinates,
    /// the exact accelerations ([`CompiledDynamics::from_accelerations`]);
    /// the one with the smaller [`CompiledDynamics::estimated_cost`] is
    /// kept, the exact accelerations on a tie. For n > [`BEST_MAX_N`], or
    /// when the exact accelerations cannot be derived, M and f are used
    /// without deriving anything more. An error only when M and f do not
    /// compile.
    pub fn best(
        lagrange: &Lagrange,
        params: &FxHashMap<Var, f64>,
    ) -> Result<(Self, Choice), String> {
        let via_m = Self::new(lagrange, params)?;
        let mass_cost = via_m.estimated_cost();
        let n = via_m.n;
        let what = |d: &Self| match d.evaluator() {
            Evaluator::ConstantMass => "f with the constant M inverted once",
            _ => "M and f with a Cholesky solve",
        };
        if n > BEST_MAX_N {
            let reason = format!(
                "{n} coordinates (more than {BEST_MAX_N}): the exact accelerations are not derived"
            );
            let evaluator = via_m.evaluator();
            return Ok((
                via_m,
                Choice {
                    evaluator,
                    mass_cost,
                    accelerations_cost: None,
                    reason,
                },
            ));
        }
        let via_acc = match Self::from_accelerations(lagrange, params) {
            Ok(d) => d,
            Err(e) => {
                let reason = format!("no exact accelerations: {e}");
                let evaluator = via_m.evaluator();
                return Ok((
                    via_m,
                    Choice {
                        evaluator,
                        mass_cost,
                        accelerations_cost: None,
                        reason,
                    },
                ));
            }
        };
        let acc_cost = via_acc.estimated_cost();
        let (kept, reason) = if acc_cost <= mass_cost {
            let reason = format!(
                "≈ {acc_cost:.0} flops per RHS against ≈ {mass_cost:.0} for {}",
                what(&via_m)
            );
            (via_acc, reason)
        } else {
            let reason = format!(
                "≈ {mass_cost:.0} flops per RHS against ≈ {acc_cost:.0} for the exact accelerations"
            );
            (via_m, reason)
        };
        let evaluator = kept.evaluator();
        Ok((
            kept,
            Choice {
                evaluator,
                mass_cost,
                accelerations_cost: Some(acc_cost),
                reason,
            },
        ))
    }

    /// The estimated cost of one right-hand side, in flops: the program's
    /// additions and multiplications ([`Program::op_counts`]), divisions
    /// weighted by [`DIVISION_COST`] and function calls by [`CALL_COST`],
    /// plus the solve. For a varying M: n³/3 + 2n² additions and
    /// multiplications (Cholesky and the two triangular solves),
    /// n(n − 1)/2 + 2n divisions and n square roots (weighted as divisions: they lie
    /// on the solve's critical path), and n² + n copies (M filled from its
    /// upper triangle, f). For a constant M: the product with the kept M⁻¹,
    /// n² multiplications and n(n − 1) additions. Nothing for the exact
    /// accelerations.
    pub fn estimated_cost(&self) -> f64 {
        let (add, mul, div, call) = self.program.op_counts();
        let n = self.n as f64;
        let solve = match self.mode {
            Mode::MassMatrix => {
                n * n * n / 3.0
                    + 2.0 * n * n
                    + DIVISION_COST * (n * (n - 1.0) / 2.0 + 3.0 * n)
                    + n * n
                    + n
            }
            Mode::ConstantMass(_) => 2.0 * n * n - n,
            Mode::Accelerations => 0.0,
        };
        (add + mul) as f64 + DIVISION_COST * div as f64 + CALL_COST * call as f64 + solve
    }

    /// How q̈ is evaluated.
    pub fn evaluator(&self) -> Evaluator {
        match self.mode {
            Mode::MassMatrix => Evaluator::MassMatrix,
            Mode::ConstantMass(_) => Evaluator::ConstantMass,
            Mode::Accelerations => Evaluator::Accelerations,
        }
    }

    fn with(n: usize, program: Program, mode: Mode) -> Self {
        CompiledDynamics {
            n,
            regs: program.registers(),
            m: vec![0.0; n * n],
            f: vec![0.0; n],
            program,
            mode,
        }
    }

    /// The number of coordinates.
    pub fn n(&self) -> usize {
        self.n
    }

    /// The compiled program (inputs `[t, q…, q̇…]`).
    pub fn program(&self) -> &Program {
        &self.program
    }

    /// Whether M was found constant and factored once.
    pub fn constant_mass(&self) -> bool {
        matches!(self.mode, Mode::ConstantMass(_))
    }

    /// Evaluate M (full, row-major, n×n) and f at (t, q, q̇) — only for a
    /// program compiled from M and f (else an error).
    pub fn mass_and_forcing(
        &mut self,
        t: f64,
        q: &[f64],
        qd: &[f64],
        m: &mut [f64],
        f: &mut [f64],
    ) -> Result<(), String> {
        let n = self.n;
        if q.len() != n || qd.len() != n || m.len() != n * n || f.len() != n {
            return Err(format!("expected {n} coordinates and an {n}×{n} matrix"));
        }
        self.load(t, q, qd);
        let (regs, outs) = (&self.regs, self.program.output_registers());
        match &self.mode {
            Mode::MassMatrix => {
                let k = n * (n + 1) / 2;
                let mut idx = 0;
                for i in 0..n {
                    for j in i..n {
                        let v = regs[outs[idx] as usize];
                        m[i * n + j] = v;
                        m[j * n + i] = v;
                        idx += 1;
                    }
                }
                for (fi, &o) in f.iter_mut().zip(&outs[k..]) {
                    *fi = regs[o as usize];
                }
                Ok(())
            }
            Mode::ConstantMass(_) => Err("the mass matrix is constant and factored".into()),
            Mode::Accelerations => Err("compiled from the accelerations".into()),
        }
    }

    /// Write (t, q, q̇) into the input registers and run the program.
    #[inline]
    fn load(&mut self, t: f64, q: &[f64], qd: &[f64]) {
        let off = self.program.input_offset();
        let r = &mut self.regs[off..off + 1 + 2 * self.n];
        r[0] = t;
        let (rq, rqd) = r[1..].split_at_mut(self.n);
        copy_small(rq, q);
        copy_small(rqd, qd);
        self.program.run(&mut self.regs);
    }

    /// q̈ at (t, q, q̇), allocation-free. An error when M is singular there
    /// (or the slices have the wrong length).
    pub fn accelerations(
        &mut self,
        t: f64,
        q: &[f64],
        qd: &[f64],
        qdd: &mut [f64],
    ) -> Result<(), String> {
        let n = self.n;
        if q.len() != n || qd.len() != n || qdd.len() != n {
            return Err(format!("expected {n} coordinates"));
        }
        self.load(t, q, qd);
        self.finish(qdd)
    }

    /// q̈ from the program's outputs (after [`Self::load`]), by the mode.
    #[inline]
    fn finish(&mut self, qdd: &mut [f64]) -> Result<(), String> {
        let n = self.n;
        let (regs, outs) = (&self.regs, self.program.output_registers());
        match &self.mode {
            Mode::Accelerations => {
                for (a, &o) in qdd.iter_mut().zip(outs) {
                    *a = regs[o as usize];
                }
            }
            Mode::ConstantMass(inv) => {
                // q̈ = M⁻¹·f, f read from its registers.
                for (a, row) in qdd.iter_mut().zip(inv.chunks_exact(n)) {
                    *a = row
                        .iter()
                        .zip(outs)
                        .map(|(m, &o)| m * regs[o as usize])
                        .sum();
                }
            }
            Mode::MassMatrix => {
                let k = n * (n + 1) / 2;
                let mut idx = 0;
                for i in 0..n {
                    for j in i..n {
                        let v = regs[outs[idx] as usize];
                        self.m[i * n + j] = v;
                        self.m[j * n + i] = v;
                        idx += 1;
                    }
                }
                for (fi, &o) in self.f.iter_mut().zip(&outs[k..]) {
                    *fi = regs[o as usize];
                }
                solve_spd(&mut self.m, &mut self.f, n)?;
                qdd.copy_from_slice(&self.f);
            }
        }
        Ok(())
    }
}

/// The full symmetric matrix from its upper triangle, row by row.
fn fill_symmetric(upper: &[f64], m: &mut [f64], n: usize) {
    let mut k = 0;
    for i in 0..n {
        for j in i..n {
            m[i * n + j] = upper[k];
            m[j * n + i] = upper[k];
            k += 1;
        }
    }
}

impl System for CompiledDynamics {
    fn dim(&self) -> usize {
        2 * self.n
    }

    /// y = (q, q̇), y' = (q̇, M⁻¹·f); NaN accelerations where M is singular
    /// (the integrators stop with `Status::NotFinite`).
    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) {
        let n = self.n;
        if y.len() != 2 * n || dy.len() != 2 * n {
            dy.fill(f64::NAN);
            return;
        }
        let (dq, dqd) = dy.split_at_mut(n);
        copy_small(dq, &y[n..]);
        // y = (q, q̇) is the program's input after t: one copy
        let off = self.program.input_offset();
        self.regs[off] = t;
        copy_small(&mut self.regs[off + 1..off + 1 + 2 * n], y);
        self.program.run(&mut self.regs);
        if self.finish(dqd).is_err() {
            dqd.fill(f64::NAN);
        }
    }
}

/// `dst.copy_from_slice(src)` (equal lengths), as plain moves for the
/// lengths of small systems: a right-hand side of a few flops would
/// otherwise spend a good part of its time in `memcpy` calls.
#[inline(always)]
fn copy_small(dst: &mut [f64], src: &[f64]) {
    macro_rules! fixed {
        ($($k:literal)*) => {
            match src.len() {
                $($k => dst[..$k].copy_from_slice(&src[..$k]),)*
                _ => dst.copy_from_slice(src),
            }
        };
    }
    fixed!(1 2 3 4 5 6 7 8)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solve_spd_cholesky_and_fallback() {
        // SPD: [[4, 2], [2, 3]]·x = [2, 1] → x = [1/2, 0].
        let mut m = vec![4.0, 2.0, 2.0, 3.0];
        let mut f = vec![2.0, 1.0];
        solve_spd(&mut m, &mut f, 2).unwrap();
        assert!((f[0] - 0.5).abs() < 1e-15 && f[1].abs() < 1e-15);
        // Symmetric indefinite: [[1, 2], [2, 1]]·x = [3, 3] → x = [1, 1];
        // Cholesky fails at column 1 and the diagonal is restored.
        let mut m = vec![1.0, 2.0, 2.0, 1.0];
        let mut f = vec![3.0, 3.0];
        solve_spd(&mut m, &mut f, 2).unwrap();
        assert!((f[0] - 1.0).abs() < 1e-15 && (f[1] - 1.0).abs() < 1e-15);
        // Zero first pivot: [[0, 1], [1, 0]]·x = [2, 5] → x = [5, 2].
        let mut m = vec![0.0, 1.0, 1.0, 0.0];
        let mut f = vec![2.0, 5.0];
        solve_spd(&mut m, &mut f, 2).unwrap();
        assert_eq!(f, vec![5.0, 2.0]);
        // Singular.
        let mut m = vec![1.0, 1.0, 1.0, 1.0];
        let mut f = vec![1.0, 2.0];
        assert!(solve_spd(&mut m, &mut f, 2).is_err());
    }

    #[test]
    fn restore_recovers_the_matrix() {
        // 3×3 with positive leading 2×2 minor but indefinite.
        let orig = [2.0, 1.0, 3.0, 1.0, 2.0, 1.0, 3.0, 1.0, 1.0];
        let mut a = orig;
        let j = cholesky(&mut a, 3).unwrap_err();
        assert_eq!(j, 2);
        restore(&mut a, 3, j);
        for (x, y) in a.iter().zip(&orig) {
            assert!((x - y).abs() < 1e-14, "{a:?}");
        }
    }

    #[test]
    fn powi_matches_repeated_multiplication() {
        for n in 0..12u32 {
            let x = 1.3f64;
            let mut p = 1.0;
            for _ in 0..n {
                p *= x;
            }
            assert!((powi(x, n) - p).abs() <= 1e-14 * p, "{n}");
        }
    }
}
