//! The expression rules, by precedence: sums, products, unary signs,
//! powers, primes, calls, groups and vectors, names.

use super::*;

impl<'s> Parser<'s> {
    /// `whole_expr ::= ws_nl expr ws_nl` — the input of [`parse_expr`]; it
    /// must end after the expression.
    pub(super) fn whole_expr(&self, i: &'s str) -> RuleResult<'s, Node> {
        let _p = self.open_paren();
        let (rest, node) = self.expr(i)?;
        let rest = self.ws_nl(rest);
        if !rest.is_empty() {
            return self.fail(self.unexpected(rest));
        }
        Ok((rest, node))
    }

    /// `expr ::= sum`
    #[inline(never)]
    pub(super) fn expr(&self, i: &'s str) -> RuleResult<'s, Node> {
        let _g = self.enter_ws(i)?;
        self.sum(i)
    }

    /// `sum ::= product ( ws ( "+" | "-" ) ws_nl product )*`
    pub(super) fn sum(&self, i: &'s str) -> RuleResult<'s, Node> {
        let (mut i, mut lhs) = self.product(i)?;
        loop {
            let j = self.ws(i);
            let (op, op_str) = match j.as_bytes().first() {
                Some(b'+') => (BinOp::Add, "+"),
                Some(b'-') => (BinOp::Sub, "-"),
                _ => break,
            };
            let k = &j[1..];
            let op_span = self.span(j, k);
            let k = self.ws_nl(k);
            let (rest, rhs) = match self.product(k) {
                Ok(x) => x,
                Err(e) => return Err(self.op_error(e, k, op_str, op_span)),
            };
            lhs = self.bin(op, lhs, rhs)?;
            i = rest;
        }
        Ok((i, lhs))
    }

    /// `product ::= unary ( ws ( "*" | "/" ) ws_nl unary | implicit_factor )*`
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(super) fn product(&self, i: &'s str) -> RuleResult<'s, Node> {
        let (mut i, mut lhs) = self.unary(i)?;
        let mut last = lhs.outer;
        let mut last_is_name = matches!(lhs.e.kind, ExprKind::Name(_));
        loop {
            if self.implicit_here(i) {
                let (rest, f) = self.implicit_factor(i)?;
                last = f.outer;
                last_is_name = false;
                lhs = self.bin(BinOp::Mul, lhs, f)?;
                i = rest;
                continue;
            }
            let j = self.ws(i);
            let (op, op_str) = match j.as_bytes().first() {
                Some(b'*') => (BinOp::Mul, "*"),
                Some(b'/') => (BinOp::Div, "/"),
                _ => {
                    self.side_by_side(j, last, last_is_name)?;
                    return Ok((i, lhs));
                }
            };
            let k = &j[1..];
            let op_span = self.span(j, k);
            if op == BinOp::Mul && k.starts_with('*') {
                return Err(star_star(op_span));
            }
            let k = self.ws_nl(k);
            let (rest, rhs) = match self.unary(k) {
                Ok(x) => x,
                Err(e) => return Err(self.op_error(e, k, op_str, op_span)),
            };
            last = rhs.outer;
            last_is_name = matches!(rhs.e.kind, ExprKind::Name(_));
            lhs = self.bin(op, lhs, rhs)?;
            i = rest;
        }
    }

    /// Is an implicit product allowed at `i` (directly after a number or `)`)?
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(super) fn implicit_here(&self, i: &str) -> bool {
        let p = self.pos(i);
        // a non-ASCII character never ends in an ASCII byte
        match self.src.as_bytes()[..p].last() {
            Some(d) if d.is_ascii_digit() => i.starts_with('(') || starts_ident(i),
            Some(b')') => i.starts_with('('),
            _ => false,
        }
    }

    /// `implicit_factor ::= power` — only where [`Parser::implicit_here`] holds.
    pub(super) fn implicit_factor(&self, i: &'s str) -> RuleResult<'s, Node> {
        self.power(i)
    }

    /// Reject two operands side by side (`a b`) with a helpful hint; `j` is
    /// after the white space following the left operand. Where a stop word
    /// is active (the first expression of `load` or `torque`), the
    /// expression ends instead: the statement then expects its keyword.
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(super) fn side_by_side(
        &self,
        j: &'s str,
        left: Span,
        left_is_name: bool,
    ) -> Result<(), nom::Err<RuleError>> {
        if !starts_operand(j) || self.stopping() {
            return Ok(());
        }
        Err(self.side_by_side_error(j, left, left_is_name))
    }

    /// The error for an operand at `j` right after the operand at `left`.
    #[cold]
    #[inline(never)]
    pub(super) fn side_by_side_error(
        &self,
        j: &'s str,
        left: Span,
        left_is_name: bool,
    ) -> nom::Err<RuleError> {
        let right = match self.power(j) {
            Ok((_, r)) => r.outer,
            Err(nom::Err::Error(_)) => self.token(j).0,
            Err(e) => return e,
        };
        let l = excerpt(&self.src[left.start..left.end]);
        let r = excerpt(&self.src[right.start..right.end]);
        let after_number = l.ends_with(|c: char| c.is_ascii_digit());
        let mut hint = if left_is_name && j.starts_with('(') {
            format!("to call `{l}`, write `{l}{r}` without a space; to multiply, write `{l}*{r}`")
        } else if after_number && r == "deg" {
            format!("for an angle in degrees write `{l}deg` without a space, or `{l}°`")
        } else if after_number && (j.starts_with('(') || first(j).is_some_and(ident_start)) {
            format!("did you mean `{l}*{r}`? (an implicit product is written without a space: `{l}{r}`)")
        } else {
            format!("did you mean `{l}*{r}`?")
        };
        if self.src[left.end..right.start].contains('\n') {
            hint.push_str(" (or is a `)` missing before the line break?)");
        }
        failure(
            Diagnostic::error(right, "two expressions side by side")
                .with_hint(hint)
                .with_kind(crate::diag::ErrorKind::Syntax),
        )
    }

    /// `unary ::= ws ( "-" | "+" ) unary | power`
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(super) fn unary(&self, i: &'s str) -> RuleResult<'s, Node> {
        let j = self.ws(i);
        match j.as_bytes().first() {
            Some(b'-') => self.signed(j, "-"),
            Some(b'+') => self.signed(j, "+"),
            _ => self.power(j),
        }
    }

    /// The first alternative of `unary`: `sign` at `j`, then a `unary`.
    #[inline(never)]
    pub(super) fn signed(&self, j: &'s str, sign: &'static str) -> RuleResult<'s, Node> {
        let k = &j[1..];
        let _g = self.enter(j)?;
        let sign_span = self.span(j, k);
        let (rest, inner) = match self.unary(k) {
            Ok(x) => x,
            Err(e) => return Err(self.op_error(e, k, sign, sign_span)),
        };
        let span = sign_span.to(inner.outer);
        if sign == "-" {
            let node = self.node(ExprKind::Neg(inner.e), span, inner.d + 1, sign_span)?;
            Ok((rest, node))
        } else {
            // unary plus leaves no node; the operand keeps its own span
            let mut inner = inner;
            inner.outer = span;
            Ok((rest, inner))
        }
    }

    /// `power ::= postfix ( ws "^" ws_nl exponent )?`
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(super) fn power(&self, i: &'s str) -> RuleResult<'s, Node> {
        let (i, base) = self.postfix(i)?;
        let j = self.ws(i);
        let Some(k) = j.strip_prefix('^') else {
            return Ok((i, base));
        };
        let op_span = self.span(j, k);
        let k = self.ws_nl(k);
        let (rest, ex) = match self.exponent(k) {
            Ok(x) => x,
            Err(e) => return Err(self.op_error(e, k, "^", op_span)),
        };
        Ok((rest, self.bin(BinOp::Pow, base, ex)?))
    }

    /// `exponent ::= ws ( "-" | "+" ) exponent | power`
    pub(super) fn exponent(&self, i: &'s str) -> RuleResult<'s, Node> {
        let j = self.ws(i);
        let _g = self.enter(j)?;
        let sign = match j.as_bytes().first() {
            Some(b'-') => "-",
            Some(b'+') => "+",
            _ => return self.power(j),
        };
        let k = &j[1..];
        let sign_span = self.span(j, k);
        let (rest, inner) = match self.exponent(k) {
            Ok(x) => x,
            Err(e) => return Err(self.op_error(e, k, sign, sign_span)),
        };
        let span = sign_span.to(inner.outer);
        if sign == "-" {
            let node = self.node(ExprKind::Neg(inner.e), span, inner.d + 1, sign_span)?;
            Ok((rest, node))
        } else {
            // unary plus leaves no node; the operand keeps its own span
            let mut inner = inner;
            inner.outer = span;
            Ok((rest, inner))
        }
    }

    /// `postfix ::= atom ( ws "'" | index )*`
    ///
    /// `i` is after white space: [`Parser::power`] is only called there.
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(super) fn postfix(&self, i: &'s str) -> RuleResult<'s, Node> {
        let start = i;
        let (mut i, mut a) = self.atom(start)?;
        let mut order: u32 = 0;
        let mut first_prime = None;
        loop {
            // `2[a]` stays two operands side by side: a number has no components
            let number = matches!(a.e.kind, ExprKind::Num(_) | ExprKind::Degrees(_))
                && order == 0
                && !start.starts_with('(');
            if i.starts_with('[') && !number {
                // the primes so far apply before the index: `P'[1]`
                a = self.primed(start, a, order, first_prime.take(), i)?;
                order = 0;
                let (rest, indexed) = self.index(i, a)?;
                a = indexed;
                i = rest;
                continue;
            }
            let j = self.ws(i);
            match j.strip_prefix('\'') {
                Some(k) => {
                    first_prime.get_or_insert(self.span(j, k));
                    order = order.saturating_add(1);
                    i = k;
                }
                None => break,
            }
        }
        let node = self.primed(start, a, order, first_prime, i)?;
        Ok((i, node))
    }

    /// `a` with `order` primes (the first at `prime_span`) ending before `i`.
    #[cfg_attr(not(debug_assertions), inline(always))]
    fn primed(
        &self,
        start: &'s str,
        a: Node,
        order: u32,
        prime_span: Option<Span>,
        i: &'s str,
    ) -> Result<Node, nom::Err<RuleError>> {
        let Some(prime_span) = prime_span else {
            return Ok(a);
        };
        let is_group = start.starts_with('(');
        if !is_group && matches!(a.e.kind, ExprKind::Num(_) | ExprKind::Degrees(_)) {
            return Err(prime_on_number(prime_span));
        }
        if order == u32::MAX {
            return Err(too_many_primes(prime_span));
        }
        let span = Span::new(a.outer.start, self.pos(i));
        let d = a.d + 1;
        self.node(ExprKind::Prime(a.e, order), span, d, prime_span)
    }

    /// `index ::= "[" ws_nl expr ws_nl "]"` right after an operand (no
    /// space: `P[2]`), the component of a vector.
    #[inline(never)]
    pub(super) fn index(&self, i: &'s str, a: Node) -> RuleResult<'s, Node> {
        let open = self.pos(i);
        let _p = self.open_paren();
        let k = self.ws_nl(&i[1..]);
        let (rest, ix) =
            match self.expr(k) {
                Ok(x) => x,
                Err(nom::Err::Error(_)) => return self.fail(self.expected(
                    k,
                    "a component number after `[`",
                    "`P[k]` is the k-th component of the vector P, counted from 1: `P[1]`, `P[2]`",
                    None,
                )),
                Err(e) => return Err(e),
            };
        let j = self.ws_nl(rest);
        let Some(after) = j.strip_prefix(']') else {
            if j.starts_with(',') {
                return self.fail(
                    Diagnostic::error(self.token(j).0, "one component number between `[` and `]`")
                        .with_hint("`P[k]` takes one component; a vector literal needs a space or an operator before it").with_kind(crate::diag::ErrorKind::Syntax),
                );
            }
            if j.is_empty() {
                return Err(unclosed_bracket(open));
            }
            return self.fail(self.expected(
                j,
                "`]` after the component number",
                "`P[k]` is the k-th component of the vector P: `P[1]`",
                None,
            ));
        };
        let span = Span::new(a.outer.start, self.pos(after));
        let d = a.d.max(ix.d) + 1;
        let at = Span::new(open, open + 1);
        Ok((after, self.node(ExprKind::Index(a.e, ix.e), span, d, at)?))
    }

    /// `atom ::= literal | call | name | group | vector`
    ///
    /// `i` is after white space (see [`Parser::postfix`]).
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(super) fn atom(&self, i: &'s str) -> RuleResult<'s, Node> {
        match i.as_bytes().first() {
            Some(c) if c.is_ascii_digit() => self.literal(i),
            Some(b'.') if starts_operand(i) => self.literal(i),
            Some(b'(') => self.group(i),
            _ => match ident_len(i) {
                // `[` is tested last (a vector is rare; the hot path of
                // names stays as short as it was)
                0 => self.vector(i),
                len if i[len..].starts_with('(') => self.call(i),
                len => self.name(i, len),
            },
        }
    }

    /// `call ::= ident "(" ws_nl ( arg ( ws_nl "," ws_nl arg )* ws_nl )? ")"`
    pub(super) fn call(&self, i: &'s str) -> RuleResult<'s, Node> {
        let (rest, name) = self.ident(i)?;
        let Some(mut k) = rest.strip_prefix('(') else {
            return self.nothing(rest);
        };
        let open = self.pos(rest);
        let _p = self.open_paren();
        let mut args = Vec::new();
        let mut d = 0;
        let j = self.ws(k);
        if let Some(after) = j.strip_prefix(')') {
            k = after;
        } else {
            loop {
                let (rest, arg) = match self.arg(k) {
                    Ok(x) => x,
                    Err(e) => return Err(self.arg_error(e, k, &name, args.is_empty())),
                };
                d = d.max(arg.d);
                args.push(*arg.e);
                let j = self.ws(rest);
                match j.as_bytes().first() {
                    Some(b',') => k = &j[1..],
                    Some(b')') => {
                        k = &j[1..];
                        break;
                    }
                    _ => return Err(self.args_unclosed(j, open, &name)),
                }
            }
        }
        let span = Span::new(name.span.start, self.pos(k));
        let at = name.span;
        let callee = Callee::resolve(name);
        Ok((k, self.node(ExprKind::Call(callee, args), span, d + 1, at)?))
    }

    /// `arg ::= expr ( ws_nl "=" ws_nl expr )?`
    pub(super) fn arg(&self, i: &'s str) -> RuleResult<'s, Node> {
        let (rest, arg) = self.expr(i)?;
        let j = self.ws(rest);
        let Some(after) = j.strip_prefix('=') else {
            return Ok((rest, arg));
        };
        let (rest, value) = match self.expr(after) {
            Ok(x) => x,
            Err(nom::Err::Error(_)) => {
                return Err(failure(self.expected(
                    self.ws(after),
                    "a value after `=`",
                    "a named argument is written `x = value`, as in subs(E, x = 0)",
                    None,
                )))
            }
            Err(e) => return Err(e),
        };
        let span = arg.outer.to(value.outer);
        let d = arg.d.max(value.d) + 1;
        let at = value.outer;
        Ok((
            rest,
            self.node(ExprKind::Assign(arg.e, value.e), span, d, at)?,
        ))
    }

    /// The error for a missing argument at `k` of the call of `name`.
    #[cold]
    #[inline(never)]
    pub(super) fn arg_error(
        &self,
        e: nom::Err<RuleError>,
        k: &'s str,
        name: &Ident,
        first_arg: bool,
    ) -> nom::Err<RuleError> {
        if !matches!(e, nom::Err::Error(_)) {
            return e;
        }
        let at = self.ws(k);
        let (what, hint) = if first_arg {
            (format!("an argument of `{}`", name.name), HINT_EXPR)
        } else if at.starts_with(')') {
            (
                "an argument after `,`".to_string(),
                "remove the trailing `,`",
            )
        } else {
            ("an argument after `,`".to_string(), HINT_EXPR)
        };
        failure(self.expected(at, &what, hint, None))
    }

    /// The error when neither `,` nor `)` follows an argument of `name`.
    #[cold]
    #[inline(never)]
    pub(super) fn args_unclosed(
        &self,
        j: &'s str,
        open: usize,
        name: &Ident,
    ) -> nom::Err<RuleError> {
        let what = format!("`,` or `)` after an argument of `{}`", name.name);
        failure(self.close_expected(j, open, &what))
    }

    /// The error when `)` (or `,`) is expected at `j` for the `(` at `open`.
    pub(super) fn close_expected(&self, j: &'s str, open: usize, what: &str) -> Diagnostic {
        if j.is_empty() {
            return Diagnostic::error(Span::new(open, open + 1), "unclosed `(`")
                .with_hint("add the matching `)`")
                .with_kind(crate::diag::ErrorKind::Syntax);
        }
        let (line, col) = Diagnostic::line_col(self.src, open);
        self.expected(
            j,
            what,
            &format!("the `(` at line {line}, column {col} is still open"),
            None,
        )
    }

    /// `name ::= ident`
    ///
    /// `i` is after white space and starts with an `ident` of `len` bytes
    /// (scanned by [`Parser::atom`]).
    #[cfg_attr(not(debug_assertions), inline(always))]
    pub(super) fn name(&self, i: &'s str, len: usize) -> RuleResult<'s, Node> {
        let start = self.pos(i);
        let span = Span::new(start, start + len);
        if !i.as_bytes()[..len].is_ascii() {
            self.check_letters(&i[..len], start)?;
        }
        Ok((
            &i[len..],
            Self::leaf(ExprKind::Name(i[..len].to_string()), span),
        ))
    }

    /// `group ::= "(" ws_nl expr ws_nl ")"`
    pub(super) fn group(&self, i: &'s str) -> RuleResult<'s, Node> {
        let Some(k) = i.strip_prefix('(') else {
            return self.nothing(i);
        };
        let open = self.pos(i);
        let _p = self.open_paren();
        let (rest, mut inner) = match self.expr(k) {
            Ok(x) => x,
            Err(e) => return Err(self.group_error(e, k, open)),
        };
        let j = self.ws(rest);
        match j.strip_prefix(')') {
            Some(after) => {
                inner.outer = Span::new(open, self.pos(after));
                Ok((after, inner))
            }
            None => Err(failure(self.close_expected(j, open, "`)`"))),
        }
    }

    /// The error when no expression follows the `(` at `open`.
    #[cold]
    #[inline(never)]
    pub(super) fn group_error(
        &self,
        e: nom::Err<RuleError>,
        k: &'s str,
        open: usize,
    ) -> nom::Err<RuleError> {
        if !matches!(e, nom::Err::Error(_)) {
            return e;
        }
        let at = self.ws(k);
        if at.starts_with(')') {
            return failure(
                Diagnostic::error(Span::new(open, self.pos(at) + 1), "empty parentheses `()`")
                    .with_hint("put an expression inside the parentheses, or remove them")
                    .with_kind(crate::diag::ErrorKind::Syntax),
            );
        }
        if at.is_empty() {
            return failure(self.close_expected(at, open, ""));
        }
        failure(self.expected(at, "an expression after `(`", HINT_EXPR, None))
    }

    /// `vector ::= "[" ws_nl expr ( ws_nl "," ws_nl expr )* ws_nl "]"`
    ///
    /// "Nothing here" unless `i` starts with `[`.
    #[inline(never)]
    pub(super) fn vector(&self, i: &'s str) -> RuleResult<'s, Node> {
        let Some(mut k) = i.strip_prefix('[') else {
            return self.nothing(i);
        };
        let open = self.pos(i);
        let _p = self.open_paren();
        let mut components = Vec::new();
        let mut d = 0;
        loop {
            let (rest, c) = match self.expr(k) {
                Ok(x) => x,
                Err(e) => return Err(self.component_error(e, k, open, components.is_empty())),
            };
            d = d.max(c.d);
            components.push(*c.e);
            let j = self.ws(rest);
            match j.as_bytes().first() {
                Some(b',') => k = &j[1..],
                Some(b']') => {
                    k = &j[1..];
                    break;
                }
                _ => return Err(self.vector_unclosed(j, open)),
            }
        }
        let span = Span::new(open, self.pos(k));
        let at = Span::new(open, open + 1);
        Ok((k, self.node(ExprKind::Vector(components), span, d + 1, at)?))
    }

    /// The error for a missing component at `k` of the vector opened at
    /// `open` (`first`: no component yet).
    #[cold]
    #[inline(never)]
    pub(super) fn component_error(
        &self,
        e: nom::Err<RuleError>,
        k: &'s str,
        open: usize,
        first: bool,
    ) -> nom::Err<RuleError> {
        if !matches!(e, nom::Err::Error(_)) {
            return e;
        }
        let at = self.ws(k);
        if at.is_empty() {
            return unclosed_bracket(open);
        }
        let closes = at.starts_with(']');
        let d = if first && closes {
            Diagnostic::error(
                Span::new(open, self.pos(at) + 1),
                "a vector needs at least one component",
            )
            .with_hint("write its components separated by commas, like `[x, y]`")
            .with_kind(crate::diag::ErrorKind::Syntax)
        } else if first {
            self.expected(at, "an expression after `[`", HINT_EXPR, None)
        } else if closes {
            self.expected(at, "a component after `,`", "remove the trailing `,`", None)
        } else {
            self.expected(at, "a component after `,`", HINT_EXPR, None)
        };
        failure(d)
    }

    /// The error when neither `,` nor `]` follows (at `j`) a component of
    /// the vector opened at `open`.
    #[cold]
    #[inline(never)]
    pub(super) fn vector_unclosed(&self, j: &'s str, open: usize) -> nom::Err<RuleError> {
        if j.is_empty() {
            return unclosed_bracket(open);
        }
        let (line, col) = Diagnostic::line_col(self.src, open);
        failure(self.expected(
            j,
            "`,` or `]` after a component of the vector",
            &format!("the `[` at line {line}, column {col} is still open"),
            None,
        ))
    }

    // ----- tokens ------------------------------------------------------------

    /// `ident ::= ident_start ident_char*`
    pub(super) fn ident(&self, i: &'s str) -> RuleResult<'s, Ident> {
        let i = self.ws(i);
        let len = ident_len(i);
        if len == 0 {
            return self.nothing(i);
        }
        if !i.as_bytes()[..len].is_ascii() {
            self.check_letters(&i[..len], self.pos(i))?;
        }
        Ok((
            &i[len..],
            Ident {
                name: i[..len].to_string(),
                span: Span::new(self.pos(i), self.pos(i) + len),
            },
        ))
    }
}

impl Parser<'_> {
    /// Refuse a look-alike letter in the name `name` at byte `start` (see
    /// [`chars::refused_letter`]).
    #[cold]
    #[inline(never)]
    pub(super) fn check_letters(
        &self,
        name: &str,
        start: usize,
    ) -> Result<(), nom::Err<RuleError>> {
        match chars::refused_letter(name) {
            None => Ok(()),
            Some((p, c, message, hint)) => {
                let at = Span::new(start + p, start + p + c.len_utf8());
                Err(failure(
                    Diagnostic::error(at, message)
                        .with_hint(hint)
                        .with_kind(crate::diag::ErrorKind::Syntax),
                ))
            }
        }
    }
}
