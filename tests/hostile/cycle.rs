//! `qdot cycle` (issue 46, items 6–9): verdicts that changed with the
//! units (dead points of the book's slider-crank in other units), a note
//! hidden behind another, a friction solvable but not by iteration, and
//! the reactions at a stick.

use crate::bound::*;

fn json(o: &Outcome) -> serde_json::Value {
    o.assert_clean();
    assert_eq!(o.code, Some(0), "{o:?}");
    serde_json::from_str(&o.stdout).unwrap_or_else(|e| panic!("{e}: {o:?}"))
}

/// The book's numbers for seed 21.3 with every length ×`l` (forces ×l,
/// moments of inertia ×l², the spring's stiffness unchanged), and the
/// guess in the same unit.
fn seed_set(l: f64) -> [String; 2] {
    [
        format!(
            "G1={},G2={},G3={},g={},R={},AB={},AC={},J2={},k=500,l0={},mu=0.15,omega=20",
            20.0 * l,
            15.0 * l,
            10.0 * l,
            9.81 * l,
            0.1 * l,
            0.4 * l,
            0.15 * l,
            0.02 * l * l,
            0.45 * l
        ),
        format!("x2={},xB={}", 0.25 * l, 0.5 * l),
    ]
}

fn seed(over: &str, l: f64, format: &str) -> Outcome {
    let [set, guess] = seed_set(l);
    qdot(&[
        "cycle",
        "examples/seed_21_3.qd",
        "--over",
        over,
        "--set",
        &set,
        "--guess",
        &guess,
        "--output",
        format,
    ])
}

fn qdot(args: &[&str]) -> Outcome {
    qdot_bounded(args, "", SECONDS, MEMORY_MIB)
}

const STICK_S: &str = "so its friction may be anywhere between its values for sliding either way: the reactions are given at both, the limits v → 0⁻ and v → 0⁺";

/// Item 6: with every length ×1e4, φ = 90° and 270° were dead points
/// without reactions; ×1e-6, every row was. In any unit the same rows are
/// noted, and the couple M is the one in metres ×l².
#[test]
fn the_books_slider_crank_has_the_same_verdicts_in_every_length_unit() {
    let metres = json(&seed("phi=0:360deg:5", 1.0, "json"));
    let m = metres["columns"]
        .as_array()
        .unwrap()
        .iter()
        .position(|c| c == "M")
        .unwrap();
    assert!((metres["rows"][1][m].as_f64().unwrap() - 1.516_373_552_287_715).abs() < 1e-12);
    for l in [1e4, 1e-6] {
        let v = json(&seed("phi=0:360deg:5", l, "json"));
        for r in 0..5 {
            let note = &v["notes"][r];
            if r % 2 == 1 {
                assert_eq!(note, &serde_json::Value::Null, "×{l}, row {r}");
                let want = metres["rows"][r][m].as_f64().unwrap() * l * l;
                let got = v["rows"][r][m].as_f64().unwrap();
                assert!(
                    (got - want).abs() <= 1e-9 * want.abs(),
                    "×{l}, row {r}: M {got}, want {want}"
                );
            } else {
                let note = note.as_str().unwrap();
                assert!(
                    note.starts_with(
                        "stick: the relative velocity in the joint `S` vanishes here ("
                    ) && note.ends_with(STICK_S),
                    "×{l}, row {r}: {note}"
                );
            }
        }
    }
    // the text: no value of a small unit printed as 0
    let t = seed("phi=90deg:90deg:1", 1e-6, "text");
    assert_eq!(t.code, Some(0), "{t:?}");
    assert!(t.stdout.contains("1.51637e-12"), "{t:?}");
}

