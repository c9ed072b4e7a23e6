//! `qdot sweep`: every run of a grid is the run `qdot simulate` makes with
//! those values; random designs are reproducible on any number of threads;
//! the scene is compiled once when only initial values vary; bad input is
//! refused with a hint. And `simulate --plot` draws the dense output.

use std::process::Command;

fn qdot(args: &[&str]) -> (bool, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_qdot"))
        .args(args)
        .current_dir(env!("QDOT_ROOT"))
        .output()
        .expect("qdot runs");
    (
        out.status.success(),
        String::from_utf8(out.stdout).expect("UTF-8"),
        String::from_utf8(out.stderr).expect("UTF-8"),
    )
}

const PENDULUM: &str = "examples/pendulum.qd";

#[test]
fn every_grid_run_is_the_simulation_with_its_values() {
    let (ok, out, err) = qdot(&[
        "sweep",
        PENDULUM,
        "--set",
        "m=1,g=9.81",
        "--init",
        "theta'=0",
        "--vary",
        "l=0.5:2:4",
        "--vary",
        "theta=0.1:3:3",
        "--t-end",
        "3",
    ]);
    assert!(ok, "{err}");
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(
        lines[0],
        "l,theta,status,t,theta(t),theta'(t),max|theta|,energy_drift,steps"
    );
    assert_eq!(lines.len(), 1 + 12);
    // the first axis varies slowest: l = 0.5 for the first three rows
    let values: Vec<(String, String)> = lines[1..]
        .iter()
        .map(|l| {
            let c: Vec<&str> = l.split(',').collect();
            (c[0].to_string(), c[1].to_string())
        })
        .collect();
    assert_eq!(values[0], ("0.5".into(), "0.1".into()));
    assert_eq!(values[1], ("0.5".into(), "1.55".into()));
    assert_eq!(values[3], ("1".into(), "0.1".into()));
    assert_eq!(values[11], ("2".into(), "3".into()));
    for row in [0usize, 4, 11] {
        let cells: Vec<&str> = lines[1 + row].split(',').collect();
        assert_eq!(cells[2], "done");
        let (ok, sim, err) = qdot(&[
            "simulate",
            PENDULUM,
            "--set",
            &format!("m=1,g=9.81,l={}", cells[0]),
            "--init",
            &format!("theta={},theta'=0", cells[1]),
            "--t-end",
            "3",
        ]);
        assert!(ok, "{err}");
        let last: Vec<&str> = sim.lines().last().expect("rows").split(',').collect();
        // t, theta, theta' of the last row are the sweep's final state
        assert_eq!(&cells[3..6], &last[0..3], "row {row}");
        // max |θ| over the same output times
        let max = sim
            .lines()
            .skip(1)
            .map(|l| {
                l.split(',')
                    .nth(1)
                    .expect("theta")
                    .parse::<f64>()
                    .expect("a number")
                    .abs()
            })
            .fold(0.0, f64::max);
        assert_eq!(cells[6].parse::<f64>().expect("max"), max);
    }
}

#[test]
fn random_points_are_reproducible_on_any_number_of_threads_and_compiled_once() {
    let run = |threads: &str, seed: &str| {
        qdot(&[
            "sweep",
            PENDULUM,
            "--set",
            "m=1,g=9.81,l=1",
            "--init",
            "theta'=0",
            "--vary",
            "theta=0.1:3",
            "--samples",
            "300",
            "--seed",
            seed,
            "--t-end",
            "2",
            "--threads",
            threads,
            "--stats",
        ])
    };
    let (ok1, a, err1) = run("1", "7");
    // the interpreter asked for by name gives the same rows as auto
    // (machine code, when built with it, is bit for bit the interpreter)
    let (ok0, a0, _) = qdot(&[
        "sweep",
        PENDULUM,
        "--set",
        "m=1,g=9.81,l=1",
        "--init",
        "theta'=0",
        "--vary",
        "theta=0.1:3",
        "--samples",
        "300",
        "--seed",
        "7",
        "--t-end",
        "2",
        "--evaluator",
        "interpreter",
    ]);
    assert!(ok0);
    assert_eq!(a0, a);
    let (ok2, b, err2) = run("2", "7");
    let (_, c, _) = run("2", "8");
    assert!(ok1 && ok2, "{err1}{err2}");
    assert_eq!(a, b);
    assert_ne!(a, c);
    assert_eq!(a.lines().count(), 301);
    for line in a.lines().skip(1) {
        let theta: f64 = line
            .split(',')
            .next()
            .expect("theta")
            .parse()
            .expect("a number");
        assert!((0.1..3.0).contains(&theta), "{theta}");
    }
    assert!(err1.contains("300 runs on 1 threads"), "{err1}");
    assert!(err2.contains("300 runs on 2 threads"), "{err2}");
    assert!(
        err1.contains("equations compiled 1 time;") || err1.ends_with("compiled 1 time\n"),
        "{err1}"
    );
}

