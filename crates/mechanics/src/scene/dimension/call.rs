//! The dimensions of the built-in functions' results, and what they ask of
//! their arguments (`parse::functions` is the table of the functions).

use super::form::DimForm;
use super::walk::{DimValue, Walker, Want, Why};
use crate::diag::Diagnostic;
use crate::num::Q;
use crate::parse::ast::{Builtin, Callee, Expr, ExprKind};

type Checked<T> = Result<T, Diagnostic>;

/// The dimension of `f(args)`.
pub(super) fn call(w: &mut Walker, f: &Callee, args: &[Expr]) -> Checked<DimValue> {
    let b = match f {
        Callee::Builtin(b, _) => *b,
        // a given function `s(t)` has its declared or found dimension;
        // unknown functions are reported when the scene is resolved
        Callee::Named(id) => {
            return Ok(match w.names.get(id.name.as_str()) {
                Some(super::walk::NameDim::Fixed(_)) => w.name(&id.name),
                _ => DimValue::Scalar(None),
            })
        }
    };
    #[deny(
        clippy::wildcard_enum_match_arm,
        clippy::match_wildcard_for_single_variants
    )]
    match b {
        Builtin::Sin
        | Builtin::Cos
        | Builtin::Tan
        | Builtin::Exp
        | Builtin::Ln
        | Builtin::Asin
        | Builtin::Acos
        | Builtin::Atan => {
            let want = Want {
                form: DimForm::one(),
                why: Why::Argument {
                    function: b.name().to_string(),
                },
            };
            for a in args {
                w.value(a, Some(&want))?;
            }
            Ok(DimValue::Scalar(Some(DimForm::one())))
        }
        Builtin::Sqrt => match args.first() {
            Some(a) => Ok(w.value(a, None)?.map(|f| f.pow(&half()))),
            None => Ok(DimValue::Scalar(None)),
        },
        Builtin::Expand | Builtin::Factor => match args.first() {
            Some(a) => w.value(a, None),
            None => Ok(DimValue::Scalar(None)),
        },
        Builtin::Dt => match args.first() {
            Some(a) => {
                let v = w.value(a, None)?;
                Ok(v.map(|f| f.div(&Walker::time())))
            }
            None => Ok(DimValue::Scalar(None)),
        },
        Builtin::Diff => match args {
            [f, x] => {
                let v = w.value(f, None)?;
                let by = scalar(&w.value(x, None)?);
                Ok(match by {
                    Some(d) => v.map(|f| f.div(&d)),
                    None => v,
                })
            }
            _ => Ok(DimValue::Scalar(None)),
        },
        Builtin::Inertia => match args {
            [m, x] => {
                let m = scalar(&w.value(m, None)?);
                let x = w.value(x, None)?;
                let t2 = Walker::time().pow(&Q::from_i64(-2));
                Ok(match m {
                    Some(m) => x.map(|f| f.mul(&m).mul(&t2)),
                    None => DimValue::Scalar(None),
                })
            }
            _ => Ok(DimValue::Scalar(None)),
        },
        Builtin::Dot => vector_function(w, Product::Dot, args),
        Builtin::Cross => vector_function(w, Product::Cross, args),
        Builtin::Norm => vector_function(w, Product::Norm, args),
        Builtin::Rot => rot(w, args),
        Builtin::Axis => match args {
            [f, _] => {
                w.value(f, None)?;
                Ok(DimValue::Vector(vec![Some(DimForm::one()); 3]))
            }
            _ => Ok(DimValue::Scalar(None)),
        },
        Builtin::Express => match args {
            [v, f] => {
                w.value(f, None)?;
                let v = w.value(v, None)?;
                let d = common(w, &v, &args[0])?;
                Ok(DimValue::Vector(vec![d; 3]))
            }
            _ => Ok(DimValue::Scalar(None)),
        },
        Builtin::Omega => match args {
            [f] => {
                w.value(f, None)?;
                let per_time = DimForm::one().div(&Walker::time());
                Ok(DimValue::Vector(vec![Some(per_time); 3]))
            }
            _ => Ok(DimValue::Scalar(None)),
        },
        Builtin::Subs => substitution(w, args),
        Builtin::Taylor => taylor(w, args),
        Builtin::Series => {
            let moves = |n: &str| n == "t" || w.coordinates.contains(n);
            if crate::scene::is_taylor_form(args, moves) {
                return taylor(w, args);
            }
            springs(w, args)
        }
        Builtin::Parallel => springs(w, args),
    }
}

/// A rotation's dimensions: its matrix, nine pure numbers.
pub(super) fn rotation() -> DimValue {
    DimValue::Vector(vec![Some(DimForm::one()); 9])
}

