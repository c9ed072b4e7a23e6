//! The JSON of every command as typed wire structs: one struct per JSON
//! object, its fields the keys in the order they are written. The keys are
//! a public contract (scripts depend on them; the book's CLI chapter
//! lists them): each struct's documentation is where its keys are
//! documented. Every expression string is in qdot's input syntax and
//! re-parses to the same expression; a key documented "absent" is left
//! out, one documented "null" is written as `null`.

use super::dimensions::results;
use super::{as_input, position_strings};
use crate::diag::Diagnostic;
use crate::expr::Expr;
use crate::mechanics::{Accelerations, Hamiltonian, Integrals, Lagrange};
use crate::scene::dimension::{Dimension, DimensionReport, DimensionSource, DimensionedName};
use crate::scene::Scene;
use crate::solve::equilibrium::{self, Equilibria, Position, Values};
use crate::solve::oscillations::{self as osc, Modes, NumericFree, StandardForm};
use crate::solve::system::{self, BlockSolution};
use serde::ser::{SerializeMap, Serializer};
use serde::Serialize;

/// `value` as pretty JSON (two-space indent) and a final newline.
pub(super) fn json_string(value: &impl Serialize) -> String {
    let mut s = serde_json::to_string_pretty(value).unwrap_or_default();
    s.push('\n');
    s
}

/// A JSON object keyed by names (coordinates, unknowns, multipliers), in
/// insertion order; a name given twice keeps its first place and its last
/// value, as a JSON object built key by key does.
#[derive(Clone, Debug, PartialEq)]
pub struct Named<V>(Vec<(String, V)>);

impl<V> Named<V> {
    fn insert(&mut self, name: String, value: V) {
        match self.0.iter_mut().find(|(n, _)| *n == name) {
            Some(slot) => slot.1 = value,
            None => self.0.push((name, value)),
        }
    }
}

impl<V> Default for Named<V> {
    fn default() -> Self {
        Named(Vec::new())
    }
}

impl<V> FromIterator<(String, V)> for Named<V> {
    fn from_iter<I: IntoIterator<Item = (String, V)>>(iter: I) -> Self {
        let mut m = Named::default();
        for (n, v) in iter {
            m.insert(n, v);
        }
        m
    }
}

impl<V: Serialize> Serialize for Named<V> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut m = s.serialize_map(Some(self.0.len()))?;
        for (n, v) in &self.0 {
            m.serialize_entry(n, v)?;
        }
        m.end()
    }
}

/// name → expression, pairing `names` with `es`.
fn named(names: &[String], es: &[Expr]) -> Named<String> {
    names.iter().cloned().zip(es.iter().map(as_input)).collect()
}

/// name → expression, from pairs.
fn named_pairs(pairs: &[(String, Expr)]) -> Named<String> {
    pairs
        .iter()
        .map(|(n, e)| (n.clone(), as_input(e)))
        .collect()
}

fn inputs(es: &[Expr]) -> Vec<String> {
    es.iter().map(as_input).collect()
}

fn matrix(m: &[Vec<Expr>]) -> Vec<Vec<String>> {
    m.iter().map(|r| inputs(r)).collect()
}

/// A command's object followed by the keys every command of its scene
/// carries ([`SceneJson`]).
#[derive(Serialize)]
pub struct WithScene<T> {
    /// The command's own keys.
    #[serde(flatten)]
    pub command: T,
    /// `bodies`, `constraints`, `dimensions`, after the command's keys.
    #[serde(flatten)]
    pub scene: SceneJson,
}

/// The keys every command but `check` adds for its scene, after its own.
#[derive(Serialize)]
pub struct SceneJson {
    /// For a scene with `body`, `particle` or `gravity` statements: one
    /// [`BodyJson`] per body in statement order; absent otherwise.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub bodies: Option<Vec<BodyJson>>,
    /// For a scene with `constraint` statements: one [`ConstraintJson`]
    /// per constraint, in order; absent otherwise.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub constraints: Option<Vec<ConstraintJson>>,
    /// For a scene that annotates a dimension (always last): coordinate,
    /// parameter, `solve` unknown → dimension in annotation syntax, or null
    /// where the scene leaves one free; absent otherwise.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub dimensions: Option<Named<Option<String>>>,
}

impl SceneJson {
    /// The scene keys of `scene` (its dimension report, when annotated).
    pub fn new(scene: &Scene) -> Result<SceneJson, Diagnostic> {
        Ok(SceneJson {
            bodies: non_empty(BodyJson::all(scene)),
            constraints: non_empty(ConstraintJson::all(scene)),
            dimensions: match scene.dimensions_checked {
                true => Some(dimensions(&scene.dimension_report()?)),
                false => None,
            },
        })
    }
}

/// `v`, or `None` when it is empty (a key left out).
fn non_empty<T>(v: Vec<T>) -> Option<Vec<T>> {
    (!v.is_empty()).then_some(v)
}

/// A body: its kinetic energy and, under gravity, its potential.
#[derive(Serialize)]
pub struct BodyJson {
    /// The body's name.
    pub name: String,
    /// `"body"` or `"particle"`.
    pub kind: &'static str,
    /// The line of its statement (1-based).
    pub line: usize,
    /// The definition that holds its kinetic energy, or null.
    pub kinetic: Option<EnergyJson>,
    /// The definition that holds its potential under gravity, or null.
    pub potential: Option<EnergyJson>,
}

