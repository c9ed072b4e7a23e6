//! The `constraint` statement: a holonomic constraint or one linear in the
//! velocities, each with a Lagrange multiplier.

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
}
