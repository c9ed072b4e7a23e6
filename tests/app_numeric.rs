//! `simulate`, `sweep` and `codegen` through the application layer:
//! `app::run` within a context gives a typed report that `output::render`
//! writes as the command line does.

use qdot::app::{self, AnyReport, Command, CommandOptions, Context, Format, ProgressHook};
use qdot::simulate::codegen::{CodegenRequest, Lang};
use qdot::simulate::elliptic::pendulum_period;
use qdot::simulate::run::Request;
use qdot::simulate::sweep::{parse_axis, Outcome, Sweep};
use qdot::simulate::Status;
use std::sync::{Arc, Mutex};

const OSCILLATOR: &str = "coordinates x\nparameters m, k\n\
                          kinetic E = 1/2*m*x'^2\npotential V = 1/2*k*x^2";

fn values(pairs: &[(&str, f64)]) -> qdot::solve::equilibrium::Values {
    pairs.iter().map(|(k, v)| (k.to_string(), *v)).collect()
}

fn tight(t_end: f64, points: usize, init: &[(&str, f64)]) -> Request {
    Request {
        t_end,
        points,
        rtol: 1e-12,
        atol: 1e-12,
        init: values(init),
        ..Request::default()
    }
}

fn run(cmd: Command, src: &str, opts: &CommandOptions) -> AnyReport {
    app::run(&Context::new(), cmd, src, opts).expect("the command runs")
}

/// m·ẍ = −k·x from x = 1 at rest is x = cos(2t) for k/m = 4: the rows at
/// t = 0, π/4, π/2, 3π/4, π, and the energy k·x²/2 + m·ẋ²/2 = 2 in each.
#[test]
fn simulate_is_the_exact_solution_of_the_oscillator() {
    let pi = std::f64::consts::PI;
    let opts = CommandOptions {
        set: values(&[("m", 1.0), ("k", 4.0)]),
        simulate: tight(pi, 5, &[("x", 1.0), ("x'", 0.0)]),
        ..CommandOptions::default()
    };
    let report = run(Command::Simulate, OSCILLATOR, &opts);
    let AnyReport::Simulate(r) = &report else {
        panic!("a simulate report: {:?}", report.command());
    };
    let sim = &r.result;
    assert_eq!(sim.run.columns, ["t", "x", "x'", "energy"]);
    assert_eq!(sim.request.set, opts.set);
    assert_eq!(sim.run.solution.status, Status::Done);
    assert_eq!(sim.zero_velocities_note(), None);
    assert!(sim.stopped_early().is_none());
    for (row, x) in sim.run.rows.iter().zip([1.0, 0.0, -1.0, 0.0, 1.0]) {
        assert!((row[1] - x).abs() < 1e-9, "x({}) = {}", row[0], row[1]);
        assert!((row[3] - 2.0).abs() < 1e-9, "energy {}", row[3]);
    }
    // its CSV is the command line's
    let csv = qdot::output::render(&report, Format::Csv).expect("CSV");
    assert!(csv.starts_with("t,x,x',energy\n0.00000000000000000e0,1.00000000000000000e0,"));
    assert_eq!(csv.lines().count(), 6);
    let json = qdot::output::render(&report, Format::Json).expect("JSON");
    assert!(
        json.starts_with("{\"method\":\"dop853\",\"status\":\"done\","),
        "{json}"
    );
    // and no LaTeX
    let e = qdot::output::render(&report, Format::Latex).unwrap_err();
    assert_eq!(e.message, "`simulate` writes csv, json, not latex");
}

/// The pendulum from θ = 3 at rest first passes θ = 0 after a quarter of
/// its period 4·K(sin²(θ₀/2))/ω₀ (ω₀² = g/l).
#[test]
fn simulate_stops_at_a_quarter_of_the_pendulums_period() {
    let opts = CommandOptions {
        set: values(&[("m", 1.0), ("l", 1.0), ("g", 1.0)]),
        simulate: Request {
            stop_when: Some("theta = 0".into()),
            ..tight(10.0, 3, &[("theta", 3.0)])
        },
        ..CommandOptions::default()
    };
    let src = std::fs::read_to_string("examples/pendulum.qd").expect("the example");
    let AnyReport::Simulate(r) = run(Command::Simulate, &src, &opts) else {
        panic!("a simulate report");
    };
    let Status::Event { t } = r.result.run.solution.status else {
        panic!("an event: {:?}", r.result.run.solution.status);
    };
    let quarter = pendulum_period(3.0, 1.0) / 4.0;
    assert!((t - quarter).abs() < 1e-9, "{t} against {quarter}");
    assert_eq!(
        r.result.zero_velocities_note().as_deref(),
        Some("note: velocities not given are 0: theta'")
    );
    assert_eq!(
        r.result.event_note(),
        Some(format!(
            "stopped at t = {t:.15e}, where the --stop-when condition changes sign"
        ))
    );
}

