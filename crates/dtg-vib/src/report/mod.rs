//! What writes the application's reports: the figures and pages of a fitted
//! model (the paper's figures), of a diagnosis and of an Allan analysis,
//! drawn with the [`plot`] crate. Each page is assembled from one writer per
//! section, in a file of its own.

mod allan;
mod diagnosis;
mod paper;
mod provenance;

pub use allan::write_allan_report;
pub use diagnosis::write_diagnosis_report;
pub use paper::{
    Baseline, DiagnosisExtra, NoiseFloor, ReportExtras, ReportSummary, build_report, write_report,
};
pub use provenance::Provenance;

/// One meaning per colour, in every figure of every report (indices into
/// [`plot::PALETTE`]).
pub(crate) mod colours {
    /// Without compensation, measured, bias only: vermillion.
    pub const BEFORE: usize = 1;
    /// With compensation, the model's prediction, the residual after: blue.
    pub const AFTER: usize = 0;
    /// An acceleration (an input): bluish green.
    pub const INPUT: usize = 2;
    /// A baseline model compared against: reddish purple.
    pub const BASELINE: usize = 3;
    /// A reference or fitted curve (white floor, noise floor, fitted noise
    /// line, a candidate effect scaled by its coefficient): black.
    pub const REFERENCE: usize = 6;

    /// The sentence that says so on every page.
    pub const LEGEND: &str = "Colours mean the same in every figure: vermillion = without compensation / measured / bias only; blue = with compensation / the model's prediction / the residual after; green = an input (acceleration or extra column; where several share a panel: ax solid, ay dashed, az dotted, extra columns as dots); purple = a baseline model; black = a reference or fitted line (white floor, noise floor, a candidate effect scaled by its coefficient, and the Allan noise-term lines: dashed when read on the curve before compensation, dotted after).";
}

/// A spectrum without its 0 Hz bin, which a log frequency axis cannot show
/// (drawing it would only add a "skipped point" note).
pub(crate) fn positive_freq(f: &[f64], d: &[f64]) -> (Vec<f64>, Vec<f64>) {
    f.iter()
        .zip(d)
        .filter(|(f, d)| **f > 0.0 && **d > 0.0)
        .map(|(f, d)| (*f, *d))
        .unzip()
}

use crate::error::DtgVibError;
pub(crate) use crate::numfmt::{fmt, short};
use plot::{Figure, FigureFiles};
use rayon::prelude::*;
use std::path::Path;

/// Figures once drawn, by file stem.
pub(crate) struct Drawn(Vec<(&'static str, FigureFiles)>);

impl Drawn {
    /// The files of the figure saved as `stem`.
    #[track_caller]
    pub(crate) fn get(&self, stem: &str) -> &FigureFiles {
        self.0
            .iter()
            .find(|(s, _)| *s == stem)
            .map(|(_, f)| f)
            .unwrap_or_else(|| panic!("figure {stem:?} was not drawn"))
    }
}

/// Renders figures in parallel (each writes its own PNG and SVG), returning
/// `(stem, files)` in the given order.
fn save_all(figs: Vec<(Figure, &'static str)>, dir: &Path) -> Result<Drawn, DtgVibError> {
    figs.into_par_iter()
        .map(|(fig, stem)| Ok((stem, fig.save(dir, stem)?)))
        .collect::<Result<Vec<_>, DtgVibError>>()
        .map(Drawn)
}

#[cfg(test)]
mod tests {
    #[test]
    fn short_drops_trailing_zeros() {
        assert_eq!(super::short(0.19), "0.19");
        assert_eq!(super::short(0.1), "0.1");
        assert_eq!(super::short(2.0), "2");
        assert_eq!(super::short(20.0), "20");
    }

    #[test]
    fn fmt_keeps_four_significant_digits() {
        assert_eq!(super::fmt(1.23456), "1.235");
        assert_eq!(super::fmt(123.456), "123.5");
        assert_eq!(super::fmt(0.0123456), "0.01235");
        assert_eq!(super::fmt(1.5e-7), "1.500e-7");
        assert_eq!(super::fmt(0.0), "0");
    }
}
