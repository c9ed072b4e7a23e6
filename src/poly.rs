//! Sparse multivariate polynomials over the exact rationals [`Q`].
//!
//! A [`Poly`] is a list of `(Mono, Q)` terms kept sorted in descending
//! lexicographic order (smallest variable id most significant), with no zero
//! coefficients and no duplicate monomials, so structural equality is value
//! equality.
//!
//! Multiplication and exact division temporarily pack monomials into `u128`
//! keys (one bit field per variable, smallest variable in the most significant
//! bits, so integer order is the monomial order) whenever the exponents fit;
//! otherwise they fall back to working on [`Mono`] directly.
//!
//! The GCD ([`Poly::gcd`]) works over Z after clearing denominators and uses
//! a cascade of reductions (monomial content, variables present in only one
//! argument, variables that modular images prove absent from the GCD, trial
//! division), then a heuristic GCD (GCDHEU) for few variables, and a recursive
//! subresultant PRS as the always-correct fallback. Every candidate is verified
//! by exact division and certified against modular degree bounds.

use crate::num::Q;
use num_bigint::BigInt;
use num_integer::Integer;
use num_traits::{Signed, ToPrimitive, Zero};
use rustc_hash::FxHashMap;
use smallvec::SmallVec;
use std::cell::Cell;
use std::cmp::Ordering;
use std::collections::hash_map::Entry;
use std::collections::BinaryHeap;
use std::fmt;
use std::hash::Hash;
use std::ops::{Add, AddAssign, Mul, MulAssign, Neg, Sub, SubAssign};

/// A variable id.
pub type Var = u32;

/// A power product: `(variable, exponent)` pairs sorted by variable ascending,
/// exponents > 0. The empty product is the monomial `1`.
#[derive(Clone, PartialEq, Eq, Hash, Debug, Default)]
pub struct Mono(pub SmallVec<[(Var, u32); 4]>);

/// A polynomial: terms sorted by monomial in DESCENDING lexicographic order,
/// no zero coefficients, no duplicate monomials. The leading term is `terms[0]`.
#[derive(Clone, PartialEq, Eq, Hash, Debug, Default)]
pub struct Poly {
    terms: Vec<(Mono, Q)>,
}

static ZERO_Q: Q = Q::zero();

// ===========================================================================
// Mono
// ===========================================================================

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
    fn split_by(&self, set: &[Var]) -> (Mono, Mono) {
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

// ===========================================================================
// monomial encodings (packed u128 keys or plain Mono)
// ===========================================================================

/// Sorted `(var, max exponent)` list.
type DegList = SmallVec<[(Var, u32); 8]>;

fn merge_deglists(a: &DegList, b: &DegList, sum: bool) -> DegList {
    let mut out = DegList::with_capacity(a.len() + b.len());
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
                let e = if sum {
                    a[i].1.saturating_add(b[j].1)
                } else {
                    a[i].1.max(b[j].1)
                };
                out.push((a[i].0, e));
                i += 1;
                j += 1;
            }
        }
    }
    out.extend_from_slice(&a[i..]);
    out.extend_from_slice(&b[j..]);
    out
}

/// How monomials are represented inside multiplication and division.
trait Repr {
    type K: Clone + Ord + Hash + Eq;
    fn enc(&self, m: &Mono) -> Option<Self::K>;
    fn dec(&self, k: &Self::K) -> Mono;
    fn mul(&self, a: &Self::K, b: &Self::K) -> Self::K;
    /// `a / b` if divisible and every exponent of the quotient is within the
    /// bounds this representation was built with.
    fn div_bounded(&self, a: &Self::K, b: &Self::K) -> Option<Self::K>;
}

/// Packed `u128` keys: one bit field per variable, smallest variable highest.
struct Packed {
    vars: SmallVec<[Var; 16]>,
    shifts: SmallVec<[u32; 16]>,
    masks: SmallVec<[u128; 16]>,
    /// quotient exponent bounds (for `div_bounded`)
    qbound: SmallVec<[u32; 16]>,
}

impl Packed {
    /// Fields wide enough for the given maximum exponents; `qb` gives the
    /// quotient bounds per variable (same order), if division is needed.
    fn new(maxdeg: &DegList, qb: Option<&[u32]>) -> Option<Packed> {
        let mut total = 0u32;
        let mut widths: SmallVec<[u32; 16]> = SmallVec::new();
        for &(_, d) in maxdeg.iter() {
            let w = (32 - d.leading_zeros()).max(1);
            total += w;
            if total > 128 {
                return None;
            }
            widths.push(w);
        }
        let mut shifts = SmallVec::new();
        let mut masks = SmallVec::new();
        let mut s = total;
        for &w in widths.iter() {
            s -= w;
            shifts.push(s);
            masks.push((1u128 << w) - 1);
        }
        Some(Packed {
            vars: maxdeg.iter().map(|p| p.0).collect(),
            shifts,
            masks,
            qbound: match qb {
                Some(q) => q.iter().copied().collect(),
                None => SmallVec::new(),
            },
        })
    }
}

impl Repr for Packed {
    type K = u128;

    #[inline]
    fn enc(&self, m: &Mono) -> Option<u128> {
        let mut k = 0u128;
        let mut j = 0;
        for &(v, e) in m.0.iter() {
            while j < self.vars.len() && self.vars[j] < v {
                j += 1;
            }
            if j >= self.vars.len() || self.vars[j] != v || (e as u128) > self.masks[j] {
                return None;
            }
            k |= (e as u128) << self.shifts[j];
        }
        Some(k)
    }

    #[inline]
    fn dec(&self, k: &u128) -> Mono {
        let mut out = SmallVec::new();
        for j in 0..self.vars.len() {
            let e = (k >> self.shifts[j]) & self.masks[j];
            if e != 0 {
                out.push((self.vars[j], e as u32));
            }
        }
        Mono(out)
    }

    #[inline]
    fn mul(&self, a: &u128, b: &u128) -> u128 {
        a + b
    }

    #[inline]
    fn div_bounded(&self, a: &u128, b: &u128) -> Option<u128> {
        for j in 0..self.vars.len() {
            let ea = (a >> self.shifts[j]) & self.masks[j];
            let eb = (b >> self.shifts[j]) & self.masks[j];
            if ea < eb || (ea - eb) > self.qbound[j] as u128 {
                return None;
            }
        }
        Some(a - b)
    }
}

/// Plain monomials (fallback when exponents do not pack).
struct Plain {
    qbound: DegList,
}

impl Repr for Plain {
    type K = Mono;

    #[inline]
    fn enc(&self, m: &Mono) -> Option<Mono> {
        Some(m.clone())
    }

    #[inline]
    fn dec(&self, k: &Mono) -> Mono {
        k.clone()
    }

    #[inline]
    fn mul(&self, a: &Mono, b: &Mono) -> Mono {
        a.mul(b)
    }

