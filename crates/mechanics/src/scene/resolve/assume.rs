//! `assume e real, R > r`: the scene's assumptions beyond positive
//! parameters ([`crate::algebra::assume`]).

use super::Resolver;
use crate::algebra::assume::Assumptions;
use crate::algebra::sign::Sign;
use crate::diag::Diagnostic;
use crate::expr::atom;
use crate::parse::ast::{Fact, Stmt};
use crate::scene::Parameter;

impl Resolver<'_> {
    /// Every `assume` statement's facts, checked: `real` names a
    /// parameter; an order compares constants and is not known false.
    pub(super) fn assumptions(
        &mut self,
        stmts: &[Stmt],
        parameters: &[Parameter],
    ) -> Result<Assumptions, Diagnostic> {
        let mut real = Vec::new();
        let mut positive = Vec::new();
        for st in stmts {
            let Stmt::Assume(facts, _) = st else { continue };
            for f in facts {
                match f {
                    Fact::Real(name) => {
                        if !parameters.iter().any(|p| p.name == name.name) {
                            return Err(Diagnostic::error(
                                name.span,
                                format!("`assume {} real` needs a parameter, and `{0}` is not one", name.name),
                            )
                            .with_hint("coordinates and definitions have the signs their values give; declare it with `parameters`").with_kind(crate::diag::ErrorKind::InvalidScene));
                        }
                        let v = atom::param(&name.name);
                        if !real.contains(&v) {
                            real.push(v);
                        }
                    }
                    Fact::Order {
                        greater,
                        less,
                        span,
                    } => {
                        let d = self.ev.expr(greater)?.sub(&self.ev.expr(less)?);
                        if d.is_time_dependent() {
                            return Err(Diagnostic::error(
                                *span,
                                "an order fact compares constants, and this one changes with time",
                            )
                            .with_hint("assume facts about the parameters: `assume R > r`")
                            .with_kind(crate::diag::ErrorKind::InvalidScene));
                        }
                        if let Some(u) = crate::scene::first_unknown(&d) {
                            return Err(Diagnostic::error(
                                *span,
                                format!("an order fact uses `{u}`, an unknown of a `solve` block"),
                            )
                            .with_hint("assume facts about the parameters: `assume R > r`")
                            .with_kind(crate::diag::ErrorKind::InvalidScene));
                        }
                        let so_far = Assumptions::new(real.clone(), positive.clone());
                        let known = crate::algebra::assume::sign_under(&so_far, &d);
                        match known {
                            Some(Sign::Positive) => {}
                            Some(_) => return Err(Diagnostic::error(
                                *span,
                                "this fact is false for the parameters as declared",
                            )
                            .with_hint(
                                "parameters are positive unless assumed `real`; check the order",
                            )
                            .with_kind(crate::diag::ErrorKind::Unphysical)),
                            None => positive.push(d),
                        }
                    }
                }
            }
        }
        Ok(Assumptions::new(real, positive))
    }
}
