//! The built-in functions of the expression language: one table, written
//! once below, that defines the [`Builtin`] enum (the parser resolves a
//! call's name to it), each function's name, arity and usage (the
//! evaluator's error hints), the REPL's completion, highlighting and
//! `:help`, and the grammar's documentation.

/// How many arguments a built-in function takes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Arity {
    /// Exactly this many.
    Exactly(usize),
    /// Two or more (`series`, `parallel`), or a form of its own (`subs`).
    Variadic,
}

const ONE: &str = "one argument, in parentheses";

/// The table: one row per built-in function, in the order `:help` lists
/// them: `Variant => "name", arity, "usage";`. It defines the enum and
/// every per-function fact, so a function can't be added to one of them
/// and missed by another.
macro_rules! builtins {
    ($($(#[$doc:meta])* $variant:ident => $name:literal, $arity:expr, $usage:expr;)*) => {
        /// A built-in function, resolved from its name by the parser.
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
        pub enum Builtin {
            $($(#[$doc])* $variant,)*
        }

        impl Builtin {
            /// Every built-in function, in the order `:help` lists them.
            pub const ALL: &'static [Builtin] = &[$(Builtin::$variant,)*];

            /// Its name, as written in a scene.
            pub fn name(self) -> &'static str {
                match self {
                    $(Builtin::$variant => $name,)*
                }
            }

            /// How many arguments it takes.
            pub fn arity(self) -> Arity {
                match self {
                    $(Builtin::$variant => $arity,)*
                }
            }

            /// How to call it, for the hint of a wrong number of arguments.
            pub fn usage(self) -> &'static str {
                match self {
                    $(Builtin::$variant => $usage,)*
                }
            }
        }
    };
}

use Arity::{Exactly, Variadic};

builtins! {
    /// `sin(x)`.
    Sin => "sin", Exactly(1), ONE;
    /// `cos(x)`.
    Cos => "cos", Exactly(1), ONE;
    /// `tan(x)` = sin(x)/cos(x).
    Tan => "tan", Exactly(1), ONE;
    /// `sqrt(x)`.
    Sqrt => "sqrt", Exactly(1), ONE;
    /// `exp(x)`.
    Exp => "exp", Exactly(1), ONE;
    /// `ln(x)`, the natural logarithm.
    Ln => "ln", Exactly(1), ONE;
    /// `atan(x)`, the arctangent of one ratio.
    Atan => "atan", Exactly(1), "atan(y/x) is the arctangent of one ratio";
    /// `asin(x)`.
    Asin => "asin", Exactly(1), ONE;
    /// `acos(x)`.
    Acos => "acos", Exactly(1), ONE;
    /// `dot(a, b)`: the scalar product of two vectors.
    Dot => "dot", Exactly(2), "two vectors: dot(a, b), cross(a, b)";
    /// `cross(a, b)`: the vector product (a number for plane vectors).
    Cross => "cross", Exactly(2), "two vectors: dot(a, b), cross(a, b)";
    /// `norm(v)`: the length of a vector.
    Norm => "norm", Exactly(1), ONE;
    /// `rot(AXIS, ANGLE)`: a rotation.
    Rot => "rot", Exactly(2),
        "rot(AXIS, ANGLE): AXIS is x, y, z or a unit vector [ux, uy, uz]";
    /// `axis(F, k)`: the k-th unit vector of a frame.
    Axis => "axis", Exactly(2),
        "axis(F, k) is the k-th unit vector (k = 1, 2, 3) of the frame F";
    /// `express(v, F)`: a vector's components along a frame's axes.
    Express => "express", Exactly(2),
        "express(v, F) is the components of the vector v along the axes of the frame F";
    /// `omega(F)`: a frame's angular velocity.
    Omega => "omega", Exactly(1), "omega(F) is the angular velocity of the frame F";
    /// `inertia(m, x)` = m·x''.
    Inertia => "inertia", Exactly(2),
        "inertia(m, x) is m·x'' for a mass m (or moment of inertia) and a coordinate or point x";
    /// `series(k1, k2, …)`: springs in series, or a Taylor series
    /// (`series(f, x = a, n)`).
    Series => "series", Variadic, "write series(k1, k2) or series(k1, k2, k3)";
    /// `parallel(k1, k2, …)`: springs in parallel.
    Parallel => "parallel", Variadic, "write parallel(k1, k2) or parallel(k1, k2, k3)";
    /// `diff(f, x)` = ∂f/∂x.
    Diff => "diff", Exactly(2),
        "diff(f, x) is ∂f/∂x for a coordinate, a velocity (x'), a parameter or t";
    /// `dt(f)`: the total time derivative.
    Dt => "dt", Exactly(1), ONE;
    /// `subs(f, x = value, …)`.
    Subs => "subs", Variadic, "subs(f, x = value, …)";
    /// `expand(f)`: f, shown expanded.
    Expand => "expand", Exactly(1), ONE;
    /// `factor(f)`: f, shown factored.
    Factor => "factor", Exactly(1), ONE;
    /// `taylor(f, x, n)` or `taylor(f, x = a, n)`.
    Taylor => "taylor", Exactly(3),
        "taylor(f, x, n) expands f about x = 0 to the power n; taylor(f, x = a, n) about a";
}

impl Builtin {
    /// The built-in function called `name`, if there is one.
    pub fn from_name(name: &str) -> Option<Builtin> {
        Builtin::ALL.iter().copied().find(|b| b.name() == name)
    }
}

/// The names of the built-in functions, in table order.
pub fn names() -> impl Iterator<Item = &'static str> {
    Builtin::ALL.iter().map(|b| b.name())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_unique_and_resolve_to_their_function() {
        for (i, a) in Builtin::ALL.iter().enumerate() {
            assert!(
                Builtin::ALL[i + 1..].iter().all(|b| b.name() != a.name()),
                "{}",
                a.name()
            );
            assert_eq!(Builtin::from_name(a.name()), Some(*a));
        }
        assert_eq!(Builtin::from_name("sinh"), None);
        assert_eq!(Builtin::from_name("Sin"), None);
    }

    #[test]
    fn every_variant_is_listed_once() {
        // the match has no wildcard: a new variant fails to compile here
        // until it has a position in the table
        let position = |b: Builtin| match b {
            Builtin::Sin => 0,
            Builtin::Cos => 1,
            Builtin::Tan => 2,
            Builtin::Sqrt => 3,
            Builtin::Exp => 4,
            Builtin::Ln => 5,
            Builtin::Atan => 6,
            Builtin::Asin => 7,
            Builtin::Acos => 8,
            Builtin::Dot => 9,
            Builtin::Cross => 10,
            Builtin::Norm => 11,
            Builtin::Rot => 12,
            Builtin::Axis => 13,
            Builtin::Express => 14,
            Builtin::Omega => 15,
            Builtin::Inertia => 16,
            Builtin::Series => 17,
            Builtin::Parallel => 18,
            Builtin::Diff => 19,
            Builtin::Dt => 20,
            Builtin::Subs => 21,
            Builtin::Expand => 22,
            Builtin::Factor => 23,
            Builtin::Taylor => 24,
        };
        assert_eq!(Builtin::ALL.len(), 25);
        for (i, b) in Builtin::ALL.iter().enumerate() {
            assert_eq!(position(*b), i, "{}", b.name());
        }
    }
}
