//! `inertia I about P` (the parallel-axis theorem) and a body without a
//! mass turning about its fixed centre (issue 38): each new form derives
//! exactly the equations of the form it replaces, and what the forms
//! cannot mean is refused (the wrong scenes are in
//! `tests/data/frames/wrong/about_*.qd` and `massless_*.qd`).

use qdot::Scene;

fn scene(src: &str) -> Scene {
    Scene::parse(src).unwrap_or_else(|d| panic!("{}", d.render("scene", src)))
}

fn example(name: &str) -> String {
    std::fs::read_to_string(format!("examples/{name}.qd")).expect("the example")
}

/// The residuals lhs − Q of a scene's equations.
fn residuals(s: &Scene) -> Vec<qdot::Expr> {
    let l = s.lagrange().expect("equations");
    l.equations.iter().map(|e| e.lhs.sub(&e.rhs)).collect()
}

/// Both scenes derive the same equations, exactly; neither warns.
fn same_equations(new: &str, old: &str) {
    let (a, b) = (scene(new), scene(old));
    for s in [&a, &b] {
        let w: Vec<&str> = s.warnings.iter().map(|w| w.message.as_str()).collect();
        assert!(w.is_empty(), "{w:?}");
    }
    let (x, y) = (residuals(&a), residuals(&b));
    assert_eq!(x.len(), y.len());
    for (k, (p, q)) in x.iter().zip(&y).enumerate() {
        assert!(p.equals(q), "equation {k}: {p}\n  vs {q}");
    }
}

/// Goldstein's top, its moments I1, I3 about the fixed point, is the top
/// whose moments about the centre are I1 − m·l² and I3.
#[test]
fn the_heavy_top_about_its_fixed_point_is_the_top_about_its_centre() {
    let about_centre = example("heavy_top_pivot").replace(
        "inertia [I1, I1, I3] about O",
        "inertia [I1 - m*l^2, I1 - m*l^2, I3]",
    );
    assert!(about_centre.contains("inertia [I1 - m*l^2"));
    same_equations(&example("heavy_top_pivot"), &about_centre);
    let s = scene(&example("heavy_top_pivot"));
    let theta = s
        .lagrange()
        .unwrap()
        .accelerations()
        .unwrap()
        .into_iter()
        .find(|(q, _)| *q == "theta")
        .unwrap()
        .1;
    let want = s
        .expr("((I1 - I3)*cos(theta)*sin(theta)*phi'^2 - I3*sin(theta)*phi'*psi' + g*l*m*sin(theta))/I1")
        .unwrap();
    assert!(theta.equals(&want), "{theta}");
}

/// The gyrocompass's rotor without a mass is the rotor with a dummy one.
#[test]
fn the_gyrocompass_rotor_needs_no_mass() {
    let new = example("gyrocompass");
    assert!(!new.contains("mass m"));
    let old = new
        .replace(
            "parameters A: mass*length^2",
            "parameters m: mass, A: mass*length^2",
        )
        .replace("body rotor: inertia", "body rotor: mass m, inertia");
    assert!(old.contains("body rotor: mass m, inertia [C, A, A]"));
    same_equations(&new, &old);
    let s = scene(&new);
    assert_eq!(s.parameters.len(), 5);
}

/// A torque-free body about its fixed centre: no mass, and its energy is
/// ½·ωᵀ·I·ω whatever a mass would have been.
#[test]
fn the_torque_free_body_needs_no_mass() {
    let new = example("torque_free_body");
    let old = new
        .replace(
            "parameters I1: mass*length^2",
            "parameters m: mass, I1: mass*length^2",
        )
        .replace("body b: inertia", "body b: mass m, inertia");
    assert!(old.contains("mass m, inertia [I1, I2, I3]"));
    same_equations(&new, &old);
}

