//! Fraction-free elimination over trigonometric polynomials in the
//! exponential basis.
//!
//! With zₖ = e^{iθₖ}, cos θₖ = (zₖ + zₖ⁻¹)/2 and sin θₖ = (zₖ − zₖ⁻¹)/(2i), so
//! the ring qdot reduces in, ℚ[sin θ, cos θ, x]/(sin²θₖ + cos²θₖ − 1), extended
//! by i, is the Laurent polynomial ring ℚ(i)[z^±, x]: an integral domain in
//! which sin² + cos² = 1 holds by construction and Sylvester's divisions are
//! exact divisions of Laurent polynomials. Elimination there keeps every
//! entry at the size of its reduced form. In the free ring (sin and cos
//! independent, [`super::solve`]'s fallback) the entries carry multiples of
//! sin² + cos² − 1 that only the final reduction removes: 7× more terms in
//! the 5-link chain's determinant, 10× in its Cramer numerators.
//!
//! Both rings give the same determinant and Cramer numerators (reduction is
//! a ring homomorphism), so the canonical quotients are identical.
//!
//! Monomials are packed keys of 32 signed 8-bit exponents (biased by 128),
//! the angles' zₖ first; lexicographic comparison of the words is the
//! lexicographic order on ℤ³², a group order, so leading terms multiply and
//! exact division by leading terms works as for polynomials. Whatever does
//! not fit (more than 32 atoms, exponents beyond ±127, radicals) is left to
//! the free ring: [`solve`] answers `None`.

use super::{dependent_unknowns, SolveError};
use crate::expr::atom;
use crate::expr::Expr;
use crate::num::Q;
use crate::poly::{Mono, Poly, Var};
use rustc_hash::FxHashMap;
use std::collections::hash_map::Entry;
use std::collections::BinaryHeap;

/// The number of exponent fields in a key.
const FIELDS: usize = 32;
/// The largest |exponent| a field holds.
const MAX_EXP: i32 = 127;
/// 128 in every field: the bias of a key.
const BIAS: Key = [0x8080_8080_8080_8080; 4];

/// A packed exponent vector: field j is byte `7 − j % 8` (counted from the
/// least significant) of word `j / 8`, holding exponent + 128.
type Key = [u64; 4];

fn key_mul(a: &Key, b: &Key) -> Key {
    // exact as long as every field's sum stays within ±127: the carries
    // between fields of a + b are taken back by − BIAS (mod 2⁶⁴)
    std::array::from_fn(|w| a[w].wrapping_add(b[w]).wrapping_sub(BIAS[w]))
}

fn key_div(a: &Key, b: &Key) -> Key {
    std::array::from_fn(|w| a[w].wrapping_sub(b[w]).wrapping_add(BIAS[w]))
}

fn field(k: &Key, j: usize) -> i32 {
    ((k[j / 8] >> (56 - 8 * (j % 8))) & 0xff) as i32 - 128
}

/// The key of exponent 0 everywhere but `e` in field `j` (|e| ≤ 127).
fn key_unit(j: usize, e: i32) -> Key {
    let mut k = BIAS;
    let sh = 56 - 8 * (j % 8);
    k[j / 8] = (k[j / 8] & !(0xff << sh)) | (((e + 128) as u64) << sh);
    k
}

/// A Gaussian rational re + i·im.
#[derive(Clone, Debug, Default, PartialEq)]
struct Cq {
    re: Q,
    im: Q,
}

impl Cq {
    fn real(re: Q) -> Cq {
        Cq { re, im: Q::zero() }
    }

    fn is_zero(&self) -> bool {
        self.re.is_zero() && self.im.is_zero()
    }

    fn mul(&self, o: &Cq) -> Cq {
        Cq {
            re: &(&self.re * &o.re) - &(&self.im * &o.im),
            im: &(&self.re * &o.im) + &(&self.im * &o.re),
        }
    }

    fn add_assign(&mut self, o: &Cq) {
        self.re += &o.re;
        self.im += &o.im;
    }

