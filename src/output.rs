//! Rendering results: readable text and the JSON contract.
//!
//! JSON keys are a public interface (scripts depend on them):
//! * `derive`: `coordinates`, `equations` (`coordinate`, `lhs`, `rhs`),
//!   `mass_matrix`, `forcing`;
//! * `solve`: those plus `accelerations` (when the scene has dynamics), and
//!   `solutions` (unknown → value), `free_unknowns`, `checks` (equations
//!   implied by the others, each `{"block", "equation"}`, 1-based) when it
//!   has `solve` blocks;
//! * `forces`: `coordinates`, `generalized_forces`;
//! * `equilibrium`: `coordinates`, `generalized_forces`, `conditions`,
//!   `exact`, `equilibria` (a list of coordinate → value objects, "any" for
//!   a free coordinate; numeric values as numbers), `stability` (parallel
//!   to `equilibria`: "stable", "unstable", "undecided"), `notes` (parallel:
//!   the reason when undecided, existence conditions), `approx` (parallel:
//!   the numeric values of an exact position under `--set`, else null).
//!   A check of a vector equation also has `component` ("x", "y", "z").
//!
//! Every expression string is in qdot's input syntax and re-parses to the
//! same expression.

use crate::diag::Diagnostic;
use crate::expr::print::{self, pretty_name};
use crate::expr::Expr;
use crate::mechanics::Lagrange;
use crate::scene::Scene;
use crate::solve::equilibrium::{self, Equilibria, Position, Values};
use crate::solve::system::{self, BlockSolution};
use serde_json::{json, Map, Value};

/// The commands of the CLI.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Command {
    Derive,
    Solve,
    Forces,
    Equilibrium,
}

/// Run `cmd` on the scene source `src`: the output, and the warnings to show.
pub fn run(
    cmd: Command,
    src: &str,
    fmt: Format,
    set: &Values,
) -> Result<(String, Vec<Diagnostic>), Diagnostic> {
    let scene = Scene::parse(src)?;
    let out = match cmd {
        Command::Derive => {
            let lag = scene.lagrange()?;
            match fmt {
                Format::Text => derive_text(&lag),
                Format::Json => json_string(derive_json(&lag)),
            }
        }
        Command::Solve => {
            let dynamics = scene.has_dynamics();
            if !dynamics && scene.systems.is_empty() {
                // the usual error for a scene with nothing to solve
                scene.lagrange()?;
            }
            let lag = if dynamics {
                let l = scene.lagrange()?;
                let acc = l.accelerations()?;
                Some((l, acc))
            } else {
                None
            };
            let blocks = system::solve_scene(&scene)?;
            match fmt {
                Format::Text => {
                    let mut out = match &lag {
                        Some((l, acc)) => solve_text(l, acc),
                        None => String::new(),
                    };
                    if !blocks.is_empty() {
                        if !out.is_empty() {
                            out.push('\n');
                        }
                        out.push_str(&solutions_text(&scene, &blocks));
                    }
                    out
                }
                Format::Json => {
                    let mut m = match &lag {
                        Some((l, acc)) => solve_json(l, acc),
                        None => Map::new(),
                    };
                    if !blocks.is_empty() {
                        solutions_json(&scene, &blocks, &mut m);
                    }
                    json_string(m)
                }
            }
        }
        Command::Forces => {
            let q = crate::mechanics::generalized_forces(&scene);
            if scene.coordinates.is_empty() {
                return Err(Diagnostic::global(
                    "the scene declares no coordinates, so there are no generalized forces",
                )
                .with_hint("declare the generalized coordinates with `coordinates q1, q2, …`"));
            }
            let names: Vec<String> = scene.coordinates.iter().map(|c| c.name.clone()).collect();
            match fmt {
                Format::Text => forces_text(&names, &q),
                Format::Json => {
                    let mut m = Map::new();
                    m.insert("coordinates".into(), json!(names));
                    m.insert("generalized_forces".into(), named(&names, &q));
                    json_string(m)
                }
            }
        }
        Command::Equilibrium => {
            for name in set.keys() {
                if !scene.parameters.iter().any(|p| &p.name == name) {
                    let list: Vec<&str> =
                        scene.parameters.iter().map(|p| p.name.as_str()).collect();
                    return Err(Diagnostic::global(format!(
                        "`--set {name}=…`: `{name}` is not a parameter of the scene"
                    ))
                    .with_hint(if list.is_empty() {
                        "the scene has no parameters".to_string()
                    } else {
                        format!("the parameters are {}", list.join(", "))
                    }));
                }
            }
            let eq = equilibrium::equilibria(&scene, set)?;
            match fmt {
                Format::Text => equilibrium_text(&eq),
                Format::Json => json_string(equilibrium_json(&eq)),
            }
        }
    };
    Ok((out, scene.warnings.clone()))
}

