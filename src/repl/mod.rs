//! The REPL: a scene built line by line, with results on demand.
//!
//! [`Session`] is the engine, independent of any terminal: it takes one
//! complete *entry* at a time (a statement, several statements, a bare
//! expression or a `:command`) and answers with a [`Response`]. The scene
//! is kept as the list of its statements' texts, re-resolved by
//! [`Scene::parse`] after every change, so a statement that fails leaves
//! the session exactly as it was, `:scene` prints a file `qdot solve`
//! accepts, and `:undo` restores the previous list. The `qdot` binary puts
//! a line editor, history, completion and Ctrl-C around it.
//!
//! ```
//! use qdot::repl::Session;
//! let mut s = Session::new();
//! for line in ["coordinates x", "parameters m, k", "kinetic E = 1/2*m*x'^2",
//!              "potential V = 1/2*k*x^2"] {
//!     assert!(!s.execute(line).failed);
//! }
//! assert_eq!(s.execute("diff(E, x')").out, "m·x\u{307}\n"); // ẋ: x and a combining dot
//! assert!(s.execute(":solve").out.contains("= −k/m·x"));
//! ```

mod commands;
pub mod editing;
mod layout;
mod running;

pub use commands::{commands, ReplCommand};

use crate::diag::Diagnostic;
use crate::expr::latex::{self as tex, Names};
use crate::expr::print;
use crate::expr::Expr;
use crate::output::{self, Command, CommandOptions, Format};
use crate::parse::ast::{Builtin, Callee, ExprKind, Stmt};
use crate::scene::{Scene, Value};
use layout::Layout;

/// The label of the REPL's own input in error messages.
pub const INPUT: &str = "input";

/// What an entry produced: text for stdout, text for stderr (errors and
/// warnings, already rendered), whether it failed, and whether the user
/// asked to quit.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Response {
    /// For standard output.
    pub out: String,
    /// For standard error: errors and warnings, rendered.
    pub err: String,
    /// Whether the entry failed (the session is as it was).
    pub failed: bool,
    /// Whether the user asked to leave.
    pub quit: bool,
}

impl Response {
    /// Output only.
    pub fn out(s: impl Into<String>) -> Response {
        let mut out: String = s.into();
        if !out.is_empty() && !out.ends_with('\n') {
            out.push('\n');
        }
        Response {
            out,
            ..Response::default()
        }
    }
    fn error(s: impl Into<String>) -> Response {
        let mut err: String = s.into();
        if !err.ends_with('\n') {
            err.push('\n');
        }
        Response {
            err,
            failed: true,
            ..Response::default()
        }
    }
}

/// One statement of the scene, as the user wrote it.
#[derive(Clone, Debug, PartialEq)]
struct Statement {
    text: String,
    /// The name a definition or role statement gives a value to.
    defines: Option<String>,
}

/// The state the user can go back to with `:undo`.
#[derive(Clone, Debug)]
struct Snapshot {
    statements: Vec<Statement>,
    last: Option<Value>,
    /// What the change was, as `:undo` says it.
    what: String,
}

/// A REPL session: the scene so far, the last result, the output format.
#[derive(Clone, Debug)]
pub struct Session {
    statements: Vec<Statement>,
    scene: Scene,
    last: Option<Value>,
    /// The last command that printed a result (`:solve`, `:modes`, …) with
    /// its arguments, when it came after the last expression: what `:latex`
    /// typesets.
    last_command: Option<(Command, String)>,
    undo: Vec<Snapshot>,
    /// How results are printed (`:format`).
    pub format: Format,
    /// The work budget of every entry (`:max-terms`, `qdot --max-terms`).
    pub max_terms: usize,
    /// Where the entry being executed comes from, for error positions.
    origin: Origin,
    /// The last file `:load`ed: the name of generated code and pictures.
    source: Option<String>,
}

/// Where an entry comes from: the name errors give it and the line of that
/// source it starts on (a script piped in, a file loaded).
#[derive(Clone, Debug)]
struct Origin {
    name: String,
    first_line: usize,
}

impl Origin {
    fn typed() -> Origin {
        Origin {
            name: INPUT.to_string(),
            first_line: 1,
        }
    }
}

impl Default for Session {
    fn default() -> Self {
        Session::new()
    }
}

// The keywords, for completion and highlighting: the parser's list.
use crate::parse::keywords;

const HELP: &str = "\
Type statements as in a .qd file, one per line:
  coordinates y3, theta3        parameters G, g, r
  m = G/g                       kinetic E = 1/2*m*y3'^2
  forcefunction U = G*y3        solve a, T { … }  (over several lines)
