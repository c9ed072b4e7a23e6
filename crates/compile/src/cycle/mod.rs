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
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Over {
    /// `t` or a driven coordinate.
    pub name: String,
    /// The first value.
    pub from: f64,
    /// The last value.
    pub to: f64,
    /// How many positions (≥ 2, or 1 for a single position at FROM).
    pub count: usize,
}

pub use crate::limits::MAX_CYCLE_POSITIONS;

impl Over {
    /// Parse `phi=0:360deg:73`: `deg` (or `°`) and `pi` are allowed after
    /// a number (`2pi`, `pi`, `-90deg`).
    pub fn parse(s: &str) -> Result<Over, Diagnostic> {
        let bad = |why: String| {
            Diagnostic::global(format!("`--over {s}`: {why}"))
                .with_hint("write the varied quantity, its first and last values and the number of positions: --over phi=0:360deg:73 or --over t=0:2:101")
                .with_kind(ErrorKind::bad_option("--over"))
        };
        let (name, range) = s.split_once('=').ok_or_else(|| bad("no `=`".into()))?;
        let parts: Vec<&str> = range.split(':').collect();
        let [from, to, count] = parts[..] else {
            return Err(bad(format!(
                "{} parts after `=`, and it takes 3 (FROM:TO:COUNT)",
                parts.len()
            )));
        };
        let count: usize = count
            .trim()
            .parse()
            .map_err(|_| bad(format!("`{count}` is not a number of positions")))?;
        if count == 0 || count > MAX_CYCLE_POSITIONS {
            return Err(bad(format!(
                "{count} positions: give 1 to {MAX_CYCLE_POSITIONS}"
            )));
        }
        Ok(Over {
            name: name.trim().to_string(),
            from: angle_value(from).ok_or_else(|| bad(format!("`{from}` is not a number")))?,
            to: angle_value(to).ok_or_else(|| bad(format!("`{to}` is not a number")))?,
            count,
        })
    }

    /// The k-th value.
    pub fn value(&self, k: usize) -> f64 {
        if self.count == 1 {
            return self.from;
        }
        self.from + (self.to - self.from) * k as f64 / (self.count - 1) as f64
    }
}

/// `360deg` → 2π, `2pi` → 2π, `pi` → π, `0.5` → 0.5.
fn angle_value(s: &str) -> Option<f64> {
    let s = s.trim();
    let (number, scale) = if let Some(n) = s.strip_suffix("deg").or_else(|| s.strip_suffix('°')) {
        (n.trim(), std::f64::consts::PI / 180.0)
    } else if let Some(n) = s.strip_suffix("pi").or_else(|| s.strip_suffix('π')) {
        (n.trim(), std::f64::consts::PI)
    } else {
        (s, 1.0)
    };
    let x: f64 = match number {
        "" => 1.0,
        "-" => -1.0,
        n => n.trim_end_matches('*').parse().ok()?,
    };
    let v = x * scale;
    v.is_finite().then_some(v)
}

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
        }));
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
