//! The `qdot` command line.

/// The command line's own modules (not the library's).
mod cli {
    pub mod terminal;
}

use clap::{Parser, Subcommand, ValueEnum};
use qdot::diag::ErrorKind;
use qdot::output::{self, Format};
use std::process::ExitCode;

// Exact arithmetic allocates many small polynomials; mimalloc serves them
// faster than the system allocator (measured: ~25% of all instructions were
// glibc malloc/free on the seed problems).
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

#[derive(Parser)]
#[command(
    name = "qdot",
    version,
    about = "Exact analytical mechanics: Lagrange's equations, derived and solved exactly"
)]
struct Cli {
    /// Without a command, qdot starts the REPL.
    #[command(subcommand)]
    command: Option<Command>,
    /// The work budget of exact computation: the most terms one expression
    /// may reach before qdot stops with an error (every command; the REPL
    /// has :max-terms).
    #[arg(long = "max-terms", global = true, default_value_t = qdot::limits::DEFAULT_MAX_TERMS)]
    max_terms: usize,
}

/// `--format` of `cmd`: the formats it writes, by their names in the one
/// table of formats (`qdot::app::Format`).
fn format_arg(cmd: output::Command) -> impl clap::builder::TypedValueParser<Value = Format> {
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
enum CodegenLang {
    C,
    Rust,
    Python,
    Julia,
}

#[derive(Clone, Copy, ValueEnum)]
enum CodegenForm {
    /// y' = F(t, y) for y = (q, q̇), M·q̈ = f solved inside
    Accelerations,
    /// M(q, t) and f(q, q̇, t) as two functions
    MassMatrix,
}

#[derive(Subcommand)]
enum Command {
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
        /// The title of the --standalone document (default: the file's
        /// base name)
        #[arg(long)]
        title: Option<String>,
        /// Parameter values, for scenes whose equilibria need them: m=1,g=9.81
        #[arg(long)]
        set: Option<String>,
    },
    /// Integrate the equations numerically: the exact M and f compiled to
    /// f64, then RK4, DOPRI5, DOP853, Vern7, Gauss6 or Radau5.
    Simulate {
        /// The scene file (.qd).
        file: String,
        /// Every parameter's value: m=1,g=9.81
        #[arg(long)]
        set: Option<String>,
        /// Every coordinate's initial value, and the velocities' (0 where not given): theta=0.5,theta'=0
        #[arg(long)]
        init: Option<String>,
        #[command(flatten)]
        integration: Integration,
        /// csv or json
        #[arg(long, default_value = "csv")]
        output: String,
        /// Steps, rejections, RHS evaluations, factorizations, wall time (on stderr).
        #[arg(long)]
        stats: bool,
        /// Also draw the motion to this SVG file: q(t), the phase portrait,
        /// and the energy error when the scene conserves energy.
        #[arg(long)]
        plot: Option<String>,
        /// End the run where this changes sign: "theta = 0", "x' = 0"
        /// (located on the dense output of dopri5, dop853, vern7 or rk4).
        #[arg(long = "stop-when")]
        stop_when: Option<String>,
        /// The definition of a given function of time (`functions s` in the
        /// scene), once per function: --function "s=1/10*sin(2*t)"
        #[arg(long = "function")]
        function: Vec<String>,
        /// Baumgarte's rate for a scene with constraints, in 1/time of the
        /// scene: drift from the constraints decays like exp(-rate*t); 0 turns it off.
        #[arg(long, default_value_t = 1.0)]
        baumgarte: f64,
    },
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
    Codegen {
        /// The scene file (.qd).
        file: String,
        /// The language of the code.
        #[arg(long, value_enum)]
        lang: CodegenLang,
        /// The functions: the right-hand side, or M and f apart.
        #[arg(long, value_enum, default_value = "accelerations")]
        form: CodegenForm,
        /// Parameters made constants of the code (the others stay
        /// arguments): m=1,g=9.81
        #[arg(long)]
        set: Option<String>,
        /// The definition of a given function of time, once per function:
        /// --function "s=1/10*sin(2*t)"
        #[arg(long = "function")]
        function: Vec<String>,
        /// Baumgarte's rate for a scene with constraints (a constant of
        /// the code).
        #[arg(long, default_value_t = 1.0)]
        baumgarte: f64,
    },
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

/// Write a result to standard output. A reader that has gone (`qdot … |
/// head`) is not an error of the run: `print!` would panic on the closed
/// pipe; the rest is dropped instead.
fn emit(text: &str) {
    use std::io::Write;
    let mut out = std::io::stdout().lock();
    if let Err(e) = out.write_all(text.as_bytes()).and_then(|()| out.flush()) {
        if e.kind() != std::io::ErrorKind::BrokenPipe {
            eprintln!("error: cannot write the result: {e}");
        }
    }
}

/// `qdot modes`' arguments.
#[derive(clap::Args)]
struct ModesArgs {
    /// The scene file (.qd).
    file: String,
    #[arg(long, value_parser = format_arg(output::Command::Modes), default_value = "text")]
    format: Format,
    /// The equilibrium to linearize about (default: every q = 0), e.g.
    /// th=pi; about a steady motion, also the steady rates: th=pi/3,phi'=w
    #[arg(long)]
    at: Option<String>,
    /// Linearize about a steady motion: these cyclic coordinates turn
    /// at constant rates (their symbols q̇, or the rates --at gives),
    /// the others rest at --at; the rates are reduced away Routh's way
    #[arg(long, value_name = "Q,…")]
    steady: Option<String>,
    /// Initial conditions for the free response: y1=1/10,y1'=0
    #[arg(long)]
    init: Option<String>,
    /// Parameter values for numeric frequencies and sign decisions
    #[arg(long)]
    set: Option<String>,
    /// With --format latex: a whole `article` document that compiles
    /// with pdflatex (without it, a fragment to \input)
    #[arg(long)]
    standalone: bool,
    /// The title of the --standalone document (default: the file's
    /// base name)
    #[arg(long, requires = "standalone")]
    title: Option<String>,
}

impl ModesArgs {
    /// Put these options into `opts`; an error when `--standalone` is
    /// asked for without LaTeX.
    fn apply(&self, opts: &mut output::CommandOptions) -> Result<(), qdot::Diagnostic> {
        opts.at = self.at.clone();
        opts.steady = self.steady.clone();
        opts.init = self.init.clone();
        if self.standalone && self.format != Format::Latex {
            return Err(
                qdot::Diagnostic::global("--standalone makes a LaTeX document")
                    .with_hint("add --format latex")
                    .with_kind(ErrorKind::bad_option("--standalone")),
            );
        }
        opts.standalone = self.standalone;
        opts.title = self.title.clone().unwrap_or_else(|| base_name(&self.file));
        Ok(())
    }
}

/// `--expand` / `--structured`: how results are written.
#[derive(clap::Args, Debug, Clone)]
struct StructureArgs {
    /// Write the results fully expanded, however large.
    #[arg(long, conflicts_with = "structured")]
    expand: bool,
    /// Write the results through named intermediates (a scene's moving
    /// vectors and frames kept, M = L·D·Lᵀ for the accelerations), however
    /// small. Without either flag, qdot expands unless the expanded M and
    /// f would pass 256 terms.
    #[arg(long)]
    structured: bool,
    /// Keep these definitions as intermediates (`--keep alpha,beta`): the
    /// results are written in them and their rates (alpha_dot,
    /// alpha_ddot).
    #[arg(long, value_delimiter = ',', value_name = "NAME,…")]
    keep: Vec<String>,
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

fn main() -> ExitCode {
    let cli = Cli::parse();
    let Some(command) = cli.command else {
        return repl(None, false, cli.max_terms);
    };
    let mut opts = output::CommandOptions {
        max_terms: cli.max_terms,
        ..output::CommandOptions::default()
    };
    let (cmd, file, fmt, set) = match &command {
        Command::Repl { file, echo } => return repl(file.as_deref(), *echo, cli.max_terms),
        Command::Simulate {
            file,
            set,
            init,
            integration,
            output,
            stats,
            plot,
            stop_when,
            function,
            baumgarte,
        } => {
            let report = Reporter::new(file, output == "json");
            return on_scene(report, cli.max_terms, |src| {
                simulate(
                    report,
                    src,
                    set.as_deref(),
                    init.as_deref(),
                    qdot::simulate::run::Request {
                        stop_when: stop_when.clone(),
                        functions: function.clone(),
                        baumgarte: *baumgarte,
                        progress: std::io::IsTerminal::is_terminal(&std::io::stderr()),
                        ..integration.request()
                    },
                    (&integration.method, &integration.evaluator),
                    output,
                    *stats,
                    plot.as_deref(),
                )
            });
        }
        Command::Sweep(args) => {
            let report = Reporter::new(&args.file, args.output == "json");
            return on_scene(report, cli.max_terms, |src| sweep(report, src, args));
        }
        Command::Cycle(o) => return o.study(cli.max_terms),
        Command::Response(o) => return o.study(cli.max_terms),
        Command::Floquet(o) => return o.study(cli.max_terms),
        Command::Codegen {
            file,
            lang,
            form,
            set,
            function,
            baumgarte,
        } => {
            let report = Reporter::new(file, false);
            let req =
                match codegen_request(file, set.as_deref(), *lang, *form, function, *baumgarte) {
                    Ok(r) => r,
                    Err(d) => return report.fail(&d, ""),
                };
            return on_scene(report, cli.max_terms, |src| codegen(report, src, &req));
        }
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
            let cmd = match command {
                Command::Derive { .. } => output::Command::Derive,
                _ => output::Command::Solve,
            };
            (cmd, file, *format, None)
        }
        Command::Forces { file, format } => (output::Command::Forces, file, *format, None),
        Command::Hamilton { file, format } => (output::Command::Hamilton, file, *format, None),
        Command::Integrals { file, format } => (output::Command::Integrals, file, *format, None),
        Command::Check { file, format } => (output::Command::Check, file, *format, None),
        Command::Equilibrium {
            file,
            format,
            set,
            steady,
        } => {
            opts.steady = steady.clone();
            (output::Command::Equilibrium, file, *format, set.as_deref())
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
            opts.title = title.clone().unwrap_or_else(|| base_name(file));
            (output::Command::Latex, file, Format::Latex, set.as_deref())
        }
        Command::Modes(args) => {
            if let Err(d) = args.apply(&mut opts) {
                Reporter::new(&args.file, args.format == Format::Json).print(&d, "");
                return ExitCode::from(2);
            }
            (
                output::Command::Modes,
                &args.file,
                args.format,
                args.set.as_deref(),
            )
        }
    };
    let report = Reporter::new(file, fmt == Format::Json);
    opts.set = match set.map(output::parse_set_any_sign).transpose() {
        Ok(s) => s.unwrap_or_default(),
        Err(d) => return report.fail(&d, ""),
    };
    let src = match report.read_scene() {
        Ok(s) => s,
        Err(code) => return code,
    };
    match output::run_with(cmd, &src, fmt, &opts) {
        Ok((out, warnings)) => {
            for w in &warnings {
                report.print(w, &src);
            }
            emit(&out);
            ExitCode::SUCCESS
        }
        Err(d) => report.fail(&d, &src),
    }
}

/// Where a command's errors and warnings go: standard error, as text about
/// the scene file, or (`--format json`, `--output json`) one JSON object
/// per line ([`qdot::Diagnostic::to_json`]).
#[derive(Clone, Copy)]
struct Reporter<'a> {
    /// The scene file, as named on the command line.
    file: &'a str,
    /// Whether diagnostics are printed as JSON.
    json: bool,
}