A definition typed again replaces the earlier one.
Type an expression to see it simplified; `_` is the last result:
  diff(E, y3')   ∂E/∂ẏ₃          dt(x)            the total time derivative
  subs(E, x = 0, m = 2)           taylor(f, x, n)  or taylor(f, x = a, n);
  expand(f)      every term        series(f, x, n) when x is a coordinate
  factor(f)      over the rationals";

impl Session {
    /// An empty session.
    pub fn new() -> Session {
        Session {
            statements: Vec::new(),
            scene: Scene::default(),
            last: None,
            last_command: None,
            undo: Vec::new(),
            format: Format::Text,
            max_terms: crate::limits::DEFAULT_MAX_TERMS,
            origin: Origin::typed(),
            source: None,
        }
    }

    /// The scene so far.
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// The last result (`_`).
    pub fn last(&self) -> Option<&Value> {
        self.last.as_ref()
    }

    /// The names worth completing: coordinates (with `'`), parameters,
    /// definitions, `solve` unknowns.
    pub fn names(&self) -> Vec<String> {
        let s = &self.scene;
        let mut out: Vec<String> = s.coordinates.iter().map(|c| c.name.clone()).collect();
        out.extend(s.parameters.iter().map(|p| p.name.clone()));
        out.extend(s.definitions.iter().map(|d| d.name.clone()));
        out.extend(s.deferred.iter().map(|d| d.name.name.clone()));
        out.extend(
            s.systems
                .iter()
                .flat_map(|b| b.unknowns.iter().map(|u| u.name.clone())),
        );
        out
    }

    /// The scene as a `.qd` file.
    pub fn scene_text(&self) -> String {
        let mut out = String::from("# qdot scene, written by the REPL\n");
        for s in &self.statements {
            out.push_str(&s.text);
            out.push('\n');
        }
        out
    }

    /// Run one complete entry (see [`is_complete`]).
    pub fn execute(&mut self, entry: &str) -> Response {
        self.execute_from(entry, INPUT, 1)
    }

    /// [`execute`](Self::execute) an entry that starts at line `first_line`
    /// of the source `name` (a script read line by line): its errors point
    /// at that source's lines.
    pub fn execute_from(&mut self, entry: &str, name: &str, first_line: usize) -> Response {
        let outer = std::mem::replace(
            &mut self.origin,
            Origin {
                name: name.to_string(),
                first_line,
            },
        );
        let r = self.execute_bounded(entry);
        self.origin = outer;
        r
    }

    fn execute_bounded(&mut self, entry: &str) -> Response {
        let max_terms = self.max_terms;
        // an entry over budget changes nothing: statements are committed
        // only after the scene they make has been resolved
        // the scene as it stands orders the printed terms (a statement
        // that changes the coordinates prints nothing that depends on it)
        let ctx = crate::app::Context::new()
            .with_max_terms(max_terms)
            .for_scene(&self.scene);
        ctx.within(|| self.execute_unbounded(entry))
            .unwrap_or_else(|e| {
                let hint = format!(
                    "raise the limit with :max-terms {} (it is {})",
                    e.limit.saturating_mul(10),
                    e.limit
                );
                Response::error(
                    Diagnostic::global(e.message())
                        .with_hint(hint)
                        .with_kind(crate::diag::ErrorKind::TooLarge { measure: e.measure })
                        .render(&self.origin.name, ""),
                )
            })
    }

    fn execute_unbounded(&mut self, entry: &str) -> Response {
        let trimmed = entry.trim();
        if trimmed.is_empty() {
            return Response::default();
        }
        if let Some(cmd) = trimmed.strip_prefix(':') {
            return self.command(cmd);
        }
        if let Some(r) = self.bare_command(trimmed) {
            return r;
        }
        let expr_try = crate::parse::parse_expr(entry);
        match expr_try {
            Ok(e) => self.expression(entry, &e),
            Err(expr_err) => match crate::parse::parse_scene(entry) {
                Ok(stmts) => self.statements(entry, &stmts),
                Err(stmt_err) => {
                    let d = if looks_like_statement(entry) {
                        stmt_err
                    } else {
                        expr_err
                    };
                    Response::error(self.render(&d, entry))
                }
            },
        }
    }

    /// A command typed without its colon, when its word names nothing in
    /// the scene: `exit` and `quit` leave, `help` shows the commands, and a
    /// command's name alone or before options (`solve`, `modes --set …`)
    /// says to type the colon.
    fn bare_command(&mut self, entry: &str) -> Option<Response> {
        let (word, rest) = match entry.find(char::is_whitespace) {
            Some(i) => (&entry[..i], entry[i..].trim()),
            None => (entry, ""),
        };
        if !(rest.is_empty() || rest.starts_with("--")) || self.names().iter().any(|n| n == word) {
            return None;
        }
        match word {
            "exit" | "quit" if rest.is_empty() => {
                return Some(self.command("quit"));
            }
            "help" if rest.is_empty() => return Some(self.command("help")),
            _ => {}
        }
        let c = commands::find(word).filter(|c| c.name == word || word == "eq")?;
        Some(Response::error(format!(
            "error: `{word}` is a command: commands start with a colon\n  = hint: type `:{}{}{rest}`\n",
            c.name,
            if rest.is_empty() { "" } else { " " }
        )))
    }

    // ------------------------------------------------------------ statements

    fn statements(&mut self, entry: &str, stmts: &[Stmt]) -> Response {
        if stmts.is_empty() {
            return Response::default();
        }
        // `_` in a statement stands for the last result's value.
        if mentions_last(entry) {
            let Some(last) = &self.last else {
                return Response::error(
                    "error: `_` is the last result, and there is none yet\n  = hint: type an expression first\n",
                );
            };
            let replaced = replace_last(entry, &value_input(last));
            return match crate::parse::parse_scene(&replaced) {
                Ok(s) => self.statements(&replaced, &s),
                Err(d) => Response::error(self.render(&d, &replaced)),
            };
        }
        let mut list = self.statements.clone();
        // where each new statement sits in `list`, and its span in `entry`
        let mut placed: Vec<(usize, usize)> = Vec::new();
        let mut notes = String::new();
        for st in stmts {
            let span = st.span();
            let text = entry[span.start..span.end].trim_end().to_string();
            let defines = match st {
                Stmt::Def { name, .. } | Stmt::Role { name, .. } => Some(name.name.clone()),
                _ => None,
            };
            let previous = defines
                .as_ref()
                .and_then(|n| list.iter().position(|s| s.defines.as_ref() == Some(n)));
            let item = Statement { text, defines };
            match previous {
                Some(i) if !placed.iter().any(|&(j, _)| j == i) => {
                    notes.push_str(&format!(
                        "(replaces the earlier `{}`)\n",
                        list[i].text.lines().next().unwrap_or("")
                    ));
                    list[i] = item;
                    placed.push((i, span.start));
                }
                _ => {
                    list.push(item);
                    placed.push((list.len() - 1, span.start));
                }
            }
        }
        let (src, offsets) = join(&list);
        let scene = match Scene::parse(&src) {
            Ok(s) => s,
            Err(d) => return Response::error(self.locate(&d, &src, &offsets, &placed, entry)),
        };
        // a definition entered here is shown, so evaluated: its error
        // refuses it, though nothing in the scene uses it
        for st in stmts {
            if let Stmt::Def { name, .. } | Stmt::Role { name, .. } = st {
                if let Some(Err(d)) = scene.try_value(&name.name) {
                    return Response::error(self.locate(d, &src, &offsets, &placed, entry));
                }
            }
        }
        // show the warnings about the new statements only
        let mut err = String::new();
        for w in &scene.warnings {
            if let Some(span) = w.span {
                if let Some(d) = shift(w, span.start, &offsets, &placed) {
                    err.push_str(&self.render(&d, entry));
                }
            }
        }
        let first = |i: usize| list[i].text.lines().next().unwrap_or("").to_string();
        let what = match placed.as_slice() {
            [(i, _)] => format!("`{}`", first(*i)),
            [(i, _), ..] => format!("{} statements from `{}`", placed.len(), first(*i)),
            [] => "nothing".to_string(),
        };
        self.push_undo(what);
        self.statements = list;
        self.scene = scene;
        let mut out = notes;
        for st in stmts {
            if let Stmt::Def { name, .. } | Stmt::Role { name, .. } = st {
                if let Some(v) = self.scene.value(&name.name) {
                    out.push_str(&self.show_value(Some(&name.name), v, Layout::Plain));
                }
            }
        }
        Response {
            out,
            err,
            ..Response::default()
        }
    }

    /// A diagnostic of the whole scene, rendered against the entry when it
    /// points into one of the entry's statements.
    fn locate(
        &self,
        d: &Diagnostic,
        src: &str,
        offsets: &[usize],
        placed: &[(usize, usize)],
        entry: &str,
    ) -> String {
        match d.span {
            Some(span) => match shift(d, span.start, offsets, placed) {
                Some(e) => self.render(&e, entry),
                None => d.render("scene", src),
            },
            None => self.render(d, entry),
        }
    }

    /// `d` rendered against the entry, positioned in the entry's source.
    fn render(&self, d: &Diagnostic, entry: &str) -> String {
        match self.dot_hint(d) {
            Some(d) => d.render_from(&self.origin.name, entry, self.origin.first_line),
            None => d.render_from(&self.origin.name, entry, self.origin.first_line),
        }
    }

    /// `d` with a better hint when it is an unknown name written as a
    /// coordinate's derivative in words (`thetadot`, `xddot`): the prime.
    fn dot_hint(&self, d: &Diagnostic) -> Option<Diagnostic> {
        let crate::diag::ErrorKind::UnknownName { name } = d.kind() else {
            return None;
        };
        let (stem, primes) = [("ddot", "''"), ("dd", "''"), ("dot", "'"), ("d", "'")]
            .into_iter()
            .find_map(|(suffix, primes)| Some((name.strip_suffix(suffix)?, primes)))
            .filter(|(stem, _)| self.scene.coordinates.iter().any(|c| c.name == *stem))?;
        let mut d = d.clone();
        d.hint = Some(format!(
            "a time derivative is written with primes: `{stem}{primes}` (`{stem}'` the velocity, `{stem}''` the acceleration)"
        ));
        Some(d)
    }

    /// Remember the state before a change, `what` saying the change.
    fn push_undo(&mut self, what: String) {
        self.undo.push(Snapshot {
            statements: self.statements.clone(),
            last: self.last.clone(),
            what,
        });
    }

    // ------------------------------------------------------------ expressions

    fn expression(&mut self, entry: &str, e: &crate::parse::ast::Expr) -> Response {
        let extra: Vec<(&str, Value)> = self.last.iter().map(|v| ("_", v.clone())).collect();
        let (value, warnings) = match self.scene.evaluate(e, &extra) {
            Ok(x) => x,
            Err(d) => {
                let d = if d.message.starts_with("unknown name `_`") {
                    Diagnostic {
                        message: "`_` is the last result, and there is none yet".into(),
                        hint: Some("type an expression first".into()),
                        ..d
                    }
                } else {
                    d
                };
                return Response::error(self.render(&d, entry));
            }
        };
        let layout = self.layout(e, &extra);
        let out = self.show_value(None, &value, layout);
        let err: String = warnings.iter().map(|w| self.render(w, entry)).collect();
        self.push_undo(format!(
            "the result of `{}`",
            entry.trim().lines().next().unwrap_or("")
        ));
        self.last = Some(value);
        self.last_command = None;
        Response {
            out,
            err,
            ..Response::default()
        }
    }

    /// The layout the outermost call asks for.
    fn layout(&self, e: &crate::parse::ast::Expr, extra: &[(&str, Value)]) -> Layout {
        let ExprKind::Call(Callee::Builtin(f, _), args) = &e.kind else {
            return Layout::Plain;
        };
        #[deny(
            clippy::wildcard_enum_match_arm,
            clippy::match_wildcard_for_single_variants
        )]
        match f {
            Builtin::Expand => Layout::Expanded,
            Builtin::Factor => Layout::Factored,
            Builtin::Taylor | Builtin::Series => self.series_layout(*f, args, extra),
            Builtin::Sin
            | Builtin::Cos
            | Builtin::Tan
            | Builtin::Sqrt
            | Builtin::Exp
            | Builtin::Ln
            | Builtin::Atan
            | Builtin::Asin
            | Builtin::Acos
            | Builtin::Dot
            | Builtin::Cross
            | Builtin::Norm
            | Builtin::Rot
            | Builtin::Axis
            | Builtin::Express
            | Builtin::Omega
            | Builtin::Inertia
            | Builtin::Parallel
            | Builtin::Diff
            | Builtin::Dt
            | Builtin::Subs => Layout::Plain,
        }
    }

    /// `taylor(f, x, n)` or `series(f, x = a, n)` shown as a series in x
    /// about its point; `series(k1, k2, k3)` of springs is a plain value.
    fn series_layout(
        &self,
        f: Builtin,
        args: &[crate::parse::ast::Expr],
        extra: &[(&str, Value)],
    ) -> Layout {
        if args.len() != 3 {
            return Layout::Plain;
        }
        let (x, a) = match &args[1].kind {
            ExprKind::Assign(x, a) => (&**x, Some(&**a)),
            _ => (&args[1], None),
        };
        let scalar = |x: &crate::parse::ast::Expr| match self.scene.evaluate(x, extra) {
            Ok((Value::Scalar(v), _)) => Some(v),
            _ => None,
        };
        let var = scalar(x).and_then(|v| v.as_var());
        let point = match a {
            Some(a) => scalar(a),
            None => Some(Expr::zero()),
        };
        let taylor = f == Builtin::Taylor
            || crate::scene::is_taylor_form(args, |n| {
                n == "t" || self.scene.coordinates.iter().any(|c| c.name == n)
            });
        match (var, point) {
            (Some(var), Some(point)) if taylor => Layout::Series { var, point },
            _ => Layout::Plain,
        }
    }

    fn names_tex(&self) -> Names {
        let mut n = Names::new();
        for l in &self.scene.latex_names {
            n.set(&l.name, &l.tex);
        }
        n
    }

    /// A value (with its name, for definitions) in the current format.
    fn show_value(&self, name: Option<&str>, v: &Value, layout: Layout) -> String {
        let layout = &layout;
        match self.format {
            // a value has no table: CSV shows it as text
            Format::Text | Format::Csv => {
                let body = match v {
                    Value::Scalar(e) => layout.text(e),
                    Value::Vector(c) => format!(
                        "[{}]",
                        c.iter()
                            .map(|e| layout.text(e))
                            .collect::<Vec<_>>()
                            .join(", ")
                    ),
                    Value::Rotation(r) => {
                        let rows: Vec<String> = r
                            .matrix()
                            .iter()
                            .map(|row| {
                                let c: Vec<String> = row.iter().map(|e| layout.text(e)).collect();
                                format!("[{}]", c.join(", "))
                            })
                            .collect();
                        format!("rotation [{}]", rows.join(", "))
                    }
                };
                match name {
                    Some(n) => format!("{} = {body}\n", print::pretty_name(n, 0)),
                    None => format!("{body}\n"),
                }
            }
            Format::Latex => {
                let names = self.names_tex();
                let body = match v {
                    Value::Scalar(e) => layout.latex(e, &names),
                    Value::Vector(c) => format!(
                        "\\begin{{pmatrix}} {} \\end{{pmatrix}}",
                        c.iter()
                            .map(|e| layout.latex(e, &names))
                            .collect::<Vec<_>>()
                            .join(" \\\\ ")
                    ),
                    Value::Rotation(r) => rotation_latex(r, |e| layout.latex(e, &names)),
                };
                match name {
                    Some(n) => format!("{} = {body}\n", names.symbol(n, 0)),
                    None => format!("{body}\n"),
                }
            }
            Format::Json => {
                use crate::output::wire::{ReplValueJson, ReplValueKindJson as Kind};
                let all = |es: &[Expr]| es.iter().map(print::input).collect();
                let value = match v {
                    Value::Scalar(e) => Kind::Scalar(print::input(e)),
                    Value::Vector(c) => Kind::Vector(all(c)),
                    Value::Rotation(r) => {
                        Kind::Matrix(r.matrix().iter().map(|row| all(row)).collect())
                    }
                };
                ReplValueJson {
                    name: name.map(str::to_string),
                    value,
                }
                .line()
            }
        }
    }

    // ------------------------------------------------------------ commands

    fn command(&mut self, cmd: &str) -> Response {
        let cmd = cmd.trim();
        let (name, args) = match cmd.find(char::is_whitespace) {
            Some(i) => (&cmd[..i], cmd[i..].trim()),
            None => (cmd, ""),
        };
        let entry = commands::find(name);
        if let Some(c) = &entry {
            match c.name {
                "simulate" => return self.simulate(c, args),
                "sweep" => return self.sweep(c, args),
                "codegen" => return self.codegen(c, args),
                _ => {}
            }
            if let Some(cmd) = repl_command(c.name) {
                return self.run_result(c, cmd, args);
            }
        }
        match name {
            "q" | "quit" | "exit" => Response {
                quit: true,
                ..Response::default()
            },
            "help" | "h" | "?" => Response::out(help_text()),
            "latex" => self.latex(args),
            "show" => self.show(args),
            "scene" => Response::out(self.scene_text()),
            "max-terms" => match args.replace(['_', ','], "").parse::<usize>() {
                Ok(n) if n > 0 => {
                    self.max_terms = n;
                    Response::out(format!("(at most {} terms per expression)", crate::budget::grouped(n)))
                }
                _ if args.is_empty() => Response::out(format!(
                    "at most {} terms per expression",
                    crate::budget::grouped(self.max_terms)
                )),
                _ => Response::error(format!(
                    "error: `:max-terms {args}` needs a whole number of terms\n  = hint: :max-terms 10000000\n"
                )),
            },
            "load" => self.load(args),
            "save" => self.save(args),
            "undo" => match self.undo.pop() {
                Some(s) => {
                    let (src, _) = join(&s.statements);
                    match Scene::parse(&src) {
                        Ok(scene) => {
                            self.scene = scene;
                            self.statements = s.statements;
                            self.last = s.last;
                            self.last_command = None;
                            Response::out(format!("(undone: {})", s.what))
                        }
                        Err(d) => Response::error(d.render("scene", &src)),
                    }
                }
                None => Response::error("error: nothing to undo"),
            },
            "reset" => {
                self.push_undo(":reset".to_string());
                self.statements.clear();
                self.scene = Scene::default();
                self.last = None;
                self.last_command = None;
                Response::out("(an empty scene; :undo brings the old one back)")
            }
            "format" => match Format::from_name(args) {
                Some(f) => self.set_format(f),
                None if args.is_empty() => {
                    Response::out(format!("the format is {}", self.format.name()))
                }
                None => Response::error(format!(
                    "error: unknown format `{args}`\n  = hint: :format {}\n",
                    Format::ALL.map(Format::name).join(", :format ")
                )),
            },
            _ => {
                let all = commands();
                let names = || all.iter().map(|c| c.name);
                let near = crate::spelling::nearest(name, names())
                    .or_else(|| names().find(|c| c.starts_with(name) && !name.is_empty()));
                let hint = match near {
                    Some(c) => format!("did you mean `:{c}`? :help lists the commands"),
                    None => ":help lists the commands".to_string(),
                };
                Response::error(format!(
                    "error: unknown command `:{name}`\n  = hint: {hint}\n"
                ))
            }
        }
    }

    fn set_format(&mut self, f: Format) -> Response {
        self.format = f;
        Response::out(format!("(results as {})", f.name()))
    }

    /// [`Session::run`], remembered as the last result when it succeeds
    /// and `:latex` can typeset it.
    fn run_result(&mut self, c: &ReplCommand, cmd: Command, args: &str) -> Response {
        let r = self.run(c, cmd, args);
        if r.err.is_empty() || !r.out.is_empty() {
            self.last_command = cmd
                .formats()
                .contains(&Format::Latex)
                .then(|| (cmd, args.to_string()));
        }
        r
    }

    fn latex(&self, args: &str) -> Response {
        if let ("" | "last", Some((cmd, opts))) = (args, &self.last_command) {
            return self.latex_of_command(*cmd, opts);
        }
        match (args, &self.last) {
            ("" | "last", Some(v)) => {
                let names = self.names_tex();
                Response::out(match v {
                    Value::Scalar(e) => tex::latex_with(e, &names),
                    Value::Vector(c) => format!(
                        "\\begin{{pmatrix}} {} \\end{{pmatrix}}",
                        c.iter()
                            .map(|e| tex::latex_with(e, &names))
                            .collect::<Vec<_>>()
                            .join(" \\\\ ")
                    ),
                    Value::Rotation(r) => rotation_latex(r, |e| tex::latex_with(e, &names)),
                })
            }
            ("last", None) => Response::error("error: there is no result yet"),
            ("" | "all" | "steps" | "derivation", _) => {
                let (src, _) = join(&self.statements);
                let opts = CommandOptions {
                    steps: args == "steps" || args == "derivation",
                    ..CommandOptions::default()
                };
                match output::run_with(Command::Latex, &src, Format::Latex, &opts) {
                    Ok((out, _)) => Response::out(out),
                    Err(d) => Response::error(d.render("scene", &src)),
                }
            }
            (other, _) => Response::error(format!(
                "error: `:latex {other}`: expected nothing, `steps` or `last`\n  = hint: :latex prints the last result (or the equations when there is none); :latex steps the whole derivation\n"
            )),
        }
    }

    /// The LaTeX of a command's result, with the options it was run with.
    fn latex_of_command(&self, cmd: Command, args: &str) -> Response {
        let Some(c) = commands()
            .into_iter()
            .find(|c| repl_command(c.name) == Some(cmd))
        else {
            return Response::error(format!("error: `:{}` has no LaTeX", cmd.name()));
        };
        let opts = match commands::parse(&c, args)
            .and_then(|o| commands::app_options(cmd, &o, self.max_terms))
        {
            Ok((opts, _)) => opts,
            Err(e) => return Response::error(e),
        };
        let (src, _) = join(&self.statements);
        match output::run_with(cmd, &src, Format::Latex, &opts) {
            Ok((out, _)) => Response::out(out),
            Err(d) => Response::error(d.render("scene", &src)),
        }
    }

    fn show(&self, name: &str) -> Response {
        if name.is_empty() {
            return Response::error("error: `:show` needs a name\n  = hint: :show E");
        }
        let s = &self.scene;
        if name == "_" {
            return match &self.last {
                Some(v) => Response::out(self.show_value(Some("_"), v, Layout::Plain)),
                None => Response::error("error: there is no result yet"),
            };
        }
        let definition = s.definitions.iter().find(|d| d.name == name);
        let found = definition
            .map(|d| (d.role, &d.value))
            .or_else(|| s.value(name).map(|v| (None, v)));
        if let Some((role, value)) = found {
            let role = role
                .map(|r| format!("{} ", r.keyword()))
                .unwrap_or_default();
            let text = self
                .statements
                .iter()
                .find(|st| st.defines.as_deref() == Some(name))
                .map(|st| format!("  (as written: {})\n", st.text))
                .unwrap_or_default();
            return Response::out(format!(
                "{role}{}{text}",
                self.show_value(Some(name), value, Layout::Plain)
            ));
        }
        if s.coordinates.iter().any(|c| c.name == name) {
            return Response::out(format!(
                "{name} is a generalized coordinate (a function of t; {name}' and {name}'' are its derivatives)"
            ));
        }
        if let Some(p) = s.parameters.iter().find(|p| p.name == name) {
            let dim = p
                .dimension
                .as_ref()
                .map(|d| format!(" ({d})"))
                .unwrap_or_default();
            return Response::out(format!("{name} is a parameter{dim}: a positive constant"));
        }
        if s.systems
            .iter()
            .any(|b| b.unknowns.iter().any(|u| u.name == name))
        {
            return Response::out(format!(
                "{name} is an unknown of a solve block (:solve finds it)"
            ));
        }
        Response::error(format!(
            "error: `{name}` is not in the scene\n  = hint: the names are {}\n",
            self.names().join(", ")
        ))
    }

    fn load(&mut self, path: &str) -> Response {
        if path.is_empty() {
            return Response::error(
                "error: `:load` needs a file\n  = hint: :load examples/seed_23_4.qd",
            );
        }
        let src = match crate::diag::read_source(path) {
            Ok(s) => s,
            Err(e) => return Response::error(e.to_string()),
        };
        let stmts = match crate::parse::parse_scene(&src) {
            Ok(s) => s,
            Err(d) => return Response::error(d.render(path, &src)),
        };
        let outer = std::mem::replace(
            &mut self.origin,
            Origin {
                name: path.to_string(),
                first_line: 1,
            },
        );
        let mut r = self.statements(&src, &stmts);
        self.origin = outer;
        if !r.failed {
            self.source = Some(path.to_string());
        }
        // the definitions of a whole file are not echoed
        if !r.failed {
            r.out = format!("(loaded {} statements from {path})\n", stmts.len());
        }
        r
    }

    fn save(&self, path: &str) -> Response {
        if path.is_empty() {
            return Response::error("error: `:save` needs a file\n  = hint: :save my_scene.qd");
        }
        match std::fs::write(path, self.scene_text()) {
            Ok(()) => Response::out(format!(
                "(saved {} statements to {path})",
                self.statements.len()
            )),
            Err(e) => Response::error(format!("error: cannot write `{path}`: {e}")),
        }
    }
}

