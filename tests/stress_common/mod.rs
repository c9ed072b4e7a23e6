//! The stress experiments of the simulator, shared by `tests/stress.rs`
//! (small sizes, with assertions) and `examples/stress_report.rs` (full
//! sizes, written to `book/src/simulation/stress.md`).
//!
//! 1. [`energy_drift`]: the energy error of a pendulum over many periods.
//! 2. [`chain_accuracy`]: the f64 solve of M·q̈ = f against the exact one.
//! 3. [`stiff_run`]: a stiff spring pair, explicit vs implicit methods.
//! 4. [`chaos_parting`]: a chaotic double pendulum at several tolerances.

#![allow(dead_code)]

use nalgebra::DMatrix;
use num_rational::BigRational;
use qdot::num::Q;
use qdot::simulate::compile::{solve_spd, CompiledDynamics};
use qdot::simulate::elliptic::pendulum_period;
use qdot::simulate::problems::Problem;
use qdot::simulate::{integrate, IntegratorOptions, Method, Solution, Stats, Status};
use qdot::Expr;
// the random states' generator, for `tests/stress.rs` too
pub use qdot_exact::rng::SplitMix64;

// ===================================================================== 1

/// The pendulum of `problems::PENDULUM` with g = l = m = 1 released from rest
/// at θ0.
pub fn pendulum(theta0: f64) -> Problem {
    Problem {
        y0: vec![theta0, 0.0],
        ..Problem::pendulum()
    }
}

/// How one method is run in the drift experiment.
#[derive(Clone, Copy, Debug)]
pub enum Stepping {
    /// A fixed step T/`steps_per_period` (RK4, Gauss6).
    Fixed { steps_per_period: f64 },
    /// Adaptive with rtol = atol = `tol`.
    Adaptive { tol: f64 },
}

/// The energy error of one run of [`energy_drift`].
#[derive(Clone, Debug)]
pub struct Drift {
    /// The method and how it stepped.
    pub method: Method,
    pub stepping: Stepping,
    /// The period T.
    pub period: f64,
    /// (P, max |H − H0| over every accepted step of the first P periods),
    /// for each requested checkpoint P.
    pub checkpoints: Vec<(u64, f64)>,
    /// (P, H − H0) at the end of every chunk (P periods done).
    pub chunk_ends: Vec<(u64, f64)>,
    /// Log-spaced bins of periods (8 per decade): (last period of the bin,
    /// max |H − H0| over its steps), for the figure.
    pub bins: Vec<(f64, f64)>,
    /// Least-squares slope of H − H0 at the chunk ends against P, per period.
    pub rate: f64,
    /// The work, summed over the calls, and the wall-clock time.
    pub stats: Stats,
    pub seconds: f64,
    /// The final status (`Done` unless something failed).
    pub status: Status,
}

fn add_stats(a: &mut Stats, b: &Stats) {
    a.steps += b.steps;
    a.rejected += b.rejected;
    a.rhs_evals += b.rhs_evals;
    a.jacobians += b.jacobians;
    a.factorizations += b.factorizations;
}

