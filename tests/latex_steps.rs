//! `qdot latex --steps` as lecture notes: the scene's definitions and each
//! body's data before the energies, no step repeating the one before it,
//! radicands that start with a positive term, and the characteristic
//! equation with content-free factors.

use qdot::output::latex::document;
use qdot::{CommandOptions, Scene};

/// A cart on springs carrying a disk that rolls on it: a definition, a
/// particle and a plane body.
const CART: &str = "book/scenes/cart_and_disk.qd";

/// `qdot ARGS`'s standard output, run as a user runs it: the order of the
/// terms follows the names in the order the scene declares them, which a
/// test process sharing its names between tests would not keep.
fn qdot(args: &[&str]) -> String {
    let (code, out, err) = crate::common::run::qdot(args);
    assert_eq!(code, 0, "qdot {args:?} failed: {err}");
    out
}

fn steps(path: &str) -> String {
    qdot(&["latex", "--steps", path])
}

fn example_steps(name: &str) -> String {
    steps(&format!("examples/{name}"))
}

#[test]
fn the_definitions_come_first_as_written() {
    let out = steps(CART);
    assert!(
        out.starts_with(
            "\\paragraph{Definitions.} As the scene writes them, and in the coordinates where that differs:\n\
             \\begin{align*}\n  \\varphi &= \\frac{x - s}{R}\n\\end{align*}\n"
        ),
        "{out}"
    );
    // written with the definitions' names, then in the coordinates
    let seed = example_steps("seed_24_1.qd");
    for row in [
        "  J_{3} &= \\frac{1}{3} l^{2} m_{3} = 36 m r^{2} \\\\\n",
        "  \\theta_{3} &= \\frac{y_{1}}{3 r} \\\\\n",
        "  x_{B} &= 4 r \\theta_{3} = \\frac{4}{3} y_{1} \\\\\n",
        "  E_{2} &= \\frac{1}{2} J_{2} \\dot{\\theta}_{2}^{2} = 2 m \\dot{y}_{1}^{2} \\\\\n",
    ] {
        assert!(seed.contains(row), "missing {row:?} in\n{seed}");
    }
    let seed = example_steps("seed_23_4.qd");
    assert!(
        seed.contains("  E_{1} &= \\frac{1}{2} m \\dot{y}_{1}^{2} = \\frac{G}{2 g} (\\dot{y}_{3} + 2 r \\dot{\\theta}_{3})^{2} \\\\\n"),
        "{seed}"
    );
}

#[test]
fn a_body_shows_its_data_and_the_textbook_energy() {
    let out = steps(CART);
    let disk = "The body $\\mathrm{disk}$: its mass, moment of inertia about the centre, angle and centre:\n\
        \\begin{align*}\n  \
        m_{\\mathrm{disk}} &= m \\\\\n  \
        J_{\\mathrm{disk}} &= \\frac{1}{2} m R^{2} \\\\\n  \
        \\varphi_{\\mathrm{disk}} &= \\varphi = \\frac{x - s}{R} \\\\\n  \
        \\mathbf{r}_{\\mathrm{disk}} &= \\begin{pmatrix} s \\\\ R \\end{pmatrix} \\\\\n  \
        v_{\\mathrm{disk}}^{2} &= \\dot{s}^{2} \\\\\n  \
        \\omega_{\\mathrm{disk}} &= \\dot{\\varphi} = \\frac{\\dot{x} - \\dot{s}}{R} \\\\\n  \
        E_{\\mathrm{disk}} &= \\frac{1}{2} m_{\\mathrm{disk}} v_{\\mathrm{disk}}^{2} + \\frac{1}{2} J_{\\mathrm{disk}} \\omega_{\\mathrm{disk}}^{2} = \\frac{1}{4} m \\dot{x}^{2} - \\frac{1}{2} m \\dot{s} \\dot{x} + \\frac{3}{4} m \\dot{s}^{2}\n\
        \\end{align*}\n";
    assert!(out.contains(disk), "{out}");
    assert!(
        out.contains("  E &= E_{\\mathrm{cart}} + E_{\\mathrm{disk}} = \\frac{1}{4} (2 M_{0} + m) \\dot{x}^{2} - \\frac{1}{2} m \\dot{s} \\dot{x} + \\frac{3}{4} m \\dot{s}^{2}\n"),
        "{out}"
    );
    // in space: the inertia tensor, ω in the body's axes, ½·ωᵀ·I·ω
    let top = example_steps("heavy_top.qd");
    for row in [
        "  I_{\\mathrm{top}} &= \\begin{pmatrix} A & 0 & 0 \\\\ 0 & A & 0 \\\\ 0 & 0 & C \\end{pmatrix} \\\\\n",
        "  \\boldsymbol{\\omega}_{\\mathrm{top}} &= \\begin{pmatrix} \\dot{\\varphi} \\sin\\psi \\sin\\theta + \\dot{\\theta} \\cos\\psi \\\\ \\dot{\\varphi} \\cos\\psi \\sin\\theta - \\dot{\\theta} \\sin\\psi \\\\ \\dot{\\varphi} \\cos\\theta + \\dot{\\psi} \\end{pmatrix} \\\\\n",
        "  E_{\\mathrm{top}} &= \\frac{1}{2} m_{\\mathrm{top}} v_{\\mathrm{top}}^{2} + \\frac{1}{2} \\boldsymbol{\\omega}_{\\mathrm{top}}^{T} I_{\\mathrm{top}} \\boldsymbol{\\omega}_{\\mathrm{top}} = ",
    ] {
        assert!(top.contains(row), "missing {row:?} in\n{top}");
    }
}

