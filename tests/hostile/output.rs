//! Hostile inputs for the printers and the simulator: text wider than
//! `format!` can pad, names of 65,536 characters, simulation runs whose
//! values overflow, and out-of-range options.

use crate::bound::*;

/// A scene whose mass-matrix entry (and forcing) print wider than 65,535
/// characters: the sum of `n` parameters (in definitions of 500 terms, as
/// one expression may be at most 1,000 levels deep).
fn wide_scene(n: usize, wide_mass: bool) -> String {
    let names: Vec<String> = (0..n).map(|i| format!("m{i}")).collect();
    let mut src = format!("coordinates x\nparameters k, {}\n", names.join(", "));
    let parts: Vec<String> = names
        .chunks(500)
        .enumerate()
        .map(|(j, c)| {
            src.push_str(&format!("s{j} = {}\n", c.join(" + ")));
            format!("s{j}")
        })
        .collect();
    let total = parts.join(" + ");
    let mass = if wide_mass { total.as_str() } else { "k" };
    src.push_str(&format!(
        "kinetic E = 1/2*({mass})*x'^2\npotential V = 1/2*k*x^2 - ({total})*x\n"
    ));
    src
}

#[test]
fn a_matrix_entry_wider_than_65535_characters_prints() {
    let src = wide_scene(9000, true);
    // solve divides by the mass: a wide forcing over a short mass there
    let short_mass = wide_scene(9000, false);
    for (cmd, src) in [("derive", &src), ("solve", &short_mass), ("forces", &src)] {
        let o = qdot_scene("wide", src.as_bytes(), cmd, &[]);
        o.assert_clean();
        assert_eq!(o.code, Some(0), "{cmd}: {o:?}");
        let widest = o
            .stdout
            .lines()
            .map(|l| l.chars().count())
            .max()
            .unwrap_or(0);
        assert!(widest > 65_535, "{cmd}: widest line {widest}");
    }
    // the mass matrix is one entry, its terms in name order: `[ m₀ + m₁ + m₁₀ + … ]`
    let o = qdot_scene("wide", src.as_bytes(), "derive", &[]);
    let row = o
        .stdout
        .lines()
        .find(|l| l.starts_with("  [ "))
        .expect("the matrix row");
    assert!(
        row.starts_with("  [ m₀ + m₁ + m₁₀ + m₁₀₀ + m₁₀₀₀ + "),
        "{}",
        &row[..60]
    );
    assert!(
        row.ends_with(" + m₉₉₈ + m₉₉₉ ]"),
        "{}",
        &row[row.len() - 60..]
    );
}

#[test]
fn the_repl_prints_a_wide_matrix() {
    let mut input = String::new();
    for line in wide_scene(9000, true).lines() {
        input.push_str(line);
        input.push('\n');
    }
    input.push_str(":equations\n");
    let o = qdot_bounded(&["repl"], &input, SECONDS, MEMORY_MIB);
    o.assert_clean();
    assert_eq!(o.code, Some(0), "{o:?}");
    assert!(o.stdout.contains(" + m₉₉₈ + m₉₉₉ ]"), "{o:?}");
}

#[test]
fn a_coordinate_name_of_65536_characters_prints() {
    let name = "q".repeat(65_536);
    let src = format!("coordinates {name}\nparameters m, k\nkinetic E = 1/2*m*{name}'^2\npotential V = 1/2*k*{name}^2\n");
    for cmd in ["derive", "solve", "forces"] {
        let o = qdot_scene("longname", src.as_bytes(), cmd, &[]);
        o.assert_clean();
        assert_eq!(o.code, Some(0), "{cmd}: {o:?}");
    }
    let o = qdot_scene("longname", src.as_bytes(), "solve", &[]);
    assert!(
        o.stdout.contains(&format!("  {name}′′ = −k/m·{name}\n")),
        "{o:?}"
    );
}

const PENDULUM: &str = "examples/pendulum.qd";

fn simulate(args: &[&str]) -> Outcome {
    let mut all = vec!["simulate", PENDULUM];
    all.extend_from_slice(args);
    qdot_bounded(&all, "", SECONDS, MEMORY_MIB)
}

/// A NaN or ∞ in any column (here the energy, with l = 1e308) ends the
/// run: status "not finite", exit status 3, no row with a null.
#[test]
fn a_value_that_is_not_finite_ends_the_run() {
    let o = simulate(&[
        "--set",
        "m=1,g=9.81,l=1e308",
        "--init",
        "theta=0.5,theta'=0",
        "--t-end",
        "1",
        "--points",
        "3",
        "--output",
        "json",
    ]);
    o.assert_clean();
    assert_eq!(o.code, Some(3), "{o:?}");
    assert!(o.stdout.starts_with("{\"method\":\"dop853\",\"status\":\"not finite\",\"columns\":[\"t\",\"theta\",\"theta'\",\"energy\"],\"rows\":[]"), "{o:?}");
    let rows =
        &o.stdout[o.stdout.find("\"rows\"").unwrap_or(0)..o.stdout.find("\"stats\"").unwrap_or(0)];
    assert!(!rows.contains("null"), "{o:?}");
    // under --output json the error is a JSON object
    assert_eq!(
        o.stderr,
        "{\"error\":{\"kind\":\"integration\",\"data\":{},\"message\":\"the integration stopped early: not finite at t = 0.000000e0\",\"line\":null,\"column\":null,\
         \"hint\":\"`energy` is NaN there: a function outside its domain (√ or ln of a negative number, asin or acos past ±1), 0/0, ∞·0 or ∞ − ∞; the rows before it are printed\",\"labels\":[]}}\n"
    );
}