/// A slider-crank with a steep rod (R = 0.1, L = 0.116) and μ = 0.8 on
/// its guide.
const STEEP: &str = "\
coordinates x1, y1, phi, x2, y2, th, xb, yb
parameters R: length, L: length, omega, m1, J1, m2, J2, m3, g, mu
body crank: mass m1, inertia J1, angle phi, at [x1, y1]
body rod: mass m2, inertia J2, angle th, at [x2, y2]
particle block: mass m3, at [xb, yb]
gravity [0, -g]
joint O: pin ground at [0, 0], crank at [x1, y1] - R/2*[cos(phi), sin(phi)]
joint A: pin crank at [x1, y1] + R/2*[cos(phi), sin(phi)], rod at [x2, y2] - L/2*[cos(th), sin(th)]
joint B: pin rod at [x2, y2] + L/2*[cos(th), sin(th)], block at [xb, yb]
joint G: slider ground at [0, 0], block at [xb, yb] along [1, 0]
drive M: phi = omega*t
friction G: mu
";
const STEEP_SET: &str = "R=0.1,L=0.116,omega=10,m1=1,J1=0.01,m2=1,J2=0.01,m3=1,g=9.81,mu=0.8";
const STEEP_GUESS: &str = "x1=0.05,x2=0.15,xb=0.2";

/// Item 8: the fixed-point iteration contracted too slowly (μ·tan θ ≈
/// 0.9) and the rows at 60°, 120°, 240°, 300° said "did not converge";
/// the one solution, proved by the two cases of G_n's sign, is printed,
/// and it obeys G_f = −μ·|G_n|·sgn ẋ_b.
#[test]
fn a_friction_the_iteration_could_not_solve_is_solved_by_its_sign_cases() {
    let args = [
        "--over",
        "phi=0:360deg:7",
        "--set",
        STEEP_SET,
        "--guess",
        STEEP_GUESS,
        "--columns",
        "xb',G_n,G_f,M",
    ];
    let mut text = args.to_vec();
    text.extend(["--output", "text"]);
    let o = qdot_scene("steep", STEEP.as_bytes(), "cycle", &text);
    assert_eq!(o.code, Some(0), "{o:?}");
    for line in [
        "       60    -1.4271   8.39787   6.71829    1.72598\n",
        "      120  -0.304947   17.2676   13.8141  -0.127773\n",
        "      240   0.304947  -32.6491  -26.1192    0.36453\n",
        "      300     1.4271   7.11018  -5.68814    1.02555\n",
    ] {
        assert!(o.stdout.contains(line), "{line}{o:?}");
    }
    assert!(!o.stdout.contains("converge"), "{o:?}");
    let mut js = args.to_vec();
    js.extend(["--output", "json"]);
    let v = json(&qdot_scene("steep", STEEP.as_bytes(), "cycle", &js));
    for r in [1, 2, 4, 5] {
        assert_eq!(v["notes"][r], serde_json::Value::Null, "row {r}");
        let x = |k: usize| v["rows"][r][k].as_f64().unwrap();
        let (vb, n, f) = (x(1), x(2), x(3));
        assert!(
            (f + 0.8 * n.abs() * vb.signum()).abs() < 1e-12 * n.abs(),
            "row {r}"
        );
    }
}

