//! Implicit Runge–Kutta methods: Radau IIA (order 5, L-stable, adaptive) for
//! stiff systems and Gauss–Legendre (order 6, symplectic, fixed step) for
//! conservative ones.
//!
//! * [`radau5`]: Hairer & Wanner's RADAU5 (Solving ODEs II, IV.8): the
//!   3-stage Radau IIA collocation method, its stage system transformed to
//!   one real and one complex linear system, simplified Newton iterations,
//!   Gustafsson's predictive step-size controller and the collocation
//!   polynomial as dense output.
//! * [`gauss6`]: the 3-stage Gauss–Legendre collocation method (Hairer,
//!   Lubich & Wanner, Geometric Numerical Integration, II.1.3 and VIII.6),
//!   stage equations solved by fixed-point iteration to round-off.
//!
//! All work arrays are allocated once per integration; the step loops do
//! not allocate (except to record the solution).

// Hairer's coefficients are kept digit for digit as published.
#![allow(clippy::excessive_precision)]

use super::{IntegratorOptions, Solution, Stats, Status, System};
use crate::dense::Lu;
use nalgebra::Complex;
use std::fmt;

/// Why an implicit integration could not start (invalid input).
#[derive(Clone, Debug, PartialEq)]
pub enum ImplicitError {
    /// `y0.len()` differs from `System::dim()`.
    DimensionMismatch {
        /// `System::dim()`.
        expected: usize,
        /// `y0.len()`.
        got: usize,
    },
    /// A fixed-step method ([`gauss6`]) was called without `IntegratorOptions::dt`.
    MissingStep,
    /// `IntegratorOptions::dt` is not a positive finite number.
    InvalidStep(f64),
    /// `t0` or `t_end` is not finite, or `t_end < t0`.
    InvalidInterval {
        /// The initial time given.
        t0: f64,
        /// The final time given.
        t_end: f64,
    },
    /// `rtol` must be finite and above 10·ε, `atol` finite and ≥ 0.
    InvalidTolerance {
        /// The relative tolerance given.
        rtol: f64,
        /// The absolute tolerance given.
        atol: f64,
    },
    /// The initial state has a non-finite component.
    NotFiniteInitialState,
}

impl fmt::Display for ImplicitError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ImplicitError::DimensionMismatch { expected, got } => {
                write!(
                    f,
                    "initial state has {got} components, the system {expected}"
                )
            }
            ImplicitError::MissingStep => {
                write!(
                    f,
                    "a fixed-step method needs a step size (IntegratorOptions::dt)"
                )
            }
            ImplicitError::InvalidStep(h) => write!(f, "step size {h} is not positive and finite"),
            ImplicitError::InvalidInterval { t0, t_end } => {
                write!(f, "invalid time interval [{t0}, {t_end}]")
            }
            ImplicitError::InvalidTolerance { rtol, atol } => {
                write!(f, "invalid tolerances rtol = {rtol}, atol = {atol}")
            }
            ImplicitError::NotFiniteInitialState => {
                write!(f, "the initial state has a non-finite component")
            }
        }
    }
}

impl std::error::Error for ImplicitError {}

/// The Jacobian ∂F/∂y at (t, y) into `jac` (row-major): analytic when the
/// system provides it, else forward differences with Hairer's increments
/// √(ε·max(1e-5, |y_i|)) (RADAU5's ESTRAD companion); `f0` = F(t, y).
fn jacobian(
    sys: &mut dyn System,
    t: f64,
    y: &mut [f64],
    f0: &[f64],
    jac: &mut [f64],
    tmp: &mut [f64],
    stats: &mut Stats,
) {
    stats.jacobians += 1;
    if sys.jacobian(t, y, jac) {
        return;
    }
    let n = y.len();
    for c in 0..n {
        let ysafe = y[c];
        let delt = (f64::EPSILON * ysafe.abs().max(1e-5)).sqrt();
        y[c] = ysafe + delt;
        sys.rhs(t, y, tmp);
        stats.rhs_evals += 1;
        for r in 0..n {
            jac[r * n + c] = (tmp[r] - f0[r]) / delt;
        }
        y[c] = ysafe;
    }
}

fn check_common(
    sys: &dyn System,
    y0: &[f64],
    opts: &IntegratorOptions,
) -> Result<(), ImplicitError> {
    if y0.len() != sys.dim() {
        return Err(ImplicitError::DimensionMismatch {
            expected: sys.dim(),
            got: y0.len(),
        });
    }
    if !opts.t0.is_finite() || !opts.t_end.is_finite() || opts.t_end < opts.t0 {
        return Err(ImplicitError::InvalidInterval {
            t0: opts.t0,
            t_end: opts.t_end,
        });
    }
    if y0.iter().any(|v| !v.is_finite()) {
        return Err(ImplicitError::NotFiniteInitialState);
    }
    Ok(())
}

/// Records the solution: at every step when `t_out` is empty, else at the
/// requested times inside [t0, t_end] (increasing; others skipped).
struct Recorder<'a> {
    t_out: &'a [f64],
    next: usize,
    t: Vec<f64>,
    y: Vec<Vec<f64>>,
}

