//! `qdot cycle` by its former paths: the command is
//! [`crate::app::Command::Cycle`], the engine [`crate::cycle`], the
//! renderers [`crate::output::cycle`]; here the reading of `--columns`.

pub use crate::app::CycleRun;
pub use crate::output::cycle::{csv, json, text, CycleJson, LimitsJson};

/// `--columns O_x, O_y,,M` as its names.
pub fn column_names(names: &str) -> Vec<String> {
    names
        .split(',')
        .map(str::trim)
        .filter(|n| !n.is_empty())
        .map(String::from)
        .collect()
}
