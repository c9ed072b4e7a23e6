//! `inertia I about P`: an inertia given about a point of the body other
//! than its centre of mass (a top's fixed point, as textbooks give it),
//! turned into the inertia about the centre by the parallel-axis theorem,
//! I_C = I_P − m·(|d|²·1 − d·dᵀ), d = C − P along the body's axes (in the
//! plane J_C = J_P − m·|d|²). P is written in ground components, like the
//! centre C; it must be a point of the body, so d along the body's axes
//! is constant. The result is checked as any inertia about the centre:
//! a provably impossible one is refused, an undecided one is a warning.

use super::inertia::{self, Written};
use super::{positions_only, Resolver, Value};
use crate::algebra::assume::sign_under;
use crate::algebra::sign::Sign;
use crate::diag::Diagnostic;
use crate::expr::Expr;
use crate::parse::ast::{About, BodyProperty, Span};
use crate::scene::rotation::Rotation;

/// How a point of the body is written, for hints.
const POINT_HINT: &str = "P is in ground components, like the centre of mass, and moves with the body: a top's fixed point at the origin is `about [0, 0, 0]`, the end of a rod `about C - l/2*axis(B, 3)` for its centre C";

/// The label at `about P` in the plane (`inertia` labels the space's).
const PLANE_LABEL: &str = "the moment is given about this point; about the centre of mass it is J − m·|d|², d from this point to the centre";

/// The body an inertia `about` a point belongs to.
pub(super) struct Owner<'a> {
    /// Its name.
    pub(super) name: &'a str,
    /// Its mass; `None` for a body without one (its centre fixed).
    pub(super) mass: Option<&'a Expr>,
    /// Its centre of mass, 2 or 3 components.
    pub(super) centre: &'a [Expr],
}

/// `[a, b, c]`, for messages.
fn vector_input(v: &[Expr]) -> String {
    let parts: Vec<String> = v.iter().map(Expr::to_input).collect();
    format!("[{}]", parts.join(", "))
}

/// Where `inertia I about P` is written from `about` to the point's end.
fn about_span(about: &About) -> Span {
    about.key_span.to(about.point.span)
}