/// A definition holding an energy.
#[derive(Serialize)]
pub struct EnergyJson {
    /// The definition's name.
    pub name: String,
    /// Its value.
    pub value: String,
}

impl BodyJson {
    fn all(scene: &Scene) -> Vec<BodyJson> {
        let energy = |name: &str| {
            scene.definition(name).map(|value| EnergyJson {
                name: name.to_string(),
                value: as_input(value),
            })
        };
        scene
            .bodies
            .iter()
            .map(|b| BodyJson {
                name: b.name.clone(),
                kind: b.kind.keyword(),
                line: crate::diag::Diagnostic::line_col(&scene.source, b.span.start).0,
                kinetic: energy(&b.kinetic),
                potential: b.gravity.as_deref().and_then(energy),
            })
            .collect()
    }
}

/// A constraint a·q̇ + b = 0.
#[derive(Serialize)]
pub struct ConstraintJson {
    /// The name after `constraint`, or null.
    pub name: Option<String>,
    /// Its multiplier's name.
    pub multiplier: String,
    /// `"holonomic"` or `"velocity"`.
    pub kind: &'static str,
    /// lhs − rhs as written.
    pub expression: String,
    /// a, one coefficient per coordinate.
    pub coefficients: Vec<String>,
    /// b.
    pub rest: String,
}

impl ConstraintJson {
    fn all(scene: &Scene) -> Vec<ConstraintJson> {
        scene
            .constraints
            .iter()
            .map(|c| ConstraintJson {
                name: c.name.clone(),
                multiplier: c.multiplier.clone(),
                kind: if c.holonomic { "holonomic" } else { "velocity" },
                expression: as_input(&c.expression),
                coefficients: inputs(&c.coefficients),
                rest: as_input(&c.rest),
            })
            .collect()
    }
}

/// `qdot derive`.
#[derive(Serialize)]
pub struct DeriveJson {
    /// The named intermediates the expressions below are written through,
    /// in evaluation order (each uses only the names before it); absent
    /// when the results are expanded.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub intermediates: Option<Vec<IntermediateJson>>,
    /// The coordinates, in declaration order.
    pub coordinates: Vec<String>,
    /// Lagrange's equations, one per coordinate.
    pub equations: Vec<EquationJson>,
    /// M, row by row.
    pub mass_matrix: Vec<Vec<String>>,
    /// f, one entry per coordinate.
    pub forcing: Vec<String>,
}

/// One of Lagrange's equations, lhs = rhs.
#[derive(Serialize)]
pub struct EquationJson {
    /// The coordinate it belongs to.
    pub coordinate: String,
    /// d/dt(∂E/∂q̇) − ∂E/∂q.
    pub lhs: String,
    /// The generalized force Q.
    pub rhs: String,
}

/// One named intermediate: `name = value`.
#[derive(Serialize)]
pub struct IntermediateJson {
    /// Its name, an identifier (`B2_13`, `P1_x_dot`).
    pub name: String,
    /// Its value, in the names before it.
    pub value: String,
}

/// The entries of `tape` that `roots` use, in order; `None` when none.
fn intermediates_json<'a>(
    tape: Option<&crate::expr::tape::Tape>,
    roots: impl IntoIterator<Item = &'a Expr>,
) -> Option<Vec<IntermediateJson>> {
    let tape = tape?;
    let used = tape.used_by(roots);
    (!used.is_empty()).then(|| {
        used.into_iter()
            .map(|i| {
                let e = &tape.entries()[i];
                IntermediateJson {
                    name: e.input_name(),
                    value: as_input(&e.value),
                }
            })
            .collect()
    })
}

/// Every expression of `l` that the output prints.
pub(crate) fn lagrange_exprs(l: &Lagrange) -> impl Iterator<Item = &Expr> {
    l.equations
        .iter()
        .flat_map(|e| [&e.lhs, &e.rhs])
        .chain(l.mass_matrix.iter().flatten())
        .chain(&l.forcing)
}

/// The tape a result is written through, and every expression that
/// output prints with it: with dynamics (`l`), the scene's energies (its
/// bodies'), the equations and the accelerations when there are; and the
/// `solve` blocks' solutions. `None` when nothing is written through one.
pub(crate) fn structured_roots<'a>(
    scene: &'a Scene,
    l: Option<&'a Lagrange>,
    acc: Option<&'a Accelerations>,
    blocks: &'a [BlockSolution],
) -> Option<(&'a crate::expr::tape::Tape, Vec<&'a Expr>)> {
    // the accelerations' tape extends the equations', which extends the scene's
    let tape = acc
        .and_then(Accelerations::intermediates)
        .or(l.and_then(|l| l.intermediates.as_deref()))
        .or(scene.tape.as_ref())?;
    let mut roots: Vec<&Expr> = Vec::new();
    if let Some(l) = l {
        let energies = scene.definitions.iter().filter(|d| d.role.is_some());
        roots.extend(energies.flat_map(|d| d.value.components()));
        roots.extend(lagrange_exprs(l));
    }
    roots.extend(acc.map_or(&[][..], |a| a.values()));
    roots.extend(blocks.iter().flat_map(|b| b.values.iter().map(|(_, v)| v)));
    Some((tape, roots))
}

