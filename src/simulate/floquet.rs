//! `qdot floquet`: the Floquet stability of a scene with periodic
//! coefficients (the engine is [`crate::floquet`]), at one
//! set of parameter values or over a grid of one or two (`--over`, on
//! every core), rendered as text, CSV or JSON.

use crate::algebra::sign::Values;
use crate::diag::{Diagnostic, ErrorKind};
use crate::expr::Expr;
use crate::floquet::{
    monodromy::{certified, shortest},
    prepare, Floquet, FloquetRequest, Prepared,
};
use crate::poly::Var;
use crate::scene::Scene;
use rayon::prelude::*;
use rustc_hash::FxHashMap;

/// One varied parameter of `--over`: COUNT values from FROM to TO.
#[derive(Clone, Debug, PartialEq)]
pub struct Axis {
    /// The parameter.
    pub name: String,
    /// The first value.
    pub from: f64,
    /// The last value.
    pub to: f64,
    /// How many evenly spaced values, ends included.
    pub count: usize,
}

impl Axis {
    /// The k-th value.
    pub fn value(&self, k: usize) -> f64 {
        if self.count <= 1 {
            return self.from;
        }
        self.from + (self.to - self.from) * k as f64 / (self.count - 1) as f64
    }
}

/// `--over p=FROM:TO:COUNT[,r=FROM:TO:COUNT]`: one or two axes.
pub fn parse_over(text: &str) -> Result<Vec<Axis>, Diagnostic> {
    let bad = |what: String| {
        Diagnostic::global(format!("`--over {text}`: {what}"))
            .with_hint("--over NAME=FROM:TO:COUNT, or two of them for a chart: --over \"delta=-1:3:81,eps=0:2:41\"")
            .with_kind(ErrorKind::bad_option("--over"))
    };
    let mut axes = Vec::new();
    for part in text.split(',') {
        let (name, range) = part
            .split_once('=')
            .ok_or_else(|| bad(format!("no `=` in `{part}`")))?;
        let name = name.trim();
        let parts: Vec<&str> = range.split(':').map(str::trim).collect();
        let [from, to, count] = parts[..] else {
            return Err(bad(format!("`{part}`: the range is FROM:TO:COUNT")));
        };
        let number = |s: &str| match s.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(v),
            _ => Err(bad(format!("`{s}` is not a number"))),
        };
        let limit = crate::limits::MAX_FLOQUET_POINTS;
        let count = count
            .parse::<usize>()
            .ok()
            .filter(|c| (1..=limit).contains(c))
            .ok_or_else(|| {
                bad(format!(
                    "COUNT `{count}` must be a whole number from 1 to {}",
                    crate::budget::grouped(limit)
                ))
            })?;
        axes.push(Axis {
            name: name.to_string(),
            from: number(from)?,
            to: number(to)?,
            count,
        });
    }
    if axes.len() > 2 {
        return Err(bad("one or two parameters vary, not more".into()));
    }
    if axes.len() == 2 && axes[0].name == axes[1].name {
        // as `sweep --vary` says it
        let name = &axes[0].name;
        return Err(
            Diagnostic::global(format!("`--over {name}`: `{name}` is varied twice"))
                .with_hint("vary each parameter once")
                .with_kind(ErrorKind::bad_option("--over")),
        );
    }
    let total = axes.iter().map(|a| a.count).product::<usize>();
    if total > crate::limits::MAX_FLOQUET_POINTS {
        return Err(bad(format!(
            "{} points, more than {}",
            crate::budget::grouped(total),
            crate::budget::grouped(crate::limits::MAX_FLOQUET_POINTS)
        )));
    }
    Ok(axes)
}

/// What `qdot floquet` runs.
#[derive(Clone, Debug, Default)]
pub struct Request {
    /// The reference, given functions and period.
    pub floquet: FloquetRequest,
    /// `--set`: the parameters' values (the varied ones may be left out).
    pub set: Values,
    /// `--over`: none, one or two axes.
    pub over: Vec<Axis>,
}

/// One point of a grid: the varied parameters' values, and the analysis
/// or why it failed.
pub type Point = (Vec<f64>, Result<Floquet, String>);

/// A finished `qdot floquet`.
pub struct FloquetRun {
    /// The linearized scene.
    pub prepared: Prepared,
    /// The axes (empty for one point).
    pub axes: Vec<Axis>,
    /// Without axes, the one point; else every grid point, the first
    /// axis varying fastest.
    pub points: Vec<Point>,
}

