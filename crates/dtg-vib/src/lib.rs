//! dtg-vib: vibration-induced error identification and compensation for a
//! skewed cluster of Dynamically Tuned Gyroscopes, with RBF networks.

pub mod effects;
pub mod report;
pub mod residuals;
pub mod signal;
pub mod window;
