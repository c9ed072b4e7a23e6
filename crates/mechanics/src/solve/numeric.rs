//! Numeric roots of small square nonlinear systems F(x) = 0, x ∈ ℝⁿ.
//!
//! This is the fallback used when qdot cannot find the equilibria of a
//! mechanical system in closed form: the unknowns are generalized
//! coordinates, some of them angles (2π-periodic), the others lengths
//! (unbounded), and F_k(q) are the generalized forces. Sizes are small
//! (n = 1..≈8), so everything is dense and simple.
//!
//! # Method
//!
//! [`find_roots`] runs damped Newton iterations from many starting points and
//! uses *deflation* (P. E. Farrell, Á. Birkisson, S. W. Funke, "Deflation
//! techniques for finding distinct solutions of nonlinear partial differential
//! equations", SIAM J. Sci. Comput. 37(4), 2015): once roots r₁, r₂, … are
//! known, Newton's method is applied to
//!
//! ```text
//! G(x) = M(x)·F(x),   M(x) = Π_i m_i(x),   m_i(x) = 1/‖x − r_i‖ᵖ + σ,   p = 2, σ = 1,
//! ```
//!
//! which has the same roots as F except the known ones (there G stays away
//! from 0, and near a known root it blows up, so the line search pushes the
//! iterate away). Distances are taken modulo 2π in periodic coordinates (each
//! periodic difference is wrapped into (−π, π]). With s_i = ‖x − r_i‖² and
//! d_i the (wrapped) difference x − r_i,
//!
//! ```text
//! ∇m_i = −2·d_i/s_i²,   ∇M/M = Σ_i ∇m_i/m_i = Σ_i −2·d_i / (s_i·(1 + σ·s_i)) =: w,
//! J_G = M·J_F + F·(∇M)ᵀ = M·(J_F + F·wᵀ).
//! ```
//!
//! The Newton system J_G·δ = −G is divided by M, i.e. (J_F + F·wᵀ)·δ = −F
//! is solved, so the possibly huge or tiny factor M never appears in the
//! linear algebra; the merit function ‖G‖² of the line search is compared in
//! logarithms (ln ‖G‖² = ln ‖F‖² + 2·Σ_i ln(1/s_i + σ)) for the same reason.
//!
//! For every starting point x₀: run the deflated Newton iteration (deflated by
//! all roots known so far); polish its end point with *undeflated* Newton;
//! evaluate F (not G) at the result and accept it if max_k |F_k| is within
//! the tolerance; wrap it into (−π, π] in periodic coordinates; discard it if
//! it duplicates a known root (distance < 10⁻⁶·(1 + ‖x‖), periodic-aware;
//! the copy with the smaller residual is kept). Whenever a start yields a new
//! root, the deflated iteration is restarted from the *same* x₀ (now deflated
//! by the new root too), as recommended by Farrell et al.; a start is left
//! when it fails or reproduces a known root. The roots are returned sorted
//! lexicographically by x.
//!
//! # Choices
//!
//! * **Starting points.** First a small regular grid: each coordinate takes
//!   the values {0, +a, −a} with a = scale/2 for lengths and a = 2π/3 for
//!   angles (multiples of π/2 are avoided, as they are typical critical points
//!   of trigonometric forces); the full 3ⁿ grid is used if 3ⁿ ≤ starts/2,
//!   otherwise the origin and the 2n points ±a·e_i. The origin always comes
//!   first. The rest are pseudo-random, uniform in [−scale, scale] for lengths
//!   and (−π, π] for angles, from a SplitMix64 generator with a fixed seed:
//!   the same inputs always give the same outputs.
//! * **Tolerance.** The residual scale S is the median over the starting
//!   points (where F is defined) of max_k |F_k(x₀)|; if that median is 0, the
//!   largest such value, and if all are 0, 1. A point is accepted as a root if
//!   max_k |F_k| ≤ tol·S. So tol is relative to the size of the forces over
//!   the search box: a system with forces ~10³ and one with forces ~10⁻³ are
//!   treated alike. (If no starting point has F defined, nothing is found.)
//!   A negative or NaN tol accepts only exact zeros.
//! * **Convergence.** The deflated iteration stops as soon as max |F_k| ≤
//!   tol·S. The polishing iteration does not stop at the tolerance: it keeps
//!   taking Newton steps until F is exactly 0, the step is negligible
//!   (≤ 4ε·(1 + ‖x‖_∞)), the line search cannot decrease ‖F‖² any more, or
//!   `max_iter` is reached. So simple roots are polished to full accuracy, and
//!   multiple roots (where Newton converges only linearly, halving the error
//!   for a double root) are still driven to the floating-point floor, which
//!   keeps the copies reached from different starts within the de-duplication
//!   distance.
//! * **Damping.** Backtracking line search on ‖G‖² (‖F‖² when polishing):
//!   λ = 1, ½, ¼, … (at most 40 halvings), accepting the Armijo condition
//!   ‖G(x + λδ)‖² ≤ (1 − 2·10⁻⁴·λ)·‖G(x)‖². A trial point where `f` returns
//!   `None`, a wrong length or a non-finite value, or where a non-periodic
//!   coordinate leaves the box |x_i| ≤ 10⁶·max(scale, 1), counts as a failed
//!   trial and is backtracked from. If no λ is accepted the iteration stops
//!   (its end point is still polished and checked). Before the line search the
//!   step length is capped at 10·max(scale, π, ‖x‖_∞).
//! * **Singular Jacobian.** The linear systems are solved by Gaussian
//!   elimination with partial pivoting; a pivot ≤ n·ε·max|A_ij| counts as
//!   singular. Then a regularized (Levenberg–Marquardt) step is taken
//!   instead: (AᵀA + μI)·δ = −AᵀF with μ = 10⁻⁶·max_i (AᵀA)_ii. It is a
//!   descent direction for ‖F‖², so the line search only asks for a strict
//!   decrease. If A = 0 (or AᵀF = 0, as at a critical point such as x = 0 for
//!   x² − 2) the step vanishes and the iteration stops: such a start is
//!   effectively abandoned.
//! * **Undefined values.** If `f` is undefined at a starting point, that start
//!   is skipped; if `jac` is undefined at an iterate, the iteration stops there
//!   (the point is still polished/checked). Nothing panics on NaN or infinite
//!   values: every result of `f`/`jac` is checked for finiteness and every
//!   division is guarded.
//! * **Reporting.** Periodic coordinates are reported in (−π, π]; a value
//!   within 16ε of −π is reported as π (so the root π of sin x is π, not −π),
//!   and −0 is reported as 0. `residual` is max_k |F_k| at the reported x.

