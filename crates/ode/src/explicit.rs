//! Explicit Runge–Kutta methods: RK4 (fixed step), Dormand–Prince 5(4),
//! DOP853 and Verner's 7(6) (adaptive).
//!
//! The adaptive methods follow Hairer's codes `dopri5.f` and `dop853.f`
//! (Hairer, Nørsett & Wanner, Solving ODEs I, II.4–II.6 and II.10): the
//! weighted RMS error norm, the PI step-size controller
//! h_new = h·clamp(safe·err^(−expo)·err_old^β), the starting-step rule, FSAL,
//! Hairer's continuous extensions (order 4 for DOPRI5, 7 for DOP853) and his
//! stiffness test (h·|λ| estimated from the two last stages at t + h; the
//! test is made after every accepted step, i.e. `dopri5.f` with NSTIFF = 1).
//! Vern7 uses Verner's interpolant (6 extra stages; published as of order
//! 7, of order 6 by the continuous order conditions, see `tableaus`) and the
//! same controller with β = 0, and the same stiffness test on its two
//! stages at t + h (stage 10 and f(t + h, y₁)), with the limit 4.5 just
//! inside its real stability boundary 4.64.
//!
//! Output: every accepted step when `IntegratorOptions::t_out` is empty, else exactly
//! the requested times, evaluated by the dense output (RK4: the Hermite cubic
//! through the step's end values and slopes). Events: see
//! [`integrate_with_event`].
//!
//! The stage vectors are allocated once per integration; the step loop does
//! not allocate (except to record output).

mod combine;
mod stepper;
mod tableaus;

use super::{initial_step, IntegratorOptions, Method, SimError, Solution, Stats, Status, System};
use stepper::{all_finite, Stepper};
use tableaus::Tableau;

/// Integrate with an explicit method (`Rk4`, `Dopri5`, `Dop853`, `Vern7`);
/// see [`super::integrate`]. RK4 needs `opts.dt`.
pub fn integrate<S: System + ?Sized>(
    sys: &mut S,
    method: Method,
    y0: &[f64],
    opts: &IntegratorOptions,
) -> Result<Solution, SimError> {
    let fixed = method == Method::Rk4;
    run(sys, method, y0, opts, fixed, None)
}

/// Integrate until `event(t, y)` changes sign; see
/// [`super::integrate_with_event`].
pub fn integrate_with_event<S: System + ?Sized>(
    sys: &mut S,
    method: Method,
    y0: &[f64],
    opts: &IntegratorOptions,
    event: &mut dyn FnMut(f64, &[f64]) -> f64,
) -> Result<Solution, SimError> {
    let fixed = method == Method::Rk4;
    run(sys, method, y0, opts, fixed, Some(event))
}

/// Run any explicit method's formula with the fixed step `opts.dt` (the last
/// step shortened to land on `t_end`), without error control or stiffness
/// test: the hook with which the tests measure the order of convergence of
/// the adaptive pairs and of their dense output.
pub fn integrate_fixed<S: System + ?Sized>(
    sys: &mut S,
    method: Method,
    y0: &[f64],
    opts: &IntegratorOptions,
) -> Result<Solution, SimError> {
    run(sys, method, y0, opts, true, None)
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Kind {
    Rk4,
    Dopri5,
    Dop853,
    Vern7,
}

/// Hairer's controller parameters and the method's constants.
struct Params {
    /// Exponent of err in the step-size factor (1/q, q = lower order + 1),
    /// before the PI correction: expo = 1/q − 0.75·β.
    expo: f64,
    beta: f64,
    /// Bounds of h_new/h: `fac1` ≤ h_new/h ≤ `fac2`.
    fac1: f64,
    fac2: f64,
    safe: f64,
    /// The order used in the starting-step rule.
    order: i32,
    /// h·|λ| threshold of the stiffness test, if the method has one.
    stiff_limit: Option<f64>,
}

impl Kind {
    fn of(method: Method) -> Option<Kind> {
        match method {
            Method::Rk4 => Some(Kind::Rk4),
            Method::Dopri5 => Some(Kind::Dopri5),
            Method::Dop853 => Some(Kind::Dop853),
            Method::Vern7 => Some(Kind::Vern7),
            Method::Gauss6 | Method::Radau5 => None,
        }
    }

    fn tableau(self) -> &'static Tableau {
        match self {
            Kind::Rk4 => &tableaus::RK4,
            Kind::Dopri5 => &tableaus::DOPRI5,
            Kind::Dop853 => &tableaus::DOP853,
            Kind::Vern7 => &tableaus::VERN7,
        }
    }

    fn params(self) -> Params {
        match self {
            // dopri5.f defaults: BETA = 0.04, FAC1 = 0.2, FAC2 = 10
            Kind::Dopri5 | Kind::Rk4 => Params {
                expo: 0.2 - 0.04 * 0.75,
                beta: 0.04,
                fac1: 0.2,
                fac2: 10.0,
                safe: 0.9,
                order: 5,
                stiff_limit: Some(3.25),
            },
            // dop853.f defaults: BETA = 0, FAC1 = 0.333, FAC2 = 6
            Kind::Dop853 => Params {
                expo: 1.0 / 8.0,
                beta: 0.0,
                fac1: 0.333,
                fac2: 6.0,
                safe: 0.9,
                order: 8,
                stiff_limit: Some(6.1),
            },
            Kind::Vern7 => Params {
                expo: 1.0 / 7.0,
                beta: 0.0,
                fac1: 0.2,
                fac2: 10.0,
                safe: 0.9,
                order: 7,
                // just inside the real stability boundary 4.64 (tableaus'
                // test), as Hairer's 3.25 and 6.1 for DOPRI5 and DOP853
                stiff_limit: Some(4.5),
            },
        }
    }

    /// Number of coefficient vectors of the dense output.
    fn n_cont(self) -> usize {
        match self {
            Kind::Rk4 => 4,
            Kind::Dopri5 => 5,
            Kind::Dop853 | Kind::Vern7 => 8,
        }
    }
}

