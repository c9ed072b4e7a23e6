//! Criterion benchmarks of `qdot cycle` (issue 36): the single-cylinder
//! engine of examples/mechanisms/slider_crank_engine.qd with Coulomb
//! friction in two pins and the cylinder wall (the values and guess of
//! tests/fixtures/mechanisms/slider_crank_engine.json) over 3,600
//! positions of the crank, `phi=0:360deg:3600`:
//!
//! - `cycle/whole_3600`: scene text → parse → Lagrange's equations →
//!   compile → 3,600 positions, velocities, accelerations, reactions and
//!   frictions, as the command line does it (derivatives of atoms are
//!   memoized process-wide, so after the first iteration the derivation
//!   is warm);
//! - `cycle/positions_3600`: the positions alone, the equations compiled
//!   once ([`CompiledCycle::run`]).
//!
//! The target: 3,600 positions with friction in ≤ 50 ms. After
//! criterion, when `python3 -c 'import numpy'` works, the NumPy reference
//! (scripts/mechanism_reference.py `--time slider_crank_engine 3600`, the
//! same cycle without its per-row checks, best of 3) is timed and both
//! times and their ratio printed.

#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

use criterion::Criterion;
use qdot::cycle::{cycle, parse_guess, CompiledCycle, CycleRequest, CycleTable, Over};
use qdot::Scene;
use std::hint::black_box;
use std::path::Path;
use std::time::{Duration, Instant};

const POSITIONS: usize = 3600;
const ROOT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/..");

/// The fixture's scene and request, over `POSITIONS` positions.
fn engine() -> (String, CycleRequest) {
    let path = Path::new(ROOT).join("tests/fixtures/mechanisms/slider_crank_engine.json");
    let text = std::fs::read_to_string(&path).expect("the engine's fixture");
    let f: serde_json::Value = serde_json::from_str(&text).expect("JSON");
    let scene = std::fs::read_to_string(Path::new(ROOT).join(f["scene"].as_str().unwrap()))
        .expect("the engine's scene");
    let req = CycleRequest {
        over: Over::parse(&format!("phi=0:360deg:{POSITIONS}")).unwrap(),
        set: qdot::output::parse_set_any_sign(f["set"].as_str().unwrap())
            .unwrap()
            .into_iter()
            .collect(),
        guess: parse_guess(f["guess"].as_str().unwrap()).unwrap(),
    };
    (scene, req)
}

/// Every row computed, with its friction.
fn checked(t: CycleTable) -> CycleTable {
    assert_eq!(t.rows.len(), POSITIONS);
    assert!(t.rows.iter().all(|r| r.note.is_none() && r.iterations > 1));
    t
}

fn whole(src: &str, req: &CycleRequest) -> CycleTable {
    let scene = Scene::parse(src).expect("parses");
    cycle(&scene, req).expect("runs")
}

/// The best of `runs` timings of `f`, in seconds.
fn best_of(runs: usize, mut f: impl FnMut()) -> f64 {
    (0..runs)
        .map(|_| {
            let start = Instant::now();
            f();
            start.elapsed().as_secs_f64()
        })
        .fold(f64::INFINITY, f64::min)
}

/// The NumPy reference's seconds for the same cycle, when Python with
/// NumPy is there.
fn numpy_seconds() -> Result<f64, String> {
    let has_numpy = std::process::Command::new("python3")
        .args(["-c", "import numpy"])
        .status()
        .map_err(|e| format!("python3: {e}"))?;
    if !has_numpy.success() {
        return Err("python3 has no numpy (pip install numpy)".into());
    }
    let script = Path::new(ROOT).join("scripts/mechanism_reference.py");
    let out = std::process::Command::new("python3")
        .arg(&script)
        .args(["--time", "slider_crank_engine", &POSITIONS.to_string(), "3"])
        .output()
        .map_err(|e| format!("python3: {e}"))?;
    if !out.status.success() {
        return Err(format!(
            "{} failed: {}",
            script.display(),
            String::from_utf8_lossy(&out.stderr)
        ));
    }
    let text = String::from_utf8_lossy(&out.stdout);
    text.trim()
        .parse()
        .map_err(|_| format!("not a number of seconds: {text}"))
}

fn main() {
    let (src, req) = engine();
    let scene = Scene::parse(&src).expect("parses");
    let mut compiled = CompiledCycle::new(&scene, &req).expect("compiles");
    checked(whole(&src, &req));
    checked(compiled.run().expect("runs"));

    let mut c = Criterion::default()
        .sample_size(20)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(4))
        .configure_from_args();
    let mut g = c.benchmark_group("cycle");
    g.bench_function("whole_3600", |b| {
        b.iter(|| black_box(whole(black_box(&src), &req)))
    });
    g.bench_function("positions_3600", |b| {
        b.iter(|| black_box(compiled.run().expect("runs")))
    });
    g.finish();
    c.final_summary();

    let whole_s = best_of(10, || {
        black_box(whole(&src, &req));
    });
    let positions_s = best_of(10, || {
        black_box(compiled.run().expect("runs"));
    });
    println!(
        "qdot cycle, {POSITIONS} positions of the engine with friction (best of 10): whole {:.1} ms, positions {:.1} ms (target ≤ 50 ms)",
        whole_s * 1e3,
        positions_s * 1e3
    );
    match numpy_seconds() {
        Ok(s) => println!(
            "NumPy reference, the same {POSITIONS} positions (best of 3): {:.1} ms; NumPy / qdot: {:.0}× (whole), {:.0}× (positions)",
            s * 1e3,
            s / whole_s,
            s / positions_s
        ),
        Err(why) => println!("NumPy reference not timed: {why}"),
    }
}