impl Resolver<'_> {
    /// The inertia about the centre of a body in space whose inertia `i`
    /// is given about `about`'s point; `r` is its frame.
    pub(super) fn space_about(
        &mut self,
        p: &BodyProperty,
        about: &About,
        i: [[Expr; 3]; 3],
        r: &Rotation,
        owner: &Owner,
    ) -> Result<[[Expr; 3]; 3], Diagnostic> {
        let ground = self.offset(about, owner)?;
        let d = r.to_frame(&[ground[0].clone(), ground[1].clone(), ground[2].clone()]);
        self.fixed_in_body(about, owner, &d)?;
        let Some(m) = self.mass_for(about, owner, &d)? else {
            return Ok(i);
        };
        let d2 = d.iter().fold(Expr::zero(), |s, c| s.add(&c.mul(c)));
        let centroidal: [[Expr; 3]; 3] = std::array::from_fn(|a| {
            std::array::from_fn(|b| {
                let shift = if a == b {
                    d2.sub(&d[a].mul(&d[b]))
                } else {
                    d[a].mul(&d[b]).neg()
                };
                i[a][b].sub(&m.mul(&shift))
            })
        });
        let written = Written {
            body: owner.name,
            span: p.value.span,
            moments: None,
            about: Some(about_span(about)),
        };
        if let Some(w) = inertia::check(&centroidal, &written, &self.assumed)? {
            self.warnings.push(w);
        }
        Ok(centroidal)
    }

    /// The moment of inertia about the centre of a body in the plane
    /// whose moment `j` is given about `about`'s point; `angle` is its angle.
    pub(super) fn plane_about(
        &mut self,
        p: &BodyProperty,
        about: &About,
        j: Expr,
        angle: &Expr,
        owner: &Owner,
    ) -> Result<Expr, Diagnostic> {
        let ground = self.offset(about, owner)?;
        let (s, c) = crate::expr::func::sin_cos(angle);
        let d = [
            c.mul(&ground[0]).add(&s.mul(&ground[1])),
            c.mul(&ground[1]).sub(&s.mul(&ground[0])),
        ];
        self.fixed_in_body(about, owner, &d)?;
        let Some(m) = self.mass_for(about, owner, &d)? else {
            return Ok(j);
        };
        let d2 = d.iter().fold(Expr::zero(), |s, c| s.add(&c.mul(c)));
        let centroidal = j.sub(&m.mul(&d2));
        let who = format!("`{}` about its centre of mass", owner.name);
        match sign_under(&self.assumed, &centroidal) {
            Some(Sign::Negative) => Err(Diagnostic::error(
                p.value.span,
                format!(
                    "the inertia of {who}: a moment of inertia can't be negative, and {} is",
                    centroidal.to_input()
                ),
            )
            .with_label(about_span(about), PLANE_LABEL)
            .with_hint("the moment about a point exceeds the one about the centre by m·|d|², d from the point to the centre: check the moment and the point").with_kind(crate::diag::ErrorKind::Unphysical)),
            Some(_) => Ok(centroidal),
            None => {
                self.warnings.push(
                    Diagnostic::warning(
                        p.value.span,
                        format!(
                            "qdot can't tell that the inertia of {who} is one a rigid body can have: {} ≥ 0 is not decided",
                            centroidal.to_input()
                        ),
                    )
                    .with_label(about_span(about), PLANE_LABEL)
                    .with_hint(format!(
                        "a moment of inertia is ≥ 0; state it with `assume {} > 0` or give numbers",
                        centroidal.to_input()
                    )),
                );
                Ok(centroidal)
            }
        }
    }

    /// C − P in ground components: P a position like the centre.
    fn offset(&mut self, about: &About, owner: &Owner) -> Result<Vec<Expr>, Diagnostic> {
        let span = about.point.span;
        let point = match self.ev.value(&about.point)? {
            Value::Vector(c) if c.len() == owner.centre.len() => c,
            v => {
                return Err(Diagnostic::error(
                    span,
                    format!(
                        "the point an inertia is taken about is a position like the centre of `{}`, a vector with {} components, and this is {}",
                        owner.name,
                        owner.centre.len(),
                        v.describe()
                    ),
                )
                .with_hint(POINT_HINT).with_kind(crate::diag::ErrorKind::TypeMismatch))
            }
        };
        positions_only(&point, span, "the point of `about`")?;
        Ok(owner
            .centre
            .iter()
            .zip(&point)
            .map(|(c, p)| c.sub(p))
            .collect())
    }

    /// An error unless `d` (from the point to the centre, along the body's
    /// axes) is constant: the point is one of the body's.
    fn fixed_in_body(&self, about: &About, owner: &Owner, d: &[Expr]) -> Result<(), Diagnostic> {
        if d.iter().any(Expr::is_time_dependent) {
            return Err(Diagnostic::error(
                about.point.span,
                format!(
                    "an inertia is taken about a point of the body, and this point moves against `{}`: from it to the centre of mass is {} along the body's axes, which changes with time",
                    owner.name,
                    vector_input(d)
                ),
            )
            .with_hint(POINT_HINT).with_kind(crate::diag::ErrorKind::InvalidScene));
        }
        Ok(())
    }

    /// The mass the parallel-axis theorem needs: `None` when the point is
    /// the centre itself (nothing to move), an error for a body without a
    /// mass otherwise.
    fn mass_for<'m>(
        &self,
        about: &About,
        owner: &Owner<'m>,
        d: &[Expr],
    ) -> Result<Option<&'m Expr>, Diagnostic> {
        if d.iter().all(Expr::is_zero) {
            return Ok(None);
        }
        match owner.mass {
            Some(m) => Ok(Some(m)),
            None => Err(Diagnostic::error(
                about.key_span,
                format!(
                    "`{}` has no mass, and moving its inertia from this point to its centre of mass (the parallel-axis theorem) needs one",
                    owner.name
                ),
            )
            .with_hint("give its mass (`mass m`), or its inertia about its centre (without `about`)").with_kind(crate::diag::ErrorKind::InvalidScene)),
        }
    }
}
