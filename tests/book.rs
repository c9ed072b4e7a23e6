//! The book shows qdot's real output: every ```text block preceded by a
//! `<!-- qdot ARGS -->` comment must equal what `qdot ARGS` prints (run
//! from the repository root). `QDOT_BLESS=1 cargo test --test book` rewrites
//! the blocks from the current output.

use std::process::Command;

fn run(args: &str) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_qdot"))
        .args(args.split_whitespace())
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("qdot runs");
    assert!(
        out.status.success(),
        "qdot {args} failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// The page with every marked block replaced by the current output, and
/// the number of blocks.
fn regenerate(page: &str) -> (String, usize) {
    let mut out = String::with_capacity(page.len());
    let mut rest = page;
    let mut n = 0;
    while let Some(at) = rest.find("<!-- qdot ") {
        let end = rest[at..]
            .find("-->")
            .map(|e| at + e)
            .expect("marker closed");
        let args = rest[at + "<!-- qdot ".len()..end].trim();
        let fence = rest[end..]
            .find("```text\n")
            .map(|f| end + f)
            .expect("a text block follows the marker");
        let body = fence + "```text\n".len();
        let close = rest[body..]
            .find("```")
            .map(|c| body + c)
            .expect("block closed");
        out.push_str(&rest[..body]);
        out.push_str(&run(args));
        rest = &rest[close..];
        n += 1;
    }
    out.push_str(rest);
    (out, n)
}

#[test]
fn book_output_is_qdots_real_output() {
    let dir = format!("{}/book/src", env!("CARGO_MANIFEST_DIR"));
    let bless = std::env::var_os("QDOT_BLESS").is_some();
    let mut blocks = 0;
    for entry in std::fs::read_dir(&dir).expect("book/src") {
        let path = entry.expect("entry").path();
        if path.extension().is_none_or(|e| e != "md") {
            continue;
        }
        let page = std::fs::read_to_string(&path).expect("page");
        let (fresh, n) = regenerate(&page);
        blocks += n;
        if bless {
            std::fs::write(&path, &fresh).expect("write page");
        } else {
            pretty_assertions::assert_eq!(
                page,
                fresh,
                "{} drifted; run QDOT_BLESS=1 cargo test --test book",
                path.display()
            );
        }
    }
    assert!(blocks >= 5, "only {blocks} checked blocks");
}
