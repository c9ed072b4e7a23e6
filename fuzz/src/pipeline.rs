//! What each fuzz target does with its input, shared by the targets
//! (fuzz/fuzz_targets/*.rs) and the regression tests
//! (tests/fuzz_regressions.rs includes this file with `#[path]`), so a
//! finding replays through exactly the code that found it.
//!
//! Every function takes the raw bytes and returns nothing: an `Err` of the
//! library is a correct answer to bad input; a panic, an abort, a stack
//! overflow, a hang or a memory blow-up is a finding.

use qdot::output::{self, Command, CommandOptions, Format};
use qdot::repl::{is_complete, Session};
use qdot::simulate::run;

/// The work budget of every fuzzed command, a tenth of the default: the
/// fuzz build (coverage counters, debug assertions) runs several times
/// slower than a release build, and an input that only does much bounded
/// work is not a finding; one that escapes the budget still is.
const FUZZ_MAX_TERMS: usize = qdot::limits::DEFAULT_MAX_TERMS / 10;

/// The most steps of a fuzzed simulation, a tenth of the default: the
/// step limit's own refusal is tested in tests/simulate_cli.rs.
const FUZZ_MAX_STEPS: usize = 100_000;

/// The target names, in the order the script runs them.
pub const TARGETS: [&str; 6] = [
    "parse", "pipeline", "repl", "simulate", "commands", "motions",
];

/// Replay `data` through the target called `name`.
pub fn by_name(name: &str, data: &[u8]) {
    match name {
        "parse" => parse(data),
        "pipeline" => pipeline(data),
        "repl" => repl(data),
        "simulate" => simulate(data),
        "commands" => commands(data),
        "motions" => motions(data),
        _ => panic!("no fuzz target `{name}`"), // ok: a typo in a test, not input
    }
}

/// Target `parse`: the syntax alone, as a scene and as one expression,
/// with every error rendered (the caret line exercises the spans).
pub fn parse(data: &[u8]) {
    let Ok(src) = std::str::from_utf8(data) else {
        return;
    };
    if let Err(d) = qdot::parse::parse_scene(src) {
        let _ = d.render("fuzz.qd", src);
    }
    if let Err(d) = qdot::parse::parse_expr(src) {
        let _ = d.render("fuzz.qd", src);
    }
}

/// The header a `pipeline` input may start with: `#@ COMMAND FORMAT [SET]`
/// on its first line (a comment, so the input stays a valid scene), e.g.
/// `#@ equilibrium json m=1,g=9.81`. Without one: `solve` as text.
fn header(src: &str) -> (Command, Format, Option<&str>) {
    let first = src.lines().next().unwrap_or("");
    let Some(rest) = first.strip_prefix("#@") else {
        return (Command::Solve, Format::Text, None);
    };
    let mut words = rest.split_whitespace();
    let cmd = words
        .next()
        .and_then(Command::from_name)
        .unwrap_or(Command::Solve);
    let fmt = words
        .next()
        .and_then(Format::from_name)
        .unwrap_or(Format::Text);
    (cmd, fmt, words.next())
}

/// Target `pipeline`: parse → scene → derive → solve (or forces,
/// equilibrium, modes, LaTeX) → print, as `qdot COMMAND --format FORMAT`
/// does, the command chosen by the input's [`header`]. `latex` runs both
/// the fragment and `--steps --standalone`.
pub fn pipeline(data: &[u8]) {
    let Ok(src) = std::str::from_utf8(data) else {
        return;
    };
    let (cmd, fmt, set) = header(src);
    let mut opts = CommandOptions {
        max_terms: FUZZ_MAX_TERMS,
        ..CommandOptions::default()
    };
    if let Some(set) = set {
        match output::parse_set(set) {
            Ok(s) => opts.set = s,
            Err(d) => {
                let _ = d.render("--set", set);
                return;
            }
        }
    }
    let mut runs = vec![(cmd, fmt, opts.clone())];
    if cmd == Command::Latex {
        opts.steps = true;
        opts.standalone = true;
        opts.title = "fuzz.qd".into();
        runs.push((cmd, fmt, opts));
    }
    for (cmd, fmt, opts) in runs {
        run_rendered(cmd, src, fmt, &opts);
    }
}

