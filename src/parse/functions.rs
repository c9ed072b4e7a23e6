//! The built-in functions of the expression language: one table for the
//! evaluator (name, arity), its error hints, the REPL's completion,
//! highlighting and `:help`, and the grammar's documentation.

/// How many arguments a built-in function takes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Arity {
    /// Exactly this many.
    Exactly(usize),
    /// Two or more (`series`, `parallel`), or a form of its own (`subs`).
    Variadic,
}

/// One built-in function.
#[derive(Clone, Copy, Debug)]
pub struct BuiltinFunction {
    /// Its name, as written in a scene.
    pub name: &'static str,
    /// How many arguments it takes.
    pub arity: Arity,
    /// How to call it, for the hint of a wrong number of arguments.
    pub usage: &'static str,
}

const fn f(name: &'static str, n: usize, usage: &'static str) -> BuiltinFunction {
    BuiltinFunction {
        name,
        arity: Arity::Exactly(n),
        usage,
    }
}

const ONE: &str = "one argument, in parentheses";

/// Every built-in function, in the order `:help` lists them.
pub const FUNCTIONS: &[BuiltinFunction] = &[
    f("sin", 1, ONE),
    f("cos", 1, ONE),
    f("tan", 1, ONE),
    f("sqrt", 1, ONE),
    f("exp", 1, ONE),
    f("ln", 1, ONE),
    f("atan", 1, "atan(y/x) is the arctangent of one ratio"),
    f("asin", 1, ONE),
    f("acos", 1, ONE),
    f("dot", 2, "two vectors: dot(a, b), cross(a, b)"),
    f("cross", 2, "two vectors: dot(a, b), cross(a, b)"),
    f("norm", 1, ONE),
    f(
        "rot",
        2,
        "rot(AXIS, ANGLE): AXIS is x, y, z or a unit vector [ux, uy, uz]",
    ),
    f(
        "axis",
        2,
        "axis(F, k) is the k-th unit vector (k = 1, 2, 3) of the frame F",
    ),
    f(
        "express",
        2,
        "express(v, F) is the components of the vector v along the axes of the frame F",
    ),
    f(
        "omega",
        1,
        "omega(F) is the angular velocity of the frame F",
    ),
    f(
        "inertia",
        2,
        "inertia(m, x) is m·x'' for a mass m (or moment of inertia) and a coordinate or point x",
    ),
    BuiltinFunction {
        name: "series",
        arity: Arity::Variadic,
        usage: "write series(k1, k2) or series(k1, k2, k3)",
    },
    BuiltinFunction {
        name: "parallel",
        arity: Arity::Variadic,
        usage: "write parallel(k1, k2) or parallel(k1, k2, k3)",
    },
    f(
        "diff",
        2,
        "diff(f, x) is ∂f/∂x for a coordinate, a velocity (x'), a parameter or t",
    ),
    f("dt", 1, ONE),
    BuiltinFunction {
        name: "subs",
        arity: Arity::Variadic,
        usage: "subs(f, x = value, …)",
    },
    f("expand", 1, ONE),
    f("factor", 1, ONE),
    f(
        "taylor",
        3,
        "taylor(f, x, n) expands f about x = 0 to the power n; taylor(f, x = a, n) about a",
    ),
];

/// The built-in function `name`, if there is one.
pub fn builtin(name: &str) -> Option<&'static BuiltinFunction> {
    FUNCTIONS.iter().find(|f| f.name == name)
}

/// The names of the built-in functions, in table order.
pub fn names() -> impl Iterator<Item = &'static str> {
    FUNCTIONS.iter().map(|f| f.name)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_unique() {
        for (i, a) in FUNCTIONS.iter().enumerate() {
            assert!(
                FUNCTIONS[i + 1..].iter().all(|b| b.name != a.name),
                "{}",
                a.name
            );
        }
    }
}
