//! The work-precision report: run time against error for every adaptive
//! method on every benchmark problem (`qdot::simulate::problems`), with the
//! peers measured side by side in the same run.
//!
//! ```text
//! cargo bench -p qdot-benches --bench work_precision            # the full report (~10 min)
//! cargo bench -p qdot-benches --bench work_precision -- --quick # 3 tolerances, no SciPy
//! ```
//!
//! writes `book/src/simulation/work-precision.md` (tables and the ratios at
//! equal error), one SVG diagram per problem beside it, and the raw numbers
//! in `benches/results/work_precision.json`.
//!
//! Series, each a sweep of rtol = atol = 1e-3 … 1e-13 (fixed-step methods:
//! a sweep of h = T/N):
//! * qdot's Dopri5, Dop853, Vern7, Radau5 on the compiled equations as
//!   machine code (`--evaluator jit`, what `auto` runs past 25,000
//!   right-hand sides), and RK4, Gauss6 at fixed steps;
//! * qdot's Dop853 on the same equations interpreted (`--evaluator
//!   interpreter`);
//! * qdot's Dop853 on a hand-written Rust right-hand side (`hand/mod.rs`),
//!   plain and tuned;
//! * the `ode_solvers` crate's Dop853 on the same compiled right-hand side;
//! * SciPy's `solve_ivp` (DOP853, RK45) on hand-written numpy right-hand
//!   sides, by `benches/wp_scipy.py` (needs `python3 -m pip install numpy
//!   scipy`; the report says when it was skipped).
//!
//! Time is the minimum over repeated runs (at least 3, until 0.3 s are
//! spent, unless one run takes over 1 s); error is max |yᵢ(T) − refᵢ| at
//! the final time against the exact solution or, for the double pendulum
//! and the chain, against Vern7 at rtol = atol = 1e-14 (whose distance to
//! DOP853 at 1e-14 is reported as the reference's own error); for
//! conservative problems also max |H − H0| over the accepted steps, and
//! for the constrained one (the Cartesian pendulum, integrated as the
//! Baumgarte-stabilized augmented system) max |g| over the accepted steps
//! (an untimed run).
//!
//! The report ends with the symbolic side (`wp_symbolic.rs`): the n-link
//! chain derived by qdot and SymEngine, and the 5-link chain's exact
//! accelerations by `qdot solve` as a process.
//!
//! For the constrained problem the report also measures Baumgarte's α:
//! the qdot adaptive methods at α = 0, 1 and 10 on [0, T] (time at equal
//! error, drift) and DOP853 over about 100 periods, where the drift of
//! α = 0 grows and that of α > 0 does not.

#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

#[path = "hand/mod.rs"]
mod hand;
mod wp_symbolic;

use hand::Hand;
use plotters::prelude::*;
use qdot::simulate::compile::{CompiledDynamics, Engine, Program};
use qdot::simulate::problems::Problem;
use qdot::simulate::{integrate, IntegratorOptions, Method, System};
use serde_json::{json, Value};
use std::cell::RefCell;
use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

/// One point of a work-precision curve.
#[derive(Clone, Debug)]
struct Point {
    /// The tolerance (adaptive) or the step h (fixed).
    tol: f64,
    seconds: f64,
    error: f64,
    energy_error: Option<f64>,
    /// max |g| over the constraints and the accepted steps.
    drift: Option<f64>,
    steps: usize,
    rhs: usize,
}

/// A curve: one method on one right-hand side.
#[derive(Clone, Debug)]
struct Series {
    label: String,
    /// `qdot`, `hand`, `ode_solvers`, `scipy`.
    family: &'static str,
    fixed_step: bool,
    points: Vec<Point>,
}

struct Report {
    problem: Problem,
    reference: Vec<f64>,
    /// The reference's own error (0 for closed forms).
    reference_error: f64,
    h0: Option<f64>,
    /// The check point (t = 0.7, y, F(t, y) compiled) the hand-written and
    /// SciPy right-hand sides must reproduce.
    check_y: Vec<f64>,
    check_dy: Vec<f64>,
    series: Vec<Series>,
    /// Baumgarte's α measured, for a problem with constraints.
    alpha: Option<AlphaStudy>,
}

/// The constrained problem at α = 0, 1, 10: one series per α and adaptive
/// method on [0, T], and one DOP853 run per α over `long_t`.
struct AlphaStudy {
    /// How many constraints the scene has.
    constraints: usize,
    alphas: Vec<f64>,
    /// (α, series) on [0, T].
    series: Vec<(f64, Series)>,
    long_t: f64,
    long_tol: f64,
    /// (α, point) over [0, long_t], its error against the exact solution.
    long: Vec<(f64, Point)>,
}

/// What a qdot point measures beside the final error: max |H − H0| and
/// max |g| over the accepted steps, each when the problem has it.
#[derive(Clone, Copy)]
struct Extra<'a> {
    energy: Option<(&'a Program, f64)>,
    constraints: Option<&'a Program>,
}

fn max_abs_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// The minimum time of `f` over repeated runs, and its last result. Short
/// runs repeat until 20 ms are spent (at most 1,000 runs): the minimum of
/// 50 runs of 25 µs still moved by ±15 % between reports on the shared
/// machine, while 300 interleaved runs of two drivers agree within 5 %
/// (`driver_cost PROBLEM time`).
fn time_min<R>(mut f: impl FnMut() -> R) -> (f64, R) {
    let (mut best, mut spent, mut runs) = (f64::INFINITY, 0.0, 0);
    loop {
        let t0 = Instant::now();
        let r = f();
        let s = t0.elapsed().as_secs_f64();
        best = best.min(s);
        spent += s;
        runs += 1;
        if s > 1.0 || (runs >= 3 && spent > 0.3) || (runs >= 50 && spent > 0.02) || runs >= 1000 {
            return (best, r);
        }
    }
}

