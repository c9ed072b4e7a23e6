//! The numeric studies `cycle`, `response` and `floquet` through the
//! application layer (`app::run` → typed report → `output::render`): what
//! the REPL and Python call, the same bytes as the CLI.

use crate::common::run::qdot;
use qdot::app::{self, AnyReport, Command, CommandOptions, Context, Format, FrequencyResponse};

fn source(file: &str) -> String {
    std::fs::read_to_string(format!("{}/{file}", env!("QDOT_ROOT"))).expect("scene")
}

const SET_213: &str =
    "G1=20,G2=15,G3=10,g=9.81,R=0.1,AB=0.4,AC=0.15,J2=0.02,k=500,l0=0.45,mu=0.15,omega=20";

fn cycle_options() -> CommandOptions {
    CommandOptions {
        over: app::parse_over(Command::Cycle, "phi=0:360deg:13").expect("over"),
        set: qdot::output::parse_set_any_sign(SET_213).expect("set"),
        guess: qdot::cycle::parse_guess("x2=0.25,xB=0.5").expect("guess"),
        ..CommandOptions::default()
    }
}

/// The CLI's standard output for `args`, which must succeed.
fn cli(args: &[&str]) -> String {
    let (code, out, err) = qdot(args);
    assert_eq!(code, 0, "{err}");
    out
}

#[test]
fn cycle_through_app_is_the_clis_table() {
    let src = source("examples/seed_21_3.qd");
    let report = app::run(&Context::new(), Command::Cycle, &src, &cycle_options()).expect("cycle");
    let AnyReport::Cycle(r) = &report else {
        panic!("a cycle report");
    };
    assert!(r.result.degrees, "phi is the crank's angle");
    assert_eq!(r.result.table.rows.len(), 13);
    let args = [
        "cycle",
        "examples/seed_21_3.qd",
        "--over",
        "phi=0:360deg:13",
        "--set",
        SET_213,
        "--guess",
        "x2=0.25,xB=0.5",
    ];
    for (fmt, name) in [
        (Format::Csv, "csv"),
        (Format::Json, "json"),
        (Format::Text, "text"),
    ] {
        let ours = qdot::output::render(&report, fmt).expect("rendered");
        let theirs = cli(&[&args[..], &["--output", name]].concat());
        assert_eq!(ours, theirs, "--output {name}");
    }
    let csv = qdot::output::render(&report, Format::Csv).expect("csv");
    let first = csv.lines().nth(1).expect("a row");
    // phi = 0: the crank along x, the rocker's pin B at x = AB + … = 0.5
    assert!(first.starts_with("0.00000000000000000e0,"), "{first}");
    assert!(
        first.contains(",5.00000000000000000e-1,"),
        "xB = 0.5 at phi = 0: {first}"
    );
    // LaTeX is not a table's format
    let e = qdot::output::render(&report, Format::Latex).unwrap_err();
    assert_eq!(e.message, "`cycle` writes csv, json, text, not latex");
}

#[test]
fn cycle_columns_choose_what_is_written() {
    let mut opts = cycle_options();
    opts.columns = Some(vec!["M".into(), "O_x".into()]);
    let src = source("examples/seed_21_3.qd");
    let report = app::run(&Context::new(), Command::Cycle, &src, &opts).expect("cycle");
    let csv = qdot::output::render(&report, Format::Csv).expect("csv");
    assert_eq!(csv.lines().next(), Some("phi,M,O_x,note"));
    opts.columns = Some(vec!["Q".into()]);
    let e = app::run(&Context::new(), Command::Cycle, &src, &opts).unwrap_err();
    assert_eq!(e.message, "`--columns Q`: the table has no column `Q`");
}

