//! The accelerations of equations written through intermediates: M·q̈ = f
//! solved by M = L·D·Lᵀ, every factor an intermediate, so q̈ costs O(n³)
//! small expressions instead of an expanded inverse.
//!
//! ```text
//! D_j  = M_jj − Σ_{k<j} L_jk²·D_k
//! L_ij = (M_ij − Σ_{k<j} L_ik·L_jk·D_k) / D_j        (i > j)
//! y_i  = f_i − Σ_{k<i} L_ik·y_k,   z_i = y_i / D_i
//! q̈_i  = z_i − Σ_{k>i} L_ki·q̈_k                      (from the last)
//! ```
//!
//! M is a kinetic energy's Hessian, positive semi-definite: the pivots D_j
//! are positive unless M is singular. A pivot whose canonical form is zero
//! is refused as singular; one that is zero only after expansion (the
//! canonical form cannot see relations between intermediates) is caught
//! numerically at random states and refused too, never divided by.

use crate::diag::Diagnostic;
use crate::expr::atom::Atom;
use crate::expr::tape::Tape;
use crate::expr::Expr;

/// Write the equations of `l` through `tape`: M_ij (once for M_ji), the
/// velocity terms h_k, the generalized forces Q_k and f_k = Q_k − h_k
/// become intermediates, and each equation reads M_k·q̈ + h_k = Q_k.
pub(crate) fn name_equations(tape: &mut Tape, l: &mut super::Lagrange) {
    let n = l.coordinates.len();
    let index = |i: usize, j: usize| {
        if n < 10 {
            format!("{}{}", i + 1, j + 1)
        } else {
            format!("{}_{}", i + 1, j + 1)
        }
    };
    for i in 0..n {
        for j in i..n {
            let m = tape.define(&format!("M_{}", index(i, j)), l.mass_matrix[i][j].clone());
            l.mass_matrix[i][j] = m.clone();
            l.mass_matrix[j][i] = m;
        }
    }
    let accelerations: Vec<Expr> = l.coordinates.iter().map(|c| Expr::coord(c, 2)).collect();
    let inertial_loads = l.equations.iter().any(|e| {
        accelerations
            .iter()
            .filter_map(Expr::as_var)
            .any(|a| e.rhs.depends_on(a))
    });
    if inertial_loads {
        // D'Alembert's form: Q carries inertia forces that M took over, so
        // the equations stay as derived and only f is named
        for k in 0..n {
            l.forcing[k] = tape.define(&format!("f_{}", k + 1), l.forcing[k].clone());
        }
        return;
    }
    for k in 0..n {
        let eq = &mut l.equations[k];
        // lhs = M_k·q̈ + h_k, h_k the velocity terms (q̈ = 0), f_k = Q_k − h_k
        let at_rest: rustc_hash::FxHashMap<_, _> = accelerations
            .iter()
            .filter_map(Expr::as_var)
            .map(|v| (v, Expr::zero()))
            .collect();
        let h = eq
            .lhs
            .subs_many(&at_rest)
            .unwrap_or_else(|_| eq.lhs.clone());
        let h = tape.define(&format!("h_{}", eq.coordinate), h);
        let q = tape.define(&format!("Q_{}", eq.coordinate), eq.rhs.clone());
        l.forcing[k] = tape.define(&format!("f_{}", k + 1), q.sub(&h));
        eq.lhs = dot(&l.mass_matrix[k], &accelerations).add(&h);
        eq.rhs = q;
    }
}

/// Σ a_j·b_j.
fn dot(a: &[Expr], b: &[Expr]) -> Expr {
    a.iter()
        .zip(b)
        .fold(Expr::zero(), |s, (x, y)| s.add(&x.mul(y)))
}

/// How many random states a pivot is evaluated at.
const PIVOT_PROBES: u64 = 3;

