//! Parametric excitation: the stability of a motion whose linearized
//! equations have periodic coefficients, by Floquet theory.
//!
//! About a reference q0 that is a motion for all t, the scene's equations
//! linearize to M(t)·q̈ + C(t)·q̇ + K(t)·q = 0 ([`qdot_mechanics::solve::linearize`],
//! exact). With x = (q, q̇) that is x' = A(t)·x, A = [[0, I], [−M⁻¹K,
//! −M⁻¹C]], of period T. The monodromy matrix Φ(T) (the solution matrix
//! after one period, Φ(0) = I) decides the stability: its eigenvalues, the
//! Floquet multipliers μ, give x(t + T) = μ·x(t) for the Floquet solutions
//! (Hairer, Nørsett & Wanner, Solving ODEs I, I.14; Nayfeh & Mook,
//! Nonlinear Oscillations, 5.2).
//!
//! * [`period`]: T from the time dependence (sin/cos of ω·t, commensurate
//!   frequencies), exactly.
//! * [`monodromy`]: Φ(T) integrated by DOP853 at two tolerances, the
//!   multipliers, what their difference certifies, and the verdict.
//!
//! The coefficients are compiled once ([`crate::compile::compile`]) with
//! t and the parameters as inputs, so a chart over two parameters reuses
//! one program.

pub mod monodromy;
pub mod period;

use crate::compile::{compile, Program};
use crate::diag::{Diagnostic, ErrorKind};
use crate::expr::atom::{self, Atom};
use crate::expr::Expr;
use crate::poly::Var;
use crate::scene::Scene;
use qdot_mechanics::solve::linearize::{linearize, Reference};
use rustc_hash::FxHashMap;

pub use monodromy::{Floquet, Multiplier, Verdict};

/// What `qdot floquet` analyses.
#[derive(Clone, Debug, Default)]
pub struct FloquetRequest {
    /// `--at q=value,…`: the reference position (every q = 0 without it).
    pub at: Option<String>,
    /// `--function s=EXPR`: the definition of each given function of time.
    pub functions: Vec<String>,
    /// `--period T`: the period, when it is not found from the time
    /// dependence (then checked on the compiled coefficients).
    pub period: Option<f64>,
    /// `--max-steps N`: the steps one integration over the period may take
    /// ([`crate::limits::DEFAULT_MAX_STEPS`] when `None`).
    pub max_steps: Option<usize>,
}

/// A scene linearized about its reference, with the coefficients compiled:
/// ready for [`Prepared::analyse`] at any parameter values.
#[derive(Clone, Debug)]
pub struct Prepared {
    /// The (independent) coordinates, in declaration order.
    pub coordinates: Vec<String>,
    /// The reference position.
    pub at: Vec<Expr>,
    /// M, C and K, exact (functions of t and the parameters).
    pub mass: Vec<Vec<Expr>>,
    /// C = ∂R/∂q̇.
    pub damping: Vec<Vec<Expr>>,
    /// K = ∂R/∂q.
    pub stiffness: Vec<Vec<Expr>>,
    /// The fundamental angular frequency Ω (T = 2π/|Ω|), exact; `None`
    /// when the period was given.
    pub frequency: Option<Expr>,
    /// The given period (`--period`).
    pub given_period: Option<f64>,
    /// The steps one integration over the period may take.
    pub max_steps: usize,
    /// Whether the linearized equations are the Euler–Lagrange equations of
    /// a quadratic Lagrangian ([`is_lagrangian`]): then the multipliers
    /// come in pairs μ, 1/μ̄ and simple ones on the unit circle stay there.
    pub lagrangian: bool,
    /// The parameters the program reads, in its input order (after t).
    pub parameters: Vec<Var>,
    /// M, C, K (row-major, n² each), then Ω when found, of (t, parameters).
    program: Program,
}

