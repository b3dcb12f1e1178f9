//! Skewed DTG geometry and parity residues, IEEE-style DTG (Std 813) and
//! accelerometer (Std 1293) error models, a vibration environment, and a
//! vibration-test simulator with its record, calibration and truth files.
//! It fits no model (that is `rbf` and `dtg-vib`) and knows no RBF.
//!
//! Layers, bottom up:
//! - [`geometry`]: channels, frames, eqs. 1–6 of Malini, Mohanlal & Harikumar;
//! - [`dtg`], [`accel`]: sensor error models, forward and inverse;
//! - [`rate`]: the rate-gyro error model (IEEE Std 952/1431), forward and inverse;
//! - [`unit`]: a unit of any gyros and accelerometers, from its description
//!   file: measurement matrix, parity, each gyro's error model;
//! - [`fdi`]: fault detection and isolation on a unit's parity vector;
//! - [`vibration`]: PSD tables, synthesis, schedules, Welch PSD;
//! - [`noise`]: Allan deviation and the IEEE Std 952 noise terms read from it;
//! - [`sim`]: scenarios and the shaker-test simulator;
//! - [`record`], [`calibration`]: the files a test produces (the truth is
//!   [`sim::UnitTruth`]);
//! - [`regressors`]: what the physics makes of a record of any unit
//!   (specific force, term regressors, parity residues);
//! - [`signal`]: the second-order sections the sensor dynamics use.
//!
//! The paper's experiment in a few lines: simulate the Z-axis random test,
//! compensate with the ground calibration, and look at a parity residue.
//!
//! ```
//! use nav_sensors::sim::{simulate_unit, Scenario};
//! use nav_sensors::unit::Unit;
//!
//! let paper = Unit::paper();
//! let sim = simulate_unit(&paper, &Scenario { duration_s: 20.0, ..Scenario::default() }).unwrap();
//! let compensated = sim.calibration.compensate(&paper, &sim.record).unwrap();
//! let k0 = &compensated.unit_residues(&paper)[0];
//! assert_eq!(paper.residue_names()[0], "K0");
//! let rms = |x: &[f64]| (x.iter().map(|v| v * v).sum::<f64>() / x.len() as f64).sqrt();
//! // Shaker off for the first 5 s: K0 is noise; then vibration rectifies.
//! assert!(rms(&k0[..250]) < 2.0 * sim.truth.residue_noise_floor_deg_h["K0"]);
//! assert!(rms(&k0[500..]) > 3.0 * rms(&k0[..250]));
//! // What no model of the record can remove, per channel (here Z):
//! assert_eq!(sim.truth.channels[4].channel, "Z");
//! assert!(sim.truth.channels[4].noise_floor_deg_h > 0.0);
//! ```

pub mod accel;
pub mod dtg;
pub mod fdi;
pub mod files;
pub mod geometry;
pub mod noise;
pub mod rate;
pub mod regressors;
pub mod signal;
pub mod sim;
pub mod unit;
pub mod vibration;

pub use files::{calibration, record};
