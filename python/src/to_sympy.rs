//! An expression of qdot's syntax as the source of a SymPy constructor.
//!
//! The text calls five builders the Python side defines (`qdot/_sympy.py`):
//! `N_(name, order)` a name with `order` primes, `R_(p, q)` an exact
//! rational (digits as strings: any size), `A_(…)` a sum, `M_(…)` a
//! product, `P_(base, exp)` a power, `F_(name, arg…)` a function call,
//! `V_(x…)` a vector. Sums and products are flattened, so the nesting of
//! the text is that of the parentheses of the input, which the parser
//! bounds, not the number of terms (CPython refuses ~200 nested calls).

use num_traits::Signed;
use qdot::parse::ast::{BinOp, Expr, ExprKind};

/// The SymPy source of `e`, or why it has none.
pub fn of(e: &Expr) -> Result<String, String> {
    let mut out = String::new();
    write(e, &mut out)?;
    Ok(out)
}

/// The operands of the chain of `op` (and its inverse) at `e`, each with
/// whether it is inverted (subtracted, divided); walked iteratively down
/// the left spine, where a long sum's depth is.
fn chain(e: &Expr, add: bool) -> Vec<(&Expr, bool)> {
    let (op, inv) = if add {
        (BinOp::Add, BinOp::Sub)
    } else {
        (BinOp::Mul, BinOp::Div)
    };
    let mut out = Vec::new();
    let mut cur = e;
    while let ExprKind::Bin(o, l, r) = &cur.kind {
        if *o == op || *o == inv {
            out.push((&**r, *o == inv));
            cur = l;
        } else {
            break;
        }
    }
    out.push((cur, false));
    out.reverse();
    out
}

fn write(e: &Expr, out: &mut String) -> Result<(), String> {
    match &e.kind {
        ExprKind::Num(q) => rational(q, out),
        ExprKind::Degrees(q) => {
            out.push_str("M_(");
            rational(q, out);
            out.push_str(", N_('pi', 0), R_('1', '180'))");
        }
        ExprKind::Name(n) => name(n, 0, out),
        ExprKind::Prime(inner, k) => match &inner.kind {
            ExprKind::Name(n) => name(n, *k, out),
            _ => {
                out.push_str("D_(");
                write(inner, out)?;
                out.push_str(&format!(", {k})"));
            }
        },
        ExprKind::Neg(x) => {
            out.push_str("M_(R_('-1', '1'), ");
            write(x, out)?;
            out.push(')');
        }
        ExprKind::Bin(BinOp::Pow, b, x) => {
            out.push_str("P_(");
            write(b, out)?;
            out.push_str(", ");
            write(x, out)?;
            out.push(')');
        }
        ExprKind::Bin(op, _, _) => {
            let add = matches!(op, BinOp::Add | BinOp::Sub);
            out.push_str(if add { "A_(" } else { "M_(" });
            for (i, (x, inverted)) in chain(e, add).into_iter().enumerate() {
                if i > 0 {
                    out.push_str(", ");
                }
                match (inverted, add) {
                    (false, _) => write(x, out)?,
                    (true, true) => {
                        out.push_str("M_(R_('-1', '1'), ");
                        write(x, out)?;
                        out.push(')');
                    }
                    (true, false) => {
                        out.push_str("P_(");
                        write(x, out)?;
                        out.push_str(", R_('-1', '1'))");
                    }
                }
            }
            out.push(')');
        }
        ExprKind::Call(f, args) => {
            out.push_str(&format!("F_({}", quoted(f.name())));
            for a in args {
                out.push_str(", ");
                write(a, out)?;
            }
            out.push(')');
        }
        ExprKind::Vector(xs) => {
            out.push_str("V_(");
            for (i, x) in xs.iter().enumerate() {
                if i > 0 {
                    out.push_str(", ");
                }
                write(x, out)?;
            }
            out.push(')');
        }
        ExprKind::Index(..) | ExprKind::Assign(..) => {
            return Err("an indexed or assigned expression is not a result qdot gives".into())
        }
    }
    Ok(())
}

fn rational(q: &num_rational::BigRational, out: &mut String) {
    let sign = if q.is_negative() { "-" } else { "" };
    out.push_str(&format!("R_('{sign}{}', '{}')", q.numer().abs(), q.denom()));
}

fn name(n: &str, order: u32, out: &mut String) {
    out.push_str(&format!("N_({}, {order})", quoted(n)));
}

/// A Python string literal of a qdot name (letters, digits, `_`; Unicode
/// letters such as θ are kept, escaped when not ASCII).
fn quoted(s: &str) -> String {
    let mut q = String::from("'");
    for c in s.chars() {
        match c {
            '\'' | '\\' => {
                q.push('\\');
                q.push(c);
            }
            c if c.is_ascii_graphic() || c == ' ' => q.push(c),
            c => q.push_str(&format!("\\U{:08x}", c as u32)),
        }
    }
    q.push('\'');
    q
}
