//! `qdot codegen`: the generated C (gcc -O2), Rust (rustc -O) and Python
//! compiled and run by a driver written here, at random states and
//! parameter sets of several scenes, against qdot's compiled evaluator
//! (`CompiledDynamics::accelerations`, the compiled M and f, the compiled
//! energy); Julia's output (no Julia on the machine: it is not in the
//! registries it reaches) by snapshot. A language whose toolchain is
//! missing is skipped with a message.

use qdot::expr::atom;
use qdot::simulate::codegen::{codegen, CodegenRequest, Form, Lang};
use qdot::simulate::compile::{compile_with, state_inputs, CompiledDynamics};
use qdot::simulate::{constrained, given, run};
use qdot::Scene;
use qdot_exact::rng::SplitMix64;
use rustc_hash::FxHashMap;
use std::path::PathBuf;
use std::process::Command;

/// Relative tolerance, against max(|expected|, 1e-2·‖output‖∞) (so an
/// entry near zero among large ones is compared absolutely).
const TOL: f64 = 1e-13;
/// Random states and parameter sets per scene.
const CASES: usize = 20;

struct SceneCase {
    /// The base name (the generated functions' prefix).
    name: &'static str,
    src: String,
    functions: Vec<String>,
}

fn read(path: &str) -> String {
    std::fs::read_to_string(PathBuf::from(env!("QDOT_ROOT")).join(path)).unwrap()
}

fn scenes() -> Vec<SceneCase> {
    let plain = |name, src| SceneCase {
        name,
        src,
        functions: Vec::new(),
    };
    vec![
        plain("pendulum", read("examples/pendulum.qd")),
        plain("double_pendulum", qdot::engine::gallery::pendulum_chain(2)),
        plain("seed_24_2", read("examples/seed_24_2.qd")),
        plain("heavy_top", read("examples/heavy_top.qd")),
        plain("chain5", qdot::engine::gallery::pendulum_chain(5)),
        plain(
            "cartesian_pendulum",
            qdot::simulate::problems::Problem::cartesian_pendulum().scene,
        ),
        SceneCase {
            name: "moving_support",
            src: read("examples/moving_support.qd"),
            functions: vec!["s=1/10*sin(2*t)".to_string()],
        },
    ]
}

/// One call of a generated function and what qdot's evaluator gives.
struct Call {
    /// `rhs`, `energy`, `mass_matrix`, `forcing`.
    function: &'static str,
    /// The file's base name (the prefix).
    prefix: String,
    t: f64,
    y: Vec<f64>,
    params: Vec<f64>,
    expected: Vec<f64>,
}

