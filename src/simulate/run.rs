//! `qdot simulate`: a scene's exact equations compiled and integrated.
//!
//! The parameters get values (`--set`), every coordinate and velocity an
//! initial value (`--init`); M and f are compiled ([`CompiledDynamics`])
//! and integrated by the chosen [`Method`]. When the scene is conservative
//! (no work, dissipation, forces, loads or torques, and no explicit t) the
//! Jacobi integral h = Σ q̇ₖ·∂E/∂q̇ₖ − E + V − U (E + V − U for a natural
//! system) is compiled too and reported as `energy`, so its drift shows
//! the integration error.

use super::compile::{
    compile_with, state_inputs, Choice, CompiledDynamics, Engine, EngineReport, Program,
};
#[cfg(feature = "cli")]
use super::progress::Progress;
use super::{
    integrate, integrate_with_event, IntegratorOptions, Method, SimError, Solution, Status, System,
};
use crate::algebra::sign::Values;
use crate::diag::{Diagnostic, ErrorKind};
use crate::expr::Expr;
use crate::poly::Var;
use crate::scene::Scene;
use rustc_hash::FxHashMap;
use std::sync::Arc;
use std::time::Instant;

/// What `qdot simulate` was asked.
#[derive(Clone, Debug)]
pub struct Request {
    /// Parameter values (every parameter of the scene needs one).
    pub set: Values,
    /// Initial values: `q` and `q'` for every coordinate.
    pub init: Values,
    /// The final time (the run starts at t = 0).
    pub t_end: f64,
    /// The integration method.
    pub method: Method,
    /// The relative tolerance of the adaptive methods.
    pub rtol: f64,
    /// The absolute tolerance of the adaptive methods.
    pub atol: f64,
    /// The step of RK4 and Gauss6 (required for them), the first step of
    /// the adaptive methods.
    pub dt: Option<f64>,
    /// Number of evenly spaced output times from 0 to `t_end` (2 to
    /// [`crate::limits::MAX_POINTS`]).
    pub points: usize,
    /// Steps (accepted and rejected) before the run gives up.
    pub max_steps: usize,
    /// `--stop-when`: `lhs = rhs` (or one expression, = 0) in the scene's
    /// names; the run ends where it first changes sign.
    pub stop_when: Option<String>,
    /// `--function s=EXPR`: the definition of each given function of time
    /// (an expression in t and the parameters), as written.
    pub functions: Vec<String>,
    /// Baumgarte's rate α for a scene with constraints (1/time of the
    /// scene; 0 turns the stabilization off): see [`super::constrained`].
    pub baumgarte: f64,
    /// Show a progress bar on standard error when the integration lasts
    /// more than half a second (`simulate::progress`, with the `cli`
    /// feature); the command line sets it when standard error is a
    /// terminal. Without it nothing is wrapped.
    pub progress: bool,
    /// Also sample the dense output at this many evenly spaced times for
    /// a plot ([`Run::plot_rows`]; 0: none). The run's steps do not change:
    /// the interpolant is evaluated between them.
    pub plot_samples: usize,
    /// `--evaluator`: what runs the compiled right-hand side, the
    /// interpreter or machine code ([`CompiledDynamics::use_engine`]).
    pub engine: Engine,
}

impl Default for Request {
    fn default() -> Self {
        Request {
            set: Values::new(),
            init: Values::new(),
            t_end: 1.0,
            method: Method::Dop853,
            rtol: 1e-8,
            atol: 1e-10,
            dt: None,
            points: 101,
            max_steps: crate::limits::DEFAULT_MAX_STEPS,
            stop_when: None,
            functions: Vec::new(),
            baumgarte: 1.0,
            progress: false,
            plot_samples: 0,
            engine: Engine::Auto,
        }
    }
}

