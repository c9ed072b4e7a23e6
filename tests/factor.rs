//! Factorization over ℚ (`qdot::engine::poly::factor`): known answers, the SymPy
//! oracle (`tests/fixtures/factor.json`, written by `gen_factor.py` with
//! `factor_list`), and properties on random products.

use proptest::prelude::*;
use qdot::engine::poly::factor::{factor, square_free, Factorization};
use qdot::engine::poly::{Mono, Poly};
use qdot::num::Q;
use serde_json::Value;

/// Variable names of the test polynomials, by id (`l` stands for λ).
const NAMES: [&str; 10] = ["x", "y", "z", "w", "a", "b", "c", "k", "m", "l"];

/// A tiny parser for SymPy's printed polynomials: integers, the names of
/// [`NAMES`], `+ - * / ** ^` and parentheses (division by constants only).
struct Parser<'a> {
    s: &'a [u8],
    i: usize,
}

impl Parser<'_> {
    fn skip(&mut self) {
        while self.i < self.s.len() && self.s[self.i] == b' ' {
            self.i += 1;
        }
    }
    fn peek(&mut self) -> Option<u8> {
        self.skip();
        self.s.get(self.i).copied()
    }
    fn sum(&mut self) -> Poly {
        let mut acc = match self.peek() {
            Some(b'-') => {
                self.i += 1;
                -self.product()
            }
            _ => self.product(),
        };
        loop {
            match self.peek() {
                Some(b'+') => {
                    self.i += 1;
                    acc = &acc + &self.product();
                }
                Some(b'-') => {
                    self.i += 1;
                    acc = &acc - &self.product();
                }
                _ => return acc,
            }
        }
    }
    fn product(&mut self) -> Poly {
        let mut acc = self.power();
        loop {
            self.skip();
            if self.s[self.i..].starts_with(b"**") {
                unreachable!("handled in power")
            }
            match self.peek() {
                Some(b'*') => {
                    self.i += 1;
                    acc = &acc * &self.power();
                }
                Some(b'/') => {
                    self.i += 1;
                    let d = self.power();
                    let d = d.as_constant().expect("constant divisor").clone();
                    acc = acc.scale(&d.recip().expect("nonzero"));
                }
                _ => return acc,
            }
        }
    }
    fn power(&mut self) -> Poly {
        let base = self.atom();
        self.skip();
        if self.s[self.i..].starts_with(b"**") || self.peek() == Some(b'^') {
            self.i += if self.s[self.i] == b'^' { 1 } else { 2 };
            self.skip();
            let start = self.i;
            while self.i < self.s.len() && self.s[self.i].is_ascii_digit() {
                self.i += 1;
            }
            let e: u32 = std::str::from_utf8(&self.s[start..self.i])
                .expect("ascii")
                .parse()
                .expect("exponent");
            return base.pow(e);
        }
        base
    }
    fn atom(&mut self) -> Poly {
        match self.peek() {
            Some(b'(') => {
                self.i += 1;
                let p = self.sum();
                assert_eq!(self.peek(), Some(b')'));
                self.i += 1;
                p
            }
            Some(b'-') => {
                self.i += 1;
                -self.power()
            }
            Some(ch) if ch.is_ascii_digit() => {
                let start = self.i;
                while self.i < self.s.len() && self.s[self.i].is_ascii_digit() {
                    self.i += 1;
                }
                let n: Q = std::str::from_utf8(&self.s[start..self.i])
                    .expect("ascii")
                    .parse()
                    .expect("integer");
                Poly::constant(n)
            }
            Some(ch) if ch.is_ascii_alphabetic() => {
                let start = self.i;
                while self.i < self.s.len() && self.s[self.i].is_ascii_alphanumeric() {
                    self.i += 1;
                }
                let name = std::str::from_utf8(&self.s[start..self.i]).expect("ascii");
                let v = NAMES.iter().position(|n| *n == name).expect("known name");
                Poly::var(v as u32)
            }
            other => panic!("unexpected {other:?} at {}", self.i),
        }
    }
}

