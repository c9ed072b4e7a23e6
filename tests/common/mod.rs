//! Shared test helpers: a compact S-expression printer of the AST, a
//! fully parenthesized source printer, span stripping, and error locations.
#![allow(dead_code)]

pub mod numeric;
pub mod run;

use qdot::diag::Diagnostic;
use qdot::parse::ast::{BinOp, Callee, Expr, ExprKind, Ident, Span, Stmt};
use qdot::parse::{parse_expr, parse_scene};

fn op_str(op: BinOp) -> &'static str {
    match op {
        BinOp::Add => "+",
        BinOp::Sub => "-",
        BinOp::Mul => "*",
        BinOp::Div => "/",
        BinOp::Pow => "^",
    }
}

/// `(* 2 r)`, `(^ (' y1 1) 2)`, `(- x)` (unary minus), `(sin x)` (a call),
/// `(f)` (a call without arguments), `1/4`, `30deg`, `[x y]` (a vector).
pub fn sexpr(e: &Expr) -> String {
    match &e.kind {
        ExprKind::Num(r) => r.to_string(),
        ExprKind::Degrees(r) => format!("{r}deg"),
        ExprKind::Name(n) => n.clone(),
        ExprKind::Neg(x) => format!("(- {})", sexpr(x)),
        ExprKind::Bin(op, a, b) => format!("({} {} {})", op_str(*op), sexpr(a), sexpr(b)),
        ExprKind::Call(f, args) => {
            let mut s = format!("({}", f.name());
            for a in args {
                s.push(' ');
                s.push_str(&sexpr(a));
            }
            s.push(')');
            s
        }
        ExprKind::Prime(x, n) => format!("(' {} {n})", sexpr(x)),
        ExprKind::Vector(cs) => format!("[{}]", cs.iter().map(sexpr).collect::<Vec<_>>().join(" ")),
        ExprKind::Assign(a, b) => format!("(= {} {})", sexpr(a), sexpr(b)),
        ExprKind::Index(a, b) => format!("(index {} {})", sexpr(a), sexpr(b)),
    }
}

/// The facts of an `assume` statement, `e real` and `R > r` each.
fn facts_text(
    facts: &[qdot::parse::ast::Fact],
    show: impl Fn(&Expr) -> String,
    sep: &str,
) -> String {
    facts
        .iter()
        .map(|f| match f {
            qdot::parse::ast::Fact::Real(n) => format!("{} real", n.name),
            qdot::parse::ast::Fact::Order { greater, less, .. } => {
                format!("{} > {}", show(greater), show(less))
            }
        })
        .collect::<Vec<_>>()
        .join(sep)
}

/// The properties of a body statement, as `(mass m) (at P)`.
fn properties(b: &qdot::parse::ast::BodyStmt, show: impl Fn(&Expr) -> String, sep: &str) -> String {
    b.properties
        .iter()
        .map(|p| match &p.about {
            Some(a) => format!(
                "{} {} about {}",
                p.key.keyword(),
                show(&p.value),
                show(&a.point)
            ),
            None => format!("{} {}", p.key.keyword(), show(&p.value)),
        })
        .collect::<Vec<_>>()
        .join(sep)
}

fn decls(ds: &[qdot::parse::ast::Decl]) -> String {
    ds.iter()
        .map(|d| match &d.dimension {
            Some(dim) => format!("{}:{}", d.name.name, sexpr(dim)),
            None => d.name.name.clone(),
        })
        .collect::<Vec<_>>()
        .join(" ")
}

