//! Monomials: [`Mono`], a power product of variables as sorted `(variable,
//! exponent)` pairs, with its arithmetic and the lexicographic term order
//! that [`Poly`](super::Poly) keeps its terms in.

use super::Var;
use smallvec::SmallVec;
use std::cmp::Ordering;
use std::fmt;

/// A power product: `(variable, exponent)` pairs sorted by variable ascending,
/// exponents > 0. The empty product is the monomial `1`.
#[derive(Clone, PartialEq, Eq, Hash, Debug, Default)]
pub struct Mono(pub SmallVec<[(Var, u32); 4]>);

impl Mono {
    /// The monomial `1`.
    #[inline]
    pub fn one() -> Mono {
        Mono(SmallVec::new())
    }

    /// The monomial `v`.
    #[inline]
    pub fn var(v: Var) -> Mono {
        let mut s = SmallVec::new();
        s.push((v, 1));
        Mono(s)
    }

    /// The monomial `v^e` (`1` if `e == 0`).
    #[inline]
    pub fn var_pow(v: Var, e: u32) -> Mono {
        let mut s = SmallVec::new();
        if e > 0 {
            s.push((v, e));
        }
        Mono(s)
    }

    /// From arbitrary `(var, exp)` pairs: sorts, merges repeated variables and
    /// drops zero exponents.
    pub fn from_pairs<I: IntoIterator<Item = (Var, u32)>>(pairs: I) -> Mono {
        let mut v: SmallVec<[(Var, u32); 4]> = pairs.into_iter().filter(|p| p.1 > 0).collect();
        v.sort_unstable_by_key(|p| p.0);
        let mut out: SmallVec<[(Var, u32); 4]> = SmallVec::with_capacity(v.len());
        for (x, e) in v {
            match out.last_mut() {
                Some(last) if last.0 == x => last.1 = last.1.saturating_add(e),
                _ => out.push((x, e)),
            }
        }
        Mono(out)
    }

    /// The `(var, exp)` pairs.
    #[inline]
    pub fn pairs(&self) -> &[(Var, u32)] {
        &self.0
    }

    /// `self == 1`.
    #[inline]
    pub fn is_one(&self) -> bool {
        self.0.is_empty()
    }

    /// Exponent of `v`.
    #[inline]
    pub fn degree(&self, v: Var) -> u32 {
        for &(x, e) in self.0.iter() {
            if x == v {
                return e;
            }
            if x > v {
                break;
            }
        }
        0
    }

    /// Sum of exponents.
    #[inline]
    pub fn total_degree(&self) -> u32 {
        self.0.iter().map(|p| p.1).sum()
    }

