//! `qdot cycle` (issue 36): every row of every mechanism equals the
//! independent NumPy reference of tests/fixtures/mechanisms to 1e-9; a
//! published worked example (Marghitu) reproduced; the drive's couple
//! equals the one from virtual work, and its mean over a frictionless
//! cycle is zero; bad input is a positioned error or a row that says what
//! and where; dead points are named and the assembly branch never changes
//! silently.

use qdot::cycle::{cycle, parse_guess, CycleRequest, CycleTable, Over};
use qdot::expr::atom::Atom;
use qdot::{Diagnostic, Scene};
use std::collections::HashMap;
use std::process::Command;

/// |a − b| ≤ 1e-9·max(1, |a|): the agreement the issue asks of every value.
const TOLERANCE: f64 = 1e-9;

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= TOLERANCE * a.abs().max(1.0)
}

/// One fixture of tests/fixtures/mechanisms.
struct Fixture {
    json: serde_json::Value,
    scene: String,
    over: String,
    set: String,
    guess: String,
    columns: Vec<String>,
    rows: Vec<Vec<f64>>,
}

fn fixture(name: &str) -> Fixture {
    let path = format!(
        "{}/tests/fixtures/mechanisms/{name}.json",
        env!("QDOT_ROOT")
    );
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    let json: serde_json::Value = serde_json::from_str(&text).expect("fixture JSON");
    let s = |k: &str| json[k].as_str().unwrap_or("").to_string();
    let columns = json["columns"]
        .as_array()
        .expect("columns")
        .iter()
        .map(|c| c.as_str().expect("a column name").to_string())
        .collect();
    let rows = json["rows"]
        .as_array()
        .expect("rows")
        .iter()
        .map(|r| {
            r.as_array()
                .expect("a row")
                .iter()
                .map(|x| x.as_f64().expect("a number"))
                .collect()
        })
        .collect();
    Fixture {
        scene: s("scene"),
        over: s("over"),
        set: s("set"),
        guess: s("guess"),
        columns,
        rows,
        json,
    }
}

fn source(path: &str) -> String {
    let path = format!("{}/{path}", env!("QDOT_ROOT"));
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"))
}

fn request(over: &str, set: &str, guess: &str) -> CycleRequest {
    CycleRequest {
        over: Over::parse(over).expect("--over"),
        set: qdot::output::parse_set_any_sign(set)
            .expect("--set")
            .into_iter()
            .collect(),
        guess: parse_guess(guess).expect("--guess"),
    }
}

/// `qdot cycle` through the library, or its error rendered.
fn try_cycle(src: &str, req: &CycleRequest) -> Result<CycleTable, String> {
    let scene = Scene::parse(src).map_err(|d| d.render("scene.qd", src))?;
    cycle(&scene, req).map_err(|d| d.render("scene.qd", src))
}

fn run_cycle(src: &str, req: &CycleRequest) -> CycleTable {
    try_cycle(src, req).unwrap_or_else(|e| panic!("{e}"))
}

fn run_fixture(f: &Fixture) -> CycleTable {
    run_cycle(&source(&f.scene), &request(&f.over, &f.set, &f.guess))
}

/// A column's index by name (the varied name is also a coordinate: the
/// coordinate's column is meant, so the first column is skipped).
fn col(t: &CycleTable, name: &str) -> usize {
    t.columns
        .iter()
        .skip(1)
        .position(|c| c == name)
        .map(|k| k + 1)
        .unwrap_or_else(|| panic!("no column `{name}` in {:?}", t.columns))
}

fn value(t: &CycleTable, row: usize, name: &str) -> f64 {
    t.rows[row].values[col(t, name)]
        .unwrap_or_else(|| panic!("row {row} has no `{name}`: {:?}", t.rows[row].note))
}

/// Every value of every row equals the fixture's, columns matched by
/// name; qdot's only other columns are the frictions `NAME_f`.
fn assert_fixture(name: &str) {
    let f = fixture(name);
    let t = run_fixture(&f);
    assert_eq!(
        t.columns[..f.columns.len()],
        f.columns[..],
        "{name}: columns"
    );
    for extra in &t.columns[f.columns.len()..] {
        assert!(extra.ends_with("_f"), "{name}: unexpected column `{extra}`");
    }
    assert_eq!(t.rows.len(), f.rows.len(), "{name}: rows");
    for (i, (want, got)) in f.rows.iter().zip(&t.rows).enumerate() {
        assert_eq!(got.note, None, "{name}: row {i}");
        for (k, &w) in want.iter().enumerate() {
            let g = got.values[k]
                .unwrap_or_else(|| panic!("{name}: row {i}, `{}` is missing", f.columns[k]));
            assert!(
                close(w, g),
                "{name}: row {i}, `{}`: qdot {g:e}, NumPy {w:e}",
                f.columns[k]
            );
        }
    }
    assert!(!f.rows.is_empty() && f.rows.iter().all(|r| r.len() == f.columns.len()));
}

#[test]
fn the_engine_with_friction_equals_the_numpy_reference() {
    assert_fixture("slider_crank_engine");
}

#[test]
fn the_frictionless_engine_equals_the_numpy_reference() {
    assert_fixture("slider_crank_engine_frictionless");
}

#[test]
fn the_four_bar_with_a_coupler_mass_equals_the_numpy_reference() {
    assert_fixture("four_bar");
}

#[test]
fn the_quick_return_with_friction_equals_the_numpy_reference() {
    assert_fixture("quick_return");
}

#[test]
fn the_frictionless_quick_return_equals_the_numpy_reference() {
    assert_fixture("quick_return_frictionless");
}

#[test]
fn marghitus_slider_crank_equals_the_numpy_reference() {
    assert_fixture("marghitu_slider_crank");
}

