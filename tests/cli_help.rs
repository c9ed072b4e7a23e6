//! `qdot --help` and every command's help wrap at 100 columns at most
//! (clap's `wrap_help`, capped by `max_term_width`): piped, as here, and
//! on any terminal wider than that.

use crate::common::run::qdot;

#[test]
fn every_help_line_fits_in_100_columns() {
    let mut commands: Vec<&str> = qdot::app::Command::ALL.iter().map(|c| c.name()).collect();
    commands.extend(["repl", ""]);
    for name in commands {
        let args: Vec<&str> = [name, "--help"]
            .into_iter()
            .filter(|a| !a.is_empty())
            .collect();
        let (code, out, err) = qdot(&args);
        assert_eq!(code, 0, "qdot {name} --help: {err}");
        assert!(out.lines().count() > 3, "qdot {name} --help: {out}");
        for line in out.lines() {
            assert!(
                line.chars().count() <= 100,
                "qdot {name} --help has a line of {} columns:\n{line}",
                line.chars().count()
            );
        }
    }
}