/// Whether g's sign change located at `te` in the step `span` is a zero:
/// |g| must shrink toward `te` like a continuous function's (at a pole it
/// grows, at a jump it stays), checked at two distances 1,000 times apart.
/// Where the step leaves no room for them, |g(te)| must be small beside
/// the step's end values `ends`.
fn is_zero_crossing(
    g: &mut dyn FnMut(f64) -> f64,
    te: f64,
    span: (f64, f64),
    ends: (f64, f64),
    tol: f64,
) -> bool {
    let at = g(te);
    if !at.is_finite() {
        return false;
    }
    if at == 0.0 {
        return true;
    }
    let room = (te - span.0).abs().min((span.1 - te).abs());
    let far = room / 2.0;
    let near = far * 1e-3;
    if near < 100.0 * tol {
        return at.abs() <= 1e-2 * ends.0.abs().max(ends.1.abs());
    }
    let size = |d: f64, g: &mut dyn FnMut(f64) -> f64| (g(te - d).abs(), g(te + d).abs());
    let (n1, n2) = size(near, g);
    let (f1, f2) = size(far, g);
    n1.is_finite() && n2.is_finite() && n1.max(n2) < 0.1 * f1.min(f2)
}

/// Brent's root finder (zeroin; Brent 1973, ch. 4) on [a, b] with
/// f(a)·f(b) < 0: returns a point within `tol` (+4ε|t|) of a sign change.
fn brent(f: &mut dyn FnMut(f64) -> f64, a0: f64, b0: f64, fa0: f64, fb0: f64, tol: f64) -> f64 {
    let (mut a, mut b, mut fa, mut fb) = (a0, b0, fa0, fb0);
    let (mut c, mut fc) = (a, fa);
    let mut d = b - a;
    let mut e = d;
    for _ in 0..200 {
        if (fb > 0.0 && fc > 0.0) || (fb < 0.0 && fc < 0.0) {
            c = a;
            fc = fa;
            d = b - a;
            e = d;
        }
        if fc.abs() < fb.abs() {
            a = b;
            b = c;
            c = a;
            fa = fb;
            fb = fc;
            fc = fa;
        }
        let tol1 = 2.0 * f64::EPSILON * b.abs() + 0.5 * tol;
        let xm = 0.5 * (c - b);
        if xm.abs() <= tol1 || fb == 0.0 {
            return b;
        }
        if e.abs() >= tol1 && fa.abs() > fb.abs() {
            let s = fb / fa;
            let (mut p, mut q);
            if a == c {
                p = 2.0 * xm * s;
                q = 1.0 - s;
            } else {
                let qq = fa / fc;
                let r = fb / fc;
                p = s * (2.0 * xm * qq * (qq - r) - (b - a) * (r - 1.0));
                q = (qq - 1.0) * (r - 1.0) * (s - 1.0);
            }
            if p > 0.0 {
                q = -q;
            } else {
                p = -p;
            }
            if 2.0 * p < (3.0 * xm * q - (tol1 * q).abs()).min((e * q).abs()) {
                e = d;
                d = p / q;
            } else {
                d = xm;
                e = d;
            }
        } else {
            d = xm;
            e = d;
        }
        a = b;
        fa = fb;
        b += if d.abs() > tol1 { d } else { tol1.copysign(xm) };
        fb = f(b);
    }
    b
}