/// The intermediates of [`structured_roots`] as JSON.
fn structured_json(
    scene: &Scene,
    l: Option<&Lagrange>,
    acc: Option<&Accelerations>,
    blocks: &[BlockSolution],
) -> Option<Vec<IntermediateJson>> {
    let (tape, roots) = structured_roots(scene, l, acc, blocks)?;
    intermediates_json(Some(tape), roots)
}

impl DeriveJson {
    /// The JSON of `derive` for `l` (on `scene`, whose energies it may
    /// write through the same intermediates).
    pub fn new(scene: &Scene, l: &Lagrange) -> DeriveJson {
        DeriveJson {
            intermediates: structured_json(scene, Some(l), None, &[]),
            ..DeriveJson::expressions(l)
        }
    }

    /// The keys after `intermediates`.
    fn expressions(l: &Lagrange) -> DeriveJson {
        DeriveJson {
            intermediates: None,
            coordinates: l.coordinates.clone(),
            equations: l
                .equations
                .iter()
                .map(|e| EquationJson {
                    coordinate: e.coordinate.clone(),
                    lhs: as_input(&e.lhs),
                    rhs: as_input(&e.rhs),
                })
                .collect(),
            mass_matrix: matrix(&l.mass_matrix),
            forcing: inputs(&l.forcing),
        }
    }
}

/// `qdot solve` on a scene with dynamics: [`DeriveJson`]'s keys, then the
/// accelerations.
#[derive(Serialize)]
pub struct DynamicsJson {
    /// `derive`'s keys.
    #[serde(flatten)]
    pub derive: DeriveJson,
    /// coordinate → q̈.
    pub accelerations: Named<String>,
    /// With constraints: multiplier → λ; absent otherwise.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub multipliers: Option<Named<String>>,
}

impl DynamicsJson {
    /// The JSON of `solve`'s dynamics: `l` and its accelerations `acc`.
    pub fn new(scene: &Scene, l: &Lagrange, acc: &Accelerations) -> DynamicsJson {
        DynamicsJson {
            derive: DeriveJson {
                intermediates: structured_json(scene, Some(l), Some(acc), &[]),
                ..DeriveJson::expressions(l)
            },
            ..DynamicsJson::expressions(l, acc)
        }
    }

    /// The keys without `intermediates` (`solve` lists them first).
    fn expressions(l: &Lagrange, acc: &Accelerations) -> DynamicsJson {
        let multipliers = acc.multipliers();
        DynamicsJson {
            derive: DeriveJson::expressions(l),
            accelerations: acc
                .into_iter()
                .map(|(q, e)| (q.to_string(), as_input(e)))
                .collect(),
            multipliers: (!multipliers.is_empty()).then(|| named_pairs(multipliers)),
        }
    }
}

/// `qdot solve`: [`DynamicsJson`]'s keys when the scene has dynamics,
/// `reactions`, then [`BlocksJson`]'s keys when it has `solve` blocks;
/// `intermediates` first when any of them is written through some.
#[derive(Serialize)]
pub struct SolveJson {
    /// The named intermediates of everything below, in evaluation order;
    /// absent when the results are expanded.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub intermediates: Option<Vec<IntermediateJson>>,
    /// The equations and accelerations; absent without dynamics.
    #[serde(flatten)]
    pub dynamics: Option<DynamicsJson>,
    /// One [`ReactionJson`] per `reaction` statement; absent without.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reactions: Option<Vec<ReactionJson>>,
    /// The `solve` blocks' solutions; absent without blocks.
    #[serde(flatten)]
    pub blocks: Option<BlocksJson>,
    /// A driven mechanism's equations and reactions; absent otherwise.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mechanism: Option<MechanismJson>,
}

/// A driven mechanism in `solve`'s JSON.
#[derive(Serialize)]
pub struct MechanismJson {
    /// `derive`'s keys: the equations, M and f.
    #[serde(flatten)]
    pub derive: DeriveJson,
    /// Every reaction component and drive force → its value, in solving
    /// order when `in_order` (each may use those before it, the
    /// accelerations and the frictions).
    pub reactions: Named<String>,
    /// Whether `reactions` are in solving order.
    pub in_order: bool,
    /// The frictions' laws.
    pub friction: Vec<FrictionJson>,
}

/// `NAME_f = −c·N·sgn(v)`: one friction's law.
#[derive(Serialize)]
pub struct FrictionJson {
    /// The friction's name (`G_f`).
    pub name: String,
    /// The coefficient c.
    pub coefficient: String,
    /// The reaction components whose magnitude N is: one (|N|) or two
    /// (√(x² + y²)).
    pub normal: Vec<String>,
    /// The relative velocity whose sense it opposes.
    pub relative_velocity: String,
}

impl MechanismJson {
    /// The JSON of a driven mechanism's `solve`.
    pub fn new(l: &Lagrange, r: &crate::solve::kinetostatic::MechanismReactions) -> MechanismJson {
        let mut reactions = Named::default();
        for (n, v) in &r.values {
            reactions.insert(n.clone(), as_input(v));
        }
        MechanismJson {
            derive: DeriveJson::expressions(l),
            reactions,
            in_order: r.in_order,
            friction: r
                .friction
                .iter()
                .map(|f| FrictionJson {
                    name: f.name.clone(),
                    coefficient: as_input(&f.coefficient),
                    normal: f.normal.clone(),
                    relative_velocity: as_input(&f.relative_velocity),
                })
                .collect(),
        }
    }
}