/// The generated code of every scene in `lang` (both forms), and the calls
/// to check.
fn generate(lang: Lang) -> (String, Vec<Call>, usize) {
    let mut code = String::new();
    let mut calls = Vec::new();
    let mut rng = SplitMix64::new(0x9E37_79B9_7F4A_7C15);
    for sc in scenes() {
        let mut req = CodegenRequest::new(&format!("{}.qd", sc.name), lang);
        req.functions = sc.functions.clone();
        code.push_str(&codegen(&sc.src, &req).unwrap_or_else(|d| panic!("{}: {d:?}", sc.name)));
        req.file = format!("{}_m.qd", sc.name);
        req.form = Form::MassMatrix;
        code.push_str(&codegen(&sc.src, &req).unwrap_or_else(|d| panic!("{}: {d:?}", sc.name)));

        let scene = Scene::parse(&sc.src).unwrap();
        let lag = given::defined(&scene, scene.lagrange().unwrap(), &sc.functions).unwrap();
        let has_constraints = !lag.constraints.multipliers.is_empty();
        let lag = constrained::stabilized(lag).unwrap();
        let n = lag.coordinates.len();
        let names: Vec<String> = scene.parameters.iter().map(|p| p.name.clone()).collect();
        let upper: Vec<_> = (0..n)
            .flat_map(|i| (i..n).map(move |j| (i, j)))
            .map(|(i, j)| lag.mass_matrix[i][j].clone())
            .collect();
        for _ in 0..CASES {
            let params: Vec<f64> = names.iter().map(|_| rng.uniform(0.5, 2.0)).collect();
            let mut map: FxHashMap<_, _> = names
                .iter()
                .zip(&params)
                .map(|(k, &v)| (atom::param(k), v))
                .collect();
            if has_constraints {
                map.insert(constrained::alpha_var(), 1.0);
            }
            let t = rng.uniform(0.0, 2.0);
            let mut y: Vec<f64> = (0..n).map(|_| rng.uniform(0.2, 2.9)).collect();
            y.extend((0..n).map(|_| rng.uniform(-2.0, 2.0)));
            let call = |function, prefix: String, expected| Call {
                function,
                prefix,
                t,
                y: y.clone(),
                params: params.clone(),
                expected,
            };
            let (mut dynamics, _) = CompiledDynamics::best(&lag, &map).unwrap();
            let mut qdd = vec![0.0; n];
            dynamics
                .accelerations(t, &y[..n], &y[n..], &mut qdd)
                .unwrap();
            let mut dy = y[n..].to_vec();
            dy.extend(qdd);
            calls.push(call("rhs", sc.name.to_string(), dy));
            let inputs = state_inputs(&lag.coordinates);
            let mut input = vec![t];
            input.extend(&y);
            let eval = |exprs: &[qdot::Expr]| {
                let p = compile_with(exprs, &inputs, &map).unwrap();
                let mut out = vec![0.0; exprs.len()];
                p.eval(&input, &mut p.registers(), &mut out);
                out
            };
            let m = eval(&upper);
            let mut full = vec![0.0; n * n];
            let mut k = 0;
            for i in 0..n {
                for j in i..n {
                    full[i * n + j] = m[k];
                    full[j * n + i] = m[k];
                    k += 1;
                }
            }
            calls.push(call("mass_matrix", format!("{}_m", sc.name), full));
            calls.push(call(
                "forcing",
                format!("{}_m", sc.name),
                eval(&lag.forcing),
            ));
            if let Some(p) = run::conserved_quantity(&scene, &lag.coordinates, &map).unwrap() {
                let mut out = [0.0];
                p.eval(&input, &mut p.registers(), &mut out);
                calls.push(call("energy", sc.name.to_string(), out.to_vec()));
            }
        }
    }
    let n = calls.len();
    (code, calls, n)
}

