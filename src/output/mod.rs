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
//! * `hamilton`: `coordinates`, `momenta` (coordinate → p in q, q̇),
//!   `velocities` (coordinate → q̇ in q, p), `hamiltonian`, `equations`
//!   (`coordinate`, `momentum`, `qdot`, `pdot`), `other_forces`
//!   (coordinate → Q̃, the generalized forces outside H);
//! * `integrals`: `coordinates`, `momenta` (cyclic coordinate → p),
//!   `cyclic`, `energy` (or null), `energy_is_e_plus_v`, `routhian`,
//!   `effective_potential`, `reduced_accelerations` (null without a
//!   reduction), `notes`;
//! * `equilibrium`: `coordinates`, `generalized_forces`, `conditions`,
//!   `exact`, `equilibria` (a list of coordinate → value objects, "any" for
//!   a free coordinate; numeric values as numbers), `stability` (parallel
//!   to `equilibria`: "stable", "unstable", "undecided"), `notes` (parallel:
//!   the reason when undecided, existence conditions), `approx` (parallel:
//!   the numeric values of an exact position under `--set`, else null),
//!   and with constraints `multipliers` (parallel: multiplier → λ);
//!   A check of a vector equation also has `component` ("x", "y", "z").
//! * `check`: `dimensions`, `definitions`, `sources`, `accelerations`,
//!   `generalized_forces` (dimensions as strings in annotation syntax, or
//!   null where the scene leaves one free);
//! * every command but `check`, for a scene with `body`, `particle` or `gravity`
//!   statements: `bodies` (a list of `{"name", "kind", "line", "kinetic",
//!   "potential"}`, the energies as `{"name", "value"}` or null);
//! * every command but `check`, for a scene with `constraint` statements:
//!   `constraints` (a list of `{"name", "multiplier", "kind", "expression",
//!   "coefficients", "rest"}`: kind "holonomic" or "velocity", the
//!   constraint a·q̇ + b = 0 as its coefficients a per coordinate and b);
//!   `solve` adds `multipliers` (multiplier → λ, after `accelerations`)
//!   and, for `reaction` statements, `reactions` (a list of
//!   `{"constraint", "point", "force"}`, the force a list of components);
//! * every command, for a scene that annotates a dimension: `dimensions`
//!   last (coordinate, parameter, `solve` unknown → dimension or null).
//!
//! Every expression string is in qdot's input syntax and re-parses to the
//! same expression.

use crate::diag::Diagnostic;
use crate::expr::print::{self};
use crate::expr::Expr;
use crate::scene::Scene;
use crate::solve::equilibrium::{self, Equilibria, Position, Values};
use crate::solve::system::{self};
use serde_json::{json, Map};

mod dimensions;
mod json;
pub mod latex;
mod modes;
mod text;

pub use dimensions::{check_json, check_text, dimensions_json};
use json::named;
pub use json::{
    bodies_json, constraints_json, derive_json, equilibrium_json, modes_json, solutions_json,
    solve_json,
};
pub use modes::modes_text;
pub use text::{derive_text, equilibrium_text, forces_text, padded, solutions_text, solve_text};

/// The commands of the CLI.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Command {
    /// `qdot derive`: Lagrange's equations, the mass matrix M and the forcing f.
    Derive,
    /// `qdot solve`: the accelerations q̈ = M⁻¹f and the scene's `solve` blocks.
    Solve,
    /// `qdot forces`: the generalized forces Q_k.
    Forces,
    /// `qdot equilibrium`: the positions of equilibrium at rest and their stability.
    Equilibrium,
    /// `qdot modes`: small oscillations about an equilibrium (M, C, K, the
    /// frequencies, the modes, the responses).
    Modes,
    /// LaTeX of the scene's main result (see [`latex::document`]).
    Latex,
    /// `qdot check`: the dimension of every name and result (text or JSON).
    Check,
    /// `qdot hamilton`: the momenta, H(q, p, t) and Hamilton's equations.
    Hamilton,
    /// `qdot integrals`: cyclic coordinates, the energy integral, Routh.
    Integrals,
}

/// CommandOptions of the commands beyond the file and the format.
#[derive(Clone, Debug, Default)]
pub struct CommandOptions {
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
    let opts = CommandOptions {
        set: set.clone(),
        ..CommandOptions::default()
    };
    run_with(cmd, src, fmt, &opts)
}

/// [`run`] with every option, within the work budget `opts.max_terms`.
pub fn run_with(
    cmd: Command,
    src: &str,
    fmt: Format,
    opts: &CommandOptions,
) -> Result<(String, Vec<Diagnostic>), Diagnostic> {
    let max_terms = match opts.max_terms {
        0 => crate::limits::DEFAULT_MAX_TERMS,
        n => n,
    };
    crate::budget::within(max_terms, || run_unbounded(cmd, src, fmt, opts))
        .unwrap_or_else(|e| Err(too_large(&e)))
}

/// The error of an exceeded work budget (kept here too: it was first public here).
pub use crate::diag::too_large;

