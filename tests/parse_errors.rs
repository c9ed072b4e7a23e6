//! Error positions (line, column, width in characters), messages and hints.

use crate::common::{expr_err, locate, scene_err, At};
use pretty_assertions::assert_eq;
use qdot::parse::{parse_expr, parse_scene, MAX_DEPTH, MAX_NESTING};

fn short(src: &str) -> String {
    src.chars().take(60).collect()
}

/// Check one scene error: position `line:col`, width, exact message, and a
/// piece of the hint.
#[track_caller]
fn check(src: &str, line: usize, col: usize, width: usize, message: &str, hint_part: &str) {
    let at = scene_err(src);
    assert_eq!(
        (at.line, at.col, at.width, at.message.as_str()),
        (line, col, width, message),
        "for {:?}",
        short(src)
    );
    assert!(
        at.hint.contains(hint_part),
        "hint {:?} lacks {hint_part:?} for {:?}",
        at.hint,
        short(src)
    );
}

#[track_caller]
fn check_expr(src: &str, line: usize, col: usize, width: usize, message: &str, hint_part: &str) {
    let At {
        line: l,
        col: c,
        width: w,
        message: m,
        hint,
    } = expr_err(src);
    assert_eq!(
        (l, c, w, m.as_str()),
        (line, col, width, message),
        "for {src:?}"
    );
    assert!(
        hint.contains(hint_part),
        "hint {hint:?} lacks {hint_part:?}"
    );
}

#[test]
fn unknown_characters() {
    check(
        "x = 3 $ 4",
        1,
        7,
        1,
        "unknown character `$`",
        "not part of the .qd language",
    );
    check(
        "x = 1\r\ny = $",
        2,
        5,
        1,
        "unknown character `$`",
        "not part",
    );
    check("x = a → b", 1, 7, 1, "unknown character `→`", "not part");
    check("x = x²", 1, 6, 1, "unknown character `²`", "`x^2`");
    check("x = a × b", 1, 7, 1, "unknown character `×`", "`*`");
    check("x = a − b", 1, 7, 1, "unknown character `−`", "ASCII `-`");
    check(
        "x = \u{1}",
        1,
        5,
        1,
        "unknown character U+0001 (a control character)",
        "delete it",
    );
    check("x = a ¦ b", 1, 7, 1, "unknown character `¦`", "not part");
    check("θ = ε $", 1, 7, 1, "unknown character `$`", "not part");
}

/// Characters that can't be seen or can't be told from ASCII are named by
/// their code point; columns count characters.
#[test]
fn invisible_and_look_alike_characters() {
    let invisible = ", which is invisible";
    check(
        "θ = 1\nx = a\u{200B} + b",
        2,
        6,
        1,
        &format!("unknown character U+200B (ZERO WIDTH SPACE){invisible}"),
        "delete it",
    );
    // a bidirectional control, even in a comment or a string
    check(
        "x = a + b # \u{202E}c",
        1,
        13,
        1,
        "invisible character U+202E (RIGHT-TO-LEFT OVERRIDE), which reorders how the line is displayed",
        "refused in comments and strings too",
    );
    check(
        "y = 1\nlatex x = \"\u{2066}\"",
        2,
        12,
        1,
        "invisible character U+2066 (LEFT-TO-RIGHT ISOLATE), which reorders how the line is displayed",
        "the text shown is not the text read",
    );
    assert_eq!(
        expr_err("a + \u{200F}b").message,
        "invisible character U+200F (RIGHT-TO-LEFT MARK), which reorders how the line is displayed"
    );
    check(
        "x = a\u{2060}",
        1,
        6,
        1,
        &format!("unknown character U+2060 (WORD JOINER){invisible}"),
        "delete it",
    );
    check(
        "x = 1\u{37E} y = 2",
        1,
        6,
        1,
        "unknown character U+037E (GREEK QUESTION MARK), which looks like `;`",
        "replace it with the ASCII `;`",
    );
    check(
        "x = a\u{FF0A}b",
        1,
        6,
        1,
        "unknown character U+FF0A (a fullwidth form), which looks like `*`",
        "ASCII `*`",
    );
    check(
        "x = \u{FF11}",
        1,
        5,
        1,
        "unknown character U+FF11 (FULLWIDTH DIGIT 1), which looks like `1`",
        "ASCII `1`",
    );
    // a look-alike letter in a name: at that letter
    check(
        "parameters m\u{430}ss, k",
        1,
        13,
        1,
        "the name `m\u{430}ss` has the character U+0430 (CYRILLIC SMALL LETTER A), which looks like `a`",
        "retype it as the ASCII `a`",
    );
    check(
        "y = 2*\u{3BF}",
        1,
        7,
        1,
        "the name `\u{3BF}` has the character U+03BF (GREEK SMALL LETTER OMICRON), which looks like `o`",
        "ASCII `o`",
    );
    check(
        "v = x\u{2BC}",
        1,
        6,
        1,
        "the name `x\u{2BC}` has the character U+02BC (MODIFIER LETTER APOSTROPHE), which looks like `'`",
        "ASCII prime",
    );
    check(
        "\u{FF58} = 1",
        1,
        1,
        1,
        "the name `\u{FF58}` has the character U+FF58 (FULLWIDTH LATIN SMALL LETTER X), which looks like `x`",
        "ASCII `x`",
    );
    // names in other scripts are names
    assert!(parse_scene("масса = 1\nθ3 = 2*масса\nΔx = θ3").is_ok());
    // a no-break space is white space
    assert!(parse_scene("x =\u{A0}1").is_ok());
}

