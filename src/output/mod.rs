//! Rendering results: readable text and the JSON contract.
//!
//! JSON keys are a public interface (scripts depend on them): each
//! command's JSON object is a typed wire struct of [`wire`], whose
//! documentation lists its keys in order: [`wire::DeriveJson`],
//! [`wire::SolveJson`], [`wire::ForcesJson`], [`wire::HamiltonJson`],
//! [`wire::IntegralsJson`], [`wire::EquilibriumJson`],
//! [`wire::ModesJson`], [`wire::CheckJson`]; every command but `check`
//! then adds its scene's keys, [`wire::SceneJson`] (`bodies`,
//! `constraints`, and `dimensions` last).
//!
//! Every expression string is in qdot's input syntax and re-parses to the
//! same expression.

use crate::app::{AnyReport, Context, Report};
use crate::diag::Diagnostic;
use crate::expr::print::{self};
use crate::expr::Expr;
use crate::scene::Scene;
use crate::solve::equilibrium::{self, Equilibria, Position, Values};

mod at_values;
pub mod cycle;
mod dimensions;
pub mod floquet;
pub mod latex;
mod modes;
pub mod response;
pub mod run;
pub mod sweep;
pub mod table;
mod text;
pub mod wire;

pub use dimensions::check_text;
pub use modes::modes_text;
pub use text::{derive_text, equilibrium_text, forces_text, padded, solutions_text, solve_text};
pub use wire::{bodies_json, dimensions_json, solve_json};
use wire::{
    json_string, CheckJson, DeriveJson, EquilibriumJson, ForcesJson, HamiltonJson, IntegralsJson,
    ModesJson, SceneJson, SolveJson, WithScene,
};

pub use crate::app::{Command, CommandOptions, Format};

/// Run `cmd` on the scene source `src`: the output, and the warnings to show.
pub fn run(
    cmd: Command,
    src: &str,
    fmt: Format,
    set: &Values,
) -> Result<(String, Vec<Diagnostic>), Diagnostic> {
    let opts = CommandOptions {
        set: set.clone(),
        ..CommandOptions::default()
    };
    run_with(cmd, src, fmt, &opts)
}

/// [`run()`] with every option, within the work budget `opts.max_terms`:
/// [`crate::app::run`], then [`render`].
pub fn run_with(
    cmd: Command,
    src: &str,
    fmt: Format,
    opts: &CommandOptions,
) -> Result<(String, Vec<Diagnostic>), Diagnostic> {
    let ctx = Context::new().with_max_terms(opts.max_terms);
    let report = crate::app::run(&ctx, cmd, src, opts)?;
    let out = render(&report, fmt)?;
    Ok((out, report.warnings().to_vec()))
}

/// The error of an exceeded work budget (kept here too: it was first public here).
pub use crate::diag::too_large;

