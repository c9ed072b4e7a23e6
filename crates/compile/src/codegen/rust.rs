//! Rust: `let` locals, fixed-size arrays in and out (no allocation),
//! `.sin_cos()` for sin and cos of one argument.

use super::ir::Fun;
use super::render::{param_list, shortest, Context, Function, Kind, Syntax, Uses};

/// Rust's keywords (strict and reserved), the prelude's value names and the
/// code's own names.
pub(super) const RESERVED: &[&str] = &[
    "as", "break", "const", "continue", "crate", "else", "enum", "extern", "false", "fn", "for",
    "if", "impl", "in", "let", "loop", "match", "mod", "move", "mut", "pub", "ref", "return",
    "self", "Self", "static", "struct", "super", "trait", "true", "type", "unsafe", "use", "where",
    "while", "async", "await", "dyn", "abstract", "become", "box", "do", "final", "macro",
    "override", "priv", "typeof", "unsized", "virtual", "yield", "try", "gen", "union", "f64",
    "usize", "Ok", "Err", "Some", "None", "t", "y", "q", "dy", "mass", "forcing",
];

pub(super) struct Rust;

impl Syntax for Rust {
    fn lit(&self, x: f64) -> String {
        if x.is_nan() {
            "f64::NAN".into()
        } else if x.is_infinite() {
            if x > 0.0 {
                "f64::INFINITY"
            } else {
                "f64::NEG_INFINITY"
            }
            .into()
        } else {
            shortest(x)
        }
    }

    fn call(&self, f: Fun, arg: &str) -> String {
        let name = match f {
            Fun::Ln => "ln",
            f => f.libm_name(),
        };
        if arg.starts_with(|c: char| c.is_ascii_digit() || c == '(') {
            format!("f64::{name}({arg})")
        } else {
            format!("{arg}.{name}()")
        }
    }

    fn signature(&self, cx: &Context, f: &Function) -> String {
        let params = param_list(cx, &|p| format!("{p}: f64"));
        let input = format!("{}: &[f64; {}]", f.kind.input(), cx.input_len(f.kind));
        let (out, ret) = match f.kind {
            Kind::Rhs => (
                format!(", dy: &mut [f64; {}]", 2 * cx.n),
                " -> Result<(), usize>",
            ),
            Kind::Mass => (format!(", mass: &mut [f64; {}]", cx.n * cx.n), ""),
            Kind::Forcing => (format!(", forcing: &mut [f64; {}]", cx.n), ""),
            Kind::Energy => (String::new(), " -> f64"),
        };
        format!("pub fn {}(t: f64, {input}{params}{out}){ret}", f.name)
    }

    fn open(&self, cx: &Context, f: &Function, _uses: &Uses) -> String {
        format!(
            "#[allow(unused_variables, non_snake_case, clippy::too_many_arguments, clippy::approx_constant)]\n{} {{\n",
            self.signature(cx, f)
        )
    }

    fn bind(&self, name: &str, array: &str, index: usize) -> String {
        format!("    let {name} = {array}[{index}];\n")
    }

    fn let_(&self, name: &str, value: &str) -> String {
        format!("    let {name} = {value};\n")
    }

    fn sin_cos(&self, sin: &str, cos: &str, arg: &str) -> String {
        format!("    let ({sin}, {cos}) = {}.sin_cos();\n", arg)
    }

    fn pivot(&self, _cx: &Context, _f: &Function, value: &str, column: usize) -> String {
        format!(
            "    if {value}.is_nan() || {value} <= 0.0 {{\n        // M is not positive definite\n        dy.fill(f64::NAN);\n        return Err({column});\n    }}\n"
        )
    }

    fn finish(&self, _cx: &Context, f: &Function, outs: &[String]) -> String {
        let mut s = String::new();
        if f.kind == Kind::Energy {
            s.push_str(&format!("    {}\n}}\n", outs[0]));
            return s;
        }
        for (k, o) in outs.iter().enumerate() {
            s.push_str(&format!("    {}[{k}] = {o};\n", f.kind.output()));
        }
        if f.kind == Kind::Rhs {
            s.push_str("    Ok(())\n");
        }
        s.push_str("}\n");
        s
    }
}
