//! The compiled f64 evaluator (`qdot::simulate::compile`) against the tree
//! walk `Expr::eval_f64`: every seed example's mass matrix, forcing and
//! accelerations, the n-link chain, random expressions; the amount of
//! common-subexpression sharing; and `CompiledDynamics`' accelerations.

use proptest::prelude::*;
use qdot::engine::poly::{Poly, Var};
use qdot::expr::atom::{self, Atom};
use qdot::expr::func;
use qdot::simulate::compile::{
    compile, compile_with, naive_op_count, solve_spd, CompileError, CompiledDynamics, Evaluator,
    Instr, Program,
};
use qdot::simulate::System;
use qdot::{Expr, Lagrange, Scene};
use qdot_exact::rng::SplitMix64;
use rustc_hash::FxHashMap;

/// Every parameter, unknown, coordinate and time atom the expressions
/// mention (through function arguments too), sorted.
pub(crate) fn leaves(exprs: &[Expr]) -> Vec<Var> {
    fn walk(e: &Expr, out: &mut Vec<Var>) {
        for v in e.vars() {
            match atom::atom(v) {
                Atom::Param(_) | Atom::Unknown(_) | Atom::Coord(..) | Atom::Time => out.push(v),
                a => {
                    if let Some(u) = a.argument() {
                        walk(u, out);
                    }
                }
            }
        }
    }
    let mut out = Vec::new();
    for e in exprs {
        walk(e, &mut out);
    }
    out.sort_unstable();
    out.dedup();
    out
}

/// A random value per leaf: parameters in [0.5, 2], coordinates and
/// velocities in [−1.5, 1.5], t in [0, 2].
fn random_point(vars: &[Var], rng: &mut SplitMix64) -> FxHashMap<Var, f64> {
    // drawn in the order of the leaves' names, not of their interning
    // (which depends on what other tests interned first): a failing case
    // replays in any process
    let mut by_name: Vec<Var> = vars.to_vec();
    by_name.sort_by_key(|&v| qdot::expr::print::atom_input(&atom::atom(v)));
    by_name
        .iter()
        .map(|&v| {
            let x = match atom::atom(v) {
                Atom::Param(_) | Atom::Unknown(_) => rng.uniform(0.5, 2.0),
                Atom::Time => rng.uniform(0.0, 2.0),
                _ => rng.uniform(-1.5, 1.5),
            };
            (v, x)
        })
        .collect()
}

fn tree_eval(e: &Expr, at: &FxHashMap<Var, f64>) -> f64 {
    let env = |a: &Atom| -> Option<f64> {
        match a {
            Atom::Param(_) | Atom::Unknown(_) | Atom::Coord(..) | Atom::Time => {
                let v = match a {
                    Atom::Param(n) => atom::param(n),
                    Atom::Unknown(n) => atom::unknown(n),
                    Atom::Coord(n, k) => atom::coord(n, *k),
                    _ => atom::time(),
                };
                at.get(&v).copied()
            }
            _ => None,
        }
    };
    e.eval_f64(&env).unwrap_or(f64::NAN)
}

/// Σ|term| / |Σ term| of numerator and denominator at the point: how much
/// evaluating the expanded form may cancel (1 when nothing cancels).
fn condition(e: &Expr, at: &FxHashMap<Var, f64>) -> f64 {
    sum_condition(e, at) * nested_condition(e, at)
}

/// The cancellation of `e`'s own sums: Σ|terms| / |Σ terms| of its
/// numerator and denominator.
fn sum_condition(e: &Expr, at: &FxHashMap<Var, f64>) -> f64 {
    let part = |p: &Poly| {
        let (mut sum, mut abs) = (0.0f64, 0.0f64);
        for (m, c) in p.terms() {
            let mut t = c.to_f64();
            for &(v, k) in m.0.iter() {
                t *= tree_eval(&Expr::var(v), at).powi(k as i32);
            }
            sum += t;
            abs += t.abs();
        }
        abs / sum.abs().max(f64::MIN_POSITIVE)
    };
    part(e.num()).max(part(e.den())).max(1.0)
}