/// H at every state of `ys` against H0: max |H − H0|.
fn energy_error(energy: &Program, h0: f64, ts: &[f64], ys: &[Vec<f64>]) -> f64 {
    let mut regs = energy.registers();
    let (mut input, mut out) = (Vec::new(), [0.0]);
    let mut worst: f64 = 0.0;
    for (t, y) in ts.iter().zip(ys) {
        input.clear();
        input.push(*t);
        input.extend_from_slice(y);
        energy.eval(&input, &mut regs, &mut out);
        worst = worst.max((out[0] - h0).abs());
    }
    worst
}

/// max |gⱼ| over the constraints and the states of `ys`.
fn constraint_drift(g: &Program, ts: &[f64], ys: &[Vec<f64>]) -> f64 {
    let mut regs = g.registers();
    let (mut input, mut out) = (Vec::new(), vec![0.0; g.n_outputs()]);
    let mut worst: f64 = 0.0;
    for (t, y) in ts.iter().zip(ys) {
        input.clear();
        input.push(*t);
        input.extend_from_slice(y);
        g.eval(&input, &mut regs, &mut out);
        worst = out.iter().fold(worst, |w, v| w.max(v.abs()));
    }
    worst
}

fn energy_at(energy: &Program, t: f64, y: &[f64]) -> f64 {
    let mut input = vec![t];
    input.extend_from_slice(y);
    let mut out = [0.0];
    energy.eval(&input, &mut energy.registers(), &mut out);
    out[0]
}

/// One qdot point: the timed run records the final state only; an untimed
/// run records every step for the energy error and the constraint drift.
fn qdot_point<S: System>(
    sys: &mut S,
    method: Method,
    p: &Problem,
    reference: &[f64],
    extra: Extra,
    tol: f64,
    fixed_step: bool,
) -> Option<Point> {
    let opts = IntegratorOptions {
        t_end: p.t_end,
        rtol: tol,
        atol: tol,
        dt: fixed_step.then_some(tol),
        t_out: vec![p.t_end],
        max_steps: 50_000_000,
        ..IntegratorOptions::default()
    };
    let (seconds, sol) = time_min(|| integrate(sys, method, &p.y0, &opts));
    let sol = sol.ok()?;
    let y = sol.y.last()?;
    if sol.t.last() != Some(&p.t_end) || y.iter().any(|v| !v.is_finite()) {
        return None;
    }
    let every_step = if extra.energy.is_some() || extra.constraints.is_some() {
        let all = IntegratorOptions {
            t_out: Vec::new(),
            ..opts.clone()
        };
        integrate(sys, method, &p.y0, &all).ok()
    } else {
        None
    };
    let energy_error = extra
        .energy
        .zip(every_step.as_ref())
        .map(|((e, h0), all)| energy_error(e, h0, &all.t, &all.y));
    let drift = extra
        .constraints
        .zip(every_step.as_ref())
        .map(|(g, all)| constraint_drift(g, &all.t, &all.y));
    Some(Point {
        tol,
        seconds,
        error: max_abs_diff(y, reference),
        energy_error,
        drift,
        steps: sol.stats.steps,
        rhs: sol.stats.rhs_evals,
    })
}

/// One `ode_solvers` Dop853 point ([`qdot_benches::ode_solvers_dop853`])
/// on `sys`, compiled once by the caller: the timed runs only build the
/// stepper (its work space) and integrate.
fn ode_solvers_point<const D: usize>(
    p: &Problem,
    sys: &RefCell<CompiledDynamics>,
    reference: &[f64],
    extra: Extra,
    tol: f64,
) -> Option<Point> {
    let (seconds, (stepper, stats)) = time_min(|| {
        let mut stepper = qdot_benches::ode_solvers_dop853::<D>(p, sys, tol);
        let stats = stepper.integrate();
        (stepper, stats)
    });
    let stats = match stats {
        Ok(s) => s,
        Err(e) => {
            eprintln!("\node_solvers Dop853 on {} at {tol:e}: {e}", p.name);
            return None;
        }
    };
    let (ts, ys) = (stepper.x_out(), stepper.y_out());
    let y = ys.last()?;
    if ts
        .last()
        .is_none_or(|t| (t - p.t_end).abs() > 1e-12 * p.t_end)
    {
        eprintln!(
            "\node_solvers Dop853 on {} at {tol:e} ended at {:?}",
            p.name,
            ts.last()
        );
        return None;
    }
    let error = max_abs_diff(y.as_slice(), reference);
    let ys: Vec<Vec<f64>> = ys.iter().map(|v| v.as_slice().to_vec()).collect();
    let energy_error = extra.energy.map(|(e, h0)| energy_error(e, h0, ts, &ys));
    let drift = extra.constraints.map(|g| constraint_drift(g, ts, &ys));
    Some(Point {
        tol,
        seconds,
        error,
        energy_error,
        drift,
        steps: stats.accepted_steps as usize + stats.rejected_steps as usize,
        rhs: stats.num_eval as usize,
    })
}

fn method_label(m: Method) -> &'static str {
    match m {
        Method::Rk4 => "RK4",
        Method::Dopri5 => "Dopri5",
        Method::Dop853 => "DOP853",
        Method::Vern7 => "Vern7",
        Method::Gauss6 => "Gauss6",
        Method::Radau5 => "Radau5",
    }
}

