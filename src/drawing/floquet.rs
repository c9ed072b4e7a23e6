//! `qdot floquet --over … --plot FILE.svg`: the stability chart over two
//! parameters (the Ince–Strutt diagram for the Mathieu equation), one
//! filled cell per grid point, or the largest |μ| against one parameter.

use crate::app::FloquetRun;
use crate::drawing::style::{self, PALETTE};
use crate::floquet::Verdict;
use crate::simulate::plot::{pretty_column, tick_label, PlotError};
use plotters::prelude::*;

/// The fill of unstable, stable, undecided and failed cells.
const UNSTABLE: RGBColor = RGBColor(214, 39, 40);
const STABLE: RGBColor = RGBColor(235, 242, 250);
const UNDECIDED: RGBColor = RGBColor(150, 150, 150);
const FAILED: RGBColor = RGBColor(0, 0, 0);

/// The figure as SVG text; an error without `--over`.
pub fn svg(run: &FloquetRun, title: &str) -> Result<String, PlotError> {
    match run.axes.len() {
        1 => curve(run, title),
        2 => chart(run, title),
        _ => Err(PlotError {
            message: "--plot draws a chart over --over parameters: give one or two".into(),
        }),
    }
}

/// Half a grid step of `count` values over `from..to` (at least a little).
fn half_step(from: f64, to: f64, count: usize) -> f64 {
    let step = (to - from).abs() / (count.max(2) - 1) as f64;
    if step > 0.0 {
        0.5 * step
    } else {
        0.5
    }
}

/// Two parameters: a cell per point, coloured by the verdict.
fn chart(run: &FloquetRun, title: &str) -> Result<String, PlotError> {
    let (a, b) = (&run.axes[0], &run.axes[1]);
    let (ha, hb) = (
        half_step(a.from, a.to, a.count),
        half_step(b.from, b.to, b.count),
    );
    let (x0, x1) = (a.from.min(a.to) - ha, a.from.max(a.to) + ha);
    let (y0, y1) = (b.from.min(b.to) - hb, b.from.max(b.to) + hb);
    let mut out = String::new();
    {
        let root = SVGBackend::with_string(&mut out, (800, 640)).into_drawing_area();
        root.fill(&WHITE).map_err(PlotError::drawing)?;
        let caption =
            format!("{title}: stability chart (red: unstable, pale: stable, grey: undecided)");
        let mut c = ChartBuilder::on(&root)
            .caption(caption, style::font(style::CAPTION))
            .margin(14)
            .x_label_area_size(50)
            .y_label_area_size(80)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(PlotError::drawing)?;
        style::mesh(&mut c.configure_mesh())
            .disable_mesh()
            .x_desc(pretty_column(&a.name))
            .y_desc(pretty_column(&b.name))
            .x_label_formatter(&|v| tick_label(*v, x1 - x0))
            .y_label_formatter(&|v| tick_label(*v, y1 - y0))
            .draw()
            .map_err(PlotError::drawing)?;
        // one rectangle per run of equal verdicts along a row
        let colour = |f: &Result<crate::floquet::Floquet, String>| match f {
            Ok(f) if f.verdict == Verdict::Unstable => UNSTABLE,
            Ok(f) if f.verdict == Verdict::Stable => STABLE,
            Ok(_) => UNDECIDED,
            Err(_) => FAILED,
        };
        let mut cells = Vec::new();
        for row in run.points.chunks(a.count) {
            let mut start = 0;
            for i in 1..=row.len() {
                if i == row.len() || colour(&row[i].1) != colour(&row[start].1) {
                    let (v0, v1) = (&row[start].0, &row[i - 1].0);
                    let (lo, hi) = (v0[0].min(v1[0]), v0[0].max(v1[0]));
                    cells.push(Rectangle::new(
                        [(lo - ha, v0[1] - hb), (hi + ha, v0[1] + hb)],
                        colour(&row[start].1).filled(),
                    ));
                    start = i;
                }
            }
        }
        c.draw_series(cells).map_err(PlotError::drawing)?;
        root.present().map_err(PlotError::drawing)?;
    }
    Ok(out)
}

/// One parameter: the largest |μ| against it, the line |μ| = 1 marked.
fn curve(run: &FloquetRun, title: &str) -> Result<String, PlotError> {
    let a = &run.axes[0];
    let points: Vec<(f64, f64)> = run
        .points
        .iter()
        .filter_map(|(v, f)| f.as_ref().ok().map(|f| (v[0], f.max_abs)))
        .filter(|(_, y)| y.is_finite())
        .collect();
    let (x0, x1) = (
        a.from.min(a.to),
        a.from.max(a.to).max(a.from.min(a.to) + 1e-12),
    );
    let hi = points.iter().fold(1.0f64, |m, p| m.max(p.1)) * 1.05;
    let lo = points.iter().fold(1.0f64, |m, p| m.min(p.1)).min(0.95);
    let mut out = String::new();
    {
        let root = SVGBackend::with_string(&mut out, (800, 420)).into_drawing_area();
        root.fill(&WHITE).map_err(PlotError::drawing)?;
        let mut c = ChartBuilder::on(&root)
            .caption(
                format!("{title}: the largest |μ|"),
                style::font(style::CAPTION),
            )
            .margin(14)
            .x_label_area_size(50)
            .y_label_area_size(80)
            .build_cartesian_2d(x0..x1, lo..hi)
            .map_err(PlotError::drawing)?;
        style::mesh(&mut c.configure_mesh())
            .x_desc(pretty_column(&a.name))
            .y_desc("max |μ|")
            .x_label_formatter(&|v| tick_label(*v, x1 - x0))
            .y_label_formatter(&|v| tick_label(*v, hi - lo))
            .draw()
            .map_err(PlotError::drawing)?;
        c.draw_series(LineSeries::new([(x0, 1.0), (x1, 1.0)], BLACK.mix(0.5)))
            .map_err(PlotError::drawing)?;
        c.draw_series(LineSeries::new(
            points,
            PALETTE[0].stroke_width(style::LINE),
        ))
        .map_err(PlotError::drawing)?;
        root.present().map_err(PlotError::drawing)?;
    }
    Ok(out)
}