    fn div_bounded(&self, a: &Mono, b: &Mono) -> Option<Mono> {
        let q = a.div(b)?;
        let mut j = 0;
        for &(v, e) in q.0.iter() {
            while j < self.qbound.len() && self.qbound[j].0 < v {
                j += 1;
            }
            if j >= self.qbound.len() || self.qbound[j].0 != v || e > self.qbound[j].1 {
                return None;
            }
        }
        Some(q)
    }
}

/// Hash-accumulated product of two term lists (both non-empty).
fn mul_with<R: Repr>(r: &R, a: &[(Mono, Q)], b: &[(Mono, Q)]) -> Option<Vec<(Mono, Q)>> {
    let ka: Vec<R::K> = a.iter().map(|t| r.enc(&t.0)).collect::<Option<_>>()?;
    let kb: Vec<R::K> = b.iter().map(|t| r.enc(&t.0)).collect::<Option<_>>()?;
    let cap = (a.len() * b.len()).min(1 << 16);
    let mut index: FxHashMap<R::K, usize> = FxHashMap::default();
    index.reserve(cap);
    let mut acc: Vec<(R::K, Q)> = Vec::with_capacity(cap);
    for (i, (_, ca)) in a.iter().enumerate() {
        for (j, (_, cb)) in b.iter().enumerate() {
            let k = r.mul(&ka[i], &kb[j]);
            let c = ca * cb;
            match index.entry(k) {
                Entry::Occupied(e) => acc[*e.get()].1 += c,
                Entry::Vacant(e) => {
                    let k = e.key().clone();
                    e.insert(acc.len());
                    acc.push((k, c));
                }
            }
        }
    }
    drop(index);
    acc.retain(|t| !t.1.is_zero());
    acc.sort_unstable_by(|x, y| y.0.cmp(&x.0));
    Some(acc.into_iter().map(|(k, c)| (r.dec(&k), c)).collect())
}

/// Exact division by heap/hash remainder tracking. `Some(None)`: not exact;
/// `None`: could not encode.
fn div_with<R: Repr>(r: &R, a: &[(Mono, Q)], d: &[(Mono, Q)]) -> Option<Option<Vec<(Mono, Q)>>> {
    let kd: Vec<(R::K, &Q)> = d
        .iter()
        .map(|t| r.enc(&t.0).map(|k| (k, &t.1)))
        .collect::<Option<_>>()?;
    let mut rem: FxHashMap<R::K, Q> = FxHashMap::default();
    rem.reserve(a.len() * 2);
    let mut heap: BinaryHeap<R::K> = BinaryHeap::with_capacity(a.len() * 2);
    for (m, c) in a {
        let k = r.enc(m)?;
        heap.push(k.clone());
        rem.insert(k, c.clone());
    }
    let (ld, lc) = (&kd[0].0, kd[0].1);
    let lc_inv = lc.recip()?;
    let mut q: Vec<(R::K, Q)> = Vec::new();
    while let Some(k) = heap.pop() {
        let c = match rem.remove(&k) {
            Some(c) if !c.is_zero() => c,
            _ => continue,
        };
        let t = match r.div_bounded(&k, ld) {
            Some(t) => t,
            None => return Some(None),
        };
        let tc = &c * &lc_inv;
        for (kdj, cdj) in kd[1..].iter() {
            let key = r.mul(&t, kdj);
            let p = &tc * *cdj;
            match rem.entry(key) {
                Entry::Occupied(mut e) => *e.get_mut() -= p,
                Entry::Vacant(e) => {
                    heap.push(e.key().clone());
                    e.insert(-p);
                }
            }
        }
        q.push((t, tc));
    }
    Some(Some(q.into_iter().map(|(k, c)| (r.dec(&k), c)).collect()))
}

// ===========================================================================
// Poly: construction and inspection
// ===========================================================================

impl Poly {
    /// The zero polynomial.
    #[inline]
    pub fn zero() -> Poly {
        Poly { terms: Vec::new() }
    }

    /// The constant 1.
    #[inline]
    pub fn one() -> Poly {
        Poly::constant(Q::one())
    }

    /// A constant.
    pub fn constant(c: Q) -> Poly {
        if c.is_zero() {
            Poly::zero()
        } else {
            Poly {
                terms: vec![(Mono::one(), c)],
            }
        }
    }

    /// The variable `v`.
    pub fn var(v: Var) -> Poly {
        Poly {
            terms: vec![(Mono::var(v), Q::one())],
        }
    }

    /// The single term `c * m`.
    pub fn monomial(m: Mono, c: Q) -> Poly {
        if c.is_zero() {
            Poly::zero()
        } else {
            Poly {
                terms: vec![(m, c)],
            }
        }
    }

    /// From arbitrary terms: sorts, merges duplicate monomials, drops zeros.
    /// Monomials must themselves be normalized (see [`Mono::from_pairs`]).
    pub fn from_terms(mut terms: Vec<(Mono, Q)>) -> Poly {
        terms.sort_unstable_by(|a, b| b.0.cmp(&a.0));
        let mut out: Vec<(Mono, Q)> = Vec::with_capacity(terms.len());
        for (m, c) in terms {
            match out.last_mut() {
                Some(last) if last.0 == m => last.1 += c,
                _ => {
                    if let Some(last) = out.last() {
                        if last.1.is_zero() {
                            out.pop();
                        }
                    }
                    out.push((m, c));
                }
            }
        }
        if let Some(last) = out.last() {
            if last.1.is_zero() {
                out.pop();
            }
        }
        Poly { terms: out }
    }

    /// From terms already sorted descending, distinct and nonzero.
    #[inline]
    fn from_sorted(terms: Vec<(Mono, Q)>) -> Poly {
        debug_assert!(terms.windows(2).all(|w| w[0].0 > w[1].0));
        debug_assert!(terms.iter().all(|t| !t.1.is_zero()));
        Poly { terms }
    }

    /// The terms, in descending monomial order.
    #[inline]
    pub fn terms(&self) -> &[(Mono, Q)] {
        &self.terms
    }

    /// Consumes the polynomial, returning its terms.
    #[inline]
    pub fn into_terms(self) -> Vec<(Mono, Q)> {
        self.terms
    }

    /// Number of terms.
    #[inline]
    pub fn len(&self) -> usize {
        self.terms.len()
    }

    /// `self == 0`.
    #[inline]
    pub fn is_zero(&self) -> bool {
        self.terms.is_empty()
    }

    /// `self == 1`.
    #[inline]
    pub fn is_one(&self) -> bool {
        self.terms.len() == 1 && self.terms[0].0.is_one() && self.terms[0].1.is_one()
    }

    /// `self` is a constant (including zero).
    #[inline]
    pub fn is_constant(&self) -> bool {
        self.terms.is_empty() || (self.terms.len() == 1 && self.terms[0].0.is_one())
    }

    /// The value if `self` is constant; `Some(&0)` for the zero polynomial
    /// (a reference to a static zero, no allocation).
    #[inline]
    pub fn as_constant(&self) -> Option<&Q> {
        match self.terms.len() {
            0 => Some(&ZERO_Q),
            1 if self.terms[0].0.is_one() => Some(&self.terms[0].1),
            _ => None,
        }
    }

