//! What each statement asks of dimensions: energies and powers for the
//! role statements, the conjugate of a coordinate for `force`, work for
//! `load` and `torque`, like sides for a `solve` equation.

use super::dim::Dimension;
use super::form::DimForm;
use super::walk::{DimValue, NameDim, Walker, Want, Why};
use crate::diag::Diagnostic;
use crate::parse::ast::{BodyStmt, Equation, Expr, ExprKind, Ident, PropertyKey, Role, SolveBlock};

type Checked<T> = Result<T, Diagnostic>;

/// The dimension a role statement's value has, and what the role is called.
pub(super) fn role_want(role: Role, name: &str) -> Want {
    let (dimension, what) = match role {
        Role::Kinetic => (Dimension::ENERGY, "a kinetic energy"),
        Role::Potential => (Dimension::ENERGY, "a potential energy"),
        Role::ForceFunction => (Dimension::ENERGY, "a force function (U = −V, an energy)"),
        Role::Work => (Dimension::ENERGY, "the work of the non-conservative forces"),
        Role::Lagrangian => (Dimension::ENERGY, "a Lagrangian (an energy)"),
        Role::Dissipation => (Dimension::POWER, "a dissipation function (a power)"),
        Role::Rayleigh => (
            Dimension::POWER,
            "Rayleigh's dissipation function (a power)",
        ),
    };
    Want {
        form: DimForm::known(dimension),
        why: Why::Role {
            name: name.to_string(),
            role: what,
        },
    }
}

fn energy() -> DimForm {
    DimForm::known(Dimension::ENERGY)
}

/// `force q: Q`: Q·δq is work.
pub(super) fn force(w: &mut Walker, coordinate: &Ident, value: &Expr) -> Checked<()> {
    let q = match w.names.get(coordinate.name.as_str()) {
        Some(NameDim::Fixed(f)) => f.clone(),
        _ => return Ok(()),
    };
    let want = Want {
        form: energy().div(&q),
        why: Why::Force {
            coordinate: coordinate.name.clone(),
        },
    };
    w.value(value, Some(&want))?;
    Ok(())
}

/// `load F at P`: F·P is work, component by component.
pub(super) fn load(w: &mut Walker, force: &Expr, point: &Expr) -> Checked<()> {
    let f = w.value(force, None)?;
    let p = w.value(point, None)?;
    for (fk, pk) in f.components().iter().zip(p.components()) {
        let (Some(fk), Some(pk)) = (fk, pk) else {
            continue;
        };
        if w.vars.unify(&fk.mul(pk), &energy(), force.span) {
            continue;
        }
        return Err(misapplied(w, (force, fk), (point, pk), Kind::Load));
    }
    Ok(())
}

/// `torque M on phi`: M·phi is work.
pub(super) fn torque(w: &mut Walker, moment: &Expr, angle: &Expr) -> Checked<()> {
    let m = w.value(moment, None)?;
    let a = w.value(angle, None)?;
    if let (DimValue::Scalar(Some(m)), DimValue::Scalar(Some(a))) = (&m, &a) {
        if !w.vars.unify(&m.mul(a), &energy(), moment.span) {
            return Err(misapplied(w, (moment, m), (angle, a), Kind::Torque));
        }
    }
    Ok(())
}

#[derive(Clone, Copy, PartialEq)]
enum Kind {
    Load,
    Torque,
}

/// The error of a load or torque whose work is not an energy: at the
/// point (or angle) when the force (or moment) is what it should be, else
/// at the force.
fn misapplied(
    w: &Walker,
    agent: (&Expr, &DimForm),
    place: (&Expr, &DimForm),
    kind: Kind,
) -> Diagnostic {
    let (agent_dim, place_dim, agent_word, place_word) = match kind {
        Kind::Load => (
            Dimension::FORCE,
            Dimension::LENGTH,
            "a force",
            "its point of application: a position (a length)",
        ),
        Kind::Torque => (
            Dimension::ENERGY,
            Dimension::ONE,
            "a torque (an energy per radian)",
            "the angle it turns: dimensionless",
        ),
    };
    let agent_needed = DimForm::known(agent_dim);
    let place_needed = DimForm::known(place_dim);
    let a = w.vars.normalize(agent.1);
    let p = w.vars.normalize(place.1);
    if a == agent_needed {
        let msg = format!(
            "this is {}, but {agent_word} acts over {place_word}",
            w.vars.phrase(&p)
        );
        let d = w.error(place.0, msg, &p, &place_needed);
        return match (kind, p.as_known()) {
            (Kind::Load, Some(d1)) if d1.is_one() => d.with_hint(
                "a force on an angle is a torque: write `torque M on theta` with the moment M",
            ),
            _ => d,
        };
    }
    let work = a.mul(&p);
    let msg = if p == place_needed {
        format!(
            "this is {}, but a {} acting on {} must be {agent_word}",
            w.vars.phrase(&a),
            if kind == Kind::Load { "load" } else { "torque" },
            if kind == Kind::Load {
                "a position (a length)"
            } else {
                "an angle"
            },
        )
    } else {
        format!(
            "this {} does work of dimension {}, not an energy",
            if kind == Kind::Load { "load" } else { "torque" },
            w.vars.unicode(&work)
        )
    };
    w.error(agent.0, msg, &a, &agent_needed)
}

