//! `qdot simulate --plot`: the figure names the scene, labels every axis
//! (with its unit where the scene declares dimensions) and every curve;
//! the book's figures are what the commands on its page draw.

use std::process::Command;

const ROOT: &str = env!("QDOT_ROOT");

/// The book's page that shows the figures, and where they are kept.
const PAGE: &str = "book/src/simulation.md";
const FIGURES: &str = "book/src/simulation/";

/// Runs qdot from the repository root: success, stderr.
fn qdot(args: &[String]) -> (bool, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_qdot"))
        .args(args)
        .current_dir(ROOT)
        .output()
        .expect("qdot runs");
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// A temporary directory of this test's own.
fn temp(tag: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("qdot-plot-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a temporary directory");
    dir
}

/// The SVG `simulate --plot` draws for `args` (without `--plot`).
fn plot(tag: &str, args: &[&str]) -> String {
    let svg = temp(tag).join("figure.svg");
    let mut all: Vec<String> = std::iter::once("simulate")
        .chain(args.iter().copied())
        .map(String::from)
        .collect();
    all.extend(["--plot".into(), svg.to_str().expect("a path").into()]);
    let (ok, err) = qdot(&all);
    assert!(ok, "{err}");
    std::fs::read_to_string(&svg).expect("the SVG")
}

/// Every `<text>` element's text.
fn texts(svg: &str) -> Vec<&str> {
    svg.split("<text")
        .skip(1)
        .map(|t| {
            let t = &t[t.find('>').expect("a tag") + 1..];
            t[..t.find("</text>").expect("a closing tag")].trim()
        })
        .collect()
}

fn assert_has(texts: &[&str], wanted: &[&str]) {
    for w in wanted {
        assert!(
            texts.contains(w),
            "`{w}` is not a text of the figure: {texts:?}"
        );
    }
}

/// A scene written to a temporary file named `name`.
fn scene(name: &str, src: &str) -> String {
    let path = temp("scenes").join(name);
    std::fs::write(&path, src).expect("the scene written");
    path.to_str().expect("a path").to_string()
}

#[test]
fn the_double_pendulum_is_titled_and_every_axis_has_its_unit() {
    let svg = plot(
        "double",
        &[
            "examples/double_pendulum.qd",
            "--set",
            "m1=1,m2=1,l1=1,l2=1,g=9.81",
            "--init",
            "th1=2,th2=1.5,th1'=0,th2'=0",
            "--t-end",
            "2",
        ],
    );
    let texts = texts(&svg);
    assert_has(
        &texts,
        &[
            // the scene's first comment, then the file, parameters, method
            "The double pendulum",
            "double_pendulum.qd · m₁ = 1, m₂ = 1, l₁ = 1, l₂ = 1, g = 9.81 · dop853, rtol 1e-8, atol 1e-10",
            // both angles share one panel against time, named in a legend
            "angles against time",
            "θ₁, θ₂ [rad]",
            "t [s]",
            "θ₁",
            "θ₂",
            // a phase portrait per coordinate
            "phase portrait of θ₁",
            "θ₁ [rad]",
            "θ̇₁ [rad/s]",
            "phase portrait of θ₂",
            "θ₂ [rad]",
            "θ̇₂ [rad/s]",
            "energy error",
            "h(t) − h(0) [J]",
        ],
    );
    // the method is no longer the title, and no minor grid: the grid's
    // lines are the labelled ticks' (one colour, the light grey)
    assert!(!texts.iter().any(|t| t.starts_with("dop853")), "{texts:?}");
    assert!(svg.contains("stroke=\"#E1E1E1\""), "the light grid");
    // readable on a slide: no text under 16 pixels
    for size in svg.split("font-size=\"").skip(1) {
        let px: f64 = size[..size.find('"').unwrap()].parse().unwrap();
        assert!(px >= 15.99, "a text of {px} px");
    }
}

#[test]
fn coordinates_of_different_units_get_panels_of_their_own() {
    let svg = plot(
        "mixed",
        &[
            "examples/seed_21_2.qd",
            "--set",
            "G=10,g=9.81,r=0.2",
            "--init",
            "y3=0,theta3=0,y3'=0.1,theta3'=0",
            "--t-end",
            "1",
        ],
    );
    let texts = texts(&svg);
    assert_has(
        &texts,
        &[
            "Seed problem 21.2 / 22.3",
            "y₃ against time",
            "y₃ [m]",
            "θ₃ against time",
            "θ₃ [rad]",
            "y\u{307}₃ [m/s]",
            "θ̇₃ [rad/s]",
        ],
    );
    // each of the two panels against t names its curve in a legend
    assert_eq!(texts.iter().filter(|t| **t == "y₃").count(), 1);
    assert_eq!(texts.iter().filter(|t| **t == "θ₃").count(), 1);
    assert_eq!(texts.iter().filter(|t| **t == "t [s]").count(), 2);
}

#[test]
fn a_scene_without_dimensions_gets_labels_without_units() {
    let src = "# A mass on a spring, and a pendulum beside it\ncoordinates x, theta\nparameters m, k, l, g\nkinetic E = 1/2*m*x'^2 + 1/2*m*l^2*theta'^2\npotential V = 1/2*k*x^2 - m*g*l*cos(theta)\n";
    let path = scene("spring_and_pendulum.qd", src);
    let svg = plot(
        "plain",
        &[
            path.as_str(),
            "--set",
            "m=1,k=4,l=1,g=9.81",
            "--init",
            "x=0.1,theta=1,x'=0,theta'=0",
            "--t-end",
            "1",
        ],
    );
    let shown = texts(&svg);
    assert_has(
        &shown,
        &[
            "A mass on a spring",
            "coordinates against time",
            "x, θ",
            "t",
            "x",
            "θ",
            "x\u{307}",
            "θ̇",
            "h(t) − h(0)",
        ],
    );
    assert!(!shown.iter().any(|t| t.contains('[')), "{shown:?}");
    // without a comment, the file's stem names the scene
    let path = scene("bare.qd", &src[src.find('\n').unwrap() + 1..]);
    let svg = plot(
        "bare",
        &[
            path.as_str(),
            "--set",
            "m=1,k=4,l=1,g=9.81",
            "--init",
            "x=0.1,theta=1,x'=0,theta'=0",
            "--t-end",
            "1",
        ],
    );
    assert_has(&texts(&svg), &["bare"]);
}

/// `line` split as sh splits it, for the book's commands: on blanks
/// outside double quotes, the quotes removed.
fn words(line: &str) -> Vec<String> {
    let (mut out, mut word, mut quoted) = (Vec::new(), String::new(), false);
    for c in line.chars() {
        match c {
            '"' => quoted = !quoted,
            ' ' if !quoted => {
                if !word.is_empty() {
                    out.push(std::mem::take(&mut word));
                }
            }
            c => word.push(c),
        }
    }
    if !word.is_empty() {
        out.push(word);
    }
    out
}

/// A PNG's width and height (its IHDR chunk).
fn png_size(bytes: &[u8]) -> (u32, u32) {
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n", "a PNG");
    let at = |i: usize| u32::from_be_bytes(bytes[i..i + 4].try_into().unwrap());
    (at(16), at(20))
}

/// The book's figures: every `qdot simulate … --plot book/src/simulation/
/// NAME.svg` line of the page draws the SVG kept there (`QDOT_BLESS=1`
/// rewrites it), and beside it is its PNG (`scripts/plot_pngs.sh` makes
/// it; a browser renders it, so CI only checks it is there, of the SVG's
/// size and small).
#[test]
fn the_books_figures_are_what_its_commands_draw() {
    let page = std::fs::read_to_string(format!("{ROOT}/{PAGE}")).expect("the page");
    let commands: Vec<&str> = page
        .lines()
        .filter(|l| l.starts_with("qdot simulate ") && l.contains(" --plot "))
        .collect();
    assert_eq!(commands.len(), 2, "{commands:?}");
    let dir = temp("book");
    for line in commands {
        let mut args = words(line);
        assert_eq!(args.remove(0), "qdot");
        let at = args.iter().position(|a| a == "--plot").unwrap() + 1;
        let kept = args[at].clone();
        let name = kept
            .strip_prefix(FIGURES)
            .unwrap_or_else(|| panic!("{kept} is not in {FIGURES}"));
        let made = dir.join(name);
        args[at] = made.to_str().unwrap().to_string();
        let (ok, err) = qdot(&args);
        assert!(ok, "{line}: {err}");
        let now = std::fs::read_to_string(&made).unwrap();
        let book = format!("{ROOT}/{kept}");
        if std::env::var_os("QDOT_BLESS").is_some() {
            std::fs::write(&book, &now).unwrap();
        }
        assert!(
            std::fs::read_to_string(&book).unwrap_or_default() == now,
            "{book} drifted: QDOT_BLESS=1 cargo test --release --test it simulate_plot::, then scripts/plot_pngs.sh"
        );
        let png = book.replace(".svg", ".png");
        let bytes =
            std::fs::read(&png).unwrap_or_else(|_| panic!("{png}: run scripts/plot_pngs.sh"));
        assert!(bytes.len() < 150_000, "{png} has {} bytes", bytes.len());
        let svg_size = |k: &str| -> u32 {
            let v = &now[now.find(&format!("{k}=\"")).unwrap() + k.len() + 2..];
            v[..v.find('"').unwrap()].parse().unwrap()
        };
        assert_eq!(
            png_size(&bytes),
            (svg_size("width"), svg_size("height")),
            "{png} is not the SVG's size: run scripts/plot_pngs.sh"
        );
        // the page shows the PNG
        let shown = format!("({})", &png[ROOT.len() + "/book/src/".len()..]);
        assert!(page.contains(&shown), "{PAGE} does not show {shown}");
    }
}