impl<'a> Recorder<'a> {
    fn new(opts: &'a IntegratorOptions, y0: &[f64]) -> Self {
        let mut r = Recorder {
            t_out: &opts.t_out,
            next: 0,
            t: Vec::new(),
            y: Vec::new(),
        };
        if r.t_out.is_empty() {
            r.t.push(opts.t0);
            r.y.push(y0.to_vec());
        } else {
            while r.next < r.t_out.len() && (r.t_out[r.next] < opts.t0 || r.t_out[r.next].is_nan())
            {
                r.next += 1;
            }
            while r.next < r.t_out.len() && r.t_out[r.next] == opts.t0 {
                r.t.push(opts.t0);
                r.y.push(y0.to_vec());
                r.next += 1;
            }
        }
        r
    }

    /// After a step from `t_old` to `t_new`: record `y_new` (every-step
    /// mode), or every requested time in (t_old, t_new] by `interp(t, out)`.
    fn step(
        &mut self,
        t_old: f64,
        t_new: f64,
        y_new: &[f64],
        mut interp: impl FnMut(f64, &mut [f64]),
    ) {
        if self.t_out.is_empty() {
            self.t.push(t_new);
            self.y.push(y_new.to_vec());
            return;
        }
        while self.next < self.t_out.len() && self.t_out[self.next] <= t_new {
            let t = self.t_out[self.next];
            if t > t_old {
                let mut v = vec![0.0; y_new.len()];
                if t == t_new {
                    v.copy_from_slice(y_new);
                } else {
                    interp(t, &mut v);
                }
                self.t.push(t);
                self.y.push(v);
            }
            self.next += 1;
        }
    }

    fn finish(self, stats: Stats, status: Status) -> Solution {
        Solution {
            t: self.t,
            y: self.y,
            stats,
            status,
            stiff_at: None,
            event_poles: Vec::new(),
        }
    }
}

// ---------------------------------------------------------------------------
// Radau IIA, order 5.

/// √6, and the nodes c1 = (4 − √6)/10, c2 = (4 + √6)/10, c3 = 1.
const SQ6: f64 = 2.449_489_742_783_178;
const C1: f64 = (4.0 - SQ6) / 10.0;
const C2: f64 = (4.0 + SQ6) / 10.0;
const C1M1: f64 = C1 - 1.0;
const C2M1: f64 = C2 - 1.0;
const C1MC2: f64 = C1 - C2;
/// The error-estimate weights (γ0·h)⁻¹·(e1, e2, e3) of RADAU5's ESTRAD.
const DD1: f64 = -(13.0 + 7.0 * SQ6) / 3.0;
const DD2: f64 = (-13.0 + 7.0 * SQ6) / 3.0;
const DD3: f64 = -1.0 / 3.0;
/// T, with A⁻¹ = T·diag(γ, [[α, −β], [β, α]])·T⁻¹ (T32 = 1, T33 = 0), and
/// T⁻¹: Hairer's RADAU5 (radau5.f, RADCOR), checked by a unit test.
const T11: f64 = 9.123_239_487_089_294_279e-2;
const T12: f64 = -0.141_255_295_020_954_208_43;
const T13: f64 = -3.002_919_410_514_742_449_2e-2;
const T21: f64 = 0.241_717_932_707_107_018_96;
const T22: f64 = 0.204_129_352_293_799_931_99;
const T23: f64 = 0.382_942_112_757_261_937_79;
const T31: f64 = 0.966_048_182_615_092_936_19;
const TI11: f64 = 4.325_579_890_063_155_351;
const TI12: f64 = 0.339_199_251_815_809_869_54;
const TI13: f64 = 0.541_770_539_935_874_871_19;
const TI21: f64 = -4.178_718_591_551_904_727_3;
const TI22: f64 = -0.327_682_820_761_062_387_08;
const TI23: f64 = 0.476_623_554_500_550_451_96;
const TI31: f64 = -0.502_872_634_945_786_875_95;
const TI32: f64 = 2.571_926_949_855_605_429_2;
const TI33: f64 = -0.596_039_204_828_224_924_97;

/// The eigenvalues of A⁻¹: γ (real) and α ± iβ.
fn radau_eigen() -> (f64, f64, f64) {
    let c81 = 81f64.cbrt();
    let c9 = 9f64.cbrt();
    let u1 = (6.0 + c81 - c9) / 30.0;
    let alph = (12.0 - c81 + c9) / 60.0;
    let beta = (c81 + c9) * 3f64.sqrt() / 60.0;
    let cno = alph * alph + beta * beta;
    (1.0 / u1, alph / cno, beta / cno)
}

/// Integrate `sys` from `y0` over [t0, t_end] with Radau IIA of order 5
/// (Hairer & Wanner, Solving ODEs II, IV.8, the code RADAU5).
///
/// The stage system is solved by simplified Newton iterations on one real
/// system (γ/h − J) and one complex system ((α + iβ)/h − J), the
/// eigen-decomposition of the Butcher matrix; the Jacobian J (from
/// [`System::jacobian`], else forward differences) is kept while Newton
/// converges fast (θ ≤ 0.001), and the matrices are refactored only when h
/// changes by more than the ratio band [1, 1.2]. The error estimate is
/// filtered through (I − h·γ0·J)⁻¹ (IV.8.19–20), the step size follows
/// Gustafsson's predictive controller (IV.8.25) with factors in [1/5, 8],
/// and the tolerances are transformed as in RADAU5 (rtol' = 0.1·rtol^(2/3)).
/// Output at `IntegratorOptions::t_out` comes from the collocation polynomial
/// (order 3 in the step, uniformly; the step end values are of order 5).
///
/// The step starts at `IntegratorOptions::dt` when given, else at 1e-6. On failure
/// the solution so far is returned with `Status::StepTooSmall` (also after
/// five consecutive singular iteration matrices), `TooManySteps` or
/// `NotFinite`.
pub fn radau5(
    sys: &mut dyn System,
    y0: &[f64],
    opts: &IntegratorOptions,
) -> Result<Solution, ImplicitError> {
    radau5_core(sys, y0, opts, None)
}

