//! dtg-vib: vibration-induced error identification and compensation for a
//! skewed cluster of Dynamically Tuned Gyroscopes.

pub mod effects;
pub mod residuals;
pub mod signal;
pub mod window;