use crate::dense::Lu;
use crate::rng::SplitMix64;
use std::cmp::Ordering;
use std::f64::consts::{PI, TAU};

/// σ in the deflation operator M(x) = Π_i (1/‖x − r_i‖² + σ).
const SIGMA: f64 = 1.0;
/// Armijo constant of the backtracking line search.
const ARMIJO: f64 = 1e-4;
/// Maximum number of step halvings in one line search.
const MAX_HALVINGS: usize = 40;
/// Relative Levenberg–Marquardt shift used when the Jacobian is singular.
const REGULARIZATION: f64 = 1e-6;
/// Relative distance below which two roots are the same.
const DEDUP: f64 = 1e-6;
/// Non-periodic coordinates are confined to |x_i| ≤ BOX·max(scale, 1).
const BOX: f64 = 1e6;
/// Seed of the pseudo-random starting points.
const SEED: u64 = 0x71D0_7E9A_5C3B_2F41;

/// F: ℝⁿ → ℝⁿ, `None` where undefined.
type Function<'a> = dyn Fn(&[f64]) -> Option<Vec<f64>> + 'a;
/// J_F as rows (`[k][i]` = ∂F_k/∂x_i), `None` where undefined.
type Jacobian<'a> = dyn Fn(&[f64]) -> Option<Vec<Vec<f64>>> + 'a;

/// Settings for [`find_roots`].
///
/// The number of unknowns n is `periodic.len()`.
#[derive(Clone, Debug, PartialEq)]
pub struct RootOptions {
    /// Per coordinate: true if it is an angle (period 2π; roots are reported in (−π, π]).
    pub periodic: Vec<bool>,
    /// Box for starting points of non-periodic coordinates: [-scale, scale] (angles use (−π, π]).
    /// A non-finite or non-positive value is treated as 1.
    pub scale: f64,
    /// Number of starting points (deterministic pseudo-random + a small regular grid including the origin).
    pub starts: usize,
    /// Maximum number of Newton steps per iteration (deflated run and polishing each).
    pub max_iter: usize,
    /// Residual tolerance on max |F_k| relative to the function's typical magnitude:
    /// a point is a root if max_k |F_k| ≤ tol·S, where S is the median over the
    /// starting points of max_k |F_k| (see the module documentation).
    pub tol: f64,
    /// Upper bound on roots returned.
    pub max_roots: usize,
}

impl Default for RootOptions {
    /// No coordinates (set `periodic`), scale 10, 64 starts, 100 iterations,
    /// tol 10⁻¹⁰, at most 32 roots.
    fn default() -> Self {
        RootOptions {
            periodic: Vec::new(),
            scale: 10.0,
            starts: 64,
            max_iter: 100,
            tol: 1e-10,
            max_roots: 32,
        }
    }
}

/// A root, with max |F_k| at it.
#[derive(Clone, Debug, PartialEq)]
pub struct Root {
    /// The root; periodic coordinates in (−π, π].
    pub x: Vec<f64>,
    /// max_k |F_k(x)|.
    pub residual: f64,
}

