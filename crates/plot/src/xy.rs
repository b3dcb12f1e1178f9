//! Turning a [`Panel`] into pixels: cleaning the data (NaN, log axes),
//! choosing ranges and ticks, decimating, then drawing with any plotters
//! backend.
//!
//! Preparation happens once and is backend-independent; drawing is generic
//! over `DrawingBackend`, so the PNG and the SVG of a figure come from the
//! same numbers and the same code and cannot drift apart.

use plotters::chart::{ChartBuilder, ChartContext};
use plotters::coord::Shift;
use plotters::coord::cartesian::Cartesian2d;
use plotters::drawing::{DrawingArea, DrawingAreaErrorKind};
use plotters::element::{Circle, DashedPathElement, PathElement, Rectangle};
use plotters::prelude::DrawingBackend;
use plotters::style::{Color, RGBColor};

use super::axis::{self, Axis, Extent};
use super::decimate;
use super::legend::{Entry, Header, Swatch};
use super::panel::Panel;
use super::series::SeriesStyle;
use super::style::{self, GRID, GRID_LIGHT, INK, LABEL_SIZE, REFERENCE, TICK_SIZE};

/// Height reserved under the plot for x tick labels and the x axis label.
pub(crate) const X_LABEL_AREA: u32 = 50;
/// Margins around the plotting area inside a panel.
pub(crate) const MARGIN_TOP: u32 = 6;
pub(crate) const MARGIN_RIGHT: u32 = 28;
pub(crate) const MARGIN_LEFT: u32 = 8;
/// Opacity of a band's fill.
const BAND_ALPHA: f64 = 0.15;

/// A series in plot space, split at gaps, not yet decimated.
#[derive(Clone, Debug)]
struct Cleaned {
    segments: Vec<Vec<(f64, f64)>>,
    style: SeriesStyle,
    colour: RGBColor,
    label: String,
}

/// A panel after the data pass: everything that does not depend on pixels.
#[derive(Clone, Debug)]
pub(crate) struct Collected {
    panel_title: String,
    x_label: String,
    y_label: String,
    log_x: bool,
    log_y: bool,
    series: Vec<Cleaned>,
    band: Option<(f64, String)>,
    ref_lines: Vec<(f64, String)>,
    /// Shaded x ranges in plot coordinates, with their labels.
    x_spans: Vec<(f64, f64, String)>,
    pub x_extent: Extent,
    y_extent: Extent,
    /// Only lines: the x axis can be tight (time series end at the data).
    lines_only: bool,
}

impl Collected {
    pub fn log_x(&self) -> bool {
        self.log_x
    }
    pub fn lines_only(&self) -> bool {
        self.lines_only
    }
}

/// Cleans a panel's data into plot space, recording what had to be skipped.
pub(crate) fn collect(panel: &Panel, warnings: &mut Vec<String>) -> Collected {
    let mut x_extent = Extent::default();
    let mut y_extent = Extent::default();
    let mut series = Vec::with_capacity(panel.series.len());
    for (i, s) in panel.series.iter().enumerate() {
        let mut segments = Vec::new();
        let mut current = Vec::new();
        let (mut non_finite, mut non_positive) = (0usize, 0usize);
        for (&x, &y) in s.x().iter().zip(s.y()) {
            match (axis::to_plot(x, panel.log_x), axis::to_plot(y, panel.log_y)) {
                (Some(px), Some(py)) => {
                    x_extent.add(px);
                    y_extent.add(py);
                    current.push((px, py));
                }
                _ => {
                    if x.is_finite() && y.is_finite() {
                        non_positive += 1;
                    } else {
                        non_finite += 1;
                    }
                    if !current.is_empty() {
                        segments.push(std::mem::take(&mut current));
                    }
                }
            }
        }
        if !current.is_empty() {
            segments.push(current);
        }
        let name = if s.label().is_empty() {
            format!("#{}", i + 1)
        } else {
            s.label().to_string()
        };
        if non_finite > 0 {
            warnings.push(format!(
                "panel {:?}, series {name:?}: skipped {non_finite} point(s) with NaN or infinite values",
                panel.title
            ));
        }
        if non_positive > 0 {
            warnings.push(format!(
                "panel {:?}, series {name:?}: skipped {non_positive} point(s) with a value ≤ 0 on a log axis",
                panel.title
            ));
        }
        series.push(Cleaned {
            segments,
            style: s.style(),
            colour: style::colour(s.colour_index().unwrap_or(i)),
            label: s.label().to_string(),
        });
    }

    // Reference marks count towards the y range: a band or noise floor that
    // is off-screen would say nothing.
    let band = panel.band.as_ref().map(|b| (b.limit, b.label.clone()));
    if let Some((limit, _)) = &band {
        for v in [-limit, *limit] {
            if let Some(p) = axis::to_plot(v, panel.log_y) {
                y_extent.add(p);
            }
        }
    }
    let mut ref_lines = Vec::new();
    for r in &panel.ref_lines {
        match axis::to_plot(r.y, panel.log_y) {
            Some(p) => {
                y_extent.add(p);
                ref_lines.push((p, r.label.clone()));
            }
            None => warnings.push(format!(
                "panel {:?}: reference line {:?} at {} cannot be drawn on this axis",
                panel.title, r.label, r.y
            )),
        }
    }
    let x_spans = panel
        .x_spans
        .iter()
        .filter_map(|sp| {
            let a = axis::to_plot(sp.from, panel.log_x)?;
            let b = axis::to_plot(sp.to, panel.log_x)?;
            Some((a, b, sp.label.clone()))
        })
        .collect();
    // Stems grow from zero, so zero belongs in a linear range.
    if !panel.log_y && series.iter().any(|s| s.style == SeriesStyle::Stems) {
        y_extent.add(0.0);
    }
    Collected {
        panel_title: panel.title.clone(),
        x_label: panel.x_label.clone(),
        y_label: panel.y_label.clone(),
        log_x: panel.log_x,
        log_y: panel.log_y,
        lines_only: panel.series.iter().all(|s| s.style().is_line()),
        series,
        band,
        ref_lines,
        x_spans,
        x_extent,
        y_extent,
    }
}

