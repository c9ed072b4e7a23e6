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
/// Invariant: exponents are fractions of 32-bit integers in lowest terms.
/// An operation whose exact result leaves that range marks the dimension
/// `overflow`; such a dimension is never one, and unification refuses it,
/// so it can only end in an error, never in a wrong answer.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub struct Dimension {
    exponents: [Exponent; 5],
    overflow: bool,
}

/// A rational exponent n/d in lowest terms, d > 0 (0 is 0/1).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
struct Exponent {
    n: i32,
    d: i32,
}

impl Default for Exponent {
    fn default() -> Exponent {
        Exponent { n: 0, d: 1 }
    }
}

impl Exponent {
    /// n/d in lowest terms, if it fits.
    fn new(n: i64, d: i64) -> Option<Exponent> {
        if d == 1 {
            return Some(Exponent {
                n: i32::try_from(n).ok()?,
                d: 1,
            });
        }
        if d == 0 {
            return None;
        }
        let (n, d) = if d < 0 {
            (n.checked_neg()?, d.checked_neg()?)
        } else {
            (n, d)
        };
        // both fit in i64 and d > 0, so the gcd does too
        let g = crate::num::gcd_u64(n.unsigned_abs(), d.unsigned_abs()).max(1) as i64;
        let (n, d) = (n / g, d / g);
        Some(Exponent {
            n: i32::try_from(n).ok()?,
            d: i32::try_from(d).ok()?,
        })
    }
    fn add(self, o: Exponent) -> Option<Exponent> {
        if self.d == 1 && o.d == 1 {
            return Some(Exponent {
                n: self.n.checked_add(o.n)?,
                d: 1,
            });
        }
        let (a, b, c, d) = (self.n as i64, self.d as i64, o.n as i64, o.d as i64);
        Exponent::new(a * d + c * b, b * d)
    }
    fn mul(self, o: Exponent) -> Option<Exponent> {
        if self.d == 1 && o.d == 1 {
            return Some(Exponent {
                n: self.n.checked_mul(o.n)?,
                d: 1,
            });
        }
        Exponent::new(self.n as i64 * o.n as i64, self.d as i64 * o.d as i64)
    }
    fn is_zero(self) -> bool {
        self.n == 0
    }
    fn to_q(self) -> Q {
        Q::new(self.n as i64, self.d as i64).unwrap_or_default()
    }
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
        Dimension {
            exponents: e.map(|x| Exponent { n: x as i32, d: 1 }),
            overflow: false,
        }
    }

    /// The named dimension of the table (`"force"`); panics on a name the
    /// table lacks, so only for names written in qdot's code.
    pub(crate) fn named(name: &str) -> Dimension {
        // ok: the callers pass names of DIMENSION_NAMES (a unit test checks them)
        dimension_named(name).expect("a name of DIMENSION_NAMES")
    }

    /// The exponents of mass, length, time, charge and temperature.
    pub fn exponents(&self) -> [Q; 5] {
        self.exponents.map(Exponent::to_q)
    }

    /// Whether an exponent left the range qdot keeps exactly (|n|, d <
    /// 2³¹); such a dimension is refused wherever it is used.
    pub fn overflowed(&self) -> bool {
        self.overflow
    }

    /// Whether this is the dimension of a pure number.
    pub fn is_one(&self) -> bool {
        !self.overflow && self.exponents.iter().all(|e| e.is_zero())
    }

    fn zip(
        &self,
        other: &Dimension,
        f: impl Fn(Exponent, Exponent) -> Option<Exponent>,
    ) -> Dimension {
        let mut r = Dimension {
            overflow: self.overflow || other.overflow,
            ..*self
        };
        for (a, b) in r.exponents.iter_mut().zip(other.exponents) {
            match f(*a, b) {
                Some(x) => *a = x,
                None => r.overflow = true,
            }
        }
        r
    }

    /// The product of two dimensions.
    pub fn mul(&self, other: &Dimension) -> Dimension {
        self.zip(other, Exponent::add)
    }

    /// The quotient of two dimensions.
    pub fn div(&self, other: &Dimension) -> Dimension {
        self.zip(other, |a, b| {
            a.add(Exponent {
                n: b.n.checked_neg()?,
                d: b.d,
            })
        })
    }

    /// This dimension to a rational power.
    pub fn pow(&self, p: &Q) -> Dimension {
        let Some(p) = p.small().and_then(|(n, d)| Exponent::new(n, d)) else {
            return Dimension {
                overflow: true,
                ..*self
            };
        };
        let mut r = *self;
        for a in r.exponents.iter_mut() {
            match a.mul(p) {
                Some(x) => *a = x,
                None => r.overflow = true,
            }
        }
        r
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
            let nonzero: Vec<usize> = (0..5).filter(|&i| !rest.exponents[i].is_zero()).collect();
            if let [i] = nonzero[..] {
                let e = rest.exponents[i];
                if e.d == 1 && e.n.abs() <= 2 {
                    return Some((d.name, i, e.n as i64));
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
        let nonzero = self.exponents.iter().filter(|e| !e.is_zero()).count();
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
            .filter(|&i| !self.exponents[i].is_zero())
            .map(|i| (BASE_DIMENSIONS[i].to_string(), self.exponents[i].to_q()))
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
        for name in [
            "force",
            "energy",
            "length",
            "time",
            "acceleration",
            "power",
            "mass",
        ] {
            assert_eq!(Dimension::named(name).name(), Some(name));
        }
    }

    #[test]
    fn printing() {
        let f = Dimension::named("force");
        let l = Dimension::named("length");
        assert_eq!(f.div(&l).unicode(), "stiffness");
        assert_eq!(
            Dimension::named("energy")
                .div(&l.pow(&Q::from_i64(3)))
                .unicode(),
            "pressure"
        );
        assert_eq!(f.mul(&l).mul(&l).mul(&l).unicode(), "energy·length²");
        assert_eq!(f.mul(&l).mul(&l).mul(&l).ascii(), "energy*length^2");
        let odd = Dimension::from_small([1, 3, -5, 0, 0]);
        assert_eq!(odd.unicode(), "mass·length³·time⁻⁵");
        assert_eq!(odd.ascii(), "mass*length^3/time^5");
        assert_eq!(l.pow(&Q::new(1, 2).unwrap()).ascii(), "length^(1/2)");
        assert_eq!(Dimension::one().phrase(), "dimensionless");
        assert_eq!(Dimension::named("energy").phrase(), "an energy");
        assert_eq!(Dimension::named("energy").plural(), "energies");
        assert_eq!(Dimension::named("mass").plural(), "masses");
    }
}
