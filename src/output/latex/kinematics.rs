//! The derivation's first steps, as lecture notes write them: the scene's
//! definitions (its kinematic table and constants) as written, each body's
//! data and its kinetic energy in the textbook form ½·m·v_C² + ½·J·ω² with
//! v_C² and ω in the coordinates, and the total after substitution.

use super::written::{written, Written};
use super::{Row, Writer, LINE};
use crate::expr::Expr;
use crate::mechanics::Lagrange;
use crate::num::Q;
use crate::parse::ast::{self, BodyStmt, PropertyKey, Role, Stmt};
use crate::scene::{Body, Scene, Turning, Value};

impl Writer {
    /// The definitions, the bodies and the kinetic energy: its name in the
    /// derivation, and whether the scene has kinetic energies.
    pub(super) fn steps_energies(&mut self, scene: &Scene, lag: &Lagrange) -> (String, bool) {
        let stmts = crate::parse::parse_scene(&scene.source).unwrap_or_default();
        self.definitions(scene, &stmts);
        let coords: Vec<String> = lag.coordinates.iter().map(|c| self.sym(c, 0)).collect();
        let energies: Vec<&crate::scene::Definition> = scene.role(Role::Kinetic).collect();
        let e_name = match energies.as_slice() {
            [d] => self.sym(&d.name, 0),
            _ => "E".to_string(),
        };
        if energies.is_empty() {
            return (e_name, false);
        }
        // a body's energy comes with its own sentence: the lead-in ends
        // before it, as a sentence of its own
        let of_bodies = energies
            .first()
            .is_some_and(|d| scene.bodies.iter().any(|b| b.kinetic == d.name));
        let what = match (energies.len() > 1, of_bodies) {
            (true, true) => "the kinetic energy is found body by body.",
            (false, true) => "the kinetic energy is found from the body's data.",
            (true, false) => "body by body, the kinetic energy is",
            (false, false) => "the kinetic energy is",
        };
        self.para(
            "Kinetic energy.",
            &format!("In the coordinates ${}$, {what}", coords.join(", ")),
        );
        let mut rows: Vec<Row> = Vec::new();
        for d in &energies {
            let value = match energies.len() {
                1 => lag.kinetic.clone(),
                _ => d.value.as_scalar().cloned().unwrap_or_else(Expr::zero),
            };
            if let Some(body) = scene.bodies.iter().find(|b| b.kinetic == d.name) {
                let stmt = stmts.iter().find_map(|s| match s {
                    Stmt::Body(b) if b.name.name == body.name => Some(b),
                    _ => None,
                });
                let pending = std::mem::take(&mut rows);
                self.align(false, &pending);
                self.body(scene, body, stmt, &value);
                continue;
            }
            let mut chain = vec![self.one(self.sym(&d.name, 0))];
            if let Some(Written::Scalar(w)) = role_statement(&stmts, &d.name)
                .and_then(|e| written(e, scene))
                .filter(|w| !matches!(w, Written::Scalar(x) if *x == value))
            {
                chain.push(self.table_terms(&w));
            }
            chain.push(self.terms(&value));
            rows.push(chain);
        }
        if energies.len() > 1 {
            if rows.is_empty() {
                self.line("In total:");
            }
            let names: Vec<String> = energies.iter().map(|d| self.sym(&d.name, 0)).collect();
            rows.push(vec![
                self.one("E".into()),
                vec![(false, names.join(" + "))],
                self.terms(&lag.kinetic),
            ]);
        }
        self.align(false, &rows);
        (e_name, true)
    }

    /// The scene's definitions in source order, each as written and, where
    /// that differs, in the coordinates.
    fn definitions(&mut self, scene: &Scene, stmts: &[Stmt]) {
        let mut rows: Vec<Row> = Vec::new();
        for s in stmts {
            let Stmt::Def { name, value, .. } = s else {
                continue;
            };
            let n = &name.name;
            let mut chain = vec![self.one(self.sym(n, 0))];
            let evaluated = scene.value(n);
            match (written(value, scene), evaluated) {
                (Some(Written::Scalar(w)), Some(Value::Scalar(x))) if w == *x => {}
                (Some(Written::Vector(w)), Some(Value::Vector(x))) if w == *x => {}
                (Some(Written::Scalar(w)), _) => chain.push(self.table_terms(&w)),
                (Some(Written::Vector(v)), _) => chain.push(self.one(self.vector(&v))),
                (None, _) => {}
            }
            match evaluated {
                Some(Value::Scalar(x)) => chain.push(self.table_terms(x)),
                Some(Value::Vector(v)) => chain.push(self.one(self.vector(v))),
                _ => {}
            }
            // a value too long for a table row stays behind its name
            if chain.len() > 2 && side_width(&chain[chain.len() - 1]) > 2.0 * LINE {
                chain.pop();
            }
            if chain.len() > 1 && side_width(&chain[1]) <= 2.0 * LINE {
                rows.push(chain);
            }
        }
        if rows.is_empty() {
            return;
        }
        self.para(
            "Definitions.",
            "As the scene writes them, and in the coordinates where that differs:",
        );
        self.align(false, &rows);
    }

