//! A progress bar on standard error for long integrations (`indicatif`).
//!
//! The integrators are not touched: [`Progress`] wraps a [`System`] and,
//! every [`CHECK_EVERY`] right-hand-side calls, moves the bar to the largest
//! t seen so far (the stages of a step evaluate F at times inside the step,
//! so the largest is where the integration has reached). The bar appears
//! only once the run has lasted [`DELAY`], and is cleared when the wrapper
//! is dropped. `qdot simulate` wraps its system only when standard error is
//! a terminal; otherwise nothing is wrapped and nothing is drawn.

use super::System;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::time::{Duration, Instant};

/// Right-hand-side calls between two looks at the clock and the bar.
pub const CHECK_EVERY: u32 = 1024;

/// How long a run goes on before its bar appears.
pub const DELAY: Duration = Duration::from_millis(500);

/// How often the estimate of the time left is renewed.
pub const MESSAGE_EVERY: Duration = Duration::from_millis(250);

/// The bar's resolution: its length in ticks over [t0, t_end].
const TICKS: u64 = 1000;

/// A [`System`] that forwards to `inner` and reports its progress over
/// [t0, t_end] on a bar drawn on standard error (see the module docs).
pub struct Progress<'a, S: System + ?Sized> {
    inner: &'a mut S,
    t0: f64,
    t_end: f64,
    t_max: f64,
    calls: u32,
    start: Instant,
    bar: Option<ProgressBar>,
    /// When (since `start`) the message was last set.
    message_at: Option<Duration>,
}

impl<'a, S: System + ?Sized> Progress<'a, S> {
    /// Wrap `inner` for an integration over [`t0`, `t_end`]; the clock of
    /// [`DELAY`] starts now.
    pub fn new(inner: &'a mut S, t0: f64, t_end: f64) -> Self {
        Progress {
            inner,
            t0,
            t_end,
            t_max: t0,
            calls: 0,
            start: Instant::now(),
            bar: None,
            message_at: None,
        }
    }

    /// Whether the bar has been shown (the run outlasted [`DELAY`]).
    pub fn shown(&self) -> bool {
        self.bar.is_some()
    }

    /// Create the bar once the delay has passed, then move it to `t_max`
    /// and, every [`MESSAGE_EVERY`], estimate the time left.
    fn update(&mut self) {
        let elapsed = self.start.elapsed();
        if self.bar.is_none() && elapsed < DELAY {
            return;
        }
        let span = self.t_end - self.t0;
        let frac = if span != 0.0 {
            ((self.t_max - self.t0) / span).clamp(0.0, 1.0)
        } else {
            1.0
        };
        let bar = self.bar.get_or_insert_with(|| {
            // drawn only once its position and message are set
            let bar = ProgressBar::with_draw_target(Some(TICKS), ProgressDrawTarget::hidden())
                .with_elapsed(elapsed);
            if let Ok(style) =
                ProgressStyle::with_template("{prefix} [{bar:30}] {percent:>3}% {elapsed}{msg}")
            {
                bar.set_style(style.progress_chars("=> "));
            }
            bar.set_prefix(format!("simulating to t = {}", self.t_end));
            bar
        });
        bar.set_position((frac * TICKS as f64) as u64);
        if self.message_at.is_none_or(|m| elapsed >= m + MESSAGE_EVERY) {
            self.message_at = Some(elapsed);
            // the rate so far: t advances about linearly in wall time
            if frac > 0.0 {
                let left = elapsed.as_secs_f64() * (1.0 - frac) / frac;
                bar.set_message(format!(", {left:.0}s left"));
            }
            if bar.is_hidden() {
                bar.set_draw_target(ProgressDrawTarget::stderr());
            }
        }
    }
}

impl<S: System + ?Sized> System for Progress<'_, S> {
    fn dim(&self) -> usize {
        self.inner.dim()
    }

    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) {
        self.inner.rhs(t, y, dy);
        // |t − t0| so that a backward integration advances the bar too
        if (t - self.t0).abs() > (self.t_max - self.t0).abs() {
            self.t_max = t;
        }
        self.calls = self.calls.wrapping_add(1);
        if self.calls.is_multiple_of(CHECK_EVERY) {
            self.update();
        }
    }

    fn jacobian(&mut self, t: f64, y: &[f64], jac: &mut [f64]) -> bool {
        self.inner.jacobian(t, y, jac)
    }
}

impl<S: System + ?Sized> Drop for Progress<'_, S> {
    /// Clear the bar, leaving standard error as it was.
    fn drop(&mut self) {
        if let Some(bar) = self.bar.take() {
            bar.finish_and_clear();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::simulate::FnSystem;

    #[test]
    fn forwards_and_tracks_the_largest_time() {
        let mut inner = FnSystem {
            dim: 1,
            f: |t: f64, y: &[f64], dy: &mut [f64]| dy[0] = t * y[0],
        };
        let mut p = Progress::new(&mut inner, 0.0, 2.0);
        assert_eq!(p.dim(), 1);
        let mut dy = [0.0];
        for t in [0.5, 1.5, 1.0] {
            p.rhs(t, &[2.0], &mut dy);
            assert_eq!(dy[0], 2.0 * t);
        }
        assert_eq!(p.t_max, 1.5);
        assert_eq!(p.calls, 3);
        // far less than DELAY has passed: no bar
        assert!(!p.shown());
    }
}
