//! A driven mechanism in LaTeX: the kinetostatic equations body by body
//! (the seed's (21.91)–(21.101), in ground axes), the frictions' laws
//! and the reactions in solving order.

use super::Writer;
use crate::expr::Expr;
use crate::mechanics::Lagrange;
use crate::scene::{Scene, Turning};
use crate::solve::kinetostatic::{FrictionLaw, MechanismReactions};

impl Writer {
    /// The mechanism's equations (body by body under `steps`), its
    /// frictions and its reactions.
    pub fn mechanism(
        &mut self,
        scene: &Scene,
        lag: &Lagrange,
        r: &MechanismReactions,
        steps: bool,
    ) {
        if steps {
            self.joints(scene);
            self.para(
                "Kinetostatic equations.",
                "Each body has its own coordinates; a joint's reaction acts on its two bodies equal and opposite (the seed's (21.86)), so it is written once, as the force on the second body. With the inertia forces $-m\\,\\mathbf{a}$ and the inertia couples $-J\\,\\varepsilon$ (21.76)--(21.77), every body is in equilibrium:",
            );
            let owner = owners(scene, lag);
            for (b, body) in scene.bodies.iter().enumerate() {
                let rows = self.balance_rows(lag, |k| owner[k] == Some(b));
                if !rows.is_empty() {
                    let name = format!("\\mathrm{{{}}}", body.name.replace('_', "\\_"));
                    self.para(&format!("The {} ${name}$.", kind(body)), "");
                    self.align(true, &rows);
                }
            }
            let rest = self.balance_rows(lag, |k| owner[k].is_none());
            if !rest.is_empty() {
                self.para("The other coordinates.", "");
                self.align(true, &rest);
            }
        } else {
            self.equations(lag);
        }
        if !r.friction.is_empty() {
            self.para(
                "Friction.",
                "Coulomb's law in every joint that has it, opposing the relative motion (the seed's (21.74)--(21.75)):",
            );
            let mut rows = Vec::new();
            for f in &r.friction {
                // a long relative velocity gets a name and a row of its own
                let v = self.tex(&f.relative_velocity);
                let named = super::width(&v) > super::LINE / 3.0;
                let shown = if named { velocity_name(f) } else { v };
                rows.push(vec![
                    self.one(self.sym(&f.name, 0)),
                    self.one(self.law(f, &shown)),
                ]);
                if named {
                    rows.push(vec![self.one(shown), self.terms(&f.relative_velocity)]);
                }
            }
            self.align(false, &rows);
        }
        let how = if r.in_order {
            "The equations are linear in the reactions; solved body by body, each through those before it:"
        } else {
            "The equations are linear in the reactions:"
        };
        self.para("Reactions.", how);
        let rows: Vec<_> = r
            .values
            .iter()
            .map(|(n, v)| vec![self.one(self.sym(n, 0)), self.terms(v)])
            .collect();
        self.align(false, &rows);
    }

    /// Each joint's condition, the point on the second body written
    /// through it equal to the point on the first (a slider: across the
    /// guide), and its reaction's names.
    fn joints(&mut self, scene: &Scene) {
        self.para(
            "Joints.",
            "Each joint ties a point of one body to a point (or a line) of another; the components of its reaction, the force on the second body, are the multipliers of its conditions:",
        );
        let mut rows = Vec::new();
        for jt in &scene.joints {
            for (k, &j) in jt.constraints.iter().enumerate() {
                let c = &scene.constraints[j];
                let name = self.sym(&c.multiplier, 0);
                let row = match (jt.along.is_some(), k) {
                    (false, _) => vec![
                        self.one(format!("{name}:\\quad {}", self.tex(&jt.points[1][k]))),
                        self.terms(&jt.points[0][k]),
                    ],
                    (true, _) => vec![
                        self.one(format!("{name}:\\quad {}", self.tex(&c.expression))),
                        self.one("0".into()),
                    ],
                };
                rows.push(row);
            }
        }
        for d in &scene.drives {
            let q = &scene.coordinates[d.coordinate].name;
            rows.push(vec![
                self.one(format!(
                    "{}:\\quad {}",
                    self.sym(&d.name, 0),
                    self.sym(q, 0)
                )),
                self.terms(&d.value),
            ]);
        }
        self.align(false, &rows);
    }

    /// Q_k − (d/dt ∂E/∂q̇_k − ∂E/∂q_k) = 0 for the coordinates `mine` picks.
    fn balance_rows(
        &self,
        lag: &Lagrange,
        mine: impl Fn(usize) -> bool,
    ) -> Vec<Vec<Vec<(bool, String)>>> {
        lag.equations
            .iter()
            .enumerate()
            .filter(|(k, _)| mine(*k))
            .map(|(_, eq)| vec![self.terms(&eq.rhs.sub(&eq.lhs)), self.one("0".into())])
            .collect()
    }

    /// `-\mu \left|G_{n}\right| \operatorname{sgn}(\dot{x}_{b})`.
    fn law(&self, f: &FrictionLaw, velocity: &str) -> String {
        let normal = match &f.normal[..] {
            [one] => format!("\\left|{}\\right|", self.sym(one, 0)),
            many => {
                let squares: Vec<String> = many
                    .iter()
                    .map(|n| format!("{}^{{2}}", self.sym(n, 0)))
                    .collect();
                format!("\\sqrt{{{}}}", squares.join(" + "))
            }
        };
        let c = self.tex(&f.coefficient);
        let c = if crate::expr::print::is_sum(&c) {
            format!("\\left({c}\\right)")
        } else {
            c
        };
        format!("-{c} \\, {normal} \\operatorname{{sgn}}\\left({velocity}\\right)")
    }
}

/// `v_{G}` (a slider's slide) or `\omega_{B}` (a pin's relative turn):
/// the name of a friction's relative velocity.
fn velocity_name(f: &FrictionLaw) -> String {
    let joint = f
        .name
        .strip_suffix("_f")
        .unwrap_or(&f.name)
        .replace('_', "\\_");
    let head = if f.normal.len() == 1 { "v" } else { "\\omega" };
    format!("{head}_{{\\mathrm{{{joint}}}}}")
}

/// "body" or "particle".
fn kind(b: &crate::scene::Body) -> &'static str {
    match b.mass_properties.turning {
        Some(Turning::Plane { .. } | Turning::Space { .. }) => "body",
        None => "particle",
    }
}

/// The body each coordinate belongs to: the first whose centre or angle
/// moves with it.
fn owners(scene: &Scene, lag: &Lagrange) -> Vec<Option<usize>> {
    lag.coordinates
        .iter()
        .map(|c| {
            let v = crate::expr::atom::coord(c, 0);
            scene.bodies.iter().position(|b| {
                let mp = &b.mass_properties;
                let angle = match &mp.turning {
                    Some(Turning::Plane { angle, .. }) => Some(angle),
                    _ => None,
                };
                mp.centre
                    .iter()
                    .chain(angle)
                    .any(|e: &Expr| e.depends_on(v))
            })
        })
        .collect()
}
