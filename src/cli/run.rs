//! The command line's commands through the application layer: the
//! options read, [`qdot::app::run`] within a context, the report rendered
//! by [`qdot::output::render`]; beside it what only a terminal wants (the
//! progress bar, `--stats`, `--plot`'s picture, the notes on standard
//! error) and the exit status.

use super::args::{CodegenArgs, ExactArgs, SimulateArgs, SweepArgs};
use super::report::{emit, Reporter};
use qdot::app::{self, AnyReport, Command, Context, ProgressHook};
use qdot::output::{self, Format};
use qdot::Diagnostic;
use std::process::ExitCode;
use std::sync::{Arc, Mutex, OnceLock};
use std::time::Instant;

/// An exact command: its options, the scene, the result and the scene's
/// warnings.
pub fn exact(a: ExactArgs, max_terms: usize) -> ExitCode {
    let report = Reporter::new(a.file, a.format == Format::Json);
    let mut opts = match a.options {
        Ok(o) => o,
        Err(d) => {
            report.print(&d, "");
            return ExitCode::from(2);
        }
    };
    opts.max_terms = max_terms;
    opts.set = match a.set.map(output::parse_set_any_sign).transpose() {
        Ok(s) => s.unwrap_or_default(),
        Err(d) => return report.fail(&d, ""),
    };
    let src = match report.read_scene() {
        Ok(s) => s,
        Err(code) => return code,
    };
    match output::run_with(a.command, &src, a.format, &opts) {
        Ok((out, warnings)) => {
            for w in &warnings {
                report.print(w, &src);
            }
            emit(&out);
            match a
                .animate
                .map(|path| modes_animation(path, &src, report.file, &opts))
            {
                Some(Err(d)) => report.fail(&d, &src),
                _ => ExitCode::SUCCESS,
            }
        }
        Err(d) => report.fail(&d, &src),
    }
}

/// `modes --animate PATH`: each mode shape moving about the equilibrium.
fn modes_animation(
    path: &str,
    src: &str,
    file: &str,
    opts: &qdot::CommandOptions,
) -> Result<(), Diagnostic> {
    let ctx = Context::new().with_max_terms(opts.max_terms);
    let r = app::modes(&ctx, src, opts)?;
    let (title, subtitle) =
        qdot::drawing::motion::titles(src, file, Some(r.scene()), &r.result.set);
    let page = qdot::drawing::modes_page(r.scene(), &r.result, &title, &subtitle)?;
    write_page(path, &page)
}

/// A page written to `path` (`--animate`).
fn write_page(path: &str, page: &str) -> Result<(), Diagnostic> {
    std::fs::write(path, page).map_err(|e| {
        Diagnostic::global(format!("cannot write the animation `{path}`: {e}"))
            .with_kind(qdot::diag::ErrorKind::bad_option("--animate"))
    })
}

/// `cmd` on `src` in the context of `--max-terms`.
fn run(cmd: Command, src: &str, opts: &qdot::CommandOptions) -> Result<AnyReport, Diagnostic> {
    app::run(
        &Context::new().with_max_terms(opts.max_terms),
        cmd,
        src,
        opts,
    )
}

/// The error of a report of another command than asked (never made).
fn mismatched(cmd: Command) -> Diagnostic {
    Diagnostic::global(format!("`{}` made another report", cmd.name()))
        .with_kind(qdot::diag::ErrorKind::Internal)
}

/// `--output`: JSON, or the table's CSV.
fn output_format(output: &str) -> Format {
    if output == "json" {
        Format::Json
    } else {
        Format::Csv
    }
}

/// `qdot simulate`: the table on standard output; the notes, `--stats`,
/// the warnings and why a run stopped early on standard error; exit
/// status 3 for a run that stopped early.
pub fn simulate(a: &SimulateArgs, max_terms: usize) -> ExitCode {
    let report = Reporter::new(&a.file, a.output == "json");
    let src = match report.read_scene() {
        Ok(s) => s,
        Err(code) => return code,
    };
    let terminal = std::io::IsTerminal::is_terminal(&std::io::stderr());
    let opts = match a.options(max_terms, terminal) {
        Ok(o) => o,
        Err(d) => return report.fail(&d, ""),
    };
    let ran = run(Command::Simulate, &src, &opts);
    let (any, table) = match ran.and_then(|r| {
        let table = output::render(&r, output_format(&a.output))?;
        Ok((r, table))
    }) {
        Ok(x) => x,
        Err(d) => return report.fail(&d, &src),
    };
    let AnyReport::Simulate(r) = &any else {
        return report.fail(&mismatched(Command::Simulate), "");
    };
    let sim = &r.result;
    if let Some(note) = sim.zero_velocities_note() {
        eprintln!("{note}");
    }
    emit(&table);
    if a.stats {
        eprint!("{}", output::run::stats_text(&sim.run));
    }
    if let Some(path) = &a.plot {
        let labels =
            qdot::simulate::plot::Labels::of_run(Some(r.scene()), &src, report.file, &sim.request);
        let written = qdot::simulate::plot::svg(&sim.run, &labels)
            .map_err(|e| e.to_string())
            .and_then(|svg| std::fs::write(path, svg).map_err(|e| e.to_string()));
        if let Err(e) = written {
            let d = Diagnostic::global(format!("cannot write the plot `{path}`: {e}"))
                .with_kind(qdot::diag::ErrorKind::bad_option("--plot"));
            return report.fail(&d, "");
        }
    }
    if let Some(path) = &a.animate {
        let labels =
            qdot::simulate::plot::Labels::of_run(Some(r.scene()), &src, report.file, &sim.request);
        let written = qdot::drawing::run_page(
            r.scene(),
            &sim.run,
            &sim.request.set,
            &labels.title,
            &labels.subtitle,
        )
        .and_then(|page| write_page(path, &page));
        if let Err(d) = written {
            return report.fail(&d, "");
        }
    }
    for w in sim.run_warnings() {
        report.print(&w, "");
    }
    if let Some(note) = sim.event_note() {
        eprintln!("{note}");
    }
    match sim.stopped_early() {
        Some(d) => {
            report.print(&d, "");
            ExitCode::from(3)
        }
        None => ExitCode::SUCCESS,
    }
}

