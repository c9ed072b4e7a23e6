//! `qdot cycle --plot FILE.svg`: the reaction diagrams over a cycle as an
//! SVG figure (plotters).
//!
//! Panels, top to bottom: each joint's reaction components against the
//! varied quantity (a slider's moment in a panel of its own: it is not a
//! force); the drives' generalized forces; then, two to a row, the polar
//! diagram of every pin's force (`NAME_y` against `NAME_x`, equal scales,
//! the origin marked). A row whose value is `None` (a dead point, a stick)
//! breaks the curve: each unbroken run is one `<polyline>`, and a run of a
//! single row is a dot.

use crate::cycle::{CycleTable, JointKind};
use crate::drawing::style::{self, PALETTE};
use crate::simulate::plot::{pretty_column, tick_label, PlotError};
use plotters::coord::ranged1d::{DefaultFormatting, KeyPointHint};
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use std::ops::Range;

/// The figure's width, a curve panel's height and a polar panel's side
/// (two polar panels share a row of the figure's width), in pixels.
const WIDTH: u32 = 900;
const PANEL_HEIGHT: u32 = 280;
const POLAR_SIDE: u32 = WIDTH / 2;
/// The figure's title bar.
const TITLE_HEIGHT: u32 = 50;
const MARGIN: u32 = 12;
const X_LABELS: u32 = 50;
const Y_LABELS: u32 = 80;

/// One panel of curves against the varied quantity.
struct CurvePanel {
    caption: String,
    /// The curves' columns in [`CycleTable::columns`].
    columns: Vec<usize>,
}

/// One pin's polar diagram.
struct PolarPanel {
    caption: String,
    x: usize,
    y: usize,
}

/// Column `c`'s name as the text prints it (`?` past the last column).
fn column_name(table: &CycleTable, c: usize) -> String {
    table
        .columns
        .get(c)
        .map_or_else(|| "?".into(), |n| pretty_column(n))
}

/// Who a joint's reaction acts on, and from whom.
pub(super) fn acting(bodies: &[Option<String>; 2]) -> (String, String) {
    let name = |b: &Option<String>| b.clone().unwrap_or_else(|| "ground".into());
    (name(&bodies[1]), name(&bodies[0]))
}

/// The panels a table draws: curves against the varied quantity, and the
/// pins' polar diagrams.
fn panels(table: &CycleTable) -> (Vec<CurvePanel>, Vec<PolarPanel>) {
    let mut curves = Vec::new();
    let mut polars = Vec::new();
    for joint in &table.joints {
        let (on, from) = acting(&joint.bodies);
        let name = pretty_column(&joint.name);
        match joint.kind {
            JointKind::Pin => {
                curves.push(CurvePanel {
                    caption: format!("pin {name}: force on {on} from {from}"),
                    columns: joint.columns.clone(),
                });
                if let [x, y] = joint.columns[..] {
                    polars.push(PolarPanel {
                        caption: format!("pin {name}: polar diagram of its force on {on}"),
                        x,
                        y,
                    });
                }
            }
            JointKind::Slider => {
                // NAME_n is a force, NAME_m (when present) a moment
                let (force, moment) = joint.columns.split_at(joint.columns.len().min(1));
                curves.push(CurvePanel {
                    caption: format!("slider {name}: force on {on} across the guide"),
                    columns: force.to_vec(),
                });
                if !moment.is_empty() {
                    curves.push(CurvePanel {
                        caption: format!("slider {name}: moment on {on}"),
                        columns: moment.to_vec(),
                    });
                }
            }
        }
    }
    if !table.drives.is_empty() {
        let names: Vec<String> = table
            .drives
            .iter()
            .map(|d| {
                format!(
                    "{} (along {})",
                    pretty_column(&d.name),
                    pretty_column(&d.coordinate)
                )
            })
            .collect();
        curves.push(CurvePanel {
            caption: format!("driving force: {}", names.join(", ")),
            columns: table.drives.iter().map(|d| d.column).collect(),
        });
    }
    (curves, polars)
}

