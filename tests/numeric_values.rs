//! Every numeric option reads its values with one evaluator
//! (`qdot::scene::given::constant_value`): `30deg`, `pi/6`, `2*pi` are
//! accepted by `--set`, `--init`, `--over` and `--vary` of every command,
//! and give exactly the output of the same double written out; the
//! refusals say the same thing everywhere. Also: one range reader for
//! `sweep --vary`, one checked parameter map for `response --over` and
//! `floquet --over`, and `--threads` honoured by `floquet --over`.

use crate::common::run::{qdot, qdot_on};
use qdot::scene::given::{constant_value, ConstantError};

/// A hoop turning at Ω about its vertical diameter, with a bead on it.
const HOOP: &str = "coordinates theta: angle\nparameters m, R, Omega, g\nkinetic E = 1/2*m*R^2*(theta'^2 + Omega^2*sin(theta)^2)\npotential V = -m*g*R*cos(theta)\n";

/// The parameters of seed_21_3 but ω.
const SET_213: &str = "G1=20,G2=15,G3=10,g=9.81,R=0.1,AB=0.4,AC=0.15,J2=0.02,k=500,l0=0.45,mu=0.15";

/// `qdot ARGS`, which must succeed: its standard output and error.
fn ok(args: &[&str]) -> (String, String) {
    let (code, out, err) = qdot(args);
    assert_eq!(code, 0, "qdot {args:?} failed: {err}");
    (out, err)
}

/// `qdot COMMAND HOOP REST`, which must succeed: its outputs.
fn ok_hoop(tag: &str, command: &str, rest: &[&str]) -> (String, String) {
    let (code, out, err) = qdot_on("numeric_values", tag, HOOP, command, rest);
    assert_eq!(code, 0, "qdot {command} {rest:?} failed: {err}");
    (out, err)
}

#[test]
fn the_evaluator_reads_numbers_angles_and_constant_expressions() {
    use std::f64::consts::PI;
    for (text, want) in [
        ("0.1", 0.1),
        ("-2.5e-3", -2.5e-3),
        ("30deg", 30.0 * (PI / 180.0)),
        ("30 °", 30.0 * (PI / 180.0)),
        ("pi", PI),
        ("-pi", -PI),
        ("2pi", 2.0 * PI),
        ("2*pi", 2.0 * PI),
        ("π", PI),
        ("2/5", 0.4),
        ("sqrt(2)", std::f64::consts::SQRT_2),
    ] {
        assert_eq!(constant_value(text), Ok(want), "{text}");
    }
    for (text, why) in [
        ("", ConstantError::NotNumber),
        ("-", ConstantError::NotNumber),
        ("deg", ConstantError::NotNumber),
        ("abc", ConstantError::NotNumber),
        ("inf", ConstantError::NotNumber),
        ("NaN", ConstantError::NotNumber),
        ("sqrt(-1)", ConstantError::NotNumber),
        ("1e400", ConstantError::BeyondRange),
        ("10^400", ConstantError::BeyondRange),
        ("1e-400", ConstantError::BelowSmallest),
        ("1/10^400", ConstantError::BelowSmallest),
    ] {
        assert_eq!(constant_value(text), Err(why), "{text:?}");
    }
}

#[test]
fn init_30deg_and_set_2pi_are_their_doubles_in_simulate_and_sweep() {
    let run = |set: &str, init: &str| {
        ok_hoop(
            "simulate",
            "simulate",
            &[
                "--set", set, "--init", init, "--t-end", "1", "--points", "3",
            ],
        )
    };
    let written = run("m=1,R=1,Omega=2*pi,g=9.81", "theta=30deg");
    assert_eq!(
        written,
        run(
            "m=1,R=1,Omega=6.283185307179586,g=9.81",
            "theta=0.5235987755982988"
        )
    );
    assert_eq!(
        written.0.lines().nth(1),
        Some("0.00000000000000000e0,5.23598775598298816e-1,0.00000000000000000e0,-1.34305114116700217e1")
    );
    let sweep = |set: &str, init: &str, vary: &str| {
        ok_hoop(
            "sweep",
            "sweep",
            &[
                "--set",
                set,
                "--init",
                init,
                "--vary",
                vary,
                "--t-end",
                "1",
                "--points",
                "3",
                "--threads",
                "1",
                "--output",
                "csv",
            ],
        )
        .0
    };
    let written = sweep("m=1,R=1,g=9.81", "theta=pi/6", "Omega=pi:2*pi:2");
    assert_eq!(
        written,
        sweep(
            "m=1,R=1,g=9.81",
            "theta=0.5235987755982988",
            "Omega=3.141592653589793:6.283185307179586:2"
        )
    );
    assert_eq!(
        written
            .lines()
            .nth(2)
            .map(|l| l.split(',').take(2).collect::<Vec<_>>()),
        Some(vec!["6.283185307179586", "done"])
    );
}

