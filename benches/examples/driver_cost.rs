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
use qdot::simulate::{integrate, IntegratorOptions, Method, System};
use std::cell::RefCell;
use std::hint::black_box;

/// The compiled dynamics behind `ode_solvers`' `&self` interface, as in
/// `work_precision.rs`.
struct OdeSolversRhs<'a, const D: usize>(&'a RefCell<CompiledDynamics>);

impl<const D: usize> ode_solvers::System<f64, ode_solvers::SVector<f64, D>>
    for OdeSolversRhs<'_, D>
{
    fn system(
        &self,
        t: f64,
        y: &ode_solvers::SVector<f64, D>,
        dy: &mut ode_solvers::SVector<f64, D>,
    ) {
        self.0.borrow_mut().rhs(t, y.as_slice(), dy.as_mut_slice());
    }
}

/// One `ode_solvers` run: (accepted steps, rejected, evaluations, y(T)).
fn ode_solvers_run<const D: usize>(
    p: &Problem,
    sys: &RefCell<CompiledDynamics>,
    tol: f64,
) -> (u32, u32, u32, Vec<f64>) {
    use ode_solvers::{Dop853, OutputType, SVector};
    let y0 = SVector::<f64, D>::from_column_slice(&p.y0);
    let mut stepper = Dop853::from_param(
        OdeSolversRhs::<D>(sys),
        0.0,
        p.t_end,
        p.t_end,
        y0,
        tol,
        tol,
        0.9,
        0.0,
        0.333,
        6.0,
        p.t_end,
        0.0,
        50_000_000,
        u32::MAX,
        OutputType::Sparse,
    );
    let st = stepper.integrate().expect("integrates");
    let y = stepper.y_out().last().expect("a state").as_slice().to_vec();
    (st.accepted_steps, st.rejected_steps, st.num_eval, y)
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
            let opts = IntegratorOptions {
                t_end: p.t_end,
                rtol: tol,
                atol: tol,
                t_out: vec![p.t_end],
                max_steps: 50_000_000,
                ..IntegratorOptions::default()
            };
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
                let (acc, rej, ev, y) = match p.y0.len() {
                    2 => ode_solvers_run::<2>(&p, &shared, tol),
                    4 => ode_solvers_run::<4>(&p, &shared, tol),
                    20 => ode_solvers_run::<20>(&p, &shared, tol),
                    d => panic!("no ode_solvers instance for dimension {d}"),
                };
                if k == 0 {
                    println!("ode_solvers: {acc} steps, {rej} rejected, {ev} RHS, y(T) = {y:?}");
                }
                black_box(&y);
            }
        }
        "time" => {
            // both drivers interleaved, RUNS times each: min and median µs
            let opts = IntegratorOptions {
                t_end: p.t_end,
                rtol: tol,
                atol: tol,
                t_out: vec![p.t_end],
                max_steps: 50_000_000,
                ..IntegratorOptions::default()
            };
            let shared = RefCell::new(sys);
            let (mut tq, mut to) = (Vec::new(), Vec::new());
            for _ in 0..runs {
                let t0 = std::time::Instant::now();
                let sol = integrate(&mut *shared.borrow_mut(), Method::Dop853, &p.y0, &opts);
                tq.push(t0.elapsed().as_secs_f64() * 1e6);
                black_box(&sol);
                let t0 = std::time::Instant::now();
                let r = match p.y0.len() {
                    2 => ode_solvers_run::<2>(&p, &shared, tol),
                    4 => ode_solvers_run::<4>(&p, &shared, tol),
                    _ => ode_solvers_run::<20>(&p, &shared, tol),
                };
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
