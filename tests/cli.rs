//! The command line: the README's run command, the JSON contract of
//! `solve`, `derive`, `forces` and `equilibrium` for every bundled example
//! (the keys each kind of scene has, every expression string re-parsing to
//! the library's result), error rendering with file:line:column, a caret
//! and a hint, exit code 1, and warnings on stderr with exit code 0.

use crate::common::run::{json, keys, qdot, BLOCK_KEYS, DYNAMICS_KEYS, EQUILIBRIUM_KEYS};
use qdot::Scene;

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

/// `s` re-parsed in the scene's names, or a panic naming the example.
fn reparse(scene: &Scene, name: &str, what: &str, s: &serde_json::Value) -> qdot::Expr {
    let s = s
        .as_str()
        .unwrap_or_else(|| panic!("{name}: {what} is not a string: {s}"));
    scene
        .expr(s)
        .unwrap_or_else(|d| panic!("{name}: {what} `{s}` does not re-parse: {}", d.message))
}

/// The dynamics part of `solve`/`derive` JSON against the library.
fn check_dynamics(name: &str, scene: &Scene, v: &serde_json::Value, with_acc: bool) {
    let l = scene.lagrange().unwrap();
    assert_eq!(v["coordinates"], serde_json::json!(l.coordinates), "{name}");
    let eqs = v["equations"].as_array().unwrap();
    assert_eq!(eqs.len(), l.equations.len(), "{name}");
    for (i, eq) in eqs.iter().enumerate() {
        assert_eq!(keys(eq), ["coordinate", "lhs", "rhs"], "{name}");
        assert_eq!(eq["coordinate"], l.coordinates[i].as_str());
        let lhs = reparse(scene, name, "lhs", &eq["lhs"]);
        let rhs = reparse(scene, name, "rhs", &eq["rhs"]);
        assert_eq!(lhs, l.equations[i].lhs, "{name}: lhs {}", eq["lhs"]);
        assert_eq!(rhs, l.equations[i].rhs, "{name}: rhs {}", eq["rhs"]);
    }
    let rows = v["mass_matrix"].as_array().unwrap();
    assert_eq!(rows.len(), l.coordinates.len(), "{name}");
    for (i, row) in rows.iter().enumerate() {
        let row = row.as_array().unwrap();
        assert_eq!(row.len(), l.coordinates.len(), "{name}");
        for (j, m) in row.iter().enumerate() {
            assert_eq!(
                reparse(scene, name, "M", m),
                l.mass_matrix[i][j],
                "{name}: M[{i}][{j}]"
            );
        }
    }
    let f = v["forcing"].as_array().unwrap();
    assert_eq!(f.len(), l.forcing.len());
    for (i, x) in f.iter().enumerate() {
        assert_eq!(reparse(scene, name, "f", x), l.forcing[i], "{name}: f[{i}]");
    }
    if with_acc {
        let acc = l.accelerations().unwrap();
        let names: Vec<&str> = acc.iter().map(|(q, _)| q).collect();
        assert_eq!(keys(&v["accelerations"]), names, "{name}");
        for (q, a) in &acc {
            let got = reparse(scene, name, "acceleration", &v["accelerations"][q]);
            assert_eq!(&got, a, "{name}: {q}");
        }
    }
}

/// The `solve` blocks' part of the JSON against the library.
fn check_blocks(name: &str, scene: &Scene, v: &serde_json::Value) {
    let blocks = qdot::solve::system::solve_scene(scene).unwrap();
    let mut sols = Vec::new();
    let mut free = Vec::new();
    let mut checks = Vec::new();
    for (b, (sys, sol)) in scene.systems.iter().zip(&blocks).enumerate() {
        for (n, e) in &sol.values {
            if !sol.free.contains(n) {
                sols.push((n.clone(), e.clone()));
            }
        }
        free.extend(sol.free.iter().cloned());
        for &i in &sol.checks {
            checks.push(serde_json::json!({
                "block": b + 1,
                "equation": qdot::solve::system::equation_number(sys, i)
            }));
        }
    }
    let names: Vec<&str> = sols.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(keys(&v["solutions"]), names, "{name}");
    for (n, e) in &sols {
        let got = reparse(scene, name, "solution", &v["solutions"][n.as_str()]);
        assert_eq!(&got, e, "{name}: {n}");
    }
    assert_eq!(v["free_unknowns"], serde_json::json!(free), "{name}");
    assert_eq!(v["checks"], serde_json::json!(checks), "{name}");
}

