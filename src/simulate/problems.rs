//! The benchmark problems of the work-precision report, the stress tests and
//! the simulation benches: each a scene with parameter values, an initial
//! state, an end time and, where one exists, the exact solution.
//!
//! | name | scene | reference |
//! |---|---|---|
//! | `oscillator` | damped forced linear oscillator | closed form |
//! | `two_mode` | seed 24.2 (two masses, two springs) | modal solution (qdot's exact modes) |
//! | `pendulum` | pendulum released at 3 rad (172°) | Jacobi elliptic functions |
//! | `cartesian_pendulum` | the same pendulum in x, y with `constraint rod` | the same, mapped to x, y |
//! | `double_pendulum` | 2-link chain | tight-tolerance run |
//! | `chain10` | 10-link chain | tight-tolerance run |
//!
//! Every scene here goes through the same path as `qdot simulate`:
//! [`Problem::dynamics`] compiles its exact equations by
//! [`CompiledDynamics::best`], a scene with constraints after
//! [`constrained::stabilized`] with Baumgarte's α of [`Problem::baumgarte`].

use super::compile::{compile_with, state_inputs, CompiledDynamics};
use super::constrained;
use super::elliptic::pendulum_exact;
use super::run::conserved_quantity;
use crate::diag::Diagnostic;
use crate::expr::atom;
use crate::poly::Var;
use crate::simulate::compile::Program;
use crate::Scene;
use rustc_hash::FxHashMap;

/// Which exact solution a [`Problem`] has.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    Oscillator,
    TwoMode,
    Pendulum,
    CartesianPendulum,
    DoublePendulum,
    Chain10,
}

/// A benchmark problem: a scene, values, an initial state y0 = (q, q̇), and
/// [0, t_end].
#[derive(Clone, Debug)]
pub struct Problem {
    /// Short name (file names, JSON keys): `oscillator`, `two_mode`, …
    pub name: &'static str,
    /// One line for tables and diagram titles.
    pub title: &'static str,
    pub kind: Kind,
    /// The scene's text (the `.qd` language).
    pub scene: String,
    /// Parameter values.
    pub params: Vec<(&'static str, f64)>,
    /// y0 = (q₁ … qₙ, q̇₁ … q̇ₙ) in the scene's coordinate order.
    pub y0: Vec<f64>,
    pub t_end: f64,
    /// Baumgarte's rate α ([`constrained::stabilized`]) for a scene with
    /// constraints, in 1/time of the scene; None without constraints.
    pub baumgarte: Option<f64>,
}

/// The damped forced oscillator m·ẍ + c·ẋ + k·x = F0·cos(p·t)
/// (`examples/forced_oscillator.qd`).
pub const OSCILLATOR: &str = include_str!("../../examples/forced_oscillator.qd");

/// The pendulum of mass m on a massless rod l (`examples/pendulum.qd`).
pub const PENDULUM: &str = include_str!("../../examples/pendulum.qd");

/// The same pendulum in Cartesian coordinates (y up, the pivot at the
/// origin), its rod a holonomic constraint.
pub const CARTESIAN_PENDULUM: &str =
    "# The pendulum of `examples/pendulum.qd` in x, y: the rod is a constraint
coordinates x: length, y: length
parameters m: mass, l: length, g: acceleration
kinetic E = 1/2*m*(x'^2 + y'^2)
potential V = m*g*y
constraint rod: x^2 + y^2 = l^2
";

/// Baumgarte's α of [`Problem::cartesian_pendulum`]: α = ω₀ = √(g/l) = 1,
/// the drift damped on the pendulum's own time scale (the measurements
/// that chose it are in [`Problem::cartesian_pendulum`]).
pub const CARTESIAN_ALPHA: f64 = 1.0;

impl Problem {
    /// The damped forced oscillator: m = 1, k = 4, c = 0.4 (ζ = 0.1),
    /// F0 = 1, p = 1.5; x(0) = 1, ẋ(0) = 0; t ∈ [0, 20].
    pub fn oscillator() -> Problem {
        Problem {
            name: "oscillator",
            title: "damped forced oscillator (closed form)",
            kind: Kind::Oscillator,
            scene: OSCILLATOR.to_string(),
            params: vec![("m", 1.0), ("k", 4.0), ("c", 0.4), ("F0", 1.0), ("p", 1.5)],
            y0: vec![1.0, 0.0],
            t_end: 20.0,
            baumgarte: None,
        }
    }

    /// Seed 24.2 with m = 1, k = 6, R = 1/2 (ω₁² = 1, ω₂² = 6);
    /// x = (1, 0), ẋ = (0.1, −0.2); t ∈ [0, 20].
    pub fn two_mode() -> Problem {
        Problem {
            name: "two_mode",
            title: "seed 24.2, two modes (modal solution)",
            kind: Kind::TwoMode,
            scene: include_str!("../../examples/seed_24_2.qd").to_string(),
            params: vec![("m", 1.0), ("k", 6.0), ("R", 0.5)],
            y0: vec![1.0, 0.0, 0.1, -0.2],
            t_end: 20.0,
            baumgarte: None,
        }
    }

