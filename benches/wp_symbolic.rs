//! The work-precision report's symbolic section: what a simulation costs
//! before it starts. The n-link chain's equations derived by qdot and by
//! SymEngine (`benches/anchor_symengine.py`) in the same run, and the
//! 5-link chain's exact accelerations by the whole command line, `qdot
//! solve` as a user runs it (process start, parse, derive, solve in lowest
//! terms, print).

use serde_json::Value;
use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

/// The chain lengths of the derivation comparison.
const NS: [usize; 3] = [10, 20, 30];

/// What the section measured.
pub struct Symbolic {
    /// (n, qdot's seconds, SymEngine's seconds if measured)
    pub derive: Vec<(usize, f64, Option<f64>)>,
    /// SymEngine's version, or why it was not measured.
    pub symengine: Result<String, String>,
    /// The 5-link chain: `qdot solve` as a process (best wall time), or why
    /// not measured; and the same work in-process (`qdot::run`).
    pub chain5_cli: Result<f64, String>,
    pub chain5_library: f64,
}

fn best_of<R>(runs: usize, mut f: impl FnMut() -> R) -> f64 {
    (0..runs)
        .map(|_| {
            let t0 = Instant::now();
            std::hint::black_box(f());
            t0.elapsed().as_secs_f64()
        })
        .fold(f64::INFINITY, f64::min)
}

/// qdot's derivation of the n-link chain: parse, then Lagrange's equations.
fn qdot_derive(n: usize) -> Result<f64, String> {
    let src = qdot::engine::gallery::pendulum_chain(n);
    qdot::Scene::parse(&src)
        .and_then(|s| s.lagrange())
        .map_err(|d| d.message)?;
    Ok(best_of(3, || {
        qdot::Scene::parse(&src).and_then(|s| s.lagrange())
    }))
}

/// The anchor's seconds per n, by the anchors' venv's Python if there is
/// one (`target/anchors-venv`), else `python3`.
fn symengine(root: &Path) -> Result<(String, Vec<(usize, f64)>), String> {
    let venv = root.join("target/anchors-venv/bin/python");
    let python = if venv.exists() {
        venv.display().to_string()
    } else {
        "python3".to_string()
    };
    let out = std::process::Command::new(&python)
        .arg(root.join("benches/anchor_symengine.py"))
        .args(NS.iter().map(|n| n.to_string()))
        .output()
        .map_err(|e| format!("{python}: {e}"))?;
    if !out.status.success() {
        let err = String::from_utf8_lossy(&out.stderr);
        return Err(format!(
            "anchor_symengine.py failed: {}",
            err.lines().last().unwrap_or("")
        ));
    }
    let v: Value = serde_json::from_slice(&out.stdout).map_err(|e| e.to_string())?;
    let rows = v["rows"]
        .as_array()
        .ok_or("no rows")?
        .iter()
        .filter_map(|r| Some((r["n"].as_u64()? as usize, r["seconds"].as_f64()?)))
        .collect();
    Ok((
        format!(
            "SymEngine {} on Python {}",
            v["symengine"].as_str().unwrap_or("?"),
            v["python"].as_str().unwrap_or("?")
        ),
        rows,
    ))
}

/// `target/release/qdot solve chain5.qd`, best of 5 (the binary must be
/// built: `cargo build --release`).
fn chain5_cli(root: &Path, scene: &Path) -> Result<f64, String> {
    let exe = root.join("target/release/qdot");
    if !exe.exists() {
        return Err("target/release/qdot is not built (cargo build --release)".into());
    }
    let run = || {
        std::process::Command::new(&exe)
            .arg("solve")
            .arg(scene)
            .output()
    };
    let first = run().map_err(|e| e.to_string())?;
    if !first.status.success() {
        return Err(String::from_utf8_lossy(&first.stderr).into_owned());
    }
    Ok(best_of(5, run))
}

pub fn measure(root: &Path) -> Result<Symbolic, String> {
    let anchor = symengine(root);
    let mut derive = Vec::new();
    for n in NS {
        eprint!("\rsymbolic: qdot derive n = {n}   ");
        let ours = qdot_derive(n)?;
        let theirs = anchor
            .as_ref()
            .ok()
            .and_then(|(_, rows)| rows.iter().find(|r| r.0 == n).map(|r| r.1));
        derive.push((n, ours, theirs));
    }
    let src = qdot::engine::gallery::pendulum_chain(5);
    let dir = root.join("target/wp");
    std::fs::create_dir_all(&dir).map_err(|e| e.to_string())?;
    let scene = dir.join("chain5.qd");
    std::fs::write(&scene, &src).map_err(|e| e.to_string())?;
    let library = || {
        qdot::run(
            qdot::Command::Solve,
            &src,
            qdot::Format::Text,
            &Default::default(),
        )
    };
    library().map_err(|d| d.message)?;
    eprintln!();
    Ok(Symbolic {
        derive,
        symengine: anchor.map(|(v, _)| v),
        chain5_cli: chain5_cli(root, &scene),
        chain5_library: best_of(5, library),
    })
}

pub fn markdown(s: &Result<Symbolic, String>) -> String {
    let mut md = String::from("\n### Before the simulation: the equations\n\n");
    let s = match s {
        Ok(s) => s,
        Err(e) => {
            let _ = writeln!(md, "Not measured in this run: {e}.");
            return md;
        }
    };
    match &s.symengine {
        Ok(v) => {
            let _ = writeln!(md, "Lagrange's equations of the n-link pendulum chain (`qdot::engine::gallery::pendulum_chain`), derived by qdot (parse and derive, in lowest terms) and by {v} (`benches/anchor_symengine.py`: the same energies, d/dt by the chain rule, expanded), best of 3:\n");
        }
        Err(e) => {
            let _ = writeln!(md, "SymEngine was **not** measured in this run: {e}.\n");
        }
    }
    let _ = writeln!(md, "| n | qdot | SymEngine | SymEngine / qdot |");
    let _ = writeln!(md, "|---|---|---|---|");
    for (n, ours, theirs) in &s.derive {
        let (t, r) = match theirs {
            Some(t) => (format!("{:.1} ms", t * 1e3), format!("{:.1}", t / ours)),
            None => ("—".into(), "—".into()),
        };
        let _ = writeln!(md, "| {n} | {:.1} ms | {t} | {r} |", ours * 1e3);
    }
    let cli = match &s.chain5_cli {
        Ok(t) => format!("**{:.3} s**", t),
        Err(e) => format!("not measured ({e})"),
    };
    let _ = writeln!(
        md,
        "\nThe 5-link chain's exact accelerations in lowest terms, `qdot solve` as a process (start, parse, derive, solve, print; best of 5): {cli}; the same in-process (`qdot::run`): {:.3} s.",
        s.chain5_library
    );
    md
}
