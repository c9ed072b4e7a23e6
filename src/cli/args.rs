//! The command line's arguments (clap) and their reading into the
//! application layer's [`CommandOptions`]: every check of an option that
//! needs no scene is made here, before the scene is read.

use super::study::{CycleArgs, FloquetArgs, ResponseArgs};
use clap::{Parser, Subcommand, ValueEnum};
use qdot::app::{self, CommandOptions, SweepOptions};
use qdot::diag::ErrorKind;
use qdot::output::{self, Format};
use qdot::simulate::run::{self, Request};
use qdot::Diagnostic;

#[derive(Parser)]
#[command(
    name = "qdot",
    version,
    // help lines wrap at the terminal's width, and never past 100 columns
    max_term_width = 100,
    about = "Exact analytical mechanics: Lagrange's equations, derived and solved exactly"
)]
pub struct Cli {
    /// Without a command, qdot starts the REPL.
    #[command(subcommand)]
    pub command: Option<Command>,
    /// The work budget of exact computation: the most terms one expression
    /// may reach before qdot stops with an error (every command; the REPL
    /// has :max-terms).
    #[arg(long = "max-terms", global = true, default_value_t = qdot::limits::DEFAULT_MAX_TERMS)]
    pub max_terms: usize,
}

/// `--format` of `cmd`: the formats it writes, by their names in the one
/// table of formats (`qdot::app::Format`).
pub fn format_arg(cmd: output::Command) -> impl clap::builder::TypedValueParser<Value = Format> {
    let names = cmd.formats().iter().map(|f| {
        let value = clap::builder::PossibleValue::new(f.name());
        match f.about() {
            Some(about) => value.help(about),
            None => value,
        }
    });
    // only the listed names get through, and each is a format
    clap::builder::TypedValueParser::map(
        clap::builder::PossibleValuesParser::new(names),
        |name: String| Format::from_name(&name).unwrap_or(Format::Text),
    )
}

#[derive(Clone, Copy, ValueEnum)]
pub enum CodegenLang {
    C,
    Rust,
    Python,
    Julia,
}

#[derive(Clone, Copy, ValueEnum)]
pub enum CodegenForm {
    /// y' = F(t, y) for y = (q, q̇), M·q̈ = f solved inside
    Accelerations,
    /// M(q, t) and f(q, q̇, t) as two functions
    MassMatrix,
}

