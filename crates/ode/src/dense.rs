//! Dense linear algebra in floating point: the one home of qdot's
//! numeric solvers. LU with partial pivoting, real or complex (the
//! implicit integrators' Newton systems, Newton's method for equilibria,
//! determinants of numeric Hessians), and the symmetric solve of
//! M·q̈ = f (Cholesky, LU as fallback) for the compiled dynamics.
//!
//! Floats only: nothing here enters an exact result.

pub use nalgebra::Complex;
use std::ops::{Add, Div, Mul, Sub};

/// Why a dense solve failed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DenseError {
    /// The slices are shorter than an n×n system needs.
    Shape {
        /// The size asked for.
        n: usize,
    },
    /// The matrix is singular to working precision: a zero (or not
    /// finite) pivot in `column`.
    Singular {
        /// The column of the pivot.
        column: usize,
    },
}

impl std::fmt::Display for DenseError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            DenseError::Shape { n } => write!(
                f,
                "solve_spd: a {n}×{n} system needs {} and {n} values",
                n * n
            ),
            DenseError::Singular { column } => {
                write!(f, "the matrix is singular (column {column})")
            }
        }
    }
}

impl std::error::Error for DenseError {}

/// The scalars of [`Lu`]: `f64` and `Complex<f64>`.
pub trait Scalar:
    Copy + Add<Output = Self> + Sub<Output = Self> + Mul<Output = Self> + Div<Output = Self>
{
    /// A magnitude for pivoting (|re| + |im| for complex, as LINPACK's
    /// ZGEFA).
    fn mag(self) -> f64;

    /// self / d, bit for bit.
    fn quotient(self, d: Self) -> Self {
        self / d
    }
}

impl Scalar for f64 {
    fn mag(self) -> f64 {
        self.abs()
    }
}

impl Scalar for Complex<f64> {
    fn mag(self) -> f64 {
        self.re.abs() + self.im.abs()
    }

    /// num-complex's division (x·d̄ / |d|²), without its two divisions
    /// when x is zero and |d|² positive: a signed zero over a positive
    /// number is that zero (the zeros below a banded matrix's pivots).
    fn quotient(self, d: Self) -> Self {
        let norm_sqr = d.re * d.re + d.im * d.im;
        let re = self.re * d.re + self.im * d.im;
        let im = self.im * d.re - self.re * d.im;
        if self.re == 0.0 && self.im == 0.0 && norm_sqr > 0.0 {
            Complex::new(re, im)
        } else {
            Complex::new(re / norm_sqr, im / norm_sqr)
        }
    }
}

/// A square matrix (row-major) and, after [`Lu::factor`], its LU factors
/// P·A = L·U (unit lower L below the diagonal, U on and above).
pub struct Lu<T> {
    n: usize,
    /// The matrix, row-major, to fill before [`Lu::factor`]; its factors after.
    pub a: Vec<T>,
    piv: Vec<usize>,
    /// Scratch of [`solve_complex_scaled`]: the columns' powers of two,
    /// their largest entries.
    column_scale: Vec<i32>,
    column_big: Vec<f64>,
}

impl<T: Scalar> Lu<T> {
    /// An n×n matrix of zeros.
    pub fn new(n: usize, zero: T) -> Self {
        Lu {
            n,
            a: vec![zero; n * n],
            piv: vec![0; n],
            column_scale: vec![0; n],
            column_big: vec![0.0; n],
        }
    }

    /// Factor in place (Golub & Van Loan, Algorithm 3.4.1). False when a
    /// pivot is zero or not finite (the matrix is singular to working
    /// precision).
    pub fn factor(&mut self) -> bool {
        self.factor_above(0.0)
    }

    /// [`Lu::factor`], failing also on a pivot of magnitude ≤ `tiny` (a
    /// relative singularity test).
    pub fn factor_above(&mut self, tiny: f64) -> bool {
        let n = self.n;
        let a = &mut self.a[..n * n];
        for k in 0..n {
            let mut p = k;
            let mut best = a[k * n + k].mag();
            for i in k + 1..n {
                let v = a[i * n + k].mag();
                if v > best {
                    best = v;
                    p = i;
                }
            }
            self.piv[k] = p;
            if best <= tiny || !best.is_finite() {
                return false;
            }
            if p != k {
                let (above, from_p) = a.split_at_mut(p * n);
                above[k * n..(k + 1) * n].swap_with_slice(&mut from_p[..n]);
            }
            // rows as slices: the same operations in the same order, without
            // an index check per entry
            let (to_k, below) = a.split_at_mut((k + 1) * n);
            let row_k = &to_k[k * n..];
            let pivot = row_k[k];
            for row_i in below.chunks_exact_mut(n) {
                let l = row_i[k].quotient(pivot);
                row_i[k] = l;
                if l.mag() != 0.0 {
                    for (x, &u) in row_i[k + 1..].iter_mut().zip(&row_k[k + 1..]) {
                        *x = *x - l * u;
                    }
                }
            }
        }
        true
    }

