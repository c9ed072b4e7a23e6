//! Exact rational numbers with a small-value fast path.
//!
//! [`Q`] is either `Small(n, d)` — a reduced fraction of two machine integers —
//! or `Big` — a heap-allocated [`BigRational`] used only when the reduced value
//! does not fit `Small`. Because the representation is canonical, equal values
//! always use the same variant, which keeps `Eq`/`Hash` cheap and consistent.
//!
//! Arithmetic on `Small` operands uses checked `i64`/`i128` intermediates and
//! falls back to `BigRational` on overflow; `Big` results are demoted back to
//! `Small` whenever they fit.

use num_bigint::BigInt;
use num_integer::Integer;
use num_rational::{BigRational, Ratio};
use num_traits::{One, Signed, ToPrimitive, Zero};
use std::cmp::Ordering;
use std::fmt;
use std::hash::{Hash, Hasher};
use std::ops::{Add, AddAssign, Div, Mul, MulAssign, Neg, Sub, SubAssign};
use std::str::FromStr;

/// An exact rational number.
///
/// Invariants (relied upon by `PartialEq`, `Hash` and all arithmetic):
/// * `Small(n, d)`: `d > 0`, `gcd(n, d) == 1`, `n != i64::MIN`, `d != i64::MIN`
///   (so negation and reciprocal never overflow).
/// * `Big(r)`: `r` is normalized (reduced, positive denominator) and does NOT fit
///   the `Small` invariants.
///
/// The representation is private: values are built by the constructors
/// ([`Q::new`], [`Q::from_big`], …), so the invariants always hold.
#[derive(Clone, Debug)]
pub struct Q(Repr);

/// The representation of a [`Q`], private to it: machine integers when the
/// value fits, a boxed `BigRational` otherwise.
#[derive(Clone, Debug)]
pub(crate) enum Repr {
    /// A reduced fraction `n/d` of machine integers.
    Small(i64, i64),
    /// A value that does not fit `Small`.
    Big(Box<BigRational>),
}

/// Error returned by [`Q::from_str`].
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ParseQError {
    msg: String,
}

impl fmt::Display for ParseQError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "invalid rational number: {}", self.msg)
    }
}

impl std::error::Error for ParseQError {}

// ---------------------------------------------------------------------------
// integer helpers
// ---------------------------------------------------------------------------

/// Binary gcd on `u64`.
#[inline]
pub fn gcd_u64(mut a: u64, mut b: u64) -> u64 {
    if a == 0 {
        return b;
    }
    if b == 0 {
        return a;
    }
    let shift = (a | b).trailing_zeros();
    a >>= a.trailing_zeros();
    loop {
        b >>= b.trailing_zeros();
        if a > b {
            std::mem::swap(&mut a, &mut b);
        }
        b -= a;
        if b == 0 {
            return a << shift;
        }
    }
}

/// Binary gcd on `u128` (drops to `u64` when both operands fit).
#[inline]
fn gcd_u128(mut a: u128, mut b: u128) -> u128 {
    if a <= u64::MAX as u128 && b <= u64::MAX as u128 {
        return gcd_u64(a as u64, b as u64) as u128;
    }
    if a == 0 {
        return b;
    }
    if b == 0 {
        return a;
    }
    let shift = (a | b).trailing_zeros();
    a >>= a.trailing_zeros();
    loop {
        b >>= b.trailing_zeros();
        if a > b {
            std::mem::swap(&mut a, &mut b);
        }
        b -= a;
        if b == 0 {
            return a << shift;
        }
        if a <= u64::MAX as u128 && b <= u64::MAX as u128 {
            return (gcd_u64(a as u64, b as u64) as u128) << shift;
        }
    }
}

/// 2^53: integers up to this magnitude are exactly representable in `f64`.
const F64_EXACT: i64 = 1 << 53;

impl Q {
    /// `(n, d)` when the value is a fraction of machine integers (the fast
    /// paths of modular arithmetic).
    #[inline]
    pub fn small(&self) -> Option<(i64, i64)> {
        match self.0 {
            Repr::Small(n, d) => Some((n, d)),
            Repr::Big(_) => None,
        }
    }

    // -----------------------------------------------------------------------
    // internal constructors
    // -----------------------------------------------------------------------

    /// From an already reduced fraction with `d > 0`.
    #[inline]
    fn from_reduced_i128(n: i128, d: i128) -> Q {
        if n > i64::MIN as i128 && n <= i64::MAX as i128 && d <= i64::MAX as i128 {
            Q(Repr::Small(n as i64, d as i64))
        } else {
            Q(Repr::Big(Box::new(BigRational::new_raw(
                BigInt::from(n),
                BigInt::from(d),
            ))))
        }
    }

