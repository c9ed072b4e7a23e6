//! What a scene assumes beyond "every parameter is positive" (`assume e
//! real, R > r`), and how a sign is decided under it.
//!
//! An order fact d > 0 that is linear in a parameter p (d = c·p + rest, c
//! a nonzero number) is used by eliminating p: p = (δ − rest)/c with a new
//! positive symbol δ standing for d. Every point where the parameters are
//! positive and the facts hold maps to a point where δ and the remaining
//! parameters are positive, so a sign decided for all positive values
//! after the elimination is decided for the scene (the converse need not
//! hold: such a decision may be left undecided, never wrong). A parameter
//! of either sign is decided case by case: positive, negative (p → −p)
//! and zero must agree.
//!
//! The assumptions in force are a per-thread context, read by
//! [`crate::algebra::sign::sign_exact`]. The context that runs a command
//! sets them ([`assuming`], from `app::Context` or `Scene::assumptions_in_force`);
//! the engine's functions that decide signs for a scene check them
//! ([`in_force`]); a reader that is still building a scene's assumptions
//! passes them explicitly ([`sign_under`]).

use super::sign::Sign;
use crate::expr::atom::{self, Atom};
use crate::expr::Expr;
use crate::num::Q;
use crate::poly::{Poly, Var};
use rustc_hash::FxHashMap;
use std::cell::RefCell;
use std::rc::Rc;

use crate::limits::MAX_REAL_CASES;

/// What a scene assumes (see the module docs).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Assumptions {
    /// The parameters of either sign (`assume e real`).
    pub real: Vec<Var>,
    /// The expressions assumed positive (`assume R > r`: R − r).
    pub positive: Vec<Expr>,
    /// The eliminations of the order facts, in order.
    eliminations: Vec<(Var, Expr)>,
}

impl Assumptions {
    /// Assumptions of the parameters `real` of either sign and the facts
    /// `positive` (each > 0).
    pub fn new(real: Vec<Var>, positive: Vec<Expr>) -> Assumptions {
        let mut eliminations: Vec<(Var, Expr)> = Vec::new();
        for (i, d) in positive.iter().enumerate() {
            let mut d = d.clone();
            for (v, by) in &eliminations {
                match d.subs(*v, by) {
                    Ok(x) => d = x,
                    Err(_) => continue,
                }
            }
            if let Some(e) = elimination(&d, i, &real) {
                eliminations.push(e);
            }
        }
        Assumptions {
            real,
            positive,
            eliminations,
        }
    }

    /// Whether nothing is assumed beyond positive parameters.
    pub fn is_empty(&self) -> bool {
        self.real.is_empty() && self.positive.is_empty()
    }
}

/// p = (δ − rest)/c for a parameter p in which `d` is linear with a
/// numeric coefficient c (`i` names δ). Preferred: c > 0 with every other
/// term of d negative, where p = (δ + |rest|)/c is positive by itself and
/// nothing is lost; then c > 0; then any.
fn elimination(d: &Expr, i: usize, real: &[Var]) -> Option<(Var, Expr)> {
    if !d.den().vars().is_empty() {
        return None;
    }
    let num = d.num();
    let mut best: Option<(u8, Var, Q, Poly)> = None;
    for p in num.vars() {
        // a parameter of the scene, not the δ of an earlier fact (whose
        // name is not an identifier): eliminating a δ would lose that fact
        let Atom::Param(name) = atom::atom(p) else {
            continue;
        };
        if real.contains(&p) || name.contains(">0#") {
            continue;
        }
        let cs = num.coeffs_in(p);
        if cs.len() != 2 {
            continue;
        }
        let Some(c) = Expr::from_poly(cs[1].clone()).as_rational() else {
            continue;
        };
        let rank = if !c.is_positive() {
            2
        } else if cs[0].terms().iter().all(|(_, k)| k.is_negative()) {
            0
        } else {
            1
        };
        if best.as_ref().is_none_or(|b| rank < b.0) {
            best = Some((rank, p, c, cs[0].clone()));
        }
    }
    let (_, p, c, rest) = best?;
    // δ: a symbol no scene can name (its name is not an identifier)
    let delta = Expr::param(&format!("({})>0#{i}", d.to_input()));
    let by = delta.sub(&Expr::from_poly(rest)).scale(&c.recip()?);
    Some((p, by))
}

thread_local! {
    static CURRENT: RefCell<Rc<Assumptions>> = RefCell::new(Rc::new(Assumptions::default()));
}

/// Run `f` with `a` in force (restored afterwards, also on unwinding).
pub fn assuming<R>(a: &Assumptions, f: impl FnOnce() -> R) -> R {
    struct Restore(Option<Rc<Assumptions>>);
    impl Drop for Restore {
        fn drop(&mut self) {
            if let Some(prev) = self.0.take() {
                CURRENT.with(|c| *c.borrow_mut() = prev);
            }
        }
    }
    let prev = CURRENT.with(|c| std::mem::replace(&mut *c.borrow_mut(), Rc::new(a.clone())));
    let _restore = Restore(Some(prev));
    f()
}

/// Whether `a` are the assumptions in force on this thread.
pub fn in_force(a: &Assumptions) -> bool {
    CURRENT.with(|c| *c.borrow().as_ref() == *a)
}

/// The sign of `e` (as [`super::sign::sign_exact`] decides it) under `a`,
/// whatever is in force: for a reader building a scene's assumptions,
/// which no context above it has.
pub fn sign_under(a: &Assumptions, e: &Expr) -> Option<Sign> {
    assuming(a, || super::sign::sign_exact(e))
}

/// The sign of `e` under the assumptions in force, `plain` deciding for
/// positive parameters.
pub(super) fn decide(e: &Expr, plain: impl Fn(&Expr) -> Option<Sign>) -> Option<Sign> {
    let a = CURRENT.with(|c| c.borrow().clone());
    if a.is_empty() {
        return plain(e);
    }
    // a fact itself times a number: also one no elimination reaches
    // (`assume cos(lat) > 0`, whose atom is not a parameter)
    for f in &a.positive {
        if f.num().len() != e.num().len() || f.den().len() != e.den().len() {
            continue;
        }
        if let Some(q) = e.div(f).ok().and_then(|r| r.as_rational()) {
            if q.is_positive() {
                return Some(Sign::Positive);
            }
            if q.is_negative() {
                return Some(Sign::Negative);
            }
        }
    }
    let mut e = e.clone();
    for (v, by) in &a.eliminations {
        if e.depends_on(*v) {
            e = e.subs(*v, by).ok()?;
        }
    }
    let present: Vec<Var> = a
        .real
        .iter()
        .copied()
        .filter(|&v| e.depends_on(v))
        .collect();
    if present.is_empty() {
        return plain(&e);
    }
    if present.len() > MAX_REAL_CASES {
        return None;
    }
    let mut sign = None;
    let cases = 3usize.pow(present.len() as u32);
    for case in 0..cases {
        let mut map: FxHashMap<Var, Expr> = FxHashMap::default();
        let mut k = case;
        for &v in &present {
            let value = match k % 3 {
                0 => Expr::var(v),
                1 => Expr::var(v).neg(),
                _ => Expr::zero(),
            };
            k /= 3;
            map.insert(v, value);
        }
        let s = plain(&e.subs_many(&map).ok()?)?;
        match sign {
            None => sign = Some(s),
            Some(t) if t == s => {}
            Some(_) => return None,
        }
    }
    sign
}
