//! The solved accelerations q̈ = M⁻¹·f, by coordinate.

use crate::expr::Expr;

/// The exact accelerations, one per coordinate in declaration order.
///
/// ```
/// let scene = qdot_mechanics::scene::Scene::parse("coordinates x\nparameters m, k\n\
///     kinetic E = 1/2*m*x'^2\npotential V = 1/2*k*x^2").unwrap();
/// let acc = scene.lagrange().unwrap().accelerations().unwrap();
/// assert_eq!(acc["x"].to_string(), "-k*x/m");
/// for (q, a) in &acc {
///     assert_eq!((q, a.to_string().as_str()), ("x", "-k*x/m"));
/// }
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Accelerations {
    coordinates: Vec<String>,
    values: Vec<Expr>,
    /// The constraints' multipliers (name, λ), in constraint order.
    multipliers: Vec<(String, Expr)>,
    /// The intermediates the values are written through, if any.
    intermediates: Option<Box<crate::expr::tape::Tape>>,
}

impl Accelerations {
    /// Pair the coordinates with their accelerations (same length).
    pub(crate) fn new(coordinates: Vec<String>, values: Vec<Expr>) -> Accelerations {
        debug_assert_eq!(coordinates.len(), values.len());
        Accelerations {
            coordinates,
            values,
            multipliers: Vec::new(),
            intermediates: None,
        }
    }

    /// Write the values through `tape`'s intermediates.
    pub(crate) fn set_intermediates(&mut self, tape: crate::expr::tape::Tape) {
        self.intermediates = Some(Box::new(tape));
    }

    /// The intermediates the values mention, if they are written through
    /// some (see [`crate::expr::tape`]).
    pub fn intermediates(&self) -> Option<&crate::expr::tape::Tape> {
        self.intermediates.as_deref()
    }

    /// Attach the multipliers λ of the constraints (same length as `names`).
    pub(crate) fn set_multipliers(&mut self, names: Vec<String>, values: Vec<Expr>) {
        debug_assert_eq!(names.len(), values.len());
        self.multipliers = names.into_iter().zip(values).collect();
    }

    /// The Lagrange multipliers (name, λ) of the scene's constraints, in
    /// their order: λ_j·a_jk is the generalized force of constraint j on
    /// q_k. Empty without constraints.
    pub fn multipliers(&self) -> &[(String, Expr)] {
        &self.multipliers
    }

    /// q̈ of the coordinate `name`, if it is one.
    pub fn get(&self, name: &str) -> Option<&Expr> {
        let k = self.coordinates.iter().position(|c| c == name)?;
        self.values.get(k)
    }

    /// The coordinates, in declaration order.
    pub fn coordinates(&self) -> &[String] {
        &self.coordinates
    }

    /// The accelerations, in the coordinates' order.
    pub fn values(&self) -> &[Expr] {
        &self.values
    }

    /// (coordinate, q̈) pairs in declaration order.
    pub fn iter(&self) -> impl Iterator<Item = (&str, &Expr)> {
        self.coordinates
            .iter()
            .map(String::as_str)
            .zip(self.values.iter())
    }

    /// The number of coordinates.
    pub fn len(&self) -> usize {
        self.values.len()
    }

    /// True for a scene without coordinates.
    pub fn is_empty(&self) -> bool {
        self.values.is_empty()
    }
}

impl std::ops::Index<&str> for Accelerations {
    type Output = Expr;

    /// q̈ of the coordinate `name`; panics if it is not a coordinate (use
    /// [`Accelerations::get`] to ask).
    fn index(&self, name: &str) -> &Expr {
        match self.get(name) {
            Some(e) => e,
            // qdot's own code never indexes by name: no scene reaches this
            None => panic!("`{name}` is not a coordinate"), // ok: `Index`'s documented contract
        }
    }
}

impl<'a> IntoIterator for &'a Accelerations {
    type Item = (&'a str, &'a Expr);
    type IntoIter = std::iter::Zip<
        std::iter::Map<std::slice::Iter<'a, String>, fn(&String) -> &str>,
        std::slice::Iter<'a, Expr>,
    >;

    fn into_iter(self) -> Self::IntoIter {
        let name: fn(&String) -> &str = String::as_str;
        self.coordinates.iter().map(name).zip(self.values.iter())
    }
}

impl IntoIterator for Accelerations {
    type Item = (String, Expr);
    type IntoIter = std::iter::Zip<std::vec::IntoIter<String>, std::vec::IntoIter<Expr>>;

    fn into_iter(self) -> Self::IntoIter {
        self.coordinates.into_iter().zip(self.values)
    }
}