    /// From an arbitrary fraction with `d != 0`, `n` and `d` not `i128::MIN`.
    #[inline]
    fn from_i128_frac(n: i128, d: i128) -> Q {
        debug_assert!(d != 0);
        let (mut n, mut d) = if d < 0 { (-n, -d) } else { (n, d) };
        if n == 0 {
            return Q::zero();
        }
        if d != 1 {
            let g = gcd_u128(n.unsigned_abs(), d as u128) as i128;
            if g != 1 {
                n /= g;
                d /= g;
            }
        }
        Q::from_reduced_i128(n, d)
    }

    #[inline]
    fn small_int(n: i64) -> Q {
        if n == i64::MIN {
            Q(Repr::Big(Box::new(BigRational::from_integer(
                BigInt::from(n),
            ))))
        } else {
            Q(Repr::Small(n, 1))
        }
    }

    // -----------------------------------------------------------------------
    // public constructors
    // -----------------------------------------------------------------------

    /// The number 0.
    #[inline]
    pub const fn zero() -> Q {
        Q(Repr::Small(0, 1))
    }

    /// The number 1.
    #[inline]
    pub const fn one() -> Q {
        Q(Repr::Small(1, 1))
    }

    /// The integer `n`.
    #[inline]
    pub fn from_i64(n: i64) -> Q {
        Q::small_int(n)
    }

    /// The fraction `n/d`, or `None` if `d == 0`.
    pub fn new(n: i64, d: i64) -> Option<Q> {
        if d == 0 {
            return None;
        }
        Some(Q::from_i128_frac(n as i128, d as i128))
    }

    /// From a `BigRational` (normalized, as every `BigRational` produced by the
    /// `num-rational` API is); demoted to `Small` when it fits.
    pub fn from_big(r: BigRational) -> Q {
        let r = if r.denom().is_negative() {
            BigRational::new(r.numer().clone(), r.denom().clone())
        } else {
            r
        };
        match (r.numer().to_i64(), r.denom().to_i64()) {
            (Some(n), Some(d)) if n != i64::MIN => Q(Repr::Small(n, d)),
            _ => Q(Repr::Big(Box::new(r))),
        }
    }

    /// From a `BigInt`; demoted to `Small` when it fits.
    pub fn from_bigint(n: BigInt) -> Q {
        match n.to_i64() {
            Some(v) if v != i64::MIN => Q(Repr::Small(v, 1)),
            _ => Q(Repr::Big(Box::new(BigRational::from_integer(n)))),
        }
    }

    /// The value as a `BigRational`.
    pub fn to_big(&self) -> BigRational {
        match &self.0 {
            Repr::Small(n, d) => BigRational::new_raw(BigInt::from(*n), BigInt::from(*d)),
            Repr::Big(r) => (**r).clone(),
        }
    }

    /// The (reduced) numerator; carries the sign.
    pub fn numer(&self) -> BigInt {
        match &self.0 {
            Repr::Small(n, _) => BigInt::from(*n),
            Repr::Big(r) => r.numer().clone(),
        }
    }

    /// The (reduced, positive) denominator.
    pub fn denom(&self) -> BigInt {
        match &self.0 {
            Repr::Small(_, d) => BigInt::from(*d),
            Repr::Big(r) => r.denom().clone(),
        }
    }

    // -----------------------------------------------------------------------
    // predicates
    // -----------------------------------------------------------------------

    /// `self == 0`.
    #[inline]
    pub fn is_zero(&self) -> bool {
        matches!(self.0, Repr::Small(0, _))
    }

    /// `self == 1`.
    #[inline]
    pub fn is_one(&self) -> bool {
        matches!(self.0, Repr::Small(1, 1))
    }

    /// `self` is an integer.
    #[inline]
    pub fn is_integer(&self) -> bool {
        match &self.0 {
            Repr::Small(_, d) => *d == 1,
            Repr::Big(r) => r.denom().is_one(),
        }
    }

    /// `self < 0`.
    #[inline]
    pub fn is_negative(&self) -> bool {
        match &self.0 {
            Repr::Small(n, _) => *n < 0,
            Repr::Big(r) => r.numer().is_negative(),
        }
    }

    /// `self > 0`.
    #[inline]
    pub fn is_positive(&self) -> bool {
        match &self.0 {
            Repr::Small(n, _) => *n > 0,
            Repr::Big(r) => r.numer().is_positive(),
        }
    }

    /// -1, 0 or 1.
    #[inline]
    pub fn signum(&self) -> i32 {
        match &self.0 {
            Repr::Small(n, _) => n.signum() as i32,
            Repr::Big(r) => {
                if r.numer().is_negative() {
                    -1
                } else {
                    1
                }
            }
        }
    }

    // -----------------------------------------------------------------------
    // unary operations
    // -----------------------------------------------------------------------

    /// `|self|`.
    pub fn abs(&self) -> Q {
        match &self.0 {
            Repr::Small(n, d) => Q(Repr::Small(n.abs(), *d)),
            Repr::Big(r) => Q(Repr::Big(Box::new(r.abs()))),
        }
    }

