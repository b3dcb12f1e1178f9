//! Horizontal bar charts: ranked ERR of candidate effects, and per-sensor
//! rms before and after a change.
//!
//! Bars run horizontally so that category labels (effect ids such as
//! `u_sq`, `col:temp`, sensor names) are written level and never collide,
//! however many candidates there are; the first category is at the top, which
//! is where a ranking is read from. Each bar carries its value as text, since
//! a report is read for numbers as much as for shapes.

use plotters::chart::ChartBuilder;
use plotters::coord::Shift;
use plotters::drawing::{DrawingArea, DrawingAreaErrorKind};
use plotters::element::{DashedPathElement, EmptyElement, Rectangle, Text};
use plotters::prelude::DrawingBackend;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use plotters::style::{Color, RGBColor, WHITE};
use serde::Serialize;

use super::axis::{self, Axis, Extent};
use super::legend::{Entry, Header, Swatch};
use super::style::{self, GRID, INK, LABEL_SIZE, LEGEND_SIZE, MUTED, REFERENCE, TICK_SIZE};
use super::xy::{MARGIN_LEFT, MARGIN_RIGHT, MARGIN_TOP, X_LABEL_AREA};

/// Opacity of bars below the threshold: still readable, visibly "not chosen".
const BELOW_ALPHA: f64 = 0.35;

/// One set of values, one per category (e.g. "before" or "after").
#[derive(Clone, Debug, PartialEq, Serialize)]
struct Group {
    label: String,
    values: Vec<f64>,
    colour: usize,
}

/// A horizontal bar chart of categories, with one or more groups of values
/// and an optional threshold line.
///
/// With a threshold and a single group, bars below it are drawn faded: the
/// ERR chart then shows at a glance which candidate effects are significant.
/// NaN values draw no bar and are labelled "n/a".
///
/// ```
/// use plot::{BarChart, Figure};
///
/// // Per-sensor rms before and after adding an effect.
/// let sensors = ["A", "B", "C", "D", "E", "F"];
/// let chart = BarChart::new("Validation rms per sensor", "rms (mV)", sensors)
///     .group("before", vec![0.61, 0.58, 0.40, 0.42, 0.77, 0.35])
///     .group("after", vec![0.12, 0.11, 0.10, 0.13, 0.12, 0.10]);
/// let files = Figure::new("Adding u_sq to Z").panel(chart)
///     .save(std::env::temp_dir().join("plot-doc"), "before_after_rms")?;
/// assert!(files.warnings.is_empty());
/// # Ok::<(), plot::ReportError>(())
/// ```
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct BarChart {
    title: String,
    value_label: String,
    categories: Vec<String>,
    groups: Vec<Group>,
    threshold: Option<(f64, String)>,
}

impl BarChart {
    /// A chart with the given categories (top to bottom) and no values yet.
    /// `value_label` names the value axis, with its unit.
    ///
    /// ```
    /// use plot::BarChart;
    /// let c = BarChart::new("rms", "rms (mV)", ["s0", "s1"]);
    /// assert_eq!(c.categories(), &["s0", "s1"]);
    /// ```
    pub fn new(
        title: impl Into<String>,
        value_label: impl Into<String>,
        categories: impl IntoIterator<Item = impl Into<String>>,
    ) -> Self {
        BarChart {
            title: title.into(),
            value_label: value_label.into(),
            categories: categories.into_iter().map(Into::into).collect(),
            groups: Vec::new(),
            threshold: None,
        }
    }

