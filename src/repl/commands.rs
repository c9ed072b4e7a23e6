//! The REPL's commands: one table, built from the application layer's
//! ([`Command::ALL`]) and the REPL's own, with each command's options;
//! the reading of `--name value` options after a command word.

use crate::app::{Command, CommandOptions, Format};
use crate::diag::Diagnostic;

/// A REPL command: `:name`, its arguments as `:help` shows them, what it
/// does, and the option names it takes (`--name value`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ReplCommand {
    /// The word after `:`.
    pub name: &'static str,
    /// The arguments, as `:help` shows them.
    pub args: &'static str,
    /// What it does.
    pub about: &'static str,
    /// The options it takes, without `--`.
    pub options: &'static [&'static str],
}

const fn cmd(
    name: &'static str,
    args: &'static str,
    about: &'static str,
    options: &'static [&'static str],
) -> ReplCommand {
    ReplCommand {
        name,
        args,
        about,
        options,
    }
}

/// The integration options `:simulate` and `:sweep` share (as the CLI's).
const INTEGRATION: [&str; 8] = [
    "t-end",
    "method",
    "rtol",
    "atol",
    "dt",
    "points",
    "max-steps",
    "evaluator",
];

const SIMULATE_OPTIONS: [&str; 15] = [
    "set",
    "init",
    INTEGRATION[0],
    INTEGRATION[1],
    INTEGRATION[2],
    INTEGRATION[3],
    INTEGRATION[4],
    INTEGRATION[5],
    INTEGRATION[6],
    INTEGRATION[7],
    "stop-when",
    "function",
    "baumgarte",
    "output",
    "plot",
];

const SWEEP_OPTIONS: [&str; 16] = [
    "set",
    "init",
    "vary",
    "samples",
    "seed",
    "threads",
    INTEGRATION[0],
    INTEGRATION[1],
    INTEGRATION[2],
    INTEGRATION[3],
    INTEGRATION[4],
    INTEGRATION[5],
    INTEGRATION[6],
    INTEGRATION[7],
    "stop-when",
    "output",
];

/// The REPL's entry for an application command.
fn of_app(c: Command) -> ReplCommand {
    match c {
        Command::Derive => cmd(
            "equations",
            "",
            "Lagrange's equations, the mass matrix and the forcing",
            &[],
        ),
        Command::Solve => cmd(
            "solve",
            "",
            "the exact accelerations and the solve blocks' solutions",
            &[],
        ),
        Command::Forces => cmd("forces", "", "the generalized forces Q_k", &[]),
        Command::Hamilton => cmd(
            "hamilton",
            "",
            "the momenta, H(q, p, t) and Hamilton's equations",
            &[],
        ),
        Command::Integrals => cmd(
            "integrals",
            "",
            "cyclic coordinates, the energy integral, Routh's function",
            &[],
        ),
        Command::Equilibrium => cmd(
            "equilibrium",
            "[--set m=1,g=9.81] [--steady q,…]",
            "the equilibria (or steady motions) and their stability",
            &["set", "steady"],
        ),
        Command::Modes => cmd(
            "modes",
            "[--at q=…] [--steady q,…] [--init q=…,q'=…] [--set …]",
            "small oscillations: frequencies and modes",
            &["set", "at", "init", "steady"],
        ),
        Command::Latex => cmd(
            "latex",
            "[steps]",
            "LaTeX of the last result (an expression, or the last :solve, :modes, :equilibrium, …), or of the whole derivation",
            &[],
        ),
        Command::Check => cmd(
            "check",
            "",
            "the dimension of every name and result",
            &[],
        ),
        Command::Cycle => cmd(
            "cycle",
            "--over phi=0:360deg:73 [--set …] [--guess q=…] [--columns …] [--output F] [--plot F.svg] [--animate F.html]",
            "a planar mechanism over its cycle: positions, velocities, accelerations, reactions",
            &["over", "set", "guess", "columns", "output", "plot", "animate"],
        ),
        Command::Response => cmd(
            "response",
            "[--at q=…] [--set …] [--over Omega=FROM:TO:COUNT] [--output F] [--plot F.svg]",
            "the frequency response to the harmonic load: exact, or swept over Omega",
            &["at", "set", "over", "output", "plot"],
        ),
        Command::Floquet => cmd(
            "floquet",
            "[--at q=…] [--set …] [--function s=…] [--period T] [--max-steps N] [--over …] [--threads N] [--output F] [--plot F.svg]",
            "Floquet multipliers and stability about a motion, at a point or over parameters",
            &["at", "set", "function", "period", "max-steps", "over", "threads", "output", "plot"],
        ),
        #[allow(unreachable_patterns)] // a command the REPL does not describe yet
        _ => cmd(c.name(), "", "", &[]),
    }
}

