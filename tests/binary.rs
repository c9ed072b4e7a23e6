//! The root package's one integration test. Cargo builds a package's
//! binaries for its integration tests only, so this target is what makes
//! `cargo test` build the `qdot` binary that the suite (the `qdot-it`
//! package, tests/Cargo.toml) runs. It is named `it` like the suite, so
//! that `cargo test --release --test it` builds the binary too.

use std::process::Command;

#[test]
fn the_binary_prints_its_version() {
    let out = Command::new(env!("CARGO_BIN_EXE_qdot"))
        .arg("--version")
        .output()
        .expect("the qdot binary runs");
    assert!(out.status.success());
    assert_eq!(
        String::from_utf8_lossy(&out.stdout).trim(),
        concat!("qdot ", env!("CARGO_PKG_VERSION"))
    );
}