    /// Variables present.
    pub fn vars(&self) -> impl Iterator<Item = Var> + '_ {
        self.0.iter().map(|p| p.0)
    }

    /// The product `self * other` (exponents saturate at `u32::MAX`).
    #[allow(clippy::should_implement_trait)]
    pub fn mul(&self, other: &Mono) -> Mono {
        if other.0.is_empty() {
            return self.clone();
        }
        if self.0.is_empty() {
            return other.clone();
        }
        let (a, b) = (&self.0, &other.0);
        let mut out: SmallVec<[(Var, u32); 4]> = SmallVec::with_capacity(a.len() + b.len());
        let (mut i, mut j) = (0, 0);
        while i < a.len() && j < b.len() {
            let (va, ea) = a[i];
            let (vb, eb) = b[j];
            match va.cmp(&vb) {
                Ordering::Less => {
                    out.push((va, ea));
                    i += 1;
                }
                Ordering::Greater => {
                    out.push((vb, eb));
                    j += 1;
                }
                Ordering::Equal => {
                    out.push((va, ea.saturating_add(eb)));
                    i += 1;
                    j += 1;
                }
            }
        }
        out.extend_from_slice(&a[i..]);
        out.extend_from_slice(&b[j..]);
        Mono(out)
    }

    /// `self / other` if `other` divides `self`.
    #[allow(clippy::should_implement_trait)]
    pub fn div(&self, other: &Mono) -> Option<Mono> {
        let (a, b) = (&self.0, &other.0);
        if b.len() > a.len() {
            return None;
        }
        let mut out: SmallVec<[(Var, u32); 4]> = SmallVec::with_capacity(a.len());
        let mut j = 0;
        for &(va, ea) in a.iter() {
            if j < b.len() && b[j].0 == va {
                let eb = b[j].1;
                if eb > ea {
                    return None;
                }
                if ea > eb {
                    out.push((va, ea - eb));
                }
                j += 1;
            } else if j < b.len() && b[j].0 < va {
                return None;
            } else {
                out.push((va, ea));
            }
        }
        if j < b.len() {
            return None;
        }
        Some(Mono(out))
    }

    /// `self` divides `other`.
    pub fn divides(&self, other: &Mono) -> bool {
        let (a, b) = (&self.0, &other.0);
        let mut j = 0;
        for &(va, ea) in a.iter() {
            while j < b.len() && b[j].0 < va {
                j += 1;
            }
            if j >= b.len() || b[j].0 != va || b[j].1 < ea {
                return false;
            }
            j += 1;
        }
        true
    }

    /// Greatest common divisor (minimum exponents).
    pub fn gcd(&self, other: &Mono) -> Mono {
        let (a, b) = (&self.0, &other.0);
        let mut out: SmallVec<[(Var, u32); 4]> = SmallVec::new();
        let (mut i, mut j) = (0, 0);
        while i < a.len() && j < b.len() {
            match a[i].0.cmp(&b[j].0) {
                Ordering::Less => i += 1,
                Ordering::Greater => j += 1,
                Ordering::Equal => {
                    out.push((a[i].0, a[i].1.min(b[j].1)));
                    i += 1;
                    j += 1;
                }
            }
        }
        Mono(out)
    }

    /// Least common multiple (maximum exponents).
    pub fn lcm(&self, other: &Mono) -> Mono {
        let (a, b) = (&self.0, &other.0);
        let mut out: SmallVec<[(Var, u32); 4]> = SmallVec::with_capacity(a.len() + b.len());
        let (mut i, mut j) = (0, 0);
        while i < a.len() && j < b.len() {
            match a[i].0.cmp(&b[j].0) {
                Ordering::Less => {
                    out.push(a[i]);
                    i += 1;
                }
                Ordering::Greater => {
                    out.push(b[j]);
                    j += 1;
                }
                Ordering::Equal => {
                    out.push((a[i].0, a[i].1.max(b[j].1)));
                    i += 1;
                    j += 1;
                }
            }
        }
        out.extend_from_slice(&a[i..]);
        out.extend_from_slice(&b[j..]);
        Mono(out)
    }

    /// `self^e` (exponents saturate).
    pub fn pow(&self, e: u32) -> Mono {
        if e == 0 {
            return Mono::one();
        }
        Mono(
            self.0
                .iter()
                .map(|&(v, x)| (v, x.saturating_mul(e)))
                .collect(),
        )
    }

    /// `self` with variable `v` removed.
    pub fn without(&self, v: Var) -> Mono {
        Mono(self.0.iter().copied().filter(|p| p.0 != v).collect())
    }

    /// Splits into (part in `set`, part not in `set`); `set` sorted.
    pub(super) fn split_by(&self, set: &[Var]) -> (Mono, Mono) {
        let mut a = SmallVec::new();
        let mut b = SmallVec::new();
        for &p in self.0.iter() {
            if set.binary_search(&p.0).is_ok() {
                a.push(p);
            } else {
                b.push(p);
            }
        }
        (Mono(a), Mono(b))
    }
}

/// Greatest common divisor of two monomials.
pub fn mono_gcd(a: &Mono, b: &Mono) -> Mono {
    a.gcd(b)
}

impl Ord for Mono {
    /// Lexicographic, smallest variable id most significant.
    #[inline]
    fn cmp(&self, other: &Mono) -> Ordering {
        let (a, b) = (&self.0, &other.0);
        let n = a.len().min(b.len());
        for i in 0..n {
            let (va, ea) = a[i];
            let (vb, eb) = b[i];
            if va != vb {
                return if va < vb {
                    Ordering::Greater
                } else {
                    Ordering::Less
                };
            }
            if ea != eb {
                return ea.cmp(&eb);
            }
        }
        a.len().cmp(&b.len())
    }
}

impl PartialOrd for Mono {
    #[inline]
    fn partial_cmp(&self, other: &Mono) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl fmt::Display for Mono {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.0.is_empty() {
            return write!(f, "1");
        }
        for (i, &(v, e)) in self.0.iter().enumerate() {
            if i > 0 {
                write!(f, "*")?;
            }
            if e == 1 {
                write!(f, "x{v}")?;
            } else {
                write!(f, "x{v}^{e}")?;
            }
        }
        Ok(())
    }
}
