//! qdot's ODE integrators: a first-order system y' = F(t, y) integrated
//! by our own methods, and the small dense linear algebra they need.
//! Nothing of qdot's exact side is here (this crate depends on no other
//! of qdot's): everything is floating point, and nothing from it ever
//! flows back into an exact result.
//!
//! * [`System`]: a first-order ODE y' = F(t, y) (what every method integrates).
//! * [`IntegratorOptions`], [`Stats`], [`Solution`]: the common inputs and outputs.
//! * [`explicit`]: RK4, Dormand–Prince 5(4), DOP853, Verner 7(6) — dense
//!   output, Hairer's step-size control, stiffness detection, events.
//! * [`implicit`]: Radau IIA (order 5, L-stable), Gauss–Legendre (symplectic).
//! * [`elliptic`]: Jacobi elliptic functions (exact pendulum references).
//! * [`dense`]: LU and friends on small dense matrices of `f64`.
//!
//! [`integrate`] and [`integrate_with_event`] dispatch on [`Method`].

pub mod dense;
pub mod elliptic;
pub mod explicit;
pub mod implicit;

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
    /// The dimension of y.
    pub dim: usize,
    /// `f(t, y, dy)` writes F(t, y) into `dy`.
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

impl Method {
    /// The method's name as the command line takes it: `dop853`, `radau5`.
    pub fn name(self) -> &'static str {
        match self {
            Method::Rk4 => "rk4",
            Method::Dopri5 => "dopri5",
            Method::Dop853 => "dop853",
            Method::Vern7 => "vern7",
            Method::Gauss6 => "gauss6",
            Method::Radau5 => "radau5",
        }
    }
}

/// What to integrate and how precisely.
#[derive(Clone, Debug)]
pub struct IntegratorOptions {
    /// The initial time.
    pub t0: f64,
    /// The final time (`t_end ≥ t0`).
    pub t_end: f64,
    /// Relative and absolute tolerances of adaptive methods.
    pub rtol: f64,
    /// The absolute tolerance (`rtol` is the relative one).
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

impl Default for IntegratorOptions {
    fn default() -> Self {
        IntegratorOptions {
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
    /// Accepted steps.
    pub steps: usize,
    /// Rejected steps, retried with a smaller step.
    pub rejected: usize,
    /// Evaluations of F (including those of finite-difference Jacobians).
    pub rhs_evals: usize,
    /// Evaluations of the Jacobian ∂F/∂y (implicit methods).
    pub jacobians: usize,
    /// LU factorizations of the Newton matrices (implicit methods).
    pub factorizations: usize,
}

/// Why an integration ended early, or a warning about it.
#[derive(Clone, Debug, PartialEq)]
pub enum Status {
    /// Reached `t_end`.
    Done,
    /// An event function crossed zero at this time (see `explicit`'s events).
    Event {
        /// The time of the crossing.
        t: f64,
    },
    /// The step size fell below what f64 can resolve at `t`.
    StepTooSmall {
        /// The time reached.
        t: f64,
    },
    /// `max_steps` reached at `t`.
    TooManySteps {
        /// The time reached.
        t: f64,
    },
    /// A non-finite value appeared at `t`.
    NotFinite {
        /// The time reached.
        t: f64,
    },
}

/// The recorded trajectory and what it cost.
#[derive(Clone, Debug)]
pub struct Solution {
    /// Recorded times, increasing.
    pub t: Vec<f64>,
    /// The state at each recorded time.
    pub y: Vec<Vec<f64>>,
    /// The work counters.
    pub stats: Stats,
    /// How the integration ended.
    pub status: Status,
    /// Set by explicit adaptive methods when the stiffness test (Hairer's,
    /// as in DOPRI5/DOP853) fired: the time at which it did.
    pub stiff_at: Option<f64>,
    /// The times where the event function changed sign without passing
    /// through zero (a pole or a jump: `1/(θ − ½)` at θ = ½): not events,
    /// so the integration went on.
    pub event_poles: Vec<f64>,
}

/// Why an integration could not start.
#[derive(Clone, Debug, PartialEq)]
pub enum SimError {
    /// An explicit-only entry point ([`explicit`]) was given an implicit method.
    NotExplicit(Method),
    /// The inputs are inconsistent (dimension, tolerances, times, step).
    BadInput(String),
}

impl std::fmt::Display for SimError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            SimError::NotExplicit(m) => write!(f, "{} is not an explicit method", m.name()),
            SimError::BadInput(s) => write!(f, "bad input: {s}"),
        }
    }
}

impl std::error::Error for SimError {}

