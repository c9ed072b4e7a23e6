//! LaTeX for lecture notes: `qdot latex` and `--format latex`.
//!
//! The output is amsmath: every Lagrange equation a numbered line of an
//! `align`, results in `align*`, matrices as `pmatrix`. Long equations are
//! broken before a `+` or `−` (continuation lines indented by `\quad`, the
//! number on the last line) so that an `article` page holds them. Without
//! `--standalone` the output is a fragment to `\input`; with it, a whole
//! document that compiles with `pdflatex`.
//!
//! `--steps` writes the derivation as the seed does (§23.5): the kinetic
//! energy body by body and in total; the force function, potential, work
//! and dissipation; for every coordinate ∂E/∂q̇_k, its time derivative,
//! ∂E/∂q_k and Q_k term by term; the equation; then the solution.

mod kinematics;
mod mechanism;
mod written;

use super::position_strings;
use crate::diag::Diagnostic;
use crate::expr::latex::{join, latex_expanded, latex_with, Names};
use crate::expr::Expr;
use crate::mechanics::{Lagrange, Source};
use crate::parse::ast::Role;
use crate::scene::Scene;
use crate::solve::equilibrium::{Equilibria, Stability};
use crate::solve::oscillations::Modes;
use crate::solve::system::{self, BlockSolution};

/// The widest line, in the units of [`width`] (about one italic letter):
/// an `article` at 10pt with 2.5 cm margins holds about 70 letters of
/// mathematics beside an equation number.
const LINE: f64 = 56.0;

/// One aligned row: a chain `side₀ = side₁ = …`, each side its signed terms.
type Row = Vec<Vec<(bool, String)>>;

/// `qdot latex`: the scene's main result — with dynamics, Lagrange's
/// equations and the accelerations; its `solve` blocks and their
/// solutions; without either, the generalized forces and the equilibria —
/// with the derivation first under `--steps`, and as a whole document
/// under `--standalone`.
pub fn document(scene: &Scene, opts: &super::CommandOptions) -> Result<String, Diagnostic> {
    crate::diag::bounded(|| document_within(scene, opts))
}

/// [`document`] within the budget in force.
fn document_within(scene: &Scene, opts: &super::CommandOptions) -> Result<String, Diagnostic> {
    let mut w = Writer::new(scene);
    let dynamics = scene.has_dynamics();
    if dynamics && crate::solve::kinetostatic::is_driven_mechanism(scene) {
        let lag = scene.lagrange()?;
        let r = crate::solve::kinetostatic::mechanism_reactions(scene, &lag)?;
        if opts.steps {
            w.steps_energies(scene, &lag);
            w.forces_steps(scene);
        }
        w.mechanism(scene, &lag, &r, opts.steps);
    } else if dynamics && !opts.steps && scene.systems.is_empty() && structured(scene, &mut w)? {
        // written through intermediates, as `solve` writes it
    } else if dynamics {
        let lag = scene.lagrange()?;
        let acc = lag.accelerations()?;
        if opts.steps {
            w.steps(scene, &lag);
            w.para(
                "Solution.",
                "The equations are linear in the accelerations.",
            );
        } else {
            w.equations(&lag);
        }
        w.accelerations(&acc);
    }
    if !scene.systems.is_empty() {
        let blocks = system::solve_scene(scene)?;
        w.blocks(scene, &blocks);
    }
    if !dynamics && scene.systems.is_empty() {
        if scene.coordinates.is_empty() {
            // the usual error for a scene with nothing to derive
            scene.lagrange()?;
        }
        let eq = crate::solve::equilibrium::equilibria(scene, &opts.set)?;
        if opts.steps {
            w.forces_steps(scene);
        }
        w.equilibrium(&eq);
    }
    let body = w.finish();
    Ok(if opts.standalone {
        standalone(&opts.title, &body)
    } else {
        body
    })
}

/// A scene whose expanded equations would be large (`solve`'s size rule,
/// [`crate::scene::Structure::Auto`]) written as `solve` writes it: the
/// intermediates, then Lagrange's equations and the accelerations through
/// them (M = L·D·Lᵀ). Expanded, a chain of 30 rods has no accelerations
/// within any budget; through intermediates they take a second and read
/// line by line. `false` (nothing written) for a scene that reads
/// expanded. Not under `--steps`: its derivation differentiates the
/// expanded energies term by term.
fn structured(scene: &Scene, w: &mut Writer) -> Result<bool, Diagnostic> {
    let kept = Scene::read(&scene.source, crate::scene::Structure::Auto)?;
    if kept.tape.as_ref().is_none_or(|t| t.is_empty()) {
        return Ok(false);
    }
    let lag = kept.lagrange()?;
    let acc = lag.accelerations()?;
    *w = Writer::new(&kept);
    if let Some((tape, roots)) = super::wire::structured_roots(&kept, Some(&lag), Some(&acc), &[]) {
        w.intermediates(Some(tape), roots);
    }
    w.equations(&lag);
    w.accelerations(&acc);
    Ok(true)
}

/// What `f` writes with the notation of `scene`.
pub fn write(scene: &Scene, f: impl FnOnce(&mut Writer)) -> String {
    let mut w = Writer::new(scene);
    f(&mut w);
    w.finish()
}

/// A LaTeX writer with a scene's notation.
pub struct Writer {
    names: Names,
    out: String,
}

impl Writer {
    /// A writer with the notation of `scene` (its `latex` statements).
    pub fn new(scene: &Scene) -> Writer {
        let mut names = Names::new();
        for n in &scene.latex_names {
            names.set(&n.name, &n.tex);
        }
        Writer {
            names,
            out: String::new(),
        }
    }

    /// The LaTeX written so far.
    pub fn finish(self) -> String {
        self.out
    }

    fn tex(&self, e: &Expr) -> String {
        latex_with(e, &self.names)
    }

