//! `qdot simulate`: the compiled equations integrated, checked against
//! exact solutions (seed 23.4's constant accelerations, the pendulum's
//! elliptic-function solution, the damped oscillator's closed form), and
//! the command line's errors and JSON keys.

use qdot::simulate::elliptic::pendulum_exact;
use std::process::Command;

fn qdot(args: &[&str]) -> (bool, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_qdot"))
        .args(args)
        .current_dir(env!("QDOT_ROOT"))
        .output()
        .expect("qdot runs");
    (
        out.status.success(),
        String::from_utf8(out.stdout).unwrap(),
        String::from_utf8(out.stderr).unwrap(),
    )
}

fn scene(name: &str, text: &str) -> String {
    let dir = std::env::temp_dir().join(format!("qdot-sim-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p.to_str().unwrap().to_string()
}

fn rows(csv: &str) -> (Vec<String>, Vec<Vec<f64>>) {
    let mut lines = csv.lines();
    let head = lines
        .next()
        .unwrap()
        .split(',')
        .map(str::to_string)
        .collect();
    let rows = lines
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    (head, rows)
}

const PENDULUM: &str = "coordinates th\nparameters m, g, l\n\
    kinetic E = 1/2*m*l^2*th'^2\npotential V = -m*g*l*cos(th)\n";

#[test]
fn seed_23_4_moves_with_its_exact_constant_accelerations() {
    let (ok, out, err) = qdot(&[
        "simulate",
        "examples/seed_23_4.qd",
        "--set",
        "G=2,g=9.81,r=0.5",
        "--init",
        "y3=0,theta3=0,y3'=1,theta3'=0",
        "--t-end",
        "2",
        "--points",
        "5",
    ]);
    assert!(ok, "{err}");
    let (head, rows) = rows(&out);
    assert_eq!(head, ["t", "y3", "theta3", "y3'", "theta3'"]);
    assert_eq!(rows.len(), 5);
    // ÿ₃ = 343/460·g, θ̈₃ = 13/460·g/r (friction: no energy column)
    let (a, e) = (343.0 / 460.0 * 9.81, 13.0 / 460.0 * 9.81 / 0.5);
    for r in &rows {
        let t = r[0];
        assert!((r[1] - (t + a * t * t / 2.0)).abs() < 1e-9, "{r:?}");
        assert!((r[2] - e * t * t / 2.0).abs() < 1e-9, "{r:?}");
        assert!((r[3] - (1.0 + a * t)).abs() < 1e-9, "{r:?}");
        assert!((r[4] - e * t).abs() < 1e-9, "{r:?}");
    }
}

#[test]
fn the_pendulum_at_large_amplitude_matches_the_elliptic_solution() {
    let file = scene("pendulum.qd", PENDULUM);
    for (method, extra, tol) in [
        ("dop853", vec!["--rtol", "1e-11", "--atol", "1e-12"], 1e-8),
        ("vern7", vec!["--rtol", "1e-11", "--atol", "1e-12"], 1e-8),
        ("dopri5", vec!["--rtol", "1e-10", "--atol", "1e-12"], 1e-6),
        ("radau5", vec!["--rtol", "1e-10", "--atol", "1e-12"], 1e-5),
        ("gauss6", vec!["--dt", "0.01"], 1e-8),
        ("rk4", vec!["--dt", "0.001"], 1e-8),
    ] {
        let mut args = vec![
            "simulate",
            &file,
            "--set",
            "m=1,g=9.81,l=1",
            "--init",
            "th=2.5,th'=0",
            "--t-end",
            "10",
            "--points",
            "11",
            "--method",
            method,
        ];
        args.extend(extra);
        let (ok, out, err) = qdot(&args);
        assert!(ok, "{method}: {err}");
        let (head, rows) = rows(&out);
        assert_eq!(head, ["t", "th", "th'", "energy"]);
        let h0 = rows[0][3];
        // E + V at rest at 2.5 rad
        assert!((h0 - (-9.81 * 2.5f64.cos())).abs() < 1e-12);
        for r in &rows {
            let (th, thd) = pendulum_exact(2.5, 9.81, r[0]);
            assert!(
                (r[1] - th).abs() < tol,
                "{method} at t = {}: {} vs {th}",
                r[0],
                r[1]
            );
            assert!(
                (r[2] - thd).abs() < 10.0 * tol,
                "{method}: {} vs {thd}",
                r[2]
            );
            assert!(
                (r[3] - h0).abs() < 10.0 * tol,
                "{method}: energy {} vs {h0}",
                r[3]
            );
        }
    }
}

#[test]
fn a_damped_oscillator_matches_its_closed_form_and_has_no_energy_column() {
    let file = scene(
        "damped.qd",
        "coordinates x\nparameters m, k, c\nkinetic E = 1/2*m*x'^2\n\
         potential V = 1/2*k*x^2\nrayleigh R = 1/2*c*x'^2\n",
    );
    let (ok, out, err) = qdot(&[
        "simulate",
        &file,
        "--set",
        "m=1,k=4,c=0.4",
        "--init",
        "x=1,x'=0",
        "--t-end",
        "5",
        "--points",
        "6",
        "--rtol",
        "1e-12",
        "--atol",
        "1e-14",
    ]);
    assert!(ok, "{err}");
    let (head, rows) = rows(&out);
    assert_eq!(head, ["t", "x", "x'"]);
    // x'' + 0.4 x' + 4 x = 0: α = 0.2, ω_d = √(4 − 0.04)
    let (alpha, wd) = (0.2f64, (4.0f64 - 0.04).sqrt());
    for r in &rows {
        let t = r[0];
        let x = (-alpha * t).exp() * ((wd * t).cos() + alpha / wd * (wd * t).sin());
        assert!((r[1] - x).abs() < 1e-10, "t = {t}: {} vs {x}", r[1]);
    }
}

#[test]
fn json_output_and_stats() {
    let file = scene("pendulum_json.qd", PENDULUM);
    let (ok, out, err) = qdot(&[
        "simulate",
        &file,
        "--set",
        "m=1,g=9.81,l=1",
        "--init",
        "th=1,th'=0",
        "--t-end",
        "1",
        "--points",
        "3",
        "--output",
        "json",
        "--stats",
    ]);
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let keys: Vec<&str> = v.as_object().unwrap().keys().map(String::as_str).collect();
    assert_eq!(
        keys,
        [
            "method",
            "status",
            "columns",
            "rows",
            "stats",
            "stiff_at",
            "event_t",
            "event_poles"
        ]
    );
    assert!(v["event_t"].is_null());
    assert_eq!(v["event_poles"], serde_json::json!([]));
    assert_eq!(v["method"], "dop853");
    assert_eq!(v["status"], "done");
    assert_eq!(v["rows"].as_array().unwrap().len(), 3);
    assert!(v["stats"]["rhs_evals"].as_u64().unwrap() > 10);
    assert!(err.starts_with("method dop853: "), "{err}");
    assert!(err.contains("RHS evaluations"), "{err}");
    // the evaluator of q̈: 1 dof, M = m·l² constant; the exact acceleration
    // −g/l·sin θ (one multiplication, one sin: 21) saves the triangular
    // solves (2 flops, 2 divisions of 4, 1 copy: 32)
    let stats: Vec<&str> = v["stats"]
        .as_object()
        .unwrap()
        .keys()
        .map(String::as_str)
        .collect();
    assert_eq!(
        stats,
        [
            "steps",
            "rejected",
            "rhs_evals",
            "jacobians",
            "factorizations",
            "seconds",
            "compile_seconds",
            "engine",
            "evaluator"
        ]
    );
    // `--evaluator auto` on a run of a few hundred right-hand sides: the
    // interpreter, which compiling would not pay for; its line third
    assert_eq!(v["stats"]["engine"]["name"], "interpreter");
    assert_eq!(v["stats"]["engine"]["requested"], "auto");
    let reason = if cfg!(feature = "jit") {
        "auto: fewer than 25,000 right-hand sides, too few to pay for machine code"
    } else {
        "built without the `jit` feature"
    };
    assert_eq!(v["stats"]["engine"]["reason"], reason);
    assert_eq!(
        err.lines().nth(2).unwrap(),
        format!("engine interpreter: {reason}"),
        "{err}"
    );
    let ev = &v["stats"]["evaluator"];
    assert_eq!(ev["name"], "accelerations");
    assert_eq!(ev["cost"]["accelerations"], 21.0);
    assert_eq!(ev["cost"]["mass_matrix"], 22.0);
    assert!(
        err.contains("\nevaluator accelerations: ≈ 21 flops per RHS against ≈ 22 for f with the constant M inverted once\n"),
        "{err}"
    );
    assert_eq!(
        ev["reason"],
        err.lines().nth(1).unwrap()["evaluator accelerations: ".len()..]
    );
}

/// `auto` compiles to machine code once a run has made 25,000 right-hand
/// sides, and the rows do not change: the machine code computes what the
/// interpreter computes, bit for bit.
#[test]
fn auto_compiles_a_long_run_midway_and_its_rows_do_not_change() {
    let file = scene("pendulum_long.qd", PENDULUM);
    let run = |evaluator: &str| {
        let (ok, out, err) = qdot(&[
            "simulate",
            &file,
            "--set",
            "m=1,g=9.81,l=1",
            "--init",
            "th=1,th'=0",
            "--t-end",
            "1000",
            "--points",
            "101",
            "--stats",
            "--evaluator",
            evaluator,
        ]);
        assert!(ok, "{err}");
        (out, err)
    };
    let (auto, err) = run("auto");
    let (interpreted, _) = run("interpreter");
    assert_eq!(auto, interpreted);
    let evals: u64 = err
        .split(" RHS evaluations")
        .next()
        .and_then(|s| s.rsplit(' ').next())
        .and_then(|s| s.parse().ok())
        .expect("the RHS count");
    assert!(evals > 25_000, "{err}");
    let engine = if cfg!(feature = "jit") {
        "engine jit: machine code"
    } else {
        "engine interpreter: built without"
    };
    assert!(err.lines().nth(2).unwrap().starts_with(engine), "{err}");
}

#[test]
fn missing_values_are_listed() {
    let file = scene("pendulum_err.qd", PENDULUM);
    let (ok, _, err) = qdot(&[
        "simulate",
        &file,
        "--set",
        "m=1",
        "--init",
        "th=1,th'=0",
        "--t-end",
        "1",
    ]);
    assert!(!ok);
    assert_eq!(
        err,
        "error: no value for the parameters g, l\n  = hint: give every parameter a value: --set g=1,l=1\n"
    );
    let (ok, _, err) = qdot(&["simulate", &file, "--set", "m=1,g=1,l=1", "--t-end", "1"]);
    assert!(!ok);
    assert_eq!(
        err,
        "error: no initial value for the coordinate th\n  = hint: give every coordinate a value (a velocity not given is 0): --init th=0\n"
    );
    let (ok, _, err) = qdot(&[
        "simulate",
        &file,
        "--set",
        "m=1,g=1,l=1,q=2",
        "--init",
        "th=1,th'=0",
        "--t-end",
        "1",
    ]);
    assert!(!ok);
    assert!(err.contains("`q` is not a parameter of the scene"), "{err}");
    let (ok, _, err) = qdot(&[
        "simulate",
        &file,
        "--set",
        "m=1,g=1,l=1",
        "--init",
        "th=1,th'=0,x=1",
        "--t-end",
        "1",
    ]);
    assert!(!ok);
    assert!(
        err.contains("`x` is not a coordinate or a velocity"),
        "{err}"
    );
    let (ok, _, err) = qdot(&[
        "simulate",
        &file,
        "--set",
        "m=1,g=1,l=1",
        "--init",
        "th=1,th'=0",
        "--t-end",
        "1",
        "--method",
        "euler",
    ]);
    assert!(!ok);
    assert!(err.contains("unknown method `euler`"), "{err}");
    let (ok, _, err) = qdot(&[
        "simulate",
        &file,
        "--set",
        "m=1,g=1,l=1",
        "--init",
        "th=1,th'=0",
        "--t-end",
        "1",
        "--method",
        "rk4",
    ]);
    assert!(!ok);
    assert!(err.contains("--dt"), "{err}");
}

#[test]
fn a_stiff_scene_is_detected_by_explicit_methods_and_radau_solves_it() {
    // two masses, springs of stiffness 1 and 1e6
    let file = scene(
        "stiff.qd",
        "coordinates x1, x2\nparameters m, k, K\nkinetic E = 1/2*m*(x1'^2 + x2'^2)\n\
         potential V = 1/2*k*x1^2 + 1/2*K*(x2 - x1)^2\nrayleigh R = 1/2*K/1000*(x2' - x1')^2\n",
    );
    let base = [
        "simulate",
        &file,
        "--set",
        "m=1,k=1,K=1000000",
        "--init",
        "x1=1,x2=1,x1'=0,x2'=0",
        "--t-end",
        "10",
        "--points",
        "3",
        "--rtol",
        "1e-6",
        "--atol",
        "1e-8",
        "--output",
        "json",
    ];
    let (ok, out, err) = qdot(&[&base[..], &["--method", "dopri5"]].concat());
    assert!(ok, "{err}");
    assert!(err.contains("looks stiff"), "{err}");
    let explicit: serde_json::Value = serde_json::from_str(&out).unwrap();
    let (ok, out, err) = qdot(&[&base[..], &["--method", "radau5"]].concat());
    assert!(ok, "{err}");
    assert!(!err.contains("looks stiff"), "{err}");
    let radau: serde_json::Value = serde_json::from_str(&out).unwrap();
    let steps = |v: &serde_json::Value| v["stats"]["steps"].as_u64().unwrap();
    assert!(steps(&radau) < 200, "{}", steps(&radau));
    assert!(
        steps(&explicit) > 20 * steps(&radau),
        "{} vs {}",
        steps(&explicit),
        steps(&radau)
    );
    // both agree on the slow motion: x1 ≈ x2 ≈ cos(t/√2)
    let last = |v: &serde_json::Value| v["rows"][2][1].as_f64().unwrap();
    assert!((last(&radau) - (10.0 / 2f64.sqrt()).cos()).abs() < 1e-3);
    assert!((last(&radau) - last(&explicit)).abs() < 1e-4);
}

/// The `points` of every `<polyline>` of an SVG, as (x, y) pixels.
fn polylines(svg: &str) -> Vec<Vec<(f64, f64)>> {
    let mut out = Vec::new();
    let mut rest = svg;
    while let Some(at) = rest.find("<polyline") {
        rest = &rest[at..];
        let end = rest.find('>').unwrap();
        let tag = &rest[..end];
        if let Some(p) = tag.find("points=\"") {
            let body = &tag[p + 8..];
            let body = &body[..body.find('"').unwrap()];
            out.push(
                body.split_whitespace()
                    .map(|xy| {
                        let (x, y) = xy.split_once(',').unwrap();
                        (x.parse().unwrap(), y.parse().unwrap())
                    })
                    .collect(),
            );
        }
        rest = &rest[end..];
    }
    out
}

/// Least-squares fit y ≈ a + b·x: (b, max residual relative to the span).
fn affine(xs: &[f64], ys: &[f64]) -> (f64, f64) {
    let n = xs.len() as f64;
    let (mx, my) = (xs.iter().sum::<f64>() / n, ys.iter().sum::<f64>() / n);
    let sxy: f64 = xs.iter().zip(ys).map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = xs.iter().map(|x| (x - mx) * (x - mx)).sum();
    let b = sxy / sxx;
    let a = my - b * mx;
    let span =
        ys.iter().cloned().fold(f64::MIN, f64::max) - ys.iter().cloned().fold(f64::MAX, f64::min);
    let worst = xs
        .iter()
        .zip(ys)
        .map(|(x, y)| (y - (a + b * x)).abs())
        .fold(0.0, f64::max);
    (b, worst / span)
}

#[test]
fn plot_of_seed_24_2_shows_the_motion() {
    let dir = std::env::temp_dir().join(format!("qdot-plot-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let svg_path = dir.join("seed_24_2.svg");
    let (ok, out, err) = qdot(&[
        "simulate",
        "examples/seed_24_2.qd",
        "--set",
        "m=1,k=10,R=0.2",
        "--init",
        "x1=0.1,x2=0,x1'=0,x2'=0",
        "--t-end",
        "5",
        // the output times are the plot's own samples (plot::SAMPLES), so
        // each curve's points are the CSV rows
        "--points",
        "4000",
        "--plot",
        svg_path.to_str().unwrap(),
    ]);
    assert!(ok, "{err}");
    let (head, rows) = rows(&out);
    assert_eq!(head, ["t", "x1", "x2", "x1'", "x2'", "energy"]);
    let svg = std::fs::read_to_string(&svg_path).unwrap();
    assert!(svg.starts_with("<svg"));
    for caption in [
        "lengths against time",
        "phase portrait of x₁",
        "phase portrait of x₂",
        "energy error",
    ] {
        assert!(svg.contains(caption), "{caption}");
    }
    // tick labels print 0 as 0 (not 0.0, -0.0 or a rounding residue like
    // -2.6e-23) and the legend writes the coordinates as the text does
    let labels: Vec<&str> = svg
        .split("</text>")
        .filter_map(|t| t.rsplit('>').next())
        .map(str::trim)
        .collect();
    assert!(labels.contains(&"0"), "{labels:?}");
    for bad in ["0.0", "-0.0", "-0"] {
        assert!(!labels.contains(&bad), "{bad}: {labels:?}");
    }
    assert!(
        !labels
            .iter()
            .any(|l| l.parse::<f64>().is_ok_and(|v| v != 0.0 && v.abs() < 1e-20)),
        "{labels:?}"
    );
    assert!(
        labels.contains(&"x₁") && labels.contains(&"x₂"),
        "{labels:?}"
    );
    // the series: one per coordinate against t, one per phase portrait,
    // and the energy error, each with a point per output time
    let series: Vec<Vec<(f64, f64)>> = polylines(&svg)
        .into_iter()
        .filter(|p| p.len() == qdot::simulate::plot::SAMPLES)
        .collect();
    assert_eq!(series.len(), 2 + 2 + 1);
    for k in 0..2 {
        let s = &series[k];
        // time runs left to right (4,000 samples share pixel columns)
        assert!(s.windows(2).all(|w| w[1].0 >= w[0].0));
        // the pixels are the CSV values under an affine map (y grows down)
        let q: Vec<f64> = rows.iter().map(|r| r[1 + k]).collect();
        let py: Vec<f64> = s.iter().map(|p| p.1).collect();
        let (slope, residual) = affine(&q, &py);
        assert!(slope < 0.0 && residual < 0.01, "{slope} {residual}");
        // and they move: x1 swings through its amplitude
        let span = py.iter().cloned().fold(f64::MIN, f64::max)
            - py.iter().cloned().fold(f64::MAX, f64::min);
        assert!(span > 50.0, "{span}");
    }
    // the phase portrait of x1: x pixels follow x1, y pixels follow x1'
    let x1: Vec<f64> = rows.iter().map(|r| r[1]).collect();
    let v1: Vec<f64> = rows.iter().map(|r| r[3]).collect();
    let px: Vec<f64> = series[2].iter().map(|p| p.0).collect();
    let py: Vec<f64> = series[2].iter().map(|p| p.1).collect();
    assert!(affine(&x1, &px).0 > 0.0 && affine(&x1, &px).1 < 0.01);
    assert!(affine(&v1, &py).0 < 0.0 && affine(&v1, &py).1 < 0.01);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn stop_when_lands_on_the_event_within_1e_10() {
    use qdot::simulate::elliptic::ellipk;
    let file = scene("pendulum_event.qd", PENDULUM);
    let quarter = ellipk((0.5f64).sin().powi(2)) / 9.81f64.sqrt();
    for method in ["dop853", "dopri5", "vern7"] {
        let (ok, out, err) = qdot(&[
            "simulate",
            &file,
            "--set",
            "m=1,g=9.81,l=1",
            "--init",
            "th=1,th'=0",
            "--t-end",
            "10",
            "--rtol",
            "1e-12",
            "--atol",
            "1e-14",
            "--stop-when",
            "th = 0",
            "--method",
            method,
        ]);
        assert!(ok, "{err}");
        assert!(err.starts_with("stopped at t = "), "{err}");
        let (_, rows) = rows(&out);
        let last = rows.last().unwrap();
        // released from rest at 1 rad, θ first reaches 0 at a quarter period K(k²)/ω₀
        assert!(
            (last[0] - quarter).abs() < 1e-10,
            "{method}: {} vs {quarter}",
            last[0]
        );
        assert!(last[1].abs() < 1e-10, "{method}: θ = {}", last[1]);
        assert!(rows.windows(2).all(|w| w[1][0] > w[0][0]));
    }
    // a velocity condition: the first turning point, θ' = 0 after t > 0,
    // is at half a period (the start, with θ' = 0 exactly, is no crossing)
    let (ok, out, err) = qdot(&[
        "simulate",
        &file,
        "--set",
        "m=1,g=9.81,l=1",
        "--init",
        "th=1,th'=0.000001",
        "--t-end",
        "10",
        "--rtol",
        "1e-12",
        "--atol",
        "1e-14",
        "--stop-when",
        "th' = 0",
        "--output",
        "json",
    ]);
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["status"], "event");
    let t = v["event_t"].as_f64().unwrap();
    assert!(t > 0.0 && t < 2.0 * quarter + 1e-3, "{t}");
    // errors
    let (ok, _, err) = qdot(&[
        "simulate",
        &file,
        "--set",
        "m=1,g=9.81,l=1",
        "--init",
        "th=1,th'=0",
        "--t-end",
        "1",
        "--stop-when",
        "th = qq",
    ]);
    assert!(!ok);
    assert!(
        err.starts_with("error: `--stop-when th = qq`: unknown name `qq`"),
        "{err}"
    );
    let (ok, _, err) = qdot(&[
        "simulate",
        &file,
        "--set",
        "m=1,g=9.81,l=1",
        "--init",
        "th=1,th'=0",
        "--t-end",
        "1",
        "--stop-when",
        "th = 0",
        "--method",
        "radau5",
    ]);
    assert!(!ok);
    assert!(
        err.contains("dense output of the explicit methods"),
        "{err}"
    );
}

/// One rule for `--init`, as `modes --init` has it: a velocity not given is
/// 0, and a note on standard error names it; the run equals the one with
/// the velocity written 0. A coordinate not given is still an error.
#[test]
fn a_velocity_not_given_is_zero() {
    let file = scene("pendulum_init.qd", PENDULUM);
    let run = |init: &str| {
        qdot(&[
            "simulate",
            &file,
            "--set",
            "m=1,g=9.81,l=1",
            "--init",
            init,
            "--t-end",
            "1",
            "--points",
            "3",
        ])
    };
    let (ok, implicit, err) = run("th=0.5");
    assert!(ok, "{err}");
    assert_eq!(err, "note: velocities not given are 0: th'\n");
    let (ok, explicit, err) = run("th=0.5,th'=0");
    assert!(ok && err.is_empty(), "{err}");
    assert_eq!(implicit, explicit);
    let two = scene(
        "two_init.qd",
        "coordinates x, s\nparameters m, k\nkinetic E = 1/2*m*(x'^2 + s'^2)\npotential V = 1/2*k*(x - s)^2 + 1/2*k*x^2\n",
    );
    let (ok, out, err) = qdot(&[
        "simulate",
        &two,
        "--set",
        "m=1,k=1",
        "--init",
        "x=0.1,s=0",
        "--t-end",
        "1",
        "--points",
        "2",
    ]);
    assert!(ok, "{err}");
    assert_eq!(err, "note: velocities not given are 0: x', s'\n");
    let (_, r) = rows(&out);
    assert_eq!(&r[0][1..5], &[0.1, 0.0, 0.0, 0.0]);
    let (ok, _, err) = qdot(&[
        "simulate",
        &two,
        "--set",
        "m=1,k=1",
        "--init",
        "x=0.1,x'=1",
        "--t-end",
        "1",
    ]);
    assert!(!ok);
    assert_eq!(
        err,
        "error: no initial value for the coordinate s\n  = hint: give every coordinate a value (a velocity not given is 0): --init s=0\n"
    );
}

/// `--set c=0` in a numeric run: the damping's zero is taken as it is, and
/// the run is the undamped scene's (its energy, computed from the rows,
/// drifts by no more than the tolerances); a zero mass, which makes the
/// mass matrix singular, is refused; and `modes --set c=0` is refused with
/// the fix named, never given a damped verdict.
#[test]
fn a_zero_damping_runs_in_numeric_commands() {
    let damped = scene(
        "zero_damping.qd",
        "coordinates x\nparameters m, k, c\nkinetic E = 1/2*m*x'^2\npotential V = 1/2*k*x^2\nrayleigh R = 1/2*c*x'^2\n",
    );
    let undamped = scene(
        "no_damping.qd",
        "coordinates x\nparameters m, k\nkinetic E = 1/2*m*x'^2\npotential V = 1/2*k*x^2\n",
    );
    let args = |file: &str, set: &str| {
        qdot(&[
            "simulate", file, "--set", set, "--init", "x=1,x'=0", "--t-end", "20", "--points",
            "41", "--rtol", "1e-12", "--atol", "1e-12",
        ])
    };
    let (ok, out, err) = args(&damped, "m=2,k=3,c=0");
    assert!(ok && err.is_empty(), "{err}");
    let (head, zero) = rows(&out);
    assert_eq!(head, ["t", "x", "x'"]);
    let (ok, out, err) = args(&undamped, "m=2,k=3");
    assert!(ok, "{err}");
    let (_, free) = rows(&out);
    let energy = |r: &Vec<f64>| 0.5 * 2.0 * r[2] * r[2] + 0.5 * 3.0 * r[1] * r[1];
    for (a, b) in zero.iter().zip(&free) {
        assert!((a[1] - b[1]).abs() < 1e-12 && (a[2] - b[2]).abs() < 1e-12);
        assert!((energy(a) - 1.5).abs() < 1e-9, "{a:?}");
    }
    let (ok, _, err) = args(&damped, "m=0,k=3,c=1");
    assert!(!ok);
    assert_eq!(
        err,
        "error: `--set m=0`: m is in the mass matrix or a constraint, where 0 can make the equations singular (a massless body, a rod of no length)\n  = hint: give m a positive value, or write the scene without what it measures\n"
    );
    let (ok, out, err) = qdot(&["modes", &damped, "--set", "m=2,k=3,c=0"]);
    assert!(!ok && out.is_empty());
    assert_eq!(
        err,
        "error: `--set c=0`: parameters are positive, and 0 is not\n  = hint: exact results are derived for c > 0; with `assume c real` in the scene they are derived for any c, its sign taken from the value (the numeric commands, `simulate`, `sweep`, `cycle`, `floquet`, `response --over`, take c=0 where c is not in the mass matrix)\n"
    );
    // the fix the hint names: derived for any c, undamped at c = 0
    let real = scene(
        "zero_damping_real.qd",
        "coordinates x\nparameters m, k, c\nassume c real\nkinetic E = 1/2*m*x'^2\npotential V = 1/2*k*x^2\nrayleigh R = 1/2*c*x'^2\n",
    );
    let (ok, out, err) = qdot(&["modes", &real, "--set", "m=2,k=3,c=0"]);
    assert!(ok, "{err}");
    assert!(out.contains("  regime: undamped\n"), "{out}");
    assert!(
        out.contains("Stability of the equilibrium: stable\n"),
        "{out}"
    );
}
