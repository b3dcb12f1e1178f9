//! A causal model on-line: its onboard tables (the layout the `dtg-onboard`
//! evaluator and the exported C read: the paper's unit's, and any unit's)
//! and its step-by-step run over a record. The exporter writes the tables
//! out; compensation runs them.

pub mod error;
mod fade;
mod step;
mod tables;
mod unit_tables;

pub use error::ExportError;
pub use step::{Stepped, UnitStepped, step_record, step_unit_record};
pub use tables::{Tables, extra_columns, tables};
pub use unit_tables::{unit_extra_columns, unit_tables};