/// Test hook: Radau IIA with the fixed step `opts.dt` and no error control
/// (Newton iterated to the tolerance of `opts.rtol`), for measuring the
/// order of convergence. Not for production use.
#[doc(hidden)]
pub fn radau5_fixed_step(
    sys: &mut dyn System,
    y0: &[f64],
    opts: &IntegratorOptions,
) -> Result<Solution, ImplicitError> {
    let dt = opts.dt.ok_or(ImplicitError::MissingStep)?;
    if !(dt > 0.0 && dt.is_finite()) {
        return Err(ImplicitError::InvalidStep(dt));
    }
    radau5_core(sys, y0, opts, Some(dt))
}

enum Next {
    Jacobian,
    Factor,
    Step,
}

fn radau5_core(
    sys: &mut dyn System,
    y0: &[f64],
    opts: &IntegratorOptions,
    fixed: Option<f64>,
) -> Result<Solution, ImplicitError> {
    check_common(sys, y0, opts)?;
    let (rtol_in, atol_in) = (opts.rtol, opts.atol);
    if !(rtol_in.is_finite()
        && rtol_in > 10.0 * f64::EPSILON
        && atol_in.is_finite()
        && atol_in >= 0.0)
    {
        return Err(ImplicitError::InvalidTolerance {
            rtol: rtol_in,
            atol: atol_in,
        });
    }
    if let Some(h) = opts.dt {
        if !(h > 0.0 && h.is_finite()) {
            return Err(ImplicitError::InvalidStep(h));
        }
    }
    let n = y0.len();
    let mut stats = Stats::default();
    let mut rec = Recorder::new(opts, y0);
    let (x0, xend) = (opts.t0, opts.t_end);
    if xend == x0 || n == 0 {
        return Ok(rec.finish(stats, Status::Done));
    }

    // Constants of RADCOR.
    let uround = f64::EPSILON;
    let rtol = 0.1 * rtol_in.powf(2.0 / 3.0);
    let atol = rtol * (atol_in / rtol_in);
    let fnewt = (10.0 * uround / rtol).max(0.03f64.min(rtol.sqrt()));
    let nit: usize = if fixed.is_some() { 50 } else { 7 };
    let safe = 0.9f64;
    let thet = 0.001;
    let (quot1, quot2) = (1.0, 1.2);
    let (facl, facr): (f64, f64) = (5.0, 1.0 / 8.0);
    let cfac = safe * (1 + 2 * nit) as f64;
    let hmax = xend - x0;
    let (u1, alph, beta) = radau_eigen();

    // Work arrays, allocated once.
    let mut y = y0.to_vec();
    let mut f0 = vec![0.0; n]; // F(x, y)
    let mut jac = vec![0.0; n * n];
    let mut e1 = Lu::new(n, 0.0);
    let mut e2 = Lu::new(n, Complex::new(0.0, 0.0));
    let mut cbuf = vec![Complex::new(0.0, 0.0); n];
    let (mut z1, mut z2, mut z3) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    let (mut w1, mut w2, mut w3) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    let (mut k1, mut k2, mut k3) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    let mut cont = vec![0.0; 3 * n];
    let mut tmp = vec![0.0; n];
    let mut ev = vec![0.0; n];
    let mut scal = vec![0.0; n];
    let set_scal = |scal: &mut [f64], y: &[f64]| {
        for (s, v) in scal.iter_mut().zip(y) {
            *s = atol + rtol * v.abs();
        }
    };
    set_scal(&mut scal, &y);

    let mut x = x0;
    let mut h = fixed.or(opts.dt).unwrap_or(1e-6).min(hmax);
    let mut last = false;
    if x + h * 1.0001 - xend >= 0.0 {
        h = xend - x;
        last = true;
    }
    let (mut hold, mut hacc, mut erracc) = (h, h, 1.0);
    let mut faccon = 1.0f64;
    let mut theta: f64;
    let (mut first, mut reject, mut caljac) = (true, false, false);
    let mut nsing = 0;
    let mut attempts = 0usize;
    let (mut fac1, mut alphn, mut betan) = (0.0, 0.0, 0.0);
    sys.rhs(x, &y, &mut f0);
    stats.rhs_evals += 1;
    let mut next = Next::Jacobian;

    let status = 'outer: loop {
        match next {
            Next::Jacobian => {
                jacobian(sys, x, &mut y, &f0, &mut jac, &mut tmp, &mut stats);
                caljac = true;
                next = Next::Factor;
            }
            Next::Factor => {
                fac1 = u1 / h;
                alphn = alph / h;
                betan = beta / h;
                let shift = Complex::new(alphn, betan);
                for r in 0..n {
                    for c in 0..n {
                        let j = jac[r * n + c];
                        e1.a[r * n + c] = -j;
                        e2.a[r * n + c] = Complex::new(-j, 0.0);
                    }
                    e1.a[r * n + r] += fac1;
                    e2.a[r * n + r] += shift;
                }
                stats.factorizations += 1;
                if !(e1.factor() && e2.factor()) {
                    nsing += 1;
                    if nsing >= 5 || fixed.is_some() {
                        break 'outer Status::StepTooSmall { t: x };
                    }
                    h *= 0.5;
                    reject = true;
                    last = false;
                    stats.rejected += 1;
                    next = Next::Factor;
                    continue;
                }
                nsing = 0;
                next = Next::Step;
            }
            Next::Step => {
                attempts += 1;
                if attempts > opts.max_steps {
                    break 'outer Status::TooManySteps { t: x };
                }
                if 0.1 * h.abs() <= x.abs() * uround || !h.is_finite() {
                    break 'outer Status::StepTooSmall { t: x };
                }
                let xph = x + h;
                // Starting values for Newton: the last collocation
                // polynomial extrapolated (RADCOR, label 30).
                if first {
                    for v in [&mut z1, &mut z2, &mut z3, &mut w1, &mut w2, &mut w3] {
                        v.fill(0.0);
                    }
                } else {
                    let c3q = h / hold;
                    let c1q = C1 * c3q;
                    let c2q = C2 * c3q;
                    for i in 0..n {
                        let (ak1, ak2, ak3) = (cont[i], cont[n + i], cont[2 * n + i]);
                        let a = c1q * (ak1 + (c1q - C2M1) * (ak2 + (c1q - C1M1) * ak3));
                        let b = c2q * (ak1 + (c2q - C2M1) * (ak2 + (c2q - C1M1) * ak3));
                        let c = c3q * (ak1 + (c3q - C2M1) * (ak2 + (c3q - C1M1) * ak3));
                        z1[i] = a;
                        z2[i] = b;
                        z3[i] = c;
                        w1[i] = TI11 * a + TI12 * b + TI13 * c;
                        w2[i] = TI21 * a + TI22 * b + TI23 * c;
                        w3[i] = TI31 * a + TI32 * b + TI33 * c;
                    }
                }
                // Simplified Newton iterations.
                faccon = faccon.max(uround).powf(0.8);
                theta = thet;
                let mut newt = 0usize;
                let (mut dynold, mut thqold) = (0.0f64, 0.0f64);
                let mut newton_failed = false;
                let mut slow = false;
                loop {
                    if newt >= nit {
                        newton_failed = true;
                        break;
                    }
                    for i in 0..n {
                        tmp[i] = y[i] + z1[i];
                    }
                    sys.rhs(x + C1 * h, &tmp, &mut k1);
                    for i in 0..n {
                        tmp[i] = y[i] + z2[i];
                    }
                    sys.rhs(x + C2 * h, &tmp, &mut k2);
                    for i in 0..n {
                        tmp[i] = y[i] + z3[i];
                    }
                    sys.rhs(xph, &tmp, &mut k3);
                    stats.rhs_evals += 3;
                    for i in 0..n {
                        let (a, b, c) = (k1[i], k2[i], k3[i]);
                        let r1 = TI11 * a + TI12 * b + TI13 * c - fac1 * w1[i];
                        let r2 = TI21 * a + TI22 * b + TI23 * c - alphn * w2[i] + betan * w3[i];
                        let r3 = TI31 * a + TI32 * b + TI33 * c - betan * w2[i] - alphn * w3[i];
                        k1[i] = r1;
                        cbuf[i] = Complex::new(r2, r3);
                    }
                    e1.solve(&mut k1);
                    e2.solve(&mut cbuf);
                    let mut dyno = 0.0;
                    for i in 0..n {
                        k2[i] = cbuf[i].re;
                        k3[i] = cbuf[i].im;
                        let s = scal[i];
                        dyno += (k1[i] / s).powi(2) + (k2[i] / s).powi(2) + (k3[i] / s).powi(2);
                    }
                    newt += 1;
                    let dyno = (dyno / (3 * n) as f64).sqrt();
                    if !dyno.is_finite() {
                        newton_failed = true;
                        break;
                    }
                    if newt > 1 && newt < nit {
                        let thq = dyno / dynold;
                        theta = if newt == 2 {
                            thq
                        } else {
                            (thq * thqold).sqrt()
                        };
                        thqold = thq;
                        if theta < 0.99 {
                            faccon = theta / (1.0 - theta);
                            let dyth = faccon * dyno * theta.powi((nit - 1 - newt) as i32) / fnewt;
                            if dyth >= 1.0 && fixed.is_none() {
                                let qnewt = dyth.clamp(1e-4, 20.0);
                                let hhfac =
                                    0.8 * qnewt.powf(-1.0 / (4.0 + (nit - 1 - newt) as f64));
                                h *= hhfac;
                                slow = true;
                                break;
                            }
                        } else {
                            newton_failed = true;
                            break;
                        }
                    }
                    dynold = dyno.max(uround);
                    for i in 0..n {
                        w1[i] += k1[i];
                        w2[i] += k2[i];
                        w3[i] += k3[i];
                        z1[i] = T11 * w1[i] + T12 * w2[i] + T13 * w3[i];
                        z2[i] = T21 * w1[i] + T22 * w2[i] + T23 * w3[i];
                        z3[i] = T31 * w1[i] + w2[i];
                    }
                    if faccon * dyno <= fnewt {
                        break;
                    }
                }
                if newton_failed || slow {
                    if newton_failed {
                        if fixed.is_some() {
                            break 'outer Status::StepTooSmall { t: x };
                        }
                        h *= 0.5;
                    }
                    stats.rejected += 1;
                    reject = true;
                    last = false;
                    next = if caljac { Next::Factor } else { Next::Jacobian };
                    continue;
                }

                // Error estimate (ESTRAD).
                let err = if fixed.is_some() {
                    0.0
                } else {
                    let (hee1, hee2, hee3) = (DD1 / h, DD2 / h, DD3 / h);
                    for i in 0..n {
                        tmp[i] = hee1 * z1[i] + hee2 * z2[i] + hee3 * z3[i];
                        ev[i] = tmp[i] + f0[i];
                    }
                    e1.solve(&mut ev);
                    let mut err = rms(&ev, &scal).max(1e-10);
                    if err >= 1.0 && (first || reject) {
                        for i in 0..n {
                            ev[i] += y[i];
                        }
                        sys.rhs(x, &ev, &mut k1);
                        stats.rhs_evals += 1;
                        for i in 0..n {
                            ev[i] = k1[i] + tmp[i];
                        }
                        e1.solve(&mut ev);
                        err = rms(&ev, &scal).max(1e-10);
                    }
                    err
                };
                if !err.is_finite() {
                    break 'outer Status::NotFinite { t: x };
                }

                // The new step size, Gustafsson's predictive controller.
                let fac = safe.min(cfac / (newt + 2 * nit) as f64);
                let mut quot = facr.max(facl.min(err.powf(0.25) / fac));
                let mut hnew = h / quot;
                if err < 1.0 {
                    first = false;
                    stats.steps += 1;
                    if stats.steps > 1 {
                        let facgus =
                            ((hacc / h) * (err * err / erracc).powf(0.25) / safe).clamp(facr, facl);
                        quot = quot.max(facgus);
                        hnew = h / quot;
                    }
                    hacc = h;
                    erracc = err.max(1e-2);
                    let xold = x;
                    hold = h;
                    x = xph;
                    for i in 0..n {
                        y[i] += z3[i];
                        let c1 = (z2[i] - z3[i]) / C2M1;
                        let ak = (z1[i] - z2[i]) / C1MC2;
                        let acont3 = (ak - z1[i] / C1) / C2;
                        let c2 = (ak - c1) / C1M1;
                        cont[i] = c1;
                        cont[n + i] = c2;
                        cont[2 * n + i] = c2 - acont3;
                    }
                    if y.iter().any(|v| !v.is_finite()) {
                        break 'outer Status::NotFinite { t: x };
                    }
                    set_scal(&mut scal, &y);
                    rec.step(xold, x, &y, |t, out| {
                        let s = (t - x) / hold;
                        for i in 0..n {
                            out[i] = y[i]
                                + s * (cont[i]
                                    + (s - C2M1) * (cont[n + i] + (s - C1M1) * cont[2 * n + i]));
                        }
                    });
                    caljac = false;
                    if last {
                        break 'outer Status::Done;
                    }
                    sys.rhs(x, &y, &mut f0);
                    stats.rhs_evals += 1;
                    if let Some(dt) = fixed {
                        hnew = dt;
                    }
                    hnew = hnew.min(hmax);
                    if reject {
                        hnew = hnew.min(h);
                    }
                    reject = false;
                    if x + hnew / quot1 - xend >= 0.0
                        || (fixed.is_some() && x + hnew * (1.0 + 1e-9) >= xend)
                    {
                        h = xend - x;
                        last = true;
                    } else {
                        let qt = hnew / h;
                        if theta <= thet && (quot1..=quot2).contains(&qt) {
                            next = Next::Step;
                            continue;
                        }
                        h = hnew;
                    }
                    next = if theta <= thet {
                        Next::Factor
                    } else {
                        Next::Jacobian
                    };
                } else {
                    reject = true;
                    last = false;
                    if first {
                        h *= 0.1;
                    } else {
                        h = hnew;
                    }
                    stats.rejected += 1;
                    next = if caljac { Next::Factor } else { Next::Jacobian };
                }
            }
        }
    };
    Ok(rec.finish(stats, status))
}

