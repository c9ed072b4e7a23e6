//! A physical dimension: a vector of rational exponents over the base
//! dimensions, and the one table of dimension names.

use crate::num::Q;
use std::fmt::Write as _;

/// The base dimensions, in the order of [`Dimension`]'s exponents.
pub const BASE_DIMENSIONS: [&str; 5] = ["mass", "length", "time", "charge", "temperature"];

/// A physical dimension: mass^a·length^b·time^c·charge^d·temperature^e with
/// rational exponents (a dimensionless quantity, an angle among them, has
/// every exponent 0).
///
/// Invariant: the exponents are `num[i]/den` with `den > 0` and
/// gcd(den, num…) = 1, so equal dimensions are equal values. An operation
/// whose exact result leaves 32-bit integers marks the dimension
/// `overflow`; such a dimension is never one, and unification refuses it,
/// so it can only end in an error, never in a wrong answer.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Dimension {
    num: [i32; 5],
    den: i32,
    overflow: bool,
}

impl Default for Dimension {
    fn default() -> Dimension {
        Dimension {
            num: [0; 5],
            den: 1,
            overflow: false,
        }
    }
}

/// i64 exponents over a common denominator, reduced and fitted to i32
/// (`None` when they do not fit).
fn reduced(num: [i64; 5], den: i64) -> Option<Dimension> {
    let (num, den) = if den < 0 {
        (num.map(|n| n.checked_neg()), den.checked_neg()?)
    } else {
        (num.map(Some), den)
    };
    let mut n = [0i64; 5];
    for (x, y) in n.iter_mut().zip(num) {
        *x = y?;
    }
    if den == 0 {
        return None;
    }
    let mut g = den.unsigned_abs();
    if g != 1 {
        for x in n {
            g = crate::num::gcd_u64(g, x.unsigned_abs());
        }
    }
    let g = g.max(1) as i64;
    let mut out = Dimension {
        num: [0; 5],
        den: i32::try_from(den / g).ok()?,
        overflow: false,
    };
    for (o, x) in out.num.iter_mut().zip(n) {
        *o = i32::try_from(x / g).ok()?;
    }
    Some(out)
}

/// What a name of the table is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DimensionNameKind {
    /// One of the five base dimensions.
    Base,
    /// A derived dimension qdot prints by this name (`force`, `energy`).
    Derived,
    /// Another name for a derived dimension, accepted but never printed
    /// (`work`, `torque`: an energy).
    Synonym,
    /// An SI unit symbol, standing for its dimension (`N`, `kg`, `rad`).
    Unit,
}

/// One name of a dimension.
#[derive(Clone, Copy, Debug)]
pub struct DimensionName {
    /// The name as written in an annotation.
    pub name: &'static str,
    /// Exponents of mass, length, time, charge, temperature.
    pub exponents: [i8; 5],
    /// Base, derived (printed), synonym or unit.
    pub kind: DimensionNameKind,
}

const fn n(name: &'static str, exponents: [i8; 5], kind: DimensionNameKind) -> DimensionName {
    DimensionName {
        name,
        exponents,
        kind,
    }
}

use DimensionNameKind::{Base, Derived, Synonym, Unit};