    /// Solve A·x = b in place (after a successful [`Lu::factor`]).
    pub fn solve(&self, b: &mut [T]) {
        let n = self.n;
        let a = &self.a;
        for k in 0..n {
            let p = self.piv[k];
            if p != k {
                b.swap(k, p);
            }
        }
        for i in 0..n {
            let mut s = b[i];
            for (&l, &x) in a[i * n..i * n + i].iter().zip(&b[..i]) {
                s = s - l * x;
            }
            b[i] = s;
        }
        for i in (0..n).rev() {
            let mut s = b[i];
            for (&u, &x) in a[i * n + i + 1..(i + 1) * n].iter().zip(&b[i + 1..n]) {
                s = s - u * x;
            }
            b[i] = s / a[i * n + i];
        }
    }
}

impl Lu<f64> {
    /// The determinant, after a [`Lu::factor`] that succeeded: the product
    /// of U's diagonal, negated per row swap.
    pub fn determinant(&self) -> f64 {
        let n = self.n;
        let mut d = 1.0;
        for k in 0..n {
            if self.piv[k] != k {
                d = -d;
            }
            d *= self.a[k * n + k];
        }
        d
    }
}

/// 2^e·x without overflow of 2^e itself (|e| up to the whole exponent
/// range of f64): exact unless the result is subnormal or out of range.
fn scaled_by_power_of_two(mut x: f64, mut e: i32) -> f64 {
    let big = power_of_two(STEP);
    while e > STEP {
        x *= big;
        e -= STEP;
    }
    while e < -STEP {
        x /= big;
        e += STEP;
    }
    x * power_of_two(e)
}

/// The largest power of two [`scaled_by_power_of_two`] multiplies by at once.
const STEP: i32 = 1000;

/// 2^e for −1022 ≤ e ≤ 1023, from its bits (a normal double).
fn power_of_two(e: i32) -> f64 {
    debug_assert!((-1022..=1023).contains(&e));
    f64::from_bits(((e + 1023) as u64) << 52)
}

/// The e with 2^(e−1) ≤ x < 2^e for a positive finite x (0 for anything
/// else): the power of two that brings x into [1/2, 1), read off the bits.
fn binary_exponent(x: f64) -> i32 {
    if !(x > 0.0 && x.is_finite()) {
        return 0;
    }
    let bits = x.to_bits();
    let biased = (bits >> 52) as i32;
    if biased == 0 {
        // subnormal: x = f·2^-1074, 2^(b−1074) ≤ x < 2^(b−1073) for f's top bit b
        return (63 - bits.leading_zeros() as i32) - 1073;
    }
    biased - 1022
}

/// The larger of |re| and |im|: a magnitude that cannot overflow.
fn max_part(z: Complex<f64>) -> f64 {
    z.re.abs().max(z.im.abs())
}

/// [`max_part`] of a finite z (no NaN to rule on).
fn finite_max_part(z: Complex<f64>) -> f64 {
    let (re, im) = (z.re.abs(), z.im.abs());
    if im > re {
        im
    } else {
        re
    }
}

/// The largest [`max_part`] of the finite entries of `row`.
fn largest(row: &[Complex<f64>]) -> f64 {
    let mut big = 0.0f64;
    for &z in row {
        let m = finite_max_part(z);
        if m > big {
            big = m;
        }
    }
    big
}

/// [`scale_complex`] of every entry of `row` by the one power 2^e.
fn scale_row(row: &mut [Complex<f64>], e: i32) {
    if (-STEP..=STEP).contains(&e) {
        let f = power_of_two(e);
        for z in row {
            *z = Complex::new(z.re * f, z.im * f);
        }
    } else {
        for z in row {
            *z = scale_complex(*z, e);
        }
    }
}

fn scale_complex(z: Complex<f64>, e: i32) -> Complex<f64> {
    Complex::new(
        scaled_by_power_of_two(z.re, e),
        scaled_by_power_of_two(z.im, e),
    )
}

