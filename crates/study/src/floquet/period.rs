//! The period of linearized coefficients, from their time dependence:
//! every t must stand in a sine or cosine of ω·t + φ (directly, or inside
//! another function's argument); the frequencies must be commensurate, and
//! the period is 2π/Ω for their greatest common divisor Ω. Exact.

use crate::diag::{Diagnostic, ErrorKind};
use crate::expr::atom::{self, Atom};
use crate::expr::Expr;
use crate::poly::Var;
use qdot_exact::num::Q;

const HINT: &str = "give the period: --period T";

/// The fundamental angular frequency Ω of `coefficients` (T = 2π/|Ω|).
pub fn fundamental(coefficients: &[&Expr]) -> Result<Expr, Diagnostic> {
    let t = atom::time();
    let mut omegas: Vec<Expr> = Vec::new();
    for e in coefficients {
        frequencies(e, t, &mut omegas)?;
    }
    let Some(first) = omegas.first().cloned() else {
        return Err(not_periodic(
            "the coefficients depend on t, but not through sin or cos",
        ));
    };
    // Ω = first·gcd(ratios to first)
    let mut g = Q::from_i64(1);
    for w in &omegas[1..] {
        let ratio = w.div(&first).ok().and_then(|r| r.as_rational());
        let Some(r) = ratio else {
            return Err(Diagnostic::global(format!(
                "the coefficients oscillate at the angular frequencies {} and {}, whose ratio is not a rational number: they have no common period",
                crate::expr::print::unicode(&first),
                crate::expr::print::unicode(w)
            ))
            .with_hint(HINT)
            .with_kind(ErrorKind::bad_option("--period")));
        };
        g = g.gcd(&r);
    }
    Ok(first.scale(&g))
}

fn not_periodic(what: &str) -> Diagnostic {
    Diagnostic::global(format!(
        "the linearized coefficients are not periodic in t: {what}"
    ))
    .with_hint("Floquet theory needs coefficients periodic in t (sin and cos of w*t, or a periodic --function); give --period T if they are periodic in another way").with_kind(ErrorKind::Unsupported)
}

/// Push the angular frequency ω of every sin(ω·t + φ) and cos(ω·t + φ) in
/// `e` (ω free of t) to `out`, once each; an error for t anywhere else.
fn frequencies(e: &Expr, t: Var, out: &mut Vec<Expr>) -> Result<(), Diagnostic> {
    for v in e.vars() {
        if v == t {
            return Err(not_periodic(&format!(
                "t stands outside a sine or cosine in {}",
                crate::expr::print::unicode(e)
            )));
        }
        let a = atom::atom(v);
        let Some(arg) = a.argument() else {
            continue;
        };
        if !arg.depends_on(t) {
            continue;
        }
        if matches!(a, Atom::Sin(_) | Atom::Cos(_)) {
            let omega = arg.diff(t);
            if omega.depends_on(t) {
                return Err(not_periodic(&format!(
                    "the angle {} does not grow linearly with t",
                    crate::expr::print::unicode(arg)
                )));
            }
            let omega = if omega
                .num()
                .terms()
                .first()
                .is_some_and(|(_, c)| c.is_negative())
            {
                omega.neg()
            } else {
                omega
            };
            if !out
                .iter()
                .any(|w| w.equals(&omega) || w.equals(&omega.neg()))
            {
                out.push(omega);
            }
        } else {
            frequencies(arg, t, out)?;
        }
    }
    Ok(())
}
