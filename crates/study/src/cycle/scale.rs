//! The mechanism's own units, so that no verdict depends on the units the
//! scene is written in: each coordinate's natural scale (1 for an angle,
//! the mechanism's size ℓ for a length), each constraint's (how much it
//! changes when the coordinates move by their natural scales), and the
//! constraint Jacobian measured in them. A change of the length unit by L
//! multiplies ℓ, the lengths and their constraints by L and leaves the
//! scaled Jacobian as it was; mass and time units do not enter.

use super::model::Model;
use crate::expr::atom::{self, Atom};
use crate::scene::Scene;
use nalgebra::DMatrix;

/// Every coordinate's natural scale.
#[derive(Clone, Debug)]
pub(super) struct Scales {
    /// 1 for an angle, ℓ for a length (or any other coordinate).
    pub coordinate: Vec<f64>,
    /// The mechanism's size ℓ: the largest distance between two of its
    /// drawing's points.
    pub length: f64,
}

impl Scales {
    /// The scales of `scene`'s coordinates, with ℓ from the drawing's
    /// points at the guess `q` (time `t`).
    pub fn new(scene: &Scene, model: &mut Model, q: &[f64], t: f64) -> Scales {
        let angles = angles(scene);
        let n = model.n;
        let mut motion = vec![0.0; model.layout().len];
        let ins: Vec<f64> = q.iter().copied().chain(vec![0.0; n]).chain([t]).collect();
        model.motion.eval(&ins, &mut motion);
        let at = model.layout().points;
        // a slider's guide point is one unit (not one length) along the guide
        let guides: Vec<usize> = model
            .drawing
            .joints
            .iter()
            .filter_map(|j| j.guide.map(|g| g[1]))
            .collect();
        let points: Vec<[f64; 2]> = (0..model.points)
            .filter(|k| !guides.contains(k))
            .map(|k| [motion[at + 2 * k], motion[at + 2 * k + 1]])
            .filter(|p| p[0].is_finite() && p[1].is_finite())
            .collect();
        let mut length = 0.0f64;
        for (i, p) in points.iter().enumerate() {
            for r in &points[i + 1..] {
                length = length.max((p[0] - r[0]).hypot(p[1] - r[1]));
            }
        }
        if !(length > 0.0 && length.is_finite()) {
            // no extent to read: the guessed lengths, else the scene's unit
            length = (0..n)
                .filter(|&j| !angles[j])
                .map(|j| q[j].abs())
                .filter(|x| x.is_finite())
                .fold(0.0, f64::max);
            if length == 0.0 {
                length = 1.0;
            }
        }
        Scales {
            coordinate: angles
                .iter()
                .map(|&a| if a { 1.0 } else { length })
                .collect(),
            length,
        }
    }

    /// max_j |x_j| / S_j: a vector of coordinate changes in natural units.
    pub fn norm(&self, x: &[f64]) -> f64 {
        x.iter()
            .zip(&self.coordinate)
            .fold(0.0f64, |m, (v, s)| m.max((v / s).abs()))
    }

    /// 1 + max_j |q_j| / S_j: the size of a position in natural units
    /// (1 is a radian, or the mechanism's size).
    pub fn size(&self, q: &[f64]) -> f64 {
        1.0 + self.norm(q)
    }

    /// Every constraint's scale at the Jacobian `a`: T_i = max_j |A_ij|·S_j,
    /// its change when one coordinate moves by its natural scale (1 where
    /// the row is zero).
    pub fn rows(&self, a: &DMatrix<f64>) -> Vec<f64> {
        (0..a.nrows())
            .map(|i| {
                let t = (0..a.ncols())
                    .fold(0.0f64, |m, j| m.max((a[(i, j)] * self.coordinate[j]).abs()));
                if t > 0.0 && t.is_finite() {
                    t
                } else {
                    1.0
                }
            })
            .collect()
    }

    /// The Jacobian in natural units: A_ij·S_j / T_i, every row's largest
    /// entry 1.
    pub fn scaled(&self, a: &DMatrix<f64>) -> DMatrix<f64> {
        let rows = self.rows(a);
        DMatrix::from_fn(a.nrows(), a.ncols(), |i, j| {
            a[(i, j)] * self.coordinate[j] / rows[i]
        })
    }
}

/// Which coordinates are angles: annotated `angle` (or `rad`, or
/// dimensionless), or, unannotated, inside the argument of a sine or
/// cosine of a constraint.
fn angles(scene: &Scene) -> Vec<bool> {
    let coords: Vec<_> = scene
        .coordinates
        .iter()
        .map(|c| atom::coord(&c.name, 0))
        .collect();
    let mut trig = vec![false; coords.len()];
    for c in &scene.constraints {
        for v in c.expression.vars() {
            for w in std::iter::once(v).chain(atom::inner_atoms(v).iter().copied()) {
                if let Atom::Sin(u) | Atom::Cos(u) = atom::atom(w) {
                    for (k, &q) in coords.iter().enumerate() {
                        trig[k] |= u.depends_on(q);
                    }
                }
            }
        }
    }
    scene
        .coordinates
        .iter()
        .zip(trig)
        .map(|(c, trig)| match c.dimension.as_deref().map(str::trim) {
            Some("angle" | "rad" | "dimensionless" | "1") => true,
            Some(_) => false,
            None => trig,
        })
        .collect()
}
