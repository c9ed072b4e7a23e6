//! One integration's work space and the step formulas of the explicit
//! methods: the stages, the solution, the error estimates, the stiffness
//! estimate and the dense output.
//!
//! Every per-step routine is compiled once per [`Lanes`] (`by_dim!`): for
//! n ≤ 8 the loops over the components have a constant trip count and the
//! tableaus' rows are constants (the `stages!` macro names the slots
//! literally), so that a step on a small system is straight-line code.

use super::combine::{by_dim, Blocks, Fixed, Lanes};
use super::tableaus::{self, Tableau};
use super::Kind;
use crate::{error_norm, Stats, System};

/// One integration's work space.
pub(super) struct Stepper {
    pub(super) kind: Kind,
    pub(super) tab: &'static Tableau,
    pub(super) n: usize,
    /// Stage derivatives, slot-major (`slots × n`); slot 0 = f(t, y).
    pub(super) k: Vec<f64>,
    /// The last stage point of the step proper (kept for the stiffness test).
    ytmp: Vec<f64>,
    /// The proposed y(t + h).
    pub(super) y_new: Vec<f64>,
    /// Error estimate vectors.
    pub(super) err: Vec<f64>,
    err2: Vec<f64>,
    /// Dense-output coefficient vectors (`n_cont × n`).
    cont: Vec<f64>,
    /// n zeros (the base point of an estimate).
    zeros: Vec<f64>,
}

/// The work arrays a stage reads and writes.
struct Work<'a> {
    t: f64,
    y: &'a [f64],
    h: f64,
    k: &'a mut [f64],
    ytmp: &'a mut [f64],
}

/// Stage `i` of `tab`: ytmp = y + h Σⱼ aᵢⱼ kⱼ, kᵢ = f(t + cᵢh, ytmp).
#[inline(always)]
fn stage<L: Lanes, S: System + ?Sized>(l: L, sys: &mut S, tab: &Tableau, i: usize, w: &mut Work) {
    let n = l.n();
    let (done, rest) = w.k.split_at_mut(i * n);
    l.comb(w.y, w.h, tab.a[i], done, w.ytmp);
    sys.rhs(w.t + tab.c[i] * w.h, w.ytmp, &mut rest[..n]);
}

/// The stages of the slots listed (literals, so that each row is a
/// constant where [`Lanes::comb`] is inlined).
macro_rules! stages {
    ($l:expr, $sys:expr, $tab:expr, $w:expr; $($i:literal)+) => {
        { $( stage($l, $sys, &$tab, $i, $w); )+ }
    };
}

impl Stepper {
    pub(super) fn new(kind: Kind, n: usize) -> Stepper {
        let tab = kind.tableau();
        Stepper {
            kind,
            tab,
            n,
            k: vec![0.0; tab.slots * n],
            ytmp: vec![0.0; n],
            y_new: vec![0.0; n],
            err: vec![0.0; n],
            err2: vec![0.0; n],
            cont: vec![0.0; kind.n_cont() * n],
            zeros: vec![0.0; n],
        }
    }

    /// One attempted step from (t, y) with slot 0 = f(t, y): the stages, the
    /// proposed `y_new`, and the error norm (0 when `estimate` is false or
    /// the method has no estimator).
    #[allow(clippy::too_many_arguments)]
    pub(super) fn attempt<S: System + ?Sized>(
        &mut self,
        sys: &mut S,
        t: f64,
        y: &[f64],
        h: f64,
        rtol: f64,
        atol: f64,
        estimate: bool,
        stats: &mut Stats,
    ) -> f64 {
        let tol = (rtol, atol);
        by_dim!(self.n, l => match self.kind {
            Kind::Rk4 => self.rk4(l, sys, t, y, h, stats),
            Kind::Dopri5 => self.dopri5(l, sys, t, y, h, tol, estimate, stats),
            Kind::Dop853 => self.dop853(l, sys, t, y, h, tol, estimate, stats),
            Kind::Vern7 => self.vern7(l, sys, t, y, h, tol, estimate, stats),
        })
    }

    fn rk4<L: Lanes, S: System + ?Sized>(
        &mut self,
        l: L,
        sys: &mut S,
        t: f64,
        y: &[f64],
        h: f64,
        stats: &mut Stats,
    ) -> f64 {
        let tab = &tableaus::RK4;
        let (k, ytmp) = (&mut self.k[..tab.slots * l.n()], &mut self.ytmp[..]);
        let w = &mut Work { t, y, h, k, ytmp };
        stages!(l, sys, tableaus::RK4, w; 1 2 3);
        stats.rhs_evals += tab.s - 1;
        l.comb(y, h, tab.b, &self.k, &mut self.y_new);
        0.0
    }