/// A misspelled keyword: "did you mean", at the word.
#[test]
fn misspelled_keywords() {
    for (src, width, kw) in [
        ("potental V = 1/2*k*x^2", 8, "potential"),
        ("coordinate x", 10, "coordinates"),
        ("paramters m, k", 9, "parameters"),
        ("kinectic E = 1/2*m*x'^2", 8, "kinetic"),
        ("forcefuntion U = m*g*x", 12, "forcefunction"),
        ("rayliegh R = 1/2*b*x'^2", 8, "rayleigh"),
        ("solv a { a = 1 }", 4, "solve"),
        ("Potential V = x", 9, "potential"),
        ("lod F at P", 3, "load"),
    ] {
        let word = &src[..width];
        check(
            &format!("x = 1\n  {src}"),
            2,
            3,
            width,
            &format!("unknown keyword `{word}`"),
            &format!("did you mean `{kw}`?"),
        );
    }
    // not near a keyword: the usual message
    check(
        "energy E = 1",
        1,
        8,
        1,
        "expected `=` after `energy`, found `E`",
        "a definition is written",
    );
    // a keyword spelled with a look-alike letter: that letter
    check(
        "p\u{43E}tential V = x",
        1,
        2,
        1,
        "the name `p\u{43E}tential` has the character U+043E (CYRILLIC SMALL LETTER O), which looks like `o`",
        "ASCII `o`",
    );
    // a definition of a name that looks like a keyword is a definition
    assert!(parse_scene("potental = 3").is_ok());
}

#[test]
fn side_by_side() {
    check(
        "x = a b",
        1,
        7,
        1,
        "two expressions side by side",
        "did you mean `a*b`?",
    );
    check(
        "x = 2*a b+c",
        1,
        9,
        1,
        "two expressions side by side",
        "did you mean `a*b`?",
    );
    check("x = 3 4", 1, 7, 1, "two expressions side by side", "`3*4`");
    check(
        "x = 2 r",
        1,
        7,
        1,
        "two expressions side by side",
        "without a space: `2r`",
    );
    check(
        "x = (a+b) (c+d)",
        1,
        11,
        5,
        "two expressions side by side",
        "`(a+b)*(c+d)`",
    );
    check(
        "x = (a)b",
        1,
        8,
        1,
        "two expressions side by side",
        "`(a)*b`",
    );
    check(
        "x = sin (x)",
        1,
        9,
        3,
        "two expressions side by side",
        "write `sin(x)` without a space",
    );
    check(
        "x = 30 deg",
        1,
        8,
        3,
        "two expressions side by side",
        "`30deg` without a space, or `30°`",
    );
    check(
        "x = f(a b)",
        1,
        9,
        1,
        "two expressions side by side",
        "`a*b`",
    );
    check("x = a'b", 1, 7, 1, "two expressions side by side", "`a'*b`");
    check(
        "x = 30°x",
        1,
        8,
        1,
        "two expressions side by side",
        "`30°*x`",
    );
    check(
        "x = (a\n b)",
        2,
        2,
        1,
        "two expressions side by side",
        "is a `)` missing",
    );
    check_expr("a b", 1, 3, 1, "two expressions side by side", "`a*b`");
}

#[test]
fn definitions() {
    check(
        "m G/g",
        1,
        3,
        1,
        "expected `=` after `m`, found `G`",
        "`m = expression`",
    );
    check(
        "m\nn = 1",
        1,
        2,
        0,
        "expected `=` after `m`, but the line ends",
        "`m = expression`",
    );
    check(
        "f(x) = x^2",
        1,
        2,
        1,
        "expected `=` after `f`, found `(`",
        "functions can't be defined",
    );
    check(
        "x =",
        1,
        3,
        1,
        "expected an expression after `=`, but the file ends",
        "a number, a name",
    );
    check(
        "x = \ny = 1",
        1,
        5,
        0,
        "expected an expression after `=`, but the line ends",
        "a number",
    );
    check(
        "x = # nothing\ny = 1",
        1,
        14,
        0,
        "expected an expression after `=`, but the line ends",
        "a number",
    );
    check(
        "x = ; y = 1",
        1,
        5,
        1,
        "expected an expression after `=`, found `;`",
        "a number",
    );
    check(
        "x = a = b",
        1,
        7,
        1,
        "unexpected `=`",
        "separate them with `;`",
    );
    check("x = a, b", 1, 6, 1, "unexpected `,`", "commas separate");
    check(
        "x = 1: 2",
        1,
        6,
        1,
        "unexpected `:`",
        "`force COORD: expression`",
    );
    check(
        "3 = x",
        1,
        1,
        1,
        "a statement must start with a name or a keyword, found `3`",
        "`NAME = expression`",
    );
    check(
        "+ b",
        1,
        1,
        1,
        "a statement can't start with `+`",
        "end the previous line with the operator",
    );
    check(
        "a = 1\n  * b",
        2,
        3,
        1,
        "a statement can't start with `*`",
        "end the previous line",
    );
    check("x = 3\n)", 2, 1, 1, "unmatched `)`", "matching `(`");
    check("'x = 1", 1, 1, 1, "unexpected `'`", "a prime");
}

