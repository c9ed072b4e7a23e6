//! The machine code (`simulate::compile::jit`, feature `jit`) against its
//! oracle, the interpreter: every scene of examples/, every problem of the
//! work-precision report, the pendulum chains and random expressions,
//! evaluated at random states by both; the results agree bit for bit (the
//! generated code does the interpreter's operations in the interpreter's
//! order, with no fused multiply-add). And the fallbacks: a mass matrix
//! that is not positive definite, `--evaluator` on the command line.

use crate::compile::random_expr;
use proptest::prelude::*;
use qdot::engine::poly::Var;
use qdot::expr::atom;
use qdot::expr::func;
use qdot::simulate::compile::jit::{compile_program, compile_rhs, Tail};
use qdot::simulate::compile::{compile, CompiledDynamics, Engine};
use qdot::simulate::problems::Problem;
use qdot::simulate::{constrained, System};
use qdot::{Expr, Lagrange, Scene};
use qdot_exact::rng::SplitMix64;
use rustc_hash::FxHashMap;
use std::process::Command;

/// Equal bits, or both NaN.
fn same(a: f64, b: f64) -> bool {
    a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan())
}

/// `d` on the JIT against the interpreter at `points` random states;
/// returns how many states had finite derivatives.
fn check_dynamics(d: &mut CompiledDynamics, what: &str, points: usize, seed: u64) -> usize {
    let report = d.use_engine(Engine::Jit);
    assert_eq!(report.ran, Engine::Jit, "{what}: {:?}", report.reason);
    assert_eq!(d.engine(), Engine::Jit);
    let n = d.n();
    let mut rng = SplitMix64::new(seed);
    let mut finite = 0;
    for _ in 0..points {
        let y: Vec<f64> = (0..2 * n).map(|_| rng.uniform(-1.5, 1.5)).collect();
        let t = rng.uniform(0.0, 2.0);
        let (mut a, mut b) = (vec![0.0; 2 * n], vec![0.0; 2 * n]);
        d.rhs(t, &y, &mut a);
        d.rhs_interpreted(t, &y, &mut b);
        for k in 0..2 * n {
            assert!(
                same(a[k], b[k]),
                "{what} ({:?}) at t = {t}, y = {y:?}: component {k}: jit {} vs interpreter {}",
                d.evaluator(),
                a[k],
                b[k]
            );
        }
        finite += usize::from(a.iter().all(|x| x.is_finite()));
    }
    finite
}

/// Random values in [0.5, 2] for the scene's parameters, α = 1.
fn params_of(scene: &Scene, rng: &mut SplitMix64) -> FxHashMap<Var, f64> {
    let mut p: FxHashMap<Var, f64> = scene
        .parameters
        .iter()
        .map(|p| (atom::param(&p.name), rng.uniform(0.5, 2.0)))
        .collect();
    p.insert(constrained::alpha_var(), 1.0);
    p
}

/// Every form of `lag` that compiles: M and f (or the constant M), and the
/// exact accelerations for n ≤ 3.
fn forms(lag: &Lagrange, params: &FxHashMap<Var, f64>) -> Vec<CompiledDynamics> {
    let mut v = Vec::new();
    if let Ok(d) = CompiledDynamics::new(lag, params) {
        v.push(d);
    }
    if lag.coordinates.len() <= 3 {
        if let Ok(d) = CompiledDynamics::from_accelerations(lag, params) {
            v.push(d);
        }
    }
    v
}

