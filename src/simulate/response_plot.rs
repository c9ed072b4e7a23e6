//! `qdot response --over … --plot FILE.svg`: the resonance curves as an
//! SVG figure (plotters).
//!
//! Two panels against Ω on a logarithmic axis: every coordinate's
//! amplitude |X_j| (logarithmic too) and its phase φ_j in degrees (made
//! continuous along each curve: no jumps of 360° where the principal value
//! wraps); each
//! undamped natural frequency is a dashed grey vertical line in both. Rows
//! with Ω ≤ 0, a zero amplitude or a singular matrix break the curves.

use super::plot::{pretty_column, tick_label, PlotError};
use super::response::ResponseTable;
use crate::drawing::style::{self, colour, log_label};
use plotters::prelude::*;

/// The runs of consecutive finite points with positive x (and positive y
/// when `log_y`).
fn runs(x: &[f64], y: impl Iterator<Item = Option<f64>>, log_y: bool) -> Vec<Vec<(f64, f64)>> {
    let mut out: Vec<Vec<(f64, f64)>> = vec![Vec::new()];
    for (&x, y) in x.iter().zip(y) {
        match y {
            Some(y) if x > 0.0 && y.is_finite() && (!log_y || y > 0.0) => {
                if let Some(last) = out.last_mut() {
                    last.push((x, y));
                }
            }
            _ => out.push(Vec::new()),
        }
    }
    out.retain(|r| !r.is_empty());
    out
}

/// A run of phases made continuous: a jump of more than 180° between
/// neighbours is the principal value wrapping, and is taken out.
fn unwrap_degrees(run: &mut [(f64, f64)]) {
    let mut shift = 0.0;
    for k in 1..run.len() {
        let step = run[k].1 + shift - run[k - 1].1;
        if step > 180.0 {
            shift -= 360.0;
        } else if step < -180.0 {
            shift += 360.0;
        }
        run[k].1 += shift;
    }
}

/// The least and largest of `v`, or `None` when it is empty.
fn span(v: impl Iterator<Item = f64>) -> Option<(f64, f64)> {
    v.fold(None, |acc, x| match acc {
        None => Some((x, x)),
        Some((lo, hi)) => Some((lo.min(x), hi.max(x))),
    })
}

/// The figure of a sweep, as SVG text, titled `title`.
pub fn svg(t: &ResponseTable, title: &str) -> Result<String, PlotError> {
    let n = t.coordinates.len();
    let amp: Vec<Vec<Vec<(f64, f64)>>> = (0..n)
        .map(|j| runs(&t.omega, t.amplitude.iter().map(|r| r[j]), true))
        .collect();
    let phase: Vec<Vec<Vec<(f64, f64)>>> = (0..n)
        .map(|j| {
            let mut rs = runs(
                &t.omega,
                t.phase.iter().map(|r| r[j].map(f64::to_degrees)),
                false,
            );
            rs.iter_mut().for_each(|r| unwrap_degrees(r));
            rs
        })
        .collect();
    let none = || PlotError {
        message: "nothing to draw: a logarithmic axis needs Ω > 0 and an amplitude > 0".into(),
    };
    let (w0, w1) = span(amp.iter().flatten().flatten().map(|p| p.0)).ok_or_else(none)?;
    let (a0, a1) = span(amp.iter().flatten().flatten().map(|p| p.1)).ok_or_else(none)?;
    let (w1, a1) = (w1.max(w0 * 1.0001), a1.max(a0 * 1.0001));
    let (a0, a1) = (a0 / 1.5, a1 * 1.5);
    let marks: Vec<f64> = t
        .natural_frequencies
        .iter()
        .copied()
        .filter(|w| (w0..=w1).contains(w))
        .collect();
    let mut out = String::new();
    {
        let root = SVGBackend::with_string(&mut out, (900, 640)).into_drawing_area();
        root.fill(&WHITE).map_err(PlotError::drawing)?;
        let areas = root.split_evenly((2, 1));
        let mut chart = ChartBuilder::on(&areas[0])
            .caption(
                format!("{title} — amplitude |X| against Ω"),
                style::font(style::CAPTION),
            )
            .margin(12)
            .x_label_area_size(50)
            .y_label_area_size(90)
            .build_cartesian_2d((w0..w1).log_scale(), (a0..a1).log_scale())
            .map_err(PlotError::drawing)?;
        style::mesh(&mut chart.configure_mesh())
            .x_desc("Ω")
            .x_label_formatter(&|v| log_label(*v))
            .y_label_formatter(&|v| log_label(*v))
            .draw()
            .map_err(PlotError::drawing)?;
        for &w in &marks {
            chart
                .draw_series(DashedLineSeries::new(
                    [(w, a0), (w, a1)],
                    6,
                    4,
                    RGBColor(150, 150, 150).into(),
                ))
                .map_err(PlotError::drawing)?;
        }
        for (j, rs) in amp.iter().enumerate() {
            let c = colour(j);
            for (k, r) in rs.iter().enumerate() {
                let s = chart
                    .draw_series(LineSeries::new(
                        r.iter().copied(),
                        c.stroke_width(style::LINE),
                    ))
                    .map_err(PlotError::drawing)?;
                if k == 0 {
                    s.label(pretty_column(&t.coordinates[j]))
                        .legend(move |(x, y)| {
                            PathElement::new(
                                vec![(x, y), (x + 24, y)],
                                c.stroke_width(style::LINE + 1),
                            )
                        });
                }
            }
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .label_font(style::font(style::LEGEND))
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .draw()
            .map_err(PlotError::drawing)?;

        let (p0, p1) = span(phase.iter().flatten().flatten().map(|p| p.1)).unwrap_or((0.0, 180.0));
        let (p0, p1) = (p0 - 10.0, p1 + 10.0);
        let mut chart = ChartBuilder::on(&areas[1])
            .caption("phase φ (degrees) against Ω", style::font(style::CAPTION))
            .margin(12)
            .x_label_area_size(50)
            .y_label_area_size(90)
            .build_cartesian_2d((w0..w1).log_scale(), p0..p1)
            .map_err(PlotError::drawing)?;
        style::mesh(&mut chart.configure_mesh())
            .x_desc("Ω")
            .x_label_formatter(&|v| log_label(*v))
            .y_label_formatter(&|v| tick_label(*v, p1 - p0))
            .draw()
            .map_err(PlotError::drawing)?;
        for &w in &marks {
            chart
                .draw_series(DashedLineSeries::new(
                    [(w, p0), (w, p1)],
                    6,
                    4,
                    RGBColor(150, 150, 150).into(),
                ))
                .map_err(PlotError::drawing)?;
        }
        for (j, rs) in phase.iter().enumerate() {
            let c = colour(j);
            for r in rs {
                chart
                    .draw_series(LineSeries::new(
                        r.iter().copied(),
                        c.stroke_width(style::LINE),
                    ))
                    .map_err(PlotError::drawing)?;
            }
        }
        root.present().map_err(PlotError::drawing)?;
    }
    Ok(out)
}