    #[allow(clippy::too_many_arguments)]
    fn dopri5<L: Lanes, S: System + ?Sized>(
        &mut self,
        l: L,
        sys: &mut S,
        t: f64,
        y: &[f64],
        h: f64,
        (rtol, atol): (f64, f64),
        estimate: bool,
        stats: &mut Stats,
    ) -> f64 {
        let (tab, n) = (&tableaus::DOPRI5, l.n());
        let (k, ytmp) = (&mut self.k[..tab.slots * n], &mut self.ytmp[..]);
        let w = &mut Work { t, y, h, k, ytmp };
        stages!(l, sys, tableaus::DOPRI5, w; 1 2 3 4 5);
        stats.rhs_evals += tab.s - 1;
        l.comb(y, h, tab.b, &self.k, &mut self.y_new);
        if !estimate {
            return 0.0;
        }
        // FSAL: slot 6 = f(t + h, y_new) enters the estimate
        sys.rhs(t + h, &self.y_new, &mut self.k[tab.s * n..(tab.s + 1) * n]);
        stats.rhs_evals += 1;
        l.comb(&self.zeros, h, &tableaus::DOPRI5_E, &self.k, &mut self.err);
        error_norm(&self.err[..n], y, &self.y_new, rtol, atol)
    }

    #[allow(clippy::too_many_arguments)]
    fn dop853<L: Lanes, S: System + ?Sized>(
        &mut self,
        l: L,
        sys: &mut S,
        t: f64,
        y: &[f64],
        h: f64,
        (rtol, atol): (f64, f64),
        estimate: bool,
        stats: &mut Stats,
    ) -> f64 {
        let (tab, n) = (&tableaus::DOP853, l.n());
        let (k, ytmp) = (&mut self.k[..tab.slots * n], &mut self.ytmp[..]);
        let w = &mut Work { t, y, h, k, ytmp };
        stages!(l, sys, tableaus::DOP853, w; 1 2 3 4 5 6 7 8 9 10 11);
        stats.rhs_evals += tab.s - 1;
        l.comb(y, h, tab.b, &self.k, &mut self.y_new);
        if !estimate {
            return 0.0;
        }
        // 5th-order estimate `err`, 3rd-order estimate `err2`
        let k = &self.k[..tab.s * n];
        l.comb(&self.zeros, 1.0, &tableaus::DOP853_ER, k, &mut self.err);
        let (y, y_new) = (&y[..n], &self.y_new[..n]);
        let (err, err2) = (&self.err[..n], &mut self.err2[..n]);
        for i in 0..n {
            let mut v = (y_new[i] - y[i]) / h;
            for &(j, w) in &tableaus::DOP853_BHH {
                v -= w * k[j * n + i];
            }
            err2[i] = v;
        }
        let (mut e5, mut e3) = (0.0, 0.0);
        for i in 0..n {
            let sk = atol + rtol * y[i].abs().max(y_new[i].abs());
            // e3's terms first: they wait for the divisions by h above
            e3 += (err2[i] / sk).powi(2);
            e5 += (err[i] / sk).powi(2);
        }
        let mut deno = e5 + 0.01 * e3;
        if deno <= 0.0 {
            deno = 1.0;
        }
        h.abs() * e5 * (1.0 / (n.max(1) as f64 * deno)).sqrt()
    }

    #[allow(clippy::too_many_arguments)]
    fn vern7<L: Lanes, S: System + ?Sized>(
        &mut self,
        l: L,
        sys: &mut S,
        t: f64,
        y: &[f64],
        h: f64,
        (rtol, atol): (f64, f64),
        estimate: bool,
        stats: &mut Stats,
    ) -> f64 {
        let (tab, n) = (&tableaus::VERN7, l.n());
        let (k, ytmp) = (&mut self.k[..tab.slots * n], &mut self.ytmp[..]);
        let w = &mut Work { t, y, h, k, ytmp };
        stages!(l, sys, tableaus::VERN7, w; 1 2 3 4 5 6 7 8 9);
        stats.rhs_evals += tab.s - 1;
        l.comb(y, h, tab.b, &self.k, &mut self.y_new);
        if !estimate {
            return 0.0;
        }
        l.comb(&self.zeros, h, &tableaus::VERN7_E, &self.k, &mut self.err);
        error_norm(&self.err[..n], y, &self.y_new, rtol, atol)
    }

    /// After acceptance: slot `s` = f(t + h, y_new) (already there for
    /// DOPRI5 when the estimate was made).
    pub(super) fn finish<S: System + ?Sized>(
        &mut self,
        sys: &mut S,
        t: f64,
        h: f64,
        have_fsal: bool,
        stats: &mut Stats,
    ) {
        if self.kind == Kind::Dopri5 && have_fsal {
            return;
        }
        let (n, s) = (self.n, self.tab.s);
        sys.rhs(t + h, &self.y_new, &mut self.k[s * n..(s + 1) * n]);
        stats.rhs_evals += 1;
    }