#[test]
fn every_example_agrees_with_the_interpreter() {
    let dir = format!("{}/examples", env!("QDOT_ROOT"));
    let mut names: Vec<_> = std::fs::read_dir(&dir)
        .expect("examples/")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "qd"))
        .collect();
    names.sort();
    let (mut checked, mut finite) = (0, 0);
    let mut rng = SplitMix64::new(5);
    for path in names {
        let src = std::fs::read_to_string(&path).expect("reads");
        let Ok(scene) = Scene::parse(&src) else {
            continue;
        };
        if !scene.has_dynamics() {
            continue;
        }
        let Ok(lag) = scene.lagrange() else { continue };
        let Ok(lag) = constrained::stabilized(lag) else {
            continue;
        };
        let params = params_of(&scene, &mut rng);
        for mut d in forms(&lag, &params) {
            finite += check_dynamics(&mut d, &path.display().to_string(), 40, checked as u64);
            checked += 1;
        }
    }
    assert!(
        checked >= 30,
        "only {checked} forms of the examples compiled"
    );
    assert!(finite > 500, "only {finite} finite right-hand sides");
}

#[test]
fn report_problems_and_chains_agree_with_the_interpreter() {
    let mut evaluators = Vec::new();
    for p in Problem::all() {
        let mut d = p.dynamics().expect("compiles");
        evaluators.push(d.evaluator());
        let finite = check_dynamics(&mut d, p.name, 50, 11);
        assert_eq!(finite, 50, "{}", p.name);
        // and M, f (or the constant M) where `best` chose the accelerations
        let scene = Scene::parse(&p.scene).expect("parses");
        let lag = constrained::stabilized(scene.lagrange().expect("derives")).expect("stabilizes");
        let mut d = CompiledDynamics::new(&lag, &p.param_map()).expect("compiles");
        evaluators.push(d.evaluator());
        check_dynamics(&mut d, p.name, 50, 12);
    }
    // all three tails
    use qdot::simulate::compile::Evaluator;
    for e in [
        Evaluator::MassMatrix,
        Evaluator::ConstantMass,
        Evaluator::Accelerations,
    ] {
        assert!(evaluators.contains(&e), "no problem uses {e:?}");
    }
    let mut rng = SplitMix64::new(3);
    for src in [
        qdot::engine::gallery::pendulum_chain(10),
        qdot::engine::gallery::pendulum_chain(20),
        qdot::engine::gallery::rod_chain_3d(3),
    ] {
        let scene = Scene::parse(&src).expect("parses");
        let lag = scene.lagrange().expect("derives");
        let params = params_of(&scene, &mut rng);
        let mut d = CompiledDynamics::new(&lag, &params).expect("compiles");
        check_dynamics(&mut d, &src[..40.min(src.len())], 20, 4);
    }
}

/// A mass matrix that is singular where q = 0: the Cholesky pivot is 0,
/// the machine code says so and the interpreter's solve (Gaussian
/// elimination, then NaN) answers for that call.
#[test]
fn a_pivot_that_is_not_positive_falls_back_to_the_interpreter() {
    let q = Expr::coord("q", 0);
    let p = Expr::coord("p", 0);
    let mass = vec![
        vec![q.mul(&q), Expr::zero()],
        vec![Expr::zero(), Expr::int(1).add(&p.mul(&p))],
    ];
    let forcing = vec![Expr::int(1), q.clone()];
    let coords = vec!["q".to_string(), "p".to_string()];
    let mut d = CompiledDynamics::from_parts(&coords, &mass, &forcing, &FxHashMap::default())
        .expect("compiles");
    assert_eq!(d.use_engine(Engine::Jit).ran, Engine::Jit);
    // an indefinite M: Cholesky fails at column 0, elimination solves it
    let mass = vec![
        vec![q.clone(), Expr::int(2)],
        vec![Expr::int(2), Expr::int(1)],
    ];
    let mut e = CompiledDynamics::from_parts(&coords, &mass, &forcing, &FxHashMap::default())
        .expect("compiles");
    assert_eq!(e.use_engine(Engine::Jit).ran, Engine::Jit);
    for d in [&mut d, &mut e] {
        for y in [
            [0.0, 0.3, 0.1, 0.2],
            [-0.5, 0.3, 0.1, 0.2],
            [0.7, 0.3, 0.1, 0.2],
        ] {
            let (mut a, mut b) = ([0.0; 4], [0.0; 4]);
            d.rhs(0.0, &y, &mut a);
            d.rhs_interpreted(0.0, &y, &mut b);
            for k in 0..4 {
                assert!(same(a[k], b[k]), "{y:?}: {a:?} vs {b:?}");
            }
        }
    }
    let (mut a, y) = ([0.0; 4], [0.0, 0.3, 0.1, 0.2]);
    d.rhs(0.0, &y, &mut a);
    assert!(a[2].is_nan(), "{a:?}");
    e.rhs(0.0, &[-0.5, 0.3, 0.1, 0.2], &mut a);
    assert!(a[2].is_finite(), "{a:?}");
}

