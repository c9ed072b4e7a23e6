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

pub mod latex;

/// The commands of the CLI.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Command {
    Derive,
    Solve,
    Forces,
    Equilibrium,
    Modes,
    /// LaTeX of the scene's main result (see [`latex::document`]).
    Latex,
}

/// Options of the commands beyond the file and the format.
#[derive(Clone, Debug, Default)]
pub struct Options {
    /// `--set`: parameter values.
    pub set: Values,
    /// `modes --at q=value,…`: the equilibrium (expressions in the scene).
    pub at: Option<String>,
    /// `modes --init q=…,q'=…`: initial conditions.
    pub init: Option<String>,
    /// `latex --steps`: the derivation line by line.
    pub steps: bool,
    /// `latex --standalone`: a whole document, not a fragment.
    pub standalone: bool,
    /// The title of a standalone document (the file name).
    pub title: String,
    /// `--max-terms`: the work budget ([`crate::budget`]); 0 means the
    /// default, [`crate::limits::DEFAULT_MAX_TERMS`].
    pub max_terms: usize,
}

/// Run `cmd` on the scene source `src`: the output, and the warnings to show.
pub fn run(
    cmd: Command,
    src: &str,
    fmt: Format,
    set: &Values,
) -> Result<(String, Vec<Diagnostic>), Diagnostic> {
    let opts = Options {
        set: set.clone(),
        ..Options::default()
    };
    run_with(cmd, src, fmt, &opts)
}

/// [`run`] with every option, within the work budget `opts.max_terms`.
pub fn run_with(
    cmd: Command,
    src: &str,
    fmt: Format,
    opts: &Options,
) -> Result<(String, Vec<Diagnostic>), Diagnostic> {
    let max_terms = match opts.max_terms {
        0 => crate::limits::DEFAULT_MAX_TERMS,
        n => n,
    };
    crate::budget::within(max_terms, || run_unbounded(cmd, src, fmt, opts))
        .unwrap_or_else(|e| Err(too_large(&e)))
}

/// The error of an exceeded work budget, at the statement it names.
pub fn too_large(e: &crate::budget::TooLarge) -> Diagnostic {
    let hint = format!(
        "exact expressions this large are rarely what a scene means (expand less, or choose other coordinates); to go on, raise the limit: --max-terms {}",
        e.limit.saturating_mul(10)
    );
    match e.context.as_ref().and_then(|c| c.span) {
        Some((a, b)) => Diagnostic::error(crate::parse::ast::Span::new(a, b), e.message()),
        None => Diagnostic::global(e.message()),
    }
    .with_hint(hint)
}

fn run_unbounded(
    cmd: Command,
    src: &str,
    fmt: Format,
    opts: &Options,
) -> Result<(String, Vec<Diagnostic>), Diagnostic> {
    let set = &opts.set;
    let scene = Scene::parse(src)?;
    let out = match cmd {
        Command::Derive => {
            let lag = scene.lagrange()?;
            match fmt {
                Format::Text => derive_text(&lag),
                Format::Json => json_string(derive_json(&lag)),
                Format::Latex => latex::write(&scene, |w| w.derive(&lag)),
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
                Format::Latex => latex::write(&scene, |w| {
                    if let Some((l, acc)) = &lag {
                        w.equations(l);
                        w.accelerations(acc);
                    }
                    w.blocks(&scene, &blocks);
                }),
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
                Format::Latex => latex::write(&scene, |w| w.forces(&names, &q)),
                Format::Json => {
                    let mut m = Map::new();
                    m.insert("coordinates".into(), json!(names));
                    m.insert("generalized_forces".into(), named(&names, &q));
                    json_string(m)
                }
            }
        }
        Command::Modes => {
            check_set(&scene, set)?;
            let at = match &opts.at {
                Some(a) => Some(scene.coordinate_values(a)?),
                None => None,
            };
            // an equilibrium is a constant position
            if let Some(vals) = &at {
                for (c, v) in scene.coordinates.iter().zip(vals) {
                    if v.is_time_dependent() {
                        return Err(Diagnostic::global(format!(
                            "`--at {}={}`: an equilibrium is a constant position, and this changes with time",
                            c.name,
                            crate::expr::print::input(v)
                        ))
                        .with_hint("give the coordinates constant values: --at theta=0 (the motion about a moving state is not small oscillations)"));
                    }
                }
            }
            let md = crate::solve::oscillations::modes(&scene, at.as_deref(), set)?;
            let free = match &opts.init {
                Some(i) => {
                    let (q0, v0) = scene.initial_conditions(i)?;
                    Some(crate::solve::oscillations::free_response(&md, &q0, &v0)?)
                }
                None => None,
            };
            match fmt {
                Format::Text => modes_text(&md, set, free.as_deref()),
                Format::Json => json_string(modes_json(&md, set, free.as_deref())),
                Format::Latex => latex::write(&scene, |w| w.modes(&md)),
            }
        }
        Command::Equilibrium => {
            check_set(&scene, set)?;
            let eq = equilibrium::equilibria(&scene, set)?;
            match fmt {
                Format::Text => equilibrium_text(&eq),
                Format::Json => json_string(equilibrium_json(&eq)),
                Format::Latex => latex::write(&scene, |w| w.equilibrium(&eq)),
            }
        }
        Command::Latex => {
            check_set(&scene, set)?;
            latex::document(&scene, opts)?
        }
    };
    Ok((out, scene.warnings.clone()))
}

