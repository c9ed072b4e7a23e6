//! Differentiation: partial derivatives with respect to an atom, and the
//! total time derivative d/dt = ∂/∂t + Σ q̇·∂/∂q + Σ q̈·∂/∂q̇ + ….
//!
//! A polynomial's derivative is Σ over its atoms a of (∂p/∂a)·(da/dx): the
//! first factor is plain polynomial differentiation, the second the atom's
//! own derivative (chain rule through `sin(u)`, `√P`, …), memoized
//! process-wide. Both derivations respect the relations of the canonical
//! form (d(sin² + cos²) = 0, d(√P²) = dP), so reduced inputs give correct
//! results after reduction.

use super::atom::{self, Atom};
use super::Expr;
use crate::num::Q;
use crate::poly::{Poly, Var};
use rustc_hash::FxHashMap;
use std::sync::{OnceLock, RwLock};

/// With respect to what.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Wrt {
    /// ∂/∂v for an atom v (a coordinate, a velocity, a parameter, t).
    Var(Var),
    /// The total time derivative.
    Time,
}

type Cache = RwLock<FxHashMap<(Var, Wrt), Option<Expr>>>;

fn cache() -> &'static Cache {
    static C: OnceLock<Cache> = OnceLock::new();
    C.get_or_init(|| RwLock::new(FxHashMap::default()))
}

/// The derivative of atom `a`, or `None` when it is zero.
pub fn atom_derivative(a: Var, wrt: Wrt) -> Option<Expr> {
    if let Wrt::Var(v) = wrt {
        if a == v {
            return Some(Expr::one());
        }
    }
    if let Ok(c) = cache().read() {
        if let Some(d) = c.get(&(a, wrt)) {
            return d.clone();
        }
    }
    let d = compute_atom_derivative(a, wrt);
    if let Ok(mut c) = cache().write() {
        c.insert((a, wrt), d.clone());
    }
    d
}

fn compute_atom_derivative(a: Var, wrt: Wrt) -> Option<Expr> {
    let at = atom::atom(a);
    let inner_d = |u: &Expr| -> Option<Expr> {
        let d = u.derivative(wrt);
        (!d.is_zero()).then_some(d)
    };
    match (&at, wrt) {
        (
            Atom::Param(_)
            | Atom::Unknown(_)
            | Atom::Named(_)
            | Atom::Pi
            | Atom::Root(_)
            | Atom::Shown(..)
            | Atom::Group(_),
            _,
        ) => None,
        (Atom::Coord(..) | Atom::Given(..) | Atom::Time, Wrt::Var(_)) => None,
        (Atom::Coord(name, k), Wrt::Time) => Some(Expr::var(atom::coord(name, k + 1))),
        (Atom::Given(name, k), Wrt::Time) => Some(Expr::var(atom::given(name, k + 1))),
        (Atom::Time, Wrt::Time) => Some(Expr::one()),
        (Atom::Sin(u), _) => {
            let du = inner_d(u)?;
            let (_, c) = atom::intern_trig(u);
            Some(Expr::var(c).mul(&du))
        }
        (Atom::Cos(u), _) => {
            let du = inner_d(u)?;
            let (s, _) = atom::intern_trig(u);
            Some(Expr::var(s).mul(&du).neg())
        }
        (Atom::SqrtOf(u), _) => {
            // d√u = du / (2√u)
            let du = inner_d(u)?;
            let two_r = Expr::var(a).scale(&Q::from_i64(2));
            du.div(&two_r).ok()
        }
        (Atom::Exp(u), _) => {
            let du = inner_d(u)?;
            Some(Expr::var(a).mul(&du))
        }
        (Atom::Ln(u), _) => {
            let du = inner_d(u)?;
            du.div(u).ok()
        }
        (Atom::Atan(u), _) => {
            let du = inner_d(u)?;
            du.div(&Expr::one().add(&u.mul(u))).ok()
        }
        (Atom::Asin(u) | Atom::Acos(u), _) => {
            // d asin u = du/√(1 − u²), d acos u = −du/√(1 − u²)
            let du = inner_d(u)?;
            let r = super::func::sqrt(&Expr::one().sub(&u.mul(u))).ok()?;
            let d = du.div(&r).ok()?;
            Some(if matches!(at, Atom::Acos(_)) {
                d.neg()
            } else {
                d
            })
        }
    }
}

/// Whether atom `a` depends on `v` through its argument.
pub fn atom_depends_on(a: Var, v: Var) -> bool {
    atom::contains(a, v)
}

/// Whether an expression with atoms `vars` depends on `v`, directly or
/// through an atom's argument.
pub fn vars_depend_on(vars: &[Var], v: Var) -> bool {
    vars.iter().any(|&a| atom_depends_on(a, v))
}

/// Whether atom `a` depends on any key of `map`.
pub fn atom_depends_on_any(a: Var, map: &FxHashMap<Var, Expr>) -> bool {
    map.keys().any(|&v| atom_depends_on(a, v))
}

/// d p / d wrt as (polynomial part, non-polynomial rest).
fn poly_derivative(p: &Poly, wrt: Wrt) -> Expr {
    let mut poly_part = Poly::zero();
    let mut rest = Expr::zero();
    for a in p.vars() {
        let Some(da) = atom_derivative(a, wrt) else {
            continue;
        };
        let dp = p.diff(a);
        if dp.is_zero() {
            continue;
        }
        if da.is_poly() {
            poly_part = &poly_part + &(&dp * da.num());
        } else {
            rest = rest.add(&Expr::from_poly(dp).mul(&da));
        }
    }
    Expr::from_poly(poly_part).add(&rest)
}

impl Expr {
    /// The derivative with respect to `wrt`.
    pub fn derivative(&self, wrt: Wrt) -> Expr {
        let dn = poly_derivative(self.num(), wrt);
        if self.is_poly() {
            return dn;
        }
        let dd = poly_derivative(self.den(), wrt);
        if dd.is_zero() {
            // (n/d)' = n'/d
            return dn
                .div(&Expr::from_poly(self.den().clone()))
                .unwrap_or_else(|_| Expr::zero());
        }
        // (n/d)' = (n'·d − n·d') / d²
        let n = Expr::from_poly(self.num().clone());
        let d = Expr::from_poly(self.den().clone());
        let top = dn.mul(&d).sub(&n.mul(&dd));
        top.div(&d.mul(&d)).unwrap_or_else(|_| Expr::zero())
    }

    /// ∂/∂v.
    pub fn diff(&self, v: Var) -> Expr {
        self.derivative(Wrt::Var(v))
    }

    /// d/dt, the total time derivative.
    pub fn dt(&self) -> Expr {
        self.derivative(Wrt::Time)
    }

    /// Whether the expression changes with time (mentions a coordinate or t).
    pub fn is_time_dependent(&self) -> bool {
        self.vars().into_iter().any(atom::is_moving)
    }

    /// The highest time derivative of a coordinate in the expression, with
    /// its coordinate: `(x, 2)` for `m·ẍ + sin(ẋ)`; `None` when no
    /// coordinate appears. Function arguments count (kept per atom, so
    /// shared arguments are not walked again).
    pub fn highest_time_derivative(&self) -> Option<(std::sync::Arc<str>, u32)> {
        self.vars()
            .into_iter()
            .filter_map(atom::highest_time_derivative)
            .max_by_key(|(_, k)| *k)
    }
}
