//! Where the suite finds what it tests: the `qdot` binary that the same
//! `cargo test` builds for the root package (`CARGO_BIN_EXE_qdot`, the name
//! cargo gives it in a package's own integration tests), and the
//! repository's root (`QDOT_ROOT`), which the tests' paths are relative to.

use std::path::{Path, PathBuf};

fn main() {
    let out = PathBuf::from(std::env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    // OUT_DIR is <target>/<profile>/build/qdot-it-<hash>/out
    let profile = out.ancestors().nth(3).expect("OUT_DIR is four levels deep");
    let binary = profile.join(format!("qdot{}", std::env::consts::EXE_SUFFIX));
    println!("cargo:rustc-env=CARGO_BIN_EXE_qdot={}", binary.display());
    let manifest = std::env::var_os("CARGO_MANIFEST_DIR").expect("cargo sets CARGO_MANIFEST_DIR");
    let root = Path::new(&manifest).parent().expect("tests/ has a parent");
    println!("cargo:rustc-env=QDOT_ROOT={}", root.display());
    println!("cargo:rerun-if-changed=build.rs");
}