/// `output::run_with`, its warnings or its error rendered.
fn run_rendered(cmd: Command, src: &str, fmt: Format, opts: &CommandOptions) {
    match output::run_with(cmd, src, fmt, opts) {
        Ok((_, warnings)) => {
            for w in warnings {
                let _ = w.render("fuzz.qd", src);
            }
        }
        Err(d) => {
            let _ = d.render("fuzz.qd", src);
        }
    }
}

/// Target `repl`: the input's lines fed to a [`Session`] as the piped REPL
/// feeds them (an entry is complete when [`is_complete`] says so). `:load`
/// and `:save` are skipped: they would read and write the fuzzer's disk.
pub fn repl(data: &[u8]) {
    let text = String::from_utf8_lossy(data);
    let mut session = Session::new();
    session.max_terms = FUZZ_MAX_TERMS;
    let mut entry = String::new();
    let feed = |session: &mut Session, entry: &str| -> bool {
        let cmd = entry.trim_start();
        let word = cmd.split_whitespace().next().unwrap_or("");
        if word == ":load" || word == ":save" || !repl_entry_is_bounded(cmd) {
            return false;
        }
        session.execute(entry).quit
    };
    for line in text.lines() {
        entry.push_str(line);
        entry.push('\n');
        if !is_complete(&entry) {
            continue;
        }
        if feed(&mut session, &entry) {
            return;
        }
        entry.clear();
    }
    if !entry.trim().is_empty() {
        feed(&mut session, &entry);
    }
    let _ = session.scene_text();
}

/// The scene of a `simulate` input that brings none: the pendulum.
const PENDULUM: &str = "coordinates theta
parameters m, l, g
kinetic E = 1/2*m*l^2*theta'^2
potential V = -m*g*l*cos(theta)
";

/// Target `simulate`: `qdot simulate` with fuzzed options. The input is
/// the options, one `--name value` a line (as on the command line), then
/// optionally a line `---` and the scene (the pendulum without one):
///
/// ```text
/// --set m=1,l=1,g=9.81
/// --init theta=0.5,theta'=0
/// --t-end 10
/// --method rk4
/// --dt 0.01
/// ```
///
/// Values are converted as the CLI's parser (clap, `FromStr`) does; one
/// it would refuse ends the run, as it would. The run is checked,
/// integrated and written as CSV and JSON (and SVG with `--plot`).
pub fn simulate(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let (opts, scene) = match text.split_once("\n---\n") {
        Some((o, s)) => (o, s),
        None => (text, PENDULUM),
    };
    let mut req = run::Request {
        max_steps: FUZZ_MAX_STEPS,
        ..run::Request::default()
    };
    let (mut set, mut init, mut t_end, mut plot) = (None, None, None, false);
    let (mut output, mut method) = ("csv", "dop853");
    for line in opts.lines() {
        let line = line.trim();
        let (key, value) = match line.split_once(char::is_whitespace) {
            Some((k, v)) => (k, v.trim()),
            None => (line, ""),
        };
        let num = || value.parse::<f64>().ok();
        match key {
            "--set" => set = Some(value),
            "--init" => init = Some(value),
            "--method" => method = value,
            "--output" => output = value,
            "--stop-when" => req.stop_when = Some(value.to_string()),
            "--plot" => plot = true,
            "--t-end" => match num() {
                Some(x) => t_end = Some(x),
                None => return,
            },
            "--rtol" => match num() {
                Some(x) => req.rtol = x,
                None => return,
            },
            "--atol" => match num() {
                Some(x) => req.atol = x,
                None => return,
            },
            "--dt" => match num() {
                Some(x) => req.dt = Some(x),
                None => return,
            },
            "--points" => match value.parse::<usize>() {
                Ok(n) => req.points = n,
                Err(_) => return,
            },
            _ => {}
        }
    }
    // --t-end is required by the CLI
    let Some(t_end) = t_end else { return };
    req.t_end = t_end;
    if output != "csv" && output != "json" {
        return;
    }
    match run::method_by_name(method) {
        Ok(m) => req.method = m,
        Err(d) => {
            let _ = d.render("fuzz.qd", "");
            return;
        }
    }
    match set.map(output::parse_set).transpose() {
        Ok(s) => req.set = s.unwrap_or_default().into_iter().collect(),
        Err(d) => {
            let _ = d.render("fuzz.qd", "");
            return;
        }
    }
    match init.map(run::parse_init).transpose() {
        Ok(s) => req.init = s.unwrap_or_default(),
        Err(d) => {
            let _ = d.render("fuzz.qd", "");
            return;
        }
    }
    // as the CLI runs it: within the work budget
    let ctx = qdot::app::Context::new().with_max_terms(FUZZ_MAX_TERMS);
    match qdot::app::simulate(&ctx, scene, &req) {
        Ok(r) => {
            let _ = run::csv(&r);
            let _ = run::json(&r);
            let _ = run::stats_text(&r);
            let _ = run::status_word(&r.solution.status);
            if plot {
                let labels = qdot::simulate::plot::Labels::of_scene(scene, "fuzz.qd", &req);
                let _ = qdot::simulate::plot::svg(&r, &labels);
            }
        }
        Err(d) => {
            let _ = d.render("fuzz.qd", scene);
        }
    }
}