    /// Exactly one term (nonzero).
    #[inline]
    pub fn is_monomial(&self) -> bool {
        self.terms.len() == 1
    }

    /// Coefficient of the leading term.
    #[inline]
    pub fn leading_coeff(&self) -> Option<&Q> {
        self.terms.first().map(|t| &t.1)
    }

    /// Monomial of the leading term.
    #[inline]
    pub fn leading_mono(&self) -> Option<&Mono> {
        self.terms.first().map(|t| &t.0)
    }

    /// The leading term.
    #[inline]
    pub fn leading_term(&self) -> Option<&(Mono, Q)> {
        self.terms.first()
    }

    /// Coefficient of monomial `m` (zero if absent).
    pub fn coeff_of(&self, m: &Mono) -> Q {
        match self.terms.binary_search_by(|t| m.cmp(&t.0)) {
            Ok(i) => self.terms[i].1.clone(),
            Err(_) => Q::zero(),
        }
    }

    // -----------------------------------------------------------------------
    // structure
    // -----------------------------------------------------------------------

    /// Sorted list of `(var, max exponent)`.
    fn max_degrees(&self) -> DegList {
        let mut out = DegList::new();
        for (m, _) in &self.terms {
            for &(v, e) in m.0.iter() {
                match out.binary_search_by_key(&v, |p| p.0) {
                    Ok(i) => {
                        if out[i].1 < e {
                            out[i].1 = e;
                        }
                    }
                    Err(i) => out.insert(i, (v, e)),
                }
            }
        }
        out
    }

    /// Variables present, sorted ascending, unique.
    pub fn vars(&self) -> Vec<Var> {
        self.max_degrees().iter().map(|p| p.0).collect()
    }

    /// Whether `v` occurs.
    pub fn contains_var(&self, v: Var) -> bool {
        self.terms.iter().any(|t| t.0.degree(v) > 0)
    }

    /// Degree in `v` (0 for the zero polynomial).
    pub fn degree(&self, v: Var) -> u32 {
        self.terms.iter().map(|t| t.0.degree(v)).max().unwrap_or(0)
    }

    /// Total degree (0 for the zero polynomial).
    pub fn total_degree(&self) -> u32 {
        self.terms
            .iter()
            .map(|t| t.0.total_degree())
            .max()
            .unwrap_or(0)
    }

    /// Coefficients with respect to `v`: index = power of `v`, `v` removed
    /// from the coefficients. Empty for the zero polynomial.
    pub fn coeffs_in(&self, v: Var) -> Vec<Poly> {
        if self.is_zero() {
            return Vec::new();
        }
        let d = self.degree(v) as usize;
        let mut buckets: Vec<Vec<(Mono, Q)>> = vec![Vec::new(); d + 1];
        for (m, c) in &self.terms {
            let e = m.degree(v) as usize;
            let mm = if e == 0 { m.clone() } else { m.without(v) };
            buckets[e].push((mm, c.clone()));
        }
        // removing a variable common to a bucket preserves the order
        buckets.into_iter().map(Poly::from_sorted).collect()
    }

    /// Inverse of [`Poly::coeffs_in`]: `sum coeffs[i] * v^i` (the
    /// coefficients may contain `v`, too).
    pub fn from_coeffs_in(v: Var, coeffs: &[Poly]) -> Poly {
        let mut terms = Vec::with_capacity(coeffs.iter().map(|c| c.len()).sum());
        for (i, c) in coeffs.iter().enumerate() {
            let vm = Mono::var_pow(v, i as u32);
            for (m, q) in &c.terms {
                terms.push((m.mul(&vm), q.clone()));
            }
        }
        Poly::from_terms(terms)
    }

    /// Groups the terms by their power product in the variables of `set`
    /// (sorted), returning the coefficient polynomials (free of `set`).
    fn split_by_vars(&self, set: &[Var]) -> Vec<Poly> {
        let mut groups: FxHashMap<Mono, usize> = FxHashMap::default();
        let mut out: Vec<Vec<(Mono, Q)>> = Vec::new();
        for (m, c) in &self.terms {
            let (inset, rest) = m.split_by(set);
            let idx = *groups.entry(inset).or_insert_with(|| {
                out.push(Vec::new());
                out.len() - 1
            });
            out[idx].push((rest, c.clone()));
        }
        out.into_iter().map(Poly::from_sorted).collect()
    }

    /// Partial derivative with respect to `v`.
    pub fn diff(&self, v: Var) -> Poly {
        let mut terms = Vec::new();
        for (m, c) in &self.terms {
            let e = m.degree(v);
            if e == 0 {
                continue;
            }
            let mm = Mono(
                m.0.iter()
                    .filter_map(|&(x, k)| {
                        if x != v {
                            Some((x, k))
                        } else if k > 1 {
                            Some((x, k - 1))
                        } else {
                            None
                        }
                    })
                    .collect(),
            );
            terms.push((mm, c * &Q::from_i64(e as i64)));
        }
        Poly::from_sorted(terms)
    }

    /// Substitutes the polynomial `p` for the variable `v`.
    pub fn subst(&self, v: Var, p: &Poly) -> Poly {
        if !self.contains_var(v) {
            return self.clone();
        }
        let cs = self.coeffs_in(v);
        // Horner
        let mut acc = Poly::zero();
        for c in cs.iter().rev() {
            acc = &(&acc * p) + c;
        }
        acc
    }

    /// Substitutes a rational value for `v`.
    pub fn eval_var(&self, v: Var, val: &Q) -> Poly {
        if !self.contains_var(v) {
            return self.clone();
        }
        if val.is_zero() {
            return Poly::from_sorted(
                self.terms
                    .iter()
                    .filter(|t| t.0.degree(v) == 0)
                    .cloned()
                    .collect(),
            );
        }
        let d = self.degree(v) as usize;
        let mut pows = Vec::with_capacity(d + 1);
        pows.push(Q::one());
        for i in 1..=d {
            let next = &pows[i - 1] * val;
            pows.push(next);
        }
        let terms = self
            .terms
            .iter()
            .map(|(m, c)| {
                let e = m.degree(v) as usize;
                if e == 0 {
                    (m.clone(), c.clone())
                } else {
                    (m.without(v), c * &pows[e])
                }
            })
            .collect();
        Poly::from_terms(terms)
    }

    /// Floating-point evaluation.
    pub fn eval_f64(&self, f: &dyn Fn(Var) -> f64) -> f64 {
        let mut cache: FxHashMap<Var, f64> = FxHashMap::default();
        let mut sum = 0.0;
        for (m, c) in &self.terms {
            let mut t = c.to_f64();
            for &(v, e) in m.0.iter() {
                let x = *cache.entry(v).or_insert_with(|| f(v));
                t *= x.powi(e.min(i32::MAX as u32) as i32);
            }
            sum += t;
        }
        sum
    }

