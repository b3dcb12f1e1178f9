//! An x–y panel: axes with units, series, and reference marks.

use serde::Serialize;

use super::series::Series;

/// A shaded band `−limit ≤ y ≤ +limit`, e.g. the 95 % confidence band of a
/// correlation test (±1.96/√N). Set with [`Panel::band`].
///
/// ```
/// use plot::{Band, Panel};
/// let p = Panel::new("r", "lag (samples)", "r (–)").band(-0.028, "95 % band");
/// assert_eq!(p.band_limit(), Some(0.028)); // a half-width: the sign is dropped
/// let b = Band { limit: 0.028, label: "95 % band".into() };
/// assert_eq!(b.limit, 0.028);
/// ```
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Band {
    /// Half-width of the band, in the units of the y axis.
    pub limit: f64,
    /// Legend text, e.g. "95 % band (±1.96/√N)".
    pub label: String,
}

/// A horizontal dashed reference line, e.g. a PSD noise floor. Add with
/// [`Panel::ref_line`].
///
/// ```
/// use plot::{Panel, RefLine};
/// let p = Panel::psd("s0", "PSD (V²/Hz)").ref_line(4e-6, "noise floor");
/// assert_eq!(p.ref_lines(), &[RefLine { y: 4e-6, label: "noise floor".into() }]);
/// ```
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RefLine {
    /// Height of the line, in the units of the y axis.
    pub y: f64,
    /// Legend text.
    pub label: String,
}

/// One x–y panel of a [`Figure`](super::Figure): a title, axis labels (with
/// units, e.g. `"time (s)"`, `"signal s0 (mV)"`, `"PSD (V²/Hz)"`),
/// any number of [`Series`], optional log axes, an optional ±band and
/// horizontal reference lines.
///
/// On a log axis, points with a value ≤ 0 (or NaN) cannot be placed: they are
/// skipped, a line gets a gap there, and the skip is reported in
/// [`FigureFiles::warnings`](super::FigureFiles::warnings) rather than
/// clamped, because a clamped point would look like data.
///
/// ```
/// use plot::{Figure, Panel, Series};
///
/// let t: Vec<f64> = (0..5000).map(|i| i as f64 * 0.02).collect();
/// let az: Vec<f64> = t.iter().map(|t| 2.0 * (31.0 * t).sin()).collect();
/// let k0: Vec<f64> = az.iter().map(|a| 0.05 * a * a).collect();
/// // Fig. 3: a signal and the input acceleration.
/// let fig = Figure::new("Fig. 3 — signal and input acceleration")
///     .share_x()
///     .panel(Panel::new("Signal s0", "time (s)", "s0 (mV)").series(Series::line("s0", t.clone(), k0)))
///     .panel(Panel::new("Input acceleration", "time (s)", "az (g)").series(Series::line("az", t, az)));
/// let files = fig.save(std::env::temp_dir().join("plot-doc"), "fig3")?;
/// assert!(files.png.exists() && files.svg.exists());
/// # Ok::<(), plot::ReportError>(())
/// ```
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Panel {
    pub(crate) title: String,
    pub(crate) x_label: String,
    pub(crate) y_label: String,
    pub(crate) series: Vec<Series>,
    pub(crate) log_x: bool,
    pub(crate) log_y: bool,
    pub(crate) band: Option<Band>,
    pub(crate) ref_lines: Vec<RefLine>,
    pub(crate) x_spans: Vec<XSpan>,
}

/// A shaded stretch of the x axis with a legend entry (e.g. the part of a
/// record a model was fitted on), drawn under the series.
///
/// ```
/// use plot::Panel;
/// let p = Panel::new("p", "time (s)", "y (V)").x_span(0.0, 50.0, "training rows");
/// assert_eq!(p.x_spans()[0].to, 50.0);
/// ```
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct XSpan {
    /// Where the span starts, in x units.
    pub from: f64,
    /// Where it ends, in x units.
    pub to: f64,
    /// Its legend entry.
    pub label: String,
}

