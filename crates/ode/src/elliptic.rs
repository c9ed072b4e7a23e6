//! Jacobi elliptic functions and the complete elliptic integral of the first
//! kind, in double precision: the exact references against which the
//! integrators are measured (the pendulum released from rest).
//!
//! The parameter convention is `m = k²` throughout (Abramowitz & Stegun,
//! 16.1 and 17.2). Everything is valid for 0 ≤ m < 1; outside it the
//! functions return NaN (or +∞ for `ellipk(1)`), never panic.

use std::f64::consts::PI;

/// The arithmetic–geometric mean of `a` and `b` (a, b ≥ 0), by Gauss's
/// iteration to round-off (quadratic convergence: ≤ 6 rounds for f64 when
/// a/b ≤ 1e6).
fn agm(mut a: f64, mut b: f64) -> f64 {
    for _ in 0..64 {
        let an = 0.5 * (a + b);
        let bn = (a * b).sqrt();
        if (an - bn).abs() <= 2.0 * f64::EPSILON * an {
            return 0.5 * (an + bn);
        }
        a = an;
        b = bn;
    }
    0.5 * (a + b)
}

/// The complete elliptic integral of the first kind
/// K(m) = ∫₀^{π/2} dφ / √(1 − m sin²φ), by the arithmetic–geometric mean:
/// K(m) = π / (2·AGM(1, √(1 − m))) (Abramowitz & Stegun, 17.6).
///
/// Valid for m < 1 (including m < 0); `ellipk(1.0)` is +∞, and m > 1 or NaN
/// gives NaN. Relative accuracy a few ulps.
pub fn ellipk(m: f64) -> f64 {
    if m.is_nan() || m > 1.0 {
        return f64::NAN;
    }
    if m == 1.0 {
        return f64::INFINITY;
    }
    PI / (2.0 * agm(1.0, (1.0 - m).sqrt()))
}

/// The Jacobi elliptic functions (sn u, cn u, dn u) of parameter m, for
/// 0 ≤ m < 1 (NaN outside), by the descending Landen transformation / AGM
/// scale (Abramowitz & Stegun, 16.4; Cephes `ellpj`): a = 1, b = √(1 − m),
/// c = √m, iterated to c/a below round-off, then φ_N = 2^N a_N u and the
/// backward recurrence sin(2φ_{n−1} − φ_n) = (c_n/a_n) sin φ_n; with
/// sn = sin φ₀, cn = cos φ₀ and dn = √(1 − m + m·cn²).
///
/// The argument is first reduced modulo the real period 4K(m). For m below
/// 1e-9 and above 1 − 1e-10 the first-order expansions in m and 1 − m
/// (A&S 16.13, 16.15) are used (the latter only while (1 − m)·cosh²u is
/// below 1e-4); their errors are O(m²) and O((1 − m)²·cosh⁴u).
pub fn ellipj(u: f64, m: f64) -> (f64, f64, f64) {
    if !(0.0..1.0).contains(&m) || !u.is_finite() {
        return (f64::NAN, f64::NAN, f64::NAN);
    }
    if m < 1e-9 {
        let t = u.sin();
        let b = u.cos();
        let ai = 0.25 * m * (u - t * b);
        return (t - ai * b, b + ai * t, 1.0 - 0.5 * m * t * t);
    }
    if m >= 0.999_999_999_9 && (1.0 - m) * u.cosh().powi(2) < 1e-4 {
        let ai = 0.25 * (1.0 - m);
        let b = u.cosh();
        let t = u.tanh();
        let phi = 1.0 / b;
        let twon = b * u.sinh();
        let sn = t + ai * (twon - u) / (b * b);
        let ai = ai * t * phi;
        return (sn, phi - ai * (twon - u), phi + ai * (twon + u));
    }
    // Reduce u to [−2K, 2K]: sn, cn, dn all have the real period 4K.
    let period = 4.0 * ellipk(m);
    let u = u - period * (u / period).round();
    let mut a = [0.0f64; 10];
    let mut c = [0.0f64; 10];
    a[0] = 1.0;
    c[0] = m.sqrt();
    let mut b = (1.0 - m).sqrt();
    let mut twon = 1.0;
    let mut i = 0;
    while (c[i] / a[i]).abs() > f64::EPSILON && i < 9 {
        let ai = a[i];
        i += 1;
        c[i] = 0.5 * (ai - b);
        let t = (ai * b).sqrt();
        a[i] = 0.5 * (ai + b);
        b = t;
        twon *= 2.0;
    }
    let mut phi = twon * a[i] * u;
    while i > 0 {
        let t = c[i] * phi.sin() / a[i];
        phi = 0.5 * (t.asin() + phi);
        i -= 1;
    }
    let cn = phi.cos();
    // dn² = k'² + m·cn² (a sum of non-negative terms: no cancellation,
    // unlike Cephes' cn / cos(φ₁ − φ₀), which is 0/0 at u = K).
    (phi.sin(), cn, ((1.0 - m) + m * cn * cn).sqrt())
}

