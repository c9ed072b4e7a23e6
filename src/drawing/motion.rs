//! `qdot simulate --animate FILE.html` and `qdot modes --animate
//! FILE.html`: any motion of a scene drawn in 3D (a plane scene in the
//! plane z = 0, seen from the front) on one self-contained page.
//!
//! What is drawn is read from the scene (a [`Stage`]): every body's and
//! particle's centre, every vector definition and every pair of scalar
//! definitions `x…`, `y…` (`z…`) that depends on the coordinates (a
//! kinematic point), a rigid body's axes (its orientation), and a link
//! between two points kept at a constant distance by the motion (a rod).
//! The positions are evaluated along the motion here, once; the page
//! embeds them as JSON with three.js (pinned in book/package.json,
//! vendored under assets/vendor/three/) and a small player.

use crate::diag::ErrorKind;
use crate::expr::atom::Atom;
use crate::expr::tape::Tape;
use crate::scene::dimension::Dimension;
use crate::scene::{Scene, Turning, Value};
use crate::solve::equilibrium::Values;
use crate::{Diagnostic, Expr};
use qdot_syntax::parse::ast::BodyKind;
use serde_json::{json, Value as Json};
use std::cell::RefCell;

/// three.js 0.170.0's single-file ES module (its MIT licence beside it).
const THREE: &str = include_str!("../../assets/vendor/three/three.module.min.js");
/// The page: its style, its controls and the player; `/*QDOT_DATA*/` and
/// `/*QDOT_THREE*/` are replaced by the motion and three.js.
const PAGE: &str = include_str!("motion.html");
/// A page holds at most this many frames of a run (evenly chosen).
const MAX_FRAMES: usize = 1_500;
/// Two points are linked when their distance varies by less than this
/// fraction of the scene's size along the motion.
const RIGID: f64 = 1e-6;

/// What a point of the drawing is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Marker {
    /// A `particle`'s position.
    Particle,
    /// A `body`'s centre of mass.
    Body,
    /// A kinematic point: a vector definition, or `x…`, `y…` definitions.
    Point,
}

impl Marker {
    fn name(self) -> &'static str {
        match self {
            Marker::Particle => "particle",
            Marker::Body => "body",
            Marker::Point => "point",
        }
    }
}

/// A point of the drawing: its name, kind, position (x, y, z; z = 0 in
/// the plane) and the coordinates it depends on.
#[derive(Clone, Debug)]
struct StagePoint {
    name: String,
    marker: Marker,
    at: [Expr; 3],
    depends: Vec<usize>,
}

/// A rigid body's orientation: its frame's matrix (row by row: the body's
/// axes are its columns), or its angle in the plane.
#[derive(Clone, Debug)]
enum Orientation {
    Frame(Vec<Expr>),
    Angle(Expr),
}

/// What a scene's motion draws: its points and rigid bodies' axes.
#[derive(Clone, Debug)]
pub struct Stage {
    points: Vec<StagePoint>,
    /// (point index, orientation) of each rigid body that turns.
    axes: Vec<(usize, Orientation)>,
    /// Whether any point has three components.
    pub space: bool,
}

/// One drawing of the stage: every point's position, every body's axes
/// (three columns of a rotation, nine numbers).
#[derive(Clone, Debug, PartialEq)]
pub struct Pose {
    /// x, y, z of each point.
    pub points: Vec<[f64; 3]>,
    /// Each turning body's matrix, row by row.
    pub axes: Vec<[f64; 9]>,
}

/// A motion to draw: its label, the times, the coordinates (and their
/// rates) at each.
pub struct Motion<'a> {
    /// What the page's chooser calls it (a mode's frequency).
    pub label: String,
    /// Whether it repeats (a mode's period) rather than runs once.
    pub periodic: bool,
    /// The time of each frame.
    pub times: Vec<f64>,
    /// q and q̇ at each frame, in the scene's coordinates' order.
    pub states: Vec<(Vec<f64>, Vec<f64>)>,
    /// Parameter values.
    pub set: &'a Values,
}

/// Whether a definition's value is a length, where the scene declares
/// dimensions (else every vector counts as a position).
fn is_length(scene: &Scene, name: &str) -> bool {
    if !scene.dimensions_checked {
        return true;
    }
    let Ok(report) = scene.dimension_report() else {
        return true;
    };
    report
        .names
        .iter()
        .find(|n| n.name == name)
        .and_then(|n| n.dimension)
        .is_none_or(|d| d == Dimension::LENGTH)
}

