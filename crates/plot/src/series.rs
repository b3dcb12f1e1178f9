//! One named sequence of (x, y) points and how to mark it.

use serde::Serialize;

/// How a series is marked; chosen by the [`Series`] constructor.
///
/// ```
/// use plot::{Series, SeriesStyle};
/// assert_eq!(Series::points("r", vec![0.0], vec![1.0]).style(), SeriesStyle::Points);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum SeriesStyle {
    /// Connected line; NaN values (and, on log axes, values ≤ 0) break it.
    Line,
    /// A dot per point, for scatter plots (residual against a candidate effect).
    Points,
    /// A vertical stem from zero with a dot on top, for correlations at lags.
    Stems,
    /// A dashed line (a fitted or reference line over the data it describes).
    Dashed,
    /// A dotted line (a third line of one colour, after a solid and a dashed one).
    Dotted,
}

impl SeriesStyle {
    /// A connected line of any pattern (solid, dashed, dotted).
    ///
    /// ```
    /// use plot::SeriesStyle;
    /// assert!(SeriesStyle::Dashed.is_line() && !SeriesStyle::Stems.is_line());
    /// ```
    pub fn is_line(self) -> bool {
        matches!(
            self,
            SeriesStyle::Line | SeriesStyle::Dashed | SeriesStyle::Dotted
        )
    }
}

/// A labelled series of points, owned, so figures can be built from any
/// source without lifetimes.
///
/// Construct with [`Series::line`], [`Series::points`], [`Series::stems`] or
/// [`Series::sampled`]. NaN and infinite values are allowed: they are skipped
/// when drawing (a line gets a gap). An empty label keeps the series out of
/// the legend.
///
/// ```
/// use plot::{Series, SeriesStyle};
///
/// let t: Vec<f64> = (0..5000).map(|i| i as f64 * 0.02).collect();
/// let k0: Vec<f64> = t.iter().map(|t| 0.1 * (7.0 * t).sin()).collect();
/// let s = Series::line("s0 before", t, k0).colour(1);
/// assert_eq!(s.len(), 5000);
/// assert_eq!(s.style(), SeriesStyle::Line);
/// ```
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Series {
    label: String,
    x: Vec<f64>,
    y: Vec<f64>,
    style: SeriesStyle,
    colour: Option<usize>,
}

impl Series {
    /// A connected line through `(x[i], y[i])`.
    ///
    /// # Panics
    /// If `x` and `y` differ in length: that is a bug in the caller, not a
    /// property of the data.
    ///
    /// ```
    /// use plot::Series;
    /// let s = Series::line("az", vec![0.0, 0.02, 0.04], &[0.1, -0.3, 0.2][..]);
    /// assert_eq!(s.x(), &[0.0, 0.02, 0.04]);
    /// ```
    #[track_caller]
    pub fn line(label: impl Into<String>, x: impl Into<Vec<f64>>, y: impl Into<Vec<f64>>) -> Self {
        Self::with_style(label.into(), x.into(), y.into(), SeriesStyle::Line)
    }

    /// A dashed line through `(x[i], y[i])`: a fitted line drawn over the
    /// curve it was fitted to, or a second series of the same meaning (and
    /// colour) as a solid one.
    ///
    /// # Panics
    /// If `x` and `y` differ in length.
    ///
    /// ```
    /// use plot::{Series, SeriesStyle};
    /// let s = Series::dashed("fitted", vec![1.0, 10.0], vec![3.0, 1.0]).colour(6);
    /// assert_eq!(s.style(), SeriesStyle::Dashed);
    /// ```
    #[track_caller]
    pub fn dashed(
        label: impl Into<String>,
        x: impl Into<Vec<f64>>,
        y: impl Into<Vec<f64>>,
    ) -> Self {
        Self::with_style(label.into(), x.into(), y.into(), SeriesStyle::Dashed)
    }

    /// A dotted line through `(x[i], y[i])`: a third series of one colour
    /// after [`Series::line`] and [`Series::dashed`].
    ///
    /// # Panics
    /// If `x` and `y` differ in length.
    ///
    /// ```
    /// use plot::{Series, SeriesStyle};
    /// let s = Series::dotted("az", vec![0.0, 1.0], vec![0.1, 0.0]);
    /// assert_eq!(s.style(), SeriesStyle::Dotted);
    /// ```
    #[track_caller]
    pub fn dotted(
        label: impl Into<String>,
        x: impl Into<Vec<f64>>,
        y: impl Into<Vec<f64>>,
    ) -> Self {
        Self::with_style(label.into(), x.into(), y.into(), SeriesStyle::Dotted)
    }

    /// Unconnected dots, e.g. the residual against a candidate regressor.
    ///
    /// # Panics
    /// If `x` and `y` differ in length.
    ///
    /// ```
    /// use plot::{Series, SeriesStyle};
    /// let s = Series::points("residual", vec![0.1, 0.2], vec![1.0, 2.0]);
    /// assert_eq!(s.style(), SeriesStyle::Points);
    /// ```
    #[track_caller]
    pub fn points(
        label: impl Into<String>,
        x: impl Into<Vec<f64>>,
        y: impl Into<Vec<f64>>,
    ) -> Self {
        Self::with_style(label.into(), x.into(), y.into(), SeriesStyle::Points)
    }

