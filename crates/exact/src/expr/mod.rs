//! Canonical expressions: rational functions over atoms.
//!
//! An [`Expr`] is `num / den` with `num`, `den` polynomials over ℚ in the
//! atoms of [`atom`]. The canonical form (every constructor goes through
//! [`Expr::from_parts`]) is:
//!
//! 1. *reduced*: no reducible atom appears squared (`cos²u → 1 − sin²u`,
//!    `√3² → 3`, `√P² → P`), in `num` or in `den`;
//! 2. *rationalized*: `den` contains no radical atom (`1/√3 = √3/3`);
//! 3. *in lowest terms*: `gcd(num, den) = 1` in the polynomial ring;
//! 4. *normalized*: `den` has leading coefficient 1 (so a constant `den` is 1).
//!
//! Polynomials are canonical (a unique sparse representation in a fixed
//! monomial order), so two equal polynomial expressions are structurally
//! equal, and so are two equal rational functions whose denominators are
//! free of `cos` atoms (the extension by radicals is a free module, and the
//! minimal radical-free denominator is unique). Denominators with `cos` are
//! kept as written rather than rationalized (that would multiply their size);
//! equality of such expressions is decided exactly by [`Expr::equals`]
//! (cross-multiplication and reduction modulo sin² + cos² = 1, which is exact
//! because reduced polynomials are unique representatives of the quotient ring).

#[doc(hidden)]
pub mod atom;
pub mod compact;
pub mod diff;
pub mod func;
pub mod hidden_zero;
pub mod latex;
pub mod print;
pub mod tape;

use crate::num::Q;
use crate::poly::{Mono, Poly, Var};
use std::fmt;
use std::sync::Arc;

/// An error of exact arithmetic: division by zero, an unsupported power, …
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct MathError {
    /// What went wrong.
    pub message: String,
    /// A suggestion for the user, when there is one.
    pub hint: Option<String>,
}

impl MathError {
    /// An error with a message and no hint.
    pub fn new(message: impl Into<String>) -> MathError {
        MathError {
            message: message.into(),
            hint: None,
        }
    }
    /// The same error with a hint attached.
    pub fn hint(mut self, h: impl Into<String>) -> MathError {
        self.hint = Some(h.into());
        self
    }
}

impl fmt::Display for MathError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.message)
    }
}

impl std::error::Error for MathError {}

#[derive(Clone, Debug, PartialEq, Eq, Hash)]
struct Rat {
    num: Poly,
    den: Poly,
}

/// A canonical exact expression (cheap to clone: shared).
///
/// Expressions can be built in code as well as parsed:
///
/// ```
/// use qdot_exact::expr::{func, Expr};
/// let (m, l, g) = (Expr::param("m"), Expr::param("l"), Expr::param("g"));
/// let th = Expr::coord("th", 0);
/// // E = ½·m·l²·θ̇², V = −m·g·l·cos θ
/// let half = Expr::rational(qdot_exact::num::Q::new(1, 2).unwrap());
/// let thd = th.dt();
/// let e = half.mul(&m).mul(&l.powi(2).unwrap()).mul(&thd.powi(2).unwrap());
/// let v = m.mul(&g).mul(&l).mul(&func::cos(&th)).neg();
/// let th_var = qdot_exact::expr::atom::coord("th", 0);
/// let thd_var = qdot_exact::expr::atom::coord("th", 1);
/// // d/dt(∂E/∂θ̇) + ∂V/∂θ
/// let lhs = e.diff(thd_var).dt().add(&v.diff(th_var));
/// assert_eq!(lhs.to_string(), "l^2*m*th'' + g*l*m*sin(th)");
/// // sin² + cos² = 1, exactly
/// let one = func::sin(&th).powi(2).unwrap().add(&func::cos(&th).powi(2).unwrap());
/// assert!(one.is_one());
/// ```
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Expr(Arc<Rat>);

// ---------------------------------------------------------------- reduction

/// Whether some reducible atom appears squared (checked from the kind bits,
/// without touching the atom table).
fn needs_reduction(p: &Poly) -> bool {
    p.terms()
        .iter()
        .any(|(m, _)| m.0.iter().any(|&(v, e)| e >= 2 && atom::is_reducible(v)))
}

