//! C99: `const double` locals, `<math.h>`; sin and cos of one argument
//! as two calls on one local, which GCC and Clang merge into one `sincos`
//! at -O1 and above.

use super::ir::Fun;
use super::render::{param_list, shortest, Context, Function, Kind, Syntax, Uses};

/// Keywords of C99 and the names of `<math.h>` the code calls or defines.
pub(super) const RESERVED: &[&str] = &[
    "auto",
    "break",
    "case",
    "char",
    "const",
    "continue",
    "default",
    "do",
    "double",
    "else",
    "enum",
    "extern",
    "float",
    "for",
    "goto",
    "if",
    "inline",
    "int",
    "long",
    "register",
    "restrict",
    "return",
    "short",
    "signed",
    "sizeof",
    "static",
    "struct",
    "switch",
    "typedef",
    "union",
    "unsigned",
    "void",
    "volatile",
    "while",
    "_Bool",
    "_Complex",
    "_Imaginary",
    "sin",
    "cos",
    "tan",
    "exp",
    "log",
    "sqrt",
    "atan",
    "asin",
    "acos",
    "sincos",
    "pow",
    "fabs",
    "NAN",
    "INFINITY",
    "main",
    "k",
    "t",
    "y",
    "q",
    "dy",
    "mass",
    "forcing",
];

/// Whether a name may be a macro where the generated C is compiled, so
/// that a local of that name would not compile (`const double M_E = …`
/// expands M_E to a number): the names `<math.h>` and GCC define as
/// macros, by their families (`M_PI`, `FP_NAN`, `MATH_ERRNO`, …), and the
/// names C reserves to the implementation (`_X…`, `__…`).
pub(super) fn may_be_a_macro(name: &str) -> bool {
    const MACROS: &[&str] = &[
        "HUGE_VAL",
        "HUGE_VALF",
        "HUGE_VALL",
        "math_errhandling",
        "fpclassify",
        "isfinite",
        "isinf",
        "isnan",
        "isnormal",
        "signbit",
        "isgreater",
        "isgreaterequal",
        "isless",
        "islessequal",
        "islessgreater",
        "isunordered",
        "errno",
        "unix",
        "linux",
        "i386",
    ];
    let reserved_underscore = name.starts_with("__")
        || name
            .strip_prefix('_')
            .is_some_and(|r| r.starts_with(|c: char| c.is_ascii_uppercase()));
    MACROS.contains(&name)
        || ["M_", "FP_", "MATH_"].iter().any(|p| name.starts_with(p))
        || reserved_underscore
}

pub(super) struct C;

impl Syntax for C {
    fn lit(&self, x: f64) -> String {
        if x.is_nan() {
            "NAN".into()
        } else if x.is_infinite() {
            if x > 0.0 { "INFINITY" } else { "(-INFINITY)" }.into()
        } else {
            shortest(x)
        }
    }

    fn call(&self, f: Fun, arg: &str) -> String {
        let name = f.libm_name();
        format!("{name}({arg})")
    }

    fn signature(&self, cx: &Context, f: &Function) -> String {
        let params = param_list(cx, &|p| format!("double {p}"));
        let (ret, out) = match f.kind {
            Kind::Rhs => ("int", ", double *dy"),
            Kind::Mass => ("void", ", double *mass"),
            Kind::Forcing => ("void", ", double *forcing"),
            Kind::Energy => ("double", ""),
        };
        format!(
            "{ret} {}(double t, const double *{}{params}{out})",
            f.name,
            f.kind.input()
        )
    }

    fn open(&self, cx: &Context, f: &Function, uses: &Uses) -> String {
        let mut s = format!("{}\n{{\n", self.signature(cx, f));
        if !uses.time {
            s.push_str("    (void)t;\n");
        }
        if !uses.state.iter().any(|&u| u) {
            s.push_str(&format!("    (void){};\n", f.kind.input()));
        }
        for (p, used) in cx.params.iter().zip(&uses.params) {
            if !used {
                s.push_str(&format!("    (void){p};\n"));
            }
        }
        s
    }

    fn bind(&self, name: &str, array: &str, index: usize) -> String {
        format!("    const double {name} = {array}[{index}];\n")
    }

    fn let_(&self, name: &str, value: &str) -> String {
        format!("    const double {name} = {value};\n")
    }

    fn sin_cos(&self, sin: &str, cos: &str, arg: &str) -> String {
        format!("    const double {sin} = sin({arg}), {cos} = cos({arg});\n")
    }

    fn pivot(&self, cx: &Context, _f: &Function, value: &str, column: usize) -> String {
        format!(
            "    if (!({value} > 0.0)) {{ /* M is not positive definite */\n        for (int k = 0; k < {}; k++) dy[k] = NAN;\n        return {};\n    }}\n",
            2 * cx.n,
            column + 1
        )
    }

    fn finish(&self, _cx: &Context, f: &Function, outs: &[String]) -> String {
        let mut s = String::new();
        if f.kind == Kind::Energy {
            s.push_str(&format!("    return {};\n}}\n", outs[0]));
            return s;
        }
        for (k, o) in outs.iter().enumerate() {
            s.push_str(&format!("    {}[{k}] = {o};\n", f.kind.output()));
        }
        if f.kind == Kind::Rhs {
            s.push_str("    return 0;\n");
        }
        s.push_str("}\n");
        s
    }
}
