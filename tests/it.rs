//! The integration tests: one test crate (one link of the library instead
//! of one per file), each file of tests/ a module, in a package of its own
//! (tests/Cargo.toml) so that the suite's code builds unoptimized. Helpers
//! shared by several modules are in `common` and `stress_common`; the
//! hostile-input suite is a directory of its own.

/// The tests name files relative to the repository's root (`examples/…`),
/// in process and in the commands they run, while cargo starts a package's
/// tests in its own directory (tests/): move to the root before any test.
#[ctor::ctor(unsafe)]
fn run_from_the_repository_root() {
    std::env::set_current_dir(env!("QDOT_ROOT")).expect("the repository's root exists");
}

mod common;
mod compact;
mod stress_common;

mod app_numeric;
mod articulated;
mod assumptions;
mod book;
mod book_markdown;
mod builtins;
mod cli;
mod cli_help;
mod closed_values;
mod codegen;
mod compile;
mod constraints;
mod context;
mod cycle_pty;
mod cycle_scale;
mod definite_props;
mod determinism;
mod dimensions;
mod equilibrium;
mod error_kinds;
mod errors_json;
mod factor;
mod floquet;
mod frames;
mod fuzz_regressions;
mod hamilton;
mod hostile;
// the hostile modules say `crate::bound` (they were a crate of their own)
use hostile::bound;
mod architecture;
mod house;
mod house_rules;
mod implicit;
mod inertia_about;
mod integrators;
mod integrators_alloc;
#[cfg(feature = "jit")]
mod jit;
mod joints;
mod latex;
mod latex_pdf;
mod latex_steps;
mod lazy;
mod lecturer_form;
mod library_budget;
mod limits_doc;
mod mechanisms;
mod modes;
mod motion_pages;
mod no_panic;
mod numeric_values;
mod oscillation_details;
mod parse_ast;
mod parse_errors;
mod parse_grammar;
mod parse_props;
mod print_stability;
mod properties;
mod readme;
mod repl;
mod repl_pty;
mod repl_studies;
mod response;
mod scenes;
mod seed;
mod simulate_cli;
mod simulate_plot;
mod simulate_pty;
mod solve_blocks;
mod stability_verdicts;
mod steady;
mod stress;
mod structured;
mod studies;
mod sweep;
mod sympy_fixtures;
mod work_precision;
