//! A causal model on-line: its onboard tables (the one layout the
//! `dtg-onboard` evaluator and the exported C read, for any unit, the
//! paper's included) and its step-by-step run over a record. The exporter
//! writes the tables out; compensation runs them.

mod effects;
pub mod error;
mod fade;
mod step;
mod tables;

pub use error::ExportError;
pub use step::{Stepped, step_record, step_tables};
pub(crate) use tables::accel_floats;
pub use tables::{Tables, extra_columns, tables};