#[test]
fn set_2pi_is_its_double_in_modes_equilibrium_and_response() {
    for command in ["modes", "equilibrium"] {
        let run = |omega: &str| {
            ok_hoop(
                command,
                command,
                &["--set", &format!("m=1,R=1,Omega={omega},g=9.81")],
            )
        };
        assert_eq!(run("2*pi"), run("6.283185307179586"), "{command}");
    }
    // the exact modes at θ = 30deg, read in the scene: the same as pi/6
    let at = |init: &str| {
        ok_hoop(
            "modes-init",
            "modes",
            &["--set", "m=1,R=1,Omega=2*pi,g=9.81", "--init", init],
        )
    };
    let written = at("theta=30deg");
    assert_eq!(written, at("theta=pi/6"));
    assert!(written.0.contains("  θ(t) = 1/6·π·cos("), "{}", written.0);
    let response = |set: &str, over: &str| {
        ok(&[
            "response",
            "examples/forced_oscillator.qd",
            "--set",
            set,
            "--over",
            over,
            "--output",
            "csv",
        ])
        .0
    };
    let written = response("m=1,k=4,c=1/10,F0=1", "Omega=0:2*pi:3");
    assert_eq!(
        written,
        response("m=1,k=4,c=0.1,F0=1", "Omega=0:6.283185307179586:3")
    );
    assert_eq!(
        written.lines().last(),
        Some("6.28318530717958623e0,2.81817308792634211e-2,3.12388462440135273e0")
    );
    let exact = |p: &str| {
        ok(&[
            "response",
            "examples/forced_oscillator.qd",
            "--set",
            &format!("m=1,k=4,c=0.1,F0=1,p={p}"),
        ])
    };
    assert_eq!(exact("2*pi"), exact("6.283185307179586"));
}

#[test]
fn set_2pi_is_its_double_in_cycle_and_floquet() {
    let cycle = |omega: &str, over: &str| {
        ok(&[
            "cycle",
            "examples/seed_21_3.qd",
            "--over",
            over,
            "--set",
            &format!("{SET_213},omega={omega}"),
            "--guess",
            "x2=0.25,xB=0.5",
            "--output",
            "text",
        ])
        .0
    };
    assert_eq!(
        cycle("2*pi", "phi=0:360deg:5"),
        cycle("6.283185307179586", "phi=0:6.283185307179586:5")
    );
    let floquet = |at: &str, w: &str| {
        ok(&[
            "floquet",
            "examples/kapitza.qd",
            "--at",
            at,
            "--set",
            &format!("m=1,l=1,g=9.81,a=0.05,w={w}"),
        ])
    };
    assert_eq!(
        floquet("theta=180deg", "20*pi"),
        floquet("theta=pi", "62.83185307179586")
    );
}

