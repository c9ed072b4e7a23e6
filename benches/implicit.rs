//! Criterion benchmarks of the implicit integrators (`qdot::simulate::implicit`).
//!
//! * `radau5/robertson`: Robertson's kinetics to t = 1e11, rtol = 1e-8,
//!   atol = 1e-14 (forward-difference Jacobian).
//! * `radau5/vdpol`: Van der Pol, ε = 1e-6, on [0, 2], rtol = atol = 1e-6,
//!   analytic Jacobian.
//! * `gauss6/pendulum`: the pendulum θ0 = 2, 1000 periods at 32 steps per
//!   period (32 000 steps), energy error ~3e-8.

#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

use criterion::{criterion_group, criterion_main, Criterion};
use qdot::simulate::elliptic::pendulum_period;
use qdot::simulate::implicit::{gauss6, radau5};
use qdot::simulate::{FnSystem, IntegratorOptions, System};
use std::hint::black_box;

struct Vdp;

impl System for Vdp {
    fn dim(&self) -> usize {
        2
    }
    fn rhs(&mut self, _t: f64, y: &[f64], dy: &mut [f64]) {
        dy[0] = y[1];
        dy[1] = ((1.0 - y[0] * y[0]) * y[1] - y[0]) / 1e-6;
    }
    fn jacobian(&mut self, _t: f64, y: &[f64], jac: &mut [f64]) -> bool {
        jac[0] = 0.0;
        jac[1] = 1.0;
        jac[2] = (-2.0 * y[0] * y[1] - 1.0) / 1e-6;
        jac[3] = (1.0 - y[0] * y[0]) / 1e-6;
        true
    }
}

fn implicit(c: &mut Criterion) {
    let mut g = c.benchmark_group("radau5");
    let opts = IntegratorOptions {
        t_end: 1e11,
        rtol: 1e-8,
        atol: 1e-14,
        t_out: vec![1e11],
        ..IntegratorOptions::default()
    };
    g.bench_function("robertson", |b| {
        b.iter(|| {
            let mut sys = FnSystem {
                dim: 3,
                f: |_t: f64, y: &[f64], dy: &mut [f64]| {
                    let (a, b, c) = (0.04 * y[0], 1e4 * y[1] * y[2], 3e7 * y[1] * y[1]);
                    dy[0] = -a + b;
                    dy[1] = a - b - c;
                    dy[2] = c;
                },
            };
            black_box(radau5(&mut sys, black_box(&[1.0, 0.0, 0.0]), &opts).expect("valid input"))
        })
    });
    let opts = IntegratorOptions {
        t_end: 2.0,
        rtol: 1e-6,
        atol: 1e-6,
        t_out: vec![2.0],
        ..IntegratorOptions::default()
    };
    g.bench_function("vdpol", |b| {
        b.iter(|| black_box(radau5(&mut Vdp, black_box(&[2.0, 0.0]), &opts).expect("valid input")))
    });
    g.finish();

    let mut g = c.benchmark_group("gauss6");
    let period = pendulum_period(2.0, 1.0);
    let opts = IntegratorOptions {
        t_end: 1000.0 * period,
        dt: Some(period / 32.0),
        t_out: vec![1000.0 * period],
        ..IntegratorOptions::default()
    };
    g.bench_function("pendulum", |b| {
        b.iter(|| {
            let mut sys = FnSystem {
                dim: 2,
                f: |_t: f64, y: &[f64], dy: &mut [f64]| {
                    dy[0] = y[1];
                    dy[1] = -y[0].sin();
                },
            };
            black_box(gauss6(&mut sys, black_box(&[2.0, 0.0]), &opts).expect("valid input"))
        })
    });
    g.finish();
}

criterion_group!(benches, implicit);
criterion_main!(benches);