    /// The pendulum with g/l = 1 released from rest at θ = 3 rad (k =
    /// sin 1.5, period 4K(k²) ≈ 15.6); t ∈ [0, 20].
    pub fn pendulum() -> Problem {
        Problem {
            name: "pendulum",
            title: "pendulum at 3 rad (Jacobi elliptic functions)",
            kind: Kind::Pendulum,
            scene: PENDULUM.to_string(),
            params: vec![("m", 1.0), ("l", 1.0), ("g", 1.0)],
            y0: vec![3.0, 0.0],
            t_end: 20.0,
            baumgarte: None,
        }
    }

    /// The pendulum of [`Problem::pendulum`] (m = l = g = 1, released from
    /// rest at θ = 3 rad) in Cartesian coordinates, the rod
    /// x² + y² = l² a constraint: y0 = (l sin θ, −l cos θ, 0, 0);
    /// t ∈ [0, 20]. Its equations are the index-reduced augmented system
    /// with Baumgarte's stabilization at α = [`CARTESIAN_ALPHA`], as
    /// `qdot simulate` integrates it, and its exact solution is the angle
    /// pendulum's mapped to x, y.
    ///
    /// α = 1 was chosen from DOP853 runs at rtol = atol = 1e-10 (max |g|
    /// over the accepted steps, error at the final time, steps):
    ///
    /// | α | [0, 20]: max \|g\| | error | steps | [0, 1616] (100 periods): max \|g\| | error | steps |
    /// |---|---|---|---|---|---|---|
    /// | 0 | 6.8e-9 | 1.4e-6 | 100 | 4.1e-5 | 2.9e-2 | 8069 |
    /// | 1 | 4.0e-10 | 6.2e-7 | 107 | 4.2e-10 | 1.8e-4 | 8665 |
    /// | 10 | 5.5e-13 | 2.2e-10 | 725 | 5.5e-13 | 6.7e-8 | 58541 |
    ///
    /// Without stabilization the drift grows with t; with α = 1 it stays
    /// where the first periods put it, at the cost of α = 0 (0.8 to 1.2
    /// times its time at equal final error on [0, 20], for Dopri5, DOP853,
    /// Vern7 and Radau5). α = 10 holds g smaller still, but the explicit
    /// methods take 3 to 7 times the steps at each tolerance, and at equal
    /// final error every method is 1.6 to 4 times slower than at α = 1.
    /// The report measures the three (`benches/work_precision.rs`).
    pub fn cartesian_pendulum() -> Problem {
        let (m, l, g, theta0) = (1.0, 1.0, 1.0, 3.0f64);
        let (s, c) = theta0.sin_cos();
        Problem {
            name: "cartesian_pendulum",
            title: "pendulum at 3 rad in x, y with a constraint (Jacobi elliptic functions)",
            kind: Kind::CartesianPendulum,
            scene: CARTESIAN_PENDULUM.to_string(),
            params: vec![("m", m), ("l", l), ("g", g)],
            y0: vec![l * s, -l * c, 0.0, 0.0],
            t_end: 20.0,
            baumgarte: Some(CARTESIAN_ALPHA),
        }
    }

    /// The double pendulum (`gallery::pendulum_chain(2)`), m = l = 1,
    /// g = 9.81, released from rest at (0.5, 1.0); t ∈ [0, 10].
    pub fn double_pendulum() -> Problem {
        Problem {
            name: "double_pendulum",
            title: "double pendulum (tight reference)",
            kind: Kind::DoublePendulum,
            scene: crate::gallery::pendulum_chain(2),
            params: vec![("m", 1.0), ("l", 1.0), ("g", 9.81)],
            y0: vec![0.5, 1.0, 0.0, 0.0],
            t_end: 10.0,
            baumgarte: None,
        }
    }

    /// The 10-link chain, m = l = 1, g = 9.81, released from rest at
    /// qᵢ = 0.3 + 0.02·i (i = 0 … 9); t ∈ [0, 10].
    pub fn chain10() -> Problem {
        let mut y0: Vec<f64> = (0..10).map(|i| 0.3 + 0.02 * i as f64).collect();
        y0.extend([0.0; 10]);
        Problem {
            name: "chain10",
            title: "10-link pendulum chain (tight reference)",
            kind: Kind::Chain10,
            scene: crate::gallery::particle_chain(10),
            params: vec![("m", 1.0), ("l", 1.0), ("g", 9.81)],
            y0,
            t_end: 10.0,
            baumgarte: None,
        }
    }