fn check_inputs<S: System + ?Sized>(
    sys: &S,
    y0: &[f64],
    opts: &IntegratorOptions,
    fixed: bool,
) -> Result<(), SimError> {
    let bad = |s: String| Err(SimError::BadInput(s));
    if y0.len() != sys.dim() {
        return bad(format!(
            "y0 has {} components, the system {}",
            y0.len(),
            sys.dim()
        ));
    }
    if !opts.t0.is_finite() || !opts.t_end.is_finite() {
        return bad("t0 and t_end must be finite".into());
    }
    if fixed {
        match opts.dt {
            Some(dt) if dt.is_finite() && dt != 0.0 => {}
            _ => return bad("a fixed-step integration needs a finite, nonzero dt".into()),
        }
    } else {
        let ok = |x: f64| x.is_finite() && x >= 0.0;
        if !ok(opts.rtol) || !ok(opts.atol) || opts.rtol + opts.atol <= 0.0 {
            return bad("rtol and atol must be finite, ≥ 0 and not both 0".into());
        }
        if let Some(dt) = opts.dt {
            if !dt.is_finite() || dt == 0.0 {
                return bad("the initial step dt must be finite and nonzero".into());
            }
        }
    }
    Ok(())
}

/// An optional event function g(t, y).
type EventFn<'a> = Option<&'a mut dyn FnMut(f64, &[f64]) -> f64>;

/// The output times in the direction of integration (sorted; NaNs
/// dropped); times beyond t_end are never reached.
fn output_times(opts: &IntegratorOptions, dir: f64) -> Vec<f64> {
    let mut t_out: Vec<f64> = opts.t_out.iter().copied().filter(|t| !t.is_nan()).collect();
    t_out.sort_by(|a, b| (dir * a).total_cmp(&(dir * b)));
    t_out
}

/// Record the initial state (every step is recorded, or the output times
/// equal to t0); the index of the first output time still ahead.
fn record_initial(
    sol: &mut Solution,
    t_out: &[f64],
    t0: f64,
    dir: f64,
    y: &[f64],
    record_steps: bool,
) -> usize {
    let mut iout = 0;
    while iout < t_out.len() && (t_out[iout] - t0) * dir < 0.0 {
        iout += 1;
    }
    if record_steps {
        sol.t.push(t0);
        sol.y.push(y.to_vec());
    } else {
        while iout < t_out.len() && t_out[iout] == t0 {
            sol.t.push(t0);
            sol.y.push(y.to_vec());
            iout += 1;
        }
    }
    iout
}

/// The first step: `dt` (at most the whole interval for adaptive methods),
/// or Hairer's initial-step estimate.
#[allow(clippy::too_many_arguments)]
fn first_step<S: System + ?Sized>(
    sys: &mut S,
    st: &mut Stepper,
    opts: &IntegratorOptions,
    fixed: bool,
    y: &[f64],
    dir: f64,
    hmax: f64,
    stats: &mut Stats,
) -> f64 {
    let n = y.len();
    if fixed {
        opts.dt.unwrap_or(hmax).abs() * dir
    } else if let Some(dt) = opts.dt {
        dt.abs().min(hmax) * dir
    } else {
        let (y1, f1) = (&mut st.y_new, &mut st.err);
        initial_step(
            sys,
            opts.t0,
            y,
            &st.k[..n],
            dir,
            st.kind.params().order,
            hmax,
            opts.rtol,
            opts.atol,
            y1,
            f1,
            stats,
        )
    }
}

/// The solution as it ends, with its statistics.
fn finish(mut sol: Solution, stats: Stats, status: Status) -> Result<Solution, SimError> {
    sol.stats = stats;
    sol.status = status;
    Ok(sol)
}