    fn sub_assign(&mut self, o: &Cq) {
        self.re -= &o.re;
        self.im -= &o.im;
    }

    fn neg(&self) -> Cq {
        Cq {
            re: -&self.re,
            im: -&self.im,
        }
    }

    fn recip(&self) -> Option<Cq> {
        let n = &(&self.re * &self.re) + &(&self.im * &self.im);
        let inv = n.recip()?;
        Some(Cq {
            re: &self.re * &inv,
            im: -&(&self.im * &inv),
        })
    }
}

/// A Laurent polynomial over ℚ(i): terms sorted by key, descending, no
/// zero coefficients.
#[derive(Clone, Debug, Default, PartialEq)]
struct LPoly {
    terms: Vec<(Key, Cq)>,
}

/// Per-field exponent range of a nonzero Laurent polynomial.
struct Range {
    min: [i32; FIELDS],
    max: [i32; FIELDS],
}

impl LPoly {
    fn is_zero(&self) -> bool {
        self.terms.is_empty()
    }

    fn len(&self) -> usize {
        self.terms.len()
    }

    fn from_unsorted(mut acc: Vec<(Key, Cq)>) -> LPoly {
        acc.retain(|t| !t.1.is_zero());
        acc.sort_unstable_by_key(|t| std::cmp::Reverse(t.0));
        debug_assert!(acc.windows(2).all(|w| w[0].0 != w[1].0));
        LPoly { terms: acc }
    }

    fn range(&self) -> Range {
        let mut r = Range {
            min: [i32::MAX; FIELDS],
            max: [i32::MIN; FIELDS],
        };
        for (k, _) in &self.terms {
            for j in 0..FIELDS {
                let e = field(k, j);
                r.min[j] = r.min[j].min(e);
                r.max[j] = r.max[j].max(e);
            }
        }
        r
    }

    /// The largest |exponent| of any field of any term.
    fn span(&self) -> i32 {
        let r = self.range();
        (0..FIELDS)
            .map(|j| r.min[j].abs().max(r.max[j].abs()))
            .max()
            .unwrap_or(0)
    }

    /// The product; `None` if an exponent could leave ±127.
    fn mul(&self, o: &LPoly) -> Option<LPoly> {
        if self.is_zero() || o.is_zero() {
            return Some(LPoly::default());
        }
        if self.span() + o.span() > MAX_EXP {
            return None;
        }
        crate::cancel::check();
        crate::budget::check_product(self.len(), o.len());
        let limit = crate::budget::limit();
        let cap = (self.len() * o.len()).min(1 << 16);
        let mut index: FxHashMap<Key, usize> = FxHashMap::default();
        index.reserve(cap);
        let mut acc: Vec<(Key, Cq)> = Vec::with_capacity(cap);
        for (ka, ca) in &self.terms {
            for (kb, cb) in &o.terms {
                let c = ca.mul(cb);
                match index.entry(key_mul(ka, kb)) {
                    Entry::Occupied(e) => acc[*e.get()].1.add_assign(&c),
                    Entry::Vacant(e) => {
                        let k = *e.key();
                        e.insert(acc.len());
                        acc.push((k, c));
                        if acc.len() > limit {
                            crate::budget::check_terms(acc.len());
                        }
                    }
                }
            }
        }
        Some(LPoly::from_unsorted(acc))
    }

    fn sub(&self, o: &LPoly) -> LPoly {
        let (a, b) = (&self.terms, &o.terms);
        let mut out = Vec::with_capacity(a.len() + b.len());
        let (mut i, mut j) = (0, 0);
        while i < a.len() && j < b.len() {
            match a[i].0.cmp(&b[j].0) {
                std::cmp::Ordering::Greater => {
                    out.push(a[i].clone());
                    i += 1;
                }
                std::cmp::Ordering::Less => {
                    out.push((b[j].0, b[j].1.neg()));
                    j += 1;
                }
                std::cmp::Ordering::Equal => {
                    let mut c = a[i].1.clone();
                    c.sub_assign(&b[j].1);
                    if !c.is_zero() {
                        out.push((a[i].0, c));
                    }
                    i += 1;
                    j += 1;
                }
            }
        }
        out.extend_from_slice(&a[i..]);
        out.extend(b[j..].iter().map(|(k, c)| (*k, c.neg())));
        LPoly { terms: out }
    }

