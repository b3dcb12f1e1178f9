//! The application's figures and report pages, drawn with the [`plot`]
//! vocabulary: the paper's figures for a fitted model, and the diagnosis.

mod allan;
mod diagnosis;
mod paper;

pub use allan::write_allan_report;
pub use diagnosis::write_diagnosis_report;
pub use paper::{Baseline, ReportSummary, write_report};

use crate::error::DtgVibError;
use plot::{Figure, FigureFiles};
use rayon::prelude::*;
use std::path::Path;

/// Renders figures in parallel (each writes its own PNG and SVG), returning
/// `(stem, files)` in the given order.
fn save_all<'s>(
    figs: Vec<(Figure, &'s str)>,
    dir: &Path,
) -> Result<Vec<(&'s str, FigureFiles)>, DtgVibError> {
    figs.into_par_iter()
        .map(|(fig, stem)| Ok((stem, fig.save(dir, stem)?)))
        .collect()
}

/// A number for a table: four significant digits, no exponent for everyday sizes.
pub(crate) fn fmt(v: f64) -> String {
    if v == 0.0 {
        "0".to_string()
    } else if (1e-3..1e5).contains(&v.abs()) {
        let digits = (3 - v.abs().log10().floor() as i32).clamp(0, 6) as usize;
        format!("{v:.digits$}")
    } else {
        format!("{v:.3e}")
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn fmt_keeps_four_significant_digits() {
        assert_eq!(super::fmt(1.23456), "1.235");
        assert_eq!(super::fmt(123.456), "123.5");
        assert_eq!(super::fmt(0.0123456), "0.01235");
        assert_eq!(super::fmt(1.5e-7), "1.500e-7");
        assert_eq!(super::fmt(0.0), "0");
    }
}