/// Integrate the pendulum at θ0 for `periods` periods in chunks of `chunk`
/// periods (each a fresh call started from the last state, every accepted
/// step recorded and reduced to its energy error, then dropped), and
/// collect the energy error H − H0 of every accepted step.
pub fn energy_drift(
    theta0: f64,
    method: Method,
    stepping: Stepping,
    periods: u64,
    chunk: u64,
    checkpoints: &[u64],
) -> Drift {
    let start = std::time::Instant::now();
    let p = pendulum(theta0);
    let mut sys = p.dynamics().expect("the pendulum compiles");
    let energy = p.energy().expect("compiles").expect("conservative");
    let mut regs = energy.registers();
    let mut out = [0.0];
    let mut h_of = |t: f64, y: &[f64]| {
        energy.eval(&[t, y[0], y[1]], &mut regs, &mut out);
        out[0]
    };
    let period = pendulum_period(theta0, 1.0);
    let h0 = h_of(0.0, &p.y0);
    let mut y = p.y0.clone();
    let mut stats = Stats::default();
    let mut running = 0.0f64;
    let mut cps = Vec::new();
    let mut ends = Vec::new();
    let mut bins: Vec<(f64, f64)> = Vec::new();
    let mut bin_end = 1.0f64; // bins end at 10^(k/8) periods
    let mut bin_max = 0.0f64;
    let mut next_cp = 0;
    let mut done = 0u64;
    let mut status = Status::Done;
    while done < periods {
        let mut c = chunk.min(periods - done);
        if next_cp < checkpoints.len() && checkpoints[next_cp] > done {
            c = c.min(checkpoints[next_cp] - done);
        }
        let t0 = done as f64 * period;
        let t_end = (done + c) as f64 * period;
        let mut opts = IntegratorOptions {
            t0,
            t_end,
            max_steps: usize::MAX,
            ..IntegratorOptions::default()
        };
        match stepping {
            Stepping::Fixed { steps_per_period } => {
                opts.dt = Some(period / steps_per_period);
            }
            Stepping::Adaptive { tol } => {
                opts.rtol = tol;
                opts.atol = tol;
            }
        }
        let sol: Solution = integrate(&mut sys, method, &y, &opts).expect("runs");
        add_stats(&mut stats, &sol.stats);
        for (t, yy) in sol.t.iter().zip(&sol.y).skip(1) {
            let e = (h_of(*t, yy) - h0).abs();
            let per = t / period;
            while per > bin_end * (1.0 + 1e-12) {
                bins.push((bin_end, bin_max));
                bin_max = 0.0;
                bin_end *= 10f64.powf(0.125);
            }
            bin_max = bin_max.max(e);
            running = running.max(e);
        }
        done += c;
        while next_cp < checkpoints.len() && checkpoints[next_cp] <= done {
            cps.push((checkpoints[next_cp], running));
            next_cp += 1;
        }
        y = sol.y.last().expect("a state").clone();
        ends.push((done, h_of(t_end, &y) - h0));
        if sol.status != Status::Done {
            status = sol.status.clone();
            break;
        }
    }
    if bin_max > 0.0 {
        bins.push((bin_end.min(done as f64), bin_max));
    }
    Drift {
        method,
        stepping,
        period,
        checkpoints: cps,
        rate: slope(&ends),
        chunk_ends: ends,
        bins,
        stats,
        seconds: start.elapsed().as_secs_f64(),
        status,
    }
}

/// The least-squares slope of v against P.
fn slope(pts: &[(u64, f64)]) -> f64 {
    let n = pts.len() as f64;
    if pts.len() < 2 {
        return f64::NAN;
    }
    let mx = pts.iter().map(|p| p.0 as f64).sum::<f64>() / n;
    let my = pts.iter().map(|p| p.1).sum::<f64>() / n;
    let sxy: f64 = pts.iter().map(|p| (p.0 as f64 - mx) * (p.1 - my)).sum();
    let sxx: f64 = pts.iter().map(|p| (p.0 as f64 - mx).powi(2)).sum();
    sxy / sxx
}

// ===================================================================== 2

/// The n-link chain compiled from qdot's exact M and f (m = l = 1,
/// g = 9.81), and how long deriving and compiling took (s).
pub fn chain_dynamics(n: usize) -> (CompiledDynamics, f64, f64) {
    let t0 = std::time::Instant::now();
    let scene = qdot::Scene::parse(&qdot::engine::gallery::pendulum_chain(n)).expect("parses");
    let lag = scene.lagrange().expect("derives");
    let derive = t0.elapsed().as_secs_f64();
    let t1 = std::time::Instant::now();
    let p = Problem {
        params: vec![("m", 1.0), ("l", 1.0), ("g", 9.81)],
        ..Problem::chain10()
    };
    let d = CompiledDynamics::new(&lag, &p.param_map()).expect("compiles");
    (d, derive, t1.elapsed().as_secs_f64())
}