    /// Exact evaluation with rational values for all variables; `None` if
    /// `f` returns `None` for a variable that occurs.
    pub fn eval_q(&self, f: &dyn Fn(Var) -> Option<Q>) -> Option<Q> {
        let mut cache: FxHashMap<(Var, u32), Q> = FxHashMap::default();
        let mut vals: FxHashMap<Var, Q> = FxHashMap::default();
        let mut sum = Q::zero();
        for (m, c) in &self.terms {
            let mut t = c.clone();
            for &(v, e) in m.0.iter() {
                let p = match cache.get(&(v, e)) {
                    Some(p) => p.clone(),
                    None => {
                        let x = match vals.get(&v) {
                            Some(x) => x.clone(),
                            None => {
                                let x = f(v)?;
                                vals.insert(v, x.clone());
                                x
                            }
                        };
                        let p = x.pow_u32(e);
                        cache.insert((v, e), p.clone());
                        p
                    }
                };
                t *= &p;
            }
            sum += &t;
        }
        Some(sum)
    }

    /// Renames variables (`f` need not be injective; colliding variables are
    /// multiplied together).
    pub fn map_vars(&self, f: &dyn Fn(Var) -> Var) -> Poly {
        let terms = self
            .terms
            .iter()
            .map(|(m, c)| {
                (
                    Mono::from_pairs(m.0.iter().map(|&(v, e)| (f(v), e))),
                    c.clone(),
                )
            })
            .collect();
        Poly::from_terms(terms)
    }

    /// Alias of [`Poly::map_vars`].
    pub fn rename(&self, f: &dyn Fn(Var) -> Var) -> Poly {
        self.map_vars(f)
    }

    /// Applies `f` to every coefficient (zero results are dropped).
    pub fn map_coeffs(&self, f: impl Fn(&Q) -> Q) -> Poly {
        Poly::from_sorted(
            self.terms
                .iter()
                .filter_map(|(m, c)| {
                    let d = f(c);
                    if d.is_zero() {
                        None
                    } else {
                        Some((m.clone(), d))
                    }
                })
                .collect(),
        )
    }

    // -----------------------------------------------------------------------
    // arithmetic
    // -----------------------------------------------------------------------

    /// `c * self`.
    pub fn scale(&self, c: &Q) -> Poly {
        if c.is_zero() {
            return Poly::zero();
        }
        if c.is_one() {
            return self.clone();
        }
        Poly::from_sorted(self.terms.iter().map(|(m, x)| (m.clone(), x * c)).collect())
    }

    /// `c * m * self`.
    pub fn mul_mono(&self, m: &Mono, c: &Q) -> Poly {
        if c.is_zero() {
            return Poly::zero();
        }
        Poly::from_sorted(
            self.terms
                .iter()
                .map(|(mm, x)| (mm.mul(m), x * c))
                .collect(),
        )
    }

    /// `self / m` if `m` divides every term.
    pub fn div_mono(&self, m: &Mono) -> Option<Poly> {
        if m.is_one() {
            return Some(self.clone());
        }
        let terms = self
            .terms
            .iter()
            .map(|(mm, c)| mm.div(m).map(|q| (q, c.clone())))
            .collect::<Option<Vec<_>>>()?;
        Some(Poly::from_sorted(terms))
    }

    /// `self^e` (`0^0 == 1`).
    pub fn pow(&self, mut e: u32) -> Poly {
        if e == 0 {
            return Poly::one();
        }
        if self.is_zero() {
            return Poly::zero();
        }
        if self.terms.len() == 1 {
            let (m, c) = &self.terms[0];
            return Poly::monomial(m.pow(e), c.pow_u32(e));
        }
        let mut result: Option<Poly> = None;
        let mut base = self.clone();
        loop {
            if e & 1 == 1 {
                result = Some(match result {
                    None => base.clone(),
                    Some(r) => &r * &base,
                });
            }
            e >>= 1;
            if e == 0 {
                break;
            }
            base = &base * &base;
        }
        result.unwrap_or_else(Poly::one)
    }

    fn merge(a: &[(Mono, Q)], b: &[(Mono, Q)], negate_b: bool) -> Vec<(Mono, Q)> {
        let mut out = Vec::with_capacity(a.len() + b.len());
        let (mut i, mut j) = (0, 0);
        while i < a.len() && j < b.len() {
            match a[i].0.cmp(&b[j].0) {
                Ordering::Greater => {
                    out.push(a[i].clone());
                    i += 1;
                }
                Ordering::Less => {
                    let c = if negate_b { -&b[j].1 } else { b[j].1.clone() };
                    out.push((b[j].0.clone(), c));
                    j += 1;
                }
                Ordering::Equal => {
                    let c = if negate_b {
                        &a[i].1 - &b[j].1
                    } else {
                        &a[i].1 + &b[j].1
                    };
                    if !c.is_zero() {
                        out.push((a[i].0.clone(), c));
                    }
                    i += 1;
                    j += 1;
                }
            }
        }
        out.extend_from_slice(&a[i..]);
        if negate_b {
            out.extend(b[j..].iter().map(|(m, c)| (m.clone(), -c)));
        } else {
            out.extend_from_slice(&b[j..]);
        }
        out
    }

    /// In-place merge consuming `self`'s terms (no clones of `self`'s monomials).
    fn merge_into(&mut self, b: &[(Mono, Q)], negate_b: bool) {
        if b.is_empty() {
            return;
        }
        if self.terms.is_empty() {
            self.terms = if negate_b {
                b.iter().map(|(m, c)| (m.clone(), -c)).collect()
            } else {
                b.to_vec()
            };
            return;
        }
        let a = std::mem::take(&mut self.terms);
        let mut out = Vec::with_capacity(a.len() + b.len());
        let mut j = 0;
        for (m, c) in a {
            while j < b.len() && b[j].0 > m {
                let c2 = if negate_b { -&b[j].1 } else { b[j].1.clone() };
                out.push((b[j].0.clone(), c2));
                j += 1;
            }
            if j < b.len() && b[j].0 == m {
                let s = if negate_b { c - &b[j].1 } else { c + &b[j].1 };
                if !s.is_zero() {
                    out.push((m, s));
                }
                j += 1;
            } else {
                out.push((m, c));
            }
        }
        if negate_b {
            out.extend(b[j..].iter().map(|(m, c)| (m.clone(), -c)));
        } else {
            out.extend_from_slice(&b[j..]);
        }
        self.terms = out;
    }

    fn mul_impl(&self, other: &Poly) -> Poly {
        let (a, b) = (&self.terms, &other.terms);
        if a.is_empty() || b.is_empty() {
            return Poly::zero();
        }
        if a.len() == 1 {
            return other.mul_mono(&a[0].0, &a[0].1);
        }
        if b.len() == 1 {
            return self.mul_mono(&b[0].0, &b[0].1);
        }
        let deg = merge_deglists(&self.max_degrees(), &other.max_degrees(), true);
        if let Some(pk) = Packed::new(&deg, None) {
            if let Some(t) = mul_with(&pk, a, b) {
                return Poly::from_sorted(t);
            }
        }
        let plain = Plain {
            qbound: DegList::new(),
        };
        match mul_with(&plain, a, b) {
            Some(t) => Poly::from_sorted(t),
            None => Poly::zero(), // unreachable: Plain always encodes
        }
    }

