//! Closed forms evaluated at the `--set` values, beside the formulas of
//! `modes` and `response`: only the digits the evaluation certifies, at
//! most 6 significant ones.
//!
//! The value is computed in floating point; its rounding noise is
//! estimated as `certify` estimates a function's, from evaluations with
//! each parameter's value moved by a unit or two in the last place (a
//! cancellation, such as a bandwidth's difference of close terms, shows
//! as a large spread). The digits printed are those the ends of value ± 16 × noise
//! share.

use crate::expr::atom::Atom;
use crate::expr::Expr;
use crate::solve::certify::significant;
use crate::solve::equilibrium::Values;

/// The most significant digits printed.
const DIGITS: usize = 6;

/// A value known to lie in `[lo, hi]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Enclosed {
    lo: f64,
    hi: f64,
}

impl Enclosed {
    /// √ of the value (monotone), when it is not negative.
    pub fn sqrt(self) -> Option<Enclosed> {
        (self.lo >= 0.0).then(|| Enclosed {
            lo: self.lo.sqrt(),
            hi: self.hi.sqrt(),
        })
    }

    /// The value divided by 2π (a frequency in Hz from rad/s).
    pub fn per_turn(self) -> Enclosed {
        let turn = 2.0 * std::f64::consts::PI;
        Enclosed {
            lo: self.lo / turn * (1.0 - 4.0 * f64::EPSILON),
            hi: self.hi / turn * (1.0 + 4.0 * f64::EPSILON),
        }
    }

    /// The digits `lo` and `hi` share (at most [`DIGITS`]), both rounded
    /// at one power of ten; `≈ 0` when no digit is certain.
    pub fn text(self) -> String {
        let big = self.lo.abs().max(self.hi.abs());
        if big == 0.0 {
            return "0".into();
        }
        let scale = 10f64.powi(big.log10().floor() as i32);
        for d in (1..=DIGITS).rev() {
            let a = format!("{:.*}", d - 1, self.lo / scale);
            if a == format!("{:.*}", d - 1, self.hi / scale) {
                let Ok(v) = a.parse::<f64>() else { break };
                return significant(v * scale, d).replace('-', "−");
            }
        }
        "≈ 0 (no digit certain)".into()
    }
}

/// `e` at the parameter values `set`, enclosed; `None` when a value is
/// missing or the result is not finite.
pub(crate) fn evaluate(e: &Expr, set: &Values) -> Option<Enclosed> {
    if set.is_empty() {
        return None;
    }
    let at = |bump: &dyn Fn(usize) -> f64| {
        let names: Vec<&String> = set.keys().collect();
        e.eval_f64(&|a: &Atom| match a {
            Atom::Param(n) => {
                let i = names.iter().position(|k| k.as_str() == &**n)?;
                set.get(&**n).map(|v| v * (1.0 + bump(i) * f64::EPSILON))
            }
            _ => None,
        })
        .filter(|v| v.is_finite())
    };
    let v = at(&|_| 0.0)?;
    let mut noise = 0.0f64;
    // each value moved alone by one and two ulps either way (moved
    // together, a homogeneous form's changes could cancel)
    for i in 0..set.len() {
        for bump in [1.0, -1.0, 2.0, -2.0] {
            let moved = at(&|j| if j == i { bump } else { 0.0 })?;
            noise = noise.max((moved - v).abs());
        }
    }
    let width = 16.0 * noise + 8.0 * f64::EPSILON * v.abs();
    Some(Enclosed {
        lo: v - width,
        hi: v + width,
    })
}

/// `ωᵢ² = …, ωᵢ = … rad/s, fᵢ = … Hz` for the frequency squared `w2` at
/// `set` (`sub`: the subscript, `₁`); only ω² when it is negative.
pub(crate) fn frequency(sub: &str, w2: &Expr, set: &Values) -> Option<String> {
    let v = evaluate(w2, set)?;
    let mut out = format!("ω{sub}² = {}", v.text());
    if let Some(w) = v.sqrt() {
        out.push_str(&format!(
            ", ω{sub} = {} rad/s, f{sub} = {} Hz",
            w.text(),
            w.per_turn().text()
        ));
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shared_digits_at_most_six() {
        let t = |lo, hi| Enclosed { lo, hi }.text();
        assert_eq!(t(0.16666666666, 0.16666666667), "0.166667");
        assert_eq!(t(0.1661, 0.1669), "0.17");
        assert_eq!(t(-2.5, -2.5), "−2.50000");
        assert_eq!(t(-1e-3, 1e-3), "≈ 0 (no digit certain)");
    }
}