/// Item 9: at the dead centres of seed 21.3 (v_B = 0) the rows had no
/// reactions at all; now both limits of sliding, S_f = ±μ·|S_n|, in
/// text (two lines), CSV (two lines) and JSON (`limits`).
#[test]
fn the_reactions_at_a_stick_are_given_at_both_limits() {
    let o = seed("phi=0:180deg:2", 1.0, "text");
    assert_eq!(o.code, Some(0), "{o:?}");
    let lines: Vec<&str> = o.stdout.lines().collect();
    assert_eq!(lines.len(), 7, "{o:?}");
    assert!(lines[1].starts_with("    0 [1]  "), "{o:?}");
    assert!(lines[2].starts_with("    0 [1]  "), "{o:?}");
    assert!(lines[3].starts_with("  180 [2]  "), "{o:?}");
    assert_eq!(
        lines[5],
        format!("[1] row 1: stick: the relative velocity in the joint `S` vanishes here (0.0e0), {STICK_S} (the first line the limit v → 0⁻, the second v → 0⁺)")
    );
    let v = json(&seed("phi=0:180deg:2", 1.0, "json"));
    let columns: Vec<&str> = v["columns"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c.as_str().unwrap())
        .collect();
    let k = |name: &str| columns.iter().position(|c| *c == name).unwrap();
    for r in 0..2 {
        // the row itself leaves the reactions out, as before
        assert_eq!(v["rows"][r][k("S_n")], serde_json::Value::Null);
        let l = &v["limits"][r];
        assert_eq!(l["joint"], "S");
        for (side, sense) in [("minus", -1.0), ("plus", 1.0)] {
            let x = |name: &str| l[side][k(name)].as_f64().unwrap();
            assert!((x("S_n") - 15.625).abs() < 1e-12, "row {r} {side}");
            assert!(
                (x("S_f") + 0.15 * 15.625 * sense).abs() < 1e-12,
                "row {r} {side}"
            );
            assert!((x("M") - if r == 0 { 0.9375 } else { -0.9375 }).abs() < 1e-12);
        }
    }
    let bx = v["limits"][1]["minus"][k("B_x")].as_f64().unwrap();
    assert!((bx - -46.762_710_244_648_35).abs() < 1e-9, "{bx}");
    let c = seed("phi=0:180deg:2", 1.0, "csv");
    assert_eq!(c.code, Some(0), "{c:?}");
    let rows: Vec<&str> = c.stdout.lines().skip(1).collect();
    assert_eq!(rows.len(), 4, "{c:?}");
    assert!(
        rows[0].ends_with("the limits v → 0⁻ and v → 0⁺; this line: the limit v → 0⁻\""),
        "{c:?}"
    );
    assert!(
        rows[1].ends_with("the limits v → 0⁻ and v → 0⁺; this line: the limit v → 0⁺\""),
        "{c:?}"
    );
}

/// A slider-driven crank with a large friction couple in its pin A: the
/// row after the toggle changed branch and its friction equations have
/// two solutions; the row said only the second.
const SLIDER_DRIVEN: &str = "\
coordinates x1, y1, phi, x2, y2, th, xb, yb
parameters R: length, L: length, omega, m1, J1, m2, J2, m3, mu
body crank: mass m1, inertia J1, angle phi, at [x1, y1]
body rod: mass m2, inertia J2, angle th, at [x2, y2]
particle block: mass m3, at [xb, yb]
joint O: pin ground at [0, 0], crank at [x1, y1] - R/2*[cos(phi), sin(phi)]
joint A: pin crank at [x1, y1] + R/2*[cos(phi), sin(phi)], rod at [x2, y2] - L/2*[cos(th), sin(th)]
joint B: pin rod at [x2, y2] + L/2*[cos(th), sin(th)], block at [xb, yb]
joint G: slider ground at [0, 0], block at [xb, yb] along [1, 0]
drive D: xb = L + R*cos(omega*t)
friction A: mu
";

/// Item 7: every note that applies to a row is shown, in every format.
#[test]
fn a_branch_change_is_said_beside_a_friction_refusal() {
    let want = "the constraint Jacobian's determinant changed sign since the previous regular position: a dead point lies between them, and the assembly branch changed there; the friction equations have 2 solutions here (2 magnitudes of the pin's reaction agree with the friction couple it makes), so the reactions are not determined";
    let run = |format: &str| {
        qdot_scene(
            "slider_driven",
            SLIDER_DRIVEN.as_bytes(),
            "cycle",
            &[
                "--over",
                "t=0.2:6:30",
                "--set",
                "R=0.1,L=0.3,omega=1,m1=1,J1=0.01,m2=1,J2=0.01,m3=1,mu=0.05",
                "--guess",
                "phi=0.2,x1=0.05,x2=0.25,xb=0.39",
                "--output",
                format,
            ],
        )
    };
    let v = json(&run("json"));
    assert_eq!(v["notes"][15], want);
    let c = run("csv");
    assert!(
        c.stdout
            .lines()
            .nth(16)
            .unwrap()
            .ends_with(&format!(",\"{want}\"")),
        "{c:?}"
    );
    let t = run("text");
    assert!(t.stdout.contains(&format!("] row 16: {want}\n")), "{t:?}");
}