#[test]
fn large_programs_allocate_registers_in_one_pass() {
    use qdot::simulate::compile::jit::{estimated_size, FAST_ALLOCATION};
    let size = |p: Problem| {
        let d = p.dynamics().expect("compiles");
        estimated_size(d.program(), d.n(), Tail::MassMatrix)
    };
    assert!(size(Problem::chain10()) > FAST_ALLOCATION);
    assert!(size(Problem::double_pendulum()) < FAST_ALLOCATION / 4);
}

#[test]
fn the_interpreter_when_asked() {
    let p = Problem::pendulum();
    let mut d = p.dynamics().expect("compiles");
    let r = d.use_engine(Engine::Interpreter);
    assert_eq!(r.ran, Engine::Interpreter);
    assert_eq!(d.engine(), Engine::Interpreter);
    assert_eq!(Engine::by_name("JIT"), Some(Engine::Jit));
    assert_eq!(Engine::by_name("fast"), None);
    // a program whose shape is not the right-hand side's: an error, no panic
    let x = Expr::coord("x", 0);
    let prog = compile(std::slice::from_ref(&x), &[atom::coord("x", 0)]).expect("compiles");
    assert!(compile_rhs(&prog, 1, Tail::MassMatrix).is_err());
    assert!(compile_rhs(&prog, 2, Tail::ConstantMass(&[1.0])).is_err());
}

/// `program` compiled alone against the interpreter at `points` random
/// inputs, bit for bit.
fn check_program(exprs: &[Expr], points: usize, seed: u64) {
    let inputs = crate::compile::leaves(exprs);
    let p = compile(exprs, &inputs).expect("compiles");
    let j = compile_program(&p).expect("jit compiles");
    let mut rng = SplitMix64::new(seed);
    let (mut regs, mut a, mut b) = (
        p.registers(),
        vec![0.0; exprs.len()],
        vec![0.0; exprs.len()],
    );
    for _ in 0..points {
        let x: Vec<f64> = inputs.iter().map(|_| rng.uniform(-1.5, 1.5)).collect();
        p.eval(&x, &mut regs, &mut a);
        j.eval(&x, &mut b);
        for k in 0..a.len() {
            assert!(same(a[k], b[k]), "{}: {} vs {}", exprs[k], a[k], b[k]);
        }
    }
}

fn pw(x: &Expr, n: i64) -> Expr {
    x.powi(n).expect("power")
}

#[test]
fn elementary_functions_and_powers_agree() {
    let (x, y, a, t) = (
        Expr::coord("x", 0),
        Expr::coord("y", 1),
        Expr::param("a"),
        Expr::time(),
    );
    let third = Expr::rational(qdot::num::Q::new(1, 3).expect("1/3"));
    let exprs = vec![
        func::exp(&x.neg()).mul(&t),
        func::ln(&a.mul(&a).add(&x.mul(&x))).expect("ln"),
        func::atan(&x.mul(&y)),
        func::asin(&x.mul(&third)).expect("asin"),
        func::acos(&y.mul(&third)).expect("acos"),
        func::sin(&a).mul(&func::cos(&t)),
        func::sin(&x).mul(&func::cos(&x)).add(&pw(&y, 7)),
        pw(&x, 2).add(&pw(&y, 3)).add(&pw(&a, 4)).add(&pw(&t, 13)),
        func::sqrt(&a.mul(&a).add(&Expr::int(1))).expect("sqrt"),
    ];
    check_program(&exprs, 50, 9);
}

