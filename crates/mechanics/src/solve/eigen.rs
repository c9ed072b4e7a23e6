//! Numeric generalized symmetric eigenproblem K·v = λ·M·v for small
//! oscillations.
//!
//! Near an equilibrium the linearized Lagrange equations are M·q̈ + K·q = 0,
//! with M the (symmetric positive definite) mass matrix and K the symmetric
//! stiffness matrix. The normal modes are q = v·e^{±i√λ·t}, where
//! K·v = λ·M·v: λ = ω² > 0 for a stable mode, λ < 0 for an unstable one (K
//! may be indefinite). qdot derives these exactly elsewhere; this module is
//! the independent floating-point check and fallback. Sizes are small
//! (n = 1..≈20), so everything is dense.
//!
//! # Method
//!
//! [`generalized_symmetric`] reduces the problem to a standard symmetric one:
//!
//! ```text
//! M = L·Lᵀ (Cholesky),   A = L⁻¹·K·L⁻ᵀ,   A·w = λ·w,   v = L⁻ᵀ·w.
//! ```
//!
//! A is formed by two triangular solves and then symmetrized ((A + Aᵀ)/2),
//! and its eigendecomposition is nalgebra's [`SymmetricEigen`] (Householder
//! tridiagonalization + implicit QR with Wilkinson shifts). Since the w are
//! orthonormal, the v are M-orthonormal: vᵢᵀ·M·vⱼ = wᵢᵀ·wⱼ = δᵢⱼ; each v is
//! then rescaled by 1/√(vᵀ·M·v) (with the input M) to clean up rounding.
//!
//! # Output conventions
//!
//! * Eigenvalues are sorted ascending (by [`f64::total_cmp`]; ties keep the
//!   solver's order), and the eigenvectors are permuted along.
//! * Each eigenvector's sign is fixed so that its first entry with
//!   |xᵢ| > 10⁻¹²·max|x| is positive, so the output is deterministic.
//! * For a repeated eigenvalue, the eigenvectors are *some* M-orthonormal
//!   basis of its eigenspace.
//!
//! # Errors
//!
//! Nothing panics on bad input; every problem is an `Err` with a message:
//! non-square or mismatched matrices, non-finite entries, M or K not
//! symmetric (|Xᵢⱼ − Xⱼᵢ| > 10⁻¹²·max|X|), M not positive definite (the
//! Cholesky factorization fails, or a pivot is ≤ 10⁻¹³·max|M|, i.e. M is
//! numerically singular), overflow, or non-convergence of the QR iteration.
//! The 0×0 problem is not an error: it has no modes.

use nalgebra::{Cholesky, DMatrix, SymmetricEigen};

/// Relative tolerance of the symmetry checks: |Xᵢⱼ − Xⱼᵢ| ≤ SYMMETRY_RTOL·max|X|.
const SYMMETRY_RTOL: f64 = 1e-12;
/// A Cholesky pivot (Lᵢᵢ²) ≤ SINGULAR_RTOL·max|M| means M is numerically singular.
const SINGULAR_RTOL: f64 = 1e-13;
/// An entry counts for the sign normalization if |xᵢ| > SIGN_RTOL·max|x|.
const SIGN_RTOL: f64 = 1e-12;
/// [`distribution_coefficients`] needs |v₀| > DISTRIBUTION_RTOL·max|v|.
const DISTRIBUTION_RTOL: f64 = 1e-10;

/// Eigenvalues (ascending) and M-orthonormal eigenvectors (columns:
/// vᵢᵀ·M·vⱼ = δᵢⱼ), so that K·vᵢ = λᵢ·M·vᵢ.
///
/// Produced by [`generalized_symmetric`]; see the module documentation for
/// the ordering and sign conventions.
#[derive(Clone, Debug)]
pub struct GeneralizedEigen {
    /// The eigenvalues λᵢ, ascending. For small oscillations λ = ω²; a
    /// negative value is an unstable direction.
    pub values: Vec<f64>,
    /// `vectors[i]` is the eigenvector of `values[i]` (length n), normalized
    /// so that vᵢᵀ·M·vᵢ = 1 and with its first significant entry positive.
    pub vectors: Vec<Vec<f64>>,
}

