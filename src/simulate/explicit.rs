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

mod tableaus;

use super::{initial_step, IntegratorOptions, Method, SimError, Solution, Stats, Status, System};
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

/// One integration's work space.
struct Stepper {
    kind: Kind,
    tab: &'static Tableau,
    n: usize,
    /// Stage derivatives, slot-major (`slots × n`); slot 0 = f(t, y).
    k: Vec<f64>,
    /// The last stage point of the step proper (kept for the stiffness test).
    ytmp: Vec<f64>,
    /// The proposed y(t + h).
    y_new: Vec<f64>,
    /// Error estimate vectors.
    err: Vec<f64>,
    err2: Vec<f64>,
    /// Dense-output coefficient vectors (`n_cont × n`).
    cont: Vec<f64>,
    /// The tableau's rows a and b without zeros.
    rows: Vec<Row>,
    b: Row,
    /// The weights of the (first) error estimate without zeros: DOPRI5's
    /// e, DOP853's 5th-order estimate, Vern7's b − b̂.
    est: Row,
    /// n zeros (the base point of an estimate).
    zeros: Vec<f64>,
}

/// A row of a Butcher tableau without its zeros: the slot offsets j·n and
/// the coefficients aⱼ of the nonzero entries (built once per integration).
#[derive(Clone, Debug, Default)]
struct Row {
    offsets: Vec<usize>,
    coefs: Vec<f64>,
}

impl Row {
    fn new(row: &[f64], n: usize) -> Row {
        let mut r = Row::default();
        for (j, &a) in row.iter().enumerate() {
            if a != 0.0 {
                r.offsets.push(j * n);
                r.coefs.push(a);
            }
        }
        r
    }
}

/// out = y + h Σⱼ aⱼ kⱼ over the nonzero entries of `row`.
///
/// Systems of dimension n ≤ 8 use a copy of the loop with n known at
/// compile time ([`combine_n`]), which the compiler unrolls into a few
/// vector instructions per stage; with n unknown, the per-stage loops of
/// length 2 or 4 cost more in overhead than in arithmetic (the `ode_solvers`
/// comparison of the work-precision report showed it). Larger systems add
/// one scaled stage vector at a time (axpy), which vectorizes.
fn combine(y: &[f64], h: f64, row: &Row, k: &[f64], n: usize, out: &mut [f64]) {
    match n {
        1 => combine_n::<1>(y, h, row, k, out),
        2 => combine_n::<2>(y, h, row, k, out),
        3 => combine_n::<3>(y, h, row, k, out),
        4 => combine_n::<4>(y, h, row, k, out),
        5 => combine_n::<5>(y, h, row, k, out),
        6 => combine_n::<6>(y, h, row, k, out),
        7 => combine_n::<7>(y, h, row, k, out),
        8 => combine_n::<8>(y, h, row, k, out),
        _ => {
            out.copy_from_slice(y);
            for (&base, &a) in row.offsets.iter().zip(&row.coefs) {
                let ha = h * a;
                for (o, &kv) in out.iter_mut().zip(&k[base..base + n]) {
                    *o += ha * kv;
                }
            }
        }
    }
}

/// [`combine`] for a dimension N known at compile time.
#[inline]
fn combine_n<const N: usize>(y: &[f64], h: f64, row: &Row, k: &[f64], out: &mut [f64]) {
    let mut acc = [0.0f64; N];
    for (&base, &a) in row.offsets.iter().zip(&row.coefs) {
        if let Ok(kj) = <&[f64; N]>::try_from(&k[base..base + N]) {
            for (s, kv) in acc.iter_mut().zip(kj) {
                *s += a * kv;
            }
        }
    }
    for ((o, yi), s) in out.iter_mut().zip(y).zip(&acc) {
        *o = yi + h * s;
    }
}

fn all_finite(v: &[f64]) -> bool {
    v.iter().all(|x| x.is_finite())
}