/// The common driver of all explicit methods (Hairer's DOPRI5/DOP853
/// driver: step-size control with Lund stabilization, stiffness detection,
/// dense output).
fn run<S: System + ?Sized>(
    sys: &mut S,
    method: Method,
    y0: &[f64],
    opts: &IntegratorOptions,
    fixed: bool,
    mut event: EventFn<'_>,
) -> Result<Solution, SimError> {
    let Some(kind) = Kind::of(method) else {
        return Err(SimError::NotExplicit(method));
    };
    check_inputs(sys, y0, opts, fixed)?;
    let n = y0.len();
    let (t0, t_end) = (opts.t0, opts.t_end);
    let dir = if t_end >= t0 { 1.0 } else { -1.0 };
    let mut st = Stepper::new(kind, n);
    let mut stats = Stats::default();
    let mut sol = Solution {
        t: Vec::new(),
        y: Vec::new(),
        stats: Stats::default(),
        status: Status::Done,
        stiff_at: None,
        event_poles: Vec::new(),
    };
    let mut y = y0.to_vec();
    let mut buf = vec![0.0; n];

    let t_out = output_times(opts, dir);
    let t_out = &t_out[..];
    let record_steps = opts.t_out.is_empty();
    let mut iout = record_initial(&mut sol, t_out, t0, dir, &y, record_steps);

    sys.rhs(t0, &y, &mut st.k[..n]);
    stats.rhs_evals += 1;
    if !all_finite(&y) || !all_finite(&st.k[..n]) {
        return finish(sol, stats, Status::NotFinite { t: t0 });
    }
    let mut g_prev = match event.as_mut() {
        Some(ev) => ev(t0, &y),
        None => 0.0,
    };
    if t0 == t_end {
        return finish(sol, stats, Status::Done);
    }

    let hmax = (t_end - t0).abs();
    let mut h = first_step(sys, &mut st, opts, fixed, &y, dir, hmax, &mut stats);

    let mut t = t0;
    let mut ctl = Controller {
        par: kind.params(),
        facold: 1e-4,
        reject: false,
        hmax,
        dir,
    };
    let mut last_nonfinite = false;
    let (mut iasti, mut nonsti) = (0usize, 0usize);
    loop {
        if stats.steps + stats.rejected >= opts.max_steps {
            return finish(sol, stats, Status::TooManySteps { t });
        }
        if 0.1 * h.abs() <= t.abs() * f64::EPSILON || h == 0.0 {
            let status = if last_nonfinite {
                Status::NotFinite { t }
            } else {
                Status::StepTooSmall { t }
            };
            return finish(sol, stats, status);
        }
        let mut last = false;
        let slack = if fixed { 1.0 + 1e-10 } else { 1.01 };
        if (t + slack * h - t_end) * dir >= 0.0 {
            h = t_end - t;
            last = true;
        }

        let err = st.attempt(sys, t, &y, h, opts.rtol, opts.atol, !fixed, &mut stats);

        // the next step: the controller's for adaptive methods, h for fixed
        let h_next = if fixed {
            st.finish(sys, t, h, false, &mut stats);
            h
        } else {
            last_nonfinite = !err.is_finite();
            match ctl.judge(err, h) {
                Ok(h_new) => {
                    st.finish(sys, t, h, true, &mut stats);
                    h_new
                }
                Err(smaller) => {
                    stats.rejected += 1;
                    h = smaller;
                    continue;
                }
            }
        };
        stats.steps += 1;
        // the stiffness test (adaptive methods) and whether the step's end
        // is finite, in one pass
        let (finite, stiff) = st.check_end(h, if fixed { None } else { ctl.par.stiff_limit });
        if let Some(stiff) = stiff {
            count_stiffness(stiff, t, &mut iasti, &mut nonsti, &mut sol);
        }
        if !finite {
            return finish(sol, stats, Status::NotFinite { t });
        }
        let t_new = if last { t_end } else { t + h };
        // nothing to record or check in this step: skip the call
        let quiet = event.is_none()
            && !record_steps
            && t_out.get(iout).is_none_or(|&to| (to - t_new) * dir > 0.0);
        if !quiet {
            if let Some(te) = output(
                sys,
                &mut st,
                &mut sol,
                &mut stats,
                &mut event,
                &mut g_prev,
                t_out,
                &mut iout,
                record_steps,
                t,
                t_new,
                &y,
                h,
                &mut buf,
            ) {
                return finish(sol, stats, Status::Event { t: te });
            }
        }
        st.advance(&mut y);
        t = t_new;
        if last {
            return finish(sol, stats, Status::Done);
        }
        h = h_next;
    }
}

/// Hairer's step-size controller with Lund stabilization.
struct Controller {
    par: Params,
    /// The error norm of the last accepted step (at least 1e-4).
    facold: f64,
    /// The last attempt was rejected.
    reject: bool,
    hmax: f64,
    dir: f64,
}