/// Solve K v = λ M v by Cholesky M = L Lᵀ, A = L⁻¹ K L⁻ᵀ (symmetrized),
/// nalgebra's SymmetricEigen on A, v = L⁻ᵀ w.
///
/// `k` and `m` are given as rows (`k[i][j]` = Kᵢⱼ) and must both be n×n.
/// The eigenvalues are returned ascending, with the eigenvectors permuted
/// along; each eigenvector is M-normalized and its sign is normalized so that
/// its first entry with |x| > 1e-12·max|x| is positive (deterministic
/// output).
///
/// M and K are symmetrized ((X + Xᵀ)/2) after the symmetry check, so an
/// asymmetry within the tolerance does not matter.
///
/// # Errors
///
/// * non-square or mismatched sizes (including ragged rows);
/// * non-finite entries (NaN, ±∞);
/// * M not symmetric (|Mᵢⱼ − Mⱼᵢ| > 1e-12·max|M|), K likewise;
/// * M not positive definite (Cholesky fails, or a pivot Lᵢᵢ² ≤
///   1e-13·max|M|: numerically singular);
/// * overflow (K too large relative to M for `f64`), or the QR iteration not
///   converging.
///
/// A 0×0 problem returns empty `values` and `vectors`.
///
/// # Example
///
/// ```
/// use qdot_mechanics::solve::eigen::generalized_symmetric;
/// // Two masses 4 and 1.5 coupled by springs: λ = 1/6 and 1.
/// let k = vec![vec![2.0, -1.0], vec![-1.0, 1.0]];
/// let m = vec![vec![4.0, 0.0], vec![0.0, 1.5]];
/// let e = generalized_symmetric(&k, &m).unwrap();
/// assert!((e.values[0] - 1.0 / 6.0).abs() < 1e-12);
/// assert!((e.values[1] - 1.0).abs() < 1e-12);
/// ```
pub fn generalized_symmetric(
    k: &[Vec<f64>],
    m: &[Vec<f64>],
) -> Result<GeneralizedEigen, EigenError> {
    let n = m.len();
    check_square(m, "M")?;
    check_square(k, "K")?;
    if k.len() != n {
        return Err(EigenError::Shape(format!(
            "K is {0}×{0} but M is {1}×{1}: the matrices must have the same size",
            k.len(),
            n
        )));
    }
    if n == 0 {
        return Ok(GeneralizedEigen {
            values: Vec::new(),
            vectors: Vec::new(),
        });
    }
    check_finite(m, "M")?;
    check_finite(k, "K")?;
    let m_max = check_symmetric(m, "M")?;
    check_symmetric(k, "K")?;

    let m_sym = DMatrix::from_fn(n, n, |i, j| 0.5 * (m[i][j] + m[j][i]));
    let k_sym = DMatrix::from_fn(n, n, |i, j| 0.5 * (k[i][j] + k[j][i]));

    // M = L·Lᵀ.
    let chol = Cholesky::new(m_sym.clone()).ok_or(EigenError::NotPositiveDefinite)?;
    let l = chol.l();
    let min_pivot = (0..n)
        .map(|i| l[(i, i)] * l[(i, i)])
        .fold(f64::INFINITY, f64::min);
    if !min_pivot.is_finite() || min_pivot <= SINGULAR_RTOL * m_max {
        return Err(EigenError::SingularMass {
            pivot: Some(min_pivot),
            bound: SINGULAR_RTOL * m_max,
        });
    }

    // A = L⁻¹·K·L⁻ᵀ = L⁻¹·(L⁻¹·K)ᵀ (K symmetric), then symmetrized.
    let singular = || EigenError::SingularMass {
        pivot: None,
        bound: 0.0,
    };
    let x = l.solve_lower_triangular(&k_sym).ok_or_else(singular)?;
    let a = l
        .solve_lower_triangular(&x.transpose())
        .ok_or_else(singular)?;
    let a = (&a + a.transpose()) * 0.5;
    if a.iter().any(|v| !v.is_finite()) {
        return Err(EigenError::Overflow);
    }

    let max_niter = 100 * n + 100;
    let eig =
        SymmetricEigen::try_new(a, f64::EPSILON, max_niter).ok_or(EigenError::NoConvergence {
            iterations: max_niter,
        })?;

    // v = L⁻ᵀ·w, column by column.
    let v = l
        .tr_solve_lower_triangular(&eig.eigenvectors)
        .ok_or_else(singular)?;

    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&i, &j| eig.eigenvalues[i].total_cmp(&eig.eigenvalues[j]));

    let mut values = Vec::with_capacity(n);
    let mut vectors = Vec::with_capacity(n);
    for &c in &order {
        let lambda = eig.eigenvalues[c];
        let mut vec: Vec<f64> = v.column(c).iter().copied().collect();
        // Clean up the M-normalization with the input M.
        let mut norm2 = 0.0;
        for i in 0..n {
            for j in 0..n {
                norm2 += vec[i] * m_sym[(i, j)] * vec[j];
            }
        }
        if !norm2.is_finite() || norm2 <= 0.0 || !lambda.is_finite() {
            return Err(EigenError::Breakdown(format!(
                "eigenvalue {lambda:e} with vᵀ·M·v = {norm2:e}"
            )));
        }
        let scale = 1.0 / norm2.sqrt();
        for x in &mut vec {
            *x *= scale;
        }
        normalize_sign(&mut vec);
        if vec.iter().any(|x| !x.is_finite()) {
            return Err(EigenError::Breakdown(format!(
                "non-finite eigenvector for eigenvalue {lambda:e}"
            )));
        }
        values.push(lambda);
        vectors.push(vec);
    }
    Ok(GeneralizedEigen { values, vectors })
}