/// A finished simulation.
#[derive(Clone, Debug)]
pub struct Run {
    /// Column names: `t`, each q, each q', and `energy` when conservative.
    pub columns: Vec<String>,
    /// One row per output time.
    pub rows: Vec<Vec<f64>>,
    /// With [`Request::plot_samples`]: the rows at the output times and at
    /// the plot's samples, in time order (what `--plot` draws); else empty.
    pub plot_rows: Vec<Vec<f64>>,
    /// The integrator's trajectory, work counters and status.
    pub solution: Solution,
    /// The method used.
    pub method: Method,
    /// Wall time of the integration alone (compilation excluded).
    pub seconds: f64,
    /// Wall time of compiling M, f (and the energy).
    pub compile_seconds: f64,
    /// How q̈ was evaluated, and why ([`CompiledDynamics::best`]).
    pub evaluator: Choice,
    /// What ran the right-hand side (the interpreter or machine code), the
    /// time the machine code took to compile, or why the interpreter ran.
    pub engine: EngineReport,
    /// The largest |g| (or |a·q̇ + b|) over the output rows and the
    /// constraints, for a scene with constraints (their `drift_…` columns).
    pub constraint_drift: Option<f64>,
    /// The column where a NaN or ∞ appeared (the run then ends with
    /// [`Status::NotFinite`] at the last row before it).
    pub not_finite_column: Option<String>,
    /// Whether that value was a NaN (a function outside its domain, 0/0,
    /// ∞·0) rather than ±∞.
    pub not_finite_is_nan: bool,
}

impl Run {
    /// Why the run ended with [`Status::NotFinite`], for its message.
    pub fn not_finite_reason(&self) -> String {
        const NAN: &str = "a function outside its domain (√ or ln of a negative number, asin or acos past ±1), 0/0, ∞·0 or ∞ − ∞";
        const INF: &str = "a division by zero, or a value out of the double range";
        match &self.not_finite_column {
            Some(c) if self.not_finite_is_nan => {
                format!("`{c}` is NaN there: {NAN}; the rows before it are printed")
            }
            Some(c) => format!("`{c}` is infinite there: {INF}; the rows before it are printed"),
            None => {
                format!("q̈ was NaN or infinite within the step after the last row: {NAN}, or {INF}")
            }
        }
    }
}

/// The initial state y0 = (q, q̇) from `--init`: every coordinate, and
/// the velocities, a velocity not given being 0 (as in `modes --init`;
/// [`zero_velocities_note`] names them). A
/// coordinate has no such default: where a run starts is the user's to say.
fn initial_values(names: &[String], req: &Request) -> Result<Vec<f64>, Diagnostic> {
    for k in req.init.keys() {
        let base = k.trim_end_matches('\'');
        if !names.iter().any(|q| q == base) || k.len() - base.len() > 1 {
            return Err(Diagnostic::global(format!(
                "`--init {k}=…`: `{k}` is not a coordinate or a velocity"
            ))
            .with_hint(format!(
                "the coordinates are {}; velocities are written q'",
                names.join(", ")
            ))
            .with_kind(ErrorKind::bad_option("--init")));
        }
    }
    let missing: Vec<&String> = names
        .iter()
        .filter(|q| !req.init.contains_key(*q))
        .collect();
    if !missing.is_empty() {
        let list: Vec<&str> = missing.iter().map(|q| q.as_str()).collect();
        let example: Vec<String> = list.iter().map(|q| format!("{q}=0")).collect();
        return Err(Diagnostic::global(format!(
            "no initial value for the coordinate{} {}",
            if list.len() == 1 { "" } else { "s" },
            list.join(", ")
        ))
        .with_hint(format!(
            "give every coordinate a value (a velocity not given is 0): --init {}",
            example.join(",")
        ))
        .with_kind(ErrorKind::bad_option("--init")));
    }
    let value = |key: &str| req.init.get(key).copied().unwrap_or(0.0);
    let mut y0: Vec<f64> = names.iter().map(|q| value(q)).collect();
    y0.extend(names.iter().map(|q| value(&format!("{q}'"))));
    Ok(y0)
}

/// The note that says which velocities of the coordinates `names` a run
/// starts with at 0 (those `given` is false for), or `None` when every
/// velocity is given.
pub fn zero_velocities_note<'a>(
    names: impl IntoIterator<Item = &'a str>,
    given: impl Fn(&str) -> bool,
) -> Option<String> {
    let zero: Vec<String> = names
        .into_iter()
        .map(|q| format!("{q}'"))
        .filter(|v| !given(v))
        .collect();
    (!zero.is_empty()).then(|| format!("note: velocities not given are 0: {}", zero.join(", ")))
}

