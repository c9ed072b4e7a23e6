//! `qdot codegen`: the compiled equations written out as source code in C,
//! Rust, Python or Julia, for a user's own simulator or controller.
//!
//! The functions are the [`crate::compile`] programs of `qdot
//! simulate` written one statement per instruction (`ir` lowers them,
//! `render` walks the statements, one file per language says how each
//! reads), so they share what the compiler shares: every common
//! subexpression is a local computed once, sin and cos of one angle come
//! from one `sin_cos` (C: two calls on one argument, which GCC and Clang
//! merge into `sincos`; Rust `.sin_cos()`; Julia `sincos`; Python two
//! `math` calls), powers are the interpreter's products. With `--form
//! accelerations` (the default) one function gives y' = F(t, y) for y =
//! (q, q̇), q̈ found as [`CompiledDynamics::best`] finds it: the exact
//! accelerations when they are estimated cheaper (n ≤ 3), M⁻¹·f with M⁻¹
//! computed here when M is a constant, else M·q̈ = f solved by an
//! unrolled Cholesky factorization (`dense::solve_spd`'s order of
//! operations) inside the function; with `--form mass-matrix` two
//! functions, M(q, t) and f(q, q̇, t). Either form adds the Jacobi integral
//! when the scene conserves it (as `qdot simulate`'s `energy` column).
//!
//! The parameters are arguments, in the scene's order, so one generated
//! function serves every parameter set; those given by `--set` are
//! constants instead (folded, as `qdot simulate` folds them). Names are
//! made valid identifiers of the language (`names`): θ is `theta`; the
//! header lists every renaming. C and Rust take the state and the outputs
//! as arrays the caller owns (no allocation), Python returns a list.
//!
//! [`CompiledDynamics::best`]: crate::compile::CompiledDynamics::best

mod c;
mod ir;
mod julia;
mod names;
mod python;
mod render;
mod rust;

use crate::algebra::sign::Values;
use crate::compile::{
    compile_through, estimated_cost_of, is_constant, solve_spd, state_inputs, Evaluator, Program,
    BEST_MAX_N,
};
use crate::diag::Diagnostic;
use crate::expr::{atom, Expr};
use crate::mechanics::Lagrange;
use crate::poly::Var;
use crate::scene::Scene;
use crate::{constrained, given};
use ir::{Lowering, Op, Stmt, Val};
use render::{Context, Function, Kind, Syntax};
use rustc_hash::FxHashMap;

/// The language of the generated code.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Lang {
    /// C99 with `<math.h>`.
    C,
    /// Rust (no dependencies).
    Rust,
    /// Python 3 with `math`.
    Python,
    /// Julia (the in-place form of DifferentialEquations.jl).
    Julia,
}

impl Lang {
    /// The name on the command line: `c`, `rust`, `python`, `julia`.
    pub fn name(self) -> &'static str {
        match self {
            Lang::C => "c",
            Lang::Rust => "rust",
            Lang::Python => "python",
            Lang::Julia => "julia",
        }
    }
}

/// Which functions to generate.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Form {
    /// y' = F(t, y), M·q̈ = f solved inside.
    Accelerations,
    /// M(q, t) and f(q, q̇, t), apart.
    MassMatrix,
}

impl Form {
    /// The name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Form::Accelerations => "accelerations",
            Form::MassMatrix => "mass-matrix",
        }
    }
}

/// What `qdot codegen` was asked.
#[derive(Clone, Debug)]
pub struct CodegenRequest {
    /// The scene's file name, for the header; its base name prefixes the
    /// functions' names (`pendulum_rhs`).
    pub file: String,
    /// The language.
    pub lang: Lang,
    /// The functions.
    pub form: Form,
    /// Parameters made constants (the others are arguments).
    pub set: Values,
    /// `--function s=EXPR`: each given function of time's definition, as
    /// `qdot simulate` takes it.
    pub functions: Vec<String>,
    /// Baumgarte's rate α for a scene with constraints (a constant of the
    /// code; `qdot simulate`'s default is 1).
    pub baumgarte: f64,
}

