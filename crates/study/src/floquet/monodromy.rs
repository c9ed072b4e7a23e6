//! The monodromy matrix Φ(T) of x' = A(t)·x, its eigenvalues (the Floquet
//! multipliers) and what they certify.
//!
//! Φ is integrated by DOP853 twice, at a loose and a tight tolerance; the
//! multipliers of the two runs, matched, differ by about the loose run's
//! error, which bounds the tight run's (a thousand times smaller for an
//! eighth-order method). That difference, with a floor for rounding, is
//! the error `e` every claim must clear: unstable when some |μ| > 1 + e,
//! asymptotically stable when every |μ| < 1 − e; for a Lagrangian system
//! (multipliers in pairs μ, 1/μ̄) stable when every |μ| is within e of 1
//! and the multipliers are more than 2e apart (simple multipliers on the
//! unit circle stay there: Krein; for one coordinate, |tr Φ| < 2);
//! undecided otherwise — on a stability boundary, or too close to one for
//! the error.

use super::Prepared;
use crate::diag::{Diagnostic, ErrorKind};
use qdot_mechanics::solve::certify::significant;
use qdot_ode::{explicit, IntegratorOptions, Method, Status, System};

/// The loose and the tight relative tolerance (and absolute: Φ starts at I).
const LOOSE: f64 = 1e-10;
const TIGHT: f64 = 1e-13;
/// Rounding's share of the error: this many ulps of the largest |Φᵢⱼ|.
const ROUNDING_ULPS: f64 = 64.0;

/// A Floquet multiplier μ = re + i·im.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Multiplier {
    /// The real part.
    pub re: f64,
    /// The imaginary part.
    pub im: f64,
}

impl Multiplier {
    /// |μ|.
    pub fn abs(&self) -> f64 {
        self.re.hypot(self.im)
    }
    fn distance(&self, o: &Multiplier) -> f64 {
        (self.re - o.re).hypot(self.im - o.im)
    }
}

/// The stability of the reference motion.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Verdict {
    /// Every solution of the linearized equations stays bounded (or
    /// decays).
    Stable,
    /// Some solution grows without bound.
    Unstable,
    /// On a stability boundary, or closer to one than the error.
    Undecided,
}

impl Verdict {
    /// `stable`, `unstable` or `undecided`.
    pub fn name(self) -> &'static str {
        match self {
            Verdict::Stable => "stable",
            Verdict::Unstable => "unstable",
            Verdict::Undecided => "undecided",
        }
    }
}

/// The Floquet analysis at one set of parameter values.
#[derive(Clone, Debug)]
pub struct Floquet {
    /// The period T.
    pub period: f64,
    /// Φ(T), 2n × 2n row-major (x = (q, q̇)), from the tight run.
    pub monodromy: Vec<f64>,
    /// The multipliers (tight run), by decreasing |μ|, then decreasing
    /// imaginary part.
    pub multipliers: Vec<Multiplier>,
    /// tr Φ(T), the sum of the multipliers.
    pub trace: f64,
    /// The largest |μ|.
    pub max_abs: f64,
    /// The error bound of each multiplier (and of |μ|, tr Φ to within the
    /// dimension): the two runs' difference, at least the rounding.
    pub error: f64,
    /// The verdict.
    pub verdict: Verdict,
    /// Why (a sentence).
    pub note: String,
    /// The tight run's accepted steps.
    pub steps: usize,
}

