//! Tests of `Poly`'s arithmetic and structure (the gcd's are in
//! `gcd/tests.rs`), and the helpers and generators the other test modules of
//! `poly` share.

use super::*;
use proptest::prelude::*;

pub(super) fn x(v: Var) -> Poly {
    Poly::var(v)
}

pub(super) fn c(n: i64) -> Poly {
    Poly::constant(Q::from_i64(n))
}

pub(super) fn cq(n: i64, d: i64) -> Poly {
    Poly::constant(Q::new(n, d).expect("nonzero denominator"))
}

pub(super) fn m(pairs: &[(Var, u32)]) -> Mono {
    Mono::from_pairs(pairs.iter().copied())
}

pub(super) fn is_canonical(p: &Poly) -> bool {
    p.terms.windows(2).all(|w| w[0].0 > w[1].0)
        && p.terms.iter().all(|t| !t.1.is_zero())
        && p.terms
            .iter()
            .all(|t| t.0 .0.windows(2).all(|w| w[0].0 < w[1].0) && t.0 .0.iter().all(|e| e.1 > 0))
}

#[test]
fn mono_order() {
    let a = m(&[(0, 2)]);
    let b = m(&[(0, 1), (1, 5)]);
    let cc = m(&[(0, 1)]);
    let d = m(&[(1, 9)]);
    let e = Mono::one();
    assert!(a > b && b > cc && cc > d && d > e);
    let mut v = vec![e.clone(), cc.clone(), a.clone(), d.clone(), b.clone()];
    v.sort();
    assert_eq!(v, vec![e, d, cc, b, a]);
    assert_eq!(
        m(&[(0, 1), (2, 3)]).mul(&m(&[(1, 1), (2, 1)])),
        m(&[(0, 1), (1, 1), (2, 4)])
    );
    assert_eq!(
        m(&[(0, 2), (2, 3)]).div(&m(&[(2, 1)])),
        Some(m(&[(0, 2), (2, 2)]))
    );
    assert_eq!(m(&[(0, 2), (2, 3)]).div(&m(&[(1, 1)])), None);
    assert_eq!(m(&[(0, 2)]).div(&m(&[(0, 3)])), None);
    assert_eq!(
        m(&[(0, 2), (3, 1)]).gcd(&m(&[(0, 1), (1, 4), (3, 2)])),
        m(&[(0, 1), (3, 1)])
    );
    assert_eq!(
        m(&[(0, 2), (3, 1)]).lcm(&m(&[(0, 1), (1, 4)])),
        m(&[(0, 2), (1, 4), (3, 1)])
    );
    assert!(m(&[(1, 1)]).divides(&m(&[(0, 1), (1, 2)])));
    assert!(!m(&[(1, 3)]).divides(&m(&[(0, 1), (1, 2)])));
    assert_eq!(m(&[(3, 2), (1, 1), (3, 1), (0, 0)]), m(&[(1, 1), (3, 3)]));
    assert_eq!(m(&[(1, 1), (3, 3)]).total_degree(), 4);
    assert_eq!(m(&[(1, 1), (3, 3)]).degree(3), 3);
    assert_eq!(m(&[(1, 1), (3, 3)]).to_string(), "x1*x3^3");
}

#[test]
fn construction_and_display() {
    let p = Poly::from_terms(vec![
        (m(&[(1, 1)]), Q::from_i64(2)),
        (Mono::one(), Q::from_i64(1)),
        (m(&[(0, 2)]), Q::from_i64(3)),
        (m(&[(1, 1)]), Q::from_i64(-2)),
        (m(&[(0, 1), (1, 1)]), Q::new(-1, 2).expect("q")),
    ]);
    assert!(is_canonical(&p));
    assert_eq!(p.to_string(), "3*x0^2 - 1/2*x0*x1 + 1");
    assert_eq!(p.len(), 3);
    assert_eq!(p.leading_coeff(), Some(&Q::from_i64(3)));
    assert_eq!(p.leading_mono(), Some(&m(&[(0, 2)])));
    assert_eq!(Poly::zero().as_constant(), Some(&Q::zero()));
    assert_eq!(c(5).as_constant(), Some(&Q::from_i64(5)));
    assert_eq!(p.as_constant(), None);
    assert!(Poly::one().is_one());
    assert!(x(3).is_monomial());
    assert_eq!(Poly::zero().to_string(), "0");
    assert_eq!((-&x(2) + c(1)).to_string(), "-x2 + 1");
    assert_eq!(p.vars(), vec![0, 1]);
    assert_eq!(p.degree(0), 2);
    assert_eq!(p.total_degree(), 2);
    assert!(p.contains_var(1) && !p.contains_var(2));
    assert_eq!(p.coeff_of(&m(&[(0, 2)])), Q::from_i64(3));
    assert_eq!(p.coeff_of(&m(&[(0, 1)])), Q::zero());
}

