//! `qdot floquet`'s options: the Floquet stability of a scene with
//! periodic coefficients (the engine is [`crate::floquet`], the command
//! [`crate::app::Command::Floquet`], its renderers
//! [`crate::output::floquet`]), at one set of parameter values or over a
//! grid of one or two (`--over`).

use crate::diag::Diagnostic;

/// One varied parameter of `--over`: COUNT values from FROM to TO.
pub use crate::scene::given::GridAxis as Axis;

/// `--over p=FROM:TO:COUNT[,r=FROM:TO:COUNT]`: one or two axes
/// ([`crate::scene::given::parse_ranges`] with
/// [`crate::scene::given::FLOQUET_OVER`]).
pub fn parse_over(text: &str) -> Result<Vec<Axis>, Diagnostic> {
    crate::scene::given::parse_ranges(&crate::scene::given::FLOQUET_OVER, text)
}

/// One point of a grid: the varied parameters' values, and the analysis
/// or why it failed.
pub type Point = crate::app::FloquetPoint;

pub use crate::app::FloquetRun;
pub use crate::output::floquet::{csv, equations, json, text};