/// `rot(AXIS, ANGLE)`: a rotation, its angle a pure number.
fn rot(w: &mut Walker, args: &[Expr]) -> Checked<DimValue> {
    let [axis, angle] = args else {
        return Ok(DimValue::Scalar(None));
    };
    if crate::scene::axis_name(args).is_none() {
        w.value(axis, None)?;
    }
    let want = Want {
        form: DimForm::one(),
        why: Why::Argument {
            function: Builtin::Rot.name().to_string(),
        },
    };
    w.value(angle, Some(&want))?;
    Ok(rotation())
}

fn half() -> Q {
    Q::new(1, 2).unwrap_or_default()
}

fn scalar(v: &DimValue) -> Option<DimForm> {
    match v {
        DimValue::Scalar(t) => t.clone(),
        DimValue::Vector(_) => None,
    }
}

/// The one dimension of a vector's components (dot, cross and norm need
/// one), or the error at `at`.
fn common(w: &mut Walker, v: &DimValue, at: &Expr) -> Checked<Option<DimForm>> {
    let mut first: Option<DimForm> = None;
    for (k, c) in v.components().iter().enumerate() {
        let Some(c) = c else { continue };
        match &first {
            None => first = Some(c.clone()),
            Some(f) => {
                if !w.vars.unify(c, f, at.span) {
                    let msg = format!(
                        "the components of this vector differ in dimension: component {} is {}, the first is {}",
                        k + 1,
                        w.vars.phrase(c),
                        w.vars.phrase(f)
                    );
                    return Err(w.error(at, msg, c, f));
                }
            }
        }
    }
    Ok(first)
}

/// What `dot`, `cross` and `norm` make of their vectors' dimensions.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Product {
    Dot,
    Cross,
    Norm,
}

fn vector_function(w: &mut Walker, product: Product, args: &[Expr]) -> Checked<DimValue> {
    let mut dims = Vec::with_capacity(args.len());
    let mut len = 0;
    for a in args {
        let v = w.value(a, None)?;
        len = v.components().len();
        dims.push(common(w, &v, a)?);
    }
    let value = match (product, &dims[..]) {
        (Product::Norm, [a]) => a.clone(),
        (Product::Dot | Product::Cross, [Some(a), Some(b)]) => Some(a.mul(b)),
        _ => None,
    };
    Ok(if product == Product::Cross && len == 3 {
        DimValue::Vector(vec![value; 3])
    } else {
        DimValue::Scalar(value)
    })
}

/// `subs(f, x = a, …)`: each value has its variable's dimension.
fn substitution(w: &mut Walker, args: &[Expr]) -> Checked<DimValue> {
    let Some((f, rest)) = args.split_first() else {
        return Ok(DimValue::Scalar(None));
    };
    let v = w.value(f, None)?;
    for a in rest {
        assigned(w, a)?;
    }
    Ok(v)
}

/// `x = a` in `subs` or `taylor`: `a` has `x`'s dimension.
fn assigned(w: &mut Walker, a: &Expr) -> Checked<()> {
    let ExprKind::Assign(x, value) = &a.kind else {
        return Ok(());
    };
    if let Some(f) = scalar(&w.value(x, None)?) {
        let want = Want {
            form: f,
            why: Why::Substituted {
                variable: w.src[x.span.start..x.span.end].to_string(),
            },
        };
        w.value(value, Some(&want))?;
    }
    Ok(())
}

/// `taylor(f, x, n)`, `taylor(f, x = a, n)`, `series(f, x = a, n)`.
fn taylor(w: &mut Walker, args: &[Expr]) -> Checked<DimValue> {
    let Some(f) = args.first() else {
        return Ok(DimValue::Scalar(None));
    };
    let v = w.value(f, None)?;
    if let Some(a) = args.get(1) {
        assigned(w, a)?;
    }
    Ok(v)
}

/// `series(k1, k2, …)`, `parallel(k1, k2, …)`: springs of one kind.
fn springs(w: &mut Walker, args: &[Expr]) -> Checked<DimValue> {
    let mut first: Option<DimForm> = None;
    for a in args {
        let Some(f) = scalar(&w.value(a, None)?) else {
            continue;
        };
        match &first {
            None => first = Some(f),
            Some(g) => {
                if !w.vars.unify(&f, g, a.span) {
                    let msg = format!(
                        "this spring is {}; the first is {}",
                        w.vars.phrase(&f),
                        w.vars.phrase(g)
                    );
                    return Err(w.error(a, msg, &f, g));
                }
            }
        }
    }
    Ok(DimValue::Scalar(first))
}
