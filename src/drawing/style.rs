//! The one look of qdot's figures (`simulate`, `cycle`, `response` and
//! `floquet --plot`): the curves' colours, the fonts' sizes and the grid.
//! Sizes are for a figure about 1,200 pixels wide shown on a slide.

use plotters::chart::MeshStyle;
use plotters::coord::ranged1d::Ranged;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// The curves' colours: Okabe and Ito's palette (told apart with every
/// common colour-vision deficiency), its yellow left out (too pale on
/// white). Curve k takes `PALETTE[k % 7]`.
pub const PALETTE: [RGBColor; 7] = [
    RGBColor(0, 114, 178),   // blue
    RGBColor(213, 94, 0),    // vermillion
    RGBColor(0, 158, 115),   // bluish green
    RGBColor(204, 121, 167), // reddish purple
    RGBColor(230, 159, 0),   // orange
    RGBColor(86, 180, 233),  // sky blue
    RGBColor(0, 0, 0),       // black
];

/// The colour of curve `k`.
pub fn colour(k: usize) -> RGBColor {
    PALETTE[k % PALETTE.len()]
}

/// A figure's title, in pixels (the sizes of its text follow).
pub const TITLE: f64 = 30.0;
/// The subtitle under the title.
pub const SUBTITLE: f64 = 17.0;
/// A panel's caption.
pub const CAPTION: f64 = 21.0;
/// An axis's name.
pub const AXIS: f64 = 19.0;
/// The tick labels.
pub const TICKS: f64 = 16.0;
/// A legend's entries.
pub const LEGEND: f64 = 18.0;

/// A curve's line width in pixels.
pub const LINE: u32 = 2;

/// The grid: light grey lines at the labelled ticks only.
pub const GRID: RGBColor = RGBColor(225, 225, 225);
/// The axes and their ticks.
pub const AXES: RGBColor = RGBColor(80, 80, 80);
/// Text other than a curve's name.
pub const TEXT: RGBColor = RGBColor(30, 30, 30);
/// A secondary text (a subtitle).
pub const MUTED: RGBColor = RGBColor(90, 90, 90);

/// plotters' SVG backend writes a font of size s as `font-size` s/1.24:
/// the size to ask for so the SVG says `px`.
fn asked(px: f64) -> f64 {
    px * 1.24
}

/// The sans-serif font of `px` pixels, in the text colour.
pub fn font(px: f64) -> TextStyle<'static> {
    ("sans-serif", asked(px)).into_font().color(&TEXT)
}

/// The font of `px` pixels, anchored at its left end and vertical centre
/// (a legend's entry, a title drawn at a point).
pub fn font_left(px: f64) -> TextStyle<'static> {
    font(px).pos(Pos::new(HPos::Left, VPos::Center))
}

/// About how wide `text` is in a font of `px` pixels (plotters cannot
/// measure text for SVG; the viewer's font decides): half an em a
/// character, which errs wide for sans-serif text.
pub fn text_width(text: &str, px: f64) -> u32 {
    (text.chars().count() as f64 * 0.55 * px).ceil() as u32
}

/// The mesh of every figure: the axes, a light grid at the labelled ticks
/// (no minor lines between them), and the fonts of the tick labels and
/// the axes' names. The caller adds the names and label formatters.
pub fn mesh<'m, 'a, 'b, X, Y, DB>(
    m: &'m mut MeshStyle<'a, 'b, X, Y, DB>,
) -> &'m mut MeshStyle<'a, 'b, X, Y, DB>
where
    X: Ranged,
    Y: Ranged,
    DB: DrawingBackend,
{
    m.bold_line_style(GRID.stroke_width(1))
        .light_line_style(TRANSPARENT)
        .max_light_lines(0)
        .axis_style(AXES.stroke_width(1))
        .label_style(font(TICKS))
        .axis_desc_style(font(AXIS))
}

/// A tick of a logarithmic axis as people write numbers: `10`, `100`,
/// `0.01`, `2.5`; a power of ten beyond 10⁵ or below 10⁻³ as `1e-5`,
/// `2.5e6` (never `1.0e1`).
pub fn log_label(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    let trim = |s: String| {
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        }
    };
    if (1e-3..1e5).contains(&v.abs()) {
        // three significant digits
        let decimals = (2 - v.abs().log10().floor() as i32).max(0) as usize;
        return trim(format!("{v:.decimals$}"));
    }
    let s = format!("{v:.2e}");
    match s.split_once('e') {
        Some((mantissa, exponent)) => format!("{}e{exponent}", trim(mantissa.to_string())),
        None => s,
    }
}

#[cfg(test)]
mod tests {
    use super::log_label;

    /// Decades as people write them, on either side of 1, and beyond.
    #[test]
    fn log_ticks_read_as_numbers() {
        let got: Vec<String> = [
            10.0, 100.0, 1.0, 0.1, 0.01, 0.001, 2.5, 1e5, 1e-5, 2.5e6, 12345.0,
        ]
        .iter()
        .map(|&v| log_label(v))
        .collect();
        assert_eq!(
            got,
            ["10", "100", "1", "0.1", "0.01", "0.001", "2.5", "1e5", "1e-5", "2.5e6", "12345"]
        );
    }
}
