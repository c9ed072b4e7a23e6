//! The numeric studies on the command line (`cycle`, `response`,
//! `floquet`): their arguments read into the application layer's options,
//! the study run by it, the pictures written, the report printed.

use super::args::base_name;
use super::report::{emit, Reporter};
use qdot::diag::ErrorKind;
use qdot::output::{self, Format};
use std::process::ExitCode;

/// The options of `qdot cycle`.
#[derive(clap::Args)]
pub struct CycleArgs {
    /// The scene file (.qd).
    pub file: String,
    /// The varied quantity, `t` or a driven coordinate, from FROM to TO in
    /// COUNT positions: phi=0:360deg:73 (deg and pi allowed)
    #[arg(long)]
    pub over: String,
    /// Every parameter's value: R=0.1,L=0.4
    #[arg(long)]
    pub set: Option<String>,
    /// Coordinates of an assembly near the first position (the others
    /// start from 0): th=-0.3,xb=0.5
    #[arg(long)]
    pub guess: Option<String>,
    /// text (the reactions, aligned, 5 significant digits), csv (every
    /// column, every digit) or json; default: text on a terminal, csv
    /// when standard output is piped
    #[arg(long, visible_alias = "format")]
    pub output: Option<String>,
    /// Print only these columns after the varied one: O_x,O_y,M
    #[arg(long)]
    pub columns: Option<String>,
    /// Also draw the reaction diagrams to this SVG file: each joint's
    /// components and each drive against the varied quantity, and the
    /// polar diagram of each pin force.
    #[arg(long)]
    pub plot: Option<String>,
    /// Also write the mechanism moving through its cycle: a
    /// self-contained HTML page (FILE.html) or an animated SVG (FILE.svg).
    #[arg(long)]
    pub animate: Option<String>,
}

impl CycleArgs {
    /// `--output`, or by default text on a terminal and CSV otherwise.
    pub fn output_name(&self) -> &str {
        match &self.output {
            Some(name) => name,
            None if std::io::IsTerminal::is_terminal(&std::io::stdout()) => "text",
            None => "csv",
        }
    }

    /// These options as the application layer's.
    pub fn options(&self, opts: &mut output::CommandOptions) -> Result<Format, qdot::Diagnostic> {
        let fmt = study_format(
            self.output_name(),
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
    pub fn pictures(&self, report: &qdot::AnyReport) -> Result<(), qdot::Diagnostic> {
        let qdot::AnyReport::Cycle(r) = report else {
            return Ok(());
        };
        let (run, title) = (&r.result, figure_title(&self.file, r.scene()));
        if let Some(path) = &self.plot {
            let svg =
                qdot::drawing::reaction_diagrams(&run.table, &title, run.degrees).map_err(|e| {
                    qdot::Diagnostic::global(format!("cannot draw the reaction diagrams: {e}"))
                        .with_kind(ErrorKind::bad_option("--plot"))
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

/// A figure's title: the scene's name (its first comment's first
/// phrase, as `simulate --plot` takes it), else the file's base name.
fn figure_title(file: &str, scene: &qdot::Scene) -> String {
    qdot::simulate::plot::scene_title(&scene.source).unwrap_or_else(|| base_name(file))
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
pub fn run(
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
pub struct ResponseArgs {
    /// The scene file (.qd).
    pub file: String,
    /// The equilibrium to linearize about (default: every q = 0), e.g. th=pi
    #[arg(long)]
    pub at: Option<String>,
    /// Parameter values: for sign decisions, and every parameter's value
    /// with --over: m=1,k=4,c=0.2,F0=1
    #[arg(long)]
    pub set: Option<String>,
    /// Sweep the forcing frequency numerically: Omega=FROM:TO:COUNT
    #[arg(long)]
    pub over: Option<String>,
    /// text or json; with --over also csv (every digit)
    #[arg(long, default_value = "text")]
    pub output: String,
    /// With --over: draw amplitude and phase against Ω (log-log) to this
    /// SVG file, the natural frequencies marked.
    #[arg(long, requires = "over")]
    pub plot: Option<String>,
}

impl ResponseArgs {
    /// These options as the application layer's.
    pub fn options(&self, opts: &mut output::CommandOptions) -> Result<Format, qdot::Diagnostic> {
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
    pub fn pictures(&self, report: &qdot::AnyReport) -> Result<(), qdot::Diagnostic> {
        let (Some(path), qdot::AnyReport::Response(r)) = (&self.plot, report) else {
            return Ok(());
        };
        let qdot::app::FrequencyResponse::Swept(table) = &r.result else {
            return Ok(());
        };
        qdot::simulate::response_plot::svg(table, &figure_title(&self.file, r.scene()))
            .map_err(|e| e.to_string())
            .and_then(|svg| std::fs::write(path, svg).map_err(|e| e.to_string()))
            .map_err(|e| qdot::Diagnostic::global(format!("cannot write the plot `{path}`: {e}")))
    }
}

/// The options of `qdot floquet`.
#[derive(clap::Args)]
pub struct FloquetArgs {
    /// The scene file (.qd).
    pub file: String,
    /// The reference position, a motion for all t (default: every q = 0),
    /// e.g. theta=pi
    #[arg(long)]
    pub at: Option<String>,
    /// Every parameter's value (the --over ones may be left out): g=9.81,l=1
    #[arg(long)]
    pub set: Option<String>,
    /// The definition of a given function of time, once per function:
    /// --function "s=a*cos(w*t)"
    #[arg(long = "function")]
    pub function: Vec<String>,
    /// The period of the coefficients, when it is not found from their
    /// time dependence: a number or a constant expression (2*pi).
    #[arg(long, value_parser = super::args::number)]
    pub period: Option<f64>,
    /// The most steps one integration over the period may take (a period
    /// long against the motion's own time scale needs more).
    #[arg(long, default_value_t = qdot::limits::DEFAULT_MAX_STEPS)]
    pub max_steps: usize,
    /// One or two parameters varied over a grid: delta=-1:3:81,eps=0:2:41
    #[arg(long)]
    pub over: Option<String>,
    /// text, csv or json
    #[arg(long, default_value = "text")]
    pub output: String,
    /// With --over: also draw to this SVG file the largest |μ| (one
    /// parameter) or the stability chart (two).
    #[arg(long)]
    pub plot: Option<String>,
    /// With --over: the grid's points on this many threads (0: one per
    /// core), as `sweep --threads`; the output is the same for any number.
    #[arg(long, default_value_t = 0)]
    pub threads: usize,
}

impl FloquetArgs {
    /// These options as the application layer's.
    pub fn options(&self, opts: &mut output::CommandOptions) -> Result<Format, qdot::Diagnostic> {
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
        opts.threads = self.threads;
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
    pub fn pictures(&self, report: &qdot::AnyReport) -> Result<(), qdot::Diagnostic> {
        let (Some(path), qdot::AnyReport::Floquet(r)) = (&self.plot, report) else {
            return Ok(());
        };
        qdot::drawing::floquet::svg(&r.result, &figure_title(&self.file, r.scene()))
            .map_err(|e| format!("cannot draw the chart: {e}"))
            .and_then(|svg| {
                std::fs::write(path, svg).map_err(|e| format!("cannot write `{path}`: {e}"))
            })
            .map_err(qdot::Diagnostic::global)
    }
}
