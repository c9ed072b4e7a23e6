//! What every language shares: the functions to write, the identifiers,
//! and the walk over the statements; each language says how a statement
//! reads ([`Syntax`]).

use super::ir::{Fun, Op, Stmt, Val};

/// What a generated function computes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Kind {
    /// y' = F(t, y) into `dy`; may fail (M not positive definite).
    Rhs,
    /// M(q, t), n×n row by row, into `mass`.
    Mass,
    /// f(q, q̇, t) into `forcing`.
    Forcing,
    /// The conserved Jacobi integral, returned.
    Energy,
}

impl Kind {
    /// The input array: `q` for the mass matrix, else `y`.
    pub(super) fn input(self) -> &'static str {
        match self {
            Kind::Mass => "q",
            _ => "y",
        }
    }
    /// The output array (none for the energy).
    pub(super) fn output(self) -> &'static str {
        match self {
            Kind::Rhs => "dy",
            Kind::Mass => "mass",
            Kind::Forcing => "forcing",
            Kind::Energy => "",
        }
    }
}

/// One generated function.
pub(super) struct Function {
    pub(super) kind: Kind,
    /// Its identifier (the Julia writers add `!` to the mutating ones).
    pub(super) name: String,
    pub(super) stmts: Vec<Stmt>,
    /// Whether it contains a Cholesky pivot check.
    pub(super) can_fail: bool,
}

/// The names and sizes shared by the functions of one output.
pub(super) struct Context {
    /// The number of coordinates.
    pub(super) n: usize,
    /// The identifiers of the parameter arguments, in order.
    pub(super) params: Vec<String>,
    /// The identifiers of y's entries: the coordinates, then their
    /// velocities.
    pub(super) state: Vec<String>,
}

impl Context {
    /// The length of a function's input array.
    pub(super) fn input_len(&self, k: Kind) -> usize {
        match k {
            Kind::Mass => self.n,
            _ => 2 * self.n,
        }
    }
    /// The length of a function's output array.
    pub(super) fn output_len(&self, k: Kind) -> usize {
        match k {
            Kind::Rhs => 2 * self.n,
            Kind::Mass => self.n * self.n,
            Kind::Forcing => self.n,
            Kind::Energy => 1,
        }
    }
}

/// What a function reads: the time, each parameter, each input entry.
pub(super) struct Uses {
    pub(super) time: bool,
    pub(super) params: Vec<bool>,
    pub(super) state: Vec<bool>,
}

pub(super) fn uses(cx: &Context, f: &Function) -> Uses {
    let mut u = Uses {
        time: false,
        params: vec![false; cx.params.len()],
        state: vec![false; 2 * cx.n],
    };
    let mut see = |v: &Val| match *v {
        Val::Time => u.time = true,
        Val::Param(k) => u.params[k] = true,
        Val::State(i) => u.state[i] = true,
        Val::Lit(_) | Val::Temp(_) => {}
    };
    for s in &f.stmts {
        match s {
            Stmt::Let(_, op) => match op {
                Op::Add(a, b) | Op::Sub(a, b) | Op::Mul(a, b) | Op::Div(a, b) => {
                    see(a);
                    see(b)
                }
                Op::Neg(a) | Op::Call(_, a) => see(a),
                Op::Dot(init, ps) => {
                    init.iter().for_each(&mut see);
                    ps.iter().for_each(|(a, b)| {
                        see(a);
                        see(b)
                    })
                }
                Op::SubDot(init, ps) => {
                    see(init);
                    ps.iter().for_each(|(a, b)| {
                        see(a);
                        see(b)
                    })
                }
            },
            Stmt::SinCos { arg, .. } => see(arg),
            Stmt::Pivot { value, .. } | Stmt::Out(_, value) => see(value),
        }
    }
    u
}

