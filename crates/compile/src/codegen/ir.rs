//! The generated functions before they are written in a language: a
//! straight-line list of statements over single-assignment temporaries,
//! lowered from compiled [`Program`]s one instruction at a time (so the
//! program's shared subexpressions and `sin_cos` pairs carry over), plus
//! the unrolled Cholesky solve and the constant-M⁻¹ product of
//! `CompiledDynamics`, in the same operation order.

use crate::compile::{Instr, Program};

/// An operand: a literal, a temporary, the time, an entry of the input
/// array (y, or q for the mass matrix) or a parameter (by its index among
/// the function's parameter arguments).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Val {
    Lit(f64),
    Temp(u32),
    Time,
    State(usize),
    Param(usize),
}

/// A function of one argument.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Fun {
    Sin,
    Cos,
    Exp,
    Ln,
    Sqrt,
    Atan,
    Asin,
    Acos,
}

impl Fun {
    /// Every function (C and Julia call them by their bare names, so their
    /// lists of reserved names must hold each one: checked at compile time
    /// below, [`EVERY_FUNCTION_IS_RESERVED`]).
    const ALL: [Fun; 8] = [
        Fun::Sin,
        Fun::Cos,
        Fun::Exp,
        Fun::Ln,
        Fun::Sqrt,
        Fun::Atan,
        Fun::Asin,
        Fun::Acos,
    ];

    /// Its name in C's libm, which C, Python's `math` and Julia share
    /// (Rust writes `ln` for `log`).
    pub(super) const fn libm_name(self) -> &'static str {
        match self {
            Fun::Sin => "sin",
            Fun::Cos => "cos",
            Fun::Exp => "exp",
            Fun::Ln => "log",
            Fun::Sqrt => "sqrt",
            Fun::Atan => "atan",
            Fun::Asin => "asin",
            Fun::Acos => "acos",
        }
    }

    fn eval(self, x: f64) -> f64 {
        match self {
            Fun::Sin => x.sin(),
            Fun::Cos => x.cos(),
            Fun::Exp => x.exp(),
            Fun::Ln => x.ln(),
            Fun::Sqrt => x.sqrt(),
            Fun::Atan => x.atan(),
            Fun::Asin => x.asin(),
            Fun::Acos => x.acos(),
        }
    }
}

/// The right-hand side of a temporary's definition.
#[derive(Clone, Debug, PartialEq)]
pub(super) enum Op {
    Add(Val, Val),
    Sub(Val, Val),
    Mul(Val, Val),
    Div(Val, Val),
    Neg(Val),
    /// `init + a₁·b₁ + a₂·b₂ + …`, summed left to right (without `init`,
    /// from the first product).
    Dot(Option<Val>, Vec<(Val, Val)>),
    /// `init − a₁·b₁ − a₂·b₂ − …`, left to right.
    SubDot(Val, Vec<(Val, Val)>),
    Call(Fun, Val),
}

/// One statement.
#[derive(Clone, Debug, PartialEq)]
pub(super) enum Stmt {
    /// A new temporary.
    Let(u32, Op),
    /// Two new temporaries: the sine and the cosine of one argument.
    SinCos { sin: u32, cos: u32, arg: Val },
    /// The Cholesky pivot of `column` must be positive (else M is not
    /// positive definite there and the function fails).
    Pivot { value: Val, column: usize },
    /// Output `index` (of dy, the mass matrix row by row, f, or the one
    /// value returned) is `value`. Outputs come last.
    Out(usize, Val),
}

/// Statements under construction.
#[derive(Default)]
pub(super) struct Lowering {
    pub(super) stmts: Vec<Stmt>,
    next: u32,
    /// Whether each temporary depends on the parameters and literals only.
    params_only: Vec<bool>,
    /// 1/b for the parameter-only divisors b met so far.
    reciprocals: Vec<(Val, Val)>,
}