/// Solve A·x = b in place for a complex A of any scale (`lu.a` filled,
/// row-major; b of length n). The rows, then the columns of A, and b are
/// scaled by powers of two (exactly) so that each one's largest entry lies
/// in [1/2, 1); the scaled system is factored by [`Lu`] with partial
/// pivoting, and x is scaled back. So |K − Ω²·M| of 1e300 or of 1e-300
/// neither overflows nor underflows in the pivots' |z|² (which `Lu` alone
/// forms in every complex division). A pivot below √(f64::MIN_POSITIVE)
/// of the equilibrated matrix (condition ≳ 1e154) counts as singular.
/// An entry of x beyond the range of f64 comes back ±∞ or NaN: the caller
/// checks finiteness. `lu.a` holds the scaled factors afterwards.
pub fn solve_complex_scaled(
    lu: &mut Lu<Complex<f64>>,
    b: &mut [Complex<f64>],
) -> Result<(), DenseError> {
    let n = lu.n;
    if lu.a.len() < n * n || b.len() < n {
        return Err(DenseError::Shape { n });
    }
    let a = &mut lu.a;
    if a[..n * n]
        .iter()
        .any(|z| !(z.re.is_finite() && z.im.is_finite()))
    {
        return Err(DenseError::Singular { column: 0 });
    }
    // (every entry of A is finite: `largest` needs no NaN rule)
    for (i, row) in a[..n * n].chunks_exact_mut(n).enumerate() {
        let big = largest(row);
        if big == 0.0 {
            return Err(DenseError::Singular { column: i });
        }
        let e = -binary_exponent(big);
        scale_row(row, e);
        b[i] = scale_complex(b[i], e);
    }
    // the columns' largest entries in one pass over the rows
    let column_big = &mut lu.column_big;
    column_big.clear();
    column_big.resize(n, 0.0);
    for row in a[..n * n].chunks_exact(n) {
        for (big, &z) in column_big.iter_mut().zip(row) {
            let m = finite_max_part(z);
            if m > *big {
                *big = m;
            }
        }
    }
    let column = &mut lu.column_scale;
    column.resize(n, 0);
    for (j, (c, &big)) in column.iter_mut().zip(column_big.iter()).enumerate() {
        if big == 0.0 {
            return Err(DenseError::Singular { column: j });
        }
        *c = -binary_exponent(big);
    }
    if column.iter().all(|c| (-STEP..=STEP).contains(c)) {
        // each column's 2^c once: one product per part, as scale_complex
        for (f, &c) in column_big.iter_mut().zip(column.iter()) {
            *f = power_of_two(c);
        }
        for row in a[..n * n].chunks_exact_mut(n) {
            for (z, &f) in row.iter_mut().zip(column_big.iter()) {
                *z = Complex::new(z.re * f, z.im * f);
            }
        }
    } else {
        for row in a[..n * n].chunks_exact_mut(n) {
            for (z, &c) in row.iter_mut().zip(column.iter()) {
                *z = scale_complex(*z, c);
            }
        }
    }
    let big_b = b[..n].iter().fold(0.0f64, |m, &z| m.max(max_part(z)));
    let eb = -binary_exponent(big_b);
    b[..n].iter_mut().for_each(|z| *z = scale_complex(*z, eb));
    let tiny = f64::MIN_POSITIVE.sqrt();
    if !lu.factor_above(tiny) {
        // the columns before the failing one have a pivot above `tiny`
        let column = (0..n)
            .find(|&k| {
                (k..n).all(|i| {
                    let m = lu.a[i * n + k].mag();
                    m <= tiny || m.is_nan()
                })
            })
            .unwrap_or(0);
        return Err(DenseError::Singular { column });
    }
    lu.solve(b);
    for (z, &c) in b[..n].iter_mut().zip(&lu.column_scale) {
        *z = scale_complex(*z, c - eb);
    }
    Ok(())
}