impl<'a> Reporter<'a> {
    fn new(file: &'a str, json: bool) -> Reporter<'a> {
        Reporter { file, json }
    }

    /// Print a diagnostic about `src` (an error or a warning).
    fn print(&self, d: &qdot::Diagnostic, src: &str) {
        if self.json {
            eprintln!("{}", d.to_json(src));
        } else {
            eprint!("{}", d.render(self.file, src));
        }
    }

    /// Print an error about `src`; the exit status of a failed command.
    fn fail(&self, d: &qdot::Diagnostic, src: &str) -> ExitCode {
        self.print(d, src);
        ExitCode::from(1)
    }

    /// The scene file's text, or the exit status after reporting why it
    /// cannot be read or is not UTF-8.
    fn read_scene(&self) -> Result<String, ExitCode> {
        qdot::diag::read_source(self.file).map_err(|e| {
            let (d, text) = e.diagnostic();
            self.fail(&d, text)
        })
    }
}

/// The request of `qdot codegen` from its options.
fn codegen_request(
    file: &str,
    set: Option<&str>,
    lang: CodegenLang,
    form: CodegenForm,
    functions: &[String],
    baumgarte: f64,
) -> Result<qdot::simulate::codegen::CodegenRequest, qdot::Diagnostic> {
    use qdot::simulate::codegen::{CodegenRequest, Form, Lang};
    let mut req = CodegenRequest::new(
        file,
        match lang {
            CodegenLang::C => Lang::C,
            CodegenLang::Rust => Lang::Rust,
            CodegenLang::Python => Lang::Python,
            CodegenLang::Julia => Lang::Julia,
        },
    );
    req.form = match form {
        CodegenForm::Accelerations => Form::Accelerations,
        CodegenForm::MassMatrix => Form::MassMatrix,
    };
    req.functions = functions.to_vec();
    req.baumgarte = baumgarte;
    req.set = set
        .map(output::parse_set_any_sign)
        .transpose()?
        .unwrap_or_default();
    Ok(req)
}

fn codegen(report: Reporter, src: &str, req: &qdot::simulate::codegen::CodegenRequest) -> ExitCode {
    match qdot::simulate::codegen::codegen(src, req) {
        Ok(code) => {
            emit(&code);
            ExitCode::SUCCESS
        }
        Err(d) => report.fail(&d, src),
    }
}

/// Run a command that derives outside `output::run_with` (simulate, sweep,
/// codegen) on the scene's text, under the work budget `--max-terms` as
/// every other command is.
fn on_scene(report: Reporter, max_terms: usize, f: impl FnOnce(&str) -> ExitCode) -> ExitCode {
    let src = match report.read_scene() {
        Ok(s) => s,
        Err(code) => return code,
    };
    match qdot::Context::new()
        .with_max_terms(max_terms)
        .within(|| f(&src))
    {
        Ok(code) => code,
        // the statement it names is shown in its source
        Err(e) => report.fail(&output::too_large(&e), &src),
    }
}

fn repl(file: Option<&str>, echo: bool, max_terms: usize) -> ExitCode {
    match cli::terminal::run(file, echo, max_terms) {
        0 => ExitCode::SUCCESS,
        _ => ExitCode::from(1),
    }
}

#[allow(clippy::too_many_arguments)]
fn simulate(
    report: Reporter,
    src: &str,
    set: Option<&str>,
    init: Option<&str>,
    mut req: qdot::simulate::run::Request,
    (method, evaluator): (&str, &str),
    output: &str,
    stats: bool,
    plot: Option<&str>,
) -> ExitCode {
    use qdot::simulate::run;
    let req_max_steps = req.max_steps;
    let options = (|| -> Result<(), qdot::Diagnostic> {
        output_by_name(output)?;
        req.method = run::method_by_name(method)?;
        req.engine = engine_by_name(evaluator)?;
        req.set = set
            .map(output::parse_set_any_sign)
            .transpose()?
            .unwrap_or_default();
        req.init = init.map(run::parse_init).transpose()?.unwrap_or_default();
        Ok(())
    })();
    if let Err(d) = options {
        return report.fail(&d, "");
    }
    if plot.is_some() {
        req.plot_samples = qdot::simulate::plot::SAMPLES;
    }
    let r = match run::simulate(src, &req) {
        Ok(r) => r,
        Err(d) => return report.fail(&d, src),
    };
    let coordinates = r.columns.iter().filter_map(|c| c.strip_suffix('\''));
    if let Some(note) = run::zero_velocities_note(coordinates, |v| req.init.contains_key(v)) {
        eprintln!("{note}");
    }
    emit(&if output == "json" {
        run::json(&r)
    } else {
        run::csv(&r)
    });
    if stats {
        eprint!("{}", run::stats_text(&r));
    }
    if let Some(path) = plot {
        let labels = qdot::simulate::plot::Labels::of_scene(src, report.file, &req);
        let written = qdot::simulate::plot::svg(&r, &labels)
            .map_err(|e| e.to_string())
            .and_then(|svg| std::fs::write(path, svg).map_err(|e| e.to_string()));
        if let Err(e) = written {
            let d = qdot::Diagnostic::global(format!("cannot write the plot `{path}`: {e}"));
            return report.fail(&d, "");
        }
    }
    if let Some(t) = r.solution.stiff_at {
        let w = qdot::Diagnostic::global_warning(format!(
            "the problem looks stiff from t = {t:.6e} on (Hairer's test); --method radau5 integrates it in far fewer steps"
        ));
        report.print(&w, "");
    }
    for t in &r.solution.event_poles {
        let w = qdot::Diagnostic::global_warning(format!(
            "the --stop-when condition changed sign at t = {t:.6e} without passing through zero (a pole or a jump): not an event, the run went on"
        ));
        report.print(&w, "");
    }
    if let qdot::simulate::Status::Event { t } = r.solution.status {
        eprintln!("stopped at t = {t:.15e}, where the --stop-when condition changes sign");
    }
    use qdot::simulate::Status;
    let (t, hint) = match r.solution.status {
        Status::Done | Status::Event { .. } => return ExitCode::SUCCESS,
        Status::TooManySteps { t } => (t, format!("raise --max-steps (it is {}), loosen --rtol and --atol, or use --method radau5 if the problem is stiff", req_max_steps)),
        Status::StepTooSmall { t } => (t, "the solution may blow up there; check the scene and the initial values, or loosen the tolerances".to_string()),
        Status::NotFinite { t } => (t, r.not_finite_reason()),
    };
    let d = qdot::Diagnostic::global(format!(
        "the integration stopped early: {} at t = {t:.6e}",
        run::status_word(&r.solution.status),
    ))
    .with_hint(hint)
    .with_kind(ErrorKind::Integration);
    report.print(&d, "");
    ExitCode::from(3)
}

/// The options of `qdot cycle`.
#[derive(clap::Args)]
struct CycleArgs {
    /// The scene file (.qd).
    file: String,
    /// The varied quantity, `t` or a driven coordinate, from FROM to TO in
    /// COUNT positions: phi=0:360deg:73 (deg and pi allowed)
    #[arg(long)]
    over: String,
    /// Every parameter's value: R=0.1,L=0.4
    #[arg(long)]
    set: Option<String>,
    /// Coordinates of an assembly near the first position (the others
    /// start from 0): th=-0.3,xb=0.5
    #[arg(long)]
    guess: Option<String>,
    /// csv, json or text (aligned, 6 digits)
    #[arg(long, default_value = "csv")]
    output: String,
    /// Print only these columns after the varied one: O_x,O_y,M
    #[arg(long)]
    columns: Option<String>,
    /// Also draw the reaction diagrams to this SVG file: each joint's
    /// components and each drive against the varied quantity, and the
    /// polar diagram of each pin force.
    #[arg(long)]
    plot: Option<String>,
    /// Also write the mechanism moving through its cycle: a
    /// self-contained HTML page (FILE.html) or an animated SVG (FILE.svg).
    #[arg(long)]
    animate: Option<String>,
}

impl CycleArgs {
    /// `qdot cycle` through the application layer ([`study`]).
    fn study(&self, max_terms: usize) -> ExitCode {
        let cmd = output::Command::Cycle;
        let (options, pictures) = (|x: &mut _| self.options(x), |r: &_| self.pictures(r));
        study(cmd, &self.file, &self.output, max_terms, options, pictures)
    }