#[test]
fn roles_forces_and_declarations() {
    check(
        "kinetic 3 = x",
        1,
        9,
        1,
        "expected a name after `kinetic`, found `3`",
        "`kinetic NAME = expression`",
    );
    check(
        "kinetic",
        1,
        8,
        0,
        "expected a name after `kinetic`, but the file ends",
        "`kinetic = expression`",
    );
    check(
        "kinetic E 1/2*m",
        1,
        11,
        1,
        "expected `=` after `kinetic E`, found `1`",
        "`kinetic E = expression`",
    );
    check(
        "kinetic E",
        1,
        10,
        0,
        "expected `=` after `kinetic E`, but the file ends",
        "`kinetic E = expression`",
    );
    check(
        "rayleigh R: x",
        1,
        11,
        1,
        "expected `=` after `rayleigh R`, found `:`",
        "`rayleigh R = expression`",
    );
    check(
        "kinetic T =",
        1,
        11,
        1,
        "expected an expression after `=`, but the file ends",
        "a number",
    );
    check(
        "force th = 3",
        1,
        10,
        1,
        "expected `:` after `force th`, found `=`",
        "`force th: expression`",
    );
    check(
        "force 3: x",
        1,
        7,
        1,
        "expected a coordinate name after `force`, found `3`",
        "`force COORD: expression`",
    );
    check(
        "force: 3",
        1,
        6,
        1,
        "expected a coordinate name after `force`, found `:`",
        "`force COORD: expression`",
    );
    check(
        "force th:",
        1,
        9,
        1,
        "expected an expression after `:`, but the file ends",
        "a number",
    );
    check(
        "coordinates",
        1,
        1,
        11,
        "empty `coordinates` list",
        "`coordinates x, y`",
    );
    check(
        "parameters # none",
        1,
        1,
        10,
        "empty `parameters` list",
        "`parameters x, y`",
    );
    check(
        "coordinates 3",
        1,
        13,
        1,
        "expected a name after `coordinates`, found `3`",
        "`coordinates x, y`",
    );
    check(
        "coordinates x y",
        1,
        15,
        1,
        "expected `,` before `y`",
        "separate the names with commas",
    );
    check(
        "coordinates x,",
        1,
        15,
        0,
        "expected a name after `,`, but the file ends",
        "separated by commas",
    );
    check(
        "coordinates x,,y",
        1,
        15,
        1,
        "expected a name after `,`, found `,`",
        "separated by commas",
    );
    check(
        "parameters r:",
        1,
        14,
        0,
        "expected a dimension name after `r:`, but the file ends",
        "`r: length`",
    );
    check(
        "parameters m = 3",
        1,
        14,
        1,
        "a declaration can't have a value",
        "write a definition `m = …`",
    );
    check(
        "parameters m; x",
        1,
        16,
        0,
        "expected `=` after `x`, but the file ends",
        "`x = expression`",
    );
}

#[test]
fn parentheses() {
    check(
        "x = (a + b\ny = 3",
        1,
        5,
        1,
        "unclosed `(`",
        "add the matching `)`",
    );
    check(
        "x = f(a, b",
        1,
        6,
        1,
        "unclosed `(`",
        "add the matching `)`",
    );
    check("x = (a", 1, 5, 1, "unclosed `(`", "add the matching `)`");
    check(
        "y = 1 # ok (\nx = (a + # open\n  b\nz = 2",
        2,
        5,
        1,
        "unclosed `(`",
        "matching `)`",
    );
    check(
        "x = sin(a\nkinetic T = 3",
        1,
        8,
        1,
        "unclosed `(`",
        "matching `)`",
    );
    check("x = a)", 1, 6, 1, "unmatched `)`", "matching `(`");
    check("x = (a))", 1, 8, 1, "unmatched `)`", "matching `(`");
    check(
        "x = (a, b)",
        1,
        7,
        1,
        "expected `)`, found `,`",
        "the `(` at line 1, column 5 is still open",
    );
    check(
        "x = f(a; b)",
        1,
        8,
        1,
        "expected `,` or `)` after an argument of `f`, found `;`",
        "column 6 is still open",
    );
    check(
        "x = f(a,)",
        1,
        9,
        1,
        "expected an argument after `,`, found `)`",
        "remove the trailing `,`",
    );
    check(
        "x = f(,a)",
        1,
        7,
        1,
        "expected an argument of `f`, found `,`",
        "a number",
    );
    check(
        "x = ()",
        1,
        5,
        2,
        "empty parentheses `()`",
        "put an expression inside",
    );
    check(
        "x = ( = )",
        1,
        7,
        1,
        "expected an expression after `(`, found `=`",
        "a number",
    );
    check_expr("(a", 1, 1, 1, "unclosed `(`", "matching `)`");
    check_expr("a)", 1, 2, 1, "unmatched `)`", "matching `(`");
}