    /// One body: its mass, inertia, angle and centre as declared, v_C² and
    /// ω in the coordinates, and E = ½·m·v_C² + ½·J·ω² (a particle's
    /// without the turning).
    fn body(&mut self, scene: &Scene, body: &Body, stmt: Option<&BodyStmt>, energy: &Expr) {
        let label = format!("\\mathrm{{{}}}", body.name.replace('_', "\\_"));
        let sub = |head: &str| format!("{head}_{{{label}}}");
        let declared = |key: PropertyKey| -> Option<&ast::Expr> {
            stmt?
                .properties
                .iter()
                .find(|p| p.key == key)
                .map(|p| &p.value)
        };
        let mp = &body.mass_properties;
        // a body without a mass turns about its fixed centre: no m, no v²
        let massless = declared(PropertyKey::Mass).is_none() && mp.mass.is_zero();
        let mut rows: Vec<Row> = Vec::new();
        if !massless {
            rows.push(self.declared_row(sub("m"), declared(PropertyKey::Mass), scene, &mp.mass));
        }
        let mut turning_text = String::new();
        let mut omega_rows: Vec<Row> = Vec::new();
        match &mp.turning {
            Some(Turning::Plane { angle, inertia }) => {
                rows.push(self.declared_row(
                    sub("J"),
                    declared(PropertyKey::Inertia),
                    scene,
                    inertia,
                ));
                rows.push(self.declared_row(
                    sub("\\varphi"),
                    declared(PropertyKey::Angle),
                    scene,
                    angle,
                ));
                let rate = angle.dt();
                let mut chain = vec![self.one(sub("\\omega"))];
                if let Some(Written::Scalar(w)) =
                    declared(PropertyKey::Angle).and_then(|e| written(e, scene))
                {
                    if w.dt() != rate {
                        chain.push(self.table_terms(&w.dt()));
                    }
                }
                chain.push(self.table_terms(&rate));
                omega_rows.push(chain);
                turning_text = format!(" + \\frac{{1}}{{2}} {} {}^{{2}}", sub("J"), sub("\\omega"));
            }
            Some(Turning::Space { frame, inertia }) => {
                let rows3: Vec<Vec<Expr>> = inertia.iter().map(|r| r.to_vec()).collect();
                rows.push(vec![self.one(sub("I")), self.one(self.pmatrix(&rows3))]);
                let w = sub("\\boldsymbol{\\omega}");
                omega_rows.push(vec![
                    self.one(w.clone()),
                    self.one(self.vector(&frame.omega_frame())),
                ]);
                turning_text = format!(" + \\frac{{1}}{{2}} {w}^{{T}} {} {w}", sub("I"));
            }
            None => {}
        }
        rows.push(
            match declared(PropertyKey::At).and_then(|e| written(e, scene)) {
                Some(Written::Vector(v)) if v != mp.centre => vec![
                    self.one(sub("\\mathbf{r}")),
                    self.one(self.vector(&v)),
                    self.one(self.vector(&mp.centre)),
                ],
                _ => vec![
                    self.one(sub("\\mathbf{r}")),
                    self.one(self.vector(&mp.centre)),
                ],
            },
        );
        let rates: Vec<Expr> = mp.centre.iter().map(Expr::dt).collect();
        if !massless {
            rows.push(vec![
                self.one(format!("{}^{{2}}", sub("v"))),
                self.squares(&rates),
            ]);
        }
        rows.extend(omega_rows);
        let formula = if massless {
            turning_text.trim_start_matches(" + ").to_string()
        } else {
            format!(
                "\\frac{{1}}{{2}} {} {}^{{2}}{turning_text}",
                sub("m"),
                sub("v")
            )
        };
        rows.push(vec![
            self.one(self.sym(&body.kinetic, 0)),
            self.one(formula),
            self.terms(energy),
        ]);
        let what = match body.kind {
            ast::BodyKind::Rigid => "body",
            ast::BodyKind::Particle => "particle",
        };
        let data = match &mp.turning {
            Some(Turning::Space { .. }) if massless => {
                "no mass (its centre is fixed), its inertia about the centre in its own axes (and its angular velocity in them) and centre"
            }
            Some(Turning::Plane { .. }) if massless => {
                "no mass (its centre is fixed), its moment of inertia about the centre, angle and centre"
            }
            Some(Turning::Plane { .. }) => {
                "its mass, moment of inertia about the centre, angle and centre"
            }
            Some(Turning::Space { .. }) => {
                "its mass, inertia about the centre in its own axes (and its angular velocity in them) and centre"
            }
            None => "its mass and position",
        };
        self.line(&format!("The {what} ${label}$: {data}:"));
        self.align(false, &rows);
    }