/// Read the reference, define the given functions, linearize (under the
/// scene's assumptions) and compile.
pub fn prepare(scene: &Scene, req: &FloquetRequest) -> Result<Prepared, Diagnostic> {
    let at = match &req.at {
        Some(a) => Some(scene.coordinate_values(a)?),
        None => None,
    };
    if let (Some(vals), Some(text)) = (&at, &req.at) {
        if vals.iter().any(Expr::is_time_dependent) {
            return Err(Diagnostic::global(format!(
                "`--at {text}`: the reference is a constant position, and this changes with time"
            ))
            .with_hint("give the coordinates constant values: --at theta=pi")
            .with_kind(ErrorKind::bad_option("--at")));
        }
    }
    let defs = crate::given::definitions(scene, &req.functions, "for its Floquet multipliers")?;
    scene.assumptions_required("the Floquet analysis")?;
    check_motion(scene, at.as_deref(), &defs)?;
    let lin = linearize(scene, &Reference::at(at.as_deref()).time_varying())?;
    let define = |rows: &[Vec<Expr>]| -> Result<Vec<Vec<Expr>>, Diagnostic> {
        rows.iter()
            .map(|r| {
                r.iter()
                    .map(|e| crate::given::substitute(e, &defs))
                    .collect()
            })
            .collect()
    };
    let mass = define(&lin.mass)?;
    let damping = define(&lin.damping)?;
    let stiffness = define(&lin.stiffness)?;
    for (k, f) in lin.forcing.iter().enumerate() {
        let f = crate::given::substitute(f, &defs)?;
        if !f.is_zero() {
            return Err(not_a_motion(&lin.coordinates, &lin.at, k, &f));
        }
    }
    let t = atom::time();
    let all: Vec<&Expr> = mass
        .iter()
        .chain(&damping)
        .chain(&stiffness)
        .flatten()
        .collect();
    if !all.iter().any(|e| e.depends_on(t)) {
        return Err(Diagnostic::global(
            "the linearized coefficients do not change with time: there is no parametric excitation",
        )
        .with_hint("`qdot modes` gives the small oscillations about an equilibrium").with_kind(ErrorKind::NothingToSolve));
    }
    let frequency = match req.period {
        Some(p) if p.is_finite() && p > 0.0 => None,
        Some(p) => {
            return Err(Diagnostic::global(format!(
                "--period {} must be a positive number",
                monodromy::shortest(p)
            ))
            .with_kind(ErrorKind::bad_option("--period")))
        }
        None => Some(period::fundamental(&all)?),
    };
    let mut parameters: Vec<Var> = Vec::new();
    for e in all.iter().copied().chain(frequency.as_ref()) {
        for v in e.vars() {
            for w in std::iter::once(v).chain(atom::inner_atoms(v).iter().copied()) {
                if matches!(atom::atom(w), Atom::Param(_)) && !parameters.contains(&w) {
                    parameters.push(w);
                }
            }
        }
    }
    parameters.sort_unstable_by_key(|&v| name_of(v));
    let mut outputs: Vec<Expr> = all.iter().map(|&e| e.clone()).collect();
    outputs.extend(frequency.clone());
    let mut inputs = vec![t];
    inputs.extend(&parameters);
    let program = compile(&outputs, &inputs).map_err(|e| {
        Diagnostic::global(format!("cannot compile the linearized coefficients: {e}"))
            .with_kind(e.kind())
    })?;
    let lagrangian = is_lagrangian(&mass, &damping, &stiffness);
    Ok(Prepared {
        coordinates: lin.coordinates,
        at: lin.at,
        mass,
        damping,
        stiffness,
        frequency,
        given_period: req.period,
        max_steps: req.max_steps.unwrap_or(crate::limits::DEFAULT_MAX_STEPS),
        lagrangian,
        parameters,
        program,
    })
}

/// An error unless the reference `at` (every q = 0 when `None`) is a
/// motion of the scene for all t, its given functions defined by `defs`:
/// the forces left there must vanish. (With constraints the multipliers
/// that hold the reference come first: [`linearize`] checks their constant
/// part, [`prepare`] the rest.)
fn check_motion(
    scene: &Scene,
    at: Option<&[Expr]>,
    defs: &FxHashMap<&str, Expr>,
) -> Result<(), Diagnostic> {
    if !scene.constraints.is_empty() {
        return Ok(());
    }
    let l = scene.lagrange()?;
    let zero = vec![Expr::zero(); l.coordinates.len()];
    let q0 = at.unwrap_or(&zero);
    let mut point: FxHashMap<Var, Expr> = FxHashMap::default();
    for (c, v) in l.coordinates.iter().zip(q0) {
        point.insert(atom::coord(c, 0), v.clone());
        point.insert(atom::coord(c, 1), Expr::zero());
        point.insert(atom::coord(c, 2), Expr::zero());
    }
    for (k, eq) in l.equations.iter().enumerate() {
        let f = eq
            .rhs
            .sub(&eq.lhs)
            .subs_many(&point)
            .map_err(|m| Diagnostic::global(m.message).with_kind(ErrorKind::Undefined))?;
        let f = crate::given::substitute(&f, defs)?;
        if !f.is_zero() {
            return Err(not_a_motion(&l.coordinates, q0, k, &f));
        }
    }
    Ok(())
}