/// A fresh directory for one language's files.
fn workdir(lang: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("qdot-codegen-{}-{lang}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn have(tool: &str) -> bool {
    match Command::new(tool).arg("--version").output() {
        Ok(o) => o.status.success(),
        Err(_) => false,
    }
}

fn run_ok(cmd: &mut Command) -> String {
    let out = cmd.output().expect("the tool runs");
    assert!(
        out.status.success(),
        "{cmd:?} failed:\n{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// Every line the driver printed against the calls' expected values;
/// the largest relative error.
fn compare(lang: &str, calls: &[Call], printed: &str) -> f64 {
    let lines: Vec<&str> = printed.lines().collect();
    assert_eq!(lines.len(), calls.len(), "{lang}: one line per call");
    let mut worst: f64 = 0.0;
    for (c, line) in calls.iter().zip(lines) {
        let got: Vec<f64> = line
            .split_whitespace()
            .map(|s| {
                s.parse()
                    .unwrap_or_else(|_| panic!("{lang}: `{s}` in `{line}`"))
            })
            .collect();
        assert_eq!(
            got.len(),
            c.expected.len(),
            "{lang} {}_{}",
            c.prefix,
            c.function
        );
        let scale = c.expected.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        for (k, (g, e)) in got.iter().zip(&c.expected).enumerate() {
            let err = (g - e).abs() / e.abs().max(1e-2 * scale).max(f64::MIN_POSITIVE);
            worst = worst.max(err);
            assert!(
                err <= TOL,
                "{lang} {}_{}[{k}] at t = {}, y = {:?}, params {:?}: {g:e} against qdot's {e:e} (relative {err:.2e})",
                c.prefix,
                c.function,
                c.t,
                c.y,
                c.params
            );
        }
    }
    worst
}

fn list(xs: &[f64], f: &dyn Fn(f64) -> String) -> String {
    xs.iter().map(|&x| f(x)).collect::<Vec<_>>().join(", ")
}

#[test]
fn generated_c_matches_the_compiled_evaluator() {
    if !have("gcc") {
        eprintln!("SKIPPED: gcc is not on this machine; the generated C is not compiled");
        return;
    }
    let (code, calls, _) = generate(Lang::C);
    let lit = |x: f64| format!("{x:?}");
    let mut main = String::from("#include <stdio.h>\n\nint main(void)\n{\n");
    for c in &calls {
        let n = c.expected.len();
        let (y, ps) = (list(&c.y, &lit), list(&c.params, &lit));
        let args = if ps.is_empty() {
            String::new()
        } else {
            format!(", {ps}")
        };
        let f = format!("{}_{}", c.prefix, c.function);
        main.push_str(&format!("    {{\n        const double y[] = {{{y}}};\n"));
        if c.function == "energy" {
            main.push_str(&format!(
                "        printf(\"%.17g\\n\", {f}({:?}, y{args}));\n",
                c.t
            ));
        } else {
            main.push_str(&format!("        double out[{n}];\n"));
            let call = format!("{f}({:?}, y{args}, out)", c.t);
            if c.function == "rhs" {
                main.push_str(&format!("        if ({call} != 0) return 1;\n"));
            } else {
                main.push_str(&format!("        {call};\n"));
            }
            main.push_str(&format!(
                "        for (int k = 0; k < {n}; k++) printf(\"%.17g%s\", out[k], k + 1 < {n} ? \" \" : \"\\n\");\n"
            ));
        }
        main.push_str("    }\n");
    }
    main.push_str("    return 0;\n}\n");
    let dir = workdir("c");
    std::fs::write(dir.join("gen.c"), format!("{code}\n{main}")).unwrap();
    run_ok(
        Command::new("gcc")
            .args([
                "-O2", "-std=c99", "-Wall", "-Wextra", "-Werror", "gen.c", "-o", "gen", "-lm",
            ])
            .current_dir(&dir),
    );
    let printed = run_ok(&mut Command::new(dir.join("gen")));
    let worst = compare("C", &calls, &printed);
    eprintln!(
        "C: {} calls, largest relative difference {worst:.2e}",
        calls.len()
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn generated_rust_matches_the_compiled_evaluator() {
    if !have("rustc") {
        eprintln!("SKIPPED: rustc is not on this machine; the generated Rust is not compiled");
        return;
    }
    let (code, calls, _) = generate(Lang::Rust);
    let lit = |x: f64| format!("{x:?}");
    let mut main = String::from(
        "fn show(xs: &[f64]) {\n    let s: Vec<String> = xs.iter().map(|x| format!(\"{x:?}\")).collect();\n    println!(\"{}\", s.join(\" \"));\n}\n\nfn main() {\n",
    );
    for c in &calls {
        let (y, ps) = (list(&c.y, &lit), list(&c.params, &lit));
        let args = if ps.is_empty() {
            String::new()
        } else {
            format!(", {ps}")
        };
        let f = format!("{}_{}", c.prefix, c.function);
        let t = c.t;
        main.push_str(&format!("    {{\n        let y = [{y}];\n"));
        match c.function {
            "energy" => main.push_str(&format!("        show(&[{f}({t:?}, &y{args})]);\n")),
            "mass_matrix" => {
                let n = c.y.len() / 2;
                main.push_str(&format!(
                    "        let q: [f64; {n}] = y[..{n}].try_into().unwrap();\n        let mut out = [0.0; {}];\n        {f}({t:?}, &q{args}, &mut out);\n        show(&out);\n",
                    c.expected.len()
                ));
            }
            "rhs" => main.push_str(&format!(
                "        let mut out = [0.0; {}];\n        {f}({t:?}, &y{args}, &mut out).unwrap();\n        show(&out);\n",
                c.expected.len()
            )),
            _ => main.push_str(&format!(
                "        let mut out = [0.0; {}];\n        {f}({t:?}, &y{args}, &mut out);\n        show(&out);\n",
                c.expected.len()
            )),
        }
        main.push_str("    }\n");
    }
    main.push_str("}\n");
    let dir = workdir("rust");
    std::fs::write(dir.join("gen.rs"), format!("{code}\n{main}")).unwrap();
    run_ok(
        Command::new("rustc")
            .args([
                "-O",
                "--edition",
                "2021",
                "-D",
                "warnings",
                "gen.rs",
                "-o",
                "gen",
            ])
            .current_dir(&dir),
    );
    let printed = run_ok(&mut Command::new(dir.join("gen")));
    let worst = compare("Rust", &calls, &printed);
    eprintln!(
        "Rust: {} calls, largest relative difference {worst:.2e}",
        calls.len()
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn generated_python_matches_the_compiled_evaluator() {
    if !have("python3") {
        eprintln!("SKIPPED: python3 is not on this machine; the generated Python is not run");
        return;
    }
    let (code, calls, _) = generate(Lang::Python);
    let lit = |x: f64| format!("{x:?}");
    let mut main =
        String::from("\n\ndef show(xs):\n    print(' '.join(repr(float(x)) for x in xs))\n\n");
    for c in &calls {
        let (y, ps) = (list(&c.y, &lit), list(&c.params, &lit));
        let args = if ps.is_empty() {
            String::new()
        } else {
            format!(", {ps}")
        };
        let f = format!("{}_{}", c.prefix, c.function);
        let t = c.t;
        main.push_str(&match c.function {
            "energy" => format!("show([{f}({t:?}, [{y}]{args})])\n"),
            "mass_matrix" => {
                format!(
                    "show([x for row in {f}({t:?}, [{y}][:{}]{args}) for x in row])\n",
                    c.y.len() / 2
                )
            }
            _ => format!("show({f}({t:?}, [{y}]{args}))\n"),
        });
    }
    let dir = workdir("python");
    std::fs::write(dir.join("gen.py"), format!("{code}{main}")).unwrap();
    let printed = run_ok(Command::new("python3").arg("gen.py").current_dir(&dir));
    let worst = compare("Python", &calls, &printed);
    eprintln!(
        "Python: {} calls, largest relative difference {worst:.2e}",
        calls.len()
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// `code` with the version in its header (`generated by qdot 0.1.0 (`)
/// written `VERSION`, so that the snapshot outlives a release.
fn unversioned(code: &str) -> String {
    const BY: &str = "generated by qdot ";
    let Some(at) = code.find(BY) else {
        return code.to_string();
    };
    let from = at + BY.len();
    let to = from + code[from..].find(" (").unwrap_or(0);
    format!("{}VERSION{}", &code[..from], &code[to..])
}

#[test]
fn julia_output_snapshot() {
    // Julia is not installable from the registries this machine reaches
    // (Debian has no package, PyPI none that carries the toolchain): the
    // text is checked by snapshot, generated by the binary as a user runs
    // it (the operand order no longer depends on what a process interned
    // before: determinism::a_scene_prints_as_in_a_fresh_process).
    let dir = std::env::temp_dir().join(format!("qdot-codegen-jl-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (name, src) in [
        ("pendulum", read("examples/pendulum.qd")),
        ("double_pendulum", qdot::engine::gallery::pendulum_chain(2)),
        ("chain3", qdot::engine::gallery::pendulum_chain(3)),
    ] {
        let file = format!("{name}.qd");
        std::fs::write(dir.join(&file), src).unwrap();
        for (form, suffix) in [("accelerations", ""), ("mass-matrix", "_mass")] {
            let out = std::process::Command::new(env!("CARGO_BIN_EXE_qdot"))
                .args(["codegen", &file, "--lang", "julia", "--form", form])
                .current_dir(&dir)
                .output()
                .unwrap();
            assert!(
                out.status.success(),
                "{}",
                String::from_utf8_lossy(&out.stderr)
            );
            let code = String::from_utf8(out.stdout).unwrap();
            insta::assert_snapshot!(format!("codegen_julia_{name}{suffix}"), unversioned(&code));
        }
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn names_become_identifiers_of_every_language() {
    let src = "coordinates θ1, x2\nparameters m, ω, int, y, w3, lambda\nkinetic E = 1/2*m*θ1'^2 + 1/2*int*x2'^2\npotential V = 1/2*ω^2*θ1^2 + y*x2 + w3*lambda*x2^2\n";
    for lang in [Lang::C, Lang::Rust, Lang::Python, Lang::Julia] {
        let code = codegen(src, &CodegenRequest::new("names.qd", lang)).unwrap();
        assert!(code.contains("] = θ1 (theta1)"), "{code}");
        assert!(code.contains("ω (omega)"), "{code}");
        assert!(code.contains("w3 (w3_)"), "{code}");
        assert!(code.contains("y (y_)"), "{code}");
        assert_eq!(
            code.contains("int (int_)"),
            lang == Lang::C,
            "`int` is a keyword of C only: {code}"
        );
        assert_eq!(
            code.contains("lambda (lambda_)"),
            lang == Lang::Python,
            "`lambda` is a keyword of Python only: {code}"
        );
        let body = code
            .lines()
            .filter(|l| !l.starts_with("//") && !l.starts_with('#'));
        for line in body {
            assert!(line.is_ascii(), "{lang:?}: non-ASCII code `{line}`");
        }
    }
    if have("gcc") {
        let dir = workdir("names");
        let code = codegen(src, &CodegenRequest::new("names.qd", Lang::C)).unwrap();
        std::fs::write(dir.join("names.c"), code).unwrap();
        run_ok(
            Command::new("gcc")
                .args(["-std=c99", "-Wall", "-Wextra", "-Werror", "-c", "names.c"])
                .current_dir(&dir),
        );
        std::fs::remove_dir_all(&dir).ok();
    }
}

#[test]
fn set_parameters_become_constants() {
    let src = read("examples/pendulum.qd");
    let mut req = CodegenRequest::new("pendulum.qd", Lang::C);
    req.set = [("g".to_string(), 9.81), ("l".to_string(), 2.0)]
        .into_iter()
        .collect();
    let code = codegen(&src, &req).unwrap();
    assert!(
        code.contains("Parameters (arguments, in this order): m."),
        "{code}"
    );
    assert!(
        code.contains("Constants (--set): g = 9.81, l = 2."),
        "{code}"
    );
    assert!(code.contains("int pendulum_rhs(double t, const double *y, double m, double *dy)"));
    // −g/l folded into one constant
    assert!(code.contains("-4.905"), "{code}");
}

#[test]
fn errors_are_diagnostics() {
    let req = CodegenRequest::new("x.qd", Lang::C);
    // a given function without its definition
    let e = codegen(&read("examples/moving_support.qd"), &req).unwrap_err();
    assert!(e.message.contains("needs a definition"), "{}", e.message);
    // --set of something that is not a parameter
    let mut r = req.clone();
    r.set.insert("zz".into(), 1.0);
    let e = codegen(&read("examples/pendulum.qd"), &r).unwrap_err();
    assert!(
        e.message.contains("`zz` is not a parameter"),
        "{}",
        e.message
    );
    // no coordinates: a kinetostatic scene
    let e = codegen(&read("examples/seed_21_1_kinetostatic.qd"), &req).unwrap_err();
    assert!(!e.message.is_empty());
    // a scene that does not parse
    assert!(codegen("coordinates x\nkinetic E = ", &req).is_err());
}

#[test]
fn cli_codegen() {
    let out = Command::new(env!("CARGO_BIN_EXE_qdot"))
        .args([
            "codegen",
            "examples/pendulum.qd",
            "--lang",
            "python",
            "--set",
            "g=9.81",
        ])
        .current_dir(env!("QDOT_ROOT"))
        .output()
        .unwrap();
    assert!(out.status.success());
    let code = String::from_utf8(out.stdout).unwrap();
    assert!(code.contains("def pendulum_rhs(t, y, m, l):"), "{code}");
    let out = Command::new(env!("CARGO_BIN_EXE_qdot"))
        .args(["codegen", "examples/moving_support.qd", "--lang", "c"])
        .current_dir(env!("QDOT_ROOT"))
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("error") && err.contains("--function"), "{err}");
}