pub fn stmt_sexpr(s: &Stmt) -> String {
    match s {
        Stmt::Latex { name, tex, .. } => format!("(latex {} {tex:?})", name.name),
        Stmt::Coordinates(ds, _) => format!("(coordinates {})", decls(ds)),
        Stmt::Parameters(ds, _) => format!("(parameters {})", decls(ds)),
        Stmt::Functions(ds, _) => format!("(functions {})", decls(ds)),
        Stmt::Def { name, value, .. } => format!("(def {} {})", name.name, sexpr(value)),
        Stmt::Role {
            role, name, value, ..
        } => format!("({} {} {})", role.keyword(), name.name, sexpr(value)),
        Stmt::Force {
            coordinate, value, ..
        } => format!("(force {} {})", coordinate.name, sexpr(value)),
        Stmt::Load { force, point, .. } => format!("(load {} {})", sexpr(force), sexpr(point)),
        Stmt::Torque { moment, angle, .. } => {
            format!("(torque {} {})", sexpr(moment), sexpr(angle))
        }
        Stmt::Frame { name, value, .. } => format!("(frame {} {})", name.name, sexpr(value)),
        Stmt::Gravity { value, .. } => format!("(gravity {})", sexpr(value)),
        Stmt::Assume(facts, _) => format!("(assume {})", facts_text(facts, sexpr, " ")),
        Stmt::Reaction {
            constraint, point, ..
        } => format!("(reaction {} {})", constraint.name, sexpr(point)),
        Stmt::Joint(j) => format!(
            "(joint {} {} ({} {}) ({} {}){})",
            j.name.name,
            j.kind.keyword(),
            j.first.body.name,
            sexpr(&j.first.point),
            j.second.body.name,
            sexpr(&j.second.point),
            j.along
                .as_ref()
                .map_or(String::new(), |u| format!(" (along {})", sexpr(u)))
        ),
        Stmt::Drive {
            name,
            coordinate,
            value,
            ..
        } => format!("(drive {} {} {})", name.name, coordinate.name, sexpr(value)),
        Stmt::Friction {
            joint, coefficient, ..
        } => format!("(friction {} {})", joint.name, sexpr(coefficient)),
        Stmt::Constraint { name, equation, .. } => format!(
            "(constraint {}(= {} {}))",
            name.as_ref()
                .map_or(String::new(), |n| format!("{} ", n.name)),
            sexpr(&equation.lhs),
            sexpr(&equation.rhs)
        ),
        Stmt::Body(b) => format!(
            "({} {} ({}))",
            b.kind.keyword(),
            b.name.name,
            properties(b, sexpr, ") (")
        ),
        Stmt::Solve(b) => {
            let mut s = format!(
                "(solve ({})",
                b.unknowns
                    .iter()
                    .map(|u| u.name.as_str())
                    .collect::<Vec<_>>()
                    .join(" ")
            );
            for eq in &b.equations {
                s.push_str(&format!(" (= {} {})", sexpr(&eq.lhs), sexpr(&eq.rhs)));
            }
            s.push(')');
            s
        }
    }
}

/// The S-expression of a scene, one statement per line.
pub fn scene(src: &str) -> String {
    match parse_scene(src) {
        Ok(stmts) => stmts.iter().map(stmt_sexpr).collect::<Vec<_>>().join("\n"),
        Err(d) => panic!("parse error in {src:?}: {d} at {:?}", d.span),
    }
}

/// The S-expression of one expression.
pub fn ex(src: &str) -> String {
    match parse_expr(src) {
        Ok(e) => sexpr(&e),
        Err(d) => panic!("parse error in {src:?}: {d} at {:?}", d.span),
    }
}

/// The value of `x = SRC` in a scene, as an S-expression.
pub fn def(src: &str) -> String {
    let full = format!("x = {src}");
    match parse_scene(&full) {
        Ok(stmts) => {
            assert_eq!(stmts.len(), 1, "{full:?}");
            match &stmts[0] {
                Stmt::Def { value, .. } => sexpr(value),
                s => panic!("not a definition: {s:?}"),
            }
        }
        Err(d) => panic!("parse error in {full:?}: {d} at {:?}", d.span),
    }
}