/// The pendulum θ'' = −ω0²·sin θ released from rest at θ(0) = θ0
/// (|θ0| < π), exactly: with k = sin(θ0/2), k' = cos(θ0/2), m = k² and
/// u = ω0·t,
///
/// sin(θ/2) = k·sn(K(m) − u; m) = k·cd(u; m),  cos(θ/2) = k'/dn(u; m),
///
/// so θ = 2·atan2(k·cn u, k') and θ' = −2·k·k'·ω0·sn u / dn u
/// (Lawden, Elliptic Functions and Applications, 5.2). Returns (θ, θ').
///
/// The energy θ'²/2 − ω0² cos θ equals −ω0² cos θ0 identically. NaN when
/// |θ0| ≥ π (the separatrix and beyond) or ω0² ≤ 0.
pub fn pendulum_exact(theta0: f64, omega0_sq: f64, t: f64) -> (f64, f64) {
    if theta0.abs() >= PI || omega0_sq.is_nan() || omega0_sq <= 0.0 || !theta0.is_finite() {
        return (f64::NAN, f64::NAN);
    }
    let w = omega0_sq.sqrt();
    let (k, kp) = (0.5 * theta0).sin_cos();
    let (sn, cn, dn) = ellipj(w * t, k * k);
    (2.0 * (k * cn).atan2(kp), -2.0 * k * kp * w * sn / dn)
}

