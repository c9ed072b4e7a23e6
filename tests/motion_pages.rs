//! `simulate --animate` and `modes --animate`: the page's data are the
//! motion's positions (the run's, or the modes' about the equilibrium),
//! its links the rods, and a scene with nothing to draw is refused.

use qdot::app::{self, AnyReport, Command, CommandOptions, Context};
use qdot::drawing::motion::{page, Stage};
use qdot::drawing::motion_of::{modes_data, run_data};
use qdot::simulate::run::Request;
use serde_json::Value;

fn values(pairs: &[(&str, f64)]) -> qdot::solve::equilibrium::Values {
    pairs.iter().map(|(k, v)| (k.to_string(), *v)).collect()
}

/// The run of `file` and its page's data (with `plot` samples when
/// asked, as `--animate` asks for).
fn simulated(
    file: &str,
    set: &[(&str, f64)],
    init: &[(&str, f64)],
    plot: bool,
) -> (Vec<Vec<f64>>, Vec<String>, Value) {
    let src = std::fs::read_to_string(file).expect("the example");
    let opts = CommandOptions {
        set: values(set),
        simulate: Request {
            t_end: 3.0,
            points: 31,
            init: values(init),
            plot_samples: if plot {
                qdot::simulate::plot::SAMPLES
            } else {
                0
            },
            ..Request::default()
        },
        ..CommandOptions::default()
    };
    let AnyReport::Simulate(r) =
        app::run(&Context::new(), Command::Simulate, &src, &opts).expect("the run")
    else {
        panic!("a simulate report");
    };
    let run = &r.result.run;
    let data = run_data(r.scene(), run, &opts.set, "title", "subtitle").expect("the page's data");
    let rows = if plot {
        run.plot_rows.clone()
    } else {
        run.rows.clone()
    };
    (rows, run.columns.clone(), data)
}

fn floats(v: &Value) -> Vec<f64> {
    v.as_array()
        .expect("an array")
        .iter()
        .map(|x| x.as_f64().expect("a number"))
        .collect()
}

fn close(a: &[f64], b: &[f64]) {
    assert_eq!(a.len(), b.len(), "{a:?} against {b:?}");
    for (x, y) in a.iter().zip(b) {
        assert!((x - y).abs() < 1e-12, "{a:?} against {b:?}");
    }
}

/// The double pendulum (x1, y1), (x2, y2): P1 = l1·(sin θ1, −cos θ1), P2 =
/// P1 + l2·(sin θ2, −cos θ2) at the first and last rows; the links the
/// two rods (the pivot to P1, P1 to P2); a plane scene.
#[test]
fn the_double_pendulums_page_is_its_run() {
    let (l1, l2) = (1.0, 2.0);
    let (rows, columns, data) = simulated(
        "examples/double_pendulum.qd",
        &[
            ("m1", 1.0),
            ("m2", 2.0),
            ("l1", l1),
            ("l2", l2),
            ("g", 9.81),
        ],
        &[("th1", 1.0), ("th2", -0.5)],
        false,
    );
    assert_eq!(data["space"], false);
    assert_eq!(
        data["points"],
        serde_json::json!([{"name": "P1", "kind": "point"}, {"name": "P2", "kind": "point"}])
    );
    assert_eq!(data["links"], serde_json::json!([[-1, 0], [0, 1]]));
    let motion = &data["motions"][0];
    assert_eq!(motion["periodic"], false);
    let times = floats(&motion["t"]);
    assert_eq!(times.len(), rows.len());
    let th1 = columns.iter().position(|c| c == "th1").unwrap();
    let th2 = columns.iter().position(|c| c == "th2").unwrap();
    for k in [0, rows.len() - 1] {
        let (a, b) = (rows[k][th1], rows[k][th2]);
        let (x1, y1) = (l1 * a.sin(), -l1 * a.cos());
        let (x2, y2) = (x1 + l2 * b.sin(), y1 - l2 * b.cos());
        assert_eq!(times[k], rows[k][0]);
        close(
            &floats(&motion["positions"][k]),
            &[x1, y1, 0.0, x2, y2, 0.0],
        );
    }
    assert_eq!(
        floats(&motion["positions"][0])[..2],
        [1.0f64.sin(), -1.0f64.cos()]
    );
}

