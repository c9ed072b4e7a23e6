//! Property tests: no input makes the parser panic, every error is well
//! formed, and printing a tree with full parentheses parses back to it.

use crate::common::{print_full, print_stmt, stmt_sexpr, strip};
use num_bigint::BigInt;
use num_rational::BigRational;
use proptest::prelude::*;
use qdot::diag::Diagnostic;
use qdot::parse::ast::{BinOp, Callee, Equation, Expr, ExprKind, Ident, SolveBlock, Span, Stmt};
use qdot::parse::{parse_expr, parse_scene};

/// An error must point inside the source, on character boundaries, and
/// carry a message and a hint.
fn check_diag(src: &str, d: &Diagnostic) -> Result<(), TestCaseError> {
    let span = d.span.expect("parse errors have a span");
    prop_assert!(span.start <= span.end, "{d:?}");
    prop_assert!(span.end <= src.len(), "{d:?} beyond {}", src.len());
    prop_assert!(src.is_char_boundary(span.start) && src.is_char_boundary(span.end));
    prop_assert!(!d.message.is_empty());
    prop_assert!(
        d.hint.as_ref().is_some_and(|h| !h.is_empty()),
        "no hint: {d:?}"
    );
    // rendering never panics either
    let _ = d.render("t.qd", src);
    Ok(())
}

fn check_span(src: &str, s: Span) -> Result<(), TestCaseError> {
    prop_assert!(s.start <= s.end && s.end <= src.len(), "{s:?}");
    prop_assert!(src.is_char_boundary(s.start) && src.is_char_boundary(s.end));
    Ok(())
}

fn check_expr_spans(src: &str, e: &Expr) -> Result<(), TestCaseError> {
    check_span(src, e.span)?;
    match &e.kind {
        ExprKind::Neg(x) | ExprKind::Prime(x, _) => {
            prop_assert!(e.span.start <= x.span.start && x.span.end <= e.span.end);
            check_expr_spans(src, x)
        }
        ExprKind::Bin(_, a, b) | ExprKind::Index(a, b) => {
            prop_assert!(e.span.start <= a.span.start && b.span.end <= e.span.end);
            check_expr_spans(src, a)?;
            check_expr_spans(src, b)
        }
        ExprKind::Call(f, args) => {
            check_span(src, f.span())?;
            prop_assert_eq!(&src[f.span().start..f.span().end], f.name());
            args.iter().try_for_each(|a| check_expr_spans(src, a))
        }
        ExprKind::Name(n) => {
            prop_assert_eq!(&src[e.span.start..e.span.end], n.as_str());
            Ok(())
        }
        ExprKind::Vector(cs) => {
            prop_assert!(!cs.is_empty());
            prop_assert!(src[e.span.start..].starts_with('['));
            prop_assert!(src[..e.span.end].ends_with(']'));
            for c in cs {
                prop_assert!(e.span.start < c.span.start && c.span.end < e.span.end);
                check_expr_spans(src, c)?;
            }
            Ok(())
        }
        _ => Ok(()),
    }
}

