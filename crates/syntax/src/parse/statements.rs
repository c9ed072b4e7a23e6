//! The statement rules: a scene is lines of declarations, roles, loads,
//! torques, `latex` names, `solve` blocks and definitions.

use super::*;

/// The words of a `load` or `torque` statement, for parsing and messages.
pub(super) struct Applied {
    keyword: &'static str,
    separator: &'static str,
    /// "a force": what comes after the keyword.
    first: &'static str,
    /// "force": the first expression in "`at` after the force".
    first_noun: &'static str,
    /// "a point": what comes after the separator.
    second: &'static str,
    /// "a load": the statement.
    what: &'static str,
    form: &'static str,
    parts: &'static str,
    example: &'static str,
}

pub(super) const LOAD: Applied = Applied {
    keyword: "load",
    separator: "at",
    first: "a force",
    first_noun: "force",
    second: "a point",
    what: "a load",
    form: "load F at P",
    parts: "the force F, then `at` and the point P it acts on",
    example: "load [0, -m*g] at [x, y]",
};

pub(super) const TORQUE: Applied = Applied {
    keyword: "torque",
    separator: "on",
    first: "a moment",
    first_noun: "moment",
    second: "an angle",
    what: "a torque",
    form: "torque M on phi",
    parts: "the moment M, then `on` and the angle phi it turns",
    example: "torque -c*phi' on phi",
};