/// The error for a reference that is not a motion: the force left on
/// coordinate `k` changes with time.
fn not_a_motion(names: &[String], at: &[Expr], k: usize, f: &Expr) -> Diagnostic {
    let q0: Vec<String> = names
        .iter()
        .zip(at)
        .map(|(c, v)| format!("{c} = {}", crate::expr::print::unicode(v)))
        .collect();
    Diagnostic::global(format!(
        "{} is not a motion of the scene: the force on `{}` there is {} ≠ 0",
        q0.join(", "),
        names[k],
        crate::expr::print::unicode(f)
    ))
    .with_hint(
        "Floquet theory linearizes about a motion: choose --at where the forces vanish at every t",
    )
    .with_kind(ErrorKind::NoEquilibrium)
}

/// Whether M·q̈ + C·q̇ + K·q = 0 are the Euler–Lagrange equations of
/// L₂ = ½·q̇ᵀMq̇ + q̇ᵀGq + ½·qᵀPq for some G and symmetric P: then
/// C = Ṁ + G − Gᵀ and K = Ġ − P, so M is symmetric, C − Ṁ antisymmetric
/// and, with G = ½(C − Ṁ), K − ½(Ċ − M̈) symmetric. Exact.
pub fn is_lagrangian(m: &[Vec<Expr>], c: &[Vec<Expr>], k: &[Vec<Expr>]) -> bool {
    let n = m.len();
    let g = |i: usize, j: usize| c[i][j].sub(&m[i][j].dt());
    // 2·(K − ½(Ċ − M̈)), symmetric when K − ½(Ċ − M̈) is
    let p = |i: usize, j: usize| {
        k[i][j]
            .add(&k[i][j])
            .sub(&c[i][j].dt().sub(&m[i][j].dt().dt()))
    };
    (0..n).all(|i| {
        (0..n).all(|j| {
            m[i][j].equals(&m[j][i]) && g(i, j).add(&g(j, i)).is_zero() && p(i, j).equals(&p(j, i))
        })
    })
}

/// An atom's name as the input syntax writes it.
fn name_of(v: Var) -> String {
    crate::expr::print::input(&Expr::var(v))
}

impl Prepared {
    /// Parameter values by name (`--set`, with a grid point's values) as
    /// [`Prepared::analyse`] takes them, checked as every numeric command
    /// checks them ([`crate::scene::given::parameter_map`]): every
    /// parameter of `scene` given, no other name, signs and `assume` facts
    /// kept, and not 0 where 0 makes M singular or the period infinite.
    pub fn parameter_map(
        &self,
        scene: &Scene,
        set: &crate::algebra::sign::Values,
    ) -> Result<FxHashMap<Var, f64>, Diagnostic> {
        crate::scene::given::parameter_map(scene, set, &self.inertial_parameters(scene))
    }

    /// The parameters of `scene` in M or in the coefficients' frequency.
    pub fn inertial_parameters(&self, scene: &Scene) -> Vec<String> {
        scene
            .parameters
            .iter()
            .map(|p| p.name.clone())
            .filter(|p| {
                let v = atom::param(p);
                self.mass
                    .iter()
                    .flatten()
                    .chain(&self.frequency)
                    .any(|e| e.depends_on(v))
            })
            .collect()
    }

    /// The number of coordinates.
    pub fn n(&self) -> usize {
        self.coordinates.len()
    }

    /// The program's parameter inputs from `values`: an error names a
    /// parameter without a value.
    pub fn inputs(&self, values: &FxHashMap<Var, f64>) -> Result<Vec<f64>, Diagnostic> {
        let mut missing = Vec::new();
        let mut out = Vec::with_capacity(self.parameters.len());
        for &p in &self.parameters {
            match values.get(&p) {
                Some(&v) => out.push(v),
                None => {
                    missing.push(name_of(p));
                    out.push(0.0);
                }
            }
        }
        if missing.is_empty() {
            return Ok(out);
        }
        let example: Vec<String> = missing.iter().map(|m| format!("{m}=1")).collect();
        Err(Diagnostic::global(format!(
            "no value for the parameter{} {}",
            if missing.len() > 1 { "s" } else { "" },
            missing.join(", ")
        ))
        .with_hint(format!(
            "give every parameter a value: --set {}",
            example.join(",")
        ))
        .with_kind(ErrorKind::bad_option("--set")))
    }