impl SolveJson {
    /// The JSON of `solve` on `scene`.
    pub fn new(
        scene: &Scene,
        dynamics: Option<&(Lagrange, Accelerations)>,
        reactions: &[Vec<Expr>],
        blocks: &[BlockSolution],
    ) -> SolveJson {
        // one list for the whole output, first
        let (l, acc) = (dynamics.map(|d| &d.0), dynamics.map(|d| &d.1));
        SolveJson {
            intermediates: structured_json(scene, l, acc, blocks),
            dynamics: dynamics.map(|(l, acc)| DynamicsJson::expressions(l, acc)),
            reactions: (!reactions.is_empty()).then(|| ReactionJson::all(scene, reactions)),
            blocks: (!blocks.is_empty()).then(|| BlocksJson::new(scene, blocks)),
            mechanism: None,
        }
    }
}

/// The force a constraint exerts at a point.
#[derive(Serialize)]
pub struct ReactionJson {
    /// The constraint's name.
    pub constraint: Option<String>,
    /// The point as written.
    pub point: String,
    /// The force, component by component.
    pub force: Vec<String>,
}

impl ReactionJson {
    fn all(scene: &Scene, forces: &[Vec<Expr>]) -> Vec<ReactionJson> {
        scene
            .reactions
            .iter()
            .zip(forces)
            .map(|(r, f)| ReactionJson {
                constraint: scene.constraints[r.constraint].name.clone(),
                point: r.written.clone(),
                force: inputs(f),
            })
            .collect()
    }
}

/// The `solve` blocks' solutions.
#[derive(Serialize)]
pub struct BlocksJson {
    /// unknown → value (free unknowns left out).
    pub solutions: Named<String>,
    /// The unknowns the equations leave free.
    pub free_unknowns: Vec<String>,
    /// The equations implied by the others.
    pub checks: Vec<CheckedEquationJson>,
}

/// An equation implied by the others of its block.
#[derive(Serialize)]
pub struct CheckedEquationJson {
    /// The block (1-based).
    pub block: usize,
    /// The equation in its block (1-based).
    pub equation: usize,
    /// For a vector equation: `"x"`, `"y"` or `"z"`; absent otherwise.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub component: Option<&'static str>,
}

impl BlocksJson {
    /// The solutions of `scene`'s blocks.
    pub fn new(scene: &Scene, blocks: &[BlockSolution]) -> BlocksJson {
        let mut out = BlocksJson {
            solutions: Named::default(),
            free_unknowns: Vec::new(),
            checks: Vec::new(),
        };
        for (b, (sys, sol)) in scene.systems.iter().zip(blocks).enumerate() {
            for (n, v) in &sol.values {
                if !sol.free.contains(n) {
                    out.solutions.insert(n.clone(), as_input(v));
                }
            }
            out.free_unknowns.extend(sol.free.iter().cloned());
            for &i in &sol.checks {
                out.checks.push(CheckedEquationJson {
                    block: b + 1,
                    equation: system::equation_number(sys, i),
                    component: sys.equations[i]
                        .component
                        .map(|k| ["x", "y", "z"][k.min(2)]),
                });
            }
        }
        out
    }
}

/// `qdot forces`.
#[derive(Serialize)]
pub struct ForcesJson {
    /// The named intermediates the bodies' energies (under `bodies`) are
    /// written through, for a scene read with its kinematics kept; absent
    /// otherwise. The generalized forces are always expanded.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub intermediates: Option<Vec<IntermediateJson>>,
    /// The coordinates.
    pub coordinates: Vec<String>,
    /// coordinate → Q.
    pub generalized_forces: Named<String>,
}

impl ForcesJson {
    /// The JSON of `forces` on `scene`: `q` parallel to `coordinates`.
    pub fn new(scene: &Scene, coordinates: &[String], q: &[Expr]) -> ForcesJson {
        let energies = scene.definitions.iter().filter(|d| d.role.is_some());
        ForcesJson {
            intermediates: intermediates_json(
                scene.tape.as_ref(),
                energies.flat_map(|d| d.value.components()),
            ),
            coordinates: coordinates.to_vec(),
            generalized_forces: named(coordinates, q),
        }
    }
}

/// A coordinate's value at an equilibrium.
#[derive(Serialize)]
#[serde(untagged)]
pub enum PositionJson {
    /// Found numerically: a number.
    Number(f64),
    /// In closed form: an expression, or `"any"` for a free coordinate.
    Exact(String),
}