    /// `1/self`, or `None` if `self == 0`.
    pub fn recip(&self) -> Option<Q> {
        match &self.0 {
            Repr::Small(0, _) => None,
            Repr::Small(n, d) => {
                if *n < 0 {
                    Some(Q(Repr::Small(-*d, -*n)))
                } else {
                    Some(Q(Repr::Small(*d, *n)))
                }
            }
            Repr::Big(r) => Some(Q::from_big(r.recip())),
        }
    }

    /// log₁₀ of the larger of |numerator| and denominator (from the bit
    /// length for big numbers: within 0.31): a power qᵏ has about
    /// k·log₁₀ + 1 digits.
    pub fn log10_size(&self) -> f64 {
        match &self.0 {
            Repr::Small(n, d) => (n.unsigned_abs().max(d.unsigned_abs()) as f64).log10(),
            Repr::Big(r) => {
                r.numer().bits().max(r.denom().bits()) as f64 * std::f64::consts::LOG10_2
            }
        }
    }

    /// Charge an operation on `a` and `b` past machine size to the work
    /// budget ([`crate::budget::charge_big_numbers`]).
    fn charge(a: &Q, b: &Q) {
        crate::budget::charge_big_numbers(a.words(), b.words(), || {
            (a.log10_size().max(b.log10_size()) as usize).saturating_add(1)
        });
    }

    /// The 64-bit words of numerator and denominator (1 for a machine
    /// fraction): what an operation on the number costs.
    fn words(&self) -> usize {
        match &self.0 {
            Repr::Small(..) => 1,
            Repr::Big(r) => (r.numer().bits() + r.denom().bits()).div_ceil(64) as usize,
        }
    }

    /// `self^e`; `None` for `0^e` with `e < 0`. `0^0 == 1`.
    pub fn pow(&self, e: i32) -> Option<Q> {
        if e < 0 {
            let r = self.recip()?;
            Some(r.pow_u32(e.unsigned_abs()))
        } else {
            Some(self.pow_u32(e as u32))
        }
    }

    /// `self^e` for a non-negative exponent.
    pub fn pow_u32(&self, mut e: u32) -> Q {
        let mut result = Q::one();
        if e == 0 {
            return result;
        }
        if self.is_zero() || self.is_one() {
            return self.clone();
        }
        let mut base = self.clone();
        loop {
            if e & 1 == 1 {
                result = &result * &base;
            }
            e >>= 1;
            if e == 0 {
                break;
            }
            base = &base * &base;
        }
        result
    }

    /// `self / other`, or `None` if `other == 0`.
    pub fn checked_div(&self, other: &Q) -> Option<Q> {
        let r = other.recip()?;
        Some(self * &r)
    }

    /// Nearest `f64` (correctly rounded for `Big` and for small operands; huge
    /// magnitudes become `±inf`, tiny ones `0`).
    pub fn to_f64(&self) -> f64 {
        match &self.0 {
            Repr::Small(n, d) => {
                if n.abs() <= F64_EXACT && *d <= F64_EXACT {
                    *n as f64 / *d as f64
                } else {
                    Ratio::new_raw(*n, *d)
                        .to_f64()
                        .unwrap_or(*n as f64 / *d as f64)
                }
            }
            Repr::Big(r) => r.to_f64().unwrap_or_else(|| {
                // `ratio_to_f64` does not fail for BigInt; keep a fallback anyway.
                let n = r.numer().to_f64().unwrap_or(f64::NAN);
                let d = r.denom().to_f64().unwrap_or(f64::NAN);
                n / d
            }),
        }
    }

    /// The value as `i64` if it is an integer that fits.
    pub fn as_i64(&self) -> Option<i64> {
        match &self.0 {
            Repr::Small(n, 1) => Some(*n),
            Repr::Small(..) => None,
            Repr::Big(r) => {
                if r.denom().is_one() {
                    r.numer().to_i64()
                } else {
                    None
                }
            }
        }
    }

    /// Positive rational gcd: `gcd(numerators) / lcm(denominators)`;
    /// `gcd(0, x) == |x|`, `gcd(0, 0) == 0`.
    pub fn gcd(&self, other: &Q) -> Q {
        match (&self.0, &other.0) {
            (Repr::Small(a, b), Repr::Small(c, d)) => {
                let g = gcd_u64(a.unsigned_abs(), c.unsigned_abs());
                if g == 0 {
                    return Q::zero();
                }
                let h = gcd_u64(*b as u64, *d as u64);
                let l = (*b as u128 / h as u128) * (*d as u128);
                // gcd(g, l) == 1 since g | a, c and l | b*d.
                Q::from_reduced_i128(g as i128, l as i128)
            }
            _ => {
                if self.is_zero() {
                    return other.abs();
                }
                if other.is_zero() {
                    return self.abs();
                }
                Q::charge(self, other);
                let (x, y) = (self.to_big(), other.to_big());
                let n = x.numer().gcd(y.numer());
                let d = x.denom().lcm(y.denom());
                Q::from_big(BigRational::new_raw(n, d))
            }
        }
    }

