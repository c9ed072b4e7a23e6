//! Criterion benchmarks of the compiled f64 evaluator (`simulate::compile`)
//! on the 10-link pendulum chain (`gallery::pendulum_chain`), in one run:
//!
//! * `compile/chain10`: compiling M's upper triangle and f (parameters bound);
//! * `eval/chain10/{compiled,tree_walk,hand,hand_tuned}`: evaluating M's
//!   upper triangle and f at one state by the compiled program, by
//!   `Expr::eval_f64` (tree walking), and M (full) and f by the
//!   hand-written Rust of `hand/mod.rs` (the work-precision report's), plain
//!   (one sin_cos per pair) and tuned (one per angle, addition theorems);
//! * `rhs/chain10/{compiled,jit,hand}`: the whole right-hand side y' = (q̇, M⁻¹f),
//!   i.e. the above plus `solve_spd`, interpreted, as machine code
//!   (`--evaluator jit`) and hand-written;
//! * `rhs/double_pendulum/{mass_matrix,accelerations}[_jit]`: M and f
//!   compiled and solved against the compiled exact accelerations, each
//!   interpreted and as machine code.
//!
//! The hand-written chain is checked against qdot's M and f before timing.
//!
//! Measured (2 shared cores under load, so ±30 %): compile ≈ 0.4–0.7 ms;
//! eval compiled ≈ 1.1–2.4 µs, hand ≈ 2.0–3.9 µs (compiled/hand ≈ 0.5–0.65),
//! hand_tuned ≈ 0.65–1.05 µs (compiled/tuned ≈ 1.2–2.2), tree walk ≈
//! 150–360 µs (≈ 130× the compiled program).

#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

#[path = "hand/mod.rs"]
mod hand;

use criterion::{criterion_group, criterion_main, Criterion};
use hand::Hand;
use qdot::engine::poly::Var;
use qdot::expr::atom::{self, Atom};
use qdot::simulate::compile::{compile_with, state_inputs, CompiledDynamics, Engine};
use qdot::simulate::problems::Problem;
use qdot::simulate::System;
use qdot::{Expr, Lagrange, Scene};
use rustc_hash::FxHashMap;
use std::hint::black_box;

const N: usize = 10;
const M: f64 = 1.3;
const L: f64 = 0.7;
const G: f64 = 9.81;

/// The hand-written chain with this bench's m, l, g.
fn hand(tuned: bool) -> Hand {
    let mut p = Problem::chain10();
    p.params = vec![("m", M), ("l", L), ("g", G)];
    Hand::new(&p, tuned)
}

fn setup() -> (Lagrange, Vec<Expr>, FxHashMap<Var, f64>) {
    let l = Scene::parse(&qdot::engine::gallery::pendulum_chain(N))
        .expect("parses")
        .lagrange()
        .expect("derives");
    let upper: Vec<Expr> = (0..N)
        .flat_map(|i| (i..N).map(move |j| (i, j)))
        .map(|(i, j)| l.mass_matrix[i][j].clone())
        .collect();
    let params: FxHashMap<Var, f64> = [("m", M), ("l", L), ("g", G)]
        .iter()
        .map(|(k, v)| (atom::param(k), *v))
        .collect();
    (l, upper, params)
}

fn state() -> (Vec<f64>, Vec<f64>) {
    let q = (0..N).map(|i| 0.3 + 0.17 * i as f64).collect();
    let qd = (0..N).map(|i| 0.5 - 0.11 * i as f64).collect();
    (q, qd)
}