/// Read the scene, linearize, and analyse every point.
pub fn run(src: &str, req: &Request) -> Result<FloquetRun, Diagnostic> {
    let scene = Scene::parse(src)?;
    let prepared = prepare(&scene, &req.floquet)?;
    let mut set = req.set.clone();
    for a in &req.over {
        if !scene.parameters.iter().any(|p| p.name == a.name) {
            let names: Vec<&str> = scene.parameters.iter().map(|p| p.name.as_str()).collect();
            return Err(Diagnostic::global(format!(
                "`--over {}=…`: `{}` is not a parameter of the scene",
                a.name, a.name
            ))
            .with_hint(format!("the parameters are {}", names.join(", ")))
            .with_kind(ErrorKind::bad_option("--over")));
        }
        set.insert(a.name.clone(), a.from);
    }
    // 0 is refused where it makes M singular or the period infinite
    let inertial: Vec<String> = scene
        .parameters
        .iter()
        .map(|p| p.name.clone())
        .filter(|p| {
            let v = crate::expr::atom::param(p);
            prepared
                .mass
                .iter()
                .flatten()
                .chain(&prepared.frequency)
                .any(|e| e.depends_on(v))
        })
        .collect();
    let base = crate::scene::given::parameter_map(&scene, &set, &inertial)?;
    if req.over.is_empty() {
        let f = prepared.analyse(&base)?;
        return Ok(FloquetRun {
            prepared,
            axes: Vec::new(),
            points: vec![(Vec::new(), Ok(f))],
        });
    }
    let vars: Vec<Var> = req
        .over
        .iter()
        .map(|a| crate::expr::atom::param(&a.name))
        .collect();
    let total: usize = req.over.iter().map(|a| a.count).product();
    let grid: Vec<Vec<f64>> = (0..total)
        .map(|i| {
            let first = i % req.over[0].count;
            let mut v = vec![req.over[0].value(first)];
            if let Some(b) = req.over.get(1) {
                v.push(b.value(i / req.over[0].count));
            }
            v
        })
        .collect();
    let points = grid
        .into_par_iter()
        .map(|v| {
            let mut values: FxHashMap<Var, f64> = base.clone();
            for (var, x) in vars.iter().zip(&v) {
                values.insert(*var, *x);
            }
            let r = prepared.analyse(&values).map_err(|d| d.message.clone());
            (v, r)
        })
        .collect();
    Ok(FloquetRun {
        prepared,
        axes: req.over.clone(),
        points,
    })
}

/// The linearized equations, one line per coordinate: `M·q̈ + C·q̇ + K·q`.
pub fn equations(p: &Prepared) -> Vec<Expr> {
    let n = p.n();
    (0..n)
        .map(|k| {
            let mut e = Expr::zero();
            for (j, c) in p.coordinates.iter().enumerate() {
                for (order, m) in [(2, &p.mass), (1, &p.damping), (0, &p.stiffness)] {
                    e = e.add(&m[k][j].mul(&Expr::coord(c, order)));
                }
            }
            e
        })
        .collect()
}

