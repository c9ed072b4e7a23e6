//! Criterion benchmarks of the exact core.
//!
//! * `seed/<problem>`: parse + derive + exact solve of each seed example:
//!   accelerations and `solve` blocks (target: under 100 µs each for the
//!   Lagrange scenes) — the kinetostatic ones side by side with SymPy's
//!   `linsolve` on the same system (`scripts/anchor_kinetostatic.py`).
//! * `equilibrium/<problem>`: closed-form equilibria and their stability.
//! * `modes/<scene>`: linearization, det(K − λM) factored, exact ω² and
//!   modes — side by side with SymPy (`scripts/anchor_kinetostatic.py`).
//! * `npendulum/derive/<n>`: parse + derive (equations, mass matrix,
//!   forcing) of the n-link pendulum chain, n = 2…12 — measured side by side
//!   with ../shared/anchors/symengine_npendulum.py (`scripts/anchors.sh`).
//! * `npendulum/solve/<n>`: the exact accelerations in lowest terms.
//! * `frames/heavy_top`: the heavy top end to end (target: under 1 ms);
//!   `frames/chain3d/<n>`: the equations of n rods in space, beside SymPy's
//!   LagrangesMethod (`scripts/anchor_frames.py`);
//!   `frames/chain3d_structured/<n>`: the same chain's equations and
//!   accelerations through named intermediates, beside SymPy's KanesMethod
//!   (`scripts/anchor_kane.py`).
//! * `compact/<scene>`: printing every acceleration of a panel scene in its
//!   compact form (the search of `qdot::expr::compact`; target: the double
//!   pendulum under 10 ms) — beside SymPy's `simplify` on the same
//!   expressions (`scripts/compact_panel.py time`).
//! * `lazy/{solve,derive}/<n>`: `qdot solve` and `qdot derive` (parse,
//!   derive, print) of the 1-dof oscillator with n unused definitions
//!   `u_i = (a+b+x)^30`, which are checked but not evaluated (issue 35);
//!   `lazy/parse/<n>`: reading that text alone, the floor of the others.

#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use qdot::Scene;
use std::hint::black_box;

fn seeds(c: &mut Criterion) {
    let mut g = c.benchmark_group("seed");
    for name in qdot::engine::gallery::SEED_EXAMPLES {
        let path = format!(
            "{}/examples/{name}.qd",
            concat!(env!("CARGO_MANIFEST_DIR"), "/..")
        );
        let src = std::fs::read_to_string(&path).expect("example exists");
        g.bench_function(*name, |b| {
            b.iter(|| {
                let s = Scene::parse(black_box(&src)).expect("parses");
                if s.has_dynamics() {
                    let l = s.lagrange().expect("derives");
                    black_box(l.accelerations().expect("solves"));
                }
                black_box(qdot::solve::system::solve_scene(&s).expect("blocks solve"))
            })
        });
    }
    g.finish();
}

fn equilibria(c: &mut Criterion) {
    let mut g = c.benchmark_group("equilibrium");
    let scenes = [
        ("seed_23_1", std::fs::read_to_string(format!("{}/examples/seed_23_1.qd", concat!(env!("CARGO_MANIFEST_DIR"), "/.."))).expect("example exists")),
        ("hoop", "coordinates th\nparameters m, g, r, W\nkinetic E = 1/2*m*r^2*(th'^2 + W^2*sin(th)^2)\npotential V = -m*g*r*cos(th)\n".to_string()),
    ];
    for (name, src) in &scenes {
        g.bench_function(*name, |b| {
            b.iter(|| {
                let s = Scene::parse(black_box(src)).expect("parses");
                black_box(
                    qdot::solve::equilibrium::equilibria(&s, &Default::default()).expect("solves"),
                )
            })
        });
    }
    g.finish();
}

fn modes(c: &mut Criterion) {
    let mut g = c.benchmark_group("modes");
    let chain = "coordinates x1, x2, x3\nparameters m, k\n\
        kinetic E = 1/2*m*(x1'^2 + x2'^2 + x3'^2)\n\
        potential V = 1/2*k*(x1^2 + (x2 - x1)^2 + (x3 - x2)^2 + x3^2)\n"
        .to_string();
    let seed = std::fs::read_to_string(format!(
        "{}/examples/seed_24_2.qd",
        concat!(env!("CARGO_MANIFEST_DIR"), "/..")
    ))
    .expect("example exists");
    for (name, src) in [("seed_24_2", seed), ("chain3", chain)] {
        g.bench_function(name, |b| {
            b.iter(|| {
                let s = Scene::parse(black_box(&src)).expect("parses");
                black_box(
                    qdot::solve::oscillations::modes(&s, None, &Default::default()).expect("modes"),
                )
            })
        });
    }
    g.finish();
}