    /// The period at these parameter inputs ([`Prepared::inputs`]).
    pub fn period(&self, params: &[f64]) -> Result<f64, Diagnostic> {
        if let Some(p) = self.given_period {
            return Ok(p);
        }
        let mut out = vec![0.0; self.program.n_outputs()];
        self.eval(0.0, params, &mut out);
        let omega = out[out.len() - 1].abs();
        if !(omega.is_finite() && omega > 0.0) {
            let w = self.frequency.as_ref().map(crate::expr::print::unicode);
            return Err(Diagnostic::global(format!(
                "the coefficients' angular frequency {} is {} at these values: no period",
                w.unwrap_or_default(),
                monodromy::shortest(omega)
            ))
            .with_hint("give the parameters values with a nonzero frequency")
            .with_kind(ErrorKind::Undefined));
        }
        Ok(2.0 * std::f64::consts::PI / omega)
    }

    /// The compiled outputs (M, C, K row-major, then Ω) at time t.
    pub(crate) fn eval(&self, t: f64, params: &[f64], out: &mut [f64]) {
        let mut inputs = Vec::with_capacity(params.len() + 1);
        inputs.push(t);
        inputs.extend_from_slice(params);
        let mut regs = self.program.registers();
        self.program.eval(&inputs, &mut regs, out);
    }

    /// An error unless the coefficients repeat after the given period
    /// (compared at a few times, to 1e-9 relative).
    pub(crate) fn check_given_period(&self, params: &[f64], period: f64) -> Result<(), Diagnostic> {
        let k = self.program.n_outputs();
        let (mut a, mut b) = (vec![0.0; k], vec![0.0; k]);
        for i in 0..7 {
            let t = (i as f64 + 0.37) * period / 7.0;
            self.eval(t, params, &mut a);
            self.eval(t + period, params, &mut b);
            if a.iter()
                .zip(&b)
                .any(|(x, y)| (x - y).abs() > 1e-9 * (1.0 + x.abs()))
            {
                return Err(Diagnostic::global(format!(
                    "the linearized coefficients do not repeat after --period {}: they differ at t = {} and t + T",
                    monodromy::shortest(period),
                    qdot_mechanics::solve::certify::significant(t, 7)
                ))
                .with_hint("give the period of the time dependence, or leave --period out to find it")
                .with_kind(ErrorKind::bad_option("--period")));
            }
        }
        Ok(())
    }

    /// The compiled program.
    pub(crate) fn program(&self) -> &Program {
        &self.program
    }

    /// The multipliers and the verdict at the parameter values `values`.
    pub fn analyse(&self, values: &FxHashMap<Var, f64>) -> Result<Floquet, Diagnostic> {
        let params = self.inputs(values)?;
        monodromy::analyse(self, &params)
    }

    /// The value of parameter `name` between `lo` and `hi` where the
    /// verdict changes from unstable to not unstable (or back), by
    /// bisection to the last bit the verdict can resolve; the other
    /// parameters from `values`. An error when the verdicts at the ends
    /// do not differ.
    pub fn boundary(
        &self,
        values: &FxHashMap<Var, f64>,
        name: &str,
        lo: f64,
        hi: f64,
    ) -> Result<f64, Diagnostic> {
        let mut values = values.clone();
        let p = atom::param(name);
        let mut unstable = |x: f64| -> Result<bool, Diagnostic> {
            values.insert(p, x);
            Ok(self.analyse(&values)?.verdict == Verdict::Unstable)
        };
        let (mut a, mut b) = (lo, hi);
        let at_a = unstable(a)?;
        if at_a == unstable(b)? {
            return Err(Diagnostic::global(format!(
                "the verdict is the same at {name} = {} and {name} = {}: no boundary to bisect",
                monodromy::shortest(lo),
                monodromy::shortest(hi)
            ))
            .with_kind(ErrorKind::NothingToSolve));
        }
        for _ in 0..200 {
            let mid = 0.5 * (a + b);
            if mid <= a.min(b) || mid >= a.max(b) {
                break;
            }
            if unstable(mid)? == at_a {
                a = mid;
            } else {
                b = mid;
            }
        }
        Ok(0.5 * (a + b))
    }
}
