//! The generated C (`qdot codegen --lang c`, gcc -O2) against hand-written
//! C right-hand sides (`hand/rhs.c`) of the pendulum, the double pendulum
//! and seed 24.2: each checked against the other at the timed state, then
//! 10⁷ calls timed, best of 5, the functions in their own translation
//! units (called, not inlined, as an integrator calls them). Prints the
//! table and writes `benches/results/codegen_c.json`. Needs gcc (skipped
//! with a message without it).
//!
//! `cargo bench -p qdot-benches --bench codegen_c`

use qdot::simulate::codegen::{codegen, CodegenRequest, Lang};
use std::path::PathBuf;
use std::process::Command;

const CALLS: u64 = 10_000_000;
const REPEATS: usize = 5;

/// name, scene, parameter values, state.
fn problems() -> Vec<(&'static str, String, Vec<f64>, Vec<f64>)> {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..");
    let read = |p: &str| std::fs::read_to_string(root.join(p)).expect("the example");
    vec![
        (
            "pendulum",
            read("examples/pendulum.qd"),
            vec![1.0, 1.0, 9.81],
            vec![3.0, 0.1],
        ),
        (
            "double_pendulum",
            qdot::engine::gallery::pendulum_chain(2),
            vec![1.0, 1.0, 9.81],
            vec![0.5, 1.0, 0.3, -0.2],
        ),
        (
            "seed_24_2",
            read("examples/seed_24_2.qd"),
            vec![1.0, 4.0, 0.5],
            vec![0.1, -0.2, 0.3, 0.05],
        ),
    ]
}

fn main() {
    if Command::new("gcc").arg("--version").output().is_err() {
        eprintln!("SKIPPED: gcc is not on this machine");
        return;
    }
    let dir = std::env::temp_dir().join(format!("qdot-codegen-bench-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut generated = String::new();
    let mut driver = String::from(
        "#define _POSIX_C_SOURCE 199309L\n#include <stdio.h>\n#include <math.h>\n#include <time.h>\n\nstatic double now(void)\n{\n    struct timespec ts;\n    clock_gettime(CLOCK_MONOTONIC, &ts);\n    return ts.tv_sec + 1e-9 * ts.tv_nsec;\n}\n\n",
    );
    let mut body = String::from("int main(void)\n{\n");
    for (name, scene, params, y) in problems() {
        let code = codegen(&scene, &CodegenRequest::new(&format!("{name}.qd"), Lang::C)).unwrap();
        generated.push_str(&code);
        let n = y.len();
        let ps: Vec<String> = params.iter().map(|p| format!("{p:?}")).collect();
        let ys: Vec<String> = y.iter().map(|p| format!("{p:?}")).collect();
        let sig = format!(
            "int {{}}(double, const double *, {}double *);\n",
            "double, ".repeat(params.len())
        );
        driver.push_str(&sig.replace("{}", &format!("{name}_rhs")));
        driver.push_str(&sig.replace("{}", &format!("hand_{name}_rhs")));
        body.push_str(&format!(
            "    {{\n        double y[{n}] = {{{}}}, a[{n}], b[{n}];\n        {name}_rhs(0.0, y, {p}, a);\n        hand_{name}_rhs(0.0, y, {p}, b);\n        double err = 0.0;\n        for (int k = 0; k < {n}; k++) {{ double e = fabs(a[k] - b[k]) / (fabs(b[k]) + 1e-300); if (e > err) err = e; }}\n        double best[2] = {{1e300, 1e300}}, sink = 0.0;\n        for (int r = 0; r < {REPEATS}; r++) {{\n",
            ys.join(", "),
            p = ps.join(", ")
        ));
        for (slot, f) in [(0, format!("{name}_rhs")), (1, format!("hand_{name}_rhs"))] {
            body.push_str(&format!(
                "            {{\n                double t0 = now();\n                for (long i = 0; i < {CALLS}L; i++) {{\n                    y[0] = {y0:?} + 1e-12 * (double)(i & 1023);\n                    {f}(0.0, y, {p}, a);\n                    sink += a[{last}];\n                }}\n                double dt = now() - t0;\n                if (dt < best[{slot}]) best[{slot}] = dt;\n            }}\n",
                y0 = y[0],
                p = ps.join(", "),
                last = n - 1
            ));
        }
        body.push_str(&format!(
            "        }}\n        printf(\"{name} %.6e %.6e %.3e %g\\n\", best[0] / {CALLS}.0 * 1e9, best[1] / {CALLS}.0 * 1e9, err, sink);\n    }}\n"
        ));
    }
    body.push_str("    return 0;\n}\n");
    std::fs::write(dir.join("gen.c"), generated).unwrap();
    std::fs::write(dir.join("hand.c"), include_str!("hand/rhs.c")).unwrap();
    std::fs::write(dir.join("main.c"), driver + &body).unwrap();
    let cc = Command::new("gcc")
        .args([
            "-O2", "-std=c99", "gen.c", "hand.c", "main.c", "-o", "bench", "-lm",
        ])
        .current_dir(&dir)
        .output()
        .unwrap();
    assert!(
        cc.status.success(),
        "{}",
        String::from_utf8_lossy(&cc.stderr)
    );
    let out = Command::new(dir.join("bench")).output().unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    println!("| problem | generated C (ns/call) | hand-written C (ns/call) | ratio | max rel. difference |");
    println!("|---|---|---|---|---|");
    let mut rows = Vec::new();
    for line in text.lines() {
        let f: Vec<&str> = line.split_whitespace().collect();
        let (gen, hand, err): (f64, f64, f64) = (
            f[1].parse().unwrap(),
            f[2].parse().unwrap(),
            f[3].parse().unwrap(),
        );
        println!(
            "| {} | {gen:.2} | {hand:.2} | {:.3} | {err:.1e} |",
            f[0],
            gen / hand
        );
        rows.push(serde_json::json!({
            "problem": f[0], "generated_ns": gen, "hand_ns": hand, "ratio": gen / hand, "max_rel_difference": err,
        }));
    }
    let json = serde_json::json!({ "calls": CALLS, "repeats": REPEATS, "compiler": "gcc -O2", "rows": rows });
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("results/codegen_c.json");
    std::fs::write(&path, format!("{json:#}\n")).unwrap();
    println!("written {}", path.display());
    std::fs::remove_dir_all(&dir).ok();
}
