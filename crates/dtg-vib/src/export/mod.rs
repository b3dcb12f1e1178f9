//! A causal model made portable, for any unit, the paper's included: its
//! onboard tables written out ([`crate::onboard`] lays them out), the C99
//! sources, and the model as reviewable equations.

mod c;
mod c_kernels;
mod c_main;
mod c_step;
mod c_tables;
mod precision;
mod text;

pub use c::{CSources, c_sources, c_sources_from_tables};
pub use precision::Precision;
pub use text::equations;

pub use crate::onboard::{ExportError, Tables, extra_columns, tables};
