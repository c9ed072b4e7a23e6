//! The statement rules of bodies in space and in the plane: `frame`,
//! `body`/`particle` and `gravity`.

use super::ast::{About, BodyKind, BodyProperty, BodyStmt, PropertyKey};
use super::*;

impl<'s> Parser<'s> {
    /// `frame_stmt ::= "frame" ws ident ws "=" ws expr`
    #[inline(never)]
    pub(super) fn frame_stmt(&self, i: &'s str) -> RuleResult<'s, Stmt> {
        let i = self.ws(i);
        let start = self.pos(i);
        let Some(rest) = i.strip_prefix("frame") else {
            return self.nothing(i);
        };
        let (rest, name) = self.ident(rest)?;
        let rest = match self.equals(rest) {
            Ok(k) => k,
            Err(j) => {
                let head = format!("frame {}", name.name);
                let hint = format!(
                    "a frame is named like `frame {} = rot(z, phi) * rot(x, theta)`",
                    name.name
                );
                return Err(self.equals_error(j, &head, &hint));
            }
        };
        let (rest, (value, outer)) = self.rhs(rest, "=")?;
        let span = Span::new(start, outer.end);
        Ok((rest, Stmt::Frame { name, value, span }))
    }

    /// `gravity_stmt ::= "gravity" ws expr`
    #[inline(never)]
    pub(super) fn gravity_stmt(&self, i: &'s str) -> RuleResult<'s, Stmt> {
        let i = self.ws(i);
        let start = self.pos(i);
        let Some(rest) = i.strip_prefix("gravity") else {
            return self.nothing(i);
        };
        let kw = Span::new(start, start + "gravity".len());
        let (rest, value) = match self.expr(rest) {
            Ok((rest, node)) => (rest, node),
            Err(nom::Err::Error(_)) => {
                return self.fail(self.expected(
                    self.ws(rest),
                    "the acceleration of gravity after `gravity`",
                    "write it as a vector, `gravity [0, -g]` in the plane or `gravity [0, 0, -g]` in space; to define a name `gravity`, write `gravity = expression`",
                    Some(kw),
                ))
            }
            Err(e) => return Err(e),
        };
        let span = Span::new(start, value.outer.end);
        Ok((
            rest,
            Stmt::Gravity {
                value: *value.e,
                span,
            },
        ))
    }

    /// `body_stmt ::= ( "body" | "particle" ) ws ident ws ":" ws property ( ws "," ws property )*`
    #[inline(never)]
    pub(super) fn body_stmt(&self, i: &'s str) -> RuleResult<'s, Stmt> {
        let i = self.ws(i);
        let start = self.pos(i);
        let (rest, kind) = if let Some(rest) = i.strip_prefix("body") {
            (rest, BodyKind::Rigid)
        } else if let Some(rest) = i.strip_prefix("particle") {
            (rest, BodyKind::Particle)
        } else {
            return self.nothing(i);
        };
        let (rest, name) = self.ident(rest)?;
        let example = body_example(kind, &name.name);
        let j = self.ws(rest);
        let Some(mut rest) = j.strip_prefix(':') else {
            return self.fail(self.expected(
                j,
                &format!("`:` after `{} {}`", kind.keyword(), name.name),
                &format!("a {} is written `{example}`", kind.keyword()),
                None,
            ));
        };
        let mut properties = Vec::new();
        loop {
            let (after, p) = self.property(rest, kind, &example)?;
            properties.push(p);
            let j = self.ws(after);
            match j.strip_prefix(',') {
                Some(k) => rest = k,
                None if matches!(j.as_bytes().first(), None | Some(b'\n' | b';')) => {
                    rest = after;
                    break;
                }
                None => {
                    let len = ident_len(j);
                    let hint = if len > 0 && PropertyKey::from_keyword(&j[..len]).is_some() {
                        "separate the properties with commas: `mass m, at P`".to_string()
                    } else {
                        format!("a {} is written `{example}`", kind.keyword())
                    };
                    return self.fail(self.expected(
                        j,
                        &format!("`,` after the {}", p_key_noun(&properties)),
                        &hint,
                        None,
                    ));
                }
            }
        }
        let end = properties
            .last()
            .map_or(name.span.end, |p| p.value.span.end);
        let span = Span::new(start, end);
        Ok((
            rest,
            Stmt::Body(BodyStmt {
                kind,
                name,
                properties,
                span,
            }),
        ))
    }

    /// `property ::= ( "mass" | "inertia" | "frame" | "angle" | "at" ) ws expr ( ws "about" ws expr )?`
    pub(super) fn property(
        &self,
        i: &'s str,
        kind: BodyKind,
        example: &str,
    ) -> RuleResult<'s, BodyProperty> {
        let j = self.ws(i);
        let len = ident_len(j);
        let key = PropertyKey::from_keyword(&j[..len]);
        let Some(key) = key.filter(|_| len > 0) else {
            if &j[..len] == ABOUT {
                return self.fail(
                    Diagnostic::error(
                        self.token(j).0,
                        "`about` belongs to the inertia: it follows the inertia's value, without a comma",
                    )
                    .with_hint(ABOUT_FORM).with_kind(crate::diag::ErrorKind::Syntax),
                );
            }
            let words: Vec<&str> = PropertyKey::ALL.iter().map(|k| k.keyword()).collect();
            return self.fail(self.expected(
                j,
                &format!("a property of the {}", kind.keyword()),
                &format!("the properties are {}: `{example}`", words.join(", ")),
                None,
            ));
        };
        let key_span = Span::new(self.pos(j), self.pos(j) + len);
        let rest = &j[len..];
        // the value ends where another operand would follow (`mass m at P`
        // is a missing comma, said by the caller)
        self.stop.set(true);
        let value = self.expr(rest);
        self.stop.set(false);
        match value {
            Ok((rest, node)) => {
                let (rest, about) = self.about(rest, key)?;
                Ok((
                    rest,
                    BodyProperty {
                        key,
                        key_span,
                        value: *node.e,
                        about,
                    },
                ))
            }
            Err(nom::Err::Error(_)) => self.fail(self.expected(
                self.ws(rest),
                &format!("a value after `{}`", key.keyword()),
                &format!("a {} is written `{example}`", kind.keyword()),
                Some(key_span),
            )),
            Err(e) => Err(e),
        }
    }

    /// `( ws "about" ws expr )?` after the value of the property `key`:
    /// only an inertia is taken about a point, and about one.
    fn about(&self, i: &'s str, key: PropertyKey) -> RuleResult<'s, Option<About>> {
        let j = self.ws(i);
        if !starts_with_about(j) {
            return Ok((i, None));
        }
        let key_span = Span::new(self.pos(j), self.pos(j) + ABOUT.len());
        if key != PropertyKey::Inertia {
            return self.fail(
                Diagnostic::error(
                    key_span,
                    format!(
                        "`about` follows an inertia, and this follows the {}",
                        p_key_noun_of(key)
                    ),
                )
                .with_hint(ABOUT_FORM)
                .with_kind(crate::diag::ErrorKind::Syntax),
            );
        }
        let rest = &j[ABOUT.len()..];
        self.stop.set(true);
        let point = self.expr(rest);
        self.stop.set(false);
        let (rest, point) = match point {
            Ok((rest, node)) => (rest, *node.e),
            Err(nom::Err::Error(_)) => {
                return self.fail(self.expected(
                    self.ws(rest),
                    "the point after `about`",
                    ABOUT_FORM,
                    Some(key_span),
                ))
            }
            Err(e) => return Err(e),
        };
        let k = self.ws(rest);
        if starts_with_about(k) {
            let again = Span::new(self.pos(k), self.pos(k) + ABOUT.len());
            return self.fail(
                Diagnostic::error(
                    again,
                    "an inertia is taken about one point, and this gives a second",
                )
                .with_hint(ABOUT_FORM)
                .with_kind(crate::diag::ErrorKind::Syntax),
            );
        }
        Ok((rest, Some(About { key_span, point })))
    }
}

/// The word of [`About`].
const ABOUT: &str = "about";

/// How an inertia about a point is written, for hints.
const ABOUT_FORM: &str = "an inertia about a point other than the centre of mass is written `inertia [A, A, C] about O`, O the point in ground components (a point of the body, such as a fixed pivot), right after the inertia";

/// Whether `i` starts with the word `about`.
fn starts_with_about(i: &str) -> bool {
    ident_len(i) == ABOUT.len() && i.starts_with(ABOUT)
}

/// "mass" / "position": how the property `key` is named in messages.
fn p_key_noun_of(key: PropertyKey) -> &'static str {
    match key {
        PropertyKey::At => "position",
        k => k.keyword(),
    }
}

/// "mass" / "position": the last property parsed, for messages.
fn p_key_noun(properties: &[BodyProperty]) -> &'static str {
    properties.last().map_or("name", |p| p_key_noun_of(p.key))
}

/// How a body or particle named `name` is written, for hints.
fn body_example(kind: BodyKind, name: &str) -> String {
    match kind {
        BodyKind::Rigid => {
            format!("body {name}: mass m, inertia [A, A, C], frame B, at P")
        }
        BodyKind::Particle => format!("particle {name}: mass m, at P"),
    }
}