#[test]
fn arithmetic_exact() {
    let (a, b) = (x(0), x(1));
    let s = &a + &b;
    let sq = &s * &s;
    assert_eq!(sq.to_string(), "x0^2 + 2*x0*x1 + x1^2");
    assert_eq!(s.pow(3).to_string(), "x0^3 + 3*x0^2*x1 + 3*x0*x1^2 + x1^3");
    assert_eq!((&sq - &sq), Poly::zero());
    let d = &a - &b;
    assert_eq!((&s * &d).to_string(), "x0^2 - x1^2");
    assert_eq!(
        s.scale(&Q::new(1, 2).expect("q")).to_string(),
        "1/2*x0 + 1/2*x1"
    );
    assert_eq!(
        s.mul_mono(&m(&[(1, 2)]), &Q::from_i64(-3)).to_string(),
        "-3*x0*x1^2 - 3*x1^3"
    );
    let mut acc = Poly::zero();
    acc += &s;
    acc -= &a;
    acc *= &b;
    assert_eq!(acc.to_string(), "x1^2");
    assert_eq!(s.clone() + d.clone(), a.scale(&Q::from_i64(2)));
    assert_eq!(s.clone() - d.clone(), b.scale(&Q::from_i64(2)));
    assert_eq!(&s - d.clone(), b.scale(&Q::from_i64(2)));
    assert_eq!(s.clone() * &d, &s * &d);
    assert_eq!(Poly::zero().pow(0), Poly::one());
    assert_eq!(c(2).pow(10), c(1024));
    assert_eq!(-(s.clone()), -&s);
}

#[test]
fn division() {
    let s = &(&x(0) + &x(1)) + &c(1);
    let p3 = s.pow(3);
    assert_eq!(p3.div_exact(&s), Some(s.pow(2)));
    assert_eq!(p3.div_exact(&s.pow(3)), Some(Poly::one()));
    assert_eq!(p3.div_exact(&s.pow(4)), None);
    let q = &x(0) * &x(0) + c(1);
    assert_eq!(q.div_exact(&(&x(0) + &c(1))), None);
    assert_eq!(q.div_exact(&Poly::zero()), None);
    assert_eq!(Poly::zero().div_exact(&q), Some(Poly::zero()));
    assert_eq!(q.div_exact(&c(2)), Some(q.scale(&Q::new(1, 2).expect("q"))));
    assert_eq!(x(0).div_exact(&(&x(0) - &x(1))), None);
    assert_eq!((&x(0) * &x(1)).div_exact(&x(1)), Some(x(0)));
    assert_eq!(x(0).div_exact(&x(1)), None);
    // huge exponents: exercises the unpacked (plain) paths
    let big: Poly = (0..6)
        .map(|v| Poly::monomial(Mono::var_pow(v, 1 << 30), Q::one()))
        .fold(Poly::zero(), |a, b| a + b);
    let big2 = &big + &c(1);
    let prod = &big * &big2;
    assert!(is_canonical(&prod));
    assert_eq!(prod.div_exact(&big2), Some(big.clone()));
    assert_eq!(prod.div_exact(&big), Some(big2.clone()));
    assert_eq!((&prod + &c(1)).div_exact(&big), None);
}