    /// `Some(q)` iff `d` divides `self` exactly (`self == q * d`); `None` if
    /// a remainder appears or `d == 0`.
    pub fn div_exact(&self, d: &Poly) -> Option<Poly> {
        if d.is_zero() {
            return None;
        }
        if self.is_zero() {
            return Some(Poly::zero());
        }
        if d.terms.len() == 1 {
            let (m, c) = &d.terms[0];
            let inv = c.recip()?;
            return Some(self.div_mono(m)?.scale(&inv));
        }
        if self.terms.len() < 2 {
            return None;
        }
        // leading and trailing monomials must divide
        if !d.terms[0].0.divides(&self.terms[0].0) {
            return None;
        }
        let (ld, la) = (
            &d.terms[d.terms.len() - 1].0,
            &self.terms[self.terms.len() - 1].0,
        );
        if !ld.divides(la) {
            return None;
        }
        let da = self.max_degrees();
        let dd = d.max_degrees();
        // quotient bounds per variable of self; every var of d must occur in self
        let mut qb: SmallVec<[u32; 16]> = SmallVec::with_capacity(da.len());
        let mut j = 0;
        for &(v, e) in da.iter() {
            let mut f = 0;
            if j < dd.len() && dd[j].0 == v {
                f = dd[j].1;
                j += 1;
            } else if j < dd.len() && dd[j].0 < v {
                return None;
            }
            if f > e {
                return None;
            }
            qb.push(e - f);
        }
        if j < dd.len() {
            return None;
        }
        if let Some(pk) = Packed::new(&da, Some(&qb)) {
            if let Some(res) = div_with(&pk, &self.terms, &d.terms) {
                return res.map(Poly::from_sorted);
            }
        }
        let plain = Plain {
            qbound: da.iter().zip(qb.iter()).map(|(p, &b)| (p.0, b)).collect(),
        };
        div_with(&plain, &self.terms, &d.terms).and_then(|r| r.map(Poly::from_sorted))
    }

    // -----------------------------------------------------------------------
    // content and normalization
    // -----------------------------------------------------------------------

    /// Positive rational gcd of the coefficients (0 for the zero polynomial).
    pub fn content(&self) -> Q {
        let mut g = Q::zero();
        for (_, c) in &self.terms {
            g = g.gcd(c);
            if g.is_one() {
                // can still shrink for fractional coefficients
                if self.terms.iter().all(|t| t.1.is_integer()) {
                    return g;
                }
            }
        }
        g
    }

    /// `self / content()`: integer coefficients with gcd 1, same signs as
    /// `self` (so `self == content * primitive`).
    pub fn primitive(&self) -> Poly {
        let c = self.content();
        if c.is_zero() || c.is_one() {
            return self.clone();
        }
        match c.recip() {
            Some(r) => self.scale(&r),
            None => self.clone(),
        }
    }

    /// Leading coefficient 1 (zero stays zero).
    pub fn monic(&self) -> Poly {
        match self.leading_coeff() {
            None => Poly::zero(),
            Some(c) if c.is_one() => self.clone(),
            Some(c) => match c.recip() {
                Some(r) => self.scale(&r),
                None => self.clone(),
            },
        }
    }

    /// Primitive integer polynomial with positive leading coefficient.
    fn normalize_z(&self) -> Poly {
        let c = self.content();
        if c.is_zero() {
            return Poly::zero();
        }
        let c = if self.terms[0].1.is_negative() { -c } else { c };
        if c.is_one() {
            return self.clone();
        }
        match c.recip() {
            Some(r) => self.scale(&r),
            None => self.clone(),
        }
    }

    /// The gcd of all monomials (largest monomial dividing every term).
    pub fn mono_content(&self) -> Mono {
        let mut it = self.terms.iter();
        let mut g = match it.next() {
            Some(t) => t.0.clone(),
            None => return Mono::one(),
        };
        for (m, _) in it {
            if g.is_one() {
                break;
            }
            g = g.gcd(m);
        }
        g
    }

    // -----------------------------------------------------------------------
    // gcd
    // -----------------------------------------------------------------------

    /// Greatest common divisor over Q, monic (leading coefficient 1);
    /// `gcd(0, 0) == 0`, `gcd(0, p) == p.monic()`.
    pub fn gcd(&self, other: &Poly) -> Poly {
        if self.is_zero() {
            return other.monic();
        }
        if other.is_zero() {
            return self.monic();
        }
        gcd_core(&self.normalize_z(), &other.normalize_z()).monic()
    }

    /// `(g, self / g, other / g)` with `g = self.gcd(other)`. For two zero
    /// inputs returns three zeros.
    pub fn gcd_cofactors(&self, other: &Poly) -> (Poly, Poly, Poly) {
        let g = self.gcd(other);
        if g.is_zero() {
            return (Poly::zero(), Poly::zero(), Poly::zero());
        }
        let a = self.div_exact(&g).unwrap_or_default();
        let b = other.div_exact(&g).unwrap_or_default();
        (g, a, b)
    }

    /// Least common multiple, monic (0 if either is 0).
    pub fn lcm(&self, other: &Poly) -> Poly {
        if self.is_zero() || other.is_zero() {
            return Poly::zero();
        }
        let g = self.gcd(other);
        match self.div_exact(&g) {
            Some(q) => (&q * other).monic(),
            None => Poly::zero(),
        }
    }
}

// ===========================================================================
// GCD machinery (all polynomials here have integer coefficients)
// ===========================================================================

const PRIMES: [u64; 6] = [
    4611686018427387847,
    4611686018427387817,
    4611686018427387787,
    4611686018427387761,
    4611686018427387751,
    4611686018427387737,
];

thread_local! {
    static RNG: Cell<u64> = const { Cell::new(0x9E37_79B9_7F4A_7C15) };
}

fn next_rand() -> u64 {
    RNG.with(|s| {
        let mut z = s.get().wrapping_add(0x9E37_79B9_7F4A_7C15);
        s.set(z);
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    })
}

#[inline]
fn mulmod(a: u64, b: u64, p: u64) -> u64 {
    ((a as u128 * b as u128) % p as u128) as u64
}

#[inline]
fn addmod(a: u64, b: u64, p: u64) -> u64 {
    let s = a + b; // p < 2^62: no overflow
    if s >= p {
        s - p
    } else {
        s
    }
}

#[inline]
fn submod(a: u64, b: u64, p: u64) -> u64 {
    if a >= b {
        a - b
    } else {
        a + p - b
    }
}