/// `qdot equilibrium`. The lists from `equilibria` to `enclosure` are
/// parallel: one entry per equilibrium.
#[derive(Serialize)]
pub struct EquilibriumJson {
    /// The coordinates.
    pub coordinates: Vec<String>,
    /// coordinate → Q at rest.
    pub generalized_forces: Named<String>,
    /// coordinate → the condition of equilibrium.
    pub conditions: Named<String>,
    /// Whether the positions are in closed form.
    pub exact: bool,
    /// coordinate → value per equilibrium.
    pub equilibria: Vec<Named<PositionJson>>,
    /// `"stable"`, `"unstable"` or `"undecided"`.
    pub stability: Vec<&'static str>,
    /// Existence conditions, the reason when undecided, why digits are not
    /// certified, joined by "; " (empty when none).
    pub notes: Vec<String>,
    /// The numeric values of an exact position under `--set`, else null.
    pub approx: Vec<Option<Vec<f64>>>,
    /// The multiplicity of each root.
    pub multiplicity: Vec<u32>,
    /// A numeric position's digits as the text prints them (certified, else
    /// 6 significant); null for an exact one.
    pub digits: Vec<Option<Vec<String>>>,
    /// Whether a numeric position's digits are certified; null for an
    /// exact one.
    pub certified: Vec<Option<bool>>,
    /// coordinate → `[lo, hi]`, an interval certified to hold the root; or
    /// null.
    pub enclosure: Vec<Option<Named<[f64; 2]>>>,
    /// Whether `caveat` is null: the positions are in closed form (or none
    /// was found).
    pub complete: bool,
    /// What a numeric search cannot promise, or null.
    pub caveat: Option<&'static str>,
    /// With constraints: multiplier → λ per equilibrium; absent otherwise.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub multipliers: Option<Vec<Named<String>>>,
    /// `--steady`: steady coordinate → its rate (the symbol `phi'`); the
    /// positions are steady motions of the other coordinates. Absent for
    /// equilibria.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub steady: Option<Named<String>>,
}

impl EquilibriumJson {
    /// The JSON of `equilibrium` for `eq`.
    pub fn new(eq: &Equilibria) -> EquilibriumJson {
        let list = &eq.equilibria;
        EquilibriumJson {
            coordinates: eq.coordinates.clone(),
            generalized_forces: named(&eq.coordinates, &eq.forces),
            conditions: named(&eq.coordinates, &eq.conditions),
            exact: eq.exact,
            equilibria: list.iter().map(|e| position(eq, e)).collect(),
            stability: list.iter().map(|e| e.stability.word()).collect(),
            notes: list.iter().map(notes).collect(),
            approx: list.iter().map(|e| e.approx.clone()).collect(),
            multiplicity: list.iter().map(|e| e.multiplicity).collect(),
            digits: list.iter().map(digits).collect(),
            certified: list
                .iter()
                .map(|e| {
                    matches!(e.position, Position::Numeric(_)).then_some(e.certified.is_some())
                })
                .collect(),
            enclosure: list
                .iter()
                .map(|e| match (e.enclosure, eq.coordinates.first()) {
                    (Some((lo, hi)), Some(c)) => Some(Named(vec![(c.clone(), [lo, hi])])),
                    _ => None,
                })
                .collect(),
            complete: super::search_caveat(eq).is_none(),
            caveat: super::search_caveat(eq),
            multipliers: list
                .iter()
                .any(|e| !e.multipliers.is_empty())
                .then(|| list.iter().map(|e| named_pairs(&e.multipliers)).collect()),
            steady: (!eq.steady.is_empty()).then(|| named_pairs(&eq.steady)),
        }
    }
}

fn position(eq: &Equilibria, e: &equilibrium::Equilibrium) -> Named<PositionJson> {
    match &e.position {
        Position::Numeric(xs) => eq
            .coordinates
            .iter()
            .cloned()
            .zip(xs.iter().map(|x| PositionJson::Number(*x)))
            .collect(),
        Position::Exact(_) => eq
            .coordinates
            .iter()
            .cloned()
            .zip(
                position_strings(eq, e, &as_input)
                    .into_iter()
                    .map(PositionJson::Exact),
            )
            .collect(),
    }
}

/// The digits the text prints: certified, else 6 significant.
fn digits(e: &equilibrium::Equilibrium) -> Option<Vec<String>> {
    match (&e.position, &e.certified) {
        (Position::Numeric(_), Some(d)) => Some(d.clone()),
        (Position::Numeric(xs), None) => Some(
            xs.iter()
                .map(|x| crate::solve::certify::significant(*x, 6))
                .collect(),
        ),
        (Position::Exact(_), _) => None,
    }
}

fn notes(e: &equilibrium::Equilibrium) -> String {
    let mut n: Vec<String> = e
        .conditions
        .iter()
        .map(|c| format!("exists when {c}"))
        .collect();
    if let equilibrium::Stability::Undecided(why) = &e.stability {
        n.push(why.clone());
    }
    n.extend(super::uncertified_note(e).map(String::from));
    n.join("; ")
}

