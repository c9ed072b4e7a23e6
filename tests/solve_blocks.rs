//! `solve` blocks: exact linear systems of any shape. Square, over-determined
//! (checks that hold, or a contradiction pointing at its equation),
//! under-determined (free unknowns), nonlinear and ill-named unknowns
//! (errors), vector equations, definitions through unknowns, q̈ replaced by
//! Lagrange's accelerations, and the `qdot solve` output of all that.
//! Every expected value is derived by hand in a comment.

use crate::common::run::{json, keys, qdot_on, BLOCK_KEYS, DYNAMICS_KEYS};
use qdot::solve::system::{equation_label, solve_scene, BlockSolution};
use qdot::{Expr, Scene};
use std::collections::BTreeMap;

fn parse(src: &str) -> Scene {
    match Scene::parse(src) {
        Ok(s) => s,
        Err(d) => panic!("{}", d.render("scene.qd", src)),
    }
}

fn blocks(s: &Scene) -> Vec<BlockSolution> {
    match solve_scene(s) {
        Ok(b) => b,
        Err(d) => panic!("{}", d.render("scene.qd", &s.source)),
    }
}

/// Every unknown's value, over all blocks.
fn solutions(s: &Scene) -> BTreeMap<String, Expr> {
    blocks(s).into_iter().flat_map(|b| b.values).collect()
}

/// Exact equality, also structurally (the canonical form is unique).
fn check(s: &Scene, got: &Expr, want: &str) {
    let w = s.expr(want).expect("expected value parses");
    assert!(got.equals(&w), "got {got}, want {want} (= {w})");
    assert_eq!(got, &w, "not in the same canonical form: {got} vs {w}");
}

/// The rendered error of a scene that parses but whose blocks do not solve.
fn block_error(src: &str) -> String {
    let s = parse(src);
    match solve_scene(&s) {
        Ok(b) => panic!("expected an error for {src:?}, got {b:?}"),
        Err(d) => d.render("scene.qd", src),
    }
}

/// The rendered error of a scene that does not even resolve.
fn scene_error(src: &str) -> String {
    match Scene::parse(src) {
        Ok(_) => panic!("expected an error for {src:?}"),
        Err(d) => d.render("scene.qd", src),
    }
}

fn assert_starts(got: &str, want: &str) {
    assert!(
        got.starts_with(want),
        "got:\n{got}\nwant to start with:\n{want}"
    );
}

/// Run `qdot ARGS FILE` on a scene written to a temporary file; the file
/// name in messages is replaced by `scene.qd`.
fn run(tag: &str, src: &str, args: &[&str]) -> (i32, String, String) {
    qdot_on("solve-blocks", tag, src, args[0], &args[1..])
}

// ---------------------------------------------------------------- square

#[test]
fn a_square_block_is_solved_exactly() {
    // x + 2y + 3z = a, 2x + y = b, z = c:
    //   x + 2y = a − 3c and 2x + y = b give 3x = 2b − a + 3c,
    //   x = (2b − a + 3c)/3, y = b − 2x = (2a − b − 6c)/3.
    let s = parse(
        "parameters a, b, c\n\
         solve x, y, z {\n  x + 2*y + 3*z = a\n  2*x + y = b\n  z = c\n}\n",
    );
    let sol = solutions(&s);
    check(&s, &sol["x"], "(2*b - a + 3*c)/3");
    check(&s, &sol["y"], "(2*a - b - 6*c)/3");
    check(&s, &sol["z"], "c");
    let b = &blocks(&s)[0];
    assert!(b.free.is_empty() && b.checks.is_empty() && !b.used_accelerations);
    // values come in the order of the unknowns
    let names: Vec<&str> = b.values.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(names, ["x", "y", "z"]);
}