/// `report` written in `fmt`, in the context it was computed in (its
/// budget bounds what printing writes out).
pub fn render(report: &AnyReport, fmt: Format) -> Result<String, Diagnostic> {
    let cmd = report.command();
    if fmt == Format::Csv && !cmd.formats().contains(&fmt) {
        return Err(not_written(cmd, fmt));
    }
    match report {
        AnyReport::Derive(r) => in_context(r, |r| {
            let lag = &r.result.lagrange;
            let scene = r.scene();
            Ok(match fmt {
                Format::Csv => return Err(not_written(cmd, fmt)),
                Format::Text => text::dynamics_text(scene, lag, None, &[]),
                Format::Json => scene_json(scene, DeriveJson::new(scene, lag))?,
                Format::Latex => latex::write(scene, |w| {
                    if let Some((tape, roots)) = wire::structured_roots(scene, Some(lag), None, &[])
                    {
                        w.intermediates(Some(tape), roots);
                    }
                    w.derive(lag)
                }),
            })
        }),
        AnyReport::Solve(r) => in_context(r, |r| solve_output(r.scene(), &r.result, fmt)),
        AnyReport::Forces(r) => in_context(r, |r| {
            let (names, q) = (&r.result.coordinates, &r.result.forces);
            let scene = r.scene();
            Ok(match fmt {
                Format::Csv => return Err(not_written(cmd, fmt)),
                Format::Text => forces_text(names, q),
                Format::Latex => latex::write(scene, |w| w.forces(names, q)),
                Format::Json => scene_json(scene, ForcesJson::new(scene, names, q))?,
            })
        }),
        AnyReport::Equilibrium(r) => in_context(r, |r| {
            let eq = &r.result;
            Ok(match fmt {
                Format::Csv => return Err(not_written(cmd, fmt)),
                Format::Text => equilibrium_text(eq),
                Format::Json => scene_json(r.scene(), EquilibriumJson::new(eq))?,
                Format::Latex => latex::write(r.scene(), |w| w.equilibrium(eq)),
            })
        }),
        AnyReport::Modes(r) => in_context(r, |r| {
            let o = &r.result;
            let (md, set) = (&o.modes, &o.set);
            Ok(match fmt {
                Format::Csv => return Err(not_written(cmd, fmt)),
                Format::Text => modes_text(md, set, o.free.as_deref(), o.numeric.as_ref()),
                Format::Json => scene_json(
                    r.scene(),
                    ModesJson::new(md, set, o.free.as_deref(), o.numeric.as_ref()),
                )?,
                Format::Latex => {
                    let body = latex::write(r.scene(), |w| w.modes(md));
                    match &o.standalone {
                        Some(title) => latex::standalone(title, &body),
                        None => body,
                    }
                }
            })
        }),
        AnyReport::Hamilton(r) => in_context(r, |r| {
            let h = &r.result;
            Ok(match fmt {
                Format::Csv => return Err(not_written(cmd, fmt)),
                Format::Text => text::hamilton_text(h),
                Format::Json => scene_json(r.scene(), HamiltonJson::new(h))?,
                Format::Latex => latex::write(r.scene(), |w| {
                    w.intermediates(h.intermediates.as_deref(), h.exprs());
                    w.hamilton(h)
                }),
            })
        }),
        AnyReport::Integrals(r) => in_context(r, |r| {
            let i = &r.result;
            Ok(match fmt {
                Format::Csv => return Err(not_written(cmd, fmt)),
                Format::Text => text::integrals_text(i),
                Format::Json => scene_json(r.scene(), IntegralsJson::new(i))?,
                Format::Latex => latex::write(r.scene(), |w| w.integrals(i)),
            })
        }),
        // `latex` writes LaTeX whatever the format
        AnyReport::Latex(r) => in_context(r, |r| {
            let q = &r.result;
            let opts = CommandOptions {
                set: q.set.clone(),
                steps: q.steps,
                standalone: q.standalone,
                title: q.title.clone(),
                ..CommandOptions::default()
            };
            latex::document(r.scene(), &opts)
        }),
        AnyReport::Check(r) => in_context(r, |r| {
            Ok(match fmt {
                Format::Json => json_string(&CheckJson::new(r.scene(), &r.result)),
                // `check` has no LaTeX: its text
                Format::Text | Format::Latex | Format::Csv => check_text(r.scene(), &r.result),
            })
        }),
        AnyReport::Cycle(r) => in_context(r, |r| {
            let run = &r.result;
            Ok(match fmt {
                Format::Csv => cycle::csv(run.shown()),
                Format::Json => cycle::json(run.shown()),
                Format::Text => cycle::reading(run),
                Format::Latex => return Err(not_written(cmd, fmt)),
            })
        }),
        AnyReport::Response(r) => in_context(r, |r| response::render(&r.result, fmt)),
        AnyReport::Floquet(r) => in_context(r, |r| {
            Ok(match fmt {
                Format::Text => floquet::text(&r.result),
                Format::Csv => floquet::csv(&r.result),
                Format::Json => floquet::json(&r.result),
                Format::Latex => return Err(not_written(cmd, fmt)),
            })
        }),
        // simulate and sweep: their table as CSV, or JSON
        AnyReport::Simulate(r) => match fmt {
            Format::Json => Ok(run::json(&r.result.run)),
            Format::Csv => Ok(run::csv(&r.result.run)),
            Format::Text | Format::Latex => Err(not_written(cmd, fmt)),
        },
        AnyReport::Sweep(r) => match fmt {
            Format::Json => Ok(sweep::json(&r.result.sweep)),
            Format::Csv => Ok(sweep::csv(&r.result.sweep)),
            Format::Text | Format::Latex => Err(not_written(cmd, fmt)),
        },
        // `codegen` writes its language whatever the format
        AnyReport::Codegen(r) => Ok(r.result.code.clone()),
    }
}

/// The error of a format `cmd` does not write.
fn not_written(cmd: Command, fmt: Format) -> Diagnostic {
    let names: Vec<&str> = cmd.formats().iter().map(|f| f.name()).collect();
    Diagnostic::global(format!(
        "`{}` writes {}, not {}",
        cmd.name(),
        names.join(", "),
        fmt.name()
    ))
    .with_kind(crate::diag::ErrorKind::bad_option("--format"))
}

/// `f` on `report` within the report's context.
fn in_context<T>(
    report: &Report<T>,
    f: impl FnOnce(&Report<T>) -> Result<String, Diagnostic>,
) -> Result<String, Diagnostic> {
    report.context().run(|| f(report))
}

/// A command's JSON object as text, followed by the keys every command
/// of this scene carries ([`SceneJson`]).
fn scene_json(scene: &Scene, command: impl serde::Serialize) -> Result<String, Diagnostic> {
    let scene = SceneJson::new(scene)?;
    Ok(json_string(&WithScene { command, scene }))
}

