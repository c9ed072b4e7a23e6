//! The readable text of `derive`, `solve`, `forces`, `solve` blocks and
//! `equilibrium`.

use super::{as_unicode, minus, position_strings};
use crate::expr::print::pretty_name;
use crate::expr::Expr;
use crate::mechanics::Lagrange;
use crate::scene::Scene;
use crate::solve::equilibrium::{self, Equilibria};
use crate::solve::system::{self, BlockSolution};

/// The text of `qdot derive`.
pub fn derive_text(l: &Lagrange) -> String {
    let mut out = intermediates_text(l.intermediates.as_deref(), super::wire::lagrange_exprs(l));
    equations_text(&mut out, l);
    out
}

/// The named intermediates `roots` are written through, in evaluation
/// order, as a block before the results (empty without them).
pub fn intermediates_text<'a>(
    tape: Option<&crate::expr::tape::Tape>,
    roots: impl IntoIterator<Item = &'a Expr>,
) -> String {
    let Some(tape) = tape else {
        return String::new();
    };
    let used = tape.used_by(roots);
    if used.is_empty() {
        return String::new();
    }
    let mut out =
        String::from("Intermediates  (in order: each is written in the ones before it)\n");
    for i in used {
        let e = &tape.entries()[i];
        out.push_str(&format!(
            "  {} = {}\n",
            as_unicode(&e.expr()),
            as_unicode(&e.value)
        ));
    }
    out.push('\n');
    out
}

/// Lagrange's equations, M and f.
fn equations_text(out: &mut String, l: &Lagrange) {
    out.push_str("Lagrange's equations  d/dt(∂E/∂q̇) − ∂E/∂q = Q\n");
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
            as_unicode(&e.lhs),
            as_unicode(&e.rhs)
        ));
    }
    out.push('\n');
    matrix_text(out, "Mass matrix M  (M·q̈ = f)", &l.mass_matrix);
    out.push_str("\nForcing f\n");
    for (c, f) in l.coordinates.iter().zip(&l.forcing) {
        out.push_str(&format!(
            "  {}  {}\n",
            padded(&pretty_name(c, 0), width),
            as_unicode(f)
        ));
    }
    constraints_text(out, l);
}

/// The constraints at the level of the accelerations, A·q̈ = γ, and the
/// multipliers they bring (nothing without constraints).
fn constraints_text(out: &mut String, l: &Lagrange) {
    let rows = &l.constraints;
    if rows.is_empty() {
        return;
    }
    out.push_str(
        "
Constraints  A·q̈ = γ  (constraint j adds λ_j·A_jk to Q_k)
",
    );
    let q: Vec<String> = l.coordinates.iter().map(|c| pretty_name(c, 0)).collect();
    for (j, label) in rows.labels.iter().enumerate() {
        let kind = if rows.holonomic[j] {
            "holonomic"
        } else {
            "in the velocities"
        };
        out.push_str(&format!(
            "  {} ({kind}), multiplier {}
",
            label.trim_matches('`'),
            pretty_name(&rows.multipliers[j], 0)
        ));
        let row: Vec<String> = rows.matrix[j]
            .iter()
            .zip(&q)
            .filter(|(a, _)| !a.is_zero())
            .map(|(a, q)| format!("A_{q} = {}", as_unicode(a)))
            .collect();
        out.push_str(&format!(
            "    {}
",
            row.join(", ")
        ));
        out.push_str(&format!(
            "    γ = {}
",
            as_unicode(&rows.forcing[j])
        ));
    }
}

/// The energies the `body`, `particle` and `gravity` statements
/// contribute, each with the statement that gives it (empty for a scene
/// without them).
pub fn bodies_text(scene: &Scene) -> String {
    if scene.bodies.is_empty() {
        return String::new();
    }
    let line =
        |span: crate::diag::Span| crate::diag::Diagnostic::line_col(&scene.source, span.start).0;
    let mut out = String::from("Energies of the bodies  E = Σ E_body, V = Σ V_body + …\n");
    for b in &scene.bodies {
        out.push_str(&format!(
            "  {} {} (line {})\n",
            b.kind.keyword(),
            b.name,
            line(b.span)
        ));
        let energies =
            std::iter::once((&b.kinetic, None)).chain(b.gravity.iter().map(|g| (g, scene.gravity)));
        for (name, from) in energies {
            let Some(value) = scene.definition(name) else {
                continue;
            };
            let from = from.map_or(String::new(), |s| format!("  (gravity, line {})", line(s)));
            out.push_str(&format!(
                "    {} = {}{from}\n",
                pretty_name(name, 0),
                as_unicode(value)
            ));
        }
    }
    out.push('\n');
    out
}

