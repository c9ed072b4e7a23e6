//! A fingerprint of the explicit methods' results, to check that a change
//! of the driver leaves them bit for bit as they were: every method on
//! systems of dimension 1 to 21 (coupled, nonlinear), with every step
//! recorded, with output times (the dense output), with an event, with a
//! stiff system (the stiffness test), at fixed steps, and on the report's
//! problems (machine code). One line per case: its name, a hash of the bits
//! of every recorded time and state, the counters and the status.
//!
//! ```text
//! cargo run --release -p qdot-benches --example driver_bits > before.txt
//! # … change the driver …
//! cargo run --release -p qdot-benches --example driver_bits | diff before.txt -
//! ```

use qdot::simulate::compile::Engine;
use qdot::simulate::explicit::integrate_fixed;
use qdot::simulate::problems::Problem;
use qdot::simulate::{
    integrate, integrate_with_event, FnSystem, IntegratorOptions, Method, Solution, System,
};

/// FNV-1a over 64-bit words.
struct Fnv(u64);

impl Fnv {
    fn word(&mut self, w: u64) {
        for b in w.to_le_bytes() {
            self.0 ^= u64::from(b);
            self.0 = self.0.wrapping_mul(0x100_0000_01b3);
        }
    }
}

fn fingerprint(sol: &Solution) -> String {
    let mut h = Fnv(0xcbf2_9ce4_8422_2325);
    for (t, y) in sol.t.iter().zip(&sol.y) {
        h.word(t.to_bits());
        for v in y {
            h.word(v.to_bits());
        }
    }
    let s = &sol.stats;
    format!(
        "{:016x} steps {} rejected {} rhs {} points {} {:?} stiff {:?}",
        h.0,
        s.steps,
        s.rejected,
        s.rhs_evals,
        sol.t.len(),
        sol.status,
        sol.stiff_at.map(f64::to_bits)
    )
}

/// A chain of n coupled nonlinear oscillators (n ≥ 1), with a slow forcing
/// in t so that the nodes c matter.
fn chain(n: usize) -> impl FnMut(f64, &[f64], &mut [f64]) {
    move |t: f64, y: &[f64], dy: &mut [f64]| {
        for i in 0..n {
            let left = if i > 0 { y[i - 1] } else { 0.0 };
            let right = if i + 1 < n { y[i + 1] } else { 0.0 };
            let j = (i + 1) % n;
            dy[i] = y[j] - 0.3 * y[i].sin()
                + 0.1 * (left - 2.0 * y[i] + right)
                + 0.05 * (t + i as f64).cos();
        }
    }
}

fn y0(n: usize) -> Vec<f64> {
    (0..n).map(|i| 0.5 + 0.3 * (i as f64 * 1.7).sin()).collect()
}

const METHODS: [Method; 4] = [Method::Rk4, Method::Dopri5, Method::Dop853, Method::Vern7];

fn opts(method: Method, tol: f64, t_out: Vec<f64>) -> IntegratorOptions {
    IntegratorOptions {
        t_end: 6.0,
        rtol: tol,
        atol: tol,
        dt: (method == Method::Rk4).then_some(0.05),
        t_out,
        ..IntegratorOptions::default()
    }
}

fn line(name: String, r: Result<Solution, qdot::simulate::SimError>) {
    match r {
        Ok(sol) => println!("{name}: {}", fingerprint(&sol)),
        Err(e) => println!("{name}: error {e}"),
    }
}

fn main() {
    let grid: Vec<f64> = (0..=37).map(|i| 6.0 * i as f64 / 37.0).collect();
    for n in (1..=12).chain([16, 20, 21]) {
        let y = y0(n);
        for m in METHODS {
            for tol in [1e-3, 1e-7, 1e-11] {
                if m == Method::Rk4 && tol != 1e-3 {
                    continue;
                }
                let mut sys = FnSystem {
                    dim: n,
                    f: chain(n),
                };
                let o = opts(m, tol, Vec::new());
                line(
                    format!("n{n} {m:?} {tol:e} steps"),
                    integrate(&mut sys, m, &y, &o),
                );
                let o = opts(m, tol, grid.clone());
                line(
                    format!("n{n} {m:?} {tol:e} grid"),
                    integrate(&mut sys, m, &y, &o),
                );
                let o = opts(m, tol, vec![6.0]);
                line(
                    format!("n{n} {m:?} {tol:e} end"),
                    integrate(&mut sys, m, &y, &o),
                );
                // backwards, with a first step given
                let o = IntegratorOptions {
                    t0: 6.0,
                    t_end: -1.0,
                    dt: Some(0.1),
                    ..opts(m, tol, vec![5.0, 2.0, -1.0])
                };
                line(
                    format!("n{n} {m:?} {tol:e} back"),
                    integrate(&mut sys, m, &y, &o),
                );
                let mut ev = |_t: f64, y: &[f64]| y[0] - 0.9;
                let o = opts(m, tol, Vec::new());
                line(
                    format!("n{n} {m:?} {tol:e} event"),
                    integrate_with_event(&mut sys, m, &y, &o, &mut ev),
                );
            }
            let mut sys = FnSystem {
                dim: n,
                f: chain(n),
            };
            let o = IntegratorOptions {
                dt: Some(0.07),
                ..opts(m, 1e-6, grid.clone())
            };
            line(
                format!("n{n} {m:?} fixed"),
                integrate_fixed(&mut sys, m, &y, &o),
            );
        }
        // stiff: y' = −λ (y − cos t) with λ = 1e4, every component
        for m in [Method::Dopri5, Method::Dop853, Method::Vern7] {
            let mut sys = FnSystem {
                dim: n,
                f: |t: f64, y: &[f64], dy: &mut [f64]| {
                    for (i, (d, v)) in dy.iter_mut().zip(y).enumerate() {
                        *d = -1e4 * (1.0 + i as f64) * (v - t.cos());
                    }
                },
            };
            let o = IntegratorOptions {
                max_steps: 3000,
                ..opts(m, 1e-6, Vec::new())
            };
            line(format!("n{n} {m:?} stiff"), integrate(&mut sys, m, &y, &o));
            // a blow-up at t = 1/y0: the step shrinks to nothing or overflows
            let mut sys = FnSystem {
                dim: n,
                f: |_t: f64, y: &[f64], dy: &mut [f64]| {
                    for (d, v) in dy.iter_mut().zip(y) {
                        *d = v * v;
                    }
                },
            };
            let ones = vec![1.0; n];
            line(
                format!("n{n} {m:?} blow-up"),
                integrate(&mut sys, m, &ones, &opts(m, 1e-8, Vec::new())),
            );
        }
    }
    // the report's problems on the machine code
    for p in Problem::all() {
        let mut sys = p.dynamics().expect("compiles");
        sys.use_engine(Engine::Jit);
        for m in METHODS {
            for tol in [1e-4, 1e-9] {
                let o = IntegratorOptions {
                    t_end: p.t_end,
                    rtol: tol,
                    atol: tol,
                    dt: (m == Method::Rk4).then_some(0.01),
                    ..IntegratorOptions::default()
                };
                line(
                    format!("{} {m:?} {tol:e}", p.name),
                    integrate(&mut sys as &mut dyn System, m, &p.y0, &o),
                );
            }
        }
    }
}