/// The worst cancellation inside a function's argument, at any depth
/// (`sin(u)` with u = a − b nearly equal): the compiled program and the
/// tree walk round u differently, and the function carries that relative
/// error on. The tree walk's inputs-only sensitivity cannot see it.
fn nested_condition(e: &Expr, at: &FxHashMap<Var, f64>) -> f64 {
    let mut worst = 1.0f64;
    for v in e.vars() {
        for w in std::iter::once(v).chain(atom::inner_atoms(v).iter().copied()) {
            if let Some(u) = atom::atom(w).argument() {
                worst = worst.max(sum_condition(u, at));
            }
        }
    }
    worst
}

/// Σ_v |∂ log e/∂ log v| at the point, by finite differences: how much the
/// rounding of the inputs (and of a function's argument near a zero of
/// the function, `cos u` at u ≈ π/2) is amplified in the value.
fn sensitivity(e: &Expr, at: &FxHashMap<Var, f64>, value: f64) -> f64 {
    const H: f64 = 1e-7;
    let mut total = 0.0;
    for (&v, &x) in at {
        let mut moved = at.clone();
        moved.insert(v, x * (1.0 + H));
        let change = (tree_eval(e, &moved) - value).abs() / value.abs().max(f64::MIN_POSITIVE);
        if change.is_finite() {
            total += change / H;
        }
    }
    total
}

/// Compare the compiled program with the tree walk at `points` random
/// points, relative tolerance 1e-12 times the condition of the expanded
/// form or of the expression itself, whichever is larger; returns the
/// largest relative error seen.
fn check_program(exprs: &[Expr], points: usize, seed: u64) -> f64 {
    let inputs = leaves(exprs);
    let prog = compile(exprs, &inputs).expect("compiles");
    let mut regs = prog.registers();
    let mut out = vec![0.0; exprs.len()];
    let mut rng = SplitMix64::new(seed);
    let mut worst = 0.0f64;
    for _ in 0..points {
        let at = random_point(&inputs, &mut rng);
        let x: Vec<f64> = inputs.iter().map(|v| at[v]).collect();
        prog.eval(&x, &mut regs, &mut out);
        for (e, &got) in exprs.iter().zip(&out) {
            let want = tree_eval(e, &at);
            let scale = want.abs().max(got.abs()).max(f64::MIN_POSITIVE);
            let rel = (got - want).abs() / scale;
            let tol = 1e-12 * condition(e, &at).max(sensitivity(e, &at, want));
            assert!(
                rel <= tol,
                "{e}: compiled {got}, tree walk {want} (relative {rel:e} > {tol:e})"
            );
            worst = worst.max(rel);
        }
    }
    worst
}

fn example(name: &str) -> Scene {
    let path = format!("{}/examples/{name}.qd", env!("QDOT_ROOT"));
    let src = std::fs::read_to_string(path).expect("example exists");
    Scene::parse(&src).expect("example parses")
}

fn chain(n: usize) -> Lagrange {
    Scene::parse(&qdot::engine::gallery::pendulum_chain(n))
        .expect("chain parses")
        .lagrange()
        .expect("chain derives")
}

fn parts(l: &Lagrange) -> Vec<Expr> {
    let mut v: Vec<Expr> = l.mass_matrix.iter().flatten().cloned().collect();
    v.extend(l.forcing.iter().cloned());
    v
}

#[test]
fn seed_examples_agree_with_tree_walk() {
    let mut dynamic = 0;
    for name in qdot::engine::gallery::SEED_EXAMPLES {
        let s = example(name);
        if !s.has_dynamics() {
            continue;
        }
        dynamic += 1;
        let l = s.lagrange().expect("derives");
        check_program(&parts(&l), 20, 1);
        let acc: Vec<Expr> = l
            .accelerations()
            .expect("accelerations")
            .into_iter()
            .map(|(_, e)| e)
            .collect();
        check_program(&acc, 20, 2);
    }
    assert!(dynamic >= 8, "only {dynamic} seed examples have dynamics");
}