/// The most runs a `commands` input's sweep may ask for: the fuzzer's
/// time-out is per input, and the sweep's own bound (a million runs) is
/// tested in tests/hostile.
const MAX_FUZZ_SWEEP_RUNS: usize = 16;

/// Target `commands`: every command by its name in the application's
/// table (`app::Command::ALL`) with fuzzed options: each in the format
/// asked (with `--set`), the numeric studies and steady motions as the
/// `motions` target runs them, and the commands beside the table: `sweep` (its `--vary` axes, `--samples`,
/// `--threads`, `--stop-when`, CSV and JSON) and `codegen` (every
/// language and form, `--set`, `--function`, and a fuzzed file name,
/// which names the generated functions). The input is option lines, the
/// first `--command NAME`, then optionally `---` and the scene (the
/// pendulum without one):
///
/// ```text
/// --command sweep
/// --set m=1,g=9.81
/// --init theta'=0
/// --vary l=0.5:2:3
/// --t-end 1
/// ```
pub fn commands(data: &[u8]) {
    let Some((o, scene)) = OptionLines::with_scene(data) else {
        return;
    };
    match o.one("--command") {
        // as the CLI runs them: within the work budget
        Some("sweep") => {
            let _ = qdot::budget::within(FUZZ_MAX_TERMS, || sweep(scene, &o));
        }
        Some("codegen") => codegen(scene, &o),
        // the numeric studies and the steady motions: the `motions` target's
        Some("cycle" | "response" | "floquet" | "modes" | "equilibrium") => motions(data),
        // any other command of the application's table
        Some(name) => {
            if let Some(cmd) = Command::from_name(name) {
                scene_command(cmd, scene, o.one("--format"), o.one("--set"))
            }
        }
        None => {}
    }
}

/// `--name value` lines, as a command line gives them.
struct OptionLines<'a>(Vec<(&'a str, &'a str)>);

impl<'a> OptionLines<'a> {
    /// A `commands`/`motions` input: the option lines, then `---` and the
    /// scene (the pendulum without one); `None` when it is not UTF-8.
    fn with_scene(data: &'a [u8]) -> Option<(OptionLines<'a>, &'a str)> {
        let text = std::str::from_utf8(data).ok()?;
        let (opts, scene) = text.split_once("\n---\n").unwrap_or((text, PENDULUM));
        Some((OptionLines::read(opts), scene))
    }

