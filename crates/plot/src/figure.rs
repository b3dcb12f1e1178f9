//! A figure: a title over vertically stacked panels, written as PNG and SVG.

use std::fs;
use std::path::{Path, PathBuf};

use plotters::coord::Shift;
use plotters::drawing::{DrawingArea, DrawingAreaErrorKind, IntoDrawingArea};
use plotters::prelude::{BitMapBackend, DrawingBackend, SVGBackend};
use plotters::style::text_anchor::{HPos, Pos, VPos};
use plotters::style::{Color, WHITE};
use serde::Serialize;

use super::axis::{self, Extent};
use super::bars::BarChart;
use super::bars::{self, PreparedBars};
use super::error::ReportError;
use super::panel::Panel;
use super::style::{self, FIGURE_TITLE_SIZE, INK};
use super::xy::{self, MARGIN_LEFT, MARGIN_RIGHT, PreparedXy};

/// Default width in pixels: legible when scaled to a page or a browser column.
const DEFAULT_WIDTH: u32 = 1100;
/// Natural height of one x–y panel when the figure size is not set.
const XY_HEIGHT: u32 = 270;
/// Height of a figure's only x–y panel: a lone plot gets more room.
const SINGLE_XY_HEIGHT: u32 = 400;
/// Height of the figure title strip (one line of title).
const TITLE_HEIGHT: u32 = 48;
/// Height each further line of a wrapped title adds.
const TITLE_LINE: u32 = 32;
/// Width of the phone rendering ([`FigureFiles::narrow_png`]): drawn with the
/// same text sizes, so that scaled to a 390-px screen (≈ 370 px of figure)
/// its text is about three quarters of its size instead of a third.
pub const NARROW_WIDTH: u32 = 500;

/// Anything a [`Figure`] can stack: an x–y [`Panel`] or a [`BarChart`].
/// Build it with `.into()` or pass either type to [`Figure::panel`].
///
/// ```
/// use plot::{BarChart, Chart, Panel};
/// let a: Chart = Panel::new("p", "t (s)", "y (g)").into();
/// let b: Chart = BarChart::new("b", "rms (mV)", ["X"]).into();
/// assert!(matches!(a, Chart::Xy(_)) && matches!(b, Chart::Bars(_)));
/// ```
#[derive(Clone, Debug, PartialEq, Serialize)]
pub enum Chart {
    /// An x–y panel.
    Xy(Panel),
    /// A horizontal bar chart.
    Bars(BarChart),
}

impl From<Panel> for Chart {
    fn from(p: Panel) -> Self {
        Chart::Xy(p)
    }
}

impl From<BarChart> for Chart {
    fn from(b: BarChart) -> Self {
        Chart::Bars(b)
    }
}

/// What [`Figure::save`] wrote, and what it had to leave out.
///
/// `warnings` lists data that could not be drawn (NaN values, values ≤ 0 on
/// a log axis), one line per series; show them next to the figure
/// ([`Section::figure`](super::Section::figure) does) so that a gap in a line
/// is never mistaken for a property of the data.
///
/// ```
/// use plot::{Figure, Panel, Series};
///
/// let f = vec![0.0, 0.5, 1.0, 1.5];
/// let psd = vec![1e-3, 5e-4, 2e-4, 1e-4];
/// let files = Figure::new("PSD")
///     .panel(Panel::psd("s0", "PSD (V²/Hz)").series(Series::line("s0", f, psd)))
///     .save(std::env::temp_dir().join("plot-doc"), "psd_k0")?;
/// // The 0 Hz bin has no place on a log axis, and the files say so.
/// assert_eq!(files.warnings.len(), 1);
/// assert!(files.warnings[0].contains("value ≤ 0 on a log axis"));
/// # Ok::<(), plot::ReportError>(())
/// ```
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct FigureFiles {
    /// The PNG file.
    pub png: PathBuf,
    /// The SVG file.
    pub svg: PathBuf,
    /// The same figure laid out for a phone ([`NARROW_WIDTH`] px wide, the
    /// same text sizes, legends and titles wrapped): `stem.narrow.png`.
    /// `None` for a figure given its own [`Figure::size`].
    pub narrow_png: Option<PathBuf>,
    /// Data left out of the drawing, in words.
    pub warnings: Vec<String>,
}

