//! Exact linear systems A·x = b over the field of rational functions.
//!
//! Fraction-free (Bareiss) elimination: each row is cleared of denominators,
//! the elimination runs on polynomials with exact divisions by the previous
//! pivot (Sylvester's identity), and back-substitution computes the Cramer
//! numerators X_i = det·x_i, again with exact divisions. Only the final
//! quotients X_i/det are brought to canonical form, so intermediate
//! expressions never carry denominators and no gcd is computed until the end.
//!
//! Systems with angles and no radicals are eliminated in the exponential
//! basis zₖ = e^{iθₖ} (`linear/laurent.rs`), where sin² + cos² = 1 holds throughout
//! and the entries stay as small as their reduced forms. The others run in
//! the free polynomial ring (sin and cos as independent variables), where
//! Sylvester's identity makes every division exact; the relation
//! sin² + cos² = 1 is applied when the results are made canonical, which is
//! sound because reduction is a ring homomorphism. Both give the same
//! canonical answer.

use crate::expr::{Expr, MathError};
use crate::poly::{Poly, Var};

mod laurent;

/// Why a linear system has no unique exact solution.
#[derive(Clone, Debug)]
pub enum SolveError {
    /// The matrix is singular; `dependent` lists the unknowns (column
    /// indices) of a null vector's support.
    Singular {
        /// The unknowns (column indices) of a null vector's support.
        dependent: Vec<usize>,
    },
    /// An entry could not be formed exactly (a division by zero, a
    /// budget).
    Math(MathError),
}

/// lcm of two polynomials (by their gcd).
pub(crate) fn lcm(a: &Poly, b: &Poly) -> Poly {
    if b.is_one() {
        return a.clone();
    }
    if a.is_one() {
        return b.clone();
    }
    let g = a.gcd(b);
    match b.div_exact(&g) {
        Some(q) => a * &q,
        None => a * b,
    }
}

/// Solve `a·x = b` exactly (a square).
pub fn solve(a: &[Vec<Expr>], b: &[Expr]) -> Result<Vec<Expr>, SolveError> {
    let n = a.len();
    if n == 0 {
        return Ok(Vec::new());
    }
    let m = cleared_rows(a, b);
    if let Some(answer) = laurent::solve(a, &m) {
        return answer;
    }
    solve_free(a, m)
}

/// Bareiss elimination of the cleared rows `m` of `[a | b]` in the free ring.
fn solve_free(a: &[Vec<Expr>], mut m: Vec<Vec<Poly>>) -> Result<Vec<Expr>, SolveError> {
    let n = m.len();
    let work = crate::budget::WorkMeter::new();
    let mut prev = Poly::one();
    for k in 0..n {
        // Pivot: the nonzero (also modulo sin² + cos² = 1) entry with fewest
        // terms, one provably nonzero first (`may_be_zero`).
        let piv = (k..n)
            .filter(|&r| nonzero(&m[r][k]))
            .min_by_key(|&r| (may_be_zero(&m[r][k]), m[r][k].len()));
        let Some(p) = piv else {
            return Err(SolveError::Singular {
                dependent: dependent_unknowns(a),
            });
        };
        m.swap(k, p);
        for i in k + 1..n {
            for j in k + 1..=n {
                m[i][j] = bareiss_entry(&work, [&m[k][k], &m[i][j], &m[i][k], &m[k][j]], &prev)?;
            }
            m[i][k] = Poly::zero();
        }
        prev = m[k][k].clone();
    }
    let det = m[n - 1][n - 1].clone();
    if crate::expr::reduce_poly(&det).is_zero() {
        return Err(SolveError::Singular {
            dependent: dependent_unknowns(a),
        });
    }
    // Cramer numerators X_i = det·x_i.
    let mut xs = vec![Poly::zero(); n];
    for i in (0..n).rev() {
        work.charge(det.len(), m[i][n].len());
        let mut t = &det * &m[i][n];
        work.charge_built(powers(&t));
        for j in i + 1..n {
            work.charge(m[i][j].len(), xs[j].len());
            let p = &m[i][j] * &xs[j];
            work.charge_built(powers(&p));
            t = &t - &p;
        }
        work.charge(t.len(), m[i][i].len());
        xs[i] = exact(&t, &m[i][i])?;
        work.charge_built(powers(&xs[i]));
    }
    xs.into_iter()
        .map(|x| {
            Expr::from_parts(x, det.clone()).map_err(|_| SolveError::Singular {
                dependent: dependent_unknowns(a),
            })
        })
        .collect()
}