#[test]
fn structure_ops() {
    // p = 3 x0^2 x1 + x0 x2 - 5 x1 + 7
    let p = Poly::from_terms(vec![
        (m(&[(0, 2), (1, 1)]), Q::from_i64(3)),
        (m(&[(0, 1), (2, 1)]), Q::from_i64(1)),
        (m(&[(1, 1)]), Q::from_i64(-5)),
        (Mono::one(), Q::from_i64(7)),
    ]);
    let cs = p.coeffs_in(0);
    assert_eq!(cs.len(), 3);
    assert_eq!(cs[0].to_string(), "-5*x1 + 7");
    assert_eq!(cs[1].to_string(), "x2");
    assert_eq!(cs[2].to_string(), "3*x1");
    assert_eq!(Poly::from_coeffs_in(0, &cs), p);
    let cs1 = p.coeffs_in(1);
    assert_eq!(Poly::from_coeffs_in(1, &cs1), p);
    assert_eq!(p.diff(0).to_string(), "6*x0*x1 + x2");
    assert_eq!(p.diff(1).to_string(), "3*x0^2 - 5");
    assert_eq!(p.diff(5), Poly::zero());
    // subst x0 -> x1 + 1
    let s = p.subst(0, &(&x(1) + &c(1)));
    let expect = &(&(&c(3) * &(&x(1) + &c(1)).pow(2)) * &x(1) + &(&(&x(1) + &c(1)) * &x(2)))
        - &(&c(5) * &x(1))
        + c(7);
    assert_eq!(s, expect);
    let val = p.eval_q(&|v| Some(Q::from_i64(v as i64 + 2)));
    // x0=2,x1=3,x2=4: 3*4*3 + 2*4 - 15 + 7 = 36
    assert_eq!(val, Some(Q::from_i64(36)));
    assert_eq!(
        p.eval_q(&|v| if v == 2 { None } else { Some(Q::one()) }),
        None
    );
    assert_eq!(p.eval_f64(&|v| v as f64 + 2.0), 36.0);
    assert_eq!(p.eval_var(0, &Q::from_i64(2)), p.subst(0, &c(2)));
    let r = p.map_vars(&|v| v + 10);
    assert_eq!(r.vars(), vec![10, 11, 12]);
    assert_eq!(r.map_vars(&|v| v - 10), p);
    // content / primitive / monic
    let q = Poly::from_terms(vec![
        (m(&[(0, 1)]), Q::new(3, 4).expect("q")),
        (Mono::one(), Q::new(-9, 10).expect("q")),
    ]);
    assert_eq!(q.content(), Q::new(3, 20).expect("q"));
    assert_eq!(q.primitive().to_string(), "5*x0 - 6");
    assert_eq!(q.monic().to_string(), "x0 - 6/5");
    assert_eq!((-&q).primitive().to_string(), "-5*x0 + 6");
    assert_eq!(Poly::zero().content(), Q::zero());
    assert_eq!((&x(0) * &x(1) + x(0).pow(2)).mono_content(), m(&[(0, 1)]));
}

// ------------------------------------------------------------------
// property tests
// ------------------------------------------------------------------

pub(super) const VARS: [Var; 4] = [0, 3, 17, 40];

pub(super) fn arb_coeff() -> impl Strategy<Value = Q> {
    prop_oneof![
        4 => (-6i64..=6).prop_filter("nonzero", |n| *n != 0).prop_map(Q::from_i64),
        1 => ((-6i64..=6), (1i64..=5)).prop_filter_map("nonzero", |(n, d)| Q::new(n, d).filter(|q| !q.is_zero())),
        1 => any::<i32>().prop_map(|n| Q::from_i64(n as i64)),
    ]
}

pub(super) fn arb_poly(nvars: usize, maxdeg: u32, maxterms: usize) -> impl Strategy<Value = Poly> {
    proptest::collection::vec(
        (proptest::collection::vec(0..=maxdeg, nvars), arb_coeff()),
        0..=maxterms,
    )
    .prop_map(move |ts| {
        Poly::from_terms(
            ts.into_iter()
                .map(|(es, cf)| (Mono::from_pairs(VARS.iter().copied().zip(es)), cf))
                .collect(),
        )
    })
}

pub(super) fn arb_small() -> impl Strategy<Value = Poly> {
    arb_poly(3, 2, 4).prop_map(|p| {
        p.map_coeffs(|c| {
            if c.numer().bits() > 8 {
                Q::from_i64(3)
            } else {
                c.clone()
            }
        })
    })
}