    /// The terms of an expression, signs apart, for line breaking.
    fn terms(&self, e: &Expr) -> Vec<(bool, String)> {
        let t = crate::expr::latex::terms_with(e, &self.names);
        if t.len() == 1 && width(&t[0].1) > LINE {
            // a long quotient: 1/D times its numerator's terms, in brackets
            if let Some((neg, d, mut n)) = crate::expr::latex::quotient_terms(e, &self.names) {
                let last = n.len() - 1;
                n[last].1.push_str(" \\bigr)");
                let (n0, t0) = n[0].clone();
                let sign = if n0 { "-" } else { "" };
                n[0] = (neg, format!("\\frac{{1}}{{{d}}} \\bigl({sign}{t0}"));
                return n;
            }
        }
        t
    }

    fn sym(&self, name: &str, dots: u32) -> String {
        self.names.symbol(name, dots)
    }

    /// `Q_{y_{3}}`: a quantity indexed by a coordinate.
    fn indexed(&self, head: &str, coord: &str) -> String {
        format!("{head}_{{{}}}", self.sym(coord, 0))
    }

    fn para(&mut self, title: &str, text: &str) {
        self.out.push_str(&format!("\\paragraph{{{title}}}"));
        if !text.is_empty() {
            self.out.push(' ');
            self.out.push_str(text);
        }
        self.out.push('\n');
    }

    fn line(&mut self, text: &str) {
        self.out.push_str(text);
        self.out.push('\n');
    }

    /// An `align` (numbered) or `align*` of rows, each a chain
    /// `side₀ = side₁ = …` of signed terms.
    fn align(&mut self, numbered: bool, rows: &[Vec<Vec<(bool, String)>>]) {
        if rows.is_empty() {
            return;
        }
        let env = if numbered { "align" } else { "align*" };
        self.out.push_str(&format!("\\begin{{{env}}}\n"));
        let last = rows.len() - 1;
        for (i, row) in rows.iter().enumerate() {
            let lines = layout(&distinct_steps(row));
            let n = lines.len();
            for (j, l) in lines.iter().enumerate() {
                self.out.push_str("  ");
                self.out.push_str(l);
                if j + 1 < n {
                    if numbered {
                        self.out.push_str(" \\nonumber");
                    }
                    self.out.push_str(" \\\\\n");
                } else if i < last {
                    self.out.push_str(" \\\\\n");
                } else {
                    self.out.push('\n');
                }
            }
        }
        self.out.push_str(&format!("\\end{{{env}}}\n"));
    }

    /// A matrix's rows, each `a & b & c`.
    fn matrix_rows(&self, m: &[Vec<Expr>]) -> Vec<String> {
        m.iter()
            .map(|r| {
                r.iter()
                    .map(|e| self.tex(e))
                    .collect::<Vec<_>>()
                    .join(" & ")
            })
            .collect()
    }

    /// A matrix `name = (…)` in `equation*`.
    fn matrix(&mut self, name: &str, m: &[Vec<Expr>]) {
        let rows = self.matrix_rows(m);
        self.out.push_str(&format!(
            "\\begin{{equation*}}\n  {name} = \\begin{{pmatrix}}\n    {}\n  \\end{{pmatrix}}\n\\end{{equation*}}\n",
            rows.join(" \\\\\n    ")
        ));
    }

    /// A column vector `name = (…)` in `equation*`.
    fn column(&mut self, name: &str, v: &[Expr]) {
        let m: Vec<Vec<Expr>> = v.iter().map(|e| vec![e.clone()]).collect();
        self.matrix(name, &m);
    }

    fn one(&self, s: String) -> Vec<(bool, String)> {
        vec![(false, s)]
    }

    // ------------------------------------------------------------ results

    /// Lagrange's equations, numbered.
    pub fn equations(&mut self, lag: &Lagrange) {
        self.line("Lagrange's equations, $\\frac{d}{dt}\\frac{\\partial E}{\\partial \\dot{q}_{k}} - \\frac{\\partial E}{\\partial q_{k}} = Q_{k}$:");
        let rows: Vec<_> = lag
            .equations
            .iter()
            .map(|eq| vec![self.terms(&eq.lhs), self.terms(&eq.rhs)])
            .collect();
        self.align(true, &rows);
        let c = &lag.constraints;
        if !c.is_empty() {
            self.line("with the constraints, each with its multiplier $\\lambda$:");
            let rows: Vec<_> = (0..c.velocity.len())
                .map(|j| {
                    let e = c.position[j].as_ref().unwrap_or(&c.velocity[j]);
                    vec![self.terms(e), self.one("0".into())]
                })
                .collect();
            self.align(true, &rows);
        }
    }