/// Where an error is: (line, column, end line, end column, message, hint).
#[derive(Debug, PartialEq)]
pub struct At {
    pub line: usize,
    pub col: usize,
    pub width: usize,
    pub message: String,
    pub hint: String,
}

pub fn locate(src: &str, d: &Diagnostic) -> At {
    let span = d.span.expect("error has a span");
    let (line, col) = Diagnostic::line_col(src, span.start);
    At {
        line,
        col,
        width: src[span.start..span.end].chars().count(),
        message: d.message.clone(),
        hint: d.hint.clone().unwrap_or_default(),
    }
}

pub fn scene_err(src: &str) -> At {
    match parse_scene(src) {
        Ok(s) => panic!("expected an error for {src:?}, got {s:?}"),
        Err(d) => locate(src, &d),
    }
}

pub fn expr_err(src: &str) -> At {
    match parse_expr(src) {
        Ok(e) => panic!("expected an error for {src:?}, got {}", sexpr(&e)),
        Err(d) => locate(src, &d),
    }
}

/// Zero all spans, to compare trees modulo positions.
pub fn strip(e: &Expr) -> Expr {
    let kind = match &e.kind {
        ExprKind::Neg(x) => ExprKind::Neg(Box::new(strip(x))),
        ExprKind::Bin(op, a, b) => ExprKind::Bin(*op, Box::new(strip(a)), Box::new(strip(b))),
        ExprKind::Call(f, args) => ExprKind::Call(
            Callee::resolve(Ident {
                name: f.name().to_string(),
                span: Span::default(),
            }),
            args.iter().map(strip).collect(),
        ),
        ExprKind::Prime(x, n) => ExprKind::Prime(Box::new(strip(x)), *n),
        ExprKind::Vector(cs) => ExprKind::Vector(cs.iter().map(strip).collect()),
        ExprKind::Assign(a, b) => ExprKind::Assign(Box::new(strip(a)), Box::new(strip(b))),
        k => k.clone(),
    };
    Expr {
        kind,
        span: Span::default(),
    }
}

/// Print an exact rational as a decimal literal, if it has one.
pub fn decimal(r: &num_rational::BigRational) -> Option<String> {
    use num_bigint::BigInt;
    use num_traits::{Signed, Zero};
    if r.is_negative() {
        return None;
    }
    let den = r.denom().clone();
    let mut k = 0usize;
    let ten = BigInt::from(10);
    let mut scale = BigInt::from(1);
    // multiply by 10 until the denominator divides the scale
    while !(&scale % &den).is_zero() {
        scale *= &ten;
        k += 1;
        if k > 2100 {
            return None;
        }
    }
    let scaled = r.numer() * (&scale / &den);
    let digits = scaled.to_string();
    if k == 0 {
        return Some(digits);
    }
    let digits = format!("{:0>width$}", digits, width = k + 1);
    let (int, frac) = digits.split_at(digits.len() - k);
    Some(format!("{int}.{frac}"))
}

/// Fully parenthesized source text of an expression.
pub fn print_full(e: &Expr) -> String {
    match &e.kind {
        ExprKind::Num(r) => decimal(r).unwrap_or_else(|| format!("({}/{})", r.numer(), r.denom())),
        ExprKind::Degrees(r) => format!("{}deg", decimal(r).expect("decimal degrees")),
        ExprKind::Name(n) => n.clone(),
        ExprKind::Neg(x) => format!("(-{})", print_full(x)),
        ExprKind::Bin(op, a, b) => {
            format!("({} {} {})", print_full(a), op_str(*op), print_full(b))
        }
        ExprKind::Call(f, args) => format!(
            "{}({})",
            f.name(),
            args.iter().map(print_full).collect::<Vec<_>>().join(", ")
        ),
        ExprKind::Prime(x, n) => {
            let inner = match &x.kind {
                ExprKind::Name(_) | ExprKind::Call(..) | ExprKind::Vector(_) => print_full(x),
                _ => format!("({})", print_full(x)),
            };
            format!("{inner}{}", "'".repeat(*n as usize))
        }
        ExprKind::Vector(cs) => format!(
            "[{}]",
            cs.iter().map(print_full).collect::<Vec<_>>().join(", ")
        ),
        ExprKind::Assign(a, b) => format!("{} = {}", print_full(a), print_full(b)),
        ExprKind::Index(a, b) => {
            let inner = match &a.kind {
                ExprKind::Name(_) | ExprKind::Call(..) | ExprKind::Vector(_) => print_full(a),
                _ => format!("({})", print_full(a)),
            };
            format!("{inner}[{}]", print_full(b))
        }
    }
}

