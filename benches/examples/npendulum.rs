//! Library example: derive the n-link pendulum chain and time it.
//!
//! `cargo run --release -p qdot-benches --example npendulum -- 12` prints, for n = 1…N,
//! the seconds to parse and derive the equations (and, for n ≤ 3, to solve
//! for the exact accelerations), in the format of
//! ../shared/anchors/symengine_npendulum.py so the two can be compared
//! side by side in one run.

#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

use std::time::Instant;

fn main() -> Result<(), qdot::Diagnostic> {
    let nmax: usize = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(8);
    let solve_max: usize = std::env::args()
        .nth(2)
        .and_then(|s| s.parse().ok())
        .unwrap_or(3);
    for n in 1..=nmax {
        let src = qdot::engine::gallery::pendulum_chain(n);
        // best of a few runs
        let mut best = f64::INFINITY;
        let mut terms = 0;
        for _ in 0..5 {
            let t0 = Instant::now();
            let scene = qdot::Scene::parse(&src)?;
            let l = scene.lagrange()?;
            best = best.min(t0.elapsed().as_secs_f64());
            terms = l.equations.iter().map(|e| e.lhs.num().len()).sum::<usize>();
        }
        let solve = if n <= solve_max {
            let t0 = Instant::now();
            let scene = qdot::Scene::parse(&src)?;
            let acc = scene.lagrange()?.accelerations()?;
            let dt = t0.elapsed().as_secs_f64();
            let size: usize = acc.iter().map(|(_, e)| e.num().len() + e.den().len()).sum();
            format!("{dt:.4} ({size} terms)")
        } else {
            "skip".into()
        };
        println!("{n} {best:.6} {terms} solve {solve}");
    }
    Ok(())
}