    /// These options as the application layer's.
    fn options(&self, opts: &mut output::CommandOptions) -> Result<Format, qdot::Diagnostic> {
        let fmt = study_format(
            &self.output,
            &[Format::Csv, Format::Json, Format::Text],
            "--output csv, --output json or --output text".into(),
        )?;
        opts.over = qdot::app::parse_over(output::Command::Cycle, &self.over)?;
        opts.set = parse_set(self.set.as_deref())?;
        opts.guess = self
            .guess
            .as_deref()
            .map(qdot::cycle::parse_guess)
            .transpose()?
            .unwrap_or_default();
        opts.columns = self
            .columns
            .as_deref()
            .map(qdot::simulate::cycle::column_names);
        Ok(fmt)
    }

    /// `--plot` and `--animate`: the pictures written to their files.
    fn pictures(&self, report: &qdot::AnyReport) -> Result<(), qdot::Diagnostic> {
        let qdot::AnyReport::Cycle(r) = report else {
            return Ok(());
        };
        let (run, title) = (&r.result, base_name(&self.file));
        if let Some(path) = &self.plot {
            let svg =
                qdot::drawing::reaction_diagrams(&run.table, &title, run.degrees).map_err(|e| {
                    qdot::Diagnostic::global(format!("cannot draw the reaction diagrams: {e}"))
                })?;
            write_picture(path, &svg)?;
        }
        if let Some(path) = &self.animate {
            let page = if path.ends_with(".svg") {
                qdot::drawing::animation_svg(&run.table, &title)
            } else {
                qdot::drawing::animation_html(&run.table, &title, run.degrees)
            };
            write_picture(path, &page)?;
        }
        Ok(())
    }
}

/// A picture written to `path`.
fn write_picture(path: &str, text: &str) -> Result<(), qdot::Diagnostic> {
    std::fs::write(path, text)
        .map_err(|e| qdot::Diagnostic::global(format!("cannot write `{path}`: {e}")))
}

/// `--set` of a numeric study: any sign.
fn parse_set(set: Option<&str>) -> Result<qdot::solve::equilibrium::Values, qdot::Diagnostic> {
    Ok(set
        .map(output::parse_set_any_sign)
        .transpose()?
        .unwrap_or_default())
}

/// `--output NAME` of a numeric study, one of `accepted`.
fn study_format(name: &str, accepted: &[Format], hint: String) -> Result<Format, qdot::Diagnostic> {
    Format::from_name(name)
        .filter(|f| accepted.contains(f))
        .ok_or_else(|| {
            qdot::Diagnostic::global(format!("unknown output `{name}`"))
                .with_hint(hint)
                .with_kind(ErrorKind::bad_option("--output"))
        })
}

/// `qdot cycle`, `response` or `floquet` on the scene `file`: the options
/// read by `options`, the study run by the application layer, its
/// pictures written by `pictures`, the report printed.
fn study(
    cmd: output::Command,
    file: &str,
    output_name: &str,
    max_terms: usize,
    options: impl FnOnce(&mut output::CommandOptions) -> Result<Format, qdot::Diagnostic>,
    pictures: impl FnOnce(&qdot::AnyReport) -> Result<(), qdot::Diagnostic>,
) -> ExitCode {
    let report = Reporter::new(file, output_name == "json");
    let src = match report.read_scene() {
        Ok(s) => s,
        Err(code) => return code,
    };
    let mut opts = output::CommandOptions::default();
    let fmt = match options(&mut opts) {
        Ok(f) => f,
        Err(d) => return report.fail(&d, ""),
    };
    let ctx = qdot::Context::new().with_max_terms(max_terms);
    let result = match qdot::app::run(&ctx, cmd, &src, &opts) {
        Ok(r) => r,
        Err(d) => return report.fail(&d, &src),
    };
    if let Err(d) = pictures(&result) {
        return report.fail(&d, "");
    }
    match output::render(&result, fmt) {
        Ok(out) => {
            emit(&out);
            ExitCode::SUCCESS
        }
        Err(d) => report.fail(&d, &src),
    }
}

/// The options of `qdot response`.
#[derive(clap::Args)]
struct ResponseArgs {
    /// The scene file (.qd).
    file: String,
    /// The equilibrium to linearize about (default: every q = 0), e.g. th=pi
    #[arg(long)]
    at: Option<String>,
    /// Parameter values: for sign decisions, and every parameter's value
    /// with --over: m=1,k=4,c=0.2,F0=1
    #[arg(long)]
    set: Option<String>,
    /// Sweep the forcing frequency numerically: Omega=FROM:TO:COUNT
    #[arg(long)]
    over: Option<String>,
    /// text or json; with --over also csv (every digit)
    #[arg(long, default_value = "text")]
    output: String,
    /// With --over: draw amplitude and phase against Ω (log-log) to this
    /// SVG file, the natural frequencies marked.
    #[arg(long, requires = "over")]
    plot: Option<String>,
}

impl ResponseArgs {
    /// `qdot response` through the application layer ([`study`]).
    fn study(&self, max_terms: usize) -> ExitCode {
        let cmd = output::Command::Response;
        let (options, pictures) = (|x: &mut _| self.options(x), |r: &_| self.pictures(r));
        study(cmd, &self.file, &self.output, max_terms, options, pictures)
    }

