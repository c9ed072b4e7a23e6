//! The operator traits for [`Poly`] (`+ - * neg` and their assigning forms,
//! by value and by reference), `Sum`, `Product` and `From<Q>`.

use super::Poly;
use crate::num::Q;
use std::ops::{Add, AddAssign, Mul, MulAssign, Neg, Sub, SubAssign};

impl Neg for &Poly {
    type Output = Poly;
    fn neg(self) -> Poly {
        Poly::from_sorted(self.terms.iter().map(|(m, c)| (m.clone(), -c)).collect())
    }
}

impl Neg for Poly {
    type Output = Poly;
    fn neg(mut self) -> Poly {
        for t in self.terms.iter_mut() {
            t.1 = -std::mem::take(&mut t.1);
        }
        self
    }
}

impl Add<&Poly> for &Poly {
    type Output = Poly;
    fn add(self, rhs: &Poly) -> Poly {
        Poly::from_sorted(Poly::merge(&self.terms, &rhs.terms, false))
    }
}

impl Sub<&Poly> for &Poly {
    type Output = Poly;
    fn sub(self, rhs: &Poly) -> Poly {
        Poly::from_sorted(Poly::merge(&self.terms, &rhs.terms, true))
    }
}

impl Mul<&Poly> for &Poly {
    type Output = Poly;
    fn mul(self, rhs: &Poly) -> Poly {
        crate::cancel::check();
        self.mul_impl(rhs)
    }
}

impl Add<Poly> for Poly {
    type Output = Poly;
    fn add(mut self, rhs: Poly) -> Poly {
        if self.len() < rhs.len() {
            let mut r = rhs;
            r.merge_into(&self.terms, false);
            return r;
        }
        self.merge_into(&rhs.terms, false);
        self
    }
}

impl Add<&Poly> for Poly {
    type Output = Poly;
    fn add(mut self, rhs: &Poly) -> Poly {
        self.merge_into(&rhs.terms, false);
        self
    }
}

impl Add<Poly> for &Poly {
    type Output = Poly;
    fn add(self, mut rhs: Poly) -> Poly {
        rhs.merge_into(&self.terms, false);
        rhs
    }
}

impl Sub<Poly> for Poly {
    type Output = Poly;
    fn sub(mut self, rhs: Poly) -> Poly {
        self.merge_into(&rhs.terms, true);
        self
    }
}

impl Sub<&Poly> for Poly {
    type Output = Poly;
    fn sub(mut self, rhs: &Poly) -> Poly {
        self.merge_into(&rhs.terms, true);
        self
    }
}

impl Sub<Poly> for &Poly {
    type Output = Poly;
    fn sub(self, rhs: Poly) -> Poly {
        // self - rhs == -(rhs - self)
        let mut r = rhs;
        r.merge_into(&self.terms, true);
        -r
    }
}

impl Mul<Poly> for Poly {
    type Output = Poly;
    fn mul(self, rhs: Poly) -> Poly {
        self.mul_impl(&rhs)
    }
}

impl Mul<&Poly> for Poly {
    type Output = Poly;
    fn mul(self, rhs: &Poly) -> Poly {
        self.mul_impl(rhs)
    }
}

impl Mul<Poly> for &Poly {
    type Output = Poly;
    fn mul(self, rhs: Poly) -> Poly {
        self.mul_impl(&rhs)
    }
}

impl AddAssign<&Poly> for Poly {
    fn add_assign(&mut self, rhs: &Poly) {
        self.merge_into(&rhs.terms, false);
    }
}

impl AddAssign<Poly> for Poly {
    fn add_assign(&mut self, rhs: Poly) {
        if self.len() < rhs.len() {
            let mut r = rhs;
            r.merge_into(&self.terms, false);
            *self = r;
        } else {
            self.merge_into(&rhs.terms, false);
        }
    }
}

impl SubAssign<&Poly> for Poly {
    fn sub_assign(&mut self, rhs: &Poly) {
        self.merge_into(&rhs.terms, true);
    }
}

impl SubAssign<Poly> for Poly {
    fn sub_assign(&mut self, rhs: Poly) {
        self.merge_into(&rhs.terms, true);
    }
}

impl MulAssign<&Poly> for Poly {
    fn mul_assign(&mut self, rhs: &Poly) {
        *self = self.mul_impl(rhs);
    }
}

impl MulAssign<Poly> for Poly {
    fn mul_assign(&mut self, rhs: Poly) {
        *self = self.mul_impl(&rhs);
    }
}

// Sums collect every term and merge once: adding one by one is quadratic.
impl std::iter::Sum for Poly {
    fn sum<I: Iterator<Item = Poly>>(iter: I) -> Poly {
        let mut terms = Vec::new();
        for p in iter {
            terms.extend_from_slice(p.terms());
            crate::budget::check_product(terms.len(), 1);
        }
        Poly::from_terms(terms)
    }
}

impl<'a> std::iter::Sum<&'a Poly> for Poly {
    fn sum<I: Iterator<Item = &'a Poly>>(iter: I) -> Poly {
        let mut terms = Vec::new();
        for p in iter {
            terms.extend_from_slice(p.terms());
            crate::budget::check_product(terms.len(), 1);
        }
        Poly::from_terms(terms)
    }
}

impl std::iter::Product for Poly {
    fn product<I: Iterator<Item = Poly>>(iter: I) -> Poly {
        iter.fold(Poly::one(), |a, b| a * b)
    }
}

impl From<Q> for Poly {
    fn from(c: Q) -> Poly {
        Poly::constant(c)
    }
}