#[test]
fn coefficients_may_be_trigonometric_and_radical() {
    // A force F along the direction th, split into components X, Y along
    // axes turned by th: the rotation's inverse, X = F·cos th, Y = F·sin th.
    // The third, X·cos th − Y·sin th = F·(cos² th − sin² th), is implied
    // only through sin² + cos² = 1.
    let s = parse(
        "coordinates th\nparameters F\n\
         solve X, Y {\n\
           X*cos(th) + Y*sin(th) = F\n\
           -X*sin(th) + Y*cos(th) = 0\n\
           X*cos(th) - Y*sin(th) = F*(1 - 2*sin(th)^2)\n\
         }\n",
    );
    let b = &blocks(&s)[0];
    let sol: BTreeMap<_, _> = b.values.iter().cloned().collect();
    // X is right but not in lowest terms: −F·(sin² th − 1)/cos th, a cos in
    // its denominator (see the report); `equals` decides it exactly.
    let x = s.expr("F*cos(th)").unwrap();
    assert!(sol["X"].equals(&x), "X = {}", sol["X"]);
    check(&s, &sol["Y"], "F*sin(th)");
    assert_eq!(b.checks, vec![2]);
    // radicals in the coefficients: √2·x + √3·y = 1, √3·x − √2·y = 0
    //   x = √2/5, y = √3/5 (det = −2 − 3 = −5)
    let s = parse(
        "parameters a\nsolve x, y {\n  sqrt(2)*x + sqrt(3)*y = 1\n  sqrt(3)*x - sqrt(2)*y = 0\n}\n",
    );
    let sol = solutions(&s);
    check(&s, &sol["x"], "sqrt(2)/5");
    check(&s, &sol["y"], "sqrt(3)/5");
}

// ---------------------------------------------------------------- shapes

#[test]
fn an_overdetermined_consistent_block_reports_its_checks() {
    // x + y = a, x − y = b: x = (a + b)/2, y = (a − b)/2; then 2x = a + b holds.
    let src = "parameters a, b\nsolve x, y {\n  x + y = a\n  x - y = b\n  2*x = a + b\n}\n";
    let s = parse(src);
    let b = &blocks(&s)[0];
    check(&s, &b.values[0].1, "(a + b)/2");
    check(&s, &b.values[1].1, "(a - b)/2");
    assert_eq!(b.checks, vec![2]);
    assert_eq!(equation_label(&s.systems[0], 2), "equation 3");
    let (code, out, err) = run("overdetermined", src, &["solve"]);
    assert_eq!(code, 0, "{err}");
    assert!(err.is_empty(), "{err}");
    assert_eq!(
        out,
        "Solutions  (solve x, y)\n  x = 1/2·a + 1/2·b\n  y = 1/2·a − 1/2·b\n  \
         check: equation 3 follows from the others and holds\n"
    );
    let (code, out, _) = run("overdetermined", src, &["solve", "--format", "json"]);
    assert_eq!(code, 0);
    let v = json(&out);
    assert_eq!(keys(&v), ["solutions", "free_unknowns", "checks"]);
    assert_eq!(
        v["checks"],
        serde_json::json!([{"block": 1, "equation": 3}])
    );
    assert_eq!(v["free_unknowns"], serde_json::json!([]));
    assert_eq!(v["solutions"]["x"], "a/2 + b/2");
}

