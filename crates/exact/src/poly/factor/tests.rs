//! Tests of the factorization: known answers, the square-free
//! decomposition, and the two multivariate methods (Kronecker, evaluation
//! and lifting) against each other.

use super::*;
use crate::poly::Mono;

fn x() -> Poly {
    Poly::var(0)
}

fn c(n: i64) -> Poly {
    Poly::constant(Q::from_i64(n))
}

#[test]
fn univariate_known_answers() {
    let f = &x().pow(2) - &c(1);
    let r = factor(&f);
    assert_eq!(r.factors.len(), 2);
    assert_eq!(r.factors[0].0, &x() - &c(1));
    assert_eq!(r.factors[1].0, &x() + &c(1));
    assert_eq!(r.expand(), f);
    // x^4 + 1 and x^4 - 10x^2 + 1 are irreducible over Q
    for f in [
        &x().pow(4) + &c(1),
        &(&x().pow(4) - &(&c(10) * &x().pow(2))) + &c(1),
    ] {
        let r = factor(&f);
        assert_eq!(r.factors, vec![(f.clone(), 1)]);
        assert_eq!(r.unit, Q::one());
    }
}

#[test]
fn square_free_of_powers() {
    let a = &x() + &c(1);
    let b = &x() - &c(2);
    let f = &(&a.pow(3) * &b.pow(2)) * &c(-3);
    let sf = square_free(&f);
    assert_eq!(sf, vec![(b, 2), (a, 3)]);
}

fn parse2(terms: &[(i64, u32, u32)]) -> Poly {
    Poly::from_terms(
        terms
            .iter()
            .map(|&(c, i, j)| (Mono::from_pairs([(0, i), (1, j)]), Q::from_i64(c)))
            .collect(),
    )
}

#[test]
fn kronecker_and_hensel_agree() {
    // x^4 - y^4 (after the linear factors: x^2 + y^2 irreducible) and
    // (x^2 + xy + y^2)(x^2 - xy + y^2) = x^4 + x^2 y^2 + y^4;
    // x^2 y^2 - 1 needs a nonzero evaluation point (lc_x = y^2)
    let cases = [
        (parse2(&[(1, 4, 0), (-1, 0, 4)]), 3),
        (parse2(&[(1, 4, 0), (1, 2, 2), (1, 0, 4)]), 2),
        (parse2(&[(1, 2, 2), (-1, 0, 0)]), 2),
        (parse2(&[(1, 2, 0), (1, 0, 2)]), 1),
    ];
    for (f, n) in cases {
        let vars = f.vars();
        let mut k = kronecker_factor(&f, &vars, &Trials::budgeted());
        let mut h = hensel_factor(&f, &vars, &Trials::budgeted()).expect("a good point");
        k.sort_by(canonical_cmp);
        h.sort_by(canonical_cmp);
        assert_eq!(k.len(), n, "{f}");
        assert_eq!(k, h, "{f}");
        assert_eq!(k.iter().cloned().product::<Poly>(), f);
    }
}

/// The Swinnerton-Dyer polynomial of √2, √3, √5, √7 (degree 16,
/// irreducible over ℚ, at least 8 factors modulo every prime): the
/// product of the 16 x ± √2 ± √3 ± √5 ± √7 (coefficients from SymPy).
fn swinnerton_dyer_4() -> Poly {
    let coeffs: [i64; 9] = [
        1, -136, 6476, -141912, 1513334, -7453176, 13950764, -5596840, 46225,
    ];
    coeffs
        .iter()
        .enumerate()
        .map(|(i, &k)| &c(k) * &x().pow(16 - 2 * i as u32))
        .fold(Poly::zero(), |a, b| &a + &b)
}

/// Within a fixed number of subsets the factorization is given up (`None`);
/// under a work budget it unwinds with the subsets' measure; with room,
/// the polynomial is found irreducible.
#[test]
fn recombination_is_bounded_by_its_subsets() {
    let f = swinnerton_dyer_4();
    assert_eq!(factor_within(&f, 3), None);
    let r = factor_within(&f, 1_000_000).expect("room enough");
    assert_eq!(r.factors, vec![(f.clone(), 1)]);
    let e = crate::budget::within(16, || factor(&f)).expect_err("2 subsets allowed");
    assert_eq!(e.measure, crate::budget::Measure::Subsets);
    assert_eq!(
        e.message(),
        "factoring too costly: 3 subsets of modular factors tried (the limit is 16 terms, and 2 subsets)"
    );
}
