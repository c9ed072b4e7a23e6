//! The `qdot` command line: the arguments read into the application
//! layer's options (`cli::args`), each command run through it
//! (`cli::run`).

/// The command line's own modules (not the library's).
mod cli {
    pub mod args;
    pub mod report;
    pub mod run;
    pub mod terminal;
}

use clap::Parser;
use cli::args::{base_name, Cli, Command};
use cli::report::{emit, on_scene, Reporter};
use qdot::diag::ErrorKind;
use qdot::output;
use std::process::ExitCode;

// Exact arithmetic allocates many small polynomials; mimalloc serves them
// faster than the system allocator (measured: ~25% of all instructions were
// glibc malloc/free on the seed problems).
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn main() -> ExitCode {
    let cli = Cli::parse();
    let max_terms = cli.max_terms;
    let Some(command) = cli.command else {
        return cli::run::repl(None, false, max_terms);
    };
    match &command {
        Command::Repl { file, echo } => cli::run::repl(file.as_deref(), *echo, max_terms),
        Command::Simulate(args) => cli::run::simulate(args, max_terms),
        Command::Sweep(args) => cli::run::sweep(args, max_terms),
        Command::Codegen(args) => cli::run::codegen(args, max_terms),
        Command::Cycle(args) => {
            let report = Reporter::new(&args.file, args.output == "json");
            on_scene(report, max_terms, |src| cycle(report, src, args))
        }
        Command::Response(args) => response(args, max_terms),
        Command::Floquet(args) => floquet(args, max_terms),
        // the exact commands (every other is matched above)
        exact => exact
            .exact()
            .map_or(ExitCode::FAILURE, |a| cli::run::exact(a, max_terms)),
    }
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

fn cycle(report: Reporter, src: &str, o: &CycleArgs) -> ExitCode {
    use qdot::cycle::{parse_guess, CycleRequest, Over};
    use qdot::simulate::cycle as render;
    let req = (|| -> Result<CycleRequest, qdot::Diagnostic> {
        if !["csv", "json", "text"].contains(&o.output.as_str()) {
            return Err(
                qdot::Diagnostic::global(format!("unknown output `{}`", o.output))
                    .with_hint("--output csv, --output json or --output text")
                    .with_kind(ErrorKind::bad_option("--output")),
            );
        }
        Ok(CycleRequest {
            over: Over::parse(&o.over)?,
            set: o
                .set
                .as_deref()
                .map(output::parse_set_any_sign)
                .transpose()?
                .unwrap_or_default(),
            guess: o
                .guess
                .as_deref()
                .map(parse_guess)
                .transpose()?
                .unwrap_or_default(),
        })
    })();
    let req = match req {
        Ok(r) => r,
        Err(d) => return report.fail(&d, ""),
    };
    let run = match render::run(src, &req) {
        Ok(t) => t,
        Err(d) => return report.fail(&d, src),
    };
    if let Err(d) = cycle_pictures(&run, &base_name(&o.file), o) {
        return report.fail(&d, "");
    }
    let table = &run.table;
    let shown = match o
        .columns
        .as_deref()
        .map(|c| render::select(table, c))
        .transpose()
    {
        Ok(t) => t,
        Err(d) => return report.fail(&d, ""),
    };
    let table = shown.as_ref().unwrap_or(table);
    emit(&match o.output.as_str() {
        "json" => render::json(table),
        "text" => render::text(table, run.degrees),
        _ => render::csv(table),
    });
    ExitCode::SUCCESS
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

fn response(o: &ResponseArgs, max_terms: usize) -> ExitCode {
    let report = Reporter::new(&o.file, o.output == "json");
    on_scene(report, max_terms, |src| {
        response_of(report, src, o, max_terms)
    })
}

/// `qdot response` on the scene text `src`.
fn response_of(report: Reporter, src: &str, o: &ResponseArgs, max_terms: usize) -> ExitCode {
    use qdot::simulate::response as sweep;
    let outputs: &[&str] = if o.over.is_some() {
        &["csv", "json", "text"]
    } else {
        &["json", "text"]
    };
    let options = (|| -> Result<_, qdot::Diagnostic> {
        if !outputs.contains(&o.output.as_str()) {
            return Err(
                qdot::Diagnostic::global(format!("unknown output `{}`", o.output))
                    .with_hint(format!(
                        "--output {}{}",
                        outputs.join(", --output "),
                        if o.over.is_some() {
                            ""
                        } else {
                            " (csv with --over)"
                        }
                    ))
                    .with_kind(ErrorKind::bad_option("--output")),
            );
        }
        let set = o
            .set
            .as_deref()
            .map(output::parse_set_any_sign)
            .transpose()?
            .unwrap_or_default();
        let over = o.over.as_deref().map(sweep::parse_over).transpose()?;
        Ok((set, over))
    })();
    let (set, over) = match options {
        Ok(x) => x,
        Err(d) => return report.fail(&d, ""),
    };
    let Some(over) = over else {
        return match output::response::response_output(
            src,
            o.at.as_deref(),
            &set,
            max_terms,
            o.output == "json",
        ) {
            Ok(text) => {
                emit(&text);
                ExitCode::SUCCESS
            }
            Err(d) => report.fail(&d, src),
        };
    };
    let table = match sweep::sweep(src, o.at.as_deref(), &set, &over) {
        Ok(t) => t,
        Err(d) => return report.fail(&d, src),
    };
    if let Some(path) = &o.plot {
        let written = qdot::simulate::response_plot::svg(&table, &base_name(&o.file))
            .map_err(|e| e.to_string())
            .and_then(|svg| std::fs::write(path, svg).map_err(|e| e.to_string()));
        if let Err(e) = written {
            let d = qdot::Diagnostic::global(format!("cannot write the plot `{path}`: {e}"));
            return report.fail(&d, "");
        }
    }
    emit(&match o.output.as_str() {
        "json" => sweep::json(&table),
        "csv" => sweep::csv(&table),
        _ => sweep::text(&table),
    });
    ExitCode::SUCCESS
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

/// `qdot floquet`, under the work budget `--max-terms`.
fn floquet(o: &FloquetArgs, max_terms: usize) -> ExitCode {
    let report = Reporter::new(&o.file, o.output == "json");
    on_scene(report, max_terms, |src| floquet_on(report, src, o))
}

fn floquet_on(report: Reporter, src: &str, o: &FloquetArgs) -> ExitCode {
    use qdot::simulate::floquet as render;
    let req = (|| -> Result<render::Request, qdot::Diagnostic> {
        if !["csv", "json", "text"].contains(&o.output.as_str()) {
            return Err(
                qdot::Diagnostic::global(format!("unknown output `{}`", o.output))
                    .with_hint("--output text, --output csv or --output json")
                    .with_kind(ErrorKind::bad_option("--output")),
            );
        }
        if o.plot.is_some() && o.over.is_none() {
            return Err(qdot::Diagnostic::global(
                "--plot draws the stability over the --over parameters",
            )
            .with_hint("add --over NAME=FROM:TO:COUNT: one parameter draws the largest |μ|, two the stability chart")
            .with_kind(ErrorKind::bad_option("--plot")));
        }
        Ok(render::Request {
            floquet: qdot::floquet::FloquetRequest {
                at: o.at.clone(),
                functions: o.function.clone(),
                period: o.period,
                max_steps: Some(o.max_steps),
            },
            set: o
                .set
                .as_deref()
                .map(output::parse_set_any_sign)
                .transpose()?
                .unwrap_or_default(),
            over: o
                .over
                .as_deref()
                .map(render::parse_over)
                .transpose()?
                .unwrap_or_default(),
        })
    })();
    let req = match req {
        Ok(r) => r,
        Err(d) => return report.fail(&d, ""),
    };
    let run = match render::run(src, &req) {
        Ok(r) => r,
        Err(d) => return report.fail(&d, src),
    };
    if let Some(path) = &o.plot {
        let drawn = qdot::drawing::floquet::svg(&run, &base_name(&o.file))
            .map_err(|e| format!("cannot draw the chart: {e}"))
            .and_then(|svg| {
                std::fs::write(path, svg).map_err(|e| format!("cannot write `{path}`: {e}"))
            });
        if let Err(e) = drawn {
            return report.fail(&qdot::Diagnostic::global(e), "");
        }
    }
    emit(&match o.output.as_str() {
        "json" => render::json(&run),
        "csv" => render::csv(&run),
        _ => render::text(&run),
    });
    ExitCode::SUCCESS
}

/// `cycle --plot` and `--animate`: the pictures written to their files.
fn cycle_pictures(
    run: &qdot::simulate::cycle::CycleRun,
    title: &str,
    o: &CycleArgs,
) -> Result<(), qdot::Diagnostic> {
    let write = |path: &str, text: &str| {
        std::fs::write(path, text)
            .map_err(|e| qdot::Diagnostic::global(format!("cannot write `{path}`: {e}")))
    };
    if let Some(path) = &o.plot {
        let svg =
            qdot::drawing::reaction_diagrams(&run.table, title, run.degrees).map_err(|e| {
                qdot::Diagnostic::global(format!("cannot draw the reaction diagrams: {e}"))
            })?;
        write(path, &svg)?;
    }
    if let Some(path) = &o.animate {
        let page = if path.ends_with(".svg") {
            qdot::drawing::animation_svg(&run.table, title)
        } else {
            qdot::drawing::animation_html(&run.table, title, run.degrees)
        };
        write(path, &page)?;
    }
    Ok(())
}
