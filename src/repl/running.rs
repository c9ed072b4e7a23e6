//! The REPL's commands that run on the scene: the application's commands
//! (rendered by [`output::render`] in the session's format), and
//! `:simulate`, `:sweep`, `:codegen`.

use super::commands::{self, number, option_error, Options, ReplCommand};
use super::{join, Response, Session};
use crate::app::{self, AnyReport, Command, Context, Format};
use crate::diag::Diagnostic;
use crate::output;
use crate::simulate::{codegen, run, sweep};

impl Session {
    /// The name pictures, generated code and plots take: the last file
    /// `:load`ed, else `scene`.
    fn source_name(&self) -> &str {
        self.source.as_deref().unwrap_or("scene")
    }

    /// The context of a command: the session's budget.
    fn context(&self) -> Context {
        Context::new().with_max_terms(self.max_terms)
    }

    /// An application command with the options in `args`.
    pub(super) fn run(&self, c: &ReplCommand, cmd: Command, args: &str) -> Response {
        let parsed = match commands::parse(c, args) {
            Ok(o) => o,
            Err(e) => return Response::error(e),
        };
        let (opts, asked) = match commands::app_options(cmd, &parsed, self.max_terms) {
            Ok(x) => x,
            Err(e) => return Response::error(e),
        };
        // the session's format is a preference: a command that does not
        // write it writes text
        let fmt = asked.unwrap_or(if cmd.formats().contains(&self.format) {
            self.format
        } else {
            Format::Text
        });
        let (src, _) = join(&self.statements);
        let report = match app::run(&self.context(), cmd, &src, &opts) {
            Ok(r) => r,
            Err(d) => return Response::error(d.render("scene", &src)),
        };
        let notes = match self.pictures(&report, &parsed) {
            Ok(n) => n,
            Err(e) => return Response::error(e),
        };
        match output::render(&report, fmt) {
            Ok(out) => {
                let err: String = report
                    .warnings()
                    .iter()
                    .map(|w| w.render("scene", &src))
                    .collect();
                let mut out = if out.ends_with('\n') || out.is_empty() {
                    out
                } else {
                    out + "\n"
                };
                out.push_str(&notes);
                Response {
                    out,
                    err,
                    ..Response::default()
                }
            }
            Err(d) => Response::error(d.render("scene", &src)),
        }
    }

    /// `--plot` and `--animate` without the pictures built in.
    #[cfg(not(feature = "drawing"))]
    fn pictures(&self, _: &AnyReport, o: &Options) -> Result<String, String> {
        match o.get("plot").or(o.get("animate")) {
            Some(_) => Err(NO_PICTURES.to_string()),
            None => Ok(String::new()),
        }
    }

    /// `--plot` and `--animate` of the numeric studies, written to their
    /// files; what was written, one line each.
    #[cfg(feature = "drawing")]
    fn pictures(&self, report: &AnyReport, o: &Options) -> Result<String, String> {
        let title = base_name(self.source_name());
        let mut written = Vec::new();
        let cannot = |what: &str, e: &dyn std::fmt::Display| format!("error: cannot {what}: {e}\n");
        if let Some(path) = o.get("plot") {
            let svg = match report {
                AnyReport::Cycle(r) => {
                    crate::drawing::reaction_diagrams(&r.result.table, &title, r.result.degrees)
                        .map_err(|e| cannot("draw the reaction diagrams", &e))?
                }
                AnyReport::Response(r) => match &r.result {
                    app::FrequencyResponse::Swept(t) => {
                        crate::simulate::response_plot::svg(t, &title)
                            .map_err(|e| cannot("draw the response", &e))?
                    }
                    app::FrequencyResponse::Exact(_) => String::new(),
                },
                AnyReport::Floquet(r) => crate::drawing::floquet::svg(&r.result, &title)
                    .map_err(|e| cannot("draw the chart", &e))?,
                _ => String::new(),
            };
            if !svg.is_empty() {
                write(path, &svg)?;
                written.push(path);
            }
        }
        if let (Some(path), AnyReport::Cycle(r)) = (o.get("animate"), report) {
            let page = if path.ends_with(".svg") {
                crate::drawing::animation_svg(&r.result.table, &title)
            } else {
                crate::drawing::animation_html(&r.result.table, &title, r.result.degrees)
            };
            write(path, &page)?;
            written.push(path);
        }
        Ok(written.iter().map(|p| format!("(wrote {p})\n")).collect())
    }

