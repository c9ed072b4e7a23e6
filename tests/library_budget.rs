//! Issue 52: a library call made without a budget runs within the default
//! one. Every public entry point that does exact work is called, with no
//! budget installed, on the 3D rod chain (`examples/rod_chain.qd`) and the
//! 30-link pendulum chain: each returns, an answer, a refusal with its
//! reason or the default budget's `TooLarge`, and takes at most a few
//! seconds of CPU (measured: at most 5.4 s, 8 s on a loaded machine).
//!
//! The calls run in a child process (this test binary again, on the test
//! [`entry_points_child`]) under a CPU-time bound, so that a call without
//! end fails the test instead of hanging it; the child prints a line per
//! call, and the parent compares the verdicts with the expected ones.

use qdot::app::{self, Context};
use qdot::mechanics::{expanded_generalized_forces, Hamiltonian, Integrals};
use qdot::scene::Structure;
use qdot::solve::linearize::{linearize, Reference};
use qdot::solve::response::ForcedSystem;
use qdot::solve::system::solve_scene;
use qdot::{equilibria, modes, CommandOptions, Diagnostic, Lagrange, Scene};
use std::io::Read;
use std::path::Path;
use std::process::Command as Process;
use std::time::Duration;

/// The scene the child runs on: `rod_chain` or `chain30`.
const ENV: &str = "QDOT_LIBRARY_BUDGET";

/// The test [`entry_points_child`] by its full name in the test crate.
const CHILD: &str = "library_budget::entry_points_child";

/// The most CPU time one call may take: the default budget stops every
/// one of them within a few seconds (measured: at most 7.5 s).
const CALL_SECONDS: f64 = 30.0;

/// This thread's CPU time (user and system), from /proc.
fn thread_cpu() -> Duration {
    let stat = std::fs::read_to_string("/proc/thread-self/stat").expect("/proc/thread-self/stat");
    let after = &stat[stat.rfind(')').expect("the command's end") + 1..];
    let fields: Vec<&str> = after.split_whitespace().collect();
    // utime and stime, the 14th and 15th fields, in USER_HZ = 100 ticks
    let ticks: u64 =
        fields[11].parse::<u64>().expect("utime") + fields[12].parse::<u64>().expect("stime");
    Duration::from_millis(ticks * 10)
}

/// `answer`, `too large` (with the default budget's limit, else the
/// limit), or `refused: MESSAGE`.
fn verdict<T>(r: Result<T, Diagnostic>) -> String {
    match r {
        Ok(_) => "answer".into(),
        Err(d) => match *d.kind {
            qdot::diag::ErrorKind::TooLarge { .. } => {
                let default = format!(
                    "(the limit is {}",
                    qdot::budget::grouped(qdot::limits::DEFAULT_MAX_TERMS)
                );
                if d.message.contains(&default) {
                    "too large".into()
                } else {
                    format!("too large, not at the default: {}", d.message)
                }
            }
            _ => format!("refused: {}", d.message),
        },
    }
}

/// Every entry point on `src`, each as (name, verdict); with `all` false,
/// those that stop at the budget in a phase the rod chain's calls already
/// show are left out (each takes seconds).
fn entry_points(src: &str, all: bool) -> Vec<(String, String)> {
    let mut out = Vec::new();
    let mut call = |name: &str, f: &mut dyn FnMut() -> String| {
        assert!(!qdot::budget::installed(), "{name}: a budget is installed");
        let t0 = thread_cpu();
        let v = f();
        let cpu = (thread_cpu() - t0).as_secs_f64();
        println!("call\t{name}\t{v}\t{cpu:.2}");
        out.push((name.to_string(), v));
    };
    let set = Default::default();
    let expanded = Scene::parse(src).expect("the scene");
    let kept = Scene::read(src, Structure::Auto).expect("the scene");
    call("Scene::parse", &mut || verdict(Scene::parse(src)));
    call("Scene::read", &mut || {
        verdict(Scene::read(src, Structure::Auto))
    });
    call("Lagrange::derive", &mut || {
        verdict(Lagrange::derive(&expanded))
    });
    call("Lagrange::accelerations", &mut || {
        verdict(expanded.lagrange().and_then(|l| l.accelerations()))
    });
    if all {
        call("Lagrange::accelerations (kept)", &mut || {
            verdict(kept.lagrange().and_then(|l| l.accelerations()))
        });
    }
    call("expanded_generalized_forces (kept)", &mut || {
        verdict(expanded_generalized_forces(&kept))
    });
    // the engine's functions that decide signs take the scene's
    // assumptions from their caller
    call("equilibria", &mut || {
        verdict(expanded.assumptions_in_force(|| equilibria(&expanded, &set)))
    });
    call("modes", &mut || {
        verdict(expanded.assumptions_in_force(|| modes(&expanded, None, &set)))
    });
    call("linearize", &mut || {
        verdict(linearize(&expanded, &Reference::at(None)))
    });
    call("ForcedSystem::of_scene", &mut || {
        verdict(ForcedSystem::of_scene(&expanded, None))
    });
    if all {
        call("Hamiltonian::derive", &mut || {
            verdict(Hamiltonian::derive(&expanded))
        });
    }
    call("Integrals::find", &mut || {
        verdict(Integrals::find(&expanded))
    });
    call("solve_scene", &mut || verdict(solve_scene(&expanded)));
    if all {
        for steps in [false, true] {
            let opts = CommandOptions {
                steps,
                ..Default::default()
            };
            let name = if steps {
                "latex::document --steps"
            } else {
                "latex::document"
            };
            call(name, &mut || {
                verdict(qdot::output::latex::document(&expanded, &opts))
            });
        }
        // the application layer installs its context's budget, the default
        call("app::solve", &mut || {
            verdict(app::solve(&Context::new(), src))
        });
    }
    out
}

