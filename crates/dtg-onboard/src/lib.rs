//! On-line gyro vibration-error compensation, one output period per step,
//! in bounded time and memory: no standard library, no heap. It does not
//! fit or choose anything: it evaluates what `dtg-vib export` wrote.
//!
//! A model fitted by `dtg-vib fit --causal` is exported as flat tables (the
//! versioned byte layout of docs/formats.md, "Onboard tables") for any unit:
//! up to [`MAX_CHANNELS`] DTG or rate-gyro channels, each network on its own
//! window signals, the unit's operators and calibration. [`Model`] reads
//! them from a byte slice (a file, flash, an `include_bytes!`);
//! [`Evaluator`] keeps the state (filter states, the last six specific
//! forces and the three pending samples, the input windows, the numbers a step reads in vector
//! lanes) in a caller-provided `f64` buffer of [`Model::state_len`]
//! elements, and [`Evaluator::step`] turns one period's raw gyro outputs
//! (deg/h), accelerations (g) and extra columns into the compensated rates
//! (deg/h) of the period three before: [`LOOKAHEAD`] periods of latency
//! (60 ms at 50 Hz), because the g² terms' within-interval covariance of a
//! sample is estimated from the means of the three samples on each side. Tables written before ([`LAYOUT_2`], the paper's six DTG
//! channels; [`LAYOUT_3`], any unit with one list of window signals) are
//! read as they always were and run as today's `compensate` runs them
//! (the seven-mean covariance, three periods late). Channels that share their window
//! signals, centres and widths (the same numbers in the tables) take each
//! kernel value computed once.
//!
//! Each sample goes through, in this order (the same as `dtg-vib
//! compensate` on a causal model, which runs this code):
//!
//! 1. ground calibration: the specific force from the accelerometers (the
//!    triad's static inverse when the tables hold it), then each gyro's
//!    inverse model, a DTG's with the other-axis rates from the
//!    least-squares rate (two passes), the g² terms with the
//!    within-interval covariance from the sample and the three on each
//!    side ([`WITHIN_INTERVAL_FACTORS`]);
//! 2. per channel, the effect regressors from the calibrated specific
//!    force, rates and extra columns, each through the tables' effect
//!    low-pass (none in the tables `dtg-vib export` writes: the effects are
//!    subtracted unfiltered, θ·z);
//! 3. the window signals through the causal input low-pass into their
//!    windows (and, for the statistics input, their running statistics);
//! 4. once the windows are full, per channel the predicted error
//!    `bias + Σ θⱼ·zⱼ + Σₖ wₖ·exp(−‖x − cₖ‖²/βₖ²)`, its network part faded
//!    outside the training range and smoothed, subtracted from the
//!    calibrated output.
//!
//! ```
//! # fn tables() -> Vec<u8> { dtg_onboard::doc_tables().to_vec() }
//! use dtg_onboard::{Evaluator, Model};
//! let bytes = tables(); // e.g. include_bytes!("model.dtgo")
//! let model = Model::parse(&bytes).unwrap();
//! let mut state = [0.0f64; 4096];
//! let mut ev = Evaluator::new(model, &mut state).unwrap();
//! for _ in 0..model.window_len() {
//!     // Outputs lag three samples: the window_len-th sample's comes with
//!     // the third after it.
//!     assert!(ev.step(&[0.0; 6], &[0.0, 0.0, 1.0], &[]).unwrap().is_none());
//! }
//! // The record's last three samples; only the last has a full window.
//! let [_, _, last] = ev.flush();
//! let out = last.expect("the record's last sample, with a full window");
//! assert!(out.rates().iter().all(|w| w.is_finite()));
//! ```

#![no_std]
// Unsafe only where the kernels' AVX2 build is called after cpuid said
// the CPU runs it (vector.rs).
#![deny(unsafe_code)]
// One dependency, itself no_std and dependency-free: `fastexp`, whose
// `exp_neg11` (a few ulps from the desktop's `exp_neg`, in fewer operations)
// the exported C writes out constant for constant, so Rust and C give the
// same bits. The rest needs only `+ − × ÷`, comparisons and bit operations.

mod calibration;
mod cost;
mod error;
mod evaluator;
mod fade;
mod interval;
mod kernels;
mod lanes;
mod layout;
mod maths;
mod model;
mod vector;

pub use error::Error;
pub use evaluator::{Evaluator, Output};
pub use interval::{LOOKAHEAD, WITHIN_INTERVAL_FACTORS};
pub use model::{Floats, Model, Part};

pub use layout::{
    FIXED_HEADER_WORDS, FLAG_ACCEL_TRIAD, FLAG_CALIBRATION, FLAG_FADE, FLAG_FADE_SHAPE, LANES,
    LAYOUT_2, LAYOUT_2_HEADER_WORDS, LAYOUT_3, MAGIC, MAX_ACCELS, MAX_CHANNELS, MAX_SIGNALS,
    VERSION, fade_floats, gyro, gyro_cal_len, input, kind, kind_params_of,
};

/// Header words of [`doc_tables`].
const DOC_WORDS: usize = FIXED_HEADER_WORDS + 4 * 6 + 1 + 2;
/// Numbers of [`doc_tables`]: the period, the log's units, frames, rate and
/// specific-force operators, and per channel bias, width, weight, centre.
const DOC_FLOATS: usize = 1 + 2 + 54 + 18 + 9 + 6 * 7;

/// Tables of a small model for the examples: six DTG channels, three
/// accelerometers, no calibration, one centre per channel (channel c's
/// bias c, width 1, weight 0.5, centre four samples of 1 g), a 4-sample
/// window of `az`, no filters.
#[doc(hidden)]
pub fn doc_tables() -> [u8; 4 * DOC_WORDS + 8 * DOC_FLOATS] {
    let mut b = [0u8; 4 * DOC_WORDS + 8 * DOC_FLOATS];
    let mut words = [0u32; DOC_WORDS];
    let head = [u32::from_le_bytes(MAGIC), VERSION, DOC_WORDS as u32, 0, 0];
    words[..5].copy_from_slice(&head);
    words[7..11].copy_from_slice(&[4, 1, 6, 3]);
    let lists = FIXED_HEADER_WORDS;
    // Effects 0, centres 1, models DTG (0), each channel on signal 0.
    words[lists + 6..lists + 12].fill(1);
    words[lists + 18..lists + 24].fill(1);
    words[lists + 24] = 2; // the signal: calibrated accelerometer 2 (az)
    words[lists + 25] = input::RAW;
    for (i, w) in words.iter().enumerate() {
        b[4 * i..4 * i + 4].copy_from_slice(&w.to_le_bytes());
    }
    let mut at = 4 * DOC_WORDS;
    let mut put = |v: f64| {
        b[at..at + 8].copy_from_slice(&v.to_le_bytes());
        at += 8;
    };
    for v in [0.02, 1.0, 1.0] {
        put(v);
    }
    for _ in 0..54 + 18 {
        put(0.0);
    }
    for i in 0..9 {
        put(if i % 4 == 0 { 1.0 } else { 0.0 });
    }
    for c in 0..6 {
        for v in [c as f64, 1.0, 0.5, 1.0, 1.0, 1.0, 1.0] {
            put(v); // bias, width, weight, centre
        }
    }
    b
}

#[cfg(test)]
extern crate std;

#[cfg(test)]
mod tests;
