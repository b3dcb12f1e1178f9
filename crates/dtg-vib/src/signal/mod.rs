//! Pre-processing of 50-Hz sensor records: the Butterworth low-pass and its
//! zero-phase filtering. The filters themselves live in the `iir` crate,
//! below both the sensor models (whose dynamics run the same [`Biquad`])
//! and the identification loop, so the workspace has one filter type; this
//! module keeps the application's paths.
//!
//! ```
//! use dtg_vib::signal::LowPass;
//! let lp = LowPass::butterworth(4, 5.0, 50.0).unwrap();
//! assert!((lp.gain_at(5.0) - 0.5_f64.sqrt()).abs() < 1e-12);
//! ```

pub use iir::{Biquad, FilterError, LowPass, MAX_ORDER, MIN_CUTOFF_PER_RATE, num};
