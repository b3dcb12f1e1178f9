//! The files a vibration test produces: the record (CSV), the ground
//! calibration handed to the user (JSON) and the simulator's truth (JSON).
//! Re-exported at the crate root as [`crate::record`], [`crate::calibration`]
//! and [`crate::truth`].

pub mod calibration;
pub mod record;
pub mod truth;
