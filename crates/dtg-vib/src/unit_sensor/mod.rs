//! The gyro plug-in of the identification loop for any unit a unit file
//! describes ([`nav_sensors::unit::Unit`]): its gyros are the channels,
//! named as the file names them; a `dtg` channel keeps the IEEE Std 813
//! candidates in its own (I, O, S) axes, a `rate` channel gets the rate
//! gyro's g- and g²-sensitivities in the unit frame ([`UnitEffect`]); the
//! reference rate is removed through the unit's H, and the separation
//! advice works along the unit's x, y, z axes.
//!
//! It serves every unit, the paper's included (the built-in `paper`
//! unit); a paper model file written before the unit was stored reads as
//! the paper unit's model.

mod applied;
mod apply;
mod calibrated;
mod calibration;
pub mod check;
mod dynamic;
pub(crate) mod effect;
pub(crate) mod error;
pub mod fdi;
pub mod frequency_response;
pub(crate) mod model;
mod observable;
mod parity;
mod preprocess;
mod range;
pub(crate) mod sensor;
mod separate;
mod signals;
mod window;

pub use applied::{
    BeforeAfter, ChannelOnRecord, EffectRow, UnitApplied, compensated, gyros_before_after,
    residue_series, residues_of,
};
pub use apply::Applied;
pub use calibration::{calibration_from_json, load_calibration};
pub use dynamic::{ACCEL_PREFIX, Dynamic, DynamicError, MAX_LAG, Stimulus, expand_dynamic};
pub use effect::{
    ANISOINERTIA_MIN_RATE_DEG_S, COLUMN_PREFIX, RATE_EFFECTS, TERM_EFFECTS, UnitEffect,
    UnitEffectError,
};
pub use error::UnitSensorError;
pub use model::{FORMAT_VERSION, UnitModel};
pub use observable::{
    MOVING_RATE_STD_DEG_S, Observability, observability, rate_families_observable,
};
pub use parity::{ResidueSeries, ResidueStats, pooled};
pub use preprocess::{PARITY_NOTE, RateReference, StoredPreprocess};
pub use sensor::{FLIGHT_EFFECTS, MIN_SCALE_G, UnitSensor};
pub use separate::response;
pub use signals::{UnitRecord, read_unit_records, to_record, to_signals};
pub use window::default_window_signals;
