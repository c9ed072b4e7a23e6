//! Tests of the gcd: known answers, the Zippel routine directly, random
//! cases against an independent reference gcd and coprimality proofs of the
//! cofactors, and property tests.

use super::prs::prem;
use super::zippel::zippel_gcd;
use crate::num::Q;
use crate::poly::tests::{arb_poly, arb_small, c, cq, is_canonical, m, x};
use crate::poly::{Mono, Poly, Var};
use crate::rng::SplitMix64;
use proptest::prelude::*;

fn check_gcd(a: &Poly, b: &Poly, expect: &Poly) {
    let g = a.gcd(b);
    assert_eq!(&g, &expect.monic(), "gcd({a}, {b})");
    let g2 = b.gcd(a);
    assert_eq!(&g2, &expect.monic());
    let (gg, ca, cb) = a.gcd_cofactors(b);
    assert_eq!(gg, g);
    assert_eq!(&(&ca * &g), a);
    assert_eq!(&(&cb * &g), b);
}

#[test]
fn gcd_simple() {
    let (a, b, z) = (x(0), x(1), x(2));
    check_gcd(&Poly::zero(), &Poly::zero(), &Poly::zero());
    check_gcd(
        &Poly::zero(),
        &(&a.scale(&Q::from_i64(3)) + &c(6)),
        &(&a + &c(2)),
    );
    check_gcd(&c(4), &c(6), &c(1));
    check_gcd(&(&a * &b), &(&b * &z), &b);
    check_gcd(
        &(&a.pow(3) * &b),
        &(&(&a.pow(2) * &b.pow(2)) + &a.pow(5)),
        &a.pow(2),
    );
    check_gcd(&(&a + &b), &(&a - &b), &c(1));
    check_gcd(
        &(&a.pow(2) - &b.pow(2)),
        &(&(&a + &b) * &(&a + &z)),
        &(&a + &b),
    );
    check_gcd(
        &(&a.pow(2) - &c(1)),
        &(&a.pow(2) - &(&c(2) * &a) + c(1)),
        &(&a - &c(1)),
    );
}

#[test]
fn gcd_hard_cases() {
    let (xx, yy, zz) = (x(0), x(1), x(2));
    // (x+y+z)^5 (x-y) and (x+y+z)^3 (x+2z)^2
    let s = &(&xx + &yy) + &zz;
    let a = &s.pow(5) * &(&xx - &yy);
    let b = &s.pow(3) * &(&xx + &zz.scale(&Q::from_i64(2))).pow(2);
    check_gcd(&a, &b, &s.pow(3));
    // rational coefficients
    let f = &xx.scale(&Q::new(1, 2).expect("q")) + &yy.scale(&Q::new(1, 3).expect("q"));
    let a = &f * &(&xx - &cq(1, 5));
    let b = &f * &(&yy + &cq(7, 4));
    check_gcd(&a, &b, &f);
    // many variables only in one argument
    let mut big = Poly::zero();
    for v in 10..40u32 {
        big += &(&x(v) * &x(v + 1)).scale(&Q::from_i64(v as i64 - 20));
    }
    big += &c(3);
    let common = &xx + &yy;
    let a = &common * &big;
    let b = &common * &(&xx - &yy.scale(&Q::from_i64(3)));
    check_gcd(&a, &b, &common);
    // univariate degree 20
    let g: Poly = (0..=10)
        .map(|i| Poly::monomial(Mono::var_pow(0, i), Q::from_i64((i as i64 * 7) % 5 - 2)))
        .fold(Poly::zero(), |p, q| p + q);
    let u1: Poly = (0..=10)
        .map(|i| Poly::monomial(Mono::var_pow(0, i), Q::from_i64((i as i64 * 3) % 7 - 3)))
        .fold(Poly::zero(), |p, q| p + q);
    let u2: Poly = (0..=9)
        .map(|i| Poly::monomial(Mono::var_pow(0, i), Q::from_i64((i as i64 * 5) % 11 - 5)))
        .fold(Poly::zero(), |p, q| p + q);
    let e = &g * &u1.gcd(&u2);
    check_gcd(&(&g * &u1), &(&g * &u2), &e);
    // many variables in the gcd itself (PRS path): 8 variables
    let mut lin = c(1);
    for v in 0..8u32 {
        lin += &x(v).scale(&Q::from_i64(v as i64 + 1));
    }
    let mut other = c(-2);
    for v in 0..8u32 {
        other += &(&x(v) * &x((v + 1) % 8));
    }
    let a = &lin * &other;
    let b = &lin * &(&lin + &x(3).pow(2));
    check_gcd(&a, &b, &lin);
    check_gcd(&(&a * &lin), &(&b * &lin), &lin.pow(2));
}