/// The eigenvalues of a real square matrix, each as often as its
/// multiplicity, in the Schur form's order.
///
/// nalgebra's `complex_eigenvalues` runs its double-shift QR iteration
/// without a bound, and without exceptional shifts it can cycle forever
/// (the Penning trap's first-order matrix at some values did). Here the
/// iteration is bounded (`SCHUR_ITERATIONS_PER_ROW` per row); when it
/// stalls, the same matrix is tried after an orthogonal similarity (same
/// eigenvalues, another iteration path), and after `SCHUR_TRIES` the
/// answer is [`EigenError::NoConvergence`].
///
/// # Errors
///
/// A matrix that is not square or has an entry that is not finite, or
/// the iteration not converging.
pub fn general_eigenvalues(a: &DMatrix<f64>) -> Result<Vec<nalgebra::Complex<f64>>, EigenError> {
    let n = a.nrows();
    if a.ncols() != n {
        return Err(EigenError::Shape(format!(
            "the matrix is {n}×{}: eigenvalues need a square matrix",
            a.ncols()
        )));
    }
    if let Some(p) = a.iter().position(|v| !v.is_finite()) {
        return Err(EigenError::NotFinite {
            matrix: "A",
            entry: (p % n.max(1), p / n.max(1)),
            value: a[p],
        });
    }
    if n == 0 {
        // nalgebra's eigenvalues of a 0×0 Schur form underflow an index
        return Ok(Vec::new());
    }
    let max_niter = SCHUR_ITERATIONS_PER_ROW * n + SCHUR_ITERATIONS_PER_ROW;
    for attempt in 0..SCHUR_TRIES {
        let m = if attempt == 0 {
            a.clone()
        } else {
            let h = reflection(n, attempt);
            &h * a * &h
        };
        if let Some(schur) = nalgebra::Schur::try_new(m, f64::EPSILON, max_niter) {
            let values: Vec<_> = schur.complex_eigenvalues().iter().copied().collect();
            if values.iter().all(|z| z.re.is_finite() && z.im.is_finite()) {
                return Ok(values);
            }
        }
    }
    Err(EigenError::NoConvergence {
        iterations: SCHUR_TRIES * max_niter,
    })
}

/// The double-shift QR iterations allowed per row of the matrix (LAPACK's
/// DHSEQR allows 30 per eigenvalue).
const SCHUR_ITERATIONS_PER_ROW: usize = 40;
/// How many matrices similar to the given one the Schur decomposition tries.
const SCHUR_TRIES: usize = 3;

/// The Householder reflection I − 2·v·vᵀ/(vᵀ·v) with v = (1, 1 + t, 1 + 2t,
/// …), its own inverse: an orthogonal similarity that moves a stalled QR
/// iteration without changing the eigenvalues or the conditioning.
fn reflection(n: usize, t: usize) -> DMatrix<f64> {
    let v: Vec<f64> = (0..n).map(|i| 1.0 + (i * t) as f64 / n as f64).collect();
    let vv: f64 = v.iter().map(|x| x * x).sum();
    DMatrix::from_fn(n, n, |i, j| {
        let id = if i == j { 1.0 } else { 0.0 };
        id - 2.0 * v[i] * v[j] / vv
    })
}

/// The textbook's "distribution coefficients" of a mode: μⱼ = xⱼ/x₁, i.e.
/// `v` divided by `v[0]` (so μ₀ = 1).
///
/// Returns `None` if `v` is empty, has a non-finite entry, or its first
/// entry is tiny relative to the others (|v₀| ≤ 1e-10·max|v|, including the
/// zero vector): then the mode does not move the first coordinate and the
/// coefficients are undefined.
///
/// # Example
///
/// ```
/// use qdot_mechanics::solve::eigen::distribution_coefficients;
/// assert_eq!(distribution_coefficients(&[2.0, -4.0]), Some(vec![1.0, -2.0]));
/// assert_eq!(distribution_coefficients(&[0.0, 1.0]), None);
/// ```
pub fn distribution_coefficients(v: &[f64]) -> Option<Vec<f64>> {
    let first = *v.first()?;
    if v.iter().any(|x| !x.is_finite()) {
        return None;
    }
    let max = v.iter().fold(0.0_f64, |a, x| a.max(x.abs()));
    if first.abs() <= DISTRIBUTION_RTOL * max {
        return None;
    }
    Some(v.iter().map(|x| x / first).collect())
}

/// Flip `v` so that its first entry with |x| > SIGN_RTOL·max|x| is positive.
fn normalize_sign(v: &mut [f64]) {
    let max = v.iter().fold(0.0_f64, |a, x| a.max(x.abs()));
    if let Some(&x) = v.iter().find(|x| x.abs() > SIGN_RTOL * max) {
        if x < 0.0 {
            for y in v.iter_mut() {
                *y = -*y;
            }
        }
    }
}

/// Every row of `x` has length `x.len()`.
fn check_square(x: &[Vec<f64>], name: &str) -> Result<(), EigenError> {
    let n = x.len();
    match x.iter().position(|row| row.len() != n) {
        Some(i) => Err(EigenError::Shape(format!(
            "{name} is not square: it has {n} rows but row {i} has {} entries",
            x[i].len()
        ))),
        None => Ok(()),
    }
}

/// Every entry of `x` is finite.
fn check_finite(x: &[Vec<f64>], name: &'static str) -> Result<(), EigenError> {
    for (i, row) in x.iter().enumerate() {
        if let Some(j) = row.iter().position(|v| !v.is_finite()) {
            return Err(EigenError::NotFinite {
                matrix: name,
                entry: (i, j),
                value: row[j],
            });
        }
    }
    Ok(())
}