    /// The named intermediates `roots` are written through, in evaluation
    /// order (nothing without them).
    pub fn intermediates<'a>(
        &mut self,
        tape: Option<&crate::expr::tape::Tape>,
        roots: impl IntoIterator<Item = &'a Expr>,
    ) {
        let Some(tape) = tape else { return };
        let used = tape.used_by(roots);
        if used.is_empty() {
            return;
        }
        self.line("The intermediates, in order (each is written in the ones before it):");
        let rows: Vec<_> = used
            .into_iter()
            .map(|i| {
                let e = &tape.entries()[i];
                vec![self.one(self.tex(&e.expr())), self.terms(&e.value)]
            })
            .collect();
        self.align(false, &rows);
    }

    /// `qdot derive`: the equations, the mass matrix and the forcing.
    pub fn derive(&mut self, lag: &Lagrange) {
        self.equations(lag);
        self.line("The mass matrix and the forcing, $M \\ddot{q} = f$:");
        self.matrix("M", &lag.mass_matrix);
        self.column("f", &lag.forcing);
    }

    /// `qdot hamilton`: the momenta, the velocities, H and Hamilton's
    /// equations.
    pub fn hamilton(&mut self, h: &crate::mechanics::Hamiltonian) {
        let n = h.coordinates.len();
        let p: Vec<String> = h.momentum_names.iter().map(|m| self.sym(m, 0)).collect();
        self.line("The momenta, $p_{k} = \\frac{\\partial L}{\\partial \\dot{q}_{k}}$:");
        let rows: Vec<_> = (0..n)
            .map(|k| vec![self.one(p[k].clone()), self.terms(&h.momenta[k])])
            .collect();
        self.align(false, &rows);
        self.line("The velocities in terms of the momenta:");
        let rows: Vec<_> = (0..n)
            .map(|k| {
                vec![
                    self.one(self.sym(&h.coordinates[k], 1)),
                    self.terms(&h.velocities[k]),
                ]
            })
            .collect();
        self.align(false, &rows);
        self.line("The Hamiltonian, $H = \\sum_{k} p_{k} \\dot{q}_{k} - L$:");
        let rows = vec![vec![self.one("H".into()), self.terms(&h.hamiltonian)]];
        self.align(true, &rows);
        self.line("Hamilton's equations, $\\dot{q}_{k} = \\frac{\\partial H}{\\partial p_{k}}$, $\\dot{p}_{k} = -\\frac{\\partial H}{\\partial q_{k}} + \\tilde{Q}_{k}$:");
        let mut rows = Vec::with_capacity(2 * n);
        for (k, pk) in p.iter().enumerate() {
            rows.push(vec![
                self.one(self.sym(&h.coordinates[k], 1)),
                self.terms(&h.velocities[k]),
            ]);
            rows.push(vec![
                self.one(format!("\\dot{{{pk}}}")),
                self.terms(&h.momentum_rates[k]),
            ]);
        }
        self.align(true, &rows);
    }

    /// `qdot integrals`: the conserved momenta, the energy integral and
    /// Routh's reduction.
    pub fn integrals(&mut self, i: &crate::mechanics::Integrals) {
        if !i.cyclic.is_empty() {
            self.line("The cyclic coordinates' momenta are conserved:");
            let rows: Vec<_> = i
                .cyclic
                .iter()
                .map(|(q, p)| {
                    let name = crate::scene::momentum_name(q);
                    vec![
                        self.one(self.sym(&name, 0)),
                        self.terms(p),
                        self.one("\\mathrm{const}".into()),
                    ]
                })
                .collect();
            self.align(true, &rows);
        }
        if let Some(h) = &i.energy {
            self.line("The energy integral, $h = \\sum_{k} \\dot{q}_{k} \\frac{\\partial L}{\\partial \\dot{q}_{k}} - L$:");
            let rows = vec![vec![
                self.one("h".into()),
                self.terms(h),
                self.one("\\mathrm{const}".into()),
            ]];
            self.align(true, &rows);
        }
        if let Some(r) = &i.routh {
            self.line("The Routhian, $R = L - \\sum_{c} p_{c} \\dot{q}_{c}$ over the cyclic coordinates, and the effective potential:");
            let rows = vec![
                vec![self.one("R".into()), self.terms(&r.routhian)],
                vec![
                    self.one("V_{\\mathrm{eff}}".into()),
                    self.terms(&r.effective_potential),
                ],
            ];
            self.align(true, &rows);
            self.line("The reduced equations give:");
            let rows: Vec<_> = r
                .accelerations
                .iter()
                .map(|(q, a)| vec![self.one(self.sym(q, 2)), self.terms(a)])
                .collect();
            self.align(false, &rows);
        }
    }

    /// The exact accelerations.
    pub fn accelerations(&mut self, acc: &crate::mechanics::Accelerations) {
        self.line("The accelerations:");
        let rows: Vec<_> = acc
            .iter()
            .map(|(q, a)| vec![self.one(self.sym(q, 2)), self.terms(a)])
            .collect();
        self.align(false, &rows);
        if !acc.multipliers().is_empty() {
            self.line(
                "The multipliers (the generalized constraint forces are $\\lambda_j a_{jk}$):",
            );
            let rows: Vec<_> = acc
                .multipliers()
                .iter()
                .map(|(name, l)| vec![self.one(self.sym(name, 0)), self.terms(l)])
                .collect();
            self.align(false, &rows);
        }
    }

    /// The `solve` blocks: their equations (numbered) and solutions.
    pub fn blocks(&mut self, scene: &Scene, blocks: &[BlockSolution]) {
        for (b, (sys, sol)) in scene.systems.iter().zip(blocks).enumerate() {
            let unknowns: Vec<String> = sys.unknowns.iter().map(|u| self.sym(&u.name, 0)).collect();
            let which = if scene.systems.len() > 1 {
                format!(" {}", b + 1)
            } else {
                String::new()
            };
            self.line(&format!("The system{which} for ${}$:", unknowns.join(", ")));
            let rows: Vec<_> = sys
                .equations
                .iter()
                .map(|e| vec![self.terms(&e.residual), self.one("0".into())])
                .collect();
            self.align(true, &rows);
            if sol.used_accelerations {
                self.line("With the accelerations of Lagrange's equations put in, its solution:");
            } else {
                self.line("Its solution:");
            }
            let rows: Vec<_> = sol
                .values
                .iter()
                .filter(|(n, _)| !sol.free.contains(n))
                .map(|(n, v)| vec![self.one(self.sym(n, 0)), self.terms(v)])
                .collect();
            self.align(false, &rows);
            if !sol.free.is_empty() {
                let f: Vec<String> = sol
                    .free
                    .iter()
                    .map(|n| format!("${}$", self.sym(n, 0)))
                    .collect();
                self.line(&format!("The equations leave {} free.", f.join(", ")));
            }
            if !sol.checks.is_empty() {
                let c: Vec<String> = sol
                    .checks
                    .iter()
                    .map(|&i| system::equation_number(sys, i).to_string())
                    .collect();
                self.line(&format!(
                    "Equations {} follow from the others and hold.",
                    c.join(", ")
                ));
            }
        }
    }

    /// `qdot forces`: Q_k.
    pub fn forces(&mut self, coords: &[String], q: &[Expr]) {
        self.line("The generalized forces, $\\delta L = \\sum_{k} Q_{k}\\,\\delta q_{k}$:");
        let rows: Vec<_> = coords
            .iter()
            .zip(q)
            .map(|(c, e)| vec![self.one(self.indexed("Q", c)), self.terms(e)])
            .collect();
        self.align(false, &rows);
    }

    /// `qdot equilibrium`: the conditions and the positions.
    pub fn equilibrium(&mut self, eq: &Equilibria) {
        if eq.steady.is_empty() {
            self.forces(&eq.coordinates, &eq.forces);
            self.line("The equilibrium conditions:");
        } else {
            let turning: Vec<String> = eq.steady.iter().map(|(c, _)| self.sym(c, 0)).collect();
            self.line(&format!(
                "Steady motions: ${}$ turning at constant rates, the other coordinates at rest where",
                turning.join(", ")
            ));
        }
        let rows: Vec<_> = eq
            .conditions
            .iter()
            .map(|f| vec![self.terms(f), self.one("0".into())])
            .collect();
        self.align(true, &rows);
        if eq.equilibria.is_empty() {
            self.line("There is no equilibrium.");
            return;
        }
        self.line(if !eq.steady.is_empty() {
            "The steady motions:"
        } else if eq.exact {
            "The equilibria:"
        } else {
            "The equilibria (numeric, at the given parameter values):"
        });
        self.out.push_str("\\begin{enumerate}\n");
        for e in &eq.equilibria {
            let tex = |x: &Expr| latex_with(x, &self.names);
            let vals = match &e.position {
                crate::solve::equilibrium::Position::Exact(_) => position_strings(eq, e, &tex),
                crate::solve::equilibrium::Position::Numeric(_) => {
                    position_strings(eq, e, &|x: &Expr| crate::expr::print::input(x))
                }
            };
            let parts: Vec<String> = eq
                .coordinates
                .iter()
                .zip(&vals)
                .map(|(c, v)| {
                    let v = if v == "any" {
                        "\\text{any}".to_string()
                    } else {
                        v.clone()
                    };
                    format!("{} = {v}", self.sym(c, 0))
                })
                .collect();
            let why = match &e.stability {
                Stability::Undecided(_) => " (undecided)".to_string(),
                s => format!(": {}", s.word()),
            };
            self.out
                .push_str(&format!("  \\item ${}${why}\n", parts.join(",\\quad ")));
        }
        self.out.push_str("\\end{enumerate}\n");
    }

    /// A steady motion: its conditions and solved rates, and the momenta
    /// Routh's reduction holds.
    fn steady_motion(&mut self, sm: &crate::solve::oscillations::SteadyMotion) {
        let cyclic: Vec<String> = sm.rates.iter().map(|(c, _)| self.sym(c, 0)).collect();
        self.line(&format!(
            "A steady motion: ${}$ turning at constant rates, the other coordinates at rest.",
            cyclic.join(", ")
        ));
        let mut rows = Vec::new();
        for (_, f) in sm.conditions.iter().chain(&sm.held) {
            rows.push(vec![self.terms(f), self.one("0".into())]);
        }
        for s in &sm.solved {
            let power = if s.squared { "^{2}" } else { "" };
            let rate = format!("{}{power}", self.sym(&s.coordinate, 1));
            rows.push(vec![self.one(rate.clone()), self.terms(&s.value)]);
            for o in &s.others {
                rows.push(vec![
                    self.one(format!("\\text{{or }}{rate}")),
                    self.terms(o),
                ]);
            }
        }
        self.align(false, &rows);
        let held: Vec<String> = cyclic.iter().map(|c| format!("p_{{{c}}}")).collect();
        self.line(&format!(
            "Linearized about it with the momenta ${}$ held (Routh's reduction).",
            held.join(", ")
        ));
    }

    /// `qdot modes`: M, C, K, the characteristic equation, ω², the modes.
    pub fn modes(&mut self, md: &Modes) {
        let q: Vec<String> = md.coordinates.iter().map(|c| self.sym(c, 0)).collect();
        if let Some(sm) = &md.steady {
            self.steady_motion(sm);
        }
        self.line(&format!(
            "Small oscillations in ${}$, $M \\ddot{{q}} + C \\dot{{q}} + K q = f(t)$:",
            q.join(", ")
        ));
        self.matrix("M", &md.mass);
        if md.damping.iter().flatten().any(|e| !e.is_zero()) {
            self.matrix("C", &md.damping);
        }
        self.matrix("K", &md.stiffness);
        // λ = ω², with ω printed as a coordinate so that the terms are
        // collected by its powers
        let lambda = crate::expr::atom::unknown(crate::solve::oscillations::LAMBDA);
        let w2 = Expr::coord("omega", 0).powi(2);
        let subst = |e: &Expr| w2.as_ref().ok().and_then(|w| e.subs(lambda, w).ok());
        let factored = self.characteristic_factors(md.factors.iter().filter_map(&subst));
        self.line("The characteristic equation:");
        let det = if md.gyroscopic {
            "\\det(K + s C + s^{2} M),\\ s = i\\omega"
        } else {
            "\\det(K - \\omega^{2} M)"
        };
        let mut chain = vec![self.one(det.into())];
        if let Some(c) = subst(&md.characteristic) {
            // expanded here, factored next
            chain.push(crate::expr::compact::canonical_only(|| self.terms(&c)));
        }
        if let Some(f) = factored {
            chain.push(self.one(f));
        }
        chain.push(self.one("0".into()));
        self.align(true, &[chain]);
        if md.omega_squared.is_empty() {
            let why = md.no_closed_form.as_deref().unwrap_or("no closed form");
            self.line(&format!("It has no closed-form roots ({why})."));
            return;
        }
        if md.modes.is_empty() {
            // gyroscopic (complex modes) or defective: the frequencies alone
            self.line(if md.gyroscopic {
                "The natural frequencies (the modes of a gyroscopic system are complex):"
            } else {
                "The natural frequencies (a repeated one has fewer modes than its multiplicity):"
            });
            let rows: Vec<Vec<Vec<(bool, String)>>> = md
                .omega_squared
                .iter()
                .enumerate()
                .map(|(i, w)| {
                    vec![
                        self.one(format!("\\omega_{{{}}}^{{2}}", i + 1)),
                        self.one(latex_expanded(w, &self.names)),
                    ]
                })
                .collect();
            self.align(false, &rows);
            return;
        }
        self.line("The natural frequencies and the modes (normalized to the first coordinate):");
        let mut rows = Vec::new();
        for (i, (w, mode)) in md.omega_squared.iter().zip(&md.modes).enumerate() {
            let k = i + 1;
            rows.push(vec![
                self.one(format!("\\omega_{{{k}}}^{{2}}")),
                self.one(latex_expanded(w, &self.names)),
            ]);
            // display-style fractions: a mode's ratios are read, not skimmed
            let v: Vec<String> = mode
                .iter()
                .map(|x| self.tex(x).replace("\\frac{", "\\dfrac{"))
                .collect();
            rows.push(vec![
                self.one(format!("v_{{{k}}}")),
                self.one(format!(
                    "\\begin{{pmatrix}} {} \\end{{pmatrix}}",
                    v.join(" \\\\ ")
                )),
            ]);
        }
        self.align(false, &rows);
        let st = match &md.stability {
            Stability::Stable => "stable (every $\\omega^{2} > 0$)",
            Stability::Unstable => "unstable (a solution of the linearization grows)",
            Stability::Undecided(_) => {
                "undecided (the parameters or the linearization leave it open)"
            }
        };
        self.line(&format!("The equilibrium is {st}."));
    }

    /// The characteristic polynomial's factors as a lecturer writes them:
    /// each with integer coefficients without a common divisor and a
    /// positive first term, the rational content and the signs gathered in
    /// one number in front (`\frac{1}{2} (m (3 M_{0} + m) \omega^{4} - …)`);
    /// `None` when that is the expanded polynomial again.
    fn characteristic_factors(&self, factors: impl Iterator<Item = Expr>) -> Option<String> {
        let mut constant = crate::num::Q::one();
        let mut polys: Vec<Expr> = Vec::new();
        // factors 1/r, 1/d⁶: written with the content as one fraction
        let mut reciprocals = Expr::one();
        for f in factors {
            if let Some(q) = f.as_rational() {
                constant *= q;
                continue;
            }
            if f.num().is_constant() {
                reciprocals = reciprocals.mul(&f);
                continue;
            }
            let content = f.num().content().checked_div(&f.den().content())?;
            let mut f = f.scale(&content.recip()?);
            constant *= content;
            if self.terms(&f).first().is_some_and(|t| t.0) {
                f = f.neg();
                constant = -constant;
            }
            polys.push(f);
        }
        let unit = constant.abs().is_one() && reciprocals.is_one();
        if polys.len() < 2 && unit {
            return None;
        }
        let mut out = Vec::new();
        if !unit {
            out.push(self.tex(&reciprocals.scale(&constant.abs())));
        }
        for f in &polys {
            let s = join(self.terms(f));
            out.push(if crate::expr::print::is_sum(&s) {
                parens(&s)
            } else {
                s
            });
        }
        let sign = if constant.is_negative() { "-" } else { "" };
        Some(format!("{sign}{}", out.join(" ")))
    }

    // -------------------------------------------------------------- steps

    /// The derivation, line by line (§23.5 of the seed).
    pub fn steps(&mut self, scene: &Scene, lag: &Lagrange) {
        let (e_name, has_bodies) = self.steps_energies(scene, lag);
        self.forces_steps(scene);
        self.constraints_steps(scene);
        self.steps_equations(scene, lag, &e_name, has_bodies);
    }

    /// Each coordinate's Lagrange equation, term by term.
    fn steps_equations(&mut self, scene: &Scene, lag: &Lagrange, e_name: &str, has_bodies: bool) {
        for eq in &lag.equations {
            let c = &eq.coordinate;
            let q = self.sym(c, 0);
            let qd = self.sym(c, 1);
            self.para(&format!("The coordinate ${q}$."), "");
            let e_var = |order: u32| crate::expr::atom::coord(c, order);
            let e = &lag.kinetic;
            let p = e.diff(e_var(1));
            let mut rows = Vec::new();
            if has_bodies {
                let dq = format!("\\frac{{\\partial {e_name}}}{{\\partial {qd}}}");
                rows.push(vec![self.one(dq.clone()), self.terms(&p)]);
                rows.push(vec![
                    self.one(format!("\\frac{{d}}{{dt}} {dq}")),
                    self.terms(&p.dt()),
                ]);
                rows.push(vec![
                    self.one(format!("\\frac{{\\partial {e_name}}}{{\\partial {q}}}")),
                    self.terms(&e.diff(e_var(0))),
                ]);
            }
            let parts = eq.rhs_terms.as_slice();
            let mut chain = vec![self.one(self.indexed("Q", c))];
            if !parts.is_empty() {
                let formulas: Vec<(bool, String)> = parts
                    .iter()
                    .flat_map(|t| self.source(scene, t.source, c))
                    .collect();
                chain.push(formulas);
                // the sources' values side by side, unless they are the
                // result's terms in another order
                let spread: Vec<(bool, String)> =
                    parts.iter().flat_map(|t| self.terms(&t.value)).collect();
                if parts.len() > 1 && !same_terms(&spread, &self.terms(&eq.rhs)) {
                    chain.push(
                        parts
                            .iter()
                            .enumerate()
                            .map(|(i, t)| {
                                let s = self.tex(&t.value);
                                let (neg, body) = match s.strip_prefix('-') {
                                    Some(b) if !crate::expr::print::is_sum(&s) => {
                                        (true, b.to_string())
                                    }
                                    _ if crate::expr::print::is_sum(&s) && i > 0 => {
                                        (false, parens(&s))
                                    }
                                    _ => (false, s),
                                };
                                (neg, body)
                            })
                            .collect(),
                    );
                }
            }
            chain.push(self.terms(&eq.rhs));
            rows.push(chain);
            self.align(false, &rows);
            self.line("and Lagrange's equation");
            self.align(true, &[vec![self.terms(&eq.lhs), self.terms(&eq.rhs)]]);
        }
    }

    /// The constraints, numbered as the generalized forces name them
    /// (`g_j` holonomic, `h_j` in the velocities), with their multipliers.
    fn constraints_steps(&mut self, scene: &Scene) {
        if scene.constraints.is_empty() {
            return;
        }
        self.para(
            "Constraints.",
            "A holonomic constraint $g_{j} = 0$ adds its multiplier times $\\frac{\\partial g_{j}}{\\partial q_{k}}$ to $Q_{k}$, a constraint in the velocities $h_{j} = \\sum_{k} a_{j,k} \\dot{q}_{k} + b_{j} = 0$ its multiplier times $a_{j,k}$:",
        );
        let rows: Vec<_> = scene
            .constraints
            .iter()
            .enumerate()
            .map(|(j, c)| {
                let k = j + 1;
                let name = if c.holonomic { "g" } else { "h" };
                vec![
                    self.one(format!("{name}_{{{k}}}")),
                    self.terms(&c.expression),
                    self.one("0".into()),
                ]
            })
            .collect();
        self.align(false, &rows);
        let lambdas: Vec<String> = scene
            .constraints
            .iter()
            .enumerate()
            .map(|(j, c)| {
                let name = if c.holonomic { "g" } else { "h" };
                format!(
                    "${}$ for ${name}_{{{}}}$",
                    self.sym(&c.multiplier, 0),
                    j + 1
                )
            })
            .collect();
        let list: Vec<&str> = lambdas.iter().map(String::as_str).collect();
        self.line(&format!("The multipliers: {}.", sentence(&list)));
    }

    /// The force function, potential, work, dissipation and the loads.
    fn forces_steps(&mut self, scene: &Scene) {
        let roles = [
            (Role::ForceFunction, "the force function"),
            (Role::Potential, "the potential energy"),
            (Role::Work, "the work of the non-conservative forces"),
            (Role::Dissipation, "the dissipation function"),
            (Role::Rayleigh, "Rayleigh's dissipation function"),
        ];
        let mut rows = Vec::new();
        let mut what = Vec::new();
        for (role, text) in roles {
            for d in scene.role(role) {
                if let Some(v) = d.value.as_scalar() {
                    rows.push(vec![self.one(self.sym(&d.name, 0)), self.terms(v)]);
                    if !what.contains(&text) {
                        what.push(text);
                    }
                }
            }
        }
        if rows.is_empty()
            && scene.loads.is_empty()
            && scene.torques.is_empty()
            && scene.forces.is_empty()
        {
            return;
        }
        let intro = if what.is_empty() {
            String::new()
        } else {
            format!("{}:", sentence(&what))
        };
        self.para("Forces.", &capitalize(&intro));
        self.align(false, &rows);
        if !scene.loads.is_empty() {
            self.line("The loads, each a force $\\mathbf{F}_{i}$ at a point $\\mathbf{r}_{i}$:");
            let mut lrows = Vec::new();
            for (i, ld) in scene.loads.iter().enumerate() {
                let k = i + 1;
                lrows.push(vec![
                    self.one(format!("\\mathbf{{F}}_{{{k}}}")),
                    self.one(self.value(&ld.force)),
                ]);
                lrows.push(vec![
                    self.one(format!("\\mathbf{{r}}_{{{k}}}")),
                    self.one(self.value(&ld.point)),
                ]);
            }
            self.align(false, &lrows);
        }
        if !scene.torques.is_empty() {
            self.line("The torques, each a moment $M_{i}$ on an angle $\\varphi_{i}$:");
            let mut trows = Vec::new();
            for (i, t) in scene.torques.iter().enumerate() {
                let k = i + 1;
                trows.push(vec![self.one(format!("M_{{{k}}}")), self.terms(&t.moment)]);
                trows.push(vec![
                    self.one(format!("\\varphi_{{{k}}}")),
                    self.terms(&t.angle),
                ]);
            }
            self.align(false, &trows);
        }
    }

    fn value(&self, v: &crate::scene::Value) -> String {
        match v {
            crate::scene::Value::Scalar(e) => self.tex(e),
            crate::scene::Value::Vector(c) => {
                let parts: Vec<String> = c.iter().map(|e| self.tex(e)).collect();
                format!(
                    "\\begin{{pmatrix}} {} \\end{{pmatrix}}",
                    parts.join(" \\\\ ")
                )
            }
            crate::scene::Value::Rotation(r) => {
                let rows: Vec<String> = r
                    .matrix()
                    .iter()
                    .map(|row| {
                        let cells: Vec<String> = row.iter().map(|e| self.tex(e)).collect();
                        cells.join(" & ")
                    })
                    .collect();
                format!(
                    "\\begin{{pmatrix}} {} \\end{{pmatrix}}",
                    rows.join(" \\\\ ")
                )
            }
        }
    }

    /// The formula of one source of Q_k: `\frac{\partial U}{\partial y_{3}}`.
    fn source(&self, scene: &Scene, s: Source, c: &str) -> Vec<(bool, String)> {
        let q = self.sym(c, 0);
        let qd = self.sym(c, 1);
        let d = |f: &str, x: &str| format!("\\frac{{\\partial {f}}}{{\\partial {x}}}");
        let name = |role: Role, default: &str| {
            let mut it = scene.role(role);
            match (it.next(), it.next()) {
                (Some(one), None) => self.sym(&one.name, 0),
                _ => default.to_string(),
            }
        };
        // +∂A/∂x − ∂B/∂x for the roles the scene has: U and V, D and R
        let pair = |plus: (Role, &str), minus: (Role, &str), x: &str| {
            [(false, plus), (true, minus)]
                .into_iter()
                .filter(|(_, (role, _))| scene.has_role(*role))
                .map(|(neg, (role, letter))| (neg, d(&name(role, letter), x)))
                .collect::<Vec<_>>()
        };
        match s {
            Source::Potential => {
                // a velocity-dependent (generalized) potential also has
                // its d/dt ∂/∂q̇ term: Q = d/dt(∂V/∂q̇) − ∂V/∂q
                let qd_var = crate::expr::atom::coord(c, 1);
                let mut terms = Vec::new();
                for (neg, role, letter) in [
                    (false, Role::ForceFunction, "U"),
                    (true, Role::Potential, "V"),
                ] {
                    if !scene.has_role(role) {
                        continue;
                    }
                    let f = name(role, letter);
                    terms.push((neg, d(&f, &q)));
                    if scene.role_sum(role).depends_on(qd_var) {
                        terms.push((!neg, format!("\\frac{{d}}{{dt}} {}", d(&f, &qd))));
                    }
                }
                terms
            }
            Source::Work => vec![(false, d(&name(Role::Work, "L"), &q))],
            Source::Dissipation => pair((Role::Dissipation, "D"), (Role::Rayleigh, "R"), &qd),
            Source::Force => vec![(false, format!("Q^{{*}}_{{{q}}}"))],
            Source::Load(i) => {
                let k = i + 1;
                vec![(
                    false,
                    format!(
                        "\\mathbf{{F}}_{{{k}}} \\cdot {}",
                        d(&format!("\\mathbf{{r}}_{{{k}}}"), &q)
                    ),
                )]
            }
            Source::Torque(i) => {
                let k = i + 1;
                vec![(
                    false,
                    format!("M_{{{k}}} {}", d(&format!("\\varphi_{{{k}}}"), &q)),
                )]
            }
            Source::Constraint(j) => {
                // λ_j·∂g_j/∂q_k for a holonomic g_j = 0, λ_j·a_jk otherwise
                let Some(c) = scene.constraints.get(j) else {
                    return Vec::new();
                };
                let lambda = self.sym(&c.multiplier, 0);
                let k = j + 1;
                let factor = if c.holonomic {
                    d(&format!("g_{{{k}}}"), &q)
                } else {
                    format!("a_{{{k},{q}}}")
                };
                vec![(false, format!("{lambda} {factor}"))]
            }
            Source::Friction(i) => {
                // F·∂s/∂q_k, s the slide (or the relative angle) it opposes
                let Some(f) = scene.joints.get(i).and_then(|j| j.friction.as_ref()) else {
                    return Vec::new();
                };
                let k = i + 1;
                vec![(
                    false,
                    format!(
                        "{} {}",
                        self.sym(&f.unknown, 0),
                        d(&format!("s_{{{k}}}"), &q)
                    ),
                )]
            }
        }
    }
}