/// The options' numbers: a positive, finite `--t-end`, `--dt` and
/// `--max-steps`, 2 to [`crate::limits::MAX_POINTS`] output times,
/// tolerances a double can meet.
fn check_numbers(req: &Request) -> Result<(), Diagnostic> {
    use crate::limits::{MAX_POINTS, MIN_RTOL};
    if !(req.t_end.is_finite() && req.t_end > 0.0) {
        return Err(
            Diagnostic::global(format!("--t-end {} must be a positive number", req.t_end))
                .with_kind(ErrorKind::bad_option("--t-end")),
        );
    }
    if let Some(dt) = req.dt {
        if !(dt.is_finite() && dt > 0.0) {
            return Err(
                Diagnostic::global(format!("--dt {dt} must be a positive number"))
                    .with_hint("the run goes forward from t = 0 to --t-end: --dt 0.01")
                    .with_kind(ErrorKind::bad_option("--dt")),
            );
        }
    }
    if !(2..=MAX_POINTS).contains(&req.points) {
        return Err(Diagnostic::global(format!(
            "--points {} must be from 2 to {MAX_POINTS}",
            req.points
        ))
        .with_hint(
            "the output times include t = 0 and --t-end; for more, run in pieces with --t-end",
        )
        .with_kind(ErrorKind::bad_option("--points")));
    }
    if !(req.baumgarte.is_finite() && req.baumgarte >= 0.0) {
        return Err(Diagnostic::global(format!(
            "--baumgarte {} must be a number ≥ 0",
            req.baumgarte
        ))
        .with_hint("the rate at which constraint drift decays, in 1/time of the scene (0: no stabilization)")
        .with_kind(ErrorKind::bad_option("--baumgarte")));
    }
    if req.max_steps == 0 {
        return Err(Diagnostic::global("--max-steps must be at least 1")
            .with_kind(ErrorKind::bad_option("--max-steps")));
    }
    if !(req.rtol.is_finite() && req.rtol >= MIN_RTOL) {
        return Err(Diagnostic::global(format!(
            "--rtol {} is below what a double can meet ({MIN_RTOL:e}, ten units in the last place)",
            req.rtol
        ))
        .with_hint("--rtol 1e-12 is about as tight as the integrators go")
        .with_kind(ErrorKind::bad_option("--rtol")));
    }
    if !(req.atol.is_finite() && req.atol >= 0.0) {
        return Err(
            Diagnostic::global(format!("--atol {} must be a number ≥ 0", req.atol))
                .with_kind(ErrorKind::bad_option("--atol")),
        );
    }
    Ok(())
}

/// The integrators, each with the kind an unknown name's hint groups them
/// by; each is named once, by [`method_name`].
const METHODS: [(Method, &str); 6] = [
    (Method::Rk4, "explicit"),
    (Method::Dopri5, "explicit"),
    (Method::Dop853, "explicit"),
    (Method::Vern7, "explicit"),
    (Method::Gauss6, "symplectic"),
    (Method::Radau5, "stiff"),
];

/// SciPy's names (`solve_ivp`'s `method`) of methods qdot names otherwise:
/// refused, with a hint naming qdot's.
const SCIPY_NAMES: [(&str, Method); 2] = [("RK45", Method::Dopri5), ("Radau", Method::Radau5)];

/// The method named on the command line (case aside).
pub fn method_by_name(s: &str) -> Result<Method, Diagnostic> {
    let lower = s.to_ascii_lowercase();
    if let Some((m, _)) = METHODS.iter().find(|(m, _)| method_name(*m) == lower) {
        return Ok(*m);
    }
    let mut hint = String::from("the methods are ");
    for (i, (m, kind)) in METHODS.iter().enumerate() {
        hint.push_str(method_name(*m));
        if METHODS.get(i + 1).is_none_or(|next| next.1 != *kind) {
            hint.push_str(&format!(" ({kind})"));
        }
        hint.push_str(match METHODS.len() - i {
            1 => "",
            2 => " and ",
            _ => ", ",
        });
    }
    if let Some((scipy, ours)) = SCIPY_NAMES
        .iter()
        .find(|(scipy, _)| scipy.to_ascii_lowercase() == lower)
    {
        hint = format!("SciPy's {scipy} is `{}` here; {hint}", method_name(*ours));
    }
    Err(Diagnostic::global(format!("unknown method `{s}`"))
        .with_hint(hint)
        .with_kind(ErrorKind::bad_option("--method")))
}

