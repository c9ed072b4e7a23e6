//! `qdot simulate --plot FILE.svg`: the motion as an SVG figure (plotters),
//! made to be shown on a slide.
//!
//! The scene's name heads it, with the file, the parameters' values and
//! the method beneath ([`Labels`]). Then, full width, the coordinates
//! against t: one panel per unit (metres and radians do not share an
//! axis), each curve named in a legend beside it. Below, a grid of
//! panels: the phase portrait (q̇ against q) of each coordinate in its
//! colour and, when the scene is conservative, the energy error
//! h(t) − h(0), which shows the integrator's drift. Where the scene
//! declares dimensions every axis carries its unit (`t [s]`, `θ₁ [rad]`,
//! `θ̇₁ [rad/s]`). Each curve is one `<polyline>` with one point per row.

use super::run::{method_name, Request, Run};
use crate::drawing::style::{self, colour};
use crate::drawing::units::Quantity;
use crate::scene::dimension::DimensionSource;
use crate::scene::Scene;
use crate::simulate::Method;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

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
/// (4,000 is ~4 samples per pixel column of the plotting area).
pub const SAMPLES: usize = 4_000;

/// The figure's width; the height of its head (title and subtitle), of a
/// panel of coordinates against t (shorter when there are several), and
/// of a row of the grid below; the grid's most panels to a row.
const WIDTH: u32 = 1200;
const HEAD: u32 = 96;
const TIME_PANEL: u32 = 380;
const TIME_PANELS: u32 = 320;
const CELL: u32 = 420;
const CELLS_PER_ROW: usize = 3;
/// Room around a panel, for the tick labels and axis names below and
/// left of it, and for a legend's sample line.
const MARGIN: u32 = 16;
const X_LABELS: u32 = 56;
const Y_LABELS: u32 = 100;
const SAMPLE_LINE: u32 = 32;
/// Room above a plotting area for its caption.
const CAPTION_ROOM: u32 = 44;
/// A title longer than this many characters is cut at a word.
const TITLE_CHARS: usize = 72;

/// What a figure writes beside its curves: the title and subtitle, and
/// what each coordinate measures.
#[derive(Clone, Debug, Default)]
pub struct Labels {
    /// The scene's name: its first comment's first phrase, else the file's
    /// stem.
    pub title: String,
    /// The file, the parameters' values and the method.
    pub subtitle: String,
    /// Each coordinate's quantity, where the scene declares dimensions.
    pub quantities: Vec<(String, Quantity)>,
    /// Whether the scene declares dimensions: t is then in seconds and the
    /// energy in joules.
    pub dimensions: bool,
}

impl Labels {
    /// The labels of a run of the scene `src`, read from the file `file`
    /// with the request `req`. A scene that cannot be read again (it was,
    /// to run) gets no units rather than an error.
    pub fn of_scene(src: &str, file: &str, req: &Request) -> Labels {
        let scene = Scene::parse_structured(src)
            .or_else(|_| Scene::parse(src))
            .ok();
        Labels::of_run(scene.as_ref(), src, file, req)
    }

    /// [`Labels::of_scene`] with the scene already read (the one the run
    /// was made from), or none.
    pub fn of_run(scene: Option<&Scene>, src: &str, file: &str, req: &Request) -> Labels {
        let path = std::path::Path::new(file);
        let stem = path.file_stem().and_then(|s| s.to_str()).unwrap_or(file);
        let name = path.file_name().and_then(|s| s.to_str()).unwrap_or(file);
        let parameters: Vec<String> = scene
            .iter()
            .flat_map(|s| s.parameters.iter().map(|p| p.name.clone()))
            .collect();
        let quantities = scene
            .filter(|s| s.dimensions_checked)
            .map(quantities)
            .unwrap_or_default();
        Labels {
            title: scene_title(src).unwrap_or_else(|| stem.to_string()),
            subtitle: subtitle(name, &parameters, req),
            dimensions: scene.is_some_and(|s| s.dimensions_checked),
            quantities,
        }
    }

    /// What coordinate `name` measures, if the scene declares it.
    fn quantity(&self, name: &str) -> Option<&Quantity> {
        self.quantities
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, q)| q)
    }

    /// `name [unit]`, or `name` without a unit.
    fn axis(name: &str, unit: Option<String>) -> String {
        match unit {
            Some(u) => format!("{name} [{u}]"),
            None => name.to_string(),
        }
    }

    /// The time axis's name: `t [s]` or `t`.
    fn time(&self) -> String {
        Labels::axis("t", self.dimensions.then(|| "s".to_string()))
    }
}