fn p(s: &str) -> Poly {
    let mut parser = Parser {
        s: s.as_bytes(),
        i: 0,
    };
    let r = parser.sum();
    assert_eq!(parser.peek(), None, "trailing input in {s}");
    r
}

/// Primitive, positive leading coefficient.
fn norm(f: &Poly) -> Poly {
    let q = f.primitive();
    if q.leading_coeff().is_some_and(|c| c.is_negative()) {
        -q
    } else {
        q
    }
}

fn factors_of(s: &str) -> Vec<(Poly, u32)> {
    factor(&p(s)).factors
}

fn check(f: &Poly, r: &Factorization) {
    assert_eq!(&r.expand(), f, "expand(factor(f)) == f");
    for (g, e) in &r.factors {
        assert!(*e >= 1);
        assert!(!g.is_constant());
        assert_eq!(&norm(g), g, "factor {g} is primitive with positive lc");
    }
}

#[test]
fn zero_and_constants() {
    let r = factor(&Poly::zero());
    assert_eq!(r.unit, Q::zero());
    assert!(r.factors.is_empty());
    let r = factor(&p("-3/7"));
    assert_eq!(r.unit, Q::new(-3, 7).expect("q"));
    assert!(r.factors.is_empty());
    assert!(square_free(&p("5")).is_empty());
}

#[test]
fn known_answers() {
    assert_eq!(
        factors_of("x^4 - y^4"),
        vec![(p("x - y"), 1), (p("x + y"), 1), (p("x^2 + y^2"), 1)]
    );
    assert_eq!(
        factors_of("(x + y)^2*(x - 2*y)"),
        vec![(p("x - 2*y"), 1), (p("x + y"), 2)]
    );
    assert_eq!(
        factors_of("x^6 - 1"),
        vec![
            (p("x - 1"), 1),
            (p("x + 1"), 1),
            (p("x^2 - x + 1"), 1),
            (p("x^2 + x + 1"), 1)
        ]
    );
    // contents: numeric 6, monomial y
    let r = factor(&p("6*x^2*y + 12*x*y^2 + 6*y^3"));
    assert_eq!(r.unit, Q::from_i64(6));
    assert_eq!(r.factors, vec![(p("y"), 1), (p("x + y"), 2)]);
    // rational coefficients: 3/4 (x + 1/3)(y - 2/5) = 1/20 (3x + 1)(5y - 2)
    let r = factor(&p("3/4*(x + 1/3)*(y - 2/5)"));
    assert_eq!(r.unit, Q::new(1, 20).expect("q"));
    assert_eq!(r.factors, vec![(p("3*x + 1"), 1), (p("5*y - 2"), 1)]);
    // a negative unit
    let r = factor(&p("y^2 - x^2"));
    assert_eq!(r.unit, Q::from_i64(-1));
    assert_eq!(r.factors, vec![(p("x - y"), 1), (p("x + y"), 1)]);
}

#[test]
fn irreducibles_with_many_modular_factors() {
    // Swinnerton-Dyer polynomials: irreducible over Q, split into factors of
    // degree <= 2 modulo every prime
    for s in [
        "x^4 - 10*x^2 + 1",
        "x^8 - 40*x^6 + 352*x^4 - 960*x^2 + 576",
        "x^4 + 1",
        "2*k^2 - 4*k*m*l + m^2*l^2",
    ] {
        let f = p(s);
        let r = factor(&f);
        assert_eq!(r.factors, vec![(f.clone(), 1)], "{s} is irreducible");
        assert_eq!(r.unit, Q::one());
    }
    assert_eq!(
        factors_of("(x^4 - 10*x^2 + 1)*(x^2 - 2)"),
        vec![(p("x^2 - 2"), 1), (p("x^4 - 10*x^2 + 1"), 1)]
    );
}

