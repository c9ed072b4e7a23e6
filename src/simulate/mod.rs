//! Numerical simulation: the exact equations compiled to f64 and integrated.
//!
//! The data's path ends here: [`crate::mechanics`] gives M(q, t)·q̈ = f(q, q̇, t)
//! exactly; this module integrates the first-order system y = (q, q̇) with
//! our own methods. Everything here is floating point, and nothing from it
//! ever flows back into an exact result.
//!
//! * [`System`]: a first-order ODE y' = F(t, y) (what every method integrates).
//! * [`Options`], [`Stats`], [`Solution`]: the common inputs and outputs.
//! * `explicit`: RK4, Dormand–Prince 5(4), DOP853, Verner 7(6) — dense
//!   output, Hairer's step-size control, stiffness detection, events.
//! * `implicit`: Radau IIA (order 5, L-stable), Gauss–Legendre (symplectic).
//! * `elliptic`: Jacobi elliptic functions (exact pendulum references).

pub mod compile;

/// A first-order system y' = F(t, y) of fixed dimension.
pub trait System {
    /// The dimension of y.
    fn dim(&self) -> usize;
    /// Write F(t, y) into `dy` (`dy.len() == y.len() == dim()`).
    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]);
    /// The Jacobian ∂F/∂y at (t, y), row-major into `jac` (dim × dim).
    /// Return `false` when the system has no analytic Jacobian: implicit
    /// methods then use forward differences (counted in `Stats::rhs_evals`).
    fn jacobian(&mut self, _t: f64, _y: &[f64], _jac: &mut [f64]) -> bool {
        false
    }
}

/// A closure as a [`System`]: `FnSystem { dim, f: |t, y, dy| … }`.
pub struct FnSystem<F: FnMut(f64, &[f64], &mut [f64])> {
    pub dim: usize,
    pub f: F,
}

impl<F: FnMut(f64, &[f64], &mut [f64])> System for FnSystem<F> {
    fn dim(&self) -> usize {
        self.dim
    }
    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) {
        (self.f)(t, y, dy)
    }
}

/// Integration methods.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    /// Classical Runge–Kutta, order 4, fixed step.
    Rk4,
    /// Dormand–Prince 5(4), adaptive, dense output of order 4.
    Dopri5,
    /// Dormand–Prince 8(5,3) (Hairer's DOP853), adaptive, dense output of order 7.
    Dop853,
    /// Verner's 7(6) "most efficient" pair, adaptive, for tight tolerances.
    Vern7,
    /// Gauss–Legendre, 3 stages, order 6: symplectic, fixed step.
    Gauss6,
    /// Radau IIA, 3 stages, order 5: L-stable, adaptive, for stiff systems.
    Radau5,
}

/// What to integrate and how precisely.
#[derive(Clone, Debug)]
pub struct Options {
    pub t0: f64,
    pub t_end: f64,
    /// Relative and absolute tolerances of adaptive methods.
    pub rtol: f64,
    pub atol: f64,
    /// The step of fixed-step methods (RK4, Gauss6); the initial step of
    /// adaptive ones when `Some` (else chosen by Hairer's starting-step rule).
    pub dt: Option<f64>,
    /// Times at which to record the solution (by dense output for adaptive
    /// methods); empty: record every accepted step.
    pub t_out: Vec<f64>,
    /// Give up after this many steps (accepted + rejected).
    pub max_steps: usize,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            t0: 0.0,
            t_end: 1.0,
            rtol: 1e-6,
            atol: 1e-9,
            dt: None,
            t_out: Vec::new(),
            max_steps: 10_000_000,
        }
    }
}

/// Work counters, for `--stats` and the benchmarks.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Stats {
    pub steps: usize,
    pub rejected: usize,
    pub rhs_evals: usize,
    pub jacobians: usize,
    pub factorizations: usize,
}

/// Why an integration ended early, or a warning about it.
#[derive(Clone, Debug, PartialEq)]
pub enum Status {
    /// Reached `t_end`.
    Done,
    /// An event function crossed zero at this time (see `explicit`'s events).
    Event { t: f64 },
    /// The step size fell below what f64 can resolve at `t`.
    StepTooSmall { t: f64 },
    /// `max_steps` reached at `t`.
    TooManySteps { t: f64 },
    /// A non-finite value appeared at `t`.
    NotFinite { t: f64 },
}

/// The recorded trajectory and what it cost.
#[derive(Clone, Debug)]
pub struct Solution {
    /// Recorded times, increasing.
    pub t: Vec<f64>,
    /// The state at each recorded time.
    pub y: Vec<Vec<f64>>,
    pub stats: Stats,
    pub status: Status,
    /// Set by explicit adaptive methods when the stiffness test (Hairer's,
    /// as in DOPRI5/DOP853) fired: the time at which it did.
    pub stiff_at: Option<f64>,
}
