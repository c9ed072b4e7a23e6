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
    fn drawing(e: impl std::fmt::Display) -> PlotError {
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

/// The figure of a run, as SVG text.
pub fn svg(run: &Run) -> Result<String, PlotError> {
    let n = (run.columns.len() - 1) / 2;
    let energy = run.columns.last().is_some_and(|c| c == "energy");
    let panels = if energy { 3 } else { 2 };
    let mut out = String::new();
    {
        let root =
            SVGBackend::with_string(&mut out, (900, 320 * panels as u32)).into_drawing_area();
        root.fill(&WHITE).map_err(PlotError::drawing)?;
        let areas = root.split_evenly((panels, 1));
        let t: Vec<f64> = run.rows.iter().map(|r| r[0]).collect();
        let col = |k: usize| -> Vec<f64> { run.rows.iter().map(|r| r[k]).collect() };
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
            .draw()
            .map_err(PlotError::drawing)?;
        for (i, q) in qs.iter().enumerate() {
            let c = PALETTE[i % PALETTE.len()];
            chart
                .draw_series(LineSeries::new(t.iter().copied().zip(q.iter().copied()), c))
                .map_err(PlotError::drawing)?
                .label(run.columns[1 + i].clone())
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], c));
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .draw()
            .map_err(PlotError::drawing)?;

        // phase portrait
        let qds: Vec<Vec<f64>> = (1..=n).map(|k| col(n + k)).collect();
        let (xlo, xhi) = range(&qs);
        let (ylo, yhi) = range(&qds);
        let mut chart = ChartBuilder::on(&areas[1])
            .caption("phase portrait q' against q", ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(30)
            .y_label_area_size(60)
            .build_cartesian_2d(xlo..xhi, ylo..yhi)
            .map_err(PlotError::drawing)?;
        chart
            .configure_mesh()
            .x_desc("q")
            .y_desc("q'")
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
                .y_label_formatter(&|v| format!("{v:.1e}"))
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
