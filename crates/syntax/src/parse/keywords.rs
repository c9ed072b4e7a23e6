//! The keywords of the language, and the suggestion for a misspelled one.
//!
//! This is the one list: the parser's statement rules, the suggestion
//! `did you mean `potential`?` and the REPL's completion and highlighting
//! all read it. The role keywords come from [`Role::keyword`] for every
//! role in [`ROLES`]; a new `Role` does not compile until it is listed there.

use super::ast::Role;

/// Every role, in the grammar's order.
pub const ROLES: &[Role] = &[
    Role::Kinetic,
    Role::Potential,
    Role::ForceFunction,
    Role::Work,
    Role::Dissipation,
    Role::Rayleigh,
    Role::Lagrangian,
];

/// The position of `r` in [`ROLES`]: an exhaustive match, so that a new
/// variant of `Role` is a compile error here until [`ROLES`] lists it.
#[cfg_attr(not(test), allow(dead_code))]
const fn role_index(r: Role) -> usize {
    match r {
        Role::Kinetic => 0,
        Role::Potential => 1,
        Role::ForceFunction => 2,
        Role::Work => 3,
        Role::Dissipation => 4,
        Role::Rayleigh => 5,
        Role::Lagrangian => 6,
    }
}

/// The keywords that start a statement, other than the roles.
pub const STATEMENT: &[&str] = &[
    "coordinates",
    "parameters",
    "force",
    "load",
    "torque",
    "solve",
    "latex",
    "frame",
    "body",
    "particle",
    "gravity",
    "functions",
    "assume",
    "constraint",
    "reaction",
    "joint",
    "drive",
    "friction",
];

/// The stop words inside `load … at …`, `torque … on …`, `joint … at
/// … along …` and a body's `inertia … about …`.
pub const STOP: &[&str] = &["at", "on", "along", "about"];

/// The property words of `body` and `particle` (`mass m, at P`).
pub fn body_properties() -> impl Iterator<Item = &'static str> {
    super::ast::PropertyKey::ALL
        .into_iter()
        .map(|k| k.keyword())
}

/// Every keyword that starts a statement: declarations, roles, the rest.
pub fn statement_keywords() -> impl Iterator<Item = &'static str> {
    STATEMENT[..2]
        .iter()
        .copied()
        .chain(ROLES.iter().map(|r| r.keyword()))
        .chain(STATEMENT[2..].iter().copied())
}

/// Every keyword, the stop words included.
pub fn all() -> impl Iterator<Item = &'static str> {
    statement_keywords()
        .chain(STOP.iter().copied())
        .chain(body_properties().filter(|w| !STOP.contains(w) && !STATEMENT.contains(w)))
}

/// The statement keyword `word` is most likely a misspelling of (see
/// [`spelling::nearest`](crate::spelling::nearest)): within edit distance 1
/// of a keyword of up to 6 letters, 2 of a longer one (transpositions count
/// 1; case is ignored). `None` for a keyword itself and for words shorter
/// than 3 letters.
pub fn suggest(word: &str) -> Option<&'static str> {
    crate::spelling::nearest(word, statement_keywords())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn roles_are_listed_once_each_in_their_place() {
        for (i, &r) in ROLES.iter().enumerate() {
            assert_eq!(role_index(r), i);
            assert_eq!(Role::from_keyword(r.keyword()), Some(r));
        }
    }

    #[test]
    fn suggestions() {
        for (typo, kw) in [
            ("potental", "potential"),
            ("coordinate", "coordinates"),
            ("paramters", "parameters"),
            ("kinectic", "kinetic"),
            ("forcefuntion", "forcefunction"),
            ("rayliegh", "rayleigh"),
            ("solv", "solve"),
            ("Potential", "potential"),
            ("torqe", "torque"),
            ("dissipaton", "dissipation"),
        ] {
            assert_eq!(suggest(typo), Some(kw), "{typo}");
        }
        for none in ["potential", "x", "energy", "sin", "mass", "at"] {
            assert_eq!(suggest(none), None, "{none}");
        }
    }
}