impl Lowering {
    /// A temporary defined by `op`, or the literal it folds to when every
    /// operand is a literal. A division of a value that moves by one that
    /// does not (a parameter's, like g/l's l) becomes a product with the
    /// reciprocal, computed apart: the division then runs beside the
    /// state's work instead of at its end (C compilers may not do this
    /// without -ffast-math; the result moves by at most one rounding).
    pub(super) fn temp(&mut self, op: Op) -> Val {
        if let Some(x) = fold(&op) {
            return Val::Lit(x);
        }
        if let Op::Div(a, b) = op {
            if !matches!(a, Val::Lit(_)) && !self.is_params_only(a) && self.is_params_only(b) {
                let r = match self.reciprocals.iter().find(|(d, _)| *d == b) {
                    Some(&(_, r)) => r,
                    None => {
                        let r = self.push(Op::Div(Val::Lit(1.0), b));
                        self.reciprocals.push((b, r));
                        r
                    }
                };
                return self.push(Op::Mul(a, r));
            }
        }
        self.push(op)
    }

    fn push(&mut self, op: Op) -> Val {
        let params_only = operands(&op).iter().all(|v| self.is_params_only(*v));
        let k = self.next;
        self.next += 1;
        self.params_only.push(params_only);
        self.stmts.push(Stmt::Let(k, op));
        Val::Temp(k)
    }

    fn is_params_only(&self, v: Val) -> bool {
        match v {
            Val::Lit(_) | Val::Param(_) => true,
            Val::Time | Val::State(_) => false,
            Val::Temp(k) => self.params_only[k as usize],
        }
    }

    /// The instructions of `program` with `inputs` in its input registers;
    /// the values of its outputs.
    pub(super) fn program(&mut self, program: &Program, inputs: &[Val]) -> Vec<Val> {
        let mut cur = vec![Val::Lit(0.0); program.n_registers()];
        for (r, &c) in cur.iter_mut().zip(program.constants()) {
            *r = Val::Lit(c);
        }
        let off = program.input_offset();
        for (k, &v) in inputs.iter().enumerate() {
            cur[off + k] = v;
        }
        let pairs = program.pairs();
        for ins in program.instructions() {
            let g = |r: u32| cur[r as usize];
            let (dst, v) = match *ins {
                Instr::Add { dst, a, b } => (dst, self.temp(Op::Add(g(a), g(b)))),
                Instr::Sub { dst, a, b } => (dst, self.temp(Op::Sub(g(a), g(b)))),
                Instr::Mul { dst, a, b } => (dst, self.temp(Op::Mul(g(a), g(b)))),
                Instr::MulAdd { dst, a, b, c } => {
                    (dst, self.temp(Op::Dot(Some(g(c)), vec![(g(a), g(b))])))
                }
                Instr::Dot {
                    dst,
                    init,
                    start,
                    len,
                } => {
                    let init = (init != u32::MAX).then(|| g(init));
                    let ps = pairs[start as usize..(start + len) as usize]
                        .iter()
                        .map(|&(a, b)| (g(a), g(b)))
                        .collect();
                    (dst, self.temp(Op::Dot(init, ps)))
                }
                Instr::Div { dst, a, b } => (dst, self.temp(Op::Div(g(a), g(b)))),
                Instr::Neg { dst, a } => (dst, self.temp(Op::Neg(g(a)))),
                Instr::Powi { dst, a, n } => (dst, self.powi(g(a), n)),
                Instr::Sin { dst, a } => (dst, self.temp(Op::Call(Fun::Sin, g(a)))),
                Instr::Cos { dst, a } => (dst, self.temp(Op::Call(Fun::Cos, g(a)))),
                Instr::Exp { dst, a } => (dst, self.temp(Op::Call(Fun::Exp, g(a)))),
                Instr::Ln { dst, a } => (dst, self.temp(Op::Call(Fun::Ln, g(a)))),
                Instr::Sqrt { dst, a } => (dst, self.temp(Op::Call(Fun::Sqrt, g(a)))),
                Instr::Atan { dst, a } => (dst, self.temp(Op::Call(Fun::Atan, g(a)))),
                Instr::Asin { dst, a } => (dst, self.temp(Op::Call(Fun::Asin, g(a)))),
                Instr::Acos { dst, a } => (dst, self.temp(Op::Call(Fun::Acos, g(a)))),
                Instr::SinCos { sin, cos, a } => {
                    let (s, c) = (self.next, self.next + 1);
                    self.next += 2;
                    let p = self.is_params_only(g(a));
                    self.params_only.extend([p, p]);
                    self.stmts.push(Stmt::SinCos {
                        sin: s,
                        cos: c,
                        arg: g(a),
                    });
                    cur[sin as usize] = Val::Temp(s);
                    (cos, Val::Temp(c))
                }
            };
            cur[dst as usize] = v;
        }
        program
            .output_registers()
            .iter()
            .map(|&r| cur[r as usize])
            .collect()
    }