/// Φ(T) and the multipliers at the parameter inputs `params`.
pub(super) fn analyse(p: &Prepared, params: &[f64]) -> Result<Floquet, Diagnostic> {
    let period = p.period(params)?;
    within_steps(p, params, period)?;
    if p.given_period.is_some() {
        p.check_given_period(params, period)?;
    }
    let (loose, _) = monodromy(p, params, period, LOOSE)?;
    let (phi, steps) = monodromy(p, params, period, TIGHT)?;
    let d = 2 * p.n();
    let mu = multipliers(&phi, d)?;
    let mu_loose = multipliers(&loose, d)?;
    let largest = phi.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let mut error = ROUNDING_ULPS * f64::EPSILON * largest.max(1.0);
    let mut used = vec![false; d];
    for m in &mu {
        let (k, dist) = mu_loose
            .iter()
            .enumerate()
            .filter(|(k, _)| !used[*k])
            .map(|(k, o)| (k, m.distance(o)))
            .fold((0, f64::INFINITY), |a, b| if b.1 < a.1 { b } else { a });
        if k < d {
            used[k] = true;
        }
        error = error.max(dist);
    }
    let trace = (0..d).map(|i| phi[i * d + i]).sum();
    let max_abs = mu.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let (verdict, note) = verdict(&mu, max_abs, error, p.lagrangian);
    Ok(Floquet {
        period,
        monodromy: phi,
        multipliers: mu,
        trace,
        max_abs,
        error,
        verdict,
        note,
        steps,
    })
}

/// The verdict and its reason, from the multipliers `mu`, their largest
/// modulus and the error bound.
fn verdict(mu: &[Multiplier], max_abs: f64, e: f64, lagrangian: bool) -> (Verdict, String) {
    if max_abs > 1.0 + e {
        return (
            Verdict::Unstable,
            format!(
                "|μ| = {} > 1: a solution grows by that factor every period",
                certified(max_abs, e)
            ),
        );
    }
    if max_abs < 1.0 - e {
        return (
            Verdict::Stable,
            "every |μ| < 1: every solution decays (asymptotically stable)".to_string(),
        );
    }
    let on_circle = mu.iter().all(|m| (m.abs() - 1.0).abs() <= e);
    let closest = mu
        .iter()
        .enumerate()
        .flat_map(|(i, a)| mu[i + 1..].iter().map(move |b| a.distance(b)))
        .fold(f64::INFINITY, f64::min);
    if lagrangian && on_circle && closest > 2.0 * e {
        return (
            Verdict::Stable,
            "every multiplier simple and on the unit circle, where a Lagrangian system keeps them"
                .to_string(),
        );
    }
    let why = if !lagrangian {
        "the largest |μ| is 1 within the error, and the system is not Lagrangian"
    } else if closest <= 2.0 * e {
        "on a stability boundary: two multipliers meet on the unit circle (within the error)"
    } else {
        "the largest |μ| is 1 within the error"
    };
    (Verdict::Undecided, why.to_string())
}

/// `x` with the digits the error `e` leaves certain (at most 15): fixed
/// decimals from 10⁻⁴ to 10⁶, scientific notation outside (as
/// [`significant`]); a value below the error is 0.
pub fn certified(x: f64, e: f64) -> String {
    let decimals = if e > 0.0 {
        ((-e.log10()).floor() as i32).min(15)
    } else {
        15
    };
    let exp = if x == 0.0 {
        i32::MIN / 2
    } else {
        x.abs().log10().floor() as i32
    };
    let digits = exp.saturating_add(1).saturating_add(decimals);
    if decimals >= 0 && (exp < 6 && (exp >= -4 || digits < 1)) {
        let s = format!("{x:.*}", decimals as usize);
        return if s
            .trim_start_matches('-')
            .chars()
            .all(|c| c == '0' || c == '.')
        {
            s.trim_start_matches('-').to_string()
        } else {
            s
        };
    }
    if digits < 1 || !x.is_finite() {
        return if x.is_finite() {
            "0".into()
        } else {
            format!("{x}")
        };
    }
    significant(x, digits.min(15) as usize)
}