#[test]
fn a_contradiction_points_at_its_equation() {
    // With x = (a + b)/2 from the first two, 2x = a − b reads 0 = −2b.
    let err =
        block_error("parameters a, b\nsolve x, y {\n  x + y = a\n  x - y = b\n  2*x = a - b\n}\n");
    assert_starts(
        &err,
        "error: equation 3 contradicts the others: with their solution it reads 0 = −2·b\n\
         \x20--> scene.qd:5:3\n  |\n5 |   2*x = a - b\n  |   ^^^^^^^^^^^\n",
    );
    assert!(err.contains("more equations than unknowns"), "{err}");
    // Square but dependent on the left: x + y = a, 2x + 2y = b gives 0 = b − 2a.
    let err = block_error("parameters a, b\nsolve x, y {\n  x + y = a\n  2*x + 2*y = b\n}\n");
    assert_starts(
        &err,
        "error: equation 2 contradicts the others: with their solution it reads 0 = b − 2·a\n\
         \x20--> scene.qd:4:3\n",
    );
    assert!(
        err.contains("dependent on the left but not on the right"),
        "{err}"
    );
    // Contradictions in a later block, on a line with two equations
    let err =
        block_error("parameters a\nsolve u { u = a }\nsolve p, q {\n  p = u; q = p; q = 2*u\n}\n");
    assert_starts(
        &err,
        "error: equation 3 contradicts the others: with their solution it reads 0 = a\n\
         \x20--> scene.qd:4:17\n",
    );
    // An equation without unknowns is a check that holds or a contradiction
    let s = parse("parameters a, b\nsolve x {\n  x = a\n  a + b = b + a\n}\n");
    assert_eq!(blocks(&s)[0].checks, vec![1]);
    let err = block_error("parameters a, b\nsolve x {\n  x = a\n  a = b\n}\n");
    assert_starts(
        &err,
        "error: equation 2 involves none of the unknowns and does not hold: it reads 0 = b − a\n\
         \x20--> scene.qd:4:3\n",
    );
    assert!(err.contains("should mention its unknowns"), "{err}");
    // An unknown that cancels: x − x = a is 0 = a
    let err = block_error("parameters a\nsolve x {\n  x - x = a\n}\n");
    assert_starts(
        &err,
        "error: equation 1 involves none of the unknowns and does not hold: it reads 0 = a\n",
    );
}

#[test]
fn an_underdetermined_block_has_free_unknowns() {
    // x + y + z = a, y − z = b: z is free, y = b + z, x = a − b − 2z.
    let src = "parameters a, b\nsolve x, y, z {\n  x + y + z = a\n  y - z = b\n}\n";
    let s = parse(src);
    let b = &blocks(&s)[0];
    assert_eq!(b.free, ["z"]);
    assert!(b.checks.is_empty());
    let sol: BTreeMap<_, _> = b.values.iter().cloned().collect();
    check(&s, &sol["x"], "a - b - 2*z");
    check(&s, &sol["y"], "b + z");
    check(&s, &sol["z"], "z");
    let (code, out, _) = run("free", src, &["solve"]);
    assert_eq!(code, 0);
    assert_eq!(
        out,
        "Solutions  (solve x, y, z)\n  x = a − b − 2·z\n  y = b + z\n  \
         free: z (the equations do not determine it)\n"
    );
    let (code, out, _) = run("free", src, &["solve", "--format", "json"]);
    assert_eq!(code, 0);
    let v = json(&out);
    assert_eq!(v["free_unknowns"], serde_json::json!(["z"]));
    // a free unknown is not among the solutions
    assert_eq!(keys(&v["solutions"]), ["x", "y"]);
    for (n, e) in v["solutions"].as_object().unwrap() {
        assert_eq!(s.expr(e.as_str().unwrap()).unwrap(), sol[n], "{n}");
    }
    // an unknown that no equation mentions is free too
    let s = parse("parameters a\nsolve p, q, r {\n  p + r = a\n  r = 2*a\n}\n");
    let b = &blocks(&s)[0];
    assert_eq!(b.free, ["q"]);
    check(&s, &b.values[0].1, "-a");
    // two free unknowns: "them"
    let (code, out, _) = run(
        "free2",
        "parameters a\nsolve x, y, z { x + y + z = a }\n",
        &["solve"],
    );
    assert_eq!(code, 0);
    assert!(out.contains("  x = a − y − z\n"), "{out}");
    assert!(
        out.contains("free: y, z (the equations do not determine them)"),
        "{out}"
    );
}