fn run_unbounded(
    cmd: Command,
    src: &str,
    fmt: Format,
    opts: &CommandOptions,
) -> Result<(String, Vec<Diagnostic>), Diagnostic> {
    let scene = Scene::parse(src)?;
    let coordinates: Vec<String> = scene.coordinates.iter().map(|c| c.name.clone()).collect();
    crate::expr::print::with_coordinate_order(&coordinates, || {
        crate::algebra::assume::assuming(&scene.assumptions, || run_scene(cmd, &scene, fmt, opts))
    })
}

/// A command's JSON object as text, with the keys every command of this
/// scene carries: `bodies` for a scene with bodies, `dimensions` (last)
/// for an annotated one.
fn scene_json(scene: &Scene, mut m: Map<String, serde_json::Value>) -> Result<String, Diagnostic> {
    if !scene.bodies.is_empty() {
        m.insert("bodies".into(), json::bodies_json(scene));
    }
    if !scene.constraints.is_empty() {
        m.insert("constraints".into(), json::constraints_json(scene));
    }
    if scene.dimensions_checked {
        m.insert(
            "dimensions".into(),
            dimensions_json(&scene.dimension_report()?),
        );
    }
    Ok(json::json_string(m))
}

/// [`run_unbounded`] once the scene is parsed, its assumptions in force.
fn run_scene(
    cmd: Command,
    scene: &Scene,
    fmt: Format,
    opts: &CommandOptions,
) -> Result<(String, Vec<Diagnostic>), Diagnostic> {
    let set = &opts.set;
    crate::scene::given::parameter_signs(scene, set)?;
    let json_string = |m| scene_json(scene, m);
    let out = match cmd {
        Command::Derive => {
            let lag = scene.lagrange()?;
            match fmt {
                Format::Text => text::bodies_text(scene) + &derive_text(&lag),
                Format::Json => json_string(derive_json(&lag))?,
                Format::Latex => latex::write(scene, |w| w.derive(&lag)),
            }
        }
        Command::Solve => solve_output(scene, fmt)?,
        Command::Forces => {
            let q = crate::mechanics::generalized_forces(scene);
            if scene.coordinates.is_empty() {
                return Err(Diagnostic::global(
                    "the scene declares no coordinates, so there are no generalized forces",
                )
                .with_hint("declare the generalized coordinates with `coordinates q1, q2, …`"));
            }
            let names: Vec<String> = scene.coordinates.iter().map(|c| c.name.clone()).collect();
            match fmt {
                Format::Text => forces_text(&names, &q),
                Format::Latex => latex::write(scene, |w| w.forces(&names, &q)),
                Format::Json => {
                    let mut m = Map::new();
                    m.insert("coordinates".into(), json!(names));
                    m.insert("generalized_forces".into(), named(&names, &q));
                    json_string(m)?
                }
            }
        }
        Command::Modes => {
            check_set(scene, set)?;
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
            let md = crate::solve::oscillations::modes(scene, at.as_deref(), set)?;
            // exact when it can be, else numeric at the --set values
            let (free, numeric) = match &opts.init {
                Some(i) => {
                    use crate::solve::oscillations as osc;
                    let (q0, v0) = scene.initial_conditions(i)?;
                    match osc::free_response(&md, &q0, &v0) {
                        Ok(f) => (Some(f), None),
                        Err(_) if !md.gyroscopic && !set.is_empty() => {
                            (None, Some(osc::numeric_free_response(&md, set, &q0, &v0)?))
                        }
                        Err(e) => return Err(e),
                    }
                }
                None => (None, None),
            };
            match fmt {
                Format::Text => modes_text(&md, set, free.as_deref(), numeric.as_ref()),
                Format::Json => {
                    json_string(modes_json(&md, set, free.as_deref(), numeric.as_ref()))?
                }
                Format::Latex => {
                    let body = latex::write(scene, |w| w.modes(&md));
                    if opts.standalone {
                        latex::standalone(&opts.title, &body)
                    } else {
                        body
                    }
                }
            }
        }
        Command::Equilibrium => {
            check_set(scene, set)?;
            let eq = equilibrium::equilibria(scene, set)?;
            match fmt {
                Format::Text => equilibrium_text(&eq),
                Format::Json => json_string(equilibrium_json(&eq))?,
                Format::Latex => latex::write(scene, |w| w.equilibrium(&eq)),
            }
        }
        Command::Hamilton | Command::Integrals => beyond_lagrange(cmd, scene, fmt)?,
        Command::Latex => {
            check_set(scene, set)?;
            latex::document(scene, opts)?
        }
        Command::Check => {
            let report = scene.dimension_report()?;
            match fmt {
                Format::Json => json::json_string(check_json(scene, &report)),
                _ => check_text(scene, &report),
            }
        }
    };
    let mut warnings = scene.warnings.clone();
    if cmd == Command::Modes {
        warnings.extend(matrix_name_clashes(scene));
    }
    Ok((out, warnings))
}

/// The names `modes` gives its own matrices: a parameter with one of them
/// would read as the matrix in M·q̈ + C·q̇ + K·q = f(t).
const MODES_MATRIX_NAMES: [(&str, &str); 3] = [("M", "mass"), ("C", "damping"), ("K", "stiffness")];