fn run_problem(p: &Problem, tolerances: &[f64], quick: bool) -> Result<Report, String> {
    let mut sys = p.dynamics().map_err(|d| d.message)?;
    // the interpreter's copy, then machine code (what `qdot simulate` runs
    // past its first 25,000 right-hand sides; compiled before the timing)
    let mut interpreted = sys.clone();
    sys.use_engine(Engine::Jit);
    let energy = p.energy().map_err(|d| d.message)?;
    let constraints = p.constraints().map_err(|d| d.message)?;
    let h0 = energy.as_ref().map(|e| energy_at(e, 0.0, &p.y0));
    let en = Extra {
        energy: energy.as_ref().zip(h0),
        constraints: constraints.as_ref(),
    };

    // The reference: exact, or Vern7 at 1e-14 checked against DOP853 at 1e-14.
    let (reference, reference_error) = match p.exact(p.t_end) {
        Some(y) => (y, 0.0),
        None => {
            let opts = IntegratorOptions {
                t_end: p.t_end,
                rtol: 1e-14,
                atol: 1e-14,
                t_out: vec![p.t_end],
                max_steps: 50_000_000,
                ..IntegratorOptions::default()
            };
            let a = integrate(&mut sys, Method::Vern7, &p.y0, &opts).map_err(|e| e.to_string())?;
            let b = integrate(&mut sys, Method::Dop853, &p.y0, &opts).map_err(|e| e.to_string())?;
            let (ya, yb) = (a.y.last().cloned(), b.y.last().cloned());
            let (Some(ya), Some(yb)) = (ya, yb) else {
                return Err("the reference run recorded nothing".into());
            };
            let d = max_abs_diff(&ya, &yb);
            (ya, d)
        }
    };

    // The hand-written right-hand side agrees with the compiled one.
    let mut hand = Hand::new(p, false);
    let mut tuned = Hand::new(p, true);
    let y: Vec<f64> =
        p.y0.iter()
            .enumerate()
            .map(|(i, v)| v + 0.1 * (i as f64 + 1.0).sin())
            .collect();
    let (mut a, mut b, mut c) = (vec![0.0; y.len()], vec![0.0; y.len()], vec![0.0; y.len()]);
    sys.rhs(0.7, &y, &mut a);
    hand.rhs(0.7, &y, &mut b);
    tuned.rhs(0.7, &y, &mut c);
    let scale = a.iter().fold(1.0f64, |m, v| m.max(v.abs()));
    if max_abs_diff(&a, &b) > 1e-12 * scale || max_abs_diff(&a, &c) > 1e-12 * scale {
        return Err(format!(
            "{}: the hand-written RHS disagrees: {a:?} vs {b:?} / {c:?}",
            p.name
        ));
    }

    let mut series = Vec::new();
    let adaptive = [
        Method::Dopri5,
        Method::Dop853,
        Method::Vern7,
        Method::Radau5,
    ];
    for m in adaptive {
        let mut pts = Vec::new();
        for &tol in tolerances {
            eprint!("\r{:<16} qdot {:<8} {tol:.0e}   ", p.name, method_label(m));
            if let Some(pt) = qdot_point(&mut sys, m, p, &reference, en, tol, false) {
                pts.push(pt);
            }
        }
        series.push(Series {
            label: format!("qdot {}", method_label(m)),
            family: "qdot",
            fixed_step: false,
            points: pts,
        });
    }
    // Fixed steps h = T/N, N = 25·2^k.
    let ns: Vec<usize> = if quick {
        vec![100, 400, 1600]
    } else {
        (0..12).map(|k| 25usize << k).collect()
    };
    for m in [Method::Rk4, Method::Gauss6] {
        let mut pts = Vec::new();
        for &n in &ns {
            let h = p.t_end / n as f64;
            eprint!("\r{:<16} qdot {:<8} N={n}   ", p.name, method_label(m));
            if let Some(pt) = qdot_point(&mut sys, m, p, &reference, en, h, true) {
                let tiny = pt.error < 1e-13;
                pts.push(pt);
                if tiny {
                    break;
                }
            }
        }
        series.push(Series {
            label: format!("qdot {} (fixed h)", method_label(m)),
            family: "qdot",
            fixed_step: true,
            points: pts,
        });
    }
    let mut pts = Vec::new();
    for &tol in tolerances {
        eprint!("\r{:<16} qdot DOP853 interpreted {tol:.0e}   ", p.name);
        if let Some(pt) = qdot_point(
            &mut interpreted,
            Method::Dop853,
            p,
            &reference,
            en,
            tol,
            false,
        ) {
            pts.push(pt);
        }
    }
    series.push(Series {
        label: "qdot DOP853, interpreter".into(),
        family: "qdot",
        fixed_step: false,
        points: pts,
    });
    for (h, label) in [
        (&mut hand, "DOP853, hand-written RHS"),
        (&mut tuned, "DOP853, tuned hand-written RHS"),
    ] {
        let mut pts = Vec::new();
        for &tol in tolerances {
            eprint!("\r{:<16} {label:<30} {tol:.0e}   ", p.name);
            if let Some(pt) = qdot_point(h, Method::Dop853, p, &reference, en, tol, false) {
                pts.push(pt);
            }
        }
        series.push(Series {
            label: format!("qdot {label}"),
            family: "hand",
            fixed_step: false,
            points: pts,
        });
    }
    let mut pts = Vec::new();
    let shared = RefCell::new(sys);
    for &tol in tolerances {
        eprint!("\r{:<16} ode_solvers Dop853 {tol:.0e}   ", p.name);
        let pt = match p.y0.len() {
            2 => ode_solvers_point::<2>(p, &shared, &reference, en, tol),
            4 => ode_solvers_point::<4>(p, &shared, &reference, en, tol),
            20 => ode_solvers_point::<20>(p, &shared, &reference, en, tol),
            d => return Err(format!("no ode_solvers instance for dimension {d}")),
        };
        pts.extend(pt);
    }
    series.push(Series {
        label: "ode_solvers Dop853 (compiled RHS)".into(),
        family: "ode_solvers",
        fixed_step: false,
        points: pts,
    });
    let alpha = match &constraints {
        Some(g) => Some(alpha_study(p, g, en.energy, &reference, tolerances, quick)?),
        None => None,
    };
    eprintln!();
    Ok(Report {
        problem: p.clone(),
        reference,
        reference_error,
        h0,
        check_y: y,
        check_dy: a,
        series,
        alpha,
    })
}