#[test]
fn nonlinear_blocks_are_errors() {
    let cases: &[(&str, &str)] = &[
        (
            "parameters a, b\nsolve x, y {\n  x*y = a\n  x - y = b\n}\n",
            "error: equation 1 is not linear in the unknowns: the term has x·y\n --> scene.qd:3:3\n",
        ),
        (
            "parameters a, b\nsolve x, y {\n  x - y = b\n  x^2 = a\n}\n",
            "error: equation 2 is not linear in the unknowns: the term has x\n --> scene.qd:4:3\n",
        ),
        (
            "parameters a, b\nsolve x, y {\n  sin(x) = a\n  x - y = b\n}\n",
            "error: equation 1 is not linear in the unknowns: `x` appears inside a function\n --> scene.qd:3:3\n",
        ),
        (
            "parameters a, b\nsolve x {\n  sqrt(a*x) = b\n}\n",
            "error: equation 1 is not linear in the unknowns: `x` appears inside a function\n --> scene.qd:3:3\n",
        ),
        (
            "parameters a, b\nsolve x {\n  a/x = 1\n}\n",
            "error: equation 1 is not linear in the unknowns: `x` divides\n --> scene.qd:3:3\n",
        ),
        (
            "parameters a, b\nsolve x, y {\n  [x, y] = [a, b]\n  [x*y, 0] = [1, 0]\n}\n",
            "error: equation 2 (component x) is not linear in the unknowns: the term has x·y\n --> scene.qd:4:3\n",
        ),
        (
            // nonlinear through a definition
            "parameters a\nF = x*x\nsolve x { F = a }\n",
            "error: equation 1 is not linear in the unknowns: the term has x\n --> scene.qd:3:11\n",
        ),
    ];
    for (src, head) in cases {
        let err = block_error(src);
        assert_starts(&err, head);
        assert!(
            err.contains("= hint: a `solve` block solves linear equations exactly"),
            "{err}"
        );
    }
}

#[test]
fn an_unknown_must_be_a_new_name() {
    let cases: &[(&str, &str, &str)] = &[
        (
            "parameters a, F\nsolve F { F = a }\n",
            "error: the unknown `F` is already a parameter\n --> scene.qd:2:7\n",
            "remove `F` from `parameters` (line 1)",
        ),
        (
            "parameters a\nc = 2*a\nsolve c { c = 1 }\n",
            "error: the unknown `c` is already defined\n --> scene.qd:3:7\n",
            "`c` already has a value (line 2)",
        ),
        (
            "coordinates q\nparameters a\nsolve q { q = a }\n",
            "error: the unknown `q` is already a coordinate\n --> scene.qd:3:7\n",
            "solve for a new name",
        ),
        (
            "coordinates q\nparameters m\nkinetic E = 1/2*m*q'^2\nsolve E { E = m }\n",
            "error: the unknown `E` is already defined\n --> scene.qd:4:7\n",
            "(line 3)",
        ),
        (
            "parameters a\nsolve x { x = a }\nsolve y, x { x = y }\n",
            "error: the unknown `x` is listed twice\n --> scene.qd:3:10\n",
            "list each unknown once, in one `solve` block (`x` is first at line 2)",
        ),
        (
            "parameters a\nsolve x, x { x = a }\n",
            "error: the unknown `x` is listed twice\n --> scene.qd:2:10\n",
            "(`x` is first at line 2)",
        ),
        (
            "parameters a\nsolve t { t = a }\n",
            "error: `t` is reserved: it is time\n --> scene.qd:2:7\n",
            "choose another name",
        ),
        (
            "parameters a\nsolve pi { pi = a }\n",
            "error: `pi` is reserved: it is the constant π\n --> scene.qd:2:7\n",
            "choose another name",
        ),
        (
            // a definition after the block may not reuse the unknown's name
            "parameters a\nsolve x { x = a }\nx = 2\n",
            "error: name used twice: `x` is already an unknown of a `solve` block\n --> scene.qd:3:1\n",
            "",
        ),
        (
            // unknowns do not enter energies
            "coordinates q\nparameters m\nsolve v { v = m }\nkinetic E = 1/2*v*q'^2\n",
            "error: `kinetic E` uses `v`, an unknown of a `solve` block\n --> scene.qd:4:13\n",
            "unknowns belong in `solve` equations",
        ),
        (
            "coordinates q\nparameters m\nk = 2*v\npotential V = 1/2*k*q^2\nsolve v { v = m }\n",
            "error: `potential V` uses `v`, an unknown of a `solve` block\n --> scene.qd:4:15\n",
            "",
        ),
    ];
    for (src, head, hint) in cases {
        let err = scene_error(src);
        assert_starts(&err, head);
        assert!(err.contains(hint), "no `{hint}` in\n{err}");
    }
}

// ---------------------------------------------------------------- vectors