    /// xⁿ (n ≥ 2) by the interpreter's binary powering (`program::powi`):
    /// the same products in the same order.
    fn powi(&mut self, x: Val, n: u32) -> Val {
        let (mut acc, mut base, mut e): (Option<Val>, Val, u32) = (None, x, n);
        while e > 0 {
            if e & 1 == 1 {
                acc = Some(match acc {
                    None => base,
                    Some(a) => self.temp(Op::Mul(a, base)),
                });
            }
            e >>= 1;
            if e > 0 {
                base = self.temp(Op::Mul(base, base));
            }
        }
        acc.unwrap_or(Val::Lit(1.0))
    }

    /// Solve M·x = f by Cholesky, unrolled (`dense::solve_spd`'s order of
    /// operations): `upper(i, j)` is M's entry for i ≤ j.
    pub(super) fn cholesky(&mut self, upper: &dyn Fn(usize, usize) -> Val, f: &[Val]) -> Vec<Val> {
        let n = f.len();
        let mut l = vec![vec![Val::Lit(0.0); n]; n];
        for j in 0..n {
            let d = if j == 0 {
                upper(0, 0)
            } else {
                let s = self.temp(Op::Dot(None, (0..j).map(|k| (l[j][k], l[j][k])).collect()));
                self.temp(Op::Sub(upper(j, j), s))
            };
            if !matches!(d, Val::Lit(x) if x > 0.0) {
                self.stmts.push(Stmt::Pivot {
                    value: d,
                    column: j,
                });
            }
            let ljj = self.temp(Op::Call(Fun::Sqrt, d));
            l[j][j] = ljj;
            if j + 1 == n {
                break;
            }
            let inv = self.temp(Op::Div(Val::Lit(1.0), ljj));
            for i in j + 1..n {
                let v = if j == 0 {
                    upper(0, i)
                } else {
                    let s = self.temp(Op::Dot(None, (0..j).map(|k| (l[i][k], l[j][k])).collect()));
                    self.temp(Op::Sub(upper(j, i), s))
                };
                l[i][j] = self.temp(Op::Mul(v, inv));
            }
        }
        let mut b: Vec<Val> = Vec::with_capacity(n);
        for i in 0..n {
            let num = if i == 0 {
                f[0]
            } else {
                let s = self.temp(Op::Dot(None, (0..i).map(|k| (l[i][k], b[k])).collect()));
                self.temp(Op::Sub(f[i], s))
            };
            b.push(self.temp(Op::Div(num, l[i][i])));
        }
        let mut x = vec![Val::Lit(0.0); n];
        for i in (0..n).rev() {
            let num = if i + 1 == n {
                b[i]
            } else {
                self.temp(Op::SubDot(
                    b[i],
                    (i + 1..n).map(|k| (l[k][i], x[k])).collect(),
                ))
            };
            x[i] = self.temp(Op::Div(num, l[i][i]));
        }
        x
    }

