//! The context installs the thread-local state, the engine checks it:
//! the engine's functions that decide signs refuse to run without the
//! scene's assumptions (rather than decide a sign for positive parameters
//! where the scene assumes otherwise), `Scene::assumptions_in_force` is the
//! library user's door, and `budget::probe` nests a trial budget inside
//! the one in force.

use qdot::solve::equilibrium::Values;
use qdot::{budget, Scene, Stability};

/// `k` of either sign: x = 0 is stable only when k > 0.
const EITHER_SIGN: &str = "coordinates x\nparameters m, k\nassume k real\nkinetic T = 1/2*m*x'^2\npotential V = 1/2*k*x^2\n";

#[cfg(not(debug_assertions))]
const REFUSAL: &str =
    "the search for equilibria needs the scene's assumptions (`assume …`) in force, and they are not";

// a debug build asserts instead (debug_assert!): a bug in the caller
#[cfg(not(debug_assertions))]
#[test]
fn the_engine_refuses_without_the_scenes_assumptions() {
    let s = Scene::parse(EITHER_SIGN).expect("the scene");
    let d = qdot::equilibria(&s, &Values::new()).expect_err("no assumptions in force");
    assert_eq!(d.message, REFUSAL);
    assert_eq!(d.kind().name(), "internal");
    // another scene's assumptions (none) in force: refused too
    let other =
        Scene::parse("coordinates x\nparameters m\nkinetic T = 1/2*m*x'^2\n").expect("the scene");
    let d = other.assumptions_in_force(|| qdot::equilibria(&s, &Values::new()));
    assert_eq!(d.expect_err("not this scene's").message, REFUSAL);
    let d = qdot::modes(&s, None, &Values::new()).expect_err("no assumptions in force");
    assert_eq!(
        d.message,
        "small oscillations needs the scene's assumptions (`assume …`) in force, and they are not"
    );
}

#[test]
fn with_the_scenes_assumptions_the_answer_is_the_commands() {
    let s = Scene::parse(EITHER_SIGN).expect("the scene");
    let eq = s
        .assumptions_in_force(|| qdot::equilibria(&s, &Values::new()))
        .expect("equilibria");
    assert_eq!(eq.equilibria.len(), 1);
    // undecided, as `qdot equilibrium` says: never "stable" for k > 0 alone
    assert!(
        matches!(&eq.equilibria[0].stability, Stability::Undecided(_)),
        "{:?}",
        eq.equilibria[0].stability
    );
    let ctx = qdot::Context::new();
    let report = qdot::app::equilibria(&ctx, EITHER_SIGN, &Values::new()).expect("the command");
    let out =
        qdot::render(&qdot::AnyReport::Equilibrium(report), qdot::Format::Text).expect("text");
    assert!(
        out.contains(
            "1. x = 0  — undecided (stable when k > 0, unstable when < 0; give values with --set)"
        ),
        "{out}"
    );
}

#[test]
fn a_probe_nests_inside_the_budget_in_force() {
    // the smaller of the two applies
    assert_eq!(
        budget::within(100, || budget::probe(10_000, budget::limit)),
        Ok(Ok(100))
    );
    assert_eq!(
        budget::within(10_000, || budget::probe(100, budget::limit)),
        Ok(Ok(100))
    );
    // past the probe's budget: an error for the caller, the outer goes on
    let r = budget::within(10_000, || {
        let probe = budget::probe(10, || budget::check_terms(50));
        (probe.map_err(|e| (e.terms, e.limit)), budget::limit())
    });
    assert_eq!(r, Ok((Err((50, 10)), 10_000)));
}
