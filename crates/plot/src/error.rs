//! The one error type of the report layer.
//!
//! Misuse that only a programmer can cause (x and y of different lengths, a
//! table row with the wrong number of cells, an absurd image size) panics at
//! the call site with `#[track_caller]`; everything that depends on the
//! machine or on names coming from data is a [`ReportError`].

use std::path::PathBuf;

/// Why a figure or a report could not be written.
///
/// ```
/// use plot::{Figure, Panel, ReportError, Series};
///
/// // A stem with a path separator would write outside the chosen directory.
/// let fig = Figure::new("t").panel(Panel::new("p", "t (s)", "y (g)"));
/// let err = fig.save(std::env::temp_dir(), "../escape").unwrap_err();
/// assert!(matches!(err, ReportError::InvalidStem { .. }));
/// assert!(err.to_string().contains("../escape"));
/// ```
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ReportError {
    /// Creating a directory or writing a file failed.
    #[error("cannot write {}: {source}", path.display())]
    Io {
        /// The directory or file that could not be written.
        path: PathBuf,
        /// What the operating system said.
        #[source]
        source: std::io::Error,
    },
    /// plotters failed while drawing or encoding a figure; its error is kept
    /// as text because the backend error types differ between PNG and SVG.
    #[error("cannot draw {}: {message}", path.display())]
    Draw {
        /// The file being drawn.
        path: PathBuf,
        /// plotters' description of the failure.
        message: String,
    },
    /// A file stem that is empty, has a path separator, or starts with a dot.
    /// Stems often come from data (sensor names), so this is an error, not a panic.
    #[error(
        "invalid file stem {stem:?}: use a plain name such as \"fig7_signals\" \
         (no path separator, no leading dot, not empty)"
    )]
    InvalidStem {
        /// The rejected stem.
        stem: String,
    },
    /// The embedded font was rejected by plotters (it never is for the font
    /// shipped in `assets/`; the variant exists so that the failure is not a panic).
    #[error("the embedded font could not be registered with plotters")]
    Font,
}