    /// After an accepted step: whether y_new and f(t + h, y_new) (slot `s`)
    /// are finite, and with a `limit`, Hairer's stiffness test: is
    /// h·|λ| > `limit`, h·|λ| ≈ h·‖f(y₁) − f(ŷ)‖/‖y₁ − ŷ‖ with ŷ the last stage
    /// point (also at t + h)? (`None` when y₁ = ŷ.)
    pub(super) fn check_end(&self, h: f64, limit: Option<f64>) -> (bool, Option<bool>) {
        by_dim!(self.n, l => {
            let Some(limit) = limit else {
                return (self.finite_end(l), None);
            };
            let (num, den) = self.stiffness_sums(l);
            // a component that is not finite makes num or den so
            let finite = (num.is_finite() && den.is_finite()) || self.finite_end(l);
            (finite, (den > 0.0).then(|| exceeds(h, num, den, limit)))
        })
    }

    /// ‖f(y₁) − f(ŷ)‖² and ‖y₁ − ŷ‖².
    fn stiffness_sums<L: Lanes>(&self, l: L) -> (f64, f64) {
        let (n, s) = (l.n(), self.tab.s);
        let (f1, f0) = (&self.k[s * n..(s + 1) * n], &self.k[(s - 1) * n..s * n]);
        let (y1, y0) = (&self.y_new[..n], &self.ytmp[..n]);
        let (mut num, mut den) = (0.0, 0.0);
        for i in 0..n {
            num += (f1[i] - f0[i]).powi(2);
            den += (y1[i] - y0[i]).powi(2);
        }
        (num, den)
    }

    /// y_new and f(t + h, y_new) (slot `s`) are finite.
    fn finite_end<L: Lanes>(&self, l: L) -> bool {
        let (n, s) = (l.n(), self.tab.s);
        all_finite(&self.y_new[..n]) && all_finite(&self.k[s * n..(s + 1) * n])
    }

    /// Move to the accepted step's end: y ← y_new, slot 0 ← slot `s`.
    pub(super) fn advance(&mut self, y: &mut Vec<f64>) {
        std::mem::swap(y, &mut self.y_new);
        by_dim!(self.n, l => {
            let (n, s) = (l.n(), self.tab.s);
            let (first, rest) = self.k.split_at_mut(s * n);
            first[..n].copy_from_slice(&rest[..n]);
        })
    }

    /// Build the dense output of the accepted step (t, y) → (t + h, y_new),
    /// slot `s` holding f(t + h, y_new).
    #[allow(clippy::needless_range_loop)]
    pub(super) fn prepare_dense<S: System + ?Sized>(
        &mut self,
        sys: &mut S,
        t: f64,
        y: &[f64],
        h: f64,
        stats: &mut Stats,
    ) {
        let n = self.n;
        let s = self.tab.s;
        if matches!(self.kind, Kind::Dop853 | Kind::Vern7) {
            let (k, ytmp) = (&mut self.k[..], &mut self.ytmp[..]);
            let w = &mut Work { t, y, h, k, ytmp };
            match self.kind {
                Kind::Dop853 => by_dim!(n, l => stages!(l, sys, tableaus::DOP853, w; 13 14 15)),
                _ => by_dim!(n, l => stages!(l, sys, tableaus::VERN7, w; 11 12 13 14 15)),
            }
            stats.rhs_evals += self.tab.slots - (s + 1);
        }
        if self.kind == Kind::Vern7 {
            // cont[0] = y, cont[k+1] = h Σᵢ bi[i][k] kᵢ
            self.cont[..n].copy_from_slice(y);
            for m in 0..7 {
                let c = &mut self.cont[(m + 1) * n..(m + 2) * n];
                c.fill(0.0);
                for (i, row) in tableaus::VERN7_BI.iter().enumerate() {
                    let w = h * row[m];
                    if w != 0.0 {
                        for (o, &kv) in c.iter_mut().zip(&self.k[i * n..(i + 1) * n]) {
                            *o += w * kv;
                        }
                    }
                }
            }
            return;
        }
        // Hairer's form: y + θ(Δ + θ₁(hf₀ − Δ + θ(Δ − hf₁ − (hf₀ − Δ) + θ₁(…))))
        for i in 0..n {
            let ydiff = self.y_new[i] - y[i];
            let bspl = h * self.k[i] - ydiff;
            self.cont[i] = y[i];
            self.cont[n + i] = ydiff;
            self.cont[2 * n + i] = bspl;
            self.cont[3 * n + i] = ydiff - h * self.k[s * n + i] - bspl;
        }
        match self.kind {
            Kind::Dopri5 => {
                for i in 0..n {
                    let mut v = 0.0;
                    for (j, &d) in tableaus::DOPRI5_D.iter().enumerate() {
                        v += d * self.k[j * n + i];
                    }
                    self.cont[4 * n + i] = h * v;
                }
            }
            Kind::Dop853 => {
                for (r, drow) in tableaus::DOP853_D.iter().enumerate() {
                    for i in 0..n {
                        let mut v = 0.0;
                        for (j, &d) in drow.iter().enumerate() {
                            if d != 0.0 {
                                v += d * self.k[j * n + i];
                            }
                        }
                        self.cont[(4 + r) * n + i] = h * v;
                    }
                }
            }
            Kind::Rk4 | Kind::Vern7 => {}
        }
    }

