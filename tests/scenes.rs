//! Scenes that no example uses, with answers derived by hand (and checked
//! against SymPy in tests/fixtures): E depending on q, explicit time in the
//! kinematics, `potential` + `rayleigh` + `work` together, a singular mass
//! matrix; vectors (arithmetic, dot, cross, norm, primes, inertia), the
//! double pendulum written with vectors and in D'Alembert's form (identical
//! equations), loads and torques (plane and space), the 30° incline with a
//! pulley by Lagrange, by kinetostatics and by vector equations, vector
//! errors with line:column, and the warning for loads that do no work.

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

// ---------------------------------------------------------------- vectors

/// The components of a vector-valued expression.
fn vector(s: &Scene, src: &str) -> Vec<Expr> {
    match s.value_of(src) {
        Ok(qdot::scene::Value::Vector(c)) => c,
        Ok(v) => panic!("{src}: expected a vector, got {}", v.describe()),
        Err(d) => panic!("{src}: {}", d.render("expr", src)),
    }
}

/// Assert that the vector `got` has exactly the components `want`.
fn check_vec(s: &Scene, got: &str, want: &[&str]) {
    let g = vector(s, got);
    assert_eq!(g.len(), want.len(), "{got}: {} components", g.len());
    for (k, (x, w)) in g.iter().zip(want).enumerate() {
        let w = s.expr(w).expect("expected component parses");
        assert!(x.equals(&w), "{got}[{k}]: got {x}, want {w}");
        assert_eq!(x, &w, "{got}[{k}]: not in the same canonical form");
    }
}

/// The error of a scene, rendered as the CLI does (`scene.qd:line:col`).
fn scene_error(src: &str) -> String {
    match Scene::parse(src) {
        Ok(_) => panic!("expected an error for {src:?}"),
        Err(d) => d.render("scene.qd", src),
    }
}

#[test]
fn vector_arithmetic_is_exact() {
    let s = parse(
        "coordinates x, y\nparameters a, b, c, d, e, f\n\
         u = [a, b, c]\nw = [d, e, f]\np = [a, b]\nq = [c, d]\n",
    );
    check_vec(&s, "p + q", &["a + c", "b + d"]);
    check_vec(&s, "p - q", &["a - c", "b - d"]);
    check_vec(&s, "-p", &["-a", "-b"]);
    check_vec(&s, "2*p", &["2*a", "2*b"]);
    check_vec(&s, "p*2", &["2*a", "2*b"]);
    check_vec(&s, "p/2", &["a/2", "b/2"]);
    check_vec(&s, "u/a", &["1", "b/a", "c/a"]);
    check_vec(&s, "(u + w)/2 - w/2", &["a/2", "b/2", "c/2"]);
    check_vec(&s, "x*[1, 0] + y*[0, 1]", &["x", "y"]);
    // dot products
    check(&s, &s.expr("dot(p, q)").unwrap(), "a*c + b*d");
    check(&s, &s.expr("dot(u, w)").unwrap(), "a*d + b*e + c*f");
    check(&s, &s.expr("dot(u, w) - dot(w, u)").unwrap(), "0");
    // cross products: 3D gives a vector, 2D the z component (a number)
    check_vec(&s, "cross(u, w)", &["b*f - c*e", "c*d - a*f", "a*e - b*d"]);
    check_vec(&s, "cross(u, w) + cross(w, u)", &["0", "0", "0"]);
    check_vec(&s, "cross(u, u)", &["0", "0", "0"]);
    check(&s, &s.expr("cross(p, q)").unwrap(), "a*d - b*c");
    check(&s, &s.expr("cross(p, p)").unwrap(), "0");
    check_vec(&s, "cross([a, b, 0], [c, d, 0])", &["0", "0", "a*d - b*c"]);
    check_vec(&s, "cross([1, 0, 0], [0, 1, 0])", &["0", "0", "1"]);
    // u·(u × w) = 0 and Lagrange's identity |u × w|² = |u|²|w|² − (u·w)²
    check(&s, &s.expr("dot(u, cross(u, w))").unwrap(), "0");
    check(
        &s,
        &s.expr("dot(cross(u, w), cross(u, w))").unwrap(),
        "dot(u, u)*dot(w, w) - dot(u, w)^2",
    );
    // norms: exact radicals
    check(&s, &s.expr("norm([3, 4])").unwrap(), "5");
    check(&s, &s.expr("norm([1, 2, 2])").unwrap(), "3");
    check(&s, &s.expr("norm([1, 1])").unwrap(), "sqrt(2)");
    check(&s, &s.expr("norm(p)").unwrap(), "sqrt(a^2 + b^2)");
    check(&s, &s.expr("norm(p)^2").unwrap(), "dot(p, p)");
    check(&s, &s.expr("norm(3*p)").unwrap(), "3*norm(p)");
    // Scene::expr refuses a vector, Scene::value_of keeps it
    let err = s.expr("p").unwrap_err();
    assert!(
        err.message.contains("a vector with 2 components"),
        "{}",
        err.message
    );
}