    /// Floor of the value as a `BigInt`.
    pub fn floor_bigint(&self) -> BigInt {
        match &self.0 {
            Repr::Small(n, d) => BigInt::from(n.div_euclid(*d)),
            Repr::Big(r) => r.floor().to_integer(),
        }
    }

    // -----------------------------------------------------------------------
    // slow paths
    // -----------------------------------------------------------------------

    /// The integer value (only meaningful when `is_integer()`), borrowed if big.
    #[inline]
    fn int_cow(&self) -> std::borrow::Cow<'_, BigInt> {
        match &self.0 {
            Repr::Small(n, _) => std::borrow::Cow::Owned(BigInt::from(*n)),
            Repr::Big(r) => std::borrow::Cow::Borrowed(r.numer()),
        }
    }

    /// Big-operand slow path; integer operands avoid `BigRational`'s gcds.
    #[cold]
    fn big_op(
        a: &Q,
        b: &Q,
        op: fn(&BigRational, &BigRational) -> BigRational,
        iop: Option<fn(&BigInt, &BigInt) -> BigInt>,
    ) -> Q {
        Q::charge(a, b);
        if let Some(iop) = iop {
            if a.is_integer() && b.is_integer() {
                return Q::from_bigint(iop(&a.int_cow(), &b.int_cow()));
            }
        }
        match (&a.0, &b.0) {
            (Repr::Big(x), Repr::Big(y)) => Q::from_big(op(x, y)),
            (Repr::Big(x), _) => Q::from_big(op(x, &b.to_big())),
            (_, Repr::Big(y)) => Q::from_big(op(&a.to_big(), y)),
            _ => Q::from_big(op(&a.to_big(), &b.to_big())),
        }
    }

    #[inline]
    fn add_ref(&self, other: &Q) -> Q {
        if let (Repr::Small(a, b), Repr::Small(c, d)) = (&self.0, &other.0) {
            let (a, b, c, d) = (*a, *b, *c, *d);
            if b == d {
                if b == 1 {
                    return match a.checked_add(c) {
                        Some(s) if s != i64::MIN => Q(Repr::Small(s, 1)),
                        _ => Q::from_reduced_i128(a as i128 + c as i128, 1),
                    };
                }
                return Q::from_i128_frac(a as i128 + c as i128, b as i128);
            }
            let n = a as i128 * d as i128 + c as i128 * b as i128;
            return Q::from_i128_frac(n, b as i128 * d as i128);
        }
        Q::big_op(self, other, |x, y| x + y, Some(|x, y| x + y))
    }

    #[inline]
    fn sub_ref(&self, other: &Q) -> Q {
        if let (Repr::Small(a, b), Repr::Small(c, d)) = (&self.0, &other.0) {
            let (a, b, c, d) = (*a, *b, *c, *d);
            if b == d {
                if b == 1 {
                    return match a.checked_sub(c) {
                        Some(s) if s != i64::MIN => Q(Repr::Small(s, 1)),
                        _ => Q::from_reduced_i128(a as i128 - c as i128, 1),
                    };
                }
                return Q::from_i128_frac(a as i128 - c as i128, b as i128);
            }
            let n = a as i128 * d as i128 - c as i128 * b as i128;
            return Q::from_i128_frac(n, b as i128 * d as i128);
        }
        Q::big_op(self, other, |x, y| x - y, Some(|x, y| x - y))
    }

    #[inline]
    fn mul_ref(&self, other: &Q) -> Q {
        if let (Repr::Small(a, b), Repr::Small(c, d)) = (&self.0, &other.0) {
            let (a, b, c, d) = (*a, *b, *c, *d);
            if a == 0 || c == 0 {
                return Q::zero();
            }
            if b == 1 && d == 1 {
                return match a.checked_mul(c) {
                    Some(p) if p != i64::MIN => Q(Repr::Small(p, 1)),
                    _ => Q::from_reduced_i128(a as i128 * c as i128, 1),
                };
            }
            let g1 = gcd_u64(a.unsigned_abs(), d as u64) as i64;
            let g2 = gcd_u64(c.unsigned_abs(), b as u64) as i64;
            let n = (a / g1) as i128 * (c / g2) as i128;
            let den = (b / g2) as i128 * (d / g1) as i128;
            return Q::from_reduced_i128(n, den);
        }
        if self.is_zero() || other.is_zero() {
            return Q::zero();
        }
        Q::big_op(self, other, |x, y| x * y, Some(|x, y| x * y))
    }

    #[inline]
    fn neg_ref(&self) -> Q {
        match &self.0 {
            Repr::Small(n, d) => Q(Repr::Small(-*n, *d)),
            Repr::Big(r) => Q::from_big(-(**r).clone()),
        }
    }
}