/// The three components of a plane or space vector (z = 0 in the plane).
fn padded(v: &[Expr]) -> Option<[Expr; 3]> {
    match v {
        [x, y] => Some([x.clone(), y.clone(), Expr::zero()]),
        [x, y, z] => Some([x.clone(), y.clone(), z.clone()]),
        _ => None,
    }
}

impl Stage {
    /// The stage of `scene`; an error with a hint when it has nothing to
    /// draw.
    pub fn of_scene(scene: &Scene) -> Result<Stage, Diagnostic> {
        let mut stage = Stage {
            points: Vec::new(),
            axes: Vec::new(),
            space: false,
        };
        for b in &scene.bodies {
            let mp = &b.mass_properties;
            let Some(at) = padded(&mp.centre) else {
                continue;
            };
            stage.space |= mp.centre.len() == 3;
            let marker = match b.kind {
                BodyKind::Particle => Marker::Particle,
                BodyKind::Rigid => Marker::Body,
            };
            let index = stage.points.len();
            stage.add(scene, &b.name, marker, at);
            let orientation = match &mp.turning {
                Some(Turning::Space { frame, .. }) => {
                    Some(Orientation::Frame(frame.entries().to_vec()))
                }
                Some(Turning::Plane { angle, .. }) => Some(Orientation::Angle(angle.clone())),
                None => None,
            };
            if let (Some(o), true) = (orientation, stage.points.len() > index) {
                stage.axes.push((index, o));
            }
        }
        for d in scene.definitions.iter().filter(|d| d.role.is_none()) {
            if let Value::Vector(v) = &d.value {
                if let Some(at) = padded(v).filter(|_| is_length(scene, &d.name)) {
                    stage.space |= v.len() == 3;
                    stage.add(scene, &d.name, Marker::Point, at);
                }
            }
        }
        stage.add_scalar_points(scene);
        if stage.points.is_empty() {
            return Err(Diagnostic::global(
                "nothing to animate: no body, particle or point of the scene moves with its coordinates",
            )
            .with_hint(
                "give the scene a position: `particle bob: mass m, at [l*sin(th), -l*cos(th)]`, a vector definition `P = [x, 0]`, or definitions `x1 = …` and `y1 = …`",
            ).with_kind(ErrorKind::NothingToSolve));
        }
        Ok(stage)
    }

    /// The points `x<s>`, `y<s>` (and `z<s>`) of scalar definitions.
    fn add_scalar_points(&mut self, scene: &Scene) {
        let scalar = |name: &str| {
            scene
                .definitions
                .iter()
                .find(|d| d.name == name && d.role.is_none())
                .and_then(|d| d.value.as_scalar().cloned())
                .filter(|_| is_length(scene, name))
        };
        for d in &scene.definitions {
            let Some(suffix) = d.name.strip_prefix('x') else {
                continue;
            };
            let (Some(x), Some(y)) = (scalar(&d.name), scalar(&format!("y{suffix}"))) else {
                continue;
            };
            let z = scalar(&format!("z{suffix}"));
            self.space |= z.is_some();
            let name = if suffix.is_empty() {
                "(x, y)".to_string()
            } else {
                format!("P{suffix}")
            };
            self.add(
                scene,
                &name,
                Marker::Point,
                [x, y, z.unwrap_or_else(Expr::zero)],
            );
        }
    }

    /// Add the point `at` when it moves with the coordinates (and with
    /// nothing else: no velocity, no given function) and is not already
    /// drawn.
    fn add(&mut self, scene: &Scene, name: &str, marker: Marker, at: [Expr; 3]) {
        if self.points.iter().any(|p| p.at == at) {
            return;
        }
        let Some(depends) = dependencies(scene, &at) else {
            return;
        };
        if depends.is_empty() {
            return;
        }
        self.points.push(StagePoint {
            name: name.to_string(),
            marker,
            at,
            depends,
        });
    }