/// A titled figure of panels stacked top to bottom, saved as PNG and SVG.
///
/// Both files come from one drawing function, generic over the plotters
/// backend, so they always show the same thing. Without [`Figure::size`] the
/// figure is 1100 px wide and each x–y panel 270 px high (400 px if it is
/// the only one; bar charts as high as their number of bars needs).
///
/// ```
/// use plot::{Figure, Panel, Series};
///
/// // Fig. 7: the six signals with and without compensation.
/// let t: Vec<f64> = (0..5000).map(|i| i as f64 * 0.02).collect();
/// let mut fig = Figure::new("Fig. 7 — signals with and without compensation").share_x();
/// for k in 0..6 {
///     let before: Vec<f64> = t.iter().map(|t| 0.3 * (5.0 * t + k as f64).sin()).collect();
///     let after: Vec<f64> = before.iter().map(|v| 0.1 * v).collect();
///     fig = fig.panel(
///         Panel::new(format!("s{k}"), "time (s)", format!("s{k} (mV)"))
///             .series(Series::line("without compensation", t.clone(), before).colour(1))
///             .series(Series::line("with compensation", t.clone(), after).colour(0)),
///     );
/// }
/// let files = fig.save(std::env::temp_dir().join("plot-doc"), "fig7_signals")?;
/// assert!(files.png.ends_with("fig7_signals.png"));
/// assert!(files.svg.ends_with("fig7_signals.svg"));
/// # Ok::<(), plot::ReportError>(())
/// ```
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Figure {
    title: String,
    charts: Vec<Chart>,
    size: Option<(u32, u32)>,
    share_x: bool,
}

impl Figure {
    /// An empty figure with a title.
    ///
    /// ```
    /// use plot::Figure;
    /// assert_eq!(Figure::new("Fig. 5").panel_count(), 0);
    /// ```
    pub fn new(title: impl Into<String>) -> Self {
        Figure {
            title: title.into(),
            charts: Vec::new(),
            size: None,
            share_x: false,
        }
    }

    /// Appends a panel or bar chart below the previous ones.
    ///
    /// ```
    /// use plot::{BarChart, Figure, Panel};
    /// let f = Figure::new("f")
    ///     .panel(Panel::new("p", "t (s)", "y (g)"))
    ///     .panel(BarChart::new("b", "rms (mV)", ["X"]));
    /// assert_eq!(f.panel_count(), 2);
    /// ```
    pub fn panel(mut self, chart: impl Into<Chart>) -> Self {
        self.charts.push(chart.into());
        self
    }

    /// Gives all x–y panels the same x range (the union of their data), so
    /// that stacked time series line up sample for sample. Panels with a log x
    /// axis share among themselves, linear ones among themselves.
    ///
    /// ```
    /// use plot::Figure;
    /// let f = Figure::new("f").share_x();
    /// # let _ = f;
    /// ```
    pub fn share_x(mut self) -> Self {
        self.share_x = true;
        self
    }

    /// Sets the size in pixels (default: 1100 wide, height from the panels).
    ///
    /// # Panics
    /// If a side is outside 200..=8000 px: that is a bug, and a huge value
    /// would try to allocate gigabytes for the bitmap.
    ///
    /// ```
    /// use plot::Figure;
    /// assert_eq!(Figure::new("f").size(800, 600).pixel_size(), (800, 600));
    /// ```
    #[track_caller]
    pub fn size(mut self, width: u32, height: u32) -> Self {
        assert!(
            (200..=8000).contains(&width) && (200..=8000).contains(&height),
            "figure size {width}×{height} px is outside 200..=8000 px per side"
        );
        self.size = Some((width, height));
        self
    }