#[test]
fn response_through_app_exact_and_swept() {
    let src = source("examples/vibration_absorber.qd");
    let ctx = Context::new();
    let exact = app::run(&ctx, Command::Response, &src, &CommandOptions::default()).expect("exact");
    let AnyReport::Response(r) = &exact else {
        panic!("a response report");
    };
    let FrequencyResponse::Exact(e) = &r.result else {
        panic!("exact without over");
    };
    // Den Hartog: the machine stands still at Ω² = k2/m2
    let anti: Vec<String> = e.1.antiresonances[0]
        .iter()
        .map(|w| r.print(w).expect("printed"))
        .collect();
    assert_eq!(anti, ["k2/m2"]);
    for (fmt, name) in [(Format::Text, "text"), (Format::Json, "json")] {
        let ours = qdot::output::render(&exact, fmt).expect("rendered");
        let theirs = cli(&[
            "response",
            "examples/vibration_absorber.qd",
            "--output",
            name,
        ]);
        assert_eq!(ours, theirs, "--output {name}");
    }
    let set = "m1=1,m2=0.2,k1=1,k2=0.2,c=0.02,F0=1";
    let opts = CommandOptions {
        set: qdot::output::parse_set_any_sign(set).expect("set"),
        over: app::parse_over(Command::Response, "Omega=0.6:1.4:9").expect("over"),
        ..CommandOptions::default()
    };
    let swept = app::run(&ctx, Command::Response, &src, &opts).expect("swept");
    let AnyReport::Response(r) = &swept else {
        panic!("a response report");
    };
    let FrequencyResponse::Swept(t) = &r.result else {
        panic!("swept with over");
    };
    assert_eq!(t.omega.len(), 9);
    // at the tuning Ω = 1 = √(k2/m2) the absorber holds the machine to a
    // fortieth of its amplitude at the resonance Ω = 0.8 (damped: not 0)
    let x1 = t.amplitude[4][0].expect("finite");
    let peak = t.amplitude[2][0].expect("finite");
    assert!((x1 - 0.497518595105).abs() < 1e-9, "|X1| at Ω = 1: {x1}");
    assert!(x1 < peak / 39.0, "{x1} against {peak}");
    let csv = qdot::output::render(&swept, Format::Csv).expect("csv");
    assert_eq!(
        csv.lines().next(),
        Some("Omega,amp_x1,phase_x1,amp_x2,phase_x2")
    );
    assert!(csv
        .lines()
        .nth(1)
        .is_some_and(|l| l.starts_with("5.99999999999999978e-1,1.89441919060055364e0,")));
    let theirs = cli(&[
        "response",
        "examples/vibration_absorber.qd",
        "--set",
        set,
        "--over",
        "Omega=0.6:1.4:9",
        "--output",
        "csv",
    ]);
    assert_eq!(csv, theirs);
    // the exact response has no CSV
    let e = qdot::output::render(&exact, Format::Csv).unwrap_err();
    assert_eq!(e.message, "unknown output `csv`");
}

#[test]
fn floquet_through_app_on_mathieu() {
    let src = source("examples/mathieu.qd");
    let opts = CommandOptions {
        set: qdot::output::parse_set_any_sign("m=1,w=1").expect("set"),
        over: app::parse_over(Command::Floquet, "delta=-0.5:2.5:13,eps=0:2:5").expect("over"),
        ..CommandOptions::default()
    };
    let report = app::run(&Context::new(), Command::Floquet, &src, &opts).expect("floquet");
    let AnyReport::Floquet(r) = &report else {
        panic!("a floquet report");
    };
    assert_eq!(r.result.points.len(), 65);
    // delta = -0.5, eps = 0: x'' = x/2 grows by exp(2π/√2) = 85.0197 a period
    let (v, f) = &r.result.points[0];
    assert_eq!(v, &[-0.5, 0.0]);
    let f = f.as_ref().expect("analysed");
    let grows = (2.0 * std::f64::consts::PI / 2f64.sqrt()).exp();
    assert!((f.max_abs - grows).abs() < 1e-6 * grows, "{}", f.max_abs);
    assert_eq!(f.verdict, qdot::floquet::Verdict::Unstable);
    for (fmt, name) in [
        (Format::Text, "text"),
        (Format::Csv, "csv"),
        (Format::Json, "json"),
    ] {
        let ours = qdot::output::render(&report, fmt).expect("rendered");
        let theirs = cli(&[
            "floquet",
            "examples/mathieu.qd",
            "--set",
            "m=1,w=1",
            "--over",
            "delta=-0.5:2.5:13,eps=0:2:5",
            "--output",
            name,
        ]);
        assert_eq!(ours, theirs, "--output {name}");
    }
}

#[test]
fn every_study_is_a_command_with_its_formats() {
    for (cmd, name) in [
        (Command::Cycle, "cycle"),
        (Command::Response, "response"),
        (Command::Floquet, "floquet"),
    ] {
        assert_eq!(Command::from_name(name), Some(cmd));
        assert!(cmd.formats().contains(&Format::Csv));
        assert!(!cmd.formats().contains(&Format::Latex));
    }
    assert_eq!(Format::from_name("csv"), Some(Format::Csv));
    assert!(!Command::Derive.formats().contains(&Format::Csv));
    // an exact command has no CSV
    let src = "coordinates x\nparameters m, k\nkinetic E = 1/2*m*x'^2\npotential V = 1/2*k*x^2";
    let r = app::run(
        &Context::new(),
        Command::Solve,
        src,
        &CommandOptions::default(),
    )
    .expect("solve");
    let e = qdot::output::render(&r, Format::Csv).unwrap_err();
    assert_eq!(e.message, "`solve` writes text, json, latex, not csv");
    // cycle needs its varied quantity
    let e = app::run(
        &Context::new(),
        Command::Cycle,
        src,
        &CommandOptions::default(),
    )
    .unwrap_err();
    assert_eq!(
        e.message,
        "`qdot cycle` varies one quantity, and 0 were given"
    );
}