/// Parse `--set m=1,g=9.81` into parameter values.
pub fn parse_set(s: &str) -> Result<Values, Diagnostic> {
    let mut out = Values::default();
    for part in s.split(',').map(str::trim).filter(|p| !p.is_empty()) {
        let Some((k, v)) = part.split_once('=').filter(|(k, _)| !k.trim().is_empty()) else {
            return Err(
                Diagnostic::global(format!("`--set {part}`: expected name=value"))
                    .with_hint("for example --set m=1,g=9.81,l=0.5"),
            );
        };
        let k = k.trim();
        if out.contains_key(k) {
            return Err(Diagnostic::global(format!("`--set`: `{k}` is given twice"))
                .with_hint("give each parameter one value"));
        }
        let v: f64 = match v.trim().parse() {
            Ok(x) if f64::is_finite(x) => x,
            _ => {
                return Err(Diagnostic::global(format!(
                    "`--set {part}`: `{}` is not a number",
                    v.trim()
                ))
                .with_hint("write decimal numbers: --set m=1.5,g=9.81"))
            }
        };
        if v <= 0.0 {
            return Err(Diagnostic::global(format!(
                "`--set {part}`: parameters are positive, and {v} is not"
            ))
            .with_hint("qdot takes every parameter to be positive; write a negative quantity as −p in the scene"));
        }
        out.insert(k.to_string(), v);
    }
    Ok(out)
}

fn json_string(m: Map<String, Value>) -> String {
    let mut s = serde_json::to_string_pretty(&Value::Object(m)).unwrap_or_default();
    s.push('\n');
    s
}

fn named(names: &[String], es: &[Expr]) -> Value {
    let mut m = Map::new();
    for (n, e) in names.iter().zip(es) {
        m.insert(n.clone(), Value::String(s(e)));
    }
    Value::Object(m)
}

/// Output format.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    Text,
    Json,
}

fn s(e: &Expr) -> String {
    print::input(e)
}

fn u(e: &Expr) -> String {
    print::unicode(e)
}

/// The JSON of `qdot derive`.
pub fn derive_json(l: &Lagrange) -> Map<String, Value> {
    let mut m = Map::new();
    m.insert("coordinates".into(), json!(l.coordinates));
    m.insert(
        "equations".into(),
        Value::Array(
            l.equations
                .iter()
                .map(|e| json!({"coordinate": e.coordinate, "lhs": s(&e.lhs), "rhs": s(&e.rhs)}))
                .collect(),
        ),
    );
    m.insert(
        "mass_matrix".into(),
        json!(l
            .mass_matrix
            .iter()
            .map(|r| r.iter().map(s).collect::<Vec<_>>())
            .collect::<Vec<_>>()),
    );
    m.insert(
        "forcing".into(),
        json!(l.forcing.iter().map(s).collect::<Vec<_>>()),
    );
    m
}

/// The JSON of `qdot solve`: derive's keys plus `accelerations`.
pub fn solve_json(l: &Lagrange, acc: &[(String, Expr)]) -> Map<String, Value> {
    let mut m = derive_json(l);
    let mut a = Map::new();
    for (q, e) in acc {
        a.insert(q.clone(), Value::String(s(e)));
    }
    m.insert("accelerations".into(), Value::Object(a));
    m
}

