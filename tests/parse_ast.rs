//! Exact syntax trees for every construct and precedence rule.

use crate::common::{def, ex, scene};
use pretty_assertions::assert_eq;
use qdot::parse::ast::{Builtin, Callee, ExprKind, Span, Stmt};
use qdot::parse::{parse_expr, parse_scene};

#[test]
fn the_example_scene() {
    let src = r#"# seed problem 23.4
coordinates y3, theta3          # generalized coordinates, functions of time t
parameters G, g, r              # constant symbols
mu = 1/8                        # a definition: a name for an expression
m = G/g
J3 = 4*G*r^2/g
y1 = y3 + 2*r*theta3            # kinematic table
kinetic E1 = 1/2*m*y1'^2        # ' is d/dt
kinetic E3 = 1/2*(3*m)*y3'^2 + 1/2*J3*theta3'^2
forcefunction U = G*y1 + 3*G*y3
work L = -mu*2*G*x5
force theta3: M0*cos(Omega*t)
parameters r: length, m: mass     # optional dimension annotations
"#;
    let expected = "\
(coordinates y3 theta3)
(parameters G g r)
(def mu (/ 1 8))
(def m (/ G g))
(def J3 (/ (* (* 4 G) (^ r 2)) g))
(def y1 (+ y3 (* (* 2 r) theta3)))
(kinetic E1 (* (* (/ 1 2) m) (^ (' y1 1) 2)))
(kinetic E3 (+ (* (* (/ 1 2) (* 3 m)) (^ (' y3 1) 2)) (* (* (/ 1 2) J3) (^ (' theta3 1) 2))))
(forcefunction U (+ (* G y1) (* (* 3 G) y3)))
(work L (* (* (* (- mu) 2) G) x5))
(force theta3 (* M0 (cos (* Omega t))))
(parameters r:length m:mass)";
    assert_eq!(scene(src), expected);
}

#[test]
fn all_roles() {
    let src = "kinetic T = a\npotential V = b\nforcefunction U = c\nwork L = d\ndissipation D = e\nrayleigh R = f";
    assert_eq!(
        scene(src),
        "(kinetic T a)\n(potential V b)\n(forcefunction U c)\n(work L d)\n(dissipation D e)\n(rayleigh R f)"
    );
}

#[test]
fn keywords_do_not_reserve_names() {
    let src = "R = 5\nwork = 3\nforce = 2\nparameters = 3\ncoordinates = 1\nkinetic = x\nrayleigh=1\nx = kinetic + work*force";
    assert_eq!(
        scene(src),
        "(def R 5)\n(def work 3)\n(def force 2)\n(def parameters 3)\n(def coordinates 1)\n(def kinetic x)\n(def rayleigh 1)\n(def x (+ kinetic (* work force)))"
    );
    // keywords as declared names and as role/force targets
    assert_eq!(
        scene("parameters work, force\ncoordinates kinetic\nkinetic work = force\nforce kinetic: work"),
        "(parameters work force)\n(coordinates kinetic)\n(kinetic work force)\n(force kinetic work)"
    );
}

#[test]
fn declarations() {
    assert_eq!(scene("coordinates x"), "(coordinates x)");
    assert_eq!(scene("coordinates  x ,y,  z"), "(coordinates x y z)");
    assert_eq!(
        scene("parameters r: length, m:mass, k"),
        "(parameters r:length m:mass k)"
    );
}

#[test]
fn lines_comments_semicolons_crlf() {
    assert_eq!(scene(""), "");
    assert_eq!(scene("\n\n  # only a comment\n\t\n"), "");
    assert_eq!(scene("a = 1; b = 2"), "(def a 1)\n(def b 2)");
    assert_eq!(scene("a = 1;; b = 2;"), "(def a 1)\n(def b 2)");
    assert_eq!(scene("a = 1 # c\r\nb = 2\r\n"), "(def a 1)\n(def b 2)");
    assert_eq!(scene("a = 1#no space before the comment"), "(def a 1)");
    assert_eq!(scene("\u{feff}a = 1"), "(def a 1)");
}

#[test]
fn continuation_lines() {
    // a newline inside parentheses is white space
    assert_eq!(
        scene("e = (a +\n  b\n  + c)\nf = 1"),
        "(def e (+ (+ a b) c))\n(def f 1)"
    );
    assert_eq!(
        scene("e = atan(\n  y,   # the ordinate\n  x\n)"),
        "(def e (atan y x))"
    );
    // a line ending in a binary operator continues
    for op in ["+", "-", "*", "/", "^"] {
        let src = format!("e = a {op}\n   b\nf = 1");
        let want = format!("(def e ({op} a b))\n(def f 1)");
        assert_eq!(scene(&src), want, "{src:?}");
    }
    // comments and blank lines after the operator
    assert_eq!(scene("e = a +  # more\n\n  b"), "(def e (+ a b))");
    assert_eq!(scene("e = a +\r\n b\r\n"), "(def e (+ a b))");
    // a line that does not end in an operator ends the statement
    assert_eq!(scene("e = a\nf = b"), "(def e a)\n(def f b)");
}

#[test]
fn numbers_are_exact() {
    assert_eq!(def("3"), "3");
    assert_eq!(def("0.25"), "1/4");
    assert_eq!(def("1.5e-3"), "3/2000");
    assert_eq!(def("2E3"), "2000");
    assert_eq!(def("2e+3"), "2000");
    assert_eq!(def("2.50"), "5/2");
    assert_eq!(def("007"), "7");
    assert_eq!(def("1e0"), "1");
    assert_eq!(
        def("123456789012345678901234567890"),
        "123456789012345678901234567890"
    );
    assert_eq!(def("0.000"), "0");
}

#[test]
fn scientific_only_with_a_digit() {
    assert_eq!(def("2e"), "(* 2 e)");
    assert_eq!(def("2e-x"), "(- (* 2 e) x)");
    assert_eq!(def("2e+x"), "(+ (* 2 e) x)");
    assert_eq!(def("2ex"), "(* 2 ex)");
    assert_eq!(def("2E"), "(* 2 E)");
}

#[test]
fn angles() {
    assert_eq!(def("30deg"), "30deg");
    assert_eq!(def("30°"), "30deg");
    assert_eq!(def("30 °"), "30deg");
    assert_eq!(def("1.5deg"), "3/2deg");
    assert_eq!(def("30degrees"), "(* 30 degrees)");
    assert_eq!(def("30deg_x"), "(* 30 deg_x)");
    assert_eq!(def("30deg2"), "(* 30 deg2)");
    assert_eq!(def("-45deg + 90°"), "(+ (- 45deg) 90deg)");
    assert_eq!(def("sin(30deg)"), "(sin 30deg)");
    assert_eq!(def("2*30deg"), "(* 2 30deg)");
}

#[test]
fn identifiers() {
    assert_eq!(
        def("θ3 + ε + y_1 + J2 + _a + Ωx"),
        "(+ (+ (+ (+ (+ θ3 ε) y_1) J2) _a) Ωx)"
    );
    assert_eq!(scene("θ = 1"), "(def θ 1)");
    assert_eq!(scene("coordinates φ, ψ"), "(coordinates φ ψ)");
}

#[test]
fn sums_and_products_are_left_associative() {
    assert_eq!(def("a - b - c"), "(- (- a b) c)");
    assert_eq!(def("a + b - c + d"), "(+ (- (+ a b) c) d)");
    assert_eq!(def("a / b / c"), "(/ (/ a b) c)");
    assert_eq!(def("a / b * c"), "(* (/ a b) c)");
    assert_eq!(def("a + b * c"), "(+ a (* b c))");
    assert_eq!(def("a * b + c"), "(+ (* a b) c)");
    assert_eq!(def("(a + b) * c"), "(* (+ a b) c)");
}

#[test]
fn unary_signs() {
    assert_eq!(def("-x"), "(- x)");
    assert_eq!(def("-x^2"), "(- (^ x 2))");
    assert_eq!(def("-2^2"), "(- (^ 2 2))");
    assert_eq!(def("-a*b"), "(* (- a) b)");
    assert_eq!(def("a*-b"), "(* a (- b))");
    assert_eq!(def("a - -b"), "(- a (- b))");
    assert_eq!(def("--a"), "(- (- a))");
    assert_eq!(def("+a"), "a");
    assert_eq!(def("a + +b"), "(+ a b)");
    assert_eq!(def("-x'"), "(- (' x 1))");
    assert_eq!(def("-3"), "(- 3)");
}

#[test]
fn powers_are_right_associative_and_tight() {
    assert_eq!(def("a^b^c"), "(^ a (^ b c))");
    assert_eq!(def("2^-1"), "(^ 2 (- 1))");
    assert_eq!(def("2^+1"), "(^ 2 1)");
    assert_eq!(def("x^-y^2"), "(^ x (- (^ y 2)))");
    assert_eq!(def("2^--1"), "(^ 2 (- (- 1)))");
    assert_eq!(def("a*b^c"), "(* a (^ b c))");
    assert_eq!(def("a^b*c"), "(* (^ a b) c)");
    assert_eq!(def("(a^b)^c"), "(^ (^ a b) c)");
    assert_eq!(def("x^(1/2)"), "(^ x (/ 1 2))");
}

#[test]
fn primes() {
    assert_eq!(def("y1'"), "(' y1 1)");
    assert_eq!(def("x''"), "(' x 2)");
    assert_eq!(def("x'''"), "(' x 3)");
    assert_eq!(def("x'^2"), "(^ (' x 1) 2)");
    assert_eq!(def("(y3/2)''"), "(' (/ y3 2) 2)");
    assert_eq!(def("sin(x)'"), "(' (sin x) 1)");
    assert_eq!(def("(x')'"), "(' (' x 1) 1)");
    assert_eq!(def("(3)'"), "(' 3 1)");
    assert_eq!(def("x^y'"), "(^ x (' y 1))");
    assert_eq!(def("x' '"), "(' x 2)");
    assert_eq!(def("a*b'"), "(* a (' b 1))");
}

#[test]
fn calls() {
    assert_eq!(def("sin(x)"), "(sin x)");
    assert_eq!(def("atan(y, x)"), "(atan y x)");
    assert_eq!(def("f()"), "(f)");
    assert_eq!(def("f( )"), "(f)");
    assert_eq!(def("whatever(a, b, c+1)"), "(whatever a b (+ c 1))");
    assert_eq!(def("sqrt(sin(x)^2)"), "(sqrt (^ (sin x) 2))");
    assert_eq!(def("sin(x)^2"), "(^ (sin x) 2)");
    assert_eq!(def("kinetic(x)"), "(kinetic x)");
}

#[test]
fn implicit_multiplication() {
    assert_eq!(def("2r"), "(* 2 r)");
    assert_eq!(def("2(x+y)"), "(* 2 (+ x y))");
    assert_eq!(def("3sin(x)"), "(* 3 (sin x))");
    assert_eq!(def("(a+b)(c+d)"), "(* (+ a b) (+ c d))");
    assert_eq!(def("sin(x)(y)"), "(* (sin x) y)");
    assert_eq!(def("2r^2"), "(* 2 (^ r 2))");
    assert_eq!(def("2x'"), "(* 2 (' x 1))");
    assert_eq!(def("2(x)'"), "(* 2 (' x 1))");
    assert_eq!(def("1/2r"), "(* (/ 1 2) r)");
    assert_eq!(def("2^3r"), "(* (^ 2 3) r)");
    assert_eq!(def("x^2y"), "(* (^ x 2) y)");
    assert_eq!(def("-2r"), "(* (- 2) r)");
    assert_eq!(def("0.5m*v^2"), "(* (* 1/2 m) (^ v 2))");
    // an identifier directly followed by `(` is always a call
    assert_eq!(def("2r(a)(b)"), "(* (* 2 (r a)) b)");
    assert_eq!(def("1.5e3x"), "(* 1500 x)");
    assert_eq!(def("a + 2b"), "(+ a (* 2 b))");
}

#[test]
fn parse_expr_takes_one_whole_expression() {
    assert_eq!(ex("a + b"), "(+ a b)");
    assert_eq!(ex("  \n a +\n b \n"), "(+ a b)");
    assert_eq!(ex("a\n+ b"), "(+ a b)");
    assert_eq!(ex("x # comment"), "x");
    assert_eq!(ex("(1/3)*x'"), "(* (/ 1 3) (' x 1))");
    assert!(parse_expr("").is_err());
    assert!(parse_expr("a b").is_err());
    assert!(parse_expr("x = 1").is_err());
    assert!(parse_expr("a)").is_err());
}

#[test]
fn spans_of_statements_and_nodes() {
    let src = "coordinates y3, theta3 # c\nm = 2r + (a)\nkinetic T = x''\nforce y3: -30deg";
    let stmts = parse_scene(src).unwrap();
    let text = |s: Span| &src[s.start..s.end];
    assert_eq!(text(stmts[0].span()), "coordinates y3, theta3");
    let Stmt::Coordinates(ds, _) = &stmts[0] else {
        panic!()
    };
    assert_eq!(text(ds[1].name.span), "theta3");
    let Stmt::Def { name, value, span } = &stmts[1] else {
        panic!()
    };
    assert_eq!(text(*span), "m = 2r + (a)");
    assert_eq!(text(name.span), "m");
    assert_eq!(text(value.span), "2r + (a)");
    let ExprKind::Bin(_, l, r) = &value.kind else {
        panic!()
    };
    assert_eq!(text(l.span), "2r");
    assert_eq!(text(r.span), "a");
    let Stmt::Role {
        value, span, name, ..
    } = &stmts[2]
    else {
        panic!()
    };
    assert_eq!(text(*span), "kinetic T = x''");
    assert_eq!(text(name.span), "T");
    assert_eq!(text(value.span), "x''");
    let Stmt::Force {
        coordinate,
        value,
        span,
    } = &stmts[3]
    else {
        panic!()
    };
    assert_eq!(text(*span), "force y3: -30deg");
    assert_eq!(text(coordinate.span), "y3");
    assert_eq!(text(value.span), "-30deg");
    let ExprKind::Neg(inner) = &value.kind else {
        panic!()
    };
    assert_eq!(text(inner.span), "30deg");

    // dimension annotations and calls
    let src2 = "parameters r: length\nf = atan(y, x)'";
    let text = |s: Span| &src2[s.start..s.end];
    let stmts = parse_scene(src2).unwrap();
    assert_eq!(text(stmts[0].span()), "parameters r: length");
    let Stmt::Def { value, .. } = &stmts[1] else {
        panic!()
    };
    assert_eq!(text(value.span), "atan(y, x)'");
    let ExprKind::Prime(call, 1) = &value.kind else {
        panic!()
    };
    assert_eq!(text(call.span), "atan(y, x)");
    let ExprKind::Call(f, args) = &call.kind else {
        panic!()
    };
    assert_eq!(text(f.span()), "atan");
    assert!(matches!(f, Callee::Builtin(Builtin::Atan, _)));
    assert_eq!(text(args[1].span), "x");
}

#[test]
fn spans_are_byte_offsets() {
    let src = "θ = ε + 30°";
    let stmts = parse_scene(src).unwrap();
    let Stmt::Def { value, .. } = &stmts[0] else {
        panic!()
    };
    assert_eq!(&src[value.span.start..value.span.end], "ε + 30°");
    // unary plus leaves no node: the operand keeps its own span
    let e = parse_expr("  +x ").unwrap();
    assert_eq!(e.span, Span::new(3, 4));
    let e = parse_expr("-x").unwrap();
    assert_eq!(e.span, Span::new(0, 2));
}

#[test]
fn parentheses_widen_parent_spans_only() {
    let src = "x = (a+b)*(c) + (+d)";
    let stmts = parse_scene(src).unwrap();
    let text = |s: Span| &src[s.start..s.end];
    let Stmt::Def { value, span, .. } = &stmts[0] else {
        panic!()
    };
    assert_eq!(text(*span), src);
    assert_eq!(text(value.span), "(a+b)*(c) + (+d)");
    let ExprKind::Bin(_, prod, d) = &value.kind else {
        panic!()
    };
    assert_eq!(text(prod.span), "(a+b)*(c)");
    assert_eq!(text(d.span), "d");
    let ExprKind::Bin(_, sum, c) = &prod.kind else {
        panic!()
    };
    assert_eq!(text(sum.span), "a+b");
    assert_eq!(text(c.span), "c");
    // a statement ends with its closing parenthesis
    let src = "kinetic T = (m*v^2)/2 + (x)";
    let stmts = parse_scene(src).unwrap();
    assert_eq!(stmts[0].span(), Span::new(0, src.len()));
    let src = "y = (x)''";
    let Stmt::Def { value, .. } = &parse_scene(src).unwrap()[0] else {
        panic!()
    };
    assert_eq!(&src[value.span.start..value.span.end], "(x)''");
    let ExprKind::Prime(x, 2) = &value.kind else {
        panic!()
    };
    assert_eq!(x.span, Span::new(5, 6));
}

#[test]
fn vectors() {
    assert_eq!(def("[x, y]"), "[x y]");
    assert_eq!(def("[x]"), "[x]");
    assert_eq!(def("[1, 0, 0]"), "[1 0 0]");
    assert_eq!(def("[ a+b , -c*d ]"), "[(+ a b) (* (- c) d)]");
    assert_eq!(def("[sin(q), atan(y, x)]"), "[(sin q) (atan y x)]");
    // nested, primed, and inside other expressions
    assert_eq!(def("[[a, b], [c, d]]"), "[[a b] [c d]]");
    assert_eq!(def("[x, y]'"), "(' [x y] 1)");
    assert_eq!(def("[x, y]''"), "(' [x y] 2)");
    assert_eq!(def("[x', y'']"), "[(' x 1) (' y 2)]");
    assert_eq!(def("2*[x, y] + [1, 0]"), "(+ (* 2 [x y]) [1 0])");
    assert_eq!(def("-[x, y]"), "(- [x y])");
    assert_eq!(def("[x, y]/2"), "(/ [x y] 2)");
    assert_eq!(def("dot([a, b], [c, d])"), "(dot [a b] [c d])");
    assert_eq!(def("([a, b])"), "[a b]");
    // a newline inside brackets is white space, comments included
    assert_eq!(
        scene("r = [\n  l*sin(q),   # x\n  -l*cos(q)   # y\n]\nm = 1"),
        "(def r [(* l (sin q)) (* (- l) (cos q))])\n(def m 1)"
    );
    assert_eq!(scene("r = [a\n, b]"), "(def r [a b])");
    assert_eq!(scene("r = [a,\r\n b]\r\n"), "(def r [a b])");
    assert_eq!(ex("[a,\n b]"), "[a b]");
}

#[test]
fn vector_spans() {
    let src = "r = [x, 2*y]' + [a]";
    let stmts = parse_scene(src).unwrap();
    let text = |s: Span| &src[s.start..s.end];
    let Stmt::Def { value, span, .. } = &stmts[0] else {
        panic!()
    };
    assert_eq!(text(*span), src);
    let ExprKind::Bin(_, l, r) = &value.kind else {
        panic!()
    };
    assert_eq!(text(l.span), "[x, 2*y]'");
    assert_eq!(text(r.span), "[a]");
    let ExprKind::Prime(v, 1) = &l.kind else {
        panic!()
    };
    assert_eq!(text(v.span), "[x, 2*y]");
    let ExprKind::Vector(cs) = &v.kind else {
        panic!()
    };
    assert_eq!(text(cs[0].span), "x");
    assert_eq!(text(cs[1].span), "2*y");
}

#[test]
fn loads_and_torques() {
    assert_eq!(
        scene("load [0, -m*g] at [x, y]"),
        "(load [0 (* (- m) g)] [x y])"
    );
    // a scalar force at a scalar displacement along it
    assert_eq!(scene("load -m*g at y"), "(load (* (- m) g) y)");
    assert_eq!(scene("load F at P"), "(load F P)");
    assert_eq!(
        scene("load F1 + F2*cos(t) at [x + r*cos(q), y]'"),
        "(load (+ F1 (* F2 (cos t))) (' [(+ x (* r (cos q))) y] 1))"
    );
    assert_eq!(
        scene("torque -c*phi' on phi"),
        "(torque (* (- c) (' phi 1)) phi)"
    );
    assert_eq!(
        scene("torque M0*cos(Omega*t) on theta3"),
        "(torque (* M0 (cos (* Omega t))) theta3)"
    );
    // no space needed around brackets and parentheses
    assert_eq!(scene("load[0, -g] at[x, y]"), "(load [0 (- g)] [x y])");
    assert_eq!(scene("load (a) at (b)"), "(load a b)");
    // the force continues after an operator at the end of a line
    assert_eq!(scene("load F +\n  G at P"), "(load (+ F G) P)");
    // several statements, comments
    assert_eq!(
        scene("load F at P; torque M on q # moments\nx = 1"),
        "(load F P)\n(torque M q)\n(def x 1)"
    );
}

#[test]
fn stop_words_end_the_first_expression_only() {
    // `at`/`on` stay ordinary names everywhere else
    assert_eq!(
        scene("at = 1\non = 2\nx = at + on"),
        "(def at 1)\n(def on 2)\n(def x (+ at on))"
    );
    assert_eq!(scene("load F at at"), "(load F at)");
    assert_eq!(scene("torque M on on"), "(torque M on)");
    assert_eq!(scene("load on at P"), "(load on P)");
    assert_eq!(scene("torque at on P"), "(torque at P)");
    // as an operand, the stop word is a name: it ends the force only where
    // an operator could follow
    assert_eq!(scene("load at at P"), "(load at P)");
    assert_eq!(scene("torque on on q"), "(torque on q)");
    assert_eq!(scene("load F*at at P"), "(load (* F at) P)");
    assert_eq!(scene("load -at' at P"), "(load (- (' at 1)) P)");
    assert_eq!(scene("load F +\n  at at P"), "(load (+ F at) P)");
    // an implicit product after a number takes it too (no space)
    assert_eq!(scene("load 2at at P"), "(load (* 2 at) P)");
    assert_eq!(scene("load 2 at P"), "(load 2 P)");
    // inside parentheses, brackets and calls it is a name
    assert_eq!(scene("load (at) at P"), "(load at P)");
    assert_eq!(scene("load [at, 0] at P"), "(load [at 0] P)");
    assert_eq!(scene("load f(at) at P"), "(load (f at) P)");
    assert_eq!(scene("load (F*at)' at P"), "(load (' (* F at) 1) P)");
    // directly before `(` it is a call; longer names are names
    assert_eq!(scene("load at(x) at P"), "(load (at x) P)");
    assert_eq!(scene("load atx + at_2 at P"), "(load (+ atx at_2) P)");
    assert_eq!(scene("load F at (P)"), "(load F P)");
    // after the statement, `at` is a name again
    assert_eq!(
        scene("load F at P\nx = a*at"),
        "(load F P)\n(def x (* a at))"
    );
}

#[test]
fn load_torque_and_solve_are_not_reserved() {
    assert_eq!(
        scene("load = 3\ntorque = 2\nsolve = 1\nx = load*torque + solve"),
        "(def load 3)\n(def torque 2)\n(def solve 1)\n(def x (+ (* load torque) solve))"
    );
    assert_eq!(
        scene("parameters load, torque, solve\nkinetic load = solve"),
        "(parameters load torque solve)\n(kinetic load solve)"
    );
    assert_eq!(scene("load load at torque"), "(load load torque)");
    assert_eq!(scene("torque solve on load"), "(torque solve load)");
    assert_eq!(
        scene("solve load { load = solve }"),
        "(solve (load) (= load solve))"
    );
}

#[test]
fn solve_blocks() {
    assert_eq!(
        scene("solve a3, T1 { m*a3 = T1 - m*g; J*a3/r = -T1*r }"),
        "(solve (a3 T1) (= (* m a3) (- T1 (* m g))) (= (/ (* J a3) r) (* (- T1) r)))"
    );
    assert_eq!(scene("solve x { x = 1 }"), "(solve (x) (= x 1))");
    assert_eq!(scene("solve x {x=1}"), "(solve (x) (= x 1))");
    assert_eq!(scene("solve x{x=1}"), "(solve (x) (= x 1))");
    // one equation per line; `}` on its own line or after the last equation
    let multi = "solve a, b {\n  a + b = 1\n  a - b = 0\n}\nx = a";
    assert_eq!(
        scene(multi),
        "(solve (a b) (= (+ a b) 1) (= (- a b) 0))\n(def x a)"
    );
    assert_eq!(
        scene("solve a, b {\n  a + b = 1\n  a - b = 0 }\nx = a"),
        "(solve (a b) (= (+ a b) 1) (= (- a b) 0))\n(def x a)"
    );
    // blank lines, comments, extra `;`, CRLF
    let messy = "solve a, b {   # the unknowns\r\n\r\n  # first\r\n  a = 1;;\r\n  ; b = 2 ; # second\r\n\r\n}   # done\r\ny = 1";
    assert_eq!(scene(messy), "(solve (a b) (= a 1) (= b 2))\n(def y 1)");
    // a newline inside an equation: after an operator, in parentheses or brackets
    assert_eq!(
        scene("solve x {\n  x = a +\n      b\n  [x, y] = [\n    1, 2]\n  (x\n  ) = 3\n}"),
        "(solve (x) (= x (+ a b)) (= [x y] [1 2]) (= x 3))"
    );
    // vectors, primes and calls in equations
    assert_eq!(
        scene("solve F { m*[x, y]'' = F + [0, -m*g] }"),
        "(solve (F) (= (* m (' [x y] 2)) (+ F [0 (* (- m) g)])))"
    );
    // statements on the same line before and after `;`
    assert_eq!(
        scene("a = 1; solve x { x = a }; b = 2"),
        "(def a 1)\n(solve (x) (= x a))\n(def b 2)"
    );
}

#[test]
fn spans_of_new_statements() {
    let src =
        "load [0, -g] at [x, y] # c\ntorque -c*q' on q\nsolve a, b {\n  a = 1  # one\n  b = (a)\n}";
    let stmts = parse_scene(src).unwrap();
    let text = |s: Span| &src[s.start..s.end];
    let Stmt::Load { force, point, span } = &stmts[0] else {
        panic!()
    };
    assert_eq!(text(*span), "load [0, -g] at [x, y]");
    assert_eq!(text(force.span), "[0, -g]");
    assert_eq!(text(point.span), "[x, y]");
    let Stmt::Torque {
        moment,
        angle,
        span,
    } = &stmts[1]
    else {
        panic!()
    };
    assert_eq!(text(*span), "torque -c*q' on q");
    assert_eq!(text(moment.span), "-c*q'");
    assert_eq!(text(angle.span), "q");
    let Stmt::Solve(b) = &stmts[2] else { panic!() };
    assert_eq!(text(b.span), "solve a, b {\n  a = 1  # one\n  b = (a)\n}");
    assert_eq!(stmts[2].span(), b.span);
    assert_eq!(text(b.unknowns[0].span), "a");
    assert_eq!(text(b.unknowns[1].span), "b");
    assert_eq!(text(b.equations[0].span), "a = 1");
    // the equation's span includes the parentheses of its right side
    assert_eq!(text(b.equations[1].span), "b = (a)");
    assert_eq!(text(b.equations[1].lhs.span), "b");
    assert_eq!(text(b.equations[1].rhs.span), "a");
    // a load ends with the parentheses of its point
    let src = "load (F) at (P)";
    assert_eq!(parse_scene(src).unwrap()[0].span(), Span::new(0, src.len()));
}

// ---------------------------------------------------------------- latex

fn latex_of(src: &str) -> (String, String) {
    let stmts = qdot::parse::parse_scene(src).expect("parses");
    match &stmts[0] {
        Stmt::Latex { name, tex, span } => {
            assert_eq!(
                &src[span.start..span.end],
                src.trim_end().split(';').next().unwrap().trim()
            );
            (name.name.clone(), tex.clone())
        }
        other => panic!("not a latex statement: {other:?}"),
    }
}

#[test]
fn latex_statement_keeps_backslashes_braces_and_hashes() {
    assert_eq!(
        latex_of("latex theta3 = \"\\vartheta_{3}\""),
        ("theta3".to_string(), "\\vartheta_{3}".to_string())
    );
    assert_eq!(
        latex_of("latex x = \"\\dot{x}_{\\mathrm{rel}} # not a comment\""),
        (
            "x".to_string(),
            "\\dot{x}_{\\mathrm{rel}} # not a comment".to_string()
        )
    );
    // `latex` may itself be the name
    assert_eq!(
        latex_of("latex latex = \"L\""),
        ("latex".to_string(), "L".to_string())
    );
}

#[test]
fn latex_is_not_reserved() {
    let stmts = qdot::parse::parse_scene("latex = 3").expect("parses");
    assert!(matches!(&stmts[0], Stmt::Def { name, .. } if name.name == "latex"));
    // a statement may follow on the line
    let stmts = qdot::parse::parse_scene("latex x = \"X\"; y = 2").expect("parses");
    assert_eq!(stmts.len(), 2);
}