/// The text of `qdot solve`: the accelerations, after the equations.
pub fn solve_text(l: &Lagrange, acc: &crate::mechanics::Accelerations) -> String {
    let mut out = match acc.intermediates() {
        Some(tape) => {
            let roots = super::wire::lagrange_exprs(l).chain(acc.values());
            intermediates_text(Some(tape), roots)
        }
        None => String::new(),
    };
    equations_text(&mut out, l);
    accelerations_text(&mut out, acc);
    out
}

/// `derive` (`acc` None) or `solve`'s dynamics on `scene`: the
/// intermediates first when there are (they cover the bodies' energies
/// and the `blocks`' solutions too), the bodies' energies, the equations,
/// the accelerations.
pub(crate) fn dynamics_text(
    scene: &Scene,
    l: &Lagrange,
    acc: Option<&crate::mechanics::Accelerations>,
    blocks: &[crate::solve::system::BlockSolution],
) -> String {
    let mut out = match super::wire::structured_roots(scene, Some(l), acc, blocks) {
        Some((tape, roots)) => intermediates_text(Some(tape), roots),
        None => String::new(),
    };
    out.push_str(&bodies_text(scene));
    equations_text(&mut out, l);
    if let Some(acc) = acc {
        accelerations_text(&mut out, acc);
    }
    out
}

/// The accelerations and the multipliers.
fn accelerations_text(out: &mut String, acc: &crate::mechanics::Accelerations) {
    out.push_str("\nAccelerations\n");
    for (q, e) in acc {
        out.push_str(&format!("  {} = {}\n", pretty_name(q, 2), as_unicode(e)));
    }
    if !acc.multipliers().is_empty() {
        out.push_str("\nMultipliers  (λ_j·A_jk is the generalized constraint force on q_k)\n");
        for (name, e) in acc.multipliers() {
            out.push_str(&format!("  {} = {}\n", pretty_name(name, 0), as_unicode(e)));
        }
    }
}

/// A driven mechanism's reactions and its frictions' laws.
pub fn mechanism_text(r: &crate::solve::kinetostatic::MechanismReactions) -> String {
    let mut out = String::from(if r.in_order {
        "\nReactions  (kinetostatics: Aᵀ·λ = M·q̈ − f, the accelerations known from the kinematics; in solving order)\n"
    } else {
        "\nReactions  (kinetostatics: Aᵀ·λ = M·q̈ − f, the accelerations known from the kinematics)\n"
    });
    for (name, e) in &r.values {
        out.push_str(&format!("  {} = {}\n", pretty_name(name, 0), as_unicode(e)));
    }
    if !r.friction.is_empty() {
        out.push_str(
            "\nFriction  (Coulomb, the seed's (21.74)–(21.75): opposing the relative motion)\n",
        );
        for f in &r.friction {
            out.push_str(&format!(
                "  {}\n",
                friction_law(f, &|n| pretty_name(n, 0), &as_unicode)
            ));
        }
    }
    out
}