#[test]
fn chain_agrees_with_tree_walk() {
    for n in [3, 5, 10] {
        let l = chain(n);
        check_program(&parts(&l), 10, n as u64);
    }
    let l = chain(3);
    let acc: Vec<Expr> = l
        .accelerations()
        .expect("accelerations")
        .into_iter()
        .map(|(_, e)| e)
        .collect();
    check_program(&acc, 20, 7);
}

#[test]
fn bound_parameters_fold_into_constants() {
    let l = chain(3);
    let exprs = parts(&l);
    let (m, len, g) = (atom::param("m"), atom::param("l"), atom::param("g"));
    let params: FxHashMap<Var, f64> = [(m, 1.5), (len, 0.7), (g, 9.81)].into_iter().collect();
    let inputs: Vec<Var> = leaves(&exprs)
        .into_iter()
        .filter(|v| !params.contains_key(v))
        .collect();
    let bound = compile_with(&exprs, &inputs, &params).expect("compiles");
    assert_eq!(bound.n_inputs(), 6);
    // Unbound, a parameter is an error unless it is an input.
    let err = compile(&exprs, &inputs).expect_err("m, l, g are unbound");
    assert!(
        matches!(&err, CompileError::UnsetParameter(p) if ["m", "l", "g"].contains(&p.as_str())),
        "{err:?}"
    );
    assert!(
        err.to_string()
            .ends_with(" has no value and is not an input"),
        "{err}"
    );
    let mut rng = SplitMix64::new(11);
    let mut regs = bound.registers();
    let mut out = vec![0.0; exprs.len()];
    for _ in 0..10 {
        let mut at = random_point(&inputs, &mut rng);
        let x: Vec<f64> = inputs.iter().map(|v| at[v]).collect();
        bound.eval(&x, &mut regs, &mut out);
        at.extend(params.iter().map(|(k, v)| (*k, *v)));
        for (e, &got) in exprs.iter().zip(&out) {
            let want = tree_eval(e, &at);
            assert!(
                (got - want).abs() <= 1e-12 * condition(e, &at) * want.abs().max(got.abs()),
                "{e}: {got} vs {want}"
            );
        }
    }
    // Constants only: π, √2, sin(1/3) all fold.
    let c = Expr::pi()
        .mul(&func::sqrt(&Expr::int(2)).expect("√2"))
        .add(&func::sin(&Expr::rational(
            qdot::num::Q::new(1, 3).expect("1/3"),
        )));
    let p = compile(std::slice::from_ref(&c), &[]).expect("compiles");
    assert!(p.instructions().is_empty(), "{:?}", p.instructions());
    let mut out = [0.0];
    p.eval(&[], &mut p.registers(), &mut out);
    let want = std::f64::consts::PI * 2f64.sqrt() + (1.0f64 / 3.0).sin();
    assert!((out[0] - want).abs() < 1e-15);
}

fn count(p: &Program, f: impl Fn(&Instr) -> bool) -> usize {
    p.instructions().iter().filter(|i| f(i)).count()
}