    /// The exact quotient `self / d` (d nonzero), `None` if it is not exact.
    ///
    /// Quotient terms come out in decreasing order; a quotient of an exact
    /// division lies in the box [min(t) − min(d), max(t) − max(d)] (leading
    /// and trailing terms multiply in a group order), so a term outside it
    /// proves a remainder and also bounds the loop.
    fn div_exact(&self, d: &LPoly) -> Option<LPoly> {
        if self.is_zero() {
            return Some(LPoly::default());
        }
        let (rt, rd) = (self.range(), d.range());
        let lo: [i32; FIELDS] = std::array::from_fn(|j| rt.min[j] - rd.min[j]);
        let hi: [i32; FIELDS] = std::array::from_fn(|j| rt.max[j] - rd.max[j]);
        if (0..FIELDS).any(|j| lo[j] > hi[j] || lo[j] < -MAX_EXP || hi[j] > MAX_EXP) {
            return None;
        }
        crate::cancel::check();
        let (ld, lc) = (&d.terms[0].0, d.terms[0].1.recip()?);
        let mut rem: FxHashMap<Key, Cq> = FxHashMap::default();
        rem.reserve(self.len() * 2);
        let mut heap: BinaryHeap<Key> = BinaryHeap::with_capacity(self.len() * 2);
        for (k, c) in &self.terms {
            heap.push(*k);
            rem.insert(*k, c.clone());
        }
        let limit = crate::budget::limit();
        let mut q: Vec<(Key, Cq)> = Vec::new();
        while let Some(k) = heap.pop() {
            let c = match rem.remove(&k) {
                Some(c) if !c.is_zero() => c,
                _ => continue,
            };
            // field by field first: a difference out of range would wrap
            if (0..FIELDS).any(|j| !(lo[j]..=hi[j]).contains(&(field(&k, j) - field(ld, j)))) {
                return None;
            }
            let t = key_div(&k, ld);
            let tc = c.mul(&lc);
            for (kd, cd) in &d.terms[1..] {
                let p = tc.mul(cd);
                match rem.entry(key_mul(&t, kd)) {
                    Entry::Occupied(mut e) => e.get_mut().sub_assign(&p),
                    Entry::Vacant(e) => {
                        heap.push(*e.key());
                        e.insert(p.neg());
                    }
                }
            }
            q.push((t, tc));
            if q.len() > limit || rem.len() > limit {
                crate::budget::check_terms(q.len().max(rem.len()));
            }
        }
        Some(LPoly { terms: q })
    }
}