/// `a`, `a and b`, `a, b and c`.
fn sentence(items: &[&str]) -> String {
    match items {
        [] => String::new(),
        [a] => a.to_string(),
        [rest @ .., last] => format!("{} and {last}", rest.join(", ")),
    }
}

fn capitalize(s: &str) -> String {
    let mut c = s.chars();
    match c.next() {
        Some(f) => f.to_uppercase().chain(c).collect(),
        None => String::new(),
    }
}

/// A chain without its repeated steps: a side with the same terms as the
/// next one, in any order, is left out (`= -k x - c \dot{x} = -c \dot{x} -
/// k x` is one step), the later kept for its display order. The first side
/// is what the row defines, and stays.
fn distinct_steps(sides: &[Vec<(bool, String)>]) -> Vec<Vec<(bool, String)>> {
    let mut out: Vec<Vec<(bool, String)>> = Vec::with_capacity(sides.len());
    for side in sides {
        if out.len() >= 2 && out.last().is_some_and(|last| same_terms(last, side)) {
            out.pop();
        }
        out.push(side.clone());
    }
    out
}

/// Whether two sums have the same signed terms, in any order.
fn same_terms(a: &[(bool, String)], b: &[(bool, String)]) -> bool {
    let sorted = |side: &[(bool, String)]| {
        let mut t = side.to_vec();
        t.sort();
        t
    };
    a.len() == b.len() && sorted(a) == sorted(b)
}