/// Each coordinate's quantity in a scene that declares dimensions (a
/// coordinate the scene leaves free has none).
fn quantities(scene: &Scene) -> Vec<(String, Quantity)> {
    let Ok(report) = scene.dimension_report() else {
        return Vec::new();
    };
    scene
        .coordinates
        .iter()
        .filter_map(|c| {
            let named = report.names.iter().find(|n| n.name == c.name)?;
            let angle = matches!(&named.source,
                DimensionSource::Declared(w) if matches!(w.trim(), "angle" | "rad"));
            let dimension = named.dimension?;
            Some((c.name.clone(), Quantity { dimension, angle }))
        })
        .collect()
}

/// The scene's name from its first comment: the comment lines before the
/// first statement, up to the first blank comment line, joined, then cut
/// at the first `: `, ` — `, `, `, `. ` or `; ` (`# Seed problem 24.1 —
/// one degree of freedom…` → `Seed problem 24.1`).
pub fn scene_title(src: &str) -> Option<String> {
    let mut words: Vec<&str> = Vec::new();
    for line in src.lines() {
        let Some(text) = line.trim().strip_prefix('#') else {
            break;
        };
        let text = text.trim();
        if text.is_empty() {
            break;
        }
        words.push(text);
    }
    let joined = words.join(" ");
    let end = [": ", " — ", " - ", ", ", ". ", "; "]
        .iter()
        .filter_map(|sep| joined.find(sep))
        .min()
        .unwrap_or(joined.len());
    let title = joined[..end].trim_end_matches(['.', ':', ',', ';']).trim();
    if title.is_empty() {
        return None;
    }
    if title.chars().count() <= TITLE_CHARS {
        return Some(title.to_string());
    }
    let cut: String = title.chars().take(TITLE_CHARS).collect();
    let at_word = cut.rfind(' ').map_or(cut.as_str(), |i| &cut[..i]);
    Some(format!("{at_word} …"))
}

/// A number as short as it reads exactly: `9.81`, `0.1`, `1e-9`.
fn short(v: f64) -> String {
    if v == 0.0 || (1e-3..1e5).contains(&v.abs()) {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}

/// `seed_24_1.qd · m = 1, r = 0.1, … · dop853, rtol 1e-8, atol 1e-10`: the
/// parameters in the scene's order, as many as fit the figure's width.
fn subtitle(file: &str, parameters: &[String], req: &Request) -> String {
    let method = match (req.method, req.dt) {
        (Method::Rk4 | Method::Gauss6, Some(dt)) => {
            format!("{}, dt {}", method_name(req.method), short(dt))
        }
        (m, _) => format!(
            "{}, rtol {}, atol {}",
            method_name(m),
            short(req.rtol),
            short(req.atol)
        ),
    };
    let values: Vec<String> = parameters
        .iter()
        .filter_map(|p| {
            let v = req.set.get(p)?;
            Some(format!(
                "{} = {}",
                crate::expr::print::pretty_name(p, 0),
                short(*v)
            ))
        })
        .collect();
    let room = WIDTH - 2 * MARGIN;
    for shown in (0..=values.len()).rev() {
        let mut list = values[..shown].join(", ");
        if shown < values.len() {
            list.push_str(if shown == 0 { "…" } else { ", …" });
        }
        let line = if list.is_empty() {
            format!("{file} · {method}")
        } else {
            format!("{file} · {list} · {method}")
        };
        if style::text_width(&line, style::SUBTITLE) <= room || shown == 0 {
            return line;
        }
    }
    format!("{file} · {method}")
}

type Area<'a> = DrawingArea<SVGBackend<'a>, plotters::coord::Shift>;

/// A panel's axes over `x` × `y`, with room for its caption and labels.
type Panel<'a, 'b> = ChartContext<
    'a,
    SVGBackend<'b>,
    Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>,
>;

fn panel<'a, 'b>(
    area: &'a Area<'b>,
    x: std::ops::Range<f64>,
    y: std::ops::Range<f64>,
) -> Result<Panel<'a, 'b>, PlotError> {
    ChartBuilder::on(area)
        .margin(MARGIN)
        .margin_top(CAPTION_ROOM)
        .x_label_area_size(X_LABELS)
        .y_label_area_size(Y_LABELS)
        .build_cartesian_2d(x, y)
        .map_err(PlotError::drawing)
}

/// One coordinate: its column, its name, and what it measures.
struct Coordinate<'r> {
    column: usize,
    name: &'r str,
    quantity: Option<Quantity>,
}