/// `qdot modes`: the small oscillations about `at`.
#[derive(Serialize)]
pub struct ModesJson {
    /// The coordinates.
    pub coordinates: Vec<String>,
    /// coordinate → its value at the equilibrium.
    pub at: Named<String>,
    /// With constraints: dependent coordinate → its value; absent without.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub dependent: Option<Named<String>>,
    /// M, row by row.
    pub mass_matrix: Vec<Vec<String>>,
    /// K, row by row.
    pub stiffness_matrix: Vec<Vec<String>>,
    /// C, row by row.
    pub damping_matrix: Vec<Vec<String>>,
    /// The forcing, one entry per coordinate.
    pub forcing: Vec<String>,
    /// det(K − ω²M), expanded.
    pub characteristic_polynomial: String,
    /// Its factors.
    pub characteristic_factors: Vec<String>,
    /// Whether C is skew and not zero (a spinning rotor, a rotating frame):
    /// then `modes` is empty (the modes are complex).
    pub gyroscopic: bool,
    /// ω² per mode, term by term over a monomial denominator.
    pub omega_squared: Vec<String>,
    /// The mode shapes.
    pub modes: Vec<Vec<String>>,
    /// Why `omega_squared` is empty, or null.
    pub no_closed_form: Option<String>,
    /// `"stable"`, `"unstable"` or `"undecided"`.
    pub stability: &'static str,
    /// Why, when undecided; else null.
    pub stability_note: Option<String>,
    /// One coordinate: ÿ + 2αẏ + ω²y = f as [`StandardFormJson`]; else null.
    pub standard_form: Option<StandardFormJson>,
    /// ω² evaluated at the `--set` values, or null.
    pub numeric_omega_squared: Option<Vec<f64>>,
    /// The numeric mode shapes, or null.
    pub numeric_modes: Option<Vec<Vec<f64>>>,
    /// Why there are no numeric modes, or null.
    pub numeric_modes_note: Option<String>,
    /// With `--init`: coordinate → q(t) in closed form; else null.
    pub free_response: Option<Named<String>>,
    /// Without closed forms: coordinate → q(t) with decimal numbers (10
    /// significant digits) at the `--set` values; else null.
    pub numeric_free_response: Option<Named<String>>,
    /// The steady response to f = F·cos(p·t), or null.
    pub forced_response: Option<ForcedJson>,
    /// About a steady motion (`--steady`): [`SteadyMotionJson`]; absent
    /// about an equilibrium.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub steady_motion: Option<SteadyMotionJson>,
}

/// The steady motion `modes --steady` linearizes about.
#[derive(Serialize)]
pub struct SteadyMotionJson {
    /// steady coordinate → its rate (`phi'` itself where it was found
    /// from the conditions).
    pub rates: Named<String>,
    /// coordinate → its equation at the steady motion, which must vanish
    /// (only those that do not vanish by themselves).
    pub conditions: Named<String>,
    /// The rates solved from the conditions, in order.
    pub solved: Vec<SolvedRateJson>,
    /// coordinate → its equation at the steady motion where it holds no
    /// unknown rate and vanishes only at the `--set` values.
    pub held: Named<String>,
}

/// A rate solved from a steady motion's condition.
#[derive(Serialize)]
pub struct SolvedRateJson {
    /// The steady coordinate.
    pub coordinate: String,
    /// Whether `value` is the rate's square.
    pub squared: bool,
    /// The rate, or its square.
    pub value: String,
    /// The other roots of a condition quadratic in the rate (the analysis
    /// is about `value`).
    pub others: Vec<String>,
}

/// One coordinate's equation ÿ + 2αẏ + ω²y = f.
#[derive(Serialize)]
pub struct StandardFormJson {
    /// ω².
    pub omega_squared: String,
    /// α.
    pub alpha: String,
    /// ζ, or null.
    pub zeta: Option<String>,
    /// f.
    pub forcing: String,
    /// `"undamped"`, `"underdamped"`, `"critically damped"`,
    /// `"overdamped"` or `"undecided"`.
    pub regime: String,
}

/// The steady response to f = F·cos(p·t).
#[derive(Serialize)]
#[serde(untagged)]
pub enum ForcedJson {
    /// Undamped: the amplitudes (K − p²M)⁻¹·F.
    Undamped {
        /// p.
        p: String,
        /// coordinate → amplitude.
        amplitudes: Named<String>,
    },
    /// One damped coordinate: amplitude X and tan ψ.
    Damped {
        /// p.
        p: String,
        /// X.
        amplitude: String,
        /// tan ψ.
        tan_psi: String,
    },
}

impl ModesJson {
    /// The JSON of `modes`: `free` the closed-form free response,
    /// `numeric` the numeric one.
    pub fn new(
        md: &Modes,
        set: &Values,
        free: Option<&[Expr]>,
        numeric: Option<&NumericFree>,
    ) -> ModesJson {
        use crate::expr::print::expanded_input;
        let standard = osc::standard_form(md, set);
        let eigen_or_why = osc::numeric_modes_or_why(md, set);
        let eigen = eigen_or_why.as_ref().ok().and_then(Option::as_ref);
        ModesJson {
            coordinates: md.coordinates.clone(),
            at: named(&md.coordinates, &md.at),
            dependent: (!md.dependent.is_empty()).then(|| named_pairs(&md.dependent)),
            mass_matrix: matrix(&md.mass),
            stiffness_matrix: matrix(&md.stiffness),
            damping_matrix: matrix(&md.damping),
            forcing: inputs(&md.forcing),
            // expanded: the factored form is `characteristic_factors`
            characteristic_polynomial: crate::expr::compact::canonical_only(|| {
                as_input(&md.characteristic)
            }),
            characteristic_factors: inputs(&md.factors),
            gyroscopic: md.gyroscopic,
            omega_squared: md.omega_squared.iter().map(expanded_input).collect(),
            modes: matrix(&md.modes),
            no_closed_form: md.no_closed_form.clone(),
            stability: md.stability.word(),
            stability_note: match &md.stability {
                osc::Stability::Undecided(why) => Some(why.clone()),
                _ => None,
            },
            standard_form: standard.as_ref().map(|sf| StandardFormJson {
                omega_squared: expanded_input(&sf.omega_squared),
                alpha: expanded_input(&sf.alpha),
                zeta: sf.zeta.as_ref().map(as_input),
                forcing: as_input(&sf.forcing),
                regime: sf.regime.clone(),
            }),
            numeric_omega_squared: eigen.map(|g| g.values.clone()),
            numeric_modes: eigen.map(|g| g.vectors.clone()),
            numeric_modes_note: eigen_or_why.as_ref().err().cloned(),
            free_response: free.map(|f| named(&md.coordinates, f)),
            numeric_free_response: numeric.map(|nf| {
                md.coordinates
                    .iter()
                    .enumerate()
                    .map(|(j, c)| (c.clone(), super::modes::numeric_response(nf, j, false)))
                    .collect()
            }),
            forced_response: forced(md, standard.as_ref()),
            steady_motion: md.steady.as_ref().map(|sm| SteadyMotionJson {
                rates: named_pairs(&sm.rates),
                conditions: named_pairs(&sm.conditions),
                solved: sm
                    .solved
                    .iter()
                    .map(|s| SolvedRateJson {
                        coordinate: s.coordinate.clone(),
                        squared: s.squared,
                        value: as_input(&s.value),
                        others: s.others.iter().map(as_input).collect(),
                    })
                    .collect(),
                held: named_pairs(&sm.held),
            }),
        }
    }
}

