//! `qdot floquet`'s options: the Floquet stability of a scene with
//! periodic coefficients (the engine is [`crate::floquet`], the command
//! [`crate::app::Command::Floquet`], its renderers
//! [`crate::output::floquet`]), at one set of parameter values or over a
//! grid of one or two (`--over`).

use crate::algebra::sign::Values;
use crate::diag::{Diagnostic, ErrorKind};
use crate::floquet::FloquetRequest;

/// One varied parameter of `--over`: COUNT values from FROM to TO.
pub use crate::scene::given::GridAxis as Axis;

/// `--over p=FROM:TO:COUNT[,r=FROM:TO:COUNT]`: one or two axes.
pub fn parse_over(text: &str) -> Result<Vec<Axis>, Diagnostic> {
    let bad = |what: String| {
        Diagnostic::global(format!("`--over {text}`: {what}"))
            .with_hint("--over NAME=FROM:TO:COUNT, or two of them for a chart: --over \"delta=-1:3:81,eps=0:2:41\"")
            .with_kind(ErrorKind::bad_option("--over"))
    };
    let mut axes = Vec::new();
    for part in text.split(',') {
        let (name, range) = part
            .split_once('=')
            .ok_or_else(|| bad(format!("no `=` in `{part}`")))?;
        let name = name.trim();
        let parts: Vec<&str> = range.split(':').map(str::trim).collect();
        let [from, to, count] = parts[..] else {
            return Err(bad(format!("`{part}`: the range is FROM:TO:COUNT")));
        };
        let number = |s: &str| match s.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(v),
            _ => Err(bad(format!("`{s}` is not a number"))),
        };
        let limit = crate::limits::MAX_FLOQUET_POINTS;
        let count = count
            .parse::<usize>()
            .ok()
            .filter(|c| (1..=limit).contains(c))
            .ok_or_else(|| {
                bad(format!(
                    "COUNT `{count}` must be a whole number from 1 to {}",
                    crate::budget::grouped(limit)
                ))
            })?;
        axes.push(Axis {
            name: name.to_string(),
            from: number(from)?,
            to: number(to)?,
            count,
        });
    }
    if axes.len() > 2 {
        return Err(bad("one or two parameters vary, not more".into()));
    }
    if axes.len() == 2 && axes[0].name == axes[1].name {
        // as `sweep --vary` says it
        let name = &axes[0].name;
        return Err(
            Diagnostic::global(format!("`--over {name}`: `{name}` is varied twice"))
                .with_hint("vary each parameter once")
                .with_kind(ErrorKind::bad_option("--over")),
        );
    }
    let total = axes.iter().map(|a| a.count).product::<usize>();
    if total > crate::limits::MAX_FLOQUET_POINTS {
        return Err(bad(format!(
            "{} points, more than {}",
            crate::budget::grouped(total),
            crate::budget::grouped(crate::limits::MAX_FLOQUET_POINTS)
        )));
    }
    Ok(axes)
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
