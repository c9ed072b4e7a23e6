//! `qdot floquet`: the Mathieu equation's stability boundaries against
//! SciPy's characteristic values (tests/fixtures/floquet/mathieu.json,
//! written by scripts/floquet_reference.py) and their series; Kapitza's
//! threshold a²ω² = 2gl; the multipliers where they are known in closed
//! form (constant coefficients, Liouville's det Φ = exp(−∫tr C dt)); the
//! chart; and the refusals, word for word.

use qdot::floquet::{prepare, FloquetRequest, Prepared, Verdict};
use qdot::Scene;
use std::f64::consts::PI;

use crate::common::run::qdot;

const MATHIEU: &str = "examples/mathieu.qd";
const KAPITZA: &str = "examples/kapitza.qd";

fn prepared(file: &str, at: Option<&str>) -> Prepared {
    let src = std::fs::read_to_string(file).expect("the example");
    let scene = Scene::parse(&src).expect("the scene parses");
    let req = FloquetRequest {
        at: at.map(String::from),
        ..FloquetRequest::default()
    };
    scene
        .assumptions_in_force(|| prepare(&scene, &req))
        .expect("the scene linearizes")
}

/// `pairs` as `p` takes them, checked as `--set` values are in the scene
/// `file`.
fn values(
    p: &Prepared,
    file: &str,
    pairs: &[(&str, f64)],
) -> rustc_hash::FxHashMap<qdot_exact::poly::Var, f64> {
    let scene = Scene::parse(&std::fs::read_to_string(file).expect("the example"))
        .expect("the scene parses");
    let set = pairs.iter().map(|(k, v)| (k.to_string(), *v)).collect();
    p.parameter_map(&scene, &set)
        .expect("values the scene takes")
}

/// The rows of the SciPy fixture: ε and the boundaries a0, b1, a1 in δ.
fn fixture() -> Vec<(f64, f64, f64, f64)> {
    let text = std::fs::read_to_string("tests/fixtures/floquet/mathieu.json").expect("fixture");
    let v: serde_json::Value = serde_json::from_str(&text).expect("JSON");
    v["rows"]
        .as_array()
        .expect("rows")
        .iter()
        .map(|r| {
            let f = |k: &str| r[k].as_f64().expect("a number");
            (f("eps"), f("a0"), f("b1"), f("a1"))
        })
        .collect()
}

#[test]
fn mathieu_first_tongue_is_scipys_to_1e_6_and_follows_its_series() {
    let p = prepared(MATHIEU, None);
    assert!(p.lagrangian);
    for (eps, a0, b1, a1) in fixture() {
        let v = values(
            &p,
            MATHIEU,
            &[("delta", 0.0), ("eps", eps), ("m", 1.0), ("w", 1.0)],
        );
        let lower = p
            .boundary(&v, "delta", 0.25 - eps, 0.25)
            .expect("lower edge");
        let upper = p
            .boundary(&v, "delta", 0.25, 0.25 + eps)
            .expect("upper edge");
        assert!(
            (lower - b1).abs() < 1e-6,
            "ε = {eps}: {lower} against b1/4 = {b1}"
        );
        assert!(
            (upper - a1).abs() < 1e-6,
            "ε = {eps}: {upper} against a1/4 = {a1}"
        );
        // δ = 1/4 ∓ ε/2 − ε²/8 ± ε³/32 + O(ε⁴)
        let series = |s: f64| 0.25 + s * eps / 2.0 - eps * eps / 8.0 - s * eps.powi(3) / 32.0;
        assert!(
            (lower - series(-1.0)).abs() < eps.powi(4),
            "ε = {eps}: {lower}"
        );
        assert!(
            (upper - series(1.0)).abs() < eps.powi(4),
            "ε = {eps}: {upper}"
        );
        // below a0/4 the trivial solution is unstable (the Kapitza edge)
        let edge = p.boundary(&v, "delta", -0.1, 0.1).expect("the edge near 0");
        assert!(
            (edge - a0).abs() < 1e-6,
            "ε = {eps}: {edge} against a0/4 = {a0}"
        );
    }
}

