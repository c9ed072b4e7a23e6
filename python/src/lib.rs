//! `qdot._native`: the thin layer between Python and the qdot library.
//!
//! Everything crosses as strings, numbers and bytes: the commands' JSON and
//! LaTeX (the public contracts of the command line), the simulation's rows
//! as little-endian f64 bytes (NumPy reads them without a copy per value),
//! and SymPy source text for `.to_sympy()`. The Python package (`qdot/`)
//! builds its classes on these functions.

use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict};
use qdot::app::{self, Context};
use qdot::engine::algebra::sign::Values;
use qdot::output::{self, CommandOptions, Format};
use qdot::simulate::run::{self, Request};
use qdot::Diagnostic;

mod to_sympy;

create_exception!(
    _native,
    QdotError,
    PyException,
    "An error of qdot: the message, and the positioned diagnostic (line:column, a caret, a hint) as qdot prints it."
);

/// The exception for a diagnostic about `src`: `str(e)` is the diagnostic as
/// qdot prints it; `e.kind` (the name `--format json` gives it:
/// `"unknown_name"`, …), `e.message`, `e.hint`, `e.line`, `e.column`
/// (1-based; 0 when it has no position).
fn error(d: &Diagnostic, file: &str, src: &str) -> PyErr {
    let (line, column) = match d.span {
        Some(s) => Diagnostic::line_col(src, s.start),
        None => (0, 0),
    };
    let mut d = d.clone();
    d.hint = d.hint.as_deref().map(python_hint);
    let d = &d;
    let err = QdotError::new_err(d.render(file, src).trim_end().to_string());
    Python::attach(|py| {
        let value = err.value(py);
        // setting attributes on a fresh exception object cannot fail
        let _ = value.setattr("kind", d.kind().name());
        let _ = value.setattr("message", d.message.clone());
        let _ = value.setattr("hint", d.hint.clone());
        let _ = value.setattr("line", line);
        let _ = value.setattr("column", column);
    });
    err
}

/// A hint in Python's terms: the command line's options become the
/// keyword arguments of the same name (`--set m=1,g=9.81` is
/// `set={"m": 1, "g": 9.81}`, `--at x=0` is `at="x=0"`, `--dt 0.01` is
/// `dt=0.01`, `--expand` is `structure="expanded"`).
fn python_hint(hint: &str) -> String {
    let mut out = String::with_capacity(hint.len());
    let mut rest = hint;
    while let Some(i) = rest.find("--") {
        let before = &rest[..i];
        let after = &rest[i + 2..];
        out.push_str(before);
        let len = after
            .find(|c: char| !(c.is_ascii_lowercase() || c == '-'))
            .unwrap_or(after.len());
        let starts_word = before.is_empty() || before.ends_with([' ', '`', '(', '"']);
        if len == 0 || !starts_word {
            out.push_str("--");
            rest = after;
            continue;
        }
        let name = &after[..len];
        let tail = &after[len..];
        // an argument: the next word when it assigns (`m=1,g=9.81`)
        let arg = tail.strip_prefix(' ').map(|t| {
            let end = t
                .find(|c: char| c.is_whitespace() || c == '`' || c == ')')
                .unwrap_or(t.len());
            &t[..end]
        });
        let arg = arg.filter(|a| a.contains('=') || a.parse::<f64>().is_ok());
        let dict = |a: &str| {
            let items: Vec<String> = a
                .split(',')
                .map(|item| match item.split_once('=') {
                    Some((k, v)) => format!("\"{k}\": {v}"),
                    None => item.to_string(),
                })
                .collect();
            format!("{{{}}}", items.join(", "))
        };
        let keyword = name.replace('-', "_");
        out.push_str(&match (name, arg) {
            ("expand", _) => "structure=\"expanded\"".to_string(),
            ("structured", _) => "structure=\"structured\"".to_string(),
            ("set" | "init" | "guess", Some(a)) => format!("{keyword}={}", dict(a)),
            ("set" | "init" | "guess", None) => format!("{keyword}={{…}}"),
            (_, Some(a)) if a.parse::<f64>().is_ok() => format!("{keyword}={a}"),
            (_, Some(a)) => format!("{keyword}=\"{a}\""),
            (_, None) => keyword,
        });
        rest = match arg {
            Some(a) => &tail[1 + a.len()..],
            None => tail,
        };
    }
    out.push_str(rest);
    out
}