/// The lower-case name of a method, as the command line spells it.
pub fn method_name(m: Method) -> &'static str {
    m.name()
}

pub use crate::scene::given::numeric_initial_values as parse_init;

/// Parse, derive, compile and integrate: `qdot simulate` on the scene
/// source `src`.
pub fn simulate(src: &str, req: &Request) -> Result<Run, Diagnostic> {
    Prepared::new(src, &req.functions)?.run(req)
}

/// A scene ready to simulate: parsed and derived once, then compiled and
/// integrated for as many parameter values and initial states as wanted
/// (the runs of a sweep, [`super::sweep`]).
#[derive(Clone, Debug)]
pub struct Prepared {
    scene: Arc<Scene>,
    lag: crate::mechanics::Lagrange,
    drift: Vec<(String, Expr)>,
    /// The parameters that cannot be 0 here
    /// ([`crate::scene::given::inertial_parameters`]).
    inertial: Vec<String>,
}

/// A [`Prepared`] scene compiled for one set of parameter values: what
/// every run with those values shares (clone it per run).
#[derive(Clone, Debug)]
pub struct Compiled {
    dynamics: CompiledDynamics,
    evaluator: Choice,
    engine: EngineReport,
    energy: Option<Program>,
    drift: Option<Program>,
    event: Option<Program>,
    seconds: f64,
}

impl Prepared {
    /// Parse `src` and derive its equations (`functions`: the definitions
    /// of its given functions of time, `--function s=…`).
    pub fn new(src: &str, functions: &[String]) -> Result<Prepared, Diagnostic> {
        // a large body scene is simulated from its intermediates
        let scene = Scene::read(src, crate::scene::Structure::Auto)?;
        Prepared::of_scene(Arc::new(scene), functions)
    }

    /// Derive the equations of a scene already read (as [`Prepared::new`]
    /// reads it: `Structure::Auto`).
    pub fn of_scene(scene: Arc<Scene>, functions: &[String]) -> Result<Prepared, Diagnostic> {
        let lag = super::given::defined(&scene, scene.lagrange()?, functions)?;
        let inertial = crate::scene::given::inertial_parameters(&scene, &lag);
        let drift = super::constrained::drift(&lag);
        let lag = super::constrained::stabilized(lag)?;
        Ok(Prepared {
            scene,
            lag,
            drift,
            inertial,
        })
    }

    /// The coordinates, in the order of the state y = (q, q̇).
    pub fn coordinates(&self) -> &[String] {
        &self.lag.coordinates
    }

    /// The scene's parameters, in declaration order.
    pub fn parameters(&self) -> Vec<String> {
        self.scene
            .parameters
            .iter()
            .map(|p| p.name.clone())
            .collect()
    }

    /// Compile for `req.set` (and `req.stop_when`, `req.baumgarte`).
    pub fn compile(&self, req: &Request) -> Result<Compiled, Diagnostic> {
        let mut params = crate::scene::given::parameter_map(&self.scene, &req.set, &self.inertial)?;
        if !self.drift.is_empty() {
            params.insert(super::constrained::alpha_var(), req.baumgarte);
        }
        let names = &self.lag.coordinates;
        let start = Instant::now();
        let (mut dynamics, evaluator) =
            best_dynamics(&self.scene, &self.lag, &params).map_err(|e| {
                Diagnostic::global(format!("cannot compile the equations: {e}")).with_kind(e.kind())
            })?;
        // timed apart (`EngineReport::compile_seconds`), so excluded below
        let engine = dynamics.use_engine(req.engine);
        let energy = conserved_quantity(&self.scene, names, &params)?;
        let drift = if self.drift.is_empty() {
            None
        } else {
            let exprs: Vec<Expr> = self.drift.iter().map(|(_, e)| e.clone()).collect();
            Some(
                compile_with(&exprs, &state_inputs(names), &params).map_err(|e| {
                    Diagnostic::global(format!("cannot compile the constraints: {e}"))
                        .with_kind(e.kind())
                })?,
            )
        };
        let event = match &req.stop_when {
            Some(text) => Some(event_program(&self.scene, names, &params, text)?),
            None => None,
        };
        Ok(Compiled {
            dynamics,
            evaluator,
            energy,
            drift,
            event,
            seconds: (start.elapsed().as_secs_f64() - engine.compile_seconds).max(0.0),
            engine,
        })
    }