fn forced(md: &Modes, sf: Option<&StandardForm>) -> Option<ForcedJson> {
    let damped = md.damping.iter().flatten().any(|e| !e.is_zero());
    if !damped {
        return osc::forced_amplitudes(md).map(|(p, x)| ForcedJson::Undamped {
            p: as_input(&p),
            amplitudes: named(&md.coordinates, &x),
        });
    }
    sf.and_then(|sf| osc::damped_steady_state(md, sf))
        .map(|(p, x, t)| ForcedJson::Damped {
            p: as_input(&p),
            amplitude: as_input(&x),
            tan_psi: as_input(&t),
        })
}

/// `qdot hamilton`.
#[derive(Serialize)]
pub struct HamiltonJson {
    /// The named intermediates the expressions below are written through
    /// (the velocities `v_q`), in evaluation order; absent when the
    /// results are expanded.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub intermediates: Option<Vec<IntermediateJson>>,
    /// The coordinates.
    pub coordinates: Vec<String>,
    /// coordinate → p in q, q̇.
    pub momenta: Named<String>,
    /// coordinate → q̇ in q, p.
    pub velocities: Named<String>,
    /// H(q, p, t).
    pub hamiltonian: String,
    /// Hamilton's equations, one per coordinate.
    pub equations: Vec<HamiltonEquationJson>,
    /// coordinate → Q̃, the generalized forces outside H.
    pub other_forces: Named<String>,
}

/// Hamilton's equations of one coordinate.
#[derive(Serialize)]
pub struct HamiltonEquationJson {
    /// q.
    pub coordinate: String,
    /// The name of its momentum p.
    pub momentum: String,
    /// q̇ = ∂H/∂p.
    pub qdot: String,
    /// ṗ = −∂H/∂q + Q̃.
    pub pdot: String,
}

impl HamiltonJson {
    /// The JSON of `hamilton` for `h`.
    pub fn new(h: &Hamiltonian) -> HamiltonJson {
        HamiltonJson {
            intermediates: intermediates_json(h.intermediates.as_deref(), h.exprs()),
            coordinates: h.coordinates.clone(),
            momenta: named(&h.coordinates, &h.momenta),
            velocities: named(&h.coordinates, &h.velocities),
            hamiltonian: as_input(&h.hamiltonian),
            equations: (0..h.coordinates.len())
                .map(|k| HamiltonEquationJson {
                    coordinate: h.coordinates[k].clone(),
                    momentum: h.momentum_names[k].clone(),
                    qdot: as_input(&h.velocities[k]),
                    pdot: as_input(&h.momentum_rates[k]),
                })
                .collect(),
            other_forces: named(&h.coordinates, &h.other_forces),
        }
    }
}

/// `qdot integrals`.
#[derive(Serialize)]
pub struct IntegralsJson {
    /// The coordinates.
    pub coordinates: Vec<String>,
    /// cyclic coordinate → its conserved momentum p in q, q̇.
    pub momenta: Named<String>,
    /// The cyclic coordinates.
    pub cyclic: Vec<String>,
    /// The energy integral h, or null.
    pub energy: Option<String>,
    /// Whether h is E + V.
    pub energy_is_e_plus_v: bool,
    /// Routh's function, or null without a reduction.
    pub routhian: Option<String>,
    /// The effective potential, or null without a reduction.
    pub effective_potential: Option<String>,
    /// remaining coordinate → q̈, or null without a reduction.
    pub reduced_accelerations: Option<Named<String>>,
    /// Why an integral is missing: one line each.
    pub notes: Vec<String>,
}

impl IntegralsJson {
    /// The JSON of `integrals` for `i`.
    pub fn new(i: &Integrals) -> IntegralsJson {
        let r = i.routh.as_ref();
        IntegralsJson {
            coordinates: i.coordinates.clone(),
            momenta: named_pairs(&i.cyclic),
            cyclic: i.cyclic.iter().map(|(q, _)| q.clone()).collect(),
            energy: i.energy.as_ref().map(as_input),
            energy_is_e_plus_v: i.energy_is_e_plus_v,
            routhian: r.map(|r| as_input(&r.routhian)),
            effective_potential: r.map(|r| as_input(&r.effective_potential)),
            reduced_accelerations: r.map(|r| named_pairs(&r.accelerations)),
            notes: i.notes.clone(),
        }
    }
}

