//! The application layer: qdot's commands run on a scene, each giving a
//! typed report ([`report`]) that [`crate::output`] renders as text, JSON
//! or LaTeX. The CLI, the REPL, Python and the fuzz targets all come
//! through here: one table of commands and formats ([`Command`],
//! [`Format`]), one [`Context`] passed explicitly.
//!
//! ```
//! use qdot::app::{self, Context};
//! let src = "coordinates x\nparameters m, k\n\
//!            kinetic E = 1/2*m*x'^2\npotential V = 1/2*k*x^2";
//! let r = app::solve(&Context::new(), src).unwrap();
//! let a = r.result.acceleration("x").unwrap();
//! assert_eq!(r.print(a).unwrap(), "-k*x/m");
//! ```

mod context;
pub mod report;
mod simulation;

pub use context::Context;
pub use report::{
    AnyReport, CheckReport, DeriveReport, Derived, EquilibriaReport, Forces, ForcesReport,
    HamiltonReport, IntegralsReport, LatexReport, LatexRequest, ModesReport, Oscillations, Report,
    SolveReport, Solved,
};
pub use report::{
    CodegenReport, GeneratedCode, SimulateReport, Simulation, SweepReport, SweepStudy,
};
pub use report::{
    CycleReport, CycleRun, FloquetPoint, FloquetReport, FloquetRun, FrequencyResponse,
    ResponseReport,
};
pub use simulation::{thread_count, thread_pool, ProgressHook, SweepOptions};
pub use studies::parse_over;

use crate::diag::Diagnostic;
use crate::scene::Scene;
use crate::solve::equilibrium::Values;
use std::sync::Arc;

/// qdot's commands on a scene.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Command {
    /// `qdot derive`: Lagrange's equations, the mass matrix M and the forcing f.
    Derive,
    /// `qdot solve`: the accelerations q̈ = M⁻¹f and the scene's `solve` blocks.
    Solve,
    /// `qdot forces`: the generalized forces Q_k.
    Forces,
    /// `qdot equilibrium`: the positions of equilibrium at rest and their stability.
    Equilibrium,
    /// `qdot modes`: small oscillations about an equilibrium (M, C, K, the
    /// frequencies, the modes, the responses).
    Modes,
    /// LaTeX of the scene's main result (see [`crate::output::latex::document`]).
    Latex,
    /// `qdot check`: the dimension of every name and result (text or JSON).
    Check,
    /// `qdot hamilton`: the momenta, H(q, p, t) and Hamilton's equations.
    Hamilton,
    /// `qdot integrals`: cyclic coordinates, the energy integral, Routh.
    Integrals,
    // the numeric studies (options: `over`, `guess`, `columns`,
    // `functions`, `period`, `max_steps` of [`CommandOptions`])
    /// `qdot cycle`: a planar mechanism over its cycle (`over`: `t` or a
    /// driven coordinate): positions, velocities, accelerations, reactions.
    Cycle,
    /// `qdot response`: the frequency response to the harmonic load,
    /// exact, or swept over `Omega` numerically (`over`).
    Response,
    /// `qdot floquet`: the Floquet stability about a motion, at one point
    /// or over one or two parameters (`over`).
    Floquet,
    // the numeric commands
    /// `qdot simulate`: the exact equations compiled and integrated.
    Simulate,
    /// `qdot sweep`: many runs of one scene over a grid or random points.
    Sweep,
    /// `qdot codegen`: the equations of motion as source code.
    Codegen,
}

impl Command {
    /// Every command, in the order the CLI's help lists them.
    pub const ALL: [Command; 15] = [
        Command::Derive,
        Command::Solve,
        Command::Forces,
        Command::Equilibrium,
        Command::Modes,
        Command::Hamilton,
        Command::Integrals,
        Command::Latex,
        Command::Check,
        Command::Cycle,
        Command::Response,
        Command::Floquet,
        Command::Simulate,
        Command::Sweep,
        Command::Codegen,
    ];