/// All roots found: Newton's method with damping (backtracking line search on
/// ‖F‖²) from many starting points, with deflation (Farrell, Birkisson &
/// Funke 2015: G(x) = M(x)·F(x), M(x) = Π_i (1/‖x − r_i‖^p + σ), p = 2,
/// σ = 1, distances taken modulo 2π in periodic coordinates) so that starts
/// converging to known roots are pushed to new ones. Each candidate is
/// polished with undeflated Newton, checked against F (not G), wrapped into
/// (−π, π] in periodic coordinates, and de-duplicated (distance <
/// 1e-6·(1+|x|), periodic-aware). Returned sorted (lexicographically by x).
///
/// `f` returns F(x) (length n = `opts.periodic.len()`), `jac` the Jacobian
/// as rows: `jac(x)[k][i]` = ∂F_k/∂x_i. Either may return `None` where the
/// function is undefined; a wrong length or a non-finite entry is treated
/// the same way. See the module documentation for the tolerance, the
/// starting points and the handling of singular Jacobians.
///
/// ```
/// use qdot_mechanics::solve::numeric::{find_roots, RootOptions};
/// let opts = RootOptions { periodic: vec![true], ..RootOptions::default() };
/// let f = |x: &[f64]| Some(vec![x[0].sin()]);
/// let j = |x: &[f64]| Some(vec![vec![x[0].cos()]]);
/// let roots = find_roots(&f, &j, &opts);
/// assert_eq!(roots.len(), 2);
/// assert_eq!(roots[0].x, [0.0]);
/// assert_eq!(roots[1].x, [std::f64::consts::PI]);
/// ```
#[allow(clippy::type_complexity)] // the closure types are spelled out for the reader
pub fn find_roots(
    f: &dyn Fn(&[f64]) -> Option<Vec<f64>>,
    jac: &dyn Fn(&[f64]) -> Option<Vec<Vec<f64>>>,
    opts: &RootOptions,
) -> Vec<Root> {
    if opts.max_roots == 0 {
        return Vec::new();
    }
    let Some((problem, starts)) = setup(f, jac, opts) else {
        return Vec::new();
    };
    let mut roots: Vec<Root> = Vec::new();
    'starts: for x0 in &starts {
        loop {
            if roots.len() >= opts.max_roots {
                break 'starts;
            }
            let Some(end) = problem.newton(x0, &roots, true) else {
                break;
            };
            let Some(x) = problem.newton(&end, &[], false) else {
                break;
            };
            let x = problem.report(x);
            let Some(fx) = problem.eval(&x) else {
                break;
            };
            let residual = max_abs(&fx);
            // Both sides are non-NaN: `eval` checks finiteness, `setup` the tolerance.
            if residual > problem.threshold {
                break;
            }
            match roots.iter().position(|r| problem.same(&r.x, &x)) {
                Some(i) => {
                    if residual < roots[i].residual {
                        roots[i] = Root { x, residual };
                    }
                    break;
                }
                None => roots.push(Root { x, residual }),
            }
        }
    }
    roots.sort_by(|a, b| lexicographic(&a.x, &b.x));
    roots
}

/// The problem with its acceptance threshold, and the starting points.
/// `None` if there are no unknowns or F is defined at no starting point.
fn setup<'a>(
    f: &'a Function<'a>,
    jac: &'a Jacobian<'a>,
    opts: &'a RootOptions,
) -> Option<(Problem<'a>, Vec<Vec<f64>>)> {
    if opts.periodic.is_empty() {
        return None;
    }
    let scale = effective_scale(opts.scale);
    let mut problem = Problem {
        f,
        jac,
        periodic: &opts.periodic,
        max_iter: opts.max_iter,
        threshold: 0.0,
        limit: BOX * scale.max(1.0),
        step_floor: 10.0 * scale.max(PI),
    };
    let starts = start_points(opts);
    let mut mags: Vec<f64> = starts
        .iter()
        .filter_map(|x| problem.eval(x))
        .map(|fx| max_abs(&fx))
        .collect();
    if mags.is_empty() {
        return None;
    }
    mags.sort_by(f64::total_cmp);
    let m = mags.len();
    let median = if m % 2 == 1 {
        mags[m / 2]
    } else {
        0.5 * mags[m / 2 - 1] + 0.5 * mags[m / 2]
    };
    let largest = mags[m - 1];
    let s = if median > 0.0 {
        median
    } else if largest > 0.0 {
        largest
    } else {
        1.0
    };
    let tol = if opts.tol >= 0.0 { opts.tol } else { 0.0 };
    problem.threshold = tol * s.max(f64::MIN_POSITIVE);
    Some((problem, starts))
}

fn effective_scale(scale: f64) -> f64 {
    if scale.is_finite() && scale > 0.0 {
        scale
    } else {
        1.0
    }
}

/// Grid points first (origin first), then pseudo-random ones; `opts.starts`
/// in all.
fn start_points(opts: &RootOptions) -> Vec<Vec<f64>> {
    let n = opts.periodic.len();
    let total = opts.starts;
    let scale = effective_scale(opts.scale);
    let half: Vec<f64> = opts
        .periodic
        .iter()
        .map(|&p| if p { TAU / 3.0 } else { 0.5 * scale })
        .collect();
    let mut points: Vec<Vec<f64>> = Vec::with_capacity(total);
    let full = u32::try_from(n)
        .ok()
        .and_then(|e| 3usize.checked_pow(e))
        .filter(|&g| g <= total / 2);
    match full {
        Some(g) => {
            for mut idx in 0..g {
                let mut x = vec![0.0; n];
                for (xi, &a) in x.iter_mut().zip(&half) {
                    *xi = match idx % 3 {
                        0 => 0.0,
                        1 => a,
                        _ => -a,
                    };
                    idx /= 3;
                }
                points.push(x);
            }
        }
        None => {
            points.push(vec![0.0; n]);
            for (i, &a) in half.iter().enumerate() {
                for sign in [1.0, -1.0] {
                    let mut x = vec![0.0; n];
                    x[i] = sign * a;
                    points.push(x);
                }
            }
        }
    }
    points.truncate(total);
    let mut rng = SplitMix64::new(SEED ^ (n as u64));
    while points.len() < total {
        let x = opts
            .periodic
            .iter()
            .map(|&p| {
                let u = rng.unit();
                if p {
                    PI - TAU * u
                } else {
                    scale * (2.0 * u - 1.0)
                }
            })
            .collect();
        points.push(x);
    }
    points
}