impl Stepper {
    fn new(kind: Kind, n: usize) -> Stepper {
        let tab = kind.tableau();
        Stepper {
            kind,
            tab,
            n,
            k: vec![0.0; tab.slots * n],
            ytmp: vec![0.0; n],
            y_new: vec![0.0; n],
            err: vec![0.0; n],
            err2: vec![0.0; n],
            cont: vec![0.0; kind.n_cont() * n],
            rows: tab.a.iter().map(|r| Row::new(r, n)).collect(),
            b: Row::new(tab.b, n),
            est: match kind {
                Kind::Rk4 => Row::default(),
                Kind::Dopri5 => Row::new(&tableaus::DOPRI5_E, n),
                Kind::Dop853 => Row::new(&tableaus::DOP853_ER, n),
                Kind::Vern7 => {
                    let e: Vec<f64> = tab
                        .b
                        .iter()
                        .zip(&tableaus::VERN7_BHAT)
                        .map(|(b, bh)| b - bh)
                        .collect();
                    Row::new(&e, n)
                }
            },
            zeros: vec![0.0; n],
        }
    }

    fn slot(&self, i: usize) -> &[f64] {
        &self.k[i * self.n..(i + 1) * self.n]
    }

    /// Compute the stages of slots `from..to` (each from the slots before it).
    #[allow(clippy::too_many_arguments)]
    fn stages<S: System + ?Sized>(
        &mut self,
        sys: &mut S,
        t: f64,
        y: &[f64],
        h: f64,
        from: usize,
        to: usize,
        stats: &mut Stats,
    ) {
        let n = self.n;
        for i in from..to {
            let (done, rest) = self.k.split_at_mut(i * n);
            combine(y, h, &self.rows[i], done, n, &mut self.ytmp);
            sys.rhs(t + self.tab.c[i] * h, &self.ytmp, &mut rest[..n]);
        }
        stats.rhs_evals += to.saturating_sub(from);
    }

    /// One attempted step from (t, y) with slot 0 = f(t, y): the stages, the
    /// proposed `y_new`, and the error norm (0 when `estimate` is false or
    /// the method has no estimator).
    #[allow(clippy::too_many_arguments, clippy::needless_range_loop)]
    fn attempt<S: System + ?Sized>(
        &mut self,
        sys: &mut S,
        t: f64,
        y: &[f64],
        h: f64,
        rtol: f64,
        atol: f64,
        estimate: bool,
        stats: &mut Stats,
    ) -> f64 {
        let n = self.n;
        let s = self.tab.s;
        self.stages(sys, t, y, h, 1, s, stats);
        combine(y, h, &self.b, &self.k, n, &mut self.y_new);
        if !estimate {
            return 0.0;
        }
        match self.kind {
            Kind::Rk4 => 0.0,
            Kind::Dopri5 => {
                // FSAL: slot 6 = f(t + h, y_new) enters the estimate
                let (_, rest) = self.k.split_at_mut(s * n);
                sys.rhs(t + h, &self.y_new, &mut rest[..n]);
                stats.rhs_evals += 1;
                combine(&self.zeros, h, &self.est, &self.k, n, &mut self.err);
                super::error_norm(&self.err, y, &self.y_new, rtol, atol)
            }
            Kind::Dop853 => {
                // 5th-order estimate `err`, 3rd-order estimate `err2`
                combine(&self.zeros, 1.0, &self.est, &self.k, n, &mut self.err);
                for i in 0..n {
                    let mut v = (self.y_new[i] - y[i]) / h;
                    for &(j, w) in &tableaus::DOP853_BHH {
                        v -= w * self.k[j * n + i];
                    }
                    self.err2[i] = v;
                }
                let (mut e5, mut e3) = (0.0, 0.0);
                for i in 0..n {
                    let sk = atol + rtol * y[i].abs().max(self.y_new[i].abs());
                    e5 += (self.err[i] / sk).powi(2);
                    e3 += (self.err2[i] / sk).powi(2);
                }
                let mut deno = e5 + 0.01 * e3;
                if deno <= 0.0 {
                    deno = 1.0;
                }
                h.abs() * e5 * (1.0 / (n.max(1) as f64 * deno)).sqrt()
            }
            Kind::Vern7 => {
                combine(&self.zeros, h, &self.est, &self.k, n, &mut self.err);
                super::error_norm(&self.err, y, &self.y_new, rtol, atol)
            }
        }
    }