/// Baumgarte's α measured on the constrained problem `p`: the adaptive
/// methods at α = 0, 1, 10 over [0, T] (all of `tolerances`), and DOP853
/// at rtol = atol = 1e-10 over 100 periods of the angle pendulum (timed
/// once; the error against the exact solution at the end).
fn alpha_study(
    p: &Problem,
    g: &Program,
    energy: Option<(&Program, f64)>,
    reference: &[f64],
    tolerances: &[f64],
    quick: bool,
) -> Result<AlphaStudy, String> {
    let alphas = vec![0.0, 1.0, 10.0];
    let theta0 = p.y0[0].atan2(-p.y0[1]);
    let period = qdot::simulate::elliptic::pendulum_period(theta0, p.param("g") / p.param("l"));
    let long_t = (100.0 * period).ceil();
    let long_tol = 1e-10;
    let extra = Extra {
        energy,
        constraints: Some(g),
    };
    let (mut series, mut long) = (Vec::new(), Vec::new());
    for &alpha in &alphas {
        let q = Problem {
            baumgarte: Some(alpha),
            ..p.clone()
        };
        let mut sys = q.dynamics().map_err(|d| d.message)?;
        let methods: &[Method] = if quick {
            &[Method::Dop853]
        } else {
            &[
                Method::Dopri5,
                Method::Dop853,
                Method::Vern7,
                Method::Radau5,
            ]
        };
        for &m in methods {
            let mut pts = Vec::new();
            for &tol in tolerances {
                eprint!(
                    "\r{:<16} α = {alpha:<4} {:<8} {tol:.0e}   ",
                    p.name,
                    method_label(m)
                );
                pts.extend(qdot_point(&mut sys, m, &q, reference, extra, tol, false));
            }
            series.push((
                alpha,
                Series {
                    label: format!("qdot {} at α = {alpha}", method_label(m)),
                    family: "qdot",
                    fixed_step: false,
                    points: pts,
                },
            ));
        }
        let q = Problem { t_end: long_t, ..q };
        let exact = q.exact(long_t).ok_or("no exact solution")?;
        eprint!(
            "\r{:<16} α = {alpha:<4} DOP853 over [0, {long_t}]   ",
            p.name
        );
        let opts = IntegratorOptions {
            t_end: long_t,
            rtol: long_tol,
            atol: long_tol,
            max_steps: 50_000_000,
            ..IntegratorOptions::default()
        };
        let t0 = Instant::now();
        let sol = integrate(&mut sys, Method::Dop853, &q.y0, &opts).map_err(|e| e.to_string())?;
        let seconds = t0.elapsed().as_secs_f64();
        let y = sol.y.last().ok_or("the long run recorded nothing")?;
        long.push((
            alpha,
            Point {
                tol: long_tol,
                seconds,
                error: max_abs_diff(y, &exact),
                energy_error: energy.map(|(e, h0)| energy_error(e, h0, &sol.t, &sol.y)),
                drift: Some(constraint_drift(g, &sol.t, &sol.y)),
                steps: sol.stats.steps,
                rhs: sol.stats.rhs_evals,
            },
        ));
    }
    Ok(AlphaStudy {
        constraints: g.n_outputs(),
        alphas,
        series,
        long_t,
        long_tol,
        long,
    })
}

/// Time at error `e` on a curve, by log-log interpolation along its lower
/// envelope: at each point's error, the least time of any point reaching
/// that error or a smaller one (a loose tolerance that happens to land on a
/// small error counts for it). None outside the curve's range.
fn time_at(s: &Series, e: f64) -> Option<f64> {
    let mut pts: Vec<(f64, f64)> = s
        .points
        .iter()
        .filter(|p| p.error > 0.0 && p.seconds > 0.0)
        .map(|p| (p.error.log10(), p.seconds.log10()))
        .collect();
    pts.sort_by(|a, b| a.0.total_cmp(&b.0));
    // Least time reaching error ≤ x: a running minimum from the small errors.
    for i in 1..pts.len() {
        pts[i].1 = pts[i].1.min(pts[i - 1].1);
    }
    let x = e.log10();
    let first = pts.first()?;
    let last = pts.last()?;
    if x < first.0 || x > last.0 {
        return None;
    }
    for w in pts.windows(2) {
        let ((x0, y0), (x1, y1)) = (w[0], w[1]);
        if x >= x0 && x <= x1 {
            let y = if x1 > x0 {
                y0 + (y1 - y0) * (x - x0) / (x1 - x0)
            } else {
                y0.min(y1)
            };
            return Some(10f64.powf(y));
        }
    }
    (pts.len() == 1).then(|| 10f64.powf(first.1))
}

const COLORS: [RGBColor; 12] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(127, 127, 127),
    RGBColor(23, 190, 207),
    RGBColor(188, 189, 34),
    RGBColor(255, 127, 14),
    RGBColor(227, 119, 194),
    RGBColor(0, 0, 0),
    RGBColor(255, 187, 120),
];

/// What a diagram plots against time.
#[derive(Clone, Copy, PartialEq)]
enum Plot {
    /// The final error.
    Error,
    /// max |H − H0| over the run.
    Energy,
    /// max |g| over the run (constrained problems).
    Drift,
}