#[test]
fn gcd_dense_bivariate_degree_10() {
    let (xx, yy) = (x(0), x(1));
    let dense = |seed: i64, dx: u32, dy: u32| -> Poly {
        let mut t = Vec::new();
        for i in 0..=dx {
            for j in 0..=dy {
                let cf = ((seed + 3 * i as i64 + 7 * j as i64 + (i * j) as i64) % 9) - 4;
                t.push((m(&[(0, i), (1, j)]), Q::from_i64(cf)));
            }
        }
        Poly::from_terms(t)
    };
    let g = &dense(1, 5, 5) + &(&xx.pow(5) * &yy.pow(5));
    let a = &g * &(&dense(2, 5, 5) + &xx.pow(6));
    let b = &g * &(&dense(5, 5, 5) + &yy.pow(6));
    let expect = &g * &(&dense(2, 5, 5) + &xx.pow(6)).gcd(&(&dense(5, 5, 5) + &yy.pow(6)));
    check_gcd(&a, &b, &expect);
    assert!(a.degree(0) >= 10 && a.degree(1) >= 10);
}

#[test]
fn gcd_sparse_many_vars() {
    // nontrivial gcd of degree 3 in 8 variables (sparse modular path)
    let t = |c: i64, e: &[(Var, u32)]| Poly::monomial(m(e), Q::from_i64(c));
    let g = &(&(&t(3, &[(1, 3), (4, 1), (10, 1), (19, 2)])
        - &t(1, &[(1, 2), (4, 2), (13, 1), (34, 2)]))
        + &t(8, &[(1, 1), (10, 2), (19, 3), (25, 2)]))
        - &(&t(8, &[(4, 3), (10, 3), (13, 3), (25, 3), (28, 2), (34, 3)])
            + &t(1, &[(4, 2), (19, 1), (25, 3), (28, 2), (34, 1)]));
    let ca = &(&t(2, &[(1, 1), (28, 3), (34, 1)]) - &t(5, &[(4, 2), (13, 1)]))
        + &t(7, &[(10, 1), (19, 1), (25, 2)]);
    let cb = &(&t(1, &[(1, 2), (10, 1)]) + &t(4, &[(13, 2), (28, 1), (34, 3)]))
        - &t(3, &[(4, 1), (19, 2), (25, 1)]);
    check_gcd(&(&g * &ca), &(&g * &cb), &g);
    check_gcd(&(&(&g * &ca) * &cb), &(&g * &cb.pow(2)), &(&g * &cb));
    // the same through the Zippel routine directly
    let (a, b) = ((&g * &ca).normalize_z(), (&g * &cb).normalize_z());
    let vars = a.vars();
    let bounds: Vec<u32> = vars.iter().map(|&v| g.degree(v)).collect();
    let z = zippel_gcd(&a, &b, &vars, &bounds).expect("zippel succeeds");
    assert_eq!(z.monic(), g.monic());
}

#[test]
fn gcd_pendulum_like() {
    // trig-polynomial style expressions: s_i, c_i, masses, lengths
    let n = 6u32;
    let sv = |i: u32| x(i);
    let cv = |i: u32| x(10 + i);
    let mv = |i: u32| x(20 + i);
    let lv = |i: u32| x(30 + i);
    let mut mass_sum = Poly::zero();
    for i in 0..n {
        mass_sum += &mv(i);
    }
    let mut e1 = Poly::zero();
    for i in 0..n {
        e1 +=
            &(&(&mv(i) * &lv(i)) * &(&(&sv(i) * &cv((i + 1) % n)) - &(&cv(i) * &sv((i + 1) % n))));
    }
    let mut e2 = Poly::zero();
    for i in 0..n {
        e2 += &(&lv(i).pow(2) * &(&sv(i).pow(2) + &cv(i).pow(2)));
    }
    let a = &mass_sum * &e1;
    let b = &mass_sum * &e2;
    check_gcd(&a, &b, &mass_sum);
    check_gcd(&e1, &e2, &c(1));
    let k = &lv(0) * &mv(1);
    check_gcd(&(&a * &k), &(&e2 * &(&k * &lv(2))), &k);
}