struct Problem<'a> {
    f: &'a Function<'a>,
    jac: &'a Jacobian<'a>,
    periodic: &'a [bool],
    max_iter: usize,
    /// A point is a root if max_k |F_k| ≤ threshold (= tol·S).
    threshold: f64,
    /// Non-periodic coordinates must satisfy |x_i| ≤ limit.
    limit: f64,
    /// Newton steps are capped at max(step_floor, 10·‖x‖_∞).
    step_floor: f64,
}

impl Problem<'_> {
    fn n(&self) -> usize {
        self.periodic.len()
    }

    /// F(x), or `None` if undefined, of the wrong length or not finite.
    fn eval(&self, x: &[f64]) -> Option<Vec<f64>> {
        let v = (self.f)(x)?;
        (v.len() == self.n() && v.iter().all(|t| t.is_finite())).then_some(v)
    }

    /// J_F(x), or `None` if undefined, of the wrong shape or not finite.
    fn jacobian(&self, x: &[f64]) -> Option<Vec<Vec<f64>>> {
        let j = (self.jac)(x)?;
        let n = self.n();
        let ok = j.len() == n
            && j.iter()
                .all(|row| row.len() == n && row.iter().all(|t| t.is_finite()));
        ok.then_some(j)
    }

    /// Wraps the periodic coordinates into (−π, π].
    fn wrap(&self, x: &mut [f64]) {
        for (t, &p) in x.iter_mut().zip(self.periodic) {
            if p {
                *t = wrap_angle(*t);
            }
        }
    }

    /// The form in which a root is reported.
    fn report(&self, mut x: Vec<f64>) -> Vec<f64> {
        self.wrap(&mut x);
        for t in &mut x {
            *t += 0.0; // −0 → 0
        }
        x
    }

    fn admissible(&self, x: &[f64]) -> bool {
        x.iter()
            .zip(self.periodic)
            .all(|(t, &p)| t.is_finite() && (p || t.abs() <= self.limit))
    }

    /// a − b, wrapped into (−π, π] in periodic coordinates.
    fn diff(&self, a: &[f64], b: &[f64]) -> Vec<f64> {
        a.iter()
            .zip(b)
            .zip(self.periodic)
            .map(|((&s, &t), &p)| if p { wrap_angle(s - t) } else { s - t })
            .collect()
    }

    /// ‖a − b‖², periodic-aware, without allocating.
    fn dist_sq(&self, a: &[f64], b: &[f64]) -> f64 {
        a.iter()
            .zip(b)
            .zip(self.periodic)
            .map(|((&s, &t), &p)| {
                let d = if p { wrap_angle(s - t) } else { s - t };
                d * d
            })
            .sum()
    }

    /// Whether the candidate `x` duplicates the known root `r`.
    fn same(&self, r: &[f64], x: &[f64]) -> bool {
        norm(&self.diff(x, r)) < DEDUP * (1.0 + norm(x))
    }

    /// ln ‖G(x)‖² = ln ‖F(x)‖² + 2·Σ_i ln(1/s_i + σ), s_i = ‖x − r_i‖².
    /// `None` at a known root (where G is infinite).
    fn log_merit(&self, x: &[f64], fx: &[f64], known: &[Root]) -> Option<f64> {
        let mut lm = log_norm_sq(fx);
        for r in known {
            let s = self.dist_sq(x, &r.x);
            if !(s > 0.0 && s.is_finite()) {
                return None;
            }
            // ln(1/s + σ) = ln(1 + σ·s) − ln s, without forming 1/s.
            lm += 2.0 * ((SIGMA * s).ln_1p() - s.ln());
        }
        (!lm.is_nan()).then_some(lm)
    }

    /// w = ∇M/M = Σ_i −2·d_i / (s_i·(1 + σ·s_i)), so that J_G = M·(J_F + F·wᵀ).
    fn deflation_weight(&self, x: &[f64], known: &[Root]) -> Option<Vec<f64>> {
        let mut w = vec![0.0; self.n()];
        for r in known {
            let d = self.diff(x, &r.x);
            let s = norm_sq(&d);
            let c = -2.0 / (s * (1.0 + SIGMA * s));
            if !c.is_finite() {
                return None;
            }
            for (wi, di) in w.iter_mut().zip(&d) {
                *wi += c * di;
            }
        }
        w.iter().all(|t| t.is_finite()).then_some(w)
    }

    /// Damped Newton from `x0` on G = M·F deflated by `known` (plain F if
    /// `known` is empty). With `deflated`, stops once max |F_k| ≤ threshold;
    /// otherwise (polishing) goes on until no further progress is possible.
    /// Returns the last iterate, or `None` if the start itself is unusable
    /// (F undefined there, outside the box, or at a known root).
    fn newton(&self, x0: &[f64], known: &[Root], deflated: bool) -> Option<Vec<f64>> {
        let mut x = x0.to_vec();
        self.wrap(&mut x);
        if !self.admissible(&x) {
            return None;
        }
        let mut fx = self.eval(&x)?;
        let mut merit = self.log_merit(&x, &fx, known)?;
        for _ in 0..self.max_iter {
            let r = max_abs(&fx);
            if r == 0.0 || (deflated && r <= self.threshold) {
                break;
            }
            let Some(mut a) = self.jacobian(&x) else {
                break;
            };
            if !known.is_empty() {
                let Some(w) = self.deflation_weight(&x, known) else {
                    break;
                };
                for (row, &fk) in a.iter_mut().zip(&fx) {
                    for (aki, &wi) in row.iter_mut().zip(&w) {
                        *aki += fk * wi;
                    }
                }
            }
            let rhs: Vec<f64> = fx.iter().map(|t| -t).collect();
            // Newton step (Armijo slope) or regularized step (strict decrease).
            let (mut step, armijo) = match solve(a.clone(), rhs) {
                Some(s) => (s, ARMIJO),
                None => match regularized_step(&a, &fx) {
                    Some(s) => (s, 0.0),
                    None => break,
                },
            };
            let len = norm(&step);
            if !len.is_finite() {
                break;
            }
            let cap = self.step_floor.max(10.0 * max_abs(&x));
            if len > cap {
                let shrink = cap / len;
                for t in &mut step {
                    *t *= shrink;
                }
            }
            if max_abs(&step) <= 4.0 * f64::EPSILON * (1.0 + max_abs(&x)) {
                break;
            }
            let mut lambda = 1.0;
            let mut accepted = false;
            for _ in 0..MAX_HALVINGS {
                let mut trial: Vec<f64> =
                    x.iter().zip(&step).map(|(a, s)| a + lambda * s).collect();
                self.wrap(&mut trial);
                if self.admissible(&trial) {
                    if let Some(ft) = self.eval(&trial) {
                        if let Some(mt) = self.log_merit(&trial, &ft, known) {
                            let ok = if armijo > 0.0 {
                                mt <= merit + (-2.0 * armijo * lambda).ln_1p()
                            } else {
                                mt < merit
                            };
                            if ok {
                                x = trial;
                                fx = ft;
                                merit = mt;
                                accepted = true;
                                break;
                            }
                        }
                    }
                }
                lambda *= 0.5;
            }
            if !accepted {
                break;
            }
        }
        Some(x)
    }
}