#[derive(Subcommand)]
pub enum Command {
    /// The interactive session: build a scene line by line, ask for
    /// results (:help lists the commands). Reads entries from stdin
    /// without prompts when stdin is not a terminal.
    Repl {
        /// A scene file (.qd) to start from.
        file: Option<String>,
        /// With stdin not a terminal: print each entry after its prompt
        /// and everything on stdout, as a transcript of the session.
        #[arg(long)]
        echo: bool,
    },
    /// Derive Lagrange's equations, the mass matrix and the forcing.
    Derive {
        /// The scene file (.qd).
        file: String,
        #[arg(long, value_parser = format_arg(output::Command::Derive), default_value = "text")]
        format: Format,
        #[command(flatten)]
        structure: StructureArgs,
    },
    /// Solve exactly: the accelerations of Lagrange's equations, and the
    /// scene's `solve` blocks (reactions, kinetostatic systems).
    Solve {
        /// The scene file (.qd).
        file: String,
        #[arg(long, value_parser = format_arg(output::Command::Solve), default_value = "text")]
        format: Format,
        #[command(flatten)]
        structure: StructureArgs,
    },
    /// The generalized forces Q_k (virtual work δL = Σ Q_k·δq_k).
    Forces {
        /// The scene file (.qd).
        file: String,
        #[arg(long, value_parser = format_arg(output::Command::Forces), default_value = "text")]
        format: Format,
    },
    /// Hamilton's equations: the momenta p = ∂L/∂q̇, the velocities in
    /// terms of them, H(q, p, t) and q̇ = ∂H/∂p, ṗ = −∂H/∂q + Q̃.
    Hamilton {
        /// The scene file (.qd).
        file: String,
        #[arg(long, value_parser = format_arg(output::Command::Hamilton), default_value = "text")]
        format: Format,
    },
    /// Integrals of motion: cyclic coordinates and their momenta, the
    /// energy integral, Routh's reduction.
    Integrals {
        /// The scene file (.qd).
        file: String,
        #[arg(long, value_parser = format_arg(output::Command::Integrals), default_value = "text")]
        format: Format,
    },
    /// Small oscillations about an equilibrium (or a steady motion): M, C,
    /// K, det(K − ω²M), the natural frequencies, the modes, and the
    /// responses.
    Modes(ModesArgs),
    /// LaTeX for lecture notes: the equations and the solution (amsmath).
    Latex {
        /// The scene file (.qd).
        file: String,
        /// Write the derivation line by line: the kinetic energy per body,
        /// ∂E/∂q̇, d/dt(∂E/∂q̇), ∂E/∂q, each Q_k, the equations, the solution
        #[arg(long)]
        steps: bool,
        /// A whole `article` document that compiles with pdflatex (without
        /// it, a fragment to \input)
        #[arg(long)]
        standalone: bool,
        /// The title of the --standalone document (default: the scene's
        /// first comment, else the file's base name)
        #[arg(long)]
        title: Option<String>,
        /// Parameter values, for scenes whose equilibria need them: m=1,g=9.81
        #[arg(long)]
        set: Option<String>,
    },
    /// Integrate the equations numerically: the exact M and f compiled to
    /// f64, then RK4, DOPRI5, DOP853, Vern7, Gauss6 or Radau5.
    Simulate(SimulateArgs),
    /// Many simulations of one scene on every core: a grid over parameters
    /// and initial values (--vary NAME=FROM:TO:COUNT, repeated), or random
    /// points in that box (--samples N). One summary row per run.
    Sweep(SweepArgs),
    /// A planar mechanism over its cycle: positions (Newton's method,
    /// continued on one assembly branch), velocities, accelerations, then
    /// every joint's reaction and every drive's force, with Coulomb
    /// friction by iteration. One row per position.
    Cycle(CycleArgs),
    /// The frequency response to the scene's harmonic load at a free
    /// frequency Omega: the exact receptance (K − Ω²M + iΩC)⁻¹·F, amplitude
    /// and phase, antiresonances, and for one degree of freedom the
    /// resonance peak, half-power bandwidth and transmissibility; with
    /// --over, amplitude and phase swept numerically.
    Response(ResponseArgs),
    /// Parametric excitation: the scene linearized about a motion
    /// (--at), its periodic coefficients' monodromy matrix over one
    /// period, the Floquet multipliers and the stability verdict; over one
    /// or two parameters (--over), a table or the stability chart.
    Floquet(FloquetArgs),
    /// Source code for the equations of motion (C, Rust, Python or Julia):
    /// the right-hand side of y' = F(t, y), or M and f, and the energy when
    /// conserved; shared subexpressions computed once, the parameters as
    /// arguments.
    Codegen(CodegenArgs),
    /// The dimension of every name, declared or found, and of the results;
    /// an error at the first term of the wrong dimension.
    Check {
        /// The scene file (.qd).
        file: String,
        #[arg(long, value_parser = format_arg(output::Command::Check), default_value = "text")]
        format: Format,
    },
    /// Equilibrium positions (Q_k = 0) and their stability; with
    /// --steady, the steady motions.
    Equilibrium {
        /// The scene file (.qd).
        file: String,
        #[arg(long, value_parser = format_arg(output::Command::Equilibrium), default_value = "text")]
        format: Format,
        /// Parameter values for numeric roots and sign decisions: m=1,g=9.81
        #[arg(long)]
        set: Option<String>,
        /// Find steady motions instead: these cyclic coordinates turn at
        /// constant rates (their symbols q̇), the others rest where their
        /// equations hold
        #[arg(long, value_name = "Q,…")]
        steady: Option<String>,
    },
}