fn ascii(d: Option<&Dimension>) -> Option<String> {
    d.map(Dimension::ascii)
}

/// coordinate, parameter and `solve` unknown → dimension in annotation
/// syntax, or null when the scene leaves it free.
fn dimensions(report: &DimensionReport) -> Named<Option<String>> {
    report
        .names
        .iter()
        .filter(|n| n.kind != DimensionedName::Definition)
        .map(|n| (n.name.clone(), ascii(n.dimension.as_ref())))
        .collect()
}

/// `qdot check`: dimensions as strings in annotation syntax, or null
/// where the scene leaves one free.
#[derive(Serialize)]
pub struct CheckJson {
    /// coordinate, parameter, `solve` unknown → dimension.
    pub dimensions: Named<Option<String>>,
    /// definition → dimension.
    pub definitions: Named<Option<String>>,
    /// name → `"declared"`, `"inferred"`, `"defined"` or `"free"`.
    pub sources: Named<&'static str>,
    /// coordinate → the dimension of q̈.
    pub accelerations: Named<Option<String>>,
    /// coordinate → the dimension of Q.
    pub generalized_forces: Named<Option<String>>,
}

impl CheckJson {
    /// The JSON of `check` for `scene` and its dimension `report`.
    pub fn new(scene: &Scene, report: &DimensionReport) -> CheckJson {
        let results: Vec<_> = scene
            .coordinates
            .iter()
            .map(|c| (c.name.clone(), results(report, &c.name)))
            .collect();
        CheckJson {
            dimensions: dimensions(report),
            definitions: report
                .names
                .iter()
                .filter(|n| n.kind == DimensionedName::Definition)
                .map(|n| (n.name.clone(), ascii(n.dimension.as_ref())))
                .collect(),
            sources: report
                .names
                .iter()
                .map(|n| {
                    let s = match n.source {
                        DimensionSource::Declared(_) => "declared",
                        DimensionSource::Inferred(_) => "inferred",
                        DimensionSource::Defined => "defined",
                        DimensionSource::Free => "free",
                    };
                    (n.name.clone(), s)
                })
                .collect(),
            accelerations: results
                .iter()
                .map(|(c, r)| (c.clone(), ascii(r.acceleration.as_ref())))
                .collect(),
            generalized_forces: results
                .iter()
                .map(|(c, r)| (c.clone(), ascii(r.force.as_ref())))
                .collect(),
        }
    }
}

/// The `bodies` key of `scene` as a JSON value (an empty list without
/// bodies).
pub fn bodies_json(scene: &Scene) -> serde_json::Value {
    serde_json::to_value(BodyJson::all(scene)).unwrap_or_default()
}

/// The `dimensions` key of a scene's dimension `report` as a JSON value.
pub fn dimensions_json(report: &DimensionReport) -> serde_json::Value {
    serde_json::to_value(dimensions(report)).unwrap_or_default()
}

/// The JSON of `solve`'s dynamics for `l` and its accelerations `acc`.
pub fn solve_json(l: &Lagrange, acc: &Accelerations) -> DynamicsJson {
    DynamicsJson::new(&Scene::default(), l, acc)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Keys keep their first place; a key given again takes the new value.
    #[test]
    fn named_keeps_insertion_order_and_the_last_value() {
        let m: Named<i32> = [("b", 1), ("a", 2), ("b", 3)]
            .into_iter()
            .map(|(k, v)| (k.to_string(), v))
            .collect();
        assert_eq!(serde_json::to_string(&m).unwrap(), r#"{"b":3,"a":2}"#);
    }

    /// The scene's keys follow the command's; absent ones are left out, a
    /// null one is written.
    #[test]
    fn scene_keys_follow_the_command_keys() {
        let wire = WithScene {
            command: ForcesJson {
                intermediates: None,
                coordinates: vec!["x".into()],
                generalized_forces: Named(vec![("x".into(), "-k*x".into())]),
            },
            scene: SceneJson {
                bodies: None,
                constraints: None,
                dimensions: Some(Named(vec![("x".into(), None)])),
            },
        };
        assert_eq!(
            serde_json::to_string(&wire).unwrap(),
            r#"{"coordinates":["x"],"generalized_forces":{"x":"-k*x"},"dimensions":{"x":null}}"#
        );
    }
}

/// The REPL's value of a name or an expression under `:format json`, on
/// one line: `{"name": "E", "value": …}`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ReplValueJson {
    /// The name shown (absent for a bare expression).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// The value: a string (a scalar), a list of strings (a vector's
    /// components) or a list of rows (a rotation's matrix).
    pub value: ReplValueKindJson,
}

/// The shapes of [`ReplValueJson::value`].
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(untagged)]
pub enum ReplValueKindJson {
    /// A scalar.
    Scalar(String),
    /// A vector's components.
    Vector(Vec<String>),
    /// A rotation's matrix, by rows.
    Matrix(Vec<Vec<String>>),
}

impl ReplValueJson {
    /// The value as one line of JSON and a newline.
    pub fn line(&self) -> String {
        let mut s = serde_json::to_string(self).unwrap_or_default();
        s.push('\n');
        s
    }
}