#[test]
fn a_value_is_refused_with_the_same_words_by_every_option() {
    let refused = |command: &str, rest: &[&str]| {
        let (code, out, err) = qdot_on("numeric_values", "refused", HOOP, command, rest);
        assert_eq!((code, out.as_str()), (1, ""), "{command} {rest:?}");
        err
    };
    let set = |v: &str| format!("m=1,R=1,Omega={v},g=9.81");
    assert_eq!(
        refused("simulate", &["--set", &set("abc"), "--t-end", "1"]),
        "error: `--set Omega=abc`: `abc` is not a number\n  = hint: write numbers or constant expressions: --set m=1.5,g=9.81,Omega=2*pi\n"
    );
    assert_eq!(
        refused("modes", &["--set", &set("10^400")]),
        "error: `--set Omega=10^400`: `10^400` is beyond the range of double precision (about 1.8e308)\n  = hint: numeric work is done in doubles; rescale the units\n"
    );
    assert_eq!(
        refused("simulate", &["--set", &set("1"), "--init", "theta=1/10^400", "--t-end", "1"]),
        "error: `--init theta=1/10^400`: `1/10^400` is below the smallest double (about 4.9e-324)\n  = hint: numeric work is done in doubles; rescale the units\n"
    );
    assert_eq!(
        refused("simulate", &["--set", &set("1"), "--init", "theta=sqrt(-1)", "--t-end", "1"]),
        "error: `--init theta=sqrt(-1)`: `sqrt(-1)` is not a number\n  = hint: write numbers or constant expressions: --init x=0.1,x'=-2.5,theta=30deg\n"
    );
    assert_eq!(
        refused("sweep", &["--set", "m=1,R=1,g=9.81", "--vary", "Omega=1e400:1:2", "--t-end", "1"]),
        "error: `--vary Omega=1e400:1:2`: `1e400` is beyond the range of double precision (about 1.8e308)\n  = hint: --vary NAME=FROM:TO:COUNT, e.g. --vary \"l=0.5:2:16\" (COUNT may be left out with --samples)\n"
    );
    assert_eq!(
        refused("sweep", &["--set", "m=1,R=1,g=9.81", "--vary", "Omega=:1:2", "--t-end", "1"]),
        "error: `--vary Omega=:1:2`: `` is not a number\n  = hint: --vary NAME=FROM:TO:COUNT, e.g. --vary \"l=0.5:2:16\" (COUNT may be left out with --samples)\n"
    );
    // a comma inside parentheses belongs to its value
    assert_eq!(
        refused("simulate", &["--set", &set("max(1, 2)"), "--t-end", "1"]),
        "error: `--set Omega=max(1, 2)`: `max(1, 2)` is not a number\n  = hint: write numbers or constant expressions: --set m=1.5,g=9.81,Omega=2*pi\n"
    );
}

#[test]
fn every_vary_spelling_of_before_is_read_as_before() {
    use qdot::simulate::sweep::{parse_axis, Axis};
    let axis = |name: &str, from: f64, to: f64, count: usize| Axis {
        name: name.into(),
        from,
        to,
        count,
    };
    for (text, want) in [
        ("l=0.5:2:16", axis("l", 0.5, 2.0, 16)),
        (" l = 0.5 : 2 : 16 ", axis("l", 0.5, 2.0, 16)),
        ("theta'=-1:1", axis("theta'", -1.0, 1.0, 0)),
        ("x=1e-3:2E2:1", axis("x", 1e-3, 2e2, 1)),
        ("x=-.5:+.5:1000000", axis("x", -0.5, 0.5, 1_000_000)),
        (
            "theta=0:90deg:3",
            axis("theta", 0.0, std::f64::consts::FRAC_PI_2, 3),
        ),
    ] {
        assert_eq!(parse_axis(text).map_err(|d| d.message), Ok(want), "{text}");
    }
    for (text, message) in [
        ("theta=0;1", "`--vary theta=0;1`: 1 parts after `=`, and it takes 2 or 3 (FROM:TO or FROM:TO:COUNT)"),
        ("theta=0:1:2:3", "`--vary theta=0:1:2:3`: 4 parts after `=`, and it takes 2 or 3 (FROM:TO or FROM:TO:COUNT)"),
        ("=0:1:2", "`--vary =0:1:2`: no name before `=`"),
        ("theta", "`--vary theta`: no `=`"),
        ("a=0:1:2,b=0:1:2", "`--vary a=0:1:2,b=0:1:2`: one name varies per --vary"),
        ("theta=0:1:1000001", "`--vary theta=0:1:1000001`: COUNT `1000001` must be a whole number from 1 to 1,000,000"),
    ] {
        assert_eq!(parse_axis(text).map_err(|d| d.message), Err(message.to_string()), "{text}");
    }
}