/// How one language writes the pieces of a function.
pub(super) trait Syntax {
    /// A double literal (a negative one in parentheses).
    fn lit(&self, x: f64) -> String;
    /// `f(arg)`; `arg` is a name or a literal.
    fn call(&self, f: Fun, arg: &str) -> String;
    /// The signature, one line (the header lists it).
    fn signature(&self, cx: &Context, f: &Function) -> String;
    /// The opening of the function, through its first line of body.
    fn open(&self, cx: &Context, f: &Function, uses: &Uses) -> String;
    /// A local bound to entry `index` of the input array.
    fn bind(&self, name: &str, array: &str, index: usize) -> String;
    /// A new local.
    fn let_(&self, name: &str, value: &str) -> String;
    /// Two new locals: the sine and cosine of `arg`.
    fn sin_cos(&self, sin: &str, cos: &str, arg: &str) -> String;
    /// The check of a Cholesky pivot.
    fn pivot(&self, cx: &Context, f: &Function, value: &str, column: usize) -> String;
    /// The outputs stored (or returned) and the function closed.
    fn finish(&self, cx: &Context, f: &Function, outs: &[String]) -> String;
}

/// The function written by `syn`.
pub(super) fn function(syn: &dyn Syntax, cx: &Context, f: &Function) -> String {
    let u = uses(cx, f);
    let mut out = syn.open(cx, f, &u);
    for (i, used) in u.state.iter().enumerate() {
        if *used {
            out.push_str(&syn.bind(&cx.state[i], f.kind.input(), i));
        }
    }
    let val = |v: &Val| -> String {
        match *v {
            Val::Lit(x) => syn.lit(x),
            Val::Temp(k) => format!("w{k}"),
            Val::Time => "t".to_string(),
            Val::State(i) => cx.state[i].clone(),
            Val::Param(k) => cx.params[k].clone(),
        }
    };
    let products = |ps: &[(Val, Val)], sep: &str| -> String {
        ps.iter()
            .map(|(a, b)| format!("{}*{}", val(a), val(b)))
            .collect::<Vec<_>>()
            .join(sep)
    };
    let mut outs = vec![String::new(); cx.output_len(f.kind)];
    for s in &f.stmts {
        match s {
            Stmt::Let(k, op) => {
                let e = match op {
                    Op::Add(a, b) => format!("{} + {}", val(a), val(b)),
                    Op::Sub(a, b) => format!("{} - {}", val(a), val(b)),
                    Op::Mul(a, b) => format!("{}*{}", val(a), val(b)),
                    Op::Div(a, b) => format!("{}/{}", val(a), val(b)),
                    Op::Neg(a) => format!("-{}", val(a)),
                    Op::Dot(None, ps) => products(ps, " + "),
                    Op::Dot(Some(init), ps) => format!("{} + {}", val(init), products(ps, " + ")),
                    Op::SubDot(init, ps) => format!("{} - {}", val(init), products(ps, " - ")),
                    Op::Call(fun, a) => syn.call(*fun, &val(a)),
                };
                out.push_str(&syn.let_(&format!("w{k}"), &e));
            }
            Stmt::SinCos { sin, cos, arg } => {
                out.push_str(&syn.sin_cos(&format!("w{sin}"), &format!("w{cos}"), &val(arg)))
            }
            Stmt::Pivot { value, column } => out.push_str(&syn.pivot(cx, f, &val(value), *column)),
            Stmt::Out(k, v) => outs[*k] = val(v),
        }
    }
    out.push_str(&syn.finish(cx, f, &outs));
    out
}

/// Rust's shortest round-trip spelling of a finite double (`0.5`, `9.81`,
/// `1e-7`, `2.0`): a valid literal in C, Rust, Python and Julia.
pub(super) fn shortest(x: f64) -> String {
    let s = format!("{x:?}");
    if x < 0.0 {
        format!("({s})")
    } else {
        s
    }
}

/// The argument list's parameter part: `prefix name suffix` for each,
/// joined by `, `, with a leading `, ` when there is any.
pub(super) fn param_list(cx: &Context, each: &dyn Fn(&str) -> String) -> String {
    cx.params.iter().map(|p| format!(", {}", each(p))).collect()
}
