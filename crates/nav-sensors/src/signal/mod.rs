//! The workspace's filters (crate `iir`), under the path the sensor
//! models and their users have always named them by.

pub use iir::{Biquad, FilterError, LowPass, MAX_ORDER, MIN_CUTOFF_PER_RATE, num};
