//! Figures and the HTML report, over plain data.
//!
//! A small plotting vocabulary for the paper's figures (Fig. 3 a parity
//! residue and the thrust acceleration, Fig. 5 processed acceleration and
//! rate, Fig. 6 target and network output, Fig. 7 residues with and without
//! compensation, residue spectra) and for the diagnosis loop (residual
//! against candidate effects, PSD against a noise floor, correlation tests
//! with confidence bands, ERR rankings, before/after comparisons):
//!
//! - [`Series`]: labelled points drawn as a line, dots or stems;
//! - [`Panel`]: axes with units, series, optional log axes, a ±band
//!   ([`Panel::correlation`]) and reference lines ([`Panel::psd`] for spectra);
//! - [`BarChart`]: horizontal bars, ranked ([`BarChart::ranked`], with a
//!   threshold) or grouped (before/after);
//! - [`Figure`]: a title over stacked panels, saved as PNG **and** SVG by one
//!   drawing routine generic over the plotters backend;
//! - [`HtmlReport`]: a single self-contained `index.html` with text, tables
//!   and figures.
//!
//! The module knows nothing of gyros or RBF networks: it takes slices and
//! strings, so the pipeline can change without touching the drawing.
//!
//! Robustness is part of the contract: empty, constant and NaN-laden series
//! draw without panicking; long series are decimated per pixel column keeping
//! peaks ([`decimate_m4`]); values a log axis cannot show are skipped and
//! reported in [`FigureFiles::warnings`]. Programmer errors (x and y of
//! different lengths, a table row of the wrong width) panic at the caller.
//!
//! ```
//! use plot::{BarChart, Figure, HtmlReport, Panel, Section, Series};
//!
//! let dir = std::env::temp_dir().join("dtg-vib-doc-overview");
//! let t: Vec<f64> = (0..5000).map(|i| i as f64 * 0.02).collect();
//! let k0: Vec<f64> = t.iter().map(|t| 0.2 * (4.0 * t).sin()).collect();
//! let residues = Figure::new("Residue K0")
//!     .panel(Panel::new("K0", "time (s)", "K0 (deg/h)").series(Series::line("K0", t, k0)))
//!     .save(&dir, "k0")?;
//! let err = Figure::new("Candidate effects, channel Z")
//!     .panel(BarChart::ranked("ERR", "ERR (–)", "ERR", [("gg_IS", 0.41), ("g_S", 0.004)])
//!         .threshold(0.01, "significance threshold"))
//!     .save(&dir, "err_z")?;
//! let index = HtmlReport::new("Report")
//!     .section(Section::new("Residues").figure(&residues, "K0 over the record"))
//!     .section(Section::new("Diagnosis").figure(&err, "ERR of candidate effects"))
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
pub use panel::{Band, Panel, RefLine};
pub use series::{Series, SeriesStyle};
pub use style::{PALETTE, colour};