#[test]
fn operators() {
    check(
        "x = a ** b",
        1,
        7,
        2,
        "`**` is not an operator",
        "write powers with `^`",
    );
    check(
        "x = a +",
        1,
        7,
        1,
        "expected an expression after `+`, but the file ends",
        "remove the trailing `+`",
    );
    check(
        "x = a +\n\n# end\n",
        1,
        7,
        1,
        "expected an expression after `+`, but the file ends",
        "remove the trailing `+`",
    );
    check(
        "x = a /",
        1,
        7,
        1,
        "expected an expression after `/`, but the file ends",
        "remove the trailing `/`",
    );
    check(
        "x = 2^",
        1,
        6,
        1,
        "expected an expression after `^`, but the file ends",
        "remove the trailing `^`",
    );
    check(
        "x = -",
        1,
        5,
        1,
        "expected an expression after `-`, but the file ends",
        "remove the trailing `-`",
    );
    check(
        "x = 1 +* 2",
        1,
        8,
        1,
        "expected an expression after `+`, found `*`",
        "a number",
    );
    check(
        "a = 1\nb = 2\nc = 3 ^ ^ 2",
        3,
        9,
        1,
        "expected an expression after `^`, found `^`",
        "a number",
    );
    check(
        "x = a // b",
        1,
        8,
        1,
        "expected an expression after `/`, found `/`",
        "a number",
    );
    // a trailing operator makes the next line part of the expression
    check(
        "x = 2 ^\ny = 3",
        2,
        3,
        1,
        "unexpected `=`",
        "line 1 ends with `^`",
    );
    check(
        "x = a +  # c\nkinetic T = 3",
        2,
        9,
        1,
        "two expressions side by side",
        "line 1 ends with `+`",
    );
    check(
        "x = a *\n\ny = 3",
        3,
        3,
        1,
        "unexpected `=`",
        "remove the trailing `*`",
    );
}

#[test]
fn numbers() {
    check(
        "x = .5",
        1,
        5,
        2,
        "a number can't start with a decimal point",
        "write `0.5`",
    );
    check(
        "x = a*.25",
        1,
        7,
        3,
        "a number can't start with a decimal point",
        "write `0.25`",
    );
    check(
        "x = 1.2.3",
        1,
        5,
        5,
        "malformed number `1.2.3`",
        "at most one decimal point",
    );
    check(
        "x = 1.5e3.2",
        1,
        5,
        7,
        "malformed number `1.5e3.2`",
        "at most one decimal point",
    );
    check(
        "x = 3.x",
        1,
        5,
        2,
        "malformed number `3.`",
        "write `3.0` or `3`",
    );
    check(
        "x = 3.",
        1,
        5,
        2,
        "malformed number `3.`",
        "write `3.0` or `3`",
    );
    check("x = a..b", 1, 6, 1, "unexpected `.`", "inside a number");
    check(
        "x = 1e99999",
        1,
        6,
        6,
        "exponent out of range",
        "up to 1000",
    );
    check(
        "x = 1e-1001",
        1,
        6,
        6,
        "exponent out of range",
        "up to 1000",
    );
    check(
        "x = 2'",
        1,
        6,
        1,
        "a prime `'` (time derivative) can't follow a number",
        "`(2*x)'`",
    );
    check(
        "x = 30deg'",
        1,
        10,
        1,
        "a prime `'` (time derivative) can't follow a number",
        "names, calls",
    );
    check("x = a°", 1, 6, 1, "unexpected `°`", "`30°`");
}

#[test]
fn parse_expr_errors() {
    check_expr(
        "",
        1,
        1,
        0,
        "expected an expression, but the file ends",
        "a number",
    );
    check_expr(
        "  \n ",
        2,
        2,
        0,
        "expected an expression, but the file ends",
        "a number",
    );
    check_expr("x = 1", 1, 3, 1, "unexpected `=`", "`;`");
    check_expr(
        "a +",
        1,
        3,
        1,
        "expected an expression after `+`, but the file ends",
        "trailing `+`",
    );
    check_expr(
        ")",
        1,
        1,
        1,
        "expected an expression, found `)`",
        "a number",
    );
}