fn chain(c: &mut Criterion) {
    let (lagrange, upper, params) = setup();
    let mut outputs = upper;
    outputs.extend(lagrange.forcing.iter().cloned());
    let inputs = state_inputs(&lagrange.coordinates);
    let prog = compile_with(&outputs, &inputs, &params).expect("compiles");
    let (q, qd) = state();
    let mut x = vec![0.0];
    x.extend(&q);
    x.extend(&qd);

    // The three evaluators agree.
    let k = N * (N + 1) / 2;
    let mut regs = prog.registers();
    let mut out = vec![0.0; k + N];
    prog.eval(&x, &mut regs, &mut out);
    let (mut plain, mut tuned) = (hand(false), hand(true));
    let upper_pairs: Vec<(usize, usize)> =
        (0..N).flat_map(|i| (i..N).map(move |j| (i, j))).collect();
    let vals: FxHashMap<Var, f64> = inputs.iter().copied().zip(x.iter().copied()).collect();
    let env = |a: &Atom| -> Option<f64> {
        match a {
            Atom::Param(p) => params.get(&atom::param(p)).copied(),
            Atom::Coord(name, o) => vals.get(&atom::coord(name, *o)).copied(),
            Atom::Time => Some(0.0),
            _ => None,
        }
    };
    for h in [&mut plain, &mut tuned] {
        let (hm, hf) = h.chain(&q, &qd);
        for (i, e) in outputs.iter().enumerate() {
            let tree = e.eval_f64(&env).expect("evaluates");
            let hand = match upper_pairs.get(i) {
                Some(&(r, c)) => hm[r * N + c],
                None => hf[i - k],
            };
            let scale = tree.abs().max(1.0);
            assert!(
                (out[i] - tree).abs() < 1e-10 * scale,
                "{i}: {} vs {tree}",
                out[i]
            );
            assert!(
                (hand - tree).abs() < 1e-10 * scale,
                "{i}: hand {hand} vs {tree}"
            );
        }
    }
    println!(
        "chain10: {} instructions, {} registers, {} constants",
        prog.instructions().len(),
        prog.n_registers(),
        prog.constants().len()
    );

    c.bench_function("compile/chain10", |b| {
        b.iter(|| compile_with(black_box(&outputs), &inputs, &params).expect("compiles"))
    });
    let mut g = c.benchmark_group("eval/chain10");
    g.bench_function("compiled", |b| {
        b.iter(|| prog.eval(black_box(&x), &mut regs, &mut out))
    });
    g.bench_function("hand", |b| {
        b.iter(|| {
            black_box(plain.chain(black_box(&q), black_box(&qd)));
        })
    });
    g.bench_function("hand_tuned", |b| {
        b.iter(|| {
            black_box(tuned.chain(black_box(&q), black_box(&qd)));
        })
    });
    g.bench_function("tree_walk", |b| {
        b.iter(|| {
            for (o, e) in out.iter_mut().zip(&outputs) {
                *o = e.eval_f64(&env).unwrap_or(f64::NAN);
            }
            black_box(&out);
        })
    });
    g.finish();

    let mut dynamics = CompiledDynamics::new(&lagrange, &params).expect("compiles");
    let mut jit = dynamics.clone();
    assert_eq!(jit.use_engine(Engine::Jit).ran, Engine::Jit);
    let mut y = q.clone();
    y.extend(&qd);
    let mut dy = vec![0.0; 2 * N];
    let mut g = c.benchmark_group("rhs/chain10");
    g.bench_function("compiled", |b| {
        b.iter(|| dynamics.rhs(0.0, black_box(&y), &mut dy))
    });
    g.bench_function("jit", |b| b.iter(|| jit.rhs(0.0, black_box(&y), &mut dy)));
    g.bench_function("hand", |b| {
        b.iter(|| plain.rhs(0.0, black_box(&y), &mut dy))
    });
    g.finish();
}

/// The double pendulum (the 2-link chain): M⁻¹f by `solve_spd` against the
/// compiled exact accelerations (`CompiledDynamics::from_accelerations`).
fn double_pendulum(c: &mut Criterion) {
    let l = Scene::parse(&qdot::engine::gallery::pendulum_chain(2))
        .expect("parses")
        .lagrange()
        .expect("derives");
    let params: FxHashMap<Var, f64> = [("m", M), ("l", L), ("g", G)]
        .iter()
        .map(|(k, v)| (atom::param(k), *v))
        .collect();
    let mut via_m = CompiledDynamics::new(&l, &params).expect("compiles");
    let mut via_acc = CompiledDynamics::from_accelerations(&l, &params).expect("compiles");
    let y = [0.4, -0.3, 0.2, 0.7];
    let (mut d1, mut d2) = ([0.0; 4], [0.0; 4]);
    via_m.rhs(0.0, &y, &mut d1);
    via_acc.rhs(0.0, &y, &mut d2);
    for (a, b) in d1.iter().zip(&d2) {
        assert!((a - b).abs() < 1e-12 * a.abs().max(1.0), "{d1:?} vs {d2:?}");
    }
    let mut g = c.benchmark_group("rhs/double_pendulum");
    g.bench_function("mass_matrix", |b| {
        b.iter(|| via_m.rhs(0.0, black_box(&y), &mut d1))
    });
    g.bench_function("accelerations", |b| {
        b.iter(|| via_acc.rhs(0.0, black_box(&y), &mut d2))
    });
    for (d, name) in [
        (&mut via_m, "mass_matrix_jit"),
        (&mut via_acc, "accelerations_jit"),
    ] {
        assert_eq!(d.use_engine(Engine::Jit).ran, Engine::Jit);
        g.bench_function(name, |b| b.iter(|| d.rhs(0.0, black_box(&y), &mut d1)));
    }
    g.finish();
}

criterion_group!(benches, chain, double_pendulum);
criterion_main!(benches);