    /// `:simulate`: the scene integrated (`qdot simulate`'s options).
    pub(super) fn simulate(&self, c: &ReplCommand, args: &str) -> Response {
        let parsed = match commands::parse(c, args) {
            Ok(o) => o,
            Err(e) => return Response::error(e),
        };
        let mut req = run::Request::default();
        let json = match self.request(&parsed, &mut req) {
            Ok(j) => j,
            Err(e) => return Response::error(e),
        };
        if parsed.get("t-end").is_none() {
            return Response::error(
                "error: `:simulate` needs --t-end\n  = hint: the final time: :simulate --t-end 10\n",
            );
        }
        let plot = parsed.get("plot");
        if plot.is_some() {
            req.plot_samples = PLOT_SAMPLES;
        }
        let (src, _) = join(&self.statements);
        let r = match app::simulate(&self.context(), &src, &req) {
            Ok(r) => r,
            Err(d) => return Response::error(d.render("scene", &src)),
        };
        let mut err = String::new();
        let coordinates = r.columns.iter().filter_map(|c| c.strip_suffix('\''));
        if let Some(note) = run::zero_velocities_note(coordinates, |v| req.init.contains_key(v)) {
            err.push_str(&note);
            err.push('\n');
        }
        let mut out = if json { run::json(&r) } else { run::csv(&r) };
        if let Some(path) = plot {
            match self.simulation_plot(&src, &r, &req, path) {
                Ok(()) => out.push_str(&format!("(wrote {path})\n")),
                Err(e) => return Response::error(e),
            }
        }
        use crate::simulate::Status;
        let stopped = match r.solution.status {
            Status::Done | Status::Event { .. } => None,
            Status::TooManySteps { t } => Some((t, format!("raise --max-steps (it is {}), loosen --rtol and --atol, or use --method radau5 if the problem is stiff", req.max_steps))),
            Status::StepTooSmall { t } => Some((t, "the solution may blow up there; check the scene and the initial values, or loosen the tolerances".to_string())),
            Status::NotFinite { t } => Some((t, r.not_finite_reason())),
        };
        if let Some((t, hint)) = &stopped {
            let d = Diagnostic::global(format!(
                "the integration stopped early: {} at t = {t:.6e}",
                run::status_word(&r.solution.status),
            ))
            .with_hint(hint.clone())
            .with_kind(crate::diag::ErrorKind::Integration);
            err.push_str(&d.render("scene", ""));
        }
        Response {
            out,
            err,
            failed: stopped.is_some(),
            ..Response::default()
        }
    }

    /// `:simulate --plot`: the motion drawn to `path`.
    #[cfg(feature = "drawing")]
    fn simulation_plot(
        &self,
        src: &str,
        r: &run::Run,
        req: &run::Request,
        path: &str,
    ) -> Result<(), String> {
        let labels = crate::simulate::plot::Labels::of_scene(src, self.source_name(), req);
        let svg = crate::simulate::plot::svg(r, &labels)
            .map_err(|e| format!("error: cannot draw the plot: {e}\n"))?;
        write(path, &svg)
    }

    #[cfg(not(feature = "drawing"))]
    fn simulation_plot(
        &self,
        _: &str,
        _: &run::Run,
        _: &run::Request,
        _: &str,
    ) -> Result<(), String> {
        Err(NO_PICTURES.to_string())
    }

    /// The simulation request of `:simulate` or `:sweep` from its options;
    /// whether the output is JSON (`--output`, else the session's format).
    fn request(&self, o: &Options, req: &mut run::Request) -> Result<bool, String> {
        let mut json = self.format == Format::Json;
        for (k, v) in &o.pairs {
            let err = |d: Diagnostic| option_error(k, v, &d);
            match k.as_str() {
                "set" => req.set = output::parse_set_any_sign(v).map_err(err)?,
                "init" => req.init = run::parse_init(v).map_err(err)?,
                "t-end" => req.t_end = number(k, v)?,
                "method" => req.method = run::method_by_name(v).map_err(err)?,
                "rtol" => req.rtol = number(k, v)?,
                "atol" => req.atol = number(k, v)?,
                "dt" => req.dt = Some(number(k, v)?),
                "points" => req.points = number(k, v)?,
                "max-steps" => req.max_steps = number(k, v)?,
                "evaluator" => {
                    req.engine = crate::simulate::compile::Engine::by_name(v).ok_or_else(|| {
                        format!("error: unknown evaluator `{v}`\n  = hint: --evaluator auto, jit (machine code) or interpreter\n")
                    })?
                }
                "stop-when" => req.stop_when = Some(v.clone()),
                "function" => req.functions.push(v.clone()),
                "baumgarte" => req.baumgarte = number(k, v)?,
                "output" => {
                    json = match v.as_str() {
                        "json" => true,
                        "csv" => false,
                        _ => {
                            return Err(format!(
                                "error: unknown output `{v}`\n  = hint: --output csv or --output json\n"
                            ))
                        }
                    }
                }
                _ => {}
            }
        }
        Ok(json)
    }