/// The eigenvalues of the d × d row-major matrix `phi`, by decreasing
/// modulus, then decreasing imaginary part (a bounded iteration: its
/// failure is an error, not a hang).
fn multipliers(phi: &[f64], d: usize) -> Result<Vec<Multiplier>, Diagnostic> {
    let m = nalgebra::DMatrix::from_row_slice(d, d, phi);
    let mut mu: Vec<Multiplier> = qdot_mechanics::solve::eigen::general_eigenvalues(&m)
        .map_err(|e| {
            Diagnostic::global(format!(
                "the Floquet multipliers (the eigenvalues of the monodromy matrix) could not be computed: {e}"
            )).with_kind(ErrorKind::Convergence)
        })?
        .iter()
        .map(|z| Multiplier { re: z.re, im: z.im })
        .collect();
    mu.sort_by(|a, b| b.abs().total_cmp(&a.abs()).then(b.im.total_cmp(&a.im)));
    Ok(mu)
}

/// x' = A(t)·x for the d × d solution matrix, row-major.
struct Variational<'a> {
    p: &'a Prepared,
    n: usize,
    /// t, then the parameters.
    inputs: Vec<f64>,
    regs: Vec<f64>,
    /// M, C, K row-major.
    coefficients: Vec<f64>,
    /// M⁻¹·[K | C], n × 2n row-major.
    solved: Vec<f64>,
    /// Set when M is singular at some t.
    singular_at: Option<f64>,
}

impl System for Variational<'_> {
    fn dim(&self) -> usize {
        4 * self.n * self.n
    }
    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) {
        let n = self.n;
        let d = 2 * n;
        let prog = self.p.program();
        self.inputs[0] = t;
        let off = prog.input_offset();
        self.regs[off..off + self.inputs.len()].copy_from_slice(&self.inputs);
        prog.run(&mut self.regs);
        for (c, &r) in self.coefficients.iter_mut().zip(prog.output_registers()) {
            *c = self.regs[r as usize];
        }
        if !solve_mass(&mut self.coefficients, &mut self.solved, n) {
            self.singular_at.get_or_insert(t);
            dy.fill(f64::NAN);
            return;
        }
        // rows 0..n: q̇ = v; rows n..2n: v̇ = −M⁻¹K·q − M⁻¹C·v
        dy[..n * d].copy_from_slice(&y[n * d..]);
        for i in 0..n {
            let out = &mut dy[(n + i) * d..(n + i + 1) * d];
            out.fill(0.0);
            let row = &self.solved[i * d..(i + 1) * d];
            for (j, &a) in row.iter().enumerate() {
                if a != 0.0 {
                    for (o, x) in out.iter_mut().zip(&y[j * d..(j + 1) * d]) {
                        *o -= a * x;
                    }
                }
            }
        }
    }
}

/// Solve M·X = [K | C] by Gaussian elimination with partial pivoting;
/// `coefficients` holds M, C, K (row-major, n² each) and is overwritten.
/// False when M is singular.
fn solve_mass(coefficients: &mut [f64], x: &mut [f64], n: usize) -> bool {
    let d = 2 * n;
    let (m, rest) = coefficients.split_at_mut(n * n);
    let (c, k) = rest.split_at(n * n);
    for i in 0..n {
        x[i * d..i * d + n].copy_from_slice(&k[i * n..(i + 1) * n]);
        x[i * d + n..(i + 1) * d].copy_from_slice(&c[i * n..(i + 1) * n]);
    }
    for col in 0..n {
        let pivot = (col..n)
            .max_by(|&a, &b| m[a * n + col].abs().total_cmp(&m[b * n + col].abs()))
            .unwrap_or(col);
        if m[pivot * n + col] == 0.0 || !m[pivot * n + col].is_finite() {
            return false;
        }
        if pivot != col {
            for j in 0..n {
                m.swap(col * n + j, pivot * n + j);
            }
            for j in 0..d {
                x.swap(col * d + j, pivot * d + j);
            }
        }
        for r in col + 1..n {
            let f = m[r * n + col] / m[col * n + col];
            for j in col..n {
                m[r * n + j] -= f * m[col * n + j];
            }
            for j in 0..d {
                x[r * d + j] -= f * x[col * d + j];
            }
        }
    }
    for col in (0..n).rev() {
        for j in 0..d {
            let mut s = x[col * d + j];
            for k2 in col + 1..n {
                s -= m[col * n + k2] * x[k2 * d + j];
            }
            x[col * d + j] = s / m[col * n + col];
        }
    }
    true
}