/// Wraps an angle into (−π, π]; values within 16ε of −π become π.
fn wrap_angle(t: f64) -> f64 {
    let mut r = t.rem_euclid(TAU); // in [0, 2π] (2π only by rounding)
    if r > PI {
        r -= TAU;
    }
    if r <= -PI + 16.0 * f64::EPSILON {
        r = PI;
    }
    r + 0.0
}

fn max_abs(v: &[f64]) -> f64 {
    v.iter().fold(0.0, |m: f64, t| m.max(t.abs()))
}

fn norm_sq(v: &[f64]) -> f64 {
    v.iter().map(|t| t * t).sum()
}

fn norm(v: &[f64]) -> f64 {
    let m = max_abs(v);
    if m > 0.0 && m.is_finite() {
        m * v.iter().map(|t| (t / m) * (t / m)).sum::<f64>().sqrt()
    } else {
        m
    }
}

/// ln ‖v‖², without overflow; −∞ for v = 0.
fn log_norm_sq(v: &[f64]) -> f64 {
    let m = max_abs(v);
    if m > 0.0 && m.is_finite() {
        2.0 * m.ln() + v.iter().map(|t| (t / m) * (t / m)).sum::<f64>().ln()
    } else if m == 0.0 {
        f64::NEG_INFINITY
    } else {
        f64::INFINITY
    }
}

fn lexicographic(a: &[f64], b: &[f64]) -> Ordering {
    for (s, t) in a.iter().zip(b) {
        match s.total_cmp(t) {
            Ordering::Equal => {}
            other => return other,
        }
    }
    a.len().cmp(&b.len())
}

/// Solves A·x = b by Gaussian elimination with partial pivoting. `None` if A
/// is (numerically) singular — a pivot ≤ n·ε·max|A_ij| — or not square, or
/// the result is not finite.
fn solve(a: Vec<Vec<f64>>, mut b: Vec<f64>) -> Option<Vec<f64>> {
    let n = b.len();
    if a.len() != n || a.iter().any(|row| row.len() != n) {
        return None;
    }
    let size = a.iter().map(|row| max_abs(row)).fold(0.0, f64::max);
    if !(size > 0.0 && size.is_finite()) {
        return None;
    }
    let mut lu = Lu::new(n, 0.0);
    lu.a = a.concat();
    if !lu.factor_above(n as f64 * f64::EPSILON * size) {
        return None;
    }
    lu.solve(&mut b);
    b.iter().all(|t| t.is_finite()).then_some(b)
}

/// Levenberg–Marquardt step (AᵀA + μI)·δ = −AᵀF, μ = 10⁻⁶·max_i (AᵀA)_ii,
/// for a singular A. `None` if A = 0, the step vanishes or is not finite.
fn regularized_step(a: &[Vec<f64>], fx: &[f64]) -> Option<Vec<f64>> {
    let n = fx.len();
    let mut ata = vec![vec![0.0; n]; n];
    let mut g = vec![0.0; n];
    for (row, &fk) in a.iter().zip(fx) {
        for i in 0..n {
            g[i] -= row[i] * fk;
            for k in 0..n {
                ata[i][k] += row[i] * row[k];
            }
        }
    }
    let dmax = (0..n).map(|i| ata[i][i]).fold(0.0, f64::max);
    if !(dmax > 0.0 && dmax.is_finite()) {
        return None;
    }
    let mu = REGULARIZATION * dmax;
    for (i, row) in ata.iter_mut().enumerate() {
        row[i] += mu;
    }
    let step = solve(ata, g)?;
    (max_abs(&step) > 0.0).then_some(step)
}

#[cfg(test)]
mod tests {
    use super::*;

    type F = Box<dyn Fn(&[f64]) -> Option<Vec<f64>>>;
    type J = Box<dyn Fn(&[f64]) -> Option<Vec<Vec<f64>>>>;

