//! Dense f64 linear algebra for M·q̈ = f.

use super::error::CompileError;

/// Solve M·x = f in place for a symmetric M (n×n, row-major, both
/// triangles filled): Cholesky M = L·Lᵀ (Golub & Van Loan, Matrix
/// Computations, 4.2.5), and when M is not numerically positive definite
/// Gaussian elimination with partial pivoting (3.4) on the restored M.
/// The solution replaces `f`; `m` is overwritten. Allocation-free.
/// An error when M is numerically singular (a zero pivot).
pub fn solve_spd(m: &mut [f64], f: &mut [f64], n: usize) -> Result<(), CompileError> {
    if m.len() < n * n || f.len() < n {
        return Err(CompileError::Shape(format!(
            "solve_spd: a {n}×{n} system needs {} and {n} values",
            n * n
        )));
    }
    match cholesky(m, n) {
        Ok(()) => {
            cholesky_solve(m, f, n);
            Ok(())
        }
        Err(j) => {
            restore(m, n, j);
            gauss_solve(m, f, n)
        }
    }
}

/// In-place Cholesky: L into the lower triangle and the diagonal, the
/// strict upper triangle untouched. Err(j) when the pivot of column j is
/// not positive (columns < j are then factored, column j untouched).
fn cholesky(a: &mut [f64], n: usize) -> Result<(), usize> {
    let dot = |x: &[f64], y: &[f64]| -> f64 { x.iter().zip(y).map(|(p, q)| p * q).sum() };
    for j in 0..n {
        let (done, rest) = a[..n * n].split_at_mut((j + 1) * n);
        let row_j = &mut done[j * n..];
        let d = row_j[j] - dot(&row_j[..j], &row_j[..j]);
        if d.is_nan() || d <= 0.0 {
            return Err(j);
        }
        let d = d.sqrt();
        row_j[j] = d;
        let (lj, inv) = (&row_j[..j], 1.0 / d);
        for row_i in rest.chunks_exact_mut(n) {
            row_i[j] = (row_i[j] - dot(&row_i[..j], lj)) * inv;
        }
    }
    Ok(())
}

fn cholesky_solve(l: &[f64], b: &mut [f64], n: usize) {
    for i in 0..n {
        let row = &l[i * n..i * n + i];
        let s: f64 = row.iter().zip(&b[..i]).map(|(p, q)| p * q).sum();
        b[i] = (b[i] - s) / l[i * n + i];
    }
    for i in (0..n).rev() {
        let mut s = b[i];
        for k in i + 1..n {
            s -= l[k * n + i] * b[k];
        }
        b[i] = s / l[i * n + i];
    }
}

/// Undo a Cholesky factorization that failed at column `j`: the diagonal
/// entries k < j from the rows of L (M_kk = Σ L_ki²), the lower triangle
/// from the untouched upper one.
fn restore(a: &mut [f64], n: usize, j: usize) {
    for k in 0..j.min(n) {
        let s: f64 = (0..=k).map(|i| a[k * n + i] * a[k * n + i]).sum();
        a[k * n + k] = s;
    }
    for i in 0..n {
        for k in 0..i {
            a[i * n + k] = a[k * n + i];
        }
    }
}

/// Gaussian elimination with partial pivoting on (a | b), in place.
fn gauss_solve(a: &mut [f64], b: &mut [f64], n: usize) -> Result<(), CompileError> {
    for j in 0..n {
        let p = (j..n)
            .max_by(|&x, &y| a[x * n + j].abs().total_cmp(&a[y * n + j].abs()))
            .unwrap_or(j);
        let piv = a[p * n + j];
        if piv == 0.0 || !piv.is_finite() {
            return Err(CompileError::Singular {
                column: j,
                constant_mass: false,
            });
        }
        if p != j {
            for k in 0..n {
                a.swap(j * n + k, p * n + k);
            }
            b.swap(j, p);
        }
        for i in j + 1..n {
            let f = a[i * n + j] / piv;
            if f != 0.0 {
                for k in j + 1..n {
                    a[i * n + k] -= f * a[j * n + k];
                }
                b[i] -= f * b[j];
            }
        }
    }
    for i in (0..n).rev() {
        let mut s = b[i];
        for k in i + 1..n {
            s -= a[i * n + k] * b[k];
        }
        b[i] = s / a[i * n + i];
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solve_spd_cholesky_and_fallback() {
        // SPD: [[4, 2], [2, 3]]·x = [2, 1] → x = [1/2, 0].
        let mut m = vec![4.0, 2.0, 2.0, 3.0];
        let mut f = vec![2.0, 1.0];
        solve_spd(&mut m, &mut f, 2).unwrap();
        assert!((f[0] - 0.5).abs() < 1e-15 && f[1].abs() < 1e-15);
        // Symmetric indefinite: [[1, 2], [2, 1]]·x = [3, 3] → x = [1, 1];
        // Cholesky fails at column 1 and the diagonal is restored.
        let mut m = vec![1.0, 2.0, 2.0, 1.0];
        let mut f = vec![3.0, 3.0];
        solve_spd(&mut m, &mut f, 2).unwrap();
        assert!((f[0] - 1.0).abs() < 1e-15 && (f[1] - 1.0).abs() < 1e-15);
        // Zero first pivot: [[0, 1], [1, 0]]·x = [2, 5] → x = [5, 2].
        let mut m = vec![0.0, 1.0, 1.0, 0.0];
        let mut f = vec![2.0, 5.0];
        solve_spd(&mut m, &mut f, 2).unwrap();
        assert_eq!(f, vec![5.0, 2.0]);
        // Singular.
        let mut m = vec![1.0, 1.0, 1.0, 1.0];
        let mut f = vec![1.0, 2.0];
        assert_eq!(
            solve_spd(&mut m, &mut f, 2),
            Err(CompileError::Singular {
                column: 1,
                constant_mass: false
            })
        );
        assert!(matches!(
            solve_spd(&mut m, &mut f, 3),
            Err(CompileError::Shape(_))
        ));
    }

    #[test]
    fn restore_recovers_the_matrix() {
        // 3×3 with positive leading 2×2 minor but indefinite.
        let orig = [2.0, 1.0, 3.0, 1.0, 2.0, 1.0, 3.0, 1.0, 1.0];
        let mut a = orig;
        let j = cholesky(&mut a, 3).unwrap_err();
        assert_eq!(j, 2);
        restore(&mut a, 3, j);
        for (x, y) in a.iter().zip(&orig) {
            assert!((x - y).abs() < 1e-14, "{a:?}");
        }
    }
}