impl<'a> Variational<'a> {
    /// The variational system of `p` at the parameter values `params`.
    fn new(p: &'a Prepared, params: &[f64]) -> Self {
        let n = p.n();
        let mut inputs = vec![0.0];
        inputs.extend_from_slice(params);
        Variational {
            p,
            n,
            inputs,
            regs: p.program().registers(),
            coefficients: vec![0.0; 3 * n * n],
            solved: vec![0.0; n * 2 * n],
            singular_at: None,
        }
    }
}

/// The d×d identity, row-major.
fn identity(d: usize) -> Vec<f64> {
    let mut id = vec![0.0; d * d];
    for i in 0..d {
        id[i * d + i] = 1.0;
    }
    id
}

/// Φ(T) at tolerance `tol`, and the accepted steps.
fn monodromy(
    p: &Prepared,
    params: &[f64],
    period: f64,
    tol: f64,
) -> Result<(Vec<f64>, usize), Diagnostic> {
    let d = 2 * p.n();
    let mut sys = Variational::new(p, params);
    let y0 = identity(d);
    let opts = IntegratorOptions {
        t0: 0.0,
        t_end: period,
        rtol: tol,
        atol: tol,
        dt: None,
        t_out: vec![period],
        max_steps: p.max_steps,
    };
    let sol = explicit::integrate(&mut sys, Method::Dop853, &y0, &opts).map_err(|e| {
        Diagnostic::global(format!("cannot integrate over the period: {e}"))
            .with_kind(ErrorKind::Integration)
    })?;
    if let Some(t) = sys.singular_at {
        return Err(Diagnostic::global(format!(
            "the linearized mass matrix M is singular at t = {t:.6e}"
        ))
        .with_hint("a singular M has no x' = A(t)·x: check the reference and the parameters")
        .with_kind(ErrorKind::Integration));
    }
    match (&sol.status, sol.y.last()) {
        (Status::Done, Some(y)) => Ok((y.clone(), sol.stats.steps)),
        (status, _) => Err(stopped(status, period, p.max_steps)),
    }
}

/// The error of an integration over the period that stopped at `status`.
fn stopped(status: &Status, period: f64, max_steps: usize) -> Diagnostic {
    let (t, why, hint) = match *status {
        Status::TooManySteps { t } => {
            // the steps so far, scaled to the whole period
            let needed = max_steps as f64 * period / t.max(f64::MIN_POSITIVE);
            (
                t,
                format!(
                    "it took the most steps allowed ({}) and had covered {} of the period",
                    crate::budget::grouped(max_steps),
                    percent(t / period)
                ),
                more_steps_hint("about", needed),
            )
        }
        Status::StepTooSmall { t } => (
            t,
            "the step size fell below what a double resolves there".to_string(),
            "the linearized solution may blow up there (a coefficient that is singular at these parameter values): check the parameters".to_string(),
        ),
        Status::NotFinite { t } => (
            t,
            "a value became infinite or not a number".to_string(),
            "the coefficients may not be finite over the period: check the parameters".to_string(),
        ),
        // no events are asked for, and a finished run records its end
        Status::Event { t } => (t, "it stopped at an event".to_string(), String::new()),
        Status::Done => (period, "it recorded no state".to_string(), String::new()),
    };
    let d = Diagnostic::global(format!(
        "the integration over the period T = {} stopped at t = {}: {why}",
        shortest(period),
        significant(t, 7)
    ))
    .with_kind(ErrorKind::Integration);
    if hint.is_empty() {
        d
    } else {
        d.with_hint(hint)
    }
}

/// `x` (a fraction) as a percentage with two significant digits.
fn percent(x: f64) -> String {
    format!("{}%", significant(100.0 * x, 2))
}