/// The statements joined into one source, and where each starts.
fn join(list: &[Statement]) -> (String, Vec<usize>) {
    let mut src = String::new();
    let mut offsets = Vec::with_capacity(list.len());
    for s in list {
        offsets.push(src.len());
        src.push_str(&s.text);
        src.push('\n');
    }
    (src, offsets)
}

/// `d` moved from the joined source into the entry, when the offset falls
/// in one of the entry's new statements.
fn shift(
    d: &Diagnostic,
    at: usize,
    offsets: &[usize],
    placed: &[(usize, usize)],
) -> Option<Diagnostic> {
    let i = match offsets.binary_search(&at) {
        Ok(i) => i,
        Err(0) => return None,
        Err(i) => i - 1,
    };
    let &(_, entry_start) = placed.iter().find(|&&(j, _)| j == i)?;
    let span = d.span?;
    let delta = entry_start as isize - offsets[i] as isize;
    let mv = |x: usize| (x as isize + delta).max(0) as usize;
    let mut e = d.clone();
    e.span = Some(crate::parse::ast::Span::new(mv(span.start), mv(span.end)));
    // a second place in the same statement moves with it; one elsewhere in
    // the scene is not in the entry's text, which is all the entry shows
    let end = offsets.get(i + 1).copied().unwrap_or(usize::MAX);
    e.labels
        .retain(|l| (offsets[i]..end).contains(&l.span.start));
    for l in &mut e.labels {
        l.span = crate::parse::ast::Span::new(mv(l.span.start), mv(l.span.end));
    }
    Some(e)
}