/// `--set` names must be parameters of the scene.
fn check_set(scene: &Scene, set: &Values) -> Result<(), Diagnostic> {
    for name in set.keys() {
        if !scene.parameters.iter().any(|p| &p.name == name) {
            let list: Vec<&str> = scene.parameters.iter().map(|p| p.name.as_str()).collect();
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
    Ok(())
}

pub use crate::scene::given::parameter_values as parse_set;

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
    /// amsmath LaTeX (see [`latex`]).
    Latex,
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
            "  {}  {} = {}\n",
            padded(&name, width),
            u(&e.lhs),
            u(&e.rhs)
        ));
    }
    out.push('\n');
    matrix_text(&mut out, "Mass matrix M  (M·q̈ = f)", &l.mass_matrix);
    out.push_str("\nForcing f\n");
    for (c, f) in l.coordinates.iter().zip(&l.forcing) {
        out.push_str(&format!(
            "  {}  {}\n",
            padded(&pretty_name(c, 0), width),
            u(f)
        ));
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
        out.push_str(&format!(
            "  Q_{} = {}\n",
            padded(&pretty_name(c, 0), width),
            u(e)
        ));
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
            out.push_str(&format!(
                "  {} = {}\n",
                padded(&pretty_name(n, 0), width),
                u(v)
            ));
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
    st: &dyn Fn(&Expr) -> String,
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
        Position::Numeric(xs) => match &e.certified {
            Some(digits) => digits.iter().map(|d| minus(d.clone())).collect(),
            None => xs
                .iter()
                .map(|x| minus(crate::solve::certify::significant(*x, 6)))
                .collect(),
        },
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
    if !eq.exact && !eq.equilibria.is_empty() {
        out.push_str(if eq.coordinates.len() == 1 {
            "  (found by Newton's method from many starting points: roots far from them may be missed; digits shown are certified by a sign change)\n"
        } else {
            "  (found by Newton's method from many starting points: roots far from them may be missed)\n"
        });
    }
    for (i, e) in eq.equilibria.iter().enumerate() {
        let vals = position_strings(eq, e, &u);
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
        if e.multiplicity > 1 {
            out.push_str(&format!(
                "     a root of multiplicity {} of the condition (V'' = 0 there; decided by the first derivative of V that is not 0)\n",
                e.multiplicity
            ));
        }
        if let (Position::Numeric(xs), None) = (&e.position, &e.certified) {
            out.push_str(if xs.len() == 1 {
                "     not certified: no sign change of the condition found around it (a multiple root, or one lost in rounding); 6 digits shown\n"
            } else {
                "     not certified (several coordinates: qdot encloses roots of one equation only); 6 digits shown\n"
            });
        }
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
    let mut multiplicity = Vec::new();
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
                for (c, v) in eq.coordinates.iter().zip(position_strings(eq, e, &s)) {
                    o.insert(c.clone(), Value::String(v));
                }
            }
        }
        list.push(Value::Object(o));
        stab.push(json!(e.stability.word()));
        multiplicity.push(json!(e.multiplicity));
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
    m.insert("multiplicity".into(), Value::Array(multiplicity));
    m
}

