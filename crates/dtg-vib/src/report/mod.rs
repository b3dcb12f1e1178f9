//! Figures and the HTML report, over plain data.

#![warn(missing_docs)]

mod axis;
mod decimate;
mod error;
mod style;

pub use decimate::decimate_m4;
pub use error::ReportError;
pub use style::{PALETTE, colour};
