//! Golden tests of the LaTeX output: one per construct, exact strings.
//!
//! The expected strings are insta snapshots under `tests/snapshots/`;
//! each was read and checked by hand when it was accepted. To review a
//! change: `INSTA_UPDATE=always cargo test --release --test it latex::`, then
//! `git diff tests/snapshots`.

use crate::common;
use insta::assert_snapshot;
use qdot::expr::latex::{latex, latex_with, Names};
use qdot::Scene;

/// `qdot ARGS`'s standard output; it must succeed.
fn qdot(args: &[&str]) -> String {
    let (code, out, err) = common::run::qdot(args);
    assert_eq!(code, 0, "qdot {args:?} failed: {err}");
    out
}

/// A scene with the names the constructs below use.
fn scene() -> Scene {
    Scene::parse(
        "coordinates y3, theta3, x, phi, a, b, eps3
         parameters G, g, r, m, k, c, l, omega, Omega, mu, J2, F0, M0, p, alpha
         ",
    )
    .expect("scene parses")
}

fn tex(src: &str) -> String {
    let e = scene().expr(src).expect("expression parses");
    latex(&e)
}

#[test]
fn fractions() {
    assert_snapshot!("fraction_rational", tex("343/460*g"));
    assert_snapshot!("fraction_symbolic", tex("13*g/(460*r)"));
    assert_snapshot!(
        "fraction_coefficients",
        tex("13/2*G/g*y3'' + G*r/g*theta3''")
    );
    assert_snapshot!(
        "fraction_of_sums",
        tex("g*r*(G*r - p*l)/(G*r^2 + J2*g + p*l^2)")
    );
    assert_snapshot!("fraction_unit_numerator", tex("1/(2*m)"));
    assert_snapshot!("fraction_half", tex("1/2*m*x'^2"));
}

#[test]
fn radicals() {
    assert_snapshot!("radical_number", tex("sqrt(3)"));
    assert_snapshot!("radical_half", tex("sqrt(3)/2*G"));
    assert_snapshot!("radical_times_integer", tex("2*sqrt(3)*G"));
    assert_snapshot!("radical_fraction", tex("30*sqrt(3)/23*G"));
    assert_snapshot!("radical_of_expression", tex("sqrt(k/m)"));
    assert_snapshot!("radical_of_sum", tex("sqrt(k + m)"));
}

#[test]
fn dots() {
    assert_snapshot!("dot_velocity", tex("y3'"));
    assert_snapshot!("dot_acceleration", tex("theta3''"));
    assert_snapshot!("dot_third", tex("x'''"));
    assert_snapshot!("dot_squared", tex("y3'^2"));
    assert_snapshot!("dot_product", tex("y3'*theta3'"));
}

#[test]
fn greek_names() {
    assert_snapshot!("greek_indexed", tex("theta3 + eps3 + omega + mu"));
    assert_snapshot!("greek_capital", tex("Omega*t"));
    assert_snapshot!("greek_phi_dot", tex("phi'"));
    assert_snapshot!("subscripts", tex("J2 + F0 + M0"));
    let unicode = Scene::parse("coordinates θ3\nparameters ω").expect("scene");
    assert_snapshot!(
        "greek_unicode",
        latex(&unicode.expr("ω*θ3''").expect("expression"))
    );
}

#[test]
fn nested_powers_and_functions() {
    assert_snapshot!("sin_squared", tex("sin(theta3)^2"));
    assert_snapshot!("sin_cubed_of_product", tex("sin(Omega*t)^3"));
    assert_snapshot!("function_of_product", tex("M0*cos(Omega*t)"));
    assert_snapshot!("function_last", tex("m*g*l*sin(phi)"));
    assert_snapshot!("function_times_acceleration", tex("m*l^2*cos(a - b)*b''"));
    assert_snapshot!("power_of_power", tex("(x^2)^3"));
    assert_snapshot!("exponential", tex("exp(-alpha*t)*x"));
    assert_snapshot!("exponential_over", tex("exp(-alpha*t)*x/m"));
    assert_snapshot!("exponential_squared", tex("exp(alpha*t)^2"));
    assert_snapshot!("logarithm", tex("ln(k)"));
    assert_snapshot!("inverse_trig", tex("atan(k/m) + asin(1/3)"));
    assert_snapshot!("pi", tex("2*pi*sqrt(m/k)"));
}