/// Check |xᵢⱼ − xⱼᵢ| ≤ SYMMETRY_RTOL·max|x| for a square finite `x`, and
/// return max|x|.
fn check_symmetric(x: &[Vec<f64>], name: &'static str) -> Result<f64, EigenError> {
    let max = x
        .iter()
        .flat_map(|row| row.iter())
        .fold(0.0_f64, |a, v| a.max(v.abs()));
    let tol = SYMMETRY_RTOL * max;
    for (i, row) in x.iter().enumerate() {
        for (j, &xij) in row.iter().enumerate().take(i) {
            let xji = x[j][i];
            if (xij - xji).abs() > tol {
                return Err(EigenError::NotSymmetric {
                    matrix: name,
                    entry: (i, j),
                    values: (xij, xji),
                });
            }
        }
    }
    Ok(max)
}

/// Why the generalized eigenproblem K·v = λ·M·v was not solved. Its
/// `Display` is the message qdot prints.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum EigenError {
    /// A matrix is not square, or K and M differ in size: what is wrong.
    Shape(String),
    /// An entry is NaN or infinite.
    NotFinite {
        /// "K" or "M".
        matrix: &'static str,
        /// (row, column).
        entry: (usize, usize),
        /// The entry.
        value: f64,
    },
    /// `matrix[i][j]` and `matrix[j][i]` differ past the tolerance.
    NotSymmetric {
        /// "K" or "M".
        matrix: &'static str,
        /// (i, j) with j < i.
        entry: (usize, usize),
        /// (`matrix[i][j]`, `matrix[j][i]`).
        values: (f64, f64),
    },
    /// M is not positive definite: its Cholesky factorization failed.
    NotPositiveDefinite,
    /// M is numerically singular: its smallest Cholesky pivot, when
    /// there is one, is at most `bound` (a relative tolerance times max|M|).
    SingularMass {
        /// The smallest pivot; `None` for a zero pivot met in a solve.
        pivot: Option<f64>,
        /// The pivot's lower bound.
        bound: f64,
    },
    /// L⁻¹·K·L⁻ᵀ overflowed: K is too large relative to M.
    Overflow,
    /// The QR iteration did not converge.
    NoConvergence {
        /// The iterations allowed.
        iterations: usize,
    },
    /// An eigenpair came out non-finite: which.
    Breakdown(String),
}

impl std::fmt::Display for EigenError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            EigenError::Shape(what) => f.write_str(what),
            EigenError::NotFinite {
                matrix,
                entry: (i, j),
                value,
            } => write!(f, "{matrix}[{i}][{j}] = {value} is not finite"),
            EigenError::NotSymmetric {
                matrix: m,
                entry: (i, j),
                values: (a, b),
            } => write!(
                f,
                "{m} is not symmetric: {m}[{i}][{j}] = {a} but {m}[{j}][{i}] = {b}"
            ),
            EigenError::NotPositiveDefinite => {
                f.write_str("M is not positive definite (Cholesky factorization failed)")
            }
            EigenError::SingularMass {
                pivot: Some(p),
                bound,
            } => write!(
                f,
                "M is numerically singular (smallest Cholesky pivot {p:e} ≤ {SINGULAR_RTOL:e}·max|M| = {bound:e})"
            ),
            EigenError::SingularMass { pivot: None, .. } => {
                f.write_str("M is numerically singular (zero Cholesky pivot)")
            }
            EigenError::Overflow => {
                f.write_str("overflow: L⁻¹·K·L⁻ᵀ is not finite (K too large relative to M)")
            }
            EigenError::NoConvergence { iterations } => write!(
                f,
                "the QR iteration for the eigenvalues did not converge in {iterations} iterations"
            ),
            EigenError::Breakdown(what) => write!(f, "numerical breakdown: {what}"),
        }
    }
}

