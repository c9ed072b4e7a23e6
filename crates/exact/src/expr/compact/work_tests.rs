//! The compact search's work allowance ([`super::work_allowance`]),
//! counted in the terms of the rewritings built ([`super::search_work`]),
//! not timed.
// A test module: compiled only under #[cfg(test)] (its parent's `mod` line).

use super::*;
use crate::expr::{func, Expr};

/// (x + y + z)·sin¹⁰(a)·sin¹⁰(b)·sin¹⁰(c): each rewriting within
/// [`MAX_TRIG_EXPANSION`] (the Fourier form 3·11³ = 3,993 terms at most),
/// all of them together past the allowance of four terms.
fn dear_product() -> Expr {
    let sum = Expr::param("x")
        .add(&Expr::param("y"))
        .add(&Expr::param("z"));
    ["wa", "wb", "wc"].iter().fold(sum, |e, name| {
        let s = func::sin(&Expr::coord(name, 0));
        e.mul(&s.powi(10).unwrap())
    })
}

fn plan_of(e: &Expr) -> Plan {
    let angles = fourier::angles(&[e.num(), e.den()]);
    Plan::new(e.num(), e.den(), &angles)
}

#[test]
fn a_search_past_its_allowance_is_not_made() {
    let e = dear_product();
    let terms = e.num().len() + e.den().len();
    assert_eq!(terms, 4);
    let plan = plan_of(&e);
    // only the allowance stops it: every rewriting is within its own bound
    assert!(plan.fourier && plan.masks.len() == 7, "{:?}", plan.masks);
    // 4 as it is; 7 reductions of 3·(6, 6, 6, 36, 36, 36, 216) terms, and
    // the denominator 1 in each; the Fourier form 3·11³ and 1
    assert_eq!(plan.work, 4 + 3 * 342 + 7 + 3_993 + 1);
    assert!(plan.work > work_allowance(terms));
    let before = search_work();
    let (n, d) = display_parts(e.num(), e.den());
    assert_eq!(search_work(), before, "the search was made");
    // the canonical form, as it is
    assert_eq!((&n, &d), (e.num(), e.den()));
    assert_eq!(
        print::render_parts(&n, &d, Style::Unicode),
        "(x + y + z)·sin¹⁰(wa)·sin¹⁰(wb)·sin¹⁰(wc)"
    );
}

#[test]
fn a_search_within_its_allowance_is_made_and_counted() {
    // the same product in two angles: 3·11² Fourier terms and 3 reductions
    let sum = Expr::param("x").add(&Expr::param("y"));
    let e = ["wd", "we"].iter().fold(sum, |e, name| {
        let s = func::sin(&Expr::coord(name, 0));
        e.mul(&s.powi(10).unwrap())
    });
    let terms = e.num().len() + e.den().len();
    let plan = plan_of(&e);
    assert!(plan.work <= work_allowance(terms), "{}", plan.work);
    let before = search_work();
    display_parts(e.num(), e.den());
    // the product's search (and the searches of the sums it prints)
    assert!(search_work() - before >= plan.work as u64);
}

#[test]
fn the_allowance_grows_with_the_expression() {
    assert_eq!(work_allowance(0), COMPACT_WORK_BASE);
    assert_eq!(
        work_allowance(100) - work_allowance(99),
        COMPACT_WORK_PER_TERM
    );
    // a whole search of the largest expression searched, past its base
    assert!(work_allowance(MAX_COMPACT_TERMS) > COMPACT_WORK_BASE);
}