/// Solve M·x = f in place for a symmetric M (n×n, row-major, both
/// triangles filled): Cholesky M = L·Lᵀ (Golub & Van Loan, Matrix
/// Computations, 4.2.5), and when M is not numerically positive definite
/// Gaussian elimination with partial pivoting (3.4) on the restored M.
/// The solution replaces `f`; `m` is overwritten. Allocation-free.
/// An error when M is numerically singular (a zero pivot).
pub fn solve_spd(m: &mut [f64], f: &mut [f64], n: usize) -> Result<(), DenseError> {
    if m.len() < n * n || f.len() < n {
        return Err(DenseError::Shape { n });
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
fn gauss_solve(a: &mut [f64], b: &mut [f64], n: usize) -> Result<(), DenseError> {
    for j in 0..n {
        let p = (j..n)
            .max_by(|&x, &y| a[x * n + j].abs().total_cmp(&a[y * n + j].abs()))
            .unwrap_or(j);
        let piv = a[p * n + j];
        if piv == 0.0 || !piv.is_finite() {
            return Err(DenseError::Singular { column: j });
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
    fn the_complex_quotient_is_the_division_bit_for_bit() {
        let parts = [0.0, -0.0, 1.5, -2.25, 1e-310, -3e300, f64::MIN_POSITIVE];
        let bits = |z: Complex<f64>| (z.re.to_bits(), z.im.to_bits());
        for &xr in &parts {
            for &xi in &parts {
                for &dr in &parts {
                    for &di in &parts {
                        let (x, d) = (Complex::new(xr, xi), Complex::new(dr, di));
                        assert_eq!(bits(x.quotient(d)), bits(x / d), "{x} / {d}");
                    }
                }
            }
        }
    }

    #[test]
    fn the_binary_exponent_brackets_x() {
        for x in [
            5e-324,
            1e-310,
            f64::MIN_POSITIVE,
            0.5,
            0.75,
            1.0,
            3.0,
            1e300,
            f64::MAX,
        ] {
            let e = binary_exponent(x);
            assert!(scaled_by_power_of_two(x, -e) < 1.0, "{x:e}");
            assert!(scaled_by_power_of_two(x, 1 - e) >= 1.0, "{x:e}");
        }
        assert_eq!(binary_exponent(1.0), 1);
        assert_eq!(binary_exponent(5e-324), -1073);
        assert_eq!(binary_exponent(0.0), 0);
    }

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
            Err(DenseError::Singular { column: 1 })
        );
        assert!(matches!(
            solve_spd(&mut m, &mut f, 3),
            Err(DenseError::Shape { n: 3 })
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

    #[test]
    fn lu_solves_real_and_complex_systems() {
        let mut lu = Lu::new(3, 0.0);
        lu.a.copy_from_slice(&[0.0, 2.0, 1.0, 1.0, 1.0, 0.0, 3.0, 0.0, 1.0]);
        assert!(lu.factor());
        let mut b = [5.0, 3.0, 6.0];
        lu.solve(&mut b);
        // A·x = b0 (the zero first pivot forces a row exchange).
        let a = [0.0, 2.0, 1.0, 1.0, 1.0, 0.0, 3.0, 0.0, 1.0];
        let b0 = [5.0, 3.0, 6.0];
        for r in 0..3 {
            let s: f64 = (0..3).map(|c| a[r * 3 + c] * b[c]).sum();
            assert!((s - b0[r]).abs() < 1e-14);
        }
        let mut lu = Lu::new(2, Complex::new(0.0, 0.0));
        let i = Complex::new(0.0, 1.0);
        let one = Complex::new(1.0, 0.0);
        lu.a.copy_from_slice(&[i, one, one, i + one]);
        assert!(lu.factor());
        let x = [Complex::new(1.0, -2.0), Complex::new(0.5, 3.0)];
        let mut b = [i * x[0] + x[1], x[0] + (i + one) * x[1]];
        lu.solve(&mut b);
        assert!((b[0] - x[0]).norm() < 1e-15 && (b[1] - x[1]).norm() < 1e-15);
        let mut s = Lu::new(2, 0.0);
        s.a.copy_from_slice(&[1.0, 2.0, 2.0, 4.0]);
        assert!(!s.factor());
    }

    #[test]
    fn the_determinant_counts_the_row_swaps() {
        // [[0, 2, 1], [1, 1, 0], [3, 0, 1]]: det = 0·1 − 2·1 + 1·(−3) = −5
        let mut lu = Lu::new(3, 0.0);
        lu.a.copy_from_slice(&[0.0, 2.0, 1.0, 1.0, 1.0, 0.0, 3.0, 0.0, 1.0]);
        assert!(lu.factor());
        assert!(
            (lu.determinant() + 5.0).abs() < 1e-14,
            "{}",
            lu.determinant()
        );
        // a relative singularity test refuses a tiny pivot
        let mut lu = Lu::new(2, 0.0);
        lu.a.copy_from_slice(&[1.0, 1.0, 1.0, 1.0 + 1e-15]);
        assert!(lu.factor());
        lu.a.copy_from_slice(&[1.0, 1.0, 1.0, 1.0 + 1e-15]);
        assert!(!lu.factor_above(1e-12));
    }

    /// A·x for a row-major complex A.
    fn times(a: &[Complex<f64>], x: &[Complex<f64>]) -> Vec<Complex<f64>> {
        let n = x.len();
        (0..n)
            .map(|i| (0..n).fold(Complex::new(0.0, 0.0), |s, j| s + a[i * n + j] * x[j]))
            .collect()
    }

    fn relative_error(got: &[Complex<f64>], want: &[Complex<f64>]) -> f64 {
        got.iter()
            .zip(want)
            .map(|(g, w)| (g - w).norm() / w.norm())
            .fold(0.0, f64::max)
    }

    /// The same well-conditioned system at the scales 1e±300, with rows of
    /// scales 1e300 and 1e-300 together: x to a few ulps every time,
    /// where |z|² of the entries overflows or underflows.
    #[test]
    fn the_scaled_complex_solve_neither_overflows_nor_underflows() {
        let c = |re: f64, im: f64| Complex::new(re, im);
        let base = [c(2.0, 1.0), c(0.0, 1.0), c(1.0, 0.0), c(3.0, -1.0)];
        let x = [c(1.0, -2.0), c(0.5, 3.0)];
        for (r0, r1) in [
            (1e300, 1e300),
            (1e-300, 1e-300),
            (1e300, 1e-300),
            (1e155, 1.0),
        ] {
            let a: Vec<Complex<f64>> = base
                .iter()
                .enumerate()
                .map(|(k, z)| z * if k < 2 { r0 } else { r1 })
                .collect();
            let mut b = times(&a, &x);
            let mut lu = Lu::new(2, c(0.0, 0.0));
            lu.a.copy_from_slice(&a);
            solve_complex_scaled(&mut lu, &mut b).unwrap();
            assert!(relative_error(&b, &x) < 1e-15, "{r0:e}, {r1:e}: {b:?}");
        }
        // m·ẍ + k·x = cos(t), m = 1, k = 1e155: x = 1/(1e155 − 1)
        let mut lu = Lu::new(1, c(0.0, 0.0));
        lu.a[0] = c(1e155 - 1.0, 0.0);
        let mut b = [c(1.0, 0.0)];
        solve_complex_scaled(&mut lu, &mut b).unwrap();
        assert!(relative_error(&b, &[c(1e-155, 0.0)]) < 1e-15, "{b:?}");
        // and k = m = 1e-160 at Ω = 1/2 with c = 1e-160: x = 1/((3/4 + i/2)·1e-160)
        lu.a[0] = c(0.75e-160, 0.5e-160);
        let mut b = [c(1.0, 0.0)];
        solve_complex_scaled(&mut lu, &mut b).unwrap();
        let want = c(1.0, 0.0) / c(0.75, 0.5) * 1e160;
        assert!(relative_error(&b, &[want]) < 1e-15, "{b:?}");
        // a solution beyond the range of f64 is not finite
        lu.a[0] = c(1e-300, 0.0);
        let mut b = [c(1e100, 0.0)];
        solve_complex_scaled(&mut lu, &mut b).unwrap();
        assert!(b[0].re.is_infinite());
    }

    #[test]
    fn the_scaled_complex_solve_finds_singular_matrices_at_any_scale() {
        let c = |re: f64, im: f64| Complex::new(re, im);
        for s in [1e300, 1.0, 1e-300] {
            let mut lu = Lu::new(2, c(0.0, 0.0));
            lu.a.copy_from_slice(&[c(s, s), c(2.0 * s, 0.0), c(s, s), c(2.0 * s, 0.0)]);
            let mut b = [c(1.0, 0.0), c(1.0, 0.0)];
            assert_eq!(
                solve_complex_scaled(&mut lu, &mut b),
                Err(DenseError::Singular { column: 1 }),
                "{s:e}"
            );
        }
        let mut lu = Lu::new(2, c(0.0, 0.0));
        lu.a.copy_from_slice(&[c(1.0, 0.0), c(0.0, 0.0), c(0.0, 0.0), c(0.0, 0.0)]);
        let mut b = [c(1.0, 0.0), c(1.0, 0.0)];
        assert_eq!(
            solve_complex_scaled(&mut lu, &mut b),
            Err(DenseError::Singular { column: 1 })
        );
        lu.a.copy_from_slice(&[c(f64::NAN, 0.0), c(0.0, 0.0), c(0.0, 0.0), c(1.0, 0.0)]);
        assert!(solve_complex_scaled(&mut lu, &mut b).is_err());
    }

    #[test]
    fn binary_exponents_bring_a_value_into_a_half_to_one() {
        for x in [
            1.0,
            0.5,
            0.75,
            3.0,
            1e300,
            1e-300,
            5e-324,
            f64::MAX,
            2f64.powi(-1022),
        ] {
            let m = scaled_by_power_of_two(x, -binary_exponent(x));
            assert!((0.5..1.0).contains(&m), "{x:e}: {m}");
        }
    }
}
