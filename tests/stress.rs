//! Stress tests of numerical stability, at sizes that run in seconds (the
//! full-size runs are `examples/stress_report.rs`, whose results are in
//! `book/src/simulation/stress.md`; the experiments are shared, in
//! `tests/stress_common`).
//!
//! 1. Energy over 10⁴ periods of a pendulum: bounded for Gauss6, growing
//!    linearly for RK4 and DOP853.
//! 2. The n-link chain: qdot's M and f against the closed form; the f64
//!    solve of M·q̈ = f against the exact solve, within κ₂(M)·ε.
//! 3. A stiff spring pair: explicit methods detect stiffness; Radau5 needs
//!    a small fraction of their steps.
//! 4. A chaotic double pendulum: tighter tolerances agree longer.

use crate::stress_common::*;
use qdot::simulate::{Method, Status};

fn at(d: &Drift, p: u64) -> f64 {
    d.checkpoints
        .iter()
        .find(|c| c.0 == p)
        .map(|c| c.1)
        .expect("checkpoint recorded")
}

/// Gauss6 at h = T/16.3 over 10⁴ periods of the pendulum at θ0 = 1: the
/// energy error stays where it was after 100 periods (measured: 4.43e-8 at
/// 10² and at 10⁴ periods; drift of H − H0 at the chunk ends ≈ 1e-16 per
/// period). (h = T/16 exactly is a step-size resonance, whose growth shows
/// only after ~10⁵ periods: see the report.)
#[test]
fn gauss6_energy_error_stays_bounded() {
    let d = energy_drift(
        1.0,
        Method::Gauss6,
        Stepping::Fixed {
            steps_per_period: 16.3,
        },
        10_000,
        1000,
        &[100, 10_000],
    );
    assert_eq!(d.status, Status::Done);
    let (e2, e4) = (at(&d, 100), at(&d, 10_000));
    eprintln!(
        "gauss6: {e2:.3e} at 10^2, {e4:.3e} at 10^4, rate {:.3e}",
        d.rate
    );
    // O(h⁶) with h ≈ 0.42: small, but not at round-off
    assert!(e2 > 1e-9 && e2 < 1e-7, "{e2}");
    assert!(e4 <= 2.0 * e2, "grew from {e2} to {e4}");
    // a fitted drift over 10⁴ periods far below the oscillation itself
    assert!(d.rate.abs() * 1e4 < 0.01 * e4, "rate {}", d.rate);
}

/// RK4 at h = T/64 and DOP853 at tol 1e-8 lose energy at a steady rate: the
/// error grows ~100× from 10² to 10⁴ periods (measured: RK4 3.87e-5 →
/// 3.85e-3, DOP853 2.76e-7 → 2.77e-5); a bounded error would grow ~1×.
#[test]
fn rk4_and_dop853_energy_errors_grow_linearly() {
    for (m, s) in [
        (
            Method::Rk4,
            Stepping::Fixed {
                steps_per_period: 64.0,
            },
        ),
        (Method::Dop853, Stepping::Adaptive { tol: 1e-8 }),
    ] {
        let d = energy_drift(1.0, m, s, 10_000, 1000, &[100, 1000, 10_000]);
        assert_eq!(d.status, Status::Done);
        let (e2, e3, e4) = (at(&d, 100), at(&d, 1000), at(&d, 10_000));
        eprintln!("{m:?}: {e2:.3e}, {e3:.3e}, {e4:.3e}; rate {:.3e}", d.rate);
        assert!(e4 >= 30.0 * e2, "{m:?}: {e2} → {e4}");
        assert!(e3 >= 5.0 * e2 && e4 >= 5.0 * e3, "{m:?}: {e2}, {e3}, {e4}");
        // both dissipate: H decreases, at the rate the errors show
        assert!(d.rate < 0.0, "{m:?}: rate {}", d.rate);
        let implied = -d.rate * 1e4;
        assert!(
            implied > 0.5 * e4 && implied < 2.0 * e4,
            "{m:?}: {implied} vs {e4}"
        );
    }
}

/// qdot's exact M and f of the n-link chain, compiled and evaluated at
/// random states, equal the closed form to round-off (n ≤ 10).
#[test]
fn chain_matches_the_closed_form() {
    let mut rng = SplitMix64::new(7);
    for n in [2usize, 3, 5, 10] {
        let (mut d, _, _) = chain_dynamics(n);
        let (mut m, mut f) = (vec![0.0; n * n], vec![0.0; n]);
        for _ in 0..5 {
            let (q, qd) = random_state(&mut rng, n);
            d.mass_and_forcing(0.0, &q, &qd, &mut m, &mut f)
                .expect("M and f");
            let (mc, fc) = chain_closed_form(&q, &qd, 9.81);
            let scale = (n * n) as f64 * 10.0;
            for (a, b) in m.iter().zip(&mc) {
                assert!((a - b).abs() <= 1e-13 * scale, "n = {n}: M {a} vs {b}");
            }
            for (a, b) in f.iter().zip(&fc) {
                assert!((a - b).abs() <= 1e-13 * scale, "n = {n}: f {a} vs {b}");
            }
        }
    }
}