/// A statement printed back as source, expressions fully parenthesized.
pub fn print_stmt(s: &Stmt) -> String {
    let ds = |ds: &[qdot::parse::ast::Decl]| {
        ds.iter()
            .map(|d| match &d.dimension {
                Some(dim) => format!("{}: {}", d.name.name, print_full(dim)),
                None => d.name.name.clone(),
            })
            .collect::<Vec<_>>()
            .join(", ")
    };
    match s {
        Stmt::Latex { name, tex, .. } => format!("latex {} = \"{tex}\"", name.name),
        Stmt::Coordinates(d, _) => format!("coordinates {}", ds(d)),
        Stmt::Parameters(d, _) => format!("parameters {}", ds(d)),
        Stmt::Functions(d, _) => format!("functions {}", ds(d)),
        Stmt::Def { name, value, .. } => format!("{} = {}", name.name, print_full(value)),
        Stmt::Role {
            role, name, value, ..
        } => format!("{} {} = {}", role.keyword(), name.name, print_full(value)),
        Stmt::Force {
            coordinate, value, ..
        } => format!("force {}: {}", coordinate.name, print_full(value)),
        Stmt::Load { force, point, .. } => {
            format!("load {} at {}", print_full(force), print_full(point))
        }
        Stmt::Torque { moment, angle, .. } => {
            format!("torque {} on {}", print_full(moment), print_full(angle))
        }
        Stmt::Frame { name, value, .. } => format!("frame {} = {}", name.name, print_full(value)),
        Stmt::Gravity { value, .. } => format!("gravity {}", print_full(value)),
        Stmt::Assume(facts, _) => format!("assume {}", facts_text(facts, print_full, ", ")),
        Stmt::Reaction {
            constraint, point, ..
        } => format!("reaction {} at {}", constraint.name, print_full(point)),
        Stmt::Joint(j) => format!(
            "joint {}: {} {} at {}, {} at {}{}",
            j.name.name,
            j.kind.keyword(),
            j.first.body.name,
            print_full(&j.first.point),
            j.second.body.name,
            print_full(&j.second.point),
            j.along
                .as_ref()
                .map_or(String::new(), |u| format!(" along {}", print_full(u)))
        ),
        Stmt::Drive {
            name,
            coordinate,
            value,
            ..
        } => format!(
            "drive {}: {} = {}",
            name.name,
            coordinate.name,
            print_full(value)
        ),
        Stmt::Friction {
            joint, coefficient, ..
        } => format!("friction {}: {}", joint.name, print_full(coefficient)),
        Stmt::Constraint { name, equation, .. } => format!(
            "constraint {}{} = {}",
            name.as_ref()
                .map_or(String::new(), |n| format!("{}: ", n.name)),
            print_full(&equation.lhs),
            print_full(&equation.rhs)
        ),
        Stmt::Body(b) => format!(
            "{} {}: {}",
            b.kind.keyword(),
            b.name.name,
            properties(b, print_full, ", ")
        ),
        Stmt::Solve(b) => {
            let names = b
                .unknowns
                .iter()
                .map(|u| u.name.as_str())
                .collect::<Vec<_>>()
                .join(", ");
            let eqs = b
                .equations
                .iter()
                .map(|eq| format!("{} = {}", print_full(&eq.lhs), print_full(&eq.rhs)))
                .collect::<Vec<_>>()
                .join("; ");
            format!("solve {names} {{ {eqs} }}")
        }
    }
}

