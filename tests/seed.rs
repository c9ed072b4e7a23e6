//! Every seed problem covered by the exact core, asserting the verified
//! answers of ../shared/problems.md (not the book's misprints).

use qdot::{Expr, Scene};

fn scene(name: &str) -> Scene {
    let path = format!("{}/examples/{name}.qd", env!("QDOT_ROOT"));
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
        .into_iter()
        .collect()
}

/// The solutions of every `solve` block, by unknown.
fn solutions(s: &Scene) -> std::collections::BTreeMap<String, Expr> {
    let blocks = qdot::solve::system::solve_scene(s).expect("blocks solve");
    blocks.into_iter().flat_map(|b| b.values).collect()
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
fn seed_22_2_lagrange() {
    let s = scene("seed_22_2_lagrange");
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
    // The kinetostatic follow-up in the scene's `solve` block:
    // T23 = J3·ε3/r + m4·a4 + μ·2G with ε3 = 3/2·ε1, a4 = 3r/2·ε1.
    let sol = solutions(&s);
    assert_exact(&s, &sol["T23"], "377/158*G");
    assert_exact(&s, &sol["T34"], "619/316*G");
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

#[test]
fn seed_21_1_kinetostatic() {
    let s = scene("seed_21_1_kinetostatic");
    let sol = solutions(&s);
    assert_exact(&s, &sol["a1"], "256/715*g");
    assert_exact(&s, &sol["T1"], "459/715*G");
    assert_exact(&s, &sol["T2"], "2348/2145*G");
    assert_exact(&s, &sol["T3"], "632/429*G");
    assert_exact(&s, &sol["T4"], "4016/2145*G");
    assert_exact(&s, &sol["H"], "2008/2145*sqrt(3)*G");
    assert_exact(&s, &sol["V"], "11603/2145*G");
    assert_exact(&s, &sol["Ff"], "719/2145*G");
    assert_exact(&s, &sol["N"], "sqrt(3)*G");
    assert_exact(&s, &sol["Mr"], "G*r/10");
}

#[test]
fn seed_21_2_kinetostatic_accelerations_and_all_reactions() {
    let s = scene("seed_21_2_kinetostatic");
    let sol = solutions(&s);
    for (name, want) in [
        ("a3", "14/23*g"),
        ("eps3", "1/23*g/r"),
        ("T1", "7/23*G"),
        ("T2", "10/23*G"),
        ("T3", "44/23*G"),
        ("T4", "60/23*G"),
        ("N", "sqrt(3)*G"),
        ("Ff", "G"),
        ("H", "30*sqrt(3)/23*G"),
        ("V", "143/23*G"),
    ] {
        assert_exact(&s, &sol[name], want);
    }
    let blocks = qdot::solve::system::solve_scene(&s).unwrap();
    assert!(blocks[0].free.is_empty() && blocks[0].checks.is_empty());
}

#[test]
fn seed_22_2_virtual_work_and_reactions_with_a_check() {
    let s = scene("seed_22_2");
    // D'Alembert's inertia forces are loads: the mass is read off them.
    let l = s.lagrange().unwrap();
    assert_exact(&s, &l.mass_matrix[0][0], "127/16*G/g");
    assert_exact(&s, &l.forcing[0], "89/40*G");
    assert_exact(&s, &accelerations(&s)[0].1, "178/635*g");
    let blocks = qdot::solve::system::solve_scene(&s).unwrap();
    let b = &blocks[0];
    // ten equations for nine unknowns: the last one is the check, and holds
    assert_eq!(b.checks, vec![9]);
    assert!(b.used_accelerations && b.free.is_empty());
    let sol = solutions(&s);
    for (name, want) in [
        ("T1", "457/635*G"),
        ("T2", "1727/1905*G"),
        ("T3", "2386/1905*G"),
        ("T4", "634/381*G"),
        ("H", "317*sqrt(3)/381*G"),
        ("V", "7781/1905*G"),
        ("N", "sqrt(3)*G"),
        ("Mr", "G*r/20"),
        ("Ff", "464/1905*G"),
    ] {
        assert_exact(&s, &sol[name], want);
    }
    // The book's decimals (table 22.3), except its misprinted T4 ≈ 1.690·G.
    let val = |n: &str| {
        sol[n]
            .eval_f64(&|a| match a {
                qdot::expr::atom::Atom::Param(p) if &**p == "G" => Some(1.0),
                qdot::expr::atom::Atom::Param(_) => Some(1.0),
                _ => None,
            })
            .unwrap()
    };
    for (n, book) in [
        ("T1", 0.720),
        ("T2", 0.906),
        ("T3", 1.252),
        ("H", 1.441),
        ("V", 4.085),
        ("Ff", 0.243),
    ] {
        assert!(
            (val(n) - book).abs() < 1.5e-3,
            "{n}: {} vs book {book}",
            val(n)
        );
    }
    assert!((val("T4") - 1.664).abs() < 1e-3);
}

#[test]
fn seed_22_3_virtual_work_two_dof() {
    let s = scene("seed_22_3");
    let a = accelerations(&s);
    assert_exact(&s, &a[0].1, "14/23*g");
    assert_exact(&s, &a[1].1, "1/23*g/r");
    // δL = 0 for every δq: no kinetic energy, the equations are 0 = Q
    let l = s.lagrange().unwrap();
    assert!(l.kinetic.is_zero());
    assert!(l.equations.iter().all(|e| e.lhs.is_zero()));
}

#[test]
fn seed_23_1_equilibrium_by_generalized_forces() {
    let s = scene("seed_23_1");
    let q = qdot::mechanics::generalized_forces(&s);
    assert_exact(
        &s,
        &q[0],
        "-G*l*sin(theta1) - 2*G*l*sin(theta1) + 2*P*l*cos(theta1)",
    );
    assert_exact(&s, &q[1], "-G*l*sin(theta2) + 2*P*l*cos(theta2)");
    let eq = qdot::solve::equilibrium::equilibria(&s, &Default::default()).unwrap();
    assert!(eq.exact);
    assert_eq!(eq.equilibria.len(), 4);
    let first = &eq.equilibria[0];
    let qdot::solve::equilibrium::Position::Exact(v) = &first.position else {
        panic!("exact")
    };
    assert_exact(&s, &v[0], "atan(2*P/(3*G))");
    assert_exact(&s, &v[1], "atan(2*P/G)");
    assert_eq!(first.stability, qdot::solve::equilibrium::Stability::Stable);
    // tan θ1 = 2P/(3G), tan θ2 = 2P/G
    let t1 = qdot::expr::func::tan(&v[0]).unwrap();
    assert_exact(&s, &t1, "2*P/(3*G)");
    let t2 = qdot::expr::func::tan(&v[1]).unwrap();
    assert_exact(&s, &t2, "2*P/G");
    // the other three are unstable (a bar standing up)
    for e in &eq.equilibria[1..] {
        assert_eq!(e.stability, qdot::solve::equilibrium::Stability::Unstable);
    }
}

// ---------------------------------------------------------------- cross-checks

/// The accelerations of one scene by name.
fn acc_map(name: &str) -> std::collections::BTreeMap<String, Expr> {
    accelerations(&scene(name)).into_iter().collect()
}

#[test]
fn cross_check_21_1_kinetostatics_equals_lagrange() {
    let k = solutions(&scene("seed_21_1_kinetostatic"));
    let l = acc_map("seed_21_1");
    assert_eq!(k["a1"], l["y1"]);
}

#[test]
fn cross_check_21_2_kinetostatics_virtual_work_and_lagrange_agree() {
    let k = solutions(&scene("seed_21_2_kinetostatic"));
    let l = acc_map("seed_21_2");
    let v = acc_map("seed_22_3");
    assert_eq!(k["a3"], l["y3"]);
    assert_eq!(k["eps3"], l["theta3"]);
    assert_eq!(v["y3"], l["y3"]);
    assert_eq!(v["theta3"], l["theta3"]);
}

#[test]
fn cross_check_22_2_virtual_work_equals_lagrange() {
    let v = acc_map("seed_22_2");
    let l = acc_map("seed_22_2_lagrange");
    assert_eq!(v["y1"], l["y1"]);
    // and the kinetostatic system with a1 as an unknown: same a1, same reactions
    let k = solutions(&scene("seed_22_2_kinetostatic"));
    assert_eq!(k["a1"], l["y1"]);
    let reactions = solutions(&scene("seed_22_2"));
    for n in ["T1", "T2", "T3", "T4", "H", "V", "N", "Mr", "Ff"] {
        assert_eq!(k[n], reactions[n], "{n}");
    }
}