/// Every dimension name an annotation may use. Printing uses the first
/// base or derived name of a dimension, so the common names come first.
pub const DIMENSION_NAMES: &[DimensionName] = &[
    n("mass", [1, 0, 0, 0, 0], Base),
    n("length", [0, 1, 0, 0, 0], Base),
    n("time", [0, 0, 1, 0, 0], Base),
    n("charge", [0, 0, 0, 1, 0], Base),
    n("temperature", [0, 0, 0, 0, 1], Base),
    n("dimensionless", [0, 0, 0, 0, 0], Derived),
    n("angle", [0, 0, 0, 0, 0], Synonym),
    n("velocity", [0, 1, -1, 0, 0], Derived),
    n("acceleration", [0, 1, -2, 0, 0], Derived),
    n("force", [1, 1, -2, 0, 0], Derived),
    n("energy", [1, 2, -2, 0, 0], Derived),
    n("work", [1, 2, -2, 0, 0], Synonym),
    n("torque", [1, 2, -2, 0, 0], Synonym),
    n("power", [1, 2, -3, 0, 0], Derived),
    n("momentum", [1, 1, -1, 0, 0], Derived),
    n("impulse", [1, 1, -1, 0, 0], Synonym),
    n("angular_momentum", [1, 2, -1, 0, 0], Derived),
    n("inertia", [1, 2, 0, 0, 0], Derived),
    n("stiffness", [1, 0, -2, 0, 0], Derived),
    n("damping", [1, 0, -1, 0, 0], Derived),
    n("frequency", [0, 0, -1, 0, 0], Derived),
    n("angular_velocity", [0, 0, -1, 0, 0], Synonym),
    n("angular_acceleration", [0, 0, -2, 0, 0], Synonym),
    n("area", [0, 2, 0, 0, 0], Derived),
    n("volume", [0, 3, 0, 0, 0], Derived),
    n("pressure", [1, -1, -2, 0, 0], Derived),
    n("stress", [1, -1, -2, 0, 0], Synonym),
    n("density", [1, -3, 0, 0, 0], Derived),
    n("linear_density", [1, -1, 0, 0, 0], Derived),
    n("area_density", [1, -2, 0, 0, 0], Derived),
    n("current", [0, 0, -1, 1, 0], Derived),
    n("voltage", [1, 2, -2, -1, 0], Derived),
    n("electric_field", [1, 1, -2, -1, 0], Derived),
    n("magnetic_field", [1, 0, -1, -1, 0], Derived),
    n("kg", [1, 0, 0, 0, 0], Unit),
    n("m", [0, 1, 0, 0, 0], Unit),
    n("s", [0, 0, 1, 0, 0], Unit),
    n("rad", [0, 0, 0, 0, 0], Unit),
    n("N", [1, 1, -2, 0, 0], Unit),
    n("J", [1, 2, -2, 0, 0], Unit),
    n("W", [1, 2, -3, 0, 0], Unit),
    n("Pa", [1, -1, -2, 0, 0], Unit),
    n("Hz", [0, 0, -1, 0, 0], Unit),
    n("C", [0, 0, 0, 1, 0], Unit),
    n("A", [0, 0, -1, 1, 0], Unit),
    n("V", [1, 2, -2, -1, 0], Unit),
    n("K", [0, 0, 0, 0, 1], Unit),
];

/// The dimension named `name` in an annotation, if the table has it.
pub fn dimension_named(name: &str) -> Option<Dimension> {
    DIMENSION_NAMES
        .iter()
        .find(|d| d.name == name)
        .map(|d| Dimension::from_small(d.exponents))
}

impl Dimension {
    /// The dimension of a pure number (and of an angle).
    pub fn one() -> Dimension {
        Dimension::default()
    }

    /// A dimension from integer exponents (mass, length, time, charge,
    /// temperature).
    pub fn from_small(e: [i8; 5]) -> Dimension {
        Dimension::integer(e.map(i32::from))
    }

    const fn integer(num: [i32; 5]) -> Dimension {
        Dimension {
            num,
            den: 1,
            overflow: false,
        }
    }

