//! Scenes that no example uses, with answers derived by hand (and checked
//! against SymPy in tests/fixtures): E depending on q, explicit time in the
//! kinematics, `potential` + `rayleigh` + `work` together, a singular mass
//! matrix.

use qdot::{Expr, Scene};

fn parse(src: &str) -> Scene {
    match Scene::parse(src) {
        Ok(s) => s,
        Err(d) => panic!("{}", d.render("scene.qd", src)),
    }
}

fn acc(s: &Scene) -> Vec<Expr> {
    s.lagrange()
        .expect("derives")
        .accelerations()
        .expect("solves")
        .into_iter()
        .map(|(_, e)| e)
        .collect()
}

fn check(s: &Scene, got: &Expr, want: &str) {
    let w = s.expr(want).expect("expected value parses");
    assert!(got.equals(&w), "got {got}, want {w}");
}

#[test]
fn bead_on_a_spinning_hoop() {
    let s = parse(
        "coordinates th\nparameters m, a, w, g\n\
         kinetic E = 1/2*m*(a^2*th'^2 + a^2*w^2*sin(th)^2)\n\
         potential V = -m*g*a*cos(th)\n",
    );
    let a = acc(&s);
    check(&s, &a[0], "w^2*sin(th)*cos(th) - g/a*sin(th)");
    // Relative equilibria: the acceleration vanishes at cos th = g/(a w^2).
}

#[test]
fn elastic_pendulum() {
    let s = parse(
        "coordinates r, th\nparameters m, k, l, g\n\
         x = r*sin(th)\ny = -r*cos(th)\n\
         kinetic E = 1/2*m*(x'^2 + y'^2)\n\
         potential V = m*g*y + 1/2*k*(r - l)^2\n",
    );
    let l = s.lagrange().unwrap();
    check(&s, &l.mass_matrix[0][0], "m");
    check(&s, &l.mass_matrix[1][1], "m*r^2");
    check(&s, &l.mass_matrix[0][1], "0");
    let a = acc(&s);
    check(&s, &a[0], "r*th'^2 + g*cos(th) - k/m*(r - l)");
    check(&s, &a[1], "-(g*sin(th) + 2*r'*th')/r");
}

const DOUBLE_XY: &str = "coordinates q1, q2\nparameters m1, m2, l1, l2, g\n\
    x1 = l1*sin(q1)\ny1 = -l1*cos(q1)\n\
    x2 = x1 + l2*sin(q2)\ny2 = y1 - l2*cos(q2)\n\
    kinetic E1 = 1/2*m1*(x1'^2 + y1'^2)\nkinetic E2 = 1/2*m2*(x2'^2 + y2'^2)\n\
    potential V = m1*g*y1 + m2*g*y2\n";

const DOUBLE_COS: &str = "coordinates q1, q2\nparameters m1, m2, l1, l2, g\n\
    kinetic E = 1/2*(m1 + m2)*l1^2*q1'^2 + 1/2*m2*l2^2*q2'^2 + m2*l1*l2*cos(q1 - q2)*q1'*q2'\n\
    potential V = -(m1 + m2)*g*l1*cos(q1) - m2*g*l2*cos(q2)\n";

#[test]
fn double_pendulum_two_ways_identical() {
    let a = parse(DOUBLE_XY);
    let b = parse(DOUBLE_COS);
    let la = a.lagrange().unwrap();
    let lb = b.lagrange().unwrap();
    for k in 0..2 {
        assert_eq!(la.equations[k].lhs, lb.equations[k].lhs, "lhs {k}");
        assert_eq!(la.equations[k].rhs, lb.equations[k].rhs, "rhs {k}");
        assert_eq!(la.forcing[k], lb.forcing[k], "forcing {k}");
        for j in 0..2 {
            assert_eq!(la.mass_matrix[k][j], lb.mass_matrix[k][j]);
        }
    }
    check(&a, &la.mass_matrix[0][1], "m2*l1*l2*cos(q1 - q2)");
    check(&a, &la.mass_matrix[0][0], "(m1 + m2)*l1^2");
    let xa = acc(&a);
    let xb = acc(&b);
    for k in 0..2 {
        assert!(xa[k].equals(&xb[k]));
    }
    // The textbook closed form of q1'':
    check(
        &a,
        &xa[0],
        "(-g*(2*m1 + m2)*sin(q1) - m2*g*sin(q1 - 2*q2) - 2*sin(q1 - q2)*m2*(q2'^2*l2 + q1'^2*l1*cos(q1 - q2))) \
         / (l1*(2*m1 + m2 - m2*cos(2*q1 - 2*q2)))",
    );
}

#[test]
fn pendulum_on_a_driven_support() {
    let s = parse(
        "coordinates th\nparameters m, l, a, Omega, g\n\
         x = a*cos(Omega*t) + l*sin(th)\ny = -l*cos(th)\n\
         kinetic E = 1/2*m*(x'^2 + y'^2)\npotential V = m*g*y\n",
    );
    let a = acc(&s);
    check(&s, &a[0], "(a*Omega^2*cos(Omega*t)*cos(th) - g*sin(th))/l");
}

#[test]
fn potential_rayleigh_work_and_force_together() {
    let s = parse(
        "coordinates x, y\nparameters m, k, c, F0, w, M0\n\
         kinetic E = 1/2*m*x'^2 + 1/2*m*y'^2\n\
         potential V = 1/2*k*x^2 + 1/2*k*(y - x)^2\n\
         rayleigh R = 1/2*c*x'^2\n\
         dissipation D = -1/2*c*(y' - x')^2\n\
         work L = F0*cos(w*t)*x\n\
         force y: M0*sin(w*t)\n",
    );
    let l = s.lagrange().unwrap();
    check(
        &s,
        &l.equations[0].rhs,
        "-k*x + k*(y - x) - c*x' + c*(y' - x') + F0*cos(w*t)",
    );
    check(
        &s,
        &l.equations[1].rhs,
        "-k*(y - x) - c*(y' - x') + M0*sin(w*t)",
    );
    let a = acc(&s);
    check(&s, &a[0], "(-2*k*x + k*y - 2*c*x' + c*y' + F0*cos(w*t))/m");
    check(&s, &a[1], "(k*x - k*y + c*x' - c*y' + M0*sin(w*t))/m");
}

#[test]
fn singular_mass_matrix_names_the_coordinates() {
    let s =
        parse("coordinates x, y, z\nparameters m\nkinetic E = 1/2*m*(x' + y')^2 + 1/2*m*z'^2\n");
    let err = s.lagrange().unwrap().accelerations().unwrap_err();
    assert!(err.message.contains("singular"), "{}", err.message);
    assert!(err.message.contains("x, y"), "{}", err.message);
    assert!(!err.message.contains('z'), "{}", err.message);
}

#[test]
fn skips_what_is_not_needed() {
    // E independent of q: no ∂E/∂q; no dissipation: none in Q.
    let s =
        parse("coordinates x\nparameters m, k\nkinetic E = 1/2*m*x'^2\npotential V = 1/2*k*x^2\n");
    let l = s.lagrange().unwrap();
    check(&s, &l.equations[0].lhs, "m*x''");
    check(&s, &l.equations[0].rhs, "-k*x");
}
