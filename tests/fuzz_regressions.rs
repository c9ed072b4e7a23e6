//! Every input the fuzzers ever found (fuzz/regressions/TARGET/*) and the
//! seed corpus (fuzz/corpus/TARGET/*) replayed through the fuzz targets'
//! own code (fuzz/src/pipeline.rs, included below), each in a child
//! process under a CPU-time and an address-space bound (`crate::bound`), so that a panic, an
//! abort, a stack overflow, a hang and a memory blow-up all fail the test
//! (each named with its file) instead of the whole test binary.
//!
//! The child is this test binary itself, re-run on the test [`replay`]
//! with `QDOT_FUZZ_REPLAY` set; fuzz/README.md says how a finding gets here.

use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::Command;

#[allow(dead_code)]
#[path = "../fuzz/src/pipeline.rs"]
mod pipeline;

/// The bounds of one replay: the fuzzers' `-timeout` (seconds, here of
/// CPU time) and `-rss_limit_mb`, the latter as an address-space limit.
const SECONDS: u64 = 10;
const MEMORY_MIB: u64 = 2048;

/// The test [`replay`] by its full name in the test crate.
const REPLAY_TEST: &str = "fuzz_regressions::replay";

/// `TARGET` then the files, one a line.
const ENV: &str = "QDOT_FUZZ_REPLAY";

/// The child's side: replay the files named in `QDOT_FUZZ_REPLAY` (in the
/// parent this test has nothing to do).
#[test]
fn replay() {
    let Ok(job) = std::env::var(ENV) else {
        return;
    };
    let mut lines = job.lines();
    let target = lines.next().expect("a target");
    for file in lines {
        eprintln!("replaying {file}");
        let data = std::fs::read(file).expect("the input file");
        match target {
            "self-test-panic" => panic!("a planted panic"),
            "self-test-overflow" => {
                std::hint::black_box(deep(data.len() as u64 + 1));
            }
            // a hang that computes: the CPU-time bound ends it
            "self-test-hang" => loop {
                std::hint::black_box(0u64);
            },
            _ => pipeline::by_name(target, &data),
        }
    }
    eprintln!("replayed cleanly");
}

/// Recursion without bound, for [`the_replay_catches_failures`].
#[allow(unconditional_recursion)]
fn deep(n: u64) -> u64 {
    let pad = std::hint::black_box([n; 64]);
    deep(pad[(n % 64) as usize] + 1) + pad[0]
}

/// The files of `dir`, sorted (none when it does not exist).
fn files(dir: &Path) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .map(|rd| rd.filter_map(|e| e.ok().map(|e| e.path())).collect())
        .unwrap_or_default();
    v.retain(|p| p.is_file() && !p.ends_with("README.md"));
    v.sort();
    v
}

/// Replay `inputs` through `target` in a bounded child: `None` when clean,
/// else what went wrong.
fn replay_bounded(target: &str, inputs: &[PathBuf], seconds: u64) -> Option<String> {
    let mut job = target.to_string();
    for f in inputs {
        job.push('\n');
        job.push_str(&f.to_string_lossy());
    }
    let exe = std::env::current_exe().expect("the test binary");
    let mut command = Command::new(&exe);
    command
        .args([REPLAY_TEST, "--exact", "--nocapture", "--test-threads=1"])
        .env(ENV, job)
        .env("RUST_BACKTRACE", "0");
    let mut bounded = crate::bound::spawn_bounded(&exe, &mut command, seconds, MEMORY_MIB);
    drop(bounded.child.stdin.take());
    // drain both pipes while the child runs (a long panic message must not block it)
    let mut out = bounded.child.stdout.take().expect("stdout");
    let drain = std::thread::spawn(move || {
        let _ = std::io::copy(&mut out, &mut std::io::sink());
    });
    let mut pipe = bounded.child.stderr.take().expect("stderr");
    let reader = std::thread::spawn(move || {
        let mut s = String::new();
        let _ = pipe.read_to_string(&mut s);
        s
    });
    let (code, timed_out, _) = bounded.wait();
    let _ = drain.join();
    let err = reader.join().unwrap_or_default();
    let last = err
        .lines()
        .rfind(|l| l.starts_with("replaying "))
        .map_or("", |l| &l["replaying ".len()..])
        .to_string();
    if timed_out {
        return Some(format!("{last}: timed out after {seconds} s of CPU"));
    }
    if code == Some(0) && err.contains("replayed cleanly") {
        return None;
    }
    // the panic message, or the runtime's last words (stack overflow, failed allocation)
    let why: Vec<&str> = err
        .lines()
        .filter(|l| !l.starts_with("replaying ") && !l.trim().is_empty())
        .filter(|l| !l.starts_with("running ") && !l.starts_with("test "))
        .take(4)
        .collect();
    let status = match code {
        Some(c) => format!("exit status {c}"),
        None => "ended by a signal".to_string(),
    };
    Some(format!("{last}: {status}: {}", why.join(" | ")))
}