#[test]
fn json_contract_and_reparse() {
    let mut kinds = std::collections::BTreeSet::new();
    for name in qdot::engine::gallery::SEED_EXAMPLES {
        let path = format!("examples/{name}.qd");
        let src = std::fs::read_to_string(format!("{}/{path}", env!("QDOT_ROOT"))).unwrap();
        let scene = Scene::parse(&src).unwrap();
        let dynamics = scene.has_dynamics() && scene.lagrange().is_ok();
        let blocks = !scene.systems.is_empty();
        kinds.insert((dynamics, blocks));
        let (code, out, err) = qdot(&["solve", &path, "--format", "json"]);
        if !dynamics && !blocks {
            // statics alone (seed 23.1): nothing to solve, `equilibrium` is
            // the command for it
            assert_eq!(code, 1, "{name}: {out}");
            assert!(out.is_empty());
            assert_eq!(
                json(&err)["error"]["kind"],
                "nothing_to_solve",
                "{name}: {err}"
            );
        } else {
            assert_eq!(code, 0, "{name}: {err}");
            let v = json(&out);
            let mut want: Vec<&str> = Vec::new();
            if dynamics {
                want.extend(DYNAMICS_KEYS);
            }
            if blocks {
                want.extend(BLOCK_KEYS);
            }
            let want = crate::common::contract_keys(&v, &scene, &want);
            assert_eq!(keys(&v), want, "{name}");
            if dynamics {
                check_dynamics(name, &scene, &v, true);
            }
            if blocks {
                check_blocks(name, &scene, &v);
            }
        }
        if dynamics {
            let (code, out, err) = qdot(&["derive", &path, "--format", "json"]);
            assert_eq!(code, 0, "{name}: {err}");
            let v = json(&out);
            let want = crate::common::contract_keys(&v, &scene, &DYNAMICS_KEYS[..4]);
            assert_eq!(keys(&v), want, "{name}");
            check_dynamics(name, &scene, &v, false);
        }
        if scene.coordinates.is_empty() {
            continue;
        }
        // `forces`: Q_k in the coordinates' order
        let (code, out, err) = qdot(&["forces", &path, "--format", "json"]);
        assert_eq!(code, 0, "{name}: {err}");
        let v = json(&out);
        let want = crate::common::contract_keys(&v, &scene, &["coordinates", "generalized_forces"]);
        assert_eq!(keys(&v), want, "{name}");
        let q = qdot::mechanics::generalized_forces(&scene);
        let names: Vec<&str> = scene.coordinates.iter().map(|c| c.name.as_str()).collect();
        assert_eq!(v["coordinates"], serde_json::json!(names));
        assert_eq!(keys(&v["generalized_forces"]), names, "{name}");
        for (k, c) in names.iter().enumerate() {
            let got = reparse(&scene, name, "Q", &v["generalized_forces"][c]);
            assert_eq!(got, q[k], "{name}: Q_{c}");
        }
        // `equilibrium`, where the forces do not depend on time
        let Ok(eq) = scene.assumptions_in_force(|| {
            qdot::solve::equilibrium::equilibria(&scene, &Default::default())
        }) else {
            let (code, _, err) = qdot(&["equilibrium", &path, "--format", "json"]);
            assert_eq!(code, 1, "{name}");
            assert!(err.contains("depends on time"), "{name}: {err}");
            continue;
        };
        let (code, out, err) = qdot(&["equilibrium", &path, "--format", "json"]);
        assert_eq!(code, 0, "{name}: {err}");
        let v = json(&out);
        let want = crate::common::contract_keys(&v, &scene, &EQUILIBRIUM_KEYS);
        assert_eq!(keys(&v), want, "{name}");
        for (k, c) in names.iter().enumerate() {
            let got = reparse(&scene, name, "Q", &v["generalized_forces"][c]);
            assert_eq!(got, eq.forces[k], "{name}: Q_{c}");
            let got = reparse(&scene, name, "condition", &v["conditions"][c]);
            assert_eq!(got, eq.conditions[k], "{name}: F_{c}");
        }
        let list = v["equilibria"].as_array().unwrap();
        assert_eq!(list.len(), eq.equilibria.len(), "{name}");
        for (j, e) in list.iter().zip(&eq.equilibria) {
            let qdot::solve::equilibrium::Position::Exact(vals) = &e.position else {
                panic!("{name}: numeric without --set")
            };
            for (k, c) in names.iter().enumerate() {
                assert_eq!(reparse(&scene, name, "position", &j[c]), vals[k], "{name}");
            }
        }
    }
    // the gallery has every kind of scene
    assert!(kinds.contains(&(true, false)), "{kinds:?}");
    assert!(kinds.contains(&(true, true)), "{kinds:?}");
    assert!(kinds.contains(&(false, true)), "{kinds:?}");
    assert!(kinds.contains(&(false, false)), "{kinds:?}");
    let (_, out, _) = qdot(&["solve", "examples/seed_21_2.qd", "--format", "json"]);
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["accelerations"]["y3"], "14*g/23");
    assert_eq!(v["accelerations"]["theta3"], "g/(23*r)");
    // a blocks-only example: the three keys and nothing else
    let (_, out, _) = qdot(&[
        "solve",
        "examples/seed_21_2_kinetostatic.qd",
        "--format",
        "json",
    ]);
    let v = json(&out);
    let scene = Scene::parse(
        &std::fs::read_to_string(concat!(
            env!("QDOT_ROOT"),
            "/examples/seed_21_2_kinetostatic.qd"
        ))
        .unwrap(),
    )
    .unwrap();
    assert_eq!(
        keys(&v),
        crate::common::contract_keys(&v, &scene, &BLOCK_KEYS)
    );
    assert_eq!(v["solutions"]["a3"], "14*g/23");
    assert_eq!(v["solutions"]["eps3"], "g/(23*r)");
    // seed 22.2: dynamics, then its block with the check (equation 10)
    let (_, out, _) = qdot(&["solve", "examples/seed_22_2.qd", "--format", "json"]);
    let v = json(&out);
    assert_eq!(v["accelerations"]["y1"], "178*g/635");
    assert_eq!(
        v["checks"],
        serde_json::json!([{"block": 1, "equation": 10}])
    );
    assert_eq!(v["free_unknowns"], serde_json::json!([]));
}

