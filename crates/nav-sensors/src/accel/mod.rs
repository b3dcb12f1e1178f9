//! The servo accelerometer model (IEEE Std 1293 terms): coefficients, forward
//! and static inverse, servo-loop dynamics and noise.

mod dynamics;
mod model;

pub use dynamics::{AccelNoise, ServoLoop};
pub use model::{AccelCoefficients, compensate_triad, ipo_components};