#[test]
fn nesting_limits() {
    let n = MAX_NESTING as usize;
    // parentheses: the top-level expression is one level, each group one more
    let ok = format!("x = {}1{}", "(".repeat(n - 1), ")".repeat(n - 1));
    assert!(parse_scene(&ok).is_ok());
    let deep = format!("x = {}1{}", "(".repeat(n), ")".repeat(n));
    check(
        &deep,
        1,
        5 + n,
        1,
        "expression nested too deeply (more than 200 levels)",
        "split it",
    );
    let huge = format!("x = {}1{}", "(".repeat(100_000), ")".repeat(100_000));
    check(
        &huge,
        1,
        5 + n,
        1,
        "expression nested too deeply (more than 200 levels)",
        "split it",
    );
    // calls, unary signs and power towers
    let calls = format!("x = {}1{}", "f(".repeat(50_000), ")".repeat(50_000));
    assert_eq!(
        scene_err(&calls).message,
        "expression nested too deeply (more than 200 levels)"
    );
    let signs = format!("x = {}x", "-".repeat(100_000));
    assert_eq!(
        scene_err(&signs).message,
        "expression nested too deeply (more than 200 levels)"
    );
    let tower = format!("x = 2{}", "^2".repeat(100_000));
    assert_eq!(
        scene_err(&tower).message,
        "expression nested too deeply (more than 200 levels)"
    );
    let unclosed = "(".repeat(100_000);
    assert!(parse_expr(&unclosed).is_err());
    assert!(parse_scene(&format!("x = {unclosed}")).is_err());
}

#[test]
fn depth_limit_on_long_chains() {
    let n = MAX_DEPTH as usize;
    // `1+1+…+1` with n terms has depth n
    let ok = format!("x = 1{}", "+1".repeat(n - 1));
    assert!(parse_scene(&ok).is_ok());
    let deep = format!("x = 1{}", "+1".repeat(n));
    check(
        &deep,
        1,
        4 + 2 * n + 1,
        1,
        "expression too deep (more than 1000 levels)",
        "split it",
    );
    let huge = format!("x = 1{}", "*x".repeat(200_000));
    assert_eq!(
        scene_err(&huge).message,
        "expression too deep (more than 1000 levels)"
    );
    // many primes are one node
    let primes = format!("x = y{}", "'".repeat(10_000));
    assert!(parse_scene(&primes).is_ok());
}

#[test]
fn rendered_error() {
    let src = "m = 1\nx = 3 $ 4\n";
    let d = parse_scene(src).unwrap_err();
    assert_eq!(
        d.render("scene.qd", src),
        "error: unknown character `$`\n --> scene.qd:2:7\n  |\n2 | x = 3 $ 4\n  |       ^\n  = hint: this character is not part of the .qd language\n"
    );
    let at = locate(src, &d);
    assert_eq!((at.line, at.col), (2, 7));
}

#[test]
fn vectors() {
    check(
        "x = []",
        1,
        5,
        2,
        "a vector needs at least one component",
        "like `[x, y]`",
    );
    check(
        "x = [ # nothing\n ]",
        1,
        5,
        14,
        "a vector needs at least one component",
        "like `[x, y]`",
    );
    check(
        "x = [a,]",
        1,
        8,
        1,
        "expected a component after `,`, found `]`",
        "remove the trailing `,`",
    );
    check(
        "x = [a,\n]",
        2,
        1,
        1,
        "expected a component after `,`, found `]`",
        "remove the trailing `,`",
    );
    check(
        "x = [a,,b]",
        1,
        8,
        1,
        "expected a component after `,`, found `,`",
        "a number",
    );
    check(
        "x = [,a]",
        1,
        6,
        1,
        "expected an expression after `[`, found `,`",
        "a number",
    );
    check("x = [a", 1, 5, 1, "unclosed `[`", "add the matching `]`");
    check("x = [a,", 1, 5, 1, "unclosed `[`", "add the matching `]`");
    check(
        "x = [a,\n  b\ny = 3",
        1,
        5,
        1,
        "unclosed `[`",
        "inside brackets a line break does not end the statement",
    );
    check(
        "x = [a; b]",
        1,
        7,
        1,
        "expected `,` or `]` after a component of the vector, found `;`",
        "the `[` at line 1, column 5 is still open",
    );
    check(
        "x = [a)",
        1,
        7,
        1,
        "expected `,` or `]` after a component of the vector, found `)`",
        "column 5 is still open",
    );
    check(
        "x = (a]",
        1,
        7,
        1,
        "expected `)`, found `]`",
        "the `(` at line 1, column 5 is still open",
    );
    check("x = a]", 1, 6, 1, "unmatched `]`", "add the matching `[`");
    check("x = [a]]", 1, 8, 1, "unmatched `]`", "add the matching `[`");
    check(
        "x = [a b]",
        1,
        8,
        1,
        "two expressions side by side",
        "did you mean `a*b`?",
    );
    check(
        "x = f[1]",
        1,
        6,
        3,
        "two expressions side by side",
        "did you mean `f*[1]`?",
    );
    check(
        "x = 2[a]",
        1,
        6,
        3,
        "two expressions side by side",
        "did you mean `2*[a]`?",
    );
    check(
        "[a] = 3",
        1,
        1,
        1,
        "a statement must start with a name or a keyword, found `[`",
        "`NAME = expression`",
    );
    check(
        "x = [a, b\n  c]",
        2,
        3,
        1,
        "two expressions side by side",
        "is a `)` missing",
    );
    check_expr("[a", 1, 1, 1, "unclosed `[`", "matching `]`");
    check_expr(
        "[]",
        1,
        1,
        2,
        "a vector needs at least one component",
        "`[x, y]`",
    );
}