/// A `solve` block: the two sides of each equation alike. Equations with
/// fewer unknowns go first: they decide the unknowns' dimensions, so a
/// wrong term elsewhere is reported where it is written.
/// `constraint NAME: lhs = rhs`: both sides of one dimension.
pub(super) fn constraint(w: &mut Walker, eq: &Equation) -> Checked<()> {
    match w.value(&eq.lhs, None)? {
        DimValue::Scalar(Some(f)) => {
            let want = Want {
                form: f,
                why: Why::OtherSide,
            };
            w.value(&eq.rhs, Some(&want))?;
        }
        _ => {
            w.value(&eq.rhs, None)?;
        }
    }
    Ok(())
}

pub(super) fn solve_block(w: &mut Walker, block: &SolveBlock) -> Checked<()> {
    let mut order: Vec<(usize, &Equation)> = block
        .equations
        .iter()
        .map(|eq| (unknowns_in(block, eq), eq))
        .collect();
    order.sort_by_key(|(n, _)| *n);
    for (_, eq) in order {
        let l = w.value(&eq.lhs, None)?;
        match &l {
            DimValue::Scalar(Some(f)) => {
                let want = Want {
                    form: f.clone(),
                    why: Why::OtherSide,
                };
                w.value(&eq.rhs, Some(&want))?;
            }
            DimValue::Scalar(None) => {
                w.value(&eq.rhs, None)?;
            }
            DimValue::Vector(lc) => {
                let r = w.value(&eq.rhs, None)?;
                for (k, (a, b)) in lc.iter().zip(r.components()).enumerate() {
                    let (Some(a), Some(b)) = (a, b) else { continue };
                    if !w.vars.unify(b, a, eq.rhs.span) {
                        // at the component itself when it is written out
                        let at = match &eq.rhs.kind {
                            ExprKind::Vector(cs) if cs.len() > k => &cs[k],
                            _ => &eq.rhs,
                        };
                        let msg = format!(
                            "component {} of this side is {}; of the other side, {}",
                            k + 1,
                            w.vars.phrase(b),
                            w.vars.phrase(a)
                        );
                        return Err(w.error(at, msg, b, a));
                    }
                }
            }
        }
    }
    Ok(())
}

/// How many of the block's unknowns an equation names.
fn unknowns_in(block: &SolveBlock, eq: &Equation) -> usize {
    let mut seen: Vec<&str> = Vec::new();
    super::walk::for_each_name(&[&eq.lhs, &eq.rhs], |n| {
        if block.unknowns.iter().any(|u| u.name == n) && !seen.contains(&n) {
            seen.push(n);
        }
    });
    seen.len()
}

/// `body`/`particle`: a mass, a moment of inertia per entry, a length
/// per component of the position and of an inertia's `about` point, a
/// pure number for a plane angle.
pub(super) fn body(w: &mut Walker, b: &BodyStmt) -> Checked<()> {
    let name = &b.name.name;
    for p in &b.properties {
        let (dimension, what) = match p.key {
            PropertyKey::Mass => (Dimension::MASS, format!("the mass of `{name}`")),
            PropertyKey::Inertia => (
                Dimension::MOMENT_OF_INERTIA,
                format!("the inertia of `{name}` (mass·length²)"),
            ),
            PropertyKey::At => (Dimension::LENGTH, format!("the position of `{name}`")),
            PropertyKey::Angle => (Dimension::ONE, format!("the angle of `{name}`")),
            PropertyKey::Frame => {
                w.value(&p.value, None)?;
                continue;
            }
        };
        let want = Want {
            form: DimForm::known(dimension),
            why: Why::Property { what },
        };
        // an inertia matrix `[[…], …]`: each entry
        match &p.value.kind {
            ExprKind::Vector(rows)
                if rows.iter().any(|r| matches!(r.kind, ExprKind::Vector(_))) =>
            {
                for r in rows {
                    match &r.kind {
                        ExprKind::Vector(items) => {
                            for it in items {
                                w.value(it, Some(&want))?;
                            }
                        }
                        _ => {
                            w.value(r, Some(&want))?;
                        }
                    }
                }
            }
            _ => {
                w.value(&p.value, Some(&want))?;
            }
        }
        if let Some(about) = &p.about {
            let want = Want {
                form: DimForm::known(Dimension::LENGTH),
                why: Why::Property {
                    what: format!("the point the inertia of `{name}` is taken about"),
                },
            };
            w.value(&about.point, Some(&want))?;
        }
    }
    Ok(())
}

/// `gravity G`: an acceleration per component.
pub(super) fn gravity(w: &mut Walker, value: &Expr) -> Checked<()> {
    let want = Want {
        form: DimForm::known(Dimension::ACCELERATION),
        why: Why::Property {
            what: "gravity is an acceleration".to_string(),
        },
    };
    w.value(value, Some(&want))?;
    Ok(())
}

/// `assume a > b`: both sides alike (`e real` asks nothing).
pub(super) fn assumption(w: &mut Walker, facts: &[crate::parse::ast::Fact]) -> Checked<()> {
    for f in facts {
        let crate::parse::ast::Fact::Order { greater, less, .. } = f else {
            continue;
        };
        match w.value(greater, None)? {
            DimValue::Scalar(Some(g)) => {
                let want = Want {
                    form: g,
                    why: Why::Compared,
                };
                w.value(less, Some(&want))?;
            }
            _ => {
                w.value(less, None)?;
            }
        }
    }
    Ok(())
}
