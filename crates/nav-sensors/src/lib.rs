//! Skewed DTG geometry and parity residues, IEEE-style DTG (Std 813) and
//! accelerometer (Std 1293) error models, a vibration environment, and a
//! vibration-test simulator with its record, calibration and truth files.
//!
//! Layers, bottom up:
//! - [`geometry`]: channels, frames, eqs. 1–6 of Malini, Mohanlal & Harikumar, FDI;
//! - [`dtg`], [`accel`]: sensor error models, forward and inverse;
//! - [`vibration`]: PSD tables, synthesis, schedules, Welch PSD;
//! - [`sim`]: scenarios and the shaker-test simulator;
//! - [`record`], [`calibration`], [`truth`]: the files a test produces.

pub mod accel;
pub mod dtg;
pub mod files;
pub mod geometry;
pub mod signal;
pub mod vibration;

pub use files::record;