    /// These options as the application layer's.
    fn options(&self, opts: &mut output::CommandOptions) -> Result<Format, qdot::Diagnostic> {
        let fmt = if self.over.is_some() {
            study_format(
                &self.output,
                &[Format::Csv, Format::Json, Format::Text],
                "--output csv, --output json, --output text".into(),
            )
        } else {
            study_format(
                &self.output,
                &[Format::Json, Format::Text],
                "--output json, --output text (csv with --over)".into(),
            )
        }?;
        opts.set = parse_set(self.set.as_deref())?;
        opts.over = self
            .over
            .as_deref()
            .map(|o| qdot::app::parse_over(output::Command::Response, o))
            .transpose()?
            .unwrap_or_default();
        opts.at = self.at.clone();
        Ok(fmt)
    }

    /// `--plot`: the resonance curves written to their file.
    fn pictures(&self, report: &qdot::AnyReport) -> Result<(), qdot::Diagnostic> {
        let (Some(path), qdot::AnyReport::Response(r)) = (&self.plot, report) else {
            return Ok(());
        };
        let qdot::app::FrequencyResponse::Swept(table) = &r.result else {
            return Ok(());
        };
        qdot::simulate::response_plot::svg(table, &base_name(&self.file))
            .map_err(|e| e.to_string())
            .and_then(|svg| std::fs::write(path, svg).map_err(|e| e.to_string()))
            .map_err(|e| qdot::Diagnostic::global(format!("cannot write the plot `{path}`: {e}")))
    }
}

/// The options of `qdot floquet`.
#[derive(clap::Args)]
struct FloquetArgs {
    /// The scene file (.qd).
    file: String,
    /// The reference position, a motion for all t (default: every q = 0),
    /// e.g. theta=pi
    #[arg(long)]
    at: Option<String>,
    /// Every parameter's value (the --over ones may be left out): g=9.81,l=1
    #[arg(long)]
    set: Option<String>,
    /// The definition of a given function of time, once per function:
    /// --function "s=a*cos(w*t)"
    #[arg(long = "function")]
    function: Vec<String>,
    /// The period of the coefficients, when it is not found from their
    /// time dependence.
    #[arg(long)]
    period: Option<f64>,
    /// The most steps one integration over the period may take (a period
    /// long against the motion's own time scale needs more).
    #[arg(long, default_value_t = qdot::limits::DEFAULT_MAX_STEPS)]
    max_steps: usize,
    /// One or two parameters varied over a grid: delta=-1:3:81,eps=0:2:41
    #[arg(long)]
    over: Option<String>,
    /// text, csv or json
    #[arg(long, default_value = "text")]
    output: String,
    /// With --over: also draw to this SVG file the largest |μ| (one
    /// parameter) or the stability chart (two).
    #[arg(long)]
    plot: Option<String>,
}

impl FloquetArgs {
    /// `qdot floquet` through the application layer ([`study`]).
    fn study(&self, max_terms: usize) -> ExitCode {
        let cmd = output::Command::Floquet;
        let (options, pictures) = (|x: &mut _| self.options(x), |r: &_| self.pictures(r));
        study(cmd, &self.file, &self.output, max_terms, options, pictures)
    }