/// The diagram: time against final error (or energy error, or constraint
/// drift), log-log, one curve per series.
fn diagram(r: &Report, plot: Plot) -> Result<String, String> {
    let mut out = String::new();
    {
        let root = SVGBackend::with_string(&mut out, (900, 620)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let err = |p: &Point| match plot {
            Plot::Error => Some(p.error),
            Plot::Energy => p.energy_error,
            Plot::Drift => p.drift,
        };
        let (mut xlo, mut xhi, mut ylo, mut yhi) = (1e-15f64, 1e-2f64, f64::INFINITY, 0.0f64);
        for s in &r.series {
            for p in &s.points {
                if let Some(e) = err(p).filter(|e| *e > 0.0) {
                    xlo = xlo.min(e);
                    xhi = xhi.max(e);
                    ylo = ylo.min(p.seconds);
                    yhi = yhi.max(p.seconds);
                }
            }
        }
        if !ylo.is_finite() {
            return Err("no points".into());
        }
        let title = format!(
            "{}: {}",
            r.problem.title,
            match plot {
                Plot::Error => "final error against time",
                Plot::Energy => "max |H − H0| against time",
                Plot::Drift => "max |g| against time",
            }
        );
        let mut chart = ChartBuilder::on(&root)
            .caption(title, ("sans-serif", 18))
            .margin(14)
            .x_label_area_size(40)
            .y_label_area_size(70)
            .build_cartesian_2d(
                (xlo / 3.0..xhi * 3.0).log_scale(),
                (ylo / 2.0..yhi * 2.0).log_scale(),
            )
            .map_err(|e| e.to_string())?;
        chart
            .configure_mesh()
            .x_desc(match plot {
                Plot::Error => "max |y(T) − y_ref(T)|",
                Plot::Energy => "max |H − H0| over the run",
                Plot::Drift => "max |x² + y² − l²| over the run",
            })
            .y_desc("time [s], minimum of repeated runs")
            .x_label_formatter(&|v| format!("{v:.0e}"))
            .y_label_formatter(&|v| format!("{v:.0e}"))
            .draw()
            .map_err(|e| e.to_string())?;
        for (i, s) in r.series.iter().enumerate() {
            let c = COLORS[i % COLORS.len()];
            let pts: Vec<(f64, f64)> = s
                .points
                .iter()
                .filter_map(|p| err(p).filter(|e| *e > 0.0).map(|e| (e, p.seconds)))
                .collect();
            if pts.is_empty() {
                continue;
            }
            let style = if s.family == "qdot" {
                c.stroke_width(2)
            } else {
                c.stroke_width(1)
            };
            chart
                .draw_series(LineSeries::new(pts.iter().copied(), style))
                .map_err(|e| e.to_string())?
                .label(s.label.clone())
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(2))
                });
            let family = s.family;
            chart
                .draw_series(pts.iter().map(|&(x, y)| -> DynElement<_, _> {
                    match family {
                        "scipy" => TriangleMarker::new((x, y), 5, c.filled()).into_dyn(),
                        "hand" | "ode_solvers" => {
                            Cross::new((x, y), 4, c.stroke_width(2)).into_dyn()
                        }
                        _ => Circle::new((x, y), 3, c.filled()).into_dyn(),
                    }
                }))
                .map_err(|e| e.to_string())?;
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .label_font(("sans-serif", 12))
            .draw()
            .map_err(|e| e.to_string())?;
        root.present().map_err(|e| e.to_string())?;
    }
    Ok(out)
}

/// SciPy's points from `benches/wp_scipy.py`'s JSON output.
fn scipy_series(v: &Value, problem: &str) -> Vec<Series> {
    let mut out: Vec<Series> = Vec::new();
    let Some(results) = v["results"].as_array() else {
        return out;
    };
    for r in results {
        if r["problem"].as_str() != Some(problem) || !r["skipped"].is_null() {
            continue;
        }
        if r["success"].as_bool() == Some(false) {
            continue;
        }
        let method = r["method"].as_str().unwrap_or("?");
        let label = format!("SciPy solve_ivp {method}");
        let pt = Point {
            tol: r["tol"].as_f64().unwrap_or(f64::NAN),
            seconds: r["seconds"].as_f64().unwrap_or(f64::NAN),
            error: r["error"].as_f64().unwrap_or(f64::NAN),
            energy_error: r["energy_error"].as_f64(),
            drift: r["constraint_drift"].as_f64(),
            steps: r["steps"].as_u64().unwrap_or(0) as usize,
            rhs: r["nfev"].as_u64().unwrap_or(0) as usize,
        };
        if !(pt.seconds.is_finite() && pt.error.is_finite()) {
            continue;
        }
        match out.iter_mut().find(|s| s.label == label) {
            Some(s) => s.points.push(pt),
            None => out.push(Series {
                label,
                family: "scipy",
                fixed_step: false,
                points: vec![pt],
            }),
        }
    }
    out
}

fn run_scipy(reports: &[Report], tolerances: &[f64], dir: &Path) -> Result<Value, String> {
    let problems: Vec<Value> = reports
        .iter()
        .map(|r| {
            let p = &r.problem;
            let params: serde_json::Map<String, Value> = p
                .params
                .iter()
                .map(|(k, v)| (k.to_string(), json!(v)))
                .collect();
            json!({
                "name": p.name, "params": params, "y0": p.y0, "t_end": p.t_end,
                "baumgarte_alpha": p.baumgarte,
                "reference": r.reference, "energy_reference": r.h0,
                "check": {"t": 0.7, "y": r.check_y, "dy": r.check_dy},
            })
        })
        .collect();
    let input = json!({
        "tolerances": tolerances, "methods": ["DOP853", "RK45"], "time_budget": 1.0,
        "problems": problems,
    });
    std::fs::create_dir_all(dir).map_err(|e| e.to_string())?;
    let (inp, outp) = (dir.join("problems.json"), dir.join("scipy.json"));
    std::fs::write(
        &inp,
        serde_json::to_string_pretty(&input).map_err(|e| e.to_string())?,
    )
    .map_err(|e| e.to_string())?;
    let script = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/..")).join("benches/wp_scipy.py");
    let status = std::process::Command::new("python3")
        .arg(&script)
        .arg(&inp)
        .arg(&outp)
        .status()
        .map_err(|e| format!("python3: {e}"))?;
    if !status.success() {
        return Err(format!("{} failed ({status})", script.display()));
    }
    let text = std::fs::read_to_string(&outp).map_err(|e| e.to_string())?;
    serde_json::from_str(&text).map_err(|e| e.to_string())
}

fn fmt_e(x: f64) -> String {
    if x.is_finite() {
        format!("{x:.1e}")
    } else {
        "—".into()
    }
}

fn fmt_s(x: f64) -> String {
    if x >= 1.0 {
        format!("{x:.2} s")
    } else if x >= 1e-3 {
        format!("{:.2} ms", x * 1e3)
    } else {
        format!("{:.1} µs", x * 1e6)
    }
}

/// The ratio rows at equal error: `num` / `den` at each target error.
/// Time of series `num` over series `den` on `r` at error `e`.
fn ratio_at(r: &Report, num: &str, den: &str, e: f64) -> Option<f64> {
    let at = |l: &str| {
        r.series
            .iter()
            .find(|s| s.label == l)
            .and_then(|s| time_at(s, e))
    };
    Some(at(num)? / at(den)?)
}