impl Coordinate<'_> {
    fn unit(&self) -> Option<String> {
        self.quantity.and_then(|q| q.unit())
    }
}

/// The run's values, as the figure draws them.
struct Data<'r> {
    t: Vec<f64>,
    rows: &'r [Vec<f64>],
}

impl Data<'_> {
    fn column(&self, k: usize) -> Vec<f64> {
        self.rows.iter().map(|r| r[k]).collect()
    }

    fn t_range(&self) -> (f64, f64) {
        let t0 = self.t.first().copied().unwrap_or(0.0);
        let t1 = self.t.last().copied().unwrap_or(1.0);
        (t0, t1.max(t0 + 1e-12))
    }
}

/// The smallest and largest finite values, padded by 5%.
fn range<'a>(values: impl Iterator<Item = &'a f64>) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in values.filter(|x| x.is_finite()) {
        lo = lo.min(*v);
        hi = hi.max(*v);
    }
    if !lo.is_finite() {
        return (-1.0, 1.0);
    }
    let pad = ((hi - lo) * 0.05).max(1e-12 * (1.0 + hi.abs()));
    (lo - pad, hi + pad)
}

/// The coordinates grouped by unit, in the order of their first member.
fn by_unit<'c, 'r>(coordinates: &'c [Coordinate<'r>]) -> Vec<Vec<&'c Coordinate<'r>>> {
    let mut groups: Vec<Vec<&Coordinate>> = Vec::new();
    for c in coordinates {
        match groups.iter_mut().find(|g| g[0].unit() == c.unit()) {
            Some(g) => g.push(c),
            None => groups.push(vec![c]),
        }
    }
    groups
}

/// The figure of a run, as SVG text: [`Run::plot_rows`] when the run
/// sampled them, else its rows.
pub fn svg(run: &Run, labels: &Labels) -> Result<String, PlotError> {
    let rows = if run.plot_rows.is_empty() {
        &run.rows
    } else {
        &run.plot_rows
    };
    let data = Data {
        t: rows.iter().map(|r| r[0]).collect(),
        rows,
    };
    // the coordinates come first, then their velocities (named `q'`)
    let n = run.columns[1..]
        .iter()
        .take_while(|c| !c.ends_with('\''))
        .count();
    let coordinates: Vec<Coordinate> = (0..n)
        .map(|k| Coordinate {
            column: 1 + k,
            name: &run.columns[1 + k],
            quantity: labels.quantity(&run.columns[1 + k]).copied(),
        })
        .collect();
    let energy = run.columns.iter().position(|c| c == "energy");
    let groups = by_unit(&coordinates);
    let panel = if groups.len() > 1 {
        TIME_PANELS
    } else {
        TIME_PANEL
    };
    let cells = n + usize::from(energy.is_some());
    let per_row = cells.clamp(1, CELLS_PER_ROW);
    let grid_rows = cells.div_ceil(per_row) as u32;
    let height = HEAD + panel * groups.len() as u32 + CELL * grid_rows;
    let mut out = String::new();
    {
        let root = SVGBackend::with_string(&mut out, (WIDTH, height)).into_drawing_area();
        root.fill(&WHITE).map_err(PlotError::drawing)?;
        let (head, body) = root.split_vertically(HEAD);
        draw_head(&head, labels)?;
        let (top, bottom) = body.split_vertically(panel * groups.len() as u32);
        if !groups.is_empty() {
            for (group, area) in groups.iter().zip(top.split_evenly((groups.len(), 1))) {
                time_panel(&area, &data, group, labels)?;
            }
        }
        if cells > 0 {
            let grid = bottom.split_evenly((grid_rows as usize, per_row));
            for (k, c) in coordinates.iter().enumerate() {
                phase_panel(&grid[k], &data, c, k, n)?;
            }
            if let Some(e) = energy {
                energy_panel(&grid[n], &data, e, labels)?;
            }
        }
        root.present().map_err(PlotError::drawing)?;
    }
    Ok(out)
}

