//! The files a vibration test produces: the record (CSV), the ground
//! calibration handed to the user (JSON); the simulator's truth file is
//! [`crate::sim::truth`], beside the scenario it records. Re-exported at the
//! crate root as [`crate::record`] and [`crate::calibration`].

pub mod calibration;
mod error;
pub(crate) mod io;
pub(crate) mod paper_calibration;
pub mod record;