/// `sweep`'s progress on standard error: a bar on a terminal, else a line
/// every `log_every` seconds.
struct SweepProgress {
    bar: OnceLock<indicatif::ProgressBar>,
    /// When the runs started, and when a line was last written.
    clock: Mutex<Option<(Instant, Instant)>>,
    log_every: f64,
}

impl SweepProgress {
    fn tick(&self, done: usize, total: usize) {
        let bar = self.bar.get_or_init(|| {
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
            bar
        });
        bar.set_position(done as u64);
        let Ok(mut clock) = self.clock.try_lock() else {
            return;
        };
        let now = Instant::now();
        let (start, last) = clock.get_or_insert((now, now));
        // without a terminal (a log, a pipe) a line every `log_every` instead
        if !bar.is_hidden() || done == 0 {
            return;
        }
        if last.elapsed().as_secs_f64() >= self.log_every && done < total {
            *last = now;
            let spent = start.elapsed().as_secs_f64();
            let left = spent * (total - done) as f64 / done.max(1) as f64;
            eprintln!(
                "sweep: {} of {} runs done in {spent:.0} s, about {left:.0} s left",
                qdot::budget::grouped(done),
                qdot::budget::grouped(total)
            );
        }
    }

    fn clear(&self) {
        if let Some(bar) = self.bar.get() {
            bar.finish_and_clear();
        }
    }
}

/// `qdot sweep`: one summary row per run on standard output; the notes,
/// `--stats` and the failed runs' count on standard error.
pub fn sweep(a: &SweepArgs, max_terms: usize) -> ExitCode {
    let report = Reporter::new(&a.file, a.output == "json");
    let src = match report.read_scene() {
        Ok(s) => s,
        Err(code) => return code,
    };
    let mut opts = match a.options(max_terms) {
        Ok(o) => o,
        Err(d) => return report.fail(&d, ""),
    };
    let progress = Arc::new(SweepProgress {
        bar: OnceLock::new(),
        clock: Mutex::new(None),
        log_every: a.log_every,
    });
    let told = Arc::clone(&progress);
    opts.sweep.progress = Some(ProgressHook::new(move |done, total| told.tick(done, total)));
    let ran = run(Command::Sweep, &src, &opts);
    progress.clear();
    let (any, table) = match ran.and_then(|r| {
        let table = output::render(&r, output_format(&a.output))?;
        Ok((r, table))
    }) {
        Ok(x) => x,
        Err(d) => return report.fail(&d, &src),
    };
    let AnyReport::Sweep(r) = &any else {
        return report.fail(&mismatched(Command::Sweep), "");
    };
    let study = &r.result;
    if let Some(note) = study.zero_velocities_note() {
        eprintln!("{note}");
    }
    emit(&table);
    if a.stats {
        eprint!("{}", output::sweep::stats_text(&study.sweep));
    }
    if let Some(w) = study.failures() {
        report.print(&w, "");
    }
    ExitCode::SUCCESS
}

/// `qdot codegen`: the source code on standard output.
pub fn codegen(a: &CodegenArgs, max_terms: usize) -> ExitCode {
    let report = Reporter::new(&a.file, false);
    let opts = match a.options(max_terms) {
        Ok(o) => o,
        Err(d) => return report.fail(&d, ""),
    };
    let src = match report.read_scene() {
        Ok(s) => s,
        Err(code) => return code,
    };
    match run(Command::Codegen, &src, &opts).and_then(|r| output::render(&r, Format::Text)) {
        Ok(code) => {
            emit(&code);
            ExitCode::SUCCESS
        }
        Err(d) => report.fail(&d, &src),
    }
}

/// The REPL, on `file` if given.
pub fn repl(file: Option<&str>, echo: bool, max_terms: usize) -> ExitCode {
    match super::terminal::run(file, echo, max_terms) {
        0 => ExitCode::SUCCESS,
        _ => ExitCode::from(1),
    }
}
