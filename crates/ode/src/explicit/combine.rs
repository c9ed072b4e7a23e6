//! The stage combinations y + h Σⱼ aⱼ kⱼ of the explicit methods, for a
//! dimension known at compile time ([`Fixed`], n ≤ 8) or only at run time
//! ([`Blocks`]).
//!
//! The step formulas call [`Lanes::comb`] with rows that are constants of
//! the tableaus and have it inlined: the loop over the row then unrolls,
//! its zeros drop out and its coefficients become immediates, which is
//! most of a step's cost on a system of a few flops (the `ode_solvers`
//! comparison of the work-precision report measured it).
//!
//! Both keep the order of the floating-point operations the driver always
//! had, so that results do not depend on this choice: for n ≤ 8 the sum
//! Σⱼ aⱼkⱼ from 0, then y + h·sum; for larger n, y then += (h·aⱼ)·kⱼ in
//! the row's order.

/// A dimension and the combination of stage vectors at it.
pub(super) trait Lanes: Copy {
    /// The dimension n.
    fn n(self) -> usize;

    /// out = y + h Σⱼ rowⱼ kⱼ over the nonzero entries of `row`, kⱼ the
    /// j-th slot (`n` values) of `k`.
    fn comb(self, y: &[f64], h: f64, row: &[f64], k: &[f64], out: &mut [f64]);
}

/// n = N, known at compile time (N ≤ 8: the order of [`Lanes::comb`]
/// depends on it).
#[derive(Clone, Copy)]
pub(super) struct Fixed<const N: usize>;

/// Any n > 8, in blocks of 4 components (and single ones for the rest):
/// each block's partial sums stay in registers across the row.
#[derive(Clone, Copy)]
pub(super) struct Blocks(pub(super) usize);

impl<const N: usize> Lanes for Fixed<N> {
    #[inline(always)]
    fn n(self) -> usize {
        N
    }

    #[inline(always)]
    fn comb(self, y: &[f64], h: f64, row: &[f64], k: &[f64], out: &mut [f64]) {
        // exactly row.len() slots, so that the loop's trip count is the
        // row's (a constant)
        let (slots, _) = k[..row.len() * N].as_chunks::<N>();
        let mut acc = [0.0f64; N];
        for (&a, kj) in row.iter().zip(slots) {
            if a != 0.0 {
                for (s, kv) in acc.iter_mut().zip(kj) {
                    *s += a * kv;
                }
            }
        }
        if let (Some(y), Some(out)) = (y.first_chunk::<N>(), out.first_chunk_mut::<N>()) {
            for ((o, yi), s) in out.iter_mut().zip(y).zip(&acc) {
                *o = yi + h * s;
            }
        }
    }
}

impl Lanes for Blocks {
    #[inline(always)]
    fn n(self) -> usize {
        self.0
    }

    #[inline(always)]
    fn comb(self, y: &[f64], h: f64, row: &[f64], k: &[f64], out: &mut [f64]) {
        let n = self.0;
        if n == 0 || row.len() > MAX_ROW {
            return axpy(n, y, h, row, k, out);
        }
        // the nonzero entries' h·aⱼ and slots (constants but for h and the
        // addresses, where `row` is one)
        let mut ha = [0.0; MAX_ROW];
        let mut ks: [&[f64]; MAX_ROW] = [&[]; MAX_ROW];
        let mut m = 0;
        for (j, &a) in row.iter().enumerate() {
            if a != 0.0 {
                ha[m] = h * a;
                ks[m] = &k[j * n..(j + 1) * n];
                m += 1;
            }
        }
        let (ha, ks) = (&ha[..m], &ks[..m]);
        let (y, out) = (&y[..n], &mut out[..n]);
        let (yb, _) = y.as_chunks::<4>();
        let (ob, _) = out.as_chunks_mut::<4>();
        for (b, (o, yv)) in ob.iter_mut().zip(yb).enumerate() {
            let mut acc = *yv;
            for (&c, kj) in ha.iter().zip(ks) {
                if let Some(kv) = kj.as_chunks::<4>().0.get(b) {
                    for (s, kv) in acc.iter_mut().zip(kv) {
                        *s += c * kv;
                    }
                }
            }
            *o = acc;
        }
        for i in n - n % 4..n {
            let mut acc = y[i];
            for (&c, kj) in ha.iter().zip(ks) {
                acc += c * kj[i];
            }
            out[i] = acc;
        }
    }
}

/// The longest row [`Blocks::comb`] takes in registers.
const MAX_ROW: usize = 16;

/// [`Blocks::comb`] one scaled stage vector at a time.
fn axpy(n: usize, y: &[f64], h: f64, row: &[f64], k: &[f64], out: &mut [f64]) {
    out[..n].copy_from_slice(&y[..n]);
    for (j, &a) in row.iter().enumerate() {
        if a != 0.0 {
            let ha = h * a;
            for (o, &kv) in out[..n].iter_mut().zip(&k[j * n..(j + 1) * n]) {
                *o += ha * kv;
            }
        }
    }
}

/// `$body` with `$l` the [`Lanes`] of dimension `$n`: [`Fixed`] for
/// n = 1…8, [`Blocks`] past it.
macro_rules! by_dim {
    ($n:expr, $l:ident => $body:expr) => {
        by_dim!(@arms $n, $l => $body; 1 2 3 4 5 6 7 8)
    };
    (@arms $n:expr, $l:ident => $body:expr; $($k:literal)+) => {
        match $n {
            $(
                $k => {
                    let $l = Fixed::<$k>;
                    $body
                }
            )+
            n => {
                let $l = Blocks(n);
                $body
            }
        }
    };
}
pub(super) use by_dim;