impl Controller {
    /// The verdict on an attempt of step `h` with error norm `err`: the
    /// next step when it is accepted, else the smaller step to retry with
    /// (`err` not finite: a stage left the domain or overflowed).
    fn judge(&mut self, err: f64, h: f64) -> Result<f64, f64> {
        let par = &self.par;
        if !err.is_finite() {
            self.reject = true;
            return Err(h * par.fac1);
        }
        let fac11 = err.powf(par.expo);
        // with β = 0 (DOP853, Vern7) facold^β = 1 exactly: no pow call and
        // no division by it on the way to the next step
        let fac = if par.beta == 0.0 {
            fac11 / par.safe
        } else {
            fac11 / self.facold.powf(par.beta) / par.safe
        };
        let fac = fac.clamp(1.0 / par.fac2, 1.0 / par.fac1);
        if err > 1.0 {
            self.reject = true;
            return Err(h / (1.0 / par.fac1).min(fac11 / par.safe));
        }
        self.facold = err.max(1e-4);
        let mut h_new = h / fac;
        if h_new.abs() > self.hmax {
            h_new = self.hmax * self.dir;
        }
        if self.reject {
            h_new = h_new.abs().min(h.abs()) * self.dir;
        }
        self.reject = false;
        Ok(h_new)
    }
}

/// Hairer's stiffness bookkeeping after an accepted step: 15 positive tests
/// (h·|λ| > limit) without 6 negative ones in a row in between → stiff.
fn count_stiffness(stiff: bool, t: f64, iasti: &mut usize, nonsti: &mut usize, sol: &mut Solution) {
    if stiff {
        *nonsti = 0;
        *iasti += 1;
        if *iasti == 15 && sol.stiff_at.is_none() {
            sol.stiff_at = Some(t);
        }
    } else {
        *nonsti += 1;
        if *nonsti == 6 {
            *iasti = 0;
        }
    }
}

/// Record the accepted step (t, y) → (t_new, y_new): the event check, the
/// requested output times, or the step's end. Returns the event time when
/// the event function changed sign in the step.
#[allow(clippy::too_many_arguments)]
fn output<S: System + ?Sized>(
    sys: &mut S,
    st: &mut Stepper,
    sol: &mut Solution,
    stats: &mut Stats,
    event: &mut EventFn<'_>,
    g_prev: &mut f64,
    t_out: &[f64],
    iout: &mut usize,
    record_steps: bool,
    t: f64,
    t_new: f64,
    y: &[f64],
    h: f64,
    buf: &mut [f64],
) -> Option<f64> {
    let dir = h.signum();
    let mut dense_ready = false;
    let mut t_stop = t_new;
    let mut hit = None;
    if let Some(ev) = event.as_mut() {
        let g_new = ev(t_new, &st.y_new);
        let crossed = *g_prev != 0.0
            && g_new.is_finite()
            && (g_new == 0.0 || (g_new > 0.0) != (*g_prev > 0.0));
        if crossed {
            let (te, zero) = if g_new == 0.0 {
                (t_new, true)
            } else {
                st.prepare_dense(sys, t, y, h, stats);
                dense_ready = true;
                let tol = 1e-12 * t.abs().max(t_new.abs()).max(h.abs());
                let stp: &Stepper = st;
                let mut g = |tt: f64| {
                    stp.dense((tt - t) / h, buf);
                    ev(tt, buf)
                };
                let te = brent(&mut g, t, t_new, *g_prev, g_new, tol);
                let zero = is_zero_crossing(&mut g, te, (t, t_new), (*g_prev, g_new), tol);
                (te, zero)
            };
            if zero {
                t_stop = te;
                hit = Some(te);
            } else {
                sol.event_poles.push(te);
            }
        }
        if g_new.is_finite() && g_new != 0.0 {
            *g_prev = g_new;
        }
    }
    while *iout < t_out.len() && (t_out[*iout] - t_stop) * dir <= 0.0 {
        let to = t_out[*iout];
        if to == t_new {
            sol.y.push(st.y_new.clone());
        } else {
            if !dense_ready {
                st.prepare_dense(sys, t, y, h, stats);
                dense_ready = true;
            }
            st.dense((to - t) / h, buf);
            sol.y.push(buf.to_vec());
        }
        sol.t.push(to);
        *iout += 1;
    }
    if let Some(te) = hit {
        if sol.t.last() != Some(&te) {
            if te == t_new {
                sol.y.push(st.y_new.clone());
            } else {
                st.dense((te - t) / h, buf);
                sol.y.push(buf.to_vec());
            }
            sol.t.push(te);
        }
        return Some(te);
    }
    if record_steps {
        sol.t.push(t_new);
        sol.y.push(st.y_new.clone());
    }
    None
}
