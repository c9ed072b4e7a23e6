//! A scene's expression as it is written, for the derivation's tables: the
//! names it uses stay names (`\varphi = \frac{x - s}{R}`, `E_{1} =
//! \frac{1}{2} m \dot{y}_{1}^{2}`) where the scene's values have every
//! definition put in. The arithmetic is exact, so the written form and the
//! value differ only in what the definitions hide.

use crate::expr::{atom, func, Expr};
use crate::num::Q;
use crate::parse::ast::{self, BinOp, Callee, ExprKind};
use crate::parse::functions::Builtin;
use crate::scene::{Scene, Value};

/// An expression as written: a number or a vector of them.
pub(super) enum Written {
    Scalar(Expr),
    Vector(Vec<Expr>),
}

/// `e` with its names kept, or `None` for what has no such form here (a
/// frame, `axis`, `dot`, `subs`, a vector definition used inside it, …):
/// the derivation then shows the value.
pub(super) fn written(e: &ast::Expr, scene: &Scene) -> Option<Written> {
    use Written::{Scalar, Vector};
    Some(match &e.kind {
        ExprKind::Num(r) => Scalar(Expr::rational(Q::from_big(r.clone()))),
        ExprKind::Degrees(d) => {
            let turn = Q::from_big(d.clone()).checked_div(&Q::from_i64(180))?;
            Scalar(Expr::var(atom::pi()).scale(&turn))
        }
        ExprKind::Name(n) => Scalar(name(n, scene)?),
        ExprKind::Neg(a) => match written(a, scene)? {
            Scalar(x) => Scalar(x.neg()),
            Vector(v) => Vector(v.iter().map(Expr::neg).collect()),
        },
        ExprKind::Prime(a, k) => {
            let mut x = scalar(a, scene)?;
            for _ in 0..*k {
                x = x.dt();
            }
            Scalar(x)
        }
        ExprKind::Vector(cs) => Vector(
            cs.iter()
                .map(|c| scalar(c, scene))
                .collect::<Option<Vec<_>>>()?,
        ),
        ExprKind::Bin(op, a, b) => binary(*op, written(a, scene)?, written(b, scene)?)?,
        ExprKind::Call(Callee::Builtin(f, _), args) => {
            let [a] = args.as_slice() else { return None };
            let x = scalar(a, scene)?;
            Scalar(match f {
                Builtin::Sin => func::sin(&x),
                Builtin::Cos => func::cos(&x),
                Builtin::Tan => func::tan(&x).ok()?,
                Builtin::Sqrt => func::sqrt(&x).ok()?,
                Builtin::Exp => func::exp(&x),
                Builtin::Ln => func::ln(&x).ok()?,
                Builtin::Atan => func::atan(&x),
                Builtin::Asin => func::asin(&x).ok()?,
                Builtin::Acos => func::acos(&x).ok()?,
                _ => return None,
            })
        }
        // a given function of time, `s(t)`
        ExprKind::Call(Callee::Named(f), args) => match args.as_slice() {
            [a] if matches!(&a.kind, ExprKind::Name(t) if t == "t")
                && scene.functions.iter().any(|g| g.name == f.name) =>
            {
                Scalar(Expr::var(atom::given(&f.name, 0)))
            }
            _ => return None,
        },
        ExprKind::Index(..) | ExprKind::Assign(..) => return None,
    })
}

fn scalar(e: &ast::Expr, scene: &Scene) -> Option<Expr> {
    match written(e, scene)? {
        Written::Scalar(x) => Some(x),
        Written::Vector(_) => None,
    }
}

/// A name as a symbol: a definition's name is written like a coordinate,
/// so that its rate is dotted (`\dot{y}_{1}`).
fn name(n: &str, scene: &Scene) -> Option<Expr> {
    let v = match n {
        "t" => atom::time(),
        "pi" => atom::pi(),
        _ if scene.parameters.iter().any(|p| p.name == n) => atom::param(n),
        _ if scene.functions.iter().any(|g| g.name == n) => atom::given(n, 0),
        // a vector or a frame cannot stand as a symbol in exact arithmetic
        _ if matches!(scene.value(n), Some(Value::Vector(_) | Value::Rotation(_))) => return None,
        _ => atom::coord(n, 0),
    };
    Some(Expr::var(v))
}

fn binary(op: BinOp, a: Written, b: Written) -> Option<Written> {
    use Written::{Scalar, Vector};
    let each = |v: &[Expr], f: &dyn Fn(&Expr) -> Option<Expr>| {
        v.iter().map(f).collect::<Option<Vec<Expr>>>().map(Vector)
    };
    match (op, a, b) {
        (BinOp::Add, Scalar(x), Scalar(y)) => Some(Scalar(x.add(&y))),
        (BinOp::Sub, Scalar(x), Scalar(y)) => Some(Scalar(x.sub(&y))),
        (BinOp::Mul, Scalar(x), Scalar(y)) => Some(Scalar(x.mul(&y))),
        (BinOp::Div, Scalar(x), Scalar(y)) => x.div(&y).ok().map(Scalar),
        (BinOp::Pow, Scalar(x), Scalar(y)) => {
            let n = y.as_rational()?.as_i64()?;
            x.powi(n).ok().map(Scalar)
        }
        (BinOp::Add | BinOp::Sub, Vector(u), Vector(v)) if u.len() == v.len() => {
            let minus = op == BinOp::Sub;
            Some(Vector(
                u.iter()
                    .zip(&v)
                    .map(|(x, y)| if minus { x.sub(y) } else { x.add(y) })
                    .collect(),
            ))
        }
        (BinOp::Mul, Scalar(x), Vector(v)) | (BinOp::Mul, Vector(v), Scalar(x)) => {
            each(&v, &|c| Some(x.mul(c)))
        }
        (BinOp::Div, Vector(v), Scalar(x)) => each(&v, &|c| c.div(&x).ok()),
        _ => None,
    }
}
