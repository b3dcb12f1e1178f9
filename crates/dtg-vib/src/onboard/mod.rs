//! A causal model on-line: its onboard tables (the layout the `dtg-onboard`
//! evaluator and the exported C read) and its step-by-step run over a
//! record. The exporter writes the tables out; compensation runs them.

pub mod error;
mod fade;
mod step;
mod tables;

pub use error::ExportError;
pub use step::{Stepped, step_record};
pub use tables::{Tables, extra_columns, tables};