/// M (row-major) and f of the n-link chain at (q, q̇) by the closed form
/// M_ij = m l² (n − max(i, j)) cos(qi − qj),
/// f_i = −m l² Σ_j (n − max(i, j)) sin(qi − qj) q̇j² − m g l (n − i) sin qi
/// (0-based), with m = l = 1.
pub fn chain_closed_form(q: &[f64], qd: &[f64], g: f64) -> (Vec<f64>, Vec<f64>) {
    let n = q.len();
    let mut m = vec![0.0; n * n];
    let mut f = vec![0.0; n];
    for i in 0..n {
        for j in 0..n {
            let w = (n - i.max(j)) as f64;
            m[i * n + j] = w * (q[i] - q[j]).cos();
            f[i] -= w * (q[i] - q[j]).sin() * qd[j] * qd[j];
        }
        f[i] -= g * (n - i) as f64 * q[i].sin();
    }
    (m, f)
}

/// A random chain state: angles uniform in [−π, π), rates in [−2, 2).
pub fn random_state(rng: &mut SplitMix64, n: usize) -> (Vec<f64>, Vec<f64>) {
    let pi = std::f64::consts::PI;
    let q = (0..n).map(|_| rng.uniform(-pi, pi)).collect();
    let qd = (0..n).map(|_| rng.uniform(-2.0, 2.0)).collect();
    (q, qd)
}

/// The exact rational value of a finite f64.
pub fn exact(x: f64) -> Q {
    Q::from_big(BigRational::from_float(x).expect("finite"))
}

/// One solve of [`chain_accuracy`].
#[derive(Clone, Debug)]
pub struct SolveError {
    /// The number of links.
    pub n: usize,
    /// The 2-norm condition number of M (SVD in f64).
    pub cond: f64,
    /// ‖x_float − x_exact‖₂ / ‖x_exact‖₂, x_exact rounded to f64.
    pub rel_err: f64,
    /// Whether M·x − f = 0 held exactly for the exact x.
    pub residual_zero: bool,
    /// Seconds of the exact solve.
    pub exact_seconds: f64,
}

/// Solve M·x = f (f64 entries) by `solve_spd` and exactly (each entry the
/// rational it is; qdot's fraction-free solver), and compare.
pub fn compare_solves(m: &[f64], f: &[f64]) -> SolveError {
    let n = f.len();
    let mut mm = m.to_vec();
    let mut x = f.to_vec();
    solve_spd(&mut mm, &mut x, n).expect("M is positive definite");
    let t0 = std::time::Instant::now();
    let mq: Vec<Vec<Q>> = (0..n)
        .map(|i| (0..n).map(|j| exact(m[i * n + j])).collect())
        .collect();
    let fq: Vec<Q> = f.iter().map(|&v| exact(v)).collect();
    let a: Vec<Vec<Expr>> = mq
        .iter()
        .map(|r| r.iter().map(|q| Expr::rational(q.clone())).collect())
        .collect();
    let b: Vec<Expr> = fq.iter().map(|q| Expr::rational(q.clone())).collect();
    let sol = qdot::solve::linear::solve(&a, &b).expect("nonsingular");
    let xq: Vec<Q> = sol
        .iter()
        .map(|e| e.as_rational().expect("a number"))
        .collect();
    let exact_seconds = t0.elapsed().as_secs_f64();
    let residual_zero = (0..n).all(|i| {
        let mut s = Q::from_i64(0);
        for j in 0..n {
            s += &mq[i][j] * &xq[j];
        }
        (s - &fq[i]).is_zero()
    });
    let xe: Vec<f64> = xq.iter().map(|q| q.to_f64()).collect();
    let num: f64 = x
        .iter()
        .zip(&xe)
        .map(|(a, b)| (a - b).powi(2))
        .sum::<f64>()
        .sqrt();
    let den: f64 = xe.iter().map(|b| b * b).sum::<f64>().sqrt();
    let sv = DMatrix::from_row_slice(n, n, m).singular_values();
    let cond = sv.max() / sv.min();
    SolveError {
        n,
        cond,
        rel_err: num / den,
        residual_zero,
        exact_seconds,
    }
}

