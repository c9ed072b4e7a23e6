//! Certified digits of a numeric root of one equation f(x) = 0.
//!
//! A root found by Newton's method is only a point where |f| is small. It
//! is *certified* here by a sign change: two points lo < hi where f has
//! opposite signs, each sign trusted only where |f| exceeds a bound on the
//! rounding error of its evaluation (estimated from evaluating f at points
//! one unit in the last place apart). By continuity f has a root in
//! [lo, hi]; the interval is narrowed by bisection, and only the digits
//! lo and hi share are printed. Without a certified sign change (a root of
//! even multiplicity, or one too close to the rounding noise) the root is
//! reported as not certified.

/// A root enclosed in `[lo, hi]` with a sign change of f.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Enclosure {
    /// The lower end: f has one sign here.
    pub lo: f64,
    /// The upper end: f has the opposite sign here.
    pub hi: f64,
}

impl Enclosure {
    /// The digits `lo` and `hi` share, both rounded at the same power of
    /// ten (so 9.99999…e-5 and 1.00000…e-4 share 1.00000e-4):
    /// `0.7390851332`, `1.000000000e-12`.
    pub fn digits(&self) -> String {
        let big = self.lo.abs().max(self.hi.abs());
        // a root at 0: certified to the width of the enclosure
        if big == 0.0 || (self.lo <= 0.0 && self.hi >= 0.0 && big < 1e-12) {
            return "0".into();
        }
        let scale = 10f64.powi(big.log10().floor() as i32);
        for d in (1..=15).rev() {
            let a = format!("{:.*}", d - 1, self.lo / scale);
            if a == format!("{:.*}", d - 1, self.hi / scale) {
                let v: f64 = a.parse().unwrap_or(0.0); // ok: formatted just above
                return significant(v * scale, d);
            }
        }
        // not even one digit in common (an enclosure across zero)
        format!(
            "in [{}, {}]",
            significant(self.lo, 3),
            significant(self.hi, 3)
        )
    }
}

/// `x` to `d` significant digits: fixed notation from 10⁻⁴ to 10⁶,
/// scientific outside.
pub fn significant(x: f64, d: usize) -> String {
    if x == 0.0 {
        return "0".into();
    }
    let e = x.abs().log10().floor() as i32;
    if (-4..6).contains(&e) {
        let decimals = (d as i32 - 1 - e).max(0) as usize;
        format!("{x:.decimals$}")
    } else {
        format!("{x:.*e}", d.saturating_sub(1))
    }
}

/// The sign of f(x) if it is certain beyond the rounding noise of f near
/// x (the spread of f over a few neighbouring doubles, times a margin).
fn sure_sign(f: &dyn Fn(f64) -> Option<f64>, x: f64) -> Option<f64> {
    let v = f(x)?;
    let mut noise = 0.0f64;
    let mut y = x;
    for _ in 0..4 {
        y = next_up(y);
        noise = noise.max((f(y)? - v).abs());
    }
    (v.abs() > 16.0 * noise && v != 0.0).then_some(v.signum())
}

fn next_up(x: f64) -> f64 {
    if x == 0.0 {
        return f64::from_bits(1);
    }
    let b = x.to_bits();
    f64::from_bits(if x > 0.0 { b + 1 } else { b - 1 })
}

/// Enclose the root of f near `x` by a certified sign change, searching
/// outward from a width of 10⁻¹⁰·(1 + |x|), then narrow it by bisection to
/// the doubles' resolution. `None` when no sign change is found.
pub fn enclose(f: &dyn Fn(f64) -> Option<f64>, x: f64) -> Option<Enclosure> {
    let mut h = 1e-13 * (1.0 + x.abs());
    let (mut lo, mut hi, mut slo) = (x, x, 0.0);
    let mut found = false;
    for _ in 0..40 {
        lo = x - h;
        hi = x + h;
        if let (Some(a), Some(b)) = (sure_sign(f, lo), sure_sign(f, hi)) {
            if a != b {
                slo = a;
                found = true;
                break;
            }
        }
        h *= 4.0;
        if h > 1e-3 * (1.0 + x.abs()) {
            break;
        }
    }
    if !found {
        return None;
    }
    for _ in 0..400 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        // the midpoint, else a quarter point whose sign is sure (near the
        // root the signs drown in the rounding noise)
        let probe = [mid, 0.5 * (lo + mid), 0.5 * (mid + hi)]
            .into_iter()
            .find_map(|p| sure_sign(f, p).map(|s| (p, s)));
        match probe {
            Some((p, s)) if s == slo => lo = p,
            Some((p, _)) => hi = p,
            None => break, // lo and hi still enclose the root
        }
    }
    Some(Enclosure { lo, hi })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_root_of_x_minus_cos_x_is_certified_to_its_digits() {
        let f = |x: f64| Some(x - x.cos());
        let e = enclose(&f, 0.739).expect("a sign change");
        assert!(
            e.lo <= 0.739_085_133_215_160_6 && 0.739_085_133_215_160_6 <= e.hi,
            "{e:?}"
        );
        let d = e.digits();
        assert!(d.starts_with("0.73908513321"), "{d}");
    }

    #[test]
    fn a_tiny_root_keeps_its_significant_digits() {
        // k·x − ε·cos x with ε = 1e-12: the root is 1e-12·(1 − …)
        let f = |x: f64| Some(x - 1e-12 * x.cos());
        let d = enclose(&f, 1e-12).expect("a sign change").digits();
        assert!(d.starts_with("1.0000000000") && d.ends_with("e-12"), "{d}");
    }

    #[test]
    fn an_enclosure_across_a_power_of_ten_shares_its_digits() {
        let e = Enclosure {
            lo: 9.999_999_999_999_9e-5,
            hi: 1.000_000_000_000_1e-4,
        };
        assert_eq!(e.digits(), "0.0001000000000000");
    }

    #[test]
    fn a_double_root_has_no_sign_change() {
        let f = |x: f64| Some((x - 1.0) * (x - 1.0));
        assert_eq!(enclose(&f, 1.0), None);
    }

    #[test]
    fn significant_digits() {
        assert_eq!(significant(0.7390851332, 4), "0.7391");
        assert_eq!(significant(-1.2345678, 5), "-1.2346");
        assert_eq!(significant(1e-12, 3), "1.00e-12");
        assert_eq!(significant(123456789.0, 3), "1.23e8");
    }
}