/// The context of a call: the work budget of exact computation
/// (`max_terms`, 0: the default), as the command line runs every command:
/// an expression that grows past it is an error, not a hang.
fn context(max_terms: usize) -> Context {
    Context::new().with_max_terms(max_terms)
}

fn values(pairs: Vec<(String, f64)>) -> Values {
    pairs.into_iter().collect()
}

fn command_by_name(name: &str) -> PyResult<output::Command> {
    output::Command::from_name(name)
        .ok_or_else(|| pyo3::exceptions::PyValueError::new_err(format!("unknown command `{name}`")))
}

/// `structure` of `derive` and `solve`: "auto" (the default: through
/// named intermediates when the expanded results would be large),
/// "expanded" (`--expand`) or "structured" (`--structured`).
fn structure_by_name(name: &str) -> PyResult<app::Structure> {
    match name {
        "auto" => Ok(app::Structure::Auto),
        "expanded" => Ok(app::Structure::Expanded),
        "structured" => Ok(app::Structure::Kept),
        _ => Err(pyo3::exceptions::PyValueError::new_err(format!(
            "unknown structure `{name}`: auto, expanded or structured"
        ))),
    }
}

/// The options of a command (the CLI's flags) as the application's.
#[allow(clippy::too_many_arguments)]
fn command_options(
    cmd: output::Command,
    set: Vec<(String, f64)>,
    at: Option<String>,
    init: Option<String>,
    steady: Option<String>,
    steps: bool,
    standalone: bool,
    title: String,
    max_terms: usize,
    structure: &str,
    keep: Vec<String>,
    study: StudyOptions,
) -> PyResult<CommandOptions> {
    let over = match &study.over {
        Some(text) => app::parse_over(cmd, text).map_err(|d| error(&d, "over", text))?,
        None => Vec::new(),
    };
    Ok(CommandOptions {
        set: values(set),
        at,
        init,
        steady,
        steps,
        standalone,
        title,
        max_terms,
        structure: structure_by_name(structure)?,
        keep,
        over,
        guess: study.guess,
        columns: study.columns,
        functions: study.functions,
        period: study.period,
        max_steps: study.max_steps,
        threads: study.threads,
        // simulate, sweep and codegen have calls of their own (`simulate`,
        // `sweep`, `codegen` below), with their options
        ..CommandOptions::default()
    })
}

/// The options of the numeric studies (`cycle`, `response`, `floquet`).
#[derive(Default)]
struct StudyOptions {
    over: Option<String>,
    guess: Vec<(String, f64)>,
    columns: Option<Vec<String>>,
    functions: Vec<String>,
    period: Option<f64>,
    max_steps: Option<usize>,
    /// `floquet --threads`: 0 is one per core (`qdot::app::thread_count`).
    threads: usize,
}

fn format_by_name(name: &str) -> PyResult<Format> {
    Format::from_name(name).ok_or_else(|| {
        let all: Vec<&str> = Format::ALL.iter().map(|f| f.name()).collect();
        pyo3::exceptions::PyValueError::new_err(format!(
            "unknown format `{name}`: {}",
            all.join(", ")
        ))
    })
}

/// The commands of the application layer (`app::Command::ALL`), each
/// with the formats it writes: the table `qdot.run_command` reads.
#[pyfunction]
fn commands() -> Vec<(&'static str, Vec<&'static str>)> {
    output::Command::ALL
        .iter()
        .map(|c| (c.name(), c.formats().iter().map(|f| f.name()).collect()))
        .collect()
}