#[test]
fn vector_equations_are_pairs_of_scalar_equations() {
    // [x + y, x − y] = [a, b]: x = (a + b)/2, y = (a − b)/2; the second
    // vector equation repeats them doubled: two checks, one per component.
    let src = "parameters a, b\nsolve x, y {\n  [x + y, x - y] = [a, b]\n  \
               [2*x, 2*y] = [a + b, a - b]\n}\n";
    let s = parse(src);
    let sys = &s.systems[0];
    assert_eq!(sys.equations.len(), 4);
    assert_eq!(
        (0..4).map(|i| equation_label(sys, i)).collect::<Vec<_>>(),
        [
            "equation 1 (component x)",
            "equation 1 (component y)",
            "equation 2 (component x)",
            "equation 2 (component y)"
        ]
    );
    let b = &blocks(&s)[0];
    assert_eq!(b.checks, vec![2, 3]);
    check(&s, &b.values[0].1, "(a + b)/2");
    check(&s, &b.values[1].1, "(a - b)/2");
    let (code, out, _) = run("vec-checks", src, &["solve"]);
    assert_eq!(code, 0);
    assert!(
        out.ends_with(
            "  check: equation 2 (component x) follows from the others and holds\n  \
             check: equation 2 (component y) follows from the others and holds\n"
        ),
        "{out}"
    );
    let (_, out, _) = run("vec-checks", src, &["solve", "--format", "json"]);
    let v = json(&out);
    let checks = v["checks"].as_array().unwrap();
    assert_eq!(checks.len(), 2);
    for c in checks {
        assert_eq!(c["block"], 1);
        assert_eq!(c["equation"], 2);
    }
    // a contradiction in one component names it
    let err = block_error(
        "parameters a, b\nsolve x, y {\n  [x + y, x - y] = [a, b]\n  \
         [2*x, 2*y] = [a + b, a - b + 1]\n}\n",
    );
    assert_starts(
        &err,
        "error: equation 2 (component y) contradicts the others: with their solution it reads 0 = 1\n\
         \x20--> scene.qd:4:3\n",
    );
    // 3D: m·a = F + N for a point on a smooth plane z = 0 under gravity and
    // a force [P, 0, Q] with Q < m g (write it as m*g - Q0):
    //   ax = P/m, ay = 0, N = m g − Q
    let s = parse(
        "parameters m, g, P, Q\n\
         solve ax, ay, N {\n  m*[ax, ay, 0] = [P, 0, Q] + [0, 0, N] + [0, 0, -m*g]\n}\n",
    );
    let sol = solutions(&s);
    check(&s, &sol["ax"], "P/m");
    check(&s, &sol["ay"], "0");
    check(&s, &sol["N"], "m*g - Q");
    // sizes must agree
    let err = scene_error("parameters a, b\nsolve x, y {\n  [x + y, x - y] = [a, b, 1]\n}\n");
    assert_starts(
        &err,
        "error: the left side is a vector with 2 components and the right side a vector with 3 components\n\
         \x20--> scene.qd:3:3\n",
    );
    let err = scene_error("parameters a, b\nsolve x, y {\n  a = [x, y]\n}\n");
    assert_starts(
        &err,
        "error: the left side is a number and the right side a vector with 2 components\n\
         \x20--> scene.qd:3:3\n",
    );
    assert!(err.contains("write `[0, 0]` for the zero vector"), "{err}");
}

// ---------------------------------------------------------------- definitions