/// q̈ = M⁻¹·f through `tape` (M symmetric, given in full; M and f are
/// already named by [`name_equations`]).
pub(crate) fn solve_ldl(
    tape: &mut Tape,
    coordinates: &[String],
    m: &[Vec<Expr>],
    f: &[Expr],
) -> Result<Vec<Expr>, Diagnostic> {
    let n = f.len();
    let mut l: Vec<Vec<Expr>> = vec![Vec::new(); n];
    let mut d: Vec<Expr> = Vec::with_capacity(n);
    for j in 0..n {
        let mut pivot = m[j][j].clone();
        for k in 0..j {
            pivot = pivot.sub(&l[j][k].mul(&l[j][k]).mul(&d[k]));
        }
        check_pivot(tape, &pivot, coordinates, j)?;
        let dj = tape.define(&format!("D_{}", j + 1), pivot);
        for i in (j + 1)..n {
            let mut s = m[i][j].clone();
            for k in 0..j {
                s = s.sub(&l[i][k].mul(&l[j][k]).mul(&d[k]));
            }
            let lij = s.div(&dj).map_err(|e| {
                Diagnostic::global(e.message).with_kind(crate::diag::ErrorKind::Undefined)
            })?;
            let lij = tape.define(&format!("L_{}{}", i + 1, j + 1), lij);
            l[i].push(lij);
        }
        d.push(dj);
    }
    // l[i] holds L_ik for k < i, in order of k
    let mut z: Vec<Expr> = Vec::with_capacity(n);
    let mut y: Vec<Expr> = Vec::with_capacity(n);
    for i in 0..n {
        let mut yi = f[i].clone();
        for k in 0..i {
            yi = yi.sub(&l[i][k].mul(&y[k]));
        }
        let yi = tape.define(&format!("y_{}", i + 1), yi);
        let zi = yi.div(&d[i]).map_err(|e| {
            Diagnostic::global(e.message).with_kind(crate::diag::ErrorKind::Undefined)
        })?;
        z.push(tape.define(&format!("z_{}", i + 1), zi));
        y.push(yi);
    }
    let mut acc: Vec<Expr> = vec![Expr::zero(); n];
    let mut named: Vec<Expr> = vec![Expr::zero(); n];
    for i in (0..n).rev() {
        let mut a = z[i].clone();
        for k in (i + 1)..n {
            a = a.sub(&l[k][i].mul(&named[k]));
        }
        named[i] = if i > 0 {
            tape.define(&format!("{}_dd", coordinates[i]), a.clone())
        } else {
            a.clone()
        };
        acc[i] = a;
    }
    Ok(acc)
}

/// An error unless the pivot is nonzero: exactly in its canonical form,
/// and numerically at random states (see the module docs).
fn check_pivot(
    tape: &Tape,
    pivot: &Expr,
    coordinates: &[String],
    j: usize,
) -> Result<(), Diagnostic> {
    let singular = || {
        Diagnostic::global(format!(
            "the mass matrix is singular: the velocity of {} carries no kinetic energy that the others do not",
            coordinates[j]
        ))
        .with_hint("a combination of the velocities carries no kinetic energy; remove a redundant coordinate or add the missing inertia")
        .with_kind(crate::diag::ErrorKind::SingularSystem {
            unknowns: vec![coordinates[j].clone()],
        })
    };
    if pivot.is_zero() {
        return Err(singular());
    }
    let mut rng = crate::rng::SplitMix64::new(0x5eed_0000 + j as u64);
    let mut zero_at_every_probe = true;
    for _ in 0..PIVOT_PROBES {
        let seed = rng.next_u64();
        let value = tape.eval_f64(pivot, &|a: &Atom| {
            Some(crate::rng::SplitMix64::keyed(seed, a).uniform(0.5, 1.5))
        });
        match value {
            Some(v) if v.abs() > 1e-9 => {
                zero_at_every_probe = false;
                break;
            }
            _ => {}
        }
    }
    if zero_at_every_probe {
        return Err(singular());
    }
    Ok(())
}
