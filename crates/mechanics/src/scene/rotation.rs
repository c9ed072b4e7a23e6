//! Rotations: the orientation of a frame in the ground frame.
//!
//! A [`Rotation`] keeps the body-fixed sequence of elementary turns it was
//! built from (`rot(z, phi) * rot(x, theta)`: turn about z, then about the
//! new x) beside its matrix R, whose columns are the frame's unit vectors
//! in ground components. The sequence gives the angular velocity without
//! differentiating R: for R = R₁·R₂·…·Rₙ, turn i about the constant unit
//! axis uᵢ by θᵢ,
//!
//! ```text
//! ω (ground components) = Σᵢ R₁⋯Rᵢ₋₁·uᵢ·θ̇ᵢ
//! ω (frame components)  = Σᵢ (Rᵢ₊₁⋯Rₙ)ᵀ·uᵢ·θ̇ᵢ
//! ```
//!
//! (Rᵢᵀ·uᵢ = uᵢ: a turn leaves its axis in place). Both are evaluated by
//! Horner's scheme, one matrix–vector product per turn, so they come out
//! in the textbook's form (φ̇·sin θ·sin ψ + θ̇·cos ψ, …) and equal the axial
//! vector of Ṙ·Rᵀ exactly (a test checks it).

use crate::expr::{func, Expr};

/// A 3×3 matrix of exact expressions, row-major.
pub type Matrix3 = [[Expr; 3]; 3];

/// One elementary turn: by `angle` about the constant unit vector `axis`.
#[derive(Clone, Debug)]
struct Turn {
    axis: [Expr; 3],
    angle: Expr,
    matrix: Matrix3,
}

/// A rotation (see the module docs).
///
/// Invariant: `matrix` is the product of the turns' matrices, in order;
/// every axis is a constant unit vector.
#[derive(Clone, Debug)]
pub struct Rotation {
    turns: Vec<Turn>,
    matrix: Matrix3,
    /// The nine entries of `matrix`, row by row (what [`super::Value`]'s
    /// components are for a rotation).
    entries: Vec<Expr>,
    /// The angular velocity in the frame's components, when it is kept
    /// (named on a tape, with the matrix): then the matrix's entries are
    /// the tape's names for the product of the turns, and composition
    /// goes on from the names instead of the turns.
    omega: Option<[Expr; 3]>,
}

/// Why a turn can't be built, or two rotations composed.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum TurnError {
    /// The composition would have more than
    /// [`crate::limits::MAX_ROTATION_TURNS`] turns.
    TooManyTurns,
    /// The axis is not of length 1: the squared length it has.
    NotUnit(String),
    /// The axis changes with time.
    Moving,
}

fn identity() -> Matrix3 {
    let (o, z) = (Expr::one(), Expr::zero());
    [
        [o.clone(), z.clone(), z.clone()],
        [z.clone(), o.clone(), z.clone()],
        [z.clone(), z, o],
    ]
}

fn entries_of(m: &Matrix3) -> Vec<Expr> {
    m.iter().flatten().cloned().collect()
}

/// a·b of two 3×3 matrices.
fn product(a: &Matrix3, b: &Matrix3) -> Matrix3 {
    std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            (0..3).fold(Expr::zero(), |s, k| {
                if a[i][k].is_zero() || b[k][j].is_zero() {
                    s
                } else {
                    s.add(&a[i][k].mul(&b[k][j]))
                }
            })
        })
    })
}

/// m·v, or mᵀ·v when `transpose`.
fn apply(m: &Matrix3, v: &[Expr; 3], transpose: bool) -> [Expr; 3] {
    std::array::from_fn(|i| {
        (0..3).fold(Expr::zero(), |s, k| {
            let e = if transpose { &m[k][i] } else { &m[i][k] };
            if e.is_zero() || v[k].is_zero() {
                s
            } else {
                s.add(&e.mul(&v[k]))
            }
        })
    })
}

impl Rotation {
    /// The identity: the ground frame itself.
    pub fn identity() -> Rotation {
        let matrix = identity();
        Rotation {
            turns: Vec::new(),
            entries: entries_of(&matrix),
            matrix,
            omega: None,
        }
    }