    /// The dense output at θ = (t − t_step)/h into `out`.
    pub(super) fn dense(&self, theta: f64, out: &mut [f64]) {
        let n = self.n;
        let m = self.kind.n_cont();
        let c = |j: usize, i: usize| self.cont[j * n + i];
        if self.kind == Kind::Vern7 {
            for (i, o) in out.iter_mut().enumerate() {
                let mut acc = c(7, i);
                for j in (1..7).rev() {
                    acc = c(j, i) + theta * acc;
                }
                *o = c(0, i) + theta * acc;
            }
            return;
        }
        let theta1 = 1.0 - theta;
        for (i, o) in out.iter_mut().enumerate() {
            // multiplier after coefficient j (0-based): θ for even j, θ₁ for odd
            let mut acc = c(m - 1, i);
            for j in (0..m - 1).rev() {
                let w = if j % 2 == 0 { theta } else { theta1 };
                acc = c(j, i) + w * acc;
            }
            *o = acc;
        }
    }
}

pub(super) fn all_finite(v: &[f64]) -> bool {
    v.iter().all(|x| x.is_finite())
}

/// |h|·√(num/den) > `limit` (den > 0), as computed in floating point, but
/// decided by products where they settle it: the division and the square
/// root would wait for the divider, which the error norm and the
/// step-size controller need at the same time (skipping them saved 8% of
/// the time of the `two_mode` problem, whose right-hand side is a few
/// flops).
///
/// With h², num and den in [1e-150, 1e150] nothing over- or underflows:
/// a = h²·num and b = limit²·den are within 2 ulps and the computed
/// |h|·√(num/den) within 3 ulps of their exact values, so a ≤ b·(1 − 1e-12)
/// or a ≥ b·(1 + 1e-12) decides the computed comparison the same way.
/// Otherwise, or when a and b are that close, it is evaluated as written.
fn exceeds(h: f64, num: f64, den: f64, limit: f64) -> bool {
    const MARGIN: f64 = 1e-12;
    let moderate = |x: f64| (1e-150..=1e150).contains(&x);
    let h2 = h * h;
    if moderate(h2) && moderate(num) && moderate(den) {
        let (a, b) = (h2 * num, limit * limit * den);
        if a <= b * (1.0 - MARGIN) {
            return false;
        }
        if a >= b * (1.0 + MARGIN) {
            return true;
        }
    }
    h.abs() * (num / den).sqrt() > limit
}

#[cfg(test)]
mod tests {
    use super::exceeds;
    use qdot_exact::rng::SplitMix64;

    /// The products decide as the formula does, near the limit too.
    #[test]
    fn the_stiffness_comparison_is_the_formula() {
        let plain = |h: f64, num: f64, den: f64, limit: f64| h.abs() * (num / den).sqrt() > limit;
        let mut rng = SplitMix64::new(0x9E37_79B9_7F4A_7C15);
        let mut next = || rng.unit();
        for _ in 0..200_000 {
            let limit = [3.25, 6.1, 4.5][(next() * 3.0) as usize];
            let h = (next() - 0.5) * 10f64.powf(next() * 40.0 - 20.0);
            let den = 10f64.powf(next() * 400.0 - 200.0);
            // num near (limit/h)²·den, within a few ulps or far
            let exact = (limit / h).powi(2) * den;
            let num = match (next() * 3.0) as usize {
                0 => exact * (1.0 + (next() - 0.5) * 1e-14),
                1 => exact * 10f64.powf(next() * 4.0 - 2.0),
                _ => 10f64.powf(next() * 600.0 - 300.0),
            };
            assert_eq!(
                exceeds(h, num, den, limit),
                plain(h, num, den, limit),
                "h {h:e}, num {num:e}, den {den:e}, limit {limit}"
            );
        }
        for &(h, num, den) in &[
            (0.0, 1.0, 1.0),
            (1.0, 0.0, 1.0),
            (1.0, f64::INFINITY, 1.0),
            (1.0, f64::NAN, 1.0),
            (1e-200, 1e300, 1e-300),
        ] {
            assert_eq!(exceeds(h, num, den, 6.1), plain(h, num, den, 6.1));
        }
    }
}