impl<'s> Parser<'s> {
    /// `scene ::= line ( newline line )*`
    pub(super) fn scene(&self, mut i: &'s str) -> RuleResult<'s, Vec<Stmt>> {
        // room for one statement per line (up to a bound), so that the
        // vector is not reallocated as it grows
        let lines = count_newlines(i.as_bytes()) + 1;
        let mut out = Vec::with_capacity(lines.min(256));
        loop {
            let (rest, ()) = self.line(i, &mut out)?;
            if rest.is_empty() {
                return Ok((rest, out));
            }
            match Self::newline(rest) {
                Ok((rest, _)) => i = rest,
                Err(_) => return self.fail(self.unexpected(rest)),
            }
        }
    }

    /// `line ::= ws statement? ( ws ";" ws statement? )* ws`
    ///
    /// The statements are appended to `out`.
    pub(super) fn line(&self, mut i: &'s str, out: &mut Vec<Stmt>) -> RuleResult<'s, ()> {
        loop {
            i = self.ws(i);
            let start = self.pos(i);
            if !matches!(i.as_bytes().first(), None | Some(b'\n' | b';')) {
                let (rest, stmt) = match self.statement(i) {
                    Err(nom::Err::Failure(RuleError::Diag(d))) => {
                        return Err(failure(self.note_continuation(start, *d)))
                    }
                    other => other?,
                };
                out.push(stmt);
                i = self.ws(rest);
            }
            match i.as_bytes().first() {
                Some(b';') => i = &i[1..],
                None | Some(b'\n') => return Ok((i, ())),
                Some(_) => {
                    let d = self.unexpected(i);
                    return Err(failure(self.note_continuation(start, d)));
                }
            }
        }
    }

    /// If the statement starting at `start` ran over a line break outside
    /// parentheses and brackets before the error because a line ended in an
    /// operator, that trailing operator is the likely mistake, so the hint
    /// says so. (Inside a solve block a line break also ends an equation; a
    /// line that ends in anything else forgets an earlier operator.)
    pub(super) fn note_continuation(&self, start: usize, d: Diagnostic) -> Diagnostic {
        let Some(span) = d.span else { return d };
        let end = span.start.min(self.src.len());
        let mut depth = 0i64;
        let mut in_comment = false;
        let mut last = None; // last significant char on the current line
        let mut continued = None; // (line offset, operator)
        for (p, c) in self.src[start.min(end)..end].char_indices() {
            match c {
                '\n' => {
                    in_comment = false;
                    if depth <= 0 {
                        match last {
                            Some(op @ ('+' | '-' | '*' | '/' | '^')) => {
                                continued = Some((start + p, op))
                            }
                            Some(_) => continued = None,
                            None => {}
                        }
                    }
                    last = None;
                }
                _ if in_comment => {}
                '#' => in_comment = true,
                c if is_space(c) => {}
                c => {
                    match c {
                        '(' | '[' => depth += 1,
                        ')' | ']' => depth -= 1,
                        _ => {}
                    }
                    last = Some(c);
                }
            }
        }
        match continued {
            Some((p, op)) => {
                let (line, _) = Diagnostic::line_col(self.src, p);
                let hint = format!(
                    "line {line} ends with `{op}`, so the expression continues on the next line; complete it or remove the trailing `{op}`"
                );
                d.with_hint(hint)
            }
            None => d,
        }
    }

    /// `statement ::= declaration | role_stmt | force_stmt | load_stmt | torque_stmt | solve_block | latex_stmt | frame_stmt | body_stmt | gravity_stmt | assume_stmt | constraint_stmt | reaction_stmt | joint_stmt | drive_stmt | friction_stmt | definition`
    ///
    /// Keywords do not reserve names: the tokens after the first identifier
    /// decide (see the grammar).
    pub(super) fn statement(&self, i: &'s str) -> RuleResult<'s, Stmt> {
        // the first identifier, looked at without building an `Ident`
        let j = self.ws(i);
        let len = ident_len(j);
        if len == 0 {
            return self.fail(self.statement_start(i));
        }
        let (word, after) = j.split_at(len);
        let next = self.ws(after);
        let next_is_ident = starts_ident(next);
        let next_is_eq = next.starts_with('=');
        let at_end = matches!(next.as_bytes().first(), None | Some(b'\n' | b';'));
        match word {
            "coordinates" | "parameters" | "functions" if !next_is_eq => {
                if next_is_ident {
                    self.declaration(i)
                } else if at_end {
                    self.fail(
                        Diagnostic::error(self.span(j, after), format!("empty `{word}` list"))
                            .with_hint(format!("list at least one name: `{word} x, y`"))
                            .with_kind(crate::diag::ErrorKind::Syntax),
                    )
                } else {
                    self.fail(self.expected(
                        next,
                        &format!("a name after `{word}`"),
                        &format!("declare names like `{word} x, y`; to define a name `{word}`, write `{word} = expression`"),
                        None,
                    ))
                }
            }
            "force" if !next_is_eq => {
                if next_is_ident {
                    self.force_stmt(i)
                } else {
                    self.fail(self.expected(
                        next,
                        "a coordinate name after `force`",
                        "a generalized force is written `force COORD: expression`",
                        None,
                    ))
                }
            }
            "load" if !next_is_eq => self.load_stmt(i),
            "frame" if next_is_ident => self.frame_stmt(i),
            "body" | "particle" if next_is_ident => self.body_stmt(i),
            "gravity" if !next_is_eq => self.gravity_stmt(i),
            "assume" if !next_is_eq => self.assume_stmt(i),
            "constraint" if !next_is_eq => self.constraint_stmt(i),
            "reaction" if next_is_ident => self.reaction_stmt(i),
            "joint" if next_is_ident => self.joint_stmt(i),
            "drive" if next_is_ident => self.drive_stmt(i),
            "friction" if next_is_ident => self.friction_stmt(i),
            "torque" if !next_is_eq => self.torque_stmt(i),
            "solve" if !next_is_eq => self.solve_block(i),
            "latex" if !next_is_eq => {
                if next_is_ident {
                    self.latex_stmt(i)
                } else {
                    self.fail(self.expected(
                        next,
                        "a name after `latex`",
                        "give a name its LaTeX like `latex theta3 = \"\\vartheta_{3}\"`; to define a name `latex`, write `latex = expression`",
                        None,
                    ))
                }
            }
            _ if !next_is_eq && Role::from_keyword(word).is_some() => {
                if next_is_ident {
                    self.role_stmt(i)
                } else {
                    self.fail(self.expected(
                        next,
                        &format!("a name after `{word}`"),
                        &format!("write `{word} NAME = expression`; to define a name `{word}`, write `{word} = expression`"),
                        None,
                    ))
                }
            }
            _ if !next_is_eq && !next.starts_with('(') => match keywords::suggest(word) {
                // a definition needs `=` next: this line is no definition
                Some(k) => {
                    if !word.is_ascii() {
                        // `pоtential` with a Cyrillic о: that letter first
                        self.check_letters(word, self.pos(j))?;
                    }
                    self.fail(
                        Diagnostic::error(self.span(j, after), format!("unknown keyword `{word}`"))
                            .with_hint(format!("did you mean `{k}`?"))
                            .with_kind(crate::diag::ErrorKind::Syntax),
                    )
                }
                None => self.definition(i),
            },
            _ => self.definition(i),
        }
    }

    /// The error for a line that does not start with an identifier.
    pub(super) fn statement_start(&self, i: &'s str) -> Diagnostic {
        let (span, shown) = self.token(i);
        match first(i) {
            Some(c) if c.is_ascii_digit() || c == '(' || c == '[' || c == '.' => Diagnostic::error(
                span,
                format!("a statement must start with a name or a keyword, found {shown}"),
            )
            .with_hint("a definition is written `NAME = expression`").with_kind(crate::diag::ErrorKind::Syntax),
            Some('+' | '-' | '*' | '/' | '^') => Diagnostic::error(
                span,
                format!("a statement can't start with {shown}"),
            )
            .with_hint("to continue an expression on the next line, end the previous line with the operator").with_kind(crate::diag::ErrorKind::Syntax),
            _ => self.unexpected(i),
        }
    }

    /// `declaration ::= ( "coordinates" | "parameters" | "functions" ) ws decl ( ws "," ws decl )*`
    pub(super) fn declaration(&self, i: &'s str) -> RuleResult<'s, Stmt> {
        let i = self.ws(i);
        let start = self.pos(i);
        let (mut i, kw) = if let Some(rest) = i.strip_prefix("coordinates") {
            (rest, "coordinates")
        } else if let Some(rest) = i.strip_prefix("parameters") {
            (rest, "parameters")
        } else if let Some(rest) = i.strip_prefix("functions") {
            (rest, "functions")
        } else {
            return self.nothing(i);
        };
        let mut decls = Vec::new();
        let (rest, d) = self.decl(i)?;
        decls.push(d);
        i = rest;
        loop {
            let j = self.ws(i);
            match j.strip_prefix(',') {
                Some(k) => match self.decl(k) {
                    Ok((rest, d)) => {
                        decls.push(d);
                        i = rest;
                    }
                    Err(nom::Err::Error(_)) => {
                        return self.fail(self.expected(
                            self.ws(k),
                            "a name after `,`",
                            "list names separated by commas: `x, y`",
                            None,
                        ))
                    }
                    Err(e) => return Err(e),
                },
                None => {
                    if starts_operand(j) {
                        let (span, shown) = self.token(j);
                        return self.fail(
                            Diagnostic::error(span, format!("expected `,` before {shown}"))
                                .with_hint("separate the names with commas: `x, y`")
                                .with_kind(crate::diag::ErrorKind::Syntax),
                        );
                    }
                    if j.starts_with('=') {
                        let name = &decls[decls.len() - 1].name.name;
                        return self.fail(
                            Diagnostic::error(self.token(j).0, "a declaration can't have a value")
                                .with_hint(format!(
                                    "to give `{name}` a value, write a definition `{name} = …` instead of declaring it"
                                )).with_kind(crate::diag::ErrorKind::Syntax),
                        );
                    }
                    break;
                }
            }
        }
        let last = &decls[decls.len() - 1];
        let end = last
            .dimension
            .as_ref()
            .map_or(last.name.span, |d| d.span)
            .end;
        let span = Span::new(start, end);
        let stmt = match kw {
            "coordinates" => Stmt::Coordinates(decls, span),
            "functions" => Stmt::Functions(decls, span),
            _ => Stmt::Parameters(decls, span),
        };
        Ok((i, stmt))
    }

    /// `decl ::= ident ( ws ":" dimension )?`
    pub(super) fn decl(&self, i: &'s str) -> RuleResult<'s, Decl> {
        let (i, name) = self.ident(i)?;
        let j = self.ws(i);
        match j.strip_prefix(':') {
            Some(k) => match self.dimension(k) {
                Ok((rest, dim)) => Ok((
                    rest,
                    Decl {
                        name,
                        dimension: Some(dim),
                    },
                )),
                Err(nom::Err::Error(_)) => self.fail(self.expected(
                    self.ws(k),
                    &format!("a dimension after `{}:`", name.name),
                    "annotate a dimension like `r: length` or `k: force/length`",
                    None,
                )),
                Err(e) => Err(e),
            },
            None => Ok((
                i,
                Decl {
                    name,
                    dimension: None,
                },
            )),
        }
    }

    /// `dimension ::= ws product`
    pub(super) fn dimension(&self, i: &'s str) -> RuleResult<'s, Expr> {
        let (rest, node) = self.product(self.ws(i))?;
        Ok((rest, *node.e))
    }

    /// `role_stmt ::= role ws ident ws "=" ws expr`
    pub(super) fn role_stmt(&self, i: &'s str) -> RuleResult<'s, Stmt> {
        let (rest, role) = self.role(i)?;
        let start = self.pos(self.ws(i));
        let (rest, name) = self.ident(rest)?;
        let rest = match self.equals(rest) {
            Ok(k) => k,
            Err(j) => {
                let head = format!("{} {}", role.keyword(), name.name);
                let hint = format!("write `{head} = expression`");
                return Err(self.equals_error(j, &head, &hint));
            }
        };
        let (rest, (value, outer)) = self.rhs(rest, "=")?;
        let span = Span::new(start, outer.end);
        Ok((
            rest,
            Stmt::Role {
                role,
                name,
                value,
                span,
            },
        ))
    }

    /// `role ::= "kinetic" | "potential" | "forcefunction" | "work" | "dissipation" | "rayleigh" | "lagrangian"`
    pub(super) fn role(&self, i: &'s str) -> RuleResult<'s, Role> {
        let j = self.ws(i);
        let len = ident_len(j);
        if len == 0 {
            return self.nothing(j);
        }
        match Role::from_keyword(&j[..len]) {
            Some(r) => Ok((&j[len..], r)),
            None => self.nothing(i),
        }
    }

    /// `force_stmt ::= "force" ws ident ws ":" ws expr`
    pub(super) fn force_stmt(&self, i: &'s str) -> RuleResult<'s, Stmt> {
        let i = self.ws(i);
        let start = self.pos(i);
        let Some(rest) = i.strip_prefix("force") else {
            return self.nothing(i);
        };
        let (rest, coordinate) = self.ident(rest)?;
        let j = self.ws(rest);
        let rest = match j.strip_prefix(':') {
            Some(k) => k,
            None => {
                let c = &coordinate.name;
                return self.fail(self.expected(
                    j,
                    &format!("`:` after `force {c}`"),
                    &format!("a generalized force is written `force {c}: expression`"),
                    None,
                ));
            }
        };
        let (rest, (value, outer)) = self.rhs(rest, ":")?;
        let span = Span::new(start, outer.end);
        Ok((
            rest,
            Stmt::Force {
                coordinate,
                value,
                span,
            },
        ))
    }

    /// `latex_stmt ::= "latex" ws ident ws "=" ws string`
    #[inline(never)]
    pub(super) fn latex_stmt(&self, i: &'s str) -> RuleResult<'s, Stmt> {
        let i = self.ws(i);
        let start = self.pos(i);
        let Some(rest) = i.strip_prefix("latex") else {
            return self.nothing(i);
        };
        let (rest, name) = self.ident(rest)?;
        let hint = format!(
            "write the notation in double quotes: `latex {} = \"\\vartheta_{{3}}\"`",
            name.name
        );
        let rest = match self.equals(rest) {
            Ok(k) => k,
            Err(j) => {
                return Err(self.equals_error(j, &format!("latex {}", name.name), &hint));
            }
        };
        let j = self.ws(rest);
        let (rest, tex) = match self.string(j) {
            Ok(x) => x,
            Err(nom::Err::Error(_)) => {
                return self.fail(self.expected(j, "a string in double quotes", &hint, None));
            }
            Err(e) => return Err(e),
        };
        let span = Span::new(start, self.pos(rest));
        Ok((rest, Stmt::Latex { name, tex, span }))
    }

    /// `string ::= '"' [^"#x0A]* '"'` (not empty; no escapes: a backslash
    /// is itself)
    pub(super) fn string(&self, i: &'s str) -> RuleResult<'s, String> {
        let Some(body) = i.strip_prefix('"') else {
            return self.nothing(i);
        };
        let end = body.find(['"', '\n']).unwrap_or(body.len());
        if !body[end..].starts_with('"') {
            let open = Span::new(self.pos(i), self.pos(i) + 1);
            return self.fail(
                Diagnostic::error(open, "this string is not closed on its line")
                    .with_hint("end the string with `\"` before the end of the line")
                    .with_kind(crate::diag::ErrorKind::Syntax),
            );
        }
        if end == 0 {
            return self.fail(
                Diagnostic::error(self.span(i, &body[1..]), "empty LaTeX notation")
                    .with_hint("write the notation between the quotes, e.g. `\"\\vartheta_{3}\"`")
                    .with_kind(crate::diag::ErrorKind::Syntax),
            );
        }
        Ok((&body[end + 1..], body[..end].to_string()))
    }

    /// `load_stmt ::= "load" ws expr ws "at" ws expr`
    ///
    /// The force ends at the stop word `at` (see the grammar). (Not inlined,
    /// like the other new statements and [`Parser::vector`]: they are rare, and
    /// inlined they would make the hot paths larger.)
    #[inline(never)]
    pub(super) fn load_stmt(&self, i: &'s str) -> RuleResult<'s, Stmt> {
        let (rest, (force, point, span)) = self.applied(i, &LOAD)?;
        Ok((rest, Stmt::Load { force, point, span }))
    }

    /// `torque_stmt ::= "torque" ws expr ws "on" ws expr`
    ///
    /// The moment ends at the stop word `on` (see the grammar).
    #[inline(never)]
    pub(super) fn torque_stmt(&self, i: &'s str) -> RuleResult<'s, Stmt> {
        let (rest, (moment, angle, span)) = self.applied(i, &TORQUE)?;
        Ok((
            rest,
            Stmt::Torque {
                moment,
                angle,
                span,
            },
        ))
    }

    /// `KEYWORD ws expr ws SEPARATOR ws expr` (a `load_stmt` or a
    /// `torque_stmt`): both expressions and the statement's span.
    pub(super) fn applied(&self, i: &'s str, w: &Applied) -> RuleResult<'s, (Expr, Expr, Span)> {
        let i = self.ws(i);
        let start = self.pos(i);
        let Some(rest) = i.strip_prefix(w.keyword) else {
            return self.nothing(i);
        };
        let kw_span = self.span(i, rest);
        // the first expression, ended by the stop word
        self.stop.set(true);
        let first = self.expr(rest);
        self.stop.set(false);
        let (rest, first) = match first {
            Ok((rest, node)) => (rest, node),
            Err(e) => return Err(self.applied_error(e, rest, w, kw_span, true)),
        };
        let j = self.ws(rest);
        let len = w.separator.len();
        let sep = j
            .strip_prefix(w.separator)
            .filter(|k| !starts_with_class(k, ident_char) && !k.starts_with('('));
        let Some(k) = sep else {
            return Err(self.separator_error(j, w, &first));
        };
        let sep_span = Span::new(self.pos(j), self.pos(j) + len);
        let (rest, second) = match self.expr(k) {
            Ok(x) => x,
            Err(e) => return Err(self.applied_error(e, k, w, sep_span, false)),
        };
        let span = Span::new(start, second.outer.end);
        Ok((rest, (*first.e, *second.e, span)))
    }

    /// The error for a missing first (`first`) or second expression at `k`
    /// of a `load` or `torque` statement, after the token at `after`.
    #[cold]
    #[inline(never)]
    pub(super) fn applied_error(
        &self,
        e: nom::Err<RuleError>,
        k: &'s str,
        w: &Applied,
        after: Span,
        first: bool,
    ) -> nom::Err<RuleError> {
        if !matches!(e, nom::Err::Error(_)) {
            return e;
        }
        let j = self.ws(k);
        let (what, after_word) = if first {
            (w.first, w.keyword)
        } else {
            (w.second, w.separator)
        };
        let mut hint = format!("{} is written `{}`, like `{}`", w.what, w.form, w.example);
        if first {
            hint.push_str(&format!(
                "; to define a name `{0}`, write `{0} = expression`",
                w.keyword
            ));
        }
        failure(self.expected(
            j,
            &format!("{what} after `{after_word}`"),
            &hint,
            Some(after),
        ))
    }

    /// The error when the separator (`at`, `on`) is missing at `j`, after
    /// the first expression `first`.
    #[cold]
    #[inline(never)]
    pub(super) fn separator_error(
        &self,
        j: &'s str,
        w: &Applied,
        first: &Node,
    ) -> nom::Err<RuleError> {
        let sep = w.separator;
        // `load at P`: the "force" is the bare word `at` (as written, not
        // parenthesized), so the force is missing
        if matches!(&first.e.kind, ExprKind::Name(n) if n == sep) && first.outer == first.e.span {
            let at = &self.src[first.outer.start..];
            let hint = format!(
                "{} is written `{}`, like `{}`; the {} is missing before `{sep}` (for a name `{sep}`, write `({sep})`)",
                w.what, w.form, w.example, w.first_noun
            );
            return failure(self.expected(
                at,
                &format!("{} after `{}`", w.first, w.keyword),
                &hint,
                None,
            ));
        }
        let mut hint = format!("{} is written `{}`: {}", w.what, w.form, w.parts);
        let text = &self.src[first.outer.start..first.outer.end];
        let number = text
            .strip_suffix(sep)
            .map(|head| head.trim_end_matches(|c: char| c.is_ascii_digit() || c == '.'))
            .filter(|n| n.len() + sep.len() < text.len() && !n.ends_with(ident_char));
        if let Some(n) = number {
            // `load 2at P`: the number and `at` form an implicit product
            let glued = &text[n.len()..];
            hint.push_str(&format!(
                "; `{glued}` is an implicit product, write a space before `{sep}`"
            ));
        } else if j.starts_with(sep) && j[sep.len()..].starts_with('(') {
            hint = format!(
                "directly before `(`, `{0}` is a call: write a space, `{0} (…)`",
                w.separator
            );
        } else if j.starts_with('=') {
            hint.push_str(&format!(
                "; to define a name `{0}`, write `{0} = expression`",
                w.keyword
            ));
        }
        failure(self.expected(
            j,
            &format!(
                "`{}` after the {} in `{}`",
                w.separator, w.first_noun, w.form
            ),
            &hint,
            None,
        ))
    }

    /// `solve_block ::= "solve" ws ident ( ws "," ws ident )* ws "{" block_ws equation ( ws ( ";" | newline ) block_ws equation )* block_ws "}"`
    #[inline(never)]
    pub(super) fn solve_block(&self, i: &'s str) -> RuleResult<'s, Stmt> {
        let i = self.ws(i);
        let start = self.pos(i);
        let Some(rest) = i.strip_prefix("solve") else {
            return self.nothing(i);
        };
        // the unknowns
        let mut unknowns = Vec::new();
        let (mut rest, first) = match self.ident(rest) {
            Ok(x) => x,
            Err(nom::Err::Error(_)) => {
                return self.fail(self.expected(
                    self.ws(rest),
                    "the unknowns after `solve`",
                    "name the unknowns before the equations: `solve x, y { … }`; to define a name `solve`, write `solve = expression`",
                    None,
                ))
            }
            Err(e) => return Err(e),
        };
        unknowns.push(first);
        loop {
            let j = self.ws(rest);
            let Some(k) = j.strip_prefix(',') else {
                rest = j;
                break;
            };
            match self.ident(k) {
                Ok((after, name)) => {
                    unknowns.push(name);
                    rest = after;
                }
                Err(nom::Err::Error(_)) => {
                    return self.fail(self.expected(
                        self.ws(k),
                        "a name after `,`",
                        "list the unknowns separated by commas: `solve x, y { … }`",
                        None,
                    ))
                }
                Err(e) => return Err(e),
            }
        }
        // `{`, on this line
        let Some(body) = rest.strip_prefix('{') else {
            return Err(self.open_brace_error(rest));
        };
        let open = self.pos(rest);
        let mut equations = Vec::new();
        let mut k = self.block_ws(body);
        loop {
            match k.as_bytes().first() {
                Some(b'}') if equations.is_empty() => return Err(self.empty_block(open, k)),
                Some(b'}') => break,
                None => return Err(unclosed_block(open)),
                _ => {}
            }
            let (rest, eq) = self.equation(k)?;
            equations.push(eq);
            let j = self.ws(rest);
            k = match j.as_bytes().first() {
                Some(b';' | b'\n') => self.block_ws(&j[1..]),
                Some(b'}') => j,
                None => return Err(unclosed_block(open)),
                Some(b'=') => return Err(self.second_equals(j)),
                Some(_) => return Err(self.after_equation(j)),
            };
        }
        let after = &k[1..];
        let span = Span::new(start, self.pos(after));
        let j = self.ws(after);
        if !matches!(j.as_bytes().first(), None | Some(b'\n' | b';')) {
            return Err(self.after_block(j));
        }
        Ok((
            after,
            Stmt::Solve(SolveBlock {
                unknowns,
                equations,
                span,
            }),
        ))
    }

    /// The error when the `{` of a solve block is missing at `j`.
    #[cold]
    #[inline(never)]
    pub(super) fn open_brace_error(&self, j: &'s str) -> nom::Err<RuleError> {
        if starts_operand(j) {
            let (span, shown) = self.token(j);
            return failure(
                Diagnostic::error(span, format!("expected `,` before {shown}"))
                    .with_hint("separate the unknowns with commas: `solve x, y { … }`")
                    .with_kind(crate::diag::ErrorKind::Syntax),
            );
        }
        failure(self.expected(
            j,
            "`{` after the unknowns of `solve`",
            "the equations follow in braces that open on the `solve` line: `solve x, y { … }`",
            None,
        ))
    }

    /// The error for a solve block without equations (`{` at `open`, `}` at
    /// `close`).
    #[cold]
    #[inline(never)]
    pub(super) fn empty_block(&self, open: usize, close: &'s str) -> nom::Err<RuleError> {
        let end = self.pos(close) + 1;
        // the whole `{ … }` if it is on one line, else the `{`
        let end = if self.src[open..end].contains('\n') {
            open + 1
        } else {
            end
        };
        failure(
            Diagnostic::error(Span::new(open, end), "empty solve block").with_hint(
                "write the equations inside the braces, one per line or separated by `;`: `solve x { a*x = b }`",
            ).with_kind(crate::diag::ErrorKind::Syntax),
        )
    }

    /// The error for the token at `j` after an equation (not `;`, a line
    /// break, `}` or `=`).
    #[cold]
    #[inline(never)]
    pub(super) fn after_equation(&self, j: &'s str) -> nom::Err<RuleError> {
        if matches!(j.as_bytes().first(), Some(b')' | b']')) {
            return failure(self.unexpected(j));
        }
        failure(self.expected(
            j,
            "`;`, a line break or `}` after the equation",
            "put each equation on its own line or separate them with `;`",
            None,
        ))
    }

    /// The error for the token at `j` after the `}` of a solve block.
    #[cold]
    #[inline(never)]
    pub(super) fn after_block(&self, j: &'s str) -> nom::Err<RuleError> {
        if matches!(j.as_bytes().first(), Some(b')' | b']' | b'}')) {
            return failure(self.unexpected(j));
        }
        failure(self.expected(
            j,
            "the end of the line after `}`",
            "a solve block ends its statement: start the next statement on a new line, or after `;`",
            None,
        ))
    }

    /// The error for a second `=` at `j` in one equation.
    #[cold]
    #[inline(never)]
    pub(super) fn second_equals(&self, j: &'s str) -> nom::Err<RuleError> {
        failure(
            Diagnostic::error(self.token(j).0, "an equation has exactly one `=`")
                .with_hint(
                    "write each equation on its own line or separate them with `;`: `a = b; b = c`",
                )
                .with_kind(crate::diag::ErrorKind::Syntax),
        )
    }

    /// `block_ws ::= ( space | comment | newline | ";" )*`
    pub(super) fn block_ws(&self, mut i: &'s str) -> &'s str {
        loop {
            i = self.ws_nl(i);
            match i.strip_prefix(';') {
                Some(rest) => i = rest,
                None => return i,
            }
        }
    }

    /// `equation ::= expr ws "=" ws expr`
    pub(super) fn equation(&self, i: &'s str) -> RuleResult<'s, Equation> {
        let (rest, lhs) = match self.expr(i) {
            Ok(x) => x,
            Err(e) => return Err(self.equation_error(e, i)),
        };
        let j = self.ws(rest);
        let Some(k) = j.strip_prefix('=') else {
            return Err(self.no_equals(j, lhs.outer));
        };
        let (rest, (rhs, outer)) = self.rhs(k, "=")?;
        let span = lhs.outer.to(outer);
        Ok((
            rest,
            Equation {
                lhs: *lhs.e,
                rhs,
                span,
            },
        ))
    }

    /// The error for a missing left side at `i` of an equation.
    #[cold]
    #[inline(never)]
    pub(super) fn equation_error(&self, e: nom::Err<RuleError>, i: &'s str) -> nom::Err<RuleError> {
        if !matches!(e, nom::Err::Error(_)) {
            return e;
        }
        let what = if i.starts_with('=') {
            "an expression before `=`"
        } else {
            "an equation"
        };
        failure(self.expected(
            i,
            what,
            "an equation is written `lhs = rhs`, one per line or separated by `;`",
            None,
        ))
    }

    /// The error when no `=` follows (at `j`) the left side `lhs` of an
    /// equation.
    #[cold]
    #[inline(never)]
    pub(super) fn no_equals(&self, j: &'s str, lhs: Span) -> nom::Err<RuleError> {
        if matches!(j.as_bytes().first(), None | Some(b'\n' | b';' | b'}')) {
            let l = excerpt(&self.src[lhs.start..lhs.end]);
            return failure(
                Diagnostic::error(lhs, "an equation needs `=`")
                    .with_hint(format!("write it as `lhs = rhs`, like `{l} = 0`"))
                    .with_kind(crate::diag::ErrorKind::Syntax),
            );
        }
        failure(self.expected(
            j,
            "`=` after the left side of the equation",
            "an equation is written `lhs = rhs`",
            None,
        ))
    }

    /// `definition ::= ident ws "=" ws expr`
    pub(super) fn definition(&self, i: &'s str) -> RuleResult<'s, Stmt> {
        let (rest, name) = self.ident(i)?;
        let rest = match self.equals(rest) {
            Ok(k) => k,
            Err(j) => {
                let hint = if rest.starts_with('(') {
                    format!(
                        "functions can't be defined in a scene; define a name instead: `{} = expression`",
                        name.name
                    )
                } else {
                    format!("a definition is written `{} = expression`", name.name)
                };
                return Err(self.equals_error(j, &name.name, &hint));
            }
        };
        let (rest, (value, outer)) = self.rhs(rest, "=")?;
        let span = name.span.to(outer);
        Ok((rest, Stmt::Def { name, value, span }))
    }

    /// The `"="` of a definition or role statement: the input after it, or
    /// (as the error) the input where it is missing.
    pub(super) fn equals(&self, i: &'s str) -> Result<&'s str, &'s str> {
        let j = self.ws(i);
        j.strip_prefix('=').ok_or(j)
    }

    /// The error for a missing `"="` at `j`, after `head`.
    #[cold]
    #[inline(never)]
    pub(super) fn equals_error(&self, j: &'s str, head: &str, hint: &str) -> nom::Err<RuleError> {
        failure(self.expected(j, &format!("`=` after `{head}`"), hint, None))
    }

    /// The expression after `=` or `:` that ends a statement, with the
    /// source span it came from (including enclosing parentheses).
    pub(super) fn rhs(&self, i: &'s str, after: &str) -> RuleResult<'s, (Expr, Span)> {
        match self.expr(i) {
            Ok((rest, node)) => Ok((rest, (*node.e, node.outer))),
            Err(e) => Err(self.rhs_error(e, i, after)),
        }
    }

    /// The error for a missing expression at `i`, after `after`.
    #[cold]
    #[inline(never)]
    pub(super) fn rhs_error(
        &self,
        e: nom::Err<RuleError>,
        i: &'s str,
        after: &str,
    ) -> nom::Err<RuleError> {
        if !matches!(e, nom::Err::Error(_)) {
            return e;
        }
        let op_span = Span::new(self.pos(i) - after.len(), self.pos(i));
        failure(self.expected(
            self.ws(i),
            &format!("an expression after `{after}`"),
            HINT_EXPR,
            Some(op_span),
        ))
    }

    // ----- expressions -------------------------------------------------------
}