/// Rewrite every `r^e` (r reducible, e ≥ 2) as `P^(e div 2) · r^(e mod 2)`.
/// Returns `None` when `p` is already reduced (the common case, checked
/// without touching the atom table).
fn reduce(p: &Poly) -> Option<Poly> {
    if !needs_reduction(p) {
        return None;
    }
    let mut out = p.clone();
    // Substitution may create new squares of other reducible atoms (a
    // polynomial square may contain radicals), so iterate to a fixpoint.
    loop {
        // collected, then merged once: adding term by term is quadratic
        let mut acc: Vec<(Mono, Q)> = Vec::with_capacity(out.len());
        let mut changed = false;
        for (m, c) in out.terms() {
            let mut rest = Mono::default();
            let mut factor = Poly::constant(c.clone());
            for &(v, e) in m.0.iter() {
                if e >= 2 && atom::is_reducible(v) {
                    if let Some(sq) = atom::square_of(v) {
                        changed = true;
                        factor = &factor * &sq.pow(e / 2);
                        if e % 2 == 1 {
                            rest.0.push((v, 1));
                        }
                        continue;
                    }
                }
                rest.0.push((v, e));
            }
            acc.extend_from_slice(factor.mul_mono(&rest, &Q::one()).terms());
            crate::budget::check_product(acc.len(), 1);
        }
        out = Poly::from_terms(acc);
        if !changed || !needs_reduction(&out) {
            return Some(out);
        }
    }
}

/// The reduced representative of a polynomial (cos² → 1 − sin², √3² → 3).
pub fn reduce_poly(p: &Poly) -> Poly {
    reduce(p).unwrap_or_else(|| p.clone())
}

fn reduced(p: Poly) -> Poly {
    match reduce(&p) {
        Some(r) => r,
        None => p,
    }
}

/// The refusal to divide by a polynomial in opaque constants that is zero
/// to 10^−[`hidden_zero::ZERO_DIGITS`] but not provably zero.
fn undecided_division(den: Poly) -> MathError {
    let shown = Expr::poly(den).to_string();
    let shown = if shown.chars().count() > 120 {
        "the denominator".to_string()
    } else {
        shown
    };
    MathError::new(format!(
        "this divisor may be zero: {shown} is 0 to {} digits, and qdot cannot prove it is not \
         (it holds atoms whose relations qdot does not use: constants such as cos(π/7), or \
         sin and cos of both x and x/2)",
        hidden_zero::ZERO_DIGITS
    ))
    .hint(
        "write a constant by its exact value if it has one, and an angle and its fraction on \
         one base (sin x as 2·sin(x/2)·cos(x/2)), or do not divide by it",
    )
}

/// The first radical atom of a polynomial, if any.
fn first_radical(p: &Poly) -> Option<Var> {
    for (m, _) in p.terms() {
        for &(v, _) in m.0.iter() {
            if atom::is_radical(v) {
                return Some(v);
            }
        }
    }
    None
}

impl Expr {
    // ------------------------------------------------------------ constructors

    /// The canonical form of `num / den`. Fails only when `den` is zero
    /// (after reduction: `den` may be a disguised zero such as `√2² − 2`).
    pub fn from_parts(num: Poly, den: Poly) -> Result<Expr, MathError> {
        crate::cancel::check();
        crate::budget::check_terms(num.len().max(den.len()));
        let mut num = reduced(num);
        let mut den = reduced(den);
        if den.is_zero() {
            return Err(MathError::new("division by zero"));
        }
        // Rationalize: multiply by the conjugate in each radical of den.
        let mut steps = 0;
        while let Some(r) = first_radical(&den) {
            steps += 1;
            if steps > crate::limits::MAX_RATIONALIZE_STEPS {
                return Err(MathError::new(format!(
                    "the denominator has more than {} radicals to rationalize",
                    crate::limits::MAX_RATIONALIZE_STEPS
                )));
            }
            let cs = den.coeffs_in(r);
            let a = cs.first().cloned().unwrap_or_default();
            let b = cs.get(1).cloned().unwrap_or_default();
            let conj = &a - &b.mul_mono(&Mono::var(r), &Q::one());
            let sq = atom::square_of(r).unwrap_or_default();
            num = reduced(&num * &conj);
            den = reduced(&(&a * &a) - &(&(&b * &b) * &sq));
            if den.is_zero() {
                return Err(MathError::new("division by zero"));
            }
        }
        if hidden_zero::may_be_zero(&den) {
            return Err(undecided_division(den));
        }
        Ok(Expr::normalize(num, den))
    }