/// Independent reference gcd: plain recursive primitive PRS, no shortcuts.
fn ref_gcd(a: &Poly, b: &Poly) -> Poly {
    if a.is_zero() {
        return b.normalize_z();
    }
    if b.is_zero() {
        return a.normalize_z();
    }
    let (ma, mb) = (a.mono_content(), b.mono_content());
    if !ma.is_one() || !mb.is_one() {
        let g = ref_gcd(
            &a.div_mono(&ma).expect("mono"),
            &b.div_mono(&mb).expect("mono"),
        );
        return g.mul_mono(&ma.gcd(&mb), &Q::one());
    }
    let mut vars = a.vars();
    vars.extend(b.vars());
    vars.sort_unstable();
    vars.dedup();
    // main variable: smallest total degree in a and b
    let v = match vars.iter().min_by_key(|&&v| (a.degree(v) + b.degree(v), v)) {
        Some(v) => *v,
        None => return Poly::one(),
    };
    if !a.contains_var(v) {
        return b
            .coeffs_in(v)
            .iter()
            .fold(a.normalize_z(), |g, c| ref_gcd(&g, c));
    }
    if !b.contains_var(v) {
        return a
            .coeffs_in(v)
            .iter()
            .fold(b.normalize_z(), |g, c| ref_gcd(&g, c));
    }
    let content = |cs: &[Poly]| cs.iter().fold(Poly::zero(), |g, c| ref_gcd(&g, c));
    let prim = |cs: &[Poly]| -> Vec<Poly> {
        let ct = content(cs);
        cs.iter()
            .map(|c| c.div_exact(&ct).expect("content divides"))
            .collect()
    };
    let (ca, cb) = (a.coeffs_in(v), b.coeffs_in(v));
    let cont = ref_gcd(&content(&ca), &content(&cb));
    let (mut u, mut w) = (prim(&ca), prim(&cb));
    if u.len() < w.len() {
        std::mem::swap(&mut u, &mut w);
    }
    let last = loop {
        let r = prem(&u, &w);
        if r.is_empty() {
            break prim(&w);
        }
        if r.len() == 1 {
            break vec![Poly::one()];
        }
        u = w;
        w = prim(&r);
    };
    (&Poly::from_coeffs_in(v, &last) * &cont).normalize_z()
}

fn rand_poly(st: &mut SplitMix64, vars: &[Var], maxdeg: u32, nterms: usize, cmax: i64) -> Poly {
    let mut t = Vec::new();
    for _ in 0..nterms {
        let mo = Mono::from_pairs(
            vars.iter()
                .map(|&v| (v, st.below(maxdeg as u64 + 1) as u32)),
        );
        let cf = st.below(2 * cmax as u64 + 1) as i64 - cmax;
        t.push((mo, Q::from_i64(cf)));
    }
    Poly::from_terms(t)
}

/// 1…maxvars distinct variables out of twelve, sorted.
fn random_vars(st: &mut SplitMix64, maxvars: usize) -> Vec<Var> {
    let all: Vec<Var> = (0..12).map(|i| i * 3 + 1).collect();
    let nv = 1 + st.below(maxvars as u64) as usize;
    let mut vars: Vec<Var> = Vec::new();
    while vars.len() < nv {
        let v = all[st.below(all.len() as u64) as usize];
        if !vars.contains(&v) {
            vars.push(v);
        }
    }
    vars.sort_unstable();
    vars
}