#[test]
fn json_output_has_its_keys() {
    let (ok, out, err) = qdot(&[
        "sweep",
        PENDULUM,
        "--set",
        "m=1,g=9.81",
        "--init",
        "theta=1,theta'=0",
        "--vary",
        "l=1:2:2",
        "--t-end",
        "1",
        "--output",
        "json",
    ]);
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).expect("JSON");
    assert_eq!(v["names"], serde_json::json!(["l"]));
    assert_eq!(v["coordinates"], serde_json::json!(["theta"]));
    assert_eq!(v["runs"].as_array().expect("runs").len(), 2);
    let run = &v["runs"][1];
    assert_eq!(run["values"], serde_json::json!([2.0]));
    assert_eq!(run["status"], "done");
    assert_eq!(run["t"], 1.0);
    assert_eq!(run["y"].as_array().expect("y").len(), 2);
    assert!(run["energy_drift"].as_f64().expect("drift") < 1e-6);
    assert!(v["threads"].as_u64().expect("threads") >= 1);
}

#[test]
fn bad_sweeps_are_refused_with_a_hint() {
    let base = [
        "sweep",
        PENDULUM,
        "--set",
        "m=1,g=9.81,l=1",
        "--init",
        "theta'=0",
        "--t-end",
        "1",
    ];
    let cases: &[(&[&str], &str, &str)] = &[
        (
            &["--vary", "x=0:1:3"],
            "`x` is not a parameter, a coordinate or a velocity",
            "the parameters are m, l, g",
        ),
        (
            &["--vary", "theta=0:1"],
            "a grid needs COUNT",
            "--samples N",
        ),
        (
            &["--vary", "theta=0:1:0"],
            "COUNT `0` must be a whole number from 1 to 1,000,000",
            "--vary NAME=FROM:TO:COUNT",
        ),
        (
            &["--vary", "theta=0;1"],
            "1 parts after `=`, and it takes 2 or 3 (FROM:TO or FROM:TO:COUNT)",
            "--vary",
        ),
        (&["--vary", "theta=a:1:2"], "`a` is not a number", "--vary"),
        (
            &["--vary", "theta=0:1:2000", "--vary", "theta'=0:1:1000"],
            "2000 × 1000 runs: more than 1,000,000",
            "split the study",
        ),
        (
            &["--vary", "theta=0:1", "--samples", "0"],
            "`--samples 0`: a random design needs at least one run",
            "--samples 100",
        ),
    ];
    for (extra, message, hint) in cases {
        let mut args: Vec<&str> = base.to_vec();
        args.extend_from_slice(extra);
        let (ok, _, err) = qdot(&args);
        assert!(!ok, "{extra:?} should fail");
        assert!(err.contains(message), "{extra:?}: {err}");
        assert!(err.contains(hint), "{extra:?}: {err}");
    }
    // a missing value is one error, before any run
    let (ok, out, err) = qdot(&[
        "sweep",
        PENDULUM,
        "--set",
        "m=1,g=9.81",
        "--vary",
        "l=1:2:3",
        "--t-end",
        "1",
    ]);
    assert!(!ok && out.is_empty());
    assert_eq!(
        err,
        "error: no initial value for the coordinate theta\n  = hint: give every coordinate a value (a velocity not given is 0): --init theta=0\n"
    );
    // a velocity not given is 0, as in simulate, and the note says so once
    let (ok, out, err) = qdot(&[
        "sweep",
        PENDULUM,
        "--set",
        "m=1,g=9.81",
        "--init",
        "theta=0.5",
        "--vary",
        "l=1:2:2",
        "--t-end",
        "1",
    ]);
    assert!(ok, "{err}");
    assert_eq!(err, "note: velocities not given are 0: theta'\n");
    let (ok, explicit, _) = qdot(&[
        "sweep",
        PENDULUM,
        "--set",
        "m=1,g=9.81",
        "--init",
        "theta=0.5,theta'=0",
        "--vary",
        "l=1:2:2",
        "--t-end",
        "1",
    ]);
    assert!(ok);
    assert_eq!(out, explicit);
    // a varied velocity is given
    let (ok, _, err) = qdot(&[
        "sweep",
        PENDULUM,
        "--set",
        "m=1,g=9.81,l=1",
        "--init",
        "theta=0.5",
        "--vary",
        "theta'=0:1:2",
        "--t-end",
        "1",
    ]);
    assert!(ok && err.is_empty(), "{err}");
}