#[test]
fn response_over_checks_its_values_as_every_numeric_command() {
    let refused = |set: &str| {
        let (code, out, err) = qdot(&[
            "response",
            "examples/forced_oscillator.qd",
            "--set",
            set,
            "--over",
            "Omega=0:1:3",
        ]);
        assert_eq!((code, out.as_str()), (1, ""), "{set}");
        err
    };
    assert_eq!(
        refused("m=1,k=4,c=0.1"),
        "error: no value for the parameter F0\n  = hint: give every parameter a value: --set F0=1\n"
    );
    assert_eq!(
        refused("m=1,k=4,c=0.1,F0=1,zz=3"),
        "error: `--set zz=…`: `zz` is not a parameter of the scene\n  = hint: the parameters are m, k, c, F0, p\n"
    );
    assert_eq!(
        refused("m=-1,k=4,c=0.1,F0=1"),
        "error: `--set m=-1`: parameters are positive, and -1 is not\n  = hint: qdot takes every parameter to be positive; write a negative quantity as −m in the scene, or `assume m real`\n"
    );
    assert_eq!(
        refused("m=0,k=4,c=0.1,F0=1"),
        "error: `--set m=0`: m is in the mass matrix or a constraint, where 0 can make the equations singular (a massless body, a rod of no length)\n  = hint: give m a positive value, or write the scene without what it measures\n"
    );
    // 0 is a value where it is not in M: the undamped response
    let (out, _) = ok(&[
        "response",
        "examples/forced_oscillator.qd",
        "--set",
        "m=1,k=4,c=0,F0=1",
        "--over",
        "Omega=1:1:1",
        "--output",
        "csv",
    ]);
    assert_eq!(
        out,
        "Omega,amp_x,phase_x\n1.00000000000000000e0,3.33333333333333315e-1,0.00000000000000000e0\n"
    );
}

#[test]
fn floquet_over_checks_every_point_of_its_grid() {
    let (code, out, err) = qdot(&[
        "floquet",
        "examples/kapitza.qd",
        "--at",
        "theta=pi",
        "--set",
        "m=1,l=1,g=9.81,a=0.05",
        "--over",
        "w=10:-10:3",
    ]);
    assert_eq!((code, out.as_str()), (1, ""));
    assert_eq!(
        err,
        "error: `--over w=10:-10:3` reaches values qdot refuses: `--set w=0`: w is in the mass matrix or a constraint, where 0 can make the equations singular (a massless body, a rod of no length)\n  = hint: give w a positive value, or write the scene without what it measures\n"
    );
}

#[test]
fn floquet_over_gives_the_same_bytes_on_one_thread_and_on_two() {
    let run = |threads: &str| {
        ok(&[
            "floquet",
            "examples/mathieu.qd",
            "--set",
            "m=1,w=1",
            "--over",
            "delta=-0.5:2.5:13,eps=0:2:5",
            "--output",
            "csv",
            "--threads",
            threads,
        ])
    };
    let one = run("1");
    assert_eq!(one, run("2"));
    assert_eq!(one.0.lines().count(), 1 + 13 * 5);
}

#[test]
fn time_options_take_constant_expressions_and_keep_their_checks() {
    let run = |t_end: &str| {
        ok_hoop(
            "t-end",
            "simulate",
            &[
                "--set",
                "m=1,R=1,Omega=1,g=9.81",
                "--init",
                "theta=1",
                "--t-end",
                t_end,
                "--points",
                "3",
            ],
        )
    };
    assert_eq!(run("2*pi"), run("6.283185307179586"));
    let (code, _, err) = qdot_on(
        "numeric_values",
        "t-end-inf",
        HOOP,
        "simulate",
        &[
            "--set",
            "m=1,R=1,Omega=1,g=9.81",
            "--init",
            "theta=1",
            "--t-end",
            "inf",
        ],
    );
    assert_eq!(
        (code, err.as_str()),
        (1, "error: --t-end inf must be a positive number\n")
    );
    let floquet = |period: &str| {
        ok(&[
            "floquet",
            "examples/mathieu.qd",
            "--set",
            "m=1,w=1,delta=1,eps=0.1",
            "--period",
            period,
        ])
    };
    assert_eq!(floquet("2*pi"), floquet("6.283185307179586"));
}