fn random_gcd_round(seed: u64, rounds: usize, maxvars: usize) {
    let mut st = SplitMix64::new(seed);
    for round in 0..rounds {
        let vars = random_vars(&mut st, maxvars);
        let pick = |st: &mut SplitMix64| -> Vec<Var> {
            vars.iter().copied().filter(|_| st.below(3) != 0).collect()
        };
        let (va, vb, vg) = (pick(&mut st), pick(&mut st), pick(&mut st));
        let deg = 1 + st.below(3) as u32;
        let na = 1 + st.below(5) as usize;
        let a = rand_poly(&mut st, &va, deg, na, 5);
        let nb = 1 + st.below(5) as usize;
        let b = rand_poly(&mut st, &vb, deg, nb, 5);
        let ng = 1 + st.below(4) as usize;
        let g = rand_poly(&mut st, &vg, deg, ng, 5);
        let (ag, bg) = (&a * &g, &b * &g);
        if ag.len() + bg.len() > 24 || ag.total_degree() + bg.total_degree() > 12 {
            // the naive reference gets too slow
            continue;
        }
        if std::env::var("GCD_TRACE").is_ok() {
            eprintln!("seed {seed} round {round}: a={ag}\n b={bg}");
        }
        let t0 = std::time::Instant::now();
        let h = ag.gcd(&bg);
        let t1 = t0.elapsed();
        let r = ref_gcd(&ag, &bg).monic();
        let t2 = t0.elapsed() - t1;
        if t1.as_millis() > 200 || t2.as_millis() > 200 {
            eprintln!(
                "slow round {round}: gcd {t1:?} ref {t2:?} vars {} terms {}/{}",
                vars.len(),
                ag.len(),
                bg.len()
            );
        }
        assert_eq!(h, r, "round {round}: gcd({ag}, {bg})");
    }
}

#[test]
fn gcd_matches_reference() {
    random_gcd_round(12345, 150, 4);
}

/// Remainder of univariate polynomials in `v` over Q.
fn urem(mut a: Poly, b: &Poly, v: Var) -> Poly {
    let db = b.degree(v);
    let lb = b.leading_coeff().cloned().unwrap_or_else(Q::one);
    while !a.is_zero() && a.degree(v) >= db {
        let k = a.degree(v) - db;
        let f = a.leading_coeff().cloned().unwrap_or_else(Q::zero) / &lb;
        a = &a - &b.mul_mono(&Mono::var_pow(v, k), &f);
    }
    a
}

/// Independent coprimality proof: for every variable, the univariate
/// images (all other variables at random rationals, leading coefficient
/// kept) have a constant gcd. `false` means "not proven".
fn proven_coprime(a: &Poly, b: &Poly, st: &mut SplitMix64) -> bool {
    if a.is_constant() || b.is_constant() {
        return !(a.is_zero() && b.is_zero());
    }
    let mut vars = a.vars();
    vars.extend(b.vars());
    vars.sort_unstable();
    vars.dedup();
    'var: for &x in &vars {
        for _ in 0..8 {
            let vals: Vec<(Var, Q)> = vars
                .iter()
                .map(|&w| {
                    (
                        w,
                        Q::new(st.below(97) as i64 - 48, 1 + st.below(5) as i64).expect("q"),
                    )
                })
                .collect();
            let sub = |p: &Poly| {
                vals.iter()
                    .filter(|(w, _)| *w != x)
                    .fold(p.clone(), |p, (w, q)| p.eval_var(*w, q))
            };
            let (ua, ub) = (sub(a), sub(b));
            if ua.degree(x) != a.degree(x)
                || ub.degree(x) != b.degree(x)
                || ua.is_zero()
                || ub.is_zero()
            {
                continue;
            }
            let (mut f, mut g) = (ua, ub);
            while !g.is_zero() {
                let r = urem(f, &g, x);
                f = g;
                g = r;
            }
            if f.is_constant() {
                continue 'var;
            }
            // an unlucky point can only make the image gcd larger: retry
        }
        return false;
    }
    true
}

