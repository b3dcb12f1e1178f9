//! dtg-vib: vibration-induced error identification and compensation for a
//! skewed cluster of Dynamically Tuned Gyroscopes, with RBF networks fed by
//! the same unit's accelerometers — the gyro plug-in of the identification
//! loop ([`sysid`]) for the paper's unit, compensation and export, Allan
//! glue and reports; its `dtg-vib` binary only parses flags and prints.
//!
//! It is not the identification loop (`sysid`), not a sensor model or a
//! simulator (`nav-sensors`), not an RBF engine (`rbf`), not a plotting
//! library (`plot`), and not the onboard evaluator (`dtg-onboard`, which it
//! exports to). Data flow one way:
//!
//! Any other unit (a unit file, `--unit`) plugs in through [`unit_sensor`]
//! instead of [`paper_unit`], with the loop's own types.
//!
//! record → [`paper_unit`] (the unit as a [`sysid::Sensor`]: calibration,
//! rate reference, candidate effects [`effects`]) → [`pipeline`] (the loop's
//! preparation by channel) → [`fit`] ([`model`]) → [`apply`], [`check`],
//! [`allan`], [`export`] → [`diagnose`] → [`explain`] → report. The loop's
//! own modules are re-exported under their old paths ([`split`],
//! [`window`], [`inference`], [`residuals`], [`operating`]).

pub mod allan;
pub mod apply;
pub mod caveats;
pub mod check;
pub mod diagnose;
pub mod effects;
pub mod error;
pub mod explain;
pub mod export;
pub mod fit;
pub mod fleet;
pub mod model;
pub mod numfmt;
pub mod onboard;
pub mod paper_unit;
pub mod parity;
pub mod pipeline;
pub mod report;
pub mod signal;
pub mod unit_demo;
pub mod unit_page;
pub mod unit_sensor;

pub use error::DtgVibError;
pub use sysid::{inference, operating, residuals, split, window};