/// The command a REPL command word runs through the application layer:
/// the CLI's name (`:latex` and `:check` are the REPL's own), or
/// `:equations`/`:eq` for `derive`.
fn repl_command(word: &str) -> Option<Command> {
    match word {
        "equations" | "eq" => Some(Command::Derive),
        // `:latex` typesets the last result
        _ => Command::from_name(word).filter(|c| *c != Command::Latex),
    }
}

fn help_text() -> String {
    let mut out = String::from(HELP);
    out.push_str("\nCommands:\n");
    for c in commands() {
        let head = if c.args.is_empty() {
            format!(":{}", c.name)
        } else {
            format!(":{} {}", c.name, c.args)
        };
        if head.chars().count() > 44 {
            // a long list of options: the description on a line of its own
            out.push_str(&format!("  {head}\n  {:<44} {}\n", "", c.about));
        } else {
            out.push_str(&format!("  {head:<44} {}\n", c.about));
        }
    }
    let functions: Vec<&str> = crate::parse::functions::names().collect();
    out.push_str(&format!("Functions: {}\n", functions.join(", ")));
    out
}

/// Whether an entry that parses neither way was meant as a statement: it
/// starts with a keyword or has `=` outside brackets.
fn looks_like_statement(entry: &str) -> bool {
    let first: String = entry
        .trim_start()
        .chars()
        .take_while(|c| c.is_alphanumeric() || *c == '_')
        .collect();
    if keywords::statement_keywords().any(|k| k == first) {
        return true;
    }
    // a misspelled keyword before a name (`solv a { … }`): a statement
    let rest = entry.trim_start()[first.len()..].trim_start();
    if rest.starts_with(|c: char| c.is_alphabetic() || c == '_')
        && keywords::suggest(&first).is_some()
    {
        return true;
    }
    let mut depth = 0i32;
    for c in entry.chars() {
        match c {
            '#' => break,
            '(' | '[' | '{' => depth += 1,
            ')' | ']' | '}' => depth -= 1,
            '=' if depth == 0 => return true,
            _ => {}
        }
    }
    false
}

