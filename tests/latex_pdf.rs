//! Every seed example's `qdot latex --standalone --steps` compiles with a
//! real `pdflatex`, with no errors, no warnings and no box more than 10pt
//! too wide.
//!
//! `.ci/run` installs TeX Live (Debian's texlive-latex-base) and sets
//! `QDOT_REQUIRE_TEX=1`, so in CI a missing pdflatex fails this test. On a
//! machine without TeX it says so and checks nothing else.

use crate::common;
use std::path::Path;
use std::process::Command;

fn pdflatex_present() -> bool {
    Command::new("pdflatex")
        .arg("--version")
        .output()
        .is_ok_and(|o| o.status.success())
}

/// The widths of the overfull boxes a log reports, in pt.
fn overfull(log: &str) -> Vec<f64> {
    log.lines()
        .filter_map(|l| l.strip_prefix("Overfull \\hbox ("))
        .filter_map(|l| l.split("pt too wide").next())
        .filter_map(|w| w.parse().ok())
        .collect()
}

#[test]
fn overfull_boxes_are_read_from_the_log() {
    let log = "Overfull \\hbox (12.5pt too wide) in paragraph\nOverfull \\hbox (0.3pt too wide) detected at line 4\n";
    assert_eq!(overfull(log), vec![12.5, 0.3]);
}

#[test]
fn every_seed_example_compiles_with_pdflatex() {
    if !pdflatex_present() {
        assert!(
            std::env::var_os("QDOT_REQUIRE_TEX").is_none(),
            "pdflatex is required (QDOT_REQUIRE_TEX is set) but not installed: apt-get install texlive-latex-base"
        );
        eprintln!(
            "pdflatex not found: the LaTeX compile test checks nothing here (CI installs it)"
        );
        return;
    }
    let root = Path::new(env!("QDOT_ROOT"));
    let dir = std::env::temp_dir().join(format!("qdot-pdflatex-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let mut compiled = 0;
    let mut examples: Vec<_> = std::fs::read_dir(root.join("examples"))
        .expect("examples/")
        .map(|e| e.expect("entry").path())
        .filter(|p| {
            p.extension().is_some_and(|e| e == "qd")
                && p.file_name()
                    .and_then(|n| n.to_str())
                    .is_some_and(|n| n.starts_with("seed_"))
        })
        .collect();
    examples.sort();
    for path in &examples {
        let rel = path.strip_prefix(root).expect("under the root");
        let rel = rel.to_str().expect("utf-8 path");
        let (code, tex, err) = common::run::qdot(&["latex", "--standalone", "--steps", rel]);
        assert_eq!(code, 0, "qdot latex {rel}: {err}");
        let stem = path.file_stem().and_then(|s| s.to_str()).expect("stem");
        std::fs::write(dir.join(format!("{stem}.tex")), &tex).expect("write .tex");
        let out = Command::new("pdflatex")
            .args(["-interaction=nonstopmode", "-halt-on-error"])
            .arg(format!("{stem}.tex"))
            .current_dir(&dir)
            .output()
            .expect("pdflatex runs");
        let log = std::fs::read_to_string(dir.join(format!("{stem}.log"))).unwrap_or_default();
        assert!(
            out.status.success(),
            "pdflatex failed on {rel}:\n{}",
            String::from_utf8_lossy(&out.stdout)
        );
        assert!(dir.join(format!("{stem}.pdf")).exists(), "{rel}: no PDF");
        let wide: Vec<f64> = overfull(&log).into_iter().filter(|&w| w > 10.0).collect();
        assert!(wide.is_empty(), "{rel}: overfull boxes {wide:?}pt");
        assert!(
            !log.contains("LaTeX Warning") && !log.contains("Package amsmath Warning"),
            "{rel}: warnings in the log"
        );
        compiled += 1;
    }
    assert_eq!(compiled, 17, "every seed example was compiled");
    let _ = std::fs::remove_dir_all(&dir);
}
