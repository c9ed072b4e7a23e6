//! `qdot response` (issue 37): the exact frequency response against the
//! textbook closed forms of one degree of freedom, Den Hartog's absorber's
//! antiresonance, seed 24.1's steady state as `qdot modes` gives it, the
//! numeric sweep against the exact values, and the errors.

use crate::common::run::qdot;
use qdot::cycle::Over;
use qdot::expr::atom::Atom;
use qdot::expr::func;
use qdot::simulate::response::{parse_over, CompiledResponse};
use qdot::solve::equilibrium::Values;
use qdot::solve::oscillations as osc;
use qdot::solve::response::{response, ForcedSystem, Peak, Response, OMEGA};
use qdot::{Expr, Scene};

fn p(name: &str) -> Expr {
    Expr::param(name)
}

fn q(n: i64) -> Expr {
    Expr::int(n)
}

fn div(a: &Expr, b: &Expr) -> Expr {
    a.div(b).unwrap()
}

fn values(s: &str) -> Values {
    qdot::output::parse_set_any_sign(s).unwrap()
}

fn exact(file: &str) -> (osc::Modes, Response) {
    let scene = Scene::parse(&std::fs::read_to_string(file).unwrap()).unwrap();
    let md = osc::modes(&scene, None, &Values::new()).unwrap();
    let r = response(ForcedSystem::from_modes(&md).unwrap(), &Values::new()).unwrap();
    (md, r)
}

/// `e` at the values `set` and Ω = `omega`.
fn at(e: &Expr, set: &Values, omega: f64) -> f64 {
    e.eval_f64(&|a: &Atom| match a {
        Atom::Param(n) if &**n == OMEGA => Some(omega),
        Atom::Param(n) => set.get(&**n).copied(),
        _ => None,
    })
    .unwrap()
}

/// |X_j| and φ_j (radians) swept numerically at the single frequency `omega`.
fn swept(file: &str, set: &Values, omega: f64) -> Vec<(f64, f64)> {
    let scene = Scene::parse(&std::fs::read_to_string(file).unwrap()).unwrap();
    let sys = scene
        .assumptions_in_force(|| ForcedSystem::of_scene(&scene, None))
        .unwrap();
    let over = Over {
        name: OMEGA.into(),
        from: omega,
        to: omega,
        count: 1,
    };
    let t = CompiledResponse::new(&scene, &sys, set).unwrap().run(&over);
    (0..sys.coordinates.len())
        .map(|j| (t.amplitude[0][j].unwrap(), t.phase[0][j].unwrap()))
        .collect()
}