/// The keys of a command's JSON for `scene`: `base`, then `dimensions`
/// when the scene annotates a dimension; the `dimensions` value is checked
/// against the library's report.
pub fn contract_keys<'a>(
    v: &serde_json::Value,
    scene: &qdot::Scene,
    base: &[&'a str],
) -> Vec<&'a str> {
    let mut want = base.to_vec();
    if !scene.bodies.is_empty() {
        want.push("bodies");
        assert_eq!(v["bodies"], qdot::output::bodies_json(scene));
    }
    if scene.dimensions_checked {
        want.push("dimensions");
        let report = scene.dimension_report().unwrap();
        assert_eq!(v["dimensions"], qdot::output::dimensions_json(&report));
    }
    want
}

/// The `.qd` files of a directory of cases, sorted.
pub fn cases(dir: &std::path::Path) -> Vec<std::path::PathBuf> {
    let mut v: Vec<std::path::PathBuf> = std::fs::read_dir(dir)
        .expect("the cases' directory")
        .map(|e| e.expect("an entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "qd"))
        .collect();
    v.sort();
    v
}

/// Compare `actual` with the blessed `.txt` beside `case`, or write it
/// under `QDOT_BLESS=1`; a difference is printed and pushed to `failures`.
pub fn blessed(case: &std::path::Path, actual: &str, failures: &mut Vec<String>) {
    let txt = case.with_extension("txt");
    if std::env::var_os("QDOT_BLESS").is_some() {
        if std::fs::read_to_string(&txt).ok().as_deref() != Some(actual) {
            std::fs::write(&txt, actual).expect("write the blessed output");
        }
        return;
    }
    match std::fs::read_to_string(&txt) {
        Ok(expected) if expected == actual => {}
        Ok(expected) => {
            eprintln!(
                "{}: differs (< blessed, > now):\n{}",
                case.display(),
                pretty_assertions::StrComparison::new(&expected, &actual)
            );
            failures.push(format!("{}: differs from its .txt", case.display()));
        }
        Err(_) => failures.push(format!("{}: no blessed .txt", case.display())),
    }
}

/// Every `.qd` of `dir` is refused by `Scene::parse` with a positioned
/// error and a hint, blessed as `NAME.txt` (line:column, then the rendered
/// error), and `derive` refuses it with the same message; at least `min`
/// cases.
pub fn refused_where_written(dir: &std::path::Path, min: usize) {
    use qdot::output::{self, Command, Format};
    let all = cases(dir);
    assert!(all.len() >= min, "{} wrong scenes", all.len());
    let mut failures = Vec::new();
    for case in &all {
        let src = std::fs::read_to_string(case).unwrap();
        let name = case.file_name().unwrap().to_string_lossy().into_owned();
        let err = match qdot::Scene::parse(&src) {
            Ok(_) => {
                failures.push(format!("{name}: accepted"));
                continue;
            }
            Err(d) => d,
        };
        let Some(span) = err.span else {
            failures.push(format!("{name}: no position: {}", err.message));
            continue;
        };
        assert!(err.hint.is_some(), "{name}: no hint: {}", err.message);
        let (line, col) = qdot::Diagnostic::line_col(&src, span.start);
        let text = format!("{line}:{col}\n{}", err.render(&name, &src));
        blessed(case, &text, &mut failures);
        let got = output::run(Command::Derive, &src, Format::Json, &Default::default());
        assert_eq!(got.err().map(|d| d.message), Some(err.message.clone()));
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// A property test's number of cases: `n`, or `PROPTEST_CASES` when set,
/// so a long campaign (`PROPTEST_CASES=50000 cargo test --release --test it
/// -- properties::`) needs no edit.
pub fn proptest_cases(n: u32) -> u32 {
    std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(n)
}