/// `G_f = −μ·|G_n|·sgn(xb′)` in the notation `name` and `expr` give.
pub(crate) fn friction_law(
    f: &crate::solve::kinetostatic::FrictionLaw,
    name: &dyn Fn(&str) -> String,
    expr: &dyn Fn(&Expr) -> String,
) -> String {
    let normal = match &f.normal[..] {
        [one] => format!("|{}|", name(one)),
        many => format!(
            "√({})",
            many.iter()
                .map(|n| format!("{}²", name(n)))
                .collect::<Vec<_>>()
                .join(" + ")
        ),
    };
    let c = expr(&f.coefficient);
    let c = if f.coefficient.as_rational().is_some() || !c.contains([' ', '+', '−']) {
        c
    } else {
        format!("({c})")
    };
    format!(
        "{} = −{c}·{normal}·sgn({})",
        name(&f.name),
        expr(&f.relative_velocity)
    )
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
            as_unicode(e)
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
                as_unicode(v)
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

/// The text of `qdot equilibrium`.
pub fn equilibrium_text(eq: &Equilibria) -> String {
    if !eq.steady.is_empty() {
        return steady_motions_text(eq);
    }
    let mut out = forces_text(&eq.coordinates, &eq.forces);
    if eq.kinetic_terms {
        out.push_str("\nEquilibrium conditions at rest (Q_k plus the kinetic energy's terms ∂E/∂q_k at q̇ = 0)\n");
        for (c, f) in eq.coordinates.iter().zip(&eq.conditions) {
            out.push_str(&format!(
                "  {}:  {} = 0\n",
                pretty_name(c, 0),
                as_unicode(f)
            ));
        }
    }
    out.push_str(if eq.exact {
        "\nEquilibria\n"
    } else {
        "\nEquilibria (numeric: no closed form)\n"
    });
    out.push_str(&positions_text(eq));
    out
}

/// `equilibrium --steady`: the conditions of a steady motion and the ones
/// found.
fn steady_motions_text(eq: &Equilibria) -> String {
    let rates: Vec<String> = eq
        .steady
        .iter()
        .map(|(c, _)| format!("{} = const", pretty_name(c, 1)))
        .collect();
    let mut out = format!(
        "Steady motions  {}, the other coordinates at rest\nConditions (each coordinate's equation there)\n",
        rates.join(", ")
    );
    for (c, f) in eq.coordinates.iter().zip(&eq.conditions) {
        out.push_str(&format!(
            "  {}:  {} = 0\n",
            pretty_name(c, 0),
            as_unicode(f)
        ));
    }
    out.push_str("\nSteady motions (stability about each: `qdot modes --steady`)\n");
    out.push_str(&positions_text(eq));
    out
}

/// The list of equilibria (or steady motions), each with its verdict.
fn positions_text(eq: &Equilibria) -> String {
    let mut out = String::new();
    if eq.equilibria.is_empty() {
        out.push_str("  none\n");
    }
    if let Some(caveat) = super::search_caveat(eq) {
        out.push_str(&format!("  ({caveat})\n"));
    }
    for (i, e) in eq.equilibria.iter().enumerate() {
        let vals = position_strings(eq, e, &as_unicode);
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
        if !e.multipliers.is_empty() {
            let ls: Vec<String> = e
                .multipliers
                .iter()
                .map(|(n, v)| format!("{} = {}", pretty_name(n, 0), as_unicode(v)))
                .collect();
            out.push_str(&format!("     multipliers: {}\n", ls.join(", ")));
        }
        if e.multiplicity > 1 {
            out.push_str(&format!(
                "     a root of multiplicity {} of the condition (V'' = 0 there; decided by the first derivative of V that is not 0)\n",
                e.multiplicity
            ));
        }
        if let Some(why) = super::uncertified_note(e) {
            out.push_str(&format!("     {why}\n"));
        }
        for c in &e.conditions {
            out.push_str(&format!("     exists when {c}\n"));
        }
    }
    out
}

/// `s` padded with spaces to `width` characters. (`format!`'s `{:<w$}`
/// panics for widths over 65,535, and a matrix entry or a name can be
/// longer than that.)
pub fn padded(s: &str, width: usize) -> String {
    let n = display_width(s);
    let mut out = String::with_capacity(s.len() + width.saturating_sub(n));
    out.push_str(s);
    out.extend(std::iter::repeat_n(' ', width.saturating_sub(n)));
    out
}

/// The columns `s` takes on a terminal: combining marks (the dots of
/// ẋ, ẍ) take none.
pub fn display_width(s: &str) -> usize {
    s.chars()
        .filter(|c| !matches!(*c as u32, 0x300..=0x36F | 0x20D0..=0x20FF))
        .count()
}

pub(super) fn matrix_text(out: &mut String, title: &str, m: &[Vec<Expr>]) {
    out.push_str(title);
    out.push('\n');
    let cells: Vec<Vec<String>> = m
        .iter()
        .map(|r| r.iter().map(as_unicode).collect())
        .collect();
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

/// The text of `qdot hamilton`: the momenta, the velocities in them, H
/// and Hamilton's equations.
pub fn hamilton_text(h: &crate::mechanics::Hamiltonian) -> String {
    let q: Vec<String> = h.coordinates.iter().map(|c| pretty_name(c, 0)).collect();
    let p: Vec<String> = h.momentum_names.iter().map(|n| pretty_name(n, 0)).collect();
    let qd: Vec<String> = h.coordinates.iter().map(|c| pretty_name(c, 1)).collect();
    // ṗ_θ: the dot on the p
    let pd = |k: usize| format!("ṗ{}", p[k].strip_prefix('p').unwrap_or(&p[k]));
    let wp = p.iter().map(|s| display_width(s)).max().unwrap_or(1);
    let wq = qd.iter().map(|s| display_width(s)).max().unwrap_or(1);
    let mut out = intermediates_text(h.intermediates.as_deref(), h.exprs());
    out.push_str("Momenta  p = ∂L/∂q̇\n");
    for (k, m) in h.momenta.iter().enumerate() {
        out.push_str(&format!("  {} = {}\n", padded(&p[k], wp), as_unicode(m)));
    }
    out.push_str("\nVelocities\n");
    for (k, v) in h.velocities.iter().enumerate() {
        out.push_str(&format!("  {} = {}\n", padded(&qd[k], wq), as_unicode(v)));
    }
    out.push_str("\nHamiltonian  H = Σ p·q̇ − L\n");
    out.push_str(&format!("  H = {}\n", as_unicode(&h.hamiltonian)));
    let nonconservative = h.other_forces.iter().any(|f| !f.is_zero());
    out.push_str(if nonconservative {
        "\nHamilton's equations  q̇ = ∂H/∂p, ṗ = −∂H/∂q + Q̃\n"
    } else {
        "\nHamilton's equations  q̇ = ∂H/∂p, ṗ = −∂H/∂q\n"
    });
    let w = wp.max(wq);
    for (k, qdk) in qd.iter().enumerate() {
        out.push_str(&format!(
            "  {} = {}\n",
            padded(qdk, w),
            as_unicode(&h.velocities[k])
        ));
        out.push_str(&format!(
            "  {} = {}\n",
            padded(&pd(k), w),
            as_unicode(&h.momentum_rates[k])
        ));
    }
    if nonconservative {
        out.push_str("\nForces outside H  Q̃\n");
        for (k, f) in h.other_forces.iter().enumerate() {
            if !f.is_zero() {
                out.push_str(&format!("  Q̃_{} = {}\n", q[k], as_unicode(f)));
            }
        }
    }
    out
}

/// The text of `qdot integrals`: the conserved momenta, the energy
/// integral, Routh's reduction and why an integral is missing.
pub fn integrals_text(i: &crate::mechanics::Integrals) -> String {
    let mut out = String::from(
        "Cyclic coordinates  (absent from L, no other force on them: p = ∂L/∂q̇ is conserved)\n",
    );
    if i.cyclic.is_empty() {
        out.push_str("  none\n");
    }
    for (q, p) in &i.cyclic {
        out.push_str(&format!(
            "  {}: {} = {} = const\n",
            pretty_name(q, 0),
            pretty_name(&crate::scene::momentum_name(q), 0),
            as_unicode(p)
        ));
    }
    out.push_str("\nEnergy integral  h = Σ q̇·∂L/∂q̇ − L\n");
    match &i.energy {
        Some(h) if i.energy_is_e_plus_v => {
            out.push_str(&format!("  h = E + V = {} = const\n", as_unicode(h)))
        }
        Some(h) => out.push_str(&format!("  h = {} = const\n", as_unicode(h))),
        None => out.push_str("  none\n"),
    }
    if let Some(r) = &i.routh {
        let cyc: Vec<String> = i.cyclic.iter().map(|(q, _)| pretty_name(q, 0)).collect();
        out.push_str(&format!(
            "\nRouthian  R = L − Σ p·q̇ over {}, the momenta constant\n",
            cyc.join(", ")
        ));
        out.push_str(&format!("  R = {}\n", as_unicode(&r.routhian)));
        out.push_str(&format!(
            "  effective potential  V_eff = −R at rest = {}\n",
            as_unicode(&r.effective_potential)
        ));
        out.push_str("\nReduced equations  d/dt(∂R/∂q̇) − ∂R/∂q = Q̃\n");
        for (q, a) in &r.accelerations {
            out.push_str(&format!("  {} = {}\n", pretty_name(q, 2), as_unicode(a)));
        }
    }
    if !i.notes.is_empty() {
        out.push_str("\nNotes\n");
        for n in &i.notes {
            out.push_str(&format!("  {n}\n"));
        }
    }
    out
}

/// The forces of the `reaction` statements (nothing without them).
pub fn reactions_text(scene: &Scene, forces: &[Vec<Expr>]) -> String {
    if forces.is_empty() {
        return String::new();
    }
    let mut out = String::from("\nReactions  (R at P: Σ_i R_i·∂P_i/∂q_k = λ·A_k)\n");
    for (r, f) in scene.reactions.iter().zip(forces) {
        let c = &scene.constraints[r.constraint];
        let value = match f.as_slice() {
            [one] => as_unicode(one),
            many => format!(
                "[{}]",
                many.iter().map(as_unicode).collect::<Vec<_>>().join(", ")
            ),
        };
        out.push_str(&format!(
            "  {} at {}:  R = {value}\n",
            c.label(r.constraint).trim_matches('`'),
            r.written
        ));
    }
    out
}
