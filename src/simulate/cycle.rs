//! `qdot cycle` by its former paths: the command is
//! [`crate::app::Command::Cycle`], the engine [`crate::cycle`], the
//! renderers [`crate::output::cycle`]. Kept for the Python module and the
//! fuzz targets.

use crate::cycle::{CycleRequest, CycleTable};
use crate::diag::Diagnostic;

pub use crate::app::CycleRun;
pub use crate::output::cycle::{csv, json, text, CycleJson, LimitsJson};

/// Read the scene `src` and analyse its mechanism as `req` asks:
/// [`crate::app::run`] of [`crate::app::Command::Cycle`].
#[doc(hidden)]
pub fn run(src: &str, req: &CycleRequest) -> Result<CycleRun, Diagnostic> {
    use crate::app::{self, AnyReport, Command, CommandOptions, Context};
    let opts = CommandOptions {
        over: vec![req.over.clone()],
        set: req.set.clone(),
        guess: req.guess.clone(),
        ..CommandOptions::default()
    };
    match app::run(
        &Context::new().with_max_terms(crate::budget::limit()),
        Command::Cycle,
        src,
        &opts,
    )? {
        AnyReport::Cycle(r) => Ok(r.result),
        _ => Err(Diagnostic::global("no cycle")),
    }
}

/// The table with only the columns `names` (comma-separated) after the
/// varied one, in the order given (`--columns O_x,O_y,M`).
#[doc(hidden)]
pub fn select(table: &CycleTable, names: &str) -> Result<CycleTable, Diagnostic> {
    table.select(&column_names(names))
}

/// `--columns O_x, O_y,,M` as its names.
pub fn column_names(names: &str) -> Vec<String> {
    names
        .split(',')
        .map(str::trim)
        .filter(|n| !n.is_empty())
        .map(String::from)
        .collect()
}