/// How the atoms of a system map to key fields: the angles (one field per
/// sin/cos pair, zₖ = cos θₖ + i·sin θₖ) first, then the plain atoms.
struct Basis {
    /// (sin, cos) per angle field
    angles: Vec<(Var, Var)>,
    /// atom → (field, role)
    fields: FxHashMap<Var, (usize, Role)>,
    /// field → plain atom (for fields past the angles)
    plain: Vec<Var>,
    /// ((s-exponent, c-exponent), angle field) → the power's expansion
    powers: FxHashMap<(u32, u32, usize), LPoly>,
    /// (angle field, k) → (cos kθ, sin kθ)
    cis: std::cell::RefCell<FxHashMap<(usize, i32), (Poly, Poly)>>,
    /// the term products of the elimination and the conversion back
    work: crate::budget::WorkMeter,
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum Role {
    Sin,
    Cos,
    Plain,
}

impl Basis {
    /// `None` if a radical is among the atoms, there is no angle (nothing
    /// to gain), or the atoms need more than 32 fields.
    fn of(rows: &[Vec<Poly>]) -> Option<Basis> {
        let mut vars: Vec<Var> = rows
            .iter()
            .flatten()
            .flat_map(|p| p.vars())
            .collect::<rustc_hash::FxHashSet<Var>>()
            .into_iter()
            .collect();
        vars.sort_unstable();
        let mut angles: Vec<(Var, Var)> = Vec::new();
        let mut plain: Vec<Var> = Vec::new();
        for &v in &vars {
            if atom::is_radical(v) {
                return None;
            }
            let pair = if atom::kind(v) == atom::TRIG_COS {
                Some((atom::sin_partner(v), v))
            } else {
                atom::cos_partner(v).map(|c| (v, c))
            };
            match pair {
                Some(p) if !angles.contains(&p) => angles.push(p),
                Some(_) => {}
                None if atom::is_reducible(v) => return None,
                None => plain.push(v),
            }
        }
        if angles.is_empty() || angles.len() + plain.len() > FIELDS {
            return None;
        }
        let mut fields = FxHashMap::default();
        for (j, &(s, c)) in angles.iter().enumerate() {
            fields.insert(s, (j, Role::Sin));
            fields.insert(c, (j, Role::Cos));
        }
        for (i, &v) in plain.iter().enumerate() {
            fields.insert(v, (angles.len() + i, Role::Plain));
        }
        Some(Basis {
            angles,
            fields,
            plain,
            powers: FxHashMap::default(),
            cis: Default::default(),
            work: Default::default(),
        })
    }

    /// sinᵃθ·cosᵇθ of angle field j: ((z − z⁻¹)/2i)ᵃ·((z + z⁻¹)/2)ᵇ.
    fn power(&mut self, a: u32, b: u32, j: usize) -> Option<LPoly> {
        if let Some(p) = self.powers.get(&(a, b, j)) {
            return Some(p.clone());
        }
        let half = Q::new(1, 2)?;
        let sin = LPoly::from_unsorted(vec![
            (
                key_unit(j, 1),
                Cq {
                    re: Q::zero(),
                    im: -&half,
                },
            ),
            (
                key_unit(j, -1),
                Cq {
                    re: Q::zero(),
                    im: half.clone(),
                },
            ),
        ]);
        let cos = LPoly::from_unsorted(vec![
            (key_unit(j, 1), Cq::real(half.clone())),
            (key_unit(j, -1), Cq::real(half)),
        ]);
        let mut p = LPoly {
            terms: vec![(BIAS, Cq::real(Q::one()))],
        };
        for _ in 0..a {
            p = p.mul(&sin)?;
        }
        for _ in 0..b {
            p = p.mul(&cos)?;
        }
        self.powers.insert((a, b, j), p.clone());
        Some(p)
    }

    fn laurent_of(&mut self, p: &Poly) -> Option<LPoly> {
        let mut acc: FxHashMap<Key, Cq> = FxHashMap::default();
        for (m, c) in p.terms() {
            // the plain part as one key; the angles' powers by expansion
            let mut key = BIAS;
            let mut trig: smallvec::SmallVec<[(usize, u32, u32); 8]> = smallvec::SmallVec::new();
            for &(v, e) in m.pairs() {
                let &(j, role) = self.fields.get(&v)?;
                match role {
                    Role::Plain => {
                        let e = i32::try_from(e).ok().filter(|&e| e <= MAX_EXP)?;
                        key = key_mul(&key, &key_unit(j, e));
                    }
                    Role::Sin | Role::Cos => {
                        let at = match trig.iter().position(|t| t.0 == j) {
                            Some(i) => i,
                            None => {
                                trig.push((j, 0, 0));
                                trig.len() - 1
                            }
                        };
                        if role == Role::Sin {
                            trig[at].1 = e;
                        } else {
                            trig[at].2 = e;
                        }
                    }
                }
            }
            let mut term = LPoly {
                terms: vec![(key, Cq::real(c.clone()))],
            };
            for &(j, a, b) in &trig {
                if a + b > MAX_EXP as u32 {
                    return None;
                }
                let power = self.power(a, b, j)?;
                // a term of n angles expands into up to 3ⁿ: charged to
                // the elimination's meter, and the sum bounded below
                self.work.charge(term.len(), power.len());
                term = term.mul(&power)?;
            }
            for (k, c) in term.terms {
                match acc.entry(k) {
                    Entry::Occupied(mut e) => e.get_mut().add_assign(&c),
                    Entry::Vacant(e) => {
                        e.insert(c);
                    }
                }
            }
            crate::budget::check_terms(acc.len());
        }
        Some(LPoly::from_unsorted(acc.into_iter().collect()))
    }