impl Default for CodegenRequest {
    /// C for `scene.qd`, the default form, nothing bound.
    fn default() -> CodegenRequest {
        CodegenRequest::new("scene.qd", Lang::C)
    }
}

impl CodegenRequest {
    /// A request for `file` in `lang`, the default form, nothing bound.
    pub fn new(file: &str, lang: Lang) -> CodegenRequest {
        CodegenRequest {
            file: file.to_string(),
            lang,
            form: Form::Accelerations,
            set: Values::new(),
            functions: Vec::new(),
            baumgarte: 1.0,
        }
    }
}

/// The source code for the scene `src` as `req` asks: a header comment
/// and the functions. An error when the scene does not compile (a
/// function the compiled code cannot evaluate, a given function without
/// its definition, a `--set` of no parameter, no coordinates).
pub fn codegen(src: &str, req: &CodegenRequest) -> Result<String, Diagnostic> {
    // a large body scene is generated from its intermediates
    let scene = Scene::read(src, crate::scene::Structure::Auto)?;
    codegen_scene(&scene, req)
}

/// [`codegen`] on a scene already read (as [`codegen`] reads it:
/// `Structure::Auto`).
pub fn codegen_scene(scene: &Scene, req: &CodegenRequest) -> Result<String, Diagnostic> {
    let lag = given::defined(scene, scene.lagrange()?, &req.functions)?;
    let constraints: Vec<String> = lag.constraints.multipliers.clone();
    let lag = constrained::stabilized(lag)?;
    let n = lag.coordinates.len();
    if n == 0 {
        return Err(Diagnostic::global(
            "the scene has no coordinates: there are no equations of motion to generate",
        )
        .with_kind(crate::diag::ErrorKind::NothingToSolve));
    }
    let mut bound = bound_parameters(scene, req)?;
    if !constraints.is_empty() {
        if !(req.baumgarte.is_finite() && req.baumgarte >= 0.0) {
            return Err(Diagnostic::global(format!(
                "--baumgarte {} must be a number ≥ 0",
                req.baumgarte
            ))
            .with_kind(crate::diag::ErrorKind::bad_option("--baumgarte")));
        }
        bound.insert(constrained::alpha_var(), req.baumgarte);
    }
    let free: Vec<String> = scene
        .parameters
        .iter()
        .filter(|p| !req.set.contains_key(&p.name))
        .map(|p| p.name.clone())
        .collect();
    let prefix = names::base(&base_name(&req.file)).to_ascii_lowercase();
    let no_form: names::ReservedForm = |_| false;
    let (syn, reserved, form): (&dyn Syntax, &[&str], names::ReservedForm) = match req.lang {
        Lang::C => (&c::C, c::RESERVED, c::may_be_a_macro),
        Lang::Rust => (&rust::Rust, rust::RESERVED, no_form),
        Lang::Python => (&python::Python, python::RESERVED, no_form),
        Lang::Julia => (&julia::Julia, julia::RESERVED, no_form),
    };
    let mut namer = names::Namer::new(reserved, form);
    for f in ["rhs", "mass_matrix", "forcing", "energy"] {
        namer.take(&format!("{prefix}_{f}"));
    }
    let params: Vec<String> = free.iter().map(|p| namer.fresh(p)).collect();
    let mut state: Vec<String> = lag.coordinates.iter().map(|q| namer.fresh(q)).collect();
    let velocities: Vec<String> = lag
        .coordinates
        .iter()
        .map(|q| namer.fresh(&format!("{q}_dot")))
        .collect();
    state.extend(velocities);
    let cx = Context { n, params, state };

    let mut inputs = state_inputs(&lag.coordinates);
    inputs.extend(free.iter().map(|p| atom::param(p)));
    let mut vals = vec![Val::Time];
    vals.extend((0..2 * n).map(Val::State));
    vals.extend((0..free.len()).map(Val::Param));
    // a tree of rigid bodies read with its kinematics kept: q̈ in O(n)
    let articulated = lag.articulated_accelerations(scene).ok();
    let g = Generator {
        lag: &lag,
        articulated: articulated.as_ref(),
        inputs: &inputs,
        vals: &vals,
        bound: &bound,
        prefix: &prefix,
    };

    let (mut functions, how) = match req.form {
        Form::Accelerations => {
            let (f, how) = g.rhs()?;
            (vec![f], how)
        }
        Form::MassMatrix => (
            vec![g.mass_matrix()?, g.forcing()?],
            "M and f apart: solve M·q̈ = f with them".to_string(),
        ),
    };
    if let Some(h) = crate::mechanics::integrals::conserved_energy(scene)
        .ok()
        .flatten()
    {
        functions.push(g.energy(&h)?);
    }
    let mut out = header(req, &lag, &cx, &free, &constraints, &how, syn, &functions);
    out.push_str(match req.lang {
        Lang::C => "\n#include <math.h>\n",
        Lang::Python => "\nimport math\n",
        Lang::Rust | Lang::Julia => "",
    });
    for f in &functions {
        out.push('\n');
        out.push_str(&render::function(syn, &cx, f));
    }
    Ok(out)
}