/// The REPL's own commands (after the application's).
const OWN: &[ReplCommand] = &[
    cmd(
        "simulate",
        "--t-end T [--set …] [--init q=…] [--method M] [--output csv|json] [--plot F.svg] …",
        "integrate the equations numerically",
        &SIMULATE_OPTIONS,
    ),
    cmd(
        "sweep",
        "--vary NAME=FROM:TO:COUNT --t-end T [--samples N] [--set …] [--output csv|json] …",
        "many simulations over a grid or random points, one summary row each",
        &SWEEP_OPTIONS,
    ),
    cmd(
        "codegen",
        "--lang c|rust|python|julia [--form accelerations|mass-matrix] [--set …] [--function s=…]",
        "source code for the equations of motion",
        &["lang", "form", "set", "function", "baumgarte"],
    ),
    cmd(
        "show",
        "NAME",
        "what a name is: its value, role or declaration",
        &[],
    ),
    cmd("scene", "", "the scene so far, as a .qd file", &[]),
    cmd("load", "FILE", "run a .qd file's statements", &[]),
    cmd("save", "FILE", "write the scene to a .qd file", &[]),
    cmd("undo", "", "take back the last change", &[]),
    cmd("reset", "", "start from an empty scene", &[]),
    cmd(
        "format",
        "text|latex|json|csv",
        "how results are printed",
        &[],
    ),
    cmd(
        "max-terms",
        "N",
        "the work budget: the most terms an expression may reach",
        &[],
    ),
    cmd("help", "", "this list", &[]),
    cmd("quit", "", "leave (Ctrl-D does too)", &[]),
];

/// Every REPL command, for `:help`, completion and did-you-mean: the
/// application's commands in [`Command::ALL`]'s order, then the REPL's own.
pub fn commands() -> Vec<ReplCommand> {
    let mut out: Vec<ReplCommand> = Command::ALL
        .into_iter()
        .map(|c| {
            let entry = of_app(c);
            // a REPL entry of the same name says more
            OWN.iter()
                .find(|o| o.name == entry.name)
                .copied()
                .unwrap_or(entry)
        })
        .collect();
    for o in OWN {
        if !out.iter().any(|c| c.name == o.name) {
            out.push(*o);
        }
    }
    out
}

/// The command called `name` (without `:`), or an application command by
/// its CLI name (`:derive`, `:eq` for `:equations`).
pub fn find(name: &str) -> Option<ReplCommand> {
    let name = if name == "eq" { "equations" } else { name };
    let all = commands();
    all.iter().find(|c| c.name == name).copied().or_else(|| {
        let entry = of_app(Command::from_name(name)?);
        all.into_iter().find(|c| c.name == entry.name)
    })
}

/// A command's options as written: `--name value` or `--name=value`,
/// values quoted with `"…"` when they hold spaces.
#[derive(Clone, Debug, Default)]
pub(super) struct Options {
    pub pairs: Vec<(String, String)>,
}

impl Options {
    /// The value of the last `--name`.
    pub fn get(&self, name: &str) -> Option<&str> {
        self.pairs
            .iter()
            .rev()
            .find(|(k, _)| k == name)
            .map(|(_, v)| v.as_str())
    }

    /// Every value of `--name`, in order (`--function`, `--vary`).
    pub fn all(&self, name: &str) -> Vec<String> {
        self.pairs
            .iter()
            .filter(|(k, _)| k == name)
            .map(|(_, v)| v.clone())
            .collect()
    }
}

/// The words of `args`, split at white space outside quotes.
fn words(args: &str) -> Result<Vec<String>, String> {
    let mut out = Vec::new();
    let mut word = String::new();
    let mut quote: Option<char> = None;
    let mut started = false;
    for c in args.chars() {
        match quote {
            Some(q) if c == q => quote = None,
            Some(_) => word.push(c),
            // only `"`: a prime is part of a name (`theta'=0`)
            None if c == '"' => {
                quote = Some(c);
                started = true;
            }
            None if c.is_whitespace() => {
                if started {
                    out.push(std::mem::take(&mut word));
                    started = false;
                }
            }
            None => {
                word.push(c);
                started = true;
            }
        }
    }
    if let Some(q) = quote {
        return Err(format!(
            "error: a quote {q} is not closed\n  = hint: quote a value with spaces: --function \"s = sin(t)\"\n"
        ));
    }
    if started {
        out.push(word);
    }
    Ok(out)
}

