//! The accelerations of a tree of rigid bodies by the articulated-body
//! recursion (`Lagrange::articulated_accelerations`): equal to M⁻¹·f, and
//! refused with a reason where it does not apply (its equality with
//! Pinocchio's `aba` is in `structured::chain_accelerations_equal_pinocchio_aba`).

use qdot::expr::atom::Atom;
use qdot::scene::Scene;

fn chain3d(n: usize) -> String {
    qdot::engine::gallery::rod_chain_3d(n)
}

/// The recursion's q̈ equals M⁻¹·f (solved numerically) at random states.
fn assert_equals_mass_matrix_solve(src: &str) {
    let scene = Scene::parse_structured(src).unwrap();
    let l = scene.lagrange().unwrap();
    let acc = l.articulated_accelerations(&scene).unwrap();
    let n = l.coordinates.len();
    let lt = l.intermediates.as_deref().unwrap();
    let tape = acc.intermediates().unwrap();
    let mut rng = qdot_exact::rng::SplitMix64::new(7);
    for _ in 0..5 {
        let seed = rng.next_u64();
        let value = |a: &Atom| Some(qdot_exact::rng::SplitMix64::keyed(seed, a).uniform(0.2, 1.7));
        let m: Vec<f64> = lt.eval_many_f64(&l.mass_matrix.concat(), &value).unwrap();
        let f = lt.eval_many_f64(&l.forcing, &value).unwrap();
        let got = tape.eval_many_f64(acc.values(), &value).unwrap();
        // M·q̈ − f, relative to the size of the terms
        for i in 0..n {
            let r: f64 = (0..n).map(|j| m[i * n + j] * got[j]).sum::<f64>() - f[i];
            let size = (0..n).map(|j| (m[i * n + j] * got[j]).abs()).sum::<f64>() + f[i].abs();
            assert!(
                r.abs() <= 1e-11 * (1.0 + size),
                "{src}\nrow {i}: residual {r}"
            );
        }
    }
}

/// The examples' trees: rods in space (every joint axis), a planar chain of
/// bodies with relative angles, particles with absolute angles, a bead on a
/// turning rod, a rod with two bodies on one link (one merged link), a
/// two-coordinate joint, springs and dampers and a torque besides gravity.
#[test]
fn the_recursion_equals_the_mass_matrix_solve_on_trees_of_bodies() {
    for n in [1, 2, 3, 6] {
        assert_equals_mass_matrix_solve(&chain3d(n));
    }
    assert_equals_mass_matrix_solve(
        "coordinates a, b, c\nparameters m, J, l, g, k\n\
         body r1: mass m, inertia J, angle a, at l/2*[sin(a), -cos(a)]\n\
         body r2: mass 2*m, inertia J, angle a + b, at l*[sin(a), -cos(a)] + l/2*[sin(a + b), -cos(a + b)]\n\
         body r3: mass m, inertia 3*J, angle a + b + c, at l*[sin(a), -cos(a)] + l*[sin(a + b), -cos(a + b)] + l/3*[sin(a + b + c), -cos(a + b + c)]\n\
         gravity [0, -g]\npotential Vs = 1/2*k*b^2\ndissipation D = -1/2*k*c'^2\n",
    );
    assert_equals_mass_matrix_solve(
        "coordinates q1, q2\nparameters m, l, g\n\
         P1 = l*[sin(q1), -cos(q1)]\nparticle p1: mass m, at P1\n\
         particle p2: mass 3*m, at P1 + l*[sin(q2), -cos(q2)]\ngravity [0, -g]\n",
    );
    assert_equals_mass_matrix_solve(
        "coordinates th, r\nparameters m, M, J, g, k\n\
         body rod: mass M, inertia J, angle th, at [0, 0]\n\
         particle bead: mass m, at r*[cos(th), sin(th)]\ngravity [0, -g]\npotential V = 1/2*k*r^2\n",
    );
    assert_equals_mass_matrix_solve(
        "coordinates phi, psi\nparameters m, A, C, l, g, T\n\
         frame B = rot(z, phi) * rot(x, psi)\n\
         body disk: mass m, inertia [A, A, C], frame B, at l*axis(B, 3)\n\
         particle tip: mass m, at 2*l*axis(B, 3)\n\
         gravity [0, 0, -g]\ntorque T on phi\n",
    );
    assert_equals_mass_matrix_solve(
        "coordinates x, th\nparameters m, M, A, C, l, g, k\n\
         frame B = rot(y, th)\n\
         body cart: mass M, inertia [A, A, C], frame rot(z, 0), at [x, 0, 0]\n\
         body rod: mass m, inertia [A, A, C], frame B, at [x, 0, 0] - l*axis(B, 3)\n\
         gravity [0, 0, -g]\npotential V = 1/2*k*x^2\n",
    );
}