/// The `--set` values by atom: each a parameter of the scene.
fn bound_parameters(
    scene: &Scene,
    req: &CodegenRequest,
) -> Result<FxHashMap<Var, f64>, Diagnostic> {
    crate::scene::given::parameter_signs(scene, &req.set)?;
    crate::scene::given::set_names_are_parameters(scene, &req.set)?;
    let mut bound = FxHashMap::default();
    for (k, &v) in &req.set {
        bound.insert(atom::param(k), v);
    }
    Ok(bound)
}

/// The programs of the generated functions, over the inputs `[t, q…, q̇…,
/// free parameters…]`.
struct Generator<'a> {
    lag: &'a Lagrange,
    /// The accelerations by the articulated-body recursion, when the
    /// scene is a tree of rigid bodies read through intermediates.
    articulated: Option<&'a crate::mechanics::Accelerations>,
    inputs: &'a [Var],
    vals: &'a [Val],
    bound: &'a FxHashMap<Var, f64>,
    prefix: &'a str,
}

impl Generator<'_> {
    fn compile(&self, what: &str, exprs: &[Expr]) -> Result<Program, Diagnostic> {
        let tape = self.lag.intermediates.as_deref();
        compile_through(exprs, self.inputs, self.bound, tape).map_err(|e| {
            Diagnostic::global(format!("cannot generate code for {what}: {e}"))
                .with_hint("the generated code evaluates the functions `qdot simulate` evaluates")
                .with_kind(crate::diag::ErrorKind::Unsupported)
        })
    }

    fn n(&self) -> usize {
        self.lag.coordinates.len()
    }

    /// M's upper triangle, row by row.
    fn upper(&self) -> Vec<Expr> {
        let (n, m) = (self.n(), &self.lag.mass_matrix);
        (0..n)
            .flat_map(|i| (i..n).map(move |j| m[i][j].clone()))
            .collect()
    }

    fn function(&self, kind: Kind, stmts: Vec<Stmt>) -> Function {
        let name = match kind {
            Kind::Rhs => "rhs",
            Kind::Mass => "mass_matrix",
            Kind::Forcing => "forcing",
            Kind::Energy => "energy",
        };
        Function {
            kind,
            name: format!("{}_{name}", self.prefix),
            can_fail: stmts.iter().any(|s| matches!(s, Stmt::Pivot { .. })),
            stmts,
        }
    }

    /// y' = F(t, y), and how q̈ is found (for the header).
    fn rhs(&self) -> Result<(Function, String), Diagnostic> {
        let n = self.n();
        let upper = self.upper();
        let tape = self.lag.intermediates.as_deref();
        let (program, evaluator, inverse) = if is_constant(&upper, self.inputs, tape) {
            let inverse = self.constant_inverse(&upper)?;
            let p = self.compile("f", &self.lag.forcing)?;
            (p, Evaluator::ConstantMass, inverse)
        } else {
            let mut outs = upper;
            outs.extend(self.lag.forcing.iter().cloned());
            let p = self.compile("M and f", &outs)?;
            (p, Evaluator::MassMatrix, Vec::new())
        };
        let mass_cost = estimated_cost_of(&program, evaluator, n);
        let mut chosen = (program, evaluator);
        let mut how = match evaluator {
            Evaluator::ConstantMass => "q̈ = M⁻¹·f, the constant M⁻¹ computed by qdot".to_string(),
            _ if n == 1 => "q̈ = f/M".to_string(),
            _ => "M·q̈ = f solved by Cholesky (unrolled) in the function".to_string(),
        };
        if n <= BEST_MAX_N {
            // an option, as in `CompiledDynamics::best`: past the work
            // budget M and f serve
            let exact = crate::budget::probe(crate::budget::limit(), || self.lag.accelerations());
            if let Ok(Ok(acc)) = exact {
                let exprs: Vec<Expr> = acc.values().to_vec();
                let tape = acc.intermediates();
                if let Ok(p) = compile_through(&exprs, self.inputs, self.bound, tape) {
                    let cost = estimated_cost_of(&p, Evaluator::Accelerations, n);
                    if cost <= mass_cost {
                        how = format!(
                            "the exact accelerations q̈ = M⁻¹·f derived by qdot (≈ {cost:.0} flops per call against ≈ {mass_cost:.0} with M, f and the solve)"
                        );
                        chosen = (p, Evaluator::Accelerations);
                    }
                }
            }
        }
        if let Some(acc) = self.articulated {
            let tape = acc.intermediates();
            if let Ok(p) = compile_through(acc.values(), self.inputs, self.bound, tape) {
                let cost = estimated_cost_of(&p, Evaluator::Articulated, n);
                let other = estimated_cost_of(&chosen.0, chosen.1, n);
                if cost < other {
                    how = format!(
                        "the articulated-body recursion (Featherstone), O(n) intermediates (≈ {cost:.0} flops per call against ≈ {other:.0})"
                    );
                    chosen = (p, Evaluator::Articulated);
                }
            }
        }
        let mut low = Lowering::default();
        let outs = low.program(&chosen.0, self.vals);
        let qdd = match chosen.1 {
            Evaluator::Accelerations | Evaluator::Articulated => outs,
            Evaluator::ConstantMass => low.constant_product(&inverse, &outs),
            Evaluator::MassMatrix => {
                let (m, f) = outs.split_at(n * (n + 1) / 2);
                if n == 1 {
                    vec![low.temp(Op::Div(f[0], m[0]))]
                } else {
                    let at = |i: usize, j: usize| m[i * n - i * i.saturating_sub(1) / 2 + j - i];
                    low.cholesky(&at, f)
                }
            }
        };
        for i in 0..n {
            low.stmts.push(Stmt::Out(i, Val::State(n + i)));
        }
        for (i, v) in qdd.into_iter().enumerate() {
            low.stmts.push(Stmt::Out(n + i, v));
        }
        Ok((self.function(Kind::Rhs, low.stmts), how))
    }

    /// M⁻¹ of a constant M, row-major, as `CompiledDynamics` computes it.
    fn constant_inverse(&self, upper: &[Expr]) -> Result<Vec<f64>, Diagnostic> {
        let n = self.n();
        let p = self.compile("M", upper)?;
        let mut vals = vec![0.0; upper.len()];
        p.eval(&vec![0.0; self.inputs.len()], &mut p.registers(), &mut vals);
        let mut inverse = vec![0.0; n * n];
        let (mut m, mut col) = (vec![0.0; n * n], vec![0.0; n]);
        for j in 0..n {
            let mut k = 0;
            for r in 0..n {
                for c in r..n {
                    m[r * n + c] = vals[k];
                    m[c * n + r] = vals[k];
                    k += 1;
                }
            }
            col.fill(0.0);
            col[j] = 1.0;
            solve_spd(&mut m, &mut col, n).map_err(|e| {
                Diagnostic::global(format!("the constant mass matrix cannot be inverted: {e}"))
                    .with_kind(crate::diag::ErrorKind::SingularSystem {
                        unknowns: Vec::new(),
                    })
            })?;
            for i in 0..n {
                inverse[i * n + j] = col[i];
            }
        }
        Ok(inverse)
    }

    /// M(q, t), both triangles, row by row.
    fn mass_matrix(&self) -> Result<Function, Diagnostic> {
        let n = self.n();
        let upper = self.upper();
        let qd: Vec<Var> = self.inputs[1 + n..1 + 2 * n].to_vec();
        if upper.iter().any(|e| qd.iter().any(|&v| e.depends_on(v))) {
            return Err(Diagnostic::global(
                "the mass matrix depends on the velocities: it cannot be written as M(q, t)",
            )
            .with_kind(crate::diag::ErrorKind::Unsupported));
        }
        let p = self.compile("M", &upper)?;
        let mut low = Lowering::default();
        let outs = low.program(&p, self.vals);
        let mut k = 0;
        for i in 0..n {
            for j in i..n {
                low.stmts.push(Stmt::Out(i * n + j, outs[k]));
                if i != j {
                    low.stmts.push(Stmt::Out(j * n + i, outs[k]));
                }
                k += 1;
            }
        }
        Ok(self.function(Kind::Mass, low.stmts))
    }

    /// f(q, q̇, t).
    fn forcing(&self) -> Result<Function, Diagnostic> {
        let p = self.compile("f", &self.lag.forcing)?;
        let mut low = Lowering::default();
        let outs = low.program(&p, self.vals);
        for (i, v) in outs.into_iter().enumerate() {
            low.stmts.push(Stmt::Out(i, v));
        }
        Ok(self.function(Kind::Forcing, low.stmts))
    }

    /// The Jacobi integral h.
    fn energy(&self, h: &Expr) -> Result<Function, Diagnostic> {
        let p = self.compile("the energy", std::slice::from_ref(h))?;
        let mut low = Lowering::default();
        let outs = low.program(&p, self.vals);
        low.stmts.push(Stmt::Out(0, outs[0]));
        Ok(self.function(Kind::Energy, low.stmts))
    }
}