#[test]
fn primes_on_vectors_differentiate_each_component() {
    let s = parse(
        "coordinates q, x, y\nparameters l, a, w\n\
         r = l*[sin(q), -cos(q)]\n\
         s = [x, y, a*t]\n",
    );
    check_vec(&s, "r'", &["l*cos(q)*q'", "l*sin(q)*q'"]);
    check_vec(
        &s,
        "r''",
        &[
            "l*cos(q)*q'' - l*sin(q)*q'^2",
            "l*sin(q)*q'' + l*cos(q)*q'^2",
        ],
    );
    check_vec(
        &s,
        "(r')'",
        &[
            "l*cos(q)*q'' - l*sin(q)*q'^2",
            "l*sin(q)*q'' + l*cos(q)*q'^2",
        ],
    );
    check_vec(&s, "[x, y]'", &["x'", "y'"]);
    check_vec(&s, "s'", &["x'", "y'", "a"]);
    check_vec(&s, "s''", &["x''", "y''", "0"]);
    check_vec(
        &s,
        "(2*r + [x, y])'",
        &["2*l*cos(q)*q' + x'", "2*l*sin(q)*q' + y'"],
    );
    // |r'|² = l²q̇²: the vector kinetic energy of a pendulum bob
    check(&s, &s.expr("dot(r', r')").unwrap(), "l^2*q'^2");
    check(&s, &s.expr("norm(r)").unwrap(), "l");
    // inertia(m, x) = m·x'' for numbers and vectors
    check(&s, &s.expr("inertia(a, x)").unwrap(), "a*x''");
    check(&s, &s.expr("inertia(a, l*q)").unwrap(), "a*l*q''");
    check_vec(
        &s,
        "inertia(a, r)",
        &[
            "a*(l*cos(q)*q'' - l*sin(q)*q'^2)",
            "a*(l*sin(q)*q'' + l*cos(q)*q'^2)",
        ],
    );
    check_vec(&s, "inertia(w, s)", &["w*x''", "w*y''", "0"]);
    // a constant vector has no derivative
    let err = s.value_of("[1, 0]'").unwrap_err();
    assert!(
        err.message.contains("not a function of time"),
        "{}",
        err.message
    );
    let err = s.value_of("inertia(a, [l, 0])").unwrap_err();
    assert!(err.message.contains("does not move"), "{}", err.message);
}

const DOUBLE_VEC: &str = "coordinates q1, q2\nparameters m1, m2, l1, l2, g\n\
    r1 = l1*[sin(q1), -cos(q1)]\n\
    r2 = r1 + l2*[sin(q2), -cos(q2)]\n\
    kinetic E1 = 1/2*m1*dot(r1', r1')\nkinetic E2 = 1/2*m2*dot(r2', r2')\n\
    potential V = dot([0, g], m1*r1 + m2*r2)\n";

/// The double pendulum in D'Alembert's form: no kinetic energy, the inertia
/// forces are loads (and so is gravity).
const DOUBLE_DALEMBERT: &str = "coordinates q1, q2\nparameters m1, m2, l1, l2, g\n\
    r1 = l1*[sin(q1), -cos(q1)]\n\
    r2 = r1 + l2*[sin(q2), -cos(q2)]\n\
    load [0, -m1*g] - inertia(m1, r1) at r1\n\
    load [0, -m2*g] - inertia(m2, r2) at r2\n";

/// Half and half: body 1 by its kinetic energy and potential, body 2 by
/// loads (with the points in space, z = 0).
const DOUBLE_MIXED: &str = "coordinates q1, q2\nparameters m1, m2, l1, l2, g\n\
    r1 = l1*[sin(q1), -cos(q1), 0]\n\
    r2 = r1 + l2*[sin(q2), -cos(q2), 0]\n\
    kinetic E1 = 1/2*m1*dot(r1', r1')\n\
    potential V1 = m1*g*dot(r1, [0, 1, 0])\n\
    load -m2*g*[0, 1, 0] - inertia(m2, r2) at r2\n";