#[test]
fn common_subexpressions_are_shared() {
    let l = chain(10);
    let exprs = parts(&l);
    let inputs = leaves(&exprs);
    let prog = compile(&exprs, &inputs).expect("compiles");
    let naive = naive_op_count(&exprs);
    let (add, mul, div, fun) = prog.op_counts();
    let ours = add + mul + div + fun;
    let ratio = naive as f64 / ours as f64;
    println!(
        "10-link chain M and f: {} instructions, {ours} operations ({add} add, {mul} mul, {div} div, {fun} calls), naive tree walk {naive} operations: ratio {ratio:.1}",
        prog.instructions().len()
    );
    // Measured: 653 operations against 5170 (ratio 7.9), 263 instructions.
    assert!(
        ratio > 7.0,
        "only {ratio:.1}× fewer operations than the tree walk"
    );
    assert!(
        prog.instructions().len() < 300,
        "{} instructions",
        prog.instructions().len()
    );
    // Ten angles: ten sin_cos, no lone sin or cos.
    assert_eq!(count(&prog, |i| matches!(i, Instr::SinCos { .. })), 10);
    assert_eq!(
        count(&prog, |i| matches!(
            i,
            Instr::Sin { .. } | Instr::Cos { .. }
        )),
        0
    );
    // No division: the chain's M and f are polynomials.
    assert_eq!(prog.op_counts().2, 0);
    // Topological order: every operand register is written before it is
    // read (constants and inputs are preloaded).
    let fixed = prog.constants().len() + prog.n_inputs();
    let mut written = vec![false; prog.n_registers()];
    written[..fixed].iter_mut().for_each(|w| *w = true);
    for i in prog.instructions() {
        let (reads, writes): (Vec<u32>, Vec<u32>) = match *i {
            Instr::Add { dst, a, b }
            | Instr::Sub { dst, a, b }
            | Instr::Mul { dst, a, b }
            | Instr::Div { dst, a, b } => (vec![a, b], vec![dst]),
            Instr::MulAdd { dst, a, b, c } => (vec![a, b, c], vec![dst]),
            Instr::Dot {
                dst,
                init,
                start,
                len,
            } => {
                let mut reads: Vec<u32> = prog.pairs()[start as usize..(start + len) as usize]
                    .iter()
                    .flat_map(|&(a, b)| [a, b])
                    .collect();
                if init != u32::MAX {
                    reads.push(init);
                }
                (reads, vec![dst])
            }
            Instr::SinCos { sin, cos, a } => (vec![a], vec![sin, cos]),
            Instr::Neg { dst, a }
            | Instr::Powi { dst, a, .. }
            | Instr::Sin { dst, a }
            | Instr::Cos { dst, a }
            | Instr::Exp { dst, a }
            | Instr::Ln { dst, a }
            | Instr::Sqrt { dst, a }
            | Instr::Atan { dst, a }
            | Instr::Asin { dst, a }
            | Instr::Acos { dst, a } => (vec![a], vec![dst]),
        };
        for r in reads {
            assert!(written[r as usize], "register {r} read before written");
        }
        for w in writes {
            assert!(w as usize >= fixed, "constant or input overwritten");
            written[w as usize] = true;
        }
    }
    // Register reuse keeps the file small.
    assert!(
        prog.n_registers() < ours,
        "{} registers",
        prog.n_registers()
    );
}

#[test]
fn one_sin_cos_per_angle_and_shared_denominator() {
    let x = Expr::coord("x", 0);
    let a = Expr::param("a");
    let (s, c) = func::sin_cos(&x);
    let den = a.add(&c.mul(&c)).add(&Expr::int(2)); // a + cos² x + 2 = a + 3 − sin² x
    let e1 = s.div(&den).expect("nonzero");
    let e2 = c.div(&den).expect("nonzero");
    let inputs = [atom::coord("x", 0), atom::param("a")];
    let p = compile(&[e1.clone(), e2.clone()], &inputs).expect("compiles");
    assert_eq!(count(&p, |i| matches!(i, Instr::SinCos { .. })), 1);
    assert_eq!(count(&p, |i| matches!(i, Instr::Div { .. })), 2);
    // The denominator a + 3 − sin² x once: sin² one powi.
    assert_eq!(count(&p, |i| matches!(i, Instr::Powi { .. })), 1);
    check_program(&[e1, e2], 20, 3);
}