    /// Lowest terms and a monic denominator; both parts already reduced and
    /// `den` radical-free and nonzero.
    fn normalize(num: Poly, den: Poly) -> Expr {
        if num.is_zero() {
            return Expr::zero();
        }
        if let Some(c) = den.as_constant() {
            let c = c.clone();
            let num = if c.is_one() {
                num
            } else {
                num.scale(&Q::one().checked_div(&c).unwrap_or_else(Q::one))
            };
            return Expr::poly(num);
        }
        let (num, den) = {
            let g = num.gcd(&den);
            if g.as_constant().is_some() {
                (num, den)
            } else {
                (
                    num.div_exact(&g).unwrap_or(num),
                    den.div_exact(&g).unwrap_or(den),
                )
            }
        };
        let lc = den.leading_coeff().cloned().unwrap_or_else(Q::one);
        if lc.is_one() {
            Expr::canonical(Rat { num, den })
        } else {
            let inv = Q::one().checked_div(&lc).unwrap_or_else(Q::one);
            Expr::canonical(Rat {
                num: num.scale(&inv),
                den: den.scale(&inv),
            })
        }
    }

    /// Wrap parts already in canonical form (checked in debug builds).
    #[inline]
    fn canonical(r: Rat) -> Expr {
        let e = Expr(Arc::new(r));
        e.debug_assert_canonical();
        e
    }

    /// Check the canonical-form invariants (see the type's documentation)
    /// in debug builds and under the fuzzer: reduced parts, a radical-free
    /// monic denominator, and — for parts small enough to check cheaply —
    /// lowest terms.
    #[inline]
    fn debug_assert_canonical(&self) {
        #[cfg(debug_assertions)]
        {
            let (num, den) = (&self.0.num, &self.0.den);
            debug_assert!(!den.is_zero(), "zero denominator");
            debug_assert!(!needs_reduction(num), "unreduced numerator: {num}");
            debug_assert!(!needs_reduction(den), "unreduced denominator: {den}");
            debug_assert!(
                first_radical(den).is_none(),
                "radical in the denominator: {den}"
            );
            debug_assert!(
                den.leading_coeff().is_some_and(Q::is_one),
                "denominator not monic: {den}"
            );
            debug_assert!(
                !num.is_zero() || den.is_one(),
                "zero with a denominator: 0/{den}"
            );
            if num.len() * den.len() <= 64 && !den.is_constant() {
                debug_assert!(
                    num.gcd(den).is_constant(),
                    "not in lowest terms: ({num})/({den})"
                );
            }
        }
    }

    /// A polynomial expression (must already be reduced).
    fn poly(p: Poly) -> Expr {
        Expr::canonical(Rat {
            num: p,
            den: Poly::one(),
        })
    }

    /// A polynomial, reduced.
    pub fn from_poly(p: Poly) -> Expr {
        Expr::poly(reduced(p))
    }

    /// The number 0.
    pub fn zero() -> Expr {
        Expr::poly(Poly::zero())
    }
    /// The number 1.
    pub fn one() -> Expr {
        Expr::poly(Poly::one())
    }
    /// The integer `n`.
    pub fn int(n: i64) -> Expr {
        Expr::poly(Poly::constant(Q::from_i64(n)))
    }
    /// The rational number `q`.
    pub fn rational(q: Q) -> Expr {
        Expr::poly(Poly::constant(q))
    }
    /// The atom `v` as an expression.
    pub fn var(v: Var) -> Expr {
        Expr::poly(Poly::var(v))
    }
    /// A parameter (a constant symbol), by name.
    pub fn param(name: &str) -> Expr {
        Expr::var(atom::param(name))
    }
    /// An unknown of a `solve` block (a symbol with no sign assumed).
    pub fn unknown(name: &str) -> Expr {
        Expr::var(atom::unknown(name))
    }
    /// The `order`-th time derivative of coordinate `name`.
    pub fn coord(name: &str, order: u32) -> Expr {
        Expr::var(atom::coord(name, order))
    }
    /// The `order`-th derivative of the given function of time `name`.
    pub fn given(name: &str, order: u32) -> Expr {
        Expr::var(atom::given(name, order))
    }
    /// The time t.
    pub fn time() -> Expr {
        Expr::var(atom::time())
    }
    /// The constant π (an atom: kept exact, never a decimal).
    pub fn pi() -> Expr {
        Expr::var(atom::pi())
    }

