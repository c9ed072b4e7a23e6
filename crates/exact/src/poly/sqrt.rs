//! The square root of a polynomial that is a perfect square.

use super::{Mono, Poly};
use crate::num::Q;

impl Poly {
    /// q with q² = self, when self is the square of a polynomial with
    /// rational coefficients (q's leading term positive); `None` otherwise.
    /// Term by term from the leading one, as for integers: each step's
    /// remainder d − q² gives q's next term, and the leading term decides
    /// fast when it is not a square.
    pub fn exact_sqrt(&self) -> Option<Poly> {
        let d = self;
        if d.is_zero() {
            return Some(Poly::zero());
        }
        let lead = |p: &Poly| p.terms().iter().max_by(|a, b| a.0.cmp(&b.0)).cloned();
        let (m, c) = lead(d)?;
        if c.is_negative() || m.0.iter().any(|&(_, e)| e % 2 == 1) {
            return None;
        }
        let (n, dn) = (c.numer(), c.denom());
        let (rn, rd) = (n.sqrt(), dn.sqrt());
        if &rn * &rn != n || &rd * &rd != dn {
            return None;
        }
        let half = Mono(m.0.iter().map(|&(v, e)| (v, e / 2)).collect());
        let sc = Q::from_bigint(rn).checked_div(&Q::from_bigint(rd))?;
        let two_sc = &sc * &Q::from_i64(2);
        let mut p = Poly::monomial(half.clone(), sc);
        for _ in 0..=d.len() + 1 {
            let r = d - &(&p * &p);
            if r.is_zero() {
                return Some(p);
            }
            let (rm, rc) = lead(&r)?;
            let tm = rm.div(&half)?;
            if tm >= half {
                return None;
            }
            p = &p + &Poly::monomial(tm, rc.checked_div(&two_sc)?);
        }
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::poly::Var;

    fn p(terms: &[(&[(Var, u32)], i64)]) -> Poly {
        Poly::from_terms(
            terms
                .iter()
                .map(|(m, c)| (Mono::from_pairs(m.iter().copied()), Q::from_i64(*c)))
                .collect(),
        )
    }

    #[test]
    fn perfect_squares_have_their_root_and_others_none() {
        let (a, b) = (4, 8);
        // (a − 2b)² = a² − 4ab + 4b²
        let sq = p(&[(&[(a, 2)], 1), (&[(a, 1), (b, 1)], -4), (&[(b, 2)], 4)]);
        let q = sq.exact_sqrt().expect("a square");
        assert_eq!(&q * &q, sq);
        // a² + b² is not a square; nor is −a², nor a³
        assert_eq!(p(&[(&[(a, 2)], 1), (&[(b, 2)], 1)]).exact_sqrt(), None);
        assert_eq!(p(&[(&[(a, 2)], -1)]).exact_sqrt(), None);
        assert_eq!(p(&[(&[(a, 3)], 1)]).exact_sqrt(), None);
        // 9/4·a²
        let r = Poly::monomial(Mono::from_pairs([(a, 2)]), Q::new(9, 4).expect("q"));
        let q = r.exact_sqrt().expect("a square");
        assert_eq!(
            q,
            Poly::monomial(Mono::from_pairs([(a, 1)]), Q::new(3, 2).expect("q"))
        );
    }
}