    /// The real polynomial in sin and cos (reduced: cos at most linear in
    /// each angle) equal to a Laurent polynomial whose coefficients of z^e
    /// and z^−e are conjugate (the image of a real one).
    fn poly_of(&self, x: &LPoly) -> Poly {
        let (re, im) = self.substitute(&x.terms, 0);
        debug_assert!(im.is_zero(), "the image of a real polynomial");
        re
    }

    /// Real and imaginary parts of Σ aₑ·zᵉ with zⱼ = cos θⱼ + i·sin θⱼ for
    /// the angles from `j` on, Horner-like: grouped by the exponent k of
    /// angle j, each group substituted in the later angles first, then
    /// multiplied by cos kθⱼ + i·sin kθⱼ. (Expanding every term's product
    /// of all its angles at once made 2^angles terms per term to cancel.)
    fn substitute(&self, terms: &[(Key, Cq)], j: usize) -> (Poly, Poly) {
        let na = self.angles.len();
        if j == na {
            let (mut re, mut im) = (Vec::new(), Vec::new());
            for (k, c) in terms {
                // (plain exponents stay ≥ 0: Sylvester's quotients are minors)
                debug_assert!((0..self.plain.len()).all(|i| field(k, na + i) >= 0));
                let mono = Mono::from_pairs(
                    self.plain
                        .iter()
                        .enumerate()
                        .map(|(i, &v)| (v, field(k, na + i).max(0) as u32)),
                );
                re.push((mono.clone(), c.re.clone()));
                im.push((mono, c.im.clone()));
            }
            return (Poly::from_terms(re), Poly::from_terms(im));
        }
        let mut groups: std::collections::BTreeMap<i32, Vec<(Key, Cq)>> = Default::default();
        for t in terms {
            groups.entry(field(&t.0, j)).or_default().push(t.clone());
        }
        let (mut re, mut im) = (Vec::new(), Vec::new());
        for (k, group) in groups {
            let (gr, gi) = self.substitute(&group, j + 1);
            if k == 0 {
                re.extend_from_slice(gr.terms());
                im.extend_from_slice(gi.terms());
                continue;
            }
            let (c, s) = self.cis(j, k);
            self.work
                .charge(2 * (c.len() + s.len()), gr.len() + gi.len());
            re.extend_from_slice((&(&c * &gr) - &(&s * &gi)).terms());
            im.extend_from_slice((&(&c * &gi) + &(&s * &gr)).terms());
        }
        (Poly::from_terms(re), Poly::from_terms(im))
    }

    /// (cos kθ, sin kθ) of angle field j, reduced.
    fn cis(&self, j: usize, k: i32) -> (Poly, Poly) {
        if let Some(p) = self.cis.borrow().get(&(j, k)) {
            return p.clone();
        }
        let p = self.cis_of(j, k);
        self.cis.borrow_mut().insert((j, k), p.clone());
        p
    }