/// `s` padded with spaces to `width` characters. (`format!`'s `{:<w$}`
/// panics for widths over 65,535, and a matrix entry or a name can be
/// longer than that.)
pub fn padded(s: &str, width: usize) -> String {
    let n = s.chars().count();
    let mut out = String::with_capacity(s.len() + width.saturating_sub(n));
    out.push_str(s);
    out.extend(std::iter::repeat_n(' ', width.saturating_sub(n)));
    out
}

fn matrix_text(out: &mut String, title: &str, m: &[Vec<Expr>]) {
    out.push_str(title);
    out.push('\n');
    let cells: Vec<Vec<String>> = m.iter().map(|r| r.iter().map(u).collect()).collect();
    let n = cells.first().map(|r| r.len()).unwrap_or(0);
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
            .map(|(j, c)| padded(c, widths[j]))
            .collect();
        out.push_str(&format!("  [ {} ]\n", row.join("   ")));
    }
}

/// The generalized symmetric eigenproblem K·v = ω²·M·v at `set`.
fn numeric_eigen(
    md: &crate::solve::oscillations::Modes,
    set: &Values,
) -> Option<crate::solve::eigen::GeneralizedEigen> {
    if set.is_empty() {
        return None;
    }
    let at = |a: &crate::expr::atom::Atom| match a {
        crate::expr::atom::Atom::Param(n) => set.get(&**n).copied(),
        _ => None,
    };
    let num = |m: &[Vec<Expr>]| -> Option<Vec<Vec<f64>>> {
        m.iter()
            .map(|r| r.iter().map(|e| e.eval_f64(&at)).collect())
            .collect()
    };
    crate::solve::eigen::generalized_symmetric(&num(&md.stiffness)?, &num(&md.mass)?).ok()
}

