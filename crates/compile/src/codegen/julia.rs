//! Julia: the in-place form of DifferentialEquations.jl, `f!(du, u, p, t)`
//! with the parameters a tuple (or vector) `p` in the header's order;
//! arrays are 1-based; `sincos` for sin and cos of one argument.

use super::ir::Fun;
use super::render::{shortest, Context, Function, Kind, Syntax, Uses};

/// Julia's keywords, the functions the code calls and its own names.
pub(super) const RESERVED: &[&str] = &[
    "baremodule",
    "begin",
    "break",
    "catch",
    "const",
    "continue",
    "do",
    "else",
    "elseif",
    "end",
    "export",
    "false",
    "finally",
    "for",
    "function",
    "global",
    "if",
    "import",
    "let",
    "local",
    "macro",
    "module",
    "quote",
    "return",
    "struct",
    "true",
    "try",
    "using",
    "while",
    "abstract",
    "mutable",
    "primitive",
    "type",
    "where",
    "outer",
    "in",
    "isa",
    "sin",
    "cos",
    "sincos",
    "exp",
    "log",
    "sqrt",
    "atan",
    "asin",
    "acos",
    "error",
    "NaN",
    "Inf",
    "fill",
    "nothing",
    "t",
    "y",
    "q",
    "p",
    "dy",
    "mass",
    "forcing",
];

pub(super) struct Julia;

impl Syntax for Julia {
    fn lit(&self, x: f64) -> String {
        if x.is_nan() {
            "NaN".into()
        } else if x.is_infinite() {
            if x > 0.0 { "Inf" } else { "(-Inf)" }.into()
        } else {
            shortest(x)
        }
    }

    fn call(&self, f: Fun, arg: &str) -> String {
        let name = f.libm_name();
        format!("{name}({arg})")
    }

    fn signature(&self, _cx: &Context, f: &Function) -> String {
        match f.kind {
            Kind::Energy => format!("{}(y, p, t)", f.name),
            k => format!("{}!({}, {}, p, t)", f.name, k.output(), k.input()),
        }
    }

    fn open(&self, cx: &Context, f: &Function, _uses: &Uses) -> String {
        let mut s = format!("function {}\n", self.signature(cx, f));
        match cx.params.len() {
            0 => {}
            1 => s.push_str(&format!("    {}, = p\n", cx.params[0])),
            _ => s.push_str(&format!("    {} = p\n", cx.params.join(", "))),
        }
        s
    }

    fn bind(&self, name: &str, array: &str, index: usize) -> String {
        format!("    {name} = {array}[{}]\n", index + 1)
    }

    fn let_(&self, name: &str, value: &str) -> String {
        format!("    {name} = {value}\n")
    }

    fn sin_cos(&self, sin: &str, cos: &str, arg: &str) -> String {
        format!("    {sin}, {cos} = sincos({arg})\n")
    }

    fn pivot(&self, _cx: &Context, _f: &Function, value: &str, column: usize) -> String {
        format!(
            "    if !({value} > 0.0)\n        error(\"the mass matrix is not positive definite (column {})\")\n    end\n",
            column + 1
        )
    }

    fn finish(&self, cx: &Context, f: &Function, outs: &[String]) -> String {
        let mut s = String::new();
        match f.kind {
            Kind::Energy => s.push_str(&format!("    return {}\n", outs[0])),
            Kind::Mass => {
                for (k, o) in outs.iter().enumerate() {
                    s.push_str(&format!(
                        "    mass[{}, {}] = {o}\n",
                        k / cx.n + 1,
                        k % cx.n + 1
                    ));
                }
                s.push_str("    return nothing\n");
            }
            k => {
                for (i, o) in outs.iter().enumerate() {
                    s.push_str(&format!("    {}[{}] = {o}\n", k.output(), i + 1));
                }
                s.push_str("    return nothing\n");
            }
        }
        s.push_str("end\n");
        s
    }
}
