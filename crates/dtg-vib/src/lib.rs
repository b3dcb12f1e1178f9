//! dtg-vib: vibration-induced error identification and compensation for a
//! skewed cluster of Dynamically Tuned Gyroscopes, with RBF networks fed by
//! the same unit's accelerometers — the application, whose `dtg-vib`
//! binary only parses flags and prints.
//!
//! It is not a sensor model or a simulator (`nav-sensors`), not an RBF
//! engine (`rbf`), not a plotting library (`plot`), and not the onboard
//! evaluator (`dtg-onboard`, which it exports to). Data flow one way:
//!
//! record → [`pipeline`] (calibration, rate reference, low-pass, windows,
//! several records laid end to end) → [`split`] → [`fit`] ([`model`]) →
//! [`apply`], [`check`], [`allan`] → [`diagnose`] ([`inference`],
//! [`residuals`]) → [`explain`] → report.

pub mod allan;
pub mod apply;
pub mod check;
pub mod demo;
pub mod diagnose;
pub mod effects;
pub mod error;
pub mod explain;
pub mod export;
pub mod fit;
pub mod inference;
pub mod model;
mod numfmt;
pub mod onboard;
pub mod operating;
pub mod parity;
pub mod pipeline;
pub mod report;
pub mod residuals;
pub mod signal;
pub mod split;
pub mod window;

pub use error::DtgVibError;