    /// The command's name on the command line, in the REPL and in Python.
    pub fn name(self) -> &'static str {
        match self {
            Command::Derive => "derive",
            Command::Solve => "solve",
            Command::Forces => "forces",
            Command::Equilibrium => "equilibrium",
            Command::Modes => "modes",
            Command::Latex => "latex",
            Command::Check => "check",
            Command::Hamilton => "hamilton",
            Command::Integrals => "integrals",
            Command::Cycle => "cycle",
            Command::Response => "response",
            Command::Floquet => "floquet",
            Command::Simulate => "simulate",
            Command::Sweep => "sweep",
            Command::Codegen => "codegen",
        }
    }

    /// The command called `name`.
    pub fn from_name(name: &str) -> Option<Command> {
        Command::ALL.into_iter().find(|c| c.name() == name)
    }

    /// The formats the command writes (`latex` writes LaTeX whatever the
    /// format; `check` writes text or JSON; the numeric studies write
    /// tables: CSV, JSON or text, `response` without `over` text or JSON;
    /// `simulate` and `sweep` CSV or JSON; `codegen` its language as text).
    pub fn formats(self) -> &'static [Format] {
        match self {
            Command::Latex => &[Format::Latex],
            Command::Check => &[Format::Text, Format::Json],
            Command::Cycle => &[Format::Csv, Format::Json, Format::Text],
            Command::Response => &[Format::Text, Format::Json, Format::Csv],
            Command::Floquet => &[Format::Text, Format::Csv, Format::Json],
            Command::Simulate | Command::Sweep => &[Format::Csv, Format::Json],
            Command::Codegen => &[Format::Text],
            _ => &[Format::Text, Format::Json, Format::Latex],
        }
    }
}

/// Output format.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Format {
    /// Plain text with Unicode notation (θ̈₃, ·, −).
    Text,
    /// JSON, expressions as strings in qdot's input syntax.
    Json,
    /// amsmath LaTeX (see [`crate::output::latex`]).
    Latex,
    /// Comma-separated values, every digit of each double (the numeric
    /// studies' tables).
    Csv,
}

impl Format {
    /// Every format.
    pub const ALL: [Format; 4] = [Format::Text, Format::Json, Format::Latex, Format::Csv];

    /// The format's name (`--format NAME`).
    pub fn name(self) -> &'static str {
        match self {
            Format::Text => "text",
            Format::Json => "json",
            Format::Latex => "latex",
            Format::Csv => "csv",
        }
    }

    /// The format called `name`.
    pub fn from_name(name: &str) -> Option<Format> {
        Format::ALL.into_iter().find(|f| f.name() == name)
    }

    /// What the command line's help says of the format, if anything.
    pub fn about(self) -> Option<&'static str> {
        match self {
            Format::Text | Format::Json | Format::Csv => None,
            Format::Latex => Some("amsmath LaTeX, a fragment to \\input"),
        }
    }
}

