//! Running the `qdot` binary from integration tests.

use std::process::Command;

/// `qdot ARGS` from the repository root: exit code, stdout, stderr.
pub fn qdot(args: &[&str]) -> (i32, String, String) {
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