#[test]
fn kapitza_inverted_pendulum_is_stable_above_the_threshold_within_1_percent() {
    let p = prepared(KAPITZA, Some("theta=pi"));
    assert!(p.lagrangian);
    for (l, g, a) in [(1.0f64, 9.81, 0.05), (0.5, 9.81, 0.02), (2.0, 1.62, 0.1)] {
        let threshold = (2.0 * g * l).sqrt() / a;
        // w is varied by `boundary`: any value the scene takes
        let v = values(
            &p,
            KAPITZA,
            &[("m", 1.0), ("l", l), ("g", g), ("a", a), ("w", threshold)],
        );
        let w = p
            .boundary(&v, "w", 0.5 * threshold, 2.0 * threshold)
            .expect("a threshold");
        assert!(
            (w / threshold - 1.0).abs() < 0.01,
            "l = {l}, g = {g}, a = {a}: {w}"
        );
        // beyond Kapitza's averaging: δ = a0(2ε)/4 = −ε²/2 + 7ε⁴/32 − … with
        // δ = −g/(l·w²), ε = a/l gives w = √(2gl)/a·(1 + 7ε²/32 + O(ε⁴))
        let eps = a / l;
        let second = 7.0 * eps * eps / 32.0;
        assert!(
            (w / threshold - 1.0 - second).abs() < eps.powi(4),
            "ε = {eps}: {w}"
        );
        let at = |w: f64| {
            let v = values(
                &p,
                KAPITZA,
                &[("m", 1.0), ("l", l), ("g", g), ("a", a), ("w", w)],
            );
            p.analyse(&v).expect("analysed").verdict
        };
        assert_eq!(at(0.9 * w), Verdict::Unstable);
        assert_eq!(at(1.1 * w), Verdict::Stable);
    }
}

/// `qdot floquet ARGS --output json`: the first point.
fn point(args: &[&str]) -> serde_json::Value {
    let mut all = vec!["floquet"];
    all.extend(args);
    all.extend(["--output", "json"]);
    let (code, out, err) = qdot(&all);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).expect("JSON");
    v["points"][0].clone()
}

fn number(v: &serde_json::Value, key: &str) -> f64 {
    v[key].as_f64().unwrap_or_else(|| panic!("{key} in {v}"))
}

#[test]
fn constant_coefficients_give_the_exact_multipliers() {
    // ε = 0: x'' + δ·x = 0 turns by 2π·√δ in one period
    let p = point(&[MATHIEU, "--set", "delta=0.5,eps=0,m=1,w=1"]);
    let trace = number(&p, "trace");
    assert!(
        (trace - 2.0 * (2.0 * PI * 0.5f64.sqrt()).cos()).abs() < 1e-9,
        "{trace}"
    );
    assert!((number(&p, "max_abs_multiplier") - 1.0).abs() < 1e-9);
    assert_eq!(p["verdict"], "stable");
    // δ = −1: x grows like e^t, by e^(2π) in one period
    let p = point(&[MATHIEU, "--set", "delta=-1,eps=0,m=1,w=1"]);
    let mu = number(&p, "max_abs_multiplier");
    assert!((mu / (2.0 * PI).exp() - 1.0).abs() < 1e-9, "{mu}");
    assert_eq!(p["verdict"], "unstable");
    assert!(number(&p, "error") < 1e-6);
}