/// The text of `qdot modes`.
pub fn modes_text(
    md: &crate::solve::oscillations::Modes,
    set: &Values,
    free: Option<&[Expr]>,
) -> String {
    let names: Vec<String> = md.coordinates.iter().map(|c| pretty_name(c, 0)).collect();
    let standard = crate::solve::oscillations::standard_form(md, set);
    let at: Vec<String> = names
        .iter()
        .zip(&md.at)
        .map(|(c, v)| format!("{c} = {}", u(v)))
        .collect();
    let mut out = format!(
        "Linearized about {}   M·q̈ + C·q̇ + K·q = f(t)\n",
        at.join(", ")
    );
    matrix_text(&mut out, "Mass matrix M", &md.mass);
    if md.damping.iter().flatten().any(|e| !e.is_zero()) {
        matrix_text(&mut out, "Damping matrix C", &md.damping);
    }
    matrix_text(&mut out, "Stiffness matrix K", &md.stiffness);
    if md.forcing.iter().any(|e| !e.is_zero()) {
        out.push_str("Forcing f(t)\n");
        for (c, f) in names.iter().zip(&md.forcing) {
            out.push_str(&format!("  {c}  {}\n", u(f)));
        }
    }
    if let Some(sf) = &standard {
        let q = &md.coordinates[0];
        out.push_str("\nStandard form  ÿ + 2α·ẏ + ω²·y = f(t)/M\n");
        let mut lhs = pretty_name(q, 2);
        if !sf.alpha.is_zero() {
            lhs.push_str(&format!(
                " + {}·{}",
                paren_str(&expanded(&sf.alpha.scale(&crate::num::Q::from_i64(2)))),
                pretty_name(q, 1)
            ));
        }
        lhs.push_str(&format!(
            " + {}·{}",
            paren_str(&expanded(&sf.omega_squared)),
            pretty_name(q, 0)
        ));
        out.push_str(&format!("  {lhs} = {}\n", u(&sf.forcing)));
        out.push_str(&format!("  ω² = {}\n", expanded(&sf.omega_squared)));
        let w = crate::expr::func::sqrt(&sf.omega_squared).ok().filter(|w| {
            w.num().len() == 1
                && w.den().len() == 1
                && !w.vars().iter().any(|&v| {
                    matches!(
                        crate::expr::atom::atom(v),
                        crate::expr::atom::Atom::SqrtOf(_)
                    )
                })
        });
        let ws = match &w {
            Some(w) => u(w),
            None => format!("√({})", expanded(&sf.omega_squared)),
        };
        out.push_str(&format!("  ω = {ws}   T = 2π/ω   f = ω/(2π)\n"));
        if !sf.alpha.is_zero() {
            out.push_str(&format!("  α = {}", expanded(&sf.alpha)));
            match (&sf.zeta, &w) {
                (Some(z), Some(_)) => out.push_str(&format!("   ζ = α/ω = {}", u(z))),
                _ => out.push_str("   ζ = α/ω"),
            }
            out.push('\n');
        }
        out.push_str(&format!("  regime: {}\n", sf.regime));
    }
    out.push_str("\nCharacteristic equation  det(K − λ·M) = 0,  λ = ω²\n");
    let lv = crate::expr::atom::unknown(crate::solve::oscillations::LAMBDA);
    // the equation is "= 0": constant factors are left out
    let shown: Vec<&Expr> = md.factors.iter().filter(|f| f.depends_on(lv)).collect();
    let factors: Vec<String> = shown
        .iter()
        .map(|f| {
            let s = lambda_poly(f);
            if shown.len() > 1 && (s.contains(" + ") || s.contains(" − ")) {
                format!("({s})")
            } else {
                s
            }
        })
        .collect();
    if factors.is_empty() {
        out.push_str(&format!("  {} = 0\n", lambda_poly(&md.characteristic)));
    } else {
        out.push_str(&format!("  {} = 0\n", factors.join("·")));
    }
    if md.omega_squared.is_empty() {
        out.push_str("  (no closed form for its roots)\n");
    } else {
        out.push_str(
            "\nNatural frequencies and modes  (distribution coefficients μ_j = x_j/x_1)\n",
        );
        for (i, (w2, mode)) in md.omega_squared.iter().zip(&md.modes).enumerate() {
            let m: Vec<String> = mode.iter().map(u).collect();
            out.push_str(&format!(
                "  ω{}² = {}    mode ({})\n",
                print::subscript(&(i + 1).to_string()),
                expanded(w2),
                m.join(", ")
            ));
        }
    }
    if let Some(g) = numeric_eigen(md, set) {
        let v: Vec<String> = g.values.iter().map(|x| minus(format!("{x:.10}"))).collect();
        out.push_str(&format!("  numeric ω² (eigen-solver): {}\n", v.join(", ")));
        out.push_str("  mass-normalized modes (numeric, vᵀ·M·v = 1):\n");
        for v in &g.vectors {
            let c: Vec<String> = v.iter().map(|x| minus(format!("{x:.8}"))).collect();
            out.push_str(&format!("    ({})\n", c.join(", ")));
        }
    }
    if !md.omega_squared.is_empty() && md.omega_squared.len() == md.coordinates.len() {
        out.push_str("\nGeneral solution (undamped)  q(t) = Σ Cᵢ·uᵢ·cos(ωᵢ·t + φᵢ)\n");
        for (j, c) in names.iter().enumerate() {
            let mut terms = Vec::new();
            for (i, mode) in md.modes.iter().enumerate() {
                let mu = &mode[j];
                if mu.is_zero() {
                    continue;
                }
                let i1 = print::subscript(&(i + 1).to_string());
                let wave = format!("C{i1}·cos(ω{i1}·t + φ{i1})");
                let (neg, body) = signed_coefficient(&u(mu));
                terms.push((
                    neg,
                    if body == "1" {
                        wave
                    } else {
                        format!("{body}·{wave}")
                    },
                ));
            }
            let line = print::join_terms(terms.into_iter(), print::Style::Unicode);
            out.push_str(&format!("  {c} = {line}\n"));
        }
    }
    out.push_str(&format!(
        "\nStability of the equilibrium: {}",
        md.stability.word()
    ));
    if let crate::solve::oscillations::Stability::Undecided(why) = &md.stability {
        out.push_str(&format!(" ({why})"));
    }
    out.push('\n');
    if md.coordinates.len() > 1 && md.damping.iter().flatten().any(|e| !e.is_zero()) {
        out.push_str("  (the modes are those of the undamped system)\n");
    }
    if let Some(free) = free {
        out.push_str("\nFree response (undamped) from the initial conditions\n");
        for (c, q) in names.iter().zip(free) {
            out.push_str(&format!("  {c}(t) = {}\n", u(q)));
        }
        if md.coordinates.len() == 1 && md.omega_squared.len() == 1 {
            // the seed's form y = A·sin(ω·t + φ)
            let q = &free[0];
            let t = crate::expr::atom::time();
            let zero: rustc_hash::FxHashMap<_, _> = [(t, Expr::zero())].into_iter().collect();
            let y0 = q.subs_many(&zero).ok();
            let v0 = q.diff(t).subs_many(&zero).ok();
            if let (Some(y0), Some(v0)) = (y0, v0) {
                if let Some((a, phi)) =
                    crate::solve::oscillations::amplitude_phase(&md.omega_squared[0], &y0, &v0)
                {
                    out.push_str(&format!(
                        "  = A·sin(ω·t + φ),  A = √(y₀² + (v₀/ω)²) = {},  φ = atan(y₀·ω/v₀) = {}\n",
                        u(&a),
                        u(&phi)
                    ));
                }
            }
        }
    }
    if let Some(sf) = &standard {
        if !sf.alpha.is_zero() {
            if let Some((p, _, tan_psi)) = crate::solve::oscillations::damped_steady_state(md, sf) {
                // X is exact in the JSON; the formula reads better here
                out.push_str(&format!(
                    "\nSteady state under F·cos(p·t), p = {}:  y = X·cos(p·t − ψ)\n  X = (F/M)/√((ω² − p²)² + 4α²p²),  F/M = {}\n  tan ψ = 2αp/(ω² − p²) = {}\n",
                    u(&p),
                    crate::solve::oscillations::harmonic_load(md)
                        .and_then(|(_, f)| f[0].div(&md.mass[0][0]).ok())
                        .map(|a| u(&a))
                        .unwrap_or_default(),
                    u(&tan_psi)
                ));
            }
        }
    }
    if let Some((p, x)) = crate::solve::oscillations::forced_amplitudes(md) {
        if md.damping.iter().flatten().all(|e| e.is_zero()) {
            out.push_str(&format!(
                "\nSteady state under f = F·cos(p·t), p = {}  (undamped amplitudes; resonance at p² = ωᵢ²)\n",
                u(&p)
            ));
            for (c, a) in names.iter().zip(&x) {
                out.push_str(&format!("  {c}: {}·cos(p·t)\n", paren(a)));
            }
        }
    }
    out
}

