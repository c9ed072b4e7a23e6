//! No input makes qdot panic: random bytes and random token sequences go
//! through the parser and the whole pipeline (derive, solve, print); every
//! failure must be a `Diagnostic`.

use proptest::prelude::*;
use qdot::Scene;

fn pipeline(src: &str) {
    let Ok(scene) = Scene::parse(src) else {
        return;
    };
    let Ok(l) = scene.lagrange() else {
        return;
    };
    let _ = qdot::output::derive_text(&l);
    if let Ok(acc) = l.accelerations() {
        let _ = qdot::output::solve_json(&l, &acc);
    }
}

const TOKENS: &[&str] = &[
    "coordinates",
    "parameters",
    "kinetic",
    "potential",
    "forcefunction",
    "work",
    "dissipation",
    "rayleigh",
    "force",
    "load",
    "torque",
    "solve",
    " at ",
    " on ",
    "at",
    "on",
    "x",
    "y",
    "a",
    "b",
    "t",
    "pi",
    "E",
    "V",
    "=",
    ":",
    ",",
    "+",
    "-",
    "*",
    "/",
    "^",
    "(",
    ")",
    "'",
    "''",
    "\n",
    " ",
    "#",
    "1",
    "2",
    "0",
    "0.5",
    "1e-3",
    "30deg",
    "°",
    "sin",
    "cos",
    "sqrt",
    "tan",
    "ln",
    "exp",
    "atan",
    "θ",
    ";",
    "[",
    "]",
    "[",
    "]",
    ",",
    "{",
    "}",
    "\"",
];

fn token_soup() -> impl Strategy<Value = String> {
    prop::collection::vec(prop::sample::select(TOKENS), 0..40).prop_map(|v| v.concat())
}

/// Mostly well-formed scenes with random right-hand sides.
fn near_scene() -> impl Strategy<Value = String> {
    (token_soup(), token_soup()).prop_map(|(a, b)| {
        format!("coordinates x, y\nparameters a, b\nkinetic E = 1/2*a*x'^2 + 1/2*b*y'^2 + {a}\npotential V = {b}\n")
    })
}

/// Small well-formed scalar expressions in the scene's names.
fn fragment() -> impl Strategy<Value = &'static str> {
    prop::sample::select(vec![
        "a", "b", "x", "y", "0", "1", "2", "-a*x", "sin(x)", "x'", "a + b", "b*y'", "cos(y)",
    ])
}

/// Well-formed scenes with random loads, torques and solve blocks (and,
/// now and then, a token soup in one place).
fn near_scene_with_new_statements() -> impl Strategy<Value = String> {
    (
        prop::collection::vec(fragment(), 6),
        token_soup(),
        0usize..7,
        prop::bool::weighted(0.2),
    )
        .prop_map(|(f, soup, at, spoil)| {
            let mut f: Vec<String> = f.into_iter().map(String::from).collect();
            if spoil {
                f[at.min(5)] = soup;
            }
            format!(
                "coordinates x, y\nparameters a, b\nkinetic E = 1/2*a*x'^2 + 1/2*b*y'^2\nload [{}, -a] at [x, {}]\ntorque {} on y\nload {} at x\nsolve u {{ a*u = {} }}\npotential V = {}\n",
                f[0], f[1], f[2], f[3], f[4], f[5]
            )
        })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: crate::common::proptest_cases(400), ..ProptestConfig::default() })]

    #[test]
    fn random_bytes_never_panic(bytes in prop::collection::vec(any::<u8>(), 0..200)) {
        let src = String::from_utf8_lossy(&bytes);
        pipeline(&src);
    }

    #[test]
    fn random_tokens_never_panic(src in token_soup()) {
        pipeline(&src);
    }

    #[test]
    fn random_scenes_never_panic(src in near_scene()) {
        pipeline(&src);
    }

    #[test]
    fn random_scenes_with_loads_and_blocks_never_panic(src in near_scene_with_new_statements()) {
        pipeline(&src);
    }
}