#[test]
fn several_variables() {
    assert_eq!(
        factors_of("(a*b + c)*(a - c^2)*(b + 1)^2"),
        vec![(p("b + 1"), 2), (p("a*b + c"), 1), (p("a - c^2"), 1)]
    );
    assert_eq!(
        factors_of("(k - 6*m*l)*(k - m*l)"),
        vec![(p("k - 6*m*l"), 1), (p("k - m*l"), 1)]
    );
    assert_eq!(
        factors_of("(x*y*z - w)*(x^2 - y*w)*(z^2 + w^2)"),
        vec![
            (p("x^2 - y*w"), 1),
            (p("z^2 + w^2"), 1),
            (p("x*y*z - w"), 1)
        ]
    );
    // no variable of degree 1: the Kronecker path
    assert_eq!(
        factors_of("(x^2 + x*y + y^2)*(x^2 - x*y + y^2)"),
        vec![(p("x^2 - x*y + y^2"), 1), (p("x^2 + x*y + y^2"), 1)]
    );
    assert_eq!(
        factors_of("(x^2*y^2 - 2)*(x^2*y^2 + 2)*(x^2 + y^2 + z^2 - 1)"),
        vec![
            (p("x^2 + y^2 + z^2 - 1"), 1),
            (p("x^2*y^2 - 2"), 1),
            (p("x^2*y^2 + 2"), 1)
        ]
    );
}

/// qdot's factors equal SymPy's `factor_list` as a multiset, after both are
/// normalized (primitive, positive leading coefficient in qdot's order).
#[test]
fn sympy_oracle() {
    let text = include_str!("fixtures/factor.json");
    let cases: Value = serde_json::from_str(text).expect("json");
    let cases = cases.as_array().expect("array");
    assert!(cases.len() >= 40);
    for case in cases {
        let src = case["poly"].as_str().expect("poly");
        let f = p(src);
        let r = factor(&f);
        check(&f, &r);
        let mut want: Vec<(Poly, u32)> = case["factors"]
            .as_array()
            .expect("factors")
            .iter()
            .map(|fe| {
                let g = norm(&p(fe[0].as_str().expect("factor")));
                (g, fe[1].as_u64().expect("exponent") as u32)
            })
            .collect();
        let mut got = r.factors.clone();
        let key = |a: &(Poly, u32)| format!("{}^{}", a.0, a.1);
        want.sort_by_key(key);
        got.sort_by_key(key);
        assert_eq!(got, want, "factors of {src}");
    }
}

fn small_poly(vars: usize) -> impl Strategy<Value = Poly> {
    prop::collection::vec((-4i64..=4, prop::collection::vec(0u32..=2, vars)), 1..=4).prop_map(
        |terms| {
            Poly::from_terms(
                terms
                    .into_iter()
                    .map(|(c, es)| {
                        let m = Mono::from_pairs(
                            es.into_iter().enumerate().map(|(v, e)| (v as u32, e)),
                        );
                        (m, Q::from_i64(c))
                    })
                    .collect(),
            )
        },
    )
}

fn pieces() -> impl Strategy<Value = Vec<Poly>> {
    (2usize..=3).prop_flat_map(|nv| prop::collection::vec(small_poly(nv), 1..=3))
}

proptest! {
    #![proptest_config(ProptestConfig { cases: crate::common::proptest_cases(48), ..ProptestConfig::default() })]

    #[test]
    fn random_products(pieces in pieces(), num in -6i64..=6, den in 1i64..=5) {
        let f: Poly = pieces.iter().cloned().product();
        prop_assume!(!f.is_zero());
        let r = factor(&f);
        check(&f, &r);
        let nonconstant = pieces.iter().filter(|q| !q.is_constant()).count() as u32;
        let count: u32 = r.factors.iter().map(|(_, e)| *e).sum();
        prop_assert!(count >= nonconstant);
        for (g, _) in &r.factors {
            prop_assert_eq!(square_free(g), vec![(g.clone(), 1)]);
        }
        // deterministic, and scaling only changes the unit
        prop_assert_eq!(&factor(&f), &r);
        prop_assume!(num != 0);
        let s = Q::new(num, den).expect("q");
        let rs = factor(&f.scale(&s));
        prop_assert_eq!(&rs.factors, &r.factors);
        prop_assert_eq!(rs.unit, &r.unit * &s);
    }
}