fn random_gcd_proof_round(seed: u64, rounds: usize, maxvars: usize, maxdeg: u64) {
    let mut st = SplitMix64::new(seed);
    for round in 0..rounds {
        let vars = random_vars(&mut st, maxvars);
        let pick = |st: &mut SplitMix64| -> Vec<Var> {
            vars.iter().copied().filter(|_| st.below(4) != 0).collect()
        };
        let (va, vb, vg) = (pick(&mut st), pick(&mut st), pick(&mut st));
        let deg = 1 + st.below(maxdeg) as u32;
        let na = 1 + st.below(8) as usize;
        let a = rand_poly(&mut st, &va, deg, na, 9);
        let nb = 1 + st.below(8) as usize;
        let b = rand_poly(&mut st, &vb, deg, nb, 9);
        let ng = 1 + st.below(6) as usize;
        let g = rand_poly(&mut st, &vg, deg, ng, 9);
        let (ag, bg) = (&a * &g, &b * &g);
        if std::env::var("GCD_TRACE").is_ok() {
            eprintln!("seed {seed} round {round}: a={ag}\n b={bg}");
        }
        let t0 = std::time::Instant::now();
        let h = ag.gcd(&bg);
        let el = t0.elapsed();
        if el.as_millis() > 500 {
            eprintln!("slow gcd round {round}: {el:?}\n a={ag}\n b={bg}");
        }
        if ag.is_zero() && bg.is_zero() {
            assert!(h.is_zero());
            continue;
        }
        let ca = ag.div_exact(&h).expect("gcd divides a");
        let cb = bg.div_exact(&h).expect("gcd divides b");
        assert!(
            h.div_exact(&g).is_some() || g.is_zero(),
            "g does not divide gcd"
        );
        assert!(
            proven_coprime(&ca, &cb, &mut st),
            "seed {seed} round {round}: cofactors not coprime: gcd({ag}, {bg}) = {h}; cofactors {ca} ; {cb}"
        );
    }
}

#[test]
fn gcd_cofactors_proven_coprime() {
    random_gcd_proof_round(777, 60, 5, 3);
}

/// Longer randomized checks (about 3 s in release builds, which CI uses).
#[test]
fn gcd_long_random_reference() {
    for seed in 0..10 {
        let t = std::time::Instant::now();
        random_gcd_round(seed * 7919 + 1, 300, 3);
        eprintln!("reference seed {seed}: {:?}", t.elapsed());
    }
}

#[test]
fn gcd_long_random_big() {
    for seed in 0..10 {
        let t = std::time::Instant::now();
        random_gcd_proof_round(seed * 15485863 + 11, 200, 12, 6);
        eprintln!("big seed {seed}: {:?}", t.elapsed());
    }
}

#[test]
fn gcd_long_random_proof() {
    for seed in 0..20 {
        let t = std::time::Instant::now();
        random_gcd_proof_round(seed * 104729 + 5, 500, 8, 4);
        eprintln!("proof seed {seed}: {:?}", t.elapsed());
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn prop_gcd(a in arb_small(), b in arb_small(), g in arb_small()) {
        prop_assume!(!g.is_zero());
        let ag = &a * &g;
        let bg = &b * &g;
        let h = ag.gcd(&bg);
        prop_assert!(is_canonical(&h));
        if ag.is_zero() && bg.is_zero() {
            prop_assert!(h.is_zero());
            return Ok(());
        }
        prop_assert_eq!(h.leading_coeff(), Some(&Q::one()));
        prop_assert!(h.div_exact(&g).is_some(), "g does not divide gcd: {} / {}", h, g);
        prop_assert!(ag.div_exact(&h).is_some());
        prop_assert!(bg.div_exact(&h).is_some());
        let gab = a.gcd(&b);
        prop_assert_eq!(&h, &(&g * &gab).monic());
        prop_assert_eq!(&h, &bg.gcd(&ag));
        // cofactors are coprime
        let (_, ca, cb) = ag.gcd_cofactors(&bg);
        prop_assert!(ca.gcd(&cb).is_one() || (ca.is_zero() || cb.is_zero()));
    }

    #[test]
    fn prop_gcd_coprime(a in arb_poly(3, 2, 4), b in arb_poly(3, 2, 4)) {
        // a*x0 + 1 and b*x3 + x0 + 2 ... constructions that are coprime
        let p = &(&a * &x(0)) + &c(1);
        let q = &p + &x(3);
        // gcd(p, p + x3) = gcd(p, x3) = 1 since p(x3=0) != 0 mod x3 ... p has constant term 1
        prop_assume!(!p.is_zero());
        prop_assert!(p.gcd(&q).is_one());
        let r = &(&b * &x(3)) + &c(2);
        let pr = &p * &r;
        prop_assert_eq!(pr.gcd(&p), p.monic());
    }
}