/// The options of `:name` (the command `c`) in `args`, each one `c` takes.
pub(super) fn parse(c: &ReplCommand, args: &str) -> Result<Options, String> {
    let takes = || {
        if c.options.is_empty() {
            format!(":{} takes no options", c.name)
        } else {
            let all: Vec<String> = c.options.iter().map(|o| format!("--{o}")).collect();
            format!(":{} takes {}", c.name, all.join(", "))
        }
    };
    let mut out = Options::default();
    let mut it = words(args)?.into_iter();
    while let Some(w) = it.next() {
        let Some(k) = w.strip_prefix("--") else {
            return Err(format!(
                "error: unexpected `{w}`\n  = hint: options are written --name value (--set m=1,g=9.81); {}\n",
                takes()
            ));
        };
        let (key, value) = match k.split_once('=') {
            Some((k, v)) => (k.to_string(), Some(v.to_string())),
            None => (k.to_string(), it.next()),
        };
        if !c.options.contains(&key.as_str()) {
            let near = crate::spelling::nearest(&key, c.options.iter().copied())
                .map(|k| format!("did you mean `--{k}`? "))
                .unwrap_or_default();
            return Err(format!(
                "error: `:{}` takes no option `--{key}`\n  = hint: {near}{}\n",
                c.name,
                takes()
            ));
        }
        match value {
            Some(v) => out.pairs.push((key, v)),
            None => return Err(format!("error: `--{key}` needs a value\n")),
        }
    }
    Ok(out)
}

/// An option's diagnostic, rendered against its value.
pub(super) fn option_error(key: &str, value: &str, d: &Diagnostic) -> String {
    d.render(&format!("--{key}"), value)
}

/// A number option's value.
pub(super) fn number<T: std::str::FromStr>(key: &str, value: &str) -> Result<T, String> {
    value
        .trim()
        .parse()
        .map_err(|_| format!("error: `--{key} {value}`: not a number\n"))
}

/// `--output NAME`: a format `c` writes.
pub(super) fn output_format(c: Command, name: &str) -> Result<Format, String> {
    match Format::from_name(name).filter(|f| c.formats().contains(f)) {
        Some(f) => Ok(f),
        None => {
            let all: Vec<&str> = c.formats().iter().map(|f| f.name()).collect();
            Err(format!(
                "error: unknown output `{name}`\n  = hint: `{}` writes {}\n",
                c.name(),
                all.join(", ")
            ))
        }
    }
}

/// The application's options for `c` from the REPL's; also the format
/// asked with `--output`.
pub(super) fn app_options(
    c: Command,
    o: &Options,
    max_terms: usize,
) -> Result<(CommandOptions, Option<Format>), String> {
    let mut opts = CommandOptions {
        max_terms,
        ..CommandOptions::default()
    };
    let mut fmt = None;
    for (k, v) in &o.pairs {
        let err = |d: Diagnostic| option_error(k, v, &d);
        match k.as_str() {
            "set" => opts.set = crate::output::parse_set_any_sign(v).map_err(err)?,
            "at" => opts.at = Some(v.clone()),
            "init" => opts.init = Some(v.clone()),
            "steady" => opts.steady = Some(v.clone()),
            "over" => opts.over = crate::app::parse_over(c, v).map_err(err)?,
            "guess" => opts.guess = crate::cycle::parse_guess(v).map_err(err)?,
            "columns" => opts.columns = Some(crate::simulate::cycle::column_names(v)),
            "function" => opts.functions.push(v.clone()),
            "period" => opts.period = Some(number(k, v)?),
            "max-steps" => opts.max_steps = Some(number(k, v)?),
            "threads" => opts.threads = number(k, v)?,
            "output" => fmt = Some(output_format(c, v)?),
            // the pictures are written after the run
            _ => {}
        }
    }
    if c == Command::Cycle && opts.over.is_empty() {
        return Err(
            "error: `:cycle` needs --over\n  = hint: the varied quantity, `t` or a driven coordinate: --over phi=0:360deg:73\n"
                .into(),
        );
    }
    if c == Command::Floquet && o.get("plot").is_some() && opts.over.is_empty() {
        return Err("error: --plot draws the stability over the --over parameters\n  = hint: add --over NAME=FROM:TO:COUNT: one parameter draws the largest |μ|, two the stability chart\n".into());
    }
    if c == Command::Response && o.get("plot").is_some() && opts.over.is_empty() {
        return Err(
            "error: --plot draws the swept response\n  = hint: add --over Omega=FROM:TO:COUNT\n"
                .into(),
        );
    }
    Ok((opts, fmt))
}