#[test]
fn braces_outside_solve_blocks() {
    check(
        "x = {a}",
        1,
        5,
        1,
        "expected an expression after `=`, found `{`",
        "a number",
    );
    check("x = 1 {", 1, 7, 1, "unexpected `{`", "`solve x, y { … }`");
    check("{ x = 1 }", 1, 1, 1, "unexpected `{`", "solve block");
    check("x = 1 }", 1, 7, 1, "unmatched `}`", "open a solve block");
    check("x = 1\n}", 2, 1, 1, "unmatched `}`", "open a solve block");
    check_expr("a }", 1, 3, 1, "unmatched `}`", "solve block");
}

#[test]
fn loads_and_torques() {
    check(
        "load at P",
        1,
        6,
        2,
        "expected a force after `load`, found `at`",
        "the force is missing before `at` (for a name `at`, write `(at)`)",
    );
    check(
        "load at",
        1,
        6,
        2,
        "expected a force after `load`, found `at`",
        "the force is missing before `at`",
    );
    check(
        "load 2at P",
        1,
        10,
        1,
        "expected `at` after the force in `load F at P`, found `P`",
        "`2at` is an implicit product, write a space before `at`",
    );
    check(
        "load F + 1.5at P",
        1,
        16,
        1,
        "expected `at` after the force in `load F at P`, found `P`",
        "`1.5at` is an implicit product",
    );
    check(
        "load",
        1,
        1,
        4,
        "expected a force after `load`, but the file ends",
        "to define a name `load`, write `load = expression`",
    );
    check(
        "load\nx = 1",
        1,
        5,
        0,
        "expected a force after `load`, but the line ends",
        "`load [0, -m*g] at [x, y]`",
    );
    check(
        "load; x = 1",
        1,
        5,
        1,
        "expected a force after `load`, found `;`",
        "`load F at P`",
    );
    check(
        "load F P",
        1,
        8,
        1,
        "expected `at` after the force in `load F at P`, found `P`",
        "the force F, then `at` and the point P it acts on",
    );
    check(
        "load F",
        1,
        7,
        0,
        "expected `at` after the force in `load F at P`, but the file ends",
        "then `at`",
    );
    check(
        "load F\n  at P",
        1,
        7,
        0,
        "expected `at` after the force in `load F at P`, but the line ends",
        "then `at`",
    );
    check(
        "load [0, -g] [x, y]",
        1,
        14,
        1,
        "expected `at` after the force in `load F at P`, found `[`",
        "then `at`",
    );
    check(
        "load(x) = 3",
        1,
        9,
        1,
        "expected `at` after the force in `load F at P`, found `=`",
        "to define a name `load`, write `load = expression`",
    );
    check(
        "load F at(P)",
        1,
        8,
        2,
        "expected `at` after the force in `load F at P`, found `at`",
        "directly before `(`, `at` is a call: write a space, `at (…)`",
    );
    check(
        "load F at",
        1,
        8,
        2,
        "expected a point after `at`, but the file ends",
        "`load [0, -m*g] at [x, y]`",
    );
    check(
        "load F at # where?\nx = 1",
        1,
        19,
        0,
        "expected a point after `at`, but the line ends",
        "`load F at P`",
    );
    check(
        "load F at = 3",
        1,
        11,
        1,
        "expected a point after `at`, found `=`",
        "`load F at P`",
    );
    check(
        "load F at P at Q",
        1,
        13,
        2,
        "two expressions side by side",
        "`P*at`",
    );
    // inside brackets `at` is a name
    check(
        "load [F at P]",
        1,
        9,
        2,
        "two expressions side by side",
        "`F*at`",
    );
    check(
        "torque on q",
        1,
        8,
        2,
        "expected a moment after `torque`, found `on`",
        "the moment is missing before `on`",
    );
    check(
        "torque",
        1,
        1,
        6,
        "expected a moment after `torque`, but the file ends",
        "to define a name `torque`, write `torque = expression`",
    );
    check(
        "torque M at q",
        1,
        10,
        2,
        "expected `on` after the moment in `torque M on phi`, found `at`",
        "the moment M, then `on` and the angle phi it turns",
    );
    check(
        "torque M",
        1,
        9,
        0,
        "expected `on` after the moment in `torque M on phi`, but the file ends",
        "then `on`",
    );
    check(
        "torque M on",
        1,
        10,
        2,
        "expected an angle after `on`, but the file ends",
        "`torque -c*phi' on phi`",
    );
}