/// √(Σ (v_i / s_i)² / n).
fn rms(v: &[f64], s: &[f64]) -> f64 {
    let sum: f64 = v.iter().zip(s).map(|(a, b)| (a / b).powi(2)).sum();
    (sum / v.len() as f64).sqrt()
}

// ---------------------------------------------------------------------------
// Gauss–Legendre, 3 stages, order 6.

/// √15, the nodes c = 1/2 ∓ √15/10, 1/2 and the Butcher matrix and weights
/// of the 3-stage Gauss method (Hairer, Nørsett & Wanner, Solving ODEs I,
/// II.7, Table 7.4).
const SQ15: f64 = 3.872_983_346_207_417;
const GC: [f64; 3] = [0.5 - SQ15 / 10.0, 0.5, 0.5 + SQ15 / 10.0];
const GA: [[f64; 3]; 3] = [
    [
        5.0 / 36.0,
        2.0 / 9.0 - SQ15 / 15.0,
        5.0 / 36.0 - SQ15 / 30.0,
    ],
    [
        5.0 / 36.0 + SQ15 / 24.0,
        2.0 / 9.0,
        5.0 / 36.0 - SQ15 / 24.0,
    ],
    [
        5.0 / 36.0 + SQ15 / 30.0,
        2.0 / 9.0 + SQ15 / 15.0,
        5.0 / 36.0,
    ],
];
const GB: [f64; 3] = [5.0 / 18.0, 4.0 / 9.0, 5.0 / 18.0];