// ---------------------------------------------------------------------------
// conversions
// ---------------------------------------------------------------------------

impl Default for Q {
    fn default() -> Q {
        Q::zero()
    }
}

impl From<i64> for Q {
    fn from(n: i64) -> Q {
        Q::from_i64(n)
    }
}

impl From<i32> for Q {
    fn from(n: i32) -> Q {
        Q(Repr::Small(n as i64, 1))
    }
}

impl From<BigInt> for Q {
    fn from(n: BigInt) -> Q {
        Q::from_bigint(n)
    }
}

impl From<BigRational> for Q {
    fn from(r: BigRational) -> Q {
        Q::from_big(r)
    }
}

// ---------------------------------------------------------------------------
// equality, hashing, ordering
// ---------------------------------------------------------------------------

impl PartialEq for Q {
    #[inline]
    fn eq(&self, other: &Q) -> bool {
        match (&self.0, &other.0) {
            (Repr::Small(a, b), Repr::Small(c, d)) => a == c && b == d,
            (Repr::Big(x), Repr::Big(y)) => x == y,
            // canonical representation: a Big never equals a Small
            _ => false,
        }
    }
}

impl Eq for Q {}

impl Hash for Q {
    fn hash<H: Hasher>(&self, state: &mut H) {
        match &self.0 {
            Repr::Small(n, d) => {
                state.write_u8(0);
                state.write_i64(*n);
                state.write_i64(*d);
            }
            Repr::Big(r) => {
                state.write_u8(1);
                r.numer().hash(state);
                r.denom().hash(state);
            }
        }
    }
}

impl Ord for Q {
    fn cmp(&self, other: &Q) -> Ordering {
        match (&self.0, &other.0) {
            (Repr::Small(a, b), Repr::Small(c, d)) => {
                if b == d {
                    a.cmp(c)
                } else {
                    (*a as i128 * *d as i128).cmp(&(*c as i128 * *b as i128))
                }
            }
            _ => {
                let (s, t) = (self.signum(), other.signum());
                if s != t {
                    return s.cmp(&t);
                }
                self.to_big().cmp(&other.to_big())
            }
        }
    }
}

impl PartialOrd for Q {
    fn partial_cmp(&self, other: &Q) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

// ---------------------------------------------------------------------------
// formatting and parsing
// ---------------------------------------------------------------------------

impl fmt::Display for Q {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.0 {
            Repr::Small(n, 1) => write!(f, "{n}"),
            Repr::Small(n, d) => write!(f, "{n}/{d}"),
            Repr::Big(r) => {
                if r.denom().is_one() {
                    write!(f, "{}", r.numer())
                } else {
                    write!(f, "{}/{}", r.numer(), r.denom())
                }
            }
        }
    }
}

fn parse_int(s: &str) -> Result<BigInt, ParseQError> {
    let err = || ParseQError {
        msg: format!("{s:?}"),
    };
    let digits = s.strip_prefix(['-', '+']).unwrap_or(s);
    if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
        return Err(err());
    }
    BigInt::from_str(s).map_err(|_| err())
}

/// Parses `"int"`, `"int/int"` or a decimal `"int.digits"` (exactly).
fn parse_num(s: &str) -> Result<Q, ParseQError> {
    if let Ok(v) = s.parse::<i64>() {
        return Ok(Q::from_i64(v));
    }
    if let Some((ip, fp)) = s.split_once('.') {
        if fp.is_empty() || !fp.bytes().all(|b| b.is_ascii_digit()) {
            return Err(ParseQError {
                msg: format!("{s:?}"),
            });
        }
        let neg = ip.starts_with('-');
        let ip_digits = ip.strip_prefix(['-', '+']).unwrap_or(ip);
        let whole = if ip_digits.is_empty() {
            BigInt::zero()
        } else {
            parse_int(ip_digits)?
        };
        let frac = parse_int(fp)?;
        let scale = num_traits::pow(BigInt::from(10u32), fp.len());
        let mut n = whole * &scale + frac;
        if neg {
            n = -n;
        }
        return Ok(Q::from_big(BigRational::new(n, scale)));
    }
    Ok(Q::from_bigint(parse_int(s)?))
}

impl FromStr for Q {
    type Err = ParseQError;

    /// Accepts `-3`, `14/23`, `-14/23`, `3/-6` and exact decimals like `0.25`
    /// (surrounding whitespace is ignored).
    fn from_str(s: &str) -> Result<Q, ParseQError> {
        let s = s.trim();
        match s.split_once('/') {
            None => parse_num(s),
            Some((n, d)) => {
                let n = parse_num(n.trim())?;
                let d = parse_num(d.trim())?;
                n.checked_div(&d).ok_or_else(|| ParseQError {
                    msg: format!("zero denominator in {s:?}"),
                })
            }
        }
    }
}