/// The f64 Cholesky solve of M·q̈ = f against the exact solve of the same
/// f64 system, n ≤ 20: the exact solution satisfies M·x = f exactly and the
/// f64 one is within C·κ₂(M)·ε of it with C = 4 (measured: at most 0.47,
/// n = 2; ≈ 0.1 for n = 10, 20).
#[test]
fn chain_float_solve_is_within_cond_times_eps() {
    let eps = f64::EPSILON;
    for n in [2usize, 5, 10, 20] {
        let (mut d, _, _) = chain_dynamics(n);
        let mut errs = chain_accuracy(&mut d, 3, 2026 + n as u64);
        // the stretched chain: M is the min-matrix min(n − i, n − j)
        let (mut m, mut f) = (vec![0.0; n * n], vec![0.0; n]);
        let qd: Vec<f64> = (0..n).map(|i| 0.1 * i as f64).collect();
        d.mass_and_forcing(0.0, &vec![0.3; n], &qd, &mut m, &mut f)
            .expect("M and f");
        errs.push(compare_solves(&m, &f));
        for e in &errs {
            eprintln!(
                "n = {n}: κ₂ = {:.1}, rel. error {:.2e} = {:.3} κ₂ε",
                e.cond,
                e.rel_err,
                e.rel_err / (e.cond * eps)
            );
            assert!(e.residual_zero, "n = {n}: M·x − f ≠ 0");
            assert!(e.rel_err <= 4.0 * e.cond * eps, "n = {n}: {e:?}");
        }
        // its eigenvalues are 1/(4 sin²((2k − 1)π/(4n + 2))), k = 1 … n
        let st = errs.last().expect("the stretched chain");
        let x = std::f64::consts::PI / (4 * n + 2) as f64;
        let k = (((2 * n - 1) as f64 * x).sin() / x.sin()).powi(2);
        assert!(
            (st.cond / k - 1.0).abs() < 1e-9,
            "n = {n}: κ₂ {} vs {k}",
            st.cond
        );
    }
}

/// The stiff spring pair (K/k = 1e6, rtol 1e-6, atol 1e-8, t ∈ [0, 10]):
/// DOPRI5, DOP853 and Vern7 report stiffness early (measured t ≈ 0.07,
/// 0.26, 0.1) and take thousands of steps (2158 to 4304); Radau5 takes 60
/// and lands within 1e-5 of a tight reference (measured 7e-8).
#[test]
fn stiff_pair_is_detected_and_radau5_is_cheap() {
    let reference = stiff_run(Method::Dop853, 1e-13, 10.0).0;
    let yref = reference.y.last().expect("a state").clone();
    let (radau, _) = stiff_run(Method::Radau5, 1e-6, 10.0);
    assert_eq!(radau.status, Status::Done);
    let err = |y: &[f64]| {
        y.iter()
            .zip(&yref)
            .fold(0.0f64, |a, (p, q)| a.max((p - q).abs()))
    };
    let ry = radau.y.last().expect("a state");
    eprintln!("radau5: {:?}, error {:.2e}", radau.stats, err(ry));
    assert!(radau.stats.steps <= 150, "{:?}", radau.stats);
    assert!(err(ry) < 1e-5, "{}", err(ry));
    // the slow mode x1 ≈ x2 ≈ cos(t/√2) survives
    assert!((ry[0] - (10.0 / 2f64.sqrt()).cos()).abs() < 1e-3, "{ry:?}");
    for m in [Method::Dopri5, Method::Dop853, Method::Vern7] {
        let (sol, _) = stiff_run(m, 1e-6, 10.0);
        eprintln!(
            "{m:?}: stiff at {:?}, {:?}, error {:.2e}",
            sol.stiff_at,
            sol.stats,
            err(sol.y.last().expect("a state"))
        );
        assert_eq!(sol.status, Status::Done, "{m:?}");
        let t = sol.stiff_at.expect("stiffness detected");
        assert!(t < 1.0, "{m:?}: detected late, at {t}");
        assert!(
            sol.stats.steps >= 20 * radau.stats.steps,
            "{m:?}: {} vs {}",
            sol.stats.steps,
            radau.stats.steps
        );
    }
}

/// The double pendulum released from rest at (2, 2.5), DOP853 and Vern7 at
/// tol 1e-4 … 1e-12 on a grid of 0.01: the 1e-12 and 1e-10 runs agree
/// (within 1e-2 in both angles) longer than the 1e-6 and 1e-4 runs
/// (measured: 10.1 vs 2.8 for DOP853, 11.5 vs 5.7 for Vern7), and every
/// pair parts before t = 30.
#[test]
fn chaotic_runs_agree_longer_at_tighter_tolerances() {
    let p = double_pendulum(2.0, 2.5, 30.0);
    let tols = [1e-4, 1e-6, 1e-8, 1e-10, 1e-12];
    for m in [Method::Dop853, Method::Vern7] {
        let runs: Vec<_> = tols.iter().map(|&t| grid_run(&p, m, t, 0.01)).collect();
        let parts: Vec<f64> = runs
            .windows(2)
            .map(|w| parting_time(&w[0], &w[1], 2, 1e-2).expect("chaos parts them"))
            .collect();
        eprintln!("{m:?}: parting times {parts:?}");
        assert!(runs.iter().all(|r| r.status == Status::Done));
        assert!(parts[3] > parts[0] + 2.0, "{m:?}: {parts:?}");
        // the loosest pair parts soon, but not at once
        assert!(parts[0] > 1.0, "{m:?}: {parts:?}");
    }
}