/// The identifiers of `src` (outside comments and strings), with offsets.
fn idents(src: &str) -> Vec<(usize, &str)> {
    let mut out = Vec::new();
    let mut it = src.char_indices().peekable();
    while let Some((i, c)) = it.next() {
        if c == '#' {
            while it.peek().is_some_and(|&(_, c)| c != '\n') {
                it.next();
            }
        } else if c == '"' {
            while it.peek().is_some_and(|&(_, c)| c != '"' && c != '\n') {
                it.next();
            }
            it.next();
        } else if c.is_alphabetic() || c == '_' {
            let mut end = i + c.len_utf8();
            while let Some(&(j, d)) = it.peek() {
                if d.is_alphanumeric() || d == '_' {
                    end = j + d.len_utf8();
                    it.next();
                } else {
                    break;
                }
            }
            out.push((i, &src[i..end]));
        } else if c.is_ascii_digit() {
            // a number with its exponent and unit (`2e3`, `30deg`) is not a name
            while it
                .peek()
                .is_some_and(|&(_, d)| d.is_alphanumeric() || d == '.' || d == '_')
            {
                it.next();
            }
        }
    }
    out
}

fn mentions_last(src: &str) -> bool {
    idents(src).iter().any(|(_, w)| *w == "_")
}

/// `src` with every identifier `_` replaced by `(value)`.
fn replace_last(src: &str, value: &str) -> String {
    let mut out = String::with_capacity(src.len() + value.len());
    let mut prev = 0;
    for (i, w) in idents(src) {
        if w == "_" {
            out.push_str(&src[prev..i]);
            out.push('(');
            out.push_str(value);
            out.push(')');
            prev = i + 1;
        }
    }
    out.push_str(&src[prev..]);
    out
}