    /// The size the figure will be drawn at.
    ///
    /// ```
    /// use plot::{Figure, Panel};
    /// let f = Figure::new("f").panel(Panel::new("a", "t (s)", "y (g)")).panel(Panel::new("b", "t (s)", "y (g)"));
    /// assert_eq!(f.pixel_size(), (1100, 48 + 2 * 270));
    /// ```
    pub fn pixel_size(&self) -> (u32, u32) {
        self.size
            .unwrap_or_else(|| self.natural_size(DEFAULT_WIDTH))
    }

    /// The size at `width` when no size is set: the title (wrapped to the
    /// width) over the panels' natural heights.
    fn natural_size(&self, width: u32) -> (u32, u32) {
        let panels: u32 = match self.charts.as_slice() {
            [Chart::Xy(_)] => SINGLE_XY_HEIGHT,
            charts => charts.iter().map(natural_height).sum(),
        };
        let title = title_height(wrap_title(&self.title, width).len());
        (width, (title + panels).clamp(200, 8000))
    }

    /// Number of panels and bar charts.
    ///
    /// ```
    /// # use plot::Figure;
    /// assert_eq!(Figure::new("f").panel_count(), 0);
    /// ```
    pub fn panel_count(&self) -> usize {
        self.charts.len()
    }

    /// Writes `dir/stem.png` and `dir/stem.svg`, creating `dir` if needed.
    ///
    /// `stem` is a plain file name without extension; one with a path
    /// separator or a leading dot is refused ([`ReportError::InvalidStem`]),
    /// since stems are often made from data such as sensor names.
    ///
    /// ```
    /// use plot::{Figure, Panel, Series};
    ///
    /// let lags: Vec<f64> = (0..=20).map(f64::from).collect();
    /// let r: Vec<f64> = lags.iter().map(|&k| 0.8_f64.powf(k)).collect();
    /// let fig = Figure::new("Whiteness test")
    ///     .panel(Panel::correlation("Autocorrelation of the X residual", "lag (samples)", lags, r, 0.028));
    /// let files = fig.save(std::env::temp_dir().join("plot-doc"), "whiteness_x")?;
    /// assert!(std::fs::metadata(&files.png)?.len() > 1000);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn save(&self, dir: impl AsRef<Path>, stem: &str) -> Result<FigureFiles, ReportError> {
        validate_stem(stem)?;
        let dir = dir.as_ref();
        fs::create_dir_all(dir).map_err(|source| ReportError::Io {
            path: dir.to_path_buf(),
            source,
        })?;
        style::ensure_font()?;

        let mut warnings = Vec::new();
        let prepared = self.prepare(self.pixel_size(), &mut warnings);

        let png = dir.join(format!("{stem}.png"));
        write_png(&prepared, dir, stem, &png)?;
        let narrow_png = match self.size {
            Some(_) => None,
            None => {
                let narrow = self.prepare(self.natural_size(NARROW_WIDTH), &mut Vec::new());
                let path = dir.join(format!("{stem}.narrow.png"));
                write_png(&narrow, dir, &format!("{stem}.narrow"), &path)?;
                Some(path)
            }
        };