#[test]
fn definitions_may_use_unknowns() {
    // Definitions through unknowns, forward references included:
    // F = m1·acc with m1 = 2a; F = T − b and T = 3b give acc = 2b/(2a) = b/a.
    // The later block uses both: z = acc·T + F = 3b²/a + 2b.
    let s = parse(
        "parameters a, b\nF = m1*acc\nm1 = 2*a\n\
         solve acc, T {\n  F = T - b\n  T = 3*b\n}\n\
         solve z { z = acc*T + F }\n",
    );
    let sol = solutions(&s);
    check(&s, &sol["acc"], "b/a");
    check(&s, &sol["T"], "3*b");
    check(&s, &sol["z"], "3*b^2/a + 2*b");
    // a later block may be nonlinear in an earlier block's unknowns, which
    // are known by then: x = b/a, then x·y = 1 gives y = a/b
    let s =
        parse("parameters a, b\nsolve x { a*x = b }\nsolve y { x*y = 1 }\nsolve w { w = x^2 }\n");
    let sol = solutions(&s);
    check(&s, &sol["y"], "a/b");
    check(&s, &sol["w"], "b^2/a^2");
    // an earlier free unknown stays a symbol in the later blocks
    let s = parse("parameters a\nsolve x, y { x + y = a }\nsolve z { z = 2*x }\n");
    let sol = solutions(&s);
    check(&s, &sol["x"], "a - y");
    check(&s, &sol["z"], "2*a - 2*y");
    // the definitions see the unknowns as symbols
    check(&s, &s.expr("x + y").unwrap(), "y + x");
}

// ---------------------------------------------------------------- dynamics

const PENDULUM: &str = "coordinates th\nparameters m, l, g\n\
    r = l*[sin(th), -cos(th)]\n\
    kinetic E = 1/2*m*dot(r', r')\n\
    potential V = m*g*dot(r, [0, 1])\n";

#[test]
fn accelerations_are_put_in_for_qddot() {
    // The rod's force on the bob, R = [Rx, Ry]: m·r'' = R + [0, −m g], with
    // th'' = −g/l·sin th. By hand, r'' = l·(cos th·th'' − sin th·th'²,
    //                                       sin th·th'' + cos th·th'²):
    //   Rx = m l (cos th·th'' − sin th·th'²) = −m g sin th cos th − m l sin th·th'²
    //   Ry = m l (sin th·th'' + cos th·th'²) + m g = m g cos² th + m l cos th·th'²
    // and the tension along the rod T = m l th'² + m g cos th.
    let src = format!(
        "{PENDULUM}solve Rx, Ry {{ m*r'' = [Rx, Ry] + [0, -m*g] }}\n\
         solve T {{ m*l*th'^2 = T - m*g*cos(th) }}\n"
    );
    let s = parse(&src);
    let b = blocks(&s);
    assert!(b[0].used_accelerations);
    assert!(!b[1].used_accelerations);
    let sol = solutions(&s);
    check(&s, &sol["Rx"], "-m*g*sin(th)*cos(th) - m*l*sin(th)*th'^2");
    check(&s, &sol["Ry"], "m*g*cos(th)^2 + m*l*cos(th)*th'^2");
    check(&s, &sol["T"], "m*l*th'^2 + m*g*cos(th)");
    // |R| = T: the reaction is along the rod
    check(
        &s,
        &sol["Rx"].mul(&sol["Rx"]).add(&sol["Ry"].mul(&sol["Ry"])),
        "(m*l*th'^2 + m*g*cos(th))^2",
    );
    // CLI: derive's keys, accelerations, then the blocks' keys
    let (code, out, err) = run("pendulum-blocks", &src, &["solve", "--format", "json"]);
    assert_eq!(code, 0, "{err}");
    let v = json(&out);
    let want: Vec<&str> = DYNAMICS_KEYS.iter().chain(&BLOCK_KEYS).copied().collect();
    assert_eq!(keys(&v), want);
    assert_eq!(v["accelerations"]["th"], "-g*sin(th)/l");
    for (n, e) in v["solutions"].as_object().unwrap() {
        assert_eq!(s.expr(e.as_str().unwrap()).unwrap(), sol[n], "{n}: {e}");
    }
    let (code, out, _) = run("pendulum-blocks", &src, &["solve"]);
    assert_eq!(code, 0);
    assert!(
        out.contains(
            "\n\nSolutions  (solve Rx, Ry)\n  Rx = −l·m·sin(θ)·θ̇² − g·m·cos(θ)·sin(θ)\n  \
             Ry = l·m·cos(θ)·θ̇² + g·m·cos²(θ)\n  (q̈ taken from the accelerations"
        ),
        "{out}"
    );
    assert!(
        out.ends_with("\n\nSolutions  (solve T)\n  T = l·m·θ̇² + g·m·cos(θ)\n"),
        "{out}"
    );
    // `derive` ignores the blocks
    let (code, out, _) = run("pendulum-blocks", &src, &["derive", "--format", "json"]);
    assert_eq!(code, 0);
    assert_eq!(
        keys(&json(&out)),
        ["coordinates", "equations", "mass_matrix", "forcing"]
    );
}