fn powmod(mut b: u64, mut e: u64, p: u64) -> u64 {
    let mut r = 1u64;
    b %= p;
    while e > 0 {
        if e & 1 == 1 {
            r = mulmod(r, b, p);
        }
        b = mulmod(b, b, p);
        e >>= 1;
    }
    r
}

fn invmod(a: u64, p: u64) -> u64 {
    powmod(a, p - 2, p)
}

/// `c mod p`, `None` if the denominator vanishes mod `p`.
fn q_mod(c: &Q, p: u64) -> Option<u64> {
    match c {
        Q::Small(n, d) => {
            let nm = n.rem_euclid(p as i64) as u64;
            if *d == 1 {
                return Some(nm);
            }
            let dm = (*d as u64) % p;
            if dm == 0 {
                return None;
            }
            Some(mulmod(nm, invmod(dm, p), p))
        }
        Q::Big(_) => {
            let pb = BigInt::from(p);
            let nm = c.numer().mod_floor(&pb).to_u64()?;
            let dm = c.denom().mod_floor(&pb).to_u64()?;
            if dm == 0 {
                return None;
            }
            Some(mulmod(nm, invmod(dm, p), p))
        }
    }
}

fn trim(v: &mut Vec<u64>) {
    while v.last() == Some(&0) {
        v.pop();
    }
}

/// Degree of the monic gcd of two nonzero dense polynomials over Z_p.
fn gcd_degree_modp(mut a: Vec<u64>, mut b: Vec<u64>, p: u64) -> usize {
    if a.len() < b.len() {
        std::mem::swap(&mut a, &mut b);
    }
    while !b.is_empty() {
        // a <- a mod b
        let lb = match b.last() {
            Some(&x) => x,
            None => break,
        };
        let inv = invmod(lb, p);
        while a.len() >= b.len() {
            let top = match a.last() {
                Some(&x) => x,
                None => break,
            };
            let c = mulmod(top, inv, p);
            let shift = a.len() - b.len();
            for (i, &bi) in b.iter().enumerate() {
                a[shift + i] = submod(a[shift + i], mulmod(c, bi, p), p);
            }
            a.pop();
            trim(&mut a);
        }
        std::mem::swap(&mut a, &mut b);
    }
    a.len().saturating_sub(1)
}

/// For each variable `vars[i]`, the univariate image of `a` in that variable
/// with all other variables evaluated at `pts` mod `p` (dense, index = power).
fn univariate_images(
    a: &Poly,
    vars: &[Var],
    degs: &[u32],
    pts: &[u64],
    p: u64,
) -> Option<Vec<Vec<u64>>> {
    let mut imgs: Vec<Vec<u64>> = degs.iter().map(|&d| vec![0u64; d as usize + 1]).collect();
    let mut total = 0u64;
    let mut pw: SmallVec<[u64; 16]> = SmallVec::new();
    let mut idx: SmallVec<[usize; 16]> = SmallVec::new();
    let mut suffix: SmallVec<[u64; 16]> = SmallVec::new();
    for (m, c) in &a.terms {
        let cm = q_mod(c, p)?;
        pw.clear();
        idx.clear();
        for &(v, e) in m.0.iter() {
            let i = vars.binary_search(&v).ok()?;
            idx.push(i);
            pw.push(powmod(pts[i], e as u64, p));
        }
        let k = pw.len();
        suffix.clear();
        suffix.resize(k + 1, 1);
        for j in (0..k).rev() {
            suffix[j] = mulmod(suffix[j + 1], pw[j], p);
        }
        let full = mulmod(cm, suffix[0], p);
        total = addmod(total, full, p);
        let mut prefix = cm;
        for j in 0..k {
            let excl = mulmod(prefix, suffix[j + 1], p);
            let i = idx[j];
            let e = m.0[j].1 as usize;
            imgs[i][0] = submod(imgs[i][0], full, p);
            imgs[i][e] = addmod(imgs[i][e], excl, p);
            prefix = mulmod(prefix, pw[j], p);
        }
    }
    for img in imgs.iter_mut() {
        img[0] = addmod(img[0], total, p);
    }
    Some(imgs)
}

/// Upper bounds on the degree of `gcd(a, b)` in each variable of `vars`
/// (both `a` and `b` have exactly these variables, degrees `da`, `db`).
fn degree_bounds(a: &Poly, b: &Poly, vars: &[Var], da: &[u32], db: &[u32]) -> Vec<u32> {
    let n = vars.len();
    let mut bounds: Vec<Option<u32>> = vec![None; n];
    for attempt in 0..3 {
        let p = PRIMES[(attempt + (next_rand() as usize)) % PRIMES.len()];
        let pts: Vec<u64> = (0..n).map(|_| 1 + next_rand() % (p - 1)).collect();
        let (ia, ib) = match (
            univariate_images(a, vars, da, &pts, p),
            univariate_images(b, vars, db, &pts, p),
        ) {
            (Some(x), Some(y)) => (x, y),
            _ => continue,
        };
        for (i, (mut x, mut y)) in ia.into_iter().zip(ib).enumerate() {
            if bounds[i].is_some() {
                continue;
            }
            trim(&mut x);
            trim(&mut y);
            let okx = x.len() == da[i] as usize + 1;
            let oky = y.len() == db[i] as usize + 1;
            if !(okx || oky) || x.is_empty() || y.is_empty() {
                continue;
            }
            bounds[i] = Some(gcd_degree_modp(x, y, p) as u32);
        }
        if bounds.iter().all(|b| b.is_some()) {
            break;
        }
    }
    bounds
        .iter()
        .enumerate()
        .map(|(i, b)| b.unwrap_or(da[i].min(db[i])))
        .collect()
}

/// gcd of a list of nonzero integer polynomials (primitive, positive lc).
fn multi_gcd(mut list: Vec<Poly>) -> Poly {
    list.retain(|p| !p.is_zero());
    if list.is_empty() {
        return Poly::zero();
    }
    if list.iter().any(|p| p.is_constant()) {
        return Poly::one();
    }
    list.sort_by_key(|p| p.len());
    let mut it = list.into_iter();
    let mut g = match it.next() {
        Some(p) => p.normalize_z(),
        None => return Poly::zero(),
    };
    for p in it {
        g = gcd_core(&g, &p);
        if g.is_constant() {
            return Poly::one();
        }
    }
    g
}

/// gcd of two nonzero integer polynomials: primitive, positive leading coeff.
fn gcd_core(a: &Poly, b: &Poly) -> Poly {
    if a.is_constant() || b.is_constant() {
        return Poly::one();
    }
    if a.terms.len() == 1 {
        return Poly::monomial(a.terms[0].0.gcd(&b.mono_content()), Q::one());
    }
    if b.terms.len() == 1 {
        return Poly::monomial(b.terms[0].0.gcd(&a.mono_content()), Q::one());
    }
    let a = a.normalize_z();
    let b = b.normalize_z();
    if a == b {
        return a;
    }
    let ma = a.mono_content();
    let mb = b.mono_content();
    let gm = ma.gcd(&mb);
    let a = a.div_mono(&ma).unwrap_or_else(|| a.clone());
    let b = b.div_mono(&mb).unwrap_or_else(|| b.clone());
    let g = gcd_nomono(&a, &b);
    if gm.is_one() {
        g
    } else {
        g.mul_mono(&gm, &Q::one())
    }
}

