//! Monomial encodings inside multiplication and exact division: packed
//! `[u64; W]` keys (one bit field per variable, so integer order is the term
//! order and key addition is monomial multiplication) when the exponents fit,
//! plain [`Mono`]s otherwise; and the hash/heap product and division loops
//! generic over the encoding.

use super::{Mono, Var};
use crate::num::Q;
use rustc_hash::FxHashMap;
use smallvec::SmallVec;
use std::cmp::Ordering;
use std::collections::hash_map::Entry;
use std::collections::BinaryHeap;
use std::hash::Hash;

/// Sorted `(var, max exponent)` list.
pub(super) type DegList = SmallVec<[(Var, u32); 8]>;

pub(super) fn merge_deglists(a: &DegList, b: &DegList, sum: bool) -> DegList {
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

/// Bit-field layout for packed monomial keys: one field per variable,
/// smallest variable in the most significant bits of word 0, fields never
/// straddle words. Key comparison (`[u64; W]` lexicographic) is then the
/// monomial order, and key addition is monomial multiplication as long as no
/// field overflows (guaranteed by sizing the fields for the maximum exponent).
struct Layout {
    vars: SmallVec<[Var; 16]>,
    /// (word, shift, mask) per variable
    fields: SmallVec<[(u8, u8, u64); 16]>,
    /// quotient exponent bounds (for `div_bounded`)
    qbound: SmallVec<[u32; 16]>,
    words: usize,
    /// for each word and bit, the index of the field holding that bit
    bit_field: Vec<[u8; 64]>,
}

impl Layout {
    /// Fields wide enough for the given maximum exponents; `qb` gives the
    /// quotient bounds per variable (same order), if division is needed.
    /// `None` if more than 8 words would be needed.
    fn new(maxdeg: &DegList, qb: Option<&[u32]>) -> Option<Layout> {
        if maxdeg.len() > 255 {
            return None;
        }
        let mut fields = SmallVec::new();
        let mut bit_field = vec![[0u8; 64]];
        let mut word = 0usize;
        let mut free = 64u32;
        for (j, &(_, d)) in maxdeg.iter().enumerate() {
            let w = (32 - d.leading_zeros()).max(1);
            if w > free {
                word += 1;
                free = 64;
                if word >= 8 {
                    return None;
                }
                bit_field.push([0u8; 64]);
            }
            free -= w;
            let mask = if w == 64 { u64::MAX } else { (1u64 << w) - 1 };
            fields.push((word as u8, free as u8, mask));
            for b in free..free + w {
                bit_field[word][b as usize] = j as u8;
            }
        }
        Some(Layout {
            vars: maxdeg.iter().map(|p| p.0).collect(),
            fields,
            qbound: match qb {
                Some(q) => q.iter().copied().collect(),
                None => SmallVec::new(),
            },
            words: word + 1,
            bit_field,
        })
    }
}

/// Packed keys of `W` words.
struct Packed<'a, const W: usize>(&'a Layout);

