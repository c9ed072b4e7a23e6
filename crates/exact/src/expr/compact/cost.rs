//! The operations a display polynomial prints with, estimated from its
//! structure (what [`super::count_ops`] would count on the printed text,
//! up to signs): the search compares dozens of candidates and printing
//! each would cost more than the search itself.

use super::super::atom::{self, Atom};
use super::super::print;
use crate::poly::{Mono, Poly, Var};
use rustc_hash::FxHashMap;
use std::cell::RefCell;

thread_local! {
    /// Operations of an atom written out (0 for a symbol), per atom, in the
    /// print order in force (the text of a sum depends on it).
    static ATOM_OPS: RefCell<FxHashMap<Var, usize>> = RefCell::new(FxHashMap::default());
}

/// Empties [`ATOM_OPS`] when the print order changes.
pub(super) fn forget() {
    ATOM_OPS.with(|c| c.borrow_mut().clear());
}

/// Operations of num/den printed as a quotient (or a polynomial).
pub(super) fn quotient(num: &Poly, den: &Poly) -> usize {
    if den.is_constant() {
        return factored_sum(num) + usize::from(!den.is_one());
    }
    factored_sum(num) + factored_sum(den) + 1
}

/// A polynomial with its rational content and common power product
/// pulled out, as the printers write a side of a quotient.
pub(super) fn factored_sum(p: &Poly) -> usize {
    if p.len() < 2 {
        return p
            .terms()
            .first()
            .map_or(0, |(m, c)| term(m, c.is_one() || (-c.clone()).is_one()));
    }
    let c = p.content();
    let m = p.mono_content();
    let prim_terms: usize = p
        .terms()
        .iter()
        .map(|(t, q)| {
            let t = t.div(&m).unwrap_or_else(|| t.clone());
            let unit = (q / &c).abs().is_one();
            term(&t, unit) + 1
        })
        .sum::<usize>()
        - 1;
    let head = usize::from(!c.abs().is_one()) + mono(&m);
    prim_terms + head + usize::from(head > 0 || !m.is_one())
}

/// One term: its coefficient (a multiplication, or none when ±1) and its
/// power product.
fn term(m: &Mono, unit: bool) -> usize {
    mono(m) + usize::from(!unit && !m.is_one())
}

/// A power product: a multiplication between factors, a power for each
/// exponent above 1, and what each atom takes written out.
fn mono(m: &Mono) -> usize {
    let pairs = m.pairs();
    if pairs.is_empty() {
        return 0;
    }
    pairs.len() - 1
        + pairs
            .iter()
            .map(|&(v, e)| usize::from(e > 1) + atom_ops(v))
            .sum::<usize>()
}

fn atom_ops(v: Var) -> usize {
    if let Some(n) = ATOM_OPS.with(|c| c.borrow().get(&v).copied()) {
        return n;
    }
    let n = match atom::atom(v) {
        Atom::Param(_)
        | Atom::Unknown(_)
        | Atom::Coord(..)
        | Atom::Given(..)
        | Atom::Time
        | Atom::Pi => 0,
        Atom::Group(p) => factored_sum(&p),
        _ => super::count_ops(&print::atom_input_text(v)),
    };
    ATOM_OPS.with(|c| c.borrow_mut().insert(v, n));
    n
}