/// The unbroken runs of a curve: a point is dropped, and the run broken,
/// where either coordinate is `None` or not finite.
fn runs(points: impl Iterator<Item = (Option<f64>, Option<f64>)>) -> Vec<Vec<(f64, f64)>> {
    let mut out: Vec<Vec<(f64, f64)>> = Vec::new();
    let mut run: Vec<(f64, f64)> = Vec::new();
    for p in points {
        match p {
            (Some(x), Some(y)) if x.is_finite() && y.is_finite() => run.push((x, y)),
            _ if !run.is_empty() => out.push(std::mem::take(&mut run)),
            _ => {}
        }
    }
    if !run.is_empty() {
        out.push(run);
    }
    out
}

/// The smallest and largest finite values, padded by 5% (a constant by
/// ±10% of itself, or ±1 at 0, so its axis has ticks).
fn padded_range(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in values.filter(|v| v.is_finite()) {
        lo = lo.min(v);
        hi = hi.max(v);
    }
    if !lo.is_finite() {
        return (-1.0, 1.0);
    }
    let size = lo.abs().max(hi.abs());
    if hi - lo <= 1e-9 * size {
        let pad = if size > 0.0 { 0.1 * size } else { 1.0 };
        return (lo - pad, hi + pad);
    }
    let pad = 0.05 * (hi - lo);
    (lo - pad, hi + pad)
}