// ---------------------------------------------------------------------------
// operator impls
// ---------------------------------------------------------------------------

macro_rules! binop {
    ($tr:ident, $m:ident, $f:ident) => {
        impl $tr<&Q> for &Q {
            type Output = Q;
            #[inline]
            fn $m(self, rhs: &Q) -> Q {
                self.$f(rhs)
            }
        }
        impl $tr<Q> for &Q {
            type Output = Q;
            #[inline]
            fn $m(self, rhs: Q) -> Q {
                self.$f(&rhs)
            }
        }
        impl $tr<&Q> for Q {
            type Output = Q;
            #[inline]
            fn $m(self, rhs: &Q) -> Q {
                (&self).$f(rhs)
            }
        }
        impl $tr<Q> for Q {
            type Output = Q;
            #[inline]
            fn $m(self, rhs: Q) -> Q {
                (&self).$f(&rhs)
            }
        }
    };
}

binop!(Add, add, add_ref);
binop!(Sub, sub, sub_ref);
binop!(Mul, mul, mul_ref);

impl Q {
    /// Division for the operator impls; panics on division by zero.
    #[inline]
    fn div_ref(&self, rhs: &Q) -> Q {
        match self.checked_div(rhs) {
            Some(q) => q,
            // qdot's own code divides only with `checked_div`: the library
            // builds without this impl, so no input reaches it
            None => panic!("qdot::num::Q: division by zero"), // ok: `/`'s documented contract
        }
    }
}

// `Div` panics when the divisor is zero (documented); use `checked_div` otherwise.
binop!(Div, div, div_ref);

impl Neg for Q {
    type Output = Q;
    #[inline]
    fn neg(self) -> Q {
        match self.0 {
            Repr::Small(n, d) => Q(Repr::Small(-n, d)),
            Repr::Big(r) => Q::from_big(-*r),
        }
    }
}

impl Neg for &Q {
    type Output = Q;
    #[inline]
    fn neg(self) -> Q {
        self.neg_ref()
    }
}

impl AddAssign<&Q> for Q {
    #[inline]
    fn add_assign(&mut self, rhs: &Q) {
        *self = self.add_ref(rhs);
    }
}

impl AddAssign<Q> for Q {
    #[inline]
    fn add_assign(&mut self, rhs: Q) {
        *self = self.add_ref(&rhs);
    }
}

impl SubAssign<&Q> for Q {
    #[inline]
    fn sub_assign(&mut self, rhs: &Q) {
        *self = self.sub_ref(rhs);
    }
}

impl SubAssign<Q> for Q {
    #[inline]
    fn sub_assign(&mut self, rhs: Q) {
        *self = self.sub_ref(&rhs);
    }
}

impl MulAssign<&Q> for Q {
    #[inline]
    fn mul_assign(&mut self, rhs: &Q) {
        *self = self.mul_ref(rhs);
    }
}

impl MulAssign<Q> for Q {
    #[inline]
    fn mul_assign(&mut self, rhs: Q) {
        *self = self.mul_ref(&rhs);
    }
}

impl std::iter::Sum for Q {
    fn sum<I: Iterator<Item = Q>>(iter: I) -> Q {
        iter.fold(Q::zero(), |a, b| a + b)
    }
}

impl<'a> std::iter::Sum<&'a Q> for Q {
    fn sum<I: Iterator<Item = &'a Q>>(iter: I) -> Q {
        iter.fold(Q::zero(), |a, b| a + b)
    }
}

impl std::iter::Product for Q {
    fn product<I: Iterator<Item = Q>>(iter: I) -> Q {
        iter.fold(Q::one(), |a, b| a * b)
    }
}

impl<'a> std::iter::Product<&'a Q> for Q {
    fn product<I: Iterator<Item = &'a Q>>(iter: I) -> Q {
        iter.fold(Q::one(), |a, b| a * b)
    }
}

