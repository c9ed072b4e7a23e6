//! `qdot simulate --plot FILE.svg`: the motion as an SVG figure (plotters).
//!
//! Panels, top to bottom: every coordinate against t; the phase portrait
//! (q̇ against q) of every coordinate; and, when the scene is conservative,
//! the energy error h(t) − h(0), which shows the integrator's drift. Each
//! curve is one `<polyline>` with one point per output time.

use super::run::{method_name, Run};
use plotters::prelude::*;

/// The curves' colours (matplotlib's first six), also used by the
/// stress report's figures.
pub const PALETTE: [RGBColor; 6] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(255, 127, 14),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
];

/// The plotting backend failed to draw the figure: its message.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PlotError {
    /// What the backend reported.
    pub message: String,
}

impl PlotError {
    pub(crate) fn drawing(e: impl std::fmt::Display) -> PlotError {
        PlotError {
            message: e.to_string(),
        }
    }
}

impl std::fmt::Display for PlotError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for PlotError {}

/// A tick label: 0 as `0` (not `0.0`, `-0.0` or `-2.6e-23`, rounding
/// left over from the tick arithmetic), the rest with the decimals the
/// axis's span needs, or in scientific notation for a span far from 1.
pub fn tick_label(v: f64, span: f64) -> String {
    let span = if span.is_finite() && span > 0.0 {
        span
    } else {
        1.0
    };
    if v.abs() <= span * 1e-9 {
        return "0".into();
    }
    if !(1e-3..1e5).contains(&span) {
        return format!("{v:.1e}");
    }
    let decimals = (-(span / 10.0).log10().floor()).clamp(0.0, 6.0) as usize;
    let s = format!("{v:.decimals$}");
    let s = if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    };
    if s == "-0" {
        "0".into()
    } else {
        s
    }
}

/// A column's name as the text prints it: `theta` → θ, `x1'` → ẋ₁.
pub(crate) fn pretty_column(name: &str) -> String {
    let base = name.trim_end_matches('\'');
    let dots = (name.len() - base.len()) as u32;
    crate::expr::print::pretty_name(base, dots)
}

/// How many evenly spaced times `--plot` samples the dense output at,
/// beside the output times of `--points`: smooth curves at any `--points`
/// (4,000 is ~4 samples per pixel column of the 900-pixel figure).
pub const SAMPLES: usize = 4_000;

