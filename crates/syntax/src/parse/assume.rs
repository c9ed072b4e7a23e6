//! The `assume` statement: parameters of either sign and order facts.

use super::ast::Fact;
use super::*;

const HINT: &str =
    "write facts like `assume e real` (e may have either sign) or `assume R > r`, separated by commas";

impl<'s> Parser<'s> {
    /// `assume_stmt ::= "assume" ws fact ( ws "," ws fact )*`
    #[inline(never)]
    pub(super) fn assume_stmt(&self, i: &'s str) -> RuleResult<'s, Stmt> {
        let i = self.ws(i);
        let start = self.pos(i);
        let Some(mut rest) = i.strip_prefix("assume") else {
            return self.nothing(i);
        };
        let mut facts = Vec::new();
        loop {
            let (after, f) = self.fact(rest)?;
            facts.push(f);
            let j = self.ws(after);
            match j.strip_prefix(',') {
                Some(k) => rest = k,
                None => {
                    rest = after;
                    break;
                }
            }
        }
        let span = Span::new(start, self.pos(rest));
        Ok((rest, Stmt::Assume(facts, span)))
    }

    /// `fact ::= ident ws "real" | expr ws ( "<" | ">" ) ws expr`
    pub(super) fn fact(&self, i: &'s str) -> RuleResult<'s, Fact> {
        let j = self.ws(i);
        let len = ident_len(j);
        if len > 0 {
            let after = self.ws(&j[len..]);
            let word = ident_len(after);
            let ends = |k: &str| {
                matches!(
                    self.ws(k).as_bytes().first(),
                    None | Some(b'\n' | b';' | b',')
                )
            };
            if &after[..word] == "real" && ends(&after[word..]) {
                let (_, name) = self.ident(j)?;
                return Ok((&after[word..], Fact::Real(name)));
            }
        }
        let (rest, left) = match self.expr(j) {
            Ok(x) => x,
            Err(nom::Err::Error(_)) => {
                return self.fail(self.expected(j, "a fact after `assume`", HINT, None))
            }
            Err(e) => return Err(e),
        };
        let k = self.ws(rest);
        let greater = match k.as_bytes().first() {
            Some(b'>') => true,
            Some(b'<') => false,
            _ => return self.fail(self.expected(k, "`<` or `>` in the fact", HINT, None)),
        };
        if k[1..].starts_with('=') {
            return self.fail(
                Diagnostic::error(Span::new(self.pos(k), self.pos(k) + 2), "only strict order facts are supported")
                    .with_hint("write `>` or `<`: a fact `a >= b` would allow a = b, where signs are undecided").with_kind(crate::diag::ErrorKind::Syntax),
            );
        }
        let (rest, right) = match self.expr(&k[1..]) {
            Ok(x) => x,
            Err(nom::Err::Error(_)) => {
                return self.fail(self.expected(
                    self.ws(&k[1..]),
                    "an expression after the comparison",
                    HINT,
                    None,
                ))
            }
            Err(e) => return Err(e),
        };
        let span = left.outer.to(right.outer);
        let (greater, less) = if greater {
            (*left.e, *right.e)
        } else {
            (*right.e, *left.e)
        };
        Ok((
            rest,
            Fact::Order {
                greater,
                less,
                span,
            },
        ))
    }
}
