//! Criterion benchmarks of `qdot simulate`'s path: the 10-link chain end to
//! end — scene text (`gallery::pendulum_chain(10)`) → parse → Lagrange's
//! equations → [`CompiledDynamics::best`] → DOP853 over 10 s at rtol = atol
//! = 1e-8 from `Problem::chain10()`'s y0, 101 output times as the command
//! line records — and its stages (`stage/parse_derive`, `stage/compile`,
//! `stage/integrate`); then every `Problem::all()` with DOPRI5, DOP853,
//! Vern7 and Radau5 at rtol = atol = 1e-8 (`problem/NAME/METHOD`, the
//! evaluator `CompiledDynamics::best` picks). The target: the chain
//! end to end under 1 s.
//!
//! Derivatives of atoms are memoized process-wide, so after the first
//! iteration `parse_derive` measures a warm derivation (a fresh `qdot`
//! process pays the cold one once; see `hyperfine` in the report).
//! Samples are few and short so the whole run takes a few minutes.

#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

use criterion::{criterion_group, criterion_main, Criterion};
use qdot::simulate::compile::CompiledDynamics;
use qdot::simulate::problems::Problem;
use qdot::simulate::{integrate, IntegratorOptions, Method, Status};
use qdot::Scene;
use std::hint::black_box;
use std::time::Duration;

const TOL: f64 = 1e-8;

fn options(t_end: f64) -> IntegratorOptions {
    IntegratorOptions {
        t_end,
        rtol: TOL,
        atol: TOL,
        t_out: (0..=100).map(|i| t_end * i as f64 / 100.0).collect(),
        ..IntegratorOptions::default()
    }
}

/// Scene text → q(t_end)₁ of the 10-link chain, as `qdot simulate` does it.
fn chain_end_to_end(src: &str, p: &Problem) -> f64 {
    let scene = Scene::parse(src).expect("parses");
    let lag = scene.lagrange().expect("derives");
    let (mut d, _) = CompiledDynamics::best(&lag, &p.param_map()).expect("compiles");
    let sol = integrate(&mut d, Method::Dop853, &p.y0, &options(p.t_end)).expect("integrates");
    assert_eq!(sol.status, Status::Done);
    sol.y.last().map_or(f64::NAN, |y| y[0])
}

fn chain(c: &mut Criterion) {
    let p = Problem::chain10();
    let src = qdot::engine::gallery::pendulum_chain(10);
    let mut g = c.benchmark_group("end_to_end");
    g.sample_size(10)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(3));
    g.bench_function("chain10_10s", |b| {
        b.iter(|| black_box(chain_end_to_end(black_box(&src), &p)))
    });
    g.finish();

    let mut g = c.benchmark_group("stage");
    g.sample_size(10)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2));
    g.bench_function("parse_derive", |b| {
        b.iter(|| {
            let scene = Scene::parse(black_box(&src)).expect("parses");
            black_box(scene.lagrange().expect("derives"))
        })
    });
    let lag = Scene::parse(&src)
        .expect("parses")
        .lagrange()
        .expect("derives");
    let params = p.param_map();
    g.bench_function("compile", |b| {
        b.iter(|| black_box(CompiledDynamics::best(black_box(&lag), &params).expect("compiles")))
    });
    let (mut d, _) = CompiledDynamics::best(&lag, &params).expect("compiles");
    let opts = options(p.t_end);
    g.bench_function("integrate", |b| {
        b.iter(|| {
            let sol = integrate(&mut d, Method::Dop853, black_box(&p.y0), &opts).expect("runs");
            black_box(sol.y.last().map_or(f64::NAN, |y| y[0]))
        })
    });
    g.finish();
}

fn problems(c: &mut Criterion) {
    for p in Problem::all() {
        let lag = Scene::parse(&p.scene)
            .expect("parses")
            .lagrange()
            .expect("derives");
        // a constrained problem runs the stabilized system, as `simulate` does
        let lag = qdot::simulate::constrained::stabilized(lag).expect("stabilizes");
        let (mut d, choice) = CompiledDynamics::best(&lag, &p.param_map()).expect("compiles");
        eprintln!("{}: evaluator {}", p.name, choice.evaluator.name());
        let opts = options(p.t_end);
        let mut g = c.benchmark_group(format!("problem/{}", p.name));
        g.sample_size(10)
            .warm_up_time(Duration::from_millis(300))
            .measurement_time(Duration::from_secs(1));
        for method in [
            Method::Dopri5,
            Method::Dop853,
            Method::Vern7,
            Method::Radau5,
        ] {
            let sol = integrate(&mut d, method, &p.y0, &opts).expect("runs");
            assert_eq!(sol.status, Status::Done, "{} {method:?}", p.name);
            g.bench_function(format!("{method:?}"), |b| {
                b.iter(|| {
                    let sol = integrate(&mut d, method, black_box(&p.y0), &opts).expect("runs");
                    black_box(sol.y.last().map_or(f64::NAN, |y| y[0]))
                })
            });
        }
        g.finish();
    }
}

criterion_group!(benches, chain, problems);
criterion_main!(benches);