/// Run a command of the CLI on a scene once and write it in each of
/// `formats`: (the outputs, warnings rendered). The options are the
/// CLI's; `over` its `--over` text.
#[pyfunction]
#[pyo3(signature = (command, source, formats, file="<scene>", set=Vec::new(), at=None, init=None, steady=None, steps=false, standalone=false, title=String::new(), max_terms=0, structure="auto", keep=Vec::new(), over=None, guess=Vec::new(), columns=None, functions=Vec::new(), period=None, max_steps=None, threads=0))]
#[allow(clippy::too_many_arguments)]
fn run_report(
    py: Python<'_>,
    command: &str,
    source: &str,
    formats: Vec<String>,
    file: &str,
    set: Vec<(String, f64)>,
    at: Option<String>,
    init: Option<String>,
    steady: Option<String>,
    steps: bool,
    standalone: bool,
    title: String,
    max_terms: usize,
    structure: &str,
    keep: Vec<String>,
    over: Option<String>,
    guess: Vec<(String, f64)>,
    columns: Option<Vec<String>>,
    functions: Vec<String>,
    period: Option<f64>,
    max_steps: Option<usize>,
    threads: usize,
) -> PyResult<(Vec<String>, Vec<String>)> {
    let cmd = command_by_name(command)?;
    let fmts = formats
        .iter()
        .map(|f| format_by_name(f))
        .collect::<PyResult<Vec<_>>>()?;
    let study = StudyOptions {
        over,
        guess,
        columns,
        functions,
        period,
        max_steps,
        threads,
    };
    let opts = command_options(
        cmd, set, at, init, steady, steps, standalone, title, max_terms, structure, keep, study,
    )?;
    let result = py.detach(|| {
        let report = app::run(&context(max_terms), cmd, source, &opts)?;
        let outs = fmts
            .iter()
            .map(|f| output::render(&report, *f))
            .collect::<Result<Vec<_>, _>>()?;
        Ok::<_, Diagnostic>((outs, report.warnings().to_vec()))
    });
    match result {
        Ok((outs, warnings)) => Ok((
            outs,
            warnings.iter().map(|w| w.render(file, source)).collect(),
        )),
        Err(d) => Err(error(&d, file, source)),
    }
}

/// Run a command of the CLI on a scene: (output, warnings rendered).
#[pyfunction]
#[pyo3(signature = (command, source, format, file="<scene>", set=Vec::new(), at=None, init=None, steady=None, steps=false, standalone=false, title=String::new(), max_terms=0, structure="auto", keep=Vec::new()))]
#[allow(clippy::too_many_arguments)]
fn run_command(
    py: Python<'_>,
    command: &str,
    source: &str,
    format: &str,
    file: &str,
    set: Vec<(String, f64)>,
    at: Option<String>,
    init: Option<String>,
    steady: Option<String>,
    steps: bool,
    standalone: bool,
    title: String,
    max_terms: usize,
    structure: &str,
    keep: Vec<String>,
) -> PyResult<(String, Vec<String>)> {
    let cmd = command_by_name(command)?;
    let fmt = format_by_name(format)?;
    let opts = command_options(
        cmd,
        set,
        at,
        init,
        steady,
        steps,
        standalone,
        title,
        max_terms,
        structure,
        keep,
        StudyOptions::default(),
    )?;
    let result = py.detach(|| output::run_with(cmd, source, fmt, &opts));
    match result {
        Ok((out, warnings)) => Ok((
            out,
            warnings.iter().map(|w| w.render(file, source)).collect(),
        )),
        Err(d) => Err(error(&d, file, source)),
    }
}

/// Parse and resolve a scene; a QdotError for the first problem. Its
/// names, each with what qdot assumes of it (for `.to_sympy()`'s
/// Symbols): `"coordinate"`, `"parameter"` (positive) or `"real
/// parameter"` (`assume e real`: either sign, or 0).
#[pyfunction]
#[pyo3(signature = (source, file="<scene>", max_terms=0))]
fn check_scene(
    py: Python<'_>,
    source: &str,
    file: &str,
    max_terms: usize,
) -> PyResult<Vec<(String, &'static str)>> {
    py.detach(|| context(max_terms).run(|| qdot::Scene::parse(source).map(|s| names(&s))))
        .map_err(|d| error(&d, file, source))
}

