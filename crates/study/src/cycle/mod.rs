//! Planar mechanisms over a cycle (`qdot cycle`): the positions by
//! Newton's method on the joints' constraints, continued position by
//! position on one assembly branch; the velocities and accelerations
//! from the exact linear equations A·q̇ = −b and A·q̈ = γ; then every
//! joint's reaction and every drive's force from the kinetostatic
//! equations Aᵀ·λ = M·q̈ − f, with Coulomb friction by iteration
//! (`friction.rs`).

mod diagnose;
mod friction;
mod model;
mod positions;
mod scale;
mod table;

pub use friction::MAX_FRICTION_ITERATIONS;
pub use table::*;

use crate::diag::{Diagnostic, ErrorKind};
use crate::poly::Var;
use crate::scene::Scene;
use model::Model;
use rustc_hash::FxHashMap;

/// What `qdot cycle` is asked.
#[derive(Clone, Debug, Default)]
pub struct CycleRequest {
    /// The varied quantity and its values.
    pub over: Over,
    /// Every parameter's value.
    pub set: crate::algebra::sign::Values,
    /// Coordinates of an assembly near the first position; the others
    /// start from 0.
    pub guess: Vec<(String, f64)>,
}

/// `--over NAME=FROM:TO:COUNT`: `t` or a driven coordinate, from FROM to
/// TO in COUNT positions (both ends included), in the scene's units.
pub use crate::scene::given::GridAxis as Over;

/// The most positions of one `qdot cycle`: the one limit of `--over` grids.
pub use crate::scene::given::MAX_GRID_POINTS as MAX_CYCLE_POSITIONS;

use crate::scene::given::range_value as angle_value;

/// Analyse the mechanism of `scene` over `req.over`.
pub fn cycle(scene: &Scene, req: &CycleRequest) -> Result<CycleTable, Diagnostic> {
    CompiledCycle::new(scene, req)?.run()
}

/// An error unless the scene is a mechanism with as many conditions as
/// coordinates.
fn counted(scene: &Scene) -> Result<(), Diagnostic> {
    if scene.joints.is_empty() && scene.drives.is_empty() {
        return Err(Diagnostic::global("the scene has no joints and no drives: `qdot cycle` analyses a mechanism")
            .with_hint("tie the bodies with `joint NAME: pin A at P, B at Q` and prescribe the input with `drive M: phi = omega*t`")
            .with_kind(ErrorKind::NothingToSolve));
    }
    let n = scene.coordinates.len();
    let m = scene.constraints.len();
    if m < n {
        let driven: Vec<&str> = scene
            .drives
            .iter()
            .map(|d| scene.coordinates[d.coordinate].name.as_str())
            .collect();
        return Err(Diagnostic::global(format!(
            "the mechanism has {} degree{} of freedom that no drive prescribes ({m} conditions on {n} coordinates)",
            n - m,
            if n - m == 1 { "" } else { "s" }
        ))
        .with_hint(if driven.is_empty() {
            "prescribe the input: `drive M: phi = omega*t`".to_string()
        } else {
            format!("drive one more coordinate besides {}, or check that every joint is declared", driven.join(", "))
        }).with_kind(ErrorKind::InvalidScene));
    }
    Ok(())
}

/// A mechanism's equations derived and compiled for one request: the
/// positions of [`CompiledCycle::run`] are the whole work left (for
/// timing them apart, or running them again).
pub struct CompiledCycle<'a> {
    scene: &'a Scene,
    model: Model,
    varied: Varied,
    guess: Vec<f64>,
    over: Over,
    layout: table::Layout,
}

impl<'a> CompiledCycle<'a> {
    /// Derive and compile the mechanism of `scene` for `req`.
    pub fn new(scene: &'a Scene, req: &CycleRequest) -> Result<CompiledCycle<'a>, Diagnostic> {
        counted(scene)?;
        let lag = scene.lagrange()?;
        let inertial = crate::scene::given::inertial_parameters(scene, &lag);
        let params = crate::scene::given::parameter_map(scene, &req.set, &inertial)?;
        Ok(CompiledCycle {
            scene,
            model: Model::new(scene, &lag, &params)?,
            varied: varied(scene, &req.over, &params)?,
            guess: guess(scene, &req.guess)?,
            over: req.over.clone(),
            layout: table::Layout::of(scene, &req.over.name),
        })
    }

    /// Every position of the request.
    pub fn run(&mut self) -> Result<CycleTable, Diagnostic> {
        positions::run(
            self.scene,
            &mut self.model,
            &mut self.varied,
            self.guess.clone(),
            &self.over,
            &self.layout,
        )
    }
}

/// How the varied quantity gives the time: `t` itself, or the drive law
/// f(t) = value solved for t.
enum Varied {
    Time,
    Drive(model::Evaluator),
}

fn varied(scene: &Scene, over: &Over, params: &FxHashMap<Var, f64>) -> Result<Varied, Diagnostic> {
    if over.name == "t" {
        return Ok(Varied::Time);
    }
    let drive = scene
        .drives
        .iter()
        .find(|d| scene.coordinates[d.coordinate].name == over.name);
    let Some(d) = drive else {
        let driven: Vec<String> = scene
            .drives
            .iter()
            .map(|d| scene.coordinates[d.coordinate].name.clone())
            .collect();
        return Err(Diagnostic::global(format!(
            "`--over {}`: `{}` is not a driven coordinate",
            over.name, over.name
        ))
        .with_hint(format!(
            "vary `t`{}",
            if driven.is_empty() {
                String::new()
            } else {
                format!(" or a driven coordinate: {}", driven.join(", "))
            }
        ))
        .with_kind(ErrorKind::bad_option("--over")));
    };
    model::law(&d.value, params).map(Varied::Drive)
}

/// The first position's starting point: the guessed coordinates, 0 for
/// the others.
fn guess(scene: &Scene, given: &[(String, f64)]) -> Result<Vec<f64>, Diagnostic> {
    let mut q = vec![0.0; scene.coordinates.len()];
    for (name, v) in given {
        let Some(k) = scene.coordinates.iter().position(|c| &c.name == name) else {
            let names: Vec<&str> = scene.coordinates.iter().map(|c| c.name.as_str()).collect();
            return Err(Diagnostic::global(format!(
                "`--guess {name}=…`: `{name}` is not a coordinate"
            ))
            .with_hint(format!(
                "guess coordinates of an assembly near the first position: {}",
                names.join(", ")
            ))
            .with_kind(ErrorKind::bad_option("--guess")));
        };
        q[k] = *v;
    }
    Ok(q)
}

/// Parse `--guess th=-0.3,xb=0.5` (angles may be written `30deg`).
pub fn parse_guess(s: &str) -> Result<Vec<(String, f64)>, Diagnostic> {
    let mut out = Vec::new();
    for part in s.split(',').map(str::trim).filter(|p| !p.is_empty()) {
        let parsed = part
            .split_once('=')
            .and_then(|(k, v)| Some((k.trim().to_string(), angle_value(v)?)));
        match parsed {
            Some(kv) => out.push(kv),
            None => return Err(Diagnostic::global(format!(
                "`--guess {part}`: expected NAME=NUMBER"
            ))
            .with_hint(
                "give coordinates of an assembly near the first position: --guess th=-0.3,xb=0.5",
            )
            .with_kind(ErrorKind::bad_option("--guess"))),
        }
    }
    Ok(out)
}