/// The hint for an integration that needs `needed` steps (`how`: "about",
/// or "at least" for a lower bound).
fn more_steps_hint(how: &str, needed: f64) -> String {
    let shorter = "choose parameter values with a shorter period";
    let n = significant(needed, 2);
    if needed <= 1e9 {
        format!(
            "the period is long against the motion's own time scale: raise --max-steps to {how} {n} (the time grows in proportion), or {shorter}"
        )
    } else {
        format!(
            "the period is long against the motion's own time scale, beyond any integration ({how} {n} steps): {shorter}"
        )
    }
}

/// Refuse a period that the steps allowed cannot cover: every explicit
/// method takes at least one step per radian of the fastest motion, whose
/// rate is the largest |eigenvalue| of A(t), sampled over the period.
fn within_steps(p: &Prepared, params: &[f64], period: f64) -> Result<(), Diagnostic> {
    let rate = fastest_rate(p, params, period);
    let needed = rate * period;
    if needed.is_nan() || needed <= p.max_steps as f64 {
        return Ok(());
    }
    Err(Diagnostic::global(format!(
        "the period T = {} is too long to integrate: the linearized motion turns at rates up to {} per unit time, so one period takes at least {} steps, more than the {} allowed",
        shortest(period),
        significant(rate, 3),
        significant(needed, 2),
        crate::budget::grouped(p.max_steps)
    ))
    .with_hint(more_steps_hint("at least", needed))
    .with_kind(ErrorKind::Integration))
}

/// The largest |eigenvalue| of A(t) at eight times over the period (0
/// where M is singular at all of them: the integration says so).
fn fastest_rate(p: &Prepared, params: &[f64], period: f64) -> f64 {
    let d = 2 * p.n();
    let mut sys = Variational::new(p, params);
    let identity = identity(d);
    let mut a = vec![0.0; d * d];
    let mut rate = 0.0f64;
    for i in 0..8 {
        sys.singular_at = None;
        sys.rhs((i as f64 + 0.37) * period / 8.0, &identity, &mut a);
        if sys.singular_at.is_some() || a.iter().any(|x| !x.is_finite()) {
            continue;
        }
        // a sample whose eigenvalues fail to converge adds nothing to the estimate
        for m in multipliers(&a, d).unwrap_or_default() {
            rate = rate.max(m.abs());
        }
    }
    rate
}

/// `x` with the shortest digits that read back to it, in scientific
/// notation below 10⁻⁴ and from 10⁶ on (as [`significant`]).
pub fn shortest(x: f64) -> String {
    let e = if x == 0.0 {
        0
    } else {
        x.abs().log10().floor() as i32
    };
    if (-4..6).contains(&e) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

#[cfg(test)]
mod tests {
    use super::{certified, shortest};

    #[test]
    fn certified_digits_are_scientific_outside_1e_minus4_to_1e6() {
        // the fixed range as before: the decimals the error leaves
        assert_eq!(certified(1.0000171314, 4e-11), "1.0000171314");
        assert_eq!(certified(-0.0923112, 1e-6), "-0.092311");
        assert_eq!(certified(3e-5, 1e-3), "0.000");
        assert_eq!(certified(-3e-5, 1e-3), "0.000");
        // small and large: scientific, the same certified digits
        assert_eq!(certified(5e-5, 1e-12), "5.0000000e-5");
        assert_eq!(certified(1.5e300, 1.4e286), "1.5000000000000e300");
        assert_eq!(certified(2.5e7, 0.01), "2.500000000e7");
        // below the error: 0, however large the error
        assert_eq!(certified(3.0, 1e4), "0");
        assert_eq!(certified(2.5e7, 1e4), "2.500e7");
    }

    #[test]
    fn shortest_reads_back_and_is_scientific_outside_1e_minus4_to_1e6() {
        assert_eq!(shortest(std::f64::consts::TAU), "6.283185307179586");
        assert_eq!(shortest(6283185.307179586), "6.283185307179586e6");
        assert_eq!(shortest(1e308), "1e308");
        assert_eq!(shortest(-2.5e-7), "-2.5e-7");
        assert_eq!(shortest(0.0), "0");
        assert_eq!(shortest(999999.0), "999999");
    }
}
