//! The skewed DTG geometry of the paper (eqs. 1–6): channel names, frames,
//! measurement matrix and parity residues (fault detection on a unit's parity
//! vector is [`crate::fdi`], above the unit).

mod channel;
mod frame;
mod parity;

pub use channel::{Axis, Channel, Dtg, ParseNameError};
pub use frame::{ChannelFrame, DtgAxes, Ios, dtg_frame, input_axis, spin_axis};
pub use parity::{
    AxisMeasurements, Residue, axis_measurements, ideal_outputs, least_squares_operator,
    least_squares_rate, measurement_matrix, parity_matrix, parity_vector, residues,
};