/// A series ready to draw.
#[derive(Clone, Debug)]
struct Drawn {
    segments: Vec<Vec<(f64, f64)>>,
    style: SeriesStyle,
    colour: RGBColor,
    stroke: u32,
}

/// A panel laid out for a pixel size.
#[derive(Clone, Debug)]
pub(crate) struct PreparedXy {
    header: Header,
    x_label: String,
    y_label: String,
    x: Axis,
    y: Axis,
    series: Vec<Drawn>,
    band: Option<(f64, f64)>,
    ref_lines: Vec<f64>,
    x_spans: Vec<(f64, f64)>,
    empty: bool,
}

/// About one labelled y tick per this many pixels: a 150-pixel panel gets
/// four or five, enough to read a value off without a ruler.
pub(crate) const Y_TICK_SPACING_PX: u32 = 24;
/// About one labelled x tick per this many pixels (labels are wider than tall).
pub(crate) const X_TICK_SPACING_PX: u32 = 80;

/// Vertical pixels the plot itself gets in a panel `height` tall with this header.
fn plot_height(height: u32, header: &Header) -> u32 {
    height
        .saturating_sub(header.height() + X_LABEL_AREA + MARGIN_TOP)
        .max(20)
}

/// First layout step: header and y axis, which do not depend on the plot
/// width. Returns them with the width the y labels need, so the figure can
/// give every stacked panel the same label width.
pub(crate) fn layout_y(c: &Collected, width: u32, height: u32, y_pad: f64) -> (Header, Axis, u32) {
    let mut entries: Vec<Entry> = c
        .series
        .iter()
        .filter(|s| !s.label.is_empty())
        .map(|s| Entry {
            swatch: match s.style {
                SeriesStyle::Line => Swatch::Line(s.colour),
                SeriesStyle::Points => Swatch::Dot(s.colour),
                SeriesStyle::Stems => Swatch::Stem(s.colour),
                SeriesStyle::Dashed => Swatch::Dashed(s.colour),
                SeriesStyle::Dotted => Swatch::Dotted(s.colour),
            },
            label: s.label.clone(),
        })
        .collect();
    let mut span_labels: Vec<&str> = Vec::new();
    for (_, _, label) in &c.x_spans {
        if !span_labels.contains(&label.as_str()) {
            span_labels.push(label);
            entries.push(Entry {
                swatch: Swatch::Fill(SPAN, SPAN_ALPHA * 2.0),
                label: label.clone(),
            });
        }
    }
    if let Some((_, label)) = &c.band {
        entries.push(Entry {
            swatch: Swatch::Fill(band_colour(), BAND_ALPHA * 2.0),
            label: label.clone(),
        });
    }
    for (_, label) in &c.ref_lines {
        entries.push(Entry {
            swatch: Swatch::Dashed(REFERENCE),
            label: label.clone(),
        });
    }
    let header = Header::layout(&c.panel_title, entries, width);
    let (lo, hi) = axis::padded(c.y_extent, y_pad, c.log_y);
    let y = Axis::new(
        lo,
        hi,
        c.log_y,
        plot_height(height, &header),
        Y_TICK_SPACING_PX,
    );
    let tick_w = y
        .ticks
        .iter()
        .map(|(_, s)| style::text_size(s, TICK_SIZE).0)
        .max()
        .unwrap_or(0);
    let desc_h = style::text_size(&c.y_label, LABEL_SIZE).1;
    // Tick label, tick mark and gaps, then the rotated axis label.
    (header, y, tick_w + desc_h + 28)
}

