//! Forms of an expression in the parameters alone, as a condition on them
//! is written (`cos(lat)·(C·s + (C − A)·Ω·cos(lat)) > 0`): its
//! representations modulo sin² + cos² = 1, from which the condition's
//! factors are read, and a sum printed with its terms collected by their
//! sines and cosines (a condition has no coordinates to collect by).

use super::atom::{self, Atom};
use super::print::{self, Style};
use super::{collected_by, fourier, group, ops_of, MAX_TRIG_EXPANSION};
use crate::expr::Expr;
use crate::poly::{Mono, Poly, Var};

/// `p` under each reduction modulo sin² + cos² = 1 the printers consider:
/// the canonical form first (cos² → 1 − sin²), then each choice of angles
/// whose sin² is written 1 − cos² (every subset of up to three angles;
/// beyond, all of them), each within [`MAX_TRIG_EXPANSION`] terms.
pub fn trig_representations(p: &Poly) -> Vec<Poly> {
    let angles = fourier::angles(&[p]);
    let n = angles.len();
    let masks: Vec<u32> = match n {
        0 => Vec::new(),
        1..=3 => (1..(1u32 << n)).collect(),
        _ => vec![(1u32 << n.min(31)) - 1],
    };
    let mut out = vec![p.clone()];
    for mask in masks {
        if fourier::cos_reduced_size(p, &angles, mask) <= MAX_TRIG_EXPANSION {
            out.push(fourier::cos_reduced(p, &angles, mask));
        }
    }
    out
}

/// Whether `v` is a sine or a cosine.
fn is_trig(v: Var) -> bool {
    matches!(atom::atom(v), Atom::Sin(_) | Atom::Cos(_))
}

/// `p` in Unicode with its terms collected by their monomial in sines and
/// cosines where that is shorter: C·s + (C − A)·Ω·cos(lat), not
/// C·s + C·Ω·cos(lat) − A·Ω·cos(lat). `p` is taken as it is (no other
/// reduction modulo sin² + cos² = 1 is searched).
pub fn unicode_collected(p: &Poly) -> String {
    match collected_by(p, is_trig) {
        Some(c) if ops_of(&c) < ops_of(p) => {
            print::render_parts(&positive_groups(&c), &Poly::one(), Style::Unicode)
        }
        _ => print::unicode(&Expr::from_poly(p.clone())),
    }
}

/// `p` with each negative term −c·(a − b) written +c·(b − a), a sum in
/// parentheses taking the sign: C·s + (C − A)·Ω·cos(lat).
fn positive_groups(p: &Poly) -> Poly {
    let terms = p.terms().iter().map(|(m, c)| {
        let sum = m
            .pairs()
            .iter()
            .position(|&(v, e)| e == 1 && matches!(atom::atom(v), Atom::Group(_)));
        let (Some(i), true) = (sum, c.is_negative()) else {
            return (m.clone(), c.clone());
        };
        let Atom::Group(g) = atom::atom(m.pairs()[i].0) else {
            return (m.clone(), c.clone());
        };
        let mut pairs = m.pairs().to_vec();
        pairs[i] = (group(-&*g), 1);
        (Mono::from_pairs(pairs), -c.clone())
    });
    Poly::from_terms(terms.collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::expr::func;

    #[test]
    fn a_sum_is_collected_by_its_cosines() {
        let (c, a, s, w) = (
            Expr::param("C"),
            Expr::param("A"),
            Expr::param("s"),
            Expr::param("W"),
        );
        let cos = func::cos(&Expr::param("lat"));
        let e = c.mul(&s).add(&c.sub(&a).mul(&w).mul(&cos));
        assert_eq!(unicode_collected(e.num()), "W·(C − A)·cos(lat) + C·s");
    }

    #[test]
    fn sine_squares_can_be_written_as_cosines() {
        // cos²(u) is canonically 1 − sin²(u); the other reduction gives it back
        let cos = func::cos(&Expr::param("u"));
        let e = cos.mul(&cos);
        let reps = trig_representations(e.num());
        assert_eq!(reps.len(), 2);
        assert_eq!(print::unicode(&Expr::from_poly(reps[0].clone())), "cos²(u)");
        assert!(reps[1].len() == 1, "{:?}", reps[1]);
    }
}