    fn read(text: &'a str) -> OptionLines<'a> {
        OptionLines(
            text.lines()
                .map(|line| {
                    let line = line.trim();
                    match line.split_once(char::is_whitespace) {
                        Some((k, v)) => (k, v.trim()),
                        None => (line, ""),
                    }
                })
                .collect(),
        )
    }

    /// The first value of `key`.
    fn one(&self, key: &str) -> Option<&'a str> {
        self.0.iter().find(|(k, _)| *k == key).map(|(_, v)| *v)
    }

    /// Every value of a repeated `key`, in order.
    fn all(&self, key: &str) -> Vec<String> {
        self.0
            .iter()
            .filter(|(k, _)| *k == key)
            .map(|(_, v)| v.to_string())
            .collect()
    }

    fn number<T: std::str::FromStr>(&self, key: &str) -> Option<T> {
        self.one(key).and_then(|v| v.parse().ok())
    }
}

/// `qdot COMMAND --format FORMAT [--set …]` on `src`.
fn scene_command(cmd: Command, src: &str, format: Option<&str>, set: Option<&str>) {
    let fmt = format.and_then(Format::from_name).unwrap_or(Format::Text);
    let mut opts = CommandOptions {
        max_terms: FUZZ_MAX_TERMS,
        ..CommandOptions::default()
    };
    if let Some(set) = set {
        match output::parse_set_any_sign(set) {
            Ok(s) => opts.set = s,
            Err(d) => {
                let _ = d.render("--set", set);
                return;
            }
        }
    }
    run_rendered(cmd, src, fmt, &opts);
}

/// `qdot sweep` as the CLI runs it (its design bounded for the fuzzer).
fn sweep(src: &str, o: &OptionLines) {
    use qdot::simulate::sweep::{self as sw, Design};
    let mut req = run::Request {
        max_steps: FUZZ_MAX_STEPS,
        t_end: o.number("--t-end").unwrap_or(1.0),
        stop_when: o.one("--stop-when").map(String::from),
        ..Default::default()
    };
    if let Some(p) = o.number("--points") {
        req.points = p;
    }
    let parsed = (|| -> Result<_, qdot::Diagnostic> {
        req.method = run::method_by_name(o.one("--method").unwrap_or("dop853"))?;
        req.set = o
            .one("--set")
            .map(output::parse_set_any_sign)
            .transpose()?
            .unwrap_or_default();
        req.init = o
            .one("--init")
            .map(run::parse_init)
            .transpose()?
            .unwrap_or_default();
        let axes = o
            .all("--vary")
            .iter()
            .map(|v| sw::parse_axis(v))
            .collect::<Result<Vec<_>, _>>()?;
        let design = match o.number("--samples") {
            Some(samples) => Design::Random {
                samples,
                seed: o.number("--seed").unwrap_or(0),
            },
            None => Design::Grid,
        };
        Ok((axes, design))
    })();
    let (axes, design) = match parsed {
        Ok(x) => x,
        Err(d) => {
            let _ = d.render("fuzz.qd", "");
            return;
        }
    };
    let threads = o.number("--threads").unwrap_or(0);
    let result = run::Prepared::new(src, &[]).and_then(|p| {
        if sw::design_points(&axes, design)?.len() > MAX_FUZZ_SWEEP_RUNS {
            return Ok(None);
        }
        sw::sweep(&p, &req, &axes, design, threads, &|_| {}).map(Some)
    });
    match result {
        Ok(Some(s)) => {
            let _ = sw::csv(&s);
            let _ = sw::json(&s);
        }
        Ok(None) => {}
        Err(d) => {
            let _ = d.render("fuzz.qd", src);
        }
    }
}