impl Panel {
    /// An empty panel with a title and axis labels. Put the unit in each axis
    /// label: the report never guesses units.
    ///
    /// ```
    /// use plot::Panel;
    /// let p = Panel::new("Rate X", "time (s)", "rate (mV)");
    /// assert_eq!(p.title(), "Rate X");
    /// ```
    pub fn new(
        title: impl Into<String>,
        x_label: impl Into<String>,
        y_label: impl Into<String>,
    ) -> Self {
        Panel {
            title: title.into(),
            x_label: x_label.into(),
            y_label: y_label.into(),
            series: Vec::new(),
            log_x: false,
            log_y: false,
            band: None,
            ref_lines: Vec::new(),
            x_spans: Vec::new(),
        }
    }

    /// A log–log panel for power spectral densities, x labelled
    /// `"frequency (Hz)"`. The 0 Hz bin of a periodogram cannot be shown on a
    /// log axis and is skipped with a warning.
    ///
    /// ```
    /// use plot::{Panel, Series};
    ///
    /// let f: Vec<f64> = (0..=1250).map(|k| k as f64 * 0.02).collect(); // 0..25 Hz
    /// let before: Vec<f64> = f.iter().map(|f| 1e-2 / (1.0 + f * f)).collect();
    /// let after: Vec<f64> = f.iter().map(|f| 1e-4 + 1e-3 / (1.0 + f * f)).collect();
    /// let p = Panel::psd("s0 spectrum", "PSD (V²/Hz)")
    ///     .series(Series::line("before", f.clone(), before).colour(1))
    ///     .series(Series::line("after", f, after).colour(0))
    ///     .ref_line(1e-4, "noise floor");
    /// assert!(p.is_log_x() && p.is_log_y());
    /// ```
    pub fn psd(title: impl Into<String>, y_label: impl Into<String>) -> Self {
        Panel::new(title, "frequency (Hz)", y_label).log_x().log_y()
    }

    /// A correlation test: `r` at each lag drawn as stems, with the ±`band`
    /// confidence band (typically 1.96/√N for 95 %). The y axis is the
    /// dimensionless normalised correlation.
    ///
    /// # Panics
    /// If `lags` and `r` differ in length.
    ///
    /// ```
    /// use plot::Panel;
    ///
    /// let n = 5000.0_f64;
    /// let lags: Vec<f64> = (0..=25).map(f64::from).collect();
    /// let r: Vec<f64> = lags.iter().map(|&k| if k == 0.0 { 1.0 } else { 0.3 * 0.7_f64.powf(k) }).collect();
    /// let p = Panel::correlation("Autocorrelation of the s0 residual", "lag (samples)", lags, r, 1.96 / n.sqrt());
    /// assert!(p.band_limit().unwrap() < 0.03);
    /// ```
    #[track_caller]
    pub fn correlation(
        title: impl Into<String>,
        lag_label: impl Into<String>,
        lags: impl Into<Vec<f64>>,
        r: impl Into<Vec<f64>>,
        band: f64,
    ) -> Self {
        Panel::new(title, lag_label, "correlation (–)")
            // No legend entry for the stems: the title says what they are.
            .series(Series::stems("", lags, r))
            .band(band, "95 % confidence band")
    }

    /// Adds a series; it takes the next palette colour unless it has its own.
    ///
    /// ```
    /// use plot::{Panel, Series};
    /// let p = Panel::new("p", "t (s)", "y (g)").series(Series::sampled("a", 0.0, 1.0, vec![1.0]));
    /// assert_eq!(p.series_count(), 1);
    /// ```
    pub fn series(mut self, series: Series) -> Self {
        self.series.push(series);
        self
    }

    /// Log scale (base 10) on x.
    ///
    /// ```
    /// # use plot::Panel;
    /// assert!(Panel::new("p", "f (Hz)", "y (g)").log_x().is_log_x());
    /// ```
    pub fn log_x(mut self) -> Self {
        self.log_x = true;
        self
    }