// ---------------------------------------------------------------------------
// tests
// ---------------------------------------------------------------------------

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;
    use std::collections::hash_map::DefaultHasher;

    fn q(n: i64, d: i64) -> Q {
        Q::new(n, d).expect("nonzero denominator")
    }

    fn h(x: &Q) -> u64 {
        let mut s = DefaultHasher::new();
        x.hash(&mut s);
        s.finish()
    }

    /// Checks the representation invariants.
    fn canonical(x: &Q) -> bool {
        match &x.0 {
            Repr::Small(n, d) => {
                *d > 0
                    && *n != i64::MIN
                    && gcd_u64(n.unsigned_abs(), *d as u64) == 1
                    && (*n != 0 || *d == 1)
            }
            Repr::Big(r) => {
                let fits = matches!((r.numer().to_i64(), r.denom().to_i64()), (Some(n), Some(_)) if n != i64::MIN);
                !fits && r.denom().is_positive() && r.numer().gcd(r.denom()).is_one()
            }
        }
    }

    #[test]
    fn basics() {
        assert_eq!(q(6, -4), q(-3, 2));
        assert_eq!(q(6, -4).to_string(), "-3/2");
        assert_eq!(Q::from_i64(-3).to_string(), "-3");
        assert_eq!(q(14, 23).to_string(), "14/23");
        assert_eq!("14/23".parse::<Q>(), Ok(q(14, 23)));
        assert_eq!("-3".parse::<Q>(), Ok(Q::from_i64(-3)));
        assert_eq!(" 3 / -6 ".parse::<Q>(), Ok(q(-1, 2)));
        assert_eq!("0.25".parse::<Q>(), Ok(q(1, 4)));
        assert_eq!("-1.5".parse::<Q>(), Ok(q(-3, 2)));
        assert!("1/0".parse::<Q>().is_err());
        assert!("abc".parse::<Q>().is_err());
        assert!("".parse::<Q>().is_err());
        assert!("1.".parse::<Q>().is_err());
        assert!("--1".parse::<Q>().is_err());
        assert_eq!(Q::new(1, 0), None);
        assert_eq!(Q::new(0, -5), Some(Q::zero()));
        assert!(q(0, 7).is_zero());
        assert!(q(7, 7).is_one());
        assert_eq!(q(1, 2) + q(1, 3), q(5, 6));
        assert_eq!(q(1, 2) - q(1, 3), q(1, 6));
        assert_eq!(q(2, 3) * q(9, 4), q(3, 2));
        assert_eq!(q(2, 3) / q(4, 9), q(3, 2));
        assert_eq!(q(2, 3).checked_div(&Q::zero()), None);
        assert_eq!(q(-2, 3).recip(), Some(q(-3, 2)));
        assert_eq!(Q::zero().recip(), None);
        assert_eq!(q(-2, 3).pow(3), Some(q(-8, 27)));
        assert_eq!(q(-2, 3).pow(-2), Some(q(9, 4)));
        assert_eq!(Q::zero().pow(-1), None);
        assert_eq!(Q::zero().pow(0), Some(Q::one()));
        assert_eq!(q(4, 6).gcd(&q(6, 15)), q(2, 15));
        assert_eq!(Q::zero().gcd(&q(-3, 4)), q(3, 4));
        assert_eq!(Q::zero().gcd(&Q::zero()), Q::zero());
        assert_eq!(q(-7, 2).signum(), -1);
        assert_eq!(q(7, 2).as_i64(), None);
        assert_eq!(q(14, 2).as_i64(), Some(7));
        assert!(q(1, 3) < q(1, 2));
        assert!(q(-1, 3) > q(-1, 2));
        assert_eq!(q(1, 4).to_f64(), 0.25);
    }

    #[test]
    fn overflow_and_demotion() {
        let max = Q::from_i64(i64::MAX);
        let s = &max + &Q::one();
        assert!(matches!(s.0, Repr::Big(_)));
        assert_eq!(s.to_string(), "9223372036854775808");
        let back = &s - &Q::one();
        assert!(matches!(back.0, Repr::Small(..)));
        assert_eq!(back, max);
        // i64::MIN is not representable as Small
        let m = Q::from_i64(i64::MIN);
        assert!(matches!((m).0, Repr::Big(_)));
        assert!(canonical(&m));
        assert_eq!(-(-m.clone()), m);
        assert_eq!(&m + &Q::one(), Q::from_i64(i64::MIN + 1));
        assert!(matches!((&m + &Q::one()).0, Repr::Small(..)));
        let neg_max = -max.clone();
        assert!(matches!((&neg_max - &Q::one()).0, Repr::Big(_)));
        assert_eq!(Q::new(i64::MIN, i64::MIN), Some(Q::one()));
        assert_eq!(Q::new(1, i64::MIN).map(|x| canonical(&x)), Some(true));
        let big = Q::from_i64(3).pow(100).expect("pow");
        assert!(matches!((big).0, Repr::Big(_)));
        let r = &big / &Q::from_i64(3).pow(99).expect("pow");
        assert_eq!(r, Q::from_i64(3));
        assert!(matches!((r).0, Repr::Small(..)));
        let huge = Q::from_i64(10).pow(400).expect("pow");
        assert_eq!(huge.to_f64(), f64::INFINITY);
        let ratio = &huge / &Q::from_i64(10).pow(399).expect("pow");
        assert_eq!(ratio.to_f64(), 10.0);
        let frac = &(&huge + &Q::one()) / &(&huge * &Q::from_i64(3));
        assert!((frac.to_f64() - 1.0 / 3.0).abs() < 1e-15);
        assert_eq!(Q::from_bigint(BigInt::from(5)), Q::from_i64(5));
    }

    fn arb_i64() -> impl Strategy<Value = i64> {
        prop_oneof![
            -20i64..20,
            any::<i64>(),
            (i64::MAX - 5)..=i64::MAX,
            i64::MIN..(i64::MIN + 5),
            (-(1i64 << 32) - 3)..(-(1i64 << 32) + 3),
            ((1i64 << 31) - 3)..((1i64 << 31) + 3),
        ]
    }

    fn arb_q() -> impl Strategy<Value = Q> {
        prop_oneof![
            (arb_i64(), arb_i64()).prop_filter_map("d != 0", |(n, d)| Q::new(n, d)),
            (arb_i64(), arb_i64(), arb_i64()).prop_filter_map("d != 0", |(a, b, d)| {
                // a*b/d, to produce Big values
                if d == 0 {
                    None
                } else {
                    Some(Q::from_big(BigRational::new(
                        BigInt::from(a) * BigInt::from(b),
                        BigInt::from(d),
                    )))
                }
            }),
        ]
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(400))]

        #[test]
        fn prop_ops_match_bigrational(a in arb_q(), b in arb_q()) {
            let (x, y) = (a.to_big(), b.to_big());
            prop_assert!(canonical(&a) && canonical(&b));
            let s = &a + &b;
            prop_assert!(canonical(&s));
            prop_assert_eq!(s.to_big(), &x + &y);
            let d = &a - &b;
            prop_assert!(canonical(&d));
            prop_assert_eq!(d.to_big(), &x - &y);
            let p = &a * &b;
            prop_assert!(canonical(&p));
            prop_assert_eq!(p.to_big(), &x * &y);
            if !b.is_zero() {
                let qt = &a / &b;
                prop_assert!(canonical(&qt));
                prop_assert_eq!(qt.to_big(), &x / &y);
            } else {
                prop_assert!(a.checked_div(&b).is_none());
            }
            let n = -&a;
            prop_assert!(canonical(&n));
            prop_assert_eq!(n.to_big(), -x.clone());
            prop_assert_eq!(a.abs().to_big(), x.abs());
            prop_assert_eq!(a.cmp(&b), x.cmp(&y));
            prop_assert_eq!(a == b, x == y);
            if a == b { prop_assert_eq!(h(&a), h(&b)); }
            // owned variants agree
            prop_assert_eq!(a.clone() + b.clone(), s.clone());
            prop_assert_eq!(a.clone() - &b, d.clone());
            prop_assert_eq!(&a * b.clone(), p.clone());
            let mut m = a.clone(); m += &b; prop_assert_eq!(&m, &s);
            let mut m = a.clone(); m -= b.clone(); prop_assert_eq!(&m, &d);
            let mut m = a.clone(); m *= &b; prop_assert_eq!(&m, &p);
            // round trips
            prop_assert_eq!(Q::from_big(x.clone()), a.clone());
            prop_assert_eq!(a.to_string().parse::<Q>(), Ok(a.clone()));
            prop_assert_eq!(a.numer(), x.numer().clone());
            prop_assert_eq!(a.denom(), x.denom().clone());
            prop_assert_eq!(a.is_integer(), x.is_integer());
            prop_assert_eq!(a.signum(), if x.is_negative() { -1 } else if x.is_zero() { 0 } else { 1 });
            prop_assert_eq!(a.as_i64(), if x.is_integer() { x.numer().to_i64() } else { None });
            prop_assert_eq!(a.to_f64(), x.to_f64().unwrap_or(f64::NAN));
            // gcd
            let g = a.gcd(&b);
            prop_assert!(canonical(&g));
            let gn = x.numer().gcd(y.numer());
            let gd = x.denom().lcm(y.denom());
            prop_assert_eq!(g.to_big(), BigRational::new(gn, gd));
            if !g.is_zero() {
                prop_assert!((&a / &g).is_integer());
                prop_assert!((&b / &g).is_integer());
            }
        }

        #[test]
        fn prop_hash_eq_consistent(a in arb_q(), b in arb_q()) {
            // two different computations of the same value
            let s1 = &(&a + &b) - &b;
            prop_assert_eq!(&s1, &a);
            prop_assert_eq!(h(&s1), h(&a));
            if !b.is_zero() {
                let s2 = &(&a * &b) / &b;
                prop_assert_eq!(&s2, &a);
                prop_assert_eq!(h(&s2), h(&a));
            }
        }

        #[test]
        fn prop_pow(a in arb_q(), e in -6i32..7) {
            let r = a.pow(e);
            if a.is_zero() && e < 0 {
                prop_assert!(r.is_none());
            } else {
                let r = r.expect("pow");
                prop_assert!(canonical(&r));
                let x = a.to_big();
                let expect = if e >= 0 {
                    num_traits::pow(x, e as usize)
                } else {
                    num_traits::pow(x.recip(), (-e) as usize)
                };
                prop_assert_eq!(r.to_big(), expect);
            }
        }
    }
}
