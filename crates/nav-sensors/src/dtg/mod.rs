//! The DTG error model (IEEE Std 813 terms): coefficient table with stable
//! term ids, forward model and inverse (compensation), noise parameters, and
//! the 2N angular-vibration rectification detector.

mod coefficients;
mod input;
mod interval;
mod model;
mod noise;
mod rect2n;
mod term;

pub use coefficients::DtgCoefficients;
pub use input::DtgInput;
pub use interval::{
    WITHIN_INTERVAL_FACTORS, WITHIN_INTERVAL_REACH, resolve_covariance, within_interval_covariance,
    within_interval_factors,
};
pub use noise::DtgNoise;
pub use rect2n::Rect2nDetector;
pub use term::DtgTerm;