/// The options of the commands beyond the scene and the format.
#[derive(Clone, Debug, Default)]
pub struct CommandOptions {
    /// `--set`: parameter values.
    pub set: Values,
    /// `modes --at q=value,…`: the equilibrium (expressions in the scene);
    /// `response --at`, `floquet --at`: the position linearized about.
    pub at: Option<String>,
    /// `modes --steady q,…` / `equilibrium --steady q,…`: the coordinates
    /// turning at constant rates (a steady motion).
    pub steady: Option<String>,
    /// `modes --init q=…,q'=…`: initial conditions.
    pub init: Option<String>,
    /// `latex --steps`: the derivation line by line.
    pub steps: bool,
    /// `latex --standalone`: a whole document, not a fragment.
    pub standalone: bool,
    /// The title of a standalone document (the file name).
    pub title: String,
    /// `--max-terms`: the work budget ([`crate::budget`]); 0 means the
    /// default, [`crate::limits::DEFAULT_MAX_TERMS`].
    pub max_terms: usize,
    /// `--expand` / `--structured`: whether `derive` and `solve` write their
    /// results through named intermediates.
    pub structure: Structure,
    /// `--keep NAME,…`: definitions `derive` and `solve` keep as
    /// intermediates (the scene is then read structured).
    pub keep: Vec<String>,
    // the numeric studies: cycle, response, floquet
    /// `--over NAME=FROM:TO:COUNT` ([`parse_over`]): `cycle`'s varied
    /// quantity (one axis, required), `response`'s `Omega` (none: the
    /// exact response), `floquet`'s parameters (none: one point; one or
    /// two axes: a table or a chart).
    pub over: Vec<crate::scene::given::GridAxis>,
    /// `cycle --guess th=-0.3,…` ([`crate::cycle::parse_guess`]):
    /// coordinates of an assembly near the first position.
    pub guess: Vec<(String, f64)>,
    /// `cycle --columns O_x,M`: only these columns after the varied one
    /// (`None`: every column).
    pub columns: Option<Vec<String>>,
    /// `floquet --function s=EXPR`: each given function of time.
    pub functions: Vec<String>,
    /// `floquet --period T`: the period, when it is not found.
    pub period: Option<f64>,
    /// `floquet --max-steps N`: the steps one integration over the period
    /// may take (`None`: [`crate::limits::DEFAULT_MAX_STEPS`]).
    pub max_steps: Option<usize>,
    /// `floquet --threads N`: the grid's points on N threads (0: one per
    /// core; [`thread_count`], the policy `sweep --threads` follows too).
    pub threads: usize,
    // the numeric commands
    /// `simulate` and `sweep`: the run (`--t-end`, `--method`, `--init`,
    /// …); its `set` is not read: the parameter values are
    /// [`CommandOptions::set`].
    pub simulate: crate::simulate::run::Request,
    /// `sweep`: what varies, how, on how many threads.
    pub sweep: SweepOptions,
    /// `codegen`: the language, the form, the file named in the code; its
    /// `set` is not read: the parameters made constants are
    /// [`CommandOptions::set`].
    pub codegen: crate::simulate::codegen::CodegenRequest,
}

pub use crate::scene::Structure;

/// Run `cmd` on the scene source `src` in `ctx`: parse, resolve, compute,
/// all within the context's budget.
pub fn run(
    ctx: &Context,
    cmd: Command,
    src: &str,
    opts: &CommandOptions,
) -> Result<AnyReport, Diagnostic> {
    let (structure, keep) = match cmd {
        Command::Derive | Command::Solve => (opts.structure, opts.keep.as_slice()),
        // a large body scene is simulated (and generated) from its intermediates
        Command::Simulate | Command::Sweep | Command::Codegen => (Structure::Auto, &[][..]),
        // the generalized forces are expanded, the kinetic energy need not be
        Command::Forces => (Structure::Auto, &[][..]),
        _ => (Structure::Expanded, &[][..]),
    };
    ctx.run(|| {
        let scene = Arc::new(Scene::read_keeping(src, structure, keep)?);
        let ctx = ctx.for_scene(&scene);
        ctx.run(|| commands::run_scene(&ctx, cmd, &scene, opts))
    })
}

/// Parse and resolve `src` within `ctx`'s budget, then run `f` on the
/// scene in the scene's context.
fn on_scene<T>(
    ctx: &Context,
    src: &str,
    f: impl FnOnce(&Context, &Arc<Scene>) -> Result<T, Diagnostic>,
) -> Result<T, Diagnostic> {
    on_scene_as(ctx, src, Structure::Expanded, f)
}

/// [`on_scene`] with the scene read as `structure` asks.
fn on_scene_as<T>(
    ctx: &Context,
    src: &str,
    structure: Structure,
    f: impl FnOnce(&Context, &Arc<Scene>) -> Result<T, Diagnostic>,
) -> Result<T, Diagnostic> {
    ctx.run(|| {
        let scene = Arc::new(Scene::read(src, structure)?);
        let ctx = ctx.for_scene(&scene);
        ctx.run(|| f(&ctx, &scene))
    })
}

/// `derive` on the scene source `src`.
pub fn derive(ctx: &Context, src: &str) -> Result<DeriveReport, Diagnostic> {
    on_scene_as(ctx, src, Structure::Auto, commands::derive)
}

/// `solve` on the scene source `src`.
pub fn solve(ctx: &Context, src: &str) -> Result<SolveReport, Diagnostic> {
    on_scene_as(ctx, src, Structure::Auto, commands::solve)
}

/// `equilibrium` on the scene source `src`, parameters at `set`.
pub fn equilibria(ctx: &Context, src: &str, set: &Values) -> Result<EquilibriaReport, Diagnostic> {
    on_scene(ctx, src, |ctx, scene| commands::equilibria(ctx, scene, set))
}