fn check_scene(src: &str) -> Result<Option<Vec<Stmt>>, TestCaseError> {
    match parse_scene(src) {
        Ok(stmts) => {
            for s in &stmts {
                check_span(src, s.span())?;
                match s {
                    Stmt::Def { value, .. }
                    | Stmt::Role { value, .. }
                    | Stmt::Force { value, .. }
                    | Stmt::Frame { value, .. }
                    | Stmt::Gravity { value, .. } => check_expr_spans(src, value)?,
                    Stmt::Drive { value, .. } => check_expr_spans(src, value)?,
                    Stmt::Friction { coefficient, .. } => check_expr_spans(src, coefficient)?,
                    Stmt::Joint(j) => {
                        check_expr_spans(src, &j.first.point)?;
                        check_expr_spans(src, &j.second.point)?;
                        if let Some(u) = &j.along {
                            check_expr_spans(src, u)?;
                        }
                    }
                    Stmt::Assume(facts, span) => {
                        prop_assert!(src[span.start..].starts_with("assume"));
                        for f in facts {
                            if let qdot::parse::ast::Fact::Order { greater, less, .. } = f {
                                check_expr_spans(src, greater)?;
                                check_expr_spans(src, less)?;
                            }
                        }
                    }
                    Stmt::Reaction {
                        constraint,
                        point,
                        span,
                    } => {
                        prop_assert!(src[span.start..].starts_with("reaction"));
                        prop_assert!(constraint.span.end < point.span.start);
                        prop_assert!(point.span.end == span.end);
                        check_expr_spans(src, point)?;
                    }
                    Stmt::Constraint {
                        name,
                        equation,
                        span,
                    } => {
                        prop_assert!(src[span.start..].starts_with("constraint"));
                        if let Some(n) = name {
                            prop_assert!(
                                span.start < n.span.start && n.span.end < equation.span.start
                            );
                        }
                        prop_assert!(equation.span.end == span.end);
                        check_expr_spans(src, &equation.lhs)?;
                        check_expr_spans(src, &equation.rhs)?;
                    }
                    Stmt::Body(b) => {
                        for p in &b.properties {
                            prop_assert!(b.span.start < p.key_span.start);
                            prop_assert!(p.key_span.end < p.value.span.start);
                            prop_assert!(p.value.span.end <= b.span.end);
                            check_expr_spans(src, &p.value)?;
                        }
                    }
                    Stmt::Coordinates(ds, _) | Stmt::Parameters(ds, _) | Stmt::Functions(ds, _) => {
                        prop_assert!(!ds.is_empty());
                    }
                    Stmt::Latex { name, tex, span } => {
                        prop_assert!(src[span.start..].starts_with("latex"));
                        prop_assert!(src[..span.end].ends_with('"'));
                        prop_assert!(!tex.is_empty() && !tex.contains('"'));
                        check_span(src, name.span)?;
                    }
                    Stmt::Load {
                        force: a,
                        point: b,
                        span,
                    }
                    | Stmt::Torque {
                        moment: a,
                        angle: b,
                        span,
                    } => {
                        prop_assert!(span.start < a.span.start && a.span.end < b.span.start);
                        prop_assert!(b.span.end <= span.end);
                        check_expr_spans(src, a)?;
                        check_expr_spans(src, b)?;
                    }
                    Stmt::Solve(b) => {
                        prop_assert!(!b.unknowns.is_empty() && !b.equations.is_empty());
                        prop_assert!(src[b.span.start..].starts_with("solve"));
                        let closes = src[..b.span.end].ends_with('}');
                        prop_assert!(closes, "{:?}", b.span);
                        for u in &b.unknowns {
                            check_span(src, u.span)?;
                            prop_assert_eq!(&src[u.span.start..u.span.end], u.name.as_str());
                        }
                        for eq in &b.equations {
                            check_span(src, eq.span)?;
                            prop_assert!(b.span.start < eq.span.start && eq.span.end < b.span.end);
                            prop_assert!(eq.span.start <= eq.lhs.span.start);
                            prop_assert!(eq.lhs.span.end < eq.rhs.span.start);
                            prop_assert!(eq.rhs.span.end <= eq.span.end);
                            check_expr_spans(src, &eq.lhs)?;
                            check_expr_spans(src, &eq.rhs)?;
                        }
                    }
                }
            }
            Ok(Some(stmts))
        }
        Err(d) => {
            check_diag(src, &d)?;
            Ok(None)
        }
    }
}

fn check_one_expr(src: &str) -> Result<(), TestCaseError> {
    match parse_expr(src) {
        Ok(e) => check_expr_spans(src, &e),
        Err(d) => check_diag(src, &d),
    }
}

// ---------------------------------------------------------------------------
// (a) arbitrary input

proptest! {
    #![proptest_config(ProptestConfig { cases: crate::common::proptest_cases(512), ..ProptestConfig::default() })]

    #[test]
    fn random_bytes_never_panic(bytes in prop::collection::vec(any::<u8>(), 0..200)) {
        let src = String::from_utf8_lossy(&bytes);
        check_scene(&src)?;
        check_one_expr(&src)?;
    }

    #[test]
    fn random_strings_never_panic(src in any::<String>()) {
        check_scene(&src)?;
        check_one_expr(&src)?;
    }

    #[test]
    fn strings_of_language_characters_never_panic(
        src in "[a-zθε_0-9 +*/^'()\\[\\]{}=,:;.#°$\n\r\t-]{0,80}"
    ) {
        check_scene(&src)?;
        check_one_expr(&src)?;
    }
}

// ---------------------------------------------------------------------------
// (b) random token sequences