#[test]
fn a_failed_run_is_a_row_not_an_abort() {
    // at a = b the mass matrix (a − b) is singular: that run fails, the
    // others go on
    let dir = std::env::temp_dir().join(format!("qdot-sweep-fail-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a temp dir");
    let scene = dir.join("singular.qd");
    std::fs::write(
        &scene,
        "coordinates x\nparameters a, b, k\nkinetic E = 1/2*(a - b)*x'^2\npotential V = 1/2*k*x^2\n",
    )
    .expect("the scene");
    let (ok, out, err) = qdot(&[
        "sweep",
        scene.to_str().expect("a path"),
        "--set",
        "b=1,k=1",
        "--init",
        "x=1,x'=0",
        "--vary",
        "a=1:2:2",
        "--t-end",
        "1",
    ]);
    assert!(ok, "{err}");
    let lines: Vec<&str> = out.lines().collect();
    assert!(lines[1].starts_with("1,\"error: "), "{}", lines[1]);
    assert!(lines[2].starts_with("2,done,"), "{}", lines[2]);
    assert!(err.contains("1 of 2 runs failed"), "{err}");
}

#[test]
fn the_plot_samples_the_dense_output_whatever_the_points() {
    let dir = std::env::temp_dir().join(format!("qdot-sweep-plot-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a temp dir");
    let svg = dir.join("p.svg");
    let (ok, out, err) = qdot(&[
        "simulate",
        PENDULUM,
        "--set",
        "m=1,l=1,g=9.81",
        "--init",
        "theta=2.5,theta'=0",
        "--t-end",
        "10",
        "--points",
        "3",
        "--plot",
        svg.to_str().expect("a path"),
    ]);
    assert!(ok, "{err}");
    // the CSV keeps its three rows
    assert_eq!(out.lines().count(), 4, "{out}");
    let text = std::fs::read_to_string(&svg).expect("the SVG");
    // the q(t) curve: one polyline with the 4,000 samples (and the 3 rows, 2 of them shared)
    let longest = text
        .split("<polyline")
        .skip(1)
        .map(|p| {
            p.split("points=\"").nth(1).map_or(0, |s| {
                s.split('"').next().unwrap_or("").split_whitespace().count()
            })
        })
        .max()
        .unwrap_or(0);
    assert!(
        longest >= 2_000,
        "the longest polyline has {longest} points"
    );
}

/// simulate, sweep and codegen derive outside `output::run_with`; they run
/// under `--max-terms` as every command does. The exact accelerations are
/// an option: past the budget, M and f serve; past it for M and f, the
/// error names the statement in its source.
#[test]
fn the_work_budget_holds_for_simulate_sweep_and_codegen() {
    let scene = "examples/double_pendulum.qd";
    let init = "th1=1,th2=1,th1'=0,th2'=0";
    let simulate = |terms: &str| {
        qdot(&[
            "simulate",
            scene,
            "--set",
            "m1=1,m2=1,l1=1,l2=1,g=9.81",
            "--init",
            init,
            "--t-end",
            "1",
            "--points",
            "2",
            "--stats",
            "--max-terms",
            terms,
        ])
    };
    let sweep = |terms: &str| {
        qdot(&[
            "sweep",
            scene,
            "--set",
            "m1=1,l1=1,l2=1,g=9.81",
            "--init",
            init,
            "--vary",
            "m2=1:2:2",
            "--t-end",
            "1",
            "--max-terms",
            terms,
        ])
    };
    let codegen = |terms: &str| qdot(&["codegen", scene, "--lang", "c", "--max-terms", terms]);
    for (name, (ok, _, err)) in [
        ("simulate", simulate("2")),
        ("sweep", sweep("2")),
        ("codegen", codegen("2")),
    ] {
        assert!(!ok, "{name}");
        assert!(
            err.contains("expression too large: 3 terms while evaluating `E` (the limit is 2)"),
            "{name}: {err}"
        );
        assert!(
            err.contains("--> examples/double_pendulum.qd:9:13"),
            "{name}: {err}"
        );
        assert!(err.contains("--max-terms 20"), "{name}: {err}");
    }
    let (ok, out, err) = simulate("5");
    assert!(ok, "{err}");
    assert!(
        err.contains("evaluator mass_matrix: no exact accelerations: past the work budget"),
        "{err}"
    );
    // the same trajectory as with the exact accelerations, to rounding
    let (_, full, _) = simulate("2000000");
    let last = |s: &str| -> Vec<f64> {
        s.lines()
            .last()
            .expect("a row")
            .split(',')
            .map(|x| x.parse().expect("a number"))
            .collect()
    };
    for (a, b) in last(&out).iter().zip(last(&full)) {
        assert!((a - b).abs() < 1e-6, "{a} {b}");
    }
    let (ok, out, err) = sweep("5");
    assert!(ok, "{err}");
    assert_eq!(
        out.lines().filter(|l| l.contains(",done,")).count(),
        2,
        "{out}"
    );
    let (ok, out, err) = codegen("5");
    assert!(ok, "{err}");
    assert!(out.contains("M·q̈ = f solved by Cholesky"), "{out}");
}
