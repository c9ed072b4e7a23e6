//! Python 3: scalar code on the `math` module, a list returned (the mass
//! matrix a list of rows); no NumPy needed, and what it returns is what
//! `scipy.integrate.solve_ivp(fun, …, args=(…))` expects.

use super::ir::Fun;
use super::render::{param_list, shortest, Context, Function, Kind, Syntax, Uses};

/// Python's keywords and the code's own names.
pub(super) const RESERVED: &[&str] = &[
    "False",
    "None",
    "True",
    "and",
    "as",
    "assert",
    "async",
    "await",
    "break",
    "class",
    "continue",
    "def",
    "del",
    "elif",
    "else",
    "except",
    "finally",
    "for",
    "from",
    "global",
    "if",
    "import",
    "in",
    "is",
    "lambda",
    "nonlocal",
    "not",
    "or",
    "pass",
    "raise",
    "return",
    "try",
    "while",
    "with",
    "yield",
    "match",
    "case",
    "type",
    "math",
    "ValueError",
    "t",
    "y",
    "q",
];

pub(super) struct Python;

impl Syntax for Python {
    fn lit(&self, x: f64) -> String {
        if x.is_nan() {
            "math.nan".into()
        } else if x.is_infinite() {
            if x > 0.0 { "math.inf" } else { "(-math.inf)" }.into()
        } else {
            shortest(x)
        }
    }

    fn call(&self, f: Fun, arg: &str) -> String {
        let name = f.libm_name();
        format!("math.{name}({arg})")
    }

    fn signature(&self, cx: &Context, f: &Function) -> String {
        let params = param_list(cx, &|p| p.to_string());
        format!("def {}(t, {}{params})", f.name, f.kind.input())
    }

    fn open(&self, cx: &Context, f: &Function, _uses: &Uses) -> String {
        format!("{}:\n", self.signature(cx, f))
    }

    fn bind(&self, name: &str, array: &str, index: usize) -> String {
        format!("    {name} = {array}[{index}]\n")
    }

    fn let_(&self, name: &str, value: &str) -> String {
        format!("    {name} = {value}\n")
    }

    fn sin_cos(&self, sin: &str, cos: &str, arg: &str) -> String {
        format!("    {sin} = math.sin({arg}); {cos} = math.cos({arg})\n")
    }

    fn pivot(&self, _cx: &Context, _f: &Function, value: &str, column: usize) -> String {
        format!(
            "    if not {value} > 0.0:\n        raise ValueError(\"the mass matrix is not positive definite (column {column})\")\n"
        )
    }

    fn finish(&self, cx: &Context, f: &Function, outs: &[String]) -> String {
        match f.kind {
            Kind::Energy => format!("    return {}\n", outs[0]),
            Kind::Mass => {
                let rows: Vec<String> = outs
                    .chunks(cx.n)
                    .map(|r| format!("[{}]", r.join(", ")))
                    .collect();
                format!("    return [{}]\n", rows.join(", "))
            }
            _ => format!("    return [{}]\n", outs.join(", ")),
        }
    }
}
