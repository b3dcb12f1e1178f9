//! dtg-vib: vibration-induced error identification and compensation for
//! the gyros of an inertial unit — the paper's skewed cluster of Dynamically
//! Tuned Gyroscopes (the built-in `paper` unit) or any unit a unit file
//! describes — with RBF networks fed by the same unit's accelerometers: the
//! gyro plug-in of the identification loop ([`sysid`]), compensation and
//! export, Allan glue and reports; its `dtg-vib` binary only parses flags
//! and prints.
//!
//! It is not the identification loop (`sysid`), not a sensor model or a
//! simulator (`nav-sensors`), not an RBF engine (`rbf`), not a plotting
//! library (`plot`), and not the onboard evaluator (`dtg-onboard`, which it
//! exports to). Data flow one way:
//!
//! record → [`unit_sensor`] (the unit as a [`sysid::Sensor`]: calibration,
//! rate reference, candidate effects, the model file, apply, check, parity
//! residues with fault detection) → [`allan`], [`export`] / [`onboard`] →
//! [`diagnose`] → report ([`page`], [`demo`]). [`commands`]
//! is each command's work from its flags to its result, which the binary
//! prints and the Python package returns. The loop's own
//! modules are re-exported under their old paths ([`split`], [`window`],
//! [`inference`], [`residuals`], [`operating`]).

pub mod allan;
pub mod caveats;
pub mod commands;
pub mod demo;
pub mod diagnose;
pub mod error;
pub mod export;
pub mod fleet;
pub mod numfmt;
pub mod onboard;
pub mod page;
pub mod report;
pub mod signal;
pub mod unit_sensor;

pub use error::DtgVibError;
pub use sysid::{inference, operating, residuals, split, window};