/// gcd of primitive integer polynomials without monomial content.
fn gcd_nomono(a: &Poly, b: &Poly) -> Poly {
    if a.is_constant() || b.is_constant() || a.terms.len() == 1 || b.terms.len() == 1 {
        return Poly::one();
    }
    let dla = a.max_degrees();
    let dlb = b.max_degrees();
    let only_a: Vec<Var> = dla
        .iter()
        .map(|p| p.0)
        .filter(|v| dlb.binary_search_by_key(v, |p| p.0).is_err())
        .collect();
    let only_b: Vec<Var> = dlb
        .iter()
        .map(|p| p.0)
        .filter(|v| dla.binary_search_by_key(v, |p| p.0).is_err())
        .collect();
    if !only_a.is_empty() || !only_b.is_empty() {
        let mut list = if only_a.is_empty() {
            vec![a.clone()]
        } else {
            a.split_by_vars(&only_a)
        };
        if only_b.is_empty() {
            list.push(b.clone());
        } else {
            list.extend(b.split_by_vars(&only_b));
        }
        return multi_gcd(list);
    }
    // same variable set
    let vars: Vec<Var> = dla.iter().map(|p| p.0).collect();
    let da: Vec<u32> = dla.iter().map(|p| p.1).collect();
    let db: Vec<u32> = dlb.iter().map(|p| p.1).collect();
    let bounds = degree_bounds(a, b, &vars, &da, &db);
    let zero_vars: Vec<Var> = vars
        .iter()
        .zip(bounds.iter())
        .filter(|(_, &d)| d == 0)
        .map(|(v, _)| *v)
        .collect();
    if zero_vars.len() == vars.len() {
        return Poly::one();
    }
    if !zero_vars.is_empty() {
        let mut list = a.split_by_vars(&zero_vars);
        list.extend(b.split_by_vars(&zero_vars));
        return multi_gcd(list);
    }
    // one divides the other?
    if bounds == db && a.len() >= b.len() && a.div_exact(b).is_some() {
        return b.clone();
    }
    if bounds == da && b.div_exact(a).is_some() {
        return a.clone();
    }
    // heuristic gcd for few variables
    if let Some(h) = heu_entry(a, b, &vars, &da, &db) {
        if !h.is_constant() {
            let hd: Vec<u32> = vars.iter().map(|&v| h.degree(v)).collect();
            if hd == bounds {
                return h;
            }
            if let (Some(qa), Some(qb)) = (a.div_exact(&h), b.div_exact(&h)) {
                let rest = gcd_core(&qa, &qb);
                return (&h * &rest).normalize_z();
            }
        }
    }
    prs_gcd(a, b, &vars, &da, &db, &bounds)
}

// ---------------------------------------------------------------------------
// heuristic gcd (GCDHEU)
// ---------------------------------------------------------------------------

/// Max |coefficient| as BigInt.
fn max_norm(p: &Poly) -> BigInt {
    let mut best = BigInt::zero();
    for (_, c) in &p.terms {
        let n = c.numer().abs();
        if n > best {
            best = n;
        }
    }
    best
}

fn heu_entry(a: &Poly, b: &Poly, vars: &[Var], da: &[u32], db: &[u32]) -> Option<Poly> {
    if vars.len() > 3 {
        return None;
    }
    // estimate the size of the integers met at the bottom of the recursion
    let mut bits = max_norm(a).bits().min(max_norm(b).bits()) as f64 + 6.0;
    for i in 0..vars.len() {
        let d = da[i].max(db[i]) as f64;
        bits += d * (bits + 8.0);
        if bits > 60_000.0 {
            return None;
        }
    }
    // evaluate the variable of highest degree last (innermost)
    let mut order: Vec<usize> = (0..vars.len()).collect();
    order.sort_by_key(|&i| da[i].max(db[i]));
    let ovars: Vec<Var> = order.iter().map(|&i| vars[i]).collect();
    let h = heu_gcd(a, b, &ovars, 0)?;
    Some(h.normalize_z())
}

/// Symmetric residue of the integer `c` modulo the positive integer `m`.
fn sym_mod(c: &Q, m: &BigInt, m_small: Option<i64>) -> Q {
    if let (Q::Small(n, 1), Some(ms)) = (c, m_small) {
        let r = n.rem_euclid(ms);
        return Q::from_i64(if r > ms / 2 { r - ms } else { r });
    }
    let r = c.numer().mod_floor(m);
    let r = if &r * 2 > *m { r - m } else { r };
    Q::from_bigint(r)
}

/// xi-adic interpolation of `h` into a polynomial in `v`.
fn heu_interpolate(h: &Poly, xi: &BigInt, v: Var) -> Poly {
    let xi_small = xi.to_i64();
    let xi_q = Q::from_bigint(xi.clone());
    let xi_inv = match xi_q.recip() {
        Some(r) => r,
        None => return Poly::zero(),
    };
    let mut terms: Vec<(Mono, Q)> = Vec::new();
    let mut h = h.clone();
    let mut i = 0u32;
    while !h.is_zero() {
        let g = h.map_coeffs(|c| sym_mod(c, xi, xi_small));
        let vm = Mono::var_pow(v, i);
        for (m, c) in &g.terms {
            terms.push((m.mul(&vm), c.clone()));
        }
        h = (&h - &g).scale(&xi_inv);
        i += 1;
        if i > 100_000 {
            return Poly::zero();
        }
    }
    let r = Poly::from_terms(terms);
    match r.leading_coeff() {
        Some(c) if c.is_negative() => -&r,
        _ => r,
    }
}