    // ------------------------------------------------------------ access

    /// The address of the shared representation: equal ids mean the same
    /// shared value (used to memoize work on shared subexpressions).
    pub fn id(&self) -> usize {
        Arc::as_ptr(&self.0) as usize
    }

    /// The numerator, a polynomial over ℚ in the atoms.
    pub fn num(&self) -> &Poly {
        &self.0.num
    }
    /// The denominator (leading coefficient 1; exactly 1 for a polynomial).
    pub fn den(&self) -> &Poly {
        &self.0.den
    }
    /// Whether the expression is 0.
    pub fn is_zero(&self) -> bool {
        self.0.num.is_zero()
    }
    /// Whether the expression is 1.
    pub fn is_one(&self) -> bool {
        self.0.num.is_one() && self.0.den.is_one()
    }
    /// Whether the expression is a polynomial in its atoms (denominator 1).
    pub fn is_poly(&self) -> bool {
        self.0.den.is_one()
    }
    /// The value, if the expression is a rational number.
    pub fn as_rational(&self) -> Option<Q> {
        if self.0.num.is_zero() {
            return Some(Q::zero());
        }
        if self.0.den.is_one() {
            return self.0.num.as_constant().cloned();
        }
        None
    }
    /// The variable, if the expression is exactly one atom.
    pub fn as_var(&self) -> Option<Var> {
        if !self.is_poly() || self.0.num.len() != 1 {
            return None;
        }
        let (m, c) = &self.0.num.terms()[0];
        if c.is_one() && m.0.len() == 1 && m.0[0].1 == 1 {
            Some(m.0[0].0)
        } else {
            None
        }
    }
    /// Every atom the expression mentions directly (sorted, unique).
    pub fn vars(&self) -> Vec<Var> {
        let mut v = self.0.num.vars();
        v.extend(self.0.den.vars());
        v.sort_unstable();
        v.dedup();
        v
    }
    /// Whether `v` occurs, directly or inside another atom's argument.
    pub fn depends_on(&self, v: Var) -> bool {
        diff::vars_depend_on(&self.vars(), v)
    }

    /// The first given function of time (`functions s`) the expression
    /// contains, at any depth, by name.
    pub fn given_function(&self) -> Option<Arc<str>> {
        self.vars().into_iter().find_map(|v| {
            std::iter::once(v)
                .chain(atom::inner_atoms(v).iter().copied())
                .find_map(|w| match atom::atom(w) {
                    Atom::Given(name, _) => Some(name.clone()),
                    _ => None,
                })
        })
    }

    /// Whether the expression changes with time by itself, not only
    /// through the coordinates: it holds t, or a given function of time.
    pub fn depends_on_time(&self) -> bool {
        self.depends_on(atom::time()) || self.given_function().is_some()
    }

    /// Exact equality, also for denominators with `cos` atoms.
    pub fn equals(&self, other: &Expr) -> bool {
        if self == other {
            return true;
        }
        if self.0.den == other.0.den {
            return false; // same denominator, canonical numerators differ
        }
        let lhs = reduced(&self.0.num * &other.0.den);
        let rhs = reduced(&other.0.num * &self.0.den);
        lhs == rhs
    }

    // ------------------------------------------------------------ arithmetic

