//! A causal model made portable: its onboard tables written out
//! ([`crate::onboard`] lays them out), the C99 sources, and the model as
//! reviewable equations.

mod c;
mod text;

pub use c::{CSources, Precision, c_sources, c_sources_from_tables};
pub use text::equations;

pub use crate::onboard::{ExportError, Tables, extra_columns, tables};