proptest! {
    #![proptest_config(ProptestConfig { cases: crate::common::proptest_cases(64), ..ProptestConfig::default() })]
    #[test]
    fn random_expressions_agree(es in prop::collection::vec(random_expr(), 1..4), seed in 0u64..1000) {
        check_program(&es, 4, seed);
    }
}

fn qdot(args: &[&str]) -> (bool, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_qdot"))
        .args(args)
        .output()
        .expect("runs");
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn simulate_evaluator_option() {
    let file = format!("{}/examples/pendulum.qd", env!("QDOT_ROOT"));
    let base = [
        "simulate",
        &file,
        "--set",
        "m=1,l=1,g=9.81",
        "--init",
        "theta=1,theta'=0",
        "--t-end",
        "2",
        "--stats",
    ];
    let mut outs = Vec::new();
    for (engine, word) in [
        ("jit", "machine code"),
        ("interpreter", "interpreter"),
        ("auto", "machine code"),
    ] {
        let mut args = base.to_vec();
        args.extend(["--evaluator", engine]);
        let (ok, out, err) = qdot(&args);
        assert!(ok, "{engine}: {err}");
        let all = format!("{out}{err}");
        assert!(all.contains(word), "{engine}: {all}");
        outs.push(
            out.lines()
                .take_while(|l| !l.starts_with("method"))
                .collect::<Vec<_>>()
                .join("\n"),
        );
    }
    // the same rows, digit for digit
    assert_eq!(outs[0], outs[1]);
    let mut args = base.to_vec();
    args.extend(["--evaluator", "fast"]);
    let (ok, _, err) = qdot(&args);
    assert!(!ok && err.contains("interpreter"), "{err}");
}

/// `auto` counts the right-hand sides of all clones of one compiled system
/// (a sweep's runs) and compiles once, in the clone that crosses
/// `AUTO_JIT_AFTER_CALLS`; the other clones adopt that machine code.
#[test]
fn auto_compiles_once_for_all_clones_after_enough_calls() {
    use qdot::simulate::compile::AUTO_JIT_AFTER_CALLS;
    let q = Expr::coord("q", 0);
    let mass = vec![vec![Expr::int(2).add(&q.mul(&q))]];
    let forcing = vec![q.neg()];
    let coords = vec!["q".to_string()];
    let mut a = CompiledDynamics::from_parts(&coords, &mass, &forcing, &FxHashMap::default())
        .expect("compiles");
    let report = a.use_engine(Engine::Auto);
    assert_eq!(report.ran, Engine::Interpreter);
    let mut b = a.clone();
    let (y, mut dy) = ([0.5, -0.25], [0.0; 2]);
    let half = AUTO_JIT_AFTER_CALLS / 2 + 1024;
    for _ in 0..half {
        a.rhs(0.0, &y, &mut dy);
    }
    assert!(a.deferred_engine().is_none(), "half the calls: not yet");
    assert_eq!(a.engine(), Engine::Interpreter);
    for _ in 0..half {
        b.rhs(0.0, &y, &mut dy);
    }
    let Some((report, compiled_here)) = b.deferred_engine() else {
        panic!("the calls of both clones add up past the threshold");
    };
    assert_eq!(
        (report.ran, report.requested, compiled_here),
        (Engine::Jit, Engine::Auto, true)
    );
    assert_eq!(b.engine(), Engine::Jit);
    // `a` adopts the same code at its next batch of calls
    for _ in 0..1024 {
        a.rhs(0.0, &y, &mut dy);
    }
    assert_eq!(a.engine(), Engine::Jit);
    assert!(matches!(a.deferred_engine(), Some((_, false))));
    // and computes what the interpreter computes
    let mut interpreted = [0.0; 2];
    a.rhs_interpreted(0.0, &y, &mut interpreted);
    a.rhs(0.0, &y, &mut dy);
    assert!(dy.iter().zip(&interpreted).all(|(x, y)| same(*x, *y)));
}
