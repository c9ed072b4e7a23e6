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
        env!("CARGO_MANIFEST_DIR")
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
    let path = format!("{}/{path}", env!("CARGO_MANIFEST_DIR"));
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
    assert_eq!(t.columns[..f.columns.len()], f.columns[..], "{name}: columns");
    for extra in &t.columns[f.columns.len()..] {
        assert!(extra.ends_with("_f"), "{name}: unexpected column `{extra}`");
    }
    assert_eq!(t.rows.len(), f.rows.len(), "{name}: rows");
    let mut worst = 0.0f64;
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
            worst = worst.max((w - g).abs() / w.abs().max(1.0));
        }
    }
    assert!(worst > 0.0 || name.is_empty(), "{name}: the comparison ran");
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
    let dir = format!("{}/tests/fixtures/mechanisms", env!("CARGO_MANIFEST_DIR"));
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
    assert!(close(t.rows[row].values[0].unwrap(), std::f64::consts::FRAC_PI_4));
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
        .current_dir(env!("CARGO_MANIFEST_DIR"))
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
        assert!(v["iterations"][i].as_u64().unwrap() > 1, "friction iterates");
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
    assert_eq!(header[..f.columns.len()], f.columns[..]);
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
        let p = [
            value(t, r, "x4") - c4 * u[0],
            value(t, r, "y4") - c4 * u[1],
        ];
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
        let rate = value(&t, 0, if name == "quick_return" { "th2'" } else { "phi'" });
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
                (drive * rate - (ideal + dissipated)).abs() <= 1e-10 * (drive * rate).abs().max(1.0),
                "{name} row {r}: drive power {}, ideal {ideal} + friction {dissipated}",
                drive * rate
            );
            assert!(drive * rate > ideal, "{name} row {r}");
            mean += drive / rows as f64;
            mean_free += value(&free, r, "M") / rows as f64;
            mean_dissipated += dissipated / rate / rows as f64;
        }
        assert!(mean_free.abs() < 1e-9, "{name}: frictionless mean {mean_free}");
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
        assert!(close(values[0], values[values.len() - 1]), "{name}: periodic");
    }
}

#[allow(dead_code)]
fn rendered(d: &Diagnostic, src: &str) -> String {
    d.render("scene.qd", src)
}