/// Parentheses around a sum, grown to its height when it holds a fraction,
/// a radical or a matrix.
fn parens(s: &str) -> String {
    if ["\\frac", "\\dfrac", "\\sqrt", "\\begin"]
        .iter()
        .any(|tall| s.contains(tall))
    {
        format!("\\left({s}\\right)")
    } else {
        format!("({s})")
    }
}

/// Lines of one aligned row `side₀ = side₁ = …`, broken before a term
/// where a line would grow past [`LINE`].
fn layout(sides: &[Vec<(bool, String)>]) -> Vec<String> {
    // pieces: (starts a side after the first, text with its sign)
    let mut pieces: Vec<(bool, String, f64)> = Vec::new();
    for (i, side) in sides.iter().enumerate() {
        let side: Vec<(bool, String)> = if side.is_empty() {
            vec![(false, "0".into())]
        } else {
            side.clone()
        };
        for (j, (neg, t)) in side.iter().enumerate() {
            let text = match (i > 0, j == 0, neg) {
                (true, true, false) => format!("= {t}"),
                (true, true, true) => format!("= -{t}"),
                (false, true, true) => format!("-{t}"),
                (false, true, false) => t.clone(),
                (_, false, true) => format!("- {t}"),
                (_, false, false) => format!("+ {t}"),
            };
            let w = width(&text);
            pieces.push((i > 0 && j == 0, text, w));
        }
    }
    let total: f64 = pieces.iter().map(|p| p.2).sum();
    let lhs_end = pieces.iter().position(|p| p.0).unwrap_or(pieces.len());
    let lhs_width: f64 = pieces[..lhs_end].iter().map(|p| p.2).sum();
    let concat = |ps: &[(bool, String, f64)]| {
        ps.iter()
            .map(|p| p.1.as_str())
            .collect::<Vec<_>>()
            .join(" ")
    };
    if total <= LINE {
        if lhs_end == pieces.len() {
            return vec![concat(&pieces)];
        }
        return vec![format!(
            "{} &{}",
            concat(&pieces[..lhs_end]),
            concat(&pieces[lhs_end..])
        )];
    }
    // The left side on the first line when it fits, aligned at its `=`.
    let lhs_fits = lhs_width <= LINE * 0.6 && lhs_end < pieces.len();
    let mut lines: Vec<String> = Vec::new();
    let mut cur = String::new();
    let mut cur_w = 0.0;
    let start = if lhs_fits {
        cur = format!("{} &", concat(&pieces[..lhs_end]));
        cur_w = lhs_width;
        lhs_end
    } else {
        cur.push('&');
        0
    };
    let mut first_on_line = !lhs_fits;
    for (k, (is_eq, text, w)) in pieces[start..].iter().enumerate() {
        let avail = if lines.is_empty() { LINE } else { LINE - 2.0 };
        if cur_w + w > avail && !first_on_line && k > 0
            || (*is_eq && !lines.is_empty() && !first_on_line && !lhs_fits)
        {
            lines.push(cur);
            cur = if *is_eq {
                "&".to_string()
            } else {
                "&\\quad".to_string()
            };
            cur_w = if *is_eq { 0.0 } else { 2.0 };
        }
        if !(cur.ends_with('&') && text.starts_with('=')) {
            cur.push(' ');
        }
        cur.push_str(text);
        cur_w += w;
        first_on_line = false;
    }
    lines.push(cur);
    lines
}

