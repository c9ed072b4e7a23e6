//! Given functions of time in a simulation: each `functions s` of the
//! scene needs its definition (`--function "s=1/10*sin(2*t)"`, an
//! expression in t and the parameters); the equations are simulated with
//! s, ṡ, s̈, … replaced by the definition and its exact derivatives.

use crate::diag::Diagnostic;
use crate::expr::atom::{self, Atom};
use crate::expr::Expr;
use crate::mechanics::Lagrange;
use crate::poly::Var;
use crate::scene::Scene;
use rustc_hash::FxHashMap;

const HINT: &str = "define each given function of the scene once, in t and the parameters: --function \"s=1/10*sin(2*t)\"";

/// The kind of every error of the definitions given with `--function`.
fn function_option() -> crate::diag::ErrorKind {
    crate::diag::ErrorKind::bad_option("--function")
}

/// The definitions `defs` (`s=EXPR` each) of the scene's given functions,
/// by name: an error names a function without a definition (needed
/// `purpose`, e.g. "to simulate"), a definition of no given function, or
/// one that is not a function of t and the parameters.
pub fn definitions<'a>(
    scene: &Scene,
    defs: &'a [String],
    purpose: &str,
) -> Result<FxHashMap<&'a str, Expr>, Diagnostic> {
    let mut values: FxHashMap<&str, Expr> = FxHashMap::default();
    for d in defs {
        let Some((name, text)) = d.split_once('=') else {
            return Err(
                Diagnostic::global(format!("--function expects NAME=EXPR, found `{d}`"))
                    .with_hint(HINT)
                    .with_kind(function_option()),
            );
        };
        let name = name.trim();
        if !scene.functions.iter().any(|f| f.name == name) {
            let list: Vec<&str> = scene.functions.iter().map(|f| f.name.as_str()).collect();
            let have = if list.is_empty() {
                "the scene declares none".to_string()
            } else {
                format!("the scene's are {}", list.join(", "))
            };
            return Err(Diagnostic::global(format!(
                "--function defines `{name}`, which is not a given function of the scene ({have})"
            ))
            .with_hint("declare it with `functions NAME`, or remove the option")
            .with_kind(function_option()));
        }
        let e = scene.expr(text).map_err(|e| {
            Diagnostic::global(format!("--function {name}: {}", e.message))
                .with_hint(HINT)
                .with_kind(function_option())
        })?;
        if let Some(bad) = e.vars().into_iter().find(|&v| !of_time(v)) {
            return Err(Diagnostic::global(format!(
                "--function {name}: the definition uses {}, but a given function depends on t and the parameters only",
                crate::expr::print::input(&Expr::var(bad))
            ))
            .with_hint(HINT).with_kind(function_option()));
        }
        if values.insert(name, e).is_some() {
            return Err(
                Diagnostic::global(format!("--function {name} is given twice"))
                    .with_hint(HINT)
                    .with_kind(function_option()),
            );
        }
    }
    if let Some(f) = scene
        .functions
        .iter()
        .find(|f| !values.contains_key(f.name.as_str()))
    {
        return Err(Diagnostic::global(format!(
            "the given function `{}` needs a definition {purpose}",
            f.name
        ))
        .with_hint(HINT)
        .with_kind(function_option()));
    }
    Ok(values)
}

/// `lag` with the scene's given functions replaced by their definitions
/// `defs` ([`definitions`]).
pub fn defined(scene: &Scene, lag: Lagrange, defs: &[String]) -> Result<Lagrange, Diagnostic> {
    let values = definitions(scene, defs, "to simulate")?;
    if values.is_empty() {
        return Ok(lag);
    }
    let map = derivatives(&lag, &values);
    let subs = |e: &Expr| {
        e.subs_many(&map)
            .map_err(|m| Diagnostic::global(m.message).with_kind(crate::diag::ErrorKind::Undefined))
    };
    let mut out = lag.clone();
    for row in &mut out.mass_matrix {
        for m in row.iter_mut() {
            *m = subs(m)?;
        }
    }
    for f in &mut out.forcing {
        *f = subs(f)?;
    }
    for eq in &mut out.equations {
        eq.lhs = subs(&eq.lhs)?;
        eq.rhs = subs(&eq.rhs)?;
    }
    out.kinetic = subs(&out.kinetic)?;
    for e in out.constraints.expressions_mut() {
        *e = subs(e)?;
    }
    Ok(out)
}

/// Whether an atom is a constant or t, or a function of them.
fn of_time(v: Var) -> bool {
    std::iter::once(v)
        .chain(atom::inner_atoms(v).iter().copied())
        .all(|w| {
            !matches!(
                atom::atom(w),
                Atom::Coord(..) | Atom::Given(..) | Atom::Unknown(_)
            )
        })
}

/// Every derivative of a given function the equations use, mapped to the
/// derivative of its definition.
fn derivatives(lag: &Lagrange, values: &FxHashMap<&str, Expr>) -> FxHashMap<Var, Expr> {
    let all = lag
        .mass_matrix
        .iter()
        .flatten()
        .chain(&lag.forcing)
        .chain(lag.equations.iter().flat_map(|e| [&e.lhs, &e.rhs]))
        .chain(std::iter::once(&lag.kinetic))
        .chain(lag.constraints.expressions());
    derivative_map(all, values)
}

/// Every derivative of a given function in `exprs` that `values` defines,
/// mapped to the derivative of its definition.
fn derivative_map<'a>(
    exprs: impl IntoIterator<Item = &'a Expr>,
    values: &FxHashMap<&str, Expr>,
) -> FxHashMap<Var, Expr> {
    let mut highest: FxHashMap<String, u32> = FxHashMap::default();
    for e in exprs {
        for v in e.vars() {
            for w in std::iter::once(v).chain(atom::inner_atoms(v).iter().copied()) {
                if let Atom::Given(n, k) = atom::atom(w) {
                    let h = highest.entry(n.to_string()).or_insert(0);
                    *h = (*h).max(k);
                }
            }
        }
    }
    let mut map = FxHashMap::default();
    for (name, k) in highest {
        let Some(def) = values.get(name.as_str()) else {
            continue;
        };
        let mut d = def.clone();
        for order in 0..=k {
            map.insert(atom::given(&name, order), d.clone());
            d = d.dt();
        }
    }
    map
}

/// `e` with every derivative of a given function replaced by the
/// derivative of its definition in `values` ([`definitions`]).
pub fn substitute(e: &Expr, values: &FxHashMap<&str, Expr>) -> Result<Expr, Diagnostic> {
    let map = derivative_map(std::iter::once(e), values);
    e.subs_many(&map)
        .map_err(|m| Diagnostic::global(m.message).with_kind(crate::diag::ErrorKind::Undefined))
}