    /// `self + o`.
    pub fn add(&self, o: &Expr) -> Expr {
        if self.is_zero() {
            return o.clone();
        }
        if o.is_zero() {
            return self.clone();
        }
        let (a, b, c, d) = (&self.0.num, &self.0.den, &o.0.num, &o.0.den);
        if b.is_one() && d.is_one() {
            return Expr::poly(a + c);
        }
        if d.is_one() || b.is_one() {
            // a/b + c = (a + c·b)/b is in lowest terms unless reducing c·b
            // (cos², √2²) changed it.
            let (p, q, den) = if d.is_one() { (a, c, b) } else { (c, a, d) };
            let prod = q * den;
            return match reduce(&prod) {
                None => Expr::finish(p + &prod, den.clone()),
                Some(r) => Expr::normalize(p + &r, den.clone()),
            };
        }
        if b == d {
            let n = a + c;
            return Expr::normalize_reduced(n, b.clone());
        }
        // Henrici: g = gcd(b, d), b = g·b', d = g·d'.
        let (_, b1, d1) = cofactors(b, d);
        let n = &reduced(a * &d1) + &reduced(c * &b1);
        let den = reduced(&b1 * d);
        Expr::normalize(n, den)
    }

    /// `−self`.
    pub fn neg(&self) -> Expr {
        Expr::canonical(Rat {
            num: -&self.0.num,
            den: self.0.den.clone(),
        })
    }

    /// `self − o`.
    pub fn sub(&self, o: &Expr) -> Expr {
        self.add(&o.neg())
    }

    /// `self · o`.
    pub fn mul(&self, o: &Expr) -> Expr {
        if self.is_zero() || o.is_zero() {
            return Expr::zero();
        }
        if self.is_one() {
            return o.clone();
        }
        if o.is_one() {
            return self.clone();
        }
        let (a, b, c, d) = (&self.0.num, &self.0.den, &o.0.num, &o.0.den);
        if b.is_one() && d.is_one() {
            return Expr::poly(reduced(a * c));
        }
        if let Some(k) = c.as_constant().filter(|_| d.is_one()) {
            return Expr::canonical(Rat {
                num: a.scale(k),
                den: b.clone(),
            });
        }
        if let Some(k) = a.as_constant().filter(|_| b.is_one()) {
            return Expr::canonical(Rat {
                num: c.scale(k),
                den: d.clone(),
            });
        }
        // (a/b)(c/d) with cross cancellation.
        let (_, a1, d1) = cofactors(a, d);
        let (_, c1, b1) = cofactors(c, b);
        let n = pmul(&a1, &c1);
        let den = pmul(&b1, &d1);
        // Reduction (cos², √2²) can create common factors: renormalize then.
        match (reduce(&n), reduce(&den)) {
            (None, None) => Expr::finish(n, den),
            (rn, rd) => Expr::normalize(rn.unwrap_or(n), rd.unwrap_or(den)),
        }
    }

    /// `self / o`; an error when `o` is zero.
    pub fn div(&self, o: &Expr) -> Result<Expr, MathError> {
        if o.is_zero() {
            return Err(MathError::new("division by zero"));
        }
        if let Some(q) = o.as_rational() {
            let inv = Q::one()
                .checked_div(&q)
                .ok_or_else(|| MathError::new("division by zero"))?;
            return Ok(self.scale(&inv));
        }
        Ok(self.mul(&o.recip()?))
    }

    /// Whether this nonzero expression may nevertheless be the number 0: a
    /// polynomial in constants such as sin(π/7) whose relations the
    /// canonical form does not use, zero to 9 digits ([`hidden_zero`]).
    /// False for 0 itself and for every expression without such constants.
    pub fn may_be_zero(&self) -> bool {
        hidden_zero::may_be_zero(&self.0.num)
    }

    /// `1 / self`.
    pub fn recip(&self) -> Result<Expr, MathError> {
        if self.is_zero() {
            return Err(MathError::new("division by zero"));
        }
        if self.may_be_zero() {
            return Err(undecided_division(self.0.num.clone()));
        }
        if first_radical(&self.0.num).is_none() {
            // Already reduced and coprime: only the new denominator's
            // leading coefficient needs normalizing.
            return Ok(Expr::finish(self.0.den.clone(), self.0.num.clone()));
        }
        Expr::from_parts(self.0.den.clone(), self.0.num.clone())
    }

