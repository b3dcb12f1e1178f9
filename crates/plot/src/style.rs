//! Colours, font and text sizes shared by every figure.
//!
//! One place decides how figures look, so that the figures and the
//! analysis figures read as one report.

use std::sync::OnceLock;

use plotters::style::{Color, FontStyle, RGBColor, TextStyle};

use super::error::ReportError;

/// The Okabe–Ito palette, reordered so that the first colours are the ones
/// most distinguishable for all common colour-vision deficiencies and on white
/// paper (yellow, nearly invisible on white, comes last).
///
/// Series take `PALETTE[i % 8]`, where `i` is the series' position in its
/// panel unless [`Series::colour`](super::Series::colour) sets it.
///
/// ```
/// use plot::PALETTE;
/// assert_eq!(PALETTE.len(), 8);
/// assert_eq!((PALETTE[0].0, PALETTE[0].1, PALETTE[0].2), (0, 114, 178)); // blue
/// ```
pub const PALETTE: [RGBColor; 8] = [
    RGBColor(0, 114, 178),   // blue
    RGBColor(213, 94, 0),    // vermillion
    RGBColor(0, 158, 115),   // bluish green
    RGBColor(204, 121, 167), // reddish purple
    RGBColor(230, 159, 0),   // orange
    RGBColor(86, 180, 233),  // sky blue
    RGBColor(0, 0, 0),       // black
    RGBColor(240, 228, 66),  // yellow
];

/// The palette colour for an index, wrapping around after eight.
///
/// ```
/// use plot::{colour, PALETTE};
/// assert_eq!(colour(9), PALETTE[1]);
/// ```
pub fn colour(index: usize) -> RGBColor {
    PALETTE[index % PALETTE.len()]
}

/// Text, axes and frames.
pub(crate) const INK: RGBColor = RGBColor(30, 30, 30);
/// Secondary text (notes such as "no data").
pub(crate) const MUTED: RGBColor = RGBColor(110, 110, 110);
/// Reference lines (noise floor, significance threshold).
pub(crate) const REFERENCE: RGBColor = RGBColor(60, 60, 60);
/// Major grid lines.
pub(crate) const GRID: RGBColor = RGBColor(215, 215, 215);
/// Minor grid lines (log axes only).
pub(crate) const GRID_LIGHT: RGBColor = RGBColor(238, 238, 238);

/// The family name the embedded font is registered under. plotters maps
/// `FontFamily::SansSerif` to this name, and the SVG backend writes it as the
/// `font-family`, so browsers substitute their own sans-serif.
pub(crate) const FAMILY: &str = "sans-serif";

/// Text sizes in plotters units (≈ pixels per em) for a figure about 1100 px
/// wide: large enough to read when the PNG is scaled to a page width.
pub(crate) const FIGURE_TITLE_SIZE: f64 = 26.0;
pub(crate) const PANEL_TITLE_SIZE: f64 = 20.0;
pub(crate) const LABEL_SIZE: f64 = 18.0;
pub(crate) const TICK_SIZE: f64 = 16.0;
pub(crate) const LEGEND_SIZE: f64 = 16.0;

/// A text style of the embedded font in the given size and colour.
pub(crate) fn text(size: f64, colour: RGBColor) -> TextStyle<'static> {
    TextStyle {
        color: colour.to_backend_color(),
        ..TextStyle::from((FAMILY, size, FontStyle::Normal))
    }
}

// Strictly, DejaVu Sans is Bitstream Vera-licensed; its licence sits next to
// it in assets/.
static FONT_BYTES: &[u8] = include_bytes!("../assets/DejaVuSans.ttf");

/// Registers the embedded DejaVu Sans as `sans-serif`, once per process.
///
/// Without a registered font plotters (built without its `ttf` feature, which
/// would need system font libraries) fails every text call with
/// `FontUnavailable`, for PNG and SVG alike. Registering is process-global, so
/// a `OnceLock` keeps concurrent tests from racing and keeps the outcome.
pub(crate) fn ensure_font() -> Result<(), ReportError> {
    static REGISTERED: OnceLock<bool> = OnceLock::new();
    let ok = *REGISTERED.get_or_init(|| {
        plotters::style::register_font(FAMILY, FontStyle::Normal, FONT_BYTES).is_ok()
    });
    if ok { Ok(()) } else { Err(ReportError::Font) }
}

/// Width and height in pixels of `s` in the embedded font at `size`.
///
/// Layout (label areas, legend wrapping) is computed from these numbers once,
/// before drawing, so that the PNG and the SVG share one layout.
pub(crate) fn text_size(s: &str, size: f64) -> (u32, u32) {
    let font = plotters::style::FontDesc::new(
        plotters::style::FontFamily::Name(FAMILY),
        size,
        FontStyle::Normal,
    );
    // Only fails when the font is missing, which `ensure_font` rules out;
    // fall back to a generous estimate rather than fail the figure.
    font.box_size(s)
        .unwrap_or((s.chars().count() as u32 * size as u32 * 6 / 10, size as u32))
}

/// `#RRGGBB` for a colour, as plotters' SVG backend spells it (tests look
/// for series by their stroke colour).
#[cfg(test)]
pub(crate) fn hex(c: RGBColor) -> String {
    format!("#{:02X}{:02X}{:02X}", c.0, c.1, c.2)
}

/// Writes "no data" in the middle of an empty panel's plotting area.
pub(crate) fn no_data<DB: plotters::prelude::DrawingBackend>(
    plot: &plotters::drawing::DrawingArea<DB, plotters::coord::Shift>,
) -> Result<(), plotters::drawing::DrawingAreaErrorKind<DB::ErrorType>> {
    use plotters::style::text_anchor::{HPos, Pos, VPos};
    let (w, h) = plot.dim_in_pixel();
    plot.draw_text(
        "no data",
        &text(LABEL_SIZE, MUTED).pos(Pos::new(HPos::Center, VPos::Center)),
        (w as i32 / 2, h as i32 / 2),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn font_registers_and_measures() {
        ensure_font().unwrap();
        ensure_font().unwrap(); // idempotent
        let (w, h) = text_size("signal s0 (mV)", LABEL_SIZE);
        assert!(w > 100 && w < 300, "width {w}");
        assert!(h > 5 && h < 40, "height {h}");
    }

    #[test]
    fn palette_colours_are_distinct() {
        for (i, a) in PALETTE.iter().enumerate() {
            assert!(PALETTE[..i].iter().all(|b| b != a), "colour {i} repeats");
        }
        assert_eq!(hex(PALETTE[0]), "#0072B2");
    }
}