#[test]
fn signs() {
    assert_snapshot!("negative_leading_term", tex("-k*x/m + g"));
    assert_snapshot!("negative_fraction", tex("-1/8*G*y3"));
    assert_snapshot!("negative_quotient", tex("-k/(m + c)"));
    assert_snapshot!("negative_sum_coefficient", tex("(c - k)*x'' + x"));
    assert_snapshot!("zero", tex("x - x"));
}

#[test]
fn folded_angles() {
    // cos(a)cos(b) + sin(a)sin(b) folds back to cos(a − b)
    assert_snapshot!(
        "folded_difference",
        tex("l^2*m*(cos(a)*cos(b) + sin(a)*sin(b))*b''")
    );
}

#[test]
fn names_can_be_overridden() {
    let mut names = Names::new();
    names.set("theta3", "\\vartheta_3");
    let e = scene().expr("theta3'' + sin(theta3)").expect("expression");
    assert_snapshot!("override", latex_with(&e, &names));
}

#[test]
fn matrices_m_and_k() {
    assert_snapshot!(
        "modes_24_2",
        qdot(&["modes", "examples/seed_24_2.qd", "--format", "latex"])
    );
}

#[test]
fn equations_and_accelerations() {
    assert_snapshot!("latex_23_4", qdot(&["latex", "examples/seed_23_4.qd"]));
    assert_snapshot!(
        "derive_23_2",
        qdot(&["derive", "examples/seed_23_2.qd", "--format", "latex"])
    );
}

#[test]
fn steps_follow_the_seed() {
    assert_snapshot!(
        "steps_23_4",
        qdot(&["latex", "--steps", "examples/seed_23_4.qd"])
    );
}

#[test]
fn standalone_is_a_document() {
    let doc = qdot(&["latex", "--standalone", "examples/seed_22_2.qd"]);
    assert!(doc.starts_with("\\documentclass[10pt]{article}\n"));
    assert!(doc.contains("\\usepackage{amsmath}"));
    // titled by the scene's first comment (as `simulate --plot`), or by
    // --title
    assert!(
        doc.contains("\\section*{Seed problem 22.2 as the book solves it}"),
        "{doc}"
    );
    let titled = qdot(&[
        "latex",
        "--standalone",
        "--title",
        "Two disks",
        "examples/seed_22_2.qd",
    ]);
    assert!(titled.contains("\\section*{Two disks}"));
    assert!(doc.ends_with("\\end{document}\n"));
    // the fragment is the document's body
    let body = qdot(&["latex", "examples/seed_22_2.qd"]);
    assert!(doc.contains(&body));
}

#[test]
fn modes_as_a_standalone_document() {
    let doc = qdot(&[
        "modes",
        "examples/seed_24_2.qd",
        "--format",
        "latex",
        "--standalone",
    ]);
    assert!(doc.starts_with("\\documentclass[10pt]{article}\n"));
    assert!(doc.contains("\\section*{Seed problem 24.2}"), "{doc}");
    assert!(doc.contains(&qdot(&[
        "modes",
        "examples/seed_24_2.qd",
        "--format",
        "latex"
    ])));
    assert!(doc.ends_with("\\end{document}\n"));
}

#[test]
fn kinetostatic_and_equilibrium_scenes() {
    assert_snapshot!(
        "latex_21_2_kinetostatic",
        qdot(&["latex", "examples/seed_21_2_kinetostatic.qd"])
    );
    assert_snapshot!("latex_23_1", qdot(&["latex", "examples/seed_23_1.qd"]));
    assert_snapshot!(
        "forces_23_3",
        qdot(&["forces", "examples/seed_23_3.qd", "--format", "latex"])
    );
}