#[test]
fn every_fixture_is_tested() {
    let dir = format!("{}/tests/fixtures/mechanisms", env!("QDOT_ROOT"));
    let mut names: Vec<String> = std::fs::read_dir(&dir)
        .expect("the fixtures")
        .filter_map(|e| {
            let p = e.ok()?.path();
            (p.extension()? == "json").then(|| p.file_stem()?.to_str().map(String::from))?
        })
        .collect();
    names.sort();
    assert_eq!(
        names,
        [
            "four_bar",
            "marghitu_slider_crank",
            "quick_return",
            "quick_return_frictionless",
            "slider_crank_engine",
            "slider_crank_engine_frictionless"
        ]
    );
}

/// The book's numbers (Marghitu, Mechanisms and Robots Analysis with
/// MATLAB, 2009, ch. 4, p. 144) and the closed forms the fixture records,
/// against qdot's row at φ = 45°.
#[test]
fn marghitus_printed_forces_are_reproduced() {
    let f = fixture("marghitu_slider_crank");
    let t = run_fixture(&f);
    let row = f.json["printed_row"].as_u64().expect("printed_row") as usize;
    assert!(close(
        t.rows[row].values[0].unwrap(),
        std::f64::consts::FRAC_PI_4
    ));
    let r2 = std::f64::consts::SQRT_2;
    // F12, printed: −¼(400 + 7√2) ı + 5/4(84 + √2) ȷ N
    let printed = [
        ("B_x", -(400.0 + 7.0 * r2) / 4.0),
        ("B_y", 5.0 / 4.0 * (84.0 + r2)),
    ];
    // the printed decimals too
    assert!((value(&t, row, "B_x") - -102.4749).abs() < 5e-5);
    assert!((value(&t, row, "B_y") - 106.7678).abs() < 5e-5);
    // α1 = α2 = 0 printed; the rest solved by hand from the free-body
    // diagrams (the fixture's `closed_forms`)
    let closed = [
        ("phi''", 0.0),
        ("th''", 0.0),
        ("th'", -1.0),
        ("xc'", -r2),
        ("xc''", -r2),
        ("A_x", -100.0 - 2.0 * r2),
        ("A_y", 115.0 + r2),
        ("C_x", -100.0 - r2),
        ("C_y", 95.0 + 1.5 * r2),
        ("T_n", -85.0 - 1.5 * r2),
        ("Me", 3.0 + 105.0 * r2),
    ];
    for (name, want) in printed.iter().chain(&closed) {
        let got = value(&t, row, name);
        assert!(close(*want, got), "{name}: qdot {got}, Marghitu {want}");
    }
    // and the printed values it records
    let agreement = f.json["agreement"].as_object().expect("agreement");
    assert_eq!(agreement.len(), 2);
    for (name, record) in agreement {
        let printed = record["printed_value"].as_f64().unwrap();
        let got = value(&t, row, name);
        assert!(close(printed, got), "{name}: qdot {got}, printed {printed}");
    }
    // the fixture records the same closed forms
    let forms = f.json["closed_forms"].as_object().expect("closed_forms");
    assert_eq!(forms["Me"], "3 + 105*sqrt(2) N m");
    assert_eq!(forms["T_n"], "-85 - 3*sqrt(2)/2 N");
    assert_eq!(forms["C_y"], "95 + 3*sqrt(2)/2 N");
    assert_eq!(forms["A_x"], "-100 - 2*sqrt(2) N");
}

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

/// The command line prints the fixture's rows: JSON (`columns`, `rows`,
/// `notes`) and CSV (every digit, a `note` column).
#[test]
fn the_cli_prints_the_reference_rows_as_json_and_csv() {
    let f = fixture("slider_crank_engine");
    let args = |output: &'static str| {
        vec![
            "cycle".to_string(),
            f.scene.clone(),
            "--over".into(),
            f.over.clone(),
            "--set".into(),
            f.set.clone(),
            "--guess".into(),
            f.guess.clone(),
            "--output".into(),
            output.into(),
        ]
    };
    let json_args = args("json");
    let (ok, out, err) = qdot(&json_args.iter().map(String::as_str).collect::<Vec<_>>());
    assert!(ok, "{err}");
    assert_eq!(err, "");
    let v: serde_json::Value = serde_json::from_str(&out).expect("JSON");
    assert_eq!(v["varied"], "phi");
    let columns: Vec<&str> = v["columns"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c.as_str().unwrap())
        .collect();
    assert_eq!(columns[..f.columns.len()], f.columns[..]);
    assert_eq!(columns[f.columns.len()..], ["O_f", "A_f", "G_f"]);
    let rows = v["rows"].as_array().unwrap();
    assert_eq!(rows.len(), f.rows.len());
    for (i, (want, got)) in f.rows.iter().zip(rows).enumerate() {
        assert!(v["notes"][i].is_null());
        assert!(
            v["iterations"][i].as_u64().unwrap() > 1,
            "friction iterates"
        );
        for (k, w) in want.iter().enumerate() {
            let g = got[k].as_f64().unwrap();
            assert!(close(*w, g), "json row {i} `{}`: {g} vs {w}", f.columns[k]);
        }
    }

    let csv_args = args("csv");
    let (ok, out, err) = qdot(&csv_args.iter().map(String::as_str).collect::<Vec<_>>());
    assert!(ok, "{err}");
    let mut lines = out.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    // the varied angle is also a coordinate: its column says `(varied)`
    assert_eq!(header[0], format!("{} (varied)", f.columns[0]));
    assert_eq!(header[1..f.columns.len()], f.columns[1..]);
    assert_eq!(header[f.columns.len()..], ["O_f", "A_f", "G_f", "note"]);
    let body: Vec<&str> = lines.collect();
    assert_eq!(body.len(), f.rows.len());
    for (i, (want, line)) in f.rows.iter().zip(&body).enumerate() {
        let cells: Vec<&str> = line.split(',').collect();
        assert_eq!(cells.len(), header.len());
        assert_eq!(*cells.last().unwrap(), "", "row {i} has no note");
        for (k, w) in want.iter().enumerate() {
            let g: f64 = cells[k].parse().unwrap();
            assert!(close(*w, g), "csv row {i} `{}`: {g} vs {w}", f.columns[k]);
        }
    }
}

