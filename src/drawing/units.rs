//! The SI unit of a dimension, as an axis's name writes it: `m`, `rad/s`,
//! `J` (not `kg·m²/s²`), `kg^(1/2)·m`.

use crate::scene::dimension::{Dimension, DimensionNameKind, DIMENSION_NAMES};

/// What a coordinate measures: its dimension, and whether it is an angle
/// (an angle and a pure number share the dimension one; the scene's
/// `angle` or `rad` says which).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Quantity {
    /// The dimension.
    pub dimension: Dimension,
    /// Declared `angle` or `rad`: measured in radians.
    pub angle: bool,
}

impl Quantity {
    /// The unit of the quantity: `m`, `rad`; `None` for a pure number.
    pub fn unit(&self) -> Option<String> {
        with_radians(si_unit(&self.dimension), self.angle)
    }

    /// The unit of its rate of change: `m/s`, `rad/s`, `1/s`.
    pub fn rate_unit(&self) -> Option<String> {
        let rate = self.dimension.div(&Dimension::TIME);
        with_radians(si_unit(&rate), self.angle)
    }

    /// The quantities of its kind, for a panel's caption: `angles`,
    /// `lengths`; `None` where the dimension has no name.
    pub fn plural(&self) -> Option<String> {
        if self.angle {
            return Some("angles".into());
        }
        match self.dimension.name() {
            Some("dimensionless") | None => None,
            Some(_) => Some(self.dimension.plural()),
        }
    }
}

/// `rad` times a unit: `rad`, `rad/s`, `rad·m`.
fn with_radians(unit: Option<String>, angle: bool) -> Option<String> {
    match (unit, angle) {
        (u, false) => u,
        (None, true) => Some("rad".into()),
        (Some(u), true) => Some(match u.strip_prefix("1/") {
            Some(per) => format!("rad/{per}"),
            None => format!("rad·{u}"),
        }),
    }
}

/// The symbol of the table's unit of exactly this dimension, if any.
fn symbol_of(d: &Dimension, fits: impl Fn(&[i8; 5]) -> bool) -> Option<&'static str> {
    DIMENSION_NAMES
        .iter()
        .filter(|n| n.kind == DimensionNameKind::Unit && fits(&n.exponents))
        .find(|n| Dimension::from_small(n.exponents) == *d)
        .map(|n| n.name)
}

/// The SI unit of a dimension (`None` for a pure number): a named unit
/// of two base dimensions or more where one fits exactly (`N`, `J`, `W`,
/// `Pa`), else a product of the base units (a rate stays `1/s`, not `Hz`).
pub fn si_unit(d: &Dimension) -> Option<String> {
    if d.is_one() || d.overflowed() {
        return None;
    }
    let named = |e: &[i8; 5]| e.iter().filter(|x| **x != 0).count() >= 2;
    if let Some(s) = symbol_of(d, named) {
        return Some(s.to_string());
    }
    let (mut over, mut under) = (Vec::new(), Vec::new());
    for (i, q) in d.exponents().iter().enumerate() {
        let (num, den) = q.small()?;
        if num == 0 {
            continue;
        }
        let mut unit = [0i8; 5];
        unit[i] = 1;
        let base = symbol_of(&Dimension::from_small(unit), |_| true).unwrap_or("?");
        let factor = power(base, num.abs(), den);
        if num > 0 {
            over.push(factor);
        } else {
            under.push(factor);
        }
    }
    let over = if over.is_empty() {
        "1".to_string()
    } else {
        over.join("·")
    };
    Some(match under.len() {
        0 => over,
        1 => format!("{over}/{}", under[0]),
        _ => format!("{over}/({})", under.join("·")),
    })
}

/// `base` to the power num/den (num > 0): `m`, `s²`, `kg^(1/2)`.
fn power(base: &str, num: i64, den: i64) -> String {
    const DIGITS: [char; 10] = ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹'];
    match (num, den) {
        (1, 1) => base.to_string(),
        (n, 1) => {
            let sup: String = n
                .to_string()
                .chars()
                .map(|c| DIGITS[c.to_digit(10).unwrap_or(0) as usize])
                .collect();
            format!("{base}{sup}")
        }
        (n, d) => format!("{base}^({n}/{d})"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::num::Q;

    fn q(e: [i8; 5], angle: bool) -> Quantity {
        Quantity {
            dimension: Dimension::from_small(e),
            angle,
        }
    }

    #[test]
    fn units_are_written_as_a_lecturer_would() {
        assert_eq!(q([0, 1, 0, 0, 0], false).unit().as_deref(), Some("m"));
        assert_eq!(
            q([0, 1, 0, 0, 0], false).rate_unit().as_deref(),
            Some("m/s")
        );
        assert_eq!(q([0; 5], true).unit().as_deref(), Some("rad"));
        assert_eq!(q([0; 5], true).rate_unit().as_deref(), Some("rad/s"));
        assert_eq!(q([0; 5], false).unit(), None);
        assert_eq!(q([0; 5], false).rate_unit().as_deref(), Some("1/s"));
        assert_eq!(si_unit(&Dimension::ENERGY).as_deref(), Some("J"));
        assert_eq!(si_unit(&Dimension::FORCE).as_deref(), Some("N"));
        assert_eq!(si_unit(&Dimension::TIME).as_deref(), Some("s"));
        assert_eq!(si_unit(&Dimension::AREA).as_deref(), Some("m²"));
        // mass·length²·time⁻¹ has no symbol of its own
        assert_eq!(
            si_unit(&Dimension::from_small([1, 2, -1, 0, 0])).as_deref(),
            Some("kg·m²/s")
        );
        assert_eq!(
            si_unit(&Dimension::from_small([0, 0, -2, 0, 1])).as_deref(),
            Some("K/s²")
        );
        assert_eq!(
            si_unit(&Dimension::from_small([-1, 0, -2, 0, 0])).as_deref(),
            Some("1/(kg·s²)")
        );
        let root = Dimension::MASS.pow(&Q::new(1, 2).unwrap());
        assert_eq!(si_unit(&root).as_deref(), Some("kg^(1/2)"));
        assert_eq!(
            q([0, 1, 0, 0, 0], false).plural().as_deref(),
            Some("lengths")
        );
        assert_eq!(q([0; 5], true).plural().as_deref(), Some("angles"));
        assert_eq!(q([0; 5], false).plural(), None);
    }
}
