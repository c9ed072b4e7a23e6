//! The `constraint` statement: a holonomic constraint or one linear in the
//! velocities, each with a Lagrange multiplier; and `reaction`, the force
//! of a constraint at a point.

use super::*;

impl<'s> Parser<'s> {
    /// `constraint_stmt ::= "constraint" ws ( ident ws ":" ws )? equation`
    #[inline(never)]
    pub(super) fn constraint_stmt(&self, i: &'s str) -> RuleResult<'s, Stmt> {
        let i = self.ws(i);
        let start = self.pos(i);
        let Some(rest) = i.strip_prefix("constraint") else {
            return self.nothing(i);
        };
        // a name is an identifier followed by `:`; anything else starts
        // the equation (`constraint x = l*cos(th)`)
        let j = self.ws(rest);
        let len = ident_len(j);
        let (rest, name) = if len > 0 && self.ws(&j[len..]).starts_with(':') {
            let (after, name) = self.ident(j)?;
            let colon = self.ws(after);
            (&colon[1..], Some(name))
        } else {
            (rest, None)
        };
        let j = self.ws(rest);
        if matches!(j.as_bytes().first(), None | Some(b'\n' | b';')) {
            return self.fail(self.expected(
                j,
                "an equation after `constraint`",
                "write `constraint rod: x^2 + y^2 = l^2` (holonomic) or `constraint roll: x' = r*theta'` (linear in the velocities)",
                None,
            ));
        }
        let (rest, equation) = self.equation(j)?;
        let span = Span::new(start, equation.span.end);
        Ok((
            rest,
            Stmt::Constraint {
                name,
                equation,
                span,
            },
        ))
    }

    /// `reaction_stmt ::= "reaction" ws ident ws "at" ws expr`
    #[inline(never)]
    pub(super) fn reaction_stmt(&self, i: &'s str) -> RuleResult<'s, Stmt> {
        let i = self.ws(i);
        let start = self.pos(i);
        let Some(rest) = i.strip_prefix("reaction") else {
            return self.nothing(i);
        };
        let (rest, constraint) = self.ident(rest)?;
        let j = self.ws(rest);
        let after_at = j
            .strip_prefix("at")
            .filter(|k| !k.starts_with(|c: char| c.is_alphanumeric() || c == '_'));
        let Some(k) = after_at else {
            let c = &constraint.name;
            return self.fail(self.expected(
                j,
                &format!("`at` after `reaction {c}`"),
                &format!("the force of a constraint at a point is written `reaction {c} at P`"),
                None,
            ));
        };
        let (rest, (point, outer)) = self.rhs(k, "at")?;
        let span = Span::new(start, outer.end);
        Ok((
            rest,
            Stmt::Reaction {
                constraint,
                point,
                span,
            },
        ))
    }
}