    /// `:sweep`: many simulations, one summary row each.
    pub(super) fn sweep(&self, c: &ReplCommand, args: &str) -> Response {
        let parsed = match commands::parse(c, args) {
            Ok(o) => o,
            Err(e) => return Response::error(e),
        };
        let mut base = run::Request::default();
        let json = match self.request(&parsed, &mut base) {
            Ok(j) => j,
            Err(e) => return Response::error(e),
        };
        let mut axes = Vec::new();
        for v in parsed.all("vary") {
            match sweep::parse_axis(&v) {
                Ok(a) => axes.push(a),
                Err(d) => return Response::error(option_error("vary", &v, &d)),
            }
        }
        if axes.is_empty() || parsed.get("t-end").is_none() {
            return Response::error(
                "error: `:sweep` needs --vary and --t-end\n  = hint: :sweep --vary \"l=0.5:2:16\" --t-end 10\n",
            );
        }
        let numbers = (|| -> Result<_, String> {
            let seed = match parsed.get("seed") {
                Some(v) => number("seed", v)?,
                None => 0,
            };
            let threads = match parsed.get("threads") {
                Some(v) => number("threads", v)?,
                None => 0,
            };
            let design = match parsed.get("samples") {
                Some(v) => sweep::Design::Random {
                    samples: number("samples", v)?,
                    seed,
                },
                None => sweep::Design::Grid,
            };
            Ok((design, threads))
        })();
        let (design, threads) = match numbers {
            Ok(x) => x,
            Err(e) => return Response::error(e),
        };
        let (src, _) = join(&self.statements);
        let s = match app::sweep(
            &self.context(),
            &src,
            &base,
            &axes,
            design,
            threads,
            &|_| {},
        ) {
            Ok(s) => s,
            Err(d) => return Response::error(d.render("scene", &src)),
        };
        let mut err = String::new();
        let given = |v: &str| base.init.contains_key(v) || axes.iter().any(|a| a.name == v);
        if let Some(note) =
            run::zero_velocities_note(s.coordinates.iter().map(String::as_str), given)
        {
            err.push_str(&note);
            err.push('\n');
        }
        let failed = s.runs.iter().filter(|(_, r)| r.is_err()).count();
        if failed > 0 {
            let w = Diagnostic::global_warning(format!(
                "{failed} of {} runs failed (their rows say why)",
                s.runs.len()
            ));
            err.push_str(&w.render("scene", ""));
        }
        Response {
            out: if json {
                sweep::json(&s)
            } else {
                sweep::csv(&s)
            },
            err,
            ..Response::default()
        }
    }

    /// `:codegen`: the equations as C, Rust, Python or Julia source.
    pub(super) fn codegen(&self, c: &ReplCommand, args: &str) -> Response {
        let parsed = match commands::parse(c, args) {
            Ok(o) => o,
            Err(e) => return Response::error(e),
        };
        let req = match self.codegen_request(&parsed) {
            Ok(r) => r,
            Err(e) => return Response::error(e),
        };
        let (src, _) = join(&self.statements);
        match app::codegen(&self.context(), &src, &req) {
            Ok(code) => Response::out(code),
            Err(d) => Response::error(d.render("scene", &src)),
        }
    }

    fn codegen_request(&self, o: &Options) -> Result<codegen::CodegenRequest, String> {
        use codegen::{Form, Lang};
        let langs = [Lang::C, Lang::Rust, Lang::Python, Lang::Julia];
        let Some(name) = o.get("lang") else {
            return Err(
                "error: `:codegen` needs --lang\n  = hint: --lang c, rust, python or julia\n"
                    .into(),
            );
        };
        let Some(lang) = langs.into_iter().find(|l| l.name() == name) else {
            return Err(format!(
                "error: unknown language `{name}`\n  = hint: --lang c, rust, python or julia\n"
            ));
        };
        let mut req = codegen::CodegenRequest::new(self.source_name(), lang);
        for (k, v) in &o.pairs {
            match k.as_str() {
                "form" => {
                    req.form = [Form::Accelerations, Form::MassMatrix]
                        .into_iter()
                        .find(|f| f.name() == v)
                        .ok_or_else(|| {
                            format!("error: unknown form `{v}`\n  = hint: --form accelerations or --form mass-matrix\n")
                        })?
                }
                "set" => {
                    req.set = output::parse_set_any_sign(v).map_err(|d| option_error(k, v, &d))?
                }
                "function" => req.functions.push(v.clone()),
                "baumgarte" => req.baumgarte = number(k, v)?,
                _ => {}
            }
        }
        Ok(req)
    }
}

/// The samples of a `:simulate --plot` (the CLI's).
#[cfg(feature = "drawing")]
const PLOT_SAMPLES: usize = crate::simulate::plot::SAMPLES;
#[cfg(not(feature = "drawing"))]
const PLOT_SAMPLES: usize = 0;

/// The refusal of a picture in a build without them.
#[cfg(not(feature = "drawing"))]
const NO_PICTURES: &str = "error: this build of qdot draws no pictures\n  = hint: use the qdot command line, or build with the `drawing` feature\n";

/// A file's name without its folders and extension (a picture's title).
#[cfg_attr(not(feature = "drawing"), allow(dead_code))]
fn base_name(file: &str) -> String {
    std::path::Path::new(file)
        .file_stem()
        .and_then(|s| s.to_str())
        .unwrap_or(file)
        .to_string()
}

/// A picture written to `path`.
#[cfg_attr(not(feature = "drawing"), allow(dead_code))]
fn write(path: &str, text: &str) -> Result<(), String> {
    std::fs::write(path, text).map_err(|e| format!("error: cannot write `{path}`: {e}\n"))
}