/// `qdot simulate`'s arguments.
#[derive(clap::Args)]
pub struct SimulateArgs {
    /// The scene file (.qd).
    pub file: String,
    /// Every parameter's value: m=1,g=9.81
    #[arg(long)]
    pub set: Option<String>,
    /// Every coordinate's initial value, and the velocities' (0 where not given): theta=0.5,theta'=0
    #[arg(long)]
    pub init: Option<String>,
    #[command(flatten)]
    pub integration: Integration,
    /// csv or json
    #[arg(long, default_value = "csv")]
    pub output: String,
    /// Steps, rejections, RHS evaluations, factorizations, wall time (on stderr).
    #[arg(long)]
    pub stats: bool,
    /// Also draw the motion to this SVG file: q(t), the phase portrait,
    /// and the energy error when the scene conserves energy.
    #[arg(long)]
    pub plot: Option<String>,
    /// Also write the motion to this self-contained HTML page: the
    /// scene's bodies, particles and points moving in 3D (play, pause,
    /// scrub, orbit the camera).
    #[arg(long)]
    pub animate: Option<String>,
    /// End the run where this changes sign: "theta = 0", "x' = 0"
    /// (located on the dense output of dopri5, dop853, vern7 or rk4).
    #[arg(long = "stop-when")]
    pub stop_when: Option<String>,
    /// The definition of a given function of time (`functions s` in the
    /// scene), once per function: --function "s=1/10*sin(2*t)"
    #[arg(long = "function")]
    pub function: Vec<String>,
    /// Baumgarte's rate for a scene with constraints, in 1/time of the
    /// scene: drift from the constraints decays like exp(-rate*t); 0 turns it off.
    #[arg(long, default_value_t = 1.0)]
    pub baumgarte: f64,
}

/// `qdot codegen`'s arguments.
#[derive(clap::Args)]
pub struct CodegenArgs {
    /// The scene file (.qd).
    pub file: String,
    /// The language of the code.
    #[arg(long, value_enum)]
    pub lang: CodegenLang,
    /// The functions: the right-hand side, or M and f apart.
    #[arg(long, value_enum, default_value = "accelerations")]
    pub form: CodegenForm,
    /// Parameters made constants of the code (the others stay
    /// arguments): m=1,g=9.81
    #[arg(long)]
    pub set: Option<String>,
    /// The definition of a given function of time, once per function:
    /// --function "s=1/10*sin(2*t)"
    #[arg(long = "function")]
    pub function: Vec<String>,
    /// Baumgarte's rate for a scene with constraints (a constant of
    /// the code).
    #[arg(long, default_value_t = 1.0)]
    pub baumgarte: f64,
}

/// `qdot modes`' arguments.
#[derive(clap::Args)]
pub struct ModesArgs {
    /// The scene file (.qd).
    pub file: String,
    #[arg(long, value_parser = format_arg(output::Command::Modes), default_value = "text")]
    pub format: Format,
    /// The equilibrium to linearize about (default: every q = 0), e.g.
    /// th=pi; about a steady motion, also the steady rates: th=pi/3,phi'=w
    #[arg(long)]
    pub at: Option<String>,
    /// Linearize about a steady motion: these cyclic coordinates turn
    /// at constant rates (their symbols q̇, or the rates --at gives),
    /// the others rest at --at; the rates are reduced away Routh's way
    #[arg(long, value_name = "Q,…")]
    pub steady: Option<String>,
    /// Initial conditions for the free response: y1=1/10,y1'=0
    #[arg(long)]
    pub init: Option<String>,
    /// Parameter values for numeric frequencies and sign decisions
    #[arg(long)]
    pub set: Option<String>,
    /// With --format latex: a whole `article` document that compiles
    /// with pdflatex (without it, a fragment to \input)
    #[arg(long)]
    pub standalone: bool,
    /// The title of the --standalone document (default: the scene's
    /// first comment, else the file's base name)
    #[arg(long, requires = "standalone")]
    pub title: Option<String>,
    /// Also write each mode shape oscillating about the equilibrium to
    /// this self-contained HTML page (needs every parameter's --set value).
    #[arg(long)]
    pub animate: Option<String>,
}

impl ModesArgs {
    /// Put these options into `opts`; an error when `--standalone` is
    /// asked for without LaTeX.
    fn apply(&self, opts: &mut CommandOptions) -> Result<(), Diagnostic> {
        opts.at = self.at.clone();
        opts.steady = self.steady.clone();
        opts.init = self.init.clone();
        if self.standalone && self.format != Format::Latex {
            return Err(Diagnostic::global("--standalone makes a LaTeX document")
                .with_hint("add --format latex")
                .with_kind(ErrorKind::bad_option("--standalone")));
        }
        opts.standalone = self.standalone;
        opts.title = self
            .title
            .clone()
            .unwrap_or_else(|| document_title(&self.file));
        Ok(())
    }
}

