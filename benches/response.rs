//! Criterion benchmarks of `qdot response --over` (issue 37): the damped
//! chain of ten masses of examples/damped_chain.qd (m = 1, k = 1,
//! c = 0.02, F0 = 1) over 10,000 frequencies, `Omega=0.01:2.5:10000`:
//!
//! - `response/whole_10000`: scene text → parse → linearization → the
//!   program of Ω compiled → 10,000 complex LU solves, amplitudes, phases
//!   and peaks, as the command line does it;
//! - `response/sweep_10000`: the sweep alone, compiled once
//!   ([`CompiledResponse::run`]);
//! - the whole command written out as `--output csv` and `--output json`
//!   (`app::run`, then `output::render`), what the command line prints.
//!
//! The target: 10,000 frequencies of a 10-dof chain in ≤ 50 ms.
//! After criterion, the amplitudes are checked against the NumPy reference
//! (scripts/response_reference.py `--check`), and the reference's batched
//! `numpy.linalg.solve` is timed (`--time 10000 3`, best of 3) and both
//! times and their ratio printed, when `$PYTHON` (default `python3`) has
//! NumPy.

#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

use criterion::Criterion;
use qdot::app::{self, AnyReport, CommandOptions, Context, Format, FrequencyResponse};
use qdot::cycle::Over;
use qdot::simulate::response::{CompiledResponse, ResponseTable};
use qdot::solve::response::ForcedSystem;
use qdot::Scene;
use std::hint::black_box;
use std::path::Path;
use std::process::Command;
use std::time::{Duration, Instant};

const FREQUENCIES: usize = 10_000;
const ROOT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/..");
const SET: &str = "m=1,k=1,c=0.02,F0=1";

fn over(count: usize) -> Over {
    Over::parse(&format!("Omega=0.01:2.5:{count}")).unwrap()
}

fn values() -> qdot::solve::equilibrium::Values {
    qdot::output::parse_set_any_sign(SET).unwrap()
}

