//! Dimensions not yet known: a dimension times powers of unknowns (the
//! dimensions of names nobody annotated), and the unification that solves
//! for those unknowns as evidence arrives.
//!
//! Dimensions multiply, so in exponent space a [`DimForm`] is a linear form
//! `base + Σ c_v·v` over ℚ. Equating two forms is one linear equation,
//! solved for one of its unknowns; solutions are kept substituted into each
//! other, so a form is normalized in one pass.

use super::dim::{factors, Dimension};
use crate::diag::Span;
use crate::num::Q;

/// The index of an unknown dimension (of one undeclared name).
pub(super) type DimVar = usize;

/// A dimension times rational powers of unknown dimensions.
///
/// Invariant: `vars` is sorted by unknown, without zero exponents.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct DimForm {
    /// The known part.
    pub base: Dimension,
    /// Unknowns and their exponents.
    pub vars: Vec<(DimVar, Q)>,
}

impl DimForm {
    pub fn known(d: Dimension) -> DimForm {
        DimForm {
            base: d,
            vars: Vec::new(),
        }
    }

    pub fn one() -> DimForm {
        DimForm::known(Dimension::one())
    }

    pub fn var(v: DimVar) -> DimForm {
        DimForm {
            base: Dimension::one(),
            vars: vec![(v, Q::from_i64(1))],
        }
    }

    /// The dimension, when no unknown is left in it.
    pub fn as_known(&self) -> Option<&Dimension> {
        self.vars.is_empty().then_some(&self.base)
    }

    pub fn mul(&self, other: &DimForm) -> DimForm {
        if other.vars.is_empty() {
            return DimForm {
                base: self.base.mul(&other.base),
                vars: self.vars.clone(),
            };
        }
        let mut vars = Vec::with_capacity(self.vars.len() + other.vars.len());
        let (mut i, mut j) = (0, 0);
        while i < self.vars.len() || j < other.vars.len() {
            let a = self.vars.get(i);
            let b = other.vars.get(j);
            match (a, b) {
                (Some(x), Some(y)) if x.0 == y.0 => {
                    let mut c = x.1.clone();
                    c += &y.1;
                    if !c.is_zero() {
                        vars.push((x.0, c));
                    }
                    i += 1;
                    j += 1;
                }
                (Some(x), Some(y)) if x.0 < y.0 => {
                    vars.push(x.clone());
                    i += 1;
                }
                (Some(x), None) => {
                    vars.push(x.clone());
                    i += 1;
                }
                (_, Some(y)) => {
                    vars.push(y.clone());
                    j += 1;
                }
                (None, None) => break,
            }
        }
        let f = DimForm {
            base: self.base.mul(&other.base),
            vars,
        };
        debug_assert!(f.vars.windows(2).all(|w| w[0].0 < w[1].0));
        f
    }

    pub fn div(&self, other: &DimForm) -> DimForm {
        if other.vars.is_empty() {
            return DimForm {
                base: self.base.div(&other.base),
                vars: self.vars.clone(),
            };
        }
        self.mul(&other.pow(&Q::from_i64(-1)))
    }

    pub fn pow(&self, p: &Q) -> DimForm {
        if p.is_zero() {
            return DimForm::one();
        }
        DimForm {
            base: self.base.pow(p),
            vars: self
                .vars
                .iter()
                .map(|(v, c)| {
                    let mut c = c.clone();
                    c *= p;
                    (*v, c)
                })
                .collect(),
        }
    }

    pub fn mentions(&self, v: DimVar) -> bool {
        self.vars.iter().any(|(w, _)| *w == v)
    }
}

/// Where an unknown's dimension was found.
#[derive(Clone, Debug)]
pub(super) struct Solution {
    /// The unknown's dimension, in unknowns not solved yet.
    pub form: DimForm,
    /// The expression whose dimension decided it.
    pub at: Span,
}

/// The unknown dimensions of a scene and what is known of them.
///
/// Invariant: a solution mentions only unknowns not solved yet (each new
/// solution is substituted into the earlier ones that mention it, found
/// through `users`, so the substitution costs what it changes, not the
/// number of unknowns).
#[derive(Default)]
pub(super) struct DimVars {
    names: Vec<String>,
    solved: Vec<Option<Solution>>,
    /// For each unknown, the solved unknowns whose solution may mention it.
    users: Vec<Vec<DimVar>>,
    /// Unknowns substituted so far, against `MAX_DIMENSION_WORK`.
    work: u64,
}

impl DimVars {
    /// A new unknown: the dimension of the name `name`.
    pub fn fresh(&mut self, name: &str) -> DimVar {
        self.names.push(name.to_string());
        self.solved.push(None);
        self.users.push(Vec::new());
        self.names.len() - 1
    }

    /// The solution of `v`, if evidence decided it.
    pub fn solution(&self, v: DimVar) -> Option<&Solution> {
        self.solved.get(v).and_then(Option::as_ref)
    }