/// `examples/seed_24_2.qd` → `seed_24_2`.
fn base_name(file: &str) -> String {
    std::path::Path::new(file)
        .file_stem()
        .and_then(|s| s.to_str())
        .filter(|s| !s.is_empty())
        .unwrap_or("scene")
        .to_string()
}

/// The header comment: the scene, the command, the state layout, the
/// parameters, how q̈ is found, the functions.
#[allow(clippy::too_many_arguments)]
fn header(
    req: &CodegenRequest,
    lag: &Lagrange,
    cx: &Context,
    free: &[String],
    constraints: &[String],
    how: &str,
    syn: &dyn Syntax,
    functions: &[Function],
) -> String {
    let n = cx.n;
    let base = usize::from(req.lang == Lang::Julia);
    let mut l: Vec<String> = Vec::new();
    let mut command = format!(
        "qdot codegen {} --lang {} --form {}",
        req.file,
        req.lang.name(),
        req.form.name()
    );
    if !req.set.is_empty() {
        let s: Vec<String> = req.set.iter().map(|(k, v)| format!("{k}={v}")).collect();
        command.push_str(&format!(" --set {}", s.join(",")));
    }
    l.push(format!(
        "{}: generated by qdot {} ({command}).",
        req.file,
        env!("CARGO_PKG_VERSION")
    ));
    l.push(String::new());
    l.push("Lagrange's equations M(q, t)·q̈ = f(q, q̇, t) as the first-order system".into());
    l.push("y' = F(t, y) with y = (q, q̇), y' = (q̇, q̈); the state y is".into());
    for (i, q) in lag.coordinates.iter().enumerate() {
        l.push(format!("  y[{}] = {}", i + base, shown(q, &cx.state[i])));
    }
    for (i, q) in lag.coordinates.iter().enumerate() {
        l.push(format!(
            "  y[{}] = {}",
            n + i + base,
            shown(&format!("{q}'"), &cx.state[n + i])
        ));
    }
    if free.is_empty() {
        l.push("Parameters: none are arguments.".into());
    } else {
        let ps: Vec<String> = free
            .iter()
            .zip(&cx.params)
            .map(|(p, id)| shown(p, id))
            .collect();
        let order = if req.lang == Lang::Julia {
            "the tuple p, in this order"
        } else {
            "arguments, in this order"
        };
        l.push(format!("Parameters ({order}): {}.", ps.join(", ")));
    }
    if !req.set.is_empty() {
        let s: Vec<String> = req.set.iter().map(|(k, v)| format!("{k} = {v}")).collect();
        l.push(format!("Constants (--set): {}.", s.join(", ")));
    }
    if !constraints.is_empty() {
        l.push(format!(
            "Constraints ({}): the accelerations of the augmented system, Baumgarte's rate {} (--baumgarte).",
            constraints.join(", "),
            req.baumgarte
        ));
    }
    for d in &req.functions {
        l.push(format!("Given function (--function): {d}."));
    }
    l.push(format!("q̈: {how}."));
    l.push("Shared subexpressions are computed once (w0, w1, …).".into());
    l.push(String::new());
    for f in functions {
        l.push(syn.signature(cx, f));
        l.push(format!("    {}", describe(req.lang, f, n)));
    }
    let prefix = match req.lang {
        Lang::C | Lang::Rust => "//",
        Lang::Python | Lang::Julia => "#",
    };
    l.iter()
        .map(|s| {
            if s.is_empty() {
                format!("{prefix}\n")
            } else {
                format!("{prefix} {s}\n")
            }
        })
        .collect()
}