/// The rows of `[A | b]`, each multiplied by the lcm of its denominators:
/// polynomials, for fraction-free elimination.
pub fn cleared_rows(a: &[Vec<Expr>], b: &[Expr]) -> Vec<Vec<Poly>> {
    a.iter()
        .zip(b)
        .map(|(ai, bi)| {
            let row: Vec<&Expr> = ai.iter().chain(std::iter::once(bi)).collect();
            let l = row.iter().fold(Poly::one(), |l, e| lcm(&l, e.den()));
            row.iter()
                .map(|e| {
                    if e.den().is_one() {
                        e.num() * &l
                    } else {
                        let f = l.div_exact(e.den()).unwrap_or_else(|| l.clone());
                        e.num() * &f
                    }
                })
                .collect()
        })
        .collect()
}

/// Nonzero also modulo sin² + cos² = 1 (the elimination runs in the free
/// ring, so a pivot must be tested after reduction).
pub fn nonzero(p: &Poly) -> bool {
    !p.is_zero() && !crate::expr::reduce_poly(p).is_zero()
}

/// Whether a pivot that is nonzero as a polynomial may be zero as a number
/// ([`crate::expr::hidden_zero`]): such a pivot is taken last, and dividing
/// by it is refused.
pub fn may_be_zero(p: &Poly) -> bool {
    crate::expr::hidden_zero::can_arise()
        && crate::expr::hidden_zero::may_be_zero(&crate::expr::reduce_poly(p))
}

/// One entry of a fraction-free elimination step, (p·x − l·u) / prev with
/// `[p, x, l, u]` the pivot, the entry, its row's pivot-column entry and
/// its column's pivot-row entry (Sylvester's identity makes it exact);
/// every product and the division charged to `work`, and the terms each
/// built.
pub fn bareiss_entry(
    work: &crate::budget::WorkMeter,
    [p, x, l, u]: [&Poly; 4],
    prev: &Poly,
) -> Result<Poly, SolveError> {
    work.charge(p.len(), x.len());
    work.charge(l.len(), u.len());
    let px = p * x;
    work.charge_built(powers(&px));
    let lu = l * u;
    work.charge_built(powers(&lu));
    let t = &px - &lu;
    work.charge(t.len(), prev.len());
    let q = exact(&t, prev)?;
    work.charge_built(powers(&q));
    Ok(q)
}

/// The variable powers of `p`'s terms in all (a term `m₁·l₁²·cos q₁`
/// holds 3): what building `p` cost past its term products.
fn powers(p: &Poly) -> usize {
    p.terms().iter().map(|(m, _)| m.0.len()).sum()
}

/// t / d, which fraction-free elimination guarantees to be exact.
pub(crate) fn exact(t: &Poly, d: &Poly) -> Result<Poly, SolveError> {
    if d.is_one() {
        return Ok(t.clone());
    }
    t.div_exact(d).ok_or_else(|| {
        SolveError::Math(MathError::new(
            "internal error: a fraction-free elimination step did not divide exactly",
        ))
    })
}

/// The support of a null vector of a singular matrix (Gaussian elimination
/// over the canonical expressions, whose zero test is exact).
pub fn dependent_unknowns(a: &[Vec<Expr>]) -> Vec<usize> {
    let n = a.len();
    let cols = a.first().map(|r| r.len()).unwrap_or(0);
    let mut m: Vec<Vec<Expr>> = a.to_vec();
    let mut pivot_cols = Vec::new();
    let mut row = 0;
    for c in 0..cols {
        let Some(p) = (row..n).find(|&r| !m[r][c].is_zero()) else {
            continue;
        };
        m.swap(row, p);
        let inv = match m[row][c].recip() {
            Ok(x) => x,
            Err(_) => continue,
        };
        for x in m[row].iter_mut() {
            *x = x.mul(&inv);
        }
        for r in 0..n {
            if r != row && !m[r][c].is_zero() {
                let f = m[r][c].clone();
                let pivot_row = m[row].clone();
                for (x, p) in m[r].iter_mut().zip(&pivot_row) {
                    *x = x.sub(&f.mul(p));
                }
            }
        }
        pivot_cols.push(c);
        row += 1;
        if row == n {
            break;
        }
    }
    // The first free column gives a null vector: x_free = 1, x_pivot = −m[r][free].
    let Some(free) = (0..cols).find(|c| !pivot_cols.contains(c)) else {
        return (0..cols).collect();
    };
    let mut out = vec![free];
    for (r, &pc) in pivot_cols.iter().enumerate() {
        if !m[r][free].is_zero() {
            out.push(pc);
        }
    }
    out.sort_unstable();
    out
}