    /// A pure number (and an angle).
    pub const ONE: Dimension = Dimension::integer([0, 0, 0, 0, 0]);
    /// mass
    pub const MASS: Dimension = Dimension::integer([1, 0, 0, 0, 0]);
    /// length
    pub const LENGTH: Dimension = Dimension::integer([0, 1, 0, 0, 0]);
    /// time
    pub const TIME: Dimension = Dimension::integer([0, 0, 1, 0, 0]);
    /// length²
    pub const AREA: Dimension = Dimension::integer([0, 2, 0, 0, 0]);
    /// length·time⁻²
    pub const ACCELERATION: Dimension = Dimension::integer([0, 1, -2, 0, 0]);
    /// mass·length·time⁻²
    pub const FORCE: Dimension = Dimension::integer([1, 1, -2, 0, 0]);
    /// mass·length²·time⁻²
    pub const ENERGY: Dimension = Dimension::integer([1, 2, -2, 0, 0]);
    /// mass·length²·time⁻³
    pub const POWER: Dimension = Dimension::integer([1, 2, -3, 0, 0]);
    /// mass·length² (a moment of inertia).
    pub const MOMENT_OF_INERTIA: Dimension = Dimension::integer([1, 2, 0, 0, 0]);

    /// The exponent of base dimension `i` (0 mass … 4 temperature).
    fn exponent(&self, i: usize) -> Q {
        Q::new(i64::from(self.num[i]), i64::from(self.den)).unwrap_or_default()
    }

    /// The exponents of mass, length, time, charge and temperature.
    pub fn exponents(&self) -> [Q; 5] {
        [0, 1, 2, 3, 4].map(|i| self.exponent(i))
    }

    /// Whether an exponent left the range qdot keeps exactly (32-bit
    /// numerators and denominators); such a dimension is refused wherever
    /// it is used.
    pub fn overflowed(&self) -> bool {
        self.overflow
    }

    /// Whether this is the dimension of a pure number.
    pub fn is_one(&self) -> bool {
        !self.overflow && self.num == [0; 5]
    }

    fn overflowing(&self) -> Dimension {
        Dimension {
            overflow: true,
            ..*self
        }
    }

    /// `self · other^sign`, sign ±1.
    fn combine(&self, other: &Dimension, sign: i64) -> Dimension {
        let flag = self.overflow || other.overflow;
        if self.den == 1 && other.den == 1 {
            let mut r = *self;
            r.overflow = flag;
            for (a, b) in r.num.iter_mut().zip(other.num) {
                let b = if sign < 0 { b.checked_neg() } else { Some(b) };
                match b.and_then(|b| a.checked_add(b)) {
                    Some(x) => *a = x,
                    None => return self.overflowing(),
                }
            }
            return r;
        }
        let (d1, d2) = (i64::from(self.den), i64::from(other.den));
        let mut num = [0i64; 5];
        for (i, n) in num.iter_mut().enumerate() {
            *n = i64::from(self.num[i]) * d2 + sign * i64::from(other.num[i]) * d1;
        }
        match reduced(num, d1 * d2) {
            Some(mut r) => {
                r.overflow = flag;
                r
            }
            None => self.overflowing(),
        }
    }

    /// The product of two dimensions.
    pub fn mul(&self, other: &Dimension) -> Dimension {
        self.combine(other, 1)
    }

    /// The quotient of two dimensions.
    pub fn div(&self, other: &Dimension) -> Dimension {
        self.combine(other, -1)
    }

    /// This dimension to a rational power.
    pub fn pow(&self, p: &Q) -> Dimension {
        let Some((pn, pd)) = p.small() else {
            return self.overflowing();
        };
        if self.den == 1 && pd == 1 {
            let mut r = *self;
            for a in r.num.iter_mut() {
                match i32::try_from(pn).ok().and_then(|p| a.checked_mul(p)) {
                    Some(x) => *a = x,
                    None => return self.overflowing(),
                }
            }
            return r;
        }
        let num = self.num.map(|n| i64::from(n).checked_mul(pn));
        let mut n = [0i64; 5];
        for (x, y) in n.iter_mut().zip(num) {
            match y {
                Some(y) => *x = y,
                None => return self.overflowing(),
            }
        }
        match i64::from(self.den)
            .checked_mul(pd)
            .and_then(|d| reduced(n, d))
        {
            Some(mut r) => {
                r.overflow = self.overflow;
                r
            }
            None => self.overflowing(),
        }
    }

