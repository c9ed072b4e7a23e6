//! Numbers: the `literal` rules and their exact values.

use super::*;

/// `10^n`.
pub(super) fn pow10(n: usize) -> BigInt {
    num_traits::pow(BigInt::from(10u32), n)
}

/// A `number` as written: `int.frac` times `10^exp` (the digit strings
/// are ASCII digits).
pub(super) struct Decimal<'s> {
    int: &'s str,
    frac: &'s str,
    exp: i64,
}

impl Decimal<'_> {
    /// The exact value, in lowest terms.
    #[inline]
    pub(super) fn value(&self) -> BigRational {
        exact_value(self.int, self.frac, self.exp)
    }
}

/// The exact value of the decimal number `int.frac` times `10^exp` (the
/// digit strings are ASCII digits), in lowest terms.
#[cfg_attr(not(debug_assertions), inline(always))]
pub(super) fn exact_value(int: &str, frac: &str, exp: i64) -> BigRational {
    // fast path: the significant digits fit in a u64 (at most 19 digits)
    if int.len() + frac.len() <= 19 {
        let mut n = 0u64;
        for &c in int.as_bytes() {
            n = n * 10 + u64::from(c - b'0');
        }
        for &c in frac.as_bytes() {
            n = n * 10 + u64::from(c - b'0');
        }
        if n == 0 {
            return BigRational::zero();
        }
        let e = exp - frac.len() as i64;
        if e >= 0 {
            let m = u32::try_from(e)
                .ok()
                .and_then(|e| 10u64.checked_pow(e))
                .and_then(|p| n.checked_mul(p));
            if let Some(m) = m {
                return BigRational::from_integer(BigInt::from(m));
            }
        } else if let Some(d) = u32::try_from(-e).ok().and_then(|e| 10u64.checked_pow(e)) {
            let g = num_integer::gcd(n, d);
            return BigRational::new_raw(BigInt::from(n / g), BigInt::from(d / g));
        }
    }
    exact_value_big(int, frac, exp)
}

/// [`exact_value`] for numbers too long for machine integers.
#[cold]
#[inline(never)]
pub(super) fn exact_value_big(int: &str, frac: &str, exp: i64) -> BigRational {
    let mut numer: BigInt = format!("{int}{frac}")
        .parse()
        .unwrap_or_else(|_| BigInt::zero());
    let mut denom = pow10(frac.len());
    if exp >= 0 {
        numer *= pow10(exp as usize);
    } else {
        denom *= pow10(exp.unsigned_abs() as usize);
    }
    if denom.is_zero() {
        denom = BigInt::one();
    }
    BigRational::new(numer, denom)
}

