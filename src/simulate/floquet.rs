//! `qdot floquet`'s options: the Floquet stability of a scene with
//! periodic coefficients (the engine is [`crate::floquet`], the command
//! [`crate::app::Command::Floquet`], its renderers
//! [`crate::output::floquet`]), at one set of parameter values or over a
//! grid of one or two (`--over`).

use crate::algebra::sign::Values;
use crate::diag::Diagnostic;
use crate::floquet::FloquetRequest;

/// One varied parameter of `--over`: COUNT values from FROM to TO.
pub use crate::scene::given::GridAxis as Axis;

/// `--over p=FROM:TO:COUNT[,r=FROM:TO:COUNT]`: one or two axes
/// ([`crate::scene::given::parse_ranges`] with
/// [`crate::scene::given::FLOQUET_OVER`]).
pub fn parse_over(text: &str) -> Result<Vec<Axis>, Diagnostic> {
    crate::scene::given::parse_ranges(&crate::scene::given::FLOQUET_OVER, text)
}

/// What `qdot floquet` runs.
#[derive(Clone, Debug, Default)]
pub struct Request {
    /// The reference, given functions and period.
    pub floquet: FloquetRequest,
    /// `--set`: the parameters' values (the varied ones may be left out).
    pub set: Values,
    /// `--over`: none, one or two axes.
    pub over: Vec<Axis>,
}

/// One point of a grid: the varied parameters' values, and the analysis
/// or why it failed.
pub type Point = crate::app::FloquetPoint;

pub use crate::app::FloquetRun;
pub use crate::output::floquet::{csv, equations, json, text};

/// Read the scene, linearize, and analyse every point: [`crate::app::run`]
/// of [`crate::app::Command::Floquet`] (kept for the fuzz targets).
#[doc(hidden)]
pub fn run(src: &str, req: &Request) -> Result<FloquetRun, Diagnostic> {
    use crate::app::{self, AnyReport, Command, CommandOptions, Context};
    let opts = CommandOptions {
        at: req.floquet.at.clone(),
        functions: req.floquet.functions.clone(),
        period: req.floquet.period,
        max_steps: req.floquet.max_steps,
        set: req.set.clone(),
        over: req.over.clone(),
        ..CommandOptions::default()
    };
    match app::run(
        &Context::new().with_max_terms(crate::budget::limit()),
        Command::Floquet,
        src,
        &opts,
    )? {
        AnyReport::Floquet(r) => Ok(r.result),
        _ => Err(Diagnostic::global("no Floquet analysis")),
    }
}