    /// The turn by `angle` about `axis`, a constant unit vector (Rodrigues:
    /// R = cos θ·I + sin θ·\[u\]× + (1 − cos θ)·u·uᵀ).
    pub fn turn(axis: [Expr; 3], angle: Expr) -> Result<Rotation, TurnError> {
        if axis.iter().any(Expr::is_time_dependent) {
            return Err(TurnError::Moving);
        }
        let length2 = axis.iter().fold(Expr::zero(), |s, c| s.add(&c.mul(c)));
        if !length2.equals(&Expr::one()) {
            return Err(TurnError::NotUnit(length2.to_input()));
        }
        let (c, s) = (func::cos(&angle), func::sin(&angle));
        let one_c = Expr::one().sub(&c);
        let u = &axis;
        // [u]× v = u × v
        let cross = [
            [Expr::zero(), u[2].neg(), u[1].clone()],
            [u[2].clone(), Expr::zero(), u[0].neg()],
            [u[1].neg(), u[0].clone(), Expr::zero()],
        ];
        let matrix: Matrix3 = std::array::from_fn(|i| {
            std::array::from_fn(|j| {
                let diagonal = if i == j { c.clone() } else { Expr::zero() };
                diagonal
                    .add(&s.mul(&cross[i][j]))
                    .add(&one_c.mul(&u[i].mul(&u[j])))
            })
        });
        Ok(Rotation {
            entries: entries_of(&matrix),
            turns: vec![Turn {
                axis,
                angle,
                matrix: matrix.clone(),
            }],
            matrix,
            omega: None,
        })
    }

    /// The unit vector along the coordinate axis `k` (0, 1, 2).
    pub fn unit(k: usize) -> [Expr; 3] {
        std::array::from_fn(|i| if i == k { Expr::one() } else { Expr::zero() })
    }

    /// `self * other`: first this rotation, then `other` about the turned
    /// axes (the body-fixed sequence). Its entries are counted against the
    /// work budget ([`crate::budget`]): products of many turns about
    /// different constant angles double in size with each turn.
    pub fn then(&self, other: &Rotation) -> Result<Rotation, TurnError> {
        if self.turns.len() + other.turns.len() > crate::limits::MAX_ROTATION_TURNS {
            return Err(TurnError::TooManyTurns);
        }
        let matrix = if self.turns.is_empty() {
            other.matrix.clone()
        } else if other.turns.is_empty() {
            self.matrix.clone()
        } else {
            product(&self.matrix, &other.matrix)
        };
        let entries = entries_of(&matrix);
        // a rotation is nine entries, each multiplied into every vector it
        // turns: it gets an eighth of the budget
        let terms: usize = entries.iter().map(|e| e.num().len() + e.den().len()).sum();
        crate::budget::check_terms(terms.saturating_mul(8));
        let mut turns = self.turns.clone();
        turns.extend(other.turns.iter().cloned());
        let omega = (self.omega.is_some() || other.omega.is_some()).then(|| {
            // ω of R·S along S's axes: Sᵀ·ω_R + ω_S
            let back = apply(&other.matrix, &self.omega_frame(), true);
            let own = other.omega_frame();
            std::array::from_fn(|i| back[i].add(&own[i]))
        });
        Ok(Rotation {
            entries,
            turns,
            matrix,
            omega,
        })
    }

    /// The matrix R (columns: the frame's unit vectors in ground components).
    pub fn matrix(&self) -> &Matrix3 {
        &self.matrix
    }

    /// R's nine entries, row by row.
    pub fn entries(&self) -> &[Expr] {
        &self.entries
    }

    /// The frame's unit vector `k` (0, 1, 2) in ground components: column k.
    pub fn axis(&self, k: usize) -> [Expr; 3] {
        std::array::from_fn(|i| self.matrix[i][k].clone())
    }

    /// R·v: the ground components of the vector whose frame components are v.
    pub fn to_ground(&self, v: &[Expr; 3]) -> [Expr; 3] {
        apply(&self.matrix, v, false)
    }

    /// Rᵀ·v: the frame components of the ground vector v.
    pub fn to_frame(&self, v: &[Expr; 3]) -> [Expr; 3] {
        apply(&self.matrix, v, true)
    }

    /// The same turns with `matrix` and `omega` standing for their
    /// product and angular velocity (a tape's names for them).
    pub fn with_structure(&self, matrix: Matrix3, omega: [Expr; 3]) -> Rotation {
        Rotation {
            entries: entries_of(&matrix),
            turns: self.turns.clone(),
            matrix,
            omega: Some(omega),
        }
    }

    /// The angular velocity in ground components (see the module docs).
    pub fn omega_ground(&self) -> [Expr; 3] {
        if let Some(w) = &self.omega {
            return apply(&self.matrix, w, false);
        }
        let mut w: [Expr; 3] = std::array::from_fn(|_| Expr::zero());
        for t in self.turns.iter().rev() {
            let rate = t.angle.dt();
            let turned = apply(&t.matrix, &w, false);
            w = std::array::from_fn(|i| turned[i].add(&t.axis[i].mul(&rate)));
        }
        w
    }

    /// The angular velocity in the frame's own components.
    pub fn omega_frame(&self) -> [Expr; 3] {
        if let Some(w) = &self.omega {
            return w.clone();
        }
        let mut w: [Expr; 3] = std::array::from_fn(|_| Expr::zero());
        for t in &self.turns {
            let rate = t.angle.dt();
            let back = apply(&t.matrix, &w, true);
            w = std::array::from_fn(|i| back[i].add(&t.axis[i].mul(&rate)));
        }
        w
    }