#[test]
fn the_number_of_points_is_bounded() {
    for (points, shown) in [("0", "0"), ("1", "1"), ("37179586", "37179586")] {
        let o = simulate(&[
            "--set",
            "m=1,g=1,l=1",
            "--init",
            "theta=0.5,theta'=0",
            "--t-end",
            "1",
            "--points",
            points,
        ]);
        o.assert_clean();
        assert_eq!(o.code, Some(1), "{o:?}");
        assert!(o.stdout.is_empty(), "{o:?}");
        assert!(
            o.stderr.starts_with(&format!(
                "error: --points {shown} must be from 2 to 1000000\n"
            )),
            "{o:?}"
        );
    }
}

/// Every method refuses a step that is not positive.
#[test]
fn a_negative_or_zero_step_is_refused_by_every_method() {
    for method in ["rk4", "dopri5", "dop853", "vern7", "gauss6", "radau5"] {
        for dt in ["-0.1", "0", "-1e-300"] {
            let o = simulate(&[
                "--set",
                "m=1,g=1,l=1",
                "--init",
                "theta=0.5,theta'=0",
                "--t-end",
                "1",
                "--method",
                method,
                &format!("--dt={dt}"),
            ]);
            o.assert_clean();
            assert_eq!(o.code, Some(1), "{method} {dt}: {o:?}");
            let dt_shown: f64 = dt.parse().expect("a number");
            assert!(
                o.stderr.starts_with(&format!(
                    "error: --dt {dt_shown} must be a positive number\n"
                )),
                "{method} {dt}: {o:?}"
            );
        }
    }
}

/// "too many steps" reports where the run stopped (not the last output
/// time), exits with 3, and prints the rows before the stop.
#[test]
fn too_many_steps_says_where_and_exits_with_3() {
    let o = simulate(&[
        "--set",
        "m=1,g=1,l=1",
        "--init",
        "theta=0.5,theta'=0",
        "--t-end",
        "1e17",
        "--max-steps",
        "1000",
    ]);
    o.assert_clean();
    assert_eq!(o.code, Some(3), "{o:?}");
    let first = o.stderr.lines().next().unwrap_or("");
    let t: f64 = first
        .strip_prefix("error: the integration stopped early: too many steps at t = ")
        .and_then(|x| x.parse().ok())
        .unwrap_or_else(|| panic!("{o:?}"));
    assert!(t > 100.0 && t < 1e6, "{t}");
    assert!(
        o.stderr.contains("hint: raise --max-steps (it is 1000)"),
        "{o:?}"
    );
    // the row at t = 0 only: the next output time is 1e15
    assert_eq!(o.stdout.lines().count(), 2, "{o:?}");
}

#[test]
fn tolerances_a_double_cannot_meet_are_refused() {
    let o = simulate(&[
        "--set",
        "m=1,g=1,l=1",
        "--init",
        "theta=1,theta'=0",
        "--t-end",
        "10",
        "--rtol",
        "0",
        "--atol",
        "1e-42",
    ]);
    o.assert_clean();
    assert_eq!(o.code, Some(1), "{o:?}");
    assert!(o.stderr.starts_with("error: --rtol 0 is below what a double can meet (2.220446049250313e-15, ten units in the last place)\n"), "{o:?}");
}

/// The caret's indent copies the line's tabs, so it stays under its column
/// whatever the tab stops.
#[test]
fn the_caret_stays_under_its_column_after_tabs() {
    let o = qdot_scene(
        "tabs",
        b"coordinates x\n\tparameters m\nkinetic E = 1/2*m*x'^2\t+ \tbogus\n",
        "solve",
        &[],
    );
    o.assert_clean();
    assert!(
        o.stderr.starts_with("error: unknown name `bogus`\n --> scene.qd:3:27\n  |\n3 | kinetic E = 1/2*m*x'^2\t+ \tbogus\n  |                       \t  \t^^^^^\n"),
        "{o:?}"
    );
}

/// The fuzzer's finding: a LaTeX name with a backslash before a non-ASCII
/// character (`"\é"`), or `^` before one, panicked while measuring the
/// width of a line (a byte slice inside the character). The equations
/// print, with the name as written.
#[test]
fn a_latex_name_with_a_multibyte_character_after_a_backslash_prints() {
    for name in [r"\éll", r"\ell^é", "é^é"] {
        let src = format!(
            "coordinates theta\nparameters m, g, l\nlatex l = \"{name}\"\nkinetic E = 1/2*m*l^2*theta'^2\npotential V = -m*g*l*cos(theta)\n"
        );
        let o = qdot_scene("latex_multibyte", src.as_bytes(), "latex", &["--steps"]);
        o.assert_clean();
        assert_eq!(o.code, Some(0), "{name}: {o:?}");
        assert!(o.stdout.contains(name), "{name}: {o:?}");
    }
}