    fn opts(periodic: &[bool]) -> RootOptions {
        RootOptions {
            periodic: periodic.to_vec(),
            ..RootOptions::default()
        }
    }

    /// Runs `find_roots` and checks the invariants every result must satisfy:
    /// residual ≤ tol·S and equal to max |F| at x, angles in (−π, π], sorted,
    /// no duplicates, deterministic.
    fn run(f: &F, j: &J, o: &RootOptions) -> Vec<Root> {
        let roots = find_roots(f.as_ref(), j.as_ref(), o);
        let again = find_roots(f.as_ref(), j.as_ref(), o);
        assert_eq!(roots, again, "not deterministic");
        assert!(roots.len() <= o.max_roots);
        if let Some((p, _)) = setup(f.as_ref(), j.as_ref(), o) {
            for r in &roots {
                assert!(r.residual <= p.threshold, "{r:?} above {}", p.threshold);
                let fx = f(&r.x).unwrap();
                assert_eq!(max_abs(&fx), r.residual);
                for (t, &per) in r.x.iter().zip(&o.periodic) {
                    if per {
                        assert!(*t > -PI && *t <= PI, "{t} not in (−π, π]");
                    }
                }
            }
            for w in roots.windows(2) {
                assert_eq!(lexicographic(&w[0].x, &w[1].x), Ordering::Less);
                assert!(!p.same(&w[0].x, &w[1].x));
            }
        } else {
            assert!(roots.is_empty());
        }
        roots
    }

    fn assert_roots(roots: &[Root], expected: &[&[f64]], eps: f64) {
        let got: Vec<&Vec<f64>> = roots.iter().map(|r| &r.x).collect();
        assert_eq!(roots.len(), expected.len(), "got {got:?}");
        for (r, e) in roots.iter().zip(expected) {
            for (a, b) in r.x.iter().zip(e.iter()) {
                assert!((a - b).abs() <= eps, "got {got:?}, expected {expected:?}");
            }
        }
    }

    #[test]
    fn square_root_of_two() {
        let f: F = Box::new(|x| Some(vec![x[0] * x[0] - 2.0]));
        let j: J = Box::new(|x| Some(vec![vec![2.0 * x[0]]]));
        let roots = run(&f, &j, &opts(&[false]));
        let s = 2f64.sqrt();
        assert_roots(&roots, &[&[-s], &[s]], 1e-14);
    }

    #[test]
    fn sine_periodic_has_exactly_zero_and_pi() {
        let f: F = Box::new(|x| Some(vec![x[0].sin()]));
        let j: J = Box::new(|x| Some(vec![vec![x[0].cos()]]));
        let roots = run(&f, &j, &opts(&[true]));
        assert_roots(&roots, &[&[0.0], &[PI]], 1e-15);
        assert_eq!(roots[0].x[0], 0.0);
        assert_eq!(roots[1].x[0], PI, "π must be reported as π, not −π");
    }

    #[test]
    fn pendulum_on_rotating_hoop() {
        let f: F = Box::new(|x| Some(vec![x[0].sin() * (x[0].cos() - 0.5)]));
        let j: J = Box::new(|x| {
            let (s, c) = x[0].sin_cos();
            Some(vec![vec![c * (c - 0.5) - s * s]])
        });
        let roots = run(&f, &j, &opts(&[true]));
        let t = PI / 3.0;
        assert_roots(&roots, &[&[-t], &[0.0], &[t], &[PI]], 1e-14);
        assert_eq!(roots[3].x[0], PI);
    }

    #[test]
    fn two_bar_chain() {
        let f: F = Box::new(|x| {
            Some(vec![
                -3.0 * x[0].sin() + 2.0 * 0.7 * x[0].cos(),
                -x[1].sin() + 2.0 * 0.7 * x[1].cos(),
            ])
        });
        let j: J = Box::new(|x| {
            Some(vec![
                vec![-3.0 * x[0].cos() - 1.4 * x[0].sin(), 0.0],
                vec![0.0, -x[1].cos() - 1.4 * x[1].sin()],
            ])
        });
        let roots = run(&f, &j, &opts(&[true, true]));
        let a = (1.4f64 / 3.0).atan();
        let b = 1.4f64.atan();
        assert_roots(
            &roots,
            &[&[a - PI, b - PI], &[a - PI, b], &[a, b - PI], &[a, b]],
            1e-14,
        );
    }

    #[test]
    fn polynomial_system_with_four_real_roots() {
        let f: F = Box::new(|x| Some(vec![x[0] * x[0] + x[1] * x[1] - 5.0, x[0] * x[1] - 2.0]));
        let j: J = Box::new(|x| Some(vec![vec![2.0 * x[0], 2.0 * x[1]], vec![x[1], x[0]]]));
        let roots = run(&f, &j, &opts(&[false, false]));
        assert_roots(
            &roots,
            &[&[-2.0, -1.0], &[-1.0, -2.0], &[1.0, 2.0], &[2.0, 1.0]],
            1e-13,
        );
    }

    #[test]
    fn no_real_roots() {
        let f: F = Box::new(|x| Some(vec![x[0] * x[0] + 1.0]));
        let j: J = Box::new(|x| Some(vec![vec![2.0 * x[0]]]));
        assert!(run(&f, &j, &opts(&[false])).is_empty());
    }

