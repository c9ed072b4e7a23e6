//! One right-hand side y' = F(t, y) of the report's problems on every
//! engine, side by side in one run: the interpreter of the register
//! program, the machine code (`--evaluator jit`), and the hand-written Rust
//! of `hand/mod.rs` (plain and tuned).
//!
//! ```text
//! cargo run --release -p qdot-benches --example rhs_engines            # the table
//! cargo run --release -p qdot-benches --example rhs_engines -- chain10 jit 100000
//! ```
//!
//! The table: ns per right-hand side (the minimum over 7 timed batches at a
//! few states), the JIT's compile time (the best of 3) and code size, and the ratios
//! jit / hand-written and interpreter / jit. With `PROBLEM ENGINE COUNT`
//! (ENGINE: `interpreter`, `jit`, `hand`, `tuned`) it only evaluates COUNT
//! right-hand sides, for `valgrind --tool=callgrind`: the instructions of
//! two counts, subtracted, over their difference are the instructions per
//! right-hand side without the set-up. With COUNT `sim` it integrates the
//! problem once by DOP853 at rtol = atol = 1e-10 (the whole simulation, for
//! callgrind).

#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

#[path = "../hand/mod.rs"]
mod hand;

use hand::Hand;
use qdot::simulate::compile::Engine;
use qdot::simulate::problems::Problem;
use qdot::simulate::{integrate, IntegratorOptions, Method, System};
use std::hint::black_box;
use std::time::Instant;

/// The problems: pendulum, double pendulum, seed 24.2, the 10-link chain.
fn problems() -> Vec<Problem> {
    vec![
        Problem::pendulum(),
        Problem::double_pendulum(),
        Problem::two_mode(),
        Problem::chain10(),
    ]
}

/// A few states near y0, cycled through.
fn states(p: &Problem) -> Vec<Vec<f64>> {
    (0..8)
        .map(|k| {
            p.y0.iter()
                .enumerate()
                .map(|(i, v)| v + 0.1 * ((k * 7 + i) as f64).sin())
                .collect()
        })
        .collect()
}

fn system(p: &Problem, engine: &str) -> Box<dyn System> {
    match engine {
        "hand" => Box::new(Hand::new(p, false)),
        "tuned" => Box::new(Hand::new(p, true)),
        e => {
            let mut d = p.dynamics().expect("compiles");
            let engine = Engine::by_name(e).expect("an engine");
            let r = d.use_engine(engine);
            assert!(
                engine == Engine::Interpreter || r.ran == Engine::Jit,
                "{r:?}"
            );
            Box::new(d)
        }
    }
}

/// ns per right-hand side: the minimum over 7 batches.
fn time(sys: &mut dyn System, ys: &[Vec<f64>]) -> f64 {
    let mut dy = vec![0.0; ys[0].len()];
    let mut batch = 1usize;
    // a batch of about 5 ms
    loop {
        let t = Instant::now();
        for k in 0..batch {
            sys.rhs(0.3, black_box(&ys[k % ys.len()]), &mut dy);
        }
        if t.elapsed().as_secs_f64() > 5e-3 {
            break;
        }
        batch *= 2;
    }
    let mut best = f64::INFINITY;
    for _ in 0..7 {
        let t = Instant::now();
        for k in 0..batch {
            sys.rhs(0.3, black_box(&ys[k % ys.len()]), &mut dy);
            black_box(&dy);
        }
        best = best.min(t.elapsed().as_secs_f64() / batch as f64);
    }
    best * 1e9
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if let [name, engine, count] = args.as_slice() {
        let p = problems()
            .into_iter()
            .find(|p| p.name == name)
            .expect("pendulum, double_pendulum, two_mode or chain10");
        let mut sys = system(&p, engine);
        if count == "sim" {
            // one DOP853 run over the problem's [0, t_end] at 1e-10
            let opts = IntegratorOptions {
                t_end: p.t_end,
                rtol: 1e-10,
                atol: 1e-10,
                t_out: vec![p.t_end],
                max_steps: 50_000_000,
                ..IntegratorOptions::default()
            };
            let sol = integrate(sys.as_mut(), Method::Dop853, &p.y0, &opts).expect("integrates");
            println!("{} RHS, y(T) = {:?}", sol.stats.rhs_evals, sol.y.last());
            return;
        }
        let ys = states(&p);
        let count: usize = count.parse().expect("a count");
        let mut dy = vec![0.0; p.y0.len()];
        for k in 0..count {
            sys.rhs(0.3, black_box(&ys[k % ys.len()]), &mut dy);
            black_box(&dy);
        }
        return;
    }
    println!(
        "| problem | evaluator | interpreter ns | jit ns | hand ns | tuned ns | jit / hand | jit / tuned | interpreter / jit | jit compile ms | code bytes |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|");
    for p in problems() {
        let ys = states(&p);
        let mut d = p.dynamics().expect("compiles");
        // the compile time: the best of 3
        let report = (0..3)
            .map(|_| d.use_engine(Engine::Jit))
            .min_by(|a, b| a.compile_seconds.total_cmp(&b.compile_seconds))
            .expect("three");
        let t: Vec<f64> = ["interpreter", "jit", "hand", "tuned"]
            .iter()
            .map(|e| time(system(&p, e).as_mut(), &ys))
            .collect();
        println!(
            "| {} | {} | {:.1} | {:.1} | {:.1} | {:.1} | {:.2} | {:.2} | {:.2} | {:.2} | {} |",
            p.name,
            d.evaluator().name(),
            t[0],
            t[1],
            t[2],
            t[3],
            t[1] / t[2],
            t[1] / t[3],
            t[0] / t[1],
            report.compile_seconds * 1e3,
            report.code_bytes
        );
    }
}