/// The table cell of [`ratio_at`].
fn ratio_cell(r: &Report, num: &str, den: &str, e: f64) -> String {
    ratio_at(r, num, den, e).map_or_else(|| "—".into(), |x| format!("{x:.2}"))
}

fn markdown(reports: &[Report], scipy: &Result<Value, String>, started: &str, wall: f64) -> String {
    let mut md = String::new();
    let _ = writeln!(
        md,
        "<!-- generated by `cargo bench -p qdot-benches --bench work_precision`: do not edit -->"
    );
    let _ = writeln!(
        md,
        "Generated {started} in {wall:.0} s on this project's 2-core shared machine."
    );
    match scipy {
        Ok(v) => {
            let _ = writeln!(
                md,
                "Peers in the same run: SciPy {} with NumPy {} on Python {}, `ode_solvers` 0.6.2.",
                v["scipy"].as_str().unwrap_or("?"),
                v["numpy"].as_str().unwrap_or("?"),
                v["python"].as_str().unwrap_or("?"),
            );
        }
        Err(e) => {
            let _ = writeln!(md, "SciPy was **not** measured in this run: {e}.");
        }
    }
    let targets = [1e-4, 1e-6, 1e-8, 1e-10];
    // The ranges of the headline ratios over problems and target errors.
    let range = |num: &str, den: &str, skip: &[&str]| -> String {
        let mut v: Vec<f64> = reports
            .iter()
            .filter(|r| !skip.contains(&r.problem.name))
            .flat_map(|r| {
                targets
                    .iter()
                    .filter_map(move |&e| ratio_at(r, num, den, e))
            })
            .collect();
        v.sort_by(f64::total_cmp);
        match (v.first(), v.last()) {
            (Some(lo), Some(hi)) => format!(
                "{lo:.2} … {hi:.2} (median {:.2}, {} points)",
                v[v.len() / 2],
                v.len()
            ),
            _ => "not measured".into(),
        }
    };
    let _ = writeln!(md, "\n### Summary\n");
    let _ = writeln!(md, "Ranges over the problems and the target errors 1e-4, 1e-6, 1e-8, 1e-10 of the table below (time of the first over the second at equal error):\n");
    let _ = writeln!(
        md,
        "- SciPy DOP853 / qdot DOP853: {}",
        range("SciPy solve_ivp DOP853", "qdot DOP853", &[])
    );
    let _ = writeln!(
        md,
        "- SciPy RK45 / qdot Dopri5: {}",
        range("SciPy solve_ivp RK45", "qdot Dopri5", &[])
    );
    let _ = writeln!(
        md,
        "- ode_solvers Dop853 / qdot DOP853 (oscillator left out: see below): {}",
        range(
            "ode_solvers Dop853 (compiled RHS)",
            "qdot DOP853",
            &["oscillator"]
        )
    );
    let _ = writeln!(
        md,
        "- compiled / hand-written RHS, both with qdot's DOP853: {}",
        range("qdot DOP853", "qdot DOP853, hand-written RHS", &[])
    );
    let _ = writeln!(
        md,
        "- compiled / tuned hand-written RHS: {}",
        range("qdot DOP853", "qdot DOP853, tuned hand-written RHS", &[])
    );
    let _ = writeln!(
        md,
        "- interpreter / machine code (`--evaluator interpreter` / `jit`), both with qdot's DOP853: {}",
        range("qdot DOP853, interpreter", "qdot DOP853", &[])
    );
    let _ = writeln!(
        md,
        "\n`ode_solvers` 0.6.2's Dop853 has the node c₁₂ = 0 where Hairer's DOP853 has 1 \
         (`butcher_tableau.rs`; the fix is the open pull request srenevey/ode-solvers#42), so it \
         evaluates its 12th stage at t instead of t + h. Autonomous problems do not notice; on the \
         forced oscillator, whose right-hand side depends on t, it is a first-order method, its \
         error stalls near the tolerance's square root and its step count explodes. Its \
         oscillator series measures that bug, not its speed."
    );
    let _ = writeln!(md, "\n### Ratios at equal error\n");
    let _ = writeln!(
        md,
        "Time of the first series over the second, interpolated (log-log) at the same final error; \
         above 1 means the second is faster; — where a curve does not reach that error.\n"
    );
    let _ = writeln!(md, "| problem | ratio | error 1e-4 | 1e-6 | 1e-8 | 1e-10 |");
    let _ = writeln!(md, "|---|---|---|---|---|---|");
    let pairs = [
        (
            "SciPy solve_ivp DOP853",
            "qdot DOP853",
            "SciPy DOP853 / qdot DOP853",
        ),
        (
            "SciPy solve_ivp RK45",
            "qdot Dopri5",
            "SciPy RK45 / qdot Dopri5",
        ),
        (
            "ode_solvers Dop853 (compiled RHS)",
            "qdot DOP853",
            "ode_solvers Dop853 / qdot DOP853",
        ),
        (
            "qdot DOP853",
            "qdot DOP853, hand-written RHS",
            "compiled / hand-written RHS",
        ),
        (
            "qdot DOP853",
            "qdot DOP853, tuned hand-written RHS",
            "compiled / tuned hand-written RHS",
        ),
        (
            "qdot DOP853, interpreter",
            "qdot DOP853",
            "interpreter / machine code",
        ),
    ];
    for r in reports {
        for (num, den, label) in pairs {
            let cells: Vec<String> = targets
                .iter()
                .map(|&e| ratio_cell(r, num, den, e))
                .collect();
            let _ = writeln!(
                md,
                "| {} | {label} | {} |",
                r.problem.name,
                cells.join(" | ")
            );
        }
    }
    for r in reports {
        let p = &r.problem;
        let _ = writeln!(md, "\n### {}\n", p.title);
        let _ = writeln!(
            md,
            "![work-precision diagram of {}](wp_{}.svg)\n",
            p.name, p.name
        );
        if r.h0.is_some() {
            let _ = writeln!(
                md,
                "![energy error of {}](wp_{}_energy.svg)\n",
                p.name, p.name
            );
        }
        if r.alpha.is_some() {
            let _ = writeln!(
                md,
                "![constraint drift of {}](wp_{}_drift.svg)\n",
                p.name, p.name
            );
        }
        let n = p.y0.len() / 2;
        let reference = if r.reference_error == 0.0 {
            "the exact solution".to_string()
        } else {
            format!(
                "Vern7 at rtol = atol = 1e-14 (its distance to DOP853 at 1e-14: {})",
                fmt_e(r.reference_error)
            )
        };
        let plural = |k: usize| if k == 1 { "" } else { "s" };
        let freedom = match &r.alpha {
            Some(a) => format!(
                "{n} coordinates, {} constraint{} ({} degree{} of freedom)",
                a.constraints,
                plural(a.constraints),
                n - a.constraints,
                plural(n - a.constraints)
            ),
            None => format!("{n} degree{} of freedom", plural(n)),
        };
        let _ = writeln!(
            md,
            "{freedom}, t ∈ [0, {}]; reference: {reference}.\n",
            p.t_end
        );
        if let Some(study) = &r.alpha {
            constrained_notes(&mut md, r, study);
        }
        let drift = r.alpha.is_some();
        let _ = writeln!(
            md,
            "| series | tol or h | time | error | max \\|H − H0\\| |{} steps | RHS evals |",
            if drift { " max \\|g\\| |" } else { "" }
        );
        let _ = writeln!(
            md,
            "|---|---|---|---|---|{}---|---|",
            if drift { "---|" } else { "" }
        );
        for s in &r.series {
            for pt in &s.points {
                let tol = if s.fixed_step {
                    format!("h = {:.2e}", pt.tol)
                } else {
                    format!("{:.0e}", pt.tol)
                };
                let g = if drift {
                    format!(" {} |", pt.drift.map(fmt_e).unwrap_or_else(|| "—".into()))
                } else {
                    String::new()
                };
                let _ = writeln!(
                    md,
                    "| {} | {tol} | {} | {} | {} |{g} {} | {} |",
                    s.label,
                    fmt_s(pt.seconds),
                    fmt_e(pt.error),
                    pt.energy_error.map(fmt_e).unwrap_or_else(|| "—".into()),
                    pt.steps,
                    pt.rhs
                );
            }
        }
    }
    md
}