#[test]
fn one_dof_amplitude_and_phase_are_the_textbook_closed_forms() {
    let (_, r) = exact("examples/forced_oscillator.qd");
    let (m, k, c, f0, w) = (p("m"), p("k"), p("c"), p("F0"), p(OMEGA));
    // r² = Ω²/ω₀² = m·Ω²/k, (2ζr)² = c²·Ω²/k², 2ζr = c·Ω/k
    let r2 = div(&m.mul(&w).mul(&w), &k);
    let two_zeta_r = div(&c.mul(&w), &k);
    let one_minus = q(1).sub(&r2);
    let d2 = one_minus.mul(&one_minus).add(&two_zeta_r.mul(&two_zeta_r));
    let x_static = div(&f0, &k);
    let amplitude2 = div(&x_static.mul(&x_static), &d2);
    assert_eq!(r.amplitude_squared[0], amplitude2);
    assert_eq!(
        r.amplitude_squared[0].to_string(),
        "F0^2/(m^2*Omega^4 + c^2*Omega^2 - 2*k*m*Omega^2 + k^2)"
    );
    let tan_phi = div(&two_zeta_r, &one_minus);
    assert_eq!(r.tan_phase[0].as_ref().unwrap(), &tan_phi);
    let s = r.single.as_ref().unwrap();
    assert_eq!(s.omega0_squared, div(&k, &m));
    assert_eq!(s.zeta_squared, div(&c.mul(&c), &q(4).mul(&k).mul(&m)));
    assert_eq!(s.static_deflection.as_ref().unwrap(), &x_static);
    assert_eq!(s.magnification_squared, div(&q(1), &d2));
    let t2 = div(&q(1).add(&two_zeta_r.mul(&two_zeta_r)), &d2);
    assert_eq!(s.transmissibility_squared, t2);
    // the numeric sweep agrees at m = 1, k = 4, c = 0.4, F0 = 1 (ζ = 0.1)
    let set = values("m=1,k=4,c=0.4,F0=1");
    for omega in [0.3, 1.9, 2.0, 2.2, 7.0] {
        let (amp, phase) = swept("examples/forced_oscillator.qd", &set, omega)[0];
        let exact_amp = at(&r.amplitude_squared[0], &set, omega).sqrt();
        assert!((amp - exact_amp).abs() <= 1e-14 * exact_amp, "Ω = {omega}");
        let exact_tan = at(&tan_phi, &set, omega);
        assert!((phase.tan() - exact_tan).abs() <= 1e-12 * exact_tan.abs().max(1.0));
        // the lag is between 0 and π
        assert!((0.0..std::f64::consts::PI).contains(&phase), "Ω = {omega}");
    }
}

#[test]
fn one_dof_peak_half_power_points_and_bandwidth_are_the_textbook_closed_forms() {
    let (_, r) = exact("examples/forced_oscillator.qd");
    let (m, k, c, f0) = (p("m"), p("k"), p("c"), p("F0"));
    let s = r.single.as_ref().unwrap();
    let Peak::At {
        omega_squared,
        magnification_squared,
        amplitude,
        half_power,
        bandwidth_squared,
        condition,
    } = &s.peak
    else {
        panic!("a damped oscillator has a peak: {:?}", s.peak)
    };
    // ω_peak² = ω₀²·(1 − 2ζ²), ζ² = c²/(4km)
    let w0sq = div(&k, &m);
    let zeta2 = div(&c.mul(&c), &q(4).mul(&k).mul(&m));
    let peak2 = w0sq.mul(&q(1).sub(&zeta2.scale(&qdot::Q::from_i64(2))));
    assert_eq!(omega_squared, &peak2);
    assert_eq!(
        condition.as_ref(),
        Some(&peak2),
        "ζ² < 1/2 is undecided without values"
    );
    // D_peak² = 1/(4ζ²(1 − ζ²))
    let d_peak2 = div(&q(1), &q(4).mul(&zeta2).mul(&q(1).sub(&zeta2)));
    assert_eq!(magnification_squared, &d_peak2);
    assert_eq!(
        amplitude.as_ref().unwrap().mul(amplitude.as_ref().unwrap()),
        div(&f0, &k).mul(&div(&f0, &k)).mul(&d_peak2)
    );
    // Ω₁,₂² = ω₀²·(1 − 2ζ² ∓ 2ζ·√(1 − ζ²)), ζ·√(1 − ζ²) = √(ζ²(1 − ζ²))
    let spread = func::sqrt(&zeta2.mul(&q(1).sub(&zeta2)))
        .unwrap()
        .mul(&w0sq)
        .scale(&qdot::Q::from_i64(2));
    let (lower, upper) = half_power;
    let set = values("m=1,k=4,c=0.4,F0=1");
    let num = |e: &Expr| at(e, &set, 0.0);
    assert!((num(lower.as_ref().unwrap()) - num(&peak2.sub(&spread))).abs() < 1e-14);
    assert!((num(upper) - num(&peak2.add(&spread))).abs() < 1e-14);
    assert_eq!(
        lower.as_ref().unwrap().to_string(),
        "(2*k*m - c*sqrt(4*k*m - c^2) - c^2)/(2*m^2)"
    );
    // ζ = 0.1, ω₀ = 2: ω_peak = 2·√0.98, D_peak = 1/(0.2·√0.99)
    assert!((num(omega_squared).sqrt() - 2.0 * 0.98f64.sqrt()).abs() < 1e-14);
    let x_peak = 0.25 / (0.2 * 0.99f64.sqrt());
    assert!((num(amplitude.as_ref().unwrap()) - x_peak).abs() < 1e-14);
    // the sweep: |X| at ω_peak is X_peak, at the half-power points X_peak/√2
    let file = "examples/forced_oscillator.qd";
    let (a, _) = swept(file, &set, num(omega_squared).sqrt())[0];
    assert!((a - x_peak).abs() < 1e-13 * x_peak);
    for w2 in [num(lower.as_ref().unwrap()), num(upper)] {
        let (a, _) = swept(file, &set, w2.sqrt())[0];
        assert!((a - x_peak / 2f64.sqrt()).abs() < 1e-13 * x_peak);
    }
    // the bandwidth: (Ω₂ − Ω₁)², close to (2ζω₀)² = 0.16 for light damping
    let band = num(&bandwidth_squared.clone().unwrap());
    let direct = num(upper).sqrt() - num(lower.as_ref().unwrap()).sqrt();
    assert!((band - direct * direct).abs() < 1e-14);
    assert!((band.sqrt() - 0.4).abs() < 0.01);
}