/// The text of `qdot derive`.
pub fn derive_text(l: &Lagrange) -> String {
    let mut out = String::from("Lagrange's equations  d/dt(∂E/∂q̇) − ∂E/∂q = Q\n");
    let width = l
        .coordinates
        .iter()
        .map(|c| pretty_name(c, 0).chars().count())
        .max()
        .unwrap_or(1);
    for e in &l.equations {
        let name = pretty_name(&e.coordinate, 0);
        out.push_str(&format!(
            "  {name:<width$}  {} = {}\n",
            u(&e.lhs),
            u(&e.rhs)
        ));
    }
    out.push_str("\nMass matrix M  (M·q̈ = f)\n");
    let cells: Vec<Vec<String>> = l
        .mass_matrix
        .iter()
        .map(|r| r.iter().map(u).collect())
        .collect();
    let n = l.coordinates.len();
    let widths: Vec<usize> = (0..n)
        .map(|j| {
            cells
                .iter()
                .map(|r| r[j].chars().count())
                .max()
                .unwrap_or(1)
        })
        .collect();
    for r in &cells {
        let row: Vec<String> = r
            .iter()
            .enumerate()
            .map(|(j, c)| format!("{c:<w$}", w = widths[j]))
            .collect();
        out.push_str(&format!("  [ {} ]\n", row.join("   ")));
    }
    out.push_str("\nForcing f\n");
    for (c, f) in l.coordinates.iter().zip(&l.forcing) {
        out.push_str(&format!("  {:<width$}  {}\n", pretty_name(c, 0), u(f)));
    }
    out
}

/// The text of `qdot solve`: the accelerations, after the equations.
pub fn solve_text(l: &Lagrange, acc: &[(String, Expr)]) -> String {
    let mut out = derive_text(l);
    out.push_str("\nAccelerations\n");
    for (q, e) in acc {
        out.push_str(&format!("  {} = {}\n", pretty_name(q, 2), u(e)));
    }
    out
}

/// The text of `qdot forces`.
pub fn forces_text(names: &[String], q: &[Expr]) -> String {
    let mut out = String::from("Generalized forces  δL = Σ Q_k·δq_k\n");
    let width = names
        .iter()
        .map(|c| pretty_name(c, 0).chars().count())
        .max()
        .unwrap_or(1);
    for (c, e) in names.iter().zip(q) {
        out.push_str(&format!("  Q_{:<width$} = {}\n", pretty_name(c, 0), u(e)));
    }
    out
}

/// The solutions of the `solve` blocks as text.
pub fn solutions_text(scene: &Scene, blocks: &[BlockSolution]) -> String {
    let mut out = String::new();
    for (b, (sys, sol)) in scene.systems.iter().zip(blocks).enumerate() {
        let names: Vec<&str> = sys.unknowns.iter().map(|u| u.name.as_str()).collect();
        if b > 0 {
            out.push('\n');
        }
        let names: Vec<String> = names.iter().map(|n| pretty_name(n, 0)).collect();
        out.push_str(&format!("Solutions  (solve {})\n", names.join(", ")));
        let width = sol
            .values
            .iter()
            .map(|(n, _)| pretty_name(n, 0).chars().count())
            .max()
            .unwrap_or(1);
        for (n, v) in &sol.values {
            if sol.free.contains(n) {
                continue;
            }
            out.push_str(&format!("  {:<width$} = {}\n", pretty_name(n, 0), u(v)));
        }
        if !sol.free.is_empty() {
            let f: Vec<String> = sol.free.iter().map(|n| pretty_name(n, 0)).collect();
            out.push_str(&format!(
                "  free: {} (the equations do not determine {})\n",
                f.join(", "),
                if f.len() == 1 { "it" } else { "them" }
            ));
        }
        for &i in &sol.checks {
            out.push_str(&format!(
                "  check: {} follows from the others and holds\n",
                system::equation_label(sys, i)
            ));
        }
        if sol.used_accelerations {
            out.push_str("  (q̈ taken from the accelerations above)\n");
        }
    }
    out
}

/// Add `solutions`, `free_unknowns` and `checks` to a JSON object.
pub fn solutions_json(scene: &Scene, blocks: &[BlockSolution], m: &mut Map<String, Value>) {
    let mut sols = Map::new();
    let mut free = Vec::new();
    let mut checks = Vec::new();
    for (b, (sys, sol)) in scene.systems.iter().zip(blocks).enumerate() {
        for (n, v) in &sol.values {
            if !sol.free.contains(n) {
                sols.insert(n.clone(), Value::String(s(v)));
            }
        }
        free.extend(sol.free.iter().cloned());
        for &i in &sol.checks {
            let mut c = json!({"block": b + 1, "equation": system::equation_number(sys, i)});
            if let Some(k) = sys.equations[i].component {
                c["component"] = json!(["x", "y", "z"][k.min(2)]);
            }
            checks.push(c);
        }
    }
    m.insert("solutions".into(), Value::Object(sols));
    m.insert("free_unknowns".into(), json!(free));
    m.insert("checks".into(), Value::Array(checks));
}