/// Integrate y' = F(t, y), y(`opts.t0`) = `y0`, to `opts.t_end` with `method`.
///
/// Explicit methods are in [`explicit`], `Gauss6` and `Radau5` in
/// [`implicit`].
/// Early ends (step too small, too many steps, non-finite values) are a
/// [`Status`] of the returned [`Solution`], not an error.
pub fn integrate<S: System + ?Sized>(
    sys: &mut S,
    method: Method,
    y0: &[f64],
    opts: &IntegratorOptions,
) -> Result<Solution, SimError> {
    match method {
        Method::Rk4 | Method::Dopri5 | Method::Dop853 | Method::Vern7 => {
            explicit::integrate(sys, method, y0, opts)
        }
        Method::Radau5 => Ok(implicit::radau5(&mut Dyn(sys), y0, opts)?),
        Method::Gauss6 => Ok(implicit::gauss6(&mut Dyn(sys), y0, opts)?),
    }
}

/// A `System` behind any reference, as a sized `dyn System`.
struct Dyn<'a, S: System + ?Sized>(&'a mut S);

impl<S: System + ?Sized> System for Dyn<'_, S> {
    fn dim(&self) -> usize {
        self.0.dim()
    }
    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) {
        self.0.rhs(t, y, dy)
    }
    fn jacobian(&mut self, t: f64, y: &[f64], jac: &mut [f64]) -> bool {
        self.0.jacobian(t, y, jac)
    }
}

impl From<implicit::ImplicitError> for SimError {
    fn from(e: implicit::ImplicitError) -> SimError {
        SimError::BadInput(e.to_string())
    }
}

/// [`integrate`], stopping where `event(t, y)` changes sign between two
/// accepted steps: the crossing is located on the dense output (Brent's
/// method, |t − t*| ≤ 1e-12 relative), the solution ends there with
/// [`Status::Event`], and its last recorded state is the state at t*.
pub fn integrate_with_event<S: System + ?Sized>(
    sys: &mut S,
    method: Method,
    y0: &[f64],
    opts: &IntegratorOptions,
    event: &mut dyn FnMut(f64, &[f64]) -> f64,
) -> Result<Solution, SimError> {
    match method {
        Method::Rk4 | Method::Dopri5 | Method::Dop853 | Method::Vern7 => {
            explicit::integrate_with_event(sys, method, y0, opts, event)
        }
        Method::Gauss6 | Method::Radau5 => Err(SimError::BadInput(format!(
            "events are located on the dense output of the explicit methods; {} has none here: use dopri5, dop853 or vern7",
            method.name()
        ))),
    }
}

/// Hairer's weighted RMS norm of a local error estimate `err`:
/// √(1/n Σ (errᵢ/skᵢ)²), skᵢ = atol + rtol·max(|y0ᵢ|, |y1ᵢ|)
/// (Hairer, Nørsett & Wanner, Solving ODEs I, II.4, (4.11)).
pub(crate) fn error_norm(err: &[f64], y0: &[f64], y1: &[f64], rtol: f64, atol: f64) -> f64 {
    let n = err.len().max(1) as f64;
    let mut s = 0.0;
    for ((e, a), b) in err.iter().zip(y0).zip(y1) {
        let sk = atol + rtol * a.abs().max(b.abs());
        s += (e / sk) * (e / sk);
    }
    (s / n).sqrt()
}

/// Hairer's starting-step rule (`HINIT` of dopri5.f / dop853.f; Solving ODEs
/// I, II.4): a first guess from ‖y0‖/‖f0‖, one explicit Euler step to
/// estimate the second derivative, then h = (0.01 / max(‖f′‖, ‖f0‖))^(1/order),
/// at most 100 times the first guess and `hmax`. Returns the signed step
/// (direction `dir` = ±1); `y1` and `f1` are work space.
#[allow(clippy::too_many_arguments)]
pub(crate) fn initial_step<S: System + ?Sized>(
    sys: &mut S,
    t0: f64,
    y0: &[f64],
    f0: &[f64],
    dir: f64,
    order: i32,
    hmax: f64,
    rtol: f64,
    atol: f64,
    y1: &mut [f64],
    f1: &mut [f64],
    stats: &mut Stats,
) -> f64 {
    let (mut dnf, mut dny) = (0.0, 0.0);
    for (y, f) in y0.iter().zip(f0) {
        let sk = atol + rtol * y.abs();
        dnf += (f / sk) * (f / sk);
        dny += (y / sk) * (y / sk);
    }
    let mut h = if dnf <= 1e-10 || dny <= 1e-10 {
        1e-6
    } else {
        (dny / dnf).sqrt() * 0.01
    };
    h = h.min(hmax);
    for ((y1, y), f) in y1.iter_mut().zip(y0).zip(f0) {
        *y1 = y + dir * h * f;
    }
    sys.rhs(t0 + dir * h, y1, f1);
    stats.rhs_evals += 1;
    let mut der2 = 0.0;
    for ((a, b), y) in f1.iter().zip(f0).zip(y0) {
        let sk = atol + rtol * y.abs();
        der2 += ((a - b) / sk) * ((a - b) / sk);
    }
    let der2 = der2.sqrt() / h;
    let der12 = der2.max(dnf.sqrt());
    let h1 = if der12 <= 1e-15 || !der12.is_finite() {
        (h * 1e-3).max(1e-6)
    } else {
        (0.01 / der12).powf(1.0 / order as f64)
    };
    dir * (100.0 * h).min(h1).min(hmax)
}