/// The printed width of mathematics in letters, roughly: a fraction as
/// wide as its wider part, scripts at 70 %, commands by what they show.
pub fn width(tex: &str) -> f64 {
    let b = tex.as_bytes();
    let mut i = 0;
    let mut w = 0.0;
    // the brace group starting at j (b[j] == '{'): (content, index after)
    let group = |j: usize| -> (&str, usize) {
        if j >= b.len() || b[j] != b'{' {
            return ("", j);
        }
        let mut depth = 0;
        for (k, &c) in b.iter().enumerate().skip(j) {
            if c == b'{' {
                depth += 1;
            } else if c == b'}' {
                depth -= 1;
                if depth == 0 {
                    return (&tex[j + 1..k], k + 1);
                }
            }
        }
        (&tex[j + 1..], b.len())
    };
    while i < b.len() {
        let c = b[i];
        match c {
            b'\\' => {
                let mut j = i + 1;
                while j < b.len() && b[j].is_ascii_alphabetic() {
                    j += 1;
                }
                if j == i + 1 {
                    // \\ \, \; \{ — or any one character, whole (a user's
                    // LaTeX name may hold `\é`)
                    j += tex[i + 1..].chars().next().map_or(0, char::len_utf8);
                }
                let cmd = &tex[i + 1..j.min(tex.len())];
                match cmd {
                    "frac" => {
                        let (a, k) = group(j);
                        let (d, k2) = group(k);
                        w += width(a).max(width(d)) * 0.85 + 0.5;
                        i = k2;
                        continue;
                    }
                    "sqrt" => {
                        let (a, k) = group(j);
                        w += width(a) + 1.0;
                        i = k;
                        continue;
                    }
                    "dot" | "ddot" | "dddot" | "ddddot" | "mathbf" | "mathrm" | "text" => {
                        let (a, k) = group(j);
                        w += width(a);
                        i = k;
                        continue;
                    }
                    "mathit" => {
                        let (a, k) = group(j);
                        w += width(a) * 0.9;
                        i = k;
                        continue;
                    }
                    "left" | "right" | "nonumber" | "begin" | "end" => {}
                    "sin" | "cos" | "det" => w += 2.2,
                    "ln" => w += 1.4,
                    "arctan" | "arcsin" | "arccos" => w += 4.0,
                    "quad" => w += 2.0,
                    "qquad" => w += 4.0,
                    "cdot" => w += 1.2,
                    "partial" => w += 1.0,
                    "," | ";" => w += 0.3,
                    "\\" => {}
                    _ => w += 1.0, // a Greek letter
                }
                i = j;
            }
            b'^' | b'_' => {
                let (a, k) = if i + 1 < b.len() && b[i + 1] == b'{' {
                    group(i + 1)
                } else {
                    // one character, whole
                    let end = i + 1 + tex[i + 1..].chars().next().map_or(0, char::len_utf8);
                    (&tex[i + 1..end], end)
                };
                w += width(a) * 0.7;
                i = k;
            }
            b'{' | b'}' | b' ' | b'&' => i += 1,
            b'+' | b'-' | b'=' => {
                w += 1.8;
                i += 1;
            }
            b'(' | b')' => {
                w += 0.5;
                i += 1;
            }
            _ => {
                // one character, whatever its bytes
                w += 1.0;
                i += tex[i..].chars().next().map_or(1, char::len_utf8);
            }
        }
    }
    w
}