/// The figure of a run, as SVG text: [`Run::plot_rows`] when the run
/// sampled them, else its rows.
pub fn svg(run: &Run) -> Result<String, PlotError> {
    let rows = if run.plot_rows.is_empty() {
        &run.rows
    } else {
        &run.plot_rows
    };
    let n = (run.columns.len() - 1) / 2;
    let energy = run.columns.last().is_some_and(|c| c == "energy");
    let panels = if energy { 3 } else { 2 };
    let mut out = String::new();
    {
        let root =
            SVGBackend::with_string(&mut out, (900, 320 * panels as u32)).into_drawing_area();
        root.fill(&WHITE).map_err(PlotError::drawing)?;
        let areas = root.split_evenly((panels, 1));
        let t: Vec<f64> = rows.iter().map(|r| r[0]).collect();
        let col = |k: usize| -> Vec<f64> { rows.iter().map(|r| r[k]).collect() };
        let range = |vs: &[Vec<f64>]| -> (f64, f64) {
            let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
            for v in vs.iter().flatten().filter(|x| x.is_finite()) {
                lo = lo.min(*v);
                hi = hi.max(*v);
            }
            if !lo.is_finite() {
                return (-1.0, 1.0);
            }
            let pad = ((hi - lo) * 0.05).max(1e-12 * (1.0 + hi.abs()));
            (lo - pad, hi + pad)
        };
        let (t0, t1) = (
            t.first().copied().unwrap_or(0.0),
            t.last().copied().unwrap_or(1.0),
        );
        let title = format!("{} — {}", method_name(run.method), "q(t)");

        // q(t)
        let qs: Vec<Vec<f64>> = (1..=n).map(col).collect();
        let (lo, hi) = range(&qs);
        // headroom above the curves for the legend (upper right)
        let hi = hi + (hi - lo) * (0.1 + 0.1 * n as f64).min(0.8);
        let mut chart = ChartBuilder::on(&areas[0])
            .caption(title, ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(30)
            .y_label_area_size(60)
            .build_cartesian_2d(t0..t1.max(t0 + 1e-12), lo..hi)
            .map_err(PlotError::drawing)?;
        chart
            .configure_mesh()
            .x_desc("t")
            .x_label_formatter(&|v| tick_label(*v, t1 - t0))
            .y_label_formatter(&|v| tick_label(*v, hi - lo))
            .draw()
            .map_err(PlotError::drawing)?;
        for (i, q) in qs.iter().enumerate() {
            let c = PALETTE[i % PALETTE.len()];
            chart
                .draw_series(LineSeries::new(t.iter().copied().zip(q.iter().copied()), c))
                .map_err(PlotError::drawing)?
                .label(pretty_column(&run.columns[1 + i]))
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], c));
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .draw()
            .map_err(PlotError::drawing)?;

        // phase portrait
        let qds: Vec<Vec<f64>> = (1..=n).map(|k| col(n + k)).collect();
        let (xlo, xhi) = range(&qs);
        let (ylo, yhi) = range(&qds);
        let mut chart = ChartBuilder::on(&areas[1])
            .caption("phase portrait q̇ against q", ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(30)
            .y_label_area_size(60)
            .build_cartesian_2d(xlo..xhi, ylo..yhi)
            .map_err(PlotError::drawing)?;
        chart
            .configure_mesh()
            .x_desc("q")
            .y_desc("q̇")
            .x_label_formatter(&|v| tick_label(*v, xhi - xlo))
            .y_label_formatter(&|v| tick_label(*v, yhi - ylo))
            .draw()
            .map_err(PlotError::drawing)?;
        for (i, (q, qd)) in qs.iter().zip(&qds).enumerate() {
            let c = PALETTE[i % PALETTE.len()];
            chart
                .draw_series(LineSeries::new(
                    q.iter().copied().zip(qd.iter().copied()),
                    c,
                ))
                .map_err(PlotError::drawing)?;
        }

        // energy error
        if energy {
            let h = col(run.columns.len() - 1);
            let h0 = h.first().copied().unwrap_or(0.0);
            let dh: Vec<f64> = h.iter().map(|x| x - h0).collect();
            let (lo, hi) = range(std::slice::from_ref(&dh));
            let mut chart = ChartBuilder::on(&areas[2])
                .caption("energy error h(t) − h(0)", ("sans-serif", 18))
                .margin(12)
                .x_label_area_size(30)
                .y_label_area_size(80)
                .build_cartesian_2d(t0..t1.max(t0 + 1e-12), lo..hi)
                .map_err(PlotError::drawing)?;
            chart
                .configure_mesh()
                .x_desc("t")
                .x_label_formatter(&|v| tick_label(*v, t1 - t0))
                .y_label_formatter(&|v| {
                    if v.abs() <= (hi - lo).abs() * 1e-9 {
                        "0".into()
                    } else {
                        format!("{v:.1e}")
                    }
                })
                .draw()
                .map_err(PlotError::drawing)?;
            chart
                .draw_series(LineSeries::new(t.iter().copied().zip(dh), BLACK))
                .map_err(PlotError::drawing)?;
        }
        root.present().map_err(PlotError::drawing)?;
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::tick_label;

    #[test]
    fn ticks_print_zero_as_zero_and_only_the_digits_the_span_needs() {
        assert_eq!(tick_label(0.0, 2.0), "0");
        assert_eq!(tick_label(-0.0, 2.0), "0");
        assert_eq!(tick_label(-2.6e-23, 2.0), "0");
        assert_eq!(tick_label(0.2, 2.0), "0.2");
        assert_eq!(tick_label(-1.0, 2.0), "-1");
        assert_eq!(tick_label(15.0, 100.0), "15");
        assert_eq!(tick_label(2.0e-8, 1.0e-7), "2.0e-8");
        assert_eq!(tick_label(0.0, 1.0e-7), "0");
    }
}