#[test]
fn plainly_stable_and_unstable_points() {
    let verdict = |file: &str, args: &[&str]| {
        let mut all = vec![file];
        all.extend(args);
        point(&all)["verdict"].as_str().unwrap_or("").to_string()
    };
    assert_eq!(
        verdict(MATHIEU, &["--set", "delta=0.5,eps=0.2,m=1,w=1"]),
        "stable"
    );
    assert_eq!(
        verdict(MATHIEU, &["--set", "delta=0.25,eps=0.2,m=1,w=1"]),
        "unstable"
    );
    assert_eq!(
        verdict(MATHIEU, &["--set", "delta=1,eps=0.5,m=1,w=1"]),
        "unstable"
    );
    // on the boundary itself: δ = 1/4, ε = 0 (a double multiplier −1)
    assert_eq!(
        verdict(MATHIEU, &["--set", "delta=0.25,eps=0,m=1,w=1"]),
        "undecided"
    );
    let kapitza = |w: &str| {
        verdict(
            KAPITZA,
            &[
                "--at",
                "theta=pi",
                "--set",
                &format!("m=1,l=1,g=9.81,a=0.1,w={w}"),
            ],
        )
    };
    assert_eq!(kapitza("60"), "stable");
    assert_eq!(kapitza("30"), "unstable");
    // hanging down it is stable however the support moves slowly
    let down = verdict(KAPITZA, &["--set", "m=1,l=1,g=9.81,a=0.01,w=1"]);
    assert_eq!(down, "stable");
}