#[test]
fn solve_blocks() {
    check(
        "solve x { }",
        1,
        9,
        3,
        "empty solve block",
        "write the equations inside the braces",
    );
    check(
        "solve x {}",
        1,
        9,
        2,
        "empty solve block",
        "`solve x { a*x = b }`",
    );
    check(
        "solve x { ;; }",
        1,
        9,
        6,
        "empty solve block",
        "separated by `;`",
    );
    check(
        "solve x {\n  # nothing yet\n}",
        1,
        9,
        1,
        "empty solve block",
        "one per line",
    );
    check(
        "solve x {\n  a = b",
        1,
        9,
        1,
        "unclosed `{`",
        "add the matching `}` after the last equation",
    );
    check("solve x { a = b", 1, 9, 1, "unclosed `{`", "matching `}`");
    check("solve x {", 1, 9, 1, "unclosed `{`", "matching `}`");
    check("solve x {\n\n", 1, 9, 1, "unclosed `{`", "matching `}`");
    // the open block swallowed the following statements
    check(
        "solve x {\n  a = b\nkinetic T = 3",
        1,
        9,
        1,
        "unclosed `{`",
        "matching `}`",
    );
    check(
        "m = 1\nsolve x {\n  x = 1\nsolve y {\n  y = 2\n}",
        2,
        9,
        1,
        "unclosed `{`",
        "matching `}`",
    );
    // an unclosed `(` inside a closed block is the `(`
    check(
        "solve x {\n  a = (b\n}",
        2,
        7,
        1,
        "unclosed `(`",
        "matching `)`",
    );
    check(
        "solve x { a + b }",
        1,
        11,
        5,
        "an equation needs `=`",
        "write it as `lhs = rhs`, like `a + b = 0`",
    );
    check(
        "solve x {\n  m*x'' + k*x\n}",
        2,
        3,
        11,
        "an equation needs `=`",
        "like `m*x'' + k*x = 0`",
    );
    check(
        "solve x { a = 1; b }",
        1,
        18,
        1,
        "an equation needs `=`",
        "like `b = 0`",
    );
    check(
        "solve x { a = b = c }",
        1,
        17,
        1,
        "an equation has exactly one `=`",
        "separate them with `;`",
    );
    check(
        "solve x { a : b }",
        1,
        13,
        1,
        "expected `=` after the left side of the equation, found `:`",
        "`lhs = rhs`",
    );
    check(
        "solve x { = 3 }",
        1,
        11,
        1,
        "expected an expression before `=`, found `=`",
        "`lhs = rhs`",
    );
    check(
        "solve x { * 3 = 1 }",
        1,
        11,
        1,
        "expected an equation, found `*`",
        "`lhs = rhs`",
    );
    check(
        "solve x { a = }",
        1,
        15,
        1,
        "expected an expression after `=`, found `}`",
        "a number",
    );
    check(
        "solve x { a = 1, b = 2 }",
        1,
        16,
        1,
        "expected `;`, a line break or `}` after the equation, found `,`",
        "separate them with `;`",
    );
    check(
        "solve x { a = 1) }",
        1,
        16,
        1,
        "unmatched `)`",
        "matching `(`",
    );
    check(
        "solve x {\n  a = b +\n}",
        3,
        1,
        1,
        "expected an expression after `+`, found `}`",
        "line 2 ends with `+`",
    );
    check(
        "solve { x = 1 }",
        1,
        7,
        1,
        "expected the unknowns after `solve`, found `{`",
        "`solve x, y { … }`",
    );
    check(
        "solve",
        1,
        6,
        0,
        "expected the unknowns after `solve`, but the file ends",
        "to define a name `solve`, write `solve = expression`",
    );
    check(
        "solve 3 { x = 1 }",
        1,
        7,
        1,
        "expected the unknowns after `solve`, found `3`",
        "name the unknowns",
    );
    check(
        "solve x",
        1,
        8,
        0,
        "expected `{` after the unknowns of `solve`, but the file ends",
        "braces that open on the `solve` line",
    );
    check(
        "solve x\n{ x = 1 }",
        1,
        8,
        0,
        "expected `{` after the unknowns of `solve`, but the line ends",
        "braces that open on the `solve` line",
    );
    check(
        "solve x = 3",
        1,
        9,
        1,
        "expected `{` after the unknowns of `solve`, found `=`",
        "`solve x, y { … }`",
    );
    check(
        "solve x y { x = 1 }",
        1,
        9,
        1,
        "expected `,` before `y`",
        "separate the unknowns with commas",
    );
    check(
        "solve x, { x = 1 }",
        1,
        10,
        1,
        "expected a name after `,`, found `{`",
        "list the unknowns separated by commas",
    );
    check(
        "solve x { x = 1 } y = 2",
        1,
        19,
        1,
        "expected the end of the line after `}`, found `y`",
        "start the next statement on a new line",
    );
    check(
        "solve x { x = 1 }}",
        1,
        18,
        1,
        "unmatched `}`",
        "open a solve block",
    );
    check(
        "solve x { x = 1 }\n}",
        2,
        1,
        1,
        "unmatched `}`",
        "open a solve block",
    );
}