/// Second layout step, once the shared y-label width and x range are known.
pub(crate) fn finish(
    c: &Collected,
    header: Header,
    y: Axis,
    x_range: (f64, f64),
    plot_width: u32,
    height: u32,
) -> PreparedXy {
    let x = Axis::new(x_range.0, x_range.1, c.log_x, plot_width, X_TICK_SPACING_PX);
    let columns = plot_width.max(1) as usize;
    let rows = plot_height(height, &header) as usize;
    let series = c
        .series
        .iter()
        .map(|s| {
            let segments: Vec<Vec<(f64, f64)>> = s
                .segments
                .iter()
                .map(|seg| match s.style {
                    SeriesStyle::Line
                    | SeriesStyle::Dashed
                    | SeriesStyle::Dotted
                    | SeriesStyle::Stems => decimate::m4(seg, columns),
                    SeriesStyle::Points => {
                        decimate::thin_points(seg, (x.lo, x.hi), (y.lo, y.hi), (columns, rows))
                    }
                })
                .collect();
            let n: usize = segments.iter().map(Vec::len).sum();
            // Dense lines are drawn thin so that detail is not smeared.
            let stroke = if s.style == SeriesStyle::Line && n * 3 > columns {
                1
            } else {
                2
            };
            Drawn {
                segments,
                style: s.style,
                colour: s.colour,
                stroke,
            }
        })
        .collect();
    let band = c.band.as_ref().and_then(|(limit, _)| {
        if c.log_y {
            axis::to_plot(*limit, true).map(|top| (y.lo, top))
        } else {
            Some((-limit, *limit))
        }
    });
    PreparedXy {
        header,
        x_label: c.x_label.clone(),
        y_label: c.y_label.clone(),
        empty: c.series.iter().all(|s| s.segments.is_empty()),
        x,
        y,
        series,
        band,
        ref_lines: c.ref_lines.iter().map(|r| r.0).collect(),
        x_spans: c.x_spans.iter().map(|r| (r.0, r.1)).collect(),
    }
}

/// Dash and gap lengths (px) of a dashed series, and of a dotted one.
pub(crate) const DASH: u32 = 8;
pub(crate) const DASH_GAP: u32 = 5;
pub(crate) const DOT: u32 = 2;
pub(crate) const DOT_GAP: u32 = 4;

/// The shade of an x span: grey, so it reads as background under any series.
const SPAN: RGBColor = RGBColor(110, 110, 110);
/// Opacity of an x span's fill.
const SPAN_ALPHA: f64 = 0.12;

fn band_colour() -> RGBColor {
    style::colour(5) // sky blue: visible, yet quieter than any series
}

