//! Hand-written Rust right-hand sides of the benchmark problems
//! (`qdot::simulate::problems`), the baseline the compiled evaluator is
//! measured against: what a careful programmer writes from the textbook
//! formulas, with the same linear solve (`solve_spd`) where M varies.
//! Each is checked against the compiled program before it is timed.

use qdot::simulate::compile::solve_spd;
use qdot::simulate::problems::{Kind, Problem};
use qdot::simulate::System;

/// A problem's hand-written y' = F(t, y).
pub struct Hand {
    kind: Kind,
    n: usize,
    p: [f64; 5],
    m: Vec<f64>,
    f: Vec<f64>,
    /// Scratch: sin θ and cos θ of each angle (tuned), or sin(θ_i − θ_j)
    /// for every pair (plain, n × n).
    sc: Vec<f64>,
    /// The chain's entries by addition theorems (one sin_cos per angle).
    pub tuned: bool,
}

impl Hand {
    pub fn new(problem: &Problem, tuned: bool) -> Hand {
        let n = problem.y0.len() / 2;
        let p = match problem.kind {
            Kind::Oscillator => ["m", "k", "c", "F0", "p"].map(|k| problem.param(k)),
            Kind::TwoMode => ["m", "k", "R", "m", "m"].map(|k| problem.param(k)),
            Kind::CartesianPendulum => {
                let [m, l, g] = ["m", "l", "g"].map(|k| problem.param(k));
                [m, l, g, problem.baumgarte.unwrap_or(0.0), 0.0]
            }
            _ => ["m", "l", "g", "m", "m"].map(|k| problem.param(k)),
        };
        Hand {
            kind: problem.kind,
            n,
            p,
            m: vec![0.0; n * n],
            f: vec![0.0; n],
            sc: vec![0.0; (2 * n).max(n * n)],
            tuned,
        }
    }

    /// The chain's M (full, row-major) and f at (q, q̇) (equal m, l; angles
    /// from the downward vertical, 0-based):
    /// M_ij = m l² (n − max(i, j)) cos(θ_i − θ_j),
    /// f_i = −m l² Σ_j (n − max(i, j)) sin(θ_i − θ_j) θ̇_j² − m g l (n − i) sin θ_i.
    /// The plain version takes one sin_cos per pair i < j (sin is odd);
    /// the tuned one, one per angle and the addition theorems.
    pub fn chain(&mut self, q: &[f64], qd: &[f64]) -> (&[f64], &[f64]) {
        let n = self.n;
        let [m, l, g, _, _] = self.p;
        let ml2 = m * l * l;
        if self.tuned {
            let (s, c) = self.sc.split_at_mut(n);
            for i in 0..n {
                (s[i], c[i]) = q[i].sin_cos();
            }
            for i in 0..n {
                self.m[i * n + i] = ml2 * (n - i) as f64;
                for j in i + 1..n {
                    let v = ml2 * (n - j) as f64 * (c[i] * c[j] + s[i] * s[j]);
                    self.m[i * n + j] = v;
                    self.m[j * n + i] = v;
                }
            }
            for i in 0..n {
                let (mut sc_sum, mut ss_sum) = (0.0, 0.0);
                for j in 0..n {
                    let w = (n - i.max(j)) as f64 * qd[j] * qd[j];
                    sc_sum += w * c[j];
                    ss_sum += w * s[j];
                }
                self.f[i] =
                    -ml2 * (s[i] * sc_sum - c[i] * ss_sum) - m * g * l * (n - i) as f64 * s[i];
            }
        } else {
            let sd = &mut self.sc[..n * n];
            for i in 0..n {
                self.m[i * n + i] = ml2 * (n - i) as f64;
                sd[i * n + i] = 0.0;
                for j in i + 1..n {
                    let (s, c) = (q[i] - q[j]).sin_cos();
                    let v = ml2 * (n - j) as f64 * c;
                    self.m[i * n + j] = v;
                    self.m[j * n + i] = v;
                    sd[i * n + j] = s;
                    sd[j * n + i] = -s;
                }
            }
            for i in 0..n {
                let mut acc = 0.0;
                for j in 0..n {
                    acc += (n - i.max(j)) as f64 * sd[i * n + j] * qd[j] * qd[j];
                }
                self.f[i] = -ml2 * acc - m * g * l * (n - i) as f64 * q[i].sin();
            }
        }
        (&self.m, &self.f)
    }
}

impl System for Hand {
    fn dim(&self) -> usize {
        2 * self.n
    }

    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) {
        let n = self.n;
        let (q, qd) = y.split_at(n);
        dy[..n].copy_from_slice(qd);
        match self.kind {
            Kind::Oscillator => {
                let [m, k, c, f0, p] = self.p;
                dy[1] = (f0 * (p * t).cos() - c * y[1] - k * y[0]) / m;
            }
            Kind::TwoMode => {
                // M = diag(4m, 3m/2), K = [[2k, −k], [−k, k]]
                let [m, k, _, _, _] = self.p;
                dy[2] = (-2.0 * k * y[0] + k * y[1]) / (4.0 * m);
                dy[3] = (k * y[0] - k * y[1]) / (1.5 * m);
            }
            Kind::Pendulum => {
                let [_, l, g, _, _] = self.p;
                dy[1] = -(g / l) * y[0].sin();
            }
            Kind::CartesianPendulum => {
                // The rod x² + y² = l² with Baumgarte's α: the acceleration
                // (0, −g) + μ·(x, y) along the rod with μ such that
                // g̈ + 2α·ġ + α²·g = 0, i.e.
                // 2·(x ẍ + y ÿ) = −2v² − 4α·(x ẋ + y ẏ) − α²·(r² − l²).
                let [_, l, g, alpha, _] = self.p;
                let (x, y, vx, vy) = (y[0], y[1], y[2], y[3]);
                let r2 = x * x + y * y;
                let v2 = vx * vx + vy * vy;
                let s = x * vx + y * vy;
                let rhs = -2.0 * v2 - 4.0 * alpha * s - alpha * alpha * (r2 - l * l);
                let mu = (rhs + 2.0 * g * y) / (2.0 * r2);
                dy[2] = mu * x;
                dy[3] = mu * y - g;
            }
            Kind::DoublePendulum | Kind::Chain10 => {
                self.chain(q, qd);
                let mut f = std::mem::take(&mut self.f);
                if solve_spd(&mut self.m, &mut f, n).is_err() {
                    f.iter_mut().for_each(|x| *x = f64::NAN);
                }
                dy[n..].copy_from_slice(&f);
                self.f = f;
            }
        }
    }
}
