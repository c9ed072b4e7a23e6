//! Running the `qdot` binary from integration tests.

use std::process::Command;

/// The JSON keys of `qdot solve` for a scene with dynamics, in order.
pub const DYNAMICS_KEYS: [&str; 5] = [
    "coordinates",
    "equations",
    "mass_matrix",
    "forcing",
    "accelerations",
];

/// The JSON keys `qdot solve` adds for `solve` blocks, in order.
pub const BLOCK_KEYS: [&str; 3] = ["solutions", "free_unknowns", "checks"];

/// The JSON keys of `qdot equilibrium`, in order.
pub const EQUILIBRIUM_KEYS: [&str; 14] = [
    "coordinates",
    "generalized_forces",
    "conditions",
    "exact",
    "equilibria",
    "stability",
    "notes",
    "approx",
    "multiplicity",
    "digits",
    "certified",
    "enclosure",
    "complete",
    "caveat",
];

/// `qdot ARGS` from the repository root: exit code, stdout, stderr.
pub fn qdot(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_qdot"))
        .args(args)
        .current_dir(env!("QDOT_ROOT"))
        .output()
        .expect("qdot runs");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// `qdot COMMAND FILE REST…` on `src` written to a temporary file named
/// after `suite` and `tag`; the file's path in messages reads `scene.qd`.
pub fn qdot_on(
    suite: &str,
    tag: &str,
    src: &str,
    command: &str,
    rest: &[&str],
) -> (i32, String, String) {
    let dir = std::env::temp_dir().join(format!("qdot-{suite}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temporary directory");
    let path = dir.join(format!("{tag}.qd"));
    std::fs::write(&path, src).expect("scene written");
    let p = path.to_str().expect("utf-8 path").to_string();
    let mut all = vec![command, p.as_str()];
    all.extend_from_slice(rest);
    let (code, out, err) = qdot(&all);
    (code, out, err.replace(&p, "scene.qd"))
}

/// Parse JSON output, or panic showing it.
pub fn json(out: &str) -> serde_json::Value {
    serde_json::from_str(out).unwrap_or_else(|e| panic!("invalid JSON ({e}):\n{out}"))
}

/// The keys of a JSON object, in order.
pub fn keys(v: &serde_json::Value) -> Vec<&str> {
    v.as_object()
        .unwrap_or_else(|| panic!("not an object: {v}"))
        .keys()
        .map(String::as_str)
        .collect()
}