    /// The rotation in input syntax, as its turns: `rot(z, phi)*rot(x, theta)`
    /// (`rot(z, 0)` for the identity); it re-parses to the same rotation.
    pub fn to_input(&self) -> String {
        if self.turns.is_empty() {
            return "rot(z, 0)".into();
        }
        let names = ["x", "y", "z"];
        let parts: Vec<String> = self
            .turns
            .iter()
            .map(|t| {
                let axis = (0..3)
                    .find(|&k| {
                        t.axis
                            .iter()
                            .enumerate()
                            .all(|(i, c)| if i == k { c.is_one() } else { c.is_zero() })
                    })
                    .map_or_else(
                        || {
                            let c: Vec<String> = t.axis.iter().map(Expr::to_input).collect();
                            format!("[{}]", c.join(", "))
                        },
                        |k| names[k].to_string(),
                    );
                format!("rot({axis}, {})", t.angle.to_input())
            })
            .collect();
        parts.join("*")
    }

    /// Whether the rotation changes with time.
    pub fn is_moving(&self) -> bool {
        self.turns.iter().any(|t| t.angle.is_time_dependent())
    }

    /// The same rotation with `f` applied to every axis and angle (a
    /// substitution), its matrix rebuilt.
    pub fn map_angles(&self, mut f: impl FnMut(&Expr) -> Expr) -> Result<Rotation, TurnError> {
        let mut r = Rotation::identity();
        for t in &self.turns {
            let axis = [f(&t.axis[0]), f(&t.axis[1]), f(&t.axis[2])];
            r = r.then(&Rotation::turn(axis, f(&t.angle))?)?;
        }
        Ok(r)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn angle(n: &str) -> Expr {
        Expr::coord(n, 0)
    }

    fn rate(n: &str) -> Expr {
        Expr::coord(n, 1)
    }

    fn turn(k: usize, a: &str) -> Rotation {
        Rotation::turn(Rotation::unit(k), angle(a)).unwrap()
    }

    fn same(a: &[Expr; 3], b: &[Expr; 3]) {
        for (x, y) in a.iter().zip(b) {
            assert!(x.equals(y), "{x} vs {y}");
        }
    }

    /// ω = axial vector of Ṙ·Rᵀ, the definition, for a 3-1-3 and a 1-2-3
    /// sequence; and the frame components are Rᵀ·ω.
    #[test]
    fn omega_is_the_axial_vector_of_rdot_rt() {
        for seq in [[2, 0, 2], [0, 1, 2]] {
            let r = turn(seq[0], "p")
                .then(&turn(seq[1], "q"))
                .unwrap()
                .then(&turn(seq[2], "s"))
                .unwrap();
            let m = r.matrix();
            let rd: Matrix3 = std::array::from_fn(|i| std::array::from_fn(|j| m[i][j].dt()));
            let rt: Matrix3 = std::array::from_fn(|i| std::array::from_fn(|j| m[j][i].clone()));
            let w = product(&rd, &rt);
            let axial = [w[2][1].clone(), w[0][2].clone(), w[1][0].clone()];
            same(&r.omega_ground(), &axial);
            same(&r.omega_frame(), &r.to_frame(&r.omega_ground()));
        }
    }

    /// The 3-1-3 table: ω along the body axes is
    /// (φ̇ sin θ sin ψ + θ̇ cos ψ, φ̇ sin θ cos ψ − θ̇ sin ψ, φ̇ cos θ + ψ̇).
    #[test]
    fn euler_313_table() {
        let r = turn(2, "phi")
            .then(&turn(0, "th"))
            .unwrap()
            .then(&turn(2, "psi"))
            .unwrap();
        let (s, c) = (
            |n: &str| func::sin(&angle(n)),
            |n: &str| func::cos(&angle(n)),
        );
        let want = [
            rate("phi")
                .mul(&s("th"))
                .mul(&s("psi"))
                .add(&rate("th").mul(&c("psi"))),
            rate("phi")
                .mul(&s("th"))
                .mul(&c("psi"))
                .sub(&rate("th").mul(&s("psi"))),
            rate("phi").mul(&c("th")).add(&rate("psi")),
        ];
        same(&r.omega_frame(), &want);
    }

    #[test]
    fn axes_must_be_constant_unit_vectors() {
        let half = Expr::rational(crate::num::Q::new(1, 2).unwrap());
        let bad = [half.clone(), half, Expr::zero()];
        assert!(matches!(
            Rotation::turn(bad, angle("a")),
            Err(TurnError::NotUnit(_))
        ));
        let moving = [func::cos(&angle("b")), func::sin(&angle("b")), Expr::zero()];
        assert_eq!(
            Rotation::turn(moving, angle("a")).unwrap_err(),
            TurnError::Moving
        );
        let p = Expr::param("a");
        let unit = [func::cos(&p), func::sin(&p), Expr::zero()];
        assert!(Rotation::turn(unit, angle("c")).is_ok());
    }
}