/// The Lagrange basis on the nodes {0, c1, c2, c3}: ℓ_j(θ) for the node
/// c_j (j = 0, 1, 2), so that the collocation polynomial of a step is
/// u(t0 + θh) = y0 + Σ_j Z_j·ℓ_j(θ).
fn gauss_basis(theta: f64) -> [f64; 3] {
    let mut l = [0.0; 3];
    for (j, lj) in l.iter_mut().enumerate() {
        let mut v = theta / GC[j];
        for (m, cm) in GC.iter().enumerate() {
            if m != j {
                v *= (theta - cm) / (GC[j] - cm);
            }
        }
        *lj = v;
    }
    l
}

/// The three stage derivatives of Gauss6: f[j] = F(t + c_j·h, y + z[j]),
/// with `tmp` as work space.
#[allow(clippy::too_many_arguments)]
fn gauss_stages(
    sys: &mut dyn System,
    t: f64,
    h: f64,
    y: &[f64],
    z: &[Vec<f64>; 3],
    tmp: &mut [f64],
    f: &mut [Vec<f64>; 3],
    stats: &mut Stats,
) {
    for j in 0..3 {
        for ((tc, yc), zc) in tmp.iter_mut().zip(y).zip(&z[j]) {
            *tc = yc + zc;
        }
        sys.rhs(t + GC[j] * h, tmp, &mut f[j]);
    }
    stats.rhs_evals += 3;
}