/// The period 4K(k²)/ω0 of [`pendulum_exact`] (k = sin(θ0/2)); 2π/ω0 in
/// the small-amplitude limit. NaN when |θ0| ≥ π or ω0² ≤ 0.
pub fn pendulum_period(theta0: f64, omega0_sq: f64) -> f64 {
    if theta0.abs() >= PI || omega0_sq.is_nan() || omega0_sq <= 0.0 || !theta0.is_finite() {
        return f64::NAN;
    }
    let k = (0.5 * theta0).sin();
    4.0 * ellipk(k * k) / omega0_sq.sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;
    use qdot_exact::rng::SplitMix64;
    use std::f64::consts::FRAC_PI_2 as K0;

    #[test]
    fn ellipk_known_values() {
        assert_eq!(ellipk(0.0), K0);
        assert!((ellipk(0.5) - 1.854_074_677_301_371_9).abs() < 1e-15);
        // A&S Table 17.1 / Legendre: K(sin²(π/12))... use m = 0.9:
        // K(0.9) = 2.5780921133481733 (DLMF 19.2, mpmath).
        assert!((ellipk(0.9) - 2.578_092_113_348_173_3).abs() < 4e-15);
        // K(m) ~ ln(4/√(1−m)) as m → 1 (A&S 17.3.26).
        let m: f64 = 1.0 - 1e-12;
        let approx = (4.0 / (1.0 - m).sqrt()).ln();
        assert!((ellipk(m) - approx).abs() < 1e-10, "{}", ellipk(m) - approx);
        // Small m: K = π/2 (1 + m/4 + 9m²/64 + …).
        let m = 1e-6;
        assert!((ellipk(m) - K0 * (1.0 + m / 4.0 + 9.0 * m * m / 64.0)).abs() < 1e-17);
        assert!(ellipk(1.5).is_nan());
        assert_eq!(ellipk(1.0), f64::INFINITY);
    }

    #[test]
    fn ellipj_limits() {
        for &u in &[0.0, 0.3, -1.2, 2.5] {
            let (sn, cn, dn) = ellipj(u, 0.0);
            assert!((sn - f64::sin(u)).abs() < 1e-15);
            assert!((cn - f64::cos(u)).abs() < 1e-15);
            assert_eq!(dn, 1.0);
            // m → 1: sn → tanh, cn, dn → sech (A&S 16.15).
            let (sn, cn, dn) = ellipj(u, 1.0 - 1e-13);
            let sech = 1.0 / f64::cosh(u);
            assert!((sn - f64::tanh(u)).abs() < 1e-11, "{u} {sn}");
            assert!((cn - sech).abs() < 1e-11);
            assert!((dn - sech).abs() < 1e-11);
        }
        // The AGM branch near the m → 1 switch agrees with the expansion.
        let (a, b, c) = ellipj(0.7, 0.999_999_999_8);
        let sech = 1.0 / f64::cosh(0.7);
        assert!((a - f64::tanh(0.7)).abs() < 1e-9 && (b - sech).abs() < 1e-9);
        assert!((c - sech).abs() < 1e-9);
    }

    #[test]
    fn ellipj_quarter_period_and_known_value() {
        for &m in &[0.1, 0.5, 0.9, 0.99] {
            let k = ellipk(m);
            let (sn, cn, dn) = ellipj(k, m);
            assert!((sn - 1.0).abs() < 1e-15, "{m} {sn}");
            assert!(cn.abs() < 1e-14, "{m} {cn}");
            assert!((dn - (1.0 - m).sqrt()).abs() < 1e-14);
            // Half period: sn(2K) = 0, cn(2K) = −1.
            let (sn, cn, _) = ellipj(2.0 * k, m);
            assert!(sn.abs() < 1e-14 && (cn + 1.0).abs() < 1e-15);
        }
        // sn(K/2) = 1/√(1 + k') (A&S 16.5.2).
        for &m in &[0.3, 0.7] {
            let (sn, _, _) = ellipj(0.5 * ellipk(m), m);
            let kp = (1.0 - m).sqrt();
            assert!((sn - 1.0 / (1.0 + kp).sqrt()).abs() < 1e-15);
        }
    }

    #[test]
    fn ellipj_identities_and_derivative_at_random_points() {
        let mut s = SplitMix64::new(0x9E37_79B9_7F4A_7C15);
        for _ in 0..2000 {
            let m = s.unit() * 0.999;
            let u = (s.unit() - 0.5) * 20.0;
            let (sn, cn, dn) = ellipj(u, m);
            assert!((sn * sn + cn * cn - 1.0).abs() < 1e-14, "{u} {m}");
            assert!((dn * dn + m * sn * sn - 1.0).abs() < 1e-14, "{u} {m}");
            // d sn/du = cn·dn, d cn/du = −sn·dn by a 4th-order central
            // difference (error ~ h⁴ + eps/h ~ 1e-12).
            let h = 1e-3;
            let f = |x: f64| ellipj(x, m).0;
            let d =
                (f(u - 2.0 * h) - 8.0 * f(u - h) + 8.0 * f(u + h) - f(u + 2.0 * h)) / (12.0 * h);
            assert!((d - cn * dn).abs() < 1e-11, "{u} {m} {}", d - cn * dn);
            let g = |x: f64| ellipj(x, m).2;
            let d =
                (g(u - 2.0 * h) - 8.0 * g(u - h) + 8.0 * g(u + h) - g(u + 2.0 * h)) / (12.0 * h);
            assert!(
                (d + m * sn * cn).abs() < 1e-11,
                "{u} {m} {}",
                d + m * sn * cn
            );
            // Odd / even symmetry.
            let (sm, cm, dm) = ellipj(-u, m);
            assert!((sm + sn).abs() < 1e-14 && (cm - cn).abs() < 1e-14);
            assert!((dm - dn).abs() < 1e-14);
            // Addition of a quarter period: sn(u + K) = cd(u).
            let (sk, _, _) = ellipj(u + ellipk(m), m);
            assert!((sk - cn / dn).abs() < 1e-13, "{u} {m}");
        }
    }

    #[test]
    fn ellipj_outside_domain_is_nan() {
        assert!(ellipj(0.3, 1.0).0.is_nan());
        assert!(ellipj(0.3, -0.1).0.is_nan());
        assert!(ellipj(f64::INFINITY, 0.5).0.is_nan());
        assert!(pendulum_exact(PI, 1.0, 0.0).0.is_nan());
        assert!(pendulum_period(0.5, -1.0).is_nan());
    }

    #[test]
    fn pendulum_exact_solves_the_ode_and_conserves_energy() {
        let mut s = SplitMix64::new(7);
        for _ in 0..200 {
            let th0 = (s.unit() - 0.5) * 6.0; // |θ0| < 3
            let w2 = 0.5 + 4.0 * s.unit();
            let t = 30.0 * s.unit();
            let (th, thd) = pendulum_exact(th0, w2, t);
            let e0 = -w2 * th0.cos();
            assert!((0.5 * thd * thd - w2 * th.cos() - e0).abs() < 1e-12 * (1.0 + w2));
            // θ' and θ'' by central differences.
            let h = 1e-4;
            let f = |x: f64| pendulum_exact(th0, w2, x).0;
            let d1 =
                (f(t - 2.0 * h) - 8.0 * f(t - h) + 8.0 * f(t + h) - f(t + 2.0 * h)) / (12.0 * h);
            assert!((d1 - thd).abs() < 1e-8, "{th0} {w2} {t}: {}", d1 - thd);
            let d2 = (f(t + h) - 2.0 * th + f(t - h)) / (h * h);
            assert!((d2 + w2 * th.sin()).abs() < 1e-4, "{}", d2 + w2 * th.sin());
        }
        // Initial conditions.
        let (th, thd) = pendulum_exact(2.0, 3.0, 0.0);
        assert!((th - 2.0).abs() < 1e-15 && thd == 0.0);
    }

    #[test]
    fn pendulum_period_is_4k_over_omega() {
        for &(th0, w2) in &[(0.1, 1.0), (1.0, 2.0), (2.5, 0.7), (-3.0, 9.0)] {
            let p = pendulum_period(th0, w2);
            let k: f64 = f64::sin(0.5 * th0);
            assert!((p - 4.0 * ellipk(k * k) / f64::sqrt(w2)).abs() < 1e-15 * p);
            let (a, ad) = pendulum_exact(th0, w2, p);
            assert!((a - th0).abs() < 1e-12 && ad.abs() < 1e-11, "{a} {ad}");
            // Half period: θ = −θ0.
            let (a, ad) = pendulum_exact(th0, w2, 0.5 * p);
            assert!((a + th0).abs() < 1e-12 && ad.abs() < 1e-11);
            // Small amplitudes: T → 2π/ω0 (1 + θ0²/16).
        }
        let p = pendulum_period(1e-3, 4.0);
        assert!((p - PI * (1.0 + 1e-6 / 16.0)).abs() < 1e-12);
    }
}