    /// `self^n` for an integer n (negative powers need a nonzero base).
    pub fn powi(&self, n: i64) -> Result<Expr, MathError> {
        if n == 0 {
            return Ok(Expr::one());
        }
        if n < 0 {
            return self.recip()?.powi(-n);
        }
        let n = u32::try_from(n).map_err(|_| MathError::new("exponent too large"))?;
        if n > 10_000 {
            return Err(MathError::new(format!("exponent {n} is too large")));
        }
        if let Some(q) = self.as_rational() {
            // a number's power: its digits grow n-fold
            let digits = (q.log10_size() * f64::from(n)).floor() as usize + 1;
            let max = crate::limits::MAX_NUMBER_DIGITS;
            if digits > max {
                return Err(MathError::new(format!(
                    "this power of a number has about {digits} digits; qdot keeps numbers to {max} digits"
                )));
            }
        }
        if self.is_poly() {
            return Ok(Expr::poly(reduced(self.0.num.pow(n))));
        }
        let num = reduced(self.0.num.pow(n));
        let den = reduced(self.0.den.pow(n));
        Ok(Expr::normalize_reduced(num, den))
    }

    /// `q · self` for a rational number `q`.
    pub fn scale(&self, q: &Q) -> Expr {
        if q.is_zero() {
            return Expr::zero();
        }
        Expr::canonical(Rat {
            num: self.0.num.scale(q),
            den: self.0.den.clone(),
        })
    }

    /// num/den where num and den are reduced, den radical-free, and known
    /// coprime: only the denominator normalization remains.
    fn finish(num: Poly, den: Poly) -> Expr {
        if num.is_zero() {
            return Expr::zero();
        }
        if let Some(c) = den.as_constant() {
            let inv = Q::one().checked_div(c).unwrap_or_else(Q::one);
            return Expr::poly(num.scale(&inv));
        }
        let lc = den.leading_coeff().cloned().unwrap_or_else(Q::one);
        if lc.is_one() {
            return Expr::canonical(Rat { num, den });
        }
        let inv = Q::one().checked_div(&lc).unwrap_or_else(Q::one);
        Expr::canonical(Rat {
            num: num.scale(&inv),
            den: den.scale(&inv),
        })
    }

    fn normalize_reduced(num: Poly, den: Poly) -> Expr {
        let num = reduced(num);
        let den = reduced(den);
        if first_radical(&den).is_some() {
            return Expr::from_parts(num, den).unwrap_or_else(|_| Expr::zero());
        }
        Expr::normalize(num, den)
    }

    // ------------------------------------------------------------ substitution

    /// Replace atom `v` by `value` everywhere (also inside function atoms).
    pub fn subs(&self, v: Var, value: &Expr) -> Result<Expr, MathError> {
        let mut map = rustc_hash::FxHashMap::default();
        map.insert(v, value.clone());
        self.subs_many(&map)
    }

    /// Replace several atoms at once.
    pub fn subs_many(&self, map: &rustc_hash::FxHashMap<Var, Expr>) -> Result<Expr, MathError> {
        let n = subs_poly(&self.0.num, map)?;
        let d = subs_poly(&self.0.den, map)?;
        n.div(&d)
    }

    /// Numeric value with `f` giving each non-constant atom's value.
    pub fn eval_f64(&self, f: &dyn Fn(&Atom) -> Option<f64>) -> Option<f64> {
        let val = |v: Var| -> f64 { func::eval_atom(v, f).unwrap_or(f64::NAN) };
        let n = self.0.num.eval_f64(&val);
        let d = self.0.den.eval_f64(&val);
        (!n.is_nan() && !d.is_nan()).then_some(n / d)
    }
}

use atom::Atom;

/// Substitute into a polynomial, atom by atom.
fn subs_poly(p: &Poly, map: &rustc_hash::FxHashMap<Var, Expr>) -> Result<Expr, MathError> {
    let mut cache: rustc_hash::FxHashMap<Var, Option<Expr>> = Default::default();
    let mut acc = Expr::zero();
    for (m, c) in p.terms() {
        let mut term = Expr::rational(c.clone());
        for &(v, e) in m.0.iter() {
            let val = match cache.get(&v) {
                Some(x) => x.clone(),
                None => {
                    let x = func::subs_atom(v, map)?;
                    cache.insert(v, x.clone());
                    x
                }
            };
            let base = val.unwrap_or_else(|| Expr::var(v));
            term = term.mul(&base.powi(e as i64)?);
        }
        acc = acc.add(&term);
    }
    Ok(acc)
}