    /// The errors of `req` that do not depend on the values: a missing or
    /// unknown parameter or initial value, a bad option, a `--stop-when`
    /// that names no quantity of the scene.
    pub fn check(&self, req: &Request) -> Result<(), Diagnostic> {
        let params = crate::scene::given::parameter_map(&self.scene, &req.set, &self.inertial)?;
        initial_values(&self.lag.coordinates, req)?;
        check_numbers(req)?;
        if let Some(text) = &req.stop_when {
            event_program(&self.scene, &self.lag.coordinates, &params, text)?;
        }
        Ok(())
    }

    /// Compile and integrate.
    pub fn run(&self, req: &Request) -> Result<Run, Diagnostic> {
        let compiled = self.compile(req)?;
        self.integrate(compiled, req)
    }

    /// Integrate from `req.init` with what [`Prepared::compile`] made for
    /// `req.set` (only `req.init`, the times, tolerances and method are
    /// read here).
    pub fn integrate(&self, compiled: Compiled, req: &Request) -> Result<Run, Diagnostic> {
        let names = &self.lag.coordinates;
        let y0 = initial_values(names, req)?;
        check_numbers(req)?;
        let Compiled {
            mut dynamics,
            evaluator,
            engine,
            energy,
            drift: drift_program,
            event,
            seconds: compile_seconds,
        } = compiled;
        let evenly = |k: usize| -> Vec<f64> {
            (0..k)
                .map(|i| req.t_end * i as f64 / (k - 1) as f64)
                .collect()
        };
        let requested = evenly(req.points);
        // the plot's samples that are not output times, sorted
        let plot_only: Vec<f64> = if req.plot_samples >= 2 {
            evenly(req.plot_samples)
                .into_iter()
                .filter(|t| requested.binary_search_by(|r| r.total_cmp(t)).is_err())
                .collect()
        } else {
            Vec::new()
        };
        let mut t_out = requested.clone();
        t_out.extend_from_slice(&plot_only);
        t_out.sort_by(f64::total_cmp);
        let opts = IntegratorOptions {
            t0: 0.0,
            t_end: req.t_end,
            rtol: req.rtol,
            atol: req.atol,
            dt: req.dt,
            t_out,
            max_steps: req.max_steps,
        };
        let start = Instant::now();
        #[cfg(feature = "cli")]
        let solution = if req.progress {
            let mut sys = Progress::new(&mut dynamics, opts.t0, opts.t_end);
            run_method(&mut sys, req.method, &y0, &opts, event.as_ref())
        } else {
            run_method(&mut dynamics, req.method, &y0, &opts, event.as_ref())
        };
        // without the `cli` feature there is no bar to draw
        #[cfg(not(feature = "cli"))]
        let solution = run_method(&mut dynamics, req.method, &y0, &opts, event.as_ref());
        let solution = solution.map_err(|e| match e {
            SimError::BadInput(s) => Diagnostic::global(s)
                .with_hint(match req.method {
                    _ if event.is_some() && matches!(req.method, Method::Gauss6 | Method::Radau5) => {
                        "--stop-when finds its time on the dense output: --method dopri5, dop853 or vern7"
                    }
                    Method::Rk4 | Method::Gauss6 => "RK4 and Gauss6 take a fixed step: --dt 0.01",
                    _ => "check --rtol, --atol and --dt",
                })
                .with_kind(ErrorKind::Integration),
            e => Diagnostic::global(e.to_string()).with_kind(ErrorKind::Integration),
        })?;
        let mut seconds = start.elapsed().as_secs_f64();
        // `auto` may have compiled during the run
        let engine = match dynamics.deferred_engine() {
            Some((report, compiled_here)) => {
                if compiled_here {
                    seconds = (seconds - report.compile_seconds).max(0.0);
                }
                report
            }
            None => engine,
        };
        let mut run = self.rows(solution, energy.as_ref(), drift_program.as_ref(), evaluator);
        if req.plot_samples >= 2 {
            let only = |t: f64| plot_only.binary_search_by(|p| p.total_cmp(&t)).is_ok();
            run.plot_rows = run.rows.clone();
            run.rows.retain(|r| !only(r[0]));
        }
        run.method = req.method;
        run.seconds = seconds;
        run.compile_seconds = compile_seconds;
        run.engine = engine;
        Ok(run)
    }