/// The child's side: the entry points on the scene named in the
/// environment (in the parent this test has nothing to do).
#[test]
fn entry_points_child() {
    let Ok(which) = std::env::var(ENV) else {
        return;
    };
    let src = scene(&which);
    // after the harness's `test NAME ... ` on the same line
    println!();
    entry_points(&src, which == "rod_chain");
    println!("done");
}

fn scene(which: &str) -> String {
    match which {
        "rod_chain" => {
            std::fs::read_to_string(Path::new(env!("QDOT_ROOT")).join("examples/rod_chain.qd"))
                .expect("examples/rod_chain.qd")
        }
        "chain30" => qdot::engine::gallery::pendulum_chain(30),
        other => panic!("no scene {other}"),
    }
}

/// The child's verdicts on `which`, each call's CPU time checked.
fn verdicts(which: &str) -> Vec<(String, String)> {
    let exe = std::env::current_exe().expect("the test binary");
    let mut command = Process::new(&exe);
    command
        .args([CHILD, "--exact", "--nocapture", "--test-threads=1"])
        .env(ENV, which);
    // the whole child: every call's bound, with room
    let mut child = crate::bound::spawn_bounded(&exe, &mut command, 240, 4096);
    drop(child.child.stdin.take());
    let mut err = child.child.stderr.take().expect("stderr");
    let errs = std::thread::spawn(move || {
        let mut s = String::new();
        let _ = err.read_to_string(&mut s);
        s
    });
    let mut out = String::new();
    child
        .child
        .stdout
        .take()
        .expect("stdout")
        .read_to_string(&mut out)
        .expect("the child's output");
    let (code, timed_out, cpu) = child.wait();
    let errs = errs.join().unwrap_or_default();
    assert!(
        !timed_out && code == Some(0) && out.contains("\ndone\n"),
        "{which}: code {code:?}, timed out {timed_out} after {cpu:?}\n{out}\n{errs}"
    );
    out.lines()
        .filter_map(|l| l.strip_prefix("call\t"))
        .map(|l| {
            let f: Vec<&str> = l.split('\t').collect();
            let seconds: f64 = f[2].parse().expect("seconds");
            assert!(seconds < CALL_SECONDS, "{which}: {l}");
            (f[0].to_string(), f[1].to_string())
        })
        .collect()
}

fn expect(which: &str, expected: &[(&str, &str)]) {
    let got = verdicts(which);
    let got: Vec<(&str, &str)> = got.iter().map(|(a, b)| (a.as_str(), b.as_str())).collect();
    pretty_assertions::assert_eq!(got, expected, "{which}");
}

const NO_CLOSED_FORM: &str = "refused: no closed form for these equilibrium equations; they can be solved numerically given parameter values";
const NO_LOAD: &str = "refused: the scene has no harmonic load: the frequency response needs a force F·cos(p·t) (or sin) on the system";

/// The rod chain's accelerations expanded, its Hamiltonian and its LaTeX
/// (which solves for the accelerations expanded) pass the default budget;
/// through its intermediates it answers.
#[test]
fn every_entry_point_on_the_rod_chain_returns_within_the_default_budget() {
    expect(
        "rod_chain",
        &[
            ("Scene::parse", "answer"),
            ("Scene::read", "answer"),
            ("Lagrange::derive", "answer"),
            ("Lagrange::accelerations", "too large"),
            ("Lagrange::accelerations (kept)", "answer"),
            ("expanded_generalized_forces (kept)", "answer"),
            ("equilibria", NO_CLOSED_FORM),
            ("modes", "answer"),
            ("linearize", "answer"),
            ("ForcedSystem::of_scene", NO_LOAD),
            ("Hamiltonian::derive", "too large"),
            ("Integrals::find", "answer"),
            ("solve_scene", "answer"),
            ("latex::document", "answer"),
            ("latex::document --steps", "too large"),
            ("app::solve", "answer"),
        ],
    );
}

/// The 30-link chain's accelerations pass the default budget, and its
/// equilibria the case limit.
#[test]
fn every_entry_point_on_a_thirty_link_chain_returns_within_the_default_budget() {
    expect(
        "chain30",
        &[
            ("Scene::parse", "answer"),
            ("Scene::read", "answer"),
            ("Lagrange::derive", "answer"),
            ("Lagrange::accelerations", "too large"),
            ("expanded_generalized_forces (kept)", "answer"),
            ("equilibria", "refused: too many equilibria: the exact search for the equilibria split into more than 10,000 cases (each root of one equation put into the others is a case)"),
            ("modes", "answer"),
            ("linearize", "answer"),
            ("ForcedSystem::of_scene", NO_LOAD),
            ("Integrals::find", "answer"),
            ("solve_scene", "answer"),
        ],
    );
}