#[test]
fn compiled_dynamics_matches_exact_accelerations() {
    let dp = Scene::parse(
        "coordinates a, b\nparameters m1, m2, l1, l2, g\n\
         x1 = l1*sin(a)\ny1 = -l1*cos(a)\nx2 = x1 + l2*sin(b)\ny2 = y1 - l2*cos(b)\n\
         kinetic E = 1/2*m1*(x1'^2 + y1'^2) + 1/2*m2*(x2'^2 + y2'^2)\n\
         potential V = m1*g*y1 + m2*g*y2\n",
    )
    .expect("parses")
    .lagrange()
    .expect("derives");
    let dp_params = [
        ("m1", 1.3),
        ("m2", 0.8),
        ("l1", 1.1),
        ("l2", 0.6),
        ("g", 9.81),
    ];
    for (l, params) in [
        (dp, &dp_params[..]),
        (chain(3), &[("m", 1.2), ("l", 0.9), ("g", 9.81)][..]),
        (chain(5), &[("m", 1.2), ("l", 0.9), ("g", 9.81)][..]),
    ] {
        let n = l.coordinates.len();
        let map: FxHashMap<Var, f64> = params.iter().map(|(k, v)| (atom::param(k), *v)).collect();
        let acc = l.accelerations().expect("accelerations");
        let mut via_m = CompiledDynamics::new(&l, &map).expect("compiles");
        let mut via_acc = CompiledDynamics::from_accelerations(&l, &map).expect("compiles");
        assert!(!via_m.constant_mass());
        let mut rng = SplitMix64::new(5);
        for _ in 0..10 {
            let q: Vec<f64> = (0..n).map(|_| rng.uniform(-1.5, 1.5)).collect();
            let qd: Vec<f64> = (0..n).map(|_| rng.uniform(-1.5, 1.5)).collect();
            let mut at = map.clone();
            for (i, c) in l.coordinates.iter().enumerate() {
                at.insert(atom::coord(c, 0), q[i]);
                at.insert(atom::coord(c, 1), qd[i]);
            }
            let (mut a1, mut a2) = (vec![0.0; n], vec![0.0; n]);
            via_m.accelerations(0.0, &q, &qd, &mut a1).expect("solves");
            via_acc
                .accelerations(0.0, &q, &qd, &mut a2)
                .expect("evaluates");
            let mut y: Vec<f64> = q.clone();
            y.extend(&qd);
            let mut dy = vec![0.0; 2 * n];
            via_m.rhs(0.0, &y, &mut dy);
            assert_eq!(&dy[..n], &qd[..]);
            for i in 0..n {
                let want = tree_eval(&acc.values()[i], &at);
                let tol = 1e-9 * want.abs().max(1.0);
                assert!((a1[i] - want).abs() <= tol, "M⁻¹f: {} vs {want}", a1[i]);
                assert!((a2[i] - want).abs() <= tol, "exact: {} vs {want}", a2[i]);
                assert_eq!(dy[n + i], a1[i]);
            }
        }
    }
}

#[test]
fn constant_mass_matrix_is_factored_once() {
    // Two masses on springs: M = diag(m1, m2) + coupling through E.
    let l = Scene::parse(
        "coordinates x, y\nparameters m, k\n\
         kinetic E = 1/2*m*x'^2 + 1/2*m*(x' + y')^2\n\
         potential V = 1/2*k*x^2 + 1/2*k*(y - x)^2 + 1/2*k*y^2*x^2\n",
    )
    .expect("parses")
    .lagrange()
    .expect("derives");
    let map: FxHashMap<Var, f64> = [(atom::param("m"), 2.0), (atom::param("k"), 3.0)]
        .into_iter()
        .collect();
    let mut d = CompiledDynamics::new(&l, &map).expect("compiles");
    assert!(d.constant_mass());
    assert_eq!(d.program().n_outputs(), 2);
    let acc = l.accelerations().expect("accelerations");
    let (q, qd) = ([0.3, -0.7], [0.1, 0.2]);
    let mut a = [0.0; 2];
    d.accelerations(0.0, &q, &qd, &mut a).expect("solves");
    let mut at = map.clone();
    at.insert(atom::coord("x", 0), q[0]);
    at.insert(atom::coord("y", 0), q[1]);
    for i in 0..2 {
        let want = tree_eval(&acc.values()[i], &at);
        assert!((a[i] - want).abs() < 1e-13 * want.abs().max(1.0), "{a:?}");
    }
}