/// A value with 4 significant digits, without trailing zeros.
fn round(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return if v.is_finite() {
            "0".into()
        } else {
            v.to_string()
        };
    }
    let decimals = (3 - v.abs().log10().floor() as i32).clamp(0, 12) as usize;
    let s = format!("{v:.decimals$}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

/// The varied axis: its ticks where [`ticks`] puts them (plotters'
/// own would put 50° steps on a turn of the crank).
struct Ticked {
    range: RangedCoordf64,
    ticks: Vec<f64>,
}

impl Ticked {
    fn new(lo: f64, hi: f64, degrees: bool) -> Ticked {
        Ticked {
            range: (lo..hi).into(),
            ticks: ticks(lo, hi, degrees),
        }
    }
}

impl Ranged for Ticked {
    type FormatOption = DefaultFormatting;
    type ValueType = f64;

    fn map(&self, value: &f64, limit: (i32, i32)) -> i32 {
        self.range.map(value, limit)
    }

    fn key_points<Hint: KeyPointHint>(&self, _hint: Hint) -> Vec<f64> {
        self.ticks.clone()
    }

    fn range(&self) -> Range<f64> {
        self.range.range()
    }
}

/// The varied axis's ticks: multiples of a round angle (15°, 30°, 45°,
/// 90°, …) in degrees, else of 1, 2 or 5 times a power of ten; about ten.
fn ticks(lo: f64, hi: f64, degrees: bool) -> Vec<f64> {
    let span = hi - lo;
    if !(span.is_finite() && span > 0.0) {
        return vec![lo];
    }
    let decade = 10f64.powf((span / 10.0).log10().floor());
    let steps: Vec<f64> = if degrees && span >= 30.0 {
        [15.0, 30.0, 45.0, 90.0, 180.0, 360.0, 720.0, 1440.0]
            .into_iter()
            .chain([1.0, 2.0, 5.0].map(|m| m * decade * 10.0))
            .collect()
    } else {
        [1.0, 2.0, 5.0, 10.0].map(|m| m * decade).to_vec()
    };
    let most = if degrees { 12.0 } else { 10.0 };
    let step = steps.into_iter().find(|s| span / s <= most).unwrap_or(span);
    let first = (lo / step).ceil() as i64;
    let last = (hi / step).floor() as i64;
    (first..=last).map(|k| k as f64 * step).collect()
}

/// The reaction diagrams of a cycle, as SVG text. `degrees`: the varied
/// column is an angle in radians (a crank's), shown in degrees; false for
/// `t` or a length.
pub fn reaction_diagrams(
    table: &CycleTable,
    title: &str,
    degrees: bool,
) -> Result<String, PlotError> {
    // a stick is drawn as the jump between its two limits, not a hole
    let table = &table.stick_rows_split();
    let (curves, polars) = panels(table);
    let polar_rows = polars.len().div_ceil(2) as u32;
    let height = TITLE_HEIGHT + PANEL_HEIGHT * curves.len() as u32 + POLAR_SIDE * polar_rows;
    let mut out = String::new();
    {
        let root = SVGBackend::with_string(&mut out, (WIDTH, height)).into_drawing_area();
        root.fill(&WHITE).map_err(PlotError::drawing)?;
        let (head, body) = root.split_vertically(TITLE_HEIGHT);
        head.titled(title, style::font(style::TITLE))
            .map_err(PlotError::drawing)?;
        let (top, bottom) = body.split_vertically(PANEL_HEIGHT * curves.len() as u32);
        let varied: Vec<Option<f64>> = table
            .rows
            .iter()
            .map(|r| {
                let v = r.values.first().copied().flatten();
                if degrees {
                    v.map(f64::to_degrees)
                } else {
                    v
                }
            })
            .collect();
        let x_desc = if degrees {
            format!("{} (°)", pretty_column(&table.varied))
        } else {
            pretty_column(&table.varied)
        };
        if !curves.is_empty() {
            for (panel, area) in curves.iter().zip(top.split_evenly((curves.len(), 1))) {
                curve_panel(table, panel, &area, &varied, &x_desc, degrees)?;
            }
        }
        if polar_rows > 0 {
            let cells = bottom.split_evenly((polar_rows as usize, 2));
            for (panel, area) in polars.iter().zip(cells) {
                polar_panel(table, panel, &area, degrees)?;
            }
        }
        root.present().map_err(PlotError::drawing)?;
    }
    Ok(out)
}

type Area<'a> = DrawingArea<SVGBackend<'a>, plotters::coord::Shift>;

/// One panel of curves against the varied quantity, with a legend.
fn curve_panel(
    table: &CycleTable,
    panel: &CurvePanel,
    area: &Area,
    varied: &[Option<f64>],
    x_desc: &str,
    degrees: bool,
) -> Result<(), PlotError> {
    let value = |row: usize, col: usize| table.rows[row].values.get(col).copied().flatten();
    let (x0, x1) = {
        let finite = || varied.iter().flatten().copied().filter(|v| v.is_finite());
        let lo = finite().fold(f64::INFINITY, f64::min);
        let hi = finite().fold(f64::NEG_INFINITY, f64::max);
        if lo < hi {
            (lo, hi)
        } else if lo.is_finite() {
            (lo - 1.0, lo + 1.0)
        } else {
            (0.0, 1.0)
        }
    };
    let (lo, hi) = padded_range(
        panel
            .columns
            .iter()
            .flat_map(|&c| (0..table.rows.len()).filter_map(move |r| value(r, c))),
    );
    // headroom above the curves for the legend (upper right)
    let hi = hi + (hi - lo) * 0.12 * panel.columns.len() as f64;
    let mut chart = ChartBuilder::on(area)
        .caption(&panel.caption, style::font(style::CAPTION))
        .margin(MARGIN)
        .x_label_area_size(X_LABELS)
        .y_label_area_size(Y_LABELS)
        .build_cartesian_2d(Ticked::new(x0, x1, degrees), lo..hi)
        .map_err(PlotError::drawing)?;
    let names: Vec<String> = panel
        .columns
        .iter()
        .map(|&c| column_name(table, c))
        .collect();
    style::mesh(&mut chart.configure_mesh())
        .y_labels(6)
        .x_desc(x_desc)
        .y_desc(names.join(", "))
        .x_label_formatter(&|v| tick_label(*v, x1 - x0))
        .y_label_formatter(&|v| tick_label(*v, hi - lo))
        .draw()
        .map_err(PlotError::drawing)?;
    for (i, (&col, name)) in panel.columns.iter().zip(&names).enumerate() {
        let colour = style::colour(i);
        let line = colour.stroke_width(style::LINE);
        let curve = runs((0..table.rows.len()).map(|r| (varied[r], value(r, col))));
        let mut labelled = false;
        for run in curve {
            let series = if run.len() == 1 {
                chart.draw_series(std::iter::once(Circle::new(run[0], 3, colour.filled())))
            } else {
                chart.draw_series(LineSeries::new(run, line))
            }
            .map_err(PlotError::drawing)?;
            if !labelled {
                series.label(name.as_str()).legend(move |(x, y)| {
                    PathElement::new(
                        vec![(x, y), (x + 24, y)],
                        colour.stroke_width(style::LINE + 1),
                    )
                });
                labelled = true;
            }
        }
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperRight)
        .label_font(style::font(style::LEGEND))
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .draw()
        .map_err(PlotError::drawing)?;
    Ok(())
}

/// Ranges around the data (and the origin) with one unit per pixel on
/// both axes, for a plotting area of `pixels`.
fn equal_scale(x: (f64, f64), y: (f64, f64), pixels: (u32, u32)) -> ((f64, f64), (f64, f64)) {
    let (w, h) = (pixels.0.max(1) as f64, pixels.1.max(1) as f64);
    let per_pixel = ((x.1 - x.0) / w).max((y.1 - y.0) / h);
    let (xc, yc) = ((x.0 + x.1) / 2.0, (y.0 + y.1) / 2.0);
    (
        (xc - per_pixel * w / 2.0, xc + per_pixel * w / 2.0),
        (yc - per_pixel * h / 2.0, yc + per_pixel * h / 2.0),
    )
}

/// A pin's polar diagram: its force's y component against its x
/// component over the cycle, equal scales, the origin marked by a cross
/// and the first row by a dot.
fn polar_panel(
    table: &CycleTable,
    panel: &PolarPanel,
    area: &Area,
    degrees: bool,
) -> Result<(), PlotError> {
    let value = |row: &crate::cycle::CycleRow, col: usize| row.values.get(col).copied().flatten();
    let pairs: Vec<(Option<f64>, Option<f64>)> = table
        .rows
        .iter()
        .map(|r| (value(r, panel.x), value(r, panel.y)))
        .collect();
    let origin = std::iter::once(0.0);
    let x = padded_range(pairs.iter().filter_map(|p| p.0).chain(origin.clone()));
    let y = padded_range(pairs.iter().filter_map(|p| p.1).chain(origin));
    let inner = area
        .titled(&panel.caption, style::font(style::AXIS))
        .map_err(PlotError::drawing)?;
    let builder = || {
        let mut b = ChartBuilder::on(&inner);
        b.margin(MARGIN)
            .x_label_area_size(X_LABELS)
            .y_label_area_size(Y_LABELS);
        b
    };
    // building a chart without a caption draws nothing: measure its
    // plotting area first, then build it with equal scales
    let pixels = builder()
        .build_cartesian_2d(0.0..1.0, 0.0..1.0)
        .map_err(PlotError::drawing)?
        .plotting_area()
        .dim_in_pixel();
    let ((x0, x1), (y0, y1)) = equal_scale(x, y, pixels);
    let mut chart: ChartContext<_, Cartesian2d<RangedCoordf64, RangedCoordf64>> = builder()
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(PlotError::drawing)?;
    let (xn, yn) = (column_name(table, panel.x), column_name(table, panel.y));
    style::mesh(&mut chart.configure_mesh())
        .x_labels(6)
        .y_labels(8)
        .x_desc(xn.as_str())
        .y_desc(yn.as_str())
        .x_label_formatter(&|v| tick_label(*v, x1 - x0))
        .y_label_formatter(&|v| tick_label(*v, y1 - y0))
        .draw()
        .map_err(PlotError::drawing)?;
    chart
        .draw_series(std::iter::once(Cross::new(
            (0.0, 0.0),
            7,
            BLACK.stroke_width(2),
        )))
        .map_err(PlotError::drawing)?;
    let colour = PALETTE[0];
    for run in runs(pairs.iter().copied()) {
        if run.len() == 1 {
            chart.draw_series(std::iter::once(Circle::new(run[0], 3, colour.filled())))
        } else {
            chart.draw_series(LineSeries::new(run, colour.stroke_width(style::LINE)))
        }
        .map_err(PlotError::drawing)?;
    }
    // where the cycle starts, so the diagram's sense can be read
    let start = table.rows.iter().zip(&pairs).find_map(|(r, p)| match p {
        (Some(x), Some(y)) => Some((r, (*x, *y))),
        _ => None,
    });
    if let Some((row, at)) = start {
        let v = row.values.first().copied().flatten().unwrap_or(f64::NAN);
        let label = if degrees {
            format!(
                "{} = {}°",
                pretty_column(&table.varied),
                round(v.to_degrees())
            )
        } else {
            format!("{} = {}", pretty_column(&table.varied), round(v))
        };
        chart
            .draw_series(std::iter::once(Circle::new(at, 5, PALETTE[1].filled())))
            .map_err(PlotError::drawing)?
            .label(label)
            .legend(|(x, y)| Circle::new((x + 10, y), 5, PALETTE[1].filled()));
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .label_font(style::font(style::LEGEND))
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .draw()
            .map_err(PlotError::drawing)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::drawing::fixture::{slider_crank, with_dead_point};

    /// The points of every `<polyline>` with more than two (a legend's
    /// sample line has two), as (x, y) pixels.
    fn curves(svg: &str) -> Vec<Vec<(f64, f64)>> {
        svg.split("<polyline")
            .skip(1)
            .filter_map(|tag| {
                let tag = &tag[..tag.find('>').unwrap()];
                let body = &tag[tag.find("points=\"")? + 8..];
                let body = &body[..body.find('"').unwrap()];
                let points: Vec<(f64, f64)> = body
                    .split_whitespace()
                    .map(|xy| {
                        let (x, y) = xy.split_once(',').unwrap();
                        (x.parse().unwrap(), y.parse().unwrap())
                    })
                    .collect();
                (points.len() > 2).then_some(points)
            })
            .collect()
    }

    /// Every `<text>` element's text.
    fn texts(svg: &str) -> Vec<&str> {
        svg.split("<text")
            .skip(1)
            .map(|t| {
                let t = &t[t.find('>').unwrap() + 1..];
                t[..t.find("</text>").unwrap()].trim()
            })
            .collect()
    }

    #[test]
    fn every_curve_is_one_polyline_through_every_row() {
        let svg = reaction_diagrams(&slider_crank(), "slider-crank", true).unwrap();
        // O_x, O_y, A_x, A_y, B_x, B_y, G_n, M; the polar diagrams of O, A, B
        let curves = curves(&svg);
        assert_eq!(curves.len(), 8 + 3);
        assert!(curves.iter().all(|c| c.len() == 13), "{curves:?}");
        // the varied axis: φ left to right
        assert!(curves[0].windows(2).all(|w| w[1].0 > w[0].0));
        let texts = texts(&svg);
        for label in [
            "O_x",
            "O_y",
            "A_x",
            "B_y",
            "G_n",
            "M",
            "φ (°)",
            "slider-crank",
        ] {
            assert!(texts.contains(&label), "{label} not in {texts:?}");
        }
        // the crank angle's ticks every 30°
        for tick in ["0", "30", "90", "150", "180", "270", "330", "360"] {
            assert!(texts.contains(&tick), "{tick} not in {texts:?}");
        }
        assert!(texts.contains(&"pin O: polar diagram of its force on crank"));
        assert!(texts.contains(&"φ = 0°"), "{texts:?}");
    }

    #[test]
    fn a_row_without_values_breaks_every_curve_there() {
        let svg = reaction_diagrams(&with_dead_point(6), "dead point", true).unwrap();
        let curves = curves(&svg);
        // rows 0..=5 and 7..=12 of each of the 11 curves, nothing across row 6
        assert_eq!(curves.len(), 2 * 11);
        assert!(curves.iter().all(|c| c.len() == 6), "{curves:?}");
        let left = &curves[0];
        let right = &curves[1];
        assert!(left.last().unwrap().0 < right[0].0);
    }

    #[test]
    fn a_single_row_between_gaps_is_a_dot() {
        let mut t = with_dead_point(5);
        for v in &mut t.rows[7].values[25..] {
            *v = None;
        }
        let svg = reaction_diagrams(&t, "isolated", false).unwrap();
        // rows 0..=4 and 8..=12 as polylines, row 6 as one dot per curve
        // (plus the polar diagrams' start dots and their legend)
        assert_eq!(curves(&svg).len(), 2 * 11);
        assert_eq!(svg.matches("<circle").count(), 11 + 3 + 3);
        // t in radians: the axis says φ alone
        assert!(texts(&svg).contains(&"φ"));
    }

    #[test]
    fn a_polar_diagram_has_one_unit_per_pixel_both_ways() {
        // 4 by 1 in a 400 by 300 area: x fills it, y widens about its centre
        let (x, y) = equal_scale((-1.0, 3.0), (0.0, 1.0), (400, 300));
        assert_eq!(x, (-1.0, 3.0));
        assert_eq!(y, (-1.0, 2.0));
        // pixels: the polar O curve's extent in x over its extent in y is
        // the data's (O_y = A_y, O_x = B_x)
        let t = slider_crank();
        let svg = reaction_diagrams(&t, "", true).unwrap();
        let polar = &curves(&svg)[8];
        let span = |f: &dyn Fn(&(f64, f64)) -> f64, pts: &[(f64, f64)]| {
            let v: Vec<f64> = pts.iter().map(f).collect();
            v.iter().cloned().fold(f64::MIN, f64::max) - v.iter().cloned().fold(f64::MAX, f64::min)
        };
        let col = |c: usize| -> Vec<f64> { t.rows.iter().map(|r| r.values[c].unwrap()).collect() };
        let (ox, oy) = (col(25), col(26));
        let data_ratio = span(&|v| v.0, &ox.iter().map(|&x| (x, 0.0)).collect::<Vec<_>>())
            / span(&|v| v.0, &oy.iter().map(|&y| (y, 0.0)).collect::<Vec<_>>());
        let pixel_ratio = span(&|p| p.0, polar) / span(&|p| p.1, polar);
        assert!(
            (pixel_ratio / data_ratio - 1.0).abs() < 0.02,
            "{pixel_ratio} {data_ratio}"
        );
    }

    #[test]
    fn a_table_without_rows_draws_empty_panels() {
        let mut t = slider_crank();
        t.rows.clear();
        let svg = reaction_diagrams(&t, "nothing yet", true).unwrap();
        assert_eq!(curves(&svg).len(), 0);
        assert!(texts(&svg).contains(&"pin O: polar diagram of its force on crank"));
        let html = crate::drawing::animation_html(&t, "nothing yet", true);
        assert!(html.contains("max=\"0\""));
        assert!(html.contains("\"rows\":[],\"targets\":[],\"frames\":[]"));
    }

    #[test]
    fn the_varied_axis_ticks_are_round() {
        assert_eq!(
            ticks(0.0, 360.0, true),
            (0..=12).map(|k| k as f64 * 30.0).collect::<Vec<_>>()
        );
        assert_eq!(ticks(-180.0, 180.0, true)[..3], [-180.0, -150.0, -120.0]);
        assert_eq!(
            ticks(0.0, 90.0, true),
            [0.0, 15.0, 30.0, 45.0, 60.0, 75.0, 90.0]
        );
        assert_eq!(
            ticks(0.0, 720.0, true),
            (0..=8).map(|k| k as f64 * 90.0).collect::<Vec<_>>()
        );
        assert_eq!(ticks(0.0, 6.3, false), [0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0]);
        assert_eq!(
            ticks(-2.5, 12.0, false),
            [-2.0, 0.0, 2.0, 4.0, 6.0, 8.0, 10.0, 12.0]
        );
    }

    #[test]
    fn runs_break_at_none_and_non_finite() {
        let r = runs(
            [
                (Some(0.0), Some(1.0)),
                (Some(1.0), None),
                (Some(2.0), Some(2.0)),
                (Some(3.0), Some(f64::NAN)),
                (None, Some(1.0)),
                (Some(5.0), Some(3.0)),
                (Some(6.0), Some(4.0)),
            ]
            .into_iter(),
        );
        assert_eq!(
            r,
            vec![
                vec![(0.0, 1.0)],
                vec![(2.0, 2.0)],
                vec![(5.0, 3.0), (6.0, 4.0)]
            ]
        );
        assert_eq!(round(12.3456), "12.35");
        assert_eq!(round(-0.0012345), "-0.001234");
        assert_eq!(round(360.0), "360");
    }
}