/// `qdot codegen` as the CLI runs it, the file name fuzzed too.
fn codegen(src: &str, o: &OptionLines) {
    use qdot::simulate::codegen::{CodegenRequest, Form, Lang};
    let lang = match o.one("--lang") {
        Some("rust") => Lang::Rust,
        Some("python") => Lang::Python,
        Some("julia") => Lang::Julia,
        _ => Lang::C,
    };
    let mut req = CodegenRequest::new(o.one("--file").unwrap_or("fuzz.qd"), lang);
    if o.one("--form") == Some("mass-matrix") {
        req.form = Form::MassMatrix;
    }
    req.functions = o.all("--function");
    if let Some(b) = o.number("--baumgarte") {
        req.baumgarte = b;
    }
    match o.one("--set").map(output::parse_set_any_sign).transpose() {
        Ok(s) => req.set = s.unwrap_or_default(),
        Err(d) => {
            let _ = d.render("fuzz.qd", "");
            return;
        }
    }
    let ctx = qdot::app::Context::new().with_max_terms(FUZZ_MAX_TERMS);
    if let Err(d) = qdot::app::codegen(&ctx, src, &req) {
        let _ = d.render("fuzz.qd", src);
    }
}

/// The most positions, frequencies or grid points a `motions` input may
/// ask of `cycle`, `response --over` and `floquet --over`: each point is a
/// numeric solve or a monodromy integration, and the fuzzer's time-out is
/// per input; the commands' own bounds (a million) are tested in
/// tests/hostile.
const MAX_FUZZ_POINTS: usize = 12;

/// Target `motions`: the analyses of motion, with fuzzed options, through
/// the application layer as the CLI runs them ([`study`]): `cycle`
/// (`--over`, `--set`, `--guess`, `--columns`, every output and both
/// pictures), `response` (`--at`, `--set`, and `--over` with its plot),
/// `floquet` (`--at`, `--set`, `--function`, `--period`, `--over` with
/// its chart), and the steady
/// motions, `modes` (`--steady`, `--at`, `--init`, `--set`) and
/// `equilibrium` (`--steady`, `--set`), in every format. The layout is
/// the `commands` target's:
///
/// ```text
/// --command floquet
/// --set delta=0.5,eps=0.2,m=1,w=1
/// ---
/// coordinates x
/// …
/// ```
pub fn motions(data: &[u8]) {
    let Some((o, scene)) = OptionLines::with_scene(data) else {
        return;
    };
    let ctx = qdot::app::Context::new().with_max_terms(FUZZ_MAX_TERMS);
    let outcome = match o.one("--command") {
        Some("cycle") => ctx.within(|| study(Command::Cycle, scene, &o)),
        Some("response") => ctx.within(|| study(Command::Response, scene, &o)),
        Some("floquet") => ctx.within(|| study(Command::Floquet, scene, &o)),
        Some("modes") => {
            steady(Command::Modes, scene, &o);
            Ok(Ok(()))
        }
        Some("equilibrium") => {
            steady(Command::Equilibrium, scene, &o);
            Ok(Ok(()))
        }
        _ => Ok(Ok(())),
    };
    match outcome {
        Ok(Err(d)) => {
            let _ = d.render("fuzz.qd", scene);
        }
        Err(e) => {
            let _ = output::too_large(&e).render("fuzz.qd", scene);
        }
        Ok(Ok(())) => {}
    }
}

/// Values of `--set` (any sign, as the CLI reads them), empty without it.
fn set_values(o: &OptionLines) -> Result<qdot::solve::equilibrium::Values, qdot::Diagnostic> {
    Ok(o.one("--set")
        .map(output::parse_set_any_sign)
        .transpose()?
        .unwrap_or_default())
}