/// `--expand` / `--structured`: how results are written.
#[derive(clap::Args, Debug, Clone)]
pub struct StructureArgs {
    /// Write the results fully expanded, however large.
    #[arg(long, conflicts_with = "structured")]
    pub expand: bool,
    /// Write the results through named intermediates (a scene's moving
    /// vectors and frames kept, M = L·D·Lᵀ for the accelerations), however
    /// small. Without either flag, qdot expands unless the expanded M and
    /// f would pass 256 terms.
    #[arg(long)]
    pub structured: bool,
    /// Keep these definitions as intermediates (`--keep alpha,beta`): the
    /// results are written in them and their rates (alpha_dot,
    /// alpha_ddot).
    #[arg(long, value_delimiter = ',', value_name = "NAME,…")]
    pub keep: Vec<String>,
}

impl StructureArgs {
    fn choice(&self) -> qdot::app::Structure {
        match (self.expand, self.structured) {
            (true, _) => qdot::app::Structure::Expanded,
            (_, true) => qdot::app::Structure::Kept,
            _ => qdot::app::Structure::Auto,
        }
    }
}

/// The integration options `simulate` and `sweep` share.
#[derive(clap::Args)]
pub struct Integration {
    /// The final time (from t = 0): a number or a constant expression
    /// (2*pi).
    #[arg(long = "t-end", value_parser = number)]
    pub t_end: f64,
    /// rk4, dopri5, dop853, vern7, gauss6 (symplectic) or radau5 (stiff)
    #[arg(long, default_value = "dop853")]
    pub method: String,
    /// Relative tolerance of the adaptive methods.
    #[arg(long, default_value_t = 1e-8)]
    pub rtol: f64,
    /// Absolute tolerance of the adaptive methods.
    #[arg(long, default_value_t = 1e-10)]
    pub atol: f64,
    /// The step of rk4 and gauss6 (the first step of the others).
    #[arg(long, value_parser = number)]
    pub dt: Option<f64>,
    /// Evenly spaced output times from 0 to --t-end (2 to 1,000,000); a
    /// sweep reads max|q| and the energy drift at them.
    #[arg(long, default_value_t = 101)]
    pub points: usize,
    /// Give up (a run) after this many steps, accepted and rejected.
    #[arg(long = "max-steps", default_value_t = qdot::limits::DEFAULT_MAX_STEPS)]
    pub max_steps: usize,
    /// What runs the compiled equations: auto (machine code where it
    /// compiles), jit or interpreter.
    #[arg(long, default_value = "auto")]
    pub evaluator: String,
}

/// `--evaluator NAME`.
fn engine_by_name(name: &str) -> Result<qdot::simulate::compile::Engine, Diagnostic> {
    qdot::simulate::compile::Engine::by_name(name).ok_or_else(|| {
        Diagnostic::global(format!("unknown evaluator `{name}`"))
            .with_hint("--evaluator auto, jit (machine code) or interpreter")
            .with_kind(ErrorKind::bad_option("--evaluator"))
    })
}

/// `--output csv|json` of `simulate` and `sweep`.
fn output_by_name(name: &str) -> Result<(), Diagnostic> {
    if name == "csv" || name == "json" {
        return Ok(());
    }
    Err(Diagnostic::global(format!("unknown output `{name}`"))
        .with_hint("--output csv or --output json")
        .with_kind(ErrorKind::bad_option("--output")))
}

impl Integration {
    /// The request with these options (the method is read apart: its
    /// name may be wrong).
    fn request(&self) -> qdot::simulate::run::Request {
        qdot::simulate::run::Request {
            t_end: self.t_end,
            rtol: self.rtol,
            atol: self.atol,
            dt: self.dt,
            points: self.points,
            max_steps: self.max_steps,
            ..Default::default()
        }
    }
}