/// Heuristic gcd in Z[vars] (including the integer content), or `None`.
fn heu_gcd(a: &Poly, b: &Poly, vars: &[Var], depth: usize) -> Option<Poly> {
    if a.is_zero() {
        return Some(b.normalize_z().scale(&b.content()));
    }
    if b.is_zero() {
        return Some(a.normalize_z().scale(&a.content()));
    }
    let ca = a.content();
    let cb = b.content();
    let cg = ca.gcd(&cb);
    if a.is_constant() || b.is_constant() {
        return Some(Poly::constant(cg));
    }
    let (v, rest) = match vars.split_first() {
        Some(x) => x,
        None => return Some(Poly::constant(cg)),
    };
    if !a.contains_var(*v) && !b.contains_var(*v) {
        return heu_gcd(a, b, rest, depth);
    }
    let ap = a.scale(&ca.recip()?);
    let bp = b.scale(&cb.recip()?);
    let na = max_norm(&ap);
    let nb = max_norm(&bp);
    let lca = ap.terms[0].1.numer().abs();
    let lcb = bp.terms[0].1.numer().abs();
    let bb: BigInt = BigInt::from(2) * (&na).min(&nb) + 29;
    let sq: BigInt = BigInt::from(99) * bb.sqrt();
    let x1: BigInt = bb.min(sq);
    let ra: BigInt = &na / &lca;
    let rb: BigInt = &nb / &lcb;
    let x2: BigInt = BigInt::from(2) * ra.min(rb) + 2;
    let mut xi = x1.max(x2);
    for _ in 0..6 {
        if xi.bits() > 1_000_000 {
            return None;
        }
        let xq = Q::from_bigint(xi.clone());
        let aa = ap.eval_var(*v, &xq);
        let bbv = bp.eval_var(*v, &xq);
        if !aa.is_zero() && !bbv.is_zero() {
            let h = heu_gcd(&aa, &bbv, rest, depth + 1)?;
            let hh = heu_interpolate(&h, &xi, *v).normalize_z();
            if !hh.is_zero() && ap.div_exact(&hh).is_some() && bp.div_exact(&hh).is_some() {
                return Some(hh.scale(&cg));
            }
            // cofactor attempts
            for (x, xx, y) in [(&aa, &ap, &bp), (&bbv, &bp, &ap)] {
                if let Some(cf) = x.div_exact(&h) {
                    let c = heu_interpolate(&cf, &xi, *v);
                    if let Some(g) = xx.div_exact(&c) {
                        let g = g.normalize_z();
                        if !g.is_zero() && y.div_exact(&g).is_some() {
                            return Some(g.scale(&cg));
                        }
                    }
                }
            }
        }
        let s = xi.sqrt().sqrt();
        xi = xi * BigInt::from(73794) * s / BigInt::from(27011);
    }
    None
}

// ---------------------------------------------------------------------------
// recursive subresultant PRS
// ---------------------------------------------------------------------------

fn dense_trim(v: &mut Vec<Poly>) {
    while v.last().is_some_and(|p| p.is_zero()) {
        v.pop();
    }
}

/// Pseudo-remainder of dense polynomials (coefficients in the other vars).
fn prem(f: &[Poly], g: &[Poly]) -> Vec<Poly> {
    let mut r = f.to_vec();
    dense_trim(&mut r);
    let dg = g.len() - 1;
    let lc = &g[dg];
    let mut e = (f.len() + 1).saturating_sub(g.len()) as u32;
    while r.len() >= g.len() {
        let t = match r.last() {
            Some(t) => t.clone(),
            None => break,
        };
        let k = r.len() - g.len();
        let top = r.len() - 1;
        for x in r[..top].iter_mut() {
            if !x.is_zero() {
                *x = &*x * lc;
            }
        }
        for j in 0..dg {
            if !g[j].is_zero() {
                r[k + j] -= &(&t * &g[j]);
            }
        }
        r.pop();
        dense_trim(&mut r);
        e = e.saturating_sub(1);
    }
    if e > 0 && !r.is_empty() {
        let m = lc.pow(e);
        for x in r.iter_mut() {
            *x = &*x * &m;
        }
    }
    r
}

/// Content (w.r.t. the main variable) and primitive part of a dense poly.
fn dense_primitive(f: &[Poly]) -> (Poly, Vec<Poly>) {
    let c = multi_gcd(f.to_vec());
    if c.is_one() || c.is_zero() {
        return (Poly::one(), f.to_vec());
    }
    let mut out = Vec::with_capacity(f.len());
    for x in f {
        match x.div_exact(&c) {
            Some(q) => out.push(q),
            None => return (Poly::one(), f.to_vec()),
        }
    }
    (c, out)
}

fn prs_gcd(a: &Poly, b: &Poly, vars: &[Var], da: &[u32], db: &[u32], bounds: &[u32]) -> Poly {
    // main variable: smallest gcd degree bound, then smallest degree
    let mut best = 0;
    for i in 1..vars.len() {
        let key = (bounds[i], da[i].min(db[i]), da[i].max(db[i]));
        let bk = (bounds[best], da[best].min(db[best]), da[best].max(db[best]));
        if key < bk {
            best = i;
        }
    }
    let v = vars[best];
    let (conta, pa) = dense_primitive(&a.coeffs_in(v));
    let (contb, pb) = dense_primitive(&b.coeffs_in(v));
    let cont = gcd_core(&conta, &contb);
    let g = subresultant(pa, pb);
    if g.len() <= 1 {
        return cont;
    }
    let (_, pg) = dense_primitive(&g);
    let res = Poly::from_coeffs_in(v, &pg);
    (&res * &cont).normalize_z()
}

/// Last nonzero subresultant (or a primitive PRS element) of two dense
/// polynomials of positive degree in the main variable.
fn subresultant(a: Vec<Poly>, b: Vec<Poly>) -> Vec<Poly> {
    let (mut f, mut g) = if a.len() >= b.len() { (a, b) } else { (b, a) };
    let mut gg = Poly::one();
    let mut h = Poly::one();
    let mut primitive_mode = false;
    loop {
        let delta = (f.len() - g.len()) as u32;
        let r = prem(&f, &g);
        if r.is_empty() {
            return g;
        }
        if r.len() == 1 {
            return vec![Poly::one()];
        }
        let next = if primitive_mode {
            None
        } else {
            let div = &gg * &h.pow(delta);
            r.iter()
                .map(|c| c.div_exact(&div))
                .collect::<Option<Vec<_>>>()
        };
        let next = match next {
            Some(n) => n,
            None => {
                primitive_mode = true;
                dense_primitive(&r).1
            }
        };
        f = g;
        g = next;
        if !primitive_mode {
            gg = f.last().cloned().unwrap_or_else(Poly::one);
            h = match delta {
                0 => h,
                1 => gg.clone(),
                _ => match gg.pow(delta).div_exact(&h.pow(delta - 1)) {
                    Some(x) => x,
                    None => {
                        primitive_mode = true;
                        h
                    }
                },
            };
        } else {
            g = dense_primitive(&g).1;
        }
    }
}

// ===========================================================================
// operators
// ===========================================================================

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

impl From<Q> for Poly {
    fn from(c: Q) -> Poly {
        Poly::constant(c)
    }
}

impl fmt::Display for Poly {
    /// Like `3*x0^2*x1 - 1/2*x2 + 1`; `0` for the zero polynomial.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.terms.is_empty() {
            return write!(f, "0");
        }
        for (i, (m, c)) in self.terms.iter().enumerate() {
            let neg = c.is_negative();
            let a = c.abs();
            if i == 0 {
                if neg {
                    write!(f, "-")?;
                }
            } else if neg {
                write!(f, " - ")?;
            } else {
                write!(f, " + ")?;
            }
            if m.is_one() {
                write!(f, "{a}")?;
            } else if a.is_one() {
                write!(f, "{m}")?;
            } else {
                write!(f, "{a}*{m}")?;
            }
        }
        Ok(())
    }
}