    /// Stems from zero, e.g. a correlation at each lag.
    ///
    /// # Panics
    /// If `x` and `y` differ in length.
    ///
    /// ```
    /// use plot::Series;
    /// let lags: Vec<f64> = (0..=20).map(f64::from).collect();
    /// let r: Vec<f64> = lags.iter().map(|&k| if k == 0.0 { 1.0 } else { 0.02 }).collect();
    /// let s = Series::stems("autocorrelation", lags, r);
    /// assert_eq!(s.len(), 21);
    /// ```
    #[track_caller]
    pub fn stems(label: impl Into<String>, x: impl Into<Vec<f64>>, y: impl Into<Vec<f64>>) -> Self {
        Self::with_style(label.into(), x.into(), y.into(), SeriesStyle::Stems)
    }

    /// A line of uniformly sampled values, `x[i] = t0 + i·dt` (a record's
    /// sensor against time in s without building the time vector).
    ///
    /// ```
    /// use plot::Series;
    /// let s = Series::sampled("X", 0.0, 0.02, vec![1.0, 2.0, 3.0]);
    /// assert_eq!(s.x(), &[0.0, 0.02, 0.04]);
    /// ```
    pub fn sampled(label: impl Into<String>, t0: f64, dt: f64, y: impl Into<Vec<f64>>) -> Self {
        let y = y.into();
        let x = (0..y.len()).map(|i| t0 + i as f64 * dt).collect();
        Self::with_style(label.into(), x, y, SeriesStyle::Line)
    }

    #[track_caller]
    fn with_style(label: String, x: Vec<f64>, y: Vec<f64>, style: SeriesStyle) -> Self {
        assert_eq!(
            x.len(),
            y.len(),
            "series {label:?}: x has {} values but y has {}",
            x.len(),
            y.len()
        );
        Series {
            label,
            x,
            y,
            style,
            colour: None,
        }
    }

    /// Chooses the palette colour ([`PALETTE`](super::PALETTE)`[index % 8]`)
    /// instead of the series' position in its panel; use it to keep one
    /// meaning per colour across panels (e.g. "before" always vermillion).
    ///
    /// ```
    /// use plot::Series;
    /// let s = Series::sampled("after", 0.0, 1.0, vec![0.0]).colour(0);
    /// assert_eq!(s.colour_index(), Some(0));
    /// ```
    pub fn colour(mut self, index: usize) -> Self {
        self.colour = Some(index);
        self
    }

    /// The legend label.
    ///
    /// ```
    /// # use plot::Series;
    /// assert_eq!(Series::sampled("s3", 0.0, 1.0, vec![]).label(), "s3");
    /// ```
    pub fn label(&self) -> &str {
        &self.label
    }

    /// The x values.
    ///
    /// ```
    /// # use plot::Series;
    /// assert_eq!(Series::sampled("a", 1.0, 1.0, vec![5.0]).x(), &[1.0]);
    /// ```
    pub fn x(&self) -> &[f64] {
        &self.x
    }

    /// The y values.
    ///
    /// ```
    /// # use plot::Series;
    /// assert_eq!(Series::sampled("a", 1.0, 1.0, vec![5.0]).y(), &[5.0]);
    /// ```
    pub fn y(&self) -> &[f64] {
        &self.y
    }

    /// The marking style.
    ///
    /// ```
    /// # use plot::{Series, SeriesStyle};
    /// assert_eq!(Series::stems("r", vec![0.0], vec![1.0]).style(), SeriesStyle::Stems);
    /// ```
    pub fn style(&self) -> SeriesStyle {
        self.style
    }

    /// The palette index set with [`Series::colour`], if any.
    ///
    /// ```
    /// # use plot::Series;
    /// assert_eq!(Series::sampled("a", 0.0, 1.0, vec![]).colour_index(), None);
    /// ```
    pub fn colour_index(&self) -> Option<usize> {
        self.colour
    }

    /// Number of points (including any NaN).
    ///
    /// ```
    /// # use plot::Series;
    /// assert_eq!(Series::sampled("a", 0.0, 1.0, vec![f64::NAN, 1.0]).len(), 2);
    /// ```
    pub fn len(&self) -> usize {
        self.x.len()
    }

    /// Whether the series has no points.
    ///
    /// ```
    /// # use plot::Series;
    /// assert!(Series::sampled("a", 0.0, 1.0, vec![]).is_empty());
    /// ```
    pub fn is_empty(&self) -> bool {
        self.x.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    #[should_panic(expected = "series \"bad\": x has 3 values but y has 2")]
    fn mismatched_lengths_panic_with_the_label() {
        let _ = Series::line("bad", vec![0.0, 1.0, 2.0], vec![0.0, 1.0]);
    }
}