#[test]
fn nesting_limits_of_vectors() {
    let n = MAX_NESTING as usize;
    let ok = format!("x = {}1{}", "[".repeat(n - 1), "]".repeat(n - 1));
    assert!(parse_scene(&ok).is_ok());
    let deep = format!("x = {}1{}", "[".repeat(n), "]".repeat(n));
    check(
        &deep,
        1,
        5 + n,
        1,
        "expression nested too deeply (more than 200 levels)",
        "split it",
    );
    let huge = format!("x = {}1{}", "[".repeat(100_000), "]".repeat(100_000));
    check(
        &huge,
        1,
        5 + n,
        1,
        "expression nested too deeply (more than 200 levels)",
        "split it",
    );
    let mixed = format!("x = {}1{}", "[(".repeat(50_000), ")]".repeat(50_000));
    assert_eq!(
        scene_err(&mixed).message,
        "expression nested too deeply (more than 200 levels)"
    );
    let unclosed = "[".repeat(100_000);
    assert!(parse_expr(&unclosed).is_err());
    assert!(parse_scene(&format!("x = {unclosed}")).is_err());
    assert!(parse_scene(&format!("load {unclosed}")).is_err());
    assert!(parse_scene(&format!("solve x {{ {unclosed}")).is_err());
    // long vectors are flat: many components are one level
    let long = format!("x = [{}]", vec!["a"; 10_000].join(", "));
    assert!(parse_scene(&long).is_ok());
    // many equations are fine too
    let eqs = format!("solve x {{\n{}}}", "x = 1\n".repeat(10_000));
    assert!(parse_scene(&eqs).is_ok());
}

// ---------------------------------------------------------------- latex

fn latex_error(src: &str) -> (String, usize, usize, String) {
    let d = qdot::parse::parse_scene(src).expect_err("an error");
    let span = d.span.expect("a position");
    let (line, col) = qdot::Diagnostic::line_col(src, span.start);
    (d.message, line, col, d.hint.unwrap_or_default())
}

#[test]
fn latex_statement_errors() {
    let (m, l, c, h) = latex_error("latex x = 3");
    assert_eq!(
        (m.as_str(), l, c),
        ("expected a string in double quotes, found `3`", 1, 11)
    );
    assert_eq!(
        h,
        "write the notation in double quotes: `latex x = \"\\vartheta_{3}\"`"
    );
    let (m, l, c, h) = latex_error("latex x = \"abc\ny = 1");
    assert_eq!(
        (m.as_str(), l, c),
        ("this string is not closed on its line", 1, 11)
    );
    assert_eq!(h, "end the string with `\"` before the end of the line");
    let (m, _, c, _) = latex_error("latex x = \"abc");
    assert_eq!(
        (m.as_str(), c),
        ("this string is not closed on its line", 11)
    );
    let (m, _, c, _) = latex_error("latex x = \"\"");
    assert_eq!((m.as_str(), c), ("empty LaTeX notation", 11));
    let (m, _, c, _) = latex_error("latex 3");
    assert_eq!(
        (m.as_str(), c),
        ("expected a name after `latex`, found `3`", 7)
    );
    let (m, _, c, _) = latex_error("latex x");
    assert_eq!(c, 8);
    assert!(m.starts_with("expected `=` after `latex x`"), "{m}");
    let (m, _, _, _) = latex_error("latex x = \"X\" y");
    assert!(!m.is_empty());
}

/// The echoed source line: an invisible character shows as `�` (one
/// character for one, so the caret stays under its column), but a tab and
/// the `\r` of a CRLF line end are printed as they are.
#[test]
fn the_echoed_line_shows_invisible_characters() {
    let src = "x = 1\r\ny =\t3 \u{200B} 4\r\n";
    let d = parse_scene(src).unwrap_err();
    assert_eq!(
        d.render("scene.qd", src),
        "error: unknown character U+200B (ZERO WIDTH SPACE), which is invisible\n --> scene.qd:2:7\n  |\n2 | y =\t3 \u{FFFD} 4\r\n  |    \t  ^\n  = hint: delete it (invisible characters often come with text pasted from a web page or a word processor)\n"
    );
}
