//! Criterion benchmark of the dimension check (issue 19: it must cost at
//! most 10% of `solve`): on each seed example, the check alone
//! (`scene::dimension::validate` on the parsed statements, what every
//! command runs on an annotated scene) beside the whole
//! `qdot solve` run of the same annotated scene, in one run.

#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

use criterion::{criterion_group, criterion_main, Criterion};
use qdot::output::{self, Command, Format};
use std::hint::black_box;

fn dimensions(c: &mut Criterion) {
    let mut g = c.benchmark_group("dimensions");
    for name in qdot::engine::gallery::SEED_EXAMPLES {
        let path = format!(
            "{}/examples/{name}.qd",
            concat!(env!("CARGO_MANIFEST_DIR"), "/..")
        );
        let src = std::fs::read_to_string(&path).expect("example exists");
        let stmts = qdot::parse::parse_scene(&src).expect("parses");
        let scene = qdot::Scene::parse(&src).expect("resolves");
        let constant = |n: &str| scene.definition(n).and_then(qdot::Expr::as_rational);
        g.bench_function(format!("check/{name}"), |b| {
            b.iter(|| {
                qdot::scene::dimension::validate(black_box(&src), &stmts, &constant)
                    .expect("checks")
            })
        });
        // statics alone (seed 23.1) has nothing to solve: its command is `equilibrium`
        let cmd = if scene.has_dynamics() || !scene.systems.is_empty() {
            Command::Solve
        } else {
            Command::Equilibrium
        };
        g.bench_function(format!("solve/{name}"), |b| {
            b.iter(|| {
                black_box(
                    output::run(cmd, black_box(&src), Format::Text, &Default::default())
                        .expect("solves"),
                )
            })
        });
    }
    g.finish();
}

criterion_group!(benches, dimensions);
criterion_main!(benches);