#[test]
fn without_dynamics_qddot_stays_a_symbol() {
    // No kinetic energy and no loads: nothing to take q̈ from.
    let s = parse("coordinates x\nparameters m, k\nsolve F { m*x'' = F - k*x }\n");
    assert!(!s.has_dynamics());
    let b = &blocks(&s)[0];
    assert!(!b.used_accelerations);
    check(&s, &b.values[0].1, "m*x'' + k*x");
    let (code, out, _) = run(
        "no-dynamics",
        "coordinates x\nparameters m, k\nsolve F { m*x'' = F - k*x }\n",
        &["solve", "--format", "json"],
    );
    assert_eq!(code, 0);
    let v = json(&out);
    assert_eq!(keys(&v), ["solutions", "free_unknowns", "checks"]);
    assert_eq!(v["solutions"]["F"], "m*x'' + k*x");
}

#[test]
fn a_dalembert_scene_feeds_its_blocks() {
    // A mass on a spring, pulled by F, written with an inertia load: the
    // spring force S = k x, and the load's balance m x'' = F − S with
    // x'' = (F − k x)/m from the load is a check.
    let s = parse(
        "coordinates x\nparameters m, k, F\n\
         load F - k*x - inertia(m, x) at x\n\
         solve S {\n  S = k*x\n  m*x'' = F - S\n}\n",
    );
    let l = s.lagrange().unwrap();
    check(&s, &l.mass_matrix[0][0], "m");
    let b = &blocks(&s)[0];
    assert!(b.used_accelerations);
    assert_eq!(b.checks, vec![1]);
    check(&s, &b.values[0].1, "k*x");
}

#[test]
fn a_singular_mass_matrix_stops_a_block_that_needs_qddot() {
    let s = parse(
        "coordinates x, y\nparameters m\nkinetic E = 1/2*m*(x' + y')^2\n\
         solve F { F = m*x'' }\nsolve G { G = m }\n",
    );
    let err = solve_scene(&s).unwrap_err();
    assert!(err.message.contains("singular"), "{}", err.message);
}

// ---------------------------------------------------------------- the CLI

#[test]
fn a_scene_of_blocks_alone_works_with_solve() {
    // Two unknowns, three equations (a check), and a second block with a
    // free unknown.
    let src = "parameters G, g\nalpha = 30deg\nm = G/g\n\
               solve a, N {\n  m*a = G*sin(alpha)\n  N = G*cos(alpha)\n  \
               N*sin(alpha) = m*a*cos(alpha)\n}\n\
               solve p, q {\n  p - q = a\n}\n";
    let s = parse(src);
    let sol = solutions(&s);
    check(&s, &sol["a"], "g/2");
    check(&s, &sol["N"], "sqrt(3)/2*G");
    check(&s, &sol["p"], "q + g/2");
    let b = blocks(&s);
    assert_eq!(b[0].checks, vec![2]);
    assert_eq!(b[1].free, ["q"]);
    let (code, out, err) = run("blocks-only", src, &["solve", "--format", "json"]);
    assert_eq!(code, 0, "{err}");
    assert!(err.is_empty(), "{err}");
    let v = json(&out);
    assert_eq!(keys(&v), ["solutions", "free_unknowns", "checks"]);
    assert_eq!(keys(&v["solutions"]), ["a", "N", "p"]);
    assert_eq!(v["free_unknowns"], serde_json::json!(["q"]));
    assert_eq!(
        v["checks"],
        serde_json::json!([{"block": 1, "equation": 3}])
    );
    for (n, e) in v["solutions"].as_object().unwrap() {
        assert_eq!(s.expr(e.as_str().unwrap()).unwrap(), sol[n], "{n}: {e}");
    }
    let (code, out, _) = run("blocks-only", src, &["solve"]);
    assert_eq!(code, 0);
    assert_eq!(
        out,
        "Solutions  (solve a, N)\n  a = 1/2·g\n  N = 1/2·G·√3\n  \
         check: equation 3 follows from the others and holds\n\n\
         Solutions  (solve p, q)\n  p = 1/2·g + q\n  \
         free: q (the equations do not determine it)\n"
    );
    // `derive`, `forces` and `equilibrium` need coordinates
    for cmd in ["derive", "forces", "equilibrium"] {
        let (code, _, err) = run("blocks-only", src, &[cmd]);
        assert_eq!(code, 1, "{cmd}");
        assert!(
            err.starts_with("error: the scene declares no coordinates"),
            "{cmd}: {err}"
        );
    }
    // errors in blocks are rendered with the source line and exit 1
    let (code, out, err) = run(
        "blocks-bad",
        "parameters a, b\nsolve x, y {\n  x + y = a\n  2*x + 2*y = b\n}\n",
        &["solve"],
    );
    assert_eq!(code, 1);
    assert!(out.is_empty(), "{out}");
    assert!(
        err.starts_with(
            "error: equation 2 contradicts the others: with their solution it reads 0 = b − 2·a\n\
             \x20--> scene.qd:4:3\n  |\n4 |   2*x + 2*y = b\n  |   ^^^^^^^^^^^^^\n"
        ),
        "{err}"
    );
}