    /// `name = as declared = value` (the value where it differs).
    fn declared_row(
        &self,
        name: String,
        declared: Option<&ast::Expr>,
        scene: &Scene,
        value: &Expr,
    ) -> Row {
        let mut chain = vec![self.one(name)];
        if let Some(Written::Scalar(w)) = declared.and_then(|e| written(e, scene)) {
            if w != *value {
                chain.push(self.table_terms(&w));
            }
        }
        chain.push(self.table_terms(value));
        chain
    }

    /// A table's entry: a quotient by a symbolic denominator as one
    /// fraction (`\frac{x - s}{R}`, `\frac{y_{3}}{2 r}`), as a table is
    /// written, not collected by the coordinates as the equations are.
    fn table_terms(&self, e: &Expr) -> Vec<(bool, String)> {
        if e.den().is_constant() {
            return self.terms(e);
        }
        // the rational content as integers on each side: \frac{y_{3}}{2 r}
        let (cn, cd) = (e.num().content(), e.den().content());
        let (Some(q), Some(rn), Some(rd)) = (cn.checked_div(&cd), cn.recip(), cd.recip()) else {
            return self.terms(e);
        };
        let top = Expr::from_poly(e.num().scale(&rn)).scale(&Q::from_bigint(q.numer()));
        let bottom = Expr::from_poly(e.den().scale(&rd)).scale(&Q::from_bigint(q.denom()));
        let t = self.terms(&top);
        let (neg, top) = if t.len() == 1 && t[0].0 {
            (true, self.tex(&top.neg()))
        } else {
            (false, self.tex(&top))
        };
        vec![(neg, format!("\\frac{{{top}}}{{{}}}", self.tex(&bottom)))]
    }

    /// v² as the sum of its components' squares, each unexpanded where it
    /// fits on a line (else the expanded sum, which breaks between terms).
    fn squares(&self, rates: &[Expr]) -> Vec<(bool, String)> {
        let mut out = Vec::new();
        for r in rates.iter().filter(|r| !r.is_zero()) {
            let t = self.terms(r);
            let s = if t.len() == 1 {
                self.tex(&r.mul(r))
            } else {
                // (−a − b)² is (a + b)²: the sign that reads better
                let r = if t[0].0 { r.neg() } else { r.clone() };
                format!("{}^{{2}}", super::parens(&self.tex(&r)))
            };
            if super::width(&s) > LINE * 0.8 {
                let v2 = rates.iter().fold(Expr::zero(), |a, r| a.add(&r.mul(r)));
                return self.terms(&v2);
            }
            out.push((false, s));
        }
        if out.is_empty() {
            out.push((false, "0".into()));
        }
        out
    }

    /// A column vector, inline.
    fn vector(&self, v: &[Expr]) -> String {
        let parts: Vec<String> = v.iter().map(|e| self.tex(e)).collect();
        format!(
            "\\begin{{pmatrix}} {} \\end{{pmatrix}}",
            parts.join(" \\\\ ")
        )
    }

    /// A matrix, inline.
    fn pmatrix(&self, m: &[Vec<Expr>]) -> String {
        let rows = self.matrix_rows(m);
        format!(
            "\\begin{{pmatrix}} {} \\end{{pmatrix}}",
            rows.join(" \\\\ ")
        )
    }
}

/// The right-hand side of the role statement (`kinetic E1 = …`) defining
/// `name`.
fn role_statement<'a>(stmts: &'a [Stmt], name: &str) -> Option<&'a ast::Expr> {
    stmts.iter().find_map(|s| match s {
        Stmt::Role { name: n, value, .. } if n.name == name => Some(value),
        _ => None,
    })
}

/// The printed width of one side of a row.
fn side_width(side: &[(bool, String)]) -> f64 {
    side.iter().map(|(_, t)| super::width(t) + 1.8).sum()
}