    /// q̈ = M⁻¹·f with M⁻¹ known (row-major), as `CompiledDynamics` does
    /// for a constant M: zero entries skipped, a lone 1 a copy.
    pub(super) fn constant_product(&mut self, inverse: &[f64], f: &[Val]) -> Vec<Val> {
        let n = f.len();
        (0..n)
            .map(|i| {
                let terms: Vec<(Val, Val)> = (0..n)
                    .filter(|&j| inverse[i * n + j] != 0.0)
                    .map(|j| (Val::Lit(inverse[i * n + j]), f[j]))
                    .collect();
                match terms.as_slice() {
                    [] => Val::Lit(0.0),
                    [(Val::Lit(c), v)] if *c == 1.0 => *v,
                    _ => self.temp(Op::Dot(None, terms)),
                }
            })
            .collect()
    }
}

/// The operands of an operation.
fn operands(op: &Op) -> Vec<Val> {
    match op {
        Op::Add(a, b) | Op::Sub(a, b) | Op::Mul(a, b) | Op::Div(a, b) => vec![*a, *b],
        Op::Neg(a) | Op::Call(_, a) => vec![*a],
        Op::Dot(init, ps) => init
            .iter()
            .copied()
            .chain(ps.iter().flat_map(|&(a, b)| [a, b]))
            .collect(),
        Op::SubDot(init, ps) => std::iter::once(*init)
            .chain(ps.iter().flat_map(|&(a, b)| [a, b]))
            .collect(),
    }
}

/// The value of an operation on literals only.
fn fold(op: &Op) -> Option<f64> {
    let lit = |v: &Val| match v {
        Val::Lit(x) => Some(*x),
        _ => None,
    };
    let dot = |init: Option<f64>, ps: &[(Val, Val)], sign: f64| -> Option<f64> {
        let mut acc = init;
        for (a, b) in ps {
            let p = lit(a)? * lit(b)?;
            acc = Some(match acc {
                None => p,
                Some(s) => s + sign * p,
            });
        }
        acc
    };
    Some(match op {
        Op::Add(a, b) => lit(a)? + lit(b)?,
        Op::Sub(a, b) => lit(a)? - lit(b)?,
        Op::Mul(a, b) => lit(a)? * lit(b)?,
        Op::Div(a, b) => lit(a)? / lit(b)?,
        Op::Neg(a) => -lit(a)?,
        Op::Dot(init, ps) => {
            let init = match init {
                Some(v) => Some(lit(v)?),
                None => None,
            };
            dot(init, ps, 1.0)?
        }
        Op::SubDot(init, ps) => dot(Some(lit(init)?), ps, -1.0)?,
        Op::Call(f, a) => f.eval(lit(a)?),
    })
}

/// Whether `list` holds `name` (`<[&str]>::contains` in a constant).
const fn holds(list: &[&str], name: &str) -> bool {
    let mut i = 0;
    while i < list.len() {
        let (a, b) = (list[i].as_bytes(), name.as_bytes());
        if a.len() == b.len() {
            let mut k = 0;
            while k < a.len() && a[k] == b[k] {
                k += 1;
            }
            if k == a.len() {
                return true;
            }
        }
        i += 1;
    }
    false
}

/// A parameter named like a called function would shadow it, so C's and
/// Julia's reserved names hold every function's name, and `ALL` holds
/// every function (the match has no wildcard: a new function fails to
/// compile here until it has its position in `ALL`).
const EVERY_FUNCTION_IS_RESERVED: () = {
    let mut i = 0;
    while i < Fun::ALL.len() {
        let f = Fun::ALL[i];
        let position = match f {
            Fun::Sin => 0,
            Fun::Cos => 1,
            Fun::Exp => 2,
            Fun::Ln => 3,
            Fun::Sqrt => 4,
            Fun::Atan => 5,
            Fun::Asin => 6,
            Fun::Acos => 7,
        };
        assert!(position == i, "Fun::ALL is in the order of the enum");
        assert!(holds(super::c::RESERVED, f.libm_name()), "C reserves it");
        assert!(
            holds(super::julia::RESERVED, f.libm_name()),
            "Julia reserves it"
        );
        i += 1;
    }
};
const _: () = EVERY_FUNCTION_IS_RESERVED;