fn error_of(src: &str) -> (i32, String) {
    let path = scene_file("bad", src);
    let (code, _, err) = qdot(&["derive", &path]);
    (code, err.replace(&path, "bad.qd"))
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
            // `z` is used: an unused definition's error is a warning (tests/lazy.rs)
            "coordinates x\nparameters m\nz = m/(m - m)\nkinetic E = 1/2*z*x'^2\n",
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

/// Write `src` to a fresh temporary file; its path.
fn scene_file(tag: &str, src: &str) -> String {
    use std::sync::atomic::{AtomicUsize, Ordering};
    static N: AtomicUsize = AtomicUsize::new(0);
    let dir = std::env::temp_dir().join(format!("qdot-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(format!("{tag}-{}.qd", N.fetch_add(1, Ordering::Relaxed)));
    std::fs::write(&path, src).unwrap();
    path.to_str().unwrap().to_string()
}

/// `qdot CMD FILE ARGS…` on `src`, with the file shown as `scene.qd`.
fn run_on(src: &str, cmd: &str, args: &[&str]) -> (i32, String, String) {
    let path = scene_file(cmd, src);
    let mut all = vec![cmd, path.as_str()];
    all.extend_from_slice(args);
    let (code, out, err) = qdot(&all);
    (code, out, err.replace(&path, "scene.qd"))
}

#[test]
fn vector_load_and_block_errors_render_with_line_and_column() {
    let cases: &[(&str, &str, &str)] = &[
        (
            // `v` is used: an unused definition's error is a warning (tests/lazy.rs)
            "coordinates x\nparameters m\nv = [1, 2] + 3\nkinetic E = 1/2*m*x'^2\nforce x: 0*v\n",
            "error: can't add a vector and a number\n --> bad.qd:3:5\n  |\n\
             3 | v = [1, 2] + 3\n  |     ^^^^^^^^^^\n",
            "the left side is a vector and the right side a number",
        ),
        (
            "coordinates x\nparameters m\nv = [x, 1] + [1, 2, 3]\nkinetic E = 1/2*m*x'^2\nforce x: 0*v\n",
            "error: vectors of different sizes: 2 and 3 components\n --> bad.qd:3:5\n",
            "write plane vectors as [x, y, 0]",
        ),
        (
            "coordinates x\nparameters m, F\nkinetic E = 1/2*m*x'^2\nload [F, 0] at x\n",
            "error: the force is a vector with 2 components but the point is a number\n\
             \x20--> bad.qd:4:1\n  |\n4 | load [F, 0] at x\n  | ^^^^^^^^^^^^^^^^\n",
            "a vector force needs a position vector",
        ),
        (
            "coordinates x\nparameters m, F\nkinetic E = 1/2*m*x'^2\n\
             load [F, 0] at [x, 0, 0]\n",
            "error: the force has 2 components and the point 3\n --> bad.qd:4:1\n",
            "write both in the plane [x, y] or both in space [x, y, z]",
        ),
        (
            "coordinates x\nparameters m, F\nkinetic E = 1/2*m*x'^2\n\
             solve F {\n  F = m*x''\n}\n",
            "error: the unknown `F` is already a parameter\n --> bad.qd:4:7\n  |\n\
             4 | solve F {\n  |       ^\n",
            "remove `F` from `parameters` (line 2)",
        ),
        (
            "coordinates x, y\nparameters m\nr = [x, y]\nkinetic E = 1/2*m*r'\n",
            "error: `kinetic E` must be a number, but this is a vector with 2 components\n\
             \x20--> bad.qd:4:13\n  |\n4 | kinetic E = 1/2*m*r'\n  |             ^^^^^^^^\n",
            "the kinetic energy of a point with velocity v is 1/2*m*dot(v, v)",
        ),
        (
            "coordinates th\nparameters m, l, F\nkinetic E = 1/2*m*l^2*th'^2\n\
             r = l*[sin(th), -cos(th), 0]\ntorque cross(r, [F, 0, 0]) on th\n",
            "error: a torque is a number (the moment about the axis of its angle), found a vector with 3 components\n\
             \x20--> bad.qd:5:8\n  |\n5 | torque cross(r, [F, 0, 0]) on th\n  |        ^^^^^^^^^^^^^^^^^^^\n",
            "in the plane write the moment's z component",
        ),
    ];
    for (src, head, hint) in cases {
        let (code, err) = error_of(src);
        assert_eq!(code, 1, "{src}: {err}");
        assert!(
            err.starts_with(head),
            "for {src:?}\ngot:\n{err}\nwant to start with:\n{head}"
        );
        assert!(err.contains("\n  = hint: "), "no hint in\n{err}");
        assert!(err.contains(hint), "no hint `{hint}` in\n{err}");
    }
}

#[test]
fn block_errors_through_solve() {
    // nonlinear, and a contradiction in an over-determined block
    let (code, out, err) = run_on(
        "parameters a, b\nsolve x, y {\n  x*y = a\n  x - y = b\n}\n",
        "solve",
        &[],
    );
    assert_eq!(code, 1);
    assert!(out.is_empty(), "{out}");
    assert!(
        err.starts_with(
            "error: equation 1 is not linear in the unknowns: the term has x·y\n --> scene.qd:3:3\n"
        ),
        "{err}"
    );
    let (code, _, err) = run_on(
        "parameters a, b\nsolve x, y {\n  x + y = a; x - y = b; 2*x = a - b\n}\n",
        "solve",
        &[],
    );
    assert_eq!(code, 1);
    assert!(
        err.starts_with(
            "error: equation 3 contradicts the others: with their solution it reads 0 = −2·b\n\
             \x20--> scene.qd:3:25\n  |\n3 |   x + y = a; x - y = b; 2*x = a - b\n\
             \x20 |                         ^^^^^^^^^^^\n"
        ),
        "{err}"
    );
}

#[test]
fn warnings_go_to_stderr_and_the_run_succeeds() {
    let src = "coordinates x\nparameters m, F, a\nkinetic E = 1/2*m*x'^2\n\
               load [F, 0] at [a, 0]\nload F at x\n";
    for args in [&[][..], &["--format", "json"][..]] {
        let (code, out, err) = run_on(src, "solve", args);
        assert_eq!(code, 0, "{err}");
        let warning = if args.is_empty() {
            "warning: this load does no virtual work: its point does not move with any coordinate\n\
             \x20--> scene.qd:4:16\n  |\n4 | load [F, 0] at [a, 0]\n  |                ^^^^^^\n  \
             = hint: a force at a fixed point (a reaction of a support) does not enter the generalized forces; check the point's definition\n"
        } else {
            // with --format json, one JSON object a line
            "{\"warning\":{\"kind\":\"other\",\"data\":{},\"message\":\"this load does no virtual work: its point does not move with any coordinate\",\
             \"line\":4,\"column\":16,\"hint\":\"a force at a fixed point (a reaction of a support) does not enter the generalized forces; check the point's definition\",\
             \"labels\":[]}}\n"
        };
        assert_eq!(err, warning);
        if args.is_empty() {
            assert!(out.contains("  x\u{308} = F/m\n"), "{out}");
        } else {
            // stdout stays pure JSON
            assert_eq!(json(&out)["accelerations"]["x"], "F/m");
        }
    }
    for cmd in ["derive", "forces", "equilibrium"] {
        let (code, _, err) = run_on(src, cmd, &[]);
        assert_eq!(code, 0, "{cmd}: {err}");
        assert!(
            err.starts_with("warning: this load does no virtual work"),
            "{cmd}: {err}"
        );
    }
    // a torque on a constant angle
    let (code, _, err) = run_on(
        "coordinates x\nparameters m, M, a\nkinetic E = 1/2*m*x'^2\ntorque M on a\n",
        "forces",
        &[],
    );
    assert_eq!(code, 0);
    assert!(
        err.starts_with(
            "warning: this torque does no virtual work: its angle does not change with any coordinate\n\
             \x20--> scene.qd:4:13\n"
        ),
        "{err}"
    );
    // no warning when every load moves
    let (code, _, err) = run_on(
        "coordinates x\nparameters m, F\nkinetic E = 1/2*m*x'^2\nload F at x\n",
        "solve",
        &[],
    );
    assert_eq!(code, 0);
    assert!(err.is_empty(), "{err}");
}

#[test]
fn forces_command() {
    // A bar of length 2l at angle th from the vertical (y down), weight G at
    // its middle, horizontal force P at its end and a torque M:
    //   Q = −G·l·sin th + 2P·l·cos th + M
    let src = "coordinates th\nparameters G, P, l, M\n\
               load [0, G] at l*[sin(th), cos(th)]\n\
               load [P, 0] at 2*l*[sin(th), cos(th)]\n\
               torque M on th\n";
    let (code, out, err) = run_on(src, "forces", &[]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(
        out,
        "Generalized forces  δL = Σ Q_k·δq_k\n  Q_θ = 2·l·P·cos(θ) − G·l·sin(θ) + M\n"
    );
    let (code, out, _) = run_on(src, "forces", &["--format", "json"]);
    assert_eq!(code, 0);
    let v = json(&out);
    assert_eq!(keys(&v), ["coordinates", "generalized_forces"]);
    let scene = Scene::parse(src).unwrap();
    let q = scene
        .expr(v["generalized_forces"]["th"].as_str().unwrap())
        .unwrap();
    assert_eq!(q, scene.expr("-G*l*sin(th) + 2*P*l*cos(th) + M").unwrap());
    // a statics scene has forces but no accelerations
    let (code, _, err) = run_on(src, "solve", &[]);
    assert_eq!(code, 1);
    assert!(
        err.starts_with("error: ") && err.contains("no accelerations"),
        "{err}"
    );
    // several coordinates: aligned names, in declaration order
    let (code, out, _) = run_on(
        "coordinates x, phi\nparameters k, M\npotential V = 1/2*k*x^2\ntorque M on phi\n",
        "forces",
        &[],
    );
    assert_eq!(code, 0);
    assert_eq!(
        out,
        "Generalized forces  δL = Σ Q_k·δq_k\n  Q_x = −k·x\n  Q_φ = M\n"
    );
    // no coordinates
    let (code, _, err) = run_on("parameters a\nb = a\n", "forces", &[]);
    assert_eq!(code, 1);
    assert!(
        err.starts_with(
            "error: the scene declares no coordinates, so there are no generalized forces\n"
        ),
        "{err}"
    );
}

#[test]
fn equilibrium_command_line() {
    let (code, out, err) = qdot(&["equilibrium", "examples/seed_23_1.qd"]);
    assert_eq!(code, 0, "{err}");
    assert!(
        out.contains("\nEquilibria\n  1. θ₁ = atan(2/3·P/G), θ₂ = atan(2·P/G)  — stable\n"),
        "{out}"
    );
    // --set belongs to `equilibrium` only
    let (code, _, _) = qdot(&["solve", "examples/seed_23_1.qd", "--set", "G=1"]);
    assert_eq!(code, 2);
    // malformed --set values are reported before the file is read; a
    // value's sign needs the scene (`assume G real` allows a negative one)
    let (code, _, err) = qdot(&["equilibrium", "no/such/file.qd", "--set", "G=x"]);
    assert_eq!(code, 1);
    assert!(
        err.starts_with("error: `--set G=x`: `x` is not a number\n"),
        "{err}"
    );
    let (code, _, err) = qdot(&["equilibrium", "examples/seed_23_1.qd", "--set", "G=-1"]);
    assert_eq!(code, 1);
    assert!(
        err.starts_with("error: `--set G=-1`: parameters are positive, and -1 is not\n"),
        "{err}"
    );
    let (code, _, err) = qdot(&["equilibrium", "examples/seed_23_1.qd", "--set", "G=1,Q=2"]);
    assert_eq!(code, 1);
    assert_eq!(
        err,
        "error: `--set Q=…`: `Q` is not a parameter of the scene\n  = hint: the parameters are G, P, l\n"
    );
    // with values: the numbers are shown next to the exact positions
    let (code, out, _) = qdot(&[
        "equilibrium",
        "examples/seed_23_1.qd",
        "--set",
        "G=3,P=1,l=1",
    ]);
    assert_eq!(code, 0);
    // atan(2/9) = 0.218669…, atan(2/3) = 0.588003…
    assert!(
        out.contains(
            "  1. θ₁ = atan(2/3·P/G), θ₂ = atan(2·P/G)  ≈ (0.218669, 0.588003)  — stable\n"
        ),
        "{out}"
    );
}

#[test]
fn denominators_are_parenthesized_once() {
    let (_, out, _) = qdot(&["solve", "examples/seed_23_2.qd", "--format", "json"]);
    assert_eq!(
        json(&out)["accelerations"]["y1"],
        "g*R*(G*R - P*r)/(G*R^2 + P*r^2 + g*J2)"
    );
    let (_, out, _) = qdot(&["solve", "examples/seed_23_2.qd"]);
    assert!(
        out.contains("y\u{308}₁ = g·R·(G·R − P·r)/(G·R² + P·r² + g·J₂)\n"),
        "{out}"
    );
    let s = Scene::parse("parameters a, c, d").unwrap();
    assert_eq!(s.expr("a/(2*c + d)").unwrap().to_string(), "a/(2*c + d)");
    assert_eq!(s.expr("a/(c + d)").unwrap().to_string(), "a/(c + d)");
}

/// A parameter named like one of `modes`' matrices (M, C, K) is a warning
/// at its declaration; other commands do not mind.
#[test]
fn modes_warns_of_a_parameter_named_like_its_matrices() {
    let src = "coordinates x\nparameters M, K\nkinetic E = 1/2*M*x'^2\npotential V = 1/2*K*x^2\n";
    let (code, out, err) = run_on(src, "modes", &[]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("ω₁² = K/M"), "{out}");
    assert!(
        err.contains(
            "warning: the parameter `M` has the name of the mass matrix M of `modes`' output"
        ),
        "{err}"
    );
    assert!(err.contains("scene.qd:2:12"), "{err}");
    assert!(
        err.contains("the parameter `K` has the name of the stiffness matrix K"),
        "{err}"
    );
    let (_, _, err) = run_on(src, "solve", &[]);
    assert!(!err.contains("warning"), "{err}");
}