/// A whole `article` around a body.
pub fn standalone(title: &str, body: &str) -> String {
    format!(
        "\\documentclass[10pt]{{article}}\n\
         \\usepackage{{amsmath}}\n\
         \\usepackage[margin=2.5cm]{{geometry}}\n\
         \\setlength{{\\parindent}}{{0pt}}\n\
         \\setlength{{\\parskip}}{{0.5ex}}\n\
         \\begin{{document}}\n\
         \\section*{{{}}}\n\
         {body}\
         \\end{{document}}\n",
        escape_text(title)
    )
}

/// Text (not mathematics) with TeX's special characters escaped.
pub fn escape_text(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '\\' => out.push_str("\\textbackslash{}"),
            '_' | '%' | '$' | '#' | '&' | '{' | '}' => {
                out.push('\\');
                out.push(c);
            }
            '~' => out.push_str("\\textasciitilde{}"),
            '^' => out.push_str("\\textasciicircum{}"),
            // what pdflatex's UTF-8 input cannot set in text (a title
            // taken from a scene's comment: `−k/r²`, `θ`)
            '−' => out.push_str("\\ensuremath{-}"),
            'Ͱ'..='Ͽ' => {
                let tex = crate::expr::latex::Names::new().symbol(&c.to_string(), 0);
                if tex.starts_with('\\') {
                    out.push_str(&format!("\\ensuremath{{{tex}}}"));
                } else {
                    out.push(c);
                }
            }
            c => out.push(c),
        }
    }
    out
}