/// det of a square matrix of expressions: each row is cleared of its
/// denominators, the polynomial rows are eliminated fraction-free
/// (Bareiss: exact divisions by the previous pivot, every product and
/// division charged to one [`crate::budget::WorkMeter`]), and only the
/// final quotient by the rows' multipliers takes a gcd. (Elimination over
/// the canonical fractions took a gcd per entry per step, with
/// coefficients growing: det(K − λ·M) of the 30-link chain took 28 s
/// outside the budget.) The determinant is a polynomial identity in the
/// free ring, so it holds whatever the pivots' values. `None` when the
/// quotient has no canonical form.
pub fn det(m: Vec<Vec<Expr>>) -> Option<Expr> {
    let n = m.len();
    let mut den = Poly::one();
    let mut a: Vec<Vec<Poly>> = Vec::with_capacity(n);
    for row in &m {
        let l = row.iter().fold(Poly::one(), |l, e| lcm(&l, e.den()));
        a.push(
            row.iter()
                .map(|e| match l.div_exact(e.den()) {
                    Some(f) => e.num() * &f,
                    None => e.num() * &l,
                })
                .collect(),
        );
        den = &den * &l;
    }
    let work = crate::budget::WorkMeter::new();
    let mut prev = Poly::one();
    let mut negate = false;
    for k in 0..n {
        let Some(p) = (k..n)
            .filter(|&r| !a[r][k].is_zero())
            .min_by_key(|&r| a[r][k].len())
        else {
            return Some(Expr::zero());
        };
        if p != k {
            a.swap(p, k);
            negate = !negate;
        }
        for i in k + 1..n {
            for j in k + 1..n {
                a[i][j] =
                    bareiss_entry(&work, [&a[k][k], &a[i][j], &a[i][k], &a[k][j]], &prev).ok()?;
            }
            a[i][k] = Poly::zero();
        }
        prev = a[k][k].clone();
    }
    let d = if negate { -&prev } else { prev };
    Expr::from_parts(d, den).ok()
}

/// Split `e` (linear in the variables `vs`) as Σ coef_j·vs_j + rest. An
/// error only if a part has no canonical form (a coefficient over the
/// denominator of `e` cannot vanish, so this does not happen in practice;
/// it is reported, never turned into 0).
pub fn split_linear(e: &Expr, vs: &[Var]) -> Result<(Vec<Expr>, Expr), crate::expr::MathError> {
    let den = e.den().clone();
    let mut rest = e.num().clone();
    let mut coefs = Vec::with_capacity(vs.len());
    for &v in vs {
        if !rest.contains_var(v) {
            coefs.push(Expr::zero());
            continue;
        }
        let cs = rest.coeffs_in(v);
        let c1 = cs.get(1).cloned().unwrap_or_default();
        // Any higher power would mean a nonlinear left-hand side; Lagrange's
        // left-hand sides are always linear in q̈, so cs.len() ≤ 2.
        rest = cs.first().cloned().unwrap_or_default();
        if cs.len() > 2 {
            let higher: Vec<Poly> = cs[2..].to_vec();
            let mut extra = Poly::zero();
            for (i, c) in higher.iter().enumerate() {
                extra = &extra + &(c * &Poly::var(v).pow(i as u32 + 2));
            }
            rest = &rest + &extra;
        }
        coefs.push(Expr::from_parts(c1, den.clone())?);
    }
    let rest = Expr::from_parts(rest, den)?;
    Ok((coefs, rest))
}