    /// A ranking, e.g. candidate effects by error-reduction ratio: one group,
    /// categories sorted by value, largest first (NaN last).
    ///
    /// ```
    /// use plot::BarChart;
    /// let c = BarChart::ranked("ERR of candidates, sensor Z", "ERR (–)", "ERR",
    ///     [("g_I", 0.002), ("u_sq", 0.41), ("col:temp", f64::NAN), ("v", 0.03)])
    ///     .threshold(0.01, "significance threshold");
    /// assert_eq!(c.categories(), &["u_sq", "v", "g_I", "col:temp"]);
    /// ```
    pub fn ranked(
        title: impl Into<String>,
        value_label: impl Into<String>,
        group_label: impl Into<String>,
        items: impl IntoIterator<Item = (impl Into<String>, f64)>,
    ) -> Self {
        let mut items: Vec<(String, f64)> = items.into_iter().map(|(l, v)| (l.into(), v)).collect();
        // Descending, NaN last; stable, so ties keep the caller's order.
        items.sort_by(|a, b| match (a.1.is_nan(), b.1.is_nan()) {
            (false, false) => b.1.total_cmp(&a.1),
            (x, y) => x.cmp(&y),
        });
        let (labels, values): (Vec<String>, Vec<f64>) = items.into_iter().unzip();
        BarChart::new(title, value_label, labels).group(group_label, values)
    }

    /// Adds a group of values, one per category, coloured by the next palette
    /// colour.
    ///
    /// # Panics
    /// If `values` does not have one value per category.
    ///
    /// ```
    /// use plot::BarChart;
    /// let c = BarChart::new("rms", "rms (mV)", ["s0", "s1"]).group("before", vec![1.0, 2.0]);
    /// assert_eq!(c.group_count(), 1);
    /// ```
    #[track_caller]
    pub fn group(self, label: impl Into<String>, values: impl Into<Vec<f64>>) -> Self {
        let colour = self.groups.len();
        self.group_coloured(label, values, colour)
    }

    /// Adds a group of values in palette colour `colour` (as
    /// [`Series::colour`](super::Series::colour)), to keep one colour per
    /// meaning across a figure, e.g. "before" vermillion in the bars and in
    /// the time series below them.
    ///
    /// # Panics
    /// If `values` does not have one value per category.
    ///
    /// ```
    /// use plot::BarChart;
    /// let c = BarChart::new("rms", "rms (mV)", ["s0", "s1"])
    ///     .group_coloured("before", vec![1.0, 2.0], 1)
    ///     .group_coloured("after", vec![0.2, 0.3], 0);
    /// assert_eq!(c.group_count(), 2);
    /// ```
    #[track_caller]
    pub fn group_coloured(
        mut self,
        label: impl Into<String>,
        values: impl Into<Vec<f64>>,
        colour: usize,
    ) -> Self {
        let label = label.into();
        let values = values.into();
        assert_eq!(
            values.len(),
            self.categories.len(),
            "bar group {label:?}: {} values for {} categories",
            values.len(),
            self.categories.len()
        );
        self.groups.push(Group {
            label,
            values,
            colour,
        });
        self
    }

    /// A vertical dashed line at `value` (e.g. the ERR significance level).
    ///
    /// ```
    /// use plot::BarChart;
    /// let c = BarChart::new("ERR", "ERR (–)", ["a"]).group("ERR", vec![0.5]).threshold(0.05, "5 % level");
    /// assert_eq!(c.threshold_value(), Some(0.05));
    /// ```
    pub fn threshold(mut self, value: f64, label: impl Into<String>) -> Self {
        self.threshold = Some((value, label.into()));
        self
    }

    /// The categories, top to bottom.
    ///
    /// ```
    /// # use plot::BarChart;
    /// assert!(BarChart::new("t", "v (g)", Vec::<String>::new()).categories().is_empty());
    /// ```
    pub fn categories(&self) -> &[String] {
        &self.categories
    }

    /// Number of groups.
    ///
    /// ```
    /// # use plot::BarChart;
    /// assert_eq!(BarChart::new("t", "v (g)", ["a"]).group_count(), 0);
    /// ```
    pub fn group_count(&self) -> usize {
        self.groups.len()
    }

    /// The threshold, if set.
    ///
    /// ```
    /// # use plot::BarChart;
    /// assert_eq!(BarChart::new("t", "v (g)", ["a"]).threshold_value(), None);
    /// ```
    pub fn threshold_value(&self) -> Option<f64> {
        self.threshold.as_ref().map(|t| t.0)
    }