#[test]
fn double_pendulum_with_vectors_equals_the_scalar_forms() {
    let v = parse(DOUBLE_VEC);
    let c = parse(DOUBLE_COS);
    let x = parse(DOUBLE_XY);
    let lv = v.lagrange().unwrap();
    let lc = c.lagrange().unwrap();
    let lx = x.lagrange().unwrap();
    assert_eq!(lv.kinetic, lc.kinetic);
    for k in 0..2 {
        assert_eq!(lv.equations[k].lhs, lc.equations[k].lhs, "lhs {k}");
        assert_eq!(lv.equations[k].rhs, lc.equations[k].rhs, "rhs {k}");
        assert_eq!(lv.equations[k].lhs, lx.equations[k].lhs, "lhs {k}");
        assert_eq!(lv.forcing[k], lc.forcing[k], "forcing {k}");
        for j in 0..2 {
            assert_eq!(lv.mass_matrix[k][j], lc.mass_matrix[k][j], "M[{k}][{j}]");
        }
    }
    let (av, ac) = (acc(&v), acc(&c));
    for k in 0..2 {
        assert_eq!(av[k], ac[k], "acceleration {k}");
    }
    check(&v, &lv.mass_matrix[1][0], "m2*l1*l2*cos(q1 - q2)");
    check(&v, &lv.mass_matrix[1][1], "m2*l2^2");
    check(&v, &lv.equations[0].rhs, "-(m1 + m2)*g*l1*sin(q1)");
}

#[test]
fn double_pendulum_dalembert_and_mixed_equal_lagrange() {
    let c = parse(DOUBLE_COS);
    let lc = c.lagrange().unwrap();
    let ac = acc(&c);
    for src in [DOUBLE_DALEMBERT, DOUBLE_MIXED] {
        let s = parse(src);
        assert!(s.has_dynamics());
        let l = s.lagrange().unwrap();
        for k in 0..2 {
            assert_eq!(l.forcing[k], lc.forcing[k], "forcing {k} of\n{src}");
            for j in 0..2 {
                assert_eq!(
                    l.mass_matrix[k][j], lc.mass_matrix[k][j],
                    "M[{k}][{j}] of\n{src}"
                );
            }
        }
        let a = acc(&s);
        for k in 0..2 {
            assert_eq!(a[k], ac[k], "acceleration {k} of\n{src}");
        }
    }
    // D'Alembert: E = 0, every equation reads 0 = Q with the inertia in Q
    let d = parse(DOUBLE_DALEMBERT);
    let l = d.lagrange().unwrap();
    assert!(l.kinetic.is_zero());
    assert!(l.equations.iter().all(|e| e.lhs.is_zero()));
    // and at rest the generalized forces are the weights' alone
    let q = qdot::mechanics::generalized_forces(&d);
    let l2 = lc.equations[1].lhs.clone();
    check(&d, &q[1].add(&l2), "-m2*g*l2*sin(q2)");
}

#[test]
fn loads_and_torques_give_the_virtual_work() {
    // A bar of length l hinged at O, angle th from the downward vertical:
    // a horizontal force P at its end as a vector load, as a torque
    // cross(r, F) (the plane cross product is the z component) and as a
    // scalar load along the horizontal displacement x = l·sin th.
    let head = "coordinates th\nparameters m, l, g, P, M\n\
                r = l*[sin(th), -cos(th)]\nx = l*sin(th)\n\
                kinetic E = 1/2*m*l^2*th'^2\n";
    let a = parse(&format!("{head}load [P, 0] at r\n"));
    let b = parse(&format!("{head}torque cross(r, [P, 0]) on th\n"));
    let c = parse(&format!("{head}load P at x\n"));
    let d = parse(&format!("{head}force th: P*l*cos(th)\n"));
    let qa = qdot::mechanics::generalized_forces(&a);
    check(&a, &qa[0], "P*l*cos(th)");
    for s in [&b, &c, &d] {
        assert_eq!(qdot::mechanics::generalized_forces(s), qa);
        assert_eq!(acc(s), acc(&a));
    }
    check(&a, &acc(&a)[0], "P/(m*l)*cos(th)");
    // loads, torques, forces and potentials add up
    let s = parse(&format!(
        "{head}potential V = -m*g*l*cos(th)\nload [P, 0] at r\n\
         torque M on th\ntorque M on 2*th\nload [0, -m*g] at r\n"
    ));
    let q = qdot::mechanics::generalized_forces(&s);
    check(&s, &q[0], "-2*m*g*l*sin(th) + P*l*cos(th) + 3*M");
    // a torque on a definition: the angle's derivative scales the moment
    let s = parse(
        "coordinates y\nparameters r, M, J\nphi = y/(2*r)\n\
         kinetic E = 1/2*J*phi'^2\ntorque M on phi\n",
    );
    check(&s, &qdot::mechanics::generalized_forces(&s)[0], "M/(2*r)");
    check(&s, &acc(&s)[0], "2*M*r/J");
}