/// A scene's coordinates and parameters, each with its kind (see
/// [`check_scene`]); read where the scene's atoms were made.
fn names(scene: &qdot::Scene) -> Vec<(String, &'static str)> {
    let coordinates = scene
        .coordinates
        .iter()
        .map(|c| (c.name.clone(), "coordinate"));
    let parameters = scene.parameters.iter().map(|p| {
        let real = scene
            .assumptions
            .real
            .contains(&qdot::expr::atom::param(&p.name));
        (
            p.name.clone(),
            if real { "real parameter" } else { "parameter" },
        )
    });
    coordinates.chain(parameters).collect()
}

/// `name=value,…` as (name, value) pairs: `kind` "set" (parameters, any
/// sign), "guess" (coordinates, `30deg` and `pi` allowed, as `cycle
/// --guess`) or "init" (coordinates and velocities, `q'`).
#[pyfunction]
fn parse_values(text: &str, kind: &str) -> PyResult<Vec<(String, f64)>> {
    let parsed = match kind {
        "set" => output::parse_set_any_sign(text).map(|v| v.into_iter().collect()),
        "guess" => qdot::cycle::parse_guess(text),
        _ => run::parse_init(text).map(|v| v.into_iter().collect()),
    };
    parsed.map_err(|d| error(&d, kind, text))
}

/// A simulation: a dict with `columns` (list of names), `data` (bytes of
/// little-endian f64, row-major), `rows`, `status`, `t_reached`, `stats`,
/// `method`, `evaluator`, `seconds`, `compile_seconds`.
#[pyfunction]
#[pyo3(signature = (source, set, init, t_end, method="dop853", rtol=1e-8, atol=1e-10, dt=None, points=101, max_steps=qdot::limits::DEFAULT_MAX_STEPS, stop_when=None, functions=Vec::new(), baumgarte=1.0, file="<scene>", max_terms=0))]
#[allow(clippy::too_many_arguments)]
fn simulate<'py>(
    py: Python<'py>,
    source: &str,
    set: Vec<(String, f64)>,
    init: Vec<(String, f64)>,
    t_end: f64,
    method: &str,
    rtol: f64,
    atol: f64,
    dt: Option<f64>,
    points: usize,
    max_steps: usize,
    stop_when: Option<String>,
    functions: Vec<String>,
    baumgarte: f64,
    file: &str,
    max_terms: usize,
) -> PyResult<Bound<'py, PyDict>> {
    let method = run::method_by_name(method).map_err(|d| error(&d, file, ""))?;
    let req = Request {
        set: values(set),
        init: values(init),
        t_end,
        method,
        rtol,
        atol,
        dt,
        points,
        max_steps,
        stop_when,
        functions,
        baumgarte,
        ..Request::default()
    };
    let r = py
        .detach(|| app::simulate(&context(max_terms), source, &req))
        .map_err(|d| error(&d, file, source))?;
    let mut bytes = Vec::with_capacity(r.rows.len() * r.columns.len() * 8);
    for row in &r.rows {
        for x in row {
            bytes.extend_from_slice(&x.to_le_bytes());
        }
    }
    let d = PyDict::new(py);
    d.set_item("columns", &r.columns)?;
    // the columns are t, every q, every q', …: the q are those before the first primed name
    let n = r
        .columns
        .iter()
        .skip(1)
        .take_while(|c| !c.ends_with('\''))
        .count();
    d.set_item("coordinates", &r.columns[1..1 + n])?;
    d.set_item("rows", r.rows.len())?;
    d.set_item("data", PyBytes::new(py, &bytes))?;
    d.set_item("status", run::status_word(&r.solution.status))?;
    d.set_item("method", run::method_name(r.method))?;
    d.set_item("evaluator", r.evaluator.evaluator.name())?;
    d.set_item("seconds", r.seconds)?;
    d.set_item("compile_seconds", r.compile_seconds)?;
    let s = &r.solution.stats;
    let stats = PyDict::new(py);
    stats.set_item("steps", s.steps)?;
    stats.set_item("rejected", s.rejected)?;
    stats.set_item("rhs_evals", s.rhs_evals)?;
    stats.set_item("jacobians", s.jacobians)?;
    stats.set_item("factorizations", s.factorizations)?;
    d.set_item("stats", stats)?;
    d.set_item("csv", run::csv(&r))?;
    Ok(d)
}

