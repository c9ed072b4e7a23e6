//! The command line: the README's run command, the JSON contract (every
//! expression string re-parses to the library's result), and error
//! rendering with file:line:column, a caret and a hint, exit code 1.

use qdot::Scene;
use std::process::Command;

fn qdot(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_qdot"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("qdot runs");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn readme_command_prints_the_accelerations() {
    let (code, out, err) = qdot(&["solve", "examples/seed_23_4.qd"]);
    assert_eq!(code, 0, "{err}");
    // Dots are combining characters: y + U+0308 is ÿ, θ + U+0308 is θ̈.
    assert!(out.contains("y\u{308}₃ = 343/460·g"), "{out}");
    assert!(out.contains("θ\u{308}₃ = 13/460·g/r"), "{out}");
    assert!(
        out.contains("13/2·G/g·y\u{308}₃ + G·r/g·θ\u{308}₃ = 39/8·G"),
        "{out}"
    );
}

#[test]
fn json_contract_and_reparse() {
    for name in qdot::gallery::SEED_EXAMPLES {
        let path = format!("examples/{name}.qd");
        let (code, out, err) = qdot(&["solve", &path, "--format", "json"]);
        assert_eq!(code, 0, "{err}");
        let v: serde_json::Value = serde_json::from_str(&out).expect("valid JSON");
        let keys: Vec<&str> = v.as_object().unwrap().keys().map(|k| k.as_str()).collect();
        assert_eq!(
            keys,
            [
                "coordinates",
                "equations",
                "mass_matrix",
                "forcing",
                "accelerations"
            ]
        );
        let src =
            std::fs::read_to_string(format!("{}/{path}", env!("CARGO_MANIFEST_DIR"))).unwrap();
        let scene = Scene::parse(&src).unwrap();
        let l = scene.lagrange().unwrap();
        let acc = l.accelerations().unwrap();
        for (i, eq) in v["equations"].as_array().unwrap().iter().enumerate() {
            assert_eq!(eq["coordinate"], l.coordinates[i].as_str());
            let lhs = scene.expr(eq["lhs"].as_str().unwrap()).unwrap();
            let rhs = scene.expr(eq["rhs"].as_str().unwrap()).unwrap();
            assert_eq!(lhs, l.equations[i].lhs, "{name}: lhs {}", eq["lhs"]);
            assert_eq!(rhs, l.equations[i].rhs, "{name}: rhs {}", eq["rhs"]);
        }
        for (i, row) in v["mass_matrix"].as_array().unwrap().iter().enumerate() {
            for (j, m) in row.as_array().unwrap().iter().enumerate() {
                assert_eq!(
                    scene.expr(m.as_str().unwrap()).unwrap(),
                    l.mass_matrix[i][j]
                );
            }
        }
        for (q, a) in &acc {
            let s = v["accelerations"][q.as_str()].as_str().unwrap();
            assert_eq!(&scene.expr(s).unwrap(), a, "{name}: {q}: {s}");
        }
    }
    let (_, out, _) = qdot(&["solve", "examples/seed_21_2.qd", "--format", "json"]);
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["accelerations"]["y3"], "14*g/23");
    assert_eq!(v["accelerations"]["theta3"], "g/(23*r)");
}

fn error_of(src: &str) -> (i32, String) {
    let dir = std::env::temp_dir().join(format!("qdot-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(format!("bad{}.qd", src.len()));
    std::fs::write(&path, src).unwrap();
    let (code, _, err) = qdot(&["derive", path.to_str().unwrap()]);
    (code, err.replace(path.to_str().unwrap(), "bad.qd"))
}

#[test]
fn errors_point_at_the_source() {
    let cases: &[(&str, &str, &str)] = &[
        (
            "coordinates x\nparameters m\nkinetic E = 1/2*m*x'^2 + q\n",
            "error: unknown name `q`\n --> bad.qd:3:26\n  |\n3 | kinetic E = 1/2*m*x'^2 + q\n  |                          ^\n",
            "hint: declare it with `parameters q`",
        ),
        (
            "coordinates x, x\n",
            "error: coordinate declared twice: `x` is already a coordinate\n --> bad.qd:1:16\n",
            "hint:",
        ),
        (
            "coordinates x\nparameters m\na = b + 1\nb = 2*a\nkinetic E = m*x'^2\n",
            "error: cyclic definition: a → b → a\n --> bad.qd:4:7\n",
            "cannot use itself",
        ),
        (
            "coordinates x\nparameters m\nkinetic E = 1/2*m'^2\n",
            "error: `m` is not a function of time, so `'` cannot be taken\n --> bad.qd:3:17\n",
            "d/dt",
        ),
        (
            "coordinates x\nparameters m\nz = m/(m - m)\n",
            "error: division by zero: this divisor is exactly 0\n --> bad.qd:3:8\n  |\n3 | z = m/(m - m)\n  |        ^^^^^\n",
            "hint:",
        ),
        (
            "coordinates x\nparameters m\nkinetic E = 1.2.3*m*x'^2\n",
            "error: malformed number `1.2.3`\n --> bad.qd:3:13\n",
            "at most one decimal point",
        ),
        (
            "coordinates x\nparameters m\nkinetic E = 1/2*m*x'^2\nforce y: 3\n",
            "error: `force y:` needs a coordinate, and `y` is not one\n --> bad.qd:4:7\n",
            "the coordinates are x",
        ),
        (
            "coordinates x\nparameters m\nkinetic E = 1/2*m*x'^2\nV = sinn(x)\n",
            "error: unknown function `sinn`\n --> bad.qd:4:5\n",
            "the functions are",
        ),
        (
            "parameters t\n",
            "error: `t` is reserved: it is time\n --> bad.qd:1:12\n",
            "choose another name",
        ),
        (
            "coordinates x, y\nparameters m\nkinetic E = 1/2*m*(x' + y')^2\n",
            "error: the mass matrix is singular",
            "",
        ),
    ];
    for (src, head, hint) in cases {
        let (code, err) = if head.contains("singular") {
            let dir = std::env::temp_dir();
            let p = dir.join(format!("qdot-sing-{}.qd", std::process::id()));
            std::fs::write(&p, src).unwrap();
            let (c, _, e) = qdot(&["solve", p.to_str().unwrap()]);
            (c, e)
        } else {
            error_of(src)
        };
        assert_eq!(code, 1, "{src}: {err}");
        assert!(
            err.starts_with(head),
            "for {src:?}\ngot:\n{err}\nwant to start with:\n{head}"
        );
        assert!(
            err.contains(hint),
            "for {src:?}: no hint `{hint}` in\n{err}"
        );
    }
}

#[test]
fn usage_errors_and_missing_files() {
    let (code, _, err) = qdot(&["solve", "no/such/file.qd"]);
    assert_eq!(code, 1);
    assert!(err.contains("cannot read `no/such/file.qd`"), "{err}");
    let (code, _, _) = qdot(&["solve", "examples/seed_21_1.qd", "--format", "yaml"]);
    assert_eq!(code, 2);
}
