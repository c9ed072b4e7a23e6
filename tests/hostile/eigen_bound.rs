//! Numeric eigenvalues that never converged (issue 46, item 10): the
//! Penning trap at d = 0.45 made nalgebra's Schur iteration, which had no
//! bound, cycle for ever. Every run here is bounded by CPU time (`ulimit
//! -t`), not by the wall clock, so a loaded machine cannot fail it.

use std::process::Command;

/// `qdot ARGS` from the repository root under `cpu_seconds` of CPU time
/// (SIGXCPU past it): exit code (`None` when a signal ended it), stdout,
/// stderr.
fn qdot_cpu_bounded(args: &[&str], cpu_seconds: u32) -> (Option<i32>, String, String) {
    let out = Command::new("sh")
        .arg("-c")
        .arg(format!("ulimit -t {cpu_seconds} && exec \"$0\" \"$@\""))
        .arg(env!("CARGO_BIN_EXE_qdot"))
        .args(args)
        .current_dir(env!("QDOT_ROOT"))
        .output()
        .expect("qdot starts");
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn the_penning_trap_past_its_stability_limit_answers_unstable() {
    // B² = 9 < 2·m·V0/(e·d²) = 9.88: the magnetron motion grows
    for d in ["0.45", "0.44", "0.4"] {
        let set = format!("m=1,e=1,V0=1,d={d},B=3");
        let (code, out, err) =
            qdot_cpu_bounded(&["modes", "examples/penning_modes.qd", "--set", &set], 10);
        assert_eq!(code, Some(0), "d = {d}: {err}");
        assert!(
            out.ends_with("Stability of the equilibrium: unstable\n"),
            "d = {d}:\n{out}"
        );
    }
    // and inside it, stable
    let (code, out, err) = qdot_cpu_bounded(
        &[
            "modes",
            "examples/penning_modes.qd",
            "--set",
            "m=1,e=1,V0=1,d=0.472,B=3",
        ],
        10,
    );
    assert_eq!(code, Some(0), "{err}");
    assert!(
        out.contains("Stability of the equilibrium: stable\n"),
        "{out}"
    );
}