#[test]
fn a_damped_mathieu_oscillator_decays_and_keeps_liouvilles_determinant() {
    let dir = std::env::temp_dir().join(format!("qdot-floquet-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a temporary directory");
    let file = dir.join("damped.qd");
    std::fs::write(
        &file,
        "coordinates x\nparameters delta, eps, c\nkinetic E = 1/2*x'^2\n\
         potential V = 1/2*(delta + eps*cos(t))*x^2\ndissipation D = -1/2*c*x'^2\n",
    )
    .expect("written");
    let file = file.to_str().expect("UTF-8");
    let (code, out, err) = qdot(&["floquet", file, "--set", "delta=0.5,eps=0.2,c=0.1"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("Lagrangian: no\n"), "{out}");
    assert!(
        out.contains(
            "Verdict: stable (every |μ| < 1: every solution decays (asymptotically stable))"
        ),
        "{out}"
    );
    let p = point(&[file, "--set", "delta=0.5,eps=0.2,c=0.1"]);
    let mu = p["multipliers"].as_array().expect("multipliers");
    let (re0, im0) = (number(&mu[0], "re"), number(&mu[0], "im"));
    let (re1, im1) = (number(&mu[1], "re"), number(&mu[1], "im"));
    // det Φ(T) = μ1·μ2 = exp(−c·T)
    let det_re = re0 * re1 - im0 * im1;
    let det_im = re0 * im1 + im0 * re1;
    assert!((det_re - (-0.1 * 2.0 * PI).exp()).abs() < 1e-9, "{det_re}");
    assert!(det_im.abs() < 1e-9);
}

#[test]
fn a_given_function_drives_the_support_as_an_explicit_t_does() {
    let dir = std::env::temp_dir().join(format!("qdot-floquet-fn-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a temporary directory");
    let file = dir.join("given.qd");
    std::fs::write(
        &file,
        "coordinates theta: angle\nparameters m, l, g, a, w\nfunctions s\n\
         particle bob: mass m, at [l*sin(theta), s(t) - l*cos(theta)]\ngravity [0, -g]\n",
    )
    .expect("written");
    let set = "m=1,l=1,g=9.81,a=0.1,w=50";
    let given = point(&[
        file.to_str().expect("UTF-8"),
        "--at",
        "theta=pi",
        "--function",
        "s=a*cos(w*t)",
        "--set",
        set,
    ]);
    let explicit = point(&[KAPITZA, "--at", "theta=pi", "--set", set]);
    assert_eq!(given["monodromy"], explicit["monodromy"]);
    assert_eq!(given["verdict"], "stable");
}

#[test]
fn the_chart_marks_the_tongues_and_is_drawn() {
    let svg = std::env::temp_dir().join(format!("qdot-floquet-{}.svg", std::process::id()));
    let svg = svg.to_str().expect("UTF-8");
    let (code, out, err) = qdot(&[
        "floquet",
        MATHIEU,
        "--set",
        "m=1,w=1",
        "--over",
        "delta=-0.5:2.5:13,eps=0:0.5:3",
        "--plot",
        svg,
    ]);
    assert_eq!(code, 0, "{err}");
    // ε = 0 (the bottom row): undecided exactly at δ = 0, 1/4, 1 and 9/4,
    // unstable below 0; the tongues at δ = 1/4 and 1 open as ε grows, and
    // at ε = 1/2 δ = 0 is past the edge a0/4 = −0.114…
    let lines: Vec<&str> = out.lines().collect();
    let start = lines
        .iter()
        .position(|l| l.starts_with("Stability chart"))
        .expect("the chart")
        + 2;
    assert_eq!(
        lines[start..start + 3],
        ["  ####..#......", "  ##.#..#......", "  ##??..?....?."],
        "{out}"
    );
    assert!(
        out.contains("39 points: 11 unstable, 24 stable, 4 undecided, 0 failed"),
        "{out}"
    );
    let drawn = std::fs::read_to_string(svg).expect("the chart");
    assert!(
        drawn.contains("stability chart") && drawn.contains("<rect"),
        "{drawn}"
    );
    // titled with the scene's name (its first comment), not the file's
    assert!(
        drawn.contains(
            "The Mathieu equation x&apos;&apos; + (delta + eps*cos(w*t))*x = 0: stability chart"
        ),
        "{drawn}"
    );
    let (code, csv, _) = qdot(&[
        "floquet",
        MATHIEU,
        "--set",
        "m=1,w=1",
        "--over",
        "delta=0:1:3,eps=0.1:0.1:1",
        "--output",
        "csv",
    ]);
    assert_eq!(code, 0);
    assert_eq!(
        csv.lines().next(),
        Some("delta,eps,period,max_abs_multiplier,trace,error,verdict,note")
    );
    assert_eq!(csv.lines().count(), 4);
}

/// The chart in the book (book/src/oscillations.md) is what `--plot` draws.
#[test]
fn the_books_chart_is_what_floquet_draws() {
    let made = std::env::temp_dir().join(format!("qdot-floquet-book-{}.svg", std::process::id()));
    let (code, _, err) = qdot(&[
        "floquet",
        MATHIEU,
        "--set",
        "m=1,w=1",
        "--over",
        "delta=-0.5:2.5:151,eps=0:2:81",
        "--plot",
        made.to_str().expect("UTF-8"),
    ]);
    assert_eq!(code, 0, "{err}");
    let now = std::fs::read_to_string(&made).expect("the chart");
    let book = concat!(
        env!("QDOT_ROOT"),
        "/book/src/oscillations/mathieu_chart.svg"
    );
    if std::env::var_os("QDOT_BLESS").is_some() {
        std::fs::write(book, &now).expect("blessed");
    }
    assert!(
        std::fs::read_to_string(book).unwrap_or_default() == now,
        "{book} drifted: QDOT_BLESS=1 cargo test --release --test it floquet::"
    );
    let _ = std::fs::remove_file(made);
}

#[test]
fn json_has_its_keys() {
    let (code, out, err) = qdot(&[
        "floquet",
        KAPITZA,
        "--at",
        "theta=pi",
        "--set",
        "m=1,l=1,g=9.81,a=0.1,w=60",
        "--output",
        "json",
    ]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).expect("JSON");
    let keys: Vec<&str> = v
        .as_object()
        .expect("object")
        .keys()
        .map(String::as_str)
        .collect();
    assert_eq!(
        keys,
        [
            "coordinates",
            "at",
            "equations",
            "frequency",
            "lagrangian",
            "parameters",
            "points"
        ]
    );
    let keys: Vec<&str> = v["points"][0]
        .as_object()
        .expect("object")
        .keys()
        .map(String::as_str)
        .collect();
    assert_eq!(
        keys,
        [
            "values",
            "period",
            "monodromy",
            "multipliers",
            "trace",
            "max_abs_multiplier",
            "error",
            "verdict",
            "note"
        ]
    );
    assert_eq!(v["at"][0], "pi");
    assert_eq!(v["frequency"], "w");
    assert_eq!(
        v["equations"][0],
        "l^2*m*theta'' + a*l*m*w^2*cos(w*t)*theta - g*l*m*theta"
    );
    let period = number(&v["points"][0], "period");
    assert!((period - 2.0 * PI / 60.0).abs() < 1e-15);
}

/// `qdot floquet ARGS` fails with this message on stderr.
fn refused(args: &[&str], message: &str) {
    let mut all = vec!["floquet"];
    all.extend(args);
    let (code, _, err) = qdot(&all);
    assert_eq!(code, 1, "{err}");
    assert_eq!(err, message);
}

#[test]
fn refusals_say_why() {
    let dir = std::env::temp_dir().join(format!("qdot-floquet-no-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a temporary directory");
    let write = |name: &str, potential: &str| {
        let f = dir.join(name);
        std::fs::write(
            &f,
            format!(
                "coordinates x\nparameters k\nkinetic E = 1/2*x'^2\npotential V = {potential}\n"
            ),
        )
        .expect("written");
        f.to_str().expect("UTF-8").to_string()
    };
    let growing = write("growing.qd", "1/2*k*(1 + t)*x^2");
    refused(
        &[&growing, "--set", "k=1"],
        "error: the linearized coefficients are not periodic in t: t stands outside a sine or cosine in k·t + k\n  = hint: Floquet theory needs coefficients periodic in t (sin and cos of w*t, or a periodic --function); give --period T if they are periodic in another way\n",
    );
    let two = write("two.qd", "1/2*k*(1 + cos(t) + cos(sqrt(2)*t))*x^2");
    refused(
        &[&two, "--set", "k=1"],
        "error: the coefficients oscillate at the angular frequencies 1 and √2, whose ratio is not a rational number: they have no common period\n  = hint: give the period: --period T\n",
    );
    refused(
        &[&two, "--set", "k=1", "--period", "6.283185307179586"],
        "error: the linearized coefficients do not repeat after --period 6.283185307179586: they differ at t = 0.3321112 and t + T\n  = hint: give the period of the time dependence, or leave --period out to find it\n",
    );
    refused(
        &[KAPITZA, "--at", "theta=pi/2", "--set", "m=1,l=1,g=9.81,a=0.1,w=1"],
        "error: theta = 1/2·π is not a motion of the scene: the force on `theta` there is a·l·m·w²·cos(w·t) − g·l·m ≠ 0\n  = hint: Floquet theory linearizes about a motion: choose --at where the forces vanish at every t\n",
    );
    refused(
        &["examples/moving_support.qd", "--function", "s=1/10*cos(3*t)", "--set", "m=1,l=1,g=9.81"],
        "error: theta = 0 is not a motion of the scene: the force on `theta` there is 9/10·l·m·cos(3·t) ≠ 0\n  = hint: Floquet theory linearizes about a motion: choose --at where the forces vanish at every t\n",
    );
    refused(
        &["examples/moving_support.qd", "--set", "m=1,l=1,g=9.81"],
        "error: the given function `s` needs a definition for its Floquet multipliers\n  = hint: define each given function of the scene once, in t and the parameters: --function \"s=1/10*sin(2*t)\"\n",
    );
    refused(
        &[KAPITZA, "--at", "theta=pi", "--set", "m=1,l=1,g=9.81"],
        "error: no value for the parameters a, w\n  = hint: give every parameter a value: --set a=1,w=1\n",
    );
    refused(
        &["examples/pendulum.qd", "--set", "m=1,g=1,l=1"],
        "error: the linearized coefficients do not change with time: there is no parametric excitation\n  = hint: `qdot modes` gives the small oscillations about an equilibrium\n",
    );
    refused(
        &[MATHIEU, "--over", "delta=0:1:3,eps=0:1", "--set", "eps=1"],
        "error: `--over delta=0:1:3,eps=0:1`: `eps=0:1`: 2 parts after `=`, and it takes 3 (FROM:TO:COUNT)\n  = hint: --over NAME=FROM:TO:COUNT, or two of them for a chart: --over \"delta=-1:3:81,eps=0:2:41\"\n",
    );
    refused(
        &[MATHIEU, "--over", "delta=0:1:1001,eps=0:1:1000"],
        "error: `--over delta=0:1:1001,eps=0:1:1000`: 1,001,000 points, more than 1,000,000\n  = hint: --over NAME=FROM:TO:COUNT, or two of them for a chart: --over \"delta=-1:3:81,eps=0:2:41\"\n",
    );
    refused(
        &[MATHIEU, "--set", "delta=1", "--plot", "x.svg"],
        "error: --plot draws the stability over the --over parameters\n  = hint: add --over NAME=FROM:TO:COUNT: one parameter draws the largest |μ|, two the stability chart\n",
    );
}

#[test]
fn the_period_is_the_frequencies_common_period() {
    let dir = std::env::temp_dir().join(format!("qdot-floquet-period-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a temporary directory");
    let file = dir.join("two.qd");
    std::fs::write(
        &file,
        "coordinates x\nparameters k, w\nkinetic E = 1/2*x'^2\n\
         potential V = 1/2*k*(3 + cos(w*t) + sin(3/2*w*t))*x^2\n",
    )
    .expect("written");
    let (code, out, err) = qdot(&[
        "floquet",
        file.to_str().expect("UTF-8"),
        "--set",
        "k=1,w=2",
        "--output",
        "json",
    ]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).expect("JSON");
    // gcd(w, 3w/2) = w/2: T = 4π/w
    assert_eq!(v["frequency"], "w/2");
    assert!((number(&v["points"][0], "period") - 2.0 * PI).abs() < 1e-15);
    // over two periods Φ(2T) = Φ(T)²: tr Φ(2T) = (tr Φ(T))² − 2·det Φ(T), det = 1
    let once = point(&[MATHIEU, "--set", "delta=0.4,eps=0.3,m=1,w=1"]);
    let twice = point(&[
        MATHIEU,
        "--set",
        "delta=0.4,eps=0.3,m=1,w=1",
        "--period",
        "12.566370614359172",
    ]);
    let (t1, t2) = (number(&once, "trace"), number(&twice, "trace"));
    assert!((t2 - (t1 * t1 - 2.0)).abs() < 1e-8, "{t1} {t2}");
}

#[test]
fn two_coordinates_a_double_inverted_pendulum_on_a_driven_support() {
    let dir = std::env::temp_dir().join(format!("qdot-floquet-double-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a temporary directory");
    let file = dir.join("double.qd");
    std::fs::write(
        &file,
        "coordinates th1, th2\nparameters m, l, g, a, w\n\
         particle p1: mass m, at [l*sin(th1), a*cos(w*t) - l*cos(th1)]\n\
         particle p2: mass m, at [l*sin(th1) + l*sin(th2), a*cos(w*t) - l*cos(th1) - l*cos(th2)]\n\
         gravity [0, -g]\n",
    )
    .expect("written");
    let file = file.to_str().expect("UTF-8");
    let at = |w: &str| {
        let set = format!("m=1,l=1,g=9.81,a=0.05,w={w}");
        point(&[file, "--at", "th1=pi,th2=pi", "--set", &set])
    };
    let fast = at("200");
    assert_eq!(fast["verdict"], "stable");
    let mu = fast["multipliers"].as_array().expect("multipliers");
    assert_eq!(mu.len(), 4);
    for m in mu {
        assert!((number(m, "abs") - 1.0).abs() < 1e-9, "{m}");
    }
    // Kapitza's one-pendulum threshold (88.6) does not hold the double one
    assert_eq!(at("100")["verdict"], "unstable");
}