/// Draws a prepared panel into `area`, with `y_label_area` pixels left of the
/// plot for the y labels (equal across stacked panels so their axes align).
pub(crate) fn draw<DB: DrawingBackend>(
    p: &PreparedXy,
    area: &DrawingArea<DB, Shift>,
    y_label_area: u32,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let (head, body) = area.split_vertically(p.header.height());
    p.header.draw(&head)?;

    let mut chart = ChartBuilder::on(&body)
        .margin_top(MARGIN_TOP)
        .margin_right(MARGIN_RIGHT)
        .margin_left(MARGIN_LEFT)
        .x_label_area_size(X_LABEL_AREA)
        .y_label_area_size(y_label_area)
        .build_cartesian_2d(p.x.clone(), p.y.clone())?;
    let x_fmt = |v: &f64| p.x.label(*v);
    let y_fmt = |v: &f64| p.y.label(*v);
    chart
        .configure_mesh()
        .x_desc(p.x_label.as_str())
        .y_desc(p.y_label.as_str())
        .x_label_formatter(&x_fmt)
        .y_label_formatter(&y_fmt)
        .label_style(style::text(TICK_SIZE, INK))
        .axis_desc_style(style::text(LABEL_SIZE, INK))
        .bold_line_style(GRID.stroke_width(1))
        .light_line_style(GRID_LIGHT.stroke_width(1))
        .axis_style(INK.stroke_width(1))
        .draw()?;

    draw_spans_and_band(&mut chart, p)?;
    let baseline = if p.y.log {
        p.y.lo
    } else {
        0.0f64.clamp(p.y.lo, p.y.hi)
    };
    for s in &p.series {
        draw_series(&mut chart, s, baseline)?;
    }

    let (x0, x1) = (p.x.lo, p.x.hi);
    for &v in &p.ref_lines {
        chart.draw_series(std::iter::once(DashedPathElement::new(
            vec![(x0, v), (x1, v)],
            8,
            5,
            REFERENCE.stroke_width(2),
        )))?;
    }

    if p.empty {
        style::no_data(&chart.plotting_area().strip_coord_spec())?;
    }
    Ok(())
}

/// The chart a panel is drawn on: plot coordinates on both axes.
type Chart<'a, DB> = ChartContext<'a, DB, Cartesian2d<Axis, Axis>>;

/// The shaded x ranges and the ±band with its dashed edges, under the series.
fn draw_spans_and_band<DB: DrawingBackend>(
    chart: &mut Chart<'_, DB>,
    p: &PreparedXy,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let (x0, x1) = (p.x.lo, p.x.hi);
    for &(a, b) in &p.x_spans {
        let (a, b) = (a.clamp(x0, x1), b.clamp(x0, x1));
        if b > a {
            chart.draw_series(std::iter::once(Rectangle::new(
                [(a, p.y.lo), (b, p.y.hi)],
                SPAN.mix(SPAN_ALPHA).filled(),
            )))?;
        }
    }
    if let Some((lo, hi)) = p.band {
        let c = band_colour();
        chart.draw_series(std::iter::once(Rectangle::new(
            [(x0, lo), (x1, hi)],
            c.mix(BAND_ALPHA).filled(),
        )))?;
        for v in [lo, hi] {
            if v > p.y.lo && v < p.y.hi {
                chart.draw_series(std::iter::once(DashedPathElement::new(
                    vec![(x0, v), (x1, v)],
                    6,
                    4,
                    c.stroke_width(1),
                )))?;
            }
        }
    }
    Ok(())
}

/// One series in its style; stems rise from `baseline`.
fn draw_series<DB: DrawingBackend>(
    chart: &mut Chart<'_, DB>,
    s: &Drawn,
    baseline: f64,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    match s.style {
        SeriesStyle::Line => {
            for seg in &s.segments {
                if seg.len() == 1 {
                    // A lone point between gaps would be invisible as a path.
                    chart.draw_series(std::iter::once(Circle::new(
                        seg[0],
                        2,
                        s.colour.filled(),
                    )))?;
                } else {
                    chart.draw_series(std::iter::once(PathElement::new(
                        seg.clone(),
                        s.colour.stroke_width(s.stroke),
                    )))?;
                }
            }
        }
        SeriesStyle::Dashed | SeriesStyle::Dotted => {
            let (dash, gap) = if s.style == SeriesStyle::Dashed {
                (DASH, DASH_GAP)
            } else {
                (DOT, DOT_GAP)
            };
            for seg in &s.segments {
                chart.draw_series(std::iter::once(DashedPathElement::new(
                    seg.clone(),
                    dash,
                    gap,
                    s.colour.stroke_width(2),
                )))?;
            }
        }
        SeriesStyle::Points => {
            let dense = s.segments.iter().map(Vec::len).sum::<usize>() > 2000;
            let fill = if dense {
                s.colour.mix(0.5).filled()
            } else {
                s.colour.filled()
            };
            chart.draw_series(
                s.segments
                    .iter()
                    .flatten()
                    .map(|&pt| Circle::new(pt, 2, fill)),
            )?;
        }
        SeriesStyle::Stems => {
            for seg in &s.segments {
                chart.draw_series(seg.iter().map(|&(x, y)| {
                    PathElement::new(vec![(x, baseline), (x, y)], s.colour.stroke_width(2))
                }))?;
                chart.draw_series(seg.iter().map(|&pt| Circle::new(pt, 3, s.colour.filled())))?;
            }
        }
    }
    Ok(())
}
