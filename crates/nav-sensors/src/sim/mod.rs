//! The vibration-test simulator: scenarios (TOML, seeded), the simulation
//! itself, the ground calibration it hands out and the truth it keeps. A
//! scenario may move the unit (a flight-like [`MotionProfile`]): attitude
//! changes move gravity among the sensor axes and body rates reach the
//! gyros.

mod budget;
mod calibrate;
mod engine;
mod error;
mod lsq;
mod motion;
mod output;
mod paper_truth;
mod predictable;
mod presets;
mod scenario;
mod site;
mod thermal;
mod truth;
mod unit;

pub use error::SimError;
pub use motion::{MotionProfile, Phase};
pub use output::Components;
pub use presets::low_frequency_psd;
pub use scenario::{
    AccelSet, CalibrationError, GyroSet, HiddenEffect, Scenario, ScenarioError, UnitGyros,
    UnitHiddenEffect,
};
pub use site::{Direction, EARTH_RATE_DEG_H, Orientation, Site};
pub use thermal::Thermal;
pub use truth::{TruthFileError, UnitChannelTruth, UnitCollinear, UnitHiddenTruth, UnitTruth};
pub use unit::{UnitSimulation, simulate_unit};