    /// The output rows of `solution`: t, q, q̇, the energy and the
    /// constraints' drift; a non-finite value ends them. (The method and
    /// the times are the caller's to fill in.)
    fn rows(
        &self,
        mut solution: Solution,
        energy: Option<&Program>,
        drift: Option<&Program>,
        evaluator: Choice,
    ) -> Run {
        let names = &self.lag.coordinates;
        let mut columns = vec!["t".to_string()];
        columns.extend(names.iter().cloned());
        columns.extend(names.iter().map(|q| format!("{q}'")));
        if energy.is_some() {
            columns.push("energy".into());
        }
        columns.extend(self.drift.iter().map(|(c, _)| c.clone()));
        let mut max_drift: Option<f64> = drift.map(|_| 0.0);
        let (mut drift_regs, mut drift_out) = match drift {
            Some(p) => (p.registers(), vec![0.0; p.n_outputs()]),
            None => (Vec::new(), Vec::new()),
        };
        let mut rows = Vec::with_capacity(solution.t.len());
        let (mut regs, mut out) = match energy {
            Some(p) => (p.registers(), vec![0.0; p.n_outputs()]),
            None => (Vec::new(), Vec::new()),
        };
        let mut not_finite = None;
        for (t, y) in solution.t.iter().zip(&solution.y) {
            let mut row = Vec::with_capacity(columns.len());
            row.push(*t);
            row.extend_from_slice(y);
            if let Some(p) = energy {
                // the row so far, [t, q…, q̇…], is the program's input
                p.eval(&row, &mut regs, &mut out);
                row.push(out[0]);
            }
            if let Some(p) = drift {
                p.eval(&row[..1 + 2 * names.len()], &mut drift_regs, &mut drift_out);
                for &g in &drift_out {
                    max_drift = max_drift.map(|m| m.max(g.abs()));
                }
                row.extend_from_slice(&drift_out);
            }
            // a NaN or ∞ in any column ends the run there: no row prints one
            if let Some(j) = row.iter().position(|x| !x.is_finite()) {
                not_finite = Some((columns[j].clone(), *t, row[j].is_nan()));
                break;
            }
            rows.push(row);
        }
        if let Some((_, t, _)) = &not_finite {
            solution.status = Status::NotFinite { t: *t };
        }
        Run {
            constraint_drift: max_drift,
            not_finite_is_nan: not_finite.as_ref().is_some_and(|n| n.2),
            not_finite_column: not_finite.map(|(c, _, _)| c),
            columns,
            rows,
            plot_rows: Vec::new(),
            solution,
            method: Method::Dop853,
            seconds: 0.0,
            compile_seconds: 0.0,
            evaluator,
            engine: EngineReport::interpreter(Engine::Auto, 0.0, ""),
        }
    }
}