/// A value in input syntax (re-parses to the same value).
fn value_input(v: &Value) -> String {
    match v {
        Value::Scalar(e) => print::input(e),
        Value::Vector(c) => format!(
            "[{}]",
            c.iter().map(print::input).collect::<Vec<_>>().join(", ")
        ),
        Value::Rotation(r) => format!("({})", r.to_input()),
    }
}

/// A rotation's matrix as a LaTeX `pmatrix`.
fn rotation_latex(
    r: &crate::scene::Rotation,
    tex: impl Fn(&crate::expr::Expr) -> String,
) -> String {
    let rows: Vec<String> = r
        .matrix()
        .iter()
        .map(|row| row.iter().map(&tex).collect::<Vec<_>>().join(" & "))
        .collect();
    format!(
        "\\begin{{pmatrix}} {} \\end{{pmatrix}}",
        rows.join(" \\\\ ")
    )
}

/// Whether `text` is a whole entry, or the user is still typing one: an
/// open `(`, `[` or `{`, or a line ending in a binary operator, `,` or `=`,
/// asks for another line.
pub fn is_complete(text: &str) -> bool {
    let mut depth = 0i32;
    let mut last = ' ';
    for line in text.lines() {
        let mut in_str = false;
        for c in line.chars() {
            if in_str {
                if c == '"' {
                    in_str = false;
                }
                continue;
            }
            match c {
                '#' => break,
                '"' => in_str = true,
                '(' | '[' | '{' => depth += 1,
                ')' | ']' | '}' => depth -= 1,
                _ => {}
            }
            if !c.is_whitespace() {
                last = c;
            }
        }
    }
    if text.trim_start().starts_with(':') {
        return true;
    }
    depth <= 0 && !matches!(last, '+' | '-' | '*' | '/' | '^' | ',' | '=')
}