    /// After acceptance: slot `s` = f(t + h, y_new) (already there for
    /// DOPRI5 when the estimate was made).
    fn finish<S: System + ?Sized>(
        &mut self,
        sys: &mut S,
        t: f64,
        h: f64,
        have_fsal: bool,
        stats: &mut Stats,
    ) {
        if self.kind == Kind::Dopri5 && have_fsal {
            return;
        }
        let n = self.n;
        let s = self.tab.s;
        let (_, rest) = self.k.split_at_mut(s * n);
        sys.rhs(t + h, &self.y_new, &mut rest[..n]);
        stats.rhs_evals += 1;
    }

    /// Hairer's stiffness estimate h·|λ| ≈ h·‖f(y₁) − f(ŷ)‖/‖y₁ − ŷ‖ with ŷ the
    /// last stage point (also at t + h).
    fn stiffness(&self, h: f64) -> Option<f64> {
        let s = self.tab.s;
        let (mut num, mut den) = (0.0, 0.0);
        for i in 0..self.n {
            num += (self.slot(s)[i] - self.slot(s - 1)[i]).powi(2);
            den += (self.y_new[i] - self.ytmp[i]).powi(2);
        }
        (den > 0.0).then(|| h.abs() * (num / den).sqrt())
    }

    /// Build the dense output of the accepted step (t, y) → (t + h, y_new),
    /// slot `s` holding f(t + h, y_new).
    #[allow(clippy::needless_range_loop)]
    fn prepare_dense<S: System + ?Sized>(
        &mut self,
        sys: &mut S,
        t: f64,
        y: &[f64],
        h: f64,
        stats: &mut Stats,
    ) {
        let n = self.n;
        let s = self.tab.s;
        if self.kind == Kind::Vern7 {
            self.stages(sys, t, y, h, s + 1, self.tab.slots, stats);
            // cont[0] = y, cont[k+1] = h Σᵢ bi[i][k] kᵢ
            self.cont[..n].copy_from_slice(y);
            for m in 0..7 {
                let c = &mut self.cont[(m + 1) * n..(m + 2) * n];
                c.fill(0.0);
                for (i, row) in tableaus::VERN7_BI.iter().enumerate() {
                    let w = h * row[m];
                    if w != 0.0 {
                        for (o, &kv) in c.iter_mut().zip(&self.k[i * n..(i + 1) * n]) {
                            *o += w * kv;
                        }
                    }
                }
            }
            return;
        }
        if self.kind == Kind::Dop853 {
            self.stages(sys, t, y, h, s + 1, self.tab.slots, stats);
        }
        // Hairer's form: y + θ(Δ + θ₁(hf₀ − Δ + θ(Δ − hf₁ − (hf₀ − Δ) + θ₁(…))))
        for i in 0..n {
            let ydiff = self.y_new[i] - y[i];
            let bspl = h * self.k[i] - ydiff;
            self.cont[i] = y[i];
            self.cont[n + i] = ydiff;
            self.cont[2 * n + i] = bspl;
            self.cont[3 * n + i] = ydiff - h * self.k[s * n + i] - bspl;
        }
        match self.kind {
            Kind::Dopri5 => {
                for i in 0..n {
                    let mut v = 0.0;
                    for (j, &d) in tableaus::DOPRI5_D.iter().enumerate() {
                        v += d * self.k[j * n + i];
                    }
                    self.cont[4 * n + i] = h * v;
                }
            }
            Kind::Dop853 => {
                for (r, drow) in tableaus::DOP853_D.iter().enumerate() {
                    for i in 0..n {
                        let mut v = 0.0;
                        for (j, &d) in drow.iter().enumerate() {
                            if d != 0.0 {
                                v += d * self.k[j * n + i];
                            }
                        }
                        self.cont[(4 + r) * n + i] = h * v;
                    }
                }
            }
            Kind::Rk4 | Kind::Vern7 => {}
        }
    }