    /// `f` with every solved unknown replaced by its solution.
    pub fn normalize(&self, f: &DimForm) -> DimForm {
        if f.vars.iter().all(|(v, _)| self.solved[*v].is_none()) {
            return f.clone();
        }
        let mut out = DimForm::known(f.base);
        for (v, c) in &f.vars {
            out = match &self.solved[*v] {
                Some(s) => out.mul(&s.form.pow(c)),
                None => out.mul(&DimForm::var(*v).pow(c)),
            };
        }
        out
    }

    /// Whether unification gave up on `MAX_DIMENSION_WORK` (every later
    /// unification fails, and the walker reports the limit).
    pub fn exhausted(&self) -> bool {
        self.work > crate::limits::MAX_DIMENSION_WORK
    }

    /// Make `a` and `b` the same dimension, solving for an unknown when they
    /// have one; `false` when they cannot be (both normalized then differ in
    /// their known parts only) or the work limit is reached.
    pub fn unify(&mut self, a: &DimForm, b: &DimForm, at: Span) -> bool {
        if self.exhausted() {
            return false;
        }
        if a.vars.is_empty() && b.vars.is_empty() {
            return a.base == b.base && !a.base.overflowed();
        }
        let d = self.normalize(&a.div(b));
        if d.base.overflowed() {
            return false;
        }
        let Some((v, c)) = d.vars.first().cloned() else {
            return d.base.is_one();
        };
        // v^c · rest = 1  ⇒  v = rest^(−1/c)
        let rest = d.div(&DimForm::var(v).pow(&c));
        let Some(inv) = c.recip() else {
            return false;
        };
        let form = rest.pow(&-inv);
        debug_assert!(!form.mentions(v));
        for u in std::mem::take(&mut self.users[v]) {
            let Some(s) = self.solved[u].as_mut() else {
                continue;
            };
            let Some(k) = s.form.vars.iter().position(|(w, _)| *w == v) else {
                continue; // listed twice, already substituted
            };
            self.work += 1 + form.vars.len() as u64;
            let e = s.form.vars[k].1.clone();
            let mut without = s.form.clone();
            without.vars.remove(k);
            s.form = without.mul(&form.pow(&e));
            for (w, _) in &form.vars {
                self.users[*w].push(u);
            }
        }
        for (w, _) in &form.vars {
            self.users[*w].push(v);
        }
        self.solved[v] = Some(Solution { form, at });
        true
    }

    /// A form as text: `length`, `dim(x)·length⁻¹`.
    pub fn unicode(&self, f: &DimForm) -> String {
        let f = self.normalize(f);
        if f.vars.is_empty() {
            return f.base.unicode();
        }
        let mut fs: Vec<(String, Q)> = f
            .vars
            .iter()
            .map(|(v, c)| (format!("dim({})", self.names[*v]), c.clone()))
            .collect();
        if !f.base.is_one() {
            fs.push((f.base.unicode(), Q::from_i64(1)));
        }
        factors(&fs, false)
    }

    /// "a length", "dimensionless", "of dimension dim(x)·length".
    pub fn phrase(&self, f: &DimForm) -> String {
        let f = self.normalize(f);
        match f.as_known() {
            Some(d) => d.phrase(),
            None => format!("of dimension {}", self.unicode(&f)),
        }
    }

    /// Like [`DimVars::phrase`], after "the others are".
    pub fn plural(&self, f: &DimForm) -> String {
        let f = self.normalize(f);
        match f.as_known() {
            Some(d) => d.plural(),
            None => format!("of dimension {}", self.unicode(&f)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unify_solves_and_detects_conflicts() {
        let mut vars = DimVars::default();
        let x = vars.fresh("x");
        let y = vars.fresh("y");
        let l = DimForm::known(Dimension::LENGTH);
        let t = DimForm::known(Dimension::TIME);
        // y = x·time, then x = length  ⇒  y = length·time
        assert!(vars.unify(&DimForm::var(y), &DimForm::var(x).mul(&t), Span::default()));
        assert!(vars.unify(
            &DimForm::var(x).pow(&Q::from_i64(2)),
            &l.mul(&l),
            Span::default()
        ));
        let yn = vars.normalize(&DimForm::var(y));
        assert_eq!(yn.as_known(), Some(&Dimension::from_small([0, 1, 1, 0, 0])));
        // a conflict: y is not a length
        assert!(!vars.unify(&DimForm::var(y), &l, Span::default()));
        assert_eq!(vars.unicode(&DimForm::var(y)), "length·time");
    }

    #[test]
    fn past_the_work_limit_nothing_unifies() {
        let mut vars = DimVars::default();
        let x = vars.fresh("x");
        vars.work = crate::limits::MAX_DIMENSION_WORK + 1;
        assert!(vars.exhausted());
        let l = DimForm::known(Dimension::LENGTH);
        assert!(!vars.unify(&DimForm::var(x), &l, Span::default()));
        assert!(!vars.unify(&l, &l, Span::default()));
    }
}