    /// Every problem, in report order.
    pub fn all() -> Vec<Problem> {
        vec![
            Problem::oscillator(),
            Problem::two_mode(),
            Problem::pendulum(),
            Problem::cartesian_pendulum(),
            Problem::double_pendulum(),
            Problem::chain10(),
        ]
    }

    /// The value of parameter `name`.
    pub fn param(&self, name: &str) -> f64 {
        self.params
            .iter()
            .find(|(k, _)| *k == name)
            .map(|&(_, v)| v)
            .unwrap_or(f64::NAN)
    }

    /// The parameter values keyed by atom, as [`CompiledDynamics::new`] takes
    /// them, with Baumgarte's α ([`constrained::alpha_var`]) when the
    /// problem has one.
    pub fn param_map(&self) -> FxHashMap<Var, f64> {
        let mut map: FxHashMap<Var, f64> = self
            .params
            .iter()
            .map(|&(k, v)| (atom::param(k), v))
            .collect();
        if let Some(alpha) = self.baumgarte {
            map.insert(constrained::alpha_var(), alpha);
        }
        map
    }

    /// The scene read and its equations compiled as `qdot simulate` does
    /// (M and f, the exact accelerations, or the articulated-body
    /// recursion, whichever is estimated cheapest); a scene
    /// with constraints as the stabilized augmented system
    /// ([`constrained::stabilized`], α from [`Problem::baumgarte`]).
    pub fn dynamics(&self) -> Result<CompiledDynamics, Diagnostic> {
        let scene = Scene::read(&self.scene, crate::scene::Structure::Auto)?;
        let lag = constrained::stabilized(scene.lagrange()?)?;
        super::run::best_dynamics(&scene, &lag, &self.param_map())
            .map(|(d, _)| d)
            .map_err(|e| {
                Diagnostic::global(format!("cannot compile {}: {e}", self.name)).with_kind(e.kind())
            })
    }

    /// The conserved Jacobi integral compiled over `[t, q…, q̇…]`, when the
    /// scene conserves one (every problem here but the oscillator).
    pub fn energy(&self) -> Result<Option<Program>, Diagnostic> {
        let scene = Scene::parse(&self.scene)?;
        let lag = scene.lagrange()?;
        conserved_quantity(&scene, &lag.coordinates, &self.param_map())
    }

    /// The scene's constraints g(q, t) (a·q̇ + b for a velocity
    /// constraint) compiled over `[t, q…, q̇…]`, one output each, as the
    /// `drift_…` columns of `qdot simulate`; None without constraints.
    pub fn constraints(&self) -> Result<Option<Program>, Diagnostic> {
        let scene = Scene::parse(&self.scene)?;
        let lag = scene.lagrange()?;
        let drift = constrained::drift(&lag);
        if drift.is_empty() {
            return Ok(None);
        }
        let exprs: Vec<_> = drift.into_iter().map(|(_, e)| e).collect();
        compile_with(&exprs, &state_inputs(&lag.coordinates), &self.param_map())
            .map(Some)
            .map_err(|e| {
                Diagnostic::global(format!("cannot compile the constraints: {e}"))
                    .with_kind(e.kind())
            })
    }

    /// The exact state at `t`, for the problems that have a closed form.
    pub fn exact(&self, t: f64) -> Option<Vec<f64>> {
        match self.kind {
            Kind::Oscillator => Some(self.oscillator_exact(t)),
            Kind::TwoMode => Some(self.two_mode_exact(t)),
            Kind::Pendulum => {
                let w2 = self.param("g") / self.param("l");
                let (th, om) = pendulum_exact(self.y0[0], w2, t);
                Some(vec![th, om])
            }
            Kind::CartesianPendulum => {
                // released from rest at θ0 = atan2(x, −y)
                let l = self.param("l");
                let theta0 = self.y0[0].atan2(-self.y0[1]);
                let (th, om) = pendulum_exact(theta0, self.param("g") / l, t);
                let (s, c) = th.sin_cos();
                Some(vec![l * s, -l * c, l * c * om, l * s * om])
            }
            Kind::DoublePendulum | Kind::Chain10 => None,
        }
    }