/// The chains `a = b = c` of every example's steps, one string a side.
fn chains(tex: &str) -> Vec<Vec<String>> {
    let mut rows: Vec<String> = Vec::new();
    let mut inside = false;
    for line in tex.lines() {
        let l = line.trim();
        if l.starts_with("\\begin{align") {
            inside = true;
            rows.push(String::new());
        } else if l.starts_with("\\end{align") {
            inside = false;
        } else if inside {
            let last = rows.last_mut().expect("a row");
            let l = l.trim_end_matches("\\nonumber").trim();
            let (l, ends) = match l.strip_suffix("\\\\") {
                Some(x) => (x, true),
                None => (l, false),
            };
            last.push(' ');
            last.push_str(l.replace("&\\quad", "").replace('&', "").trim());
            if ends {
                rows.push(String::new());
            }
        }
    }
    // a side starts at a top-level `=` (outside braces and environments)
    rows.iter()
        .map(|r| {
            let mut sides = vec![String::new()];
            let mut depth = 0i32;
            for c in r.chars() {
                match c {
                    '{' => depth += 1,
                    '}' => depth -= 1,
                    '=' if depth == 0 => {
                        sides.push(String::new());
                        continue;
                    }
                    _ => {}
                }
                sides.last_mut().expect("a side").push(c);
            }
            sides
        })
        .collect()
}

/// The terms of one side, signs kept, sorted: equal up to term order.
fn term_set(side: &str) -> Vec<String> {
    let mut terms = Vec::new();
    let mut cur = String::new();
    let mut depth = 0i32;
    for c in side.chars() {
        match c {
            '{' | '(' => depth += 1,
            '}' | ')' => depth -= 1,
            '+' | '-' if depth == 0 && !cur.trim().is_empty() => {
                terms.push(cur.trim().to_string());
                cur.clear();
            }
            _ => {}
        }
        cur.push(c);
    }
    terms.push(cur.trim().to_string());
    terms.sort();
    terms
}

#[test]
fn no_step_repeats_the_one_before_in_any_example() {
    let dir = std::path::Path::new(env!("QDOT_ROOT")).join("examples");
    let mut checked = 0;
    let mut too_large = Vec::new();
    for entry in std::fs::read_dir(&dir).expect("examples/") {
        let path = entry.expect("entry").path();
        if path.extension().is_none_or(|e| e != "qd") {
            continue;
        }
        let src = std::fs::read_to_string(&path).expect("example");
        let scene = Scene::parse(&src).expect("example parses");
        let opts = CommandOptions {
            steps: true,
            ..Default::default()
        };
        // an example too large to solve exactly (rod_chain) stops at the
        // default budget (no context installed one) and has nothing to check
        let tex = match document(&scene, &opts) {
            Ok(tex) => tex,
            Err(d) => {
                assert!(
                    matches!(*d.kind, qdot::diag::ErrorKind::TooLarge { .. }),
                    "{}: {}",
                    path.display(),
                    d.message
                );
                too_large.push(path.file_name().expect("a name").to_owned());
                continue;
            }
        };
        checked += 1;
        for sides in chains(&tex) {
            for pair in sides.windows(2).skip(1) {
                assert_ne!(
                    term_set(&pair[0]),
                    term_set(&pair[1]),
                    "{}: a step repeats the one before: {sides:?}",
                    path.display()
                );
            }
        }
    }
    assert!(checked > 30, "only {checked} examples checked");
    assert_eq!(too_large, ["rod_chain.qd"]);
    // the seed's 24.1: Q_y1 is its sources' values once, in display order
    let seed = example_steps("seed_24_1.qd");
    assert!(
        seed.contains("  Q_{y_{1}} &= \\frac{\\partial U}{\\partial y_{1}} + \\frac{\\partial L}{\\partial y_{1}} + \\frac{\\partial D}{\\partial \\dot{y}_{1}} = -\\frac{4}{9} c \\dot{y}_{1} - \\frac{16}{9} k y_{1} + F_{0} \\cos(p t) + 3 g m \\sin\\left(\\frac{1}{3 r} y_{1}\\right)\n"),
        "{seed}"
    );
    // a step that combines terms stays
    let seed = example_steps("seed_23_4.qd");
    assert!(
        seed.contains("= 5 G - \\frac{1}{8} G = \\frac{39}{8} G\n"),
        "{seed}"
    );
}