/// For each state: M and f of `dyn_` in f64, then [`compare_solves`].
pub fn chain_accuracy(dyn_: &mut CompiledDynamics, states: usize, seed: u64) -> Vec<SolveError> {
    let n = dyn_.n();
    let mut rng = SplitMix64::new(seed);
    let mut m = vec![0.0; n * n];
    let mut f = vec![0.0; n];
    (0..states)
        .map(|_| {
            let (q, qd) = random_state(&mut rng, n);
            dyn_.mass_and_forcing(0.0, &q, &qd, &mut m, &mut f)
                .expect("M and f");
            compare_solves(&m, &f)
        })
        .collect()
}

// ===================================================================== 3

/// Two unit masses: a soft spring k to the wall, a stiff one K = 1e6·k
/// between them, damped by c = K/1000 (the fast mode decays like
/// e^(−1000 t)): the scene of `tests/simulate_cli.rs`.
pub const STIFF: &str = "\
# Two masses, springs k and K = 1e6 k, the stiff one damped
coordinates x1, x2
parameters m, k, K
kinetic E = 1/2*m*(x1'^2 + x2'^2)
potential V = 1/2*k*x1^2 + 1/2*K*(x2 - x1)^2
rayleigh R = 1/2*K/1000*(x2' - x1')^2
";

/// The stiff pair with m = k = 1, K = 1e6, released at x1 = x2 = 1.
pub fn stiff_problem() -> Problem {
    Problem {
        name: "stiff_pair",
        title: "stiff spring pair",
        scene: STIFF.to_string(),
        params: vec![("m", 1.0), ("k", 1.0), ("K", 1e6)],
        y0: vec![1.0, 1.0, 0.0, 0.0],
        t_end: 10.0,
        ..Problem::pendulum()
    }
}

/// Integrate the stiff pair with `method` at rtol = `tol`, atol = `tol`/100
/// over [0, t_end], every accepted step recorded.
pub fn stiff_run(method: Method, tol: f64, t_end: f64) -> (Solution, f64) {
    let p = stiff_problem();
    let mut sys = p.dynamics().expect("compiles");
    let opts = IntegratorOptions {
        t_end,
        rtol: tol,
        atol: tol / 100.0,
        ..IntegratorOptions::default()
    };
    let t0 = std::time::Instant::now();
    let sol = integrate(&mut sys, method, &p.y0, &opts).expect("runs");
    (sol, t0.elapsed().as_secs_f64())
}

// ===================================================================== 4

/// The double pendulum (m = l = 1, g = 9.81) released from rest at (a, b).
pub fn double_pendulum(a: f64, b: f64, t_end: f64) -> Problem {
    Problem {
        y0: vec![a, b, 0.0, 0.0],
        t_end,
        ..Problem::double_pendulum()
    }
}

/// The trajectory of `p` by `method` at rtol = atol = `tol`, on the grid
/// k·`dt` (k = 0 … t_end/dt).
pub fn grid_run(p: &Problem, method: Method, tol: f64, dt: f64) -> Solution {
    let mut sys = p.dynamics().expect("compiles");
    let steps = (p.t_end / dt).round() as usize;
    let opts = IntegratorOptions {
        t_end: p.t_end,
        rtol: tol,
        atol: tol,
        t_out: (0..=steps).map(|k| k as f64 * dt).collect(),
        ..IntegratorOptions::default()
    };
    integrate(&mut sys, method, &p.y0, &opts).expect("runs")
}

/// The first grid time at which two runs' angles differ by more than
/// `gap` (None: never on the common grid).
pub fn parting_time(a: &Solution, b: &Solution, n: usize, gap: f64) -> Option<f64> {
    a.t.iter()
        .zip(a.y.iter().zip(&b.y))
        .find(|(_, (ya, yb))| (0..n).any(|i| (ya[i] - yb[i]).abs() > gap))
        .map(|(t, _)| *t)
}

/// max over angles of |a − b| at each grid time.
pub fn angle_gap(a: &Solution, b: &Solution, n: usize) -> Vec<(f64, f64)> {
    a.t.iter()
        .zip(a.y.iter().zip(&b.y))
        .map(|(t, (ya, yb))| {
            let d = (0..n).fold(0.0f64, |m, i| m.max((ya[i] - yb[i]).abs()));
            (*t, d)
        })
        .collect()
}