    /// Log scale (base 10) on y.
    ///
    /// ```
    /// # use plot::Panel;
    /// assert!(Panel::new("p", "f (Hz)", "y (g)").log_y().is_log_y());
    /// ```
    pub fn log_y(mut self) -> Self {
        self.log_y = true;
        self
    }

    /// A shaded band between −`limit` and +`limit` (replacing any earlier
    /// one). On a log y axis only the part above zero can be drawn: the band
    /// fills from the bottom of the axis up to `limit`.
    ///
    /// ```
    /// # use plot::Panel;
    /// let p = Panel::new("p", "lag (samples)", "r (–)").band(0.028, "95 % band");
    /// assert_eq!(p.band_limit(), Some(0.028));
    /// ```
    pub fn band(mut self, limit: f64, label: impl Into<String>) -> Self {
        self.band = Some(Band {
            limit: limit.abs(),
            label: label.into(),
        });
        self
    }

    /// A horizontal dashed reference line at `y` (noise floor, limit, …).
    ///
    /// ```
    /// # use plot::Panel;
    /// let p = Panel::psd("p", "PSD (g²/Hz)").ref_line(1e-6, "noise floor");
    /// assert_eq!(p.ref_lines()[0].y, 1e-6);
    /// ```
    pub fn ref_line(mut self, y: f64, label: impl Into<String>) -> Self {
        self.ref_lines.push(RefLine {
            y,
            label: label.into(),
        });
        self
    }

    /// Shades the x range `from..to` (in x units) under the series, with a
    /// legend entry; several spans share one legend entry per distinct label.
    ///
    /// ```
    /// # use plot::Panel;
    /// let p = Panel::new("p", "time (s)", "y (V)")
    ///     .x_span(0.0, 50.0, "training")
    ///     .x_span(80.0, 90.0, "training");
    /// assert_eq!(p.x_spans().len(), 2);
    /// ```
    pub fn x_span(mut self, from: f64, to: f64, label: impl Into<String>) -> Self {
        self.x_spans.push(XSpan {
            from: from.min(to),
            to: from.max(to),
            label: label.into(),
        });
        self
    }

    /// The shaded x ranges.
    ///
    /// ```
    /// # use plot::Panel;
    /// assert!(Panel::new("p", "t (s)", "y (V)").x_spans().is_empty());
    /// ```
    pub fn x_spans(&self) -> &[XSpan] {
        &self.x_spans
    }

    /// The panel title.
    ///
    /// ```
    /// # use plot::Panel;
    /// assert_eq!(Panel::new("s5", "t (s)", "s5 (mV)").title(), "s5");
    /// ```
    pub fn title(&self) -> &str {
        &self.title
    }

    /// Number of series.
    ///
    /// ```
    /// # use plot::Panel;
    /// assert_eq!(Panel::new("p", "t (s)", "y (g)").series_count(), 0);
    /// ```
    pub fn series_count(&self) -> usize {
        self.series.len()
    }

    /// Whether x is on a log scale.
    ///
    /// ```
    /// # use plot::Panel;
    /// assert!(!Panel::new("p", "t (s)", "y (g)").is_log_x());
    /// ```
    pub fn is_log_x(&self) -> bool {
        self.log_x
    }

    /// Whether y is on a log scale.
    ///
    /// ```
    /// # use plot::Panel;
    /// assert!(Panel::psd("p", "PSD (g²/Hz)").is_log_y());
    /// ```
    pub fn is_log_y(&self) -> bool {
        self.log_y
    }

    /// The band half-width, if a band is set.
    ///
    /// ```
    /// # use plot::Panel;
    /// assert_eq!(Panel::new("p", "t (s)", "y (g)").band_limit(), None);
    /// ```
    pub fn band_limit(&self) -> Option<f64> {
        self.band.as_ref().map(|b| b.limit)
    }

    /// The reference lines.
    ///
    /// ```
    /// # use plot::Panel;
    /// assert!(Panel::new("p", "t (s)", "y (g)").ref_lines().is_empty());
    /// ```
    pub fn ref_lines(&self) -> &[RefLine] {
        &self.ref_lines
    }
}