/// A sweep (`qdot sweep`): `axes` as (name, from, to, count); `samples`
/// (with `seed`) for random points instead of a grid. A dict with `names`,
/// `coordinates`, `values` and `summary` (bytes of f64, row-major: the
/// varied values; the final t, q, q̇, max |q|, energy drift (NaN when not
/// conserved) and steps), `status` (a list of words or error messages),
/// `seconds`, `threads`, `compilations`.
#[pyfunction]
#[pyo3(signature = (source, set, init, axes, t_end, samples=None, seed=0, threads=0, method="dop853", rtol=1e-8, atol=1e-10, dt=None, points=101, stop_when=None, file="<scene>", max_terms=0))]
#[allow(clippy::too_many_arguments)]
fn sweep<'py>(
    py: Python<'py>,
    source: &str,
    set: Vec<(String, f64)>,
    init: Vec<(String, f64)>,
    axes: Vec<(String, f64, f64, usize)>,
    t_end: f64,
    samples: Option<usize>,
    seed: u64,
    threads: usize,
    method: &str,
    rtol: f64,
    atol: f64,
    dt: Option<f64>,
    points: usize,
    stop_when: Option<String>,
    file: &str,
    max_terms: usize,
) -> PyResult<Bound<'py, PyDict>> {
    use qdot::simulate::sweep::{Axis, Design};
    let method = run::method_by_name(method).map_err(|d| error(&d, file, ""))?;
    let base = Request {
        set: values(set),
        init: values(init),
        t_end,
        method,
        rtol,
        atol,
        dt,
        points,
        stop_when,
        ..Request::default()
    };
    let axes: Vec<Axis> = axes
        .into_iter()
        .map(|(name, from, to, count)| Axis {
            name,
            from,
            to,
            count,
        })
        .collect();
    let design = match samples {
        Some(samples) => Design::Random { samples, seed },
        None => Design::Grid,
    };
    let s = py
        .detach(|| {
            app::sweep(
                &context(max_terms),
                source,
                &base,
                &axes,
                design,
                threads,
                &|_| {},
            )
        })
        .map_err(|d| error(&d, file, source))?;
    let n = s.coordinates.len();
    let mut bytes = Vec::new();
    let mut status = Vec::with_capacity(s.runs.len());
    for (vals, outcome) in &s.runs {
        let mut row: Vec<f64> = vals.clone();
        match outcome {
            Ok(o) => {
                row.push(o.t);
                row.extend_from_slice(&o.y);
                row.extend_from_slice(&o.max_abs_q);
                row.push(o.energy_drift.unwrap_or(f64::NAN));
                row.push(o.steps as f64);
                status.push(run::status_word(&o.status).to_string());
            }
            Err(m) => {
                row.extend(std::iter::repeat_n(f64::NAN, 3 + 3 * n));
                status.push(format!("error: {m}"));
            }
        }
        for x in row {
            bytes.extend_from_slice(&x.to_le_bytes());
        }
    }
    let d = PyDict::new(py);
    d.set_item("names", &s.names)?;
    d.set_item("coordinates", &s.coordinates)?;
    d.set_item("runs", s.runs.len())?;
    d.set_item("summary", PyBytes::new(py, &bytes))?;
    d.set_item("status", status)?;
    d.set_item("seconds", s.seconds)?;
    d.set_item("threads", s.threads)?;
    d.set_item("compilations", s.compilations)?;
    Ok(d)
}

/// A mechanism's cycle (`qdot cycle`), kept for its pictures, with its
/// CSV and JSON as the CLI writes them.
#[pyclass(frozen)]
struct CycleTable {
    run: app::CycleRun,
    csv: String,
    json: String,
}

#[pymethods]
impl CycleTable {
    /// The reaction diagrams as SVG text (`cycle --plot`).
    fn reaction_diagrams(&self, title: &str) -> PyResult<String> {
        qdot::drawing::reaction_diagrams(&self.run.table, title, self.run.degrees).map_err(|e| {
            let d = Diagnostic::global(format!("cannot draw the reaction diagrams: {e}"));
            error(&d, "<plot>", "")
        })
    }