fn expanded(e: &Expr) -> String {
    print::expanded(e)
}

/// A polynomial in λ in ascending powers: k − 6·m·λ, 2·k² − 4·k·m·λ + m²·λ².
fn lambda_poly(f: &Expr) -> String {
    let lv = crate::expr::atom::unknown(crate::solve::oscillations::LAMBDA);
    if !f.den().is_one() || !f.num().contains_var(lv) {
        return u(f);
    }
    let mut terms = Vec::new();
    for (i, c) in f.num().coeffs_in(lv).into_iter().enumerate() {
        if c.is_zero() {
            continue;
        }
        let (neg, cs) = signed_coefficient(&expanded(&Expr::from_poly(c)));
        let pow = match i {
            0 => String::new(),
            1 => "λ".to_string(),
            k => format!("λ{}", print::superscript(k as u32)),
        };
        let term = match (i, cs.as_str()) {
            (0, _) => cs.clone(),
            (_, "1") => pow,
            _ => format!("{cs}·{pow}"),
        };
        terms.push((neg, term));
    }
    print::join_terms(terms.into_iter(), print::Style::Unicode)
}

/// A printed coefficient as (sign outside, body): `−a` → (true, `a`), a
/// sum → (false, `(a − b)`), else (false, itself).
fn signed_coefficient(s: &str) -> (bool, String) {
    if s.contains(" + ") || s.contains(" − ") {
        return (false, format!("({s})"));
    }
    match s.strip_prefix('−') {
        Some(r) => (true, r.to_string()),
        None => (false, s.to_string()),
    }
}

