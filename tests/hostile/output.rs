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
        let widest = o.stdout.lines().map(|l| l.chars().count()).max().unwrap_or(0);
        assert!(widest > 65_535, "{cmd}: widest line {widest}");
    }
    // the mass matrix is one entry, its terms in name order: `[ m₀ + m₁ + m₁₀ + … ]`
    let o = qdot_scene("wide", src.as_bytes(), "derive", &[]);
    let row = o
        .stdout
        .lines()
        .find(|l| l.starts_with("  [ "))
        .expect("the matrix row");
    assert!(row.starts_with("  [ m₀ + m₁ + m₁₀ + m₁₀₀ + m₁₀₀₀ + "), "{}", &row[..60]);
    assert!(row.ends_with(" + m₉₉₈ + m₉₉₉ ]"), "{}", &row[row.len() - 60..]);
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