#[test]
fn heavy_damping_has_no_peak_and_the_text_says_so() {
    let (code, out, err) = qdot(&[
        "response",
        "examples/forced_oscillator.qd",
        "--set",
        "m=1,k=1,c=1.5,F0=1",
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(
        out.contains("  resonance: no peak (ζ² ≥ 1/2): D falls from 1 at Ω = 0\n"),
        "{out}"
    );
}

#[test]
fn den_hartog_absorber_holds_the_machine_still_at_k2_over_m2() {
    let (_, r) = exact("examples/vibration_absorber.qd");
    assert_eq!(r.antiresonances[0], vec![div(&p("k2"), &p("m2"))]);
    assert!(r.antiresonances[1].is_empty());
    // |X₁|² has the absorber's factor (k₂ − m₂Ω²)² + c²Ω² on top
    let w = p(OMEGA);
    let top = p("k2").sub(&p("m2").mul(&w).mul(&w));
    let top = top.mul(&top).add(&p("c").mul(&p("c")).mul(&w).mul(&w));
    let ratio = r.amplitude_squared[0].div(&top).unwrap();
    assert!(ratio
        .num()
        .vars()
        .iter()
        .all(|&v| v != qdot::expr::atom::param("k2")));
    // undamped and tuned, the machine stands still; the absorber moves
    // against the force: X₂ = −F0/k2
    let set = values("m1=1,m2=0.2,k1=1,k2=0.3,c=0,F0=1");
    let tuned = (0.3f64 / 0.2).sqrt();
    let x = swept("examples/vibration_absorber.qd", &set, tuned);
    assert!(x[0].0 < 1e-14, "{x:?}");
    assert!((x[1].0 - 1.0 / 0.3).abs() < 1e-12, "{x:?}");
    let (code, out, err) = qdot(&["response", "examples/vibration_absorber.qd"]);
    assert_eq!(code, 0, "{err}");
    assert!(
        out.contains("Antiresonances (undamped: X = 0)\n  x₁: Ω² = k₂/m₂\n  x₂: none\n"),
        "{out}"
    );
}

#[test]
fn seed_24_1_response_is_the_steady_state_modes_prints() {
    let (md, r) = exact("examples/seed_24_1.qd");
    let sf = osc::standard_form(&md, &Values::new()).unwrap();
    let (pf, x, tan_psi) = osc::damped_steady_state(&md, &sf).unwrap();
    assert_eq!(pf, p("p"));
    let to_omega: rustc_hash::FxHashMap<_, _> = [(qdot::expr::atom::param("p"), p(OMEGA))]
        .into_iter()
        .collect();
    let x = x.subs_many(&to_omega).unwrap();
    let tan_psi = tan_psi.subs_many(&to_omega).unwrap();
    assert_eq!(r.amplitude_squared[0], x.mul(&x));
    assert_eq!(r.tan_phase[0].as_ref().unwrap(), &tan_psi);
    assert_eq!(
        r.tan_phase[0].as_ref().unwrap().to_string(),
        "-4*c*Omega*r/(81*m*Omega^2*r + 9*g*m - 16*k*r)"
    );
    // and what the command line prints for `modes`
    let (_, modes_out, _) = qdot(&["modes", "examples/seed_24_1.qd"]);
    assert!(modes_out.contains(&format!(
        "tan ψ = 2αp/(ω² − p²) = {}",
        r.tan_phase[0]
            .as_ref()
            .unwrap()
            .subs_many(
                &[(qdot::expr::atom::param(OMEGA), p("p"))]
                    .into_iter()
                    .collect()
            )
            .unwrap()
            .to_unicode()
    )));
}

#[test]
fn json_keys_of_the_exact_response_and_of_the_sweep() {
    let (code, out, err) = qdot(&[
        "response",
        "examples/forced_oscillator.qd",
        "--output",
        "json",
    ]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["frequency"], "p");
    assert_eq!(v["tan_phase"][0], "c*Omega/(k - m*Omega^2)");
    assert_eq!(v["single"]["omega0_squared"], "k/m");
    assert_eq!(v["single"]["resonance"], "peak");
    assert_eq!(v["single"]["peak_omega_squared"], "(2*k*m - c^2)/(2*m^2)");
    let (code, out, err) = qdot(&[
        "response",
        "examples/forced_oscillator.qd",
        "--set",
        "m=1,k=4,c=0.4,F0=1",
        "--over",
        "Omega=1:3:201",
        "--output",
        "json",
    ]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(
        v["columns"],
        serde_json::json!(["Omega", "amp_x", "phase_x"])
    );
    assert_eq!(v["rows"].as_array().unwrap().len(), 201);
    assert_eq!(v["natural_frequencies"], serde_json::json!([2.0]));
    // the grid's peak is the point nearest ω_peak = 1.9799 (step 0.01)
    let peak = &v["peaks"]["x"][0];
    assert_eq!(peak[0].as_f64().unwrap(), 1.98);
}

#[test]
fn bad_input_is_refused_with_a_reason() {
    let cases: [(&[&str], &str); 5] = [
        (
            &["response", "examples/four_mass_chain.qd"],
            "error: the scene has no harmonic load: the frequency response needs a force F·cos(p·t) (or sin) on the system\n  = hint: write a harmonic load in the scene, e.g. `work L = F0*cos(p*t)*x` (p the forcing frequency)\n",
        ),
        (
            &["response", "examples/forced_oscillator.qd", "--over", "p=0:1:10"],
            "error: `--over p=0:1:10`: `qdot response` varies the forcing frequency, `Omega`, not `p`\n  = hint: --over Omega=0:3:600: the first and last frequencies, and how many\n",
        ),
        (
            &["response", "examples/forced_oscillator.qd", "--over", "Omega=0:1"],
            "error: `--over Omega=0:1`: 2 parts after `=`, and it takes 3 (FROM:TO:COUNT)\n  = hint: --over Omega=0:3:600: the first and last frequencies, and how many\n",
        ),
        (
            &["response", "examples/forced_oscillator.qd", "--over", "Omega=0:1:10", "--set", "m=1,k=2"],
            "error: no value for the parameters c, F0\n  = hint: give every parameter a value: --set c=1,F0=1\n",
        ),
        (
            &["response", "examples/forced_oscillator.qd", "--output", "csv"],
            "error: unknown output `csv`\n  = hint: --output json, --output text (csv with --over)\n",
        ),
    ];
    for (args, expected) in cases {
        let (code, out, err) = qdot(args);
        assert_eq!(code, 1, "{args:?}: {out}");
        assert_eq!(err, expected, "{args:?}");
    }
    assert!(parse_over("Omega=0:3:0").is_err());
    // as JSON, a scene without a load has nothing to solve
    let (code, _, err) = qdot(&[
        "response",
        "examples/four_mass_chain.qd",
        "--output",
        "json",
    ]);
    assert_eq!(code, 1);
    let v: serde_json::Value = serde_json::from_str(&err).unwrap();
    assert_eq!(v["error"]["kind"], "nothing_to_solve");
}

#[test]
fn a_load_of_two_frequencies_is_refused() {
    let refused = |work: &str| {
        let scene = Scene::parse(&format!(
            "coordinates x\nparameters m, k, F0, p, w\nkinetic E = 1/2*m*x'^2\npotential V = 1/2*k*x^2\nwork L = {work}\n"
        ))
        .unwrap();
        scene
            .assumptions_in_force(|| ForcedSystem::of_scene(&scene, None))
            .unwrap_err()
            .message
    };
    assert_eq!(
        refused("F0*(cos(p*t) + cos(w*t))*x"),
        "the load has more than one frequency (cos(p·t) and cos(w·t)): the frequency response takes one harmonic load"
    );
    // cos(p·t)·cos(2·p·t) = (cos(p·t) + cos(3·p·t))/2: two harmonics
    assert_eq!(
        refused("F0*cos(p*t)*cos(2*p*t)*x"),
        "the load has more than one frequency (cos(p·t) and cos(3·p·t)): the frequency response takes one harmonic load"
    );
    // sin(2·p·t)/2, written in cos(p·t) and sin(p·t) of degree 2, is one
    // harmonic load at 2·p
    let scene = Scene::parse(
        "coordinates x\nparameters m, k, F0, p\nkinetic E = 1/2*m*x'^2\npotential V = 1/2*k*x^2\nwork L = F0*cos(p*t)*sin(p*t)*x\n",
    )
    .unwrap();
    let sys = scene
        .assumptions_in_force(|| ForcedSystem::of_scene(&scene, None))
        .unwrap();
    assert_eq!(sys.frequency.to_string(), "2*p");
    assert!(sys.load_cos[0].is_zero());
    assert_eq!(sys.load_sin[0], div(&p("F0"), &q(2)));
}

#[test]
fn a_sine_load_and_a_rotating_unbalance_read_their_amplitudes() {
    // base excitation through the spring and damper: f = k·Y·cos + c·Y·Ω·(−sin)
    let scene = Scene::parse(
        "coordinates x\nparameters m, k, c, e, p\nkinetic E = 1/2*m*x'^2\npotential V = 1/2*k*x^2\nrayleigh R = 1/2*c*x'^2\nwork L = m*e*p^2*sin(p*t)*x\n",
    )
    .unwrap();
    let sys = scene
        .assumptions_in_force(|| ForcedSystem::of_scene(&scene, None))
        .unwrap();
    let w = p(OMEGA);
    assert!(sys.load_cos[0].is_zero());
    assert_eq!(sys.load_sin[0], p("m").mul(&p("e")).mul(&w).mul(&w));
    assert!(sys.depends_on_omega());
    let r = response(sys, &Values::new()).unwrap();
    assert!(r.single.as_ref().unwrap().static_deflection.is_none());
    assert_eq!(
        r.amplitude_squared[0].to_string(),
        "e^2*m^2*Omega^4/(m^2*Omega^4 + c^2*Omega^2 - 2*k*m*Omega^2 + k^2)"
    );
}

/// The book's figure is what `--plot` draws (`QDOT_BLESS=1` rewrites it).
#[test]
fn book_figure_is_the_commands_plot() {
    let dir = std::env::temp_dir().join(format!("qdot-response-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let svg = dir.join("vibration_absorber_response.svg");
    let (code, _, err) = qdot(&[
        "response",
        "examples/vibration_absorber.qd",
        "--set",
        "m1=1,m2=0.2,k1=1,k2=0.2,c=0.02,F0=1",
        "--over",
        "Omega=0.3:3:1500",
        "--plot",
        svg.to_str().unwrap(),
        "--output",
        "csv",
    ]);
    assert_eq!(code, 0, "{err}");
    let now = std::fs::read_to_string(&svg).unwrap();
    let book = concat!(
        env!("QDOT_ROOT"),
        "/book/src/oscillations/vibration_absorber_response.svg"
    );
    if std::env::var_os("QDOT_BLESS").is_some() {
        std::fs::write(book, &now).unwrap();
    }
    assert!(
        std::fs::read_to_string(book).unwrap() == now,
        "{book} drifted: QDOT_BLESS=1 cargo test --release --test it response::"
    );
    assert!(
        now.matches("<polyline").count() >= 4,
        "two amplitudes and two phases"
    );
    // titled with the scene's name; the logarithmic axes read 0.1, 1, 10,
    // never 1.0e-1
    assert!(
        now.contains("Den Hartog&apos;s vibration absorber — amplitude |X| against Ω"),
        "{now}"
    );
    assert!(!now.contains(".0e"), "an axis labelled 1.0e1");
    for tick in ["\n0.1\n", "\n1\n", "\n10\n"] {
        assert!(now.contains(tick), "no tick {tick}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// A particle on a spring in a frame turning at W: C = 2mW·[[0, −1], [1, 0]]
/// is gyroscopic, and the receptance takes it as it is; the frame's
/// natural frequencies are √(k/m) ± W.
#[test]
fn a_gyroscopic_system_is_solved_with_its_skew_c() {
    let src = "coordinates x, y\nparameters m, k, W, F0, p\nkinetic E = 1/2*m*((x' - W*y)^2 + (y' + W*x)^2)\npotential V = 1/2*k*(x^2 + y^2)\nwork L = F0*cos(p*t)*x\n";
    let scene = Scene::parse(src).unwrap();
    let sys = scene
        .assumptions_in_force(|| ForcedSystem::of_scene(&scene, None))
        .unwrap();
    assert!(sys.gyroscopic());
    let r = response(sys.clone(), &Values::new()).unwrap();
    assert_eq!(
        r.antiresonance_note.as_deref(),
        Some("C has gyroscopic terms, which the undamped system keeps: no antiresonances computed")
    );
    let set = values("m=1,k=4,W=0.5,F0=1");
    let t = CompiledResponse::new(&scene, &sys, &set)
        .unwrap()
        .run(&Over {
            name: OMEGA.into(),
            from: 0.7,
            to: 3.1,
            count: 3,
        });
    let w = &t.natural_frequencies;
    assert!(
        (w[0] - 1.5).abs() < 1e-12 && (w[1] - 2.5).abs() < 1e-12,
        "{w:?}"
    );
    for (k, omega) in [0.7, 1.9, 3.1].into_iter().enumerate() {
        for j in 0..2 {
            let exact = at(&r.amplitude_squared[j], &set, omega).sqrt();
            let swept = t.amplitude[k][j].unwrap();
            assert!((swept - exact).abs() <= 1e-13 * exact, "Ω = {omega}, {j}");
        }
    }
}

/// The scene m·ẍ + c·ẋ + k·x = load (F = 1 at evaluation): a constant
/// force, a rotating unbalance F·p², or a base F·cos(p·t) moved through
/// the spring and the damper.
fn one_dof(kind: usize, m: i64, k: i64, c: i64) -> String {
    let (potential, rayleigh, work) = match kind {
        0 => ("x^2", "x'^2", "\nwork L = F*cos(p*t)*x"),
        1 => ("x^2", "x'^2", "\nwork L = F*p^2*cos(p*t)*x"),
        _ => ("(x - F*cos(p*t))^2", "(x' + F*p*sin(p*t))^2", ""),
    };
    format!("coordinates x\nparameters F, p\nkinetic E = 1/2*{m}*x'^2\npotential V = 1/2*{k}*{potential}\nrayleigh R = 1/2*{c}*{rayleigh}{work}\n")
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(24))]

    /// The exact peak of |X| for the scene's load is the largest |X| on a
    /// fine grid and a local maximum; at the half-power points |X|² is
    /// half its peak; where qdot says there is no peak, |X| is monotone.
    #[test]
    fn the_exact_peak_is_the_maximum_of_the_amplitude(
        kind in 0usize..3, m in 1i64..20, k in 1i64..2000, c in 1i64..120,
    ) {
        let scene = Scene::parse(&one_dof(kind, m, k, c)).unwrap();
        let sys = scene
        .assumptions_in_force(|| ForcedSystem::of_scene(&scene, None))
        .unwrap();
        let r = response(sys, &Values::new()).unwrap();
        let set = values("F=1");
        let a2 = |w: f64| at(&r.amplitude_squared[0], &set, w);
        let num = |e: &Expr| at(e, &set, 0.0);
        let w0 = (k as f64 / m as f64).sqrt();
        let grid: Vec<f64> = (0..4000).map(|i| w0 * 1e-3 * 1e4f64.powf(i as f64 / 3999.0)).collect();
        let top = grid.iter().map(|&w| a2(w)).fold(0.0, f64::max);
        let s = r.single.as_ref().unwrap();
        let (peak, half, none): (Option<Expr>, Vec<Expr>, Option<bool>) = match &s.peak {
            Peak::At { omega_squared, half_power, .. } => (
                Some(omega_squared.clone()),
                half_power.0.iter().chain([&half_power.1]).cloned().collect(),
                None,
            ),
            Peak::None => (None, Vec::new(), Some(false)),
            Peak::Load(l) => {
                let note = l.note.clone().unwrap_or_default();
                let none = match l.omega_squared {
                    Some(_) => None,
                    None if note == "no peak: |X| rises with Ω for every Ω > 0" => Some(true),
                    None if note == "no peak: |X| falls with Ω for every Ω > 0" => Some(false),
                    None => panic!("undecided with numbers: {note}"),
                };
                (l.omega_squared.clone(), l.half_power.0.iter().chain(&l.half_power.1).cloned().collect(), none)
            }
            Peak::Undamped => panic!("damped"),
        };
        // The exact radicals lose digits in f64 by cancellation (Ω_peak² of a
        // light base excitation is a difference of two terms ~1/ζ² times it),
        // so the float checks allow 1e-12 (resp. 1e-9) times 1 + 1/ζ².
        let zeta = c as f64 / (2.0 * ((k * m) as f64).sqrt());
        let cond = 1.0 + 1.0 / (zeta * zeta);
        if let Some(w2) = peak {
            let wp = num(&w2).sqrt();
            let ap = a2(wp);
            proptest::prop_assert!(ap >= top * (1.0 - 1e-12 * cond), "{ap} < {top} at {wp}");
            proptest::prop_assert!(ap >= a2(wp * 0.999) && ap >= a2(wp * 1.001));
            for h in &half {
                let v = a2(num(h).sqrt());
                proptest::prop_assert!((v - ap / 2.0).abs() <= 1e-9 * cond * ap, "{v} {ap}");
            }
        }
        if let Some(rises) = none {
            for pair in grid.windows(2) {
                let (x, y) = (a2(pair[0]), a2(pair[1]));
                let ok = if rises { y >= x * (1.0 - 1e-12) } else { y <= x * (1.0 + 1e-12) };
                proptest::prop_assert!(ok, "not monotone at {pair:?}: {x} {y}");
            }
        }
    }
}