/// Maximum fixed-point iterations before falling back to Newton.
const GAUSS_FP_MAX: usize = 40;
/// Maximum Newton iterations of the fallback.
const GAUSS_NEWTON_MAX: usize = 30;

/// Integrate `sys` from `y0` over [t0, t_end] with the 3-stage
/// Gauss–Legendre collocation method (order 6) and the fixed step
/// `IntegratorOptions::dt` (required: [`ImplicitError::MissingStep`] without it; the
/// last step is shortened to land on t_end).
///
/// The method is symplectic and symmetric (Hairer, Lubich & Wanner,
/// Geometric Numerical Integration, VI.4): for a Hamiltonian system in
/// canonical variables y = (q, p) the energy error stays bounded, O(h⁶),
/// over exponentially long times, without drift. For y = (q, q̇) it is
/// symplectic only when the mass matrix is constant (p = M·q̇ is then a
/// linear change of variables, and Runge–Kutta methods commute with linear
/// maps, so the (q, q̇) run is the symplectic (q, p) one in other
/// coordinates). With a configuration-dependent M(q) it is not symplectic
/// in (q, q̇), but it stays symmetric (time-reversible), which for
/// reversible, integrable systems still keeps the energy error bounded
/// (GNI, XI), without the symplectic guarantee in general.
///
/// Stage equations Z = h·(A ⊗ I)·F(y0 + Z) are solved by fixed-point
/// iteration to round-off (until ‖ΔZ‖∞ ≤ ε·max(‖y‖∞, ‖Z‖∞) or the
/// increments stop decreasing at round-off level), starting from the previous step's
/// collocation polynomial extrapolated (GNI, VIII.6.1); when that does not
/// converge within 40 iterations, simplified Newton with the Jacobian at
/// the step start takes over. The update is summed with compensation
/// (Kahan) to keep round-off from drifting. Output at `IntegratorOptions::t_out` is
/// the collocation polynomial (order 3 between steps; step values order 6).
///
/// `rtol` and `atol` are not used. Stops with `Status::StepTooSmall` if
/// even Newton cannot solve the stage equations (h too large for the
/// problem), `NotFinite` or `TooManySteps`.
pub fn gauss6(
    sys: &mut dyn System,
    y0: &[f64],
    opts: &IntegratorOptions,
) -> Result<Solution, ImplicitError> {
    check_common(sys, y0, opts)?;
    let dt = opts.dt.ok_or(ImplicitError::MissingStep)?;
    if !(dt > 0.0 && dt.is_finite()) {
        return Err(ImplicitError::InvalidStep(dt));
    }
    let n = y0.len();
    let mut stats = Stats::default();
    let mut rec = Recorder::new(opts, y0);
    let span = opts.t_end - opts.t0;
    if span == 0.0 || n == 0 {
        return Ok(rec.finish(stats, Status::Done));
    }
    let q = span / dt;
    let nsteps = if (q - q.round()).abs() <= 1e-9 * q.max(1.0) {
        q.round().max(1.0)
    } else {
        q.ceil()
    };
    if nsteps > usize::MAX as f64 / 2.0 {
        return Err(ImplicitError::InvalidStep(dt));
    }
    let nsteps = nsteps as usize;

    let mut y = y0.to_vec();
    let mut yold = vec![0.0; n];
    let mut comp = vec![0.0; n];
    let mut z = [vec![0.0; n], vec![0.0; n], vec![0.0; n]];
    let mut zn = [vec![0.0; n], vec![0.0; n], vec![0.0; n]];
    let mut f = [vec![0.0; n], vec![0.0; n], vec![0.0; n]];
    let mut tmp = vec![0.0; n];
    // Newton fallback, allocated on first use.
    let mut newton: Option<(Vec<f64>, Lu<f64>, Vec<f64>)> = None;
    let mut have_prev = false;
    let mut hprev = dt;
    let mut t = opts.t0;

    let eps = f64::EPSILON;
    let mut status = Status::Done;
    for k in 0..nsteps {
        if k >= opts.max_steps {
            status = Status::TooManySteps { t };
            break;
        }
        let tnew = if k + 1 == nsteps {
            opts.t_end
        } else {
            opts.t0 + (k + 1) as f64 * dt
        };
        let h = if k + 1 == nsteps { tnew - t } else { dt };
        // Starting values: the last collocation polynomial at the new nodes.
        if have_prev {
            let r = h / hprev;
            let l1 = gauss_basis(1.0);
            for (i, zni) in zn.iter_mut().enumerate() {
                let li = gauss_basis(1.0 + r * GC[i]);
                let w = [li[0] - l1[0], li[1] - l1[1], li[2] - l1[2]];
                for c in 0..n {
                    zni[c] = w[0] * z[0][c] + w[1] * z[1][c] + w[2] * z[2][c];
                }
            }
            std::mem::swap(&mut z, &mut zn);
        } else {
            for zi in z.iter_mut() {
                zi.fill(0.0);
            }
        }
        let ynorm = y
            .iter()
            .fold(0.0f64, |a, v| a.max(v.abs()))
            .max(f64::MIN_POSITIVE);
        // Fixed-point iteration.
        let mut converged = false;
        let mut dold = f64::INFINITY;
        for it in 1..=GAUSS_FP_MAX {
            gauss_stages(sys, t, h, &y, &z, &mut tmp, &mut f, &mut stats);
            let (mut d, mut zmax) = (0.0f64, 0.0f64);
            for (i, zi) in z.iter_mut().enumerate() {
                for c in 0..n {
                    let v = h * (GA[i][0] * f[0][c] + GA[i][1] * f[1][c] + GA[i][2] * f[2][c]);
                    d = d.max((v - zi[c]).abs());
                    zmax = zmax.max(v.abs());
                    zi[c] = v;
                }
            }
            if !d.is_finite() {
                break;
            }
            let sc = ynorm.max(zmax);
            if d <= eps * sc || (it >= 3 && d >= dold && d <= 1e3 * eps * sc) {
                converged = true;
                break;
            }
            if it >= 3 && d >= dold {
                break; // diverging
            }
            dold = d;
        }
        if !converged {
            // Reset the stages and use simplified Newton.
            let (jac, lu, rhs) = newton
                .get_or_insert_with(|| (vec![0.0; n * n], Lu::new(3 * n, 0.0), vec![0.0; 3 * n]));
            sys.rhs(t, &y, &mut tmp);
            stats.rhs_evals += 1;
            // (jacobian() perturbs y one component at a time and restores it.)
            jacobian(sys, t, &mut y, &tmp, jac, &mut f[0], &mut stats);
            let m = 3 * n;
            for (bi, arow) in GA.iter().enumerate() {
                for (bj, aij) in arow.iter().enumerate() {
                    for r in 0..n {
                        for c in 0..n {
                            let delta = if bi == bj && r == c { 1.0 } else { 0.0 };
                            lu.a[(bi * n + r) * m + bj * n + c] = delta - h * aij * jac[r * n + c];
                        }
                    }
                }
            }
            stats.factorizations += 1;
            if !lu.factor() {
                status = Status::StepTooSmall { t };
                break;
            }
            for zi in z.iter_mut() {
                zi.fill(0.0);
            }
            let mut dold = f64::INFINITY;
            for it in 1..=GAUSS_NEWTON_MAX {
                gauss_stages(sys, t, h, &y, &z, &mut tmp, &mut f, &mut stats);
                for i in 0..3 {
                    for c in 0..n {
                        let g = h * (GA[i][0] * f[0][c] + GA[i][1] * f[1][c] + GA[i][2] * f[2][c]);
                        rhs[i * n + c] = g - z[i][c];
                    }
                }
                lu.solve(rhs);
                let (mut d, mut zmax) = (0.0f64, 0.0f64);
                for i in 0..3 {
                    for c in 0..n {
                        d = d.max(rhs[i * n + c].abs());
                        z[i][c] += rhs[i * n + c];
                        zmax = zmax.max(z[i][c].abs());
                    }
                }
                if !d.is_finite() {
                    break;
                }
                let sc = ynorm.max(zmax);
                if d <= eps * sc || (it >= 3 && d >= dold && d <= 1e3 * eps * sc) {
                    converged = true;
                    break;
                }
                if it >= 4 && d >= dold {
                    break;
                }
                dold = d;
            }
            if !converged {
                status = if z.iter().flatten().all(|v| v.is_finite()) {
                    Status::StepTooSmall { t }
                } else {
                    Status::NotFinite { t }
                };
                break;
            }
            gauss_stages(sys, t, h, &y, &z, &mut tmp, &mut f, &mut stats);
        }
        // y1 = y0 + h·Σ b_j F_j, with compensated summation.
        yold.copy_from_slice(&y);
        for c in 0..n {
            let inc = h * (GB[0] * f[0][c] + GB[1] * f[1][c] + GB[2] * f[2][c]) + comp[c];
            let ynew = y[c] + inc;
            comp[c] = (y[c] - ynew) + inc;
            y[c] = ynew;
        }
        if y.iter().any(|v| !v.is_finite()) {
            status = Status::NotFinite { t };
            break;
        }
        stats.steps += 1;
        let told = t;
        t = tnew;
        rec.step(told, t, &y, |tt, out| {
            let l = gauss_basis((tt - told) / h);
            for c in 0..n {
                out[c] = yold[c] + l[0] * z[0][c] + l[1] * z[1][c] + l[2] * z[2][c];
            }
        });
        have_prev = true;
        hprev = h;
    }
    Ok(rec.finish(stats, status))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The Radau IIA Butcher matrix (Solving ODEs II, Table IV.5.6).
    fn radau_a() -> [[f64; 3]; 3] {
        let s6 = 6f64.sqrt();
        [
            [
                (88.0 - 7.0 * s6) / 360.0,
                (296.0 - 169.0 * s6) / 1800.0,
                (-2.0 + 3.0 * s6) / 225.0,
            ],
            [
                (296.0 + 169.0 * s6) / 1800.0,
                (88.0 + 7.0 * s6) / 360.0,
                (-2.0 - 3.0 * s6) / 225.0,
            ],
            [(16.0 - s6) / 36.0, (16.0 + s6) / 36.0, 1.0 / 9.0],
        ]
    }

    fn mul(a: &[[f64; 3]; 3], b: &[[f64; 3]; 3]) -> [[f64; 3]; 3] {
        let mut c = [[0.0; 3]; 3];
        for i in 0..3 {
            for j in 0..3 {
                c[i][j] = (0..3).map(|k| a[i][k] * b[k][j]).sum();
            }
        }
        c
    }

    #[test]
    fn radau_transformation_diagonalizes_a_inverse() {
        let t = [[T11, T12, T13], [T21, T22, T23], [T31, 1.0, 0.0]];
        let ti = [[TI11, TI12, TI13], [TI21, TI22, TI23], [TI31, TI32, TI33]];
        let id = mul(&t, &ti);
        for (i, row) in id.iter().enumerate() {
            for (j, v) in row.iter().enumerate() {
                assert!(
                    (v - if i == j { 1.0 } else { 0.0 }).abs() < 1e-15,
                    "{i}{j} {v}"
                );
            }
        }
        // T⁻¹·A·T = Λ⁻¹, Λ = diag(γ, [[α, −β], [β, α]]).
        let (g, al, be) = radau_eigen();
        let lam = [[g, 0.0, 0.0], [0.0, al, -be], [0.0, be, al]];
        let prod = mul(&mul(&mul(&ti, &radau_a()), &t), &lam);
        for (i, row) in prod.iter().enumerate() {
            for (j, v) in row.iter().enumerate() {
                assert!(
                    (v - if i == j { 1.0 } else { 0.0 }).abs() < 1e-14,
                    "{i}{j} {v}"
                );
            }
        }
        // Row sums of A are the nodes; the last row is b (stiffly accurate).
        let a = radau_a();
        for (ai, ci) in a.iter().zip([C1, C2, 1.0]) {
            assert!((ai.iter().sum::<f64>() - ci).abs() < 1e-15);
        }
    }

    #[test]
    fn radau_error_weights_annihilate_order_conditions() {
        // The embedded formula ŷ1 − y1 = γ0·(h·f0 + Σ dd_i·Z_i) (Solving
        // ODEs II, IV.8.19) is exact (zero) for y = t^q, q ≤ 3:
        // Z_i = (c_i h)^q, f0 = δ_{q1}, i.e. δ_{q1} + Σ dd_i c_i^q = 0.
        let c = [C1, C2, 1.0];
        let d = [DD1, DD2, DD3];
        for q in 1..=3 {
            let f0 = if q == 1 { 1.0 } else { 0.0 };
            let s: f64 = (0..3).map(|i| d[i] * c[i].powi(q)).sum();
            assert!((s + f0).abs() < 1e-13, "q = {q}: {}", s + f0);
        }
    }

    #[test]
    fn gauss_order_and_symplecticity_conditions() {
        for i in 0..3 {
            assert!((GA[i].iter().sum::<f64>() - GC[i]).abs() < 1e-15);
        }
        // B(6): Σ b_i c_i^{k−1} = 1/k, k = 1..6.
        for k in 1..=6 {
            let s: f64 = (0..3).map(|i| GB[i] * GC[i].powi(k - 1)).sum();
            assert!((s - 1.0 / k as f64).abs() < 1e-15, "B({k})");
        }
        // C(3): Σ_j a_ij c_j^{k−1} = c_i^k / k.
        for i in 0..3 {
            for k in 1..=3 {
                let s: f64 = (0..3).map(|j| GA[i][j] * GC[j].powi(k - 1)).sum();
                assert!((s - GC[i].powi(k) / k as f64).abs() < 1e-15);
            }
        }
        // b_i a_ij + b_j a_ji = b_i b_j (Sanz-Serna, Lasagni).
        for i in 0..3 {
            for j in 0..3 {
                assert!((GB[i] * GA[i][j] + GB[j] * GA[j][i] - GB[i] * GB[j]).abs() < 1e-16);
            }
        }
        // The basis interpolates.
        let l = gauss_basis(GC[1]);
        assert!((l[0]).abs() < 1e-15 && (l[1] - 1.0).abs() < 1e-15 && l[2].abs() < 1e-15);
    }
}