        let svg = dir.join(format!("{stem}.svg"));
        let mut text = String::new();
        {
            let root = SVGBackend::with_string(&mut text, prepared.size).into_drawing_area();
            prepared
                .draw(&root)
                .and_then(|()| root.present())
                .map_err(|e| ReportError::Draw {
                    path: svg.clone(),
                    message: e.to_string(),
                })?;
        }
        outfile::write_bytes(&svg, text).map_err(|source| ReportError::Io {
            path: svg.clone(),
            source,
        })?;
        Ok(FigureFiles {
            png,
            svg,
            narrow_png,
            warnings,
        })
    }

    /// Everything that does not depend on the backend: cleaned data, ranges,
    /// ticks, legend layout, decimated points.
    fn prepare(&self, (width, height): (u32, u32), warnings: &mut Vec<String>) -> Prepared {
        let title = wrap_title(&self.title, width);
        let title_h = title_height(title.len());
        let heights = split_heights(
            &self.charts.iter().map(natural_height).collect::<Vec<_>>(),
            height.saturating_sub(title_h),
        );

        // Data pass.
        let collected: Vec<Option<xy::Collected>> = self
            .charts
            .iter()
            .map(|c| match c {
                Chart::Xy(p) => Some(xy::collect(p, warnings)),
                Chart::Bars(_) => None,
            })
            .collect();

        // Shared x ranges, one per kind of x axis.
        let xys = || collected.iter().flatten();
        let mut shared = [Extent::default(), Extent::default()];
        for c in xys() {
            shared[c.log_x() as usize].merge(c.x_extent);
        }
        let x_pad = |c: &xy::Collected| {
            let lines_only = if self.share_x {
                xys().all(xy::Collected::lines_only)
            } else {
                c.lines_only()
            };
            if lines_only { 0.0 } else { 0.03 }
        };

        // y layout first: it fixes the label width shared by all x–y panels,
        // so their plot areas (and shared x axes) line up.
        let y_layouts: Vec<Option<_>> = collected
            .iter()
            .zip(&heights)
            .map(|(c, &h)| c.as_ref().map(|c| xy::layout_y(c, width, h, 0.05)))
            .collect();
        // Capped, so that one absurd label cannot squeeze every plot away.
        let y_label_area = y_layouts
            .iter()
            .flatten()
            .map(|(_, _, w)| *w)
            .max()
            .unwrap_or(60)
            .min(width / 4);
        let plot_width = width
            .saturating_sub(y_label_area + MARGIN_LEFT + MARGIN_RIGHT)
            .max(20);

        let parts = self
            .charts
            .iter()
            .zip(collected.iter().zip(y_layouts))
            .zip(&heights)
            .map(|((chart, (c, y_layout)), &h)| match (chart, c, y_layout) {
                (Chart::Xy(_), Some(c), Some((header, y, _))) => {
                    let extent = if self.share_x {
                        shared[c.log_x() as usize]
                    } else {
                        c.x_extent
                    };
                    let x_range = axis::padded(extent, x_pad(c), c.log_x());
                    (
                        Part::Xy(xy::finish(c, header, y, x_range, plot_width, h)),
                        h,
                    )
                }
                (Chart::Bars(b), _, _) => (Part::Bars(bars::prepare(b, width, warnings)), h),
                _ => unreachable!("x–y charts are collected, bar charts are not"),
            })
            .collect();
        Prepared {
            size: (width, height),
            title,
            title_height: title_h,
            parts,
            y_label_area,
        }
    }
}

/// Writes a prepared figure as a PNG at `png`: drawn under a temporary name
/// and renamed, so an interrupted run leaves no half-drawn figure.
fn write_png(prepared: &Prepared, dir: &Path, stem: &str, png: &Path) -> Result<(), ReportError> {
    // plotters writes the PNG itself and reports a failure as text; opening
    // the file first gives a typed I/O error with the path. (The image
    // encoder picks the format from the extension, so it stays .png.)
    let png_part = dir.join(format!(".{stem}.part.png"));
    fs::File::create(&png_part).map_err(|source| ReportError::Io {
        path: png.to_path_buf(),
        source,
    })?;
    {
        let root = BitMapBackend::new(&png_part, prepared.size).into_drawing_area();
        prepared
            .draw(&root)
            .and_then(|()| root.present())
            .map_err(|e| {
                let _ = fs::remove_file(&png_part);
                ReportError::Draw {
                    path: png.to_path_buf(),
                    message: e.to_string(),
                }
            })?;
    }
    fs::rename(&png_part, png).map_err(|source| ReportError::Io {
        path: png.to_path_buf(),
        source,
    })
}