impl std::error::Error for EigenError {}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::SplitMix64;

    const SQRT2: f64 = std::f64::consts::SQRT_2;

    fn mat(rows: &[&[f64]]) -> Vec<Vec<f64>> {
        rows.iter().map(|r| r.to_vec()).collect()
    }

    fn identity(n: usize) -> Vec<Vec<f64>> {
        (0..n)
            .map(|i| (0..n).map(|j| if i == j { 1.0 } else { 0.0 }).collect())
            .collect()
    }

    fn mul(a: &[Vec<f64>], v: &[f64]) -> Vec<f64> {
        a.iter()
            .map(|row| row.iter().zip(v).map(|(x, y)| x * y).sum())
            .collect()
    }

    fn dot(a: &[f64], b: &[f64]) -> f64 {
        a.iter().zip(b).map(|(x, y)| x * y).sum()
    }

    fn norm(a: &[f64]) -> f64 {
        dot(a, a).sqrt()
    }

    fn frobenius(a: &[Vec<f64>]) -> f64 {
        a.iter().flatten().map(|x| x * x).sum::<f64>().sqrt()
    }

    fn assert_close(got: f64, want: f64, tol: f64) {
        assert!(
            (got - want).abs() <= tol,
            "got {got:.17e}, want {want:.17e} (|diff| = {:e} > {tol:e})",
            (got - want).abs()
        );
    }

    fn assert_vec_close(got: &[f64], want: &[f64], tol: f64) {
        assert_eq!(got.len(), want.len(), "{got:?} vs {want:?}");
        for (g, w) in got.iter().zip(want) {
            assert_close(*g, *w, tol);
        }
    }

    /// Checks every documented property of a decomposition: ascending order,
    /// M-orthonormality, residual, sign convention. Returns the largest
    /// relative residual and orthonormality error seen.
    fn check_decomposition(k: &[Vec<f64>], m: &[Vec<f64>], e: &GeneralizedEigen) -> (f64, f64) {
        let n = m.len();
        assert_eq!(e.values.len(), n);
        assert_eq!(e.vectors.len(), n);
        for w in e.values.windows(2) {
            assert!(w[0] <= w[1], "not ascending: {:?}", e.values);
        }
        let (kf, mf) = (frobenius(k), frobenius(m));
        let mut worst_res = 0.0_f64;
        let mut worst_orth = 0.0_f64;
        for (i, (lambda, v)) in e.values.iter().zip(&e.vectors).enumerate() {
            assert_eq!(v.len(), n);
            // Sign convention.
            let max = v.iter().fold(0.0_f64, |a, x| a.max(x.abs()));
            let first = v.iter().find(|x| x.abs() > 1e-12 * max).unwrap();
            assert!(*first > 0.0, "sign not normalized: {v:?}");
            // Residual ‖K v − λ M v‖ ≤ 1e-12·(‖K‖ + |λ|·‖M‖)·‖v‖.
            let kv = mul(k, v);
            let mv = mul(m, v);
            let r: Vec<f64> = kv.iter().zip(&mv).map(|(a, b)| a - lambda * b).collect();
            let scale = (kf + lambda.abs() * mf) * norm(v);
            let rel = norm(&r) / scale;
            assert!(rel <= 1e-12, "residual {rel:e} for λ = {lambda}");
            worst_res = worst_res.max(rel);
            // M-orthonormality.
            for (j, w) in e.vectors.iter().enumerate() {
                let g = dot(v, &mul(m, w));
                let want = if i == j { 1.0 } else { 0.0 };
                let err = (g - want).abs();
                assert!(err <= 1e-12, "v{i}ᵀ·M·v{j} = {g:e}");
                worst_orth = worst_orth.max(err);
            }
        }
        (worst_res, worst_orth)
    }

    #[test]
    fn one_by_one() {
        let k = mat(&[&[3.0]]);
        let m = mat(&[&[2.0]]);
        let e = generalized_symmetric(&k, &m).unwrap();
        assert_vec_close(&e.values, &[1.5], 1e-15);
        assert_vec_close(&e.vectors[0], &[1.0 / SQRT2], 1e-15);
        check_decomposition(&k, &m, &e);
    }

    #[test]
    fn one_by_one_negative_stiffness_flips_no_sign() {
        // Inverted pendulum, one coordinate: λ = −g/l < 0; vector stays positive.
        let e = generalized_symmetric(&mat(&[&[-9.81]]), &mat(&[&[1.0]])).unwrap();
        assert_vec_close(&e.values, &[-9.81], 1e-15);
        assert_vec_close(&e.vectors[0], &[1.0], 1e-15);
    }

    #[test]
    fn seed_24_2_two_masses() {
        let m = mat(&[&[4.0, 0.0], &[0.0, 1.5]]);
        let k = mat(&[&[2.0, -1.0], &[-1.0, 1.0]]);
        let e = generalized_symmetric(&k, &m).unwrap();
        assert_vec_close(&e.values, &[1.0 / 6.0, 1.0], 1e-12);
        let mu0 = distribution_coefficients(&e.vectors[0]).unwrap();
        let mu1 = distribution_coefficients(&e.vectors[1]).unwrap();
        assert_vec_close(&mu0, &[1.0, 4.0 / 3.0], 1e-12);
        assert_vec_close(&mu1, &[1.0, -2.0], 1e-12);
        // M-normalization: x₁²·(4 + 1.5·μ²) = 1.
        assert_close(
            e.vectors[0][0],
            1.0 / (4.0 + 1.5 * 16.0 / 9.0_f64).sqrt(),
            1e-12,
        );
        assert_close(e.vectors[1][0], 1.0 / (4.0 + 1.5 * 4.0_f64).sqrt(), 1e-12);
        check_decomposition(&k, &m, &e);
    }

    #[test]
    fn three_mass_chain() {
        let k = mat(&[&[2.0, -1.0, 0.0], &[-1.0, 2.0, -1.0], &[0.0, -1.0, 2.0]]);
        let m = identity(3);
        let e = generalized_symmetric(&k, &m).unwrap();
        assert_vec_close(&e.values, &[2.0 - SQRT2, 2.0, 2.0 + SQRT2], 1e-12);
        let modes = [[1.0, SQRT2, 1.0], [1.0, 0.0, -1.0], [1.0, -SQRT2, 1.0]];
        for (v, want) in e.vectors.iter().zip(&modes) {
            assert_vec_close(&distribution_coefficients(v).unwrap(), want, 1e-12);
            // Normalized: ‖v‖ = 1 since M = I, and v₀ > 0.
            assert_close(norm(v), 1.0, 1e-12);
            assert!(v[0] > 0.0);
        }
        assert_vec_close(&e.vectors[0], &[0.5, SQRT2 / 2.0, 0.5], 1e-12);
        check_decomposition(&k, &m, &e);
    }

    #[test]
    fn double_pendulum() {
        // m = l = g = 1: T = ½(2φ̇₁² + 2φ̇₁φ̇₂ + φ̇₂²), V ≈ ½(2φ₁² + φ₂²).
        let m = mat(&[&[2.0, 1.0], &[1.0, 1.0]]);
        let k = mat(&[&[2.0, 0.0], &[0.0, 1.0]]);
        let e = generalized_symmetric(&k, &m).unwrap();
        assert_vec_close(&e.values, &[2.0 - SQRT2, 2.0 + SQRT2], 1e-12);
        // (2 − 2λ)·x₁ = λ·x₂ ⇒ μ = (2 − 2λ)/λ = ±√2.
        let mu0 = distribution_coefficients(&e.vectors[0]).unwrap();
        let mu1 = distribution_coefficients(&e.vectors[1]).unwrap();
        assert_vec_close(&mu0, &[1.0, SQRT2], 1e-12);
        assert_vec_close(&mu1, &[1.0, -SQRT2], 1e-12);
        check_decomposition(&k, &m, &e);
    }

    #[test]
    fn indefinite_stiffness_gives_negative_eigenvalue() {
        // Double pendulum with the upper rod inverted: det(K − λM) = λ² − 2.
        let m = mat(&[&[2.0, 1.0], &[1.0, 1.0]]);
        let k = mat(&[&[-2.0, 0.0], &[0.0, 1.0]]);
        let e = generalized_symmetric(&k, &m).unwrap();
        assert_vec_close(&e.values, &[-SQRT2, SQRT2], 1e-12);
        assert!(e.values[0] < 0.0);
        check_decomposition(&k, &m, &e);

        // Fully inverted double pendulum: both modes unstable, λ = −(2 ± √2).
        let k = mat(&[&[-2.0, 0.0], &[0.0, -1.0]]);
        let e = generalized_symmetric(&k, &m).unwrap();
        assert_vec_close(&e.values, &[-2.0 - SQRT2, -2.0 + SQRT2], 1e-12);
        check_decomposition(&k, &m, &e);
    }

    #[test]
    fn repeated_eigenvalue() {
        let m = mat(&[&[2.0, 0.0, 0.0], &[0.0, 2.0, 0.0], &[0.0, 0.0, 2.0]]);
        let k = mat(&[&[6.0, 0.0, 0.0], &[0.0, 6.0, 0.0], &[0.0, 0.0, 6.0]]);
        let e = generalized_symmetric(&k, &m).unwrap();
        assert_vec_close(&e.values, &[3.0, 3.0, 3.0], 1e-12);
        check_decomposition(&k, &m, &e);
        // Zero stiffness: all λ = 0 (free motion).
        let e = generalized_symmetric(&mat(&[&[0.0, 0.0], &[0.0, 0.0]]), &identity(2)).unwrap();
        assert_vec_close(&e.values, &[0.0, 0.0], 0.0);
    }

    #[test]
    fn tiny_asymmetry_within_tolerance_is_accepted() {
        let m = mat(&[&[4.0, 1e-13], &[0.0, 1.5]]);
        let k = mat(&[&[2.0, -1.0], &[-1.0 + 1e-13, 1.0]]);
        let e = generalized_symmetric(&k, &m).unwrap();
        assert_vec_close(&e.values, &[1.0 / 6.0, 1.0], 1e-12);
    }

    #[test]
    fn scaling_is_harmless() {
        // Same as seed 24.2 with M·1e-100 and K·1e100: λ·1e200.
        let m = mat(&[&[4e-100, 0.0], &[0.0, 1.5e-100]]);
        let k = mat(&[&[2e100, -1e100], &[-1e100, 1e100]]);
        let e = generalized_symmetric(&k, &m).unwrap();
        assert_close(e.values[0] / 1e200, 1.0 / 6.0, 1e-12);
        assert_close(e.values[1] / 1e200, 1.0, 1e-12);
        let mu1 = distribution_coefficients(&e.vectors[1]).unwrap();
        assert_vec_close(&mu1, &[1.0, -2.0], 1e-12);
    }

    /// An n×n matrix of entries uniform in [−1, 1).
    fn random_matrix(rng: &mut SplitMix64, n: usize) -> Vec<Vec<f64>> {
        (0..n)
            .map(|_| (0..n).map(|_| rng.uniform(-1.0, 1.0)).collect())
            .collect()
    }

    #[test]
    fn random_spd_m_and_symmetric_k() {
        let mut rng = SplitMix64::new(0x9E37_79B9_7F4A_7C15);
        let mut worst = (0.0_f64, 0.0_f64);
        let mut negatives = 0;
        for n in 1..=12 {
            for _ in 0..4 {
                // M = AᵀA + n·I (SPD), K = (B + Bᵀ)/2·s (symmetric, indefinite in general).
                let a = random_matrix(&mut rng, n);
                let b = random_matrix(&mut rng, n);
                let s = 10f64.powi(rng.below(7) as i32 - 3);
                let m: Vec<Vec<f64>> = (0..n)
                    .map(|i| {
                        (0..n)
                            .map(|j| {
                                let ata: f64 = (0..n).map(|r| a[r][i] * a[r][j]).sum();
                                ata + if i == j { n as f64 } else { 0.0 }
                            })
                            .collect()
                    })
                    .collect();
                let k: Vec<Vec<f64>> = (0..n)
                    .map(|i| (0..n).map(|j| 0.5 * (b[i][j] + b[j][i]) * s).collect())
                    .collect();
                let e = generalized_symmetric(&k, &m).unwrap();
                let (res, orth) = check_decomposition(&k, &m, &e);
                worst = (worst.0.max(res), worst.1.max(orth));
                negatives += e.values.iter().filter(|l| **l < 0.0).count();
                // Σλ = tr(M⁻¹K) = tr(A) is a cheap independent check: compare
                // with Σ vᵢᵀ·K·vᵢ (= Σλᵢ for M-orthonormal eigenvectors).
                let sum: f64 = e.values.iter().sum();
                let rayleigh: f64 = e.vectors.iter().map(|v| dot(v, &mul(&k, v))).sum();
                assert_close(sum, rayleigh, 1e-12 * s * n as f64);
            }
        }
        // The random K are indefinite: unstable directions must show up.
        assert!(negatives > 0);
        eprintln!(
            "random: worst relative residual {:e}, worst M-orthonormality error {:e}",
            worst.0, worst.1
        );
    }

    #[test]
    fn deterministic_output() {
        let m = mat(&[&[2.0, 1.0], &[1.0, 1.0]]);
        let k = mat(&[&[2.0, 0.0], &[0.0, 1.0]]);
        let a = generalized_symmetric(&k, &m).unwrap();
        let b = generalized_symmetric(&k, &m).unwrap();
        assert_eq!(a.values, b.values);
        assert_eq!(a.vectors, b.vectors);
    }

    #[test]
    fn empty_problem_has_no_modes() {
        let e = generalized_symmetric(&[], &[]).unwrap();
        assert!(e.values.is_empty());
        assert!(e.vectors.is_empty());
    }

    fn err(k: &[Vec<f64>], m: &[Vec<f64>]) -> String {
        match generalized_symmetric(k, m) {
            Ok(e) => panic!("expected an error, got {e:?}"),
            Err(e) => e.to_string(),
        }
    }

    #[test]
    fn error_m_not_positive_definite() {
        let k = identity(2);
        // Indefinite.
        let msg = err(&k, &mat(&[&[1.0, 2.0], &[2.0, 1.0]]));
        assert!(msg.contains("positive definite"), "{msg}");
        // Negative.
        let msg = err(&mat(&[&[1.0]]), &mat(&[&[-1.0]]));
        assert!(msg.contains("positive definite"), "{msg}");
        // Zero.
        let msg = err(&k, &mat(&[&[0.0, 0.0], &[0.0, 0.0]]));
        assert!(
            msg.contains("positive definite") || msg.contains("singular"),
            "{msg}"
        );
        // Semidefinite (rank 1).
        let msg = err(&k, &mat(&[&[1.0, 1.0], &[1.0, 1.0]]));
        assert!(
            msg.contains("positive definite") || msg.contains("singular"),
            "{msg}"
        );
        // Semidefinite up to rounding: 0.1 + 0.2 ≠ 0.3 leaves a ~1e-17 pivot.
        let (a, b) = (0.1, 0.2);
        let msg = err(&k, &mat(&[&[a * a, a * b], &[a * b, b * b]]));
        assert!(
            msg.contains("positive definite") || msg.contains("singular"),
            "{msg}"
        );
        // Positive definite in floating point, but numerically singular:
        // the second Cholesky pivot is 1e-15 (Cholesky itself succeeds).
        let msg = err(&k, &mat(&[&[1.0, 1.0], &[1.0, 1.0 + 1e-15]]));
        assert!(msg.contains("numerically singular"), "{msg}");
        // A badly scaled but well-conditioned M is fine (pivots relative to max|M|).
        let e = generalized_symmetric(&k, &mat(&[&[1e-20, 0.0], &[0.0, 2e-20]])).unwrap();
        assert_vec_close(&e.values, &[0.5e20, 1e20], 1e8);
    }

    #[test]
    fn error_non_square_or_mismatched() {
        let m2 = identity(2);
        let k2 = identity(2);
        // Ragged row in M.
        let msg = err(&k2, &mat(&[&[1.0, 0.0], &[0.0]]));
        assert!(msg.contains("M is not square"), "{msg}");
        // 2×3 K.
        let msg = err(&mat(&[&[1.0, 0.0, 0.0], &[0.0, 1.0, 0.0]]), &m2);
        assert!(msg.contains("K is not square"), "{msg}");
        // Sizes differ.
        let msg = err(&identity(3), &m2);
        assert!(msg.contains("same size"), "{msg}");
        let msg = err(&k2, &identity(1));
        assert!(msg.contains("same size"), "{msg}");
        let msg = err(&[], &m2);
        assert!(msg.contains("same size"), "{msg}");
    }

    #[test]
    fn error_non_finite() {
        let msg = err(&mat(&[&[1.0, f64::NAN], &[0.0, 1.0]]), &identity(2));
        assert!(
            msg.contains("K[0][1]") && msg.contains("not finite"),
            "{msg}"
        );
        let msg = err(&identity(2), &mat(&[&[1.0, 0.0], &[0.0, f64::INFINITY]]));
        assert!(
            msg.contains("M[1][1]") && msg.contains("not finite"),
            "{msg}"
        );
        let msg = err(&mat(&[&[f64::NEG_INFINITY]]), &mat(&[&[1.0]]));
        assert!(msg.contains("not finite"), "{msg}");
    }

    #[test]
    fn error_not_symmetric() {
        let msg = err(&identity(2), &mat(&[&[2.0, 1.0], &[0.0, 2.0]]));
        assert!(msg.contains("M is not symmetric"), "{msg}");
        let msg = err(&mat(&[&[2.0, 1e-6], &[0.0, 2.0]]), &identity(2));
        assert!(msg.contains("K is not symmetric"), "{msg}");
    }

    #[test]
    fn error_overflow() {
        let msg = err(&mat(&[&[1e300]]), &mat(&[&[1e-300]]));
        assert!(msg.contains("overflow"), "{msg}");
    }

    /// The first-order matrix of the Penning trap (m = e = V0 = 1,
    /// d = 0.45, B = 3) on which nalgebra's unbounded Schur iteration
    /// cycled forever: bounded, it converges on a similar matrix, and the
    /// eigenvalues are the exact ones, s = ±i/d (axial) and
    /// s = ±i·B/2 ± √(2/d² − B²)/2 (radial: unstable).
    #[test]
    fn the_penning_trap_matrix_that_stalled_the_schur_iteration() {
        let (d, b) = (0.45f64, 3.0f64);
        let kr = -1.0 / (2.0 * d * d);
        let kz = 1.0 / (d * d);
        #[rustfmt::skip]
        let a = DMatrix::from_row_slice(6, 6, &[
            0.0, 0.0, 0.0, 1.0, 0.0, 0.0,
            0.0, 0.0, 0.0, 0.0, 1.0, 0.0,
            0.0, 0.0, 0.0, 0.0, 0.0, 1.0,
            -kr, 0.0, 0.0, 0.0, b, 0.0,
            0.0, -kr, 0.0, -b, 0.0, 0.0,
            0.0, 0.0, -kz, 0.0, 0.0, 0.0,
        ]);
        // nalgebra's own iteration stalls on it (this fails when that is
        // fixed; the retries stay harmless)
        assert!(nalgebra::Schur::try_new(a.clone(), f64::EPSILON, 100_000).is_none());
        let mut s = general_eigenvalues(&a).unwrap();
        s.sort_by(|x, y| x.re.total_cmp(&y.re).then(x.im.total_cmp(&y.im)));
        let g = (2.0 / (d * d) - b * b).sqrt() / 2.0;
        let want = [
            (-g, -b / 2.0),
            (-g, b / 2.0),
            (0.0, -1.0 / d),
            (0.0, 1.0 / d),
            (g, -b / 2.0),
            (g, b / 2.0),
        ];
        for (z, (re, im)) in s.iter().zip(want) {
            assert_close(z.re, re, 1e-9);
            assert_close(z.im, im, 1e-9);
        }
    }

    #[test]
    fn general_eigenvalues_refuse_what_is_not_a_square_finite_matrix() {
        let e = general_eigenvalues(&DMatrix::zeros(2, 3)).unwrap_err();
        assert_eq!(
            e.to_string(),
            "the matrix is 2×3: eigenvalues need a square matrix"
        );
        let mut a = DMatrix::<f64>::zeros(2, 2);
        a[(1, 0)] = f64::NAN;
        assert_eq!(
            general_eigenvalues(&a).unwrap_err().to_string(),
            "A[1][0] = NaN is not finite"
        );
        assert!(general_eigenvalues(&DMatrix::zeros(0, 0))
            .unwrap()
            .is_empty());
    }

    #[test]
    fn distribution_coefficients_cases() {
        assert_eq!(
            distribution_coefficients(&[2.0, -4.0, 1.0]),
            Some(vec![1.0, -2.0, 0.5])
        );
        assert_eq!(distribution_coefficients(&[-3.0]), Some(vec![1.0]));
        assert_eq!(distribution_coefficients(&[]), None);
        assert_eq!(distribution_coefficients(&[0.0, 1.0]), None);
        assert_eq!(distribution_coefficients(&[1e-17, 1.0]), None);
        assert_eq!(distribution_coefficients(&[0.0, 0.0]), None);
        assert_eq!(distribution_coefficients(&[1.0, f64::NAN]), None);
        assert_eq!(distribution_coefficients(&[f64::INFINITY, 1.0]), None);
    }
}