/// A warning for each parameter named like one of `modes`' matrices.
fn matrix_name_clashes(scene: &Scene) -> Vec<Diagnostic> {
    scene
        .parameters
        .iter()
        .filter_map(|p| {
            let (_, what) = MODES_MATRIX_NAMES.iter().find(|(n, _)| *n == p.name)?;
            Some(
                Diagnostic::warning(
                    p.span,
                    format!(
                        "the parameter `{}` has the name of the {what} matrix {} of `modes`' output",
                        p.name, p.name
                    ),
                )
                .with_hint(format!(
                    "the output writes M·q̈ + C·q̇ + K·q = f(t); a name like {}0 tells them apart",
                    p.name
                )),
            )
        })
        .collect()
}

/// `qdot solve`: the accelerations (and multipliers, and the constraints'
/// reactions) and the `solve` blocks' solutions.
fn solve_output(scene: &Scene, fmt: Format) -> Result<String, Diagnostic> {
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
    let reactions = match &lag {
        Some((_, acc)) => crate::solve::constrained::reaction_forces(scene, acc)?,
        None => Vec::new(),
    };
    let blocks = system::solve_scene(scene)?;
    Ok(match fmt {
        Format::Text => {
            let mut out = match &lag {
                Some((l, acc)) => {
                    text::bodies_text(scene)
                        + &solve_text(l, acc)
                        + &text::reactions_text(scene, &reactions)
                }
                None => String::new(),
            };
            if !blocks.is_empty() {
                if !out.is_empty() {
                    out.push('\n');
                }
                out.push_str(&solutions_text(scene, &blocks));
            }
            out
        }
        Format::Latex => latex::write(scene, |w| {
            if let Some((l, acc)) = &lag {
                w.equations(l);
                w.accelerations(acc);
            }
            w.blocks(scene, &blocks);
        }),
        Format::Json => {
            let mut m = match &lag {
                Some((l, acc)) => solve_json(l, acc),
                None => Map::new(),
            };
            if !reactions.is_empty() {
                m.insert("reactions".into(), json::reactions_json(scene, &reactions));
            }
            if !blocks.is_empty() {
                solutions_json(scene, &blocks, &mut m);
            }
            scene_json(scene, m)?
        }
    })
}

/// `hamilton` and `integrals`: Hamilton's equations, the integrals of
/// motion.
fn beyond_lagrange(cmd: Command, scene: &Scene, fmt: Format) -> Result<String, Diagnostic> {
    if cmd == Command::Hamilton {
        let h = crate::mechanics::Hamiltonian::derive(scene)?;
        return Ok(match fmt {
            Format::Text => text::hamilton_text(&h),
            Format::Json => scene_json(scene, json::hamilton_json(&h))?,
            Format::Latex => latex::write(scene, |w| w.hamilton(&h)),
        });
    }
    let i = crate::mechanics::Integrals::find(scene)?;
    Ok(match fmt {
        Format::Text => text::integrals_text(&i),
        Format::Json => scene_json(scene, json::integrals_json(&i))?,
        Format::Latex => latex::write(scene, |w| w.integrals(&i)),
    })
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
pub use crate::scene::given::parameter_values_any_sign as parse_set_any_sign;

/// Output format.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// Plain text with Unicode notation (θ̈₃, ·, −).
    Text,
    /// JSON, expressions as strings in qdot's input syntax.
    Json,
    /// amsmath LaTeX (see [`latex`]).
    Latex,
}

/// An expression in qdot's input syntax (JSON strings re-parse to it).
fn as_input(e: &Expr) -> String {
    print::input(e)
}

/// An expression as the text output writes it (Unicode names, `·`, `−`).
fn as_unicode(e: &Expr) -> String {
    print::unicode(e)
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

/// What a numeric search of equilibria cannot promise, said by every
/// format: `None` for positions in closed form (or none found).
pub(super) fn search_caveat(eq: &equilibrium::Equilibria) -> Option<&'static str> {
    if eq.exact || eq.equilibria.is_empty() {
        None
    } else if eq.coordinates.len() == 1 {
        Some("found by Newton's method from many starting points: roots far from them may be missed; digits shown are certified by a sign change")
    } else {
        Some(
            "found by Newton's method from many starting points: roots far from them may be missed",
        )
    }
}

/// Why a numeric position's digits are not certified, when they are not.
pub(super) fn uncertified_note(e: &equilibrium::Equilibrium) -> Option<&'static str> {
    match (&e.position, &e.certified) {
        (Position::Numeric(xs), None) => Some(if xs.len() == 1 {
            "not certified: no sign change of the condition found around it (a multiple root, or one lost in rounding); 6 digits shown"
        } else {
            "not certified (several coordinates: qdot encloses roots of one equation only); 6 digits shown"
        }),
        _ => None,
    }
}

/// A number with the typographic minus of the text output.
pub(super) fn minus(s: String) -> String {
    match s.strip_prefix('-') {
        Some(r) => format!("−{r}"),
        None => s,
    }
}