fn npendulum(c: &mut Criterion) {
    let mut g = c.benchmark_group("npendulum/derive");
    g.sample_size(20);
    for n in [2usize, 3, 4, 6, 8, 10, 12] {
        let src = qdot::engine::gallery::pendulum_chain(n);
        g.bench_with_input(BenchmarkId::from_parameter(n), &src, |b, src| {
            b.iter(|| {
                let s = Scene::parse(black_box(src)).expect("parses");
                black_box(s.lagrange().expect("derives"))
            })
        });
    }
    g.finish();
    let mut g = c.benchmark_group("npendulum/solve");
    g.sample_size(10);
    for n in [2usize, 3] {
        let src = qdot::engine::gallery::pendulum_chain(n);
        g.bench_with_input(BenchmarkId::from_parameter(n), &src, |b, src| {
            b.iter(|| {
                let s = Scene::parse(black_box(src)).expect("parses");
                black_box(
                    s.lagrange()
                        .expect("derives")
                        .accelerations()
                        .expect("solves"),
                )
            })
        });
    }
    g.finish();
}

/// Frames and rigid bodies: the heavy top end to end (parse → equations →
/// accelerations), and the equations of the chain of n rods in space
/// (`qdot::engine::gallery::rod_chain_3d`) beside SymPy's LagrangesMethod on the
/// same system (`scripts/anchor_frames.py`, run by `scripts/anchors.sh`).
fn frames(c: &mut Criterion) {
    let mut g = c.benchmark_group("frames");
    let top = std::fs::read_to_string(format!(
        "{}/examples/heavy_top.qd",
        concat!(env!("CARGO_MANIFEST_DIR"), "/..")
    ))
    .expect("example exists");
    g.bench_function("heavy_top", |b| {
        b.iter(|| {
            let s = Scene::parse(black_box(&top)).expect("parses");
            let l = s.lagrange().expect("derives");
            black_box(l.accelerations().expect("solves"))
        })
    });
    g.finish();
    let mut g = c.benchmark_group("frames/chain3d");
    g.sample_size(10);
    for n in [2usize, 3, 5, 10] {
        let src = qdot::engine::gallery::rod_chain_3d(n);
        g.bench_with_input(BenchmarkId::from_parameter(n), &src, |b, src| {
            b.iter(|| {
                let s = Scene::parse(black_box(src)).expect("parses");
                black_box(s.lagrange().expect("derives"))
            })
        });
    }
    g.finish();
    // through named intermediates (`Scene::parse_structured`): the
    // accelerations too, beside SymPy's KanesMethod (`scripts/anchor_kane.py`)
    let mut g = c.benchmark_group("frames/chain3d_structured");
    g.sample_size(10);
    for n in [4usize, 8, 20] {
        let src = qdot::engine::gallery::rod_chain_3d(n);
        g.bench_with_input(BenchmarkId::from_parameter(n), &src, |b, src| {
            b.iter(|| {
                let s = Scene::parse_structured(black_box(src)).expect("parses");
                let l = s.lagrange().expect("derives");
                black_box(l.accelerations().expect("solves"))
            })
        });
    }
    g.finish();
}

fn compact(c: &mut Criterion) {
    let mut g = c.benchmark_group("compact");
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/..");
    for path in [
        "tests/data/compact/double_pendulum.qd",
        "tests/data/compact/triple_pendulum.qd",
        "tests/data/compact/cart_double_pendulum.qd",
        "examples/heavy_top.qd",
    ] {
        let src = std::fs::read_to_string(format!("{root}/{path}")).expect("scene exists");
        let s = Scene::parse(&src).expect("parses");
        let acc = s
            .lagrange()
            .expect("derives")
            .accelerations()
            .expect("solves");
        let name = path
            .rsplit('/')
            .next()
            .unwrap_or(path)
            .trim_end_matches(".qd");
        g.bench_function(name, |b| {
            b.iter(|| {
                for e in acc.values() {
                    black_box(e.to_input());
                }
            })
        });
    }
    g.finish();
}

/// The oscillator with `n` definitions nothing uses.
fn oscillator_with_unused(n: usize) -> String {
    let mut src = "coordinates x\nparameters m, k, a, b\nkinetic E = 1/2*m*x'^2\n\
                   potential V = 1/2*k*x^2\n"
        .to_string();
    for i in 1..=n {
        src.push_str(&format!("u{i} = (a+b+x)^30\n"));
    }
    src
}

fn lazy(c: &mut Criterion) {
    use qdot::output::{run, Command, Format};
    let mut g = c.benchmark_group("lazy");
    for n in [0, 300] {
        let src = oscillator_with_unused(n);
        // the floor: reading the text, which every definition costs
        g.bench_with_input(BenchmarkId::new("parse", n), &src, |b, src| {
            b.iter(|| black_box(qdot::parse::parse_scene(src).expect("parses")))
        });
        for (name, cmd) in [("solve", Command::Solve), ("derive", Command::Derive)] {
            g.bench_with_input(BenchmarkId::new(name, n), &src, |b, src| {
                b.iter(|| {
                    black_box(run(cmd, src, Format::Text, &Default::default()).expect("runs"))
                })
            });
        }
    }
    g.finish();
}

criterion_group!(benches, seeds, equilibria, modes, npendulum, frames, compact, lazy);
criterion_main!(benches);