#[test]
fn solve_spd_agrees_with_multiplication() {
    let mut rng = SplitMix64::new(9);
    for n in 1..8 {
        // A = B·Bᵀ + I (SPD) and a symmetric indefinite matrix.
        let b: Vec<f64> = (0..n * n).map(|_| rng.uniform(-1.0, 1.0)).collect();
        for spd in [true, false] {
            let mut a = vec![0.0; n * n];
            for i in 0..n {
                for j in 0..n {
                    a[i * n + j] = if spd {
                        (0..n).map(|k| b[i * n + k] * b[j * n + k]).sum::<f64>()
                            + if i == j { 1.0 } else { 0.0 }
                    } else {
                        b[i * n + j] + b[j * n + i]
                    };
                }
            }
            let x: Vec<f64> = (0..n).map(|_| rng.uniform(-1.0, 1.0)).collect();
            let mut f: Vec<f64> = (0..n)
                .map(|i| (0..n).map(|j| a[i * n + j] * x[j]).sum())
                .collect();
            let mut m = a.clone();
            solve_spd(&mut m, &mut f, n).expect("nonsingular");
            for i in 0..n {
                assert!(
                    (f[i] - x[i]).abs() < 1e-9,
                    "n = {n}, spd = {spd}: {f:?} vs {x:?}"
                );
            }
        }
    }
}

/// Random expressions over x, y (coordinates) and a, b (parameters) from
/// Expr's operations: sums, products, quotients, sin/cos of sums, √.
pub(crate) fn random_expr() -> impl Strategy<Value = Expr> {
    let leaf = prop_oneof![
        (1i64..6).prop_map(Expr::int),
        Just(Expr::coord("x", 0)),
        Just(Expr::coord("y", 0)),
        Just(Expr::param("a")),
        Just(Expr::param("b")),
        Just(Expr::pi()),
    ];
    leaf.prop_recursive(4, 24, 2, |inner| {
        prop_oneof![
            (inner.clone(), inner.clone()).prop_map(|(l, r)| l.add(&r)),
            (inner.clone(), inner.clone()).prop_map(|(l, r)| l.sub(&r)),
            (inner.clone(), inner.clone()).prop_map(|(l, r)| l.mul(&r)),
            // Divide by a positive denominator: 1 + a + r² > 0.
            (inner.clone(), inner.clone()).prop_map(|(l, r)| {
                let d = Expr::one().add(&Expr::param("a")).add(&r.mul(&r));
                l.div(&d).unwrap_or(l)
            }),
            (inner.clone(), inner.clone()).prop_map(|(l, r)| func::sin(&l.add(&r))),
            (inner.clone(), inner.clone()).prop_map(|(l, r)| func::cos(&l.sub(&r))),
            inner
                .clone()
                .prop_map(|u| func::sqrt(&Expr::param("b").add(&u.mul(&u))).unwrap_or(u)),
        ]
    })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: crate::common::proptest_cases(200), ..ProptestConfig::default() })]
    #[test]
    fn random_expressions_agree(es in prop::collection::vec(random_expr(), 1..4), seed in 0u64..1000) {
        check_program(&es, 3, seed);
    }
}

#[test]
fn elementary_functions_and_time() {
    let (x, y, a, t) = (
        Expr::coord("x", 0),
        Expr::coord("y", 1),
        Expr::param("a"),
        Expr::time(),
    );
    let third = Expr::rational(qdot::num::Q::new(1, 3).expect("1/3"));
    let exprs = vec![
        func::exp(&x.neg()).mul(&t),
        func::ln(&a.add(&x.mul(&x))).expect("ln"),
        func::atan(&x.mul(&y)),
        func::asin(&x.mul(&third)).expect("asin"),
        func::acos(&y.mul(&third)).expect("acos"),
        func::sin(&a).mul(&func::cos(&t)),
    ];
    let worst = check_program(&exprs, 30, 21);
    assert!(worst < 1e-14, "{worst:e}");
    let inputs = leaves(&exprs);
    let p = compile(&exprs, &inputs).expect("compiles");
    for want in [
        |i: &Instr| matches!(i, Instr::Exp { .. }),
        |i: &Instr| matches!(i, Instr::Ln { .. }),
        |i: &Instr| matches!(i, Instr::Atan { .. }),
        |i: &Instr| matches!(i, Instr::Asin { .. }),
        |i: &Instr| matches!(i, Instr::Acos { .. }),
    ] {
        assert_eq!(count(&p, want), 1, "{:?}", p.instructions());
    }
    // sin a and cos t alone: no pair to share.
    assert_eq!(count(&p, |i| matches!(i, Instr::Sin { .. })), 1);
    assert_eq!(count(&p, |i| matches!(i, Instr::Cos { .. })), 1);
    // With a bound, sin a is a constant.
    let params: FxHashMap<Var, f64> = [(atom::param("a"), 0.8)].into_iter().collect();
    let free: Vec<Var> = inputs
        .iter()
        .copied()
        .filter(|v| *v != atom::param("a"))
        .collect();
    let bound = compile_with(&exprs, &free, &params).expect("compiles");
    assert_eq!(count(&bound, |i| matches!(i, Instr::Sin { .. })), 0);
    assert_eq!(bound.n_inputs(), free.len());
}