/// The title's lines: words wrapped so that each line fits `width` less a
/// margin either side (a phone-width figure would cut a long title off).
fn wrap_title(title: &str, width: u32) -> Vec<String> {
    let room = width.saturating_sub(40).max(100);
    let mut lines: Vec<String> = Vec::new();
    for word in title.split_whitespace() {
        match lines.last_mut() {
            Some(line)
                if style::text_size(&format!("{line} {word}"), FIGURE_TITLE_SIZE).0 <= room =>
            {
                line.push(' ');
                line.push_str(word);
            }
            _ => lines.push(word.to_string()),
        }
    }
    if lines.is_empty() {
        lines.push(String::new());
    }
    lines
}

/// Height of a title of `lines` lines.
fn title_height(lines: usize) -> u32 {
    TITLE_HEIGHT + lines.saturating_sub(1) as u32 * TITLE_LINE
}

fn natural_height(c: &Chart) -> u32 {
    match c {
        Chart::Xy(_) => XY_HEIGHT,
        Chart::Bars(b) => b.natural_height(),
    }
}

/// Splits `total` pixels in proportion to `natural`, the last part taking the
/// rounding remainder so that the panels fill the figure exactly.
fn split_heights(natural: &[u32], total: u32) -> Vec<u32> {
    let sum: u64 = natural.iter().map(|&h| u64::from(h)).sum();
    if sum == 0 {
        return Vec::new();
    }
    let mut out: Vec<u32> = natural
        .iter()
        .map(|&h| (u64::from(h) * u64::from(total) / sum) as u32)
        .collect();
    let used: u32 = out.iter().sum();
    if let Some(last) = out.last_mut() {
        *last += total - used;
    }
    out
}

fn validate_stem(stem: &str) -> Result<(), ReportError> {
    let bad = stem.is_empty()
        || stem.starts_with('.')
        || stem
            .chars()
            .any(|c| c == '/' || c == '\\' || c.is_control());
    if bad {
        Err(ReportError::InvalidStem {
            stem: stem.to_string(),
        })
    } else {
        Ok(())
    }
}

enum Part {
    Xy(PreparedXy),
    Bars(PreparedBars),
}

struct Prepared {
    size: (u32, u32),
    /// The title's lines, wrapped to the width.
    title: Vec<String>,
    title_height: u32,
    parts: Vec<(Part, u32)>,
    y_label_area: u32,
}

impl Prepared {
    /// The single drawing routine behind both files.
    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
    ) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
        root.fill(&WHITE)?;
        let (title_area, mut rest) = root.split_vertically(self.title_height);
        for (k, line) in self.title.iter().enumerate() {
            title_area.draw_text(
                line,
                &style::text(FIGURE_TITLE_SIZE, INK).pos(Pos::new(HPos::Center, VPos::Center)),
                (
                    self.size.0 as i32 / 2,
                    (TITLE_HEIGHT / 2 + k as u32 * TITLE_LINE) as i32,
                ),
            )?;
        }
        for (i, (part, h)) in self.parts.iter().enumerate() {
            let (area, below) = rest.split_vertically(*h);
            rest = below;
            match part {
                Part::Xy(p) => xy::draw(p, &area, self.y_label_area)?,
                Part::Bars(b) => bars::draw(b, &area)?,
            }
            // A hairline between panels makes the stack easy to scan.
            if i + 1 < self.parts.len() {
                let (w, h) = area.dim_in_pixel();
                area.draw(&plotters::element::PathElement::new(
                    vec![(20, h as i32 - 1), (w as i32 - 20, h as i32 - 1)],
                    style::GRID_LIGHT.stroke_width(1),
                ))?;
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn heights_fill_the_figure() {
        assert_eq!(split_heights(&[270, 270, 270], 1000), vec![333, 333, 334]);
        assert!(split_heights(&[], 1000).is_empty());
    }

    #[test]
    fn stems_with_separators_are_refused() {
        for bad in ["", ".hidden", "a/b", "a\\b", "x\ny"] {
            assert!(validate_stem(bad).is_err(), "{bad:?}");
        }
        assert!(validate_stem("fig7_signals s0").is_ok());
    }
}