    /// The stage's pose at the parameters `set`, coordinates `q`, rates
    /// `qd` and time `t`; `None` where a value is not finite.
    pub fn pose(&self, scene: &Scene, set: &Values, q: &[f64], qd: &[f64], t: f64) -> Option<Pose> {
        let value = |a: &Atom| match a {
            Atom::Param(n) => set.get(&**n).copied(),
            Atom::Coord(n, k) => {
                let i = scene.coordinates.iter().position(|c| *c.name == **n)?;
                match k {
                    0 => q.get(i).copied(),
                    1 => qd.get(i).copied(),
                    _ => None,
                }
            }
            Atom::Time => Some(t),
            _ => None,
        };
        let mut exprs: Vec<Expr> = self.points.iter().flat_map(|p| p.at.clone()).collect();
        for (_, o) in &self.axes {
            match o {
                Orientation::Frame(m) => exprs.extend(m.iter().cloned()),
                Orientation::Angle(a) => exprs.push(a.clone()),
            }
        }
        let values = eval_many(scene.tape.as_ref(), &exprs, &value)?;
        if values.iter().any(|v| !v.is_finite()) {
            return None;
        }
        let n = 3 * self.points.len();
        let points = values[..n].chunks(3).map(|c| [c[0], c[1], c[2]]).collect();
        let mut rest = &values[n..];
        let mut axes = Vec::with_capacity(self.axes.len());
        for (_, o) in &self.axes {
            match o {
                Orientation::Frame(_) => {
                    let mut m = [0.0; 9];
                    m.copy_from_slice(&rest[..9]);
                    axes.push(m);
                    rest = &rest[9..];
                }
                Orientation::Angle(_) => {
                    let (s, c) = rest[0].sin_cos();
                    axes.push([c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0]);
                    rest = &rest[1..];
                }
            }
        }
        Some(Pose { points, axes })
    }
}

/// `es` evaluated together (through the scene's intermediates, if it has
/// any).
fn eval_many(
    tape: Option<&Tape>,
    es: &[Expr],
    f: &dyn Fn(&Atom) -> Option<f64>,
) -> Option<Vec<f64>> {
    match tape {
        Some(tape) => tape.eval_many_f64(es, f),
        None => es.iter().map(|e| e.eval_f64(f)).collect(),
    }
}

/// The coordinates the position `at` depends on (indices), or `None`
/// when it depends on a velocity, a given function or an unknown (not a
/// position of the configuration).
fn dependencies(scene: &Scene, at: &[Expr; 3]) -> Option<Vec<usize>> {
    let seen = RefCell::new(vec![false; scene.coordinates.len()]);
    let foreign = RefCell::new(false);
    let probe = |a: &Atom| match a {
        Atom::Param(_) => Some(1.0),
        Atom::Time => Some(0.5),
        Atom::Coord(n, 0) => {
            let i = scene.coordinates.iter().position(|c| *c.name == **n)?;
            seen.borrow_mut()[i] = true;
            Some(0.3 + 0.1 * i as f64)
        }
        Atom::Coord(..) | Atom::Given(..) | Atom::Unknown(_) => {
            *foreign.borrow_mut() = true;
            Some(0.0)
        }
        _ => None,
    };
    eval_many(scene.tape.as_ref(), at, &probe)?;
    if foreign.into_inner() {
        return None;
    }
    let seen = seen.into_inner();
    Some((0..seen.len()).filter(|&i| seen[i]).collect())
}

/// The links between points: each point to the point (or the origin) it
/// keeps a constant distance from along every pose, that depends on the
/// fewest more coordinates; `-1` is the origin.
fn links(stage: &Stage, poses: &[Pose], size: f64) -> Vec<(i64, usize)> {
    let tolerance = RIGID * size;
    let distance = |a: [f64; 3], b: [f64; 3]| {
        ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
    };
    let rigid = |at: &dyn Fn(&Pose) -> [f64; 3], i: usize| {
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for p in poses {
            let d = distance(at(p), p.points[i]);
            lo = lo.min(d);
            hi = hi.max(d);
        }
        hi - lo <= tolerance && lo > tolerance
    };
    let mut out = Vec::new();
    for (i, p) in stage.points.iter().enumerate() {
        // the candidates depend on fewer coordinates, all among p's
        let mut best: Option<(usize, f64, i64)> = None;
        for (j, other) in stage.points.iter().enumerate() {
            let within = other.depends.len() < p.depends.len()
                && other.depends.iter().all(|d| p.depends.contains(d));
            if within && rigid(&|pose: &Pose| pose.points[j], i) {
                let d = distance(poses[0].points[j], poses[0].points[i]);
                let better = best.is_none_or(|(n, bd, _)| {
                    other.depends.len() > n || (other.depends.len() == n && d < bd)
                });
                if better {
                    best = Some((other.depends.len(), d, j as i64));
                }
            }
        }
        if best.is_none() && rigid(&|_: &Pose| [0.0; 3], i) {
            best = Some((0, 0.0, -1));
        }
        if let Some((_, _, j)) = best {
            out.push((j, i));
        }
    }
    out
}

/// The largest extent of the drawing over every pose (at least the
/// distance from the origin): the unit of its markers' sizes.
fn size_of(poses: &[Pose]) -> f64 {
    let mut size: f64 = 0.0;
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for p in poses.iter().flat_map(|p| &p.points) {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
            size = size.max(p[k].abs());
        }
    }
    for k in 0..3 {
        if lo[k].is_finite() {
            size = size.max(hi[k] - lo[k]);
        }
    }
    if size > 0.0 {
        size
    } else {
        1.0
    }
}