#[test]
fn dead_code_is_removed() {
    // (a − 2)·sin x + y with a = 2: sin x is lowered, then its term folds
    // to zero; no instruction computes it.
    let (x, y, a) = (Expr::coord("x", 0), Expr::coord("y", 0), Expr::param("a"));
    let e = a.sub(&Expr::int(2)).mul(&func::sin(&x)).add(&y);
    let params: FxHashMap<Var, f64> = [(atom::param("a"), 2.0)].into_iter().collect();
    let p = compile_with(
        std::slice::from_ref(&e),
        &[atom::coord("x", 0), atom::coord("y", 0)],
        &params,
    )
    .expect("compiles");
    assert!(p.instructions().is_empty(), "{:?}", p.instructions());
    let mut out = [0.0];
    p.eval(&[0.3, 1.25], &mut p.registers(), &mut out);
    assert_eq!(out[0], 1.25);
}

fn chain_params() -> FxHashMap<Var, f64> {
    [("m", 1.0), ("l", 1.0), ("g", 9.81)]
        .iter()
        .map(|(k, v)| (atom::param(k), *v))
        .collect()
}

#[test]
fn best_evaluator_by_estimated_cost() {
    // 1 dof, the pendulum: M = m·l² is constant; the exact acceleration
    // −g/l·sin q1 is the forcing's program (one multiplication, one sin:
    // 1 + 20) without the product by the kept M⁻¹ (n² + n(n − 1) = 1 flop).
    let (d, c) = CompiledDynamics::best(&chain(1), &chain_params()).expect("compiles");
    assert_eq!(c.evaluator, Evaluator::Accelerations);
    assert_eq!(d.evaluator(), Evaluator::Accelerations);
    assert_eq!(c.accelerations_cost, Some(21.0));
    assert_eq!(c.mass_cost, 22.0);
    assert!(c.reason.contains("constant M"), "{}", c.reason);

    // The double pendulum: the exact accelerations (a common determinant,
    // Cramer numerators) cost more than M, f and a 2×2 Cholesky (measured:
    // a tie within 3 %, ≈ 133 ns each; see the report).
    let (d, c) = CompiledDynamics::best(&chain(2), &chain_params()).expect("compiles");
    assert_eq!(c.evaluator, Evaluator::MassMatrix);
    assert_eq!(d.evaluator(), Evaluator::MassMatrix);
    let acc = c.accelerations_cost.expect("derived for n = 2");
    assert!(acc > c.mass_cost, "{c:?}");
    // the solve's share: n³/3 + 2n² = 8/3 + 8 flops, n(n − 1)/2 + 2n = 5
    // divisions and n = 2 square roots of 4, n² + n = 6 copies
    let via_m = CompiledDynamics::new(&chain(2), &chain_params()).expect("compiles");
    let (a, m, dv, calls) = via_m.program().op_counts();
    let program = (a + m) as f64 + 4.0 * dv as f64 + 20.0 * calls as f64;
    assert!((c.mass_cost - program - (8.0 / 3.0 + 8.0 + 28.0 + 6.0)).abs() < 1e-12);

    // The 10-link chain: beyond BEST_MAX_N = 3, nothing more is derived.
    let (d, c) = CompiledDynamics::best(&chain(10), &chain_params()).expect("compiles");
    assert_eq!(c.evaluator, Evaluator::MassMatrix);
    assert_eq!(d.n(), 10);
    assert_eq!(c.accelerations_cost, None);
    assert!(c.reason.contains("10 coordinates"), "{}", c.reason);

    // Seed 24.2: M constant; the exact accelerations fold M⁻¹ into the
    // coefficients of the same linear forcing, so they win by exactly the
    // product by the kept M⁻¹: n² + n(n − 1) = 6 flops.
    let l = example("seed_24_2").lagrange().expect("derives");
    let params: FxHashMap<Var, f64> = [("m", 1.0), ("k", 6.0), ("R", 0.5)]
        .iter()
        .map(|(k, v)| (atom::param(k), *v))
        .collect();
    let via_m = CompiledDynamics::new(&l, &params).expect("compiles");
    assert_eq!(via_m.evaluator(), Evaluator::ConstantMass);
    let (d, c) = CompiledDynamics::best(&l, &params).expect("compiles");
    assert_eq!(c.evaluator, Evaluator::Accelerations);
    assert_eq!(d.evaluator(), Evaluator::Accelerations);
    let acc = c.accelerations_cost.expect("derived");
    assert_eq!(acc + 6.0, c.mass_cost, "{c:?}");
}