fn token() -> impl Strategy<Value = &'static str> {
    prop::sample::select(vec![
        // names and keywords
        "x",
        "y1",
        "θ",
        "ε_2",
        "_a",
        "J2",
        "e",
        "deg",
        "t",
        "sin",
        "atan",
        "kinetic",
        "potential",
        "forcefunction",
        "work",
        "dissipation",
        "rayleigh",
        "force",
        "coordinates",
        "parameters",
        "load",
        "torque",
        "solve",
        "at",
        "on",
        "at",
        "on",
        // numbers, good and bad
        "3",
        "0",
        "0.25",
        "1.5e-3",
        "2E3",
        "2e",
        ".5",
        "1.2.3",
        "3.",
        "30deg",
        "30°",
        "°",
        "1e9999",
        "007",
        // operators and punctuation
        "+",
        "-",
        "*",
        "/",
        "^",
        "**",
        "'",
        "''",
        "(",
        ")",
        "(",
        ")",
        "=",
        "=",
        ",",
        ":",
        ";",
        "[",
        "]",
        "[",
        "]",
        ",",
        "{",
        "}",
        // layout
        "\n",
        "\n",
        "\r\n",
        "# note",
        " ",
        "\t",
        // junk
        "$",
        "²",
        "\u{0}",
        "é",
        "\"",
    ])
}

fn token_source() -> impl Strategy<Value = String> {
    prop::collection::vec((token(), prop::bool::ANY), 0..40).prop_map(|toks| {
        let mut s = String::new();
        for (t, space) in toks {
            s.push_str(t);
            if space {
                s.push(' ');
            }
        }
        s
    })
}

/// A token sequence shaped like a statement, so that many parse.
fn statement_source() -> impl Strategy<Value = String> {
    let head = prop::sample::select(vec![
        "x = ",
        "kinetic T = ",
        "work L = ",
        "force x: ",
        "y1=",
        "work = ",
        "load ",
        "load [",
        "torque ",
        "solve x { ",
        "solve x, y {\n",
        "at = ",
        "constraint ",
        "constraint c: ",
        "constraint x ",
        "reaction c at ",
        "reaction c ",
    ]);
    prop::collection::vec((head, prop::collection::vec(token(), 1..12)), 1..5).prop_map(|lines| {
        lines
            .into_iter()
            .map(|(h, toks)| format!("{h}{}", toks.concat()))
            .collect::<Vec<_>>()
            .join("\n")
    })
}

/// Print a scene back with full parentheses; it must parse to the same
/// statements (modulo spans).
fn reprint_roundtrip(stmts: &[Stmt]) -> Result<(), TestCaseError> {
    let printed = stmts.iter().map(print_stmt).collect::<Vec<_>>().join("\n");
    let again = parse_scene(&printed)
        .map_err(|d| TestCaseError::fail(format!("reprint {printed:?} fails: {d}")))?;
    let a: Vec<String> = stmts.iter().map(stmt_sexpr).collect();
    let b: Vec<String> = again.iter().map(stmt_sexpr).collect();
    prop_assert_eq!(a, b, "reprinted as {:?}", printed);
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: crate::common::proptest_cases(1024), ..ProptestConfig::default() })]

    #[test]
    fn token_sequences_never_panic(src in token_source()) {
        if let Some(stmts) = check_scene(&src)? {
            reprint_roundtrip(&stmts)?;
        }
        check_one_expr(&src)?;
    }

    #[test]
    fn statement_like_sequences_never_panic(src in statement_source()) {
        if let Some(stmts) = check_scene(&src)? {
            reprint_roundtrip(&stmts)?;
        }
    }
}

// ---------------------------------------------------------------------------
// (c) random trees print and parse back

fn num() -> impl Strategy<Value = BigRational> {
    (0u32..100_000, 0usize..4)
        .prop_map(|(n, k)| BigRational::new(BigInt::from(n), num_traits::pow(BigInt::from(10), k)))
}

fn name() -> impl Strategy<Value = String> {
    prop_oneof![
        prop::sample::select(vec![
            "x",
            "y1",
            "θ3",
            "ε",
            "_a",
            "J2",
            "e",
            "E",
            "deg",
            "t",
            "pi",
            "kinetic",
            "work",
            "force",
            "coordinates",
            "degrees",
            "load",
            "torque",
            "solve",
            "at",
            "on",
        ])
        .prop_map(str::to_string),
        // no omicron: drawn like `o`, refused in names
        "[a-zA-Zα-ξπ-ω_][a-zA-Z0-9_]{0,5}",
    ]
}

fn at(kind: ExprKind) -> Expr {
    Expr {
        kind,
        span: Span::default(),
    }
}