/// The constrained problem's notes: what it integrates, and Baumgarte's α
/// measured (time at equal error against the problem's own α, drift, and
/// the long runs).
fn constrained_notes(md: &mut String, r: &Report, study: &AlphaStudy) {
    let p = &r.problem;
    let chosen = p.baumgarte.unwrap_or(f64::NAN);
    let _ = writeln!(
        md,
        "The scene is the pendulum above in x, y with `constraint rod: x^2 + y^2 = l^2`; \
         every series integrates the same index-reduced augmented system with Baumgarte's \
         stabilization g̈ + 2α·ġ + α²·g = 0 at α = {chosen} (qdot's through \
         `simulate::constrained::stabilized`, the hand-written and SciPy right-hand sides \
         written from the same formulas and checked against it), and the exact solution is \
         the angle pendulum's θ(t) mapped to (l sin θ, −l cos θ) and its derivative. \
         The column max \\|g\\| is the constraint drift, max \\|x² + y² − l²\\| over the \
         accepted steps (an untimed run), beside the error at the final time.\n"
    );
    let _ = writeln!(md, "#### Baumgarte's α\n");
    let _ = writeln!(
        md,
        "The same problem at α = {}: time at equal final error over the time at α = {chosen} \
         (interpolated as in the ratio table above; — where a curve does not reach the error), \
         and the drift at each tolerance.\n",
        study
            .alphas
            .iter()
            .map(|a| a.to_string())
            .collect::<Vec<_>>()
            .join(", ")
    );
    let targets = [1e-4, 1e-6, 1e-8, 1e-10];
    let _ = writeln!(
        md,
        "| method | time ratio | error 1e-4 | 1e-6 | 1e-8 | 1e-10 |"
    );
    let _ = writeln!(md, "|---|---|---|---|---|---|");
    let find = |alpha: f64, method: &str| {
        study
            .series
            .iter()
            .find(|(a, s)| *a == alpha && s.label.starts_with(&format!("qdot {method} ")))
            .map(|(_, s)| s)
    };
    let methods = ["Dopri5", "DOP853", "Vern7", "Radau5"];
    for m in methods {
        let Some(base) = find(chosen, m) else {
            continue;
        };
        for &alpha in study.alphas.iter().filter(|&&a| a != chosen) {
            let Some(other) = find(alpha, m) else {
                continue;
            };
            let cells: Vec<String> = targets
                .iter()
                .map(|&e| match (time_at(other, e), time_at(base, e)) {
                    (Some(a), Some(b)) => format!("{:.2}", a / b),
                    _ => "—".into(),
                })
                .collect();
            let _ = writeln!(
                md,
                "| {m} | α = {alpha} / α = {chosen} | {} |",
                cells.join(" | ")
            );
        }
    }
    let _ = writeln!(
        md,
        "\n| method | tol | α | time | error | max \\|g\\| | steps |"
    );
    let _ = writeln!(md, "|---|---|---|---|---|---|---|");
    let shown = [1e-4, 1e-6, 1e-8, 1e-10, 1e-12];
    for m in methods {
        for tol in shown {
            for &alpha in &study.alphas {
                let Some(pt) =
                    find(alpha, m).and_then(|s| s.points.iter().find(|pt| pt.tol == tol))
                else {
                    continue;
                };
                let _ = writeln!(
                    md,
                    "| {m} | {tol:.0e} | {alpha} | {} | {} | {} | {} |",
                    fmt_s(pt.seconds),
                    fmt_e(pt.error),
                    pt.drift.map(fmt_e).unwrap_or_else(|| "—".into()),
                    pt.steps
                );
            }
        }
    }
    let _ = writeln!(
        md,
        "\nOver t ∈ [0, {}] (100 periods of the angle pendulum), DOP853 at rtol = atol = {:.0e}, \
         one timed run each:\n",
        study.long_t, study.long_tol
    );
    let _ = writeln!(
        md,
        "| α | time | error at t = {} | max \\|g\\| | max \\|H − H0\\| | steps |",
        study.long_t
    );
    let _ = writeln!(md, "|---|---|---|---|---|---|");
    for (alpha, pt) in &study.long {
        let _ = writeln!(
            md,
            "| {alpha} | {} | {} | {} | {} | {} |",
            fmt_s(pt.seconds),
            fmt_e(pt.error),
            pt.drift.map(fmt_e).unwrap_or_else(|| "—".into()),
            pt.energy_error.map(fmt_e).unwrap_or_else(|| "—".into()),
            pt.steps
        );
    }
    let _ = writeln!(md);
}

