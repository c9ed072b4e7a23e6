//! Hostile inputs for the exact engine's work: expressions that explode.
//! Each stops with the work budget's error (naming the statement or the
//! phase, positioned at a definition) within its time and memory bounds,
//! and `--max-terms` raises the budget.

use crate::bound::*;

/// `qdot COMMAND` on `src` within `seconds` and 2 GiB: it must end with
/// status 1 and an error starting with `message`.
fn stops(tag: &str, src: &str, command: &str, seconds: u64, message: &str) -> Outcome {
    let dir = std::env::temp_dir().join(format!("qdot-hostile-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temporary directory");
    let path = dir.join(format!("{tag}.qd"));
    std::fs::write(&path, src).expect("scene written");
    let p = path.to_str().expect("utf-8 path").to_string();
    let mut o = qdot_bounded(&[command, &p], "", seconds, 2048);
    o.stderr = o.stderr.replace(&p, "scene.qd");
    o.assert_clean();
    assert_eq!(o.code, Some(1), "{tag}: {o:?}");
    assert!(o.stderr.starts_with(message), "{tag}: {o:?}");
    assert!(
        o.stderr
            .contains("hint: exact expressions this large are rarely what a scene means"),
        "{tag}: {o:?}"
    );
    o
}

#[test]
fn a_sum_to_the_power_200() {
    let src = "coordinates x\nparameters m, a, b, c, d\nkinetic E = 1/2*m*x'^2\npotential V = (a+b+c+d)^200*x^2\n";
    stops(
        "power200",
        src,
        "solve",
        SECONDS,
        "error: expression too large: a product of 6,545 by 6,545 terms while evaluating `V` (the limit is 2,000,000 terms, and 16,000,000 term products)\n --> scene.qd:4:15\n",
    );
}

#[test]
fn repeated_squaring_through_definitions() {
    let mut src = String::from("coordinates x\nparameters m, y\na1 = (x+y+1)^2\n");
    for i in 2..=30 {
        src.push_str(&format!("a{i} = a{}^2\n", i - 1));
    }
    src.push_str("kinetic E = 1/2*m*x'^2\npotential V = a30\n");
    stops(
        "squaring",
        &src,
        "solve",
        SECONDS,
        "error: expression too large: a product of 8,385 by 8,385 terms while evaluating `a8` (the limit is 2,000,000 terms, and 16,000,000 term products)\n  --> scene.qd:10:6\n",
    );
}

#[test]
fn a_product_of_thirty_sums() {
    let ps: Vec<String> = (0..30).map(|i| format!("p{i}")).collect();
    let product: Vec<String> = ps.iter().map(|p| format!("(x+{p})")).collect();
    let src = format!(
        "coordinates x\nparameters m, {}\nV0 = {}\nkinetic E = 1/2*m*x'^2\npotential V = V0\n",
        ps.join(", "),
        product.join("*")
    );
    stops(
        "primes",
        &src,
        "solve",
        SECONDS,
        "error: expression too large: ",
    );
}

#[test]
fn a_ten_by_ten_symbolic_system() {
    let n = 10;
    let mut ps = Vec::new();
    for i in 0..n {
        for j in 0..n {
            ps.push(format!("a{i}_{j}"));
        }
        ps.push(format!("b{i}"));
    }
    let us: Vec<String> = (0..n).map(|i| format!("u{i}")).collect();
    let mut src = format!("parameters {}\nsolve {} {{\n", ps.join(", "), us.join(", "));
    for i in 0..n {
        let row: Vec<String> = (0..n).map(|j| format!("a{i}_{j}*u{j}")).collect();
        src.push_str(&format!("  {} = b{i}\n", row.join(" + ")));
    }
    src.push_str("}\n");
    stops(
        "system10",
        &src,
        "solve",
        SECONDS,
        "error: expression too large: 132,479,104 term products in all while solving the `solve` blocks (the limit is 2,000,000 terms, and 128,000,000 term products in all)",
    );
}

/// The n-link pendulum chain in absolute angles.
fn chain(n: usize) -> String {
    let names: Vec<String> = (1..=n).map(|i| format!("th{i}")).collect();
    let mut src = format!("coordinates {}\nparameters m, l, g\n", names.join(", "));
    let (mut x, mut y) = (String::from("0"), String::from("0"));
    for i in 1..=n {
        x.push_str(&format!(" + l*sin(th{i})"));
        y.push_str(&format!(" - l*cos(th{i})"));
        src.push_str(&format!(
            "x{i} = {x}\ny{i} = {y}\nkinetic T{i} = 1/2*m*(x{i}'^2 + y{i}'^2)\npotential V{i} = m*g*y{i}\n"
        ));
    }
    src
}

/// Eliminating with sin² + cos² = 1 built in (the exponential basis) keeps
/// the 8-link chain's accelerations within the budget: solved, exactly.
#[test]
fn an_eight_link_pendulum_is_solved_exactly() {
    let dir = std::env::temp_dir().join(format!("qdot-hostile-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temporary directory");
    let path = dir.join("chain8.qd");
    std::fs::write(&path, chain(8)).expect("scene written");
    let o = qdot_bounded(
        &["solve", path.to_str().expect("utf-8 path")],
        "",
        SECONDS,
        2048,
    );
    o.assert_clean();
    assert_eq!(o.code, Some(0), "chain8: {o:?}");
    assert!(o.stdout.contains("\n  θ̈₈ = "), "chain8: {o:?}");
}

/// The 12-link chain's elimination takes more term products in all than the
/// budget allows, each product small: it stops within seconds, not minutes.
#[test]
fn a_twelve_link_pendulum_stops_at_the_elimination_budget() {
    stops(
        "chain12",
        &chain(12),
        "solve",
        SECONDS,
        "error: expression too large: 131,080,740 term products in all while solving M·q̈ = f for the accelerations (the limit is 2,000,000 terms, and 128,000,000 term products in all)",
    );
}

#[test]
fn the_equilibria_of_a_nested_sine() {
    let mut e = String::from("x");
    for _ in 0..22 {
        e = format!("sin({e})");
    }
    let src =
        format!("coordinates x\nparameters m, k\nkinetic E = 1/2*m*x'^2\npotential V = k*{e}\n");
    stops(
        "nested_sin",
        &src,
        "equilibrium",
        SECONDS,
        "error: expression too large: 2,000,001 terms while finding the equilibria (the limit is 2,000,000)\n",
    );
}

/// `--max-terms` lowers and raises the budget; the REPL's `:max-terms` too,
/// and the session goes on after the error.
#[test]
fn max_terms_moves_the_limit() {
    let src = b"coordinates x\nparameters m, a, b, c\nkinetic E = 1/2*m*x'^2\npotential V = (a+b+c)^12*x^2\n";
    let o = qdot_scene("max_terms_low", src, "solve", &["--max-terms", "50"]);
    o.assert_clean();
    assert_eq!(o.code, Some(1), "{o:?}");
    assert!(
        o.stderr.starts_with("error: expression too large: "),
        "{o:?}"
    );
    assert!(o.stderr.contains("(the limit is 50"), "{o:?}");
    assert!(o.stderr.contains("--max-terms 500"), "{o:?}");
    let o = qdot_scene("max_terms_high", src, "solve", &["--max-terms", "1000"]);
    o.assert_clean();
    assert_eq!(o.code, Some(0), "{o:?}");
    assert!(o.stdout.contains("x\u{308} = −2·(132·a·b·c¹⁰ + "), "{o:?}");
    // the REPL: the budget error, then the session answers
    let o = qdot_bounded(
        &["repl"],
        "parameters a, b, c\n:max-terms 50\nexpand((a+b+c)^12)\n:max-terms\n2*a\n",
        SECONDS,
        MEMORY_MIB,
    );
    o.assert_clean();
    assert_eq!(
        o.stderr,
        "error: expression too large: a product of 15 by 45 terms (the limit is 50 terms, and 400 term products)\n  = hint: raise the limit with :max-terms 500 (it is 50)\n"
    );
    assert_eq!(
        o.stdout,
        "(at most 50 terms per expression)\nat most 50 terms per expression\n2·a\n"
    );
}