/// `qdot sweep`'s arguments.
#[derive(clap::Args)]
pub struct SweepArgs {
    /// The scene file (.qd).
    pub file: String,
    /// The values of the parameters that do not vary: m=1,g=9.81
    #[arg(long)]
    pub set: Option<String>,
    /// The initial values that do not vary (a velocity not given is 0): theta=0.5
    #[arg(long)]
    pub init: Option<String>,
    /// A varied parameter, coordinate or velocity: "l=0.5:2:16"
    /// (16 values from 0.5 to 2); repeat for a grid over several.
    #[arg(long = "vary", required = true)]
    pub vary: Vec<String>,
    /// Draw this many random points in the box of the --vary ranges
    /// instead of a grid (COUNT may then be left out).
    #[arg(long)]
    pub samples: Option<usize>,
    /// The seed of --samples (the same seed, the same points).
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Threads (0: one per core); never more than the cores or the runs.
    #[arg(long, default_value_t = 0)]
    pub threads: usize,
    #[command(flatten)]
    pub integration: Integration,
    /// End each run where this changes sign: "theta = 0"
    #[arg(long = "stop-when")]
    pub stop_when: Option<String>,
    /// csv or json
    #[arg(long, default_value = "csv")]
    pub output: String,
    /// Runs, threads, wall time and runs per second (on stderr).
    #[arg(long)]
    pub stats: bool,
    /// Without a terminal (a log, a pipe): a progress line on stderr every
    /// SECONDS (a terminal gets a bar).
    #[arg(long, value_name = "SECONDS", default_value_t = 10.0)]
    pub log_every: f64,
}

/// An exact command (`derive` … `equilibrium`, `latex`, `check`) read from
/// its arguments.
pub struct ExactArgs<'a> {
    /// The command of the application layer.
    pub command: app::Command,
    /// The scene file.
    pub file: &'a str,
    /// `--format` (LaTeX for `latex`).
    pub format: Format,
    /// `--set`, as written (read after the other options).
    pub set: Option<&'a str>,
    /// The other options, or the error of an option that cannot be
    /// (`modes --standalone` without LaTeX).
    pub options: Result<CommandOptions, Diagnostic>,
    /// `modes --animate`: the page to write the mode shapes to.
    pub animate: Option<&'a str>,
}

impl Command {
    /// The command as an exact command of the application layer; `None`
    /// for the REPL and the numeric commands.
    pub fn exact(&self) -> Option<ExactArgs<'_>> {
        let mut opts = CommandOptions::default();
        let (command, file, format, set) = match self {
            Command::Derive {
                file,
                format,
                structure,
            }
            | Command::Solve {
                file,
                format,
                structure,
            } => {
                opts.structure = structure.choice();
                opts.keep = structure.keep.clone();
                let cmd = match self {
                    Command::Derive { .. } => app::Command::Derive,
                    _ => app::Command::Solve,
                };
                (cmd, file, *format, None)
            }
            Command::Forces { file, format } => (app::Command::Forces, file, *format, None),
            Command::Hamilton { file, format } => (app::Command::Hamilton, file, *format, None),
            Command::Integrals { file, format } => (app::Command::Integrals, file, *format, None),
            Command::Check { file, format } => (app::Command::Check, file, *format, None),
            Command::Equilibrium {
                file,
                format,
                set,
                steady,
            } => {
                opts.steady = steady.clone();
                (app::Command::Equilibrium, file, *format, set.as_deref())
            }
            Command::Latex {
                file,
                steps,
                standalone,
                title,
                set,
            } => {
                opts.steps = *steps;
                opts.standalone = *standalone;
                opts.title = title.clone().unwrap_or_else(|| document_title(file));
                (app::Command::Latex, file, Format::Latex, set.as_deref())
            }
            Command::Modes(args) => {
                let options = args.apply(&mut opts).map(|()| opts);
                return Some(ExactArgs {
                    command: app::Command::Modes,
                    file: &args.file,
                    format: args.format,
                    set: args.set.as_deref(),
                    options,
                    animate: args.animate.as_deref(),
                });
            }
            _ => return None,
        };
        Some(ExactArgs {
            command,
            file,
            format,
            set,
            options: Ok(opts),
            animate: None,
        })
    }
}

/// `--set`, values of any sign (a sign the scene assumes is checked where
/// the command needs it).
fn values(set: Option<&str>) -> Result<qdot::solve::equilibrium::Values, Diagnostic> {
    Ok(set
        .map(output::parse_set_any_sign)
        .transpose()?
        .unwrap_or_default())
}