    #[test]
    fn undefined_on_half_the_domain() {
        // √x − 1.5, defined for x > 0 only; the root is 2.25.
        let f: F = Box::new(|x| (x[0] > 0.0).then(|| vec![x[0].sqrt() - 1.5]));
        let j: J = Box::new(|x| (x[0] > 0.0).then(|| vec![vec![0.5 / x[0].sqrt()]]));
        let roots = run(&f, &j, &opts(&[false]));
        assert_roots(&roots, &[&[2.25]], 1e-14);
    }

    #[test]
    fn cubic_with_double_root() {
        // (x − 1)²(x + 2): the double root 1 converges only linearly.
        let f: F = Box::new(|x| Some(vec![(x[0] - 1.0) * (x[0] - 1.0) * (x[0] + 2.0)]));
        let j: J = Box::new(|x| {
            let t = x[0];
            Some(vec![vec![
                2.0 * (t - 1.0) * (t + 2.0) + (t - 1.0) * (t - 1.0),
            ]])
        });
        let roots = run(&f, &j, &opts(&[false]));
        assert_roots(&roots, &[&[-2.0], &[1.0]], 1e-7);
        // The same in expanded form x³ − 3x + 2 (rounding floor near x = 1).
        let f: F = Box::new(|x| Some(vec![x[0] * x[0] * x[0] - 3.0 * x[0] + 2.0]));
        let j: J = Box::new(|x| Some(vec![vec![3.0 * x[0] * x[0] - 3.0]]));
        let roots = run(&f, &j, &opts(&[false]));
        assert_roots(&roots, &[&[-2.0], &[1.0]], 1e-7);
    }

    #[test]
    fn deflation_finds_all_roots_from_a_single_start() {
        // Only the origin as starting point: plain Newton reaches one root,
        // the deflated restarts from the same point find the other two.
        let f: F = Box::new(|x| Some(vec![(x[0] - 1.0) * (x[0] - 2.0) * (x[0] - 3.0)]));
        let j: J = Box::new(|x| {
            let t = x[0];
            Some(vec![vec![3.0 * t * t - 12.0 * t + 11.0]])
        });
        let o = RootOptions {
            starts: 1,
            ..opts(&[false])
        };
        let roots = run(&f, &j, &o);
        assert_roots(&roots, &[&[1.0], &[2.0], &[3.0]], 1e-14);
    }

    #[test]
    fn tolerance_is_relative_to_the_force_scale() {
        // Pendulum on a spring (r, θ): F_r = −k(r − L) + m g cos θ,
        // F_θ = −m g r sin θ, at scales 10³ and 10⁻³.
        for unit in [1e3, 1e-3] {
            let (k, l, mg) = (50.0 * unit, 1.0, 10.0 * unit);
            let f: F = Box::new(move |x| {
                let (s, c) = x[1].sin_cos();
                Some(vec![-k * (x[0] - l) + mg * c, -mg * x[0] * s])
            });
            let j: J = Box::new(move |x| {
                let (s, c) = x[1].sin_cos();
                Some(vec![vec![-k, -mg * s], vec![-mg * s, -mg * x[0] * c]])
            });
            let roots = run(&f, &j, &opts(&[false, true]));
            // r = L ± mg/k with θ = 0 / π, and r = 0 with cos θ = −kL/(mg) (none: kL/mg = 5).
            assert_roots(&roots, &[&[0.8, PI], &[1.2, 0.0]], 1e-13);
        }
    }

    #[test]
    fn max_roots_caps_the_result() {
        let f: F = Box::new(|x| Some(vec![(3.0 * x[0]).sin()]));
        let j: J = Box::new(|x| Some(vec![vec![3.0 * (3.0 * x[0]).cos()]]));
        assert_eq!(run(&f, &j, &opts(&[true])).len(), 6);
        let o = RootOptions {
            max_roots: 2,
            ..opts(&[true])
        };
        assert_eq!(run(&f, &j, &o).len(), 2);
    }

    #[test]
    fn hostile_inputs_do_not_panic() {
        let j: J = Box::new(|_| Some(vec![vec![1.0]]));
        // Undefined everywhere.
        let f: F = Box::new(|_| None);
        assert!(run(&f, &j, &opts(&[false])).is_empty());
        // NaN and infinity.
        let f: F = Box::new(|_| Some(vec![f64::NAN]));
        assert!(run(&f, &j, &opts(&[false])).is_empty());
        let f: F = Box::new(|x| Some(vec![1.0 / x[0]]));
        let jn: J = Box::new(|x| Some(vec![vec![-1.0 / (x[0] * x[0])]]));
        assert!(run(&f, &jn, &opts(&[false])).is_empty());
        // Wrong lengths.
        let f: F = Box::new(|x| Some(vec![x[0], 1.0]));
        assert!(run(&f, &j, &opts(&[false])).is_empty());
        let f: F = Box::new(|x| Some(vec![x[0] - 1.0]));
        let jw: J = Box::new(|_| Some(vec![vec![1.0, 0.0]]));
        assert!(run(&f, &jw, &opts(&[false])).is_empty());
        // Jacobian with NaN entries, or identically zero.
        let jnan: J = Box::new(|_| Some(vec![vec![f64::NAN]]));
        assert!(run(&f, &jnan, &opts(&[false])).is_empty());
        let jz: J = Box::new(|_| Some(vec![vec![0.0]]));
        assert!(run(&f, &jz, &opts(&[false])).is_empty());
        // Degenerate options.
        let o = RootOptions {
            scale: f64::NAN,
            tol: f64::NAN,
            ..opts(&[false])
        };
        // Scale → 1, tol → 0: only exact zeros; Newton hits x = 1 exactly.
        assert_roots(&run(&f, &j, &o), &[&[1.0]], 0.0);
        assert!(run(&f, &j, &RootOptions::default()).is_empty());
        let o = RootOptions {
            starts: 0,
            ..opts(&[false])
        };
        assert!(run(&f, &j, &o).is_empty());
        let o = RootOptions {
            max_iter: 0,
            ..opts(&[false])
        };
        assert!(run(&f, &j, &o).is_empty());
        // A singular Jacobian everywhere with a root line: x + y = 1 twice.
        let f: F = Box::new(|x| Some(vec![x[0] + x[1] - 1.0, x[0] + x[1] - 1.0]));
        let j: J = Box::new(|_| Some(vec![vec![1.0, 1.0], vec![1.0, 1.0]]));
        let o = RootOptions {
            max_roots: 5,
            ..opts(&[false, false])
        };
        let roots = run(&f, &j, &o);
        assert!(!roots.is_empty());
    }