/// Where the recursion does not apply, it says why, and the dense solve
/// serves: a kinetic energy written by hand, coordinates that are not a
/// tree, and rods with absolute angles (the joint's rate θ̇₂ − θ̇₁ involves
/// the parent's coordinate: the comparison with M⁻¹·f refuses it).
#[test]
fn scenes_the_recursion_does_not_read_are_refused_with_a_reason() {
    let why = |src: &str| {
        let scene = Scene::parse_structured(src).unwrap();
        let l = scene.lagrange().unwrap();
        l.articulated_accelerations(&scene).unwrap_err()
    };
    assert_eq!(
        why("coordinates x, y\nparameters m, g\nparticle p: mass m, at [x, y]\nkinetic E = 1/2*m*x'^2\ngravity [0, -g]\n"),
        "the scene has kinetic energy besides its bodies'"
    );
    assert_eq!(
        why("coordinates a, b, c\nparameters m\nparticle p: mass m, at [a, b]\nparticle q: mass m, at [b, c]\n"),
        "the bodies' coordinates do not form a tree"
    );
    assert_eq!(
        why("coordinates a, b\nparameters m, J, l, g\n\
             body r1: mass m, inertia J, angle a, at l/2*[sin(a), -cos(a)]\n\
             body r2: mass m, inertia J, angle b, at l*[sin(a), -cos(a)] + l/2*[sin(b), -cos(b)]\n\
             gravity [0, -g]\n"),
        "the recursion does not reproduce M⁻¹·f: the bodies are not a tree of rigid joints"
    );
    let other = Scene::parse_structured(&chain3d(2)).unwrap();
    let l = Scene::parse_structured(&chain3d(2))
        .unwrap()
        .lagrange()
        .unwrap();
    assert_eq!(
        l.articulated_accelerations(&other).unwrap_err(),
        "the equations were not derived from this scene"
    );
    let expanded = Scene::parse(&chain3d(2)).unwrap();
    let l = expanded.lagrange().unwrap();
    assert_eq!(
        l.articulated_accelerations(&expanded).unwrap_err(),
        "the equations are expanded"
    );
}

/// `simulate` and `codegen` of the 20-rod chain evaluate q̈ by the recursion,
/// and the compiled right-hand side equals the one through M and f.
#[test]
fn simulate_and_codegen_choose_the_recursion_for_a_long_chain() {
    use qdot::simulate::compile::{CompiledDynamics, Evaluator};
    let src = chain3d(20);
    let scene = Scene::parse_structured(&src).unwrap();
    let l = scene.lagrange().unwrap();
    let acc = l.articulated_accelerations(&scene).unwrap();
    let params: rustc_hash::FxHashMap<_, _> =
        [("m", 1.0), ("A", 0.1), ("C", 0.05), ("l", 1.0), ("g", 9.81)]
            .iter()
            .map(|&(k, v)| (qdot::expr::atom::param(k), v))
            .collect();
    let (mut rec, choice) = CompiledDynamics::best_among(&l, &params, Some(&acc)).unwrap();
    assert_eq!(
        choice.evaluator,
        Evaluator::Articulated,
        "{}",
        choice.reason
    );
    let (mut dense, _) = CompiledDynamics::best(&l, &params).unwrap();
    assert_eq!(dense.evaluator(), Evaluator::MassMatrix);
    let y: Vec<f64> = (0..40)
        .map(|k| 0.4 * (1.3 * k as f64 + 0.2).sin())
        .collect();
    let (mut a, mut b) = (vec![0.0; 40], vec![0.0; 40]);
    rec.rhs_interpreted(0.0, &y, &mut a);
    dense.rhs_interpreted(0.0, &y, &mut b);
    let scale = b.iter().fold(1.0f64, |m, x| m.max(x.abs()));
    for (x, z) in a.iter().zip(&b) {
        assert!((x - z).abs() <= 1e-10 * scale, "{a:?}\n{b:?}");
    }
    // the recursion's program grows like n (twice the links, at most 2.3
    // times the operations), the dense one like n³
    let ops = |d: &CompiledDynamics| {
        let (add, mul, div, call) = d.program().op_counts();
        add + mul + div + call
    };
    let half = Scene::parse_structured(&chain3d(10)).unwrap();
    let lh = half.lagrange().unwrap();
    let acc_half = lh.articulated_accelerations(&half).unwrap();
    let rec_half = CompiledDynamics::from_articulated(&lh, &acc_half, &params).unwrap();
    let (dense_half, _) = CompiledDynamics::best(&lh, &params).unwrap();
    assert!(
        ops(&rec) * 10 <= ops(&rec_half) * 23,
        "{} at n = 20 against {} at n = 10",
        ops(&rec),
        ops(&rec_half)
    );
    assert!(ops(&dense) > ops(&dense_half) * 4);
    let dir = std::env::temp_dir().join(format!("qdot-articulated-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("chain20.qd");
    std::fs::write(&file, &src).unwrap();
    let mut req = qdot::simulate::codegen::CodegenRequest::new(
        file.to_str().unwrap(),
        qdot::simulate::codegen::Lang::C,
    );
    req.set = [("m", 1.0), ("A", 0.1), ("C", 0.05), ("l", 1.0), ("g", 9.81)]
        .iter()
        .map(|&(k, v)| (k.to_string(), v))
        .collect();
    let c = qdot::simulate::codegen::codegen(&src, &req).unwrap();
    assert!(
        c.contains("the articulated-body recursion (Featherstone)"),
        "{}",
        &c[..2000]
    );
    std::fs::remove_dir_all(&dir).ok();
}
