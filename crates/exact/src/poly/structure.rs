//! The shape of a [`Poly`]: its variables and degrees, coefficients with
//! respect to one variable, derivatives, substitution, evaluation and
//! renaming.

use super::packed::DegList;
use super::{Mono, Poly, Var};
use crate::num::Q;
use rustc_hash::FxHashMap;

impl Poly {
    /// Sorted list of `(var, max exponent)`.
    pub(super) fn max_degrees(&self) -> DegList {
        // dense scratch array when the variable ids are small enough
        let mut max_var = 0u32;
        let mut pairs = 0usize;
        for (m, _) in &self.terms {
            if let Some(&(v, _)) = m.0.last() {
                max_var = max_var.max(v);
            }
            pairs += m.0.len();
        }
        if pairs == 0 {
            return DegList::new();
        }
        if (max_var as usize) < 4 * pairs + 64 {
            let mut dense = vec![0u32; max_var as usize + 1];
            for (m, _) in &self.terms {
                for &(v, e) in m.0.iter() {
                    let d = &mut dense[v as usize];
                    if *d < e {
                        *d = e;
                    }
                }
            }
            return dense
                .iter()
                .enumerate()
                .filter(|p| *p.1 > 0)
                .map(|(v, &e)| (v as Var, e))
                .collect();
        }
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
    pub(super) fn split_by_vars(&self, set: &[Var]) -> Vec<Poly> {
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
}
