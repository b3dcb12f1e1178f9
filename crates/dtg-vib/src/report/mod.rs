//! Figures and the HTML report, over plain data.

#![warn(missing_docs)]

mod error;
mod style;

pub use error::ReportError;
pub use style::{PALETTE, colour};