    /// The name qdot prints for this dimension when the table has one.
    pub fn name(&self) -> Option<&'static str> {
        DIMENSION_NAMES
            .iter()
            .filter(|d| matches!(d.kind, Base | Derived))
            .find(|d| Dimension::from_small(d.exponents) == *self)
            .map(|d| d.name)
    }

    /// A named dimension times one base dimension to a power ±1 or ±2
    /// (`energy/length^2`), when no name fits exactly and this one does.
    fn named_times_base(&self) -> Option<(&'static str, usize, i64)> {
        for d in DIMENSION_NAMES.iter().filter(|d| d.kind == Derived) {
            let named = Dimension::from_small(d.exponents);
            if named.is_one() {
                continue;
            }
            let rest = self.div(&named);
            let nonzero: Vec<usize> = (0..5).filter(|&i| rest.num[i] != 0).collect();
            if let [i] = nonzero[..] {
                if rest.den == 1 && rest.num[i].abs() <= 2 {
                    return Some((d.name, i, i64::from(rest.num[i])));
                }
            }
        }
        None
    }

    /// The dimension written with Unicode superscripts: `force`,
    /// `energy·length⁻²`, `mass·length²·time⁻¹`, `dimensionless`.
    pub fn unicode(&self) -> String {
        self.written(false)
    }

    /// The dimension in annotation syntax (it reads back as the same
    /// dimension): `force`, `energy/length^2`, `mass*length^2/time`, `1`.
    pub fn ascii(&self) -> String {
        if self.is_one() {
            return "1".into();
        }
        self.written(true)
    }

    fn written(&self, ascii: bool) -> String {
        if self.overflow {
            return "(an exponent beyond 2^31)".into();
        }
        if let Some(n) = self.name() {
            return n.to_string();
        }
        let nonzero = self.num.iter().filter(|e| **e != 0).count();
        if nonzero <= 2 {
            // time⁻² and length·time read better than frequency·time⁻¹
            // and velocity·time²
        } else if let Some((name, base, e)) = self.named_times_base() {
            return factors(
                &[
                    (name.to_string(), Q::from_i64(1)),
                    (BASE_DIMENSIONS[base].to_string(), Q::from_i64(e)),
                ],
                ascii,
            );
        }
        let fs: Vec<(String, Q)> = (0..5)
            .filter(|&i| self.num[i] != 0)
            .map(|i| (BASE_DIMENSIONS[i].to_string(), self.exponent(i)))
            .collect();
        factors(&fs, ascii)
    }

    /// "a force", "an energy", "dimensionless", "of dimension mass·time⁻³":
    /// the dimension after "this is".
    pub fn phrase(&self) -> String {
        if self.overflow {
            return "of a dimension with an exponent beyond 2^31".into();
        }
        if self.is_one() {
            return "dimensionless".into();
        }
        match self.name() {
            Some(n) => article(n),
            None => format!("of dimension {}", self.unicode()),
        }
    }

    /// "forces", "energies", "dimensionless", "of dimension mass·time⁻³":
    /// the dimension after "the others are".
    pub fn plural(&self) -> String {
        if self.overflow {
            return "of a dimension with an exponent beyond 2^31".into();
        }
        if self.is_one() {
            return "dimensionless".into();
        }
        match self.name() {
            Some(n) => plural(n),
            None => format!("of dimension {}", self.unicode()),
        }
    }
}

/// `a length`, `an energy`.
pub(super) fn article(name: &str) -> String {
    let vowel = name.starts_with(['a', 'e', 'i', 'o', 'u']);
    format!(
        "{} {}",
        if vowel { "an" } else { "a" },
        name.replace('_', " ")
    )
}