/// The reference as `q = value, …`.
fn reference(p: &Prepared) -> String {
    p.coordinates
        .iter()
        .zip(&p.at)
        .map(|(c, v)| format!("{c} = {}", crate::expr::print::unicode(v)))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The report of one point, or the chart or table of a grid.
pub fn text(r: &FloquetRun) -> String {
    let p = &r.prepared;
    let mut out = format!("Linearized about {}  (M·q̈ + C·q̇ + K·q = 0)\n", reference(p));
    for (c, e) in p.coordinates.iter().zip(equations(p)) {
        out.push_str(&format!(
            "  {}  {} = 0\n",
            crate::expr::print::pretty_name(c, 0),
            crate::expr::print::unicode(&e)
        ));
    }
    out.push_str(&match &p.frequency {
        Some(w) => format!(
            "Period  T = 2·π/Ω, Ω = {}\n",
            crate::expr::print::unicode(w)
        ),
        None => "Period  T given (--period)\n".to_string(),
    });
    out.push_str(if p.lagrangian {
        "Lagrangian: yes (the multipliers come in pairs μ, 1/μ̄)\n"
    } else {
        "Lagrangian: no\n"
    });
    match (r.axes.len(), r.points.first()) {
        (0, Some((_, Ok(f)))) => out.push_str(&point_text(f, p.n())),
        (1, _) => out.push_str(&table_text(r)),
        _ => out.push_str(&chart_text(r)),
    }
    out
}

/// One point: T, Φ(T), the multipliers, the verdict.
fn point_text(f: &Floquet, n: usize) -> String {
    let e = f.error;
    let d = 2 * n;
    let mut out = format!("  T = {}\n", shortest(f.period));
    out.push_str(&format!(
        "Monodromy matrix Φ(T)  (x = (q, q̇); error ≤ {e:.0e})\n"
    ));
    for i in 0..d {
        let row: Vec<String> = f.monodromy[i * d..(i + 1) * d]
            .iter()
            .map(|&x| signed(x, e))
            .collect();
        out.push_str(&format!("  [ {} ]\n", row.join("  ")));
    }
    out.push_str("Floquet multipliers μ  (eigenvalues of Φ(T))\n");
    for (k, m) in f.multipliers.iter().enumerate() {
        let im = if m.im.abs() <= e {
            String::new()
        } else {
            format!(
                " {} {}·i",
                if m.im < 0.0 { "−" } else { "+" },
                certified(m.im.abs(), e)
            )
        };
        out.push_str(&format!(
            "  μ{} = {}{im}   |μ| = {}\n",
            k + 1,
            signed(m.re, e),
            certified(m.abs(), e)
        ));
    }
    out.push_str(&format!("  tr Φ(T) = {}\n", signed(f.trace, d as f64 * e)));
    out.push_str(&format!("Verdict: {} ({})\n", f.verdict.name(), f.note));
    out
}

/// [`certified`] with the minus sign of the text.
fn signed(x: f64, e: f64) -> String {
    certified(x, e).replace('-', "−")
}

/// One axis: a row per value.
fn table_text(r: &FloquetRun) -> String {
    let name = &r.axes[0].name;
    let mut rows = vec![[
        name.clone(),
        "max |μ|".to_string(),
        "tr Φ(T)".to_string(),
        "verdict".to_string(),
    ]];
    for (v, f) in &r.points {
        rows.push(match f {
            Ok(f) => [
                shortest(v[0]).replace('-', "−"),
                certified(f.max_abs, f.error),
                signed(f.trace, 2.0 * r.prepared.n() as f64 * f.error),
                f.verdict.name().to_string(),
            ],
            Err(m) => [
                shortest(v[0]).replace('-', "−"),
                "—".into(),
                "—".into(),
                m.clone(),
            ],
        });
    }
    let widths: Vec<usize> = (0..4)
        .map(|k| rows.iter().map(|r| r[k].chars().count()).max().unwrap_or(0))
        .collect();
    let mut out = String::new();
    for row in &rows {
        let cells: Vec<String> = row
            .iter()
            .zip(&widths)
            .map(|(c, &w)| format!("{c:>w$}"))
            .collect();
        out.push_str(cells.join("  ").trim_end());
        out.push('\n');
    }
    out
}

/// The character a point draws in the text chart.
fn mark(f: &Result<Floquet, String>) -> char {
    use crate::floquet::Verdict;
    match f {
        Ok(f) if f.verdict == Verdict::Unstable => '#',
        Ok(f) if f.verdict == Verdict::Stable => '.',
        Ok(_) => '?',
        Err(_) => '!',
    }
}

/// Two axes: the chart in characters, the second axis upward.
fn chart_text(r: &FloquetRun) -> String {
    let (a, b) = (&r.axes[0], &r.axes[1]);
    let mut out = format!(
        "Stability chart  (# unstable, . stable, ? undecided, ! failed)\n  {} from {} (left) to {} (right); {} from {} (bottom) to {} (top)\n",
        a.name,
        shortest(a.from),
        shortest(a.to),
        b.name,
        shortest(b.from),
        shortest(b.to)
    );
    for j in (0..b.count).rev() {
        let line: String = (0..a.count)
            .map(|i| mark(&r.points[j * a.count + i].1))
            .collect();
        out.push_str(&format!("  {line}\n"));
    }
    let count = |c: char| r.points.iter().filter(|(_, f)| mark(f) == c).count();
    out.push_str(&format!(
        "  {} points: {} unstable, {} stable, {} undecided, {} failed\n",
        r.points.len(),
        count('#'),
        count('.'),
        count('?'),
        count('!')
    ));
    if let Some((v, Err(m))) = r.points.iter().find(|(_, f)| f.is_err()) {
        let at: Vec<String> = r
            .axes
            .iter()
            .zip(v)
            .map(|(a, x)| format!("{} = {}", a.name, shortest(*x)))
            .collect();
        out.push_str(&format!("  first failure at {}: {m}\n", at.join(", ")));
    }
    out
}

/// A value as CSV and JSON print it: every digit of the double.
fn full(x: f64) -> String {
    format!("{x:.17e}")
}

/// One row per point: the varied values, `period`, `max_abs_multiplier`,
/// `trace`, `error`, `verdict` and `note` (the reason, or why it failed).
pub fn csv(r: &FloquetRun) -> String {
    let mut header: Vec<String> = r.axes.iter().map(|a| a.name.clone()).collect();
    header.extend(
        [
            "period",
            "max_abs_multiplier",
            "trace",
            "error",
            "verdict",
            "note",
        ]
        .map(String::from),
    );
    let mut out = header.join(",");
    out.push('\n');
    for (v, f) in &r.points {
        let mut cells: Vec<String> = v.iter().map(|&x| full(x)).collect();
        match f {
            Ok(f) => {
                cells.extend([f.period, f.max_abs, f.trace, f.error].map(full));
                cells.push(f.verdict.name().into());
                cells.push(format!("\"{}\"", f.note.replace('"', "\"\"")));
            }
            Err(m) => {
                cells.extend(["", "", "", "", "failed"].map(String::from));
                cells.push(format!("\"{}\"", m.replace('"', "\"\"")));
            }
        }
        out.push_str(&cells.join(","));
        out.push('\n');
    }
    out
}

/// A multiplier in JSON.
#[derive(serde::Serialize)]
struct MultiplierJson {
    re: f64,
    im: f64,
    abs: f64,
}

/// One point in JSON.
#[derive(serde::Serialize)]
struct PointJson {
    values: Vec<f64>,
    period: Option<f64>,
    monodromy: Option<Vec<Vec<f64>>>,
    multipliers: Option<Vec<MultiplierJson>>,
    trace: Option<f64>,
    max_abs_multiplier: Option<f64>,
    error: Option<f64>,
    verdict: &'static str,
    note: String,
}

/// `--output json`.
#[derive(serde::Serialize)]
struct FloquetJson {
    coordinates: Vec<String>,
    at: Vec<String>,
    equations: Vec<String>,
    frequency: Option<String>,
    lagrangian: bool,
    parameters: Vec<String>,
    points: Vec<PointJson>,
}

/// The run as JSON (one line): the linearization, then every point.
pub fn json(r: &FloquetRun) -> String {
    let p = &r.prepared;
    let d = 2 * p.n();
    let points = r
        .points
        .iter()
        .map(|(v, f)| match f {
            Ok(f) => PointJson {
                values: v.clone(),
                period: Some(f.period),
                monodromy: Some(f.monodromy.chunks(d).map(<[f64]>::to_vec).collect()),
                multipliers: Some(
                    f.multipliers
                        .iter()
                        .map(|m| MultiplierJson {
                            re: m.re,
                            im: m.im,
                            abs: m.abs(),
                        })
                        .collect(),
                ),
                trace: Some(f.trace),
                max_abs_multiplier: Some(f.max_abs),
                error: Some(f.error),
                verdict: f.verdict.name(),
                note: f.note.clone(),
            },
            Err(m) => PointJson {
                values: v.clone(),
                period: None,
                monodromy: None,
                multipliers: None,
                trace: None,
                max_abs_multiplier: None,
                error: None,
                verdict: "failed",
                note: m.clone(),
            },
        })
        .collect();
    let wire = FloquetJson {
        coordinates: p.coordinates.clone(),
        at: p.at.iter().map(crate::expr::print::input).collect(),
        equations: equations(p).iter().map(crate::expr::print::input).collect(),
        frequency: p.frequency.as_ref().map(crate::expr::print::input),
        lagrangian: p.lagrangian,
        parameters: r.axes.iter().map(|a| a.name.clone()).collect(),
        points,
    };
    serde_json::to_string(&wire).unwrap_or_default()
}