    fn cis_of(&self, j: usize, k: i32) -> (Poly, Poly) {
        let (s1, c1) = (Poly::var(self.angles[j].0), Poly::var(self.angles[j].1));
        let (mut c, mut s) = (Poly::one(), Poly::zero());
        for _ in 0..k.unsigned_abs() {
            let nc = crate::expr::reduce_poly(&(&(&c * &c1) - &(&s * &s1)));
            let ns = crate::expr::reduce_poly(&(&(&c * &s1) + &(&s * &c1)));
            (c, s) = (nc, ns);
        }
        if k < 0 {
            s = &Poly::zero() - &s;
        }
        (c, s)
    }
}

/// [`super::solve`] in the exponential basis: `None` when the system has no
/// angle, holds a radical or does not fit the keys (the free ring then
/// solves it), else the same answer as the free ring.
pub(super) fn solve(a: &[Vec<Expr>], rows: &[Vec<Poly>]) -> Option<Result<Vec<Expr>, SolveError>> {
    let n = rows.len();
    let mut basis = Basis::of(rows)?;
    let mut m: Vec<Vec<LPoly>> = Vec::with_capacity(n);
    for row in rows {
        let mut r = Vec::with_capacity(row.len());
        for p in row {
            r.push(basis.laurent_of(&crate::expr::reduce_poly(p))?);
        }
        m.push(r);
    }
    let singular = || SolveError::Singular {
        dependent: dependent_unknowns(a),
    };
    let mut prev = LPoly {
        terms: vec![(BIAS, Cq::real(Q::one()))],
    };
    for k in 0..n {
        let piv = (k..n)
            .filter(|&r| !m[r][k].is_zero())
            .min_by_key(|&r| m[r][k].len());
        let Some(p) = piv else {
            return Some(Err(singular()));
        };
        m.swap(k, p);
        for i in k + 1..n {
            for j in k + 1..=n {
                basis.work.charge(m[k][k].len(), m[i][j].len());
                basis.work.charge(m[i][k].len(), m[k][j].len());
                let t = m[k][k].mul(&m[i][j])?.sub(&m[i][k].mul(&m[k][j])?);
                basis.work.charge(t.len(), prev.len());
                m[i][j] = t.div_exact(&prev)?;
            }
            m[i][k] = LPoly::default();
        }
        prev = m[k][k].clone();
    }
    let det = m[n - 1][n - 1].clone();
    let mut xs = vec![LPoly::default(); n];
    for i in (0..n).rev() {
        basis.work.charge(det.len(), m[i][n].len());
        let mut t = det.mul(&m[i][n])?;
        for j in i + 1..n {
            basis.work.charge(m[i][j].len(), xs[j].len());
            t = t.sub(&m[i][j].mul(&xs[j])?);
        }
        basis.work.charge(t.len(), m[i][i].len());
        xs[i] = t.div_exact(&m[i][i])?;
    }
    let det = basis.poly_of(&det);
    Some(
        xs.iter()
            .map(|x| Expr::from_parts(basis.poly_of(x), det.clone()).map_err(|_| singular()))
            .collect(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// sin/cos of two coordinates and a parameter.
    fn atoms() -> [Var; 5] {
        let (s1, c1) = atom::intern_trig(&Expr::var(atom::coord("lq1", 0)));
        let (s2, c2) = atom::intern_trig(&Expr::var(atom::coord("lq2", 0)));
        [s1, c1, s2, c2, atom::param("lm")]
    }

    /// A polynomial from (coefficient, exponents of the five atoms) terms.
    fn poly(terms: &[(i64, [u32; 5])]) -> Poly {
        let v = atoms();
        Poly::from_terms(
            terms
                .iter()
                .map(|(c, e)| {
                    (
                        Mono::from_pairs((0..5).map(|i| (v[i], e[i]))),
                        Q::from_i64(*c),
                    )
                })
                .collect(),
        )
    }

    fn expr(p: Poly) -> Expr {
        Expr::from_parts(p, Poly::one()).expect("a polynomial")
    }

    #[test]
    fn keys_hold_signed_exponents() {
        let a = key_mul(&key_unit(0, -3), &key_unit(31, 127));
        assert_eq!((field(&a, 0), field(&a, 31), field(&a, 7)), (-3, 127, 0));
        let b = key_mul(&a, &key_unit(0, 5));
        assert_eq!(field(&b, 0), 2);
        assert_eq!(key_div(&b, &key_unit(0, 5)), a);
        // lexicographic on the exponents, the first field most significant
        assert!(key_unit(0, 1) > key_unit(0, -1));
        assert!(key_unit(0, -1) < key_unit(1, 100));
    }

    #[test]
    fn the_basis_is_exact_both_ways() {
        let [s1, c1, ..] = atoms();
        // cos² + sin² is 1 in the exponential basis
        let rows = vec![vec![poly(&[(1, [2, 0, 0, 0, 0]), (1, [0, 2, 0, 0, 0])])]];
        let mut b = Basis::of(&rows).expect("an angle");
        let one = b.laurent_of(&rows[0][0]).expect("fits");
        assert_eq!(one.terms, vec![(BIAS, Cq::real(Q::one()))]);
        // and back: 3·sin·cos²·m − 2·cos, reduced
        let p = poly(&[(3, [1, 2, 0, 0, 1]), (-2, [0, 1, 0, 0, 0])]);
        let l = b.laurent_of(&p);
        assert!(l.is_none(), "lm is not an atom of the rows");
        let rows = vec![vec![p.clone()]];
        let mut b = Basis::of(&rows).expect("an angle");
        let l = b.laurent_of(&p).expect("fits");
        let back = b.poly_of(&l);
        assert_eq!(back, crate::expr::reduce_poly(&p));
        assert!(back.contains_var(s1) && back.contains_var(c1));
    }

    #[test]
    fn exponents_past_the_keys_fall_back() {
        let big = poly(&[(1, [0, 0, 0, 0, 200]), (1, [1, 0, 0, 0, 0])]);
        let rows = vec![vec![big.clone(), Poly::one()]];
        assert!(solve(&[vec![expr(big)]], &rows).is_none());
    }

    #[test]
    fn a_system_without_angles_is_left_to_the_free_ring() {
        let p = poly(&[(2, [0, 0, 0, 0, 1])]);
        let rows = vec![vec![p.clone(), Poly::one()]];
        assert!(solve(&[vec![expr(p)]], &rows).is_none());
    }

    #[test]
    fn a_singular_system_names_its_unknowns() {
        let c = poly(&[(1, [0, 1, 0, 0, 0])]);
        let a = vec![
            vec![expr(c.clone()), expr(c.clone())],
            vec![expr(c.clone()), expr(c.clone())],
        ];
        let b = vec![Expr::one(), Expr::zero()];
        let rows = super::super::cleared_rows(&a, &b);
        match solve(&a, &rows) {
            Some(Err(SolveError::Singular { dependent })) => assert_eq!(dependent, vec![0, 1]),
            other => panic!("expected singular, got {other:?}"),
        }
    }

    fn small_poly() -> impl Strategy<Value = Poly> {
        prop::collection::vec((-3i64..=3, prop::array::uniform5(0u32..=2)), 1..4)
            .prop_map(|t| poly(&t))
    }

    proptest! {
        // 12 systems of 3 random trigonometric polynomials: each takes the
        // free ring ~0.3 s, and the suite's time is shared
        #![proptest_config(ProptestConfig::with_cases(12))]
        /// The exponential basis gives the free ring's canonical answer.
        #[test]
        fn agrees_with_the_free_ring(
            entries in prop::collection::vec(small_poly(), 9),
            rhs in prop::collection::vec(small_poly(), 3),
        ) {
            let a: Vec<Vec<Expr>> = entries.chunks(3).map(|r| r.iter().cloned().map(expr).collect()).collect();
            let b: Vec<Expr> = rhs.into_iter().map(expr).collect();
            let rows = super::super::cleared_rows(&a, &b);
            let free = super::super::solve_free(&a, rows.clone());
            match (solve(&a, &rows), free) {
                (Some(Ok(x)), Ok(y)) => prop_assert_eq!(x, y),
                (Some(Err(SolveError::Singular { dependent: d1 })), Err(SolveError::Singular { dependent: d2 })) => {
                    prop_assert_eq!(d1, d2)
                }
                (None, _) => {} // no angle drawn
                (l, f) => prop_assert!(false, "laurent {:?} vs free {:?}", l, f),
            }
        }
    }
}