// ---------------------------------------------------------------------
// Virtual work
// ---------------------------------------------------------------------

/// M·q̈ − f at a row, with M and f of `scene.lagrange()` evaluated at the
/// row's q, q̇ (the unconstrained bodies' equations: no reaction in them).
fn inertia_minus_forcing(scene: &Scene, set: &str, t: &CycleTable, row: usize) -> Vec<f64> {
    let lag = scene.lagrange().expect("Lagrange");
    let params: HashMap<String, f64> = qdot::output::parse_set_any_sign(set)
        .unwrap()
        .into_iter()
        .collect();
    let n = t.coordinates;
    let names: Vec<&str> = scene.coordinates.iter().map(|c| c.name.as_str()).collect();
    let at = |a: &Atom| -> Option<f64> {
        match a {
            Atom::Param(p) => params.get(&**p).copied(),
            Atom::Coord(c, k) if *k <= 2 => {
                let i = names.iter().position(|m| *m == &**c)?;
                t.rows[row].values[1 + *k as usize * n + i]
            }
            _ => None,
        }
    };
    let qdd: Vec<f64> = (0..n)
        .map(|i| t.rows[row].values[1 + 2 * n + i].unwrap())
        .collect();
    (0..n)
        .map(|i| {
            let m: f64 = (0..n)
                .map(|j| lag.mass_matrix[i][j].eval_f64(&at).expect("M") * qdd[j])
                .sum();
            m - lag.forcing[i].eval_f64(&at).expect("f")
        })
        .collect()
}

/// Σ_k (M·q̈ − f)_k·q̇_k: the power the drives must supply without
/// friction (the virtual work of the inertia and applied forces along the
/// actual velocity; every joint's reaction does no work).
fn ideal_power(scene: &Scene, set: &str, t: &CycleTable, row: usize) -> f64 {
    let n = t.coordinates;
    inertia_minus_forcing(scene, set, t, row)
        .iter()
        .enumerate()
        .map(|(k, r)| r * t.rows[row].values[1 + n + k].unwrap())
        .sum()
}

/// The 1-DOF driven fixtures without friction: drive·q̇_driven equals the
/// power from virtual work at every row.
#[test]
fn the_drives_couple_equals_the_one_from_virtual_work() {
    for (name, drive, driven) in [
        ("slider_crank_engine_frictionless", "M", "phi'"),
        ("four_bar", "M", "th2'"),
        ("quick_return_frictionless", "M", "th2'"),
        ("marghitu_slider_crank", "Me", "phi'"),
    ] {
        let f = fixture(name);
        let src = source(&f.scene);
        let scene = Scene::parse(&src).unwrap();
        let t = run_fixture(&f);
        let scale = (0..t.rows.len())
            .map(|r| value(&t, r, drive).abs())
            .fold(0.0, f64::max);
        for r in 0..t.rows.len() {
            let rate = value(&t, r, driven);
            let from_work = ideal_power(&scene, &f.set, &t, r) / rate;
            let got = value(&t, r, drive);
            assert!(
                (got - from_work).abs() <= 1e-10 * scale,
                "{name} row {r}: cycle {got}, virtual work {from_work}"
            );
        }
    }
}