/// The heavy top (3-1-3 Euler angles): its centre l·(sin φ sin θ, −cos φ
/// sin θ, cos θ) and its frame's matrix at the first and last of the
/// run's plot rows; linked to the fixed point; a space scene.
#[test]
fn the_heavy_tops_page_is_its_run() {
    let l = 0.7;
    let (rows, columns, data) = simulated(
        "examples/heavy_top.qd",
        &[("A", 1.0), ("C", 0.5), ("m", 1.0), ("g", 9.81), ("l", l)],
        &[
            ("phi", 0.2),
            ("theta", 0.5),
            ("psi", 0.0),
            ("psi'", 20.0),
            ("phi'", 0.5),
        ],
        true,
    );
    assert_eq!(data["space"], true);
    assert_eq!(
        data["points"],
        serde_json::json!([{"name": "top", "kind": "body"}])
    );
    assert_eq!(data["links"], serde_json::json!([[-1, 0]]));
    assert_eq!(data["bodyAxes"], serde_json::json!([0]));
    let motion = &data["motions"][0];
    let times = floats(&motion["t"]);
    let col = |n: &str| columns.iter().position(|c| c == n).unwrap();
    let last = times.len() - 1;
    for (k, row) in [(0, &rows[0]), (last, &rows[rows.len() - 1])] {
        assert_eq!(times[k], row[0]);
        let (f, t, p) = (row[col("phi")], row[col("theta")], row[col("psi")]);
        let (sf, cf, st, ct, sp, cp) = (f.sin(), f.cos(), t.sin(), t.cos(), p.sin(), p.cos());
        close(
            &floats(&motion["positions"][k]),
            &[l * sf * st, -l * cf * st, l * ct],
        );
        // B = Rz(φ)·Rx(θ)·Rz(ψ), row by row
        let b = [
            cf * cp - sf * ct * sp,
            -cf * sp - sf * ct * cp,
            sf * st,
            sf * cp + cf * ct * sp,
            -sf * sp + cf * ct * cp,
            -cf * st,
            st * sp,
            st * cp,
            ct,
        ];
        close(&floats(&motion["axes"][k]), &b);
    }
}

/// The 3D chain: its rods' ends P1, P2, P3 and the bodies' centres
/// linked into one chain from the pivot.
#[test]
fn the_rod_chains_links_are_its_rods() {
    let (_, _, data) = simulated(
        "examples/rod_chain.qd",
        &[("m", 1.0), ("A", 0.1), ("C", 0.01), ("l", 1.0), ("g", 9.81)],
        &[("q1", 0.8), ("q2", 0.6), ("q3", 0.3), ("q4", 0.2)],
        false,
    );
    let names: Vec<&str> = data["points"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p["name"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["b1", "b2", "b3", "b4", "P1", "P2", "P3"]);
    assert_eq!(
        data["links"],
        serde_json::json!([[-1, 0], [4, 1], [5, 2], [6, 3], [-1, 4], [4, 5], [5, 6]])
    );
    assert_eq!(data["bodyAxes"], serde_json::json!([0, 1, 2, 3]));
}

/// A scene without positions: refused, with what to write.
#[test]
fn a_scene_with_nothing_to_draw_is_refused() {
    let scene = qdot::Scene::parse(
        "coordinates x\nparameters m, k\nkinetic T = 1/2*m*x'^2\npotential V = 1/2*k*x^2",
    )
    .expect("the scene");
    let e = Stage::of_scene(&scene).unwrap_err();
    assert_eq!(
        e.message,
        "nothing to animate: no body, particle or point of the scene moves with its coordinates"
    );
    assert_eq!(
        e.hint.as_deref(),
        Some("give the scene a position: `particle bob: mass m, at [l*sin(th), -l*cos(th)]`, a vector definition `P = [x, 0]`, or definitions `x1 = …` and `y1 = …`")
    );
}

/// The double pendulum's two modes about the hanging equilibrium: each a
/// period of frames starting at the equilibrium, labelled with ω from
/// det(K − ω²M) = 0 (m1 = m2 = l1 = l2 = 1, g = 9.81: ω² = (2 ∓ √2)·g).
#[test]
fn the_double_pendulums_modes_page() {
    let src = std::fs::read_to_string("examples/double_pendulum.qd").expect("the example");
    let opts = CommandOptions {
        set: values(&[
            ("m1", 1.0),
            ("m2", 1.0),
            ("l1", 1.0),
            ("l2", 1.0),
            ("g", 9.81),
        ]),
        ..CommandOptions::default()
    };
    let r = app::modes(&Context::new(), &src, &opts).expect("the modes");
    let data = modes_data(r.scene(), &r.result, "title", "subtitle").expect("the page's data");
    let motions = data["motions"].as_array().unwrap();
    assert_eq!(motions.len(), 2);
    let omega = |k: f64| ((2.0 + k * 2f64.sqrt()) * 9.81).sqrt();
    assert_eq!(
        motions[0]["label"],
        format!(
            "mode 1: ω = {:.3} rad/s, f = {:.4} Hz",
            omega(-1.0),
            omega(-1.0) / (2.0 * std::f64::consts::PI)
        )
    );
    let second = motions[1]["label"].as_str().unwrap();
    assert!(
        second.starts_with(&format!("mode 2: ω = {:.3} rad/s, f = ", omega(1.0))),
        "{second}"
    );
    for m in motions {
        assert_eq!(m["periodic"], true);
        close(
            &floats(&m["positions"][0]),
            &[0.0, -1.0, 0.0, 0.0, -2.0, 0.0],
        );
        let t = floats(&m["t"]);
        assert_eq!(t.len(), 73);
    }
    // the slow mode swings both masses to one side, the fast one apart
    let quarter = |k: usize| floats(&data["motions"][k]["positions"][18]);
    let (slow, fast) = (quarter(0), quarter(1));
    assert!(slow[0] > 0.0 && slow[3] > slow[0], "{slow:?}");
    assert!(fast[0] * (fast[3] - fast[0]) < 0.0, "{fast:?}");
    // the page embeds them with three.js
    let html = page(&data);
    assert!(html.contains("\"label\":\"mode 1: ω = "));
    assert!(html.contains("Copyright 2010-2024 Three.js Authors"));
    assert!(html.contains("const t=\"170\""));
}
