//! The explicit driver's own cost against `ode_solvers`' Dop853, for
//! `valgrind --tool=callgrind`: one problem of the report integrated as the
//! work-precision report times it (DOP853 on the machine code, the final
//! state only; `ode_solvers` with sparse output on the same compiled
//! right-hand side).
//!
//! ```text
//! cargo build --release -p qdot-benches --example driver_cost
//! valgrind --tool=callgrind target/release/examples/driver_cost pendulum qdot 1e-8 10
//! ```
//!
//! Arguments: PROBLEM DRIVER TOL RUNS, DRIVER one of `qdot`, `ode_solvers`,
//! `none` (the set-up only, to subtract) or `time` (both, interleaved, RUNS
//! times each: the minimum and median µs). Under callgrind, a run's
//! instructions less those of `none`, over RUNS, are one integration's;
//! less the right-hand sides' (`rhs_engines PROBLEM jit COUNT`), the
//! driver's. The minimum of `time` is the comparison that a loaded machine
//! disturbs least: both drivers meet the same load.

#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

use qdot::simulate::compile::{CompiledDynamics, Engine};
use qdot::simulate::problems::Problem;
use qdot::simulate::{integrate, IntegratorOptions, Method};
use std::cell::RefCell;
use std::hint::black_box;

/// One `ode_solvers` run, the report's configuration
/// ([`qdot_benches::ode_solvers_dop853`]): (accepted steps, rejected,
/// evaluations, y(T)).
fn ode_solvers_run<const D: usize>(
    p: &Problem,
    sys: &RefCell<CompiledDynamics>,
    tol: f64,
) -> (u32, u32, u32, Vec<f64>) {
    let mut stepper = qdot_benches::ode_solvers_dop853::<D>(p, sys, tol);
    let st = stepper.integrate().expect("integrates");
    let y = stepper.y_out().last().expect("a state").as_slice().to_vec();
    (st.accepted_steps, st.rejected_steps, st.num_eval, y)
}

/// [`ode_solvers_run`] at the problem's dimension.
fn ode_solvers_any(
    p: &Problem,
    sys: &RefCell<CompiledDynamics>,
    tol: f64,
) -> (u32, u32, u32, Vec<f64>) {
    match p.y0.len() {
        2 => ode_solvers_run::<2>(p, sys, tol),
        4 => ode_solvers_run::<4>(p, sys, tol),
        20 => ode_solvers_run::<20>(p, sys, tol),
        d => panic!("no ode_solvers instance for dimension {d}"),
    }
}

/// qdot's DOP853 as the report runs it: the final state only.
fn qdot_options(p: &Problem, tol: f64) -> IntegratorOptions {
    IntegratorOptions {
        t_end: p.t_end,
        rtol: tol,
        atol: tol,
        t_out: vec![p.t_end],
        max_steps: 50_000_000,
        ..IntegratorOptions::default()
    }
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [name, driver, tol, runs] = args.as_slice() else {
        eprintln!("usage: driver_cost PROBLEM qdot|ode_solvers|none TOL RUNS");
        std::process::exit(2);
    };
    let p = Problem::all()
        .into_iter()
        .find(|p| p.name == name)
        .expect("a problem of the report");
    let tol: f64 = tol.parse().expect("a tolerance");
    let runs: usize = runs.parse().expect("a count");
    let mut sys = p.dynamics().expect("compiles");
    let r = sys.use_engine(Engine::Jit);
    assert_eq!(r.ran, Engine::Jit, "{r:?}");
    match driver.as_str() {
        "qdot" => {
            let opts = qdot_options(&p, tol);
            for k in 0..runs {
                let sol = integrate(&mut sys, Method::Dop853, black_box(&p.y0), &opts)
                    .expect("integrates");
                if k == 0 {
                    let st = &sol.stats;
                    println!(
                        "qdot: {} steps, {} rejected, {} RHS, y(T) = {:?}",
                        st.steps,
                        st.rejected,
                        st.rhs_evals,
                        sol.y.last()
                    );
                }
                black_box(&sol);
            }
        }
        "ode_solvers" => {
            let shared = RefCell::new(sys);
            for k in 0..runs {
                let (acc, rej, ev, y) = ode_solvers_any(&p, &shared, tol);
                if k == 0 {
                    println!("ode_solvers: {acc} steps, {rej} rejected, {ev} RHS, y(T) = {y:?}");
                }
                black_box(&y);
            }
        }
        "time" => {
            // both drivers interleaved, RUNS times each: min and median µs
            let opts = qdot_options(&p, tol);
            let shared = RefCell::new(sys);
            let (mut tq, mut to) = (Vec::new(), Vec::new());
            for _ in 0..runs {
                let t0 = std::time::Instant::now();
                let sol = integrate(&mut *shared.borrow_mut(), Method::Dop853, &p.y0, &opts);
                tq.push(t0.elapsed().as_secs_f64() * 1e6);
                black_box(&sol);
                let t0 = std::time::Instant::now();
                let r = ode_solvers_any(&p, &shared, tol);
                to.push(t0.elapsed().as_secs_f64() * 1e6);
                black_box(&r);
            }
            tq.sort_by(f64::total_cmp);
            to.sort_by(f64::total_cmp);
            let (mq, mo) = (tq[tq.len() / 2], to[to.len() / 2]);
            println!(
                "{name} {tol:e}: qdot min {:.2} med {mq:.2} µs, ode_solvers min {:.2} med {mo:.2} µs, ode/qdot min {:.3} med {:.3}",
                tq[0],
                to[0],
                to[0] / tq[0],
                mo / mq
            );
        }
        "none" => {}
        d => panic!("unknown driver {d}"),
    }
}