    /// The mechanism moving through its cycle (`cycle --animate`): a
    /// self-contained HTML page, or an animated SVG when `svg`.
    fn animation(&self, title: &str, svg: bool) -> String {
        if svg {
            qdot::drawing::animation_svg(&self.run.table, title)
        } else {
            qdot::drawing::animation_html(&self.run.table, title, self.run.degrees)
        }
    }

    /// The table as `cycle --output csv` prints it.
    fn csv(&self) -> String {
        self.csv.clone()
    }

    /// The table as `cycle --output json` prints it.
    fn json(&self) -> String {
        self.json.clone()
    }
}

/// A mechanism over its cycle (`qdot cycle`): `over` as `--over`
/// (`phi=0:360deg:73`), `columns` as `--columns` (the columns shown after
/// the varied one; None: all). A dict with `varied`, `degrees` (the varied
/// quantity is an angle, its column in radians), `columns`, `rows`,
/// `data` (bytes of little-endian f64, row-major, NaN where a value is not
/// determined), `notes` (a str or None per row), `iterations` and `table`
/// (a [`CycleTable`], for the pictures).
#[pyfunction]
#[pyo3(signature = (source, over, set, guess=Vec::new(), file="<scene>", max_terms=0, columns=None))]
#[allow(clippy::too_many_arguments)]
fn cycle<'py>(
    py: Python<'py>,
    source: &str,
    over: &str,
    set: Vec<(String, f64)>,
    guess: Vec<(String, f64)>,
    file: &str,
    max_terms: usize,
    columns: Option<Vec<String>>,
) -> PyResult<Bound<'py, PyDict>> {
    let cmd = output::Command::Cycle;
    let opts = CommandOptions {
        over: app::parse_over(cmd, over).map_err(|d| error(&d, "over", over))?,
        set: values(set),
        guess,
        columns,
        max_terms,
        ..CommandOptions::default()
    };
    let ctx = context(max_terms);
    let (r, csv, json) = py
        .detach(|| {
            let report = app::run(&ctx, cmd, source, &opts)?;
            let csv = output::render(&report, Format::Csv)?;
            let json = output::render(&report, Format::Json)?;
            match report {
                app::AnyReport::Cycle(r) => Ok((r.result, csv, json)),
                _ => Err(Diagnostic::global("`cycle` gave another command's report")),
            }
        })
        .map_err(|d| error(&d, file, source))?;
    let t = r.shown();
    let mut bytes = Vec::with_capacity(t.rows.len() * t.columns.len() * 8);
    for row in &t.rows {
        for x in &row.values {
            bytes.extend_from_slice(&x.unwrap_or(f64::NAN).to_le_bytes());
        }
    }
    let d = PyDict::new(py);
    d.set_item("varied", &t.varied)?;
    d.set_item("degrees", r.degrees)?;
    d.set_item("columns", &t.columns)?;
    d.set_item("rows", t.rows.len())?;
    d.set_item("data", PyBytes::new(py, &bytes))?;
    let notes: Vec<Option<&str>> = t.rows.iter().map(|r| r.note.as_deref()).collect();
    d.set_item("notes", notes)?;
    let iterations: Vec<u32> = t.rows.iter().map(|r| r.iterations).collect();
    d.set_item("iterations", iterations)?;
    d.set_item("table", CycleTable { run: r, csv, json })?;
    Ok(d)
}

/// SymPy source text of an expression written in qdot's syntax (as the
/// JSON output writes it), for `qdot/_sympy.py` to evaluate.
#[pyfunction]
fn sympy_source(expr: &str) -> PyResult<String> {
    let ast = qdot::parse::parse_expr(expr).map_err(|d| error(&d, "<expression>", expr))?;
    to_sympy::of(&ast).map_err(|m| error(&Diagnostic::global(m), "<expression>", expr))
}