#[test]
fn both_evaluators_give_the_same_double_pendulum_trajectory() {
    use qdot::simulate::{integrate, problems::Problem, IntegratorOptions, Method};
    let p = Problem::double_pendulum();
    let l = Scene::parse(&p.scene)
        .expect("parses")
        .lagrange()
        .expect("derives");
    let params = p.param_map();
    let mut via_m = CompiledDynamics::new(&l, &params).expect("compiles");
    let mut via_acc = CompiledDynamics::from_accelerations(&l, &params).expect("compiles");
    assert_eq!(via_m.evaluator(), Evaluator::MassMatrix);
    assert_eq!(via_acc.evaluator(), Evaluator::Accelerations);
    let opts = IntegratorOptions {
        t_end: p.t_end,
        rtol: 1e-10,
        atol: 1e-10,
        t_out: (0..=100).map(|i| p.t_end * i as f64 / 100.0).collect(),
        ..IntegratorOptions::default()
    };
    let a = integrate(&mut via_m, Method::Dop853, &p.y0, &opts).expect("integrates");
    let b = integrate(&mut via_acc, Method::Dop853, &p.y0, &opts).expect("integrates");
    assert_eq!(a.t.len(), 101);
    assert_eq!(a.t, b.t);
    let mut worst: f64 = 0.0;
    for (ya, yb) in a.y.iter().zip(&b.y) {
        for (u, v) in ya.iter().zip(yb) {
            worst = worst.max((u - v).abs());
        }
    }
    assert!(worst < 1e-9, "largest difference {worst:e}");
    // the trajectory moves: not a trivially equal pair of constants
    assert!((a.y[100][0] - p.y0[0]).abs() > 1e-2);
}

/// A whole power compiles to binary powering, exact for small exponents as
/// repeated multiplication is (the register program's `powi`).
#[test]
fn whole_powers_are_repeated_multiplication() {
    let x = Expr::coord("x", 0);
    let exprs: Vec<Expr> = (0..12)
        .chain([17, 31])
        .map(|n| x.powi(n).expect("a power"))
        .collect();
    let inputs = leaves(&exprs);
    let prog = compile(&exprs, &inputs).expect("compiles");
    let mut regs = prog.registers();
    let mut out = vec![0.0; exprs.len()];
    for at in [1.3f64, -0.7, 2.0] {
        let point: Vec<f64> = inputs.iter().map(|_| at).collect();
        prog.eval(&point, &mut regs, &mut out);
        for (n, got) in (0..12).chain([17, 31]).zip(&out) {
            let mut want = 1.0f64;
            for _ in 0..n {
                want *= at;
            }
            assert!(
                (got - want).abs() <= 1e-14 * want.abs(),
                "{at}^{n}: compiled {got}, repeated multiplication {want}"
            );
        }
    }
}