    /// These options as the application layer's.
    fn options(&self, opts: &mut output::CommandOptions) -> Result<Format, qdot::Diagnostic> {
        let fmt = study_format(
            &self.output,
            &[Format::Text, Format::Csv, Format::Json],
            "--output text, --output csv or --output json".into(),
        )?;
        if self.plot.is_some() && self.over.is_none() {
            return Err(qdot::Diagnostic::global(
                "--plot draws the stability over the --over parameters",
            )
            .with_hint("add --over NAME=FROM:TO:COUNT: one parameter draws the largest |μ|, two the stability chart")
            .with_kind(ErrorKind::bad_option("--plot")));
        }
        opts.at = self.at.clone();
        opts.functions = self.function.clone();
        opts.period = self.period;
        opts.max_steps = Some(self.max_steps);
        opts.set = parse_set(self.set.as_deref())?;
        opts.over = self
            .over
            .as_deref()
            .map(|o| qdot::app::parse_over(output::Command::Floquet, o))
            .transpose()?
            .unwrap_or_default();
        Ok(fmt)
    }

    /// `--plot`: the chart written to its file.
    fn pictures(&self, report: &qdot::AnyReport) -> Result<(), qdot::Diagnostic> {
        let (Some(path), qdot::AnyReport::Floquet(r)) = (&self.plot, report) else {
            return Ok(());
        };
        qdot::drawing::floquet::svg(&r.result, &base_name(&self.file))
            .map_err(|e| format!("cannot draw the chart: {e}"))
            .and_then(|svg| {
                std::fs::write(path, svg).map_err(|e| format!("cannot write `{path}`: {e}"))
            })
            .map_err(qdot::Diagnostic::global)
    }
}

/// A file's name without its folders and extension: the default title of
/// a standalone LaTeX document (`examples/seed_24_2.qd` → `seed_24_2`).
fn base_name(file: &str) -> String {
    std::path::Path::new(file)
        .file_stem()
        .and_then(|s| s.to_str())
        .unwrap_or(file)
        .to_string()
}

/// The integration options `simulate` and `sweep` share.
#[derive(clap::Args)]
struct Integration {
    /// The final time (from t = 0).
    #[arg(long = "t-end")]
    t_end: f64,
    /// rk4, dopri5, dop853, vern7, gauss6 (symplectic) or radau5 (stiff)
    #[arg(long, default_value = "dop853")]
    method: String,
    /// Relative tolerance of the adaptive methods.
    #[arg(long, default_value_t = 1e-8)]
    rtol: f64,
    /// Absolute tolerance of the adaptive methods.
    #[arg(long, default_value_t = 1e-10)]
    atol: f64,
    /// The step of rk4 and gauss6 (the first step of the others).
    #[arg(long)]
    dt: Option<f64>,
    /// Evenly spaced output times from 0 to --t-end (2 to 1,000,000); a
    /// sweep reads max|q| and the energy drift at them.
    #[arg(long, default_value_t = 101)]
    points: usize,
    /// Give up (a run) after this many steps, accepted and rejected.
    #[arg(long = "max-steps", default_value_t = qdot::limits::DEFAULT_MAX_STEPS)]
    max_steps: usize,
    /// What runs the compiled equations: auto (machine code where it
    /// compiles), jit or interpreter.
    #[arg(long, default_value = "auto")]
    evaluator: String,
}

/// `--evaluator NAME`.
fn engine_by_name(name: &str) -> Result<qdot::simulate::compile::Engine, qdot::Diagnostic> {
    qdot::simulate::compile::Engine::by_name(name).ok_or_else(|| {
        qdot::Diagnostic::global(format!("unknown evaluator `{name}`"))
            .with_hint("--evaluator auto, jit (machine code) or interpreter")
            .with_kind(ErrorKind::bad_option("--evaluator"))
    })
}

/// `--output csv|json` of `simulate` and `sweep`.
fn output_by_name(name: &str) -> Result<(), qdot::Diagnostic> {
    if name == "csv" || name == "json" {
        return Ok(());
    }
    Err(qdot::Diagnostic::global(format!("unknown output `{name}`"))
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
struct SweepArgs {
    /// The scene file (.qd).
    file: String,
    /// The values of the parameters that do not vary: m=1,g=9.81
    #[arg(long)]
    set: Option<String>,
    /// The initial values that do not vary (a velocity not given is 0): theta=0.5
    #[arg(long)]
    init: Option<String>,
    /// A varied parameter, coordinate or velocity: "l=0.5:2:16"
    /// (16 values from 0.5 to 2); repeat for a grid over several.
    #[arg(long = "vary", required = true)]
    vary: Vec<String>,
    /// Draw this many random points in the box of the --vary ranges
    /// instead of a grid (COUNT may then be left out).
    #[arg(long)]
    samples: Option<usize>,
    /// The seed of --samples (the same seed, the same points).
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Threads (0: one per core); never more than the cores or the runs.
    #[arg(long, default_value_t = 0)]
    threads: usize,
    #[command(flatten)]
    integration: Integration,
    /// End each run where this changes sign: "theta = 0"
    #[arg(long = "stop-when")]
    stop_when: Option<String>,
    /// csv or json
    #[arg(long, default_value = "csv")]
    output: String,
    /// Runs, threads, wall time and runs per second (on stderr).
    #[arg(long)]
    stats: bool,
    /// Without a terminal (a log, a pipe): a progress line on stderr every
    /// SECONDS (a terminal gets a bar).
    #[arg(long, value_name = "SECONDS", default_value_t = 10.0)]
    log_every: f64,
}

fn sweep(report: Reporter, src: &str, o: &SweepArgs) -> ExitCode {
    use qdot::simulate::{run, sweep};
    let design = match o.samples {
        Some(samples) => sweep::Design::Random {
            samples,
            seed: o.seed,
        },
        None => sweep::Design::Grid,
    };
    let mut base = run::Request {
        stop_when: o.stop_when.clone(),
        ..o.integration.request()
    };
    let prepared = (|| {
        if !(o.log_every.is_finite() && o.log_every >= 0.0) {
            return Err(qdot::Diagnostic::global(format!(
                "`--log-every {}`: not a number of seconds",
                o.log_every
            ))
            .with_hint("--log-every 30 writes a progress line every 30 s")
            .with_kind(ErrorKind::bad_option("--log-every")));
        }
        output_by_name(&o.output)?;
        base.method = run::method_by_name(&o.integration.method)?;
        base.engine = engine_by_name(&o.integration.evaluator)?;
        base.set = o
            .set
            .as_deref()
            .map(output::parse_set_any_sign)
            .transpose()?
            .unwrap_or_default();
        base.init = o
            .init
            .as_deref()
            .map(run::parse_init)
            .transpose()?
            .unwrap_or_default();
        let axes = o
            .vary
            .iter()
            .map(|v| sweep::parse_axis(v))
            .collect::<Result<Vec<_>, _>>()?;
        Ok(axes)
    })();
    let axes = match prepared {
        Ok(a) => a,
        Err(d) => return report.fail(&d, ""),
    };
    let result = run::Prepared::new(src, &base.functions).and_then(|p| {
        let total = sweep::design_points(&axes, design)?.len();
        let bar = if std::io::IsTerminal::is_terminal(&std::io::stderr()) {
            indicatif::ProgressBar::new(total as u64)
        } else {
            indicatif::ProgressBar::hidden()
        };
        bar.set_style(
            indicatif::ProgressStyle::with_template(
                "{bar:40} {pos}/{len} runs, {per_sec}, {eta} left",
            )
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
        );
        // without a terminal (a log, a pipe) a line every LOG_EVERY instead
        let logged = std::sync::Mutex::new(std::time::Instant::now());
        let start = std::time::Instant::now();
        let tick = |done: usize| {
            bar.set_position(done as u64);
            if !bar.is_hidden() {
                return;
            }
            let Ok(mut last) = logged.try_lock() else {
                return;
            };
            if last.elapsed().as_secs_f64() >= o.log_every && done < total {
                *last = std::time::Instant::now();
                let spent = start.elapsed().as_secs_f64();
                let left = spent * (total - done) as f64 / done.max(1) as f64;
                eprintln!(
                    "sweep: {} of {} runs done in {spent:.0} s, about {left:.0} s left",
                    qdot::budget::grouped(done),
                    qdot::budget::grouped(total)
                );
            }
        };
        let s = sweep::sweep(&p, &base, &axes, design, o.threads, &tick);
        bar.finish_and_clear();
        s
    });
    let s = match result {
        Ok(s) => s,
        Err(d) => return report.fail(&d, src),
    };
    let given = |v: &str| base.init.contains_key(v) || axes.iter().any(|a| a.name == v);
    if let Some(note) = run::zero_velocities_note(s.coordinates.iter().map(String::as_str), given) {
        eprintln!("{note}");
    }
    emit(&if o.output == "json" {
        sweep::json(&s)
    } else {
        sweep::csv(&s)
    });
    if o.stats {
        eprintln!(
            "{} runs on {} threads in {:.3} s: {:.0} runs per second; equations compiled {} time{}",
            s.runs.len(),
            s.threads,
            s.seconds,
            s.runs.len() as f64 / s.seconds.max(1e-9),
            s.compilations,
            if s.compilations == 1 { "" } else { "s" }
        );
    }
    let failed = s.runs.iter().filter(|(_, r)| r.is_err()).count();
    if failed > 0 {
        let w = qdot::Diagnostic::global_warning(format!(
            "{failed} of {} runs failed (their rows say why)",
            s.runs.len()
        ));
        report.print(&w, "");
    }
    ExitCode::SUCCESS
}