fn paren(e: &Expr) -> String {
    paren_str(&u(e))
}

fn paren_str(s: &str) -> String {
    if s.contains(" + ") || s.contains(" − ") || s.starts_with('−') {
        format!("({s})")
    } else {
        s.to_string()
    }
}

/// `forced_response`: for f = F·cos(p·t), the undamped amplitudes
/// (K − p²M)⁻¹·F, or for one damped coordinate X and tan ψ.
fn forced_json(
    md: &crate::solve::oscillations::Modes,
    sf: Option<&crate::solve::oscillations::StandardForm>,
) -> Value {
    use crate::solve::oscillations as osc;
    let damped = md.damping.iter().flatten().any(|e| !e.is_zero());
    if !damped {
        return osc::forced_amplitudes(md)
            .map(|(p, x)| json!({"p": s(&p), "amplitudes": named(&md.coordinates, &x)}))
            .unwrap_or(Value::Null);
    }
    sf.and_then(|sf| osc::damped_steady_state(md, sf))
        .map(|(p, x, t)| json!({"p": s(&p), "amplitude": s(&x), "tan_psi": s(&t)}))
        .unwrap_or(Value::Null)
}

/// The JSON of `qdot modes`.
pub fn modes_json(
    md: &crate::solve::oscillations::Modes,
    set: &Values,
    free: Option<&[Expr]>,
) -> Map<String, Value> {
    let mat = |m: &[Vec<Expr>]| {
        json!(m
            .iter()
            .map(|r| r.iter().map(s).collect::<Vec<_>>())
            .collect::<Vec<_>>())
    };
    let mut m = Map::new();
    m.insert("coordinates".into(), json!(md.coordinates));
    m.insert("at".into(), named(&md.coordinates, &md.at));
    m.insert("mass_matrix".into(), mat(&md.mass));
    m.insert("stiffness_matrix".into(), mat(&md.stiffness));
    m.insert("damping_matrix".into(), mat(&md.damping));
    m.insert(
        "forcing".into(),
        json!(md.forcing.iter().map(s).collect::<Vec<_>>()),
    );
    m.insert(
        "characteristic_polynomial".into(),
        json!(s(&md.characteristic)),
    );
    m.insert(
        "characteristic_factors".into(),
        json!(md.factors.iter().map(s).collect::<Vec<_>>()),
    );
    m.insert(
        "omega_squared".into(),
        json!(md.omega_squared.iter().map(s).collect::<Vec<_>>()),
    );
    m.insert(
        "modes".into(),
        json!(md
            .modes
            .iter()
            .map(|v| v.iter().map(s).collect::<Vec<_>>())
            .collect::<Vec<_>>()),
    );
    m.insert("stability".into(), json!(md.stability.word()));
    let standard = crate::solve::oscillations::standard_form(md, set);
    let sf = standard.as_ref().map(|sf| {
        json!({
            "omega_squared": s(&sf.omega_squared),
            "alpha": s(&sf.alpha),
            "zeta": sf.zeta.as_ref().map(s),
            "forcing": s(&sf.forcing),
            "regime": sf.regime,
        })
    });
    m.insert("standard_form".into(), sf.unwrap_or(Value::Null));
    let eigen = numeric_eigen(md, set);
    m.insert(
        "numeric_omega_squared".into(),
        eigen
            .as_ref()
            .map(|g| json!(g.values))
            .unwrap_or(Value::Null),
    );
    m.insert(
        "numeric_modes".into(),
        eigen
            .as_ref()
            .map(|g| json!(g.vectors))
            .unwrap_or(Value::Null),
    );
    m.insert(
        "free_response".into(),
        free.map(|f| named(&md.coordinates, f))
            .unwrap_or(Value::Null),
    );
    m.insert("forced_response".into(), forced_json(md, standard.as_ref()));
    m
}