/// [`integrate`], or [`integrate_with_event`] with the compiled event
/// function over `[t, q…, q̇…]`.
fn run_method<S: System + ?Sized>(
    sys: &mut S,
    method: Method,
    y0: &[f64],
    opts: &IntegratorOptions,
    event: Option<&Program>,
) -> Result<Solution, SimError> {
    match event {
        Some(p) => {
            let (mut regs, mut out, mut input) =
                (p.registers(), vec![0.0; 1], vec![0.0; 1 + y0.len()]);
            let mut g = |t: f64, y: &[f64]| {
                input[0] = t;
                input[1..].copy_from_slice(y);
                p.eval(&input, &mut regs, &mut out);
                out[0]
            };
            integrate_with_event(sys, method, y0, opts, &mut g)
        }
        None => integrate(sys, method, y0, opts),
    }
}

/// `--stop-when lhs = rhs`: lhs − rhs compiled over `[t, q…, q̇…]`.
fn event_program(
    scene: &Scene,
    coordinates: &[String],
    params: &FxHashMap<Var, f64>,
    text: &str,
) -> Result<Program, Diagnostic> {
    let located = |d: Diagnostic| {
        let e = Diagnostic::global(format!("`--stop-when {text}`: {}", d.message))
            .with_kind(ErrorKind::bad_option("--stop-when"));
        match d.hint {
            Some(h) => e.with_hint(h),
            None => e,
        }
    };
    let g = match text.split_once('=') {
        Some((l, r)) => {
            let l = scene.expr(l).map_err(located)?;
            let r = scene.expr(r).map_err(located)?;
            l.sub(&r)
        }
        None => scene.expr(text).map_err(located)?,
    };
    compile_with(&[g], &state_inputs(coordinates), params).map_err(|e| {
        Diagnostic::global(format!("`--stop-when {text}` cannot be evaluated during the run: {e}"))
            .with_hint("use t, the coordinates, their velocities (q') and parameters: --stop-when \"theta = 0\"")
            .with_kind(ErrorKind::bad_option("--stop-when"))
    })
}

/// The Jacobi integral compiled over `[t, q…, q̇…]`, when the scene conserves
/// it (no work, dissipation, forces, loads or torques, and no explicit t).
pub fn conserved_quantity(
    scene: &Scene,
    coordinates: &[String],
    params: &FxHashMap<Var, f64>,
) -> Result<Option<Program>, Diagnostic> {
    let Some(h) = jacobi_integral(scene, coordinates) else {
        return Ok(None);
    };
    let program = compile_with(&[h], &state_inputs(coordinates), params).map_err(|e| {
        Diagnostic::global(format!("cannot compile the energy: {e}")).with_kind(e.kind())
    })?;
    Ok(Some(program))
}

/// The Jacobi integral h = Σ q̇·∂L/∂q̇ − L of the scene, when it conserves
/// it (`mechanics::integrals` decides: no work, dissipation or other
/// force, no t in L directly or through a given function, no constraint
/// that moves or does work).
/// `_coordinates` are the scene's, in the state's order (h is written in
/// their names, so their order does not change it).
pub fn jacobi_integral(scene: &Scene, _coordinates: &[String]) -> Option<Expr> {
    crate::mechanics::integrals::conserved_energy(scene)
        .ok()
        .flatten()
}

// the writers at their first paths, for library users
pub use crate::output::run::{
    csv, json, stats_text, CostJson, EngineJson, EvaluatorJson, RunJson, StatsJson,
};

/// `done`, `event`, `step too small`, `too many steps`, `not finite`.
pub fn status_word(s: &Status) -> &'static str {
    match s {
        Status::Done => "done",
        Status::Event { .. } => "event",
        Status::StepTooSmall { .. } => "step too small",
        Status::TooManySteps { .. } => "too many steps",
        Status::NotFinite { .. } => "not finite",
    }
}

/// The cheapest compiled evaluator of q̈ for `lag` ([`CompiledDynamics::best`]),
/// with the articulated-body recursion a candidate for a tree of rigid
/// bodies read with its kinematics kept.
pub(crate) fn best_dynamics(
    scene: &Scene,
    lag: &crate::mechanics::Lagrange,
    params: &FxHashMap<Var, f64>,
) -> Result<(CompiledDynamics, Choice), crate::simulate::compile::CompileError> {
    let articulated = lag.articulated_accelerations(scene).ok();
    CompiledDynamics::best_among(lag, params, articulated.as_ref())
}
