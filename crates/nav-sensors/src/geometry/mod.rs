//! The skewed DTG geometry of the paper (eqs. 1–6): channel names, frames,
//! measurement matrix, parity residues and fault detection and isolation.

mod channel;
mod fdi;
mod frame;
mod parity;

pub use channel::{Axis, Channel, Dtg, ParseNameError};
pub use fdi::{Fdi, FdiDecision, FdiError, FdiOutcome, ParityFdi};
pub use frame::{ChannelFrame, DtgAxes, Ios, dtg_frame, input_axis, spin_axis};
pub use parity::{
    AxisMeasurements, Residue, axis_measurements, ideal_outputs, least_squares_operator,
    least_squares_rate, measurement_matrix, parity_matrix, parity_vector, residues,
};
