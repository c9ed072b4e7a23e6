//! `qdot floquet`'s report ([`crate::app::FloquetRun`]) as text (the
//! point's monodromy matrix and multipliers, a grid's table or chart), CSV
//! or JSON.

use super::table::{full, quoted};
use crate::app::FloquetRun;
use crate::expr::Expr;
use crate::floquet::{
    monodromy::{certified, shortest},
    Floquet, Prepared,
};

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
                cells.push(quoted(&f.note));
            }
            Err(m) => {
                cells.extend(["", "", "", "", "failed"].map(String::from));
                cells.push(quoted(m));
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