/// a·b with the cheap cases (a constant factor) done without a full product.
fn pmul(a: &Poly, b: &Poly) -> Poly {
    if let Some(k) = a.as_constant() {
        return if k.is_one() { b.clone() } else { b.scale(k) };
    }
    if let Some(k) = b.as_constant() {
        return if k.is_one() { a.clone() } else { a.scale(k) };
    }
    a * b
}

/// (gcd, a/gcd, b/gcd).
fn cofactors(a: &Poly, b: &Poly) -> (Poly, Poly, Poly) {
    if a.as_constant().is_some() || b.as_constant().is_some() {
        return (Poly::one(), a.clone(), b.clone());
    }
    if a.is_monomial() && b.is_monomial() {
        // gcd of two terms: the common power product.
        let (ma, ca) = &a.terms()[0];
        let (mb, cb) = &b.terms()[0];
        let g = ma.gcd(mb);
        if g.0.is_empty() {
            return (Poly::one(), a.clone(), b.clone());
        }
        let da = ma.div(&g).unwrap_or_else(|| ma.clone());
        let db = mb.div(&g).unwrap_or_else(|| mb.clone());
        return (
            Poly::monomial(g, Q::one()),
            Poly::monomial(da, ca.clone()),
            Poly::monomial(db, cb.clone()),
        );
    }
    let g = a.gcd(b);
    if g.as_constant().is_some() {
        return (Poly::one(), a.clone(), b.clone());
    }
    let a1 = a.div_exact(&g).unwrap_or_else(|| a.clone());
    let b1 = b.div_exact(&g).unwrap_or_else(|| b.clone());
    (g, a1, b1)
}

impl std::ops::Add for &Expr {
    type Output = Expr;
    fn add(self, o: &Expr) -> Expr {
        Expr::add(self, o)
    }
}
impl std::ops::Sub for &Expr {
    type Output = Expr;
    fn sub(self, o: &Expr) -> Expr {
        Expr::sub(self, o)
    }
}
impl std::ops::Mul for &Expr {
    type Output = Expr;
    fn mul(self, o: &Expr) -> Expr {
        Expr::mul(self, o)
    }
}
impl std::ops::Neg for &Expr {
    type Output = Expr;
    fn neg(self) -> Expr {
        Expr::neg(self)
    }
}
impl std::ops::Add for Expr {
    type Output = Expr;
    fn add(self, o: Expr) -> Expr {
        Expr::add(&self, &o)
    }
}
impl std::ops::Sub for Expr {
    type Output = Expr;
    fn sub(self, o: Expr) -> Expr {
        Expr::sub(&self, &o)
    }
}
impl std::ops::Mul for Expr {
    type Output = Expr;
    fn mul(self, o: Expr) -> Expr {
        Expr::mul(&self, &o)
    }
}
impl std::ops::Neg for Expr {
    type Output = Expr;
    fn neg(self) -> Expr {
        Expr::neg(&self)
    }
}

/// `{}` writes qdot's input syntax, which re-parses to the same expression
/// (`-k*x/m + g`, as SymPy's `str`); `{:#}` writes the Unicode a reader
/// sees (`−g/l·sin(θ)`, with `θ̈₃`, `√`, `π`).
///
/// ```
/// use qdot_exact::expr::{func, Expr};
/// let (g, l) = (Expr::param("g"), Expr::param("l"));
/// let theta = Expr::coord("theta", 0);
/// let e = g.mul(&func::sin(&theta)).mul(&l.powi(-1).unwrap()).neg();
/// assert_eq!(format!("{e}"), "-g*sin(theta)/l");
/// assert_eq!(format!("{e:#}"), "−g/l·sin(θ)");
/// assert_eq!(e.to_latex(), r"-\frac{g}{l} \sin\theta");
/// ```
impl fmt::Display for Expr {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if f.alternate() {
            f.write_str(&print::unicode(self))
        } else {
            f.write_str(&print::input(self))
        }
    }
}

impl Expr {
    /// The input syntax (what `{}` writes).
    pub fn to_input(&self) -> String {
        print::input(self)
    }

    /// The Unicode form (what `{:#}` writes).
    pub fn to_unicode(&self) -> String {
        print::unicode(self)
    }

    /// LaTeX (amsmath), with names turned into notation: `theta3` →
    /// `\theta_{3}`, `x''` → `\ddot{x}`.
    pub fn to_latex(&self) -> String {
        latex::latex(self)
    }
}