#[test]
fn a_point_load_in_space_on_a_spherical_pendulum() {
    // r = l·(sin θ cos φ, sin θ sin φ, −cos θ); gravity and a constant
    // horizontal force F along x.
    //   Q_θ = F·∂x/∂θ − m g·∂z/∂θ = F l cos θ cos φ − m g l sin θ
    //   Q_φ = F·∂x/∂φ             = −F l sin θ sin φ
    let s = parse(
        "coordinates th, ph\nparameters m, g, l, F\n\
         r = l*[sin(th)*cos(ph), sin(th)*sin(ph), -cos(th)]\n\
         kinetic E = 1/2*m*dot(r', r')\n\
         load [0, 0, -m*g] at r\nload [F, 0, 0] at r\n",
    );
    let q = qdot::mechanics::generalized_forces(&s);
    check(&s, &q[0], "F*l*cos(th)*cos(ph) - m*g*l*sin(th)");
    check(&s, &q[1], "-F*l*sin(th)*sin(ph)");
    let l = s.lagrange().unwrap();
    check(&s, &l.kinetic, "1/2*m*l^2*(th'^2 + sin(th)^2*ph'^2)");
    check(&s, &l.mass_matrix[1][1], "m*l^2*sin(th)^2");
    check(&s, &l.mass_matrix[0][1], "0");
    let a = acc(&s);
    check(
        &s,
        &a[0],
        "sin(th)*cos(th)*ph'^2 + F/(m*l)*cos(th)*cos(ph) - g/l*sin(th)",
    );
    check(&s, &a[1], "-(2*cos(th)*th'*ph' + F/(m*l)*sin(ph))/sin(th)");
}

// ---------------------------------------------------------------- 30° incline

/// Block 1 (weight G) on a 30° incline, dragged up it by a rope over a
/// pulley at the top, on whose other end hangs weight 2 (also G); sliding
/// friction μ = 1/4. By hand, with m = G/g and a the common acceleration:
///   block along the incline: m·a = T − G·sin 30° − Ff
///   normal to the incline:   N = G·cos 30° = √3/2·G
///   friction:                Ff = μ·N = √3/8·G
///   hanging weight:          m·a = G − T
/// Adding the first and the last: 2m·a = G − G/2 − √3/8·G = (4 − √3)/8·G, so
///   a = (4 − √3)/16·g ≈ 0.1418·g,  T = G − m·a = (12 + √3)/16·G.
const INCLINE_LAGRANGE: &str = "coordinates s\nparameters G, g\n\
    alpha = 30deg\nmu = 1/4\nm = G/g\n\
    kinetic E1 = 1/2*m*s'^2        # the block, s up the incline\n\
    kinetic E2 = 1/2*m*s'^2        # the hanging weight, s down\n\
    forcefunction U = G*s - G*sin(alpha)*s\n\
    work L = -mu*G*cos(alpha)*s\n";

const INCLINE_KINETOSTATIC: &str = "parameters G, g\n\
    alpha = 30deg\nmu = 1/4\nm = G/g\n\
    solve a, T, N, Ff {\n\
      m*a = T - G*sin(alpha) - Ff   # block, along the incline\n\
      0 = N - G*cos(alpha)          # block, normal to it\n\
      Ff = mu*N                     # sliding friction\n\
      m*a = G - T                   # hanging weight\n\
    }\n";

/// The same system with position vectors: D'Alembert loads for the
/// accelerations, then the block's and the weight's vector equations of
/// motion for the reactions, with s'' from Lagrange's equations.
const INCLINE_VECTORS: &str = "coordinates s\nparameters G, g\n\
    alpha = 30deg\nmu = 1/4\nm = G/g\n\
    u = [cos(alpha), sin(alpha)]       # up the incline\n\
    n = [-sin(alpha), cos(alpha)]      # its normal\n\
    r1 = s*u\n\
    r2 = [0, -s]\n\
    load [0, -G] - inertia(m, r1) at r1\n\
    load -mu*G*cos(alpha)*u at r1\n\
    load [0, -G] - inertia(m, r2) at r2\n\
    solve T, N, Ff {\n\
      m*r1'' = T*u + N*n - Ff*u + [0, -G]\n\
      Ff = mu*N\n\
      m*r2'' = [0, T - G]\n\
    }\n";