/// `modes` on the scene source `src` (`--set`, `--at`, `--init` in `opts`).
pub fn modes(ctx: &Context, src: &str, opts: &CommandOptions) -> Result<ModesReport, Diagnostic> {
    on_scene(ctx, src, |ctx, scene| commands::modes(ctx, scene, opts))
}

/// `hamilton` on the scene source `src`.
pub fn hamilton(ctx: &Context, src: &str) -> Result<HamiltonReport, Diagnostic> {
    on_scene(ctx, src, commands::hamilton)
}

/// `integrals` on the scene source `src`.
pub fn integrals(ctx: &Context, src: &str) -> Result<IntegralsReport, Diagnostic> {
    on_scene(ctx, src, commands::integrals)
}

/// `simulate` on the scene source `src` (`qdot simulate`; `req.set` the
/// parameter values), within `ctx`: the run of [`Command::Simulate`]'s
/// report.
pub fn simulate(
    ctx: &Context,
    src: &str,
    req: &crate::simulate::run::Request,
) -> Result<crate::simulate::run::Run, Diagnostic> {
    let opts = CommandOptions {
        set: req.set.clone(),
        simulate: req.clone(),
        ..CommandOptions::default()
    };
    let r = on_scene_as(ctx, src, Structure::Auto, |ctx, scene| {
        simulation::simulate(ctx, scene, &opts)
    })?;
    Ok(r.result.run)
}

/// `sweep` on the scene source `src` (`qdot sweep`): `base` once per point
/// of the design, within `ctx` (see [`crate::simulate::sweep::sweep`]);
/// `progress` is told the number of finished runs after each run.
pub fn sweep(
    ctx: &Context,
    src: &str,
    base: &crate::simulate::run::Request,
    axes: &[crate::simulate::sweep::Axis],
    design: crate::simulate::sweep::Design,
    threads: usize,
    progress: &(dyn Fn(usize) + Sync),
) -> Result<crate::simulate::sweep::Sweep, Diagnostic> {
    let o = SweepOptions {
        axes: axes.to_vec(),
        design,
        threads,
        progress: None,
    };
    let told = |done: usize, _: usize| {
        if done > 0 {
            progress(done);
        }
    };
    let r = on_scene_as(ctx, src, Structure::Auto, |ctx, scene| {
        simulation::sweep_study(ctx, scene, base.clone(), &o, &told)
    })?;
    Ok(r.result.sweep)
}

/// `codegen` on the scene source `src` (`qdot codegen`; `req.set` the
/// constants): the source code, within `ctx`.
pub fn codegen(
    ctx: &Context,
    src: &str,
    req: &crate::simulate::codegen::CodegenRequest,
) -> Result<String, Diagnostic> {
    let opts = CommandOptions {
        set: req.set.clone(),
        codegen: req.clone(),
        ..CommandOptions::default()
    };
    let r = on_scene_as(ctx, src, Structure::Auto, |ctx, scene| {
        simulation::codegen(ctx, scene, &opts)
    })?;
    Ok(r.result.code)
}

mod commands;
mod studies;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_command_and_format_is_found_by_its_name() {
        for c in Command::ALL {
            assert_eq!(Command::from_name(c.name()), Some(c));
        }
        for f in Format::ALL {
            assert_eq!(Format::from_name(f.name()), Some(f));
        }
        assert_eq!(Command::from_name("Solve"), None);
        assert_eq!(Format::from_name(""), None);
    }

    /// A report prints in its scene's coordinate order with nothing set up
    /// around it; the bare printer, outside any context, orders by name.
    #[test]
    fn a_report_prints_in_its_scenes_order() {
        let src = "coordinates y, a\nparameters m\nkinetic E = 1/2*m*(y'^2 + y'*a' + a'^2)";
        let r = hamilton(&Context::new(), src).expect("hamilton");
        let p = &r.result.momenta[0];
        assert_eq!(r.print(p).expect("printed"), "m*y' + m*a'/2");
        assert_eq!(crate::expr::print::input(p), "m*a'/2 + m*y'");
    }
}