#[test]
fn a_radicand_starts_with_a_positive_term() {
    let out = example_steps("slider_crank.qd");
    assert!(!out.contains("\\sqrt{-"), "{out}");
    assert!(
        out.contains("\\sqrt{L^{2} - R^{2} \\sin^{2}(\\omega t)}"),
        "{out}"
    );
}

#[test]
fn a_parenthesized_sum_with_fractions_is_sized() {
    let out = example_steps("seed_22_2.qd");
    assert!(
        out.contains(" + \\left(-\\frac{2 G}{g} \\ddot{y}_{1} + 2 G\\right) + "),
        "{out}"
    );
}

#[test]
fn the_characteristic_factors_are_content_free() {
    let out = qdot(&["modes", CART, "--format", "latex"]);
    assert!(
        out.contains(
            "  &= \\frac{1}{2} (m (3 M_{0} + m) \\omega^{4} - k (2 M_{0} + 5 m) \\omega^{2} + 2 k^{2}) = 0\n"
        ),
        "{out}"
    );
    // two factors: no number in front
    let out = qdot(&["modes", "examples/seed_24_2.qd", "--format", "latex"]);
    assert!(
        out.contains("= (6 m \\omega^{2} - k) (m \\omega^{2} - k) = 0\n"),
        "{out}"
    );
    // the content and a factor 1/r in front as one fraction
    let out = qdot(&["modes", "examples/seed_24_1.qd", "--format", "latex"]);
    assert!(
        out.contains("= -\\frac{1}{9 r} (81 m r \\omega^{2} + 9 g m - 16 k r) = 0\n"),
        "{out}"
    );
}

/// A body without a mass turns about its fixed centre: its steps show no
/// mass, no v² and E = ½ωᵀIω.
#[test]
fn a_body_without_a_mass_shows_only_its_turning() {
    let out = example_steps("torque_free_body.qd");
    assert!(
        out.contains("The body $\\mathrm{b}$: no mass (its centre is fixed), its inertia about the centre in its own axes (and its angular velocity in them) and centre:\n\\begin{align*}\n  I_{\\mathrm{b}} &= "),
        "{out}"
    );
    assert!(
        out.contains("  E_{b} &= \\frac{1}{2} \\boldsymbol{\\omega}_{\\mathrm{b}}^{T} I_{\\mathrm{b}} \\boldsymbol{\\omega}_{\\mathrm{b}} = "),
        "{out}"
    );
    assert!(
        !out.contains("m_{\\mathrm{b}}") && !out.contains("v_{\\mathrm{b}}"),
        "{out}"
    );
}

#[test]
fn a_mechanisms_steps_read_as_sentences_titled_by_the_scene() {
    let (code, tex, err) =
        crate::common::run::qdot(&["latex", "--steps", "--standalone", "examples/seed_21_3.qd"]);
    assert_eq!(code, 0, "{err}");
    // the title is the scene's first comment, as `simulate --plot` takes it
    assert!(
        tex.contains("\\begin{document}\n\\section*{The seed's problem 21.3 (§21.5)}\n"),
        "{tex}"
    );
    // the lead-in is a sentence of its own before the first body's
    assert!(
        tex.contains(
            "\\paragraph{Kinetic energy.} In the coordinates $x_{1}, y_{1}, \\varphi, x_{2}, \
             y_{2}, \\alpha, x_{B}, y_{B}$, the kinetic energy is found body by body.\n\
             The body $\\mathrm{disk}$: its mass,"
        ),
        "{tex}"
    );
    // xB is x with the subscript B: the dot on the x alone
    assert!(
        tex.contains("v_{\\mathrm{slider}}^{2} &= \\dot{x}_{B}^{2} + \\dot{y}_{B}^{2} \\\\\n"),
        "{tex}"
    );
    assert!(!tex.contains("mathit{xB}"), "{tex}");
    // an explicit title wins
    let (_, tex, _) = crate::common::run::qdot(&[
        "latex",
        "--standalone",
        "--title",
        "Slider-crank",
        "examples/seed_21_3.qd",
    ]);
    assert!(tex.contains("\\section*{Slider-crank}\n"), "{tex}");
}

#[test]
fn a_title_with_mathematics_still_compiles() {
    assert_eq!(
        qdot::output::latex::escape_text("force −k/r² on θ (§1)"),
        "force \\ensuremath{-}k/r² on \\ensuremath{\\theta} (§1)"
    );
}