#[test]
fn incline_and_pulley_kinetostatics_equals_lagrange() {
    let l = parse(INCLINE_LAGRANGE);
    let a = acc(&l);
    check(&l, &a[0], "(4 - sqrt(3))/16*g");
    check(&l, &l.lagrange().unwrap().mass_matrix[0][0], "2*G/g");
    check(&l, &l.lagrange().unwrap().forcing[0], "(4 - sqrt(3))/8*G");

    let k = parse(INCLINE_KINETOSTATIC);
    let blocks = qdot::solve::system::solve_scene(&k).unwrap();
    assert_eq!(blocks.len(), 1);
    let b = &blocks[0];
    assert!(b.free.is_empty() && b.checks.is_empty() && !b.used_accelerations);
    let sol: std::collections::BTreeMap<_, _> = b.values.iter().cloned().collect();
    check(&k, &sol["a"], "(4 - sqrt(3))/16*g");
    check(&k, &sol["T"], "(12 + sqrt(3))/16*G");
    check(&k, &sol["N"], "sqrt(3)/2*G");
    check(&k, &sol["Ff"], "sqrt(3)/8*G");
    // the same expression, canonically, in both scenes
    assert_eq!(sol["a"], a[0]);

    let v = parse(INCLINE_VECTORS);
    assert_eq!(acc(&v), a);
    let blocks = qdot::solve::system::solve_scene(&v).unwrap();
    let b = &blocks[0];
    assert!(b.used_accelerations);
    assert!(b.free.is_empty());
    // 5 scalar equations for 3 unknowns: the weight's x component (0 = 0)
    // and its y component (T from the block agrees) are checks.
    assert_eq!(v.systems[0].equations.len(), 5);
    assert_eq!(b.checks, vec![3, 4]);
    let sol: std::collections::BTreeMap<_, _> = b.values.iter().cloned().collect();
    check(&v, &sol["T"], "(12 + sqrt(3))/16*G");
    check(&v, &sol["N"], "sqrt(3)/2*G");
    check(&v, &sol["Ff"], "sqrt(3)/8*G");
}

// ---------------------------------------------------------------- errors