/// Each regression of `target` in its own child; every failure listed.
fn regressions(target: &str) {
    let root = Path::new(env!("QDOT_ROOT"));
    let inputs = files(&root.join("fuzz/regressions").join(target));
    let failures: Vec<String> = inputs
        .iter()
        .filter_map(|f| replay_bounded(target, std::slice::from_ref(f), SECONDS))
        .collect();
    assert!(
        failures.is_empty(),
        "{} of {} fuzz regressions of `{target}` fail:\n{}",
        failures.len(),
        inputs.len(),
        failures.join("\n")
    );
}

#[test]
fn parse_regressions() {
    regressions("parse");
}

#[test]
fn pipeline_regressions() {
    regressions("pipeline");
}

#[test]
fn repl_regressions() {
    regressions("repl");
}

#[test]
fn simulate_regressions() {
    regressions("simulate");
}

#[test]
fn commands_regressions() {
    regressions("commands");
}

#[test]
fn motions_regressions() {
    regressions("motions");
}

/// The seeds of the numeric studies and of the whole command table
/// (`cycle`, `response`, `floquet`, `check`, `derive`, `codegen` through
/// the REPL, the `commands` target and a `pipeline` header) replay
/// cleanly, each in its own child; the application's commands are all
/// reached.
#[test]
fn every_command_has_replaying_seeds() {
    let root = Path::new(env!("QDOT_ROOT"));
    let mut reached = std::collections::BTreeSet::new();
    for target in ["repl", "commands", "pipeline"] {
        let seeds: Vec<PathBuf> = files(&root.join("fuzz/corpus").join(target))
            .into_iter()
            .filter(|f| {
                let name = f.file_name().map(|n| n.to_string_lossy().into_owned());
                name.is_some_and(|n| n.starts_with(&format!("seed-{target}-")))
            })
            .collect();
        assert!(seeds.len() >= 3, "`{target}` has {} seeds", seeds.len());
        for f in &seeds {
            let text = std::fs::read_to_string(f).expect("a seed");
            for c in qdot::app::Command::ALL {
                let name = c.name();
                if text.contains(&format!(":{name} "))
                    || text.contains(&format!("--command {name}\n"))
                    || text.starts_with(&format!("#@ {name} "))
                {
                    reached.insert(name);
                }
            }
            assert_eq!(replay_bounded(target, std::slice::from_ref(f), 60), None);
        }
    }
    for name in ["cycle", "response", "floquet"] {
        assert!(reached.contains(name), "{name} in {reached:?}");
    }
}

/// The committed seeds replay cleanly (one child per target, a bound for
/// the whole corpus), and there are seeds for every target.
#[test]
fn seed_corpus_replays_cleanly() {
    let root = Path::new(env!("QDOT_ROOT"));
    for target in pipeline::TARGETS {
        let inputs = files(&root.join("fuzz/corpus").join(target));
        assert!(inputs.len() >= 10, "`{target}` has {} seeds", inputs.len());
        let verdict = replay_bounded(target, &inputs, 60);
        assert_eq!(verdict, None, "a seed of `{target}` fails");
    }
}

/// The replay itself catches what it must: a child that panics, one that
/// overflows its stack and one that hangs are each reported, with the file.
#[test]
fn the_replay_catches_failures() {
    let dir = std::env::temp_dir().join(format!("qdot-fuzz-replay-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let file = dir.join("x");
    std::fs::write(&file, "x").expect("temp file");
    let files = [file];
    for (target, needle) in [
        ("self-test-panic", "panicked"),
        ("self-test-overflow", "overflow"),
        ("self-test-hang", "timed out"),
    ] {
        let verdict = replay_bounded(target, &files, 3).unwrap_or_default();
        assert!(
            verdict.contains(needle) && verdict.contains("x"),
            "{target}: {verdict:?}"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}