fn point_json(p: &Point) -> Value {
    let mut v = json!({
        "tol": p.tol, "seconds": p.seconds, "error": p.error,
        "energy_error": p.energy_error, "steps": p.steps, "rhs_evals": p.rhs,
    });
    if let Some(d) = p.drift {
        v["constraint_drift"] = json!(d);
    }
    v
}

fn series_json(s: &Series) -> Value {
    json!({
        "label": s.label, "family": s.family, "fixed_step": s.fixed_step,
        "points": s.points.iter().map(point_json).collect::<Vec<_>>(),
    })
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let quick = args.iter().any(|a| a == "--quick");
    let no_scipy = quick || args.iter().any(|a| a == "--no-scipy");
    let root = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/.."));
    let out_dir = root.join("book/src/simulation");
    let tolerances: Vec<f64> = if quick {
        vec![1e-4, 1e-8, 1e-12]
    } else {
        (3..=13).map(|k| 10f64.powi(-k)).collect()
    };
    let started = std::process::Command::new("date")
        .arg("-u")
        .arg("+%Y-%m-%d %H:%M UTC")
        .output()
        .ok()
        .and_then(|o| String::from_utf8(o.stdout).ok())
        .map(|s| s.trim().to_string())
        .unwrap_or_default();
    let t0 = Instant::now();
    let mut reports = Vec::new();
    for p in Problem::all() {
        match run_problem(&p, &tolerances, quick) {
            Ok(r) => reports.push(r),
            Err(e) => {
                eprintln!("work_precision: {e}");
                std::process::exit(1);
            }
        }
    }
    let scipy = if no_scipy {
        Err("skipped (--quick or --no-scipy)".to_string())
    } else {
        run_scipy(&reports, &tolerances, &root.join("target/wp"))
    };
    if let Ok(v) = &scipy {
        for r in &mut reports {
            let extra = scipy_series(v, r.problem.name);
            r.series.extend(extra);
        }
    } else if let Err(e) = &scipy {
        eprintln!("work_precision: SciPy not measured: {e}");
    }
    let symbolic = wp_symbolic::measure(root);
    let wall = t0.elapsed().as_secs_f64();
    if let Err(e) = std::fs::create_dir_all(&out_dir) {
        eprintln!("work_precision: {}: {e}", out_dir.display());
        std::process::exit(1);
    }
    for r in &reports {
        for plot in [Plot::Error, Plot::Energy, Plot::Drift] {
            let name = match plot {
                Plot::Error => format!("wp_{}.svg", r.problem.name),
                Plot::Energy if r.h0.is_some() => format!("wp_{}_energy.svg", r.problem.name),
                Plot::Drift if r.alpha.is_some() => format!("wp_{}_drift.svg", r.problem.name),
                _ => continue,
            };
            match diagram(r, plot) {
                Ok(svg) => {
                    if let Err(e) = std::fs::write(out_dir.join(&name), svg) {
                        eprintln!("work_precision: {name}: {e}");
                    }
                }
                Err(e) => eprintln!("work_precision: {name}: {e}"),
            }
        }
    }
    let mut md = markdown(&reports, &scipy, &started, wall);
    md.push_str(&wp_symbolic::markdown(&symbolic));
    let md_path = out_dir.join("work-precision.md");
    if let Err(e) = std::fs::write(&md_path, &md) {
        eprintln!("work_precision: {}: {e}", md_path.display());
        std::process::exit(1);
    }
    // The raw numbers.
    let raw: Vec<Value> = reports
        .iter()
        .map(|r| {
            let mut v = json!({
                "problem": r.problem.name,
                "reference_error": r.reference_error,
                "series": r.series.iter().map(series_json).collect::<Vec<_>>(),
            });
            if let Some(study) = &r.alpha {
                v["baumgarte_alpha"] = json!(r.problem.baumgarte);
                v["alpha_study"] = json!({
                    "alphas": study.alphas,
                    "series": study.series.iter().map(|(a, s)| {
                        let mut j = series_json(s);
                        j["alpha"] = json!(a);
                        j
                    }).collect::<Vec<_>>(),
                    "long_t_end": study.long_t,
                    "long_tol": study.long_tol,
                    "long": study.long.iter().map(|(a, p)| {
                        let mut j = point_json(p);
                        j["alpha"] = json!(a);
                        j
                    }).collect::<Vec<_>>(),
                });
            }
            v
        })
        .collect();
    let results = root.join("benches/results");
    let _ = std::fs::create_dir_all(&results);
    let symbolic_json = match &symbolic {
        Ok(s) => json!({
            "derive": s.derive.iter().map(|(n, q, e)| json!({"n": n, "qdot": q, "symengine": e})).collect::<Vec<_>>(),
            "symengine": s.symengine.as_ref().ok(),
            "chain5_cli_seconds": s.chain5_cli.as_ref().ok(),
            "chain5_library_seconds": s.chain5_library,
        }),
        Err(e) => json!({"error": e}),
    };
    let text = serde_json::to_string_pretty(
        &json!({"generated": started, "problems": raw, "symbolic": symbolic_json}),
    )
    .unwrap_or_default();
    if let Err(e) = std::fs::write(results.join("work_precision.json"), text) {
        eprintln!("work_precision: {e}");
    }
    println!("{md}");
    eprintln!(
        "work_precision: wrote {} and the diagrams in {}",
        md_path.display(),
        out_dir.display()
    );
}