/// The poses of `motion` (frames whose pose cannot be evaluated are left
/// out) and their times.
pub fn poses(stage: &Stage, scene: &Scene, motion: &Motion) -> (Vec<f64>, Vec<Pose>) {
    let mut times = Vec::new();
    let mut out = Vec::new();
    for (t, (q, qd)) in motion.times.iter().zip(&motion.states) {
        if let Some(p) = stage.pose(scene, motion.set, q, qd, *t) {
            times.push(*t);
            out.push(p);
        }
    }
    (times, out)
}

/// The page's data: the stage, and every motion's times and poses.
pub fn page_data(
    stage: &Stage,
    scene: &Scene,
    title: &str,
    subtitle: &str,
    motions: &[Motion],
) -> Result<Json, Diagnostic> {
    let evaluated: Vec<(Vec<f64>, Vec<Pose>)> =
        motions.iter().map(|m| poses(stage, scene, m)).collect();
    let all: Vec<Pose> = evaluated
        .iter()
        .flat_map(|(_, p)| p.iter().cloned())
        .collect();
    if all.is_empty() {
        return Err(Diagnostic::global(
            "nothing to animate: no position of the scene could be evaluated along the motion",
        )
        .with_hint("every parameter needs a value (--set) and the positions a finite value")
        .with_kind(ErrorKind::NothingToSolve));
    }
    let size = size_of(&all);
    let links = links(stage, &all, size);
    let points: Vec<Json> = stage
        .points
        .iter()
        .map(|p| json!({"name": p.name, "kind": p.marker.name()}))
        .collect();
    let axes: Vec<usize> = stage.axes.iter().map(|(i, _)| *i).collect();
    let motions: Vec<Json> = motions
        .iter()
        .zip(&evaluated)
        .map(|(m, (times, poses))| {
            let positions: Vec<Vec<f64>> = poses
                .iter()
                .map(|p| p.points.iter().flatten().copied().collect())
                .collect();
            let frames: Vec<Vec<f64>> = poses
                .iter()
                .map(|p| p.axes.iter().flatten().copied().collect())
                .collect();
            json!({
                "label": m.label,
                "periodic": m.periodic,
                "t": times,
                "positions": positions,
                "axes": frames,
            })
        })
        .collect();
    Ok(json!({
        "title": title,
        "subtitle": subtitle,
        "space": stage.space,
        "size": size,
        "points": points,
        "links": links,
        "bodyAxes": axes,
        "motions": motions,
    }))
}

/// The page around `data`.
pub fn page(data: &Json) -> String {
    // `</` inside the JSON would end its script element
    let text = data.to_string().replace("</", "<\\/");
    let title = data["title"].as_str().unwrap_or("qdot");
    PAGE.replacen("<!--QDOT_TITLE-->", &escape(title), 1)
        .replacen("/*QDOT_DATA*/", &text, 1)
        .replacen("/*QDOT_THREE*/", THREE, 1)
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// A run's rows chosen for the page: at most `MAX_FRAMES` (1,500), evenly.
pub fn thinned<T: Clone>(rows: &[T]) -> Vec<T> {
    if rows.len() <= MAX_FRAMES {
        return rows.to_vec();
    }
    let last = rows.len() - 1;
    (0..MAX_FRAMES)
        .map(|k| rows[k * last / (MAX_FRAMES - 1)].clone())
        .collect()
}

/// The title (the scene's first comment, else the file's stem) and the
/// subtitle (the file and the parameters' values) of a page that is no
/// run's (`modes --animate`).
pub fn titles(src: &str, file: &str, scene: Option<&Scene>, set: &Values) -> (String, String) {
    let path = std::path::Path::new(file);
    let stem = path.file_stem().and_then(|s| s.to_str()).unwrap_or(file);
    let name = path.file_name().and_then(|s| s.to_str()).unwrap_or(file);
    let title = crate::simulate::plot::scene_title(src).unwrap_or_else(|| stem.to_string());
    let values: Vec<String> = scene
        .iter()
        .flat_map(|s| &s.parameters)
        .filter_map(|p| {
            let v = set.get(&p.name)?;
            Some(format!(
                "{} = {v}",
                crate::expr::print::pretty_name(&p.name, 0)
            ))
        })
        .collect();
    let subtitle = if values.is_empty() {
        name.to_string()
    } else {
        format!("{name} · {}", values.join(", "))
    };
    (title, subtitle)
}
