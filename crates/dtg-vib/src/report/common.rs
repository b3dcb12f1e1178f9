//! What every report writer shares: the colours, number formats, and the
//! figures drawn in parallel and looked up by stem.

use crate::error::DtgVibError;
pub(crate) use crate::numfmt::{fmt, short};
use plot::{Figure, FigureFiles};
use rayon::prelude::*;
use std::path::Path;

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

/// Figures once drawn, by file stem.
pub(crate) struct Drawn(Vec<(&'static str, FigureFiles)>);

impl Drawn {
    /// The files of the figure saved as `stem`, if it was drawn.
    pub(crate) fn find(&self, stem: &str) -> Option<&FigureFiles> {
        self.0.iter().find(|(s, _)| *s == stem).map(|(_, f)| f)
    }

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
pub(crate) fn save_all(
    figs: Vec<(Figure, &'static str)>,
    dir: &Path,
) -> Result<Drawn, DtgVibError> {
    figs.into_par_iter()
        .map(|(fig, stem)| Ok((stem, fig.save(dir, stem)?)))
        .collect::<Result<Vec<_>, DtgVibError>>()
        .map(Drawn)
}