/// `θ (theta)` when the identifier differs from the scene's name.
fn shown(name: &str, id: &str) -> String {
    if name == id {
        name.to_string()
    } else {
        format!("{name} ({id})")
    }
}

/// What a function computes, one line for the header.
fn describe(lang: Lang, f: &Function, n: usize) -> String {
    let fails = match (lang, f.can_fail) {
        (_, false) => String::new(),
        (Lang::C, true) => {
            "; 0, or k + 1 when M's Cholesky pivot k is not positive (dy NaN)".into()
        }
        (Lang::Rust, true) => "; Err(k) when M's Cholesky pivot k is not positive (dy NaN)".into(),
        (Lang::Python, true) => "; ValueError when M's Cholesky pivot is not positive".into(),
        (Lang::Julia, true) => "; an error when M's Cholesky pivot is not positive".into(),
    };
    let list = lang == Lang::Python;
    match f.kind {
        Kind::Rhs if list => format!("y' = F(t, y), a list of {}{fails}", 2 * n),
        Kind::Rhs => format!("dy = F(t, y){fails}"),
        Kind::Mass if list => format!("M(q, t), a list of {n} rows"),
        Kind::Mass if lang == Lang::Julia => format!("M(q, t) into the {n}×{n} matrix mass"),
        Kind::Mass => format!("M(q, t) into mass, {n}×{n} row by row"),
        Kind::Forcing if list => format!("f(q, q̇, t), a list of {n}"),
        Kind::Forcing => "f(q, q̇, t) into forcing".to_string(),
        Kind::Energy => "the conserved energy (Jacobi integral h = Σ q̇·∂L/∂q̇ − L)".to_string(),
    }
}