fn tree() -> impl Strategy<Value = Expr> {
    let leaf = prop_oneof![
        num().prop_map(|r| at(ExprKind::Num(r))),
        num().prop_map(|r| at(ExprKind::Degrees(r))),
        name().prop_map(|n| at(ExprKind::Name(n))),
    ];
    leaf.prop_recursive(6, 64, 4, |inner| {
        let op = prop::sample::select(vec![
            BinOp::Add,
            BinOp::Sub,
            BinOp::Mul,
            BinOp::Div,
            BinOp::Pow,
        ]);
        prop_oneof![
            inner.clone().prop_map(|e| at(ExprKind::Neg(Box::new(e)))),
            (op, inner.clone(), inner.clone()).prop_map(|(op, a, b)| at(ExprKind::Bin(
                op,
                Box::new(a),
                Box::new(b)
            ))),
            (name(), prop::collection::vec(inner.clone(), 0..4)).prop_map(|(f, args)| at(
                ExprKind::Call(
                    Callee::resolve(Ident {
                        name: f,
                        span: Span::default()
                    }),
                    args
                )
            )),
            (inner.clone(), 1u32..4).prop_map(|(e, n)| at(ExprKind::Prime(Box::new(e), n))),
            prop::collection::vec(inner, 1..4).prop_map(|cs| at(ExprKind::Vector(cs))),
        ]
    })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: crate::common::proptest_cases(512), ..ProptestConfig::default() })]

    #[test]
    fn printed_trees_parse_back(e in tree()) {
        let src = print_full(&e);
        let back = parse_expr(&src)
            .map_err(|d| TestCaseError::fail(format!("{src:?}: {d}")))?;
        prop_assert_eq!(strip(&back), strip(&e), "printed as {:?}", src);
        check_expr_spans(&src, &back)?;
        // the same inside a scene
        let scene = format!("kinetic T = {src}\n");
        let stmts = parse_scene(&scene)
            .map_err(|d| TestCaseError::fail(format!("{scene:?}: {d}")))?;
        match &stmts[..] {
            [Stmt::Role { value, .. }] => prop_assert_eq!(strip(value), strip(&e)),
            other => prop_assert!(false, "unexpected {:?}", other),
        }
    }
}

fn ident(n: String) -> Ident {
    Ident {
        name: n,
        span: Span::default(),
    }
}

/// Random `load`, `torque` and `solve` statements (spans zeroed).
fn new_statement() -> impl Strategy<Value = Stmt> {
    let s = Span::default();
    prop_oneof![
        (tree(), tree()).prop_map(move |(force, point)| Stmt::Load {
            force,
            point,
            span: s
        }),
        (tree(), tree()).prop_map(move |(moment, angle)| Stmt::Torque {
            moment,
            angle,
            span: s
        }),
        (
            prop::collection::vec(name(), 1..4),
            prop::collection::vec((tree(), tree()), 1..4)
        )
            .prop_map(move |(us, eqs)| Stmt::Solve(SolveBlock {
                unknowns: us.into_iter().map(ident).collect(),
                equations: eqs
                    .into_iter()
                    .map(|(lhs, rhs)| Equation { lhs, rhs, span: s })
                    .collect(),
                span: s,
            })),
    ]
}

/// The layouts a printed solve block may take: one line with `;`, one
/// equation per line with the `}` on its own line, or with blank lines and
/// comments.
fn layout(printed: &str, style: u8) -> String {
    let Some((head, rest)) = printed.split_once(" { ") else {
        return printed.to_string();
    };
    let body = rest.strip_suffix(" }").expect("printed block ends in ` }`");
    match style {
        0 => printed.to_string(),
        1 => format!("{head} {{\n  {}\n}}", body.replace("; ", "\n  ")),
        _ => format!(
            "{head} {{ # the equations\n\n  {} ;\n\n  # end\n  }}",
            body.replace("; ", " # note\n\n  ")
        ),
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: crate::common::proptest_cases(512), ..ProptestConfig::default() })]

    #[test]
    fn printed_statements_parse_back(st in new_statement(), style in 0u8..3) {
        let src = layout(&print_stmt(&st), style);
        let scene = format!("x = 1\n{src}\ny = 2");
        let stmts = parse_scene(&scene)
            .map_err(|d| TestCaseError::fail(format!("{scene:?}: {d}")))?;
        prop_assert_eq!(stmts.len(), 3, "{:?}", scene);
        prop_assert_eq!(stmt_sexpr(&stmts[1]), stmt_sexpr(&st), "printed as {:?}", src);
        check_scene(&scene)?;
        let span = stmts[1].span();
        prop_assert_eq!(&scene[span.start..span.end], src.as_str());
    }
}
