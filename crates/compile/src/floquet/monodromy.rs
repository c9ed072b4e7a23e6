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
use crate::diag::Diagnostic;
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

/// `x` with the decimals the error `e` leaves certain (at most 15).
pub fn certified(x: f64, e: f64) -> String {
    let decimals = if e > 0.0 {
        (-e.log10()).floor().clamp(0.0, 15.0) as usize
    } else {
        15
    };
    let s = format!("{x:.decimals$}");
    if s.trim_start_matches('-')
        .chars()
        .all(|c| c == '0' || c == '.')
    {
        s.trim_start_matches('-').to_string()
    } else {
        s
    }
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
            ))
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

/// Φ(T) at tolerance `tol`, and the accepted steps.
fn monodromy(
    p: &Prepared,
    params: &[f64],
    period: f64,
    tol: f64,
) -> Result<(Vec<f64>, usize), Diagnostic> {
    let n = p.n();
    let d = 2 * n;
    let mut inputs = vec![0.0];
    inputs.extend_from_slice(params);
    let mut sys = Variational {
        p,
        n,
        inputs,
        regs: p.program().registers(),
        coefficients: vec![0.0; 3 * n * n],
        solved: vec![0.0; n * d],
        singular_at: None,
    };
    let mut y0 = vec![0.0; d * d];
    for i in 0..d {
        y0[i * d + i] = 1.0;
    }
    let opts = IntegratorOptions {
        t0: 0.0,
        t_end: period,
        rtol: tol,
        atol: tol,
        dt: None,
        t_out: vec![period],
        max_steps: crate::limits::DEFAULT_MAX_STEPS,
    };
    let sol = explicit::integrate(&mut sys, Method::Dop853, &y0, &opts)
        .map_err(|e| Diagnostic::global(format!("cannot integrate over the period: {e}")))?;
    if let Some(t) = sys.singular_at {
        return Err(Diagnostic::global(format!(
            "the linearized mass matrix M is singular at t = {t:.6e}"
        ))
        .with_hint("a singular M has no x' = A(t)·x: check the reference and the parameters"));
    }
    let last = match (&sol.status, sol.y.last()) {
        (Status::Done, Some(y)) => y.clone(),
        (status, _) => {
            return Err(Diagnostic::global(format!(
                "the integration over the period T = {period:.6e} stopped early ({status:?})"
            ))
            .with_hint("check the parameters: the coefficients may not be finite over the period"))
        }
    };
    Ok((last, sol.stats.steps))
}