#[test]
fn vector_errors_point_at_the_source() {
    let cases: &[(&str, &str)] = &[
        (
            "parameters a\nv = [1, 2] + 3\n",
            "error: can't add a vector and a number\n --> scene.qd:2:5\n",
        ),
        (
            "parameters a\nv = a - [1, 2]\n",
            "error: can't subtract a vector and a number\n --> scene.qd:2:5\n",
        ),
        (
            "parameters a\nv = [1, 2] + [1, 2, 3]\n",
            "error: vectors of different sizes: 2 and 3 components\n --> scene.qd:2:5\n",
        ),
        (
            "parameters a\nv = dot([a, 1], [1, 2, 3])\n",
            "error: `dot` of vectors of different sizes: 2 and 3 components\n --> scene.qd:2:5\n",
        ),
        (
            "parameters a\nv = cross([a, 1, 0], [1, 2])\n",
            "error: `cross` of vectors of different sizes: 3 and 2 components\n --> scene.qd:2:5\n",
        ),
        (
            "parameters a\nv = dot([a, 1], a)\n",
            "error: `dot` needs two vectors, and this is a number\n --> scene.qd:2:17\n",
        ),
        (
            "parameters a\nv = [a, 1]*[1, 2]\n",
            "error: two vectors can't be multiplied with `*`\n --> scene.qd:2:5\n",
        ),
        (
            "parameters a\nv = a/[1, 2]\n",
            "error: can't divide by a vector\n --> scene.qd:2:7\n",
        ),
        (
            "parameters a\nv = [a, 1]^2\n",
            "error: a vector can't be raised to a power\n --> scene.qd:2:5\n",
        ),
        (
            "parameters a\nv = [a]\n",
            "error: a vector has 2 or 3 components, this one has 1\n --> scene.qd:2:5\n",
        ),
        (
            "parameters a\nv = [a, a, a, a]\n",
            "error: a vector has 2 or 3 components, this one has 4\n --> scene.qd:2:5\n",
        ),
        (
            "parameters a\nv = [a, [1, 2]]\n",
            "error: expected a number as a vector component, found a vector with 2 components\n --> scene.qd:2:9\n",
        ),
        (
            "parameters a\nv = norm(a)\n",
            "error: norm needs a vector, found a number\n --> scene.qd:2:10\n",
        ),
        (
            "parameters a\nv = sin([a, 1])\n",
            "error: expected a number, found a vector with 2 components\n --> scene.qd:2:9\n",
        ),
        (
            "coordinates x\nparameters m\nkinetic E = 1/2*m*[x', 0]\n",
            "error: `kinetic E` must be a number, but this is a vector with 2 components\n --> scene.qd:3:13\n",
        ),
        (
            "coordinates x\nparameters k\nr = [x, 0]\npotential V = k*r\n",
            "error: `potential V` must be a number, but this is a vector with 2 components\n --> scene.qd:4:15\n",
        ),
        (
            "coordinates x\nparameters m, F\nkinetic E = 1/2*m*x'^2\nload [F, 0] at x\n",
            "error: the force is a vector with 2 components but the point is a number\n --> scene.qd:4:1\n",
        ),
        (
            "coordinates x\nparameters m, F\nkinetic E = 1/2*m*x'^2\nload F at [x, 0]\n",
            "error: the force is a number but the point is a vector with 2 components\n --> scene.qd:4:1\n",
        ),
        (
            "coordinates x\nparameters m, F\nkinetic E = 1/2*m*x'^2\nload [F, 0, 0] at [x, 0]\n",
            "error: the force has 3 components and the point 2\n --> scene.qd:4:1\n",
        ),
        (
            "coordinates x\nparameters m, F\nkinetic E = 1/2*m*x'^2\ntorque [F, 0] on x\n",
            "error: a torque is a number (the moment about the axis of its angle), found a vector with 2 components\n --> scene.qd:4:8\n",
        ),
        (
            "coordinates x\nparameters m, F\nkinetic E = 1/2*m*x'^2\ntorque F on [x, 0]\n",
            "error: a torque acts on an angle (a number), found a vector with 2 components\n --> scene.qd:4:13\n",
        ),
        (
            "coordinates x\nparameters m\nkinetic E = 1/2*m*x'^2\nforce x: [1, 0]\n",
            "error: expected a number, found a vector with 2 components\n --> scene.qd:4:10\n",
        ),
    ];
    for (src, head) in cases {
        // a `solve` block uses `v`: an unused definition's error is a
        // warning (tests/lazy.rs)
        let src = if src.contains("\nv = ") {
            format!("{src}solve u {{\n  u = v\n}}\n")
        } else {
            src.to_string()
        };
        let src = src.as_str();
        let err = scene_error(src);
        assert!(
            err.starts_with(head),
            "for {src:?}\ngot:\n{err}\nwant to start with:\n{head}"
        );
        assert!(err.contains("= hint: "), "no hint for {src:?}:\n{err}");
    }
}

#[test]
fn loads_at_fixed_points_warn() {
    let s = parse(
        "coordinates x\nparameters m, F, a\nkinetic E = 1/2*m*x'^2\n\
         P = [a, 2*a]\n\
         load [F, 0] at P\n\
         load F at a\n\
         load [F, 0] at [a*t, 0]\n\
         torque F on a\n\
         load F at x\n",
    );
    let w: Vec<String> = s
        .warnings
        .iter()
        .map(|d| d.render("scene.qd", &s.source))
        .collect();
    assert_eq!(w.len(), 4, "{w:#?}");
    for (i, (line, col)) in [(5, 16), (6, 11), (7, 16)].into_iter().enumerate() {
        assert!(
            w[i].starts_with(&format!(
                "warning: this load does no virtual work: its point does not move with any coordinate\n --> scene.qd:{line}:{col}\n"
            )),
            "{}",
            w[i]
        );
    }
    assert!(
        w[3].starts_with(
            "warning: this torque does no virtual work: its angle does not change with any coordinate\n --> scene.qd:8:13\n"
        ),
        "{}",
        w[3]
    );
    // they do no work indeed: only the last load enters Q
    check(&s, &qdot::mechanics::generalized_forces(&s)[0], "F");
    // a point that moves with a coordinate: no warning
    let s =
        parse("coordinates x\nparameters m, F\nkinetic E = 1/2*m*x'^2\nload [F, 0] at [x, 1]\n");
    assert!(s.warnings.is_empty(), "{:?}", s.warnings);
}