impl SimulateArgs {
    /// `simulate`'s options (`progress`: a bar on standard error for a
    /// long run), checked in the order the command line always has.
    pub fn options(&self, max_terms: usize, progress: bool) -> Result<CommandOptions, Diagnostic> {
        let mut req = Request {
            stop_when: self.stop_when.clone(),
            functions: self.function.clone(),
            baumgarte: self.baumgarte,
            progress,
            ..self.integration.request()
        };
        output_by_name(&self.output)?;
        req.method = run::method_by_name(&self.integration.method)?;
        req.engine = engine_by_name(&self.integration.evaluator)?;
        let set = values(self.set.as_deref())?;
        req.init = self
            .init
            .as_deref()
            .map(run::parse_init)
            .transpose()?
            .unwrap_or_default();
        if self.plot.is_some() || self.animate.is_some() {
            req.plot_samples = qdot::simulate::plot::SAMPLES;
        }
        Ok(CommandOptions {
            set,
            simulate: req,
            max_terms,
            ..CommandOptions::default()
        })
    }
}

impl SweepArgs {
    /// `sweep`'s options, checked in the order the command line always
    /// has.
    pub fn options(&self, max_terms: usize) -> Result<CommandOptions, Diagnostic> {
        use qdot::simulate::sweep::{parse_axis, Design};
        if !(self.log_every.is_finite() && self.log_every >= 0.0) {
            return Err(Diagnostic::global(format!(
                "`--log-every {}`: not a number of seconds",
                self.log_every
            ))
            .with_hint("--log-every 30 writes a progress line every 30 s")
            .with_kind(ErrorKind::bad_option("--log-every")));
        }
        output_by_name(&self.output)?;
        let mut base = Request {
            stop_when: self.stop_when.clone(),
            ..self.integration.request()
        };
        base.method = run::method_by_name(&self.integration.method)?;
        base.engine = engine_by_name(&self.integration.evaluator)?;
        let set = values(self.set.as_deref())?;
        base.init = self
            .init
            .as_deref()
            .map(run::parse_init)
            .transpose()?
            .unwrap_or_default();
        let axes = self
            .vary
            .iter()
            .map(|v| parse_axis(v))
            .collect::<Result<Vec<_>, _>>()?;
        let design = match self.samples {
            Some(samples) => Design::Random {
                samples,
                seed: self.seed,
            },
            None => Design::Grid,
        };
        Ok(CommandOptions {
            set,
            simulate: base,
            sweep: SweepOptions {
                axes,
                design,
                threads: self.threads,
                progress: None,
            },
            max_terms,
            ..CommandOptions::default()
        })
    }
}

impl CodegenArgs {
    /// `codegen`'s options.
    pub fn options(&self, max_terms: usize) -> Result<CommandOptions, Diagnostic> {
        use qdot::simulate::codegen::{CodegenRequest, Form, Lang};
        let mut req = CodegenRequest::new(
            &self.file,
            match self.lang {
                CodegenLang::C => Lang::C,
                CodegenLang::Rust => Lang::Rust,
                CodegenLang::Python => Lang::Python,
                CodegenLang::Julia => Lang::Julia,
            },
        );
        req.form = match self.form {
            CodegenForm::Accelerations => Form::Accelerations,
            CodegenForm::MassMatrix => Form::MassMatrix,
        };
        req.functions = self.function.clone();
        req.baumgarte = self.baumgarte;
        Ok(CommandOptions {
            set: values(self.set.as_deref())?,
            codegen: req,
            max_terms,
            ..CommandOptions::default()
        })
    }
}

/// The default title of a standalone LaTeX document: the scene's name
/// from its first comment, as `simulate --plot` titles it, else the
/// file's [`base_name`].
fn document_title(file: &str) -> String {
    std::fs::read_to_string(file)
        .ok()
        .and_then(|src| qdot::simulate::plot::scene_title(&src))
        .unwrap_or_else(|| base_name(file))
}

/// A file's name without its folders and extension
/// (`examples/seed_24_2.qd` → `seed_24_2`).
pub fn base_name(file: &str) -> String {
    std::path::Path::new(file)
        .file_stem()
        .and_then(|s| s.to_str())
        .unwrap_or(file)
        .to_string()
}

/// A time option's value (`--t-end`, `--dt`, `floquet --period`): a
/// decimal as a double reads it (`inf` and `1e400` too, refused with the
/// option's own message later), else a constant expression read by the
/// one evaluator of numeric values (`2*pi`, `pi/100`).
pub fn number(s: &str) -> Result<f64, String> {
    s.trim()
        .parse::<f64>()
        .or_else(|_| qdot::scene::given::constant_value(s).map_err(|e| e.message(s.trim())))
}