/// `lengths`, `energies`, `masses`.
pub(super) fn plural(name: &str) -> String {
    let name = name.replace('_', " ");
    if let Some(stem) = name.strip_suffix('y') {
        format!("{stem}ies")
    } else if name.ends_with('s') {
        format!("{name}es")
    } else {
        format!("{name}s")
    }
}

/// Factors with exponents, in Unicode (`a·b⁻²`) or annotation syntax
/// (`a/b^2`).
pub(super) fn factors(fs: &[(String, Q)], ascii: bool) -> String {
    let mut out = String::new();
    if !ascii {
        for (name, e) in fs {
            if !out.is_empty() {
                out.push('·');
            }
            out.push_str(name);
            if !e.is_one() {
                out.push_str(&superscript(e));
            }
        }
        return out;
    }
    let (num, den): (Vec<_>, Vec<_>) = fs.iter().partition(|(_, e)| e.is_positive());
    let power = |name: &str, e: &Q| -> String {
        if e.is_one() {
            name.to_string()
        } else if e.is_integer() {
            format!("{name}^{e}")
        } else {
            format!("{name}^({e})")
        }
    };
    let nums: Vec<String> = num.iter().map(|(n, e)| power(n, e)).collect();
    out.push_str(&if nums.is_empty() {
        "1".to_string()
    } else {
        nums.join("*")
    });
    for (n, e) in den {
        let _ = write!(out, "/{}", power(n, &-e));
    }
    out
}

/// `²`, `⁻¹`, `^(1/2)`: an exponent after a name.
fn superscript(e: &Q) -> String {
    if !e.is_integer() {
        return format!("^({e})");
    }
    e.to_string()
        .chars()
        .map(|c| match c {
            '-' => '⁻',
            '0' => '⁰',
            '1' => '¹',
            '2' => '²',
            '3' => '³',
            '4' => '⁴',
            '5' => '⁵',
            '6' => '⁶',
            '7' => '⁷',
            '8' => '⁸',
            _ => '⁹',
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_unique_and_named_works() {
        for (i, a) in DIMENSION_NAMES.iter().enumerate() {
            assert!(
                DIMENSION_NAMES[i + 1..].iter().all(|b| b.name != a.name),
                "{}",
                a.name
            );
        }
        // the constants are the table's dimensions of those names
        for (name, d) in [
            ("dimensionless", Dimension::ONE),
            ("mass", Dimension::MASS),
            ("length", Dimension::LENGTH),
            ("time", Dimension::TIME),
            ("area", Dimension::AREA),
            ("acceleration", Dimension::ACCELERATION),
            ("force", Dimension::FORCE),
            ("energy", Dimension::ENERGY),
            ("power", Dimension::POWER),
        ] {
            assert_eq!(dimension_named(name), Some(d));
            assert_eq!(d.name(), Some(name));
        }
    }

    #[test]
    fn printing() {
        let f = Dimension::FORCE;
        let l = Dimension::LENGTH;
        assert_eq!(f.div(&l).unicode(), "stiffness");
        assert_eq!(
            Dimension::ENERGY.div(&l.pow(&Q::from_i64(3))).unicode(),
            "pressure"
        );
        assert_eq!(f.mul(&l).mul(&l).mul(&l).unicode(), "energy·length²");
        assert_eq!(f.mul(&l).mul(&l).mul(&l).ascii(), "energy*length^2");
        let odd = Dimension::from_small([1, 3, -5, 0, 0]);
        assert_eq!(odd.unicode(), "mass·length³·time⁻⁵");
        assert_eq!(odd.ascii(), "mass*length^3/time^5");
        assert_eq!(l.pow(&Q::new(1, 2).unwrap()).ascii(), "length^(1/2)");
        assert_eq!(Dimension::one().phrase(), "dimensionless");
        assert_eq!(Dimension::ENERGY.phrase(), "an energy");
        assert_eq!(Dimension::ENERGY.plural(), "energies");
        assert_eq!(Dimension::MASS.plural(), "masses");
    }
}