    /// A height that gives every bar room for its label (used when the figure
    /// size is not set).
    pub(crate) fn natural_height(&self) -> u32 {
        let per_category = 14 * self.groups.len().max(1) as u32 + 16;
        (110 + per_category * self.categories.len() as u32).max(230)
    }
}

/// A bar chart laid out for a pixel size.
#[derive(Clone, Debug)]
pub(crate) struct PreparedBars {
    header: Header,
    value_label: String,
    x: Axis,
    categories: Vec<String>,
    groups: Vec<(Vec<f64>, RGBColor)>,
    threshold: Option<f64>,
    fade_below: bool,
    label_area: u32,
}

pub(crate) fn prepare(chart: &BarChart, width: u32, warnings: &mut Vec<String>) -> PreparedBars {
    let mut extent = Extent::default();
    extent.add(0.0); // bars grow from zero
    let mut nan = 0;
    for g in &chart.groups {
        for &v in &g.values {
            if v.is_finite() {
                extent.add(v);
            } else {
                nan += 1;
            }
        }
    }
    if nan > 0 {
        warnings.push(format!(
            "bar chart {:?}: {nan} value(s) are NaN or infinite and have no bar",
            chart.title
        ));
    }
    let threshold = chart
        .threshold
        .as_ref()
        .map(|t| t.0)
        .filter(|v| v.is_finite());
    if let Some(t) = threshold {
        extent.add(t);
    }
    let fade_below = threshold.is_some() && chart.groups.len() == 1;

    let mut entries: Vec<Entry> = chart
        .groups
        .iter()
        .map(|g| Entry {
            swatch: Swatch::Fill(style::colour(g.colour), 1.0),
            label: g.label.clone(),
        })
        .collect();
    if let Some((_, label)) = chart.threshold.as_ref().filter(|_| threshold.is_some()) {
        if fade_below {
            entries.push(Entry {
                swatch: Swatch::Fill(style::colour(0), BELOW_ALPHA),
                label: "below threshold".to_string(),
            });
        }
        entries.push(Entry {
            swatch: Swatch::Dashed(REFERENCE),
            label: label.clone(),
        });
    }
    let header = Header::layout(&chart.title, entries, width);

    // Room right of the longest bar for its value text: about a sixth of the span.
    let (lo, hi) = match extent.get() {
        Some((lo, hi)) if hi > lo => {
            let span = hi - lo;
            (
                if lo < 0.0 { lo - 0.18 * span } else { lo },
                if hi > 0.0 { hi + 0.18 * span } else { hi },
            )
        }
        _ => (0.0, 1.0),
    };
    let label_area = chart
        .categories
        .iter()
        .map(|c| style::text_size(c, TICK_SIZE).0)
        .max()
        .unwrap_or(0)
        + 24;
    let plot_width = width
        .saturating_sub(label_area + MARGIN_LEFT + MARGIN_RIGHT)
        .max(20);
    PreparedBars {
        header,
        value_label: chart.value_label.clone(),
        x: Axis::new(lo, hi, false, plot_width, crate::xy::X_TICK_SPACING_PX),
        categories: chart.categories.clone(),
        groups: chart
            .groups
            .iter()
            .map(|g| (g.values.clone(), style::colour(g.colour)))
            .collect(),
        threshold,
        fade_below,
        label_area,
    }
}

