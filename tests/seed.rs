//! Every seed problem covered by the exact core, asserting the verified
//! answers of ../shared/problems.md (not the book's misprints).

use qdot::{Expr, Scene};

fn scene(name: &str) -> Scene {
    let path = format!("{}/examples/{name}.qd", env!("CARGO_MANIFEST_DIR"));
    let src = std::fs::read_to_string(&path).expect("example exists");
    match Scene::parse(&src) {
        Ok(s) => s,
        Err(d) => panic!("{}", d.render(&path, &src)),
    }
}

/// The accelerations, by coordinate name.
fn accelerations(s: &Scene) -> Vec<(String, Expr)> {
    s.lagrange()
        .expect("derives")
        .accelerations()
        .expect("solves")
}

/// Assert exact equality, showing both sides on failure.
fn assert_exact(s: &Scene, got: &Expr, want: &str) {
    let w = s.expr(want).expect("expected value parses");
    assert!(got.equals(&w), "got {got}, want {want} (= {w})");
    // Canonical: structurally equal too (no cos in these denominators).
    assert_eq!(got, &w, "not in the same canonical form");
}

#[test]
fn seed_21_1_one_dof_incline() {
    let s = scene("seed_21_1");
    let a = accelerations(&s);
    assert_exact(&s, &a[0].1, "256/715*g");
    let l = s.lagrange().unwrap();
    assert_exact(&s, &l.mass_matrix[0][0], "143/16*G/g");
    assert_exact(&s, &l.forcing[0], "16/5*G");
}

#[test]
fn seed_22_2_virtual_work() {
    let s = scene("seed_22_2");
    let l = s.lagrange().unwrap();
    assert_exact(&s, &l.mass_matrix[0][0], "127/16*G/g");
    assert_exact(&s, &l.equations[0].rhs, "89/40*G");
    assert_exact(&s, &accelerations(&s)[0].1, "178/635*g");
}

#[test]
fn seed_21_2_two_dof() {
    let s = scene("seed_21_2");
    let a = accelerations(&s);
    assert_eq!(a[0].0, "y3");
    assert_exact(&s, &a[0].1, "14/23*g");
    assert_exact(&s, &a[1].1, "1/23*g/r");
    let l = s.lagrange().unwrap();
    assert_exact(&s, &l.mass_matrix[0][0], "13/2*G/g");
    assert_exact(&s, &l.mass_matrix[0][1], "G*r/g");
    assert_exact(&s, &l.mass_matrix[1][0], "G*r/g");
    assert_exact(&s, &l.mass_matrix[1][1], "9*G*r^2/g");
    assert_exact(&s, &l.equations[0].rhs, "4*G");
    assert_exact(&s, &l.equations[1].rhs, "G*r");
}

#[test]
fn seed_23_2_symbolic() {
    let s = scene("seed_23_2");
    let a = accelerations(&s);
    assert_exact(&s, &a[0].1, "g*R*(G*R - P*r)/(G*R^2 + J2*g + P*r^2)");
}

#[test]
fn seed_23_3_couple_and_follow_up_tension() {
    let s = scene("seed_23_3");
    let l = s.lagrange().unwrap();
    assert_exact(&s, &l.mass_matrix[0][0], "79/8*G*r^2/g");
    let a = accelerations(&s);
    assert_exact(&s, &a[0].1, "45/79*g/r");
    // Kinetostatic follow-up: T23 = J3·ε3/r + m4·a4 + μ·2G with ε3 = 3/2·ε1, a4 = 3r/2·ε1.
    let eps1 = &a[0].1;
    let j3 = s.definition("J3").unwrap();
    let m4 = s.definition("m4").unwrap();
    let mu = s.definition("mu").unwrap();
    let r = s.expr("r").unwrap();
    let g_ = s.expr("G").unwrap();
    let three_halves = s.expr("3/2").unwrap();
    let eps3 = three_halves.mul(eps1);
    let a4 = three_halves.mul(&r).mul(eps1);
    let t23 = j3
        .mul(&eps3)
        .div(&r)
        .unwrap()
        .add(&m4.mul(&a4))
        .add(&mu.mul(&s.expr("2").unwrap()).mul(&g_));
    assert_exact(&s, &t23, "377/158*G");
}

#[test]
fn seed_23_4_horizontal() {
    let s = scene("seed_23_4");
    let a = accelerations(&s);
    assert_exact(&s, &a[0].1, "343/460*g");
    assert_exact(&s, &a[1].1, "13/460*g/r");
    let l = s.lagrange().unwrap();
    // E = (G/g)·(13/4·v3² + r·v3·ω3 + 9/2·r²·ω3²)
    assert_exact(
        &s,
        &l.kinetic,
        "G/g*(13/4*y3'^2 + r*y3'*theta3' + 9/2*r^2*theta3'^2)",
    );
    assert_exact(&s, &l.equations[0].rhs, "39/8*G");
}

#[test]
fn seed_24_1_damped_forced() {
    let s = scene("seed_24_1");
    let l = s.lagrange().unwrap();
    assert_exact(&s, &l.mass_matrix[0][0], "9*m");
    let a = accelerations(&s);
    assert_exact(
        &s,
        &a[0].1,
        "-16*k/(81*m)*y1 + g/3*sin(y1/(3*r)) - 4*c/(81*m)*y1' + F0/(9*m)*cos(p*t)",
    );
}