fn position_strings(
    eq: &Equilibria,
    e: &equilibrium::Equilibrium,
    st: fn(&Expr) -> String,
) -> Vec<String> {
    match &e.position {
        Position::Exact(vals) => vals
            .iter()
            .enumerate()
            .map(|(k, v)| {
                if e.free.contains(&k) {
                    "any".to_string()
                } else {
                    st(v)
                }
            })
            .collect::<Vec<String>>(),
        Position::Numeric(xs) => xs.iter().map(|x| minus(format!("{x:.10}"))).collect(),
    }
    .into_iter()
    .take(eq.coordinates.len())
    .collect()
}

/// The text of `qdot equilibrium`.
pub fn equilibrium_text(eq: &Equilibria) -> String {
    let mut out = forces_text(&eq.coordinates, &eq.forces);
    if eq.kinetic_terms {
        out.push_str("\nEquilibrium conditions at rest (Q_k plus the kinetic energy's terms ∂E/∂q_k at q̇ = 0)\n");
        for (c, f) in eq.coordinates.iter().zip(&eq.conditions) {
            out.push_str(&format!("  {}:  {} = 0\n", pretty_name(c, 0), u(f)));
        }
    }
    out.push_str(if eq.exact {
        "\nEquilibria\n"
    } else {
        "\nEquilibria (numeric: no closed form)\n"
    });
    if eq.equilibria.is_empty() {
        out.push_str("  none\n");
    }
    for (i, e) in eq.equilibria.iter().enumerate() {
        let vals = position_strings(eq, e, u);
        let parts: Vec<String> = eq
            .coordinates
            .iter()
            .zip(&vals)
            .map(|(c, v)| format!("{} = {v}", pretty_name(c, 0)))
            .collect();
        out.push_str(&format!("  {}. {}", i + 1, parts.join(", ")));
        if let Some(a) = &e.approx {
            let nums: Vec<String> = a.iter().map(|x| minus(format!("{x:.6}"))).collect();
            out.push_str(&format!("  ≈ ({})", nums.join(", ")));
        }
        out.push_str(&format!("  — {}", e.stability.word()));
        if let equilibrium::Stability::Undecided(why) = &e.stability {
            out.push_str(&format!(" ({why})"));
        }
        out.push('\n');
        for c in &e.conditions {
            out.push_str(&format!("     exists when {c}\n"));
        }
    }
    out
}

/// A number with the typographic minus of the text output.
fn minus(s: String) -> String {
    match s.strip_prefix('-') {
        Some(r) => format!("−{r}"),
        None => s,
    }
}

/// The JSON of `qdot equilibrium`.
pub fn equilibrium_json(eq: &Equilibria) -> Map<String, Value> {
    let mut m = Map::new();
    m.insert("coordinates".into(), json!(eq.coordinates));
    m.insert(
        "generalized_forces".into(),
        named(&eq.coordinates, &eq.forces),
    );
    m.insert("conditions".into(), named(&eq.coordinates, &eq.conditions));
    m.insert("exact".into(), json!(eq.exact));
    let mut list = Vec::new();
    let mut stab = Vec::new();
    let mut notes = Vec::new();
    let mut approx = Vec::new();
    for e in &eq.equilibria {
        approx.push(match &e.approx {
            Some(a) => json!(a),
            None => Value::Null,
        });
        let mut o = Map::new();
        match &e.position {
            Position::Numeric(xs) => {
                for (c, x) in eq.coordinates.iter().zip(xs) {
                    o.insert(c.clone(), json!(x));
                }
            }
            Position::Exact(_) => {
                for (c, v) in eq.coordinates.iter().zip(position_strings(eq, e, s)) {
                    o.insert(c.clone(), Value::String(v));
                }
            }
        }
        list.push(Value::Object(o));
        stab.push(json!(e.stability.word()));
        let mut n: Vec<String> = e
            .conditions
            .iter()
            .map(|c| format!("exists when {c}"))
            .collect();
        if let equilibrium::Stability::Undecided(why) = &e.stability {
            n.push(why.clone());
        }
        notes.push(json!(n.join("; ")));
    }
    m.insert("equilibria".into(), Value::Array(list));
    m.insert("stability".into(), Value::Array(stab));
    m.insert("notes".into(), Value::Array(notes));
    m.insert("approx".into(), Value::Array(approx));
    m
}