/// Long equations break before a sign; the number stays on the last line.
#[test]
fn long_equations_break() {
    let src = qdot::engine::gallery::pendulum_chain(3);
    let dir = std::env::temp_dir().join(format!("qdot-latex-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let file = dir.join("chain3.qd");
    std::fs::write(&file, src).expect("write scene");
    let out = qdot(&["derive", file.to_str().expect("path"), "--format", "latex"]);
    let eqs: Vec<&str> = out
        .split("\\begin{align}\n")
        .nth(1)
        .expect("an align")
        .split("\\end{align}")
        .next()
        .expect("its end")
        .lines()
        .collect();
    assert!(eqs.len() > 3, "the equations were broken: {eqs:?}");
    for l in &eqs {
        let w = qdot::output::latex::width(l);
        assert!(w < 60.0, "line too wide ({w}): {l}");
    }
    assert!(eqs
        .iter()
        .any(|l| l.starts_with("  &\\quad - ") || l.starts_with("  &\\quad + ")));
    assert_eq!(
        eqs.iter().filter(|l| !l.contains("\\nonumber")).count(),
        3,
        "one number per equation"
    );
}

/// `latex NAME = "…"` in a scene changes the notation in every output.
#[test]
fn scene_notation_overrides() {
    let scene = Scene::parse(
        "coordinates theta3\nparameters m, g, l\nlatex theta3 = \"\\vartheta_{3}\"\nlatex l = \"\\ell\"\n\
         kinetic E = 1/2*m*l^2*theta3'^2\npotential V = -m*g*l*cos(theta3)",
    )
    .expect("scene");
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    assert_eq!(scene.latex_names.len(), 2);
    let (out, _) = qdot::output::run(
        qdot::output::Command::Derive,
        &scene.source,
        qdot::output::Format::Latex,
        &Default::default(),
    )
    .expect("derive");
    assert_snapshot!("scene_overrides", out);
}

#[test]
fn undeclared_or_repeated_notation_warns() {
    let scene = Scene::parse("parameters m\nlatex mm = \"M\"\nlatex m = \"a\"\nlatex m = \"b\"")
        .expect("scene");
    let w: Vec<&str> = scene.warnings.iter().map(|d| d.message.as_str()).collect();
    assert_eq!(
        w,
        [
            "`latex` gives notation for `mm`, which the scene never declares",
            "`m` is given LaTeX notation twice"
        ]
    );
    let mut names = Names::new();
    for n in &scene.latex_names {
        names.set(&n.name, &n.tex);
    }
    assert_eq!(names.symbol("m", 0), "b", "the later statement wins");
}

/// The lines of seed 21.3's LaTeX that multiply its two-letter lengths AB
/// and AC with the reactions: a `\cdot` beside every word, so that the
/// page never shows one name ABBₓ for AB·Bₓ.
#[test]
fn products_of_two_letter_names_are_dotted() {
    let out = qdot(&["latex", "examples/seed_21_3.qd"]);
    let line = |head: &str| {
        out.lines()
            .find(|l| l.trim_start().starts_with(head))
            .unwrap_or_else(|| panic!("no line `{head}` in:\n{out}"))
            .trim()
            .to_string()
    };
    assert_eq!(
        line("J_{2} \\ddot{\\alpha} &="),
        "J_{2} \\ddot{\\alpha} &= (\\mathit{AB} \\cdot B_{x} - \\mathit{AC} \\cdot B_{x} \
         + A_{x} \\cdot \\mathit{AC}) \\sin\\alpha - (\\mathit{AB} \\cdot B_{y} \
         - \\mathit{AC} \\cdot B_{y} + A_{y} \\cdot \\mathit{AC}) \\cos\\alpha \\\\"
    );
    assert_eq!(
        line("A_{y} &="),
        "A_{y} &= \\frac{G_{2} (\\mathit{AB} - \\mathit{AC}) \\ddot{y}_{2} \\cos\\alpha \
         - g J_{2} \\ddot{\\alpha} + g G_{2} (\\mathit{AB} - \\mathit{AC}) \\cos\\alpha \
         + g (\\mathit{AB} \\cdot B_{x} - \\mathit{AC} \\cdot B_{x} + A_{x} \\cdot \\mathit{AC}) \
         \\sin\\alpha}{\\mathit{AB} \\cdot g \\cos\\alpha} \\\\"
    );
    assert_eq!(
        line("B_{y} &="),
        "B_{y} &= \\frac{g (\\mathit{AB} \\cdot B_{x} - \\mathit{AC} \\cdot B_{x} \
         + A_{x} \\cdot \\mathit{AC}) \\sin\\alpha - \\mathit{AC} \\cdot G_{2} \\ddot{y}_{2} \
         \\cos\\alpha - g J_{2} \\ddot{\\alpha} - \\mathit{AC} \\cdot g G_{2} \
         \\cos\\alpha}{\\mathit{AB} \\cdot g \\cos\\alpha} \\\\"
    );
    // beside a number, a fraction or a function a word needs no dot
    let s = Scene::parse(
        "coordinates xs, xB\nparameters AB, AC, G, g, k\nlatex AC = \"\\mathrm{AC}\"\n",
    )
    .expect("scene parses");
    let names = notation(&s);
    let t = |src: &str| latex_with(&s.expr(src).expect("parses"), &names);
    assert_eq!(t("2*AB*sin(xs)"), "2 \\mathit{AB} \\sin\\mathit{xs}");
    assert_eq!(t("G/g*xs''"), "\\frac{G}{g} \\ddot{\\mathit{xs}}");
    assert_eq!(t("k*xs"), "k \\cdot \\mathit{xs}");
    // a small letter before capitals is a point's coordinate: the letter
    // with a subscript, its dot on the letter alone
    assert_eq!(t("G/g*xB''"), "\\frac{G}{g} \\ddot{x}_{B}");
    assert_eq!(t("k*xB'^2"), "k \\dot{x}_{B}^{2}");
    assert_eq!(t("AB*(G + k)"), "\\mathit{AB} \\cdot (G + k)");
    // an override that is a word is one too; single letters stay side by side
    assert_eq!(t("AC*g*k"), "\\mathrm{AC} \\cdot g k");
}

/// A scene's notation: the defaults and its `latex` statements.
fn notation(s: &Scene) -> Names {
    let mut names = Names::new();
    for n in &s.latex_names {
        names.set(&n.name, &n.tex);
    }
    names
}

/// The names a random product draws from: single letters, words, Greek
/// names and names with subscripts, as parameters and coordinates.
const PRODUCT_NAMES: [&str; 14] = [
    "A", "B", "m", "AB", "AC", "Ff", "mass", "theta", "omega", "B_x", "F_max", "J2", "xB", "q",
];

/// Split a product's LaTeX, spaces removed, into the names a reader sees:
/// runs of factors between `\cdot`s; within a run, each factor is a head
/// (a letter, a command, `\mathit{…}`, a dotted head) with its subscript
/// and exponent. `None` when a run that holds a word holds anything else:
/// on the page its letters would join the neighbour's into a longer name.
fn reread(tex: &str) -> Option<Vec<String>> {
    // spaces go, but one that ends a control word (`\theta q`) is `{}`,
    // as TeX reads it: `\thetaq` would be another command
    let mut s = String::new();
    for c in tex.chars() {
        if !c.is_whitespace() {
            s.push(c);
            continue;
        }
        let letters = s.trim_end_matches(|c: char| c.is_ascii_alphabetic());
        if letters.ends_with('\\') && letters.len() < s.len() {
            s.push_str("{}");
        }
    }
    // the end of the brace group opening at byte `i`
    let group = |i: usize| -> usize {
        let mut depth = 0;
        for (k, c) in s[i..].char_indices() {
            match c {
                '{' => depth += 1,
                '}' => {
                    depth -= 1;
                    if depth == 0 {
                        return i + k + 1;
                    }
                }
                _ => {}
            }
        }
        s.len()
    };
    let mut names = Vec::new();
    let mut start = 0;
    for run in s.split("\\cdot") {
        let mut factors: Vec<(String, bool)> = Vec::new();
        // the `{}` that ended `\cdot`
        let mut i = if run.starts_with("{}") { 2 } else { 0 };
        let base = start;
        start += run.len() + "\\cdot".len();
        while i < run.len() {
            let at = base + i;
            let rest = &run[i..];
            // the head, and whether it is a word
            let (end, word) = if let Some(cmd) = ["\\mathit{", "\\mathrm{"]
                .iter()
                .find(|c| rest.starts_with(**c))
            {
                (group(at + cmd.len() - 1) - base, true)
            } else if rest.starts_with("\\dot{") || rest.starts_with("\\ddot{") {
                let open = rest.find('{').expect("a brace");
                let inner_end = group(at + open) - base;
                (inner_end, run[i..inner_end].contains("\\mathit{"))
            } else if let Some(cmd) = rest.strip_prefix('\\') {
                let n = cmd
                    .find(|c: char| !c.is_ascii_alphabetic())
                    .map_or(rest.len(), |k| k + 1);
                (i + n, false)
            } else {
                (i + rest.chars().next().expect("a char").len_utf8(), false)
            };
            let mut head = run[i..end].to_string();
            let mut j = end;
            if run[j..].starts_with("{}") {
                j += 2;
            }
            // a subscript belongs to the name; an exponent does not
            while j < run.len() && (run[j..].starts_with("_{") || run[j..].starts_with("^{")) {
                let close = group(base + j + 1) - base;
                if run[j..].starts_with("_{") {
                    head.push_str(&run[j..close]);
                }
                j = close;
            }
            factors.push((head, word));
            i = j;
        }
        if factors.len() > 1 && factors.iter().any(|f| f.1) {
            return None;
        }
        names.extend(factors.into_iter().map(|f| f.0));
    }
    Some(names)
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig {
        cases: common::proptest_cases(200),
        ..proptest::prelude::ProptestConfig::default()
    })]

    /// A random product of names reads back as exactly its names: every
    /// word is wrapped and set apart by `\cdot`, so no two names of the
    /// product can be read as another name.
    #[test]
    fn a_product_of_names_reads_back_as_its_names(
        picks in proptest::collection::vec((0..PRODUCT_NAMES.len(), 1u32..4, 0u32..3), 1..5),
    ) {
        let s = Scene::parse(
            "coordinates xB, q\nparameters A, B, m, AB, AC, Ff, mass, theta, omega, B_x, F_max, J2\n",
        )
        .expect("scene parses");
        let names = notation(&s);
        let mut seen = std::collections::BTreeSet::new();
        let mut factors = Vec::new();
        let mut expected = Vec::new();
        for (k, power, dots) in picks {
            let name = PRODUCT_NAMES[k];
            let coordinate = name == "xB" || name == "q";
            let dots = if coordinate { dots } else { 0 };
            if !seen.insert((name, dots)) {
                continue;
            }
            factors.push(format!("{name}{}^{power}", "'".repeat(dots as usize)));
            expected.push(names.symbol(name, dots).replace(' ', ""));
        }
        let e = s.expr(&factors.join("*")).expect("parses");
        let tex = latex_with(&e, &names);
        let mut got = reread(&tex).unwrap_or_else(|| panic!("a word joins a neighbour in `{tex}`"));
        got.sort();
        expected.sort();
        proptest::prop_assert_eq!(got, expected, "{}", tex);
    }
}

/// The re-reading itself catches what it must: a word beside a name
/// without a dot.
#[test]
fn rereading_a_product_catches_a_word_beside_a_name() {
    assert_eq!(reread("\\mathit{AB} B_{x}"), None);
    assert_eq!(reread("A_{x} \\mathit{AC}"), None);
    assert_eq!(
        reread("\\mathit{AB}^{2} \\cdot B_{x}"),
        Some(vec!["\\mathit{AB}".to_string(), "B_{x}".to_string()])
    );
    assert_eq!(
        reread("m \\theta \\dot{q}^{2}"),
        Some(vec!["m".into(), "\\theta".into(), "\\dot{q}".into()])
    );
    assert_eq!(
        reread("\\theta q \\cdot \\mathit{xB}"),
        Some(vec!["\\theta".into(), "q".into(), "\\mathit{xB}".into()])
    );
}