/// The one reader of `NAME=FROM:TO:COUNT` ranges and grids
/// (`scene::given::parse_ranges`): the values it reads, and one message
/// per failure.
#[test]
fn one_range_reader() {
    use qdot::scene::given::{parse_ranges, GridAxis, CYCLE_OVER, FLOQUET_OVER, RESPONSE_OVER};
    use qdot::simulate::sweep::SWEEP_VARY;
    use std::f64::consts::PI;
    let one = |syntax, text: &str| {
        let mut axes = parse_ranges(syntax, text).expect(text);
        assert_eq!(axes.len(), 1, "{text}");
        axes.remove(0)
    };
    let axis = |name: &str, from: f64, to: f64, count: usize| GridAxis {
        name: name.into(),
        from,
        to,
        count,
    };
    assert_eq!(
        one(&CYCLE_OVER, "phi=0:360deg:73"),
        axis("phi", 0.0, 360.0 * (PI / 180.0), 73)
    );
    assert_eq!(
        one(&CYCLE_OVER, " t = -pi : 2pi : 5 "),
        axis("t", -PI, 2.0 * PI, 5)
    );
    assert_eq!(
        one(&CYCLE_OVER, "phi=-90°:2*pi:2"),
        axis("phi", -90.0 * (PI / 180.0), 2.0 * PI, 2)
    );
    // constant expressions
    let e = one(&RESPONSE_OVER, "Omega=pi/4:sqrt(2):3");
    assert_eq!((e.from, e.to), (PI / 4.0, 2f64.sqrt()));
    assert_eq!(one(&CYCLE_OVER, "t=1/4:3/4:2"), axis("t", 0.25, 0.75, 2));
    // a grid, and sweep's range without COUNT
    let grid = parse_ranges(&FLOQUET_OVER, "delta=-1:3:81,eps=0:2:41").expect("grid");
    assert_eq!(
        grid,
        [axis("delta", -1.0, 3.0, 81), axis("eps", 0.0, 2.0, 41)]
    );
    assert_eq!(one(&SWEEP_VARY, "l=0.5:2"), axis("l", 0.5, 2.0, 0));
    assert_eq!(
        GridAxis::parse("phi=0:1:3").expect("parse"),
        axis("phi", 0.0, 1.0, 3)
    );
    let refused = |syntax, text: &str, message: &str| {
        let e = parse_ranges(syntax, text).expect_err(text);
        assert_eq!(e.message, message, "{text}");
        e
    };
    let e = refused(&CYCLE_OVER, "phi", "`--over phi`: no `=`");
    assert_eq!(e.hint.as_deref(), Some(CYCLE_OVER.hint));
    refused(&CYCLE_OVER, "=0:1:3", "`--over =0:1:3`: no name before `=`");
    refused(
        &CYCLE_OVER,
        "phi=0:360deg",
        "`--over phi=0:360deg`: 2 parts after `=`, and it takes 3 (FROM:TO:COUNT)",
    );
    refused(
        &CYCLE_OVER,
        "phi=0:x:3",
        "`--over phi=0:x:3`: `x` is not a number",
    );
    refused(
        &CYCLE_OVER,
        "phi=0:1e400:3",
        "`--over phi=0:1e400:3`: `1e400` is beyond the range of double precision (about 1.8e308)",
    );
    refused(
        &CYCLE_OVER,
        "phi=0:1:0",
        "`--over phi=0:1:0`: COUNT `0` must be a whole number from 1 to 1,000,000",
    );
    refused(
        &CYCLE_OVER,
        "phi=0:1:1000001",
        "`--over phi=0:1:1000001`: COUNT `1000001` must be a whole number from 1 to 1,000,000",
    );
    refused(
        &CYCLE_OVER,
        "phi=0:1:3,t=0:1:3",
        "`--over phi=0:1:3,t=0:1:3`: one quantity varies, not more",
    );
    let e = refused(
        &FLOQUET_OVER,
        "delta=0:1:3,eps=0:1",
        "`--over delta=0:1:3,eps=0:1`: `eps=0:1`: 2 parts after `=`, and it takes 3 (FROM:TO:COUNT)",
    );
    assert_eq!(e.hint.as_deref(), Some(FLOQUET_OVER.hint));
    refused(
        &FLOQUET_OVER,
        "delta=0:1:1001,eps=0:1:1000",
        "`--over delta=0:1:1001,eps=0:1:1000`: 1,001,000 points, more than 1,000,000",
    );
    refused(
        &FLOQUET_OVER,
        "a=0:1:2,b=0:1:2,c=0:1:2",
        "`--over a=0:1:2,b=0:1:2,c=0:1:2`: one or two parameters vary, not more",
    );
    refused(
        &FLOQUET_OVER,
        "d=0:1:2,d=0:1:2",
        "`--over d`: `d` is varied twice",
    );
    refused(
        &SWEEP_VARY,
        "l=0.5:2:3:4",
        "`--vary l=0.5:2:3:4`: 4 parts after `=`, and it takes 2 or 3 (FROM:TO or FROM:TO:COUNT)",
    );
    // the commands read their --over so
    assert_eq!(
        app::parse_over(Command::Response, "p=0:1:10")
            .unwrap_err()
            .message,
        "`--over p=0:1:10`: `qdot response` varies the forcing frequency, `Omega`, not `p`"
    );
    assert_eq!(
        app::parse_over(Command::Solve, "p=0:1:10")
            .unwrap_err()
            .message,
        "`qdot solve` takes no --over"
    );
}