/// With friction the drive supplies the ideal power plus what friction
/// dissipates: drive·φ̇ = Σ (M·q̈ − f)·q̇ − Σ F·v_rel, each F·v_rel ≤ 0
/// (friction only adds to the drive's work), and over the cycle the mean
/// drive is the friction's work per radian.
#[test]
fn friction_only_adds_to_the_drives_work() {
    // the relative velocities, written by hand from the scenes: the
    // engine's main bearing O turns with the crank, its crank pin A with
    // θ' − φ', its piston slides along x; the quick return's block slides
    // along the lever at the rate d/dt[Û·(Q − P)]
    type Relative = fn(&CycleTable, usize) -> Vec<(&'static str, f64)>;
    let engine: Relative = |t, r| {
        vec![
            ("O_f", value(t, r, "phi'")),
            ("A_f", value(t, r, "th'") - value(t, r, "phi'")),
            ("G_f", value(t, r, "xb'")),
        ]
    };
    let quick: Relative = |t, r| {
        let (th4, w4) = (value(t, r, "th4"), value(t, r, "th4'"));
        let c4 = 0.3;
        let u = [th4.cos(), th4.sin()];
        let n = [-u[1], u[0]];
        let p = [value(t, r, "x4") - c4 * u[0], value(t, r, "y4") - c4 * u[1]];
        let pd = [
            value(t, r, "x4'") + c4 * w4 * u[1],
            value(t, r, "y4'") - c4 * w4 * u[0],
        ];
        let q = [value(t, r, "xs"), value(t, r, "ys")];
        let qd = [value(t, r, "xs'"), value(t, r, "ys'")];
        let slide = w4 * (n[0] * (q[0] - p[0]) + n[1] * (q[1] - p[1]))
            + u[0] * (qd[0] - pd[0])
            + u[1] * (qd[1] - pd[1]);
        vec![("S_f", slide)]
    };
    for (name, free, relative, mean_friction) in [
        (
            "slider_crank_engine",
            "slider_crank_engine_frictionless",
            engine,
            0.40,
        ),
        ("quick_return", "quick_return_frictionless", quick, 2.99),
    ] {
        let f = fixture(name);
        let src = source(&f.scene);
        let scene = Scene::parse(&src).unwrap();
        let t = run_fixture(&f);
        let free = run_fixture(&fixture(free));
        let rate = value(
            &t,
            0,
            if name == "quick_return" {
                "th2'"
            } else {
                "phi'"
            },
        );
        let rows = t.rows.len() - 1; // the periodic grid
        let (mut mean, mut mean_free, mut mean_dissipated) = (0.0, 0.0, 0.0);
        for r in 0..rows {
            let drive = value(&t, r, "M");
            let dissipated: f64 = relative(&t, r)
                .iter()
                .map(|(col, v)| {
                    let power = value(&t, r, col) * v;
                    assert!(power < 0.0, "{name} row {r}: {col} does work {power}");
                    -power
                })
                .sum();
            let ideal = ideal_power(&scene, &f.set, &t, r);
            assert!(
                (drive * rate - (ideal + dissipated)).abs()
                    <= 1e-10 * (drive * rate).abs().max(1.0),
                "{name} row {r}: drive power {}, ideal {ideal} + friction {dissipated}",
                drive * rate
            );
            assert!(drive * rate > ideal, "{name} row {r}");
            mean += drive / rows as f64;
            mean_free += value(&free, r, "M") / rows as f64;
            mean_dissipated += dissipated / rate / rows as f64;
        }
        assert!(
            mean_free.abs() < 1e-9,
            "{name}: frictionless mean {mean_free}"
        );
        assert!(
            (mean - mean_dissipated).abs() < 1e-9,
            "{name}: mean drive {mean}, friction's work per radian {mean_dissipated}"
        );
        // the means the fixtures' README states (two digits)
        assert!((mean - mean_friction).abs() < 0.01, "{name}: mean {mean}");
    }
}

/// Without friction, at constant speed, the drive's work per cycle is the
/// change of T + V (none) minus the constant loads' work (none over a
/// closed cycle): its mean over a whole cycle is zero. The trapezoid rule
/// over a periodic grid is spectrally accurate.
#[test]
fn without_friction_the_drives_mean_over_a_cycle_is_zero() {
    for (name, drive, over) in [
        ("slider_crank_engine_frictionless", "M", "phi=0:360deg:361"),
        ("four_bar", "M", "th2=0:360deg:361"),
        ("quick_return_frictionless", "M", "th2=0:360deg:361"),
    ] {
        let f = fixture(name);
        let t = run_cycle(&source(&f.scene), &request(over, &f.set, &f.guess));
        let values: Vec<f64> = (0..t.rows.len()).map(|r| value(&t, r, drive)).collect();
        let periodic = &values[..values.len() - 1];
        let mean = periodic.iter().sum::<f64>() / periodic.len() as f64;
        let largest = values.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        assert!(largest > 1.0, "{name}: the drive works ({largest})");
        assert!(
            mean.abs() <= 1e-9 * largest,
            "{name}: mean {mean:e}, largest {largest}"
        );
        assert!(
            close(values[0], values[values.len() - 1]),
            "{name}: periodic"
        );
    }
}

// ---------------------------------------------------------------------
// Bad input
// ---------------------------------------------------------------------

/// A slider-crank: crank R about the origin, rod L, block on the x axis.
const SLIDER_CRANK: &str = "\
coordinates x1, y1, phi, x2, y2, th, xb, yb
parameters R: length, L: length, omega, m1, J1, m2, J2, m3, g
body crank: mass m1, inertia J1, angle phi, at [x1, y1]
body rod: mass m2, inertia J2, angle th, at [x2, y2]
particle block: mass m3, at [xb, yb]
gravity [0, -g]
joint O: pin ground at [0, 0], crank at [x1, y1] - R/2*[cos(phi), sin(phi)]
joint A: pin crank at [x1, y1] + R/2*[cos(phi), sin(phi)], rod at [x2, y2] - L/2*[cos(th), sin(th)]
joint B: pin rod at [x2, y2] + L/2*[cos(th), sin(th)], block at [xb, yb]
joint G: slider ground at [0, 0], block at [xb, yb] along [1, 0]
drive M: phi = omega*t
";
const SLIDER_CRANK_SET: &str = "R=0.1,L=0.3,omega=1,m1=1,J1=0.01,m2=1,J2=0.01,m3=1,g=9.81";
const SLIDER_CRANK_GUESS: &str = "x1=0.05,x2=0.25,xb=0.4";

/// `src` with the line starting `from` replaced by `to` (or `to`
/// appended when `from` is empty).
fn edit(src: &str, from: &str, to: &str) -> String {
    if from.is_empty() {
        return format!("{src}{to}\n");
    }
    let lines: Vec<String> = src
        .lines()
        .map(|l| {
            if l.starts_with(from) {
                to.to_string()
            } else {
                l.to_string()
            }
        })
        .collect();
    assert_ne!(lines.join("\n") + "\n", src, "`{from}` is in the scene");
    lines.join("\n") + "\n"
}

/// The error of `qdot cycle` on `src`: its message, and its place as
/// line:column when it has one; the rendered text shows the place with
/// a caret under the statement.
fn cycle_error(src: &str, over: &str, set: &str, guess: &str) -> (String, Option<(usize, usize)>) {
    let d: Diagnostic = match Scene::parse(src) {
        Err(d) => d,
        Ok(scene) => match cycle(&scene, &request(over, set, guess)) {
            Err(d) => d,
            Ok(t) => panic!("no error: {:?}", t.rows[0]),
        },
    };
    let place = d.span.map(|s| Diagnostic::line_col(src, s.start));
    let text = d.render("scene.qd", src);
    if let Some((line, column)) = place {
        assert!(
            text.contains(&format!("--> scene.qd:{line}:{column}\n")),
            "{text}"
        );
        let statement = src.lines().nth(line - 1).unwrap();
        assert!(text.contains(&format!("{line} | {statement}\n")), "{text}");
        assert!(text.contains(" | ") && text.contains('^'), "{text}");
    }
    assert!(d.hint.is_some(), "every error has a hint: {text}");
    (d.message, place)
}

fn slider_crank_error(src: &str) -> (String, Option<(usize, usize)>) {
    cycle_error(src, "phi=0:360deg:5", SLIDER_CRANK_SET, SLIDER_CRANK_GUESS)
}

#[test]
fn the_bad_input_scene_runs_as_written() {
    let t = run_cycle(
        SLIDER_CRANK,
        &request("phi=0:360deg:5", SLIDER_CRANK_SET, SLIDER_CRANK_GUESS),
    );
    assert!(t.rows.iter().all(|r| r.note.is_none()));
    assert!(close(value(&t, 2, "xb"), 0.2));
}

#[test]
fn a_four_bar_whose_links_cannot_close_names_the_open_joints() {
    let src = "\
coordinates x2, y2, th2, x3, y3, th3, x4, y4, th4
parameters a: length, b: length, c: length, d: length, omega, m, J
body crank: mass m, inertia J, angle th2, at [x2, y2]
body coupler: mass m, inertia J, angle th3, at [x3, y3]
body rocker: mass m, inertia J, angle th4, at [x4, y4]
joint O2: pin ground at [0, 0], crank at [x2, y2] - a/2*[cos(th2), sin(th2)]
joint A: pin crank at [x2, y2] + a/2*[cos(th2), sin(th2)], coupler at [x3, y3] - b/2*[cos(th3), sin(th3)]
joint B: pin coupler at [x3, y3] + b/2*[cos(th3), sin(th3)], rocker at [x4, y4] + c/2*[cos(th4), sin(th4)]
joint O4: pin ground at [d, 0], rocker at [x4, y4] - c/2*[cos(th4), sin(th4)]
drive M: th2 = omega*t
";
    let (message, place) = cycle_error(
        src,
        "th2=0:360deg:5",
        "a=0.05,b=0.02,c=0.02,d=0.18,omega=1,m=1,J=0.01",
        "x2=0.025,x3=0.06,th3=0.1,x4=0.17,th4=0.1",
    );
    assert_eq!(
        message,
        "the mechanism cannot be assembled at the first position (th2 = 0): the joint `O2`, the joint `A`, the joint `B` and the joint `O4` cannot all hold (the nearest assembly leaves them open by up to 2.250e-2)"
    );
    assert_eq!(place, Some((6, 1)));
}

#[test]
fn a_slider_crank_whose_rod_is_too_short_says_where_in_the_rows() {
    let t = run_cycle(
        SLIDER_CRANK,
        &request(
            "phi=0:90deg:3",
            "R=0.3,L=0.1,omega=1,m1=1,J1=0.01,m2=1,J2=0.01,m3=1,g=9.81",
            "x1=0.15,x2=0.35,xb=0.4",
        ),
    );
    assert_eq!(t.rows[0].note, None);
    for row in &t.rows[1..] {
        assert!(row.values[1..].iter().all(Option::is_none));
        let note = row.note.as_deref().unwrap();
        assert!(
            note.starts_with("the mechanism cannot be assembled here: the joint `O`, the joint `A`, the joint `B`")
                && note.contains(" cannot all hold (the nearest assembly leaves them open by up to "),
            "{note}"
        );
    }
}

#[test]
fn a_second_drive_on_a_coordinate_the_joints_fix_is_refused_at_it() {
    let src = edit(SLIDER_CRANK, "", "drive N: th = omega*t");
    let (message, place) = slider_crank_error(&src);
    assert_eq!(
        message,
        "the drive `N` prescribes `th`, which the joints and drives before it already determine (9 conditions on 8 coordinates)"
    );
    assert_eq!(place, Some((12, 1)));
}

#[test]
fn a_drive_on_a_coordinate_a_constraint_fixes_names_both() {
    // the slider G already keeps yb at 0: driving yb repeats it and
    // leaves the crank free
    let src = edit(SLIDER_CRANK, "drive M:", "drive D: yb = 0*t");
    let (message, place) = cycle_error(&src, "t=0:1:3", SLIDER_CRANK_SET, SLIDER_CRANK_GUESS);
    assert_eq!(
        message,
        "the joint `G` and the drive `D` impose one condition twice (their rows of the constraint Jacobian are dependent at and near the first position, t = 0), so they leave a motion of x1, y1, phi, x2, y2, th, xb free"
    );
    assert_eq!(place, Some((11, 1)));
    // the same with a `constraint` in place of the slider
    let src = edit(&src, "joint G:", "constraint c: yb = 0");
    let (message, place) = cycle_error(&src, "t=0:1:3", SLIDER_CRANK_SET, SLIDER_CRANK_GUESS);
    assert_eq!(
        message,
        "the constraint `c` and the drive `D` impose one condition twice (their rows of the constraint Jacobian are dependent at and near the first position, t = 0), so they leave a motion of x1, y1, phi, x2, y2, th, xb free"
    );
    assert_eq!(place, Some((11, 1)));
}

#[test]
fn a_friction_on_a_joint_that_does_not_exist() {
    let src = edit(SLIDER_CRANK, "", "friction Z: 0.1");
    let (message, place) = slider_crank_error(&src);
    assert_eq!(message, "there is no joint `Z`");
    assert_eq!(place, Some((12, 10)));
}

#[test]
fn a_joint_naming_an_unknown_body() {
    let src = edit(
        SLIDER_CRANK,
        "joint A:",
        "joint A: pin crunk at [x1, y1] + R/2*[cos(phi), sin(phi)], rod at [x2, y2] - L/2*[cos(th), sin(th)]",
    );
    let (message, place) = slider_crank_error(&src);
    assert_eq!(message, "`crunk` is not a body or a particle");
    assert_eq!(place, Some((8, 14)));
}

#[test]
fn a_pin_with_a_direction() {
    let src = edit(
        SLIDER_CRANK,
        "joint O:",
        "joint O: pin ground at [0, 0], crank at [x1, y1] - R/2*[cos(phi), sin(phi)] along [1, 0]",
    );
    let (message, place) = slider_crank_error(&src);
    assert_eq!(message, "a pin has no direction");
    assert_eq!(place, Some((7, 77)));
}

#[test]
fn a_slider_without_a_direction() {
    let src = edit(
        SLIDER_CRANK,
        "joint G:",
        "joint G: slider ground at [0, 0], block at [xb, yb]",
    );
    let (message, place) = slider_crank_error(&src);
    assert_eq!(
        message,
        "expected `along` and the slider's direction after the second body's point, but the line ends"
    );
    assert_eq!(place, Some((10, 52)));
}

#[test]
fn a_point_written_through_another_bodys_coordinates() {
    let src = edit(
        SLIDER_CRANK,
        "joint B:",
        "joint B: pin rod at [x1, y2] + L/2*[cos(th), sin(th)], block at [xb, yb]",
    );
    let (message, place) = slider_crank_error(&src);
    assert_eq!(
        message,
        "this point moves with `x1`, a coordinate that is not of `rod`, which moves with x2, y2, th"
    );
    assert_eq!(place, Some((9, 21)));
}

#[test]
fn a_drive_whose_law_moves_with_a_coordinate() {
    let src = edit(SLIDER_CRANK, "drive M:", "drive M: phi = omega*t + th");
    let (message, place) = slider_crank_error(&src);
    assert_eq!(
        message,
        "a drive's law depends on time only, and this moves with `th`"
    );
    assert_eq!(place, Some((11, 16)));
}

#[test]
fn bad_options_are_refused_with_the_names_to_use() {
    let (message, place) = cycle_error(
        SLIDER_CRANK,
        "th=0:1:3",
        SLIDER_CRANK_SET,
        SLIDER_CRANK_GUESS,
    );
    assert_eq!(message, "`--over th`: `th` is not a driven coordinate");
    assert_eq!(place, None);
    let (message, _) = cycle_error(SLIDER_CRANK, "phi=0:1:3", SLIDER_CRANK_SET, "zz=1");
    assert_eq!(message, "`--guess zz=…`: `zz` is not a coordinate");
    let (message, _) = cycle_error(SLIDER_CRANK, "phi=0:1:3", "R=0.1,L=0.3", SLIDER_CRANK_GUESS);
    assert_eq!(
        message,
        "no value for the parameters omega, m1, J1, m2, J2, m3, g"
    );
    let over = Over::parse("phi=0:360deg").unwrap_err();
    assert_eq!(
        over.message,
        "`--over phi=0:360deg`: 2 parts after `=`, and it takes 3 (FROM:TO:COUNT)"
    );
    let guess = parse_guess("th").unwrap_err();
    assert_eq!(guess.message, "`--guess th`: expected NAME=NUMBER");
}

// ---------------------------------------------------------------------
// Dead points and branches
// ---------------------------------------------------------------------

const BRANCH_CHANGED: &str = "the constraint Jacobian's determinant changed sign since the previous regular position: a dead point lies between them, and the assembly branch changed there";

/// The branch (assembly mode) of every regular row, by `branch`, never
/// changes without the row saying so; the list of the rows that say so.
fn assert_no_silent_branch_change(
    t: &CycleTable,
    branch: impl Fn(&CycleTable, usize) -> f64,
) -> Vec<usize> {
    let mut previous: Option<f64> = None;
    let mut changed = Vec::new();
    for r in 0..t.rows.len() {
        if t.rows[r].values[1 + t.coordinates].is_none() {
            continue;
        }
        let side = branch(t, r).signum();
        let said = t.rows[r].note.as_deref() == Some(BRANCH_CHANGED);
        if let Some(p) = previous {
            assert_eq!(
                p != side,
                said,
                "row {r}: branch {p} → {side}, note {:?}",
                t.rows[r].note
            );
        }
        if said {
            changed.push(r);
        }
        previous = Some(side);
    }
    changed
}

/// The slider-crank driven by its slider: xb = L + R·cos(t) passes the
/// toggle positions xb = L ∓ R, where the crank and the rod are in line.
fn slider_driven() -> String {
    let src = edit(SLIDER_CRANK, "drive M:", "drive D: xb = L + R*cos(omega*t)");
    edit(&src, "gravity", "")
}

/// The crank's side of the line of the slider: its branch.
fn crank_side(t: &CycleTable, r: usize) -> f64 {
    value(t, r, "phi").sin()
}

/// |φ| from the block's position (the cosine rule in the triangle O A B).
fn crank_angle(xb: f64) -> f64 {
    let (r, l) = (0.1f64, 0.3f64);
    ((xb * xb + r * r - l * l) / (2.0 * r * xb))
        .clamp(-1.0, 1.0)
        .acos()
}

#[test]
fn a_slider_driven_crank_at_its_toggle_positions_has_dead_points() {
    // t = π and 2π are on the grid: xb = L − R and L + R exactly
    let t = run_cycle(
        &slider_driven(),
        &request(
            "t=0.5pi:2.5pi:9",
            SLIDER_CRANK_SET,
            "phi=1.2,x1=0.02,y1=0.04,x2=0.2,y2=0.04,xb=0.3,th=-0.3",
        ),
    );
    let n = t.coordinates;
    for r in [2, 6] {
        let row = &t.rows[r];
        let note = row.note.as_deref().unwrap();
        assert!(
            note.starts_with("dead point: the constraint Jacobian is singular here (pivot ratio ")
                && note.ends_with("), so the velocities, accelerations and reactions are not determined, and the position only to about 1e-8 of its scale (Newton's method at a double root); the assembly branch after it is compared with the one before"),
            "{note}"
        );
        // the position is known, nothing after it
        assert!(row.values[1..=n].iter().all(Option::is_some));
        assert!(
            row.values[n + 1..].iter().all(Option::is_none),
            "{:?}",
            row.values
        );
        let phi = value(&t, r, "phi");
        assert!(
            (phi.cos() - if r == 2 { -1.0 } else { 1.0 }).abs() < 1e-12,
            "{phi}"
        );
    }
    // every regular row is an assembly of the slider's position, on the
    // side the row's branch says
    for r in [0, 1, 3, 4, 5, 7, 8] {
        assert_eq!(t.rows[r].note.is_some(), r == 3 || r == 7, "row {r}");
        let xb = value(&t, r, "xb");
        let phi = value(&t, r, "phi");
        let want = crank_angle(xb) * crank_side(&t, r).signum();
        let wrapped = (phi - want + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU)
            - std::f64::consts::PI;
        assert!(wrapped.abs() < 1e-9, "row {r}: φ {phi}, by hand {want}");
    }
    // the crank turns on through each toggle: its side changes, and the
    // row after says so
    assert_eq!(assert_no_silent_branch_change(&t, crank_side), [3, 7]);
}

#[test]
fn a_toggle_between_two_rows_is_said_on_the_row_after_it() {
    let t = run_cycle(
        &slider_driven(),
        &request(
            "t=0.2:6:30",
            SLIDER_CRANK_SET,
            "phi=0.2,x1=0.05,x2=0.25,xb=0.39",
        ),
    );
    assert!(t.rows.iter().all(|r| r.values.iter().all(Option::is_some)));
    assert_eq!(assert_no_silent_branch_change(&t, crank_side), [15]);
}

/// A four-bar of links a (crank O2A), b (coupler AB), c (rocker O4B) on
/// the ground d, without loads.
const FOUR_BAR: &str = "\
coordinates x2, y2, th2, x3, y3, th3, x4, y4, th4
parameters a: length, b: length, c: length, d: length, omega, m, J
body crank: mass m, inertia J, angle th2, at [x2, y2]
body coupler: mass m, inertia J, angle th3, at [x3, y3]
body rocker: mass m, inertia J, angle th4, at [x4, y4]
joint O2: pin ground at [0, 0], crank at [x2, y2] - a/2*[cos(th2), sin(th2)]
joint A: pin crank at [x2, y2] + a/2*[cos(th2), sin(th2)], coupler at [x3, y3] - b/2*[cos(th3), sin(th3)]
joint B: pin coupler at [x3, y3] + b/2*[cos(th3), sin(th3)], rocker at [x4, y4] + c/2*[cos(th4), sin(th4)]
joint O4: pin ground at [d, 0], rocker at [x4, y4] - c/2*[cos(th4), sin(th4)]
drive M: th2 = omega*t
";

/// The pins A and B of a row.
fn pins(t: &CycleTable, r: usize, a: f64, b: f64) -> ([f64; 2], [f64; 2]) {
    let (th2, th3) = (value(t, r, "th2"), value(t, r, "th3"));
    let pa = [
        value(t, r, "x2") + a / 2.0 * th2.cos(),
        value(t, r, "y2") + a / 2.0 * th2.sin(),
    ];
    let pb = [pa[0] + b * th3.cos(), pa[1] + b * th3.sin()];
    (pa, pb)
}

fn cross(o: [f64; 2], p: [f64; 2], q: [f64; 2]) -> f64 {
    (p[0] - o[0]) * (q[1] - o[1]) - (p[1] - o[1]) * (q[0] - o[0])
}

/// A Grashof crank-rocker (a = 0.05, b = 0.2, c = 0.12, d = 0.18) driven
/// by its rocker: the rocker reaches only 68.7°–124.2°, where crank and
/// coupler fall in line; past it no assembly; and back inside the range
/// the crank stays on its side of the line O2B (the branch), or the row
/// says it changed.
#[test]
fn a_crank_rocker_driven_by_its_rocker_past_its_limit() {
    let (a, b) = (0.05, 0.2);
    let set = "a=0.05,b=0.2,c=0.12,d=0.18,omega=1,m=1,J=0.01";
    let guess = "th2=0.5,x2=0.02,y2=0.01,x3=0.1,y3=0.08,th3=0.6,x4=0.2,y4=0.05,th4=1.4";
    let rocker = edit(FOUR_BAR, "drive M:", "drive M: th4 = omega*t");
    let t = run_cycle(&rocker, &request("th4=80deg:130deg:11", set, guess));
    for r in 0..9 {
        assert_eq!(t.rows[r].note, None, "row {r}");
        let (pa, pb) = pins(&t, r, a, b);
        assert!((pa[0].hypot(pa[1]) - a).abs() < 1e-12);
        let rocker_tip = [
            0.18 + 0.12 * value(&t, r, "th4").cos(),
            0.12 * value(&t, r, "th4").sin(),
        ];
        assert!((pb[0] - rocker_tip[0]).hypot(pb[1] - rocker_tip[1]) < 1e-12);
    }
    for r in 9..11 {
        let note = t.rows[r].note.as_deref().unwrap();
        assert!(
            note.starts_with("the mechanism cannot be assembled here: the joint `O2`, the joint `A`, the joint `B`")
                && note.contains(" cannot all hold (the nearest assembly leaves them open by up to "),
            "{note}"
        );
        assert!(t.rows[r].values[1..].iter().all(Option::is_none));
    }
    // swung past the limit and back
    let swinging = edit(
        FOUR_BAR,
        "drive M:",
        "drive M: th4 = 1.7 + 0.5*sin(omega*t)",
    );
    let t = run_cycle(&swinging, &request("t=0:2pi:25", set, guess));
    let missing: Vec<usize> = (0..25).filter(|&r| t.rows[r].values[1].is_none()).collect();
    assert_eq!(missing, [5, 6, 7]);
    let side = |t: &CycleTable, r: usize| {
        let (pa, pb) = pins(t, r, a, b);
        cross([0.0, 0.0], pb, pa)
    };
    let changed = assert_no_silent_branch_change(&t, side);
    assert_eq!(changed, Vec::<usize>::new());
    // the angles stay near the guess's turn (no jump by whole turns)
    assert!((value(&t, 0, "th2") - -0.759714).abs() < 1e-5);
}

/// A non-Grashof four-bar (a = 0.15, b = 0.1, c = 0.12, d = 0.18) driven
/// by its crank: the crank reaches only |θ2| < 83.1°; the rows beyond say
/// the mechanism cannot be assembled, and the rows after come back on a
/// branch compared with the one before, by hand.
#[test]
fn a_non_grashof_crank_driven_past_its_limit() {
    let (a, b, c, d) = (0.15, 0.1, 0.12, 0.18);
    let t = run_cycle(
        FOUR_BAR,
        &request(
            "th2=0:360deg:25",
            "a=0.15,b=0.1,c=0.12,d=0.18,omega=1,m=1,J=0.01",
            "th2=0,x2=0.075,x3=0.19,y3=0.05,th3=1.2,x4=0.2,y4=0.05,th4=1.8",
        ),
    );
    let missing: Vec<usize> = (0..25).filter(|&r| t.rows[r].values[1].is_none()).collect();
    assert_eq!(missing, (6..19).collect::<Vec<_>>());
    // the branch: B's side of the line from A to O4, and the coupler's
    // angle on it by hand (the two circles about A and O4)
    let side = |t: &CycleTable, r: usize| {
        let (pa, pb) = pins(t, r, a, b);
        cross(pa, [d, 0.0], pb)
    };
    for r in (0..25).filter(|r| !missing.contains(r)) {
        let th2 = value(&t, r, "th2");
        let pa = [a * th2.cos(), a * th2.sin()];
        let v = [d - pa[0], -pa[1]];
        let dist = v[0].hypot(v[1]);
        let u = [v[0] / dist, v[1] / dist];
        let along = (b * b - c * c + dist * dist) / (2.0 * dist);
        let h = (b * b - along * along).sqrt() * side(&t, r).signum();
        let want = (along * u[1] + h * u[0]).atan2(along * u[0] - h * u[1]);
        let th3 = value(&t, r, "th3");
        let wrapped = (th3 - want + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU)
            - std::f64::consts::PI;
        assert!(wrapped.abs() < 1e-9, "row {r}: θ3 {th3}, by hand {want}");
    }
    assert_eq!(
        assert_no_silent_branch_change(&t, side),
        Vec::<usize>::new()
    );
    assert!(side(&t, 0) > 0.0 && side(&t, 19) > 0.0);
    // the cycle closes where it started
    for name in ["th3", "th4"] {
        assert!(close(value(&t, 0, name), value(&t, 24, name)), "{name}");
    }
}

// ---------------------------------------------------------------------
// Stick
// ---------------------------------------------------------------------

/// The engine with friction in its wrist pin B too, whose relative
/// rotation −θ' vanishes at φ = 90° and 270° (rows 18 and 54): there the
/// friction's sense is undefined, the row says so and gives the
/// reactions at both limits of sliding, where the couple is ∓μ₀·r₀·|B|;
/// with a coefficient of 0 there is no friction and no stick.
#[test]
fn a_friction_at_rest_gives_both_limits_unless_its_coefficient_is_zero() {
    let f = fixture("slider_crank_engine");
    let src = edit(&source(&f.scene), "", "friction B: mu0*r0");
    let t = run_cycle(&src, &request(&f.over, &f.set, &f.guess));
    let first_force = col(&t, "O_x");
    let (bx, by, bf) = (col(&t, "B_x"), col(&t, "B_y"), col(&t, "B_f"));
    for (r, row) in t.rows.iter().enumerate() {
        if r == 18 || r == 54 {
            let note = row.note.as_deref().unwrap();
            assert!(
                note.starts_with("stick: the relative velocity in the joint `B` vanishes here (")
                    && note.ends_with("), so its friction may be anywhere between its values for sliding either way: the reactions are given at both, the limits v → 0⁻ and v → 0⁺"),
                "{note}"
            );
            // the motion is known, the forces only at the two limits
            assert!(row.values[..first_force].iter().all(Option::is_some));
            assert!(row.values[first_force..].iter().all(Option::is_none));
            let l = row.limits.as_deref().unwrap();
            assert_eq!(l.joint, "B");
            for (side, sense) in [(&l.minus, -1.0), (&l.plus, 1.0)] {
                assert_eq!(side[..first_force], row.values[..first_force]);
                let v = |k: usize| side[k].unwrap();
                // −μ₀·r₀·|B|·sgn ω_rel with mu0 = 0.05, r0 = 0.01
                let want = -0.05 * 0.01 * v(bx).hypot(v(by)) * sense;
                assert!(close(v(bf), want), "row {r}: {} against {want}", v(bf));
            }
            assert!(l.minus[bf].unwrap() > 0.0 && l.plus[bf].unwrap() < 0.0);
        } else {
            assert_eq!(row.note, None, "row {r}");
            assert!(row.limits.is_none());
        }
    }
    let free = fixture("slider_crank_engine_frictionless");
    let t = run_cycle(&src, &request(&free.over, &free.set, &free.guess));
    for (want, got) in free.rows.iter().zip(&t.rows) {
        assert_eq!(got.note, None);
        for (k, w) in want.iter().enumerate() {
            assert!(close(*w, got.values[k].unwrap()), "`{}`", free.columns[k]);
        }
        assert_eq!(got.values[col(&t, "B_f")], Some(0.0));
    }
}

/// Started exactly at a toggle (the guess too: every y and angle 0, so
/// the Jacobian is exactly singular at Newton's start), the first row is
/// a dead point and the next ones are assembled all the same.
#[test]
fn a_cycle_started_at_a_toggle_position() {
    let t = run_cycle(
        &slider_driven(),
        &request("t=0:2pi:5", SLIDER_CRANK_SET, SLIDER_CRANK_GUESS),
    );
    let dead: Vec<usize> = (0..5)
        .filter(|&r| {
            t.rows[r]
                .note
                .as_deref()
                .is_some_and(|n| n.starts_with("dead point: "))
        })
        .collect();
    assert_eq!(dead, [0, 2, 4]);
    for r in [1, 3] {
        assert!(close(value(&t, r, "xb"), 0.3), "row {r}");
        let want = crank_angle(0.3) * crank_side(&t, r).signum();
        let phi = value(&t, r, "phi");
        let wrapped = (phi - want + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU)
            - std::f64::consts::PI;
        assert!(wrapped.abs() < 1e-9, "row {r}: φ {phi}, by hand {want}");
    }
    assert_eq!(assert_no_silent_branch_change(&t, crank_side), [3]);
}
