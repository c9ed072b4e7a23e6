//! The statements of planar mechanisms: `joint` (a pin or a slider
//! between two bodies), `drive` (a coordinate prescribed in time) and
//! `friction` (Coulomb friction in a joint).

use super::ast::{JointEnd, JointKind, JointStmt};
use super::*;

const JOINT_FORMS: &str = "a joint is written `joint A: pin crank at P, rod at Q` or `joint G: slider ground at P, block at Q along [1, 0]`";

impl<'s> Parser<'s> {
    /// `joint_stmt ::= "joint" ws ident ws ":" ws ( "pin" | "slider" ) ws joint_end ws "," ws joint_end ( ws "along" ws expr )?`
    #[inline(never)]
    pub(super) fn joint_stmt(&self, i: &'s str) -> RuleResult<'s, Stmt> {
        let i = self.ws(i);
        let start = self.pos(i);
        let Some(rest) = i.strip_prefix("joint") else {
            return self.nothing(i);
        };
        let (rest, name) = self.ident(rest)?;
        let rest = self.colon_after(rest, &format!("joint {}", name.name), JOINT_FORMS)?;
        let j = self.ws(rest);
        let len = ident_len(j);
        let kind = match &j[..len] {
            "pin" => JointKind::Pin,
            "slider" => JointKind::Slider,
            _ => {
                return self.fail(self.expected(
                    j,
                    "`pin` or `slider` after the joint's name",
                    JOINT_FORMS,
                    None,
                ))
            }
        };
        let (rest, first) = self.joint_end(&j[len..])?;
        let k = self.ws(rest);
        let Some(rest) = k.strip_prefix(',') else {
            return self.fail(self.expected(
                k,
                "`,` and the second body after the first body's point",
                JOINT_FORMS,
                None,
            ));
        };
        let (rest, second) = self.joint_end(rest)?;
        let k = self.ws(rest);
        let along_word = k
            .strip_prefix("along")
            .filter(|r| !starts_with_class(r, ident_char) && !r.starts_with('('));
        let (rest, along, end) = match (kind, along_word) {
            (JointKind::Slider, Some(r)) => {
                let (rest, (u, outer)) = self.rhs(r, "along")?;
                (rest, Some(u), outer.end)
            }
            (JointKind::Slider, None) => {
                return self.fail(self.expected(
                    k,
                    "`along` and the slider's direction after the second body's point",
                    "a slider keeps the second point on the line through the first along a direction: `joint G: slider ground at [0, 0], block at [xb, yb] along [1, 0]`",
                    None,
                ))
            }
            (JointKind::Pin, Some(_)) => {
                let sp = Span::new(self.pos(k), self.pos(k) + "along".len());
                return self.fail(
                    Diagnostic::error(sp, "a pin has no direction")
                        .with_hint("`along` belongs to a slider: `joint G: slider A at P, B at Q along U`").with_kind(crate::diag::ErrorKind::Syntax),
                );
            }
            (JointKind::Pin, None) => (rest, None, second.point.span.end),
        };
        let span = Span::new(start, end);
        Ok((
            rest,
            Stmt::Joint(JointStmt {
                name,
                kind,
                first,
                second,
                along,
                span,
            }),
        ))
    }

    /// `joint_end ::= ident ws "at" ws expr` (the point ends at a comma or
    /// at the stop word `along`).
    fn joint_end(&self, i: &'s str) -> RuleResult<'s, JointEnd> {
        let (rest, body) = self.ident(i)?;
        let j = self.ws(rest);
        let at = j
            .strip_prefix("at")
            .filter(|r| !starts_with_class(r, ident_char) && !r.starts_with('('));
        let Some(k) = at else {
            return self.fail(self.expected(
                j,
                &format!("`at` and the joint's point after `{}`", body.name),
                JOINT_FORMS,
                None,
            ));
        };
        let at_span = Span::new(self.pos(j), self.pos(j) + 2);
        self.stop.set(true);
        let point = self.expr(k);
        self.stop.set(false);
        match point {
            Ok((rest, node)) => Ok((
                rest,
                JointEnd {
                    body,
                    point: *node.e,
                },
            )),
            Err(nom::Err::Error(_)) => self.fail(self.expected(
                self.ws(k),
                "the joint's point after `at`",
                JOINT_FORMS,
                Some(at_span),
            )),
            Err(e) => Err(e),
        }
    }

    /// `drive_stmt ::= "drive" ws ident ws ":" ws ident ws "=" ws expr`
    #[inline(never)]
    pub(super) fn drive_stmt(&self, i: &'s str) -> RuleResult<'s, Stmt> {
        let i = self.ws(i);
        let start = self.pos(i);
        let Some(rest) = i.strip_prefix("drive") else {
            return self.nothing(i);
        };
        let (rest, name) = self.ident(rest)?;
        let forms = format!(
            "a drive prescribes a coordinate in time: `drive {}: phi = omega*t`",
            name.name
        );
        let rest = self.colon_after(rest, &format!("drive {}", name.name), &forms)?;
        let j = self.ws(rest);
        if ident_len(j) == 0 {
            return self.fail(self.expected(j, "the driven coordinate after `:`", &forms, None));
        }
        let (rest, coordinate) = self.ident(j)?;
        let rest = match self.equals(rest) {
            Ok(k) => k,
            Err(j) => {
                return Err(self.equals_error(
                    j,
                    &format!("drive {}: {}", name.name, coordinate.name),
                    &forms,
                ))
            }
        };
        let (rest, (value, outer)) = self.rhs(rest, "=")?;
        Ok((
            rest,
            Stmt::Drive {
                name,
                coordinate,
                value,
                span: Span::new(start, outer.end),
            },
        ))
    }

    /// `friction_stmt ::= "friction" ws ident ws ":" ws expr`
    #[inline(never)]
    pub(super) fn friction_stmt(&self, i: &'s str) -> RuleResult<'s, Stmt> {
        let i = self.ws(i);
        let start = self.pos(i);
        let Some(rest) = i.strip_prefix("friction") else {
            return self.nothing(i);
        };
        let (rest, joint) = self.ident(rest)?;
        let forms = format!(
            "friction in a joint is written `friction {0}: mu` (a slider) or `friction {0}: mu0*r0` (a pin)",
            joint.name
        );
        let rest = self.colon_after(rest, &format!("friction {}", joint.name), &forms)?;
        let (rest, (coefficient, outer)) = self.rhs(rest, ":")?;
        Ok((
            rest,
            Stmt::Friction {
                joint,
                coefficient,
                span: Span::new(start, outer.end),
            },
        ))
    }

    /// The rest after the `:` that follows `head`, else the error.
    fn colon_after(
        &self,
        i: &'s str,
        head: &str,
        forms: &str,
    ) -> Result<&'s str, nom::Err<RuleError>> {
        let j = self.ws(i);
        match j.strip_prefix(':') {
            Some(k) => Ok(k),
            None => Err(failure(self.expected(
                j,
                &format!("`:` after `{head}`"),
                forms,
                None,
            ))),
        }
    }
}