impl<'s> Parser<'s> {
    /// `literal ::= number angle_unit?`
    ///
    /// `i` is after white space (see [`Parser::atom`]).
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(super) fn literal(&self, i: &'s str) -> RuleResult<'s, Node> {
        let (rest, number) = self.number(i)?;
        // the value is built last, in place (it is large to move)
        let (rest, degrees) = match self.angle_unit(rest) {
            Ok((rest, _)) => (rest, true),
            Err(_) => (rest, false),
        };
        let span = self.span(i, rest);
        let kind = if degrees {
            ExprKind::Degrees(number.value())
        } else {
            ExprKind::Num(number.value())
        };
        Ok((rest, Self::leaf(kind, span)))
    }

    /// `angle_unit ::= "deg" | space? "°"` — `deg` not followed by an `ident_char`.
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(super) fn angle_unit(&self, i: &'s str) -> RuleResult<'s, &'s str> {
        if let Some(rest) = i.strip_prefix("deg") {
            if !starts_with_class(rest, ident_char) {
                return Ok((rest, &i[..3]));
            }
            return self.nothing(i);
        }
        let j = match Self::space(i) {
            Ok((rest, _)) => rest,
            Err(_) => i,
        };
        match j.strip_prefix('°') {
            Some(rest) => Ok((rest, &j[..j.len() - rest.len()])),
            None => self.nothing(j),
        }
    }

    /// `number ::= digits ( "." digits )? sci_exponent?`
    ///
    /// Scanned on bytes; the value is computed with machine integers when
    /// it fits (see [`exact_value`]).
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(super) fn number(&self, i: &'s str) -> RuleResult<'s, Decimal<'s>> {
        if let Some(after_dot) = i.strip_prefix('.') {
            return match Self::digits(after_dot) {
                Ok((rest, frac)) => Err(self.leading_dot(i, rest, frac)),
                Err(_) => self.nothing(i),
            };
        }
        let (mut rest, int) = Self::digits(i)?;
        let mut frac = "";
        if let Some(after_dot) = rest.strip_prefix('.') {
            match Self::digits(after_dot) {
                Ok((after, f)) => {
                    frac = f;
                    rest = after;
                }
                Err(_) => return Err(self.trailing_dot(i, after_dot, int)),
            }
        }
        let (rest, exp) = match self.sci_exponent(rest) {
            Ok((after, e)) => (after, e),
            Err(nom::Err::Error(_)) => (rest, 0),
            Err(e) => return Err(e),
        };
        if rest.starts_with('.') {
            return Err(self.second_dot(i, rest));
        }
        if int.len() + frac.len() > crate::limits::MAX_NUMBER_DIGITS {
            return Err(self.too_many_digits(i, rest, int.len() + frac.len()));
        }
        Ok((rest, Decimal { int, frac, exp }))
    }

    /// The error for `.5`.
    #[cold]
    #[inline(never)]
    pub(super) fn leading_dot(&self, i: &'s str, rest: &'s str, frac: &str) -> nom::Err<RuleError> {
        failure(
            Diagnostic::error(
                self.span(i, rest),
                "a number can't start with a decimal point",
            )
            .with_hint(format!("write `0.{frac}`"))
            .with_kind(crate::diag::ErrorKind::Syntax),
        )
    }

    /// The error for `3.`.
    #[cold]
    #[inline(never)]
    pub(super) fn trailing_dot(
        &self,
        i: &'s str,
        after_dot: &'s str,
        int: &str,
    ) -> nom::Err<RuleError> {
        failure(
            Diagnostic::error(
                self.span(i, after_dot),
                format!("malformed number `{int}.`"),
            )
            .with_hint(format!(
                "a decimal point must be followed by digits: write `{int}.0` or `{int}`"
            ))
            .with_kind(crate::diag::ErrorKind::Syntax),
        )
    }

    /// The error for `1.2.3` or `1e3.5` (a `.` at `rest`, after the number).
    /// The error for a literal of more than [`crate::limits::MAX_NUMBER_DIGITS`]
    /// digits (reading one is quadratic in its length).
    #[cold]
    #[inline(never)]
    pub(super) fn too_many_digits(
        &self,
        i: &'s str,
        rest: &'s str,
        digits: usize,
    ) -> nom::Err<RuleError> {
        let span = Span::new(self.pos(i), self.pos(rest));
        failure(
            Diagnostic::error(
                span,
                format!(
                    "a number of {digits} digits; qdot reads numbers of at most {} digits",
                    crate::limits::MAX_NUMBER_DIGITS
                ),
            )
            .with_hint("write a large or small number with an exponent: `6.02214076e23`")
            .with_kind(crate::diag::ErrorKind::Syntax),
        )
    }

    #[cold]
    #[inline(never)]
    pub(super) fn second_dot(&self, i: &'s str, rest: &'s str) -> nom::Err<RuleError> {
        let end = rest
            .find(|c: char| !(c.is_ascii_digit() || c == '.'))
            .unwrap_or(rest.len());
        let span = Span::new(self.pos(i), self.pos(rest) + end);
        failure(
            Diagnostic::error(
                span,
                format!("malformed number `{}`", &self.src[span.start..span.end]),
            )
            .with_hint(
                "a number has at most one decimal point, before any exponent: `1.25`, `1.5e-3`",
            )
            .with_kind(crate::diag::ErrorKind::Syntax),
        )
    }

    /// `sci_exponent ::= [eE] [+-]? digits` — taken only when a digit follows.
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(super) fn sci_exponent(&self, i: &'s str) -> RuleResult<'s, i64> {
        let b = i.as_bytes();
        if !matches!(b.first(), Some(b'e' | b'E')) {
            return self.nothing(i);
        }
        let (negative, at) = match b.get(1) {
            Some(b'-') => (true, 2),
            Some(b'+') => (false, 2),
            _ => (false, 1),
        };
        let (rest, digits) = Self::digits(&i[at..])?;
        let significant = digits.trim_start_matches('0');
        let n: u32 = if significant.len() > 6 {
            u32::MAX
        } else {
            significant.parse().unwrap_or(0)
        };
        if n > MAX_EXPONENT {
            return Err(self.exponent_out_of_range(i, rest));
        }
        let n = i64::from(n);
        Ok((rest, if negative { -n } else { n }))
    }

    /// The error for an exponent beyond [`MAX_EXPONENT`].
    #[cold]
    #[inline(never)]
    pub(super) fn exponent_out_of_range(&self, i: &'s str, rest: &'s str) -> nom::Err<RuleError> {
        failure(
            Diagnostic::error(self.span(i, rest), "exponent out of range")
                .with_hint(format!("exponents up to {MAX_EXPONENT} are accepted"))
                .with_kind(crate::diag::ErrorKind::Syntax),
        )
    }

    /// `digits ::= [0-9]+`
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(super) fn digits(i: &'s str) -> RuleResult<'s, &'s str> {
        match digits_len(i) {
            0 => Err(nom::Err::Error(RuleError::At(i.len()))),
            n => Ok((&i[n..], &i[..n])),
        }
    }
}