/// `qdot solve`: the accelerations (and multipliers, and the constraints'
/// reactions) and the `solve` blocks' solutions.
fn solve_output(
    scene: &Scene,
    solved: &crate::app::Solved,
    fmt: Format,
) -> Result<String, Diagnostic> {
    let (lag, reactions, blocks) = (&solved.dynamics, &solved.reactions, &solved.blocks);
    Ok(match fmt {
        Format::Csv => return Err(not_written(Command::Solve, fmt)),
        Format::Text => {
            let mut out = match (lag, &solved.mechanism) {
                (None, Some(m)) => {
                    let (l, r) = &**m;
                    let mut out = text::dynamics_text(scene, l, None, blocks);
                    out.push_str(&text::mechanism_text(r));
                    if !blocks.is_empty() {
                        out.push('\n');
                    }
                    out
                }
                (Some((l, acc)), _) => {
                    let mut out = text::dynamics_text(scene, l, Some(acc), blocks)
                        + &text::reactions_text(scene, reactions);
                    if !blocks.is_empty() {
                        out.push('\n');
                    }
                    out
                }
                // a block's own intermediates (`--keep`)
                (None, None) => match wire::structured_roots(scene, None, None, blocks) {
                    Some((tape, roots)) => text::intermediates_text(Some(tape), roots),
                    None => String::new(),
                },
            };
            if !blocks.is_empty() {
                out.push_str(&solutions_text(scene, blocks));
            }
            out
        }
        Format::Latex => latex::write(scene, |w| {
            if let Some(m) = &solved.mechanism {
                w.mechanism(scene, &m.0, &m.1, false);
            }
            let (l, acc) = (lag.as_ref().map(|d| &d.0), lag.as_ref().map(|d| &d.1));
            if let Some((tape, roots)) = wire::structured_roots(scene, l, acc, blocks) {
                w.intermediates(Some(tape), roots);
            }
            if let Some((l, acc)) = lag {
                w.equations(l);
                w.accelerations(acc);
            }
            w.blocks(scene, blocks);
        }),
        Format::Json => scene_json(
            scene,
            SolveJson {
                mechanism: solved
                    .mechanism
                    .as_ref()
                    .map(|m| wire::MechanismJson::new(&m.0, &m.1)),
                ..SolveJson::new(scene, lag.as_ref(), reactions, blocks)
            },
        )?,
    })
}

pub use crate::scene::given::parameter_values as parse_set;
pub use crate::scene::given::parameter_values_any_sign as parse_set_any_sign;

/// An expression in qdot's input syntax (JSON strings re-parse to it).
fn as_input(e: &Expr) -> String {
    print::input(e)
}

/// An expression as the text output writes it (Unicode names, `·`, `−`).
fn as_unicode(e: &Expr) -> String {
    print::unicode(e)
}

fn position_strings(
    eq: &Equilibria,
    e: &equilibrium::Equilibrium,
    st: &dyn Fn(&Expr) -> String,
) -> Vec<String> {
    match &e.position {
        Position::Exact(vals) => vals
            .iter()
            .enumerate()
            .map(|(k, v)| {
                if e.free.contains(&k) {
                    "any".to_string()
                } else {
                    st(v)
                }
            })
            .collect::<Vec<String>>(),
        Position::Numeric(xs) => match &e.certified {
            Some(digits) => digits.iter().map(|d| minus(d.clone())).collect(),
            None => xs
                .iter()
                .map(|x| minus(crate::solve::certify::significant(*x, 6)))
                .collect(),
        },
    }
    .into_iter()
    .take(eq.coordinates.len())
    .collect()
}

/// What a numeric search of equilibria cannot promise, said by every
/// format: `None` for positions in closed form (or none found).
pub(super) fn search_caveat(eq: &equilibrium::Equilibria) -> Option<&'static str> {
    if eq.exact || eq.equilibria.is_empty() {
        None
    } else if eq.coordinates.len() == 1 {
        Some("found by Newton's method from many starting points: roots far from them may be missed; digits shown are certified by a sign change")
    } else {
        Some(
            "found by Newton's method from many starting points: roots far from them may be missed",
        )
    }
}

/// Why a numeric position's digits are not certified, when they are not.
pub(super) fn uncertified_note(e: &equilibrium::Equilibrium) -> Option<&'static str> {
    match (&e.position, &e.certified) {
        (Position::Numeric(xs), None) => Some(if xs.len() == 1 {
            "not certified: no sign change of the condition found around it (a multiple root, or one lost in rounding); 6 digits shown"
        } else {
            "not certified (several coordinates: qdot encloses roots of one equation only); 6 digits shown"
        }),
        _ => None,
    }
}

/// A number with the typographic minus of the text output.
pub(super) fn minus(s: String) -> String {
    match s.strip_prefix('-') {
        Some(r) => format!("−{r}"),
        None => s,
    }
}