/// Every row solved, ten natural frequencies.
fn checked(t: ResponseTable) -> ResponseTable {
    assert_eq!(t.omega.len(), FREQUENCIES);
    assert!(t.amplitude.iter().flatten().all(Option::is_some));
    assert_eq!(t.natural_frequencies.len(), 10);
    t
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

fn python() -> String {
    std::env::var("PYTHON").unwrap_or_else(|_| "python3".into())
}

/// The reference script's stdout for `args`.
fn reference(args: &[&str]) -> Result<String, String> {
    let has_numpy = Command::new(python())
        .args(["-c", "import numpy"])
        .status()
        .map_err(|e| format!("{}: {e}", python()))?;
    if !has_numpy.success() {
        return Err(format!(
            "{} has no numpy (set PYTHON to one that has)",
            python()
        ));
    }
    let script = Path::new(ROOT).join("scripts/response_reference.py");
    let out = Command::new(python())
        .arg(&script)
        .args(args)
        .output()
        .map_err(|e| format!("{}: {e}", python()))?;
    if !out.status.success() {
        return Err(format!(
            "{} failed: {}",
            script.display(),
            String::from_utf8_lossy(&out.stderr)
        ));
    }
    Ok(String::from_utf8_lossy(&out.stdout).into_owned())
}

/// `qdot response --over` of the scene `src` at `set`, through the one
/// door every command goes through ([`app::run`]).
fn sweep(
    src: &str,
    set: &qdot::solve::equilibrium::Values,
    over: &Over,
) -> Result<ResponseTable, qdot::Diagnostic> {
    let opts = CommandOptions {
        set: set.clone(),
        over: vec![over.clone()],
        ..CommandOptions::default()
    };
    match app::run(&Context::new(), app::Command::Response, src, &opts)? {
        AnyReport::Response(r) => match r.result {
            FrequencyResponse::Swept(t) => Ok(t),
            FrequencyResponse::Exact(_) => Err(qdot::Diagnostic::global("no sweep")),
        },
        _ => Err(qdot::Diagnostic::global("no sweep")),
    }
}

/// The whole command, then its table rendered in `fmt`: what
/// `qdot response --over … --output csv|json` prints (its length).
fn rendered(src: &str, set: &qdot::solve::equilibrium::Values, over: &Over, fmt: Format) -> usize {
    let opts = CommandOptions {
        set: set.clone(),
        over: vec![over.clone()],
        ..CommandOptions::default()
    };
    let report = app::run(&Context::new(), app::Command::Response, src, &opts).expect("runs");
    qdot::output::render(&report, fmt).expect("renders").len()
}

/// The largest relative difference of our amplitudes from NumPy's at 101
/// frequencies.
fn numpy_difference(src: &str) -> Result<f64, String> {
    let text = reference(&["--check", "101"])?;
    let theirs: Vec<Vec<f64>> = serde_json::from_str(&text).map_err(|e| e.to_string())?;
    let ours = sweep(src, &values(), &over(101)).map_err(|d| d.message)?;
    let mut worst = 0.0f64;
    for (row, want) in ours.amplitude.iter().zip(&theirs) {
        for (a, b) in row.iter().zip(want) {
            worst = worst.max((a.unwrap() - b).abs() / b.abs());
        }
    }
    Ok(worst)
}

fn main() {
    let src = std::fs::read_to_string(Path::new(ROOT).join("examples/damped_chain.qd"))
        .expect("the chain's scene");
    let scene = Scene::parse(&src).expect("parses");
    let sys = scene
        .assumptions_in_force(|| ForcedSystem::of_scene(&scene, None))
        .expect("linearizes");
    let set = values();
    let over = over(FREQUENCIES);
    let mut compiled = CompiledResponse::new(&scene, &sys, &set).expect("compiles");
    let whole = || sweep(&src, &set, &over).expect("runs");
    checked(whole());
    checked(compiled.run(&over));

    let mut c = Criterion::default()
        .sample_size(20)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(4))
        .configure_from_args();
    let mut g = c.benchmark_group("response");
    g.bench_function("whole_10000", |b| b.iter(|| black_box(whole())));
    g.bench_function("sweep_10000", |b| {
        b.iter(|| black_box(compiled.run(black_box(&over))))
    });
    g.finish();
    c.final_summary();

    let whole_s = best_of(10, || {
        black_box(whole());
    });
    let sweep_s = best_of(10, || {
        black_box(compiled.run(&over));
    });
    let csv_s = best_of(10, || {
        black_box(rendered(&src, &set, &over, Format::Csv));
    });
    let json_s = best_of(10, || {
        black_box(rendered(&src, &set, &over, Format::Json));
    });
    println!(
        "qdot response, {FREQUENCIES} frequencies of the 10-mass chain (best of 10): whole {:.1} ms, sweep {:.1} ms (target ≤ 50 ms); written out: CSV {:.1} ms, JSON {:.1} ms",
        whole_s * 1e3,
        sweep_s * 1e3,
        csv_s * 1e3,
        json_s * 1e3
    );
    match numpy_difference(&src) {
        Ok(d) => println!(
            "amplitudes against NumPy's at 101 frequencies: largest relative difference {d:.1e}"
        ),
        Err(why) => println!("NumPy reference not compared: {why}"),
    }
    match reference(&["--time", &FREQUENCIES.to_string(), "3"])
        .and_then(|t| t.trim().parse::<f64>().map_err(|_| format!("not a number of seconds: {t}")))
    {
        Ok(s) => println!(
            "NumPy reference, the same {FREQUENCIES} frequencies (batched numpy.linalg.solve, best of 3): {:.1} ms; NumPy / qdot: {:.1}× (whole), {:.1}× (sweep), {:.1}× (CSV written), {:.1}× (JSON written)",
            s * 1e3,
            s / whole_s,
            s / sweep_s,
            s / csv_s,
            s / json_s
        ),
        Err(why) => println!("NumPy reference not timed: {why}"),
    }
}