pub(crate) fn draw<DB: DrawingBackend>(
    p: &PreparedBars,
    area: &DrawingArea<DB, Shift>,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let (head, body) = area.split_vertically(p.header.height());
    p.header.draw(&head)?;

    let n = p.categories.len();
    let n_f = n.max(1) as f64;
    // Category i occupies [n-1-i, n-i] in y, so the first is at the top.
    let centre = |i: usize| n_f - i as f64 - 0.5;
    let y = Axis {
        lo: 0.0,
        hi: n_f,
        log: false,
        ticks: p
            .categories
            .iter()
            .enumerate()
            .map(|(i, c)| (centre(i), c.clone()))
            .collect(),
        minor: Vec::new(),
    };
    let y_fmt = |v: &f64| y.label(*v);
    let x_fmt = |v: &f64| p.x.label(*v);
    let mut chart = ChartBuilder::on(&body)
        .margin_top(MARGIN_TOP)
        .margin_right(MARGIN_RIGHT)
        .margin_left(MARGIN_LEFT)
        .x_label_area_size(X_LABEL_AREA)
        .y_label_area_size(p.label_area)
        .build_cartesian_2d(p.x.clone(), y.clone())?;
    chart
        .configure_mesh()
        .disable_y_mesh()
        .x_desc(p.value_label.as_str())
        .x_label_formatter(&x_fmt)
        .y_label_formatter(&y_fmt)
        .label_style(style::text(TICK_SIZE, INK))
        .axis_desc_style(style::text(LABEL_SIZE, INK))
        .bold_line_style(GRID.stroke_width(1))
        .axis_style(INK.stroke_width(1))
        .draw()?;

    let groups = p.groups.len().max(1) as f64;
    let slot = 0.8 / groups; // 80 % of a category's height is bars, 20 % gap
    let bar = |g: usize, i: usize| {
        let top = n_f - i as f64 - 0.1 - g as f64 * slot;
        (top - slot * 0.92, top)
    };
    for (g, (values, colour)) in p.groups.iter().enumerate() {
        for (i, &v) in values.iter().enumerate().filter(|(_, v)| v.is_finite()) {
            let (y0, y1) = bar(g, i);
            let faded = p.fade_below && p.threshold.is_some_and(|t| v < t);
            let fill = if faded {
                colour.mix(BELOW_ALPHA).filled()
            } else {
                colour.filled()
            };
            chart.draw_series(std::iter::once(Rectangle::new([(0.0, y0), (v, y1)], fill)))?;
        }
    }
    if let Some(t) = p.threshold {
        chart.draw_series(std::iter::once(DashedPathElement::new(
            vec![(t, 0.0), (t, n_f)],
            8,
            5,
            REFERENCE.stroke_width(2),
        )))?;
    }
    // Values last, on a light backing, so the threshold line never strikes
    // through a number.
    for (g, (values, _)) in p.groups.iter().enumerate() {
        for (i, &v) in values.iter().enumerate() {
            let (y0, y1) = bar(g, i);
            let at = (if v.is_finite() { v } else { 0.0 }, (y0 + y1) / 2.0);
            let text = axis::format_significant(v);
            let (w, h) = style::text_size(&text, LEGEND_SIZE);
            let (w, h) = (w as i32, h as i32);
            let (x0, anchor) = if v >= 0.0 || !v.is_finite() {
                (6, Pos::new(HPos::Left, VPos::Center))
            } else {
                (-6 - w, Pos::new(HPos::Right, VPos::Center))
            };
            let dx = if v >= 0.0 || !v.is_finite() { 6 } else { -6 };
            let ink = if v.is_finite() { INK } else { MUTED };
            chart.draw_series(std::iter::once(
                EmptyElement::at(at)
                    + Rectangle::new(
                        [(x0 - 2, -h / 2 - 3), (x0 + w + 3, h / 2 + 3)],
                        WHITE.filled(),
                    )
                    + Text::new(text, (dx, 0), style::text(LEGEND_SIZE, ink).pos(anchor)),
            ))?;
        }
    }
    if n == 0 || p.groups.is_empty() {
        style::no_data(&chart.plotting_area().strip_coord_spec())?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    #[should_panic(expected = "bar group \"after\": 1 values for 2 categories")]
    fn group_length_must_match() {
        let _ = BarChart::new("t", "v (g)", ["a", "b"]).group("after", vec![1.0]);
    }

    #[test]
    fn ranking_sorts_descending_with_nan_last_and_stable_ties() {
        let c = BarChart::ranked(
            "t",
            "ERR (–)",
            "ERR",
            [("a", 0.1), ("b", f64::NAN), ("c", 0.5), ("d", 0.1)],
        );
        assert_eq!(c.categories(), &["c", "a", "d", "b"]);
    }
}