pub(super) fn pt(v: Var) -> Option<Q> {
    Q::new(v as i64 * 7 + 3, (v as i64 % 5) + 2)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn prop_ring_laws(a in arb_poly(4, 3, 6), b in arb_poly(4, 3, 6), d in arb_poly(4, 3, 6)) {
        prop_assert!(is_canonical(&a));
        let ab = &a * &b;
        prop_assert!(is_canonical(&ab));
        prop_assert_eq!(&ab, &(&b * &a));
        prop_assert_eq!(&a * &(&b + &d), &(&a * &b) + &(&a * &d));
        prop_assert_eq!(&(&a + &b) - &b, a.clone());
        prop_assert_eq!(&a + &b, &b + &a);
        prop_assert_eq!(a.clone() + b.clone(), &a + &b);
        prop_assert_eq!(a.clone() - b.clone(), &a - &b);
        prop_assert_eq!(&a - b.clone(), &a - &b);
        prop_assert_eq!(a.clone() - &b, &a - &b);
        prop_assert_eq!(&a + b.clone(), &a + &b);
        prop_assert_eq!(&(&a * &b) * &d, &a * &(&b * &d));
        prop_assert_eq!(ab.eval_q(&pt), Some(a.eval_q(&pt).expect("eval") * b.eval_q(&pt).expect("eval")));
        prop_assert_eq!((&a + &b).eval_q(&pt), Some(a.eval_q(&pt).expect("eval") + b.eval_q(&pt).expect("eval")));
        let f = |v: Var| pt(v).map(|q| q.to_f64()).unwrap_or(0.0);
        let (ef, eq) = (ab.eval_f64(&f), ab.eval_q(&pt).expect("eval").to_f64());
        prop_assert!((ef - eq).abs() <= 1e-6 * (1.0 + eq.abs()));
        prop_assert_eq!(a.pow(3), &(&a * &a) * &a);
        // derivative: product rule
        prop_assert_eq!(ab.diff(3), &(&a.diff(3) * &b) + &(&a * &b.diff(3)));
        // coeffs round trip
        prop_assert_eq!(Poly::from_coeffs_in(17, &a.coeffs_in(17)), a.clone());
        // substitution is a ring homomorphism
        let d2 = Poly::from_terms(d.terms().iter().take(2).cloned().collect());
        prop_assert_eq!(ab.subst(0, &d2), &a.subst(0, &d2) * &b.subst(0, &d2));
    }

    #[test]
    fn prop_big_coefficients(
        a in arb_poly(3, 2, 4),
        b in arb_poly(3, 2, 4),
        k in prop_oneof![Just(i64::MAX), Just(i64::MIN), Just(i64::MAX - 1), any::<i64>()],
    ) {
        // coefficients near the i64 limits: overflow into BigRational and back
        let kq = Q::from_i64(k);
        let ak = a.scale(&kq);
        let bk = &b + &Poly::constant(kq.clone());
        let p = &ak * &bk;
        prop_assert!(is_canonical(&p));
        prop_assert_eq!(&p, &(&bk * &ak));
        prop_assert_eq!(p.eval_q(&pt), Some(ak.eval_q(&pt).expect("eval") * bk.eval_q(&pt).expect("eval")));
        if !bk.is_zero() {
            prop_assert_eq!(p.div_exact(&bk), Some(ak.clone()));
        }
        prop_assert_eq!(&(&p - &(&ak * &b)) - &ak.scale(&kq), Poly::zero());
        if !ak.is_zero() && !bk.is_zero() {
            let g = (&ak * &bk).gcd(&ak);
            prop_assert_eq!(g, ak.monic());
        }
    }

    #[test]
    fn prop_div_exact(a in arb_poly(4, 3, 6), b in arb_poly(4, 3, 6)) {
        let ab = &a * &b;
        if !b.is_zero() {
            prop_assert_eq!(ab.div_exact(&b), Some(a.clone()));
            let r = &ab + &c(1);
            if let Some(q) = r.div_exact(&b) {
                prop_assert_eq!(&q * &b, r);
            }
        } else {
            prop_assert_eq!(ab.div_exact(&b), None);
        }
    }
}

/// An exact division whose quotient is long though its dividend is two
/// terms stops at the work a product may take (8 × the budget).
#[test]
fn a_long_division_is_bounded_by_its_work() {
    let x = Poly::var(0);
    let one = Poly::one();
    // d = 1 + x + … + x⁹ divides x¹⁰⁰⁰ − 1 with a 200-term quotient
    let d = (0..10).fold(Poly::zero(), |a, i| &a + &x.pow(i));
    let a = &x.pow(1000) - &one;
    assert_eq!(a.div_exact(&d).map(|q| q.len()), Some(200));
    let e = crate::budget::within(100, || a.div_exact(&d)).expect_err("800 products allowed");
    assert_eq!(e.measure, crate::budget::Measure::Division(2, 10));
    assert_eq!(
        e.message(),
        "expression too large: a division of 2 by 10 terms (the limit is 100 terms, and 800 term products)"
    );
}