/// The title and, beneath it, the subtitle, from the left margin.
fn draw_head(area: &Area, labels: &Labels) -> Result<(), PlotError> {
    let x = 2 * MARGIN as i32;
    area.draw(&Text::new(
        labels.title.clone(),
        (x, 32),
        style::font_left(style::TITLE),
    ))
    .map_err(PlotError::drawing)?;
    area.draw(&Text::new(
        labels.subtitle.clone(),
        (x, 70),
        style::font_left(style::SUBTITLE).color(&style::MUTED),
    ))
    .map_err(PlotError::drawing)
}

/// Coordinates of one unit against t, with their legend at the right.
fn time_panel(
    area: &Area,
    data: &Data,
    group: &[&Coordinate],
    labels: &Labels,
) -> Result<(), PlotError> {
    let names: Vec<String> = group.iter().map(|c| pretty_column(c.name)).collect();
    let legend_width = names
        .iter()
        .map(|n| style::text_width(n, style::LEGEND))
        .max()
        .unwrap_or(0)
        + SAMPLE_LINE
        + 3 * MARGIN;
    let (plot, legend_area) = area.split_horizontally(WIDTH - legend_width);
    let values: Vec<Vec<f64>> = group.iter().map(|c| data.column(c.column)).collect();
    let (lo, hi) = range(values.iter().flatten());
    let (t0, t1) = data.t_range();
    let quantity = group[0].quantity;
    let caption_text = match (&names[..], quantity.and_then(|q| q.plural())) {
        ([one], _) => format!("{one} against time"),
        (_, Some(kind)) => format!("{kind} against time"),
        (_, None) => "coordinates against time".to_string(),
    };
    let y_name = match &names[..] {
        [a] => a.clone(),
        [a, b] => format!("{a}, {b}"),
        [a, b, c] => format!("{a}, {b}, {c}"),
        [a, .., z] => format!("{a} … {z}"),
        [] => "q".into(),
    };
    let mut chart = panel(&plot, t0..t1, lo..hi)?;
    style::mesh(&mut chart.configure_mesh())
        .x_labels(10)
        .y_labels(7)
        .x_desc(labels.time())
        .y_desc(Labels::axis(&y_name, group[0].unit()))
        .x_label_formatter(&|v| tick_label(*v, t1 - t0))
        .y_label_formatter(&|v| tick_label(*v, hi - lo))
        .draw()
        .map_err(PlotError::drawing)?;
    caption(
        &plot,
        chart.plotting_area().get_pixel_range(),
        &caption_text,
    )?;
    for (c, v) in group.iter().zip(&values) {
        let k = c.column - 1;
        chart
            .draw_series(LineSeries::new(
                data.t.iter().copied().zip(v.iter().copied()),
                colour(k).stroke_width(style::LINE),
            ))
            .map_err(PlotError::drawing)?;
    }
    let entries: Vec<(String, RGBColor)> = group
        .iter()
        .zip(names)
        .map(|(c, name)| (name, colour(c.column - 1)))
        .collect();
    // the legend's first entry level with the plotting area's top
    let top = chart.plotting_area().get_pixel_range().1.start - area.get_base_pixel().1;
    legend(&legend_area, &entries, top + style::LEGEND as i32 / 2)
}

/// A panel's caption, centred over its plotting area (`pixels`, the
/// figure's pixels it covers): plotters would centre it over the whole
/// panel, tick labels included.
fn caption(
    area: &Area,
    pixels: (std::ops::Range<i32>, std::ops::Range<i32>),
    text: &str,
) -> Result<(), PlotError> {
    let (base_x, base_y) = area.get_base_pixel();
    let x = (pixels.0.start + pixels.0.end) / 2 - base_x;
    let y = pixels.1.start - base_y - CAPTION_ROOM as i32 / 2;
    area.draw(&Text::new(
        text.to_string(),
        (x, y),
        style::font(style::CAPTION).pos(Pos::new(HPos::Center, VPos::Center)),
    ))
    .map_err(PlotError::drawing)
}

/// Each curve's sample line and name, one under another.
fn legend(area: &Area, entries: &[(String, RGBColor)], top: i32) -> Result<(), PlotError> {
    let step = (style::LEGEND * 1.7) as i32;
    let x = MARGIN as i32;
    for (i, (name, c)) in entries.iter().enumerate() {
        let y = top + i as i32 * step;
        area.draw(&PathElement::new(
            vec![(x, y), (x + SAMPLE_LINE as i32, y)],
            c.stroke_width(style::LINE + 1),
        ))
        .map_err(PlotError::drawing)?;
        area.draw(&Text::new(
            name.clone(),
            (x + SAMPLE_LINE as i32 + 10, y),
            style::font_left(style::LEGEND),
        ))
        .map_err(PlotError::drawing)?;
    }
    Ok(())
}

