//! Criterion benchmark of the explicit integrators: the pendulum
//! θ'' = −sin θ, θ(0) = 2 (a large swing), θ'(0) = 0, over t ∈ [0, 20]
//! (about three periods), each adaptive method at rtol = atol = 1e-6, 1e-9,
//! 1e-12, and RK4 at three fixed steps; output at every accepted step.

#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use qdot::simulate::{integrate, FnSystem, IntegratorOptions, Method};
use std::hint::black_box;

fn pendulum() -> FnSystem<impl FnMut(f64, &[f64], &mut [f64])> {
    FnSystem {
        dim: 2,
        f: |_t: f64, y: &[f64], dy: &mut [f64]| {
            dy[0] = y[1];
            dy[1] = -y[0].sin();
        },
    }
}

fn run(method: Method, opts: &IntegratorOptions) -> f64 {
    let sol = integrate(&mut pendulum(), method, &[2.0, 0.0], opts).expect("valid input");
    sol.y.last().map_or(f64::NAN, |y| y[0])
}

fn integrators(c: &mut Criterion) {
    let mut g = c.benchmark_group("pendulum");
    for method in [Method::Dopri5, Method::Dop853, Method::Vern7] {
        for tol in [1e-6, 1e-9, 1e-12] {
            let opts = IntegratorOptions {
                t_end: 20.0,
                rtol: tol,
                atol: tol,
                ..IntegratorOptions::default()
            };
            let id = BenchmarkId::new(format!("{method:?}"), format!("tol {tol:.0e}"));
            g.bench_with_input(id, &opts, |b, o| {
                b.iter(|| black_box(run(method, black_box(o))))
            });
        }
    }
    for dt in [1e-1, 1e-2, 1e-3] {
        let opts = IntegratorOptions {
            t_end: 20.0,
            dt: Some(dt),
            ..IntegratorOptions::default()
        };
        let id = BenchmarkId::new("Rk4", format!("dt {dt:.0e}"));
        g.bench_with_input(id, &opts, |b, o| {
            b.iter(|| black_box(run(Method::Rk4, black_box(o))))
        });
    }
    g.finish();
}

criterion_group!(benches, integrators);
criterion_main!(benches);