/// `qdot cycle`, `response` or `floquet` as the CLI runs it: the options
/// read into the application's, the study run by `app::run` (its points
/// bounded), written in every format the command writes, and its pictures
/// drawn.
fn study(cmd: Command, src: &str, o: &OptionLines) -> Result<(), qdot::Diagnostic> {
    let mut opts = CommandOptions {
        max_terms: FUZZ_MAX_TERMS,
        set: set_values(o)?,
        at: o.one("--at").map(String::from),
        functions: o.all("--function"),
        columns: o.one("--columns").map(qdot::simulate::cycle::column_names),
        ..CommandOptions::default()
    };
    if let Some(g) = o.one("--guess") {
        opts.guess = qdot::cycle::parse_guess(g)?;
    }
    if let Some(p) = o.one("--period") {
        match p.parse::<f64>() {
            Ok(p) => opts.period = Some(p),
            Err(_) => return Ok(()), // the CLI's parser refuses it
        }
    }
    // `cycle` needs a varied quantity; the others run without one
    let over = match (cmd, o.one("--over")) {
        (_, Some(text)) => Some(text),
        (Command::Cycle, None) => Some("t=0:1:3"),
        _ => None,
    };
    if let Some(text) = over {
        opts.over = qdot::app::parse_over(cmd, text)?;
    }
    if opts.over.iter().map(|a| a.count).product::<usize>() > MAX_FUZZ_POINTS {
        return Ok(());
    }
    let ctx = qdot::app::Context::new().with_max_terms(FUZZ_MAX_TERMS);
    let report = qdot::app::run(&ctx, cmd, src, &opts)?;
    for fmt in cmd.formats() {
        if let Err(d) = output::render(&report, *fmt) {
            let _ = d.render("fuzz.qd", src);
        }
    }
    match &report {
        qdot::AnyReport::Cycle(r) => {
            let run = &r.result;
            let _ = qdot::drawing::reaction_diagrams(&run.table, "fuzz", run.degrees);
            let _ = qdot::drawing::animation_svg(&run.table, "fuzz");
            let _ = qdot::drawing::animation_html(&run.table, "fuzz", run.degrees);
        }
        qdot::AnyReport::Response(r) => {
            if let qdot::app::FrequencyResponse::Swept(t) = &r.result {
                let _ = qdot::simulate::response_plot::svg(t, "fuzz");
            }
        }
        qdot::AnyReport::Floquet(r) if !r.result.axes.is_empty() => {
            let _ = qdot::drawing::floquet::svg(&r.result, "fuzz");
        }
        _ => {}
    }
    Ok(())
}

/// Whether a REPL entry's numeric command is bounded for the fuzzer: no
/// picture (it would write the fuzzer's disk), at most
/// [`MAX_FUZZ_POINTS`] points over its `--over`; `:simulate` and `:sweep`
/// are left to the `simulate` and `commands` targets, which bound their
/// steps and runs.
fn repl_entry_is_bounded(entry: &str) -> bool {
    let mut words = entry.split_whitespace();
    let study = match words.next() {
        Some(":simulate" | ":sweep") => return false,
        Some(":cycle") => Command::Cycle,
        Some(":response") => Command::Response,
        Some(":floquet") => Command::Floquet,
        _ => return true,
    };
    if entry.contains("--plot") || entry.contains("--animate") {
        return false;
    }
    let mut rest = entry.split("--over").skip(1);
    rest.all(|after| {
        let value = after.trim_start_matches([' ', '=']);
        let value = value.split_whitespace().next().unwrap_or("");
        let value = value.trim_matches(['"', '\'']);
        match qdot::app::parse_over(study, value) {
            Ok(axes) => axes.iter().map(|a| a.count).product::<usize>() <= MAX_FUZZ_POINTS,
            Err(_) => true,
        }
    })
}

/// `qdot modes` or `qdot equilibrium` with `--steady` (or without it),
/// `--at`, `--init` (modes) and `--set`, in the format asked (text by
/// default).
fn steady(cmd: Command, src: &str, o: &OptionLines) {
    let fmt = o
        .one("--format")
        .and_then(Format::from_name)
        .unwrap_or(Format::Text);
    let mut opts = CommandOptions {
        max_terms: FUZZ_MAX_TERMS,
        steady: o.one("--steady").map(String::from),
        ..CommandOptions::default()
    };
    if cmd == Command::Modes {
        opts.at = o.one("--at").map(String::from);
        opts.init = o.one("--init").map(String::from);
    }
    match set_values(o) {
        Ok(s) => opts.set = s,
        Err(d) => {
            let _ = d.render("--set", "");
            return;
        }
    }
    run_rendered(cmd, src, fmt, &opts);
}
