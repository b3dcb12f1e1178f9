//! dtg-vib: vibration-induced error identification and compensation for a
//! skewed cluster of Dynamically Tuned Gyroscopes, with RBF networks.

pub mod allan;
pub mod apply;
pub mod demo;
pub mod diagnose;
pub mod effects;
pub mod error;
pub mod explain;
pub mod export;
pub mod fit;
pub mod inference;
pub mod model;
pub mod pipeline;
pub mod report;
pub mod residuals;
pub mod residue;
pub mod signal;
pub mod split;
pub mod window;

pub use error::DtgVibError;