/// A sweep of two runs: its CSV, each row the simulation with its values
/// bit for bit, and its progress told from 0 to 2 of 2.
#[test]
fn a_two_run_sweep_is_two_simulations() {
    let src = std::fs::read_to_string("examples/pendulum.qd").expect("the example");
    let told = Arc::new(Mutex::new(Vec::new()));
    let seen = Arc::clone(&told);
    let mut opts = CommandOptions {
        set: values(&[("m", 1.0), ("g", 9.81)]),
        simulate: tight(1.0, 11, &[("theta'", 0.0)]),
        ..CommandOptions::default()
    };
    opts.sweep.axes = vec![
        parse_axis("l=1:2:2").expect("axis"),
        parse_axis("theta=0.5:0.5:1").expect("axis"),
    ];
    opts.sweep.threads = 1;
    opts.sweep.progress = Some(ProgressHook::new(move |done, total| {
        seen.lock().expect("not poisoned").push((done, total))
    }));
    let report = run(Command::Sweep, &src, &opts);
    let AnyReport::Sweep(r) = &report else {
        panic!("a sweep report");
    };
    assert_eq!(
        *told.lock().expect("not poisoned"),
        [(0, 2), (1, 2), (2, 2)]
    );
    assert_eq!(r.result.sweep.threads, 1);
    assert_eq!(r.result.zero_velocities_note(), None);
    assert!(r.result.failures().is_none());
    let csv = qdot::output::render(&report, Format::Csv).expect("CSV");
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(
        lines[0],
        "l,theta,status,t,theta(t),theta'(t),max|theta|,energy_drift,steps"
    );
    assert_eq!(lines.len(), 3);
    for (line, l) in lines[1..].iter().zip([1.0, 2.0]) {
        let one = CommandOptions {
            set: values(&[("m", 1.0), ("g", 9.81), ("l", l)]),
            simulate: tight(1.0, 11, &[("theta", 0.5), ("theta'", 0.0)]),
            ..CommandOptions::default()
        };
        let AnyReport::Simulate(s) = run(Command::Simulate, &src, &one) else {
            panic!("a simulate report");
        };
        let last = s.result.run.rows.last().expect("rows");
        let cells: Vec<&str> = line.split(',').collect();
        assert_eq!(
            cells[..4],
            [&*format!("{l}"), "0.5", "done", "1.00000000000000000e0"]
        );
        assert_eq!(cells[4], format!("{:.17e}", last[1]));
        assert_eq!(cells[5], format!("{:.17e}", last[2]));
    }
}

/// A failed run's message is one CSV cell, its quotes doubled (RFC 4180).
#[test]
fn a_failed_runs_message_is_quoted_as_rfc_4180_says() {
    let done = Outcome {
        status: Status::Done,
        t: 1.0,
        y: vec![0.5, -0.25],
        max_abs_q: vec![0.5],
        energy_drift: None,
        steps: 7,
    };
    let s = Sweep {
        names: vec!["l".into()],
        coordinates: vec!["theta".into()],
        runs: vec![
            (vec![1.0], Ok(done)),
            (vec![2.0], Err("`--stop-when \"x\"`: no, really".into())),
        ],
        seconds: 0.0,
        threads: 1,
        compilations: 2,
    };
    assert_eq!(
        qdot::output::sweep::csv(&s),
        "l,status,t,theta(t),theta'(t),max|theta|,energy_drift,steps\n\
         1,done,1.00000000000000000e0,5.00000000000000000e-1,-2.50000000000000000e-1,5.00000000000000000e-1,,7\n\
         2,\"error: `--stop-when \"\"x\"\"`: no, really\",,,,,,\n"
    );
}

/// `codegen` through the application layer writes what `qdot codegen`
/// writes.
#[test]
fn codegen_is_the_command_lines() {
    let file = "examples/pendulum.qd";
    let src = std::fs::read_to_string(file).expect("the example");
    let opts = CommandOptions {
        set: values(&[("g", 9.81)]),
        codegen: CodegenRequest::new(file, Lang::C),
        ..CommandOptions::default()
    };
    let report = run(Command::Codegen, &src, &opts);
    let code = qdot::output::render(&report, Format::Text).expect("code");
    let cli = std::process::Command::new(env!("CARGO_BIN_EXE_qdot"))
        .args(["codegen", file, "--lang", "c", "--set", "g=9.81"])
        .current_dir(env!("QDOT_ROOT"))
        .output()
        .expect("qdot runs");
    assert!(cli.status.success());
    assert_eq!(code, String::from_utf8(cli.stdout).expect("UTF-8"));
    assert!(code.contains("pendulum_rhs"), "{code}");
    let AnyReport::Codegen(r) = &report else {
        panic!("a codegen report");
    };
    assert_eq!(r.result.request.set, opts.set);
    // the library's own call gives the same code
    let req = CodegenRequest {
        set: opts.set.clone(),
        ..opts.codegen.clone()
    };
    assert_eq!(
        app::codegen(&Context::new(), &src, &req).expect("code"),
        code
    );
}

/// The numeric commands are in the one table of commands, each with its
/// formats.
#[test]
fn the_numeric_commands_are_in_the_table() {
    for (name, formats) in [
        ("simulate", &[Format::Csv, Format::Json][..]),
        ("sweep", &[Format::Csv, Format::Json]),
        ("codegen", &[Format::Text]),
    ] {
        let cmd = Command::from_name(name).expect("a command");
        assert!(Command::ALL.contains(&cmd));
        assert_eq!(cmd.formats(), formats);
    }
    assert_eq!(app::thread_count(0, 1), 1);
    assert_eq!(app::thread_count(3, 2), app::thread_count(2, 2));
}
