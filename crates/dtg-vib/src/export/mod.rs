//! A causal model made portable: its onboard tables written out
//! ([`crate::onboard`] lays them out), the C99 sources, and the model as
//! reviewable equations; for the paper's unit and for any unit.

mod c;
mod c_lanes;
mod c_process;
mod c_shared;
mod c_unit;
mod layout;
mod text;
mod text_unit;

pub use c::{CSources, Precision, c_sources, c_sources_from_tables};
pub use c_unit::unit_c_sources;
pub use text::equations;
pub use text_unit::unit_equations;

pub use crate::onboard::{
    ExportError, Tables, extra_columns, tables, unit_extra_columns, unit_tables,
};