    /// x = e^{−γt}(C₁ cos ω_d t + C₂ sin ω_d t) + A cos pt + B sin pt with
    /// γ = c/2m, ω_d = √(k/m − γ²) (underdamped), (A, B) the steady state.
    fn oscillator_exact(&self, t: f64) -> Vec<f64> {
        let (m, k, c, f0, p) = (
            self.param("m"),
            self.param("k"),
            self.param("c"),
            self.param("F0"),
            self.param("p"),
        );
        // (k − m p²)·A + c p·B = F0,  −c p·A + (k − m p²)·B = 0
        let a11 = k - m * p * p;
        let cp = c * p;
        let det = a11 * a11 + cp * cp;
        let (a, b) = (f0 * a11 / det, f0 * cp / det);
        let gamma = c / (2.0 * m);
        let wd = (k / m - gamma * gamma).sqrt();
        let (x0, v0) = (self.y0[0], self.y0[1]);
        // x(0) = C1 + A, ẋ(0) = −γ C1 + ω_d C2 + p B
        let c1 = x0 - a;
        let c2 = (v0 + gamma * c1 - p * b) / wd;
        let e = (-gamma * t).exp();
        let (s, co) = (wd * t).sin_cos();
        let (sp, cpt) = (p * t).sin_cos();
        let x = e * (c1 * co + c2 * s) + a * cpt + b * sp;
        let v =
            e * (-gamma * (c1 * co + c2 * s) + wd * (-c1 * s + c2 * co)) - a * p * sp + b * p * cpt;
        vec![x, v]
    }

    /// q(t) = Σ uᵢ·(aᵢ cos ωᵢt + bᵢ/ωᵢ sin ωᵢt) over qdot's exact modes of
    /// seed 24.2: ω₁² = k/(6m), u₁ = (1, 4/3); ω₂² = k/m, u₂ = (1, −2).
    fn two_mode_exact(&self, t: f64) -> Vec<f64> {
        let (m, k) = (self.param("m"), self.param("k"));
        let w = [(k / (6.0 * m)).sqrt(), (k / m).sqrt()];
        let mu = [4.0 / 3.0, -2.0];
        // [1 1; μ1 μ2]·(c1, c2) = (z1, z2)
        let split = |z1: f64, z2: f64| {
            let c2 = (z2 - mu[0] * z1) / (mu[1] - mu[0]);
            [z1 - c2, c2]
        };
        let a = split(self.y0[0], self.y0[1]);
        let b = split(self.y0[2], self.y0[3]);
        let mut y = vec![0.0; 4];
        for i in 0..2 {
            let (s, c) = (w[i] * t).sin_cos();
            let amp = a[i] * c + b[i] / w[i] * s;
            let vel = -a[i] * w[i] * s + b[i] * c;
            y[0] += amp;
            y[1] += mu[i] * amp;
            y[2] += vel;
            y[3] += mu[i] * vel;
        }
        y
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::simulate::{integrate, IntegratorOptions, Method, System};

    /// Every closed form satisfies its scene's equations: the residual of
    /// y' = F(t, y) by central differences of `exact` is at the level of
    /// the difference formula's error.
    #[test]
    fn closed_forms_satisfy_the_compiled_equations() {
        for p in Problem::all() {
            if p.exact(0.0).is_none() {
                continue;
            }
            let mut dyn_ = p.dynamics().expect("compiles");
            let n = p.y0.len();
            assert_eq!(p.exact(0.0).unwrap().len(), n, "{}", p.name);
            for (a, b) in p.exact(0.0).unwrap().iter().zip(&p.y0) {
                assert!((a - b).abs() < 1e-14, "{}: y(0) {a} vs {b}", p.name);
            }
            let mut dy = vec![0.0; n];
            for &t in &[0.3, 1.7, 6.1, 13.9] {
                let h = 1e-4;
                let y = p.exact(t).unwrap();
                let (yp, ym) = (p.exact(t + h).unwrap(), p.exact(t - h).unwrap());
                dyn_.rhs(t, &y, &mut dy);
                for i in 0..n {
                    let fd = (yp[i] - ym[i]) / (2.0 * h);
                    assert!(
                        (fd - dy[i]).abs() < 1e-6 * (1.0 + dy[i].abs()),
                        "{} t={t} i={i}: {fd} vs {}",
                        p.name,
                        dy[i]
                    );
                }
            }
        }
    }

    /// A tight DOP853 run lands on each closed form.
    #[test]
    fn tight_runs_land_on_the_closed_forms() {
        for p in Problem::all() {
            let Some(exact) = p.exact(p.t_end) else {
                continue;
            };
            let mut sys = p.dynamics().expect("compiles");
            let opts = IntegratorOptions {
                t_end: p.t_end,
                rtol: 1e-12,
                atol: 1e-12,
                ..IntegratorOptions::default()
            };
            let sol = integrate(&mut sys, Method::Dop853, &p.y0, &opts).expect("runs");
            let y = sol.y.last().expect("a state");
            for (a, b) in y.iter().zip(&exact) {
                assert!((a - b).abs() < 1e-8, "{}: {a} vs {b}", p.name);
            }
        }
    }

    #[test]
    fn conservative_problems_have_an_energy() {
        for p in Problem::all() {
            let e = p.energy().expect("compiles");
            assert_eq!(e.is_some(), p.kind != Kind::Oscillator, "{}", p.name);
        }
    }
}