/// One coordinate's phase portrait, q̇ against q, in its colour.
fn phase_panel(
    area: &Area,
    data: &Data,
    c: &Coordinate,
    k: usize,
    n: usize,
) -> Result<(), PlotError> {
    let q = data.column(c.column);
    let qd = data.column(c.column + n);
    let (xlo, xhi) = range(q.iter());
    let (ylo, yhi) = range(qd.iter());
    let name = pretty_column(c.name);
    let mut chart = panel(area, xlo..xhi, ylo..yhi)?;
    style::mesh(&mut chart.configure_mesh())
        .x_labels(6)
        .y_labels(7)
        .x_desc(Labels::axis(&name, c.unit()))
        .y_desc(Labels::axis(
            &pretty_column(&format!("{}'", c.name)),
            c.quantity.and_then(|q| q.rate_unit()),
        ))
        .x_label_formatter(&|v| tick_label(*v, xhi - xlo))
        .y_label_formatter(&|v| tick_label(*v, yhi - ylo))
        .draw()
        .map_err(PlotError::drawing)?;
    let pixels = chart.plotting_area().get_pixel_range();
    caption(area, pixels, &format!("phase portrait of {name}"))?;
    chart
        .draw_series(LineSeries::new(
            q.into_iter().zip(qd),
            colour(k).stroke_width(style::LINE),
        ))
        .map_err(PlotError::drawing)?;
    Ok(())
}

/// The energy error h(t) − h(0) against t.
fn energy_panel(area: &Area, data: &Data, column: usize, labels: &Labels) -> Result<(), PlotError> {
    let h = data.column(column);
    let h0 = h.first().copied().unwrap_or(0.0);
    let dh: Vec<f64> = h.iter().map(|x| x - h0).collect();
    let (lo, hi) = range(dh.iter());
    let (t0, t1) = data.t_range();
    let mut chart = panel(area, t0..t1, lo..hi)?;
    style::mesh(&mut chart.configure_mesh())
        .x_labels(6)
        .y_labels(7)
        .x_desc(labels.time())
        .y_desc(Labels::axis(
            "h(t) − h(0)",
            labels.dimensions.then(|| "J".to_string()),
        ))
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
    caption(
        area,
        chart.plotting_area().get_pixel_range(),
        "energy error",
    )?;
    chart
        .draw_series(LineSeries::new(
            data.t.iter().copied().zip(dh),
            style::TEXT.stroke_width(style::LINE),
        ))
        .map_err(PlotError::drawing)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::{scene_title, short, tick_label};

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

    #[test]
    fn a_scene_is_named_by_its_first_comments_first_phrase() {
        assert_eq!(
            scene_title(
                "# Seed problem 24.1 — one degree of freedom, damped.\n# More.\ncoordinates x\n"
            )
            .as_deref(),
            Some("Seed problem 24.1")
        );
        assert_eq!(
            scene_title("# The double pendulum: two point masses on massless rods, angles from the\n# downward vertical.\n").as_deref(),
            Some("The double pendulum")
        );
        // a phrase over two lines is joined
        assert_eq!(
            scene_title("# A uniform disk rolling inside a\n# fixed cylinder. It rolls.\n")
                .as_deref(),
            Some("A uniform disk rolling inside a fixed cylinder")
        );
        // a blank comment line ends the first comment
        assert_eq!(
            scene_title("# Two masses\n#\n# and springs.\n").as_deref(),
            Some("Two masses")
        );
        assert_eq!(scene_title("coordinates x\n# late comment\n"), None);
        assert_eq!(scene_title("#\ncoordinates x\n"), None);
        let long = format!("# {}\n", "word ".repeat(30));
        let t = scene_title(&long).unwrap();
        assert!(t.ends_with(" …") && t.chars().count() <= 74, "{t}");
        assert_eq!(short(9.81), "9.81");
        assert_eq!(short(1e-9), "1e-9");
        assert_eq!(short(0.0), "0");
        assert_eq!(short(2.5e6), "2.5e6");
    }
}