/// Gravity does no work on a body whose centre is fixed: no potential.
#[test]
fn gravity_skips_a_body_without_a_mass() {
    let src = "coordinates phi
parameters A, C, g
frame B = rot(z, phi)
body wheel: inertia [A, A, C], frame B, at [0, 0, 1]
gravity [0, 0, -g]
";
    let s = scene(src);
    assert_eq!(s.bodies[0].gravity, None);
    let r = residuals(&s);
    assert_eq!(r.len(), 1);
    assert!(r[0].equals(&s.expr("C*phi''").unwrap()), "{}", r[0]);
}

/// A rod pendulum with its moment about the pivot, in the plane.
#[test]
fn a_rod_about_its_pivot_in_the_plane() {
    let about = "coordinates th
parameters m, l, g
body rod: mass m, inertia m*l^2/3 about [0, 0], angle th, at l/2*[sin(th), -cos(th)]
gravity [0, -g]
";
    let centre = about.replace("m*l^2/3 about [0, 0]", "m*l^2/12");
    same_equations(about, &centre);
}

/// The point may move, as long as it is a point of the body: the second
/// rod of a chain, its inertia about the joint with the first.
#[test]
fn an_inertia_about_a_moving_point_of_the_body() {
    let chain = |inertia: &str| {
        format!(
            "coordinates q1, q2
parameters m, A, C, l, g
assume 2*A > C
frame B1 = rot(x, q1)
frame B2 = B1 * rot(y, q2)
body b1: mass m, inertia [A, A, C], frame B1, at -l/2*axis(B1, 3)
P1 = -l*axis(B1, 3)
body b2: mass m, inertia {inertia}, frame B2, at P1 - l/2*axis(B2, 3)
gravity [0, 0, -g]
"
        )
    };
    same_equations(
        &chain("[A + m*l^2/4, A + m*l^2/4, C] about P1"),
        &chain("[A, A, C]"),
    );
}

/// What qdot can't decide about the inertia at the centre is a warning
/// that names it; `assume` settles it.
#[test]
fn an_undecided_centroidal_inertia_is_a_warning() {
    let src = example("heavy_top_pivot");
    let undecided = src.replace("assume I3 < 2*(I1 - m*l^2)", "");
    let s = scene(&undecided);
    let w: Vec<&str> = s.warnings.iter().map(|w| w.message.as_str()).collect();
    assert_eq!(
        w,
        ["qdot can't tell that the inertia of `top` about its centre of mass is one a rigid body can have: I1 - l^2*m ≥ 0 is not decided"]
    );
    assert_eq!(
        s.warnings[0].labels[0].message,
        "the inertia is given about this point; about the centre of mass it is I − m·(|d|²·1 − d·dᵀ), d from this point to the centre along the body's axes"
    );
    let half = undecided.replace("O = [0", "assume I1 > m*l^2\nO = [0");
    let s = scene(&half);
    assert_eq!(
        s.warnings[0].hint.as_deref(),
        Some("a rigid body's inertia is positive semidefinite and its principal moments satisfy the triangle inequality (each at most the sum of the other two; equal for a flat body); state it with `assume 2*I1 - 2*l^2*m > I3` or give numbers")
    );
    assert!(scene(&src).warnings.is_empty());
}

/// The parser keeps the point and where `about` is written.
#[test]
fn the_parser_keeps_the_point() {
    let src = "body top: mass m, inertia [A, A, C] about O, frame B, at P";
    let stmts = qdot::parse::parse_scene(src).expect("parses");
    let qdot::parse::ast::Stmt::Body(b) = &stmts[0] else {
        panic!("a body")
    };
    let about = b.properties[1].about.as_ref().expect("about");
    assert_eq!(&src[about.key_span.start..about.key_span.end], "about");
    assert_eq!(&src[about.point.span.start..about.point.span.end], "O");
    assert!(b
        .properties
        .iter()
        .enumerate()
        .all(|(k, p)| (k == 1) == p.about.is_some()));
}