    /// The dense output at θ = (t − t_step)/h into `out`.
    fn dense(&self, theta: f64, out: &mut [f64]) {
        let n = self.n;
        let m = self.kind.n_cont();
        let c = |j: usize, i: usize| self.cont[j * n + i];
        if self.kind == Kind::Vern7 {
            for (i, o) in out.iter_mut().enumerate() {
                let mut acc = c(7, i);
                for j in (1..7).rev() {
                    acc = c(j, i) + theta * acc;
                }
                *o = c(0, i) + theta * acc;
            }
            return;
        }
        let theta1 = 1.0 - theta;
        for (i, o) in out.iter_mut().enumerate() {
            // multiplier after coefficient j (0-based): θ for even j, θ₁ for odd
            let mut acc = c(m - 1, i);
            for j in (0..m - 1).rev() {
                let w = if j % 2 == 0 { theta } else { theta1 };
                acc = c(j, i) + w * acc;
            }
            *o = acc;
        }
    }
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
    let par = kind.params();
    let mut st = Stepper::new(kind, n);
    let mut stats = Stats::default();
    let mut sol = Solution {
        t: Vec::new(),
        y: Vec::new(),
        stats: Stats::default(),
        status: Status::Done,
        stiff_at: None,
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
    let mut facold: f64 = 1e-4;
    let mut reject = false;
    let mut last_nonfinite = false;
    let (mut iasti, mut nonsti) = (0usize, 0usize);
    let s = st.tab.s;

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
            if !err.is_finite() {
                // a stage left the domain or overflowed: retry smaller
                last_nonfinite = true;
                stats.rejected += 1;
                reject = true;
                h *= par.fac1;
                continue;
            }
            last_nonfinite = false;
            let fac11 = err.powf(par.expo);
            let fac =
                (fac11 / facold.powf(par.beta) / par.safe).clamp(1.0 / par.fac2, 1.0 / par.fac1);
            if err > 1.0 {
                stats.rejected += 1;
                reject = true;
                h /= (1.0 / par.fac1).min(fac11 / par.safe);
                continue;
            }
            facold = err.max(1e-4);
            let mut h_new = h / fac;
            if h_new.abs() > hmax {
                h_new = hmax * dir;
            }
            if reject {
                h_new = h_new.abs().min(h.abs()) * dir;
            }
            reject = false;
            st.finish(sys, t, h, true, &mut stats);
            accept_stiffness(&st, &par, h, t, &mut iasti, &mut nonsti, &mut sol);
            h_new
        };
        stats.steps += 1;
        if !all_finite(&st.y_new) || !all_finite(st.slot(s)) {
            return finish(sol, stats, Status::NotFinite { t });
        }
        let t_new = if last { t_end } else { t + h };
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
        std::mem::swap(&mut y, &mut st.y_new);
        st.k.copy_within(s * n..(s + 1) * n, 0);
        t = t_new;
        if last {
            return finish(sol, stats, Status::Done);
        }
        h = h_next;
    }
}

/// Hairer's stiffness bookkeeping after an accepted step: 15 positive tests
/// (h·|λ| > limit) without 6 negative ones in a row in between → stiff.
fn accept_stiffness(
    st: &Stepper,
    par: &Params,
    h: f64,
    t: f64,
    iasti: &mut usize,
    nonsti: &mut usize,
    sol: &mut Solution,
) {
    let Some(limit) = par.stiff_limit else {
        return;
    };
    if st.kind == Kind::Rk4 {
        return;
    }
    if let Some(hlamb) = st.stiffness(h) {
        if hlamb > limit {
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
            let te = if g_new == 0.0 {
                t_new
            } else {
                st.prepare_dense(sys, t, y, h, stats);
                dense_ready = true;
                let tol = 1e-12 * t.abs().max(t_new.abs()).max(h.abs());
                let stp: &Stepper = st;
                let mut g = |tt: f64| {
                    stp.dense((tt - t) / h, buf);
                    ev(tt, buf)
                };
                brent(&mut g, t, t_new, *g_prev, g_new, tol)
            };
            t_stop = te;
            hit = Some(te);
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