/// Found as a bug during this work (`qdot solve` failed with "the equations
/// have no accelerations" on the load form) and fixed by commit 3932fb1
/// ("Static scenes … are not dynamics"): kept as a regression test.
#[test]
fn a_statics_scene_with_loads_and_a_block_solves() {
    // The bar of seed 23.1 style with the reactions at the hinge (y down):
    // Rx + P = 0, Ry + G = 0.
    let with_load = "coordinates th\nparameters G, P, l\n\
                     r = l*[sin(th), cos(th)]\n\
                     load [P, G] at r\n\
                     solve Rx, Ry {\n  Rx + P = 0\n  Ry + G = 0\n}\n";
    let with_potential = "coordinates th\nparameters G, P, l\n\
                          r = l*[sin(th), cos(th)]\n\
                          potential V = -dot([P, G], r)\n\
                          solve Rx, Ry {\n  Rx + P = 0\n  Ry + G = 0\n}\n";
    // the library solves both
    for src in [with_load, with_potential] {
        let s = parse(src);
        let sol = solutions(&s);
        check(&s, &sol["Rx"], "-P");
        check(&s, &sol["Ry"], "-G");
    }
    let (code, out, err) = run(
        "statics-potential",
        with_potential,
        &["solve", "--format", "json"],
    );
    assert_eq!(code, 0, "{err}");
    assert_eq!(keys(&json(&out)), ["solutions", "free_unknowns", "checks"]);
    // and the CLI solves the load form the same way
    let (code, out, err) = run("statics-load", with_load, &["solve", "--format", "json"]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(keys(&json(&out)), ["solutions", "free_unknowns", "checks"]);
}

/// Messages for an equation without unknowns and a repeated unknown.
#[test]
fn equation_without_unknowns_and_repeated_unknown() {
    let s = qdot::Scene::parse("parameters a\nsolve x { x - x = a }\n").unwrap();
    let e = qdot::solve::system::solve_scene(&s).unwrap_err();
    assert!(
        e.message.starts_with(
            "equation 1 involves none of the unknowns and does not hold: it reads 0 = a"
        ),
        "{}",
        e.message
    );
    let e = qdot::Scene::parse("parameters a\nsolve x, x { x = a }\n").unwrap_err();
    assert_eq!(e.message, "the unknown `x` is listed twice");
    // a load may not use an unknown
    let e = qdot::Scene::parse(
        "coordinates y\nparameters m\nkinetic E = m*y'^2/2\nload T at y\nsolve T { T = m }\n",
    )
    .unwrap_err();
    assert!(
        e.message
            .starts_with("a load uses `T`, an unknown of a `solve` block"),
        "{}",
        e.message
    );
}