    #[test]
    fn linear_algebra() {
        let a = vec![
            vec![0.0, 2.0, 1.0],
            vec![1.0, -1.0, 0.0],
            vec![3.0, 0.0, -2.0],
        ];
        let x = solve(a, vec![7.0, -1.0, -3.0]).unwrap();
        for (s, t) in x.iter().zip([1.0, 2.0, 3.0]) {
            assert!((s - t).abs() < 1e-14);
        }
        assert!(solve(vec![vec![1.0, 2.0], vec![2.0, 4.0]], vec![1.0, 2.0]).is_none());
        assert!(solve(vec![vec![0.0]], vec![1.0]).is_none());
        assert!(solve(vec![vec![f64::INFINITY]], vec![1.0]).is_none());
    }

    #[test]
    fn deflation_gradient_matches_finite_differences() {
        let o = opts(&[false, true]);
        let f = |_: &[f64]| None;
        let j = |_: &[f64]| None;
        let p = Problem {
            f: &f,
            jac: &j,
            periodic: &o.periodic,
            max_iter: 0,
            threshold: 0.0,
            limit: 1e6,
            step_floor: 10.0,
        };
        let known = vec![
            Root {
                x: vec![0.3, 3.0],
                residual: 0.0,
            },
            Root {
                x: vec![-1.0, -0.5],
                residual: 0.0,
            },
        ];
        // ln M at x = (ln ‖G‖² − ln ‖F‖²)/2 with F = (1, 0).
        let log_m = |x: &[f64]| 0.5 * p.log_merit(x, &[1.0, 0.0], &known).unwrap();
        let x = [0.7, -2.9]; // near root 1 across the ±π seam
        let w = p.deflation_weight(&x, &known).unwrap();
        for i in 0..2 {
            let h = 1e-6;
            let (mut xp, mut xm) = (x, x);
            xp[i] += h;
            xm[i] -= h;
            let fd = (log_m(&xp) - log_m(&xm)) / (2.0 * h);
            assert!(
                (fd - w[i]).abs() < 1e-6 * (1.0 + w[i].abs()),
                "{fd} vs {}",
                w[i]
            );
        }
    }

    #[test]
    fn angle_wrapping() {
        assert_eq!(wrap_angle(-PI), PI);
        assert_eq!(wrap_angle(PI), PI);
        assert_eq!(wrap_angle(3.0 * PI), PI);
        assert_eq!(wrap_angle(-1e-20), 0.0);
        assert_eq!(wrap_angle(-0.0).to_bits(), 0.0f64.to_bits());
        assert!((wrap_angle(1.5 * PI) + 0.5 * PI).abs() < 1e-15);
        assert!(wrap_angle(f64::NAN).is_nan());
    }

    #[test]
    fn start_points_are_deterministic_and_in_the_box() {
        let o = RootOptions {
            scale: 2.0,
            ..opts(&[false, true, false, true])
        };
        let pts = start_points(&o);
        assert_eq!(pts.len(), 64);
        assert_eq!(pts, start_points(&o));
        assert_eq!(pts[0], vec![0.0; 4]);
        for x in &pts {
            assert!(x[0].abs() <= 2.0 && x[2].abs() <= 2.0);
            assert!(x[1] > -PI && x[1] <= PI && x[3] > -PI && x[3] <= PI);
        }
        // Full 3ⁿ grid for n = 2 (9 ≤ 32).
        let pts = start_points(&opts(&[false, false]));
        assert!(pts[..9].contains(&vec![5.0, -5.0]));
    }

    /// The random starts are SplitMix64's stream from SEED ^ n, bit for bit
    /// (the values are the reference algorithm's, computed outside Rust):
    /// the roots found, and so `equilibrium`'s output, depend on them.
    #[test]
    fn random_start_points_are_the_seeded_stream() {
        let o = RootOptions {
            scale: 2.0,
            ..opts(&[false, true, false, true])
        };
        let pts = start_points(&o);
        // the origin and the 8 points ±a·e_i come first
        assert_eq!(
            pts[9],
            [
                -1.6294310348067955,
                0.9440956163024272,
                -1.7859309296766868,
                1.5235121355808632
            ]
        );
        assert_eq!(
            pts[10],
            [
                1.0196211766566714,
                2.6503990116511376,
                0.8148141318053645,
                -1.9722688355012163
            ]
        );
    }
}