/// The LaTeX of each expression (qdot's syntax) in the scene's notation
/// (`latex` names of the scene, dots for time derivatives). The
/// expressions may mention the named intermediates `intermediates` (the
/// names of a result's `"intermediates"`), written as qdot writes them
/// (`B2_{13}`, `\omega_{B2,x}`, a prime per `_dot`).
#[pyfunction]
#[pyo3(signature = (source, exprs, file="<scene>", max_terms=0, intermediates=Vec::new()))]
fn latex_exprs(
    source: &str,
    exprs: Vec<String>,
    file: &str,
    max_terms: usize,
    intermediates: Vec<String>,
) -> PyResult<Vec<String>> {
    let ctx = context(max_terms);
    let scene = ctx
        .run(|| qdot::Scene::parse(source))
        .map_err(|d| error(&d, file, source))?;
    let mut names = qdot::expr::latex::Names::new();
    for n in &scene.latex_names {
        names.set(&n.name, &n.tex);
    }
    let bound: Vec<(&str, qdot::Value)> = intermediates
        .iter()
        .map(|n| (n.as_str(), qdot::Value::Scalar(intermediate(n))))
        .collect();
    // in the scene's context: its budget, its coordinates' order
    let ctx = ctx.for_scene(&scene);
    exprs
        .iter()
        .map(|text| {
            ctx.run(|| {
                let ast = qdot::parse::parse_expr(text)?;
                match scene.evaluate(&ast, &bound)?.0 {
                    qdot::Value::Scalar(e) => Ok(qdot::expr::latex::latex_with(&e, &names)),
                    v => Err(Diagnostic::global(format!(
                        "expected a number, found {}",
                        v.describe()
                    ))),
                }
            })
            .map_err(|d| error(&d, "<expression>", text))
        })
        .collect()
}

/// A stand-in atom for the intermediate called `input` in a result's JSON
/// (`P1_x`, its rate `P1_x_dot`, `_ddot`, `_d3`): printed as qdot prints
/// the intermediate; outside every tape (tapes are numbered from 1).
fn intermediate(input: &str) -> qdot::Expr {
    use qdot::expr::atom::{self, NamedAtom};
    let (name, order) = intermediate_order(input);
    qdot::Expr::var(atom::named(NamedAtom {
        name: name.into(),
        order,
        tape: 0,
        highest: None,
        moving: true,
    }))
}

/// `input` as (name, order of time derivative): the inverse of
/// `qdot::expr::tape::input_name`.
fn intermediate_order(input: &str) -> (&str, u32) {
    if let Some(base) = input.strip_suffix("_ddot") {
        return (base, 2);
    }
    if let Some(base) = input.strip_suffix("_dot") {
        return (base, 1);
    }
    if let Some((base, k)) = input.rsplit_once("_d") {
        if let Ok(k) = k.parse::<u32>() {
            if k >= 3 && !base.is_empty() {
                return (base, k);
            }
        }
    }
    (input, 0)
}

/// A figure's title for the scene `source`: its first comment's first
/// phrase, as the command line titles its pictures (`None` without one).
#[pyfunction]
fn scene_title(source: &str) -> Option<String> {
    qdot::simulate::plot::scene_title(source)
}

/// The version of the qdot library inside.
#[pyfunction]
fn version() -> &'static str {
    env!("CARGO_PKG_VERSION")
}

#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("QdotError", m.py().get_type::<QdotError>())?;
    m.add_function(wrap_pyfunction!(run_command, m)?)?;
    m.add_function(wrap_pyfunction!(scene_title, m)?)?;
    m.add_function(wrap_pyfunction!(run_report, m)?)?;
    m.add_function(wrap_pyfunction!(commands, m)?)?;
    m.add_function(wrap_pyfunction!(check_scene, m)?)?;
    m.add_function(wrap_pyfunction!(parse_values, m)?)?;
    m.add_function(wrap_pyfunction!(simulate, m)?)?;
    m.add_function(wrap_pyfunction!(sympy_source, m)?)?;
    m.add_function(wrap_pyfunction!(latex_exprs, m)?)?;
    m.add_function(wrap_pyfunction!(sweep, m)?)?;
    m.add_function(wrap_pyfunction!(cycle, m)?)?;
    m.add_class::<CycleTable>()?;
    m.add_function(wrap_pyfunction!(version, m)?)?;
    Ok(())
}