impl<const W: usize> Repr for Packed<'_, W> {
    type K = [u64; W];

    #[inline]
    fn enc(&self, m: &Mono) -> Option<[u64; W]> {
        let l = self.0;
        let mut k = [0u64; W];
        let mut j = 0;
        for &(v, e) in m.0.iter() {
            while j < l.vars.len() && l.vars[j] < v {
                j += 1;
            }
            if j >= l.vars.len() || l.vars[j] != v {
                return None;
            }
            let (w, sh, mask) = l.fields[j];
            if (e as u64) > mask {
                return None;
            }
            *k.get_mut(w as usize)? |= (e as u64) << sh;
        }
        Some(k)
    }

    #[inline]
    fn dec(&self, k: &[u64; W]) -> Mono {
        // visit only the nonzero fields, highest bits (smallest vars) first
        let l = self.0;
        let mut out = SmallVec::new();
        for (w, table) in l.bit_field.iter().enumerate() {
            let mut x = k[w];
            while x != 0 {
                let j = table[63 - x.leading_zeros() as usize] as usize;
                let (_, sh, mask) = l.fields[j];
                out.push((l.vars[j], ((x >> sh) & mask) as u32));
                x &= !(mask << sh);
            }
        }
        Mono(out)
    }

    #[inline]
    fn mul(&self, a: &[u64; W], b: &[u64; W]) -> [u64; W] {
        let mut r = *a;
        for i in 0..W {
            r[i] = r[i].wrapping_add(b[i]);
        }
        r
    }

    #[inline]
    fn div_bounded(&self, a: &[u64; W], b: &[u64; W]) -> Option<[u64; W]> {
        let l = self.0;
        for (j, &(w, sh, mask)) in l.fields.iter().enumerate() {
            let ea = (a[w as usize] >> sh) & mask;
            let eb = (b[w as usize] >> sh) & mask;
            if ea < eb || (ea - eb) > l.qbound[j] as u64 {
                return None;
            }
        }
        let mut r = *a;
        for i in 0..W {
            r[i] = r[i].wrapping_sub(b[i]);
        }
        Some(r)
    }
}

/// Runs `$f(&repr, args...)` with the smallest packed key width that fits.
macro_rules! with_packed {
    ($layout:expr, $f:ident ( $($arg:expr),* )) => {{
        let l: &Layout = $layout;
        match l.words {
            1 => $f(&Packed::<1>(l), $($arg),*),
            2 => $f(&Packed::<2>(l), $($arg),*),
            3 | 4 => $f(&Packed::<4>(l), $($arg),*),
            _ => $f(&Packed::<8>(l), $($arg),*),
        }
    }};
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
    let limit = crate::budget::limit();
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
                    if acc.len() > limit {
                        crate::budget::check_terms(acc.len());
                    }
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
    // each quotient term takes |d| − 1 term products: the work a product
    // of the two may take bounds it (a quotient need not be small)
    let mut work = 0usize;
    while let Some(k) = heap.pop() {
        let c = match rem.remove(&k) {
            Some(c) if !c.is_zero() => c,
            _ => continue,
        };
        work = work.saturating_add(kd.len());
        crate::budget::check_division(work, a.len(), d.len());
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
        crate::budget::check_terms(q.len().max(rem.len()));
    }
    Some(Some(q.into_iter().map(|(k, c)| (r.dec(&k), c)).collect()))
}

/// The product of two term lists of at least two terms each, `deg` the
/// merged (summed) degree list of the factors: packed keys when the
/// exponents fit, plain monomials otherwise.
pub(super) fn mul_terms(a: &[(Mono, Q)], b: &[(Mono, Q)], deg: &DegList) -> Vec<(Mono, Q)> {
    // (saturated exponent sums cannot be packed without field overflow)
    let packable = deg.iter().all(|p| p.1 < u32::MAX);
    if let Some(layout) = Layout::new(deg, None).filter(|_| packable) {
        if let Some(t) = with_packed!(&layout, mul_with(a, b)) {
            return t;
        }
    }
    let plain = Plain {
        qbound: DegList::new(),
    };
    // (None is unreachable: Plain always encodes)
    mul_with(&plain, a, b).unwrap_or_default()
}

/// The exact quotient `a / d`, `None` if a remainder appears; `da` is the
/// degree list of `a` and `qb` the quotient's exponent bound per variable of
/// `da` (same order).
pub(super) fn div_terms(
    a: &[(Mono, Q)],
    d: &[(Mono, Q)],
    da: &DegList,
    qb: &[u32],
) -> Option<Vec<(Mono, Q)>> {
    if let Some(layout) = Layout::new(da, Some(qb)) {
        if let Some(res) = with_packed!(&layout, div_with(a, d)) {
            return res;
        }
    }
    let plain = Plain {
        qbound: da.iter().zip(qb.iter()).map(|(p, &b)| (p.0, b)).collect(),
    };
    div_with(&plain, a, d).and_then(|r| r)
}
