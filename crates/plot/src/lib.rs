//! plot: figures and self-contained HTML reports over plain slices and strings.
//!
//! What it is: a small plotting vocabulary on [plotters] that draws each
//! figure once, generic over the backend, and saves it as PNG **and** SVG;
//! and an HTML page builder that puts text, tables and those figures into one
//! `index.html`. What it is not: a general charting toolkit (no pie charts,
//! no interactivity, no colour maps), a numeric library (it computes no
//! spectra or statistics: callers pass the numbers to draw), or anything that
//! knows what the numbers mean: it takes `&[f64]` and strings, so the
//! application that computes them can change without touching the drawing.
//!
//! - [`Series`]: labelled points drawn as a line, dots or stems;
//! - [`Panel`]: axes with units, series, optional log axes, a ±band
//!   ([`Panel::correlation`]) and reference lines ([`Panel::psd`] for spectra);
//! - [`BarChart`]: horizontal bars, ranked ([`BarChart::ranked`], with a
//!   threshold) or grouped (before/after);
//! - [`Figure`]: a title over stacked panels, saved as PNG and SVG by one
//!   drawing routine generic over the plotters backend;
//! - [`HtmlReport`]: a single self-contained `index.html` with text, tables
//!   and figures.
//!
//! Robustness is part of the contract: empty, constant and NaN-laden series
//! draw without panicking; long series are decimated per pixel column keeping
//! peaks ([`decimate_m4`]); values a log axis cannot show are skipped and
//! reported in [`FigureFiles::warnings`]. Programmer errors (x and y of
//! different lengths, a table row of the wrong width) panic at the caller;
//! everything else is a typed [`ReportError`].
//!
//! ```
//! use plot::{BarChart, Figure, HtmlReport, Panel, Section, Series};
//!
//! let dir = std::env::temp_dir().join("plot-doc-overview");
//! let t: Vec<f64> = (0..5000).map(|i| i as f64 * 0.02).collect();
//! let y: Vec<f64> = t.iter().map(|t| 0.2 * (4.0 * t).sin()).collect();
//! let signal = Figure::new("Signal s0")
//!     .panel(Panel::new("s0", "time (s)", "s0 (mV)").series(Series::line("s0", t, y)))
//!     .save(&dir, "s0")?;
//! let ranking = Figure::new("Candidate regressors")
//!     .panel(BarChart::ranked("ERR", "ERR (–)", "ERR", [("u_sq", 0.41), ("v", 0.004)])
//!         .threshold(0.01, "significance threshold"))
//!     .save(&dir, "ranking")?;
//! let index = HtmlReport::new("Report")
//!     .section(Section::new("Signals").figure(&signal, "s0 over the record"))
//!     .section(Section::new("Regressors").figure(&ranking, "ERR of the candidates"))
//!     .write(&dir)?;
//! assert!(index.exists());
//! # Ok::<(), plot::ReportError>(())
//! ```

#![warn(missing_docs)]

mod axis;
mod bars;
mod decimate;
mod error;
mod figure;
mod html;
mod legend;
mod panel;
mod series;
mod style;
mod xy;

#[cfg(test)]
mod tests;

pub use bars::BarChart;
pub use decimate::decimate_m4;
pub use error::ReportError;
pub use figure::{Chart, Figure, FigureFiles};
pub use html::{HtmlReport, Section, Table, escape_html};
pub use panel::{Band, Panel, RefLine, XSpan};
pub use series::{Series, SeriesStyle};
pub use style::{PALETTE, colour};
